/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulation (flexbond/sim.h) of a mass-spring-damper bond graph against
 * the closed-form response of m x'' + r x' + k x = F(t). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"
#include "flexbond/sim.h"

#include "bgtest_util.h"
#include "check.h"

/* Underdamped: omega_n = 5 rad/s, zeta = r / (2 sqrt(k m)) = 0.15. */
#define MASS 2.0
#define STIFF 50.0
#define DAMP 3.0
#define FORCE 10.0

/* Unit step response of the oscillator, divided by the static deflection
 * F/k: g(tau) = 1 - e^(-zeta wn tau) (cos wd tau + zeta wn / wd sin wd tau),
 * 0 for tau < 0 (Ogata, "Modern Control Engineering", 5th ed., sec. 5-3). */
static double step_shape(double tau)
{
  if (tau < 0)
    return 0;
  const double wn = sqrt(STIFF / MASS), zeta = DAMP / (2 * sqrt(STIFF * MASS));
  const double wd = wn * sqrt(1 - zeta * zeta), a = zeta * wn;
  return 1 - exp(-a * tau) * (cos(wd * tau) + a / wd * sin(wd * tau));
}

/* Its derivative: g'(tau) = e^(-zeta wn tau) wn^2 / wd sin wd tau. */
static double step_shape_rate(double tau)
{
  if (tau < 0)
    return 0;
  const double wn = sqrt(STIFF / MASS), zeta = DAMP / (2 * sqrt(STIFF * MASS));
  const double wd = wn * sqrt(1 - zeta * zeta);
  return exp(-zeta * wn * tau) * wn * wn / wd * sin(wd * tau);
}

/* Free response from x(0) = 1, x'(0) = 0 is 1 - g(tau). */
static double free_shape(double tau)
{
  return 1 - step_shape(tau);
}

/* A damper law e = r f + c2 f |f| given as callbacks, so the diagram is
 * not linear and its Newton matrix is re-evaluated. Once |f| exceeds
 * limit (when set) it fails: fatally, by returning NaN, or (inf_slope)
 * by a Jacobian of inf while its value stays finite. With calls set, it
 * counts its evaluations there, and evaluation number nan_call (if > 0)
 * returns NaN, once: a glitch. */
typedef struct damper_law {
  double r;     /* N s/m */
  double c2;    /* N s^2/m^2 */
  double limit; /* m/s, 0: never fails */
  int nan_past_limit;
  int inf_slope;
  long *calls;
  long nan_call;
} damper_law;

static int past_limit(const damper_law *d, double v)
{
  return d->limit > 0 && fabs(v) > d->limit;
}

static int damper_eval(void *ctx, const fb_law_in *in, double *y)
{
  const damper_law *d = ctx;
  const double *x = in->x;
  if (d->calls && ++*d->calls == d->nan_call) {
    y[0] = NAN;
    return 0;
  }
  if (past_limit(d, x[0]) && d->nan_past_limit) {
    y[0] = NAN;
    return 0;
  }
  if (past_limit(d, x[0]) && !d->inf_slope)
    return -1;
  y[0] = d->r * x[0] + d->c2 * x[0] * fabs(x[0]);
  return 0;
}

static int damper_jacobian(void *ctx, const fb_law_in *in, double *jac)
{
  const damper_law *d = ctx;
  const double *x = in->x;
  jac[0] = past_limit(d, x[0]) && d->inf_slope ? INFINITY : d->r + 2 * d->c2 * fabs(x[0]);
  return 0;
}

static const fb_law_ops damper_ops = {
    .name = "test damper", .eval = damper_eval, .jacobian = damper_jacobian, .free = free};

/* Mass-spring-damper: Se (force) -> 1-junction -> I (m), C (K = k), R (r).
 * Probes: displacement x (state q of the spring), velocity v (flow into
 * the mass). Takes ownership of *force. damper: NULL for a matrix law. */
static int build_msd(fb_tfun **force, const damper_law *damper, fb_bg **bg, fb_bd **bd,
                     fb_err *err)
{
  const size_t one[1] = {1};
  fb_mat *r = NULL;
  *bd = NULL;
  int rc = fb_bg_new("msd", bg, err);
  if (rc != FB_OK) {
    fb_tfun_free(force);
    return rc;
  }
  rc = add_forced_oscillator(*bg, force, MASS, STIFF, err);
  if (!rc && damper) {
    damper_law *d = malloc(sizeof *d);
    if (d)
      *d = *damper;
    rc = d ? fb_bg_add_field_law(*bg, "damper", FB_BG_R, 1, one, &damper_ops, d, err)
           : FB_ENOMEM;
  } else if (!rc) {
    rc = fb_mat_new_scaled_identity(1, DAMP, &r, err);
    if (!rc)
      rc = fb_bg_add_field(*bg, "damper", FB_BG_R, 1, one, &r, err);
  }
  if (!rc)
    rc = fb_bg_connect(*bg, "br", "J", "damper", err);
  const fb_probe_spec probes[2] = {{"x", FB_PROBE_STATE, "spring", 0, 0, 1.0, NULL, NULL, 0},
                                   {"v", FB_PROBE_FLOW, "bm", 0, 0, 1.0, NULL, NULL, 0}};
  if (!rc)
    rc = fb_bd_build(*bg, probes, 2, bd, err);
  return rc;
}

