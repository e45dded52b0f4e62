/* SPDX-License-Identifier: BSD-3-Clause */
/* Tire enveloping (flexbond/envelope.h): one conformance harness over
 * every model of a gallery, with a model a program adds at run time (a
 * moving average of the road over the tire's footprint), and each
 * built-in model against an independent answer written here: the cams
 * and the overlap over a step in closed form, the cams over a random
 * road by a brute-force contact search on a grid of its own, and the
 * long-wavelength limit, where every model is the road within a bound
 * derived below; the program's model chosen in a scenario file, its
 * parameter's error located at its generated key. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "flexbond/envelope.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle_util.h"

/* ---- A program's own model: the road's mean over [s - half, s + half]. */

typedef struct mean_params {
  double half; /* m */
} mean_params;

static const fb_param mean_param[] = {
    {.name = "half",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(mean_params, half),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_DEFAULT,
     .def = 0.1,
     .doc = "half the averaging window"},
};

static double mean_reach(const void *params, const fb_envelope_context *ctx)
{
  (void)ctx;
  return ((const mean_params *)params)->half;
}

static int mean_filter(const void *params, const fb_envelope_context *ctx, const double *z,
                       size_t n, double ds, double *w, double *beta, fb_err *err)
{
  (void)ctx;
  (void)err;
  const size_t h = (size_t)floor(((const mean_params *)params)->half / ds);
  for (size_t i = h; i + h < n; ++i) {
    double sum = 0.0;
    for (size_t k = i - h; k <= i + h; ++k)
      sum += z[k];
    w[i] = sum / (double)(2 * h + 1);
    if (beta)
      beta[i] = h ? (z[i + h] - z[i - h]) / (2.0 * (double)h * ds) : 0.0;
  }
  return FB_OK;
}

static const fb_envelope_model_ops mean_ops = {.reach = mean_reach, .filter = mean_filter};
static const fb_envelope_model mean_model = {.name = "mean",
                                             .doc = "the road's mean over the footprint",
                                             .param = mean_param,
                                             .nparams = 1,
                                             .params_size = sizeof(mean_params),
                                             .ops = &mean_ops};

/* ---- Roads. */

enum { TRACK = FB_ROAD_LEFT };
static const double PI = 3.14159265358979323846;
static const double R0 = 0.5, DEFL = 0.02, STEP_H = 0.1;

static fb_envelope_context tire_context(void)
{
  return (fb_envelope_context){.corner = "LF", .radius = R0, .static_deflection = DEFL};
}

/* A step of height h at s = 0, made as a profile whose knots are 1e-6 m
 * apart there. */
static fb_road *step_road(double h)
{
  const double s[] = {-20.0, 0.0, 1e-6, 20.0}, z[] = {0.0, 0.0, h, h};
  fb_road *road = NULL;
  fb_err err = {0};
  CHECK(fb_road_new_profile(4, s, z, z, &road, &err) == FB_OK);
  return road;
}

static fb_road *flat_road(double z0)
{
  const double s[] = {-50.0, 50.0}, z[] = {z0, z0};
  fb_road *road = NULL;
  fb_err err = {0};
  CHECK(fb_road_new_profile(2, s, z, z, &road, &err) == FB_OK);
  return road;
}

/* An ISO 8608 road of class road_class, the other parameters default
 * (1024 harmonics). */
static fb_road *iso_road(char road_class)
{
  fb_road *road = NULL;
  fb_err err = {0};
  fb_road_iso8608_params iso;
  fb_road_iso8608_defaults(&iso);
  iso.road_class = road_class;
  CHECK(fb_road_new_iso8608(&iso, &road, &err) == FB_OK);
  return road;
}

/* ---- The conformance harness: every model of g. */

static void conform_flat(const fb_envelope_model *m, const void *p,
                         const fb_envelope_context *ctx)
{
  /* A flat road is its own effective road. */
  fb_road *road = flat_road(0.3);
  fb_err err = {0};
  enum { N = 64 };
  double w[N], beta[N];
  CHECK(fb_envelope_sample(road, TRACK, m, p, ctx, -1.0, 0.01, N, w, beta, &err) == FB_OK);
  for (size_t i = 0; i < N; ++i) {
    CHECK_NEAR(w[i], 0.3, 1e-12);
    CHECK_NEAR(beta[i], 0.0, 1e-9);
  }
  fb_road_free(&road);
}

