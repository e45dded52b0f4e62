/* SPDX-License-Identifier: BSD-3-Clause */
/* The paper's oblique crossing of a road feature (road_internal.h): where
 * the leading edge lies on each track, and where each wheel starts. */
#include <math.h>

#include "flexbond/road.h"

#include "road/road_internal.h"

double road_oblique_edge(double angle, const fb_road_layout *l, int track)
{
  return track == FB_ROAD_LEFT ? 0.0 : l->track_width * tan(angle);
}

/* The edge reaches the wheel at (x, y) when the road, moving back at
 * speed V, has travelled the wheel's distance behind the first corner,
 * x_0 - x, plus the edge's extra offset at its lateral position,
 * (y_0 - y) tan(angle): that entry time, and the track's edge, place the
 * wheel at t = 0. */
double road_oblique_wheel_start(double angle, double first_contact, const fb_road_layout *l,
                                double x, double y)
{
  const double entry =
      first_contact + ((l->first_x - x) + (l->first_y - y) * tan(angle)) / l->speed;
  return road_oblique_edge(angle, l, y > 0.0 ? FB_ROAD_LEFT : FB_ROAD_RIGHT) - l->speed * entry;
}
