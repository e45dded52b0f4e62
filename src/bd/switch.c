/* Switched laws of a block diagram: guards and modes (flexbond/bd.h). */
#include <stdio.h>
#include <stdlib.h>

#include "bd/bd_internal.h"

static int is_switched(const fb_bd *bd, size_t i)
{
  const bd_block *b = &bd->blocks[i];
  return b->ops == &fb_bd_law_ops && b->law->nguards && !bd->is_const[i];
}

int fb_bd_prepare_switching(fb_bd *bd, fb_err *err)
{
  size_t n = 0;
  for (size_t i = 0; i < bd->nblocks; ++i)
    n += (size_t)is_switched(bd, i);
  bd->switched = malloc((n + 1) * sizeof *bd->switched);
  bd->guard_off = malloc((n + 1) * sizeof *bd->guard_off);
  if (!bd->switched || !bd->guard_off)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the switched laws");
  bd->nswitched = bd->nguards = 0;
  for (size_t i = 0; i < bd->nblocks; ++i)
    if (is_switched(bd, i)) {
      bd->guard_off[bd->nswitched] = bd->nguards;
      bd->switched[bd->nswitched++] = i;
      bd->nguards += bd->blocks[i].law->nguards;
    }
  bd->piecewise_linear = 1;
  for (size_t k = 0; k < bd->nnewton; ++k) {
    const bd_block *b = &bd->blocks[bd->newton_blocks[k]];
    bd->piecewise_linear &= b->ops->linear || (b->ops == &fb_bd_law_ops && b->law->affine);
  }
  return FB_OK;
}

size_t fb_bd_nguards(const fb_bd *bd)
{
  return bd->nguards;
}

int fb_bd_is_piecewise_linear(const fb_bd *bd)
{
  return bd->piecewise_linear;
}

const char *fb_bd_guard_element(const fb_bd *bd, size_t i)
{
  size_t k = 0;
  while (k + 1 < bd->nswitched && bd->guard_off[k + 1] <= i)
    ++k;
  return bd->bg->elems[bd->blocks[bd->switched[k]].elem].name;
}

/* Says in the diagram's message buffer which law call failed. */
static int law_failed(fb_bd *bd, const bd_block *b, const char *what, int rc)
{
  snprintf(bd->errbuf, sizeof bd->errbuf, "the %s of the law of '%s' failed (%s)", what,
           bd->bg->elems[b->elem].name, rc > 0 ? "recoverable" : "fatal");
  return rc;
}

int fb_bd_guards(fb_bd *bd, double t, const double *x, double *g)
{
  int rc = bd->nswitched ? fb_bd_eval(bd, t, x) : 0;
  for (size_t k = 0; !rc && k < bd->nswitched; ++k) {
    bd_block *b = &bd->blocks[bd->switched[k]];
    fb_law_in in;
    fb_bd_law_input(b, bd->w, &in);
    rc = b->law->guards(b->law_ctx, &in, g + bd->guard_off[k]);
    if (rc)
      rc = law_failed(bd, b, "guards", rc);
  }
  return rc;
}

/* 1 if one of switched law k's guards is marked in crossed. */
static int any_crossed(const fb_bd *bd, size_t k, const int *crossed)
{
  const size_t ng = bd->blocks[bd->switched[k]].law->nguards;
  for (size_t i = 0; i < ng; ++i)
    if (crossed[bd->guard_off[k] + i])
      return 1;
  return 0;
}

/* Asks the laws (all when crossed is NULL, else those with a crossed
 * guard) for their next modes at (t, x). */
static int switch_laws(fb_bd *bd, double t, const double *x, const int *crossed, int *changed)
{
  *changed = 0;
  int rc = bd->nswitched ? fb_bd_eval(bd, t, x) : 0;
  for (size_t k = 0; !rc && k < bd->nswitched; ++k) {
    if (crossed && !any_crossed(bd, k, crossed))
      continue;
    bd_block *b = &bd->blocks[bd->switched[k]];
    fb_law_in in;
    fb_bd_law_input(b, bd->w, &in);
    int mode = b->mode;
    rc = b->law->switch_mode(b->law_ctx, &in, crossed ? crossed + bd->guard_off[k] : NULL,
                             &mode);
    if (rc)
      rc = law_failed(bd, b, "mode switch", rc);
    else if (mode != b->mode) {
      b->mode = mode;
      *changed = 1;
    }
  }
  return rc;
}

int fb_bd_init_modes(fb_bd *bd, double t, const double *x, int *changed)
{
  return switch_laws(bd, t, x, NULL, changed);
}

int fb_bd_switch_modes(fb_bd *bd, double t, const double *x, const int *crossed, int *changed)
{
  return switch_laws(bd, t, x, crossed, changed);
}
