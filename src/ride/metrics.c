/* SPDX-License-Identifier: BSD-3-Clause */
/* Ride-comfort metrics of a sampled vertical acceleration (see
 * flexbond/ride.h and docs/ride-metrics.md).
 *
 * With a_w the Wk-weighted acceleration sampled at fs over the N samples
 * of the evaluated interval (duration T = N / fs), the integrals of
 * ISO 2631-1:1997 become rectangle sums, exact for sines over whole
 * periods:
 *   a_w   = (1/N sum a_w^2)^(1/2)                      (6.1)
 *   a_w(t0) = (1/M sum_{t0 - tau < t_k <= t0} a_w^2)^(1/2), M = tau fs
 *                                                       (6.3.1, linear integration)
 *   MTVV  = max over t0 of a_w(t0), windows inside the interval
 *   VDV   = (1/fs sum a_w^4)^(1/4)                      (6.3.2)
 *   crest = max |a_w| / a_w                             (6.2.1)
 * Jerk is the central difference (a_{k+1} - a_{k-1}) fs / 2 of the
 * unweighted samples (second-order accurate: for a sine of angular
 * frequency w it has amplitude w sin(w h) / (w h), h = 1 / fs). */
#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/ride.h"

#include "ride/ride_internal.h"

void fb_ride_opts_default(fb_ride_opts *opts)
{
  opts->integration_time = 1.0;
  opts->absorbed_kf = NULL;
}

/* Sample indices [*k0, *k1) whose times k / fs lie in [t0, t1); times
 * within 1e-9 sample of an index count as on it, so t = k / fs computed
 * in floating point selects sample k. */
static int window_indices(size_t n, double fs, double t0, double t1, size_t *k0, size_t *k1,
                          fb_err *err)
{
  const double span = (double)n / fs, slack = 1e-9;
  if (!isfinite(t0) || !isfinite(t1) || t0 < -slack / fs || t1 > span + slack / fs ||
      !(t1 > t0))
    return fb_err_set(err, FB_EINVAL,
                      "ride metrics: window [%g, %g) s is not an interval inside the record "
                      "[0, %g) s",
                      t0, t1, span);
  const double first = ceil(t0 * fs - slack), end = ceil(t1 * fs - slack);
  *k0 = first > 0 ? (size_t)first : 0;
  *k1 = end < (double)n ? (size_t)end : n;
  return FB_OK;
}

/* a_w r.m.s., VDV and crest factor of aw[0..n-1]. */
static void weighted_stats(const double *aw, size_t n, double fs, fb_ride_metrics *m)
{
  double sum2 = 0, sum4 = 0, peak = 0;
  for (size_t k = 0; k < n; ++k) {
    const double x2 = aw[k] * aw[k];
    sum2 += x2;
    sum4 += x2 * x2;
    peak = fmax(peak, fabs(aw[k]));
  }
  m->a_w_rms = sqrt(sum2 / (double)n);
  m->vdv = pow(sum4 / fs, 0.25);
  m->crest = m->a_w_rms > 0 ? peak / m->a_w_rms : 0;
}

/* Largest running r.m.s. of aw[0..n-1] over windows of len samples (len
 * <= n): a sliding sum, recomputed from scratch every len steps so its
 * rounding error stays at a few ulps of the window's energy. */
static double max_running_rms(const double *aw, size_t n, size_t len)
{
  double sum = 0, best = 0;
  for (size_t k = 0; k < len; ++k)
    sum += aw[k] * aw[k];
  best = sum;
  for (size_t k = len; k < n; ++k) {
    if (k % len == 0) {
      sum = 0;
      for (size_t j = k + 1 - len; j <= k; ++j)
        sum += aw[j] * aw[j];
    } else {
      sum += aw[k] * aw[k] - aw[k - len] * aw[k - len];
    }
    best = fmax(best, sum);
  }
  return sqrt(fmax(best, 0) / (double)len);
}

/* Jerk peak and r.m.s. at samples [k0, k1) of a[0..n-1], from central
 * differences where both neighbours exist, one-sided ones at the
 * record's ends (n >= 3 and k1 - k0 >= 3, so each sample has one). */
