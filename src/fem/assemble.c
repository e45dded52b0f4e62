/* SPDX-License-Identifier: BSD-3-Clause */
/* Sparse assembly of the shell model (fb_fem_assemble) and the rigid-body
 * mass properties of a mass matrix or of a mesh (fb_fem_mass_properties,
 * fb_fem_mesh_mass_properties); see flexbond/fem.h. Nothing of model size
 * is ever dense. */
#include <assert.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"

#include "fem/shell_internal.h"

/* The matrices' sparsity: the mesh's node graph (each node's neighbours
 * in any element, itself included, ascending) and, over it, full 6 x 6
 * blocks of compressed sparse columns: column 6 a + k holds the rows
 * 6 b .. 6 b + 5 of each neighbour b of node a. */
typedef struct pattern {
  size_t nnodes;
  size_t *adj_start; /* nnodes + 1 */
  size_t *adj;
  size_t *colptr; /* 6 nnodes + 1 */
} pattern;

static void pattern_free(pattern *p)
{
  free(p->adj_start);
  free(p->adj);
  free(p->colptr);
}

static int cmp_size(const void *a, const void *b)
{
  const size_t x = *(const size_t *)a, y = *(const size_t *)b;
  return (x > y) - (x < y);
}

/* Each node's neighbours: every node of every element it is in, sorted,
 * repeats removed. */
static int node_graph(const fb_mesh *m, pattern *p, fb_err *err)
{
  const size_t nn = fb_mesh_nnodes(m), ne = fb_mesh_nelements(m);
  p->nnodes = nn;
  size_t *count = calloc(nn + 1, sizeof *count);
  p->adj_start = calloc(nn + 1, sizeof *p->adj_start);
  if (!count || !p->adj_start) {
    free(count);
    return fb_err_set(err, FB_ENOMEM, "out of memory for the mesh's node graph");
  }
  for (size_t e = 0; e < ne; ++e)
    for (size_t a = 0; a < (size_t)fb_mesh_element_type(m, e); ++a)
      count[fb_mesh_element_nodes(m, e)[a] + 1] += (size_t)fb_mesh_element_type(m, e);
  /* The superelement joins all its nodes, as one element of ns nodes. */
  const size_t *super = NULL;
  const size_t ns = fb_mesh_superelement(m, &super, NULL, NULL);
  for (size_t a = 0; a < ns; ++a)
    count[super[a] + 1] += ns;
  for (size_t i = 0; i < nn; ++i)
    count[i + 1] += count[i];
  p->adj = malloc((count[nn] ? count[nn] : 1) * sizeof *p->adj);
  if (!p->adj) {
    free(count);
    return fb_err_set(err, FB_ENOMEM, "out of memory for the mesh's node graph");
  }
  memcpy(p->adj_start, count, (nn + 1) * sizeof *count);
  for (size_t e = 0; e < ne; ++e) {
    const size_t nen = (size_t)fb_mesh_element_type(m, e);
    const size_t *nodes = fb_mesh_element_nodes(m, e);
    for (size_t a = 0; a < nen; ++a)
      for (size_t b = 0; b < nen; ++b)
        p->adj[count[nodes[a]]++] = nodes[b];
  }
  for (size_t a = 0; a < ns; ++a)
    for (size_t b = 0; b < ns; ++b)
      p->adj[count[super[a]]++] = super[b];
  free(count);
  /* Sort and compact each list in place; adj_start becomes the compact
   * starts. */
  size_t out = 0;
  for (size_t i = 0; i < nn; ++i) {
    size_t *list = p->adj + p->adj_start[i];
    const size_t len = p->adj_start[i + 1] - p->adj_start[i];
    qsort(list, len, sizeof *list, cmp_size);
    const size_t start = out;
    for (size_t k = 0; k < len; ++k)
      if (out == start || p->adj[out - 1] != list[k])
        p->adj[out++] = list[k];
    p->adj_start[i] = start;
  }
  p->adj_start[nn] = out;
  return FB_OK;
}