/* The filter writes every point whose window fits, reads nothing beyond
 * the reach, and is monotone in the road (a higher road is never a lower
 * effective road). */
static void conform_filter(const fb_envelope_model *m, const void *p,
                           const fb_envelope_context *ctx)
{
  const double ds = 0.01, reach = m->ops->reach(p, ctx);
  const size_t pad = (size_t)ceil(reach / ds), n = 2 * pad + 41;
  double *z = calloc(4 * n, sizeof *z);
  double *w = z + n, *w2 = w + n, *b = w2 + n;
  fb_err err = {0};
  for (size_t j = 0; j < n; ++j)
    z[j] = 0.05 * sin(0.37 * (double)j) + 0.02 * (j % 7 == 3);
  for (size_t j = 0; j < n; ++j)
    w[j] = b[j] = NAN;
  CHECK(m->ops->filter(p, ctx, z, n, ds, w, b, &err) == FB_OK);
  for (size_t i = pad; i + pad < n; ++i)
    CHECK(isfinite(w[i]) && isfinite(b[i]));
  /* Beyond the reach of point i = n / 2: changing it changes nothing. */
  const size_t mid = n / 2, far = mid + pad + 1;
  const double keep = w[mid];
  if (far < n) {
    z[far] += 1.0;
    CHECK(m->ops->filter(p, ctx, z, n, ds, w2, NULL, &err) == FB_OK);
    CHECK(w2[mid] == keep);
    z[far] -= 1.0;
  }
  /* Monotone: raise the road anywhere within reach. */
  z[mid + 1] += 0.03;
  CHECK(m->ops->filter(p, ctx, z, n, ds, w2, NULL, &err) == FB_OK);
  for (size_t i = pad; i + pad < n; ++i)
    CHECK(w2[i] >= w[i] - 1e-12);
  free(z);
}

/* The effective road as a road: a bump's effective road starts and ends
 * at 0, and its slope integrates to its height change (the trapezoid
 * rule on a grid 10 times finer than the profile's knots). */
static void conform_road(const fb_envelope_model *m, const void *p,
                         const fb_envelope_context *ctx)
{
  fb_road *bump = NULL, *env = NULL;
  fb_err err = {0};
  CHECK(fb_road_new_bump(0.08, 1.5, 1.0, 1.5, &bump, &err) == FB_OK);
  CHECK(fb_envelope_road_new(bump, m, p, ctx, -2.0, 6.0, &env, &err) == FB_OK);
  for (int track = 0; env && track < FB_ROAD_NTRACKS; ++track) {
    CHECK_NEAR(fb_road_height(env, track, -2.0), 0.0, 1e-12);
    CHECK_NEAR(fb_road_height(env, track, 6.0), 0.0, 1e-12);
    const size_t n = 80000;
    double integral = 0.0, a = -1.0, b = 5.0, h = (b - a) / (double)n;
    for (size_t i = 0; i <= n; ++i)
      integral += (i == 0 || i == n ? 0.5 : 1.0) * fb_road_slope(env, track, a + (double)i * h);
    integral *= h;
    /* The trapezoid rule's error on a C1 piecewise cubic: h^2 / 12 times
     * the slope's variation (< 0.5 / ds): well under 1e-6. */
    CHECK_NEAR(integral, fb_road_height(env, track, b) - fb_road_height(env, track, a), 1e-6);
  }
  fb_road_free(&env);
  fb_road_free(&bump);
}

