/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of flexbond/mat.h: construction, products, inverse, KLU LU,
 * definiteness tests and Matrix Market I/O. Expected values are worked
 * out by hand (or from closed forms) in the comments next to them. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/mat.h"

#include "check.h"
#include "tmpdir.h"

/* A = [1 2 3; 4 5 6], used by several tests. */
static const double A23_ROWMAJOR[] = {1, 2, 3, 4, 5, 6};

static fb_mat *dense_rowmajor(size_t m, size_t n, const double *rm)
{
  fb_mat *a = NULL;
  fb_err err;
  CHECK(fb_mat_new_dense_rowmajor(m, n, rm, &a, &err) == FB_OK);
  return a;
}

static fb_mat *triplets(size_t m, size_t n, size_t nnz, const size_t *r, const size_t *c,
                        const double *v)
{
  fb_mat *a = NULL;
  fb_err err;
  CHECK(fb_mat_new_triplets(m, n, nnz, r, c, v, &a, &err) == FB_OK);
  return a;
}

/* The same A23 as a sparse matrix, entries shuffled and a_11 = 5 given as
 * the duplicates 2 + 3 (exact in binary, so the sum is exactly 5). */
static fb_mat *sparse_a23(void)
{
  const size_t r[] = {1, 0, 1, 0, 1, 1, 0};
  const size_t c[] = {2, 1, 1, 0, 0, 1, 2};
  const double v[] = {6, 2, 2, 1, 4, 3, 3};
  return triplets(2, 3, 7, r, c, v);
}

/* Checks every entry of a against the row-major expected values within
 * tol; m, n are the expected shape. */
static void check_entries(const fb_mat *a, size_t m, size_t n, const double *rm, double tol)
{
  CHECK(a != NULL);
  if (!a)
    return;
  CHECK(fb_mat_nrows(a) == m);
  CHECK(fb_mat_ncols(a) == n);
  for (size_t i = 0; i < m; ++i)
    for (size_t j = 0; j < n; ++j)
      CHECK_NEAR(fb_mat_get(a, i, j), rm[i * n + j], tol);
}

/* Visit log for fb_mat_foreach: checks (column, row) order as it goes. */
typedef struct visit_log {
  size_t count;
  double sum;
  size_t last_row;
  size_t last_col;
  int out_of_order;
} visit_log;

static void log_visit(void *ctx, size_t row, size_t col, double val)
{
  visit_log *log = ctx;
  if (log->count && (col < log->last_col || (col == log->last_col && row <= log->last_row)))
    log->out_of_order = 1;
  log->last_row = row;
  log->last_col = col;
  log->sum += val;
  ++log->count;
}

static visit_log visit_all(const fb_mat *a)
{
  visit_log log = {0, 0.0, 0, 0, 0};
  fb_mat_foreach(a, log_visit, &log);
  return log;
}

/* All operands below are small integers, so every product and sum is exact
 * in binary64 and the comparisons use tolerance 0. */
static void test_gemv(void)
{
  fb_mat *dense = dense_rowmajor(2, 3, A23_ROWMAJOR);
  fb_mat *sparse = sparse_a23();
  const fb_mat *both[] = {dense, sparse};
  const double x3[] = {1, -1, 2};
  const double x2[] = {1, 2};
  for (int k = 0; k < 2; ++k) {
    const fb_mat *a = both[k];
    /* A x3 = (1 - 2 + 6, 4 - 5 + 12) = (5, 11); beta = 0 ignores the NaNs. */
    double y2[2] = {NAN, NAN};
    fb_mat_gemv(a, 2.0, x3, 0.0, y2);
    CHECK_NEAR(y2[0], 10.0, 0.0);
    CHECK_NEAR(y2[1], 22.0, 0.0);
    /* 2 (5, 11) + 0.5 (2, 4) = (11, 24). */
    y2[0] = 2.0;
    y2[1] = 4.0;
    fb_mat_gemv(a, 2.0, x3, 0.5, y2);
    CHECK_NEAR(y2[0], 11.0, 0.0);
    CHECK_NEAR(y2[1], 24.0, 0.0);
    /* A^T x2 = (1 + 8, 2 + 10, 3 + 12) = (9, 12, 15). */
    double y3[3] = {NAN, NAN, NAN};
    fb_mat_gemv_t(a, 1.0, x2, 0.0, y3);
    CHECK_NEAR(y3[0], 9.0, 0.0);
    CHECK_NEAR(y3[1], 12.0, 0.0);
    CHECK_NEAR(y3[2], 15.0, 0.0);
    /* -(9, 12, 15) + 2 (1, 1, 1) = (-7, -10, -13). */
    for (int i = 0; i < 3; ++i)
      y3[i] = 1.0;
    fb_mat_gemv_t(a, -1.0, x2, 2.0, y3);
    CHECK_NEAR(y3[0], -7.0, 0.0);
    CHECK_NEAR(y3[1], -10.0, 0.0);
    CHECK_NEAR(y3[2], -13.0, 0.0);
  }
  fb_mat_free(&dense);
  fb_mat_free(&sparse);
}

