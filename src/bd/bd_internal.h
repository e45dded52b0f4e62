/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal layout of block diagrams. */
#ifndef FLEXBOND_BD_INTERNAL_H
#define FLEXBOND_BD_INTERNAL_H

#include <stddef.h>

#include "flexbond/bd.h"

#include "bg/bg_internal.h"

typedef struct bd_block bd_block;

/* A block kind, as a SUNDIALS module is one: each kind (src/bd/kind_*.c)
 * keeps its own data in the block's content and gives the diagram its
 * operations and properties here, so that no code outside a kind asks
 * which kind a block is. Functions return 0, >0 recoverable, <0 fatal. */
typedef struct bd_block_ops {
  const char *kind; /* "gain", for messages */
  /* ---- Properties. */
  /* The output is a state x (an integrator): there is no eval, the
   * diagram copies x in and reads x' from input 0, and the rows are
   * d(x) - gamma d(x'). */
  int state;
  /* 1 if the values of its rows never change (linear, time-invariant). */
  int linear;
  /* 1 if each of its rows has the coefficient 1 on its own output
   * component and 0 on the others (B = I in B d(out) - A d(in) = 0). */
  int unit_rows;
  /* The output is a function of time alone: an input u of the
   * descriptor form (fb_bd_descriptor). */
  int exogenous;
  /* The output is in_0 .* in_1 (a power e .* f): a descriptor gives it,
   * at an output, as its two factors. */
  int product;
  /* 1 if its jvp and rows are exact only where its inputs are related as
   * the diagram relates them, not at any signals: an energy's co-variable
   * (input 1) is the gradient of the energy at its state (input 0), which
   * its linearisation uses. */
  int consistent_inputs;
  /* Drawn instead of the block's label ("1/s"); NULL: the label. */
  const char *symbol;
  /* Messages name the block "noun 'label'" (a law: "law 'quadratic'");
   * NULL: by its label alone. */
  const char *label_noun;
  /* ---- Operations. */
  /* Writes the output from the inputs (w holds every signal). NULL for a
   * state. */
  int (*eval)(bd_block *b, double t, double *w);
  /* dw[out] = (d out / d in) dw[in], at the signals w. */
  int (*jvp)(bd_block *b, const double *w, double *dw);
  /* Number of triplets of the block's rows in the augmented matrix. */
  size_t (*nnz)(const bd_block *b);
  /* Writes rows, cols (when rows != NULL) and values v0, v1 of its
   * triplets at the signals w. */
  int (*jac)(bd_block *b, const double *w, size_t *rows, size_t *cols, double *v0, double *v1);
  /* Frees the content; NULL when the kind has none. */
  void (*free)(void *content);
  /* The dimension input k must have; FB_NONE for any. NULL: the output's. */
  size_t (*input_dim)(const bd_block *b, size_t k);
  /* 1 if the output changes with t at fixed inputs. NULL: never. */
  int (*time_varying)(const bd_block *b);
  /* Writes at most max of the times where the output is not smooth to bp
   * and returns how many it wrote; with bp == NULL, returns an upper bound
   * of their number. NULL: none. */
  size_t (*breakpoints)(const bd_block *b, double *bp, size_t max);
  /* 1 if its rows change only when its mode does. NULL: as linear. */
  int (*piecewise_linear)(const bd_block *b);
  /* ---- Switched kinds (modes and guards, see fb_law_ops); NULL for the
   * others. */
  size_t (*nguards)(const bd_block *b);
  /* The guards at w, in the current mode, into g[0 .. nguards). */
  int (*guards)(bd_block *b, const double *w, double *g);
  /* Moves to the mode that the guard signs sign choose at w (as
   * fb_law_ops.switch_mode); *changed = 1 if the mode changed. */
  int (*switch_mode)(bd_block *b, const double *w, const int *sign, int *changed);
} bd_block_ops;

/* What a block input refers to: a signal; during construction a bond
 * variable 2*bond + (flow ? 1 : 0), or the state of an element (the
 * modulating inputs of a law, known once every storage element has its
 * integrator), until fb_bd_build resolves them into signals. */
typedef enum bd_ref { BD_REF_SIGNAL, BD_REF_VAR, BD_REF_STATE } bd_ref;

typedef struct bd_input {
  size_t id;
  bd_ref ref;
} bd_input;

/* Wiring, geometry and origin are the diagram's, not the kind's: build,
 * layout, scheduling and the pictures treat every block alike through
 * these fields, and a kind reads its inputs and writes its output
 * through them. Everything else a kind needs is in its content. */
struct bd_block {
  const bd_block_ops *ops;
  void *content; /* the kind's own data, NULL if it needs none */
  bd_input *in;
  size_t nin;
  size_t out;          /* output signal */
  size_t *ioff, *idim; /* input offsets in w and dimensions (after layout) */
  size_t ooff, odim;   /* output offset in w and dimension */
  size_t elem;         /* origin element (FB_NONE for probes) */
  char *label;         /* for DOT and messages */
};

/* The number of guards of block b (0 unless it is switched). */
static inline size_t fb_bd_block_nguards(const bd_block *b)
{
  return b->ops->nguards ? b->ops->nguards(b) : 0;
}

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
  size_t *dyn_order; /* the part of order that the state derivatives depend on */
  size_t ndyn_order;
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

/* Evaluation order: topological, integrators cut the cycles. FB_ECAUSAL
 * with the zero-order causal path on an algebraic loop. */
int fb_bd_schedule(fb_bd *bd, fb_err *err);
/* Evaluates the blocks of constant inputs once into w and drops them
 * from the evaluation order; finds the blocks the outputs depend on. */
int fb_bd_fold_constants(fb_bd *bd, fb_err *err);
/* Finds the Newton subsystem and the pattern of its augmented matrix. */
int fb_bd_prepare_newton(fb_bd *bd, fb_err *err);
/* Finds the switched laws among the Newton blocks and lays out their
 * guards. */
int fb_bd_prepare_switching(fb_bd *bd, fb_err *err);
/* Evaluates every block at (t, x); 0, >0 recoverable, <0 fatal. */
int fb_bd_eval(fb_bd *bd, double t, const double *x);
/* As fb_bd_eval for the blocks the state derivatives depend on, which
 * include every switched law (they are Newton blocks). */
int fb_bd_eval_dynamics(fb_bd *bd, double t, const double *x);

#endif
