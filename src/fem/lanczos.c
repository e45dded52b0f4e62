/* SPDX-License-Identifier: BSD-3-Clause */
/* The lowest modes of K x = lambda M x by the spectral transformation
 * block Lanczos method (fem_lanczos, fem_internal.h): T. Ericsson & A.
 * Ruhe, "The spectral transformation Lanczos method for the numerical
 * solution of large sparse generalized symmetric eigenvalue problems",
 * Math. Comp. 35(152), 1980; R. G. Grimes, J. G. Lewis & H. D. Simon, "A
 * shifted block Lanczos algorithm for solving sparse symmetric
 * generalized eigenproblems", SIAM J. Matrix Anal. Appl. 15(1), 1994.
 *
 * The operator is A = (K + s M)^-1 M, self-adjoint in the M inner
 * product, whose eigenvalues nu = 1 / (lambda + s) are largest for the
 * lowest lambda; s > 0 makes K + s M positive definite for a free
 * structure (K singular), so one Cholesky factor serves every step. From
 * a block Q_1 of p M-orthonormal vectors the method builds
 *   W = A Q_j - Q_j A_j - Q_{j-1} B_{j-1}',   A_j = Q_j' M A Q_j,
 *   W = Q_{j+1} B_j (M-orthonormal Q_{j+1}, B_j upper triangular),
 * so that Q' M A Q is block tridiagonal (A_j on the diagonal, B_j below
 * it): its eigenpairs (theta, y) are Ritz pairs of A, the vector Q y with
 * the residual norm |B_j y_last| (y_last: y's last p entries; Grimes et
 * al., sec. 2). Every new block is also orthogonalised against all the
 * previous ones (full reorthogonalisation), so no Ritz value is found
 * twice. A block rather than a single vector finds a multiple eigenvalue
 * as often as it occurs, up to p times.
 *
 * Known eigenvectors of eigenvalue 0 (a free structure's six rigid-body
 * motions) may be given: they lead the basis, every Lanczos vector is
 * orthogonal to them, and the iteration spends no step on them (A maps
 * the orthogonal complement of an eigenvector into itself).
 *
 * Why not ARPACK: its implicit restarts keep the basis small, which a
 * structure's few hundred lowest modes do not need, and it keeps its
 * state in Fortran SAVE variables, so two solves in one process must take
 * turns; with the same Cholesky factor this method found the reference
 * hull's 101 lowest modes at density 3 in 0.77 s, ARPACK in 2.07 s
 * (measured when the solver was chosen; docs/benchmarks.md). */
#include <cblas.h>
#include <lapacke.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/util.h"
#include "fem/fem_internal.h"

/* A Ritz pair is converged when its residual norm is below CONV_TOL
 * times its Ritz value, or below CONV_FLOOR times the largest one (the
 * rounding level of the operator, whose norm is about 1 / s). The
 * residual bounds the eigenvalue's error by residual^2 / gap (Parlett,
 * "The Symmetric Eigenvalue Problem", Thm. 11.7.1): some 1e-12 relative
 * for modes a few per cent apart, far below double precision's use in a
 * report or a model; the vector's by residual / gap, some 3e-5, far
 * below what truncating a basis costs (1e-4 to 1e-3 of an output's
 * range), and a modal model built on it is a Rayleigh-Ritz model of its
 * own span all the same. 1e-8 took two more block steps of eighteen on
 * the reference hull refined three times, for no output's gain. */
#define CONV_TOL 1e-6
#define CONV_FLOOR 1e-14
/* A new vector whose M-norm after orthogonalisation is below this
 * fraction of its norm before lies in the span already built. */
#define DEFLATE_TOL 1e-8
/* A pass of reorthogonalisation that leaves less than this fraction of a
 * vector's M-norm is repeated (1 / sqrt(2), the usual choice: J. Daniel,
 * W. B. Gragg, L. Kaufman & G. W. Stewart, Math. Comp. 30(136), 1976). */
#define REORTH_KEEP 0.7071
/* The eigenproblem of T costs O(m^3): it is solved at every step while
 * the basis holds fewer than this many Lanczos vectors, every other step
 * after. */