/* Runs opts on a fresh diagram driven by *force (owned). */
static int simulate(fb_tfun **force, const damper_law *damper, const fb_sim_opts *opts,
                    fb_result **res, fb_err *err)
{
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  *res = NULL;
  int rc = build_msd(force, damper, &bg, &bd, err);
  if (rc == FB_OK)
    rc = fb_sim_run(bd, opts, res, err);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
  return rc;
}

static int simulate_step(double t_step, const damper_law *damper, const fb_sim_opts *opts,
                         fb_result **res, fb_err *err)
{
  fb_tfun *force = NULL;
  int rc = fb_tfun_new_step(t_step, 0, FORCE, &force, err);
  return rc != FB_OK ? rc : simulate(&force, damper, opts, res, err);
}

static void tight_opts(fb_sim_opts *o, double t_end)
{
  fb_sim_opts_default(o);
  o->t_end = t_end;
  o->rtol = 1e-8;
  o->atol = 1e-12;
}

/* Error bounds. CVODE keeps each step's local error below about
 * rtol |y| + atol; over these 3 s (2.4 damped periods) the global error
 * of the stable oscillator stays a modest multiple of that (measured
 * about 12 rtol). 100 rtol relative to the static deflection F/k (and to
 * the velocity scale wn F/k) is the bound: loose enough to be robust,
 * tight enough that sampling off the grid (v ~ 1 m/s: 1 ms off is 1e-3
 * m) or a wrong interpolation would fail it. */
#define X_TOL (100 * 1e-8 * FORCE / STIFF)
#define V_TOL (100 * 1e-8 * FORCE / STIFF * 5.0)

/* Compares columns x and v with F/k g(t - t_step). */
static void check_step_columns(const fb_result *res, double t_step)
{
  const long cx = fb_result_find(res, "x"), cv = fb_result_find(res, "v");
  CHECK(cx > 0 && cv > 0);
  if (cx <= 0 || cv <= 0)
    return;
  double worst_x = 0, worst_v = 0;
  for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
    const double *row = fb_result_row(res, k);
    const double tau = row[0] - t_step;
    worst_x = fmax(worst_x, fabs(row[cx] - FORCE / STIFF * step_shape(tau)));
    worst_v = fmax(worst_v, fabs(row[cv] - FORCE / STIFF * step_shape_rate(tau)));
  }
  CHECK_NEAR(worst_x, 0, X_TOL);
  CHECK_NEAR(worst_v, 0, V_TOL);
}

static void test_step_response(void)
{
  fb_sim_opts o;
  tight_opts(&o, 3.0);
  fb_result *res = NULL;
  fb_err err;
  const int rc = simulate_step(0.0, NULL, &o, &res, &err);
  CHECK(rc == FB_OK);
  if (rc != FB_OK) {
    fprintf(stderr, "  %s\n", err.msg);
    return;
  }
  check_step_columns(res, 0.0);

  /* Grid: k / 1000 exactly (0 + k / rate), the last row at t_end. */
  CHECK(fb_result_nsamples(res) == 3001);
  CHECK(fb_result_ncols(res) == 3);
  int on_grid = 1;
  for (size_t k = 0; k < fb_result_nsamples(res); ++k)
    on_grid &= fb_result_row(res, k)[0] == (double)k / 1000.0;
  CHECK(on_grid);
  CHECK(fb_result_row(res, 3000)[0] == 3.0);
  CHECK(fb_result_row(res, 3001) == NULL);
  CHECK(strcmp(fb_result_col_name(res, 0), "t") == 0);
  CHECK(strcmp(fb_result_col_unit(res, 0), "s") == 0);
  CHECK(fb_result_find(res, "t") == 0);
  CHECK(fb_result_find(res, "nope") == -1);

  /* Counters: linear model, so every Newton setup is one factorisation
   * (plus any re-pivoting ones); far fewer steps than samples. */
  const fb_sim_stats *s = fb_result_stats(res);
  CHECK(s->steps > 0 && s->steps < 3001 / 4);
  CHECK(s->rhs_evals >= s->steps);
  CHECK(s->newton_iters >= s->steps);
  CHECK(s->newton_setups >= 1 && s->newton_setups <= s->steps);
  CHECK(s->factorizations >= s->newton_setups);
  CHECK(s->last_order >= 1 && s->last_order <= 5);
  CHECK(s->wall_seconds >= 0);
  fb_result_free(&res);
  CHECK(res == NULL);
  fb_result_free(&res);
}

/* The same run sampled at 10 Hz and at 1000 Hz takes exactly the same
 * steps: outputs are interpolated, they never shorten a step. */
static void test_sampling_independent_of_steps(void)
{
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 3.0;
  fb_result *slow = NULL, *fast = NULL;
  fb_err err;
  o.sample_rate = 10;
  CHECK(simulate_step(0.0, NULL, &o, &slow, &err) == FB_OK);
  o.sample_rate = 1000;
  CHECK(simulate_step(0.0, NULL, &o, &fast, &err) == FB_OK);
  if (slow && fast) {
    CHECK(fb_result_nsamples(slow) == 31);
    CHECK(fb_result_stats(slow)->steps == fb_result_stats(fast)->steps);
    CHECK(fb_result_stats(slow)->rhs_evals == fb_result_stats(fast)->rhs_evals);
    /* Row 10 at 10 Hz and row 1000 at 1 kHz are both t = 1 s and come
     * from the same interpolant. */
    CHECK(fb_result_row(slow, 10)[0] == fb_result_row(fast, 1000)[0]);
    CHECK(fb_result_row(slow, 10)[1] == fb_result_row(fast, 1000)[1]);
  }
  fb_result_free(&slow);
  fb_result_free(&fast);
}

