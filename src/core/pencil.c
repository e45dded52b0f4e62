/* SPDX-License-Identifier: BSD-3-Clause */
/* Solves (j omega E - A) x = b for the frequencies of a frequency
 * response: one symbolic analysis of the pattern of E and A together,
 * then a complex KLU factorisation per frequency (Davis & Palamadai
 * Natarajan, "Algorithm 907: KLU", ACM TOMS 37(3), 2010; its complex
 * routines klu_zl_* take values as interleaved real and imaginary parts).
 * Pivots are chosen again at every frequency: the matrix changes from
 * -A at low frequency to j omega E at high, and one ordering of pivots
 * need not serve both. See flexbond/mat.h. */
#include <klu.h>
#include <stdint.h>
#include <stdlib.h>

#include "flexbond/mat.h"

/* One entry of the pattern: where it is and what E and A hold there. */
typedef struct pencil_entry {
  size_t row, col;
  double e, a;
} pencil_entry;

struct fb_pencil {
  size_t n, nnz;
  SuiteSparse_long *colptr, *rowidx;
  double *e, *a;  /* nnz each, in the pattern's (column) order */
  double *values; /* 2 nnz: j omega e - a, interleaved */
  klu_l_common common;
  klu_l_symbolic *symbolic;
  klu_l_numeric *numeric;
};

typedef struct collect {
  pencil_entry *entry;
  size_t n;
  int is_a;
} collect;

static void collect_entry(void *ctx, size_t row, size_t col, double val)
{
  collect *c = ctx;
  c->entry[c->n++] = (pencil_entry){row, col, c->is_a ? 0.0 : val, c->is_a ? val : 0.0};
}

static int entry_cmp(const void *p, const void *q)
{
  const pencil_entry *x = p, *y = q;
  if (x->col != y->col)
    return x->col < y->col ? -1 : 1;
  return x->row < y->row ? -1 : x->row > y->row;
}

/* The pattern of E and A in compressed columns, duplicates merged. */
static int make_pattern(fb_pencil *p, pencil_entry *entry, size_t n, fb_err *err)
{
  qsort(entry, n, sizeof *entry, entry_cmp);
  p->colptr = calloc(p->n + 1, sizeof *p->colptr);
  p->rowidx = malloc((n + 1) * sizeof *p->rowidx);
  p->e = malloc((n + 1) * sizeof *p->e);
  p->a = malloc((n + 1) * sizeof *p->a);
  p->values = malloc((2 * n + 1) * sizeof *p->values);
  if (!p->colptr || !p->rowidx || !p->e || !p->a || !p->values)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a pencil of order %zu", p->n);
  size_t k = 0;
  for (size_t i = 0; i < n; ++i) {
    if (k && entry[i].row == (size_t)p->rowidx[k - 1] && entry[i].col == entry[i - 1].col) {
      p->e[k - 1] += entry[i].e;
      p->a[k - 1] += entry[i].a;
      continue;
    }
    p->rowidx[k] = (SuiteSparse_long)entry[i].row;
    p->e[k] = entry[i].e;
    p->a[k] = entry[i].a;
    ++p->colptr[entry[i].col + 1];
    ++k;
  }
  for (size_t j = 0; j < p->n; ++j)
    p->colptr[j + 1] += p->colptr[j];
  p->nnz = k;
  return FB_OK;
}

static int check_pair(const fb_mat *E, const fb_mat *A, fb_err *err)
{
  if (!E || !A)
    return fb_err_set(err, FB_EINVAL, "pencil: a matrix is NULL");
  const size_t n = fb_mat_nrows(A);
  if (fb_mat_ncols(A) != n || fb_mat_nrows(E) != n || fb_mat_ncols(E) != n)
    return fb_err_set(err, FB_EINVAL,
                      "pencil: E (%zu x %zu) and A (%zu x %zu) are not square "
                      "of one order",
                      fb_mat_nrows(E), fb_mat_ncols(E), n, fb_mat_ncols(A));
  if (!fb_mat_all_finite(E) || !fb_mat_all_finite(A))
    return fb_err_set(err, FB_EINVAL, "pencil: a matrix has non-finite entries");
  const size_t nnz = fb_mat_nnz(E) + fb_mat_nnz(A);
  if (n >= (size_t)SuiteSparse_long_max || nnz > (size_t)SuiteSparse_long_max / 2 ||
      nnz > SIZE_MAX / (2 * sizeof(pencil_entry)))
    return fb_err_set(err, FB_EINVAL, "pencil of order %zu is too large for KLU", n);
  return FB_OK;
}

