/* SPDX-License-Identifier: BSD-3-Clause */
/* The obstacle road types (docs/roads.md, "Obstacles") and the piecewise
 * tracks they are made of (fb_road_new_pieces): each shape's height and
 * slope against its closed-form geometry written here (circles, lines,
 * sines), the slope integrating to the height change between breaks,
 * the edges a point-contact tire cannot follow, the oblique placement
 * (the bump's formula), track selection, series, a course of obstacles
 * from a file, and the piecewise track's wheel functions as data and
 * back. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "flexbond/road.h"

#include "check.h"
#include "tmpdir.h"

static const double PI = 3.14159265358979323846;

/* A layout like the paper's vehicle's: 10 km/h, track 2.1 m, the first
 * corner at (1.9, 1.05). */
static const fb_road_layout LAYOUT = {10.0 / 3.6, 2.1, 1.9, 1.05};

/* A block of type t with its declared defaults, perpendicular (angle 0),
 * first contact at 1 s. */
static fb_road_obstacle_params *block(const fb_road_type *t, fb_road_params *p)
{
  fb_road_params_init(t, p);
  fb_road_obstacle_params *o = (fb_road_obstacle_params *)(void *)p->bytes;
  o->first_contact = 1.0;
  return o;
}

/* t's road for block p, checked as the vehicle checks it (declared
 * ranges, then the type's rules); NULL (and a failed check) if refused. */
static fb_road *make(const fb_road_type *t, const fb_road_params *p)
{
  fb_err err;
  fb_road *road = NULL;
  int rc = fb_params_check(t->param, t->nparams, p->bytes, &err);
  if (!rc && t->ops->check)
    rc = t->ops->check(p->bytes, &LAYOUT, &err);
  if (!rc)
    rc = t->ops->make(p->bytes, &LAYOUT, &road, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  %s: %s\n", t->name, err.msg);
  return road;
}

/* ---- The slope integrates to the height change between breaks. */

/* The slope's integral over [a, b] by two-point Gauss-Legendre after
 * s = a + (b - a)(1 - cos th) / 2, th in [0, pi]: ds = (b - a) sin th / 2
 * cancels the 1 / sqrt(distance) of an arc's slope at a vertical
 * tangent at either end, leaving a smooth integrand; on 1e-3 rad steps
 * the rule (error O(h^4) times the integrand's fourth derivative) is
 * good to far better than the 1e-9 m checked. */
static double slope_integral(const fb_road *road, int track, double a, double b)
{
  const double g = 0.5 / sqrt(3.0);
  const int n = (int)ceil(PI / 1e-3);
  const double h = PI / n, half = 0.5 * (b - a);
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double mid = (k + 0.5) * h;
    for (int side = -1; side <= 1; side += 2) {
      const double th = mid + side * g * h;
      sum += 0.5 * h * fb_road_slope(road, track, a + half * (1.0 - cos(th))) * half * sin(th);
    }
  }
  return sum;
}

/* Between each two breaks the slope integrates to the height's change
 * from the first (the piece that begins there holds) to just before the
 * second (the left limit, one ulp before it: within sqrt(2 R ulp) < 1e-8
 * m of it at an arc's vertical tangent, exact on lines and waves). */
static void check_slope_integral(const fb_road *road, const char *what)
{
  enum { MAX_BREAKS = 64 };
  for (int track = 0; track < FB_ROAD_NTRACKS; ++track) {
    double br[MAX_BREAKS];
    const size_t n = fb_road_breaks(road, track, br, MAX_BREAKS);
    CHECK(n <= MAX_BREAKS);
    double worst = 0.0;
    for (size_t i = 0; i + 1 < n && i + 1 < MAX_BREAKS; ++i) {
      const double a = br[i], b = br[i + 1];
      const double change =
          fb_road_height(road, track, nextafter(b, -INFINITY)) - fb_road_height(road, track, a);
      worst = fmax(worst, fabs(slope_integral(road, track, a, b) - change));
    }
    CHECK(worst < 1e-8);
    if (worst >= 1e-8)
      fprintf(stderr, "  %s track %d: slope integral off by %g m\n", what, track, worst);
  }
}

/* The road's edges on both tracks are exactly want[0 .. n). */
static void check_edges(const fb_road *road, const double *want, size_t n, const char *what)
{
  for (int track = 0; track < FB_ROAD_NTRACKS; ++track) {
    double s[8];
    const size_t got = fb_road_edges(road, track, s, 8);
    CHECK(got == n);
    for (size_t i = 0; i < got && i < n; ++i)
      CHECK_NEAR(s[i], want[i], 1e-15);
    if (got != n)
      fprintf(stderr, "  %s track %d: %zu edges, want %zu\n", what, track, got, n);
  }
}

