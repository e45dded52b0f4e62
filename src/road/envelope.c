/* SPDX-License-Identifier: BSD-3-Clause */
/* The envelope gallery (flexbond/envelope.h): the soundness of an
 * envelope model, its parameter blocks, the set of models a description
 * may name, and the effective road a model makes of a road. */
#include "flexbond/envelope.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "core/registry.h"
#include "core/util.h"
#include "road/road_internal.h"

/* The built-in models, one line each; the first is a corner's default. */
static const fb_envelope_model *const gallery_builtin[] = {
    &fb_envelope_model_point,
    &fb_envelope_model_cams,
    &fb_envelope_model_overlap,
};

struct fb_envelope_gallery {
  fb_registry reg; /* the models */
};

/* The registry reads an entry's name as its first member. */
_Static_assert(offsetof(fb_envelope_model, name) == 0,
               "an envelope model's name is its first member");

int fb_envelope_model_check(const fb_envelope_model *m, fb_err *err)
{
  const fb_registry_entry none = {.kind = "envelope model"};
  if (!m)
    return fb_registry_entry_check(&none, err);
  const fb_registry_entry e = {
      "envelope model",
      m->name,
      m->doc,
      NULL,
      0,
      m->param,
      m->nparams,
      m->params_size,
      FB_ENVELOPE_PARAMS_MAX,
      "FB_ENVELOPE_PARAMS_MAX",
      1,
      m->ops && m->ops->reach && m->ops->filter
          ? NULL
          : "a model says how far it reads the road and filters it (reach, filter)"};
  return fb_registry_entry_check(&e, err);
}

void fb_envelope_params_init(const fb_envelope_model *m, fb_envelope_params *p)
{
  memset(p, 0, sizeof *p);
  fb_params_defaults(m->param, m->nparams, p->bytes);
  if (m->ops->init)
    m->ops->init(p->bytes);
}

double fb_envelope_chord(double r, double d)
{
  const double q = 2.0 * r * d - d * d;
  return q > 0.0 ? 2.0 * sqrt(q) : 0.0;
}

/* The grid's resolution against the footprint: 256 samples keep the
 * sampled maximum and overlap within footprint / 256 times the cam's or
 * circle's slope of their exact values (docs/tire-envelope.md, "Error");
 * 4096 bounds the work on a road of very short wavelength (a step made
 * of knots 1e-6 m apart). */
enum { SPACING_PER_FOOTPRINT = 256, SPACING_FINEST = 4096, SPACING_PER_WAVELENGTH = 8 };
/* The profile's knots: every KNOT_GAP samples (a quarter of the
 * footprint), and more wherever the monotone cubic through them misses
 * a sample by more than KNOT_TOL of the effective road's height range
 * (docs/tire-envelope.md, "Error"). */
enum { KNOT_GAP = 64 };
static const double KNOT_TOL = 2e-3, KNOT_TOL_MIN = 1e-7; /* -, m */

/* The worst sample of w in (knot a, knot b) that the monotone cubic
 * through the knots (s, z, slopes d; nk of them) misses by more than tol,
 * 0 when none. */
static size_t worst_miss(const double *w, double s_min, double ds, const double *s,
                         const double *z, const double *d, size_t nk, size_t a, size_t b,
                         double tol)
{
  size_t worst = 0;
  double miss = tol;
  for (size_t j = a + 1; j < b; ++j) {
    const double e = fabs(road_pchip_height(nk, s, z, d, s_min + (double)j * ds) - w[j]);
    if (e > miss) {
      miss = e;
      worst = j;
    }
  }
  return worst;
}

/* The knots of the effective road's profile among the samples w and v
 * (the two tracks, n >= 2 each, at s_min + j ds) into knot[] (room for
 * n), ascending from 0 to n - 1; returns how many. First every
 * KNOT_GAP samples, then a knot more at the worst sample of each
 * interval where the monotone cubic through them misses by more than
 * the tolerance, until none does. Every knot is a jump of the profile's
 * curvature, which the integrator steps to (docs/tire-envelope.md,
 * "Cost"), so there are no more than the tolerance needs. more: room for
 * n; work: room for 5 n. */
