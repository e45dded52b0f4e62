/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: wheeled vehicles with rigid or flexible hulls, after Leite &
 * Da Silva's modular procedure (the reference vehicle's data sheet is
 * examples/apc6x6.yaml): a scenario (the vehicle as data: any number of
 * corners and mounted bodies, the outputs it records), subsystems as
 * bond-graph fragments with ports, their assembly through the ports.
 *
 * Axes (ISO 8855): origin at the hull's centre of mass, x forward, y left,
 * z up; roll phi about x, pitch theta about y (positive nose down). A hull
 * point (x, y) moves vertically by z + y phi - x theta. Forces are positive
 * upwards; spring and tire deflections are positive in compression.
 *
 * In use (examples/c/peak_tire_force.c, built with pkg-config):
 *
 *   fb_err err;
 *   fb_scenario *s = NULL;   (the caller's: fb_scenario_free)
 *   fb_result *r = NULL;     (the caller's: fb_result_free)
 *   if (fb_scenario_load("apc6x6.yaml", &s, &err) == FB_OK &&
 *       fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err) == FB_OK) {
 *     const long j = fb_result_find(r, "tire_force_LF");  (column, -1 none)
 *     for (size_t k = 0; j >= 0 && k < fb_result_nsamples(r); ++k)
 *       printf("%g %g\n", fb_result_row(r, k)[0], fb_result_row(r, k)[j]);
 *   } else {
 *     fprintf(stderr, "%s\n", err.msg);   (file:line:column: key: what)
 *   }
 *   fb_result_free(&r);
 *   fb_scenario_free(&s); */
#ifndef FLEXBOND_VEHICLE_H
#define FLEXBOND_VEHICLE_H

#include <stddef.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"
#include "flexbond/damper.h"
#include "flexbond/envelope.h"
#include "flexbond/error.h"
#include "flexbond/fem.h"
#include "flexbond/road.h"
#include "flexbond/sim.h"
#include "flexbond/spring.h"
#include "flexbond/stop.h"
#include "flexbond/tire.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum fb_payload_model {
  FB_PAYLOAD_WEIGHT_ONLY, /* payload adds force, no mass (paper) */
  FB_PAYLOAD_LUMPED       /* payload mass spread over the load points */
} fb_payload_model;

typedef enum fb_initial_state {
  FB_INITIAL_ZERO,  /* every state zero, gravity switched on at t = 0 (paper) */
  FB_INITIAL_STATIC /* static equilibrium under gravity and loads */
} fb_initial_state;

typedef enum fb_system {
  FB_SYSTEM_RIGID = 1,   /* System 1: rigid hull (bounce, roll, pitch) */
  FB_SYSTEM_FLEXIBLE = 2 /* System 2: finite-element hull */
} fb_system;

/* A realised vehicle and System 2's finite-element hull (below). */
typedef struct fb_vehicle fb_vehicle;
typedef struct fb_fe_hull fb_fe_hull;
/* A kind of output signal (below, "Outputs"). */
typedef struct fb_output_kind fb_output_kind;

/* A rigid body moving vertically on a spring and a damper in parallel to a
 * hull point (driver plus seat, engine, a commander's seat, a cargo box). */
typedef struct fb_mount {
  char *name;       /* instance name ("driver"); its hull mesh node set is
                       the name in capitals ("DRIVER"); owned */
  double mass;      /* kg */
  double stiffness; /* N/m */
  double damping;   /* N s/m */
  double x, y;      /* attachment point, m */
} fb_mount;

/* A walking-beam bogie: a beam carrying two wheels, at a ahead of its
 * pivot and b behind it, whose pivot rides on a spring and a damper
 * (vertical, no motion ratio) to the hull, as in the walking-beam tandems
 * of heavy trucks, where the beam's centre bushing sits on the
 * suspension's spring and the axles ride at its ends. The beam pitches
 * freely about the pivot; its centre of mass is at the pivot. */
typedef struct fb_bogie_params {
  const char *name;    /* for its modes' labels ("bogie pitch <name>"); borrowed, may be NULL */
  double a, b;         /* m, the front and rear wheels' distances from the pivot, > 0 */
  double beam_mass;    /* kg, the beam's (the wheels' are theirs) */
  double beam_inertia; /* kg m^2, the beam's pitch inertia about the pivot */
  double spring_k;     /* N/m, between the hull and the pivot */
  double damper_c;     /* N s/m */
} fb_bogie_params;

/* A walking-beam bogie of the description: the wheels and tires of two
 * corners on one side (front ahead of rear) ride at its beam's ends; the
 * pivot lies between them, at pivot_x, and rides on the bogie's own
 * spring and damper to the hull, whose force the hull takes at the two
 * corners' attachment points in the lever's proportions (b/(a+b) at the
 * front one, a/(a+b) at the rear one). The corners' own springs, dampers
 * and motion ratios are not used; their wheels, tires and names are
 * (road inputs, tire outputs, contact forces). */
typedef struct fb_bogie {
  char *name;          /* unique among the bogies; owned */
  char *front, *rear;  /* the corners at its ends, by name; owned */
  double pivot_x;      /* m, in the corners' frame, strictly between their x */
  double beam_mass;    /* kg */
  double beam_inertia; /* kg m^2, pitch, about the pivot */
  double spring_k;     /* N/m, the pivot's spring to the hull */
  double damper_c;     /* N s/m */
} fb_bogie;

/* An anti-roll bar between two corners of one axle: its force, a
 * compression force on the left corner's suspension (wheel down, hull up)
 * and the opposite on the right one's, is
 *   F = (stiffness / 2) (x_left - x_right) + (damping / 2) (v_left - v_right)
 * with x the wheels' travels relative to the hull (compression
 * positive). stiffness is the bar's rate at each wheel in roll (equal and
 * opposite travels, Milliken & Milliken, Race Car Vehicle Dynamics, SAE
 * 1995, ch. 16), so that it adds stiffness t^2 / 2 to the axle's roll
 * stiffness (t the track); a wheel lifted alone meets half of it. */
typedef struct fb_antiroll_bar {
  char *name;       /* unique among the bars; owned */
  char *left;       /* the corner on the left (y > 0); owned */
  char *right;      /* the corner on the right (y < 0); owned */
  double stiffness; /* N/m, at each wheel in roll */
  double damping;   /* N s/m, at each wheel in roll; 0: none */
} fb_antiroll_bar;

/* A bushing of a mounted rigid body (fb_body): a linear spring and a
 * damper in all six components between the body and the body it is
 * mounted on, at one point. Its force on the body is
 *   -(K d + C d'),   d = the body's motion at the point relative to the
 * parent's: three translations (x, y, z) then three rotations (about x,
 * y, z; small angles), vehicle axes. Full symmetric 6x6 matrices, row
 * major; fb_bushing_set_diagonal fills a bushing with one stiffness and
 * one damping per axis. */
typedef struct fb_bushing {
  double x, y, z; /* its point, m, vehicle axes */
  double k[36];   /* stiffness: N/m, N/rad, N m/m, N m/rad by block; symmetric,
                     positive semi-definite */
  double c[36];   /* damping: N s/m, N s/rad, N m s/m, N m s/rad; symmetric,
                     positive semi-definite */
  /* System 2, a bushing on the hull: the mesh's node set its hull side
   * is coupled to (owned), or NULL: the hull's nodes of the element set
   * `surface` (owned; NULL: hull.mesh.coupling.surface) within `radius`
   * (m, in plan; 0: the scenario's coupling radius) of its point. */
  char *node_set;
  char *surface;
  double radius;
} fb_bushing;

/* Fills b's stiffness and damping as diagonal matrices: k[0..2] (N/m) and
 * c[0..2] (N s/m) along x, y, z, k[3..5] (N m/rad) and c[3..5] (N m s/rad)
 * about x, y, z. */
void fb_bushing_set_diagonal(fb_bushing *b, const double *k6, const double *c6);

/* The most bushings a body has. */
#define FB_BODY_MAX_BUSHINGS 16

/* A mounted rigid body in six degrees of freedom (a turret, a seat, an
 * engine): its inertia at its centre of mass and the bushings that carry
 * it, to the hull or to another body. Motions are small (linear
 * kinematics about the reference position: docs/scenario-format.md,
 * "Mounted bodies"). */
typedef struct fb_body {
  char *name;     /* unique among the bodies, mounts, hull masses and corners; owned */
  char *parent;   /* the body it is mounted on, one before it in the list,
                     by name; NULL: the hull. Owned */
  double mass;    /* kg */
  double x, y, z; /* its centre of mass, m, vehicle axes */
  /* Its inertia tensor about its centre of mass, vehicle axes, kg m^2:
   * the matrix [[Ixx, -Ixy, -Ixz], [-Ixy, Iyy, -Iyz], [-Ixz, -Iyz, Izz]]
   * (products of inertia Ixy = integral of x y dm), positive definite. */
  double ixx, iyy, izz, ixy, ixz, iyz;
  fb_bushing *bushing; /* nbushings of them, at least 1; owned */
  size_t nbushings;
} fb_body;

/* A non-structural mass fixed to the hull's floor (a battery, ballast, an
 * armour plate): pure inertia. Its weight is part of load.total_weight,
 * which the load points carry; its mass moves with the hull, System 1's
 * (m r r' on the rigid inertia, r = [1, y, -x]) and System 2's (m on the
 * three translations of its floor node, node set MASS_<NAME>). */
typedef struct fb_hull_point_mass {
  char *name;  /* unique among the hull masses, mounts and corners; its hull
                  mesh node set is MASS_ and the name in capitals
                  ("MASS_BATTERY"); owned */
  double mass; /* kg */
  double x, y; /* m, on the floor */
} fb_hull_point_mass;

/* A shell section of the finite-element hull (hull.sections): the plates
 * of one element set, a part of the generated hull (FLOOR, ROOF, SIDES,
 * REAR_WALL, GLACIS, BULKHEADS, BULKHEAD_<k>) or a deck's *ELSET, with
 * their own material and thickness (hull.material's where the file leaves
 * them out) and a non-structural mass per area smeared into them
 * (fb_shell_props). In the file's order: a later section takes the
 * elements it shares with an earlier one. */
typedef struct fb_hull_section {
  char *set;                 /* the element set's name; owned */
  double young, poisson;     /* Pa, - */
  double density, thickness; /* kg/m^3, m */
  double nonstructural_mass; /* kg/m^2 */
} fb_hull_section;

/* One suspension: spring and shock absorber in parallel between the hull
 * point and the wheel (massless arm: spring travel = motion_ratio x wheel
 * travel relative to the hull), the wheel mass, the tire spring and
 * damper in parallel between the wheel and the road. */
typedef struct fb_corner_params {
  char *name; /* "LF"; instance "susp_LF", mesh node set "SUSP_LF"; owned */
  /* N/m: the linear spring law's rate, and the rate estimates use (the
   * finite-element hull's attachments, plausibility warnings) whatever
   * the law. */
  double spring_k;
  /* The suspension spring: a law of a spring gallery (flexbond/spring.h;
   * borrowed, NULL: fb_spring_law_linear) and its parameter block.
   * fb_corner_set_spring sets both. */
  const fb_spring_law *spring_law;
  fb_spring_params spring;
  /* Its bump and rebound stops (flexbond/stop.h); neither given: none. */
  fb_stops stops;
  /* The shock absorber: a law of a damper gallery (flexbond/damper.h;
   * borrowed, NULL: fb_damper_law_linear) and its parameter block.
   * fb_corner_set_damper sets both. */
  const fb_damper_law *damper_law;
  fb_damper_params damper;
  double motion_ratio; /* spring travel / wheel travel, > 0 */
  double x, y;         /* attachment point, m */
  double wheel_mass;   /* kg */
  double tire_k;       /* N/m */
  double tire_c;       /* N s/m */
  /* How the tire meets the road: a model of a tire gallery
   * (flexbond/tire.h; borrowed, NULL: fb_tire_model_bilateral) and its
   * parameter block. fb_corner_set_tire sets both. */
  const fb_tire_model *tire_model;
  fb_tire_params tire;
  /* m: the tire's static deflection under an equal share of the weight
   * on the tires, (load.total_weight + every wheel's weight) / (corners
   * tire_k), for a model that scales with it (fb_tire_context);
   * fb_vehicle_graph sets it, a caller of fb_vehicle_corner sets it
   * itself. */
  double tire_static_deflection;
  /* How the tire envelops the road (flexbond/envelope.h): a model of an
   * envelope gallery (borrowed, NULL: fb_envelope_model_point) and its
   * parameter block. fb_corner_set_envelope sets both. */
  const fb_envelope_model *envelope_model;
  fb_envelope_params envelope;
  /* m: the tire's free (unloaded) radius, which an envelope model that
   * reads it needs (fb_envelope_model.needs_radius); 0: not given. */
  double tire_radius;
} fb_corner_params;

/* Most bulkheads a hull may have. */
enum { FB_HULL_MAX_BULKHEADS = 8 };
/* The most modes a report pictures when listed (fb_scenario.pictured_modes). */
enum { FB_PICTURED_MODES_MAX = 16 };

typedef struct fb_hull_mesh_params {
  double width;       /* m, between the side walls, > 0 */
  double height;      /* m, floor to roof, > 0 */
  double x_rear;      /* m, rear wall */
  double x_front;     /* m, front end of floor, roof and side-wall boxes, > x_rear */
  double nose_length; /* m, nose tip line ahead of x_front, > 0 */
  double nose_height; /* m, nose tip line above the floor, in (0, height) */
  size_t nbulkheads;  /* 0 .. FB_HULL_MAX_BULKHEADS */
  double bulkhead_x[FB_HULL_MAX_BULKHEADS]; /* m, each in (x_rear, x_front) */
  int side_rows;           /* element rows up side walls, rear wall, bulkheads, >= 1 */
  int nose_rows;           /* element rows along each glacis plate, >= 1 */
  int nose_rung_divisions; /* intervals along each side wall's interior nose rung, >= 1 */
  /* Refinement, 1 .. 64: 1 is the default mesh; d splits every element
   * into d x d quadrilaterals or d^2 triangles, so every node of the
   * default mesh (all the special points) stays a node. */
  int density;
} fb_hull_mesh_params;

