/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of the flat shell elements, assembly, mass properties, constraints
 * and modal analysis of flexbond/fem.h (the NAFEMS plate benchmarks are in
 * test_nafems.c). Expected values are closed forms, hand calculations or a
 * second method, as the comments next to them say. */
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"

#include "check.h"
#include "test_shell_util.h"

static const double PI = 3.14159265358979323846;

/* ---- Small linear-algebra helpers. */

static double max_abs(size_t n, const double *a)
{
  double m = 0.0;
  for (size_t i = 0; i < n; ++i)
    m = fmax(m, fabs(a[i]));
  return m;
}

/* Rotation matrix (row-major) with columns e1, e2, e3: a general
 * orientation (Euler angles 0.4, 0.7, -1.1 rad about z, x, z). */
static void general_rotation(double *r)
{
  const double a = 0.4, b = 0.7, c = -1.1;
  const double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cc = cos(c), sc = sin(c);
  const double rz1[9] = {ca, -sa, 0, sa, ca, 0, 0, 0, 1};
  const double rx[9] = {1, 0, 0, 0, cb, -sb, 0, sb, cb};
  const double rz2[9] = {cc, -sc, 0, sc, cc, 0, 0, 0, 1};
  double t[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      t[i * 3 + j] = 0.0;
      for (int k = 0; k < 3; ++k)
        t[i * 3 + j] += rz1[i * 3 + k] * rx[k * 3 + j];
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      r[i * 3 + j] = 0.0;
      for (int k = 0; k < 3; ++k)
        r[i * 3 + j] += t[i * 3 + k] * rz2[k * 3 + j];
    }
}

/* Column k of the row-major 3x3 r, scaled by s. */
static void column(const double *r, int k, double s, double *v)
{
  for (int i = 0; i < 3; ++i)
    v[i] = s * r[i * 3 + k];
}

/* Eigenvalues (ascending) of the symmetric n x n column-major a. */
static void sym_eigenvalues(size_t n, const double *a, double *w)
{
  double *copy = malloc(n * n * sizeof *copy);
  CHECK(copy != NULL);
  if (!copy)
    return;
  memcpy(copy, a, n * n * sizeof *copy);
  CHECK(LAPACKE_dsyev(LAPACK_COL_MAJOR, 'N', 'U', (lapack_int)n, copy, (lapack_int)n, w) == 0);
  free(copy);
}

/* ---- Meshes. */

/* The inside corner of a box: three flat faces (1.2 x 0.8, 0.8 x 0.6, 0.6 x
 * 1.2 m) meeting at a point, in a general orientation, each meshed 4 x 4
 * with irregular interior nodes. face_tri[f] selects triangles for face f. */
static fb_mesh *box_corner(const int *face_tri)
{
  fb_mesh *m = NULL;
  fb_err err;
  MUST(fb_mesh_new(&m, &err), &err);
  if (!m)
    return NULL;
  double r[9], e[3][3];
  general_rotation(r);
  const double len[3] = {1.2, 0.8, 0.6}, origin[3] = {0.3, -0.2, 0.5};
  for (int k = 0; k < 3; ++k)
    column(r, k, len[k], e[k]);
  for (int f = 0; f < 3; ++f)
    shell_face(m, origin, e[f], e[(f + 1) % 3], 4, 4, face_tri[f], 0.25);
  return m;
}

static const fb_shell_props STEEL_8MM = {210e9, 0.3, 7850.0, 0.0085, 0.0, 0.0};

/* ---- Element-level tests. */

static void check_element_spectrum(fb_elem_type type, const double *xyz)
{
  const size_t n = 6 * (size_t)type;
  double k[576], mc[576], ml[576], w[24];
  fb_err err;
  MUST(fb_shell_element(type, xyz, &STEEL_8MM, FB_MASS_CONSISTENT, k, mc, &err), &err);
  MUST(fb_shell_element(type, xyz, &STEEL_8MM, FB_MASS_LUMPED, NULL, ml, &err), &err);
  /* Symmetric to round-off of a T^T K T product (relative 1e-13). */
  double asym = 0.0;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j)
      asym = fmax(asym, fabs(k[j * n + i] - k[i * n + j]));
  CHECK(asym <= 1e-13 * max_abs(n * n, k));
  /* Exactly six zero eigenvalues (the rigid-body modes; round-off 1e-16
   * relative) and no spurious mechanism: the smallest elastic eigenvalue of
   * these elements is about 4e-5 of the largest, so 1e-12 and 1e-7 leave
   * four orders of margin on either side. */
  sym_eigenvalues(n, k, w);
  for (size_t i = 0; i < 6; ++i)
    CHECK(fabs(w[i]) < 1e-12 * w[n - 1]);
  CHECK(w[6] > 1e-7 * w[n - 1]);
  /* Both mass matrices are positive definite. */
  sym_eigenvalues(n, mc, w);
  CHECK(w[0] > 0.0);
  sym_eigenvalues(n, ml, w);
  CHECK(w[0] > 0.0);
}

/* K r = 0 for the six rigid-body motions r of the element's own nodes
 * (three translations, three rotations about the origin): relative to
 * max |K| max |r| a round-off 1e-16 with the rigid links, 5e-4 without
 * them for the warped quadrilateral below, so 1e-12 is far from both. A
 * zero-eigenvalue count cannot tell: a warped flat element without links
 * still has six, the rigid motions of its projected nodes. */
static void check_element_rigid(fb_elem_type type, const double *xyz)
{
  const size_t nn = (size_t)type, n = 6 * nn;
  double k[576];
  fb_err err;
  MUST(fb_shell_element(type, xyz, &STEEL_8MM, FB_MASS_CONSISTENT, k, NULL, &err), &err);
  const double kmax = max_abs(n * n, k);
  for (int mode = 0; mode < 6; ++mode) {
    double r[24] = {0}, om[3] = {0, 0, 0};
    if (mode >= 3)
      om[mode - 3] = 1.0;
    double rmax = 0.0;
    for (size_t a = 0; a < nn; ++a) {
      const double *x = xyz + 3 * a;
      double *d = r + 6 * a;
      d[0] = (mode == 0) + om[1] * x[2] - om[2] * x[1];
      d[1] = (mode == 1) + om[2] * x[0] - om[0] * x[2];
      d[2] = (mode == 2) + om[0] * x[1] - om[1] * x[0];
      d[3] = om[0];
      d[4] = om[1];
      d[5] = om[2];
    }
    for (size_t i = 0; i < n; ++i)
      rmax = fmax(rmax, fabs(r[i]));
    double kr = 0.0;
    for (size_t i = 0; i < n; ++i) {
      double sum = 0.0;
      for (size_t j = 0; j < n; ++j)
        sum += k[j * n + i] * r[j];
      kr = fmax(kr, fabs(sum));
    }
    CHECK(kr <= 1e-12 * kmax * rmax);
    if (!(kr <= 1e-12 * kmax * rmax))
      fprintf(stderr, "  rigid motion %d: |K r| = %.3e of max|K| max|r|\n", mode,
              kr / (kmax * rmax));
  }
}

