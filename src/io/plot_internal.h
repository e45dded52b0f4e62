/* Shared by the gnuplot figure writers of src/io. */
#ifndef FLEXBOND_IO_PLOT_INTERNAL_H
#define FLEXBOND_IO_PLOT_INTERNAL_H

#include <stdio.h>

#include "flexbond/error.h"

/* Writes s as a gnuplot single-quoted string ('' escapes a quote). */
void fb_gnuplot_quoted(FILE *fp, const char *s);

/* Writes a gnuplot script to gp that draws a PNG into png_tmp. */
typedef void (*fb_gnuplot_script_fn)(FILE *gp, const void *ctx, const char *png_tmp);

/* Runs gnuplot on the script made by fn and puts the PNG at path only
 * when gnuplot succeeded (temporary files removed in every case). */
int fb_gnuplot_png(fb_gnuplot_script_fn fn, const void *ctx, const char *path, fb_err *err);

#endif
