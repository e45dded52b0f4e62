/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's ASAM OpenCRG surface (flexbond/crg.h, docs/roads.md,
 * "OpenCRG surfaces"): the surface is read once by prepare; the road is its
 * two tracks at constant lateral positions v, sampled along the reference
 * line at the surface's u increment as the knots of a measured profile
 * (fb_road_new_profile), so that the road keeps its model-file form. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/crg.h"
#include "flexbond/road.h"

#include "core/util.h"

static const fb_param crg_params[] = {
    {.name = "file",
     .kind = FB_PARAM_FILE,
     .store = FB_PARAM_STRING,
     .offset = offsetof(fb_road_crg_params, file),
     .need = FB_PARAM_REQUIRED,
     .doc = "an OpenCRG file (ASAM OpenCRG 1.2: LRFI, LDFI, KRBI or KDBI data)"},
    {.name = "front_start",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_crg_params, front_start),
     .unit = "m",
     .need = FB_PARAM_DEFAULT,
     .doc = "the first corner's wheel's position on its track at t = 0 (0: at u_start)"},
    {.name = "z_offset",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_crg_params, z_offset),
     .unit = "m",
     .need = FB_PARAM_DEFAULT,
     .doc = "added to every height (a surface in absolute elevation: minus its height at "
            "the start)"},
    {.name = "u_start",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_crg_params, u_start),
     .unit = "m",
     .need = FB_PARAM_OPTIONAL,
     .doc =
         "the surface's u where the tracks begin (s = 0); left out: its first cross section"},
    {.name = "v_left",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_crg_params, v_left),
     .unit = "m",
     .need = FB_PARAM_OPTIONAL,
     .doc = "the left track's lateral position v on the surface; left out: track_width / 2"},
    {.name = "v_right",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_crg_params, v_right),
     .unit = "m",
     .need = FB_PARAM_OPTIONAL,
     .doc = "the right track's lateral position v; left out: -track_width / 2"},
};

static void crg_init(void *params)
{
  fb_road_crg_params *p = params;
  p->u_start = p->v_left = p->v_right = NAN;
}

/* Read once, here: the road is made from what was read. */
static int crg_prepare(void *params, fb_err *err)
{
  fb_road_crg_params *p = params;
  fb_crg_free(&p->crg);
  const int rc = fb_crg_read(p->file, &p->crg, err);
  return rc ? (fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "file"), rc) : FB_OK;
}

/* The tracks' v: given, or the vehicle centred on the reference line. */
static void track_v(const fb_road_crg_params *p, const fb_road_layout *l, double *left,
                    double *right)
{
  *left = isnan(p->v_left) ? 0.5 * l->track_width : p->v_left;
  *right = isnan(p->v_right) ? -0.5 * l->track_width : p->v_right;
}

static int crg_check(const void *params, const fb_road_layout *l, fb_err *err)
{
  const fb_road_crg_params *p = params;
  if (!p->crg)
    return fb_err_set(err, FB_EINVAL, "the surface was not read (prepare reads it)"),
           fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "file"), FB_EINVAL;
  fb_crg_info info;
  fb_crg_get_info(p->crg, &info);
  if (!isnan(p->u_start) && (p->u_start < info.u_first || p->u_start >= info.u_last))
    return fb_err_set(err, FB_EINVAL,
                      "u_start = %g m: outside the surface's u range [%g, %g) m", p->u_start,
                      info.u_first, info.u_last),
           fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "u_start"), FB_EINVAL;
  double left, right;
  track_v(p, l, &left, &right);
  if (!(left > right))
    return fb_err_set(err, FB_EINVAL, "v_left = %g m must be left of v_right = %g m", left,
                      right),
           fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT,
                           isnan(p->v_left) ? "v_right" : "v_left"),
           FB_EINVAL;
  return FB_OK;
}

/* Knot k of the tracks at u: 0, or FB_EINVAL where the surface has no
 * height. */
