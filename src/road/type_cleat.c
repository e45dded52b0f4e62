/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's cleat (docs/roads.md, "Obstacles"): a rectangular
 * bar across the track, of vertical faces unless given ramps, its top
 * edges optionally rounded. */
#include <stddef.h>
#include <stdio.h>

#include "flexbond/road.h"

#include "road/obstacle.h"

static const fb_param cleat_params[] = {
    {.name = "height",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, height),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "the cleat's height",
     .plausible_lo = 0.005,
     .plausible_hi = 1,
     .plausible_why = "cleats are some 1 to 20 cm high; an obstacle above 1 m is no cleat"},
    {.name = "length",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, length),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "the length of its top along the track",
     .plausible_lo = 0.005,
     .plausible_hi = 10,
     .plausible_why = "cleats are some centimetres long"},
    {.name = "ramp_length",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, ramp_length),
     .unit = "m",
     .range = FB_RANGE_LO,
     .need = FB_PARAM_DEFAULT,
     .def = 0.02,
     .doc = "horizontal length of each chamfer up to and down from the top; 0: vertical faces, "
            "which only a tire with an envelope follows"},
    {.name = "edge_radius",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, edge_radius),
     .unit = "m",
     .range = FB_RANGE_LO,
     .need = FB_PARAM_DEFAULT,
     .doc = "radius of the top's two edges (0: sharp)"},
    ROAD_OBSTACLE_PLACEMENT_PARAMS,
};

static void cleat_shape(const fb_road_obstacle_params *p, road_shape *out)
{
  road_plateau_shape(p->height, p->ramp_length, p->length, p->ramp_length, p->edge_radius, out);
}

static int cleat_check(const fb_road_obstacle_params *p, fb_err *err)
{
  const char *why =
      road_plateau_fits(p->height, p->ramp_length, p->length, p->ramp_length, p->edge_radius);
  if (!why)
    return FB_OK;
  return road_obstacle_refuse(err, "edge_radius", "%s (edge radius %g m)", why, p->edge_radius);
}

static const road_obstacle cleat = {
    .shape = cleat_shape,
    .check = cleat_check,
    .noun = "a %.3g m cleat",
    .noun_of = offsetof(fb_road_obstacle_params, height),
    .edge_hint = "the cleat's vertical faces cannot be followed by a point-contact tire: give "
                 "it ramps (ramp_length > 0), or give the tires an envelope"};
ROAD_OBSTACLE_OPS(cleat, cleat);

const fb_road_type fb_road_type_cleat = {
    .name = "cleat",
    .doc = "a rectangular cleat, its faces vertical or chamfered, its edges sharp or rounded",
    .param = cleat_params,
    .nparams = sizeof cleat_params / sizeof cleat_params[0],
    .params_size = sizeof(fb_road_obstacle_params),
    .ops = &cleat_ops,
};
