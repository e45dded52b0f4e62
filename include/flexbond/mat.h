/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: real matrices (dense column-major or compressed sparse column)
 * and sparse LU factorisation (SuiteSparse KLU).
 *
 * Used for the constitutive laws of multiport fields (mass, stiffness,
 * damping), for matrix transformers and for block gains. An fb_mat is
 * immutable once created. Indices are 0-based size_t in the API. */
#ifndef FLEXBOND_MAT_H
#define FLEXBOND_MAT_H

#include <stddef.h>
#include <stdio.h>

#include "flexbond/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fb_mat fb_mat;

/* Constructors copy their input arrays (the caller keeps ownership of them)
 * and return a new matrix in *out, owned by the caller (free with
 * fb_mat_free). On failure *out is NULL. */

/* Dense matrix from column-major values (nrows*ncols of them). */
int fb_mat_new_dense(size_t nrows, size_t ncols, const double *colmajor, fb_mat **out,
                     fb_err *err);
/* Dense matrix from row-major values (as written in a YAML list of rows). */
int fb_mat_new_dense_rowmajor(size_t nrows, size_t ncols, const double *rowmajor, fb_mat **out,
                              fb_err *err);
/* Sparse matrix from (row, col, value) triplets; duplicates are summed,
 * explicit zeros are kept out. Indices out of range are FB_EINVAL. */
int fb_mat_new_triplets(size_t nrows, size_t ncols, size_t nnz, const size_t *rows,
                        const size_t *cols, const double *vals, fb_mat **out, fb_err *err);
/* Sparse matrix from compressed sparse columns: column j's entries at
 * colptr[j] .. colptr[j + 1] - 1 of rowidx (rows strictly increasing) and
 * vals; explicit zeros are kept. FB_EINVAL naming the first column that is
 * out of shape. */
int fb_mat_new_csc(size_t nrows, size_t ncols, const size_t *colptr, const size_t *rowidx,
                   const double *vals, fb_mat **out, fb_err *err);
/* Square diagonal matrix (stored sparse). */
int fb_mat_new_diag(size_t n, const double *diag, fb_mat **out, fb_err *err);
/* s * identity(n) (stored sparse). */
int fb_mat_new_scaled_identity(size_t n, double s, fb_mat **out, fb_err *err);
/* Deep copy. */
int fb_mat_clone(const fb_mat *a, fb_mat **out, fb_err *err);
/* Transpose (same storage kind). */
int fb_mat_transpose(const fb_mat *a, fb_mat **out, fb_err *err);
/* Product c = a * b (sparse result if either is sparse). */
int fb_mat_multiply(const fb_mat *a, const fb_mat *b, fb_mat **out, fb_err *err);
/* c = alpha a + beta b, sparse (b may be NULL: c = alpha a); a and b of
 * the same size. */
int fb_mat_axpby(double alpha, const fb_mat *a, double beta, const fb_mat *b, fb_mat **out,
                 fb_err *err);
/* Inverse of a square non-singular matrix, returned dense. Meant for small
 * matrices (transformer inverses); FB_ESOLVER if singular. */
int fb_mat_inverse(const fb_mat *a, fb_mat **out, fb_err *err);

/* Frees *m and sets it to NULL; accepts NULL and *m == NULL. */
void fb_mat_free(fb_mat **m);

size_t fb_mat_nrows(const fb_mat *a);
size_t fb_mat_ncols(const fb_mat *a);
int fb_mat_is_sparse(const fb_mat *a);
/* Number of stored entries (nrows*ncols for dense). */
size_t fb_mat_nnz(const fb_mat *a);
/* Entry (i, j), 0 if not stored. */
double fb_mat_get(const fb_mat *a, size_t i, size_t j);

/* Visits every stored entry (structurally nonzero for sparse; nonzero
 * values only for dense) in column order. */
typedef void (*fb_mat_visit_fn)(void *ctx, size_t row, size_t col, double val);
void fb_mat_foreach(const fb_mat *a, fb_mat_visit_fn fn, void *ctx);
/* The entries fb_mat_foreach visits, in its order, as triplets into row,
 * col and val (each with room for fb_mat_nnz(a) values); returns how
 * many were written. */
size_t fb_mat_triplets(const fb_mat *a, size_t *row, size_t *col, double *val);

/* y = alpha * A x + beta * y (y must not alias x). With beta == 0, y is
 * overwritten and its previous content (even NaN) is ignored. */
void fb_mat_gemv(const fb_mat *a, double alpha, const double *x, double beta, double *y);
/* y = alpha * A^T x + beta * y. */
void fb_mat_gemv_t(const fb_mat *a, double alpha, const double *x, double beta, double *y);

/* 1 if every entry is finite. */
int fb_mat_all_finite(const fb_mat *a);
/* 1 if square and |a_ij - a_ji| <= tol * max|a| for all i, j. */
int fb_mat_is_symmetric(const fb_mat *a, double tol);
/* 1 if square, symmetric (tol as above) and positive definite (Cholesky,
 * or positive semi-definite when allow_singular: eigenvalues >= -tol*max|a|). */
int fb_mat_is_spd(const fb_mat *a, int allow_singular);

