/* SPDX-License-Identifier: BSD-3-Clause */
/* Couplings of points that are not nodes (fb_hull_coupling_build,
 * src/vehicle/coupling.c) against Navier's series for a simply supported
 * plate (Timoshenko & Woinowsky-Krieger, "Theory of Plates and Shells",
 * 2nd ed., section 30):
 *   w(x, y) = 4 P / (pi^4 D a b) sum_m sum_n sin(m pi x0 / a) sin(n pi y0 / b)
 *             sin(m pi x / a) sin(n pi y / b) / ((m / a)^2 + (n / b)^2)^2
 * for a force P at (x0, y0), D = E t^3 / (12 (1 - nu^2)); summed to
 * m, n < 400 (the terms fall as (m^2 + n^2)^-2: a truncation below 1e-6
 * away from the load).
 *
 * A 1 m square steel plate, 10 mm thick, on a 20 x 20 mesh of DKQ
 * quadrilaterals, carries 1 kN at P = (0.537, 0.461), which is no node.
 *  - Distributing coupling over the nodes within 0.08 m: its weights are in
 *    equilibrium with the force (sum 1, first moments at P, to 1e-12), and
 *    the plate's deflection at four points away from the load matches
 *    Navier's for the same nodal forces (a superposition of point loads at
 *    the nodes, the continuum's answer to exactly what the coupling
 *    applies) within 1 %: the mesh's discretisation error (DKQ converges as
 *    h^2; 0.3 to 0.4 % here, measured). The coupling point's motion w . u
 *    is work-conjugate to its force.
 *  - Kinematic coupling to the nearest node (0.55, 0.45), a rigid lever of
 *    (-0.013, 0.011) m: the force and its moments at the node act, to first
 *    order in the lever, as the force at P. The far-field deflection matches
 *    Navier's at P within 1 %, and the lever's own share (the deflection
 *    minus that of the force at the node alone, on the same mesh) matches
 *    Navier's for the couple F x lever at the node (the derivative of the
 *    point-load solution with respect to the load's position) within 5 %:
 *    the mesh's error on a concentrated couple, 0.2 to 2.3 % here, measured
 *    (a lever with a wrong sign would be 100 % or more off).
 *  - Nodes on a line that misses the point by more than 1 mm are refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "test_shell_util.h"

#define SIDE 1.0
#define NDIV 20
#define FORCE 1e3
#define PX 0.537
#define PY 0.461
#define NTERMS 400

static const fb_shell_props STEEL_10MM = {2.1e11, 0.3, 7850.0, 0.01, 0.0, 0.0};

static int near(double a, double b)
{
  return fabs(a - b) < 1e-9;
}

/* Navier's deflection at (x, y) for a unit force at (x0, y0). */
static double navier(double x0, double y0, double x, double y)
{
  const double pi = 3.14159265358979323846, t = STEEL_10MM.thickness, nu = STEEL_10MM.poisson;
  const double D = STEEL_10MM.young * t * t * t / (12.0 * (1.0 - nu * nu));
  double sum = 0.0;
  for (int m = 1; m < NTERMS; ++m) {
    const double sx = sin(m * pi * x0 / SIDE) * sin(m * pi * x / SIDE);
    for (int n = 1; n < NTERMS; ++n) {
      const double k = (double)(m * m + n * n) / (SIDE * SIDE);
      sum += sx * sin(n * pi * y0 / SIDE) * sin(n * pi * y / SIDE) / (k * k);
    }
  }
  return 4.0 / (pi * pi * pi * pi * D * SIDE * SIDE) * sum;
}

/* Simply supported edges (u_z = 0, the rotation along the edge free),
 * in-plane DOFs and drilling fixed everywhere (a plate in bending). */
static size_t fix_supported(const fb_mesh *m, size_t *fixed)
{
  size_t n = 0;
  for (size_t a = 0; a < fb_mesh_nnodes(m); ++a) {
    const double *p = fb_mesh_node_xyz(m, a);
    const int x_edge = near(p[0], 0.0) || near(p[0], SIDE);
    const int y_edge = near(p[1], 0.0) || near(p[1], SIDE);
    shell_fix(fixed, &n, a, 0);
    shell_fix(fixed, &n, a, 1);
    shell_fix(fixed, &n, a, 5);
    if (x_edge || y_edge)
      shell_fix(fixed, &n, a, 2);
    if (x_edge)
      shell_fix(fixed, &n, a, 3);
    if (y_edge)
      shell_fix(fixed, &n, a, 4);
  }
  return n;
}

/* The plate's displacements u (6 nnodes) under the coupling's force
 * FORCE w at its DOFs. */
