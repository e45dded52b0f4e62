/* SPDX-License-Identifier: BSD-3-Clause */
/* System 2's hull mesh: fb_hull_mesh_params_default and
 * fb_hull_mesh_generate (flexbond/vehicle.h; geometry, fit and sketch in
 * docs/hull-mesh.md).
 *
 * The hull is a closed box of flat plates: floor, roof, side walls, rear
 * wall, a wedge nose of two glacis plates and transverse bulkheads. The
 * generator
 *  1. computes the plates' centre of mass in the hull frame (x as given,
 *     z above the floor) from their areas, centroids and masses per area
 *     (hull.material's, or a section's);
 *  2. collects the floor's node lines: x lines at the rear wall, the box's
 *     front end, the bulkheads and every scenario point (its x plus the
 *     centre of mass's x), y lines at the side walls and every point's y;
 *  3. meshes every plate with rectangles on those lines (side walls, rear
 *     wall and bulkheads in side_rows rows, each glacis in nose_rows
 *     rows), and each side wall's nose triangle with triangles: vertical
 *     rungs at the glacis rows' ends, every pair of neighbouring rungs
 *     zipped together (each triangle takes one interval of one rung and the
 *     nearer node of the other), the last rung fanned to the nose tip;
 *  4. refines every element density x density times;
 *  5. shifts the mesh so that the centre of mass is the origin;
 *  6. names each plate's elements as an element set (hull_part below),
 *     which hull.sections give their own thickness or material.
 * Nodes are shared through a table keyed by their exact coordinates: every
 * point is computed by one formula from the line arrays, so a node reached
 * from two plates has bitwise equal coordinates. */
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* Fitted defaults (docs/hull-mesh.md, "Fit"): with width 2.10 m, nose
 * 0.80 x 0.60 m and bulkheads at -1.00 and 1.90 m, Newton's method on
 * (height, x_rear, x_front, rear bulkhead) solves mass = 4041.72 kg,
 * Ixx = 4173.49, Iyy = 15175.96 kg m^2 (8.5 mm steel, 7860 kg/m^3) and
 * centre of mass at x = 0 to round-off; kept at full precision so that
 * the bulkheads at -1.00 and 1.90 m coincide with the load lines there. */
#define FIT_HEIGHT 1.74083494988748
#define FIT_X_REAR (-2.65798412344113)
#define FIT_X_FRONT 2.47813311938948
#define FIT_REAR_BULKHEAD (-2.27413945470176)
#define DEFAULT_NOSE_LENGTH 0.80
#define DEFAULT_NOSE_HEIGHT 0.60
#define DEFAULT_REAR_AXLE_BULKHEAD (-1.00)
#define DEFAULT_FRONT_AXLE_BULKHEAD 1.90

/* Node lines closer than MERGE_TOL are one line; distinct lines must be
 * MIN_GAP apart (closer ones would make sliver elements). */
#define MERGE_TOL 1e-9
#define MIN_GAP 1e-3
#define MAX_DENSITY 64
#define MAX_DIVISIONS 1000

/* The most elements System 2's hull may have, whatever makes its mesh (the
 * generator, a deck, a gmsh file: vehicle_hull_check_size), and the memory
 * per element that bound stands for. Peak RSS (GNU time) and wall time
 * (RelWithDebInfo, 2 cores) on the reference hull refined d times, with
 * CHOLMOD's factors and block Lanczos for a modal basis (docs/benchmarks.md):
 *
 *   d  elements  `modes --system flexible`     `run --system flexible`
 *   2       960     51 MB  52 KiB/element  0.3 s     35 MB  35 KiB/element  0.4 s
 *   4      3840    208 MB  53              1.9 s    111 MB  28              1.1 s
 *   7     11760    661 MB  55               10 s    349 MB  29                6 s
 *  16     61440   3301 MB  52               58 s   1807 MB  29               25 s
 *
 * modes, which solves the whole vehicle's modes besides the hull's, takes
 * the most; the matrices, factors, Lanczos vectors and basis grow about as
 * the mesh. 64 KiB per element stays above every measured value (16 % above
 * the largest); the bound keeps that estimate within 4 GiB: 65536 elements,
 * density 16 on the reference hull. */
#define HULL_BYTES_PER_ELEMENT 65536.0
#define HULL_MAX_ELEMENTS 65536

/* The plates, as element sets: each generated element is in one part,
 * a bulkhead b in PART_BULKHEAD + b. */
typedef enum hull_part {
  PART_FLOOR,
  PART_ROOF,
  PART_SIDES, /* both side walls, their nose triangles included */
  PART_REAR_WALL,
  PART_GLACIS, /* both glacis plates */
  PART_BULKHEAD
} hull_part;
#define NPLAIN_PARTS PART_BULKHEAD
static const char *const PART_NAMES[NPLAIN_PARTS] = {"FLOOR", "ROOF", "SIDES", "REAR_WALL",
                                                     "GLACIS"};

/* Mass per area of a plate in the element set called name (and, for a
 * bulkhead, also in the set `also`) relative to hull.material's: that of
 * the last section of the scenario naming either, else exactly 1 (so that
 * a hull without sections has the area centroid to the last bit). */
static double areal_density(const fb_scenario *s, const char *name, const char *also)
{
  double w = 1.0;
  for (size_t i = 0; i < s->nsections; ++i) {
    const fb_hull_section *sec = &s->section[i];
    if (strcasecmp(sec->set, name) == 0 || (also && strcasecmp(sec->set, also) == 0))
      w = (sec->density * sec->thickness + sec->nonstructural_mass) /
          (s->density * s->thickness);
  }
  return w;
}

/* "BULKHEAD_<b + 1>" into buf. */
static void bulkhead_set(size_t b, char *buf, size_t size)
{
  snprintf(buf, size, "BULKHEAD_%zu", b + 1);
}

/* ---- Parameters. */

int fb_hull_mesh_params_default(const fb_scenario *s, fb_hull_mesh_params *p, fb_err *err)
{
  if (!s || !p)
    return fb_err_set(err, FB_EINVAL, "fb_hull_mesh_params_default: NULL argument");
  /* Side walls through the outermost suspension points, so that they lie
   * on the walls' bottom edges (2.10 m for the reference scenario). */
  double half_width = 0.0;
  for (size_t c = 0; c < s->ncorners; ++c)
    half_width = fmax(half_width, fabs(s->corner[c].y));
  if (!(half_width > 0.0))
    return fb_err_set(err, FB_EINVAL,
                      "fb_hull_mesh_params_default: the suspension points span no width");
  *p = (fb_hull_mesh_params){.width = 2.0 * half_width,
                             .height = FIT_HEIGHT,
                             .x_rear = FIT_X_REAR,
                             .x_front = FIT_X_FRONT,
                             .nose_length = DEFAULT_NOSE_LENGTH,
                             .nose_height = DEFAULT_NOSE_HEIGHT,
                             .nbulkheads = 3,
                             .bulkhead_x = {FIT_REAR_BULKHEAD, DEFAULT_REAR_AXLE_BULKHEAD,
                                            DEFAULT_FRONT_AXLE_BULKHEAD},
                             .side_rows = 2,
                             .nose_rows = 3,
                             .nose_rung_divisions = 3,
                             .density = 1};
  return FB_OK;
}

/* The error just set (its code) is about the generator's parameter
 * member (fb_hull_mesh_params, the scenario's hull_mesh), element element.
 * Returns code. */