/* An irregular triangle and quadrilateral in a general orientation. */
static void test_element_spectrum(void)
{
  double r[9];
  general_rotation(r);
  const double tri_local[9] = {0.0, 0.0, 0.0, 0.9, 0.1, 0.0, 0.3, 0.7, 0.0};
  const double quad_local[12] = {0.0, 0.0, 0.0, 1.1, 0.1, 0.0, 1.3, 0.8, 0.0, -0.2, 0.6, 0.0};
  double tri[9], quad[12];
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) {
      double s = 0.0, q = 0.0;
      for (int k = 0; k < 3; ++k) {
        s += a < 3 ? r[i * 3 + k] * tri_local[3 * a + k] : 0.0;
        q += r[i * 3 + k] * quad_local[3 * a + k];
      }
      if (a < 3)
        tri[3 * a + i] = s + 1.0;
      quad[3 * a + i] = q - 2.0;
    }
  check_element_spectrum(FB_ELEM_TRI3, tri);
  check_element_spectrum(FB_ELEM_QUAD4, quad);
  check_element_rigid(FB_ELEM_TRI3, tri);
  check_element_rigid(FB_ELEM_QUAD4, quad);
  /* Warped: the nodes alternately 0.5 mm above and below the mean plane
   * (3.3e-4 of the longer diagonal, inside fb_mesh_check's 1e-3). */
  static const double lift[4] = {5e-4, -5e-4, 5e-4, -5e-4};
  double warped[12];
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) {
      double q = 0.0;
      for (int k = 0; k < 3; ++k)
        q += r[i * 3 + k] * (k == 2 ? lift[a] : quad_local[3 * a + k]);
      warped[3 * a + i] = q - 2.0;
    }
  check_element_spectrum(FB_ELEM_QUAD4, warped);
  check_element_rigid(FB_ELEM_QUAD4, warped);
}

/* fb_shell_element's error for these arguments must be FB_EINVAL with a
 * message containing what. */
static void expect_element_error(fb_elem_type type, const double *xyz, const fb_shell_props *p,
                                 fb_mass_kind mass, const char *what)
{
  fb_err err;
  double k[576];
  CHECK(fb_shell_element(type, xyz, p, mass, k, NULL, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, what) != NULL);
  if (!strstr(err.msg, what))
    fprintf(stderr, "  message was: %s\n", err.msg);
}

static void test_element_errors(void)
{
  const double collinear[9] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
  const double tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const double square[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const double reentrant[12] = {0, 0, 0, 1, 0, 0, 0.2, 0.2, 0, 0, 1, 0};
  const double bowtie[12] = {0, 0, 0, 1, 0, 0, 0.2, 1, 0, 0.9, 1.1, 0};
  const double warped[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0.1, 0, 1, 0};
  const double repeated[12] = {0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0};
  fb_shell_props p = STEEL_8MM;
  expect_element_error(FB_ELEM_TRI3, collinear, &p, FB_MASS_CONSISTENT, "degenerate triangle");
  expect_element_error(FB_ELEM_QUAD4, reentrant, &p, FB_MASS_CONSISTENT, "not strictly convex");
  expect_element_error(FB_ELEM_QUAD4, bowtie, &p, FB_MASS_CONSISTENT, "not strictly convex");
  expect_element_error(FB_ELEM_QUAD4, warped, &p, FB_MASS_CONSISTENT, "warped");
  expect_element_error(FB_ELEM_QUAD4, repeated, &p, FB_MASS_CONSISTENT,
                       "degenerate quadrilateral");
  expect_element_error((fb_elem_type)5, square, &p, FB_MASS_CONSISTENT,
                       "unknown shell element");
  expect_element_error(FB_ELEM_TRI3, tri, &p, (fb_mass_kind)7, "unknown mass kind");
  expect_element_error(FB_ELEM_TRI3, NULL, &p, FB_MASS_CONSISTENT, "NULL coordinates");
  expect_element_error(FB_ELEM_TRI3, tri, NULL, FB_MASS_CONSISTENT, "NULL");
  p.thickness = 0.0;
  expect_element_error(FB_ELEM_TRI3, tri, &p, FB_MASS_CONSISTENT, "thickness");
  p = STEEL_8MM;
  p.poisson = 0.5;
  expect_element_error(FB_ELEM_TRI3, tri, &p, FB_MASS_CONSISTENT, "Poisson");
  p = STEEL_8MM;
  p.young = NAN;
  expect_element_error(FB_ELEM_QUAD4, square, &p, FB_MASS_CONSISTENT, "Young");
  p = STEEL_8MM;
  p.density = -1.0;
  expect_element_error(FB_ELEM_QUAD4, square, &p, FB_MASS_CONSISTENT, "density");
  p = STEEL_8MM;
  p.drill_factor = -1e-3;
  expect_element_error(FB_ELEM_QUAD4, square, &p, FB_MASS_CONSISTENT, "drilling");

  /* Assembly names the element by its user id. */
  fb_mesh *m = NULL;
  fb_err err;
  MUST(fb_mesh_new(&m, &err), &err);
  size_t idx[3];
  for (int a = 0; a < 3; ++a)
    MUST(fb_mesh_add_node(m, 10 + a, collinear[3 * a], collinear[3 * a + 1],
                          collinear[3 * a + 2], &idx[a], &err),
         &err);
  fb_mat *K = NULL, *M = NULL;
  CHECK(fb_fem_assemble(m, &STEEL_8MM, FB_MASS_CONSISTENT, &K, &M, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "no elements") != NULL);
  MUST(fb_mesh_add_element(m, 7, FB_ELEM_TRI3, idx, &err), &err);
  CHECK(fb_fem_assemble(m, &STEEL_8MM, FB_MASS_CONSISTENT, &K, &M, &err) == FB_EINVAL);
  CHECK(strncmp(err.msg, "element 7: degenerate triangle", 30) == 0);
  CHECK(K == NULL && M == NULL);
  CHECK(fb_fem_assemble(m, &STEEL_8MM, FB_MASS_CONSISTENT, NULL, NULL, &err) == FB_EINVAL);
  fb_mesh_free(&m);
}

/* Pure in-plane bending energy of a rectangular mesh unit (a x b, centred
 * at the origin in the plane z = 0): one QM6 quadrilateral or two OPT
 * triangles. The exact plane-stress field of pure bending (curvature 1):
 * u = x y, v = -(x^2 + nu y^2) / 2, rotation (v,x - u,y) / 2 = -x; its
 * strains ex = y, ey = -nu y, gxy = 0 give sx = E y, sy = 0 and the
 * energy E t a b^3 / 24. OPT is built to be exact for it at any
 * aspect ratio and Poisson's ratio (Felippa 2003), QM6 is
 * exact for it on rectangles (Taylor et al. 1976) and its drilling penalty
 * must add nothing; both to round-off (1e-12 relative). Bending the other
 * way (x <-> y) too. */
static double bending_energy(int quad, double a, double b, double nu, int swap)
{
  fb_shell_props p = {1.0, nu, 1.0, 1.0, 0.0, 0.0};
  const double xy[4][2] = {{-a / 2, -b / 2}, {a / 2, -b / 2}, {a / 2, b / 2}, {-a / 2, b / 2}};
  const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}}, quads[1][4] = {{0, 1, 2, 3}};
  double energy = 0.0;
  for (int e = 0; e < (quad ? 1 : 2); ++e) {
    const int nn = quad ? 4 : 3;
    double xyz[12] = {0.0}, k[576], d[24] = {0.0};
    for (int i = 0; i < nn; ++i) {
      const int node = quad ? quads[e][i] : tris[e][i];
      const double x = xy[node][0], y = xy[node][1];
      xyz[3 * i] = x;
      xyz[3 * i + 1] = y;
      /* Field for bending about z with fibres along x; swapped: along y. */
      const double s = swap ? y : x, t = swap ? x : y;
      const double along = s * t, across = -(s * s + nu * t * t) / 2, rot = swap ? y : -x;
      d[6 * i + (swap ? 1 : 0)] = along;
      d[6 * i + (swap ? 0 : 1)] = across;
      d[6 * i + 5] = rot;
    }
    fb_err err;
    const size_t n = 6 * (size_t)nn;
    MUST(fb_shell_element(quad ? FB_ELEM_QUAD4 : FB_ELEM_TRI3, xyz, &p, FB_MASS_CONSISTENT, k,
                          NULL, &err),
         &err);
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j)
        energy += 0.5 * d[i] * k[j * n + i] * d[j];
  }
  const double exact = swap ? b * a * a * a / 24.0 : a * b * b * b / 24.0;
  return energy / exact;
}

