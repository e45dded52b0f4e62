/* SPDX-License-Identifier: BSD-3-Clause */
/* Element-wise product: out = in_1 .* in_2 (a power probe's e .* f). */
#include "bd/kinds.h"

static int product_eval(bd_block *b, double t, double *w)
{
  (void)t;
  for (size_t i = 0; i < b->odim; ++i)
    w[b->ooff + i] = w[b->ioff[0] + i] * w[b->ioff[1] + i];
  return 0;
}

static int product_jvp(bd_block *b, const double *w, double *dw)
{
  for (size_t i = 0; i < b->odim; ++i)
    dw[b->ooff + i] =
        dw[b->ioff[0] + i] * w[b->ioff[1] + i] + w[b->ioff[0] + i] * dw[b->ioff[1] + i];
  return 0;
}

static size_t product_nnz(const bd_block *b)
{
  return 3 * b->odim;
}

static int product_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                       double *v1)
{
  bd_trip t = {rows, cols, v0, v1, 0};
  for (size_t i = 0; i < b->odim; ++i) {
    fb_bd_trip_put(&t, b->ooff + i, b->ooff + i, 1.0, 0.0);
    fb_bd_trip_put(&t, b->ooff + i, b->ioff[0] + i, -w[b->ioff[1] + i], 0.0);
    fb_bd_trip_put(&t, b->ooff + i, b->ioff[1] + i, -w[b->ioff[0] + i], 0.0);
  }
  return 0;
}

const bd_block_ops fb_bd_product_ops = {.kind = "product",
                                        .unit_rows = 1,
                                        .product = 1,
                                        .eval = product_eval,
                                        .jvp = product_jvp,
                                        .nnz = product_nnz,
                                        .jac = product_jac};

bd_kind fb_bd_product_new(void)
{
  return (bd_kind){&fb_bd_product_ops, NULL};
}
