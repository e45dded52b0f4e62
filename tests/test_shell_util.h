/* SPDX-License-Identifier: BSD-3-Clause */
/* Helpers shared by the shell element tests (test_shell.c, test_nafems.c):
 * programmatic meshes of flat faces, boundary conditions by position,
 * static solves and modal analyses. Every library call must succeed; a
 * failure prints the library's message and counts as a failed check. */
#ifndef FLEXBOND_TEST_SHELL_UTIL_H
#define FLEXBOND_TEST_SHELL_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/fem.h"

#include "check.h"

static inline int shell_ok(int rc, const fb_err *err, const char *what)
{
  if (rc)
    fprintf(stderr, "%s failed: %s\n", what, err->msg);
  return rc == 0;
}

#define MUST(call, err) CHECK(shell_ok((call), (err), #call))

/* Steel plate of the NAFEMS free-vibration benchmarks (FV12, FV16, FV52). */
static const fb_shell_props NAFEMS_STEEL = {200e9, 0.3, 8000.0, 0.05, 0.0, 0.0};

/* Index of the node at p, added (id = index + 1) if there is none within
 * 1e-9 m: faces built one after the other share their edge nodes. */
static inline size_t shell_node(fb_mesh *m, const double *p)
{
  fb_err err;
  const long found = fb_mesh_find_node_at(m, p[0], p[1], p[2], 1e-9);
  if (found >= 0)
    return (size_t)found;
  size_t index = 0;
  MUST(fb_mesh_add_node(m, (long)fb_mesh_nnodes(m) + 1, p[0], p[1], p[2], &index, &err), &err);
  return index;
}

/* Adds a flat face origin + s du + t dv, (s, t) in [0, 1]^2, meshed with
 * nx x ny quadrilaterals (tri = 0) or each split along its diagonal 1-3
 * into two triangles (tri = 1). distort > 0 moves the interior grid points
 * within the face by distort / n times a smooth field that vanishes on the
 * face's edges (so neighbouring faces still match), giving irregular
 * but convex elements for distort up to about 0.3. */
static inline void shell_face(fb_mesh *m, const double *origin, const double *du,
                              const double *dv, int nx, int ny, int tri, double distort)
{
  fb_err err;
  size_t *idx = malloc((size_t)(nx + 1) * (size_t)(ny + 1) * sizeof *idx);
  CHECK(idx != NULL);
  if (!idx)
    return;
  const double pi = 3.14159265358979323846;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      double s = (double)i / nx, t = (double)j / ny;
      const double bump = sin(pi * s) * sin(pi * t);
      s += distort / nx * bump * sin(2.0 * pi * t + 1.0);
      t += distort / ny * bump * cos(3.0 * pi * s + 0.5);
      double p[3];
      for (int k = 0; k < 3; ++k)
        p[k] = origin[k] + s * du[k] + t * dv[k];
      idx[j * (nx + 1) + i] = shell_node(m, p);
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const size_t a = idx[j * (nx + 1) + i], b = idx[j * (nx + 1) + i + 1];
      const size_t c = idx[(j + 1) * (nx + 1) + i + 1], d = idx[(j + 1) * (nx + 1) + i];
      const long id = (long)fb_mesh_nelements(m) + 1;
      if (tri) {
        const size_t t1[3] = {a, b, c}, t2[3] = {a, c, d};
        MUST(fb_mesh_add_element(m, id, FB_ELEM_TRI3, t1, &err), &err);
        MUST(fb_mesh_add_element(m, id + 1, FB_ELEM_TRI3, t2, &err), &err);
      } else {
        const size_t q[4] = {a, b, c, d};
        MUST(fb_mesh_add_element(m, id, FB_ELEM_QUAD4, q, &err), &err);
      }
    }
  free(idx);
}

/* A rectangular plate [0, lx] x [0, ly] in the plane z = 0. */
static inline fb_mesh *shell_plate(double lx, double ly, int nx, int ny, int tri,
                                   double distort)
{
  fb_mesh *m = NULL;
  fb_err err;
  MUST(fb_mesh_new(&m, &err), &err);
  const double o[3] = {0.0, 0.0, 0.0}, du[3] = {lx, 0.0, 0.0}, dv[3] = {0.0, ly, 0.0};
  if (m)
    shell_face(m, o, du, dv, nx, ny, tri, distort);
  return m;
}

