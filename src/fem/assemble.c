/* SPDX-License-Identifier: BSD-3-Clause */
/* Sparse assembly of the shell model (fb_fem_assemble) and the rigid-body
 * mass properties of a mass matrix (fb_fem_mass_properties); see
 * flexbond/fem.h.
 *
 * Assembly is element by element into (row, column, value) triplets that
 * fb_mat_new_triplets sums into compressed sparse columns; K and M share
 * the row and column arrays because every element fills the same square
 * block of both. Nothing of model size is ever dense. */
#include <assert.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "flexbond/fem.h"

#include "fem/shell_internal.h"

/* Triplet arrays for K and M (either may be unused). */
typedef struct triplets {
  size_t n, cap;
  size_t *rows, *cols;
  double *kvals, *mvals;
} triplets;

/* Frees the arrays and clears the pointers (safe to call twice). */
static void triplets_free(triplets *t)
{
  free(t->rows);
  free(t->cols);
  free(t->kvals);
  free(t->mvals);
  t->rows = t->cols = NULL;
  t->kvals = t->mvals = NULL;
}

/* Room for one full element matrix per element. */
static int triplets_alloc(const fb_mesh *m, int want_k, int want_m, triplets *t, fb_err *err)
{
  size_t cap = 0;
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    const size_t n = 6 * (size_t)fb_mesh_element_type(m, e);
    cap += n * n;
  }
  assert(cap > 0); /* the caller rejects a mesh without elements */
  *t = (triplets){0, cap, NULL, NULL, NULL, NULL};
  if (cap > SIZE_MAX / sizeof(size_t))
    return fb_err_set(err, FB_ENOMEM, "mesh too large to assemble");
  t->rows = malloc(cap * sizeof *t->rows);
  t->cols = malloc(cap * sizeof *t->cols);
  t->kvals = want_k ? malloc(cap * sizeof *t->kvals) : NULL;
  t->mvals = want_m ? malloc(cap * sizeof *t->mvals) : NULL;
  if (!t->rows || !t->cols || (want_k && !t->kvals) || (want_m && !t->mvals)) {
    triplets_free(t);
    return fb_err_set(err, FB_ENOMEM, "out of memory assembling %zu matrix entries", cap);
  }
  return FB_OK;
}

/* Computes element e and appends its entries. */
static int add_element(const fb_mesh *m, size_t e, const fb_shell_props *base,
                       fb_mass_kind mass, triplets *t, fb_err *err)
{
  const fb_shell_props props = fb_mesh_element_props(m, e, base), *p = &props;
  const fb_elem_type type = fb_mesh_element_type(m, e);
  const size_t nn = (size_t)type, n = 6 * nn;
  const size_t *nodes = fb_mesh_element_nodes(m, e);
  double xyz[3 * 4], ke[24 * 24], me[24 * 24];
  for (size_t a = 0; a < nn; ++a)
    for (size_t k = 0; k < 3; ++k)
      xyz[3 * a + k] = fb_mesh_node_xyz(m, nodes[a])[k];
  int rc =
      fb_shell_element(type, xyz, p, mass, t->kvals ? ke : NULL, t->mvals ? me : NULL, err);
  if (rc) {
    fb_err_prefix(err, "element %ld: ", fb_mesh_element_id(m, e));
    return rc;
  }
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < n; ++i) {
      t->rows[t->n] = 6 * nodes[i / 6] + i % 6;
      t->cols[t->n] = 6 * nodes[j / 6] + j % 6;
      if (t->kvals)
        t->kvals[t->n] = ke[j * n + i];
      if (t->mvals)
        t->mvals[t->n] = me[j * n + i];
      ++t->n;
    }
  return FB_OK;
}

int fb_fem_assemble(const fb_mesh *m, const fb_shell_props *p, fb_mass_kind mass, fb_mat **K,
                    fb_mat **M, fb_err *err)
{
  if (K)
    *K = NULL;
  if (M)
    *M = NULL;
  if (!m || (!K && !M))
    return fb_err_set(err, FB_EINVAL, "fb_fem_assemble: NULL mesh or no output matrix");
  if (fb_mesh_nelements(m) == 0)
    return fb_err_set(err, FB_EINVAL, "fb_fem_assemble: the mesh has no elements");
  int rc = fb_shell_check_props(p, err);
  if (rc)
    return rc;
  const size_t ndof = 6 * fb_mesh_nnodes(m);
  triplets t;
  rc = triplets_alloc(m, K != NULL, M != NULL, &t, err);
  for (size_t e = 0; !rc && e < fb_mesh_nelements(m); ++e)
    rc = add_element(m, e, p, mass, &t, err);
  if (!rc && K)
    rc = fb_mat_new_triplets(ndof, ndof, t.n, t.rows, t.cols, t.kvals, K, err);
  if (!rc && M)
    rc = fb_mat_new_triplets(ndof, ndof, t.n, t.rows, t.cols, t.mvals, M, err);
  triplets_free(&t);
  if (rc && K)
    fb_mat_free(K);
  return rc;
}

