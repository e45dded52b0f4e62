/* SPDX-License-Identifier: BSD-3-Clause */
/* Augmented sparse Newton solver (see auglin.h). KLU's 64-bit interface
 * (klu_l_*) is used, like src/core/lu.c.
 *
 * Notation: P is the augmented matrix, row-compressed with duplicates
 * merged. E are the eliminated unknowns in elimination order, K the kept
 * ones. For e in E the row of P reads z_e + sum_j P(e,j) z_j = r_e, so
 *   z_e = y_e + X(e,:) z_K,  X(e,k) = -P(e,k) - sum_{j in E} P(e,j) X(j,k),
 *                            y_e    = r_e - sum_{j in E} P(e,j) y_j,
 * and a kept row i becomes S(i,:) z_K = r_i - sum_{j in E} P(i,j) y_j with
 *   S(i,k) = P(i,k) + sum_{j in E} P(i,j) X(j,k).
 * S is stored by rows, which KLU reads as the columns of S^T: it factorises
 * S^T and solves with the transpose (klu_l_tsolve).
 *
 * The solve needs only P's entries in eliminated columns: the y_e recursion
 * and the kept rows' right-hand sides. Those are copied at each setup into
 * F, a row per eliminated unknown (in order) and then per kept one, so that
 * the solve, run once or twice per step, streams through them without
 * testing each of P's entries (at System 2's modal hull F holds 16 % of P). */
#include "sim/auglin.h"

#include <float.h>
#include <klu.h>
#include <stdlib.h>
#include <string.h>

#include "core/util.h"

/* After a refactorisation (which reuses the previous pivot order) a
 * reciprocal pivot ratio below this means the old pivots have gone bad,
 * and a full factorisation with fresh partial pivoting is done instead.
 * DBL_EPSILON^(2/3) ~ 3.7e-11 is the threshold SUNDIALS' own KLU module
 * uses for the same decision (SUNDIALS user guide, SUNLinSol_KLU). */
#define REFACTOR_RCOND_MIN 3.666852862501036e-11

/* min|U_kk| / max|U_kk| (klu_l_rcond) below DBL_EPSILON: the pivots differ
 * by more than the working precision, i.e. P(gamma) is singular to
 * working precision and the solve would return noise. */
#define SINGULAR_RCOND DBL_EPSILON

#define NONE ((size_t)-1)

/* A row-compressed sparse pattern with values. */
typedef struct csr {
  size_t n, cap;
  size_t *ptr; /* n + 1 */
  size_t *col;
  double *val;
} csr;

struct fb_auglin {
  size_t nz, nnz, nstates;
  csr p;        /* P(gamma), columns sorted within a row */
  size_t *slot; /* triplet k -> entry of p */
  size_t *elim; /* ne unknowns in elimination order */
  size_t ne, nk;
  size_t *kidx;  /* z -> index in K, or NONE if eliminated */
  csr x;         /* X: row r is X(elim[r], :) over K */
  size_t *xrow;  /* z -> row of X, or NONE */
  csr s;         /* S over K */
  csr f;         /* P's entries in eliminated columns: E rows, then K rows */
  size_t *fslot; /* entry of f -> entry of p */
  size_t *kz;    /* K -> z */
  double *acc;   /* nk accumulator, kept zero between uses */
  double *y;     /* nz: y over E, then z */
  double *rhs;   /* nk */
  size_t *state_rows;
  SuiteSparse_long *sp, *si; /* S's pattern in KLU's index type */
  klu_l_common common;
  klu_l_symbolic *symbolic;
  klu_l_numeric *numeric;
  int factored; /* numeric holds a valid LU of S */
  long nfactor;
  long singular; /* z of the unknown without a pivot, or -1 */
};

static void csr_free(csr *m)
{
  free(m->ptr);
  free(m->col);
  free(m->val);
}

