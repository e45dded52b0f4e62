/* SPDX-License-Identifier: BSD-3-Clause */
/* The modal model of a structure (fb_fem_modal, flexbond/fem.h): its
 * lowest modes, by LAPACK or by block Lanczos (lanczos.c), and reduced
 * bases of kept modes with residual flexibility and load-dependent Ritz
 * vectors.
 *
 * Both eigen-solvers solve the shifted problem (K + s M) v = (w^2 + s) M v,
 * s > 0, and subtract s. K itself is singular for a free structure, and
 * K + s M is then positive definite, so one Cholesky factor serves the
 * Lanczos steps and every static response. The shift's size trades the
 * conditioning of K + s M (about lambda_max / s) against how well the six
 * rigid-body modes (nu = 1 / s) stand apart from the first elastic ones
 * (nu = 1 / (lambda_1 + s)), which makes Lanczos converge fast when s <<
 * lambda_1. s = SHIFT_RATIO trace(K) / trace(M) ties it to the model's own
 * scale: trace(K) / trace(M) is the mean Rayleigh quotient of the unit DOF
 * vectors, of the order of the upper spectrum: measured from 4e7 s^-2 (50
 * mm steel plate, 1.25 m elements) to 3e10 s^-2 (8.5 mm plate, 0.05 m
 * elements), so s is 0.4-300 s^-2, below the lowest elastic eigenvalues of
 * interest (a 2 Hz plate mode, 160 s^-2, comes with the coarsest of those
 * meshes; a hull's first elastic mode is tens of Hz) while K + s M keeps a
 * condition number near 1e9-1e10, which a backward-stable Cholesky
 * handles (the error lies mostly along the rigid-body directions, which
 * are eigenvectors anyway). Eigenvalues in [-s, 0) are round-off of zero
 * eigenvalues (about eps lambda_max, far below s) and are set to 0; one
 * below -s means K is not positive semi-definite, an error.
 *
 * Why free-interface modes with residual flexibility rather than
 * Craig-Bampton: a hull on vertical suspensions is a free-free body.
 * Craig-Bampton's constraint modes need the interface DOFs to restrain
 * every rigid-body motion, which the vertical attachment DOFs do not
 * (surge, sway and yaw stay free); the free-free modes are also the ones
 * the modal analysis reports, so the basis is physically readable
 * (bench/basis_choice.c measures the two and load-dependent Ritz vectors
 * side by side). */
#include <cblas.h>
#include <lapacke.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/util.h"
#include "fem/fem_internal.h"

#define SHIFT_RATIO 1e-8
/* Assembled element matrices are symmetric to round-off (1e-16). */
#define SYMMETRY_TOL 1e-10
/* The Lanczos block: a free structure's six rigid-body modes and two
 * more fit in the first one. A solve that finds as many rigid-body modes
 * as the block holds (a mesh of loose parts) is repeated with blocks
 * twice as large, since a block finds a multiple eigenvalue at most as
 * often as it has vectors. */
#define LANCZOS_BLOCK 8
/* Refinements of a static response from the shifted factor towards K^+:
 * u_{k+1} = u_0 + s (K + s M)^-1 M u_k removes the shift's factor
 * lambda / (lambda + s) of each mode to order (s / lambda)^(k+1), below
 * 1e-11 after two for the modes a static correction adds (above the kept
 * ones: lambda > 1e3 s for a first elastic mode, which a shift of 1e-8
 * trace(K) / trace(M) puts far above s). */
#define STATIC_REFINEMENTS 2
/* A residual vector whose M-norm after projection is below this fraction
 * of its norm before carries nothing the basis lacks. */
#define DEPENDENT_TOL 1e-8

static const double two_pi = 6.28318530717958647692;

struct fb_fem_modal {
  const fb_mat *K, *M; /* borrowed */
  size_t n;
  double s;
  fb_eig_opts opts;
  fb_chol *shifted; /* K + s M, made when first needed */
  size_t nmodes, nrigid;
  double *lambda, *freq_hz, *shapes;
  fb_eig_info info;
};

void fb_eig_opts_default(fb_eig_opts *o)
{
  *o = (fb_eig_opts){FB_EIG_AUTO, 0, {NULL, NULL}, 0, NULL, 0, 1};
}

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

