/* SPDX-License-Identifier: BSD-3-Clause */
/* The envelope gallery's tandem elliptical cams (A. J. C. Schmeitz, "A
 * semi-empirical three-dimensional model of the pneumatic tyre rolling
 * over arbitrarily uneven road surfaces", PhD thesis, TU Delft, 2004,
 * ch. 4; H. B. Pacejka, "Tyre and Vehicle Dynamics", 3rd ed., 2012,
 * ch. 10): two cams, front and rear, l_s apart, each the lower half
 * of the super-ellipse |x / a_e|^c_e + |z / b_e|^c_e = 1 resting on the
 * road at its highest touching position; the effective height is the
 * mean of the two cams' lowest points, the effective slope their
 * difference over l_s. Defaults: the MF-Swift property file's
 * [CONTACT_PATCH] values ELLIPS_LENGTH = ELLIPS_HEIGHT = 1 (of the free
 * radius), ELLIPS_ORDER = 1.8, ELLIPS_SHIFT = 0.8 (of the contact
 * length) (docs/tire-envelope.md). */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>

#include "flexbond/envelope.h"

static const fb_param cams_params[] = {
    {.name = "length",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_envelope_cams_params, length),
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN | FB_RANGE_HI,
     .hi = 2.0,
     .need = FB_PARAM_DEFAULT,
     .def = 1.0,
     .doc = "a cam's half length a_e over the tire's free radius (MF-Swift's ELLIPS_LENGTH)",
     .why = "a cam longer than the tire's diameter would read road the tire never meets"},
    {.name = "height",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_envelope_cams_params, height),
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN | FB_RANGE_HI,
     .hi = 2.0,
     .need = FB_PARAM_DEFAULT,
     .def = 1.0,
     .doc = "a cam's half height b_e over the tire's free radius (MF-Swift's ELLIPS_HEIGHT)",
     .why = "a step higher than b_e lifts a cam at its tip: the effective road jumps"},
    {.name = "order",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_envelope_cams_params, order),
     .range = FB_RANGE_LO | FB_RANGE_HI,
     .lo = 1.0,
     .hi = 10.0,
     .need = FB_PARAM_DEFAULT,
     .def = 1.8,
     .doc = "the cams' super-ellipse exponent c_e (MF-Swift's ELLIPS_ORDER; 2: an ellipse)",
     .why = "below 1 a cam is not convex; above 10 it is a rectangle to within 7 %"},
    {.name = "shift",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_envelope_cams_params, shift),
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN | FB_RANGE_HI,
     .hi = 2.0,
     .need = FB_PARAM_DEFAULT,
     .def = 0.8,
     .doc = "the cams' spacing l_s over the contact length (MF-Swift's ELLIPS_SHIFT)",
     .why = "the cams stand within the contact patch, or near it"},
    {.name = "contact_length",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_envelope_cams_params, contact_length),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_OPTIONAL,
     .doc = "the tire's contact length at rest (default: the chord of the free circle at the "
            "static deflection, 2 sqrt(2 r0 d - d^2))",
     .plausible_lo = 0.02,
     .plausible_hi = 1.0,
     .plausible_why = "a loaded tire's contact patch is 2 cm to 1 m long"},
};

static void cams_init(void *params)
{
  ((fb_envelope_cams_params *)params)->contact_length = NAN;
}

/* The contact length: given, else the free circle's chord at the static
 * deflection (NaN when neither is known). */
static double cams_contact(const fb_envelope_cams_params *p, const fb_envelope_context *ctx)
{
  if (!isnan(p->contact_length))
    return p->contact_length;
  return ctx->static_deflection > 0.0 && ctx->static_deflection < ctx->radius
             ? fb_envelope_chord(ctx->radius, ctx->static_deflection)
             : NAN;
}