static void test_inplane_bending_unit(void)
{
  const double aspects[3] = {0.25, 1.0, 4.0}, nus[2] = {0.0, 0.3};
  for (int quad = 0; quad < 2; ++quad)
    for (int ia = 0; ia < 3; ++ia)
      for (int in = 0; in < 2; ++in)
        for (int swap = 0; swap < 2; ++swap)
          CHECK_NEAR(bending_energy(quad, 1.0, aspects[ia], nus[in], swap), 1.0, 1e-12);
}

/* The triangle's drilling freedom is real (OPT): drill_factor does not
 * change it. The quadrilateral's penalty does depend on it, and 0 selects
 * the default 1e-4. Checked entry by entry (exact equality where the same
 * arithmetic runs). */
static void test_drill_factor_element(void)
{
  const double tri[9] = {0, 0, 0, 1, 0.2, 0, 0.3, 0.9, 0};
  const double quad[12] = {0, 0, 0, 1, 0.1, 0, 1.2, 0.9, 0, 0.1, 0.8, 0};
  fb_shell_props p0 = STEEL_8MM, p1 = STEEL_8MM, p2 = STEEL_8MM;
  p1.drill_factor = 1e-4;
  p2.drill_factor = 1e-3;
  double k0[576], k1[576], k2[576];
  fb_err err;
  MUST(fb_shell_element(FB_ELEM_TRI3, tri, &p1, FB_MASS_CONSISTENT, k1, NULL, &err), &err);
  MUST(fb_shell_element(FB_ELEM_TRI3, tri, &p2, FB_MASS_CONSISTENT, k2, NULL, &err), &err);
  CHECK(memcmp(k1, k2, 324 * sizeof *k1) == 0);
  MUST(fb_shell_element(FB_ELEM_QUAD4, quad, &p0, FB_MASS_CONSISTENT, k0, NULL, &err), &err);
  MUST(fb_shell_element(FB_ELEM_QUAD4, quad, &p1, FB_MASS_CONSISTENT, k1, NULL, &err), &err);
  MUST(fb_shell_element(FB_ELEM_QUAD4, quad, &p2, FB_MASS_CONSISTENT, k2, NULL, &err), &err);
  CHECK(memcmp(k0, k1, 576 * sizeof *k0) == 0);
  CHECK(memcmp(k1, k2, 576 * sizeof *k1) != 0);
}

/* ---- Rigid-body modes of a folded mesh. */

/* Rigid motion of every node: translation tr plus rotation om about c, with
 * the rotational DOFs equal to om. */