void fb_auglin_free(fb_auglin **al)
{
  if (!al || !*al)
    return;
  fb_auglin *a = *al;
  if (a->numeric)
    klu_l_free_numeric(&a->numeric, &a->common);
  if (a->symbolic)
    klu_l_free_symbolic(&a->symbolic, &a->common);
  csr_free(&a->p);
  csr_free(&a->x);
  csr_free(&a->s);
  csr_free(&a->f);
  free(a->fslot);
  free(a->kz);
  free(a->slot);
  free(a->elim);
  free(a->kidx);
  free(a->xrow);
  free(a->acc);
  free(a->y);
  free(a->rhs);
  free(a->state_rows);
  free(a->sp);
  free(a->si);
  free(a);
  *al = NULL;
}

/* Indices in range, state rows distinct. */
static int check_pattern(size_t nz, size_t nnz, const size_t *rows, const size_t *cols,
                         const size_t *state_rows, size_t nstates, fb_err *err)
{
  if (nz == 0 || nstates > nz)
    return fb_err_set(err, FB_EINVAL, "augmented system: %zu states in %zu unknowns", nstates,
                      nz);
  if (nz > (size_t)SuiteSparse_long_max || nnz > (size_t)SuiteSparse_long_max)
    return fb_err_set(err, FB_EINVAL, "augmented system too large for KLU's index type");
  for (size_t k = 0; k < nnz; ++k)
    if (rows[k] >= nz || cols[k] >= nz)
      return fb_err_set(err, FB_EINVAL,
                        "augmented system: triplet %zu at (%zu, %zu) outside %zu x %zu", k,
                        rows[k], cols[k], nz, nz);
  unsigned char *seen = calloc(nz, 1);
  if (!seen)
    return fb_err_set(err, FB_ENOMEM, "out of memory checking the augmented pattern");
  int rc = FB_OK;
  for (size_t i = 0; i < nstates && rc == FB_OK; ++i) {
    if (state_rows[i] >= nz)
      rc = fb_err_set(err, FB_EINVAL, "augmented system: state %zu at row %zu of %zu", i,
                      state_rows[i], nz);
    else if (seen[state_rows[i]]++)
      rc = fb_err_set(err, FB_EINVAL, "augmented system: states share row %zu", state_rows[i]);
  }
  free(seen);
  return rc;
}

/* Stable counting sort of the triplet indices in `in` by key[.] < nkeys. */
static int sort_by_key(size_t nnz, const size_t *in, const size_t *key, size_t nkeys,
                       size_t *out)
{
  size_t *start = calloc(nkeys + 1, sizeof *start);
  if (!start)
    return FB_ENOMEM;
  for (size_t p = 0; p < nnz; ++p)
    ++start[key[in[p]] + 1];
  for (size_t j = 0; j < nkeys; ++j)
    start[j + 1] += start[j];
  for (size_t p = 0; p < nnz; ++p)
    out[start[key[in[p]]]++] = in[p];
  free(start);
  return FB_OK;
}

/* P's row-compressed pattern: the triplets sorted by (row, column) with
 * two stable counting sorts (column, then row), equal neighbours merged
 * into one entry. */
static int build_p(fb_auglin *a, const size_t *rows, const size_t *cols)
{
  const size_t nnz = a->nnz, n1 = nnz ? nnz : 1;
  size_t *ident = malloc(n1 * sizeof *ident), *bycol = malloc(n1 * sizeof *bycol);
  size_t *order = malloc(n1 * sizeof *order);
  a->p.n = a->nz;
  a->p.ptr = calloc(a->nz + 1, sizeof *a->p.ptr);
  a->p.col = malloc(n1 * sizeof *a->p.col);
  a->p.val = malloc(n1 * sizeof *a->p.val);
  int rc = ident && bycol && order && a->p.ptr && a->p.col && a->p.val ? FB_OK : FB_ENOMEM;
  for (size_t k = 0; rc == FB_OK && k < nnz; ++k)
    ident[k] = k;
  if (rc == FB_OK)
    rc = sort_by_key(nnz, ident, cols, a->nz, bycol);
  if (rc == FB_OK)
    rc = sort_by_key(nnz, bycol, rows, a->nz, order);
  if (rc == FB_OK) {
    size_t nentries = 0;
    for (size_t q = 0; q < nnz; ++q) {
      const size_t k = order[q], prev = q ? order[q - 1] : 0;
      if (q == 0 || rows[k] != rows[prev] || cols[k] != cols[prev]) {
        a->p.col[nentries++] = cols[k];
        ++a->p.ptr[rows[k] + 1];
      }
      a->slot[k] = nentries - 1;
    }
    for (size_t i = 0; i < a->nz; ++i)
      a->p.ptr[i + 1] += a->p.ptr[i];
  }
  free(ident);
  free(bycol);
  free(order);
  return rc;
}

