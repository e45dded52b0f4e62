/* SPDX-License-Identifier: BSD-3-Clause */
/* Ride-limiting speeds (flexbond/study.h, docs/ride-limit.md): the
 * bracketing search over speed, the metrics it can take and the run each
 * of its points needs. The NATO Reference Mobility Model rates a vehicle
 * by the speed at which the driver absorbs 6 W on a course of a given
 * roughness and the speed at which an obstacle of a given height gives a
 * 2.5 g peak seat acceleration (Ahlvin & Haley, "NATO Reference Mobility
 * Model Edition II, NRMM II User's Guide", US Army WES Technical Report
 * GL-92-19, 1992). */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/study.h"

/* Speeds below this, m/s, the search is not asked for (1 cm/s). */
static const double MIN_SPEED = 0.01;
static const double KMH = 1.0 / 3.6; /* m/s per km/h */

void fb_study_ride_limit_opts_default(fb_study_ride_limit_opts *o)
{
  *o = (fb_study_ride_limit_opts){.limit = NAN,
                                  .v_lo = 5.0 * KMH,
                                  .v_hi = 80.0 * KMH,
                                  .coarse_step = 5.0 * KMH,
                                  .tol = 0.1 * KMH,
                                  .refine_points = 1};
}

/* ---- The search. */

/* A curve's state between rounds: its bracket [lo, hi] (metric below the
 * limit at lo, at or above it at hi) while it refines. */
typedef struct curve_state {
  int active;
  double lo, hi, m_lo, m_hi;
} curve_state;

static int check_opts(const fb_study_ride_limit_opts *o, fb_err *err)
{
  if (!isfinite(o->limit))
    return fb_err_set(err, FB_EINVAL, "ride limit: the metric's limit must be finite (got %g)",
                      o->limit);
  if (!(isfinite(o->v_hi) && o->v_lo >= MIN_SPEED && o->v_hi > o->v_lo))
    return fb_err_set(err, FB_EINVAL,
                      "ride limit: speeds [%g, %g] m/s: need %g <= v_lo < v_hi, finite",
                      o->v_lo, o->v_hi, MIN_SPEED);
  if (!(o->coarse_step > 0 && isfinite(o->coarse_step)))
    return fb_err_set(err, FB_EINVAL, "ride limit: coarse step %g m/s must be > 0",
                      o->coarse_step);
  if (!(o->tol > 0 && isfinite(o->tol)))
    return fb_err_set(err, FB_EINVAL, "ride limit: tolerance %g m/s must be > 0", o->tol);
  if (o->refine_points < 1 || o->refine_points > 1000)
    return fb_err_set(err, FB_EINVAL, "ride limit: %zu refining points per round (1 to 1000)",
                      o->refine_points);
  if ((o->v_hi - o->v_lo) / o->coarse_step > 10000)
    return fb_err_set(err, FB_EINVAL, "ride limit: more than 10000 coarse speeds");
  return FB_OK;
}

/* The coarse grid's size: v_lo + i step up to v_hi, v_hi itself last
 * (a speed within step/1e9 of it counts as it). */
static size_t coarse_count(const fb_study_ride_limit_opts *o)
{
  return (size_t)ceil((o->v_hi - o->v_lo) / o->coarse_step - 1e-9) + 1;
}

static double coarse_speed(const fb_study_ride_limit_opts *o, size_t i, size_t n)
{
  return i + 1 == n ? o->v_hi : o->v_lo + (double)i * o->coarse_step;
}

/* A failed evaluation at speed fails the curve. */
static void fail_curve(fb_study_ride_limit_curve *c, curve_state *st, double speed)
{
  *c = (fb_study_ride_limit_curve){FB_RIDE_LIMIT_FAILED, NAN, NAN, NAN, NAN, speed, c->nruns};
  st->active = 0;
}

