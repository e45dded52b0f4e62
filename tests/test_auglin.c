/* SPDX-License-Identifier: BSD-3-Clause */
/* Augmented Newton solver (src/sim/auglin.c) on small systems whose
 * Newton matrix I - gamma J is known by hand. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "check.h"
#include "sim/auglin.h"

/* A mass-spring-damper written as a block diagram. States p (momentum)
 * and q (displacement); signals v = p / m and e = k q; p' = -e - r v,
 * q' = v. Unknowns z = [v, p, e, q], so the states are not the leading
 * rows. Rows of P(gamma) (state rows carry dx - gamma dx'):
 *   p: dp + gamma de + gamma r dv = b_p
 *   q: dq - gamma dv             = b_q
 *   v: dv - dp / m               = 0
 *   e: de - k dq                 = 0
 * Eliminating v and e leaves I - gamma J with J = [-r/m, -k; 1/m, 0]. The
 * (p, p) and (p, v) entries are split into two triplets each, which the
 * solver must sum. */
enum { Z_V, Z_P, Z_E, Z_Q, NZ };
#define NNZ 11

static const size_t msd_rows[NNZ] = {Z_P, Z_P, Z_P, Z_P, Z_P, Z_Q, Z_Q, Z_V, Z_V, Z_E, Z_E};
static const size_t msd_cols[NNZ] = {Z_P, Z_E, Z_V, Z_P, Z_V, Z_Q, Z_V, Z_V, Z_P, Z_E, Z_Q};
static const size_t msd_states[2] = {Z_P, Z_Q};

static void msd_values(double m, double k, double r, double *v0, double *v1)
{
  const double a0[NNZ] = {0.25, 0, 0, 0.75, 0, 1, 0, 1, -1 / m, 1, -k};
  const double a1[NNZ] = {0, 1, 0.5 * r, 0, 0.5 * r, 0, -1, 0, 0, 0, 0};
  memcpy(v0, a0, sizeof a0);
  memcpy(v1, a1, sizeof a1);
}

/* (I - gamma J)^-1 b by Cramer's rule on [1 + gamma r/m, gamma k;
 * -gamma/m, 1], the independent answer. */
static void msd_exact(double m, double k, double r, double gamma, const double b[2],
                      double x[2])
{
  const double a11 = 1 + gamma * r / m, a12 = gamma * k, a21 = -gamma / m, a22 = 1;
  const double det = a11 * a22 - a12 * a21;
  x[0] = (b[0] * a22 - a12 * b[1]) / det;
  x[1] = (a11 * b[1] - a21 * b[0]) / det;
}

/* KLU with partial pivoting is backward stable; these matrices have
 * condition numbers below 1e3, so 1e-12 relative leaves a wide margin. */
#define REL_TOL 1e-12

static void check_msd_solve(fb_auglin *al, double m, double k, double r, double gamma)
{
  double v0[NNZ], v1[NNZ];
  msd_values(m, k, r, v0, v1);
  fb_err err;
  CHECK(fb_auglin_setup(al, gamma, v0, v1, &err) == FB_OK);
  const double b[2] = {0.7, -1.3};
  double x[2], want[2];
  CHECK(fb_auglin_solve(al, b, x, &err) == FB_OK);
  msd_exact(m, k, r, gamma, b, want);
  for (int i = 0; i < 2; ++i)
    CHECK_NEAR(x[i], want[i], REL_TOL * (fabs(want[i]) + 1));
  /* b and x may alias. */
  double bx[2] = {b[0], b[1]};
  CHECK(fb_auglin_solve(al, bx, bx, &err) == FB_OK);
  CHECK_NEAR(bx[0], x[0], 0.0);
  CHECK_NEAR(bx[1], x[1], 0.0);
}

static void test_msd(void)
{
  fb_auglin *al = NULL;
  fb_err err;
  CHECK(fb_auglin_new(NZ, NNZ, msd_rows, msd_cols, NULL, msd_states, 2, &al, &err) == FB_OK);
  if (!al)
    return;
  CHECK(fb_auglin_nfactorizations(al) == 0);
  /* A solve before any setup has nothing to use. */
  double x[2];
  const double b[2] = {1, 1};
  CHECK(fb_auglin_solve(al, b, x, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "factorisation") != NULL);

  check_msd_solve(al, 2.0, 50.0, 3.0, 1e-3);
  CHECK(fb_auglin_nfactorizations(al) == 1);
  /* A new gamma and new values: refactorisation with the same pattern. */
  check_msd_solve(al, 0.5, 800.0, 0.1, 0.25);
  CHECK(fb_auglin_nfactorizations(al) == 2);
  check_msd_solve(al, 0.5, 800.0, 0.1, 0.0);
  fb_auglin_free(&al);
  CHECK(al == NULL);
  fb_auglin_free(&al); /* NULL is accepted */
}

