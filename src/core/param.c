/* SPDX-License-Identifier: BSD-3-Clause */
/* Declared parameters of gallery entries (flexbond/param.h): their
 * soundness, their defaults, and the check of a block against them. */
#include "flexbond/param.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/util.h"

static double param_scale(const fb_param *p)
{
  return p->scale != 0.0 ? p->scale : 1.0;
}

static const void *param_at(const fb_param *p, const void *block)
{
  return (const char *)block + p->offset;
}

/* The stored value of element e, in the written unit. */
static double param_number(const fb_param *p, const void *block, size_t e)
{
  const void *at = param_at(p, block);
  switch (p->store) {
  case FB_PARAM_DOUBLE: return ((const double *)at)[e] / param_scale(p);
  case FB_PARAM_INT: return (double)*(const int *)at;
  case FB_PARAM_SIZE: return (double)*(const size_t *)at;
  case FB_PARAM_U64: return (double)*(const uint64_t *)at;
  default: return NAN;
  }
}

static size_t param_nchoices(const fb_param *p)
{
  size_t n = 0;
  while (p->choices && p->choices[n])
    ++n;
  return n;
}

static size_t param_store_size(const fb_param *p)
{
  switch (p->store) {
  case FB_PARAM_DOUBLE: return sizeof(double) * (p->kind == FB_PARAM_REALS ? p->count : 1);
  case FB_PARAM_INT: return sizeof(int);
  case FB_PARAM_SIZE: return sizeof(size_t);
  case FB_PARAM_U64: return sizeof(uint64_t);
  case FB_PARAM_STRING: return sizeof(char *);
  }
  return SIZE_MAX;
}

/* 1 if the store can hold the kind. */
static int param_store_fits(const fb_param *p)
{
  switch (p->kind) {
  case FB_PARAM_REAL: return p->store == FB_PARAM_DOUBLE;
  case FB_PARAM_REALS: return p->store == FB_PARAM_DOUBLE && p->count > 0;
  case FB_PARAM_WHOLE: return p->store == FB_PARAM_SIZE || p->store == FB_PARAM_U64;
  case FB_PARAM_CHOICE: return p->store == FB_PARAM_INT && param_nchoices(p) > 0;
  case FB_PARAM_FILE: return p->store == FB_PARAM_STRING;
  }
  return 0;
}

static int param_fail(fb_err *err, const fb_param *p, const char *what)
{
  return fb_err_set(err, FB_EINVAL, "parameter %s: %s", p->name ? p->name : "(unnamed)", what),
         fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, p->name ? p->name : ""), FB_EINVAL;
}

/* 0 if the declared default of p lies in its range. */
static int param_default_ok(const fb_param *p)
{
  if (p->need != FB_PARAM_DEFAULT || p->kind == FB_PARAM_FILE)
    return 1;
  if (p->kind == FB_PARAM_CHOICE)
    return p->def >= 0 && p->def < (double)param_nchoices(p) && p->def == floor(p->def);
  const size_t n = p->kind == FB_PARAM_REALS ? p->count : 1;
  if (p->kind == FB_PARAM_REALS && !p->def_list)
    return 0;
  for (size_t e = 0; e < n; ++e) {
    const double v = p->kind == FB_PARAM_REALS ? p->def_list[e] : p->def;
    if (!isfinite(v) || !fb_range_contains(p->range, p->lo, p->hi, v))
      return 0;
  }
  return 1;
}

int fb_params_declared(const fb_param *p, size_t n, size_t block_size, fb_err *err)
{
  for (size_t i = 0; i < n; ++i) {
    if (!fb_is_identifier(p[i].name))
      return param_fail(err, &p[i], "a name is letters, digits and '_', not from a digit");
    for (size_t j = 0; j < i; ++j)
      if (!strcmp(p[i].name, p[j].name))
        return param_fail(err, &p[i], "declared twice");
    if (!param_store_fits(&p[i]))
      return param_fail(err, &p[i], "its store does not hold its kind");
    if (p[i].offset > block_size || param_store_size(&p[i]) > block_size - p[i].offset)
      return param_fail(err, &p[i], "stored outside the parameter block");
    if (!p[i].doc || !p[i].doc[0])
      return param_fail(err, &p[i], "undocumented");
    if (!param_default_ok(&p[i]))
      return param_fail(err, &p[i], "its default is outside its range");
  }
  return FB_OK;
}

