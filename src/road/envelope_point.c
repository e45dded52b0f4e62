/* SPDX-License-Identifier: BSD-3-Clause */
/* The envelope gallery's point contact: the tire meets the road at the
 * point under its centre, the road as it is (the default). */
#include <stddef.h>

#include "flexbond/envelope.h"

static double point_reach(const void *params, const fb_envelope_context *ctx)
{
  (void)params;
  (void)ctx;
  return 0.0;
}

/* The samples themselves; the slope by central differences (one-sided at
 * the ends). fb_envelope_sample reads the road's own slope instead. */
static int point_filter(const void *params, const fb_envelope_context *ctx, const double *z,
                        size_t n, double ds, double *w, double *beta, fb_err *err)
{
  (void)params;
  (void)ctx;
  (void)err;
  for (size_t i = 0; i < n; ++i)
    w[i] = z[i];
  for (size_t i = 0; beta && n > 1 && i < n; ++i) {
    const size_t lo = i > 0 ? i - 1 : 0, hi = i + 1 < n ? i + 1 : n - 1;
    beta[i] = (z[hi] - z[lo]) / ((double)(hi - lo) * ds);
  }
  return FB_OK;
}

static const fb_envelope_model_ops point_ops = {.reach = point_reach, .filter = point_filter};

const fb_envelope_model fb_envelope_model_point = {
    .name = "point",
    .doc = "point contact: the road height under the wheel centre (the paper's)",
    .ops = &point_ops,
};
