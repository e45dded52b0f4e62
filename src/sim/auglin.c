/* Augmented sparse Newton solver (see auglin.h). KLU's 64-bit interface
 * (klu_l_*) is used, like src/core/lu.c. */
#include "sim/auglin.h"

#include <float.h>
#include <klu.h>
#include <stdlib.h>
#include <string.h>

/* After a refactorisation (which reuses the previous pivot order) a
 * reciprocal pivot ratio below this means the old pivots have gone bad,
 * and a full factorisation with fresh partial pivoting is done instead.
 * DBL_EPSILON^(2/3) ~ 3.7e-11 is the threshold SUNDIALS' own KLU module
 * uses for the same decision (SUNDIALS user guide, SUNLinSol_KLU). */
#define REFACTOR_RCOND_MIN 3.666852862501036e-11

/* min|U_kk| / max|U_kk| (klu_l_rcond) below DBL_EPSILON: the pivots differ
 * by more than the working precision, i.e. P(gamma) is singular to
 * working precision and the solve would return noise. */
#define SINGULAR_RCOND DBL_EPSILON

struct fb_auglin {
  size_t nz, nnz, nstates;
  SuiteSparse_long *colptr; /* CSC pattern of P, duplicates merged */
  SuiteSparse_long *rowidx;
  double *vals; /* CSC values of P(gamma) */
  size_t *slot; /* triplet k -> index in rowidx/vals */
  size_t *state_rows;
  double *work; /* right-hand side / solution over z (nz) */
  klu_l_common common;
  klu_l_symbolic *symbolic;
  klu_l_numeric *numeric;
  int factored; /* numeric holds a valid LU of vals */
  long nfactor;
};

void fb_auglin_free(fb_auglin **al)
{
  if (!al || !*al)
    return;
  fb_auglin *a = *al;
  if (a->numeric)
    klu_l_free_numeric(&a->numeric, &a->common);
  if (a->symbolic)
    klu_l_free_symbolic(&a->symbolic, &a->common);
  free(a->colptr);
  free(a->rowidx);
  free(a->vals);
  free(a->slot);
  free(a->state_rows);
  free(a->work);
  free(a);
  *al = NULL;
}

/* Indices in range, state rows distinct. */
static int check_pattern(size_t nz, size_t nnz, const size_t *rows, const size_t *cols,
                         const size_t *state_rows, size_t nstates, fb_err *err)
{
  if (nz == 0 || nstates > nz)
    return fb_err_set(err, FB_EINVAL, "augmented system: %zu states in %zu unknowns", nstates,
                      nz);
  if (nz > (size_t)SuiteSparse_long_max || nnz > (size_t)SuiteSparse_long_max)
    return fb_err_set(err, FB_EINVAL, "augmented system too large for KLU's index type");
  for (size_t k = 0; k < nnz; ++k)
    if (rows[k] >= nz || cols[k] >= nz)
      return fb_err_set(err, FB_EINVAL,
                        "augmented system: triplet %zu at (%zu, %zu) outside %zu x %zu", k,
                        rows[k], cols[k], nz, nz);
  unsigned char *seen = calloc(nz, 1);
  if (!seen)
    return fb_err_set(err, FB_ENOMEM, "out of memory checking the augmented pattern");
  int rc = FB_OK;
  for (size_t i = 0; i < nstates && rc == FB_OK; ++i) {
    if (state_rows[i] >= nz)
      rc = fb_err_set(err, FB_EINVAL, "augmented system: state %zu at row %zu of %zu", i,
                      state_rows[i], nz);
    else if (seen[state_rows[i]]++)
      rc = fb_err_set(err, FB_EINVAL, "augmented system: states share row %zu", state_rows[i]);
  }
  free(seen);
  return rc;
}

/* Stable counting sort of the triplet indices in `in` by key[.] < nkeys. */
static int sort_by_key(size_t nnz, const size_t *in, const size_t *key, size_t nkeys,
                       size_t *out)
{
  size_t *start = calloc(nkeys + 1, sizeof *start);
  if (!start)
    return FB_ENOMEM;
  for (size_t p = 0; p < nnz; ++p)
    ++start[key[in[p]] + 1];
  for (size_t j = 0; j < nkeys; ++j)
    start[j + 1] += start[j];
  for (size_t p = 0; p < nnz; ++p)
    out[start[key[in[p]]]++] = in[p];
  free(start);
  return FB_OK;
}

