/* SPDX-License-Identifier: BSD-3-Clause */
/* Sequential causality assignment procedure (SCAP) on multibond graphs.
 *
 * Karnopp, Margolis & Rosenberg, "System Dynamics", 5th ed., section 5.2:
 * 1. sources (and non-square MTFs, whose causality is fixed) impose their
 *    causality, which is propagated through junctions, TF, GY and
 *    composites; 2. each storage element in turn gets integral causality,
 *    again propagated; 3. each resistor gets resistance causality where
 *    still free; 4. remaining bonds (junction structure loops) get an
 *    arbitrary stroke, propagated. A multibond carries one stroke for all
 *    its components (vector-wise assignment, Breedveld 1985).
 * A storage element that ends up in derivative causality, and a junction
 * forced two ways, are errors naming the elements and bonds involved. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg/bg_internal.h"

typedef struct scap {
  fb_bg *bg;
  size_t *queue; /* elements whose bonds changed */
  size_t nqueue;
  unsigned char *queued;
  fb_err *err;
} scap;

static void enqueue(scap *s, size_t e)
{
  if (!s->queued[e]) {
    s->queued[e] = 1;
    s->queue[s->nqueue++] = e;
  }
}

static const char *stroke_end_name(const fb_bg *bg, size_t b)
{
  const fb_bg_bond *bd = &bg->bonds[b];
  return bg->elems[bd->stroke == FB_STROKE_AT_TO ? bd->to : bd->from].name;
}

/* Sets bond b so that element e receives (recv = 1) or imposes (recv = 0)
 * its effort; cause is the element whose choice this follows from.
 * FB_ECAUSAL if the bond already has the other stroke. */
static int set_stroke(scap *s, size_t b, size_t e, int recv, size_t cause, size_t at)
{
  fb_bg_bond *bd = &s->bg->bonds[b];
  int want = (bd->to == e) == (recv != 0) ? FB_STROKE_AT_TO : FB_STROKE_AT_FROM;
  if (bd->stroke == want)
    return FB_OK;
  if (bd->stroke != FB_STROKE_UNSET) {
    char here[160], c1[160], c2[160];
    fb_bg_describe(s->bg, at, here, sizeof here);
    fb_bg_describe(s->bg, bd->cause, c1, sizeof c1);
    fb_bg_describe(s->bg, cause, c2, sizeof c2);
    return fb_err_set_origin(
        s->err, FB_ORIGIN_BOND, b,
        fb_err_set(s->err, FB_ECAUSAL,
                   "causal conflict at %s on bond '%s' ('%s' -> '%s'): %s gives the effort "
                   "to '%s', but %s requires the opposite stroke",
                   here, bd->name, s->bg->elems[bd->from].name, s->bg->elems[bd->to].name, c1,
                   stroke_end_name(s->bg, b), c2));
  }
  bd->stroke = want;
  bd->cause = cause;
  enqueue(s, bd->from);
  enqueue(s, bd->to);
  return FB_OK;
}

/* Junction rule. A 0-junction receives its effort from exactly one bond
 * (the strong bond); a 1-junction imposes effort on exactly one bond (the
 * bond that sets the common flow). `special` is that role as "receives". */
static int junction_rule(scap *s, size_t e)
{
  const fb_bg_elem *el = &s->bg->elems[e];
  int special_recv = el->kind == FB_BG_J0; /* J0: strong bond gives effort */
  size_t nspecial = 0, nunset = 0, special = FB_NONE, unset = FB_NONE;
  for (size_t k = 0; k < el->nports; ++k) {
    size_t b = el->bonds[k];
    if (s->bg->bonds[b].stroke == FB_STROKE_UNSET) {
      nunset++;
      unset = b;
    } else if (fb_bg_receives_effort(s->bg, b, e) == special_recv) {
      if (nspecial++) {
        char here[160], c1[160], c2[160];
        fb_bg_describe(s->bg, e, here, sizeof here);
        fb_bg_describe(s->bg, s->bg->bonds[special].cause, c1, sizeof c1);
        fb_bg_describe(s->bg, s->bg->bonds[b].cause, c2, sizeof c2);
        return fb_err_set_origin(
            s->err, FB_ORIGIN_ELEMENT, e,
            fb_err_set(s->err, FB_ECAUSAL,
                       "causal conflict at %s: bonds '%s' (from %s) and '%s' (from %s) "
                       "both set its common %s",
                       here, s->bg->bonds[special].name, c1, s->bg->bonds[b].name, c2,
                       el->kind == FB_BG_J0 ? "effort" : "flow"));
      }
      special = b;
    }
  }
  if (nspecial == 1) {
    size_t cause = s->bg->bonds[special].cause;
    for (size_t k = 0; k < el->nports; ++k) {
      size_t b = el->bonds[k];
      if (s->bg->bonds[b].stroke == FB_STROKE_UNSET) {
        int rc = set_stroke(s, b, e, !special_recv, cause, e);
        if (rc)
          return rc;
      }
    }
  } else if (nspecial == 0 && nunset == 1 && el->nports > 0) {
    size_t cause = FB_NONE;
    for (size_t k = 0; k < el->nports && cause == FB_NONE; ++k)
      if (el->bonds[k] != unset)
        cause = s->bg->bonds[el->bonds[k]].cause;
    return set_stroke(s, unset, e, special_recv, cause == FB_NONE ? e : cause, e);
  }
  return FB_OK;
}