/* Whether row r holds its diagonal (a promised unit row without one
 * cannot be eliminated by its own row). */
static int has_diagonal(const csr *p, size_t r)
{
  for (size_t q = p->ptr[r]; q < p->ptr[r + 1]; ++q)
    if (p->col[q] == r)
      return 1;
  return 0;
}

/* Depth-first search over the dependencies of the unit rows (row e
 * depends on the unknowns of its off-diagonal entries). Post-order is the
 * elimination order: every dependency of e is eliminated before e. An
 * edge back to an unknown still on the stack closes a cycle, and that
 * unknown is kept instead. Unknowns are visited in index order, states
 * first (bd numbers them first), so cycles through the dynamics tend to
 * keep a state, whose value then needs no back-substitution. */
static int plan(fb_auglin *a, const unsigned char *unit)
{
  const size_t nz = a->nz;
  enum { WHITE, GRAY, BLACK };
  unsigned char *color = calloc(nz, 1), *keep = calloc(nz, 1);
  size_t *stack = malloc(nz * sizeof *stack), *next = malloc(nz * sizeof *next);
  a->elim = malloc(nz * sizeof *a->elim);
  a->kidx = malloc(nz * sizeof *a->kidx);
  a->xrow = malloc(nz * sizeof *a->xrow);
  int rc = color && keep && stack && next && a->elim && a->kidx && a->xrow ? FB_OK : FB_ENOMEM;
  a->ne = a->nk = 0;
  for (size_t i = 0; rc == FB_OK && i < nz; ++i)
    keep[i] = !(unit && unit[i] && has_diagonal(&a->p, i));
  for (size_t root = 0; rc == FB_OK && root < nz; ++root) {
    if (keep[root] || color[root] != WHITE)
      continue;
    size_t top = 0;
    stack[top++] = root;
    color[root] = GRAY;
    next[root] = a->p.ptr[root];
    while (top) {
      const size_t e = stack[top - 1];
      if (next[e] == a->p.ptr[e + 1]) {
        color[e] = BLACK;
        --top;
        if (!keep[e])
          a->elim[a->ne++] = e;
        continue;
      }
      const size_t j = a->p.col[next[e]++];
      if (j == e || keep[j])
        continue;
      if (color[j] == GRAY) {
        keep[j] = 1;
      } else if (color[j] == WHITE) {
        color[j] = GRAY;
        next[j] = a->p.ptr[j];
        stack[top++] = j;
      }
    }
  }
  for (size_t i = 0; rc == FB_OK && i < nz; ++i) {
    a->kidx[i] = keep[i] ? a->nk++ : NONE;
    a->xrow[i] = NONE;
  }
  for (size_t r = 0; rc == FB_OK && r < a->ne; ++r)
    a->xrow[a->elim[r]] = r;
  free(color);
  free(keep);
  free(stack);
  free(next);
  return rc;
}

/* Rows are built one at a time: ptr has room for all rows, row m->n is
 * open between its entries ptr[n] .. ptr[n + 1]. */
static void row_open(csr *m)
{
  m->ptr[m->n + 1] = m->ptr[m->n];
}

/* Appends column k to the open row unless mark[k] == stamp already. */
static int row_add(csr *m, size_t *mark, size_t stamp, size_t k)
{
  if (mark[k] == stamp)
    return FB_OK;
  mark[k] = stamp;
  const size_t at = m->ptr[m->n + 1];
  if (fb_grow((void **)&m->col, &m->cap, at, sizeof *m->col) != FB_OK)
    return FB_ENOMEM;
  m->col[at] = k;
  m->ptr[m->n + 1] = at + 1;
  return FB_OK;
}

