/* SPDX-License-Identifier: BSD-3-Clause */
/* Evaluation of an OpenCRG surface on its u/v grid (flexbond/crg.h).
 * Section numbers are those of the ASAM OpenCRG specification 1.2.0. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/crg.h"

#include "road/crg_internal.h"

void crg_release(fb_crg *c)
{
  free(c->v);
  free(c->z);
  free(c->zref);
  free(c->bank);
  free(c->phi);
  free(c->rx);
  free(c->ry);
  free(c->rh);
  c->v = c->z = c->zref = c->bank = c->phi = c->rx = c->ry = c->rh = NULL;
}

void fb_crg_free(fb_crg **crg)
{
  if (!crg || !*crg)
    return;
  crg_release(*crg);
  free(*crg);
  *crg = NULL;
}

/* A copy of n doubles (NULL for NULL). */
static int copy_array(const double *from, size_t n, double **to)
{
  *to = NULL;
  if (!from)
    return 1;
  *to = malloc(n * sizeof **to);
  if (*to)
    memcpy(*to, from, n * sizeof **to);
  return *to != NULL;
}

int fb_crg_clone(const fb_crg *crg, fb_crg **out, fb_err *err)
{
  *out = NULL;
  fb_crg *c = malloc(sizeof *c);
  if (!c)
    return fb_err_set(err, FB_ENOMEM, "out of memory for an OpenCRG surface");
  *c = *crg;
  c->v = c->z = c->zref = c->bank = c->phi = c->rx = c->ry = c->rh = NULL;
  const int ok =
      copy_array(crg->v, crg->nv, &c->v) && copy_array(crg->z, crg->nu * crg->nv, &c->z) &&
      copy_array(crg->zref, crg->nu, &c->zref) && copy_array(crg->bank, crg->nu, &c->bank) &&
      copy_array(crg->phi, crg->nu, &c->phi) && copy_array(crg->rx, crg->nu, &c->rx) &&
      copy_array(crg->ry, crg->nu, &c->ry) && copy_array(crg->rh, crg->nu, &c->rh);
  if (!ok) {
    fb_crg_free(&c);
    return fb_err_set(err, FB_ENOMEM, "out of memory for an OpenCRG surface");
  }
  *out = c;
  return FB_OK;
}

void fb_crg_get_info(const fb_crg *crg, fb_crg_info *out)
{
  out->nu = crg->nu;
  out->nv = crg->nv;
  out->u_first = crg->u0;
  out->u_last = crg->u0 + (double)(crg->nu - 1) * crg->du;
  out->u_increment = crg->du;
  out->v_right = crg->v[0];
  out->v_left = crg->v[crg->nv - 1];
  out->has_phi = crg->phi != NULL;
  out->has_slope = crg->has_slope;
  out->has_banking = crg->has_banking;
  out->border_mode_u = crg->opts.border_mode_u;
  out->border_mode_v = crg->opts.border_mode_v;
}

double fb_crg_v(const fb_crg *crg, size_t j)
{
  return j < crg->nv ? crg->v[j] : NAN;
}

double fb_crg_node(const fb_crg *crg, size_t i, size_t j)
{
  return i < crg->nu && j < crg->nv ? crg->z[i * crg->nv + j] : NAN;
}

/* x brought into [lo, hi] by the border mode (3.4.4, BORDER_MODE_U/V):
 * KEEP clamps, REPEAT wraps with period hi - lo, MIRROR reflects (period
 * 2 (hi - lo)). NAN and ZERO leave x as it is (the caller answers). */
static double border_fold(double x, double lo, double hi, int mode)
{
  const double len = hi - lo;
  if (mode == FB_CRG_BORDER_KEEP || len <= 0.0)
    return x < lo ? lo : x > hi ? hi : x;
  if (mode == FB_CRG_BORDER_REPEAT) {
    double t = fmod(x - lo, len);
    return lo + (t < 0.0 ? t + len : t);
  }
  if (mode == FB_CRG_BORDER_MIRROR) {
    double t = fmod(x - lo, 2.0 * len);
    if (t < 0.0)
      t += 2.0 * len;
    return lo + (t > len ? 2.0 * len - t : t);
  }
  return x;
}

