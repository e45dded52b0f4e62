/* SPDX-License-Identifier: BSD-3-Clause */
/* What the block kinds share (bd/kinds.h): the registry that lists
 * them, the input_dim of inputs of any size, the content of the kinds
 * that hold one coefficient per input, and the triplet writer of their
 * rows. */
#include <stdlib.h>

#include "bd/kinds.h"

extern const bd_block_ops fb_bd_integrator_ops, fb_bd_source_ops, fb_bd_gain_ops,
    fb_bd_solve_ops, fb_bd_sum_ops, fb_bd_mux_ops, fb_bd_select_ops, fb_bd_product_ops,
    fb_bd_law_ops, fb_bd_energy_ops;

const bd_block_ops *const fb_bd_kinds[] = {
    &fb_bd_integrator_ops, &fb_bd_source_ops, &fb_bd_gain_ops,   &fb_bd_solve_ops,
    &fb_bd_sum_ops,        &fb_bd_mux_ops,    &fb_bd_select_ops, &fb_bd_product_ops,
    &fb_bd_law_ops,        &fb_bd_energy_ops,
};
const size_t fb_bd_nkinds = sizeof fb_bd_kinds / sizeof fb_bd_kinds[0];

int fb_bd_coef_kind_new(const bd_block_ops *ops, size_t n, const double *coef, bd_kind *out,
                        fb_err *err)
{
  bd_coef_content *content = malloc(sizeof *content);
  double *c = malloc((n + 1) * sizeof *c);
  if (!content || !c) {
    free(content);
    free(c);
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  }
  for (size_t k = 0; k < n; ++k)
    c[k] = coef ? coef[k] : 1.0;
  content->coef = c;
  out->ops = ops;
  out->content = content;
  return FB_OK;
}

void fb_bd_coef_content_free(void *content)
{
  bd_coef_content *c = content;
  if (c)
    free(c->coef);
  free(c);
}

size_t fb_bd_input_dim_any(const bd_block *b, size_t k)
{
  (void)b, (void)k;
  return FB_NONE;
}

void fb_bd_trip_put(bd_trip *t, size_t r, size_t c, double v0, double v1)
{
  if (t->rows) {
    t->rows[t->k] = r;
    t->cols[t->k] = c;
  }
  if (t->v0) {
    t->v0[t->k] = v0;
    t->v1[t->k] = v1;
  }
  t->k++;
}

void fb_bd_trip_identity(bd_trip *t, size_t off, size_t n)
{
  for (size_t i = 0; i < n; ++i)
    fb_bd_trip_put(t, off + i, off + i, 1.0, 0.0);
}

typedef struct mat_visit {
  bd_trip *t;
  size_t roff, coff;
  double scale;
} mat_visit;

static void visit_put(void *ctx, size_t r, size_t c, double v)
{
  mat_visit *m = ctx;
  fb_bd_trip_put(m->t, m->roff + r, m->coff + c, m->scale * v, 0.0);
}

void fb_bd_trip_matrix(bd_trip *t, const fb_mat *a, size_t roff, size_t coff, double scale,
                       size_t reserved)
{
  size_t start = t->k;
  mat_visit m = {t, roff, coff, scale};
  fb_mat_foreach(a, visit_put, &m);
  while (t->k < start + reserved)
    fb_bd_trip_put(t, roff, coff, 0.0, 0.0);
}
