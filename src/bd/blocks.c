/* Block kinds: evaluation, exact linearisation (jvp) and rows of the
 * augmented Newton matrix (see flexbond/bd.h). Each block's rows express
 * its law as B d(out) - sum_k A_k d(in_k) = 0; integrators give the state
 * rows d(x) - gamma d(x') = b. */
#include <string.h>

#include "bd/bd_internal.h"

/* Triplet writer: rows/cols may be NULL when only values are wanted,
 * v0/v1 NULL when only the pattern is. */
typedef struct trip {
  size_t *rows, *cols;
  double *v0, *v1;
  size_t k;
} trip;

static void put(trip *t, size_t r, size_t c, double v0, double v1)
{
  if (t->rows) {
    t->rows[t->k] = r;
    t->cols[t->k] = c;
  }
  if (t->v0) {
    t->v0[t->k] = v0;
    t->v1[t->k] = v1;
  }
  t->k++;
}

static void put_identity(trip *t, size_t off, size_t n)
{
  for (size_t i = 0; i < n; ++i)
    put(t, off + i, off + i, 1.0, 0.0);
}

/* ---- Integrator: output = state x, input = x'. */
static size_t integ_nnz(const bd_block *b)
{
  return 2 * b->odim;
}
static int integ_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                     double *v1)
{
  (void)w;
  trip t = {rows, cols, v0, v1, 0};
  for (size_t i = 0; i < b->odim; ++i) {
    put(&t, b->ooff + i, b->ooff + i, 1.0, 0.0);
    put(&t, b->ooff + i, b->ioff[0] + i, 0.0, -1.0);
  }
  return 0;
}
static int integ_jvp(bd_block *b, const double *w, double *dw)
{
  (void)b, (void)w, (void)dw;
  return 0;
}
const bd_block_ops fb_bd_integrator_ops = {"integrator", NULL,      integ_jvp,
                                           integ_nnz,    integ_jac, 1};

/* ---- Source: out_i = u_i(t). */
static int source_eval(bd_block *b, double t, double *w)
{
  for (size_t i = 0; i < b->odim; ++i)
    w[b->ooff + i] = fb_tfun_eval(b->fns[i], t);
  return 0;
}
static int source_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  memset(dw + b->ooff, 0, b->odim * sizeof *dw);
  return 0;
}
static size_t out_nnz(const bd_block *b)
{
  return b->odim;
}
static int source_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                      double *v1)
{
  (void)w;
  trip t = {rows, cols, v0, v1, 0};
  put_identity(&t, b->ooff, b->odim);
  return 0;
}
const bd_block_ops fb_bd_source_ops = {"source", source_eval, source_jvp,
                                       out_nnz,  source_jac,  1};

/* ---- Gain: out = A in. */
static int gain_apply(bd_block *b, double *v)
{
  fb_mat_gemv(b->mat, 1.0, v + b->ioff[0], 0.0, v + b->ooff);
  return 0;
}
static int gain_eval(bd_block *b, double t, double *w)
{
  (void)t;
  return gain_apply(b, w);
}
static int gain_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  return gain_apply(b, dw);
}
static size_t gain_nnz(const bd_block *b)
{
  return b->odim + fb_mat_nnz(b->mat);
}

typedef struct mat_visit {
  trip *t;
  size_t roff, coff;
  double scale;
} mat_visit;

static void visit_put(void *ctx, size_t r, size_t c, double v)
{
  mat_visit *m = ctx;
  put(m->t, m->roff + r, m->coff + c, m->scale * v, 0.0);
}

/* fb_mat_foreach visits only nonzero dense entries; pad the rest of the
 * block's reserved triplets with explicit zeros so that the count stays
 * fixed. */
static void put_matrix(trip *t, const fb_mat *a, size_t roff, size_t coff, double scale,
                       size_t reserved)
{
  size_t start = t->k;
  mat_visit m = {t, roff, coff, scale};
  fb_mat_foreach(a, visit_put, &m);
  while (t->k < start + reserved)
    put(t, roff, coff, 0.0, 0.0);
}

