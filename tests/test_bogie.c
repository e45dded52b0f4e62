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
 *      t = 0, the stored energy's change equals the weights' work; and
 *      the bond b_pitch's displacement is the beam's pitch;
 * and in a vehicle (examples/truck6x6_bogie.yaml, its bogies' pivots moved
 * off centre):
 *   4. at rest each bogie's wheels share its pivot's load (its spring's
 *      force plus the beam's weight) b/(a+b) and a/(a+b);
 *   5. System 2's undamped modes (its own matrices over the wheels'
 *      displacements, fb_vehicle_matrices and the modal basis's) in the
 *      rigid limit against System 1's (the bond graph);
 *   5b. System 2's modes of a bogie labelled as System 1's, its beam's
 *      pitch at the closed form of 2.;
 *   6. the checks' refusals, each naming the bogie's member. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle_util.h"

static const double G = 9.81, MH = 3000.0, PI = 3.14159265358979323846;

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
 * with its weight, the roads' sources (the front road rising at
 * front_rise m/s, the rear one still). */
static fb_bg *rig_rising(const fb_bogie_params *p, const fb_corner_params *front,
                         const fb_corner_params *rear, double front_rise)
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
  REQUIRE(add_const_source(bg, "road_front", FB_BG_SF, front_rise, &err), &err);
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

static fb_bg *rig(const fb_bogie_params *p, const fb_corner_params *front,
                  const fb_corner_params *rear)
{
  return rig_rising(p, front, rear, 0.0);
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

/* ---- 2b. The sign of beam_pitch: the front road rising at u under a
 * bogie at rest lifts the front wheel by about u t while the rear one
 * stays, so the beam turns by -u t / (a + b) in the pitch of the hull's
 * axes (ISO 8855, about y: positive nose down, docs/reference-vehicle.md),
 * and the signal's documented meaning says so. */
static void test_pitch_sign(void)
{
  const fb_bogie_params p = unequal(2e4);
  const fb_corner_params f = wheel(220, 9e5, 2000), r = wheel(260, 1.1e6, 2500);
  const double u = 0.02, t_end = 1.0;
  fb_bg *bg = rig_rising(&p, &f, &r, u);
  static const fb_probe_spec probes[] = {
      {"pitch_rate", FB_PROBE_FLOW, "bogie.b_pitch", -1, 0, 1.0, NULL, NULL, 0},
  };
  fb_err err;
  fb_bd *bd = NULL;
  REQUIRE(fb_bd_build(bg, probes, 1, &bd, &err), &err);
  fb_bg *bg_still = rig(&p, &f, &r); /* its rest is the start */
  fb_bd *still = NULL;
  REQUIRE(fb_bd_build(bg_still, NULL, 0, &still, &err), &err);
  double *x = at_rest(still);
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = t_end;
  o.x0 = x;
  fb_result *res = NULL;
  REQUIRE(fb_sim_run(bd, &o, &res, &err), &err);
  /* beam_pitch is the pitch rate's integral (outputs.c): the
   * trapezoidal rule over the samples, the rate's integral to far below
   * the tolerance (its transient of ~9 Hz sampled many times a period). */
  double pitch = 0.0;
  for (size_t k = 1; k < fb_result_nsamples(res); ++k) {
    const double *a = fb_result_row(res, k - 1), *b = fb_result_row(res, k);
    pitch += 0.5 * (b[0] - a[0]) * (a[1] + b[1]);
  }
  const double hand = -u * t_end / (p.a + p.b);
  fprintf(stderr, "beam pitch after the front road rose %.3g m: %.6g rad (quasi-static %.6g)\n",
          u * t_end, pitch, hand);
  /* The tires' deflections change by the load the rise moves (a few
   * tenths of a millimetre against 20 mm) and the beam's transient on
   * them: 10 % of the rise; a sign reversed is off by 200 %. */
  CHECK_NEAR(pitch, hand, 0.1 * fabs(hand));
  const fb_output_kind *kind = fb_vehicle_output_kind_find("beam_pitch");
  CHECK(kind && strstr(kind->doc, "nose down positive") != NULL);
  fb_result_free(&res);
  free(x);
  fb_bd_free(&still);
  fb_bd_free(&bd);
  fb_bg_free(&bg_still);
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
      /* The beam's pitch and its wheels' displacements. */
      {"pitch", FB_PROBE_FLOW, "bogie.b_pitch", -1, 1, 1.0, NULL, NULL, 0},
      {"z_front", FB_PROBE_FLOW, "bogie.b_front", -1, 1, 1.0, NULL, NULL, 0},
      {"z_rear", FB_PROBE_FLOW, "bogie.b_rear", -1, 1, 1.0, NULL, NULL, 0},
  };
  const size_t n = sizeof probes / sizeof probes[0], nenergy = n - 3;
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
  double worst = 0, scale = 0, worst_pitch = 0, big_pitch = 0;
  const double *first = fb_result_row(res, 0);
  for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
    const double *row = fb_result_row(res, k);
    double work = 0, stored = 0;
    for (size_t j = 1; j <= 4; ++j)
      work += row[j];
    for (size_t j = 5; j <= nenergy; ++j)
      stored += row[j] - first[j];
    worst = fmax(worst, fabs(work - stored));
    scale = fmax(scale, fabs(work));
    /* b_pitch's displacement is the beam's pitch: (z_rear - z_front) /
     * (a + b) at every sample (three integrals CVODE carries to ~rtol of
     * the wheels' ~1e-2 m travel: 1e-9 rad). */
    const double pitch = row[n - 2], zf = row[n - 1], zr = row[n];
    worst_pitch = fmax(worst_pitch, fabs(pitch - (zr - zf) / (p.a + p.b)));
    big_pitch = fmax(big_pitch, fabs(pitch));
  }
  fprintf(stderr, "pitch: largest %.3g rad, worst departure from the wheels' %.3g rad\n",
          big_pitch, worst_pitch);
  CHECK(big_pitch > 1e-4 && worst_pitch <= 1e-9);
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

