/* SPDX-License-Identifier: BSD-3-Clause */
/* The envelope gallery's geometric overlap: the tire's free circle
 * (radius r0) sinks into the road until the area it overlaps equals the
 * area it overlaps on a flat road at the reference deflection d; the
 * effective height is then its centre's height less r0 - d. On a flat
 * road that is the road's height; over a step it is the height of the
 * flat road the same circle would overlap as much. The overlap area is
 * what Project Chrono's ENVELOPE tire-terrain collision measures under a
 * disc (chrono::vehicle::ChTire, "DiscTerrainCollisionEnvelope"); fixing
 * it at the reference deflection, to make a road of it, is this model's
 * (docs/tire-envelope.md). As d tends to 0 the circle just touches the
 * road: the rigid ring of the wheel's centre path. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include "flexbond/envelope.h"

static const fb_param overlap_params[] = {
    {.name = "deflection",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_envelope_overlap_params, deflection),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_OPTIONAL,
     .doc = "the deflection whose overlap with a flat road the circle keeps (default: the "
            "static deflection under an equal share of the weight)",
     .plausible_lo = 1e-4,
     .plausible_hi = 0.3,
     .plausible_why = "a loaded tire deflects 0.1 mm to 0.3 m"},
};

static void overlap_init(void *params)
{
  ((fb_envelope_overlap_params *)params)->deflection = NAN;
}

static double overlap_deflection(const fb_envelope_overlap_params *p,
                                 const fb_envelope_context *ctx)
{
  return isnan(p->deflection) ? ctx->static_deflection : p->deflection;
}

static int overlap_check(const void *params, const fb_envelope_context *ctx, fb_err *err)
{
  if (!(ctx->radius > 0.0))
    return fb_err_set(err, FB_EINVAL, "the overlap needs the tire's free radius (got %g m)",
                      ctx->radius);
  const double d = overlap_deflection(params, ctx);
  if (d > 0.0 && d < ctx->radius)
    return FB_OK;
  fb_err_set(err, FB_EINVAL, "must be in (0, the tire's radius %g m) (got %g m)", ctx->radius,
             d);
  return fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "deflection"), FB_EINVAL;
}

static double overlap_reach(const void *params, const fb_envelope_context *ctx)
{
  (void)params;
  return ctx->radius;
}

/* The centre height zc where sum_k max(0, v_k - zc) = target (> 0): the
 * sum is convex, piecewise linear and decreasing in zc, so Newton's
 * method from a point left of the root (max v - target, where the sum is
 * at least target) stays left of it and ends when the set of
 * overlapping columns stops changing, at the root itself. */
static double overlap_centre(const double *v, size_t nv, double target)
{
  double top = -INFINITY;
  for (size_t k = 0; k < nv; ++k)
    top = v[k] > top ? v[k] : top;
  double zc = top - target;
  for (int iter = 0; iter < 64; ++iter) {
    double sum = 0.0;
    size_t count = 0;
    for (size_t k = 0; k < nv; ++k)
      if (v[k] > zc) {
        sum += v[k];
        ++count;
      }
    const double next = (sum - target) / (double)count;
    if (next <= zc) /* no move: the root (rounding may step back by an ulp) */
      return zc;
    zc = next;
  }
  return zc;
}

/* The overlap of the circle at centre height zc with the road, by
 * columns of width ds at x_k = k ds (|x_k| < r0, the midpoint rule): per
 * ds, sum_k max(0, z_{i+k} - (zc - sqrt(r0^2 - x_k^2))) = sum_k
 * max(0, v_k - zc) with v_k = z_{i+k} + sqrt(r0^2 - x_k^2). The target
 * is the same sum on a flat road at zc = r0 - d, so a flat road gives
 * its own height up to rounding. Roads above the circle's centre are
 * out of its reach (the columns are not capped by the circle's upper
 * half). */
static int overlap_filter(const void *params, const fb_envelope_context *ctx, const double *z,
                          size_t n, double ds, double *w, double *beta, fb_err *err)
{
  const double r = ctx->radius, d = overlap_deflection(params, ctx);
  const size_t half = (size_t)ceil(r / ds) - 1; /* |k ds| < r0 */
  const size_t nv = 2 * half + 1;
  double *lower = malloc(2 * nv * sizeof *lower);
  if (!lower)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a circle of %zu columns", nv);
  double *v = lower + nv, target = 0.0;
  for (size_t k = 0; k < nv; ++k) {
    const double x = ((double)k - (double)half) * ds;
    lower[k] = sqrt(r * r - x * x);
    target += fmax(0.0, lower[k] - (r - d));
  }
  for (size_t i = half; i + half < n; ++i) {
    for (size_t k = 0; k < nv; ++k)
      v[k] = z[i + k - half] + lower[k];
    w[i] = overlap_centre(v, nv, target) - (r - d);
  }
  /* The slope by central differences of the heights. */
  for (size_t i = half + 1; beta && i + half + 1 < n; ++i)
    beta[i] = (w[i + 1] - w[i - 1]) / (2.0 * ds);
  free(lower);
  return FB_OK;
}

static const fb_envelope_model_ops overlap_ops = {.init = overlap_init,
                                                  .check = overlap_check,
                                                  .reach = overlap_reach,
                                                  .filter = overlap_filter};

const fb_envelope_model fb_envelope_model_overlap = {
    .name = "overlap",
    .doc = "geometric overlap: the free circle sunk into the road as far as it sinks into a "
           "flat road at the reference deflection",
    .needs_radius = 1,
    .param = overlap_params,
    .nparams = sizeof overlap_params / sizeof overlap_params[0],
    .params_size = sizeof(fb_envelope_overlap_params),
    .ops = &overlap_ops,
};