static int gain_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                    double *v1)
{
  (void)w;
  trip t = {rows, cols, v0, v1, 0};
  put_identity(&t, b->ooff, b->odim);
  put_matrix(&t, b->mat, b->ooff, b->ioff[0], -1.0, fb_mat_nnz(b->mat));
  return 0;
}
const bd_block_ops fb_bd_gain_ops = {"gain", gain_eval, gain_jvp, gain_nnz, gain_jac, 1};

/* ---- Solve: A out = in, by the sparse LU of A. */
static int solve_apply(bd_block *b, double *v)
{
  memcpy(v + b->ooff, v + b->ioff[0], b->odim * sizeof *v);
  return fb_lu_solve(b->lu, v + b->ooff, 1, NULL) ? -1 : 0;
}
static int solve_eval(bd_block *b, double t, double *w)
{
  (void)t;
  return solve_apply(b, w);
}
static int solve_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  return solve_apply(b, dw);
}
static int solve_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                     double *v1)
{
  (void)w;
  trip t = {rows, cols, v0, v1, 0};
  put_matrix(&t, b->mat, b->ooff, b->ooff, 1.0, fb_mat_nnz(b->mat));
  for (size_t i = 0; i < b->odim; ++i)
    put(&t, b->ooff + i, b->ioff[0] + i, -1.0, 0.0);
  return 0;
}
const bd_block_ops fb_bd_solve_ops = {"solve", solve_eval, solve_jvp, gain_nnz, solve_jac, 1};

/* ---- Signed sum: out = sum_k c_k in_k (zero inputs: out = 0). */
static int sum_apply(bd_block *b, double *v)
{
  double *y = v + b->ooff;
  memset(y, 0, b->odim * sizeof *y);
  for (size_t k = 0; k < b->nin; ++k) {
    const double *u = v + b->ioff[k];
    for (size_t i = 0; i < b->odim; ++i)
      y[i] += b->coef[k] * u[i];
  }
  return 0;
}
static int sum_eval(bd_block *b, double t, double *w)
{
  (void)t;
  return sum_apply(b, w);
}
static int sum_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  return sum_apply(b, dw);
}
static size_t sum_nnz(const bd_block *b)
{
  return b->odim * (1 + b->nin);
}
static int sum_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                   double *v1)
{
  (void)w;
  trip t = {rows, cols, v0, v1, 0};
  put_identity(&t, b->ooff, b->odim);
  for (size_t k = 0; k < b->nin; ++k)
    for (size_t i = 0; i < b->odim; ++i)
      put(&t, b->ooff + i, b->ioff[k] + i, -b->coef[k], 0.0);
  return 0;
}
const bd_block_ops fb_bd_sum_ops = {"sum", sum_eval, sum_jvp, sum_nnz, sum_jac, 1};

/* ---- Mux: out = [c_1 in_1; ...; c_k in_k]. */
static int mux_apply(bd_block *b, double *v)
{
  size_t pos = b->ooff;
  for (size_t k = 0; k < b->nin; ++k)
    for (size_t i = 0; i < b->idim[k]; ++i)
      v[pos++] = b->coef[k] * v[b->ioff[k] + i];
  return 0;
}
static int mux_eval(bd_block *b, double t, double *w)
{
  (void)t;
  return mux_apply(b, w);
}
static int mux_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  return mux_apply(b, dw);
}
static size_t two_per_out(const bd_block *b)
{
  return 2 * b->odim;
}
static int mux_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                   double *v1)
{
  (void)w;
  trip t = {rows, cols, v0, v1, 0};
  size_t pos = b->ooff;
  for (size_t k = 0; k < b->nin; ++k)
    for (size_t i = 0; i < b->idim[k]; ++i, ++pos) {
      put(&t, pos, pos, 1.0, 0.0);
      put(&t, pos, b->ioff[k] + i, -b->coef[k], 0.0);
    }
  return 0;
}
const bd_block_ops fb_bd_mux_ops = {"mux", mux_eval, mux_jvp, two_per_out, mux_jac, 1};

