/* SPDX-License-Identifier: BSD-3-Clause */
/* From a causal bond graph to a block diagram (Ferreira & Da Silva, COBEM
 * 2005): every element, in its assigned causality, becomes the blocks that
 * compute its output efforts and flows from its inputs. Junctions make
 * aliases (equal efforts at a 0-junction, equal flows at a 1-junction) and
 * one signed sum. */
#include <assert.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bd/kinds.h"

#define VAR_E(b) (2 * (b))
#define VAR_F(b) (2 * (b) + 1)

static int new_signal(fb_bd *bd, size_t dim, const char *name, size_t producer, size_t *id,
                      fb_err *err)
{
  *id = SIZE_MAX; /* defined on failure too, so no caller reads an indeterminate index */
  if (fb_grow((void **)&bd->sigs, &bd->cap_sigs, bd->nsigs, sizeof *bd->sigs))
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  bd_signal *s = &bd->sigs[bd->nsigs];
  memset(s, 0, sizeof *s);
  s->dim = dim;
  s->producer = producer;
  s->name = fb_strdup(name);
  if (!s->name)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  *id = bd->nsigs++;
  return FB_OK;
}

/* Adds a block of the given kind (its content taken over, freed on
 * failure too) with nin inputs and an output signal of dimension odim
 * named signame; returns its index in *id (SIZE_MAX when no block was
 * added). */
static int new_block(fb_bd *bd, bd_kind kind, size_t nin, size_t odim, size_t elem,
                     const char *label, const char *signame, size_t *id, fb_err *err)
{
  *id = SIZE_MAX;
  if (fb_grow((void **)&bd->blocks, &bd->cap_blocks, bd->nblocks, sizeof *bd->blocks)) {
    if (kind.ops->free)
      kind.ops->free(kind.content);
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  }
  bd_block *b = &bd->blocks[bd->nblocks];
  memset(b, 0, sizeof *b);
  b->ops = kind.ops;
  b->content = kind.content;
  b->nin = nin;
  b->elem = elem;
  b->odim = odim;
  /* Counted at once, so that fb_bd_free releases the content whatever
   * fails next. */
  size_t bid = bd->nblocks++;
  b->in = calloc(nin + 1, sizeof *b->in);
  b->label = fb_strdup(label);
  if (!b->in || !b->label)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  int rc = new_signal(bd, odim, signame, bid, &bd->blocks[bid].out, err);
  *id = bid;
  return rc;
}

static void set_input_var(fb_bd *bd, size_t blk, size_t k, size_t var)
{
  bd->blocks[blk].in[k] = (bd_input){var, BD_REF_VAR};
}

static void set_input_sig(fb_bd *bd, size_t blk, size_t k, size_t sig)
{
  bd->blocks[blk].in[k] = (bd_input){sig, BD_REF_SIGNAL};
}

static size_t out_sig(const fb_bd *bd, size_t blk)
{
  return bd->blocks[blk].out;
}

static void var_name(const fb_bg *bg, size_t var, char *buf, size_t size)
{
  snprintf(buf, size, "%s:%s", var % 2 ? "f" : "e", bg->bonds[var / 2].name);
}

/* The variable var is produced as signal sig. */
static void define_var(fb_bd *bd, size_t var, size_t sig)
{
  bd->var_sig[var] = sig;
}

/* Block computing var (one output); its output signal is named after var. */
static int var_block(fb_bd *bd, bd_kind kind, size_t nin, size_t var, size_t elem,
                     const char *label, size_t *blk, fb_err *err)
{
  char name[256];
  var_name(bd->bg, var, name, sizeof name);
  int rc = new_block(bd, kind, nin, bd->bg->bonds[var / 2].dim, elem, label, name, blk, err);
  if (!rc)
    define_var(bd, var, out_sig(bd, *blk));
  return rc;
}

/* var = A * in_var, with A owned by the new block. */
static int gain_var(fb_bd *bd, size_t elem, size_t var, size_t in_var, fb_mat **a,
                    const char *label, fb_err *err)
{
  bd_kind kind;
  size_t blk;
  int rc = fb_bd_gain_new(*a, 1, &kind, err);
  *a = NULL;
  if (!rc)
    rc = var_block(bd, kind, 1, var, elem, label, &blk, err);
  if (!rc)
    set_input_var(bd, blk, 0, in_var);
  return rc;
}

static int scaled_gain_var(fb_bd *bd, size_t elem, size_t var, size_t in_var, double s,
                           fb_err *err)
{
  fb_mat *a = NULL;
  int rc = fb_mat_new_scaled_identity(bd->bg->bonds[var / 2].dim, s, &a, err);
  char label[64];
  snprintf(label, sizeof label, "gain %.6g", s);
  return rc ? rc : gain_var(bd, elem, var, in_var, &a, label, err);
}

/* The kind computing out = A^-1 in for element e: a solve with the
 * sparse LU of A (A is borrowed unless owned is set). */