static void rigid_field(const fb_mesh *m, const double *tr, const double *om, const double *c,
                        double *d)
{
  for (size_t a = 0; a < fb_mesh_nnodes(m); ++a) {
    const double *x = fb_mesh_node_xyz(m, a);
    const double r[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
    d[6 * a] = tr[0] + om[1] * r[2] - om[2] * r[1];
    d[6 * a + 1] = tr[1] + om[2] * r[0] - om[0] * r[2];
    d[6 * a + 2] = tr[2] + om[0] * r[1] - om[1] * r[0];
    for (int k = 0; k < 3; ++k)
      d[6 * a + 3 + (size_t)k] = om[k];
  }
}

static double matrix_max(const fb_mat *a)
{
  double m = 0.0;
  for (size_t j = 0; j < fb_mat_ncols(a); ++j)
    for (size_t i = 0; i < fb_mat_nrows(a); ++i)
      m = fmax(m, fabs(fb_mat_get(a, i, j)));
  return m;
}

/* K r = 0 for the six rigid-body fields (translations, rotations about an
 * arbitrary point) on the non-coplanar box corner: every entry of K r is a
 * sum of about 100 terms of size up to |K|max |r|max that cancel exactly,
 * so round-off leaves about 1e-14 of that; 1e-12 is the bound. Then the
 * free-free spectrum: exactly six modes at round-off level (below 1e-3
 * of the first elastic one) and a seventh well above. */
static void check_rigid_body(const int *face_tri, const char *name)
{
  fb_mesh *m = box_corner(face_tri);
  fb_mat *K = NULL, *M = NULL;
  fb_err err;
  MUST(fb_fem_assemble(m, &STEEL_8MM, FB_MASS_CONSISTENT, &K, &M, &err), &err);
  const size_t n = 6 * fb_mesh_nnodes(m);
  double *d = malloc(n * sizeof *d), *kd = malloc(n * sizeof *kd);
  CHECK(d && kd && K && M);
  if (d && kd && K && M) {
    const double kmax = matrix_max(K), c[3] = {2.0, -1.0, 0.5};
    for (int mode = 0; mode < 6; ++mode) {
      double tr[3] = {0.0, 0.0, 0.0}, om[3] = {0.0, 0.0, 0.0};
      if (mode < 3)
        tr[mode] = 1.0;
      else
        om[mode - 3] = 1.0;
      rigid_field(m, tr, om, c, d);
      fb_mat_gemv(K, 1.0, d, 0.0, kd);
      CHECK(max_abs(n, kd) <= 1e-12 * kmax * max_abs(n, d));
    }
    double f[7];
    const fb_eig_opts dense = eig_with(FB_EIG_DENSE);
    MUST(fb_fem_modes(K, M, 7, &dense, f, NULL, &err), &err);
    fprintf(stderr, "box corner (%s): rigid-body modes up to %.2e Hz, first elastic %.2f Hz\n",
            name, f[5], f[6]);
    CHECK(f[5] < 1e-3 * f[6]);
    CHECK(f[6] > 1.0);
  }
  free(d);
  free(kd);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mesh_free(&m);
}

static void test_rigid_body(void)
{
  const int quads[3] = {0, 0, 0}, tris[3] = {1, 1, 1}, mixed[3] = {1, 0, 0};
  check_rigid_body(quads, "quadrilaterals");
  check_rigid_body(tris, "triangles");
  check_rigid_body(mixed, "mixed");
}

/* ---- Mass properties. */

/* Total mass of the box corner: rho t times its area (1.2 * 0.8 + 0.8 *
 * 0.6 + 0.6 * 1.2 m^2; the distortion keeps every node in its face), for
 * both mass kinds and element types, to round-off (1e-12 relative). */
static void test_total_mass(void)
{
  const int kinds[2][3] = {{0, 0, 0}, {1, 1, 1}};
  const double area = 1.2 * 0.8 + 0.8 * 0.6 + 0.6 * 1.2;
  const double exact = STEEL_8MM.density * STEEL_8MM.thickness * area;
  for (int t = 0; t < 2; ++t)
    for (int lumped = 0; lumped < 2; ++lumped) {
      fb_mesh *m = box_corner(kinds[t]);
      fb_mat *M = NULL;
      fb_err err;
      double mass = 0.0, cg[3], inertia[9];
      MUST(fb_fem_assemble(m, &STEEL_8MM, lumped ? FB_MASS_LUMPED : FB_MASS_CONSISTENT, NULL,
                           &M, &err),
           &err);
      if (M)
        MUST(fb_fem_mass_properties(m, M, &mass, cg, inertia, &err), &err);
      CHECK_NEAR(mass, exact, 1e-12 * exact);
      fb_mat_free(&M);
      fb_mesh_free(&m);
    }
}

/* Consistent mass of a rectangular plate a x b x t (irregular mesh) with
 * its centre at c, turned by the rotation r. Linear and bilinear shape
 * functions interpolate a rigid rotation exactly, so the inertia about the
 * centre is the closed form of the thin plate (m b^2 / 12, m a^2 / 12,
 * m (a^2 + b^2) / 12 about the plate's axes: y^2, x^2, x^2 + y^2
 * integrated over the rectangle) plus the rotary term m t^2 / 12 that the mass matrix
 * gives every axis (see shell.c; for the in-plane axes that is exactly the
 * solid block's thickness term), turned by r: I = r diag r^T. 1e-10 of the
 * largest moment covers round-off of the sums. */
static void check_plate_consistent(int tri)
{
  const double a = 4.0, b = 2.0, t = 0.05, rho = 7800.0, c[3] = {1.0, 2.0, 3.0};
  const fb_shell_props p = {200e9, 0.3, rho, t, 0.0, 0.0};
  double r[9], du[3], dv[3], origin[3];
  general_rotation(r);
  column(r, 0, a, du);
  column(r, 1, b, dv);
  for (int k = 0; k < 3; ++k)
    origin[k] = c[k] - du[k] / 2 - dv[k] / 2;
  fb_mesh *m = NULL;
  fb_err err;
  MUST(fb_mesh_new(&m, &err), &err);
  shell_face(m, origin, du, dv, 8, 4, tri, 0.3);
  fb_mat *M = NULL;
  MUST(fb_fem_assemble(m, &p, FB_MASS_CONSISTENT, NULL, &M, &err), &err);
  double mass = 0.0, cg[3] = {0.0}, inertia[9] = {0.0};
  if (M)
    MUST(fb_fem_mass_properties(m, M, &mass, cg, inertia, &err), &err);
  const double mt = rho * a * b * t;
  const double diag[3] = {mt * (b * b + t * t) / 12, mt * (a * a + t * t) / 12,
                          mt * (a * a + b * b + t * t) / 12};
  CHECK_NEAR(mass, mt, 1e-12 * mt);
  for (int k = 0; k < 3; ++k)
    CHECK_NEAR(cg[k], c[k], 1e-12 * 4.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double expect = 0.0;
      for (int k = 0; k < 3; ++k)
        expect += r[i * 3 + k] * diag[k] * r[j * 3 + k];
      CHECK_NEAR(inertia[i * 3 + j], expect, 1e-10 * diag[2]);
    }
  fb_mat_free(&M);
  fb_mesh_free(&m);
}

/* Lumped mass of the same kind of plate against a second method: the
 * nodal masses rho t A_e / nn summed element by element from the elements'
 * areas (computed here from cross products), then m_a (|d|^2 I - d d^T)
 * about their centre of mass, plus the rotary m t^2 / 12 on each axis. */
static void check_plate_lumped(int tri)
{
  const double t = 0.05, rho = 7800.0;
  const fb_shell_props p = {200e9, 0.3, rho, t, 0.0, 0.0};
  const double origin[3] = {-1.0, 0.5, 2.0}, du[3] = {3.0, 1.0, 0.5}, dv[3] = {-0.4, 1.0, 0.8};
  fb_mesh *m = NULL;
  fb_err err;
  MUST(fb_mesh_new(&m, &err), &err);
  shell_face(m, origin, du, dv, 6, 4, tri, 0.3);
  const size_t nn = fb_mesh_nnodes(m);
  double *node_mass = calloc(nn, sizeof *node_mass), total = 0.0, first[3] = {0.0};
  CHECK(node_mass != NULL);
  for (size_t e = 0; node_mass && e < fb_mesh_nelements(m); ++e) {
    const size_t *v = fb_mesh_element_nodes(m, e), nv = (size_t)fb_mesh_element_type(m, e);
    const double *p0 = fb_mesh_node_xyz(m, v[0]), *p1 = fb_mesh_node_xyz(m, v[1]);
    const double *p2 = fb_mesh_node_xyz(m, v[2]), *p3 = fb_mesh_node_xyz(m, v[nv - 1]);
    /* Area: half the cross product of the diagonals (quadrilateral) or of
     * two sides (triangle, where p3 = p2). */
    const double d1[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    const double d2[3] = {nv == 4 ? p3[0] - p1[0] : p1[0] - p0[0],
                          nv == 4 ? p3[1] - p1[1] : p1[1] - p0[1],
                          nv == 4 ? p3[2] - p1[2] : p1[2] - p0[2]};
    const double cr[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                          d1[0] * d2[1] - d1[1] * d2[0]};
    const double area = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]) / 2;
    for (size_t i = 0; i < nv; ++i)
      node_mass[v[i]] += rho * t * area / (double)nv;
  }
  for (size_t a = 0; node_mass && a < nn; ++a) {
    total += node_mass[a];
    for (int k = 0; k < 3; ++k)
      first[k] += node_mass[a] * fb_mesh_node_xyz(m, a)[k];
  }
  double expect[9] = {0.0}, cgx[3];
  for (int k = 0; k < 3; ++k)
    cgx[k] = first[k] / total;
  for (size_t a = 0; node_mass && a < nn; ++a) {
    const double *x = fb_mesh_node_xyz(m, a);
    const double d[3] = {x[0] - cgx[0], x[1] - cgx[1], x[2] - cgx[2]};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        expect[i * 3 + j] +=
            node_mass[a] *
            ((i == j ? d[0] * d[0] + d[1] * d[1] + d[2] * d[2] : 0.0) - d[i] * d[j]);
  }
  for (int i = 0; i < 3; ++i)
    expect[i * 3 + i] += total * t * t / 12.0;
  fb_mat *M = NULL;
  MUST(fb_fem_assemble(m, &p, FB_MASS_LUMPED, NULL, &M, &err), &err);
  double mass = 0.0, cg[3] = {0.0}, inertia[9] = {0.0};
  if (M)
    MUST(fb_fem_mass_properties(m, M, &mass, cg, inertia, &err), &err);
  CHECK_NEAR(mass, total, 1e-12 * total);
  for (int k = 0; k < 3; ++k)
    CHECK_NEAR(cg[k], cgx[k], 1e-12 * 4.0);
  for (int i = 0; i < 9; ++i)
    CHECK_NEAR(inertia[i], expect[i], 1e-10 * max_abs(9, expect));
  /* A mass matrix of the wrong size is refused. */
  fb_mat *small = NULL;
  MUST(fb_mat_new_scaled_identity(6, 1.0, &small, &err), &err);
  CHECK(fb_fem_mass_properties(m, small, &mass, cg, inertia, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "6 x 6") != NULL);
  fb_mat_free(&small);
  fb_mat_free(&M);
  fb_mesh_free(&m);
  free(node_mass);
}

static void test_plate_mass_properties(void)
{
  for (int tri = 0; tri < 2; ++tri) {
    check_plate_consistent(tri);
    check_plate_lumped(tri);
  }
}

/* ---- Patch tests. */