/* ---- Each shape against its geometry. */

/* A half circle of radius h on [0, 2 h]: z = sqrt(h^2 - (s - h)^2),
 * slope -(s - h) / z, infinite at the base (edges at 0 and 2 h). */
static void test_halfround(void)
{
  fb_road_params p;
  const double h = 0.2;
  block(&fb_road_type_halfround, &p)->height = h;
  fb_road *road = make(&fb_road_type_halfround, &p);
  if (!road)
    return;
  for (double s = -0.5; s < 1.0; s += 0.0123) {
    const double inside = s > 0 && s < 2 * h;
    const double z = inside ? sqrt(h * h - (s - h) * (s - h)) : 0.0;
    for (int track = 0; track < FB_ROAD_NTRACKS; ++track) {
      CHECK_NEAR(fb_road_height(road, track, s), z, 1e-15);
      CHECK_NEAR(fb_road_slope(road, track, s), inside ? -(s - h) / z : 0.0, 1e-12);
    }
  }
  CHECK(isinf(fb_road_slope(road, FB_ROAD_LEFT, 0.0)));
  check_edges(road, (const double[]){0.0, 2 * h}, 2, "halfround");
  check_slope_integral(road, "halfround");
  char phrase[96];
  fb_road_phrase(&fb_road_type_halfround, &p, phrase, sizeof phrase);
  CHECK(!strcmp(phrase, "over a 0.2 m half-round"));
  fb_road_free(&road);
}

/* A line from 0 to h over the ramp r, then h for good; r = 0: a face at
 * 0, the road's one edge. Down (h < 0) alike. */
static void test_step(void)
{
  static const double heights[] = {0.15, -0.1}, ramps[] = {0.3, 0.0};
  for (size_t i = 0; i < 2; ++i)
    for (size_t j = 0; j < 2; ++j) {
      fb_road_params p;
      fb_road_obstacle_params *o = block(&fb_road_type_step, &p);
      const double h = heights[i], r = ramps[j];
      o->height = h;
      o->ramp_length = r;
      fb_road *road = make(&fb_road_type_step, &p);
      if (!road)
        continue;
      for (double s = -1; s < 2; s += 0.01) {
        const double z = s < 0 ? 0.0 : s < r ? h * s / r : h;
        CHECK_NEAR(fb_road_height(road, FB_ROAD_RIGHT, s), z, 1e-15);
        CHECK_NEAR(fb_road_slope(road, FB_ROAD_RIGHT, s), s >= 0 && s < r ? h / r : 0.0, 1e-15);
      }
      CHECK(fb_road_height(road, FB_ROAD_LEFT, 0.0) == (r > 0 ? 0.0 : h));
      check_edges(road, (const double[]){0.0}, r > 0 ? 0 : 1, "step");
      check_slope_integral(road, "step");
      fb_road_free(&road);
    }
}

/* The distance from (u, z) to the line through the origin rising h over
 * r (h u - r z = 0). */
static double to_ramp(double u, double z, double h, double r)
{
  return fabs(h * u - r * z) / hypot(h, r);
}

/* A cleat of height h, top L and chamfers r with rounded edges of radius
 * e: its pieces meet at breaks b0 = 0 (ramp), b1 (arc), b2 (top), b3
 * (arc), b4 (ramp down), b5 = 2 r + L. Each arc's centre lies e below
 * the top, above the top's end it touches (b2, b4 - ...), and e from
 * its ramp's line; its points are e from the centre; the height and the
 * slope are continuous at every joint (no edges). */