/* A step source at 0.5 s: the state stays exactly at rest before it and
 * follows the delayed closed form after it. */
static void test_delayed_step(void)
{
  fb_sim_opts o;
  tight_opts(&o, 3.0);
  fb_result *res = NULL;
  fb_err err;
  CHECK(simulate_step(0.5, NULL, &o, &res, &err) == FB_OK);
  if (!res)
    return;
  check_step_columns(res, 0.5);
  const long cx = fb_result_find(res, "x");
  int at_rest = 1;
  for (size_t k = 0; k < 500; ++k)
    at_rest &= fb_result_row(res, k)[cx] == 0.0;
  CHECK(at_rest);
  fb_result_free(&res);
}

/* A 0.1 ms force pulse at 0.5 s from a callback. Without breakpoints the
 * rest state lets CVODE take steps of a large fraction of a second and
 * step over the pulse entirely (checked: 3 steps, zero response); with
 * them the response is F/k [g(t - 0.5) - g(t - 0.5001)]. */
#define PULSE_START 0.5
#define PULSE_END 0.5001

static double pulse(double t, void *ctx)
{
  (void)ctx;
  return t >= PULSE_START && t < PULSE_END ? FORCE : 0.0;
}

/* from_source: the callback declares the breakpoints; otherwise they
 * come from opts, mixed with duplicates and times outside the run. */
static void check_pulse(int from_source)
{
  const double declared[2] = {PULSE_START, PULSE_END};
  const double bps[5] = {PULSE_END, -1.0, PULSE_START, 7.0, PULSE_START};
  fb_sim_opts o;
  tight_opts(&o, 3.0);
  if (!from_source) {
    o.breakpoints = bps;
    o.nbreakpoints = 5;
  }
  fb_tfun *force = NULL;
  fb_err err;
  fb_result *res = NULL;
  CHECK(fb_tfun_new_callback(pulse, NULL, from_source ? 2 : 0, declared, &force, &err) ==
        FB_OK);
  CHECK(simulate(&force, NULL, &o, &res, &err) == FB_OK);
  if (!res)
    return;
  /* Peak response ~ F width / (m wd) = 1e-4 m; the bound is 100 rtol of
   * it, as for the step. */
  const long cx = fb_result_find(res, "x");
  double worst = 0, peak = 0;
  for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
    const double *row = fb_result_row(res, k);
    const double want =
        FORCE / STIFF * (step_shape(row[0] - PULSE_START) - step_shape(row[0] - PULSE_END));
    worst = fmax(worst, fabs(row[cx] - want));
    peak = fmax(peak, fabs(want));
  }
  CHECK(peak > 5e-5);
  CHECK_NEAR(worst, 0, 100 * 1e-8 * peak);
  fb_result_free(&res);
}

static void test_pulse_breakpoints(void)
{
  check_pulse(1);
  check_pulse(0);
}

/* Grid from t_start = 0.25 s with an initial displacement (opts->x0):
 * free decay x0 (1 - g(t - t_start)); rows at 0.25 + k / rate exactly. */
static void test_grid_and_x0(void)
{
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  fb_tfun *force = NULL;
  fb_err err;
  CHECK(fb_tfun_new_const(0.0, &force, &err) == FB_OK);
  CHECK(build_msd(&force, NULL, &bg, &bd, &err) == FB_OK);
  if (!bd) {
    fb_bg_free(&bg);
    return;
  }
  const double q0 = 0.01;
  double x0[2] = {0, 0};
  CHECK(fb_bd_nstates(bd) == 2);
  for (size_t i = 0; i < 2; ++i)
    if (strcmp(fb_bd_state_name(bd, i), "spring.q") == 0)
      x0[i] = q0;
  CHECK(x0[0] + x0[1] == q0);
  fb_sim_opts o;
  tight_opts(&o, 0.75);
  o.t_start = 0.25;
  o.x0 = x0;
  fb_result *res = NULL;
  CHECK(fb_sim_run(bd, &o, &res, &err) == FB_OK);
  if (res) {
    CHECK(fb_result_nsamples(res) == 501);
    int on_grid = 1;
    double worst = 0;
    const long cx = fb_result_find(res, "x");
    for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
      const double *row = fb_result_row(res, k);
      on_grid &= row[0] == 0.25 + (double)k / 1000.0;
      worst = fmax(worst, fabs(row[cx] - q0 * free_shape(row[0] - 0.25)));
    }
    CHECK(on_grid);
    CHECK(fb_result_row(res, 500)[0] == 0.75);
    CHECK_NEAR(worst, 0, 100 * 1e-8 * q0);
    for (size_t j = 1; j < fb_result_ncols(res); ++j) {
      CHECK(strcmp(fb_result_col_name(res, j), fb_bd_output_name(bd, j - 1)) == 0);
      CHECK(strcmp(fb_result_col_unit(res, j), fb_bd_output_unit(bd, j - 1)) == 0);
    }
    fb_result_free(&res);
  }
  /* (t_end - t_start) rate = 500.5 is not an integer: 501 samples, the
   * last at 0.75 < t_end. */
  o.t_end = 0.7505;
  CHECK(fb_sim_run(bd, &o, &res, &err) == FB_OK);
  if (res) {
    CHECK(fb_result_nsamples(res) == 501);
    CHECK(fb_result_row(res, 500)[0] == 0.25 + 500 / 1000.0);
    fb_result_free(&res);
  }
  /* 0.7 s at 1 kHz is 700 intervals up to rounding: last row at t_end. */
  o.t_start = 0;
  o.t_end = 0.7;
  CHECK(fb_sim_run(bd, &o, &res, &err) == FB_OK);
  if (res) {
    CHECK(fb_result_nsamples(res) == 701);
    CHECK(fb_result_row(res, 700)[0] == 0.7);
    fb_result_free(&res);
  }
  /* A non-finite initial state is rejected naming the state. */
  x0[0] = NAN;
  CHECK(fb_sim_run(bd, &o, &res, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "x0[0]") != NULL && !strcmp(err.key, "x0[0]"));
  CHECK(strstr(err.msg, fb_bd_state_name(bd, 0)) != NULL);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* The linear damper through a law callback: the diagram is not linear,
 * so the Newton matrix is re-evaluated; the answer must not change. */
