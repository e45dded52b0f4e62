/* SPDX-License-Identifier: BSD-3-Clause */
/* Block diagrams from bond graphs: right-hand side and linearisation
 * against hand-written state equations, the augmented Newton matrix
 * against the dense Jacobian, algebraic-loop diagnostics. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"

#include "bgtest_util.h"
#include "check.h"

enum { QC_MS, QC_MU, QC_KS, QC_CS, QC_KT };
static const double qc[] = {250.0, 35.0, 16000.0, 1000.0, 160000.0};
static const double grav = 9.81;

/* Quarter car (sprung ms, unsprung mu, suspension ks || cs, tire kt) on a
 * road velocity source, with gravity. Springs between two velocities sit
 * on a 1-junction fed by a 0-junction that forms the relative velocity. */
static fb_bg *quarter_car(double road_velocity, fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("quarter_car", &bg, err), err);
  MUST(add_const_source(bg, "road", FB_BG_SF, road_velocity, err), err);
  MUST(add_const_source(bg, "gs", FB_BG_SE, -qc[QC_MS] * grav, err), err);
  MUST(add_const_source(bg, "gu", FB_BG_SE, -qc[QC_MU] * grav, err), err);
  MUST(add_scalar(bg, "ms", FB_BG_I, qc[QC_MS], err), err);
  MUST(add_scalar(bg, "mu", FB_BG_I, qc[QC_MU], err), err);
  MUST(add_scalar(bg, "ks", FB_BG_C, qc[QC_KS], err), err);
  MUST(add_scalar(bg, "cs", FB_BG_R, qc[QC_CS], err), err);
  MUST(add_scalar(bg, "kt", FB_BG_C, qc[QC_KT], err), err);
  MUST(fb_bg_add_junction(bg, "Js", FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "Ju", FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "Jsus0", FB_BG_J0, 1, err), err);
  MUST(fb_bg_add_junction(bg, "Jsus", FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "Jt0", FB_BG_J0, 1, err), err);
  MUST(fb_bg_add_junction(bg, "Jt", FB_BG_J1, 1, err), err);
  MUST(fb_bg_connect(bg, "b_road", "road", "Jt0", err), err);
  MUST(fb_bg_connect(bg, "b_tire_u", "Jt0", "Ju", err), err);
  MUST(fb_bg_connect(bg, "b_tire", "Jt0", "Jt", err), err);
  MUST(fb_bg_connect(bg, "b_kt", "Jt", "kt", err), err);
  MUST(fb_bg_connect(bg, "b_mu", "Ju", "mu", err), err);
  MUST(fb_bg_connect(bg, "b_gu", "gu", "Ju", err), err);
  MUST(fb_bg_connect(bg, "b_us", "Ju", "Jsus0", err), err);
  MUST(fb_bg_connect(bg, "b_ss", "Jsus0", "Js", err), err);
  MUST(fb_bg_connect(bg, "b_sus", "Jsus0", "Jsus", err), err);
  MUST(fb_bg_connect(bg, "b_ks", "Jsus", "ks", err), err);
  MUST(fb_bg_connect(bg, "b_cs", "Jsus", "cs", err), err);
  MUST(fb_bg_connect(bg, "b_ms", "Js", "ms", err), err);
  MUST(fb_bg_connect(bg, "b_gs", "gs", "Js", err), err);
  return bg;
}

static long state_index(const fb_bd *bd, const char *name)
{
  for (size_t i = 0; i < fb_bd_nstates(bd); ++i)
    if (strcmp(fb_bd_state_name(bd, i), name) == 0)
      return (long)i;
  return -1;
}

/* Hand-written quarter-car equations, x = [p_s, p_u, q_s, q_t] with
 * q_s = z_u - z_s (suspension compression), q_t = z_r - z_u:
 *   p_s' = ks q_s + cs (v_u - v_s) - ms g
 *   p_u' = kt q_t - ks q_s - cs (v_u - v_s) - mu g
 *   q_s' = v_u - v_s,   q_t' = v_r - v_u. */
static void hand_rhs(const double *x, double vr, double *xd)
{
  double vs = x[0] / qc[QC_MS], vu = x[1] / qc[QC_MU];
  double fs = qc[QC_KS] * x[2] + qc[QC_CS] * (vu - vs);
  xd[0] = fs - qc[QC_MS] * grav;
  xd[1] = qc[QC_KT] * x[3] - fs - qc[QC_MU] * grav;
  xd[2] = vu - vs;
  xd[3] = vr - vu;
}

/* Sorted eigenvalues of a dense n x n matrix (destroys a). */
static int cmp_eig(const void *a, const void *b)
{
  const double *x = a, *y = b;
  if (x[1] != y[1])
    return (x[1] > y[1]) - (x[1] < y[1]);
  return (x[0] > y[0]) - (x[0] < y[0]);
}