static void test_cleat(void)
{
  fb_road_params p;
  fb_road_obstacle_params *o = block(&fb_road_type_cleat, &p);
  const double h = 0.05, len = 0.2, r = 0.04, e = 0.01;
  o->height = h;
  o->length = len;
  o->ramp_length = r;
  o->edge_radius = e;
  fb_road *road = make(&fb_road_type_cleat, &p);
  if (!road)
    return;
  double b[8];
  CHECK(fb_road_breaks(road, FB_ROAD_LEFT, b, 8) == 8); /* lead-in, 5 pieces, lead-out */
  const double *k = b + 1;                              /* the cleat's joints k[0 .. 5] */
  CHECK(k[0] == 0.0 && fabs(k[5] - (2 * r + len)) < 1e-15);
  const double c1 = k[2], c2 = k[3], cz = h - e; /* the arcs' centres' s, and their z */
  CHECK_NEAR(to_ramp(c1, cz, h, r), e, 1e-15);
  /* The down ramp's line, mirrored about the cleat's middle. */
  CHECK_NEAR(to_ramp(2 * r + len - c2, cz, h, r), e, 1e-15);
  for (double s = -0.1; s < 0.4; s += 0.0005) {
    const double z = fb_road_height(road, FB_ROAD_LEFT, s);
    double want = 0.0, slope = 0.0; /* a circle's slope: -(s - c) / (z - cz) */
    if (s >= k[0] && s < k[1])
      want = h * s / r, slope = h / r;
    else if (s >= k[1] && s < k[2])
      want = cz + sqrt(e * e - (s - c1) * (s - c1)), slope = -(s - c1) / (want - cz);
    else if (s >= k[2] && s < k[3])
      want = h;
    else if (s >= k[3] && s < k[4])
      want = cz + sqrt(e * e - (s - c2) * (s - c2)), slope = -(s - c2) / (want - cz);
    else if (s >= k[4] && s < k[5])
      want = h * (2 * r + len - s) / r, slope = -h / r;
    CHECK_NEAR(z, want, 1e-15);
    CHECK_NEAR(fb_road_slope(road, FB_ROAD_LEFT, s), slope, 1e-12);
  }
  for (int i = 1; i < 5; ++i) {
    const double before = nextafter(k[i], -INFINITY);
    CHECK_NEAR(fb_road_height(road, FB_ROAD_LEFT, before), fb_road_height(road, 0, k[i]),
               1e-15);
    CHECK_NEAR(fb_road_slope(road, FB_ROAD_LEFT, before), fb_road_slope(road, 0, k[i]), 1e-9);
  }
  check_edges(road, NULL, 0, "cleat");
  check_slope_integral(road, "cleat");
  fb_road_free(&road);
  /* Vertical faces: jumps at both ends, and the rounded edge's arc
   * begins at its vertical tangent h - e up the face. */
  o->ramp_length = 0.0;
  road = make(&fb_road_type_cleat, &p);
  if (!road)
    return;
  check_edges(road, (const double[]){0.0, len}, 2, "cleat with faces");
  CHECK_NEAR(fb_road_height(road, FB_ROAD_LEFT, 0.0), h - e, 1e-15);
  CHECK_NEAR(fb_road_height(road, FB_ROAD_LEFT, 0.5 * len), h, 1e-15);
  check_slope_integral(road, "cleat with faces");
  fb_road_free(&road);
}

/* Ramps at 30 deg: z = s tan(30 deg) up to h, h over the top, down over
 * ramp_down. */
static void test_trapezoid(void)
{
  fb_road_params p;
  fb_road_obstacle_params *o = block(&fb_road_type_trapezoid, &p);
  const double h = 0.1, top = 0.5, down = 0.8, slope = tan(30 * PI / 180), up = h / slope;
  o->height = h;
  o->length = top;
  o->ramp_angle = 30 * PI / 180;
  fb_road *road = make(&fb_road_type_trapezoid, &p);
  for (double s = -0.5; road && s < 2; s += 0.01) {
    const double z = s < 0              ? 0.0
                     : s < up           ? s * slope
                     : s < up + top     ? h
                     : s < 2 * up + top ? h - (s - up - top) * slope
                                        : 0.0;
    const double dz = s < 0              ? 0.0
                      : s < up           ? slope
                      : s < up + top     ? 0.0
                      : s < 2 * up + top ? -slope
                                         : 0.0;
    CHECK_NEAR(fb_road_height(road, FB_ROAD_LEFT, s), z, 1e-15);
    CHECK_NEAR(fb_road_slope(road, FB_ROAD_LEFT, s), dz, 1e-15);
  }
  if (road)
    check_slope_integral(road, "trapezoid");
  fb_road_free(&road);
  /* Lengths instead, the down ramp its own. */
  o->ramp_angle = NAN;
  o->ramp_length = up;
  o->ramp_down = down;
  road = make(&fb_road_type_trapezoid, &p);
  for (double s = up + top; road && s < up + top + down; s += 0.01)
    CHECK_NEAR(fb_road_height(road, FB_ROAD_RIGHT, s), h * (1 - (s - up - top) / down), 1e-15);
  if (road)
    check_edges(road, NULL, 0, "trapezoid");
  fb_road_free(&road);
}

/* Rounded: the circle through the rims (0, 0), (L, 0) and the bottom
 * (L / 2, -d), of radius R = (L^2 / 4 + d^2) / (2 d) (the chord and its
 * sagitta). Rectangular: -d between two walls (edges). */
