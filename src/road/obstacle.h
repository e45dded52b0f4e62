/* SPDX-License-Identifier: BSD-3-Clause */
/* What the obstacle types of the road gallery share (obstacle.c;
 * docs/roads.md, "Obstacles"): their placement parameters (the bump's
 * oblique crossing, the track, a series), and the ops that place a
 * shape, each type giving only its shape, its words and its own checks.
 *
 * A shape is one obstacle in its own coordinate u (m) from its leading
 * edge, rising from z = 0: pieces of a piecewise track
 * (fb_road_new_pieces) in u. */
#ifndef FLEXBOND_ROAD_OBSTACLE_H
#define FLEXBOND_ROAD_OBSTACLE_H

#include <stddef.h>

#include "flexbond/road.h"

/* Most pieces of one shape (a rounded trapezoid: ramp, arc, top, arc,
 * ramp). */
#define ROAD_SHAPE_MAX 5
/* Most obstacles in a series. */
#define ROAD_OBSTACLE_COUNT_MAX 1000

typedef struct road_shape {
  fb_road_piece piece[ROAD_SHAPE_MAX]; /* in u, end to end from u = 0 */
  size_t n;
  double length; /* m, where the obstacle ends (its last piece's end; 0: a face) */
  double rise;   /* m, its height after it ends (a step's) */
  double scale;  /* m, its shortest dimension: the wavelength it puts into a wheel */
} road_shape;

/* What one obstacle type is beyond its parameters. */
typedef struct road_obstacle {
  /* After road_obstacle_init: the type's own optional values left out
   * (NULL: none). */
  void (*init)(fb_road_obstacle_params *p);
  void (*shape)(const fb_road_obstacle_params *p, road_shape *out);
  /* Its values' own rules (NULL: none), as fb_road_type_ops.check. */
  int (*check)(const fb_road_obstacle_params *p, fb_err *err);
  /* The obstacle in words, a printf format of one double: the value at
   * noun_of in the block ("a %.3g m half-round" of the height). */
  const char *noun;
  size_t noun_of;
  /* fb_road_type_ops.edge_hint's text; NULL for a shape without edges. */
  const char *edge_hint;
} road_obstacle;

/* The placement parameters every obstacle type declares, after its
 * shape's: angle_deg, first_contact, track, count, spacing. */
#define ROAD_OBSTACLE_PLACEMENT_PARAMS                                                         \
  {.name = "angle_deg",                                                                        \
   .kind = FB_PARAM_REAL,                                                                      \
   .store = FB_PARAM_DOUBLE,                                                                   \
   .offset = offsetof(fb_road_obstacle_params, angle),                                         \
   .unit = "deg",                                                                              \
   .scale = 3.14159265358979323846 / 180,                                                      \
   .range = FB_RANGE_LO | FB_RANGE_HI | FB_RANGE_HI_OPEN,                                      \
   .hi = 90,                                                                                   \
   .need = FB_PARAM_DEFAULT,                                                                   \
   .doc = "angle of the leading edge to the lateral axis, left side first (the bump's)"},      \
      {.name = "first_contact",                                                                \
       .kind = FB_PARAM_REAL,                                                                  \
       .store = FB_PARAM_DOUBLE,                                                               \
       .offset = offsetof(fb_road_obstacle_params, first_contact),                             \
       .unit = "s",                                                                            \
       .range = FB_RANGE_LO,                                                                   \
       .need = FB_PARAM_REQUIRED,                                                              \
       .doc = "time the first corner's wheel meets the leading edge's line (the bump's)"},     \
      {.name = "track",                                                                        \
       .kind = FB_PARAM_CHOICE,                                                                \
       .store = FB_PARAM_INT,                                                                  \
       .offset = offsetof(fb_road_obstacle_params, track),                                     \
       .need = FB_PARAM_DEFAULT,                                                               \
       .choices = fb_road_obstacle_tracks,                                                     \
       .doc = "the track the obstacle lies on; the other is flat"},                            \
      {.name = "count",                                                                        \
       .kind = FB_PARAM_WHOLE,                                                                 \
       .store = FB_PARAM_SIZE,                                                                 \
       .offset = offsetof(fb_road_obstacle_params, count),                                     \
       .range = FB_RANGE_LO | FB_RANGE_HI,                                                     \
       .lo = 1,                                                                                \
       .hi = ROAD_OBSTACLE_COUNT_MAX,                                                          \
       .need = FB_PARAM_DEFAULT,                                                               \
       .def = 1,                                                                               \
       .doc = "obstacles in a series of equal ones, `spacing` apart"},                         \
  {                                                                                            \
    .name = "spacing", .kind = FB_PARAM_REAL, .store = FB_PARAM_DOUBLE,                        \
    .offset = offsetof(fb_road_obstacle_params, spacing), .unit = "m",                         \
    .range = FB_RANGE_LO | FB_RANGE_LO_OPEN, .need = FB_PARAM_OPTIONAL,                        \
    .doc = "from one leading edge to the next along a track, at least an obstacle's length "   \
           "(with `count` > 1)",                                                               \
    .plausible_lo = 0.05, .plausible_hi = 1000,                                                \
    .plausible_why = "obstacles in a series are some centimetres to a kilometre apart"         \
  }

