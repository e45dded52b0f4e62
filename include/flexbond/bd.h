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
/* Index in z of state i, for i < nstates. */
size_t fb_bd_state_row(const fb_bd *bd, size_t i);
/* 1 if every block is linear and time-invariant (P0, P1 are constant). */
int fb_bd_is_linear(const fb_bd *bd);

/* Dense Jacobian dF/dx at (t, x), column-major nstates x nstates, by
 * forward propagation of each unit vector through the blocks' exact
 * linearisations (no finite differences). For linear analysis. */
int fb_bd_jacobian_dense(fb_bd *bd, double t, const double *x, double *jac, fb_err *err);

/* Breakpoints of all sources, sorted and unique, written to bp (at most
 * max), earliest first; returns how many were written (0 when out of
 * memory). With bp == NULL, returns an upper bound of their number. */
size_t fb_bd_breakpoints(const fb_bd *bd, double *bp, size_t max);

/* Graphviz DOT of the diagram, one cluster per subsystem. */
int fb_bd_write_dot(const fb_bd *bd, FILE *fp, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