static void test_pothole(void)
{
  fb_road_params p;
  fb_road_obstacle_params *o = block(&fb_road_type_pothole, &p);
  const double d = 0.08, len = 0.6, radius = (len * len / 4 + d * d) / (2 * d);
  o->depth = d;
  o->length = len;
  fb_road *road = make(&fb_road_type_pothole, &p);
  if (!road)
    return;
  CHECK_NEAR(fb_road_height(road, FB_ROAD_LEFT, 0.5 * len), -d, 1e-15);
  for (double s = 0.001; s < len; s += 0.01) {
    const double z = fb_road_height(road, FB_ROAD_LEFT, s), x = s - 0.5 * len;
    CHECK_NEAR(hypot(x, z - (radius - d)), radius, 1e-14);
    /* The lower circle's slope, x / sqrt(R^2 - x^2). */
    CHECK_NEAR(fb_road_slope(road, FB_ROAD_LEFT, s), x / sqrt(radius * radius - x * x), 1e-13);
  }
  check_edges(road, NULL, 0, "rounded pothole");
  check_slope_integral(road, "rounded pothole");
  fb_road_free(&road);
  o->shape = 0; /* rectangular */
  road = make(&fb_road_type_pothole, &p);
  if (!road)
    return;
  CHECK(fb_road_height(road, FB_ROAD_LEFT, 0.0) == -d && fb_road_height(road, 0, len) == 0);
  check_edges(road, (const double[]){0.0, len}, 2, "rectangular pothole");
  check_slope_integral(road, "rectangular pothole");
  fb_road_free(&road);
}

/* z = A(s) sin(2 pi s / lambda), A rising linearly over the first
 * ramp wave to a, falling over the last. */
static void test_washboard(void)
{
  fb_road_params p;
  fb_road_obstacle_params *o = block(&fb_road_type_washboard, &p);
  const double a = 0.02, lambda = 0.7;
  o->amplitude = a;
  o->wavelength = lambda;
  o->waves = 4;
  o->ramp_waves = 1;
  fb_road *road = make(&fb_road_type_washboard, &p);
  if (!road)
    return;
  const double end = 6 * lambda;
  for (double s = -0.5; s < end + 0.5; s += 0.0071) {
    const double amp = s < 0 || s > end ? 0.0
                       : s < lambda     ? a * s / lambda
                       : s < 5 * lambda ? a
                                        : a * (end - s) / lambda;
    const double damp = s < 0 || s > end ? 0.0
                        : s < lambda     ? a / lambda
                        : s < 5 * lambda ? 0.0
                                         : -a / lambda;
    const double k = 2 * PI / lambda;
    CHECK_NEAR(fb_road_height(road, FB_ROAD_LEFT, s), amp * sin(k * s), 1e-15);
    CHECK_NEAR(fb_road_slope(road, FB_ROAD_LEFT, s), damp * sin(k * s) + amp * k * cos(k * s),
               1e-13);
  }
  check_edges(road, NULL, 0, "washboard");
  check_slope_integral(road, "washboard");
  CHECK_NEAR(fb_road_type_washboard.ops->top_hz(&p, 1.4), 2 * 1.4 / lambda, 1e-15);
  fb_road_free(&road);
}

/* ---- Placement, tracks, series. */

/* The wheels start where the bump with the same angle and first contact
 * puts them, by the data sheet's formula written here; the right track's
 * obstacle begins track_width tan(angle) along. */
static void test_oblique(void)
{
  fb_road_params p, b;
  fb_road_obstacle_params *o = block(&fb_road_type_cleat, &p);
  o->height = 0.05;
  o->length = 0.3;
  o->angle = 25 * PI / 180;
  o->first_contact = 2.5;
  fb_road_params_init(&fb_road_type_bump, &b);
  fb_road_bump_params *bump = (fb_road_bump_params *)(void *)b.bytes;
  bump->angle = o->angle;
  bump->first_contact = o->first_contact;
  const fb_road_layout *l = &LAYOUT;
  const double xs[] = {1.9, 0.4, -1.0}, ys[] = {1.05, -1.05};
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 2; ++j) {
      const double x = xs[i], y = ys[j], t = tan(o->angle);
      const double edge = y > 0 ? 0.0 : l->track_width * t;
      const double entry = 2.5 + ((l->first_x - x) + (l->first_y - y) * t) / l->speed;
      const double s0 = fb_road_type_cleat.ops->wheel_start(&p, l, x, y);
      CHECK_NEAR(s0, edge - l->speed * entry, 1e-12);
      CHECK(s0 == fb_road_type_bump.ops->wheel_start(&b, l, x, y));
    }
  double begin, end;
  fb_road_type_cleat.ops->feature(&p, l, FB_ROAD_RIGHT, &begin, &end);
  CHECK_NEAR(begin, 2.1 * tan(o->angle), 1e-15);
  CHECK_NEAR(end - begin, 0.3 + 2 * o->ramp_length, 1e-15);
  fb_road *road = make(&fb_road_type_cleat, &p);
  for (double s = -1; road && s < 2; s += 0.01)
    CHECK_NEAR(fb_road_height(road, FB_ROAD_RIGHT, s + begin), fb_road_height(road, 0, s),
               1e-14); /* s + begin rounded: 4e-16 m on slopes up to 2.5 */
  fb_road_free(&road);
}