static int param_part(fb_err *err, const char *member, size_t element, int code)
{
  char field[FB_ERR_FIELD_MAX];
  snprintf(field, sizeof field, "hull_mesh.%s", member);
  fb_err_set_part(err, FB_PART_VEHICLE, 0, element, field);
  return code;
}

static int check_count(const char *name, int value, int max, fb_err *err)
{
  if (value < 1 || value > max)
    return param_part(err, name, FB_ERR_NO_ELEMENT,
                      fb_err_set(err, FB_EINVAL, "hull mesh: %s must be in 1 .. %d (got %d)",
                                 name, max, value));
  return FB_OK;
}

static int check_params(const fb_hull_mesh_params *p, fb_err *err)
{
  const double dims[] = {p->width, p->height, p->nose_length};
  const char *dim_names[] = {"width", "height", "nose_length"};
  for (size_t i = 0; i < 3; ++i)
    if (!(isfinite(dims[i]) && dims[i] > 0.0))
      return param_part(err, dim_names[i], FB_ERR_NO_ELEMENT,
                        fb_err_set(err, FB_EINVAL, "hull mesh: %s must be > 0 (got %g)",
                                   dim_names[i], dims[i]));
  if (!(isfinite(p->x_rear) && isfinite(p->x_front) && p->x_front > p->x_rear))
    return param_part(err, "x_front", FB_ERR_NO_ELEMENT,
                      fb_err_set(err, FB_EINVAL,
                                 "hull mesh: x_front (%g) must be > x_rear (%g)", p->x_front,
                                 p->x_rear));
  if (!(p->nose_height > 0.0 && p->nose_height < p->height))
    return param_part(err, "nose_height", FB_ERR_NO_ELEMENT,
                      fb_err_set(err, FB_EINVAL,
                                 "hull mesh: nose_height must be in (0, height = %g) (got %g)",
                                 p->height, p->nose_height));
  if (p->nbulkheads > FB_HULL_MAX_BULKHEADS)
    return param_part(err, "bulkhead_x", FB_ERR_NO_ELEMENT,
                      fb_err_set(err, FB_EINVAL, "hull mesh: at most %d bulkheads (got %zu)",
                                 FB_HULL_MAX_BULKHEADS, p->nbulkheads));
  for (size_t b = 0; b < p->nbulkheads; ++b)
    if (!(p->bulkhead_x[b] > p->x_rear && p->bulkhead_x[b] < p->x_front))
      return param_part(
          err, "bulkhead_x", b,
          fb_err_set(err, FB_EINVAL,
                     "hull mesh: bulkhead_x[%zu] = %g must lie inside the box (%g, %g)", b,
                     p->bulkhead_x[b], p->x_rear, p->x_front));
  int rc = check_count("side_rows", p->side_rows, MAX_DIVISIONS, err);
  if (rc == FB_OK)
    rc = check_count("nose_rows", p->nose_rows, MAX_DIVISIONS, err);
  if (rc == FB_OK)
    rc = check_count("nose_rung_divisions", p->nose_rung_divisions, MAX_DIVISIONS, err);
  if (rc == FB_OK)
    rc = check_count("density", p->density, MAX_DENSITY, err);
  return rc;
}

/* ---- Geometry in the hull frame (x as given, z above the floor). */

/* Station j = 0 .. nose_rows along the nose: x and the heights of the
 * lower and upper glacis there (station 0 is the box's front end, station
 * nose_rows the tip line, where both heights are nose_height). */
static void nose_station(const fb_hull_mesh_params *p, int j, double *x, double *z_low,
                         double *z_up)
{
  if (j == p->nose_rows) {
    *x = p->x_front + p->nose_length;
    *z_low = *z_up = p->nose_height;
    return;
  }
  const double f = (double)j / (double)p->nose_rows;
  *x = p->x_front + p->nose_length * f;
  *z_low = p->nose_height * f;
  *z_up = p->height + (p->nose_height - p->height) * f;
}

/* Height of level k = 0 .. side_rows up the side walls. */
static double side_level(const fb_hull_mesh_params *p, int k)
{
  return k == p->side_rows ? p->height : p->height * (double)k / (double)p->side_rows;
}

/* Accumulates a plate's area a and first moments about x = 0 and z = 0
 * of its centroid (x, z): sums[0 .. 2]. */
static void add_plate(double *sums, double a, double x, double z)
{
  sums[0] += a;
  sums[1] += a * x;
  sums[2] += a * z;
}

/* Centre of mass (x, z) of the plates: their centroids weighted by area
 * times mass per area (areal_density). The side wall is the pentagon rear-bottom,
 * front-bottom, nose tip, front-top, rear-top; its area and centroid by the
 * shoelace formulas (e.g. Bourke, "Calculating the area and centroid of a
 * polygon", 1988). */
void fb_hull_mesh_centroid(const fb_scenario *s, const fb_hull_mesh_params *p, double *cx,
                           double *cz)
{
  const double w = p->width, h = p->height, xr = p->x_rear, xf = p->x_front;
  const double xn = xf + p->nose_length, zn = p->nose_height, len = xf - xr;
  double rel[NPLAIN_PARTS];
  for (int k = 0; k < NPLAIN_PARTS; ++k)
    rel[k] = areal_density(s, PART_NAMES[k], NULL);
  double sums[3] = {0, 0, 0};
  add_plate(sums, rel[PART_FLOOR] * w * len, 0.5 * (xr + xf), 0.0);
  add_plate(sums, rel[PART_ROOF] * w * len, 0.5 * (xr + xf), h);
  add_plate(sums, rel[PART_REAR_WALL] * w * h, xr, 0.5 * h);
  for (size_t b = 0; b < p->nbulkheads; ++b) {
    char name[32];
    bulkhead_set(b, name, sizeof name);
    add_plate(sums, areal_density(s, "BULKHEADS", name) * w * h, p->bulkhead_x[b], 0.5 * h);
  }
  const double lower = hypot(p->nose_length, zn), upper = hypot(p->nose_length, h - zn);
  add_plate(sums, rel[PART_GLACIS] * w * lower, xf + 0.5 * p->nose_length, 0.5 * zn);
  add_plate(sums, rel[PART_GLACIS] * w * upper, xf + 0.5 * p->nose_length, 0.5 * (h + zn));
  const double px[5] = {xr, xf, xn, xf, xr}, pz[5] = {0.0, 0.0, zn, h, h};
  double a2 = 0.0, sx = 0.0, sz = 0.0; /* twice the area, six times its moments */
  for (int i = 0; i < 5; ++i) {
    const int k = (i + 1) % 5;
    const double cross = px[i] * pz[k] - px[k] * pz[i];
    a2 += cross;
    sx += (px[i] + px[k]) * cross;
    sz += (pz[i] + pz[k]) * cross;
  }
  /* both side walls: 2 x a2 / 2 */
  add_plate(sums, rel[PART_SIDES] * a2, sx / (3.0 * a2), sz / (3.0 * a2));
  *cx = sums[1] / sums[0];
  *cz = sums[2] / sums[0];
}

/* ---- Node lines. */

typedef struct line_src {
  double value;
  fb_err_part part; /* the description's value it comes from (an error's fb_err.part) */
  char what[80];    /* that value for a reader: "corner LF's x", "bulkhead 2" */
  int geometric;    /* a plate's own line (wall, bulkhead): its value wins */
  size_t origin;    /* index in insertion order */
} line_src;