static void solve(const fb_mesh *m, const fb_hull_coupling *c, double *u)
{
  fb_err err;
  const size_t n = 6 * fb_mesh_nnodes(m);
  size_t *fixed = malloc(n * sizeof *fixed);
  double *f = calloc(n, sizeof *f);
  fb_mat *K = NULL;
  CHECK(fixed && f);
  MUST(fb_fem_assemble(m, &STEEL_10MM, FB_MASS_CONSISTENT, &K, NULL, &err), &err);
  if (fixed && f && K) {
    for (size_t k = 0; k < c->n; ++k)
      f[c->dof[k]] += FORCE * c->w[k];
    shell_static(K, fixed, fix_supported(m, fixed), f, u);
  }
  fb_mat_free(&K);
  free(fixed);
  free(f);
}

/* Points away from the load where the deflections are compared. */
static const double PROBES[4][2] = {{0.25, 0.25}, {0.75, 0.5}, {0.5, 0.8}, {0.2, 0.65}};

static double deflection_at(const fb_mesh *m, const double *u, const double *p)
{
  const long a = fb_mesh_find_node_at(m, p[0], p[1], 0.0, 1e-9);
  CHECK(a >= 0);
  return a >= 0 ? u[6 * (size_t)a + 2] : NAN;
}

static fb_scenario coupling_scenario(fb_coupling_kind kind, double radius)
{
  fb_scenario s;
  memset(&s, 0, sizeof s);
  s.coupling = kind;
  s.coupling_radius = radius;
  s.coupling_surface = "PLATE";
  return s;
}

static fb_mesh *plate(void)
{
  fb_err err;
  fb_mesh *m = shell_plate(SIDE, SIDE, NDIV, NDIV, 0, 0.0);
  const size_t ne = fb_mesh_nelements(m);
  size_t *all = malloc(ne * sizeof *all);
  CHECK(all != NULL);
  for (size_t e = 0; all && e < ne; ++e)
    all[e] = e;
  if (all)
    MUST(fb_mesh_add_elset(m, "PLATE", ne, all, &err), &err);
  free(all);
  return m;
}

static void test_distributing(void)
{
  fb_err err;
  fb_mesh *m = plate();
  const fb_scenario s = coupling_scenario(FB_COUPLING_DISTRIBUTING, 0.08);
  fb_hull_coupling c = {0, NULL, NULL};
  size_t node = 0;
  MUST(fb_hull_coupling_build(&s, m, "P", PX, PY, &c, &node, &err), &err);
  double sum = 0.0, mx = 0.0, my = 0.0;
  for (size_t k = 0; k < c.n; ++k) {
    const double *p = fb_mesh_node_xyz(m, c.dof[k] / 6);
    CHECK(c.dof[k] % 6 == 2 && hypot(p[0] - PX, p[1] - PY) <= 0.08);
    sum += c.w[k];
    mx += c.w[k] * p[0];
    my += c.w[k] * p[1];
  }
  CHECK(c.n >= 4);
  CHECK_NEAR(sum, 1.0, 1e-12);
  CHECK_NEAR(mx, PX, 1e-12);
  CHECK_NEAR(my, PY, 1e-12);
  const double *pn = fb_mesh_node_xyz(m, node);
  CHECK(near(pn[0], 0.55) && near(pn[1], 0.45));

  const size_t n = 6 * fb_mesh_nnodes(m);
  double *u = malloc(n * sizeof *u);
  CHECK(u != NULL);
  if (u && c.n) {
    solve(m, &c, u);
    for (int q = 0; q < 4; ++q) {
      double expect = 0.0;
      for (size_t k = 0; k < c.n; ++k) {
        const double *p = fb_mesh_node_xyz(m, c.dof[k] / 6);
        expect += FORCE * c.w[k] * navier(p[0], p[1], PROBES[q][0], PROBES[q][1]);
      }
      const double got = deflection_at(m, u, PROBES[q]);
      fprintf(stderr, "distributing: w(%.2f, %.2f) = %.6g m, Navier %.6g (%+.3f %%)\n",
              PROBES[q][0], PROBES[q][1], got, expect, 100.0 * (got / expect - 1.0));
      CHECK_NEAR(got, expect, 0.01 * expect);
    }
    /* The coupling point's motion is the weighted average of its nodes'
     * (and its force times it the work of the nodal forces). */
    double at_point = 0.0, work = 0.0;
    for (size_t k = 0; k < c.n; ++k) {
      at_point += c.w[k] * u[c.dof[k]];
      work += FORCE * c.w[k] * u[c.dof[k]];
    }
    CHECK_NEAR(FORCE * at_point, work, 1e-12 * fabs(work));
  }
  free(u);
  fb_hull_coupling_free(&c);
  fb_mesh_free(&m);
}

