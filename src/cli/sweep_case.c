/* SPDX-License-Identifier: BSD-3-Clause */
/* The cases of flexbond sweep (sweep.h): each loads the scenario with its
 * values replacing the file's (fb_scenario_load_overrides, so the reader
 * checks and converts them as its own), simulates one system and reduces
 * the run to metrics: the summary.json statistics of the paper's seven
 * outputs, the tire contact, the driver's ride metrics (the study layer's
 * run summary, fb_run_summary_new) and the solver's work; and sweep.csv's
 * rows. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/escape.h"
#include "flexbond/fem.h"
#include "flexbond/ride.h"
#include "flexbond/sim.h"

#include "../core/textfile.h"
#include "cli.h"
#include "sweep.h"

static const char *const stat_names[SWEEP_NSTATS] = {"peak", "min", "rms"};
static const struct {
  const char *name, *unit;
} other_metrics[SWEEP_NOTHER] = {
    {"min_tire_force", "N"},     {"contact_loss_intervals", "-"}, {"ride_a_w_rms", "m/s^2"},
    {"ride_mtvv", "m/s^2"},      {"ride_vdv", "m/s^1.75"},        {"ride_crest_factor", "-"},
    {"ride_jerk_peak", "m/s^3"}, {"ride_jerk_rms", "m/s^3"},      {"solver_steps", "-"},
};

size_t sweep_metric_other(const sweep_args *a, size_t m)
{
  return SWEEP_NSTATS * a->base->noutputs + m;
}

/* Name of metric m ("tire_force_LF_peak") into buf. */
void sweep_metric_name(const sweep_args *a, size_t m, char *buf, size_t size)
{
  const size_t nstat = SWEEP_NSTATS * a->base->noutputs;
  if (m < nstat)
    snprintf(buf, size, "%s_%s", a->base->output[m / SWEEP_NSTATS].name,
             stat_names[m % SWEEP_NSTATS]);
  else
    snprintf(buf, size, "%s", other_metrics[m - nstat].name);
}

const char *sweep_metric_unit(const sweep_args *a, size_t m)
{
  const size_t nstat = SWEEP_NSTATS * a->base->noutputs;
  if (m >= nstat)
    return other_metrics[m - nstat].unit;
  const char *unit = a->base->output[m / SWEEP_NSTATS].unit;
  return unit ? unit : "-"; /* a bond's: its domain's, known after the build */
}

int sweep_metric_find(const sweep_args *a, const char *spec, size_t *m)
{
  const char *colon = strchr(spec, ':');
  const size_t len = colon ? (size_t)(colon - spec) : strlen(spec);
  for (size_t k = 0; colon && k < a->base->noutputs; ++k)
    for (size_t st = 0; st < SWEEP_NSTATS; ++st)
      if (strlen(a->base->output[k].name) == len &&
          !strncmp(a->base->output[k].name, spec, len) && !strcmp(colon + 1, stat_names[st])) {
        *m = SWEEP_NSTATS * k + st;
        return 0;
      }
  if (colon)
    return -1;
  for (size_t k = 0; k < a->base->noutputs; ++k)
    if (!strcmp(a->base->output[k].name, spec)) {
      *m = SWEEP_NSTATS * k + SWEEP_STAT_PEAK;
      return 0;
    }
  for (size_t i = 0; i < a->nmetrics; ++i) {
    char name[FB_ERR_KEY_MAX];
    sweep_metric_name(a, i, name, sizeof name);
    if (!strcmp(name, spec)) {
      *m = i;
      return 0;
    }
  }
  return -1;
}

void sweep_default_plots(sweep_args *a)
{
  a->nplots = 0;
  if (a->base->noutputs > 0)
    a->plot[a->nplots++] = SWEEP_STAT_PEAK;
  a->plot[a->nplots++] = sweep_metric_other(a, M_MIN_TIRE_FORCE);
  if (fb_study_ride_output(a->base) < a->base->noutputs)
    a->plot[a->nplots++] = sweep_metric_other(a, M_RIDE_A_W_RMS);
  a->plot[a->nplots++] = sweep_metric_other(a, M_CONTACT_LOSS_INTERVALS);
}

/* Index of key k's value in case i: the first key varies slowest. */
size_t sweep_value_index(const sweep_args *a, size_t i, size_t k)
{
  for (size_t j = a->nkeys; j-- > k + 1;)
    i /= a->keys[j].nvalues;
  return i % a->keys[k].nvalues;
}

/* "key=value, key=value" of case i into buf. */
void sweep_case_label(const sweep_args *a, size_t i, size_t first_key, char *buf, size_t size)
{
  size_t len = 0;
  buf[0] = '\0';
  for (size_t k = first_key; k < a->nkeys && len + 1 < size; ++k) {
    len = fb_text_append(buf, size, len, "%s%s=%s", k > first_key ? ", " : "", a->keys[k].key,
                         a->keys[k].values[sweep_value_index(a, i, k)]);
  }
}