typedef struct lines {
  line_src *src;
  size_t nsrc;
  double *values; /* merged, increasing */
  size_t n;
  size_t *line; /* line of each source, by insertion order */
} lines;

static void lines_free(lines *l)
{
  free(l->src);
  free(l->values);
  free(l->line);
  *l = (lines){0};
}

static int cmp_src(const void *a, const void *b)
{
  const double x = ((const line_src *)a)->value, y = ((const line_src *)b)->value;
  return (x > y) - (x < y);
}

static void add_src(lines *l, double value, const fb_err_part *part, const char *what,
                    int geometric)
{
  line_src *s = &l->src[l->nsrc];
  s->value = value;
  s->part = *part;
  snprintf(s->what, sizeof s->what, "%s", what);
  s->geometric = geometric;
  s->origin = l->nsrc++;
}

/* The part (kind, index, element, field) as a value. */
static fb_err_part part_of(int kind, size_t index, size_t element, const char *field)
{
  fb_err_part p = {kind, index, element, ""};
  snprintf(p.field, sizeof p.field, "%s", field);
  return p;
}

/* Records part as the error's (fb_err.part) just set, FB_EINVAL; returns
 * FB_EINVAL (also when err is NULL). */
static int set_part(fb_err *err, const fb_err_part *part)
{
  fb_err_set_part(err, part->kind, part->index, part->element, part->field);
  return FB_EINVAL;
}

/* Sorts the sources and merges those within MERGE_TOL of the line's
 * value into one line, whose value is a plate's own if one is among them
 * (so that plates meet exactly on it). Two plates on one line, or two
 * distinct lines closer than MIN_GAP, are errors. axis: "x" or "y". */
static int lines_merge(lines *l, const char *axis, fb_err *err)
{
  qsort(l->src, l->nsrc, sizeof *l->src, cmp_src);
  l->values = malloc(l->nsrc * sizeof *l->values);
  l->line = malloc(l->nsrc * sizeof *l->line);
  if (!l->values || !l->line)
    return fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the node lines");
  l->n = 0;
  const line_src *owner = NULL; /* the current line's plate, if any */
  for (size_t i = 0; i < l->nsrc; ++i) {
    const line_src *s = &l->src[i];
    const double gap = l->n > 0 ? s->value - l->values[l->n - 1] : INFINITY;
    if (gap > MERGE_TOL && gap < MIN_GAP) {
      fb_err_set(err, FB_EINVAL,
                 "at %s = %.9g m it is %.3g m from %s (%s = %.9g m): the generated hull "
                 "mesh's node lines must coincide or be at least %g m apart",
                 axis, s->value, gap, l->src[i - 1].what, axis, l->src[i - 1].value, MIN_GAP);
      return set_part(err, &s->part);
    }
    if (gap > MERGE_TOL) {
      l->values[l->n++] = s->value;
      owner = NULL;
    }
    if (s->geometric && owner) {
      fb_err_set(err, FB_EINVAL,
                 "coincides with %s (%s = %.9g m): two plates of the generated hull mesh on "
                 "one line",
                 owner->what, axis, s->value);
      return set_part(err, &s->part);
    }
    if (s->geometric) {
      owner = s;
      l->values[l->n - 1] = s->value;
    }
    l->line[s->origin] = l->n - 1;
  }
  return FB_OK;
}

/* The special points: the attachment points (in the order of the hull's
 * attach port), the load points, then the declared hull masses. */
static size_t npoints(const fb_scenario *s)
{
  return fb_scenario_nattach(s) + s->nload + s->npoint_masses;
}

/* The part of special point k's coordinate axis ("x" or "y"): a
 * corner's, a mount's or a hull mass's member, or a load point (one item
 * for both axes), and its words for a reader ("corner LF's x"). */
static void point_part(const fb_scenario *s, size_t k, const char *axis, fb_err_part *part,
                       char *what, size_t size)
{
  const size_t na = fb_scenario_nattach(s);
  if (k < s->ncorners) {
    *part = part_of(FB_PART_CORNER, k, FB_ERR_NO_ELEMENT, axis);
    snprintf(what, size, "corner %s's %s", s->corner[k].name, axis);
  } else if (k < na) {
    *part = part_of(FB_PART_MOUNT, k - s->ncorners, FB_ERR_NO_ELEMENT, axis);
    snprintf(what, size, "mount %s's %s", s->mount[k - s->ncorners].name, axis);
  } else if (k < na + s->nload) {
    *part = part_of(FB_PART_LOAD_POINT, k - na, FB_ERR_NO_ELEMENT, "");
    snprintf(what, size, "load point %zu's %s", k - na, axis);
  } else {
    *part = part_of(FB_PART_HULL_MASS, k - na - s->nload, FB_ERR_NO_ELEMENT, axis);
    snprintf(what, size, "hull mass %s's %s", s->point_mass[k - na - s->nload].name, axis);
  }
}

/* Position (x, y) of special point k in the vehicle axes. */
static void point_xy(const fb_scenario *s, size_t k, double *x, double *y)
{
  const size_t na = fb_scenario_nattach(s);
  if (k < s->ncorners) {
    *x = s->corner[k].x;
    *y = s->corner[k].y;
  } else if (k < na) {
    *x = s->mount[k - s->ncorners].x;
    *y = s->mount[k - s->ncorners].y;
  } else if (k < na + s->nload) {
    *x = s->load_x[k - na];
    *y = s->load_y[k - na];
  } else {
    *x = s->point_mass[k - na - s->nload].x;
    *y = s->point_mass[k - na - s->nload].y;
  }
}

/* Node set of special point k (new): SUSP_ and the corner's name as it
 * is, the mount's name in capitals, LOAD, or MASS_ and the hull mass's
 * name in capitals. */
static char *point_set(const fb_scenario *s, size_t k)
{
  const size_t na = fb_scenario_nattach(s);
  char *set = k < s->ncorners ? fb_strdup_printf("SUSP_%s", s->corner[k].name)
              : k < na        ? fb_strdup(s->mount[k - s->ncorners].name)
              : k < na + s->nload
                  ? fb_strdup("LOAD")
                  : fb_strdup_printf("MASS_%s", s->point_mass[k - na - s->nload].name);
  for (char *c = set; c && k >= s->ncorners && *c; ++c)
    *c = (char)toupper((unsigned char)*c);
  return set;
}

/* Sources in insertion order: the x lines are x_rear, x_front, the
 * bulkheads, then special point k at X_POINTS(p) + k; the y lines the
 * right and left side walls, then point k at Y_POINTS + k. */
#define X_POINTS(p) (2 + (p)->nbulkheads)
#define Y_POINTS 2

/* x lines (hull frame) and y lines; every special point must lie on the
 * floor. cx: the centre of mass's x in the hull frame. */