/* Curve c's coarse grid metrics m[0 .. n): its status, or its bracket. */
static void classify(const fb_study_ride_limit_opts *o, const double *m, size_t n,
                     fb_study_ride_limit_curve *c, curve_state *st)
{
  c->nruns = n;
  for (size_t i = 0; i < n; ++i) {
    const double v = coarse_speed(o, i, n);
    if (isnan(m[i])) {
      fail_curve(c, st, v);
      return;
    }
    if (m[i] < o->limit)
      continue;
    if (i == 0) {
      *c = (fb_study_ride_limit_curve){FB_RIDE_LIMIT_BELOW, NAN, NAN, v, m[0], NAN, n};
      return;
    }
    *st = (curve_state){1, coarse_speed(o, i - 1, n), v, m[i - 1], m[i]};
    return;
  }
  *c = (fb_study_ride_limit_curve){FB_RIDE_LIMIT_ABOVE, o->v_hi, m[n - 1], NAN, NAN, NAN, n};
}

/* A refining round's metrics m[0 .. k) at the bracket's k inner speeds:
 * the bracket of the first that reaches the limit. */
static void narrow(const fb_study_ride_limit_opts *o, const double *m, size_t k,
                   fb_study_ride_limit_curve *c, curve_state *st)
{
  const double lo = st->lo, width = st->hi - st->lo;
  c->nruns += k;
  for (size_t j = 0; j < k; ++j) {
    const double v = lo + width * (double)(j + 1) / (double)(k + 1);
    if (isnan(m[j])) {
      fail_curve(c, st, v);
      return;
    }
    if (m[j] >= o->limit) {
      st->hi = v;
      st->m_hi = m[j];
      break;
    }
    st->lo = v;
    st->m_lo = m[j];
  }
}

/* A bracket within tol ends the curve's search. */
static void settle(const fb_study_ride_limit_opts *o, fb_study_ride_limit_curve *c,
                   curve_state *st)
{
  if (!st->active || st->hi - st->lo > o->tol)
    return;
  *c = (fb_study_ride_limit_curve){
      FB_RIDE_LIMIT_FOUND, st->lo, st->m_lo, st->hi, st->m_hi, NAN, c->nruns};
  st->active = 0;
}

/* The refining round's points of the active curves into pts; their count. */
static size_t refine_points(const fb_study_ride_limit_opts *o, const curve_state *st,
                            size_t ncurves, fb_study_ride_limit_point *pts)
{
  size_t n = 0;
  const size_t k = o->refine_points;
  for (size_t c = 0; c < ncurves; ++c)
    for (size_t j = 0; st[c].active && j < k; ++j)
      pts[n++] = (fb_study_ride_limit_point){
          c, st[c].lo + (st[c].hi - st[c].lo) * (double)(j + 1) / (double)(k + 1)};
  return n;
}

/* Round 1: every curve's coarse grid. */
static int coarse_round(const fb_study_ride_limit_opts *o, size_t ncurves,
                        fb_study_ride_limit_eval_fn eval, void *ctx,
                        fb_study_ride_limit_point *pts, double *m,
                        fb_study_ride_limit_curve *out, curve_state *st, fb_err *err)
{
  const size_t n = coarse_count(o);
  for (size_t c = 0; c < ncurves; ++c)
    for (size_t i = 0; i < n; ++i)
      pts[c * n + i] = (fb_study_ride_limit_point){c, coarse_speed(o, i, n)};
  const int rc = eval(ctx, pts, ncurves * n, m, err);
  for (size_t c = 0; rc == FB_OK && c < ncurves; ++c) {
    classify(o, &m[c * n], n, &out[c], &st[c]);
    settle(o, &out[c], &st[c]);
  }
  return rc;
}