static int cams_check(const void *params, const fb_envelope_context *ctx, fb_err *err)
{
  const fb_envelope_cams_params *p = params;
  if (!(ctx->radius > 0.0))
    return fb_err_set(err, FB_EINVAL, "tandem cams need the tire's free radius (got %g m)",
                      ctx->radius);
  const double lc = cams_contact(p, ctx);
  if (isnan(lc)) {
    fb_err_set(err, FB_EINVAL,
               "the contact length is needed: give it, or a static deflection in (0, the "
               "radius) follows from the tire's stiffness and load (got %g m)",
               ctx->static_deflection);
    return fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "contact_length"), FB_EINVAL;
  }
  if (lc >= 2.0 * ctx->radius) {
    fb_err_set(err, FB_EINVAL, "must be < the tire's diameter %g m (got %g m)",
               2.0 * ctx->radius, lc);
    return fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "contact_length"), FB_EINVAL;
  }
  return FB_OK;
}

static double cams_base(const fb_envelope_cams_params *p, const fb_envelope_context *ctx)
{
  const double lc = cams_contact(p, ctx);
  return isnan(lc) ? 0.0 : p->shift * lc;
}

static double cams_reach(const void *params, const fb_envelope_context *ctx)
{
  const fb_envelope_cams_params *p = params;
  return p->length * ctx->radius + 0.5 * cams_base(p, ctx);
}

/* One cam at every sample whose window fits: its lowest point's height
 * when it rests on the road, e_i = max_k (z_{i+k} + g_k), with g_k =
 * b_e ((1 - |x_k / a_e|^c_e)^(1 / c_e) - 1) <= 0 the cam's lower edge
 * above its lowest point at x_k = k ds, |x_k| < a_e. The sampled maximum
 * is within ds times the steepest slope of the cam's active part of the
 * exact one (docs/tire-envelope.md, "Error"). */
static void cams_one(const double *z, size_t n, size_t half, const double *g, double *e)
{
  for (size_t i = half; i + half < n; ++i) {
    double top = -INFINITY;
    for (size_t k = 0; k <= 2 * half; ++k) {
      const double v = z[i + k - half] + g[k];
      top = v > top ? v : top;
    }
    e[i] = top;
  }
}

static int cams_filter(const void *params, const fb_envelope_context *ctx, const double *z,
                       size_t n, double ds, double *w, double *beta, fb_err *err)
{
  const fb_envelope_cams_params *p = params;
  const double a = p->length * ctx->radius, b = p->height * ctx->radius, c = p->order;
  const size_t half = (size_t)ceil(a / ds) - 1; /* |k ds| < a_e */
  /* The cams' half spacing in samples: l_s rounded to an even number of
   * samples (at least 2), within ds of the declared l_s. */
  const long rounded = lround(0.5 * cams_base(p, ctx) / ds);
  const size_t lag = rounded > 1 ? (size_t)rounded : 1;
  double *g = malloc((2 * half + 1 + n) * sizeof *g);
  if (!g)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a cam of %zu samples", 2 * half + 1);
  double *e = g + 2 * half + 1;
  for (size_t k = 0; k <= 2 * half; ++k) {
    const double u = fabs(((double)k - (double)half) * ds / a);
    g[k] = b * (pow(1.0 - pow(u, c), 1.0 / c) - 1.0);
  }
  cams_one(z, n, half, g, e);
  const double base = 2.0 * (double)lag * ds;
  for (size_t i = half + lag; i + half + lag < n; ++i) {
    const double front = e[i + lag], rear = e[i - lag];
    w[i] = 0.5 * (front + rear);
    if (beta)
      beta[i] = (front - rear) / base;
  }
  free(g);
  return FB_OK;
}

static const fb_envelope_model_ops cams_ops = {
    .init = cams_init, .check = cams_check, .reach = cams_reach, .filter = cams_filter};

const fb_envelope_model fb_envelope_model_cams = {
    .name = "cams",
    .doc = "Schmeitz's tandem elliptical cams: the mean height of two super-elliptical cams "
           "resting on the road a contact length apart",
    .needs_radius = 1,
    .param = cams_params,
    .nparams = sizeof cams_params / sizeof cams_params[0],
    .params_size = sizeof(fb_envelope_cams_params),
    .ops = &cams_ops,
};
