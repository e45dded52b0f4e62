/* Internal layout of block diagrams. */
#ifndef FLEXBOND_BD_INTERNAL_H
#define FLEXBOND_BD_INTERNAL_H

#include <stddef.h>

#include "flexbond/bd.h"

#include "bg/bg_internal.h"

typedef struct bd_block bd_block;

/* A block kind (SUNDIALS-style ops table, one static const per kind). */
typedef struct bd_block_ops {
  const char *kind;
  /* Writes the output from the inputs (w holds every signal). Returns 0,
   * >0 recoverable, <0 fatal. NULL for integrators (their output is the
   * state). */
  int (*eval)(bd_block *b, double t, double *w);
  /* dw[out] = (d out / d in) dw[in], at the signals w. */
  int (*jvp)(bd_block *b, const double *w, double *dw);
  /* Number of triplets of the block's rows in the augmented matrix. */
  size_t (*nnz)(const bd_block *b);
  /* Writes rows, cols (when rows != NULL) and values v0, v1 of its
   * triplets at the signals w. */
  int (*jac)(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0, double *v1);
  int linear; /* 1 if jac values never change */
} bd_block_ops;

/* Block input: an alias-resolved signal id. During construction inputs
 * refer to bond variables (effort or flow of a bond), resolved later. */
typedef struct bd_input {
  size_t id;
  int is_var; /* id is a variable 2*bond + (flow ? 1 : 0) until resolved */
} bd_input;

struct bd_block {
  const bd_block_ops *ops;
  bd_input *in;
  size_t nin;
  size_t out;          /* output signal */
  size_t *ioff, *idim; /* input offsets in w and dimensions (after layout) */
  size_t ooff, odim;   /* output offset in w and dimension */
  double *coef;        /* SUM coefficients, MUX/SELECT signs (per input) */
  fb_mat *mat;         /* GAIN/SOLVE matrix (owned if owns_mat) */
  int owns_mat;
  fb_lu *lu;             /* SOLVE factorisation (owned) */
  double *work;          /* scratch, size of the output or law Jacobian */
  size_t offset;         /* SELECT: first component */
  fb_tfun *const *fns;   /* SOURCE: borrowed time functions */
  const fb_law_ops *law; /* LAW/ENERGY: nonlinear law */
  void *law_ctx;
  int mode;    /* LAW: active branch of a switched law */
  double *xu;  /* LAW: the gathered inputs of a modulated law */
  size_t elem; /* origin element (FB_NONE for probes) */
  char *label; /* for DOT and messages */
};

typedef struct bd_signal {
  size_t dim;
  size_t off;      /* offset in the signal vector w */
  size_t producer; /* block index */
  char *name;      /* e.g. "e:b3", "f:b3", "Ms.p" */
} bd_signal;

typedef struct bd_output {
  char *name;
  char *unit;
  size_t signal;
  size_t comp;
  double gain;
} bd_output;

struct fb_bd {
  fb_bg *bg;
  bd_block *blocks;
  size_t nblocks, cap_blocks;
  bd_signal *sigs;
  size_t nsigs, cap_sigs;
  size_t *order; /* evaluation order of the varying non-integrator blocks */
  size_t norder;
  size_t *out_order; /* the part of order that the outputs depend on */
  size_t nout_order;
  size_t *integ; /* integrator blocks, in state order */
  size_t ninteg;
  size_t nstates; /* = total dimension of integrator outputs */
  size_t nw;      /* signal vector length */
  double *w, *dw; /* signal values and perturbations */
  double *x0;
  char **state_names;
  size_t *state_elem; /* per state: owning element, FB_NONE for probes */
  size_t *state_comp; /* per state: component within the element */
  bd_output *outs;
  size_t nouts, cap_outs;
  /* Newton subsystem: the integrators and the varying blocks upstream of
   * their inputs; its signals, numbered z (states first), are the
   * unknowns of the augmented matrix. */
  unsigned char *is_const; /* per block: folded constant */
  size_t *zmap;            /* per w entry: index in z, FB_NONE if not there */
  size_t nz;
  size_t *newton_blocks; /* blocks with rows in the augmented matrix */
  size_t nnewton;
  size_t full_nnz;       /* their triplets before dropping constant columns */
  unsigned char *keep;   /* per such triplet: 1 if kept */
  size_t aug_nnz;        /* kept triplets */
  size_t *srows, *scols; /* scratch, full_nnz each */
  double *sv0, *sv1;
  int linear;
  size_t *var_sig;    /* per bond variable: signal id or FB_NONE */
  size_t *var_alias;  /* per bond variable: aliased variable or FB_NONE */
  size_t *elem_state; /* per element: state signal of I/C fields, else FB_NONE */
  size_t *elem_co;    /* per element: its co-variable signal (f of I, e of C) */
  /* Switched laws: their blocks, and the first of their guards in the
   * diagram's guard vector. */
  size_t *switched, *guard_off;
  size_t nswitched, nguards;
  double *guard_now, *guard_ahead, *x_ahead; /* scratch of fb_bd_sync_modes */
  int *guard_sign;
  int piecewise_linear; /* linear within each mode of the switched laws */
  char errbuf[512];
};

extern const bd_block_ops fb_bd_integrator_ops, fb_bd_source_ops, fb_bd_gain_ops,
    fb_bd_solve_ops, fb_bd_sum_ops, fb_bd_mux_ops, fb_bd_select_ops, fb_bd_product_ops,
    fb_bd_law_ops, fb_bd_energy_ops;

/* Evaluation order: topological, integrators cut the cycles. FB_ECAUSAL
 * with the zero-order causal path on an algebraic loop. */
int fb_bd_schedule(fb_bd *bd, fb_err *err);
/* Evaluates the blocks of constant inputs once into w and drops them
 * from the evaluation order; finds the blocks the outputs depend on. */
int fb_bd_fold_constants(fb_bd *bd, fb_err *err);
/* Finds the Newton subsystem and the pattern of its augmented matrix. */
int fb_bd_prepare_newton(fb_bd *bd, fb_err *err);
/* The inputs of law block b at the signals w, as its law sees them. */
void fb_bd_law_input(bd_block *b, const double *w, fb_law_in *in);
/* Finds the switched laws among the Newton blocks and lays out their
 * guards. */
int fb_bd_prepare_switching(fb_bd *bd, fb_err *err);
/* Evaluates every block at (t, x); 0, >0 recoverable, <0 fatal. */
int fb_bd_eval(fb_bd *bd, double t, const double *x);

#endif
