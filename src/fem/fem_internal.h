/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal to src/fem: the block Lanczos solver (lanczos.c) that the
 * modal model (modal.c) runs. */
#ifndef FLEXBOND_FEM_INTERNAL_H
#define FLEXBOND_FEM_INTERNAL_H

#include "flexbond/fem.h"

/* Largest block fem_lanczos takes. */
#define FEM_LANCZOS_MAX_BLOCK 32

/* Level-1 operations as plain loops: OpenBLAS would hand vectors of a
 * model's size to its threads, whose wake-ups cost more than the
 * arithmetic. */
static inline double fem_dot(const double *a, const double *b, size_t n)
{
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i)
    sum += a[i] * b[i];
  return sum;
}

static inline void fem_axpy(size_t n, double alpha, const double *x, double *y)
{
  for (size_t i = 0; i < n; ++i)
    y[i] += alpha * x[i];
}

/* What an eigen-solve is asked for: the nmodes lowest modes, or (nmodes
 * 0) every mode with lambda <= lambda_cut ((rad/s)^2) and the first one
 * above it. */
typedef struct fem_lanczos_want {
  size_t nmodes;
  double lambda_cut;
} fem_lanczos_want;

/* The wanted lowest eigenpairs of K x = lambda M x, from shifted, the
 * Cholesky factor of K + s M (s > 0), and M (n x n): *lambda (ascending,
 * *nfound of them, lambda = 1 / nu - s from the Ritz values nu) and *x
 * (n x nfound, M-orthonormal), both new: first the ngiven eigenvectors
 * of eigenvalue 0 in given (n x ngiven; NULL when none), M-orthonormalised,
 * which the iteration is kept orthogonal to, then the Lanczos modes (the
 * nmodes count them all). block vectors at a time (at most
 * FEM_LANCZOS_MAX_BLOCK; a multiple eigenvalue is found at most block
 * times). The Lanczos basis grows as the modes need, checked against
 * memory_limit bytes (0: none) before each growth (FB_ENOMEM naming the
 * megabytes). pr hears of the solve every step (FB_EINTR when it asks to
 * stop). FB_EINVAL for nmodes above n / 2 (a dense solve's job) or a
 * model under 4 blocks; FB_ESOLVER if the wanted modes need the whole
 * space. */
int fem_lanczos(const fb_mat *M, fb_chol *shifted, double s, const fem_lanczos_want *want,
                const double *given, size_t ngiven, size_t block, size_t memory_limit,
                const fb_progress *pr, double **lambda, double **x, size_t *nfound,
                fb_err *err);

#endif