int fb_fem_modal_new(const fb_mat *K, const fb_mat *M, const fb_eig_opts *o, fb_fem_modal **out,
                     fb_err *err)
{
  *out = NULL;
  if (!K || !M)
    return fb_err_set(err, FB_EINVAL, "modal model: NULL matrix");
  const size_t n = fb_mat_nrows(K);
  if (n == 0 || fb_mat_ncols(K) != n || fb_mat_nrows(M) != n || fb_mat_ncols(M) != n)
    return fb_err_set(err, FB_EINVAL,
                      "modal model: K is %zu x %zu and M %zu x %zu; both must be the same "
                      "non-empty square size",
                      n, fb_mat_ncols(K), fb_mat_nrows(M), fb_mat_ncols(M));
  /* The solvers read one triangle only and assume the other; this also
   * rejects NaN and infinite entries. */
  if (!fb_mat_is_symmetric(K, SYMMETRY_TOL) || !fb_mat_is_symmetric(M, SYMMETRY_TOL))
    return fb_err_set(err, FB_EINVAL,
                      "modal model: K and M must be symmetric (to %g of their largest entry) "
                      "and finite",
                      SYMMETRY_TOL);
  fb_fem_modal *fm = calloc(1, sizeof *fm);
  if (!fm)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  fm->K = K;
  fm->M = M;
  fm->n = n;
  fm->s = choose_shift(K, M, n);
  if (o)
    fm->opts = *o;
  else
    fb_eig_opts_default(&fm->opts);
  *out = fm;
  return FB_OK;
}

static void clear_modes(fb_fem_modal *fm)
{
  free(fm->lambda);
  free(fm->freq_hz);
  free(fm->shapes);
  fm->lambda = fm->freq_hz = fm->shapes = NULL;
  fm->nmodes = fm->nrigid = 0;
}

void fb_fem_modal_free(fb_fem_modal **fm)
{
  if (!fm || !*fm)
    return;
  clear_modes(*fm);
  fb_chol_free(&(*fm)->shifted);
  free(*fm);
  *fm = NULL;
}

/* The Cholesky factor of K + s M, made once. */
static int shifted_factor(fb_fem_modal *fm, fb_err *err)
{
  if (fm->shifted)
    return FB_OK;
  char stage[96];
  snprintf(stage, sizeof stage, "Cholesky factorisation of %zu DOFs", fm->n);
  int rc = fb_progress_report(&fm->opts.progress, stage, 0.0, err);
  if (!rc)
    rc = fb_chol_new_sum(1.0, fm->K, fm->s, fm->M, fm->opts.memory_limit, &fm->shifted, err);
  if (rc == FB_ESOLVER)
    fb_err_prefix(err, "stiffness matrix is not positive semi-definite: K + %g M: ", fm->s);
  if (!rc) {
    fb_chol_set_threads(fm->shifted, fm->opts.threads);
    fm->info.factor_bytes = fb_chol_bytes(fm->shifted);
    rc = fb_progress_report(&fm->opts.progress, stage, 1.0, err);
  }
  return rc;
}

/* ---- The dense path. */

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

/* Every eigenpair of the shifted pencil by LAPACK dsygvd (divide and
 * conquer, Cholesky of M; E. Anderson et al., "LAPACK Users' Guide", 3rd
 * ed., SIAM 1999, sec. 2.3.5): into *lambda (n, new) and *x (n x n, new,
 * Z' M Z = I). */