static int build_lines(const fb_scenario *s, const fb_hull_mesh_params *p, double cx, lines *xl,
                       lines *yl, fb_err *err)
{
  const size_t n = npoints(s);
  xl->src = malloc((n + X_POINTS(p)) * sizeof *xl->src);
  yl->src = malloc((n + Y_POINTS) * sizeof *yl->src);
  if (!xl->src || !yl->src)
    return fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the node lines");
  const double half = 0.5 * p->width;
  /* Sources are named by the description's values (fb_err.part of an
   * error). */
  const fb_err_part rear = part_of(FB_PART_AT(FB_PART_VEHICLE, 0, hull_mesh.x_rear));
  const fb_err_part front = part_of(FB_PART_AT(FB_PART_VEHICLE, 0, hull_mesh.x_front));
  const fb_err_part width = part_of(FB_PART_AT(FB_PART_VEHICLE, 0, hull_mesh.width));
  add_src(xl, p->x_rear, &rear, "the rear wall", 1);
  add_src(xl, p->x_front, &front, "the front end of the box", 1);
  add_src(yl, -half, &width, "the right side wall", 1);
  add_src(yl, half, &width, "the left side wall", 1);
  for (size_t b = 0; b < p->nbulkheads; ++b) {
    char what[64];
    snprintf(what, sizeof what, "bulkhead %zu", b);
    const fb_err_part bulkhead =
        part_of(FB_PART_ELEMENT(FB_PART_VEHICLE, 0, hull_mesh.bulkhead_x, b));
    add_src(xl, p->bulkhead_x[b], &bulkhead, what, 1);
  }
  for (size_t k = 0; k < n; ++k) {
    char what_x[80], what_y[80];
    fb_err_part part_x, part_y;
    double x, y;
    point_part(s, k, "x", &part_x, what_x, sizeof what_x);
    point_part(s, k, "y", &part_y, what_y, sizeof what_y);
    point_xy(s, k, &x, &y);
    const double xh = x + cx;
    const int x_in = xh >= p->x_rear - MERGE_TOL && xh <= p->x_front + MERGE_TOL;
    if (!x_in || !(fabs(y) <= half + MERGE_TOL)) {
      fb_err_set(err, FB_EINVAL,
                 "(%g, %g) m lies outside the generated hull's floor, x in [%.6g, %.6g], y in "
                 "[%.6g, %.6g] m about the centre of mass",
                 x, y, p->x_rear - cx, p->x_front - cx, -half, half);
      return set_part(err, x_in ? &part_y : &part_x);
    }
    add_src(xl, xh, &part_x, what_x, 0);
    add_src(yl, y, &part_y, what_y, 0);
  }
  int rc = lines_merge(xl, "x", err);
  if (rc == FB_OK)
    rc = lines_merge(yl, "y", err);
  return rc;
}

/* ---- The mesh under construction: nodes (shared by exact coordinates)
 * and elements (3 or 4 node indices). */

typedef struct build_mesh {
  double *xyz;
  size_t nnodes, node_cap;
  size_t *slots; /* node + 1 by coordinates; 0 empty */
  size_t slot_cap;
  size_t *conn; /* 4 per element */
  unsigned char *nn;
  int *part; /* hull_part per element */
  size_t nelems, elem_cap;
  int current_part; /* of the elements being added */
} build_mesh;

static void build_free(build_mesh *b)
{
  free(b->xyz);
  free(b->slots);
  free(b->conn);
  free(b->nn);
  free(b->part);
  *b = (build_mesh){0};
}

/* SplitMix64 finaliser (Steele, Lea & Flood, "Fast splittable
 * pseudorandom number generators", OOPSLA 2014) as a hash mixer. */
static uint64_t mix64(uint64_t z)
{
  z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
  z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
  return z ^ (z >> 31);
}

static uint64_t hash_xyz(const double *p)
{
  uint64_t h = 0;
  for (int k = 0; k < 3; ++k) {
    const double v = p[k] == 0.0 ? 0.0 : p[k]; /* -0 and +0 alike */
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    h = mix64(h ^ bits);
  }
  return h;
}

static size_t *find_slot(const build_mesh *b, const double *p)
{
  size_t i = (size_t)hash_xyz(p) & (b->slot_cap - 1);
  for (;; i = (i + 1) & (b->slot_cap - 1)) {
    const size_t v = b->slots[i];
    if (v == 0)
      return &b->slots[i];
    const double *q = &b->xyz[3 * (v - 1)];
    if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2])
      return &b->slots[i];
  }
}

/* Keeps the table at most half full (linear probing stays short). */
static int grow_slots(build_mesh *b, fb_err *err)
{
  if (2 * (b->nnodes + 1) <= b->slot_cap)
    return FB_OK;
  const size_t cap = b->slot_cap ? 2 * b->slot_cap : 1024;
  size_t *slots = calloc(cap, sizeof *slots);
  if (!slots)
    return fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the node table");
  free(b->slots);
  b->slots = slots;
  b->slot_cap = cap;
  for (size_t n = 0; n < b->nnodes; ++n)
    *find_slot(b, &b->xyz[3 * n]) = n + 1;
  return FB_OK;
}

static int push_node(build_mesh *b, const double *p, size_t *index, fb_err *err)
{
  if (b->nnodes == b->node_cap) {
    const size_t cap = b->node_cap ? 2 * b->node_cap : 256;
    double *xyz = realloc(b->xyz, 3 * cap * sizeof *xyz);
    if (!xyz)
      return fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the nodes");
    b->xyz = xyz;
    b->node_cap = cap;
  }
  memcpy(&b->xyz[3 * b->nnodes], p, 3 * sizeof *p);
  *index = b->nnodes++;
  return FB_OK;
}

/* The node at exactly (x, y, z), added if new. */
static int node_at(build_mesh *b, double x, double y, double z, size_t *index, fb_err *err)
{
  const double p[3] = {x, y, z};
  int rc = grow_slots(b, err);
  if (rc != FB_OK)
    return rc;
  size_t *slot = find_slot(b, p);
  if (*slot) {
    *index = *slot - 1;
    return FB_OK;
  }
  rc = push_node(b, p, index, err);
  if (rc == FB_OK)
    *slot = *index + 1;
  return rc;
}

/* Normal (unnormalised) of a flat element: cross product of the diagonals
 * of a quadrilateral, of the sides from node 0 of a triangle. */
static void element_normal(const build_mesh *b, const size_t *nodes, size_t nn, double *n)
{
  const double *x0 = &b->xyz[3 * nodes[0]], *x1 = &b->xyz[3 * nodes[1]];
  const double *x2 = &b->xyz[3 * nodes[2]], *x3 = nn == 4 ? &b->xyz[3 * nodes[3]] : x0;
  double u[3], v[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = nn == 4 ? x2[k] - x0[k] : x1[k] - x0[k];
    v[k] = nn == 4 ? x3[k] - x1[k] : x2[k] - x0[k];
  }
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
}

/* Adds an element over nodes (nn = 3 or 4, in order around it), reversed
 * if needed so that its normal (right-hand rule) points along `outward`
 * (the hull's outer plates face out, bulkheads forward); outward NULL
 * keeps the order. */
static int add_element(build_mesh *b, const size_t *nodes, size_t nn, const double *outward,
                       fb_err *err)
{
  if (b->nelems == b->elem_cap) {
    const size_t cap = b->elem_cap ? 2 * b->elem_cap : 256;
    size_t *conn = realloc(b->conn, 4 * cap * sizeof *conn);
    if (!conn)
      return fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the elements");
    b->conn = conn;
    unsigned char *nnv = realloc(b->nn, cap * sizeof *nnv);
    if (!nnv)
      return fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the elements");
    b->nn = nnv;
    int *part = realloc(b->part, cap * sizeof *part);
    if (!part)
      return fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the elements");
    b->part = part;
    b->elem_cap = cap;
  }
  double n[3] = {0, 0, 0};
  if (outward)
    element_normal(b, nodes, nn, n);
  const int reverse =
      outward && n[0] * outward[0] + n[1] * outward[1] + n[2] * outward[2] < 0.0;
  size_t *dst = &b->conn[4 * b->nelems];
  for (size_t i = 0; i < nn; ++i)
    dst[i] = nodes[reverse ? nn - 1 - i : i];
  b->part[b->nelems] = b->current_part;
  b->nn[b->nelems++] = (unsigned char)nn;
  return FB_OK;
}