#define CHECK_EVERY_STEP 64

/* The working state of one solve. Q holds nd given eigenvectors, then the
 * m Lanczos vectors; T, S and theta are over the Lanczos vectors. */
typedef struct lanczos {
  const fb_mat *M;
  fb_chol *shifted;
  size_t n, p; /* order, block size */
  size_t nd;   /* given eigenvectors at the front of Q */
  size_t cap;  /* Lanczos vectors there is room for (a multiple of p) */
  size_t most; /* the most there can be: whole blocks of the space left by the nd */
  size_t m;    /* Lanczos vectors in use */
  double *Q;   /* n x (nd + cap), M-orthonormal */
  double *W;   /* n x p: the block being built */
  double *MQ;  /* n x p: M times the current block, or scratch */
  double *mw;  /* n: M times one vector */
  double *C;   /* (nd + cap) x p: projections */
  double *T;   /* cap x cap: the block tridiagonal Q' M A Q */
  double *S;   /* cap x cap: its eigenvectors */
  double *theta;
  uint64_t seed;
  size_t memory_limit;
} lanczos;

static void lanczos_free(lanczos *z)
{
  free(z->Q);
  free(z->W);
  free(z->MQ);
  free(z->mw);
  free(z->C);
  free(z->T);
  free(z->S);
  free(z->theta);
}

/* The first column of Lanczos vector j in Q. */
static double *lanczos_vector(const lanczos *z, size_t j)
{
  return z->Q + (z->nd + j) * z->n;
}

/* The columns of Q in use: the given ones and the Lanczos vectors. */
static size_t basis_size(const lanczos *z)
{
  return z->nd + z->m;
}

/* Bytes for cap Lanczos vectors: Q, C, T, S and the vectors. */
static double lanczos_bytes(const lanczos *z, size_t cap)
{
  const double q = (double)(z->nd + cap), c = (double)cap;
  return 8.0 * ((double)z->n * q + 2.0 * c * c + q * (double)z->p +
                (2.0 * (double)z->p + 1.0) * (double)z->n + c);
}

/* (Re)sizes the arrays that grow with the basis to cap Lanczos vectors,
 * keeping Q's columns in use and the leading m x m of T. */
static int lanczos_reserve(lanczos *z, size_t cap, fb_err *err)
{
  const double bytes = lanczos_bytes(z, cap);
  if (fb_check_memory(bytes, z->memory_limit, err,
                      "the eigen-solve's basis of %zu Lanczos vectors of %zu DOFs", cap, z->n))
    return FB_ENOMEM;
  const size_t q = z->nd + cap;
  if (q > SIZE_MAX / sizeof(double) / z->n || cap > SIZE_MAX / sizeof(double) / cap)
    return fb_err_set(err, FB_ENOMEM, "eigen-solve too large (%zu Lanczos vectors)", cap);
  double *Q = realloc(z->Q, z->n * q * sizeof *Q);
  if (Q)
    z->Q = Q;
  double *T = Q ? calloc(cap * cap, sizeof *T) : NULL;
  double *S = T ? malloc(cap * cap * sizeof *S) : NULL;
  double *C = S ? realloc(z->C, q * z->p * sizeof *C) : NULL;
  if (C)
    z->C = C;
  double *theta = C ? realloc(z->theta, cap * sizeof *theta) : NULL;
  if (!theta) {
    free(T);
    free(S);
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu Lanczos vectors of %zu DOFs", cap,
                      z->n);
  }
  z->theta = theta;
  for (size_t j = 0; j < z->m; ++j)
    memcpy(T + j * cap, z->T + j * z->cap, z->m * sizeof *T);
  free(z->T);
  free(z->S);
  z->T = T;
  z->S = S;
  z->cap = cap;
  return FB_OK;
}

/* A reproducible pseudo-random number in [-0.5, 0.5) (xorshift64, G.
 * Marsaglia, J. Stat. Softw. 8(14), 2003): the same start, the same
 * modes, run after run. */
static double next_random(uint64_t *state)
{
  *state ^= *state << 13;
  *state ^= *state >> 7;
  *state ^= *state << 17;
  return (double)(*state >> 11) / 9007199254740992.0 - 0.5;
}

