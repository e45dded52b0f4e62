/* SPDX-License-Identifier: BSD-3-Clause */
/* Outputs read from the hull's motion (docs/vehicle-outputs.md, "The
 * hull's motion"): the small rigid motion's rows against the cross
 * product written out; a point's shape functions on a quadrilateral and a
 * triangle against their hand-computed values; a rigid motion of a
 * distorted shell read exactly at points on and off its plates; a point
 * off the hull refused at its key; the rigid fit returning a rigid
 * motion exactly and ignoring what is M-orthogonal to it; and System 1
 * against System 2 on a stiff hull, their difference falling as 1 / E. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "test_shell_util.h"
#include "vehicle/vehicle_internal.h"
#include "vehicle_util.h"

/* u = t + theta x r written out, against the rows times (t, theta): the
 * same products in another order, equal to a few roundings of 1e-17. */
static void test_rigid_rows(void)
{
  const double r[3] = {0.7, -1.3, 0.4};
  const double q[6] = {0.01, -0.02, 0.03, 0.002, -0.003, 0.004};
  const double *t = q, *th = q + 3;
  const double want[3] = {t[0] + th[1] * r[2] - th[2] * r[1],
                          t[1] + th[2] * r[0] - th[0] * r[2],
                          t[2] + th[0] * r[1] - th[1] * r[0]};
  double rows[18];
  vehicle_rigid_rows(r, rows);
  for (int i = 0; i < 3; ++i) {
    double u = 0.0;
    for (int j = 0; j < 6; ++j)
      u += rows[6 * i + j] * q[j];
    CHECK_NEAR(u, want[i], 1e-16);
  }
  /* System 1's vertical row over (z, phi, theta) is [1, y, -x]. */
  CHECK(rows[14] == 1.0 && rows[15] == r[1] && rows[16] == -r[0]);
}

static fb_mesh *one_element(fb_elem_type type, const double (*xyz)[3])
{
  fb_err err;
  fb_mesh *m = NULL;
  MUST(fb_mesh_new(&m, &err), &err);
  const int nn = type == FB_ELEM_QUAD4 ? 4 : 3;
  size_t nodes[4];
  for (int i = 0; m && i < nn; ++i)
    MUST(fb_mesh_add_node(m, i + 1, xyz[i][0], xyz[i][1], xyz[i][2], &nodes[i], &err), &err);
  if (m)
    MUST(fb_mesh_add_element(m, 1, type, nodes, &err), &err);
  return m;
}

/* The weights of a point's uz on one element are its shape functions:
 * on the 2 x 1 rectangle at (0.5, 0.25), xi = eta = -1/2, N = (1 -+ 1/2)
 * (1 -+ 1/2) / 4 = 9/16, 3/16, 1/16, 3/16; on the unit right triangle at
 * (0.2, 0.3) its area coordinates 0.5, 0.2, 0.3. One Gauss-Newton step
 * finds a flat element's point: to rounding. */