/* Appends DOF component k (0..5) of node to the fixed list. */
static inline void shell_fix(size_t *fixed, size_t *nfixed, size_t node, size_t k)
{
  fixed[(*nfixed)++] = 6 * node + k;
}

/* Appends every DOF of the nodes at x = 0 (within 1e-9 m) to the fixed
 * list: a clamped edge. */
static inline void shell_clamp_x0(const fb_mesh *m, size_t *fixed, size_t *nfixed)
{
  for (size_t a = 0; a < fb_mesh_nnodes(m); ++a)
    if (fb_mesh_node_xyz(m, a)[0] < 1e-9)
      for (size_t k = 0; k < 6; ++k)
        shell_fix(fixed, nfixed, a, k);
}

/* K and M reduced to the DOFs not in fixed[] (which need not be sorted
 * but must be distinct); keep[] (6 nnodes) receives the kept DOFs. */
static inline void shell_reduce(const fb_mat *K, const fb_mat *M, const size_t *fixed,
                                size_t nfixed, size_t *keep, fb_mat **Kf, fb_mat **Mf)
{
  fb_err err;
  const size_t n = fb_mat_nrows(K);
  MUST(fb_fem_free_dofs(n, fixed, nfixed, keep, &err), &err);
  MUST(fb_fem_submatrix(K, keep, n - nfixed, Kf, &err), &err);
  if (M)
    MUST(fb_fem_submatrix(M, keep, n - nfixed, Mf, &err), &err);
}

/* u (6 nnodes) solves K u = f with the fixed DOFs (distinct) held at 0. */
static inline void shell_static(const fb_mat *K, const size_t *fixed, size_t nfixed,
                                const double *f, double *u)
{
  fb_err err;
  const size_t n = fb_mat_nrows(K);
  size_t *keep = malloc(n * sizeof *keep);
  double *r = malloc(n * sizeof *r);
  fb_mat *Kf = NULL;
  fb_lu *lu = NULL;
  CHECK(keep && r);
  for (size_t i = 0; i < n; ++i)
    u[i] = NAN; /* fails every later comparison if the solve fails */
  if (keep && r) {
    shell_reduce(K, NULL, fixed, nfixed, keep, &Kf, NULL);
    for (size_t i = 0; i < n - nfixed; ++i)
      r[i] = f[keep[i]];
    if (Kf)
      MUST(fb_lu_new(Kf, &lu, &err), &err);
    const int solved = lu && shell_ok(fb_lu_solve(lu, r, 1, &err), &err, "fb_lu_solve");
    CHECK(solved);
    if (solved) {
      for (size_t i = 0; i < n; ++i)
        u[i] = 0.0;
      for (size_t i = 0; i < n - nfixed; ++i)
        u[keep[i]] = r[i];
    }
  }
  fb_lu_free(&lu);
  fb_mat_free(&Kf);
  free(keep);
  free(r);
}

/* The eigen-solver's options with its method (FB_EIG_DENSE, FB_EIG_LANCZOS,
 * FB_EIG_AUTO) chosen. */
static inline fb_eig_opts eig_with(fb_eig_method method)
{
  fb_eig_opts o;
  fb_eig_opts_default(&o);
  o.method = method;
  return o;
}

/* Lowest nmodes frequencies (Hz) of the structure with the fixed DOFs
 * removed, by the eigen-solver's method. */
static inline void shell_frequencies(const fb_mesh *m, const fb_shell_props *p,
                                     fb_mass_kind mass, const size_t *fixed, size_t nfixed,
                                     size_t nmodes, fb_eig_method method, double *freq)
{
  const fb_eig_opts eig = eig_with(method);
  fb_err err;
  fb_mat *K = NULL, *M = NULL, *Kf = NULL, *Mf = NULL;
  const size_t n = 6 * fb_mesh_nnodes(m);
  size_t *keep = malloc(n * sizeof *keep);
  CHECK(keep != NULL);
  for (size_t i = 0; i < nmodes; ++i)
    freq[i] = NAN; /* fails every later comparison if the solve fails */
  MUST(fb_fem_assemble(m, p, mass, &K, &M, &err), &err);
  if (keep && K && M) {
    shell_reduce(K, M, fixed, nfixed, keep, &Kf, &Mf);
    if (Kf && Mf)
      MUST(fb_fem_modes(Kf, Mf, nmodes, &eig, freq, NULL, &err), &err);
  }
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mat_free(&Kf);
  fb_mat_free(&Mf);
  free(keep);
}

#endif
