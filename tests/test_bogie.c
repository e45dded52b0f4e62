/* SPDX-License-Identifier: BSD-3-Clause */
/* The walking-beam bogie fragment (fb_vehicle_bogie) against hand
 * derivations, on a rig: a hull mass M_h under its weight on the bogie's
 * "hull" port, both roads still (zero-velocity sources):
 *   1. the static wheel loads: the pivot carries P = (M_h + m_b) g and
 *      shares it b/(a+b) to the front wheel and a/(a+b) to the rear (the
 *      beam's moments about the pivot), each wheel adding its own weight;
 *      the pivot's spring carries M_h g;
 *   2. the beam's pitch frequency of a symmetric bogie (a = b, equal
 *      wheels and tires, no damping) against the closed form
 *      w^2 = k_t (a^2 + b^2) / I, I the beam's and wheels' pitch inertia
 *      about the pivot: by symmetry the pitch moves neither the pivot nor
 *      the hull, so it is the pitch of a fixed pivot;
 *   3. the energy balance with damping off: from rest with gravity on at
 *      t = 0, the stored energy's change equals the weights' work. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle_util.h"

static const double G = 9.81, MH = 3000.0;

/* A wheel and its linear tire (no damping unless tire_c). */
static fb_corner_params wheel(double mass, double tire_k, double tire_c)
{
  return (fb_corner_params){
      .name = "w", .wheel_mass = mass, .tire_k = tire_k, .tire_c = tire_c, .motion_ratio = 1};
}

static int add_const_source(fb_bg *bg, const char *name, fb_bg_kind kind, double v, fb_err *err)
{
  fb_tfun *f = NULL;
  int rc = fb_tfun_new_const(v, &f, err);
  return rc ? rc : fb_bg_add_source(bg, name, kind, 1, &f, err);
}

/* The rig around the bogie: the hull mass "hull" on the 1-junction "Jh"
 * with its weight, the roads' sources. */
static fb_bg *rig(const fb_bogie_params *p, const fb_corner_params *front,
                  const fb_corner_params *rear)
{
  fb_err err;
  fb_bg *bg = NULL, *frag = NULL;
  REQUIRE(fb_bg_new("rig", &bg, &err), &err);
  REQUIRE(fb_vehicle_bogie(p, front, rear, G, &frag, &err), &err);
  REQUIRE(fb_bg_adopt(bg, &frag, "bogie", &err), &err);
  fb_mat *m = NULL;
  const size_t one = 1;
  REQUIRE(fb_mat_new_scaled_identity(1, MH, &m, &err), &err);
  REQUIRE(fb_bg_add_field(bg, "hull", FB_BG_I, 1, &one, &m, &err), &err);
  REQUIRE(fb_bg_add_junction(bg, "Jh", FB_BG_J1, 1, &err), &err);
  REQUIRE(add_const_source(bg, "hull_weight", FB_BG_SE, -MH * G, &err), &err);
  REQUIRE(add_const_source(bg, "road_front", FB_BG_SF, 0.0, &err), &err);
  REQUIRE(add_const_source(bg, "road_rear", FB_BG_SF, 0.0, &err), &err);
  static const char *const bonds[][3] = {
      {"b_hull", "Jh", "hull"},
      {"b_hull_weight", "hull_weight", "Jh"},
      {"b_mount", "bogie.hull", "Jh"},
      {"b_road_front", "road_front", "bogie.road_front"},
      {"b_road_rear", "road_rear", "bogie.road_rear"},
  };
  for (size_t i = 0; i < sizeof bonds / sizeof bonds[0]; ++i)
    REQUIRE(fb_bg_connect(bg, bonds[i][0], bonds[i][1], bonds[i][2], &err), &err);
  return bg;
}

/* Its static state (x_eq, nstates of bd, new). */
static double *at_rest(fb_bd *bd)
{
  fb_err err;
  const size_t n = fb_bd_nstates(bd);
  double *x0 = calloc(n, sizeof *x0), *x = calloc(n, sizeof *x);
  CHECK(x0 && x);
  REQUIRE(fb_sim_static_state(bd, 0.0, x0, x, &err), &err);
  free(x0);
  return x;
}

/* A bogie with its pivot off centre, its pivot's damping c. */
static fb_bogie_params unequal(double c)
{
  return (fb_bogie_params){.a = 0.55,
                           .b = 0.75,
                           .beam_mass = 180,
                           .beam_inertia = 40,
                           .spring_k = 4e5,
                           .damper_c = c};
}

