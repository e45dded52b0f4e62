/* SPDX-License-Identifier: BSD-3-Clause */
/* Stepping a simulation (fb_sim_stepper, flexbond/sim.h) of a
 * mass-spring(-damper) bond graph: cut into many advances it gives what
 * one fb_sim_run gives; an input held by the caller and changed on the
 * way, and a stiffness changed by a new diagram from the current state,
 * against the closed-form response of m x'' + r x' + k x = F from the
 * state at the change; the work of the held force against its closed
 * form; a failure stops the stepper. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"
#include "flexbond/sim.h"

#include "bgtest_util.h"
#include "check.h"

#define MASS 2.0    /* kg */
#define STIFF 800.0 /* N/m: omega_n = 20 rad/s */
#define DAMP 4.0    /* N s/m: zeta = 0.05 */
#define RTOL 1e-8

/* Outputs of the diagram, in probe order. */
enum { OUT_X, OUT_V, OUT_WORK, NOUT };

/* A force the test holds: the source's time function returns it. */
static double held_force(double t, void *ctx)
{
  (void)t;
  return *(const double *)ctx;
}

/* Se (force) -> 1-junction -> I (m), C (k), R (r, none when r = 0).
 * Probes: x (the spring's q), v (the flow into the mass), and the work
 * of the force, the integral of its power. *force is taken over. */
static int build(fb_tfun **force, double k, double r, fb_bg **bg, fb_bd **bd, fb_err *err)
{
  *bd = NULL;
  int rc = fb_bg_new("osc", bg, err);
  if (rc) {
    fb_tfun_free(force);
    return rc;
  }
  rc = add_forced_oscillator(*bg, force, MASS, k, err);
  if (!rc && r > 0)
    rc = add_scalar(*bg, "damper", FB_BG_R, r, err);
  if (!rc && r > 0)
    rc = fb_bg_connect(*bg, "br", "J", "damper", err);
  const fb_probe_spec probes[NOUT] = {{"x", FB_PROBE_STATE, "spring", 0, 0, 1.0, NULL, NULL, 0},
                                      {"v", FB_PROBE_FLOW, "bm", 0, 0, 1.0, NULL, NULL, 0},
                                      {"work", FB_PROBE_POWER, "bF", 0, 1, 1.0, NULL, NULL, 0}};
  if (!rc)
    rc = fb_bd_build(*bg, probes, NOUT, bd, err);
  return rc;
}

static void tight_opts(fb_sim_opts *o, double t_end)
{
  fb_sim_opts_default(o);
  o->t_end = t_end;
  o->rtol = RTOL;
  o->atol = 1e-12;
  o->sample_rate = 100;
}

/* x(t) of m x'' + r x' + k x = F from x(0) = x0, x'(0) = v0, underdamped
 * (Ogata, "Modern Control Engineering", 5th ed., sec. 5-3). */
static double response(double k, double r, double force, double x0, double v0, double tau)
{
  const double wn = sqrt(k / MASS), a = r / (2 * MASS), wd = sqrt(wn * wn - a * a);
  const double u0 = x0 - force / k; /* about the new equilibrium */
  return force / k + exp(-a * tau) * (u0 * cos(wd * tau) + (v0 + a * u0) / wd * sin(wd * tau));
}

/* An oscillator's graph and diagram, and a stepper over it. */
typedef struct oscillator {
  fb_bg *bg;
  fb_bd *bd;
  fb_sim_stepper *st;
} oscillator;

/* The oscillator of stiffness k and damping r driven by *force (taken
 * over), with a stepper from its rest at t = 0 to t_end (the tight
 * options); 1 when every part is made, else 0 and a failed check. */
static int oscillator_start(oscillator *o, fb_tfun **force, double k, double r, double t_end)
{
  fb_err err;
  fb_sim_opts opts;
  tight_opts(&opts, t_end);
  MUST(build(force, k, r, &o->bg, &o->bd, &err), &err);
  if (o->bd)
    MUST(fb_sim_stepper_create(o->bd, &opts, &o->st, &err), &err);
  return o->st != NULL;
}

/* The same driven by a force the test holds in *force. */
static int oscillator_held(oscillator *o, double *force, double k, double r, double t_end)
{
  fb_err err;
  fb_tfun *f = NULL;
  MUST(fb_tfun_new_callback(held_force, force, 0, NULL, &f, &err), &err);
  return f && oscillator_start(o, &f, k, r, t_end);
}

static void oscillator_free(oscillator *o)
{
  fb_sim_stepper_free(&o->st);
  fb_bd_free(&o->bd);
  fb_bg_free(&o->bg);
}

/* A step of 10 N at 0.25 s (a breakpoint) on the damped oscillator: 200
 * advances to the sample times against one fb_sim_run, and both against
 * the closed form. */
