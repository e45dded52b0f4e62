/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's measured profile from a CSV file (docs/roads.md). */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/road.h"

#include "core/util.h"

static const fb_param profile_params[] = {
    {.name = "file",
     .kind = FB_PARAM_FILE,
     .store = FB_PARAM_STRING,
     .offset = offsetof(fb_road_profile_params, file),
     .need = FB_PARAM_REQUIRED,
     .doc = "CSV with columns `s, z` or `s, z_left, z_right`"},
    {.name = "front_start",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_profile_params, front_start),
     .unit = "m",
     .need = FB_PARAM_DEFAULT,
     .doc = "the first corner's wheel's position on its track at t = 0"},
};

/* Read once, here: the road is made from what was read. */
static int profile_prepare(void *params, fb_err *err)
{
  fb_road_profile_params *p = params;
  fb_road_free(&p->profile);
  const int rc = fb_road_new_csv(p->file, &p->profile, err);
  return rc ? (fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "file"), rc) : FB_OK;
}

static int profile_check(const void *params, const fb_road_layout *l, fb_err *err)
{
  (void)l;
  if (((const fb_road_profile_params *)params)->profile)
    return FB_OK;
  return fb_err_set(err, FB_EINVAL, "the profile was not read (prepare reads it)"),
         fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "file"), FB_EINVAL;
}

static int profile_make(const void *params, const fb_road_layout *l, fb_road **out, fb_err *err)
{
  (void)l;
  return fb_road_clone(((const fb_road_profile_params *)params)->profile, out, err);
}

static double profile_wheel_start(const void *params, const fb_road_layout *l, double x,
                                  double y)
{
  (void)y;
  return ((const fb_road_profile_params *)params)->front_start - l->first_x + x;
}

static int profile_copy(void *to, const void *from, fb_err *err)
{
  fb_road_profile_params *t = to;
  const fb_road_profile_params *f = from;
  t->file = NULL;
  t->profile = NULL;
  if (f->file && !(t->file = fb_strdup(f->file)))
    return fb_err_set(err, FB_ENOMEM, "out of memory for a profile's name");
  const int rc = f->profile ? fb_road_clone(f->profile, &t->profile, err) : FB_OK;
  if (rc)
    free(t->file);
  return rc;
}

static void profile_release(void *params)
{
  fb_road_profile_params *p = params;
  free(p->file);
  p->file = NULL;
  fb_road_free(&p->profile);
}

static void profile_phrase(const void *params, char *buf, size_t n)
{
  const fb_road_profile_params *p = params;
  if (p->file)
    snprintf(buf, n, "over the profile %s", p->file);
  else
    snprintf(buf, n, "over the profile");
}

static const fb_road_type_ops profile_ops = {.prepare = profile_prepare,
                                             .check = profile_check,
                                             .make = profile_make,
                                             .wheel_start = profile_wheel_start,
                                             .copy = profile_copy,
                                             .release = profile_release,
                                             .phrase = profile_phrase};

const fb_road_type fb_road_type_profile = {
    .name = "profile",
    .doc = "a measured profile (docs/roads.md)",
    .param = profile_params,
    .nparams = sizeof profile_params / sizeof profile_params[0],
    .params_size = sizeof(fb_road_profile_params),
    .ops = &profile_ops,
};
