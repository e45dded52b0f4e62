/* SPDX-License-Identifier: BSD-3-Clause */
/* Road profiles: allocation, evaluation of the two tracks, and the time
 * functions of a wheel running along a track at constant speed (see
 * flexbond/road.h for the conventions). */
#include "flexbond/road.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "road/road_internal.h"

static const double PI = 3.14159265358979323846;

size_t road_track_ndata(const road_track *t)
{
  switch (t->kind) {
  case ROAD_BUMP: return 0;
  case ROAD_HARMONICS: return 2 * t->n;
  case ROAD_PCHIP: return 3 * t->n;
  case ROAD_PIECES: return ROAD_PIECE_DOUBLES * t->n;
  }
  return 0;
}

int road_alloc(const road_track *left, const road_track *right, fb_road **out, fb_err *err)
{
  *out = NULL;
  fb_road *road = calloc(1, sizeof *road);
  if (!road)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating a road");
  road->track[FB_ROAD_LEFT] = *left;
  road->track[FB_ROAD_RIGHT] = *right;
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k) {
    size_t n = road_track_ndata(&road->track[k]);
    if (n == 0)
      continue;
    road->data[k] = malloc(n * sizeof *road->data[k]);
    if (!road->data[k]) {
      fb_road_free(&road);
      return fb_err_set(err, FB_ENOMEM, "out of memory creating a road");
    }
  }
  *out = road;
  return FB_OK;
}

/* Doubles of a track's data (road_kind). */
static size_t track_doubles(const road_track *t)
{
  switch (t->kind) {
  case ROAD_HARMONICS: return 2 * t->n;
  case ROAD_PCHIP: return 3 * t->n;
  case ROAD_PIECES: return ROAD_PIECE_DOUBLES * t->n;
  default: return 0;
  }
}

int fb_road_clone(const fb_road *road, fb_road **out, fb_err *err)
{
  *out = calloc(1, sizeof **out);
  if (!*out)
    return fb_err_set(err, FB_ENOMEM, "out of memory copying a road");
  **out = *road;
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k) {
    const size_t n = road->data[k] ? track_doubles(&road->track[k]) : 0;
    (*out)->data[k] = n ? malloc(n * sizeof *road->data[k]) : NULL;
    if (n && !(*out)->data[k]) {
      for (int j = k + 1; j < FB_ROAD_NTRACKS; ++j)
        (*out)->data[j] = NULL;
      fb_road_free(out);
      return fb_err_set(err, FB_ENOMEM, "out of memory copying a road");
    }
    if (n)
      memcpy((*out)->data[k], road->data[k], n * sizeof *road->data[k]);
  }
  return FB_OK;
}

void fb_road_free(fb_road **road)
{
  if (!road || !*road)
    return;
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k)
    free((*road)->data[k]);
  free(*road);
  *road = NULL;
}

/* ---- The (1 - cos) bump: z = (h/2)(1 - cos(2 pi u / L)) for u = s - start
 * in [0, L] (the paper's bump; data sheet docs/reference-vehicle.md),
 * so dz/ds = (pi h / L) sin(2 pi u / L): continuous (0) at both ends, its
 * derivative jumps there. */

static double bump_height(const road_track *t, double s)
{
  const double u = s - t->param[0], h = t->param[1], len = t->param[2];
  if (u < 0.0 || u > len)
    return 0.0;
  return 0.5 * h * (1.0 - cos(2.0 * PI * u / len));
}

static double bump_slope(const road_track *t, double s)
{
  const double u = s - t->param[0], h = t->param[1], len = t->param[2];
  if (u < 0.0 || u > len)
    return 0.0;
  return PI * h / len * sin(2.0 * PI * u / len);
}

/* ---- Harmonic sums (ISO 8608 roads): z = w(s) sum a_k cos(k_k s + p_k),
 * with the fade-in weight w = 3 u^2 - 2 u^3, u = s / F, clamped to [0, 1]
 * (F = 0: w = 1). w and w' vanish at u = 0 and w' at u = 1, so z and z'
 * stay continuous; z'' jumps at s = 0 and s = F. */

static void fade_weight(double fade, double s, double *w, double *dw)
{
  if (fade <= 0.0 || s >= fade) {
    *w = 1.0;
    *dw = 0.0;
    return;
  }
  if (s <= 0.0) {
    *w = *dw = 0.0;
    return;
  }
  const double u = s / fade;
  *w = u * u * (3.0 - 2.0 * u);
  *dw = 6.0 * u * (1.0 - u) / fade;
}

/* z(s) = sum_k A_k cos(kappa_k s + phi_k) and its slope, with kappa_k =
 * kappa_0 + k dkappa equally spaced: e^(i kappa_k s) by complex rotation
 * (one multiplication per harmonic instead of a cosine and a sine; the
 * rounding grows by about eps per harmonic, 1e-13 of z for 1024). */
