/* SPDX-License-Identifier: BSD-3-Clause */
/* The obstacle types' shared ops (obstacle.h; docs/roads.md,
 * "Obstacles"): a shape placed on its track(s) at the paper's oblique
 * crossing, repeated count times spacing apart, as a piecewise road. */
#include "road/obstacle.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/road.h"

#include "road/road_internal.h"

const char *const fb_road_obstacle_tracks[] = {"both", "left", "right", NULL};
const char *const fb_road_pothole_shapes[] = {"rectangular", "rounded", NULL};

enum { TRACK_BOTH = 0, TRACK_LEFT = 1, TRACK_RIGHT = 2 };

/* The flat metre laid before the first obstacle and after the last, so
 * that a face at either end is a joint between pieces. */
static const double OBSTACLE_LEAD = 1.0;

void road_obstacle_init(const road_obstacle *o, void *params)
{
  fb_road_obstacle_params *p = params;
  p->spacing = p->ramp_down = p->ramp_angle = NAN;
  if (o->init)
    o->init(p);
}

static int on_track(const fb_road_obstacle_params *p, int track)
{
  return p->track == TRACK_BOTH ||
         p->track == (track == FB_ROAD_LEFT ? TRACK_LEFT : TRACK_RIGHT);
}

int road_obstacle_on_track(const void *params, int track)
{
  return on_track(params, track);
}

int road_obstacle_refuse(fb_err *err, const char *field, const char *fmt, ...)
{
  char msg[FB_ERR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  fb_err_set(err, FB_EINVAL, "%s", msg);
  return fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, field), FB_EINVAL;
}

int road_obstacle_check(const road_obstacle *o, const void *params, const fb_road_layout *l,
                        fb_err *err)
{
  (void)l;
  const fb_road_obstacle_params *p = params;
  int rc = o->check ? o->check(p, err) : FB_OK;
  if (rc || p->count < 2)
    return rc;
  road_shape s;
  o->shape(p, &s);
  if (isnan(p->spacing))
    return road_obstacle_refuse(err, "spacing",
                                "a series of obstacles needs their spacing (count is %g)",
                                (double)p->count);
  if (p->spacing < s.length)
    return road_obstacle_refuse(err, "spacing",
                                "the obstacles would overlap: their spacing must be at least "
                                "one's length, %g m (got %g m)",
                                s.length, p->spacing);
  return FB_OK;
}

/* A copy of piece q moved by ds along the track and dz up. */
static fb_road_piece piece_moved(const fb_road_piece *q, double ds, double dz)
{
  fb_road_piece m = *q;
  m.s_begin += ds;
  m.s_end += ds;
  if (m.kind == FB_ROAD_PIECE_ARC)
    m.p[0] += ds; /* the centre's s */
  m.p[m.kind == FB_ROAD_PIECE_ARC ? 1 : 0] += dz;
  return m;
}

static fb_road_piece flat(double s_begin, double s_end, double z)
{
  return (fb_road_piece){FB_ROAD_PIECE_LINE, s_begin, s_end, {z, 0.0, 0.0, 0.0, 0.0}};
}

/* The series' pieces on a track whose leading edge is at base, into
 * out (room for 2 + count (ROAD_SHAPE_MAX + 1)); their number. */
static size_t series_pieces(const fb_road_obstacle_params *p, const road_shape *s, double base,
                            fb_road_piece *out)
{
  size_t n = 0;
  out[n++] = flat(base - OBSTACLE_LEAD, base, 0.0);
  for (size_t k = 0; k < p->count; ++k) {
    const double at = base + (double)k * (p->count > 1 ? p->spacing : 0.0);
    const double z = (double)k * s->rise, end = at + s->length;
    for (size_t i = 0; i < s->n; ++i)
      out[n++] = piece_moved(&s->piece[i], at, z);
    const double next = k + 1 < p->count ? at + p->spacing : end + OBSTACLE_LEAD;
    if (next > end)
      out[n++] = flat(end, next, z + s->rise);
  }
  return n;
}

int road_obstacle_make(const road_obstacle *o, const void *params, const fb_road_layout *l,
                       fb_road **out, fb_err *err)
{
  const fb_road_obstacle_params *p = params;
  *out = NULL;
  road_shape s;
  o->shape(p, &s);
  const size_t room = 2 + p->count * (ROAD_SHAPE_MAX + 1);
  fb_road_piece *piece[FB_ROAD_NTRACKS] = {NULL, NULL};
  size_t n[FB_ROAD_NTRACKS] = {0, 0};
  int rc = FB_OK;
  for (int k = 0; !rc && k < FB_ROAD_NTRACKS; ++k) {
    if (!on_track(p, k))
      continue;
    if (!(piece[k] = malloc(room * sizeof *piece[k])))
      rc = fb_err_set(err, FB_ENOMEM, "out of memory for an obstacle's road");
    else
      n[k] = series_pieces(p, &s, road_oblique_edge(p->angle, l, k), piece[k]);
  }
  if (!rc)
    rc = fb_road_new_pieces(n[0], piece[0], n[1], piece[1], out, err);
  free(piece[0]);
  free(piece[1]);
  return rc;
}

