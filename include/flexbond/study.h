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

/* ---- Parameter sweeps (src/study/sweep.c, docs/sweep.md): a scenario
 * run once per combination of values of some of its keys (the cases: the
 * cartesian product of the axes, the first axis varying slowest), each
 * case reduced to the same metrics: every output's peak, min and r.m.s.
 * over the response window (fb_run_summary_new), the smallest tire
 * reaction, the contact-loss intervals, the ride metrics and the solver's
 * steps. Built once (fb_study_sweep_new), run on threads
 * (fb_study_sweep_run) or case by case (fb_study_sweep_run_case, for a
 * front end that hands the cases to other processes), and read case by
 * case (fb_study_sweep_case_get). The study layer reads no file: the
 * front end makes each case's scenario (fb_study_sweep_ops.load; the io
 * layer's fb_scenario_sweep_ops loads a file with the case's overrides). */

/* Most axes of a sweep, and most cases: a case holds its metrics (some
 * 200 doubles for 64 outputs), so 100000 cases are some 160 MB at most,
 * and a System 1 case takes 15-25 ms on one core, 100000 of them about
 * 40 core-minutes. */
enum { FB_STUDY_SWEEP_MAX_AXES = 16 };
#define FB_STUDY_SWEEP_MAX_CASES ((size_t)100000)

/* The metrics of a case, in this order: output k's statistics at
 * FB_STUDY_SWEEP_NSTATS k + FB_STUDY_SWEEP_{PEAK,MIN,RMS}, then the other
 * metrics at fb_study_sweep_metric_other. */
enum { FB_STUDY_SWEEP_PEAK, FB_STUDY_SWEEP_MIN, FB_STUDY_SWEEP_RMS, FB_STUDY_SWEEP_NSTATS };
enum {
  FB_STUDY_SWEEP_MIN_TIRE_FORCE, /* N: any tire's smallest reaction from the window on */
  FB_STUDY_SWEEP_CONTACT_LOSS_INTERVALS, /* those ending after the window's start */
  /* fb_run_summary_ride's metrics (NaN without a mounted body's
   * acceleration among the outputs: a missing metric, not a failure) */
  FB_STUDY_SWEEP_RIDE_A_W_RMS,
  FB_STUDY_SWEEP_RIDE_MTVV,
  FB_STUDY_SWEEP_RIDE_VDV,
  FB_STUDY_SWEEP_RIDE_CREST_FACTOR,
  FB_STUDY_SWEEP_RIDE_JERK_PEAK,
  FB_STUDY_SWEEP_RIDE_JERK_RMS,
  FB_STUDY_SWEEP_RIDE_ABSORBED_POWER,
  FB_STUDY_SWEEP_RIDE_NRMM_PEAK,
  FB_STUDY_SWEEP_RIDE_SE,
  FB_STUDY_SWEEP_RIDE_DZ,
  FB_STUDY_SWEEP_RIDE_VDV_RATIO,
  FB_STUDY_SWEEP_RIDE_CREST_OVER_9,
  FB_STUDY_SWEEP_SOLVER_STEPS,
  FB_STUDY_SWEEP_NOTHER
};

/* One swept key and its values, as text the scenario's reader takes
 * (fb_scenario_override). Borrowed by fb_study_sweep_new, which copies. */
typedef struct fb_study_sweep_axis {
  const char *key;
  const char *const *values;
  size_t nvalues;
} fb_study_sweep_axis;

/* What the front end does for a sweep; every function may be called from
 * several threads at once, each for its own case. Initialise by member
 * names: members may be added. */
