/* SPDX-License-Identifier: BSD-3-Clause */
/* The `contact` element of model files: a spring and a damper in
 * parallel that can push but never pull, e.g. a tire on the road
 * (fb_bg_add_unilateral_contact in flexbond/bg.h; docs/model-format.md,
 * "Unilateral contact"). One entry makes two elements: the C named by
 * `name` and the modulated R named by `damper`, both one-ports that the
 * model bonds to one 1-junction. */
#include <string.h>

#include "io/model_internal.h"

/* The damper's name: a new name of the scope, not the spring's. */
static int ml_contact_damper(const ml_ctx *c, const ml_scope *s, struct fy_node *el,
                             const char *spring, const char **damper, struct fy_node **at)
{
  int rc = ml_require(c, el, "damper", at);
  if (!rc)
    rc = ml_name(c, *at, "element name", damper);
  if (rc)
    return rc;
  const ml_entry *first = ml_scope_find(s, *damper);
  if (first)
    return ml_fail(c, *at, FB_EMODEL, "duplicate element name '%s' (first defined at line %d)",
                   *damper, ml_line(first->node));
  if (!strcmp(*damper, spring))
    return ml_fail(c, *at, FB_EMODEL, "the damper needs a name of its own, not '%s'", spring);
  return FB_OK;
}

/* The damping: `c` (N s/m, Kelvin-Voigt, default 0) or `lambda` (N s/m^2,
 * Hunt-Crossley), not both. */
static int ml_contact_damping(const ml_ctx *c, const ml_scope *s, struct fy_node *el,
                              double *cd, double *lambda)
{
  struct fy_node *ckey = NULL, *lkey = NULL;
  ml_get(el, "c", &ckey);
  struct fy_node *lv = ml_get(el, "lambda", &lkey);
  if (ckey && lkey)
    return ml_fail_key(c, el, lkey, FB_EPARSE,
                       "give the damping as c (N s/m, a constant coefficient) or lambda "
                       "(N s/m^2, Hunt-Crossley: c = lambda q), not both");
  int rc = ml_opt_number(c, el, "c", s->syms, cd);
  if (!rc && !(*cd >= 0))
    rc = ml_fail(c, ml_get(el, "c", NULL), FB_EINVAL, "must be >= 0 (got %g)", *cd);
  if (!rc)
    rc = ml_opt_number(c, el, "lambda", s->syms, lambda);
  if (!rc && !(*lambda >= 0))
    rc = ml_fail(c, lv, FB_EINVAL, "must be >= 0 (got %g)", *lambda);
  return rc;
}

int ml_contact(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *name, ml_entry *e)
{
  struct fy_node *kv = NULL, *dv = NULL;
  const char *damper = NULL;
  double k = 0, cd = 0, lambda = 0;
  e->kind = FB_BG_C;
  e->nports = 1;
  int rc = ml_require(c, el, "k", &kv);
  if (!rc)
    rc = ml_number(c, kv, s->syms, &k);
  if (!rc && !(k > 0))
    rc = ml_fail(c, kv, FB_EINVAL, "must be > 0 (got %g)", k);
  if (!rc)
    rc = ml_contact_damping(c, s, el, &cd, &lambda);
  if (!rc)
    rc = ml_contact_damper(c, s, el, name, &damper, &dv);
  if (!rc &&
      (lambda > 0 ? fb_bg_add_hunt_crossley_contact(s->bg, name, damper, k, lambda, c->err)
                  : fb_bg_add_unilateral_contact(s->bg, name, damper, k, cd, c->err)))
    rc = ml_blame(c, el);
  const ml_entry d = {damper, FB_BG_R, 1, -1, el};
  if (!rc)
    rc = ml_scope_add(c, s, &d);
  if (!rc)
    rc = ml_site_record(c, FB_ORIGIN_ELEMENT, damper, dv);
  return rc;
}
