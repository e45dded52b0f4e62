/* SPDX-License-Identifier: BSD-3-Clause */
/* The tire gallery's bilateral tire: the paper's linear spring and
 * damper, always attached (so the reaction may become tensile). */
#include "flexbond/tire.h"

#include "vehicle/vehicle_internal.h"

static int bilateral_build(const void *params, const fb_tire_context *ctx, fb_bg *bg,
                           fb_err *err)
{
  (void)params;
  int rc = vehicle_add_scalar(bg, "tire_spring", FB_BG_C, ctx->tire_k, err);
  return rc ? rc : vehicle_add_scalar(bg, "tire_damper", FB_BG_R, ctx->tire_c, err);
}

static const fb_tire_model_ops bilateral_ops = {.build = bilateral_build};

const fb_tire_model fb_tire_model_bilateral = {
    .name = "bilateral",
    .doc = "the paper's linear tire",
    .meaning = "linear (the paper's): a negative reaction means the tire would have left the "
               "road",
    .pulls = 1,
    .ops = &bilateral_ops,
};