static void test_nonlinear_path(void)
{
  fb_sim_opts o;
  tight_opts(&o, 3.0);
  const damper_law d = {DAMP, 0, 0, 0, 0, NULL, 0};
  fb_result *res = NULL;
  fb_err err;
  CHECK(simulate_step(0.0, &d, &o, &res, &err) == FB_OK);
  if (!res)
    return;
  check_step_columns(res, 0.0);
  fb_result_free(&res);
}

/* m x'' = F - k x - r v - c2 v |v| by classical Runge-Kutta (RK4). */
static void rk4_derivative(const damper_law *d, const double s[2], double ds[2])
{
  ds[0] = s[1];
  ds[1] = (FORCE - STIFF * s[0] - d->r * s[1] - d->c2 * s[1] * fabs(s[1])) / MASS;
}

static void rk4_step(const damper_law *d, double h, double s[2])
{
  double k1[2], k2[2], k3[2], k4[2], tmp[2];
  rk4_derivative(d, s, k1);
  for (int i = 0; i < 2; ++i)
    tmp[i] = s[i] + 0.5 * h * k1[i];
  rk4_derivative(d, tmp, k2);
  for (int i = 0; i < 2; ++i)
    tmp[i] = s[i] + 0.5 * h * k2[i];
  rk4_derivative(d, tmp, k3);
  for (int i = 0; i < 2; ++i)
    tmp[i] = s[i] + h * k3[i];
  rk4_derivative(d, tmp, k4);
  for (int i = 0; i < 2; ++i)
    s[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
}

/* Quadratic drag (c2 = 5 N s^2/m^2, comparable to the linear damping at
 * the peak velocity): no closed form, so the reference is RK4 with
 * h = 0.1 ms, whose global error ~ (wn h)^4 ~ 1e-13 of the amplitude is
 * far below the CVODE bound X_TOL. */
static void test_quadratic_damper(void)
{
  fb_sim_opts o;
  tight_opts(&o, 3.0);
  const damper_law d = {DAMP, 5.0, 0, 0, 0, NULL, 0};
  fb_result *res = NULL;
  fb_err err;
  CHECK(simulate_step(0.0, &d, &o, &res, &err) == FB_OK);
  if (!res)
    return;
  const long cx = fb_result_find(res, "x"), cv = fb_result_find(res, "v");
  const int substeps = 10; /* 1 ms sample interval / 0.1 ms */
  double s[2] = {0, 0}, worst_x = 0, worst_v = 0, peak_v = 0;
  for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
    const double *row = fb_result_row(res, k);
    worst_x = fmax(worst_x, fabs(row[cx] - s[0]));
    worst_v = fmax(worst_v, fabs(row[cv] - s[1]));
    peak_v = fmax(peak_v, fabs(s[1]));
    for (int i = 0; i < substeps; ++i)
      rk4_step(&d, 1e-4, s);
  }
  CHECK(peak_v > 0.3); /* the drag term matters: c2 v^2 > 0.45 N */
  CHECK_NEAR(worst_x, 0, X_TOL);
  CHECK_NEAR(worst_v, 0, V_TOL);
  fb_result_free(&res);
}

/* A stiff, overdamped variant: r = 1e4 N s/m gives the modes
 * lambda1 ~ -r/m = -5000 /s and lambda2 = (k/m) / lambda1 = -0.005 /s
 * (their product is k/m), a stiffness ratio of 1e6. BDF with a proper
 * Newton matrix steps through the slow mode with large steps; an
 * explicit method, or Newton with a wrong matrix, is held to
 * h < ~2/5000 s, i.e. thousands of steps over 3 s. Closed form:
 * x = F/k [1 - (lambda2 e^(lambda1 t) - lambda1 e^(lambda2 t)) /
 * (lambda2 - lambda1)] (Ogata, sec. 5-3, overdamped case). */
