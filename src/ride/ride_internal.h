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

enum { RIDE_WK_NBIQUADS = 4 };

/* The Wk sections discretised at fs (fs >= FB_RIDE_MIN_SAMPLE_RATE). */
void ride_wk_biquads(double fs, ride_biquad q[RIDE_WK_NBIQUADS]);

/* FB_EINVAL if fs is not finite or below FB_RIDE_MIN_SAMPLE_RATE. */
int ride_check_rate(double fs, fb_err *err);

/* FB_EINVAL naming the first non-finite sample of a[0..n-1] and its time
 * k / fs. */
int ride_check_finite(const double *a, size_t n, double fs, fb_err *err);

#endif
