/* SPDX-License-Identifier: BSD-3-Clause */
/* The NRMM peak (flexbond/ride.h): the vertical acceleration at the
 * driver low-passed by a 4th-order Butterworth filter of 30 Hz cut-off,
 * whose peak |a| NATO Reference Mobility Model practice compares with
 * 2.5 g on a single obstacle (NRMM II User's Guide, Ahlvin & Haley, US
 * Army Engineer Waterways Experiment Station, TR GL-92-19, 1992, for the
 * 2.5 g criterion; the filter's order and cut-off as in Project Chrono's
 * NRMM "legacy" peak, src/chrono/utils/ChFilters.cpp,
 * ChISO2631_Shock_SeatCushionLogger::GetLegacyAz; docs/ride-metrics.md).
 * The analog filter is |G(j w)| = 1 / sqrt(1 + (w / wc)^8); each of its
 * two sections is discretised by the bilinear transform prewarped at the
 * cut-off. */
#include <math.h>
#include <stddef.h>

#include "flexbond/ride.h"

#include "ride/ride_internal.h"

double fb_ride_nrmm_magnitude(double f_hz)
{
  if (!isfinite(f_hz) || f_hz < 0)
    return NAN;
  return 1 / sqrt(1 + pow(f_hz / FB_RIDE_NRMM_CUTOFF_HZ, 2 * FB_RIDE_NRMM_ORDER));
}

static void nrmm_biquads(double fs, ride_biquad *q)
{
  ride_butterworth_lowpass(FB_RIDE_NRMM_ORDER, FB_RIDE_NRMM_CUTOFF_HZ, fs, q);
}

static const ride_cascade NRMM_CASCADE = {nrmm_biquads, FB_RIDE_NRMM_ORDER / 2,
                                          "NRMM low-pass"};

double fb_ride_nrmm_digital_magnitude(double f_hz, double fs)
{
  return ride_cascade_gain(&NRMM_CASCADE, f_hz, fs);
}

int fb_ride_nrmm_filter(const double *a, size_t n, double fs, double *y, fb_err *err)
{
  return ride_cascade_filter(&NRMM_CASCADE, a, n, fs, y, err);
}