static size_t envelope_knots(const double *w, const double *v, size_t n, double s_min,
                             double ds, size_t *knot, size_t *more, double *work)
{
  double lo = INFINITY, hi = -INFINITY;
  for (size_t j = 0; j < n; ++j) {
    lo = fmin(lo, fmin(w[j], v[j]));
    hi = fmax(hi, fmax(w[j], v[j]));
  }
  const double tol = fmax(KNOT_TOL * (hi - lo), KNOT_TOL_MIN);
  size_t count = 0;
  for (size_t j = 0; j < n - 1; j += KNOT_GAP)
    knot[count++] = j;
  knot[count++] = n - 1;
  double *s = work, *zw = s + n, *zv = zw + n, *dw = zv + n, *dv = dw + n;
  for (int added = 1; added;) {
    for (size_t i = 0; i < count; ++i) {
      s[i] = s_min + (double)knot[i] * ds;
      zw[i] = w[knot[i]];
      zv[i] = v[knot[i]];
    }
    road_pchip_slopes(count, s, zw, dw);
    road_pchip_slopes(count, s, zv, dv);
    size_t m = 0;
    added = 0;
    for (size_t i = 0; i + 1 < count; ++i) {
      more[m++] = knot[i];
      size_t j = worst_miss(w, s_min, ds, s, zw, dw, count, knot[i], knot[i + 1], tol);
      if (!j)
        j = worst_miss(v, s_min, ds, s, zv, dv, count, knot[i], knot[i + 1], tol);
      if (j) {
        more[m++] = j;
        added = 1;
      }
    }
    more[m++] = knot[count - 1];
    memcpy(knot, more, m * sizeof *knot);
    count = m;
  }
  return count;
}

double fb_envelope_spacing(const fb_envelope_model *m, const void *params,
                           const fb_envelope_context *ctx, const fb_road *road)
{
  const double foot = 2.0 * m->ops->reach(params, ctx);
  if (!(foot > 0.0))
    return 0.0;
  double ds = foot / SPACING_PER_FOOTPRINT;
  const double lambda = fb_road_shortest_wavelength(road);
  if (lambda / SPACING_PER_WAVELENGTH < ds)
    ds = lambda / SPACING_PER_WAVELENGTH;
  return ds < foot / SPACING_FINEST ? foot / SPACING_FINEST : ds;
}

/* The samples a window of the model needs on either side of a point. */
static size_t envelope_margin(const fb_envelope_model *m, const void *params,
                              const fb_envelope_context *ctx, double ds)
{
  return (size_t)ceil(m->ops->reach(params, ctx) / ds);
}

int fb_envelope_sample(const fb_road *road, int track, const fb_envelope_model *m,
                       const void *params, const fb_envelope_context *ctx, double s_min,
                       double ds, size_t n, double *w, double *beta, fb_err *err)
{
  if (!(m->ops->reach(params, ctx) > 0.0)) { /* point contact: the road itself */
    for (size_t i = 0; i < n; ++i) {
      w[i] = fb_road_height(road, track, s_min + (double)i * ds);
      if (beta)
        beta[i] = fb_road_slope(road, track, s_min + (double)i * ds);
    }
    return FB_OK;
  }
  /* The road once on the grid, the model's windows on its samples. */
  const size_t pad = envelope_margin(m, params, ctx, ds), total = n + 2 * pad;
  double *z = malloc(3 * total * sizeof *z);
  if (!z)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu road samples", total);
  double *wz = z + total, *bz = wz + total;
  const double s0 = s_min - (double)pad * ds;
  for (size_t j = 0; j < total; ++j)
    z[j] = fb_road_height(road, track, s0 + (double)j * ds);
  const int rc = m->ops->filter(params, ctx, z, total, ds, wz, beta ? bz : NULL, err);
  if (!rc) {
    memcpy(w, wz + pad, n * sizeof *w);
    if (beta)
      memcpy(beta, bz + pad, n * sizeof *beta);
  }
  free(z);
  return rc;
}