static void jerk_stats(const double *a, size_t n, size_t k0, size_t k1, double fs,
                       fb_ride_metrics *m)
{
  assert(n >= 3 && k1 <= n && k0 + 3 <= k1);
  double sum2 = 0, peak = 0;
  for (size_t k = k0; k < k1; ++k) {
    double jerk;
    if (k == 0)
      jerk = (a[1] - a[0]) * fs;
    else if (k + 1 == n)
      jerk = (a[k] - a[k - 1]) * fs;
    else
      jerk = (a[k + 1] - a[k - 1]) * fs / 2;
    sum2 += jerk * jerk;
    peak = fmax(peak, fabs(jerk));
  }
  m->jerk_peak = peak;
  m->jerk_rms = sqrt(sum2 / (double)(k1 - k0));
}

static int check_opts(const fb_ride_opts *opts, fb_err *err)
{
  if (!isfinite(opts->integration_time) || opts->integration_time <= 0)
    return fb_err_set(err, FB_EINVAL,
                      "ride metrics: running r.m.s. integration time %g s is not positive",
                      opts->integration_time);
  return FB_OK;
}

/* Checks everything fb_ride_metrics_window needs before any work. */
static int check_window_args(const double *a, size_t n, double fs, const fb_ride_opts *opts,
                             const fb_ride_metrics *m, fb_err *err)
{
  if (!a || !m)
    return fb_err_set(err, FB_EINVAL, "ride metrics: %s is NULL", a ? "m" : "a");
  int status = ride_check_rate(fs, err);
  if (status == FB_OK)
    status = check_opts(opts, err);
  if (status == FB_OK)
    status = ride_check_finite(a, n, fs, err);
  return status;
}

/* Samples in the running r.m.s. window, or 0 (with the error set) if the
 * evaluated interval of nw samples is too short for it or for the jerk. */
static size_t running_window_len(size_t nw, double fs, double tau, fb_err *err)
{
  const double len = fmax(1.0, round(tau * fs));
  if (nw < 3 || (double)nw < len) {
    fb_err_set(err, FB_EINVAL,
               "ride metrics: %zu samples (%g s) are too few: need at least 3 and the "
               "running r.m.s. window of %g s (%.0f samples)",
               nw, (double)nw / fs, tau, len);
    return 0;
  }
  return (size_t)len;
}

/* The absorbed power (the caller's K(f) table when given, else the
 * built-in filter), the NRMM peak and the ISO 2631-5 dose of samples
 * [k0, k1) of a, the filters running from a[0]; work holds k1 samples. */
static int military_metrics(const double *a, size_t k0, size_t k1, double fs,
                            const fb_ride_opts *opts, double *work, fb_ride_metrics *m,
                            fb_err *err)
{
  const size_t nw = k1 - k0;
  int status = FB_OK;
  m->dz = NAN;
  if (opts->absorbed_kf) {
    status = fb_ride_absorbed_power(a + k0, nw, fs, opts->absorbed_kf, &m->absorbed_power, err);
  } else {
    status = fb_ride_absorbed_filter(a, k1, fs, work, err);
    double sum2 = 0;
    for (size_t k = k0; status == FB_OK && k < k1; ++k)
      sum2 += work[k] * work[k];
    m->absorbed_power = sum2 / (double)nw;
  }
  if (status == FB_OK)
    status = fb_ride_nrmm_filter(a, k1, fs, work, err);
  if (status == FB_OK) {
    double peak = 0;
    for (size_t k = k0; k < k1; ++k)
      peak = fmax(peak, fabs(work[k]));
    m->nrmm_peak = peak;
    status = ride_spine_window_dose(a, k0, k1, fs, &m->dz, err);
  }
  m->se = FB_RIDE_SPINE_MZ * m->dz;
  return status;
}