static int solve_kind(const fb_bd *bd, size_t e, fb_mat *a, int owned, bd_kind *kind,
                      fb_err *err)
{
  int rc = fb_bd_solve_new(a, owned, kind, err);
  if (rc) {
    char who[160];
    fb_bg_describe(bd->bg, e, who, sizeof who);
    fb_err_prefix(err, "%s: its causality needs the inverse of its matrix: ", who);
  }
  return rc;
}

static int mat_is_diagonal(const fb_mat *a)
{
  size_t n = fb_mat_nrows(a);
  if (n != fb_mat_ncols(a))
    return 0;
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < n; ++i)
      if (i != j && fb_mat_get(a, i, j) != 0.0)
        return 0;
  return 1;
}

/* Diagonal inverse when a is diagonal with nonzero entries, else NULL. */
static int diag_inverse(const fb_mat *a, fb_mat **inv, fb_err *err)
{
  *inv = NULL;
  if (!fb_mat_is_sparse(a) || !mat_is_diagonal(a))
    return FB_OK;
  size_t n = fb_mat_nrows(a);
  double *d = malloc(n * sizeof *d);
  if (!d)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  int ok = 1;
  for (size_t i = 0; i < n; ++i) {
    double v = fb_mat_get(a, i, i);
    ok = ok && v != 0.0;
    d[i] = ok ? 1.0 / v : 0.0;
  }
  int rc = ok ? fb_mat_new_diag(n, d, inv, err) : FB_OK;
  free(d);
  return rc;
}

/* ---- Fields. */

/* Stacks the ports' input variables (efforts when in_is_effort) into one
 * signal; with one port of sign +1 no block is needed. Returns the input
 * as a variable or a signal. */
static int stack_inputs(fb_bd *bd, size_t e, int in_is_effort, int signed_flows, bd_input *in,
                        fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  size_t b0 = el->bonds[0];
  int s0 = signed_flows ? fb_bg_orientation(bd->bg, b0, e) : 1;
  if (el->nports == 1 && s0 == 1) {
    in->ref = BD_REF_VAR;
    in->id = in_is_effort ? VAR_E(b0) : VAR_F(b0);
    return FB_OK;
  }
  char name[256];
  snprintf(name, sizeof name, "%s.%s", el->name, in_is_effort ? "e" : "f");
  double *sign = malloc((el->nports + 1) * sizeof *sign);
  if (!sign)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  for (size_t k = 0; k < el->nports; ++k)
    sign[k] = signed_flows ? fb_bg_orientation(bd->bg, el->bonds[k], e) : 1.0;
  bd_kind kind;
  size_t blk;
  int rc = fb_bd_mux_new(el->nports, sign, &kind, err);
  free(sign);
  if (!rc)
    rc = new_block(bd, kind, el->nports, el->dim, e, "mux", name, &blk, err);
  for (size_t k = 0; !rc && k < el->nports; ++k) {
    size_t b = el->bonds[k];
    set_input_var(bd, blk, k, in_is_effort ? VAR_E(b) : VAR_F(b));
  }
  in->ref = BD_REF_SIGNAL;
  in->id = rc ? 0 : out_sig(bd, blk);
  return rc;
}

/* Distributes the stacked output signal sig over the ports' variables
 * (flows when out_is_flow, signed by orientation). */
static int split_outputs(fb_bd *bd, size_t e, size_t sig, int out_is_flow, fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  size_t off = 0;
  for (size_t k = 0; k < el->nports; ++k) {
    size_t b = el->bonds[k];
    size_t var = out_is_flow ? VAR_F(b) : VAR_E(b);
    double sign = out_is_flow ? fb_bg_orientation(bd->bg, b, e) : 1.0;
    if (el->nports == 1 && sign == 1.0) {
      define_var(bd, var, sig);
      return FB_OK;
    }
    bd_kind kind;
    size_t blk;
    int rc = fb_bd_select_new(off, sign, &kind, err);
    if (!rc)
      rc = var_block(bd, kind, 1, var, e, "demux", &blk, err);
    if (rc)
      return rc;
    set_input_sig(bd, blk, 0, sig);
    off += bd->bg->bonds[b].dim;
  }
  return FB_OK;
}

/* The kind of a field's nonlinear law, with the modulating values of
 * its sources' states. */
static int law_kind(const fb_bd *bd, size_t e, int inverse, bd_kind *kind, fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  if (inverse && el->kind == FB_BG_R)
    return fb_err_set_origin(
        err, FB_ORIGIN_ELEMENT, e,
        fb_err_set(err, FB_ECAUSAL,
                   "R '%s': a nonlinear law needs resistance causality (e = phi(f)), "
                   "but its bonds impose the effort",
                   el->name));
  size_t m = 0;
  for (size_t k = 0; k < el->nmod; ++k)
    m += bd->bg->elems[el->mod_src[k]].dim;
  return fb_bd_law_new(el->law_ops, el->law_ctx, el->dim, m, kind, err);
}

/* The kind and label of a field's matrix law: a gain by the matrix, or
 * for its inverse a gain by the inverse when the matrix is diagonal, else
 * a solve. */
