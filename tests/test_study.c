/* SPDX-License-Identifier: BSD-3-Clause */
/* The study layer (flexbond/study.h) against closed forms on results built
 * by hand, and its summary of a real run against the statistics of the
 * run's own columns.
 *
 * The hand-built output is 1 before t = 2 s, then 1 + A sin(2 pi f (t - 2))
 * over whole periods up to t = 6 s, then 1 again, sampled at 100 Hz; over
 * the window [2, 6] s its statistics are exact: the static value 1, the
 * peak 1 + A at a quarter period, the minimum 1 - A at three quarters,
 * and, since N = 400 samples over whole periods sum sin to 0 and sin^2 to
 * N / 2 (and the window's last sample, t = 6, is a zero of the sine), the
 * r.m.s. sqrt((N + 1 + A^2 N / 2) / (N + 1)). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/study.h"

#include "check.h"
#include "result_util.h"

#define RATE 100.0    /* Hz */
#define NSAMPLES 1001 /* 0 .. 10 s */
#define AMPLITUDE 0.5
#define FREQUENCY 1.0 /* Hz: four whole periods in [2, 6] s */
#define PI 3.14159265358979323846

/* Round-off of a few hundred additions of O(1) terms. */
#define TIGHT 1e-12

/* t, then "x" as above plus a triangle of height offset centred on
 * t_offset, 0.2 s either side. */
static fb_result *make_result(double offset, double t_offset)
{
  const char *const names[] = {"t", "x"}, *const units[] = {"s", "m"};
  fb_result *r = test_result_new(NSAMPLES, 2, names, units);
  for (size_t k = 0; r && k < NSAMPLES; ++k) {
    const double t = (double)k / RATE;
    double x = 1.0;
    if (k >= 200 && k <= 600)
      x += AMPLITUDE * sin(2 * PI * FREQUENCY * (double)(k - 200) / RATE);
    r->data[2 * k] = t;
    r->data[2 * k + 1] = x + offset * fmax(0.0, 1.0 - fabs(t - t_offset) / 0.2);
  }
  return r;
}

static void test_stats(void)
{
  fb_result *r = make_result(0.0, 0.0);
  CHECK(r != NULL);
  if (!r)
    return;
  const double window[2] = {2.0, 6.0};
  const fb_output_stats st = fb_output_stats_of(r, 1, window);
  const double n = 400;
  CHECK_NEAR(st.static_value, 1.0, 0.0);
  CHECK_NEAR(st.peak, 1.0 + AMPLITUDE, TIGHT);
  CHECK_NEAR(st.peak_time, 2.25, TIGHT);
  CHECK_NEAR(st.min, 1.0 - AMPLITUDE, TIGHT);
  CHECK_NEAR(st.min_time, 2.75, TIGHT);
  CHECK_NEAR(st.rms, sqrt((n + 1 + AMPLITUDE * AMPLITUDE * n / 2) / (n + 1)), TIGHT);
  /* The same run with a triangle of 0.1 m at t = 3 s added, where x is 1:
   * the largest difference 0.1 at 3 s, System 1's range 2 A, the peak
   * unchanged (the triangle ends before the next one, at 3.25 s), the
   * r.m.s. larger. */
  fb_result *r2 = make_result(0.1, 3.0), *diff = NULL;
  fb_err err;
  CHECK(r2 && fb_result_diff(r2, r, &diff, &err) == FB_OK);
  if (r2 && diff) {
    const fb_output_stats st2 = fb_output_stats_of(r2, 1, window);
    const fb_output_cmp c = fb_output_compare(&st, &st2, diff, 1, window);
    CHECK_NEAR(c.max_diff, 0.1, TIGHT);
    CHECK_NEAR(c.max_diff_time, 3.0, TIGHT);
    CHECK_NEAR(c.range1, 2 * AMPLITUDE, TIGHT);
    CHECK_NEAR(c.rel_diff, 0.1 / (2 * AMPLITUDE), TIGHT);
    CHECK_NEAR(c.peak_change, 0.0, TIGHT);
    CHECK(c.rms_change > 0);
  }
  /* A ratio to nothing is NaN, not an infinity. */
  const fb_output_stats zero = {0, 0, 0, 0, 0, 0};
  const fb_output_cmp z = fb_output_compare(&zero, &zero, r, 1, window);
  CHECK(isnan(z.rel_diff) && isnan(z.peak_change) && isnan(z.rms_change));
  fb_result_free(&diff);
  fb_result_free(&r2);
  fb_result_free(&r);
}

/* A real run: the summary's statistics are its columns', every tire's
 * reaction is summarised, the ride metrics are the driver's, and two
 * systems compare. */
