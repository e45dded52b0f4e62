/* SPDX-License-Identifier: BSD-3-Clause */
/* Lowest modes of K v = w^2 M v (fb_fem_modes, see flexbond/fem.h), for a
 * symmetric positive semi-definite K (free-free structures have six zero
 * eigenvalues) and a symmetric positive definite M.
 *
 * Both paths solve the same shifted problem (K + s M) v = (w^2 + s) M v,
 * s > 0, and subtract s:
 *  - dense (n <= dense_limit): LAPACK dsygvd (divide and conquer, Cholesky
 *    of M; E. Anderson et al., "LAPACK Users' Guide", 3rd ed., SIAM 1999,
 *    section 2.3.5), all eigenpairs, vectors with Z^T M Z = I;
 *  - sparse: ARPACK's implicitly restarted Lanczos in shift-invert mode 3
 *    (R. B. Lehoucq, D. C. Sorensen & C. Yang, "ARPACK Users' Guide",
 *    SIAM 1998, chapter 3, and its dsdrv4 example driver): OP =
 *    (K - sigma M)^-1 M with sigma = -s, the shifted matrix factorised
 *    once by KLU; the largest eigenvalues nu = 1 / (w^2 - sigma) of OP are
 *    the w^2 nearest sigma, i.e. the lowest, and dseupd returns w^2 itself
 *    with M-orthonormal vectors.
 *
 * The shift: K itself is singular for a free structure, so the sparse path
 * needs sigma < 0 (K - sigma M is then positive definite). Its size trades
 * the conditioning of K + s M (about lambda_max / s) against how well the
 * six rigid-body modes (nu = 1 / s) stand apart from the first elastic
 * ones (nu = 1 / (lambda_1 + s)), which makes Lanczos converge fast when
 * s << lambda_1. s = SHIFT_RATIO trace(K) / trace(M) ties it to the
 * model's own scale: trace(K) / trace(M) is the mean Rayleigh quotient of
 * the unit DOF vectors, of the order of the upper spectrum: measured from
 * 4e7 s^-2 (50 mm steel plate, 1.25 m elements) to 3e10 s^-2 (8.5 mm
 * plate, 0.05 m elements), so s is 0.4-300 s^-2, below the lowest elastic
 * eigenvalues of interest (a 2 Hz plate mode, 160 s^-2, comes with the
 * coarsest of those meshes; a hull's first elastic mode is tens of Hz)
 * while K + s M keeps a condition number near 1e9-1e10, which KLU's
 * backward-stable solves handle (the error lies mostly along the rigid-body
 * directions, which are eigenvectors anyway). The dense path uses the same
 * s so both compute the same numbers. Eigenvalues w^2 in [-s, 0) are
 * round-off of zero eigenvalues (that is about eps lambda_max, far below
 * s) and are set to 0; one below -s means K is not positive semi-definite,
 * an error. */
#include <arpack/arpack.h>
#include <lapacke.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"

#define SHIFT_RATIO 1e-8
/* Assembled element matrices are symmetric to round-off (1e-16). */
#define SYMMETRY_TOL 1e-10
/* Lanczos restarts before ARPACK gives up (it needs only a few dozen for
 * well-separated low modes). */
#define ARPACK_MAX_RESTARTS 1000
/* fb_fem_dense_limit: LAPACK when at least 1 / DENSE_FRACTION of the
 * modes are wanted. dsygvd costs O(n^3) whatever nmodes is; shift-invert
 * Lanczos one sparse factorisation plus O(n ncv^2) with ncv ~ 2 nmodes.
 * Measured on the 1296-DOF reference hull (thread CPU time, vectors
 * included): 7 modes 0.67 s dense, 0.03 s ARPACK; 81 modes 0.59 s and
 * 0.08 s; 216 modes 0.53 s and 0.37 s; 324 modes 0.56 s and 0.84 s. The
 * two meet near a fifth of the modes. */
#define DENSE_FRACTION 5

static const double two_pi = 6.28318530717958647692;

/* ARPACK's dsaupd and dseupd keep their iteration state in Fortran SAVE
 * variables (ARPACK Users' Guide, sec. 2.2: "not reentrant"), so two
 * eigen-solves at once in one process corrupt each other. This lock is
 * the one piece of process-wide state the library holds, for that
 * dependency alone: the shifted factorisation and every dense solve run
 * unlocked, so the threads of a sweep wait only for each other's
 * Lanczos iterations. */
