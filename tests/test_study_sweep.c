/* SPDX-License-Identifier: BSD-3-Clause */
/* The study layer's parameter sweeps (flexbond/study.h, fb_study_sweep):
 * the grid's order and the metrics' names, a sweep whose cases are made
 * without any file (a clone of the base with a spring scaled) against the
 * same runs made and summarised by hand, threads against one case at a
 * time, outcomes recorded from elsewhere, and a sweep stopped by its
 * front end. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/io.h"
#include "flexbond/study.h"

#include "check.h"

/* The front end of these tests: each case is the base scenario with its
 * front-left spring stiffness scaled by the case's value of the axis
 * "scale" (a number; anything else is a bad value of the case). */
typedef struct front {
  const fb_scenario *base;
  int finished;  /* cases that finished */
  int fail_from; /* finished fails (FB_EIO) from this count on; 0: never */
} front;

static int load_scaled(void *ctx, size_t i, const fb_scenario_override *ov, size_t n,
                       fb_scenario **out, fb_err *err)
{
  (void)i;
  const front *f = ctx;
  char *end = NULL;
  const double scale = n == 1 ? strtod(ov[0].value, &end) : NAN;
  if (n != 1 || end == ov[0].value || *end != '\0') {
    fb_err_set(err, FB_EINVAL, "scale '%s' is not a number", n == 1 ? ov[0].value : "");
    err->source = FB_SOURCE_OVERRIDE;
    return FB_EINVAL;
  }
  const int rc = fb_scenario_clone(f->base, out, err);
  if (rc == FB_OK)
    (*out)->corner[0].spring_k *= scale;
  return rc;
}

static int count_finished(void *ctx, size_t i, fb_err *err)
{
  (void)i;
  front *f = ctx;
  ++f->finished;
  if (f->fail_from > 0 && f->finished >= f->fail_from)
    return fb_err_set(err, FB_EIO, "the journal is full");
  return FB_OK;
}

static fb_scenario *load_base(void)
{
  fb_scenario *s = NULL;
  fb_err err;
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &s, &err) == FB_OK);
  if (s)
    s->t_end = 8.5; /* the last wheel leaves the bump at 8.132 s */
  return s;
}

static fb_study_sweep *scale_sweep(front *f, const char *const *values, size_t nvalues)
{
  const fb_study_sweep_axis axis = {.key = "scale", .values = values, .nvalues = nvalues};
  const fb_study_sweep_ops ops = {.load = load_scaled, .finished = count_finished, .ctx = f};
  fb_study_sweep *sw = NULL;
  fb_err err;
  CHECK(fb_study_sweep_new(f->base, FB_SYSTEM_RIGID, &axis, 1, &ops, &sw, &err) == FB_OK);
  return sw;
}

/* The grid: the first axis varies slowest; the metrics' names and units;
 * what a sweep refuses. */
