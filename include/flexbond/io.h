/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: results and figures as files (CSV, gnuplot pictures) and a
 * vehicle scenario's values as a report lists them. Files are written
 * atomically (flexbond/out.h). */
#ifndef FLEXBOND_IO_H
#define FLEXBOND_IO_H

#include <stdio.h>

#include "flexbond/error.h"
#include "flexbond/fem.h"
#include "flexbond/out.h"
#include "flexbond/sim.h"
#include "flexbond/study.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The first line of a CSV file of results. */
typedef enum fb_csv_header {
  FB_CSV_HEADER_UNITS, /* "t [s],name [unit],..." (a cell without unit: "name") */
  FB_CSV_HEADER_NAMES  /* "t,name,...": names only */
} fb_csv_header;

/* Writes r as CSV into fp: the header line, then one row per sample with
 * values in %.10g. Write errors stick to the stream (ferror); with an
 * fb_out stream, fb_out_commit reports them, which lets a caller commit
 * several files together. */
void fb_result_print_csv(FILE *fp, const fb_result *r, fb_csv_header header);
/* As fb_result_print_csv with only the first ncols columns (time
 * included; all of them if ncols is larger). */
void fb_result_print_csv_columns(FILE *fp, const fb_result *r, size_t ncols,
                                 fb_csv_header header);

/* Writes r as the CSV file path (fb_result_print_csv with
 * FB_CSV_HEADER_UNITS), atomically. */
int fb_result_write_csv(const fb_result *r, const char *path, fb_err *err);

/* ---- Figures (PNG, drawn by gnuplot run as a child process: FB_EIO if it
 * is missing or fails). The file appears only when gnuplot succeeded. */

/* One curve: output column col of result (0 is the first output after
 * time, as in fb_plot_png) against time. */
typedef struct fb_plot_series {
  const fb_result *result; /* borrowed */
  size_t col;
  const char *legend; /* key entry, NULL for none (no key at all when no
                         series of the panel has one) */
} fb_plot_series;

/* One panel: its curves overlaid (e.g. System 1 and System 2 of the same
 * output), in the order given (first solid blue, second dashed red, ...). */
typedef struct fb_plot_panel {
  const fb_plot_series *series; /* borrowed, nseries >= 1 */
  size_t nseries;
  /* The y axis reads "ylabel [unit]": ylabel NULL takes the first
   * series' column name and unit; with ylabel, unit is the values' unit
   * (NULL: ylabel is drawn as given, values as they are). The unit gets
   * the SI prefix that puts the largest value drawn in [1, 1000) (1.2e-5
   * rad is drawn as 12 on a "urad" axis, 14150 N as 14.15 kN), for
   * units that start with a plain SI symbol (N, m, rad, W, J, Pa, s, Hz,
   * V, A, C: not kg, nor one already prefixed). */
  const char *ylabel;
  const char *unit;
  /* focus_t0 < focus_t1: the y range fits the samples in [focus_t0,
   * focus_t1] only, and the time outside it is shaded and labelled
   * outside_label (", off scale" added where a curve leaves the range
   * there), e.g. the settling before a bump that would dwarf the bump's
   * differences. 0, 0 (default): the whole window. */
  double focus_t0, focus_t1;
  const char *outside_label; /* NULL: the shading only */
} fb_plot_panel;

/* Settings of a figure; fb_plot_opts_default fills the defaults below. */
typedef struct fb_plot_opts {
  const char *title;   /* over the whole figure, NULL for none (default) */
  double t_min, t_max; /* time window, s; t_min >= t_max (default 0, 0):
                          the span of the first series' result */
  int width;           /* pixels, 0: 900 (default) */
  int panel_height;    /* pixels per panel, 0: 220 (default) */
} fb_plot_opts;

void fb_plot_opts_default(fb_plot_opts *opts);

/* Draws panels[0..npanels) stacked vertically, sharing the time axis
 * "t [s]" over the window, into the PNG file path. FB_EINVAL if a panel
 * has no series, a column does not exist, or a window holds no sample. */
int fb_plot_panels_png(const fb_plot_panel *panels, size_t npanels, const fb_plot_opts *opts,
                       const char *path, fb_err *err);

/* Plots output columns cols[0..ncols) of r against time, one panel each
 * (labelled "name [unit]"), over the whole run. title may be NULL. */
int fb_plot_png(const fb_result *r, const size_t *cols, size_t ncols, const char *title,
                const char *path, fb_err *err);