static void test_construction(void)
{
  fb_err err;
  fb_mat *s = sparse_a23();
  CHECK(fb_mat_is_sparse(s));
  CHECK(fb_mat_nnz(s) == 6); /* 7 triplets, two of them merged */
  check_entries(s, 2, 3, A23_ROWMAJOR, 0.0);
  visit_log log = visit_all(s);
  CHECK(log.count == 6 && !log.out_of_order);
  CHECK_NEAR(log.sum, 21.0, 0.0);
  CHECK(fb_mat_get(s, 2, 0) == 0.0); /* out of range reads as not stored */
  fb_mat_free(&s);
  CHECK(s == NULL);
  fb_mat_free(&s); /* NULL is accepted */
  fb_mat_free(NULL);

  /* Duplicates cancelling to zero and explicit zeros are not stored. */
  const size_t r[] = {0, 0, 1, 1};
  const size_t c[] = {1, 1, 0, 1};
  const double v[] = {1.5, -1.5, 0.0, 7.0};
  s = triplets(2, 2, 4, r, c, v);
  CHECK(fb_mat_nnz(s) == 1);
  CHECK_NEAR(fb_mat_get(s, 1, 1), 7.0, 0.0);
  fb_mat_free(&s);

  /* Out-of-range triplets are refused and *out is cleared. */
  const size_t bad_r[] = {0, 2};
  const size_t bad_c[] = {0, 0};
  fb_mat *out = NULL;
  CHECK(fb_mat_new_triplets(2, 2, 2, bad_r, bad_c, v, &out, &err) == FB_EINVAL);
  CHECK(out == NULL);
  CHECK(strstr(err.msg, "(2, 0)") != NULL);
  CHECK(fb_mat_new_dense(2, 2, NULL, &out, &err) == FB_EINVAL);
  CHECK(fb_mat_new_dense(2, 2, v, NULL, &err) == FB_EINVAL);

  /* Column-major and row-major constructors agree. */
  const double colmajor[] = {1, 4, 2, 5, 3, 6};
  CHECK(fb_mat_new_dense(2, 3, colmajor, &out, &err) == FB_OK);
  CHECK(!fb_mat_is_sparse(out) && fb_mat_nnz(out) == 6);
  check_entries(out, 2, 3, A23_ROWMAJOR, 0.0);
  fb_mat_free(&out);

  /* Diagonal matrices store their nonzero entries only. */
  const double diag[] = {2, 0, -3};
  CHECK(fb_mat_new_diag(3, diag, &out, &err) == FB_OK);
  const double diag_full[] = {2, 0, 0, 0, 0, 0, 0, 0, -3};
  check_entries(out, 3, 3, diag_full, 0.0);
  CHECK(fb_mat_is_sparse(out) && fb_mat_nnz(out) == 2);
  fb_mat_free(&out);
  CHECK(fb_mat_new_scaled_identity(2, 0.5, &out, &err) == FB_OK);
  const double half_eye[] = {0.5, 0, 0, 0.5};
  check_entries(out, 2, 2, half_eye, 0.0);
  CHECK(fb_mat_nnz(out) == 2);
  fb_mat_free(&out);
  CHECK(fb_mat_new_scaled_identity(3, 0.0, &out, &err) == FB_OK);
  CHECK(fb_mat_nnz(out) == 0);
  fb_mat_free(&out);
}

static void test_foreach_dense_and_finite(void)
{
  const double rm[] = {0, 2, 0, 4, 0, 6};
  fb_mat *a = dense_rowmajor(2, 3, rm);
  visit_log log = visit_all(a);
  CHECK(log.count == 3); /* zeros are skipped */
  CHECK(!log.out_of_order);
  CHECK_NEAR(log.sum, 12.0, 0.0);
  CHECK(fb_mat_all_finite(a));
  fb_mat_free(&a);
  const double bad[] = {1, INFINITY};
  a = dense_rowmajor(1, 2, bad);
  CHECK(!fb_mat_all_finite(a));
  fb_mat_free(&a);
}

/* fb_mat_triplets gives back what builds the matrix again: A23 from its
 * sparse and its dense form (the dense form's zeros left out), in column
 * order, exactly. */
static void test_triplets(void)
{
  fb_err err;
  fb_mat *dense = dense_rowmajor(2, 3, A23_ROWMAJOR);
  fb_mat *sparse = sparse_a23();
  const fb_mat *both[] = {dense, sparse};
  for (int k = 0; k < 2; ++k) {
    size_t row[6], col[6];
    double val[6];
    CHECK(fb_mat_nnz(both[k]) == 6);
    const size_t n = fb_mat_triplets(both[k], row, col, val);
    CHECK(n == 6);
    for (size_t i = 1; i < n; ++i)
      CHECK(col[i] > col[i - 1] || (col[i] == col[i - 1] && row[i] > row[i - 1]));
    fb_mat *again = NULL;
    CHECK(fb_mat_new_triplets(2, 3, n, row, col, val, &again, &err) == FB_OK);
    check_entries(again, 2, 3, A23_ROWMAJOR, 0.0);
    fb_mat_free(&again);
  }
  const double rm[] = {0, 2, 0, 4, 0, 6};
  fb_mat *a = dense_rowmajor(2, 3, rm);
  size_t row[6], col[6];
  double val[6];
  CHECK(fb_mat_triplets(a, row, col, val) == 3); /* zeros are not entries */
  CHECK(row[0] == 1 && col[0] == 0 && val[0] == 4.0);
  fb_mat_free(&a);
  fb_mat_free(&dense);
  fb_mat_free(&sparse);
}

static void test_clone_transpose(void)
{
  fb_err err;
  fb_mat *dense = dense_rowmajor(2, 3, A23_ROWMAJOR);
  fb_mat *sparse = sparse_a23();
  const double a_t[] = {1, 4, 2, 5, 3, 6}; /* A^T row-major, 3 x 2 */
  const fb_mat *both[] = {dense, sparse};
  for (int k = 0; k < 2; ++k) {
    fb_mat *t = NULL, *c = NULL;
    CHECK(fb_mat_transpose(both[k], &t, &err) == FB_OK);
    check_entries(t, 3, 2, a_t, 0.0);
    CHECK(fb_mat_is_sparse(t) == fb_mat_is_sparse(both[k]));
    CHECK(fb_mat_clone(both[k], &c, &err) == FB_OK);
    check_entries(c, 2, 3, A23_ROWMAJOR, 0.0);
    CHECK(fb_mat_is_sparse(c) == fb_mat_is_sparse(both[k]));
    CHECK(fb_mat_nnz(c) == fb_mat_nnz(both[k]));
    fb_mat_free(&t);
    fb_mat_free(&c);
  }
  fb_mat_free(&dense);
  fb_mat_free(&sparse);
}

