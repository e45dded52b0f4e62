/* SPDX-License-Identifier: BSD-3-Clause */
/* The ride-limit search (fb_study_ride_limit) against synthetic metrics
 * whose crossing of the limit is known in closed form (monotone, a hump
 * that crosses and falls back, never reached, reached at v_lo, a failed
 * evaluation), the metric table, a run's end by hand (bump and random
 * road) and the metrics against the run's own samples. */
#include <math.h>
#include <string.h>

#include "flexbond/study.h"
#include "flexbond/vehicle.h"

#include "check.h"

enum { MONOTONE, HUMP, NEVER, AT_LO, FAILS, NCURVES };

/* The hump's centre and width (m/s) and the failing curve's bad speed. */
static const double HUMP_C = 9.0, HUMP_W = 1.5;

/* Each curve's metric at speed v (m/s) against a limit of 1:
 * MONOTONE (v / 10)^2: reached at 10 m/s;
 * HUMP 2 exp(-((v - c)/w)^2) + v / 100: rises above 1 on the hump's
 * flank at c - w sqrt(ln(2 / (1 - v/100))) (to the fixed point), falls
 * below again behind it, and reaches 1 for good only at 100 m/s;
 * NEVER 0.5; AT_LO 3; FAILS (v / 10)^2 but NaN above 12 m/s. */
static double metric_of(size_t curve, double v)
{
  switch (curve) {
  case MONOTONE: return (v / 10) * (v / 10);
  case HUMP: return 2 * exp(-((v - HUMP_C) / HUMP_W) * ((v - HUMP_C) / HUMP_W)) + v / 100;
  case NEVER: return 0.5;
  case AT_LO: return 3;
  default: return v > 12 ? NAN : (v / 10) * (v / 10);
  }
}

typedef struct eval_log {
  size_t calls, points[NCURVES];
} eval_log;

static int eval(void *ctx, const fb_study_ride_limit_point *pts, size_t n, double *m,
                fb_err *err)
{
  (void)err;
  eval_log *log = ctx;
  ++log->calls;
  for (size_t i = 0; i < n; ++i) {
    m[i] = metric_of(pts[i].curve, pts[i].speed);
    ++log->points[pts[i].curve];
  }
  return FB_OK;
}

/* The hump's first crossing of 1, by fixed-point iteration of
 * v = c - w sqrt(ln(2 / (1 - v/100))) (a contraction: its derivative is
 * ~0.01 w / (2 sqrt(ln 2)) ~ 0.01). */
static double hump_crossing(void)
{
  double v = HUMP_C - HUMP_W;
  for (int i = 0; i < 100; ++i)
    v = HUMP_C - HUMP_W * sqrt(log(2 / (1 - v / 100)));
  return v;
}

static void check_found(const fb_study_ride_limit_curve *c, double exact, double limit,
                        double tol)
{
  CHECK(c->status == FB_RIDE_LIMIT_FOUND);
  /* The bracket holds the exact crossing and is at most tol wide. */
  CHECK(c->speed < exact && exact <= c->speed_over);
  CHECK(c->speed_over - c->speed <= tol * (1 + 1e-12));
  CHECK(c->metric < limit && c->metric_over >= limit);
}

static void test_search(size_t k)
{
  fb_study_ride_limit_opts o;
  fb_study_ride_limit_opts_default(&o);
  o.limit = 1;
  o.v_lo = 2;
  o.v_hi = 20;
  o.coarse_step = 2; /* 2, 4, ..., 20: 10 speeds */
  o.tol = 0.01;
  o.refine_points = k;
  eval_log log = {0};
  fb_study_ride_limit_curve out[NCURVES];
  size_t rounds = 0;
  fb_err err;
  CHECK(fb_study_ride_limit(NCURVES, &o, eval, &log, out, &rounds, &err) == FB_OK);
  check_found(&out[MONOTONE], 10, 1, o.tol);
  check_found(&out[HUMP], hump_crossing(), 1, o.tol);
  CHECK(out[NEVER].status == FB_RIDE_LIMIT_ABOVE && out[NEVER].speed == 20 &&
        isnan(out[NEVER].speed_over));
  CHECK(out[AT_LO].status == FB_RIDE_LIMIT_BELOW && out[AT_LO].speed_over == 2 &&
        isnan(out[AT_LO].speed));
  /* FAILS reaches 1 at 10 m/s, on the grid: its bracket is [8, 10] and
   * its NaN above 12 m/s is never asked for. */
  check_found(&out[FAILS], 10, 1, o.tol);
  /* Rounds: a coarse bracket 2 m/s wide needs r rounds of (k + 1)-fold
   * narrowing with 2 / (k + 1)^r <= 0.01. */
  size_t need = 0;
  for (double w = 2; w > o.tol * (1 + 1e-12); w /= (double)(k + 1))
    ++need;
  CHECK(rounds == 1 + need);
  CHECK(log.calls == rounds);
  for (size_t c = 0; c < NCURVES; ++c)
    CHECK(out[c].nruns == log.points[c]);
  CHECK(out[MONOTONE].nruns == 10 + need * k);
  CHECK(out[NEVER].nruns == 10 && out[AT_LO].nruns == 10);
}

/* A NaN on the coarse grid fails the curve at that speed. */
static void test_failure(void)
{
  fb_study_ride_limit_opts o;
  fb_study_ride_limit_opts_default(&o);
  o.limit = 2; /* (v/10)^2 = 2 at 14.1 m/s, beyond the NaN at 12 */
  o.v_lo = 2;
  o.v_hi = 20;
  o.coarse_step = 2;
  eval_log log = {0};
  fb_study_ride_limit_curve out[NCURVES];
  fb_err err;
  CHECK(fb_study_ride_limit(NCURVES, &o, eval, &log, out, NULL, &err) == FB_OK);
  CHECK(out[FAILS].status == FB_RIDE_LIMIT_FAILED && out[FAILS].failed_speed == 14);
  check_found(&out[MONOTONE], sqrt(200), 2, o.tol);
}