/* The ride metrics of the summary (the first mounted body's acceleration
 * over [first bump entry, end of the run], as run puts them in
 * summary.json) into m (the other metrics); NaN when there are none: a
 * missing metric, not a failed case. */
static void ride_metrics(const fb_run_summary *sum, double *m)
{
  for (size_t k = M_RIDE_A_W_RMS; k <= M_RIDE_JERK_RMS; ++k)
    m[k] = NAN;
  fb_ride_metrics ride;
  if (!fb_run_summary_ride(sum, &ride, NULL, NULL))
    return;
  m[M_RIDE_A_W_RMS] = ride.a_w_rms;
  m[M_RIDE_MTVV] = ride.mtvv;
  m[M_RIDE_VDV] = ride.vdv;
  m[M_RIDE_CREST_FACTOR] = ride.crest;
  m[M_RIDE_JERK_PEAK] = ride.jerk_peak;
  m[M_RIDE_JERK_RMS] = ride.jerk_rms;
}

/* The smallest normal reaction of any tire from the first bump entry to
 * the end of the run (not from t = 0: under `initial: zero` every tire
 * starts unloaded, at 0 N), and the contact-loss intervals that end after
 * the first bump entry. */
static void contact_metrics(const fb_scenario *s, const fb_run_summary *sum, double *min_force,
                            double *nloss)
{
  double window[2];
  fb_run_summary_window(sum, window);
  *min_force = INFINITY;
  for (size_t c = 0; c < s->ncorners; ++c)
    *min_force = fmin(*min_force, fb_run_summary_contact(sum, c)->min);
  size_t count = 0;
  for (size_t i = 0; i < fb_run_summary_nlosses(sum); ++i)
    count += fb_run_summary_loss(sum, i)->t_end >= window[0];
  *nloss = (double)count;
}

/* Every metric of a successful run r of scenario s into m. The case's
 * outputs must be the study's: an override may rename one (a corner's
 * name, an output's `of`), which would shift sweep.csv's columns. */
static int case_metrics(const sweep_args *a, const fb_scenario *s, const fb_result *r,
                        double *m, fb_err *err)
{
  if (s->noutputs != a->base->noutputs)
    return fb_err_set(err, FB_EINVAL, "sweep: the case has %zu outputs, the study %zu",
                      s->noutputs, a->base->noutputs);
  for (size_t k = 0; k < s->noutputs; ++k)
    if (strcmp(s->output[k].name, a->base->output[k].name) != 0)
      return fb_err_set(err, FB_EINVAL,
                        "sweep: the case's output %zu is '%s', the study's '%s': a swept "
                        "value may not rename an output",
                        k + 1, s->output[k].name, a->base->output[k].name);
  fb_run_summary *sum = NULL;
  const int rc = fb_run_summary_new(s, r, NULL, &sum, err);
  if (rc)
    return fb_err_prefix(err, "sweep: "), rc;
  for (size_t k = 0; k < s->noutputs; ++k) {
    const fb_output_stats *st = fb_run_summary_output(sum, k);
    m[SWEEP_NSTATS * k + SWEEP_STAT_PEAK] = st->peak;
    m[SWEEP_NSTATS * k + SWEEP_STAT_MIN] = st->min;
    m[SWEEP_NSTATS * k + SWEEP_STAT_RMS] = st->rms;
  }
  double *other = m + sweep_metric_other(a, 0);
  other[M_SOLVER_STEPS] = (double)fb_result_stats(r)->steps;
  ride_metrics(sum, other);
  contact_metrics(s, sum, &other[M_MIN_TIRE_FORCE], &other[M_CONTACT_LOSS_INTERVALS]);
  fb_run_summary_free(&sum);
  return FB_OK;
}

/* fb_sim_progress_fn: stops a case's simulation once interrupted. */
static int stop_when_interrupted(void *ctx, double t, double t_end)
{
  (void)ctx;
  (void)t;
  (void)t_end;
  return cli_interrupted();
}

static int simulate_case(const sweep_args *a, const fb_scenario *s, fb_result **res,
                         fb_err *err)
{
  return fb_vehicle_simulate_progress(s, a->sys, stop_when_interrupted, NULL, res, err);
}

