/* SPDX-License-Identifier: BSD-3-Clause */
/* Unilateral compliant contact (fb_bg_add_unilateral_contact) and the
 * integrator's event handling (switched laws, root-finding, restarts),
 * against the closed-form impact of a mass on a Kelvin-Voigt contact that
 * cannot pull.
 *
 * A mass m flies at v0 towards a wall, with a gap g0; no gravity. On
 * touch-down (t1 = g0 / v0) the penetration is the damped oscillation
 *   q(tau) = v0 / wd e^(-s tau) sin(wd tau),  s = c / (2 m),
 *   wd = sqrt(k / m - s^2),
 * while the contact force F = k q + c q' = -m q'' is positive. It falls to
 * zero where q'' = 0, at wd tau_r = pi + atan(2 s wd / (s^2 - wd^2)),
 * before q returns to zero (Hunt & Crossley 1975). From then on the mass
 * flies freely at the release velocity q'(tau_r) < 0: the contact is
 * released (the damper cancels the spring), then separated once q = 0
 * (at tau_s = tau_r + q(tau_r) / |q'(tau_r)|). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"
#include "flexbond/sim.h"

#include "check.h"

#define MASS 1.0    /* kg */
#define STIFF 1.0e4 /* N/m: omega_n = 100 rad/s */
#define DAMP 20.0   /* N s/m: zeta = 0.1 */
#define V0 1.0      /* m/s */
#define GAP 0.01    /* m */

typedef struct impact {
  double t1, t_release, t_separate; /* s */
  double q_release, v_release;      /* m, m/s */
} impact;

static impact closed_form(void)
{
  const double s = DAMP / (2 * MASS), wd = sqrt(STIFF / MASS - s * s);
  const double tau_r = (acos(-1.0) + atan(2 * s * wd / (s * s - wd * wd))) / wd;
  impact i;
  i.t1 = GAP / V0;
  i.t_release = i.t1 + tau_r;
  i.q_release = V0 / wd * exp(-s * tau_r) * sin(wd * tau_r);
  i.v_release = V0 / wd * exp(-s * tau_r) * (wd * cos(wd * tau_r) - s * sin(wd * tau_r));
  i.t_separate = i.t_release + i.q_release / -i.v_release;
  return i;
}

/* Penetration at time t (the gap is negative). */
static double q_exact(const impact *i, double t)
{
  const double s = DAMP / (2 * MASS), wd = sqrt(STIFF / MASS - s * s);
  if (t <= i->t1)
    return -GAP + V0 * t;
  if (t <= i->t_release)
    return V0 / wd * exp(-s * (t - i->t1)) * sin(wd * (t - i->t1));
  return i->q_release + i->v_release * (t - i->t_release);
}

/* 1-junction of the mass and the contact pair: the common flow is the
 * mass's velocity towards the wall, the compression rate. The contact
 * force is minus the effort on the mass's bond. With energy_probes, the
 * energies and the damper's integrated power (a state of its own, and a
 * product that makes the diagram nonlinear). */
