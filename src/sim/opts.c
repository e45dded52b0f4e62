/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulation options and the output sample grid (see flexbond/sim.h). */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/sim.h"

#include "sim/sim_internal.h"

/* Most output samples a run may ask for (memory guard: 1e8 rows). */
#define MAX_SAMPLES 1e8

/* "No list index" for opt_fail. */
#define NO_INDEX ((size_t)-1)

/* FB_EINVAL with the message and, as err->key, the name of the setting
 * (its field name in fb_sim_opts, "breakpoints[2]" with an index): this
 * module knows no file's key, the caller says where the setting came from
 * (a model's "simulation.rtol", a command-line option). */
static int opt_fail(fb_err *err, const char *key, size_t index, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static int opt_fail(fb_err *err, const char *key, size_t index, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  fb_err_vset(err, FB_EINVAL, fmt, ap);
  va_end(ap);
  if (index == NO_INDEX)
    fb_err_set_key(err, "%s", key);
  else
    fb_err_set_key(err, "%s[%zu]", key, index);
  return FB_EINVAL;
}

/* Relative slack for "(t_end - t_start) * rate is an integer". */
#define GRID_INTEGER_TOL 1e-9

void fb_sim_opts_default(fb_sim_opts *opts)
{
  opts->t_start = 0;
  opts->t_end = 1;
  opts->rtol = 1e-6;
  opts->atol = 1e-9;
  opts->max_step = 0;
  opts->sample_rate = 1000;
  opts->max_order = 5;
  opts->max_steps = FB_SIM_DEFAULT_MAX_STEPS;
  opts->stability_limit_detection = 1;
  opts->breakpoints = NULL;
  opts->nbreakpoints = 0;
  opts->x0 = NULL;
  opts->progress = NULL;
  opts->progress_ctx = NULL;
  opts->noutputs = 0;
}

double fb_sim_same_time_tol(double a, double b)
{
  return 100 * DBL_EPSILON * fmax(fabs(a), fabs(b));
}

/* The shortest run CVODE 6.4 can start: its first CVode call refuses
 * - t_end - t_start < 2 uround max(|t_start|, |t_end|): cvHin returns
 *   CV_TOO_CLOSE (src/cvode/cvode.c; t_start = 1 s, t_end = 1 s + 2 eps
 *   fails, + 3 eps runs). We ask for fb_sim_same_time_tol, the distance
 *   at which the integration treats two times as one;
 * - (tstop - t) (tout - t) <= 0, its test that the stop time lies ahead,
 *   which for the first segment is (t_end - t_start)^2: it underflows to
 *   0 below about 1.6e-162 s and CVODE says "tstop ... is behind current
 *   t" (CV_ILL_INPUT; 1e-160 s runs, 1e-162 s fails). sqrt(DBL_MIN), where
 *   the square stops being a normal double, keeps clear of it.
 * A run shorter than one sample interval is allowed: it has one sample,
 * at t_start. */
static double shortest_run(double t_start, double t_end)
{
  return fmax(sqrt(DBL_MIN), fb_sim_same_time_tol(t_start, t_end));
}

/* The shortest "%g" of v that reads back as v, so that two times a
 * roundoff apart print differently. */
static void format_exact(double v, char *buf, size_t size)
{
  for (int digits = 6; digits <= 17; ++digits) {
    snprintf(buf, size, "%.*g", digits, v);
    if (strtod(buf, NULL) == v)
      return;
  }
}

/* The result's memory, estimated before anything is allocated: it is
 * allocated whole at the start (samples x columns doubles), so a rate
 * that cannot fit fails now, not gigabytes later. */
static int check_result_size(const fb_sim_opts *o, double nsamples, fb_err *err)
{
  const double columns = 1.0 + (double)(o->noutputs ? o->noutputs : 1);
  const double bytes = (nsamples + 1.0) * columns * (double)sizeof(double);
  if (bytes <= FB_SIM_MAX_RESULT_BYTES)
    return FB_OK;
  return opt_fail(err, "sample_rate", NO_INDEX,
                  "%g Hz over %g s gives %.3g samples of %.0f "
                  "columns, which would need about %.1f GB (samples x columns x 8 bytes), "
                  "more than the %.1f GB a run's result may take (docs/errors.md, "
                  "\"Limits\")",
                  o->sample_rate, o->t_end - o->t_start, nsamples + 1.0, columns, bytes / 1e9,
                  FB_SIM_MAX_RESULT_BYTES / 1e9);
}

static int check_times(const fb_sim_opts *o, fb_err *err)
{
  if (!isfinite(o->t_start))
    return opt_fail(err, "t_start", NO_INDEX, "must be finite, got %g", o->t_start);
  if (!isfinite(o->t_end) || !(o->t_end > o->t_start) || !isfinite(o->t_end - o->t_start))
    return opt_fail(err, "t_end", NO_INDEX,
                    "must be finite and greater than t_start = %g, got %g", o->t_start,
                    o->t_end);
  const double shortest = shortest_run(o->t_start, o->t_end);
  if (!(o->t_end - o->t_start >= shortest)) {
    char t0[32], t1[32];
    format_exact(o->t_start, t0, sizeof t0);
    format_exact(o->t_end, t1, sizeof t1);
    return opt_fail(err, "t_end", NO_INDEX,
                    "the run from t_start = %s s to t_end = %s s is too "
                    "short for the solver to take a step: t_end - t_start = %.3g s, it must "
                    "be at least %.3g s",
                    t0, t1, o->t_end - o->t_start, shortest);
  }
  if (!(o->sample_rate > 0) || !isfinite(o->sample_rate))
    return opt_fail(err, "sample_rate", NO_INDEX, "must be positive, got %g", o->sample_rate);
  const double nsamples = (o->t_end - o->t_start) * o->sample_rate;
  if (!(nsamples <= MAX_SAMPLES))
    return opt_fail(err, "sample_rate", NO_INDEX,
                    "%g Hz over %g s gives %.3g samples, more than "
                    "the limit of %.0e",
                    o->sample_rate, o->t_end - o->t_start, nsamples, MAX_SAMPLES);
  const int rc = check_result_size(o, nsamples, err);
  if (rc != FB_OK)
    return rc;
  if (o->nbreakpoints && !o->breakpoints)
    return opt_fail(err, "breakpoints", NO_INDEX, "NULL with %zu entries", o->nbreakpoints);
  for (size_t i = 0; i < o->nbreakpoints; ++i)
    if (!isfinite(o->breakpoints[i]))
      return opt_fail(err, "breakpoints", i, "must be finite, got %g", o->breakpoints[i]);
  return FB_OK;
}

/* CVODE never steps further than max_step, so a run takes at least
 * (t_end - t_start) / max_step steps; above max_steps it is certain to
 * stop with CV_TOO_MUCH_WORK, after all those steps (minutes to hours):
 * refused now instead. */
static int check_step_budget(const fb_sim_opts *o, fb_err *err)
{
  if (!(o->max_step > 0))
    return FB_OK;
  const double span = o->t_end - o->t_start;
  const double fewest = ceil(span / o->max_step);
  if (!(fewest > (double)o->max_steps))
    return FB_OK;
  return opt_fail(err, "max_step", NO_INDEX,
                  "%g s over the run's %g s (t_end - t_start) needs at "
                  "least %.3g steps, more than max_steps = %ld: the run could not "
                  "finish; raise max_step or max_steps",
                  o->max_step, span, fewest, o->max_steps);
}

static int check_solver(const fb_sim_opts *o, fb_err *err)
{
  if (!(o->rtol > 0 && o->rtol < 1))
    return opt_fail(err, "rtol", NO_INDEX, "must be in (0, 1), got %g", o->rtol);
  if (!(o->atol > 0) || !isfinite(o->atol))
    return opt_fail(err, "atol", NO_INDEX, "must be positive, got %g", o->atol);
  if (o->max_order < 1 || o->max_order > 5)
    return opt_fail(err, "max_order", NO_INDEX, "must be 1..5, got %d", o->max_order);
  if (!(o->max_step >= 0) || !isfinite(o->max_step))
    return opt_fail(err, "max_step", NO_INDEX, "must be finite and >= 0 (0: no limit), got %g",
                    o->max_step);
  if (o->max_steps < 1 || o->max_steps > FB_SIM_MAX_STEPS)
    return opt_fail(err, "max_steps", NO_INDEX,
                    "must be in 1 .. %ld (about a day of solver steps "
                    "at 0.1 ms each; docs/errors.md, \"Limits\"), got %ld",
                    FB_SIM_MAX_STEPS, o->max_steps);
  return check_step_budget(o, err);
}

int fb_sim_opts_check(const fb_sim_opts *opts, fb_err *err)
{
  const int rc = check_times(opts, err);
  return rc != FB_OK ? rc : check_solver(opts, err);
}

void fb_sample_grid_init(fb_sample_grid *g, const fb_sim_opts *opts)
{
  g->t_start = opts->t_start;
  g->t_end = opts->t_end;
  g->rate = opts->sample_rate;
  /* Bounded by MAX_SAMPLES, so the conversions below are exact. */
  const double intervals = (opts->t_end - opts->t_start) * opts->sample_rate;
  const double nearest = floor(intervals + 0.5);
  g->last_is_end = fabs(intervals - nearest) <= GRID_INTEGER_TOL * intervals;
  g->n = (size_t)(g->last_is_end ? nearest : floor(intervals)) + 1;
}

/* k / rate rather than an accumulated sum, so no rounding error builds
 * up along the grid. The clamp only matters when t_start is so large
 * that the addition rounds past t_end. */
double fb_sample_grid_time(const fb_sample_grid *g, size_t k)
{
  if (g->last_is_end && k + 1 == g->n)
    return g->t_end;
  const double t = g->t_start + (double)k / g->rate;
  return t < g->t_end ? t : g->t_end;
}
