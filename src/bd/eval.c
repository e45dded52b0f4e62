/* SPDX-License-Identifier: BSD-3-Clause */
/* Evaluation of a scheduled block diagram: right-hand side, outputs,
 * augmented sparse linearisation and dense Jacobian (flexbond/bd.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bd/bd_internal.h"
#include "core/util.h"

static int block_failed(fb_bd *bd, size_t blk, int rc)
{
  const bd_block *b = &bd->blocks[blk];
  const char *who = b->elem == FB_NONE ? "probe" : bd->bg->elems[b->elem].name;
  snprintf(bd->errbuf, sizeof bd->errbuf, "block %s of '%s' failed (%s)", b->ops->kind, who,
           rc > 0 ? "recoverable" : "fatal");
  return rc;
}

/* Evaluates the blocks order[0 .. n) at (t, x). */
static int eval_blocks(fb_bd *bd, const size_t *order, size_t n, double t, const double *x)
{
  bd->errbuf[0] = '\0'; /* the message describes the latest evaluation only */
  memcpy(bd->w, x, bd->nstates * sizeof *x);
  for (size_t k = 0; k < n; ++k) {
    bd_block *b = &bd->blocks[order[k]];
    int rc = b->ops->eval(b, t, bd->w);
    if (rc)
      return block_failed(bd, order[k], rc);
  }
  return 0;
}

int fb_bd_eval(fb_bd *bd, double t, const double *x)
{
  return eval_blocks(bd, bd->order, bd->norder, t, x);
}

int fb_bd_eval_dynamics(fb_bd *bd, double t, const double *x)
{
  return eval_blocks(bd, bd->dyn_order, bd->ndyn_order, t, x);
}

int fb_bd_rhs(fb_bd *bd, double t, const double *x, double *xdot)
{
  int rc = fb_bd_eval_dynamics(bd, t, x);
  if (rc)
    return rc;
  for (size_t k = 0; k < bd->ninteg; ++k) {
    const bd_block *b = &bd->blocks[bd->integ[k]];
    memcpy(xdot + b->ooff, bd->w + b->ioff[0], b->odim * sizeof *xdot);
  }
  return 0;
}

const char *fb_bd_last_error(const fb_bd *bd)
{
  return bd->errbuf;
}

/* ---- Where a non-finite value starts (fb_bd_explain_nonfinite). */

/* Name of w[i]: its signal's, "[k]" (1-based) for a component of a
 * vector signal. */
static void w_name(const fb_bd *bd, size_t i, char *buf, size_t size)
{
  snprintf(buf, size, "signal %zu", i);
  for (size_t s = 0; s < bd->nsigs; ++s) {
    const bd_signal *sig = &bd->sigs[s];
    if (i >= sig->off && i < sig->off + sig->dim) {
      if (sig->dim == 1)
        snprintf(buf, size, "%s", sig->name);
      else
        snprintf(buf, size, "%s[%zu]", sig->name, i - sig->off + 1);
      return;
    }
  }
}

/* "Se 'grav_body' (source)", "R 'damper' (law 'quadratic')", "probe
 * 'damper_power' (e.*f)". */
static void block_name(const fb_bd *bd, const bd_block *b, char *buf, size_t size)
{
  char who[300];
  if (b->elem == FB_NONE)
    snprintf(who, sizeof who, "probe '%s'", bd->sigs[b->out].name);
  else
    fb_bg_describe(bd->bg, b->elem, who, sizeof who);
  if (b->ops->label_noun)
    snprintf(buf, size, "%s (%s '%s')", who, b->ops->label_noun, b->label);
  else
    snprintf(buf, size, "%s (%s)", who, b->label);
}

/* Inputs of at most this many components are listed with their values;
 * a wider vector would drown the message. */
#define LISTED_INPUTS 4

/* " from finite inputs f:br = 0.51, ..." (prep "from" or "at") after
 * the text in buf; nothing for a block without inputs (a source). */