/* Adds a row to m with the pattern of sum_c P(row, c) u_c, where u_c is
 * the unit vector at kidx[c] for a kept c and X(c, :) for an eliminated
 * one; the entry c == row is left out when skip_self, and column diag is
 * stored even when structurally zero (NONE: no such column). */
static int combine_pattern(const fb_auglin *a, size_t row, int skip_self, size_t diag, csr *m,
                           size_t *mark, size_t stamp)
{
  row_open(m);
  int rc = diag == NONE ? FB_OK : row_add(m, mark, stamp, diag);
  for (size_t q = a->p.ptr[row]; q < a->p.ptr[row + 1] && rc == FB_OK; ++q) {
    const size_t c = a->p.col[q];
    if (skip_self && c == row)
      continue;
    if (a->kidx[c] != NONE) {
      rc = row_add(m, mark, stamp, a->kidx[c]);
    } else {
      const size_t r = a->xrow[c];
      for (size_t t = a->x.ptr[r]; t < a->x.ptr[r + 1] && rc == FB_OK; ++t)
        rc = row_add(m, mark, stamp, a->x.col[t]);
    }
  }
  m->n++;
  return rc;
}

/* Appends to F row `row` of P's entries in eliminated columns (its own
 * column left out). */
static void f_row(fb_auglin *a, size_t row)
{
  size_t at = a->f.ptr[a->f.n];
  for (size_t q = a->p.ptr[row]; q < a->p.ptr[row + 1]; ++q) {
    const size_t c = a->p.col[q];
    if (c != row && a->kidx[c] == NONE) {
      a->f.col[at] = c;
      a->fslot[at++] = q;
    }
  }
  a->f.ptr[++a->f.n] = at;
}

/* F's pattern: a row per eliminated unknown in order, then per kept one;
 * and K's unknowns in z. */
static int forward_pattern(fb_auglin *a)
{
  const size_t np = a->p.ptr[a->nz] ? a->p.ptr[a->nz] : 1;
  a->f.ptr = calloc(a->ne + a->nk + 1, sizeof *a->f.ptr);
  a->f.col = malloc(np * sizeof *a->f.col);
  a->f.val = malloc(np * sizeof *a->f.val);
  a->fslot = malloc(np * sizeof *a->fslot);
  a->kz = malloc((a->nk ? a->nk : 1) * sizeof *a->kz);
  if (!a->f.ptr || !a->f.col || !a->f.val || !a->fslot || !a->kz)
    return FB_ENOMEM;
  a->f.n = 0;
  for (size_t r = 0; r < a->ne; ++r)
    f_row(a, a->elim[r]);
  for (size_t i = 0; i < a->nz; ++i)
    if (a->kidx[i] != NONE) {
      a->kz[a->kidx[i]] = i;
      f_row(a, i);
    }
  return FB_OK;
}

/* The patterns of X (a row per eliminated unknown, in order) and S (a row
 * per kept unknown, its diagonal always stored). */
