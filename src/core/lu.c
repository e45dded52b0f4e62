/* SPDX-License-Identifier: BSD-3-Clause */
/* Sparse LU factorisation with SuiteSparse KLU (Davis & Palamadai
 * Natarajan, "Algorithm 907: KLU", ACM TOMS 37(3), 2010); see
 * flexbond/mat.h. The 64-bit-index interface (klu_l_*) is used so any
 * matrix that fits in memory fits KLU's index type. */
#include <float.h>
#include <klu.h>
#include <stdlib.h>

#include "flexbond/mat.h"

struct fb_lu {
  size_t n;
  klu_l_common common; /* KLU settings and status, needed again by solve */
  klu_l_symbolic *symbolic;
  klu_l_numeric *numeric;
};

/* A compressed-sparse-column copy of a matrix with KLU's index type. */
typedef struct klu_csc {
  SuiteSparse_long *colptr;
  SuiteSparse_long *rowidx;
  double *vals;
  SuiteSparse_long nnz;
} klu_csc;

/* fb_mat_foreach visits in column order, so appending entries and
 * counting per column gives CSC once the counts are summed. */
static void append_entry(void *ctx, size_t row, size_t col, double val)
{
  klu_csc *c = ctx;
  c->rowidx[c->nnz] = (SuiteSparse_long)row;
  c->vals[c->nnz++] = val;
  ++c->colptr[col + 1];
}

static void klu_csc_free(klu_csc *c)
{
  free(c->colptr);
  free(c->rowidx);
  free(c->vals);
}

/* Fills c from the square a (order n). fb_mat_nnz bounds the visited
 * entries (dense matrices visit only their nonzeros). */
static int klu_csc_from(const fb_mat *a, size_t n, klu_csc *c, fb_err *err)
{
  const size_t cap = fb_mat_nnz(a) ? fb_mat_nnz(a) : 1;
  c->nnz = 0;
  c->colptr = calloc(n + 1, sizeof *c->colptr);
  c->rowidx = malloc(cap * sizeof *c->rowidx);
  c->vals = malloc(cap * sizeof *c->vals);
  if (!c->colptr || !c->rowidx || !c->vals) {
    klu_csc_free(c);
    return fb_err_set(err, FB_ENOMEM, "out of memory copying a matrix for KLU");
  }
  fb_mat_foreach(a, append_entry, c);
  for (size_t j = 0; j < n; ++j)
    c->colptr[j + 1] += c->colptr[j];
  return FB_OK;
}

/* Turns a failed klu_l_analyze/klu_l_factor into a status and message. */
static int klu_failure(const klu_l_common *common, size_t n, fb_err *err)
{
  const long col = (long)common->singular_col;
  switch (common->status) {
  case KLU_SINGULAR:
    if (col >= 0 && (size_t)col < n)
      return fb_err_set(err, FB_ESOLVER,
                        "matrix is singular: zero pivot in column %ld (0-based)", col);
    return fb_err_set(err, FB_ESOLVER, "matrix is singular");
  case KLU_OUT_OF_MEMORY:
    return fb_err_set(err, FB_ENOMEM, "out of memory in KLU factorisation");
  default:
    return fb_err_set(err, FB_ESOLVER, "KLU factorisation failed (status %ld)",
                      (long)common->status);
  }
}

/* KLU stops only at exactly zero pivots. A matrix whose estimated
 * 1-norm condition number exceeds 1/eps is reported singular to working
 * precision instead, the criterion of LAPACK's expert driver dgesvx
 * (INFO = N+1), as a solve with it carries no correct digit in some
 * component. The estimate (klu_condest, Hager/Higham 1-norm estimator)
 * costs a few solves, negligible next to the factorisation. */
static int check_conditioning(fb_lu *lu, const klu_csc *c, fb_err *err)
{
  if (!klu_l_condest(c->colptr, c->vals, lu->symbolic, lu->numeric, &lu->common))
    return klu_failure(&lu->common, lu->n, err);
  if (!(lu->common.condest * DBL_EPSILON < 1.0))
    return fb_err_set(err, FB_ESOLVER,
                      "matrix is singular to working precision (condition number estimate "
                      "%.3g)",
                      lu->common.condest);
  return FB_OK;
}

static int factorise(fb_lu *lu, const fb_mat *a, fb_err *err)
{
  klu_csc c;
  int rc = klu_csc_from(a, lu->n, &c, err);
  if (rc)
    return rc;
  const SuiteSparse_long n = (SuiteSparse_long)lu->n;
  lu->symbolic = klu_l_analyze(n, c.colptr, c.rowidx, &lu->common);
  if (lu->symbolic)
    lu->numeric = klu_l_factor(c.colptr, c.rowidx, c.vals, lu->symbolic, &lu->common);
  rc = lu->numeric ? check_conditioning(lu, &c, err) : klu_failure(&lu->common, lu->n, err);
  klu_csc_free(&c);
  return rc;
}

int fb_lu_new(const fb_mat *a, fb_lu **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "LU output pointer is NULL");
  *out = NULL;
  if (!a)
    return fb_err_set(err, FB_EINVAL, "matrix is NULL");
  const size_t n = fb_mat_nrows(a);
  if (n != fb_mat_ncols(a))
    return fb_err_set(err, FB_EINVAL, "cannot LU-factorise a %zu x %zu matrix: not square", n,
                      fb_mat_ncols(a));
  if (n >= (size_t)SuiteSparse_long_max || fb_mat_nnz(a) > (size_t)SuiteSparse_long_max)
    return fb_err_set(err, FB_EINVAL, "matrix of order %zu is too large for KLU", n);
  if (!fb_mat_all_finite(a))
    return fb_err_set(err, FB_EINVAL, "cannot LU-factorise a matrix with non-finite entries");
  fb_lu *lu = calloc(1, sizeof *lu);
  if (!lu)
    return fb_err_set(err, FB_ENOMEM, "out of memory allocating an LU factorisation");
  lu->n = n;
  klu_l_defaults(&lu->common);
  const int rc = n ? factorise(lu, a, err) : FB_OK;
  if (rc)
    fb_lu_free(&lu);
  *out = lu;
  return rc;
}

int fb_lu_solve(fb_lu *lu, double *b, size_t nrhs, fb_err *err)
{
  if (!lu)
    return fb_err_set(err, FB_EINVAL, "LU factorisation is NULL");
  if (lu->n == 0 || nrhs == 0)
    return FB_OK;
  if (!b)
    return fb_err_set(err, FB_EINVAL, "right-hand side is NULL");
  if (nrhs > (size_t)SuiteSparse_long_max)
    return fb_err_set(err, FB_EINVAL, "too many right-hand sides (%zu)", nrhs);
  if (!klu_l_solve(lu->symbolic, lu->numeric, (SuiteSparse_long)lu->n, (SuiteSparse_long)nrhs,
                   b, &lu->common))
    return fb_err_set(err, FB_ESOLVER, "KLU solve failed (status %ld)",
                      (long)lu->common.status);
  return FB_OK;
}

size_t fb_lu_size(const fb_lu *lu)
{
  return lu->n;
}

void fb_lu_free(fb_lu **lu)
{
  if (!lu || !*lu)
    return;
  klu_l_free_numeric(&(*lu)->numeric, &(*lu)->common);
  klu_l_free_symbolic(&(*lu)->symbolic, &(*lu)->common);
  free(*lu);
  *lu = NULL;
}
