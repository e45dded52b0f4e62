/* SPDX-License-Identifier: BSD-3-Clause */
/* The eigenvalues of a diagram linearised at a state (flexbond/bd.h),
 * from LAPACK's dgeev (Hessenberg QR; Anderson et al., LAPACK Users'
 * Guide, 3rd ed., SIAM 1999, section 2.4.8). */
#include <float.h>
#include <lapacke.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>

#include "flexbond/bd.h"

#include "core/util.h"

/* By |imag|, then real, then the positive member of a pair first. */
static int compare_eigenvalues(double ra, double ia, double rb, double ib)
{
  if (fabs(ia) != fabs(ib))
    return fabs(ia) < fabs(ib) ? -1 : 1;
  if (ra != rb)
    return ra < rb ? -1 : 1;
  return (ia < ib) - (ia > ib);
}

/* Insertion sort of the n eigenvalues (re, im) in place: a few hundred at
 * most in practice, and qsort has no context argument in C11. */
static void sort_eigenvalues(double *re, double *im, size_t n)
{
  for (size_t i = 1; i < n; ++i) {
    const double r = re[i], m = im[i];
    size_t j = i;
    for (; j > 0 && compare_eigenvalues(r, m, re[j - 1], im[j - 1]) < 0; --j) {
      re[j] = re[j - 1];
      im[j] = im[j - 1];
    }
    re[j] = r;
    im[j] = m;
  }
}

static int all_finite(const double *v, size_t n)
{
  for (size_t i = 0; i < n; ++i)
    if (!isfinite(v[i]))
      return 0;
  return 1;
}

/* The Frobenius norm of the n x n matrix a. */
static double frobenius(size_t n, const double *a)
{
  double sum = 0.0;
  for (size_t k = 0; k < n * n; ++k)
    sum += a[k] * a[k];
  return sqrt(sum);
}

/* The Jacobian at (t, x) into jac (n x n, column-major). */
static int linearise(fb_bd *bd, double t, const double *x, size_t n, double *jac,
                     const char *what, fb_err *err)
{
  double *x0 = malloc(n * sizeof *x0);
  if (!x0)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory (%zu states)", what, n);
  if (x) {
    for (size_t i = 0; i < n; ++i)
      x0[i] = x[i];
  } else {
    fb_bd_initial_state(bd, x0);
  }
  int rc = fb_bd_jacobian_dense(bd, t, x0, jac, err);
  free(x0);
  if (rc == FB_OK && !all_finite(jac, n * n))
    rc = fb_err_set(err, FB_ESOLVER, "%s: the Jacobian at t = %g s has non-finite entries",
                    what, t);
  return rc;
}

/* The eigenvalues of the n x n matrix a (overwritten) into e->re, e->im. */
static int solve(size_t n, double *a, fb_bd_eigen *e, const char *what, fb_err *err)
{
  if (n > (size_t)INT_MAX)
    return fb_err_set(err, FB_EINVAL, "%s: %zu states are too many for LAPACK", what, n);
  const lapack_int ln = (lapack_int)n;
  const lapack_int info =
      LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', ln, a, ln, e->re, e->im, NULL, 1, NULL, 1);
  if (info != 0)
    return fb_err_set(err, FB_ESOLVER, "%s: LAPACK dgeev failed (info %d): %s", what, (int)info,
                      info > 0 ? "the QR algorithm did not converge" : "invalid argument");
  return FB_OK;
}

/* Keeps the eigenvalues with |lambda| > e->zero_tol (in order), sorted. */
static void drop_zeros(fb_bd_eigen *e)
{
  size_t kept = 0;
  for (size_t i = 0; i < e->n; ++i)
    if (hypot(e->re[i], e->im[i]) > e->zero_tol) {
      e->re[kept] = e->re[i];
      e->im[kept++] = e->im[i];
    }
  e->n = kept;
  sort_eigenvalues(e->re, e->im, kept);
}

int fb_bd_eigen_new(fb_bd *bd, double t, const double *x, size_t memory_limit, const char *what,
                    fb_bd_eigen **out, fb_err *err)
{
  *out = NULL;
  const size_t n = fb_bd_nstates(bd);
  /* The Jacobian and the matrix dgeev overwrites. */
  int rc = n ? fb_check_dense_eig(n, 2, memory_limit, err, "%s (%zu states)", what, n) : FB_OK;
  if (rc)
    return rc;
  fb_bd_eigen *e = calloc(1, sizeof *e);
  double *jac = malloc((n ? n * n : 1) * sizeof *jac);
  if (e) {
    e->nstates = e->n = n;
    e->re = malloc((n ? 2 * n : 1) * sizeof *e->re);
    e->im = e->re ? e->re + n : NULL;
  }
  if (!e || !jac || !e->re)
    rc = fb_err_set(err, FB_ENOMEM, "%s: out of memory (%zu states)", what, n);
  if (rc == FB_OK && n)
    rc = linearise(bd, t, x, n, jac, what, err);
  if (rc == FB_OK && n) {
    e->zero_tol = (double)n * DBL_EPSILON * frobenius(n, jac);
    rc = solve(n, jac, e, what, err);
  }
  free(jac);
  if (rc != FB_OK) {
    fb_bd_eigen_free(&e);
    return rc;
  }
  drop_zeros(e);
  *out = e;
  return FB_OK;
}

void fb_bd_eigen_free(fb_bd_eigen **e)
{
  if (!e || !*e)
    return;
  free((*e)->re); /* im is its second half */
  free(*e);
  *e = NULL;
}