double road_obstacle_wheel_start(const void *params, const fb_road_layout *l, double x,
                                 double y)
{
  const fb_road_obstacle_params *p = params;
  return road_oblique_wheel_start(p->angle, p->first_contact, l, x, y);
}

/* From the leading edge to the last obstacle's end; on a flat track, an
 * empty stretch at the edge's line. */
void road_obstacle_feature(const road_obstacle *o, const void *params, const fb_road_layout *l,
                           int track, double *begin, double *end)
{
  const fb_road_obstacle_params *p = params;
  road_shape s;
  o->shape(p, &s);
  *begin = road_oblique_edge(p->angle, l, track);
  *end = on_track(p, track)
             ? *begin + (double)(p->count - 1) * (p->count > 1 ? p->spacing : 0.0) + s.length
             : *begin;
}

/* As the bump's 2 V / length: twice the rate at which the wheel covers
 * the shape's shortest dimension (a face's height standing for its
 * width, which a real tire's contact length spreads over about that). */
double road_obstacle_top_hz(const road_obstacle *o, const void *params, double speed)
{
  road_shape s;
  o->shape(params, &s);
  return s.scale > 0 ? 2.0 * speed / s.scale : 0.0;
}

void road_obstacle_phrase(const road_obstacle *o, const void *params, char *buf, size_t n)
{
  const fb_road_obstacle_params *p = params;
  char noun[96];
  snprintf(noun, sizeof noun, o->noun,
           *(const double *)(const void *)((const char *)p + o->noun_of));
  const char *where = p->track == TRACK_LEFT    ? " on the left track"
                      : p->track == TRACK_RIGHT ? " on the right track"
                                                : "";
  if (p->count > 1)
    snprintf(buf, n, "over a series of %zu obstacles, each %s%s", p->count, noun, where);
  else
    snprintf(buf, n, "over %s%s", noun, where);
}

/* ---- The plateau: ramps, a top, rounded top edges. An edge of radius
 * e between a ramp at angle th and the top touches each at t =
 * e tan(th / 2) from their corner (the tangent length); the arc's centre
 * is e below the top, t along it from the corner. */

/* cos th of a ramp rising h over r: 0 exactly for a vertical face. */
static double ramp_cos(double h, double r)
{
  return r / hypot(h, r);
}

/* e tan(th / 2) = e sin th / (1 + cos th) = e h / (hypot(h, r) + r):
 * exactly e for a vertical face, whose arc then begins exactly at its
 * vertical tangent. */
static double tangent_length(double h, double r, double e)
{
  return e * (h / (hypot(h, r) + r)); /* h / h is 1 exactly */
}

const char *road_plateau_fits(double h, double r1, double top, double r2, double e)
{
  const double t1 = tangent_length(h, r1, e), t2 = tangent_length(h, r2, e);
  if (e > h)
    return "the edge radius exceeds the height";
  if (t1 + t2 > top)
    return "the rounded edges do not fit on the top";
  if (t1 * ramp_cos(h, r1) > r1 || t2 * ramp_cos(h, r2) > r2)
    return "the rounded edges do not fit on the ramps";
  return NULL;
}

static void add_piece(road_shape *s, fb_road_piece_kind kind, double a, double b, double p0,
                      double p1, double p2)
{
  if (!(b > a))
    return; /* a piece of no length: nothing */
  s->piece[s->n++] = (fb_road_piece){kind, a, b, {p0, p1, p2, 0.0, 0.0}};
}

void road_plateau_shape(double h, double r1, double top, double r2, double e, road_shape *out)
{
  const double t1 = tangent_length(h, r1, e), t2 = tangent_length(h, r2, e);
  const double up_end = r1 - t1 * ramp_cos(h, r1), top_begin = r1 + t1;
  const double top_end = r1 + top - t2, down_begin = r1 + top + t2 * ramp_cos(h, r2);
  out->n = 0;
  if (r1 > 0)
    add_piece(out, FB_ROAD_PIECE_LINE, 0.0, up_end, 0.0, h / r1, 0.0);
  if (e > 0)
    add_piece(out, FB_ROAD_PIECE_ARC, up_end, top_begin, top_begin, h - e, e);
  add_piece(out, FB_ROAD_PIECE_LINE, top_begin, top_end, h, 0.0, 0.0);
  if (e > 0)
    add_piece(out, FB_ROAD_PIECE_ARC, top_end, down_begin, top_end, h - e, e);
  if (r2 > 0)
    add_piece(out, FB_ROAD_PIECE_LINE, down_begin, r1 + top + r2,
              h - h / r2 * (down_begin - r1 - top), -h / r2, 0.0);
  out->length = r1 + top + r2;
  out->rise = 0.0;
  /* A face's height stands for its width; else the shortest of the
   * ramps and the top, as a bump's length. */
  out->scale = r1 > 0 && r2 > 0 ? INFINITY : h;
  const double dims[] = {r1, top, r2};
  for (size_t i = 0; i < sizeof dims / sizeof dims[0]; ++i)
    if (dims[i] > 0)
      out->scale = fmin(out->scale, dims[i]);
}
