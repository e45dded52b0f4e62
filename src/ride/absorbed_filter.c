/* SPDX-License-Identifier: BSD-3-Clause */
/* The built-in vertical absorbed-power filter (flexbond/ride.h).
 *
 * Pradko, Lee & Kaluza ("Theory of human vibration response", ASME paper
 * 66-WA/BHF-15, 1966) and Lee & Pradko ("Analytical analysis of human
 * vibration", SAE paper 680091, 1968) model the seated body as a linear
 * system whose absorbed power is the mean square of the seat's vertical
 * acceleration passed through a transfer function; with the acceleration
 * in ft/s^2 (the papers' unit) it is
 *
 *   H(s) = 14.5 s (s + 44) / ((s + 63) (s^2 + 24 s + 750)),
 *
 * P = mean of (H a)^2, W. These are the coefficients of the vertical
 * absorbed-power filter of Project Chrono (src/chrono/utils/ChFilters.cpp,
 * class ChAbsorbed_Power_Vertical, which feeds it the acceleration in
 * ft/s^2 and averages the square of its output), whose Tustin
 * discretisation factors exactly into this H(s); see docs/ride-metrics.md
 * for what could and could not be traced to the papers. Here a in m/s^2 is
 * scaled to ft/s^2 by 1 / 0.3048 (the international foot), and H is
 * discretised as two sections, the second-order one prewarped at its
 * natural frequency sqrt(750) rad/s and the first-order one at its pole
 * 63 rad/s. */
#include <math.h>
#include <stddef.h>

#include "flexbond/ride.h"

#include "ride/ride_internal.h"

static const double PI = 3.14159265358979323846;
static const double FT_PER_M = 1.0 / 0.3048;

enum { AP_NSECTIONS = 2 };

/* H(s) a_ft = H(s) FT_PER_M a: the sections with the unit scaling folded
 * into the first one's numerator. */
static void ap_sections(ride_analog_section s[AP_NSECTIONS])
{
  const double gain = 14.5 * FT_PER_M;
  s[0] = (ride_analog_section){0, gain * 44, gain, 750, 24, 1, sqrt(750.0)};
  s[1] = (ride_analog_section){1, 0, 0, 63, 1, 0, 63};
}

double fb_ride_absorbed_coef(double f_hz)
{
  if (!isfinite(f_hz) || f_hz < 0)
    return NAN;
  ride_analog_section s[AP_NSECTIONS];
  ap_sections(s);
  const double h = ride_analog_gain(s, AP_NSECTIONS, 2 * PI * f_hz);
  return h * h;
}

static void ap_biquads(double fs, ride_biquad *q)
{
  ride_analog_section s[AP_NSECTIONS];
  ap_sections(s);
  ride_bilinear_all(s, AP_NSECTIONS, fs, q);
}

static const ride_cascade AP_CASCADE = {ap_biquads, AP_NSECTIONS, "absorbed-power filter"};

double fb_ride_absorbed_digital_coef(double f_hz, double fs)
{
  const double h = ride_cascade_gain(&AP_CASCADE, f_hz, fs);
  return h * h;
}

int fb_ride_absorbed_filter(const double *a, size_t n, double fs, double *y, fb_err *err)
{
  return ride_cascade_filter(&AP_CASCADE, a, n, fs, y, err);
}