int fb_pencil_new(const fb_mat *E, const fb_mat *A, fb_pencil **out, fb_err *err)
{
  *out = NULL;
  int rc = check_pair(E, A, err);
  if (rc)
    return rc;
  fb_pencil *p = calloc(1, sizeof *p);
  collect c = {malloc((fb_mat_nnz(E) + fb_mat_nnz(A) + 1) * sizeof(pencil_entry)), 0, 0};
  if (!p || !c.entry) {
    free(p);
    free(c.entry);
    return fb_err_set(err, FB_ENOMEM, "out of memory for a pencil");
  }
  p->n = fb_mat_nrows(A);
  fb_mat_foreach(E, collect_entry, &c);
  c.is_a = 1;
  fb_mat_foreach(A, collect_entry, &c);
  rc = make_pattern(p, c.entry, c.n, err);
  free(c.entry);
  klu_l_defaults(&p->common);
  if (!rc && p->n) {
    p->symbolic = klu_l_analyze((SuiteSparse_long)p->n, p->colptr, p->rowidx, &p->common);
    if (!p->symbolic)
      rc = fb_err_set(err, p->common.status == KLU_OUT_OF_MEMORY ? FB_ENOMEM : FB_ESOLVER,
                      "pencil: KLU's analysis failed (status %ld)", (long)p->common.status);
  }
  if (rc)
    fb_pencil_free(&p);
  *out = p;
  return rc;
}

size_t fb_pencil_order(const fb_pencil *p)
{
  return p->n;
}

int fb_pencil_factor(fb_pencil *p, double omega, fb_err *err)
{
  if (!(omega == omega) || omega < 0)
    return fb_err_set(err, FB_EINVAL, "pencil: angular frequency %g rad/s", omega);
  klu_zl_free_numeric(&p->numeric, &p->common);
  if (p->n == 0)
    return FB_OK;
  for (size_t k = 0; k < p->nnz; ++k) {
    p->values[2 * k] = -p->a[k];
    p->values[2 * k + 1] = omega * p->e[k];
  }
  p->numeric = klu_zl_factor(p->colptr, p->rowidx, p->values, p->symbolic, &p->common);
  if (p->numeric)
    return FB_OK;
  if (p->common.status == KLU_SINGULAR)
    return fb_err_set(err, FB_ESOLVER,
                      "j omega E - A is singular at omega = %g rad/s (%g Hz): zero pivot in "
                      "column %ld (0-based)",
                      omega, omega / (2.0 * 3.14159265358979323846),
                      (long)p->common.singular_col);
  return fb_err_set(err, p->common.status == KLU_OUT_OF_MEMORY ? FB_ENOMEM : FB_ESOLVER,
                    "pencil: KLU's complex factorisation failed (status %ld)",
                    (long)p->common.status);
}

int fb_pencil_solve(fb_pencil *p, double *b, size_t nrhs, fb_err *err)
{
  if (p->n == 0 || nrhs == 0)
    return FB_OK;
  if (!p->numeric)
    return fb_err_set(err, FB_EINVAL, "pencil: solve before a factorisation");
  if (nrhs > (size_t)SuiteSparse_long_max)
    return fb_err_set(err, FB_EINVAL, "pencil: too many right-hand sides (%zu)", nrhs);
  if (!klu_zl_solve(p->symbolic, p->numeric, (SuiteSparse_long)p->n, (SuiteSparse_long)nrhs, b,
                    &p->common))
    return fb_err_set(err, FB_ESOLVER, "pencil: KLU's complex solve failed (status %ld)",
                      (long)p->common.status);
  return FB_OK;
}

void fb_pencil_free(fb_pencil **p)
{
  if (!p || !*p)
    return;
  klu_zl_free_numeric(&(*p)->numeric, &(*p)->common);
  klu_l_free_symbolic(&(*p)->symbolic, &(*p)->common);
  free((*p)->colptr);
  free((*p)->rowidx);
  free((*p)->e);
  free((*p)->a);
  free((*p)->values);
  free(*p);
  *p = NULL;
}