static void conform_all(const fb_envelope_gallery *g)
{
  const fb_envelope_context ctx = tire_context();
  fb_err err = {0};
  for (size_t i = 0; i < fb_envelope_gallery_count(g); ++i) {
    const fb_envelope_model *m = fb_envelope_gallery_at(g, i);
    CHECK(fb_envelope_model_check(m, &err) == FB_OK);
    CHECK(fb_envelope_gallery_find(g, m->name) == m);
    fb_envelope_params p;
    fb_envelope_params_init(m, &p);
    CHECK(!m->ops->check || m->ops->check(p.bytes, &ctx, &err) == FB_OK);
    CHECK(fb_params_check(m->param, m->nparams, p.bytes, &err) == FB_OK);
    conform_flat(m, p.bytes, &ctx);
    if (m->ops->reach(p.bytes, &ctx) > 0.0)
      conform_filter(m, p.bytes, &ctx);
    conform_road(m, p.bytes, &ctx);
    /* Every parameter with a range refused outside it, by name. */
    for (size_t k = 0; k < m->nparams; ++k) {
      const fb_param *q = &m->param[k];
      if (!(q->range & FB_RANGE_LO))
        continue;
      fb_envelope_params bad = p;
      *(double *)(void *)(bad.bytes + q->offset) = q->lo - 1.0;
      err = (fb_err){0};
      CHECK(fb_params_check(m->param, m->nparams, bad.bytes, &err) == FB_EINVAL);
      CHECK(!strcmp(err.part.field, q->name));
    }
  }
}

static void test_gallery(void)
{
  fb_envelope_gallery *g = NULL;
  fb_err err = {0};
  CHECK(fb_envelope_gallery_new(&g, &err) == FB_OK);
  CHECK(fb_envelope_gallery_count(g) == 3);
  CHECK(fb_envelope_gallery_at(g, 0) == &fb_envelope_model_point);
  CHECK(fb_envelope_gallery_add(g, &mean_model, &err) == FB_OK);
  CHECK(fb_envelope_gallery_add(g, &mean_model, &err) == FB_EINVAL); /* its name is taken */
  const fb_envelope_model_ops no_filter = {.reach = mean_reach};
  const fb_envelope_model broken = {.name = "broken", .doc = "no filter", .ops = &no_filter};
  CHECK(fb_envelope_gallery_add(g, &broken, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "filter") != NULL);
  conform_all(g);
  fb_envelope_gallery_free(&g);
  CHECK(g == NULL);
}

/* ---- Point contact: the road itself, bit for bit. */

static void test_point(void)
{
  fb_road *road = iso_road('C'), *env = NULL;
  fb_err err = {0};
  const fb_envelope_context ctx = tire_context();
  CHECK(fb_envelope_road_new(road, &fb_envelope_model_point, NULL, &ctx, 0.0, 10.0, &env,
                             &err) == FB_OK);
  for (double s = -3.0; s < 20.0; s += 0.123)
    CHECK(fb_road_height(env, TRACK, s) == fb_road_height(road, TRACK, s));
  fb_road_free(&env);
  fb_road_free(&road);
}

/* ---- The cams over a step, in closed form.
 *
 * A cam at s_c (lower edge g(x) = b ((1 - |x/a|^c)^(1/c) - 1) above its
 * lowest point) over a step of height H < b at s = 0: its lowest point
 * is at H once its centre is past the step (its bottom on the upper
 * level), and before it at max(0, H + g(s_c)), the corner touching its
 * front edge (g is even). */

static double cam_edge(double x, double a, double b, double c)
{
  const double u = fabs(x / a);
  return u >= 1.0 ? -INFINITY : b * (pow(1.0 - pow(u, c), 1.0 / c) - 1.0);
}

static double cam_over_step(double sc, double h, double a, double b, double c)
{
  return sc >= 0.0 ? h : fmax(0.0, h + cam_edge(sc, a, b, c));
}