/* Where a description came from, as whoever made it keeps it (src/io
 * keeps a file's origin of every value and its plausibility warnings):
 * content behind ops, copied with the description (fb_scenario_clone)
 * and freed with it. The library never looks inside: it names the parts
 * of the description its errors are about (fb_err.part), and the maker
 * says where they came from (fb_scenario_locate). */
typedef struct fb_scenario_source fb_scenario_source;
/* Where System 2's hull mesh comes from (flexbond/hull_source.h), and a
 * set of such sources. */
typedef struct fb_hull_source fb_hull_source;
typedef struct fb_hull_source_gallery fb_hull_source_gallery;

/* Most bytes of a hull source's parameter block. */
#define FB_HULL_SOURCE_PARAMS_MAX ((size_t)256)

/* The parameter block a description holds for its hull source (its
 * declared parameters, fb_hull_source.param); the built-in sources keep
 * theirs in hull_deck and hull_mesh and declare none. */
typedef union fb_hull_source_params {
  max_align_t align_;
  unsigned char bytes[FB_HULL_SOURCE_PARAMS_MAX];
} fb_hull_source_params;
typedef struct fb_scenario_source_ops {
  /* A deep copy of src into *out; FB_ENOMEM when memory runs out. */
  int (*clone)(const fb_scenario_source *src, fb_scenario_source **out);
  void (*free)(fb_scenario_source *src);
} fb_scenario_source_ops;
struct fb_scenario_source {
  const fb_scenario_source_ops *ops;
};

/* One recorded signal of the vehicle (the scenario's `outputs` list,
 * docs/vehicle-outputs.md): a signal kind of one subsystem instance, or an
 * effort, flow or power of any bond of the assembled graph. Strings
 * owned by the scenario. */
typedef struct fb_output_spec {
  char *name;       /* CSV column, unique: "tire_force_LF" */
  char *signal;     /* a kind of fb_vehicle_output_kinds: "tire_force", "effort" */
  char *of;         /* the corner or mount it measures ("LF", "driver"); NULL
                       for the hull's torsion and for bond signals */
  char *bond;       /* bond signals: the bond's name in the assembled graph
                       ("susp_LF.b_tire"); NULL otherwise */
  char *unit;       /* from the kind (or the bond's domain), filled at load */
  char *title;      /* figure title; from the kind when the file gives none */
  char *label;      /* short label of the signal ("LF tire normal reaction") */
  int figure;       /* figure number (the paper's 8 .. 14), 0 for none */
  double window[2]; /* time window a figure shows, s; {0, 0}: the whole run */
  /* A hull point's signal (FB_OUTPUT_OF_HULL_POINT): the point, m, in
   * the vehicle frame (x, y as every position; z from the hull's centre
   * of mass, a deck's in the deck's frame), and the axis its translation
   * is measured along, ISO 8855: 0 x (forward), 1 y (left), 2 z (up). */
  double at[3];
  int direction;
  /* A bond signal on a multibond: the component it records, 1-based; 0
   * for a scalar bond (docs/vehicle-outputs.md). */
  long component;
  /* A hull stress signal (FB_OUTPUT_OF_HULL_STRESS, docs/stresses.md):
   * the shell element it reads, by its id in the hull's mesh, or 0 for the
   * element nearest the point `at`; the surface, FB_STRESS_TOP or
   * FB_STRESS_BOTTOM; and the stress component (fb_output_stress). */
  long element;
  int surface;
  int stress;
} fb_output_spec;

/* A hull stress signal's surface: the side the element's normal points
 * to (z = +t/2) or the other (docs/stresses.md, "Axes and signs"). */
enum { FB_STRESS_TOP = 0, FB_STRESS_BOTTOM = 1 };
/* A hull stress signal's component, in the element's local axes: sigma_x,
 * sigma_y, tau_xy (fb_shell_stress_state's order). */
typedef enum fb_output_stress {
  FB_STRESS_SX = 0,
  FB_STRESS_SY = 1,
  FB_STRESS_SXY = 2
} fb_output_stress;

/* The study's parameters. Strings and arrays are owned by the scenario. */
/* The coordinates of System 2's hull (hull.fe.coordinates): its nodal
 * displacements, with M, K and B = beta K as sparse fields (the
 * reference), or its free-free modes, where the same fields are diagonal
 * (M = I, K = diag(omega^2), B = beta K; Craig & Kurdila, "Fundamentals
 * of Structural Dynamics", 2nd ed., sec. 10.3). With every mode kept the
 * two are the same model. */
typedef enum fb_hull_coordinates { FB_HULL_NODAL = 0, FB_HULL_MODAL = 1 } fb_hull_coordinates;

/* The basis of a hull in modal coordinates (hull.fe.modes): */
typedef enum fb_hull_modes_kind {
  /* `auto` (the default): the rigid-body modes and as many blocks of
   * load-dependent Ritz vectors from the patterns (every attachment
   * point's force, the load, every output read from the hull's
   * deformation) as the receptances over the excitation's band need
   * (FB_HULL_BLOCK_TOL, fb_hull_excitation_hz; up to hull_cutoff_hz when
   * given). */
  FB_HULL_MODES_AUTO = 0,
  /* `all`: every mode, from a dense eigen-solve (the model without
   * truncation; its cost grows as the cube of the DOFs). */
  FB_HULL_MODES_ALL = 1,
  /* N: the N lowest free-free modes with the static correction of every
   * pattern (fb_fem_modal_basis). */
  FB_HULL_MODES_COUNT = 2
} fb_hull_modes_kind;

/* How the suspension and mount attachment points meet the hull mesh
 * (hull.mesh.coupling, docs/hull-mesh.md "Couplings"): each is a node
 * (NONE: its node set's one node, within 1 mm); or, with a coupling, the
 * nodes of its node set or, without one, those of the element set
 * `surface` within `radius` of it in plan: DISTRIBUTING spreads its force
 * over them (equilibrium with least squares nodal forces) and averages
 * their motion with the same weights; KINEMATIC ties it to the nearest of
 * them by a rigid lever (its rotations included). */
typedef enum fb_coupling_kind {
  FB_COUPLING_NONE = 0,
  FB_COUPLING_DISTRIBUTING = 1,
  FB_COUPLING_KINEMATIC = 2
} fb_coupling_kind;

/* The parts of a vehicle description an error can be about
 * (fb_err.part.kind; fb_err_part.field is a member's name in the part's
 * struct): the vehicle's own members (fb_scenario, index 0; "t_end",
 * "hull_mesh.x_rear", "road_iso"), an item of one of its lists (index:
 * its place in the list), or a load point (index k: load_x[k], load_y[k]).
 * The library raises these, never a file's key: the description's maker
 * says where the part came from (fb_scenario_locate for a file). */
typedef enum fb_part_kind {
  FB_PART_NONE = 0,
  FB_PART_VEHICLE = 1,       /* fb_scenario's members */
  FB_PART_CORNER = 2,        /* corner[index], fb_corner_params */
  FB_PART_MOUNT = 3,         /* mount[index], fb_mount */
  FB_PART_HULL_MASS = 4,     /* point_mass[index], fb_hull_point_mass */
  FB_PART_SECTION = 5,       /* section[index], fb_hull_section */
  FB_PART_OUTPUT = 6,        /* output[index], fb_output_spec */
  FB_PART_LOAD_POINT = 7,    /* (load_x[index], load_y[index]); field "" */
  FB_PART_ROAD = 8,          /* the road type's parameter field (fb_param.name); index 0 */
  FB_PART_TIRE = 9,          /* corner[index]'s tire model's parameter field (fb_param.name) */
  FB_PART_HULL_SOURCE = 10,  /* the hull source's parameter field (fb_param.name); index 0 */
  FB_PART_DAMPER = 11,       /* corner[index]'s damper law's parameter field (fb_param.name) */
  FB_PART_SPRING = 12,       /* corner[index]'s spring law's parameter field (fb_param.name) */
  FB_PART_STOP = 13,         /* corner[index]'s stops: field "bump_stop.gap", ... */
  FB_PART_ANTIROLL_BAR = 16, /* antiroll_bar[index], fb_antiroll_bar */
  FB_PART_BOGIE = 17,        /* bogie[index], fb_bogie */
  FB_PART_BODY = 14,         /* body[index], fb_body */
  FB_PART_BUSHING = 15,      /* the index-th bushing of all bodies, in order (body 0's first;
                                fb_scenario_bushing_at), fb_bushing */
  FB_PART_ENVELOPE = 18, /* corner[index]'s envelope model's parameter field (fb_param.name) */
  FB_PART_KINDS = 19
} fb_part_kind;

/* fb_err_set_part's arguments for member m of part kind k, index i:
 * `fb_err_set_part(err, FB_PART_AT(FB_PART_CORNER, c, spring_k))`. The
 * member's name is the C expression's, checked by the compiler through
 * FB_PART_TYPE's struct. */
#define FB_PART_AT(k, i, m) (k), (i), FB_ERR_NO_ELEMENT, fb_part_member_(k, m)
/* The same for element e of array member m ("hull_mesh.bulkhead_x"). */
#define FB_PART_ELEMENT(k, i, m, e) (k), (i), (e), fb_part_member_(k, m)
#define fb_part_member_(k, m) (&#m[0 * offsetof(FB_PART_TYPE_##k, m)])
typedef struct fb_scenario FB_PART_TYPE_FB_PART_VEHICLE;
typedef struct fb_corner_params FB_PART_TYPE_FB_PART_CORNER;
typedef struct fb_mount FB_PART_TYPE_FB_PART_MOUNT;
typedef struct fb_antiroll_bar FB_PART_TYPE_FB_PART_ANTIROLL_BAR;
typedef struct fb_bogie FB_PART_TYPE_FB_PART_BOGIE;
typedef struct fb_hull_point_mass FB_PART_TYPE_FB_PART_HULL_MASS;
typedef struct fb_hull_section FB_PART_TYPE_FB_PART_SECTION;
typedef struct fb_output_spec FB_PART_TYPE_FB_PART_OUTPUT;
typedef struct fb_body FB_PART_TYPE_FB_PART_BODY;
typedef struct fb_bushing FB_PART_TYPE_FB_PART_BUSHING;

