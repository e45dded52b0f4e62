/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: time integration of a block diagram with SUNDIALS CVODE
 * (variable-order BDF, orders 1-5, Newton iteration; Hindmarsh et al.,
 * ACM TOMS 31(3), 2005), the counterpart of MATLAB's ode15s.
 *
 * The Newton systems are solved sparsely through the diagram's augmented
 * linearisation (fb_bd_aug_*), factorised with KLU. Outputs are sampled at a
 * fixed rate by CVODE's interpolating polynomial (CVodeGetDky), so sampling
 * never shortens the steps. The integrator stops exactly at breakpoints
 * (input kinks) and restarts there. Switched laws (fb_law_ops) keep their
 * modes between events; CVODE's root-finding locates where their guards
 * cross zero, the laws choose their next modes there, and the integration
 * restarts from that point when a mode changed. */
#ifndef FLEXBOND_SIM_H
#define FLEXBOND_SIM_H

#include <stddef.h>

#include "flexbond/bd.h"
#include "flexbond/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Called by fb_sim_run after every internal step with the time reached
 * (e.g. to draw a progress bar); must not call back into the run. Returns
 * 0 to go on; anything else stops the run, which then fails with
 * FB_EINTR (an interrupted command, say). */
typedef int (*fb_sim_progress_fn)(void *ctx, double t, double t_end);

/* The default budget of internal steps of a whole run (fb_sim_opts). */
#define FB_SIM_DEFAULT_MAX_STEPS 10000000L
/* The most max_steps may allow: a step of System 1 with its outputs takes
 * about 0.1 ms, so 1e9 steps are a day of computing; more is no run that
 * finishes, and would hide a max_step that cannot be met. */
#define FB_SIM_MAX_STEPS 1000000000L

typedef struct fb_sim_opts {
  double t_start;     /* s */
  double t_end;       /* s, > t_start */
  double rtol;        /* relative tolerance (default 1e-6) */
  double atol;        /* absolute tolerance, all states (default 1e-9) */
  double max_step;    /* s, 0 for no limit */
  double sample_rate; /* Hz, outputs at t_start + k / sample_rate (default 1000) */
  int max_order;      /* BDF order limit 1..5 (default 5) */
  long max_steps;     /* internal steps allowed in all (FB_SIM_DEFAULT_MAX_STEPS) */
  /* 1: CVODE's BDF stability limit detection (default 1): the order is
   * lowered where a lightly damped stiff mode, not accuracy, limits the
   * step (Hindmarsh et al., ACM TOMS 31(3), 2005, sec. 3.3). */
  int stability_limit_detection;
  const double *breakpoints; /* extra breakpoints (borrowed), besides sources' */
  size_t nbreakpoints;
  const double *x0;            /* initial state (borrowed), NULL for the graph's */
  fb_sim_progress_fn progress; /* NULL for none */
  void *progress_ctx;
  /* Outputs the run records besides t, for fb_sim_opts_check's estimate of
   * the result's memory; 0 when not known yet (counted as 1). fb_sim_run
   * checks again with its diagram's own count. */
  size_t noutputs;
} fb_sim_opts;

/* Most bytes the sampled result of one run may take: 2 GiB (samples x
 * (1 + outputs) x 8 bytes; docs/errors.md, "Limits"). Written out as CSV
 * it would be some 6 GB of text, and `flexbond run` holds three such
 * tables at once (both systems and their difference). */
#define FB_SIM_MAX_RESULT_BYTES ((double)(1UL << 31))

/* Fills the defaults stated above (t_end = 1). */
void fb_sim_opts_default(fb_sim_opts *opts);
/* FB_EINVAL when opts is inconsistent, when t_end - t_start is too short
 * for CVODE to take a first step (below max(1.5e-154 s, 100 roundoffs of
 * |t_start|, |t_end|); src/sim/opts.c says why), when the run is certain
 * not to finish ((t_end - t_start) / max_step above max_steps) or when its
 * result would take more than FB_SIM_MAX_RESULT_BYTES ("... would need
 * about X GB ..."). The setting at fault is err->key, its field name
 * ("rtol", "max_step", "breakpoints[2]"); the message does not repeat it
 * ("must be in (0, 1), got 2"), since only the caller knows where the
 * setting came from (a file's "simulation.rtol", an option "--rtol") and
 * prefixes that. fb_sim_run's own errors about a setting set err->key
 * too ("x0[3]" for a state that is not finite, "max_steps" when the step
 * budget runs out). */
int fb_sim_opts_check(const fb_sim_opts *opts, fb_err *err);

