/* SPDX-License-Identifier: BSD-3-Clause */
/* Mounted rigid bodies on System 2's finite-element hull: a turret on two
 * roof-ring bushings, each coupled to the roof's nodes around it by the
 * six-component distributing coupling, on a hull made 10^4 times
 * stiffer, rides as on System 1's rigid hull of the same mass, centre of
 * mass and inertia (the mesh's). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "energy_balance.h"
#include "vehicle_util.h"

/* The reference scenario with the turret, its hull's Young's moduli
 * times stiffen. */
static fb_scenario *with_turret(double stiffen)
{
  fb_err err;
  fb_scenario *s = load_short();
  s->young *= stiffen;
  for (size_t i = 0; i < s->nsections; ++i)
    s->section[i].young *= stiffen;
  fb_bushing ring[2] = {{.x = 0.9, .y = 0.3, .z = 0.8, .surface = "ROOF", .radius = 1.2},
                        {.x = 0.1, .y = -0.3, .z = 0.8, .surface = "ROOF", .radius = 1.2}};
  const double k[6] = {2e6, 2e6, 4e6, 2e5, 2e5, 2e5}, c[6] = {2e3, 2e3, 4e3, 200, 200, 200};
  fb_bushing_set_diagonal(&ring[0], k, c);
  fb_bushing_set_diagonal(&ring[1], k, c);
  const fb_body turret = {.name = "turret",
                          .mass = 900,
                          .x = 0.5,
                          .z = 1.1,
                          .ixx = 300,
                          .iyy = 350,
                          .izz = 400,
                          .bushing = ring,
                          .nbushings = 2};
  REQUIRE(fb_scenario_add_body(s, &turret, &err), &err);
  static const char *const signals[] = {"body_acc_z", "body_acc_pitch", "body_acc_roll",
                                        "body_acc_x"};
  for (size_t i = 0; i < sizeof signals / sizeof signals[0]; ++i) {
    const fb_output_spec o = {.signal = (char *)signals[i], .of = "turret"};
    REQUIRE(fb_scenario_add_output(s, &o, &err), &err);
  }
  /* System 1's hull: the mesh's mass and whole inertia tensor, so that
   * the two hulls differ by their elasticity alone. */
  fb_fe_hull *h = NULL;
  fb_hull_mass_props mp;
  REQUIRE(fb_vehicle_fe_hull(s, &h, &err), &err);
  REQUIRE(fb_fe_hull_mass_props(h, 0, &mp, &err), &err);
  fb_fe_hull_free(&h);
  fb_scenario_set_rigid_hull(s, mp.mass, mp.inertia[0], mp.inertia[4]);
  s->hull_izz_given = 1;
  s->hull_izz = mp.inertia[8];
  s->hull_ixy = -mp.inertia[1];
  s->hull_ixz = -mp.inertia[2];
  s->hull_iyz = -mp.inertia[5];
  REQUIRE(fb_scenario_check(s, &err), &err);
  return s;
}

/* Each output of System 2 against System 1's, the largest difference
 * over its range. What separates them: the stiffened hull's elastic
 * response, which falls as 1 / E (the roof's local bending under the
 * turret's vertical bushing load is the largest: turret_acc_z differs by
 * 3.6 % of its range with E x 100, 0.17 % with E x 10^4, measured), and
 * the modal basis's own error (about 1e-3 of a range,
 * FB_HULL_BLOCK_TOL). Measured with E x 10^4: at most 1.7e-3 (turret
 * z), 7e-4 (driver), below 1e-4 for the rest. 5e-3 of each range
 * bounds them, where a misplaced coupling (a lever arm, a sign, a
 * missing moment) changes the turret's rotations by tens of percent. */
static void test_rigid_limit(void)
{
  /* The rigid limit: the hull's elastic modes a hundred times higher
   * (frequencies grow as sqrt(E)). */
  fb_scenario *s = with_turret(1e4);
  fb_result *r1 = simulate_rigid(s), *r2 = NULL;
  fb_err err;
  REQUIRE(fb_vehicle_simulate(s, FB_SYSTEM_FLEXIBLE, &r2, &err), &err);
  for (size_t o = 0; r1 && r2 && o < s->noutputs; ++o) {
    const char *name = s->output[o].name;
    const long c1 = fb_result_find(r1, name), c2 = fb_result_find(r2, name);
    CHECK(c1 > 0 && c2 > 0);
    if (c1 <= 0 || c2 <= 0 || !strcmp(name, "torsion"))
      continue;
    double worst = 0.0;
    for (size_t k = 0; k < fb_result_nsamples(r1) && k < fb_result_nsamples(r2); ++k)
      worst = fmax(worst, fabs(fb_result_row(r1, k)[c1] - fb_result_row(r2, k)[c2]));
    const double range = result_range(r1, (size_t)c1);
    fprintf(stderr, "  %-22s System 2 - System 1: %.3g of its range %.6g\n", name,
            worst / range, range);
    CHECK(range > 0 && worst <= 5e-3 * range);
  }
  fb_result_free(&r1);
  fb_result_free(&r2);
  fb_scenario_free(&s);
}