static int solve_dense(const fb_fem_modal *fm, double **lambda, double **x, fb_err *err)
{
  const size_t n = fm->n;
  /* A and B, and dsygvd's workspace of 1 + 6 n + 2 n^2 doubles. */
  const double bytes = 8.0 * (4.0 * (double)n * (double)n + 8.0 * (double)n);
  if (n > (size_t)INT_MAX || n > SIZE_MAX / sizeof(double) / n)
    return fb_err_set(err, FB_EINVAL, "%zu DOFs is too many for a dense eigen-solve", n);
  if (fb_check_memory(bytes, fm->opts.memory_limit, err, "a dense eigen-solve of %zu DOFs", n))
    return FB_ENOMEM;
  char stage[96];
  snprintf(stage, sizeof stage, "dense eigen-solve of %zu DOFs (LAPACK)", n);
  int rc = fb_progress_report(&fm->opts.progress, stage, 0.0, err);
  if (rc)
    return rc;
  double *a = calloc(n * n, sizeof *a), *b = calloc(n * n, sizeof *b);
  double *w = malloc(n * sizeof *w);
  if (!a || !b || !w)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for a dense %zu x %zu eigenproblem", n, n);
  if (!rc) {
    dense_fill stiffness = {a, n, 1.0}, shift = {a, n, fm->s}, mass = {b, n, 1.0};
    fb_mat_foreach(fm->K, add_dense, &stiffness);
    fb_mat_foreach(fm->M, add_dense, &shift);
    fb_mat_foreach(fm->M, add_dense, &mass);
    const char jobz = fm->opts.values_only ? 'N' : 'V';
    const lapack_int info = LAPACKE_dsygvd(LAPACK_COL_MAJOR, 1, jobz, 'U', (lapack_int)n, a,
                                           (lapack_int)n, b, (lapack_int)n, w);
    if (info > (lapack_int)n)
      rc = fb_err_set(err, FB_ESOLVER,
                      "mass matrix is not positive definite (leading minor of order %d)",
                      (int)(info - (lapack_int)n));
    else if (info != 0)
      rc = fb_err_set(err, FB_ESOLVER, "LAPACK dsygvd failed (info %d)", (int)info);
  }
  for (size_t i = 0; !rc && i < n; ++i)
    w[i] -= fm->s;
  free(b);
  if (rc) {
    free(a);
    free(w);
    return rc;
  }
  *lambda = w;
  if (fm->opts.values_only) {
    free(a);
    a = NULL;
  }
  *x = a;
  return fb_progress_report(&fm->opts.progress, stage, 1.0, err);
}

/* ---- Solving. */

/* Keeps the first count of the n eigenpairs in lambda and x (shrinking
 * x; NULL: frequencies only), as the model's modes: frequencies, exact
 * zeros for the rigid-body modes, and their count. A clearly negative
 * eigenvalue is an error. */
static int adopt_modes(fb_fem_modal *fm, double *lambda, double *x, size_t count, fb_err *err)
{
  const double threshold = fb_fem_rigid_threshold_hz(fm->K, fm->M);
  double *freq = malloc(count * sizeof *freq);
  double *kept = x ? realloc(x, fm->n * count * sizeof *kept) : NULL;
  if (!freq || (x && !kept)) {
    free(freq);
    free(lambda);
    free(kept ? kept : x);
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu modes", count);
  }
  int rc = FB_OK;
  size_t nrigid = 0;
  for (size_t i = 0; i < count && !rc; ++i) {
    if (lambda[i] < -fm->s)
      rc = fb_err_set(err, FB_ESOLVER,
                      "stiffness matrix is not positive semi-definite (eigenvalue %g s^-2 "
                      "with shift %g)",
                      lambda[i], fm->s);
    freq[i] = sqrt(lambda[i] > 0.0 ? lambda[i] : 0.0) / two_pi;
    if (freq[i] <= threshold) {
      freq[i] = lambda[i] = 0.0;
      nrigid = i + 1;
    }
  }
  if (rc) {
    free(freq);
    free(lambda);
    free(kept);
    return rc;
  }
  clear_modes(fm);
  fm->lambda = lambda;
  fm->freq_hz = freq;
  fm->shapes = kept;
  fm->nmodes = count;
  fm->nrigid = nrigid;
  return FB_OK;
}

/* How many of the n ascending eigenvalues a request keeps: nmodes, or
 * every one at or below lambda_cut and the next. */
static size_t wanted_count(const double *lambda, size_t n, size_t nmodes, double lambda_cut)
{
  if (nmodes)
    return nmodes < n ? nmodes : n;
  size_t k = 0;
  while (k < n && lambda[k] <= lambda_cut)
    ++k;
  return k < n ? k + 1 : n;
}

static int use_dense(const fb_fem_modal *fm, size_t nmodes)
{
  if (fm->opts.method != FB_EIG_AUTO)
    return fm->opts.method == FB_EIG_DENSE;
  return fm->n <= FB_EIG_DENSE_AUTO_DOFS || nmodes + 1 >= fm->n || nmodes > fm->n / 2;
}

/* FB_EINVAL unless every given null vector is one: |K v| <= 1e-10
 * max|K_ii| |v| (measured 1e-16 for a shell mesh's rigid-body motions). */
