/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: multibond graphs.
 *
 * A graph holds elements joined by bonds. Every bond carries a vector effort
 * e and a vector flow f of the bond's dimension n (a multibond when n > 1)
 * and has a power direction: power e.f is positive from the bond's `from`
 * end to its `to` end (the half arrow points at `to`).
 *
 * Element kinds and their constitutive laws (Karnopp, Margolis & Rosenberg,
 * "System Dynamics", 5th ed., Wiley 2012, ch. 3-4, 7; Breedveld, "Multibond
 * graph elements in physical systems theory", J. Franklin Inst. 319, 1985):
 *   Se, Sf      effort or flow source, each component a function of time
 *   I field     p' = e (per port), f = M^-1 p    (M symmetric positive definite)
 *   C field     q' = f, e = K q                  (K symmetric positive semi-definite)
 *   R field     e = R f                          (R symmetric positive semi-definite)
 *   TF  (r)     e1 = r e2, f2 = r f1             (port 1 in, port 2 out)
 *   GY  (r)     e1 = r f2, e2 = r f1
 *   MTF (T)     f2 = T f1, e1 = T^T e2           (T is n2 x n1)
 *   0-junction  equal efforts, signed flows sum to zero
 *   1-junction  equal flows, signed efforts sum to zero
 *   composite   the paper's "horizontal line": k part bonds stacked into one
 *               whole multibond, e = [e_1; ...; e_k], f = [f_1; ...; f_k]
 * A field has one or more ports; its law acts on the stacked port vectors.
 * A one-port I, C or R is a field with one port. Laws are matrices now; a
 * nonlinear law is an fb_law (explicit causality only).
 *
 * Port references are strings:
 *   "J"          a junction (each bond to it adds a port) or a one-port element
 *   "E.k"        port k (1-based) of a multiport element; composite: "E.whole"
 *   "sub.p"      port p exported by the adopted subsystem sub (nests: "a.b.p")
 * Element names inside an adopted subsystem are prefixed "sub.". */
#ifndef FLEXBOND_BG_H
#define FLEXBOND_BG_H

#include <stddef.h>
#include <stdio.h>

#include "flexbond/error.h"
#include "flexbond/expr.h"
#include "flexbond/mat.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum fb_bg_kind {
  FB_BG_SE,
  FB_BG_SF,
  FB_BG_I,
  FB_BG_C,
  FB_BG_R,
  FB_BG_TF,
  FB_BG_GY,
  FB_BG_MTF,
  FB_BG_J0,
  FB_BG_J1,
  FB_BG_COMPOSITE
} fb_bg_kind;

/* Physical domain of a bond: sets the units of its effort, flow, and of
 * their time integrals in probes and reports. */
typedef enum fb_bg_domain {
  FB_DOMAIN_TRANSLATION, /* N, m/s, momentum N s, displacement m */
  FB_DOMAIN_ROTATION,    /* N m, rad/s, N m s, rad */
  FB_DOMAIN_ELECTRICAL,  /* V, A, V s, C */
  FB_DOMAIN_HYDRAULIC,   /* Pa, m^3/s, Pa s, m^3 */
  FB_DOMAIN_GENERIC      /* effort, flow: unit "1" */
} fb_bg_domain;

/* Direction of power at a subsystem's exported port. */
typedef enum fb_bg_dir {
  FB_PORT_IN, /* power flows into the subsystem through the port */
  FB_PORT_OUT /* power flows out of the subsystem */
} fb_bg_dir;

/* A nonlinear constitutive law y = phi(x) for a field (explicit causality:
 * I: x = p, y = f; C: x = q, y = e; R: x = f, y = e). n is the stacked
 * port dimension.
 *
 * A modulated R (the "MR" of Karnopp, Margolis & Rosenberg: a
 * resistor whose law also reads signals that carry no power) reads m more
 * values, the states of the storage elements named with fb_bg_modulate,
 * stacked after its own input: the law sees xu = [x (n); u (m)] and its
 * Jacobian has n + m columns.
 *
 * A switched law (a hybrid element: a law with smooth branches, "modes",
 * and conditions for passing between them; Mosterman & Biswas, "A theory
 * of discontinuities in physical system models", J. Franklin Inst.
 * 335(3), 1998) also gives nguards guard functions g(xu). The integrator
 * keeps the mode fixed between events, so each branch is integrated as a
 * smooth law, locates the zero crossings of the guards by root-finding,
 * asks switch_mode for the next mode at each crossing and restarts there
 * (discontinuity locking; Cellier & Kofman, "Continuous System
 * Simulation", Springer 2006, ch. 9). Guards that mean nothing in a mode
 * should return a constant there (e.g. 1), so that they do not stop the
 * integration for nothing.
 *
 * Functions return 0 on success, >0 for a recoverable failure (the solver
 * retries with a smaller step), <0 fatal. */