/* The last coarse step ends at v_hi, and a bad option is refused. */
static void test_opts(void)
{
  fb_study_ride_limit_opts o;
  fb_study_ride_limit_opts_default(&o);
  fb_err err;
  eval_log log = {0};
  fb_study_ride_limit_curve out[NCURVES];
  CHECK(fb_study_ride_limit(1, &o, eval, &log, out, NULL, &err) == FB_EINVAL); /* no limit */
  o.limit = 1;
  o.v_lo = 5;
  o.v_hi = 10.5;
  o.coarse_step = 2; /* 5, 7, 9, 10.5 */
  o.tol = 1e-3;
  CHECK(fb_study_ride_limit(1, &o, eval, &log, out, NULL, &err) == FB_OK);
  check_found(&out[MONOTONE], 10, 1, o.tol);
  CHECK(out[MONOTONE].speed_over <= 10.5);
  o.v_hi = 4;
  CHECK(fb_study_ride_limit(1, &o, eval, &log, out, NULL, &err) == FB_EINVAL);
}

static void test_table(void)
{
  size_t m = 0;
  CHECK(fb_study_ride_limit_metric_find("absorbed_power", &m) == 0);
  CHECK(fb_study_ride_limit_metric_limit(m) == FB_RIDE_ABSORBED_POWER_LIMIT);
  CHECK(!strcmp(fb_study_ride_limit_metric_unit(m), "W"));
  CHECK(fb_study_ride_limit_metric_find("a_w_rms", &m) == 0 &&
        isnan(fb_study_ride_limit_metric_limit(m)));
  CHECK(fb_study_ride_limit_metric_find("no_such", &m) == -1);
  CHECK(fb_study_ride_limit_metric_name(fb_study_ride_limit_nmetrics()) == NULL);
}

/* The run's end: on the paper's bump, settle after the last wheel (RR at
 * x = -1.00, y = -1.05 against LF at 1.90, 1.05; a 45 deg edge) leaves it:
 * first_contact + ((1.90 + 1.00) + (1.05 + 1.05) tan 45) / v + 3.70 / v +
 * settle; on the ISO road, when the last wheel (RR, 2.90 m behind LF,
 * which starts 5 m before the road) has run the course:
 * (5 + 2.90) / v + L / v. And the metrics over [first entry, end]
 * against the result's samples and fb_ride_metrics_result. */
static void test_run_and_measure(void)
{
  fb_scenario *s = NULL;
  fb_err err;
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &s, &err) == FB_OK);
  if (!s)
    return;
  const double v = s->speed;
  CHECK(fb_study_ride_limit_duration(s, 100, 2, &err) == FB_OK);
  CHECK_NEAR(s->t_end, 5.0 + (2.90 + 2.10) / v + 3.70 / v + 2, 1e-9);
  CHECK(fb_study_ride_limit_duration(s, 0, 2, &err) == FB_EINVAL);
  fb_result *r = NULL;
  CHECK(fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err) == FB_OK);
  const size_t k = fb_study_ride_output(s);
  size_t peak_m = 0, aw_m = 0;
  CHECK(fb_study_ride_limit_metric_find("abs_peak", &peak_m) == 0);
  CHECK(fb_study_ride_limit_metric_find("a_w_rms", &aw_m) == 0);
  double peak = NAN, aw = NAN;
  if (r && k < s->noutputs) {
    CHECK(fb_study_ride_limit_measure(s, r, k, peak_m, &peak, &err) == FB_OK);
    CHECK(fb_study_ride_limit_measure(s, r, k, aw_m, &aw, &err) == FB_OK);
    const long col = fb_result_find(r, s->output[k].name);
    double window[2], want = 0;
    fb_study_response_window(s, window);
    for (size_t i = 0; i < fb_result_nsamples(r); ++i)
      if (fb_result_row(r, i)[0] >= window[0])
        want = fmax(want, fabs(fb_result_row(r, i)[col]));
    CHECK(peak == want && peak > 0);
    const size_t n = fb_result_nsamples(r);
    const double t_last = fb_result_row(r, n - 1)[0];
    fb_ride_metrics m;
    CHECK(fb_ride_metrics_result(r, s->output[k].name, window[0],
                                 t_last + t_last / (double)(n - 1), NULL, &m, &err) == FB_OK);
    CHECK(aw == m.a_w_rms);
    /* absorbed power: the built-in filter's, as the metrics give it. */
    size_t ap = 0;
    double watts = 0;
    CHECK(fb_study_ride_limit_metric_find("absorbed_power", &ap) == 0);
    CHECK(fb_study_ride_limit_measure(s, r, k, ap, &watts, &err) == FB_OK &&
          watts == m.absorbed_power && watts > 0);
  }
  fb_result_free(&r);
  fb_scenario_free(&s);
  CHECK(fb_scenario_load("../examples/apc6x6_rough_course.yaml", &s, &err) == FB_OK);
  if (s) {
    s->t_end = 3600; /* a road that goes on ends its feature at the run's end */
    CHECK(fb_study_ride_limit_duration(s, 100, 2, &err) == FB_OK);
    CHECK_NEAR(s->t_end, (5 + 2.90) / s->speed + 100 / s->speed, 1e-9);
  }
  fb_scenario_free(&s);
}

int main(void)
{
  test_run_and_measure();
  test_search(1); /* bisection */
  test_search(3); /* quadrisection */
  test_failure();
  test_opts();
  test_table();
  return check_report("test_ride_limit");
}