static int check_null_vectors(const fb_fem_modal *fm, fb_err *err)
{
  double kmax = 0.0;
  for (size_t i = 0; i < fm->n; ++i)
    kmax = fmax(kmax, fabs(fb_mat_get(fm->K, i, i)));
  double *kv = fm->opts.nnull ? malloc(fm->n * sizeof *kv) : NULL;
  if (fm->opts.nnull && !kv)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  int rc = FB_OK;
  for (size_t j = 0; !rc && j < fm->opts.nnull; ++j) {
    const double *v = fm->opts.null_vectors + j * fm->n;
    fb_mat_gemv(fm->K, 1.0, v, 0.0, kv);
    if (!(sqrt(fem_dot(kv, kv, fm->n)) <= 1e-10 * kmax * sqrt(fem_dot(v, v, fm->n))))
      rc = fb_err_set(err, FB_EINVAL, "eigen-solve: given null vector %zu is not one of K", j);
  }
  free(kv);
  return rc;
}

/* Lanczos, with a larger block while the zero modes it finds (beyond the
 * given ones) fill one. */
static int solve_lanczos(fb_fem_modal *fm, const fem_lanczos_want *want, double **lambda,
                         double **x, size_t *count, fb_err *err)
{
  int rc = check_null_vectors(fm, err);
  if (!rc)
    rc = shifted_factor(fm, err);
  const double threshold = fb_fem_rigid_threshold_hz(fm->K, fm->M);
  const size_t given = fm->opts.nnull;
  /* A small model takes a smaller block: the basis needs four at least. */
  size_t first = (fm->n - fm->opts.nnull) / 4;
  first = first < LANCZOS_BLOCK ? (first ? first : 1) : LANCZOS_BLOCK;
  for (size_t block = first; !rc; block *= 2) {
    rc = fem_lanczos(fm->M, fm->shifted, fm->s, want, fm->opts.null_vectors, given, block,
                     fm->opts.memory_limit, &fm->opts.progress, lambda, x, count, err);
    fm->info.block = block;
    size_t zeros = given;
    while (!rc && zeros < *count && sqrt(fmax((*lambda)[zeros], 0.0)) / two_pi <= threshold)
      ++zeros;
    if (rc || zeros - given < block || 2 * block > FEM_LANCZOS_MAX_BLOCK || 8 * block > fm->n)
      break;
    free(*lambda);
    free(*x);
    *lambda = *x = NULL;
  }
  return rc;
}

int fb_fem_modal_solve(fb_fem_modal *fm, size_t nmodes, double cutoff_hz, fb_err *err)
{
  if (nmodes > fm->n || (nmodes == 0 && !(cutoff_hz >= 0.0 && isfinite(cutoff_hz))))
    return fb_err_set(err, FB_EINVAL, "eigen-solve: %zu modes (cut-off %g Hz) of %zu DOFs",
                      nmodes, cutoff_hz, fm->n);
  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  const fem_lanczos_want want = {nmodes, pow(two_pi * cutoff_hz, 2)};
  double *lambda = NULL, *x = NULL;
  size_t count = 0;
  int dense = use_dense(fm, nmodes);
  int rc = dense ? FB_OK : solve_lanczos(fm, &want, &lambda, &x, &count, err);
  /* A cut-off above most of the spectrum leaves Lanczos no room: every
   * mode is the dense solver's, when it is free to choose. */
  if (rc == FB_ESOLVER && nmodes == 0 && fm->opts.method == FB_EIG_AUTO)
    dense = 1;
  if (dense) {
    rc = solve_dense(fm, &lambda, &x, err);
    count = rc ? 0 : wanted_count(lambda, fm->n, nmodes, want.lambda_cut);
  }
  fm->info.method = dense ? FB_EIG_DENSE : FB_EIG_LANCZOS;
  if (dense)
    fm->info.block = 0;
  if (!rc)
    rc = adopt_modes(fm, lambda, x, count, err);
  else {
    free(lambda);
    free(x);
  }
  struct timespec t1;
  clock_gettime(CLOCK_MONOTONIC, &t1);
  fm->info.seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
  return rc;
}

size_t fb_fem_modal_ndof(const fb_fem_modal *fm)
{
  return fm->n;
}

size_t fb_fem_modal_nmodes(const fb_fem_modal *fm)
{
  return fm->nmodes;
}

size_t fb_fem_modal_nrigid(const fb_fem_modal *fm)
{
  return fm->nrigid;
}

const double *fb_fem_modal_freq_hz(const fb_fem_modal *fm)
{
  return fm->freq_hz;
}

const double *fb_fem_modal_lambda(const fb_fem_modal *fm)
{
  return fm->lambda;
}

