/* SPDX-License-Identifier: BSD-3-Clause */
/* Free-interface modal reduction with residual flexibility (see
 * fb_fem_reduce_free in flexbond/fem.h).
 *
 * Why free-interface rather than Craig-Bampton: a hull on vertical
 * suspensions is a free-free body. Craig-Bampton's constraint modes need
 * the interface DOFs to restrain every rigid-body motion, which the
 * vertical attachment DOFs do not (surge, sway and yaw stay free); the
 * free-free modes are also the ones the modal analysis already computes
 * and reports, so the basis is physically readable. Their static
 * truncation error under the suspension and load forces is what the
 * residual-flexibility vectors restore (MacNeal 1971; Craig & Kurdila,
 * "Fundamentals of Structural Dynamics", 2nd ed., sec. 18.3).
 *
 * A residual vector for a force pattern f: remove the rigid-body
 * resultant (inertia relief, f_e = f - M Phi_r Phi_r' f), solve the
 * elastic static problem, then remove what the kept modes already carry.
 * The free-free K is singular, so the static solve uses K + sigma M with
 * a shift sigma far below the first elastic eigenvalue: on f_e, which has
 * no rigid-body content, it differs from the pseudo-inverse only by the
 * factors w_i^2 / (w_i^2 + sigma) of the modes, and the modes it perturbs
 * most are the kept ones, removed afterwards. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"

/* sigma = SHIFT_RATIO * (lowest elastic eigenvalue). */
#define SHIFT_RATIO 1e-6
/* A residual vector whose M-norm after projection is below this fraction
 * of its norm before carries nothing the basis lacks. */
#define DEPENDENT_TOL 1e-8

static double dot(const double *a, const double *b, size_t n)
{
  double s = 0.0;
  for (size_t i = 0; i < n; ++i)
    s += a[i] * b[i];
  return s;
}

/* u -= V (V' M u) for the ncols M-orthonormal columns of V; mu = M u is
 * scratch. */
static void project_out(const fb_mat *M, const double *V, size_t ncols, size_t n, double *u,
                        double *mu)
{
  fb_mat_gemv(M, 1.0, u, 0.0, mu);
  for (size_t j = 0; j < ncols; ++j) {
    const double c = dot(V + j * n, mu, n);
    for (size_t i = 0; i < n; ++i)
      u[i] -= c * V[j * n + i];
  }
}

static double m_norm(const fb_mat *M, const double *u, size_t n, double *mu)
{
  fb_mat_gemv(M, 1.0, u, 0.0, mu);
  return sqrt(fmax(dot(u, mu, n), 0.0));
}

/* Static responses (K + sigma M)^-1 f_e of the nf patterns, f_e without
 * the rigid-body resultant, into R (n x nf). */
static int static_responses(const fb_mat *K, const fb_mat *M, const double *phi, size_t nrigid,
                            double sigma, const double *F, size_t nf, size_t n, double *R,
                            double *mu, fb_err *err)
{
  for (size_t j = 0; j < nf; ++j) {
    double *f = R + j * n;
    memcpy(f, F + j * n, n * sizeof *f);
    for (size_t r = 0; r < nrigid; ++r) {
      const double c = dot(phi + r * n, f, n);
      fb_mat_gemv(M, 1.0, phi + r * n, 0.0, mu);
      for (size_t i = 0; i < n; ++i)
        f[i] -= c * mu[i];
    }
  }
  fb_mat *a = NULL;
  fb_lu *lu = NULL;
  int rc = fb_mat_axpby(1.0, K, sigma, M, &a, err);
  if (!rc)
    rc = fb_lu_new(a, &lu, err);
  if (!rc)
    rc = fb_lu_solve(lu, R, nf, err);
  fb_lu_free(&lu);
  fb_mat_free(&a);
  return rc;
}

/* M-orthonormalises the residual vectors against the modes and each other
 * (classical Gram-Schmidt, done twice: Giraud et al., Numer. Math. 101,
 * 2005), compacting the kept ones to the front
 * of R; returns how many were kept. */
static size_t orthonormalise(const fb_mat *M, const double *phi, size_t nmodes, double *R,
                             size_t nf, size_t n, double *mu)
{
  size_t kept = 0;
  for (size_t j = 0; j < nf; ++j) {
    double *u = R + kept * n;
    if (j != kept)
      memcpy(u, R + j * n, n * sizeof *u);
    const double before = m_norm(M, u, n, mu);
    for (int pass = 0; pass < 2; ++pass) {
      project_out(M, phi, nmodes, n, u, mu);
      project_out(M, R, kept, n, u, mu);
    }
    const double after = m_norm(M, u, n, mu);
    if (!(after > DEPENDENT_TOL * before))
      continue;
    for (size_t i = 0; i < n; ++i)
      u[i] /= after;
    ++kept;
  }
  return kept;
}

/* Rayleigh-Ritz on the residual vectors alone (they are M- and
 * K-orthogonal to the modes already): R <- R Psi with R' K R Psi =
 * Psi diag(lambda). */