typedef struct fb_study_sweep_ops {
  /* Makes case i's scenario: the base one with ov[0 .. n) (the case's
   * values, one per axis) in place of its values, checked as a loaded
   * one. *out is new (the sweep frees it). An error about a value of ov
   * has fb_err.source FB_SOURCE_OVERRIDE. Required. */
  int (*load)(void *ctx, size_t i, const fb_scenario_override *ov, size_t n, fb_scenario **out,
              fb_err *err);
  /* Locates an error found in s after it was made (a failed simulation:
   * fb_scenario_locate for a loaded one); NULL: errors stay as they are. */
  int (*locate)(void *ctx, const fb_scenario *s, fb_err *err);
  /* Polled before a case starts and at every solver step: nonzero stops
   * the sweep (a case stopped so is FB_EINTR, and not done). NULL: never
   * (fb_study_sweep_cancel still stops it). */
  int (*stop)(void *ctx);
  /* Case i has finished (fb_study_sweep_finish: run here or recorded),
   * called under the sweep's lock, one case at a time: a journal, a
   * progress line. Not FB_OK stops the sweep: fb_study_sweep_run returns
   * it with its err. NULL: nothing. */
  int (*finished)(void *ctx, size_t i, fb_err *err);
  void *ctx;
  /* Case i has run (scenario s, result r), on its own thread, before its
   * outcome is recorded: a front end's own measure of it (the ride-limit
   * search's metric). Not FB_OK fails the case with err. NULL: nothing.
   * (Last: a binding that mirrors the struct keeps its members' places.) */
  int (*measure)(void *ctx, size_t i, const fb_scenario *s, const fb_result *r, fb_err *err);
} fb_study_sweep_ops;

/* A sweep (fb_study_sweep_new); opaque. */
typedef struct fb_study_sweep fb_study_sweep;

/* The sweep of base (the scenario without overrides, whose outputs name
 * the metrics and every case must have: borrowed, it must outlive the
 * sweep) over axes[0 .. naxes) (1 .. FB_STUDY_SWEEP_MAX_AXES, each with
 * at least one value; copied), simulating system sys, its cases made and
 * reported by ops (copied; ops->ctx must outlive the sweep). No case runs
 * yet. *out is new (fb_study_sweep_free). FB_EINVAL for no axis, too
 * many, an axis without a value or more than FB_STUDY_SWEEP_MAX_CASES
 * cases, or no ops->load; FB_ENOMEM. */
int fb_study_sweep_new(const fb_scenario *base, fb_system sys, const fb_study_sweep_axis *axes,
                       size_t naxes, const fb_study_sweep_ops *ops, fb_study_sweep **out,
                       fb_err *err);
void fb_study_sweep_free(fb_study_sweep **sw);

/* The cases, axes and metrics per case. */
size_t fb_study_sweep_ncases(const fb_study_sweep *sw);
size_t fb_study_sweep_naxes(const fb_study_sweep *sw);
size_t fb_study_sweep_nmetrics(const fb_study_sweep *sw);
/* Axis k's key and its value v (owned by sw; NULL out of range). */
const char *fb_study_sweep_axis_key(const fb_study_sweep *sw, size_t k);
size_t fb_study_sweep_axis_nvalues(const fb_study_sweep *sw, size_t k);
const char *fb_study_sweep_axis_value(const fb_study_sweep *sw, size_t k, size_t v);
/* The index of axis k's value in case i (the first axis varies slowest),
 * and that value (owned by sw). */
size_t fb_study_sweep_value_index(const fb_study_sweep *sw, size_t i, size_t k);
const char *fb_study_sweep_case_value(const fb_study_sweep *sw, size_t i, size_t k);
/* Case i's overrides, one per axis, into ov[0 .. naxes) (pointing into
 * sw; label NULL). */
void fb_study_sweep_case_overrides(const fb_study_sweep *sw, size_t i,
                                   fb_scenario_override *ov);

/* The index of the other metric m (FB_STUDY_SWEEP_MIN_TIRE_FORCE ...). */
size_t fb_study_sweep_metric_other(const fb_study_sweep *sw, size_t m);
/* Metric m's name ("tire_force_LF_peak", "min_tire_force") into buf, and
 * its unit ("N"; "-" for a count or a ratio; static or owned by base). */
void fb_study_sweep_metric_name(const fb_study_sweep *sw, size_t m, char *buf, size_t size);
const char *fb_study_sweep_metric_unit(const fb_study_sweep *sw, size_t m);

