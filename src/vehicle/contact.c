/* SPDX-License-Identifier: BSD-3-Clause */
/* Tire contact verdict (see fb_vehicle_contact_loss in
 * flexbond/vehicle.h): the paper checks by eye that the normal reactions
 * never become tensile; this lists where a tire carries no load. */
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/vehicle.h"

#include "core/util.h"

/* Time at which the reaction crosses zero between samples k - 1 and k
 * (linear interpolation). */
static double crossing(const fb_result *r, size_t col, size_t k)
{
  const double *a = fb_result_row(r, k - 1), *b = fb_result_row(r, k);
  const double fa = a[col], fb = b[col];
  return fa == fb ? b[0] : a[0] + (b[0] - a[0]) * fa / (fa - fb);
}

/* Appends the intervals of one corner's column. */
static int corner_intervals(const fb_result *r, size_t col, int corner, fb_contact_loss **out,
                            size_t *n, size_t *cap)
{
  const size_t ns = fb_result_nsamples(r);
  fb_contact_loss cur = {0};
  int open = 0;
  for (size_t k = 0; k < ns; ++k) {
    const double *row = fb_result_row(r, k);
    const double f = row[col];
    if (f <= 0.0 && !open) {
      open = 1;
      cur = (fb_contact_loss){corner, k ? crossing(r, col, k) : row[0], row[0], f, row[0]};
    }
    if (open && f < cur.min_force) {
      cur.min_force = f;
      cur.t_min = row[0];
    }
    if (open && (f > 0.0 || k + 1 == ns)) {
      cur.t_end = f > 0.0 ? crossing(r, col, k) : row[0];
      open = 0;
      /* A reaction that only touches zero (at the zero start, t = 0) is
       * not an interval. */
      if (cur.t_end <= cur.t_start)
        continue;
      if (fb_grow((void **)out, cap, *n, sizeof **out) != FB_OK)
        return FB_ENOMEM;
      (*out)[(*n)++] = cur;
    }
  }
  return FB_OK;
}

int fb_vehicle_contact_loss(const fb_scenario *s, const fb_result *r, fb_contact_loss **out,
                            size_t *n, fb_err *err)
{
  *out = NULL;
  *n = 0;
  size_t cap = 0;
  for (size_t c = 0; c < s->ncorners; ++c) {
    char name[FB_ERR_KEY_MAX];
    snprintf(name, sizeof name, "contact_force_%s", s->corner[c].name);
    const long col = fb_result_find(r, name);
    if (col < 1) {
      free(*out);
      *out = NULL;
      *n = 0;
      return fb_err_set(err, FB_EINVAL, "tire contact: the result has no column '%s'", name);
    }
    if (corner_intervals(r, (size_t)col, (int)c, out, n, &cap) != FB_OK) {
      free(*out);
      *out = NULL;
      *n = 0;
      return fb_err_set(err, FB_ENOMEM, "out of memory listing the intervals of contact loss");
    }
  }
  return FB_OK;
}