/* Displacements (6 per node, global axes) of a linear membrane field or a
 * constant-curvature plate field over a plate whose local axes are the
 * columns e1, e2, e3 of r and origin o; (X, Y) are the in-plane
 * coordinates. Membrane: u = 1e-3 (1 + 2 X - 3 Y), v = 1e-3 (-2 + X + 4 Y),
 * rz = (v,X - u,Y) / 2. Plate: w = 1e-3 (1 + X - 2 Y + (3 X^2 - 2 Y^2 +
 * 2 * 1.5 X Y) / 2), rx = w,Y, ry = -w,X. */
static void patch_field(int bending, const double *r, const double *o, const double *x,
                        double *d)
{
  double e[3][3], rel[3], X = 0.0, Y = 0.0;
  for (int k = 0; k < 3; ++k)
    column(r, k, 1.0, e[k]);
  for (int k = 0; k < 3; ++k)
    rel[k] = x[k] - o[k];
  for (int k = 0; k < 3; ++k) {
    X += rel[k] * e[0][k];
    Y += rel[k] * e[1][k];
  }
  double local[6] = {0.0};
  if (!bending) {
    local[0] = 1e-3 * (1 + 2 * X - 3 * Y);
    local[1] = 1e-3 * (-2 + X + 4 * Y);
    local[5] = 1e-3 * (1.0 - (-3.0)) / 2.0;
  } else {
    local[2] = 1e-3 * (1 + X - 2 * Y + (3 * X * X - 2 * Y * Y + 3 * X * Y) / 2);
    local[3] = 1e-3 * (-2 - 2 * Y + 1.5 * X);
    local[4] = -1e-3 * (1 + 3 * X + 1.5 * Y);
  }
  for (int k = 0; k < 3; ++k) {
    d[k] = local[0] * e[0][k] + local[1] * e[1][k] + local[2] * e[2][k];
    d[3 + k] = local[3] * e[0][k] + local[4] * e[1][k] + local[5] * e[2][k];
  }
}

/* Patch test (B. M. Irons & A. Razzaque, "Experience with the patch test
 * for convergence of finite elements", 1972): a 2 x 1 m plate in a general
 * orientation, 4 x 3 irregular elements; all six DOFs of the boundary nodes
 * take the exact field, the interior nodes are solved for and must
 * reproduce it. Tolerance 1e-9 of the field's size: the solve's round-off
 * (condition number of the interior stiffness about 1e6 here) times eps. */
static void check_patch(int tri, int bending)
{
  double r[9], du[3], dv[3];
  const double o[3] = {0.5, -1.0, 0.25};
  general_rotation(r);
  column(r, 0, 2.0, du);
  column(r, 1, 1.0, dv);
  fb_mesh *m = NULL;
  fb_err err;
  MUST(fb_mesh_new(&m, &err), &err);
  shell_face(m, o, du, dv, 4, 3, tri, 0.35);
  const size_t nn = fb_mesh_nnodes(m), n = 6 * nn;
  double *exact = malloc(n * sizeof *exact), *d = calloc(n, sizeof *d);
  double *rhs = malloc(n * sizeof *rhs);
  size_t *fixed = malloc(n * sizeof *fixed), *keep = malloc(n * sizeof *keep), nfixed = 0;
  fb_mat *K = NULL, *Kf = NULL;
  fb_lu *lu = NULL;
  MUST(fb_fem_assemble(m, &STEEL_8MM, FB_MASS_CONSISTENT, &K, NULL, &err), &err);
  CHECK(exact && d && rhs && fixed && keep && K);
  if (exact && d && rhs && fixed && keep && K) {
    for (size_t a = 0; a < nn; ++a) {
      const double *x = fb_mesh_node_xyz(m, a);
      patch_field(bending, r, o, x, exact + 6 * a);
      double X = 0.0, Y = 0.0;
      for (int k = 0; k < 3; ++k) {
        X += (x[k] - o[k]) * r[k * 3];
        Y += (x[k] - o[k]) * r[k * 3 + 1];
      }
      const int boundary =
          fabs(X) < 1e-9 || fabs(X - 2.0) < 1e-9 || fabs(Y) < 1e-9 || fabs(Y - 1.0) < 1e-9;
      for (size_t k = 0; boundary && k < 6; ++k) {
        shell_fix(fixed, &nfixed, a, k);
        d[6 * a + k] = exact[6 * a + k];
      }
    }
    CHECK(nfixed < n);
    shell_reduce(K, NULL, fixed, nfixed, keep, &Kf, NULL);
    /* Interior equations: K_ff x = -K_fp d_p. */
    fb_mat_gemv(K, -1.0, d, 0.0, rhs);
    for (size_t i = 0; i < n - nfixed; ++i)
      rhs[i] = rhs[keep[i]];
    if (Kf)
      MUST(fb_lu_new(Kf, &lu, &err), &err);
    if (lu)
      MUST(fb_lu_solve(lu, rhs, 1, &err), &err);
    double worst = 0.0;
    for (size_t i = 0; i < n - nfixed; ++i)
      worst = fmax(worst, fabs(rhs[i] - exact[keep[i]]));
    fprintf(stderr, "patch test %s %s: largest interior error %.2e\n",
            tri ? "triangles" : "quadrilaterals", bending ? "bending" : "membrane", worst);
    CHECK(worst <= 1e-9 * max_abs(n, exact));
  }
  fb_lu_free(&lu);
  fb_mat_free(&K);
  fb_mat_free(&Kf);
  fb_mesh_free(&m);
  free(exact);
  free(d);
  free(rhs);
  free(fixed);
  free(keep);
}

static void test_patch(void)
{
  for (int tri = 0; tri < 2; ++tri)
    for (int bending = 0; bending < 2; ++bending)
      check_patch(tri, bending);
}

/* ---- In-plane bending of a slender cantilever (membrane locking). */

/* Tip deflection of a cantilever 10 x 1 m (t 0.1 m, E 1 GPa, nu 0) in the
 * plane z = 0 under an end moment M0 = 1 kN m, as the linear axial
 * traction M0 y / I with consistent nodal forces, divided by the beam
 * value M0 L^2 / (2 E I) (exact here: the pure-bending field above). Root: ux = 0 on x = 0, uy
 * = 0 at its middle node; the out-of-plane DOFs are fixed everywhere. ny must be even. */