typedef struct fb_law_in {
  size_t n;        /* the law's own input and output dimension */
  size_t m;        /* modulating values (0 unless fb_bg_modulate) */
  const double *x; /* n + m values: own input, then modulating values */
  int mode;        /* active branch of a switched law, 0 for a smooth one */
} fb_law_in;

/* Which of the library's own laws an ops table is, as SUNDIALS names a
 * module's implementation (N_VGetVectorID): for the module that made a
 * law to recognise it again (fb_bg_element_table_law,
 * fb_bg_element_contact) without comparing ops pointers, and for a
 * harness to list them all (every id below FB_LAW_NIDS but
 * FB_LAW_CUSTOM has one law). A law of one's own is FB_LAW_CUSTOM, what
 * an ops table that does not set the id has. */
typedef enum fb_law_id {
  FB_LAW_CUSTOM = 0,
  FB_LAW_TABLE,          /* fb_bg_add_r_table */
  FB_LAW_CONTACT_SPRING, /* fb_bg_add_unilateral_contact: the spring (C) */
  FB_LAW_CONTACT_DAMPER, /* and the damper (modulated R) */
  FB_LAW_NIDS
} fb_law_id;

typedef struct fb_law_ops {
  const char *name;
  fb_law_id id;
  int (*eval)(void *ctx, const fb_law_in *in, double *y);
  /* dy/dxu into jac, column-major n x (n + m). */
  int (*jacobian)(void *ctx, const fb_law_in *in, double *jac);
  /* Stored energy (I, C) or co-content, for energy probes, as a function
   * of the state alone (not of a mode); may be NULL. */
  double (*energy)(void *ctx, size_t n, const double *x);
  void (*free)(void *ctx);
  /* ---- Switched laws only (nguards = 0 and NULL functions otherwise). */
  size_t nguards;
  /* The guards at in (in its mode) into g[0 .. nguards). */
  int (*guards)(void *ctx, const fb_law_in *in, double *g);
  /* Sets *mode, the mode to continue in at in (in->mode is the current
   * one), from the guards' signs: sign[i] is +1 or -1 for guard i, the
   * direction it has just crossed zero in at an event, else the sign of
   * its value at in (of its value just after in, where it is exactly
   * zero). The caller repeats the choice until no mode changes, so a law
   * may move one mode at a time. */
  int (*switch_mode)(void *ctx, const fb_law_in *in, const int *sign, int *mode);
  /* 1 when every branch is affine in xu, so the Jacobian changes only
   * with the mode and the Newton matrix only at events. */
  int affine;
  /* 1 for a resistor's law that never delivers power: y . x >= 0 over its
   * own input x (the first n values of xu), in the mode its guards choose
   * there (Karnopp et al. ch. 3). */
  int passive;
} fb_law_ops;

typedef struct fb_bg fb_bg;

/* Creates an empty graph named name (copied). */
int fb_bg_new(const char *name, fb_bg **out, fb_err *err);
/* Frees *bg and everything it owns, sets *bg to NULL; accepts NULL. */
void fb_bg_free(fb_bg **bg);
const char *fb_bg_name(const fb_bg *bg);

/* Default domain of bonds added afterwards (initially TRANSLATION). */
void fb_bg_set_domain(fb_bg *bg, fb_bg_domain domain);

/* ---- Elements. Names are unique in a graph; they may not contain '.'.
 * Functions that take `T **x` take ownership of *x and set it to NULL,
 * also on failure. */

/* Source of dimension dim; values[i] is component i. */
int fb_bg_add_source(fb_bg *bg, const char *name, fb_bg_kind kind, size_t dim, fb_tfun **values,
                     fb_err *err);
/* Replaces component k of source name's time function with *f (taken
 * over, *f set to NULL, also on failure): a vehicle's constant load made
 * an input a stepper holds, say. A diagram reads the functions of the
 * graph it was built from, except constant ones, which it folds when it
 * is built: change the graph before building the diagram. FB_EMODEL if
 * name is no source, FB_EINVAL if k is not below its dimension. */