static void eigenvalues(size_t n, double *a, double *pairs)
{
  double *wr = malloc(n * sizeof *wr), *wi = malloc(n * sizeof *wi);
  lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', (lapack_int)n, a, (lapack_int)n,
                                  wr, wi, NULL, 1, NULL, 1);
  CHECK(info == 0);
  for (size_t i = 0; i < n; ++i) {
    pairs[2 * i] = wr[i];
    pairs[2 * i + 1] = wi[i];
  }
  qsort(pairs, n, 2 * sizeof *pairs, cmp_eig);
  free(wr);
  free(wi);
}

static void test_quarter_car(void)
{
  fb_err err;
  fb_err_clear(&err);
  const double vr = 0.3;
  fb_bg *bg = quarter_car(vr, &err);
  fb_bd *bd = NULL;
  MUST(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  if (!bd) {
    fb_bg_free(&bg);
    return;
  }
  CHECK(fb_bd_nstates(bd) == 4);
  CHECK(fb_bd_is_linear(bd));
  const char *names[4] = {"ms.p", "mu.p", "ks.q", "kt.q"};
  long idx[4];
  for (int i = 0; i < 4; ++i) {
    idx[i] = state_index(bd, names[i]);
    CHECK(idx[i] >= 0);
  }
  /* Right-hand side at an arbitrary state equals the hand equations to
   * rounding (a few ulps of the largest term, ~1e5 N). */
  const double xh[4] = {120.0, -15.0, 0.012, -0.004};
  double x[4], xd[4], xdh[4];
  for (int i = 0; i < 4; ++i)
    x[idx[i]] = xh[i];
  CHECK(fb_bd_rhs(bd, 0.0, x, xd) == 0);
  hand_rhs(xh, vr, xdh);
  for (int i = 0; i < 4; ++i)
    CHECK_NEAR(xd[idx[i]], xdh[i], 1e-9);
  /* Jacobian from the blocks' linearisations equals the hand matrix,
   * built column by column from the (linear) hand equations. */
  double jac[16], hand[16], base[4];
  MUST(fb_bd_jacobian_dense(bd, 0.0, x, jac, &err), &err);
  hand_rhs((double[4]){0, 0, 0, 0}, 0.0, base);
  for (int j = 0; j < 4; ++j) {
    double e[4] = {0, 0, 0, 0}, col[4];
    e[j] = 1.0;
    hand_rhs(e, 0.0, col);
    for (int i = 0; i < 4; ++i)
      hand[j * 4 + i] = col[i] - base[i];
  }
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      CHECK_NEAR(jac[idx[j] * 4 + idx[i]], hand[j * 4 + i],
                 1e-9 * (1.0 + fabs(hand[j * 4 + i])));
  /* Eigenvalues of both (independent LAPACK runs on the two matrices). */
  double e1[8], e2[8];
  eigenvalues(4, jac, e1);
  eigenvalues(4, hand, e2);
  for (int i = 0; i < 8; ++i)
    CHECK_NEAR(e1[i], e2[i], 1e-9 * 100.0);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* The Schur complement of P(gamma) onto the states is I - gamma J:
 * solving P z = [b; 0] must give (I - gamma J)^-1 b. */
/* The augmented matrix P(gamma) at x, assembled densely and factorised
 * with LAPACK, solves (I - gamma J) z = e_j at the state rows for the
 * dense Jacobian J: (I - gamma J) z_states = e_j to tol. */
static void check_augmented_schur(fb_bd *bd, const double *x, double gamma, double tol)
{
  fb_err err;
  fb_err_clear(&err);
  size_t n = fb_bd_nstates(bd), nz = fb_bd_aug_size(bd), nnz = fb_bd_aug_nnz(bd);
  size_t *rows = malloc(nnz * sizeof *rows), *cols = malloc(nnz * sizeof *cols);
  double *v0 = malloc(nnz * sizeof *v0), *v1 = malloc(nnz * sizeof *v1);
  double *p = calloc(nz * nz, sizeof *p);
  double *jac = malloc(n * n * sizeof *jac), *rhs = calloc(nz, sizeof *rhs);
  lapack_int *piv = malloc(nz * sizeof *piv);
  fb_bd_aug_pattern(bd, rows, cols);
  CHECK(fb_bd_aug_values(bd, 0.0, x, v0, v1) == 0);
  for (size_t k = 0; k < nnz; ++k)
    p[cols[k] * nz + rows[k]] += v0[k] + gamma * v1[k];
  MUST(fb_bd_jacobian_dense(bd, 0.0, x, jac, &err), &err);
  lapack_int info =
      LAPACKE_dgetrf(LAPACK_COL_MAJOR, (lapack_int)nz, (lapack_int)nz, p, (lapack_int)nz, piv);
  CHECK(info == 0);
  for (size_t j = 0; info == 0 && j < n; ++j) {
    memset(rhs, 0, nz * sizeof *rhs);
    rhs[fb_bd_state_row(bd, j)] = 1.0;
    LAPACKE_dgetrs(LAPACK_COL_MAJOR, 'N', (lapack_int)nz, 1, p, (lapack_int)nz, piv, rhs,
                   (lapack_int)nz);
    for (size_t i = 0; i < n; ++i) {
      double r = rhs[fb_bd_state_row(bd, i)];
      for (size_t k = 0; k < n; ++k)
        r -= gamma * jac[k * n + i] * rhs[fb_bd_state_row(bd, k)];
      CHECK_NEAR(r, i == j ? 1.0 : 0.0, tol);
    }
  }
  free(rows);
  free(cols);
  free(v0);
  free(v1);
  free(p);
  free(jac);
  free(rhs);
  free(piv);
}

static void test_augmented(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = quarter_car(0.0, &err);
  fb_probe_spec probes[2] = {
      {"p_cs", FB_PROBE_POWER, "b_cs", -1, 0, 1.0, NULL, NULL, 0},
      {"z_s", FB_PROBE_FLOW, "b_ms", -1, 1, 1.0, NULL, NULL, 0},
  };
  fb_bd *bd = NULL;
  MUST(fb_bd_build(bg, probes, 2, &bd, &err), &err);
  if (!bd) {
    fb_bg_free(&bg);
    return;
  }
  size_t n = fb_bd_nstates(bd);
  CHECK(n == 5); /* 4 + the integrated probe */
  /* The power probe's product feeds no state: the Newton matrix stays
   * constant. Integrated, the product feeds a state and it does not. */
  CHECK(fb_bd_is_linear(bd));
  {
    fb_probe_spec energy = {"w_cs", FB_PROBE_POWER, "b_cs", -1, 1, 1.0, NULL, NULL, 0};
    fb_bd *bd2 = NULL;
    MUST(fb_bd_build(bg, &energy, 1, &bd2, &err), &err);
    if (bd2)
      CHECK(!fb_bd_is_linear(bd2));
    fb_bd_free(&bd2);
  }
  /* The unknowns' names (for messages): a state's row is named as the
   * state; a scalar signal by its name. */
  for (size_t i = 0; i < n; ++i) {
    char name[128];
    fb_bd_aug_unknown_name(bd, fb_bd_state_row(bd, i), name, sizeof name);
    CHECK(strcmp(name, fb_bd_state_name(bd, i)) == 0);
  }
  double x[5];
  for (size_t i = 0; i < n; ++i)
    x[i] = 0.01 * (double)(i + 1);
  /* Entries of gamma J are ~1e3 times z, so rounding leaves ~1e-12. */
  check_augmented_schur(bd, x, 3.7e-3, 1e-10);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* Se -> 1 -> R1 and 1 -> 0 -> {R2, R3}: resistors only, a zero-order
 * causal loop through R1 and the parallel pair. */
static void test_algebraic_loop(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  MUST(fb_bg_new("loop", &bg, &err), &err);
  MUST(add_const_source(bg, "U", FB_BG_SE, 1.0, &err), &err);
  MUST(fb_bg_add_junction(bg, "J1", FB_BG_J1, 1, &err), &err);
  MUST(fb_bg_add_junction(bg, "J0", FB_BG_J0, 1, &err), &err);
  MUST(add_scalar(bg, "R1", FB_BG_R, 1.0, &err), &err);
  MUST(add_scalar(bg, "R2", FB_BG_R, 2.0, &err), &err);
  MUST(add_scalar(bg, "R3", FB_BG_R, 3.0, &err), &err);
  MUST(fb_bg_connect(bg, "b1", "U", "J1", &err), &err);
  MUST(fb_bg_connect(bg, "b2", "J1", "R1", &err), &err);
  MUST(fb_bg_connect(bg, "b3", "J1", "J0", &err), &err);
  MUST(fb_bg_connect(bg, "b4", "J0", "R2", &err), &err);
  MUST(fb_bg_connect(bg, "b5", "J0", "R3", &err), &err);
  fb_bd *bd = NULL;
  CHECK(fb_bd_build(bg, NULL, 0, &bd, &err) == FB_ECAUSAL);
  CHECK(bd == NULL);
  CHECK(strstr(err.msg, "algebraic loop") != NULL);
  CHECK(strstr(err.msg, "R 'R1'") != NULL);
  CHECK(strstr(err.msg, "1-junction 'J1'") != NULL);
  CHECK(strstr(err.msg, "0-junction 'J0'") != NULL);
  fb_bg_free(&bg);
}

/* Two masses, springs and dampers, built once from scalar elements and
 * once from 2-port I, C and R fields: the two diagrams' Jacobians have the
 * same eigenvalues (the states differ by a linear change of variables). */
enum { TD_M1, TD_M2, TD_K1, TD_K2, TD_R1, TD_R2 };
static const double td[] = {3.0, 1.5, 400.0, 250.0, 4.0, 2.5};

static fb_bg *two_dof_scalar(fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("scalar", &bg, err), err);
  MUST(add_const_source(bg, "F", FB_BG_SE, 10.0, err), err);
  MUST(add_scalar(bg, "m1", FB_BG_I, td[TD_M1], err), err);
  MUST(add_scalar(bg, "m2", FB_BG_I, td[TD_M2], err), err);
  MUST(add_scalar(bg, "k1", FB_BG_C, td[TD_K1], err), err);
  MUST(add_scalar(bg, "k2", FB_BG_C, td[TD_K2], err), err);
  MUST(add_scalar(bg, "r1", FB_BG_R, td[TD_R1], err), err);
  MUST(add_scalar(bg, "r2", FB_BG_R, td[TD_R2], err), err);
  MUST(fb_bg_add_junction(bg, "J1", FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "J2", FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "J12", FB_BG_J0, 1, err), err);
  MUST(fb_bg_add_junction(bg, "Jr", FB_BG_J1, 1, err), err);
  MUST(fb_bg_connect(bg, "bF", "F", "J2", err), err);
  MUST(fb_bg_connect(bg, "bm1", "J1", "m1", err), err);
  MUST(fb_bg_connect(bg, "bm2", "J2", "m2", err), err);
  MUST(fb_bg_connect(bg, "bk1", "J1", "k1", err), err);
  MUST(fb_bg_connect(bg, "br1", "J1", "r1", err), err);
  MUST(fb_bg_connect(bg, "b21", "J2", "J12", err), err);
  MUST(fb_bg_connect(bg, "b12", "J12", "J1", err), err);
  MUST(fb_bg_connect(bg, "brel", "J12", "Jr", err), err);
  MUST(fb_bg_connect(bg, "bk2", "Jr", "k2", err), err);
  MUST(fb_bg_connect(bg, "br2", "Jr", "r2", err), err);
  return bg;
}

static int add_field2(fb_bg *bg, const char *name, fb_bg_kind kind, const double *rowmajor,
                      fb_err *err)
{
  fb_mat *m = NULL;
  const size_t dims[2] = {1, 1};
  int rc = fb_mat_new_dense_rowmajor(2, 2, rowmajor, &m, err);
  return rc ? rc : fb_bg_add_field(bg, name, kind, 2, dims, &m, err);
}

static fb_bg *two_dof_fields(fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("fields", &bg, err), err);
  const double m[4] = {td[TD_M1], 0, 0, td[TD_M2]};
  const double k[4] = {td[TD_K1] + td[TD_K2], -td[TD_K2], -td[TD_K2], td[TD_K2]};
  const double r[4] = {td[TD_R1] + td[TD_R2], -td[TD_R2], -td[TD_R2], td[TD_R2]};
  MUST(add_const_source(bg, "F", FB_BG_SE, 10.0, err), err);
  MUST(add_field2(bg, "M", FB_BG_I, m, err), err);
  MUST(add_field2(bg, "K", FB_BG_C, k, err), err);
  MUST(add_field2(bg, "R", FB_BG_R, r, err), err);
  MUST(fb_bg_add_junction(bg, "J1", FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "J2", FB_BG_J1, 1, err), err);
  MUST(fb_bg_connect(bg, "bF", "F", "J2", err), err);
  MUST(fb_bg_connect(bg, "bm1", "J1", "M.1", err), err);
  MUST(fb_bg_connect(bg, "bm2", "J2", "M.2", err), err);
  MUST(fb_bg_connect(bg, "bk1", "J1", "K.1", err), err);
  MUST(fb_bg_connect(bg, "bk2", "J2", "K.2", err), err);
  MUST(fb_bg_connect(bg, "br1", "J1", "R.1", err), err);
  MUST(fb_bg_connect(bg, "br2", "J2", "R.2", err), err);
  return bg;
}

static void test_fields_vs_scalars(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *g1 = two_dof_scalar(&err), *g2 = two_dof_fields(&err);
  fb_bd *d1 = NULL, *d2 = NULL;
  MUST(fb_bd_build(g1, NULL, 0, &d1, &err), &err);
  MUST(fb_bd_build(g2, NULL, 0, &d2, &err), &err);
  if (d1 && d2) {
    CHECK(fb_bd_nstates(d1) == 4 && fb_bd_nstates(d2) == 4);
    double x[4] = {0, 0, 0, 0}, j1[16], j2[16], e1[8], e2[8];
    MUST(fb_bd_jacobian_dense(d1, 0.0, x, j1, &err), &err);
    MUST(fb_bd_jacobian_dense(d2, 0.0, x, j2, &err), &err);
    eigenvalues(4, j1, e1);
    eigenvalues(4, j2, e2);
    /* |lambda| ~ 20 1/s; dgeev's backward error is a few eps * ||A||. */
    for (int i = 0; i < 8; ++i)
      CHECK_NEAR(e1[i], e2[i], 1e-9);
  }
  fb_bd_free(&d1);
  fb_bd_free(&d2);
  fb_bg_free(&g1);
  fb_bg_free(&g2);
}

static void test_dot(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = quarter_car(0.0, &err);
  fb_bd *bd = NULL;
  MUST(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  char *buf = NULL;
  size_t len = 0;
  FILE *fp = open_memstream(&buf, &len);
  MUST(fb_bd_write_dot(bd, fp, &err), &err);
  fclose(fp);
  CHECK(strncmp(buf, "digraph \"quarter_car\"", 21) == 0);
  CHECK(strstr(buf, "I ms\\n1/s") != NULL);
  CHECK(strstr(buf, "ks.e [1]") != NULL);
  CHECK(strstr(buf, "f:b_sus [1]") != NULL);
  if (getenv("FB_DUMP_DOT"))
    fputs(buf, stdout);
  free(buf);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* Rigid bar (bounce z, pitch theta) on two springs through a matrix
 * transformer: point velocities v = T [z'; theta'], T = [1 -x1; 1 -x2].
 * Natural frequencies equal sqrt(eig(M^-1 T' diag(k) T)), assembled by
 * hand (2x2 closed form). */
static void test_mtf_rigid_bar(void)
{
  fb_err err;
  fb_err_clear(&err);
  const double mass = 1200.0, inertia = 1500.0, x1 = 1.3, x2 = -1.7, k1 = 3.0e4, k2 = 4.0e4;
  fb_bg *bg = NULL;
  MUST(fb_bg_new("bar", &bg, &err), &err);
  const size_t two = 2;
  const double md[2] = {mass, inertia}, kd[2] = {k1, k2};
  const double t[4] = {1.0, -x1, 1.0, -x2};
  fb_mat *m = NULL, *k = NULL, *tm = NULL;
  MUST(fb_mat_new_diag(2, md, &m, &err), &err);
  MUST(fb_mat_new_diag(2, kd, &k, &err), &err);
  MUST(fb_mat_new_dense_rowmajor(2, 2, t, &tm, &err), &err);
  MUST(fb_bg_add_field(bg, "hull", FB_BG_I, 1, &two, &m, &err), &err);
  MUST(fb_bg_add_field(bg, "springs", FB_BG_C, 1, &two, &k, &err), &err);
  MUST(fb_bg_add_mtf(bg, "T", &tm, &err), &err);
  MUST(fb_bg_add_junction(bg, "Jh", FB_BG_J1, 2, &err), &err);
  MUST(fb_bg_add_junction(bg, "Jp", FB_BG_J1, 2, &err), &err);
  MUST(fb_bg_connect(bg, "bh", "Jh", "hull", &err), &err);
  MUST(fb_bg_connect(bg, "bt1", "Jh", "T.1", &err), &err);
  MUST(fb_bg_connect(bg, "bt2", "T.2", "Jp", &err), &err);
  MUST(fb_bg_connect(bg, "bk", "Jp", "springs", &err), &err);
  fb_bd *bd = NULL;
  MUST(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  if (bd) {
    double x[4] = {0, 0, 0, 0}, jac[16], ev[8];
    MUST(fb_bd_jacobian_dense(bd, 0.0, x, jac, &err), &err);
    eigenvalues(4, jac, ev);
    /* K = T' diag(k) T; omega^2 are the roots of det(K - w2 M) = 0. */
    double kzz = k1 + k2, kzt = -(k1 * x1 + k2 * x2), ktt = k1 * x1 * x1 + k2 * x2 * x2;
    double a = mass * inertia, b = -(kzz * inertia + ktt * mass), c = kzz * ktt - kzt * kzt;
    double w2lo = (-b - sqrt(b * b - 4 * a * c)) / (2 * a);
    double w2hi = (-b + sqrt(b * b - 4 * a * c)) / (2 * a);
    /* Sorted by imaginary part: -w_hi, -w_lo, +w_lo, +w_hi; real parts 0. */
    CHECK_NEAR(ev[1], -sqrt(w2hi), 1e-9 * sqrt(w2hi));
    CHECK_NEAR(ev[3], -sqrt(w2lo), 1e-9 * sqrt(w2hi));
    CHECK_NEAR(ev[5], sqrt(w2lo), 1e-9 * sqrt(w2hi));
    CHECK_NEAR(ev[7], sqrt(w2hi), 1e-9 * sqrt(w2hi));
    for (int i = 0; i < 4; ++i)
      CHECK_NEAR(ev[2 * i], 0.0, 1e-9 * sqrt(w2hi));
  }
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* Hardening spring e = k q + k3 q^3 as a nonlinear C law. */
static int cubic_eval(void *ctx, const fb_law_in *in, double *y)
{
  const double *k = ctx;
  const size_t n = in->n;
  const double *x = in->x;
  for (size_t i = 0; i < n; ++i)
    y[i] = k[0] * x[i] + k[1] * x[i] * x[i] * x[i];
  return 0;
}
static int cubic_jac(void *ctx, const fb_law_in *in, double *jac)
{
  const double *k = ctx;
  const size_t n = in->n;
  const double *x = in->x;
  for (size_t i = 0; i < n * n; ++i)
    jac[i] = 0.0;
  for (size_t i = 0; i < n; ++i)
    jac[i * n + i] = k[0] + 3.0 * k[1] * x[i] * x[i];
  return 0;
}
static double cubic_energy(void *ctx, size_t n, const double *x)
{
  const double *k = ctx;
  double e = 0.0;
  for (size_t i = 0; i < n; ++i)
    e += 0.5 * k[0] * x[i] * x[i] + 0.25 * k[1] * x[i] * x[i] * x[i] * x[i];
  return e;
}
static const fb_law_ops cubic_ops = {.name = "cubic spring",
                                     .eval = cubic_eval,
                                     .jacobian = cubic_jac,
                                     .energy = cubic_energy,
                                     .free = free};

static void test_nonlinear_law(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  MUST(fb_bg_new("duffing", &bg, &err), &err);
  double *k = malloc(2 * sizeof *k);
  k[0] = 100.0;
  k[1] = 5.0e4;
  const size_t one = 1;
  MUST(add_scalar(bg, "m", FB_BG_I, 2.0, &err), &err);
  MUST(fb_bg_add_field_law(bg, "k", FB_BG_C, 1, &one, &cubic_ops, k, &err), &err);
  MUST(fb_bg_add_junction(bg, "J", FB_BG_J1, 1, &err), &err);
  MUST(fb_bg_connect(bg, "bm", "J", "m", &err), &err);
  MUST(fb_bg_connect(bg, "bk", "J", "k", &err), &err);
  fb_probe_spec probe = {"E_k", FB_PROBE_ENERGY, "k", -1, 0, 1.0, NULL, NULL, 0};
  fb_bd *bd = NULL;
  MUST(fb_bd_build(bg, &probe, 1, &bd, &err), &err);
  if (bd) {
    CHECK(!fb_bd_is_linear(bd));
    long iq = state_index(bd, "k.q"), ip = state_index(bd, "m.p");
    double x[2], xd[2], jac[4], y;
    x[iq] = 0.03;
    x[ip] = 0.5;
    CHECK(fb_bd_rhs(bd, 0.0, x, xd) == 0);
    /* p' = -(k q + k3 q^3), q' = p / m. */
    CHECK_NEAR(xd[ip], -(100.0 * 0.03 + 5.0e4 * 0.03 * 0.03 * 0.03), 1e-12);
    CHECK_NEAR(xd[iq], 0.25, 1e-15);
    CHECK(fb_bd_outputs(bd, 0.0, x, &y) == 0);
    CHECK_NEAR(y, 0.5 * 100.0 * 9e-4 + 0.25 * 5.0e4 * 8.1e-7, 1e-15);
    /* Exact Jacobian vs central differences (error ~ h^2 k3 q = 1e-8). */
    MUST(fb_bd_jacobian_dense(bd, 0.0, x, jac, &err), &err);
    const double h = 1e-6;
    for (int j = 0; j < 2; ++j) {
      double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]}, fp[2], fm[2];
      xp[j] += h;
      xm[j] -= h;
      fb_bd_rhs(bd, 0.0, xp, fp);
      fb_bd_rhs(bd, 0.0, xm, fm);
      for (int i = 0; i < 2; ++i)
        CHECK_NEAR(jac[j * 2 + i], (fp[i] - fm[i]) / (2 * h), 1e-6);
    }
  }
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* A 2-port R field modulated by a spring's compression u, with the
 * non-symmetric bilinear law
 *   e1 = (a + b u) f1 + c f2,   e2 = d f1 + (g + h u) f2,
 * so that a transposed or shifted n x (n + m) Jacobian shows. */
static int bilinear_eval(void *ctx, const fb_law_in *in, double *y)
{
  const double *k = ctx, *x = in->x;
  y[0] = (k[0] + k[1] * x[2]) * x[0] + k[2] * x[1];
  y[1] = k[3] * x[0] + (k[4] + k[5] * x[2]) * x[1];
  return 0;
}
static int bilinear_jac(void *ctx, const fb_law_in *in, double *jac)
{
  const double *k = ctx, *x = in->x;
  /* Column-major 2 x 3: d/df1, d/df2, d/du. */
  jac[0] = k[0] + k[1] * x[2];
  jac[1] = k[3];
  jac[2] = k[2];
  jac[3] = k[4] + k[5] * x[2];
  jac[4] = k[1] * x[0];
  jac[5] = k[5] * x[1];
  return 0;
}
static const fb_law_ops bilinear_ops = {
    .name = "bilinear", .eval = bilinear_eval, .jacobian = bilinear_jac, .free = free};

/* Two masses, each on its own 1-junction with one port of the modulated
 * field; a spring on the first junction is the modulating state. The
 * exact Jacobian against central differences (exact for a bilinear law
 * but for rounding: 1e-7 of the largest entry), and the augmented Newton
 * matrix against it (as test_augmented). */
static void test_modulated_field(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  MUST(fb_bg_new("modulated", &bg, &err), &err);
  double *k = malloc(6 * sizeof *k);
  const double coef[6] = {3.0, 40.0, 0.7, -1.1, 5.0, -30.0};
  memcpy(k, coef, sizeof coef);
  const size_t ports[2] = {1, 1};
  MUST(add_scalar(bg, "m1", FB_BG_I, 2.0, &err), &err);
  MUST(add_scalar(bg, "m2", FB_BG_I, 3.0, &err), &err);
  MUST(add_scalar(bg, "spring", FB_BG_C, 50.0, &err), &err);
  MUST(fb_bg_add_field_law(bg, "R", FB_BG_R, 2, ports, &bilinear_ops, k, &err), &err);
  const char *src = "spring";
  MUST(fb_bg_modulate(bg, "R", 1, &src, &err), &err);
  MUST(fb_bg_add_junction(bg, "J1", FB_BG_J1, 1, &err), &err);
  MUST(fb_bg_add_junction(bg, "J2", FB_BG_J1, 1, &err), &err);
  const char *const bonds[][3] = {{"b1", "J1", "m1"},
                                  {"b2", "J2", "m2"},
                                  {"bs", "J1", "spring"},
                                  {"br1", "J1", "R.1"},
                                  {"br2", "J2", "R.2"}};
  for (size_t i = 0; i < 5; ++i)
    MUST(fb_bg_connect(bg, bonds[i][0], bonds[i][1], bonds[i][2], &err), &err);
  fb_bd *bd = NULL;
  MUST(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  if (bd) {
    CHECK(!fb_bd_is_linear(bd) && fb_bd_nstates(bd) == 3);
    const long ip1 = state_index(bd, "m1.p"), ip2 = state_index(bd, "m2.p"),
               iq = state_index(bd, "spring.q");
    double x[3], xd[3], jac[9];
    x[ip1] = 0.4;
    x[ip2] = -0.9;
    x[iq] = 0.05;
    /* By hand: f1 = 0.2, f2 = -0.3, u = 0.05; p1' = -(k u + e1), p2' = -e2. */
    CHECK(fb_bd_rhs(bd, 0.0, x, xd) == 0);
    const double f1 = 0.2, f2 = -0.3, u = 0.05;
    CHECK_NEAR(xd[ip1], -(50.0 * u + (3.0 + 40.0 * u) * f1 + 0.7 * f2), 1e-14);
    CHECK_NEAR(xd[ip2], -(-1.1 * f1 + (5.0 - 30.0 * u) * f2), 1e-14);
    MUST(fb_bd_jacobian_dense(bd, 0.0, x, jac, &err), &err);
    double worst = 0.0, scale = 0.0;
    for (int j = 0; j < 3; ++j) {
      const double h = 1e-5;
      double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, fp[3], fm[3];
      xp[j] += h;
      xm[j] -= h;
      fb_bd_rhs(bd, 0.0, xp, fp);
      fb_bd_rhs(bd, 0.0, xm, fm);
      for (int i = 0; i < 3; ++i) {
        worst = fmax(worst, fabs(jac[j * 3 + i] - (fp[i] - fm[i]) / (2 * h)));
        scale = fmax(scale, fabs(jac[j * 3 + i]));
      }
    }
    CHECK(worst <= 1e-7 * scale);
    check_augmented_schur(bd, x, 0.02, 1e-10);
  }
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* Softening spring e = k sqrt(q), defined for q >= 0 only: NaN below,
 * and its slope k / (2 sqrt(q)) is inf at q = 0. As a C law it reads the
 * compression, as an R law the flow. */
static int root_eval(void *ctx, const fb_law_in *in, double *y)
{
  const double *k = ctx;
  y[0] = k[0] * sqrt(in->x[0]);
  return 0;
}
static int root_jac(void *ctx, const fb_law_in *in, double *jac)
{
  const double *k = ctx;
  jac[0] = k[0] / (2 * sqrt(in->x[0]));
  return 0;
}
static double root_energy(void *ctx, size_t n, const double *x)
{
  const double *k = ctx;
  (void)n;
  return 2.0 / 3.0 * k[0] * pow(x[0], 1.5);
}
static const fb_law_ops root_ops = {.name = "root",
                                    .eval = root_eval,
                                    .jacobian = root_jac,
                                    .energy = root_energy,
                                    .free = free};

static fb_bg *root_graph(int as_damper, fb_err *err)
{
  fb_bg *bg = NULL;
  double *k = malloc(sizeof *k);
  k[0] = 100.0;
  const size_t one = 1;
  MUST(fb_bg_new("root", &bg, err), err);
  MUST(fb_bg_add_junction(bg, "J", FB_BG_J1, 1, err), err);
  if (as_damper) {
    /* Sf -1 m/s -> J -> R: the law's input and output are constants,
     * folded when the diagram is built. */
    MUST(add_const_source(bg, "v", FB_BG_SF, -1.0, err), err);
    MUST(add_scalar(bg, "c", FB_BG_C, 10.0, err), err);
    MUST(fb_bg_add_field_law(bg, "r", FB_BG_R, 1, &one, &root_ops, k, err), err);
    MUST(fb_bg_connect(bg, "bv", "v", "J", err), err);
    MUST(fb_bg_connect(bg, "bc", "J", "c", err), err);
    MUST(fb_bg_connect(bg, "br", "J", "r", err), err);
  } else {
    MUST(add_scalar(bg, "m", FB_BG_I, 2.0, err), err);
    MUST(fb_bg_add_field_law(bg, "k", FB_BG_C, 1, &one, &root_ops, k, err), err);
    MUST(fb_bg_connect(bg, "bm", "J", "m", err), err);
    MUST(fb_bg_connect(bg, "bk", "J", "k", err), err);
  }
  return bg;
}

/* Checks kind and that buf holds want. */
static void check_explained(fb_bd *bd, const double *x, int jacobian,
                            fb_bd_nonfinite_kind want_kind, const char *want)
{
  char buf[512] = "junk";
  const fb_bd_nonfinite_kind kind =
      fb_bd_explain_nonfinite(bd, 0.0, x, jacobian, buf, sizeof buf);
  CHECK(kind == want_kind);
  CHECK(strstr(buf, want) != NULL && (want[0] || buf[0] == '\0'));
  if (kind != want_kind || !strstr(buf, want))
    fprintf(stderr, "  got %d \"%s\", want %d \"%s\"\n", (int)kind, buf, (int)want_kind, want);
}

/* fb_bd_explain_nonfinite finds where a non-finite value starts: a state,
 * a law evaluated outside its domain (in the evaluation order, or among
 * the folded constants), a law's slope; nothing when all is finite. */
static void test_explain_nonfinite(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = root_graph(0, &err);
  fb_bd *bd = NULL;
  MUST(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  if (bd) {
    const long iq = state_index(bd, "k.q"), ip = state_index(bd, "m.p");
    double x[2] = {0, 0}, xd[2];
    x[ip] = 0.5;
    x[iq] = 0.04;
    check_explained(bd, x, 1, FB_NONFINITE_NONE, "");
    x[iq] = NAN;
    check_explained(bd, x, 0, FB_NONFINITE_STATE, "state k.q = nan");
    /* q < 0: p' = -k sqrt(q) is NaN, from the law of its finite input. */
    x[iq] = -0.01;
    CHECK(fb_bd_rhs(bd, 0.0, x, xd) == 0 && isnan(xd[ip]));
    check_explained(bd, x, 0, FB_NONFINITE_VALUE,
                    "C 'k' (law 'root'): k.e = nan from finite inputs k.q = -0.01");
    /* q = 0: every value is finite, the slope is not. */
    x[iq] = 0.0;
    check_explained(bd, x, 0, FB_NONFINITE_NONE, "");
    check_explained(bd, x, 1, FB_NONFINITE_JACOBIAN,
                    "C 'k' (law 'root'): d k.e / d k.q = inf at finite inputs k.q = 0");
  }
  fb_bd_free(&bd);
  fb_bg_free(&bg);

  bg = root_graph(1, &err);
  MUST(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  if (bd) {
    const double x[1] = {0.0};
    check_explained(bd, x, 0, FB_NONFINITE_VALUE,
                    "R 'r' (law 'root'): r.e = nan from finite inputs f:bv = -1");
  }
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

int main(void)
{
  test_explain_nonfinite();
  test_mtf_rigid_bar();
  test_nonlinear_law();
  test_modulated_field();
  test_quarter_car();
  test_augmented();
  test_algebraic_loop();
  test_fields_vs_scalars();
  test_dot();
  return check_report("test_bd");
}