static void test_stiff(void)
{
  const double r = 1e4;
  const double lambda1 = (-r - sqrt(r * r - 4 * MASS * STIFF)) / (2 * MASS);
  const double lambda2 = STIFF / MASS / lambda1;
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 3;
  const damper_law d = {r, 0, 0, 0, 0, NULL, 0};
  fb_result *res = NULL;
  fb_err err;
  CHECK(simulate_step(0.0, &d, &o, &res, &err) == FB_OK);
  if (!res)
    return;
  const long cx = fb_result_find(res, "x");
  double worst = 0;
  for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
    const double t = fb_result_row(res, k)[0];
    const double want =
        FORCE / STIFF *
        (1 - (lambda2 * exp(lambda1 * t) - lambda1 * exp(lambda2 * t)) / (lambda2 - lambda1));
    worst = fmax(worst, fabs(fb_result_row(res, k)[cx] - want));
  }
  /* 100 rtol of the response reached, F/k (1 - e^(3 lambda2)) ~ 3e-3 m. */
  CHECK_NEAR(worst, 0, 100 * o.rtol * FORCE / STIFF * (1 - exp(3 * lambda2)));
  CHECK(fb_result_stats(res)->steps < 500);
  fb_result_free(&res);
}

/* want is "KEY: message": the setting goes into err.key, the message
 * starts with the rest (the caller, not the sim, says where the setting
 * came from). */
static void check_opts_message(const fb_sim_opts *o, const char *want)
{
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_sim_opts_check(o, &err) == FB_EINVAL);
  const char *colon = strchr(want, ':');
  const size_t klen = colon ? (size_t)(colon - want) : strlen(want);
  const char *rest = colon ? colon + 2 : "";
  CHECK(strlen(err.key) == klen && !strncmp(err.key, want, klen));
  CHECK(!strncmp(err.msg, rest, strlen(rest)));
  if (strlen(err.key) != klen || strncmp(err.key, want, klen) ||
      strncmp(err.msg, rest, strlen(rest)))
    fprintf(stderr, "  got key \"%s\", \"%s\", want \"%s\"\n", err.key, err.msg, want);
}

static void test_opts(void)
{
  fb_sim_opts o;
  fb_err err;
  fb_sim_opts_default(&o);
  CHECK(o.t_start == 0 && o.t_end == 1 && o.rtol == 1e-6 && o.atol == 1e-9);
  CHECK(o.max_step == 0 && o.sample_rate == 1000 && o.max_order == 5);
  CHECK(o.max_steps == 10000000L && !o.breakpoints && !o.nbreakpoints && !o.x0);
  CHECK(fb_sim_opts_check(&o, &err) == FB_OK);

  o.rtol = 0;
  check_opts_message(&o, "rtol: must be in (0, 1), got 0");
  o.rtol = 1;
  check_opts_message(&o, "rtol: must be in (0, 1), got 1");
  fb_sim_opts_default(&o);
  o.atol = -1e-9;
  check_opts_message(&o, "atol: must be positive, got -1e-09");
  fb_sim_opts_default(&o);
  o.t_end = 0;
  check_opts_message(&o, "t_end: must be finite and greater than t_start = 0, got 0");
  o.t_end = INFINITY;
  check_opts_message(&o, "t_end");
  fb_sim_opts_default(&o);
  o.t_start = NAN;
  check_opts_message(&o, "t_start: must be finite");
  fb_sim_opts_default(&o);
  o.sample_rate = 0;
  check_opts_message(&o, "sample_rate: must be positive, got 0");
  o.sample_rate = 1e9;
  o.t_end = 1;
  check_opts_message(&o, "sample_rate: 1e+09 Hz over 1 s gives 1e+09 samples");
  fb_sim_opts_default(&o);
  o.max_order = 6;
  check_opts_message(&o, "max_order: must be 1..5, got 6");
  o.max_order = 0;
  check_opts_message(&o, "max_order: must be 1..5, got 0");
  fb_sim_opts_default(&o);
  o.max_step = -0.1;
  check_opts_message(&o, "max_step: must be finite and >= 0 (0: no limit), got -0.1");
  fb_sim_opts_default(&o);
  o.max_steps = 0;
  check_opts_message(&o, "max_steps: must be in 1 .. 1000000000");
  /* The bound's edge: FB_SIM_MAX_STEPS is allowed, one more is not. */
  o.max_steps = FB_SIM_MAX_STEPS + 1;
  check_opts_message(&o, "max_steps: must be in 1 .. 1000000000");
  o.max_steps = FB_SIM_MAX_STEPS;
  fb_err_clear(&err);
  CHECK(fb_sim_opts_check(&o, &err) == FB_OK);
  /* Certain not to finish: 1 s at most 1e-8 s a step is 1e8 steps, more
   * than the budget; 1e7 exactly is not refused. */
  fb_sim_opts_default(&o);
  o.max_step = 1e-8;
  check_opts_message(&o, "max_step: 1e-08 s over the run's 1 s (t_end - t_start) "
                         "needs at least 1e+08 steps, more than max_steps = "
                         "10000000: the run could not finish");
  o.max_step = 1e-7;
  CHECK(fb_sim_opts_check(&o, &err) == FB_OK);
  o.max_steps = 9999999;
  check_opts_message(&o, "max_step: 1e-07 s");
  /* The result's memory: 9.9e7 samples are within the 1e8 allowed, and
   * within 2 GiB with the count assumed when it is not known (1 output,
   * 2 columns: 1.6 GB), but not with 2 outputs (3 columns). */
  fb_sim_opts_default(&o);
  o.t_end = 9.9;
  o.sample_rate = 1e7;
  CHECK(fb_sim_opts_check(&o, &err) == FB_OK);
  o.noutputs = 2;
  check_opts_message(&o, "sample_rate: 1e+07 Hz over 9.9 s gives 9.9e+07 samples "
                         "of 3 columns, which would need about 2.4 GB (samples x columns x 8 "
                         "bytes), more than the 2.1 GB a run's result may take");
  fb_sim_opts_default(&o);
  const double bad[2] = {0.5, NAN};
  o.breakpoints = bad;
  o.nbreakpoints = 2;
  check_opts_message(&o, "breakpoints[1]: must be finite, got nan");

  /* fb_sim_run checks too, and leaves *out NULL. */
  fb_sim_opts_default(&o);
  o.rtol = 2;
  fb_result *res = (fb_result *)&o; /* any non-NULL value */
  fb_tfun *force = NULL;
  CHECK(fb_tfun_new_const(1.0, &force, &err) == FB_OK);
  CHECK(simulate(&force, NULL, &o, &res, &err) == FB_EINVAL);
  CHECK(res == NULL);
  CHECK(!strcmp(err.key, "rtol") && strstr(err.msg, "must be in (0, 1)") != NULL);
}

