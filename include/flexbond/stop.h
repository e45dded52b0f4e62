/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: a suspension's bump and rebound stops.
 *
 * A stop is an elastic block the suspension meets at the end of its
 * travel: the bump stop when the spring's travel x (compression
 * positive, the spring's state) reaches its gap, the rebound stop when
 * the extension -x reaches its own. Past its gap the stop is compressed
 * by delta = x - gap (bump) or -x - gap (rebound) and pushes back with
 * its elastic force K(delta) (a linear rate, or a force-deflection table
 * starting at (0, 0)) plus a damping force that grows from zero at first
 * touch to c v at damping_depth (so that the force is continuous in the
 * travel and its rate, as Hunt & Crossley's contact damping, J. Appl.
 * Mech. 42(2), 1975), and never pulls: the stop's force is
 * max(0, K(delta) + c min(delta / damping_depth, 1) v_delta), 0 out of
 * contact.
 *
 * A corner's stops are one modulated resistor "stops" on the spring's
 * 1-junction, reading the spring's travel (fb_bg_modulate): its effort
 * the bump stop's force less the rebound stop's (compression positive,
 * like the spring's), its flow the travel rate. A corner without stops
 * has no such element. */
#ifndef FLEXBOND_STOP_H
#define FLEXBOND_STOP_H

#include <stddef.h>

#include "flexbond/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most points of a stop's force-deflection table. */
enum { FB_STOP_MAX_POINTS = 32 };

typedef struct fb_stop {
  int given;      /* 0: no such stop */
  double gap;     /* m >= 0: the travel (bump) or extension (rebound) at first touch */
  double rate;    /* N/m > 0: the linear elastic law, when npoints is 0 */
  size_t npoints; /* 0, or 2 .. FB_STOP_MAX_POINTS knots of the table */
  /* The table: force (N, not decreasing) against the stop's own
   * compression (m, increasing from 0, where the force is 0),
   * interpolated monotonically (fb_table_law) and continued along its
   * last tangent. */
  double deflection[FB_STOP_MAX_POINTS], force[FB_STOP_MAX_POINTS];
  double damping;       /* N s/m >= 0 */
  double damping_depth; /* m > 0: the compression at which the damping is all there */
} fb_stop;

/* A corner's two stops. */
typedef struct fb_stops {
  fb_stop bump, rebound;
} fb_stops;

/* The default damping depth, m: a few millimetres of an elastomer
 * stop's compression, within which its contact area grows. */
#define FB_STOP_DAMPING_DEPTH 0.005

/* A stop given with its defaults: no gap, no rate, no table, no damping,
 * the default damping depth. */
void fb_stop_init(fb_stop *st);
/* 1 if the corner has a stop. */
int fb_stops_any(const fb_stops *s);

/* 0 if both stops' values are sound: a gap >= 0 (so the stops never
 * overlap: the bump stop is met at a travel >= 0, the rebound stop at one
 * <= 0), exactly one of a rate > 0 and a table (2 .. FB_STOP_MAX_POINTS
 * knots from (0, 0), deflections increasing, forces not decreasing),
 * damping >= 0, a damping depth > 0. FB_EINVAL otherwise, its part's
 * field "bump_stop.<member>" or "rebound_stop.<member>" (kind 0: the
 * description's checker adds its own). */
int fb_stops_check(const fb_stops *s, const char *corner, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