/* A quadrilateral over four points given in order around it. */
static int add_quad(build_mesh *b, const double (*pts)[3], const double *outward, fb_err *err)
{
  size_t nodes[4];
  for (int i = 0; i < 4; ++i) {
    const int rc = node_at(b, pts[i][0], pts[i][1], pts[i][2], &nodes[i], err);
    if (rc != FB_OK)
      return rc;
  }
  return add_element(b, nodes, 4, outward, err);
}

/* ---- Plates. */

typedef struct hull_geom {
  const fb_hull_mesh_params *p;
  const double *xs, *ys; /* floor lines (hull frame) */
  size_t nx, ny;
} hull_geom;

/* Floor (z = 0) and roof (z = height). */
static int mesh_floor_roof(build_mesh *b, const hull_geom *g, fb_err *err)
{
  const double down[3] = {0, 0, -1}, up[3] = {0, 0, 1};
  for (int roof = 0; roof < 2; ++roof) {
    const double z = roof ? g->p->height : 0.0;
    b->current_part = roof ? PART_ROOF : PART_FLOOR;
    for (size_t i = 0; i + 1 < g->nx; ++i)
      for (size_t j = 0; j + 1 < g->ny; ++j) {
        const double pts[4][3] = {{g->xs[i], g->ys[j], z},
                                  {g->xs[i + 1], g->ys[j], z},
                                  {g->xs[i + 1], g->ys[j + 1], z},
                                  {g->xs[i], g->ys[j + 1], z}};
        const int rc = add_quad(b, pts, roof ? up : down, err);
        if (rc != FB_OK)
          return rc;
      }
  }
  return FB_OK;
}

/* The box parts of both side walls (x_rear to x_front). */
static int mesh_side_boxes(build_mesh *b, const hull_geom *g, fb_err *err)
{
  const fb_hull_mesh_params *p = g->p;
  for (int left = 0; left < 2; ++left) {
    const double y = left ? g->ys[g->ny - 1] : g->ys[0];
    const double out[3] = {0, left ? 1.0 : -1.0, 0};
    for (size_t i = 0; i + 1 < g->nx; ++i)
      for (int k = 0; k < p->side_rows; ++k) {
        const double z0 = side_level(p, k), z1 = side_level(p, k + 1);
        const double pts[4][3] = {
            {g->xs[i], y, z0}, {g->xs[i + 1], y, z0}, {g->xs[i + 1], y, z1}, {g->xs[i], y, z1}};
        const int rc = add_quad(b, pts, out, err);
        if (rc != FB_OK)
          return rc;
      }
  }
  return FB_OK;
}

/* A transverse plate (rear wall or bulkhead) at x over the full cross
 * section. */
static int mesh_transverse(build_mesh *b, const hull_geom *g, double x, const double *out,
                           fb_err *err)
{
  for (size_t j = 0; j + 1 < g->ny; ++j)
    for (int k = 0; k < g->p->side_rows; ++k) {
      const double z0 = side_level(g->p, k), z1 = side_level(g->p, k + 1);
      const double pts[4][3] = {
          {x, g->ys[j], z0}, {x, g->ys[j + 1], z0}, {x, g->ys[j + 1], z1}, {x, g->ys[j], z1}};
      const int rc = add_quad(b, pts, out, err);
      if (rc != FB_OK)
        return rc;
    }
  return FB_OK;
}

/* Both glacis plates, nose_rows rows between the nose stations. Outward
 * normals in the x-z plane: forward-down (nose_height, -nose_length) for
 * the lower plate, forward-up (height - nose_height, nose_length) for the
 * upper one. */
static int mesh_glacis(build_mesh *b, const hull_geom *g, fb_err *err)
{
  const fb_hull_mesh_params *p = g->p;
  const double out_low[3] = {p->nose_height, 0, -p->nose_length};
  const double out_up[3] = {p->height - p->nose_height, 0, p->nose_length};
  for (int j = 0; j < p->nose_rows; ++j) {
    double x0, l0, u0, x1, l1, u1;
    nose_station(p, j, &x0, &l0, &u0);
    nose_station(p, j + 1, &x1, &l1, &u1);
    for (size_t i = 0; i + 1 < g->ny; ++i) {
      const double ya = g->ys[i], yb = g->ys[i + 1];
      const double low[4][3] = {{x0, ya, l0}, {x0, yb, l0}, {x1, yb, l1}, {x1, ya, l1}};
      const double up[4][3] = {{x0, ya, u0}, {x0, yb, u0}, {x1, yb, u1}, {x1, ya, u1}};
      int rc = add_quad(b, low, out_low, err);
      if (rc == FB_OK)
        rc = add_quad(b, up, out_up, err);
      if (rc != FB_OK)
        return rc;
    }
  }
  return FB_OK;
}

