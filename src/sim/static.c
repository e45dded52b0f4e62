/* Static equilibrium of a mechanical block diagram (see flexbond/sim.h).
 *
 * With momenta p (I states), displacements q (C states) and inputs held at
 * time t, rest means p = 0 and p' = F_p(q) = 0. Starting from x0, the
 * displacements can only move along what the flows integrate to:
 * q = q0 + (dF_q/dp) P for some "impulse" vector P (for x0 = 0 this keeps
 * the self-stress of a statically indeterminate support at zero, as the
 * settling from rest does). Newton on P:
 *   (dF_p/dq dF_q/dp) dP = -(F_p(x) - dF_p/dp p), then p = 0. */
#include <cblas.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/sim.h"

typedef struct static_work {
  size_t n, np, nq;
  size_t *pidx;      /* momentum state indices */
  size_t *qidx;      /* displacement state indices */
  double *jac, *f;   /* n x n Jacobian, n right-hand side */
  double *jpq, *jqp; /* np x nq and nq x np blocks of the Jacobian */
  double *a, *rhs;   /* np x np system */
  lapack_int *piv;
} static_work;

static void work_free(static_work *w)
{
  free(w->pidx);
  free(w->qidx);
  free(w->jpq);
  free(w->jqp);
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
  w->qidx = malloc((w->n + 1) * sizeof *w->qidx);
  for (size_t i = 0; w->pidx && w->qidx && i < w->n; ++i) {
    fb_state_kind k = fb_bd_state_kind(bd, i);
    if (k == FB_STATE_MOMENTUM)
      w->pidx[w->np++] = i;
    else if (k == FB_STATE_DISPLACEMENT)
      w->qidx[w->nq++] = i;
  }
  w->jpq = malloc((w->np * w->nq + 1) * sizeof *w->jpq);
  w->jqp = malloc((w->np * w->nq + 1) * sizeof *w->jqp);
  w->jac = malloc((w->n * w->n + 1) * sizeof *w->jac);
  w->f = malloc((w->n + 1) * sizeof *w->f);
  w->a = malloc((w->np * w->np + 1) * sizeof *w->a);
  w->rhs = malloc((w->np + 1) * sizeof *w->rhs);
  w->piv = malloc((w->np + 1) * sizeof *w->piv);
  return w->pidx && w->qidx && w->jpq && w->jqp && w->jac && w->f && w->a && w->rhs && w->piv
             ? FB_OK
             : FB_ENOMEM;
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
  /* a = J_pq J_qp (BLAS dgemm on the gathered blocks, column-major);
   * rhs = -(F_p - J_pp p). */
  size_t nq = w->nq;
  for (size_t j = 0; j < nq; ++j)
    for (size_t r = 0; r < np; ++r)
      w->jpq[j * np + r] = w->jac[w->qidx[j] * n + w->pidx[r]];
  for (size_t c = 0; c < np; ++c)
    for (size_t j = 0; j < nq; ++j)
      w->jqp[c * nq + j] = w->jac[w->pidx[c] * n + w->qidx[j]];
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, (int)np, (int)np, (int)nq, 1.0, w->jpq,
              (int)np, w->jqp, (int)nq, 0.0, w->a, (int)np);
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
  for (size_t j = 0; j < nq; ++j)
    for (size_t c = 0; c < np; ++c)
      x[w->qidx[j]] += w->jqp[c * nq + j] * w->rhs[c];
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
