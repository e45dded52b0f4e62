/* SPDX-License-Identifier: BSD-3-Clause */
/* A sweep's cases read from a scenario document (flexbond/io.h,
 * fb_scenario_sweep_ops): the study layer runs the sweep and asks the
 * front end for each case's scenario; this is that front end's part for a
 * file or a text, each case read with its overrides as any load is. */
#include <stdlib.h>
#include <string.h>

#include "flexbond/io.h"
#include "flexbond/vehicle.h"

/* fb_study_sweep_ops.load: the source's overrides, then the case's. */
static int load_case(void *ctx, size_t i, const fb_scenario_override *ov, size_t n,
                     fb_scenario **out, fb_err *err)
{
  (void)i;
  const fb_scenario_sweep_source *src = ctx;
  const size_t total = src->noverrides + n;
  fb_scenario_override *all = malloc((total ? total : 1) * sizeof *all);
  if (!all)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a case's overrides");
  if (src->noverrides)
    memcpy(all, src->overrides, src->noverrides * sizeof *all);
  if (n)
    memcpy(all + src->noverrides, ov, n * sizeof *all);
  const fb_scenario_load_opts opts = {.overrides = all, .noverrides = total};
  const int rc = src->path ? fb_scenario_load_with(src->path, &opts, out, err)
                           : fb_scenario_load_string_with(src->text, src->len,
                                                          src->display_name, &opts, out, err);
  free(all);
  return rc;
}

static int locate_case(void *ctx, const fb_scenario *s, fb_err *err)
{
  (void)ctx;
  return fb_scenario_locate(s, err);
}

void fb_scenario_sweep_ops(const fb_scenario_sweep_source *src, fb_study_sweep_ops *ops)
{
  /* The study layer takes its context as void *; it never writes through it. */
  *ops = (fb_study_sweep_ops){.load = load_case, .locate = locate_case, .ctx = (void *)src};
}
