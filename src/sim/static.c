/* Static equilibrium of a mechanical block diagram (see flexbond/sim.h).
 *
 * With momenta p (I states), displacements q (C states) and inputs held at
 * time t, rest means p = 0 and p' = F_p(q) = 0. Starting from x0, the
 * displacements can only move along what the flows integrate to:
 * q = q0 + (dF_q/dp) P for some "impulse" vector P (for x0 = 0 this keeps
 * the self-stress of a statically indeterminate support at zero, as the
 * settling from rest does). Newton on P:
 *   (dF_p/dq dF_q/dp) dP = -(F_p(x) - dF_p/dp p), then p = 0. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/sim.h"

typedef struct static_work {
  size_t n, np;
  size_t *pidx;    /* momentum state indices */
  double *jac, *f; /* n x n Jacobian, n right-hand side */
  double *a, *rhs; /* np x np system */
  lapack_int *piv;
} static_work;

static void work_free(static_work *w)
{
  free(w->pidx);
  free(w->jac);
  free(w->f);
  free(w->a);
  free(w->rhs);
  free(w->piv);
}

static int work_alloc(static_work *w, const fb_bd *bd)
{
  memset(w, 0, sizeof *w);
  w->n = fb_bd_nstates(bd);
  w->pidx = malloc((w->n + 1) * sizeof *w->pidx);
  for (size_t i = 0; w->pidx && i < w->n; ++i)
    if (fb_bd_state_kind(bd, i) == FB_STATE_MOMENTUM)
      w->pidx[w->np++] = i;
  w->jac = malloc((w->n * w->n + 1) * sizeof *w->jac);
  w->f = malloc((w->n + 1) * sizeof *w->f);
  w->a = malloc((w->np * w->np + 1) * sizeof *w->a);
  w->rhs = malloc((w->np + 1) * sizeof *w->rhs);
  w->piv = malloc((w->np + 1) * sizeof *w->piv);
  return w->pidx && w->jac && w->f && w->a && w->rhs && w->piv ? FB_OK : FB_ENOMEM;
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

/* One Newton step from x (updated in place). */
static int newton_step(fb_bd *bd, double t, static_work *w, double *x, fb_err *err)
{
  size_t n = w->n, np = w->np;
  int rc = fb_bd_jacobian_dense(bd, t, x, w->jac, err);
  if (rc)
    return rc;
  if (fb_bd_rhs(bd, t, x, w->f))
    return fb_err_set(err, FB_ESOLVER, "static equilibrium: %s", fb_bd_last_error(bd));
  /* a = J_pq J_qp over the displacement states q; rhs = -(F_p - J_pp p). */
  for (size_t c = 0; c < np; ++c)
    for (size_t r = 0; r < np; ++r) {
      double s = 0.0;
      for (size_t q = 0; q < n; ++q)
        if (fb_bd_state_kind(bd, q) == FB_STATE_DISPLACEMENT)
          s += w->jac[q * n + w->pidx[r]] * w->jac[w->pidx[c] * n + q];
      w->a[c * np + r] = s;
    }
  for (size_t r = 0; r < np; ++r) {
    double s = w->f[w->pidx[r]];
    for (size_t c = 0; c < np; ++c)
      s -= w->jac[w->pidx[c] * n + w->pidx[r]] * x[w->pidx[c]];
    w->rhs[r] = -s;
  }
  lapack_int info = LAPACKE_dgesv(LAPACK_COL_MAJOR, (lapack_int)np, 1, w->a, (lapack_int)np,
                                  w->piv, w->rhs, (lapack_int)np);
  if (info != 0)
    return fb_err_set(err, FB_ESOLVER,
                      "static equilibrium: the stiffness seen by the masses is singular (a "
                      "mass with no spring to the ground, or a free rigid-body mode)");
  /* q += J_qp dP; p = 0. */
  for (size_t q = 0; q < n; ++q)
    if (fb_bd_state_kind(bd, q) == FB_STATE_DISPLACEMENT)
      for (size_t c = 0; c < np; ++c)
        x[q] += w->jac[w->pidx[c] * n + q] * w->rhs[c];
  for (size_t c = 0; c < np; ++c)
    x[w->pidx[c]] = 0.0;
  return FB_OK;
}

int fb_sim_static_state(fb_bd *bd, double t, const double *x0, double *x_eq, fb_err *err)
{
  static_work w;
  if (work_alloc(&w, bd)) {
    work_free(&w);
    return fb_err_set(err, FB_ENOMEM, "out of memory computing the static equilibrium");
  }
  memcpy(x_eq, x0, w.n * sizeof *x0);
  double rp0 = 0.0, rq0 = 0.0, rp = 0.0, rq = 0.0;
  int rc = FB_OK;
  if (fb_bd_rhs(bd, t, x_eq, w.f))
    rc = fb_err_set(err, FB_ESOLVER, "static equilibrium: %s", fb_bd_last_error(bd));
  else
    residuals(bd, w.f, w.n, &rp0, &rq0);
  /* Force balance to 1e-10 of the largest initial unbalanced force (linear
   * diagrams converge in one step; a second confirms). */
  const double tol = 1e-10 * fmax(rp0, 1.0);
  for (int iter = 0; !rc && iter < 20; ++iter) {
    rc = newton_step(bd, t, &w, x_eq, err);
    if (!rc && fb_bd_rhs(bd, t, x_eq, w.f))
      rc = fb_err_set(err, FB_ESOLVER, "static equilibrium: %s", fb_bd_last_error(bd));
    if (!rc) {
      residuals(bd, w.f, w.n, &rp, &rq);
      if (rp <= tol)
        break;
    }
  }
  if (!rc && rp > tol)
    rc = fb_err_set(err, FB_ESOLVER,
                    "static equilibrium not found: unbalanced force %.3g after 20 Newton steps",
                    rp);
  if (!rc && rq > 1e-10 * fmax(rq0, 1.0) && rq > 1e-12)
    rc = fb_err_set(err, FB_ESOLVER,
                    "no static equilibrium at t = %g s: displacements still change at rest "
                    "(%.3g per s); are flow sources at rest then?",
                    t, rq);
  work_free(&w);
  return rc;
}
