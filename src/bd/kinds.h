/* SPDX-License-Identifier: BSD-3-Clause */
/* The block kinds of a diagram (src/bd/kind_*.c): their constructors,
 * the registry that lists them, and the triplet writer their rows share.
 *
 * A kind is one file: its content type, its operations and properties
 * (bd_block_ops in bd/bd_internal.h) and a constructor; fb_bd_kinds
 * lists its ops so that the conformance harness (tests/
 * test_bd_conformance.c) runs it through the same checks as every other
 * kind. Each block's rows express its law as B d(out) - sum_k A_k d(in_k)
 * = 0; a state gives d(x) - gamma d(x') = b (flexbond/bd.h). */
#ifndef FLEXBOND_BD_KINDS_H
#define FLEXBOND_BD_KINDS_H

#include <stddef.h>

#include "bd/bd_internal.h"

/* A kind and its content, as its constructor makes them, for a new block
 * to take over. */
typedef struct bd_kind {
  const bd_block_ops *ops;
  void *content;
} bd_kind;

/* Every kind, once; fb_bd_nkinds of them. */
extern const bd_block_ops *const fb_bd_kinds[];
extern const size_t fb_bd_nkinds;

/* ---- Constructors. Those that take a matrix with owned = 1 take it over,
 * and free it on failure too; the others borrow theirs, which must
 * outlive the block. */

/* out = x, the state; input 0 is x'. */
bd_kind fb_bd_integrator_new(void);
/* out_i = fns[i](t); fns (one per output component) are borrowed. */
int fb_bd_source_new(fb_tfun *const *fns, bd_kind *out, fb_err *err);
/* out = A in. */
int fb_bd_gain_new(fb_mat *a, int owned, bd_kind *out, fb_err *err);
/* A out = in, by the sparse LU of A (its failure is the caller's to
 * explain: A is singular). */
int fb_bd_solve_new(fb_mat *a, int owned, bd_kind *out, fb_err *err);
/* out = sum_k coef[k] in_k over n inputs (zero inputs: out = 0). */
int fb_bd_sum_new(size_t n, const double *coef, bd_kind *out, fb_err *err);
/* out = [coef[0] in_0; ...; coef[n-1] in_{n-1}]. */
int fb_bd_mux_new(size_t n, const double *coef, bd_kind *out, fb_err *err);
/* out = sign in[offset .. offset + odim). */
int fb_bd_select_new(size_t offset, double sign, bd_kind *out, fb_err *err);
/* out = in_0 .* in_1. */
bd_kind fb_bd_product_new(void);
/* out = law(in_0, in_1, ...) of output dimension n, with m modulating
 * values after the law's own input (fb_law_ops); law and ctx are
 * borrowed. Its mode is 0. */
int fb_bd_law_new(const fb_law_ops *law, void *ctx, size_t n, size_t m, bd_kind *out,
                  fb_err *err);
/* Stored energy of a storage field from its state (input 0) and
 * co-variable (input 1): law->energy, or x.y / 2 when law is NULL (a
 * linear field); law and ctx are borrowed. */
int fb_bd_energy_new(const fb_law_ops *law, void *ctx, bd_kind *out, fb_err *err);

/* An input_dim for kinds whose inputs may have any size (a mux's parts,
 * the whole a demux splits, an energy's vectors). */
size_t fb_bd_input_dim_any(const bd_block *b, size_t k);

/* The content of a kind whose data is one coefficient per input (sum,
 * mux). */
typedef struct bd_coef_content {
  double *coef; /* one per input */
} bd_coef_content;
/* out as a kind of ops whose content holds a copy of the n coefficients
 * coef (each 1 when coef is NULL). */
int fb_bd_coef_kind_new(const bd_block_ops *ops, size_t n, const double *coef, bd_kind *out,
                        fb_err *err);
/* Frees a bd_coef_content (bd_block_ops.free). */
void fb_bd_coef_content_free(void *content);

/* ---- Triplet writer: rows/cols may be NULL when only values are
 * wanted, v0/v1 NULL when only the pattern is. */
typedef struct bd_trip {
  size_t *rows, *cols;
  double *v0, *v1;
  size_t k;
} bd_trip;

void fb_bd_trip_put(bd_trip *t, size_t r, size_t c, double v0, double v1);
/* The coefficient 1 on out[i] for every i < n, from offset off. */
void fb_bd_trip_identity(bd_trip *t, size_t off, size_t n);
/* scale * a at (roff, coff), padded with zeros to reserved triplets
 * (fb_mat_foreach visits only the nonzero entries of a dense matrix, and
 * a block's count is fixed). */
void fb_bd_trip_matrix(bd_trip *t, const fb_mat *a, size_t roff, size_t coff, double scale,
                       size_t reserved);

#endif