int fb_study_ride_limit(size_t ncurves, const fb_study_ride_limit_opts *opts,
                        fb_study_ride_limit_eval_fn eval, void *ctx,
                        fb_study_ride_limit_curve *out, size_t *nrounds, fb_err *err)
{
  if (nrounds)
    *nrounds = 0;
  int rc = check_opts(opts, err);
  if (rc != FB_OK)
    return rc;
  if (!eval || (ncurves > 0 && !out))
    return fb_err_set(err, FB_EINVAL, "ride limit: no evaluation function or no output");
  const size_t per_round =
      ncurves *
      (coarse_count(opts) > opts->refine_points ? coarse_count(opts) : opts->refine_points);
  fb_study_ride_limit_point *pts = malloc((per_round ? per_round : 1) * sizeof *pts);
  double *m = malloc((per_round ? per_round : 1) * sizeof *m);
  curve_state *st = calloc(ncurves ? ncurves : 1, sizeof *st);
  if (!pts || !m || !st)
    rc = fb_err_set(err, FB_ENOMEM, "ride limit: out of memory for %zu curves", ncurves);
  size_t rounds = 0;
  if (rc == FB_OK && ncurves > 0) {
    rc = coarse_round(opts, ncurves, eval, ctx, pts, m, out, st, err);
    rounds = 1;
  }
  for (size_t n; rc == FB_OK && (n = refine_points(opts, st, ncurves, pts)) > 0; ++rounds) {
    rc = eval(ctx, pts, n, m, err);
    for (size_t p = 0; rc == FB_OK && p < n; p += opts->refine_points) {
      const size_t c = pts[p].curve;
      narrow(opts, &m[p], opts->refine_points, &out[c], &st[c]);
      settle(opts, &out[c], &st[c]);
    }
  }
  if (nrounds)
    *nrounds = rounds;
  free(pts);
  free(m);
  free(st);
  return rc;
}

/* ---- The metrics. */

/* What a metric is measured on: output column col of a run, over
 * [t0, t1) (s, absolute). */
typedef struct metric_record {
  const fb_result *r;
  const char *column;
  long col;
  double t0, t1;
} metric_record;

/* The largest |value| of the record's samples in its window: the
 * unfiltered peak. */
static double abs_peak(const metric_record *rec)
{
  double peak = 0;
  for (size_t k = 0; k < fb_result_nsamples(rec->r); ++k) {
    const double *row = fb_result_row(rec->r, k);
    if (row[0] >= rec->t0 && row[0] < rec->t1)
      peak = fmax(peak, fabs(row[rec->col]));
  }
  return peak;
}

/* One metric: the double of fb_ride_metrics at offset, or a function of
 * the record itself (record, when not NULL); unit NULL: the output's. */
#define RIDE_FIELD(field) offsetof(fb_ride_metrics, field), NULL
static const struct {
  const char *name, *unit;
  double limit;
  size_t offset;
  double (*record)(const metric_record *rec);
} metrics[] = {
    {"absorbed_power", "W", FB_RIDE_ABSORBED_POWER_LIMIT, RIDE_FIELD(absorbed_power)},
    {"a_w_rms", "m/s^2", NAN, RIDE_FIELD(a_w_rms)},
    {"mtvv", "m/s^2", NAN, RIDE_FIELD(mtvv)},
    {"vdv", "m/s^1.75", NAN, RIDE_FIELD(vdv)},
    {"crest_factor", "-", NAN, RIDE_FIELD(crest)},
    {"jerk_peak", "m/s^3", NAN, RIDE_FIELD(jerk_peak)},
    /* NRMM: 2.5 g after the 30 Hz low-pass (docs/ride-metrics.md). */
    {"nrmm_peak", "m/s^2", FB_RIDE_NRMM_PEAK_LIMIT, RIDE_FIELD(nrmm_peak)},
    /* ISO 2631-5:2004 Annex B: below 0.5 MPa a low probability of an
     * adverse health effect. */
    {"se", "MPa", 0.5, RIDE_FIELD(se)},
    {"dz", "m/s^2", NAN, RIDE_FIELD(dz)},
    /* 1: the lower bound of ISO 2631-1's health guidance caution zone. */
    {"vdv_ratio", "-", 1.0, RIDE_FIELD(vdv_ratio)},
    {"abs_peak", NULL, NAN, 0, abs_peak},
};
#undef RIDE_FIELD
enum { NMETRICS = sizeof metrics / sizeof metrics[0] };