int fb_bg_set_source(fb_bg *bg, const char *name, size_t k, fb_tfun **f, fb_err *err);
/* I, C or R field with nports ports of dimensions port_dims; law is the
 * stacked matrix (M, K or R) of size sum(port_dims). */
int fb_bg_add_field(fb_bg *bg, const char *name, fb_bg_kind kind, size_t nports,
                    const size_t *port_dims, fb_mat **law, fb_err *err);
/* As fb_bg_add_field with a nonlinear law; ctx is owned by the graph and
 * released with ops->free. */
int fb_bg_add_field_law(fb_bg *bg, const char *name, fb_bg_kind kind, size_t nports,
                        const size_t *port_dims, const fb_law_ops *ops, void *ctx, fb_err *err);

/* Makes the nonlinear law of the R element `element` read the states (p
 * of I, q of C, stacked in the order given) of the storage elements
 * sources[0 .. nsources) as modulating values (see fb_law_ops). The
 * sources are elements of bg at the time of the call and follow them
 * through fb_bg_adopt. FB_EMODEL when an element is missing, `element` is
 * not an R with a nonlinear law, a source is not an I or C, or the
 * element is already modulated. */
int fb_bg_modulate(fb_bg *bg, const char *element, size_t nsources, const char *const *sources,
                   fb_err *err);

/* ---- Tabulated one-port laws y = phi(x), e.g. a damper's force-velocity
 * curve (R: x = f velocity, y = e force). phi is the monotone piecewise
 * cubic Hermite interpolant of the knots (Fritsch & Carlson, "Monotone
 * piecewise cubic interpolation", SIAM J. Numer. Anal. 17(2), 1980),
 * continued linearly beyond the first and last knots with the end
 * derivatives, so phi and phi' are continuous everywhere. Monotone data
 * give a monotone phi; data on a straight line give that line (to
 * rounding). Implemented in src/bg/table_law.c. */
typedef struct fb_table_law fb_table_law;

/* Builds the law through n >= 2 knots (x[i], y[i]), copied: finite values,
 * x strictly increasing. FB_EINVAL naming the first offending knot
 * (1-based) otherwise. */
int fb_table_law_new(size_t n, const double *x, const double *y, fb_table_law **out,
                     fb_err *err);
/* Reads the knots from columns x_col and y_col of the CSV file at path: a
 * header line of comma-separated names, then rows of numbers; blank lines,
 * '#' comment lines and spaces around fields are ignored. FB_EIO when the
 * file cannot be read; FB_EPARSE "path:line: ..." for a missing column, a
 * field that is not a finite number, a row of the wrong length, x not
 * strictly increasing, or fewer than 2 rows. */
int fb_table_law_read_csv(const char *path, const char *x_col, const char *y_col,
                          fb_table_law **out, fb_err *err);
/* Frees *law, sets it to NULL; accepts NULL. */
void fb_table_law_free(fb_table_law **law);
/* The law's knots: returns their number and points *x and *y at them
 * (owned by the law, valid while it lives). */
size_t fb_table_law_knots(const fb_table_law *law, const double **x, const double **y);
/* phi(x); *slope gets phi'(x) (the exact derivative of the interpolant)
 * when slope is not NULL. */
double fb_table_law_eval(const fb_table_law *law, double x, double *slope);
/* Integral of phi from 0 to x, in closed form: for an R the co-content
 * (Millar, "Some general theorems for non-linear systems possessing
 * resistance", Phil. Mag. 42, 1951), the law's `energy`. */
double fb_table_law_integral(const fb_table_law *law, double x);
/* FB_OK when phi(x) x >= 0 for every real x, i.e. a resistor with this
 * law never delivers power (a passive R, Karnopp et al. ch. 3); phi(0)
 * may differ from 0 by rounding (16 ulp of the largest |y|). FB_EINVAL
 * naming a knot, x = 0 or an end whose linear continuation has the wrong
 * sign otherwise. */
int fb_table_law_check_passive(const fb_table_law *law, fb_err *err);
/* Adds a one-port R element (dimension 1) named name with law e = phi(f).
 * Takes ownership of *law and sets it to NULL, also on failure. Refuses
 * (FB_EINVAL, see fb_table_law_check_passive) a law that is not passive. */
int fb_bg_add_r_table(fb_bg *bg, const char *name, fb_table_law **law, fb_err *err);
/* FB_EINVAL unless the law's values do not decrease from knot to knot,
 * so that phi' >= 0 everywhere (a stable spring, a convex energy). */
