/* SPDX-License-Identifier: BSD-3-Clause */
/* Descriptor form E z' = A z + B u + f, y = C z + D u of a linear block
 * diagram (see flexbond/bd.h).
 *
 * The blocks already write their rows of the augmented Newton matrix
 * P(gamma) = P0 + gamma P1 (bd/kinds.h): an integrator's row is
 * dx - gamma dx' (v0 = 1 on x, v1 = -1 on its input), every other block's
 * rows are its linear law B d(out) - sum_k A_k d(in_k) = 0 (v1 = 0). A
 * backward Euler step of E z' = A z is (E - gamma A) z_new = E z_old with
 * the algebraic rows divided by gamma, which is P(gamma) for E = P0 at
 * the state rows (zero elsewhere) and A = E - P0 - P1: the same triplets
 * give E and A. What the Newton matrix leaves out is added here: the
 * folded constants its rows read (into f), the time-varying sources'
 * values (into B) and the blocks only the outputs depend on (appended
 * variables, so that every output is a row of C). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bd/bd_internal.h"
#include "core/util.h"

/* What a block contributes to the descriptor. */
typedef enum desc_role {
  ROLE_NONE,       /* nothing (or only its inputs, for a split power output) */
  ROLE_NEWTON,     /* rows of the augmented matrix, variables z */
  ROLE_OUTPUT,     /* a varying block only the outputs depend on */
  ROLE_CONSTANT,   /* a folded constant an output reads: 0 = -z + value */
  ROLE_SPLIT_POWER /* product e .* f at an output: exported as e and f */
} desc_role;

/* Triplets of one sparse matrix, with room reserved in advance. */
typedef struct trips {
  size_t *rows, *cols;
  double *vals;
  size_t n;
} trips;

typedef struct desc_build {
  fb_bd *bd;
  unsigned char *role; /* desc_role per block */
  size_t *vmap;        /* per entry of w: descriptor variable, FB_NONE if none */
  size_t n;            /* variables numbered so far */
  size_t ninputs;
  double *f; /* dense right-hand side, n entries */
  trips e, a, b, c;
  int linearise;         /* 1: nonlinear blocks give their Jacobians at bd->w */
  size_t *jrows, *jcols; /* one block's triplets (largest block) */
  double *jv0, *jv1;
} desc_build;

static int trips_alloc(trips *t, size_t cap)
{
  t->n = 0;
  t->rows = malloc((cap + 1) * sizeof *t->rows);
  t->cols = malloc((cap + 1) * sizeof *t->cols);
  t->vals = malloc((cap + 1) * sizeof *t->vals);
  return t->rows && t->cols && t->vals ? FB_OK : FB_ENOMEM;
}

static void trips_free(trips *t)
{
  free(t->rows);
  free(t->cols);
  free(t->vals);
}

/* Appends (r, c, v); the caller reserved the room. Zeros are left out by
 * fb_mat_new_triplets. */
static void trips_put(trips *t, size_t r, size_t c, double v)
{
  t->rows[t->n] = r;
  t->cols[t->n] = c;
  t->vals[t->n++] = v;
}

static size_t producer_of(const fb_bd *bd, size_t sig)
{
  return bd->sigs[sig].producer;
}

/* Marks the blocks the outputs depend on beyond the Newton subsystem:
 * varying ones (ROLE_OUTPUT), folded constants (ROLE_CONSTANT) and power
 * products read by an output only (ROLE_SPLIT_POWER, their inputs
 * followed instead). stack holds 2 nouts + the total of inputs. */
