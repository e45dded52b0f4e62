/* flexbond: the wheeled-vehicle study of Leite & Da Silva (see
 * ../shared/reference-vehicle.md): a scenario (every number of the data
 * sheet), subsystems as bond-graph fragments with ports, their assembly,
 * and the paper's seven outputs.
 *
 * Axes (ISO 8855): origin at the hull's centre of mass, x forward, y left,
 * z up; roll phi about x, pitch theta about y (positive nose down). A hull
 * point (x, y) moves vertically by z + y phi - x theta. Forces are positive
 * upwards; spring and tire deflections are positive in compression. */
#ifndef FLEXBOND_VEHICLE_H
#define FLEXBOND_VEHICLE_H

#include <stddef.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"
#include "flexbond/error.h"
#include "flexbond/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The six suspensions, in the order of every per-corner array. */
enum fb_corner { FB_LF, FB_RF, FB_LM, FB_RM, FB_LR, FB_RR, FB_NCORNERS };
/* "LF", "RF", ... */
const char *fb_corner_name(int corner);

/* Hull attachment points, in the order of the hull's "attach" port:
 * the six suspensions (FB_LF .. FB_RR), then the driver and the engine. */
enum { FB_ATTACH_DRIVER = FB_NCORNERS, FB_ATTACH_ENGINE, FB_NATTACH };

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

/* A rigid body moving vertically on a spring and a damper in parallel to a
 * hull point (driver plus seat, engine). */
typedef struct fb_mount {
  double mass;      /* kg */
  double stiffness; /* N/m */
  double damping;   /* N s/m */
  double x, y;      /* attachment point, m */
} fb_mount;

/* One suspension: spring and shock absorber in parallel between the hull
 * point and the wheel (massless arm: spring travel = motion_ratio x wheel
 * travel relative to the hull), the wheel mass, the tire spring and
 * damper in parallel between the wheel and the road. */
typedef struct fb_corner_params {
  double spring_k;     /* N/m */
  double damper_c;     /* N s/m */
  double motion_ratio; /* spring travel / wheel travel, > 0 */
  double x, y;         /* attachment point, m */
  double wheel_mass;   /* kg */
  double tire_k;       /* N/m */
  double tire_c;       /* N s/m */
} fb_corner_params;

/* The study's parameters. Strings and arrays are owned by the scenario. */
typedef struct fb_scenario {
  char *name;
  char *path;     /* file it was loaded from (for messages), may be NULL */
  double gravity; /* m/s^2 */
  /* Hull (paper, Tables 1-2). */
  double hull_mass;          /* kg */
  double hull_ixx, hull_iyy; /* kg m^2 about the hull's centre of mass */
  double young, poisson;     /* Pa, - (System 2) */
  double density, thickness; /* kg/m^3, m (System 2) */
  /* Edges whose roll difference is the torsion angle: front and rear
   * edge x, left and right end y (System 2 uses the mesh's node sets). */
  double edge_front_x, edge_rear_x, edge_left_y, edge_right_y; /* m */
  /* Load: total weight of hull plus payload, spread equally over the
   * load points. */
  double total_weight; /* N */
  fb_payload_model payload;
  size_t nload;
  double *load_x, *load_y; /* m, nload each */
  fb_mount driver, engine;
  fb_corner_params corner[FB_NCORNERS];
  /* Road: a (1 - cos) bump of height h and length L along each wheel's
   * path, its leading edge at bump_angle to the lateral axis, left side
   * first; the left front wheel meets it at bump_time. */
  double speed;       /* m/s */
  double bump_height; /* m */
  double bump_length; /* m */
  double bump_angle;  /* rad */
  double bump_time;   /* s */
  /* Simulation. */
  double t_end, rtol, atol, max_step, sample_rate; /* s, -, -, s, Hz */
  fb_initial_state initial;
} fb_scenario;

/* Loads and validates a scenario file (format: docs/scenario-format.md).
 * Errors are "FILE:LINE:COL: KEY: message". */
int fb_scenario_load(const char *path, fb_scenario **out, fb_err *err);
int fb_scenario_load_string(const char *text, size_t len, const char *display_name,
                            fb_scenario **out, fb_err *err);
/* Physical consistency (positive masses, stiffnesses, ...; bump inside the
 * run). FB_EINVAL naming the key, e.g. "suspensions.LF.spring_k: must be
 * > 0 (got -1)". */
int fb_scenario_check(const fb_scenario *s, fb_err *err);
void fb_scenario_free(fb_scenario **s);
/* Deep copy. */
int fb_scenario_clone(const fb_scenario *s, fb_scenario **out, fb_err *err);

/* Time at which the wheel of `corner` meets the bump's leading edge:
 * bump_time + ((x_LF - x) + (y_LF - y) tan(bump_angle)) / speed. */
