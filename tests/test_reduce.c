/* SPDX-License-Identifier: BSD-3-Clause */
/* Free-interface modal reduction with residual flexibility and
 * load-dependent Ritz vectors (fb_fem_modal_basis, src/fem/modal.c) on a
 * free-free steel plate, against the full dense modal solution of the same
 * matrices:
 *   - the basis is M-orthonormal and K-orthogonal;
 *   - the kept modes come out unchanged;
 *   - a static load in the span of the force patterns is reproduced
 *     exactly (with inertia relief), which the modes alone do not do;
 *   - the second-order block brings the forced response below the cut-off
 *     closer to the full one, by the order in frequency it is made for;
 *   - the Lanczos solver with the rigid-body motions given (deflated)
 *     finds the dense solver's modes;
 *   - dependent patterns are dropped, bad counts refused. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test_shell_util.h"

enum { NX = 6, NY = 4 };

typedef struct plate {
  fb_mesh *mesh;
  fb_mat *K, *M;
  size_t n;
  double *freq, *phi; /* all n modes: Hz and M-orthonormal vectors */
  size_t nrigid;
} plate;

static void plate_free(plate *p)
{
  fb_mesh_free(&p->mesh);
  fb_mat_free(&p->K);
  fb_mat_free(&p->M);
  free(p->freq);
  free(p->phi);
}

static int plate_new(plate *p)
{
  memset(p, 0, sizeof *p);
  fb_err err;
  fb_shell_props props = NAFEMS_STEEL;
  props.thickness = 0.01;
  p->mesh = shell_plate(2.0, 1.0, NX, NY, 0, 0.1);
  if (!p->mesh)
    return 0;
  MUST(fb_fem_assemble(p->mesh, &props, FB_MASS_CONSISTENT, &p->K, &p->M, &err), &err);
  if (!p->K)
    return 0;
  p->n = fb_mat_nrows(p->K);
  p->freq = malloc(p->n * sizeof *p->freq);
  p->phi = malloc(p->n * p->n * sizeof *p->phi);
  if (!p->freq || !p->phi)
    return 0;
  const fb_eig_opts dense = eig_with(FB_EIG_DENSE);
  MUST(fb_fem_modes(p->K, p->M, p->n, &dense, p->freq, p->phi, &err), &err);
  const double threshold = fb_fem_rigid_threshold_hz(p->K, p->M);
  while (p->nrigid < p->n && p->freq[p->nrigid] <= threshold)
    ++p->nrigid;
  return 1;
}

static double dot(const double *a, const double *b, size_t n)
{
  double s = 0.0;
  for (size_t i = 0; i < n; ++i)
    s += a[i] * b[i];
  return s;
}

/* u = sum over the columns j of V with lambda_j > 0 of v_j (v_j' f) /
 * lambda_j: the elastic static response to f with inertia relief (for an
 * M-orthonormal, K-orthogonal V, f' v_j = 0 on the rigid columns after
 * relief). */
/* fe = F less the inertia forces of the rigid-body acceleration F causes
 * (inertia relief): F - sum_r M phi_r (phi_r^T F), phi_r M-orthonormal. mt
 * is n of scratch. */
static void inertia_relieved(const plate *p, const double *F, double *fe, double *mt)
{
  const size_t n = p->n;
  memcpy(fe, F, n * sizeof *fe);
  for (size_t r = 0; r < p->nrigid; ++r) {
    const double c = dot(p->phi + r * n, F, n);
    fb_mat_gemv(p->M, 1.0, p->phi + r * n, 0.0, mt);
    for (size_t i = 0; i < n; ++i)
      fe[i] -= c * mt[i];
  }
}

static void static_response(const double *V, const double *lambda, size_t ncols, size_t n,
                            const double *f, double *u)
{
  memset(u, 0, n * sizeof *u);
  for (size_t j = 0; j < ncols; ++j) {
    if (!(lambda[j] > 0.0))
      continue;
    const double c = dot(V + j * n, f, n) / lambda[j];
    for (size_t i = 0; i < n; ++i)
      u[i] += c * V[j * n + i];
  }
}

