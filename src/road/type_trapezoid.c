/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's trapezoid (docs/roads.md, "Obstacles"): a ramp up, a
 * flat top and a ramp down, its ramps given by their lengths or their
 * angle, its top edges optionally rounded. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "flexbond/road.h"

#include "road/obstacle.h"

static const fb_param trapezoid_params[] = {
    {.name = "height",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, height),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "the height of its top",
     .plausible_lo = 0.005,
     .plausible_hi = 1,
     .plausible_why = "an obstacle above 1 m is no wheeled vehicle's"},
    {.name = "top_length",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, length),
     .unit = "m",
     .range = FB_RANGE_LO,
     .need = FB_PARAM_REQUIRED,
     .doc = "the length of its flat top (0: a triangle)",
     .plausible_lo = 0,
     .plausible_hi = 100,
     .plausible_why = "a trapezoidal obstacle's top is at most some metres long"},
    {.name = "ramp_length",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, ramp_length),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_OPTIONAL,
     .doc = "horizontal length of the ramp up (and down, unless `ramp_down`); or "
            "`ramp_angle_deg`"},
    {.name = "ramp_down",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, ramp_down),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_OPTIONAL,
     .doc = "horizontal length of the ramp down, with `ramp_length`"},
    {.name = "ramp_angle_deg",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, ramp_angle),
     .unit = "deg",
     .scale = 3.14159265358979323846 / 180,
     .range = FB_RANGE_LO | FB_RANGE_HI | FB_RANGE_LO_OPEN | FB_RANGE_HI_OPEN,
     .hi = 90,
     .need = FB_PARAM_OPTIONAL,
     .doc = "both ramps' angle to the road, instead of their lengths"},
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

static void trapezoid_init(fb_road_obstacle_params *p)
{
  p->ramp_length = NAN;
}

/* The ramps' lengths: given, or h / tan(angle). */
static void trapezoid_ramps(const fb_road_obstacle_params *p, double *up, double *down)
{
  *up = isnan(p->ramp_angle) ? p->ramp_length : p->height / tan(p->ramp_angle);
  *down = isnan(p->ramp_down) ? *up : p->ramp_down;
}

static void trapezoid_shape(const fb_road_obstacle_params *p, road_shape *out)
{
  double up, down;
  trapezoid_ramps(p, &up, &down);
  road_plateau_shape(p->height, up, p->length, down, p->edge_radius, out);
}

/* Either ramp_length (and perhaps ramp_down) or ramp_angle_deg. */
static int trapezoid_check(const fb_road_obstacle_params *p, fb_err *err)
{
  const int angle = !isnan(p->ramp_angle);
  if (angle && !isnan(p->ramp_length))
    return road_obstacle_refuse(err, "ramp_angle_deg",
                                "give either ramp_angle_deg or ramp_length, not both");
  if (angle && !isnan(p->ramp_down))
    return road_obstacle_refuse(err, "ramp_down",
                                "ramp_angle_deg gives both ramps: leave out ramp_down");
  if (!angle && isnan(p->ramp_length))
    return road_obstacle_refuse(err, "ramp_length",
                                "a trapezoid needs its ramp_length (or ramp_angle_deg)");
  double up, down;
  trapezoid_ramps(p, &up, &down);
  const char *why = road_plateau_fits(p->height, up, p->length, down, p->edge_radius);
  return why ? road_obstacle_refuse(err, "edge_radius", "%s", why) : FB_OK;
}

static const road_obstacle trapezoid = {.init = trapezoid_init,
                                        .shape = trapezoid_shape,
                                        .check = trapezoid_check,
                                        .noun = "a %.3g m trapezoid",
                                        .noun_of = offsetof(fb_road_obstacle_params, height)};
ROAD_OBSTACLE_OPS(trapezoid, trapezoid);

const fb_road_type fb_road_type_trapezoid = {
    .name = "trapezoid",
    .doc = "a trapezoidal obstacle: ramp up, flat top, ramp down",
    .param = trapezoid_params,
    .nparams = sizeof trapezoid_params / sizeof trapezoid_params[0],
    .params_size = sizeof(fb_road_obstacle_params),
    .ops = &trapezoid_ops,
};
