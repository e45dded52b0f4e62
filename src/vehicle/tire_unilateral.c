/* SPDX-License-Identifier: BSD-3-Clause */
/* The tire gallery's unilateral tire: the linear pair unable to pull, so
 * that the wheel may leave the road (fb_bg_add_unilateral_contact). */
#include "flexbond/tire.h"

static int unilateral_build(const void *params, const fb_tire_context *ctx, fb_bg *bg,
                            fb_err *err)
{
  (void)params;
  return fb_bg_add_unilateral_contact(bg, "tire_spring", "tire_damper", ctx->tire_k,
                                      ctx->tire_c, err);
}

static const fb_tire_model_ops unilateral_ops = {.build = unilateral_build};

/* In contact, at rest, its laws are the bilateral pair's (mode 0 of
 * both): that branch is its linear model. */
const fb_tire_model fb_tire_model_unilateral = {
    .name = "unilateral",
    .doc = "it never pulls, the wheel may leave the road",
    .meaning = "one-sided: it pushes but never pulls, and a wheel whose reaction would "
               "become tensile leaves the road until it lands again",
    .in_contact = &fb_tire_model_bilateral,
    .ops = &unilateral_ops,
};
