/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's ISO 8608 random road (docs/roads.md). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>

#include "flexbond/road.h"

static const char *const random_classes[] = {"A", "B", "C", "D", "E", "F", "G", "H", NULL};
static const double random_band[] = {0.011, 2.83};

static const fb_param random_params[] = {
    {.name = "class",
     .kind = FB_PARAM_CHOICE,
     .store = FB_PARAM_INT,
     .offset = offsetof(fb_road_random_params, road_class),
     .need = FB_PARAM_OPTIONAL,
     .choices = random_classes,
     .doc = "road class: Gd(n0) = 16e-6 m^3 for A, times 4 per class (or `rms`)"},
    {.name = "rms",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_random_params, rms),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_OPTIONAL,
     .doc = "r.m.s. height of each track over the band, in place of `class`: "
            "Gd(n0) = rms^2 / (n0^2 (1/n_min - 1/n_max))",
     /* Classes A to H over the default band: 3.8 mm to 0.49 m. */
     .plausible_lo = 0.001,
     .plausible_hi = 0.5,
     .plausible_why = "ISO 8608's classes A to H span 3.8 mm to 0.49 m over its band"},
    {.name = "seed",
     .kind = FB_PARAM_WHOLE,
     .store = FB_PARAM_U64,
     .offset = offsetof(fb_road_random_params, seed),
     /* Whole numbers a double holds exactly, as every front end reads
      * numbers. */
     .range = FB_RANGE_LO | FB_RANGE_HI,
     .hi = 9007199254740992.0,
     .need = FB_PARAM_REQUIRED,
     .doc = "the same seed gives the same road"},
    {.name = "band",
     .kind = FB_PARAM_REALS,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_random_params, band),
     .count = 2,
     .unit = "cycles/m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_DEFAULT,
     .def_list = random_band,
     .doc = "spatial frequency band `[n_min, n_max]` of the harmonics"},
    {.name = "harmonics",
     .kind = FB_PARAM_WHOLE,
     .store = FB_PARAM_SIZE,
     .offset = offsetof(fb_road_random_params, harmonics),
     .range = FB_RANGE_LO | FB_RANGE_HI,
     .lo = 1,
     .hi = (double)FB_ROAD_ISO8608_MAX_HARMONICS,
     .need = FB_PARAM_DEFAULT,
     .def = 1024,
     .doc = "harmonics per track (the run's time grows with them)",
     .why = "each is a sine per track in every evaluation of the road; docs/roads.md, "
            "\"Limits\""},
    {.name = "fade_in",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_random_params, fade_in),
     .unit = "m",
     .range = FB_RANGE_LO,
     .need = FB_PARAM_DEFAULT,
     .doc = "the height fades in over the first metres"},
    {.name = "front_start",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_random_params, front_start),
     .unit = "m",
     .need = FB_PARAM_DEFAULT,
     .doc = "the first corner's wheel's position on its track at t = 0"},
};

/* Neither class nor rms until given. */
static void random_init(void *params)
{
  fb_road_random_params *p = params;
  p->road_class = -1;
  p->rms = NAN;
}

/* Exactly one of class and rms. */
static int random_prepare(void *params, fb_err *err)
{
  const fb_road_random_params *p = params;
  const int by_class = p->road_class >= 0, by_rms = !isnan(p->rms);
  if (by_class == by_rms)
    return fb_err_set(err, FB_EINVAL, "give exactly one of class and rms (%s)",
                      by_class ? "both are given" : "neither is given"),
           fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, by_class ? "rms" : "class"), FB_EINVAL;
  return FB_OK;
}

static int random_iso(const void *params, fb_road_iso8608_params *out)
{
  const fb_road_random_params *p = params;
  fb_road_iso8608_defaults(out);
  if (!isnan(p->rms)) { /* the PSD's level from the r.m.s., the class nearest to it */
    out->gd0 = fb_road_iso8608_rms_gd0(p->rms, p->band[0], p->band[1]);
    out->road_class = fb_road_iso8608_class_of(out->gd0);
  } else {
    out->road_class = (char)('A' + p->road_class);
  }
  out->seed = p->seed;
  out->n_min = p->band[0];
  out->n_max = p->band[1];
  out->nharmonics = p->harmonics;
  out->fade_length = p->fade_in;
  return 1;
}

static int random_check(const void *params, const fb_road_layout *l, fb_err *err)
{
  (void)l;
  const fb_road_random_params *p = params;
  if (!(p->band[1] > p->band[0]))
    return fb_err_set(err, FB_EINVAL, "n_max must be above n_min (got [%g, %g] cycles/m)",
                      p->band[0], p->band[1]),
           fb_err_set_part(err, 0, 0, 1, "band"), FB_EINVAL;
  return FB_OK;
}

static int random_make(const void *params, const fb_road_layout *l, fb_road **out, fb_err *err)
{
  (void)l;
  fb_road_iso8608_params iso;
  random_iso(params, &iso);
  return fb_road_new_iso8608(&iso, out, err);
}

static double random_wheel_start(const void *params, const fb_road_layout *l, double x,
                                 double y)
{
  (void)y;
  return ((const fb_road_random_params *)params)->front_start - l->first_x + x;
}

/* The band's top: no harmonic lies above it. */
static double random_top_hz(const void *params, double speed)
{
  return speed * ((const fb_road_random_params *)params)->band[1];
}

static void random_phrase(const void *params, char *buf, size_t n)
{
  const fb_road_random_params *r = params;
  if (!isnan(r->rms))
    snprintf(buf, n, "on the ISO 8608 road of %.3g mm r.m.s.", r->rms * 1e3);
  else
    snprintf(buf, n, "on the ISO 8608 class %c road", 'A' + r->road_class);
}

static const fb_road_type_ops random_ops = {.init = random_init,
                                            .prepare = random_prepare,
                                            .check = random_check,
                                            .make = random_make,
                                            .wheel_start = random_wheel_start,
                                            .top_hz = random_top_hz,
                                            .random = random_iso,
                                            .phrase = random_phrase};

const fb_road_type fb_road_type_iso8608 = {
    .name = "iso8608",
    .doc = "an ISO 8608 random road (docs/roads.md)",
    .param = random_params,
    .nparams = sizeof random_params / sizeof random_params[0],
    .params_size = sizeof(fb_road_random_params),
    .ops = &random_ops,
};
