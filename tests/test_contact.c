/* SPDX-License-Identifier: BSD-3-Clause */
/* Tire contact on System 1: the verdict (fb_vehicle_contact_loss,
 * src/vehicle/contact.c) and unilateral tires (wheel.tire_contact). The
 * paper's crossing keeps every tire in compression; a 0.20 m bump at
 * 30 km/h makes five linear tires pull their wheels down, and the
 * intervals must agree with a brute-force scan of the samples. With
 * unilateral tires the same crossing lifts the wheels off instead: no
 * reaction is ever tensile, the run equals the linear one until the first
 * release, and the energy balance closes across every contact change. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/model.h"
#include "flexbond/vehicle.h"

#include "apc_layout.h"
#include "bgtest_util.h"
#include "check.h"
#include "energy_balance.h"
#include "road_util.h"
#include "vehicle_util.h"

static long column(const fb_result *r, const char *prefix, int corner)
{
  char name[32];
  snprintf(name, sizeof name, "%s%s", prefix, apc_corner_name(corner));
  return fb_result_find(r, name);
}

/* Every sample with a reaction <= 0 (after t = 0) lies in an interval of
 * its tire, every interval holds one at least, and its minimum is the
 * samples'. A tensile minimum lies strictly inside its interval; a zero
 * one (unilateral tires) may be its first sample. */
static void check_against_scan(const fb_result *r, const fb_contact_loss *iv, size_t n)
{
  for (int c = 0; c < APC_NCORNERS; ++c) {
    const long col = column(r, "contact_force_", c);
    CHECK(col > 0);
    if (col < 1)
      return;
    size_t negative = 0, covered = 0;
    for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
      const double *row = fb_result_row(r, k);
      if (!(row[col] <= 0.0) || row[0] == 0.0)
        continue;
      ++negative;
      for (size_t i = 0; i < n; ++i)
        if (iv[i].corner == c && row[0] >= iv[i].t_start && row[0] <= iv[i].t_end) {
          ++covered;
          CHECK(row[col] >= iv[i].min_force);
          break;
        }
    }
    CHECK(covered == negative);
    for (size_t i = 0; i < n; ++i) {
      if (iv[i].corner != c)
        continue;
      if (iv[i].min_force < 0.0)
        CHECK(iv[i].t_start < iv[i].t_min && iv[i].t_min < iv[i].t_end);
      else
        CHECK(iv[i].min_force == 0.0 && iv[i].t_start <= iv[i].t_min &&
              iv[i].t_min < iv[i].t_end);
      /* The minimum is a sample's value at its time. */
      const size_t k = (size_t)llround(iv[i].t_min * 1000.0);
      CHECK(fb_result_row(r, k)[col] == iv[i].min_force);
    }
  }
}

static void test_paper_crossing(const fb_scenario *s)
{
  fb_result *r = simulate_rigid(s);
  if (!r)
    return;
  /* The seven outputs, then the six reactions; LF is the paper's Fig. 8. */
  const long lf = column(r, "contact_force_", APC_LF),
             fig8 = fb_result_find(r, "tire_force_LF");
  CHECK(lf == 1 + APC_NOUTPUTS && fig8 == 1);
  for (size_t k = 0; lf > 0 && fig8 > 0 && k < fb_result_nsamples(r); k += 97)
    CHECK(fb_result_row(r, k)[lf] == fb_result_row(r, k)[fig8]);
  fb_err err;
  fb_contact_loss *iv = NULL;
  size_t n = 99;
  CHECK(fb_vehicle_contact_loss(s, r, &iv, &n, &err) == FB_OK);
  CHECK(n == 0 && iv == NULL);
  check_against_scan(r, iv, n);
  free(iv);
  fb_result_free(&r);
}

/* The 0.20 m bump at 30 km/h. */
static void high_bump(fb_scenario *s)
{
  road_bump(s)->height = 0.20;
  s->speed = 30.0 / 3.6;
}

static void set_tire_contact(fb_scenario *s, const fb_tire_model *m)
{
  for (int c = 0; c < APC_NCORNERS; ++c)
    CHECK(fb_corner_set_tire(&s->corner[c], m, NULL, NULL) == FB_OK);
}