static void test_multiply(void)
{
  fb_err err;
  /* A B with B = [1 0; 0 1; 2 -1]:
   * row 1: (1 + 0 + 6, 0 + 2 - 3) = (7, -1); row 2: (4 + 12, 5 - 6) = (16, -1). */
  const double b_rm[] = {1, 0, 0, 1, 2, -1};
  const double ab[] = {7, -1, 16, -1};
  const size_t br[] = {0, 1, 2, 2};
  const size_t bc[] = {0, 1, 0, 1};
  const double bv[] = {1, 1, 2, -1};
  fb_mat *a[2] = {dense_rowmajor(2, 3, A23_ROWMAJOR), sparse_a23()};
  fb_mat *b[2] = {dense_rowmajor(3, 2, b_rm), triplets(3, 2, 4, br, bc, bv)};
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      fb_mat *c = NULL;
      CHECK(fb_mat_multiply(a[i], b[j], &c, &err) == FB_OK);
      check_entries(c, 2, 2, ab, 0.0);
      CHECK(fb_mat_is_sparse(c) == (i || j));
      CHECK(!visit_all(c).out_of_order);
      fb_mat_free(&c);
    }
  }
  fb_mat *c = NULL;
  CHECK(fb_mat_multiply(a[0], a[1], &c, &err) == FB_EINVAL);
  CHECK(c == NULL);
  CHECK(strstr(err.msg, "2 x 3") != NULL);
  for (int k = 0; k < 2; ++k) {
    fb_mat_free(&a[k]);
    fb_mat_free(&b[k]);
  }

  /* P = [0 1; 0 0; 1 0] times (1, 1)^T accumulates row 2 before row 0;
   * the result (1, 0, 1)^T must still be stored in row order. */
  const size_t pr[] = {2, 0};
  const size_t pc[] = {0, 1};
  const double pv[] = {1, 1};
  const double ones[] = {1, 1};
  fb_mat *p = triplets(3, 2, 2, pr, pc, pv);
  fb_mat *o = dense_rowmajor(2, 1, ones);
  CHECK(fb_mat_multiply(p, o, &c, &err) == FB_OK);
  const double p_ones[] = {1, 0, 1};
  check_entries(c, 3, 1, p_ones, 0.0);
  visit_log log = visit_all(c);
  CHECK(log.count == 2 && !log.out_of_order);
  fb_mat_free(&c);
  fb_mat_free(&o);

  /* (1 1) (1, -1)^T = 0: the exact cancellation is not stored. */
  const double minus[] = {1, -1};
  fb_mat *row = triplets(1, 2, 2, (const size_t[]){0, 0}, (const size_t[]){0, 1}, ones);
  fb_mat *col = dense_rowmajor(2, 1, minus);
  CHECK(fb_mat_multiply(row, col, &c, &err) == FB_OK);
  CHECK(c && fb_mat_nnz(c) == 0 && fb_mat_get(c, 0, 0) == 0.0);
  fb_mat_free(&c);
  fb_mat_free(&row);
  fb_mat_free(&col);
  fb_mat_free(&p);
}

/* 1-norm (largest absolute column sum) of an n x n row-major array. */
static double norm1(size_t n, const double *rm)
{
  double best = 0.0;
  for (size_t j = 0; j < n; ++j) {
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i)
      sum += fabs(rm[i * n + j]);
    best = fmax(best, sum);
  }
  return best;
}

/* Largest |(A X - I)_ij| for the n x n a and x. */
static double identity_residual(const fb_mat *a, const fb_mat *x)
{
  fb_err err;
  fb_mat *ax = NULL;
  CHECK(fb_mat_multiply(a, x, &ax, &err) == FB_OK);
  if (!ax)
    return INFINITY;
  double worst = 0.0;
  for (size_t i = 0; i < fb_mat_nrows(a); ++i)
    for (size_t j = 0; j < fb_mat_nrows(a); ++j)
      worst = fmax(worst, fabs(fb_mat_get(ax, i, j) - (i == j)));
  fb_mat_free(&ax);
  return worst;
}

/* Tolerances: an inverse computed by LU with partial pivoting satisfies
 * ||A X - I|| <= c n u cond(A) and ||X - inv(A)|| / ||inv(A)|| <= c n u
 * cond(A) with a modest c (Higham, Accuracy and Stability of Numerical
 * Algorithms, 2nd ed., section 14.3); c = 10 is used here. */