/* One track carries the obstacle, the other is flat (no edges, no
 * feature); the phrase says which. */
static void test_tracks(void)
{
  for (int which = 1; which <= 2; ++which) {
    fb_road_params p;
    fb_road_obstacle_params *o = block(&fb_road_type_halfround, &p);
    o->height = 0.1;
    o->track = which; /* left, right */
    fb_road *road = make(&fb_road_type_halfround, &p);
    if (!road)
      continue;
    const int on = which == 1 ? FB_ROAD_LEFT : FB_ROAD_RIGHT, off = 1 - on;
    CHECK_NEAR(fb_road_height(road, on, 0.1), 0.1, 1e-15);
    for (double s = -1; s < 2; s += 0.01)
      CHECK(fb_road_height(road, off, s) == 0.0 && fb_road_slope(road, off, s) == 0.0);
    CHECK(fb_road_edges(road, on, NULL, 0) == 2 && fb_road_edges(road, off, NULL, 0) == 0);
    double begin, end;
    fb_road_type_halfround.ops->feature(&p, &LAYOUT, off, &begin, &end);
    CHECK(begin == end);
    char phrase[96];
    fb_road_phrase(&fb_road_type_halfround, &p, phrase, sizeof phrase);
    CHECK(strstr(phrase, which == 1 ? "on the left track" : "on the right track"));
    fb_road_free(&road);
  }
}

/* count steps up, spacing apart: a staircase, k h after the k-th; three
 * cleats: the same cleat again every spacing. */
static void test_series(void)
{
  fb_road_params p;
  fb_road_obstacle_params *o = block(&fb_road_type_step, &p);
  o->height = 0.05;
  o->ramp_length = 0.1;
  o->count = 3;
  o->spacing = 0.5;
  fb_road *road = make(&fb_road_type_step, &p);
  for (int k = 0; road && k < 3; ++k) {
    CHECK_NEAR(fb_road_height(road, FB_ROAD_LEFT, 0.5 * k + 0.05), 0.05 * k + 0.025, 1e-15);
    CHECK_NEAR(fb_road_height(road, FB_ROAD_LEFT, 0.5 * k + 0.3), 0.05 * (k + 1), 1e-15);
  }
  if (road)
    check_slope_integral(road, "staircase");
  fb_road_free(&road);
  /* Overlapping obstacles are refused at spacing. */
  fb_err err;
  o->spacing = 0.05;
  CHECK(fb_road_type_step.ops->check(&p, &LAYOUT, &err) == FB_EINVAL &&
        !strcmp(err.part.field, "spacing"));
  o->spacing = NAN;
  CHECK(fb_road_type_step.ops->check(&p, &LAYOUT, &err) == FB_EINVAL &&
        !strcmp(err.part.field, "spacing"));
  fb_road_obstacle_params *c = block(&fb_road_type_cleat, &p);
  c->height = 0.04;
  c->length = 0.1;
  c->count = 3;
  c->spacing = 1.25;
  road = make(&fb_road_type_cleat, &p);
  for (double s = -0.2; road && s < 1.2; s += 0.01)
    for (int k = 1; k < 3; ++k)
      CHECK_NEAR(fb_road_height(road, FB_ROAD_LEFT, s + 1.25 * k),
                 fb_road_height(road, FB_ROAD_LEFT, s), 1e-15);
  fb_road_free(&road);
}

/* ---- Bad values: the type's rules, at their parameters. */