static int matrix_kind(const fb_bd *bd, size_t e, int inverse, bd_kind *kind,
                       const char **label, fb_err *err)
{
  fb_mat *law = bd->bg->elems[e].law;
  if (!inverse) {
    *label = "gain";
    return fb_bd_gain_new(law, 0, kind, err);
  }
  fb_mat *dinv = NULL;
  int rc = diag_inverse(law, &dinv, err);
  if (rc)
    return rc;
  if (dinv) {
    *label = "inverse gain";
    return fb_bd_gain_new(dinv, 1, kind, err);
  }
  *label = "solve";
  return solve_kind(bd, e, law, 0, kind, err);
}

/* out = law(in) for the field's matrix or nonlinear law; inverse for
 * I fields (M^-1 p) and conductance R fields (R^-1 e). */
static int field_law(fb_bd *bd, size_t e, bd_input in, int inverse, const char *outname,
                     size_t *out, fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  bd_kind kind;
  const char *label = el->law_ops ? el->law_ops->name : NULL;
  int rc = el->law_ops ? law_kind(bd, e, inverse, &kind, err)
                       : matrix_kind(bd, e, inverse, &kind, &label, err);
  size_t blk;
  if (!rc)
    rc = new_block(bd, kind, 1 + el->nmod, el->dim, e, label, outname, &blk, err);
  if (rc)
    return rc;
  bd_block *b = &bd->blocks[blk];
  b->in[0] = in;
  /* A modulated law reads the states of its sources, which exist once
   * every element has its blocks (resolve_inputs). */
  for (size_t k = 0; k < el->nmod; ++k)
    b->in[1 + k] = (bd_input){el->mod_src[k], BD_REF_STATE};
  *out = out_sig(bd, blk);
  return FB_OK;
}

/* I field: p' = e, f = M^-1 p; C field: q' = f, e = K q (integral
 * causality, checked by fb_bg_assign_causality). */
static int emit_storage(fb_bd *bd, size_t e, fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  int is_i = el->kind == FB_BG_I;
  bd_input deriv;
  int rc = stack_inputs(bd, e, is_i, !is_i, &deriv, err);
  char name[256];
  snprintf(name, sizeof name, "%s.%s", el->name, is_i ? "p" : "q");
  size_t blk;
  if (!rc)
    rc = new_block(bd, fb_bd_integrator_new(), 1, el->dim, e, "integrator", name, &blk, err);
  if (rc)
    return rc;
  bd->blocks[blk].in[0] = deriv;
  bd_input state = {out_sig(bd, blk), BD_REF_SIGNAL};
  size_t co;
  snprintf(name, sizeof name, "%s.%s", el->name, is_i ? "f" : "e");
  rc = field_law(bd, e, state, is_i, name, &co, err);
  if (rc)
    return rc;
  bd->elem_state[e] = state.id;
  bd->elem_co[e] = co;
  return split_outputs(bd, e, co, is_i, err);
}

/* R field: resistance causality e = R f, or conductance f = R^-1 e. */
static int emit_resistor(fb_bd *bd, size_t e, fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  int conductance = fb_bg_receives_effort(bd->bg, el->bonds[0], e);
  for (size_t k = 1; k < el->nports; ++k)
    if (fb_bg_receives_effort(bd->bg, el->bonds[k], e) != conductance)
      return fb_err_set_origin(
          err, FB_ORIGIN_ELEMENT, e,
          fb_err_set(err, FB_ECAUSAL,
                     "R '%s' has mixed causality (bond '%s' imposes effort, bond '%s' "
                     "imposes flow); give all its ports the same causality, e.g. by "
                     "splitting the field",
                     el->name, bd->bg->bonds[el->bonds[conductance ? 0 : k]].name,
                     bd->bg->bonds[el->bonds[conductance ? k : 0]].name));
  bd_input in;
  int rc = stack_inputs(bd, e, conductance, !conductance, &in, err);
  char name[256];
  snprintf(name, sizeof name, "%s.%s", el->name, conductance ? "f" : "e");
  size_t out;
  if (!rc)
    rc = field_law(bd, e, in, conductance, name, &out, err);
  return rc ? rc : split_outputs(bd, e, out, conductance, err);
}

static int emit_source(fb_bd *bd, size_t e, fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  size_t b = el->bonds[0];
  bd_kind kind;
  size_t blk;
  int rc = fb_bd_source_new(el->values, &kind, err);
  return rc ? rc
            : var_block(bd, kind, 0, el->kind == FB_BG_SE ? VAR_E(b) : VAR_F(b), e, "source",
                        &blk, err);
}

/* 0-junction: the strong bond s gives the effort, every other bond's
 * effort is the same signal; sum_i sigma_i f_i = 0 gives
 * f_s = -sigma_s sum_{b != s} sigma_b f_b. 1-junction: dual. */