static void test_inverse(void)
{
  fb_err err;
  /* [4 7; 2 6]^-1 = [6 -7; -2 4] / 10 (det 10); cond_1 = 13 * 1.1. */
  const double a_rm[] = {4, 7, 2, 6};
  const double inv_rm[] = {0.6, -0.7, -0.2, 0.4};
  fb_mat *a = dense_rowmajor(2, 2, a_rm);
  fb_mat *x = NULL;
  CHECK(fb_mat_inverse(a, &x, &err) == FB_OK);
  const double cond = norm1(2, a_rm) * norm1(2, inv_rm);
  CHECK_NEAR(identity_residual(a, x), 0.0, 10 * 2 * DBL_EPSILON * cond);
  check_entries(x, 2, 2, inv_rm, 10 * 2 * DBL_EPSILON * cond * norm1(2, inv_rm));
  fb_mat_free(&a);
  fb_mat_free(&x);

  /* Sparse tridiag(-1, 2, -1) of order 4; closed-form inverse
   * (T^-1)_ij = min(i,j) (n + 1 - max(i,j)) / (n + 1), 1-based (Meurant,
   * SIAM J. Matrix Anal. Appl. 13(3), 1992). */
  enum { N = 4 };
  size_t r[3 * N], c[3 * N];
  double v[3 * N], t_rm[N * N] = {0}, tinv_rm[N * N];
  size_t nnz = 0;
  for (size_t i = 0; i < N; ++i) {
    for (size_t j = 0; j < N; ++j) {
      const double lo = (double)(i < j ? i : j) + 1, hi = (double)(i > j ? i : j) + 1;
      tinv_rm[i * N + j] = lo * (N + 1 - hi) / (N + 1);
      const double tij = i == j ? 2.0 : (i + 1 == j || j + 1 == i ? -1.0 : 0.0);
      t_rm[i * N + j] = tij;
      if (tij != 0.0) {
        r[nnz] = i;
        c[nnz] = j;
        v[nnz++] = tij;
      }
    }
  }
  fb_mat *t = triplets(N, N, nnz, r, c, v);
  CHECK(fb_mat_inverse(t, &x, &err) == FB_OK);
  CHECK(x && !fb_mat_is_sparse(x));
  const double tcond = norm1(N, t_rm) * norm1(N, tinv_rm);
  check_entries(x, N, N, tinv_rm, 10 * N * DBL_EPSILON * tcond * norm1(N, tinv_rm));
  CHECK_NEAR(identity_residual(t, x), 0.0, 10 * N * DBL_EPSILON * tcond);
  fb_mat_free(&t);
  fb_mat_free(&x);

  /* Exactly singular: [1 2; 2 4] eliminates to a zero pivot. */
  const double sing_rm[] = {1, 2, 2, 4};
  a = dense_rowmajor(2, 2, sing_rm);
  x = a; /* must be cleared on failure */
  CHECK(fb_mat_inverse(a, &x, &err) == FB_ESOLVER);
  CHECK(x == NULL);
  CHECK(strstr(err.msg, "singular") != NULL);
  fb_mat_free(&a);
  /* Singular, though rounding may leave a tiny nonzero pivot. */
  const double sing3_rm[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  a = dense_rowmajor(3, 3, sing3_rm);
  CHECK(fb_mat_inverse(a, &x, &err) == FB_ESOLVER);
  CHECK(strstr(err.msg, "singular") != NULL);
  fb_mat_free(&a);
  /* [1 1; 1 1+2^-51] is invertible in exact arithmetic, with pivot 2^-51
   * exactly, but cond_1 = (2 + 2^-51)^2 / 2^-51 ~ 9e15 > 1/eps: singular to
   * working precision. */
  const double near_rm[] = {1, 1, 1, 1 + ldexp(1.0, -51)};
  a = dense_rowmajor(2, 2, near_rm);
  CHECK(fb_mat_inverse(a, &x, &err) == FB_ESOLVER);
  CHECK(strstr(err.msg, "singular to working precision") != NULL);
  fb_mat_free(&a);
  a = dense_rowmajor(2, 3, A23_ROWMAJOR);
  CHECK(fb_mat_inverse(a, &x, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "not square") != NULL);
  fb_mat_free(&a);
}

/* A = [0 2 1; 1 0 3; 4 1 0] needs row pivoting (zero diagonal).
 * det A = 25 and inv(A) = [-3 1 6; 12 -4 1; 1 8 -2] / 25 (cofactors), so
 * cond_1(A) = 5 * 16/25 = 3.2. Solutions x1 = (1, 2, 3), x2 = (-1, 0.5, 4)
 * give b1 = (7, 10, 6), b2 = (5, 11, -3.5). The forward error of a
 * backward-stable solve is <= c n u cond(A) ||x|| (Higham, section 9.1)
 * with c = 10 here. */
static void test_lu(void)
{
  fb_err err;
  const size_t r[] = {1, 2, 0, 2, 0, 1};
  const size_t c[] = {0, 0, 1, 1, 2, 2};
  const double v[] = {1, 4, 2, 1, 1, 3};
  const double a_rm[] = {0, 2, 1, 1, 0, 3, 4, 1, 0};
  const double x_true[] = {1, 2, 3, -1, 0.5, 4};
  const double tol = 10 * 3 * DBL_EPSILON * 3.2 * 4.0;
  fb_mat *a[2] = {triplets(3, 3, 6, r, c, v), dense_rowmajor(3, 3, a_rm)};
  for (int k = 0; k < 2; ++k) {
    fb_lu *lu = NULL;
    CHECK(fb_lu_new(a[k], &lu, &err) == FB_OK);
    if (!lu)
      continue;
    CHECK(fb_lu_size(lu) == 3);
    double b[] = {7, 10, 6, 5, 11, -3.5};
    CHECK(fb_lu_solve(lu, b, 2, &err) == FB_OK);
    for (int i = 0; i < 6; ++i)
      CHECK_NEAR(b[i], x_true[i], tol);
    CHECK(fb_lu_solve(lu, NULL, 0, &err) == FB_OK); /* no right-hand side */
    fb_lu_free(&lu);
    CHECK(lu == NULL);
  }
  fb_lu_free(NULL);
  fb_mat_free(&a[0]);
  fb_mat_free(&a[1]);
}

/* Expects fb_lu_new to fail on a with code and a message containing needle. */
static void check_lu_fails(const fb_mat *a, int code, const char *needle)
{
  fb_err err;
  fb_err_clear(&err);
  fb_lu *lu = NULL;
  CHECK(fb_lu_new(a, &lu, &err) == code);
  CHECK(lu == NULL);
  CHECK(strstr(err.msg, needle) != NULL);
  if (!strstr(err.msg, needle))
    fprintf(stderr, "  expected '%s' in: %s\n", needle, err.msg);
}

static void test_lu_singular(void)
{
  /* [1 2; 2 4]: second pivot 4 - 2*2 = 0 exactly. */
  const double sing_rm[] = {1, 2, 2, 4};
  fb_mat *a = dense_rowmajor(2, 2, sing_rm);
  check_lu_fails(a, FB_ESOLVER, "singular");
  fb_mat_free(&a);
  /* Column 1 (0-based) is empty: KLU names it. */
  const size_t r[] = {0, 1, 2};
  const size_t c[] = {0, 0, 2};
  const double v[] = {1, 2, 3};
  a = triplets(3, 3, 3, r, c, v);
  check_lu_fails(a, FB_ESOLVER, "column 1");
  fb_mat_free(&a);
  /* Singular; whether rounding leaves an exact zero pivot or not. */
  const double sing3_rm[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  a = dense_rowmajor(3, 3, sing3_rm);
  check_lu_fails(a, FB_ESOLVER, "singular");
  fb_mat_free(&a);
  /* cond_1 ~ 9e15 > 1/eps, see test_inverse. */
  const double near_rm[] = {1, 1, 1, 1 + ldexp(1.0, -51)};
  a = dense_rowmajor(2, 2, near_rm);
  check_lu_fails(a, FB_ESOLVER, "singular to working precision");
  fb_mat_free(&a);
  a = dense_rowmajor(2, 3, A23_ROWMAJOR);
  check_lu_fails(a, FB_EINVAL, "not square");
  fb_mat_free(&a);
}

static void test_spd(void)
{
  /* tridiag(-1, 2, -1): eigenvalues 2 - 2 cos(k pi / 6) > 0, k = 1..5. */
  const double spd[] = {2,  -1, 0, 0, 0,  -1, 2,  -1, 0, 0, 0,  -1, 2,
                        -1, 0,  0, 0, -1, 2,  -1, 0,  0, 0, -1, 2};
  fb_mat *a = dense_rowmajor(5, 5, spd);
  CHECK(fb_mat_is_spd(a, 0) == 1);
  CHECK(fb_mat_is_spd(a, 1) == 1);
  fb_mat_free(&a);
  /* Path-graph Laplacian: semidefinite, (1, 1, 1, 1) in its null space;
   * its Cholesky pivots are 1, 1, 1, 0 exactly. Stored sparse. */
  const size_t lr[] = {0, 0, 1, 1, 1, 2, 2, 2, 3, 3};
  const size_t lc[] = {0, 1, 0, 1, 2, 1, 2, 3, 2, 3};
  const double lv[] = {1, -1, -1, 2, -1, -1, 2, -1, -1, 1};
  a = triplets(4, 4, 10, lr, lc, lv);
  CHECK(fb_mat_is_spd(a, 0) == 0);
  CHECK(fb_mat_is_spd(a, 1) == 1);
  fb_mat_free(&a);
  /* v v^T, v = (0.1, 0.2, 0.3): rank 1, and the decimal entries are
   * rounded, so its zero eigenvalues come out as +-O(eps). */
  const double w[] = {0.1, 0.2, 0.3};
  double vvt[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      vvt[i * 3 + j] = w[i] * w[j];
  a = dense_rowmajor(3, 3, vvt);
  CHECK(fb_mat_is_spd(a, 1) == 1);
  fb_mat_free(&a);
  /* Indefinite: eigenvalues 3 and -1. */
  const double indef[] = {1, 2, 2, 1};
  a = dense_rowmajor(2, 2, indef);
  CHECK(fb_mat_is_spd(a, 0) == 0);
  CHECK(fb_mat_is_spd(a, 1) == 0);
  fb_mat_free(&a);
  /* Slightly negative eigenvalue -1e-6, far beyond the 2e-12 tolerance. */
  const double neg[] = {1, 0, 0, -1e-6};
  a = dense_rowmajor(2, 2, neg);
  CHECK(fb_mat_is_spd(a, 0) == 0);
  CHECK(fb_mat_is_spd(a, 1) == 0);
  fb_mat_free(&a);
  /* Nonsymmetric although x^T A x = 2|x|^2 + x1 x2 > 0. */
  const double nonsym[] = {2, 1, 0, 2};
  a = dense_rowmajor(2, 2, nonsym);
  CHECK(fb_mat_is_spd(a, 0) == 0);
  CHECK(fb_mat_is_spd(a, 1) == 0);
  CHECK(!fb_mat_is_symmetric(a, 0.4)); /* |1 - 0| = 1 > 0.4 * 2 */
  CHECK(fb_mat_is_symmetric(a, 0.5));  /* 1 <= 0.5 * 2 */
  fb_mat_free(&a);
  /* Only a_01 stored: not symmetric. */
  const size_t r01[] = {0};
  const size_t c01[] = {1};
  const double one[] = {1};
  a = triplets(2, 2, 1, r01, c01, one);
  CHECK(!fb_mat_is_symmetric(a, 0.0));
  fb_mat_free(&a);
  const double nan_rm[] = {1, NAN, NAN, 1};
  a = dense_rowmajor(2, 2, nan_rm);
  CHECK(fb_mat_is_spd(a, 1) == 0);
  fb_mat_free(&a);
  a = dense_rowmajor(2, 3, A23_ROWMAJOR);
  CHECK(fb_mat_is_spd(a, 1) == 0);
  fb_mat_free(&a);
}

/* Writes len bytes of text (NUL bytes included) to a new temporary file;
 * path is a mkstemp template. */
static int write_temp_n(char *path, const char *text, size_t len)
{
  const int fd = mkstemp(path);
  if (fd < 0)
    return 0;
  FILE *fp = fdopen(fd, "w");
  if (!fp) {
    close(fd);
    return 0;
  }
  const int ok = fwrite(text, 1, len, fp) == len;
  return fclose(fp) == 0 && ok;
}

static int write_temp(char *path, const char *text)
{
  return write_temp_n(path, text, strlen(text));
}

static fb_mat *read_text(const char *text)
{
  char path[TEST_PATH_MAX];
  test_tmp_path("fb_test_mat_XXXXXX", path, sizeof path);
  fb_mat *a = NULL;
  fb_err err;
  CHECK(write_temp(path, text));
  CHECK(fb_mat_read_mtx(path, &a, &err) == FB_OK);
  if (!a)
    fprintf(stderr, "  read failed: %s\n", err.msg);
  unlink(path);
  return a;
}

/* %.17g round-trips binary64 exactly, so values are compared exactly; a
 * sparse matrix comes back sparse and a dense one dense. */
static void test_mtx_roundtrip(void)
{
  const size_t r[] = {0, 2, 1, 2, 0};
  const size_t c[] = {0, 0, 1, 3, 3};
  const double v[] = {0.1, 1.0 / 3.0, -1e-300, 1e300, 4 * atan(1.0)};
  fb_mat *a = triplets(3, 4, 5, r, c, v);
  const double d_rm[] = {0.1, 0, -2.5e-7, 1.0 / 7.0};
  fb_mat *d = dense_rowmajor(2, 2, d_rm);
  const fb_mat *both[] = {a, d};
  for (int k = 0; k < 2; ++k) {
    char path[TEST_PATH_MAX];
    test_tmp_path("fb_test_mat_XXXXXX", path, sizeof path);
    fb_err err;
    CHECK(write_temp(path, ""));
    CHECK(fb_mat_write_mtx(both[k], path, &err) == FB_OK);
    fb_mat *back = NULL;
    CHECK(fb_mat_read_mtx(path, &back, &err) == FB_OK);
    unlink(path);
    CHECK(back != NULL);
    if (!back)
      continue;
    CHECK(fb_mat_nrows(back) == fb_mat_nrows(both[k]));
    CHECK(fb_mat_ncols(back) == fb_mat_ncols(both[k]));
    CHECK(visit_all(back).count == visit_all(both[k]).count);
    CHECK(fb_mat_is_sparse(back) == fb_mat_is_sparse(both[k])); /* storage kept */
    for (size_t i = 0; i < fb_mat_nrows(back); ++i)
      for (size_t j = 0; j < fb_mat_ncols(back); ++j)
        CHECK(fb_mat_get(back, i, j) == fb_mat_get(both[k], i, j));
    fb_mat_free(&back);
  }
  fb_mat_free(&a);
  fb_mat_free(&d);
}

static void test_mtx_formats(void)
{
  /* Symmetric coordinate: the lower triangle is mirrored. */
  fb_mat *a = read_text("%%MatrixMarket matrix coordinate real symmetric\n"
                        "% a comment\n"
                        "\n"
                        "3 3 4\n"
                        "1 1 2\n"
                        "2 1 -1.5\n"
                        "  % comment between entries\n"
                        "3 2 -1\n"
                        "3 3 2e0\n");
  const double sym[] = {2, -1.5, 0, -1.5, 0, -1, 0, -1, 2};
  check_entries(a, 3, 3, sym, 0.0);
  CHECK(a && fb_mat_is_sparse(a) && fb_mat_nnz(a) == 6);
  fb_mat_free(&a);
  /* Integer field, mixed-case keywords, CRLF line ends. */
  a = read_text("%%MatrixMarket Matrix Coordinate Integer General\r\n2 3 3\r\n"
                "1 3 -7\r\n2 1 4\r\n1 1 1\r\n");
  const double ints[] = {1, 0, -7, 4, 0, 0};
  check_entries(a, 2, 3, ints, 0.0);
  fb_mat_free(&a);
  /* Array general lists columns in order. */
  a = read_text("%%MatrixMarket matrix array real general\n2 3\n1\n4\n2\n5\n3\n6\n");
  check_entries(a, 2, 3, A23_ROWMAJOR, 0.0);
  CHECK(a && !fb_mat_is_sparse(a));
  fb_mat_free(&a);
  /* Array symmetric lists the lower triangle column by column. */
  a = read_text("%%MatrixMarket matrix array real symmetric\n3 3\n"
                "1\n2\n3\n4\n5\n6\n");
  const double asym[] = {1, 2, 3, 2, 4, 5, 3, 5, 6};
  check_entries(a, 3, 3, asym, 0.0);
  fb_mat_free(&a);
  /* An empty matrix. */
  a = read_text("%%MatrixMarket matrix coordinate real general\n0 0 0\n");
  CHECK(a && fb_mat_nrows(a) == 0 && fb_mat_ncols(a) == 0);
  fb_mat_free(&a);
}

/* Expects reading text to fail with FB_EPARSE, a message starting with
 * "<path>:<line>: " and containing needle. */
static void check_mtx_error(const char *text, size_t line, const char *needle)
{
  char path[TEST_PATH_MAX];
  test_tmp_path("fb_test_mat_XXXXXX", path, sizeof path);
  const int failures_before = check_failures;
  CHECK(write_temp(path, text));
  fb_mat *a = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_mat_read_mtx(path, &a, &err) == FB_EPARSE);
  CHECK(err.code == FB_EPARSE);
  CHECK(a == NULL);
  char prefix[TEST_PATH_MAX + 32];
  snprintf(prefix, sizeof prefix, "%s:%zu: ", path, line);
  char shown[FB_ERR_MSG_MAX + FB_ERR_EXCERPT_MAX + 16];
  fb_err_describe(&err, shown, sizeof shown);
  CHECK(strncmp(shown, prefix, strlen(prefix)) == 0);
  CHECK(strstr(shown, needle) != NULL);
  if (check_failures != failures_before)
    fprintf(stderr, "  expected '%s%s...' got: %s\n", prefix, needle, shown);
  unlink(path);
  fb_mat_free(&a);
}

static void test_mtx_errors(void)
{
  const char *coord = "%%MatrixMarket matrix coordinate real general\n";
  char text[512];
  snprintf(text, sizeof text, "%s%% comment\n\n4 4 2\n9 1 1.0\n1 1 2\n", coord);
  check_mtx_error(text, 5, "row index 9 out of range 1..4");
  snprintf(text, sizeof text, "%s4 3 1\n1 4 1.0\n", coord);
  check_mtx_error(text, 3, "column index 4 out of range 1..3");
  snprintf(text, sizeof text, "%s4 3 1\n0 1 1.0\n", coord);
  check_mtx_error(text, 3, "row index 0 out of range 1..4");
  snprintf(text, sizeof text, "%s2 2 1\n1 1 abc\n", coord);
  check_mtx_error(text, 3, "value: not a number (read: 'abc')");
  snprintf(text, sizeof text, "%s2 2 1\n1 1\n", coord);
  check_mtx_error(text, 3, "missing value");
  snprintf(text, sizeof text, "%s2 2 1\n1 1 1.0 7\n", coord);
  check_mtx_error(text, 3, "unexpected text at the end of the line (read: '7')");
  snprintf(text, sizeof text, "%s2 2 3\n1 1 1\n%% c\n2 2 1\n", coord);
  check_mtx_error(text, 5, "file ends after 2 of the 3 declared entries");
  snprintf(text, sizeof text, "%s2 2 1\n1 1 1\n2 2 1\n", coord);
  check_mtx_error(text, 4, "more entries than the 1 declared");
  snprintf(text, sizeof text, "%s%% only comments\n", coord);
  check_mtx_error(text, 2, "missing size line");
  snprintf(text, sizeof text, "%s2 x 1\n", coord);
  check_mtx_error(text, 2, "expected size line");
  check_mtx_error("%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1\n", 3,
                  "above the diagonal");
  check_mtx_error("%%MatrixMarket matrix coordinate real symmetric\n2 3 0\n", 2,
                  "must be square");
  check_mtx_error("%%MatrixMarket matrix coordinate integer general\n1 1 1\n1 1 1.5\n", 3,
                  "invalid integer value (read: '1.5')");
  check_mtx_error("%%MatrixMarket matrix coordinate complex general\n", 1,
                  "unsupported field: expected real or integer (read: 'complex')");
  check_mtx_error("%%MatrixMarket matrix coordinate real hermitian\n", 1,
                  "unsupported symmetry: expected general or symmetric (read: 'hermitian')");
  check_mtx_error("%%MatrixMarket matrix coordinate pattern general\n", 1,
                  "unsupported field: expected real or integer (read: 'pattern')");
  check_mtx_error("%%MatrixMarket vector coordinate real general\n", 1, "header");
  check_mtx_error("3 3 1\n1 1 1\n", 1, "header");
  check_mtx_error("", 1, "empty file");
  check_mtx_error("%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n", 5,
                  "file ends after 3 of the 4 declared entries");
  check_mtx_error("%%MatrixMarket matrix array real general\n1 1\n1 2\n", 3,
                  "unexpected text at the end of the line (read: '2')");
}

/* Reading len bytes of text fails with FB_EPARSE and exactly the message
 * "path:line: want". */
static void check_mtx_message(const char *text, size_t len, size_t line, const char *want)
{
  char path[TEST_PATH_MAX];
  test_tmp_path("fb_test_mat_XXXXXX", path, sizeof path);
  char msg[FB_ERR_MSG_MAX];
  CHECK(write_temp_n(path, text, len));
  fb_mat *a = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_mat_read_mtx(path, &a, &err) == FB_EPARSE);
  CHECK(a == NULL);
  snprintf(msg, sizeof msg, "%s:%zu: %s", path, line, want);
  char shown[FB_ERR_MSG_MAX + FB_ERR_EXCERPT_MAX + 16];
  const int ok = strcmp(fb_err_describe(&err, shown, sizeof shown), msg) == 0;
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  got    \"%s\"\n  wanted \"%s\"\n", shown, msg);
  unlink(path);
  fb_mat_free(&a);
}

