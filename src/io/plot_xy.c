/* SPDX-License-Identifier: BSD-3-Clause */
/* X-Y figures through gnuplot (flexbond/io.h, fb_plot_xy_png): a grid of
 * panels, each with curves of points joined in order, such as a metric
 * of a parameter study against the swept value. The data go inline as
 * one datablock per curve, the script through fb_gnuplot_png (plot.c),
 * so a figure costs one gnuplot run however many panels it has. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/io.h"

#include "io/plot_internal.h"

/* Curve styles in order, reused cyclically: colour and point type. */
static const struct {
  const char *colour;
  int point_type;
} xy_styles[] = {{"#1f4e9a", 7},  {"#c0392b", 5}, {"#2e8b57", 9}, {"#7f7f7f", 13},
                 {"#8e44ad", 11}, {"#d35400", 6}, {"#16a085", 4}, {"#2c3e50", 8}};
enum { NXY_STYLES = sizeof xy_styles / sizeof xy_styles[0] };

/* Defaults of fb_plot_xy_opts. */
enum { XY_MAX_COLUMNS = 4, XY_PANEL_WIDTH = 420, XY_PANEL_HEIGHT = 300 };

void fb_plot_xy_opts_default(fb_plot_xy_opts *opts)
{
  *opts = (fb_plot_xy_opts){.title = NULL,
                            .xlabel = NULL,
                            .xtic_labels = NULL,
                            .nxtics = 0,
                            .columns = 0,
                            .panel_width = 0,
                            .panel_height = 0,
                            .log_x = 0,
                            .lines = 0};
}

/* A figure being written. */
typedef struct xy_script {
  const fb_plot_xy_panel *panels;
  size_t npanels;
  const fb_plot_xy_opts *opts;
  size_t columns, rows;
  double x_lo, x_hi; /* the common x range */
} xy_script;

/* 1 if v can be drawn on an axis, logarithmic when log is 1. */
static int drawable(double v, int log)
{
  return isfinite(v) && (!log || v > 0);
}

/* Range [*lo, *hi] of the drawable values of v[0..n), extended (not
 * reset) from what they hold. */
static void extend_range(const double *v, size_t n, int log, double *lo, double *hi)
{
  for (size_t i = 0; i < n; ++i)
    if (drawable(v[i], log)) {
      *lo = fmin(*lo, v[i]);
      *hi = fmax(*hi, v[i]);
    }
}

/* "set xrange/yrange [lo:hi]" widened around a single value (gnuplot's
 * autoscale would warn and widen it itself) or over nothing finite. */
static void write_range(FILE *gp, const char *axis, double lo, double hi)
{
  if (!(lo <= hi)) {
    lo = -1;
    hi = 1;
  } else if (lo == hi) {
    const double half = lo == 0 ? 1 : 0.5 * fabs(lo);
    lo -= half;
    hi += half;
  } else {
    fprintf(gp, "set autoscale %s\n", axis);
    return;
  }
  fprintf(gp, "set %srange [%.10g:%.10g]\n", axis, lo, hi);
}

/* The y values of series s drawn times scale. */
static void write_datablock(FILE *gp, size_t id, const fb_plot_xy_series *s, int log_x,
                            int log_y, double scale)
{
  fprintf(gp, "$d%zu << EOD\n", id);
  for (size_t i = 0; i < s->n; ++i) {
    /* gnuplot leaves a NaN point out and breaks the line there. */
    if (drawable(s->x[i], log_x) && drawable(s->y[i], log_y))
      fprintf(gp, "%.10g %.10g\n", s->x[i], s->y[i] * scale);
    else if (drawable(s->x[i], log_x))
      fprintf(gp, "%.10g NaN\n", s->x[i]);
  }
  fputs("EOD\n", gp);
}

/* The categorical x axis: the labels at x = 0, 1, ... */
static void write_xtics(FILE *gp, const fb_plot_xy_opts *o)
{
  if (!o->xtic_labels) {
    fputs("set xtics autofreq\n", gp);
    return;
  }
  fputs("set xtics (", gp);
  for (size_t i = 0; i < o->nxtics; ++i) {
    fputs(i ? ", " : "", gp);
    fb_gnuplot_quoted(gp, o->xtic_labels[i]);
    fprintf(gp, " %zu", i);
  }
  fputs(")\n", gp);
}