/* Two-port rule: TF and square MTF (same = 0: one port receives effort),
 * GY (same = 1: both ports alike). */
static int twoport_rule(scap *s, size_t e, int same)
{
  const fb_bg_elem *el = &s->bg->elems[e];
  size_t b0 = el->bonds[0], b1 = el->bonds[1];
  int set0 = s->bg->bonds[b0].stroke != FB_STROKE_UNSET;
  int set1 = s->bg->bonds[b1].stroke != FB_STROKE_UNSET;
  if (set0 && set1) {
    int r0 = fb_bg_receives_effort(s->bg, b0, e), r1 = fb_bg_receives_effort(s->bg, b1, e);
    if ((same && r0 == r1) || (!same && r0 != r1))
      return FB_OK;
    char here[160], c0[160], c1[160];
    fb_bg_describe(s->bg, e, here, sizeof here);
    fb_bg_describe(s->bg, s->bg->bonds[b0].cause, c0, sizeof c0);
    fb_bg_describe(s->bg, s->bg->bonds[b1].cause, c1, sizeof c1);
    return fb_err_set_origin(
        s->err, FB_ORIGIN_ELEMENT, e,
        fb_err_set(s->err, FB_ECAUSAL,
                   "causal conflict at %s: bond '%s' (from %s) and bond '%s' (from %s) both "
                   "%s, but %s",
                   here, s->bg->bonds[b0].name, c0, s->bg->bonds[b1].name, c1,
                   r0 ? "bring it an effort" : "take an effort from it",
                   same ? "a gyrator needs both ports alike"
                        : "a transformer passes the effort through, in at one port and out "
                          "at the other"));
  }
  if (!set0 && !set1)
    return FB_OK;
  size_t known = set0 ? b0 : b1, other = set0 ? b1 : b0;
  int r = fb_bg_receives_effort(s->bg, known, e);
  return set_stroke(s, other, e, same ? r : !r, s->bg->bonds[known].cause, e);
}

/* Composite: parts impose effort exactly when the whole receives it. */
static int composite_rule(scap *s, size_t e)
{
  const fb_bg_elem *el = &s->bg->elems[e];
  size_t whole = el->bonds[el->nports - 1];
  long known = -1;
  for (size_t k = 0; k < el->nports && known < 0; ++k)
    if (s->bg->bonds[el->bonds[k]].stroke != FB_STROKE_UNSET)
      known = (long)k;
  if (known < 0)
    return FB_OK;
  size_t kb = el->bonds[known];
  int whole_recv = fb_bg_receives_effort(s->bg, kb, e);
  if ((size_t)known != el->nports - 1)
    whole_recv = !whole_recv;
  size_t cause = s->bg->bonds[kb].cause;
  int rc = set_stroke(s, whole, e, whole_recv, cause, e);
  for (size_t k = 0; !rc && k + 1 < el->nports; ++k)
    rc = set_stroke(s, el->bonds[k], e, !whole_recv, cause, e);
  return rc;
}

static int is_square_mtf(const fb_bg_elem *el)
{
  return el->kind == FB_BG_MTF && el->port_dims[0] == el->port_dims[1];
}

static int apply_rule(scap *s, size_t e)
{
  const fb_bg_elem *el = &s->bg->elems[e];
  switch (el->kind) {
  case FB_BG_J0:
  case FB_BG_J1: return junction_rule(s, e);
  case FB_BG_TF: return twoport_rule(s, e, 0);
  case FB_BG_GY: return twoport_rule(s, e, 1);
  case FB_BG_MTF: return is_square_mtf(el) ? twoport_rule(s, e, 0) : FB_OK;
  case FB_BG_COMPOSITE: return composite_rule(s, e);
  default: return FB_OK;
  }
}

static int propagate(scap *s)
{
  while (s->nqueue) {
    size_t e = s->queue[--s->nqueue];
    s->queued[e] = 0;
    int rc = apply_rule(s, e);
    if (rc)
      return rc;
  }
  return FB_OK;
}