/* With r = 0 and k = -m / gamma^2 the determinant 1 + gamma^2 k / m of
 * I - gamma J vanishes: setup must report it, solve must refuse, and a
 * later regular setup must recover. */
static void test_singular(void)
{
  fb_auglin *al = NULL;
  fb_err err;
  CHECK(fb_auglin_new(NZ, NNZ, msd_rows, msd_cols, NULL, msd_states, 2, &al, &err) == FB_OK);
  if (!al)
    return;
  double v0[NNZ], v1[NNZ];
  msd_values(1.0, -4.0, 0.0, v0, v1);
  CHECK(fb_auglin_setup(al, 0.5, v0, v1, &err) == FB_ESOLVER);
  CHECK(strstr(err.msg, "singular") != NULL);
  CHECK(strstr(err.msg, "gamma = 0.5") != NULL);
  double x[2];
  const double b[2] = {1, 1};
  CHECK(fb_auglin_solve(al, b, x, &err) == FB_EINVAL);
  check_msd_solve(al, 1.0, -4.0, 0.0, 0.25);
  /* Singular after a good factorisation (refactor path, then full). */
  CHECK(fb_auglin_setup(al, 0.5, v0, v1, &err) == FB_ESOLVER);
  CHECK(fb_auglin_solve(al, b, x, &err) == FB_EINVAL);
  fb_auglin_free(&al);
}

/* P = [a, 1; 1, 2] with a = 1 - gamma, both unknowns states. The first
 * factorisation (a = 1) pivots on the diagonal; reusing that order for
 * a ~ 1e-14 would divide by a tiny pivot and lose about 14 digits, so the
 * solver must notice (pivot ratio) and factorise afresh with pivoting. */
static void test_pivot_fallback(void)
{
  const size_t rows[4] = {0, 0, 1, 1}, cols[4] = {0, 1, 0, 1}, states[2] = {0, 1};
  const double v0[4] = {1, 1, 1, 2}, v1[4] = {-1, 0, 0, 0};
  fb_auglin *al = NULL;
  fb_err err;
  CHECK(fb_auglin_new(2, 4, rows, cols, NULL, states, 2, &al, &err) == FB_OK);
  if (!al)
    return;
  CHECK(fb_auglin_setup(al, 0.0, v0, v1, &err) == FB_OK);
  const double gamma = 1 - 1e-14;
  CHECK(fb_auglin_setup(al, gamma, v0, v1, &err) == FB_OK);
  CHECK(fb_auglin_nfactorizations(al) == 3); /* factor, refactor, factor */
  const double a = v0[0] + gamma * v1[0];
  const double b[2] = {0.3, 0.7};
  double x[2];
  CHECK(fb_auglin_solve(al, b, x, &err) == FB_OK);
  /* Cramer: det = 2 a - 1. */
  const double want0 = (2 * b[0] - b[1]) / (2 * a - 1), want1 = (a * b[1] - b[0]) / (2 * a - 1);
  CHECK_NEAR(x[0], want0, REL_TOL);
  CHECK_NEAR(x[1], want1, REL_TOL);
  fb_auglin_free(&al);
}

/* A row with no entries makes P structurally singular. */
static void test_structurally_singular(void)
{
  const size_t rows[3] = {0, 0, 2}, cols[3] = {0, 1, 2}, states[1] = {0};
  const double v0[3] = {1, 1, 1}, v1[3] = {0, 0, 0};
  fb_auglin *al = NULL;
  fb_err err;
  CHECK(fb_auglin_new(3, 3, rows, cols, NULL, states, 1, &al, &err) == FB_OK);
  if (!al)
    return;
  CHECK(fb_auglin_setup(al, 0.1, v0, v1, &err) == FB_ESOLVER);
  CHECK(strstr(err.msg, "singular") != NULL);
  fb_auglin_free(&al);
}

/* The mass-spring-damper with every row a unit row (v, e and the two
 * state rows define their unknown explicitly): the elimination must keep
 * one unknown of the cycle p -> e, v -> q -> ... and still give Cramer's
 * answer. */