/* Refuses the value of parameter field with a printf-formatted message:
 * FB_EINVAL, field in err->part.field (the check ops' errors). */
int road_obstacle_refuse(fb_err *err, const char *field, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Leaves spacing, ramp_down and ramp_angle out (NaN), then o's init:
 * the init op of every obstacle type. */
void road_obstacle_init(const road_obstacle *o, void *params);

/* 1 if the obstacle of block params lies on track (its `track` is both
 * or that one), 0 if the track is flat. */
int road_obstacle_on_track(const void *params, int track);
/* The ops of an obstacle type o, each the shared one for o's shape. */
int road_obstacle_check(const road_obstacle *o, const void *params, const fb_road_layout *l,
                        fb_err *err);
int road_obstacle_make(const road_obstacle *o, const void *params, const fb_road_layout *l,
                       fb_road **out, fb_err *err);
double road_obstacle_wheel_start(const void *params, const fb_road_layout *l, double x,
                                 double y);
void road_obstacle_feature(const road_obstacle *o, const void *params, const fb_road_layout *l,
                           int track, double *begin, double *end);
double road_obstacle_top_hz(const road_obstacle *o, const void *params, double speed);
void road_obstacle_phrase(const road_obstacle *o, const void *params, char *buf, size_t n);

/* An ops table for obstacle type o, as static functions named after
 * prefix (one line per type, rather than seven wrappers each). */
#define ROAD_OBSTACLE_OPS(prefix, o)                                                           \
  static void prefix##_init_op(void *p)                                                        \
  {                                                                                            \
    road_obstacle_init(&(o), p);                                                               \
  }                                                                                            \
  static int prefix##_check_op(const void *p, const fb_road_layout *l, fb_err *err)            \
  {                                                                                            \
    return road_obstacle_check(&(o), p, l, err);                                               \
  }                                                                                            \
  static int prefix##_make_op(const void *p, const fb_road_layout *l, fb_road **out,           \
                              fb_err *err)                                                     \
  {                                                                                            \
    return road_obstacle_make(&(o), p, l, out, err);                                           \
  }                                                                                            \
  static void prefix##_feature_op(const void *p, const fb_road_layout *l, int track,           \
                                  double *begin, double *end)                                  \
  {                                                                                            \
    road_obstacle_feature(&(o), p, l, track, begin, end);                                      \
  }                                                                                            \
  static double prefix##_top_hz_op(const void *p, double speed)                                \
  {                                                                                            \
    return road_obstacle_top_hz(&(o), p, speed);                                               \
  }                                                                                            \
  static const char *prefix##_edge_hint_op(const void *p)                                      \
  {                                                                                            \
    (void)p;                                                                                   \
    return (o).edge_hint;                                                                      \
  }                                                                                            \
  static void prefix##_phrase_op(const void *p, char *buf, size_t n)                           \
  {                                                                                            \
    road_obstacle_phrase(&(o), p, buf, n);                                                     \
  }                                                                                            \
  static const fb_road_type_ops prefix##_ops = {.init = prefix##_init_op,                      \
                                                .check = prefix##_check_op,                    \
                                                .make = prefix##_make_op,                      \
                                                .wheel_start = road_obstacle_wheel_start,      \
                                                .feature = prefix##_feature_op,                \
                                                .top_hz = prefix##_top_hz_op,                  \
                                                .phrase = prefix##_phrase_op,                  \
                                                .edge_hint = prefix##_edge_hint_op}

/* A rise of height h over u in [0, r1], a top of length top, a fall
 * over [r1 + top, r1 + top + r2] (r = 0: a vertical face), its two top
 * edges rounded to radius e (0: sharp; e <= h, and each edge's tangent
 * points within its ramp and the top: road_plateau_fits): the cleat and
 * the trapezoid. */
void road_plateau_shape(double h, double r1, double top, double r2, double e, road_shape *out);
/* NULL if edge radius e fits the plateau, else why not. */
const char *road_plateau_fits(double h, double r1, double top, double r2, double e);

#endif