/* Builds the CSC pattern: the triplets sorted by (column, row) with two
 * stable counting sorts (row, then column), then equal neighbours merged
 * into one slot. */
static int build_csc(fb_auglin *a, const size_t *rows, const size_t *cols)
{
  const size_t nnz = a->nnz;
  size_t *ident = malloc((nnz ? nnz : 1) * sizeof *ident);
  size_t *byrow = malloc((nnz ? nnz : 1) * sizeof *byrow);
  size_t *order = malloc((nnz ? nnz : 1) * sizeof *order);
  int rc = (ident && byrow && order) ? FB_OK : FB_ENOMEM;
  for (size_t k = 0; rc == FB_OK && k < nnz; ++k)
    ident[k] = k;
  if (rc == FB_OK)
    rc = sort_by_key(nnz, ident, rows, a->nz, byrow);
  if (rc == FB_OK)
    rc = sort_by_key(nnz, byrow, cols, a->nz, order);
  if (rc == FB_OK) {
    size_t nslots = 0;
    for (size_t p = 0; p < nnz; ++p) {
      const size_t k = order[p];
      const size_t prev = p ? order[p - 1] : 0;
      if (p == 0 || rows[k] != rows[prev] || cols[k] != cols[prev]) {
        a->rowidx[nslots] = (SuiteSparse_long)rows[k];
        ++a->colptr[cols[k] + 1];
        ++nslots;
      }
      a->slot[k] = nslots - 1;
    }
    for (size_t j = 0; j < a->nz; ++j)
      a->colptr[j + 1] += a->colptr[j];
  }
  free(ident);
  free(byrow);
  free(order);
  return rc;
}

/* KLU's symbolic analysis: BTF, then COLAMD rather than KLU's default AMD
 * on A + A'. The augmented matrix is far from symmetric in pattern (block
 * rows B dy - A du = 0), and COLAMD orders the unsymmetric pattern itself:
 * on System 2's finite-element hull (9216 unknowns) its factorisations
 * fill in far less, 7 times faster over a run; small diagrams are
 * unaffected (System 1: 16.1 vs 18.1 ms). */
static int analyze(fb_auglin *a, fb_err *err)
{
  klu_l_defaults(&a->common);
  a->common.ordering = 1; /* COLAMD */
  a->symbolic = klu_l_analyze((SuiteSparse_long)a->nz, a->colptr, a->rowidx, &a->common);
  if (a->symbolic)
    return FB_OK;
  if (a->common.status == KLU_OUT_OF_MEMORY)
    return fb_err_set(err, FB_ENOMEM, "out of memory in KLU analysis of the Newton matrix");
  return fb_err_set(err, FB_ESOLVER, "KLU analysis of the Newton matrix failed (status %ld)",
                    (long)a->common.status);
}

int fb_auglin_new(size_t nz, size_t nnz, const size_t *rows, const size_t *cols,
                  const size_t *state_rows, size_t nstates, fb_auglin **out, fb_err *err)
{
  *out = NULL;
  int rc = check_pattern(nz, nnz, rows, cols, state_rows, nstates, err);
  if (rc != FB_OK)
    return rc;
  fb_auglin *a = calloc(1, sizeof *a);
  if (!a)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating the Newton solver");
  a->nz = nz;
  a->nnz = nnz;
  a->nstates = nstates;
  a->colptr = calloc(nz + 1, sizeof *a->colptr);
  a->rowidx = malloc((nnz ? nnz : 1) * sizeof *a->rowidx);
  a->vals = malloc((nnz ? nnz : 1) * sizeof *a->vals);
  a->slot = malloc((nnz ? nnz : 1) * sizeof *a->slot);
  a->state_rows = malloc((nstates ? nstates : 1) * sizeof *a->state_rows);
  a->work = malloc(nz * sizeof *a->work);
  if (!a->colptr || !a->rowidx || !a->vals || !a->slot || !a->state_rows || !a->work ||
      build_csc(a, rows, cols) != FB_OK) {
    fb_auglin_free(&a);
    return fb_err_set(err, FB_ENOMEM, "out of memory creating the Newton solver");
  }
  if (nstates)
    memcpy(a->state_rows, state_rows, nstates * sizeof *state_rows);
  rc = analyze(a, err);
  if (rc != FB_OK) {
    fb_auglin_free(&a);
    return rc;
  }
  *out = a;
  return FB_OK;
}

