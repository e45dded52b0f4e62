/* SPDX-License-Identifier: BSD-3-Clause */
/* Shared by the gnuplot figure writers of src/io. */
#ifndef FLEXBOND_IO_PLOT_INTERNAL_H
#define FLEXBOND_IO_PLOT_INTERNAL_H

#include <stdio.h>

#include "flexbond/error.h"
#include "flexbond/io.h"

#include "io/child.h"

/* Writes s as a gnuplot single-quoted string: '' escapes a quote, and a
 * control character (a line end would end the command, letting the rest
 * of s run as gnuplot's next line) becomes '?'. gnuplot substitutes
 * nothing inside single quotes (no backquotes, no macros), so this is the
 * one escape every text in a script passes through. */
void fb_gnuplot_quoted(FILE *fp, const char *s);

/* The SI prefix for values of unit whose largest magnitude is max_abs:
 * the power of 1000 that puts it in [1, 1000), from nano to giga. Writes
 * the prefixed unit into out (size bytes) and returns the factor to
 * multiply the values by (1e6 for "urad" as the micro sign); unit as it
 * is and 1 when no prefix applies (see fb_plot_panel.unit), max_abs is 0
 * or not finite. */
double fb_plot_si_scale(double max_abs, const char *unit, char *out, size_t size);

/* The script of fb_plot_panels_png for the window [t_min, t_max], drawing
 * into png_name (for tests: the figure is this text); nothing for more
 * than 64 panels, which fb_plot_panels_png refuses. */
void fb_plot_panels_script(FILE *gp, const fb_plot_panel *panels, size_t npanels,
                           const fb_plot_opts *o, double t_min, double t_max,
                           const char *png_name);

/* Writes a gnuplot script to gp that draws a PNG into the file png_name
 * (a plain name in gnuplot's working directory). */
typedef void (*fb_gnuplot_script_fn)(FILE *gp, const void *ctx, const char *png_name);

/* How long one gnuplot run may take before it is killed: the largest of
 * our figures (a sweep's grid of panels) draws in about a second. */
#define FB_GNUPLOT_TIMEOUT_S 120.0

/* Runs gnuplot (io/child.h: its own process group, killed after
 * FB_GNUPLOT_TIMEOUT_S) on the script made by fn, in a private directory
 * made beside path, checks that the PNG is complete (fb_png_check) and
 * only then renames it to path. The directory and its files are removed
 * in every case. FB_EIO when gnuplot fails, or succeeds with no complete
 * image (a full disk). */
int fb_gnuplot_png(fb_gnuplot_script_fn fn, const void *ctx, const char *path, fb_err *err);

/* FB_OK if the file path is a complete PNG image (signature, chunks with
 * valid CRCs, IHDR first, IEND last at the end of the file); FB_EIO "not
 * a complete PNG image: ..." otherwise. */
int fb_png_check(const char *path, fb_err *err);

/* FB_OK if the file path is a complete GIF image of one frame or more
 * (fb_gif_frames); FB_EIO "not a complete GIF image: ..." otherwise. */
int fb_gif_check(const char *path, fb_err *err);
/* The number of images (frames) of the complete GIF file at path. */
int fb_gif_frames(const char *path, size_t *nframes, fb_err *err);

/* A figure larger than this is no plot of ours: refused before reading. */
#define FB_IMAGE_MAX_BYTES (256L * 1024 * 1024)
/* Reads the regular file path (not through a link; at most
 * FB_IMAGE_MAX_BYTES) into *data (new, NULL when empty), its size in *n. */
int fb_image_read(const char *path, unsigned char **data, size_t *n, fb_err *err);

/* fb_gnuplot_png for any image format: the script draws into image_name
 * (a plain name, "plot.gif"), check reads the file back before it is
 * renamed to path. */
int fb_gnuplot_draw(fb_gnuplot_script_fn fn, const void *ctx, const char *image_name,
                    fb_child_check_fn check, const char *path, fb_err *err);

#endif