static void test_steps_equal_run(void)
{
  fb_err err;
  fb_tfun *f = NULL;
  oscillator osc = {0};
  MUST(fb_tfun_new_step(0.25, 0.0, 10.0, &f, &err), &err);
  fb_sim_opts o;
  tight_opts(&o, 2.0);
  fb_result *res = NULL;
  if (!f || !oscillator_start(&osc, &f, STIFF, DAMP, o.t_end))
    goto done;
  fb_sim_stepper *st = osc.st;
  MUST(fb_sim_run(osc.bd, &o, &res, &err), &err);
  if (!res)
    goto done;
  /* The static deflection F / k = 12.5 mm is the scale. */
  const double scale = 10.0 / STIFF;
  double worst_run = 0, worst_step = 0, worst_diff = 0;
  for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
    const double *row = fb_result_row(res, k), t = row[0];
    double y[NOUT];
    if (k > 0)
      MUST(fb_sim_stepper_advance(st, t, &err), &err);
    CHECK(fb_sim_stepper_time(st) == t);
    MUST(fb_sim_stepper_outputs(st, y, &err), &err);
    const double exact = response(STIFF, DAMP, t < 0.25 ? 0.0 : 10.0, 0, 0, t - 0.25);
    worst_run = fmax(worst_run, fabs(row[1 + OUT_X] - (t < 0.25 ? 0.0 : exact)));
    worst_step = fmax(worst_step, fabs(y[OUT_X] - (t < 0.25 ? 0.0 : exact)));
    for (size_t j = 0; j < NOUT; ++j)
      worst_diff = fmax(worst_diff, fabs(y[j] - row[1 + j]) / fmax(1.0, fabs(row[1 + j])));
  }
  /* Both integrate with rtol 1e-8: their global errors over 6 periods
   * are tens of rtol of the scale (measured: 7.8e-9 m for the run, 5.1e-9
   * m for the steps, 6e-7 of the scale); 1e-5 of it leaves a margin of
   * 16 and still fails for a sample a step of 1 ms late (x moves 2e-2
   * of the scale per ms at its fastest). */
  fprintf(stderr,
          "steps vs run: worst |x - exact| %.3g m (run), %.3g m (steps), "
          "worst relative difference %.3g\n",
          worst_run, worst_step, worst_diff);
  CHECK(worst_run <= 1e-5 * scale);
  CHECK(worst_step <= 1e-5 * scale);
  /* Work (J, about 0.1) and velocity (m/s, about 0.25) as well: 1e-6
   * absolute is 1e-5 of either. */
  CHECK(worst_diff <= 1e-6);
done:
  fb_result_free(&res);
  oscillator_free(&osc);
}

/* An undamped oscillator at rest under a held force F: 10 N from 0.3 s,
 * -5 N from 0.7 s (after fb_sim_stepper_reset each), stepped by 0.01 s.
 * After each change x follows the closed form from the state at the
 * change, and the force's work is the closed form of a constant force,
 * F (x(t) - x(t_change)), summed over the holds. */
static void test_held_input(void)
{
  fb_err err;
  double force = 0;
  oscillator osc = {0};
  if (!oscillator_held(&osc, &force, STIFF, 0.0, 1.5))
    goto done;
  fb_sim_stepper *st = osc.st;
  const double change[] = {0.3, 0.7}, value[] = {10.0, -5.0};
  double y[NOUT], x1 = 0, v1 = 0, t1 = 0, work_before = 0, worst_x = 0, worst_work = 0;
  for (int step = 1; step <= 150; ++step) {
    const double t = 0.01 * step;
    MUST(fb_sim_stepper_advance(st, t, &err), &err);
    MUST(fb_sim_stepper_outputs(st, y, &err), &err);
    worst_x = fmax(worst_x, fabs(y[OUT_X] - response(STIFF, 0.0, force, x1, v1, t - t1)));
    const double work = work_before + force * (y[OUT_X] - x1);
    worst_work = fmax(worst_work, fabs(y[OUT_WORK] - work));
    for (int c = 0; c < 2; ++c)
      if (fabs(t - change[c]) < 1e-9) {
        work_before = work;
        x1 = y[OUT_X];
        v1 = y[OUT_V];
        t1 = t;
        force = value[c];
        MUST(fb_sim_stepper_reset(st, &err), &err);
      }
  }
  /* The amplitude is 12.5 mm; the closed form starts from the state the
   * stepper reached, so what is compared is the stepping and the hold,
   * to the integration's global error (rtol 1e-8: measured 1.7e-8 m,
   * 1.4e-6 of the amplitude; the bound leaves a margin of 6). A force
   * changed 10 ms late is off by millimetres. The work: the same BDF
   * integrates x' = v and W' = F v, so with F held exactly constant
   * between changes W - F x is constant to rounding (measured 1.5e-15
   * J); a force changed anywhere but at the stepper's time breaks that
   * by F times the distance moved in the misplaced part of a step. */
  fprintf(stderr, "held input: worst |x - closed form| %.3g m, |work - closed form| %.3g J\n",
          worst_x, worst_work);
  CHECK(worst_x <= 1e-7);
  CHECK(worst_work <= 1e-12);
  CHECK(fabs(fb_sim_stepper_time(st) - 1.5) == 0);
done:
  oscillator_free(&osc);
}

