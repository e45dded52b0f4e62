/* SPDX-License-Identifier: BSD-3-Clause */
/* Topological scheduling of blocks (Kahn's algorithm). Integrator outputs
 * are states, known at the start of an evaluation, so they cut every
 * causal cycle that passes through storage; a cycle left over is an
 * algebraic loop: a zero-order causal path (Karnopp et al., section 5.3). */
#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bd/bd_internal.h"

static int is_integrator(const fb_bd *bd, size_t blk)
{
  return bd->blocks[blk].ops->state;
}

/* Producer of input k of block i, or FB_NONE if it is a state. */
static size_t dependency(const fb_bd *bd, size_t i, size_t k)
{
  size_t p = bd->sigs[bd->blocks[i].in[k].id].producer;
  return is_integrator(bd, p) ? FB_NONE : p;
}

static void describe_block(const fb_bd *bd, size_t i, char *buf, size_t size)
{
  const bd_block *b = &bd->blocks[i];
  if (b->elem == FB_NONE) {
    snprintf(buf, size, "[probe %s]", b->label);
    return;
  }
  char who[200];
  fb_bg_describe(bd->bg, b->elem, who, sizeof who);
  snprintf(buf, size, "[%s: %s]", who, b->label);
}

/* Writes the cycle through the unscheduled blocks into err. */
static int report_loop(const fb_bd *bd, const unsigned char *done, fb_err *err)
{
  size_t n = bd->nblocks;
  size_t *next = malloc(n * sizeof *next); /* next[i]: a remaining block feeding i */
  unsigned char *seen = calloc(n, 1);
  if (!next || !seen) {
    free(next);
    free(seen);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  size_t start = FB_NONE;
  for (size_t i = 0; i < n; ++i) {
    next[i] = FB_NONE;
    if (done[i] || is_integrator(bd, i))
      continue;
    for (size_t k = 0; k < bd->blocks[i].nin && next[i] == FB_NONE; ++k) {
      size_t d = dependency(bd, i, k);
      if (d != FB_NONE && !done[d])
        next[i] = d;
    }
    if (start == FB_NONE)
      start = i;
  }
  /* Walk backwards until a block repeats: that block is on a cycle. Every block left has an
   * input from another block left (else Kahn's algorithm would have scheduled it), as the
   * asserts state for the static analyzer. */
  assert(start != FB_NONE);
  size_t cur = start;
  while (!seen[cur]) {
    seen[cur] = 1;
    cur = next[cur];
    assert(cur != FB_NONE);
  }
  char path[FB_ERR_MSG_MAX] = "";
  size_t len = 0, first = cur;
  do {
    char blk[300];
    describe_block(bd, cur, blk, sizeof blk);
    size_t from = next[cur];
    len += (size_t)snprintf(path + len, len < sizeof path ? sizeof path - len : 0, "%s <- %s ",
                            blk, bd->sigs[bd->blocks[from].out].name);
    cur = from;
  } while (cur != first && len < sizeof path);
  free(next);
  free(seen);
  return fb_err_set(err, FB_ECAUSAL,
                    "algebraic loop (zero-order causal path, each block computed from the "
                    "signal after it): %s<- ... Hint: put a storage element (a small I or C) "
                    "on this path, or change a resistor's causality by reorienting the "
                    "junction structure",
                    path);
}

int fb_bd_schedule(fb_bd *bd, fb_err *err)
{
  size_t n = bd->nblocks;
  size_t *indeg = calloc(n + 1, sizeof *indeg);
  size_t *users_start = calloc(n + 2, sizeof *users_start);
  bd->order = malloc((n + 1) * sizeof *bd->order);
  unsigned char *done = calloc(n + 1, 1);
  size_t nedges = 0;
  for (size_t i = 0; i < n; ++i)
    nedges += bd->blocks[i].nin;
  size_t *users = malloc((nedges + 1) * sizeof *users);
  size_t *fill = calloc(n + 1, sizeof *fill);
  int rc = FB_OK;
  if (!indeg || !users_start || !bd->order || !done || !users || !fill) {
    rc = fb_err_set(err, FB_ENOMEM, "out of memory scheduling the block diagram");
    goto out;
  }
  /* Compressed adjacency: users of each block. */
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < bd->blocks[i].nin; ++k) {
      size_t d = is_integrator(bd, i) ? FB_NONE : dependency(bd, i, k);
      if (d != FB_NONE) {
        users_start[d + 1]++;
        indeg[i]++;
      }
    }
  for (size_t i = 0; i < n; ++i)
    users_start[i + 1] += users_start[i];
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < bd->blocks[i].nin; ++k) {
      size_t d = is_integrator(bd, i) ? FB_NONE : dependency(bd, i, k);
      if (d != FB_NONE)
        users[users_start[d] + fill[d]++] = i;
    }
  size_t head = 0;
  bd->norder = 0;
  for (size_t i = 0; i < n; ++i)
    if (!is_integrator(bd, i) && indeg[i] == 0)
      bd->order[bd->norder++] = i;
  while (head < bd->norder) {
    size_t i = bd->order[head++];
    done[i] = 1;
    for (size_t u = users_start[i]; u < users_start[i + 1]; ++u)
      if (--indeg[users[u]] == 0)
        bd->order[bd->norder++] = users[u];
  }
  size_t nonint = 0;
  for (size_t i = 0; i < n; ++i)
    nonint += !is_integrator(bd, i);
  if (bd->norder != nonint)
    rc = report_loop(bd, done, err);
