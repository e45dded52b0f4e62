/* SPDX-License-Identifier: BSD-3-Clause */
/* Bump and rebound stops (flexbond/stop.h): the element's force against
 * closed forms written here, the static equilibrium of a vehicle resting
 * on a bump stop solved by hand, a mass bouncing between undamped stops
 * keeping its energy, linear analyses that a stop out of contact leaves
 * alone, and errors and warnings at their keys. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "energy_balance.h"
#include "three_corner.h"
#include "vehicle/vehicle_internal.h"
#include "vehicle_util.h"

/* The front corner's spring (preload 2000 N, k 1e5 N/m) and stops: the
 * bump stop touched at 0.05 m of compression, 4e5 N/m, damping 2000 N s/m
 * over 0.01 m; the rebound stop touched at 0.08 m of extension, a table
 * (0, 0), (0.01, 1000), (0.02, 4000), undamped. */
#define FRONT                                                                                  \
  ", spring_preload: 2000, bump_stop: {gap: 0.05, rate: 4e5, damping: 2000, damping_depth: "   \
  "0.01}, rebound_stop: {gap: 0.08, table: {points: [[0, 0], [0.01, 1000], [0.02, 4000]]}}"
#define STOP_OUTPUT "  - {signal: stop_force, of: F}\n"

/* The stops' force at travel rate v and travel x: their element's law. */
static double stops_force(const fb_bg *bg, double v, double x, double *jac)
{
  const long e = fb_bg_find_element(bg, "stops");
  const void *ctx = NULL;
  const fb_law_ops *ops = e >= 0 ? fb_bg_element_law(bg, (size_t)e, &ctx) : NULL;
  const double xu[2] = {v, x};
  const fb_law_in in = {.n = 1, .m = 1, .x = xu};
  double f = NAN;
  if (!ops || ops->eval((void *)ctx, &in, &f) || (jac && ops->jacobian((void *)ctx, &in, jac)))
    return NAN;
  return f;
}

/* Hand values: F = max(0, k_b d + c min(d / 0.01, 1) v) past the bump
 * stop's gap (d = x - 0.05), minus the rebound table's value at
 * d = -x - 0.08 (a knot's, or its last tangent's beyond it: Fritsch &
 * Carlson's end slope is the end secant, 3e5 N/m), 0 between. The same
 * arithmetic on the same values: 1e-12 of the largest force. */
static void test_force(void)
{
  static const struct {
    double x, v, f;
  } at[] = {
      {0.0, 1.0, 0.0},    {0.05, 1.0, 0.0},    {0.06, 0.0, 4000.0}, {0.055, 0.5, 2500.0},
      {0.07, 1.0, 10000}, {0.052, -3.0, 0.0},  {-0.08, -1.0, 0.0},  {-0.09, 0.0, -1000.0},
      {-0.1, 0.0, -4000}, {-0.11, 0.0, -7000}, {-0.1, 2.0, -4000},
  };
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(three_corner_load(FRONT, "", 0.0, "zero", STOP_OUTPUT, &s, &err) == FB_OK);
  fb_bg *bg = NULL;
  CHECK(s && fb_vehicle_corner(&s->corner[0], 9.81, &bg, &err) == FB_OK);
  if (!bg) {
    fb_scenario_free(&s);
    return;
  }
  double worst = 0.0;
  for (size_t i = 0; i < sizeof at / sizeof at[0]; ++i) {
    const double f = stops_force(bg, at[i].v, at[i].x, NULL);
    worst = fmax(worst, fabs(f - at[i].f));
    if (fabs(f - at[i].f) > 1e-12 * 10000.0)
      fprintf(stderr, "  stops at x %g v %g: %.17g, want %g\n", at[i].x, at[i].v, f, at[i].f);
  }
  CHECK(worst <= 1e-12 * 10000.0);
  /* The Jacobian against central differences inside contact (away from
   * the kinks): the force is at most cubic there, so steps of 1e-6
   * leave an error of ~1e-12 of the slopes (~1e5); 1e-6 relative. */
  static const double pts[][2] = {{0.3, 0.065}, {-0.2, 0.057}, {0.0, -0.095}, {1.0, -0.11}};
  double jworst = 0.0;
  for (size_t i = 0; i < sizeof pts / sizeof pts[0]; ++i) {
    double jac[2];
    const double v = pts[i][0], x = pts[i][1], h = 1e-6;
    stops_force(bg, v, x, jac);
    const double dv =
        (stops_force(bg, v + h, x, NULL) - stops_force(bg, v - h, x, NULL)) / 2 / h;
    const double dx =
        (stops_force(bg, v, x + h, NULL) - stops_force(bg, v, x - h, NULL)) / 2 / h;
    jworst = fmax(jworst, fmax(fabs(jac[0] - dv) / fmax(fabs(dv), 1.0),
                               fabs(jac[1] - dx) / fmax(fabs(dx), 1.0)));
  }
  CHECK(jworst <= 1e-6);
  printf("stops: forces at %zu travels to %.3g N of the hand values, Jacobian to %.3g\n",
         sizeof at / sizeof at[0], worst, jworst);
  fb_bg_free(&bg);
  fb_scenario_free(&s);
}

