/* SPDX-License-Identifier: BSD-3-Clause */
/* Conformance of the block kinds (src/bd/kind_*.c) and of the elements
 * their blocks realise.
 *
 * Every kind of the registry fb_bd_kinds, as fb_bd_build makes it from
 * graphs that hold every element kind and every library law, goes
 * through the same checks at random signals (a block is checked on its
 * own: its inputs need not be what the rest of the diagram would give
 * it):
 *   - its rows: exactly nnz triplets, each in one of its output rows and
 *     in its output or input columns, the same pattern at any signals, no
 *     gamma term unless it is a state, the unit coefficient on its output
 *     where it claims unit_rows;
 *   - its jvp against central finite differences of its eval;
 *   - its jvp against its rows: B d(out) - sum_k A_k d(in_k) = 0 (for a
 *     state, d(x) - gamma d(x') = 0 with d(x) = gamma d(x'));
 *   - where it claims to be linear (or piecewise linear, in its mode):
 *     f(a x + b y) = a f(x) + b f(y) + (1 - a - b) f(0), the affine form
 *     that a source (f(0) = u(t)) satisfies too, and rows that do not
 *     change with the signals;
 *   - its other claims: a block that is not time-varying does not change
 *     with t, an exogenous one has no inputs, a product's output is
 *     in_0 .* in_1, a state has no eval, a switched one settles in a mode,
 *     every input has the dimension it asks for.
 * The diagram as a whole must balance power at every element: a
 * junction, TF, GY, MTF or composite passes it on (the sum of e.f into it
 * is 0), a storage field takes in d(energy)/dt, a resistor takes in
 * >= 0. A kind of the registry that no graph here makes, a block of a kind
 * the registry does not list, or an element kind no graph holds, fails.
 *
 * Last, the harness must bite: every kind with its jvp off by 1e-4 in one
 * component, and kinds whose jvp forgets their last input (a product
 * dropping the f term of d(e.f), a modulated law its modulating value, a
 * junction's sum one bond), must fail it. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"

#include "bd/kinds.h"
#include "bgtest_util.h"
#include "check.h"
#include "conformance.h"

/* ---- The checks of one block. */

typedef struct harness {
  size_t nw;                /* signals of the diagram under test */
  double *w, *wp, *wm, *dw; /* nw each */
  double *dw0;
  size_t cap;                        /* triplets the buffers below hold */
  size_t *rows, *cols, *prow, *pcol; /* values' and pattern's triplets */
  double *v0, *v1, *u0, *u1;
  int quiet;       /* 1 while a broken kind runs: its failures are expected */
  size_t failures; /* since the harness started */
} harness;

static void fail(harness *h, const bd_block *b, const char *what, size_t i, double got,
                 double want)
{
  h->failures++;
  if (!h->quiet)
    fprintf(stderr, "kind %s, block '%s': %s (at %zu: %.12g, expected %.12g)\n", b->ops->kind,
            b->label, what, i, got, want);
}

static int harness_reserve(harness *h, size_t nw, size_t nnz)
{
  h->nw = nw;
  free(h->w), free(h->wp), free(h->wm), free(h->dw), free(h->dw0);
  h->w = malloc((nw + 1) * sizeof *h->w);
  h->wp = malloc((nw + 1) * sizeof *h->wp);
  h->wm = malloc((nw + 1) * sizeof *h->wm);
  h->dw = malloc((nw + 1) * sizeof *h->dw);
  h->dw0 = malloc((nw + 1) * sizeof *h->dw0);
  if (nnz + 1 > h->cap) {
    h->cap = nnz + 1;
    free(h->rows), free(h->cols), free(h->prow), free(h->pcol);
    free(h->v0), free(h->v1), free(h->u0), free(h->u1);
    h->rows = malloc(h->cap * sizeof *h->rows);
    h->cols = malloc(h->cap * sizeof *h->cols);
    h->prow = malloc(h->cap * sizeof *h->prow);
    h->pcol = malloc(h->cap * sizeof *h->pcol);
    h->v0 = malloc(h->cap * sizeof *h->v0);
    h->v1 = malloc(h->cap * sizeof *h->v1);
    h->u0 = malloc(h->cap * sizeof *h->u0);
    h->u1 = malloc(h->cap * sizeof *h->u1);
  }
  return h->w && h->wp && h->wm && h->dw && h->dw0 && h->rows && h->cols && h->prow &&
         h->pcol && h->v0 && h->v1 && h->u0 && h->u1;
}

static void harness_free(harness *h)
{
  free(h->w), free(h->wp), free(h->wm), free(h->dw), free(h->dw0);
  free(h->rows), free(h->cols), free(h->prow), free(h->pcol);
  free(h->v0), free(h->v1), free(h->u0), free(h->u1);
}

static int in_output(const bd_block *b, size_t i)
{
  return i >= b->ooff && i < b->ooff + b->odim;
}

static int in_input(const bd_block *b, size_t i)
{
  for (size_t k = 0; k < b->nin; ++k)
    if (i >= b->ioff[k] && i < b->ioff[k] + b->idim[k])
      return 1;
  return 0;
}

