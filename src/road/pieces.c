/* SPDX-License-Identifier: BSD-3-Clause */
/* Piecewise tracks (flexbond/road.h, fb_road_new_pieces): lines, circular
 * arcs and waves of growing amplitude end to end, the exact geometry of
 * obstacles (docs/roads.md, "Obstacles"), with the joints where the
 * height jumps or the slope is infinite (fb_road_edges). */
#include <math.h>
#include <string.h>

#include "flexbond/road.h"

#include "road/road_internal.h"

/* A joint's height change below this (m) is rounding, not a face: the
 * pieces' ends are computed from trigonometry, some 1e-16 m apart. */
#define PIECE_JUMP_TOL 1e-9
/* An arc's end within this fraction of its radius from its circle's
 * leftmost or rightmost point has a vertical tangent there. */
#define PIECE_VERTICAL_TOL 1e-12

static double piece_height(const fb_road_piece *p, double s)
{
  const double u = s - p->s_begin;
  switch (p->kind) {
  case FB_ROAD_PIECE_LINE: return p->p[0] + p->p[1] * u;
  case FB_ROAD_PIECE_ARC: {
    const double dx = s - p->p[0], r = p->p[2];
    return p->p[1] + copysign(sqrt(fmax(r * r - dx * dx, 0.0)), r);
  }
  case FB_ROAD_PIECE_WAVE:
    return p->p[0] + (p->p[1] + p->p[2] * u) * cos(p->p[3] * u + p->p[4]);
  }
  return NAN;
}

/* The arc's slope -(s - c) / (z - z_c) is infinite at its circle's
 * leftmost and rightmost points (sign: the side it rises from). */
static double piece_slope(const fb_road_piece *p, double s)
{
  const double u = s - p->s_begin;
  switch (p->kind) {
  case FB_ROAD_PIECE_LINE: return p->p[1];
  case FB_ROAD_PIECE_ARC: {
    const double dx = s - p->p[0], r = p->p[2];
    const double root = sqrt(fmax(r * r - dx * dx, 0.0));
    return root > 0.0 ? -copysign(1.0, r) * dx / root : -copysign(INFINITY, r * dx);
  }
  case FB_ROAD_PIECE_WAVE: {
    const double phase = p->p[3] * u + p->p[4];
    return p->p[2] * cos(phase) - (p->p[1] + p->p[2] * u) * p->p[3] * sin(phase);
  }
  }
  return NAN;
}

/* The piece holding s: the last that begins at or before it (the first
 * one before them all), by bisection. */