#define CHECK_MTX(text, line, want) check_mtx_message(text, sizeof text - 1, line, want)
#define COORD "%%MatrixMarket matrix coordinate real general\n"

/* A NUL once cut "1500\0009" to 1500; strtod's hexadecimal, "inf" and
 * "nan" were read as numbers; a carriage return inside a line cut it. */
static void test_mtx_strict(void)
{
  CHECK_MTX(COORD "1 1 1\n1 1 1500\0009\n", 3,
            "binary data (byte 0x00 in column 9): not a Matrix Market text file (expected "
            "UTF-8 text)");
  CHECK_MTX(COORD "% \xfe\n1 1 1\n1 1 1\n", 2,
            "binary data (byte 0xfe in column 3): not a Matrix Market text file (expected "
            "UTF-8 text)");
  CHECK_MTX(COORD "1 1 1\n1 1 15\r00\n", 3,
            "binary data (byte 0x0d in column 7): not a Matrix Market text file (expected "
            "UTF-8 text)");
  CHECK_MTX(COORD "2 2 1\n1 1 0x10\n", 3, "value: not a decimal number (read: '0x10')");
  CHECK_MTX(COORD "2 2 1\n1 1 -inf\n", 3, "value: not a finite number (read: '-inf')");
  CHECK_MTX("%%MatrixMarket matrix array real general\n1 1\nnan\n", 3,
            "value: not a finite number (read: 'nan')");
  CHECK_MTX(COORD "2 2 1\n1 1 1e400\n", 3, "value: not a finite number (read: '1e400')");

  /* A byte-order mark before the header is skipped; decimals of every
   * form are read as before. */
  fb_mat *a = read_text("\xef\xbb\xbf%%MatrixMarket matrix coordinate real general\r\n"
                        "2 2 4\r\n1 1 +1.5\r\n1 2 -.25\r\n2 1 3.\r\n2 2 -7.5E-3\r\n");
  const double want[] = {1.5, -0.25, 3.0, -7.5e-3};
  check_entries(a, 2, 2, want, 0.0);
  fb_mat_free(&a);
}

