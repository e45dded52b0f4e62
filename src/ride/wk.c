/* SPDX-License-Identifier: BSD-3-Clause */
/* ISO 2631-1:1997 frequency weighting Wk (vertical whole-body vibration,
 * seated, standing and recumbent), analytic and digital.
 *
 * Wk is the product of four second-order analog sections (ISO 2631-1
 * Annex A, Table A.1; the same parameters appear in ISO 8041 Table 3): band limiting by a
 * Butterworth high-pass (f1 = 0.4 Hz) and low-pass (f2 = 100 Hz), an acceleration-velocity
 * transition (f3 = f4 = 12.5 Hz, Q4 = 0.63) and an upward step (f5 = 2.37 Hz, Q5 = 0.91, f6
 * = 3.35 Hz, Q6 = 0.91). Each section is discretised by the bilinear transform prewarped at its
 * own characteristic frequency (Oppenheim & Schafer, "Discrete-Time Signal Processing", 3rd
 * ed., sec. 7.2.2), which maps the analog response exactly at that frequency and compresses the
 * rest of the axis: the digital section's gain at f is the analog gain at k tan(pi f / fs) / (2
 * pi), k = w_p / tan(w_p / (2 fs)). The resulting error is in docs/ride-metrics.md. */
#include <math.h>
#include <stddef.h>

#include "flexbond/ride.h"

#include "ride/ride_internal.h"

static const double PI = 3.14159265358979323846;

enum { WK_NSECTIONS = 4 };

/* The four Wk sections (ISO 2631-1 Annex A), angular
 * frequencies w_i = 2 pi f_i. */
static void wk_sections(ride_analog_section s[WK_NSECTIONS])
{
  const double q_butter = 1.0 / sqrt(2.0);
  const double w1 = 2 * PI * 0.4, w2 = 2 * PI * 100.0;
  const double w3 = 2 * PI * 12.5, w4 = 2 * PI * 12.5, q4 = 0.63;
  const double w5 = 2 * PI * 2.37, q5 = 0.91, w6 = 2 * PI * 3.35, q6 = 0.91;
  /* High-pass s^2 / (s^2 + s w1 / Q1 + w1^2). */
  s[0] = (ride_analog_section){0, 0, 1, w1 * w1, w1 / q_butter, 1, w1};
  /* Low-pass w2^2 / (s^2 + s w2 / Q2 + w2^2). */
  s[1] = (ride_analog_section){w2 * w2, 0, 0, w2 * w2, w2 / q_butter, 1, w2};
  /* Transition (1 + s / w3) / (1 + s / (Q4 w4) + s^2 / w4^2), scaled by
   * w4^2 above and below. */
  s[2] = (ride_analog_section){w4 * w4, w4 * w4 / w3, 0, w4 * w4, w4 / q4, 1, w4};
  /* Upward step (1 + s / (Q5 w5) + s^2 / w5^2) / (1 + s / (Q6 w6) + s^2 /
   * w6^2) (w5 / w6)^2: 0.50 below f5, 1 above f6; prewarped at the
   * geometric mean of f5 and f6, where it changes. */
  s[3] = (ride_analog_section){w5 * w5, w5 / q5, 1, w6 * w6, w6 / q6, 1, sqrt(w5 * w6)};
}

double fb_ride_wk_magnitude(double f_hz)
{
  if (!isfinite(f_hz) || f_hz < 0)
    return NAN;
  ride_analog_section s[WK_NSECTIONS];
  wk_sections(s);
  return ride_analog_gain(s, WK_NSECTIONS, 2 * PI * f_hz);
}

int ride_check_rate(double fs, fb_err *err)
{
  if (!isfinite(fs) || fs < FB_RIDE_MIN_SAMPLE_RATE)
    return fb_err_set(err, FB_EINVAL,
                      "ride metrics: sample rate %g Hz is too low: the Wk weighting needs at "
                      "least %g Hz (4 x its 100 Hz band limit)",
                      fs, FB_RIDE_MIN_SAMPLE_RATE);
  return FB_OK;
}

int ride_check_finite(const double *a, size_t n, double fs, fb_err *err)
{
  for (size_t k = 0; k < n; ++k)
    if (!isfinite(a[k]))
      return fb_err_set(err, FB_EINVAL,
                        "ride metrics: acceleration sample %zu (t = %g s) is not finite (%g)",
                        k, (double)k / fs, a[k]);
  return FB_OK;
}

void ride_wk_biquads(double fs, ride_biquad q[RIDE_WK_NBIQUADS])
{
  ride_analog_section s[WK_NSECTIONS];
  wk_sections(s);
  ride_bilinear_all(s, WK_NSECTIONS, fs, q);
}

static const ride_cascade WK_CASCADE = {ride_wk_biquads, RIDE_WK_NBIQUADS, "Wk filter"};

double fb_ride_wk_digital_magnitude(double f_hz, double fs)
{
  return ride_cascade_gain(&WK_CASCADE, f_hz, fs);
}

int fb_ride_wk_filter(const double *a, size_t n, double fs, double *aw, fb_err *err)
{
  return ride_cascade_filter(&WK_CASCADE, a, n, fs, aw, err);
}