const double *fb_fem_modal_shapes(const fb_fem_modal *fm)
{
  return fm->shapes;
}

fb_eig_info fb_fem_modal_info(const fb_fem_modal *fm)
{
  return fm->info;
}

/* ---- Reduced bases. */

/* u -= V (V' M u) for the ncols M-orthonormal columns of V; mu = M u is
 * scratch. */
static void project_out(const fb_mat *M, const double *V, size_t ncols, size_t n, double *u,
                        double *mu)
{
  if (ncols == 0)
    return;
  double *c = malloc(ncols * sizeof *c);
  fb_mat_gemv(M, 1.0, u, 0.0, mu);
  if (c) {
    cblas_dgemv(CblasColMajor, CblasTrans, (int)n, (int)ncols, 1.0, V, (int)n, mu, 1, 0.0, c,
                1);
    cblas_dgemv(CblasColMajor, CblasNoTrans, (int)n, (int)ncols, -1.0, V, (int)n, c, 1, 1.0, u,
                1);
  } else {
    for (size_t j = 0; j < ncols; ++j)
      fem_axpy(n, -fem_dot(V + j * n, mu, n), V + j * n, u);
  }
  free(c);
}

static double m_norm(const fb_mat *M, const double *u, size_t n, double *mu)
{
  fb_mat_gemv(M, 1.0, u, 0.0, mu);
  return sqrt(fmax(fem_dot(u, mu, n), 0.0));
}

/* U = K^+ G column by column for the nf self-equilibrated loads G (no
 * rigid-body resultant): the shifted solve u_0 = (K + s M)^-1 g refined
 * (refine: STATIC_REFINEMENTS times) as u_{k+1} = u_0 + s (K + s M)^-1 M
 * u_k, the fixed point of K u = g on the elastic modes, then freed of the
 * rigid-body modes that its rounding (amplified by 1 / s) leaves. */
static int static_solves(fb_fem_modal *fm, const double *G, size_t nf, int refine, double *U,
                         double *mu, fb_err *err)
{
  const size_t n = fm->n;
  double *u0 = malloc(n * nf * sizeof *u0), *t = malloc(n * nf * sizeof *t);
  int rc = u0 && t ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory for static responses");
  if (!rc) {
    memcpy(u0, G, n * nf * sizeof *u0);
    rc = fb_chol_solve(fm->shifted, u0, nf, err);
  }
  if (!rc)
    memcpy(U, u0, n * nf * sizeof *U);
  for (int k = 0; !rc && refine && k < STATIC_REFINEMENTS; ++k) {
    for (size_t j = 0; j < nf; ++j)
      fb_mat_gemv(fm->M, fm->s, U + j * n, 0.0, t + j * n);
    rc = fb_chol_solve(fm->shifted, t, nf, err);
    for (size_t i = 0; !rc && i < n * nf; ++i)
      U[i] = u0[i] + t[i];
  }
  for (size_t j = 0; !rc && j < nf; ++j)
    project_out(fm->M, fm->shapes, fm->nrigid, n, U + j * n, mu);
  free(u0);
  free(t);
  return rc;
}

/* M-orthonormalises the nu vectors at U against the nv1 columns of V1 (the
 * kept modes), the nv2 of V2 (the vectors added before, which U's start
 * extends) and each other (classical Gram-Schmidt, twice: Giraud et al.,
 * Numer. Math. 101, 2005), compacting the kept ones to the front of U;
 * returns how many were kept. */