static int build(fb_bg **bg, fb_bd **bd, int energy_probes, double lambda, fb_err *err)
{
  const size_t one[1] = {1};
  fb_mat *m = NULL;
  *bd = NULL;
  int rc = fb_bg_new("impact", bg, err);
  if (!rc)
    rc = fb_mat_new_scaled_identity(1, MASS, &m, err);
  if (!rc)
    rc = fb_bg_add_field(*bg, "mass", FB_BG_I, 1, one, &m, err);
  if (!rc)
    rc =
        lambda > 0
            ? fb_bg_add_hunt_crossley_contact(*bg, "contact_k", "contact_c", STIFF, lambda, err)
            : fb_bg_add_unilateral_contact(*bg, "contact_k", "contact_c", STIFF, DAMP, err);
  if (!rc)
    rc = fb_bg_add_junction(*bg, "J", FB_BG_J1, 1, err);
  const double p0 = MASS * V0, q0 = -GAP;
  if (!rc)
    rc = fb_bg_set_initial(*bg, "mass", 1, &p0, err);
  if (!rc)
    rc = fb_bg_set_initial(*bg, "contact_k", 1, &q0, err);
  const char *const bonds[][3] = {
      {"bm", "J", "mass"}, {"bk", "J", "contact_k"}, {"bc", "J", "contact_c"}};
  for (size_t i = 0; !rc && i < 3; ++i)
    rc = fb_bg_connect(*bg, bonds[i][0], bonds[i][1], bonds[i][2], err);
  const fb_probe_spec probes[] = {
      {"q", FB_PROBE_STATE, "contact_k", 0, 0, 1.0, NULL, NULL, 0},
      {"v", FB_PROBE_FLOW, "bm", 0, 0, 1.0, NULL, NULL, 0},
      {"force", FB_PROBE_EFFORT, "bm", 0, 0, -1.0, "N", NULL, 0},
      {"dissipated", FB_PROBE_POWER, "bc", 0, 1, 1.0, NULL, NULL, 0},
      {"spring_energy", FB_PROBE_ENERGY, "contact_k", 0, 0, 1.0, NULL, NULL, 0},
      {"kinetic", FB_PROBE_ENERGY, "mass", 0, 0, 1.0, NULL, NULL, 0}};
  if (!rc)
    rc =
        fb_bd_build(*bg, probes, energy_probes ? sizeof probes / sizeof probes[0] : 3, bd, err);
  return rc;
}

static double col(const fb_result *r, size_t k, const char *name)
{
  return fb_result_row(r, k)[fb_result_find(r, name)];
}

/* The impact runs' settings: 0.1 s, tight tolerances, 10 kHz samples. */
static void impact_opts(fb_sim_opts *o)
{
  fb_sim_opts_default(o);
  o->t_end = 0.1;
  o->rtol = 1e-9;
  o->atol = 1e-12;
  o->sample_rate = 1e4;
}

/* Runs bd (if rc is FB_OK) with o into *res; on failure prints why and
 * frees the graph and diagram, returning 0. */
static int run_impact(int rc, const fb_sim_opts *o, fb_bg **bg, fb_bd **bd, fb_result **res)
{
  fb_err err;
  fb_err_clear(&err);
  if (rc == FB_OK)
    rc = fb_sim_run(*bd, o, res, &err);
  CHECK(rc == FB_OK);
  if (rc == FB_OK)
    return 1;
  fprintf(stderr, "%s\n", err.msg);
  fb_bd_free(bd);
  fb_bg_free(bg);
  return 0;
}

static void test_impact(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  fb_result *res = NULL;
  int rc = build(&bg, &bd, 1, 0.0, &err);
  CHECK(rc == FB_OK);
  CHECK(fb_bd_nguards(bd) == 3);
  fb_sim_opts o;
  impact_opts(&o);
  if (!run_impact(rc, &o, &bg, &bd, &res))
    return;
  const impact ex = closed_form();
  /* Touch-down, release, separation: three restarts, and only three (a
   * guard that means nothing in a mode must not stop the run). */
  CHECK(fb_result_stats(res)->events == 3);
  /* Errors. CVODE keeps each step's local error near rtol |y| + atol;
   * over this one impact (a third of a period in contact) the global error
   * stays within a few hundred rtol of the scales (v0, v0 / wn), and root
   * location adds far less. A bilateral contact (no release) would leave
   * at 0.729 instead of 0.744 m/s; a release a sample (0.1 ms) late would
   * shift the velocity by k |v_r| dt^2 / (2 m), 4e-5 m/s; both are far
   * outside 1e3 rtol v0 = 1e-6 m/s. */
  const double q_scale = V0 / sqrt(STIFF / MASS), q_tol = 1e3 * o.rtol * q_scale;
  double worst_q = 0, worst_neg = 0, worst_balance = 0, worst_released = 0;
  for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
    const double t = fb_result_row(res, k)[0];
    worst_q = fmax(worst_q, fabs(col(res, k, "q") - q_exact(&ex, t)));
    /* The wall never pulls: the force is >= 0 at every sample. */
    worst_neg = fmin(worst_neg, col(res, k, "force"));
    /* Released and separated, the force is exactly zero. */
    if (t > ex.t_release + 1e-6)
      worst_released = fmax(worst_released, fabs(col(res, k, "force")));
    /* Energy: kinetic + spring + dissipated = initial kinetic. */
    const double total =
        col(res, k, "kinetic") + col(res, k, "spring_energy") + col(res, k, "dissipated");
    worst_balance = fmax(worst_balance, fabs(total - 0.5 * MASS * V0 * V0));
  }
  CHECK_NEAR(worst_q, 0.0, q_tol);
  CHECK(worst_neg == 0.0);
  CHECK(worst_released == 0.0);
  /* 1e-6 of the impact energy: a few hundred rtol, as above. */
  CHECK_NEAR(worst_balance, 0.0, 1e-6 * 0.5 * MASS * V0 * V0);
  const size_t last = fb_result_nsamples(res) - 1;
  /* Restitution: the closed-form release velocity (e = 0.744 here). */
  CHECK_NEAR(col(res, last, "v"), ex.v_release, 1e3 * o.rtol * V0);
  /* The dissipated energy is what the restitution says. */
  CHECK_NEAR(col(res, last, "dissipated"), 0.5 * MASS * (V0 * V0 - ex.v_release * ex.v_release),
             1e-6 * 0.5 * MASS * V0 * V0);
  fprintf(stderr,
          "impact: release at %.6f s, separation at %.6f s; release velocity %.9f m/s "
          "(error %.2g); worst penetration error %.3g m; worst balance %.3g J; %ld steps\n",
          ex.t_release, ex.t_separate, ex.v_release, col(res, last, "v") - ex.v_release,
          worst_q, worst_balance, fb_result_stats(res)->steps);
  fb_result_free(&res);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* The largest |J - central differences of the right-hand side| at x,
 * relative to the largest |J| entry; the modes stay as they are. Every
 * branch is affine, so the differences are exact but for rounding. */
