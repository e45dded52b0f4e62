/* SPDX-License-Identifier: BSD-3-Clause */
/* Stress recovery of the shell elements (src/fem/shell_stress.c) against
 * closed forms: von Mises and principal stresses of known states,
 * membrane and bending patch tests (exact for the elements), a cantilever
 * plate under an end load (beam theory at mid-length), and modal stress
 * recovery against the nodal one on the same displacement field. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"

#include "check.h"
#include "test_shell_util.h"

static const fb_shell_props STEEL = {210e9, 0.3, 7850.0, 0.01, 0.0, 0.0};

/* The in-plane stress s (x, y, xy in the local axes, rows of axes) as a
 * global 3x3 tensor R^T S R (row-major). */
static void global_tensor(const double *axes, const double *s, double *out)
{
  const double loc[9] = {s[0], s[2], 0.0, s[2], s[1], 0.0, 0.0, 0.0, 0.0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double sum = 0.0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          sum += axes[a * 3 + i] * loc[a * 3 + b] * axes[b * 3 + j];
      out[i * 3 + j] = sum;
    }
}

static void test_von_mises_known_states(void)
{
  const double s = 120e6, tau = 50e6, zero[3] = {0.0, 0.0, 0.0};
  fb_shell_stress_state st;
  /* Round-off of a few operations on values ~1e8: 1e-6 Pa is 1e-14 relative. */
  const double tol = 1e-6;
  const double uniaxial[3] = {s, 0.0, 0.0};
  fb_shell_stress_state_from_surfaces(uniaxial, zero, 0.01, 210e9, 0.3, &st);
  CHECK_NEAR(st.von_mises_top, s, tol);
  CHECK_NEAR(st.von_mises_bottom, 0.0, tol);
  CHECK_NEAR(st.von_mises_max, s, tol);
  CHECK_NEAR(st.principal_top[0], s, tol);
  CHECK_NEAR(st.principal_top[1], 0.0, tol);
  /* Pure shear: principal +-tau, von Mises sqrt(3) tau. */
  const double shear[3] = {0.0, 0.0, tau};
  fb_shell_stress_state_from_surfaces(shear, shear, 0.01, 210e9, 0.3, &st);
  CHECK_NEAR(st.von_mises_top, sqrt(3.0) * tau, tol);
  CHECK_NEAR(st.principal_bottom[0], tau, tol);
  CHECK_NEAR(st.principal_bottom[1], -tau, tol);
  /* Equibiaxial: von Mises s; and s = -sy: sqrt(3) s (pure shear at 45 deg). */
  const double biax[3] = {s, s, 0.0}, opposite[3] = {s, -s, 0.0};
  fb_shell_stress_state_from_surfaces(biax, opposite, 0.01, 210e9, 0.3, &st);
  CHECK_NEAR(st.von_mises_top, s, tol);
  CHECK_NEAR(st.von_mises_bottom, sqrt(3.0) * s, tol);
  CHECK_NEAR(st.von_mises_max, sqrt(3.0) * s, tol);
  /* Resultants from the surfaces: N = t (top + bottom) / 2, M = t^2
   * (top - bottom) / 12; strains from Hooke's law. */
  CHECK_NEAR(st.force[0], 0.01 * s, 1e-8);
  CHECK_NEAR(st.moment[1], 1e-4 * 2.0 * s / 12.0, 1e-10);
  CHECK_NEAR(st.strain[0], (s - 0.3 * 0.0) / 210e9, 1e-18);
  CHECK_NEAR(st.curvature[1], (2.0 * s / 0.01 - 0.0) / 210e9, 1e-16);
}

/* A plate of lx x ly in the plane through origin spanned by the unit
 * vectors e_u, e_v (orthogonal), distorted, of triangles or quadrilaterals. */
static fb_mesh *tilted_plate(const double *eu, const double *ev, int tri)
{
  fb_mesh *m = NULL;
  fb_err err;
  const double lx = 2.0, ly = 1.0, o[3] = {0.3, -0.2, 0.5};
  const double du[3] = {lx * eu[0], lx * eu[1], lx * eu[2]};
  const double dv[3] = {ly * ev[0], ly * ev[1], ly * ev[2]};
  MUST(fb_mesh_new(&m, &err), &err);
  if (m)
    shell_face(m, o, du, dv, 6, 4, tri, 0.3);
  return m;
}

