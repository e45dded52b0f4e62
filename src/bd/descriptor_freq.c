/* SPDX-License-Identifier: BSD-3-Clause */
/* Frequency response of a descriptor system E x' = A x + B u, y = C x
 * (+ D u): for u = U e^{j omega t}, the steady state is x = X e^{j omega t}
 * with (j omega E - A) X = B U, so Y = C X + D U, the transfer function
 * H(j omega) = C (j omega E - A)^-1 B + D applied to U (see flexbond/bd.h).
 * One sparse complex factorisation per frequency (fb_pencil). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"

/* A sparse matrix's entries, as lists. */
typedef struct entries {
  size_t *row, *col;
  double *val;
  size_t n;
} entries;

static void entries_free(entries *t)
{
  free(t->row);
  free(t->col);
  free(t->val);
}

static int entries_of(const fb_mat *m, entries *t, fb_err *err)
{
  const size_t cap = fb_mat_nnz(m) + 1;
  t->n = 0;
  t->row = malloc(cap * sizeof *t->row);
  t->col = malloc(cap * sizeof *t->col);
  t->val = malloc(cap * sizeof *t->val);
  if (!t->row || !t->col || !t->val) {
    entries_free(t);
    return fb_err_set(err, FB_ENOMEM, "out of memory for a frequency response");
  }
  t->n = fb_mat_triplets(m, t->row, t->col, t->val);
  return FB_OK;
}

/* out (m x ncases complex) = M (m x k) in (k x ncases complex), M's
 * entries in t. */
static void apply(const entries *t, const double *in, size_t k, double *out, size_t m,
                  size_t ncases)
{
  memset(out, 0, 2 * m * ncases * sizeof *out);
  for (size_t c = 0; c < ncases; ++c)
    for (size_t i = 0; i < t->n; ++i) {
      const double *x = in + 2 * (c * k + t->col[i]);
      double *y = out + 2 * (c * m + t->row[i]);
      y[0] += t->val[i] * x[0];
      y[1] += t->val[i] * x[1];
    }
}

typedef struct response {
  const fb_descriptor *ds;
  fb_pencil *pencil;
  entries b, c, d;
  double *u, *x, *dy; /* ninputs, n and nrows_c complex per case */
} response;

static void response_free(response *r)
{
  fb_pencil_free(&r->pencil);
  entries_free(&r->b);
  entries_free(&r->c);
  entries_free(&r->d);
  free(r->u);
  free(r->x);
  free(r->dy);
}

static int response_new(const fb_descriptor *ds, size_t ncases, response *r, fb_err *err)
{
  memset(r, 0, sizeof *r);
  r->ds = ds;
  if (ncases == 0 || ds->n > SIZE_MAX / (2 * sizeof(double)) / ncases)
    return fb_err_set(err, FB_EINVAL, "frequency response: %zu input cases for %zu variables",
                      ncases, ds->n);
  int rc = fb_pencil_new(ds->E, ds->A, &r->pencil, err);
  if (!rc)
    rc = entries_of(ds->B, &r->b, err);
  if (!rc)
    rc = entries_of(ds->C, &r->c, err);
  if (!rc)
    rc = entries_of(ds->D, &r->d, err);
  if (!rc) {
    r->u = malloc((2 * ds->ninputs * ncases + 1) * sizeof *r->u);
    r->x = malloc((2 * ds->n * ncases + 1) * sizeof *r->x);
    r->dy = malloc((2 * ds->nrows_c * ncases + 1) * sizeof *r->dy);
    if (!r->u || !r->x || !r->dy)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory for a frequency response");
  }
  return rc;
}

/* FB_ESOLVER unless all n values of one frequency's response are finite:
 * an overflow in the complex solve (a pencil near singular at freq_hz)
 * must not reach a caller as a result. */
static int check_finite(const double *y, size_t n, double freq_hz, fb_err *err)
{
  for (size_t i = 0; i < n; ++i)
    if (!isfinite(y[i]))
      return fb_err_set(err, FB_ESOLVER,
                        "frequency response: not finite at %g Hz (j omega E - A is singular "
                        "there to double precision)",
                        freq_hz);
  return FB_OK;
}

int fb_descriptor_freq_response(const fb_descriptor *ds, const double *freq_hz, size_t nfreq,
                                size_t ncases, fb_freq_input_fn input, void *ctx, double *h,
                                fb_err *err)
{
  for (size_t k = 0; k < nfreq; ++k)
    if (!(freq_hz[k] >= 0.0 && freq_hz[k] <= FB_FREQ_MAX_HZ))
      return fb_err_set(err, FB_EINVAL,
                        "frequency response: the frequency at index %zu is %g Hz, not a number "
                        "from 0 to %g Hz",
                        k, freq_hz[k], FB_FREQ_MAX_HZ);
  response r;
  int rc = response_new(ds, ncases, &r, err);
  const size_t ny = ds->nrows_c;
  for (size_t k = 0; !rc && k < nfreq; ++k) {
    const double omega = 2.0 * 3.14159265358979323846 * freq_hz[k];
    input(ctx, omega, r.u);
    rc = fb_pencil_factor(r.pencil, omega, err);
    if (!rc) {
      apply(&r.b, r.u, ds->ninputs, r.x, ds->n, ncases);
      rc = fb_pencil_solve(r.pencil, r.x, ncases, err);
    }
    if (rc)
      break;
    double *y = h + 2 * k * ncases * ny;
    apply(&r.c, r.x, ds->n, y, ny, ncases);
    apply(&r.d, r.u, ds->ninputs, r.dy, ny, ncases);
    for (size_t i = 0; i < 2 * ny * ncases; ++i)
      y[i] += r.dy[i];
    rc = check_finite(y, 2 * ny * ncases, freq_hz[k], err);
  }
  response_free(&r);
  return rc;
}