static double jacobian_error(fb_bd *bd, const double *x)
{
  enum { NMAX = 4 };
  const size_t n = fb_bd_nstates(bd);
  double jac[NMAX * NMAX], xp[NMAX], fp[NMAX], fm[NMAX], worst = 0.0, scale = 0.0;
  fb_err err;
  if (n > NMAX || fb_bd_jacobian_dense(bd, 0.0, x, jac, &err) != FB_OK)
    return INFINITY;
  for (size_t j = 0; j < n; ++j) {
    const double h = 1e-4 * fmax(1e-3, fabs(x[j]));
    memcpy(xp, x, n * sizeof *xp);
    xp[j] = x[j] + h;
    fb_bd_rhs(bd, 0.0, xp, fp);
    xp[j] = x[j] - h;
    fb_bd_rhs(bd, 0.0, xp, fm);
    for (size_t i = 0; i < n; ++i) {
      worst = fmax(worst, fabs(jac[j * n + i] - (fp[i] - fm[i]) / (2 * h)));
      scale = fmax(scale, fabs(jac[j * n + i]));
    }
  }
  return worst / scale;
}

/* Guard i of the element named owner (the first if several). */
static double guard_of(const fb_bd *bd, const double *g, const char *owner, size_t which)
{
  for (size_t i = 0; i < fb_bd_nguards(bd); ++i)
    if (strcmp(fb_bd_guard_element(bd, i), owner) == 0)
      return g[i + which];
  return NAN;
}

/* Each law's modes against its definition: the force, the guards and the
 * Jacobian (against central differences; 1e-8 of the largest entry is
 * rounding for h = 1e-4 of the state, while a wrong sign or a missing
 * entry is an error of order 1). */
