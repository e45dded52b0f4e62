/* SPDX-License-Identifier: BSD-3-Clause */
/* Monotone piecewise cubic Hermite interpolation (PCHIP) of measured
 * profiles.
 *
 * Slopes: F. N. Fritsch & R. E. Carlson, "Monotone piecewise cubic
 * interpolation", SIAM J. Numer. Anal. 17(2), 1980, with the interior
 * slope as the weighted harmonic mean of the neighbouring secant slopes of
 * F. N. Fritsch & J. Butland, "A method for constructing local monotone
 * piecewise cubic interpolants", SIAM J. Sci. Stat. Comput. 5(2), 1984,
 * and a shape-preserving three-point formula at the ends (C. Moler,
 * "Numerical Computing with MATLAB", SIAM 2004, sec. 3.4). The result is
 * C1, and monotone wherever the data are. */
#include <math.h>

#include "road/road_internal.h"

/* Secant slope of interval k. */
static double secant(const double *s, const double *z, size_t k)
{
  return (z[k + 1] - z[k]) / (s[k + 1] - s[k]);
}

/* End slope from the first two intervals (widths h0, h1, secants d0, d1):
 * the derivative of the quadratic through three knots, reset to 0 if its
 * sign differs from d0's and limited to 3 d0 where the data turn, the
 * bound that keeps the first piece monotone (Fritsch & Carlson, sec. 4). */
static double end_slope(double h0, double h1, double d0, double d1)
{
  const double d = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
  if (d * d0 <= 0.0)
    return 0.0;
  if (d0 * d1 < 0.0 && fabs(d) > 3.0 * fabs(d0))
    return 3.0 * d0;
  return d;
}

void road_pchip_slopes(size_t n, const double *s, const double *z, double *d)
{
  if (n == 2) {
    d[0] = d[1] = secant(s, z, 0); /* a straight line */
    return;
  }
  for (size_t k = 1; k + 1 < n; ++k) {
    const double h0 = s[k] - s[k - 1], h1 = s[k + 1] - s[k];
    const double d0 = secant(s, z, k - 1), d1 = secant(s, z, k);
    if (d0 * d1 <= 0.0) {
      d[k] = 0.0; /* a local extremum or a flat piece: keep it flat */
      continue;
    }
    const double w0 = 2.0 * h1 + h0, w1 = h1 + 2.0 * h0;
    d[k] = (w0 + w1) / (w0 / d0 + w1 / d1);
  }
  d[0] = end_slope(s[1] - s[0], s[2] - s[1], secant(s, z, 0), secant(s, z, 1));
  d[n - 1] = end_slope(s[n - 1] - s[n - 2], s[n - 2] - s[n - 3], secant(s, z, n - 2),
                       secant(s, z, n - 3));
}

/* Index k of the interval [s[k], s[k+1]] holding x, s[0] <= x < s[n-1]
 * (binary search: long measured profiles). */
static size_t interval(size_t n, const double *s, double x)
{
  size_t lo = 0, hi = n - 1; /* invariant: s[lo] <= x < s[hi] */
  while (hi - lo > 1) {
    const size_t mid = lo + (hi - lo) / 2;
    if (s[mid] <= x)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

double road_pchip_height(size_t n, const double *s, const double *z, const double *d, double x)
{
  if (x <= s[0])
    return z[0];
  if (x >= s[n - 1])
    return z[n - 1];
  const size_t k = interval(n, s, x);
  const double h = s[k + 1] - s[k], t = (x - s[k]) / h;
  const double t2 = t * t, t3 = t2 * t;
  /* Cubic Hermite basis on [0, 1]. */
  return (2.0 * t3 - 3.0 * t2 + 1.0) * z[k] + (t3 - 2.0 * t2 + t) * h * d[k] +
         (3.0 * t2 - 2.0 * t3) * z[k + 1] + (t3 - t2) * h * d[k + 1];
}

double road_pchip_slope(size_t n, const double *s, const double *z, const double *d, double x)
{
  if (x <= s[0] || x >= s[n - 1])
    return 0.0;
  const size_t k = interval(n, s, x);
  const double h = s[k + 1] - s[k], t = (x - s[k]) / h;
  const double t2 = t * t;
  return (6.0 * t2 - 6.0 * t) * (z[k] - z[k + 1]) / h + (3.0 * t2 - 4.0 * t + 1.0) * d[k] +
         (3.0 * t2 - 2.0 * t) * d[k + 1];
}