static double rel_diff(const double *a, const double *b, size_t n)
{
  double d = 0.0, s = 0.0;
  for (size_t i = 0; i < n; ++i) {
    d += (a[i] - b[i]) * (a[i] - b[i]);
    s += b[i] * b[i];
  }
  return sqrt(d / s);
}

/* nmodes kept (6: the rigid-body modes alone, the shift then comes from
 * the first elastic mode, which is not kept). */
static void test_basis(const plate *p, size_t nmodes)
{
  const size_t n = p->n, corner = 0;
  double *F = calloc(3 * n, sizeof *F);
  if (!F)
    return;
  /* A vertical force at a corner, a uniform vertical load, and the corner
   * force again (dependent: dropped). */
  F[6 * corner + 2] = 1.0;
  for (size_t k = 0; k < n / 6; ++k)
    F[n + 6 * k + 2] = 1.0;
  F[2 * n + 6 * corner + 2] = 1.0;
  fb_err err;
  double *T = NULL, *lambda = NULL;
  size_t nb = 0, nrigid = 0, nstatic = 0;
  fb_fem_modal *fm = NULL;
  const fb_eig_opts dense = eig_with(FB_EIG_DENSE);
  MUST(fb_fem_modal_new(p->K, p->M, &dense, &fm, &err), &err);
  if (fm) {
    MUST(fb_fem_modal_solve(fm, nmodes + 1, 0.0, &err), &err);
    nrigid = fb_fem_modal_nrigid(fm);
    MUST(fb_fem_modal_basis(fm, nmodes, F, 3, 1, &T, &lambda, &nb, &nstatic, &err), &err);
  }
  fb_fem_modal_free(&fm);
  fprintf(stderr, "%zu modes: basis of %zu\n", nmodes, nb);
  CHECK(nrigid == 6 && p->nrigid == 6);
  CHECK(nb == nmodes + 2 && nstatic == 2);
  double *mt = malloc(n * sizeof *mt), *kt = malloc(n * sizeof *kt);
  double *fe = malloc(n * sizeof *fe), *u_full = malloc(n * sizeof *u_full);
  double *u_red = malloc(n * sizeof *u_red), *u_modes = malloc(n * sizeof *u_modes);
  if (T && mt && kt && fe && u_full && u_red && u_modes) {
    /* T' M T = I and T' K T = diag(lambda): dot products of vectors of
     * norm 1 in the M metric, round-off ~1e-13; 1e-9 relative to the
     * largest stiffness for K. */
    double worst_m = 0.0, worst_k = 0.0;
    for (size_t j = 0; j < nb; ++j) {
      fb_mat_gemv(p->M, 1.0, T + j * n, 0.0, mt);
      fb_mat_gemv(p->K, 1.0, T + j * n, 0.0, kt);
      for (size_t i = 0; i < nb; ++i) {
        worst_m = fmax(worst_m, fabs(dot(T + i * n, mt, n) - (i == j)));
        worst_k = fmax(worst_k, fabs(dot(T + i * n, kt, n) - (i == j ? lambda[j] : 0.0)));
      }
    }
    CHECK(worst_m < 1e-9);
    CHECK(worst_k < 1e-9 * lambda[nb - 1]);
    /* The kept modes are the full solution's (same dense eigensolver on
     * the same matrices, 1e-9 relative). */
    const double two_pi = 6.28318530717958647692;
    for (size_t j = 0; j < nmodes; ++j)
      if (j < nrigid)
        CHECK(lambda[j] == 0.0);
      else
        CHECK_NEAR(sqrt(lambda[j]) / two_pi, p->freq[j], 1e-9 * p->freq[j]);
    /* The residual vectors are stiffer than every kept mode. */
    CHECK(lambda[nmodes] > lambda[nmodes - 1] && lambda[nmodes + 1] >= lambda[nmodes]);
    /* Static response to the corner force with inertia relief: the
     * reduced basis against the sum over all n modes. The static solve's
     * shift, refined twice, leaves (s / lambda)^3 of the truncated modes'
     * share, far below 1e-6 relative. */
    inertia_relieved(p, F, fe, mt);
    double *lam_full = malloc(n * sizeof *lam_full);
    if (lam_full) {
      for (size_t j = 0; j < n; ++j)
        lam_full[j] = j < p->nrigid ? 0.0 : pow(two_pi * p->freq[j], 2);
      static_response(p->phi, lam_full, n, n, fe, u_full);
      static_response(T, lambda, nb, n, fe, u_red);
      static_response(T, lambda, nmodes, n, fe, u_modes);
      const double with = rel_diff(u_red, u_full, n), without = rel_diff(u_modes, u_full, n);
      fprintf(stderr,
              "corner force: static error %.3g with the residual vectors, %.3g with %zu "
              "modes alone\n",
              with, without, nmodes);
      CHECK(with < 1e-6);
      /* The correction matters: the modes alone miss a visible part. */
      CHECK(without > 1e-3);
      free(lam_full);
    }
  }
  free(F);
  free(T);
  free(lambda);
  free(mt);
  free(kt);
  free(fe);
  free(u_full);
  free(u_red);
  free(u_modes);
}