static void append_inputs(const fb_bd *bd, const bd_block *b, const char *prep, char *buf,
                          size_t size)
{
  size_t width = 0;
  for (size_t k = 0; k < b->nin; ++k)
    width += b->idim[k];
  if (width == 0)
    return;
  if (size == 0)
    return;
  /* len stays inside buf: snprintf returns what it would have written. */
  size_t len = strlen(buf);
  len += (size_t)snprintf(buf + len, size - len, " %s finite inputs", prep);
  if (width > LISTED_INPUTS || len >= size)
    return;
  for (size_t k = 0, listed = 0; k < b->nin && len < size; ++k)
    for (size_t c = 0; c < b->idim[k] && len < size; ++c, ++listed) {
      char name[300];
      w_name(bd, b->ioff[k] + c, name, sizeof name);
      len += (size_t)snprintf(buf + len, size - len, "%s %s = %.6g", listed ? "," : "", name,
                              bd->w[b->ioff[k] + c]);
    }
}

static int inputs_finite(const fb_bd *bd, const bd_block *b)
{
  for (size_t k = 0; k < b->nin; ++k)
    if (fb_first_nonfinite(bd->w + b->ioff[k], b->idim[k]) < b->idim[k])
      return 0;
  return 1;
}

/* FB_NONFINITE_VALUE, described into buf, if block i's output (already
 * in w) is not finite while its inputs are. */
static fb_bd_nonfinite_kind check_block_value(const fb_bd *bd, size_t i, char *buf, size_t size)
{
  const bd_block *b = &bd->blocks[i];
  const double *y = bd->w + b->ooff;
  const size_t c = fb_first_nonfinite(y, b->odim);
  if (c == b->odim || !inputs_finite(bd, b))
    return FB_NONFINITE_NONE;
  char who[400], name[300];
  block_name(bd, b, who, sizeof who);
  w_name(bd, b->ooff + c, name, sizeof name);
  snprintf(buf, size, "%s: %s = %g", who, name, fb_printable(y[c]));
  append_inputs(bd, b, "from", buf, size);
  return FB_NONFINITE_VALUE;
}

size_t fb_bd_nstates(const fb_bd *bd)
{
  return bd->nstates;
}

const char *fb_bd_state_name(const fb_bd *bd, size_t i)
{
  return bd->state_names[i];
}

fb_state_kind fb_bd_state_kind(const fb_bd *bd, size_t i)
{
  size_t e = bd->state_elem[i];
  if (e == FB_NONE)
    return FB_STATE_PROBE;
  return bd->bg->elems[e].kind == FB_BG_I ? FB_STATE_MOMENTUM : FB_STATE_DISPLACEMENT;
}

long fb_bd_state_element(const fb_bd *bd, size_t i, size_t *component)
{
  if (component)
    *component = bd->state_comp[i];
  return bd->state_elem[i] == FB_NONE ? -1 : (long)bd->state_elem[i];
}

void fb_bd_initial_state(const fb_bd *bd, double *x0)
{
  memcpy(x0, bd->x0, bd->nstates * sizeof *x0);
}

size_t fb_bd_nblocks(const fb_bd *bd)
{
  return bd->nblocks;
}

size_t fb_bd_noutputs(const fb_bd *bd)
{
  return bd->nouts;
}

const char *fb_bd_output_name(const fb_bd *bd, size_t i)
{
  return bd->outs[i].name;
}

const char *fb_bd_output_unit(const fb_bd *bd, size_t i)
{
  return bd->outs[i].unit;
}

int fb_bd_outputs(fb_bd *bd, double t, const double *x, double *y)
{
  int rc = eval_blocks(bd, bd->out_order, bd->nout_order, t, x);
  if (rc)
    return rc;
  for (size_t i = 0; i < bd->nouts; ++i) {
    const bd_output *o = &bd->outs[i];
    y[i] = o->gain * bd->w[bd->sigs[o->signal].off + o->comp];
  }
  return 0;
}

size_t fb_bd_aug_size(const fb_bd *bd)
{
  return bd->nz;
}

size_t fb_bd_aug_nnz(const fb_bd *bd)
{
  return bd->aug_nnz;
}

int fb_bd_is_linear(const fb_bd *bd)
{
  return bd->linear;
}

