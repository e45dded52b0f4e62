/* SPDX-License-Identifier: BSD-3-Clause */
/* Source: out_i = u_i(t), time functions borrowed from the graph. */
#include <stdlib.h>
#include <string.h>

#include "bd/kinds.h"

typedef struct source_content {
  fb_tfun *const *fns; /* one per output component */
} source_content;

static int source_eval(bd_block *b, double t, double *w)
{
  const source_content *s = b->content;
  for (size_t i = 0; i < b->odim; ++i)
    w[b->ooff + i] = fb_tfun_eval(s->fns[i], t);
  return 0;
}

static int source_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  memset(dw + b->ooff, 0, b->odim * sizeof *dw);
  return 0;
}

static size_t source_nnz(const bd_block *b)
{
  return b->odim;
}

static int source_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                      double *v1)
{
  (void)w;
  bd_trip t = {rows, cols, v0, v1, 0};
  fb_bd_trip_identity(&t, b->ooff, b->odim);
  return 0;
}

static int source_time_varying(const bd_block *b)
{
  const source_content *s = b->content;
  for (size_t i = 0; i < b->odim; ++i)
    if (!fb_tfun_is_constant(s->fns[i]))
      return 1;
  return 0;
}

static size_t source_breakpoints(const bd_block *b, double *bp, size_t max)
{
  const source_content *s = b->content;
  size_t n = 0;
  for (size_t i = 0; i < b->odim; ++i)
    n += fb_tfun_breakpoints(s->fns[i], bp ? bp + n : NULL, bp ? max - n : 0);
  return n;
}

const bd_block_ops fb_bd_source_ops = {.kind = "source",
                                       .linear = 1,
                                       .unit_rows = 1,
                                       .exogenous = 1,
                                       .eval = source_eval,
                                       .jvp = source_jvp,
                                       .nnz = source_nnz,
                                       .jac = source_jac,
                                       .free = free,
                                       .time_varying = source_time_varying,
                                       .breakpoints = source_breakpoints};

int fb_bd_source_new(fb_tfun *const *fns, bd_kind *out, fb_err *err)
{
  source_content *s = malloc(sizeof *s);
  if (!s)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  s->fns = fns;
  out->ops = &fb_bd_source_ops;
  out->content = s;
  return FB_OK;
}
