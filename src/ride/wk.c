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

/* An analog section (b0 + b1 s + b2 s^2) / (a0 + a1 s + a2 s^2) and the
 * angular frequency its bilinear transform is prewarped at. */
typedef struct analog_section {
  double b0, b1, b2, a0, a1, a2;
  double w_prewarp; /* rad/s */
} analog_section;

enum { WK_NSECTIONS = 4 };

/* The four Wk sections (ISO 2631-1 Annex A), angular
 * frequencies w_i = 2 pi f_i. */
static void wk_sections(analog_section s[WK_NSECTIONS])
{
  const double q_butter = 1.0 / sqrt(2.0);
  const double w1 = 2 * PI * 0.4, w2 = 2 * PI * 100.0;
  const double w3 = 2 * PI * 12.5, w4 = 2 * PI * 12.5, q4 = 0.63;
  const double w5 = 2 * PI * 2.37, q5 = 0.91, w6 = 2 * PI * 3.35, q6 = 0.91;
  /* High-pass s^2 / (s^2 + s w1 / Q1 + w1^2). */
  s[0] = (analog_section){0, 0, 1, w1 * w1, w1 / q_butter, 1, w1};
  /* Low-pass w2^2 / (s^2 + s w2 / Q2 + w2^2). */
  s[1] = (analog_section){w2 * w2, 0, 0, w2 * w2, w2 / q_butter, 1, w2};
  /* Transition (1 + s / w3) / (1 + s / (Q4 w4) + s^2 / w4^2), scaled by
   * w4^2 above and below. */
  s[2] = (analog_section){w4 * w4, w4 * w4 / w3, 0, w4 * w4, w4 / q4, 1, w4};
  /* Upward step (1 + s / (Q5 w5) + s^2 / w5^2) / (1 + s / (Q6 w6) + s^2 /
   * w6^2) (w5 / w6)^2: 0.50 below f5, 1 above f6; prewarped at the
   * geometric mean of f5 and f6, where it changes. */
  s[3] = (analog_section){w5 * w5, w5 / q5, 1, w6 * w6, w6 / q6, 1, sqrt(w5 * w6)};
}

/* |c0 + c1 s + c2 s^2| at s = j w. */
static double poly_abs_jw(double c0, double c1, double c2, double w)
{
  return hypot(c0 - c2 * w * w, c1 * w);
}

double fb_ride_wk_magnitude(double f_hz)
{
  if (!isfinite(f_hz) || f_hz < 0)
    return NAN;
  analog_section s[WK_NSECTIONS];
  wk_sections(s);
  const double w = 2 * PI * f_hz;
  double gain = 1;
  for (int i = 0; i < WK_NSECTIONS; ++i)
    gain *=
        poly_abs_jw(s[i].b0, s[i].b1, s[i].b2, w) / poly_abs_jw(s[i].a0, s[i].a1, s[i].a2, w);
  return gain;
}

/* Bilinear transform s = k (1 - z^-1) / (1 + z^-1) of one analog section
 * prewarped at its w_prewarp; fs > w_prewarp / pi, so k is finite. */
static ride_biquad bilinear(const analog_section *s, double fs)
{
  const double k = s->w_prewarp / tan(s->w_prewarp / (2 * fs)), k2 = k * k;
  /* Numerator and denominator times (1 + z^-1)^2, in powers of z^-1. */
  const double n0 = s->b0 + s->b1 * k + s->b2 * k2, n1 = 2 * (s->b0 - s->b2 * k2),
               n2 = s->b0 - s->b1 * k + s->b2 * k2;
  const double d0 = s->a0 + s->a1 * k + s->a2 * k2, d1 = 2 * (s->a0 - s->a2 * k2),
               d2 = s->a0 - s->a1 * k + s->a2 * k2;
  return (ride_biquad){n0 / d0, n1 / d0, n2 / d0, d1 / d0, d2 / d0};
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

/* |b0 + b1 z^-1 + b2 z^-2| / |1 + a1 z^-1 + a2 z^-2| at z = e^(j theta). */
static double biquad_gain(const ride_biquad *q, double theta)
{
  const double c1 = cos(theta), c2 = cos(2 * theta), s1 = sin(theta), s2 = sin(2 * theta);
  const double num = hypot(q->b0 + q->b1 * c1 + q->b2 * c2, q->b1 * s1 + q->b2 * s2);
  const double den = hypot(1 + q->a1 * c1 + q->a2 * c2, q->a1 * s1 + q->a2 * s2);
  return num / den;
}

void ride_wk_biquads(double fs, ride_biquad q[RIDE_WK_NBIQUADS])
{
  analog_section s[WK_NSECTIONS];
  wk_sections(s);
  for (int i = 0; i < WK_NSECTIONS; ++i)
    q[i] = bilinear(&s[i], fs);
}

double fb_ride_wk_digital_magnitude(double f_hz, double fs)
{
  if (ride_check_rate(fs, NULL) != FB_OK || !(f_hz >= 0 && f_hz <= fs / 2))
    return NAN;
  ride_biquad q[RIDE_WK_NBIQUADS];
  ride_wk_biquads(fs, q);
  const double theta = 2 * PI * f_hz / fs;
  double gain = 1;
  for (int i = 0; i < RIDE_WK_NBIQUADS; ++i)
    gain *= biquad_gain(&q[i], theta);
  return gain;
}

/* Runs y through one section in place (transposed direct form II, from
 * rest). */
static void biquad_run(const ride_biquad *q, double *y, size_t n)
{
  double z1 = 0, z2 = 0;
  for (size_t k = 0; k < n; ++k) {
    const double x = y[k], out = q->b0 * x + z1;
    z1 = q->b1 * x - q->a1 * out + z2;
    z2 = q->b2 * x - q->a2 * out;
    y[k] = out;
  }
}

int fb_ride_wk_filter(const double *a, size_t n, double fs, double *aw, fb_err *err)
{
  if (!a || !aw || n == 0)
    return fb_err_set(err, FB_EINVAL, "Wk filter: no samples (a %s, aw %s, n = %zu)",
                      a ? "set" : "NULL", aw ? "set" : "NULL", n);
  int status = ride_check_rate(fs, err);
  if (status == FB_OK)
    status = ride_check_finite(a, n, fs, err);
  if (status != FB_OK)
    return status;
  ride_biquad q[RIDE_WK_NBIQUADS];
  ride_wk_biquads(fs, q);
  if (aw != a)
    for (size_t k = 0; k < n; ++k)
      aw[k] = a[k];
  for (int i = 0; i < RIDE_WK_NBIQUADS; ++i)
    biquad_run(&q[i], aw, n);
  return FB_OK;
}
