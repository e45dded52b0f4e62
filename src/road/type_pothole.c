/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's pothole (docs/roads.md, "Obstacles"): a dip of a
 * depth and length, rectangular (vertical walls, flat floor) or rounded
 * (a circular arc through its two rims). */
#include <stddef.h>
#include <stdio.h>

#include "flexbond/road.h"

#include "road/obstacle.h"

enum { POTHOLE_RECTANGULAR = 0, POTHOLE_ROUNDED = 1 };

static const fb_param pothole_params[] = {
    {.name = "depth",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, depth),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "the pothole's depth below the road",
     .plausible_lo = 0.005,
     .plausible_hi = 1,
     .plausible_why = "potholes are some 2 to 30 cm deep; a hole over 1 m deep is a ditch"},
    {.name = "length",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, length),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "its length along the track, rim to rim",
     .plausible_lo = 0.05,
     .plausible_hi = 10,
     .plausible_why = "potholes are some 0.1 to 2 m long"},
    {.name = "shape",
     .kind = FB_PARAM_CHOICE,
     .store = FB_PARAM_INT,
     .offset = offsetof(fb_road_obstacle_params, shape),
     .need = FB_PARAM_DEFAULT,
     .def = POTHOLE_ROUNDED,
     .choices = fb_road_pothole_shapes,
     .doc = "rectangular: vertical walls and a flat floor; rounded: a circular dip, no deeper "
            "than half its length"},
    ROAD_OBSTACLE_PLACEMENT_PARAMS,
};

/* Rectangular: z = -d over [0, L]. Rounded: the circle through (0, 0),
 * (L / 2, -d) and (L, 0), of radius R = (L^2 / 4 + d^2) / (2 d) and
 * centre (L / 2, R - d), its lower half. */
static void pothole_shape(const fb_road_obstacle_params *p, road_shape *out)
{
  const double d = p->depth, len = p->length;
  const double r = (0.25 * len * len + d * d) / (2.0 * d);
  out->piece[0] =
      p->shape == POTHOLE_RECTANGULAR
          ? (fb_road_piece){FB_ROAD_PIECE_LINE, 0.0, len, {-d, 0.0, 0.0, 0, 0}}
          : (fb_road_piece){FB_ROAD_PIECE_ARC, 0.0, len, {0.5 * len, r - d, -r, 0, 0}};
  out->n = 1;
  out->length = len;
  out->rise = 0.0;
  /* Rounded: a dip as a bump of its length; its walls' height stands
   * for their width. */
  out->scale = p->shape == POTHOLE_ROUNDED || len < d ? len : d;
}

/* A rounded pothole deeper than half its length would be more than a
 * half circle, no height function of s. */
static int pothole_check(const fb_road_obstacle_params *p, fb_err *err)
{
  if (p->shape != POTHOLE_ROUNDED || p->depth <= 0.5 * p->length)
    return FB_OK;
  return road_obstacle_refuse(
      err, "depth",
      "a rounded pothole's walls are an arc of a circle through its rims: it is at most "
      "half its length deep (%g m; got %g m)",
      0.5 * p->length, p->depth);
}

static const road_obstacle pothole = {
    .shape = pothole_shape,
    .check = pothole_check,
    .noun = "a %.3g m deep pothole",
    .noun_of = offsetof(fb_road_obstacle_params, depth),
    .edge_hint =
        "the pothole's vertical walls cannot be followed by a point-contact tire: make it "
        "`shape: rounded` and less deep than half its length, or give the tires an envelope"};
ROAD_OBSTACLE_OPS(pothole, pothole);

const fb_road_type fb_road_type_pothole = {
    .name = "pothole",
    .doc = "a pothole, rectangular or rounded",
    .param = pothole_params,
    .nparams = sizeof pothole_params / sizeof pothole_params[0],
    .params_size = sizeof(fb_road_obstacle_params),
    .ops = &pothole_ops,
};
