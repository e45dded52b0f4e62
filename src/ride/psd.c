/* SPDX-License-Identifier: BSD-3-Clause */
/* Ride from a road spectrum (flexbond/ride.h): the temporal PSD of an
 * ISO 8608 road at a speed, and the mean square of a response from its
 * PSD. A road of spatial PSD Gd(n) (m^3, n in cycles/m) driven at V
 * (m/s) has the temporal PSD Gd(f / V) / V (m^2/Hz): a band dn of
 * wavenumbers is the band df = V dn of frequencies, with the same
 * variance (ISO 8608:2016, Annex C; Wong, "Theory of Ground Vehicles",
 * 4th ed., 2008, sec. 7.1). */
#include <math.h>

#include "flexbond/ride.h"

/* ISO 8608's reference wavenumber n0, cycles/m, and its exponent w. */
static const double N0 = 0.1, WAVINESS = 2.0;

double fb_ride_road_psd(double gd0, double speed, double f_hz)
{
  if (!(speed > 0) || !(f_hz > 0) || !(gd0 >= 0))
    return NAN;
  return gd0 * pow(f_hz / speed / N0, -WAVINESS) / speed;
}

double fb_ride_two_track_psd(const double h_left[2], const double h_right[2], double road_psd,
                             int identical)
{
  const double *l = h_left, *r = h_right;
  const double power = identical ? (l[0] + r[0]) * (l[0] + r[0]) + (l[1] + r[1]) * (l[1] + r[1])
                                 : l[0] * l[0] + l[1] * l[1] + r[0] * r[0] + r[1] * r[1];
  return power * road_psd;
}

double fb_ride_psd_integral(const double *f_hz, const double *psd, size_t n)
{
  /* The trapezoidal rule in ln f, integral of psd f d(ln f): on a log grid
   * it follows a power law such as the road's f^-2 far better than the
   * trapezoidal rule in f does. */
  double sum = 0.0;
  for (size_t k = 0; k + 1 < n; ++k)
    sum += 0.5 * (psd[k] * f_hz[k] + psd[k + 1] * f_hz[k + 1]) * log(f_hz[k + 1] / f_hz[k]);
  return sum;
}