/* The vehicle of three_corner.h at rest: the front spring carries W / 3 =
 * 10000 N with the bump stop. Without it the travel would be (10000 -
 * 2000) / 1e5 = 0.08 m, past the gap 0.05; with it
 *   2000 + 1e5 x + 4e5 (x - 0.05) = 10000,  x = 28000 / 5e5 = 0.056 m,
 * the stop carrying 4e5 * 0.006 = 2400 N and the spring 7600 N (its
 * damping is 0 at rest). The static solver's tolerance and the run's
 * rtol 1e-8: 1e-7 of the load and of the travel. */
static void test_static(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(three_corner_load(FRONT, "", 0.0, "static", STOP_OUTPUT, &s, &err) == FB_OK);
  fb_result *r = s ? simulate_rigid(s) : NULL;
  CHECK(r != NULL);
  if (r) {
    const double *row = fb_result_row(r, 0);
    const double x = row[fb_result_find(r, "spring_defl_F")];
    const double fs = row[fb_result_find(r, "spring_force_F")];
    const double fb = row[fb_result_find(r, "stop_force_F")];
    CHECK(fabs(x - 0.056) <= 1e-7 * 0.056);
    CHECK(fabs(fs - 7600.0) <= 1e-7 * 10000.0);
    CHECK(fabs(fb - 2400.0) <= 1e-7 * 10000.0);
    /* And it stays there. */
    const size_t last = fb_result_nsamples(r) - 1;
    CHECK(fabs(fb_result_row(r, last)[fb_result_find(r, "stop_force_F")] - 2400.0) <=
          1e-6 * 10000.0);
    printf("stops: static travel %.9g m (0.056 by hand), spring %.9g N (7600), stop %.9g N "
           "(2400)\n",
           x, fs, fb);
  }
  fb_result_free(&r);
  fb_scenario_free(&s);
}

/* A mass m = 300 kg on the front corner's spring and undamped linear
 * stops (bump 0.05 m, 4e5 N/m; rebound 0.04 m, 3e5 N/m), no gravity,
 * set off from zero travel at 2 m/s: it bounces between both stops. Its
 * energy by hand, m v^2 / 2 + 2000 x + 1e5 x^2 / 2 + 4e5 max(x - 0.05,
 * 0)^2 / 2 + 3e5 max(-x - 0.04, 0)^2 / 2, stays what it was: the stops
 * give back all they take. rtol 1e-10 over ~4 bounces, each contact's
 * kink costing the integrator a few steps: 1e-7 of the energy (measured
 * below); a stop that lost 1 % of its energy per contact, or a hand
 * energy that missed one (~30 % of it), fails. */