static int make_pattern(const fb_mesh *m, pattern *p, fb_err *err)
{
  memset(p, 0, sizeof *p);
  int rc = node_graph(m, p, err);
  const size_t nn = p->nnodes;
  if (!rc && nn > SIZE_MAX / 6 - 1)
    rc = fb_err_set(err, FB_ENOMEM, "mesh too large to assemble");
  if (!rc && !(p->colptr = malloc((6 * nn + 1) * sizeof *p->colptr)))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for the matrices' pattern");
  if (rc) {
    pattern_free(p);
    return rc;
  }
  p->colptr[0] = 0;
  for (size_t i = 0; i < nn; ++i) {
    const size_t len = 6 * (p->adj_start[i + 1] - p->adj_start[i]);
    for (size_t k = 0; k < 6; ++k)
      p->colptr[6 * i + k + 1] = p->colptr[6 * i + k] + len;
  }
  return FB_OK;
}

/* Where node b's rows start in node a's columns (b is a neighbour). */
static size_t block_offset(const pattern *p, size_t a, size_t b)
{
  const size_t *list = p->adj + p->adj_start[a];
  size_t k = 0;
  while (list[k] != b)
    ++k;
  return 6 * k;
}

/* Adds the dense column-major matrices ke and me (either NULL) over the
 * six DOFs of each of nodes[0 .. nen) into the values kv and mv laid out
 * by p. */
static void scatter(const pattern *p, const size_t *nodes, size_t nen, const double *ke,
                    const double *me, double *kv, double *mv)
{
  const size_t n = 6 * nen;
  for (size_t ja = 0; ja < nen; ++ja)
    for (size_t ib = 0; ib < nen; ++ib) {
      const size_t off = block_offset(p, nodes[ja], nodes[ib]);
      for (size_t k = 0; k < 6; ++k) {
        const size_t dst = p->colptr[6 * nodes[ja] + k] + off, src = (6 * ja + k) * n + 6 * ib;
        for (size_t l = 0; l < 6; ++l) {
          if (ke)
            kv[dst + l] += ke[src + l];
          if (me)
            mv[dst + l] += me[src + l];
        }
      }
    }
}

/* Computes element e and adds it into the values kv and mv (either
 * NULL) laid out by p. */
static int add_element(const fb_mesh *m, size_t e, const fb_shell_props *base,
                       fb_mass_kind mass, const pattern *p, double *kv, double *mv, fb_err *err)
{
  const fb_shell_props props = fb_mesh_element_props(m, e, base);
  const fb_elem_type type = fb_mesh_element_type(m, e);
  const size_t nen = (size_t)type;
  const size_t *nodes = fb_mesh_element_nodes(m, e);
  double xyz[3 * 4], ke[24 * 24], me[24 * 24];
  for (size_t a = 0; a < nen; ++a)
    for (size_t k = 0; k < 3; ++k)
      xyz[3 * a + k] = fb_mesh_node_xyz(m, nodes[a])[k];
  int rc = fb_shell_element(type, xyz, &props, mass, kv ? ke : NULL, mv ? me : NULL, err);
  if (rc) {
    fb_err_prefix(err, "element %ld: ", fb_mesh_element_id(m, e));
    return rc;
  }
  scatter(p, nodes, nen, kv ? ke : NULL, mv ? me : NULL, kv, mv);
  return FB_OK;
}

/* The superelement's matrices (fb_mesh_set_superelement) into kv and mv
 * (either NULL), laid out by p. */
static void add_superelement(const fb_mesh *m, const pattern *p, double *kv, double *mv)
{
  const size_t *nodes = NULL;
  const double *ks = NULL, *ms = NULL;
  const size_t ns = fb_mesh_superelement(m, &nodes, &ks, &ms);
  if (ns)
    scatter(p, nodes, ns, kv ? ks : NULL, mv ? ms : NULL, kv, mv);
}

/* The mesh's point masses on their nodes' translations (the diagonal
 * of their nodes' own blocks) of mv, laid out by p; a node in no element
 * has no block (fb_mesh_check refuses such a mesh). */
