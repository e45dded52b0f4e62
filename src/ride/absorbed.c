/* SPDX-License-Identifier: BSD-3-Clause */
/* Absorbed power (Pradko & Lee, "Vibration comfort criteria", SAE paper
 * 660139, 1966; Lee & Pradko, "Analytical analysis of human vibration",
 * SAE paper 680091, 1968): the mean power a seated person absorbs under
 * vertical vibration, P = sum_i K(f_i) a_rms,i^2, where a_rms,i is the
 * r.m.s. seat acceleration in the spectral line at f_i and K(f) the
 * published absorbed-power coefficient.
 *
 * This is the frequency-domain definition, evaluated on the record's own
 * DFT lines: for a real record of n samples, line k (0 < k < n/2) holds
 * the mean square 2 |X_k|^2 / n^2 and the Nyquist line (k = n/2, n even)
 * |X_k|^2 / n^2, so by Parseval the lines' mean squares add up to the
 * record's mean square less its mean squared. The coefficients are the
 * caller's (fb_ride_kf_table): see docs/ride-metrics.md for why none are
 * built in. */
#include <math.h>
#include <stddef.h>

#include "flexbond/ride.h"

#include "ride/ride_internal.h"

static const double PI = 3.14159265358979323846;

/* Checks a K(f) table's shape and values. */
static int check_table(const fb_ride_kf_table *kf, fb_err *err)
{
  if (!kf || !kf->freq_hz || !kf->coef || kf->n < 2)
    return fb_err_set(err, FB_EINVAL,
                      "absorbed power: the K(f) table needs at least 2 points (got %zu)",
                      kf ? kf->n : 0);
  for (size_t i = 0; i < kf->n; ++i) {
    const double f = kf->freq_hz[i], c = kf->coef[i];
    if (!isfinite(f) || f <= 0 || (i > 0 && !(f > kf->freq_hz[i - 1])))
      return fb_err_set(err, FB_EINVAL,
                        "absorbed power: K(f) table frequency %zu (%g Hz) is not positive and "
                        "above the previous one",
                        i, f);
    if (!isfinite(c) || c <= 0)
      return fb_err_set(err, FB_EINVAL,
                        "absorbed power: K(f) table coefficient %zu (%g) is not positive", i,
                        c);
  }
  return FB_OK;
}

/* K(f), log-log interpolated; 0 outside the table. *seg carries the
 * segment found for the previous (lower) frequency, as lines come in
 * increasing order. */
static double table_coef(const fb_ride_kf_table *kf, double f, size_t *seg)
{
  const size_t last = kf->n - 1;
  if (f < kf->freq_hz[0] || f > kf->freq_hz[last])
    return 0;
  while (*seg + 1 < last && f > kf->freq_hz[*seg + 1])
    ++*seg;
  const size_t i = *seg;
  const double u = log(f / kf->freq_hz[i]) / log(kf->freq_hz[i + 1] / kf->freq_hz[i]);
  return kf->coef[i] * pow(kf->coef[i + 1] / kf->coef[i], u);
}

/* |X_k|^2 of a[0..n-1] at theta = 2 pi k / n. The phasor e^(-j theta m)
 * advances by one complex multiplication per sample and is recomputed
 * exactly every 1024 samples, so its rounding error stays at ~1e-13
 * whatever n is. */
static double dft_power(const double *a, size_t n, double theta)
{
  const double step_re = cos(theta), step_im = -sin(theta);
  double re = 0, im = 0, w_re = 1, w_im = 0;
  for (size_t m = 0; m < n; ++m) {
    if (m % 1024 == 0) {
      w_re = cos(theta * (double)m);
      w_im = -sin(theta * (double)m);
    }
    re += a[m] * w_re;
    im += a[m] * w_im;
    const double next_re = w_re * step_re - w_im * step_im;
    w_im = w_re * step_im + w_im * step_re;
    w_re = next_re;
  }
  return re * re + im * im;
}

int fb_ride_absorbed_power(const double *a, size_t n, double fs, const fb_ride_kf_table *kf,
                           double *watts, fb_err *err)
{
  if (!a || !watts || n < 2)
    return fb_err_set(err, FB_EINVAL, "absorbed power: needs at least 2 samples (got %zu)",
                      a ? n : 0);
  if (!isfinite(fs) || fs <= 0)
    return fb_err_set(err, FB_EINVAL, "absorbed power: sample rate %g Hz is not positive", fs);
  int status = check_table(kf, err);
  if (status == FB_OK)
    status = ride_check_finite(a, n, fs, err);
  if (status != FB_OK)
    return status;
  const double nn = (double)n;
  double power = 0;
  size_t seg = 0;
  for (size_t k = 1; 2 * k <= n; ++k) {
    const double coef = table_coef(kf, (double)k * fs / nn, &seg);
    if (coef == 0)
      continue;
    const double line_weight = (2 * k == n) ? 1.0 : 2.0;
    power += coef * line_weight * dft_power(a, n, 2 * PI * (double)k / nn) / (nn * nn);
  }
  *watts = power;
  return FB_OK;
}