static int symbolic(fb_auglin *a)
{
  size_t *mark = malloc((a->nk ? a->nk : 1) * sizeof *mark);
  a->x.ptr = calloc(a->ne + 2, sizeof *a->x.ptr);
  a->s.ptr = calloc(a->nk + 2, sizeof *a->s.ptr);
  int rc = mark && a->x.ptr && a->s.ptr ? FB_OK : FB_ENOMEM;
  for (size_t k = 0; rc == FB_OK && k < a->nk; ++k)
    mark[k] = NONE;
  for (size_t r = 0; rc == FB_OK && r < a->ne; ++r)
    rc = combine_pattern(a, a->elim[r], 1, NONE, &a->x, mark, r);
  for (size_t i = 0; rc == FB_OK && i < a->nz; ++i)
    if (a->kidx[i] != NONE)
      rc = combine_pattern(a, i, 0, a->kidx[i], &a->s, mark, a->ne + a->kidx[i]);
  const size_t xnnz = rc == FB_OK ? a->x.ptr[a->ne] : 0;
  const size_t snnz = rc == FB_OK ? a->s.ptr[a->nk] : 0;
  if (rc == FB_OK && snnz > (size_t)SuiteSparse_long_max)
    rc = FB_EINVAL;
  if (rc == FB_OK) {
    a->x.val = malloc((xnnz ? xnnz : 1) * sizeof *a->x.val);
    a->s.val = malloc((snnz ? snnz : 1) * sizeof *a->s.val);
    a->sp = malloc((a->nk + 1) * sizeof *a->sp);
    a->si = malloc((snnz ? snnz : 1) * sizeof *a->si);
    a->acc = calloc(a->nk ? a->nk : 1, sizeof *a->acc);
    a->y = malloc(a->nz * sizeof *a->y);
    a->rhs = malloc((a->nk ? a->nk : 1) * sizeof *a->rhs);
    if (!a->x.val || !a->s.val || !a->sp || !a->si || !a->acc || !a->y || !a->rhs)
      rc = FB_ENOMEM;
  }
  for (size_t k = 0; rc == FB_OK && k <= a->nk; ++k)
    a->sp[k] = (SuiteSparse_long)a->s.ptr[k];
  for (size_t t = 0; rc == FB_OK && t < snnz; ++t)
    a->si[t] = (SuiteSparse_long)a->s.col[t];
  free(mark);
  return rc;
}

/* KLU's symbolic analysis of S^T: BTF, then AMD on S + S^T. Once the
 * explicitly defined unknowns are eliminated, S has the nearly symmetric
 * pattern of the dynamics (M + gamma B + gamma^2 K for a structure), for
 * which AMD is the natural ordering. */
static int analyze(fb_auglin *a, fb_err *err)
{
  klu_l_defaults(&a->common);
  if (a->nk == 0)
    return FB_OK;
  a->symbolic = klu_l_analyze((SuiteSparse_long)a->nk, a->sp, a->si, &a->common);
  if (a->symbolic)
    return FB_OK;
  if (a->common.status == KLU_OUT_OF_MEMORY)
    return fb_err_set(err, FB_ENOMEM, "out of memory in KLU analysis of the Newton matrix");
  return fb_err_set(err, FB_ESOLVER, "KLU analysis of the Newton matrix failed (status %ld)",
                    (long)a->common.status);
}

int fb_auglin_new(size_t nz, size_t nnz, const size_t *rows, const size_t *cols,
                  const unsigned char *unit, const size_t *state_rows, size_t nstates,
                  fb_auglin **out, fb_err *err)
{
  *out = NULL;
  int rc = check_pattern(nz, nnz, rows, cols, state_rows, nstates, err);
  if (rc != FB_OK)
    return rc;
  fb_auglin *a = calloc(1, sizeof *a);
  if (!a)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating the Newton solver");
  a->nz = nz;
  a->nnz = nnz;
  a->nstates = nstates;
  a->singular = -1;
  a->slot = malloc((nnz ? nnz : 1) * sizeof *a->slot);
  a->state_rows = malloc((nstates ? nstates : 1) * sizeof *a->state_rows);
  rc = a->slot && a->state_rows ? build_p(a, rows, cols) : FB_ENOMEM;
  if (rc == FB_OK)
    rc = plan(a, unit);
  if (rc == FB_OK)
    rc = symbolic(a);
  if (rc == FB_OK)
    rc = forward_pattern(a);
  if (rc != FB_OK) {
    fb_auglin_free(&a);
    return fb_err_set(err, rc, "%s creating the Newton solver",
                      rc == FB_ENOMEM ? "out of memory" : "kept matrix too large for KLU");
  }
  if (nstates)
    memcpy(a->state_rows, state_rows, nstates * sizeof *state_rows);
  rc = analyze(a, err);
  if (rc != FB_OK) {
    fb_auglin_free(&a);
    return rc;
  }
  *out = a;
  return FB_OK;
}

