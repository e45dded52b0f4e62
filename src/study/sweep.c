/* SPDX-License-Identifier: BSD-3-Clause */
/* The study layer's parameter sweeps (flexbond/study.h): the grid of
 * cases, each case made by the front end (ops->load), simulated and
 * reduced to the metrics of the run summary (fb_run_summary_new), and the
 * pool of threads that runs them. Cases are handed out one at a time in
 * grid order to whichever thread asks next, so long and short cases
 * balance; a finished case goes to ops->finished under one lock. Each
 * case's eigen-solve and simulation are its own (the solvers hold no
 * shared state), so cases run at once on any hull. */
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/study.h"

static const char *const stat_names[FB_STUDY_SWEEP_NSTATS] = {"peak", "min", "rms"};
static const struct {
  const char *name, *unit;
} other_metrics[FB_STUDY_SWEEP_NOTHER] = {
    {"min_tire_force", "N"},      {"contact_loss_intervals", "-"},
    {"ride_a_w_rms", "m/s^2"},    {"ride_mtvv", "m/s^2"},
    {"ride_vdv", "m/s^1.75"},     {"ride_crest_factor", "-"},
    {"ride_jerk_peak", "m/s^3"},  {"ride_jerk_rms", "m/s^3"},
    {"ride_absorbed_power", "W"}, {"ride_nrmm_peak", "m/s^2"},
    {"ride_se", "MPa"},           {"ride_dz", "m/s^2"},
    {"ride_vdv_ratio", "-"},      {"ride_crest_over_9", "-"},
    {"solver_steps", "-"},
};

/* A case's outcome; its metrics are the sweep's row i. */
typedef struct sweep_case {
  int done, status, at_value, worker;
  double wall_seconds;
  char *error; /* owned; NULL when ok or out of memory */
} sweep_case;

struct fb_study_sweep {
  const fb_scenario *base; /* borrowed */
  fb_system sys;
  fb_study_sweep_ops ops;
  size_t naxes, ncases, nmetrics;
  char *key[FB_STUDY_SWEEP_MAX_AXES];    /* owned */
  char **value[FB_STUDY_SWEEP_MAX_AXES]; /* owned, nvalues[k] each */
  size_t nvalues[FB_STUDY_SWEEP_MAX_AXES];
  sweep_case *cases;    /* ncases */
  double *metric;       /* ncases x nmetrics */
  pthread_mutex_t lock; /* next, the cases' outcomes, stop_rc, ops->finished */
  size_t next;          /* the first case not handed out */
  int stop_rc;          /* the first failure of ops->finished */
  fb_err stop_err;
  atomic_int cancelled;
};

/* ---- The grid. */

static char *copy_text(const char *text)
{
  const size_t n = strlen(text) + 1;
  char *out = malloc(n);
  if (out)
    memcpy(out, text, n);
  return out;
}

static int copy_axis(fb_study_sweep *sw, size_t k, const fb_study_sweep_axis *axis, fb_err *err)
{
  if (!axis->key || axis->nvalues == 0)
    return fb_err_set(err, FB_EINVAL, "sweep: axis %zu has %s", k + 1,
                      axis->key ? "no value" : "no key");
  sw->key[k] = copy_text(axis->key);
  sw->value[k] = calloc(axis->nvalues, sizeof *sw->value[k]);
  if (!sw->key[k] || !sw->value[k])
    return fb_err_set(err, FB_ENOMEM, "sweep: out of memory for axis %s", axis->key);
  sw->nvalues[k] = axis->nvalues;
  for (size_t v = 0; v < axis->nvalues; ++v)
    if (!(sw->value[k][v] = copy_text(axis->values[v])))
      return fb_err_set(err, FB_ENOMEM, "sweep: out of memory for axis %s", axis->key);
  return FB_OK;
}

/* The product of the axes' counts into *ncases, refused above
 * FB_STUDY_SWEEP_MAX_CASES; formed in a double, which holds 16 axes of
 * any count a front end can hold, where a size_t would wrap. */
static int count_cases(const fb_study_sweep_axis *axes, size_t naxes, size_t *ncases,
                       fb_err *err)
{
  double n = 1;
  for (size_t k = 0; k < naxes; ++k)
    n *= (double)axes[k].nvalues;
  if (n > (double)FB_STUDY_SWEEP_MAX_CASES)
    return fb_err_set(err, FB_EINVAL, "sweep: %.3g cases, more than the %zu a sweep may have",
                      n, FB_STUDY_SWEEP_MAX_CASES);
  *ncases = (size_t)n;
  return FB_OK;
}