/* 1 if panel p is drawn with a logarithmic y axis: it asks for one and
 * has a value to put on it. */
static int panel_log_y(const fb_plot_xy_panel *p)
{
  double lo = INFINITY, hi = -INFINITY;
  for (size_t j = 0; p->log_y && j < p->nseries; ++j)
    extend_range(p->series[j].y, p->series[j].n, 1, &lo, &hi);
  return lo <= hi;
}

/* The factor panel p's values are drawn times (an SI prefix's, linear
 * axes with a unit only) and the axis unit into unit. */
static double panel_scale(const fb_plot_xy_panel *p, int log_y, char *unit, size_t size)
{
  double lo = INFINITY, hi = -INFINITY;
  for (size_t j = 0; j < p->nseries; ++j)
    extend_range(p->series[j].y, p->series[j].n, log_y, &lo, &hi);
  const double max_abs = lo <= hi ? fmax(fabs(lo), fabs(hi)) : 0.0;
  return fb_plot_si_scale(log_y || !p->ylabel ? 0.0 : max_abs, p->unit, unit, size);
}

static void write_panel(FILE *gp, const fb_plot_xy_panel *p, size_t first_id, int lines)
{
  const int log_y = panel_log_y(p);
  char unit[64];
  const double scale = panel_scale(p, log_y, unit, sizeof unit);
  double lo = INFINITY, hi = -INFINITY;
  int has_key = 0;
  for (size_t j = 0; j < p->nseries; ++j) {
    extend_range(p->series[j].y, p->series[j].n, log_y, &lo, &hi);
    has_key |= p->series[j].legend != NULL;
  }
  fputs(log_y ? "set logscale y\nset format y '%g'\n" : "unset logscale y\nset format y\n", gp);
  write_range(gp, "y", lo * scale, hi * scale);
  fputs(has_key ? "set key top left\n" : "set key off\n", gp);
  fputs("set ylabel ", gp);
  fb_gnuplot_quoted(gp, p->ylabel ? p->ylabel : "");
  if (p->ylabel && p->unit) {
    fputs(".' ['.", gp);
    fb_gnuplot_quoted(gp, unit);
    fputs(".']'", gp);
  }
  fputs("\nplot ", gp);
  for (size_t j = 0; j < p->nseries; ++j) {
    const size_t style = j % NXY_STYLES;
    if (lines)
      fprintf(gp, "%s$d%zu using 1:2 with lines lw 1.5 dt %zu lc rgb '%s'", j ? ", " : "",
              first_id + j, 1 + j / 2 % 4, xy_styles[style].colour);
    else
      fprintf(gp, "%s$d%zu using 1:2 with linespoints lw 1.5 pt %d ps 0.8 lc rgb '%s'",
              j ? ", " : "", first_id + j, xy_styles[style].point_type,
              xy_styles[style].colour);
    if (p->series[j].legend) {
      fputs(" title ", gp);
      fb_gnuplot_quoted(gp, p->series[j].legend);
    } else {
      fputs(" notitle", gp);
    }
  }
  fputc('\n', gp);
}

/* fb_gnuplot_script_fn of the figure. */
static void write_xy_script(FILE *gp, const void *ctx, const char *png_name)
{
  const xy_script *xs = ctx;
  const fb_plot_xy_opts *o = xs->opts;
  size_t id = 0;
  for (size_t i = 0; i < xs->npanels; ++i) {
    const fb_plot_xy_panel *p = &xs->panels[i];
    char unit[64];
    const double scale = panel_scale(p, panel_log_y(p), unit, sizeof unit);
    for (size_t j = 0; j < p->nseries; ++j)
      write_datablock(gp, id++, &p->series[j], o->log_x, panel_log_y(p), scale);
  }
  const size_t width = (size_t)(o->panel_width > 0 ? o->panel_width : XY_PANEL_WIDTH);
  const size_t height = (size_t)(o->panel_height > 0 ? o->panel_height : XY_PANEL_HEIGHT);
  fprintf(gp,
          "set encoding utf8\nset terminal pngcairo size %zu,%zu font 'Sans,9'\nset output ",
          width * xs->columns, height * xs->rows + (o->title ? 40 : 0));
  fb_gnuplot_quoted(gp, png_name);
  fputs(o->log_x ? "\nset termoption noenhanced\nset grid xtics mxtics ytics\nset logscale "
                   "x\nset format x '%g'\nset offsets 0, 0, graph 0.05, graph 0.05\nset xlabel "
                 : "\nset termoption noenhanced\nset grid\nset offsets graph 0.03, graph "
                   "0.03, graph 0.05, graph 0.05\nset xlabel ",
        gp);
  fb_gnuplot_quoted(gp, o->xlabel ? o->xlabel : "");
  fputc('\n', gp);
  write_xtics(gp, o);
  write_range(gp, "x", xs->x_lo, xs->x_hi);
  fprintf(gp, "set multiplot layout %zu,%zu", xs->rows, xs->columns);
  if (o->title) {
    fputs(" title ", gp);
    fb_gnuplot_quoted(gp, o->title);
  }
  fputc('\n', gp);
  id = 0;
  for (size_t i = 0; i < xs->npanels; ++i) {
    write_panel(gp, &xs->panels[i], id, o->lines);
    id += xs->panels[i].nseries;
  }
  fputs("unset multiplot\nset output\n", gp);
}