/* Patch tests: a uniaxial membrane strain and a uniform moment, imposed as
 * the nodal values of the exact fields on a distorted, tilted plate. Both
 * fields are reproduced exactly by the elements (OPT, QM6: linear
 * displacements; DKT, DKQ: any quadratic w), so every element's recovered
 * state must equal the closed form to round-off. */
static void test_patches(int tri)
{
  const double c = cos(0.4), s = sin(0.4);
  const double eu[3] = {c, 0.0, s}, ev[3] = {-s * 0.6, 0.8, c * 0.6};
  const double en[3] = {eu[1] * ev[2] - eu[2] * ev[1], eu[2] * ev[0] - eu[0] * ev[2],
                        eu[0] * ev[1] - eu[1] * ev[0]};
  const double o[3] = {0.3, -0.2, 0.5}, eps = 4e-4, kx = 0.05, nu = STEEL.poisson;
  const double young = STEEL.young, t = STEEL.thickness;
  fb_mesh *m = tilted_plate(eu, ev, tri);
  fb_shell_stress *ss = NULL;
  fb_err err;
  if (!m)
    return;
  MUST(fb_shell_stress_new(m, &STEEL, &ss, &err), &err);
  const size_t nn = fb_mesh_nnodes(m), ne = fb_mesh_nelements(m);
  double *u = calloc(6 * nn, sizeof *u);
  fb_shell_stress_state *st = malloc(ne * sizeof *st);
  CHECK(u && st && ss);
  if (!u || !st || !ss)
    goto done;
  /* Membrane: u = eps s e_u - nu eps t e_v: sigma_uu = E eps, others 0. */
  for (size_t a = 0; a < nn; ++a) {
    const double *x = fb_mesh_node_xyz(m, a);
    double d[3], su = 0.0, sv = 0.0;
    for (int k = 0; k < 3; ++k)
      d[k] = x[k] - o[k];
    for (int k = 0; k < 3; ++k) {
      su += d[k] * eu[k];
      sv += d[k] * ev[k];
    }
    for (int k = 0; k < 3; ++k)
      u[6 * a + (size_t)k] = eps * su * eu[k] - nu * eps * sv * ev[k];
  }
  fb_shell_stress_eval_nodal(ss, u, st);
  /* Round-off of the strain-displacement rows: ~1e-12 of E eps (84 MPa). */
  const double sigma = young * eps, tol = 1e-9 * sigma;
  for (size_t e = 0; e < ne; ++e) {
    double g[9], want[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        want[i * 3 + j] = sigma * eu[i] * eu[j];
    global_tensor(fb_shell_stress_axes(ss, e), st[e].top, g);
    for (int k = 0; k < 9; ++k)
      CHECK_NEAR(g[k], want[k], tol);
    global_tensor(fb_shell_stress_axes(ss, e), st[e].bottom, g);
    for (int k = 0; k < 9; ++k)
      CHECK_NEAR(g[k], want[k], tol);
    CHECK_NEAR(st[e].von_mises_max, sigma, tol);
    CHECK_NEAR(st[e].principal_top[0], sigma, tol);
    CHECK_NEAR(st[e].strain[0] + st[e].strain[1], eps * (1.0 - nu), 1e-9 * eps);
    CHECK_NEAR(st[e].force[0] + st[e].force[1], sigma * t, tol * t);
  }
  /* Bending: w = -(kx s^2 + ky t^2) / 2 along the normal, ky = -nu kx, so
   * kappa = (kx, ky, 0), M_u = D (kx + nu ky) = E t^3 kx / 12, M_v = 0,
   * and the top surface (the normal's side) sigma_uu = 6 M / t^2 = E t kx
   * / 2. The rotations are those of the normal: rotation vector (w,v)
   * e_u - (w,u) e_v. */
  const double ky = -nu * kx;
  for (size_t a = 0; a < nn; ++a) {
    const double *x = fb_mesh_node_xyz(m, a);
    double su = 0.0, sv = 0.0;
    for (int k = 0; k < 3; ++k) {
      su += (x[k] - o[k]) * eu[k];
      sv += (x[k] - o[k]) * ev[k];
    }
    const double w = -(kx * su * su + ky * sv * sv) / 2.0, wu = -kx * su, wv = -ky * sv;
    for (int k = 0; k < 3; ++k) {
      u[6 * a + (size_t)k] = w * en[k];
      u[6 * a + 3 + (size_t)k] = wv * eu[k] - wu * ev[k];
    }
  }
  fb_shell_stress_eval_nodal(ss, u, st);
  const double moment = young * t * t * t * kx / 12.0, sb = 6.0 * moment / (t * t);
  for (size_t e = 0; e < ne; ++e) {
    double g[9];
    global_tensor(fb_shell_stress_axes(ss, e), st[e].top, g);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        CHECK_NEAR(g[i * 3 + j], sb * eu[i] * eu[j], 1e-9 * sb);
    global_tensor(fb_shell_stress_axes(ss, e), st[e].bottom, g);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        CHECK_NEAR(g[i * 3 + j], -sb * eu[i] * eu[j], 1e-9 * sb);
    CHECK_NEAR(st[e].principal_top[0], sb, 1e-9 * sb);
    CHECK_NEAR(st[e].principal_bottom[1], -sb, 1e-9 * sb);
    CHECK_NEAR(st[e].von_mises_max, sb, 1e-9 * sb);
    CHECK_NEAR(st[e].moment[0] + st[e].moment[1], moment, 1e-9 * moment);
    CHECK_NEAR(st[e].curvature[0] + st[e].curvature[1], kx + ky, 1e-9 * kx);
    CHECK_NEAR(st[e].force[0] + st[e].force[1], 0.0, 1e-9 * sb * t);
  }
done:
  free(u);
  free(st);
  fb_shell_stress_free(&ss);
  fb_mesh_free(&m);
}

/* Cantilever plate L x b clamped at x = 0, end load P (+z) spread over
 * the end nodes as a consistent edge load (halves at the corners). Beam
 * theory: sigma_x = -+ 6 P (L - x) / (b t^2) at the top / bottom (the top,
 * +z, in compression: the plate curves up). Returns the largest relative
 * error of the elements' sigma_x at the top and bottom over the
 * elements whose centre lies in the middle fifth of the span. */
static double cantilever_error(int nx, int ny, int tri)
{
  const double L = 1.0, b = 0.1, P = 100.0, t = STEEL.thickness;
  fb_mesh *m = shell_plate(L, b, nx, ny, tri, 0.0);
  fb_mat *K = NULL;
  fb_shell_stress *ss = NULL;
  fb_err err;
  double worst = NAN;
  if (!m)
    return worst;
  const size_t nn = fb_mesh_nnodes(m), ne = fb_mesh_nelements(m);
  double *f = calloc(6 * nn, sizeof *f), *u = malloc(6 * nn * sizeof *u);
  size_t *fixed = malloc(6 * nn * sizeof *fixed), nfixed = 0;
  fb_shell_stress_state *st = malloc(ne * sizeof *st);
  MUST(fb_fem_assemble(m, &STEEL, FB_MASS_CONSISTENT, &K, NULL, &err), &err);
  MUST(fb_shell_stress_new(m, &STEEL, &ss, &err), &err);
  CHECK(f && u && fixed && st);
  if (!f || !u || !fixed || !st || !K || !ss)
    goto done;
  shell_clamp_x0(m, fixed, &nfixed);
  for (size_t a = 0; a < nn; ++a) {
    const double *x = fb_mesh_node_xyz(m, a);
    if (x[0] > L - 1e-9) {
      const int corner = x[1] < 1e-9 || x[1] > b - 1e-9;
      f[6 * a + 2] = P / ny * (corner ? 0.5 : 1.0);
    }
  }
  shell_static(K, fixed, nfixed, f, u);
  fb_shell_stress_eval_nodal(ss, u, st);
  worst = 0.0;
  for (size_t e = 0; e < ne; ++e) {
    const size_t *nodes = fb_mesh_element_nodes(m, e);
    const size_t nv = (size_t)fb_mesh_element_type(m, e);
    double xc = 0.0;
    for (size_t a = 0; a < nv; ++a)
      xc += fb_mesh_node_xyz(m, nodes[a])[0] / (double)nv;
    if (fabs(xc - L / 2.0) > L / 10.0)
      continue;
    /* A triangle's local x runs along its edge 1-2, the diagonal for
     * half of them: compare the global sigma_xx. */
    const double want = 6.0 * P * (L - xc) / (b * t * t);
    double top[9], bottom[9];
    global_tensor(fb_shell_stress_axes(ss, e), st[e].top, top);
    global_tensor(fb_shell_stress_axes(ss, e), st[e].bottom, bottom);
    worst = fmax(worst, fabs(top[0] + want) / want);
    worst = fmax(worst, fabs(bottom[0] - want) / want);
  }
done:
  free(f);
  free(u);
  free(fixed);
  free(st);
  fb_mat_free(&K);
  fb_shell_stress_free(&ss);
  fb_mesh_free(&m);
  return worst;
}

/* Mid-span lies 5 widths from the clamp, where the clamp's restraint of
 * the plate's anticlastic curvature has died out, so beam theory holds
 * there to far below the discretisation error (measured: 3e-6 on the
 * finest mesh). DKQ's centre curvature is exact in a linearly varying
 * moment on rectangles (measured 1e-11): 1e-4 bounds it at every level.
 * DKT's centroid curvature in the cubic deflection is first-order
 * accurate (measured 4.0%, 2.1%, 1.05%): each halving of the elements
 * must at least nearly halve the error, and the finest mesh be within
 * 1.5%. */
static void test_cantilever(void)
{
  double prev = INFINITY;
  for (int level = 1; level <= 3; ++level) {
    const int nx = 10 << (level - 1), ny = 2 << (level - 1);
    const double quad = cantilever_error(nx, ny, 0), tri = cantilever_error(nx, ny, 1);
    printf("cantilever %dx%d: max relative error of sigma_x at mid-span: S4 %.3e, S3 %.3e\n",
           nx, ny, quad, tri);
    CHECK(quad < 1e-4);
    CHECK(tri < 0.55 * prev);
    prev = tri;
  }
  CHECK(prev < 0.015);
}

/* A folded, free structure of a quadrilateral face and a triangular one
 * at 120 degrees: its 12 lowest modes (rigid ones included) as Phi; for
 * q of mixed signs the stresses of u = Phi q by the nodal recovery and by
 * the stress modes must agree to round-off (the same linear map in
 * another order: 1e-12 of the largest stress). */
static void test_modal_recovery(void)
{
  fb_mesh *m = NULL;
  fb_mat *K = NULL, *M = NULL;
  fb_shell_stress *ss = NULL;
  fb_err err;
  const size_t nmodes = 12;
  const double o[3] = {0.0, 0.0, 0.0}, du[3] = {1.2, 0.0, 0.0}, dv[3] = {0.0, 0.8, 0.0};
  const double dw[3] = {0.0, -0.4, 0.4 * sqrt(3.0)};
  MUST(fb_mesh_new(&m, &err), &err);
  if (!m)
    return;
  shell_face(m, o, du, dv, 4, 3, 0, 0.2);
  shell_face(m, o, du, dw, 4, 2, 1, 0.0);
  const size_t n = 6 * fb_mesh_nnodes(m), ne = fb_mesh_nelements(m);
  double *phi = malloc(n * nmodes * sizeof *phi), *freq = malloc(nmodes * sizeof *freq);
  double *u = calloc(n, sizeof *u), q[12];
  fb_shell_stress_state *a = malloc(ne * sizeof *a), *b = malloc(ne * sizeof *b);
  CHECK(phi && freq && u && a && b);
  MUST(fb_fem_assemble(m, &STEEL, FB_MASS_CONSISTENT, &K, &M, &err), &err);
  MUST(fb_shell_stress_new(m, &STEEL, &ss, &err), &err);
  if (!phi || !freq || !u || !a || !b || !K || !M || !ss)
    goto done;
  CHECK(fb_shell_stress_eval_modal(ss, q, a, &err) == FB_EINVAL);
  CHECK(fb_shell_stress_modes(ss, phi, n - 1, nmodes, &err) == FB_EINVAL);
  MUST(fb_fem_modes(K, M, nmodes, NULL, freq, phi, &err), &err);
  MUST(fb_shell_stress_modes(ss, phi, n, nmodes, &err), &err);
  CHECK(fb_shell_stress_nmodes(ss) == nmodes);
  for (size_t k = 0; k < nmodes; ++k) {
    q[k] = (k % 3 == 0 ? -1.0 : 1.0) * (1.0 + 0.37 * (double)k);
    for (size_t i = 0; i < n; ++i)
      u[i] += phi[k * n + i] * q[k];
  }
  fb_shell_stress_eval_nodal(ss, u, a);
  MUST(fb_shell_stress_eval_modal(ss, q, b, &err), &err);
  double scale = 0.0;
  for (size_t e = 0; e < ne; ++e)
    scale = fmax(scale, a[e].von_mises_max);
  CHECK(scale > 0.0);
  for (size_t e = 0; e < ne; ++e) {
    for (int k = 0; k < 3; ++k) {
      CHECK_NEAR(a[e].top[k], b[e].top[k], 1e-12 * scale);
      CHECK_NEAR(a[e].bottom[k], b[e].bottom[k], 1e-12 * scale);
    }
    CHECK_NEAR(a[e].von_mises_max, b[e].von_mises_max, 1e-12 * scale);
    /* The mode matrix's first row is sigma_x at the top of each mode. */
    const double *se = fb_shell_stress_mode_matrix(ss, e);
    double sx = 0.0;
    for (size_t k = 0; k < nmodes; ++k)
      sx += se[k] * q[k];
    CHECK_NEAR(sx, a[e].top[0], 1e-12 * scale);
  }
  /* The rigid-body modes (the first six) carry no stress: 1e-9 of the
   * elastic modes' stresses bounds their round-off. */
  for (size_t e = 0; e < ne; ++e) {
    const double *se = fb_shell_stress_mode_matrix(ss, e);
    for (size_t r = 0; r < 6; ++r)
      for (size_t k = 0; k < 6; ++k)
        CHECK_NEAR(se[r * nmodes + k], 0.0, 1e-9 * scale);
  }
done:
  free(phi);
  free(freq);
  free(u);
  free(a);
  free(b);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_shell_stress_free(&ss);
  fb_mesh_free(&m);
}

/* A rigid motion (translation t and small rotation theta about a point)
 * strains nothing: on a distorted tilted plate of triangles and on a
 * warped quadrilateral (its frame is the mean plane's; the rigid links
 * add -h_a r_y,a to node a's u with heights h_a alternating in sign, an
 * hourglass pattern whose centre strain is zero when r_y is uniform, so
 * this checks the frame and not the links). Round-off: 1e-9 of E |theta|. */
static void test_rigid_motion(void)
{
  const double c = cos(0.4), s = sin(0.4);
  const double eu[3] = {c, 0.0, s}, ev[3] = {-s * 0.6, 0.8, c * 0.6};
  const double t[3] = {1e-3, -2e-3, 5e-4}, theta[3] = {2e-3, -1e-3, 3e-3};
  fb_mesh *meshes[2] = {tilted_plate(eu, ev, 1), NULL};
  fb_err err;
  size_t q[4];
  MUST(fb_mesh_new(&meshes[1], &err), &err);
  if (meshes[1]) {
    /* Node 3 lies 5e-3 of the diagonal above the plane of the others. */
    MUST(fb_mesh_add_node(meshes[1], 1, 0.0, 0.0, 0.0, &q[0], &err), &err);
    MUST(fb_mesh_add_node(meshes[1], 2, 1.0, 0.1, 0.0, &q[1], &err), &err);
    MUST(fb_mesh_add_node(meshes[1], 3, 1.1, 0.9, 0.007, &q[2], &err), &err);
    MUST(fb_mesh_add_node(meshes[1], 4, -0.1, 1.0, 0.0, &q[3], &err), &err);
    MUST(fb_mesh_add_element(meshes[1], 1, FB_ELEM_QUAD4, q, &err), &err);
  }
  const double scale =
      STEEL.young * sqrt(theta[0] * theta[0] + theta[1] * theta[1] + theta[2] * theta[2]);
  for (int k = 0; k < 2; ++k) {
    fb_mesh *m = meshes[k];
    fb_shell_stress *ss = NULL;
    if (!m)
      continue;
    MUST(fb_shell_stress_new(m, &STEEL, &ss, &err), &err);
    const size_t nn = fb_mesh_nnodes(m), ne = fb_mesh_nelements(m);
    double *u = malloc(6 * nn * sizeof *u);
    fb_shell_stress_state *st = malloc(ne * sizeof *st);
    CHECK(u && st);
    if (u && st && ss) {
      for (size_t a = 0; a < nn; ++a) {
        const double *x = fb_mesh_node_xyz(m, a);
        u[6 * a] = t[0] + theta[1] * x[2] - theta[2] * x[1];
        u[6 * a + 1] = t[1] + theta[2] * x[0] - theta[0] * x[2];
        u[6 * a + 2] = t[2] + theta[0] * x[1] - theta[1] * x[0];
        for (size_t d = 0; d < 3; ++d)
          u[6 * a + 3 + d] = theta[d];
      }
      fb_shell_stress_eval_nodal(ss, u, st);
      for (size_t e = 0; e < ne; ++e)
        CHECK_NEAR(st[e].von_mises_max, 0.0, 1e-9 * scale);
    }
    free(u);
    free(st);
    fb_shell_stress_free(&ss);
    fb_mesh_free(&meshes[k]);
  }
}

/* Each element takes its section's properties: half a plate 20 mm thick,
 * half 10 mm, under the uniform curvature kx (ky = -nu kx): the top
 * stress E t kx / 2 doubles in the thick half, the moment E t^3 kx / 12
 * grows eightfold (round-off 1e-9). */
static void test_sections(void)
{
  fb_mesh *m = shell_plate(2.0, 1.0, 4, 2, 0, 0.0);
  fb_shell_stress *ss = NULL;
  fb_err err;
  const size_t thick[4] = {0, 1, 2, 3};
  fb_shell_props thick_props = STEEL;
  thick_props.thickness = 0.02;
  if (!m)
    return;
  MUST(fb_mesh_add_elset(m, "THICK", 4, thick, &err), &err);
  MUST(fb_mesh_set_section(m, "THICK", &thick_props, &err), &err);
  MUST(fb_shell_stress_new(m, &STEEL, &ss, &err), &err);
  const size_t nn = fb_mesh_nnodes(m), ne = fb_mesh_nelements(m);
  const double kx = 0.02, ky = -STEEL.poisson * kx;
  double *u = calloc(6 * nn, sizeof *u);
  fb_shell_stress_state *st = malloc(ne * sizeof *st);
  CHECK(u && st);
  if (u && st && ss) {
    for (size_t a = 0; a < nn; ++a) {
      const double *x = fb_mesh_node_xyz(m, a);
      u[6 * a + 2] = -(kx * x[0] * x[0] + ky * x[1] * x[1]) / 2.0;
      u[6 * a + 3] = -ky * x[1]; /* r_x = w,y */
      u[6 * a + 4] = kx * x[0];  /* r_y = -w,x */
    }
    fb_shell_stress_eval_nodal(ss, u, st);
    for (size_t e = 0; e < ne; ++e) {
      const double t = e < 4 ? 0.02 : 0.01, sb = STEEL.young * t * kx / 2.0;
      const double moment = STEEL.young * t * t * t * kx / 12.0;
      CHECK_NEAR(st[e].top[0], sb, 1e-9 * sb);
      CHECK_NEAR(st[e].top[1], 0.0, 1e-9 * sb);
      CHECK_NEAR(st[e].moment[0], moment, 1e-9 * moment);
    }
  }
  free(u);
  free(st);
  fb_shell_stress_free(&ss);
  fb_mesh_free(&m);
}

/* A degenerate element is refused with its id. */
static void test_errors(void)
{
  fb_mesh *m = NULL;
  fb_shell_stress *ss = NULL;
  fb_err err;
  size_t nodes[3];
  MUST(fb_mesh_new(&m, &err), &err);
  if (!m)
    return;
  MUST(fb_mesh_add_node(m, 1, 0.0, 0.0, 0.0, &nodes[0], &err), &err);
  MUST(fb_mesh_add_node(m, 2, 1.0, 0.0, 0.0, &nodes[1], &err), &err);
  MUST(fb_mesh_add_node(m, 3, 2.0, 0.0, 0.0, &nodes[2], &err), &err);
  MUST(fb_mesh_add_element(m, 7, FB_ELEM_TRI3, nodes, &err), &err);
  CHECK(fb_shell_stress_new(m, &STEEL, &ss, &err) == FB_EINVAL);
  CHECK(ss == NULL);
  CHECK(strstr(err.msg, "element 7: degenerate") != NULL);
  fb_shell_stress_free(&ss);
  fb_mesh_free(&m);
}

int main(void)
{
  test_von_mises_known_states();
  test_patches(0);
  test_patches(1);
  test_cantilever();
  test_modal_recovery();
  test_rigid_motion();
  test_sections();
  test_errors();
  return check_report("test_shell_stress");
}
