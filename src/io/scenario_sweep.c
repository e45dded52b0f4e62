/* SPDX-License-Identifier: BSD-3-Clause */
/* A sweep's cases read from a scenario document (flexbond/io.h,
 * fb_scenario_sweep_ops): the study layer runs the sweep and asks the
 * front end for each case's scenario; this is that front end's part for a
 * file or a text, each case read with its overrides as any load is. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/io.h"
#include "flexbond/vehicle.h"

/* "NAME['KEY']=VALUE" of each case override into labels (n of them, each
 * its own allocation), as a caller names its axes; NULL for none. */
static char **case_labels(const char *name, const fb_scenario_override *ov, size_t n)
{
  char **labels = calloc(n ? n : 1, sizeof *labels);
  for (size_t k = 0; labels && k < n; ++k) {
    const int len = snprintf(NULL, 0, "%s['%s']=%s", name, ov[k].key, ov[k].value);
    labels[k] = len >= 0 ? malloc((size_t)len + 1) : NULL;
    if (labels[k])
      snprintf(labels[k], (size_t)len + 1, "%s['%s']=%s", name, ov[k].key, ov[k].value);
  }
  return labels;
}

static void free_labels(char **labels, size_t n)
{
  for (size_t k = 0; labels && k < n; ++k)
    free(labels[k]);
  free(labels);
}

/* fb_study_sweep_ops.load: the source's overrides, then the case's. */
static int load_case(void *ctx, size_t i, const fb_scenario_override *ov, size_t n,
                     fb_scenario **out, fb_err *err)
{
  (void)i;
  const fb_scenario_sweep_source *src = ctx;
  const size_t total = src->noverrides + n;
  fb_scenario_override *all = malloc((total ? total : 1) * sizeof *all);
  char **labels = src->axes_name ? case_labels(src->axes_name, ov, n) : NULL;
  if (!all || (src->axes_name && !labels)) {
    free(all);
    free_labels(labels, n);
    return fb_err_set(err, FB_ENOMEM, "out of memory for a case's overrides");
  }
  if (src->noverrides)
    memcpy(all, src->overrides, src->noverrides * sizeof *all);
  for (size_t k = 0; k < n; ++k) {
    all[src->noverrides + k] = ov[k];
    if (labels) /* a label lost to memory: the default one */
      all[src->noverrides + k].label = labels[k];
  }
  const fb_scenario_load_opts opts = {.overrides = all, .noverrides = total};
  const int rc = src->path ? fb_scenario_load_with(src->path, &opts, out, err)
                           : fb_scenario_load_string_with(src->text, src->len,
                                                          src->display_name, &opts, out, err);
  free(all);
  free_labels(labels, n);
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
