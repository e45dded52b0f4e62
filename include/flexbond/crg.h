/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: ASAM OpenCRG road surfaces (docs/roads.md, "OpenCRG surfaces").
 *
 * A reader of the OpenCRG 1.2 file format (ASAM OpenCRG specification
 * 1.2.0, chapter 3, "OpenCRG data format") and the evaluation of the
 * surface height z(u, v) on its curved regular grid: u along the
 * reference line, v across it (positive to the left). What is read, what
 * each section means and what is not supported: docs/roads.md.
 *
 * The reference line is placed in x/y from its start, its headings and
 * the x/y modifiers; fb_crg_uv_to_xy and fb_crg_xy_to_uv map between the
 * two (docs/roads.md gives the rules: the specification leaves the
 * interpolation between its points open). */
#ifndef FLEXBOND_CRG_H
#define FLEXBOND_CRG_H

#include <stddef.h>

#include "flexbond/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fb_crg fb_crg;

/* Reads the OpenCRG file at path and the files it references
 * ($ROAD_CRG_FILE, relative paths from the referencing file's directory),
 * and applies its modifiers ($ROAD_CRG_MODS; without such a section the
 * default GRID_NAN_MODE = 2) so that *out (new, fb_crg_free) holds the
 * surface as evaluated. Errors name the file and its line (headers,
 * formatted data) or byte offset (binary data): FB_EIO a file that cannot
 * be read, FB_EPARSE a malformed or inconsistent one, FB_ENOMEM. Nothing
 * is allocated beyond the size of the files read. */
int fb_crg_read(const char *path, fb_crg **out, fb_err *err);
/* A deep copy of crg (*out new). FB_ENOMEM. */
int fb_crg_clone(const fb_crg *crg, fb_crg **out, fb_err *err);
/* Frees *crg (NULL accepted) and sets it to NULL. */
void fb_crg_free(fb_crg **crg);

/* Border modes of BORDER_MODE_U and BORDER_MODE_V (specification 3.4.4). */
typedef enum fb_crg_border {
  FB_CRG_BORDER_NAN = 0,    /* NaN outside the grid */
  FB_CRG_BORDER_ZERO = 1,   /* 0 (plus the border offset) */
  FB_CRG_BORDER_KEEP = 2,   /* the last value at the border (plus the offset) */
  FB_CRG_BORDER_REPEAT = 3, /* the grid repeated */
  FB_CRG_BORDER_MIRROR = 4  /* the grid mirrored at its borders */
} fb_crg_border;

/* The grid as evaluated (after the modifiers). */
typedef struct fb_crg_info {
  size_t nu, nv;                       /* cross sections (rows) and long sections (columns) */
  double u_first, u_last;              /* m: the reference line's u range */
  double u_increment;                  /* m: between cross sections */
  double v_right, v_left;              /* m: the outer long sections (v_right < v_left) */
  int has_phi, has_slope, has_banking; /* the file's reference-line channels */
  int border_mode_u, border_mode_v;    /* fb_crg_border */
} fb_crg_info;

void fb_crg_get_info(const fb_crg *crg, fb_crg_info *out);
/* The v of long section j (< nv), m, ascending from the right border. */
double fb_crg_v(const fb_crg *crg, size_t j);
/* The grid's value at cross section i, long section j, m (after NaN
 * handling and the z scale; without the reference line's height): NaN for
 * a missing value that was kept. */
double fb_crg_node(const fb_crg *crg, size_t i, size_t j);

/* The surface height z(u, v), m: the bilinear interpolation of the grid,
 * plus the reference line's height (slope integrated along u) and its
 * banking times v, with the options' border modes, border offsets and
 * smoothing (docs/roads.md gives each rule and its section). NaN where
 * the surface has no value (border mode 0 outside the grid, or a missing
 * value that was kept). */
double fb_crg_z(const fb_crg *crg, double u, double v);

/* The x/y position, m, of the surface point (u, v) (u beyond the
 * reference line: along its end chord). FB_EINVAL for a non-finite u or
 * v, or for u beyond the line with REFLINE_CONTINUATION = 1 (a closed
 * track: not supported). */
int fb_crg_uv_to_xy(const fb_crg *crg, double u, double v, double *x, double *y, fb_err *err);
/* The (u, v), m, of the x/y position (x, y): of the points of the
 * reference line whose normal passes through it, the nearest (the line's
 * ends extended along their chords). FB_EINVAL for non-finite input, for
 * a point square to no part of the line, or beyond it with
 * REFLINE_CONTINUATION = 1. */
int fb_crg_xy_to_uv(const fb_crg *crg, double x, double y, double *u, double *v, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