static void harmonics_sum(const road_track *t, const double *data, double s, double *z,
                          double *dz)
{
  const size_t n = t->n;
  const double *ac = data, *as = data + n;
  const double kappa0 = t->param[1], dkappa = t->param[2];
  const double rc = cos(dkappa * s), rs = sin(dkappa * s);
  double wc = cos(kappa0 * s), ws = sin(kappa0 * s), sum = 0.0, slope = 0.0;
  for (size_t k = 0; k < n; ++k) {
    /* A cos(x + phi) = A cos(phi) cos(x) - A sin(phi) sin(x). */
    sum += ac[k] * wc - as[k] * ws;
    slope -= (kappa0 + (double)k * dkappa) * (ac[k] * ws + as[k] * wc);
    const double next = wc * rc - ws * rs;
    ws = ws * rc + wc * rs;
    wc = next;
  }
  *z = sum;
  *dz = slope;
}

static double harmonics_height(const road_track *t, const double *data, double s)
{
  double w, dw, z, dz;
  fade_weight(t->param[0], s, &w, &dw);
  if (w == 0.0)
    return 0.0;
  harmonics_sum(t, data, s, &z, &dz);
  return w * z;
}

static double harmonics_slope(const road_track *t, const double *data, double s)
{
  double w, dw, z, dz;
  fade_weight(t->param[0], s, &w, &dw);
  if (w == 0.0)
    return 0.0;
  harmonics_sum(t, data, s, &z, &dz);
  return w * dz + dw * z;
}

double road_track_height(const road_track *t, const double *data, double s)
{
  switch (t->kind) {
  case ROAD_BUMP: return bump_height(t, s);
  case ROAD_HARMONICS: return harmonics_height(t, data, s);
  case ROAD_PCHIP: return road_pchip_height(t->n, data, data + t->n, data + 2 * t->n, s);
  case ROAD_PIECES: return road_pieces_height(t->n, data, s);
  }
  return NAN;
}

double road_track_slope(const road_track *t, const double *data, double s)
{
  switch (t->kind) {
  case ROAD_BUMP: return bump_slope(t, s);
  case ROAD_HARMONICS: return harmonics_slope(t, data, s);
  case ROAD_PCHIP: return road_pchip_slope(t->n, data, data + t->n, data + 2 * t->n, s);
  case ROAD_PIECES: return road_pieces_slope(t->n, data, s);
  }
  return NAN;
}

/* 1 if segment [i, i + 1] of a PCHIP track (knots s, heights z, slopes
 * d) is flat: a constant height. */
static int pchip_flat(const double *z, const double *d, size_t i)
{
  return z[i] == z[i + 1] && d[i] == 0.0 && d[i + 1] == 0.0;
}

/* Breaks of a PCHIP track: its ends, where the held profile may meet the
 * data with a slope jump, and every knot where a flat stretch meets one
 * that is not, so that an integrator resting on a flat stretch cannot
 * step over the feature after it (a wheel at rest takes steps of seconds
 * there). The other interior knots are not breaks: there PCHIP is C1, the
 * road velocity is continuous and only its rate jumps, which the error
 * control handles better than a restart at order 1 per knot (a 5 mm
 * profile of the paper's bump: 27456 -> 15162 steps for System 1, and
 * closer to the analytic bump). */
static size_t pchip_breaks(size_t n, const double *data, double *s, size_t max)
{
  const double *z = data + n, *d = data + 2 * n;
  size_t count = 0;
  for (size_t i = 0; i < n; ++i) {
    const int end = i == 0 || i + 1 == n;
    if (end || pchip_flat(z, d, i - 1) != pchip_flat(z, d, i)) {
      if (s && count < max)
        s[count] = data[i];
      ++count;
    }
  }
  return count;
}

/* Breaks of a track in s, ascending (see fb_road_breaks). */
static size_t track_breaks(const road_track *t, const double *data, double *s, size_t max)
{
  double two[2];
  size_t count = 0;
  switch (t->kind) {
  case ROAD_PIECES: return road_pieces_breaks(t->n, data, s, max);
  case ROAD_BUMP:
    two[0] = t->param[0];
    two[1] = t->param[0] + t->param[2];
    count = 2;
    break;
  case ROAD_HARMONICS:
    two[0] = 0.0;
    two[1] = t->param[0];
    count = t->param[0] > 0.0 ? 2 : 0;
    break;
  case ROAD_PCHIP: return pchip_breaks(t->n, data, s, max);
  }
  if (s && count > 0)
    memcpy(s, two, (count < max ? count : max) * sizeof *s);
  return count;
}

static int valid_track(const fb_road *road, int track)
{
  return road && (track == FB_ROAD_LEFT || track == FB_ROAD_RIGHT);
}

