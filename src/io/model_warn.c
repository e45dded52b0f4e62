/* SPDX-License-Identifier: BSD-3-Clause */
/* Warnings of the model loader: what a file may legally say but almost
 * never means. */
#include <stdlib.h>
#include <string.h>

#include "../core/util.h"
#include "model_internal.h"

void ml_warnings_release(ml_warnings *w)
{
  free(w->warning);
  *w = (ml_warnings){0};
}

/* One bond written in the file that points out of a storage or resistive
 * element, with the number of instances that repeat it. */
typedef struct power_out {
  const ml_site *site;
  size_t bond, count;
} power_out;

/* The entry of out for the place site was written at, or NULL: the bonds
 * of instances of one definition share it. */
static power_out *power_out_find(power_out *out, size_t n, const ml_site *site)
{
  for (size_t i = 0; i < n; ++i)
    if (out[i].site->line == site->line && out[i].site->column == site->column &&
        !strcmp(out[i].site->key, site->key))
      return &out[i];
  return NULL;
}

/* The bonds of bg whose from end is an I, C or R, each written once. */
static int power_out_collect(const fb_bg *bg, const ml_sites *sites, power_out **out, size_t *n,
                             fb_err *err)
{
  size_t cap = 0;
  for (size_t b = 0; b < fb_bg_nbonds(bg); ++b) {
    const fb_bg_kind kind = fb_bg_element_kind(bg, fb_bg_bond_from(bg, b));
    if (kind != FB_BG_I && kind != FB_BG_C && kind != FB_BG_R)
      continue;
    const ml_site *site = ml_sites_find(sites, FB_ORIGIN_BOND, fb_bg_bond_name(bg, b));
    if (!site)
      continue; /* not written in the file: nothing to point at */
    power_out *seen = power_out_find(*out, *n, site);
    if (seen) {
      ++seen->count;
      continue;
    }
    if (fb_grow((void **)out, &cap, *n, sizeof **out) != FB_OK)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    (*out)[(*n)++] = (power_out){site, b, 1};
  }
  return FB_OK;
}

/* What reads with the opposite sign for an element of kind. flexbond
 * applies a law to the power flowing into its element whichever way the
 * bond is drawn (the orientation of fb_bg): a linear law is odd, so the
 * motion is the same and only the readings differ from the usual drawing;
 * a nonlinear one (a table, a contact) sees its input reversed. */
static const char *power_out_readings(fb_bg_kind kind)
{
  switch (kind) {
  case FB_BG_C: return "its state (the deflection), the bond's effort and the bond's power";
  case FB_BG_I: return "its state (the momentum), the bond's effort and the bond's power";
  default: return "the bond's effort and the bond's power";
  }
}

/* The warning for one entry: where, what, why it matters, how to mend. */
static void power_out_describe(const fb_bg *bg, const ml_sites *sites, const power_out *p,
                               fb_err *w)
{
  const size_t e = fb_bg_bond_from(bg, p->bond);
  const fb_bg_kind kind = fb_bg_element_kind(bg, e);
  /* The name the file gives it: inside a definition, without the
   * instance prefix ("front.K" is written "K"). */
  const char *full = fb_bg_element_name(bg, e);
  const char *dot = strrchr(full, '.');
  const char *local = dot ? dot + 1 : full;
  char port[64] = "";
  if (fb_bg_element_nports(bg, e) > 1)
    snprintf(port, sizeof port, "port %zu of ", fb_bg_bond_from_port(bg, p->bond) + 1);
  char more[64] = "", head[1024];
  ml_site_head(sites, p->site, head, sizeof head);
  fb_err_clear(w);
  if (p->count > 1)
    snprintf(more, sizeof more, " (and %zu more instances)", p->count - 1);
  const fb_law_ops *law = fb_bg_element_law(bg, e, NULL);
  if (law)
    fb_err_set(w, FB_EMODEL,
               "%sbond '%s' points out of %s%s '%s': its law (%s) is applied to the power "
               "flowing into it, so it sees its input reversed (an R's flow, a C's state): "
               "compression and "
               "extension swap, and the motion differs from the usual drawing unless the law "
               "is odd; write the bond with '%s' at its 'to' end%s%s",
               head, fb_bg_bond_name(bg, p->bond), port, fb_bg_kind_name(kind), full, law->name,
               local, p->site->tail, more);
  else
    fb_err_set(w, FB_EMODEL,
               "%sbond '%s' points out of %s%s '%s': the motion is the same, but %s read "
               "with the opposite sign to the usual drawing (the power is what '%s' gives "
               "out, negative while it %s energy); write the bond with '%s' at its 'to' "
               "end%s%s",
               head, fb_bg_bond_name(bg, p->bond), port, fb_bg_kind_name(kind), full,
               power_out_readings(kind), local, kind == FB_BG_R ? "dissipates" : "stores",
               local, p->site->tail, more);
  ml_site_set_fields(sites, p->site, w);
}

int ml_warn_power_out(const fb_bg *bg, const ml_sites *sites, ml_warnings *w, fb_err *err)
{
  power_out *out = NULL;
  size_t n = 0;
  int rc = power_out_collect(bg, sites, &out, &n, err);
  for (size_t i = 0; !rc && i < n; ++i) {
    rc = fb_grow((void **)&w->warning, &w->cap, w->n, sizeof *w->warning);
    if (rc)
      fb_err_set(err, rc, "out of memory");
    else
      power_out_describe(bg, sites, &out[i], &w->warning[w->n++]);
  }
  free(out);
  return rc;
}
