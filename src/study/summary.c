/* SPDX-License-Identifier: BSD-3-Clause */
/* The study layer's summary of a run (flexbond/study.h): each output's
 * statistics, each tire's contact, the ride metrics, and the comparison
 * of two systems, for every front end alike. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/study.h"

#include "core/util.h"

struct fb_run_summary {
  double window[2];
  size_t noutputs, ncorners;
  size_t *col;              /* noutputs: each output's column */
  fb_output_stats *stats;   /* noutputs */
  fb_output_stats *contact; /* ncorners: each tire's normal reaction */
  fb_contact_loss *loss;
  size_t nloss;
  int has_ride;
  fb_ride_metrics ride;
  double ride_window[2];
  char ride_note[FB_ERR_MSG_MAX];
};

void fb_study_response_window(const fb_scenario *s, double window[2])
{
  window[0] = INFINITY;
  window[1] = -INFINITY;
  for (size_t c = 0; c < s->ncorners; ++c) {
    window[0] = fmin(window[0], fb_scenario_road_entry(s, (int)c));
    window[1] = fmax(window[1], fb_scenario_road_exit(s, (int)c));
  }
}

size_t fb_study_ride_output(const fb_scenario *s)
{
  size_t k = 0;
  while (k < s->noutputs && strcmp(s->output[k].signal, "acc") != 0)
    ++k;
  return k;
}

fb_output_stats fb_output_stats_of(const fb_result *r, size_t col, const double window[2])
{
  fb_output_stats o = {NAN, -INFINITY, NAN, INFINITY, NAN, NAN};
  double sum_sq = 0;
  size_t nwindow = 0;
  for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
    const double *row = fb_result_row(r, k);
    const double t = row[0], v = row[col];
    if (t < window[0]) {
      o.static_value = v;
      continue;
    }
    /* Comparisons with NaN are false: NaN samples never become extremes. */
    if (v > o.peak) {
      o.peak = v;
      o.peak_time = t;
    }
    if (v < o.min) {
      o.min = v;
      o.min_time = t;
    }
    if (t <= window[1]) {
      sum_sq += v * v;
      ++nwindow;
    }
  }
  if (nwindow > 0)
    o.rms = sqrt(sum_sq / (double)nwindow);
  return o;
}

/* num / den, NaN when den is 0 (a ratio to nothing says nothing). */
static double ratio(double num, double den)
{
  return den != 0 ? num / den : NAN;
}

fb_output_cmp fb_output_compare(const fb_output_stats *s1, const fb_output_stats *s2,
                                const fb_result *diff, size_t col, const double window[2])
{
  fb_output_cmp c = {0, NAN, NAN, NAN, NAN, NAN};
  for (size_t k = 0; k < fb_result_nsamples(diff); ++k) {
    const double *row = fb_result_row(diff, k);
    if (row[0] >= window[0] && fabs(row[col]) > c.max_diff) {
      c.max_diff = fabs(row[col]);
      c.max_diff_time = row[0];
    }
  }
  c.range1 = s1->peak - s1->min;
  c.rel_diff = ratio(c.max_diff, c.range1);
  c.peak_change = ratio(s2->peak - s1->peak, fabs(s1->peak));
  c.rms_change = ratio(s2->rms - s1->rms, s1->rms);
  return c;
}

/* ---- A run's summary. */

/* The column of the output named name in r. */
static int column_of(const fb_result *r, const char *name, size_t *col, fb_err *err)
{
  const long j = fb_result_find(r, name);
  if (j < 1)
    return fb_err_set(err, FB_EINVAL, "the result has no output '%s'", name);
  *col = (size_t)j;
  return FB_OK;
}

/* The ride metrics of the ride output from the window's start to the
 * run's end (the last sample stands for one sampling interval, ride.h):
 * the response, without the settling after t = 0. */
static void summarise_ride(const fb_scenario *s, const fb_result *r, fb_run_summary *sum)
{
  const size_t n = fb_result_nsamples(r), k = fb_study_ride_output(s);
  sum->has_ride = 0;
  if (k == s->noutputs) {
    snprintf(sum->ride_note, sizeof sum->ride_note,
             "the outputs list no mounted body's acceleration (signal acc)");
    return;
  }
  if (n < 2) {
    snprintf(sum->ride_note, sizeof sum->ride_note, "the run has fewer than 2 samples");
    return;
  }
  const double t_first = fb_result_row(r, 0)[0], t_last = fb_result_row(r, n - 1)[0];
  sum->ride_window[0] = fmax(sum->window[0], t_first);
  sum->ride_window[1] = t_last + (t_last - t_first) / (double)(n - 1);
  fb_ride_opts opts;
  fb_ride_opts_default(&opts);
  fb_err err;
  if (fb_ride_metrics_result(r, s->output[k].name, sum->ride_window[0], sum->ride_window[1],
                             &opts, &sum->ride, &err) == FB_OK)
    sum->has_ride = 1;
  else
    snprintf(sum->ride_note, sizeof sum->ride_note, "%s", err.msg);
}