/* The mode of a switched block that its guards choose at w, as
 * fb_bd_sync_modes settles it; fails if it does not settle. */
static void settle_mode(harness *h, bd_block *b, const double *w)
{
  size_t ng = fb_bd_block_nguards(b);
  if (!ng)
    return;
  double g[8];
  int sign[8];
  if (ng > 8 || !b->ops->guards || !b->ops->switch_mode) {
    fail(h, b, "switched without guards and switch_mode (or more than 8 guards)", 0, 0, 0);
    return;
  }
  for (int round = 0; round < 16; ++round) {
    int changed = 0;
    if (b->ops->guards(b, w, g))
      fail(h, b, "guards failed", 0, 0, 0);
    for (size_t i = 0; i < ng; ++i)
      sign[i] = g[i] < 0.0 ? -1 : 1;
    if (b->ops->switch_mode(b, w, sign, &changed))
      fail(h, b, "switch_mode failed", 0, 0, 0);
    if (!changed)
      return;
  }
  fail(h, b, "the mode does not settle", 0, 0, 0);
}

/* Its triplets at h->w into rows, cols, v0, v1, beyond nnz a sentinel
 * that must stay; the pattern alone into prow, pcol. */
static void check_rows(harness *h, bd_block *b)
{
  const size_t n = b->ops->nnz(b);
  for (size_t k = 0; k <= n; ++k) {
    h->rows[k] = h->cols[k] = h->prow[k] = h->pcol[k] = SIZE_MAX;
    h->v0[k] = h->v1[k] = NAN;
  }
  if (b->ops->jac(b, h->w, h->rows, h->cols, h->v0, h->v1))
    fail(h, b, "jac failed", 0, 0, 0);
  (void)b->ops->jac(b, h->w, h->prow, h->pcol, NULL, NULL);
  if (h->rows[n] != SIZE_MAX || !isnan(h->v0[n]) || h->prow[n] != SIZE_MAX)
    fail(h, b, "writes more triplets than its nnz", n, 0, 0);
  for (size_t k = 0; k < n; ++k) {
    if (h->rows[k] == SIZE_MAX || isnan(h->v0[k]) || isnan(h->v1[k]))
      fail(h, b, "leaves a triplet of its nnz unwritten", k, 0, 0);
    else if (!in_output(b, h->rows[k]))
      fail(h, b, "a triplet outside its output rows", k, (double)h->rows[k], (double)b->ooff);
    else if (!in_output(b, h->cols[k]) && !in_input(b, h->cols[k]))
      fail(h, b, "a triplet outside its input and output columns", k, (double)h->cols[k], 0);
    if (h->prow[k] != h->rows[k] || h->pcol[k] != h->cols[k])
      fail(h, b, "the pattern differs from the values' triplets", k, (double)h->prow[k],
           (double)h->rows[k]);
    if (!b->ops->state && h->v1[k] != 0.0)
      fail(h, b, "a gamma term on a block that is not a state", k, h->v1[k], 0.0);
  }
}

/* unit_rows: on each output row, the coefficients on the output sum to 1
 * on its own component and to 0 on the others. */
static void check_unit_rows(harness *h, bd_block *b)
{
  const size_t n = b->ops->nnz(b);
  for (size_t r = b->ooff; r < b->ooff + b->odim; ++r)
    for (size_t c = b->ooff; c < b->ooff + b->odim; ++c) {
      double s = 0.0;
      for (size_t k = 0; k < n; ++k)
        if (h->rows[k] == r && h->cols[k] == c)
          s += h->v0[k];
      if (s != (r == c ? 1.0 : 0.0))
        fail(h, b, "claims unit rows, but its coefficient on its output is", r, s,
             r == c ? 1.0 : 0.0);
    }
}

/* Row residuals sum_k (v0 + gamma v1) dw[col] at dw, against their scale;
 * the triplets are those check_rows left. */
static void check_residuals(harness *h, bd_block *b, double gamma, const char *what)
{
  const size_t n = b->ops->nnz(b);
  for (size_t r = b->ooff; r < b->ooff + b->odim; ++r) {
    double res = 0.0, mag = 0.0;
    for (size_t k = 0; k < n; ++k)
      if (h->rows[k] == r) {
        const double t = (h->v0[k] + gamma * h->v1[k]) * h->dw[h->cols[k]];
        res += t;
        mag += fabs(t);
      }
    if (!(fabs(res) <= EXACT_TOL * mag))
      fail(h, b, what, r, res, 0.0);
  }
}

/* The jvp against the rows at the same signals: with dw on the inputs
 * and the jvp's d(out), every row is 0. A state's jvp passes nothing
 * on; its rows hold with d(x) = gamma d(x'). Nothing outside the output
 * may change. */