typedef struct fb_scenario {
  char *name;
  char *path;     /* file it was loaded from (for messages), may be NULL */
  double gravity; /* m/s^2 */
  /* Hull (paper, Tables 1-2). */
  /* Positions (every x and y of the file) are in the vehicle frame: the
   * hull's centre of mass unless the file declares a frame origin
   * (frame.origin, a description such as "front axle, floor"); then the
   * hull's centre of mass in that frame is hull_cg_x/y, computed from the
   * mesh (fb_vehicle_hull_properties) or given as hull.centre_of_mass. */
  char *frame_origin;          /* NULL: positions relative to the hull's centre of mass */
  int hull_cg_given;           /* hull.centre_of_mass was written */
  double hull_cg_x, hull_cg_y; /* m, in the vehicle frame (0 without a frame) */
  /* m, its height in the vehicle frame: hull.centre_of_mass's z, or set by
   * fb_vehicle_hull_complete, the generated mesh's above its floor with a
   * frame, a deck's in the deck's frame, else 0. Inside, positions and the mesh are relative to
   * the centre of mass; what a user reads is in the vehicle frame
   * (fb_scenario_frame_offset). */
  double hull_cg_z;
  /* Rigid-body properties (paper, Table 2): the structure's, without the
   * declared masses below. With a finite-element hull they may be left
   * out (hull_mass_given 0): the mesh's are used. */
  int hull_mass_given;       /* mass, Ixx, Iyy written in the file */
  double hull_mass;          /* kg */
  double hull_ixx, hull_iyy; /* kg m^2 about the hull's centre of mass */
  /* The rest of its inertia tensor (fb_body's convention), which a hull
   * carrying mounted rigid bodies (nbodies > 0) moves in six degrees of
   * freedom needs: given (hull_izz_given), or the mesh's with a
   * finite-element hull (fb_vehicle_hull_complete); products 0 unless
   * given. */
  int hull_izz_given;
  double hull_izz, hull_ixy, hull_ixz, hull_iyz; /* kg m^2 */
  /* Non-structural masses on the hull's floor (hull.masses), in the
   * file's order. */
  fb_hull_point_mass *point_mass;
  size_t npoint_masses;
  double young, poisson;     /* Pa, - (System 2) */
  double density, thickness; /* kg/m^3, m (System 2) */
  /* Per element set sections (hull.sections), in the file's order. */
  fb_hull_section *section;
  size_t nsections;
  /* Edges whose roll difference is the torsion angle: front and rear
   * edge x, left and right end y (System 2 uses the mesh's node sets). */
  double edge_front_x, edge_rear_x, edge_left_y, edge_right_y; /* m */
  /* Load: total weight of hull plus payload (the declared hull masses'
   * included), spread equally over the load points. */
  double total_weight; /* N */
  fb_payload_model payload;
  size_t nload;
  double *load_x, *load_y; /* m, nload each */
  /* The mounted bodies and the corners (wheel stations), in the file's
   * order, each with a unique name; at least 3 corners. */
  fb_mount *mount;
  size_t nmounts;
  /* The mounted rigid bodies in six degrees of freedom, in the file's
   * order: a body's parent comes before it. */
  fb_body *body;
  size_t nbodies;
  fb_corner_params *corner;
  size_t ncorners;
  /* The anti-roll bars, each between two of the corners (by name). */
  fb_antiroll_bar *antiroll_bar;
  size_t nantiroll_bars;
  /* The walking-beam bogies, each on two of the corners (by name). */
  fb_bogie *bogie;
  size_t nbogies;
  /* The signals recorded, in CSV column order (docs/vehicle-outputs.md). */
  fb_output_spec *output;
  size_t noutputs;
  double speed; /* m/s */
  /* The road under the wheels (docs/roads.md): a type of a road gallery
   * (fb_road_type_bump, fb_road_type_iso8608, fb_road_type_profile or a
   * program's own; borrowed, it outlives the description) and its
   * parameter block, which the description owns (fb_road_params_release
   * when it is freed). fb_scenario_set_road sets both. */
  const fb_road_type *road_type;
  fb_road_params road;
  /* System 2's modes a report pictures, by number (1 = the lowest),
   * whole; none: those fb_mode_set_pictured chooses. */
  size_t npictured_modes;
  double pictured_modes[FB_PICTURED_MODES_MAX];
  /* Simulation. */
  double t_end, rtol, atol, max_step, sample_rate; /* s, -, -, s, Hz */
  long max_steps;                /* internal steps allowed in all (FB_SIM_DEFAULT_MAX_STEPS) */
  int stability_limit_detection; /* fb_sim_opts.stability_limit_detection */
  fb_initial_state initial;
  /* System 2's hull (the optional hull.mesh and hull.fe sections;
   * has_fe_hull is 0 without them). */
  int has_fe_hull;
  /* Where the mesh comes from (flexbond/hull_source.h; borrowed, NULL:
   * the generator), set with fb_scenario_set_hull_source. The built-in
   * sources read their values from hull_deck (fb_hull_source_deck) and
   * hull_mesh (fb_hull_source_generator). */
  const fb_hull_source *hull_source;
  fb_hull_source_params hull_params; /* its block, set with it */
  char *hull_deck;                   /* Abaqus/CalculiX deck's or gmsh mesh's path */
  /* The hull's mesh as the loader made it, once: the one its source read
   * (moved to the structure's centre of mass), or the one it made (owned).
   * fb_vehicle_fe_hull copies it rather than making it again, as long as
   * the source's inputs are still those it was made from, hull_source_key
   * (the source's key op): a program that changes hull_mesh or a point
   * after loading gets a mesh of its own. */
  fb_mesh *hull_source_mesh;
  uint64_t hull_source_key;
  /* hull.mesh.converged_density: a density of the generator at which the
   * hull's modes have converged (docs/hull-mesh.md), where `flexbond run`
   * runs System 2 a second time to compare; 0: none. */
  int hull_converged_density;
  /* Every file the scenario names (damper tables, road profile, hull
   * deck), as resolved, each once in reading order: what a result
   * depends on besides the scenario itself (owned). */
  char **inputs;
  size_t ninputs;
  /* Where the description came from (a file's origins of its values and
   * plausibility warnings: fb_scenario_locate, fb_scenario_warning), its
   * maker's; NULL for one made without a file. Owned. */
  fb_scenario_source *source;
  fb_hull_mesh_params hull_mesh;        /* generator parameters */
  fb_mass_kind hull_mass_matrix;        /* consistent (default) or lumped */
  double hull_drill_factor;             /* fictitious drilling stiffness factor */
  double hull_damping_ratio;            /* of the first elastic free-free mode (B = beta K) */
  fb_hull_coordinates hull_coordinates; /* System 2's hull states */
  fb_coupling_kind coupling;            /* hull.mesh.coupling.kind, NONE without it */
  double coupling_radius;               /* m, in plan */
  char *coupling_surface;               /* element set of the candidate nodes; owned */
  /* Modal coordinates: which free-free modes the hull keeps
   * (hull.fe.modes; docs/hull-mesh.md, "The modal basis"). */
  fb_hull_modes_kind hull_modes_kind;
  int hull_modes;        /* FB_HULL_MODES_COUNT: the N lowest */
  double hull_cutoff_hz; /* FB_HULL_MODES_AUTO: the band's top, Hz, in place of the
                            excitation's; 0: the excitation's */
} fb_scenario;

/* The part p of s in the description's own words, into buf (size bytes):
 * the C path of the member ("corner[2] (LR).spring_k",
 * "hull_mesh.bulkhead_x[1]", "load point 3"), for a description that no
 * file or program argument gave. s may be NULL (no names). Returns buf. */
char *fb_scenario_part_text(const fb_scenario *s, const fb_err_part *p, char *buf, size_t size);

/* The hull's attachment points, in the order of the hull's "attach"
 * port: the scenario's corners (s->corner[0 .. ncorners)), then its
 * mounted bodies (s->mount[0 .. nmounts)). */
size_t fb_scenario_nattach(const fb_scenario *s);
/* The scenario's outputs (s->output) for a program that cannot read the
 * struct (a language binding): their number, and output o's name and
 * unit, owned by s (NULL when o >= fb_scenario_noutputs(s)). */
size_t fb_scenario_noutputs(const fb_scenario *s);
const char *fb_scenario_output_name(const fb_scenario *s, size_t o);
const char *fb_scenario_output_unit(const fb_scenario *s, size_t o);
/* Likewise the corners: their number, corner c's name (NULL when c is out
 * of range) and attachment point (m, in the vehicle frame, the file's:
 * fb_scenario_frame_offset; *x and *y untouched when c is out of range),
 * and the road speed (m/s). */
size_t fb_scenario_ncorners(const fb_scenario *s);
/* The name of corner c's tire model ("bilateral"), NULL when c is out
 * of range. */
const char *fb_scenario_corner_tire(const fb_scenario *s, size_t c);
const char *fb_scenario_corner_name(const fb_scenario *s, size_t c);
void fb_scenario_corner_position(const fb_scenario *s, size_t c, double *x, double *y);
double fb_scenario_speed(const fb_scenario *s);
/* Index of the corner or mount named name, -1 if none. */
long fb_scenario_corner_find(const fb_scenario *s, const char *name);
long fb_scenario_mount_find(const fb_scenario *s, const char *name);
/* Index of the bogie named name, -1 if none. */
long fb_scenario_bogie_find(const fb_scenario *s, const char *name);
/* Index of the body named name, -1 if none. */
long fb_scenario_body_find(const fb_scenario *s, const char *name);
/* The bushings of every body, body 0's first (FB_PART_BUSHING's index):
 * their number, and the body and the body's bushing of bushing k (0
 * when k is out of range). */
size_t fb_scenario_nbushings(const fb_scenario *s);
int fb_scenario_bushing_at(const fb_scenario *s, size_t k, size_t *body, size_t *bushing);
/* Index of the bogie whose beam carries corner c's wheel, -1 if none (the
 * corner then has its own spring and damper). */
long fb_scenario_corner_bogie(const fb_scenario *s, size_t c);
/* The plausibility warnings of a loaded scenario, each "FILE:LINE:COL:
 * KEY: VALUE is implausible: WHY" with the fields of a located error
 * (docs/errors.md, "Implausible values"); NULL for i out of range; owned
 * by s. */
size_t fb_scenario_nwarnings(const fb_scenario *s);
const fb_err *fb_scenario_warning(const fb_scenario *s, size_t i);
/* The declared hull masses' sum (kg), 0 without any. */
double fb_scenario_point_masses_total(const fb_scenario *s);
/* The lumped payload's mass (kg): total_weight / gravity less the hull's
 * structure (hull_mass) and its declared masses; what FB_PAYLOAD_LUMPED
 * spreads over the load points. */
double fb_scenario_payload_mass(const fb_scenario *s);
/* The density at which System 2 runs a second time to compare, its modes
 * converged: hull_converged_density when it is above the generated hull's
 * own density; 0 when there is none (or the hull is a deck, used as it
 * is). */
int fb_scenario_converged_density(const fb_scenario *s);
/* Puts s's hull in the automatic modal basis (FB_HULL_MODES_AUTO), as a
 * rerun on the converged mesh takes it whatever basis s had: every mode
 * or the nodal coordinates of the refined hull would make a dense or a
 * large problem nobody asked for. A cut-off given for the automatic basis
 * stays; any other is dropped. */
void fb_scenario_use_auto_basis(fb_scenario *s);
/* The road has two tracks: wheels with y > 0 run on the left one, the
 * others on the right one. The lateral distance between them (m): the
 * first corner's y (it leads the left track) minus the y of the first
 * corner with y <= 0; 0 when every corner is on the left. */
double fb_scenario_track_width(const fb_scenario *s);

/* Completes a scenario the loader has read and checked, in place (the
 * loader calls it last): with a declared frame (s->frame_origin), the
 * hull's centre of mass in it (the generated mesh's, or
 * hull.centre_of_mass without a mesh) goes into hull_cg_x/y and every
 * position is moved to it; with a finite-element hull, the hull's mass,
 * Ixx and Iyy are the mesh's when the file gives none, and the file's
 * are refused (FB_EINVAL naming both, about the part hull_mass ...) when
 * they differ from the mesh's by more than 0.5 %, and Izz and the
 * products of inertia are the mesh's unless given (hull_izz_given); the
 * heights (the mounted rigid bodies', a hull point's) move with the
 * other positions, by hull_cg_z. Errors name the part of
 * the description they are about (fb_err.part); the caller locates them
 * (fb_scenario_locate). */
int fb_vehicle_hull_complete(fb_scenario *s, fb_err *err);
/* Checks the outputs of a completed scenario (the loader calls it after
 * fb_vehicle_hull_complete) as far as the vehicle can before it is
 * realised: each hull point's point on the finite-element hull's mesh (if
 * it has one) within 5 cm, and each bond signal's bond in System 1's
 * assembled graph or among the finite-element hull's bonds, a multibond
 * with its component (docs/vehicle-outputs.md). FB_EINVAL about the
 * output's at, bond or component (fb_err.part), which the caller locates;
 * the realised vehicle checks its own graph again (fb_vehicle_assemble). */
int fb_vehicle_outputs_check(const fb_scenario *s, fb_err *err);
/* Where the frame inside (the hull structure's centre of mass, which
 * every position and the mesh are relative to after
 * fb_vehicle_hull_complete) lies in the vehicle frame, the file's
 * (s->frame_origin; a deck's own frame; without either, the centre of
 * mass itself): o = (hull_cg_x, hull_cg_y, hull_cg_z), m. A position p
 * inside is p + o in the file's frame; axes are parallel. */
void fb_scenario_frame_offset(const fb_scenario *s, double o[3]);

/* Loads and validates a scenario file (format: docs/scenario-format.md).
 * Errors are "FILE:LINE:COL: KEY: message". A value that is legal but
 * implausible (outside what real vehicles have: a 20 m plate, a tire of
 * 1 N/m, a weight below the hull's masses) is no error but a warning the
 * scenario keeps: fb_scenario_nwarnings, fb_scenario_warning. */
int fb_scenario_load(const char *path, fb_scenario **out, fb_err *err);
int fb_scenario_load_string(const char *text, size_t len, const char *display_name,
                            fb_scenario **out, fb_err *err);

/* One replaced value of a scenario file ("flexbond sweep --set KEY=VALUE",
 * docs/sweep.md). */
typedef struct fb_scenario_override {
  /* A key path of the scenario file ("road.speed_kmh",
   * "suspensions.axles[0].spring_k", "hull.mesh.generator.bulkheads[1]"),
   * a key the file leaves out included ("simulation.max_steps",
   * "outputs[0].name"), or a key name without '.' that names exactly one
   * key of the file, or of the format when the file has none of that name
   * ("speed_kmh", "max_steps"). */
  const char *key;
  /* The new value's text, read as if it were written in the file: a
   * number, an expression over `parameters`, a choice ("static"). One
   * scalar (never YAML structure), one line, no control characters. */
  const char *value;
  /* How the caller wrote the override, for its messages and for
   * fb_err.source_text ("overrides['speed_kmh']=-5" from Python); NULL:
   * "--set KEY=VALUE", the command line's. Initialise the struct by
   * member names: members may be added. */
  const char *label;
} fb_scenario_override;

/* Loads the scenario at path as fb_scenario_load does, the reader taking
 * each ov[i].value in place of the file's value at ov[i].key (a key the
 * file leaves out is added in its section, and the section too when the
 * file leaves that out), so that the reader's every check and unit
 * conversion applies to it; the value's origin names the override, at
 * the replaced value's line and column (at its section's for a key the
 * file leaves out). n = 0 is fb_scenario_load. Errors:
 *   FB_EINVAL "--set KEY=VALUE: FILE[:LINE:COL]: ..." for a key that is
 *     malformed, names no key of the format (with a suggestion) or an
 *     item beyond a list's, is ambiguous (naming every candidate path),
 *     is not a single value (a section, a list), or is set by two
 *     overrides, and for a value with a control character;
 *   the reader's "FILE:LINE:COL: KEY: message" prefixed by the override
 *     whose value KEY is (fb_err.source FB_SOURCE_OVERRIDE, source_text
 *     "--set KEY=VALUE"), or by every override ("--set K1=V1 --set K2=V2: ")
 *     when the message names another key (a bump that no longer fits in
 *     the run);
 *   FB_EIO, FB_EPARSE (the file itself), FB_ENOMEM without prefix. */
int fb_scenario_load_overrides(const char *path, const fb_scenario_override *ov, size_t n,
                               fb_scenario **out, fb_err *err);
/* As fb_scenario_load_overrides for a document in memory (display_name as
 * for fb_scenario_load_string). */
int fb_scenario_load_string_overrides(const char *text, size_t len, const char *display_name,
                                      const fb_scenario_override *ov, size_t n,
                                      fb_scenario **out, fb_err *err);
/* What a load knows besides the document. Initialise by member names:
 * members may be added. */
