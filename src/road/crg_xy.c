/* SPDX-License-Identifier: BSD-3-Clause */
/* The reference line of an OpenCRG surface in x/y and the mapping between
 * u/v and x/y (flexbond/crg.h). Section numbers are those of the ASAM
 * OpenCRG specification 1.2.0.
 *
 * 3.1: the reference line is given by a series of heading angles from a
 * start position; "the given start and end positions can be compared to
 * the integration results to distribute errors along the reference line".
 * Here: each step of length du goes in its heading (the channel's value in
 * the step's last row, 3.4.7's samples), the points are summed from
 * REFERENCE_LINE_START_X/_Y, and when REFERENCE_LINE_END_X/_Y are given the
 * end's miss is distributed linearly in u. Between points the line is the
 * straight chord; v is measured along the normal of a heading interpolated
 * linearly between the points' headings (each the mean of its two chords'),
 * so that x/y is continuous in u and v; beyond the ends the line goes on
 * straight (REFLINE_CONTINUATION 0, 3.4.4). */
#include <math.h>
#include <stdlib.h>

#include "flexbond/crg.h"

#include "road/crg_internal.h"

/* a - b brought into (-pi, pi]. */
static double angle_diff(double a, double b)
{
  return atan2(sin(a - b), cos(a - b));
}

/* Each point's heading: the mean of the chords on either side (the end
 * points: their one chord). */
static void point_headings(fb_crg *c)
{
  const size_t n = c->nu; /* >= 2 */
  double prev = atan2(c->ry[1] - c->ry[0], c->rx[1] - c->rx[0]);
  c->rh[0] = prev;
  for (size_t i = 1; i + 1 < n; ++i) {
    const double chord = atan2(c->ry[i + 1] - c->ry[i], c->rx[i + 1] - c->rx[i]);
    c->rh[i] = prev + 0.5 * angle_diff(chord, prev);
    prev = chord;
  }
  c->rh[n - 1] = prev;
}

/* Rotates the line by angle about (cx, cy), then moves it by (dx, dy). */
static void move_line(fb_crg *c, double cx, double cy, double angle, double dx, double dy)
{
  const double cs = cos(angle), sn = sin(angle);
  for (size_t i = 0; i < c->nu; ++i) {
    const double x = c->rx[i] - cx, y = c->ry[i] - cy;
    c->rx[i] = cx + cs * x - sn * y + dx;
    c->ry[i] = cy + sn * x + cs * y + dy;
    c->rh[i] += angle;
  }
}

/* The segment of u, the fraction t in it (outside [0, 1] beyond the ends),
 * the point on the line and the heading of v's normal there. */
static void line_at(const fb_crg *c, double u, double *px, double *py, double *h)
{
  const double f = (u - c->u0) / c->du;
  size_t i = f <= 0.0 ? 0 : (size_t)f;
  if (i > c->nu - 2)
    i = c->nu - 2;
  const double t = f - (double)i;
  *px = c->rx[i] + t * (c->rx[i + 1] - c->rx[i]);
  *py = c->ry[i] + t * (c->ry[i + 1] - c->ry[i]);
  const double tc = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
  *h = c->rh[i] + tc * angle_diff(c->rh[i + 1], c->rh[i]);
}

int crg_refline_build(fb_crg *c, const double *phi, const crg_place *pl, fb_err *err)
{
  const size_t n = c->nu;
  c->rx = calloc(n, sizeof *c->rx);
  c->ry = calloc(n, sizeof *c->ry);
  c->rh = calloc(n, sizeof *c->rh);
  if (!c->rx || !c->ry || !c->rh)
    return fb_err_set(err, FB_ENOMEM, "out of memory for an OpenCRG reference line");
  /* Step headings, SCALE_CURVATURE scaling their turn from the first. */
  double first = 0.0, unwrapped = 0.0, prev = 0.0;
  c->rx[0] = pl->start_x;
  c->ry[0] = pl->start_y;
  for (size_t i = 1; i < n; ++i) {
    double step =
        phi ? phi[i]
        : pl->end_phi_given && n > 2
            ? pl->start_phi + (pl->end_phi - pl->start_phi) * (double)(i - 1) / (double)(n - 2)
            : pl->start_phi;
    unwrapped = i == 1 ? step : unwrapped + angle_diff(step, prev);
    prev = step;
    if (i == 1)
      first = unwrapped;
    const double heading = first + pl->scale_curvature * (unwrapped - first);
    c->rx[i] = c->rx[i - 1] + c->du * cos(heading);
    c->ry[i] = c->ry[i - 1] + c->du * sin(heading);
  }
  if (pl->end_xy_given) { /* 3.1: the end's miss spread along u */
    const double ex = pl->end_x - c->rx[n - 1], ey = pl->end_y - c->ry[n - 1];
    for (size_t i = 1; i < n; ++i) {
      c->rx[i] += ex * (double)i / (double)(n - 1);
      c->ry[i] += ey * (double)i / (double)(n - 1);
    }
  }
  point_headings(c);
  /* 3.4.2: the global offsets (the heading's about the start). */
  move_line(c, c->rx[0], c->ry[0], pl->offset_phi, pl->offset_x, pl->offset_y);
  /* 3.4.5: by reference point (its (u, v) to (x, y) and heading), else by
   * rotation about the rotation centre (default: the start) and offset. */
  if (pl->by_refpoint) {
    double px, py, h;
    line_at(c, pl->ref_u, &px, &py, &h);
    px -= pl->ref_v * sin(h);
    py += pl->ref_v * cos(h);
    move_line(c, px, py, pl->ref_phi - h, pl->ref_x - px, pl->ref_y - py);
  } else {
    move_line(c, pl->rotcenter_given[0] ? pl->rot_x : c->rx[0],
              pl->rotcenter_given[1] ? pl->rot_y : c->ry[0], pl->rot_phi, pl->move_x,
              pl->move_y);
  }
  return FB_OK;
}