static int emit_junction(fb_bd *bd, size_t e, fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  if (el->nports == 0)
    return FB_OK;
  int zero = el->kind == FB_BG_J0;
  size_t strong = FB_NONE;
  for (size_t k = 0; k < el->nports && strong == FB_NONE; ++k)
    if (fb_bg_receives_effort(bd->bg, el->bonds[k], e) == zero)
      strong = el->bonds[k];
  size_t common = zero ? VAR_E(strong) : VAR_F(strong);
  for (size_t k = 0; k < el->nports; ++k) {
    size_t b = el->bonds[k];
    if (b != strong)
      bd->var_alias[zero ? VAR_E(b) : VAR_F(b)] = common;
  }
  double *coef = malloc(el->nports * sizeof *coef);
  if (!coef)
    return fb_err_set(err, FB_ENOMEM, "out of memory building the block diagram");
  int ss = fb_bg_orientation(bd->bg, strong, e);
  for (size_t k = 0, k2 = 0; k < el->nports; ++k)
    if (el->bonds[k] != strong)
      coef[k2++] = -(double)ss * fb_bg_orientation(bd->bg, el->bonds[k], e);
  bd_kind kind;
  size_t blk;
  int rc = fb_bd_sum_new(el->nports - 1, coef, &kind, err);
  free(coef);
  if (!rc)
    rc = var_block(bd, kind, el->nports - 1, zero ? VAR_F(strong) : VAR_E(strong), e, "sum",
                   &blk, err);
  for (size_t k = 0, k2 = 0; !rc && k < el->nports; ++k)
    if (el->bonds[k] != strong)
      set_input_var(bd, blk, k2++, zero ? VAR_F(el->bonds[k]) : VAR_E(el->bonds[k]));
  return rc;
}

/* TF: e1 = r e2, f2 = r f1, or inverted. GY: e1 = r f2, e2 = r f1, or
 * inverted. Bonds are oriented through (checked by causality). */
static int emit_twoport(fb_bd *bd, size_t e, fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  size_t b1 = el->bonds[0], b2 = el->bonds[1];
  double r = el->modulus;
  int recv1 = fb_bg_receives_effort(bd->bg, b1, e);
  /* TF: port 1 giving the effort inverts e1 = r e2; GY: both ports
   * receiving effort is the conductance form f = e / r. */
  int inverted = recv1;
  if (inverted && r == 0.0)
    return fb_err_set_origin(
        err, FB_ORIGIN_ELEMENT, e,
        fb_err_set(err, FB_ECAUSAL,
                   "%s '%s' has modulus 0 but its causality needs 1/modulus (bond '%s' "
                   "gives it the effort)",
                   fb_bg_kind_name(el->kind), el->name, bd->bg->bonds[b1].name));
  double g = inverted ? 1.0 / r : r;
  int rc;
  if (el->kind == FB_BG_TF) {
    rc = inverted ? scaled_gain_var(bd, e, VAR_E(b2), VAR_E(b1), g, err)
                  : scaled_gain_var(bd, e, VAR_E(b1), VAR_E(b2), g, err);
    if (!rc)
      rc = inverted ? scaled_gain_var(bd, e, VAR_F(b1), VAR_F(b2), g, err)
                    : scaled_gain_var(bd, e, VAR_F(b2), VAR_F(b1), g, err);
  } else if (inverted) {
    rc = scaled_gain_var(bd, e, VAR_F(b1), VAR_E(b2), g, err);
    if (!rc)
      rc = scaled_gain_var(bd, e, VAR_F(b2), VAR_E(b1), g, err);
  } else {
    rc = scaled_gain_var(bd, e, VAR_E(b1), VAR_F(b2), g, err);
    if (!rc)
      rc = scaled_gain_var(bd, e, VAR_E(b2), VAR_F(b1), g, err);
  }
  return rc;
}

/* var = A^-1 in_var (A owned by the new block if owned is set). */
static int solve_var(fb_bd *bd, size_t e, size_t var, size_t in_var, fb_mat *a, int owned,
                     const char *label, fb_err *err)
{
  bd_kind kind;
  size_t blk;
  int rc = solve_kind(bd, e, a, owned, &kind, err);
  if (!rc)
    rc = var_block(bd, kind, 1, var, e, label, &blk, err);
  if (!rc)
    set_input_var(bd, blk, 0, in_var);
  return rc;
}

/* MTF: f2 = T f1, e1 = T^T e2; inverted (square T): f1 = T^-1 f2,
 * e2 = T^-T e1. */
static int emit_mtf(fb_bd *bd, size_t e, fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  size_t b1 = el->bonds[0], b2 = el->bonds[1];
  fb_mat *tt = NULL;
  int rc = fb_mat_transpose(el->law, &tt, err);
  if (rc)
    return rc;
  if (!fb_bg_receives_effort(bd->bg, b1, e)) {
    fb_mat *t = NULL;
    rc = fb_mat_clone(el->law, &t, err);
    if (!rc)
      rc = gain_var(bd, e, VAR_F(b2), VAR_F(b1), &t, "T", err);
    if (!rc)
      rc = gain_var(bd, e, VAR_E(b1), VAR_E(b2), &tt, "T'", err);
    fb_mat_free(&tt);
    return rc;
  }
  rc = solve_var(bd, e, VAR_F(b1), VAR_F(b2), el->law, 0, "T^-1", err);
  if (rc) {
    fb_mat_free(&tt);
    return rc;
  }
  return solve_var(bd, e, VAR_E(b2), VAR_E(b1), tt, 1, "T'^-1", err);
}