typedef struct fb_scenario_load_opts {
  /* The road types the document may name (road.<type>); NULL: the
   * built-in ones. Borrowed for the call; its types are borrowed by the
   * scenario, and must outlive it. */
  const fb_road_gallery *roads;
  /* The tire models the document may name (wheel.tire_contact); NULL:
   * the built-in ones. Borrowed as roads is. */
  const fb_tire_gallery *tires;
  /* The hull sources the document may name (hull.mesh.<source>); NULL:
   * the built-in ones. Borrowed as roads is. */
  const fb_hull_source_gallery *hull_sources;
  /* The damper laws the document may name (a corner's damper.<law>);
   * NULL: the built-in ones. Borrowed as roads is. */
  const fb_damper_gallery *dampers;
  /* The envelope models the document may name (wheel.envelope); NULL:
   * the built-in ones. Borrowed as roads is. */
  const fb_envelope_gallery *envelopes;
  /* Values read in place of the document's, as for
   * fb_scenario_load_overrides. */
  const fb_scenario_override *overrides;
  size_t noverrides;
} fb_scenario_load_opts;
/* fb_scenario_load_overrides and fb_scenario_load_string_overrides with
 * the options o (NULL: none). An error about a road type's parameter is
 * located at its key, road.<type>.<parameter>. */
int fb_scenario_load_with(const char *path, const fb_scenario_load_opts *o, fb_scenario **out,
                          fb_err *err);
int fb_scenario_load_string_with(const char *text, size_t len, const char *display_name,
                                 const fb_scenario_load_opts *o, fb_scenario **out,
                                 fb_err *err);
/* The full key path of key (as fb_scenario_override.key) in the scenario
 * file at path, into *full (new; the caller frees it), checking that it
 * names a single value the file has or could have: lets a caller tell a
 * bad key (FB_EINVAL, the messages of fb_scenario_load_overrides without
 * the prefix) from a bad value before loading. FB_EIO, FB_EPARSE for the
 * file, FB_ENOMEM. */
int fb_scenario_override_key(const char *path, const char *key, char **full, fb_err *err);
/* The unit a scenario file writes the value at full_path in (a path as
 * fb_scenario_override_key gives it: "road.speed_kmh" is "km/h",
 * "suspensions.axles[0].spring_k" "N/m"; docs/scenario-format.md), NULL
 * for a key without a unit or no key of the format. */
const char *fb_scenario_key_unit(const char *full_path);
/* What a vehicle needs of a description, whoever made it: each scalar the
 * vehicle is built from finite and physical (positive masses and
 * stiffnesses, a Poisson's ratio in [0, 1/2), SI units; a damper table's
 * points, a road's parameters and the generator's geometry are checked by
 * their own constructors), and the rules between values (points on the
 * floor, unique names, the bump inside the run, outputs that name a
 * corner or mount). FB_EINVAL about the part concerned (fb_err.part:
 * "must be > 0 N/m (got -1)" about corner 2's spring_k), which the
 * description's maker locates (fb_scenario_locate: the file's line and
 * key). fb_vehicle_new checks its description so. */
int fb_scenario_check(const fb_scenario *s, fb_err *err);
/* For an error about s's values found after loading (by fb_scenario_check,
 * fb_vehicle_new, building System 2's hull: none of them locates its own
 * errors), whose fb_err.part names the part of the description, or whose
 * fb_err.key is a key path of the file: for a loaded scenario, sets err's
 * key, file, line, column and source fields from where the loader read
 * that value and prefixes its message "FILE:LINE:COL: PATH: " (and the
 * override's label, "--set KEY=VALUE: "), as the loader's own errors read
 * (fb_err_prefix_location: fb_err.text_start marks the text after it);
 * for a scenario made without a file, prefixes the part in the
 * description's words (fb_scenario_part_text). Nothing is read again.
 * Returns err->code. */
int fb_scenario_locate(const fb_scenario *s, fb_err *err);
void fb_scenario_free(fb_scenario **s);
/* Deep copy. */
int fb_scenario_clone(const fb_scenario *s, fb_scenario **out, fb_err *err);

/* The tire of corner c: model m (borrowed: it outlives c) and a new
 * block of its defaults (fb_tire_params_init), which *params points to
 * (inside c) for the caller to fill. FB_EINVAL when m is not sound
 * (fb_tire_model_check). */
int fb_corner_set_tire(fb_corner_params *c, const fb_tire_model *m, void **params, fb_err *err);
/* The shock absorber of corner c: law l (borrowed: it outlives c) and a
 * new block of its defaults (fb_damper_params_init), which *params
 * points to when params is not NULL. FB_EINVAL when l is not sound
 * (fb_damper_law_check). */
int fb_corner_set_damper(fb_corner_params *c, const fb_damper_law *l, void **params,
                         fb_err *err);
/* The law of corner c's shock absorber: c->damper_law,
 * fb_damper_law_linear when NULL. */
const fb_damper_law *fb_corner_damper_law(const fb_corner_params *c);
/* 1 when corner c's shock absorber is linear with its values (the law's
 * linear op), so a linear analysis needs no linearisation for it. */
int fb_corner_damper_linear(const fb_corner_params *c);
/* The spring of corner c: law l (borrowed: it outlives c) and a new
 * block of its defaults (fb_spring_params_init), which *params points to
 * when params is not NULL. FB_EINVAL when l is not sound
 * (fb_spring_law_check). */
int fb_corner_set_spring(fb_corner_params *c, const fb_spring_law *l, void **params,
                         fb_err *err);
/* The law of corner c's spring: c->spring_law, fb_spring_law_linear when
 * NULL. */
const fb_spring_law *fb_corner_spring_law(const fb_corner_params *c);
/* What c's spring law knows of c (fb_spring_context; c->name borrowed). */
fb_spring_context fb_corner_spring_context(const fb_corner_params *c);
/* The model of corner c's tire: c->tire_model, fb_tire_model_bilateral
 * when it has none (a corner made by hand, zeroed). */
const fb_tire_model *fb_corner_tire_model(const fb_corner_params *c);
/* What c's tire model knows of c (fb_tire_context; c->name borrowed). */
fb_tire_context fb_corner_tire_context(const fb_corner_params *c);
/* The envelope of corner c's tire: model m (borrowed: it outlives c)
 * and a new block of its defaults (fb_envelope_params_init), which
 * *params points to when params is not NULL. FB_EINVAL when m is not
 * sound (fb_envelope_model_check). */
int fb_corner_set_envelope(fb_corner_params *c, const fb_envelope_model *m, void **params,
                           fb_err *err);
/* The model of corner c's envelope: c->envelope_model,
 * fb_envelope_model_point when NULL. */
const fb_envelope_model *fb_corner_envelope_model(const fb_corner_params *c);
/* What c's envelope model knows of c (fb_envelope_context; c->name
 * borrowed). */
fb_envelope_context fb_corner_envelope_context(const fb_corner_params *c);

/* Every tire of s whose model names a model for linear analyses
 * (fb_tire_model.in_contact: a unilateral tire's branch in contact, at
 * rest) becomes that model, with its defaults; the others stay (a
 * Hunt-Crossley tire is linearised with the rest at the static
 * equilibrium). */
void fb_scenario_tires_in_contact(fb_scenario *s);

/* The road of s: releases the old type's block, sets type t (borrowed:
 * it outlives s) and a new block of its defaults (fb_road_params_init),
 * which *params points to (owned by s) for the caller to fill; then
 * fb_scenario_prepare_road. FB_EINVAL when t is not sound
 * (fb_road_type_check). */
int fb_scenario_set_road(fb_scenario *s, const fb_road_type *t, void **params, fb_err *err);
/* ---- A description made by a program (src/vehicle/builder.c): a new
 * one, then its parts added by copy (the description owns what it holds;
 * the caller keeps its arguments). Scalars (gravity, the hull's
 * material, the simulation's settings, has_fe_hull and hull_mesh for
 * System 2, ...) are set in the struct; fb_scenario_check says what is
 * missing or wrong, naming the part (fb_scenario_part_text). */

/* *out new: named name (NULL: "vehicle"), no corner, mount, load point
 * or output yet, no road (fb_scenario_set_road), System 1 only
 * (has_fe_hull 0); standard gravity 9.80665 m/s^2, a weight-only
 * payload, the solver's defaults (fb_sim_opts_default: t_end 1 s,
 * rtol 1e-6, atol 1e-9, 1000 samples/s) and a start from the static
 * equilibrium; for System 2, modal hull coordinates with the `auto`
 * basis. FB_ENOMEM. */
int fb_scenario_new(const char *name, fb_scenario **out, fb_err *err);
/* The rigid hull's mass (kg) and inertias about its centre of mass
 * (kg m^2), given (hull_mass_given). */
void fb_scenario_set_rigid_hull(fb_scenario *s, double mass, double ixx, double iyy);
/* Appends a copy of c (its name copied; c stays the caller's). FB_EINVAL
 * without a name, FB_ENOMEM. The same for a mounted body and a hull
 * mass; a load point is its position (m). */
int fb_scenario_add_corner(fb_scenario *s, const fb_corner_params *c, fb_err *err);
int fb_scenario_add_mount(fb_scenario *s, const fb_mount *m, fb_err *err);
int fb_scenario_add_point_mass(fb_scenario *s, const fb_hull_point_mass *m, fb_err *err);
/* Appends a copy of the anti-roll bar b (its name and corners' names
 * copied). FB_EINVAL without a name or a corner's name, FB_ENOMEM;
 * fb_scenario_check says whether its corners exist and face each other. */
int fb_scenario_add_antiroll_bar(fb_scenario *s, const fb_antiroll_bar *b, fb_err *err);
/* The same for a walking-beam bogie (fb_scenario_check says whether its
 * corners exist, on one side, around its pivot). */
int fb_scenario_add_bogie(fb_scenario *s, const fb_bogie *b, fb_err *err);
int fb_scenario_add_load_point(fb_scenario *s, double x, double y, fb_err *err);
/* Appends a copy of the mounted rigid body b: its name, its parent's
 * name and its bushings (with their node sets) copied. FB_EINVAL without
 * a name or without a bushing, or with more than FB_BODY_MAX_BUSHINGS;
 * FB_ENOMEM. fb_scenario_check checks the rest. */
int fb_scenario_add_body(fb_scenario *s, const fb_body *b, fb_err *err);
/* Appends a copy of the output o: its signal (a kind of
 * fb_vehicle_output_kinds) and subject (`of` a corner or mount added
 * before, `bond`, or none for the hull); name, unit, title and label
 * left NULL come from the kind (fb_output_spec_complete). FB_EINVAL for
 * an unknown signal, a subject the kind does not take, or a name an
 * output has already. */
int fb_scenario_add_output(fb_scenario *s, const fb_output_spec *o, fb_err *err);
/* Fills o's name, title, label and unit where NULL from kind's patterns
 * ("tire_force_%s" with o->of; a bond signal's column is the signal and
 * the bond, '.' as '_'). FB_ENOMEM. */
int fb_output_spec_complete(fb_output_spec *o, const fb_output_kind *kind, fb_err *err);

/* The road type's prepare op (reads what its values name, resolves
 * alternatives); errors name their parameter (FB_PART_ROAD). */
int fb_scenario_prepare_road(fb_scenario *s, fb_err *err);
/* What the road type needs of the vehicle (fb_road_layout). */
fb_road_layout fb_scenario_road_layout(const fb_scenario *s);
/* 1 and *out filled when the road is a stationary random one (its
 * type's random op), else 0. */
int fb_scenario_road_random(const fb_scenario *s, fb_road_iso8608_params *out);

/* Position (m) of the wheel of `corner` on its track at t = 0: it is at
 * start + speed t later (wheels of one side follow one track, the rear
 * ones behind by their spacing; docs/roads.md); the road type's
 * wheel_start. */
double fb_scenario_wheel_start(const fb_scenario *s, int corner);
/* Time at which the wheel of `corner` meets the road's feature (the
 * bump's leading edge: first_contact + ((x_LF - x) + (y_LF - y)
 * tan(angle)) / speed); on a road whose feature starts at s = 0 of its
 * tracks (a random road, a profile), the time it reaches s = 0 (negative
 * when it is already past it at t = 0). A tire that envelops the road
 * meets it earlier by its envelope's reach over the speed. */
double fb_scenario_road_entry(const fb_scenario *s, int corner);
/* Time it leaves the feature (the bump's: entry + length / speed; an
 * enveloping tire later by its reach over the speed); t_end on a road
 * that goes on. */
double fb_scenario_road_exit(const fb_scenario *s, int corner);

/* ---- System 2: the finite-element hull's mesh (docs/hull-mesh.md).
 *
 * A closed, welded box of flat plates of the scenario's thickness: floor
 * (z = 0 in the hull frame below), roof (z = height), two side walls
 * (y = +-width/2), a vertical rear wall (x = x_rear), a wedge nose of two
 * full-width glacis plates from the box's front end (x = x_front) to a
 * transverse nose tip line (x_front + nose_length, nose_height), and
 * full cross-section transverse bulkheads. Every quadrilateral is a
 * rectangle; the side walls' nose triangles (between the glacis plates)
 * are meshed with triangles. Floor lines run through every scenario point
 * (load points, the corners' and mounted bodies' attachments, the hull
 * masses), which are floor nodes (those at y = +-width/2 lie on the side
 * walls' bottom edges).
 *
 * Frame: x positions are in the vehicle axes, i.e. relative to the hull's
 * centre of mass, for the nominal geometry; the generator computes the
 * plates' actual centre of mass, places the scenario points relative to
 * it and shifts the mesh so that its centre of mass is the origin (for the
 * fitted defaults that shift is below 1e-12 m). Heights are given above
 * the floor; in the mesh the floor lies at z = -(centre of mass height). */

/* The defaults, fitted so that the mesh's mass and inertias about its
 * centre of mass equal the paper's (4041.72 kg, Ixx 4173.49, Iyy 15175.96
 * kg m^2) for 8.5 mm steel and the reference scenario's points, with 28
 * triangles and 212 quadrilaterals at density 1: width from the scenario
 * (between the left and right suspension points, 2.10 m), height 1.7408
 * m, x_rear -2.6580 m, x_front 2.4781 m, nose 0.80 m long and 0.60 m high,
 * bulkheads at -2.2741 (rear compartment), -1.00 (rear axle) and 1.90 m
 * (front axle), 2 side rows, 3 nose rows, 3 rung divisions, density 1.
 * FB_EINVAL if s or p is NULL. */
