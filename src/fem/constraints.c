/* SPDX-License-Identifier: BSD-3-Clause */
/* Boundary conditions by elimination of fixed DOFs: fb_fem_free_dofs and
 * fb_fem_submatrix (see flexbond/fem.h). */
#include <stdint.h>
#include <stdlib.h>

#include "flexbond/fem.h"

/* A DOF listed twice is an error rather than merged, because the contract
 * promises exactly n - nfixed kept DOFs (a caller fixing two overlapping
 * node sets must merge them first). */
int fb_fem_free_dofs(size_t n, const size_t *fixed, size_t nfixed, size_t *keep, fb_err *err)
{
  if ((nfixed && !fixed) || (nfixed < n && !keep))
    return fb_err_set(err, FB_EINVAL, "fb_fem_free_dofs: NULL array");
  if (nfixed > n)
    return fb_err_set(err, FB_EINVAL, "fb_fem_free_dofs: %zu fixed DOFs out of %zu", nfixed, n);
  unsigned char *is_fixed = calloc(n ? n : 1, 1);
  if (!is_fixed)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu DOF flags", n);
  for (size_t i = 0; i < nfixed; ++i) {
    const size_t d = fixed[i];
    int rc = FB_OK;
    if (d >= n)
      rc = fb_err_set(err, FB_EINVAL, "fb_fem_free_dofs: fixed DOF %zu out of range (%zu DOFs)",
                      d, n);
    else if (is_fixed[d])
      rc = fb_err_set(err, FB_EINVAL,
                      "fb_fem_free_dofs: DOF %zu (node %zu, component %zu) fixed "
                      "twice",
                      d, d / 6, d % 6);
    if (rc) {
      free(is_fixed);
      return rc;
    }
    is_fixed[d] = 1;
  }
  size_t nkeep = 0;
  for (size_t d = 0; d < n; ++d)
    if (!is_fixed[d])
      keep[nkeep++] = d;
  free(is_fixed);
  return FB_OK;
}

/* Gathers the kept entries of a, through the map from old to new index
 * (SIZE_MAX for a dropped index), as triplets (sparse) or into a dense
 * column-major array. */
typedef struct gather {
  const size_t *map;
  size_t nkeep, count;
  size_t *rows, *cols;
  double *vals;  /* triplet values (sparse) */
  double *dense; /* nkeep x nkeep (dense) */
} gather;

static void gather_entry(void *ctx, size_t row, size_t col, double val)
{
  gather *g = ctx;
  const size_t i = g->map[row], j = g->map[col];
  if (i == SIZE_MAX || j == SIZE_MAX)
    return;
  if (g->dense) {
    g->dense[j * g->nkeep + i] = val;
    return;
  }
  g->rows[g->count] = i;
  g->cols[g->count] = j;
  g->vals[g->count++] = val;
}

/* Checks keep[] (strictly increasing, below n) and builds the index map. */
static int keep_map(size_t n, const size_t *keep, size_t nkeep, size_t **map, fb_err *err)
{
  *map = NULL;
  for (size_t i = 0; i < nkeep; ++i)
    if (keep[i] >= n || (i > 0 && keep[i] <= keep[i - 1]))
      return fb_err_set(err, FB_EINVAL,
                        "fb_fem_submatrix: keep[%zu] = %zu is out of range (%zu) or not "
                        "increasing",
                        i, keep[i], n);
  *map = malloc(n * sizeof **map);
  if (!*map)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a DOF map of %zu", n);
  for (size_t i = 0; i < n; ++i)
    (*map)[i] = SIZE_MAX;
  for (size_t i = 0; i < nkeep; ++i)
    (*map)[keep[i]] = i;
  return FB_OK;
}

static int gather_build(const fb_mat *a, gather *g, fb_mat **out, fb_err *err)
{
  const size_t cap = fb_mat_is_sparse(a) ? fb_mat_nnz(a) : 0;
  if (fb_mat_is_sparse(a)) {
    g->rows = malloc((cap ? cap : 1) * sizeof *g->rows);
    g->cols = malloc((cap ? cap : 1) * sizeof *g->cols);
    g->vals = malloc((cap ? cap : 1) * sizeof *g->vals);
  } else {
    g->dense = calloc(g->nkeep * g->nkeep, sizeof *g->dense);
  }
  int rc = FB_OK;
  if (fb_mat_is_sparse(a) ? (!g->rows || !g->cols || !g->vals) : !g->dense)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory extracting a %zu x %zu submatrix", g->nkeep,
                    g->nkeep);
  if (!rc) {
    fb_mat_foreach(a, gather_entry, g);
    rc = g->dense ? fb_mat_new_dense(g->nkeep, g->nkeep, g->dense, out, err)
                  : fb_mat_new_triplets(g->nkeep, g->nkeep, g->count, g->rows, g->cols, g->vals,
                                        out, err);
  }
  free(g->rows);
  free(g->cols);
  free(g->vals);
  free(g->dense);
  return rc;
}

int fb_fem_submatrix(const fb_mat *a, const size_t *keep, size_t nkeep, fb_mat **out,
                     fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "fb_fem_submatrix: NULL output");
  *out = NULL;
  if (!a || !keep || nkeep == 0)
    return fb_err_set(err, FB_EINVAL, "fb_fem_submatrix: NULL matrix or nothing kept");
  const size_t n = fb_mat_nrows(a);
  if (fb_mat_ncols(a) != n)
    return fb_err_set(err, FB_EINVAL, "fb_fem_submatrix: matrix is %zu x %zu, not square", n,
                      fb_mat_ncols(a));
  size_t *map;
  int rc = keep_map(n, keep, nkeep, &map, err);
  if (rc)
    return rc;
  gather g = {map, nkeep, 0, NULL, NULL, NULL, NULL};
  rc = gather_build(a, &g, out, err);
  free(map);
  return rc;
}
