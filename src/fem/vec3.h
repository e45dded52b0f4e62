/* SPDX-License-Identifier: BSD-3-Clause */
/* Small 3-vector helpers shared by the shell element and mesh checks. */
#ifndef FLEXBOND_FEM_VEC3_H
#define FLEXBOND_FEM_VEC3_H

#include <math.h>

static inline void fb_sub3(const double *a, const double *b, double *d)
{
  d[0] = a[0] - b[0];
  d[1] = a[1] - b[1];
  d[2] = a[2] - b[2];
}

static inline void fb_cross3(const double *a, const double *b, double *c)
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double fb_dot3(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline double fb_norm3(const double *a)
{
  return sqrt(fb_dot3(a, a));
}

#endif
