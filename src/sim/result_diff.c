/* SPDX-License-Identifier: BSD-3-Clause */
/* The difference of two results sampled on one grid (see fb_result_diff
 * in flexbond/sim.h): what `flexbond run` plots under its overlaid
 * System 1 and System 2 curves. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/sim.h"

#include "sim/sim_internal.h"

/* FB_EINVAL naming the first difference in shape, names, units or times. */
static int check_same_grid(const fb_result *b, const fb_result *a, fb_err *err)
{
  if (a->ncols != b->ncols)
    return fb_err_set(err, FB_EINVAL, "result difference: %zu columns minus %zu columns",
                      b->ncols, a->ncols);
  if (a->ncols == 0)
    return fb_err_set(err, FB_EINVAL, "result difference: no columns");
  for (size_t j = 0; j < a->ncols; ++j) {
    if (strcmp(a->names[j], b->names[j]) != 0)
      return fb_err_set(err, FB_EINVAL, "result difference: column %zu is '%s' minus '%s'", j,
                        b->names[j], a->names[j]);
    if (strcmp(a->units[j], b->units[j]) != 0)
      return fb_err_set(err, FB_EINVAL, "result difference: column '%s' is in %s minus %s",
                        a->names[j], b->units[j], a->units[j]);
  }
  if (a->nsamples != b->nsamples)
    return fb_err_set(err, FB_EINVAL, "result difference: %zu samples minus %zu samples",
                      b->nsamples, a->nsamples);
  for (size_t k = 0; k < a->nsamples; ++k) {
    const double ta = a->data[k * a->ncols], tb = b->data[k * b->ncols];
    /* One sample grid gives the same doubles; the slack only forgives
     * rounding of a grid computed another way. */
    if (!(fabs(ta - tb) <= 1e-9 * fmax(1.0, fabs(ta))))
      return fb_err_set(err, FB_EINVAL,
                        "result difference: sample %zu is at t = %g s minus %g s", k, tb, ta);
  }
  return FB_OK;
}

/* A result shaped like a, with a's names and units, data uninitialised. */
static int alloc_like(const fb_result *a, fb_result **out, fb_err *err)
{
  if (a->nsamples > SIZE_MAX / sizeof(double) / a->ncols)
    return fb_err_set(err, FB_ENOMEM, "result of %zu samples x %zu columns is too large",
                      a->nsamples, a->ncols);
  fb_result *r = calloc(1, sizeof *r);
  if (!r)
    return fb_err_set(err, FB_ENOMEM, "out of memory allocating the result difference");
  *out = r;
  r->ncols = a->ncols;
  r->names = calloc(a->ncols, sizeof *r->names);
  r->units = calloc(a->ncols, sizeof *r->units);
  r->data = malloc((a->nsamples ? a->nsamples : 1) * a->ncols * sizeof *r->data);
  int ok = r->names && r->units && r->data;
  for (size_t j = 0; ok && j < a->ncols; ++j) {
    r->names[j] = strdup(a->names[j]);
    r->units[j] = strdup(a->units[j]);
    ok = r->names[j] && r->units[j];
  }
  if (ok) {
    r->nsamples = a->nsamples;
    return FB_OK;
  }
  fb_result_free(out);
  return fb_err_set(err, FB_ENOMEM, "out of memory allocating the result difference");
}

int fb_result_diff(const fb_result *b, const fb_result *a, fb_result **out, fb_err *err)
{
  *out = NULL;
  int rc = check_same_grid(b, a, err);
  if (rc == FB_OK)
    rc = alloc_like(a, out, err);
  if (rc != FB_OK)
    return rc;
  const size_t n = a->nsamples * a->ncols;
  for (size_t i = 0; i < n; ++i)
    (*out)->data[i] = i % a->ncols == 0 ? a->data[i] : b->data[i] - a->data[i];
  return FB_OK;
}

int fb_result_rel_diff(const fb_result *a, const fb_result *b, double t0, double *rel,
                       fb_err *err)
{
  int rc = check_same_grid(b, a, err);
  for (size_t j = 1; !rc && j < a->ncols; ++j) {
    double lo = INFINITY, hi = -INFINITY, diff = 0.0;
    for (size_t k = 0; k < a->nsamples; ++k) {
      const double *ra = a->data + k * a->ncols, *rb = b->data + k * b->ncols;
      if (ra[0] < t0)
        continue;
      lo = fmin(lo, ra[j]);
      hi = fmax(hi, ra[j]);
      diff = fmax(diff, fabs(ra[j] - rb[j]));
    }
    rel[j - 1] = hi > lo ? diff / (hi - lo) : 0.0;
  }
  return rc;
}