/* Composite: the whole multibond stacks the parts' efforts and flows. */
static int emit_composite(fb_bd *bd, size_t e, fb_err *err)
{
  const fb_bg_elem *el = &bd->bg->elems[e];
  size_t nparts = el->nports - 1, whole = el->bonds[nparts];
  int whole_gives_effort = fb_bg_receives_effort(bd->bg, whole, e);
  bd_kind kind;
  size_t mux;
  int rc = fb_bd_mux_new(nparts, NULL, &kind, err);
  if (!rc)
    rc = var_block(bd, kind, nparts, whole_gives_effort ? VAR_F(whole) : VAR_E(whole), e, "mux",
                   &mux, err);
  size_t split = whole_gives_effort ? VAR_E(whole) : VAR_F(whole);
  size_t off = 0;
  for (size_t k = 0; !rc && k < nparts; ++k) {
    size_t b = el->bonds[k];
    set_input_var(bd, mux, k, whole_gives_effort ? VAR_F(b) : VAR_E(b));
    size_t blk;
    rc = fb_bd_select_new(off, 1.0, &kind, err);
    if (!rc)
      rc = var_block(bd, kind, 1, whole_gives_effort ? VAR_E(b) : VAR_F(b), e, "demux", &blk,
                     err);
    if (!rc) {
      set_input_var(bd, blk, 0, split);
      off += bd->bg->bonds[b].dim;
    }
  }
  return rc;
}

static int emit_element(fb_bd *bd, size_t e, fb_err *err)
{
  switch (bd->bg->elems[e].kind) {
  case FB_BG_SE:
  case FB_BG_SF: return emit_source(bd, e, err);
  case FB_BG_I:
  case FB_BG_C: return emit_storage(bd, e, err);
  case FB_BG_R: return emit_resistor(bd, e, err);
  case FB_BG_TF:
  case FB_BG_GY: return emit_twoport(bd, e, err);
  case FB_BG_MTF: return emit_mtf(bd, e, err);
  case FB_BG_J0:
  case FB_BG_J1: return emit_junction(bd, e, err);
  case FB_BG_COMPOSITE: return emit_composite(bd, e, err);
  }
  return fb_err_set(err, FB_EINVAL, "unknown element kind");
}

/* Follows junction aliases to the variable that has a producer. */
static int resolve_var(const fb_bd *bd, size_t var, size_t *sig, fb_err *err)
{
  size_t nvars = 2 * bd->bg->nbonds;
  for (size_t hops = 0; hops <= nvars; ++hops) {
    if (bd->var_sig[var] != FB_NONE) {
      *sig = bd->var_sig[var];
      return FB_OK;
    }
    if (bd->var_alias[var] == FB_NONE)
      break;
    var = bd->var_alias[var];
  }
  char name[256];
  var_name(bd->bg, var, name, sizeof name);
  return fb_err_set_origin(
      err, FB_ORIGIN_BOND, var / 2,
      fb_err_set(err, FB_ECAUSAL, "no block computes %s (junction structure loop)", name));
}

/* Every input becomes a signal: a variable its producer's (through the
 * junctions' aliases), an element's state its integrator's output. */
static int resolve_inputs(fb_bd *bd, fb_err *err)
{
  for (size_t i = 0; i < bd->nblocks; ++i) {
    bd_block *b = &bd->blocks[i];
    for (size_t k = 0; k < b->nin; ++k) {
      bd_input *in = &b->in[k];
      if (in->ref == BD_REF_STATE)
        in->id = bd->elem_state[in->id];
      if (in->ref == BD_REF_VAR) {
        int rc = resolve_var(bd, in->id, &in->id, err);
        if (rc)
          return rc;
      }
      in->ref = BD_REF_SIGNAL;
    }
  }
  return FB_OK;
}

/* ---- Probes. */

static const char *probe_unit(const fb_bd *bd, const fb_probe_spec *p, size_t target)
{
  if (p->unit)
    return p->unit;
  switch (p->kind) {
  case FB_PROBE_EFFORT:
    return fb_bg_domain_unit(bd->bg->bonds[target].domain,
                             p->integrate ? FB_UNIT_MOMENTUM : FB_UNIT_EFFORT);
  case FB_PROBE_FLOW:
    return fb_bg_domain_unit(bd->bg->bonds[target].domain,
                             p->integrate ? FB_UNIT_DISPLACEMENT : FB_UNIT_FLOW);
  case FB_PROBE_POWER: return p->integrate ? "J" : "W";
  case FB_PROBE_STATE: {
    const fb_bg_elem *el = &bd->bg->elems[target];
    fb_bg_domain d = bd->bg->bonds[el->bonds[0]].domain;
    if (p->integrate)
      return "?";
    return fb_bg_domain_unit(d, el->kind == FB_BG_I ? FB_UNIT_MOMENTUM : FB_UNIT_DISPLACEMENT);
  }
  case FB_PROBE_ENERGY: return p->integrate ? "J s" : "J";
  }
  return "?";
}