static double cantilever_ratio(int nx, int ny, int tri, double drill_factor)
{
  const double len = 10.0, h = 1.0, t = 0.1, young = 1e9, moment = 1e3;
  const double second_moment = t * h * h * h / 12.0;
  const fb_shell_props p = {young, 0.0, 1.0, t, drill_factor, 0.0};
  const double o[3] = {0.0, -h / 2, 0.0}, du[3] = {len, 0.0, 0.0}, dv[3] = {0.0, h, 0.0};
  fb_mesh *m = NULL;
  fb_err err;
  MUST(fb_mesh_new(&m, &err), &err);
  shell_face(m, o, du, dv, nx, ny, tri, 0.0);
  const size_t nn = fb_mesh_nnodes(m), n = 6 * nn;
  double *f = calloc(n, sizeof *f), ratio = NAN;
  size_t *fixed = malloc(n * sizeof *fixed), *keep = malloc(n * sizeof *keep), nfixed = 0;
  fb_mat *K = NULL, *Kf = NULL;
  fb_lu *lu = NULL;
  MUST(fb_fem_assemble(m, &p, FB_MASS_CONSISTENT, &K, NULL, &err), &err);
  const long tip = fb_mesh_find_node_at(m, len, 0.0, 0.0, 1e-9);
  CHECK(f && fixed && keep && K && tip >= 0);
  if (f && fixed && keep && K && tip >= 0) {
    for (size_t a = 0; a < nn; ++a) {
      const double *x = fb_mesh_node_xyz(m, a);
      for (size_t k = 2; k < 5; ++k)
        shell_fix(fixed, &nfixed, a, k);
      if (x[0] == 0.0)
        shell_fix(fixed, &nfixed, a, 0);
      if (x[0] == 0.0 && x[1] == 0.0)
        shell_fix(fixed, &nfixed, a, 1);
    }
    for (int j = 0; j < ny; ++j) {
      const double y0 = -h / 2 + h * j / ny, y1 = -h / 2 + h * (j + 1) / ny;
      const double q0 = -moment * y0 / second_moment * t, q1 = -moment * y1 / second_moment * t;
      const long a = fb_mesh_find_node_at(m, len, y0, 0.0, 1e-9);
      const long b = fb_mesh_find_node_at(m, len, y1, 0.0, 1e-9);
      f[6 * (size_t)a] += (y1 - y0) * (2 * q0 + q1) / 6;
      f[6 * (size_t)b] += (y1 - y0) * (q0 + 2 * q1) / 6;
    }
    shell_reduce(K, NULL, fixed, nfixed, keep, &Kf, NULL);
    for (size_t i = 0; i < n - nfixed; ++i)
      f[i] = f[keep[i]];
    if (Kf)
      MUST(fb_lu_new(Kf, &lu, &err), &err);
    if (lu)
      MUST(fb_lu_solve(lu, f, 1, &err), &err);
    for (size_t i = 0; i < n - nfixed; ++i)
      if (keep[i] == 6 * (size_t)tip + 1)
        ratio = f[i] / (moment * len * len / (2 * young * second_moment));
  }
  fb_lu_free(&lu);
  fb_mat_free(&K);
  fb_mat_free(&Kf);
  fb_mesh_free(&m);
  free(f);
  free(fixed);
  free(keep);
  return ratio;
}

/* Quadrilaterals (QM6) are exact in pure bending on coarse meshes (10 x 2
 * and 20 x 4; 1e-9: the solve's round-off), whatever the drilling factor:
 * no locking. Triangles (OPT) store the exact energy of the pure-bending
 * field (test_inplane_bending_unit), but that field is not quite their
 * equilibrium: it leaves small drilling moments at the nodes of the
 * traction-free long edges, so the solution deviates near them, by less
 * at each refinement (measured 5.5 %, 1.0 %, 0.27 %); required: the error
 * falls at each step and is below 0.5 % on 80 x 8. */
static void test_inplane_cantilever(void)
{
  CHECK_NEAR(cantilever_ratio(10, 2, 0, 0.0), 1.0, 1e-9);
  CHECK_NEAR(cantilever_ratio(10, 2, 0, 1e-2), 1.0, 1e-9);
  CHECK_NEAR(cantilever_ratio(20, 4, 0, 0.0), 1.0, 1e-9);
  double err_prev = INFINITY;
  fprintf(stderr, "in-plane cantilever, triangles: tip deflection / beam theory\n");
  for (int k = 1; k <= 4; k *= 2) {
    const double ratio = cantilever_ratio(20 * k, 2 * k, 1, 0.0);
    fprintf(stderr, "  %3dx%-2d %.5f\n", 20 * k, 2 * k, ratio);
    CHECK(fabs(ratio - 1.0) < err_prev);
    err_prev = fabs(ratio - 1.0);
  }
  CHECK(err_prev < 0.005);
}

/* ---- Modal analysis. */

/* Sparse tridiagonal n x n with diagonal dg and off-diagonal off; the
 * first and last diagonal entries are dg_end (a spring chain). */
static fb_mat *chain_matrix(size_t n, double dg, double dg_end, double off)
{
  fb_mat *a = NULL;
  fb_err err;
  size_t *rows = malloc(3 * n * sizeof *rows), *cols = malloc(3 * n * sizeof *cols), nnz = 0;
  double *vals = malloc(3 * n * sizeof *vals);
  CHECK(rows && cols && vals);
  for (size_t i = 0; rows && cols && vals && i < n; ++i) {
    rows[nnz] = cols[nnz] = i;
    vals[nnz++] = i == 0 || i == n - 1 ? dg_end : dg;
    if (i + 1 < n && off != 0.0) {
      rows[nnz] = i;
      cols[nnz] = i + 1;
      vals[nnz++] = off;
      rows[nnz] = i + 1;
      cols[nnz] = i;
      vals[nnz++] = off;
    }
  }
  if (rows && cols && vals)
    MUST(fb_mat_new_triplets(n, n, nnz, rows, cols, vals, &a, &err), &err);
  free(rows);
  free(cols);
  free(vals);
  return a;
}

/* Closed forms. Two masses m on springs k (wall-k-m-k-m): w^2 = (3 -+
 * sqrt 5) k / (2 m). Free-free chain of n unit masses joined by n - 1
 * springs k: w_j^2 = 4 k sin^2(j pi / (2 n)), j = 0 .. n-1 (K is k times
 * the path graph's Laplacian, whose eigenvectors are cos(j pi (i + 1/2) /
 * n), i = 0 .. n-1; j = 0 is the rigid-body mode). Both paths to 1e-9 relative (the chain's
 * condition number as a solved problem is about 1e5; dense and Lanczos
 * converge to near machine precision). The vectors are M-orthonormal. */
static void test_modes_closed_form(void)
{
  fb_err err;
  const double k = 1000.0, m = 2.0;
  const double kk[4] = {2 * k, -k, -k, k}, mm[4] = {m, 0, 0, m};
  fb_mat *K = NULL, *M = NULL;
  MUST(fb_mat_new_dense(2, 2, kk, &K, &err), &err);
  MUST(fb_mat_new_dense(2, 2, mm, &M, &err), &err);
  double f[2], v[4];
  const fb_eig_opts dense = eig_with(FB_EIG_DENSE), lanczos = eig_with(FB_EIG_LANCZOS);
  MUST(fb_fem_modes(K, M, 2, &dense, f, v, &err), &err);
  for (int i = 0; i < 2; ++i) {
    const double w2 = (3.0 + (i ? 1 : -1) * sqrt(5.0)) * k / (2.0 * m);
    CHECK_NEAR(f[i], sqrt(w2) / (2 * PI), 1e-12 * f[i]);
  }
  CHECK_NEAR(m * (v[0] * v[0] + v[1] * v[1]), 1.0, 1e-12);
  CHECK_NEAR(m * (v[0] * v[2] + v[1] * v[3]), 0.0, 1e-12);
  fb_mat_free(&K);
  fb_mat_free(&M);

  const size_t n = 400, nmodes = 8;
  K = chain_matrix(n, 2 * k, k, -k);
  M = chain_matrix(n, 1.0, 1.0, 0.0);
  double fd[8], fa[8];
  double *va = malloc(n * nmodes * sizeof *va), *mv = malloc(n * sizeof *mv);
  CHECK(va && mv);
  if (K && M && va && mv) {
    MUST(fb_fem_modes(K, M, nmodes, &dense, fd, NULL, &err), &err);
    MUST(fb_fem_modes(K, M, nmodes, &lanczos, fa, va, &err), &err);
    CHECK(fd[0] < 1e-6 && fa[0] < 1e-6);
    for (size_t j = 1; j < nmodes; ++j) {
      const double s = sin((double)j * PI / (2.0 * (double)n));
      const double exact = sqrt(4.0 * k * s * s) / (2 * PI);
      CHECK_NEAR(fd[j], exact, 1e-9 * exact);
      CHECK_NEAR(fa[j], exact, 1e-9 * exact);
    }
    for (size_t i = 0; i < nmodes; ++i) {
      fb_mat_gemv(M, 1.0, va + i * n, 0.0, mv);
      for (size_t j = 0; j < nmodes; ++j) {
        double dot = 0.0;
        for (size_t q = 0; q < n; ++q)
          dot += va[j * n + q] * mv[q];
        CHECK_NEAR(dot, i == j ? 1.0 : 0.0, 1e-10);
      }
    }
  }
  free(va);
  free(mv);
  fb_mat_free(&K);
  fb_mat_free(&M);
}