static double dist2(const build_mesh *b, size_t i, size_t j)
{
  const double *p = &b->xyz[3 * i], *q = &b->xyz[3 * j];
  return (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
         (p[2] - q[2]) * (p[2] - q[2]);
}

/* Triangulates the strip between two node chains rising from a common
 * base edge (left[0]-right[0]) to a common top edge: nl + nr triangles,
 * each on one interval of one chain and one node of the other, advancing
 * the chain whose new diagonal is shorter (the classic contour-stitching
 * rule, Fuchs, Kedem & Uselton, CACM 20(10), 1977). The strip is a convex
 * trapezoid here, so every such triangle is inside it and non-degenerate. */
static int zip_strip(build_mesh *b, const size_t *left, size_t nl, const size_t *right,
                     size_t nr, const double *out, fb_err *err)
{
  size_t i = 0, j = 0;
  while (i < nl || j < nr) {
    const int take_left = j == nr || (i < nl && dist2(b, left[i + 1], right[j]) <=
                                                    dist2(b, left[i], right[j + 1]));
    const size_t tri[3] = {left[i], right[j], take_left ? left[i + 1] : right[j + 1]};
    const int rc = add_element(b, tri, 3, out, err);
    if (rc != FB_OK)
      return rc;
    if (take_left)
      ++i;
    else
      ++j;
  }
  return FB_OK;
}

/* Nodes of rung j (0 = the box's front end, at the side levels; then the
 * glacis stations, nose_rung_divisions intervals) of the side wall at y,
 * bottom to top; *n intervals. rung must hold max(side_rows,
 * nose_rung_divisions) + 1 entries. */
static int side_rung(build_mesh *b, const fb_hull_mesh_params *p, int j, double y, size_t *rung,
                     size_t *n, fb_err *err)
{
  double x, zl, zu;
  nose_station(p, j, &x, &zl, &zu);
  const int q = j == 0 ? p->side_rows : p->nose_rung_divisions;
  for (int i = 0; i <= q; ++i) {
    const double z = j == 0   ? side_level(p, i)
                     : i == 0 ? zl
                     : i == q ? zu
                              : zl + (zu - zl) * (double)i / (double)q;
    const int rc = node_at(b, x, y, z, &rung[i], err);
    if (rc != FB_OK)
      return rc;
  }
  *n = (size_t)q;
  return FB_OK;
}

/* Each side wall's nose triangle (box front end, nose tip): strips between
 * neighbouring rungs, then a fan from the last rung to the tip. */
static int mesh_side_noses(build_mesh *b, const hull_geom *g, fb_err *err)
{
  const fb_hull_mesh_params *p = g->p;
  const size_t cap =
      (size_t)(p->side_rows > p->nose_rung_divisions ? p->side_rows : p->nose_rung_divisions) +
      1;
  size_t *prev = malloc(2 * cap * sizeof *prev), *next = prev ? prev + cap : NULL;
  if (!prev)
    return fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the nose");
  int rc = FB_OK;
  for (int left = 0; left < 2 && rc == FB_OK; ++left) {
    const double y = left ? g->ys[g->ny - 1] : g->ys[0];
    const double out[3] = {0, left ? 1.0 : -1.0, 0};
    size_t nprev = 0, nnext = 0;
    rc = side_rung(b, p, 0, y, prev, &nprev, err);
    for (int j = 1; j < p->nose_rows && rc == FB_OK; ++j) {
      rc = side_rung(b, p, j, y, next, &nnext, err);
      if (rc == FB_OK)
        rc = zip_strip(b, prev, nprev, next, nnext, out, err);
      memcpy(prev, next, (nnext + 1) * sizeof *prev);
      nprev = nnext;
    }
    double xt, zt, unused;
    nose_station(p, p->nose_rows, &xt, &zt, &unused);
    size_t tip = 0;
    if (rc == FB_OK)
      rc = node_at(b, xt, y, zt, &tip, err);
    for (size_t i = 0; i < nprev && rc == FB_OK; ++i) {
      const size_t tri[3] = {prev[i], prev[i + 1], tip};
      rc = add_element(b, tri, 3, out, err);
    }
  }
  free(prev);
  return rc;
}

static int mesh_plates(build_mesh *b, const hull_geom *g, fb_err *err)
{
  const double back[3] = {-1, 0, 0}, fwd[3] = {1, 0, 0};
  int rc = mesh_floor_roof(b, g, err);
  b->current_part = PART_SIDES;
  if (rc == FB_OK)
    rc = mesh_side_boxes(b, g, err);
  b->current_part = PART_REAR_WALL;
  if (rc == FB_OK)
    rc = mesh_transverse(b, g, g->p->x_rear, back, err);
  for (size_t k = 0; k < g->p->nbulkheads && rc == FB_OK; ++k) {
    b->current_part = PART_BULKHEAD + (int)k;
    rc = mesh_transverse(b, g, g->p->bulkhead_x[k], fwd, err);
  }
  b->current_part = PART_GLACIS;
  if (rc == FB_OK)
    rc = mesh_glacis(b, g, err);
  b->current_part = PART_SIDES;
  if (rc == FB_OK)
    rc = mesh_side_noses(b, g, err);
  return rc;
}

/* ---- Refinement: every element into d x d (quadrilateral) or d^2
 * (triangle) similar ones; the d - 1 nodes inside each edge are made once
 * and shared through a table keyed by the edge's end nodes. The coarse
 * nodes keep their indices. */

typedef struct edge_rec {
  size_t a, b;  /* a < b */
  size_t first; /* first of its d - 1 nodes, ordered from a to b */
} edge_rec;

typedef struct edge_table {
  edge_rec *recs;
  size_t nrecs;
  size_t *slots; /* record + 1; 0 empty */
  size_t cap;    /* power of two, more than twice the edges */
} edge_table;

static size_t *edge_slot(const edge_table *t, size_t a, size_t b)
{
  size_t i = (size_t)mix64(mix64((uint64_t)a) ^ (uint64_t)b) & (t->cap - 1);
  for (;; i = (i + 1) & (t->cap - 1)) {
    const size_t v = t->slots[i];
    if (v == 0 || (t->recs[v - 1].a == a && t->recs[v - 1].b == b))
      return &t->slots[i];
  }
}

/* Node k = 0 .. d of the edge from node u to node v of the fine mesh
 * (k = 0 is u, k = d is v), creating the edge's inner nodes on first use
 * by linear interpolation. */
static int edge_node(build_mesh *fine, edge_table *t, size_t u, size_t v, int d, int k,
                     size_t *out, fb_err *err)
{
  if (k == 0 || k == d) {
    *out = k == 0 ? u : v;
    return FB_OK;
  }
  const size_t a = u < v ? u : v, b = u < v ? v : u;
  size_t *slot = edge_slot(t, a, b);
  if (!*slot) {
    edge_rec *r = &t->recs[t->nrecs];
    *r = (edge_rec){a, b, fine->nnodes};
    for (int i = 1; i < d; ++i) {
      double p[3];
      for (int c = 0; c < 3; ++c)
        p[c] = fine->xyz[3 * a + c] + (fine->xyz[3 * b + c] - fine->xyz[3 * a + c]) * i / d;
      size_t unused;
      const int rc = push_node(fine, p, &unused, err);
      if (rc != FB_OK)
        return rc;
    }
    *slot = ++t->nrecs;
  }
  const edge_rec *r = &t->recs[*slot - 1];
  *out = r->first + (size_t)(u == a ? k - 1 : d - 1 - k);
  return FB_OK;
}

/* Point at parameters (s, t) in [0, 1] of a coarse element: bilinear over
 * a quadrilateral's corners, or c0 + s (c1 - c0) + t (c2 - c0) over a
 * triangle's. */
static void element_point(const build_mesh *b, const size_t *c, size_t nn, double s, double t,
                          double *p)
{
  for (int k = 0; k < 3; ++k) {
    const double x0 = b->xyz[3 * c[0] + k], x1 = b->xyz[3 * c[1] + k],
                 x2 = b->xyz[3 * c[2] + k];
    p[k] = nn == 4 ? (1 - s) * (1 - t) * x0 + s * (1 - t) * x1 + s * t * x2 +
                         (1 - s) * t * b->xyz[3 * c[3] + k]
                   : x0 + s * (x1 - x0) + t * (x2 - x0);
  }
}

/* Fine node (i, j) of coarse element e, for 0 <= i, j <= d (and i + j <= d
 * for a triangle): edge nodes from the table, inner nodes new (their
 * indices stored in grid, (d + 1)^2 entries, by the caller's loop order). */
static int grid_node(build_mesh *fine, edge_table *t, const size_t *c, size_t nn, int d, int i,
                     int j, size_t *grid, fb_err *err)
{
  size_t *dst = &grid[(size_t)j * (size_t)(d + 1) + (size_t)i];
  if (nn == 4) {
    if (j == 0)
      return edge_node(fine, t, c[0], c[1], d, i, dst, err);
    if (i == d)
      return edge_node(fine, t, c[1], c[2], d, j, dst, err);
    if (j == d)
      return edge_node(fine, t, c[3], c[2], d, i, dst, err);
    if (i == 0)
      return edge_node(fine, t, c[0], c[3], d, j, dst, err);
  } else {
    if (j == 0)
      return edge_node(fine, t, c[0], c[1], d, i, dst, err);
    if (i == 0)
      return edge_node(fine, t, c[0], c[2], d, j, dst, err);
    if (i + j == d)
      return edge_node(fine, t, c[1], c[2], d, j, dst, err);
  }
  double p[3];
  element_point(fine, c, nn, (double)i / d, (double)j / d, p);
  return push_node(fine, p, dst, err);
}

/* Appends the fine elements of one coarse element from its node grid,
 * with the coarse element's orientation. */
static int split_element(build_mesh *fine, const size_t *grid, size_t nn, int d, fb_err *err)
{
  const size_t w = (size_t)d + 1;
#define G(i, j) grid[(size_t)(j)*w + (size_t)(i)]
  int rc = FB_OK;
  for (int j = 0; j < d && rc == FB_OK; ++j)
    for (int i = 0; i < d && rc == FB_OK; ++i) {
      if (nn == 4) {
        const size_t q[4] = {G(i, j), G(i + 1, j), G(i + 1, j + 1), G(i, j + 1)};
        rc = add_element(fine, q, 4, NULL, err);
      } else if (i + j < d) {
        const size_t up[3] = {G(i, j), G(i + 1, j), G(i, j + 1)};
        rc = add_element(fine, up, 3, NULL, err);
        if (rc == FB_OK && i + j < d - 1) {
          const size_t down[3] = {G(i + 1, j), G(i + 1, j + 1), G(i, j + 1)};
          rc = add_element(fine, down, 3, NULL, err);
        }
      }
    }
#undef G
  return rc;
}

int vehicle_hull_check_size(double elements, const char *hint, fb_err *err)
{
  if (elements <= HULL_MAX_ELEMENTS)
    return FB_OK;
  return fb_err_set(err, FB_EINVAL,
                    "which would need about %.1f GB of memory for System 2 (about %.0f KiB per "
                    "element), more than the %.1f GB allowed (at most %d elements%s; "
                    "docs/hull-mesh.md, \"Limits\")",
                    elements * HULL_BYTES_PER_ELEMENT / 1e9, HULL_BYTES_PER_ELEMENT / 1024.0,
                    HULL_MAX_ELEMENTS * HULL_BYTES_PER_ELEMENT / 1e9, HULL_MAX_ELEMENTS, hint);
}

/* The refined mesh's size, estimated from the coarse one before any of
 * it is allocated: refining splits every element into d^2 (d = 1: the
 * coarse mesh itself, which side_rows, nose_rows and nose_rung_divisions
 * up to MAX_DIVISIONS can make large too). The error names the value to
 * change: the density, with the largest this mesh allows, or the
 * generator's rows and divisions. */
static int check_refined_size(const build_mesh *coarse, int d, fb_err *err)
{
  const double elements = (double)coarse->nelems * (double)d * (double)d;
  char hint[64] = "";
  if (d > 1) {
    int most = 1;
    while ((double)coarse->nelems * (most + 1) * (most + 1) <= HULL_MAX_ELEMENTS)
      ++most;
    snprintf(hint, sizeof hint, ": density %d for this mesh", most);
  }
  const int rc = vehicle_hull_check_size(elements, hint, err);
  if (rc && d == 1) {
    fb_err_prefix(err, "the generated mesh has %zu elements, ", coarse->nelems);
    fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_mesh));
  } else if (rc) {
    fb_err_prefix(err, "%d refines the generated mesh's %zu elements into %.0f, ", d,
                  coarse->nelems, elements);
    fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_mesh.density));
  }
  return rc;
}

