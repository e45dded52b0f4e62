/* SPDX-License-Identifier: BSD-3-Clause */
/* Small rigid-body motion of a point (vehicle_internal.h): the one map
 * from a body's translation and rotation vector to a point's
 * displacement, which System 1's rigid hull, a hull point's output and
 * the rigid fit of System 2's hull share. */
#include "vehicle/vehicle_internal.h"

/* u = t + theta x r for a small rotation theta (the first-order term of
 * the rotation matrix, I + [theta]x; e.g. Shabana, "Dynamics of
 * Multibody Systems", 4th ed., sec. 2.4): rows of [I, -[r]x]. */
void vehicle_rigid_rows(const double *r, double *rows)
{
  const double m[18] = {
      1.0, 0.0, 0.0, 0.0,   r[2],  -r[1], /* ux = tx + theta_y rz - theta_z ry */
      0.0, 1.0, 0.0, -r[2], 0.0,   r[0],  /* uy = ty + theta_z rx - theta_x rz */
      0.0, 0.0, 1.0, r[1],  -r[0], 0.0,   /* uz = tz + theta_x ry - theta_y rx */
  };
  for (int i = 0; i < 18; ++i)
    rows[i] = m[i];
}