/* |(full - reduced)(omega)| / |full(omega)| of the response to the force
 * pattern f (inertia relieved) at omega, u = sum v_j v_j' f / (lambda_j -
 * omega^2) over the elastic columns of V. */
static double forced_error(const plate *p, const double *T, const double *lambda, size_t nb,
                           const double *lam_full, const double *f, double omega)
{
  const size_t n = p->n;
  double *ur = calloc(n, sizeof *ur), *uf = calloc(n, sizeof *uf);
  double e = NAN;
  if (ur && uf) {
    for (int pass = 0; pass < 2; ++pass) {
      const double *V = pass ? T : p->phi, *lam = pass ? lambda : lam_full;
      double *u = pass ? ur : uf;
      for (size_t j = 0; j < (pass ? nb : n); ++j) {
        if (!(lam[j] > 0.0))
          continue;
        const double c = dot(V + j * n, f, n) / (lam[j] - omega * omega);
        for (size_t i = 0; i < n; ++i)
          u[i] += c * V[j * n + i];
      }
    }
    e = rel_diff(ur, uf, n);
  }
  free(ur);
  free(uf);
  return e;
}

/* The second-order block (order 2: K^+ M of the static correction, the
 * load-dependent Ritz vectors of Wilson, Yuan & Dickens 1982): with the
 * static correction alone the forced response below the cut-off misses
 * truncated modes to order (omega / omega_k)^2; the next block removes
 * that order, leaving the next, smaller by (omega / omega_k)^2 <= 1/4 for
 * every truncated mode at half the first truncated frequency: the error
 * must fall by that factor at least (measured: 12). */
static void test_second_order(const plate *p, size_t nmodes)
{
  const size_t n = p->n, corner = 0;
  double *F = calloc(n, sizeof *F), *fe = malloc(n * sizeof *fe);
  double *lam_full = malloc(n * sizeof *lam_full), *mt = malloc(n * sizeof *mt);
  fb_err err;
  fb_fem_modal *fm = NULL;
  const fb_eig_opts dense = eig_with(FB_EIG_DENSE);
  double *T[2] = {NULL, NULL}, *lambda[2] = {NULL, NULL};
  size_t nb[2] = {0, 0}, nstatic = 0;
  const double two_pi = 6.28318530717958647692;
  if (F && fe && lam_full && mt) {
    F[6 * corner + 2] = 1.0;
    MUST(fb_fem_modal_new(p->K, p->M, &dense, &fm, &err), &err);
    if (fm)
      MUST(fb_fem_modal_solve(fm, nmodes + 1, 0.0, &err), &err);
    for (int order = 1; fm && order <= 2; ++order)
      MUST(fb_fem_modal_basis(fm, nmodes, F, 1, (size_t)order, &T[order - 1],
                              &lambda[order - 1], &nb[order - 1], &nstatic, &err),
           &err);
    CHECK(nb[0] == nmodes + 1 && nb[1] == nmodes + 2 && nstatic == 1);
    for (size_t j = 0; j < n; ++j)
      lam_full[j] = j < p->nrigid ? 0.0 : pow(two_pi * p->freq[j], 2);
    inertia_relieved(p, F, fe, mt);
  }
  if (T[0] && T[1]) {
    const double omega = 0.5 * two_pi * p->freq[nmodes];
    const double e1 = forced_error(p, T[0], lambda[0], nb[0], lam_full, fe, omega);
    const double e2 = forced_error(p, T[1], lambda[1], nb[1], lam_full, fe, omega);
    fprintf(stderr, "forced response at %.3g Hz: error %.3g static correction, %.3g order 2\n",
            omega / two_pi, e1, e2);
    CHECK(e2 < 0.25 * e1);
  }
  fb_fem_modal_free(&fm);
  for (int k = 0; k < 2; ++k) {
    free(T[k]);
    free(lambda[k]);
  }
  free(F);
  free(fe);
  free(lam_full);
  free(mt);
}