static void test_lift_off(fb_scenario *s)
{
  high_bump(s);
  fb_result *r = simulate_rigid(s);
  if (!r)
    return;
  fb_err err;
  fb_contact_loss *iv = NULL;
  size_t n = 0;
  CHECK(fb_vehicle_contact_loss(s, r, &iv, &n, &err) == FB_OK);
  fprintf(stderr, "0.20 m bump at 30 km/h, linear tires: %zu tensile intervals\n", n);
  for (size_t i = 0; i < n; ++i)
    fprintf(stderr, "  %s %.4f .. %.4f s, down to %.1f N at %.3f s\n",
            apc_corner_name(iv[i].corner), iv[i].t_start, iv[i].t_end, iv[i].min_force,
            iv[i].t_min);
  CHECK(n >= 4);
  check_against_scan(r, iv, n);
  free(iv);
  fb_result_free(&r);
}

/* The first time any reaction of r is <= 0 after t = 0 (t_end if none). */
static double first_loss(const fb_result *r)
{
  for (size_t k = 1; k < fb_result_nsamples(r); ++k)
    for (int c = 0; c < APC_NCORNERS; ++c)
      if (fb_result_row(r, k)[column(r, "contact_force_", c)] <= 0.0)
        return fb_result_row(r, k)[0];
  return fb_result_row(r, fb_result_nsamples(r) - 1)[0];
}

/* The high bump run with tires a, then with tires b (the scenario keeps
 * b's); 0 with both results freed if either fails. */
static int high_bump_pair(fb_scenario *s, const fb_tire_model *a, const fb_tire_model *b,
                          fb_result **ra, fb_result **rb)
{
  high_bump(s);
  set_tire_contact(s, a);
  *ra = simulate_rigid(s);
  set_tire_contact(s, b);
  *rb = simulate_rigid(s);
  if (*ra && *rb)
    return 1;
  fb_result_free(ra);
  fb_result_free(rb);
  return 0;
}

static void test_unilateral(fb_scenario *s)
{
  fb_result *linear = NULL, *r = NULL;
  if (!high_bump_pair(s, &fb_tire_model_bilateral, &fb_tire_model_unilateral, &linear, &r))
    return;
  /* Never tensile, at any sample of any tire. */
  double lowest = INFINITY;
  for (size_t k = 0; k < fb_result_nsamples(r); ++k)
    for (int c = 0; c < APC_NCORNERS; ++c)
      lowest = fmin(lowest, fb_result_row(r, k)[column(r, "contact_force_", c)]);
  CHECK(lowest == 0.0);
  fb_err err;
  fb_contact_loss *iv = NULL;
  size_t n = 0;
  CHECK(fb_vehicle_contact_loss(s, r, &iv, &n, &err) == FB_OK);
  fprintf(stderr,
          "0.20 m bump at 30 km/h, unilateral tires: %zu intervals off the road, "
          "%ld contact changes\n",
          n, fb_result_stats(r)->events);
  for (size_t i = 0; i < n; ++i)
    fprintf(stderr, "  %s %.4f .. %.4f s\n", apc_corner_name(iv[i].corner), iv[i].t_start,
            iv[i].t_end);
  CHECK(n >= 4);
  /* Each interval is a release, a separation and a landing. */
  CHECK(fb_result_stats(r)->events >= 2 * (long)n);
  check_against_scan(r, iv, n);
  /* Until the first release both tires are the same equations, stepped
   * the same way (root-finding only watches): equal to rounding. */
  const double t_release = first_loss(r);
  CHECK(t_release > fb_scenario_road_entry(s, APC_LF) &&
        t_release < fb_scenario_road_exit(s, APC_RR));
  double worst = 0.0;
  for (size_t k = 0; k < fb_result_nsamples(r) && fb_result_row(r, k)[0] < t_release; ++k)
    for (size_t j = 1; j < fb_result_ncols(r); ++j)
      worst = fmax(worst, fabs(fb_result_row(r, k)[j] - fb_result_row(linear, k)[j]) /
                              (1.0 + fabs(fb_result_row(linear, k)[j])));
  CHECK(worst <= 1e-9);
  /* The first release is where the linear reaction crosses zero: the
   * same first sample at or below zero. */
  CHECK(first_loss(linear) == t_release);
  free(iv);
  fb_result_free(&r);
  fb_result_free(&linear);
}

/* Work in = dissipated + stored change through every contact change, at
 * rtol 1e-9 (the tolerance argument of test_system1.c's balance: 100
 * rtol of the work scale, 6e-3 J here). The released damper's power
 * -k q f and the spring's energy k max(q, 0)^2 / 2 must both be right:
 * with k q^2 / 2 a lifted wheel's gap would count as stored energy
 * (RM's 7 mm: 12 J). */