/* The outcome of a case. */
typedef struct fb_study_sweep_case {
  int status;           /* FB_OK, or what failed */
  int at_value;         /* 1: the error is about one of the case's own values */
  const char *error;    /* its message; NULL when ok (or when out of memory) */
  const double *metric; /* nmetrics; NaN when failed or not defined */
  double wall_seconds;  /* of its simulation; NaN when not known */
  int worker;           /* who ran it, as the front end numbers them (0 here) */
} fb_study_sweep_case;

/* Case i's outcome (i < ncases) into *out (its pointers owned by sw, valid until the
 * case is recorded again or sw freed); 1 if it is done, 0 if it is not
 * (*out then holds NaN metrics and status FB_EINTR). */
int fb_study_sweep_case_get(const fb_study_sweep *sw, size_t i, fb_study_sweep_case *out);
int fb_study_sweep_case_done(const fb_study_sweep *sw, size_t i);

/* Runs case i now on this thread (its scenario made by ops->load,
 * simulated, measured) and records its outcome, without ops->finished
 * (fb_study_sweep_finish); its status. A case's failure is its outcome,
 * not an error of the sweep. Two threads may run two cases at once. */
int fb_study_sweep_run_case(fb_study_sweep *sw, size_t i);
/* Records case i's outcome c computed elsewhere (another process, a
 * journal read back; c and what it points to copied): done, unless its
 * status is FB_EINTR (a stopped case is run again). No ops->finished. */
void fb_study_sweep_record(fb_study_sweep *sw, size_t i, const fb_study_sweep_case *c);
/* Takes the next case not done and not taken, in grid order, into *i: 1,
 * or 0 when none is left or the sweep was stopped. Thread-safe: each case
 * is taken once. */
int fb_study_sweep_next(fb_study_sweep *sw, size_t *i);
/* Case i has finished: calls ops->finished when it is done (a case
 * stopped is not); its status, which stops the sweep when not FB_OK. */
int fb_study_sweep_finish(fb_study_sweep *sw, size_t i);
/* Runs every case not done on min(threads, cases left) threads (this one
 * among them), each taking the next case as it finishes one. FB_OK when
 * none is left to run; else what stopped it: ops->finished's failure
 * (its err), or FB_EINTR (stopped, or cancelled). Cases may run on
 * another thread meanwhile (fb_study_sweep_next, _run_case, _finish). */
int fb_study_sweep_run(fb_study_sweep *sw, size_t threads, fb_err *err);
/* Stops the sweep: no case starts any more, and those running stop at
 * their next solver step. Thread-safe, from any thread. */
void fb_study_sweep_cancel(fb_study_sweep *sw);

/* ---- Ride-limiting speeds (src/study/ride_limit.c, docs/ride-limit.md):
 * for each curve (a value of a scenario's key, on one system) the highest
 * speed below which a metric of a run stays under its limit, found by a
 * bracketing search over speed. The search asks its caller to evaluate
 * the metric at batches of (curve, speed) points, a round at a time, so
 * that a front end runs a round's cases at once (on the sweep's threads).
 * It is deterministic: the same metrics give the same rounds of points. */

/* How a curve's search ended. */
typedef enum fb_ride_limit_status {
  FB_RIDE_LIMIT_FOUND, /* the limit is reached inside (v_lo, v_hi] */
  FB_RIDE_LIMIT_BELOW, /* already reached at v_lo */
  FB_RIDE_LIMIT_ABOVE, /* not reached at any speed of the coarse grid */
  FB_RIDE_LIMIT_FAILED /* an evaluation gave no metric (a failed run, NaN) */
} fb_ride_limit_status;