static void test_msd_eliminated(void)
{
  const unsigned char unit[NZ] = {1, 1, 1, 1};
  fb_auglin *al = NULL;
  fb_err err;
  CHECK(fb_auglin_new(NZ, NNZ, msd_rows, msd_cols, unit, msd_states, 2, &al, &err) == FB_OK);
  if (!al)
    return;
  /* One cycle, p -> e, v -> q -> e ... -> p: one unknown kept. */
  CHECK(fb_auglin_nkept(al) == 1);
  check_msd_solve(al, 2.0, 50.0, 3.0, 1e-3);
  check_msd_solve(al, 0.5, 800.0, 0.1, 0.25);
  fb_auglin_free(&al);
}

/* The same system numbered z = [p, v, e, q]: the search now starts at
 * the state p and keeps it (the cycle closes back on p), so the solution
 * at a kept state is read from the factorised part directly. */
static void test_msd_state_kept(void)
{
  static const size_t perm[NZ] = {[Z_V] = 1, [Z_P] = 0, [Z_E] = 2, [Z_Q] = 3};
  size_t rows[NNZ], cols[NNZ];
  for (size_t k = 0; k < NNZ; ++k) {
    rows[k] = perm[msd_rows[k]];
    cols[k] = perm[msd_cols[k]];
  }
  const size_t states[2] = {perm[Z_P], perm[Z_Q]};
  const unsigned char unit[NZ] = {1, 1, 1, 1};
  fb_auglin *al = NULL;
  fb_err err;
  CHECK(fb_auglin_new(NZ, NNZ, rows, cols, unit, states, 2, &al, &err) == FB_OK);
  if (!al)
    return;
  CHECK(fb_auglin_nkept(al) == 1);
  check_msd_solve(al, 2.0, 50.0, 3.0, 1e-3);
  check_msd_solve(al, 0.5, 800.0, 0.1, 0.25);
  fb_auglin_free(&al);
}

/* A 2-DOF structure with a consistent mass matrix, as a finite-element
 * field enters the diagram: states p (2), q (2); signals v from the solve
 * M v = p (not a unit row), e = K q, d = B v, s = -e - d; p' = s, q' = v.
 * Unknowns z = [p1 p2 q1 q2 v1 v2 e1 e2 d1 d2 s1 s2]. Only v is kept, and
 * the kept matrix is M + gamma B + gamma^2 K. The answer is checked
 * against a dense solve of I - gamma J, J = [-B M^-1, -K; M^-1, 0]. */
enum { S_P = 0, S_Q = 2, S_V = 4, S_E = 6, S_D = 8, S_S = 10, S_NZ = 12 };

static void fem2_triplets(size_t *rows, size_t *cols, double *v0, double *v1, size_t *nnz)
{
  const double m[4] = {2.0, 0.5, 0.5, 1.0}, k[4] = {300, -100, -100, 200};
  const double bm[4] = {3.0, -1.0, -1.0, 2.0};
  size_t n = 0;
#define PUT(r, c, a0, a1) (rows[n] = (r), cols[n] = (c), v0[n] = (a0), v1[n] = (a1), ++n)
  for (size_t i = 0; i < 2; ++i) {
    PUT(S_P + i, S_P + i, 1, 0);
    PUT(S_P + i, S_S + i, 0, -1);
    PUT(S_Q + i, S_Q + i, 1, 0);
    PUT(S_Q + i, S_V + i, 0, -1);
    PUT(S_V + i, S_P + i, -1, 0);
    PUT(S_E + i, S_E + i, 1, 0);
    PUT(S_D + i, S_D + i, 1, 0);
    PUT(S_S + i, S_S + i, 1, 0);
    PUT(S_S + i, S_E + i, 1, 0);
    PUT(S_S + i, S_D + i, 1, 0);
    for (size_t j = 0; j < 2; ++j) {
      PUT(S_V + i, S_V + j, m[2 * j + i], 0);
      PUT(S_E + i, S_Q + j, -k[2 * j + i], 0);
      PUT(S_D + i, S_V + j, -bm[2 * j + i], 0);
    }
  }
#undef PUT
  *nnz = n;
}

/* x = (I - gamma J)^-1 b by Gaussian elimination with partial pivoting on
 * the 4 x 4 dense matrix, J from M^-1 in closed form. */
