/* flexbond: output files. Every file is written to a temporary name in its
 * destination directory and renamed into place only when complete, so a
 * failed run never leaves a half-written file. */
#ifndef FLEXBOND_IO_H
#define FLEXBOND_IO_H

#include <stdio.h>

#include "flexbond/error.h"
#include "flexbond/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An output file being written: fb_out_open creates "path.tmp.PID",
 * fb_out_commit flushes, closes and renames it to path, fb_out_abort
 * removes it. Exactly one of commit/abort must follow a successful open. */
typedef struct fb_out fb_out;
int fb_out_open(const char *path, fb_out **out, fb_err *err);
FILE *fb_out_stream(fb_out *o);
/* Checks every write made through the stream (disk full, I/O error). */
int fb_out_commit(fb_out **o, fb_err *err);
void fb_out_abort(fb_out **o);

/* Creates directory dir and its missing parents (mode 0777 & ~umask). */
int fb_mkdir_p(const char *dir, fb_err *err);

/* Writes r as CSV: header "t [s],name [unit],...", one row per sample,
 * values in %.10g. */
int fb_result_write_csv(const fb_result *r, const char *path, fb_err *err);

/* Plots output columns cols[0..ncols) of r against time, one panel each
 * (labelled "name [unit]"), into the PNG file path with gnuplot (run as
 * a child process; FB_EIO if it is missing or fails). The file appears
 * only when gnuplot succeeded. title may be NULL. */
int fb_plot_png(const fb_result *r, const size_t *cols, size_t ncols, const char *title,
                const char *path, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