int fb_table_law_check_monotone(const fb_table_law *law, fb_err *err);
/* Adds a one-port C element (dimension 1) named name with law e = phi(q),
 * its energy phi's integral from q = 0: a spring's force against its
 * travel, which may be nonzero at 0 (a preload). Takes ownership of *law
 * and sets it to NULL, also on failure. Refuses (FB_EINVAL, see
 * fb_table_law_check_monotone) a law that decreases. */
int fb_bg_add_c_table(fb_bg *bg, const char *name, fb_table_law **law, fb_err *err);

/* ---- Unilateral compliant contact: a spring k and a damper c in
 * parallel (Kelvin-Voigt) that can push but never pull, e.g. a tire on
 * the road. q is the spring's compression (the penetration: contact while
 * q > 0, a gap of -q otherwise) and f = q' its rate. The contact force is
 *     F = max(0, k q + c f)  while q > 0,     F = 0  while q <= 0
 * (the "no tension" condition of compliant contact, as in Hunt &
 * Crossley, J. Appl. Mech. 42(2), 1975, who discuss the Kelvin-Voigt
 * model's tensile force before separation). It is built from two
 * switched laws, so that the integrator locates every change:
 *   spring (C):  e = k q (mode 0, contact), 0 (mode 1, separated);
 *                guard q;
 *   damper (R, modulated by the spring's q):  e = c f (mode 0, contact),
 *                -k q (mode 1, released: k q + c f would pull, the damper
 *                cancels the spring), 0 (mode 2, separated);
 *                guards q and k q + c f.
 * Both laws are affine in each mode. The stored energy k max(q, 0)^2 / 2 is
 * continuous at every switch and the damper never delivers power (in
 * mode 1 its power -k q f is >= 0, since q > 0 and c f < -k q there), so
 * an energy balance closes across contact changes.
 *
 * Adds the C element `spring` and the modulated R element `damper`, both
 * one-ports of dimension 1; the caller bonds both to one 1-junction (the
 * common compression rate), where their efforts add up to F. FB_EINVAL
 * unless k > 0 and c >= 0 are finite; FB_EMODEL for a name that is
 * invalid or taken, or the same for both; nothing is added then.
 * Implemented in src/bg/contact_law.c. */
int fb_bg_add_unilateral_contact(fb_bg *bg, const char *spring, const char *damper, double k,
                                 double c, fb_err *err);
/* The same pair with Hunt & Crossley's damping (J. Appl. Mech. 42(2),
 * 1975, with a linear spring, exponent n = 1): a damping coefficient that
 * grows with the penetration, lambda q (lambda in N s/m^2), so that
 *     F = max(0, k q + lambda q f)  while q > 0,     F = 0  while q <= 0.
 * The Kelvin-Voigt damper c f jumps to c times the approach speed at
 * first contact (a wheel landing at 2 m/s on a 140 kN s/m tire damper
 * meets 280 kN at once); this one starts from zero force and grows with
 * the penetration, as the contact area of a real tire does. The damper's
 * law is then not affine in contact (de/dq = lambda f), the spring's is
 * unchanged, and the energy argument above holds as written with
 * c = lambda q >= 0. FB_EINVAL unless k > 0 and lambda >= 0 are finite;
 * otherwise as fb_bg_add_unilateral_contact. */
int fb_bg_add_hunt_crossley_contact(fb_bg *bg, const char *spring, const char *damper, double k,
                                    double lambda, fb_err *err);
/* As fb_bg_add_unilateral_contact with the spring's force in contact a
 * table's phi(q) (law, copied: knots from (0, 0), forces not decreasing,
 * not all 0; its energy phi's integral) in place of k q. Neither
 * element is then recognised by fb_bg_element_contact. */
int fb_bg_add_table_contact(fb_bg *bg, const char *spring, const char *damper,
                            const fb_table_law *law, double c, fb_err *err);

/* Initial state (p for I, q for C) of a field, stacked; default zero. */
int fb_bg_set_initial(fb_bg *bg, const char *name, size_t n, const double *x0, fb_err *err);
/* TF or GY of dimension dim with scalar modulus. */
int fb_bg_add_tf(fb_bg *bg, const char *name, fb_bg_kind kind, size_t dim, double modulus,
                 fb_err *err);
/* Matrix transformer f2 = T f1, e1 = T^T e2. */
int fb_bg_add_mtf(fb_bg *bg, const char *name, fb_mat **T, fb_err *err);
/* 0- or 1-junction of dimension dim. */
int fb_bg_add_junction(fb_bg *bg, const char *name, fb_bg_kind kind, size_t dim, fb_err *err);
/* Composite with nparts part ports (dims part_dims) and one whole port of
 * dimension sum(part_dims). */