static void check_energy_balance(const fb_scenario *s)
{
  fb_err err;
  fb_err_clear(&err);
  energy_report rep;
  MUST(energy_balance_rigid(s, 1e-9, &rep, &err), &err);
  CHECK(rep.work_scale > 100.0);
  CHECK(rep.worst <= 1e-7 * rep.work_scale);
}

static void test_unilateral_energy(fb_scenario *s)
{
  high_bump(s);
  set_tire_contact(s, &fb_tire_model_unilateral);
  check_energy_balance(s);
}

/* Hunt-Crossley tires over the same crossing: never tensile; the
 * hardest landing much softer, since the damping starts from zero at
 * first contact (the largest reaction, LF's 20.7 times its static load
 * with the constant damper, falls by more than half: to 4.5 times, as
 * examples/apc6x6_liftoff.yaml shows). Not every tire's peak falls: past
 * the reference deflection the damping lambda q exceeds tire_c, so a
 * deep, slow compression meets more of it. And the energy balance closes
 * as for the unilateral tire: its damper's power lambda q f^2 is what the
 * balance integrates. */
static void test_hunt_crossley(fb_scenario *s)
{
  fb_result *kv = NULL, *hc = NULL;
  if (!high_bump_pair(s, &fb_tire_model_unilateral, &fb_tire_model_hunt_crossley, &kv, &hc))
    return;
  double lowest = INFINITY, peak_kv = 0, peak_hc = 0;
  for (int c = 0; c < APC_NCORNERS; ++c) {
    const long j = column(hc, "contact_force_", c);
    for (size_t k = 0; k < fb_result_nsamples(hc); ++k) {
      lowest = fmin(lowest, fb_result_row(hc, k)[j]);
      peak_kv = fmax(peak_kv, fb_result_row(kv, k)[j]);
      peak_hc = fmax(peak_hc, fb_result_row(hc, k)[j]);
    }
  }
  fprintf(stderr,
          "0.20 m bump at 30 km/h: largest reaction %.0f N (constant damper), %.0f N "
          "(Hunt-Crossley)\n",
          peak_kv, peak_hc);
  CHECK(lowest == 0.0);
  CHECK(peak_hc < 0.5 * peak_kv);
  check_energy_balance(s);
  fb_result_free(&kv);
  fb_result_free(&hc);
}

/* A result without the reactions (a model's own probes) is refused. */
static void test_missing_columns(const fb_scenario *s)
{
  static const char text[] = "model: m\n"
                             "elements:\n"
                             "  - {name: F, type: Se, value: 1}\n"
                             "  - {name: v, type: 1}\n"
                             "  - {name: M, type: I, m: 1}\n"
                             "  - {name: D, type: R, r: 1}\n"
                             "bonds:\n"
                             "  - [F, v]\n"
                             "  - {name: b, from: v, to: M}\n"
                             "  - [v, D]\n"
                             "probes:\n"
                             "  - {name: vel, flow: b}\n"
                             "simulation: {t_end: 0.1}\n";
  fb_err err;
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  fb_result *r = NULL;
  size_t np = 0;
  CHECK(fb_model_load_string(text, strlen(text), "m.yaml", NULL, &m, &err) == FB_OK);
  if (!m)
    fprintf(stderr, "model: %s\n", err.msg);
  if (m) {
    const fb_probe_spec *p = fb_model_probes(m, &np);
    CHECK(fb_bd_build(fb_model_graph(m), p, np, &bd, &err) == FB_OK);
  }
  if (bd)
    CHECK(fb_sim_run(bd, fb_model_sim_opts(m), &r, &err) == FB_OK);
  if (r) {
    fb_contact_loss *iv = NULL;
    size_t n = 0;
    CHECK(fb_vehicle_contact_loss(s, r, &iv, &n, &err) == FB_EINVAL);
    CHECK(strstr(err.msg, "contact_force_LF") != NULL);
    CHECK(iv == NULL && n == 0);
  }
  fb_result_free(&r);
  fb_bd_free(&bd);
  fb_model_free(&m);
}

int main(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &s, &err) == FB_OK);
  if (s) {
    test_paper_crossing(s);
    test_lift_off(s);
    test_unilateral(s);
    test_unilateral_energy(s);
    test_hunt_crossley(s);
    test_missing_columns(s);
  }
  fb_scenario_free(&s);
  return check_report("test_contact");
}