/* Step 0: every port connected, two-ports and composites oriented
 * through (power in at port 1 / the parts, out at port 2 / the whole, or
 * the reverse for composites). */
static int check_structure(const fb_bg *bg, fb_err *err)
{
  for (size_t e = 0; e < bg->nelems; ++e) {
    const fb_bg_elem *el = &bg->elems[e];
    if (!el->fixed_ports)
      continue;
    for (size_t k = 0; k < el->nports; ++k)
      if (el->bonds[k] == FB_NONE)
        return fb_err_set_origin(err, FB_ORIGIN_ELEMENT, e,
                                 fb_err_set(err, FB_EMODEL,
                                            "%s '%s': port %zu is not connected",
                                            fb_bg_kind_name(el->kind), el->name, k + 1));
    int two = el->kind == FB_BG_TF || el->kind == FB_BG_GY || el->kind == FB_BG_MTF;
    if (two && (fb_bg_orientation(bg, el->bonds[0], e) != 1 ||
                fb_bg_orientation(bg, el->bonds[1], e) != -1))
      return fb_err_set_origin(
          err, FB_ORIGIN_ELEMENT, e,
          fb_err_set(err, FB_EMODEL,
                     "%s '%s': bond '%s' must point into port 1 and bond '%s' out of port "
                     "2 (power flows through a two-port)",
                     fb_bg_kind_name(el->kind), el->name, bg->bonds[el->bonds[0]].name,
                     bg->bonds[el->bonds[1]].name));
    if (el->kind == FB_BG_COMPOSITE) {
      int whole_dir = fb_bg_orientation(bg, el->bonds[el->nports - 1], e);
      for (size_t k = 0; k + 1 < el->nports; ++k)
        /* The part bond's direction is what to turn: it is the origin. */
        if (fb_bg_orientation(bg, el->bonds[k], e) == whole_dir)
          return fb_err_set_origin(
              err, FB_ORIGIN_BOND, el->bonds[k],
              fb_err_set(err, FB_EMODEL,
                         "composite '%s': part bond '%s' and whole bond '%s' must carry "
                         "power in opposite directions",
                         el->name, bg->bonds[el->bonds[k]].name,
                         bg->bonds[el->bonds[el->nports - 1]].name));
    }
  }
  return FB_OK;
}

/* Sets every free port of element e: recv as given; then propagates. */
static int choose(scap *s, size_t e, int recv)
{
  const fb_bg_elem *el = &s->bg->elems[e];
  for (size_t k = 0; k < el->nports; ++k) {
    size_t b = el->bonds[k];
    if (s->bg->bonds[b].stroke == FB_STROKE_UNSET) {
      int rc = set_stroke(s, b, e, recv, e, e);
      if (rc)
        return rc;
    }
  }
  return propagate(s);
}

static int step_sources(scap *s)
{
  for (size_t e = 0; e < s->bg->nelems; ++e) {
    const fb_bg_elem *el = &s->bg->elems[e];
    int rc = FB_OK;
    if (el->kind == FB_BG_SE || el->kind == FB_BG_SF) {
      /* A source's causality is not negotiable: a stroke already set the
       * other way by an earlier source is a conflict. */
      rc = set_stroke(s, el->bonds[0], e, el->kind == FB_BG_SF, e, e);
      if (!rc)
        rc = propagate(s);
    } else if (el->kind == FB_BG_MTF && !is_square_mtf(el)) {
      /* f2 = T f1, e1 = T^T e2: port 2 receives effort, port 1 imposes. */
      rc = set_stroke(s, el->bonds[1], e, 1, e, e);
      if (!rc)
        rc = set_stroke(s, el->bonds[0], e, 0, e, e);
      if (!rc)
        rc = propagate(s);
    }
    if (rc)
      return rc;
  }
  return FB_OK;
}

/* Appends to msg a note for each port of storage element e that is in
 * derivative causality. Returns the number of such ports. */
static size_t note_derivative(const fb_bg *bg, size_t e, char *msg, size_t size)
{
  const fb_bg_elem *el = &bg->elems[e];
  int want = el->kind == FB_BG_I; /* integral: I receives effort, C imposes */
  size_t count = 0;
  for (size_t k = 0; k < el->nports; ++k) {
    size_t b = el->bonds[k];
    if (fb_bg_receives_effort(bg, b, e) == want)
      continue;
    char cause[160];
    fb_bg_describe(bg, bg->bonds[b].cause, cause, sizeof cause);
    size_t len = strlen(msg);
    snprintf(msg + len, size - len,
             "%s%s '%s' is in derivative causality on bond '%s' (its %s is imposed by %s "
             "through the junction structure)",
             len ? "; " : "", fb_bg_kind_name(el->kind), el->name, bg->bonds[b].name,
             el->kind == FB_BG_I ? "flow" : "effort", cause);
    count++;
  }
  return count;
}

