/* SPDX-License-Identifier: BSD-3-Clause */
/* The tire gallery's Hunt-Crossley tire (Hunt & Crossley, J. Appl. Mech.
 * 42(2), 1975; fb_bg_add_hunt_crossley_contact): unilateral, with a
 * damping tire_c q / deflection_ref that grows from zero at first contact
 * and is tire_c at the reference deflection. */
#include <math.h>
#include <stddef.h>

#include "flexbond/tire.h"

static const fb_param hunt_crossley_params[] = {
    {.name = "deflection_ref",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_tire_hunt_crossley_params, deflection_ref),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_OPTIONAL,
     .doc = "the deflection at which the damping is `tire_c` (default: the static deflection "
            "under an equal share of the weight)",
     .plausible_lo = 1e-4,
     .plausible_hi = 0.3,
     .plausible_why = "a loaded tire deflects 0.1 mm to 0.3 m"},
};

/* Left out until given: the static deflection then. */
static void hunt_crossley_init(void *params)
{
  ((fb_tire_hunt_crossley_params *)params)->deflection_ref = NAN;
}

static double hunt_crossley_ref(const fb_tire_hunt_crossley_params *p,
                                const fb_tire_context *ctx)
{
  return isnan(p->deflection_ref) ? ctx->static_deflection : p->deflection_ref;
}

/* Without a deflection of its own, the corner's static one must be > 0
 * (a caller of fb_vehicle_corner sets it). */
static int hunt_crossley_check(const void *params, const fb_tire_context *ctx, fb_err *err)
{
  const double ref = hunt_crossley_ref(params, ctx);
  if (ref > 0.0 && isfinite(ref))
    return FB_OK;
  return fb_err_set(err, FB_EINVAL,
                    "corner '%s': a Hunt-Crossley tire needs a reference deflection > 0 "
                    "(got %g m)",
                    ctx->corner ? ctx->corner : "?", ref),
         fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "deflection_ref"), FB_EINVAL;
}

/* lambda = tire_c / deflection_ref, N s/m^2. */
static int hunt_crossley_build(const void *params, const fb_tire_context *ctx, fb_bg *bg,
                               fb_err *err)
{
  const int rc = hunt_crossley_check(params, ctx, err);
  return rc ? rc
            : fb_bg_add_hunt_crossley_contact(bg, "tire_spring", "tire_damper", ctx->tire_k,
                                              ctx->tire_c / hunt_crossley_ref(params, ctx),
                                              err);
}

static const fb_tire_model_ops hunt_crossley_ops = {
    .init = hunt_crossley_init, .check = hunt_crossley_check, .build = hunt_crossley_build};

const fb_tire_model fb_tire_model_hunt_crossley = {
    .name = "hunt_crossley",
    .doc = "unilateral, with a damping that grows with the deflection (Hunt & Crossley "
           "1975): `tire_c` at `deflection_ref`, 0 at first contact",
    .meaning = "unilateral, its damping growing from zero at first contact to tire_c at the "
               "reference deflection (Hunt-Crossley)",
    .soft_landing = 1,
    .param = hunt_crossley_params,
    .nparams = sizeof hunt_crossley_params / sizeof hunt_crossley_params[0],
    .params_size = sizeof(fb_tire_hunt_crossley_params),
    .ops = &hunt_crossley_ops,
};