static int refine(const build_mesh *coarse, int d, build_mesh *fine, fb_err *err)
{
  *fine = (build_mesh){0};
  edge_table t = {0};
  t.recs = calloc(4 * coarse->nelems, sizeof *t.recs);
  t.cap = 16;
  while (t.cap < 8 * coarse->nelems)
    t.cap *= 2;
  t.slots = calloc(t.cap, sizeof *t.slots);
  size_t *grid = malloc((size_t)(d + 1) * (size_t)(d + 1) * sizeof *grid);
  int rc = t.recs && t.slots && grid
               ? FB_OK
               : fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the refinement");
  for (size_t n = 0; n < coarse->nnodes && rc == FB_OK; ++n) {
    size_t unused;
    rc = push_node(fine, &coarse->xyz[3 * n], &unused, err);
  }
  for (size_t e = 0; e < coarse->nelems && rc == FB_OK; ++e) {
    const size_t *c = &coarse->conn[4 * e], nn = coarse->nn[e];
    for (int j = 0; j <= d && rc == FB_OK; ++j)
      for (int i = 0; i <= d && rc == FB_OK; ++i)
        if (nn == 4 || i + j <= d)
          rc = grid_node(fine, &t, c, nn, d, i, j, grid, err);
    fine->current_part = coarse->part[e];
    if (rc == FB_OK)
      rc = split_element(fine, grid, nn, d, err);
  }
  free(grid);
  free(t.recs);
  free(t.slots);
  return rc;
}

/* ---- The fb_mesh. */

static int find_node(const build_mesh *b, double x, double y, double z, size_t *index,
                     const char *what, fb_err *err)
{
  const double p[3] = {x, y, z};
  const size_t v = *find_slot(b, p);
  if (!v)
    return fb_err_set(err, FB_EMODEL, "hull mesh: no node at %s (internal error)", what);
  *index = v - 1;
  return FB_OK;
}

/* Node sets of the special points and edges, in coarse node indices
 * (kept by the refinement). Distinct load points must be distinct nodes. */
static int add_point_sets(fb_mesh *m, const build_mesh *coarse, const fb_scenario *s,
                          const lines *xl, const lines *yl, fb_err *err)
{
  const size_t xp = xl->nsrc - npoints(s);
  int rc = FB_OK;
  for (size_t k = 0; k < npoints(s) && rc == FB_OK; ++k) {
    char what[80];
    fb_err_part part;
    point_part(s, k, "x", &part, what, sizeof what);
    const double x = xl->values[xl->line[xp + k]], y = yl->values[yl->line[Y_POINTS + k]];
    size_t node = 0;
    char *set = point_set(s, k);
    if (!set)
      rc = fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the node sets");
    if (rc == FB_OK)
      rc = find_node(coarse, x, y, 0.0, &node, what, err);
    if (rc == FB_OK)
      rc = fb_mesh_add_nset(m, set, 1, &node, err);
    free(set);
  }
  const size_t *load = NULL;
  size_t nload = 0;
  if (rc == FB_OK && fb_mesh_nset(m, "LOAD", &load, &nload) && nload != s->nload)
    rc = fb_err_set(err, FB_EINVAL,
                    "the %zu points fall on only %zu nodes of the generated hull mesh (points "
                    "on one node)",
                    s->nload, nload),
    fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, load_x));
  const double ends[2] = {xl->values[xl->n - 1], xl->values[0]};
  const char *edge_sets[2] = {"FRONT_EDGE", "REAR_EDGE"};
  for (int e = 0; e < 2 && rc == FB_OK; ++e) {
    size_t nodes[2] = {0, 0};
    rc = find_node(coarse, ends[e], yl->values[yl->n - 1], 0.0, &nodes[0], edge_sets[e], err);
    if (rc == FB_OK)
      rc = find_node(coarse, ends[e], yl->values[0], 0.0, &nodes[1], edge_sets[e], err);
    if (rc == FB_OK)
      rc = fb_mesh_add_nset(m, edge_sets[e], 2, nodes, err);
  }
  return rc;
}

/* The elements of the parts first to last (inclusive) as the element set
 * name, if there are any; list holds b->nelems. */
