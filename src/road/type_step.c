/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's step (docs/roads.md, "Obstacles"): the road rises
 * (or falls) by a height and stays there, over a ramp or at a vertical
 * face. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "flexbond/road.h"

#include "road/obstacle.h"

static const fb_param step_params[] = {
    {.name = "height",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, height),
     .unit = "m",
     .need = FB_PARAM_REQUIRED,
     .doc = "the step's height: > 0 up, < 0 down",
     .plausible_lo = -1,
     .plausible_hi = 1,
     .plausible_why = "kerbs and steps a wheel drives over are at most some 0.5 m"},
    {.name = "ramp_length",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, ramp_length),
     .unit = "m",
     .range = FB_RANGE_LO,
     .need = FB_PARAM_DEFAULT,
     .def = 0.1,
     .doc = "horizontal length of the ramp up (down); 0: a vertical face, which only a tire "
            "with an envelope follows"},
    ROAD_OBSTACLE_PLACEMENT_PARAMS,
};

/* z = h u / r over [0, r], then h; r = 0: a face at u = 0. */
static void step_shape(const fb_road_obstacle_params *p, road_shape *out)
{
  const double h = p->height, r = p->ramp_length;
  out->n = 0;
  if (r > 0)
    out->piece[out->n++] = (fb_road_piece){FB_ROAD_PIECE_LINE, 0.0, r, {0.0, h / r, 0, 0, 0}};
  out->length = r;
  out->rise = h;
  out->scale = r > 0 ? r : fabs(h);
}

static int step_check(const fb_road_obstacle_params *p, fb_err *err)
{
  if (p->height != 0.0)
    return FB_OK;
  return road_obstacle_refuse(
      err, "height", "a step of height 0 is no step: give it a height (> 0 up, < 0 down)");
}

static const road_obstacle step = {
    .shape = step_shape,
    .check = step_check,
    .noun = "a step of %+.3g m",
    .noun_of = offsetof(fb_road_obstacle_params, height),
    .edge_hint = "the step's vertical face cannot be followed by a point-contact tire: give it "
                 "a ramp (ramp_length > 0), or give the tires an envelope"};
ROAD_OBSTACLE_OPS(step, step);

const fb_road_type fb_road_type_step = {
    .name = "step",
    .doc = "a step up or down, over a ramp or at a vertical face",
    .param = step_params,
    .nparams = sizeof step_params / sizeof step_params[0],
    .params_size = sizeof(fb_road_obstacle_params),
    .ops = &step_ops,
};