/* Signal measured by probe p; target is the bond or element index. */
static int probe_signal(fb_bd *bd, const fb_probe_spec *p, size_t *sig, size_t *target,
                        fb_err *err)
{
  int on_bond =
      p->kind == FB_PROBE_EFFORT || p->kind == FB_PROBE_FLOW || p->kind == FB_PROBE_POWER;
  long t = on_bond ? fb_bg_find_bond(bd->bg, p->target) : fb_bg_find_element(bd->bg, p->target);
  if (t < 0)
    return fb_err_set(err, FB_EMODEL, "probe '%s': no %s named '%s'", p->name,
                      on_bond ? "bond" : "element", p->target);
  *target = (size_t)t;
  if (p->kind == FB_PROBE_EFFORT || p->kind == FB_PROBE_FLOW)
    return resolve_var(bd, p->kind == FB_PROBE_EFFORT ? VAR_E(t) : VAR_F(t), sig, err);
  if (p->kind == FB_PROBE_POWER) {
    size_t blk;
    size_t se = 0, sf = 0;
    int rc = resolve_var(bd, VAR_E(t), &se, err);
    if (!rc)
      rc = resolve_var(bd, VAR_F(t), &sf, err);
    if (!rc)
      rc = new_block(bd, fb_bd_product_new(), 2, bd->bg->bonds[t].dim, FB_NONE, "e.*f", p->name,
                     &blk, err);
    if (rc)
      return rc;
    set_input_sig(bd, blk, 0, se);
    set_input_sig(bd, blk, 1, sf);
    *sig = out_sig(bd, blk);
    return FB_OK;
  }
  if (bd->elem_state[t] == FB_NONE)
    return fb_err_set(err, FB_EMODEL, "probe '%s': '%s' is %s, not a storage element (I or C)",
                      p->name, p->target, fb_bg_kind_name(bd->bg->elems[t].kind));
  if (p->kind == FB_PROBE_STATE) {
    *sig = bd->elem_state[t];
    return FB_OK;
  }
  const fb_bg_elem *el = &bd->bg->elems[t];
  if (el->law_ops && !el->law_ops->energy)
    return fb_err_set(err, FB_EMODEL, "probe '%s': the law of '%s' has no energy function",
                      p->name, p->target);
  bd_kind kind;
  size_t blk;
  int rc = fb_bd_energy_new(el->law_ops, el->law_ctx, &kind, err);
  if (!rc)
    rc = new_block(bd, kind, 2, 1, FB_NONE, "energy", p->name, &blk, err);
  if (rc)
    return rc;
  set_input_sig(bd, blk, 0, bd->elem_state[t]);
  set_input_sig(bd, blk, 1, bd->elem_co[t]);
  *sig = out_sig(bd, blk);
  return FB_OK;
}

