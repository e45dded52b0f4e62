/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: block diagrams built from causal bond graphs, and their
 * evaluation and linearisation.
 *
 * Every bond effort and flow becomes a vector signal produced by exactly one
 * block: integrators (the states p of I fields and q of C fields), matrix
 * gains, linear solves (M^-1 p without forming M^-1), signed sums (junction
 * laws), mux/demux (field ports, composites), sources, element-wise
 * products (power probes) and nonlinear laws. Blocks are scheduled in
 * topological order; a cycle among non-integrator blocks is an algebraic
 * loop and is reported with its zero-order causal path (Ferreira & Da
 * Silva, COBEM 2005; Karnopp et al. ch. 5).
 *
 * The diagram is the right-hand side x' = F(t, x) for an ODE solver, and it
 * linearises itself sparsely: with z the vector of all signal components
 * (states included), each block contributes the rows of its local
 * linearisation, so that the Newton matrix I - gamma dF/dx is the Schur
 * complement onto the states of the sparse matrix P(gamma) = P0 + gamma P1.
 * Solving P(gamma) z = [b at state rows, 0 elsewhere] gives the Newton
 * update at the state rows. No dense inverse (of a mass matrix, say) is
 * ever formed. */
#ifndef FLEXBOND_BD_H
#define FLEXBOND_BD_H

#include <stddef.h>
#include <stdio.h>

#include "flexbond/bg.h"
#include "flexbond/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum fb_probe_kind {
  FB_PROBE_EFFORT, /* effort of a bond */
  FB_PROBE_FLOW,   /* flow of a bond */
  FB_PROBE_POWER,  /* element-wise e .* f of a bond, W (positive from -> to) */
  FB_PROBE_STATE,  /* state (p or q) of an I or C element */
  FB_PROBE_ENERGY  /* stored energy of an I or C element, J (scalar) */
} fb_probe_kind;

/* A named measurement (the paper's "meter"). Strings are borrowed for the
 * duration of fb_bd_build only. */
typedef struct fb_probe_spec {
  const char *name; /* output name (CSV column) */
  fb_probe_kind kind;
  const char *target; /* bond name, or element name for STATE/ENERGY */
  long component;     /* 0-based component, or -1 for all (columns name[1..n]) */
  int integrate;      /* 1: record the time integral from t = 0 */
  double gain;        /* scale factor applied to the value (1 for none) */
  const char *unit;   /* unit to report, NULL to derive it from the domain */
  /* When nweights > 0: one scalar output gain * sum_k weights[k] * v[k]
   * over the nweights components of the (integrated) signal v, such as a
   * hull torsion angle from node displacements. Borrowed during the build. */
  const double *weights;
  size_t nweights;
} fb_probe_spec;

typedef struct fb_bd fb_bd;

/* Builds the diagram of bg (causality is assigned if not yet). The diagram
 * borrows bg's laws and time functions: bg must outlive it. FB_ECAUSAL with
 * the path on an algebraic loop; FB_EMODEL on an unknown probe target. */
int fb_bd_build(fb_bg *bg, const fb_probe_spec *probes, size_t nprobes, fb_bd **out,
                fb_err *err);
void fb_bd_free(fb_bd **bd);

size_t fb_bd_nstates(const fb_bd *bd);
/* "element.p" / "element.q" with "[k]" (1-based) for vector states. */
const char *fb_bd_state_name(const fb_bd *bd, size_t i);
/* What a state is: the momentum p of an I field, the displacement q of a
 * C field, or the integral kept by an integrating probe. */
typedef enum fb_state_kind {
  FB_STATE_MOMENTUM,
  FB_STATE_DISPLACEMENT,
  FB_STATE_PROBE
} fb_state_kind;
fb_state_kind fb_bd_state_kind(const fb_bd *bd, size_t i);
/* Graph element index owning state i (its component within the element
 * in *component if not NULL), or -1 for a probe's integral. */
long fb_bd_state_element(const fb_bd *bd, size_t i, size_t *component);
/* Initial state from the graph (fb_bg_set_initial), size nstates. */
void fb_bd_initial_state(const fb_bd *bd, double *x0);
size_t fb_bd_nblocks(const fb_bd *bd);

/* x' = F(t, x). Returns 0, >0 if a law asks for a smaller step, <0 on a
 * fatal failure (message in fb_bd_last_error). */
int fb_bd_rhs(fb_bd *bd, double t, const double *x, double *xdot);
const char *fb_bd_last_error(const fb_bd *bd);