typedef struct fb_sim_stats {
  long steps;          /* internal integrator steps */
  long rhs_evals;      /* right-hand-side evaluations */
  long newton_setups;  /* Newton matrix (P(gamma)) evaluations */
  long factorizations; /* numeric sparse LU factorisations */
  long newton_iters;   /* nonlinear iterations */
  long newton_conv_fails;
  long err_test_fails;
  long events; /* guard crossings that changed a mode (each a restart) */
  int last_order;
  double wall_seconds; /* wall time of fb_sim_run */
} fb_sim_stats;

/* Sampled outputs: row k holds t_k then every output of the diagram. */
typedef struct fb_result fb_result;

/* Integrates bd from opts->t_start to opts->t_end. On failure *out is NULL
 * and err says the time, the solver's flag name and a hint. A derivative,
 * Newton matrix entry or output that is not finite is recoverable while
 * CVODE can retry with a shorter step; if it gives up, or the initial
 * state's derivative is not finite, err names the state (or output) and
 * where the value starts (fb_bd_explain_nonfinite). */
int fb_sim_run(fb_bd *bd, const fb_sim_opts *opts, fb_result **out, fb_err *err);

/* ---- Stepping (co-simulation): advance, read, change, continue.
 *
 * A stepper is fb_sim_run cut at the caller's times, in the sense of an
 * FMI 2.0 co-simulation slave's fmi2DoStep (or Chrono's
 * DoStepDynamics): the caller advances it to a time, reads the
 * diagram's outputs there, may change what the diagram reads, and
 * advances again. fb_sim_run is a stepper advanced once to t_end, and a
 * run cut into N advances integrates the same way: CVODE takes its own
 * steps, past a caller's time when its step does, and gives the state
 * there from its interpolating polynomial (CV_NORMAL), as a run's
 * samples are; it lands exactly only on breakpoints and t_end. The
 * outputs agree with one run's within the tolerances (the interpolant
 * and the root search differ by rounding), not always to the bit. A
 * change restarts the integrator from the interpolated state.
 *
 * What a change means. The diagram reads its inputs through the graph's
 * time functions; a source whose function returns a value the caller
 * holds (fb_tfun_new_callback over the caller's variable) is an input
 * held constant between changes (zero-order hold). After changing such
 * a value (or anything else the diagram reads, such as a law's
 * parameter through its context) at the stepper's current time, call
 * fb_sim_stepper_reset: the integrator restarts there from the current
 * state (CVodeReInit: order 1, a fresh history, a new Newton matrix),
 * the switched laws choose their modes anew, and the sources'
 * breakpoints are collected again. A change of the diagram itself (a
 * parameter built into its blocks, such as a stiffness matrix) is a new
 * diagram: create a new stepper on it at t_start = the current time with
 * x0 = fb_sim_stepper_state (the states must mean the same: same count
 * and names), as a vehicle stepper does (flexbond/vehicle.h). */
typedef struct fb_sim_stepper fb_sim_stepper;

/* A stepper of bd at opts->t_start (bd borrowed: it must outlive the
 * stepper, and is evaluated by it, so no other simulation may use it
 * meanwhile). opts as fb_sim_run's, checked the same way; opts->t_end
 * is the horizon no advance may pass, and the breakpoints and x0 are
 * copied (not kept). opts->sample_rate plays no part: nothing is
 * recorded, so a long horizon costs no memory (fb_sim_run's bound on
 * its result does not apply). *out is new (fb_sim_stepper_free). Errors as fb_sim_run's
 * about the initial state. */
int fb_sim_stepper_create(fb_bd *bd, const fb_sim_opts *opts, fb_sim_stepper **out,
                          fb_err *err);
/* Integrates from the current time to t (s), the state at t from
 * CVODE's interpolant (no step is shortened for t; the integrator may
 * be past t after the call), stopping and restarting at every breakpoint
 * on the way; switched laws' events are handled as in fb_sim_run. At a
 * breakpoint t the state afterwards is its right limit. opts->progress
 * hears every step. FB_EINVAL (err->key "t") if t is before the current
 * time or after t_end; t within 100 roundoffs of the current time
 * (CVODE cannot take so short a step) does nothing.
 * On an integration failure (FB_ESOLVER as fb_sim_run's) the stepper
 * stays at the time of the failure and refuses to go on (FB_EINVAL);
 * after FB_EINTR (the progress function said stop) it may go on. */
int fb_sim_stepper_advance(fb_sim_stepper *st, double t, fb_err *err);
/* Restarts the integrator at the current time and state after a change
 * of what the diagram reads (above). FB_ESOLVER if the diagram's
 * derivative is not finite there. */