/* ---- X-Y figures (src/io/plot_xy.c), e.g. a metric of a parameter
 * study against the swept value. */

/* One curve: the points (x[i], y[i]), i < n, joined in order and marked;
 * a point with a non-finite y is left out and breaks the line (a failed
 * case), one with a non-finite x is left out. */
typedef struct fb_plot_xy_series {
  const double *x, *y; /* borrowed, n each */
  size_t n;
  const char *legend; /* key entry, NULL for none (no key at all when no
                         curve of the panel has one) */
} fb_plot_xy_series;

/* One panel: its curves overlaid, each in its own colour and marker. */
typedef struct fb_plot_xy_panel {
  const fb_plot_xy_series *series; /* borrowed, nseries >= 1 */
  size_t nseries;
  const char *ylabel; /* NULL for none */
  /* The values' unit, drawn as "ylabel [unit]" with an SI prefix on a
   * linear axis, as fb_plot_panel's; NULL: ylabel as given. */
  const char *unit;
  int log_y; /* 1: a logarithmic y axis (values <= 0 left out), when
                some value is > 0 */
} fb_plot_xy_panel;

/* Settings of an x-y figure; fb_plot_xy_opts_default fills the defaults. */
typedef struct fb_plot_xy_opts {
  const char *title;  /* over the whole figure, NULL for none (default) */
  const char *xlabel; /* under every panel, NULL for none (default) */
  /* A categorical x axis: label i drawn at x = i (every x must then be
   * an index 0 .. nxtics-1); NULL (default): numbers. */
  const char *const *xtic_labels;
  size_t nxtics;
  int columns; /* panels per row; 0 (default): ceil(sqrt(npanels)), at most 4 */
  int panel_width, panel_height; /* pixels; 0 (default): 420 x 300 */
  int log_x;                     /* 1: a logarithmic x axis (x <= 0 left out) */
  int lines;                     /* 1: curves as lines without marks, the
                                    third and fourth dashed, and so on */
} fb_plot_xy_opts;

void fb_plot_xy_opts_default(fb_plot_xy_opts *opts);

/* Draws panels[0..npanels) row by row in a grid sharing the x range (the
 * finite x values of every curve) into the PNG file path, with one
 * gnuplot run. A panel's y range is gnuplot's autoscale, widened around
 * a constant curve and [-1, 1] when no point is finite. FB_EINVAL if
 * there is no panel, a panel has no curve, a curve has points but no
 * arrays, or an x is not a label index of a categorical axis; FB_EIO
 * when gnuplot is missing or fails. */
int fb_plot_xy_png(const fb_plot_xy_panel *panels, size_t npanels, const fb_plot_xy_opts *opts,
                   const char *path, fb_err *err);

/* A mode shape of a vehicle with a shell hull as a 3-D PNG (gnuplot),
 * like the paper's Figs. 3-4. Everything is drawn twice: at rest in grey
 * and displaced, the largest displacement drawn largest_drawn long,
 * coloured by the length of each point's displacement (the colour bar in
 * the shape's units). The
 * hull at rest is its outline (fb_mesh_outline: where plates meet at
 * more than 20 degrees, more than two meet, or one ends);
 * displaced, every element's edges, but those of elements whose normal
 * lies within 30 degrees of the y axis (the side walls, which would hide
 * the rest) only on the outline. Mounted bodies are cubes; each wheel is
 * a circle in its x-z plane hanging by a line from its suspension's
 * attachment point, its top wheel_radius / 2 below it. Axes' ranges and
 * tics are chosen so that their labels do not meet. */
