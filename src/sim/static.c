/* SPDX-License-Identifier: BSD-3-Clause */
/* Static equilibrium of a mechanical block diagram (see flexbond/sim.h)
 * by pseudo-transient continuation (Kelley & Keyes, "Convergence analysis
 * of pseudo-transient continuation", SIAM J. Numer. Anal. 35(2), 1998):
 * implicit Euler steps of growing length h on x' = F(x) from rest,
 *   (I - h J(x_k)) dx = h F(x_k),  x_{k+1} = x_k + dx,  then p = 0,
 * with the integrator's own sparse Newton solver (the augmented matrix,
 * auglin.h), so a finite-element structure costs one sparse
 * factorisation per step and no dense matrix.
 *
 * Clearing the momenta after each step (kinetic damping, as in dynamic
 * relaxation) makes a linear mechanical step q <- q + (M/h^2 + B/h +
 * K)^-1 (f - K q): the error left is (M/h^2 + B/h + K)^-1 (M/h^2 + B/h)
 * times the previous one, a factor ~1 / (h omega)^2 for a mode of
 * frequency omega, damped or not. With h of 10^3 s and more every mode
 * above ~0.01 Hz is gone in a few steps. Directions without stiffness are
 * left alone: the free rigid-body motions no force drives (a hull's
 * surge, sway and yaw on vertical springs) and the self-stress of a
 * statically indeterminate support. Like the paper's settling from rest,
 * the equilibrium reached is the one in x0 + span of what the dynamics
 * can move, and free motions neither make the matrix singular nor
 * wander. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/sim.h"

#include "sim/auglin.h"
#include "sim/sim_internal.h"

/* First pseudo time step and its growth per iteration, s. The cap keeps
 * I - h J away from the conditioning of J itself, and round-off from
 * growing along free rigid-body motions (a Jordan block of lambda = 0,
 * which a step multiplies by h / m). A structure with free motions and
 * a stiff mesh can reach that conditioning below the cap: its matrix is
 * then M / h^2 + K along directions of K's null space, whose pivots
 * shrink as 1 / h^2 against K's largest (the Newton solver's pivot ratio
 * falls below its singularity threshold; where it does depends on the
 * pivot order's rounding, so on the machine). Such a step is taken again
 * H_GROWTH times shorter, and that length becomes the cap (the step-length
 * control of pseudo-transient continuation; Kelley & Keyes, sec. 2). */
#define H_FIRST 1e3
#define H_GROWTH 10.0
#define H_MAX 1e5
#define MAX_ITER 50

typedef struct static_work {
  size_t n;
  double *f, *dx, *v0, *v1;
  fb_auglin *lin;
  int unfactored; /* 1: the last step's matrix was refused as singular */
} static_work;

static void work_free(static_work *w)
{
  free(w->f);
  free(w->dx);
  free(w->v0);
  free(w->v1);
  fb_auglin_free(&w->lin);
}

static int work_alloc(static_work *w, fb_bd *bd, fb_err *err)
{
  memset(w, 0, sizeof *w);
  w->n = fb_bd_nstates(bd);
  const size_t nnz = fb_bd_aug_nnz(bd) ? fb_bd_aug_nnz(bd) : 1;
  w->f = malloc((w->n + 1) * sizeof *w->f);
  w->dx = malloc((w->n + 1) * sizeof *w->dx);
  w->v0 = malloc(nnz * sizeof *w->v0);
  w->v1 = malloc(nnz * sizeof *w->v1);
  if (!w->f || !w->dx || !w->v0 || !w->v1)
    return fb_err_set(err, FB_ENOMEM, "out of memory computing the static equilibrium");
  return fb_auglin_new_bd(bd, &w->lin, err);
}

/* Largest |F_p| and |F_q| at x (momentum and displacement rows). */
static void residuals(const fb_bd *bd, const double *f, size_t n, double *rp, double *rq)
{
  *rp = *rq = 0.0;
  for (size_t i = 0; i < n; ++i) {
    fb_state_kind k = fb_bd_state_kind(bd, i);
    if (k == FB_STATE_MOMENTUM)
      *rp = fmax(*rp, fabs(f[i]));
    else if (k == FB_STATE_DISPLACEMENT)
      *rq = fmax(*rq, fabs(f[i]));
  }
}

/* F(t, x) into f, which must be finite: residuals() takes maxima with
 * fmax, which drops a NaN, so one would pass for a balance. */
static int eval_rhs(fb_bd *bd, double t, const double *x, double *f, fb_err *err)
{
  if (fb_bd_rhs(bd, t, x, f))
    return fb_err_set(err, FB_ESOLVER, "static equilibrium: %s", fb_bd_last_error(bd));
  const size_t n = fb_bd_nstates(bd), bad = fb_first_nonfinite(f, n);
  if (bad == n)
    return FB_OK;
  char what[300], msg[FB_SIM_NONFINITE_MAX];
  snprintf(what, sizeof what, "the derivative of state %s is %g", fb_bd_state_name(bd, bad),
           fb_printable(f[bad]));
  fb_sim_explain_nonfinite(bd, t, x, 0, what, msg, sizeof msg);
  return fb_err_set(err, FB_ESOLVER, "static equilibrium at t = %g s: %s", t, msg);
}