/* The size line is checked before anything is allocated for it: against
 * the dimensions the caller expects, FB_MTX_MAX_DIM when it expects none,
 * the matrix's cells and what the file's bytes can hold. A header of
 * 2e8 x 2e8 once made a 68-byte file allocate 3.2 GB (2e6 here: the old
 * reader allocated 32 MB and returned the matrix). */
static void test_mtx_declared_sizes(void)
{
  CHECK_MTX(COORD "2000000 3 1\n1 1 1\n", 2,
            "2000000 rows, more than the 1000000 a Matrix Market file may declare "
            "(docs/errors.md, \"Limits\")");
  CHECK_MTX(COORD "3 2000000 1\n1 1 1\n", 2,
            "2000000 columns, more than the 1000000 a Matrix Market file may declare "
            "(docs/errors.md, \"Limits\")");
  CHECK_MTX(COORD "2 2 5\n1 1 1\n", 2, "5 entries declared, more than the 4 of a 2 x 2 matrix");
  CHECK_MTX("%%MatrixMarket matrix coordinate real symmetric\n2 2 4\n1 1 1\n", 2,
            "4 entries declared, more than the 3 of a 2 x 2 symmetric (lower triangle) matrix");
  CHECK_MTX(COORD "1000 1000 20\n1 1 1\n", 2,
            "20 entries declared, more than the file's 65 bytes can hold (each takes at least "
            "6)");
  CHECK_MTX("%%MatrixMarket matrix array real general\n100 100\n1\n", 2,
            "10000 entries declared, more than the file's 51 bytes can hold (each takes at "
            "least 2)");

  char path[TEST_PATH_MAX];
  test_tmp_path("fb_test_mat_XXXXXX", path, sizeof path);
  fb_mat *a = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(write_temp(path, COORD "3 2 1\n1 1 1\n"));
  CHECK(fb_mat_read_mtx_dims(path, 2, 2, &a, &err) == FB_EPARSE);
  CHECK(a == NULL);
  CHECK(strstr(err.msg, ":2: the matrix has 3 rows, expected 2") != NULL);
  CHECK(fb_mat_read_mtx_dims(path, 3, 3, &a, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, ":2: the matrix has 2 columns, expected 3") != NULL);
  CHECK(fb_mat_read_mtx_dims(path, 3, 2, &a, &err) == FB_OK);
  CHECK(a && fb_mat_nrows(a) == 3 && fb_mat_ncols(a) == 2);
  fb_mat_free(&a);
  /* 0: that dimension is not known. */
  CHECK(fb_mat_read_mtx_dims(path, 0, 2, &a, &err) == FB_OK);
  fb_mat_free(&a);
  unlink(path);
}