static void test_law_branches(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  CHECK(build(&bg, &bd, 0, 0.0, &err) == FB_OK);
  /* Affine in each mode: the Newton matrix changes only at events. */
  CHECK(fb_bd_is_piecewise_linear(bd) && !fb_bd_is_linear(bd));
  const size_t n = fb_bd_nstates(bd);
  double x[2] = {0}, xdot[2], g[3];
  CHECK(n == 2 && fb_bd_nguards(bd) == 3);
  CHECK(fb_bd_guard_element(bd, 3) == NULL);
  /* States: mass p, contact_k q (diagram order). */
  const size_t ip = strcmp(fb_bd_state_name(bd, 0), "mass.p") == 0 ? 0 : 1, iq = 1 - ip;
  int changed = 0;
  /* Compressed and closing: contact, F = k q + c v. */
  x[ip] = MASS * 0.5;
  x[iq] = 0.002;
  CHECK(fb_bd_sync_modes(bd, 0.0, x, &changed) == 0 && !changed);
  CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
  CHECK_NEAR(xdot[ip], -(STIFF * 0.002 + DAMP * 0.5), 1e-12);
  CHECK(fb_bd_guards(bd, 0.0, x, g) == 0);
  CHECK(guard_of(bd, g, "contact_k", 0) == 0.002 && guard_of(bd, g, "contact_c", 0) == 0.002);
  CHECK_NEAR(guard_of(bd, g, "contact_c", 1), STIFF * 0.002 + DAMP * 0.5, 1e-12);
  CHECK_NEAR(jacobian_error(bd, x), 0.0, 1e-8);
  /* Opening fast: k q + c v < 0, released, F = 0, and the damper's
   * -k q term in the Jacobian cancels the spring's. */
  x[ip] = -MASS * 5.0;
  CHECK(fb_bd_sync_modes(bd, 0.0, x, &changed) == 0 && changed);
  CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
  CHECK(xdot[ip] == 0.0);
  CHECK(fb_bd_guards(bd, 0.0, x, g) == 0);
  CHECK_NEAR(guard_of(bd, g, "contact_c", 1), STIFF * 0.002 - DAMP * 5.0, 1e-12);
  CHECK_NEAR(jacobian_error(bd, x), 0.0, 1e-8);
  /* A gap: separated, F = 0 whatever the velocity; the damper's force
   * guard is the constant 1 there. */
  x[iq] = -0.001;
  x[ip] = MASS * 3.0;
  CHECK(fb_bd_sync_modes(bd, 0.0, x, &changed) == 0 && changed);
  CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
  CHECK(xdot[ip] == 0.0);
  CHECK(fb_bd_guards(bd, 0.0, x, g) == 0);
  CHECK(guard_of(bd, g, "contact_k", 0) == -0.001 && guard_of(bd, g, "contact_c", 1) == 1.0);
  CHECK_NEAR(jacobian_error(bd, x), 0.0, 1e-8);
  /* Crossings decide by direction, not by the value at the root: q
   * crossing upwards (touch-down) while numerically still -1e-18. */
  x[iq] = -1e-18;
  int crossed[3] = {0};
  for (size_t i = 0; i < 3; ++i)
    crossed[i] = strcmp(fb_bd_guard_element(bd, i), "contact_k") == 0 || i == 1 ? 1 : 0;
  CHECK(fb_bd_switch_modes(bd, 0.0, x, crossed, &changed) == 0 && changed);
  x[iq] = 1e-4;
  CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
  CHECK_NEAR(xdot[ip], -(STIFF * 1e-4 + DAMP * 3.0), 1e-12);
  /* A guard exactly zero takes the sign it has just after: at q = 0
   * opening (v < 0) the contact is separated, closing it is in contact. */
  x[iq] = 0.0;
  x[ip] = -MASS * 1.0;
  CHECK(fb_bd_sync_modes(bd, 0.0, x, &changed) == 0 && changed);
  CHECK(fb_bd_guards(bd, 0.0, x, g) == 0 && guard_of(bd, g, "contact_c", 1) == 1.0);
  x[ip] = MASS * 1.0;
  CHECK(fb_bd_sync_modes(bd, 0.0, x, &changed) == 0 && changed);
  x[iq] = 1e-4;
  CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
  CHECK_NEAR(xdot[ip], -(STIFF * 1e-4 + DAMP * 1.0), 1e-12);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* ---- Hunt-Crossley damping: F = k q + lambda q q' (n = 1).
 *
 * The same impact with the damping lambda q. In contact m v' = -(k +
 * lambda v) q with v = q', so m v dv / (k + lambda v) = -q dq, which
 * integrates from touch-down (q = 0, v = v0) to the phase-plane invariant
 *   q^2 = (2 m / lambda) [(v0 - v) - (k / lambda) ln((k + lambda v0) / (k + lambda v))]
 * (Hunt & Crossley 1975; Marhefka & Orin, IEEE Trans. SMC-A 29(6), 1999).
 * At v = 0 it gives the deepest penetration; at q = 0 again the exit
 * velocity, the root in (-k / lambda, 0) of the bracket. The force k q +
 * lambda q v = q (k + lambda v) stays >= 0 all along (v > -k / lambda),
 * so the contact is never released: it ends at q = 0 with zero force,
 * and starts there with zero force too, where the Kelvin-Voigt damper
 * jumps to c v0. */