/* FB_EINVAL unless every panel has curves with point arrays and the
 * categorical axis, if any, has a label for every x. */
static int check_xy(const fb_plot_xy_panel *panels, size_t npanels, const fb_plot_xy_opts *o,
                    const char *path, fb_err *err)
{
  if (npanels == 0)
    return fb_err_set(err, FB_EINVAL, "%s: nothing to plot", path);
  if (o->xtic_labels && o->nxtics == 0)
    return fb_err_set(err, FB_EINVAL, "%s: xtic_labels without nxtics", path);
  for (size_t i = 0; i < npanels; ++i) {
    if (panels[i].nseries == 0 || !panels[i].series)
      return fb_err_set(err, FB_EINVAL, "%s: panel %zu has no curve", path, i + 1);
    for (size_t j = 0; j < panels[i].nseries; ++j) {
      const fb_plot_xy_series *s = &panels[i].series[j];
      if (s->n > 0 && (!s->x || !s->y))
        return fb_err_set(err, FB_EINVAL, "%s: panel %zu, curve %zu: no points given", path,
                          i + 1, j + 1);
      for (size_t k = 0; o->xtic_labels && k < s->n; ++k)
        if (!(s->x[k] >= 0 && s->x[k] <= (double)(o->nxtics - 1) && s->x[k] == floor(s->x[k])))
          return fb_err_set(err, FB_EINVAL,
                            "%s: panel %zu, curve %zu: x = %g is not a label index 0..%zu",
                            path, i + 1, j + 1, s->x[k], o->nxtics - 1);
    }
  }
  return FB_OK;
}

int fb_plot_xy_png(const fb_plot_xy_panel *panels, size_t npanels, const fb_plot_xy_opts *opts,
                   const char *path, fb_err *err)
{
  fb_plot_xy_opts o;
  fb_plot_xy_opts_default(&o);
  if (opts)
    o = *opts;
  if (!path || (npanels > 0 && !panels))
    return fb_err_set(err, FB_EINVAL, "fb_plot_xy_png: NULL argument");
  int rc = check_xy(panels, npanels, &o, path, err);
  if (rc != FB_OK)
    return rc;
  xy_script xs = {panels, npanels, &o, 0, 0, INFINITY, -INFINITY};
  /* About square: ceil(sqrt(n)) columns, at most XY_MAX_COLUMNS. */
  size_t columns = o.columns > 0 ? (size_t)o.columns : 1;
  while (o.columns <= 0 && columns < XY_MAX_COLUMNS && columns * columns < npanels)
    ++columns;
  xs.columns = columns < npanels ? columns : npanels;
  xs.rows = (npanels + xs.columns - 1) / xs.columns;
  for (size_t i = 0; i < npanels; ++i)
    for (size_t j = 0; j < panels[i].nseries; ++j)
      extend_range(panels[i].series[j].x, panels[i].series[j].n, o.log_x, &xs.x_lo, &xs.x_hi);
  if (o.xtic_labels) {
    xs.x_lo = 0;
    xs.x_hi = (double)(o.nxtics - 1);
  }
  return fb_gnuplot_png(write_xy_script, &xs, path, err);
}