static void check_jvp_rows(harness *h, bd_block *b)
{
  randomize(h->dw, h->nw);
  memcpy(h->dw0, h->dw, h->nw * sizeof *h->dw);
  if (b->ops->jvp(b, h->w, h->dw))
    fail(h, b, "jvp failed", 0, 0, 0);
  for (size_t i = 0; i < h->nw; ++i)
    if ((b->ops->state || !in_output(b, i)) && h->dw[i] != h->dw0[i])
      fail(h, b, b->ops->state ? "a state's jvp changes dw" : "jvp writes outside its output",
           i, h->dw[i], h->dw0[i]);
  if (!b->ops->state) {
    check_residuals(h, b, 0.0, "jvp disagrees with its rows: residual");
    return;
  }
  const double gamma = 0.37;
  for (size_t i = 0; i < b->odim; ++i)
    h->dw[b->ooff + i] = gamma * h->dw[b->ioff[0] + i];
  check_residuals(h, b, gamma, "a state's rows do not give d(x) = gamma d(x'): residual");
}

/* eval of b at signals v (its output written into v). */
static void eval_at(harness *h, bd_block *b, double t, double *v)
{
  if (b->ops->eval(b, t, v))
    fail(h, b, "eval failed", 0, 0, 0);
}

/* The jvp along a random direction of the inputs against the central
 * difference of eval (see FD_STEP). */
static void check_jvp_fd(harness *h, bd_block *b)
{
  const double t = 0.7;
  memset(h->dw, 0, h->nw * sizeof *h->dw);
  memcpy(h->wp, h->w, h->nw * sizeof *h->w);
  memcpy(h->wm, h->w, h->nw * sizeof *h->w);
  for (size_t i = 0; i < h->nw; ++i)
    if (in_input(b, i)) {
      h->dw[i] = urand();
      h->wp[i] += FD_STEP * h->dw[i];
      h->wm[i] -= FD_STEP * h->dw[i];
    }
  eval_at(h, b, t, h->w);
  eval_at(h, b, t, h->wp);
  eval_at(h, b, t, h->wm);
  if (b->ops->jvp(b, h->w, h->dw))
    fail(h, b, "jvp failed", 0, 0, 0);
  for (size_t i = b->ooff; i < b->ooff + b->odim; ++i) {
    const double fd = (h->wp[i] - h->wm[i]) / (2.0 * FD_STEP);
    const double tol = FD_TOL * (1.0 + fabs(h->dw[i]) + fabs(h->w[i]));
    if (!(fabs(fd - h->dw[i]) <= tol))
      fail(h, b, "jvp differs from the central difference", i, h->dw[i], fd);
  }
}

static int claims_linear(const bd_block *b)
{
  return b->ops->piecewise_linear ? b->ops->piecewise_linear(b) : b->ops->linear;
}

/* A linear (or, in its mode, piecewise linear) kind: eval affine in the
 * inputs and rows that do not change. h->w holds a point in the block's
 * mode; the other points keep that mode. */
static void check_linear(harness *h, bd_block *b)
{
  const double t = 0.7, a = urand() * 2.0, c = urand() * 2.0;
  double *x = h->w, *y = h->wp, *z = h->wm, *mix = h->dw0;
  randomize(y, h->nw);
  memcpy(z, x, h->nw * sizeof *x);
  memcpy(mix, x, h->nw * sizeof *x);
  for (size_t i = 0; i < h->nw; ++i)
    if (in_input(b, i)) {
      z[i] = 0.0;
      mix[i] = a * x[i] + c * y[i];
    }
  check_rows(h, b); /* the rows at x */
  memcpy(h->u0, h->v0, b->ops->nnz(b) * sizeof *h->u0);
  memcpy(h->u1, h->v1, b->ops->nnz(b) * sizeof *h->u1);
  eval_at(h, b, t, x);
  eval_at(h, b, t, y);
  eval_at(h, b, t, z);
  eval_at(h, b, t, mix);
  for (size_t i = b->ooff; i < b->ooff + b->odim; ++i) {
    const double want = a * x[i] + c * y[i] + (1.0 - a - c) * z[i];
    const double scale = fabs(a * x[i]) + fabs(c * y[i]) + fabs((1.0 - a - c) * z[i]);
    if (!(fabs(mix[i] - want) <= EXACT_TOL * (scale + fabs(mix[i]))))
      fail(h, b, "claims to be linear, but f(a x + b y) differs", i, mix[i], want);
  }
  memcpy(h->w, y, h->nw * sizeof *y);
  check_rows(h, b); /* the rows at y */
  for (size_t k = 0; k < b->ops->nnz(b); ++k)
    if (h->v0[k] != h->u0[k] || h->v1[k] != h->u1[k])
      fail(h, b, "claims to be linear, but its rows change with the signals", k, h->v0[k],
           h->u0[k]);
}

