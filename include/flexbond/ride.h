/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: ride-comfort metrics of a vertical acceleration record.
 *
 * From a uniformly sampled vertical acceleration a(t) (m/s^2, e.g. the
 * driver_acc output at 1 kHz) this module computes the ISO 2631-1:1997
 * whole-body vibration values of the Wk-weighted acceleration a_w(t)
 * (weighted r.m.s., running r.m.s. and MTVV, VDV, crest factor, the VDV
 * against the health guidance caution zone and the crest-factor rule),
 * the unweighted jerk, the absorbed power of Pradko & Lee, the NRMM peak
 * (30 Hz low-passed |a| against 2.5 g) and the ISO 2631-5:2004 spinal
 * dose (vertical). Definitions, sources and discretisation:
 * docs/ride-metrics.md.
 *
 * Conventions: sample k of a record is at time k / fs after the record's
 * first sample; a record of n samples spans n / fs seconds (each sample
 * stands for one sampling interval, so sums over whole periods of a sine
 * are exact). Arrays are borrowed and never kept. Every function that can
 * fail returns a status of flexbond/error.h and leaves its outputs
 * unspecified on failure. No state is kept between calls. */
#ifndef FLEXBOND_RIDE_H
#define FLEXBOND_RIDE_H

#include <stddef.h>

#include "flexbond/error.h"
#include "flexbond/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Lowest sample rate accepted, Hz: four times the Wk band-limiting
 * low-pass corner (100 Hz). The bilinear transform's frequency warping
 * makes the digital |Wk| low by 0.23 % at 31.5 Hz, 0.75 % at 63 Hz and
 * 3.3 % at 100 Hz at fs = 1 kHz, but by 1.5 %, 5.1 % and 21 % at 400 Hz;
 * at 200 Hz and below the low-pass cannot be realised at all. */
#define FB_RIDE_MIN_SAMPLE_RATE 400.0

/* Absorbed-power limit for military vehicles, W (the 6 W vertical
 * tolerance of NATO Reference Mobility Model practice). */
#define FB_RIDE_ABSORBED_POWER_LIMIT 6.0

/* The NRMM peak's limit, m/s^2: 2.5 g (g = 9.80665 m/s^2, the standard
 * gravity of ISO 80000-3), the peak vertical acceleration at the driver
 * tolerated on a single obstacle in NATO Reference Mobility Model
 * practice (docs/ride-metrics.md). */
#define FB_RIDE_NRMM_PEAK_LIMIT (2.5 * 9.80665)

/* The NRMM peak's low-pass: Butterworth of this order and cut-off (Hz). */
#define FB_RIDE_NRMM_CUTOFF_HZ 30.0
enum { FB_RIDE_NRMM_ORDER = 4 };

/* VDV's reference, m/s^1.75: the lower bound of ISO 2631-1:1997 Annex B's
 * health guidance caution zone (B.3.1: the zone spans 8.5 to 17). */
#define FB_RIDE_VDV_CAUTION 8.5

/* ISO 2631-1:1997 6.2.1: above this crest factor the basic method
 * (a_w) may underestimate the effects; use VDV or MTVV. */
#define FB_RIDE_CREST_LIMIT 9.0

/* ISO 2631-5:2004's sample rate of the spine model, Hz, and its vertical
 * constant m_z, MPa per m/s^2 (S_ed = m_z D_z for the vertical axis). */
#define FB_RIDE_SPINE_RATE 160.0
#define FB_RIDE_SPINE_MZ 0.032

typedef struct fb_ride_metrics {
  double a_w_rms;        /* Wk-weighted r.m.s. acceleration, m/s^2 (ISO 2631-1 6.1) */
  double mtvv;           /* maximum transient vibration value, m/s^2 (6.3.1) */
  double vdv;            /* vibration dose value, m/s^1.75 (6.3.2) */
  double crest;          /* max |a_w| / a_w_rms (6.2.1); 0 when a_w_rms is 0 */
  double absorbed_power; /* W: the built-in filter, or the K(f) table when given */
  double jerk_peak;      /* max |da/dt| of the unweighted signal, m/s^3 */
  double jerk_rms;       /* r.m.s. of da/dt, m/s^3 */
  double duration;       /* evaluated interval, s (samples / fs) */
  double nrmm_peak;      /* max |a| after the 30 Hz Butterworth low-pass, m/s^2 */
  double se;           /* S_ed = m_z dz, the interval as the day's exposure, MPa (ISO 2631-5) */
  double dz;           /* vertical acceleration dose D_z, m/s^2 (ISO 2631-5) */
  double vdv_ratio;    /* vdv / FB_RIDE_VDV_CAUTION */
  double crest_over_9; /* 1 when crest > FB_RIDE_CREST_LIMIT, else 0 */
} fb_ride_metrics;