/* Reads the time out of "at t = <t> s: ...". */
static double failure_time(const char *msg)
{
  double t = NAN;
  const char *at = strstr(msg, "at t = ");
  if (at)
    sscanf(at, "at t = %lf s:", &t);
  return t;
}

/* A failure from a non-finite value: what was not finite, where it starts
 * (fb_bd_explain_nonfinite), the hint. */
static void check_nonfinite_message(const char *msg, const char *what, const char *where)
{
  const char *w = strstr(msg, what);
  const char *s = w ? strstr(w, "; the non-finite value starts at ") : NULL;
  const char *h = s ? strstr(s, "; hint: a law or time function evaluated outside its domain: "
                                "log or sqrt of a negative number, a division by zero")
                    : NULL;
  CHECK(w != NULL);
  CHECK(s != NULL &&
        strncmp(s + strlen("; the non-finite value starts at "), where, strlen(where)) == 0);
  CHECK(h != NULL);
  if (!w || !s || !h ||
      strncmp(s + strlen("; the non-finite value starts at "), where, strlen(where)) != 0)
    fprintf(stderr, "  got \"%s\"\n  want \"%s\" ... \"%s\"\n", msg, what, where);
}

static void test_failures(void)
{
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 3;
  fb_result *res = NULL;
  fb_err err;

  /* The step budget is for the whole run. */
  o.max_steps = 20;
  CHECK(simulate_step(0.0, NULL, &o, &res, &err) == FB_ESOLVER);
  CHECK(res == NULL);
  CHECK(strstr(err.msg, "CVODE CV_TOO_MUCH_WORK: ") != NULL);
  CHECK(strstr(err.msg, "raise max_steps") != NULL && !strcmp(err.key, "max_steps"));
  const double t_fail = failure_time(err.msg);
  CHECK(t_fail > 0 && t_fail < 3);

  /* A law that fails for |v| > 0.5 m/s: the velocity first reaches it at
   * the root of F/k g'(tau) = 0.5 (tau ~ 0.11 s, found by bisection on
   * the closed form); the failure must be reported at an earlier time,
   * with CVODE's flag, the hint and the diagram's message. */
  fb_sim_opts_default(&o);
  o.t_end = 3;
  const damper_law d = {DAMP, 0, 0.5, 0, 0, NULL, 0};
  CHECK(simulate_step(0.0, &d, &o, &res, &err) == FB_ESOLVER);
  CHECK(res == NULL);
  double lo = 0, hi = 0.3;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (FORCE / STIFF * step_shape_rate(mid) > 0.5)
      hi = mid;
    else
      lo = mid;
  }
  const double t_cross = hi;
  const double t_law = failure_time(err.msg);
  CHECK(t_law > 0.5 * t_cross && t_law <= t_cross);
  CHECK(strstr(err.msg, "CVODE CV_") != NULL);
  CHECK(strstr(err.msg, "evaluating the model failed") != NULL);
  CHECK(strstr(err.msg, "damper") != NULL);

  /* The same law returning NaN instead: every step towards t_cross is
   * rejected and cut until it no longer advances t; that must be reported
   * there, not after max_steps (10^7) futile steps, with the state whose
   * derivative is NaN, the law that made it from a finite velocity, and
   * the hint. */
  const damper_law dnan = {DAMP, 0, 0.5, 1, 0, NULL, 0};
  CHECK(simulate_step(0.0, &dnan, &o, &res, &err) == FB_ESOLVER);
  CHECK(res == NULL);
  /* The message prints 6 significant digits: 5e-6 relative at most. */
  CHECK_NEAR(failure_time(err.msg), t_cross, 1e-5 * t_cross);
  check_nonfinite_message(err.msg, "the derivative of state mass.p is nan",
                          "R 'damper' (law 'test damper'): damper.e = nan from finite inputs "
                          "mass.f = 0.5");

  /* CV_TOO_MUCH_WORK names the state with the largest local error. */
  fb_sim_opts_default(&o);
  o.t_end = 3;
  o.max_steps = 20;
  CHECK(simulate_step(0.0, NULL, &o, &res, &err) == FB_ESOLVER);
  CHECK(strstr(err.msg, "the largest local error") != NULL);
  CHECK(strstr(err.msg, "is in state ") != NULL);
}