/* ---- Mass properties. */

/* Rigid-body field of the mesh's nodes (6 per node): translation along
 * axis k (k < 3) or rotation about axis k - 3 through point o, with the
 * rotational DOFs equal to the rotation. */
static void rigid_mode(const fb_mesh *m, int k, const double *o, double *r)
{
  const size_t nn = fb_mesh_nnodes(m);
  for (size_t i = 0; i < nn; ++i) {
    double *ri = r + 6 * i;
    for (int q = 0; q < 6; ++q)
      ri[q] = 0.0;
    if (k < 3) {
      ri[k] = 1.0;
      continue;
    }
    const int ax = k - 3, a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
    const double *x = fb_mesh_node_xyz(m, i);
    /* e_ax x (x - o): components a1 and a2 only. */
    ri[a1] = -(x[a2] - o[a2]);
    ri[a2] = x[a1] - o[a1];
    ri[3 + ax] = 1.0;
  }
}

static double dot(size_t n, const double *a, const double *b)
{
  double s = 0.0;
  for (size_t i = 0; i < n; ++i)
    s += a[i] * b[i];
  return s;
}

/* Fills r (6 vectors of n) with the rigid-body modes about o and mr with M r. */
static void rigid_modes(const fb_mesh *m, const fb_mat *M, const double *o, double *r,
                        double *mr)
{
  const size_t n = 6 * fb_mesh_nnodes(m);
  for (int k = 0; k < 6; ++k) {
    rigid_mode(m, k, o, r + (size_t)k * n);
    fb_mat_gemv(M, 1.0, r + (size_t)k * n, 0.0, mr + (size_t)k * n);
  }
}

/* From the kinetic energy v^T M v / 2 of rigid motions v: with r_k the
 * unit translations and rotations about a point o, r_tx^T M r_tx is the mass, r_t(k+1)^T M
 * r_r(k+2) = m (c - o)_k gives the centre of mass c, and r_ri^T M r_rj about c is the inertia
 * tensor (sum of m (|x|^2 delta_ij - x_i x_j) for point masses). */
int fb_fem_mass_properties(const fb_mesh *m, const fb_mat *M, double *mass, double *cg,
                           double *inertia, fb_err *err)
{
  if (!m || !M || !mass || !cg || !inertia)
    return fb_err_set(err, FB_EINVAL, "fb_fem_mass_properties: NULL argument");
  const size_t nn = fb_mesh_nnodes(m), n = 6 * nn;
  if (nn == 0 || fb_mat_nrows(M) != n || fb_mat_ncols(M) != n)
    return fb_err_set(err, FB_EINVAL,
                      "fb_fem_mass_properties: mass matrix is %zu x %zu, the mesh has %zu DOFs",
                      fb_mat_nrows(M), fb_mat_ncols(M), n);
  double *r = malloc(12 * n * sizeof *r);
  if (!r)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the rigid-body modes");
  double *mr = r + 6 * n, origin[3] = {0.0, 0.0, 0.0};
  /* Moments about the node centroid, not the global origin, so that a
   * model far from the origin loses no digits to cancellation. */
  for (size_t i = 0; i < nn; ++i)
    for (int k = 0; k < 3; ++k)
      origin[k] += fb_mesh_node_xyz(m, i)[k] / (double)nn;
  rigid_modes(m, M, origin, r, mr);
  const double total = dot(n, r, mr);
  if (!(total > 0.0 && isfinite(total))) {
    free(r);
    return fb_err_set(err, FB_EINVAL,
                      "fb_fem_mass_properties: rigid-body mass %g is not positive", total);
  }
  for (int k = 0; k < 3; ++k)
    cg[k] = origin[k] +
            dot(n, r + (size_t)((k + 1) % 3) * n, mr + (size_t)(3 + (k + 2) % 3) * n) / total;
  rigid_modes(m, M, cg, r, mr);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      inertia[3 * i + j] = dot(n, r + (size_t)(3 + i) * n, mr + (size_t)(3 + j) * n);
  *mass = total;
  free(r);
  return FB_OK;
}