/* Room for the cases, none done, every metric NaN. */
static int alloc_cases(fb_study_sweep *sw, fb_err *err)
{
  sw->cases = calloc(sw->ncases, sizeof *sw->cases);
  sw->metric = malloc(sw->ncases * sw->nmetrics * sizeof *sw->metric);
  if (!sw->cases || !sw->metric)
    return fb_err_set(err, FB_ENOMEM, "sweep: out of memory for %zu cases", sw->ncases);
  for (size_t j = 0; j < sw->ncases * sw->nmetrics; ++j)
    sw->metric[j] = NAN;
  for (size_t i = 0; i < sw->ncases; ++i)
    sw->cases[i] = (sweep_case){.status = FB_EINTR, .wall_seconds = NAN};
  return FB_OK;
}

int fb_study_sweep_new(const fb_scenario *base, fb_system sys, const fb_study_sweep_axis *axes,
                       size_t naxes, const fb_study_sweep_ops *ops, fb_study_sweep **out,
                       fb_err *err)
{
  *out = NULL;
  if (naxes == 0 || naxes > FB_STUDY_SWEEP_MAX_AXES)
    return fb_err_set(err, FB_EINVAL, "sweep: %zu axes (1 to %d)", naxes,
                      FB_STUDY_SWEEP_MAX_AXES);
  if (!ops || !ops->load)
    return fb_err_set(err, FB_EINVAL, "sweep: no function makes a case's scenario");
  size_t ncases = 0;
  int rc = count_cases(axes, naxes, &ncases, err);
  if (rc != FB_OK)
    return rc;
  fb_study_sweep *sw = calloc(1, sizeof *sw);
  if (!sw)
    return fb_err_set(err, FB_ENOMEM, "sweep: out of memory");
  *sw = (fb_study_sweep){.base = base, .sys = sys, .ops = *ops, .ncases = ncases};
  sw->nmetrics = FB_STUDY_SWEEP_NSTATS * base->noutputs + FB_STUDY_SWEEP_NOTHER;
  pthread_mutex_init(&sw->lock, NULL);
  atomic_init(&sw->cancelled, 0);
  fb_err_clear(&sw->stop_err);
  for (size_t k = 0; rc == FB_OK && k < naxes; ++k) {
    sw->naxes = k + 1; /* what free releases */
    rc = copy_axis(sw, k, &axes[k], err);
  }
  if (rc == FB_OK)
    rc = alloc_cases(sw, err);
  if (rc != FB_OK) {
    fb_study_sweep_free(&sw);
    return rc;
  }
  *out = sw;
  return FB_OK;
}

void fb_study_sweep_free(fb_study_sweep **sw)
{
  if (!sw || !*sw)
    return;
  fb_study_sweep *s = *sw;
  for (size_t k = 0; k < s->naxes; ++k) {
    for (size_t v = 0; s->value[k] && v < s->nvalues[k]; ++v)
      free(s->value[k][v]);
    free(s->value[k]);
    free(s->key[k]);
  }
  for (size_t i = 0; s->cases && i < s->ncases; ++i)
    free(s->cases[i].error);
  free(s->cases);
  free(s->metric);
  pthread_mutex_destroy(&s->lock);
  free(s);
  *sw = NULL;
}

size_t fb_study_sweep_ncases(const fb_study_sweep *sw)
{
  return sw->ncases;
}

size_t fb_study_sweep_naxes(const fb_study_sweep *sw)
{
  return sw->naxes;
}

size_t fb_study_sweep_nmetrics(const fb_study_sweep *sw)
{
  return sw->nmetrics;
}

const char *fb_study_sweep_axis_key(const fb_study_sweep *sw, size_t k)
{
  return k < sw->naxes ? sw->key[k] : NULL;
}

size_t fb_study_sweep_axis_nvalues(const fb_study_sweep *sw, size_t k)
{
  return k < sw->naxes ? sw->nvalues[k] : 0;
}

const char *fb_study_sweep_axis_value(const fb_study_sweep *sw, size_t k, size_t v)
{
  return k < sw->naxes && v < sw->nvalues[k] ? sw->value[k][v] : NULL;
}

size_t fb_study_sweep_value_index(const fb_study_sweep *sw, size_t i, size_t k)
{
  for (size_t j = sw->naxes; j-- > k + 1;)
    i /= sw->nvalues[j];
  return i % sw->nvalues[k];
}

const char *fb_study_sweep_case_value(const fb_study_sweep *sw, size_t i, size_t k)
{
  return k < sw->naxes ? sw->value[k][fb_study_sweep_value_index(sw, i, k)] : NULL;
}