static pthread_mutex_t arpack_lock = PTHREAD_MUTEX_INITIALIZER;

/* trace(K) / trace(M) times SHIFT_RATIO; 1 s^-2 if K has no positive trace
 * (a zero K: every eigenvalue is 0 and any positive shift works). */
static double choose_shift(const fb_mat *K, const fb_mat *M, size_t n)
{
  double tk = 0.0, tm = 0.0;
  for (size_t i = 0; i < n; ++i) {
    tk += fb_mat_get(K, i, i);
    tm += fb_mat_get(M, i, i);
  }
  const double s = SHIFT_RATIO * tk / tm;
  return s > 0.0 && isfinite(s) ? s : 1.0;
}

/* ---- Dense path. */

typedef struct dense_fill {
  double *a;
  size_t n;
  double scale;
} dense_fill;

static void add_dense(void *ctx, size_t row, size_t col, double val)
{
  dense_fill *f = ctx;
  f->a[col * f->n + row] += f->scale * val;
}

static int modes_dense(const fb_mat *K, const fb_mat *M, size_t n, double s, size_t nmodes,
                       double *lambda, double *vectors, fb_err *err)
{
  if (n > (size_t)INT_MAX || n > SIZE_MAX / sizeof(double) / n)
    return fb_err_set(err, FB_EINVAL, "fb_fem_modes: %zu DOFs is too many for the dense path",
                      n);
  double *a = calloc(n * n, sizeof *a), *b = calloc(n * n, sizeof *b);
  double *w = malloc(n * sizeof *w);
  int rc = FB_OK;
  if (!a || !b || !w)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for dense %zu x %zu eigenproblem", n, n);
  if (!rc) {
    dense_fill stiffness = {a, n, 1.0}, shift = {a, n, s}, mass = {b, n, 1.0};
    fb_mat_foreach(K, add_dense, &stiffness);
    fb_mat_foreach(M, add_dense, &shift);
    fb_mat_foreach(M, add_dense, &mass);
    const lapack_int info =
        LAPACKE_dsygvd(LAPACK_COL_MAJOR, 1, vectors ? 'V' : 'N', 'U', (lapack_int)n, a,
                       (lapack_int)n, b, (lapack_int)n, w);
    if (info > (lapack_int)n)
      rc = fb_err_set(err, FB_ESOLVER,
                      "fb_fem_modes: mass matrix is not positive definite (leading minor of "
                      "order %d)",
                      (int)(info - (lapack_int)n));
    else if (info != 0)
      rc = fb_err_set(err, FB_ESOLVER, "fb_fem_modes: LAPACK dsygvd failed (info %d)",
                      (int)info);
  }
  if (!rc) {
    for (size_t i = 0; i < nmodes; ++i)
      lambda[i] = w[i] - s;
    if (vectors)
      memcpy(vectors, a, n * nmodes * sizeof *vectors);
  }
  free(a);
  free(b);
  free(w);
  return rc;
}

/* ---- Sparse path (ARPACK). */

/* KLU factors of K + s M. */
static int factor_shifted(const fb_mat *K, const fb_mat *M, double s, fb_lu **lu, fb_err *err)
{
  *lu = NULL;
  fb_mat *a = NULL;
  int rc = fb_mat_axpby(1.0, K, s, M, &a, err);
  if (!rc)
    rc = fb_lu_new(a, lu, err);
  fb_mat_free(&a);
  if (rc)
    fb_err_prefix(err, "fb_fem_modes: K + %g M: ", s);
  return rc;
}

/* ARPACK work arrays. */
typedef struct lanczos {
  a_int n, nev, ncv, lworkl;
  double *resid, *v, *workd, *workl, *d, *z;
  a_int *select;
} lanczos;

static void lanczos_free(lanczos *w)
{
  free(w->resid);
  free(w->v);
  free(w->workd);
  free(w->workl);
  free(w->d);
  free(w->z);
  free(w->select);
}

/* Sizes the Lanczos basis at max(2 nev + 1, nev + 20), at most n, as the
 * ARPACK guide advises (ncv >= 2 nev), and seeds the start vector with a
 * fixed pseudo-random sequence (xorshift64, G. Marsaglia, J. Stat. Softw.
 * 8(14), 2003) so that results are reproducible run to run. */
