/* SPDX-License-Identifier: BSD-3-Clause */
/* Switched laws of a block diagram: guards and modes (flexbond/bd.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bd/bd_internal.h"

static int is_switched(const fb_bd *bd, size_t i)
{
  return fb_bd_block_nguards(&bd->blocks[i]) && !bd->is_const[i];
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
      bd->nguards += fb_bd_block_nguards(&bd->blocks[i]);
    }
  bd->guard_now = malloc((bd->nguards + 1) * sizeof *bd->guard_now);
  bd->guard_ahead = malloc((bd->nguards + 1) * sizeof *bd->guard_ahead);
  bd->guard_sign = malloc((bd->nguards + 1) * sizeof *bd->guard_sign);
  bd->x_ahead = malloc((bd->nstates + 1) * sizeof *bd->x_ahead);
  if (!bd->guard_now || !bd->guard_ahead || !bd->guard_sign || !bd->x_ahead)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the switched laws");
  bd->piecewise_linear = 1;
  for (size_t k = 0; k < bd->nnewton; ++k) {
    const bd_block *b = &bd->blocks[bd->newton_blocks[k]];
    bd->piecewise_linear &=
        b->ops->piecewise_linear ? b->ops->piecewise_linear(b) : b->ops->linear;
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
  if (i >= bd->nguards)
    return NULL;
  size_t k = 0;
  while (k + 1 < bd->nswitched && bd->guard_off[k + 1] <= i)
    ++k;
  return bd->bg->elems[bd->blocks[bd->switched[k]].elem].name;
}

/* Says in the diagram's message buffer which call of a switched block
 * failed ("the guards of the law of 'tire'"). */
static int switch_failed(fb_bd *bd, const bd_block *b, const char *what, int rc)
{
  snprintf(bd->errbuf, sizeof bd->errbuf, "the %s of the %s of '%s' failed (%s)", what,
           b->ops->kind, bd->bg->elems[b->elem].name, rc > 0 ? "recoverable" : "fatal");
  return rc;
}

int fb_bd_guards(fb_bd *bd, double t, const double *x, double *g)
{
  int rc = bd->nswitched ? fb_bd_eval_dynamics(bd, t, x) : 0;
  for (size_t k = 0; !rc && k < bd->nswitched; ++k) {
    bd_block *b = &bd->blocks[bd->switched[k]];
    rc = b->ops->guards(b, bd->w, g + bd->guard_off[k]);
    if (rc)
      rc = switch_failed(bd, b, "guards", rc);
  }
  return rc;
}

/* Asks every switched law for its next mode at (t, x) from the guard
 * signs sign; *changed |= whether one changed. */
static int switch_laws(fb_bd *bd, double t, const double *x, const int *sign, int *changed)
{
  int rc = fb_bd_eval_dynamics(bd, t, x);
  for (size_t k = 0; !rc && k < bd->nswitched; ++k) {
    bd_block *b = &bd->blocks[bd->switched[k]];
    rc = b->ops->switch_mode(b, bd->w, sign + bd->guard_off[k], changed);
    if (rc)
      rc = switch_failed(bd, b, "mode switch", rc);
  }
  return rc;
}

/* sign[i] = the sign of guard i at (t, x), or just after t where it is
 * exactly zero (zero there too counts as positive). */
static int guard_signs(fb_bd *bd, double t, const double *x, int *sign)
{
  double *g = bd->guard_now, *ahead = bd->guard_ahead;
  int rc = fb_bd_guards(bd, t, x, g);
  int any_zero = 0;
  for (size_t i = 0; !rc && i < bd->nguards; ++i)
    any_zero |= g[i] == 0.0;
  if (!rc && any_zero) {
    const double dt = 1e-8 * fmax(1.0, fabs(t));
    rc = fb_bd_rhs(bd, t, x, bd->x_ahead);
    for (size_t i = 0; !rc && i < bd->nstates; ++i)
      bd->x_ahead[i] = x[i] + dt * bd->x_ahead[i];
    if (!rc)
      rc = fb_bd_guards(bd, t + dt, bd->x_ahead, ahead);
  }
  for (size_t i = 0; !rc && i < bd->nguards; ++i) {
    const double v = g[i] != 0.0 ? g[i] : ahead[i];
    sign[i] = v < 0.0 ? -1 : 1;
  }
  return rc;
}

/* Rounds of mode choices before the modes are declared unsettled: each
 * round that changes something moves at least one law, and a law has a
 * few modes. */
#define SYNC_ROUNDS 16

/* fb_bd_sync_modes, with the guards marked in crossed (when not NULL)
 * keeping the sign of their crossing. */
static int settle_modes(fb_bd *bd, double t, const double *x, const int *crossed, int *changed)
{
  *changed = 0;
  if (!bd->nswitched)
    return 0;
  for (int round = 0; round < SYNC_ROUNDS; ++round) {
    int moved = 0;
    int rc = guard_signs(bd, t, x, bd->guard_sign);
    for (size_t i = 0; !rc && crossed && i < bd->nguards; ++i)
      if (crossed[i])
        bd->guard_sign[i] = crossed[i] > 0 ? 1 : -1;
    if (!rc)
      rc = switch_laws(bd, t, x, bd->guard_sign, &moved);
    if (rc)
      return rc;
    if (!moved)
      return 0;
    *changed = 1;
  }
  snprintf(bd->errbuf, sizeof bd->errbuf,
           "the modes of the switched laws do not settle at t = %g s (first law: '%s')", t,
           fb_bd_guard_element(bd, 0));
  return -1;
}

int fb_bd_sync_modes(fb_bd *bd, double t, const double *x, int *changed)
{
  return settle_modes(bd, t, x, NULL, changed);
}

int fb_bd_switch_modes(fb_bd *bd, double t, const double *x, const int *crossed, int *changed)
{
  return settle_modes(bd, t, x, crossed, changed);
}