static void fem2_dense(double gamma, const double b[4], double x[4])
{
  const double det = 2.0 * 1.0 - 0.5 * 0.5;
  const double mi[4] = {1.0 / det, -0.5 / det, -0.5 / det, 2.0 / det};
  const double k[4] = {300, -100, -100, 200}, bm[4] = {3.0, -1.0, -1.0, 2.0};
  double a[4][5];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      double bmi = 0;
      for (int l = 0; l < 2; ++l)
        bmi += bm[2 * l + i] * mi[2 * j + l];
      a[i][j] = (i == j) + gamma * bmi;
      a[i][j + 2] = gamma * k[2 * j + i];
      a[i + 2][j] = -gamma * mi[2 * j + i];
      a[i + 2][j + 2] = (i == j);
    }
  for (int i = 0; i < 4; ++i)
    a[i][4] = b[i];
  for (int c = 0; c < 4; ++c) {
    int piv = c;
    for (int r = c + 1; r < 4; ++r)
      if (fabs(a[r][c]) > fabs(a[piv][c]))
        piv = r;
    for (int j = 0; j < 5; ++j) {
      const double t = a[c][j];
      a[c][j] = a[piv][j];
      a[piv][j] = t;
    }
    for (int r = c + 1; r < 4; ++r) {
      const double f = a[r][c] / a[c][c];
      for (int j = c; j < 5; ++j)
        a[r][j] -= f * a[c][j];
    }
  }
  for (int i = 3; i >= 0; --i) {
    double v = a[i][4];
    for (int j = i + 1; j < 4; ++j)
      v -= a[i][j] * x[j];
    x[i] = v / a[i][i];
  }
}

static void test_fem_condensed(void)
{
  size_t rows[64], cols[64], nnz = 0;
  double v0[64], v1[64];
  fem2_triplets(rows, cols, v0, v1, &nnz);
  unsigned char unit[S_NZ];
  for (size_t i = 0; i < S_NZ; ++i)
    unit[i] = !(i == S_V || i == S_V + 1);
  const size_t states[4] = {S_P, S_P + 1, S_Q, S_Q + 1};
  for (int condensed = 0; condensed < 2; ++condensed) {
    fb_auglin *al = NULL;
    fb_err err;
    CHECK(fb_auglin_new(S_NZ, nnz, rows, cols, condensed ? unit : NULL, states, 4, &al, &err) ==
          FB_OK);
    if (!al)
      return;
    /* Condensed: the two velocities; S = M + gamma B + gamma^2 K has the
     * full 2 x 2 pattern. */
    CHECK(fb_auglin_nkept(al) == (condensed ? 2u : (size_t)S_NZ));
    if (condensed)
      CHECK(fb_auglin_kept_nnz(al) == 4);
    for (double gamma = 1e-4; gamma < 2; gamma *= 30) {
      CHECK(fb_auglin_setup(al, gamma, v0, v1, &err) == FB_OK);
      const double b[4] = {1.5, -0.2, 0.03, 0.4};
      double x[4], want[4];
      CHECK(fb_auglin_solve(al, b, x, &err) == FB_OK);
      fem2_dense(gamma, b, want);
      /* Both are backward-stable solves of a matrix with condition below
       * 1e4 for these gammas: 1e-11 relative to the size of the
       * velocity components (plus 1, absolute). */
      for (int i = 0; i < 4; ++i)
        CHECK_NEAR(x[i], want[i], 1e-11 * (fabs(want[0]) + fabs(want[1]) + 1));
    }
    fb_auglin_free(&al);
  }
}

static void test_bad_pattern(void)
{
  fb_auglin *al = NULL;
  fb_err err;
  const size_t rows[2] = {0, 3}, cols[2] = {0, 1}, states[2] = {0, 1}, same[2] = {1, 1};
  CHECK(fb_auglin_new(3, 2, rows, cols, NULL, states, 2, &al, &err) == FB_EINVAL);
  CHECK(al == NULL);
  CHECK(strstr(err.msg, "triplet 1 at (3, 1)") != NULL);
  CHECK(fb_auglin_new(3, 1, rows, cols, NULL, same, 2, &al, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "share row 1") != NULL);
  CHECK(fb_auglin_new(0, 0, rows, cols, NULL, states, 0, &al, &err) == FB_EINVAL);
  CHECK(fb_auglin_new(1, 1, rows, cols, NULL, states, 2, &al, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "2 states in 1 unknowns") != NULL);
}

int main(void)
{
  test_msd();
  test_msd_eliminated();
  test_msd_state_kept();
  test_fem_condensed();
  test_singular();
  test_pivot_fallback();
  test_structurally_singular();
  test_bad_pattern();
  return check_report("test_auglin");
}