/* Where a non-finite value of the diagram at (t, x) starts, for messages.
 * fb_bd_rhs and the linearisations pass non-finite values on without
 * complaint (checking every block would tax the hot path); a caller that
 * sees one asks this function, which re-evaluates the diagram at (t, x)
 * block by block in evaluation order (folded constants first) and stops
 * at the first of:
 *   FB_NONFINITE_STATE: a state in x that is not finite;
 *   FB_NONFINITE_VALUE: a block whose output is not finite while all its
 *     inputs are: the value starts there;
 *   FB_NONFINITE_JACOBIAN (only when jacobian is nonzero, after every
 *     value was found finite): a Newton block whose linearisation is not
 *     finite at finite inputs.
 * It writes what it found into buf (size > 0), naming the element and its
 * block, the signal (fb_bd_aug_unknown_name's names) and the value, e.g.
 *   "Se 'grav_body' (source): e:grav_body->body = nan"
 *   "C 'k' (law 'root'): k.e = nan from finite inputs k.q = -0.01"
 *   "C 'k' (law 'root'): d k.e / d k.q = inf at finite inputs k.q = 0"
 *   "state Ms.p = inf"
 * (input values are listed for up to 4 input components).
 * and returns the kind; FB_NONFINITE_NONE with buf "" if every value is
 * finite, or if a block failed (fb_bd_last_error says which). */
typedef enum fb_bd_nonfinite_kind {
  FB_NONFINITE_NONE,
  FB_NONFINITE_STATE,
  FB_NONFINITE_VALUE,
  FB_NONFINITE_JACOBIAN
} fb_bd_nonfinite_kind;
fb_bd_nonfinite_kind fb_bd_explain_nonfinite(fb_bd *bd, double t, const double *x, int jacobian,
                                             char *buf, size_t size);

/* Probe outputs, one column each (vector probes expanded). */
size_t fb_bd_noutputs(const fb_bd *bd);
const char *fb_bd_output_name(const fb_bd *bd, size_t i);
const char *fb_bd_output_unit(const fb_bd *bd, size_t i);
/* Evaluates the diagram at (t, x) and writes the outputs to y. */
int fb_bd_outputs(fb_bd *bd, double t, const double *x, double *y);

/* Augmented sparse linearisation (see above). The pattern is fixed at
 * build: nnz triplets (rows[k], cols[k]) into the nz x nz matrix P. */
size_t fb_bd_aug_size(const fb_bd *bd);
size_t fb_bd_aug_nnz(const fb_bd *bd);
void fb_bd_aug_pattern(fb_bd *bd, size_t *rows, size_t *cols);
/* Values at (t, x): P(gamma)[rows[k], cols[k]] += v0[k] + gamma * v1[k]
 * (duplicates are summed). Returns as fb_bd_rhs. */
int fb_bd_aug_values(fb_bd *bd, double t, const double *x, double *v0, double *v1);
/* unit[r] = 1 where row r of P has the constant coefficient 1 on z_r
 * (every block's output row except a linear solve's M y = u, and an
 * integrator fed by its own state): z_r is defined explicitly by the
 * other unknowns and can be eliminated first; 0 elsewhere. unit has
 * fb_bd_aug_size entries. */
void fb_bd_aug_unit_rows(const fb_bd *bd, unsigned char *unit);
/* Name of unknown z_i, i < fb_bd_aug_size, into buf: its signal's name
 * ("e:susp_LF.b_spring", "hull.body.p"), with "[k]" (1-based) for a
 * component of a vector signal; for messages. */
void fb_bd_aug_unknown_name(const fb_bd *bd, size_t i, char *buf, size_t size);
/* Index in z of state i, for i < nstates. */
size_t fb_bd_state_row(const fb_bd *bd, size_t i);
/* 1 if every block of the Newton subsystem (those the state derivatives
 * depend on) is linear and time-invariant: P0 and P1 are constant. A
 * nonlinear output probe (a power's product) does not count. */
int fb_bd_is_linear(const fb_bd *bd);

/* ---- Switched laws (hybrid elements, see fb_law_ops in flexbond/bg.h).
 * The guards of every switched law the diagram evaluates form one vector
 * g(t, x), which an integrator watches for zero crossings. Each law's
 * mode is part of the diagram's state between calls: 0 after
 * fb_bd_build, then whatever fb_bd_sync_modes and fb_bd_switch_modes
 * chose; fb_bd_rhs, fb_bd_outputs and the linearisations use the
 * current modes. These functions return as fb_bd_rhs (0, >0, <0, with
 * fb_bd_last_error). */