int fb_hull_mesh_params_default(const fb_scenario *s, fb_hull_mesh_params *p, fb_err *err);

/* Builds the hull mesh for the scenario's points (*out is new; nodes and
 * elements numbered 1, 2, ... in index order) with the node sets
 *   LOAD       the nload load points, in the scenario's order;
 *   SUSP_<CORNER> per corner, <MOUNT> (the mount's name in capitals:
 *              DRIVER, ENGINE) per mounted body: one node each, the
 *              attachment points;
 *   MASS_<NAME> per hull mass (its name in capitals: MASS_BATTERY): one
 *              node, its point;
 *   FRONT_EDGE, REAR_EDGE  the end nodes of the floor's front (x_front)
 *              and rear (x_rear) transverse edges, left (y > 0) first:
 *              the torsion angle's edge lines (Fig. 10);
 *   ALL        every node.
 * p NULL means the defaults. FB_EINVAL on bad parameters, a point outside
 * the floor, or two distinct node lines closer than 1 mm (e.g. a bulkhead
 * next to a load point), about the part of the description concerned
 * (fb_err.part: corner 0's x, load point 3, the member
 * hull_mesh.bulkhead_x's element 1); FB_ENOMEM. */
int fb_hull_mesh_generate(const fb_scenario *s, const fb_hull_mesh_params *p, fb_mesh **out,
                          fb_err *err);
/* A fingerprint of everything fb_hull_mesh_generate(s, p) reads (the
 * parameters, the materials and sections its centroid weighs, the points
 * and their names): equal keys, the same mesh. */
uint64_t fb_hull_mesh_key(const fb_scenario *s, const fb_hull_mesh_params *p);

/* ---- Subsystems as bond-graph fragments. Every fragment is a new graph
 * owned by the caller (or handed to fb_vehicle_assemble). */

/* A hull: a graph with the ports
 *   "attach" (IN, dimension fb_scenario_nattach): vertical force and
 *            velocity at the attachment points, the corners' then the
 *            mounted bodies';
 *   "load"   (IN, dimension nload): the load points;
 * and the probe that measures its torsion angle (a weighted sum over a
 * vector signal, names relative to the hull fragment). */
typedef struct fb_hull {
  fb_bg *graph;
  char *torsion_target; /* bond or element inside the fragment */
  fb_probe_kind torsion_kind;
  int torsion_integrate;
  double *torsion_weights;     /* each edge's roll from its two end nodes */
  double *torsion_fit_weights; /* from its transverse section, least squares */
  size_t ntorsion;
  /* The probes of the scenario's outputs read from the hull's motion (a
   * point's translation, a rigid-body motion; docs/vehicle-outputs.md):
   * reading[o] for output o, its target NULL for the other outputs;
   * targets and weights owned, names relative to the fragment. */
  struct fb_hull_reading *reading;
  size_t nreading;
  /* 1: it offers the port "bushing_<k>" (IN, dimension 6) for each
   * bushing k of a mounted rigid body on the hull (fb_scenario_bushing_at),
   * as System 1's does; 0: it carries no such bodies. */
  int carries_bodies;
} fb_hull;
/* One output's probe on the hull's coordinates q: a weighted sum over a
 * signal of q (their displacements, velocities or the efforts on their
 * inertia), integrated or not. */
typedef struct fb_hull_reading {
  char *target;
  fb_probe_kind kind;
  int integrate;
  double *weights;
  size_t nweights;
} fb_hull_reading;
void fb_hull_free(fb_hull **h);

/* System 1: I field diag-dominant 3x3 (bounce, roll, pitch; with the
 * declared hull masses and the lumped payload's point masses when asked)
 * and matrix transformers to the attachment and load points. A hull
 * carrying mounted rigid bodies (s->nbodies > 0) moves in six degrees of
 * freedom, (x, y, z, roll, pitch, yaw) at its centre of mass, with its
 * whole inertia tensor; its point maps are then rows of the 6-DOF map,
 * and each bushing on it has its port "bushing_<k>" (fb_hull). */
int fb_vehicle_rigid_hull(const fb_scenario *s, fb_hull **out, fb_err *err);
/* The motions of System 1's vehicle that nothing holds: with six rigid
 * coordinates (s->nbodies > 0), the whole vehicle's surge, sway and yaw,
 * 3 (the suspensions and tires are vertical); none otherwise. Each is a
 * zero eigenvalue of its linearised model (fb_vehicle_modes counts them
 * in nstatic, with those of the support's self-stress). */
size_t fb_vehicle_free_motions(const fb_scenario *s);
/* A mounted body (driver plus seat, engine, ...): port "hull" (OUT). */
int fb_vehicle_mount(const fb_mount *m, double gravity, fb_bg **out, fb_err *err);
/* Mounted rigid body i of s in six degrees of freedom: the I field
 * "inertia" (6x6 at its centre of mass), its weight, and per bushing j
 * the 6x6 spring "spring_<j>" and damper "damper_<j>" with the port
 * "parent_<j>" (OUT, dimension 6) to its parent's point; and for each
 * bushing k (fb_scenario_bushing_at) of a body mounted on it the port
 * "bushing_<k>" (IN, dimension 6). Small-motion kinematics. */
int fb_vehicle_body(const fb_scenario *s, size_t i, fb_bg **out, fb_err *err);
/* One suspension with its wheel and tire: ports "hull" (OUT), "road" (IN). */
int fb_vehicle_corner(const fb_corner_params *c, double gravity, fb_bg **out, fb_err *err);
/* The same with a port "travel" (OUT) at the wheel's velocity relative to
 * the hull, where a force in parallel with the suspension's joins it (an
 * anti-roll bar's "left" or "right"). */
int fb_vehicle_corner_coupled(const fb_corner_params *c, double gravity, fb_bg **out,
                              fb_err *err);
/* A walking-beam bogie (fb_bogie_params) on the wheels and tires of front
 * and rear (their wheel_mass and tire; their springs, dampers and motion
 * ratio are not the bogie's): ports "hull" (OUT: the pivot's spring and
 * damper to a hull point), "road_front" and "road_rear" (IN: each tire's
 * road). What it offers to measure, as bonds: the flow of "b_up" is the
 * pivot's vertical velocity, that of "b_pitch" the beam's pitch rate
 * (nose down positive, as the hull's pitch; integrated: bounce and pitch), the efforts of
 * "front.b_tire" and "rear.b_tire" the wheels' loads on the road
 * (compression positive), that of "b_spring" the pivot's spring force. */
int fb_vehicle_bogie(const fb_bogie_params *p, const fb_corner_params *front,
                     const fb_corner_params *rear, double gravity, fb_bg **out, fb_err *err);
/* An anti-roll bar (fb_antiroll_bar's law): ports "left" and "right"
 * (IN), each to a corner's "travel". */
int fb_vehicle_antiroll_bar(const fb_antiroll_bar *b, fb_bg **out, fb_err *err);
/* The road: one flow source per wheel (the road's vertical velocity under
 * that wheel: the bump, an ISO 8608 random road or a profile, src/road),
 * "v_<CORNER>", one port per corner named as it (OUT). */
int fb_vehicle_road(const fb_scenario *s, fb_bg **out, fb_err *err);
/* The load: one effort source of dimension nload, port "load" (OUT). */
int fb_vehicle_load(const fb_scenario *s, fb_bg **out, fb_err *err);

/* Connects a hull (taken over, *hull set to NULL) with the mounted
 * bodies', corners', road and load fragments built from s, through their
 * ports only. Instance names: "hull", each mount's name, "susp_<CORNER>",
 * "road", "load"; the composite "attach" stacks one scalar bond per
 * attachment point into the hull's multibond (the paper's horizontal
 * line). The hull is the only part that differs between System 1 and
 * System 2. *probes (new) measure s's outputs; an error about one has
 * the key "outputs[K]". */
int fb_vehicle_assemble(const fb_scenario *s, fb_hull **hull, fb_bg **out,
                        fb_probe_spec **probes, size_t *nprobes, fb_err *err);
/* Frees what fb_vehicle_assemble returned in *probes. */
void fb_vehicle_probes_free(fb_probe_spec **probes, size_t nprobes);

/* ---- Outputs (docs/vehicle-outputs.md). A signal kind: what it measures, of
 * which subsystem class, its unit and default name, title and label. One
 * table (src/vehicle/outputs.c); a new kind is one entry there and a row of
 * docs/vehicle-outputs.md. */
typedef enum fb_output_subject {
  FB_OUTPUT_OF_CORNER,     /* `of` names a corner */
  FB_OUTPUT_OF_MOUNT,      /* `of` names a mounted body */
  FB_OUTPUT_OF_HULL,       /* no `of`: the hull */
  FB_OUTPUT_OF_BOND,       /* `bond` names a bond of the assembled graph */
  FB_OUTPUT_OF_HULL_POINT, /* `at` a point of the hull, `direction` an axis */
  FB_OUTPUT_OF_BOGIE,      /* `of` names a walking-beam bogie */
  FB_OUTPUT_OF_BODY,       /* `of` names a mounted rigid body (fb_body) */
  FB_OUTPUT_OF_HULL_STRESS /* `element` or `at` a shell element of System 2's hull,
                              `surface` and `stress` its stress component */
} fb_output_subject;

struct fb_output_kind {
  const char *signal; /* "tire_force" */
  fb_output_subject subject;
  const char *unit;  /* NULL for bond signals: from the bond's domain */
  const char *name;  /* default column name, "%s" the subject's name */
  const char *title; /* default figure title, "%s" the subject's name */
  const char *label; /* default short label, "%s" the subject's name */
  const char *doc;   /* one line for docs/vehicle-outputs.md */
};

/* The kinds, n of them in *n. */
const fb_output_kind *fb_vehicle_output_kinds(size_t *n);
/* The kind called signal, NULL if none. */
const fb_output_kind *fb_vehicle_output_kind_find(const char *signal);
/* The first of s's outputs that System 1 cannot give (a stress of System
 * 2's shells), or fb_scenario_noutputs(s) if it can give them all. */
size_t fb_vehicle_outputs_system2_only(const fb_scenario *s);

/* ---- The road as the input of a frequency response
 * (src/vehicle/road_response.c). */

/* Which input of ds (fb_bd_descriptor of a vehicle fb_vehicle_build made)
 * is each corner's road velocity ("road.v_<CORNER>"): rate_input[c] for
 * the scenario's corners. FB_EMODEL if ds has other inputs. */
int fb_vehicle_rate_inputs(const fb_scenario *s, const fb_descriptor *ds, size_t *rate_input,
                           fb_err *err);
/* The time (s) after the leading wheel (the largest x) at which corner's
 * wheel meets a point of its track on a straight run at s->speed. */
double fb_vehicle_wheel_delay(const fb_scenario *s, size_t corner);
/* The inputs of ds for two cases, a road height e^{j omega t} (1 m) on
 * the left track (case 0) and on the right (case 1), reaching the wheels
 * of the track (fb_scenario_track_width's rule) with their delays: into u,
 * ds->ninputs (= ncorners) complex values per case, interleaved, as
 * fb_descriptor_freq_response takes them. */
void fb_vehicle_track_inputs(const fb_scenario *s, const size_t *rate_input, double omega,
                             double *u);

/* ---- The frequency response (src/vehicle/freq_response.c). */

/* The vehicle of s for system sys as a descriptor system (*out new, free
 * with fb_descriptor_free): fb_vehicle_build's diagram, its tires all in
 * contact (a unilateral tire's linear branch, its mode at rest), through
 * fb_bd_descriptor or, with a nonlinear law (a damper table), through
 * fb_bd_descriptor_at its static equilibrium under gravity
 * (fb_sim_static_state from the initial state; (*out)->linearised 1). */
int fb_vehicle_descriptor(const fb_scenario *s, fb_system sys, fb_descriptor **out,
                          fb_err *err);
/* The same of the realised vehicle v (a diagram of its own with the
 * outputs' probes alone, from the hull v holds). */
int fb_vehicle_linearise(fb_vehicle *v, fb_descriptor **out, fb_err *err);
/* The descriptor form of a vehicle's block diagram bd (fb_vehicle_build):
 * exact when every block is linear (fb_bd_descriptor), else linearised at
 * its static equilibrium under gravity reached from its initial state
 * (fb_bd_descriptor_at; (*out)->linearised 1). The one rule of every
 * front end's export: flexbond export, Python's Scenario.export. */
int fb_vehicle_diagram_descriptor(fb_bd *bd, fb_descriptor **out, fb_err *err);
/* The response of ds (fb_vehicle_descriptor of s) to a road height of 1 m
 * at the leading wheel of the left track (case 0) and of the right (case
 * 1), fb_vehicle_track_inputs, at nfreq frequencies freq_hz (Hz, >= 0):
 * into h, 2 FB_ROAD_NTRACKS ds->nrows_c nfreq values laid out as
 * fb_descriptor_freq_response's. */
int fb_vehicle_freq_response(const fb_scenario *s, const fb_descriptor *ds,
                             const double *freq_hz, size_t nfreq, double *h, fb_err *err);

/* ---- A realised vehicle (src/vehicle/vehicle.c). */

/* One system of a scenario realised once (fb_vehicle): its hull (System 2: the mesh,
 * the finite-element K and M, one eigen-solve, the modal basis), the
 * assembled bond graph, its block diagram and its probes. Simulations,
 * the linearised vehicle's modes, System 2's modes with their shapes, the
 * descriptor form, the motion of an animation and the report's pictures
 * all take it, and none of them rebuilds what it holds (libCEED's
 * operators, set up once and applied many times); fb_vehicle_work counts
 * what it computed. It borrows its scenario, which must outlive it and
 * not change meanwhile. */

/* The bytes a vehicle's factorisations and eigen-solves may take unless
 * fb_vehicle_opts says otherwise: 4 GiB. */
