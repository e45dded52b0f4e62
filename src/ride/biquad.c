/* SPDX-License-Identifier: BSD-3-Clause */
/* Second-order sections shared by the ride module's filters (Wk, the
 * absorbed-power filter, the Butterworth low-passes): the bilinear
 * transform of an analog section prewarped at one frequency (Oppenheim &
 * Schafer, "Discrete-Time Signal Processing", 3rd ed., sec. 7.2.2), the
 * gains of both forms and the recursion. */
#include <math.h>
#include <stddef.h>

#include "flexbond/ride.h"

#include "ride/ride_internal.h"

/* |c0 + c1 s + c2 s^2| at s = j w. */
static double poly_abs_jw(double c0, double c1, double c2, double w)
{
  return hypot(c0 - c2 * w * w, c1 * w);
}

double ride_analog_gain(const ride_analog_section *s, size_t n, double w)
{
  double gain = 1;
  for (size_t i = 0; i < n; ++i)
    gain *=
        poly_abs_jw(s[i].b0, s[i].b1, s[i].b2, w) / poly_abs_jw(s[i].a0, s[i].a1, s[i].a2, w);
  return gain;
}

ride_biquad ride_bilinear(const ride_analog_section *s, double fs)
{
  const double k = s->w_prewarp / tan(s->w_prewarp / (2 * fs)), k2 = k * k;
  /* Numerator and denominator times (1 + z^-1)^2, in powers of z^-1. */
  const double n0 = s->b0 + s->b1 * k + s->b2 * k2, n1 = 2 * (s->b0 - s->b2 * k2),
               n2 = s->b0 - s->b1 * k + s->b2 * k2;
  const double d0 = s->a0 + s->a1 * k + s->a2 * k2, d1 = 2 * (s->a0 - s->a2 * k2),
               d2 = s->a0 - s->a1 * k + s->a2 * k2;
  return (ride_biquad){n0 / d0, n1 / d0, n2 / d0, d1 / d0, d2 / d0};
}

void ride_bilinear_all(const ride_analog_section *s, size_t n, double fs, ride_biquad *q)
{
  for (size_t i = 0; i < n; ++i)
    q[i] = ride_bilinear(&s[i], fs);
}

double ride_biquad_gain(const ride_biquad *q, double theta)
{
  const double c1 = cos(theta), c2 = cos(2 * theta), s1 = sin(theta), s2 = sin(2 * theta);
  const double num = hypot(q->b0 + q->b1 * c1 + q->b2 * c2, q->b1 * s1 + q->b2 * s2);
  const double den = hypot(1 + q->a1 * c1 + q->a2 * c2, q->a1 * s1 + q->a2 * s2);
  return num / den;
}

void ride_biquads_run(const ride_biquad *q, size_t nq, double *y, size_t n)
{
  for (size_t i = 0; i < nq; ++i) {
    double z1 = 0, z2 = 0;
    for (size_t k = 0; k < n; ++k) {
      const double x = y[k], out = q[i].b0 * x + z1;
      z1 = q[i].b1 * x - q[i].a1 * out + z2;
      z2 = q[i].b2 * x - q[i].a2 * out;
      y[k] = out;
    }
  }
}

void ride_butterworth_lowpass(int order, double fc_hz, double fs, ride_biquad *q)
{
  const double pi = 3.14159265358979323846, wc = 2 * pi * fc_hz;
  for (int k = 1; 2 * k <= order; ++k) {
    const double angle = (2 * k - 1) * pi / (2 * order), q_factor = 1 / (2 * cos(angle));
    const ride_analog_section s = {wc * wc, 0, 0, wc * wc, wc / q_factor, 1, wc};
    q[k - 1] = ride_bilinear(&s, fs);
  }
}

double ride_cascade_gain(const ride_cascade *c, double f_hz, double fs)
{
  if (ride_check_rate(fs, NULL) != FB_OK || !(f_hz >= 0 && f_hz <= fs / 2))
    return NAN;
  ride_biquad q[RIDE_MAX_BIQUADS];
  c->design(fs, q);
  const double theta = 2 * 3.14159265358979323846 * f_hz / fs;
  double gain = 1;
  for (size_t i = 0; i < c->n; ++i)
    gain *= ride_biquad_gain(&q[i], theta);
  return gain;
}

int ride_cascade_filter(const ride_cascade *c, const double *a, size_t n, double fs, double *y,
                        fb_err *err)
{
  const int status = ride_filter_args(a, n, fs, y, c->name, err);
  if (status != FB_OK)
    return status;
  ride_biquad q[RIDE_MAX_BIQUADS];
  c->design(fs, q);
  ride_biquads_run(q, c->n, y, n);
  return FB_OK;
}

int ride_filter_args(const double *a, size_t n, double fs, double *y, const char *what,
                     fb_err *err)
{
  if (!a || !y || n == 0)
    return fb_err_set(err, FB_EINVAL, "%s: no samples (a %s, output %s, n = %zu)", what,
                      a ? "set" : "NULL", y ? "set" : "NULL", n);
  int status = ride_check_rate(fs, err);
  if (status == FB_OK)
    status = ride_check_finite(a, n, fs, err);
  if (status == FB_OK && y != a)
    for (size_t k = 0; k < n; ++k)
      y[k] = a[k];
  return status;
}