#define LAMBDA 5.0e3 /* N s/m^2: lambda v0 / k = 0.5 */

static double hc_bracket(double v)
{
  return (V0 - v) - STIFF / LAMBDA * log((STIFF + LAMBDA * V0) / (STIFF + LAMBDA * v));
}

/* The exit velocity, by bisection of the bracket (negative at -k/lambda,
 * positive at 0). */
static double hc_exit_velocity(void)
{
  double lo = -STIFF / LAMBDA * (1 - 1e-15), hi = 0.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (hc_bracket(mid) < 0)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

static void test_hunt_crossley_impact(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  fb_result *res = NULL;
  int rc = build(&bg, &bd, 1, LAMBDA, &err);
  CHECK(rc == FB_OK);
  fb_bg_contact contact;
  CHECK(rc == FB_OK &&
        fb_bg_element_contact(bg, (size_t)fb_bg_find_element(bg, "contact_c"), &contact) &&
        contact.lambda == LAMBDA && contact.c == 0.0 && contact.k == STIFF);
  /* Not affine in contact: the Newton matrix follows q and v. The force
   * and the Jacobian (central differences are exact for the bilinear
   * term, as in test_law_branches) at q = 2 mm closing at 0.5 m/s. */
  CHECK(rc == FB_OK && !fb_bd_is_piecewise_linear(bd));
  double x[4] = {0}, xdot[4];
  long ip = -1, iq = -1;
  for (size_t i = 0; rc == FB_OK && i < fb_bd_nstates(bd) && i < 4; ++i) {
    ip = strcmp(fb_bd_state_name(bd, i), "mass.p") == 0 ? (long)i : ip;
    iq = strcmp(fb_bd_state_name(bd, i), "contact_k.q") == 0 ? (long)i : iq;
  }
  CHECK(ip >= 0 && iq >= 0);
  if (ip >= 0 && iq >= 0) {
    int changed = 0;
    x[ip] = MASS * 0.5;
    x[iq] = 0.002;
    CHECK(fb_bd_sync_modes(bd, 0.0, x, &changed) == 0);
    CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
    CHECK_NEAR(xdot[ip], -(STIFF * 0.002 + LAMBDA * 0.002 * 0.5), 1e-12);
    CHECK_NEAR(jacobian_error(bd, x), 0.0, 1e-8);
  }
  fb_sim_opts o;
  impact_opts(&o);
  if (!run_impact(rc, &o, &bg, &bd, &res))
    return;
  const double v_exit = hc_exit_velocity(); /* < 0: away from the wall */
  const double q_max =
      sqrt(2 * MASS / LAMBDA * (V0 - STIFF / LAMBDA * log(1 + LAMBDA * V0 / STIFF)));
  double worst_invariant = 0, deepest = 0, worst_neg = 0, first_force = NAN, worst_balance = 0;
  for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
    const double q = col(res, k, "q"), v = col(res, k, "v"), force = col(res, k, "force");
    worst_neg = fmin(worst_neg, force);
    if (q > 0) {
      worst_invariant = fmax(worst_invariant, fabs(q * q - 2 * MASS / LAMBDA * hc_bracket(v)));
      deepest = fmax(deepest, q);
      if (isnan(first_force))
        first_force = force;
    }
    const double total =
        col(res, k, "kinetic") + col(res, k, "spring_energy") + col(res, k, "dissipated");
    worst_balance = fmax(worst_balance, fabs(total - 0.5 * MASS * V0 * V0));
  }
  /* Tolerances as in test_impact: a few hundred rtol of the scales
   * (q_max^2 for the invariant; v0 for the velocity). The deepest sample
   * lies within half a sample (50 us) of the true maximum, where q' = 0:
   * q_max - q < k q_max (50 us)^2 / (2 m) = 1e-7 m. */
  CHECK_NEAR(worst_invariant, 0.0, 1e3 * o.rtol * q_max * q_max);
  CHECK(deepest <= q_max * (1 + 1e3 * o.rtol) && deepest > q_max - 1e-7);
  CHECK(worst_neg == 0.0);
  CHECK_NEAR(worst_balance, 0.0, 1e-6 * 0.5 * MASS * V0 * V0);
  const size_t last = fb_result_nsamples(res) - 1;
  CHECK_NEAR(col(res, last, "v"), v_exit, 1e3 * o.rtol * V0);
  /* The first sample in contact (within 0.1 ms of touch-down, q < 1e-4 m)
   * carries at most q (k + lambda v0) = 1.5 N, where the Kelvin-Voigt
   * damper of test_impact starts at c v0 = 20 N. */
  CHECK(first_force >= 0.0 && first_force <= 1e-4 * (STIFF + LAMBDA * V0));
  fprintf(stderr,
          "Hunt-Crossley impact: deepest %.9f m (closed form %.9f), exit velocity %.9f m/s "
          "(closed form %.9f, restitution %.4f), worst invariant error %.3g m^2, first force "
          "%.3g N\n",
          deepest, q_max, col(res, last, "v"), v_exit, -v_exit / V0, worst_invariant,
          first_force);
  fb_result_free(&res);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* Samples of column name of r. */
static double sample(const fb_result *r, size_t k, const char *name)
{
  return fb_result_row(r, k)[fb_result_find(r, name)];
}

/* A wheel (1 kg, 10 N weight) resting on the contact, whose road drops
 * away at 2 m/s from t_drop: an input jump at a breakpoint that turns
 * k q + c f from +10 N to -30 N with no crossing to locate. The contact
 * must release at once (the restart re-chooses the modes), and the wheel
 * falls freely, q = q0 - 2 s + 5 s^2 (s = t - t_drop): it separates at
 * s = (2 - sqrt(4 - 20 q0)) / 10 and lands again at s = (2 + sqrt(4 -
 * 20 q0)) / 10 = 0.3995 s. */
static void test_road_drop(void)
{
  const size_t one[1] = {1};
  const double q0 = 1e-3, t_drop = 0.3005; /* k q0 = the weight */
  const double t_land = t_drop + (2.0 + sqrt(4.0 - 20.0 * q0)) / 10.0;
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  fb_mat *m = NULL;
  fb_tfun *weight = NULL, *road = NULL;
  int rc = fb_bg_new("drop", &bg, &err);
  if (!rc)
    rc = fb_mat_new_scaled_identity(1, 1.0, &m, &err);
  if (!rc)
    rc = fb_bg_add_field(bg, "wheel", FB_BG_I, 1, one, &m, &err);
  if (!rc)
    rc = fb_bg_add_unilateral_contact(bg, "tire_k", "tire_c", 1e4, 20.0, &err);
  if (!rc)
    rc = fb_tfun_new_const(-10.0, &weight, &err);
  if (!rc)
    rc = fb_bg_add_source(bg, "weight", FB_BG_SE, 1, &weight, &err);
  if (!rc)
    rc = fb_tfun_new_step(t_drop, 0.0, -2.0, &road, &err);
  if (!rc)
    rc = fb_bg_add_source(bg, "road", FB_BG_SF, 1, &road, &err);
  const char *const junctions[][2] = {{"Jw", "1"}, {"tire", "0"}, {"Jt", "1"}};
  for (size_t i = 0; !rc && i < 3; ++i)
    rc = fb_bg_add_junction(bg, junctions[i][0],
                            junctions[i][1][0] == '0' ? FB_BG_J0 : FB_BG_J1, 1, &err);
  if (!rc)
    rc = fb_bg_set_initial(bg, "tire_k", 1, &q0, &err);
  const char *const bonds[][3] = {{"b_wheel", "Jw", "wheel"}, {"b_weight", "weight", "Jw"},
                                  {"b_road", "road", "tire"}, {"b_contact", "tire", "Jw"},
                                  {"b_tire", "tire", "Jt"},   {"bk", "Jt", "tire_k"},
                                  {"bc", "Jt", "tire_c"}};
  for (size_t i = 0; !rc && i < 7; ++i)
    rc = fb_bg_connect(bg, bonds[i][0], bonds[i][1], bonds[i][2], &err);
  const fb_probe_spec probes[] = {
      {"force", FB_PROBE_EFFORT, "b_tire", 0, 0, 1.0, NULL, NULL, 0}};
  if (!rc)
    rc = fb_bd_build(bg, probes, 1, &bd, &err);
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 1.0;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  o.sample_rate = 1e4;
  fb_result *r = NULL;
  if (!rc)
    rc = fb_sim_run(bd, &o, &r, &err);
  CHECK(rc == FB_OK);
  if (rc) {
    fprintf(stderr, "road drop: %s\n", err.msg);
  } else {
    double lowest = INFINITY, t_first_load = NAN;
    size_t loaded_in_flight = 0;
    for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
      const double t = fb_result_row(r, k)[0], f = sample(r, k, "force");
      lowest = fmin(lowest, f);
      /* Released, then separated: no load at all. */
      loaded_in_flight += t >= t_drop && t < t_drop + 0.3 && f != 0.0;
      if (t > t_drop && f > 0.0 && isnan(t_first_load))
        t_first_load = t;
    }
    CHECK(lowest == 0.0 && loaded_in_flight == 0);
    /* Landing: the first loaded sample is the first after the closed-form
     * landing (samples every 0.1 ms). */
    CHECK(t_first_load >= t_land && t_first_load < t_land + 1e-4 + 1e-9);
    /* Release at the breakpoint, separation, landing, and the rebounds. */
    CHECK(fb_result_stats(r)->events >= 3);
    fprintf(stderr, "road drop: landing at %.6f s (closed form %.6f), %ld events\n",
            t_first_load, t_land, fb_result_stats(r)->events);
  }
  fb_result_free(&r);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* The run starts at q = 0 exactly with the mass moving away at 0.5 m/s
 * (a vehicle's zero start is q = 0 too), pushed back by 1 N: the contact
 * must start separated, so spring and damper both stay unloaded while the
 * mass flies out and back, q = -0.5 t + 0.5 t^2, and it lands at t = 1 s.
 * A spring started in its contact branch would hold k q < 0 across the
 * gap, cancelled by a released damper (a net force of zero, but a spring
 * pulling and a damper delivering power). */
static void test_start_at_zero_opening(void)
{
  const size_t one[1] = {1};
  const double p0 = -MASS * 0.5, q0 = 0.0, t_land = 1.0;
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  fb_result *r = NULL;
  fb_mat *m = NULL;
  fb_tfun *push = NULL;
  int rc = fb_bg_new("opening", &bg, &err);
  if (!rc)
    rc = fb_mat_new_scaled_identity(1, MASS, &m, &err);
  if (!rc)
    rc = fb_bg_add_field(bg, "mass", FB_BG_I, 1, one, &m, &err);
  if (!rc)
    rc = fb_bg_add_unilateral_contact(bg, "contact_k", "contact_c", STIFF, DAMP, &err);
  if (!rc)
    rc = fb_tfun_new_const(1.0, &push, &err);
  if (!rc)
    rc = fb_bg_add_source(bg, "push", FB_BG_SE, 1, &push, &err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "J", FB_BG_J1, 1, &err);
  if (!rc)
    rc = fb_bg_set_initial(bg, "mass", 1, &p0, &err);
  if (!rc)
    rc = fb_bg_set_initial(bg, "contact_k", 1, &q0, &err);
  const char *const bonds[][3] = {{"bp", "push", "J"},
                                  {"bm", "J", "mass"},
                                  {"bk", "J", "contact_k"},
                                  {"bc", "J", "contact_c"}};
  for (size_t i = 0; !rc && i < 4; ++i)
    rc = fb_bg_connect(bg, bonds[i][0], bonds[i][1], bonds[i][2], &err);
  const fb_probe_spec probes[] = {{"q", FB_PROBE_STATE, "contact_k", 0, 0, 1.0, NULL, NULL, 0},
                                  {"force", FB_PROBE_EFFORT, "bk", 0, 0, 1.0, NULL, NULL, 0},
                                  {"damper", FB_PROBE_EFFORT, "bc", 0, 0, 1.0, NULL, NULL, 0}};
  if (!rc)
    rc = fb_bd_build(bg, probes, 3, &bd, &err);
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 1.2;
  o.sample_rate = 1e4;
  if (!rc)
    rc = fb_sim_run(bd, &o, &r, &err);
  CHECK(rc == FB_OK);
  double lowest = INFINITY, worst_q = 0.0, t_first_load = NAN;
  size_t loaded_in_flight = 0;
  for (size_t k = 0; r && k < fb_result_nsamples(r); ++k) {
    const double t = fb_result_row(r, k)[0];
    const double f = sample(r, k, "force") + sample(r, k, "damper");
    lowest = fmin(lowest, f);
    if (t < t_land) {
      worst_q = fmax(worst_q, fabs(sample(r, k, "q") - (-0.5 * t + 0.5 * t * t)));
      loaded_in_flight += sample(r, k, "force") != 0.0 || sample(r, k, "damper") != 0.0;
    }
    if (f > 0.0 && isnan(t_first_load))
      t_first_load = t;
  }
  CHECK(lowest == 0.0 && loaded_in_flight == 0);
  /* Free flight: BDF integrates the parabola exactly but for rounding and
   * the error control's scale (1e3 rtol of the 0.125 m excursion). */
  CHECK_NEAR(worst_q, 0.0, 1e3 * o.rtol * 0.125);
  CHECK(t_first_load >= t_land && t_first_load < t_land + 1e-4 + 1e-9);
  fb_result_free(&r);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

static void test_bad_parameters(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  CHECK(fb_bg_new("bad", &bg, &err) == FB_OK);
  CHECK(fb_bg_add_unilateral_contact(bg, "k", "c", 0.0, 1.0, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "stiffness") != NULL);
  CHECK(fb_bg_add_unilateral_contact(bg, "k", "c", 1.0, NAN, &err) == FB_EINVAL);
  CHECK(fb_bg_add_unilateral_contact(bg, "k", "c", 1.0, -1.0, &err) == FB_EINVAL);
  /* Only a nonlinear R can be modulated, only by storage elements. */
  CHECK(fb_bg_add_unilateral_contact(bg, "k", "c", 1.0, 1.0, &err) == FB_OK);
  const char *src = "c";
  CHECK(fb_bg_modulate(bg, "k", 1, &src, &err) == FB_EMODEL);
  src = "k";
  CHECK(fb_bg_modulate(bg, "c", 1, &src, &err) == FB_EMODEL); /* already modulated */
  CHECK(strstr(err.msg, "already") != NULL);
  /* Names are checked before anything is added. */
  CHECK(fb_bg_add_unilateral_contact(bg, "k2", "k", 1.0, 1.0, &err) == FB_EMODEL);
  CHECK(fb_bg_find_element(bg, "k2") < 0);
  CHECK(fb_bg_add_unilateral_contact(bg, "k3", "k3", 1.0, 1.0, &err) == FB_EMODEL);
  CHECK(fb_bg_add_unilateral_contact(bg, "k4", "a.b", 1.0, 1.0, &err) == FB_EMODEL);
  CHECK(fb_bg_find_element(bg, "k3") < 0 && fb_bg_find_element(bg, "k4") < 0);
  CHECK(fb_bg_add_hunt_crossley_contact(bg, "h", "hc", 1.0, -1.0, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "damping per penetration") != NULL);
  CHECK(fb_bg_add_hunt_crossley_contact(bg, "h", "hc", INFINITY, 1.0, &err) == FB_EINVAL);
  CHECK(fb_bg_add_hunt_crossley_contact(bg, "h", "k", 1.0, 1.0, &err) == FB_EMODEL);
  CHECK(fb_bg_find_element(bg, "h") < 0);
  fb_bg_free(&bg);
}

int main(void)
{
  test_impact();
  test_law_branches();
  test_hunt_crossley_impact();
  test_road_drop();
  test_start_at_zero_opening();
  test_bad_parameters();
  return check_report("test_contact_law");
}
