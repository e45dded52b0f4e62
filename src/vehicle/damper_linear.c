/* SPDX-License-Identifier: BSD-3-Clause */
/* The damper gallery's linear law: the paper's shock absorber, F = c v. */
#include <stddef.h>
#include <stdio.h>

#include "flexbond/damper.h"

#include "vehicle/vehicle_internal.h"

static const fb_param linear_params[] = {
    {.name = "c",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_damper_linear_params, c),
     .unit = "N s/m",
     .range = FB_RANGE_LO,
     .lo = 0.0,
     .need = FB_PARAM_REQUIRED,
     .doc = "the force per unit travel rate",
     .why = "a passive damper dissipates: F v >= 0",
     .plausible_lo = 1e2,
     .plausible_hi = 1e6,
     .plausible_why = "a vehicle's shock absorber is 1e2 to 1e6 N s/m"},
};

static int linear_build(const void *params, fb_bg *bg, fb_err *err)
{
  const fb_damper_linear_params *p = params;
  return vehicle_add_scalar(bg, "damper", FB_BG_R, p->c, err);
}

static double linear_force(const void *params, double v)
{
  return ((const fb_damper_linear_params *)params)->c * v;
}

static int linear_linear(const void *params)
{
  (void)params;
  return 1;
}

static void linear_describe(const void *params, char *buf, size_t size)
{
  snprintf(buf, size, "linear, %g N s/m", ((const fb_damper_linear_params *)params)->c);
}

static const fb_damper_law_ops linear_ops = {.build = linear_build,
                                             .force = linear_force,
                                             .linear = linear_linear,
                                             .describe = linear_describe};

const fb_damper_law fb_damper_law_linear = {
    .name = "linear",
    .doc = "the paper's linear shock absorber, F = c v",
    .meaning = "linear (the paper's): a force proportional to the travel rate",
    .param = linear_params,
    .nparams = sizeof linear_params / sizeof linear_params[0],
    .params_size = sizeof(fb_damper_linear_params),
    .ops = &linear_ops,
};