/* The properties that do not need finite differences. */
static void check_claims(harness *h, bd_block *b)
{
  const bd_block_ops *o = b->ops;
  for (size_t k = 0; k < b->nin; ++k) {
    size_t need = o->input_dim ? o->input_dim(b, k) : b->odim;
    if (need != FB_NONE && need != b->idim[k])
      fail(h, b, "an input of another dimension than input_dim", k, (double)b->idim[k],
           (double)need);
  }
  if (o->state && (o->eval || b->nin != 1 || b->idim[0] != b->odim))
    fail(h, b, "a state with an eval, or not one input of its size", 0, (double)b->nin, 1.0);
  if (!o->state && !o->eval)
    fail(h, b, "no eval, and not a state", 0, 0, 0);
  if (o->exogenous && b->nin != 0)
    fail(h, b, "exogenous, but has inputs", 0, (double)b->nin, 0.0);
  if (o->state)
    return;
  eval_at(h, b, 0.3, h->w);
  memcpy(h->wp, h->w, h->nw * sizeof *h->w);
  eval_at(h, b, 1.9, h->wp);
  for (size_t i = b->ooff; !(o->time_varying && o->time_varying(b)) && i < b->ooff + b->odim;
       ++i)
    if (h->wp[i] != h->w[i])
      fail(h, b, "not time-varying, but its output changes with t", i, h->wp[i], h->w[i]);
  if (o->product && (b->nin != 2 || b->idim[0] != b->odim || b->idim[1] != b->odim))
    fail(h, b, "a product, but not of two inputs of its size", 0, (double)b->nin, 2.0);
  for (size_t i = 0; o->product && b->nin == 2 && i < b->odim; ++i) {
    const double want = h->w[b->ioff[0] + i] * h->w[b->ioff[1] + i];
    if (h->w[b->ooff + i] != want)
      fail(h, b, "a product, but its output is not in_0 .* in_1", i, h->w[b->ooff + i], want);
  }
}

/* Every check at the signals in h->w, in the mode they choose. */
static void check_at(harness *h, bd_block *b)
{
  settle_mode(h, b, h->w);
  check_claims(h, b);
  check_rows(h, b);
  if (b->ops->unit_rows)
    check_unit_rows(h, b);
  check_jvp_rows(h, b);
  if (!b->ops->state)
    check_jvp_fd(h, b);
  if (!b->ops->state && claims_linear(b))
    check_linear(h, b);
}

/* The signals diagram bd computes at a random state and time, with the
 * modes its guards choose there, into h->w. */
static void diagram_signals(harness *h, fb_bd *bd)
{
  const double t = 2.0 * fabs(urand());
  double *x = h->wp; /* the states are the first signals: nstates <= nw */
  int changed;
  randomize(x, bd->nstates);
  CHECK(fb_bd_sync_modes(bd, t, x, &changed) == 0);
  CHECK(fb_bd_eval(bd, t, x) == 0);
  memcpy(h->w, bd->w, h->nw * sizeof *h->w);
}

/* Every check at NSAMPLES random signal vectors (unless the kind's rows
 * need consistent inputs), then at NSAMPLES that the diagram computes. */
static void check_block(harness *h, fb_bd *bd, bd_block *b)
{
  for (int s = 0; !b->ops->consistent_inputs && s < NSAMPLES; ++s) {
    randomize(h->w, h->nw);
    check_at(h, b);
  }
  for (int s = 0; s < NSAMPLES; ++s) {
    diagram_signals(h, bd);
    check_at(h, b);
  }
}

/* The registry index of a kind, fb_bd_nkinds if it is not there. */
static size_t kind_index(const bd_block_ops *ops)
{
  size_t k = 0;
  while (k < fb_bd_nkinds && fb_bd_kinds[k] != ops)
    ++k;
  return k;
}

static int harness_for(harness *h, const fb_bd *bd)
{
  size_t nnz = 0;
  for (size_t i = 0; i < bd->nblocks; ++i) {
    const size_t n = bd->blocks[i].ops->nnz(&bd->blocks[i]);
    nnz = n > nnz ? n : nnz;
  }
  return harness_reserve(h, bd->nw, nnz);
}

/* Every block of bd; seen[k] = 1 for each registry kind k met. */
static void check_diagram(harness *h, fb_bd *bd, unsigned char *seen)
{
  CHECK(harness_for(h, bd));
  for (size_t i = 0; i < bd->nblocks; ++i) {
    bd_block *b = &bd->blocks[i];
    const size_t k = kind_index(b->ops);
    if (k == fb_bd_nkinds)
      fail(h, b, "a kind that fb_bd_kinds does not list", i, 0, 0);
    else
      seen[k] = 1;
    check_block(h, bd, b);
  }
}

/* ---- Graphs that hold every element kind, every block kind and every
 * library law. */

/* A field of n ports of dimension 1 each, or of one port of dimension n
 * (one_port), with the n x n matrix rowmajor. */
static int add_matrix_field(fb_bg *bg, const char *name, fb_bg_kind kind, size_t n,
                            int one_port, const double *rowmajor, fb_err *err)
{
  fb_mat *m = NULL;
  const size_t dims[2] = {1, 1};
  int rc = fb_mat_new_dense_rowmajor(n, n, rowmajor, &m, err);
  return rc ? rc
            : fb_bg_add_field(bg, name, kind, one_port ? 1 : n, one_port ? &n : dims, &m, err);
}

