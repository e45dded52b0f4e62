/* SPDX-License-Identifier: BSD-3-Clause */
/* Dense LAPACK-based matrix operations: inverse and definiteness tests
 * (see flexbond/mat.h). These work on a dense copy, so they are meant for
 * the small and medium matrices of element laws (transformer moduli, mass
 * and stiffness matrices), not for large sparse systems. */
#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "flexbond/mat.h"

/* Relative tolerance of fb_mat_is_spd, multiplied by n and by max|a_ij|.
 *
 * Symmetry: an exactly symmetric law computed in floating point, e.g.
 * T^T M T, differs from its transpose by a few n*eps*max|a| (Higham,
 * Accuracy and Stability of Numerical Algorithms, 2nd ed., section 3.5).
 *
 * Semi-definiteness: the eigenvalues returned by a backward-stable
 * symmetric eigensolver are exact for A + E with ||E||_2 about
 * eps*||A||_2 <= eps*n*max|a| (Golub & Van Loan, Matrix Computations,
 * 4th ed., section 8.3), so a zero eigenvalue can come out as
 * -O(eps*n*max|a|). 1e-12 leaves a margin of about 4500 over
 * eps = 2.2e-16 while still rejecting genuinely negative eigenvalues
 * larger than a millionth of a millionth of the largest entry. */
#define SPD_RTOL 1e-12

typedef struct dense_buf {
  size_t nrows;
  double *vals;
} dense_buf;

static void store_entry(void *ctx, size_t row, size_t col, double val)
{
  dense_buf *d = ctx;
  d->vals[row + col * d->nrows] = val;
}

/* Column-major copy of a, or NULL when out of memory. */
static double *dense_copy(const fb_mat *a)
{
  const size_t count = fb_mat_nrows(a) * fb_mat_ncols(a);
  dense_buf d = {fb_mat_nrows(a), calloc(count ? count : 1, sizeof(double))};
  if (d.vals)
    fb_mat_foreach(a, store_entry, &d);
  return d.vals;
}

static int lapack_failure(const char *routine, lapack_int info, fb_err *err)
{
  if (info == LAPACK_WORK_MEMORY_ERROR || info == LAPACK_TRANSPOSE_MEMORY_ERROR)
    return fb_err_set(err, FB_ENOMEM, "out of memory in LAPACK %s", routine);
  return fb_err_set(err, FB_ESOLVER, "LAPACK %s failed (info %ld)", routine, (long)info);
}

/* Replaces the n x n column-major a by its inverse: LU with partial
 * pivoting (dgetrf), a reciprocal condition estimate in the 1-norm
 * (dgecon) to reject matrices singular to working precision whose
 * pivots are tiny but not exactly zero (rcond < eps, the criterion of
 * LAPACK's expert driver dgesvx, INFO = N+1), then dgetri. */
static int invert_in_place(double *a, lapack_int n, lapack_int *ipiv, fb_err *err)
{
  const double anorm = LAPACKE_dlange(LAPACK_COL_MAJOR, '1', n, n, a, n);
  lapack_int info = LAPACKE_dgetrf(LAPACK_COL_MAJOR, n, n, a, n, ipiv);
  if (info > 0)
    return fb_err_set(err, FB_ESOLVER,
                      "matrix is singular: zero pivot in column %ld (0-based) of its LU "
                      "factorisation",
                      (long)info - 1);
  if (info < 0)
    return lapack_failure("dgetrf", info, err);
  double rcond = 0.0;
  info = LAPACKE_dgecon(LAPACK_COL_MAJOR, '1', n, a, n, anorm, &rcond);
  if (info)
    return lapack_failure("dgecon", info, err);
  if (rcond < DBL_EPSILON)
    return fb_err_set(err, FB_ESOLVER,
                      "matrix is singular to working precision (reciprocal condition "
                      "number %.3g)",
                      rcond);
  info = LAPACKE_dgetri(LAPACK_COL_MAJOR, n, a, n, ipiv);
  return info ? lapack_failure("dgetri", info, err) : FB_OK;
}

int fb_mat_inverse(const fb_mat *a, fb_mat **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "matrix output pointer is NULL");
  *out = NULL;
  if (!a)
    return fb_err_set(err, FB_EINVAL, "matrix is NULL");
  const size_t n = fb_mat_nrows(a);
  if (n != fb_mat_ncols(a))
    return fb_err_set(err, FB_EINVAL, "cannot invert a %zu x %zu matrix: not square", n,
                      fb_mat_ncols(a));
  if (n > INT32_MAX)
    return fb_err_set(err, FB_EINVAL, "matrix of order %zu is too large to invert", n);
  if (!fb_mat_all_finite(a))
    return fb_err_set(err, FB_EINVAL, "cannot invert a matrix with non-finite entries");
  double *inv = dense_copy(a);
  lapack_int *ipiv = malloc((n ? n : 1) * sizeof *ipiv);
  int rc = FB_OK;
  if (!inv || !ipiv)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory inverting a %zu x %zu matrix", n, n);
  if (!rc && n)
    rc = invert_in_place(inv, (lapack_int)n, ipiv, err);
  if (!rc)
    rc = fb_mat_new_dense(n, n, inv, out, err);
  free(inv);
  free(ipiv);
  return rc;
}

/* 1 if the smallest eigenvalue of the symmetric n x n s (lower triangle
 * used, destroyed) is >= -tol. */
static int min_eigenvalue_at_least(double *s, lapack_int n, double tol)
{
  double *w = malloc((size_t)n * sizeof *w);
  if (!w)
    return 0;
  const lapack_int info = LAPACKE_dsyev(LAPACK_COL_MAJOR, 'N', 'L', n, s, n, w);
  const int ok = info == 0 && w[0] >= -tol; /* dsyev sorts w ascending */
  free(w);
  return ok;
}

/* Returns 0 also when memory for the dense copy cannot be had: the answer
 * is then "not shown to be positive definite". */
int fb_mat_is_spd(const fb_mat *a, int allow_singular)
{
  const size_t n = fb_mat_nrows(a);
  if (n != fb_mat_ncols(a) || n > INT32_MAX || !fb_mat_all_finite(a))
    return 0;
  const double rtol = SPD_RTOL * (double)n;
  if (!fb_mat_is_symmetric(a, rtol))
    return 0;
  if (n == 0)
    return 1;
  double *s = dense_copy(a);
  if (!s)
    return 0;
  double amax = 0.0;
  for (size_t p = 0; p < n * n; ++p)
    amax = fmax(amax, fabs(s[p]));
  const lapack_int ln = (lapack_int)n;
  const int spd = allow_singular ? min_eigenvalue_at_least(s, ln, rtol * amax)
                                 : LAPACKE_dpotrf(LAPACK_COL_MAJOR, 'L', ln, s, ln) == 0;
  free(s);
  return spd;
}
