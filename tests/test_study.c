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

/* Three runs of one scenario, the front springs stiffer in each: the
 * report's comparisons are fb_study_compare's and its findings are what
 * the comparisons and the runs' columns give by hand. */
static fb_study_report *report_of(const fb_scenario *s, const fb_study_run *runs, size_t n,
                                  const fb_study_run *conv)
{
  fb_study_report *rep = NULL;
  fb_err err;
  CHECK(fb_study_report_new(s, runs, n, conv, &rep, &err) == FB_OK && rep);
  return rep;
}

/* The largest |(c - a) - (b - a)| in column col from t0 on: the two
 * meshes' System 2 apart, each as its difference from System 1 a. */
static double largest_between(const fb_result *a, const fb_result *b, const fb_result *c,
                              size_t col, double t0)
{
  double m = 0;
  for (size_t i = 0; i < fb_result_nsamples(a); ++i) {
    const double *ra = fb_result_row(a, i), *rb = fb_result_row(b, i),
                 *rc = fb_result_row(c, i);
    if (ra[0] >= t0)
      m = fmax(m, fabs((rc[col] - ra[col]) - (rb[col] - ra[col])));
  }
  return m;
}

static void check_findings(const fb_scenario *s, const fb_study_report *rep,
                           const fb_study_run *runs, const fb_study_run *conv)
{
  const fb_output_cmp *c1 = fb_study_report_cmp(rep, FB_STUDY_CMP_SYSTEM2),
                      *c3 = fb_study_report_cmp(rep, FB_STUDY_CMP_CONVERGED);
  CHECK(c1 && c3 && fb_study_report_diff(rep, FB_STUDY_CMP_CONVERGED));
  if (!c1 || !c3)
    return;
  double window[2];
  fb_study_report_window(rep, window);
  const fb_study_differences d = fb_study_report_differences(rep, FB_STUDY_CMP_SYSTEM2);
  size_t nvarying = 0, nnotable = 0, crossings = 0;
  for (size_t k = 0; k < s->noutputs; ++k) {
    const int varies = isfinite(c1[k].rel_diff);
    const int notable = varies && c1[k].rel_diff > FB_STUDY_NOTABLE_DIFF;
    nvarying += varies;
    nnotable += notable;
    crossings += varies && notable != (c3[k].rel_diff > FB_STUDY_NOTABLE_DIFF);
    CHECK(fb_study_report_notable(rep, FB_STUDY_CMP_SYSTEM2, k) == notable);
    CHECK(!varies || c1[k].rel_diff <= c1[d.largest].rel_diff);
    const size_t col = fb_run_summary_column(runs[0].sum, k);
    if (c1[k].range1 > 0)
      CHECK_NEAR(fb_study_report_mesh_diff(rep, k),
                 largest_between(runs[0].res, runs[1].res, conv->res, col, window[0]) /
                     c1[k].range1,
                 0.0);
    else
      CHECK(isnan(fb_study_report_mesh_diff(rep, k)));
  }
  CHECK(d.nvarying == nvarying && d.nnotable == nnotable && d.nnotable > 0);
  CHECK(fb_study_report_mesh_crossings(rep) == crossings);
  const size_t kr = fb_study_report_largest_rms_change(rep);
  CHECK(kr < s->noutputs);
  for (size_t k = 0; kr < s->noutputs && k < s->noutputs; ++k)
    CHECK(!isfinite(c1[k].rms_change) || fabs(c1[k].rms_change) <= fabs(c1[kr].rms_change));
}