static void test_mtx_io_errors(void)
{
  fb_err err;
  fb_mat *a = NULL;
  char missing[TEST_PATH_MAX];
  test_tmp_path("no_such_file.mtx", missing, sizeof missing);
  CHECK(fb_mat_read_mtx(missing, &a, &err) == FB_EIO);
  CHECK(a == NULL);
  CHECK(strstr(err.msg, missing) != NULL);
  CHECK(strstr(err.msg, strerror(ENOENT)) != NULL);
  a = dense_rowmajor(2, 3, A23_ROWMAJOR);
  CHECK(fb_mat_write_mtx(a, "/nonexistent_fb_dir/out.mtx", &err) == FB_EIO);
  CHECK(strstr(err.msg, "/nonexistent_fb_dir/out.mtx") != NULL);
  CHECK(strstr(err.msg, strerror(ENOENT)) != NULL);
  fb_mat_free(&a);
}

/* c = alpha a + beta b against the hand sum, mixed storage, and the
 * size check. */
static void test_axpby(void)
{
  fb_err err;
  fb_err_clear(&err);
  const double av[4] = {1.0, 2.0, 0.0, 3.0}, d[2] = {4.0, 5.0};
  fb_mat *a = NULL, *b = NULL, *c = NULL, *e = NULL;
  CHECK(fb_mat_new_dense_rowmajor(2, 2, av, &a, &err) == FB_OK);
  CHECK(fb_mat_new_diag(2, d, &b, &err) == FB_OK);
  CHECK(fb_mat_axpby(2.0, a, -1.0, b, &c, &err) == FB_OK);
  if (c) {
    CHECK(fb_mat_get(c, 0, 0) == -2.0 && fb_mat_get(c, 0, 1) == 4.0);
    CHECK(fb_mat_get(c, 1, 0) == 0.0 && fb_mat_get(c, 1, 1) == 1.0);
    CHECK(fb_mat_nnz(c) == 3); /* the zero at (1, 0) is not stored */
  }
  fb_mat_free(&c);
  CHECK(fb_mat_axpby(0.5, b, 0.0, NULL, &c, &err) == FB_OK);
  CHECK(c && fb_mat_get(c, 1, 1) == 2.5 && fb_mat_get(c, 0, 1) == 0.0);
  CHECK(fb_mat_new_scaled_identity(3, 1.0, &e, &err) == FB_OK);
  fb_mat *bad = NULL;
  CHECK(fb_mat_axpby(1.0, a, 1.0, e, &bad, &err) == FB_EINVAL && bad == NULL);
  CHECK(strstr(err.msg, "2 x 2 plus 3 x 3") != NULL);
  fb_mat_free(&a);
  fb_mat_free(&b);
  fb_mat_free(&c);
  fb_mat_free(&e);
}

int main(void)
{
  test_axpby();
  test_gemv();
  test_construction();
  test_foreach_dense_and_finite();
  test_triplets();
  test_clone_transpose();
  test_multiply();
  test_inverse();
  test_lu();
  test_lu_singular();
  test_spd();
  test_mtx_roundtrip();
  test_mtx_formats();
  test_mtx_errors();
  test_mtx_strict();
  test_mtx_declared_sizes();
  test_mtx_io_errors();
  return check_report("test_mat");
}
