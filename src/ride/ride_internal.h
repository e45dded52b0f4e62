/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal: shared pieces of the ride-comfort module (flexbond/ride.h). */
#ifndef FLEXBOND_RIDE_INTERNAL_H
#define FLEXBOND_RIDE_INTERNAL_H

#include <stddef.h>

#include "flexbond/error.h"

/* A digital section (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2). */
typedef struct ride_biquad {
  double b0, b1, b2, a1, a2;
} ride_biquad;

/* An analog section (b0 + b1 s + b2 s^2) / (a0 + a1 s + a2 s^2) and the
 * angular frequency its bilinear transform is prewarped at. A first-order
 * section has b2 = a2 = 0. */
typedef struct ride_analog_section {
  double b0, b1, b2, a0, a1, a2;
  double w_prewarp; /* rad/s, below pi fs */
} ride_analog_section;

enum { RIDE_WK_NBIQUADS = 4 };

/* The Wk sections discretised at fs (fs >= FB_RIDE_MIN_SAMPLE_RATE). */
void ride_wk_biquads(double fs, ride_biquad q[RIDE_WK_NBIQUADS]);

/* Bilinear transform s = k (1 - z^-1) / (1 + z^-1) of s prewarped at its
 * w_prewarp, k = w_prewarp / tan(w_prewarp / (2 fs)) (Oppenheim & Schafer,
 * "Discrete-Time Signal Processing", 3rd ed., sec. 7.2.2). */
ride_biquad ride_bilinear(const ride_analog_section *s, double fs);

/* ride_bilinear of each of s[0..n), into q[0..n). */
void ride_bilinear_all(const ride_analog_section *s, size_t n, double fs, ride_biquad *q);

/* |prod_i s_i(j w)| over s[0..n), w in rad/s. */
double ride_analog_gain(const ride_analog_section *s, size_t n, double w);

/* |q(e^(j theta))|, theta = 2 pi f / fs. */
double ride_biquad_gain(const ride_biquad *q, double theta);

/* Runs y[0..n-1] through the sections q[0..nq-1] in cascade, in place,
 * each a transposed direct form II from rest. */
void ride_biquads_run(const ride_biquad *q, size_t nq, double *y, size_t n);

/* The order / 2 sections of an even-order Butterworth low-pass of cut-off
 * fc_hz (< fs / 2), each prewarped at the cut-off so the digital gain is
 * exactly 1/sqrt 2 there: section k = 1..order/2 has the poles at angles
 * +-(2k - 1) pi / (2 order) from the negative real axis, Q = 1 / (2 cos)
 * of that angle (Oppenheim & Schafer, 3rd ed., sec. 7.1.2). */
void ride_butterworth_lowpass(int order, double fc_hz, double fs, ride_biquad *q);

/* A cascade of at most RIDE_MAX_BIQUADS sections designed for a sample
 * rate: fills q[0..n) for fs. */
enum { RIDE_MAX_BIQUADS = 4 };
typedef struct ride_cascade {
  void (*design)(double fs, ride_biquad *q);
  size_t n;
  const char *name; /* for messages, e.g. "Wk filter" */
} ride_cascade;

/* The cascade's gain at f_hz in [0, fs/2]; NAN outside or for fs below
 * FB_RIDE_MIN_SAMPLE_RATE. */
double ride_cascade_gain(const ride_cascade *c, double f_hz, double fs);

/* Filters a[0..n-1] into y[0..n-1] (may be a) through the cascade from
 * rest, after ride_filter_args. */
int ride_cascade_filter(const ride_cascade *c, const double *a, size_t n, double fs, double *y,
                        fb_err *err);

/* Checks the arguments of a filter of a[0..n-1] into y[0..n-1] named
 * what (a non-empty finite record at an accepted rate) and copies a into
 * y unless they are the same array. */
int ride_filter_args(const double *a, size_t n, double fs, double *y, const char *what,
                     fb_err *err);

/* The ISO 2631-5 Annex A spine network (src/ride/spine.c). */
enum { RIDE_SPINE_HIDDEN = 7, RIDE_SPINE_OUT_DELAYS = 4, RIDE_SPINE_IN_DELAYS = 8 };
typedef struct ride_spine_net {
  double w_rec[RIDE_SPINE_OUT_DELAYS][RIDE_SPINE_HIDDEN]; /* of a_lz(t - k), k = 1.. */
  double w_in[RIDE_SPINE_IN_DELAYS][RIDE_SPINE_HIDDEN];   /* of a_z(t - k), k = 1.. */
  double bias[RIDE_SPINE_HIDDEN];
  double w_out[RIDE_SPINE_HIDDEN];
  double out_bias;
} ride_spine_net;

/* The network's weights (static storage). */
const ride_spine_net *ride_spine_weights(void);

/* D_z (fb_ride_spine_dose) of the response to a[0..k1-1] (m/s^2, fs Hz)
 * low-passed against aliasing and resampled at FB_RIDE_SPINE_RATE, over
 * the model samples whose times lie in [k0 / fs, k1 / fs). The model
 * runs from a[0]. k1 >= 1, k0 < k1. FB_ENOMEM. */
int ride_spine_window_dose(const double *a, size_t k0, size_t k1, double fs, double *dz,
                           fb_err *err);

/* FB_EINVAL if fs is not finite or below FB_RIDE_MIN_SAMPLE_RATE. */
int ride_check_rate(double fs, fb_err *err);

/* FB_EINVAL naming the first non-finite sample of a[0..n-1] and its time
 * k / fs. */
int ride_check_finite(const double *a, size_t n, double fs, fb_err *err);

#endif