static void test_rules(void)
{
  fb_err err;
  fb_road_params p;
  fb_road_obstacle_params *o = block(&fb_road_type_pothole, &p);
  o->depth = 0.4;
  o->length = 0.6; /* deeper than half its length, rounded */
  CHECK(fb_road_type_pothole.ops->check(&p, &LAYOUT, &err) == FB_EINVAL &&
        !strcmp(err.part.field, "depth"));
  o = block(&fb_road_type_cleat, &p);
  o->height = 0.05;
  o->length = 0.01;
  o->edge_radius = 0.04; /* its tangents need more top than 1 cm */
  CHECK(fb_road_type_cleat.ops->check(&p, &LAYOUT, &err) == FB_EINVAL &&
        !strcmp(err.part.field, "edge_radius"));
  o = block(&fb_road_type_trapezoid, &p);
  o->height = 0.1;
  o->length = 0.5;
  CHECK(fb_road_type_trapezoid.ops->check(&p, &LAYOUT, &err) == FB_EINVAL &&
        !strcmp(err.part.field, "ramp_length"));
  o->ramp_length = 0.2;
  o->ramp_angle = 0.3;
  CHECK(fb_road_type_trapezoid.ops->check(&p, &LAYOUT, &err) == FB_EINVAL &&
        !strcmp(err.part.field, "ramp_angle_deg"));
  o = block(&fb_road_type_step, &p);
  o->height = 0.0;
  CHECK(fb_road_type_step.ops->check(&p, &LAYOUT, &err) == FB_EINVAL &&
        !strcmp(err.part.field, "height"));
}

/* ---- A course from a file. */

/* A course file at path with the given text. */
static void write_course(const char *path, const char *text)
{
  FILE *fp = fopen(path, "w");
  CHECK(fp != NULL);
  if (fp) {
    fputs(text, fp);
    fclose(fp);
  }
}

/* The course's block for file path, prepared; FB_OK or its error. */
static int course_block(char *path, double angle, fb_road_params *p, fb_err *err)
{
  fb_road_params_init(&fb_road_type_course, p);
  fb_road_course_params *c = (fb_road_course_params *)(void *)p->bytes;
  c->file = path; /* borrowed: released by the caller's own release below */
  c->angle = angle;
  c->first_contact = 1.0;
  return fb_road_type_course.ops->prepare(p->bytes, err);
}

/* The course's release frees file; the test's path is its own. */
static void course_release(fb_road_params *p)
{
  ((fb_road_course_params *)(void *)p->bytes)->file = NULL;
  fb_road_params_release(&fb_road_type_course, p);
}

/* Each obstacle of a course is the one its type makes alone, moved to
 * its distance along the course (on the right track, by the oblique
 * edge as well) and up by the steps before it. */
static void test_course(void)
{
  char path[TEST_PATH_MAX];
  test_tmp_path("course.txt", path, sizeof path);
  write_course(path, "# a course\n"
                     "cleat at=0 height=0.05 length=0.2 edge_radius=0.01  # both tracks\n"
                     "\n"
                     "step at=2 height=0.1 ramp_length=0.3 track=left\n"
                     "pothole at=4 depth=0.06 length=0.6 track=right\n"
                     "washboard at=6 amplitude=0.01 wavelength=0.5 waves=2\n");
  fb_err err;
  fb_road_params p;
  const double angle = 20 * PI / 180;
  CHECK(course_block(path, angle, &p, &err) == FB_OK);
  fb_road *road = NULL;
  CHECK(fb_road_type_course.ops->make(p.bytes, &LAYOUT, &road, &err) == FB_OK);
  if (!road) {
    fprintf(stderr, "  course: %s\n", err.msg);
    course_release(&p);
    return;
  }
  /* The obstacles alone, square, on both tracks. */
  fb_road_params one[4];
  fb_road *alone[4] = {NULL};
  const fb_road_type *types[4] = {&fb_road_type_cleat, &fb_road_type_step,
                                  &fb_road_type_pothole, &fb_road_type_washboard};
  fb_road_obstacle_params *o[4];
  for (int i = 0; i < 4; ++i)
    o[i] = block(types[i], &one[i]);
  o[0]->height = 0.05, o[0]->length = 0.2, o[0]->edge_radius = 0.01;
  o[1]->height = 0.1, o[1]->ramp_length = 0.3;
  o[2]->depth = 0.06, o[2]->length = 0.6;
  o[3]->amplitude = 0.01, o[3]->wavelength = 0.5, o[3]->waves = 2;
  for (int i = 0; i < 4; ++i)
    alone[i] = make(types[i], &one[i]);
  const double at[4] = {0, 2, 4, 6}, ends[4] = {0.24, 0.3, 0.6, 2.0};
  const double shift = LAYOUT.track_width * tan(angle);
  for (int i = 0; i < 4 && alone[3]; ++i)
    for (double u = 0.001; u < ends[i]; u += 0.01) {
      const int on_left = i != 2, on_right = i != 1;
      /* The step on the left raises what follows it there by 0.1 m. */
      const double left = fb_road_height(road, FB_ROAD_LEFT, at[i] + u);
      const double right = fb_road_height(road, FB_ROAD_RIGHT, shift + at[i] + u);
      const double z = fb_road_height(alone[i], FB_ROAD_LEFT, u);
      CHECK_NEAR(left, on_left ? z + (i == 3 ? 0.1 : 0.0) : (i == 2 ? 0.1 : 0.0), 1e-14);
      CHECK_NEAR(right, on_right ? z : 0.0, 1e-14);
    }
  check_slope_integral(road, "course");
  double begin, end;
  fb_road_type_course.ops->feature(p.bytes, &LAYOUT, FB_ROAD_RIGHT, &begin, &end);
  CHECK_NEAR(begin, shift, 1e-15);
  CHECK_NEAR(end, shift + 6 + 2.0, 1e-12);
  CHECK(fb_road_edges(road, FB_ROAD_LEFT, NULL, 0) == 0);
  CHECK(fb_road_type_course.ops->edge_hint(p.bytes) == NULL);
  char phrase[64];
  fb_road_phrase(&fb_road_type_course, &p, phrase, sizeof phrase);
  CHECK(!strcmp(phrase, "over a course of 4 obstacles"));
  for (int i = 0; i < 4; ++i)
    fb_road_free(&alone[i]);
  fb_road_free(&road);
  course_release(&p);
}

