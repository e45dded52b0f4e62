/* SPDX-License-Identifier: BSD-3-Clause */
/* Road wheel functions as data and back (flexbond/road.h): what a wheel's
 * time function was made of, read from its own context, and the road
 * rebuilt from that, so that a model file can hold a road source. */
#include <math.h>
#include <string.h>

#include "flexbond/road.h"

#include "road/road_internal.h"

int fb_road_new_profile(size_t n, const double *s, const double *z_left, const double *z_right,
                        fb_road **out, fb_err *err)
{
  if (!out || !s || !z_left || !z_right)
    return fb_err_set(err, FB_EINVAL, "road profile: NULL argument");
  *out = NULL;
  if (n < 2)
    return fb_err_set(err, FB_EINVAL, "road profile: needs at least 2 knots (got %zu)", n);
  for (size_t i = 0; i < n; ++i) {
    if (!isfinite(s[i]) || !isfinite(z_left[i]) || !isfinite(z_right[i]))
      return fb_err_set(err, FB_EINVAL, "road profile: knot %zu is not finite", i + 1);
    if (i > 0 && !(s[i] > s[i - 1]))
      return fb_err_set(err, FB_EINVAL,
                        "road profile: knot %zu: s = %g does not exceed the previous %g "
                        "(it must be strictly increasing)",
                        i + 1, s[i], s[i - 1]);
  }
  const road_track track = {ROAD_PCHIP, n, {0.0, 0.0, 0.0}};
  int rc = road_alloc(&track, &track, out, err);
  if (rc)
    return rc;
  const double *z[FB_ROAD_NTRACKS] = {z_left, z_right};
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k) {
    double *data = (*out)->data[k];
    memcpy(data, s, n * sizeof *data);
    memcpy(data + n, z[k], n * sizeof *data);
    road_pchip_slopes(n, data, data + n, data + 2 * n);
  }
  return FB_OK;
}

int fb_road_wheel_describe(const fb_tfun *f, fb_road_wheel_info *out)
{
  fb_tfun_info ti;
  fb_tfun_describe(f, &ti);
  if (ti.kind != FB_TFUN_CALLBACK ||
      (ti.fn != road_wheel_height && ti.fn != road_wheel_velocity))
    return 0;
  const road_wheel_ctx *w = ti.ctx;
  memset(out, 0, sizeof *out);
  out->velocity = ti.fn == road_wheel_velocity;
  out->speed = w->speed;
  out->s0 = w->s0;
  if (w->origin.iso8608) {
    out->kind = FB_ROAD_WHEEL_ISO8608;
    out->iso = w->origin.iso;
    out->track = w->origin.track;
  } else if (w->track.kind == ROAD_BUMP) {
    out->kind = FB_ROAD_WHEEL_BUMP;
    out->bump_start = w->track.param[0];
    out->bump_height = w->track.param[1];
    out->bump_length = w->track.param[2];
  } else if (w->track.kind == ROAD_PCHIP) {
    /* The slopes follow from the knots (road_pchip_slopes), as when the
     * profile was read. */
    out->kind = FB_ROAD_WHEEL_PROFILE;
    out->nknots = w->track.n;
    out->knot_s = w->data;
    out->knot_z = w->data + w->track.n;
  } else if (w->track.kind == ROAD_PIECES) {
    out->kind = FB_ROAD_WHEEL_PIECES;
    out->npieces = w->track.n;
    out->pieces = road_pieces_of(w->data);
  } else {
    return 0; /* harmonics not made by fb_road_new_iso8608: none exist */
  }
  return 1;
}

/* The road info describes, and which of its tracks the wheel runs on. */
static int info_road(const fb_road_wheel_info *info, fb_road **road, int *track, fb_err *err)
{
  *track = FB_ROAD_LEFT;
  switch (info->kind) {
  case FB_ROAD_WHEEL_BUMP:
    return fb_road_new_bump(info->bump_height, info->bump_length, info->bump_start,
                            info->bump_start, road, err);
  case FB_ROAD_WHEEL_ISO8608:
    if (info->track != FB_ROAD_LEFT && info->track != FB_ROAD_RIGHT)
      return fb_err_set(err, FB_EINVAL, "road wheel: track must be left or right (got %d)",
                        info->track);
    *track = info->track;
    return fb_road_new_iso8608(&info->iso, road, err);
  case FB_ROAD_WHEEL_PROFILE:
    return fb_road_new_profile(info->nknots, info->knot_s, info->knot_z, info->knot_z, road,
                               err);
  case FB_ROAD_WHEEL_PIECES:
    return fb_road_new_pieces(info->npieces, info->pieces, info->npieces, info->pieces, road,
                              err);
  }
  return fb_err_set(err, FB_EINVAL, "road wheel: unknown road kind %d", (int)info->kind);
}

int fb_road_wheel_new(const fb_road_wheel_info *info, fb_tfun **out, fb_err *err)
{
  *out = NULL;
  fb_road *road = NULL;
  int track = FB_ROAD_LEFT;
  int rc = info_road(info, &road, &track, err);
  if (!rc)
    rc = info->velocity ? fb_road_wheel_velocity(road, track, info->speed, info->s0, out, err)
                        : fb_road_wheel_height(road, track, info->speed, info->s0, out, err);
  fb_road_free(&road);
  return rc;
}