static int add_sine_source(fb_bg *bg, const char *name, fb_bg_kind kind, fb_err *err)
{
  fb_tfun *f = NULL;
  int rc = fb_tfun_new_sine(0.5, 1.3, 0.2, 0.1, &f, err);
  return rc ? rc : fb_bg_add_source(bg, name, kind, 1, &f, err);
}

static void connect_all(fb_bg *bg, const char *const (*bonds)[3], size_t n, fb_err *err)
{
  for (size_t i = 0; i < n; ++i)
    MUST(fb_bg_connect(bg, bonds[i][0], bonds[i][1], bonds[i][2], err), err);
}

/* Every element kind with matrix laws, in every causality that gives a
 * block kind of its own: scalar storage and resistors (gains, an inverse
 * gain), a TF, a GY, multiport and vector fields (mux, demux, solves of
 * an I field and of a conductance), a composite and an inverted MTF
 * (solves), junctions of both kinds and dimensions. */
static fb_bg *linear_graph(fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("linear", &bg, err), err);
  const double d[4] = {1.5, -0.5, -0.5, 1.0}, t[4] = {1.0, 0.3, -0.2, 0.8};
  const double m[4] = {2.0, 0.4, 0.4, 1.0}, kv[4] = {3.0, -1.0, -1.0, 2.0};
  const double rv[4] = {1.2, 0.3, 0.3, 0.9};
  fb_mat *tm = NULL;
  MUST(add_scalar(bg, "m1", FB_BG_I, 1.5, err), err);
  MUST(add_scalar(bg, "k1", FB_BG_C, 3.0, err), err);
  MUST(add_scalar(bg, "r1", FB_BG_R, 0.8, err), err);
  MUST(add_scalar(bg, "k2", FB_BG_C, 2.0, err), err);
  MUST(add_scalar(bg, "r2", FB_BG_R, 1.7, err), err);
  MUST(add_scalar(bg, "m4", FB_BG_I, 0.9, err), err);
  MUST(add_scalar(bg, "k5", FB_BG_C, 1.2, err), err);
  MUST(add_scalar(bg, "k6", FB_BG_C, 0.7, err), err);
  MUST(add_sine_source(bg, "vin", FB_BG_SF, err), err);
  MUST(add_const_source(bg, "fconst", FB_BG_SE, 0.4, err), err);
  MUST(fb_bg_add_tf(bg, "tf", FB_BG_TF, 1, 2.0, err), err);
  MUST(fb_bg_add_tf(bg, "gy", FB_BG_GY, 1, 1.5, err), err);
  MUST(add_matrix_field(bg, "D", FB_BG_R, 2, 0, d, err), err);
  MUST(add_matrix_field(bg, "M", FB_BG_I, 2, 1, m, err), err);
  MUST(add_matrix_field(bg, "Kv", FB_BG_C, 2, 1, kv, err), err);
  MUST(add_matrix_field(bg, "Rv", FB_BG_R, 2, 1, rv, err), err);
  MUST(fb_bg_add_composite(bg, "comp", 2, (const size_t[]){1, 1}, err), err);
  MUST(fb_mat_new_dense_rowmajor(2, 2, t, &tm, err), err);
  MUST(fb_bg_add_mtf(bg, "mtf", &tm, err), err);
  const char *const j1[] = {"J1a", "J1d", "J1e", "J1f"};
  for (size_t i = 0; i < 4; ++i)
    MUST(fb_bg_add_junction(bg, j1[i], FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "J0a", FB_BG_J0, 1, err), err);
  MUST(fb_bg_add_junction(bg, "J1v", FB_BG_J1, 2, err), err);
  MUST(fb_bg_add_junction(bg, "J0v", FB_BG_J0, 2, err), err);
  static const char *const bonds[][3] = {
      {"b_m1", "J1a", "m1"},           {"b_k1", "J1a", "k1"},     {"b_r1", "J1a", "r1"},
      {"b_tf1", "J1a", "tf.1"},        {"b_tf2", "tf.2", "J0a"},  {"b_k2", "J0a", "k2"},
      {"b_r2", "J0a", "r2"},           {"b_vin", "vin", "J0a"},   {"b_gy1", "J1a", "gy.1"},
      {"b_gy2", "gy.2", "J1d"},        {"b_m4", "J1d", "m4"},     {"b_fc", "fconst", "J1d"},
      {"b_k5", "J1e", "k5"},           {"b_k6", "J1f", "k6"},     {"b_d1", "J1e", "D.1"},
      {"b_d2", "J1f", "D.2"},          {"b_c1", "J1e", "comp.1"}, {"b_c2", "J1f", "comp.2"},
      {"b_cw", "comp.whole", "mtf.1"}, {"b_t2", "mtf.2", "J1v"},  {"b_M", "J1v", "M"},
      {"b_v", "J1v", "J0v"},           {"b_Kv", "J0v", "Kv"},     {"b_Rv", "J0v", "Rv"},
  };
  connect_all(bg, bonds, sizeof bonds / sizeof bonds[0], err);
  return bg;
}