/* w -= Q (Q' M w) over the columns of Q in use, twice. */
static void orthogonalise(lanczos *z, double *w)
{
  const size_t q = basis_size(z);
  for (int pass = 0; pass < 2 && q > 0; ++pass) {
    fb_mat_gemv(z->M, 1.0, w, 0.0, z->mw);
    for (size_t j = 0; j < q; ++j)
      fem_axpy(z->n, -fem_dot(z->Q + j * z->n, z->mw, z->n), z->Q + j * z->n, w);
  }
}

/* The block W against the whole basis: W -= Q (Q' M W), once, and again
 * when a column lost much of its M-norm in it (below REORTH_KEEP of it).
 * The norm after a pass needs no product with M: Q being M-orthonormal,
 * |w - Q c|^2 = |w|^2 - |c|^2. MQ is scratch. */
static void orthogonalise_block(lanczos *z)
{
  const int n = (int)z->n, q = (int)basis_size(z), p = (int)z->p;
  int again = 1;
  for (int pass = 0; pass < 2 && again; ++pass) {
    for (size_t c = 0; c < z->p; ++c)
      fb_mat_gemv(z->M, 1.0, z->W + c * z->n, 0.0, z->MQ + c * z->n);
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, q, p, n, 1.0, z->Q, n, z->MQ, n, 0.0,
                z->C, q);
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, n, p, q, -1.0, z->Q, n, z->C, q, 1.0,
                z->W, n);
    again = 0;
    for (size_t c = 0; c < z->p; ++c) {
      const double before = fem_dot(z->W + c * z->n, z->MQ + c * z->n, z->n);
      const double removed = fem_dot(z->C + c * (size_t)q, z->C + c * (size_t)q, (size_t)q);
      again |= before - removed < REORTH_KEEP * REORTH_KEEP * before;
    }
  }
}

/* w -= q_k (q_k' M w) for the c columns q_k before it in the new block
 * (first), whose M q_k are in MQ, twice; the coefficients are added to r
 * and M w (mw, not NULL) follows w. */
static void against_block(const lanczos *z, const double *first, size_t c, double *w,
                          double *mw, double *r)
{
  for (int pass = 0; pass < 2; ++pass)
    for (size_t k = 0; k < c; ++k) {
      const double coef = fem_dot(z->MQ + k * z->n, w, z->n);
      if (r)
        r[k] += coef;
      fem_axpy(z->n, -coef, first + k * z->n, w);
      if (mw)
        fem_axpy(z->n, -coef, z->MQ + k * z->n, mw);
    }
}

/* Makes the block W M-orthonormal column by column (modified Gram-Schmidt
 * in the M inner product; W is already orthogonal to the basis), appends
 * it to Q and returns its coefficients in R (p x p, upper triangular: W
 * = Q_new R). M times each column comes once from M, then follows its
 * updates (M (w - c q) = M w - c M q). A column that is (nearly) in the
 * span already gets a fresh random direction and a zero column in R: the
 * Krylov space was invariant, and the method goes on in a new direction.
 * MQ ends holding M times the new block. */
static void append_block(lanczos *z, double *R)
{
  const size_t n = z->n, p = z->p;
  memset(R, 0, p * p * sizeof *R);
  double *first = lanczos_vector(z, z->m);
  for (size_t c = 0; c < p; ++c) {
    double *w = z->W + c * n, *mq = z->MQ + c * n;
    fb_mat_gemv(z->M, 1.0, w, 0.0, mq);
    const double before = sqrt(fmax(fem_dot(w, mq, n), 0.0));
    against_block(z, first, c, w, mq, R + c * p);
    double norm = sqrt(fmax(fem_dot(w, mq, n), 0.0));
    R[c * p + c] = norm;
    if (!(norm > DEFLATE_TOL * before)) {
      for (size_t i = 0; i < n; ++i)
        w[i] = next_random(&z->seed);
      orthogonalise(z, w);
      against_block(z, first, c, w, NULL, NULL);
      fb_mat_gemv(z->M, 1.0, w, 0.0, mq);
      norm = sqrt(fmax(fem_dot(w, mq, n), 0.0));
      R[c * p + c] = 0.0;
    }
    for (size_t i = 0; i < n; ++i) {
      first[c * n + i] = w[i] / norm;
      mq[i] /= norm;
    }
  }
  z->m += p;
}