/* The interval k (0 <= k < n - 1) of the ascending knots x[0..n) that
 * holds t (clamped), and t's fraction in it. */
static size_t locate(const double *x, size_t n, double t, double *frac)
{
  size_t lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    const size_t mid = lo + (hi - lo) / 2;
    if (t < x[mid])
      hi = mid;
    else
      lo = mid;
  }
  const double f = (t - x[lo]) / (x[lo + 1] - x[lo]);
  *frac = f < 0.0 ? 0.0 : f > 1.0 ? 1.0 : f;
  return lo;
}

/* Smoothing factor of BORDER_SMOOTH_UBEG/UEND (3.4.4): z rises linearly
 * from 0 over the first smooth_ubeg metres of u and falls to 0 over the
 * last smooth_uend metres (0 beyond the grid's ends). */
static double smooth_factor(const fb_crg *c, double u)
{
  const double u_last = c->u0 + (double)(c->nu - 1) * c->du;
  double f = 1.0;
  if (c->opts.smooth_ubeg > 0.0 && u < c->u0 + c->opts.smooth_ubeg)
    f = fmax(0.0, (u - c->u0) / c->opts.smooth_ubeg);
  if (c->opts.smooth_uend > 0.0 && u > u_last - c->opts.smooth_uend)
    f = fmin(f, fmax(0.0, (u_last - u) / c->opts.smooth_uend));
  return f;
}

double fb_crg_z(const fb_crg *crg, double u, double v)
{
  if (!isfinite(u) || !isfinite(v))
    return NAN;
  const crg_opts *o = &crg->opts;
  const double u_last = crg->u0 + (double)(crg->nu - 1) * crg->du;
  const double v_lo = crg->v[0], v_hi = crg->v[crg->nv - 1];
  const int out_u = u < crg->u0 || u > u_last, out_v = v < v_lo || v > v_hi;
  const double smooth = smooth_factor(crg, u);
  /* 3.4.4: mode 0 returns NaN, mode 1 returns 0; the offset is the
   * border's z offset for a query beyond that border. */
  if ((out_u && o->border_mode_u == FB_CRG_BORDER_NAN) ||
      (out_v && o->border_mode_v == FB_CRG_BORDER_NAN))
    return NAN;
  if (out_u && o->border_mode_u == FB_CRG_BORDER_ZERO)
    return smooth * o->border_offset_u;
  if (out_v && o->border_mode_v == FB_CRG_BORDER_ZERO)
    return smooth * o->border_offset_v;
  const double uu = out_u ? border_fold(u, crg->u0, u_last, o->border_mode_u) : u;
  const double vv = out_v ? border_fold(v, v_lo, v_hi, o->border_mode_v) : v;
  /* Uniform u axis (3.4.2, REFERENCE_LINE_INCREMENT); v may be uneven
   * (3.4.3, "long section at v = X"). */
  double fu = (uu - crg->u0) / crg->du;
  size_t i = fu <= 0.0 ? 0 : (size_t)fu;
  if (i > crg->nu - 2)
    i = crg->nu - 2;
  fu = fmin(1.0, fmax(0.0, fu - (double)i));
  double fv;
  const size_t j = locate(crg->v, crg->nv, vv, &fv);
  const size_t nv = crg->nv;
  const double *r0 = crg->z + i * nv, *r1 = r0 + nv;
  /* Bilinear interpolation in the grid cell (3.1: one value per node of
   * the curved regular grid). */
  double z = (1.0 - fu) * ((1.0 - fv) * r0[j] + fv * r0[j + 1]) +
             fu * ((1.0 - fv) * r1[j] + fv * r1[j + 1]);
  /* The reference line's height and banking, linear between sections;
   * banking acts on v clipped to the grid's lateral range. */
  z += crg->zref[i] + fu * (crg->zref[i + 1] - crg->zref[i]);
  const double vb = v < v_lo ? v_lo : v > v_hi ? v_hi : v;
  z += (crg->bank[i] + fu * (crg->bank[i + 1] - crg->bank[i])) * vb;
  if (out_u && o->border_mode_u == FB_CRG_BORDER_KEEP)
    z += o->border_offset_u;
  if (out_v && o->border_mode_v == FB_CRG_BORDER_KEEP)
    z += o->border_offset_v;
  return smooth * z;
}
