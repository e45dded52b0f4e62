/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: the study layer. What a run of a vehicle gives an engineer,
 * computed once in the library for every front end (the flexbond command's
 * summary.json, report.md and sweep.csv, the Python package): each
 * output's statistics over the response, each tire's contact, the ride
 * metrics of a mounted body, and System 2 against System 1.
 *
 * The response window of a scenario starts where the first wheel meets
 * the road's feature (the bump's leading edge; on a random road or a
 * profile, where its track starts) and ends where the last wheel leaves it
 * (the run's end on a random road or a profile): before it the vehicle
 * sits at its static state. */
#ifndef FLEXBOND_STUDY_H
#define FLEXBOND_STUDY_H

#include <stddef.h>

#include "flexbond/error.h"
#include "flexbond/ride.h"
#include "flexbond/road.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A tire reaction above this multiple of its static value is a spike:
 * the ride over a road moves a tire's load about its static value (the
 * paper's 10 cm bump at 10 km/h: peaks of 1.36 to 1.70 times it, System
 * 1); three times it is an impact, such as a wheel landing on the paper's
 * linear tire damper (20.7 times in examples/apc6x6_liftoff.yaml). */
#define FB_CONTACT_SPIKE_RATIO 3.0

/* [first wheel's entry, last wheel's exit] of s's road (s), into window. */
void fb_study_response_window(const fb_scenario *s, double window[2]);

/* The output the ride metrics are of: the first output whose signal is a
 * mounted body's acceleration ("acc"); s->noutputs when there is none. */
size_t fb_study_ride_output(const fb_scenario *s);

/* One output's statistics over a window [t0, t1] of a result. */
typedef struct fb_output_stats {
  double static_value;    /* the last sample before t0 (NaN when none) */
  double peak, peak_time; /* the largest value from t0 on, and its first time */
  double min, min_time;   /* the smallest value from t0 on, and its first time */
  double rms;             /* r.m.s. over [t0, t1] (NaN when no sample) */
} fb_output_stats;

/* Column col (1 .. columns - 1) of r over window: NaN samples never
 * become extremes. */
fb_output_stats fb_output_stats_of(const fb_result *r, size_t col, const double window[2]);

/* System 2 against System 1 for one output, from the window's start on.
 * Ratios are fractions, NaN when their denominator is 0. */
typedef struct fb_output_cmp {
  double max_diff;      /* largest |S2 - S1|, in the output's unit */
  double max_diff_time; /* its first time, s */
  double range1;        /* System 1's peak-to-peak range, peak - min */
  double rel_diff;      /* max_diff / range1 */
  double peak_change;   /* (peak2 - peak1) / |peak1| */
  double rms_change;    /* (rms2 - rms1) / rms1 */
} fb_output_cmp;

/* s1, s2: the output's statistics in the two runs; diff: run 2 minus run
 * 1 (fb_result_diff), col its column; window as the statistics'. */
fb_output_cmp fb_output_compare(const fb_output_stats *s1, const fb_output_stats *s2,
                                const fb_result *diff, size_t col, const double window[2]);

/* A run of a scenario summarised (fb_run_summary_new): built once, read
 * through the accessors below; opaque. */
typedef struct fb_run_summary fb_run_summary;

/* The summary of r, a run of s (fb_vehicle_run, fb_vehicle_simulate:
 * its outputs and each tire's contact_force_<CORNER>) over window (NULL:
 * fb_study_response_window's): every output's statistics, every tire's
 * reaction statistics and the contact-loss intervals
 * (fb_vehicle_contact_loss), and the ride metrics (ISO 2631-1 and jerk,
 * fb_ride_metrics_result with its default options) of
 * fb_study_ride_output from the window's start to the run's end. Missing
 * ride metrics are no failure: fb_run_summary_ride says why. *out is new
 * (fb_run_summary_free). FB_EINVAL when r lacks a column s names. */
int fb_run_summary_new(const fb_scenario *s, const fb_result *r, const double window[2],
                       fb_run_summary **out, fb_err *err);
void fb_run_summary_free(fb_run_summary **sum);

/* The window the summary is over, s. */
void fb_run_summary_window(const fb_run_summary *sum, double window[2]);
/* Output k's statistics (k < s->noutputs; NULL beyond), and its column
 * in the result. */
