/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal to src/vehicle: what assemble.c needs of outputs.c and
 * layout.c, and modes.c of fragments.c (the rigid hull's inertia). */
#ifndef FLEXBOND_VEHICLE_INTERNAL_H
#define FLEXBOND_VEHICLE_INTERNAL_H

#include "flexbond/vehicle.h"

/* The probe measuring output o on the vehicle assembled around hull
 * (instance names of fb_vehicle_assemble). *p's name, target and
 * weights are new (fb_vehicle_probes_free); its unit is the kind table's
 * (NULL for bond signals: from the bond's domain). FB_EINVAL for an unknown signal or mount. */
int fb_vehicle_output_probe(const fb_scenario *s, const fb_hull *hull, const fb_output_spec *o,
                            fb_probe_spec *p, fb_err *err);

/* System 1's inertia in (z, phi, theta), row-major 3x3 (fragments.c):
 * diag(hull_mass, hull_ixx, hull_iyy), the structure's, plus m r r' for
 * each declared hull mass and, with the lumped payload, each load point's
 * share of it, r = [1, y, -x] the point's rigid row: their kinetic
 * energy 1/2 m (z' + y phi' - x theta')^2 (vertical motion only). */
void fb_vehicle_rigid_inertia(const fb_scenario *s, double *m33);

/* The generated hull's centre of mass in its own frame: x as the
 * parameters give it, z above the floor (the plates' masses per area from
 * hull.material and hull.sections; hull_mesh.c). */
void fb_hull_mesh_centroid(const fb_scenario *s, const fb_hull_mesh_params *p, double *cx,
                           double *cz);

/* The motion's probes (motion.c): the hull's coordinates (its torsion
 * probe's signal, every component), the attachment points' displacements
 * (integrated flow of the assembly's b_attach), each mounted body's and
 * each wheel's (integrated flow of NAME.b_mass, susp_NAME.b_wheel):
 * fb_vehicle_motion_nprobes(s) of them into p (names and targets new). */
size_t fb_vehicle_motion_nprobes(const fb_scenario *s);
int fb_vehicle_motion_probes(const fb_scenario *s, const fb_hull *hull, fb_probe_spec *p,
                             fb_err *err);
/* Moves the columns from first on of res (the motion probes' values)
 * into m->samples, with the time, and drops them from res: the rows
 * that cover window (the last sample at or before window[0] to the first
 * at or after window[1]), every row if window is NULL. The hull's
 * coordinates become relative to their value at t = 0, as the integrated
 * displacements are. */
int fb_vehicle_motion_take(const fb_scenario *s, fb_result *res, size_t first,
                           const double *window, fb_vehicle_motion *m, fb_err *err);

#endif
