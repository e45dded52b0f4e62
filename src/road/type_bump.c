/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's oblique (1 - cos) bump (docs/roads.md): the paper's
 * obstacle, or a Brazilian speed bump by its type. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "flexbond/road.h"

#include "road/road_internal.h"

const char *const fb_road_bump_types[] = {"I", "II", "A", "B", NULL};

static const double PI = 3.14159265358979323846;

static const fb_param bump_params[] = {
    {.name = "height",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_bump_params, height),
     .unit = "m",
     .range = FB_RANGE_LO,
     .need = FB_PARAM_OPTIONAL,
     .doc = "bump height h, with `length` (0: a flat road)",
     .plausible_lo = 0,
     .plausible_hi = 1.5,
     .plausible_why = "obstacles a wheeled vehicle crosses are at most about 1.5 m high"},
    {.name = "length",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_bump_params, length),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_OPTIONAL,
     .doc = "bump length L along each wheel's path, with `height`",
     .plausible_lo = 0.01,
     .plausible_hi = 100,
     .plausible_why = "a bump is 1 cm to 100 m long"},
    {.name = "type",
     .kind = FB_PARAM_CHOICE,
     .store = FB_PARAM_INT,
     .offset = offsetof(fb_road_bump_params, type),
     .need = FB_PARAM_OPTIONAL,
     .choices = fb_road_bump_types,
     .doc = "a Brazilian speed bump instead of height and length: I 1.50 x 0.08 m, II 3.70 x "
            "0.10 m (B, A: aliases)"},
    {.name = "angle_deg",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_bump_params, angle),
     .unit = "deg",
     .scale = PI / 180,
     .range = FB_RANGE_LO | FB_RANGE_HI | FB_RANGE_HI_OPEN,
     .hi = 90,
     .need = FB_PARAM_REQUIRED,
     .doc = "angle of the leading edge to the lateral axis, left side first"},
    {.name = "first_contact",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_bump_params, first_contact),
     .unit = "s",
     .range = FB_RANGE_LO,
     .need = FB_PARAM_REQUIRED,
     .doc = "time the first corner's wheel meets the leading edge"},
};

/* Height and length left out until given, no type. */
static void bump_init(void *params)
{
  fb_road_bump_params *b = params;
  b->height = b->length = NAN;
  b->type = -1;
}

/* Either a type or both height and length. */
static int bump_prepare(void *params, fb_err *err)
{
  fb_road_bump_params *b = params;
  const int height = !isnan(b->height), length = !isnan(b->length);
  if (b->type >= 0 && (height || length))
    return fb_err_set(err, FB_EINVAL, "give either a type or height and length, not both"),
           fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "type"), FB_EINVAL;
  if (b->type < 0 && !(height && length))
    return fb_err_set(err, FB_EINVAL, "a bump needs its %s (or a type)",
                      height ? "length" : "height"),
           fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, height ? "length" : "height"),
           FB_EINVAL;
  if (b->type < 0)
    return FB_OK;
  const int rc = fb_road_speed_bump(fb_road_bump_types[b->type], &b->height, &b->length, err);
  return rc ? (fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "type"), rc) : FB_OK;
}

static int bump_make(const void *params, const fb_road_layout *l, fb_road **out, fb_err *err)
{
  const fb_road_bump_params *b = params;
  return fb_road_new_oblique_bump(b->height, b->length, b->angle, l->track_width, out, err);
}

static double bump_wheel_start(const void *params, const fb_road_layout *l, double x, double y)
{
  const fb_road_bump_params *b = params;
  return road_oblique_wheel_start(b->angle, b->first_contact, l, x, y);
}

static void bump_feature(const void *params, const fb_road_layout *l, int track, double *begin,
                         double *end)
{
  const fb_road_bump_params *b = params;
  *begin = road_oblique_edge(b->angle, l, track);
  *end = *begin + b->length;
}

/* The (1 - cos) pulse's spectrum is down 98 % at 2 / length cycles/m. */
static double bump_top_hz(const void *params, double speed)
{
  const fb_road_bump_params *b = params;
  return b->length > 0 ? 2.0 * speed / b->length : 0.0;
}

/* A height of 0 is a flat road. */
static void bump_phrase(const void *params, char *buf, size_t n)
{
  const fb_road_bump_params *b = params;
  snprintf(buf, n, "%s", b->height > 0 ? "over the bump" : "on the flat road");
}

static const fb_road_type_ops bump_ops = {.init = bump_init,
                                          .prepare = bump_prepare,
                                          .make = bump_make,
                                          .wheel_start = bump_wheel_start,
                                          .feature = bump_feature,
                                          .top_hz = bump_top_hz,
                                          .phrase = bump_phrase};

const fb_road_type fb_road_type_bump = {
    .name = "bump",
    .doc = "the paper's oblique (1 - cos) bump",
    .param = bump_params,
    .nparams = sizeof bump_params / sizeof bump_params[0],
    .params_size = sizeof(fb_road_bump_params),
    .ops = &bump_ops,
};
