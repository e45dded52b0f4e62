/* SPDX-License-Identifier: BSD-3-Clause */
/* Stored energy of a storage field with state x (input 0) and
 * co-variable y (input 1): linear law 1/2 x.y, or the law's energy
 * function, whose gradient is y (Karnopp et al., section 7.2). The
 * linearisation of the law's energy uses that gradient, y, so it holds
 * where y is the law's output at x, as in the diagram
 * (consistent_inputs). */
#include <stdlib.h>

#include "bd/kinds.h"

typedef struct energy_content {
  const fb_law_ops *law; /* NULL for a linear field; borrowed, as ctx */
  void *ctx;
} energy_content;

static int energy_eval(bd_block *b, double t, double *w)
{
  (void)t;
  const energy_content *c = b->content;
  size_t n = b->idim[0];
  const double *x = w + b->ioff[0], *y = w + b->ioff[1];
  if (c->law) {
    w[b->ooff] = c->law->energy(c->ctx, n, x);
    return 0;
  }
  double s = 0.0;
  for (size_t i = 0; i < n; ++i)
    s += x[i] * y[i];
  w[b->ooff] = 0.5 * s;
  return 0;
}

static int energy_jvp(bd_block *b, const double *w, double *dw)
{
  const energy_content *c = b->content;
  size_t n = b->idim[0];
  const double *x = w + b->ioff[0], *y = w + b->ioff[1];
  const double *dx = dw + b->ioff[0], *dy = dw + b->ioff[1];
  double s = 0.0;
  for (size_t i = 0; i < n; ++i)
    s += c->law ? y[i] * dx[i] : 0.5 * (y[i] * dx[i] + x[i] * dy[i]);
  dw[b->ooff] = s;
  return 0;
}

static size_t energy_nnz(const bd_block *b)
{
  return 1 + 2 * b->idim[0];
}

static int energy_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                      double *v1)
{
  const energy_content *c = b->content;
  size_t n = b->idim[0];
  const double *x = w + b->ioff[0], *y = w + b->ioff[1];
  bd_trip t = {rows, cols, v0, v1, 0};
  fb_bd_trip_put(&t, b->ooff, b->ooff, 1.0, 0.0);
  for (size_t i = 0; i < n; ++i) {
    fb_bd_trip_put(&t, b->ooff, b->ioff[0] + i, c->law ? -y[i] : -0.5 * y[i], 0.0);
    fb_bd_trip_put(&t, b->ooff, b->ioff[1] + i, c->law ? 0.0 : -0.5 * x[i], 0.0);
  }
  return 0;
}

const bd_block_ops fb_bd_energy_ops = {.kind = "energy",
                                       .unit_rows = 1,
                                       .consistent_inputs = 1,
                                       .eval = energy_eval,
                                       .jvp = energy_jvp,
                                       .nnz = energy_nnz,
                                       .jac = energy_jac,
                                       .free = free,
                                       .input_dim = fb_bd_input_dim_any};

int fb_bd_energy_new(const fb_law_ops *law, void *ctx, bd_kind *out, fb_err *err)
{
  energy_content *c = malloc(sizeof *c);
  if (!c)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  *c = (energy_content){law, ctx};
  out->ops = &fb_bd_energy_ops;
  out->content = c;
  return FB_OK;
}