static size_t orthonormalise(const fb_mat *M, const double *V1, size_t nv1, const double *V2,
                             size_t nv2, double *U, size_t nu, size_t n, double *mu)
{
  size_t kept = 0;
  for (size_t j = 0; j < nu; ++j) {
    double *u = U + kept * n;
    if (j != kept)
      memcpy(u, U + j * n, n * sizeof *u);
    const double before = m_norm(M, u, n, mu);
    for (int pass = 0; pass < 2; ++pass) {
      project_out(M, V1, nv1, n, u, mu);
      project_out(M, V2, nv2 + kept, n, u, mu);
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

/* Rayleigh-Ritz on the nr added vectors R alone (M-orthonormal, and M-
 * and K-orthogonal to the kept modes): R <- R Psi with R' K R Psi = Psi
 * diag(lambda). */
static int ritz(const fb_mat *K, double *R, size_t nr, size_t n, double *lambda, fb_err *err)
{
  if (nr == 0)
    return FB_OK;
  double *kr = malloc(n * nr * sizeof *kr), *g = malloc(nr * nr * sizeof *g);
  int rc = kr && g ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t j = 0; !rc && j < nr; ++j)
    fb_mat_gemv(K, 1.0, R + j * n, 0.0, kr + j * n);
  if (!rc) {
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, (int)nr, (int)nr, (int)n, 1.0, R,
                (int)n, kr, (int)n, 0.0, g, (int)nr);
    for (size_t j = 0; j < nr; ++j) /* symmetrise the round-off */
      for (size_t i = 0; i < j; ++i)
        g[j * nr + i] = g[i * nr + j] = 0.5 * (g[j * nr + i] + g[i * nr + j]);
    if (LAPACKE_dsyev(LAPACK_COL_MAJOR, 'V', 'U', (lapack_int)nr, g, (lapack_int)nr, lambda))
      rc = fb_err_set(err, FB_ESOLVER, "modal reduction: LAPACK dsyev failed");
  }
  if (!rc) {
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, (int)n, (int)nr, (int)nr, 1.0, R,
                (int)n, g, (int)nr, 0.0, kr, (int)n);
    memcpy(R, kr, n * nr * sizeof *R);
  }
  free(kr);
  free(g);
  return rc;
}

/* The loads of the first block: each pattern less its rigid-body
 * resultant (inertia relief, f - M Phi_r Phi_r' f), into G (n x nf). */
static void relieved_loads(const fb_fem_modal *fm, const double *F, size_t nf, double *G,
                           double *mu)
{
  const size_t n = fm->n;
  memcpy(G, F, n * nf * sizeof *G);
  for (size_t j = 0; j < nf; ++j)
    for (size_t r = 0; r < fm->nrigid; ++r) {
      const double *phi = fm->shapes + r * n;
      fb_mat_gemv(fm->M, 1.0, phi, 0.0, mu);
      fem_axpy(n, -fem_dot(phi, F + j * n, n), mu, G + j * n);
    }
}

/* FB_EINVAL unless the modes were solved with their shapes and nkeep of
 * them hold every rigid-body mode. */
static int check_keep(const fb_fem_modal *fm, size_t nkeep, fb_err *err)
{
  if (!fm->shapes)
    return fb_err_set(err, FB_EINVAL, "modal reduction: the modes were solved without shapes");
  if (nkeep > fm->nmodes || nkeep < fm->nrigid)
    return fb_err_set(
        err, FB_EINVAL,
        "modal reduction: %zu modes kept of %zu solved (%zu rigid-body modes must "
        "be among them)",
        nkeep, fm->nmodes, fm->nrigid);
  return FB_OK;
}

int fb_fem_modal_extend(fb_fem_modal *fm, size_t nkeep, const double *F, size_t nf, double **A,
                        size_t *nadded, size_t *nlast, fb_err *err)
{
  const size_t n = fm->n, first = *nadded - (*nadded ? *nlast : 0);
  const size_t nu = *nadded ? *nlast : nf;
  int rc = check_keep(fm, nkeep, err);
  if (!rc && !*nadded && nf && !F)
    rc = fb_err_set(err, FB_EINVAL, "modal reduction: no force patterns");
  /* A complete set of modes, or nothing to extend, adds nothing. */
  if (rc || nkeep >= n || nu == 0) {
    if (!rc)
      *nlast = 0;
    return rc;
  }
  if (*nadded + nu > SIZE_MAX / sizeof(double) / n)
    return fb_err_set(err, FB_ENOMEM, "modal reduction: %zu vectors of %zu DOFs", *nadded + nu,
                      n);
  double *grown = realloc(*A, n * (*nadded + nu) * sizeof *grown);
  double *mu = malloc(n * sizeof *mu), *G = malloc(n * nu * sizeof *G);
  if (grown)
    *A = grown;
  rc = grown && mu && G ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = shifted_factor(fm, err);
  /* The loads: the patterns less their rigid-body resultant, or M times
   * the block before (self-equilibrated: M-orthogonal to the rigid-body
   * modes). */
  if (!rc && !*nadded)
    relieved_loads(fm, F, nf, G, mu);
  for (size_t j = 0; !rc && *nadded && j < nu; ++j)
    fb_mat_gemv(fm->M, 1.0, *A + n * (first + j), 0.0, G + j * n);
  double *U = rc ? NULL : *A + n * *nadded;
  /* The static correction must be exact (a static load's response is the
   * basis's promise); a later block is an inertia term, whose Krylov
   * sequence (K + s M)^-1 M gives as well as K^+ M (measured on the
   * reference hull: the outputs' errors unchanged to two digits). */
  if (!rc)
    rc = static_solves(fm, G, nu, *nadded == 0, U, mu, err);
  if (!rc) {
    *nlast = orthonormalise(fm->M, fm->shapes, nkeep, *A, *nadded, U, nu, n, mu);
    *nadded += *nlast;
  }
  free(mu);
  free(G);
  return rc;
}