size_t fb_bd_nguards(const fb_bd *bd);
/* Name of the element whose law owns guard i, NULL if i >= nguards. */
const char *fb_bd_guard_element(const fb_bd *bd, size_t i);
/* Evaluates the diagram at (t, x) and writes the guards to g. */
int fb_bd_guards(fb_bd *bd, double t, const double *x, double *g);
/* Makes the modes consistent with (t, x), where a run starts or restarts
 * (the start, a breakpoint whose input jump may move a guard across zero
 * without any crossing to locate): every law chooses its mode from its
 * guards' signs, where a guard that is exactly zero takes the sign it has
 * just after t (at t + dt along x + dt F(t, x), dt = 1e-8 max(1, |t|),
 * as CVODE's own root-finding decides which way a zero guard moves). The
 * choice is repeated until no mode changes, so a law whose inputs depend
 * on another switched law sees that law's new mode; -1 (fatal) if the
 * modes do not settle within 16 rounds. *changed = 1 if a mode changed. */
int fb_bd_sync_modes(fb_bd *bd, double t, const double *x, int *changed);
/* At an event at (t, x): crossed[i] is +1 or -1 where guard i has just
 * crossed zero upwards or downwards, 0 elsewhere. The modes are chosen as
 * by fb_bd_sync_modes, except that a crossed guard counts with the sign
 * of its crossing whatever its value at the root (a root is located only
 * to a tolerance); *changed = 1 if a mode changed. */
int fb_bd_switch_modes(fb_bd *bd, double t, const double *x, const int *crossed, int *changed);
/* 1 if the Newton subsystem is linear within each combination of modes
 * (every block linear, or a switched law with affine branches): P0 and
 * P1 then change only when a mode does. */
int fb_bd_is_piecewise_linear(const fb_bd *bd);

/* Dense Jacobian dF/dx at (t, x), column-major nstates x nstates, by
 * forward propagation of each unit vector through the blocks' exact
 * linearisations (no finite differences). For linear analysis. */
int fb_bd_jacobian_dense(fb_bd *bd, double t, const double *x, double *jac, fb_err *err);

/* The eigenvalues of bd's state equations linearised at (t, x)
 * (fb_bd_jacobian_dense), from LAPACK's dgeev (src/bd/eigen.c): `flexbond
 * eig`'s table and the Python package's. A backward-stable solver finds a
 * zero eigenvalue anywhere within n eps ||A||_F of 0 (zero_tol): those
 * are counted and left out. */
typedef struct fb_bd_eigen {
  size_t nstates;  /* the diagram's, n */
  size_t n;        /* eigenvalues kept, |lambda| > zero_tol */
  double *re, *im; /* n each, owned: by |imaginary part|, then real part, a
                      complex pair's positive member first */
  double zero_tol; /* n eps ||A||_F, 1/s */
} fb_bd_eigen;

/* The eigenvalues of bd at time t and state x (nstates values; NULL: the
 * diagram's initial state, fb_bd_initial_state). what names the analysis
 * in messages ("eig: quarter_car"). FB_ENOMEM, before anything is
 * allocated, when the solve is beyond FB_DENSE_EIG_MAX or its two n x n
 * matrices beyond memory_limit bytes (0: none); FB_ESOLVER for a
 * non-finite Jacobian or a failed QR algorithm. No state: *out has none.
 * *out is new (fb_bd_eigen_free). */
int fb_bd_eigen_new(fb_bd *bd, double t, const double *x, size_t memory_limit, const char *what,
                    fb_bd_eigen **out, fb_err *err);
void fb_bd_eigen_free(fb_bd_eigen **e);

/* ---- Descriptor form of a linear diagram.
 *
 * The augmented linearisation above already is a descriptor system over
 * the signals z: the rows of state i say x_i' = (its integrator's input),
 * the other rows are the blocks' algebraic relations. Written as
 *     E z' = A z + B u(t) + f,      y = C z + D u,
 * E is the identity at the state rows and zero elsewhere and A = E - P0 - P1
 * over the augmented pattern. The first nstates variables are the states
 * (fb_bd_state_name order; FB_STATE_PROBE ones are the integrals of
 * integrating probes), then the diagram's other signals in z (index i of
 * fb_bd_aug_pattern is variable i), then the signals only the outputs use.
 * Sources of constant time functions are folded into f; every component
 * of every other source that the states or outputs depend on is an input
 * u_j, whose source row reads
 * 0 = -z_s + u_j (B holds a 1 there). D is zero: the outputs read
 * variables only. An output measuring a power e .* f (FB_PROBE_POWER, a
 * product, not linear) takes two rows of C, its effort (times the probe's
 * gain) and its flow: the output is the product of those two rows.
 *
 * The pencil (A, E) has index 1: its finite generalised eigenvalues are the
 * eigenvalues of fb_bd_jacobian_dense. */
