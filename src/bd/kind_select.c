/* SPDX-License-Identifier: BSD-3-Clause */
/* Select (demux): out = c in[offset .. offset + odim), one port of a
 * field's stacked output or one part of a composite's whole. */
#include <stdlib.h>

#include "bd/kinds.h"

typedef struct select_content {
  size_t offset; /* first component */
  double sign;
} select_content;

static int select_apply(bd_block *b, double *v)
{
  const select_content *s = b->content;
  for (size_t i = 0; i < b->odim; ++i)
    v[b->ooff + i] = s->sign * v[b->ioff[0] + s->offset + i];
  return 0;
}

static int select_eval(bd_block *b, double t, double *w)
{
  (void)t;
  return select_apply(b, w);
}

static int select_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  return select_apply(b, dw);
}

static size_t select_nnz(const bd_block *b)
{
  return 2 * b->odim;
}

static int select_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                      double *v1)
{
  (void)w;
  const select_content *s = b->content;
  bd_trip t = {rows, cols, v0, v1, 0};
  for (size_t i = 0; i < b->odim; ++i) {
    fb_bd_trip_put(&t, b->ooff + i, b->ooff + i, 1.0, 0.0);
    fb_bd_trip_put(&t, b->ooff + i, b->ioff[0] + s->offset + i, -s->sign, 0.0);
  }
  return 0;
}

const bd_block_ops fb_bd_select_ops = {.kind = "demux",
                                       .linear = 1,
                                       .unit_rows = 1,
                                       .eval = select_eval,
                                       .jvp = select_jvp,
                                       .nnz = select_nnz,
                                       .jac = select_jac,
                                       .free = free,
                                       .input_dim = fb_bd_input_dim_any};

int fb_bd_select_new(size_t offset, double sign, bd_kind *out, fb_err *err)
{
  select_content *s = malloc(sizeof *s);
  if (!s)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  *s = (select_content){offset, sign};
  out->ops = &fb_bd_select_ops;
  out->content = s;
  return FB_OK;
}