static void test_cams_step(void)
{
  const fb_envelope_context ctx = tire_context();
  fb_envelope_params p;
  fb_envelope_params_init(&fb_envelope_model_cams, &p);
  const fb_envelope_cams_params *cp = (const void *)p.bytes;
  const double a = cp->length * R0, b = cp->height * R0, c = cp->order;
  const double ls = cp->shift * fb_envelope_chord(R0, DEFL);
  fb_road *road = step_road(STEP_H);
  const double ds = fb_envelope_spacing(&fb_envelope_model_cams, p.bytes, &ctx, road);
  /* The cams stand 2 lag ds apart, l_s rounded to whole samples. */
  const double ls_used = 2.0 * fmax(1.0, round(0.5 * ls / ds)) * ds;
  CHECK(fabs(ls_used - ls) <= ds);
  enum { N = 6001 };
  const double s0 = -1.5;
  double *w = malloc(2 * N * sizeof *w), *beta = w + N;
  fb_err err = {0};
  CHECK(fb_envelope_sample(road, TRACK, &fb_envelope_model_cams, p.bytes, &ctx, s0, ds, N, w,
                           beta, &err) == FB_OK);
  /* The tolerance: the sampled maximum misses the corner by at most ds
   * along the cam's edge, whose slope where it meets the corner
   * (g = -H) is |g'| = (b/a) u^(c-1) (1 - u^c)^(1/c - 1) < 1 here
   * (u = 0.54: 0.73); twice ds covers it. */
  double worst = 0.0, integral = 0.0, rise_lo = NAN, rise_hi = NAN;
  int monotone = 1;
  for (size_t i = 0; i < N; ++i) {
    const double s = s0 + (double)i * ds;
    const double exact = 0.5 * (cam_over_step(s + 0.5 * ls_used, STEP_H, a, b, c) +
                                cam_over_step(s - 0.5 * ls_used, STEP_H, a, b, c));
    worst = fmax(worst, fabs(w[i] - exact));
    monotone &= i == 0 || w[i] >= w[i - 1] - 1e-15;
    integral += (i == 0 || i == N - 1 ? 0.5 : 1.0) * beta[i] * ds;
    if (isnan(rise_lo) && w[i] > 0.0)
      rise_lo = s;
    if (isnan(rise_hi) && w[i] >= STEP_H)
      rise_hi = s;
  }
  printf("cams over a %.2f m step (r0 %.2f m, ds %.2e m): max |w - closed form| = %.3e m\n",
         STEP_H, R0, ds, worst);
  CHECK(worst <= 2.0 * ds);
  CHECK(monotone);
  /* The effective slope integrates to the step's height (trapezoid rule
   * of beta, which holds exactly sums of the two cams' differences: the
   * error is the end samples' rounding). */
  CHECK_NEAR(integral, STEP_H, 1e-9);
  /* It rises over the front cam's reach to the corner plus the cams'
   * spacing (Schmeitz's observation: about the contact length and the
   * cam's reach): from s = -x_H - l_s/2 to s = l_s/2, with g(x_H) = -H. */
  const double u_h = pow(1.0 - pow(1.0 - STEP_H / b, c), 1.0 / c), x_h = u_h * a;
  printf("cams: the effective step rises over %.4f m (closed form %.4f m)\n", rise_hi - rise_lo,
         x_h + ls_used);
  CHECK_NEAR(rise_lo, -x_h - 0.5 * ls_used, 2.0 * ds);
  CHECK_NEAR(rise_hi, 0.5 * ls_used, 2.0 * ds);
  free(w);
  fb_road_free(&road);
}

/* ---- The overlap over a step, in closed form.
 *
 * The circle (radius r, centre (0, zc)) over a road of level h on the
 * interval [x0, x1] of its own x: it overlaps the road where its lower
 * edge zc - sqrt(r^2 - x^2) is below h, |x| < X = sqrt(r^2 - (zc - h)^2),
 * by (h - zc) x + F(x) over the interval's part inside (-X, X), with
 * F(x) = (x sqrt(r^2 - x^2) + r^2 asin(x / r)) / 2 the antiderivative of
 * sqrt(r^2 - x^2). The step at s = 0 under a circle centred at s: level
 * 0 on x < -s, H on x > -s. */

static double circle_f(double r, double x)
{
  return 0.5 * (x * sqrt(fmax(0.0, r * r - x * x)) + r * r * asin(x / r));
}

static double level_overlap(double r, double zc, double h, double x0, double x1)
{
  const double depth = zc - h;
  if (depth >= r)
    return 0.0;
  const double big_x = sqrt(r * r - depth * depth);
  const double lo = fmax(x0, -big_x), hi = fmin(x1, big_x);
  return hi > lo ? (h - zc) * (hi - lo) + circle_f(r, hi) - circle_f(r, lo) : 0.0;
}

static double step_overlap(double r, double zc, double s, double h)
{
  return level_overlap(r, zc, 0.0, -r, -s) + level_overlap(r, zc, h, -s, r);
}

