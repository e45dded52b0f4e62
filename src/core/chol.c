/* SPDX-License-Identifier: BSD-3-Clause */
/* Sparse Cholesky factorisation with SuiteSparse CHOLMOD, supernodal (Y.
 * Chen, T. A. Davis, W. W. Hager & S. Rajamanickam, "Algorithm 887:
 * CHOLMOD", ACM TOMS 35(3), 2008); see flexbond/mat.h.
 *
 * Why CHOLMOD beside KLU: a shell mesh's stiffness fills in far more than
 * a circuit matrix, and KLU's left-looking LU works column by column,
 * where a supernodal Cholesky works on dense blocks with BLAS-3. On the
 * reference hull refined three times (11964 DOFs) KLU took 1.4 s for the
 * shifted stiffness, CHOLMOD 0.09 s (bench/hull_solver.sh). The 64-bit
 * interface (cholmod_l_*) is used, as for KLU, so that any matrix that
 * fits in memory fits the index type. */
#include <cholmod.h>
#include <limits.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/mat.h"

#include "core/util.h"

struct fb_chol {
  size_t n;
  size_t bytes;          /* the factor's, as predicted and checked */
  cholmod_common common; /* settings, status and the solves' workspace */
  cholmod_factor *factor;
  /* fb_chol_set_threads: a second workspace, for the half of a solve's
   * right-hand sides that a second thread solves. */
  int threads;
  cholmod_common common2;
};

/* The upper triangle of alpha a + beta b (b may be NULL), symmetric of
 * order n, as CHOLMOD's stype 1 matrix (*out new): each operand's upper
 * entries in column order (fb_mat_triplets), merged column by column,
 * equal rows summed. */
typedef struct upper_operand {
  size_t nnz, k; /* entries, the next one */
  size_t *row, *col;
  double *val;
  double scale;
} upper_operand;

static void operand_free(upper_operand *o)
{
  free(o->row);
  free(o->col);
  free(o->val);
}

static int operand_upper(double scale, const fb_mat *a, upper_operand *o)
{
  const size_t cap = fb_mat_nnz(a) ? fb_mat_nnz(a) : 1;
  *o = (upper_operand){0,
                       0,
                       malloc(cap * sizeof *o->row),
                       malloc(cap * sizeof *o->col),
                       malloc(cap * sizeof *o->val),
                       scale};
  if (!o->row || !o->col || !o->val)
    return FB_ENOMEM;
  const size_t n = fb_mat_triplets(a, o->row, o->col, o->val);
  for (size_t k = 0; k < n; ++k)
    if (o->row[k] <= o->col[k]) {
      o->row[o->nnz] = o->row[k];
      o->col[o->nnz] = o->col[k];
      o->val[o->nnz++] = o->val[k];
    }
  return FB_OK;
}

/* Appends column j's entries of the operands, rows merged ascending
 * (each operand's rows ascend within a column). */
static void merge_column(upper_operand *op, size_t nop, size_t j, SuiteSparse_long *rowidx,
                         double *vals, size_t *nnz)
{
  for (;;) {
    size_t row = SIZE_MAX;
    for (size_t i = 0; i < nop; ++i)
      if (op[i].k < op[i].nnz && op[i].col[op[i].k] == j && op[i].row[op[i].k] < row)
        row = op[i].row[op[i].k];
    if (row == SIZE_MAX)
      return;
    double v = 0.0;
    for (size_t i = 0; i < nop; ++i)
      if (op[i].k < op[i].nnz && op[i].col[op[i].k] == j && op[i].row[op[i].k] == row)
        v += op[i].scale * op[i].val[op[i].k++];
    rowidx[*nnz] = (SuiteSparse_long)row;
    vals[(*nnz)++] = v;
  }
}