void fb_study_sweep_case_overrides(const fb_study_sweep *sw, size_t i, fb_scenario_override *ov)
{
  for (size_t k = 0; k < sw->naxes; ++k)
    ov[k] =
        (fb_scenario_override){.key = sw->key[k], .value = fb_study_sweep_case_value(sw, i, k)};
}

/* ---- The metrics. */

size_t fb_study_sweep_metric_other(const fb_study_sweep *sw, size_t m)
{
  return FB_STUDY_SWEEP_NSTATS * sw->base->noutputs + m;
}

void fb_study_sweep_metric_name(const fb_study_sweep *sw, size_t m, char *buf, size_t size)
{
  const size_t nstat = FB_STUDY_SWEEP_NSTATS * sw->base->noutputs;
  if (m < nstat)
    snprintf(buf, size, "%s_%s", sw->base->output[m / FB_STUDY_SWEEP_NSTATS].name,
             stat_names[m % FB_STUDY_SWEEP_NSTATS]);
  else if (m < sw->nmetrics)
    snprintf(buf, size, "%s", other_metrics[m - nstat].name);
  else if (size > 0)
    buf[0] = '\0';
}

const char *fb_study_sweep_metric_unit(const fb_study_sweep *sw, size_t m)
{
  const size_t nstat = FB_STUDY_SWEEP_NSTATS * sw->base->noutputs;
  if (m >= sw->nmetrics)
    return "-";
  if (m >= nstat)
    return other_metrics[m - nstat].unit;
  const char *unit = sw->base->output[m / FB_STUDY_SWEEP_NSTATS].unit;
  return unit ? unit : "-"; /* a bond's: its domain's, known after the build */
}

/* Where each ride metric column finds its value in fb_ride_metrics. */
static const struct {
  size_t metric, offset;
} ride_columns[] = {
    {FB_STUDY_SWEEP_RIDE_A_W_RMS, offsetof(fb_ride_metrics, a_w_rms)},
    {FB_STUDY_SWEEP_RIDE_MTVV, offsetof(fb_ride_metrics, mtvv)},
    {FB_STUDY_SWEEP_RIDE_VDV, offsetof(fb_ride_metrics, vdv)},
    {FB_STUDY_SWEEP_RIDE_CREST_FACTOR, offsetof(fb_ride_metrics, crest)},
    {FB_STUDY_SWEEP_RIDE_JERK_PEAK, offsetof(fb_ride_metrics, jerk_peak)},
    {FB_STUDY_SWEEP_RIDE_JERK_RMS, offsetof(fb_ride_metrics, jerk_rms)},
    {FB_STUDY_SWEEP_RIDE_ABSORBED_POWER, offsetof(fb_ride_metrics, absorbed_power)},
    {FB_STUDY_SWEEP_RIDE_NRMM_PEAK, offsetof(fb_ride_metrics, nrmm_peak)},
    {FB_STUDY_SWEEP_RIDE_SE, offsetof(fb_ride_metrics, se)},
    {FB_STUDY_SWEEP_RIDE_DZ, offsetof(fb_ride_metrics, dz)},
    {FB_STUDY_SWEEP_RIDE_VDV_RATIO, offsetof(fb_ride_metrics, vdv_ratio)},
    {FB_STUDY_SWEEP_RIDE_CREST_OVER_9, offsetof(fb_ride_metrics, crest_over_9)},
};

/* The ride metrics of the summary into m (the other metrics); NaN when
 * there are none: a missing metric, not a failed case. */
static void ride_metrics(const fb_run_summary *sum, double *m)
{
  fb_ride_metrics ride;
  const int has = fb_run_summary_ride(sum, &ride, NULL, NULL);
  for (size_t i = 0; i < sizeof ride_columns / sizeof ride_columns[0]; ++i) {
    double value = NAN;
    if (has)
      memcpy(&value, (const char *)&ride + ride_columns[i].offset, sizeof value);
    m[ride_columns[i].metric] = value;
  }
}

/* The smallest normal reaction of any tire from the window's start to the
 * end of the run (not from t = 0: under `initial: zero` every tire starts
 * unloaded, at 0 N), and the contact-loss intervals that end after the
 * window's start. */
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

/* The case's outputs must be the sweep's: a swept value may rename one
 * (a corner's name, an output's `of`), which would shift the columns. */
static int same_outputs(const fb_study_sweep *sw, const fb_scenario *s, fb_err *err)
{
  if (s->noutputs != sw->base->noutputs)
    return fb_err_set(err, FB_EINVAL, "sweep: the case has %zu outputs, the study %zu",
                      s->noutputs, sw->base->noutputs);
  for (size_t k = 0; k < s->noutputs; ++k)
    if (strcmp(s->output[k].name, sw->base->output[k].name) != 0)
      return fb_err_set(err, FB_EINVAL,
                        "sweep: the case's output %zu is '%s', the study's '%s': a swept "
                        "value may not rename an output",
                        k + 1, s->output[k].name, sw->base->output[k].name);
  return FB_OK;
}