static int push_output(fb_bd *bd, const char *name, const char *unit, size_t sig, size_t comp,
                       double gain, fb_err *err)
{
  if (fb_grow((void **)&bd->outs, &bd->cap_outs, bd->nouts, sizeof *bd->outs))
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  bd_output *o = &bd->outs[bd->nouts];
  o->name = fb_strdup(name);
  o->unit = fb_strdup(unit);
  o->signal = sig;
  o->comp = comp;
  o->gain = gain;
  if (!o->name || !o->unit) {
    free(o->name);
    free(o->unit);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  bd->nouts++;
  return FB_OK;
}

/* Replaces *sig by the scalar sum_k w_k sig_k (a 1 x n gain block). */
static int weighted_sum(fb_bd *bd, const fb_probe_spec *p, size_t *sig, fb_err *err)
{
  size_t n = bd->sigs[*sig].dim;
  if (p->nweights != n || p->component >= 0)
    return fb_err_set(err, FB_EMODEL,
                      "probe '%s': %zu weights for a signal of dimension %zu (weights need "
                      "one per component and no component selection)",
                      p->name, p->nweights, n);
  fb_mat *w = NULL;
  int rc = fb_mat_new_dense(1, n, p->weights, &w, err);
  if (rc)
    return rc;
  bd_kind kind;
  size_t blk;
  rc = fb_bd_gain_new(w, 1, &kind, err);
  if (!rc)
    rc = new_block(bd, kind, 1, 1, FB_NONE, "weights", p->name, &blk, err);
  if (rc)
    return rc;
  set_input_sig(bd, blk, 0, *sig);
  *sig = out_sig(bd, blk);
  return FB_OK;
}

static int add_probe(fb_bd *bd, const fb_probe_spec *p, fb_err *err)
{
  if (!p->name || !*p->name || !p->target)
    return fb_err_set(err, FB_EMODEL, "probe without a name or target");
  for (size_t i = 0; i < bd->nouts; ++i)
    if (strncmp(bd->outs[i].name, p->name, strlen(p->name)) == 0 &&
        (bd->outs[i].name[strlen(p->name)] == '\0' || bd->outs[i].name[strlen(p->name)] == '['))
      return fb_err_set(err, FB_EMODEL, "duplicate probe name '%s'", p->name);
  if (p->gain != 1.0 && !p->unit)
    return fb_err_set(err, FB_EMODEL, "probe '%s': a gain changes the unit: give 'unit'",
                      p->name);
  size_t sig = 0, target = 0;
  int rc = probe_signal(bd, p, &sig, &target, err);
  if (rc)
    return rc;
  /* Stated for the static analyzer, which cannot see that fb_bg_find_element (graph.c)
   * returns an index below the element count. */
  assert(sig < bd->nsigs);
  if (p->integrate) {
    char name[300];
    snprintf(name, sizeof name, "integral:%s", p->name);
    size_t blk;
    rc = new_block(bd, fb_bd_integrator_new(), 1, bd->sigs[sig].dim, FB_NONE, "integrator",
                   name, &blk, err);
    if (rc)
      return rc;
    set_input_sig(bd, blk, 0, sig);
    sig = out_sig(bd, blk);
  }
  if (p->nweights) {
    rc = weighted_sum(bd, p, &sig, err);
    if (rc)
      return rc;
  }
  size_t dim = bd->sigs[sig].dim;
  if (p->component >= 0 && (size_t)p->component >= dim)
    return fb_err_set(err, FB_EMODEL, "probe '%s': component %ld out of range 1..%zu", p->name,
                      p->component + 1, dim);
  const char *unit = probe_unit(bd, p, target);
  if (p->component >= 0 || dim == 1)
    return push_output(bd, p->name, unit, sig, p->component >= 0 ? (size_t)p->component : 0,
                       p->gain, err);
  for (size_t i = 0; !rc && i < dim; ++i) {
    char name[300];
    snprintf(name, sizeof name, "%s[%zu]", p->name, i + 1);
    rc = push_output(bd, name, unit, sig, i, p->gain, err);
  }
  return rc;
}

/* ---- Layout: states first (x = w[0 .. nstates)), then other signals. */

static int layout(fb_bd *bd, fb_err *err)
{
  bd->integ = malloc((bd->nblocks + 1) * sizeof *bd->integ);
  if (!bd->integ)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  bd->ninteg = 0;
  size_t off = 0;
  for (size_t i = 0; i < bd->nblocks; ++i)
    if (bd->blocks[i].ops->state) {
      bd->integ[bd->ninteg++] = i;
      bd->sigs[bd->blocks[i].out].off = off;
      off += bd->sigs[bd->blocks[i].out].dim;
    }
  bd->nstates = off;
  for (size_t i = 0; i < bd->nblocks; ++i)
    if (!bd->blocks[i].ops->state) {
      bd->sigs[bd->blocks[i].out].off = off;
      off += bd->sigs[bd->blocks[i].out].dim;
    }
  bd->nw = off;
  for (size_t i = 0; i < bd->nblocks; ++i) {
    bd_block *b = &bd->blocks[i];
    b->ioff = malloc((b->nin + 1) * sizeof *b->ioff);
    b->idim = malloc((b->nin + 1) * sizeof *b->idim);
    if (!b->ioff || !b->idim)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    for (size_t k = 0; k < b->nin; ++k) {
      b->ioff[k] = bd->sigs[b->in[k].id].off;
      b->idim[k] = bd->sigs[b->in[k].id].dim;
    }
    b->ooff = bd->sigs[b->out].off;
  }
  return FB_OK;
}

/* Checks that every block's inputs have the dimensions it expects. */
static int check_dims(const fb_bd *bd, fb_err *err)
{
  for (size_t i = 0; i < bd->nblocks; ++i) {
    const bd_block *b = &bd->blocks[i];
    for (size_t k = 0; k < b->nin; ++k) {
      size_t need = b->ops->input_dim ? b->ops->input_dim(b, k) : b->odim;
      if (need != FB_NONE && b->idim[k] != need)
        return fb_err_set(err, FB_EMODEL,
                          "block '%s' (%s): input %zu has dimension %zu, "
                          "expected %zu",
                          b->label, b->ops->kind, k + 1, b->idim[k], need);
    }
  }
  return FB_OK;
}

static int name_states(fb_bd *bd, fb_err *err)
{
  bd->state_names = calloc(bd->nstates + 1, sizeof *bd->state_names);
  bd->x0 = calloc(bd->nstates + 1, sizeof *bd->x0);
  bd->state_elem = malloc((bd->nstates + 1) * sizeof *bd->state_elem);
  bd->state_comp = malloc((bd->nstates + 1) * sizeof *bd->state_comp);
  if (!bd->state_names || !bd->x0 || !bd->state_elem || !bd->state_comp)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t k = 0; k < bd->ninteg; ++k) {
    const bd_block *b = &bd->blocks[bd->integ[k]];
    const bd_signal *s = &bd->sigs[b->out];
    const double *x0 = b->elem != FB_NONE ? bd->bg->elems[b->elem].x0 : NULL;
    for (size_t i = 0; i < s->dim; ++i) {
      char name[300];
      if (s->dim == 1)
        snprintf(name, sizeof name, "%s", s->name);
      else
        snprintf(name, sizeof name, "%s[%zu]", s->name, i + 1);
      if (!(bd->state_names[s->off + i] = fb_strdup(name)))
        return fb_err_set(err, FB_ENOMEM, "out of memory");
      bd->x0[s->off + i] = x0 ? x0[i] : 0.0;
      bd->state_elem[s->off + i] = b->elem;
      bd->state_comp[s->off + i] = i;
    }
  }
  return FB_OK;
}

