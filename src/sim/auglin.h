/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal: sparse direct solver for Newton systems through a block
 * diagram's augmented linearisation (see flexbond/bd.h).
 *
 * The integrator needs (I - gamma J) dx = b with J = dF/dx. That matrix is
 * the Schur complement onto the state rows of the augmented matrix
 * P(gamma) = P0 + gamma P1 over all signals z, so instead of forming it we
 * solve P(gamma) z = r with r = b at the state rows and 0 elsewhere, and
 * read dx = z at the state rows (block elimination of the signal unknowns;
 * e.g. Golub & Van Loan, "Matrix Computations", 4th ed., sec. 3.2.10).
 *
 * Most rows of P define one unknown explicitly: a unit coefficient on
 * z_e and the rest on other unknowns (a gain, a sum, an integrator's
 * z_x - gamma z_x'). Those unknowns are eliminated first, in an order
 * where each row refers only to unknowns already eliminated or kept
 * (a depth-first search keeps one unknown per dependency cycle). The
 * kept unknowns (mass-matrix solves, one per cycle through the dynamics)
 * carry the Schur complement S = P_KK - P_KE P_EE^-1 P_EK, which KLU
 * factorises (Davis & Palamadai Natarajan, ACM TOMS 37(3), 2010). For a
 * finite-element structure the kept unknowns are the nodal velocities
 * and S = M + gamma B + gamma^2 K + (attached parts): the sparse Newton
 * matrix of structural dynamics, without any inverse of M. */
#ifndef FLEXBOND_SIM_AUGLIN_H
#define FLEXBOND_SIM_AUGLIN_H

#include <stddef.h>

#include "flexbond/bd.h"
#include "flexbond/error.h"

typedef struct fb_auglin fb_auglin;

/* Creates the solver for the nz x nz pattern of nnz triplets (rows[k],
 * cols[k]) (duplicates allowed: their values are summed), with state i at
 * row and column state_rows[i], i < nstates. unit[r] != 0 promises that
 * row r has the constant coefficient 1 on z_r in every setup (the
 * triplets at (r, r) sum to v0 = 1, v1 = 0): such unknowns may be
 * eliminated; unit may be NULL (none). Runs the elimination order and
 * KLU's symbolic analysis once. FB_EINVAL on an index out of range or a
 * repeated state row. */
int fb_auglin_new(size_t nz, size_t nnz, const size_t *rows, const size_t *cols,
                  const unsigned char *unit, const size_t *state_rows, size_t nstates,
                  fb_auglin **out, fb_err *err);
void fb_auglin_free(fb_auglin **al);
/* The solver for bd's augmented matrix (fb_bd_aug_pattern, unit rows
 * fb_bd_aug_unit_rows, states at fb_bd_state_row). */
int fb_auglin_new_bd(fb_bd *bd, fb_auglin **out, fb_err *err);

/* Forms P(gamma) from the triplet values v0[k] + gamma * v1[k], condenses
 * it and factorises the kept part. FB_ESOLVER if it is singular (to
 * working precision): the integrator may retry with another gamma.
 * FB_ENOMEM is fatal. */
int fb_auglin_setup(fb_auglin *al, double gamma, const double *v0, const double *v1,
                    fb_err *err);

/* x = (I - gamma J)^-1 b at the gamma of the last successful setup; b and
 * x have nstates entries and may alias. FB_EINVAL without a valid setup. */
int fb_auglin_solve(fb_auglin *al, const double *b, double *x, fb_err *err);

/* Numeric LU factorisations done so far (full and refactorisations). */
/* The unknown (index in z) that the last failed factorisation found no
 * pivot for, or -1 when the last factorisation did not fail that way. */
long fb_auglin_singular_unknown(const fb_auglin *al);
long fb_auglin_nfactorizations(const fb_auglin *al);

/* Unknowns kept after the elimination (the order of the factorised
 * matrix), and that matrix's stored entries. */
size_t fb_auglin_nkept(const fb_auglin *al);
size_t fb_auglin_kept_nnz(const fb_auglin *al);

#endif