static int crg_knot(const fb_road_crg_params *p, const fb_crg_info *info, double u, double left,
                    double right, double *zl, double *zr, fb_err *err)
{
  *zl = fb_crg_z(p->crg, u, left) + p->z_offset;
  *zr = fb_crg_z(p->crg, u, right) + p->z_offset;
  if (!isnan(*zl) && !isnan(*zr))
    return FB_OK;
  return fb_err_set(err, FB_EINVAL,
                    "the surface has no height at u = %g m, v = %g m (a missing value kept, "
                    "or v outside its lateral range [%g, %g] m with BORDER_MODE_V = 0)",
                    u, isnan(*zl) ? left : right, info->v_right, info->v_left),
         fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, isnan(*zl) ? "v_left" : "v_right"),
         FB_EINVAL;
}

/* The knots: u_start, then every cross section after it to the last. */
static int crg_make(const void *params, const fb_road_layout *l, fb_road **out, fb_err *err)
{
  const fb_road_crg_params *p = params;
  fb_crg_info info;
  fb_crg_get_info(p->crg, &info);
  const double u0 = isnan(p->u_start) ? info.u_first : p->u_start;
  double left, right;
  track_v(p, l, &left, &right);
  const size_t n = info.nu + 1;
  double *s = malloc(3 * n * sizeof *s);
  if (!s)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu knots of an OpenCRG road", n);
  double *zl = s + n, *zr = zl + n;
  s[0] = 0.0;
  int rc = crg_knot(p, &info, u0, left, right, &zl[0], &zr[0], err);
  size_t k = 1;
  for (size_t i = 0; !rc && i < info.nu; ++i) {
    const double u = info.u_first + (double)i * info.u_increment;
    if (u - u0 <= 1e-9 * info.u_increment)
      continue; /* before u_start, or on it: no knot twice */
    s[k] = u - u0;
    rc = crg_knot(p, &info, u, left, right, &zl[k], &zr[k], err);
    ++k;
  }
  if (!rc)
    rc = fb_road_new_profile(k, s, zl, zr, out, err);
  free(s);
  return rc;
}

static double crg_wheel_start(const void *params, const fb_road_layout *l, double x, double y)
{
  (void)y;
  return ((const fb_road_crg_params *)params)->front_start - l->first_x + x;
}

static int crg_copy(void *to, const void *from, fb_err *err)
{
  fb_road_crg_params *t = to;
  const fb_road_crg_params *f = from;
  t->file = NULL;
  t->crg = NULL;
  if (f->file && !(t->file = fb_strdup(f->file)))
    return fb_err_set(err, FB_ENOMEM, "out of memory for an OpenCRG file's name");
  const int rc = f->crg ? fb_crg_clone(f->crg, &t->crg, err) : FB_OK;
  if (rc) {
    free(t->file);
    t->file = NULL;
  }
  return rc;
}

static void crg_release(void *params)
{
  fb_road_crg_params *p = params;
  free(p->file);
  p->file = NULL;
  fb_crg_free(&p->crg);
}

static void crg_phrase(const void *params, char *buf, size_t n)
{
  const fb_road_crg_params *p = params;
  if (p->file)
    snprintf(buf, n, "over the OpenCRG surface %s", p->file);
  else
    snprintf(buf, n, "over the OpenCRG surface");
}

static const fb_road_type_ops crg_ops = {.init = crg_init,
                                         .prepare = crg_prepare,
                                         .check = crg_check,
                                         .make = crg_make,
                                         .wheel_start = crg_wheel_start,
                                         .copy = crg_copy,
                                         .release = crg_release,
                                         .phrase = crg_phrase};

const fb_road_type fb_road_type_crg = {
    .name = "crg",
    .doc = "an ASAM OpenCRG road surface (docs/roads.md)",
    .param = crg_params,
    .nparams = sizeof crg_params / sizeof crg_params[0],
    .params_size = sizeof(fb_road_crg_params),
    .ops = &crg_ops,
};