/* The 6x6 example with its bogies' pivots 0.25 m behind the middle of
 * their wheels (a = 0.9 m, b = 0.4 m). */
static fb_scenario *truck(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  REQUIRE(fb_scenario_load("../examples/truck6x6_bogie.yaml", &s, &err), &err);
  CHECK(s->nbogies == 2);
  for (size_t i = 0; i < s->nbogies; ++i)
    s->bogie[i].pivot_x -= 0.25;
  /* The example records the left bogie's pivot_force. */
  REQUIRE(fb_scenario_check(s, &err), &err);
  return s;
}

/* ---- 4. The lever in the vehicle: with the pivot's load P (spring force
 * plus beam weight), the front wheel's tire carries P b/(a+b) plus its
 * own weight and the rear one's P a/(a+b) plus its own. */
static void test_vehicle_split(void)
{
  fb_scenario *s = truck();
  fb_err err;
  fb_result *r = NULL;
  REQUIRE(fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err), &err);
  const fb_bogie *b = &s->bogie[0];
  const long f = fb_scenario_corner_find(s, b->front), rr = fb_scenario_corner_find(s, b->rear);
  const double a = s->corner[f].x - b->pivot_x, bb = b->pivot_x - s->corner[rr].x;
  const double *row = fb_result_row(r, 0);
  const double spring = row[fb_result_find(r, "pivot_force_left")];
  const double P = spring + b->beam_mass * s->gravity;
  const double front = row[fb_result_find(r, "tire_force_LM")];
  const double rear = row[fb_result_find(r, "tire_force_LR")];
  const double hand_f = P * bb / (a + bb) + s->corner[f].wheel_mass * s->gravity;
  const double hand_r = P * a / (a + bb) + s->corner[rr].wheel_mass * s->gravity;
  fprintf(stderr,
          "vehicle: pivot load %.10g N, LM %.10g N (hand %.10g), LR %.10g N (hand %.10g)\n", P,
          front, hand_f, rear, hand_r);
  /* The static solve's residual and rounding, as in test 1. */
  CHECK(spring > 1e3);
  CHECK_NEAR(front, hand_f, 1e-9 * P);
  CHECK_NEAR(rear, hand_r, 1e-9 * P);
  fb_result_free(&r);
  fb_scenario_free(&s);
}