int fb_auglin_new_bd(fb_bd *bd, fb_auglin **out, fb_err *err)
{
  *out = NULL;
  const size_t nz = fb_bd_aug_size(bd), nnz = fb_bd_aug_nnz(bd), n = fb_bd_nstates(bd);
  size_t *rows = malloc((nnz ? nnz : 1) * sizeof *rows);
  size_t *cols = malloc((nnz ? nnz : 1) * sizeof *cols);
  size_t *state_rows = malloc((n ? n : 1) * sizeof *state_rows);
  unsigned char *unit = malloc(nz ? nz : 1);
  int rc = rows && cols && state_rows && unit
               ? FB_OK
               : fb_err_set(err, FB_ENOMEM, "out of memory for the augmented Newton matrix");
  if (rc == FB_OK) {
    fb_bd_aug_pattern(bd, rows, cols);
    fb_bd_aug_unit_rows(bd, unit);
    for (size_t i = 0; i < n; ++i)
      state_rows[i] = fb_bd_state_row(bd, i);
    rc = fb_auglin_new(nz, nnz, rows, cols, unit, state_rows, n, out, err);
  }
  free(rows);
  free(cols);
  free(state_rows);
  free(unit);
  return rc;
}

/* Values of the open pattern row `at` of m: sign * sum_c P(row, c) u_c
 * (see combine_pattern), through the zeroed accumulator. */
static void combine_values(fb_auglin *a, size_t row, int skip_self, double sign, csr *m,
                           size_t at)
{
  for (size_t q = a->p.ptr[row]; q < a->p.ptr[row + 1]; ++q) {
    const size_t c = a->p.col[q];
    const double v = a->p.val[q];
    if (skip_self && c == row)
      continue;
    if (a->kidx[c] != NONE) {
      a->acc[a->kidx[c]] += v;
    } else {
      const size_t r = a->xrow[c];
      for (size_t t = a->x.ptr[r]; t < a->x.ptr[r + 1]; ++t)
        a->acc[a->x.col[t]] += v * a->x.val[t];
    }
  }
  for (size_t t = m->ptr[at]; t < m->ptr[at + 1]; ++t) {
    m->val[t] = sign * a->acc[m->col[t]];
    a->acc[m->col[t]] = 0;
  }
}

/* P(gamma), then X and S from it. */
static void condense(fb_auglin *a, double gamma, const double *v0, const double *v1)
{
  memset(a->p.val, 0, (a->p.ptr[a->nz] ? a->p.ptr[a->nz] : 1) * sizeof *a->p.val);
  for (size_t k = 0; k < a->nnz; ++k)
    a->p.val[a->slot[k]] += v0[k] + gamma * v1[k];
  for (size_t r = 0; r < a->ne; ++r)
    combine_values(a, a->elim[r], 1, -1.0, &a->x, r);
  for (size_t i = 0; i < a->nz; ++i)
    if (a->kidx[i] != NONE)
      combine_values(a, i, 0, 1.0, &a->s, a->kidx[i]);
  for (size_t t = 0; t < a->f.ptr[a->f.n]; ++t)
    a->f.val[t] = a->p.val[a->fslot[t]];
}

/* Reuses the pivot order of the last full factorisation. Returns 1 if the
 * result is usable, 0 if a full factorisation is needed (a zero pivot, or
 * pivots grown too unequal for the old order to be trusted). */
static int try_refactor(fb_auglin *a)
{
  ++a->nfactor;
  if (!klu_l_refactor(a->sp, a->si, a->s.val, a->symbolic, a->numeric, &a->common) ||
      a->common.status != KLU_OK)
    return 0;
  return klu_l_rcond(a->symbolic, a->numeric, &a->common) &&
         a->common.rcond >= REFACTOR_RCOND_MIN;
}