static int add_point_masses(const fb_mesh *m, const pattern *p, double *mv, fb_err *err)
{
  for (size_t i = 0; i < fb_mesh_npoint_masses(m); ++i) {
    const size_t a = fb_mesh_point_mass_node(m, i);
    if (p->adj_start[a] == p->adj_start[a + 1])
      return fb_err_set(err, FB_EINVAL, "point mass %ld: node %ld is in no element",
                        fb_mesh_point_mass_id(m, i), fb_mesh_node_id(m, a));
    const size_t off = block_offset(p, a, a);
    for (size_t k = 0; k < 3; ++k)
      mv[p->colptr[6 * a + k] + off + k] += fb_mesh_point_mass(m, i);
  }
  return FB_OK;
}

/* The matrix of values v laid out by p, its exact zeros left out. */
static int compress(const pattern *p, const double *v, fb_mat **out, fb_err *err)
{
  const size_t ncols = 6 * p->nnodes, cap = p->colptr[ncols];
  size_t *colptr = malloc((ncols + 1) * sizeof *colptr);
  size_t *rowidx = malloc((cap ? cap : 1) * sizeof *rowidx);
  double *vals = malloc((cap ? cap : 1) * sizeof *vals);
  int rc = colptr && rowidx && vals ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  size_t nnz = 0;
  for (size_t j = 0; !rc && j < ncols; ++j) {
    colptr[j] = nnz;
    const size_t a = j / 6;
    size_t k = p->colptr[j];
    for (size_t q = p->adj_start[a]; q < p->adj_start[a + 1]; ++q)
      for (size_t l = 0; l < 6; ++l, ++k)
        if (v[k] != 0.0) {
          rowidx[nnz] = 6 * p->adj[q] + l;
          vals[nnz++] = v[k];
        }
  }
  if (!rc) {
    colptr[ncols] = nnz;
    rc = fb_mat_new_csc(ncols, ncols, colptr, rowidx, vals, out, err);
  }
  free(colptr);
  free(rowidx);
  free(vals);
  return rc;
}

/* Assembly is element by element into the values of a pattern of 6 x 6
 * node blocks laid out once from the mesh's node graph: each element's
 * entries go straight to their places, in element order, so an entry is
 * the sum of its elements' contributions in that order (as a sum of
 * triplets would be). */
int fb_fem_assemble(const fb_mesh *m, const fb_shell_props *p, fb_mass_kind mass, fb_mat **K,
                    fb_mat **M, fb_err *err)
{
  if (K)
    *K = NULL;
  if (M)
    *M = NULL;
  if (!m || (!K && !M))
    return fb_err_set(err, FB_EINVAL, "fb_fem_assemble: NULL mesh or no output matrix");
  if (fb_mesh_nelements(m) == 0 && !fb_mesh_superelement(m, NULL, NULL, NULL))
    return fb_err_set(err, FB_EINVAL, "fb_fem_assemble: the mesh has no elements");
  int rc = fb_shell_check_props(p, err);
  if (rc)
    return rc;
  pattern pat;
  rc = make_pattern(m, &pat, err);
  if (rc)
    return rc;
  const size_t cap = pat.colptr[6 * pat.nnodes];
  double *kv = K ? calloc(cap ? cap : 1, sizeof *kv) : NULL;
  double *mv = M ? calloc(cap ? cap : 1, sizeof *mv) : NULL;
  if ((K && !kv) || (M && !mv))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory assembling %zu matrix entries", cap);
  for (size_t e = 0; !rc && e < fb_mesh_nelements(m); ++e)
    rc = add_element(m, e, p, mass, &pat, kv, mv, err);
  if (!rc)
    add_superelement(m, &pat, kv, mv);
  if (!rc && M)
    rc = add_point_masses(m, &pat, mv, err);
  if (!rc && K)
    rc = compress(&pat, kv, K, err);
  if (!rc && M)
    rc = compress(&pat, mv, M, err);
  free(kv);
  free(mv);
  pattern_free(&pat);
  if (rc && K)
    fb_mat_free(K);
  return rc;
}