size_t fb_study_ride_limit_nmetrics(void)
{
  return NMETRICS;
}

const char *fb_study_ride_limit_metric_name(size_t m)
{
  return m < NMETRICS ? metrics[m].name : NULL;
}

const char *fb_study_ride_limit_metric_unit(size_t m)
{
  return m < NMETRICS ? metrics[m].unit : NULL;
}

double fb_study_ride_limit_metric_limit(size_t m)
{
  return m < NMETRICS ? metrics[m].limit : NAN;
}

int fb_study_ride_limit_metric_of_acceleration(size_t m)
{
  return m < NMETRICS && !metrics[m].record;
}

int fb_study_ride_limit_metric_find(const char *name, size_t *m)
{
  for (size_t i = 0; name && i < NMETRICS; ++i)
    if (!strcmp(metrics[i].name, name)) {
      *m = i;
      return 0;
    }
  return -1;
}

/* ---- A case's run and its measure. */

int fb_study_ride_limit_duration(fb_scenario *s, double course_length, double settle_time,
                                 fb_err *err)
{
  if (!(course_length > 0 && isfinite(course_length)) ||
      !(settle_time >= 0 && isfinite(settle_time)))
    return fb_err_set(err, FB_EINVAL,
                      "ride limit: course length %g m must be > 0 and settling time %g s >= 0",
                      course_length, settle_time);
  /* A road that goes on ends its feature at the run's end. */
  const double open_end = s->t_end;
  double last_entry = -INFINITY, last_exit = -INFINITY;
  int goes_on = 0;
  for (size_t c = 0; c < s->ncorners; ++c) {
    last_entry = fmax(last_entry, fb_scenario_road_entry(s, (int)c));
    const double exit = fb_scenario_road_exit(s, (int)c);
    goes_on |= exit >= open_end;
    last_exit = fmax(last_exit, exit);
  }
  s->t_end =
      goes_on ? fmax(last_entry, 0.0) + course_length / s->speed : last_exit + settle_time;
  return FB_OK;
}

int fb_study_ride_limit_measure(const fb_scenario *s, const fb_result *r, size_t k, size_t m,
                                double *value, fb_err *err)
{
  *value = NAN;
  if (m >= NMETRICS || k >= s->noutputs)
    return fb_err_set(err, FB_EINVAL, "ride limit: no metric %zu or output %zu", m, k);
  const size_t n = fb_result_nsamples(r);
  metric_record rec = {r, s->output[k].name, fb_result_find(r, s->output[k].name), 0, 0};
  if (rec.col < 1 || n < 2)
    return fb_err_set(err, FB_EINVAL, "ride limit: the run has no column '%s' or no samples",
                      rec.column);
  double window[2];
  fb_study_response_window(s, window);
  const double t_first = fb_result_row(r, 0)[0], t_last = fb_result_row(r, n - 1)[0];
  rec.t0 = fmax(window[0], t_first);
  /* Every sample stands for one interval (flexbond/ride.h): the last's too. */
  rec.t1 = t_last + (t_last - t_first) / (double)(n - 1);
  if (metrics[m].record) {
    *value = metrics[m].record(&rec);
    return FB_OK;
  }
  fb_ride_opts opts;
  fb_ride_opts_default(&opts);
  if (rec.t1 - rec.t0 < opts.integration_time)
    return FB_OK; /* too short a window for the running r.m.s.: no metric */
  fb_ride_metrics rm;
  const int rc = fb_ride_metrics_result(r, rec.column, rec.t0, rec.t1, &opts, &rm, err);
  if (rc == FB_OK)
    memcpy(value, (const char *)&rm + metrics[m].offset, sizeof *value);
  return rc;
}