/* Block Lanczos with the rigid-body motions given as null vectors finds
 * the dense solver's modes: frequencies to 1e-9 relative (both near
 * machine precision; the Ritz values' error is their residual squared),
 * the first six exactly 0, and no given vector that is not one is
 * accepted. */
static void test_null_vectors(const plate *p)
{
  const size_t n = p->n, nmodes = 20;
  double *r = malloc(6 * n * sizeof *r), f[20];
  fb_err err;
  if (!r)
    return;
  const double centre[3] = {1.0, 0.5, 0.0};
  fb_mesh_rigid_modes(p->mesh, centre, r);
  fb_eig_opts o = eig_with(FB_EIG_LANCZOS);
  o.null_vectors = r;
  o.nnull = 6;
  MUST(fb_fem_modes(p->K, p->M, nmodes, &o, f, NULL, &err), &err);
  for (size_t j = 0; j < nmodes; ++j)
    if (j < 6)
      CHECK(f[j] == 0.0);
    else
      CHECK_NEAR(f[j], p->freq[j], 1e-9 * p->freq[j]);
  r[6 * 3 + 2] += 1e-3; /* no longer a null vector */
  CHECK(fb_fem_modes(p->K, p->M, nmodes, &o, f, NULL, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "null vector") != NULL);
  free(r);
}

static void test_errors(const plate *p)
{
  fb_err err;
  double *T = NULL, *lambda = NULL;
  size_t nb = 0, nstatic = 0;
  fb_fem_modal *fm = NULL;
  const fb_eig_opts dense = eig_with(FB_EIG_DENSE);
  MUST(fb_fem_modal_new(p->K, p->M, &dense, &fm, &err), &err);
  if (!fm)
    return;
  /* No solve yet, and then too many modes asked. */
  CHECK(fb_fem_modal_basis(fm, 6, NULL, 0, 1, &T, &lambda, &nb, &nstatic, &err) == FB_EINVAL);
  CHECK(fb_fem_modal_solve(fm, p->n + 1, 0.0, &err) == FB_EINVAL);
  MUST(fb_fem_modal_solve(fm, 8, 0.0, &err), &err);
  /* More kept than solved; three modes of a body with six rigid-body
   * modes. */
  CHECK(fb_fem_modal_basis(fm, 9, NULL, 0, 1, &T, &lambda, &nb, &nstatic, &err) == FB_EINVAL);
  CHECK(fb_fem_modal_basis(fm, 3, NULL, 0, 1, &T, &lambda, &nb, &nstatic, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "rigid-body") != NULL);
  CHECK(T == NULL && lambda == NULL && nb == 0);
  fb_fem_modal_free(&fm);
}

int main(void)
{
  plate p;
  if (plate_new(&p)) {
    test_basis(&p, 10);
    test_basis(&p, 6);
    test_second_order(&p, 10);
    test_null_vectors(&p);
    test_errors(&p);
  }
  plate_free(&p);
  return check_report("test_reduce");
}