#define FB_VEHICLE_MEMORY_LIMIT ((size_t)4 << 30)

/* What fb_vehicle_opts.motion records. */
enum {
  FB_VEHICLE_MOTION_NONE = 0,
  /* The whole motion (an animation): the hull's coordinates, and the
   * attachment points', bodies' and wheels' displacements, integrated
   * velocities that add states to the solver (its error control sees
   * them: the outputs move within its tolerance). */
  FB_VEHICLE_MOTION_ALL = 1,
  /* The hull's coordinates alone (its stresses, flexbond/hull_stress.h):
   * read from states, they add none, and the run's results are those of
   * a run without motion; the motion's nattach, nmounts and ncorners are
   * 0. */
  FB_VEHICLE_MOTION_HULL = 2
};
typedef struct fb_vehicle_opts {
  /* FB_VEHICLE_MOTION_*: probe the vehicle's motion too (fb_vehicle_run's
   * motion). */
  int motion;
  /* Bytes for the hull's factorisation, eigen-solve and basis (checked
   * before each is allocated: FB_ENOMEM naming what it needs); 0:
   * FB_VEHICLE_MEMORY_LIMIT. */
  size_t memory_limit;
  /* Hears of every set-up stage that can take time (the hull's assembly,
   * factorisation, eigen-solve and basis) and may stop it (FB_EINTR). */
  fb_progress progress;
  /* Threads the hull's eigen-solve may use (fb_eig_opts.threads): 1 (the
   * default: a program running vehicles on threads of its own) or 2. */
  int threads;
  /* Free-free modes of the hull to solve at least, for a listing
   * (fb_hull_basis.free_hz); 0: those its model needs. */
  size_t hull_modes;
  /* Steppers only (fb_vehicle_stepper_new): the road under each wheel is
   * an input, road_z_<CORNER> and road_zdot_<CORNER>, in place of the
   * scenario's road; 0 (the default): the scenario's road. */
  int road_inputs;
} fb_vehicle_opts;
/* No motion, the default memory limit, no progress, one thread, no more
 * hull modes than needed, the scenario's road. */
void fb_vehicle_opts_default(fb_vehicle_opts *o);

/* Realises system sys of s (o NULL: the defaults): checks the scenario
 * (fb_scenario_check), builds the hull (System 2: fb_vehicle_fe_hull, K
 * and M, the eigen-solve and basis of hull.fe.coordinates and
 * hull.fe.modes), assembles the vehicle and builds its block diagram with
 * the outputs' probes and every tire's contact force. Errors about a
 * value of the description name its part (fb_err.part), which the caller
 * locates (fb_scenario_locate). */
int fb_vehicle_new(const fb_scenario *s, fb_system sys, const fb_vehicle_opts *o,
                   fb_vehicle **out, fb_err *err);
void fb_vehicle_free(fb_vehicle **v);
fb_system fb_vehicle_system(const fb_vehicle *v);
const fb_scenario *fb_vehicle_scenario(const fb_vehicle *v);

/* What a vehicle has computed since fb_vehicle_new, counted where the
 * work is done. */
typedef struct fb_vehicle_work {
  size_t mesh_generations;    /* hull meshes generated (0: copied from the loaded scenario's) */
  size_t assemblies;          /* finite-element assemblies of the hull's K and M */
  size_t factorisations;      /* sparse Cholesky factorisations */
  size_t hull_eigensolves;    /* eigen-solves of the free-free hull */
  size_t vehicle_eigensolves; /* of the undamped System 2 (fb_vehicle_structural_modes) */
  size_t linear_eigensolves;  /* of the linearised vehicle (fb_vehicle_linear_modes) */
  size_t diagrams;            /* block diagrams built */
  size_t static_solves;       /* static equilibria */
  size_t simulations;         /* time integrations */
  double setup_seconds;       /* fb_vehicle_new's wall time */
  double static_seconds;      /* the static equilibria's */
} fb_vehicle_work;
fb_vehicle_work fb_vehicle_work_of(const fb_vehicle *v);

/* How System 2's hull is represented in its model. */
typedef struct fb_hull_basis {
  fb_hull_coordinates coordinates;
  fb_hull_modes_kind kind;   /* modal: how the free-free modes were chosen */
  size_t ndof;               /* the hull's nodal DOFs */
  size_t ncoords;            /* its coordinates in the model: ndof (nodal, or every mode),
                                or nmodes + nstatic */
  size_t nmodes, nrigid;     /* free-free modes kept, the rigid-body ones among them (AUTO:
                                the rigid-body ones alone) */
  size_t nstatic;            /* vectors beside the modes: the residual flexibility of the
                                patterns (COUNT), or every load-dependent Ritz vector (AUTO) */
  size_t npatterns;          /* the patterns they start from: each attachment point's force,
                                the load, and each output read from the hull's deformation */
  size_t nblocks;            /* AUTO: blocks of load-dependent Ritz vectors, the first the
                                residual flexibility; 1 otherwise */
  double cutoff_hz;          /* AUTO: the band (0, cutoff_hz] over which the basis
                                converges (the excitation's, or hull.fe.cutoff_hz); NAN
                                otherwise */
  double excitation_hz;      /* AUTO by the rule: the highest frequency reaching the hull
                                (fb_hull_excitation_hz); NAN otherwise */
  double block_change;       /* AUTO: the receptances' largest change from the basis to the
                                next block, over the band (below FB_HULL_BLOCK_TOL) */
  double f1_hz, beta;        /* the hull as built: its first elastic free-free mode, and
                                B = beta K (fb_fe_hull_damping's rule) */
  size_t nfree, nfree_rigid; /* the free-free modes solved (those kept, beta's, a listing's) */
  const double *free_hz;     /* their frequencies, Hz (the vehicle's) */
  fb_eig_info eig;           /* the hull's eigen-solve */
  size_t nestimate;          /* the error estimator's coordinates (fb_vehicle_basis_error) */
} fb_hull_basis;
/* System 2's (NULL for System 1). */
const fb_hull_basis *fb_vehicle_hull_basis(const fb_vehicle *v);
/* The free-free modes System 2's hull solved (fb_hull_basis.free_hz, at
 * least fb_vehicle_opts.hull_modes of them), for a program that cannot
 * read fb_hull_basis (a language binding): their number (0 for System 1),
 * their frequencies (Hz, ascending; owned by v) in *freq_hz and the
 * rigid-body ones among them, first, in *nrigid. */
size_t fb_vehicle_hull_free_modes(const fb_vehicle *v, const double **freq_hz, size_t *nrigid);

/* hull.fe.modes: auto. The basis is the hull's rigid-body modes and
 * blocks of load-dependent Ritz vectors (E. L. Wilson, M.-W. Yuan & J. M.
 * Dickens, "Dynamic analysis by direct superposition of Ritz vectors",
 * Earthq. Eng. Struct. Dyn. 10, 1982) started from the patterns the
 * vehicle loads the hull with or reads from it: the first block their
 * static response with inertia relief (the residual flexibility), each
 * next K^+ M applied to the block before. Blocks are added until one more
 * changes the hull's receptance between every two patterns by less than
 * FB_HULL_BLOCK_TOL of its scale (sqrt(|H_aa| |H_bb|), their peaks over
 * the band) at every frequency of the band (0, f], with the structural
 * damping; the basis is the one before that block, which the error
 * estimator adds (fb_vehicle_new_estimator). f is hull.fe.cutoff_hz or
 * fb_hull_excitation_hz, the highest frequency that reaches the hull:
 * each wheel's hop on a fixed hull, sqrt((r^2 spring_k + tire_k) /
 * wheel_mass) / 2 pi (a bogie's wheels: the higher of its beam's bounce
 * and pitch with them), each mounted body's natural frequency,
 * sqrt(stiffness / mass) / 2 pi, each rigid body's highest on its
 * bushings with its parent held, and the road's highest at the
 * scenario's speed (a bump: 2 V / length, the (1 - cos) pulse's spectrum
 * is down 98 % there; an ISO 8608 road: V n_max; a profile: V / (2
 * spacing), its Nyquist frequency). The tolerance keeps every output of
 * the examples within about 1e-3 of its range of the every-mode model,
 * whose run's own error the estimate then reports (docs/hull-mesh.md, "The
 * modal basis": bench/basis_choice.sh chose this method by measurement
 * against modes with static correction and Craig-Bampton;
 * tests/test_hull_basis.c checks the error and the estimate). */
#define FB_HULL_BLOCK_TOL 1e-3
double fb_hull_excitation_hz(const fb_scenario *s);

/* The realised bond graph and the probes of its diagram (the outputs, then
 * every tire's contact force, then with motion the motion's), owned by the
 * vehicle. The graph's causality is assigned: a caller may build other
 * diagrams of it (fb_bd_build, a picture) while v lives. */
fb_bg *fb_vehicle_bond_graph(fb_vehicle *v);
const fb_probe_spec *fb_vehicle_probe_specs(const fb_vehicle *v, size_t *nprobes);
/* System 2's hull (its mesh, couplings and nodes), NULL for System 1. */
const fb_fe_hull *fb_vehicle_fe_hull_of(const fb_vehicle *v);

/* How a run's vehicle moves, for an animation (flexbond run --animate,
 * docs/animation.md): sampled as its outputs are, every displacement
 * vertical but the finite-element hull's, up positive, in m (rad for
 * System 1's roll and pitch), from the vehicle's state at t = 0. */
typedef struct fb_vehicle_motion {
  fb_system sys;
  fb_mesh *mesh;  /* System 2: the finite-element hull's mesh (owned); System 1: NULL */
  size_t ncoords; /* the hull's coordinates: System 1's (z, phi, theta), System 2's q */
  double *basis;  /* System 2 in modal coordinates: u = basis q over the mesh's
                     6 nnodes DOFs (column-major, owned); NULL otherwise */
  size_t nattach, nmounts, ncorners;
  size_t nsamples, width; /* width = 1 + ncoords + nattach + nmounts + ncorners */
  /* nsamples rows of width: t (s), the hull's coordinates, the attachment
   * points' displacements ("attach" order: corners then mounts), the
   * mounted bodies', the wheels'. Owned. */
  double *samples;
  /* The hull's coordinates at t = 0 (ncoords, owned), which the samples'
   * are relative to: with simulation.initial: static its deflection
   * under the vehicle's weight (for the total stresses,
   * flexbond/hull_stress.h). */
  double *hull_q0;
} fb_vehicle_motion;
void fb_vehicle_motion_free(fb_vehicle_motion **m);

/* The vehicle at time t, linear between samples (clamped to the run):
 * each array may be NULL. node_u: six values per node of mesh (the
 * translation, then the rotation), the mesh being m->mesh in System 2;
 * in System 1 any mesh in the vehicle frame, whose node (x, y) rises by
 * z + y phi - x theta and turns by (phi, theta, 0): the rigid hull's
 * motion is vertical only. attach_dz (nattach), body_dz (nmounts),
 * wheel_dz (ncorners). FB_EINVAL if System 2's mesh is not m->mesh. */
int fb_vehicle_motion_at(const fb_vehicle_motion *m, const fb_mesh *mesh, double t,
                         double *node_u, double *attach_dz, double *body_dz, double *wheel_dz,
                         fb_err *err);
/* The hull's coordinates at time t (as fb_vehicle_motion_at: linear
 * between samples, clamped), total: hull_q0 plus the sample's, into q
 * (ncoords). FB_EINVAL for a run of no samples. */
int fb_vehicle_motion_coords_at(const fb_vehicle_motion *m, double t, double *q, fb_err *err);

/* Integrates the vehicle per its scenario: initial state (zero or static
 * equilibrium), breakpoints at every wheel's bump entry and exit,
 * tolerances, sampling. The result's columns are t, the scenario's outputs
 * (s->output, in order), then every tire's normal reaction
 * contact_force_<CORNER> in corner order (N, compression positive). With
 * motion not NULL (a vehicle made with fb_vehicle_opts.motion: FB_EINVAL
 * otherwise) *motion gets the run's motion (new), keeping the samples
 * that cover window = {t0, t1} (s: the last at or before t0 to the first
 * at or after t1; every sample if window is NULL), so an animation of a
 * stretch does not hold every hull coordinate of the whole run; the
 * result's columns are the same. fn hears of every step (NULL: none) and
 * may stop the run (FB_EINTR). May be called again. */
int fb_vehicle_run(fb_vehicle *v, const double *window, fb_sim_progress_fn fn, void *ctx,
                   fb_result **out, fb_vehicle_motion **motion, fb_err *err);

/* The estimator of the error of v's modal basis (System 2 in reduced modal
 * coordinates: FB_EINVAL otherwise): a vehicle on v's realised hull (no
 * second assembly or eigen-solve), its basis enriched by the next block
 * of load-dependent Ritz vectors (fb_fem_modal_basis's order 2: what
 * truncation misses to the next order in frequency), with the same
 * probes as v's runs. Run both; fb_result_rel_diff of their results is
 * the estimate. The two can run on two threads at once (they share only
 * what v's realisation made). *out borrows v, which must outlive it. */
int fb_vehicle_new_estimator(fb_vehicle *v, fb_vehicle **out, fb_err *err);
/* 1 when v's basis has an estimator: System 2 in reduced modal
 * coordinates (fewer than its nodal DOFs). */
int fb_vehicle_basis_reduced(const fb_vehicle *v);

/* The error of System 2's modal basis in a run r of v (fb_vehicle_run;
 * reduced modal coordinates only: FB_EINVAL otherwise): the same run of
 * its estimator (fb_vehicle_new_estimator), and for each output o the
 * largest |difference| from window[0] to the end of the run over o's
 * range there (its max - min), into est[o] (s->noutputs of them; 0 for a
 * constant output). fn as for fb_vehicle_run. */
int fb_vehicle_basis_error(fb_vehicle *v, const fb_result *r, const double window[2],
                           fb_sim_progress_fn fn, void *ctx, double *est, fb_err *err);