static void test_report(void)
{
  fb_scenario *s = NULL;
  fb_err err;
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &s, &err) == FB_OK);
  if (!s)
    return;
  s->t_end = 8.5;
  fb_result *r[3] = {NULL, NULL, NULL};
  fb_run_summary *sum[3] = {NULL, NULL, NULL};
  int ok = 1;
  for (size_t i = 0; i < 3; ++i) {
    ok = ok && fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r[i], &err) == FB_OK &&
         fb_run_summary_new(s, r[i], NULL, &sum[i], &err) == FB_OK;
    s->corner[0].spring_k *= 1.5;
    s->corner[3].spring_k *= 1.5;
  }
  CHECK(ok);
  const fb_study_run runs[3] = {{FB_SYSTEM_RIGID, r[0], sum[0], NULL},
                                {FB_SYSTEM_FLEXIBLE, r[1], sum[1], NULL},
                                {FB_SYSTEM_FLEXIBLE, r[2], sum[2], NULL}};
  fb_study_report *rep = NULL;
  CHECK(fb_study_report_new(s, runs, 0, NULL, &rep, &err) == FB_EINVAL && !rep);
  CHECK(fb_study_report_new(s, runs, 3, NULL, &rep, &err) == FB_EINVAL && !rep);
  CHECK(fb_study_report_new(s, runs, 1, &runs[2], &rep, &err) == FB_EINVAL && !rep);
  rep = ok ? report_of(s, runs, 2, &runs[2]) : NULL;
  if (rep) {
    check_findings(s, rep, runs, &runs[2]);
    CHECK(fb_study_report_nruns(rep) == 2 && fb_study_report_run(rep, 2) == NULL);
    CHECK(fb_study_report_converged(rep)->res == r[2]);
    CHECK(fb_study_report_tires_with(rep, &fb_tire_model_bilateral) == s->ncorners);
    double w[2];
    fb_study_report_wheel_window(rep, 1, w);
    CHECK(w[0] == fb_scenario_road_entry(s, 1) && w[1] == fb_scenario_road_exit(s, 1));
    /* The rigid hull does not twist. */
    const size_t t = fb_study_report_torsion_output(rep);
    CHECK(t < s->noutputs && !strcmp(s->output[t].signal, "torsion"));
    CHECK(t < s->noutputs && fb_study_run_max_abs(&runs[0], t) == 0.0);
    CHECK(isnan(fb_study_run_worst_basis_error(&runs[0], s->noutputs, NULL)));
  }
  fb_study_report_free(&rep);
  /* One run: no comparison; the output that grows the most and the
   * tires' extremes, by hand. */
  rep = ok ? report_of(s, runs, 1, NULL) : NULL;
  if (rep) {
    CHECK(!fb_study_report_cmp(rep, FB_STUDY_CMP_SYSTEM2) &&
          !fb_study_report_diff(rep, FB_STUDY_CMP_SYSTEM2));
    CHECK(fb_study_report_differences(rep, FB_STUDY_CMP_SYSTEM2).largest == s->noutputs);
    double factor = 0;
    const size_t g = fb_study_report_largest_growth(rep, &factor);
    CHECK(g < s->noutputs && factor > 1.0);
    for (size_t k = 0; g < s->noutputs && k < s->noutputs; ++k) {
      const fb_output_stats *st = fb_run_summary_output(sum[0], k);
      const double f = st->peak / st->static_value;
      if (fabs(st->static_value) >= FB_STUDY_NOTABLE_DIFF * (st->peak - st->min) && isfinite(f))
        CHECK(f <= factor);
    }
    size_t most = 0, least = 0;
    fb_study_report_contact_extremes(rep, &runs[0], &most, &least);
    for (size_t c = 0; c < s->ncorners; ++c) {
      CHECK(fb_run_summary_contact_ratio(sum[0], c) <=
            fb_run_summary_contact_ratio(sum[0], most));
      CHECK(fb_run_summary_contact(sum[0], c)->min >=
            fb_run_summary_contact(sum[0], least)->min);
    }
  }
  fb_study_report_free(&rep);
  for (size_t i = 0; i < 3; ++i) {
    fb_run_summary_free(&sum[i]);
    fb_result_free(&r[i]);
  }
  fb_scenario_free(&s);
}

int main(void)
{
  test_stats();
  test_summary();
  test_report();
  return check_report("test_study");
}