/* The library's laws: a unilateral contact (a switched C, a switched and
 * modulated R) and a table R, on a mass under a time-varying force. */
static fb_bg *law_graph(fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("laws", &bg, err), err);
  MUST(conformance_add_laws(bg, err), err);
  MUST(add_scalar(bg, "mass", FB_BG_I, 1.2, err), err);
  MUST(add_sine_source(bg, "force", FB_BG_SE, err), err);
  MUST(fb_bg_add_junction(bg, "Jb", FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "Jc", FB_BG_J1, 1, err), err);
  static const char *const bonds[][3] = {
      {"b_mass", "Jb", "mass"}, {"b_force", "force", "Jb"}, {"b_shock", "Jb", "shock"},
      {"b_c", "Jb", "Jc"},      {"b_tire", "Jc", "tire"},   {"b_td", "Jc", "tire_d"},
  };
  connect_all(bg, bonds, sizeof bonds / sizeof bonds[0], err);
  return bg;
}

/* ---- Probes: the ones that give the probe kinds, then the effort and
 * flow of every bond and the energy of every storage element (for the
 * power balance). */

typedef struct probes {
  fb_probe_spec *spec;
  size_t n;
  char (*names)[32];
  size_t *e_out, *f_out, *energy_out; /* per bond / element: first output */
} probes;

static fb_probe_spec probe(const char *name, fb_probe_kind kind, const char *target)
{
  return (fb_probe_spec){name, kind, target, -1, 0, 1.0, NULL, NULL, 0};
}

static int has_energy(const fb_bg *bg, size_t e)
{
  const fb_bg_kind k = fb_bg_element_kind(bg, e);
  const fb_law_ops *law = fb_bg_element_law(bg, e, NULL);
  return (k == FB_BG_I || k == FB_BG_C) && (!law || law->energy);
}

/* The probe kinds' own probes (a power, an energy, a state, an
 * integrated flow, weights over a vector state) where the graph has their
 * targets, then the balance's. */
static int probes_make(const fb_bg *bg, probes *p)
{
  static const double weights[2] = {0.5, -2.0};
  const size_t nb = fb_bg_nbonds(bg), ne = fb_bg_nelements(bg);
  p->spec = calloc(2 * nb + ne + 8, sizeof *p->spec);
  p->names = calloc(2 * nb + ne + 8, sizeof *p->names);
  p->e_out = calloc(nb + 1, sizeof *p->e_out);
  p->f_out = calloc(nb + 1, sizeof *p->f_out);
  p->energy_out = calloc(ne + 1, sizeof *p->energy_out);
  if (!p->spec || !p->names || !p->e_out || !p->f_out || !p->energy_out)
    return 0;
  p->n = 0;
  size_t nout = 0;
  if (fb_bg_find_bond(bg, "b_r1") >= 0) {
    fb_probe_spec w = probe("Kv_weighted", FB_PROBE_STATE, "Kv");
    w.weights = weights;
    w.nweights = 2;
    fb_probe_spec in = probe("k2_q", FB_PROBE_FLOW, "b_k2");
    in.integrate = 1;
    p->spec[p->n++] = probe("r1_power", FB_PROBE_POWER, "b_r1");
    p->spec[p->n++] = probe("k1_state", FB_PROBE_STATE, "k1");
    p->spec[p->n++] = in;
    p->spec[p->n++] = w;
    nout += 4;
  } else {
    p->spec[p->n++] = probe("td_power", FB_PROBE_POWER, "b_td");
    nout += 1;
  }
  /* One output per component of a bond, one per energy. */
  for (size_t b = 0; b < nb; ++b)
    for (int f = 0; f < 2; ++f) {
      char *name = p->names[p->n];
      snprintf(name, sizeof p->names[0], "%c%zu", f ? 'f' : 'e', b);
      p->spec[p->n++] =
          probe(name, f ? FB_PROBE_FLOW : FB_PROBE_EFFORT, fb_bg_bond_name(bg, b));
      (f ? p->f_out : p->e_out)[b] = nout;
      nout += fb_bg_bond_dim(bg, b);
    }
  for (size_t e = 0; e < ne; ++e)
    if (has_energy(bg, e)) {
      char *name = p->names[p->n];
      snprintf(name, sizeof p->names[0], "E%zu", e);
      p->spec[p->n++] = probe(name, FB_PROBE_ENERGY, fb_bg_element_name(bg, e));
      p->energy_out[e] = nout++;
    }
  return 1;
}

static void probes_free(probes *p)
{
  free(p->spec);
  free(p->names);
  free(p->e_out);
  free(p->f_out);
  free(p->energy_out);
}

/* ---- Power balance of the elements. */

/* Power into element e at the outputs y: sum over its bonds of e.f,
 * counted + where the bond points at e; *mag gets the sum of |e_i f_i|. */