double fb_road_height(const fb_road *road, int track, double s)
{
  if (!valid_track(road, track))
    return NAN;
  return road_track_height(&road->track[track], road->data[track], s);
}

double fb_road_slope(const fb_road *road, int track, double s)
{
  if (!valid_track(road, track))
    return NAN;
  return road_track_slope(&road->track[track], road->data[track], s);
}

size_t fb_road_breaks(const fb_road *road, int track, double *s, size_t max)
{
  if (!valid_track(road, track))
    return 0;
  return track_breaks(&road->track[track], road->data[track], s, max);
}

/* ---- A wheel's time functions. The context is one block: the wheel's
 * motion, the track header and the track's data (a flexible array), so
 * fb_tfun_new_callback_copy can own a self-contained copy. */

double road_wheel_height(double t, void *ctx)
{
  const road_wheel_ctx *w = ctx;
  return road_track_height(&w->track, w->data, w->s0 + w->speed * t);
}

/* dz/dt = V dz/ds along s = s0 + V t. */
double road_wheel_velocity(double t, void *ctx)
{
  const road_wheel_ctx *w = ctx;
  return w->speed * road_track_slope(&w->track, w->data, w->s0 + w->speed * t);
}

static int wheel_check(const fb_road *road, int track, double speed, double s0, fb_err *err)
{
  if (!road)
    return fb_err_set(err, FB_EINVAL, "road wheel: road is NULL");
  if (track != FB_ROAD_LEFT && track != FB_ROAD_RIGHT)
    return fb_err_set(err, FB_EINVAL,
                      "road wheel: track must be %d (left) or %d (right), got %d", FB_ROAD_LEFT,
                      FB_ROAD_RIGHT, track);
  if (!(isfinite(speed) && speed > 0.0))
    return fb_err_set(err, FB_EINVAL, "road wheel: speed must be > 0 m/s (got %g)", speed);
  if (!isfinite(s0))
    return fb_err_set(err, FB_EINVAL, "road wheel: start position s0 is not finite (got %g)",
                      s0);
  return FB_OK;
}

/* Builds the block and the breakpoint times, then the time function. */
static int wheel_tfun(const fb_road *road, int track, double speed, double s0, fb_tfun_fn fn,
                      fb_tfun **out, fb_err *err)
{
  if (out)
    *out = NULL;
  int rc = wheel_check(road, track, speed, s0, err);
  if (rc)
    return rc;
  const road_track *t = &road->track[track];
  const size_t ndata = road_track_ndata(t);
  const size_t nbreak = track_breaks(t, road->data[track], NULL, 0);
  const size_t size = sizeof(road_wheel_ctx) + ndata * sizeof(double);
  road_wheel_ctx *w = malloc(size);
  double *times = malloc((nbreak ? nbreak : 1) * sizeof *times);
  if (!w || !times) {
    free(w);
    free(times);
    return fb_err_set(err, FB_ENOMEM, "out of memory creating a road wheel function");
  }
  w->speed = speed;
  w->s0 = s0;
  w->origin = road->origin[track];
  w->track = *t;
  if (ndata)
    memcpy(w->data, road->data[track], ndata * sizeof(double));
  track_breaks(t, road->data[track], times, nbreak);
  for (size_t i = 0; i < nbreak; ++i)
    times[i] = (times[i] - s0) / speed;
  rc = fb_tfun_new_callback_copy(fn, w, size, nbreak, times, out, err);
  free(w);
  free(times);
  return rc;
}

int fb_road_wheel_height(const fb_road *road, int track, double speed, double s0, fb_tfun **out,
                         fb_err *err)
{
  return wheel_tfun(road, track, speed, s0, road_wheel_height, out, err);
}

int fb_road_wheel_velocity(const fb_road *road, int track, double speed, double s0,
                           fb_tfun **out, fb_err *err)
{
  return wheel_tfun(road, track, speed, s0, road_wheel_velocity, out, err);
}

/* One track's shortest wavelength (road_kind's layouts). */
static double track_shortest_wavelength(const road_track *t, const double *data)
{
  switch (t->kind) {
  case ROAD_BUMP: return 0.5 * t->param[2];
  case ROAD_HARMONICS: {
    const double k = t->param[1] + (double)(t->n ? t->n - 1 : 0) * t->param[2];
    return k > 0 ? 6.28318530717958647692 / k : INFINITY;
  }
  case ROAD_PCHIP: {
    double ds = INFINITY;
    for (size_t i = 1; i < t->n; ++i)
      ds = fmin(ds, data[i] - data[i - 1]);
    return 2.0 * ds;
  }
  case ROAD_PIECES: return road_pieces_shortest_wavelength(t->n, data);
  }
  return INFINITY;
}

double fb_road_shortest_wavelength(const fb_road *road)
{
  double w = INFINITY;
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k)
    w = fmin(w, track_shortest_wavelength(&road->track[k], road->data[k]));
  return w;
}