static void mark_output_blocks(desc_build *d, size_t *stack)
{
  const fb_bd *bd = d->bd;
  size_t top = 0;
  for (size_t o = 0; o < bd->nouts; ++o) {
    size_t i = producer_of(bd, bd->outs[o].signal);
    const bd_block *b = &bd->blocks[i];
    if (b->ops->product && d->role[i] == ROLE_NONE && !bd->is_const[i]) {
      d->role[i] = ROLE_SPLIT_POWER;
      stack[top++] = producer_of(bd, b->in[0].id);
      stack[top++] = producer_of(bd, b->in[1].id);
    } else if (d->role[i] != ROLE_SPLIT_POWER) {
      stack[top++] = i;
    }
  }
  while (top) {
    size_t i = stack[--top];
    /* A power product that another output block reads is not split: it
     * becomes an ordinary (nonlinear, hence refused) block. */
    if (d->role[i] != ROLE_NONE && d->role[i] != ROLE_SPLIT_POWER)
      continue;
    if (bd->is_const[i]) {
      d->role[i] = ROLE_CONSTANT;
      continue;
    }
    d->role[i] = ROLE_OUTPUT;
    for (size_t k = 0; k < bd->blocks[i].nin; ++k)
      stack[top++] = producer_of(bd, bd->blocks[i].in[k].id);
  }
}

/* Roles of every block; FB_EINVAL naming the first nonlinear one that the
 * states or outputs depend on. */
static int assign_roles(desc_build *d, fb_err *err)
{
  fb_bd *bd = d->bd;
  size_t nedges = 0;
  for (size_t i = 0; i < bd->nblocks; ++i)
    nedges += bd->blocks[i].nin;
  size_t *stack = malloc((nedges + 2 * bd->nouts + 1) * sizeof *stack);
  if (!stack)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the descriptor form");
  for (size_t k = 0; k < bd->nnewton; ++k)
    d->role[bd->newton_blocks[k]] = ROLE_NEWTON;
  mark_output_blocks(d, stack);
  free(stack);
  for (size_t i = 0; i < bd->nblocks; ++i) {
    const bd_block *b = &bd->blocks[i];
    if (!d->linearise && (d->role[i] == ROLE_NEWTON || d->role[i] == ROLE_OUTPUT) &&
        !b->ops->linear) {
      const char *who = b->elem == FB_NONE ? "a probe" : bd->bg->elems[b->elem].name;
      return fb_err_set(err, FB_EINVAL,
                        "descriptor form: the diagram is not linear: block '%s' (%s) of %s, "
                        "computing '%s', is nonlinear (the descriptor form needs every block "
                        "that the states and outputs depend on to be linear, power outputs "
                        "aside)",
                        b->label, b->ops->kind, who, bd->sigs[b->out].name);
    }
  }
  return FB_OK;
}

/* Variables: z as numbered by the Newton matrix (states first), then the
 * outputs' extra signals in block order. */
static void number_variables(desc_build *d)
{
  const fb_bd *bd = d->bd;
  for (size_t k = 0; k < bd->nw; ++k)
    d->vmap[k] = bd->zmap[k];
  d->n = bd->nz;
  for (size_t i = 0; i < bd->nblocks; ++i) {
    const bd_block *b = &bd->blocks[i];
    if (d->role[i] != ROLE_OUTPUT && d->role[i] != ROLE_CONSTANT)
      continue;
    for (size_t c = 0; c < b->odim; ++c)
      d->vmap[b->ooff + c] = d->n++;
  }
}

/* Room for every triplet (one pass over the blocks with rows). */
static int reserve(desc_build *d, fb_err *err)
{
  const fb_bd *bd = d->bd;
  size_t na = 0, nb = 0, maxblk = 0;
  for (size_t i = 0; i < bd->nblocks; ++i) {
    const bd_block *b = &bd->blocks[i];
    if (d->role[i] == ROLE_CONSTANT)
      na += b->odim;
    if (d->role[i] != ROLE_NEWTON && d->role[i] != ROLE_OUTPUT)
      continue;
    size_t nnz = b->ops->nnz(b);
    na += nnz;
    maxblk = nnz > maxblk ? nnz : maxblk;
    if (b->ops->exogenous)
      nb += b->odim;
  }
  d->f = calloc(d->n + 1, sizeof *d->f);
  d->jrows = malloc((maxblk + 1) * sizeof *d->jrows);
  d->jcols = malloc((maxblk + 1) * sizeof *d->jcols);
  d->jv0 = malloc((maxblk + 1) * sizeof *d->jv0);
  d->jv1 = malloc((maxblk + 1) * sizeof *d->jv1);
  int rc = d->f && d->jrows && d->jcols && d->jv0 && d->jv1 ? FB_OK : FB_ENOMEM;
  if (!rc)
    rc = trips_alloc(&d->e, bd->nstates);
  if (!rc)
    rc = trips_alloc(&d->a, na);
  if (!rc)
    rc = trips_alloc(&d->b, nb);
  if (!rc)
    rc = trips_alloc(&d->c, 2 * bd->nouts);
  return rc ? fb_err_set(err, FB_ENOMEM, "out of memory building the descriptor form") : FB_OK;
}

