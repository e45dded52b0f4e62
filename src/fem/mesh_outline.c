/* SPDX-License-Identifier: BSD-3-Clause */
/* A shell mesh's outline: the edges a drawing keeps when it leaves the
 * element edges out, the "feature edges" of surface rendering. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "flexbond/fem.h"

/* An edge (a < b) and an element it bounds. */
typedef struct edge_use {
  size_t a, b, e;
} edge_use;

static int edge_use_cmp(const void *p, const void *q)
{
  const edge_use *x = p, *y = q;
  if (x->a != y->a)
    return x->a < y->a ? -1 : 1;
  if (x->b != y->b)
    return x->b < y->b ? -1 : 1;
  return x->e < y->e ? -1 : x->e > y->e;
}

/* |cos| of the angle between the planes of elements e and f; 1 when one
 * has no area. */
static double planes_cos(const fb_mesh *m, size_t e, size_t f)
{
  double p[3], q[3];
  fb_mesh_element_area_vector(m, e, p);
  fb_mesh_element_area_vector(m, f, q);
  const double len = sqrt((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) *
                          (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]));
  return len > 0 ? fabs(p[0] * q[0] + p[1] * q[1] + p[2] * q[2]) / len : 1.0;
}

/* 1 if the edge used by the n elements of use belongs to the outline. */
static int is_feature(const fb_mesh *m, const edge_use *use, size_t n, double cos_angle)
{
  return n != 2 || planes_cos(m, use[0].e, use[1].e) < cos_angle;
}

static size_t collect(const fb_mesh *m, edge_use *use)
{
  size_t n = 0;
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    const size_t *nd = fb_mesh_element_nodes(m, e);
    const size_t nn = (size_t)fb_mesh_element_type(m, e);
    for (size_t k = 0; k < nn; ++k) {
      const size_t a = nd[k], b = nd[(k + 1) % nn];
      use[n++] = (edge_use){a < b ? a : b, a < b ? b : a, e};
    }
  }
  return n;
}

int fb_mesh_outline(const fb_mesh *m, double angle, size_t **edges, size_t *nedges, fb_err *err)
{
  const size_t ne = fb_mesh_nelements(m);
  *edges = NULL;
  *nedges = 0;
  if (ne > SIZE_MAX / (4 * sizeof(edge_use)))
    return fb_err_set(err, FB_ENOMEM, "a mesh of %zu elements is too large for its outline",
                      ne);
  edge_use *use = malloc(4 * ne * sizeof *use + 1);
  /* Two nodes per edge, at most four edges per element: no larger than use. */
  size_t *out = malloc(8 * ne * sizeof *out + 1);
  if (!use || !out) {
    free(use);
    free(out);
    return fb_err_set(err, FB_ENOMEM, "out of memory for the outline of %zu elements", ne);
  }
  const size_t nuse = collect(m, use);
  qsort(use, nuse, sizeof *use, edge_use_cmp);
  const double cos_angle = cos(angle);
  size_t n = 0;
  for (size_t i = 0, j; i < nuse; i = j) {
    for (j = i + 1; j < nuse && use[j].a == use[i].a && use[j].b == use[i].b; ++j)
      ;
    if (is_feature(m, use + i, j - i, cos_angle)) {
      out[2 * n] = use[i].a;
      out[2 * n + 1] = use[i].b;
      ++n;
    }
  }
  free(use);
  *edges = out;
  *nedges = n;
  return FB_OK;
}
