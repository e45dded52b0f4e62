/* SPDX-License-Identifier: BSD-3-Clause */
/* Signed sum: out = sum_k c_k in_k (zero inputs: out = 0), a junction's
 * law. */
#include <string.h>

#include "bd/kinds.h"

static int sum_apply(bd_block *b, double *v)
{
  const bd_coef_content *s = b->content;
  double *y = v + b->ooff;
  memset(y, 0, b->odim * sizeof *y);
  for (size_t k = 0; k < b->nin; ++k) {
    const double *u = v + b->ioff[k];
    for (size_t i = 0; i < b->odim; ++i)
      y[i] += s->coef[k] * u[i];
  }
  return 0;
}

static int sum_eval(bd_block *b, double t, double *w)
{
  (void)t;
  return sum_apply(b, w);
}

static int sum_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  return sum_apply(b, dw);
}

static size_t sum_nnz(const bd_block *b)
{
  return b->odim * (1 + b->nin);
}

static int sum_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                   double *v1)
{
  (void)w;
  const bd_coef_content *s = b->content;
  bd_trip t = {rows, cols, v0, v1, 0};
  fb_bd_trip_identity(&t, b->ooff, b->odim);
  for (size_t k = 0; k < b->nin; ++k)
    for (size_t i = 0; i < b->odim; ++i)
      fb_bd_trip_put(&t, b->ooff + i, b->ioff[k] + i, -s->coef[k], 0.0);
  return 0;
}

const bd_block_ops fb_bd_sum_ops = {.kind = "sum",
                                    .linear = 1,
                                    .unit_rows = 1,
                                    .eval = sum_eval,
                                    .jvp = sum_jvp,
                                    .nnz = sum_nnz,
                                    .jac = sum_jac,
                                    .free = fb_bd_coef_content_free};

int fb_bd_sum_new(size_t n, const double *coef, bd_kind *out, fb_err *err)
{
  return fb_bd_coef_kind_new(&fb_bd_sum_ops, n, coef, out, err);
}