/* Settings of a search; fb_study_ride_limit_opts_default fills them. */
typedef struct fb_study_ride_limit_opts {
  double limit;         /* the metric's limit, in its unit (required: no default) */
  double v_lo, v_hi;    /* m/s, 0 < v_lo < v_hi (default 5 and 80 km/h) */
  double coarse_step;   /* m/s between the coarse grid's speeds (default 5 km/h) */
  double tol;           /* m/s, > 0: the final bracket's width (default 0.1 km/h) */
  size_t refine_points; /* speeds per curve and refining round, >= 1 (default 1:
                           bisection; k points shrink the bracket k + 1 times) */
} fb_study_ride_limit_opts;

void fb_study_ride_limit_opts_default(fb_study_ride_limit_opts *o);

/* A point to evaluate: curve's metric at speed (m/s). */
typedef struct fb_study_ride_limit_point {
  size_t curve;
  double speed;
} fb_study_ride_limit_point;

/* Evaluates the metric at pts[0 .. n) into metric[0 .. n): NaN for a
 * point whose run failed (its curve fails, the others go on). Not FB_OK
 * stops the search (an interruption: FB_EINTR) with err. */
typedef int (*fb_study_ride_limit_eval_fn)(void *ctx, const fb_study_ride_limit_point *pts,
                                           size_t n, double *metric, fb_err *err);

/* A curve's outcome. */
typedef struct fb_study_ride_limit_curve {
  fb_ride_limit_status status;
  /* FOUND: the bracket's ends: the highest speed evaluated with the
   * metric below the limit (speed, metric) and the lowest above it
   * (speed_over, metric_over), speed_over - speed <= tol. BELOW: v_lo and
   * its metric in speed_over, metric_over (speed NaN); ABOVE: v_hi and its
   * metric in speed, metric (speed_over NaN). FAILED: NaN, and the point
   * in failed_speed. */
  double speed, metric, speed_over, metric_over, failed_speed;
  size_t nruns; /* evaluations of the curve */
} fb_study_ride_limit_curve;

/* Searches ncurves curves (each starting with the coarse grid v_lo, v_lo +
 * coarse_step, ..., v_hi (the last step shortened to end at v_hi), all in
 * round 1; then each curve whose grid brackets the limit takes
 * refine_points evenly spaced speeds inside its bracket per round until
 * the bracket is at most tol wide) into out[0 .. ncurves). The limit is
 * reached where the metric is >= limit; the bracket is that of the first
 * such speed evaluated (a curve whose metric dips below the limit again
 * keeps its lowest crossing, as far as the grid sees it). *nrounds (may be
 * NULL): the rounds. FB_EINVAL for bad opts; eval's failure. */
int fb_study_ride_limit(size_t ncurves, const fb_study_ride_limit_opts *opts,
                        fb_study_ride_limit_eval_fn eval, void *ctx,
                        fb_study_ride_limit_curve *out, size_t *nrounds, fb_err *err);

/* The metrics a search can take, by name (a table: adding one is a line
 * of it): fb_ride_metrics' fields of a run's output and the largest
 * |value| of the output itself, over [first wheel's entry, end of run]. */
size_t fb_study_ride_limit_nmetrics(void);
/* Metric m's name, unit and standard limit (NaN when none is standard);
 * NULL names beyond the table. */
const char *fb_study_ride_limit_metric_name(size_t m);
const char *fb_study_ride_limit_metric_unit(size_t m);
double fb_study_ride_limit_metric_limit(size_t m);
/* 1 if metric m is a ride metric of a seat's vertical acceleration (its
 * output must be one, in m/s^2), 0 if it is of the output itself. */
int fb_study_ride_limit_metric_of_acceleration(size_t m);
/* The index of the metric named name: 0 and *m set, or -1. */
int fb_study_ride_limit_metric_find(const char *name, size_t *m);

/* The run's end for a ride-limit case at s's speed into s->t_end: on a
 * road with an end (a bump, an obstacle) settle seconds after the last
 * wheel leaves it; on one that goes on (a random road, a profile) when the
 * last wheel has run course_length metres past the start of its track.
 * s->t_end must be beyond the feature on entry (a road that goes on ends
 * at it). FB_EINVAL for a non-positive course_length or negative settle. */
