/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's half-round obstacle (docs/roads.md, "Obstacles"): a
 * semicircular cross-section of radius h, the ride-limit obstacle of the
 * NATO Reference Mobility Model (NRMM). */
#include <stddef.h>
#include <stdio.h>

#include "flexbond/road.h"

#include "road/obstacle.h"

static const fb_param halfround_params[] = {
    {.name = "height",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, height),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "height h, the radius of the half circle (2 h long)",
     .plausible_lo = 0.01,
     .plausible_hi = 1,
     .plausible_why = "ride-limit half-rounds are some 2 to 30 cm high; above 1 m no wheel "
                      "rides over one"},
    ROAD_OBSTACLE_PLACEMENT_PARAMS,
};

/* z = sqrt(h^2 - (u - h)^2) over [0, 2 h]. */
static void halfround_shape(const fb_road_obstacle_params *p, road_shape *out)
{
  const double h = p->height;
  out->piece[0] = (fb_road_piece){FB_ROAD_PIECE_ARC, 0.0, 2.0 * h, {h, 0.0, h, 0.0, 0.0}};
  out->n = 1;
  out->length = 2.0 * h;
  out->rise = 0.0;
  out->scale = 2.0 * h;
}

static const road_obstacle halfround = {
    .shape = halfround_shape,
    .noun = "a %.3g m half-round",
    .noun_of = offsetof(fb_road_obstacle_params, height),
    .edge_hint =
        "the half-round's infinite slope at its base cannot be followed by a point-contact "
        "tire: give the tires an envelope, or cross a `trapezoid` or a `bump` instead"};
ROAD_OBSTACLE_OPS(halfround, halfround);

const fb_road_type fb_road_type_halfround = {
    .name = "halfround",
    .doc = "a half-round obstacle of radius `height` (NRMM's ride-limit obstacle)",
    .param = halfround_params,
    .nparams = sizeof halfround_params / sizeof halfround_params[0],
    .params_size = sizeof(fb_road_obstacle_params),
    .ops = &halfround_ops,
};
