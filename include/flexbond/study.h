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

#ifdef __cplusplus
}
#endif
#endif
