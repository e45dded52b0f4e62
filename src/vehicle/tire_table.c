/* SPDX-License-Identifier: BSD-3-Clause */
/* The tire gallery's table tire: the unilateral tire with its spring's
 * force a measured force-deflection curve (fb_bg_add_table_contact), the
 * monotone cubic Hermite interpolant of its knots (Fritsch & Carlson
 * 1980), leaving the road where its force would become tensile. Its
 * knots are a list of variable length, so it declares no scalar
 * parameters: a front end fills its block (fb_tire_table_params). */
#include <stdio.h>

#include "flexbond/tire.h"

/* The block's table as a law, *law new on success; errors name the
 * block's table ("table"). */
static int table_law(const fb_tire_table_params *p, const fb_tire_context *ctx,
                     fb_table_law **law, fb_err *err)
{
  *law = NULL;
  const char *corner = ctx->corner ? ctx->corner : "?";
  int rc = FB_OK;
  if (p->npoints < 2 || p->npoints > FB_TIRE_MAX_POINTS)
    rc = fb_err_set(err, FB_EINVAL, "corner '%s': a tire table has 2 to %d points (got %zu)",
                    corner, (int)FB_TIRE_MAX_POINTS, p->npoints);
  else if (p->deflection[0] != 0.0 || p->force[0] != 0.0)
    rc = fb_err_set(err, FB_EINVAL,
                    "corner '%s': a tire table starts at (0, 0), where the tire touches the "
                    "road (got (%g, %g))",
                    corner, p->deflection[0], p->force[0]);
  if (!rc)
    rc = fb_table_law_new(p->npoints, p->deflection, p->force, law, err);
  if (!rc)
    rc = fb_table_law_check_monotone(*law, err);
  if (!rc && !(p->force[p->npoints - 1] > 0.0))
    rc = fb_err_set(err, FB_EINVAL, "corner '%s': a tire table's forces are all 0", corner);
  if (rc) {
    fb_table_law_free(law);
    fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "tire_table");
  }
  return rc;
}

static int tire_table_check(const void *params, const fb_tire_context *ctx, fb_err *err)
{
  fb_table_law *law = NULL;
  const int rc = table_law(params, ctx, &law, err);
  fb_table_law_free(&law);
  return rc;
}

static int tire_table_build(const void *params, const fb_tire_context *ctx, fb_bg *bg,
                            fb_err *err)
{
  fb_table_law *law = NULL;
  int rc = table_law(params, ctx, &law, err);
  if (!rc)
    rc = fb_bg_add_table_contact(bg, "tire_spring", "tire_damper", law, ctx->tire_c, err);
  fb_table_law_free(&law);
  return rc;
}

static const fb_tire_model_ops tire_table_ops = {.check = tire_table_check,
                                                 .build = tire_table_build};

/* Linear analyses linearise it at the static equilibrium, in contact: the
 * table's slope there. */
const fb_tire_model fb_tire_model_table = {
    .name = "table",
    .doc = "unilateral, its force a force-deflection table, damped by `tire_c` in contact",
    .meaning = "unilateral, its force a force-deflection table: it pushes but never pulls, and "
               "a wheel whose reaction would become tensile leaves the road",
    .params_size = sizeof(fb_tire_table_params),
    .ops = &tire_table_ops,
};