/* Absorbed-power coefficients K(f): the power absorbed by a seated
 * person per unit mean-square vertical acceleration at frequency f,
 * W / (m/s^2)^2 r.m.s. Interpolated log-log between the points; 0
 * outside [freq_hz[0], freq_hz[n-1]]. */
typedef struct fb_ride_kf_table {
  const double *freq_hz; /* n > 1 values, strictly increasing, > 0 (borrowed) */
  const double *coef;    /* n values > 0 (borrowed) */
  size_t n;
} fb_ride_kf_table;

typedef struct fb_ride_opts {
  double integration_time;             /* running r.m.s. window tau, s (default 1) */
  const fb_ride_kf_table *absorbed_kf; /* NULL (default): the built-in filter */
} fb_ride_opts;

/* Fills the defaults stated above. */
void fb_ride_opts_default(fb_ride_opts *opts);

/* |Wk(j 2 pi f)|, the analytic ISO 2631-1 Annex A weighting (band
 * limiting, acceleration-velocity transition and upward step) at f_hz
 * >= 0; NAN for a negative or non-finite f_hz. */
double fb_ride_wk_magnitude(double f_hz);

/* The one-sided temporal PSD (m^2/Hz) at f_hz > 0 of a road whose spatial
 * PSD is ISO 8608's Gd(n) = gd0 (n / 0.1)^-2 (gd0 in m^3 at 0.1
 * cycles/m: fb_road_iso8608_gd0), driven at speed (m/s, > 0):
 * Gd(f / speed) / speed. NAN for a bad argument. The caller limits it to
 * the road's band. */
double fb_ride_road_psd(double gd0, double speed, double f_hz);

/* The PSD of a vehicle's output at one frequency (its unit^2/Hz) on a
 * road whose tracks each have the one-sided PSD road_psd (m^2/Hz): h_left
 * and h_right are the output's complex responses (re, im; unit/m) to a
 * unit height on the left and on the right track. Independent tracks
 * (identical 0) add their powers, |H_l|^2 + |H_r|^2; identical ones
 * (coherence 1) add their amplitudes, |H_l + H_r|^2 (Bendat & Piersol,
 * "Random Data", 4th ed., sec. 6.1: the output spectrum of a two-input
 * linear system with uncorrelated or fully coherent inputs). */
double fb_ride_two_track_psd(const double h_left[2], const double h_right[2], double road_psd,
                             int identical);

/* The integral of a one-sided PSD psd[0..n) (unit^2/Hz) over its
 * frequencies f_hz[0..n) (Hz, increasing, > 0): the mean square of the
 * signal in that band, by the trapezoidal rule in log f. */
double fb_ride_psd_integral(const double *f_hz, const double *psd, size_t n);

/* Magnitude of the digital filter fb_ride_wk_filter applies at sample
 * rate fs, at frequency f_hz in [0, fs/2]: the exact steady-state gain
 * of that filter for a sine of frequency f_hz. NAN when fs is below
 * FB_RIDE_MIN_SAMPLE_RATE or f_hz is outside [0, fs/2]. */
double fb_ride_wk_digital_magnitude(double f_hz, double fs);

/* Filters a[0..n-1] (m/s^2, sampled at fs Hz) through the Wk weighting
 * into aw[0..n-1] (may be a itself). The filter starts at rest (the
 * signal is taken as 0 before a[0]), so its transients (slowest decay
 * time ~0.56 s, from the 0.4 Hz high-pass) are part of aw. FB_EINVAL if
 * n is 0, a or aw is NULL, fs is not finite or below
 * FB_RIDE_MIN_SAMPLE_RATE, or a sample is not finite. */
int fb_ride_wk_filter(const double *a, size_t n, double fs, double *aw, fb_err *err);

/* Absorbed power of a[0..n-1] (m/s^2, fs Hz), W: sum over the record's
 * spectral lines f_k = k fs / n (0 < f_k <= fs/2) of K(f_k) times the
 * line's mean square, the record's mean power. FB_EINVAL for n < 2, a
 * NULL, fs not finite and positive, a non-finite sample or a malformed
 * table (its message says which entry). Cost: n times the number of lines
 * inside the table's band. */