const fb_output_stats *fb_run_summary_output(const fb_run_summary *sum, size_t k);
size_t fb_run_summary_column(const fb_run_summary *sum, size_t k);
/* Tire c's normal reaction (c < s->ncorners; NULL beyond), its largest
 * over its static one (NaN without a static one), and 1 when that exceeds
 * FB_CONTACT_SPIKE_RATIO with a positive static reaction. */
const fb_output_stats *fb_run_summary_contact(const fb_run_summary *sum, size_t c);
double fb_run_summary_contact_ratio(const fb_run_summary *sum, size_t c);
int fb_run_summary_contact_spike(const fb_run_summary *sum, size_t c);
/* The contact-loss intervals of the whole run, by corner, then by time
 * (fb_vehicle_contact_loss); NULL beyond. */
size_t fb_run_summary_nlosses(const fb_run_summary *sum);
const fb_contact_loss *fb_run_summary_loss(const fb_run_summary *sum, size_t i);
/* The ride metrics (1) and their window [t0, t1], or 0 and *note saying
 * why there are none (no mounted body's acceleration among the outputs,
 * a window shorter than the metrics need). Any argument but sum may be
 * NULL. */
int fb_run_summary_ride(const fb_run_summary *sum, fb_ride_metrics *m, double window[2],
                        const char **note);

/* The two systems' runs r1 and r2 of s compared, with their summaries:
 * every output's fb_output_cmp into cmp (s->noutputs of them) and, when
 * diff is not NULL, run 2 minus run 1 into *diff (new; fb_result_free).
 * FB_EINVAL when the runs' sample times differ. */
int fb_study_compare(const fb_scenario *s, const fb_result *r1, const fb_result *r2,
                     const fb_run_summary *sum1, const fb_run_summary *sum2, fb_output_cmp *cmp,
                     fb_result **diff, fb_err *err);

/* ---- The frequency response of a vehicle (src/study/freq.c,
 * docs/frequency-response.md): each output's complex amplitude per metre
 * of road height on one track, 1 m at the leading wheel, which the
 * track's other wheels meet later by their distance behind it at the
 * scenario's speed (fb_vehicle_freq_response). */

/* The most frequencies a study takes: 100 000, 32 MB of responses (two
 * tracks, 16 bytes each) for a vehicle of ten outputs. */
#define FB_STUDY_FREQ_MAX_POINTS ((size_t)100000)

/* n >= 1 frequencies from f_min to f_max (Hz, 0 < f_min <= f_max) evenly
 * spaced on a log scale into freq_hz, the ends exactly f_min and f_max. */
void fb_study_freq_log_grid(double f_min, double f_max, size_t n, double *freq_hz);

/* The response of a realised vehicle (fb_study_freq_new): its linear
 * model and the response at the frequencies asked; opaque. */
typedef struct fb_study_freq fb_study_freq;

/* The linear model of v (fb_vehicle_linearise: exact, or linearised at
 * its static equilibrium when a law is nonlinear) and its response at
 * freq_hz[0 .. nfreq) (Hz, >= 0, at most FB_STUDY_FREQ_MAX_POINTS; copied).
 * nfreq 0 keeps the linear model alone, for fb_study_ride_psd_new. v is
 * borrowed for the call; the study keeps a pointer to v's scenario
 * (fb_vehicle_scenario), which must outlive it. *out is new
 * (fb_study_freq_free). */
int fb_study_freq_new(fb_vehicle *v, const double *freq_hz, size_t nfreq, fb_study_freq **out,
                      fb_err *err);
void fb_study_freq_free(fb_study_freq **f);

/* The scenario, the frequencies (Hz; owned by f) and whether the model is
 * a linearisation (1) or exact (0). */
const fb_scenario *fb_study_freq_scenario(const fb_study_freq *f);
size_t fb_study_freq_nfreq(const fb_study_freq *f);
const double *fb_study_freq_hz(const fb_study_freq *f);
int fb_study_freq_linearised(const fb_study_freq *f);
/* 1 when output o (< s->noutputs) has a response: a power output, the
 * product of two signals, has none. */
int fb_study_freq_has_output(const fb_study_freq *f, size_t o);
/* Output o's complex amplitude (re, im; its unit per metre) on track
 * (FB_ROAD_LEFT, FB_ROAD_RIGHT) at frequency k, owned by f; NULL for a
 * power output or an index out of range. */
const double *fb_study_freq_at(const fb_study_freq *f, size_t o, int track, size_t k);
/* Output o's largest |H| over the frequencies and both tracks, where
 * (*k, *track; either may be NULL); NAN for a power output. */