/* Rows of block i: E gets v0 at the state rows, A gets E - v0 - v1; a
 * column outside the variables is a folded constant w[c], moved to f. A
 * time-varying source's row 0 = -z + u_j gets its input column in B. */
static int block_rows(desc_build *d, size_t i)
{
  fb_bd *bd = d->bd;
  bd_block *b = &bd->blocks[i];
  int rc = b->ops->jac(b, bd->w, d->jrows, d->jcols, d->jv0, d->jv1);
  if (rc)
    return rc;
  const int integ = b->ops->state;
  for (size_t k = 0, nnz = b->ops->nnz(b); k < nnz; ++k) {
    const size_t r = d->vmap[d->jrows[k]], c = d->vmap[d->jcols[k]];
    const double e = integ ? d->jv0[k] : 0.0, a = e - d->jv0[k] - d->jv1[k];
    if (c == FB_NONE) {
      d->f[r] += a * bd->w[d->jcols[k]];
      continue;
    }
    if (e != 0.0)
      trips_put(&d->e, r, c, e);
    trips_put(&d->a, r, c, a);
  }
  if (b->ops->exogenous)
    for (size_t c = 0; c < b->odim; ++c)
      trips_put(&d->b, d->vmap[b->ooff + c], d->ninputs++, 1.0);
  return FB_OK;
}

/* A folded constant read by an output: 0 = -z + value. */
static void constant_rows(desc_build *d, size_t i)
{
  const bd_block *b = &d->bd->blocks[i];
  for (size_t c = 0; c < b->odim; ++c) {
    const size_t r = d->vmap[b->ooff + c];
    trips_put(&d->a, r, r, -1.0);
    d->f[r] = d->bd->w[b->ooff + c];
  }
}

static int all_rows(desc_build *d, fb_err *err)
{
  for (size_t i = 0; i < d->bd->nblocks; ++i) {
    if (d->role[i] == ROLE_CONSTANT)
      constant_rows(d, i);
    if (d->role[i] != ROLE_NEWTON && d->role[i] != ROLE_OUTPUT)
      continue;
    if (block_rows(d, i))
      return fb_err_set(err, FB_EINVAL, "descriptor form: block '%s' (%s) has no linearisation",
                        d->bd->blocks[i].label, d->bd->blocks[i].ops->kind);
  }
  return FB_OK;
}

/* Rows of C: one per output (gain times its variable), two for a split
 * power output (gain times the effort, then the flow). */
static void output_rows(desc_build *d, fb_descriptor *ds)
{
  const fb_bd *bd = d->bd;
  size_t row = 0;
  for (size_t o = 0; o < bd->nouts; ++o) {
    const bd_output *out = &bd->outs[o];
    const bd_signal *s = &bd->sigs[out->signal];
    const bd_block *p = &bd->blocks[s->producer];
    ds->output_row[o] = row;
    if (d->role[s->producer] == ROLE_SPLIT_POWER) {
      ds->output_is_product[o] = 1;
      trips_put(&d->c, row++, d->vmap[p->ioff[0] + out->comp], out->gain);
      trips_put(&d->c, row++, d->vmap[p->ioff[1] + out->comp], 1.0);
    } else {
      ds->output_is_product[o] = 0;
      trips_put(&d->c, row++, d->vmap[s->off + out->comp], out->gain);
    }
  }
  ds->nrows_c = row;
}