static int alloc_vars(fb_bd *bd, fb_err *err)
{
  size_t nvars = 2 * bd->bg->nbonds + 1, ne = bd->bg->nelems + 1;
  bd->var_sig = malloc(nvars * sizeof *bd->var_sig);
  bd->var_alias = malloc(nvars * sizeof *bd->var_alias);
  bd->elem_state = malloc(ne * sizeof *bd->elem_state);
  bd->elem_co = malloc(ne * sizeof *bd->elem_co);
  if (!bd->var_sig || !bd->var_alias || !bd->elem_state || !bd->elem_co)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; i < nvars; ++i)
    bd->var_sig[i] = bd->var_alias[i] = FB_NONE;
  for (size_t i = 0; i < ne; ++i)
    bd->elem_state[i] = bd->elem_co[i] = FB_NONE;
  return FB_OK;
}

static int build(fb_bd *bd, const fb_probe_spec *probes, size_t nprobes, fb_err *err)
{
  int rc = fb_bg_assign_causality(bd->bg, err);
  if (!rc)
    rc = alloc_vars(bd, err);
  for (size_t e = 0; !rc && e < bd->bg->nelems; ++e)
    rc = emit_element(bd, e, err);
  if (!rc)
    rc = resolve_inputs(bd, err);
  for (size_t i = 0; !rc && i < nprobes; ++i)
    rc = add_probe(bd, &probes[i], err);
  if (!rc)
    rc = layout(bd, err);
  if (!rc)
    rc = check_dims(bd, err);
  if (!rc)
    rc = name_states(bd, err);
  if (!rc)
    rc = fb_bd_schedule(bd, err);
  if (!rc) {
    bd->w = calloc(bd->nw + 1, sizeof *bd->w);
    bd->dw = calloc(bd->nw + 1, sizeof *bd->dw);
    if (!bd->w || !bd->dw)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  if (!rc)
    rc = fb_bd_fold_constants(bd, err);
  if (!rc)
    rc = fb_bd_prepare_newton(bd, err);
  if (!rc)
    rc = fb_bd_prepare_switching(bd, err);
  return rc;
}

int fb_bd_build(fb_bg *bg, const fb_probe_spec *probes, size_t nprobes, fb_bd **out,
                fb_err *err)
{
  *out = NULL;
  fb_bd *bd = calloc(1, sizeof *bd);
  if (!bd)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  bd->bg = bg;
  int rc = build(bd, probes, nprobes, err);
  if (rc) {
    fb_bd_free(&bd);
    return rc;
  }
  *out = bd;
  return FB_OK;
}

void fb_bd_free(fb_bd **bdp)
{
  if (!bdp || !*bdp)
    return;
  fb_bd *bd = *bdp;
  for (size_t i = 0; i < bd->nblocks; ++i) {
    bd_block *b = &bd->blocks[i];
    if (b->ops->free)
      b->ops->free(b->content);
    free(b->in);
    free(b->ioff);
    free(b->idim);
    free(b->label);
  }
  for (size_t i = 0; i < bd->nsigs; ++i)
    free(bd->sigs[i].name);
  for (size_t i = 0; i < bd->nouts; ++i) {
    free(bd->outs[i].name);
    free(bd->outs[i].unit);
  }
  if (bd->state_names)
    for (size_t i = 0; i < bd->nstates; ++i)
      free(bd->state_names[i]);
  free(bd->state_names);
  free(bd->state_elem);
  free(bd->state_comp);
  free(bd->blocks);
  free(bd->sigs);
  free(bd->outs);
  free(bd->order);
  free(bd->out_order);
  free(bd->dyn_order);
  free(bd->is_const);
  free(bd->zmap);
  free(bd->newton_blocks);
  free(bd->keep);
  free(bd->srows);
  free(bd->scols);
  free(bd->sv0);
  free(bd->sv1);
  free(bd->integ);
  free(bd->w);
  free(bd->dw);
  free(bd->x0);
  free(bd->var_sig);
  free(bd->var_alias);
  free(bd->elem_state);
  free(bd->elem_co);
  free(bd->switched);
  free(bd->guard_off);
  free(bd->guard_now);
  free(bd->guard_ahead);
  free(bd->guard_sign);
  free(bd->x_ahead);
  free(bd);
  *bdp = NULL;
}