typedef struct fb_plot_body {
  double xyz[3]; /* its centre at rest, m */
  double dz;     /* its vertical displacement in the shape */
} fb_plot_body;
typedef struct fb_plot_wheel {
  double top[3]; /* the suspension's attachment point at rest, m */
  double top_dz; /* the attachment point's vertical displacement */
  double dz;     /* the wheel's */
} fb_plot_wheel;
typedef struct fb_plot_mode {
  const fb_mesh *mesh;
  const double *shape;  /* six values per node, the first three its translation */
  double largest_drawn; /* m, > 0 */
  const fb_plot_body *body;
  size_t nbodies;
  double body_side; /* m */
  const fb_plot_wheel *wheel;
  size_t nwheels;
  double wheel_radius;      /* m */
  const char *title;        /* may be NULL */
  const char *subtitle;     /* a second line under it; may be NULL */
  const char *colour_label; /* the colour bar's; NULL: "displacement (shape units)" */
  /* Where the origin of the mesh and of the points above lies in the
   * frame the axes are drawn in (a vehicle's: fb_scenario_frame_offset),
   * m; an animation's frames take frames[0]'s. */
  double origin[3];
} fb_plot_mode;
int fb_plot_mode_png(const fb_plot_mode *pic, const char *path, fb_err *err);
/* The frames as an animated GIF (gnuplot's gif terminal), each shown
 * frame_seconds (in (0, 60], rounded to gnuplot's hundredths): drawn as
 * fb_plot_mode_png draws one, with one scale, colour range and extent for
 * all (frames[0].largest_drawn for the largest displacement of any
 * frame), so that the motion reads true. Every frame draws the same mesh,
 * bodies and wheels at rest (frames[0]'s). The file is read back
 * (complete, as many images as frames) before it is renamed to path. */
int fb_plot_mode_gif(const fb_plot_mode *frames, size_t nframes, double frame_seconds,
                     const char *path, fb_err *err);

/* A value per element of a mesh drawn as its colour (a stress field),
 * through gnuplot's pm3d: every element a flat patch coloured by its
 * value (the mode pictures' palette, from 0 to the largest value), with
 * dark edges, hidden surfaces removed by depth order, in the mode
 * pictures' view and axes. */
typedef struct fb_plot_field {
  const fb_mesh *mesh;
  const double *values;     /* nelements, finite, >= 0 */
  const char *title;        /* may be NULL */
  const char *subtitle;     /* may be NULL */
  const char *colour_label; /* the colour bar's, not NULL */
  double origin[3];         /* as fb_plot_mode's */
} fb_plot_field;
int fb_plot_field_png(const fb_plot_field *pic, const char *path, fb_err *err);

/* ---- A vehicle scenario's values (flexbond/vehicle.h), as a report
 * lists them. */

typedef struct fb_scenario fb_scenario;

/* One value; the strings live for the call only. */
typedef struct fb_scenario_value {
  const char *key;   /* logical key path: "hull.mass", "corners.LF.spring_k",
                        "mounts.driver.mass", "outputs[0].name" */
  const char *path;  /* where the file wrote it ("suspensions.axles[0].spring_k",
                        "wheel.mass" for a value every corner takes), NULL for a
                        default or a scenario not loaded from a file */
  const char *unit;  /* "N/m", "" for none */
  const char *doc;   /* one line: what it is (docs/scenario-format.md) */
  const char *value; /* as text: "145300", "bilateral", "56 points" */
} fb_scenario_value;

/* Called for each value; a nonzero return stops the visit. */
typedef int (*fb_scenario_value_fn)(const fb_scenario_value *v, void *ctx);

/* Calls fn for every value s holds, in the order of the format's key
 * tables (corners, mounts and outputs item by item); values of sections
 * s does not have (a bump on a random road, a deck's generator) are left
 * out. Returns fn's first nonzero return, else FB_OK; FB_EINVAL if s or
 * fn is NULL. */
int fb_scenario_each_value(const fb_scenario *s, fb_scenario_value_fn fn, void *ctx);

/* ---- A sweep's cases loaded from a scenario file or text
 * (flexbond/study.h, fb_study_sweep_ops): each case's scenario is the
 * document read with its own overrides after the source's. */
typedef struct fb_scenario_sweep_source {
  const char *path; /* the scenario file; NULL: the text below */
  const char *text; /* a document in memory (fb_scenario_load_string), len bytes */
  size_t len;
  const char *display_name; /* the text's name in messages */
  /* Values every case reads in place of the document's, before the
   * case's own (a key set by both fails the case, as two overrides of
   * one key do). */
  const fb_scenario_override *overrides;
  size_t noverrides;
  /* How the caller names its axes in messages: "axes" labels a case's
   * value "axes['speed_kmh']=-5" (fb_scenario_override.label); NULL: the
   * default label. */
  const char *axes_name;
} fb_scenario_sweep_source;

/* ops's load (fb_scenario_load_with, or fb_scenario_load_string_with,
 * with src's overrides and then the case's) and locate
 * (fb_scenario_locate), with ctx src: borrowed, it and everything it
 * points to must outlive the sweep. stop, finished: NULL. */
void fb_scenario_sweep_ops(const fb_scenario_sweep_source *src, fb_study_sweep_ops *ops);

#ifdef __cplusplus
}
#endif
#endif