/* An open-top box 1.0 x 0.6 x 0.4 m of 8.5 mm steel, 0.1 m quadrilaterals
 * (tri = 0) or triangles, with irregular interior nodes. */
static fb_mesh *open_box(int tri)
{
  fb_mesh *m = NULL;
  fb_err err;
  MUST(fb_mesh_new(&m, &err), &err);
  if (!m)
    return NULL;
  const double lx = 1.0, ly = 0.6, lz = 0.4;
  const double o[3] = {0.0, 0.0, 0.0}, ox[3] = {lx, 0.0, 0.0}, oy[3] = {0.0, ly, 0.0};
  const double ex[3] = {lx, 0.0, 0.0}, ey[3] = {0.0, ly, 0.0}, ez[3] = {0.0, 0.0, lz};
  shell_face(m, o, ex, ey, 10, 6, tri, 0.2);  /* bottom */
  shell_face(m, o, ex, ez, 10, 4, tri, 0.2);  /* side y = 0 */
  shell_face(m, oy, ex, ez, 10, 4, tri, 0.2); /* side y = ly */
  shell_face(m, o, ey, ez, 6, 4, tri, 0.2);   /* end x = 0 */
  shell_face(m, ox, ey, ez, 6, 4, tri, 0.2);  /* end x = lx */
  return m;
}

/* The dense (LAPACK) and sparse (block Lanczos) paths on the same free-free box
 * (1230 DOFs): six rigid-body modes below 0.01 Hz in both (zero up to
 * round-off; the first elastic mode is 27 Hz), elastic frequencies equal
 * to 1e-9 relative (both converge to near machine precision), vectors
 * M-orthonormal to 1e-9 and the same up to sign for the simple elastic
 * modes (|v_d^T M v_a| = 1 to 1e-6: an eigenvector's round-off is about
 * eps over the relative gap to its neighbours, >= 1e-3 here). */
static void test_modes_paths(void)
{
  fb_mesh *m = open_box(0);
  fb_mat *K = NULL, *M = NULL;
  fb_err err;
  MUST(fb_fem_assemble(m, &STEEL_8MM, FB_MASS_CONSISTENT, &K, &M, &err), &err);
  const size_t n = 6 * fb_mesh_nnodes(m), nmodes = 16;
  double fd[16], fa[16];
  double *vd = malloc(n * nmodes * sizeof *vd), *va = malloc(n * nmodes * sizeof *va);
  double *mv = malloc(n * sizeof *mv);
  CHECK(vd && va && mv && K && M);
  if (vd && va && mv && K && M) {
    const fb_eig_opts dense = eig_with(FB_EIG_DENSE), lanczos = eig_with(FB_EIG_LANCZOS);
    MUST(fb_fem_modes(K, M, nmodes, &dense, fd, vd, &err), &err);
    MUST(fb_fem_modes(K, M, nmodes, &lanczos, fa, va, &err), &err);
    fprintf(stderr, "open box, %zu DOFs: dense / block Lanczos (Hz)\n", n);
    for (size_t i = 0; i < nmodes; ++i)
      fprintf(stderr, "  %2zu %12.6f %12.6f\n", i + 1, fd[i], fa[i]);
    for (size_t i = 0; i < 6; ++i)
      CHECK(fd[i] < 0.01 && fa[i] < 0.01);
    CHECK(fd[6] > 10.0);
    for (size_t i = 6; i < nmodes; ++i)
      CHECK_NEAR(fa[i], fd[i], 1e-9 * fd[i]);
    for (size_t i = 0; i < nmodes; ++i) {
      fb_mat_gemv(M, 1.0, va + i * n, 0.0, mv);
      double self = 0.0, cross = 0.0, dd = 0.0;
      for (size_t q = 0; q < n; ++q) {
        self += va[i * n + q] * mv[q];
        cross += vd[i * n + q] * mv[q];
      }
      fb_mat_gemv(M, 1.0, vd + i * n, 0.0, mv);
      for (size_t q = 0; q < n; ++q)
        dd += vd[i * n + q] * mv[q];
      CHECK_NEAR(self, 1.0, 1e-9);
      CHECK_NEAR(dd, 1.0, 1e-9);
      const int simple =
          i >= 6 && (i + 1 == nmodes || fd[i + 1] > 1.001 * fd[i]) && fd[i] > 1.001 * fd[i - 1];
      if (simple)
        CHECK_NEAR(fabs(cross), 1.0, 1e-6);
    }
  }
  free(vd);
  free(va);
  free(mv);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mesh_free(&m);
}

/* The fictitious drilling stiffness of the quadrilaterals must not move
 * the low frequencies: a factor of 10 from the default (1e-4 -> 1e-3)
 * changes the first ten elastic frequencies by less than 0.1 % (the
 * acceptance criterion; measured 5e-4), on the folded box, where a plate's
 * drilling rotation is its neighbour's bending rotation at the folds, and on
 * FV12's flat plate, where the membrane is uncoupled from the bending and
 * nothing may change beyond round-off. (1e-3 -> 1e-2 would move the box's
 * eighth elastic mode by 1.05e-3: the coupling at the folds grows with the
 * factor, hence the default 1e-4.) */
static void test_drill_factor_modes(void)
{
  fb_shell_props p1 = STEEL_8MM, p2 = STEEL_8MM;
  p1.drill_factor = 0.0;
  p2.drill_factor = 1e-3;
  fb_mesh *box = open_box(0);
  fb_mesh *plate = shell_plate(10.0, 10.0, 16, 16, 0, 0.0);
  double f1[16], f2[16], worst_box = 0.0, worst_plate = 0.0;
  shell_frequencies(box, &p1, FB_MASS_CONSISTENT, NULL, 0, 16, FB_EIG_AUTO, f1);
  shell_frequencies(box, &p2, FB_MASS_CONSISTENT, NULL, 0, 16, FB_EIG_AUTO, f2);
  for (size_t i = 6; i < 16; ++i)
    worst_box = fmax(worst_box, fabs(f2[i] / f1[i] - 1.0));
  CHECK(worst_box < 1e-3);
  p1 = NAFEMS_STEEL;
  p2 = NAFEMS_STEEL;
  p2.drill_factor = 1e-3;
  shell_frequencies(plate, &p1, FB_MASS_CONSISTENT, NULL, 0, 16, FB_EIG_AUTO, f1);
  shell_frequencies(plate, &p2, FB_MASS_CONSISTENT, NULL, 0, 16, FB_EIG_AUTO, f2);
  for (size_t i = 6; i < 16; ++i)
    worst_plate = fmax(worst_plate, fabs(f2[i] / f1[i] - 1.0));
  CHECK(worst_plate < 1e-10);
  fprintf(stderr,
          "drilling factor 1e-4 -> 1e-3: largest change of the first 10 elastic frequencies "
          "%.2e (open box), %.2e (FV12 plate)\n",
          worst_box, worst_plate);
  fb_mesh_free(&box);
  fb_mesh_free(&plate);
}