/* vals = P(gamma); duplicates accumulate into their shared slot. */
static void fill_values(fb_auglin *a, double gamma, const double *v0, const double *v1)
{
  const size_t nslots = (size_t)a->colptr[a->nz];
  memset(a->vals, 0, (nslots ? nslots : 1) * sizeof *a->vals);
  for (size_t k = 0; k < a->nnz; ++k)
    a->vals[a->slot[k]] += v0[k] + gamma * v1[k];
}

/* Reuses the pivot order of the last full factorisation. Returns 1 if the
 * result is usable, 0 if a full factorisation is needed (a zero pivot, or
 * pivots grown too unequal for the old order to be trusted). */
static int try_refactor(fb_auglin *a)
{
  ++a->nfactor;
  if (!klu_l_refactor(a->colptr, a->rowidx, a->vals, a->symbolic, a->numeric, &a->common) ||
      a->common.status != KLU_OK)
    return 0;
  return klu_l_rcond(a->symbolic, a->numeric, &a->common) &&
         a->common.rcond >= REFACTOR_RCOND_MIN;
}

/* Full factorisation with partial pivoting; classifies failures. */
static int full_factor(fb_auglin *a, double gamma, fb_err *err)
{
  if (a->numeric)
    klu_l_free_numeric(&a->numeric, &a->common);
  ++a->nfactor;
  a->numeric = klu_l_factor(a->colptr, a->rowidx, a->vals, a->symbolic, &a->common);
  if (a->common.status == KLU_SINGULAR)
    return fb_err_set(
        err, FB_ESOLVER,
        "Newton matrix P(gamma = %g) is singular (no pivot for unknown %ld of %zu)", gamma,
        (long)a->common.singular_col, a->nz);
  if (!a->numeric && a->common.status == KLU_OUT_OF_MEMORY)
    return fb_err_set(err, FB_ENOMEM,
                      "out of memory in KLU factorisation of the Newton matrix");
  if (!a->numeric)
    return fb_err_set(err, FB_ESOLVER,
                      "KLU factorisation of the Newton matrix failed (status %ld)",
                      (long)a->common.status);
  if (!klu_l_rcond(a->symbolic, a->numeric, &a->common) || !(a->common.rcond >= SINGULAR_RCOND))
    return fb_err_set(err, FB_ESOLVER,
                      "Newton matrix P(gamma = %g) is singular to working precision "
                      "(pivot ratio %g)",
                      gamma, a->common.rcond);
  return FB_OK;
}

int fb_auglin_setup(fb_auglin *al, double gamma, const double *v0, const double *v1,
                    fb_err *err)
{
  fill_values(al, gamma, v0, v1);
  const int reuse = al->factored && try_refactor(al);
  al->factored = 0;
  if (!reuse) {
    const int rc = full_factor(al, gamma, err);
    if (rc != FB_OK)
      return rc;
  }
  al->factored = 1;
  return FB_OK;
}

int fb_auglin_solve(fb_auglin *al, const double *b, double *x, fb_err *err)
{
  if (!al->factored)
    return fb_err_set(err, FB_EINVAL, "Newton solve without a valid factorisation");
  memset(al->work, 0, al->nz * sizeof *al->work);
  for (size_t i = 0; i < al->nstates; ++i)
    al->work[al->state_rows[i]] = b[i];
  if (!klu_l_solve(al->symbolic, al->numeric, (SuiteSparse_long)al->nz, 1, al->work,
                   &al->common))
    return fb_err_set(err, FB_ESOLVER, "KLU solve failed (status %ld)",
                      (long)al->common.status);
  for (size_t i = 0; i < al->nstates; ++i)
    x[i] = al->work[al->state_rows[i]];
  return FB_OK;
}

long fb_auglin_nfactorizations(const fb_auglin *al)
{
  return al->nfactor;
}