static int add_part_set(fb_mesh *m, const build_mesh *b, int first, int last, const char *name,
                        size_t *list, fb_err *err)
{
  size_t n = 0;
  for (size_t e = 0; e < b->nelems; ++e)
    if (b->part[e] >= first && b->part[e] <= last)
      list[n++] = e;
  return n ? fb_mesh_add_elset(m, name, n, list, err) : FB_OK;
}

/* The element sets of the plates: PART_NAMES, BULKHEADS (every bulkhead)
 * and BULKHEAD_<k>, k = 1, 2, ... from the rear. */
static int add_part_sets(fb_mesh *m, const build_mesh *b, fb_err *err)
{
  size_t *list = malloc((b->nelems ? b->nelems : 1) * sizeof *list);
  int rc = list ? FB_OK : fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the sets");
  for (int k = 0; k < NPLAIN_PARTS && rc == FB_OK; ++k)
    rc = add_part_set(m, b, k, k, PART_NAMES[k], list, err);
  if (rc == FB_OK)
    rc = add_part_set(m, b, PART_BULKHEAD, INT_MAX, "BULKHEADS", list, err);
  for (int k = 0; k < FB_HULL_MAX_BULKHEADS && rc == FB_OK; ++k) {
    char name[32];
    bulkhead_set((size_t)k, name, sizeof name);
    rc = add_part_set(m, b, PART_BULKHEAD + k, PART_BULKHEAD + k, name, list, err);
  }
  free(list);
  return rc;
}

/* Copies b into a new fb_mesh, shifted by -(cx, 0, cz), with ids 1, 2, ...,
 * the node set ALL and the plates' element sets. */
static int to_fb_mesh(const build_mesh *b, double cx, double cz, fb_mesh **out, fb_err *err)
{
  fb_mesh *m = NULL;
  int rc = fb_mesh_new(&m, err);
  for (size_t n = 0; n < b->nnodes && rc == FB_OK; ++n) {
    const double *p = &b->xyz[3 * n];
    size_t index;
    rc = fb_mesh_add_node(m, (long)n + 1, p[0] - cx, p[1], p[2] - cz, &index, err);
  }
  for (size_t e = 0; e < b->nelems && rc == FB_OK; ++e)
    rc = fb_mesh_add_element(m, (long)e + 1, b->nn[e] == 4 ? FB_ELEM_QUAD4 : FB_ELEM_TRI3,
                             &b->conn[4 * e], err);
  size_t *all = rc == FB_OK ? malloc(b->nnodes * sizeof *all) : NULL;
  if (rc == FB_OK && !all)
    rc = fb_err_set(err, FB_ENOMEM, "hull mesh: out of memory for the node sets");
  for (size_t n = 0; all && n < b->nnodes; ++n)
    all[n] = n;
  if (rc == FB_OK)
    rc = fb_mesh_add_nset(m, "ALL", b->nnodes, all, err);
  free(all);
  if (rc == FB_OK)
    rc = add_part_sets(m, b, err);
  if (rc != FB_OK)
    fb_mesh_free(&m);
  *out = m;
  return rc;
}

int fb_hull_mesh_generate(const fb_scenario *s, const fb_hull_mesh_params *p, fb_mesh **out,
                          fb_err *err)
{
  if (!s || !out)
    return fb_err_set(err, FB_EINVAL, "fb_hull_mesh_generate: NULL argument");
  *out = NULL;
  fb_hull_mesh_params defaults;
  if (!p) {
    const int rc = fb_hull_mesh_params_default(s, &defaults, err);
    if (rc != FB_OK)
      return rc;
    p = &defaults;
  }
  int rc = check_params(p, err);
  if (rc != FB_OK)
    return rc;
  double cx, cz;
  fb_hull_mesh_centroid(s, p, &cx, &cz);
  lines xl = {0}, yl = {0};
  build_mesh coarse = {0}, fine = {0};
  fb_mesh *m = NULL;
  rc = build_lines(s, p, cx, &xl, &yl, err);
  if (rc == FB_OK) {
    const hull_geom g = {p, xl.values, yl.values, xl.n, yl.n};
    rc = mesh_plates(&coarse, &g, err);
  }
  if (rc == FB_OK)
    rc = check_refined_size(&coarse, p->density, err);
  if (rc == FB_OK && p->density > 1)
    rc = refine(&coarse, p->density, &fine, err);
  if (rc == FB_OK)
    rc = to_fb_mesh(p->density > 1 ? &fine : &coarse, cx, cz, &m, err);
  if (rc == FB_OK)
    rc = add_point_sets(m, &coarse, s, &xl, &yl, err);
  if (rc == FB_OK)
    *out = m;
  else
    fb_mesh_free(&m);
  lines_free(&xl);
  lines_free(&yl);
  build_free(&coarse);
  build_free(&fine);
  return rc;
}

/* ---- What a generated mesh was made from. */

/* FNV-1a, 64 bits (G. Fowler, L. C. Noll & K.-P. Vo): a fingerprint of the
 * generator's inputs, not a security measure. */
static void key_bytes(uint64_t *h, const void *data, size_t n)
{
  const unsigned char *b = data;
  for (size_t i = 0; i < n; ++i) {
    *h ^= b[i];
    *h *= 1099511628211u;
  }
}

static void key_double(uint64_t *h, double v)
{
  key_bytes(h, &v, sizeof v);
}

static void key_name(uint64_t *h, const char *s)
{
  key_bytes(h, s ? s : "", (s ? strlen(s) : 0) + 1);
}

uint64_t fb_hull_mesh_key(const fb_scenario *s, const fb_hull_mesh_params *p)
{
  uint64_t h = 14695981039346656037u;
  const double geometry[] = {p->width,   p->height,      p->x_rear,
                             p->x_front, p->nose_length, p->nose_height};
  for (size_t k = 0; k < sizeof geometry / sizeof geometry[0]; ++k)
    key_double(&h, geometry[k]);
  for (size_t k = 0; k < p->nbulkheads; ++k)
    key_double(&h, p->bulkhead_x[k]);
  const int counts[] = {(int)p->nbulkheads, p->side_rows, p->nose_rows, p->nose_rung_divisions,
                        p->density};
  key_bytes(&h, counts, sizeof counts);
  key_double(&h, s->density);
  key_double(&h, s->thickness);
  for (size_t i = 0; i < s->nsections; ++i) {
    key_name(&h, s->section[i].set);
    key_double(&h, s->section[i].density);
    key_double(&h, s->section[i].thickness);
    key_double(&h, s->section[i].nonstructural_mass);
  }
  for (size_t c = 0; c < s->ncorners; ++c) {
    key_name(&h, s->corner[c].name);
    key_double(&h, s->corner[c].x);
    key_double(&h, s->corner[c].y);
  }
  for (size_t b = 0; b < s->nmounts; ++b) {
    key_name(&h, s->mount[b].name);
    key_double(&h, s->mount[b].x);
    key_double(&h, s->mount[b].y);
  }
  for (size_t k = 0; k < s->npoint_masses; ++k) {
    key_name(&h, s->point_mass[k].name);
    key_double(&h, s->point_mass[k].x);
    key_double(&h, s->point_mass[k].y);
  }
  for (size_t k = 0; k < s->nload; ++k) {
    key_double(&h, s->load_x[k]);
    key_double(&h, s->load_y[k]);
  }
  return h;
}
