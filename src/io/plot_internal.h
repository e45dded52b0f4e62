/* Shared by the gnuplot figure writers of src/io. */
#ifndef FLEXBOND_IO_PLOT_INTERNAL_H
#define FLEXBOND_IO_PLOT_INTERNAL_H

#include <stdio.h>

#include "flexbond/error.h"

/* Writes s as a gnuplot single-quoted string: '' escapes a quote, and a
 * control character (a line end would end the command, letting the rest
 * of s run as gnuplot's next line) becomes '?'. gnuplot substitutes
 * nothing inside single quotes (no backquotes, no macros), so this is the
 * one escape every text in a script passes through. */
void fb_gnuplot_quoted(FILE *fp, const char *s);

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

#endif