double fb_scenario_bump_entry(const fb_scenario *s, int corner);
/* Time it leaves the bump: entry + bump_length / speed. */
double fb_scenario_bump_exit(const fb_scenario *s, int corner);

/* ---- Subsystems as bond-graph fragments. Every fragment is a new graph
 * owned by the caller (or handed to fb_vehicle_assemble). */

/* A hull: a graph with the ports
 *   "attach" (IN, dimension FB_NATTACH): vertical force and velocity at
 *            the attachment points, in FB_LF .. FB_ATTACH_ENGINE order;
 *   "load"   (IN, dimension nload): the load points;
 * and the probe that measures its torsion angle (a weighted sum over a
 * vector signal, names relative to the hull fragment). */
typedef struct fb_hull {
  fb_bg *graph;
  char *torsion_target; /* bond or element inside the fragment */
  fb_probe_kind torsion_kind;
  int torsion_integrate;
  double *torsion_weights;
  size_t ntorsion;
} fb_hull;
void fb_hull_free(fb_hull **h);

/* System 1: I field diag-dominant 3x3 (bounce, roll, pitch; with the
 * lumped payload's point masses when asked) and matrix transformers to
 * the attachment and load points. */
int fb_vehicle_rigid_hull(const fb_scenario *s, fb_hull **out, fb_err *err);
/* Driver plus seat or engine: port "hull" (OUT). */
int fb_vehicle_mount(const fb_mount *m, double gravity, fb_bg **out, fb_err *err);
/* One suspension with its wheel and tire: ports "hull" (OUT), "road" (IN). */
int fb_vehicle_corner(const fb_corner_params *c, double gravity, fb_bg **out, fb_err *err);
/* The road: one flow source per wheel (the bump's vertical velocity under
 * that wheel), ports "LF" .. "RR" (OUT). */
int fb_vehicle_road(const fb_scenario *s, fb_bg **out, fb_err *err);
/* The load: one effort source of dimension nload, port "load" (OUT). */
int fb_vehicle_load(const fb_scenario *s, fb_bg **out, fb_err *err);

/* Connects a hull (taken over, *hull set to NULL) with the driver, engine,
 * six corners, road and load fragments built from s. Instance names:
 * "hull", "driver", "engine", "susp_LF" .. "susp_RR", "road", "load"; the
 * composite "attach" stacks the eight scalar bonds into the hull's
 * multibond (the paper's horizontal line). The hull is the only part that
 * differs between System 1 and System 2. */
int fb_vehicle_assemble(const fb_scenario *s, fb_hull **hull, fb_bg **out,
                        fb_probe_spec **probes, size_t *nprobes, fb_err *err);
/* Frees what fb_vehicle_assemble returned in *probes. */
void fb_vehicle_probes_free(fb_probe_spec **probes, size_t nprobes);

/* The paper's seven outputs (Figs. 8-14), in the CSV column order:
 * tire_force_LF, spring_defl_RF, torsion, driver_acc, shock_power_LM,
 * tire_defl_RM, tire_power_LR. */
enum { FB_NOUTPUTS = 7 };
const char *fb_vehicle_output_name(int k);
const char *fb_vehicle_output_unit(int k);

/* Assembles the vehicle for system sys (System 1 now; System 2 once the
 * finite-element hull exists) and builds its block diagram with the seven
 * output probes. *graph and *bd are new (free bd first: it borrows the
 * graph). */
int fb_vehicle_build(const fb_scenario *s, fb_system sys, fb_bg **graph, fb_bd **bd,
                     fb_err *err);

/* Integrates the vehicle per the scenario: initial state (zero or static
 * equilibrium), breakpoints at every wheel's bump entry and exit,
 * tolerances, sampling. The result's columns are t then the seven
 * outputs, named and ordered as fb_vehicle_output_name. */
int fb_vehicle_simulate(const fb_scenario *s, fb_system sys, fb_result **out, fb_err *err);

/* A mode of the linearised vehicle. */
typedef struct fb_mode {
  double re, im;        /* eigenvalue, 1/s and rad/s (im >= 0) */
  double freq_hz;       /* |lambda| / 2 pi (undamped: im / 2 pi) */
  double damping_ratio; /* -re / |lambda| */
  char description[96]; /* from the largest kinetic-energy share, e.g.
                           "hull bounce (62%)", "wheel hop LF (91%)" */
} fb_mode;

/* Modes of the vehicle linearised at its static equilibrium, from the
 * block diagram's exact Jacobian: with undamped set, every damper and
 * tire damper is removed first (natural frequencies). Oscillatory modes
 * come first by frequency; non-oscillatory ones (real eigenvalues) after;
 * zero eigenvalues of statically indeterminate support (the hull on six
 * springs) are counted in *nstatic and left out. *modes is new. */
int fb_vehicle_modes(const fb_scenario *s, fb_system sys, int undamped, fb_mode **modes,
                     size_t *nmodes, size_t *nstatic, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
