/* SPDX-License-Identifier: BSD-3-Clause */
/* Mounted rigid bodies in the assembled System 1 vehicle: a body that
 * sits on its one bushing and is held only vertically in the way the
 * mount is (its other motions undriven) rides as the paper's 1-DOF
 * driver mount does; and a seat on a turret on the hull keeps the
 * vehicle's energy balance with their bushings undamped. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "energy_balance.h"
#include "vehicle_util.h"

/* The six-degree-of-freedom hull needs the rest of its inertia tensor:
 * the yaw inertia of a box of the hull's mass and plan (5.1 m by 2.1 m),
 * m (a^2 + b^2) / 12; no products. Yaw is never driven by a vertical
 * road, so its value only has to be plausible. */
static void give_hull_izz(fb_scenario *s)
{
  s->hull_izz_given = 1;
  s->hull_izz = s->hull_mass * (5.1 * 5.1 + 2.1 * 2.1) / 12.0;
  s->hull_ixy = s->hull_ixz = s->hull_iyz = 0.0;
}

/* The driver's mount of s as a rigid body at its point, at the hull's
 * centre of mass height (so that no hull roll or pitch moves the point
 * sideways): the same vertical spring and damper, horizontal springs
 * that nothing drives (the hull's surge, sway and yaw stay at rest), and
 * rotational springs to a rotational inertia a million times below the
 * hull's. Its acceleration output keeps the mount's name. */
static fb_scenario *driver_as_body(const fb_scenario *base)
{
  fb_err err;
  fb_scenario *s = NULL;
  REQUIRE(fb_scenario_clone(base, &s, &err), &err);
  const long d = fb_scenario_mount_find(s, "driver");
  CHECK(d >= 0);
  const fb_mount m = s->mount[d];
  /* System 2 would couple it to the floor's load points (System 1 reads
   * no node set). */
  fb_bushing u = {.x = m.x, .y = m.y, .z = 0.0, .node_set = "LOAD"};
  const double k[6] = {1e5, 1e5, m.stiffness, 1e3, 1e3, 1e3};
  const double c[6] = {0, 0, m.damping, 0, 0, 0};
  fb_bushing_set_diagonal(&u, k, c);
  fb_body b = {.name = "driver",
               .mass = m.mass,
               .x = m.x,
               .y = m.y,
               .z = 0.0,
               .ixx = 1e-3,
               .iyy = 1e-3,
               .izz = 1e-3,
               .bushing = &u,
               .nbushings = 1};
  free(s->mount[d].name);
  memmove(&s->mount[d], &s->mount[d + 1], (s->nmounts - (size_t)d - 1) * sizeof *s->mount);
  --s->nmounts;
  REQUIRE(fb_scenario_add_body(s, &b, &err), &err);
  give_hull_izz(s);
  for (size_t o = 0; o < s->noutputs; ++o)
    if (s->output[o].of && !strcmp(s->output[o].of, "driver") &&
        !strcmp(s->output[o].signal, "acc")) {
      free(s->output[o].signal);
      s->output[o].signal = strdup("body_acc_z");
    }
  REQUIRE(fb_scenario_check(s, &err), &err);
  return s;
}

/* Every output of the mount's run against the body's, column by column
 * by name: the largest difference over the output's range. The two
 * models differ by the body's rotational inertia (2.4e-7 of the hull's
 * roll inertia) and by the integrator's steps over different state
 * vectors, whose local error is held to rtol 1e-6 of each state (the
 * differences measured: 2e-6 to 4e-6 of each range). 2e-5 of a signal's
 * range is a few times that and would show any misplaced force (a lever
 * arm, a sign), which moves the outputs by percents. */
static void test_mount_equivalence(void)
{
  fb_scenario *s = load_short();
  fb_scenario *b = driver_as_body(s);
  fb_result *rm = simulate_rigid(s), *rb = simulate_rigid(b);
  CHECK(rm && rb);
  size_t compared = 0;
  for (size_t o = 0; rm && rb && o < s->noutputs; ++o) {
    const char *name = s->output[o].name;
    const long cm = fb_result_find(rm, name), cb = fb_result_find(rb, name);
    CHECK(cm > 0 && cb > 0);
    if (cm <= 0 || cb <= 0)
      continue;
    double worst = 0.0;
    for (size_t k = 0; k < fb_result_nsamples(rm) && k < fb_result_nsamples(rb); ++k)
      worst = fmax(worst, fabs(fb_result_row(rm, k)[cm] - fb_result_row(rb, k)[cb]));
    const double range = result_range(rm, (size_t)cm);
    fprintf(stderr, "  %-20s worst difference %.3g (its range %.6g)\n", name, worst, range);
    CHECK(worst <= 2e-5 * range);
    ++compared;
  }
  CHECK(compared == s->noutputs && compared > 0);
  fb_result_free(&rm);
  fb_result_free(&rb);
  fb_scenario_free(&b);
  fb_scenario_free(&s);
}