static void expect_modes_error(const fb_mat *K, const fb_mat *M, size_t nmodes,
                               fb_eig_method method, int code, const char *what)
{
  double f[8];
  fb_err err;
  const fb_eig_opts eig = eig_with(method);
  CHECK(fb_fem_modes(K, M, nmodes, &eig, f, NULL, &err) == code);
  CHECK(strstr(err.msg, what) != NULL);
  if (!strstr(err.msg, what))
    fprintf(stderr, "  message was: %s\n", err.msg);
}

/* Errors: an indefinite K (both paths), a mass matrix that is not positive
 * definite, mismatched sizes, no modes asked. */
static void test_modes_errors(void)
{
  fb_err err;
  fb_mat *K = NULL, *M = NULL, *Mbad = NULL, *M3 = NULL;
  double kd[20], md[20];
  for (int i = 0; i < 20; ++i) {
    kd[i] = i == 0 ? -1.0 : (double)(i + 1);
    md[i] = i == 4 ? 0.0 : 1.0;
  }
  MUST(fb_mat_new_diag(20, kd, &K, &err), &err);
  MUST(fb_mat_new_scaled_identity(20, 1.0, &M, &err), &err);
  MUST(fb_mat_new_diag(20, md, &Mbad, &err), &err);
  MUST(fb_mat_new_scaled_identity(3, 1.0, &M3, &err), &err);
  expect_modes_error(K, M, 2, FB_EIG_DENSE, FB_ESOLVER, "not positive semi-definite");
  expect_modes_error(K, M, 2, FB_EIG_LANCZOS, FB_ESOLVER, "not positive semi-definite");
  expect_modes_error(M, Mbad, 2, FB_EIG_DENSE, FB_ESOLVER,
                     "mass matrix is not positive definite");
  expect_modes_error(K, M3, 2, FB_EIG_DENSE, FB_EINVAL, "same non-empty square size");
  expect_modes_error(K, M, 0, FB_EIG_DENSE, FB_EINVAL, "0 modes asked of 20 DOFs");
  expect_modes_error(K, M, 21, FB_EIG_DENSE, FB_EINVAL, "21 modes asked of 20 DOFs");
  const size_t r2[3] = {0, 0, 1}, c2[3] = {0, 1, 1};
  const double unsym[3] = {1.0, 0.5, 1.0}, with_nan[3] = {1.0, 0.0, NAN};
  fb_mat *Ku = NULL, *Kn = NULL, *I2 = NULL;
  MUST(fb_mat_new_triplets(2, 2, 3, r2, c2, unsym, &Ku, &err), &err);
  MUST(fb_mat_new_triplets(2, 2, 3, r2, c2, with_nan, &Kn, &err), &err);
  MUST(fb_mat_new_scaled_identity(2, 1.0, &I2, &err), &err);
  expect_modes_error(Ku, I2, 1, FB_EIG_DENSE, FB_EINVAL, "must be symmetric");
  expect_modes_error(Kn, I2, 1, FB_EIG_DENSE, FB_EINVAL, "must be symmetric");
  fb_mat_free(&Ku);
  fb_mat_free(&Kn);
  fb_mat_free(&I2);
  /* All but one mode are the dense path's, whatever the size: the
   * diagonal problem's eigenvalues are the diagonal, sorted. */
  double f[19];
  kd[0] = 0.5;
  fb_mat_free(&K);
  MUST(fb_mat_new_diag(20, kd, &K, &err), &err);
  const fb_eig_opts any = eig_with(FB_EIG_AUTO);
  MUST(fb_fem_modes(K, M, 19, &any, f, NULL, &err), &err);
  CHECK_NEAR(f[0], sqrt(0.5) / (2 * PI), 1e-12);
  CHECK_NEAR(f[18], sqrt(19.0) / (2 * PI), 1e-12);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mat_free(&Mbad);
  fb_mat_free(&M3);
}

/* ---- Constraints. */

static void test_constraints(void)
{
  fb_err err;
  size_t keep[6];
  const size_t fixed[2] = {4, 1}, twice[3] = {4, 1, 4}, out_of_range[1] = {6};
  MUST(fb_fem_free_dofs(6, fixed, 2, keep, &err), &err);
  CHECK(keep[0] == 0 && keep[1] == 2 && keep[2] == 3 && keep[3] == 5);
  CHECK(fb_fem_free_dofs(6, twice, 3, keep, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "DOF 4 (node 0, component 4) fixed twice") != NULL);
  CHECK(fb_fem_free_dofs(6, out_of_range, 1, keep, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "out of range") != NULL);
  MUST(fb_fem_free_dofs(3, NULL, 0, keep, &err), &err);
  CHECK(keep[0] == 0 && keep[2] == 2);

  /* a_ij = 10 i + j (+1 so no entry is zero), dense and sparse: the
   * submatrix of rows/columns {0, 2, 3} has entries 10 keep_i + keep_j + 1. */
  double vals[16];
  size_t rows[16], cols[16];
  for (size_t j = 0; j < 4; ++j)
    for (size_t i = 0; i < 4; ++i) {
      vals[j * 4 + i] = 10.0 * (double)i + (double)j + 1.0;
      rows[j * 4 + i] = i;
      cols[j * 4 + i] = j;
    }
  fb_mat *dense = NULL, *sparse = NULL, *sub = NULL;
  MUST(fb_mat_new_dense(4, 4, vals, &dense, &err), &err);
  MUST(fb_mat_new_triplets(4, 4, 16, rows, cols, vals, &sparse, &err), &err);
  const size_t kept[3] = {0, 2, 3};
  const fb_mat *inputs[2] = {dense, sparse};
  for (int s = 0; s < 2; ++s) {
    MUST(fb_fem_submatrix(inputs[s], kept, 3, &sub, &err), &err);
    CHECK(sub && fb_mat_is_sparse(sub) == s && fb_mat_nrows(sub) == 3);
    for (size_t i = 0; sub && i < 3; ++i)
      for (size_t j = 0; j < 3; ++j)
        CHECK(fb_mat_get(sub, i, j) == 10.0 * (double)kept[i] + (double)kept[j] + 1.0);
    fb_mat_free(&sub);
  }
  const size_t unsorted[2] = {2, 1}, beyond[2] = {1, 4};
  CHECK(fb_fem_submatrix(sparse, unsorted, 2, &sub, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "keep[1] = 1") != NULL);
  CHECK(fb_fem_submatrix(sparse, beyond, 2, &sub, &err) == FB_EINVAL);
  CHECK(fb_fem_submatrix(sparse, kept, 0, &sub, &err) == FB_EINVAL);
  fb_mat *rect = NULL;
  MUST(fb_mat_new_dense(2, 8, vals, &rect, &err), &err);
  CHECK(fb_fem_submatrix(rect, kept, 1, &sub, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "not square") != NULL);
  CHECK(sub == NULL);
  fb_mat_free(&rect);
  fb_mat_free(&dense);
  fb_mat_free(&sparse);
}

int main(void)
{
  test_element_spectrum();
  test_element_errors();
  test_inplane_bending_unit();
  test_drill_factor_element();
  test_rigid_body();
  test_total_mass();
  test_plate_mass_properties();
  test_patch();
  test_inplane_cantilever();
  test_modes_closed_form();
  test_modes_paths();
  test_drill_factor_modes();
  test_modes_errors();
  test_constraints();
  return check_report("test_shell");
}