/* Every metric of a successful run r of case scenario s into m. */
static int case_metrics(const fb_study_sweep *sw, const fb_scenario *s, const fb_result *r,
                        double *m, fb_err *err)
{
  int rc = same_outputs(sw, s, err);
  fb_run_summary *sum = NULL;
  if (rc == FB_OK && (rc = fb_run_summary_new(s, r, NULL, &sum, err)) != FB_OK)
    fb_err_prefix(err, "sweep: ");
  if (rc != FB_OK)
    return rc;
  for (size_t k = 0; k < s->noutputs; ++k) {
    const fb_output_stats *st = fb_run_summary_output(sum, k);
    m[FB_STUDY_SWEEP_NSTATS * k + FB_STUDY_SWEEP_PEAK] = st->peak;
    m[FB_STUDY_SWEEP_NSTATS * k + FB_STUDY_SWEEP_MIN] = st->min;
    m[FB_STUDY_SWEEP_NSTATS * k + FB_STUDY_SWEEP_RMS] = st->rms;
  }
  double *other = m + fb_study_sweep_metric_other(sw, 0);
  other[FB_STUDY_SWEEP_SOLVER_STEPS] = (double)fb_result_stats(r)->steps;
  ride_metrics(sum, other);
  contact_metrics(s, sum, &other[FB_STUDY_SWEEP_MIN_TIRE_FORCE],
                  &other[FB_STUDY_SWEEP_CONTACT_LOSS_INTERVALS]);
  fb_run_summary_free(&sum);
  return FB_OK;
}

/* ---- Running a case. */

static int stopped(fb_study_sweep *sw)
{
  return atomic_load(&sw->cancelled) || (sw->ops.stop && sw->ops.stop(sw->ops.ctx));
}

/* fb_sim_progress_fn: a case's simulation stops with the sweep. */
static int case_progress(void *ctx, double t, double t_end)
{
  (void)t;
  (void)t_end;
  return stopped(ctx);
}

/* Stores case i's outcome (error owned from here on) under the lock. */
static void store(fb_study_sweep *sw, size_t i, int status, int at_value, char *error,
                  double wall_seconds, int worker)
{
  pthread_mutex_lock(&sw->lock);
  sweep_case *c = &sw->cases[i];
  free(c->error);
  /* A stopped case has not run: it stays to be run again. */
  const int done = status != FB_EINTR;
  *c = (sweep_case){.done = done,
                    .status = status,
                    .at_value = done && at_value,
                    .worker = worker,
                    .wall_seconds = done ? wall_seconds : NAN,
                    .error = done ? error : NULL};
  if (!done)
    free(error);
  pthread_mutex_unlock(&sw->lock);
}

/* err's message in fresh memory, never empty: a failed case is told by
 * its message (NULL: out of memory). */
static char *case_error(int rc, fb_err *err)
{
  if (!err->msg[0])
    snprintf(err->msg, sizeof err->msg, "failed (%s) without a message", fb_status_name(rc));
  return copy_text(err->msg);
}

int fb_study_sweep_run_case(fb_study_sweep *sw, size_t i)
{
  if (i >= sw->ncases)
    return FB_EINVAL;
  fb_scenario_override ov[FB_STUDY_SWEEP_MAX_AXES];
  fb_study_sweep_case_overrides(sw, i, ov);
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  fb_result *res = NULL;
  double *m = &sw->metric[i * sw->nmetrics], wall = NAN;
  int rc = stopped(sw) ? fb_err_set(&err, FB_EINTR, "sweep: stopped")
                       : sw->ops.load(sw->ops.ctx, i, ov, sw->naxes, &s, &err);
  if (rc == FB_OK)
    rc = fb_vehicle_simulate_progress(s, sw->sys, case_progress, sw, &res, &err);
  if (rc == FB_OK) {
    wall = fb_result_stats(res)->wall_seconds;
    rc = case_metrics(sw, s, res, m, &err);
  }
  if (rc == FB_OK && sw->ops.measure)
    rc = sw->ops.measure(sw->ops.ctx, i, s, res, &err);
  if (rc != FB_OK && s && sw->ops.locate)
    sw->ops.locate(sw->ops.ctx, s, &err);
  if (rc != FB_OK)
    for (size_t k = 0; k < sw->nmetrics; ++k)
      m[k] = NAN;
  store(sw, i, rc, err.source == FB_SOURCE_OVERRIDE, rc != FB_OK ? case_error(rc, &err) : NULL,
        wall, 0);
  fb_result_free(&res);
  fb_scenario_free(&s);
  return rc;
}