/* Full factorisation with partial pivoting; classifies failures. */
static int full_factor(fb_auglin *a, double gamma, fb_err *err)
{
  if (a->numeric)
    klu_l_free_numeric(&a->numeric, &a->common);
  ++a->nfactor;
  a->singular = -1;
  a->numeric = klu_l_factor(a->sp, a->si, a->s.val, a->symbolic, &a->common);
  if (a->common.status == KLU_SINGULAR) {
    /* KLU names the column of S, a kept unknown; z is what callers know. */
    for (size_t z = 0; z < a->nz; ++z)
      if (a->kidx[z] != NONE && (long)a->kidx[z] == (long)a->common.singular_col)
        a->singular = (long)z;
    return fb_err_set(err, FB_ESOLVER,
                      "Newton matrix P(gamma = %g) is singular (no pivot for kept unknown %ld "
                      "of %zu)",
                      gamma, (long)a->common.singular_col, a->nk);
  }
  if (!a->numeric && a->common.status == KLU_OUT_OF_MEMORY)
    return fb_err_set(err, FB_ENOMEM,
                      "out of memory in KLU factorisation of the Newton matrix");
  if (!a->numeric)
    return fb_err_set(err, FB_ESOLVER,
                      "KLU factorisation of the Newton matrix failed (status %ld)",
                      (long)a->common.status);
  if (!klu_l_rcond(a->symbolic, a->numeric, &a->common) || !(a->common.rcond >= SINGULAR_RCOND))
    return fb_err_set(err, FB_ESOLVER,
                      "Newton matrix P(gamma = %g) is singular to working precision "
                      "(pivot ratio %g)",
                      gamma, a->common.rcond);
  return FB_OK;
}

int fb_auglin_setup(fb_auglin *al, double gamma, const double *v0, const double *v1,
                    fb_err *err)
{
  condense(al, gamma, v0, v1);
  const int reuse = al->nk == 0 || (al->factored && try_refactor(al));
  al->factored = 0;
  if (!reuse) {
    const int rc = full_factor(al, gamma, err);
    if (rc != FB_OK)
      return rc;
  }
  al->factored = 1;
  return FB_OK;
}

/* y over E by forward substitution, then the kept right-hand side. */
static void forward(fb_auglin *a)
{
  const size_t *ptr = a->f.ptr, *col = a->f.col;
  const double *val = a->f.val;
  double *y = a->y;
  for (size_t r = 0; r < a->ne; ++r) {
    double ye = y[a->elim[r]];
    for (size_t t = ptr[r]; t < ptr[r + 1]; ++t)
      ye -= val[t] * y[col[t]];
    y[a->elim[r]] = ye;
  }
  for (size_t k = 0; k < a->nk; ++k) {
    double rk = y[a->kz[k]];
    for (size_t t = ptr[a->ne + k]; t < ptr[a->ne + k + 1]; ++t)
      rk -= val[t] * y[col[t]];
    a->rhs[k] = rk;
  }
}

int fb_auglin_solve(fb_auglin *al, const double *b, double *x, fb_err *err)
{
  if (!al->factored)
    return fb_err_set(err, FB_EINVAL, "Newton solve without a valid factorisation");
  memset(al->y, 0, al->nz * sizeof *al->y);
  for (size_t i = 0; i < al->nstates; ++i)
    al->y[al->state_rows[i]] = b[i];
  forward(al);
  if (al->nk && !klu_l_tsolve(al->symbolic, al->numeric, (SuiteSparse_long)al->nk, 1, al->rhs,
                              &al->common))
    return fb_err_set(err, FB_ESOLVER, "KLU solve failed (status %ld)",
                      (long)al->common.status);
  for (size_t i = 0; i < al->nstates; ++i) {
    const size_t z = al->state_rows[i];
    if (al->kidx[z] != NONE) {
      x[i] = al->rhs[al->kidx[z]];
      continue;
    }
    const size_t r = al->xrow[z];
    double v = al->y[z];
    for (size_t t = al->x.ptr[r]; t < al->x.ptr[r + 1]; ++t)
      v += al->x.val[t] * al->rhs[al->x.col[t]];
    x[i] = v;
  }
  return FB_OK;
}

long fb_auglin_nfactorizations(const fb_auglin *al)
{
  return al->nfactor;
}

size_t fb_auglin_nkept(const fb_auglin *al)
{
  return al->nk;
}

size_t fb_auglin_kept_nnz(const fb_auglin *al)
{
  return al->s.ptr[al->nk];
}

long fb_auglin_singular_unknown(const fb_auglin *al)
{
  return al->singular;
}