int fb_bg_add_composite(fb_bg *bg, const char *name, size_t nparts, const size_t *part_dims,
                        fb_err *err);

/* ---- Bonds. Connects port reference `from` to `to` (power from -> to).
 * The bond's dimension is the ports' common dimension; a mismatch, or an
 * exported port whose power direction disagrees (a bond leaving a
 * subsystem through an IN port, say), is FB_EMODEL naming both ports.
 * name may be NULL (a name "from->to" is made). */
int fb_bg_connect(fb_bg *bg, const char *name, const char *from, const char *to, fb_err *err);
/* Domain of an existing bond (overrides the graph default). */
int fb_bg_set_bond_domain(fb_bg *bg, const char *bond, fb_bg_domain domain, fb_err *err);

/* ---- Subsystems. */
/* Declares an external port of bg named port_name at the port reference
 * target inside bg, with power direction dir as seen from bg. Re-exporting
 * an adopted subsystem's port must keep its direction. */
int fb_bg_add_port(fb_bg *bg, const char *port_name, const char *target, fb_bg_dir dir,
                   fb_err *err);
/* Moves every element, bond and port of *child into parent under the
 * prefix instance_name, frees the child shell and sets *child to NULL
 * (also on failure). The child's ports are then referenced from parent
 * as "instance_name.port". */
int fb_bg_adopt(fb_bg *parent, fb_bg **child, const char *instance_name, fb_err *err);

/* ---- Causality: sequential causality assignment procedure (Karnopp et
 * al., section 5.2; Rosenberg & Karnopp 1983): sources, then storage in
 * integral causality, then resistors, then remaining junction bonds, each
 * followed by propagation through junctions, transformers and gyrators,
 * vector-wise on multibonds. FB_ECAUSAL on a conflict or on storage in
 * derivative causality, naming the elements and bonds involved; FB_EMODEL
 * on an unconnected element port. Idempotent. */
int fb_bg_assign_causality(fb_bg *bg, fb_err *err);

/* ---- Inspection (valid indices 0 .. count-1). */
size_t fb_bg_nelements(const fb_bg *bg);
size_t fb_bg_nbonds(const fb_bg *bg);
/* Index of a named element or bond, or -1. */
long fb_bg_find_element(const fb_bg *bg, const char *name);
long fb_bg_find_bond(const fb_bg *bg, const char *name);
const char *fb_bg_element_name(const fb_bg *bg, size_t i);
fb_bg_kind fb_bg_element_kind(const fb_bg *bg, size_t i);
/* Stacked dimension of the element's ports (state size for I and C). */
size_t fb_bg_element_dim(const fb_bg *bg, size_t i);
/* What each component of an element is to a reader ("hull bounce",
 * "wheel hop LF"), as the fragment that made it declares: labels holds
 * the element's dimension of them (copied); kept through adoption, where
 * names are prefixed. A mode's description names the body it moves by its
 * label, never by parsing the element's name. FB_EMODEL for no such
 * element. */
int fb_bg_set_labels(fb_bg *bg, const char *element, const char *const *labels, fb_err *err);
/* Component component's label of element i, NULL when it has none. */
const char *fb_bg_element_label(const fb_bg *bg, size_t i, size_t component);
const char *fb_bg_bond_name(const fb_bg *bg, size_t i);
size_t fb_bg_bond_dim(const fb_bg *bg, size_t i);
fb_bg_domain fb_bg_bond_domain(const fb_bg *bg, size_t i);
/* Element indices at the bond's ends (power from -> to). */
size_t fb_bg_bond_from(const fb_bg *bg, size_t i);
size_t fb_bg_bond_to(const fb_bg *bg, size_t i);
/* After causality: 1 if the `to` element receives the effort (causal stroke
 * at the `to` end), 0 if the `from` element does, -1 if unassigned. */
int fb_bg_bond_effort_to_head(const fb_bg *bg, size_t i);

/* ---- Reading a graph back (e.g. to write it as a model file,
 * fb_model_write). Every pointer returned is owned by the graph and valid
 * while it lives and is not changed; indices as above. */
/* Default bond domain (fb_bg_set_domain). */
fb_bg_domain fb_bg_default_domain(const fb_bg *bg);
/* Ports of element i: the fixed slots of sources, fields, TF, GY, MTF
 * (port 1, 2) and composites (parts, then the whole), or the bonds
 * attached to a junction, in the order they were connected. */