/* ---- Stepping a vehicle (src/vehicle/stepper.c): a simulation advanced
 * by the caller, read between advances and changed on the way, as an
 * FMI co-simulation slave is with fmi2DoStep (or a Chrono system with
 * DoStepDynamics): a controller, a driver model or an optimiser in the
 * loop. It integrates as fb_vehicle_run does (the same diagram, initial
 * state, tolerances and road), cut at the caller's times
 * (fb_sim_stepper: the outputs agree with a run's within its
 * tolerances).
 *
 * Two kinds of change, each applied at the current time, the
 * integration restarting there from the current state:
 *  - an input (fb_vehicle_input_name), held at its value until changed
 *    (zero-order hold, FMI's "input at the communication point");
 *  - the scenario (fb_vehicle_stepper_set_scenario): any of its values,
 *    a spring's stiffness, a damper's table, the road; the vehicle is
 *    realised again (System 2: the hull's eigen-solve again) and goes on
 *    from the current state, which must mean the same in the new vehicle
 *    (the same states by name: no corner, mount or hull coordinate added
 *    or removed). The road is a function of time: a new speed or bump
 *    moves the road under the wheels from the current time on, as if it
 *    had always been so. */

/* The inputs every stepper has: "load_force", a vertical force on the
 * load (N, up positive), shared by the load points as the payload's
 * weight is (0 at first: the vehicle as its scenario says). */
#define FB_VEHICLE_NINPUTS 1
/* Input i's name (NULL for i >= FB_VEHICLE_NINPUTS); the index of the
 * input named name, -1 if none. */
const char *fb_vehicle_input_name(size_t i);
long fb_vehicle_input_find(const char *name);
/* With fb_vehicle_opts.road_inputs, a stepper has besides, for each
 * corner C in the scenario's order, the road under its wheel:
 *  - road_z_C (m, up positive): the road's height, 0 at first, where the
 *    scenario's start leaves the wheel;
 *  - road_zdot_C (m/s): its rate, which the tire's spring and damper
 *    read (the scenario's road gives the same, fb_road_wheel_velocity).
 * Between two changes the road rises at the rate held: its height is
 * road_z + road_zdot (t - t_set). A height set to another value than
 * that moves the road under the tire at once: the tire's deflection
 * (its displacement states, fb_vehicle_stepper_road_coupling) jumps by
 * the difference, as a wheel meeting a step does. An enveloped tire's
 * filtering is the caller's: the inputs are the road the tire follows. */

typedef struct fb_vehicle_stepper fb_vehicle_stepper;

/* Realises system sys of s (o NULL: the defaults; o->motion is ignored)
 * and puts it at t = 0 in its initial state (s->initial: zero or the
 * static equilibrium), every input 0. The stepper keeps a copy of s (s
 * may be freed afterwards). *out is new (fb_vehicle_stepper_free).
 * Errors as fb_vehicle_new's and fb_vehicle_run's. */
int fb_vehicle_stepper_new(const fb_scenario *s, fb_system sys, const fb_vehicle_opts *o,
                           fb_vehicle_stepper **out, fb_err *err);
void fb_vehicle_stepper_free(fb_vehicle_stepper **st);
/* Integrates to t (s), t from the current time to the scenario's t_end
 * (FB_EINVAL otherwise, err->key "t"): fb_sim_stepper_advance. */
int fb_vehicle_stepper_advance(fb_vehicle_stepper *st, double t, fb_err *err);
/* The time reached, s. */
double fb_vehicle_stepper_time(const fb_vehicle_stepper *st);
/* The outputs: the scenario's (s->output, in order), then every tire's
 * normal reaction contact_force_<CORNER> (N), as fb_vehicle_run's
 * columns after t. Names and units owned by st, valid until the next
 * fb_vehicle_stepper_set_scenario; find: the index of the output named
 * name, -1 if none. */
size_t fb_vehicle_stepper_noutputs(const fb_vehicle_stepper *st);
const char *fb_vehicle_stepper_output_name(const fb_vehicle_stepper *st, size_t k);
const char *fb_vehicle_stepper_output_unit(const fb_vehicle_stepper *st, size_t k);
long fb_vehicle_stepper_output_find(const fb_vehicle_stepper *st, const char *name);
/* The outputs at the current time into y (noutputs values, SI units). */
int fb_vehicle_stepper_outputs(fb_vehicle_stepper *st, double *y, fb_err *err);
/* Holds input name at value from the current time on. FB_EINVAL
 * (err->key the name) for an unknown input or a value that is not
 * finite. */
int fb_vehicle_stepper_set_input(fb_vehicle_stepper *st, const char *name, double value,
                                 fb_err *err);
/* The value input i holds (NAN for i >= fb_vehicle_stepper_ninputs). */
double fb_vehicle_stepper_input(const fb_vehicle_stepper *st, size_t i);
/* The stepper's inputs (FB_VEHICLE_NINPUTS, then the road's, above):
 * their count, names and units (owned by st, NULL past the count), and
 * the index of the input named name (-1 if none). */
size_t fb_vehicle_stepper_ninputs(const fb_vehicle_stepper *st);
const char *fb_vehicle_stepper_input_name(const fb_vehicle_stepper *st, size_t i);
const char *fb_vehicle_stepper_input_unit(const fb_vehicle_stepper *st, size_t i);
long fb_vehicle_stepper_input_find(const fb_vehicle_stepper *st, const char *name);
/* Holds every input at u[i] (fb_vehicle_stepper_ninputs values) from the
 * current time on, as fb_vehicle_stepper_set_input does one by one, with
 * one restart of the integrator, none if nothing changed. FB_EINVAL
 * (err->key the input's name) for a value that is not finite, the
 * stepper unchanged. */
int fb_vehicle_stepper_set_inputs(fb_vehicle_stepper *st, const double *u, fb_err *err);

/* ---- The stepper's model, for a caller that integrates it (an FMI
 * model exchange FMU): the stepper's diagram evaluated at the caller's
 * time and state. */

/* The diagram (owned by st, valid until fb_vehicle_stepper_set_scenario
 * or free): fb_bd_rhs, fb_bd_outputs, fb_bd_guards, fb_bd_sync_modes and
 * fb_bd_switch_modes at any (t, x). It reads the inputs held. Its modes
 * are shared with the stepper's own integration: a caller uses one or the
 * other, not both. */
fb_bd *fb_vehicle_stepper_diagram(fb_vehicle_stepper *st);
/* Holds u (fb_vehicle_stepper_ninputs values) as the inputs' values with
 * no restart and no jump of the state (the road's heights as at the
 * current time): the caller owns the state. */
void fb_vehicle_stepper_hold_inputs(fb_vehicle_stepper *st, const double *u);
/* With road inputs: B, the displacement states' rates per unit road rate
 * at each wheel, column-major, fb_vehicle_stepper_nstates rows by the
 * scenario's corners (owned by st, valid as the diagram is): a tire's
 * deflection state q moves with its road as q = p + B z, p the part
 * the wheel's own motion gives. NULL without road inputs. */
const double *fb_vehicle_stepper_road_coupling(const fb_vehicle_stepper *st);

/* The state at the current time (fb_vehicle_stepper_nstates values in
 * fb_bd_state_name order, owned by st, valid until the next advance,
 * change or free). */
size_t fb_vehicle_stepper_nstates(const fb_vehicle_stepper *st);
const double *fb_vehicle_stepper_state(const fb_vehicle_stepper *st);
/* Puts the stepper at time t (s, from 0 to the scenario's t_end, before
 * the current time too: a saved state restored) in state x (copied),
 * the inputs held as they are, the road's heights where the road is at
 * the current time taken as at t: fb_sim_stepper_set_state. Two steppers of one scenario set to
 * the same (t, x, inputs) go on identically. */
int fb_vehicle_stepper_set_state(fb_vehicle_stepper *st, double t, const double *x,
                                 fb_err *err);
/* Goes on with scenario s (copied; the same system) from the current
 * time and state, the inputs held as they are. FB_EINVAL naming the
 * first state that differs if s's vehicle has other states, or if its
 * t_end is not after the current time (err->key "t_end"); errors of
 * fb_vehicle_new about s. On failure the stepper is unchanged. */
int fb_vehicle_stepper_set_scenario(fb_vehicle_stepper *st, const fb_scenario *s, fb_err *err);
/* The scenario the stepper simulates now (its copy, owned by st). */
const fb_scenario *fb_vehicle_stepper_scenario(const fb_vehicle_stepper *st);

/* Convenience for a single use, each realising the vehicle, using it and
 * freeing it: */

/* Assembles the vehicle for system sys and builds its block diagram with
 * the scenario's output probes. *graph and *bd are new (free bd first: it
 * borrows the graph). */
int fb_vehicle_build(const fb_scenario *s, fb_system sys, fb_bg **graph, fb_bd **bd,
                     fb_err *err);

/* The assembled vehicle for system sys (*graph new) and every probe a
 * simulation records (*probes new, free with fb_vehicle_probes_free): the
 * outputs, then every tire's normal reaction contact_force_<CORNER>. */
int fb_vehicle_graph(const fb_scenario *s, fb_system sys, fb_bg **graph, fb_probe_spec **probes,
                     size_t *nprobes, fb_err *err);
/* The scenario's solver settings (t_end, tolerances, step limits,
 * sampling; no initial state: see s->initial). */
void fb_vehicle_sim_opts(const fb_scenario *s, fb_sim_opts *o);

/* fb_vehicle_run of system sys of s. */
int fb_vehicle_simulate(const fb_scenario *s, fb_system sys, fb_result **out, fb_err *err);
/* As fb_vehicle_simulate, reporting progress through fn (NULL for none;
 * see fb_sim_progress_fn). */
int fb_vehicle_simulate_progress(const fb_scenario *s, fb_system sys, fb_sim_progress_fn fn,
                                 void *ctx, fb_result **out, fb_err *err);

/* A time interval in which a tire carries no load: its normal reaction
 * is not compressive. With the paper's linear (bilateral) tire that means
 * tensile: the tire pulls the wheel down, where a real tire would leave
 * the road. With unilateral contact (wheel.tire_contact) the reaction is
 * exactly zero instead: the wheel is off the road, or leaving it. */
typedef struct fb_contact_loss {
  int corner; /* index into the scenario's corners */
  /* s: a tensile reaction's zero crossings, linearly interpolated between
   * samples; a unilateral tire's first and last samples of zero reaction
   * (to one sample, since the reaction falls to exactly zero); or the
   * run's ends. */
  double t_start, t_end;
  double min_force, t_min; /* the smallest reaction (N, <= 0) and its time */
} fb_contact_loss;

/* Every interval of positive length where a reaction is <= 0 in a result
 * of fb_vehicle_simulate of s (its contact_force_<CORNER> columns), by corner, then
 * by time. *out is new (NULL when there is none). FB_EINVAL if the result
 * lacks a column. */
int fb_vehicle_contact_loss(const fb_scenario *s, const fb_result *r, fb_contact_loss **out,
                            size_t *n, fb_err *err);

/* A mode of the linearised vehicle. */
typedef struct fb_mode {
  double re, im;        /* eigenvalue, 1/s and rad/s (im >= 0) */
  double freq_hz;       /* |lambda| / 2 pi (undamped: im / 2 pi) */
  double damping_ratio; /* -re / |lambda| */
  char description[96]; /* from the largest kinetic-energy share, e.g.
                           "hull bounce (62%)", "wheel hop LF (91%)" */
} fb_mode;

/* Modes of the vehicle v linearised at its static equilibrium, from the
 * block diagram's exact Jacobian: with undamped set, every damper and
 * tire damper is removed first (natural frequencies; a diagram of its own,
 * from the same realised hull). Oscillatory modes
 * come first by frequency; non-oscillatory ones (real eigenvalues) after;
 * zero eigenvalues of statically indeterminate support (the hull on more
 * than three springs) are counted in *nstatic and left out. *modes is new. */
int fb_vehicle_linear_modes(fb_vehicle *v, int undamped, fb_mode **modes, size_t *nmodes,
                            size_t *nstatic, fb_err *err);
/* fb_vehicle_linear_modes of system sys of s, realised for the purpose. */
int fb_vehicle_modes(const fb_scenario *s, fb_system sys, int undamped, fb_mode **modes,
                     size_t *nmodes, size_t *nstatic, fb_err *err);

/* ---- System 2: the finite-element hull. */

/* How one attachment point meets the hull: its vertical velocity is
 * sum w[k] v[dof[k]] over the hull's nodal DOFs, and its force f goes to
 * them as w[k] f (power-conserving: no stiffness of its own). A point on a
 * node is that node's u_z with weight 1 (src/vehicle/coupling.c). */
typedef struct fb_hull_coupling {
  size_t n;
  size_t *dof; /* owned */
  double *w;   /* owned */
} fb_hull_coupling;

/* The coupling of node's u_z alone. */
int fb_hull_coupling_node(size_t node, fb_hull_coupling *c, fb_err *err);
/* The scenario's coupling (s->coupling, not NONE) of the point (x0, y0)
 * to the nodes of the mesh's node set `set` or, without one, to those of
 * the element set s->coupling_surface within s->coupling_radius in plan;
 * *node gets the one nearest the point. FB_EMODEL naming set when there
 * are none, or when a distributing coupling's nodes lie on a line that
 * misses the point by more than 1 mm. */
int fb_hull_coupling_build(const fb_scenario *s, const fb_mesh *m, const char *set, double x0,
                           double y0, fb_hull_coupling *c, size_t *node, fb_err *err);
void fb_hull_coupling_free(fb_hull_coupling *c);
/* A six-component distributing coupling (RBE3-like; src/vehicle/coupling.c)
 * of the reference point x0 (x, y, z, m) to the n nodes of m: rows[0..6)
 * (new; fb_hull_coupling_free each) give its motion (u_x, u_y, u_z,
 * theta_x, theta_y, theta_z) as the least-squares rigid fit of the
 * nodes' translations, and by their transpose its force and moment as
 * nodal forces. FB_EMODEL naming what when the nodes cannot carry a
 * moment in every direction (one node, or nodes on one line). */