static void test_energy_mass(void)
{
  const double m = 300.0;
  fb_corner_params c = {.name = "mass", .spring_k = 1e5};
  fb_err err;
  fb_spring_linear_params *p = NULL;
  CHECK(fb_corner_set_spring(&c, &fb_spring_law_linear, (void **)&p, &err) == FB_OK);
  if (p)
    p->preload = 2000.0;
  c.stops.bump = (fb_stop){.given = 1, .gap = 0.05, .rate = 4e5, .damping_depth = 0.01};
  c.stops.rebound = (fb_stop){.given = 1, .gap = 0.04, .rate = 3e5, .damping_depth = 0.01};
  CHECK(fb_stops_check(&c.stops, "mass", &err) == FB_OK);
  /* Moving towards extension first, then back. */
  fb_result *r = NULL;
  CHECK(mass_on_corner_spring(&c, m, 0.0, -2.0 * m, 1.5, 1e-10, &r, &err) == FB_OK);
  if (r) {
    const long cx = fb_result_find(r, "x"), cv = fb_result_find(r, "v");
    double e0 = NAN, worst = 0.0, xmin = 0.0, xmax = 0.0;
    for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
      const double x = fb_result_row(r, k)[cx], v = fb_result_row(r, k)[cv];
      const double db = fmax(x - 0.05, 0.0), dr = fmax(-x - 0.04, 0.0);
      const double e = 0.5 * m * v * v + 2000.0 * x + 0.5 * 1e5 * x * x + 0.5 * 4e5 * db * db +
                       0.5 * 3e5 * dr * dr;
      if (k == 0)
        e0 = e;
      worst = fmax(worst, fabs(e - e0));
      xmin = fmin(xmin, x);
      xmax = fmax(xmax, x);
    }
    CHECK(xmax > 0.05 && xmin < -0.04); /* both stops reached */
    CHECK(worst <= 1e-6 * e0);
    printf("stops: a mass between undamped stops (travel %.4g .. %.4g m) keeps its energy "
           "to %.3g of %.6g J\n",
           xmin, xmax, worst / e0, e0);
  }
  fb_result_free(&r);
}

/* The vehicle over a 0.2 m bump with undamped stops at every corner that
 * it reaches: work in = dissipated + stored change at rtol 1e-9 (the
 * stops' integrated power counted with the resistors', their elastic
 * energy returned to the rest), as tests/test_system1.c argues: 1e-7 of
 * the work scale. */
static void test_energy_vehicle(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  const char *stops =
      ", bump_stop: {gap: 0.11, rate: 4e5}, rebound_stop: {gap: 0.02, rate: 4e5}";
  CHECK(three_corner_load(stops, stops, 0.2, "zero", STOP_OUTPUT, &s, &err) == FB_OK);
  if (!s)
    return;
  fb_result *r = simulate_rigid(s);
  double lo = 0.0, hi = 0.0;
  const long col = r ? fb_result_find(r, "stop_force_F") : -1;
  for (size_t k = 0; col > 0 && k < fb_result_nsamples(r); ++k) {
    lo = fmin(lo, fb_result_row(r, k)[col]);
    hi = fmax(hi, fb_result_row(r, k)[col]);
  }
  CHECK(lo < 0.0 && hi > 0.0); /* both front stops reached */
  fb_result_free(&r);
  energy_report rep;
  CHECK(energy_balance_rigid(s, 1e-9, &rep, &err) == FB_OK);
  CHECK(rep.worst <= 1e-7 * rep.work_scale);
  printf("stops: vehicle over a 0.2 m bump (front stop force %.6g .. %.6g N), energy balance "
         "to %.3g of the work (%.6g J)\n",
         lo, hi, rep.worst / rep.work_scale, rep.work_scale);
  fb_scenario_free(&s);
}

/* The vehicle's modes with and without stops its equilibrium does not
 * touch (gaps 0.2 m both ways, the static travels 0.08 m and 0.1 m):
 * the same to round-off (their Jacobian is 0 there); with the front bump
 * stop touched (gap 0.05 m, FRONT) the linearisation holds its rate too,
 * so the lowest mode is stiffer. */
static void test_modes(void)
{
  const char *far = ", spring_preload: 2000, bump_stop: {gap: 0.2, rate: 4e5, damping: 2000}, "
                    "rebound_stop: {gap: 0.2, rate: 4e5, damping: 2000}";
  const char *none = ", spring_preload: 2000";
  const char *front[3] = {none, far, FRONT};
  fb_mode *m[3] = {NULL, NULL, NULL};
  size_t n[3] = {0, 0, 0}, nstatic = 0;
  for (int i = 0; i < 3; ++i) {
    fb_err err;
    fb_scenario *s = NULL;
    CHECK(three_corner_load(front[i], "", 0.0, "static", "", &s, &err) == FB_OK);
    CHECK(s && fb_vehicle_modes(s, FB_SYSTEM_RIGID, 0, &m[i], &n[i], &nstatic, &err) == FB_OK);
    fb_scenario_free(&s);
  }
  CHECK(n[0] == n[1] && n[0] == n[2] && n[0] > 0);
  double worst = 0.0;
  for (size_t k = 0; m[0] && m[1] && k < n[0] && k < n[1]; ++k)
    worst = fmax(worst, fabs(m[1][k].freq_hz - m[0][k].freq_hz) / m[0][k].freq_hz +
                            fabs(m[1][k].damping_ratio - m[0][k].damping_ratio));
  CHECK(worst <= 1e-9);
  double stiffer = 0.0;
  for (size_t k = 0; m[0] && m[2] && k < n[0] && k < n[2]; ++k)
    stiffer = fmax(stiffer, m[2][k].freq_hz / m[0][k].freq_hz - 1.0);
  CHECK(stiffer > 0.01);
  printf("stops: modes untouched by stops out of contact to %.3g; on the bump stop a mode "
         "%.3g %% stiffer\n",
         worst, 100.0 * stiffer);
  for (int i = 0; i < 3; ++i)
    free(m[i]);
}