/* The effective height: the centre height (bisection, to 1e-13 m) where
 * the overlap is that of a flat road at depth d, less r - d. */
static double overlap_over_step(double r, double d, double s, double h)
{
  const double target = step_overlap(r, r - d, 1e9, 0.0);
  double lo = r - d - 0.01, hi = r - d + h + 0.01;
  while (hi - lo > 1e-13) {
    const double mid = 0.5 * (lo + hi);
    if (step_overlap(r, mid, s, h) > target)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi) - (r - d);
}

/* The tolerance, one grid spacing ds: the library's midpoint rule over
 * columns ds wide misplaces at most H ds / 2 of area at the step, which
 * moves the centre by that over the overlapping width (> 0.28 m at d =
 * 0.02 m: < ds / 5); as d tends to 0 a single column carries the
 * overlap and the effective height is the sampled rigid ring, off the
 * exact one by at most ds times the circle's slope where it meets the
 * corner (0.3 / 0.4 = 0.75). */
static void test_overlap_step(double d, const char *what)
{
  const fb_envelope_context ctx = tire_context();
  fb_envelope_params p;
  fb_envelope_params_init(&fb_envelope_model_overlap, &p);
  ((fb_envelope_overlap_params *)(void *)p.bytes)->deflection = d;
  fb_road *road = step_road(STEP_H);
  const double ds = fb_envelope_spacing(&fb_envelope_model_overlap, p.bytes, &ctx, road);
  enum { N = 8001 };
  const double s0 = -1.0;
  double *w = malloc(N * sizeof *w);
  fb_err err = {0};
  CHECK(fb_envelope_sample(road, TRACK, &fb_envelope_model_overlap, p.bytes, &ctx, s0, ds, N, w,
                           NULL, &err) == FB_OK);
  double worst = 0.0, worst_ring = 0.0;
  int monotone = 1;
  for (size_t i = 0; i < N; ++i) {
    const double s = s0 + (double)i * ds;
    worst = fmax(worst, fabs(w[i] - overlap_over_step(R0, d, s, STEP_H)));
    /* The rigid ring (d -> 0): the circle just touching the corner,
     * centre at H + sqrt(r^2 - s^2) before the step. */
    const double ring = s >= 0.0 ? STEP_H : fmax(0.0, STEP_H + sqrt(R0 * R0 - s * s) - R0);
    worst_ring = fmax(worst_ring, fabs(w[i] - ring));
    monotone &= i == 0 || w[i] >= w[i - 1] - 1e-12;
  }
  printf("overlap over a %.2f m step, %s (d %.0e m, ds %.2e m): max |w - closed form| = %.3e "
         "m, from the rigid ring %.3e m\n",
         STEP_H, what, d, ds, worst, worst_ring);
  CHECK(worst <= ds);
  CHECK(monotone);
  if (d < 1e-5) /* the rigid ring itself */
    CHECK(worst_ring <= ds);
  free(w);
  fb_road_free(&road);
}

/* ---- The cams over a random road, by a brute-force contact search of
 * its own: each cam's resting height from the road evaluated at 2001
 * points across the cam at their exact positions (not the library's
 * grid), the edge's formula written again. */

static double brute_cam(const fb_road *road, double sc, double a, double b, double c)
{
  double top = -INFINITY;
  for (int k = -1000; k <= 1000; ++k) {
    const double x = (double)k / 1000.0 * a * (1.0 - 1e-12);
    const double u = fabs(x) / a;
    const double edge = -b + b * pow(1.0 - pow(u, c), 1.0 / c);
    top = fmax(top, fb_road_height(road, TRACK, sc + x) + edge);
  }
  return top;
}