/* The energy balance of System 2 with the turret (energy_balance.h):
 * the couplings are transformers, so the power the bushings put into the
 * hull's coordinates is the power they take from the turret; the balance
 * closes as System 1's does (test_body_vehicle.c: 1e-7 of the work scale
 * at rtol 1e-9), in modal and in nodal coordinates (the rows as they
 * are). */
static void test_energy(fb_hull_coordinates coordinates)
{
  fb_err err;
  fb_scenario *s = with_turret(1.0);
  s->hull_coordinates = coordinates;
  fb_hull *hull = NULL;
  energy_report rep;
  REQUIRE(fb_vehicle_flexible_hull(s, NULL, &hull, &err), &err);
  REQUIRE(energy_balance(s, &hull, 1e-9, &rep, &err), &err);
  CHECK(rep.work_scale > 100.0 && rep.worst <= 1e-7 * rep.work_scale);
  fb_scenario_free(&s);
}

/* System 2's undamped modes with shapes (fb_vehicle_structural_modes:
 * the vehicle's matrices with each body's inertia and bushings) in the
 * rigid limit against System 1's undamped linearised modes, the lowest
 * (up to twenty) by frequency: the same vehicle, so the same
 * frequencies, but for the hull's elasticity and the modal basis (see
 * test_rigid_limit). Measured: 15 modes, the hull's, the mounts', the
 * wheels' and five of the turret's, within 0.43 % (the turret's surge,
 * near the basis's band's top); 1 % bounds that, where a bushing's
 * missing moment or lever arm moves a turret mode by tens of percent
 * (and a mode taken for a free motion leaves a gap, shifting every one
 * after it). */
static void test_modes(void)
{
  fb_err err;
  fb_scenario *s = with_turret(1e4);
  fb_mode *m1 = NULL;
  size_t n1 = 0, nstatic = 0;
  REQUIRE(fb_vehicle_modes(s, FB_SYSTEM_RIGID, 1, &m1, &n1, &nstatic, &err), &err);
  fb_vehicle *v = NULL;
  fb_mode_set *m2 = NULL;
  REQUIRE(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, NULL, &v, &err), &err);
  REQUIRE(fb_vehicle_structural_modes(v, 20, 0, &m2, &err), &err);
  CHECK(n1 >= 12 && m2->nmodes >= 12);
  double worst = 0.0;
  for (size_t k = 0; k < 20 && k < n1 && k < m2->nmodes; ++k) {
    const double d = fabs(m2->freq_hz[k] / m1[k].freq_hz - 1.0);
    fprintf(stderr, "  mode %2zu: System 1 %8.4f Hz (%s), System 2 %8.4f Hz (%s)\n", k + 1,
            m1[k].freq_hz, m1[k].description, m2->freq_hz[k], m2->description[k]);
    worst = fmax(worst, d);
  }
  fprintf(stderr, "  worst relative difference %.3g\n", worst);
  CHECK(worst <= 1e-2);
  /* A mode the turret holds the most of is the turret's part, a mounted
   * body after the mounts, with its share; and its picture is among those
   * chosen by what they are. */
  const size_t turret = s->nmounts + (size_t)fb_scenario_body_find(s, "turret");
  size_t held = m2->nmodes, chosen[FB_PICTURED_MODES_MAX];
  for (size_t k = 0; k < m2->nmodes && held == m2->nmodes; ++k)
    if (!strncmp(m2->description[k], "turret (", 8))
      held = k;
  CHECK(held < m2->nmodes && m2->nmounts == s->nmounts + s->nbodies);
  if (held < m2->nmodes) {
    CHECK(m2->part[held].kind == FB_MODE_MOUNT && m2->part[held].index == turret);
    CHECK(m2->mount_share[held * m2->nmounts + turret] > 0.5);
    const size_t n = fb_mode_set_pictured(m2, chosen, FB_PICTURED_MODES_MAX);
    int pictured = 0;
    for (size_t i = 0; i < n; ++i)
      pictured |= chosen[i] == held;
    CHECK(pictured);
  }
  fb_mode_set_free(&m2);
  fb_vehicle_free(&v);
  free(m1);
  fb_scenario_free(&s);
}

int main(void)
{
  test_modes();
  test_rigid_limit();
  test_energy(FB_HULL_MODAL);
  test_energy(FB_HULL_NODAL);
  return check_report(__FILE__);
}