static void test_shape_values(void)
{
  static const double quad[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  static const double tri[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  static const double nq[4] = {9.0 / 16, 3.0 / 16, 1.0 / 16, 3.0 / 16}, nt[3] = {0.5, 0.2, 0.3};
  const struct {
    fb_elem_type type;
    const double (*xyz)[3];
    double at[3];
    const double *n;
  } cases[2] = {{FB_ELEM_QUAD4, quad, {0.5, 0.25, 0}, nq},
                {FB_ELEM_TRI3, tri, {0.2, 0.3, 0}, nt}};
  for (int c = 0; c < 2; ++c) {
    fb_mesh *m = one_element(cases[c].type, cases[c].xyz);
    fb_output_spec o = {.at = {cases[c].at[0], cases[c].at[1], cases[c].at[2]}, .direction = 2};
    double w[24];
    fb_err err;
    MUST(vehicle_hull_point_weights(m, &o, 0, w, &err), &err);
    for (int i = 0; i < (int)cases[c].type; ++i) {
      CHECK_NEAR(w[6 * i + 2], cases[c].n[i], 1e-14);
      /* On the plate: no lever through the rotations (to rounding). */
      CHECK(fabs(w[6 * i + 3]) + fabs(w[6 * i + 4]) + fabs(w[6 * i + 5]) < 1e-15);
    }
    fb_mesh_free(&m);
  }
}

/* A rigid motion of every node (translation t + theta x x_i, rotation
 * theta) into u (6 nnodes). */
static void rigid_field(const fb_mesh *m, const double *q, double *u)
{
  for (size_t i = 0; i < fb_mesh_nnodes(m); ++i) {
    double rows[18];
    vehicle_rigid_rows(fb_mesh_node_xyz(m, i), rows);
    for (int k = 0; k < 3; ++k) {
      u[6 * i + k] = 0.0;
      for (int j = 0; j < 6; ++j)
        u[6 * i + k] += rows[6 * k + j] * q[j];
      u[6 * i + 3 + k] = q[3 + k];
    }
  }
}

/* Two distorted faces of a box (a folded shell of quadrilaterals and one
 * of triangles) moving rigidly: every point read on it, on a plate or
 * 3 cm off it, moves by t + theta x p, to rounding of the unit-size
 * products (1e-14 of the motion); the foot of a point 3 cm off the
 * floor's middle is 3 cm away. */
static void test_rigid_interpolation(void)
{
  fb_err err;
  fb_mesh *m = NULL;
  MUST(fb_mesh_new(&m, &err), &err);
  if (!m)
    return;
  const double o[3] = {0, 0, 0}, dx[3] = {2, 0, 0}, dy[3] = {0, 1, 0}, dz[3] = {0, 0, 0.8};
  shell_face(m, o, dx, dy, 4, 3, 0, 0.25);
  shell_face(m, o, dx, dz, 4, 2, 1, 0.25);
  const double q[6] = {0.01, -0.02, 0.03, 0.02, -0.03, 0.04};
  const size_t ndof = 6 * fb_mesh_nnodes(m);
  double *u = malloc(ndof * sizeof *u), *w = malloc(ndof * sizeof *w);
  CHECK(u && w);
  rigid_field(m, q, u);
  static const double points[][3] = {{0.37, 0.61, 0.0},
                                     {1.5, 0.2, 0.0},
                                     {1.1, 0.0, 0.33},
                                     {0.9, 0.5, 0.03},
                                     {1.2, -0.03, 0.5}};
  for (size_t p = 0; u && w && p < sizeof points / sizeof points[0]; ++p) {
    double rows[18];
    vehicle_rigid_rows(points[p], rows);
    for (int dir = 0; dir < 3; ++dir) {
      fb_output_spec out = {.at = {points[p][0], points[p][1], points[p][2]}, .direction = dir};
      MUST(vehicle_hull_point_weights(m, &out, p, w, &err), &err);
      double got = 0.0, want = 0.0;
      for (size_t k = 0; k < ndof; ++k)
        got += w[k] * u[k];
      for (int j = 0; j < 6; ++j)
        want += rows[6 * dir + j] * q[j];
      CHECK_NEAR(got, want, 1e-14);
    }
  }
  size_t e = 0;
  double n[4], foot[3];
  const double above[3] = {1.0, 0.5, 0.03};
  CHECK_NEAR(vehicle_hull_point_nearest(m, above, &e, n, foot), 0.03, 1e-12);
  free(u);
  free(w);
  fb_mesh_free(&m);
}

/* A point 0.1 m off the plate: refused about the output's `at`, naming
 * the distance. */
static void test_off_hull(void)
{
  static const double quad[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  fb_mesh *m = one_element(FB_ELEM_QUAD4, quad);
  fb_output_spec o = {.at = {1.0, 0.5, 0.1}, .direction = 0};
  double w[24];
  fb_err err;
  CHECK(vehicle_hull_point_weights(m, &o, 3, w, &err) == FB_EINVAL);
  CHECK(err.part.kind == FB_PART_OUTPUT && err.part.index == 3 &&
        !strcmp(err.part.field, "at"));
  CHECK(strstr(err.msg, "0.1 m from the hull's nearest element") != NULL);
  fb_mesh_free(&m);
}

/* The rigid fit of a rigid motion is the motion, and adding a field
 * M-orthogonal to every rigid motion (an elastic one) changes nothing:
 * to rounding of the 6 x 6 solve (1e-12 of the unit-size coordinates). */
static void test_rigid_fit(void)
{
  fb_err err;
  fb_mesh *m = NULL;
  MUST(fb_mesh_new(&m, &err), &err);
  if (!m)
    return;
  const double o[3] = {-1, -0.5, -0.3}, dx[3] = {2, 0, 0}, dy[3] = {0, 1, 0},
               dz[3] = {0, 0, 0.8};
  shell_face(m, o, dx, dy, 4, 2, 0, 0.2);
  shell_face(m, o, dx, dz, 4, 2, 1, 0.2);
  shell_face(m, o, dy, dz, 2, 2, 0, 0.0);
  static const fb_shell_props steel = {200e9, 0.3, 7860.0, 0.0085, 0.0, 0.0};
  fb_mat *K = NULL, *M = NULL;
  MUST(fb_fem_assemble(m, &steel, FB_MASS_CONSISTENT, &K, &M, &err), &err);
  const size_t ndof = 6 * fb_mesh_nnodes(m);
  double *u = malloc(ndof * sizeof *u), *w = malloc(6 * ndof * sizeof *w);
  double *v = malloc(ndof * sizeof *v), *mv = malloc(ndof * sizeof *mv);
  CHECK(u && w && v && mv);
  const double q[6] = {0.01, -0.02, 0.03, 0.002, -0.003, 0.004};
  rigid_field(m, q, u);
  for (int k = 0; M && u && w && k < 6; ++k) {
    MUST(vehicle_hull_rigid_fit(m, M, k, w + (size_t)k * ndof, &err), &err);
    double a = 0.0;
    for (size_t i = 0; i < ndof; ++i)
      a += w[(size_t)k * ndof + i] * u[i];
    CHECK_NEAR(a, q[k], 1e-12);
  }
  /* v = x - R a(x), a(x) the fit: M-orthogonal to R by construction of
   * the weights (R' M v = R' M x - R' M R (R'MR)^-1 R' M x = 0); its fit
   * is then 0, and u + v's is q. */
  for (size_t i = 0; v && i < ndof; ++i)
    v[i] = sin(0.37 * (double)i) * 1e-3;
  double a[6], rigid[6];
  for (int k = 0; M && v && k < 6; ++k) {
    a[k] = 0.0;
    for (size_t i = 0; i < ndof; ++i)
      a[k] += w[(size_t)k * ndof + i] * v[i];
  }
  if (M && u && v && mv) {
    rigid_field(m, a, mv);
    for (size_t i = 0; i < ndof; ++i)
      v[i] += u[i] - mv[i];
    for (int k = 0; k < 6; ++k) {
      rigid[k] = 0.0;
      for (size_t i = 0; i < ndof; ++i)
        rigid[k] += w[(size_t)k * ndof + i] * v[i];
      CHECK_NEAR(rigid[k], q[k], 1e-12);
    }
  }
  free(u);
  free(w);
  free(v);
  free(mv);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mesh_free(&m);
}

static void add_output(fb_scenario *s, const char *signal, const double *at, int direction)
{
  fb_err err;
  fb_output_spec o = {.signal = (char *)signal, .direction = direction};
  if (at)
    memcpy(o.at, at, sizeof o.at);
  REQUIRE(fb_scenario_add_output(s, &o, &err), &err);
}

/* The reference vehicle (shortened crossing) with the hull's motions
 * recorded, its plates' Young's modulus young (Pa): System 1 and System 2
 * into *r1, *r2. */
static void run_both(const char *young, fb_result **r1, fb_result **r2)
{
  fb_err err;
  fb_scenario *s = NULL;
  const fb_scenario_override ov = {.key = "hull.material.young", .value = young};
  REQUIRE(fb_scenario_load_overrides("../examples/apc6x6.yaml", &ov, 1, &s, &err), &err);
  road_bump(s)->first_contact = 1.0;
  road_bump(s)->length = 0.5;
  s->t_end = 3.0;
  /* The driver's floor point (x, y of its mount; the generated floor's
   * z, 0.8631 m below the centre of mass). */
  const double floor_point[3] = {2.10, 0.55, -0.86306};
  add_output(s, "hull_bounce", NULL, 0);
  add_output(s, "hull_roll", NULL, 0);
  add_output(s, "hull_pitch", NULL, 0);
  add_output(s, "hull_displacement", floor_point, 2);
  REQUIRE(fb_vehicle_simulate(s, FB_SYSTEM_RIGID, r1, &err), &err);
  REQUIRE(fb_vehicle_simulate(s, FB_SYSTEM_FLEXIBLE, r2, &err), &err);
  fb_scenario_free(&s);
}

/* On a hull 1000 times stiffer than steel, System 2's rigid-body motions
 * (its mass-weighted rigid fit) and a floor point's displacement are
 * System 1's: the difference is the hull's elastic deflection, about 1 %
 * of the bounce at the paper's steel (System 2's reference run), so
 * 1e-5 of the range at 1000 times the stiffness: 1e-4 leaves a factor 10
 * for the products of inertia System 1 leaves out (the mesh's Ixz is 2 %
 * of Ixx) and the integrators' tolerances. And the difference of the
 * bounce, the pitch and the point is the elasticity: it falls with the
 * stiffness (a tenth of the stiffness, at least 3 times the difference;
 * 1 / E would give 10). The roll's, 2e-5 of its range at both, is not:
 * it is what System 1 leaves out (the product of inertia that couples
 * System 2's roll with its yaw) or the integrators' tolerance. */
static void test_stiff_hull(void)
{
  static const char *const names[] = {"hull_bounce", "hull_roll", "hull_pitch",
                                      "hull_displacement_z"};
  fb_result *a1 = NULL, *a2 = NULL, *b1 = NULL, *b2 = NULL;
  run_both("200e12", &a1, &a2);
  run_both("200e11", &b1, &b2);
  for (size_t k = 0; a1 && a2 && b1 && b2 && k < sizeof names / sizeof names[0]; ++k) {
    const double stiff = result_relative_difference(a1, a2, names[k]);
    const double softer = result_relative_difference(b1, b2, names[k]);
    printf("%s: System 2 - System 1 %.3g of the range at 1000 E, %.3g at 100 E\n", names[k],
           stiff, softer);
    CHECK(stiff < 1e-4);
    CHECK(k == 1 || softer > 3.0 * stiff);
  }
  fb_result_free(&a1);
  fb_result_free(&a2);
  fb_result_free(&b1);
  fb_result_free(&b2);
}

/* System 1's accelerations come from its equations of motion: at t = 0
 * (the vehicle at rest, springs unloaded) the hull carries its load
 * alone, the total weight through its centre of mass (the load points'
 * centroid is x = y = 0), so every point falls at W / m_hull (117720 N /
 * 4041.72 kg), to rounding; and over the run the velocity is the
 * acceleration's integral (the trapezoidal rule over the 1 ms samples,
 * whose error h^2 T max|a''| / 12 and h times each jump of a tire's
 * lift-off stay below 1e-3 of the velocity's range; 9e-5 measured). */
static void test_rigid_acceleration(void)
{
  fb_err err;
  fb_scenario *s = load_short();
  const double p[3] = {-1.3, 0.8, 0.4};
  add_output(s, "hull_velocity", p, 2);
  add_output(s, "hull_acceleration", p, 2);
  fb_result *r = NULL;
  REQUIRE(fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err), &err);
  const long v = fb_result_find(r, "hull_velocity_z"),
             a = fb_result_find(r, "hull_acceleration_z");
  CHECK(v > 0 && a > 0);
  CHECK_NEAR(fb_result_row(r, 0)[a], -117720.0 / 4041.72, 1e-9);
  const double range = result_range(r, (size_t)v);
  double integral = 0.0, worst = 0.0;
  for (size_t k = 1; k < fb_result_nsamples(r); ++k) {
    const double *lo = fb_result_row(r, k - 1), *hi = fb_result_row(r, k);
    integral += 0.5 * (hi[0] - lo[0]) * (lo[a] + hi[a]);
    worst = fmax(worst, fabs(hi[v] - fb_result_row(r, 0)[v] - integral));
  }
  printf("velocity - integral of the acceleration: %.3g of the range\n", worst / range);
  CHECK(worst < 1e-3 * range);
  fb_result_free(&r);
  fb_scenario_free(&s);
}

/* The reference vehicle (shortened crossing) with System 2's hull in
 * coordinates coords (hull.fe.coordinates) and modes (hull.fe.modes, NULL:
 * the file's), the driver's floor point's acceleration and the hull's
 * bounce recorded: its System 2 run. */
static fb_result *run_flexible(const char *coords, const char *modes)
{
  fb_err err;
  fb_scenario *s = NULL;
  const fb_scenario_override ov[2] = {{.key = "hull.fe.coordinates", .value = coords},
                                      {.key = "hull.fe.modes", .value = modes}};
  REQUIRE(fb_scenario_load_overrides("../examples/apc6x6.yaml", ov, modes ? 2 : 1, &s, &err),
          &err);
  road_bump(s)->first_contact = 1.0;
  road_bump(s)->length = 0.5;
  s->t_end = 3.0;
  const double floor_point[3] = {2.10, 0.55, -0.86306};
  add_output(s, "hull_acceleration", floor_point, 2);
  add_output(s, "hull_bounce", NULL, 0);
  fb_result *r = NULL;
  REQUIRE(fb_vehicle_simulate(s, FB_SYSTEM_FLEXIBLE, &r, &err), &err);
  fb_scenario_free(&s);
  return r;
}

/* Nodal coordinates weigh the effort on the mass by M^-1 w (a solve with
 * the nodal mass matrix's factor), modal ones with every mode by T' w (M
 * = I): the same model, so the same acceleration and the same rigid fit,
 * within the integrators' tolerances: 1e-4 of the range (measured 1e-5
 * for the acceleration, which the fastest modes reach first, 2e-8 for
 * the bounce). */
static void test_nodal_modal(void)
{
  fb_result *nodal = run_flexible("nodal", NULL), *modal = run_flexible("modal", "all");
  static const char *const names[] = {"hull_acceleration_z", "hull_bounce"};
  for (size_t k = 0; nodal && modal && k < 2; ++k) {
    const double d = result_relative_difference(nodal, modal, names[k]);
    printf("%s: nodal - modal (every mode) %.3g of the range\n", names[k], d);
    CHECK(d < 1e-4);
  }
  fb_result_free(&nodal);
  fb_result_free(&modal);
}

/* A hull point at a mount's attachment node moves as the attachment
 * point the mount's bond drives: hull_velocity_z there is the flow of the
 * assembly's multibond b_attach at that point (its component: the
 * corners', then the mounts'), in System 1 (the same rigid row) and in
 * System 2 (the node's shape function is 1 there, its uz the point's), to
 * rounding; and the component selector picks that one component. */
static void test_attach_point(void)
{
  fb_err err;
  fb_scenario *s = load_short();
  const double driver[3] = {2.10, 0.55, -0.86306};
  add_output(s, "hull_velocity", driver, 2);
  fb_output_spec o = {.signal = "flow", .bond = "b_attach", .component = 7};
  REQUIRE(fb_scenario_add_output(s, &o, &err), &err);
  CHECK(!strcmp(s->output[s->noutputs - 1].name, "flow_b_attach_7"));
  CHECK(!strcmp(s->mount[0].name, "driver") && s->ncorners == 6);
  for (int sys = 0; sys < 2; ++sys) {
    fb_result *r = NULL;
    REQUIRE(fb_vehicle_simulate(s, sys ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID, &r, &err), &err);
    const long v = fb_result_find(r, "hull_velocity_z"),
               f = fb_result_find(r, "flow_b_attach_7");
    CHECK(v > 0 && f > 0);
    const double range = result_range(r, (size_t)f);
    CHECK(range > 0.1);
    for (size_t k = 0; v > 0 && f > 0 && k < fb_result_nsamples(r); ++k)
      CHECK_NEAR(fb_result_row(r, k)[v], fb_result_row(r, k)[f], 1e-12 * range);
    fb_result_free(&r);
  }
  fb_scenario_free(&s);
}

int main(void)
{
  test_rigid_rows();
  test_shape_values();
  test_rigid_interpolation();
  test_off_hull();
  test_rigid_fit();
  test_rigid_acceleration();
  test_stiff_hull();
  test_nodal_modal();
  test_attach_point();
  return check_report("test_hull_outputs");
}