int fb_ride_absorbed_power(const double *a, size_t n, double fs, const fb_ride_kf_table *kf,
                           double *watts, fb_err *err);

/* K(f) of the built-in absorbed-power filter, W / (m/s^2)^2 r.m.s.: the
 * analog |H(j 2 pi f)|^2 of Pradko, Lee & Kaluza's vertical transfer
 * function at f_hz >= 0 (docs/ride-metrics.md); NAN for a negative or
 * non-finite f_hz. */
double fb_ride_absorbed_coef(double f_hz);

/* The same of the digital filter fb_ride_absorbed_filter applies at fs
 * (>= FB_RIDE_MIN_SAMPLE_RATE), f_hz in [0, fs/2]: the exact steady-state
 * power per mean-square acceleration of a sine of f_hz. NAN otherwise. */
double fb_ride_absorbed_digital_coef(double f_hz, double fs);

/* Filters a[0..n-1] (m/s^2, fs Hz) into y[0..n-1] (W^(1/2), may be a)
 * through the absorbed-power filter, from rest: the mean of y^2 over an
 * interval is the power absorbed in it, W. Errors as fb_ride_wk_filter. */
int fb_ride_absorbed_filter(const double *a, size_t n, double fs, double *y, fb_err *err);

/* |G(j 2 pi f)| of the NRMM peak's analog Butterworth low-pass,
 * 1 / sqrt(1 + (f / fc)^(2 N)); NAN for a negative or non-finite f_hz. */
double fb_ride_nrmm_magnitude(double f_hz);

/* The digital gain of fb_ride_nrmm_filter at fs, f_hz in [0, fs/2]; NAN
 * otherwise or for fs below FB_RIDE_MIN_SAMPLE_RATE. */
double fb_ride_nrmm_digital_magnitude(double f_hz, double fs);

/* Low-passes a[0..n-1] (m/s^2, fs Hz) into y[0..n-1] (may be a), from
 * rest. Errors as fb_ride_wk_filter. */
int fb_ride_nrmm_filter(const double *a, size_t n, double fs, double *y, fb_err *err);

/* The ISO 2631-5:2004 Annex A vertical spine model: the response
 * alz[0..n-1] (m/s^2) of the lumbar spine to the seat's vertical
 * acceleration az[0..n-1] (m/s^2) sampled at FB_RIDE_SPINE_RATE, from rest
 * (az and alz 0 before the first sample). Nonlinear; alz may not be az. */
void fb_ride_spine_response(const double *az, size_t n, double *alz);

/* D_z = (sum of A_i^6)^(1/6) of a response alz[0..n-1], A_i the largest
 * value of each run of positive samples (ISO 2631-5: the positive,
 * compressive peaks between zero crossings), m/s^2. */
double fb_ride_spine_dose(const double *alz, size_t n);

/* Every metric of the whole record a[0..n-1] (m/s^2, fs Hz); opts NULL
 * for the defaults. FB_EINVAL if fs is not finite or below
 * FB_RIDE_MIN_SAMPLE_RATE, the record is shorter than the running r.m.s.
 * window (tau fs samples) or than 3 samples, a sample is not finite, or
 * opts are invalid; FB_ENOMEM. */
int fb_ride_metrics_compute(const double *a, size_t n, double fs, const fb_ride_opts *opts,
                            fb_ride_metrics *m, fb_err *err);

/* As fb_ride_metrics_compute over the samples of a[0..n-1] whose times
 * k / fs lie in [t0, t1) (s from the first sample, 0 <= t0 < t1 <=
 * n / fs). The filters (Wk, absorbed power, NRMM, spine) run from
 * a[0], so the window sees their settled state; the jerk at the window's
 * edges uses the neighbouring samples outside it when the record has them
 * (one-sided differences at the record's first and last sample). The
 * window must hold at least tau fs and 3 samples. */
int fb_ride_metrics_window(const double *a, size_t n, double fs, double t0, double t1,
                           const fb_ride_opts *opts, fb_ride_metrics *m, fb_err *err);

/* fb_ride_metrics_window on the output column named column of r, over
 * result times [t0, t1) (absolute, as in column 0). The sample rate is
 * taken from column 0, which must be uniform (every step within 1e-6
 * relative of the mean step). FB_EINVAL naming the column if it is
 * missing, or the first irregular step; FB_ENOMEM. */
int fb_ride_metrics_result(const fb_result *r, const char *column, double t0, double t1,
                           const fb_ride_opts *opts, fb_ride_metrics *m, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