/* A vertical step has no length but is part of the course: a course
 * that ends with one ends at its face, one that begins with one begins
 * there; a track without obstacles is an empty stretch at the edge. */
static void test_course_faces(void)
{
  static const struct {
    const char *text;
    double begin, end; /* left track, square crossing */
  } cases[] = {
      {"halfround at=0 height=0.05\nstep at=60 height=0.15 ramp_length=0\n", 0.0, 60.0},
      {"step at=5 height=0.1 ramp_length=0\nhalfround at=20 height=0.1\n", 5.0, 20.2},
      {"step at=7 height=0.1 ramp_length=0\n", 7.0, 7.0},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    char path[TEST_PATH_MAX];
    test_tmp_path("faces.txt", path, sizeof path);
    write_course(path, cases[i].text);
    fb_err err;
    fb_road_params p;
    CHECK(course_block(path, 0.0, &p, &err) == FB_OK);
    double begin = NAN, end = NAN;
    fb_road_type_course.ops->feature(p.bytes, &LAYOUT, FB_ROAD_LEFT, &begin, &end);
    CHECK_NEAR(begin, cases[i].begin, 1e-12);
    CHECK_NEAR(end, cases[i].end, 1e-12);
    course_release(&p);
  }
  char path[TEST_PATH_MAX];
  test_tmp_path("faces.txt", path, sizeof path);
  write_course(path, "step at=3 height=0.1 ramp_length=0 track=left\n");
  fb_err err;
  fb_road_params p;
  CHECK(course_block(path, 0.0, &p, &err) == FB_OK);
  double begin = NAN, end = NAN;
  fb_road_type_course.ops->feature(p.bytes, &LAYOUT, FB_ROAD_RIGHT, &begin, &end);
  CHECK(begin == 0.0 && end == 0.0);
  course_release(&p);
}

/* A bad line is refused at its line, naming what is wrong; obstacles
 * that overlap on a track are refused when the road is made. */
static void test_course_errors(void)
{
  static const struct {
    const char *text, *want;
  } bad[] = {
      {"cleat at=0 height=0.05 length=0.2\nbarrel at=3\n", ":2: 'barrel' is no obstacle type"},
      {"cleat height=0.05 length=0.2\n", ":1: the cleat needs its distance along the course"},
      {"cleat at=0 length=0.2\n", ":1: the cleat needs its height"},
      {"cleat at=0 height=-1 length=0.2\n", ":1: height: must be > 0 m (got -1)"},
      {"cleat at=0 height=0.05 length=0.2 colour=red\n",
       ":1: a cleat has no parameter 'colour'"},
      {"cleat at=0 height=0.05 length=0.2 angle_deg=3\n", ":1: angle_deg is the course's own"},
      {"pothole at=0 depth=0.5 length=0.6\n", ":1: depth: a rounded pothole's walls"},
      {"pothole at=0 depth=0.05 length=0.6 shape=square\n", ":1: shape: not one of its"},
      {"step at=5 height=0.1\nstep at=2 height=0.1\n", ":2: the obstacles are listed in order"},
      {"halfround at=0 height=0.1 height=0.2\n", ":1: height is given twice"},
      {"halfround at=0 at=1 height=0.1\n", ":1: at is given twice"},
      {"# nothing\n", ": no obstacles"},
  };
  char path[TEST_PATH_MAX];
  test_tmp_path("bad_course.txt", path, sizeof path);
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    write_course(path, bad[i].text);
    fb_err err;
    fb_road_params p;
    const int rc = course_block(path, 0.0, &p, &err);
    const int found = rc != FB_OK && strstr(err.msg, bad[i].want) && strstr(err.msg, path) &&
                      !strcmp(err.part.field, "file");
    CHECK(found);
    if (!found)
      fprintf(stderr, "  got \"%s\", want \"%s\"\n", err.msg, bad[i].want);
    course_release(&p);
  }
  write_course(path, "cleat at=0 height=0.05 length=0.5 ramp_length=0\n"
                     "cleat at=0.3 height=0.05 length=0.5 track=left\n");
  fb_err err;
  fb_road_params p;
  fb_road *road = NULL;
  CHECK(course_block(path, 0.0, &p, &err) == FB_OK);
  CHECK(fb_road_type_course.ops->make(p.bytes, &LAYOUT, &road, &err) == FB_EINVAL &&
        strstr(err.msg, ":2: the cleat at 0.3 m overlaps the obstacle before it on the left"));
  /* The first cleat's faces: the course's hint names its line. */
  const char *hint = fb_road_type_course.ops->edge_hint(p.bytes);
  CHECK(hint && strstr(hint, ":1: the cleat's vertical faces"));
  course_release(&p);
}