static void test_grid(const fb_scenario *base)
{
  const char *const a[] = {"1", "2", "3"}, *const b[] = {"x", "y"};
  const fb_study_sweep_axis axes[] = {{"a", a, 3}, {"b", b, 2}};
  front f = {.base = base};
  const fb_study_sweep_ops ops = {.load = load_scaled, .ctx = &f};
  fb_study_sweep *sw = NULL;
  fb_err err;
  CHECK(fb_study_sweep_new(base, FB_SYSTEM_RIGID, axes, 2, &ops, &sw, &err) == FB_OK && sw);
  if (!sw)
    return;
  CHECK(fb_study_sweep_ncases(sw) == 6 && fb_study_sweep_naxes(sw) == 2);
  CHECK(!strcmp(fb_study_sweep_case_value(sw, 1, 0), "1"));
  CHECK(!strcmp(fb_study_sweep_case_value(sw, 1, 1), "y"));
  CHECK(!strcmp(fb_study_sweep_case_value(sw, 4, 0), "3"));
  fb_scenario_override ov[2];
  fb_study_sweep_case_overrides(sw, 3, ov);
  CHECK(!strcmp(ov[0].key, "a") && !strcmp(ov[0].value, "2") && !strcmp(ov[1].value, "y"));
  CHECK(fb_study_sweep_axis_value(sw, 1, 2) == NULL && fb_study_sweep_axis_key(sw, 2) == NULL);
  CHECK(fb_study_sweep_nmetrics(sw) == 3 * base->noutputs + FB_STUDY_SWEEP_NOTHER);
  char name[256], want[256];
  snprintf(want, sizeof want, "%s_rms", base->output[1].name);
  fb_study_sweep_metric_name(sw, 3 + FB_STUDY_SWEEP_RMS, name, sizeof name);
  CHECK(!strcmp(name, want));
  const size_t steps = fb_study_sweep_metric_other(sw, FB_STUDY_SWEEP_SOLVER_STEPS);
  fb_study_sweep_metric_name(sw, steps, name, sizeof name);
  CHECK(!strcmp(name, "solver_steps") && !strcmp(fb_study_sweep_metric_unit(sw, steps), "-"));
  CHECK(!strcmp(fb_study_sweep_metric_unit(
                    sw, fb_study_sweep_metric_other(sw, FB_STUDY_SWEEP_MIN_TIRE_FORCE)),
                "N"));
  /* Nothing has run: every case is to do. */
  fb_study_sweep_case c;
  CHECK(fb_study_sweep_case_get(sw, 5, &c) == 0 && c.status == FB_EINTR && isnan(c.metric[0]));
  fb_study_sweep_free(&sw);
  CHECK(sw == NULL);
  /* No axis, no load function, an axis without values, too many cases. */
  CHECK(fb_study_sweep_new(base, FB_SYSTEM_RIGID, axes, 0, &ops, &sw, &err) == FB_EINVAL);
  const fb_study_sweep_ops none = {.ctx = &f};
  CHECK(fb_study_sweep_new(base, FB_SYSTEM_RIGID, axes, 2, &none, &sw, &err) == FB_EINVAL);
  const fb_study_sweep_axis empty = {"a", a, 0};
  CHECK(fb_study_sweep_new(base, FB_SYSTEM_RIGID, &empty, 1, &ops, &sw, &err) == FB_EINVAL);
  const char **many = calloc(1000, sizeof *many);
  for (size_t v = 0; many && v < 1000; ++v)
    many[v] = "1";
  const fb_study_sweep_axis big[] = {{"a", many, 1000}, {"b", many, 1000}};
  CHECK(many &&
        fb_study_sweep_new(base, FB_SYSTEM_RIGID, big, 2, &ops, &sw, &err) == FB_EINVAL);
  CHECK(sw == NULL && strstr(err.msg, "cases") != NULL);
  free(many);
}

/* A case's metrics are the run summary of its scenario simulated by
 * hand, bit for bit; a bad value fails its case only. */