/* ---- Mass properties. */

void fb_mesh_rigid_modes(const fb_mesh *m, const double *o, double *r)
{
  const size_t nn = fb_mesh_nnodes(m), n = 6 * nn;
  memset(r, 0, 6 * n * sizeof *r);
  for (size_t i = 0; i < nn; ++i) {
    const double *x = fb_mesh_node_xyz(m, i);
    for (int k = 0; k < 3; ++k) {
      r[(size_t)k * n + 6 * i + (size_t)k] = 1.0;
      /* Rotation about axis k through o: u = e_k x (x - o), the node's
       * rotation e_k. */
      double *col = r + (size_t)(3 + k) * n + 6 * i;
      const int a1 = (k + 1) % 3, a2 = (k + 2) % 3;
      col[a1] = -(x[a2] - o[a2]);
      col[a2] = x[a1] - o[a1];
      col[3 + k] = 1.0;
    }
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
  fb_mesh_rigid_modes(m, o, r);
  for (int k = 0; k < 6; ++k)
    fb_mat_gemv(M, 1.0, r + (size_t)k * n, 0.0, mr + (size_t)k * n);
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

/* Adds the point masses' m r' r to the 6 x 6 rigid-body mass matrix g
 * about o: r (3 x 6) moves a node at x by u = t + w x (x - o). */
static void add_point_rigid_mass(const fb_mesh *m, const double *o, double *g)
{
  for (size_t i = 0; i < fb_mesh_npoint_masses(m); ++i) {
    const double *x = fb_mesh_node_xyz(m, fb_mesh_point_mass_node(m, i));
    const double mass = fb_mesh_point_mass(m, i);
    double r[3][6] = {{0}};
    for (int k = 0; k < 3; ++k) {
      const int a1 = (k + 1) % 3, a2 = (k + 2) % 3;
      r[k][k] = 1.0;
      r[a1][3 + k] = -(x[a2] - o[a2]);
      r[a2][3 + k] = x[a1] - o[a1];
    }
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
        g[6 * a + b] += mass * (r[0][a] * r[0][b] + r[1][a] * r[1][b] + r[2][a] * r[2][b]);
  }
}

/* Adds r' me r to g (row-major 6 x 6): me the dense column-major mass
 * over the six DOFs of each of nodes[0 .. nn), r their rows of the six
 * rigid-body fields about o (rigid_mode's); r (6 * 6 nn) and mr (6 nn)
 * are the caller's room. */
static void add_rigid_block(const fb_mesh *m, const size_t *nodes, size_t nn, const double *me,
                            const double *o, double *r, double *mr, double *g)
{
  const size_t n = 6 * nn;
  memset(r, 0, 6 * n * sizeof *r);
  for (int k = 0; k < 6; ++k)
    for (size_t a = 0; a < nn; ++a) {
      const double *xyz = fb_mesh_node_xyz(m, nodes[a]);
      double *ra = r + (size_t)k * n + 6 * a;
      if (k < 3) {
        ra[k] = 1.0;
        continue;
      }
      const int ax = k - 3, a1 = (ax + 1) % 3, a2 = (ax + 2) % 3;
      ra[a1] = -(xyz[a2] - o[a2]);
      ra[a2] = xyz[a1] - o[a1];
      ra[3 + ax] = 1.0;
    }
  for (int j = 0; j < 6; ++j) {
    for (size_t i = 0; i < n; ++i) {
      double sum = 0.0;
      for (size_t l = 0; l < n; ++l)
        sum += me[l * n + i] * r[(size_t)j * n + l];
      mr[i] = sum;
    }
    for (int i = 0; i < 6; ++i)
      g[6 * i + j] += dot(n, r + (size_t)i * n, mr);
  }
}

/* The superelement's r' M r about o added to g. */
static int add_superelement_rigid_mass(const fb_mesh *m, const double *o, double *g,
                                       fb_err *err)
{
  const size_t *nodes = NULL;
  const double *ms = NULL;
  const size_t ns = fb_mesh_superelement(m, &nodes, NULL, &ms);
  if (!ns)
    return FB_OK;
  double *r = malloc(36 * ns * sizeof *r), *mr = malloc(6 * ns * sizeof *mr);
  if (r && mr)
    add_rigid_block(m, nodes, ns, ms, o, r, mr, g);
  free(r);
  free(mr);
  return r && mr ? FB_OK
                 : fb_err_set(err, FB_ENOMEM, "out of memory for a superelement's mass");
}

/* The 6 x 6 rigid-body mass matrix about o, sum over the elements (and
 * the superelement) of r_e' M_e r_e (r_e: the element's rows of the six
 * rigid-body fields about o), into g (row-major). */
static int rigid_mass_about(const fb_mesh *m, const fb_shell_props *p, fb_mass_kind kind,
                            const double *o, double *g, fb_err *err)
{
  for (int k = 0; k < 36; ++k)
    g[k] = 0.0;
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    const fb_shell_props props = fb_mesh_element_props(m, e, p);
    const fb_elem_type type = fb_mesh_element_type(m, e);
    const size_t nn = (size_t)type;
    const size_t *nodes = fb_mesh_element_nodes(m, e);
    double xyz[3 * 4], me[24 * 24], r[6 * 24], mr[24];
    for (size_t a = 0; a < nn; ++a)
      for (size_t k = 0; k < 3; ++k)
        xyz[3 * a + k] = fb_mesh_node_xyz(m, nodes[a])[k];
    const int rc = fb_shell_element(type, xyz, &props, kind, NULL, me, err);
    if (rc)
      return fb_err_prefix(err, "element %ld: ", fb_mesh_element_id(m, e)), rc;
    add_rigid_block(m, nodes, nn, me, o, r, mr, g);
  }
  add_point_rigid_mass(m, o, g);
  return add_superelement_rigid_mass(m, o, g, err);
}

/* As fb_fem_mass_properties, from the same kinetic energies of rigid
 * motions, summed element by element: about the node centroid first,
 * then about the centre of mass found there. */
int fb_fem_mesh_mass_properties(const fb_mesh *m, const fb_shell_props *p, fb_mass_kind kind,
                                double *mass, double *cg, double *inertia, fb_err *err)
{
  if (!m || !p || !mass || !cg || !inertia)
    return fb_err_set(err, FB_EINVAL, "fb_fem_mesh_mass_properties: NULL argument");
  const size_t nn = fb_mesh_nnodes(m);
  if (nn == 0 || (fb_mesh_nelements(m) == 0 && !fb_mesh_superelement(m, NULL, NULL, NULL)))
    return fb_err_set(err, FB_EINVAL, "fb_fem_mesh_mass_properties: the mesh has no elements");
  int rc = fb_shell_check_props(p, err);
  if (rc)
    return rc;
  double origin[3] = {0.0, 0.0, 0.0}, g[36];
  for (size_t i = 0; i < nn; ++i)
    for (int k = 0; k < 3; ++k)
      origin[k] += fb_mesh_node_xyz(m, i)[k] / (double)nn;
  rc = rigid_mass_about(m, p, kind, origin, g, err);
  if (rc)
    return rc;
  const double total = g[0];
  if (!(total > 0.0 && isfinite(total)))
    return fb_err_set(err, FB_EINVAL,
                      "fb_fem_mesh_mass_properties: rigid-body mass %g is not positive", total);
  for (int k = 0; k < 3; ++k)
    cg[k] = origin[k] + g[6 * ((k + 1) % 3) + 3 + (k + 2) % 3] / total;
  rc = rigid_mass_about(m, p, kind, cg, g, err);
  if (rc)
    return rc;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      inertia[3 * i + j] = g[6 * (3 + i) + 3 + j];
  *mass = total;
  return FB_OK;
}