int fb_hull_coupling6_build(const fb_mesh *m, const size_t *nodes, size_t n, const double *x0,
                            const char *what, fb_hull_coupling *rows, fb_err *err);

/* A hull mesh with its material, its declared masses and the nodes where
 * the rest of the vehicle meets it, from the mesh's node sets:
 * SUSP_<CORNER> per corner and the mounts' names in capitals (one node
 * each, in "attach" order), LOAD (nload nodes, in the scenario's
 * load-point order), MASS_<NAME> per hull mass (one node each),
 * FRONT_EDGE and REAR_EDGE (left end, then right end; the torsion
 * angle's edges). */
typedef struct fb_fe_hull {
  fb_mesh *mesh;
  fb_shell_props props;
  fb_mass_kind mass_kind;
  size_t *attach_node;               /* nattach, in "attach" order (fb_scenario_nattach): the
                                        node of each point, or its coupling's nearest */
  fb_hull_coupling *attach_coupling; /* nattach: how each point drives the hull */
  size_t nattach;
  size_t *load_node;               /* nload */
  fb_hull_coupling *load_coupling; /* nload: each load node's u_z */
  size_t nload;
  /* The bushings of mounted rigid bodies on the hull, in
   * fb_scenario_bushing_at's order (those on other bodies left out):
   * bushing_index[b] is its index k there, bushing_rows[6 b .. 6 b + 6)
   * its six-component distributing coupling (fb_hull_coupling6_build) to
   * its node set or the coupling surface's nodes around it. Owned. */
  size_t nbushings;
  size_t *bushing_index;
  fb_hull_coupling *bushing_rows;
  /* The node a bushing hangs on alone (a node set of one node: a rigid
   * lever to its six DOFs), or (size_t)-1 when its coupling spreads it
   * over several. Owned, nbushings. */
  size_t *bushing_single_node;
  size_t *point_mass_node; /* npoint_masses, in the scenario's order */
  double *point_mass;      /* their masses, kg */
  size_t npoint_masses;
  size_t edge_node[4]; /* front left, front right, rear left, rear right */
} fb_fe_hull;

/* The scenario's finite-element hull: its mesh (the one its source read
 * or makes, flexbond/hull_source.h), material and mass matrix kind.
 * FB_EINVAL if the scenario has no finite-element model (has_fe_hull).
 * Errors about a value of the description name its part (fb_err.part; the
 * caller locates it: fb_scenario_locate): a deck's are about hull_deck,
 * with the deck's "PATH:LINE: " (or "PATH: " for its node sets), a node
 * off its point about the point; the generator's as
 * fb_hull_mesh_generate's, or "hull mesh: " and no part when they concern
 * no value. */
int fb_vehicle_fe_hull(const fb_scenario *s, fb_fe_hull **out, fb_err *err);

/* Takes the mesh over (*mesh set to NULL), gives it the scenario's
 * sections (fb_mesh_set_section; a missing or repeated set is FB_EINVAL
 * about section i's set) and resolves its node sets against the scenario:
 * every set present with the right number of nodes, each node at the
 * scenario's (x, y) within 1 mm. FB_EMODEL naming the set or node
 * otherwise (a hull mass's missing set about that hull mass). */
int fb_fe_hull_new(const fb_scenario *s, fb_mesh **mesh, const fb_shell_props *props,
                   fb_mass_kind mass_kind, fb_fe_hull **out, fb_err *err);
void fb_fe_hull_free(fb_fe_hull **h);
/* The hull structure's point stiffness (N/m) along z at node: 1 / u_z
 * under a unit vertical force there, K u = f (the shells' stiffness
 * alone), with every DOF of the first ncorners attachment points' nodes
 * (the suspensions') held. FB_EINVAL for a suspension's node. */
int fb_fe_hull_point_stiffness(const fb_fe_hull *h, size_t ncorners, size_t node, double *k,
                               fb_err *err);

/* Modes of a whole undamped vehicle: natural frequencies and mode shapes
 * over ndof = 6 nnodes (hull) + nmounts + ncorners + 6 nbodies DOFs
 * (vertical motion of the mounted bodies, then of the wheels, in the
 * scenario's order, then each rigid body's six motions at its centre of
 * mass),
 * each shape normalised so that the largest displacement over the
 * mounted bodies and the hull nodes is 1 (the paper's normalisation). */
/* What holds the largest share of a mode's kinetic energy: a rigid motion
 * of the hull (index 0 .. 5: surge, sway, bounce, roll, pitch, yaw, about
 * its centre of mass), its elastic deformation (index 0), mounted body
 * index (a mount, index < s->nmounts, else rigid body index - nmounts),
 * corner index's wheel (its hop), or bogie index's beam with its
 * wheels. */
typedef enum fb_mode_part_kind {
  FB_MODE_HULL_RIGID,
  FB_MODE_HULL_ELASTIC,
  FB_MODE_MOUNT,
  FB_MODE_WHEEL,
  FB_MODE_BOGIE /* bogie index's beam, its bounce or its pitch */
} fb_mode_part_kind;
typedef struct fb_mode_part {
  fb_mode_part_kind kind;
  size_t index;
} fb_mode_part;
/* The rigid motions of the hull a mode picture is chosen for. */
enum { FB_MODE_BOUNCE = 2, FB_MODE_ROLL = 3, FB_MODE_PITCH = 4 };
typedef struct fb_mode_set {
  size_t nmodes, ndof;
  size_t nfree;            /* zero-frequency rigid-body modes left out */
  size_t nsolved;          /* modes the eigen-solve found (kept, free and spare) */
  double *freq_hz;         /* nmodes */
  double *shapes;          /* ndof x nmodes, column-major */
  char (*description)[96]; /* nmodes, e.g. "hull pitch (rigid 97%)" */
  fb_mode_part *part;      /* nmodes: what the description names */
  /* nmodes x nmounts, mode k's row first: mounted body b's share of mode
   * k's kinetic energy, in [0, 1]; the mounted bodies are the mounts
   * (b < s->nmounts), then the rigid bodies (s->body[b - s->nmounts]),
   * whose six motions count together. */
  size_t nmounts;
  double *mount_share;
} fb_mode_set;
void fb_mode_set_free(fb_mode_set **m);

/* The number of modes fb_mode_set_pictured chooses among the hull's
 * elastic ones: the first two (a torsion and a bending, as a rule). */
enum { FB_MODE_PICTURED_ELASTIC = 2 };
/* The modes of ms worth a picture, by what they are: the first mode of
 * each of the hull's supported rigid motions (bounce, roll, pitch), each
 * mounted body's mode (the first it holds the largest share of the
 * kinetic energy in, else the one that gives it its largest share), the
 * first wheel hop, and the first
 * FB_MODE_PICTURED_ELASTIC elastic modes of the hull. Writes their
 * 0-based indices into out, ascending, each once, at most max; returns
 * how many. A kind ms has no mode of adds none. */
size_t fb_mode_set_pictured(const fb_mode_set *ms, size_t *out, size_t max);

/* System 2's hull fragment (same ports as fb_vehicle_rigid_hull), realised
 * for the purpose (an fb_vehicle holds its own): the
 * finite-element matrices as multiport fields on the nodal-velocity
 * multibond (M as an I field: the hull as built, fb_fe_hull_mass_matrix,
 * with the lumped payload's point masses when asked; K as a C field;
 * B = beta K as an R field) and selection transformers to the attachment
 * and load nodes' vertical velocities. The torsion probe weighs the C
 * field's state (the nodal displacements) at the FRONT_EDGE and
 * REAR_EDGE nodes. */
int fb_vehicle_flexible_hull(const fb_scenario *s, const fb_fe_hull *h, fb_hull **out,
                             fb_err *err);

/* The hull's mass matrix as built (*M new): the structure's
 * (fb_fem_assemble) plus each declared mass on the three translations of
 * its node; the structure's alone without any. */
int fb_fe_hull_mass_matrix(const fb_fe_hull *h, fb_mat **M, fb_err *err);

/* ---- What a finite-element hull is (src/vehicle/fe_hull_facts.c), as
 * `flexbond mesh` prints it and the Python package gives it. */

/* A hull's mass (kg), centre of mass (m) and inertia tensor about it
 * (row-major 3 x 3, kg m^2), from its mass matrix's rigid-body modes
 * (fb_fem_mass_properties). */
typedef struct fb_hull_mass_props {
  double mass;
  double cg[3];
  double inertia[9];
} fb_hull_mass_props;

/* Of h's structure alone (with_masses 0: its shells, fb_fem_assemble) or
 * of the hull as built (1: with its declared masses,
 * fb_fe_hull_mass_matrix). */
int fb_fe_hull_mass_props(const fb_fe_hull *h, int with_masses, fb_hull_mass_props *out,
                          fb_err *err);
/* The structure's own stiffness and mass matrices (*K, *M new; N/m, kg;
 * six DOFs per node in node order, fb_fem_assemble), the declared masses
 * left out. */
int fb_fe_hull_matrices(const fb_fe_hull *h, fb_mat **K, fb_mat **M, fb_err *err);
/* h's mesh as built (*out new): a copy of its mesh with each declared
 * mass a point mass of the mesh on its node (fb_mesh_add_point_mass, ids
 * after every element's), so that fb_fem_assemble gives
 * fb_fe_hull_mass_matrix's M and a deck written from it
 * (fb_mesh_write_inp) carries the masses. */
int fb_fe_hull_mesh_as_built(const fb_fe_hull *h, fb_mesh **out, fb_err *err);
/* h's mesh (owned by h) and how many declared masses it carries. */
const fb_mesh *fb_fe_hull_mesh(const fb_fe_hull *h);
size_t fb_fe_hull_npoint_masses(const fb_fe_hull *h);
/* The elements of section sec of h's mesh (fb_mesh_element_section; -1:
 * those of no section, which take h's material): how many, their area
 * (m^2; a warped element's projected area) and their mass (kg: the plate's
 * density times its thickness, plus its non-structural mass, per m^2). */
typedef struct fb_hull_section_totals {
  size_t nelements;
  double area, mass;
} fb_hull_section_totals;
fb_hull_section_totals fb_fe_hull_section_totals(const fb_fe_hull *h, long sec);

/* Stiffness-proportional structural damping B = beta K of the hull, with
 * beta = 2 zeta / omega_1 so that the first elastic free-free mode of the
 * hull as built (fb_fe_hull_mass_matrix: its structure and its declared
 * masses; a lumped payload's masses aside) has the damping ratio zeta
 * (mass-proportional damping would damp the rigid-body motion; Clough &
 * Penzien, "Dynamics of Structures", 2nd ed., sec. 12-3). *B is new (may
 * be NULL if only beta is wanted). */
int fb_fe_hull_damping(const fb_fe_hull *h, double zeta, double *beta, fb_mat **B, fb_err *err);
/* The torsion angle as weights on the nodal DOFs (w, 6 per node, set
 * whole): roll of FRONT_EDGE minus roll of REAR_EDGE, each the slope dz/dy
 * of the line through its two end nodes (fit 0, the paper's `torsion`) or
 * the least-squares rigid rotation about x of every node within 1 mm of
 * the plane x = the edge's x, its whole transverse section (fit 1,
 * `torsion_fit`). */
int fb_fe_hull_torsion_weights(const fb_fe_hull *h, int fit, double *w, fb_err *err);

/* The free-free modes beta is found from: six rigid-body ones, then the
 * first elastic one. */
#define FB_HULL_BETA_MODES 7

/* The nmodes lowest free-free frequencies (Hz, rigid-body ones first at 0,
 * *nrigid of them) of a hull's K and M by o's method (o NULL: the
 * defaults); its FB_EIG_AUTO means LAPACK (eigenvalues only) up to 3000
 * DOFs, as the nodal reference results were computed, block Lanczos
 * above. info (may be NULL) gets how the solve went. */
int fb_fe_hull_frequencies(const fb_mat *K, const fb_mat *M, size_t nmodes,
                           const fb_eig_opts *o, double *freq_hz, size_t *nrigid,
                           fb_eig_info *info, fb_err *err);

/* beta = 2 zeta / omega_1 of fb_fe_hull_damping from the free-free hull's
 * modes: nrigid (which must be six) rigid-body ones, then the first
 * elastic one at f1_hz; FB_ESOLVER otherwise. */
int fb_fe_hull_beta(double zeta, size_t nrigid, double f1_hz, double *beta, fb_err *err);

/* The nmodes lowest modes of the free-free hull as built (its declared
 * masses on it; rigid-body modes first, *nrigid of them at 0 Hz):
 * frequencies only, from an eigen-solve of their own (an fb_vehicle's
 * are in fb_vehicle_hull_basis). */
int fb_fe_hull_free_modes(const fb_fe_hull *h, size_t nmodes, double *freq_hz, size_t *nrigid,
                          fb_err *err);

/* The nmodes lowest modes of the undamped System 2 of v: the finite-element
 * hull with the mounted bodies, suspension springs (k r^2 for motion ratio
 * r), wheels and tire springs attached at its attachment points. The
 * springs are vertical, so the hull's horizontal rigid-body motions
 * (surge, sway, yaw) have no stiffness: those zero-frequency modes are
 * left out and counted in nfree. exact 1, or a hull in nodal coordinates
 * or every mode: from the sparse nodal matrices (a factorisation and a
 * Lanczos solve of the whole vehicle). exact 0 with a reduced basis: the
 * Ritz modes of the basis with the bodies and wheels, a dense problem of
 * its coordinates, accurate within the band the basis converged over
 * (fb_hull_basis.cutoff_hz; for the reference vehicle to 1e-5 up to it,
 * 0.5 % just above), so only those within it. FB_EINVAL for System 1. */
int fb_vehicle_structural_modes(fb_vehicle *v, size_t nmodes, int exact, fb_mode_set **out,
                                fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