/* "name" for a scalar signal, "name[k]" (1-based) for component c. */
static char *component_name(const char *name, size_t dim, size_t c)
{
  if (dim == 1)
    return fb_strdup(name);
  size_t len = strlen(name) + 24;
  char *s = malloc(len);
  if (s)
    snprintf(s, len, "%s[%zu]", name, c + 1);
  return s;
}

static int name_variables(const desc_build *d, fb_descriptor *ds)
{
  const fb_bd *bd = d->bd;
  ds->var_names = calloc(ds->n + 1, sizeof *ds->var_names);
  if (!ds->var_names)
    return FB_ENOMEM;
  for (size_t s = 0; s < bd->nsigs; ++s) {
    const bd_signal *sig = &bd->sigs[s];
    for (size_t c = 0; c < sig->dim; ++c) {
      const size_t v = d->vmap[sig->off + c];
      if (v != FB_NONE && !(ds->var_names[v] = component_name(sig->name, sig->dim, c)))
        return FB_ENOMEM;
    }
  }
  return FB_OK;
}

/* Inputs in the order block_rows numbered them: the time-varying sources
 * with rows, in block order. */
static int name_inputs(const desc_build *d, fb_descriptor *ds)
{
  const fb_bd *bd = d->bd;
  ds->input_names = calloc(ds->ninputs + 1, sizeof *ds->input_names);
  ds->input_var = malloc((ds->ninputs + 1) * sizeof *ds->input_var);
  if (!ds->input_names || !ds->input_var)
    return FB_ENOMEM;
  size_t j = 0;
  for (size_t i = 0; i < bd->nblocks; ++i) {
    const bd_block *b = &bd->blocks[i];
    if (!b->ops->exogenous || (d->role[i] != ROLE_NEWTON && d->role[i] != ROLE_OUTPUT))
      continue;
    for (size_t c = 0; c < b->odim; ++c, ++j) {
      ds->input_var[j] = d->vmap[b->ooff + c];
      ds->input_names[j] = component_name(bd->bg->elems[b->elem].name, b->odim, c);
      if (!ds->input_names[j])
        return FB_ENOMEM;
    }
  }
  return FB_OK;
}

/* The right-hand side f as an n x 1 sparse matrix. */
static int make_f(const desc_build *d, fb_descriptor *ds, fb_err *err)
{
  trips t;
  int rc = trips_alloc(&t, d->n);
  if (rc) {
    trips_free(&t);
    return fb_err_set(err, FB_ENOMEM, "out of memory building the descriptor form");
  }
  /* A linearisation's variables are deviations from the point: no
   * constant term. */
  for (size_t i = 0; !d->linearise && i < d->n; ++i)
    if (d->f[i] != 0.0)
      trips_put(&t, i, 0, d->f[i]);
  rc = fb_mat_new_triplets(d->n, 1, t.n, t.rows, t.cols, t.vals, &ds->f, err);
  trips_free(&t);
  return rc;
}

static int make_matrices(const desc_build *d, fb_descriptor *ds, fb_err *err)
{
  const size_t n = d->n;
  int rc = fb_mat_new_triplets(n, n, d->e.n, d->e.rows, d->e.cols, d->e.vals, &ds->E, err);
  if (!rc)
    rc = fb_mat_new_triplets(n, n, d->a.n, d->a.rows, d->a.cols, d->a.vals, &ds->A, err);
  if (!rc)
    rc = fb_mat_new_triplets(n, ds->ninputs, d->b.n, d->b.rows, d->b.cols, d->b.vals, &ds->B,
                             err);
  if (!rc)
    rc = fb_mat_new_triplets(ds->nrows_c, n, d->c.n, d->c.rows, d->c.cols, d->c.vals, &ds->C,
                             err);
  if (!rc)
    rc = fb_mat_new_triplets(ds->nrows_c, ds->ninputs, 0, NULL, NULL, NULL, &ds->D, err);
  if (!rc)
    rc = make_f(d, ds, err);
  return rc;
}

