/* SPDX-License-Identifier: BSD-3-Clause */
/* Guyan's static condensation of a structure onto some of its DOFs
 * (fb_fem_guyan, flexbond/fem.h): what another finite-element tool gives
 * as a superelement, done on flexbond's own matrices so that a reduced
 * hull can be checked against the mesh it came from. */
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"

/* The DOFs not in keep (strictly increasing), in increasing order. */
static void guyan_others(size_t n, const size_t *keep, size_t nkeep, size_t *other)
{
  size_t k = 0, o = 0;
  for (size_t i = 0; i < n; ++i) {
    if (k < nkeep && keep[k] == i)
      ++k;
    else
      other[o++] = i;
  }
}

/* out (nkeep x nkeep, column-major) = T' A T, T = [I; X] in the rows
 * keep and other; half the sum with its transpose, which is symmetric to
 * rounding. */
static void guyan_project(const fb_mat *a, size_t n, const size_t *keep, size_t nkeep,
                          const size_t *other, const double *x, double *t, double *at,
                          double *out)
{
  const size_t no = n - nkeep;
  for (size_t j = 0; j < nkeep; ++j) {
    memset(t, 0, n * sizeof *t);
    t[keep[j]] = 1.0;
    for (size_t o = 0; o < no; ++o)
      t[other[o]] = x[j * no + o];
    fb_mat_gemv(a, 1.0, t, 0.0, at + j * n);
  }
  for (size_t j = 0; j < nkeep; ++j)
    for (size_t i = 0; i < nkeep; ++i) {
      double sum = at[j * n + keep[i]];
      for (size_t o = 0; o < no; ++o)
        sum += x[i * no + o] * at[j * n + other[o]];
      out[j * nkeep + i] = sum;
    }
  for (size_t j = 0; j < nkeep; ++j)
    for (size_t i = 0; i < j; ++i)
      out[j * nkeep + i] = out[i * nkeep + j] = 0.5 * (out[j * nkeep + i] + out[i * nkeep + j]);
}

int fb_fem_guyan(const fb_mat *K, const fb_mat *M, const size_t *keep, size_t nkeep, double *kr,
                 double *mr, fb_err *err)
{
  const size_t n = fb_mat_nrows(K), no = n - nkeep;
  for (size_t i = 0; i < nkeep; ++i)
    if (keep[i] >= n || (i && keep[i] <= keep[i - 1]))
      return fb_err_set(err, FB_EINVAL, "fb_fem_guyan: the DOFs kept must increase below %zu",
                        n);
  if (!nkeep || !no)
    return fb_err_set(err, FB_EINVAL, "fb_fem_guyan: nothing to keep or nothing to condense");
  size_t *other = calloc(no, sizeof *other);
  double *x = malloc(no * nkeep * sizeof *x), *t = malloc(n * sizeof *t);
  double *kt = malloc(n * nkeep * sizeof *kt);
  fb_mat *koo = NULL;
  fb_chol *chol = NULL;
  int rc = other && x && t && kt ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc) {
    guyan_others(n, keep, nkeep, other);
    rc = fb_fem_submatrix(K, other, no, &koo, err);
  }
  if (!rc)
    rc = fb_chol_new(koo, 0, &chol, err);
  /* X = -K_oo^-1 K_or: the other DOFs' static response to a unit motion
   * of each kept one, the others unloaded (Guyan, AIAA J. 3(2), 1965). */
  for (size_t j = 0; !rc && j < nkeep; ++j) {
    memset(t, 0, n * sizeof *t);
    t[keep[j]] = 1.0;
    fb_mat_gemv(K, 1.0, t, 0.0, kt);
    for (size_t o = 0; o < no; ++o)
      x[j * no + o] = -kt[other[o]];
  }
  if (!rc)
    rc = fb_chol_solve(chol, x, nkeep, err);
  if (!rc && kr)
    guyan_project(K, n, keep, nkeep, other, x, t, kt, kr);
  if (!rc && mr && M)
    guyan_project(M, n, keep, nkeep, other, x, t, kt, mr);
  fb_chol_free(&chol);
  fb_mat_free(&koo);
  free(other);
  free(x);
  free(t);
  free(kt);
  return rc;
}