/* F(t) = FORCE (1 + log(1.5 - t)): finite (however large) before 1.5 s,
 * inf at 1.5 s and NaN after. */
static double log_force(double t, void *ctx)
{
  (void)ctx;
  return FORCE * (1 + log(1.5 - t));
}

/* F(t) = FORCE sqrt(t - 1): NaN from the start. */
static double sqrt_force(double t, void *ctx)
{
  (void)ctx;
  return FORCE * sqrt(t - 1);
}

static int simulate_force(double (*fn)(double, void *), const fb_sim_opts *o,
                          const damper_law *damper, fb_result **res, fb_err *err)
{
  fb_tfun *force = NULL;
  int rc = fb_tfun_new_callback(fn, NULL, 0, NULL, &force, err);
  return rc != FB_OK ? rc : simulate(&force, damper, o, res, err);
}

/* A source whose time function leaves its domain at 1.5 s: reported at
 * 1.5 s, naming the mass whose momentum rate is not finite and the
 * source, not as a step size that no longer advances t for no reason. */
static void test_nonfinite_source(void)
{
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 3;
  fb_result *res = (fb_result *)&o; /* any non-NULL value */
  fb_err err;
  CHECK(simulate_force(log_force, &o, NULL, &res, &err) == FB_ESOLVER);
  CHECK(res == NULL);
  CHECK_NEAR(failure_time(err.msg), 1.5, 1e-5 * 1.5);
  check_nonfinite_message(err.msg, "the derivative of state mass.p is ",
                          "Se 'F' (source): e:bF = ");

  /* With a breakpoint at 1.5 s the segment after it starts there, where
   * CVODE's first evaluation has no shorter step to try
   * (CV_FIRST_RHSFUNC_ERR); its sample at 1.5 s is written first and
   * shows the output v (the flow into the mass) is still finite, so the
   * failure is the derivative's. */
  const double at = 1.5;
  o.breakpoints = &at;
  o.nbreakpoints = 1;
  o.sample_rate = 3; /* no sample at 1.5 s */
  CHECK(simulate_force(log_force, &o, NULL, &res, &err) == FB_ESOLVER);
  CHECK_NEAR(failure_time(err.msg), 1.5, 1e-5 * 1.5);
  CHECK(strstr(err.msg, "CVODE CV_FIRST_RHSFUNC_ERR: ") != NULL);
  check_nonfinite_message(err.msg, "the derivative of state mass.p is -inf",
                          "Se 'F' (source): e:bF = -inf");

  /* NaN at the initial state: at t_start, before any step. */
  fb_sim_opts_default(&o);
  o.t_end = 3;
  CHECK(simulate_force(sqrt_force, &o, NULL, &res, &err) == FB_ESOLVER);
  CHECK(failure_time(err.msg) == 0);
  CHECK(strstr(err.msg, "at the initial state") != NULL);
  check_nonfinite_message(err.msg, "the derivative of state mass.p is nan",
                          "Se 'F' (source): e:bF = nan");
}

/* A law whose slope is inf past 0.01 m/s while its value stays finite:
 * the Newton matrix, not the right-hand side, is not finite, and the
 * failure says so and names the law. CVODE refreshes the matrix only
 * when it finds it stale, so the velocity must stay past the limit for a
 * while: from 2 ms on, over most of a 3 s run. */
static void test_nonfinite_jacobian(void)
{
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 3;
  const damper_law d = {DAMP, 0, 0.01, 0, 1, NULL, 0};
  fb_result *res = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(simulate_step(0.0, &d, &o, &res, &err) == FB_ESOLVER);
  CHECK(res == NULL);
  const double t = failure_time(err.msg);
  CHECK(t > 0 && t < 3);
  check_nonfinite_message(err.msg, "the Newton matrix is not finite",
                          "R 'damper' (law 'test damper'): d damper.e / d mass.f = inf at "
                          "finite inputs mass.f = ");
}

/* A NaN that one evaluation returns and the next does not (a step that
 * probed a bad region, shortened, stays clear of it) is recovered from:
 * the run succeeds and matches the closed form. */
static void test_nonfinite_recovered(void)
{
  fb_sim_opts o;
  tight_opts(&o, 3.0);
  long calls = 0;
  const damper_law d = {DAMP, 0, 0, 0, 0, &calls, 40};
  fb_result *res = NULL;
  fb_err err;
  const int rc = simulate_step(0.0, &d, &o, &res, &err);
  CHECK(rc == FB_OK);
  if (rc != FB_OK)
    fprintf(stderr, "  %s\n", err.msg);
  CHECK(calls > 40);
  if (res)
    check_step_columns(res, 0.0);
  fb_result_free(&res);
}