/* Errors at their keys, and implausible gaps and rates warned of at
 * theirs. */
static void test_errors(void)
{
  static const struct {
    const char *front, *want;
  } bad[] = {
      {", bump_stop: {gap: -0.1, rate: 4e5}",
       "three_corner.yaml:16:82: suspensions.corners[0].bump_stop.gap: must be >= 0 m (got "
       "-0.1)"},
      {", bump_stop: {gap: 0.1}",
       "three_corner.yaml:16:76: suspensions.corners[0].bump_stop: missing one of 'rate', "
       "'table'"},
      {", bump_stop: {gap: 0.1, rate: 1e5, table: {points: [[0, 0], [0.01, 100]]}}",
       "three_corner.yaml:16:98: suspensions.corners[0].bump_stop.table: give either 'rate' or "
       "'table', not both"},
      {", rebound_stop: {gap: 0.1, table: {points: [[0.01, 0], [0.02, 100]]}}",
       "three_corner.yaml:16:97: suspensions.corners[0].rebound_stop.table: corner 'F': a "
       "stop's table starts at (0, 0)"},
      {", rebound_stop: {gap: 0.1, rate: 1e5, damping_depth: 0}",
       "suspensions.corners[0].rebound_stop.damping_depth: must be > 0 m"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i)
    three_corner_refused(bad[i].front, bad[i].want);
  /* A corner without stops offers no stop force, at the output's key. */
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(three_corner_load("", "", 0.0, "zero", STOP_OUTPUT, &s, &err) != FB_OK && !s);
  CHECK(strstr(err.msg, "three_corner.yaml:27:30: outputs[4].of: corner 'F' has no stop "
                        "(bump_stop or rebound_stop) for stop_force to measure"));
  /* Legal but implausible: a 2 m gap, a rate of 10 N/m. */
  CHECK(three_corner_load(", bump_stop: {gap: 2, rate: 10}", "", 0.0, "zero", "", &s, &err) ==
        FB_OK);
  size_t seen = 0;
  for (size_t i = 0; s && i < fb_scenario_nwarnings(s); ++i) {
    const char *w = fb_scenario_warning(s, i)->msg;
    seen += strstr(w, "three_corner.yaml:16:") &&
            (strstr(w, "bump_stop.gap: 2 m is implausible") ||
             strstr(w, "bump_stop.rate: 10 N/m is implausible"));
  }
  CHECK(seen == 2);
  fb_scenario_free(&s);
}

/* Overrides reach the stops' and the preload's keys, at the file's
 * paths: the gap moved, the preload changed, the value kept where it
 * lands. */
static void test_overrides(void)
{
  const fb_scenario_override ov[2] = {
      {.key = "suspensions.corners[0].bump_stop.gap", .value = "0.07"},
      {.key = "suspensions.corners[0].spring_preload", .value = "1500"}};
  char *t = three_corner_text(FRONT, "", 0.0, "zero", "");
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(t && fb_scenario_load_string_overrides(t, strlen(t), "three_corner.yaml", ov, 2, &s,
                                               &err) == FB_OK);
  if (s) {
    const fb_corner_params *c = &s->corner[0];
    CHECK(c->stops.bump.gap == 0.07 && c->stops.bump.rate == 4e5);
    CHECK(((const fb_spring_linear_params *)(const void *)c->spring.bytes)->preload == 1500.0);
  }
  fb_scenario_free(&s);
  free(t);
}

int main(void)
{
  test_force();
  test_static();
  test_energy_mass();
  test_energy_vehicle();
  test_modes();
  test_errors();
  test_overrides();
  return check_report("test_stops");
}