/* ---- 5. System 2's modes in the rigid limit: the paper's 6x6 with its
 * middle and rear wheels on bogies (pivot 0.95 m behind the middle axle,
 * 0.45 m ahead of the rear one) and a hull 100 times stiffer has System
 * 1's frequencies (from the bond graph) to 5e-4, test_system2_modes.c's
 * bound for that vehicle without bogies (the hull's flexibility moves
 * them by ~1.3e-4 at 100 E); the bogies' bounce and pitch are among
 * them. */
static void test_system2_rigid_limit(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  REQUIRE(fb_scenario_load("../examples/apc6x6.yaml", &s, &err), &err);
  const fb_bogie left = {"left", "LM", "LR", -0.55, 150, 30, 6e5, 3e4};
  const fb_bogie right = {"right", "RM", "RR", -0.55, 150, 30, 6e5, 3e4};
  REQUIRE(fb_scenario_add_bogie(s, &left, &err), &err);
  REQUIRE(fb_scenario_add_bogie(s, &right, &err), &err);
  /* The bogies' wheels measure their tires only. */
  for (size_t i = 0; i < s->noutputs; ++i)
    if (s->output[i].of && (!strcmp(s->output[i].of, "LM") || !strcmp(s->output[i].of, "RM") ||
                            !strcmp(s->output[i].of, "LR") || !strcmp(s->output[i].of, "RR"))) {
      free(s->output[i].signal);
      s->output[i].signal = strdup("tire_force");
    }
  REQUIRE(fb_scenario_check(s, &err), &err);
  check_rigid_limit(s, 6);
  fb_scenario_free(&s);
}

/* ---- 5b. System 2's modes of a bogie carry the bogie's labels, as System
 * 1's beam does (fb_vehicle_bogie): in examples/truck6x6_bogie.yaml as it
 * is (a = b, equal wheels and tires), each beam's pitch moves neither its
 * pivot nor the hull (test 2's symmetry), so System 2 has it at the fixed
 * pivot's w^2 = k_t (a^2 + b^2) / (J + m_w (a^2 + b^2)), labelled
 * "bogie pitch <name>"; and no mode is called a hop of a bogie's wheel
 * (they ride on the beam). */
/* The band System 2's automatic basis must reach (fb_hull_excitation_hz)
 * on examples/truck6x6_bogie.yaml, by hand: a bogie's wheels ride on its
 * beam, so their corners' own springs (160 kN/m, which would give a hop
 * of 14.07 Hz) are not in it; the front wheels' hop, sqrt((90000 +
 * 700000) / 110) / 2 pi = 13.488 Hz, is the highest, above the bogies'
 * bounce, sqrt((320000 + 2 x 700000) / (120 + 2 x 110)) / 2 pi = 11.32 Hz,
 * their pitch (11.27 Hz) and the bump's 2 V / L = 7.4 Hz. */
static void test_band(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  REQUIRE(fb_scenario_load("../examples/truck6x6_bogie.yaml", &s, &err), &err);
  const double hop = sqrt((90000.0 + 700000.0) / 110.0) / (2.0 * PI);
  CHECK_NEAR(fb_hull_excitation_hz(s), hop, 1e-12 * hop);
  fb_scenario_free(&s);
}