static void test_run(const fb_scenario *base)
{
  const char *const values[] = {"1", "1.2", "stiff"};
  front f = {.base = base};
  fb_study_sweep *sw = scale_sweep(&f, values, 3);
  if (!sw)
    return;
  fb_err err;
  CHECK(fb_study_sweep_run(sw, 2, &err) == FB_OK);
  CHECK(f.finished == 3);
  fb_study_sweep_case c;
  CHECK(fb_study_sweep_case_get(sw, 2, &c) == 1 && c.status == FB_EINVAL && c.at_value);
  CHECK(c.error && strstr(c.error, "'stiff' is not a number") && isnan(c.metric[0]));
  /* Case 1 by hand. */
  fb_scenario *s = NULL;
  fb_result *r = NULL;
  fb_run_summary *sum = NULL;
  CHECK(fb_scenario_clone(base, &s, &err) == FB_OK);
  if (s) {
    s->corner[0].spring_k *= 1.2;
    CHECK(fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err) == FB_OK);
  }
  CHECK(r && fb_run_summary_new(s, r, NULL, &sum, &err) == FB_OK);
  CHECK(fb_study_sweep_case_get(sw, 1, &c) == 1 && c.status == FB_OK && !c.error);
  for (size_t k = 0; sum && k < base->noutputs; ++k) {
    const fb_output_stats *st = fb_run_summary_output(sum, k);
    CHECK(c.metric[3 * k + FB_STUDY_SWEEP_PEAK] == st->peak);
    CHECK(c.metric[3 * k + FB_STUDY_SWEEP_MIN] == st->min);
    CHECK(c.metric[3 * k + FB_STUDY_SWEEP_RMS] == st->rms);
  }
  const double *other = c.metric + fb_study_sweep_metric_other(sw, 0);
  fb_ride_metrics ride;
  CHECK(sum && fb_run_summary_ride(sum, &ride, NULL, NULL) == 1);
  CHECK(sum && other[FB_STUDY_SWEEP_RIDE_A_W_RMS] == ride.a_w_rms);
  CHECK(sum && other[FB_STUDY_SWEEP_RIDE_ABSORBED_POWER] == ride.absorbed_power &&
        other[FB_STUDY_SWEEP_RIDE_NRMM_PEAK] == ride.nrmm_peak &&
        other[FB_STUDY_SWEEP_RIDE_SE] == ride.se && other[FB_STUDY_SWEEP_RIDE_DZ] == ride.dz &&
        other[FB_STUDY_SWEEP_RIDE_VDV_RATIO] == ride.vdv_ratio &&
        other[FB_STUDY_SWEEP_RIDE_CREST_OVER_9] == ride.crest_over_9);
  CHECK(r && other[FB_STUDY_SWEEP_SOLVER_STEPS] == (double)fb_result_stats(r)->steps);
  CHECK(other[FB_STUDY_SWEEP_MIN_TIRE_FORCE] > 0 &&
        other[FB_STUDY_SWEEP_CONTACT_LOSS_INTERVALS] == 0);
  /* The stiffer spring shows in the front-left tire. */
  fb_study_sweep_case c0;
  fb_study_sweep_case_get(sw, 0, &c0);
  CHECK(c0.status == FB_OK && c0.metric[0] != c.metric[0]);
  /* One case at a time on this thread: the same numbers. */
  front g = {.base = base};
  fb_study_sweep *one = scale_sweep(&g, values, 3);
  for (size_t i = 0; one && i < 3; ++i) {
    fb_study_sweep_run_case(one, i);
    fb_study_sweep_case d;
    fb_study_sweep_case_get(one, i, &d);
    fb_study_sweep_case_get(sw, i, &c);
    CHECK(d.status == c.status);
    for (size_t m = 0; m < fb_study_sweep_nmetrics(sw); ++m)
      CHECK(d.metric[m] == c.metric[m] || (isnan(d.metric[m]) && isnan(c.metric[m])));
  }
  CHECK(g.finished == 0); /* run_case leaves finishing to its caller */
  fb_study_sweep_free(&one);
  fb_run_summary_free(&sum);
  fb_result_free(&r);
  fb_scenario_free(&s);
  fb_study_sweep_free(&sw);
}

/* Outcomes computed elsewhere (a journal, another process) are recorded,
 * and the pool runs only the others; a stopped case is not done. */
static void test_record(const fb_scenario *base)
{
  const char *const values[] = {"1", "1.1", "1.2"};
  front f = {.base = base};
  fb_study_sweep *sw = scale_sweep(&f, values, 3);
  if (!sw)
    return;
  const size_t nm = fb_study_sweep_nmetrics(sw);
  double *m = calloc(nm, sizeof *m);
  const fb_study_sweep_case elsewhere = {
      .status = FB_OK, .metric = m, .wall_seconds = NAN, .worker = 3};
  fb_study_sweep_record(sw, 1, &elsewhere);
  const fb_study_sweep_case stopped = {.status = FB_EINTR, .error = "interrupted"};
  fb_study_sweep_record(sw, 2, &stopped);
  CHECK(fb_study_sweep_case_done(sw, 1) && !fb_study_sweep_case_done(sw, 2));
  size_t i = 9;
  CHECK(fb_study_sweep_next(sw, &i) == 1 && i == 0);
  CHECK(fb_study_sweep_next(sw, &i) == 1 && i == 2); /* 1 is done */
  CHECK(fb_study_sweep_next(sw, &i) == 0);
  CHECK(fb_study_sweep_finish(sw, 1) == FB_OK && f.finished == 1);
  CHECK(fb_study_sweep_finish(sw, 2) == FB_OK && f.finished == 1); /* not done: no report */
  fb_study_sweep_case c;
  CHECK(fb_study_sweep_case_get(sw, 1, &c) == 1 && c.worker == 3 && m && c.metric[0] == 0);
  CHECK(fb_study_sweep_case_get(sw, 2, &c) == 0 && c.error == NULL);
  free(m);
  fb_study_sweep_free(&sw);
}