size_t fb_bg_element_nports(const fb_bg *bg, size_t i);
/* 1 for numbered slots, 0 for a junction (every bond adds a port). */
int fb_bg_element_has_fixed_ports(const fb_bg *bg, size_t i);
size_t fb_bg_element_port_dim(const fb_bg *bg, size_t i, size_t k);
/* Law matrix of a linear field (M, K or R) or the T of an MTF; NULL for
 * other kinds and nonlinear laws. */
const fb_mat *fb_bg_element_matrix(const fb_bg *bg, size_t i);
/* Nonlinear law of a field and its context (in *ctx if ctx is not NULL);
 * NULL for a linear one. Which law it is: its id, or a module's own
 * accessor (fb_bg_element_table_law, fb_bg_element_contact). */
const fb_law_ops *fb_bg_element_law(const fb_bg *bg, size_t i, const void **ctx);
/* Modulus of a TF or GY (0 for other kinds). */
double fb_bg_element_modulus(const fb_bg *bg, size_t i);
/* Component k of a source's value, NULL for other kinds or k >= dim. */
const fb_tfun *fb_bg_element_source(const fb_bg *bg, size_t i, size_t k);
/* Initial state of an I or C (dim values), NULL when never set (zero). */
const double *fb_bg_element_initial(const fb_bg *bg, size_t i);
/* Port index of the bond's ends at its from and to elements. */
size_t fb_bg_bond_from_port(const fb_bg *bg, size_t i);
size_t fb_bg_bond_to_port(const fb_bg *bg, size_t i);
/* A declared port: the graph's own exported ones (exported = 1), and the
 * ports of adopted instances ("inst.p", exported = 0). */
#define FB_BG_ANY_PORT ((size_t)-1) /* a junction's: each bond adds a port */
typedef struct fb_bg_port_info {
  const char *name;
  fb_bg_dir dir;
  int exported;
  size_t element; /* target element index */
  size_t port;    /* its port index, or FB_BG_ANY_PORT for a junction */
} fb_bg_port_info;
size_t fb_bg_ndeclared_ports(const fb_bg *bg);
/* FB_EINVAL when i >= fb_bg_ndeclared_ports. */
int fb_bg_declared_port(const fb_bg *bg, size_t i, fb_bg_port_info *out);

/* The table law of an R made by fb_bg_add_r_table, NULL for any other
 * element (src/bg/table_law.c). */
const fb_table_law *fb_bg_element_table_law(const fb_bg *bg, size_t i);
/* A pair made by fb_bg_add_unilateral_contact (src/bg/contact_law.c). */
typedef struct fb_bg_contact {
  size_t spring, damper; /* element indices */
  double k, c;
  double lambda; /* N s/m^2: > 0 for fb_bg_add_hunt_crossley_contact (c is 0 then) */
} fb_bg_contact;
/* 1 and *out filled when element i is the spring or the damper of a
 * unilateral contact, 0 otherwise. */
int fb_bg_element_contact(const fb_bg *bg, size_t i, fb_bg_contact *out);

const char *fb_bg_kind_name(fb_bg_kind kind);
/* Units of effort, flow, effort integral and flow integral. */
const char *fb_bg_domain_unit(fb_bg_domain d, int which);
enum { FB_UNIT_EFFORT, FB_UNIT_FLOW, FB_UNIT_MOMENTUM, FB_UNIT_DISPLACEMENT };

/* ---- Picture: the graph as a multibond graph in Graphviz DOT (the
 * paper's Fig. 5; the conventions are in docs/diagrams.md). One node per
 * element, named by its full name and labelled with its kind and its name
 * within its subsystem (junctions "0" and "1", a composite drawn as a bar,
 * the paper's "horizontal line"); one edge per bond, from its `from` to
 * its `to` element, with a half arrow at `to` (the power direction), the
 * bond's name and, for a multibond, its dimension "[n]" (never one edge
 * per component); a causal stroke (arrow shape "tee") at the end whose
 * element receives the effort, where causality has been assigned
 * (fb_bg_assign_causality), none otherwise; one cluster per subsystem
 * instance, nested as the instances are, labelled with the instance's
 * name. Every name passes fb_dot_write_text. FB_EIO on a write error,
 * FB_ENOMEM. Implemented in src/bg/dot.c. */
int fb_bg_write_dot(const fb_bg *bg, FILE *fp, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