static int upper_triangle(double alpha, const fb_mat *a, double beta, const fb_mat *b, size_t n,
                          cholmod_common *cc, cholmod_sparse **out, fb_err *err)
{
  upper_operand op[2] = {{0}, {0}};
  const size_t nop = b ? 2 : 1;
  int rc = operand_upper(alpha, a, &op[0]);
  if (!rc && b)
    rc = operand_upper(beta, b, &op[1]);
  const size_t cap = op[0].nnz + op[1].nnz;
  cholmod_sparse *s =
      rc ? NULL : cholmod_l_allocate_sparse(n, n, cap ? cap : 1, 1, 1, 1, CHOLMOD_REAL, cc);
  if (s) {
    SuiteSparse_long *colptr = s->p;
    size_t nnz = 0;
    for (size_t j = 0; j < n; ++j) {
      colptr[j] = (SuiteSparse_long)nnz;
      merge_column(op, nop, j, s->i, s->x, &nnz);
    }
    colptr[n] = (SuiteSparse_long)nnz;
  }
  for (size_t i = 0; i < 2; ++i)
    operand_free(&op[i]);
  if (!s)
    return fb_err_set(err, FB_ENOMEM, "out of memory copying a matrix of order %zu for CHOLMOD",
                      n);
  *out = s;
  return FB_OK;
}

/* The factor's bytes once analysed: its values and indices (the
 * supernodal sizes xsize and ssize, or the simplicial nonzero count),
 * and the solves' and the factorisation's workspace, a few n-vectors. */
static size_t factor_bytes(const cholmod_factor *L, const cholmod_common *cc, size_t n)
{
  const double values = L->is_super ? (double)L->xsize : cc->lnz;
  const double indices = L->is_super ? (double)L->ssize + 2.0 * (double)L->nsuper : cc->lnz;
  const double bytes = 8.0 * (values + indices) + 8.0 * 8.0 * (double)n;
  return bytes < (double)SIZE_MAX ? (size_t)bytes : SIZE_MAX;
}

static int cholmod_failure(const cholmod_common *cc, const cholmod_factor *L, fb_err *err)
{
  switch (cc->status) {
  case CHOLMOD_NOT_POSDEF:
    return fb_err_set(err, FB_ESOLVER,
                      "matrix is not positive definite (CHOLMOD: leading minor of order %ld)",
                      L ? (long)L->minor + 1 : -1L);
  case CHOLMOD_OUT_OF_MEMORY:
  case CHOLMOD_TOO_LARGE:
    return fb_err_set(err, FB_ENOMEM, "out of memory in the CHOLMOD factorisation");
  default: return fb_err_set(err, FB_ESOLVER, "CHOLMOD failed (status %d)", cc->status);
  }
}

static int factorise(fb_chol *c, double alpha, const fb_mat *a, double beta, const fb_mat *b,
                     size_t memory_limit, fb_err *err)
{
  cholmod_sparse *upper = NULL;
  int rc = upper_triangle(alpha, a, beta, b, c->n, &c->common, &upper, err);
  if (rc)
    return rc;
  c->factor = cholmod_l_analyze(upper, &c->common);
  if (!c->factor)
    rc = cholmod_failure(&c->common, NULL, err);
  if (!rc) {
    c->bytes = factor_bytes(c->factor, &c->common, c->n);
    rc = fb_check_memory((double)c->bytes, memory_limit, err,
                         "the Cholesky factor of this %zu x %zu matrix", c->n, c->n);
  }
  if (!rc &&
      (!cholmod_l_factorize(upper, c->factor, &c->common) || c->common.status != CHOLMOD_OK))
    rc = cholmod_failure(&c->common, c->factor, err);
  cholmod_l_free_sparse(&upper, &c->common);
  return rc;
}

int fb_chol_new(const fb_mat *a, size_t memory_limit, fb_chol **out, fb_err *err)
{
  return fb_chol_new_sum(1.0, a, 0.0, NULL, memory_limit, out, err);
}

/* FB_EINVAL unless m is a finite square matrix of order n that CHOLMOD's
 * indices can hold. */
static int check_operand(const fb_mat *m, size_t n, fb_err *err)
{
  if (!m)
    return fb_err_set(err, FB_EINVAL, "matrix is NULL");
  if (fb_mat_nrows(m) != n || fb_mat_ncols(m) != n || n == 0)
    return fb_err_set(err, FB_EINVAL, "cannot Cholesky-factorise a %zu x %zu matrix",
                      fb_mat_nrows(m), fb_mat_ncols(m));
  if (n >= (size_t)SuiteSparse_long_max || fb_mat_nnz(m) >= (size_t)SuiteSparse_long_max / 2)
    return fb_err_set(err, FB_EINVAL, "matrix of order %zu is too large for CHOLMOD", n);
  if (!fb_mat_all_finite(m))
    return fb_err_set(err, FB_EINVAL,
                      "cannot Cholesky-factorise a matrix with non-finite entries");
  return FB_OK;
}