static void test_cams_random(void)
{
  fb_road *road = iso_road('E');
  fb_err err = {0};
  const fb_envelope_context ctx = tire_context();
  fb_envelope_params p;
  fb_envelope_params_init(&fb_envelope_model_cams, &p);
  const fb_envelope_cams_params *cp = (const void *)p.bytes;
  const double a = cp->length * R0, b = cp->height * R0, c = cp->order;
  const double ds = fb_envelope_spacing(&fb_envelope_model_cams, p.bytes, &ctx, road);
  const double ls = cp->shift * fb_envelope_chord(R0, DEFL);
  const double ls_used = 2.0 * fmax(1.0, round(0.5 * ls / ds)) * ds;
  enum { N = 100 };
  double w[N];
  const double s0 = 10.0;
  /* Every 10th grid point of the library's, compared. */
  double *wl = malloc(10 * N * sizeof *wl);
  CHECK(fb_envelope_sample(road, TRACK, &fb_envelope_model_cams, p.bytes, &ctx, s0, ds, 10 * N,
                           wl, NULL, &err) == FB_OK);
  double worst = 0.0, max_slope = 0.0;
  for (size_t i = 0; i < N; ++i) {
    const double s = s0 + (double)(10 * i) * ds;
    w[i] = 0.5 * (brute_cam(road, s + 0.5 * ls_used, a, b, c) +
                  brute_cam(road, s - 0.5 * ls_used, a, b, c));
    worst = fmax(worst, fabs(wl[10 * i] - w[i]));
    max_slope = fmax(max_slope, fabs(fb_road_slope(road, TRACK, s)));
  }
  /* Two samplings of one maximum differ by at most their spacings (ds
   * and a/1000) times the slope of z + g next to it: on a smooth road
   * the cam touches where g' = -z', so that slope is at most twice the
   * road's steepest. */
  const double tol = (ds + a / 1000.0) * 2.0 * max_slope;
  printf("cams over an ISO 8608 class E road: max |library - brute force| = %.3e m (bound "
         "%.3e m, ds %.2e m)\n",
         worst, tol, ds);
  CHECK(worst <= tol);
  free(wl);
  fb_road_free(&road);
}

/* ---- The long-wavelength limit.
 *
 * On a (1 - cos) bump of length L >> r0 (height h: slope at most
 * k1 = pi h / L, curvature at most k2 = 2 pi^2 h / L^2) every model is
 * the road to second order:
 * - cams: the mean of the two cams' heights l_s apart differs from the
 *   road's height by at most k2 l_s^2 / 8; a cam on a slope z' rests at
 *   the edge point where g' = -z', at most z' x* = a z' (z' a / b)^(1 /
 *   (c - 1)) above the road under its centre;
 * - overlap: the circle's centre sits (r - d) (1 / cos(theta) - 1) <=
 *   (r - d) k1^2 / 2 higher on a slope, and the curvature changes its
 *   overlap by the relative radius k2 r: at most d k2 r / 3 in height.
 * Plus the grid's error (ds times the slopes); a bound of twice the sum
 * covers the neglected higher orders. */

static void test_long_wave(void)
{
  const double h = 0.1, len = 20.0, k1 = PI * h / len, k2 = 2.0 * PI * PI * h / len / len;
  fb_road *road = NULL;
  fb_err err = {0};
  CHECK(fb_road_new_bump(h, len, 0.0, 0.0, &road, &err) == FB_OK);
  const fb_envelope_context ctx = tire_context();
  const fb_envelope_model *const models[] = {&fb_envelope_model_cams,
                                             &fb_envelope_model_overlap};
  for (size_t k = 0; k < 2; ++k) {
    fb_envelope_params p;
    fb_envelope_params_init(models[k], &p);
    double bound;
    if (k == 0) {
      const fb_envelope_cams_params *cp = (const void *)p.bytes;
      const double a = cp->length * R0, b = cp->height * R0, c = cp->order;
      const double ls = cp->shift * fb_envelope_chord(R0, DEFL);
      bound = k2 * ls * ls / 8.0 + a * k1 * pow(k1 * a / b, 1.0 / (c - 1.0));
    } else {
      bound = (R0 - DEFL) * k1 * k1 / 2.0 + DEFL * k2 * R0 / 3.0;
    }
    const double ds = fb_envelope_spacing(models[k], p.bytes, &ctx, road);
    bound = 2.0 * (bound + ds * k1);
    enum { N = 5000 };
    double *w = malloc(N * sizeof *w);
    const double s0 = -2.0, step = (len + 4.0) / N;
    double worst = 0.0;
    for (size_t i = 0; i < N; ++i) {
      CHECK(fb_envelope_sample(road, TRACK, models[k], p.bytes, &ctx, s0 + (double)i * step, ds,
                               1, &w[i], NULL, &err) == FB_OK);
      worst = fmax(worst, fabs(w[i] - fb_road_height(road, TRACK, s0 + (double)i * step)));
    }
    printf("%s on a %.0f m bump: max |w - z| = %.3e m, bound %.3e m (%.1e of its height)\n",
           models[k]->name, len, worst, bound, bound / h);
    CHECK(worst <= bound);
    CHECK(bound < 5e-3 * h); /* a fraction of a percent of the bump */
    free(w);
  }
  fb_road_free(&road);
}