int fb_envelope_road_new(const fb_road *road, const fb_envelope_model *m, const void *params,
                         const fb_envelope_context *ctx, double s_min, double s_max,
                         fb_road **out, fb_err *err)
{
  *out = NULL;
  if (!(isfinite(s_min) && isfinite(s_max) && s_min < s_max))
    return fb_err_set(err, FB_EINVAL,
                      "an enveloped road's range must be finite and increasing (got %g .. %g)",
                      s_min, s_max);
  int rc = m->ops->check ? m->ops->check(params, ctx, err) : FB_OK;
  if (rc)
    return rc;
  const double ds = fb_envelope_spacing(m, params, ctx, road);
  if (!(ds > 0.0))
    return fb_road_clone(road, out, err);
  /* The samples and the first knots on a grid fixed in s (multiples of
   * the knots' gap), not from the range's ends: the same road and tire
   * give the same profile over a stretch whatever range a run needs, so
   * runs of different lengths (a ride-limit search, a static start
   * against a settled one) meet the same effective road. */
  const double gap = (double)KNOT_GAP * ds;
  s_min = gap * floor(s_min / gap);
  s_max = gap * ceil(s_max / gap);
  const double samples = (s_max - s_min) / ds + 1.0;
  if (!(samples <= (double)FB_ENVELOPE_MAX_SAMPLES))
    return fb_err_set(err, FB_EINVAL,
                      "an enveloped road of %g m sampled every %g mm needs %.3g samples per "
                      "track, more than %zu: shorten the run",
                      s_max - s_min, 1e3 * ds, samples, (size_t)FB_ENVELOPE_MAX_SAMPLES);
  const size_t n = (size_t)lround(samples);
  double *f = malloc(8 * n * sizeof *f);
  size_t *knot = malloc(2 * n * sizeof *knot);
  if (!f || !knot) {
    free(f);
    free(knot);
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu effective road samples", n);
  }
  double *s = f + 2 * n;
  rc = fb_envelope_sample(road, FB_ROAD_LEFT, m, params, ctx, s_min, ds, n, f, NULL, err);
  if (!rc)
    rc =
        fb_envelope_sample(road, FB_ROAD_RIGHT, m, params, ctx, s_min, ds, n, f + n, NULL, err);
  size_t nknots = 0;
  if (!rc)
    nknots = envelope_knots(f, f + n, n, s_min, ds, knot, knot + n, s);
  double *zl = s + n, *zr = zl + n;
  for (size_t i = 0; !rc && i < nknots; ++i) {
    s[i] = s_min + (double)knot[i] * ds;
    zl[i] = f[knot[i]];
    zr[i] = f[n + knot[i]];
  }
  if (!rc)
    rc = fb_road_new_profile(nknots, s, zl, zr, out, err);
  free(knot);
  free(f);
  return rc;
}

int fb_envelope_gallery_new(fb_envelope_gallery **out, fb_err *err)
{
  *out = NULL;
  fb_envelope_gallery *g = calloc(1, sizeof *g);
  if (!g)
    return fb_err_set(err, FB_ENOMEM, "out of memory for an envelope gallery");
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < sizeof gallery_builtin / sizeof gallery_builtin[0]; ++i)
    rc = fb_envelope_gallery_add(g, gallery_builtin[i], err);
  if (rc)
    fb_envelope_gallery_free(&g);
  *out = g;
  return rc;
}

int fb_envelope_gallery_add(fb_envelope_gallery *g, const fb_envelope_model *m, fb_err *err)
{
  int rc = fb_envelope_model_check(m, err);
  if (rc)
    return rc;
  if (fb_envelope_gallery_find(g, m->name))
    return fb_err_set(err, FB_EINVAL,
                      "envelope model %s: a model of that name is already in the gallery",
                      m->name);
  return fb_registry_add(&g->reg, m, "envelope models", err);
}

size_t fb_envelope_gallery_count(const fb_envelope_gallery *g)
{
  return g ? g->reg.n : 0;
}

const fb_envelope_model *fb_envelope_gallery_at(const fb_envelope_gallery *g, size_t i)
{
  return fb_registry_at(g ? &g->reg : NULL, i);
}

const fb_envelope_model *fb_envelope_gallery_find(const fb_envelope_gallery *g,
                                                  const char *name)
{
  return fb_registry_find(g ? &g->reg : NULL, name);
}

void fb_envelope_gallery_free(fb_envelope_gallery **g)
{
  if (!g || !*g)
    return;
  fb_registry_release(&(*g)->reg);
  free(*g);
  *g = NULL;
}