typedef struct fb_descriptor {
  size_t n;               /* descriptor variables (rows and columns of E and A) */
  size_t nstates;         /* the first nstates variables are differential */
  size_t ninputs;         /* columns of B and D */
  size_t noutputs;        /* fb_bd_noutputs */
  size_t nrows_c;         /* rows of C and D: one per output, two per power output */
  fb_mat *E, *A;          /* n x n, sparse */
  fb_mat *B;              /* n x ninputs, sparse */
  fb_mat *f;              /* n x 1, sparse */
  fb_mat *C, *D;          /* nrows_c x n and nrows_c x ninputs, sparse */
  char **var_names;       /* n: state names, then signal names ("e:bond[k]") */
  char **input_names;     /* ninputs: the source element's name, "[k]" if a vector */
  size_t *input_var;      /* ninputs: the variable each input defines */
  size_t *output_row;     /* noutputs: the output's (first) row of C */
  int *output_is_product; /* noutputs: 1 if it is row * (row + 1) */
  int linearised;         /* 1: fb_bd_descriptor_at's linearisation */
} fb_descriptor;

/* Builds the descriptor form of bd (*out is new, free it with
 * fb_descriptor_free). Every block that the states or the outputs depend
 * on must be linear and time-invariant (power outputs aside, see above),
 * so the result does not depend on t or x: FB_EINVAL naming the first
 * block that is not (a nonlinear law, an integrated power probe). */
int fb_bd_descriptor(fb_bd *bd, fb_descriptor **out, fb_err *err);
/* The same for a diagram with nonlinear blocks, linearised at time t and
 * state x (bd's nstates values; the switched laws in the modes bd holds):
 * every block contributes its Jacobian there, and the variables, inputs
 * and outputs are deviations from their values at (t, x), so f is zero
 * (ds->linearised is 1). For a linear diagram the matrices are
 * fb_bd_descriptor's. A power output stays split into its two rows. */
int fb_bd_descriptor_at(fb_bd *bd, double t, const double *x, fb_descriptor **out, fb_err *err);
/* Frees *d and sets it to NULL; accepts NULL and *d == NULL. */
void fb_descriptor_free(fb_descriptor **d);

/* Frequency response of ds: for each frequency freq_hz[k] (Hz, >= 0) and
 * each of ncases input cases, the steady-state output amplitudes
 * Y = C (j omega E - A)^-1 B U + D U for the complex input amplitudes U
 * that input(ctx, omega, u) writes for omega = 2 pi freq_hz[k]: ninputs
 * complex values per case, interleaved real and imaginary parts, case
 * after case (u[2 (c ninputs + j)] is the real part of input j in case
 * c). h gets 2 nrows_c ncases nfreq values the same way, frequency after
 * frequency: h[2 ((k ncases + c) nrows_c + r)] is the real part of row r
 * of C. A power output's two rows are its effort's and its flow's
 * amplitudes. FB_EINVAL for a frequency that is not a number from 0 to
 * FB_FREQ_MAX_HZ; FB_ESOLVER naming the frequency where j omega E - A is
 * singular or the response is not finite. */
/* The highest frequency a response is computed at: 1 GHz, six decades
 * above anything a vehicle's structure answers; it keeps omega = 2 pi f
 * and omega E far from overflow (a frequency of 1e308 Hz made them inf). */
#define FB_FREQ_MAX_HZ 1e9
typedef void (*fb_freq_input_fn)(void *ctx, double omega, double *u);
int fb_descriptor_freq_response(const fb_descriptor *ds, const double *freq_hz, size_t nfreq,
                                size_t ncases, fb_freq_input_fn input, void *ctx, double *h,
                                fb_err *err);

/* Breakpoints of all sources, sorted and unique, written to bp (at most
 * max), earliest first; returns how many were written (0 when out of
 * memory). With bp == NULL, returns an upper bound of their number. */
size_t fb_bd_breakpoints(const fb_bd *bd, double *bp, size_t max);

/* Graphviz DOT of the diagram, one cluster per subsystem. */
int fb_bd_write_dot(const fb_bd *bd, FILE *fp, fb_err *err);
/* Graphviz DOT of the diagram in two levels, as the paper's Fig. 6
 * (docs/diagrams.md): the top level ("cluster_top") has one block per
 * subsystem instance of the graph, the blocks of the top-level elements
 * (a composite's mux and demux) and one meter per probed signal (the
 * outputs' names and units); one level down, a cluster per instance holds
 * its blocks (nested instances nested), with an in-port for each signal it
 * takes from outside and an out-port for each it gives. Instances whose
 * blocks and inner wiring are alike (six suspensions) are drawn once, the
 * cluster naming them all. Every signal is one edge labelled with its
 * dimension "[n]", never one per component. Names pass fb_dot_write_text.
 * FB_EIO on a write error, FB_ENOMEM. */
int fb_bd_write_dot_hierarchy(const fb_bd *bd, FILE *fp, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