void fb_bd_aug_unknown_name(const fb_bd *bd, size_t i, char *buf, size_t size)
{
  snprintf(buf, size, "unknown %zu", i);
  for (size_t s = 0; s < bd->nsigs; ++s) {
    const bd_signal *sig = &bd->sigs[s];
    for (size_t c = 0; c < sig->dim; ++c)
      if (bd->zmap[sig->off + c] == i) {
        if (sig->dim == 1)
          snprintf(buf, size, "%s", sig->name);
        else
          snprintf(buf, size, "%s[%zu]", sig->name, c + 1);
        return;
      }
  }
}

size_t fb_bd_state_row(const fb_bd *bd, size_t i)
{
  return bd->zmap[i]; /* states occupy w[0 .. nstates) and z[0 .. nstates) */
}

/* Fills the triplets of the Newton blocks (in w indices) into scratch. */
static int fill_scratch(fb_bd *bd, int pattern)
{
  size_t k = 0;
  for (size_t n = 0; n < bd->nnewton; ++n) {
    size_t i = bd->newton_blocks[n];
    bd_block *b = &bd->blocks[i];
    int rc = b->ops->jac(b, bd->w, pattern ? bd->srows + k : NULL,
                         pattern ? bd->scols + k : NULL, bd->sv0 + k, bd->sv1 + k);
    if (rc && !pattern)
      return block_failed(bd, i, rc);
    k += b->ops->nnz(b);
  }
  return 0;
}

/* Marks the blocks upstream of the integrators' inputs (through varying
 * blocks) as the Newton subsystem. */
static void mark_newton(const fb_bd *bd, unsigned char *in, size_t *stack)
{
  size_t top = 0;
  for (size_t k = 0; k < bd->ninteg; ++k) {
    size_t i = bd->integ[k];
    in[i] = 1;
    stack[top++] = bd->sigs[bd->blocks[i].in[0].id].producer;
  }
  while (top) {
    size_t i = stack[--top];
    if (in[i] || bd->is_const[i])
      continue;
    in[i] = 1;
    for (size_t k = 0; k < bd->blocks[i].nin; ++k)
      stack[top++] = bd->sigs[bd->blocks[i].in[k].id].producer;
  }
}

int fb_bd_prepare_newton(fb_bd *bd, fb_err *err)
{
  size_t n = bd->nblocks, nedges = 0;
  for (size_t i = 0; i < n; ++i)
    nedges += bd->blocks[i].nin;
  unsigned char *in = calloc(n + 1, 1);
  size_t *stack = malloc((nedges + bd->ninteg + 1) * sizeof *stack);
  bd->zmap = malloc((bd->nw + 1) * sizeof *bd->zmap);
  bd->newton_blocks = malloc((n + 1) * sizeof *bd->newton_blocks);
  int rc = in && stack && bd->zmap && bd->newton_blocks
               ? FB_OK
               : fb_err_set(err, FB_ENOMEM, "out of memory preparing the Newton matrix");
  if (!rc) {
    mark_newton(bd, in, stack);
    for (size_t k = 0; k < bd->nw; ++k)
      bd->zmap[k] = FB_NONE;
    /* z numbering follows the layout of w (integrators first, then the
     * other blocks, each in block order), so the states come first. */
    bd->nz = 0;
    for (int pass = 0; pass < 2; ++pass)
      for (size_t i = 0; i < n; ++i) {
        const bd_block *b = &bd->blocks[i];
        if (b->ops->state != (pass == 0))
          continue;
        for (size_t c = 0; c < b->odim; ++c)
          bd->zmap[b->ooff + c] = in[i] ? bd->nz++ : FB_NONE;
      }
    /* P0 and P1 are constant when every Newton block is linear; blocks
     * that only feed outputs (a power probe's product) do not count. */
    bd->full_nnz = 0;
    bd->linear = 1;
    for (size_t i = 0; i < n; ++i)
      if (in[i]) {
        bd->newton_blocks[bd->nnewton++] = i;
        bd->full_nnz += bd->blocks[i].ops->nnz(&bd->blocks[i]);
        bd->linear = bd->linear && bd->blocks[i].ops->linear;
      }
    bd->keep = malloc(bd->full_nnz + 1);
    bd->srows = malloc((bd->full_nnz + 1) * sizeof *bd->srows);
    bd->scols = malloc((bd->full_nnz + 1) * sizeof *bd->scols);
    bd->sv0 = malloc((bd->full_nnz + 1) * sizeof *bd->sv0);
    bd->sv1 = malloc((bd->full_nnz + 1) * sizeof *bd->sv1);
    if (!bd->keep || !bd->srows || !bd->scols || !bd->sv0 || !bd->sv1)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory preparing the Newton matrix");
  }
  if (!rc) {
    /* A column outside z is a folded constant: its perturbation is 0. */
    fill_scratch(bd, 1);
    bd->aug_nnz = 0;
    for (size_t k = 0; k < bd->full_nnz; ++k) {
      bd->keep[k] = bd->zmap[bd->scols[k]] != FB_NONE;
      bd->aug_nnz += bd->keep[k];
    }
  }
  free(in);
  free(stack);
  return rc;
}