/* A cancelled sweep runs nothing; one whose front end fails at the first
 * finished case (a journal that cannot be written) starts no other. */
static void test_stop(const fb_scenario *base)
{
  const char *const values[] = {"1", "1.1", "1.2", "1.3"};
  front f = {.base = base};
  fb_study_sweep *sw = scale_sweep(&f, values, 4);
  fb_err err;
  if (sw) {
    fb_study_sweep_cancel(sw);
    CHECK(fb_study_sweep_run(sw, 2, &err) == FB_EINTR && f.finished == 0);
    CHECK(strstr(err.msg, "4 of 4 cases not run") != NULL);
    fb_study_sweep_free(&sw);
  }
  front g = {.base = base, .fail_from = 1};
  sw = scale_sweep(&g, values, 4);
  if (sw) {
    CHECK(fb_study_sweep_run(sw, 1, &err) == FB_EIO && !strcmp(err.msg, "the journal is full"));
    CHECK(g.finished == 1 && fb_study_sweep_case_done(sw, 0) &&
          !fb_study_sweep_case_done(sw, 1));
    fb_study_sweep_free(&sw);
  }
}

/* The io layer's cases from a file: the study of a scenario file with one
 * override of its own and the case's, as loaded by hand. */
static void test_file_cases(void)
{
  const fb_scenario_override own[] = {{.key = "t_end", .value = "8.5"}};
  const fb_scenario_sweep_source src = {
      .path = "../examples/apc6x6.yaml", .overrides = own, .noverrides = 1};
  fb_study_sweep_ops ops;
  fb_scenario_sweep_ops(&src, &ops);
  fb_scenario *base = NULL;
  fb_err err;
  CHECK(fb_scenario_load_overrides(src.path, own, 1, &base, &err) == FB_OK);
  const char *const values[] = {"12", "-3"};
  const fb_study_sweep_axis axis = {.key = "speed_kmh", .values = values, .nvalues = 2};
  fb_study_sweep *sw = NULL;
  CHECK(base && fb_study_sweep_new(base, FB_SYSTEM_RIGID, &axis, 1, &ops, &sw, &err) == FB_OK);
  CHECK(sw && fb_study_sweep_run(sw, 2, &err) == FB_OK);
  fb_study_sweep_case c;
  /* -3 km/h: the reader's error, located at the override. */
  CHECK(sw && fb_study_sweep_case_get(sw, 1, &c) == 1 && c.status == FB_EINVAL && c.at_value);
  CHECK(sw && c.error && strstr(c.error, "--set speed_kmh=-3") != NULL);
  const fb_scenario_override both[] = {own[0], {.key = "speed_kmh", .value = "12"}};
  fb_scenario *s = NULL;
  fb_result *r = NULL;
  CHECK(fb_scenario_load_overrides(src.path, both, 2, &s, &err) == FB_OK);
  CHECK(s && fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err) == FB_OK);
  CHECK(sw && r && fb_study_sweep_case_get(sw, 0, &c) == 1 && c.status == FB_OK);
  CHECK(sw && r &&
        c.metric[fb_study_sweep_metric_other(sw, FB_STUDY_SWEEP_SOLVER_STEPS)] ==
            (double)fb_result_stats(r)->steps);
  fb_result_free(&r);
  fb_scenario_free(&s);
  fb_study_sweep_free(&sw);
  fb_scenario_free(&base);
}

int main(void)
{
  fb_scenario *base = load_base();
  if (base) {
    test_grid(base);
    test_run(base);
    test_record(base);
    test_stop(base);
  }
  test_file_cases();
  fb_scenario_free(&base);
  return check_report("test_study_sweep");
}