static void test_system2_labels(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  REQUIRE(fb_scenario_load("../examples/truck6x6_bogie.yaml", &s, &err), &err);
  fb_vehicle *v = NULL;
  REQUIRE(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, NULL, &v, &err), &err);
  fb_mode_set *m = NULL;
  REQUIRE(fb_vehicle_structural_modes(v, 20, 0, &m, &err), &err);
  for (size_t i = 0; i < s->nbogies; ++i) {
    const fb_bogie *b = &s->bogie[i];
    const long f = fb_scenario_corner_find(s, b->front),
               r = fb_scenario_corner_find(s, b->rear);
    const double a = s->corner[f].x - b->pivot_x, bb = b->pivot_x - s->corner[r].x;
    const double l2 = a * a + bb * bb, mw = s->corner[f].wheel_mass;
    const double hz = sqrt(s->corner[f].tire_k * l2 / (b->beam_inertia + mw * l2)) / (2 * PI);
    char pitch[96], bounce[96];
    snprintf(pitch, sizeof pitch, "bogie pitch %s (", b->name);
    snprintf(bounce, sizeof bounce, "bogie bounce %s (", b->name);
    size_t npitch = 0, nbounce = 0;
    for (size_t k = 0; k < m->nmodes; ++k) {
      const int is_bogie = m->part[k].kind == FB_MODE_BOGIE && m->part[k].index == i;
      CHECK(is_bogie == (!strncmp(m->description[k], pitch, strlen(pitch)) ||
                         !strncmp(m->description[k], bounce, strlen(bounce))));
      nbounce += !strncmp(m->description[k], bounce, strlen(bounce));
      if (strncmp(m->description[k], pitch, strlen(pitch)))
        continue;
      ++npitch;
      fprintf(stderr, "%s: %.8g Hz, closed form %.8g Hz\n", m->description[k], m->freq_hz[k],
              hz);
      /* The reduced basis keeps the wheels' DOFs exactly and the pitch
       * leaves the hull at rest: only the eigen-solve's round-off, 1e-6
       * relative a wide margin above it. */
      CHECK_NEAR(m->freq_hz[k] / hz, 1.0, 1e-6);
    }
    CHECK(npitch == 1 && nbounce >= 1);
  }
  for (size_t k = 0; k < m->nmodes; ++k)
    CHECK(m->part[k].kind != FB_MODE_WHEEL ||
          fb_scenario_corner_bogie(s, m->part[k].index) < 0);
  fb_mode_set_free(&m);
  fb_vehicle_free(&v);
  fb_scenario_free(&s);
}

/* ---- 6. Refusals, each naming the bogie's member: the truck's first
 * bogie with other corners (blamed: the bogie the error is about). */
static void expect_refusal(const char *front, const char *rear, double pivot_dx, size_t blamed,
                           const char *member, const char *words)
{
  fb_err err;
  fb_scenario *s = truck();
  fb_bogie *b = &s->bogie[0];
  free(b->front);
  free(b->rear);
  b->front = strdup(front);
  b->rear = strdup(rear);
  b->pivot_x += pivot_dx;
  fb_err_clear(&err);
  const int rc = fb_scenario_check(s, &err);
  fprintf(stderr, "refused: %s\n", err.msg);
  CHECK(rc == FB_EINVAL);
  CHECK(PART_IS(&err, FB_PART_BOGIE, blamed, member));
  CHECK(strstr(err.msg, words) != NULL);
  fb_scenario_free(&s);
}

static void test_refusals(void)
{
  /* An output of a bogie the vehicle has not. */
  fb_err err;
  fb_scenario *s = truck();
  const fb_output_spec pitch = {.signal = "beam_pitch", .of = "left", .name = "pitch"};
  REQUIRE(fb_scenario_add_output(s, &pitch, &err), &err);
  free(s->output[s->noutputs - 1].of);
  s->output[s->noutputs - 1].of = strdup("lefty");
  fb_err_clear(&err);
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL);
  fprintf(stderr, "refused: %s\n", err.msg);
  CHECK(PART_IS(&err, FB_PART_OUTPUT, s->noutputs - 1, "of") &&
        strstr(err.msg, "did you mean 'left'") != NULL);
  fb_scenario_free(&s);
  expect_refusal("LMM", "LR", 0, 0, "front", "did you mean 'LM'");
  expect_refusal("LM", "LM", 0, 0, "rear", "one corner");
  expect_refusal("LM", "RR", 0, 0, "rear", "on one line");
  /* The later bogie is blamed. */
  expect_refusal("RM", "RR", 0, 1, "front", "on bogie left already");
  expect_refusal("LM", "LR", 5.0, 0, "pivot_x", "must lie between");
  expect_refusal("LF", "LR", 0, 0, "front", "anti-roll bar front");
}

int main(void)
{
  test_static_split();
  test_pitch_frequency();
  test_pitch_sign();
  test_energy();
  test_vehicle_split();
  test_system2_rigid_limit();
  test_system2_labels();
  test_band();
  test_refusals();
  return check_report(__FILE__);
}