void fb_bd_aug_pattern(fb_bd *bd, size_t *rows, size_t *cols)
{
  /* The pattern does not depend on the signal values; a nonlinear law's
   * Jacobian evaluation failing here only affects values, not positions. */
  (void)fill_scratch(bd, 1);
  for (size_t k = 0, m = 0; k < bd->full_nnz; ++k)
    if (bd->keep[k]) {
      rows[m] = bd->zmap[bd->srows[k]];
      cols[m++] = bd->zmap[bd->scols[k]];
    }
}

/* Whether the output range of b meets one of its inputs' ranges. */
static int feeds_itself(const bd_block *b)
{
  for (size_t k = 0; k < b->nin; ++k)
    if (b->ioff[k] < b->ooff + b->odim && b->ooff < b->ioff[k] + b->idim[k])
      return 1;
  return 0;
}

void fb_bd_aug_unit_rows(const fb_bd *bd, unsigned char *unit)
{
  memset(unit, 0, bd->nz);
  for (size_t n = 0; n < bd->nnewton; ++n) {
    const bd_block *b = &bd->blocks[bd->newton_blocks[n]];
    if (!b->ops->unit_rows || feeds_itself(b))
      continue;
    for (size_t c = 0; c < b->odim; ++c)
      if (bd->zmap[b->ooff + c] != FB_NONE)
        unit[bd->zmap[b->ooff + c]] = 1;
  }
}

int fb_bd_aug_values(fb_bd *bd, double t, const double *x, double *v0, double *v1)
{
  if (!bd->linear) {
    int rc = fb_bd_eval(bd, t, x);
    if (rc)
      return rc;
  }
  int rc = fill_scratch(bd, 0);
  if (rc)
    return rc;
  for (size_t k = 0, m = 0; k < bd->full_nnz; ++k)
    if (bd->keep[k]) {
      v0[m] = bd->sv0[k];
      v1[m++] = bd->sv1[k];
    }
  return 0;
}