static void test_summary(void)
{
  fb_scenario *s = NULL;
  fb_err err;
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &s, &err) == FB_OK);
  if (!s)
    return;
  s->t_end = 8.5; /* the last wheel leaves the bump at 8.132 s */
  fb_result *r1 = NULL;
  CHECK(fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r1, &err) == FB_OK);
  fb_run_summary *sum = NULL;
  CHECK(r1 && fb_run_summary_new(s, r1, NULL, &sum, &err) == FB_OK && sum);
  if (sum) {
    double window[2], expected[2];
    fb_run_summary_window(sum, window);
    fb_study_response_window(s, expected);
    CHECK(window[0] == expected[0] && window[1] == expected[1]);
    CHECK_NEAR(window[0], 5.0, TIGHT);
    for (size_t k = 0; k < s->noutputs; ++k) {
      const fb_output_stats a = fb_output_stats_of(r1, fb_run_summary_column(sum, k), window);
      const fb_output_stats *b = fb_run_summary_output(sum, k);
      CHECK(b && b->peak == a.peak && b->rms == a.rms && b->static_value == a.static_value);
    }
    CHECK(fb_run_summary_output(sum, s->noutputs) == NULL);
    for (size_t c = 0; c < s->ncorners; ++c) {
      const fb_output_stats *t = fb_run_summary_contact(sum, c);
      /* The paper's bilateral tires carry a static load and never spike. */
      CHECK(t && t->static_value > 0 && !fb_run_summary_contact_spike(sum, c));
      CHECK_NEAR(fb_run_summary_contact_ratio(sum, c), t->peak / t->static_value, 0.0);
    }
    CHECK(fb_run_summary_nlosses(sum) == 0 && fb_run_summary_loss(sum, 0) == NULL);
    fb_ride_metrics m;
    const char *note = "x";
    CHECK(fb_study_ride_output(s) < s->noutputs);
    CHECK(fb_run_summary_ride(sum, &m, NULL, &note) == 1 && note == NULL && m.a_w_rms > 0);
    /* A run compared with itself: no difference anywhere. */
    fb_output_cmp *cmp = calloc(s->noutputs, sizeof *cmp);
    CHECK(cmp && fb_study_compare(s, r1, r1, sum, sum, cmp, NULL, &err) == FB_OK);
    for (size_t k = 0; cmp && k < s->noutputs; ++k)
      CHECK(cmp[k].max_diff == 0 && (cmp[k].peak_change == 0 || isnan(cmp[k].peak_change)));
    /* Against a stiffer front spring: each output's largest difference
     * from the window on, second run minus first, as the columns give it,
     * and the peak change from the two summaries. */
    s->corner[0].spring_k *= 1.2;
    fb_result *r2 = NULL, *diff = NULL;
    fb_run_summary *sum2 = NULL;
    CHECK(fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r2, &err) == FB_OK);
    CHECK(r2 && fb_run_summary_new(s, r2, NULL, &sum2, &err) == FB_OK);
    CHECK(cmp && sum2 && fb_study_compare(s, r1, r2, sum, sum2, cmp, &diff, &err) == FB_OK);
    for (size_t k = 0; cmp && diff && k < s->noutputs; ++k) {
      const size_t col = fb_run_summary_column(sum, k);
      double largest = 0;
      for (size_t i = 0; i < fb_result_nsamples(r1); ++i)
        if (fb_result_row(r1, i)[0] >= window[0])
          largest = fmax(largest, fabs(fb_result_row(r2, i)[col] - fb_result_row(r1, i)[col]));
      CHECK(cmp[k].max_diff == largest);
      const fb_output_stats *a = fb_run_summary_output(sum, k),
                            *b = fb_run_summary_output(sum2, k);
      if (a->peak != 0)
        CHECK(cmp[k].peak_change == (b->peak - a->peak) / fabs(a->peak));
    }
    CHECK(cmp && cmp[0].max_diff > 0); /* the LF tire feels its stiffer spring */
    fb_result_free(&diff);
    fb_run_summary_free(&sum2);
    fb_result_free(&r2);
    free(cmp);
  }
  fb_run_summary_free(&sum);
  /* A result that lacks a column the scenario names is refused. */
  if (r1 && fb_result_truncate(r1, 3, &err) == FB_OK) {
    CHECK(fb_run_summary_new(s, r1, NULL, &sum, &err) == FB_EINVAL && !sum);
    CHECK(strstr(err.msg, "the result has no output") != NULL);
  }
  fb_result_free(&r1);
  fb_scenario_free(&s);
}

int main(void)
{
  test_stats();
  test_summary();
  return check_report("test_study");
}