/* T's blocks of the block just appended: B_{j-1} = R below the diagonal
 * block of the previous one, and its transpose above it. */
static void store_coupling(lanczos *z, const double *R)
{
  const size_t p = z->p, row = z->m - p, col = z->m - 2 * p;
  for (size_t a = 0; a < p; ++a)
    for (size_t b = 0; b < p; ++b) {
      const double v = R[b * p + a];
      z->T[(col + b) * z->cap + row + a] = v;
      z->T[(row + a) * z->cap + col + b] = v;
    }
}

/* W = A Q_j for the last block (its M Q_j in MQ), A_j = Q_j' M W into T,
 * and W less Q_j A_j and Q_{j-1} B_{j-1}' (the three-term recurrence,
 * which leaves little for the full reorthogonalisation to do) and then
 * orthogonalised against the whole basis. */
static int expand(lanczos *z, fb_err *err)
{
  const size_t n = z->n, p = z->p, j0 = z->m - p;
  memcpy(z->W, z->MQ, n * p * sizeof *z->W);
  int rc = fb_chol_solve(z->shifted, z->W, p, err);
  if (rc)
    return rc;
  /* A_j = (M Q_j)' W, symmetrised. */
  cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, (int)p, (int)p, (int)n, 1.0, z->MQ,
              (int)n, z->W, (int)n, 0.0, z->C, (int)p);
  for (size_t a = 0; a < p; ++a)
    for (size_t b = 0; b < p; ++b)
      z->T[(j0 + b) * z->cap + j0 + a] = 0.5 * (z->C[b * p + a] + z->C[a * p + b]);
  const int ni = (int)n, pi = (int)p, ld = (int)z->cap;
  cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, ni, pi, pi, -1.0,
              lanczos_vector(z, j0), ni, z->T + j0 * z->cap + j0, ld, 1.0, z->W, ni);
  if (j0 >= p)
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, ni, pi, pi, -1.0,
                lanczos_vector(z, j0 - p), ni, z->T + j0 * z->cap + (j0 - p), ld, 1.0, z->W,
                ni);
  orthogonalise_block(z);
  return FB_OK;
}

/* Eigenpairs of the leading m x m of T into theta (ascending) and S. */
static int ritz_pairs(lanczos *z, fb_err *err)
{
  const size_t m = z->m;
  for (size_t j = 0; j < m; ++j)
    memcpy(z->S + j * m, z->T + j * z->cap, m * sizeof *z->S);
  const lapack_int info =
      LAPACKE_dsyev(LAPACK_COL_MAJOR, 'V', 'U', (lapack_int)m, z->S, (lapack_int)m, z->theta);
  return info ? fb_err_set(err, FB_ESOLVER, "block Lanczos: LAPACK dsyev failed (info %d)",
                           (int)info)
              : FB_OK;
}

/* The residual norm of Ritz pair k: |R y_last| for the coefficients R of
 * the block that follows the basis. */
static double residual(const lanczos *z, const double *R, size_t k)
{
  const size_t p = z->p, m = z->m;
  const double *y = z->S + k * m + (m - p);
  double sum = 0.0;
  for (size_t a = 0; a < p; ++a) {
    double v = 0.0;
    for (size_t b = a; b < p; ++b)
      v += R[b * p + a] * y[b];
    sum += v * v;
  }
  return sqrt(sum);
}

/* How many Ritz values from the largest down are converged without a gap
 * (into *nconv), and whether that is enough: the nlanczos largest, or
 * every one at or above nu_cut and one below it. */
static int converged(const lanczos *z, const double *R, size_t nlanczos, double nu_cut,
                     size_t *nconv)
{
  const size_t m = z->m;
  const double floor = CONV_FLOOR * z->theta[m - 1];
  size_t k = 0;
  while (k < m) {
    const size_t i = m - 1 - k;
    if (!(residual(z, R, i) <= CONV_TOL * fabs(z->theta[i]) + floor))
      break;
    ++k;
  }
  *nconv = k;
  if (nlanczos)
    return k >= nlanczos;
  return k > 0 && z->theta[m - k] < nu_cut;
}