int fb_bd_jacobian_dense(fb_bd *bd, double t, const double *x, double *jac, fb_err *err)
{
  size_t n = bd->nstates;
  int rc = fb_bd_eval(bd, t, x);
  for (size_t j = 0; !rc && j < n; ++j) {
    memset(bd->dw, 0, bd->nw * sizeof *bd->dw);
    bd->dw[j] = 1.0;
    for (size_t k = 0; !rc && k < bd->norder; ++k) {
      bd_block *b = &bd->blocks[bd->order[k]];
      rc = b->ops->jvp(b, bd->w, bd->dw);
      if (rc)
        rc = block_failed(bd, bd->order[k], rc);
    }
    for (size_t k = 0; !rc && k < bd->ninteg; ++k) {
      const bd_block *b = &bd->blocks[bd->integ[k]];
      memcpy(jac + j * n + b->ooff, bd->dw + b->ioff[0], b->odim * sizeof *jac);
    }
  }
  if (rc)
    return fb_err_set(err, FB_ESOLVER, "linearisation failed: %s", bd->errbuf);
  return FB_OK;
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

size_t fb_bd_breakpoints(const fb_bd *bd, double *bp, size_t max)
{
  size_t total = 0;
  for (size_t i = 0; i < bd->nblocks; ++i)
    if (bd->blocks[i].ops->breakpoints)
      total += bd->blocks[i].ops->breakpoints(&bd->blocks[i], NULL, 0);
  if (!bp || total == 0)
    return total;
  /* Collect all, then sort, merge duplicates and keep the earliest max. */
  double *all = malloc(total * sizeof *all);
  if (!all)
    return 0;
  size_t n = 0;
  for (size_t i = 0; i < bd->nblocks; ++i)
    if (bd->blocks[i].ops->breakpoints)
      n += bd->blocks[i].ops->breakpoints(&bd->blocks[i], all + n, total - n);
  qsort(all, n, sizeof *all, cmp_double);
  size_t u = 0;
  for (size_t i = 0; i < n && u < max; ++i)
    if (u == 0 || all[i] != bp[u - 1])
      bp[u++] = all[i];
  free(all);
  return u;
}

/* FB_NONFINITE_JACOBIAN, described into buf, if a Newton block's
 * triplets at the signals in w are not finite. A triplet of row r and
 * column c != r holds minus the derivative of r by c (every kind writes
 * B d(out) - A d(in) = 0), which is what is shown. */
static fb_bd_nonfinite_kind check_jacobians(fb_bd *bd, char *buf, size_t size)
{
  (void)fill_scratch(bd, 1); /* a failed law Jacobian leaves zeros, so finite */
  for (size_t n = 0, k = 0; n < bd->nnewton; ++n) {
    const bd_block *b = &bd->blocks[bd->newton_blocks[n]];
    const size_t end = k + b->ops->nnz(b);
    for (; k < end; ++k)
      if (!isfinite(bd->sv0[k]) || !isfinite(bd->sv1[k])) {
        const double v = isfinite(bd->sv0[k]) ? bd->sv1[k] : bd->sv0[k];
        const size_t r = bd->srows[k], c = bd->scols[k];
        char who[400], rn[300], cn[300];
        block_name(bd, b, who, sizeof who);
        w_name(bd, r, rn, sizeof rn);
        w_name(bd, c, cn, sizeof cn);
        snprintf(buf, size, "%s: d %s / d %s = %g", who, rn, cn, fb_printable(r == c ? v : -v));
        append_inputs(bd, b, "at", buf, size);
        return FB_NONFINITE_JACOBIAN;
      }
  }
  return FB_NONFINITE_NONE;
}

fb_bd_nonfinite_kind fb_bd_explain_nonfinite(fb_bd *bd, double t, const double *x, int jacobian,
                                             char *buf, size_t size)
{
  buf[0] = '\0';
  for (size_t i = 0; i < bd->nstates; ++i)
    if (!isfinite(x[i])) {
      snprintf(buf, size, "state %s = %g", bd->state_names[i], fb_printable(x[i]));
      return FB_NONFINITE_STATE;
    }
  /* Folded constants keep their values in w; their inputs are constants
   * too, so any order finds a start. */
  fb_bd_nonfinite_kind kind = FB_NONFINITE_NONE;
  for (size_t i = 0; !kind && i < bd->nblocks; ++i)
    if (bd->is_const[i])
      kind = check_block_value(bd, i, buf, size);
  if (kind)
    return kind;
  /* eval_blocks, with each block checked as soon as it has run. */
  bd->errbuf[0] = '\0';
  memcpy(bd->w, x, bd->nstates * sizeof *x);
  for (size_t k = 0; k < bd->norder; ++k) {
    bd_block *b = &bd->blocks[bd->order[k]];
    const int rc = b->ops->eval(b, t, bd->w);
    if (rc) {
      block_failed(bd, bd->order[k], rc);
      return FB_NONFINITE_NONE;
    }
    kind = check_block_value(bd, bd->order[k], buf, size);
    if (kind)
      return kind;
  }
  return jacobian ? check_jacobians(bd, buf, size) : FB_NONFINITE_NONE;
}
