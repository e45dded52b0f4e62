/* SPDX-License-Identifier: BSD-3-Clause */
/* Mux: out = [c_1 in_1; ...; c_k in_k], the stacked ports of a field or
 * the whole of a composite. */
#include "bd/kinds.h"

static int mux_apply(bd_block *b, double *v)
{
  const bd_coef_content *m = b->content;
  size_t pos = b->ooff;
  for (size_t k = 0; k < b->nin; ++k)
    for (size_t i = 0; i < b->idim[k]; ++i)
      v[pos++] = m->coef[k] * v[b->ioff[k] + i];
  return 0;
}

static int mux_eval(bd_block *b, double t, double *w)
{
  (void)t;
  return mux_apply(b, w);
}

static int mux_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  return mux_apply(b, dw);
}

static size_t mux_nnz(const bd_block *b)
{
  return 2 * b->odim;
}

static int mux_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                   double *v1)
{
  (void)w;
  const bd_coef_content *m = b->content;
  bd_trip t = {rows, cols, v0, v1, 0};
  size_t pos = b->ooff;
  for (size_t k = 0; k < b->nin; ++k)
    for (size_t i = 0; i < b->idim[k]; ++i, ++pos) {
      fb_bd_trip_put(&t, pos, pos, 1.0, 0.0);
      fb_bd_trip_put(&t, pos, b->ioff[k] + i, -m->coef[k], 0.0);
    }
  return 0;
}

const bd_block_ops fb_bd_mux_ops = {.kind = "mux",
                                    .linear = 1,
                                    .unit_rows = 1,
                                    .eval = mux_eval,
                                    .jvp = mux_jvp,
                                    .nnz = mux_nnz,
                                    .jac = mux_jac,
                                    .free = fb_bd_coef_content_free,
                                    .input_dim = fb_bd_input_dim_any};

int fb_bd_mux_new(size_t n, const double *coef, bd_kind *out, fb_err *err)
{
  return fb_bd_coef_kind_new(&fb_bd_mux_ops, n, coef, out, err);
}