void sweep_run_case(const sweep_args *a, size_t i, sweep_case *c)
{
  fb_scenario_override ov[SWEEP_MAX_KEYS];
  for (size_t k = 0; k < a->nkeys; ++k)
    ov[k] = (fb_scenario_override){.key = a->keys[k].key,
                                   .value = a->keys[k].values[sweep_value_index(a, i, k)]};
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  fb_result *res = NULL;
  c->wall_seconds = NAN;
  int rc = fb_scenario_load_overrides(a->scenario_path, ov, a->nkeys, &s, &err);
  /* The scenario's warnings were said once, at the start; a case says
   * those about its own swept values (located at the --set), and under
   * --strict such a value fails the case, as any bad input of a case. */
  if (rc == FB_OK && a->strict)
    rc = cli_scenario_warnings(s, 1, &err);
  for (size_t w = 0; rc == FB_OK && !a->quiet && w < fb_scenario_nwarnings(s); ++w)
    if (fb_scenario_warning(s, w)->source == FB_SOURCE_OVERRIDE)
      cli_say("flexbond: warning: case %zu: %s", i + 1, fb_scenario_warning(s, w)->msg);
  if (rc == FB_OK)
    rc = simulate_case(a, s, &res, &err);
  if (rc == FB_OK) {
    c->wall_seconds = fb_result_stats(res)->wall_seconds;
    rc = case_metrics(a, s, res, c->metric, &err);
  }
  c->status = rc;
  c->error = NULL;
  /* The reader sets the source of an error about a value a --set
   * replaced (fb_scenario_load_overrides). */
  if (rc != FB_OK && s)
    fb_scenario_locate(s, &err);
  c->at_value = rc != FB_OK && err.source == FB_SOURCE_OVERRIDE;
  if (rc != FB_OK) {
    for (size_t m = 0; m < a->nmetrics; ++m)
      c->metric[m] = NAN;
    /* Never an empty error: sweep.csv, the journal and the MPI result
     * tell a failed case by it. */
    if (!err.msg[0])
      snprintf(err.msg, sizeof err.msg, "failed (%s) without a message", fb_status_name(rc));
    c->error = malloc(strlen(err.msg) + 1);
    if (c->error)
      memcpy(c->error, err.msg, strlen(err.msg) + 1);
  }
  fb_result_free(&res);
  fb_scenario_free(&s);
}

/* ---- sweep.csv */

/* Value as a number if the whole text is one: the specs' numbers, the x
 * axis, the journal's metrics. fb_parse_decimal, as the data files and the
 * other options read numbers: strtod alone takes "0x10", "inf" and "nan". */
int sweep_numeric_value(const char *text, double *out)
{
  return fb_parse_decimal(text, out, NULL) == FB_OK;
}

void sweep_format_double(double x, char *buf, size_t size)
{
  fb_format_shortest(x, 15, buf, size);
}

/* The fields go through fb_csv_write_field (flexbond/escape.h, RFC 4180
 * quoting). The keys are text, guarded against being read as spreadsheet
 * formulas (FB_CSV_TEXT). The keys' values are not guarded: the journal
 * (sweep_journal.c) compares them with the study's byte for byte on
 * resuming, and most are numbers, "-1" among them. Nor are the errors:
 * each starts with flexbond's own words ("--set KEY=VALUE: ..."), and a '
 * would come before every one (docs/outputs.md). */
void sweep_key_label(const sweep_args *a, size_t k, char *buf, size_t size)
{
  const char *unit = fb_scenario_key_unit(a->keys[k].path);
  if (unit)
    snprintf(buf, size, "%s [%s]", a->keys[k].key, unit);
  else
    snprintf(buf, size, "%s", a->keys[k].key);
}

void sweep_csv_header(FILE *fp, const sweep_args *a, fb_csv_header header)
{
  for (size_t k = 0; k < a->nkeys; ++k) {
    char cell[FB_ERR_KEY_MAX + 64];
    if (header == FB_CSV_HEADER_UNITS)
      sweep_key_label(a, k, cell, sizeof cell);
    else
      snprintf(cell, sizeof cell, "%s", a->keys[k].key);
    fb_csv_write_field(fp, cell, FB_CSV_TEXT);
    fputc(',', fp);
  }
  for (size_t m = 0; m < a->nmetrics; ++m) {
    char name[FB_ERR_KEY_MAX], cell[FB_ERR_KEY_MAX + 64];
    sweep_metric_name(a, m, name, sizeof name);
    const char *unit = sweep_metric_unit(a, m);
    /* "-": a count or a ratio, no unit to give. */
    if (header == FB_CSV_HEADER_UNITS && strcmp(unit, "-") != 0)
      snprintf(cell, sizeof cell, "%s [%s]", name, unit);
    else
      snprintf(cell, sizeof cell, "%s", name);
    fb_csv_write_field(fp, cell, FB_CSV_TEXT);
    fputc(',', fp);
  }
  fputs("error\n", fp);
}

/* The keys' values, the metrics (empty when not finite or failed) and
 * the error. */
void sweep_csv_row(FILE *fp, const sweep_args *a, size_t i, const sweep_case *c)
{
  for (size_t k = 0; k < a->nkeys; ++k) {
    fb_csv_write_field(fp, a->keys[k].values[sweep_value_index(a, i, k)], 0);
    fputc(',', fp);
  }
  for (size_t m = 0; m < a->nmetrics; ++m) {
    if (isfinite(c->metric[m])) {
      char text[32];
      sweep_format_double(c->metric[m], text, sizeof text);
      fputs(text, fp);
    }
    fputc(',', fp);
  }
  if (c->status != FB_OK)
    fb_csv_write_field(fp, c->error ? c->error : "out of memory", 0);
  fputc('\n', fp);
}
