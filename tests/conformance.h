/* SPDX-License-Identifier: BSD-3-Clause */
/* Shared by the conformance harnesses of the block kinds and of the
 * element laws (tests/test_bd_conformance.c, tests/test_law_conformance.c):
 * random points and the tolerances of their checks. */
#ifndef FLEXBOND_TEST_CONFORMANCE_H
#define FLEXBOND_TEST_CONFORMANCE_H

#include <stddef.h>
#include <stdint.h>

#include "flexbond/bg.h"

/* Random points per block or law, and per graph for the power balance. */
enum { NSAMPLES = 16 };

/* Central differences with step h on inputs of size O(1): the truncation
 * error is h^2 |f'''| / 6 (1.7e-15 |f'''|), the rounding error eps |f| / h
 * (2.2e-9 |f|), and where a C1 law (a table's cubic pieces) has a kink in
 * f'' within h of the point, h |f''| / 2 (5e-8 |f''|, for one point in
 * about 10^6 here). A tolerance of 1e-6 (1 + |derivative| + |f|) is far
 * above all three for the laws and coefficients of these tests
 * (|f''| < 20) and far below a wrong derivative (any error of 1e-4 or
 * more). */
#define FD_STEP 1e-7
#define FD_TOL 1e-6
/* Identities that hold exactly but for rounding (rows against jvp,
 * linearity, power passed on): a few ulp per term, times the condition
 * number of the small matrices solved here (< 10). */
#define EXACT_TOL 1e-11

static uint64_t conformance_rng = 0x9e3779b97f4a7c15u;

/* Uniform in [-1, 1) (xorshift64*, a fixed seed: the same points every
 * run). */
static inline double urand(void)
{
  uint64_t *r = &conformance_rng;
  *r ^= *r >> 12;
  *r ^= *r << 25;
  *r ^= *r >> 27;
  return (double)((*r * 0x2545f4914f6cdd1du) >> 11) / 4503599627370496.0 - 1.0;
}

static inline void randomize(double *v, size_t n)
{
  for (size_t i = 0; i < n; ++i)
    v[i] = urand();
}

/* One element of each library law (every fb_law_id but FB_LAW_CUSTOM):
 * the table R "shock" (passive; |phi''| < 20 on its knots, see FD_TOL)
 * and the unilateral contact "tire" (a switched C) with its damper
 * "tire_d" (a switched R modulated by the tire's q). */
static inline int conformance_add_laws(fb_bg *bg, fb_err *err)
{
  static const double x[5] = {-1.0, -0.3, 0.0, 0.4, 1.2}, y[5] = {-2.0, -0.5, 0.0, 0.3, 1.5};
  fb_table_law *law = NULL;
  int rc = fb_table_law_new(5, x, y, &law, err);
  if (!rc)
    rc = fb_bg_add_r_table(bg, "shock", &law, err);
  return rc ? rc : fb_bg_add_unilateral_contact(bg, "tire", "tire_d", 0.5, 1.0, err);
}

#endif