void fb_params_defaults(const fb_param *p, size_t n, void *block)
{
  for (size_t i = 0; i < n; ++i) {
    if (p[i].need != FB_PARAM_DEFAULT)
      continue;
    char *at = (char *)block + p[i].offset;
    const double s = param_scale(&p[i]);
    switch (p[i].store) {
    case FB_PARAM_DOUBLE:
      for (size_t e = 0; e < (p[i].kind == FB_PARAM_REALS ? p[i].count : 1); ++e) {
        const double v = (p[i].kind == FB_PARAM_REALS ? p[i].def_list[e] : p[i].def) * s;
        memcpy(at + e * sizeof v, &v, sizeof v);
      }
      break;
    case FB_PARAM_INT: *(int *)at = (int)p[i].def; break;
    case FB_PARAM_SIZE: *(size_t *)at = (size_t)p[i].def; break;
    case FB_PARAM_U64: *(uint64_t *)at = (uint64_t)p[i].def; break;
    case FB_PARAM_STRING: break;
    }
  }
}

/* One declared value of block against its range. */
static int param_check_one(const fb_param *p, const void *block, fb_err *err)
{
  if (p->kind == FB_PARAM_FILE) {
    const char *path = *(char *const *)param_at(p, block);
    return p->need == FB_PARAM_REQUIRED && (!path || !path[0]) ? param_fail(err, p, "no file")
                                                               : FB_OK;
  }
  if (p->kind == FB_PARAM_CHOICE) {
    const int c = *(const int *)param_at(p, block);
    if (c < 0 && p->need == FB_PARAM_OPTIONAL) /* left out */
      return FB_OK;
    return c >= 0 && (size_t)c < param_nchoices(p)
               ? FB_OK
               : param_fail(err, p, "not one of its choices");
  }
  const size_t n = p->kind == FB_PARAM_REALS ? p->count : 1;
  for (size_t e = 0; e < n; ++e) {
    const double v = param_number(p, block, e);
    /* An optional value left out is NaN (the entry's defaults say so). */
    if (isnan(v) && p->need == FB_PARAM_OPTIONAL)
      continue;
    if (isfinite(v) && fb_range_contains(p->range, p->lo, p->hi, v))
      continue;
    char range[64];
    fb_range_text(p->range, p->lo, p->hi, range, sizeof range);
    const char *unit = p->unit ? p->unit : "";
    if (!isfinite(v))
      fb_err_set(err, FB_EINVAL, "must be finite%s%s%s%s (got %g)", range[0] ? " and " : "",
                 range, unit[0] && range[0] ? " " : "", range[0] ? unit : "", v);
    else
      fb_err_set(err, FB_EINVAL, "must be %s%s%s (got %.10g)", range, unit[0] ? " " : "", unit,
                 v);
    return fb_err_set_part(err, 0, 0, n > 1 ? e : FB_ERR_NO_ELEMENT, p->name), FB_EINVAL;
  }
  return FB_OK;
}

int fb_params_check(const fb_param *p, size_t n, const void *block, fb_err *err)
{
  for (size_t i = 0; i < n; ++i) {
    const int rc = param_check_one(&p[i], block, err);
    if (rc)
      return rc;
  }
  return FB_OK;
}

int fb_params_scalar(const fb_param *p, size_t n)
{
  for (size_t i = 0; i < n; ++i)
    if (p[i].kind == FB_PARAM_FILE || p[i].kind == FB_PARAM_REALS)
      return 0;
  return 1;
}