double fb_study_freq_peak(const fb_study_freq *f, size_t o, size_t *k, int *track);

/* ---- The ride from a road spectrum (src/study/ride_psd.c,
 * docs/frequency-response.md "Ride from a road spectrum"): on an ISO 8608
 * road each output's PSD, S_y(f) = the tracks' H S_road H* combined by
 * fb_ride_two_track_psd, its r.m.s. over the road's band, and the
 * driver's ISO 2631-1 weighted r.m.s. a_w from the Wk-weighted PSD of
 * fb_study_ride_output, without a time run. */

/* Frequencies over the road's band, evenly spaced on a log scale: enough
 * that the trapezoidal rule in log f resolves the narrowest resonance
 * (the wheel hop, damping ratio 0.2 or more: a width of 40 % of its
 * frequency) with some 30 points. */
enum { FB_STUDY_RIDE_PSD_POINTS = 600 };

/* The ISO 8608 road of a ride: the class road_class ('A' .. 'H', either
 * case) with ISO 8608's band (fb_road_iso8608_defaults) or, road_class 0,
 * s's own road when it is a stationary random one (its type's random op,
 * fb_scenario_road_random). 1 and *iso set when there is such a road, else
 * 0. */
int fb_study_ride_psd_iso8608(const fb_scenario *s, char road_class,
                              fb_road_iso8608_params *iso);

/* The road a ride was computed on. */
typedef struct fb_study_psd_road {
  char road_class;     /* 'A' .. 'H' */
  double gd0;          /* m^3, Gd at 0.1 cycles/m (fb_road_iso8608_gd0) */
  double n_min, n_max; /* the band, cycles/m */
  double speed;        /* m/s */
  int identical;       /* 1: both tracks one profile; 0: independent */
} fb_study_psd_road;

/* The ride from a road spectrum (fb_study_ride_psd_new); opaque. */
typedef struct fb_study_ride_psd fb_study_ride_psd;

/* The ride of the vehicle whose linear model lin holds (fb_study_freq_new,
 * any frequencies; borrowed for the call) on the road iso (its class and
 * band; borrowed), its tracks identical (1) or independent (0, as
 * fb_road_new_iso8608 makes them): the response at
 * FB_STUDY_RIDE_PSD_POINTS frequencies from speed n_min to speed n_max,
 * each output's PSD and r.m.s., and a_w. Keeps a pointer to lin's
 * scenario, which must outlive it. *out is new (fb_study_ride_psd_free).
 * FB_EINVAL for a class outside A .. H or a band that is not
 * 0 < n_min < n_max. */
int fb_study_ride_psd_new(const fb_study_freq *lin, const fb_road_iso8608_params *iso,
                          int identical, fb_study_ride_psd **out, fb_err *err);
void fb_study_ride_psd_free(fb_study_ride_psd **r);

/* The road (owned by r), whether the model is a linearisation, and the
 * band's frequencies (Hz; owned by r) with the road's temporal PSD there
 * (m^2/Hz per track, fb_ride_road_psd). */
const fb_study_psd_road *fb_study_ride_psd_road(const fb_study_ride_psd *r);
int fb_study_ride_psd_linearised(const fb_study_ride_psd *r);
size_t fb_study_ride_psd_nfreq(const fb_study_ride_psd *r);
const double *fb_study_ride_psd_hz(const fb_study_ride_psd *r);
const double *fb_study_ride_psd_road_psd(const fb_study_ride_psd *r);
/* Output o's PSD at the band's frequencies (its unit^2/Hz; owned by r),
 * NULL for a power output or o out of range; its r.m.s. over the band,
 * NAN then. */
const double *fb_study_ride_psd_output(const fb_study_ride_psd *r, size_t o);
double fb_study_ride_psd_rms(const fb_study_ride_psd *r, size_t o);
/* The output a_w is of (fb_study_ride_output; s->noutputs when none),
 * its Wk-weighted PSD ((m/s^2)^2/Hz; owned by r; NULL when none) and a_w,
 * its r.m.s. (m/s^2; NAN when none). */
size_t fb_study_ride_psd_a_w_output(const fb_study_ride_psd *r);
const double *fb_study_ride_psd_weighted(const fb_study_ride_psd *r);
double fb_study_ride_psd_a_w(const fb_study_ride_psd *r);

#ifdef __cplusplus
}
#endif
#endif