static int lanczos_alloc(size_t n, size_t nev, lanczos *w, fb_err *err)
{
  size_t ncv = 2 * nev + 1 > nev + 20 ? 2 * nev + 1 : nev + 20;
  ncv = ncv < n ? ncv : n;
  memset(w, 0, sizeof *w);
  if (n > (size_t)INT_MAX / 4 || ncv > (size_t)INT_MAX / (ncv + 8))
    return fb_err_set(err, FB_EINVAL, "fb_fem_modes: %zu DOFs is too many for ARPACK", n);
  w->n = (a_int)n;
  w->nev = (a_int)nev;
  w->ncv = (a_int)ncv;
  w->lworkl = (a_int)(ncv * (ncv + 8));
  w->resid = malloc(n * sizeof *w->resid);
  w->v = malloc(n * ncv * sizeof *w->v);
  w->workd = malloc(3 * n * sizeof *w->workd);
  w->workl = malloc((size_t)w->lworkl * sizeof *w->workl);
  w->d = malloc(nev * sizeof *w->d);
  w->z = malloc(n * nev * sizeof *w->z);
  w->select = calloc(ncv, sizeof *w->select);
  if (!w->resid || !w->v || !w->workd || !w->workl || !w->d || !w->z || !w->select) {
    lanczos_free(w);
    return fb_err_set(err, FB_ENOMEM, "out of memory for ARPACK (%zu x %zu basis)", n, ncv);
  }
  uint64_t state = 0x9E3779B97F4A7C15u;
  for (size_t i = 0; i < n; ++i) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    w->resid[i] = (double)(state >> 11) / 9007199254740992.0 - 0.5;
  }
  return FB_OK;
}

/* Runs the reverse-communication loop of dsaupd: y = OP x for ido = -1
 * (M x computed here) and ido = 1 (M x supplied in workd), y = M x for
 * ido = 2. */
static int lanczos_iterate(const fb_mat *M, fb_lu *lu, lanczos *w, a_int *iparam, a_int *ipntr,
                           fb_err *err)
{
  a_int ido = 0, info = 1; /* info = 1: resid holds the start vector */
  for (;;) {
    dsaupd_c(&ido, "G", w->n, "LM", w->nev, 0.0, w->resid, w->ncv, w->v, w->n, iparam, ipntr,
             w->workd, w->workl, w->lworkl, &info);
    if (ido == 99)
      break;
    double *x = w->workd + ipntr[0] - 1, *y = w->workd + ipntr[1] - 1;
    if (ido == 2 || ido == -1)
      fb_mat_gemv(M, 1.0, x, 0.0, y);
    if (ido == 1)
      memcpy(y, w->workd + ipntr[2] - 1, (size_t)w->n * sizeof *y);
    if (ido == 1 || ido == -1) {
      const int rc = fb_lu_solve(lu, y, 1, err);
      if (rc)
        return rc;
    }
  }
  if (info < 0 || info == 3)
    return fb_err_set(err, FB_ESOLVER, "fb_fem_modes: ARPACK dsaupd failed (info %d)",
                      (int)info);
  if (iparam[4] < w->nev)
    return fb_err_set(err, FB_ESOLVER,
                      "fb_fem_modes: ARPACK converged %d of %d modes in %d restarts (info %d)",
                      (int)iparam[4], (int)w->nev, (int)iparam[2], (int)info);
  return FB_OK;
}

static int modes_arpack(const fb_mat *K, const fb_mat *M, size_t n, double s, size_t nmodes,
                        double *lambda, double *vectors, fb_err *err)
{
  fb_lu *lu;
  int rc = factor_shifted(K, M, s, &lu, err);
  if (rc)
    return rc;
  lanczos w;
  rc = lanczos_alloc(n, nmodes, &w, err);
  if (rc) {
    fb_lu_free(&lu);
    return rc;
  }
  a_int iparam[11] = {0}, ipntr[14] = {0};
  iparam[0] = 1; /* exact shifts */
  iparam[2] = ARPACK_MAX_RESTARTS;
  iparam[6] = 3; /* shift-invert */
  pthread_mutex_lock(&arpack_lock);
  rc = lanczos_iterate(M, lu, &w, iparam, ipntr, err);
  if (!rc) {
    a_int info = 0;
    dseupd_c(vectors ? 1 : 0, "A", w.select, w.d, w.z, w.n, -s, "G", w.n, "LM", w.nev, 0.0,
             w.resid, w.ncv, w.v, w.n, iparam, ipntr, w.workd, w.workl, w.lworkl, &info);
    if (info != 0)
      rc = fb_err_set(err, FB_ESOLVER, "fb_fem_modes: ARPACK dseupd failed (info %d)",
                      (int)info);
  }
  pthread_mutex_unlock(&arpack_lock);
  if (!rc) {
    /* dseupd returns the eigenvalues in ascending order; sorting again
     * (insertion, nmodes is small) keeps that a checked fact. */
    size_t *order = malloc(nmodes * sizeof *order);
    if (!order)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory sorting %zu modes", nmodes);
    for (size_t i = 0; !rc && i < nmodes; ++i) {
      size_t j = i;
      for (; j > 0 && w.d[order[j - 1]] > w.d[i]; --j)
        order[j] = order[j - 1];
      order[j] = i;
    }
    for (size_t i = 0; !rc && i < nmodes; ++i) {
      lambda[i] = w.d[order[i]];
      if (vectors)
        memcpy(vectors + i * n, w.z + order[i] * n, n * sizeof *vectors);
    }
    free(order);
  }
  lanczos_free(&w);
  fb_lu_free(&lu);
  return rc;
}