/* ---- The cost on the ISO road of 1024 harmonics: 200 m of both tracks. */

static void test_cost(void)
{
  fb_road *road = iso_road('C'), *env = NULL;
  fb_err err = {0};
  const fb_envelope_context ctx = tire_context();
  const fb_envelope_model *const models[] = {&fb_envelope_model_cams,
                                             &fb_envelope_model_overlap};
  for (size_t k = 0; k < 2; ++k) {
    fb_envelope_params p;
    fb_envelope_params_init(models[k], &p);
    const clock_t t0 = clock();
    CHECK(fb_envelope_road_new(road, models[k], p.bytes, &ctx, 0.0, 200.0, &env, &err) ==
          FB_OK);
    printf("%s: 200 m of an ISO 8608 road of 1024 harmonics enveloped in %.3f s\n",
           models[k]->name, (double)(clock() - t0) / CLOCKS_PER_SEC);
    fb_road_free(&env);
  }
  fb_road_free(&road);
}

/* ---- The profile through the effective road: its knots are chosen so
 * that the monotone cubic through them misses no sample of the
 * effective road by more than 2e-3 of its height range (both tracks'),
 * checked here end to end through the profile made (a step, with kinks
 * where the cams first touch it, and a random road). */

static void test_profile(void)
{
  const fb_envelope_context ctx = tire_context();
  fb_road *roads[2] = {step_road(STEP_H), iso_road('E')};
  const fb_envelope_model *const models[] = {&fb_envelope_model_cams,
                                             &fb_envelope_model_overlap};
  for (size_t r = 0; r < 2; ++r)
    for (size_t k = 0; k < 2; ++k) {
      fb_envelope_params p;
      fb_envelope_params_init(models[k], &p);
      fb_road *env = NULL;
      fb_err err = {0};
      const double ds = fb_envelope_spacing(models[k], p.bytes, &ctx, roads[r]);
      /* On the profile's own grid: multiples of 64 samples (envelope.h). */
      const double gap = 64.0 * ds, s_min = -gap * ceil(3.0 / gap), s_max = -s_min;
      CHECK(fb_envelope_road_new(roads[r], models[k], p.bytes, &ctx, s_min, s_max, &env,
                                 &err) == FB_OK);
      const size_t n = (size_t)floor((s_max - s_min) / ds);
      double *w = malloc(2 * n * sizeof *w), lo = INFINITY, hi = -INFINITY, worst = 0.0;
      /* The tolerance is of both tracks' range. */
      for (int track = 0; track < FB_ROAD_NTRACKS; ++track)
        CHECK(fb_envelope_sample(roads[r], track, models[k], p.bytes, &ctx, s_min, ds, n,
                                 w + (size_t)track * n, NULL, &err) == FB_OK);
      for (size_t i = 0; i < 2 * n; ++i) {
        lo = fmin(lo, w[i]);
        hi = fmax(hi, w[i]);
        const int track = i < n ? 0 : 1;
        const double si = s_min + (double)(i % n) * ds;
        worst = fmax(worst, fabs(fb_road_height(env, track, si) - w[i]));
      }
      printf("%s profile over the %s: max |profile - samples| = %.3e m (%.2e of its range)\n",
             models[k]->name, r ? "random road" : "step", worst, worst / (hi - lo));
      CHECK(worst <= 2e-3 * (hi - lo));
      free(w);
      fb_road_free(&env);
    }
  fb_road_free(&roads[0]);
  fb_road_free(&roads[1]);
}

/* ---- The models' own rules. */