int fb_chol_new_sum(double alpha, const fb_mat *a, double beta, const fb_mat *b,
                    size_t memory_limit, fb_chol **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "Cholesky output pointer is NULL");
  *out = NULL;
  const size_t n = a ? fb_mat_nrows(a) : 0;
  int rc = check_operand(a, n, err);
  if (!rc && b)
    rc = check_operand(b, n, err);
  if (rc)
    return rc;
  fb_chol *c = calloc(1, sizeof *c);
  if (!c)
    return fb_err_set(err, FB_ENOMEM, "out of memory allocating a Cholesky factorisation");
  c->n = n;
  cholmod_l_start(&c->common);
  /* The library never prints: CHOLMOD reports through its status only. */
  c->common.print = 0;
  c->common.error_handler = NULL;
  c->common.supernodal = CHOLMOD_SUPERNODAL;
  rc = factorise(c, alpha, a, beta, b, memory_limit, err);
  if (rc) {
    fb_chol_free(&c);
    return rc;
  }
  *out = c;
  return FB_OK;
}

/* Solves in place nrhs right-hand sides at b with the workspace cc: a
 * view of b as CHOLMOD's dense matrix; the solve returns a new one,
 * copied back. 0, or -1 with cc's status. */
static int solve_part(const fb_chol *c, cholmod_common *cc, double *b, size_t nrhs)
{
  cholmod_dense rhs = {c->n, nrhs, c->n * nrhs, c->n, b, NULL, CHOLMOD_REAL, CHOLMOD_DOUBLE};
  cholmod_dense *x = cholmod_l_solve(CHOLMOD_A, c->factor, &rhs, cc);
  if (!x)
    return -1;
  memcpy(b, x->x, c->n * nrhs * sizeof *b);
  cholmod_l_free_dense(&x, cc);
  return 0;
}

/* The second thread's half of a solve. */
typedef struct solve_job {
  const fb_chol *c;
  cholmod_common *cc;
  double *b;
  size_t nrhs;
  int rc;
} solve_job;

static void *solve_thread(void *arg)
{
  solve_job *j = arg;
  j->rc = solve_part(j->c, j->cc, j->b, j->nrhs);
  return NULL;
}

int fb_chol_solve(fb_chol *c, double *b, size_t nrhs, fb_err *err)
{
  if (!c || (!b && nrhs))
    return fb_err_set(err, FB_EINVAL, "Cholesky solve: NULL argument");
  if (nrhs == 0)
    return FB_OK;
  if (nrhs > SIZE_MAX / c->n / sizeof *b)
    return fb_err_set(err, FB_EINVAL, "too many right-hand sides (%zu)", nrhs);
  /* Two threads share the factor, which a solve only reads, each with a
   * workspace of its own; when the second cannot start, this one solves
   * everything. */
  solve_job half = {c, &c->common2, NULL, nrhs / 2, -1};
  pthread_t thread;
  int started = 0;
  if (c->threads > 1 && nrhs >= 2) {
    half.b = b + c->n * (nrhs - half.nrhs);
    started = pthread_create(&thread, NULL, solve_thread, &half) == 0;
  }
  const size_t mine = started ? nrhs - half.nrhs : nrhs;
  const int rc = solve_part(c, &c->common, b, mine);
  if (started)
    pthread_join(thread, NULL);
  if (rc || (started && half.rc))
    return cholmod_failure(rc ? &c->common : &c->common2, c->factor, err);
  return FB_OK;
}

void fb_chol_set_threads(fb_chol *c, int threads)
{
  if (threads > 1 && !c->threads) {
    cholmod_l_start(&c->common2);
    c->common2.print = 0;
    c->common2.error_handler = NULL;
  }
  if (threads > 1 || c->threads)
    c->threads = threads > 1 ? 2 : 1;
}

size_t fb_chol_size(const fb_chol *c)
{
  return c->n;
}

size_t fb_chol_bytes(const fb_chol *c)
{
  return c->bytes;
}

void fb_chol_free(fb_chol **c)
{
  if (!c || !*c)
    return;
  cholmod_l_free_factor(&(*c)->factor, &(*c)->common);
  cholmod_l_finish(&(*c)->common);
  if ((*c)->threads)
    cholmod_l_finish(&(*c)->common2);
  free(*c);
  *c = NULL;
}