static int step_storage(scap *s)
{
  char msg[FB_ERR_MSG_MAX] = "";
  size_t nderiv = 0, first = 0;
  for (size_t e = 0; e < s->bg->nelems; ++e) {
    const fb_bg_elem *el = &s->bg->elems[e];
    if (el->kind != FB_BG_I && el->kind != FB_BG_C)
      continue;
    int rc = choose(s, e, el->kind == FB_BG_I);
    if (rc)
      return rc;
    const size_t n = note_derivative(s->bg, e, msg, sizeof msg);
    first = nderiv == 0 && n > 0 ? e : first;
    nderiv += n;
  }
  /* The first element in derivative causality is the origin. */
  if (nderiv)
    return fb_err_set_origin(
        s->err, FB_ORIGIN_ELEMENT, first,
        fb_err_set(s->err, FB_ECAUSAL,
                   "%s. Hint: dependent storage elements; add a compliance (C) or inertia "
                   "(I) between them, or merge them into one element",
                   msg));
  return FB_OK;
}

/* Resistors: keep one causality per field, that of an already forced
 * port if any, else resistance causality (e = R f). */
static int step_resistors(scap *s)
{
  for (size_t e = 0; e < s->bg->nelems; ++e) {
    const fb_bg_elem *el = &s->bg->elems[e];
    if (el->kind != FB_BG_R)
      continue;
    int recv = 0;
    for (size_t k = 0; k < el->nports; ++k)
      if (s->bg->bonds[el->bonds[k]].stroke != FB_STROKE_UNSET) {
        recv = fb_bg_receives_effort(s->bg, el->bonds[k], e);
        break;
      }
    int rc = choose(s, e, recv);
    if (rc)
      return rc;
  }
  return FB_OK;
}

static int step_remaining(scap *s)
{
  for (size_t b = 0; b < s->bg->nbonds; ++b) {
    if (s->bg->bonds[b].stroke != FB_STROKE_UNSET)
      continue;
    size_t to = s->bg->bonds[b].to;
    int rc = set_stroke(s, b, to, 1, to, to);
    if (!rc)
      rc = propagate(s);
    if (rc)
      return rc;
  }
  return FB_OK;
}

/* Final check: every junction has exactly one bond in its special role. */
static int check_junctions(const fb_bg *bg, fb_err *err)
{
  for (size_t e = 0; e < bg->nelems; ++e) {
    const fb_bg_elem *el = &bg->elems[e];
    if ((el->kind != FB_BG_J0 && el->kind != FB_BG_J1) || el->nports == 0)
      continue;
    int special_recv = el->kind == FB_BG_J0;
    size_t n = 0;
    for (size_t k = 0; k < el->nports; ++k)
      n += fb_bg_receives_effort(bg, el->bonds[k], e) == special_recv;
    if (n != 1)
      return fb_err_set_origin(err, FB_ORIGIN_ELEMENT, e,
                               fb_err_set(err, FB_ECAUSAL,
                                          "%s '%s': %zu bonds set its common %s (need 1)",
                                          fb_bg_kind_name(el->kind), el->name, n,
                                          el->kind == FB_BG_J0 ? "effort" : "flow"));
  }
  return FB_OK;
}

int fb_bg_assign_causality(fb_bg *bg, fb_err *err)
{
  if (bg->causal)
    return FB_OK;
  int rc = check_structure(bg, err);
  if (rc)
    return rc;
  for (size_t b = 0; b < bg->nbonds; ++b) {
    bg->bonds[b].stroke = FB_STROKE_UNSET;
    bg->bonds[b].cause = FB_NONE;
  }
  scap s = {bg, NULL, 0, NULL, err};
  s.queue = malloc((bg->nelems + 1) * sizeof *s.queue);
  s.queued = calloc(bg->nelems + 1, 1);
  if (!s.queue || !s.queued)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory assigning causality");
  if (!rc)
    rc = step_sources(&s);
  if (!rc)
    rc = step_storage(&s);
  if (!rc)
    rc = step_resistors(&s);
  if (!rc)
    rc = step_remaining(&s);
  if (!rc)
    rc = check_junctions(bg, err);
  free(s.queue);
  free(s.queued);
  if (rc) {
    for (size_t b = 0; b < bg->nbonds; ++b)
      bg->bonds[b].stroke = FB_STROKE_UNSET;
    return rc;
  }
  bg->causal = 1;
  return FB_OK;
}
