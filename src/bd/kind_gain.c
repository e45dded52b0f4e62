/* SPDX-License-Identifier: BSD-3-Clause */
/* Gain: out = A in, A borrowed from the graph or owned by the block. */
#include <stdlib.h>

#include "bd/kinds.h"

typedef struct gain_content {
  fb_mat *a;
  int owned;
} gain_content;

static int gain_apply(bd_block *b, double *v)
{
  const gain_content *g = b->content;
  fb_mat_gemv(g->a, 1.0, v + b->ioff[0], 0.0, v + b->ooff);
  return 0;
}

static int gain_eval(bd_block *b, double t, double *w)
{
  (void)t;
  return gain_apply(b, w);
}

static int gain_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  return gain_apply(b, dw);
}

static size_t gain_nnz(const bd_block *b)
{
  const gain_content *g = b->content;
  return b->odim + fb_mat_nnz(g->a);
}

static int gain_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                    double *v1)
{
  (void)w;
  const gain_content *g = b->content;
  bd_trip t = {rows, cols, v0, v1, 0};
  fb_bd_trip_identity(&t, b->ooff, b->odim);
  fb_bd_trip_matrix(&t, g->a, b->ooff, b->ioff[0], -1.0, fb_mat_nnz(g->a));
  return 0;
}

static size_t gain_input_dim(const bd_block *b, size_t k)
{
  (void)k;
  const gain_content *g = b->content;
  return fb_mat_ncols(g->a);
}

static void gain_free(void *content)
{
  gain_content *g = content;
  if (g && g->owned)
    fb_mat_free(&g->a);
  free(g);
}

const bd_block_ops fb_bd_gain_ops = {.kind = "gain",
                                     .linear = 1,
                                     .unit_rows = 1,
                                     .eval = gain_eval,
                                     .jvp = gain_jvp,
                                     .nnz = gain_nnz,
                                     .jac = gain_jac,
                                     .free = gain_free,
                                     .input_dim = gain_input_dim};

int fb_bd_gain_new(fb_mat *a, int owned, bd_kind *out, fb_err *err)
{
  gain_content *g = malloc(sizeof *g);
  if (!g) {
    if (owned)
      fb_mat_free(&a);
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  }
  *g = (gain_content){a, owned};
  out->ops = &fb_bd_gain_ops;
  out->content = g;
  return FB_OK;
}
