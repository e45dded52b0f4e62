/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal to src/vehicle: what assemble.c needs of outputs.c and
 * layout.c, and modes.c of fragments.c (the rigid hull's inertia). */
#ifndef FLEXBOND_VEHICLE_INTERNAL_H
#define FLEXBOND_VEHICLE_INTERNAL_H

#include "flexbond/vehicle.h"

/* The probe measuring output s->output[index] on the vehicle assembled
 * around hull (instance names of fb_vehicle_assemble). *p's name, target
 * and weights are new (fb_vehicle_probes_free); its unit is the kind
 * table's (NULL for bond signals: from the bond's domain). FB_EINVAL for
 * an unknown signal or mount, about the output's member (fb_err.part). */
int fb_vehicle_output_probe(const fb_scenario *s, const fb_hull *hull, size_t index,
                            fb_probe_spec *p, fb_err *err);

/* Corner c of s with its tire's static deflection under an equal share
 * of the weight on the tires (assemble.c; fb_corner_params). */
fb_corner_params vehicle_corner_loaded(const fb_scenario *s, size_t c);

/* A one-port C or R element of constant scalar parameter v
 * (fragments.c): the corners' linear springs, dampers and tires. */
int vehicle_add_scalar(fb_bg *bg, const char *name, fb_bg_kind kind, double v, fb_err *err);

/* System 1's inertia in (z, phi, theta), row-major 3x3 (fragments.c):
 * diag(hull_mass, hull_ixx, hull_iyy), the structure's, plus m r r' for
 * each declared hull mass and, with the lumped payload, each load point's
 * share of it, r = [1, y, -x] the point's rigid row: their kinetic
 * energy 1/2 m (z' + y phi' - x theta')^2 (vertical motion only). */
void fb_vehicle_rigid_inertia(const fb_scenario *s, double *m33);
/* The same in six degrees of freedom (x, y, z, roll, pitch, yaw), for a
 * hull carrying mounted rigid bodies, 6x6 row major: diag(hull_mass)
 * and the hull's whole inertia tensor, plus m T' T for each declared
 * hull mass and lumped payload share, T = vehicle_rigid_transport of its
 * point (x, y, 0) (taken at the centre of mass's height: the scenario
 * has no floor height). Its (z, roll, pitch) block is
 * fb_vehicle_rigid_inertia's. */
void vehicle_rigid_inertia6(const fb_scenario *s, double *m66);
/* On the 6-dimensional 1-junction `junction` (a rigid body's generalised
 * velocity at its reference point), the port "bushing_<k>" (IN,
 * dimension 6) of the point at r from it (small motion,
 * vehicle_rigid_transport), where bushing k of fb_scenario_bushing_at
 * meets its parent: the transformer "to_bushing_<k>" and the 1-junction
 * "bushing_<k>". */
/* System 2's undamped vehicle (fb_vehicle_matrices): its DOFs after the
 * hull's, the mounts' and the wheels' vertical motions, then six per
 * mounted rigid body (x, y, z, roll, pitch, yaw at its centre of mass). */
size_t vehicle_nlumped(const fb_scenario *s);
/* The highest natural frequency (Hz) of body b on its bushings with its
 * parent held (their stiffness at its centre of mass against its
 * inertia); 0 if LAPACK fails. */
double vehicle_body_top_hz(const fb_body *b);
/* Body b's 6x6 inertia at its centre of mass, row major. */
void vehicle_body_inertia6(const fb_body *b, double *m66);
/* Bushing k's relative motion, its parent's point minus its body's, as
 * six sparse rows over the undamped vehicle's DOFs: the hull's coupling
 * rows (fe's, over its nodal DOFs) or the parent body's rigid transport,
 * less the body's; body i's six DOFs from base + 6 i. rows new
 * (fb_hull_coupling_free each). */
int vehicle_bushing_relative_rows(const fb_scenario *s, const fb_fe_hull *fe, size_t k,
                                  size_t base, fb_hull_coupling *rows, fb_err *err);
/* The hull nodes bushing u's hull side is coupled to (*nodes new, *n of
 * them): its node set's, or those of the coupling surface within its
 * radius (or the scenario's) in plan (coupling.c). FB_EMODEL when there
 * are none. */
int vehicle_bushing_nodes(const fb_scenario *s, const fb_mesh *m, const fb_bushing *u,
                          size_t **nodes, size_t *n, fb_err *err);
/* The probe of output index of s, a mounted rigid body's signal (its
 * kind's subject FB_OUTPUT_OF_BODY): target and weights new in p. */
int vehicle_body_probe(const fb_scenario *s, size_t index, fb_probe_spec *p, fb_err *err);
int vehicle_add_bushing_port(fb_bg *bg, const char *junction, size_t k, const double *r,
                             fb_err *err);
/* The same around a transformer "to_bushing_<k>" bg has already (6 rows
 * from the body's coordinates): the junction, its bonds and the port. */
int vehicle_wire_bushing_port(fb_bg *bg, const char *junction, size_t k, fb_err *err);

/* The generated hull's centre of mass in its own frame: x as the
 * parameters give it, z above the floor (the plates' masses per area from
 * hull.material and hull.sections; hull_mesh.c). */
void fb_hull_mesh_centroid(const fb_scenario *s, const fb_hull_mesh_params *p, double *cx,
                           double *cz);

/* System 2's one bound on its hull, whatever makes the mesh (hull_mesh.c):
 * FB_EINVAL when `elements` (a mesh's count, or the generator's before it
 * refines) is above the most a hull may have, with the message "which
 * would need about ... GB of memory for System 2 ..., more than the ...
 * allowed (at most N elements<hint>; ...)" for the caller to prefix with
 * the source and its count and to give the key that names the source. */
int vehicle_hull_check_size(double elements, const char *hint, fb_err *err);

/* The motion's probes (motion.c): the hull's coordinates (its torsion
 * probe's signal, every component), the attachment points' displacements
 * (integrated flow of the assembly's b_attach), each mounted body's and
 * each wheel's (integrated flow of NAME.b_mass, susp_NAME.b_wheel):
 * fb_vehicle_motion_nprobes(s, hull_only) of them into p (names and
 * targets new); hull_only: the hull's coordinates alone. */
size_t fb_vehicle_motion_nprobes(const fb_scenario *s, int hull_only);
int fb_vehicle_motion_probes(const fb_scenario *s, const fb_hull *hull, int hull_only,
                             fb_probe_spec *p, fb_err *err);
/* Moves the columns from first on of res (the motion probes' values)
 * into m->samples, with the time, and drops them from res: the rows
 * that cover window (the last sample at or before window[0] to the first
 * at or after window[1]), every row if window is NULL. The hull's
 * coordinates become relative to their value at t = 0, as the integrated
 * displacements are. */
int fb_vehicle_motion_take(const fb_scenario *s, fb_result *res, size_t first,
                           const double *window, int hull_only, fb_vehicle_motion *m,
                           fb_err *err);

/* -1 if output o is not read from the hull's deformation, else which
 * torsion weights it takes (fb_fe_hull_torsion_weights' fit: 0 or 1). */
int fb_vehicle_output_hull_fit(const fb_output_spec *o);

/* ---- Outputs read from the hull's motion (docs/vehicle-outputs.md). */

/* A small rigid-body motion's map (rigid_kinematics.c): the displacement u
 * of the point r (m, from the body's reference point) under the
 * translation t and the small rotation vector theta, u = t + theta x r,
 * as 3 rows (row-major 3x6) over (tx, ty, tz, theta_x, theta_y, theta_z). */
void vehicle_rigid_rows(const double *r, double *rows);

/* What an output read from the hull's motion measures (outputs.c): the
 * derivative (0 displacement from t = 0, 1 velocity, 2 acceleration) of
 * its point's translation along its direction (coordinate -1) or of the
 * hull's rigid-body coordinate (vehicle_rigid_rows' order). */
typedef struct vehicle_hull_motion {
  int derivative;
  int coordinate;
} vehicle_hull_motion;
/* 1 and *how if output o is read from the hull's motion, else 0. */
int vehicle_output_hull_motion(const fb_output_spec *o, vehicle_hull_motion *how);
/* hull->reading for s's outputs, every one empty (outputs.c). */
int vehicle_hull_readings_new(const fb_scenario *s, fb_hull *hull, fb_err *err);
/* Fills one (strings and weights copied). */
int vehicle_hull_reading_set(fb_hull_reading *r, const char *target, fb_probe_kind kind,
                             int integrate, const double *weights, size_t nweights,
                             fb_err *err);
void vehicle_hull_readings_free(fb_hull *hull);

/* How far a hull point output's point may be from System 2's hull
 * surface: 5 cm, a plate's thickness and a drawing's rounding, far below
 * the size of the hull's elements (hull_point.c). */
#define VEHICLE_HULL_POINT_TOL 0.05
/* The distance from p to the nearest element of m, that element in *elem,
 * its shape functions at the foot of p on it in n (3 or 4 of n[4]) and the
 * foot in foot[3] (hull_point.c); INFINITY for a mesh without elements. */
double vehicle_hull_point_nearest(const fb_mesh *m, const double *p, size_t *elem, double *n,
                                  double *foot);
/* vehicle_hull_point_nearest of output index's point `at`, the element in
 * *e, FB_EINVAL about `at` when it is farther than VEHICLE_HULL_POINT_TOL
 * (naming the distance). */
int vehicle_hull_point_on(const fb_mesh *m, const fb_output_spec *o, size_t index, size_t *e,
                          double *n, double *foot, fb_err *err);
/* The weights w (6 nnodes, over the nodal DOFs) of output index's point
 * translation along its direction (o checked: fb_scenario_check): the nearest element's shape
 * functions at the foot, and the lever from the foot to the point through the nodes' rotations.
 * FB_EINVAL about the output's `at` when no element is within VEHICLE_HULL_POINT_TOL (naming
 * the nearest's distance). */
int vehicle_hull_point_weights(const fb_mesh *m, const fb_output_spec *o, size_t index,
                               double *w, fb_err *err);
/* The weights w (6 nnodes) of the rigid-body coordinate (vehicle_rigid_rows'
 * order, about the origin: the hull's centre of mass) fitted to the nodal
 * displacements by least squares in the norm of the mass matrix M: w =
 * M R (R' M R)^-1 e_coordinate, R the mesh's rigid-body motions. */
int vehicle_hull_rigid_fit(const fb_mesh *m, const fb_mat *M, int coordinate, double *w,
                           fb_err *err);
/* Each hull point output of s lies on its finite-element hull's mesh, if
 * it has one (s->hull_source_mesh): FB_EINVAL about its `at` otherwise;
 * and each hull stress output reads an element of it
 * (vehicle_hull_stress_element), or is refused about its signal for a
 * scenario without a finite-element hull. */
int vehicle_hull_points_check(const fb_scenario *s, fb_err *err);

/* ---- Outputs read from the stresses of System 2's shell elements
 * (hull_stress_output.c, docs/stresses.md "Stress outputs"). */

/* 1 if output o is a hull stress signal (FB_OUTPUT_OF_HULL_STRESS; outputs.c). */
int vehicle_output_hull_stress(const fb_output_spec *o);
/* The threads v may use (fb_vehicle_opts.threads; vehicle.c). */
int vehicle_threads(const fb_vehicle *v);
/* The element of m that hull stress output index reads, into *e: the one
 * with its id (`element`), FB_EINVAL about `element` when m has none; or
 * the element nearest its point, FB_EINVAL about `at` when none is within
 * VEHICLE_HULL_POINT_TOL (naming the distance), as a hull point's. */
int vehicle_hull_stress_element(const fb_mesh *m, const fb_output_spec *o, size_t index,
                                size_t *e, fb_err *err);
/* The weights w (6 nnodes, over the nodal DOFs) of hull stress output
 * index's component: its row of the element's recovery matrix D_e
 * (fb_shell_stress_recovery), the element's properties those of the hull
 * (fb_mesh_element_props over props). Errors as
 * vehicle_hull_stress_element's, and the recovery's. */
int vehicle_hull_stress_weights(const fb_mesh *m, const fb_shell_props *props,
                                const fb_output_spec *o, size_t index, double *w, fb_err *err);

/* 1 if the scenario's hull_source_mesh is the mesh its hull has now: the
 * one its source read, or the one it made from the inputs it has (equal
 * keys; fe_hull.c). */
int vehicle_source_mesh_current(const fb_scenario *s);

/* ---- System 2's hull, realised once (hull_model.c). */

typedef struct vehicle_hull vehicle_hull;

/* Builds s's finite-element hull (fb_vehicle_fe_hull), assembles its K and
 * M once, solves its eigenproblem and makes the basis of hull.fe.coordinates
 * and hull.fe.modes (docs/hull-mesh.md), counting each in *w. o (NULL: the
 * defaults) gives the memory limit of the factor, the eigen-solve and the
 * basis, the progress that hears of each stage, the eigen-solve's threads
 * and the hull modes to solve at least. Errors about a value of the
 * description name its part (fb_err.part: hull_modes, hull_cutoff_hz). */
int vehicle_hull_new(const fb_scenario *s, const fb_vehicle_opts *o, fb_vehicle_work *w,
                     vehicle_hull **out, fb_err *err);
void vehicle_hull_free(vehicle_hull **h);
const fb_fe_hull *vehicle_hull_fe(const vehicle_hull *h);
const fb_hull_basis *vehicle_hull_basis(const vehicle_hull *h);
/* The hull fragment (fb_hull, *out new) in the realised coordinates; with
 * enriched, in the error estimator's basis (made on the first call from
 * the same eigen-solve; FB_EINVAL unless the coordinates are reduced
 * modal ones). */
int vehicle_hull_fragment(const fb_scenario *s, vehicle_hull *h, int enriched, fb_hull **out,
                          fb_err *err);
/* fb_vehicle_structural_modes of the realised hull. */
int vehicle_hull_structural_modes(const fb_scenario *s, vehicle_hull *h, size_t nmodes,
                                  int exact, fb_vehicle_work *w, fb_mode_set **out,
                                  fb_err *err);

/* The name of the finite-element hull fragment's bond i (its own name,
 * in the fragment), NULL past the last: every one a multibond. */
const char *vehicle_flexible_hull_bond(size_t i);

/* ---- fe_hull.c's matrices and modes, for hull_model.c. */

/* *M (the hull's, replaced) plus each declared hull mass and, each, a
 * mass `each` on every load node (nload 0: none) on its node's three
 * translations. */
int fb_fe_hull_add_masses(const fb_fe_hull *h, size_t nload, double each, fb_mat **M,
                          fb_err *err);
/* The undamped System 2 over the hull's nodal DOFs, then the mounted
 * bodies' and the wheels' vertical motions, then the rigid bodies' six
 * each (vehicle_nlumped): *K and *M (new) from the hull's kh and mh and
 * the springs, bushings, bodies, wheels and anti-roll bars of s. */
int fb_vehicle_matrices(const fb_scenario *s, const fb_fe_hull *h, const fb_mat *kh,
                        const fb_mat *mh, fb_mat **K, fb_mat **M, fb_err *err);
/* Completes a mode set from nwant modes (freq ascending, shapes over the
 * DOFs of fb_vehicle_matrices', the hull's then the bodies' and wheels'):
 * leaves out the free horizontal rigid-body motions (counted in nfree),
 * keeps at most ms->nmodes, describes and normalises each. mh: the hull's
 * mass. */
int fb_vehicle_mode_set_fill(const fb_scenario *s, const fb_fe_hull *h, const fb_mat *mh,
                             const double *freq, const double *shapes, size_t nwant,
                             fb_mode_set *ms, fb_err *err);
/* A mode set with room for nmodes of ndof (*out new). */
int fb_mode_set_new(size_t nmodes, size_t ndof, fb_mode_set **out, fb_err *err);

/* ---- Variants of a scenario for the linear analyses (modes.c,
 * freq_response.c), made on a copy: */

/* Every damper and tire damper removed (natural frequencies). */
void vehicle_remove_damping(fb_scenario *s);
/* The vehicle at rest on flat ground: a random road or a profile moves the
 * wheels at t = 0, where the equilibrium is taken, so it is replaced by a
 * bump of zero height (the road's sources enter no matrix: the linear
 * model is the same). */
void vehicle_flatten_road(fb_scenario *s);
/* A signal a fragment offers to measure (fragments.c): its probe on one
 * of the fragment's own bonds or elements (target, as the fragment names
 * it), integrated or not, divided by the subject's mass or not. */
typedef struct vehicle_signal {
  const char *signal;
  fb_probe_kind kind;
  const char *target;
  int integrate;
  int per_mass;
  /* A corner's signal of a part it may lack: 1 when corner c has it
   * (NULL: every corner), and what it needs, for the message. */
  int (*offered)(const fb_corner_params *c);
  const char *needs;
} vehicle_signal;
/* Every corner's and mount's own signal: its body's vertical
 * displacement (the animation's motion, motion.c). */
#define VEHICLE_SIGNAL_MOTION "#motion"
/* The signal the fragment of subject's kind offers (a corner's, a
 * mount's), NULL if it offers none of that name. */
const vehicle_signal *vehicle_fragment_signal(fb_output_subject subject, const char *signal);
/* The signal corner c of s offers: its corner fragment's, or, for a wheel
 * of a bogie, the bogie's wheel's (its tire's and its motion). */
const vehicle_signal *vehicle_corner_signal(const fb_scenario *s, size_t c, const char *signal);
/* The bogie whose wheel corner c is (*rear: 1 at its rear end; may be
 * NULL), -1 for none (assemble.c). */
long vehicle_corner_bogie(const fb_scenario *s, size_t c, int *rear);
/* Bogie i of s over its wheels' vertical displacements (z_front, z_rear):
 * the corners' indices in *f and *r, the mass matrix of the beam and the
 * wheels in m (2 x 2, row-major) and the lever's weights in w, the pivot's
 * displacement w[0] z_front + w[1] z_rear (fe_hull.c). 0 when a corner is
 * missing (a description fb_scenario_check refuses). */
int vehicle_bogie_wheels(const fb_scenario *s, size_t i, long *f, long *r, double *m,
                         double *w);
/* A bogie's fragment's instance name, "bogie_<name>" (assemble.c); new. */
char *vehicle_bogie_instance(const fb_bogie *b);
/* The name the assembly gives item i's fragment in the vehicle's graph
 * (a corner's "susp_<name>", a mount's own name; assemble.c), and the
 * full name of the fragment's own bond or element local in it; new,
 * NULL when out of memory. */
char *vehicle_instance(const fb_scenario *s, fb_output_subject subject, size_t i);
char *vehicle_target(const fb_scenario *s, fb_output_subject subject, size_t i,
                     const char *local);

/* Adds corner stops s as the modulated R element name reading the
 * travel of the C element spring (flexbond/stop.h), to bg. */
int vehicle_add_stops(const fb_stops *s, const char *name, const char *spring, fb_bg *bg,
                      fb_err *err);

/* Frees the strings of an output (the output itself is its holder's). */
void vehicle_output_release(fb_output_spec *o);
/* The anti-roll bar's instance name in the vehicle's graph, "arb_<name>"
 * (assemble.c); new, NULL when out of memory. */
char *vehicle_antiroll_bar_instance(const fb_antiroll_bar *b);
/* Frees the strings an anti-roll bar (a bogie) of a description owns. */
void vehicle_antiroll_bar_release(fb_antiroll_bar *b);
void vehicle_bogie_release(fb_bogie *b);
/* Frees what a body owns (its names, bushings and their node sets) and
 * zeroes it; the body itself is its holder's. */
void vehicle_body_release(fb_body *b);
/* *dst = a deep copy of src; 0 when memory ran out (*dst then owns
 * nothing). */
int vehicle_body_copy(const fb_body *src, fb_body *dst);
/* b's inertia tensor about its centre of mass, 3x3 row major, into j. */
void vehicle_body_inertia(const fb_body *b, double *j);
/* The hull structure's whole inertia tensor (hull_ixx .. hull_iyz), the
 * same way. */
void vehicle_hull_inertia(const fb_scenario *s, double *j);
/* The eigenvalues of the symmetric 3x3 a (row major), ascending, into w;
 * FB_ESOLVER if LAPACK fails. */
int vehicle_sym3_eigenvalues(const double *a, double *w);
/* The 6x6 map (row major) from a rigid body's motion at a reference
 * point, (v, omega), to its motion at the point r from it: small motion. */
void vehicle_rigid_transport(const double *r, double *t);
/* sum += T' k T, T the transport from b's centre of mass to bushing u's
 * point: a 6x6 (row major) stiffness or damping k of u as b's centre of
 * mass sees it. */
void vehicle_bushing_add_at_centre(const fb_body *b, const fb_bushing *u, const double *k,
                                   double *sum);
/* rc, after making a road type's error about one of its parameters
 * (err->part.field set, no kind) a part of the description
 * (FB_PART_ROAD). */
int vehicle_road_error(int rc, fb_err *err);
/* The modes of the diagram bd of the vehicle graph g, linearised at its
 * static equilibrium (fb_vehicle_linear_modes): a dense eigen-solve,
 * refused beforehand (fb_check_dense_eig) beyond FB_DENSE_EIG_MAX states
 * or memory_limit bytes. */
int vehicle_linear_modes(const fb_bg *g, fb_bd *bd, size_t memory_limit, fb_mode **modes,
                         size_t *nmodes, size_t *nstatic, fb_err *err);

/* ---- The vehicle's graph (assemble.c). */

/* What a diagram of a realised vehicle probes besides the outputs. */
enum {
  VEHICLE_PROBE_CONTACT = 1,  /* every tire's contact force */
  VEHICLE_PROBE_MOTION = 2,   /* the motion's probes (fb_vehicle_motion_probes) */
  VEHICLE_PROBE_HULL_ONLY = 4 /* with VEHICLE_PROBE_MOTION: the hull's coordinates alone */
};

/* Assembles the vehicle of s around hull (taken over) with the probes of
 * the outputs and those of extras (VEHICLE_PROBE_*): *graph and *probes
 * new; *ncoords (if not NULL) the hull's coordinates, which the motion's
 * first probe records. */
int vehicle_graph_around(const fb_scenario *s, fb_hull **hull, unsigned extras, size_t *ncoords,
                         fb_bg **graph, fb_probe_spec **probes, size_t *nprobes, fb_err *err);
/* ---- Realisation (vehicle.c) and inputs (stepper.c). */

/* fb_vehicle_new whose load reads the inputs held (borrowed: they must
 * outlive the vehicle; the stepper's layout, vehicle_hold_inputs),
 * for a stepper. */
int vehicle_new_held(const fb_scenario *s, fb_system sys, const fb_vehicle_opts *o,
                     const double *held, fb_vehicle **out, fb_err *err);
/* The vehicle's own diagram (owned by v). */
fb_bd *vehicle_diagram(fb_vehicle *v);
/* The initial state of v's diagram bd per s->initial into *x0 (new,
 * nstates + 1 values): zero, or the static equilibrium. */
int vehicle_initial_state(fb_vehicle *v, fb_bd *bd, double **x0, fb_err *err);
/* Makes the load of graph (the vehicle of s), and with o->road_inputs
 * its road, read the inputs held (borrowed; the stepper's layout),
 * before its diagram is built. */
int vehicle_hold_inputs(const fb_scenario *s, const fb_vehicle_opts *o, const double *held,
                        fb_bg *graph, fb_err *err);

/* The basis over the hull's nodal DOFs its coordinates are in (ndof x
 * *nb, column-major): NULL for nodal coordinates. */
const double *vehicle_hull_coordinate_basis(const vehicle_hull *h, size_t *nb);
/* The same of v's hull (NULL for System 1 or nodal coordinates; owned by
 * v). */
const double *vehicle_coordinate_basis(const fb_vehicle *v, size_t *nb);

/* The file paths of s's hull-source block (FB_PARAM_FILE parameters,
 * strings the block owns): freed (and NULL), or, in a description copied
 * byte for byte, replaced by copies of their own (0 when memory ran out:
 * those left NULL). */
void vehicle_hull_params_release(fb_scenario *s);
int vehicle_hull_params_copy(fb_scenario *copy);

#endif