int fb_ride_metrics_window(const double *a, size_t n, double fs, double t0, double t1,
                           const fb_ride_opts *opts, fb_ride_metrics *m, fb_err *err)
{
  fb_ride_opts defaults;
  fb_ride_opts_default(&defaults);
  if (!opts)
    opts = &defaults;
  int status = check_window_args(a, n, fs, opts, m, err);
  size_t k0 = 0, k1 = 0;
  if (status == FB_OK)
    status = window_indices(n, fs, t0, t1, &k0, &k1, err);
  if (status != FB_OK)
    return status;
  const size_t nw = k1 - k0, len = running_window_len(nw, fs, opts->integration_time, err);
  if (len == 0)
    return FB_EINVAL;
  double *work = malloc(k1 * sizeof *work);
  if (!work)
    return fb_err_set(err, FB_ENOMEM, "ride metrics: out of memory for %zu samples", k1);
  status = fb_ride_wk_filter(a, k1, fs, work, err);
  if (status == FB_OK) {
    weighted_stats(work + k0, nw, fs, m);
    m->mtvv = max_running_rms(work + k0, nw, len);
    jerk_stats(a, n, k0, k1, fs, m);
    m->duration = (double)nw / fs;
    m->vdv_ratio = m->vdv / FB_RIDE_VDV_CAUTION;
    m->crest_over_9 = m->crest > FB_RIDE_CREST_LIMIT ? 1.0 : 0.0;
    status = military_metrics(a, k0, k1, fs, opts, work, m, err);
  }
  free(work);
  return status;
}

int fb_ride_metrics_compute(const double *a, size_t n, double fs, const fb_ride_opts *opts,
                            fb_ride_metrics *m, fb_err *err)
{
  const int status = ride_check_rate(fs, err);
  if (status != FB_OK)
    return status;
  return fb_ride_metrics_window(a, n, fs, 0, (double)n / fs, opts, m, err);
}

/* The sample rate of r's uniform time column, or FB_EINVAL naming the
 * first step more than 1e-6 relative away from the mean step. */
static int result_rate(const fb_result *r, double *fs, fb_err *err)
{
  const size_t n = fb_result_nsamples(r);
  if (n < 3)
    return fb_err_set(err, FB_EINVAL, "ride metrics: the result has %zu samples, need 3", n);
  const double t_first = fb_result_row(r, 0)[0], t_last = fb_result_row(r, n - 1)[0];
  const double step = (t_last - t_first) / (double)(n - 1);
  if (!(step > 0))
    return fb_err_set(err, FB_EINVAL, "ride metrics: the result's times do not increase");
  for (size_t k = 1; k < n; ++k) {
    const double dt = fb_result_row(r, k)[0] - fb_result_row(r, k - 1)[0];
    if (!(fabs(dt - step) <= 1e-6 * step))
      return fb_err_set(err, FB_EINVAL,
                        "ride metrics: the result is not uniformly sampled: step %zu is %g s, "
                        "the mean step %g s",
                        k, dt, step);
  }
  *fs = 1.0 / step;
  return FB_OK;
}

int fb_ride_metrics_result(const fb_result *r, const char *column, double t0, double t1,
                           const fb_ride_opts *opts, fb_ride_metrics *m, fb_err *err)
{
  if (!r || !column)
    return fb_err_set(err, FB_EINVAL, "ride metrics: %s is NULL", r ? "column" : "result");
  const long col = fb_result_find(r, column);
  if (col < 1)
    return fb_err_set(err, FB_EINVAL, "ride metrics: the result has no output column '%s'",
                      column);
  double fs = 0;
  int status = result_rate(r, &fs, err);
  if (status != FB_OK)
    return status;
  const size_t n = fb_result_nsamples(r);
  double *a = malloc(n * sizeof *a);
  if (!a)
    return fb_err_set(err, FB_ENOMEM, "ride metrics: out of memory for %zu samples", n);
  for (size_t k = 0; k < n; ++k)
    a[k] = fb_result_row(r, k)[col];
  const double t_first = fb_result_row(r, 0)[0];
  status = fb_ride_metrics_window(a, n, fs, t0 - t_first, t1 - t_first, opts, m, err);
  free(a);
  if (status != FB_OK)
    fb_err_prefix(err, "column '%s': ", column);
  return status;
}
