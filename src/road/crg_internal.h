/* SPDX-License-Identifier: BSD-3-Clause */
/* The OpenCRG surface as evaluated (flexbond/crg.h): shared by its reader
 * (crg_read.c) and its evaluation (crg_eval.c). */
#ifndef FLEXBOND_CRG_INTERNAL_H
#define FLEXBOND_CRG_INTERNAL_H

#include <stddef.h>

#include "flexbond/crg.h"

/* Evaluation options (specification 3.4.4), application defaults first. */
typedef struct crg_opts {
  int border_mode_u, border_mode_v;        /* fb_crg_border; default KEEP */
  double border_offset_u, border_offset_v; /* m; default 0 */
  double smooth_ubeg, smooth_uend;         /* m; default 0: none */
} crg_opts;

struct fb_crg {
  size_t nu, nv;
  double u0, du; /* m: the first cross section's u and the increment */
  double *v;     /* nv, m, ascending */
  double *z;     /* nu * nv, m: z[i * nv + j], after the modifiers */
  double *zref;  /* nu, m: the reference line's height at each section */
  double *bank;  /* nu, m/m: the banking at each section */
  double *phi;   /* nu, rad, or NULL: the heading channel as read */
  int has_slope, has_banking;
  crg_opts opts;
};

/* Frees the arrays of c (not c). */
void crg_release(fb_crg *c);

#endif
