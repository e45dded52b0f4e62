/* SPDX-License-Identifier: BSD-3-Clause */
/* The damper gallery's table law: force against velocity at knots, the
 * monotone cubic Hermite interpolant (Fritsch & Carlson 1980; src/bg/
 * table_law.c), passive (F v >= 0). Its knots are a list of variable
 * length, so it declares no scalar parameters: a front end fills its
 * block (fb_damper_table_params) from its own shape of table. */
#include <math.h>
#include <stdio.h>

#include "flexbond/damper.h"

/* A table of 2 .. FB_DAMPER_MAX_POINTS knots through fb_table_law, the
 * law's own check of order and passivity. *law new on success. */
static int table_law(const fb_damper_table_params *p, const char *corner, fb_table_law **law,
                     fb_err *err)
{
  *law = NULL;
  if (p->npoints < 2 || p->npoints > FB_DAMPER_MAX_POINTS)
    return fb_err_set(err, FB_EINVAL,
                      "corner '%s': a damper table has 2 to %d points (got %zu)",
                      corner ? corner : "?", (int)FB_DAMPER_MAX_POINTS, p->npoints),
           fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "npoints"), FB_EINVAL;
  int rc = fb_table_law_new(p->npoints, p->velocity, p->force, law, err);
  if (!rc)
    rc = fb_table_law_check_passive(*law, err);
  if (rc)
    fb_table_law_free(law);
  return rc;
}

static int table_check(const void *params, const char *corner, fb_err *err)
{
  fb_table_law *law = NULL;
  const int rc = table_law(params, corner, &law, err);
  fb_table_law_free(&law);
  return rc;
}

static int table_build(const void *params, fb_bg *bg, fb_err *err)
{
  fb_table_law *law = NULL;
  const int rc = table_law(params, NULL, &law, err);
  return rc ? rc : fb_bg_add_r_table(bg, "damper", &law, err);
}

/* The interpolant's value; NaN for a table that does not check. */
static double table_force(const void *params, double v)
{
  fb_table_law *law = NULL;
  if (table_law(params, NULL, &law, NULL))
    return NAN;
  const double f = fb_table_law_eval(law, v, NULL);
  fb_table_law_free(&law);
  return f;
}

/* Its knots' count and its two end knots, which tell tables apart. */
static void table_describe(const void *params, char *buf, size_t size)
{
  const fb_damper_table_params *p = params;
  if (p->npoints < 2 || p->npoints > FB_DAMPER_MAX_POINTS) {
    snprintf(buf, size, "a force-velocity table of %zu points", p->npoints);
    return;
  }
  const size_t last = p->npoints - 1;
  snprintf(buf, size, "a force-velocity table of %zu points, %g N at %g m/s to %g N at %g m/s",
           p->npoints, p->force[0], p->velocity[0], p->force[last], p->velocity[last]);
}

/* linear NULL: a linear analysis linearises the table at the static
 * equilibrium (its slope there), as fb_vehicle_linearise does for any
 * nonlinear law. */
static const fb_damper_law_ops table_ops = {.check = table_check,
                                            .build = table_build,
                                            .force = table_force,
                                            .describe = table_describe};

const fb_damper_law fb_damper_law_table = {
    .name = "table",
    .doc = "a passive force-velocity table (2 to 64 points), interpolated with a continuous "
           "slope",
    .meaning =
        "a force-velocity table, linearised at the static equilibrium by linear analyses",
    .params_size = sizeof(fb_damper_table_params),
    .ops = &table_ops,
};
