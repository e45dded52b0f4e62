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
  int refline_continuation;                /* 0: extrapolate, 1: closed track */
} crg_opts;

struct fb_crg {
  size_t nu, nv;
  double u0, du;   /* m: the first cross section's u and the increment */
  double *v;       /* nv, m, ascending */
  double *z;       /* nu * nv, m: z[i * nv + j], after the modifiers */
  double *zref;    /* nu, m: the reference line's height at each section */
  double *bank;    /* nu, m/m: the banking at each section */
  double *phi;     /* nu, rad, or NULL: the heading channel as read */
  double *rx, *ry; /* nu, m: the reference line's points (crg_xy.c) */
  double *rh;      /* nu, rad: its heading at each point */
  int has_slope, has_banking;
  crg_opts opts;
};

/* How the reference line is placed in x/y (3.4.2, 3.4.5), applied in
 * this order: the file's global offsets, then the modifiers' relocation
 * by reference point or by rotation and offset. */
typedef struct crg_place {
  double start_x, start_y;   /* REFERENCE_LINE_START_X, _Y */
  double start_phi, end_phi; /* the heading without a channel */
  int end_phi_given;
  int end_xy_given; /* REFERENCE_LINE_END_X and _Y */
  double end_x, end_y;
  double offset_x, offset_y, offset_phi; /* REFERENCE_LINE_OFFSET_X, _Y, _PHI */
  double scale_curvature;                /* SCALE_CURVATURE (1: none) */
  int by_refpoint;                       /* any REFPOINT_* modifier */
  double ref_u, ref_v, ref_x, ref_y, ref_phi;
  int rotcenter_given[2];
  double rot_x, rot_y;   /* REFLINE_ROTCENTER_X, _Y */
  double rot_phi;        /* REFLINE_OFFSET_PHI */
  double move_x, move_y; /* REFLINE_OFFSET_X, _Y */
} crg_place;

/* The reference line of c (c->rx, ry, rh) from the step headings phi
 * (nu values, the first unused; NULL: from place's start and end
 * headings) and place. FB_ENOMEM. */
int crg_refline_build(fb_crg *c, const double *phi, const crg_place *place, fb_err *err);

/* Frees the arrays of c (not c). */
void crg_release(fb_crg *c);

#endif
