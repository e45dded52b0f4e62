/* SPDX-License-Identifier: BSD-3-Clause */
/* The spring gallery's table law: force against travel at knots, the
 * monotone cubic Hermite interpolant (Fritsch & Carlson 1980; src/bg/
 * table_law.c) continued along its end tangents, its values not
 * decreasing (a stable spring). Its preload is its value at zero travel.
 * Its knots are a list of variable length, so it declares no scalar
 * parameters: a front end fills its block (fb_spring_table_params). */
#include <math.h>
#include <stdio.h>

#include "flexbond/spring.h"

/* A table of 2 .. FB_SPRING_MAX_POINTS knots through fb_table_law, the
 * law's own check of order and monotony. *law new on success. */
static int table_law(const fb_spring_table_params *p, const char *corner, fb_table_law **law,
                     fb_err *err)
{
  *law = NULL;
  if (p->npoints < 2 || p->npoints > FB_SPRING_MAX_POINTS)
    return fb_err_set(err, FB_EINVAL,
                      "corner '%s': a spring table has 2 to %d points (got %zu)",
                      corner ? corner : "?", (int)FB_SPRING_MAX_POINTS, p->npoints),
           fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "npoints"), FB_EINVAL;
  int rc = fb_table_law_new(p->npoints, p->travel, p->force, law, err);
  if (!rc)
    rc = fb_table_law_check_monotone(*law, err);
  if (rc) {
    fb_table_law_free(law);
    fb_err_prefix(err, "corner '%s': a spring's ", corner ? corner : "?");
    fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "table");
  }
  return rc;
}

static int table_check(const void *params, const fb_spring_context *ctx, fb_err *err)
{
  fb_table_law *law = NULL;
  const int rc = table_law(params, ctx->corner, &law, err);
  fb_table_law_free(&law);
  return rc;
}

static int table_build(const void *params, const fb_spring_context *ctx, fb_bg *bg, fb_err *err)
{
  fb_table_law *law = NULL;
  const int rc = table_law(params, ctx->corner, &law, err);
  return rc ? rc : fb_bg_add_c_table(bg, "spring", &law, err);
}

/* The interpolant's value; NaN for a table that does not check. */
static double table_force(const void *params, const fb_spring_context *ctx, double x)
{
  fb_table_law *law = NULL;
  if (table_law(params, ctx->corner, &law, NULL))
    return NAN;
  const double f = fb_table_law_eval(law, x, NULL);
  fb_table_law_free(&law);
  return f;
}

/* Its knots' count and its two end knots, which tell tables apart. */
static void table_describe(const void *params, const fb_spring_context *ctx, char *buf,
                           size_t size)
{
  (void)ctx;
  const fb_spring_table_params *p = params;
  if (p->npoints < 2 || p->npoints > FB_SPRING_MAX_POINTS) {
    snprintf(buf, size, "a force-travel table of %zu points", p->npoints);
    return;
  }
  const size_t last = p->npoints - 1;
  snprintf(buf, size, "a force-travel table of %zu points, %g N at %g m to %g N at %g m",
           p->npoints, p->force[0], p->travel[0], p->force[last], p->travel[last]);
}

static const fb_spring_law_ops table_ops = {.check = table_check,
                                            .build = table_build,
                                            .force = table_force,
                                            .describe = table_describe};

const fb_spring_law fb_spring_law_table = {
    .name = "table",
    .doc = "a force-travel table (2 to 64 points, forces not decreasing), interpolated "
           "monotonically with a continuous slope; its preload is its value at 0",
    .meaning = "a force-travel table, linearised at the static equilibrium by linear analyses",
    .params_size = sizeof(fb_spring_table_params),
    .ops = &table_ops,
};