static double power_in(const fb_bg *bg, const probes *p, const double *y, size_t e, double *mag)
{
  double s = 0.0;
  *mag = 0.0;
  for (size_t b = 0; b < fb_bg_nbonds(bg); ++b) {
    const int into = fb_bg_bond_to(bg, b) == e, from = fb_bg_bond_from(bg, b) == e;
    if (!into && !from)
      continue;
    for (size_t i = 0; i < fb_bg_bond_dim(bg, b); ++i) {
      const double ef = y[p->e_out[b] + i] * y[p->f_out[b] + i];
      s += into ? ef : -ef;
      *mag += fabs(ef);
    }
  }
  return s;
}

typedef struct balance {
  fb_bd *bd;
  const probes *p;
  size_t n;                     /* states */
  double *x, *xd, *xs, *y, *ys; /* states (x, x', shifted x) and outputs */
} balance;

/* d(energy of e)/dt at b->x along x' by central differences (FD_STEP,
 * FD_TOL: the energies here are quadratic or C1 in the state). */
static double energy_rate(balance *b, double t, size_t e)
{
  double ep[2];
  for (int s = 0; s < 2; ++s) {
    for (size_t i = 0; i < b->n; ++i)
      b->xs[i] = b->x[i] + (s ? -FD_STEP : FD_STEP) * b->xd[i];
    CHECK(fb_bd_outputs(b->bd, t, b->xs, b->ys) == 0);
    ep[s] = b->ys[b->p->energy_out[e]];
  }
  return (ep[0] - ep[1]) / (2.0 * FD_STEP);
}

/* The balance of element e at the outputs b->y; seen[kind] = 1. */
static void check_element_power(balance *b, const fb_bg *bg, double t, size_t e,
                                unsigned char *seen)
{
  const fb_bg_kind kind = fb_bg_element_kind(bg, e);
  seen[kind] = 1;
  double mag;
  const double pin = power_in(bg, b->p, b->y, e, &mag);
  const char *name = fb_bg_element_name(bg, e);
  switch (kind) {
  case FB_BG_J0:
  case FB_BG_J1:
  case FB_BG_TF:
  case FB_BG_GY:
  case FB_BG_MTF:
  case FB_BG_COMPOSITE:
    if (!(fabs(pin) <= EXACT_TOL * mag))
      fprintf(stderr, "%s '%s' does not conserve power: %.12g in (of %.12g)\n",
              fb_bg_kind_name(kind), name, pin, mag);
    CHECK(fabs(pin) <= EXACT_TOL * mag);
    break;
  case FB_BG_R:
    if (!(pin >= -EXACT_TOL * mag))
      fprintf(stderr, "R '%s' delivers power: %.12g in\n", name, pin);
    CHECK(pin >= -EXACT_TOL * mag);
    break;
  case FB_BG_I:
  case FB_BG_C: {
    const double rate = energy_rate(b, t, e), energy = b->y[b->p->energy_out[e]];
    const double tol = FD_TOL * (1.0 + fabs(pin) + fabs(energy));
    if (!(fabs(rate - pin) <= tol))
      fprintf(stderr, "%s '%s': power in %.12g, d(energy)/dt %.12g\n", fb_bg_kind_name(kind),
              name, pin, rate);
    CHECK(fabs(rate - pin) <= tol);
    break;
  }
  case FB_BG_SE:
  case FB_BG_SF: break; /* a source gives whatever power its bond takes */
  }
}

/* At random states and times, with the modes their guards choose. */
static void check_power(fb_bd *bd, const fb_bg *bg, const probes *p, unsigned char *seen)
{
  balance b = {bd, p, fb_bd_nstates(bd), NULL, NULL, NULL, NULL, NULL};
  const size_t ny = fb_bd_noutputs(bd);
  b.x = malloc((b.n + 1) * sizeof *b.x);
  b.xd = malloc((b.n + 1) * sizeof *b.xd);
  b.xs = malloc((b.n + 1) * sizeof *b.xs);
  b.y = malloc((ny + 1) * sizeof *b.y);
  b.ys = malloc((ny + 1) * sizeof *b.ys);
  CHECK(b.x && b.xd && b.xs && b.y && b.ys);
  for (int s = 0; b.ys && s < NSAMPLES; ++s) {
    const double t = 2.0 * fabs(urand());
    int changed;
    randomize(b.x, b.n);
    CHECK(fb_bd_sync_modes(bd, t, b.x, &changed) == 0);
    CHECK(fb_bd_rhs(bd, t, b.x, b.xd) == 0);
    CHECK(fb_bd_outputs(bd, t, b.x, b.y) == 0);
    for (size_t e = 0; e < fb_bg_nelements(bg); ++e)
      check_element_power(&b, bg, t, e, seen);
  }
  free(b.x);
  free(b.xd);
  free(b.xs);
  free(b.y);
  free(b.ys);
}

/* ---- Broken kinds: a real kind's ops with a jvp wrapped wrong. */

static const bd_block_ops *real_ops; /* of the block under a broken jvp */

/* The real jvp, then its first output component off by 1e-4 (relative,
 * and absolute where it is 0). */