static int ritz(const fb_mat *K, double *R, size_t nr, size_t n, double *lambda, double *mu,
                fb_err *err)
{
  if (nr == 0)
    return FB_OK;
  double *kr = malloc(nr * nr * sizeof *kr), *tmp = malloc(n * nr * sizeof *tmp);
  int rc = kr && tmp ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t j = 0; !rc && j < nr; ++j) {
    fb_mat_gemv(K, 1.0, R + j * n, 0.0, mu);
    for (size_t i = 0; i < nr; ++i)
      kr[j * nr + i] = dot(R + i * n, mu, n);
  }
  for (size_t j = 0; !rc && j < nr; ++j) /* symmetrise the round-off */
    for (size_t i = 0; i < j; ++i)
      kr[j * nr + i] = kr[i * nr + j] = 0.5 * (kr[j * nr + i] + kr[i * nr + j]);
  if (!rc && LAPACKE_dsyev(LAPACK_COL_MAJOR, 'V', 'U', (lapack_int)nr, kr, (lapack_int)nr,
                           lambda) != 0)
    rc = fb_err_set(err, FB_ESOLVER, "modal reduction: LAPACK dsyev failed");
  if (!rc) {
    memset(tmp, 0, n * nr * sizeof *tmp);
    for (size_t j = 0; j < nr; ++j)
      for (size_t l = 0; l < nr; ++l)
        for (size_t i = 0; i < n; ++i)
          tmp[j * n + i] += R[l * n + i] * kr[j * nr + l];
    memcpy(R, tmp, n * nr * sizeof *R);
  }
  free(kr);
  free(tmp);
  return rc;
}

/* The modes: nmodes kept and, when the model has more, the next one, which
 * must be elastic (the kept ones then hold every rigid-body mode) and
 * sets the static solve's shift. lam becomes (rad/s)^2, rigid ones 0. */
size_t fb_fem_reduce_nsolved(size_t n, size_t nmodes)
{
  return nmodes < n ? nmodes + 1 : n;
}

static int modes_and_shift(const fb_mat *K, const fb_mat *M, size_t nmodes, double *lam,
                           double *basis, size_t *nrigid, double *sigma, fb_err *err)
{
  const size_t n = fb_mat_nrows(K), m = fb_fem_reduce_nsolved(n, nmodes);
  int rc = fb_fem_modes(K, M, m, fb_fem_dense_limit(m), lam, basis, err);
  if (rc)
    return rc;
  const double threshold = fb_fem_rigid_threshold_hz(K, M), two_pi = 6.28318530717958647692;
  size_t rigid = 0;
  while (rigid < m && lam[rigid] <= threshold)
    ++rigid;
  if (rigid > nmodes)
    return fb_err_set(err, FB_EINVAL,
                      "modal reduction: %zu modes leave out rigid-body modes (the model has at "
                      "least %zu)",
                      nmodes, rigid);
  for (size_t i = 0; i < m; ++i)
    lam[i] = i < rigid ? 0.0 : pow(two_pi * lam[i], 2);
  *nrigid = rigid;
  /* No elastic mode at all (K = 0): nothing for a static correction. */
  *sigma = rigid < m ? SHIFT_RATIO * lam[rigid] : 0.0;
  return FB_OK;
}

int fb_fem_reduce_free(const fb_mat *K, const fb_mat *M, size_t nmodes, const double *F,
                       size_t nf, double **T, double **lambda, size_t *nbasis, size_t *nrigid,
                       fb_err *err)
{
  *T = NULL;
  *lambda = NULL;
  *nbasis = *nrigid = 0;
  const size_t n = fb_mat_nrows(K);
  if (nmodes == 0 || nmodes > n)
    return fb_err_set(err, FB_EINVAL, "modal reduction: %zu modes of a %zu-DOF model", nmodes,
                      n);
  /* Room for the extra mode, then overwritten by the residual vectors. */
  double *basis = malloc(n * (nmodes + 1 + nf) * sizeof *basis);
  double *lam = malloc((nmodes + 1 + nf) * sizeof *lam), *mu = malloc(n * sizeof *mu);
  int rc = basis && lam && mu ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  size_t rigid = 0, nres = 0;
  double sigma = 0.0;
  if (!rc)
    rc = modes_and_shift(K, M, nmodes, lam, basis, &rigid, &sigma, err);
  if (!rc && nf > 0 && sigma > 0.0) {
    double *R = basis + n * nmodes;
    rc = static_responses(K, M, basis, rigid, sigma, F, nf, n, R, mu, err);
    if (!rc) {
      nres = orthonormalise(M, basis, nmodes, R, nf, n, mu);
      rc = ritz(K, R, nres, n, lam + nmodes, mu, err);
    }
  }
  free(mu);
  if (rc) {
    free(basis);
    free(lam);
    return rc;
  }
  *T = basis;
  *lambda = lam;
  *nbasis = nmodes + nres;
  *nrigid = rigid;
  return FB_OK;
}