int fb_fem_modal_ritz(fb_fem_modal *fm, size_t nkeep, const double *A, size_t nadded,
                      double **T, double **lambda, fb_err *err)
{
  *T = *lambda = NULL;
  const size_t n = fm->n, nb = nkeep + nadded;
  int rc = check_keep(fm, nkeep, err);
  if (rc)
    return rc;
  if (nb > SIZE_MAX / sizeof(double) / n)
    return fb_err_set(err, FB_ENOMEM, "modal reduction: %zu vectors of %zu DOFs", nb, n);
  double *basis = malloc(n * (nb ? nb : 1) * sizeof *basis);
  double *lam = malloc((nb + 1) * sizeof *lam);
  rc = basis && lam ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc) {
    memcpy(basis, fm->shapes, n * nkeep * sizeof *basis);
    memcpy(lam, fm->lambda, nkeep * sizeof *lam);
    if (nadded)
      memcpy(basis + n * nkeep, A, n * nadded * sizeof *basis);
    rc = ritz(fm->K, basis + n * nkeep, nadded, n, lam + nkeep, err);
  }
  if (rc) {
    free(basis);
    free(lam);
    return rc;
  }
  *T = basis;
  *lambda = lam;
  return FB_OK;
}

int fb_fem_modal_basis(fb_fem_modal *fm, size_t nkeep, const double *F, size_t nf, size_t order,
                       double **T, double **lambda, size_t *nbasis, size_t *nstatic,
                       fb_err *err)
{
  *T = *lambda = NULL;
  *nbasis = *nstatic = 0;
  double *A = NULL;
  size_t nadded = 0, nlast = 0;
  int rc = fb_fem_modal_extend(fm, nkeep, F, nf, &A, &nadded, &nlast, err);
  const size_t nfirst = nadded;
  for (size_t b = 1; !rc && b < order && nlast; ++b)
    rc = fb_fem_modal_extend(fm, nkeep, F, nf, &A, &nadded, &nlast, err);
  if (!rc)
    rc = fb_fem_modal_ritz(fm, nkeep, A, nadded, T, lambda, err);
  free(A);
  if (!rc) {
    *nbasis = nkeep + nadded;
    *nstatic = nfirst;
  }
  return rc;
}

int fb_fem_modes(const fb_mat *K, const fb_mat *M, size_t nmodes, const fb_eig_opts *o,
                 double *freq_hz, double *vectors, fb_err *err)
{
  fb_fem_modal *fm = NULL;
  int rc = fb_fem_modal_new(K, M, o, &fm, err);
  if (!rc && (!freq_hz || nmodes == 0 || nmodes > fm->n))
    rc = fb_err_set(err, FB_EINVAL, "fb_fem_modes: %zu modes asked of %zu DOFs", nmodes, fm->n);
  if (!rc)
    rc = fb_fem_modal_solve(fm, nmodes, 0.0, err);
  if (!rc && vectors && !fm->shapes)
    rc = fb_err_set(err, FB_EINVAL, "fb_fem_modes: shapes asked with values_only");
  if (!rc) {
    memcpy(freq_hz, fm->freq_hz, nmodes * sizeof *freq_hz);
    if (vectors)
      memcpy(vectors, fm->shapes, fm->n * nmodes * sizeof *vectors);
  }
  fb_fem_modal_free(&fm);
  return rc;
}

double fb_fem_rigid_threshold_hz(const fb_mat *K, const fb_mat *M)
{
  double tk = 0.0, tm = 0.0;
  for (size_t i = 0; i < fb_mat_nrows(K); ++i) {
    tk += fb_mat_get(K, i, i);
    tm += fb_mat_get(M, i, i);
  }
  return 1e-6 * sqrt(tk / tm) / two_pi;
}