static int summarise(const fb_scenario *s, const fb_result *r, fb_run_summary *sum, fb_err *err)
{
  sum->col = calloc(sum->noutputs ? sum->noutputs : 1, sizeof *sum->col);
  sum->stats = calloc(sum->noutputs ? sum->noutputs : 1, sizeof *sum->stats);
  sum->contact = calloc(sum->ncorners ? sum->ncorners : 1, sizeof *sum->contact);
  if (!sum->col || !sum->stats || !sum->contact)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a run's summary");
  int rc = FB_OK;
  for (size_t k = 0; !rc && k < sum->noutputs; ++k) {
    rc = column_of(r, s->output[k].name, &sum->col[k], err);
    if (!rc)
      sum->stats[k] = fb_output_stats_of(r, sum->col[k], sum->window);
  }
  for (size_t c = 0; !rc && c < sum->ncorners; ++c) {
    char name[FB_ERR_KEY_MAX];
    size_t col = 0;
    snprintf(name, sizeof name, "contact_force_%s", s->corner[c].name);
    rc = column_of(r, name, &col, err);
    if (!rc)
      sum->contact[c] = fb_output_stats_of(r, col, sum->window);
  }
  if (!rc)
    rc = fb_vehicle_contact_loss(s, r, &sum->loss, &sum->nloss, err);
  if (!rc)
    summarise_ride(s, r, sum);
  return rc;
}

int fb_run_summary_new(const fb_scenario *s, const fb_result *r, const double window[2],
                       fb_run_summary **out, fb_err *err)
{
  *out = NULL;
  if (!s || !r)
    return fb_err_set(err, FB_EINVAL, "fb_run_summary_new: the scenario and the result");
  fb_run_summary *sum = calloc(1, sizeof *sum);
  if (!sum)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a run's summary");
  sum->noutputs = s->noutputs;
  sum->ncorners = s->ncorners;
  if (window) {
    sum->window[0] = window[0];
    sum->window[1] = window[1];
  } else {
    fb_study_response_window(s, sum->window);
  }
  const int rc = summarise(s, r, sum, err);
  if (rc) {
    fb_run_summary_free(&sum);
    return rc;
  }
  *out = sum;
  return FB_OK;
}

void fb_run_summary_free(fb_run_summary **sum)
{
  if (!sum || !*sum)
    return;
  free((*sum)->col);
  free((*sum)->stats);
  free((*sum)->contact);
  free((*sum)->loss);
  free(*sum);
  *sum = NULL;
}

void fb_run_summary_window(const fb_run_summary *sum, double window[2])
{
  window[0] = sum->window[0];
  window[1] = sum->window[1];
}

const fb_output_stats *fb_run_summary_output(const fb_run_summary *sum, size_t k)
{
  return k < sum->noutputs ? &sum->stats[k] : NULL;
}

size_t fb_run_summary_column(const fb_run_summary *sum, size_t k)
{
  return k < sum->noutputs ? sum->col[k] : 0;
}

const fb_output_stats *fb_run_summary_contact(const fb_run_summary *sum, size_t c)
{
  return c < sum->ncorners ? &sum->contact[c] : NULL;
}

double fb_run_summary_contact_ratio(const fb_run_summary *sum, size_t c)
{
  if (c >= sum->ncorners)
    return NAN;
  return sum->contact[c].peak / sum->contact[c].static_value;
}

int fb_run_summary_contact_spike(const fb_run_summary *sum, size_t c)
{
  return c < sum->ncorners && sum->contact[c].static_value > 0.0 &&
         sum->contact[c].peak > FB_CONTACT_SPIKE_RATIO * sum->contact[c].static_value;
}

size_t fb_run_summary_nlosses(const fb_run_summary *sum)
{
  return sum->nloss;
}

const fb_contact_loss *fb_run_summary_loss(const fb_run_summary *sum, size_t i)
{
  return i < sum->nloss ? &sum->loss[i] : NULL;
}

int fb_run_summary_ride(const fb_run_summary *sum, fb_ride_metrics *m, double window[2],
                        const char **note)
{
  if (m && sum->has_ride)
    *m = sum->ride;
  if (window) {
    window[0] = sum->ride_window[0];
    window[1] = sum->ride_window[1];
  }
  if (note)
    *note = sum->has_ride ? NULL : sum->ride_note;
  return sum->has_ride;
}

int fb_study_compare(const fb_scenario *s, const fb_result *r1, const fb_result *r2,
                     const fb_run_summary *sum1, const fb_run_summary *sum2, fb_output_cmp *cmp,
                     fb_result **diff, fb_err *err)
{
  fb_result *d = NULL;
  const int rc = fb_result_diff(r2, r1, &d, err);
  for (size_t k = 0; !rc && k < s->noutputs; ++k)
    cmp[k] = fb_output_compare(&sum1->stats[k], &sum2->stats[k], d, sum1->col[k], sum1->window);
  if (diff && !rc)
    *diff = d;
  else
    fb_result_free(&d);
  return rc;
}