void fb_study_sweep_record(fb_study_sweep *sw, size_t i, const fb_study_sweep_case *c)
{
  if (i >= sw->ncases)
    return;
  double *m = &sw->metric[i * sw->nmetrics];
  for (size_t k = 0; k < sw->nmetrics; ++k)
    m[k] = c->status == FB_OK && c->metric ? c->metric[k] : NAN;
  char *error = c->status != FB_OK && c->error ? copy_text(c->error) : NULL;
  store(sw, i, c->status, c->at_value, error, c->wall_seconds, c->worker);
}

int fb_study_sweep_case_get(const fb_study_sweep *sw, size_t i, fb_study_sweep_case *out)
{
  const sweep_case *c = &sw->cases[i];
  *out = (fb_study_sweep_case){.status = c->status,
                               .at_value = c->at_value,
                               .error = c->error,
                               .metric = &sw->metric[i * sw->nmetrics],
                               .wall_seconds = c->wall_seconds,
                               .worker = c->worker};
  return c->done;
}

int fb_study_sweep_case_done(const fb_study_sweep *sw, size_t i)
{
  return i < sw->ncases && sw->cases[i].done;
}

/* ---- The pool. */

int fb_study_sweep_next(fb_study_sweep *sw, size_t *i)
{
  const int stop = stopped(sw);
  pthread_mutex_lock(&sw->lock);
  while (sw->next < sw->ncases && sw->cases[sw->next].done)
    ++sw->next;
  /* Once ops->finished has failed (a journal that cannot be written), a
   * case run now would be lost to it: none is started. */
  const int got = sw->next < sw->ncases && !stop && sw->stop_rc == FB_OK;
  if (got)
    *i = sw->next++;
  pthread_mutex_unlock(&sw->lock);
  return got;
}

int fb_study_sweep_finish(fb_study_sweep *sw, size_t i)
{
  int rc = FB_OK;
  pthread_mutex_lock(&sw->lock);
  if (i < sw->ncases && sw->cases[i].done && sw->ops.finished) {
    fb_err err;
    fb_err_clear(&err);
    rc = sw->ops.finished(sw->ops.ctx, i, &err);
    if (rc != FB_OK && sw->stop_rc == FB_OK) {
      sw->stop_rc = rc;
      sw->stop_err = err;
    }
  }
  pthread_mutex_unlock(&sw->lock);
  return rc;
}

static void *worker(void *arg)
{
  fb_study_sweep *sw = arg;
  size_t i;
  while (fb_study_sweep_next(sw, &i)) {
    fb_study_sweep_run_case(sw, i);
    fb_study_sweep_finish(sw, i);
  }
  return NULL;
}

/* The cases not done. */
static size_t cases_left(fb_study_sweep *sw)
{
  size_t left = 0;
  pthread_mutex_lock(&sw->lock);
  for (size_t i = 0; i < sw->ncases; ++i)
    left += !sw->cases[i].done;
  pthread_mutex_unlock(&sw->lock);
  return left;
}

int fb_study_sweep_run(fb_study_sweep *sw, size_t threads, fb_err *err)
{
  const size_t left = cases_left(sw), nthreads = threads < left ? threads : left;
  /* This thread is one of them; if a thread cannot be started, the
   * others do its share. */
  pthread_t *tid = nthreads > 1 ? malloc((nthreads - 1) * sizeof *tid) : NULL;
  size_t started = 0;
  while (tid && started + 1 < nthreads && pthread_create(&tid[started], NULL, worker, sw) == 0)
    ++started;
  if (nthreads > 0)
    worker(sw);
  for (size_t t = 0; t < started; ++t)
    pthread_join(tid[t], NULL);
  free(tid);
  pthread_mutex_lock(&sw->lock);
  const int rc = sw->stop_rc;
  if (rc != FB_OK && err)
    *err = sw->stop_err;
  pthread_mutex_unlock(&sw->lock);
  if (rc != FB_OK)
    return rc;
  const size_t not_run = cases_left(sw);
  if (not_run > 0 && stopped(sw))
    return fb_err_set(err, FB_EINTR, "sweep: stopped with %zu of %zu cases not run", not_run,
                      sw->ncases);
  return FB_OK;
}

void fb_study_sweep_cancel(fb_study_sweep *sw)
{
  atomic_store(&sw->cancelled, 1);
}