int fb_study_ride_limit_duration(fb_scenario *s, double course_length, double settle,
                                 fb_err *err);

/* Metric m of output k (< s->noutputs) of run r of s over [the first
 * wheel's entry (0 if earlier), the run's end] into *value. NaN when the
 * window is too short for it (ride metrics need 1 s) or it is not defined
 * (absorbed power without a K(f) table): not a failure. FB_EINVAL for a
 * bad m or k, or a column r lacks. */
int fb_study_ride_limit_measure(const fb_scenario *s, const fb_result *r, size_t k, size_t m,
                                double *value, fb_err *err);

/* ---- The data of a run's report (src/study/report.c): the runs of a
 * scenario with their summaries, System 2 against System 1 (and against
 * it again on a converged mesh), and the findings a report states about
 * them: which outputs differ notably, how far the hull twists, which
 * output grows the most, which tire is the most loaded or the least. The
 * library decides these; a front end only words and prints them
 * (flexbond run's report.md and summary.json, the Python package). */

/* A difference between the systems is notable above 5 % of System 1's
 * peak-to-peak range over the response, a peak or r.m.s. change above 5 %
 * of System 1's value: a few times the scatter of reading the paper's
 * plots, well above the solvers' error (rtol 1e-6). */
#define FB_STUDY_NOTABLE_DIFF 0.05
#define FB_STUDY_NOTABLE_CHANGE 0.05

/* An estimated error of System 2's modal basis (fb_study_run.basis_error)
 * above this fraction of an output's range is worth keeping more modes. */
#define FB_STUDY_BASIS_ERROR_NOTABLE 1e-3

/* The mesh error of the generated hull, as measured on the reference hull
 * (bench/hull_convergence.sh, docs/hull-mesh.md "Convergence"): at
 * density 1 its first ten elastic free-free frequencies are 12 % to 21 %
 * above the converged ones, and the error falls as 1 / density^2 (observed
 * orders 1.4 to 2.4; at densities 2 to 6 the measured errors lie within
 * these bounds over d^2, the lowest mode up to 0.6 of a point below). */
#define FB_STUDY_MESH_ERROR_LOW 0.12
#define FB_STUDY_MESH_ERROR_HIGH 0.21

/* The estimated band of that error at s's mesh density into band
 * (fractions of the converged frequencies) and 1; 0 when there is no
 * estimate: a deck, or no finite-element hull. */
int fb_study_mesh_error(const fb_scenario *s, double band[2]);

/* One run handed to a report; everything borrowed, outliving the report. */
typedef struct fb_study_run {
  fb_system sys;
  const fb_result *res;      /* fb_vehicle_run's */
  const fb_run_summary *sum; /* res's summary (fb_run_summary_new) */
  /* System 2 in a reduced modal basis: each output's estimated error from
   * the basis, over its range (s->noutputs); NULL when not estimated. */
  const double *basis_error;
} fb_study_run;

/* Which comparison with System 1: System 2's, or System 2's on the
 * converged mesh. */
typedef enum fb_study_cmp_kind {
  FB_STUDY_CMP_SYSTEM2,
  FB_STUDY_CMP_CONVERGED
} fb_study_cmp_kind;

/* The report's data (fb_study_report_new); opaque. */
typedef struct fb_study_report fb_study_report;

/* The report of runs[0 .. nruns) of s (one or two; System 1 first with
 * two) and, when not NULL, converged: System 2 again on a finer mesh of
 * the same scenario, compared with runs[0]. The runs' summaries must share
 * one window. With two runs, each output's comparison (fb_study_compare)
 * and System 2 minus System 1 are computed and owned by the report; the
 * runs and s are borrowed and must outlive it. *out is new
 * (fb_study_report_free). FB_EINVAL for no run, more than two, or a
 * converged run without two runs. */
int fb_study_report_new(const fb_scenario *s, const fb_study_run *runs, size_t nruns,
                        const fb_study_run *converged, fb_study_report **out, fb_err *err);