/* The given eigenvectors D (n x nd) at the front of Q, M-orthonormalised
 * (Gram-Schmidt twice). FB_EINVAL if they are (nearly) dependent. */
static int lock_given(lanczos *z, const double *D, fb_err *err)
{
  const size_t n = z->n;
  const size_t nd = z->nd;
  z->nd = 0;
  for (size_t j = 0; j < nd; ++j) {
    double *q = z->Q + j * n;
    memcpy(q, D + j * n, n * sizeof *q);
    fb_mat_gemv(z->M, 1.0, q, 0.0, z->mw);
    const double before = sqrt(fmax(fem_dot(q, z->mw, n), 0.0));
    orthogonalise(z, q);
    fb_mat_gemv(z->M, 1.0, q, 0.0, z->mw);
    const double norm = sqrt(fmax(fem_dot(q, z->mw, n), 0.0));
    if (!(norm > DEFLATE_TOL * before))
      return fb_err_set(err, FB_EINVAL,
                        "block Lanczos: given eigenvector %zu depends on the "
                        "others",
                        j);
    for (size_t i = 0; i < n; ++i)
      q[i] /= norm;
    z->nd++;
  }
  return FB_OK;
}

/* A block of p random vectors made M-orthonormal (and orthogonal to the
 * given eigenvectors): the start. */
static void start_block(lanczos *z, double *R)
{
  for (size_t c = 0; c < z->p; ++c)
    for (size_t i = 0; i < z->n; ++i)
      z->W[c * z->n + i] = next_random(&z->seed);
  if (z->nd)
    orthogonalise_block(z);
  append_block(z, R);
}

/* The wanted eigenpairs: the given eigenvectors at lambda = 0, then the
 * converged Ritz pairs, the nlanczos largest Ritz values or, with a
 * cut-off, those at or above nu_cut and the next, as lambda = 1 / theta -
 * s, ascending, with their vectors Q y. */
static int collect(const lanczos *z, double s, size_t nconv, size_t nlanczos, double nu_cut,
                   double **lambda, double **x, size_t *nfound, fb_err *err)
{
  size_t count = nlanczos;
  if (!nlanczos)
    while (count < nconv && z->theta[z->m - 1 - count] >= nu_cut)
      ++count;
  if (!nlanczos && count < nconv)
    ++count; /* the first mode above the cut-off */
  const size_t total = z->nd + count, n = z->n, m = z->m;
  *lambda = malloc(total * sizeof **lambda);
  *x = malloc(n * total * sizeof **x);
  double *Y = malloc((m * count > 0 ? m * count : 1) * sizeof *Y);
  if (!*lambda || !*x || !Y) {
    free(Y);
    free(*lambda);
    free(*x);
    *lambda = *x = NULL;
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu modes of %zu DOFs", total, n);
  }
  for (size_t k = 0; k < z->nd; ++k)
    (*lambda)[k] = 0.0;
  memcpy(*x, z->Q, n * z->nd * sizeof **x);
  for (size_t k = 0; k < count; ++k) {
    const size_t i = m - 1 - k;
    (*lambda)[z->nd + k] = 1.0 / z->theta[i] - s;
    memcpy(Y + k * m, z->S + i * m, m * sizeof *Y);
  }
  if (count)
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, (int)n, (int)count, (int)m, 1.0,
                lanczos_vector(z, 0), (int)n, Y, (int)m, 0.0, *x + n * z->nd, (int)n);
  free(Y);
  *nfound = total;
  return FB_OK;
}

/* A first basis size: room for twice the Lanczos modes asked and a few
 * blocks. */
static size_t first_capacity(const lanczos *z, size_t nlanczos)
{
  const size_t p = z->p;
  size_t cap = nlanczos ? 2 * nlanczos + 4 * p : 16 * p;
  cap = (cap + p - 1) / p * p;
  return cap < z->most ? cap : z->most;
}