int fb_sim_stepper_reset(fb_sim_stepper *st, fb_err *err);
/* Puts the stepper at time t (s, in [opts->t_start, t_end], before the
 * current time too: a saved state restored) in state x
 * (fb_sim_stepper_nstates values, copied) and restarts the integrator
 * there as fb_sim_stepper_reset does, so two steppers set to the same
 * (t, x) go on identically. Clears an earlier integration failure.
 * FB_EINVAL (err->key "t", or the state's name) for t outside that
 * interval or a value of x that is not finite; then as
 * fb_sim_stepper_reset. */
int fb_sim_stepper_set_state(fb_sim_stepper *st, double t, const double *x, fb_err *err);
/* The time reached, s. */
double fb_sim_stepper_time(const fb_sim_stepper *st);
/* The state there: fb_sim_stepper_nstates values in fb_bd_state_name
 * order, owned by st and valid until its next advance, reset or free
 * (NULL for a diagram without states). */
size_t fb_sim_stepper_nstates(const fb_sim_stepper *st);
const double *fb_sim_stepper_state(const fb_sim_stepper *st);
/* The diagram's outputs at the current time and state into y
 * (fb_bd_noutputs values, fb_bd_output_name order, the units of
 * fb_bd_output_unit). FB_ESOLVER naming a non-finite output. */
int fb_sim_stepper_outputs(fb_sim_stepper *st, double *y, fb_err *err);
/* The solver's counters so far (wall_seconds 0). */
void fb_sim_stepper_stats(const fb_sim_stepper *st, fb_sim_stats *stats);
/* Frees *st and sets it to NULL; accepts NULL and *st == NULL. */
void fb_sim_stepper_free(fb_sim_stepper **st);

size_t fb_result_nsamples(const fb_result *r);
/* 1 + number of outputs (column 0 is time). */
size_t fb_result_ncols(const fb_result *r);
const char *fb_result_col_name(const fb_result *r, size_t j);
const char *fb_result_col_unit(const fb_result *r, size_t j);
/* Row k (ncols values). The rows are contiguous: fb_result_row(r, 0)
 * starts the whole nsamples x ncols table, row after row (what a
 * language binding copies in one go). */
const double *fb_result_row(const fb_result *r, size_t k);
/* Column index of a named output, or -1. */
long fb_result_find(const fb_result *r, const char *name);
const fb_sim_stats *fb_result_stats(const fb_result *r);
void fb_result_free(fb_result **r);
/* Keeps r's first ncols columns (time and the outputs before the rest),
 * in place: the dropped columns' names, units and values are freed.
 * FB_EINVAL if ncols is 0 or more than r has. */
int fb_result_truncate(fb_result *r, size_t ncols, fb_err *err);
/* The difference b - a of two results sampled at the same times (two
 * systems of one scenario, for a plot of their difference): column 0 is
 * the common time, column j >= 1 is b's column j minus a's, named and
 * with the units of a's; statistics zero. FB_EINVAL naming the first
 * mismatch if the column counts, column names or units, sample counts or
 * sample times (to 1e-9 s, or 1e-9 relative beyond 1 s) differ, or if
 * there are no columns; FB_ENOMEM. *out is new. */
int fb_result_diff(const fb_result *b, const fb_result *a, fb_result **out, fb_err *err);
/* For each column j >= 1 of a and b (results on one grid, with the same
 * columns: FB_EINVAL otherwise), the largest |b - a| over the samples at
 * t >= t0, over a's range there (its max - min; 0 when a is constant
 * there), into rel[j - 1]: how far b departs from a in a's own scale. */
int fb_result_rel_diff(const fb_result *a, const fb_result *b, double t0, double *rel,
                       fb_err *err);

/* Static equilibrium of a mechanical diagram under its inputs at time t,
 * reached from x0 by pseudo-transient continuation (implicit Euler steps
 * of growing length, src/sim/static.c): every momentum rate and
 * displacement rate zero, probe integrals unchanged. The equilibrium is
 * the one the damped dynamics settle to from x0: free rigid-body motions
 * no force drives stay put, and from x0 = 0 a statically indeterminate
 * support keeps zero self-stress (as the paper's settling from rest).
 * Sparse throughout (one factorisation of the Newton matrix per step);
 * undamped systems converge too (the momenta are cleared after each
 * step). FB_ESOLVER if it does not converge (a mass on no spring under a
 * force, or no equilibrium), or if flow sources move at time t. */
int fb_sim_static_state(fb_bd *bd, double t, const double *x0, double *x_eq, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