/* ---- Select (demux): out = c in[offset .. offset + odim). */
static int select_apply(bd_block *b, double *v)
{
  for (size_t i = 0; i < b->odim; ++i)
    v[b->ooff + i] = b->coef[0] * v[b->ioff[0] + b->offset + i];
  return 0;
}
static int select_eval(bd_block *b, double t, double *w)
{
  (void)t;
  return select_apply(b, w);
}
static int select_jvp(bd_block *b, const double *w, double *dw)
{
  (void)w;
  return select_apply(b, dw);
}
static int select_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                      double *v1)
{
  (void)w;
  trip t = {rows, cols, v0, v1, 0};
  for (size_t i = 0; i < b->odim; ++i) {
    put(&t, b->ooff + i, b->ooff + i, 1.0, 0.0);
    put(&t, b->ooff + i, b->ioff[0] + b->offset + i, -b->coef[0], 0.0);
  }
  return 0;
}
const bd_block_ops fb_bd_select_ops = {"demux",     select_eval, select_jvp,
                                       two_per_out, select_jac,  1};

/* ---- Element-wise product: out = in_1 .* in_2 (power e.f). */
static int product_eval(bd_block *b, double t, double *w)
{
  (void)t;
  for (size_t i = 0; i < b->odim; ++i)
    w[b->ooff + i] = w[b->ioff[0] + i] * w[b->ioff[1] + i];
  return 0;
}
static int product_jvp(bd_block *b, const double *w, double *dw)
{
  for (size_t i = 0; i < b->odim; ++i)
    dw[b->ooff + i] =
        dw[b->ioff[0] + i] * w[b->ioff[1] + i] + w[b->ioff[0] + i] * dw[b->ioff[1] + i];
  return 0;
}
static size_t product_nnz(const bd_block *b)
{
  return 3 * b->odim;
}
static int product_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                       double *v1)
{
  trip t = {rows, cols, v0, v1, 0};
  for (size_t i = 0; i < b->odim; ++i) {
    put(&t, b->ooff + i, b->ooff + i, 1.0, 0.0);
    put(&t, b->ooff + i, b->ioff[0] + i, -w[b->ioff[1] + i], 0.0);
    put(&t, b->ooff + i, b->ioff[1] + i, -w[b->ioff[0] + i], 0.0);
  }
  return 0;
}
const bd_block_ops fb_bd_product_ops = {"product",   product_eval, product_jvp,
                                        product_nnz, product_jac,  0};

/* ---- Nonlinear law: out = phi(in_0, in_1, ...): input 0 is the law's own
 * input, the others its modulating values (fb_bg_modulate). A law sees
 * them as one vector xu (gathered into xu unless there is one input);
 * work holds its n x (n + m) Jacobian. */
static size_t law_width(const bd_block *b)
{
  size_t w = 0;
  for (size_t k = 0; k < b->nin; ++k)
    w += b->idim[k];
  return w;
}

void fb_bd_law_input(bd_block *b, const double *w, fb_law_in *in)
{
  in->n = b->odim;
  in->m = law_width(b) - b->odim;
  in->mode = b->mode;
  if (b->nin == 1) {
    in->x = w + b->ioff[0];
    return;
  }
  for (size_t k = 0, c = 0; k < b->nin; c += b->idim[k++])
    memcpy(b->xu + c, w + b->ioff[k], b->idim[k] * sizeof *b->xu);
  in->x = b->xu;
}

static int law_eval(bd_block *b, double t, double *w)
{
  (void)t;
  fb_law_in in;
  fb_bd_law_input(b, w, &in);
  return b->law->eval(b->law_ctx, &in, w + b->ooff);
}