static int iterate(lanczos *z, size_t nlanczos, double nu_cut, const fb_progress *pr,
                   const char *stage, size_t *nconv, fb_err *err)
{
  double R[FEM_LANCZOS_MAX_BLOCK * FEM_LANCZOS_MAX_BLOCK];
  start_block(z, R);
  int rc = FB_OK;
  for (size_t step = 1; !rc; ++step) {
    if (z->m + z->p > z->cap) {
      const size_t most = z->most;
      if (z->cap >= most)
        return fb_err_set(err, FB_ESOLVER,
                          "block Lanczos: the modes asked need the whole space of %zu DOFs (a "
                          "dense solve)",
                          z->n);
      rc = lanczos_reserve(z, 2 * z->cap < most ? 2 * z->cap : most, err);
      if (rc)
        break;
    }
    rc = expand(z, err);
    if (!rc) {
      append_block(z, R);
      store_coupling(z, R);
    }
    /* The Ritz pairs of the basis before the new block, whose
     * coefficients R give their residuals. */
    z->m -= z->p;
    const int check = !rc && (z->m < CHECK_EVERY_STEP || step % 2 == 0);
    if (check && !(rc = ritz_pairs(z, err)) && converged(z, R, nlanczos, nu_cut, nconv))
      break;
    z->m += z->p;
    /* A fraction of 0 would say the stage begins again (fb_progress):
     * before the first mode converges the fraction is unknown. */
    if (!rc)
      rc = fb_progress_report(
          pr, stage, nlanczos && *nconv ? fmin((double)*nconv / (double)nlanczos, 0.99) : -1.0,
          err);
  }
  return rc;
}

int fem_lanczos(const fb_mat *M, fb_chol *shifted, double s, const fem_lanczos_want *want,
                const double *given, size_t ngiven, size_t block, size_t memory_limit,
                const fb_progress *pr, double **lambda, double **x, size_t *nfound, fb_err *err)
{
  *lambda = *x = NULL;
  *nfound = 0;
  const size_t n = fb_mat_nrows(M);
  if (block == 0 || block > FEM_LANCZOS_MAX_BLOCK || n < 4 * block + ngiven ||
      (want->nmodes == 0 && !(want->lambda_cut >= 0.0)) || want->nmodes > n / 2 ||
      (ngiven && !given))
    return fb_err_set(err, FB_EINVAL,
                      "block Lanczos: %zu modes (cut-off %g) of %zu DOFs with blocks of %zu",
                      want->nmodes, want->lambda_cut, n, block);
  const size_t nlanczos =
      want->nmodes ? (want->nmodes > ngiven ? want->nmodes - ngiven : 1) : 0;
  const double nu_cut = want->nmodes ? 0.0 : 1.0 / (want->lambda_cut + s);
  lanczos z = {.M = M, .shifted = shifted, .n = n, .p = block, .nd = ngiven};
  z.most = (n - ngiven) / block * block; /* block > 0 and n >= 4 block + ngiven: checked */
  z.memory_limit = memory_limit;
  z.seed = 0x9E3779B97F4A7C15u;
  z.W = malloc(n * block * sizeof *z.W);
  z.MQ = malloc(n * block * sizeof *z.MQ);
  z.mw = malloc(n * sizeof *z.mw);
  int rc = z.W && z.MQ && z.mw ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = lanczos_reserve(&z, first_capacity(&z, nlanczos), err);
  if (!rc)
    rc = lock_given(&z, given, err);
  char stage[96];
  snprintf(stage, sizeof stage, "eigen-solve of %zu DOFs by block Lanczos", n);
  size_t nconv = 0;
  if (!rc)
    rc = fb_progress_report(pr, stage, 0.0, err);
  if (!rc)
    rc = iterate(&z, nlanczos, nu_cut, pr, stage, &nconv, err);
  if (!rc)
    rc = collect(&z, s, nconv, nlanczos, nu_cut, lambda, x, nfound, err);
  if (!rc)
    rc = fb_progress_report(pr, stage, 1.0, err);
  lanczos_free(&z);
  if (rc) {
    free(*lambda);
    free(*x);
    *lambda = *x = NULL;
    *nfound = 0;
  }
  return rc;
}
