/* SPDX-License-Identifier: BSD-3-Clause */
/* A corner's shock absorber as the tests read and set it: the built-in
 * laws' blocks (flexbond/damper.h). */
#ifndef FLEXBOND_TESTS_DAMPER_UTIL_H
#define FLEXBOND_TESTS_DAMPER_UTIL_H

#include <math.h>

#include "flexbond/vehicle.h"

/* Corner c's linear coefficient, N s/m; NaN when its law is not linear. */
static inline double du_damper_c(const fb_corner_params *c)
{
  return fb_corner_damper_law(c) == &fb_damper_law_linear
             ? ((const fb_damper_linear_params *)(const void *)c->damper.bytes)->c
             : NAN;
}

/* Corner c's table, NULL when its law is not the table. */
static inline const fb_damper_table_params *du_damper_table(const fb_corner_params *c)
{
  return fb_corner_damper_law(c) == &fb_damper_law_table
             ? (const fb_damper_table_params *)(const void *)c->damper.bytes
             : NULL;
}

/* Makes corner c's shock absorber linear with coefficient cd (N s/m). */
static inline void du_set_damper_c(fb_corner_params *c, double cd)
{
  fb_damper_linear_params *p = NULL;
  if (fb_corner_set_damper(c, &fb_damper_law_linear, (void **)&p, NULL) == FB_OK)
    p->c = cd;
}

#endif