/* A stiffness changed at 0.4 s from 800 to 200 N/m: a new diagram, and a
 * new stepper on it from the first one's time and state. x follows the
 * closed form with the new stiffness from the state at the change. */
static void test_new_diagram_from_state(void)
{
  fb_err err;
  double force = 10.0;
  oscillator first = {0}, second = {0};
  fb_tfun *f = NULL;
  MUST(fb_tfun_new_const(force, &f, &err), &err);
  if (f)
    MUST(build(&f, 200.0, DAMP, &second.bg, &second.bd, &err), &err);
  double y[NOUT] = {0};
  if (second.bd && oscillator_held(&first, &force, STIFF, DAMP, 2.0)) {
    MUST(fb_sim_stepper_advance(first.st, 0.4, &err), &err);
    MUST(fb_sim_stepper_outputs(first.st, y, &err), &err);
    CHECK(fb_sim_stepper_nstates(first.st) == fb_bd_nstates(second.bd));
    fb_sim_opts o;
    tight_opts(&o, 2.0);
    o.t_start = fb_sim_stepper_time(first.st);
    o.x0 = fb_sim_stepper_state(first.st);
    MUST(fb_sim_stepper_create(second.bd, &o, &second.st, &err), &err);
  }
  double worst = 0;
  for (int step = 1; second.st && step <= 16; ++step) {
    const double t = 0.4 + 0.1 * step;
    double y2[NOUT];
    MUST(fb_sim_stepper_advance(second.st, t, &err), &err);
    MUST(fb_sim_stepper_outputs(second.st, y2, &err), &err);
    worst = fmax(worst,
                 fabs(y2[OUT_X] - response(200.0, DAMP, force, y[OUT_X], y[OUT_V], t - 0.4)));
  }
  /* The new static deflection is 50 mm; rtol 1e-8 as above (measured
   * 1.6e-8 m). A stepper that restarted from rest, or kept the old
   * stiffness, is off by millimetres. */
  fprintf(stderr, "new stiffness: worst |x - closed form| %.3g m\n", worst);
  CHECK(second.st && worst <= 1e-7);
  oscillator_free(&second);
  oscillator_free(&first);
}

/* Times out of order and past the horizon are refused with the key "t";
 * advancing to the current time does nothing. */
static void test_bad_times(void)
{
  fb_err err;
  double force = 1.0;
  oscillator osc = {0};
  if (oscillator_held(&osc, &force, STIFF, DAMP, 1.0)) {
    fb_sim_stepper *st = osc.st;
    MUST(fb_sim_stepper_advance(st, 0.5, &err), &err);
    MUST(fb_sim_stepper_advance(st, 0.5, &err), &err);
    CHECK(fb_sim_stepper_time(st) == 0.5);
    CHECK(fb_sim_stepper_advance(st, 0.4, &err) == FB_EINVAL && !strcmp(err.key, "t"));
    CHECK(fb_sim_stepper_advance(st, 1.5, &err) == FB_EINVAL && !strcmp(err.key, "t"));
    CHECK(fb_sim_stepper_advance(st, NAN, &err) == FB_EINVAL);
    CHECK(fb_sim_stepper_time(st) == 0.5);
    MUST(fb_sim_stepper_advance(st, 1.0, &err), &err);
    fb_sim_stats stats;
    fb_sim_stepper_stats(st, &stats);
    CHECK(stats.steps > 0 && stats.rhs_evals > stats.steps);
  }
  oscillator_free(&osc);
  oscillator_free(&osc); /* a second free is harmless */
  /* A horizon of 1e7 s: a run's 1e9 samples (32 GB) would be refused,
   * a stepper records none. */
  CHECK(oscillator_held(&osc, &force, STIFF, DAMP, 1e7));
  oscillator_free(&osc);
}

/* A held force made NaN: the restart reports the state's derivative as
 * not finite, and the stepper refuses to go on after that failure. */
static void test_failure_stops(void)
{
  fb_err err;
  double force = 1.0;
  oscillator osc = {0};
  if (oscillator_held(&osc, &force, STIFF, DAMP, 1.0)) {
    fb_sim_stepper *st = osc.st;
    MUST(fb_sim_stepper_advance(st, 0.25, &err), &err);
    force = NAN;
    CHECK(fb_sim_stepper_reset(st, &err) == FB_ESOLVER);
    CHECK(strstr(err.msg, "mass.p") && strstr(err.msg, "restart state"));
    CHECK(fb_sim_stepper_advance(st, 0.5, &err) == FB_EINVAL);
    CHECK(strstr(err.msg, "failed earlier") != NULL);
    CHECK(fb_sim_stepper_time(st) == 0.25);
  }
  oscillator_free(&osc);
}

int main(void)
{
  test_steps_equal_run();
  test_held_input();
  test_new_diagram_from_state();
  test_bad_times();
  test_failure_stops();
  return check_report("test_sim_stepper");
}
