/* SPDX-License-Identifier: BSD-3-Clause */
/* (1 - cos) bumps: the paper's oblique bump and the Brazilian speed bumps
 * (docs/roads.md). */
#include <math.h>
#include <string.h>

#include "flexbond/road.h"

#include "road/road_internal.h"

static const double HALF_PI = 1.57079632679489661923;

static int check_finite(const char *what, double v, fb_err *err)
{
  if (!isfinite(v))
    return fb_err_set(err, FB_EINVAL, "bump: %s is not finite (got %g)", what, v);
  return FB_OK;
}

int fb_road_new_bump(double height, double length, double start_left, double start_right,
                     fb_road **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "bump: out is NULL");
  *out = NULL;
  int rc = check_finite("height", height, err);
  if (!rc && !(isfinite(length) && length > 0.0))
    rc = fb_err_set(err, FB_EINVAL, "bump: length must be > 0 m (got %g)", length);
  if (!rc)
    rc = check_finite("left start", start_left, err);
  if (!rc)
    rc = check_finite("right start", start_right, err);
  if (rc)
    return rc;
  road_track left = {ROAD_BUMP, 0, {start_left, height, length}};
  road_track right = {ROAD_BUMP, 0, {start_right, height, length}};
  return road_alloc(&left, &right, out, err);
}

/* The leading edge crosses the left track at s = 0; a point track_width
 * to its right lies track_width tan(angle) further along the path. */
int fb_road_new_oblique_bump(double height, double length, double angle, double track_width,
                             fb_road **out, fb_err *err)
{
  if (out)
    *out = NULL;
  if (!(isfinite(angle) && fabs(angle) < HALF_PI))
    return fb_err_set(err, FB_EINVAL, "bump: angle must be in (-90, 90) deg (got %g deg)",
                      angle / HALF_PI * 90.0);
  if (!(isfinite(track_width) && track_width > 0.0))
    return fb_err_set(err, FB_EINVAL, "bump: track width must be > 0 m (got %g)", track_width);
  return fb_road_new_bump(height, length, 0.0, track_width * tan(angle), out, err);
}

int fb_road_speed_bump(const char *type, double *height, double *length, fb_err *err)
{
  /* CONTRAN resolution 39/1998, art. 3 (types I, II); resolution
   * 600/2016 (types B, A): length and maximum height. */
  static const struct {
    const char *name;
    double height, length;
  } types[] = {{"I", 0.08, 1.50}, {"II", 0.10, 3.70}, {"B", 0.08, 1.50}, {"A", 0.10, 3.70}};
  for (size_t i = 0; type && i < sizeof types / sizeof types[0]; ++i)
    if (strcmp(type, types[i].name) == 0) {
      *height = types[i].height;
      *length = types[i].length;
      return FB_OK;
    }
  return fb_err_set(err, FB_EINVAL,
                    "speed bump type '%s': expected I (1.50 m x 0.08 m) or II (3.70 m x 0.10 "
                    "m) (CONTRAN 39/1998; also B and A, CONTRAN 600/2016)",
                    type ? type : "(null)");
}
