/* SPDX-License-Identifier: BSD-3-Clause */
/* Helpers for building small bond graphs in tests. Every call must
 * succeed; a failure prints the library's message and counts as a failed
 * check. */
#ifndef FLEXBOND_TEST_BGUTIL_H
#define FLEXBOND_TEST_BGUTIL_H

#include <stdio.h>

#include "flexbond/bg.h"

#include "check.h"

static inline int ok_or_report(int rc, const fb_err *err, const char *what)
{
  if (rc)
    fprintf(stderr, "%s failed: %s\n", what, err->msg);
  return rc == 0;
}

#define MUST(call, err) CHECK(ok_or_report((call), (err), #call))

/* One-port field with a scalar parameter. */
static inline int add_scalar(fb_bg *bg, const char *name, fb_bg_kind kind, double v,
                             fb_err *err)
{
  fb_mat *m = NULL;
  const size_t one = 1;
  int rc = fb_mat_new_scaled_identity(1, v, &m, err);
  return rc ? rc : fb_bg_add_field(bg, name, kind, 1, &one, &m, err);
}

static inline int add_const_source(fb_bg *bg, const char *name, fb_bg_kind kind, double v,
                                   fb_err *err)
{
  fb_tfun *f = NULL;
  int rc = fb_tfun_new_const(v, &f, err);
  return rc ? rc : fb_bg_add_source(bg, name, kind, 1, &f, err);
}

/* A force source "F" of function *force (taken over) on a 1-junction "J"
 * shared by a mass "mass" and a spring "spring": bonds "bF", "bm" and
 * "bk" (a damper, if any, is the caller's). */
static inline int add_forced_oscillator(fb_bg *bg, fb_tfun **force, double mass, double stiff,
                                        fb_err *err)
{
  int rc = fb_bg_add_source(bg, "F", FB_BG_SE, 1, force, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "J", FB_BG_J1, 1, err);
  if (!rc)
    rc = add_scalar(bg, "mass", FB_BG_I, mass, err);
  if (!rc)
    rc = add_scalar(bg, "spring", FB_BG_C, stiff, err);
  if (!rc)
    rc = fb_bg_connect(bg, "bF", "F", "J", err);
  if (!rc)
    rc = fb_bg_connect(bg, "bm", "J", "mass", err);
  if (!rc)
    rc = fb_bg_connect(bg, "bk", "J", "spring", err);
  return rc;
}

#endif
