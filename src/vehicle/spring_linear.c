/* SPDX-License-Identifier: BSD-3-Clause */
/* The spring gallery's linear law: the paper's suspension spring,
 * F = preload + spring_k x, its rate the corner's spring_k. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/spring.h"

#include "vehicle/vehicle_internal.h"

static const fb_param linear_params[] = {
    {.name = "preload",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_spring_linear_params, preload),
     .unit = "N",
     .need = FB_PARAM_DEFAULT,
     .def = 0.0,
     .doc = "the force at zero travel, compression positive (0: the paper's spring)",
     .plausible_lo = -1e6,
     .plausible_hi = 1e6,
     .plausible_why = "a suspension spring's preload is at most a few hundred kN"},
};

/* e = preload + k q; the energy preload q + k q^2 / 2, 0 at zero travel. */
typedef struct affine_spring {
  double preload, k;
} affine_spring;

static int affine_eval(void *ctx, const fb_law_in *in, double *y)
{
  const affine_spring *a = ctx;
  y[0] = a->preload + a->k * in->x[0];
  return 0;
}

static int affine_jacobian(void *ctx, const fb_law_in *in, double *jac)
{
  (void)in;
  jac[0] = ((const affine_spring *)ctx)->k;
  return 0;
}

static double affine_energy(void *ctx, size_t n, const double *x)
{
  const affine_spring *a = ctx;
  (void)n;
  return x[0] * (a->preload + 0.5 * a->k * x[0]);
}

static const fb_law_ops affine_ops = {.name = "preloaded spring",
                                      .eval = affine_eval,
                                      .jacobian = affine_jacobian,
                                      .energy = affine_energy,
                                      .free = free,
                                      .affine = 1};

/* Without a preload the paper's linear C element, so that a description
 * that gives none builds the very same graph. */
static int linear_build(const void *params, const fb_spring_context *ctx, fb_bg *bg,
                        fb_err *err)
{
  static const size_t one_port[1] = {1};
  const fb_spring_linear_params *p = params;
  if (p->preload == 0.0)
    return vehicle_add_scalar(bg, "spring", FB_BG_C, ctx->spring_k, err);
  affine_spring *a = malloc(sizeof *a);
  if (!a)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  *a = (affine_spring){p->preload, ctx->spring_k};
  return fb_bg_add_field_law(bg, "spring", FB_BG_C, 1, one_port, &affine_ops, a, err);
}

static double linear_force(const void *params, const fb_spring_context *ctx, double x)
{
  return ((const fb_spring_linear_params *)params)->preload + ctx->spring_k * x;
}

static void linear_describe(const void *params, const fb_spring_context *ctx, char *buf,
                            size_t size)
{
  const double preload = ((const fb_spring_linear_params *)params)->preload;
  if (preload == 0.0)
    snprintf(buf, size, "linear, %g N/m", ctx->spring_k);
  else
    snprintf(buf, size, "linear, %g N/m, preload %g N", ctx->spring_k, preload);
}

static const fb_spring_law_ops linear_ops = {
    .build = linear_build, .force = linear_force, .describe = linear_describe};

const fb_spring_law fb_spring_law_linear = {
    .name = "linear",
    .doc = "the paper's linear spring of rate `spring_k`, F = preload + spring_k x",
    .meaning = "linear (the paper's): a force growing with the travel at the rate spring_k",
    .param = linear_params,
    .nparams = sizeof linear_params / sizeof linear_params[0],
    .params_size = sizeof(fb_spring_linear_params),
    .ops = &linear_ops,
};