/* ---- 1. Static wheel loads of an unequal bogie. */
static void test_static_split(void)
{
  const fb_bogie_params p = unequal(2e4);
  const fb_corner_params f = wheel(220, 9e5, 2000), r = wheel(260, 1.1e6, 2500);
  fb_bg *bg = rig(&p, &f, &r);
  static const fb_probe_spec probes[] = {
      {"front", FB_PROBE_EFFORT, "bogie.front.b_tire", -1, 0, 1.0, NULL, NULL, 0},
      {"rear", FB_PROBE_EFFORT, "bogie.rear.b_tire", -1, 0, 1.0, NULL, NULL, 0},
      {"spring", FB_PROBE_EFFORT, "bogie.b_spring", -1, 0, 1.0, NULL, NULL, 0},
  };
  fb_err err;
  fb_bd *bd = NULL;
  REQUIRE(fb_bd_build(bg, probes, 3, &bd, &err), &err);
  double *x = at_rest(bd);
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 0.01;
  o.x0 = x;
  fb_result *res = NULL;
  REQUIRE(fb_sim_run(bd, &o, &res, &err), &err);
  const double *row = fb_result_row(res, 0);
  const double P = (MH + p.beam_mass) * G, ab = p.a + p.b;
  const double hand[3] = {P * p.b / ab + f.wheel_mass * G, P * p.a / ab + r.wheel_mass * G,
                          MH * G};
  fprintf(stderr,
          "static: front %.10g N (hand %.10g), rear %.10g N (hand %.10g), spring %.10g N "
          "(hand %.10g)\n",
          row[1], hand[0], row[2], hand[1], row[3], hand[2]);
  /* A linear static solve (Newton on a linear system) of ~10 states:
   * 1e-9 of the load covers its residual test and rounding, while the
   * split reversed (a/(a+b) to the front) is off by 8 % of P. */
  for (int i = 0; i < 3; ++i)
    CHECK_NEAR(row[1 + i], hand[i], 1e-9 * P);
  fb_result_free(&res);
  free(x);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* ---- 2. Pitch of a symmetric bogie, undamped. */
static void test_pitch_frequency(void)
{
  const double a = 0.65, kt = 1e6, mw = 240, jb = 60;
  const fb_bogie_params p = {
      .a = a, .b = a, .beam_mass = 180, .beam_inertia = jb, .spring_k = 4e5, .damper_c = 0};
  const fb_corner_params w = wheel(mw, kt, 0);
  fb_bg *bg = rig(&p, &w, &w);
  fb_err err;
  fb_bd *bd = NULL;
  REQUIRE(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  double *x = at_rest(bd);
  fb_bd_eigen *e = NULL;
  REQUIRE(fb_bd_eigen_new(bd, 0.0, x, 0, "bogie", &e, &err), &err);
  const double inertia = jb + 2 * mw * a * a;
  const double omega = sqrt(kt * 2 * a * a / inertia);
  double best = INFINITY;
  for (size_t i = 0; i < e->n; ++i)
    best = fmin(best, fabs(e->im[i] - omega));
  fprintf(stderr, "pitch: closed form %.10g rad/s, nearest eigenvalue off by %.3g rad/s\n",
          omega, best);
  /* Eigenvalues of a ~10-state Jacobian by LAPACK: 1e-9 relative is far
   * above their rounding; the wheels' inertia left out (jb alone) would
   * move omega by a factor 4. */
  CHECK(best <= 1e-9 * omega);
  fb_bd_eigen_free(&e);
  free(x);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* ---- 3. Energy balance, damping off: the weights' work (integrated power
 * of their sources) against the change of the energy stored in the hull,
 * the beam, the pivot's spring and the two tires; the roads' sources do
 * no work (zero velocity). */
static void test_energy(void)
{
  const fb_bogie_params p = unequal(0);
  const fb_corner_params f = wheel(220, 9e5, 0), r = wheel(260, 1.1e6, 0);
  fb_bg *bg = rig(&p, &f, &r);
  static const fb_probe_spec probes[] = {
      {"w_hull", FB_PROBE_POWER, "b_hull_weight", -1, 1, 1.0, NULL, NULL, 0},
      {"w_front", FB_PROBE_POWER, "bogie.front.b_weight", -1, 1, 1.0, NULL, NULL, 0},
      {"w_rear", FB_PROBE_POWER, "bogie.rear.b_weight", -1, 1, 1.0, NULL, NULL, 0},
      /* The beam weight's pitch component is zero: its bounce component. */
      {"w_beam", FB_PROBE_POWER, "bogie.b_beam_weight", 0, 1, 1.0, NULL, NULL, 0},
      {"e_hull", FB_PROBE_ENERGY, "hull", -1, 0, 1.0, NULL, NULL, 0},
      {"e_beam", FB_PROBE_ENERGY, "bogie.beam", -1, 0, 1.0, NULL, NULL, 0},
      {"e_spring", FB_PROBE_ENERGY, "bogie.spring", -1, 0, 1.0, NULL, NULL, 0},
      {"e_front", FB_PROBE_ENERGY, "bogie.front.tire_spring", -1, 0, 1.0, NULL, NULL, 0},
      {"e_rear", FB_PROBE_ENERGY, "bogie.rear.tire_spring", -1, 0, 1.0, NULL, NULL, 0},
  };
  const size_t n = sizeof probes / sizeof probes[0];
  fb_err err;
  fb_bd *bd = NULL;
  REQUIRE(fb_bd_build(bg, probes, n, &bd, &err), &err);
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 2.0;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  o.sample_rate = 500;
  fb_result *res = NULL;
  REQUIRE(fb_sim_run(bd, &o, &res, &err), &err);
  CHECK(fb_result_ncols(res) == 1 + n);
  double worst = 0, scale = 0;
  const double *first = fb_result_row(res, 0);
  for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
    const double *row = fb_result_row(res, k);
    double work = 0, stored = 0;
    for (size_t j = 1; j <= 4; ++j)
      work += row[j];
    for (size_t j = 5; j <= n; ++j)
      stored += row[j] - first[j];
    worst = fmax(worst, fabs(work - stored));
    scale = fmax(scale, fabs(work));
  }
  fprintf(stderr, "energy: worst |work - stored change| %.3g J of %.6g J\n", worst, scale);
  /* Every stored energy is an exact function of the states; the work is
   * an integral CVODE carries with its other states to ~rtol of its size:
   * 1e-7 of the scale is 1000 rtol, while a weight at the wrong point (a
   * wheel's at the pivot) breaks the balance by the pitch's share of the
   * work, ~1e-2. */
  CHECK(scale > 10.0);
  CHECK(worst <= 1e-7 * scale);
  fb_result_free(&res);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

int main(void)
{
  test_static_split();
  test_pitch_frequency();
  test_energy();
  return check_report(__FILE__);
}