/* ---- Piecewise tracks as data: pieces of every kind, with a jump. */

static void test_pieces_data(void)
{
  const fb_road_piece left[] = {
      {FB_ROAD_PIECE_LINE, -1.0, 0.0, {0.0, 0.0, 0, 0, 0}},
      {FB_ROAD_PIECE_ARC, 0.0, 0.3, {0.15, 0.0, 0.15, 0, 0}},
      {FB_ROAD_PIECE_LINE, 0.3, 0.5, {0.02, 0.1, 0, 0, 0}}, /* a jump up at 0.3 */
      {FB_ROAD_PIECE_WAVE, 0.5, 1.5, {0.04 - 0.01 * cos(0.3), 0.01, 0.02, 6.0, 0.3}}};
  fb_err err;
  fb_road *road = NULL;
  CHECK(fb_road_new_pieces(4, left, 0, NULL, &road, &err) == FB_OK);
  if (!road)
    return;
  double e[4];
  CHECK(fb_road_edges(road, FB_ROAD_RIGHT, e, 4) == 0); /* a flat track */
  const size_t n = fb_road_edges(road, FB_ROAD_LEFT, e, 4);
  CHECK(n == 2 && e[0] == 0.0 && e[1] == 0.3);
  for (size_t i = 0; i < n && n != 2; ++i)
    fprintf(stderr, "  edge %zu at %g\n", i, e[i]);
  CHECK_NEAR(fb_road_height(road, FB_ROAD_LEFT, 2.0), left[3].p[0] + 0.03 * cos(6.0 + 0.3),
             1e-15); /* held at the last piece's end */
  fb_tfun *f = NULL, *g = NULL;
  CHECK(fb_road_wheel_velocity(road, FB_ROAD_LEFT, 2.0, -1.5, &f, &err) == FB_OK);
  fb_road_wheel_info info;
  CHECK(f && fb_road_wheel_describe(f, &info) == 1 && info.kind == FB_ROAD_WHEEL_PIECES &&
        info.npieces == 4);
  CHECK(f && fb_road_wheel_new(&info, &g, &err) == FB_OK);
  for (double t = 0.0; f && g && t < 2.0; t += 0.013)
    CHECK(fb_tfun_eval(f, t) == fb_tfun_eval(g, t));
  fb_tfun_free(&f);
  fb_tfun_free(&g);
  fb_road_free(&road);
  /* A gap between pieces, and an arc off its circle, are refused. */
  fb_road_piece bad[2] = {left[0], left[1]};
  bad[1].s_begin = 0.01;
  CHECK(fb_road_new_pieces(2, bad, 0, NULL, &road, &err) == FB_EINVAL &&
        strstr(err.msg, "piece 2 does not begin where"));
  bad[1] = left[1];
  bad[1].s_end = 0.31;
  CHECK(fb_road_new_pieces(2, bad, 0, NULL, &road, &err) == FB_EINVAL &&
        strstr(err.msg, "leaves its circle"));
  /* Every other road has no edges. */
  CHECK(fb_road_new_oblique_bump(0.1, 3.7, 0.7, 2.1, &road, &err) == FB_OK);
  CHECK(fb_road_edges(road, FB_ROAD_LEFT, NULL, 0) == 0);
  fb_road_free(&road);
}

int main(void)
{
  test_halfround();
  test_step();
  test_cleat();
  test_trapezoid();
  test_pothole();
  test_washboard();
  test_oblique();
  test_tracks();
  test_series();
  test_rules();
  test_course();
  test_course_faces();
  test_course_errors();
  test_pieces_data();
  return check_report("test_road_obstacles");
}