static void test_checks(void)
{
  fb_envelope_context ctx = tire_context();
  fb_err err = {0};
  fb_envelope_params p;
  fb_envelope_params_init(&fb_envelope_model_cams, &p);
  ctx.static_deflection = 0.0; /* no contact length to be had */
  CHECK(fb_envelope_model_cams.ops->check(p.bytes, &ctx, &err) == FB_EINVAL);
  CHECK(!strcmp(err.part.field, "contact_length"));
  ((fb_envelope_cams_params *)(void *)p.bytes)->contact_length = 2.0;
  CHECK(fb_envelope_model_cams.ops->check(p.bytes, &ctx, &err) == FB_EINVAL);
  ((fb_envelope_cams_params *)(void *)p.bytes)->contact_length = 0.2;
  CHECK(fb_envelope_model_cams.ops->check(p.bytes, &ctx, &err) == FB_OK);
  ctx.radius = 0.0;
  CHECK(fb_envelope_model_cams.ops->check(p.bytes, &ctx, &err) == FB_EINVAL);
  ctx = tire_context();
  fb_envelope_params_init(&fb_envelope_model_overlap, &p);
  ((fb_envelope_overlap_params *)(void *)p.bytes)->deflection = 0.6;
  CHECK(fb_envelope_model_overlap.ops->check(p.bytes, &ctx, &err) == FB_EINVAL);
  CHECK(!strcmp(err.part.field, "deflection"));
  fb_road *road = flat_road(0.0), *env = NULL;
  CHECK(fb_envelope_road_new(road, &fb_envelope_model_overlap, p.bytes, &ctx, 0.0, 1.0, &env,
                             &err) == FB_EINVAL);
  CHECK(env == NULL);
  CHECK(fb_envelope_road_new(road, &fb_envelope_model_point, NULL, &ctx, 1.0, 0.0, &env,
                             &err) == FB_EINVAL);
  fb_road_free(&road);
}

/* ---- The program's model in a scenario: the 6x6 with every tire
 * averaging the road (`wheel.envelope: mean`), loaded with a gallery that
 * holds it; its parameter generated as a key, its error located there. */

static int load_mean(const char *half, const fb_envelope_gallery *g, fb_scenario **out,
                     fb_err *err)
{
  char text[200];
  snprintf(text, sizeof text, "\n  radius: 0.55\n  envelope: mean\n  mean: {half: %s}", half);
  const fb_scenario_load_opts o = {.envelopes = g};
  return load_replaced_with("  tire_c: 140000", strlen("  tire_c: 140000"), "\n", text, &o, out,
                            err);
}

static void test_program_model_in_scenario(void)
{
  fb_envelope_gallery *g = NULL;
  fb_err err = {0};
  CHECK(fb_envelope_gallery_new(&g, &err) == FB_OK);
  CHECK(fb_envelope_gallery_add(g, &mean_model, &err) == FB_OK);
  fb_scenario *s = NULL;
  CHECK(load_mean("0.2", g, &s, &err) == FB_OK);
  for (size_t c = 0; s && c < s->ncorners; ++c) {
    CHECK(fb_corner_envelope_model(&s->corner[c]) == &mean_model);
    CHECK(((const mean_params *)(const void *)s->corner[c].envelope.bytes)->half == 0.2);
    CHECK(s->corner[c].tire_radius == 0.55);
  }
  if (s)
    CHECK(fb_scenario_check(s, &err) == FB_OK);
  fb_scenario_free(&s);
  /* Without the gallery the choice is unknown, and a bad half refused at
   * its key. */
  CHECK(load_mean("0.2", NULL, NULL, &err) != FB_OK);
  check_message(&err, "bad.yaml:92:3: wheel.mean: unknown key 'mean'");
  CHECK(load_mean("-1", g, NULL, &err) != FB_OK);
  check_message(&err, "bad.yaml:92:16: wheel.mean.half: must be > 0 m (got -1)");
  fb_envelope_gallery_free(&g);
}

int main(void)
{
  test_gallery();
  test_point();
  test_cams_step();
  test_overlap_step(DEFL, "static deflection");
  test_overlap_step(1e-6, "rigid ring");
  test_cams_random();
  test_long_wave();
  test_cost();
  test_profile();
  test_checks();
  test_program_model_in_scenario();
  return check_report("test_envelope");
}
