/* SPDX-License-Identifier: BSD-3-Clause */
/* Solve: A out = in, by the sparse LU of A (M^-1 p without forming
 * M^-1), A borrowed from the graph or owned by the block. Its rows are
 * A d(out) - d(in) = 0: the one kind whose rows do not have the unit
 * coefficient on its output. */
#include <stdlib.h>
#include <string.h>

#include "bd/kinds.h"

typedef struct solve_content {
  fb_mat *a;
  int owned;
  fb_lu *lu;
} solve_content;

static int solve_apply(bd_block *b, double *v)
{
  const solve_content *s = b->content;
  memcpy(v + b->ooff, v + b->ioff[0], b->odim * sizeof *v);
  return fb_lu_solve(s->lu, v + b->ooff, 1, NULL) ? -1 : 0;
}

static int solve_eval(bd_block *b, double t, double *w)
{
  (void)t;
  return solve_apply(b, w);
}

static int solve_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  return solve_apply(b, dw);
}

static size_t solve_nnz(const bd_block *b)
{
  const solve_content *s = b->content;
  return b->odim + fb_mat_nnz(s->a);
}

static int solve_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                     double *v1)
{
  (void)w;
  const solve_content *s = b->content;
  bd_trip t = {rows, cols, v0, v1, 0};
  fb_bd_trip_matrix(&t, s->a, b->ooff, b->ooff, 1.0, fb_mat_nnz(s->a));
  for (size_t i = 0; i < b->odim; ++i)
    fb_bd_trip_put(&t, b->ooff + i, b->ioff[0] + i, -1.0, 0.0);
  return 0;
}

static size_t solve_input_dim(const bd_block *b, size_t k)
{
  (void)k;
  const solve_content *s = b->content;
  return fb_mat_ncols(s->a);
}

static void solve_free(void *content)
{
  solve_content *s = content;
  if (!s)
    return;
  if (s->owned)
    fb_mat_free(&s->a);
  fb_lu_free(&s->lu);
  free(s);
}

const bd_block_ops fb_bd_solve_ops = {.kind = "solve",
                                      .linear = 1,
                                      .eval = solve_eval,
                                      .jvp = solve_jvp,
                                      .nnz = solve_nnz,
                                      .jac = solve_jac,
                                      .free = solve_free,
                                      .input_dim = solve_input_dim};

int fb_bd_solve_new(fb_mat *a, int owned, bd_kind *out, fb_err *err)
{
  solve_content *s = calloc(1, sizeof *s);
  if (!s) {
    if (owned)
      fb_mat_free(&a);
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  }
  s->a = a;
  s->owned = owned;
  int rc = fb_lu_new(a, &s->lu, err);
  if (rc) {
    solve_free(s);
    return rc;
  }
  out->ops = &fb_bd_solve_ops;
  out->content = s;
  return FB_OK;
}