/* A turret on two roof-ring bushings above the hull's centre of mass, a
 * seat on the turret; undamped bushings. The vehicle's energy balance
 * (energy_balance.h: work of every source = dissipation + storage
 * change, the bodies' inertias and bushing springs among the storages)
 * closes to 1e-7 of the work scale at rtol 1e-9, test_contact.c's bound:
 * a body port's power that the graph lost or made would break it. */
static void test_turret_seat_energy(void)
{
  fb_err err;
  fb_scenario *s = load_short();
  give_hull_izz(s);
  fb_bushing ring[2] = {{.x = 0.9, .y = 0.3, .z = 0.8, .surface = "ROOF", .radius = 1.2},
                        {.x = 0.1, .y = -0.3, .z = 0.8, .surface = "ROOF", .radius = 1.2}};
  const double kr[6] = {2e6, 2e6, 4e6, 2e5, 2e5, 2e5}, none[6] = {0};
  fb_bushing_set_diagonal(&ring[0], kr, none);
  fb_bushing_set_diagonal(&ring[1], kr, none);
  const fb_body turret = {.name = "turret",
                          .mass = 900,
                          .x = 0.5,
                          .z = 1.1,
                          .ixx = 300,
                          .iyy = 350,
                          .izz = 400,
                          .ixy = 5,
                          .ixz = -8,
                          .bushing = ring,
                          .nbushings = 2};
  fb_bushing post = {.x = 0.6, .y = 0.2, .z = 1.0};
  const double ks[6] = {4e4, 4e4, 3e4, 5e3, 5e3, 5e3};
  fb_bushing_set_diagonal(&post, ks, none);
  const fb_body seat = {.name = "seat",
                        .parent = "turret",
                        .mass = 110,
                        .x = 0.6,
                        .y = 0.2,
                        .z = 1.3,
                        .ixx = 8,
                        .iyy = 8,
                        .izz = 4,
                        .bushing = &post,
                        .nbushings = 1};
  REQUIRE(fb_scenario_add_body(s, &turret, &err), &err);
  REQUIRE(fb_scenario_add_body(s, &seat, &err), &err);
  REQUIRE(fb_scenario_check(s, &err), &err);
  energy_report rep;
  REQUIRE(energy_balance_rigid(s, 1e-9, &rep, &err), &err);
  CHECK(rep.work_scale > 100.0 && rep.nstorage > 0);
  CHECK(rep.worst <= 1e-7 * rep.work_scale);
  fb_scenario_free(&s);
}

/* The animation of a hull in six degrees of freedom: a node at an
 * attachment point (the corners', on the floor at the centre of mass's
 * height here, a mesh of their points) moves vertically as the point
 * does; both are integrals of one velocity over the same steps, equal to
 * round-off (1e-9 of the largest motion bounds it). */
static void test_motion(void)
{
  fb_err err;
  fb_scenario *base = load_short();
  fb_scenario *s = driver_as_body(base);
  fb_vehicle_opts o;
  fb_vehicle_opts_default(&o);
  o.motion = 1;
  fb_vehicle *v = NULL;
  fb_result *r = NULL;
  fb_vehicle_motion *m = NULL;
  REQUIRE(fb_vehicle_new(s, FB_SYSTEM_RIGID, &o, &v, &err), &err);
  REQUIRE(fb_vehicle_run(v, NULL, NULL, NULL, &r, &m, &err), &err);
  CHECK(m->ncoords == 6);
  fb_mesh *mesh = NULL;
  REQUIRE(fb_mesh_new(&mesh, &err), &err);
  for (size_t c = 0; c < s->ncorners; ++c) {
    size_t index = 0;
    REQUIRE(
        fb_mesh_add_node(mesh, (long)c + 1, s->corner[c].x, s->corner[c].y, 0.0, &index, &err),
        &err);
  }
  const size_t na = fb_scenario_nattach(s);
  double *u = malloc(6 * s->ncorners * sizeof *u), *dz = malloc(na * sizeof *dz);
  double worst = 0.0, big = 0.0;
  for (size_t i = 0; i < 60; ++i) {
    REQUIRE(fb_vehicle_motion_at(m, mesh, 0.05 * (double)i, u, dz, NULL, NULL, &err), &err);
    for (size_t c = 0; c < s->ncorners; ++c) {
      worst = fmax(worst, fabs(u[6 * c + 2] - dz[c]));
      big = fmax(big, fabs(dz[c]));
    }
  }
  CHECK(big > 0.01 && worst <= 1e-9 * big);
  free(u);
  free(dz);
  fb_mesh_free(&mesh);
  fb_vehicle_motion_free(&m);
  fb_result_free(&r);
  fb_vehicle_free(&v);
  fb_scenario_free(&s);
  fb_scenario_free(&base);
}

int main(void)
{
  test_mount_equivalence();
  test_motion();
  test_turret_seat_energy();
  return check_report(__FILE__);
}
