/* SPDX-License-Identifier: BSD-3-Clause */
/* ISO 2631-5:2004 method for vibration containing multiple shocks,
 * vertical axis (flexbond/ride.h): the lumbar spine's acceleration
 * response a_lz to the seat's vertical acceleration a_z, the acceleration
 * dose D_z and the daily equivalent static compression dose S_ed.
 *
 * The spine model is the standard's Annex A recurrent neural network
 * (Nicol, Morrison, Roddan & Rawicz, "Modelling the dynamic response of
 * the human spine to shock and vibration using a recurrent neural
 * network", International Journal of Heavy Vehicle Systems, 1997), at 160 Hz:
 *
 *   u_j(t) = tanh( sum_{k=1..4} w_kj a_lz(t-k) + sum_{k=1..8} v_kj a_z(t-k) + b_j ),
 *   a_lz(t) = sum_{j=1..7} W_j u_j(t) + W_8,
 *
 * with t counting samples; the weights below are the standard's (Annex A,
 * the same values as in Project Chrono's ChISO2631_5_Wz, which was read to
 * check the transcription and the order of the delays). The response at
 * rest settles at a_lz = -0.0216 m/s^2, so a record of zeros has no
 * positive peak and D_z = 0.
 *
 * D_z = (sum_i A_iz^6)^(1/6) over the positive peaks A_iz of a_lz, and
 * S_ed = m_z D_z with m_z = 0.032 MPa / (m/s^2) when the measured interval
 * is the day's whole exposure (the standard scales D_z by (t_d / t_m)^(1/6)
 * for a daily duration t_d over a measured t_m). */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include "flexbond/ride.h"

#include "ride/ride_internal.h"

/* The standard's weights: w_kj of a_lz(t - k) and v_kj of a_z(t - k) into
 * hidden unit j, the hidden units' biases b_j, output weights W_j and
 * output bias W_8. */
static const ride_spine_net NET = {
    .w_rec =
        {
            {0.00130, 0.01841, -0.00336, 0.01471, 0.00174, 0.00137, 0.00145},
            {-0.00646, -0.00565, -0.00539, 0.01544, -0.00542, 0.00381, 0.00497},
            {-0.00091, -0.02073, 0.00708, -0.00091, 0.00255, -0.00216, 0.01001},
            {0.00898, -0.02626, 0.00438, -0.00595, -0.00774, -0.00034, 0.01280},
        },
    .w_in =
        {
            {0.00201, 0.00579, 0.00330, -0.00065, -0.00459, -0.00417, -0.00468},
            {0.00158, 0.00859, 0.00166, 0.00490, -0.00546, 0.00057, -0.00797},
            {0.00361, 0.00490, 0.00452, 0.00079, -0.00604, -0.00638, -0.00529},
            {0.00167, -0.00098, 0.00743, 0.00795, -0.01095, 0.00627, -0.00341},
            {-0.00078, -0.00261, 0.00771, 0.00600, -0.00908, 0.00504, 0.00135},
            {-0.00405, -0.00210, 0.00520, 0.00176, -0.00465, -0.00198, 0.00451},
            {-0.00563, 0.00218, -0.00105, 0.00195, 0.00296, -0.00190, 0.00306},
            {-0.00372, 0.00037, -0.00045, -0.00197, 0.00289, -0.00448, 0.00216},
        },
    .bias = {-0.31088, -0.95883, -0.67105, 0.14423, 0.04063, 0.07029, 1.03300},
    .w_out = {57.96539, 52.32773, 49.78227, 53.16885, 56.02619, -27.79550, 72.34446},
    .out_bias = 21.51959,
};

const ride_spine_net *ride_spine_weights(void)
{
  return &NET;
}

/* x[t - k] for k >= 1, 0 before the record. */
static double past(const double *x, size_t t, size_t k)
{
  return t >= k ? x[t - k] : 0.0;
}

void fb_ride_spine_response(const double *az, size_t n, double *alz)
{
  for (size_t t = 0; t < n; ++t) {
    double out = NET.out_bias;
    for (int j = 0; j < RIDE_SPINE_HIDDEN; ++j) {
      double arg = NET.bias[j];
      for (size_t k = 1; k <= RIDE_SPINE_OUT_DELAYS; ++k)
        arg += NET.w_rec[k - 1][j] * past(alz, t, k);
      for (size_t k = 1; k <= RIDE_SPINE_IN_DELAYS; ++k)
        arg += NET.w_in[k - 1][j] * past(az, t, k);
      out += NET.w_out[j] * tanh(arg);
    }
    alz[t] = out;
  }
}

double fb_ride_spine_dose(const double *alz, size_t n)
{
  double sum6 = 0, peak = 0;
  for (size_t t = 0; t < n; ++t) {
    if (alz[t] > 0) {
      peak = fmax(peak, alz[t]);
      continue;
    }
    sum6 += pow(peak, 6);
    peak = 0;
  }
  sum6 += pow(peak, 6);
  return pow(sum6, 1.0 / 6.0);
}

/* The anti-aliasing low-pass before the 160 Hz resampling: 4th-order
 * Butterworth at 60 Hz (gain 0.998 at 30 Hz, 0.49 at the 80 Hz Nyquist
 * frequency of the model's rate). */
enum { SPINE_AA_ORDER = 4 };
static const double SPINE_AA_CUTOFF_HZ = 60.0;

int ride_spine_window_dose(const double *a, size_t k0, size_t k1, double fs, double *dz,
                           fb_err *err)
{
  const double ratio = fs / FB_RIDE_SPINE_RATE; /* input samples per model sample */
  const size_t m_count = (size_t)floor((double)(k1 - 1) / ratio) + 1;
  const double m_first = ceil((double)k0 / ratio - 1e-9);
  const size_t m0 = m_first > 0 ? (size_t)m_first : 0;
  double *lp = malloc(k1 * sizeof *lp), *az = calloc(2 * m_count, sizeof *az);
  if (!lp || !az) {
    free(lp);
    free(az);
    return fb_err_set(err, FB_ENOMEM, "ride metrics: out of memory for the spine model");
  }
  for (size_t k = 0; k < k1; ++k)
    lp[k] = a[k];
  ride_biquad q[SPINE_AA_ORDER / 2];
  ride_butterworth_lowpass(SPINE_AA_ORDER, SPINE_AA_CUTOFF_HZ, fs, q);
  ride_biquads_run(q, SPINE_AA_ORDER / 2, lp, k1);
  /* Linear interpolation at t_m = m / 160 Hz, inside [0, (k1 - 1) / fs]. */
  for (size_t m = 0; m < m_count; ++m) {
    const double x = (double)m * ratio;
    const size_t i = (size_t)floor(x);
    const double u = x - (double)i;
    az[m] = i + 1 < k1 ? lp[i] + u * (lp[i + 1] - lp[i]) : lp[i];
  }
  double *alz = az + m_count;
  fb_ride_spine_response(az, m_count, alz);
  *dz = m0 < m_count ? fb_ride_spine_dose(alz + m0, m_count - m0) : 0.0;
  free(lp);
  free(az);
  return FB_OK;
}