static int closed_track_refused(const fb_crg *c, double u, fb_err *err)
{
  const double u_last = c->u0 + (double)(c->nu - 1) * c->du;
  if (c->opts.refline_continuation && (u < c->u0 || u > u_last))
    return fb_err_set(err, FB_EINVAL,
                      "u = %g m beyond the reference line [%g, %g] m with "
                      "REFLINE_CONTINUATION = 1 (a closed track): not supported",
                      u, c->u0, u_last);
  return FB_OK;
}

int fb_crg_uv_to_xy(const fb_crg *crg, double u, double v, double *x, double *y, fb_err *err)
{
  if (!isfinite(u) || !isfinite(v))
    return fb_err_set(err, FB_EINVAL, "u, v must be finite");
  const int rc = closed_track_refused(crg, u, err);
  if (rc)
    return rc;
  double px, py, h;
  line_at(crg, u, &px, &py, &h);
  *x = px - v * sin(h);
  *y = py + v * cos(h);
  return FB_OK;
}

/* Along segment i at fraction t: the point's offset from the line, split
 * into its component along the heading (*along) and across it (*across). */
static void offset_at(const fb_crg *c, size_t i, double t, double x, double y, double *along,
                      double *across)
{
  const double px = c->rx[i] + t * (c->rx[i + 1] - c->rx[i]);
  const double py = c->ry[i] + t * (c->ry[i + 1] - c->ry[i]);
  const double h = c->rh[i] + t * angle_diff(c->rh[i + 1], c->rh[i]);
  *along = (x - px) * cos(h) + (y - py) * sin(h);
  *across = -(x - px) * sin(h) + (y - py) * cos(h);
}

int fb_crg_xy_to_uv(const fb_crg *crg, double x, double y, double *u, double *v, fb_err *err)
{
  if (!isfinite(x) || !isfinite(y))
    return fb_err_set(err, FB_EINVAL, "x, y must be finite");
  const size_t n = crg->nu;
  double best_u = NAN, best_v = INFINITY;
  /* Each segment whose normals sweep over the point: the fraction where
   * the offset is all across, by bisection (the along component falls
   * from >= 0 to <= 0 over the segment). */
  for (size_t i = 0; i + 1 < n; ++i) {
    double a0, a1, across;
    offset_at(crg, i, 0.0, x, y, &a0, &across);
    offset_at(crg, i, 1.0, x, y, &a1, &across);
    if (!(a0 >= 0.0 && a1 <= 0.0))
      continue;
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      double a;
      offset_at(crg, i, mid, x, y, &a, &across);
      if (a > 0.0)
        lo = mid;
      else
        hi = mid;
    }
    double a;
    offset_at(crg, i, 0.5 * (lo + hi), x, y, &a, &across);
    if (fabs(across) < fabs(best_v)) {
      best_v = across;
      best_u = crg->u0 + ((double)i + 0.5 * (lo + hi)) * crg->du;
    }
  }
  /* Beyond the ends, along the end chords. */
  for (int end = 0; end < 2; ++end) {
    const size_t i = end ? n - 1 : 0;
    const double h = crg->rh[i], dx = x - crg->rx[i], dy = y - crg->ry[i];
    const double along = dx * cos(h) + dy * sin(h), across = -dx * sin(h) + dy * cos(h);
    if ((end ? along > 0.0 : along < 0.0) && fabs(across) < fabs(best_v)) {
      best_v = across;
      best_u = crg->u0 + (end ? (double)(n - 1) * crg->du : 0.0) + along;
    }
  }
  if (isnan(best_u))
    return fb_err_set(err, FB_EINVAL, "no point of the reference line is square to (%g, %g)", x,
                      y);
  const int rc = closed_track_refused(crg, best_u, err);
  if (rc)
    return rc;
  *u = best_u;
  *v = best_v;
  return FB_OK;
}