static int jvp_off(bd_block *b, const double *w, double *dw)
{
  int rc = real_ops->jvp(b, w, dw);
  dw[b->ooff] += 1e-4 * (1.0 + fabs(dw[b->ooff]));
  return rc;
}

/* The real jvp with the perturbation of the last input left out. */
static int jvp_without_last_input(bd_block *b, const double *w, double *dw)
{
  const size_t k = b->nin - 1, n = b->idim[k];
  double *saved = malloc((n + 1) * sizeof *saved);
  if (!saved)
    return -1;
  memcpy(saved, dw + b->ioff[k], n * sizeof *saved);
  memset(dw + b->ioff[k], 0, n * sizeof *saved);
  int rc = real_ops->jvp(b, w, dw);
  memcpy(dw + b->ioff[k], saved, n * sizeof *saved);
  free(saved);
  return rc;
}

/* Runs block b of bd with its jvp replaced by jvp; the harness must find
 * it wrong. */
static void check_bites(harness *h, fb_bd *bd, bd_block *b,
                        int (*jvp)(bd_block *, const double *, double *), const char *how)
{
  bd_block_ops broken = *b->ops;
  broken.jvp = jvp;
  real_ops = b->ops;
  b->ops = &broken;
  CHECK(harness_for(h, bd));
  const size_t before = h->failures;
  h->quiet = 1;
  check_block(h, bd, b);
  h->quiet = 0;
  b->ops = real_ops;
  const size_t found = h->failures - before;
  h->failures = before;
  fprintf(stderr, "kind %s (block '%s') with a jvp that %s: %zu failures found%s\n",
          b->ops->kind, b->label, how, found, found ? "" : ": THE HARNESS DOES NOT BITE");
  CHECK(found > 0);
}

/* The first block of bd of that kind with at least nin inputs (and, for a
 * law, modulating ones), or NULL. */
static bd_block *find_block(fb_bd *bd, const char *kind, size_t nin)
{
  for (size_t i = 0; i < bd->nblocks; ++i)
    if (strcmp(bd->blocks[i].ops->kind, kind) == 0 && bd->blocks[i].nin >= nin)
      return &bd->blocks[i];
  return NULL;
}

/* Every kind off by 1e-4, and the kinds that read two inputs or more
 * without their last one (a law's last input is its modulating value,
 * whose derivative is not 0 where the damper is released). */
static void check_broken(harness *h, fb_bd *const *bds, size_t nbd)
{
  for (size_t k = 0; k < fb_bd_nkinds; ++k)
    for (size_t d = 0; d < nbd; ++d) {
      bd_block *b = find_block(bds[d], fb_bd_kinds[k]->kind, 0);
      if (b) {
        check_bites(h, bds[d], b, jvp_off, "is off by 1e-4");
        break;
      }
    }
  static const char *const forgetful[] = {"product", "law", "sum"};
  for (size_t k = 0; k < 3; ++k) {
    bd_block *b = NULL;
    size_t d = 0;
    for (; !b && d < nbd; ++d)
      b = find_block(bds[d], forgetful[k], 2);
    CHECK(b != NULL);
    if (b)
      check_bites(h, bds[d - 1], b, jvp_without_last_input, "forgets its last input");
  }
}

int main(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *graphs[2] = {linear_graph(&err), law_graph(&err)};
  fb_bd *bds[2] = {NULL, NULL};
  probes p[2];
  harness h;
  memset(&h, 0, sizeof h);
  unsigned char kind_seen[64] = {0}, elem_seen[64] = {0};
  CHECK(fb_bd_nkinds <= sizeof kind_seen);
  for (size_t g = 0; g < 2; ++g) {
    CHECK(graphs[g] && probes_make(graphs[g], &p[g]));
    MUST(fb_bd_build(graphs[g], p[g].spec, p[g].n, &bds[g], &err), &err);
    if (!bds[g])
      return check_report("test_bd_conformance");
    check_diagram(&h, bds[g], kind_seen);
    check_power(bds[g], graphs[g], &p[g], elem_seen);
  }
  for (size_t k = 0; k < fb_bd_nkinds; ++k) {
    if (!kind_seen[k])
      fprintf(stderr, "kind %s: no graph of the harness makes it\n", fb_bd_kinds[k]->kind);
    CHECK(kind_seen[k]);
  }
  for (int k = 0; strcmp(fb_bg_kind_name((fb_bg_kind)k), "?") != 0; ++k) {
    if (!elem_seen[k])
      fprintf(stderr, "element kind %s: no graph of the harness holds it\n",
              fb_bg_kind_name((fb_bg_kind)k));
    CHECK(elem_seen[k]);
  }
  fprintf(stderr, "test_bd_conformance: %zu failures of the real kinds\n", h.failures);
  CHECK(h.failures == 0);
  check_broken(&h, bds, 2);
  harness_free(&h);
  for (size_t g = 0; g < 2; ++g) {
    fb_bd_free(&bds[g]);
    fb_bg_free(&graphs[g]);
    probes_free(&p[g]);
  }
  return check_report("test_bd_conformance");
}