/* One implicit Euler step of length h from x (in place), ending at rest:
 * the momenta left after a long step are round-off (and zero at the
 * equilibrium), so they are cleared, as dynamic relaxation with kinetic
 * damping does. Probe integrals are measurements, not part of the
 * equilibrium, and stay as they are. */
static int pseudo_step(fb_bd *bd, double t, double h, static_work *w, double *x, fb_err *err)
{
  w->unfactored = 0;
  if (fb_bd_aug_values(bd, t, x, w->v0, w->v1))
    return fb_err_set(err, FB_ESOLVER, "static equilibrium: %s", fb_bd_last_error(bd));
  const size_t nnz = fb_bd_aug_nnz(bd);
  if (fb_first_nonfinite(w->v0, nnz) < nnz || fb_first_nonfinite(w->v1, nnz) < nnz) {
    char msg[FB_SIM_NONFINITE_MAX];
    fb_sim_explain_nonfinite(bd, t, x, 1, "the Newton matrix is not finite", msg, sizeof msg);
    return fb_err_set(err, FB_ESOLVER, "static equilibrium at t = %g s: %s", t, msg);
  }
  int rc = fb_auglin_setup(w->lin, h, w->v0, w->v1, err);
  w->unfactored = rc == FB_ESOLVER;
  for (size_t i = 0; rc == FB_OK && i < w->n; ++i)
    w->dx[i] = h * w->f[i];
  if (rc == FB_OK)
    rc = fb_auglin_solve(w->lin, w->dx, w->dx, err);
  for (size_t i = 0; rc == FB_OK && i < w->n; ++i) {
    const fb_state_kind kind = fb_bd_state_kind(bd, i);
    if (kind == FB_STATE_MOMENTUM)
      x[i] = 0.0;
    else if (kind == FB_STATE_DISPLACEMENT)
      x[i] += w->dx[i];
  }
  return rc;
}

int fb_sim_static_state(fb_bd *bd, double t, const double *x0, double *x_eq, fb_err *err)
{
  static_work w;
  int rc = work_alloc(&w, bd, err);
  if (rc) {
    work_free(&w);
    if (rc != FB_ENOMEM)
      fb_err_prefix(err, "static equilibrium: ");
    return rc;
  }
  memcpy(x_eq, x0, w.n * sizeof *x0);
  double rp0 = 0.0, rq0 = 0.0, rp = 0.0, rq = 0.0;
  rc = eval_rhs(bd, t, x_eq, w.f, err);
  if (!rc)
    residuals(bd, w.f, w.n, &rp0, &rq0);
  /* Force balance to 1e-10 of the largest initial unbalanced force, and
   * rest: displacement rates 1e-10 of their initial size (or 1e-12). A
   * stiff structure cannot always get there: its internal forces K q
   * carry a rounding error of eps cond(K) |K q| (about 5e-8 of the load
   * for a hull of E x 1000), so once the steps are at their longest and
   * the force has stopped falling, a balance within 1e-7 of the initial
   * unbalance is that rounding floor and accepted. */
  const double tol_p = 1e-10 * fmax(rp0, 1.0), tol_q = fmax(1e-10 * rq0, 1e-12);
  const double floor_p = 1e-7 * fmax(rp0, 1.0);
  double h = H_FIRST, h_max = H_MAX, rp_prev = INFINITY;
  for (int iter = 0; !rc && iter < MAX_ITER; ++iter) {
    rc = pseudo_step(bd, t, h, &w, x_eq, err);
    if (rc == FB_ESOLVER && w.unfactored && h > H_FIRST) {
      /* x_eq is as before the step: the matrix was refused. */
      h_max = h = h / H_GROWTH;
      fb_err_clear(err);
      rc = FB_OK;
      continue;
    }
    if (!rc)
      rc = eval_rhs(bd, t, x_eq, w.f, err);
    if (rc)
      break;
    residuals(bd, w.f, w.n, &rp, &rq);
    const int stalled = h == h_max && rp >= 0.5 * rp_prev;
    if (rq <= tol_q && (rp <= tol_p || (stalled && rp <= floor_p)))
      break;
    rp_prev = rp;
    h = fmin(h * H_GROWTH, h_max);
  }
  const int verdict = !rc && (rq > tol_q || (rp > tol_p && rp > floor_p));
  if (!rc && rq > tol_q)
    rc = fb_err_set(err, FB_ESOLVER,
                    "no static equilibrium at t = %g s: displacements still change at rest "
                    "(%.3g per s); are flow sources at rest then?",
                    t, rq);
  if (!rc && rp > tol_p && rp > floor_p)
    rc = fb_err_set(err, FB_ESOLVER,
                    "static equilibrium not found: unbalanced force %.3g after %d steps "
                    "(a mass with no spring to the ground, or no equilibrium at all?)",
                    rp, MAX_ITER);
  /* The solver's own failures get the context; the two verdicts above
   * name it already. */
  if (rc == FB_ESOLVER && !verdict)
    fb_err_prefix(err, "static equilibrium: ");
  work_free(&w);
  return rc;
}