/* The static equilibrium of a model whose force is NaN at that time is
 * refused naming the source; fmax in its residuals used to drop the NaN
 * and call the NaN state an equilibrium. */
static void test_nonfinite_static(void)
{
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  fb_tfun *force = NULL;
  fb_err err;
  CHECK(fb_tfun_new_callback(log_force, NULL, 0, NULL, &force, &err) == FB_OK);
  CHECK(build_msd(&force, NULL, &bg, &bd, &err) == FB_OK);
  if (bd) {
    const double x0[2] = {0, 0};
    double x[2] = {0, 0};
    CHECK(fb_sim_static_state(bd, 1.0, x0, x, &err) == FB_OK);
    CHECK(fb_sim_static_state(bd, 2.0, x0, x, &err) == FB_ESOLVER);
    CHECK(strstr(err.msg, "static equilibrium at t = 2 s: ") != NULL);
    check_nonfinite_message(err.msg, "the derivative of state mass.p is nan",
                            "Se 'F' (source): e:bF = nan");
  }
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* A run too short for CVODE's first step is refused as invalid input, with
 * the limit, before any integration: 1e-300 s after 0 (CVODE squares the
 * length, which underflows), 2 roundoffs after 1 s (CV_TOO_CLOSE). */
static void test_too_short(void)
{
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 1e-300;
  check_opts_message(&o, "t_end: the run from t_start = 0 s to t_end = 1e-300 s is "
                         "too short for the solver to take a step: t_end - t_start = 1e-300 s, "
                         "it must be at least 1.49e-154 s");
  o.t_start = 1;
  o.t_end = nextafter(nextafter(1.0, 2.0), 2.0);
  check_opts_message(&o, "t_end: the run from t_start = 1 s to t_end = "
                         "1.0000000000000004 s is too short for the solver to take a step: "
                         "t_end - t_start = 4.44e-16 s, it must be at least 2.22e-14 s");
  fb_result *res = NULL;
  fb_err err;
  CHECK(simulate_step(0.0, NULL, &o, &res, &err) == FB_EINVAL);
  CHECK(res == NULL);
  /* Just above the limits the runs succeed, with the one sample at
   * t_start (shorter than a sample interval). */
  const double t_ends[2] = {1e-150, 1 + 1e-13};
  for (int i = 0; i < 2; ++i) {
    o.t_start = i == 0 ? 0.0 : 1.0;
    o.t_end = t_ends[i];
    CHECK(fb_sim_opts_check(&o, &err) == FB_OK);
    CHECK(simulate_step(0.0, NULL, &o, &res, &err) == FB_OK);
    if (res)
      CHECK(fb_result_nsamples(res) == 1);
    fb_result_free(&res);
  }
}

/* A graph without storage is algebraic: Se -> R gives f = e / r at each
 * sample, with no integration steps. */
static void test_no_states(void)
{
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  fb_tfun *src = NULL;
  fb_mat *r = NULL;
  fb_err err;
  const size_t one[1] = {1};
  int rc = fb_bg_new("static", &bg, &err);
  if (!rc)
    rc = fb_tfun_new_sine(2.0, 3.0, 0.0, 1.0, &src, &err);
  if (!rc)
    rc = fb_bg_add_source(bg, "E", FB_BG_SE, 1, &src, &err);
  if (!rc)
    rc = fb_mat_new_scaled_identity(1, 4.0, &r, &err);
  if (!rc)
    rc = fb_bg_add_field(bg, "R", FB_BG_R, 1, one, &r, &err);
  if (!rc)
    rc = fb_bg_connect(bg, "b", "E", "R", &err);
  const fb_probe_spec probe = {"i", FB_PROBE_FLOW, "b", 0, 0, 1.0, NULL, NULL, 0};
  if (!rc)
    rc = fb_bd_build(bg, &probe, 1, &bd, &err);
  CHECK(rc == FB_OK);
  if (rc == FB_OK) {
    CHECK(fb_bd_nstates(bd) == 0);
    fb_sim_opts o;
    fb_sim_opts_default(&o);
    o.sample_rate = 100;
    fb_result *res = NULL;
    CHECK(fb_sim_run(bd, &o, &res, &err) == FB_OK);
    if (res) {
      CHECK(fb_result_nsamples(res) == 101);
      double worst = 0;
      for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
        const double *row = fb_result_row(res, k);
        const double e = 1.0 + 2.0 * sin(2 * acos(-1.0) * 3.0 * row[0]);
        worst = fmax(worst, fabs(row[1] - e / 4.0));
      }
      CHECK_NEAR(worst, 0, 1e-14); /* one division: rounding only */
      CHECK(fb_result_stats(res)->steps == 0);
      fb_result_free(&res);
    }
  }
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

int main(void)
{
  test_step_response();
  test_sampling_independent_of_steps();
  test_delayed_step();
  test_pulse_breakpoints();
  test_grid_and_x0();
  test_nonlinear_path();
  test_quadratic_damper();
  test_stiff();
  test_opts();
  test_failures();
  test_nonfinite_source();
  test_nonfinite_jacobian();
  test_nonfinite_recovered();
  test_nonfinite_static();
  test_too_short();
  test_no_states();
  return check_report("test_sim");
}