out:
  free(indeg);
  free(users_start);
  free(done);
  free(users);
  free(fill);
  return rc;
}

/* 1 if block i (other than an integrator) computes a constant: all its
 * inputs are constant (a source has none) and its output changes neither
 * with t (a source of functions that are not all constant) nor with a
 * mode (a switched law). */
static int block_is_constant(const fb_bd *bd, size_t i, const unsigned char *cst)
{
  const bd_block *b = &bd->blocks[i];
  if (fb_bd_block_nguards(b) || (b->ops->time_varying && b->ops->time_varying(b)))
    return 0;
  for (size_t k = 0; k < b->nin; ++k)
    if (!cst[bd->sigs[b->in[k].id].producer])
      return 0;
  return 1;
}

/* Marks in need[] the varying blocks upstream of the top seed blocks on
 * stack (their inputs' producers, through varying non-integrator blocks). */
static void mark_cone(const fb_bd *bd, const unsigned char *cst, unsigned char *need,
                      size_t *stack, size_t top)
{
  while (top) {
    size_t i = stack[--top];
    if (need[i] || cst[i] || is_integrator(bd, i))
      continue;
    need[i] = 1;
    for (size_t k = 0; k < bd->blocks[i].nin; ++k)
      stack[top++] = bd->sigs[bd->blocks[i].in[k].id].producer;
  }
}

/* The part of order whose blocks need[] marks, into sub (*nsub of them). */
static void sub_order(const fb_bd *bd, const unsigned char *need, size_t *sub, size_t *nsub)
{
  *nsub = 0;
  for (size_t k = 0; k < bd->norder; ++k)
    if (need[bd->order[k]])
      sub[(*nsub)++] = bd->order[k];
}

/* The two parts of order that are evaluated on their own: the blocks the
 * outputs depend on (sampling at 1 kHz must not cost a whole evaluation)
 * and those the state derivatives depend on (a power or velocity that
 * only a probe reads is not computed at every right-hand side). */
static void sub_orders(fb_bd *bd, const unsigned char *cst, unsigned char *need, size_t *stack)
{
  size_t top = 0;
  for (size_t o = 0; o < bd->nouts; ++o)
    stack[top++] = bd->sigs[bd->outs[o].signal].producer;
  mark_cone(bd, cst, need, stack, top);
  sub_order(bd, need, bd->out_order, &bd->nout_order);
  memset(need, 0, bd->nblocks);
  top = 0;
  for (size_t k = 0; k < bd->ninteg; ++k)
    stack[top++] = bd->sigs[bd->blocks[bd->integ[k]].in[0].id].producer;
  mark_cone(bd, cst, need, stack, top);
  sub_order(bd, need, bd->dyn_order, &bd->ndyn_order);
}

int fb_bd_fold_constants(fb_bd *bd, fb_err *err)
{
  size_t n = bd->nblocks, nedges = bd->nouts;
  for (size_t i = 0; i < n; ++i)
    nedges += bd->blocks[i].nin;
  unsigned char *cst = bd->is_const = calloc(n + 1, 1), *need = calloc(n + 1, 1);
  size_t *stack = malloc((nedges + n + 1) * sizeof *stack);
  bd->out_order = malloc((bd->norder + 1) * sizeof *bd->out_order);
  bd->dyn_order = malloc((bd->norder + 1) * sizeof *bd->dyn_order);
  int rc = cst && need && stack && bd->out_order && bd->dyn_order
               ? FB_OK
               : fb_err_set(err, FB_ENOMEM, "out of memory scheduling the block diagram");
  /* Constants are evaluated once, here, and left out of every later
   * evaluation; their outputs stay in w and their perturbations stay 0. */
  size_t kept = 0;
  for (size_t k = 0; !rc && k < bd->norder; ++k) {
    size_t i = bd->order[k];
    cst[i] = (unsigned char)block_is_constant(bd, i, cst);
    if (!cst[i]) {
      bd->order[kept++] = i;
      continue;
    }
    bd_block *b = &bd->blocks[i];
    if (b->ops->eval(b, 0.0, bd->w))
      rc = fb_err_set(err, FB_EMODEL, "block %s of constant inputs failed to evaluate",
                      b->label);
  }
  if (!rc) {
    bd->norder = kept;
    sub_orders(bd, cst, need, stack);
  }
  free(need);
  free(stack);
  return rc;
}
