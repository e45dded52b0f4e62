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
static int build(fb_bg **bg, fb_bd **bd, int energy_probes, fb_err *err)
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
    rc = fb_bg_add_unilateral_contact(*bg, "contact_k", "contact_c", STIFF, DAMP, err);
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

static void test_impact(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  fb_result *res = NULL;
  int rc = build(&bg, &bd, 1, &err);
  CHECK(rc == FB_OK);
  CHECK(fb_bd_nguards(bd) == 3);
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 0.1;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  o.sample_rate = 1e4;
  if (rc == FB_OK)
    rc = fb_sim_run(bd, &o, &res, &err);
  CHECK(rc == FB_OK);
  if (rc != FB_OK) {
    fprintf(stderr, "%s\n", err.msg);
    fb_bd_free(&bd);
    fb_bg_free(&bg);
    return;
  }
  const impact ex = closed_form();
  /* Touch-down, release, separation: three restarts, and only three (a
   * guard that means nothing in a mode must not stop the run). */
  CHECK(fb_result_stats(res)->events == 3);
  /* Errors. CVODE keeps each step's local error near rtol |y| + atol;
   * over this one impact (a third of a period in contact) the global error
   * stays within a few hundred rtol of the scales (v0, v0 / wn), and root
   * location adds far less. A restitution off by a wrong release time (a
   * sample's 0.1 ms) or a released contact that pulled would be off by 1e-2
   * or more. */
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
  /* Restitution: the closed-form release velocity (e = 0.7 here). */
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

/* Each law's modes against its definition. */
static void test_law_branches(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  CHECK(build(&bg, &bd, 0, &err) == FB_OK);
  /* Affine in each mode: the Newton matrix changes only at events. */
  CHECK(fb_bd_is_piecewise_linear(bd) && !fb_bd_is_linear(bd));
  const size_t n = fb_bd_nstates(bd);
  double x[8] = {0}, xdot[8], g[3];
  CHECK(n == 2);
  /* States: mass p, contact_k q (diagram order). */
  const size_t ip = strcmp(fb_bd_state_name(bd, 0), "mass.p") == 0 ? 0 : 1, iq = 1 - ip;
  int changed = 0;
  /* Compressed and closing: contact, F = k q + c v. */
  x[ip] = MASS * 0.5;
  x[iq] = 0.002;
  CHECK(fb_bd_init_modes(bd, 0.0, x, &changed) == 0);
  CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
  CHECK_NEAR(xdot[ip], -(STIFF * 0.002 + DAMP * 0.5), 1e-12);
  CHECK(fb_bd_guards(bd, 0.0, x, g) == 0);
  /* Opening fast: k q + c v < 0, released, F = 0. */
  x[ip] = -MASS * 5.0;
  CHECK(fb_bd_init_modes(bd, 0.0, x, &changed) == 0 && changed);
  CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
  CHECK(xdot[ip] == 0.0);
  /* A gap: separated, F = 0 whatever the velocity. */
  x[iq] = -0.001;
  x[ip] = MASS * 3.0;
  CHECK(fb_bd_init_modes(bd, 0.0, x, &changed) == 0 && changed);
  CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
  CHECK(xdot[ip] == 0.0);
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
  fb_bg_free(&bg);
}

int main(void)
{
  test_impact();
  test_law_branches();
  test_bad_parameters();
  return check_report("test_contact_law");
}