static void test_kinematic(void)
{
  fb_err err;
  fb_mesh *m = plate();
  const fb_scenario s = coupling_scenario(FB_COUPLING_KINEMATIC, 0.08);
  fb_hull_coupling c = {0, NULL, NULL};
  size_t node = 0;
  MUST(fb_hull_coupling_build(&s, m, "P", PX, PY, &c, &node, &err), &err);
  CHECK(c.n == 3 && c.dof[0] == 6 * node + 2);
  const double *pn = fb_mesh_node_xyz(m, node);
  const size_t n = 6 * fb_mesh_nnodes(m);
  double *u = malloc(n * sizeof *u);
  CHECK(u != NULL);
  if (u && c.n == 3) {
    solve(m, &c, u);
    double *u_node = malloc(n * sizeof *u_node);
    fb_hull_coupling direct = {0, NULL, NULL};
    MUST(fb_hull_coupling_node(node, &direct, &err), &err);
    CHECK(u_node != NULL);
    if (u_node && direct.n)
      solve(m, &direct, u_node);
    for (int q = 0; u_node && q < 4; ++q) {
      const double got = deflection_at(m, u, PROBES[q]);
      const double at_p = FORCE * navier(PX, PY, PROBES[q][0], PROBES[q][1]);
      /* The lever's own effect: the couple F r at the node, Navier's
       * derivative with respect to the load's position times the lever
       * (central differences, 1e-5 m); the mesh's error on the
       * deflection is common to both solves and cancels. */
      const double h = 1e-5, dx = PX - pn[0], dy = PY - pn[1];
      const double *pq = PROBES[q];
      const double dndx =
          (navier(pn[0] + h, pn[1], pq[0], pq[1]) - navier(pn[0] - h, pn[1], pq[0], pq[1])) /
          (2.0 * h);
      const double dndy =
          (navier(pn[0], pn[1] + h, pq[0], pq[1]) - navier(pn[0], pn[1] - h, pq[0], pq[1])) /
          (2.0 * h);
      const double lever_fe = got - deflection_at(m, u_node, PROBES[q]);
      const double lever_navier = FORCE * (dx * dndx + dy * dndy);
      fprintf(stderr,
              "kinematic: w(%.2f, %.2f) = %.6g m, Navier at P %.6g (%+.3f %%); the lever "
              "adds %.4g m, Navier %.4g\n",
              PROBES[q][0], PROBES[q][1], got, at_p, 100.0 * (got / at_p - 1.0), lever_fe,
              lever_navier);
      CHECK_NEAR(got, at_p, 0.01 * at_p);
      CHECK_NEAR(lever_fe, lever_navier, 0.05 * fabs(lever_navier));
    }
    fb_hull_coupling_free(&direct);
    free(u_node);
  }
  free(u);
  fb_hull_coupling_free(&c);
  fb_mesh_free(&m);
}

/* The nodes of a node set on the line y = 0.5, the point 0.039 m off it:
 * refused; on it (within 1 mm), accepted. */
static void test_line(void)
{
  fb_err err;
  fb_mesh *m = plate();
  size_t line[3];
  for (int k = 0; k < 3; ++k) {
    const long a = fb_mesh_find_node_at(m, 0.45 + 0.05 * k, 0.5, 0.0, 1e-9);
    CHECK(a >= 0);
    line[k] = a >= 0 ? (size_t)a : 0;
  }
  MUST(fb_mesh_add_nset(m, "SUSP_X", 3, line, &err), &err);
  const fb_scenario s = coupling_scenario(FB_COUPLING_DISTRIBUTING, 0.08);
  fb_hull_coupling c = {0, NULL, NULL};
  size_t node = 0;
  CHECK(fb_hull_coupling_build(&s, m, "SUSP_X", PX, PY, &c, &node, &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "SUSP_X: its coupling nodes lie on a line 0.039 m from it") != NULL);
  MUST(fb_hull_coupling_build(&s, m, "SUSP_X", 0.52, 0.5005, &c, &node, &err), &err);
  CHECK(c.n == 3);
  fb_hull_coupling_free(&c);
  CHECK(fb_hull_coupling_build(&s, m, "NOWHERE", 5.0, 5.0, &c, &node, &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "no node of the element set 'PLATE' lies within 0.08 m") != NULL);
  fb_mesh_free(&m);
}

int main(void)
{
  test_distributing();
  test_kinematic();
  test_line();
  return check_report("test_coupling");
}