static void desc_build_free(desc_build *d)
{
  free(d->role);
  free(d->vmap);
  free(d->f);
  free(d->jrows);
  free(d->jcols);
  free(d->jv0);
  free(d->jv1);
  trips_free(&d->e);
  trips_free(&d->a);
  trips_free(&d->b);
  trips_free(&d->c);
}

static int build(desc_build *d, fb_descriptor *ds, fb_err *err)
{
  const fb_bd *bd = d->bd;
  d->role = calloc(bd->nblocks + 1, sizeof *d->role);
  d->vmap = malloc((bd->nw + 1) * sizeof *d->vmap);
  ds->output_row = malloc((bd->nouts + 1) * sizeof *ds->output_row);
  ds->output_is_product = malloc((bd->nouts + 1) * sizeof *ds->output_is_product);
  if (!d->role || !d->vmap || !ds->output_row || !ds->output_is_product)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the descriptor form");
  int rc = assign_roles(d, err);
  if (rc)
    return rc;
  number_variables(d);
  rc = reserve(d, err);
  if (!rc)
    rc = all_rows(d, err);
  if (rc)
    return rc;
  ds->n = d->n;
  ds->nstates = bd->nstates;
  ds->ninputs = d->ninputs;
  ds->noutputs = bd->nouts;
  output_rows(d, ds);
  if (name_variables(d, ds) || name_inputs(d, ds))
    return fb_err_set(err, FB_ENOMEM, "out of memory building the descriptor form");
  return make_matrices(d, ds, err);
}

static int descriptor(fb_bd *bd, int linearise, fb_descriptor **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "descriptor form: output pointer is NULL");
  *out = NULL;
  if (!bd)
    return fb_err_set(err, FB_EINVAL, "descriptor form: block diagram is NULL");
  fb_descriptor *ds = calloc(1, sizeof *ds);
  if (!ds)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the descriptor form");
  desc_build d;
  memset(&d, 0, sizeof d);
  d.bd = bd;
  d.linearise = linearise;
  int rc = build(&d, ds, err);
  desc_build_free(&d);
  if (rc) {
    fb_descriptor_free(&ds);
    return rc;
  }
  ds->linearised = linearise;
  *out = ds;
  return FB_OK;
}

int fb_bd_descriptor(fb_bd *bd, fb_descriptor **out, fb_err *err)
{
  return descriptor(bd, 0, out, err);
}

int fb_bd_descriptor_at(fb_bd *bd, double t, const double *x, fb_descriptor **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "descriptor form: output pointer is NULL");
  *out = NULL;
  if (!bd || !x)
    return fb_err_set(err, FB_EINVAL, "descriptor form: NULL argument");
  /* Evaluating the right-hand side leaves every signal at (t, x) in w,
   * where the blocks' Jacobians are taken. */
  double *xdot = malloc((bd->nstates + 1) * sizeof *xdot);
  if (!xdot)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the descriptor form");
  int rc = fb_bd_rhs(bd, t, x, xdot);
  free(xdot);
  if (rc)
    return fb_err_set(err, rc, "descriptor form: the diagram cannot be evaluated at t = %g s",
                      t);
  return descriptor(bd, 1, out, err);
}

static void free_names(char **names, size_t n)
{
  for (size_t i = 0; names && i < n; ++i)
    free(names[i]);
  free(names);
}

void fb_descriptor_free(fb_descriptor **dp)
{
  if (!dp || !*dp)
    return;
  fb_descriptor *d = *dp;
  fb_mat_free(&d->E);
  fb_mat_free(&d->A);
  fb_mat_free(&d->B);
  fb_mat_free(&d->f);
  fb_mat_free(&d->C);
  fb_mat_free(&d->D);
  free_names(d->var_names, d->n);
  free_names(d->input_names, d->ninputs);
  free(d->input_var);
  free(d->output_row);
  free(d->output_is_product);
  free(d);
  *dp = NULL;
}