static size_t piece_at(size_t n, const fb_road_piece *p, double s)
{
  size_t lo = 0, hi = n;
  while (hi - lo > 1) {
    const size_t mid = lo + (hi - lo) / 2;
    if (p[mid].s_begin <= s)
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

double road_pieces_height(size_t n, const double *data, double s)
{
  if (n == 0)
    return 0.0;
  const fb_road_piece *p = road_pieces_of(data);
  if (s < p[0].s_begin)
    return piece_height(&p[0], p[0].s_begin);
  if (s > p[n - 1].s_end)
    return piece_height(&p[n - 1], p[n - 1].s_end);
  return piece_height(&p[piece_at(n, p, s)], s);
}

double road_pieces_slope(size_t n, const double *data, double s)
{
  if (n == 0)
    return 0.0;
  const fb_road_piece *p = road_pieces_of(data);
  if (s < p[0].s_begin || s > p[n - 1].s_end)
    return 0.0;
  return piece_slope(&p[piece_at(n, p, s)], s);
}

/* Where the joint before piece i (i == n: after the last) lies. */
static double joint_at(size_t n, const fb_road_piece *p, size_t i)
{
  return i < n ? p[i].s_begin : p[n - 1].s_end;
}

size_t road_pieces_breaks(size_t n, const double *data, double *s, size_t max)
{
  const fb_road_piece *p = road_pieces_of(data);
  const size_t count = n ? n + 1 : 0;
  for (size_t i = 0; s && i < count && i < max; ++i)
    s[i] = joint_at(n, p, i);
  return count;
}

double road_pieces_shortest_wavelength(size_t n, const double *data)
{
  const fb_road_piece *p = road_pieces_of(data);
  double w = INFINITY;
  for (size_t i = 0; i < n; ++i) {
    w = fmin(w, 2.0 * (p[i].s_end - p[i].s_begin));
    if (p[i].kind == FB_ROAD_PIECE_WAVE && p[i].p[3] != 0.0)
      w = fmin(w, 6.28318530717958647692 / fabs(p[i].p[3]));
  }
  return w;
}

/* 1 if the arc piece p touches its circle's leftmost or rightmost point
 * at s (a vertical tangent). */
static int piece_vertical_at(const fb_road_piece *p, double s)
{
  return p->kind == FB_ROAD_PIECE_ARC &&
         fabs(fabs(s - p->p[0]) - fabs(p->p[2])) <= PIECE_VERTICAL_TOL * fabs(p->p[2]);
}

/* 1 if the joint before piece i (i == n: after the last; n > 0) is an
 * edge: a height jump, or a vertical tangent on either side. */
static int joint_is_edge(size_t n, const fb_road_piece *p, size_t i)
{
  const double s = joint_at(n, p, i);
  const fb_road_piece *before = i > 0 ? &p[i - 1] : NULL, *after = i < n ? &p[i] : NULL;
  if ((before && piece_vertical_at(before, s)) || (after && piece_vertical_at(after, s)))
    return 1;
  return before && after &&
         fabs(piece_height(before, s) - piece_height(after, s)) > PIECE_JUMP_TOL;
}

size_t fb_road_edges(const fb_road *road, int track, double *s, size_t max)
{
  if (!road || (track != FB_ROAD_LEFT && track != FB_ROAD_RIGHT) ||
      road->track[track].kind != ROAD_PIECES)
    return 0;
  const size_t n = road->track[track].n;
  const fb_road_piece *p = road_pieces_of(road->data[track]);
  size_t count = 0;
  for (size_t i = 0; n && i <= n; ++i) {
    if (!joint_is_edge(n, p, i))
      continue;
    if (s && count < max)
      s[count] = joint_at(n, p, i);
    ++count;
  }
  return count;
}

/* NULL if piece i is sound, else what is wrong with it. */
static const char *piece_fault(size_t i, const fb_road_piece *p)
{
  const fb_road_piece *q = &p[i];
  int finite = isfinite(q->s_begin) && isfinite(q->s_end);
  for (size_t k = 0; k < sizeof q->p / sizeof q->p[0]; ++k)
    finite = finite && isfinite(q->p[k]);
  if (!finite)
    return "is not finite";
  if ((unsigned)q->kind > FB_ROAD_PIECE_WAVE)
    return "is of no known kind";
  if (!(q->s_end > q->s_begin))
    return "does not end after it begins";
  if (i > 0 && q->s_begin != p[i - 1].s_end)
    return "does not begin where the piece before it ends";
  const double r = fabs(q->p[2]), slack = PIECE_VERTICAL_TOL * r;
  if (q->kind == FB_ROAD_PIECE_ARC &&
      !(r > 0.0 && q->s_begin >= q->p[0] - r - slack && q->s_end <= q->p[0] + r + slack))
    return "leaves its circle";
  return NULL;
}

int fb_road_new_pieces(size_t n_left, const fb_road_piece *left, size_t n_right,
                       const fb_road_piece *right, fb_road **out, fb_err *err)
{
  if (!out || (n_left && !left) || (n_right && !right))
    return fb_err_set(err, FB_EINVAL, "road pieces: NULL argument");
  *out = NULL;
  const size_t n[FB_ROAD_NTRACKS] = {n_left, n_right};
  const fb_road_piece *pieces[FB_ROAD_NTRACKS] = {left, right};
  static const char *const side[FB_ROAD_NTRACKS] = {"left", "right"};
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k)
    for (size_t i = 0; i < n[k]; ++i) {
      const char *fault = piece_fault(i, pieces[k]);
      if (fault)
        return fb_err_set(err, FB_EINVAL, "road pieces: %s track, piece %zu %s", side[k], i + 1,
                          fault);
    }
  const road_track lt = {ROAD_PIECES, n_left, {0.0, 0.0, 0.0}};
  const road_track rt = {ROAD_PIECES, n_right, {0.0, 0.0, 0.0}};
  const int rc = road_alloc(&lt, &rt, out, err);
  for (int k = 0; !rc && k < FB_ROAD_NTRACKS; ++k)
    if (n[k])
      memcpy((*out)->data[k], pieces[k], n[k] * sizeof *pieces[k]);
  return rc;
}