void fb_study_report_free(fb_study_report **rep);

const fb_scenario *fb_study_report_scenario(const fb_study_report *rep);
size_t fb_study_report_nruns(const fb_study_report *rep);
/* Run i (NULL beyond), and the converged run (NULL when none). */
const fb_study_run *fb_study_report_run(const fb_study_report *rep, size_t i);
const fb_study_run *fb_study_report_converged(const fb_study_report *rep);
/* The response window of the runs' summaries, s. */
void fb_study_report_window(const fb_study_report *rep, double window[2]);
/* When wheel c (< s->ncorners) meets the road's feature and leaves it, s. */
void fb_study_report_wheel_window(const fb_study_report *rep, size_t c, double window[2]);
/* The unit of output k (< s->noutputs), as System 1's result names it. */
const char *fb_study_report_unit(const fb_study_report *rep, size_t k);
/* How many of the scenario's corners have tire model m. */
size_t fb_study_report_tires_with(const fb_study_report *rep, const fb_tire_model *m);

/* Each output's comparison of kind (s->noutputs, owned by rep) and the
 * difference of the runs (System 2 minus System 1, with System 1's
 * columns; owned by rep); NULL when that comparison was not made. */
const fb_output_cmp *fb_study_report_cmp(const fb_study_report *rep, fb_study_cmp_kind kind);
const fb_result *fb_study_report_diff(const fb_study_report *rep, fb_study_cmp_kind kind);

/* Of a comparison's outputs: the one with the largest relative
 * difference (s->noutputs when none varies in System 1), how many vary in
 * System 1 and how many of those differ notably. */
typedef struct fb_study_differences {
  size_t largest, nvarying, nnotable;
} fb_study_differences;
fb_study_differences fb_study_report_differences(const fb_study_report *rep,
                                                 fb_study_cmp_kind kind);
/* 1 when output k varies in System 1 and differs notably in comparison kind. */
int fb_study_report_notable(const fb_study_report *rep, fb_study_cmp_kind kind, size_t k);
/* The output whose r.m.s. changes the most (by magnitude) from System 1
 * to System 2, s->noutputs when no change is finite or not compared. */
size_t fb_study_report_largest_rms_change(const fb_study_report *rep);
/* How many outputs are notable on one mesh and not on the other (0
 * without the converged run). */
size_t fb_study_report_mesh_crossings(const fb_study_report *rep);
/* Output k's largest |System 2 on the converged mesh - System 2| from the
 * window's start on, over System 1's range; NaN without the converged run
 * or when System 1 does not vary. */
double fb_study_report_mesh_diff(const fb_study_report *rep, size_t k);

/* The torsion angle among the outputs, s->noutputs when none. */
size_t fb_study_report_torsion_output(const fb_study_report *rep);
/* Output k's largest |value| over the whole run r (0 for an output that
 * is identically zero). */
double fb_study_run_max_abs(const fb_study_run *r, size_t k);
/* The largest estimated error of r's basis over its noutputs outputs and
 * which output has it (*k; may be NULL); NaN when not estimated. */
double fb_study_run_worst_basis_error(const fb_study_run *r, size_t noutputs, size_t *k);

/* With one run: the output whose peak over the response grows the most
 * relative to its static value, among those whose static value is at
 * least FB_STUDY_NOTABLE_DIFF of their range (a ratio to a value of ~0,
 * an acceleration at rest, says nothing) and that grow (factor above 1);
 * *factor its peak over its static value. s->noutputs when none. */
size_t fb_study_report_largest_growth(const fb_study_report *rep, double *factor);
/* Of run r's tires: the one whose peak reaction is the largest multiple
 * of its static one (*c_ratio), and the one with the smallest reaction
 * from the window's start on (*c_min). */
void fb_study_report_contact_extremes(const fb_study_report *rep, const fb_study_run *r,
                                      size_t *c_ratio, size_t *c_min);

#ifdef __cplusplus
}
#endif
#endif