/* Matrix Market (https://math.nist.gov/MatrixMarket/formats.html):
 * reads "matrix coordinate real|integer general|symmetric" and
 * "matrix array real general|symmetric". Errors say path:line. The size
 * line is checked before anything is allocated: nrows x ncols when they
 * are given (0: either is not known), each at most FB_MTX_MAX_DIM when
 * not, and no more entries than the file's bytes can hold (FB_EPARSE). */
int fb_mat_read_mtx_dims(const char *path, size_t nrows, size_t ncols, fb_mat **out,
                         fb_err *err);
/* fb_mat_read_mtx_dims with neither dimension known. */
int fb_mat_read_mtx(const char *path, fb_mat **out, fb_err *err);
/* Most rows or columns a Matrix Market file may declare when the reader
 * does not know them: the sparse form keeps a pointer per column and its
 * construction a counter per row, whatever the entries (16 MB at 1e6), and
 * a field law or transformer of a bond graph has as many rows as its ports
 * carry, nowhere near a million (docs/errors.md, "Limits"). */
#define FB_MTX_MAX_DIM ((size_t)1000000)
/* Prints a as Matrix Market with %.17g values: "coordinate real general"
 * when a is sparse, "array real general" when dense (so reading it back
 * gives the same storage); write errors stick to fp. */
void fb_mat_print_mtx(FILE *fp, const fb_mat *a);
/* Writes a to path (fb_mat_print_mtx) through a temporary file created
 * exclusively beside it and renamed into place: all or nothing. */
int fb_mat_write_mtx(const fb_mat *a, const char *path, fb_err *err);

/* Sparse LU factorisation of a square matrix with KLU
 * (Davis & Palamadai Natarajan, ACM TOMS 37(3), 2010). */
typedef struct fb_lu fb_lu;
/* Factorises a; FB_ESOLVER naming the pivot when a is singular. */
int fb_lu_new(const fb_mat *a, fb_lu **out, fb_err *err);
/* Solves A x = b in place (b on entry, x on return), nrhs right-hand sides
 * stored one after the other. */
int fb_lu_solve(fb_lu *lu, double *b, size_t nrhs, fb_err *err);
size_t fb_lu_size(const fb_lu *lu);
void fb_lu_free(fb_lu **lu);

/* Sparse Cholesky factorisation A = L L' of a symmetric positive definite
 * matrix with CHOLMOD (supernodal: Chen, Davis, Hager & Rajamanickam, ACM
 * TOMS 35(3), 2008): for finite-element stiffness and mass matrices, whose
 * fill suits dense supernodes better than KLU's column-by-column LU. Only
 * a's upper triangle is read. fb_chol_new analyses the pattern first (a
 * fill-reducing ordering) and so knows the factor's size before it
 * allocates it: one above memory_limit bytes (0: no limit) is FB_ENOMEM
 * naming the megabytes it needs, with nothing allocated for it. A matrix
 * that is not positive definite is FB_ESOLVER naming the leading minor;
 * a non-square, empty or non-finite one FB_EINVAL. */
typedef struct fb_chol fb_chol;
int fb_chol_new(const fb_mat *a, size_t memory_limit, fb_chol **out, fb_err *err);
/* The same of alpha a + beta b (b NULL: alpha a), formed as CHOLMOD takes
 * it without an intermediate matrix: a shifted stiffness K + s M. */
int fb_chol_new_sum(double alpha, const fb_mat *a, double beta, const fb_mat *b,
                    size_t memory_limit, fb_chol **out, fb_err *err);
/* Solves A x = b in place for nrhs right-hand sides stored one after the
 * other. The factor keeps its own workspace: one caller at a time. */
int fb_chol_solve(fb_chol *c, double *b, size_t nrhs, fb_err *err);
/* threads 2: a solve of several right-hand sides gives half of them to a
 * second thread (the factor is only read; each thread has a workspace of
 * its own): some 1.5 times faster on two cores (measured on an 11964-DOF
 * shell stiffness, 8 right-hand sides). 1: one thread (the default). */
void fb_chol_set_threads(fb_chol *c, int threads);
size_t fb_chol_size(const fb_chol *c);
/* The bytes the factor and its workspace take (what memory_limit was
 * checked against). */
size_t fb_chol_bytes(const fb_chol *c);
void fb_chol_free(fb_chol **c);

/* The complex matrix j omega E - A of a descriptor system's pencil
 * (E, A), factorised at one angular frequency omega (rad/s) at a time
 * for a frequency response (KLU's complex routines). fb_pencil_new
 * analyses the pattern of E and A once (square, of one order, finite;
 * FB_EINVAL otherwise); fb_pencil_factor factorises at omega >= 0
 * (FB_ESOLVER naming the column when the matrix is singular there: a pole
 * on the imaginary axis, or a pencil that is singular for every omega);
 * fb_pencil_solve solves in place nrhs right-hand sides of n complex
 * values each, stored as interleaved real and imaginary parts. */
typedef struct fb_pencil fb_pencil;
int fb_pencil_new(const fb_mat *E, const fb_mat *A, fb_pencil **out, fb_err *err);
size_t fb_pencil_order(const fb_pencil *p);
int fb_pencil_factor(fb_pencil *p, double omega, fb_err *err);
int fb_pencil_solve(fb_pencil *p, double *b, size_t nrhs, fb_err *err);
void fb_pencil_free(fb_pencil **p);

#ifdef __cplusplus
}
#endif
#endif