/* The law's Jacobian into b->work; columns a law leaves alone are 0. */
static int law_jacobian(bd_block *b, const double *w)
{
  fb_law_in in;
  fb_bd_law_input(b, w, &in);
  memset(b->work, 0, in.n * (in.n + in.m) * sizeof *b->work);
  return b->law->jacobian(b->law_ctx, &in, b->work);
}

static int law_jvp(bd_block *b, const double *w, double *dw)
{
  const size_t n = b->odim;
  int rc = law_jacobian(b, w);
  if (rc)
    return rc;
  for (size_t i = 0; i < n; ++i)
    dw[b->ooff + i] = 0.0;
  for (size_t k = 0, c = 0; k < b->nin; ++k)
    for (size_t j = 0; j < b->idim[k]; ++j, ++c)
      for (size_t i = 0; i < n; ++i)
        dw[b->ooff + i] += b->work[c * n + i] * dw[b->ioff[k] + j];
  return 0;
}
static size_t law_nnz(const bd_block *b)
{
  return b->odim * (1 + law_width(b));
}
static int law_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                   double *v1)
{
  const size_t n = b->odim;
  int rc = law_jacobian(b, w);
  if (rc) /* keep the pattern complete even when the values failed */
    memset(b->work, 0, n * law_width(b) * sizeof *b->work);
  trip t = {rows, cols, v0, v1, 0};
  put_identity(&t, b->ooff, n);
  for (size_t k = 0, c = 0; k < b->nin; ++k)
    for (size_t j = 0; j < b->idim[k]; ++j, ++c)
      for (size_t i = 0; i < n; ++i)
        put(&t, b->ooff + i, b->ioff[k] + j, -b->work[c * n + i], 0.0);
  return rc;
}
const bd_block_ops fb_bd_law_ops = {"law", law_eval, law_jvp, law_nnz, law_jac, 0};

/* ---- Stored energy of a storage field with state x (input 0) and
 * co-variable y (input 1): linear law 1/2 x.y, or the law's energy
 * function, whose gradient is y (Karnopp et al., section 7.2). */
static int energy_eval(bd_block *b, double t, double *w)
{
  (void)t;
  size_t n = b->idim[0];
  const double *x = w + b->ioff[0], *y = w + b->ioff[1];
  if (b->law) {
    w[b->ooff] = b->law->energy(b->law_ctx, n, x);
    return 0;
  }
  double s = 0.0;
  for (size_t i = 0; i < n; ++i)
    s += x[i] * y[i];
  w[b->ooff] = 0.5 * s;
  return 0;
}
static int energy_jvp(bd_block *b, const double *w, double *dw)
{
  size_t n = b->idim[0];
  const double *x = w + b->ioff[0], *y = w + b->ioff[1];
  const double *dx = dw + b->ioff[0], *dy = dw + b->ioff[1];
  double s = 0.0;
  for (size_t i = 0; i < n; ++i)
    s += b->law ? y[i] * dx[i] : 0.5 * (y[i] * dx[i] + x[i] * dy[i]);
  dw[b->ooff] = s;
  return 0;
}
static size_t energy_nnz(const bd_block *b)
{
  return 1 + 2 * b->idim[0];
}
static int energy_jac(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0,
                      double *v1)
{
  size_t n = b->idim[0];
  const double *x = w + b->ioff[0], *y = w + b->ioff[1];
  trip t = {rows, cols, v0, v1, 0};
  put(&t, b->ooff, b->ooff, 1.0, 0.0);
  for (size_t i = 0; i < n; ++i) {
    put(&t, b->ooff, b->ioff[0] + i, b->law ? -y[i] : -0.5 * y[i], 0.0);
    put(&t, b->ooff, b->ioff[1] + i, b->law ? 0.0 : -0.5 * x[i], 0.0);
  }
  return 0;
}
const bd_block_ops fb_bd_energy_ops = {"energy",   energy_eval, energy_jvp,
                                       energy_nnz, energy_jac,  0};