/* Frequencies from the eigenvalues; rejects a clearly negative one. */
static int to_frequencies(const double *lambda, size_t nmodes, double s, double *freq_hz,
                          fb_err *err)
{
  for (size_t i = 0; i < nmodes; ++i) {
    if (lambda[i] < -s)
      return fb_err_set(err, FB_ESOLVER,
                        "fb_fem_modes: stiffness matrix is not positive semi-definite "
                        "(eigenvalue %g s^-2 with shift %g)",
                        lambda[i], s);
    freq_hz[i] = sqrt(lambda[i] > 0.0 ? lambda[i] : 0.0) / two_pi;
  }
  return FB_OK;
}

int fb_fem_modes(const fb_mat *K, const fb_mat *M, size_t nmodes, size_t dense_limit,
                 double *freq_hz, double *vectors, fb_err *err)
{
  if (!K || !M || !freq_hz)
    return fb_err_set(err, FB_EINVAL, "fb_fem_modes: NULL argument");
  const size_t n = fb_mat_nrows(K);
  if (n == 0 || fb_mat_ncols(K) != n || fb_mat_nrows(M) != n || fb_mat_ncols(M) != n)
    return fb_err_set(err, FB_EINVAL,
                      "fb_fem_modes: K is %zu x %zu and M %zu x %zu; both must be the same "
                      "non-empty square size",
                      n, fb_mat_ncols(K), fb_mat_nrows(M), fb_mat_ncols(M));
  if (nmodes == 0 || nmodes > n)
    return fb_err_set(err, FB_EINVAL, "fb_fem_modes: %zu modes asked of %zu DOFs", nmodes, n);
  /* Both solvers read one triangle only and assume the other; this also
   * rejects NaN and infinite entries. */
  if (!fb_mat_is_symmetric(K, SYMMETRY_TOL) || !fb_mat_is_symmetric(M, SYMMETRY_TOL))
    return fb_err_set(err, FB_EINVAL,
                      "fb_fem_modes: K and M must be symmetric (to %g of their largest entry) "
                      "and finite",
                      SYMMETRY_TOL);
  double *lambda = calloc(nmodes, sizeof *lambda);
  if (!lambda)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu eigenvalues", nmodes);
  const double s = choose_shift(K, M, n);
  /* ARPACK needs nev < ncv <= n: asking for (nearly) every mode is dense. */
  const int dense = fb_fem_modes_dense(n, nmodes, dense_limit);
  int rc = dense ? modes_dense(K, M, n, s, nmodes, lambda, vectors, err)
                 : modes_arpack(K, M, n, s, nmodes, lambda, vectors, err);
  if (!rc)
    rc = to_frequencies(lambda, nmodes, s, freq_hz, err);
  free(lambda);
  return rc;
}

int fb_fem_modes_dense(size_t n, size_t nmodes, size_t dense_limit)
{
  return n <= dense_limit || nmodes + 1 >= n;
}

size_t fb_fem_dense_limit(size_t nmodes)
{
  return nmodes > SIZE_MAX / DENSE_FRACTION ? SIZE_MAX : DENSE_FRACTION * nmodes;
}

double fb_fem_rigid_threshold_hz(const fb_mat *K, const fb_mat *M)
{
  double tk = 0.0, tm = 0.0;
  for (size_t i = 0; i < fb_mat_nrows(K); ++i) {
    tk += fb_mat_get(K, i, i);
    tm += fb_mat_get(M, i, i);
  }
  return 1e-6 * sqrt(tk / tm) / 6.28318530717958647692;
}
