/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's washboard (docs/roads.md, "Obstacles"): a
 * sinusoidal corrugation of some waves, its amplitude growing linearly
 * over the first ramp_waves and falling over the last. */
#include <stddef.h>
#include <stdio.h>

#include "flexbond/road.h"

#include "road/obstacle.h"

static const double PI = 3.14159265358979323846;

static const fb_param washboard_params[] = {
    {.name = "amplitude",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, amplitude),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "the corrugation's amplitude a (crest to trough 2 a)",
     .plausible_lo = 0.001,
     .plausible_hi = 0.2,
     .plausible_why = "washboard corrugations are some 1 to 5 cm high"},
    {.name = "wavelength",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_obstacle_params, wavelength),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "the distance from crest to crest",
     .plausible_lo = 0.1,
     .plausible_hi = 10,
     .plausible_why = "washboard corrugations are some 0.3 to 1 m apart"},
    {.name = "waves",
     .kind = FB_PARAM_WHOLE,
     .store = FB_PARAM_SIZE,
     .offset = offsetof(fb_road_obstacle_params, waves),
     .range = FB_RANGE_LO | FB_RANGE_HI,
     .lo = 1,
     .hi = 100000,
     .need = FB_PARAM_DEFAULT,
     .def = 10,
     .doc = "the waves at full amplitude"},
    {.name = "ramp_waves",
     .kind = FB_PARAM_WHOLE,
     .store = FB_PARAM_SIZE,
     .offset = offsetof(fb_road_obstacle_params, ramp_waves),
     .range = FB_RANGE_LO | FB_RANGE_HI,
     .hi = 100000,
     .need = FB_PARAM_DEFAULT,
     .def = 1,
     .doc = "the waves over which the amplitude grows from 0, and falls back at the end"},
    ROAD_OBSTACLE_PLACEMENT_PARAMS,
};

/* z = A(u) sin(2 pi u / lambda): A grows as a u / (m lambda) over the m
 * ramp waves, is a over the n waves, falls back to 0 over the last m.
 * Each piece holds whole waves, so sin is 0 at its joints and z and its
 * slope are continuous there (only z'' jumps). */
static void washboard_shape(const fb_road_obstacle_params *p, road_shape *out)
{
  const double a = p->amplitude, lambda = p->wavelength, k = 2.0 * PI / lambda;
  const double ramp = (double)p->ramp_waves * lambda, full = (double)p->waves * lambda;
  const double grow = ramp > 0 ? a / ramp : 0.0;
  out->n = 0;
  if (ramp > 0)
    out->piece[out->n++] =
        (fb_road_piece){FB_ROAD_PIECE_WAVE, 0.0, ramp, {0.0, 0.0, grow, k, -0.5 * PI}};
  out->piece[out->n++] =
      (fb_road_piece){FB_ROAD_PIECE_WAVE, ramp, ramp + full, {0.0, a, 0.0, k, -0.5 * PI}};
  if (ramp > 0)
    out->piece[out->n++] = (fb_road_piece){
        FB_ROAD_PIECE_WAVE, ramp + full, ramp + full + ramp, {0.0, a, -grow, k, -0.5 * PI}};
  out->length = ramp + full + ramp;
  out->rise = 0.0;
  out->scale = lambda;
}

static const road_obstacle washboard = {.shape = washboard_shape,
                                        .noun = "a %.3g m washboard",
                                        .noun_of =
                                            offsetof(fb_road_obstacle_params, amplitude)};
ROAD_OBSTACLE_OPS(washboard, washboard);

const fb_road_type fb_road_type_washboard = {
    .name = "washboard",
    .doc = "a washboard: a sinusoidal corrugation, its amplitude ramped in and out",
    .param = washboard_params,
    .nparams = sizeof washboard_params / sizeof washboard_params[0],
    .params_size = sizeof(fb_road_obstacle_params),
    .ops = &washboard_ops,
};
