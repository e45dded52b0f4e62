/* SPDX-License-Identifier: BSD-3-Clause */
/* Integrator: the output is a state x, input 0 its derivative x'. Its
 * rows are d(x) - gamma d(x') = b: the only rows with gamma terms. */
#include "bd/kinds.h"

static size_t integ_nnz(const bd_block *b)
{
  return 2 * b->odim;
}

static int integ_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                     double *v1)
{
  (void)w;
  bd_trip t = {rows, cols, v0, v1, 0};
  for (size_t i = 0; i < b->odim; ++i) {
    fb_bd_trip_put(&t, b->ooff + i, b->ooff + i, 1.0, 0.0);
    fb_bd_trip_put(&t, b->ooff + i, b->ioff[0] + i, 0.0, -1.0);
  }
  return 0;
}

/* A state is an unknown of its own: no perturbation flows through it
 * within one evaluation. */
static int integ_jvp(bd_block *b, const double *w, double *dw)
{
  (void)b, (void)w, (void)dw;
  return 0;
}

const bd_block_ops fb_bd_integrator_ops = {.kind = "integrator",
                                           .state = 1,
                                           .linear = 1,
                                           .unit_rows = 1,
                                           .symbol = "1/s",
                                           .jvp = integ_jvp,
                                           .nnz = integ_nnz,
                                           .jac = integ_jac};

bd_kind fb_bd_integrator_new(void)
{
  return (bd_kind){&fb_bd_integrator_ops, NULL};
}
