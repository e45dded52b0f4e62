/* SPDX-License-Identifier: BSD-3-Clause */
/* PNG figures of sampled results through gnuplot (http://gnuplot.info),
 * run on a script file with the data inline as datablocks (see
 * flexbond/io.h). Each curve gets a datablock of its own holding only the
 * samples of the time window, so curves of different results (System 1
 * and System 2, sampled alike or not) can share a panel. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/io.h"

#include "core/tmpfile.h"
#include "core/util.h"
#include "io/child.h"
#include "io/plot_internal.h"

/* Line styles of the curves of one panel, in order; a panel with more
 * curves reuses them cyclically. Blue solid and red dashed follow the
 * paper's System 1 / System 2 colours (Leite & Da Silva, Fig. 5). */
static const struct {
  const char *colour;
  int dash_type;
} line_styles[] = {{"#1f4e9a", 1}, {"#c0392b", 2}, {"#2e8b57", 4}, {"#7f7f7f", 5}};
enum { NLINE_STYLES = sizeof line_styles / sizeof line_styles[0] };

void fb_plot_opts_default(fb_plot_opts *opts)
{
  *opts = (fb_plot_opts){.title = NULL, .t_min = 0, .t_max = 0, .width = 0, .panel_height = 0};
}

void fb_gnuplot_quoted(FILE *fp, const char *s)
{
  fputc('\'', fp);
  for (; *s; ++s) {
    const unsigned char c = (unsigned char)*s;
    if (c == '\'')
      fputc('\'', fp);
    /* A line end would end the string and the command: the next line
     * would be gnuplot's to run ("!cmd" runs a shell command). */
    fputc(c < 0x20 || c == 0x7f ? '?' : c, fp);
  }
  fputc('\'', fp);
}

/* Rows [*first, *last] of r covering [t_min, t_max]: from the last sample
 * at or before t_min to the first at or after t_max, so the curve reaches
 * both edges of the window. 0 if the window misses the result. */
static int window_rows(const fb_result *r, double t_min, double t_max, size_t *first,
                       size_t *last)
{
  size_t n = fb_result_nsamples(r);
  if (n == 0 || fb_result_row(r, 0)[0] > t_max || fb_result_row(r, n - 1)[0] < t_min)
    return 0;
  size_t lo = 0;
  while (lo + 1 < n && fb_result_row(r, lo + 1)[0] <= t_min)
    ++lo;
  size_t hi = n - 1;
  while (hi > lo && fb_result_row(r, hi - 1)[0] >= t_max)
    --hi;
  *first = lo;
  *last = hi;
  return 1;
}

/* ---- SI prefixes. */

/* Unit symbols a prefix may go in front of (the first symbol of a
 * compound unit: "m/s^2", "N m"); kg and already prefixed units are not
 * among them. */
static const char *const si_symbols[] = {"N", "m",  "rad", "W", "J", "Pa",
                                         "s", "Hz", "V",   "A", "C", NULL};

/* 1 if unit starts with one of si_symbols, followed by its end or a
 * character that is no letter ("m/s^2" yes, "mm", "kg", "1" no). */
static int prefixable(const char *unit)
{
  if (!unit)
    return 0;
  size_t n = 0;
  while ((unit[n] >= 'a' && unit[n] <= 'z') || (unit[n] >= 'A' && unit[n] <= 'Z'))
    ++n;
  for (size_t i = 0; n && si_symbols[i]; ++i)
    if (strlen(si_symbols[i]) == n && !strncmp(unit, si_symbols[i], n))
      return 1;
  return 0;
}

double fb_plot_si_scale(double max_abs, const char *unit, char *out, size_t size)
{
  /* Powers of 1000 from 1e-9 to 1e9; the micro sign in UTF-8. */
  static const char *const prefixes[] = {"n", "\xc2\xb5", "m", "", "k", "M", "G"};
  int e3 = 0;
  if (prefixable(unit) && isfinite(max_abs) && max_abs > 0) {
    e3 = (int)floor(log10(max_abs) / 3.0);
    e3 = e3 < -3 ? -3 : e3 > 3 ? 3 : e3;
  }
  snprintf(out, size, "%s%s", prefixes[e3 + 3], unit ? unit : "");
  return pow(10.0, -3.0 * e3);
}

/* ---- Panels. */

/* What a panel draws, worked out before its data are written: the factor
 * its values are drawn times, the axis unit, and its y range. */
typedef struct panel_layout {
  double scale;
  char unit[64];
  int has_unit;  /* the label gets " [unit]" */
  double lo, hi; /* y range of the drawn values; lo > hi: autoscale */
  int off_scale; /* a sample outside the focus lies outside [lo, hi] */
  double f0, f1; /* the focus clipped to the window, or the window */
} panel_layout;

/* Smallest and largest finite value of p's curves over [t0, t1]. */
static void panel_extent(const fb_plot_panel *p, double t0, double t1, double *lo, double *hi)
{
  *lo = INFINITY;
  *hi = -INFINITY;
  for (size_t j = 0; j < p->nseries; ++j) {
    const fb_plot_series *s = &p->series[j];
    size_t first = 0, last = 0;
    if (!window_rows(s->result, t0, t1, &first, &last))
      continue;
    for (size_t k = first; k <= last; ++k) {
      const double *row = fb_result_row(s->result, k);
      if (isfinite(row[s->col + 1]) && row[0] >= t0 && row[0] <= t1) {
        *lo = fmin(*lo, row[s->col + 1]);
        *hi = fmax(*hi, row[s->col + 1]);
      }
    }
  }
}

static panel_layout panel_layout_of(const fb_plot_panel *p, double t_min, double t_max)
{
  panel_layout l = {.scale = 1.0, .lo = 1.0, .hi = 0.0, .f0 = t_min, .f1 = t_max};
  const int focus = p->focus_t0 < p->focus_t1 && p->focus_t0 < t_max && p->focus_t1 > t_min;
  if (focus) {
    l.f0 = fmax(p->focus_t0, t_min);
    l.f1 = fmin(p->focus_t1, t_max);
  }
  double lo = 0, hi = 0;
  panel_extent(p, l.f0, l.f1, &lo, &hi);
  const char *unit =
      p->ylabel ? p->unit : fb_result_col_unit(p->series[0].result, p->series[0].col + 1);
  l.has_unit = unit && *unit;
  if (l.has_unit)
    l.scale = fb_plot_si_scale(fmax(fabs(lo), fabs(hi)), unit, l.unit, sizeof l.unit);
  if (!(lo <= hi))
    return l; /* nothing finite: autoscale */
  if (lo == hi) {
    /* A constant curve (System 1's torsion angle is identically 0):
     * gnuplot's autoscale would widen the range itself, with a warning. */
    const double half = lo == 0 ? 1 : 0.5 * fabs(lo);
    l.lo = (lo - half) * l.scale;
    l.hi = (hi + half) * l.scale;
  } else if (focus) {
    const double margin = 0.05 * (hi - lo);
    l.lo = (lo - margin) * l.scale;
    l.hi = (hi + margin) * l.scale;
  }
  if (focus) {
    double before_lo = 0, before_hi = 0, after_lo = 0, after_hi = 0;
    panel_extent(p, t_min, l.f0, &before_lo, &before_hi);
    panel_extent(p, l.f1, t_max, &after_lo, &after_hi);
    l.off_scale = fmin(before_lo, after_lo) * l.scale < l.lo ||
                  fmax(before_hi, after_hi) * l.scale > l.hi;
  }
  return l;
}

/* Datablock $dN with the time and value columns of one series, the values
 * times scale. */
static void write_datablock(FILE *gp, size_t id, const fb_plot_series *s, double t_min,
                            double t_max, double scale)
{
  size_t first = 0, last = 0;
  window_rows(s->result, t_min, t_max, &first, &last);
  fprintf(gp, "$d%zu << EOD\n", id);
  for (size_t k = first; k <= last; ++k) {
    const double *row = fb_result_row(s->result, k);
    const double v = row[s->col + 1];
    if (isfinite(v))
      fprintf(gp, "%.10g %.10g\n", row[0], v * scale);
    else
      fprintf(gp, "%.10g NaN\n", row[0]);
  }
  fputs("EOD\n", gp);
}

static void write_ylabel(FILE *gp, const fb_plot_panel *p, const panel_layout *l)
{
  fputs("set ylabel ", gp);
  /* "name [unit]" as a gnuplot string expression: no buffer needed. */
  fb_gnuplot_quoted(gp, p->ylabel
                            ? p->ylabel
                            : fb_result_col_name(p->series[0].result, p->series[0].col + 1));
  if (l->has_unit) {
    fputs(".' ['.", gp);
    fb_gnuplot_quoted(gp, l->unit);
    fputs(".']'", gp);
  }
  fputc('\n', gp);
}

/* The y range, and the shading of the time outside the focus. */
static void write_yrange(FILE *gp, const fb_plot_panel *p, const panel_layout *l, double t_min,
                         double t_max)
{
  if (l->lo < l->hi)
    fprintf(gp, "set yrange [%.10g:%.10g]\n", l->lo, l->hi);
  else
    fputs("set autoscale y\n", gp);
  fputs("unset object\nunset label\n", gp);
  const double span[2][2] = {{t_min, l->f0}, {l->f1, t_max}};
  for (int k = 0; k < 2; ++k) {
    if (!(span[k][0] < span[k][1]))
      continue;
    fprintf(gp,
            "set object %d rect from %.10g, graph 0 to %.10g, graph 1 behind "
            "fc rgb '#e6e6e6' fs solid 1.0 noborder\n",
            k + 1, span[k][0], span[k][1]);
    if (!p->outside_label && !l->off_scale)
      continue;
    fprintf(gp, "set label %d ", k + 1);
    fb_gnuplot_quoted(gp, p->outside_label ? p->outside_label : "");
    if (l->off_scale) {
      fputc('.', gp);
      fb_gnuplot_quoted(gp, p->outside_label ? ", off scale" : "off scale");
    }
    fprintf(gp, " at %.10g, graph 0.9 center front boxed\n", 0.5 * (span[k][0] + span[k][1]));
  }
}

/* The plot command of panel p, whose first datablock is $d<first_id>. */
static void write_panel(FILE *gp, const fb_plot_panel *p, const panel_layout *l,
                        size_t first_id)
{
  int has_key = 0;
  for (size_t j = 0; j < p->nseries; ++j)
    has_key |= p->series[j].legend != NULL;
  fputs(has_key ? "set key top right\n" : "set key off\n", gp);
  write_ylabel(gp, p, l);
  fputs("plot ", gp);
  for (size_t j = 0; j < p->nseries; ++j) {
    size_t style = j % NLINE_STYLES;
    fprintf(gp, "%s$d%zu using 1:2 with lines lw 1.5 dt %d lc rgb '%s'", j ? ", " : "",
            first_id + j, line_styles[style].dash_type, line_styles[style].colour);
    if (p->series[j].legend) {
      fputs(" title ", gp);
      fb_gnuplot_quoted(gp, p->series[j].legend);
    } else {
      fputs(" notitle", gp);
    }
  }
  fputc('\n', gp);
}

/* Most panels of one figure (a layout each on the stack). */
enum { MAX_PANELS = 64 };

void fb_plot_panels_script(FILE *gp, const fb_plot_panel *panels, size_t npanels,
                           const fb_plot_opts *o, double t_min, double t_max,
                           const char *png_name)
{
  /* fb_plot_panels_png refuses more panels than fit in layout. */
  panel_layout layout[MAX_PANELS];
  if (npanels > MAX_PANELS)
    return;
  size_t id = 0;
  for (size_t i = 0; i < npanels; ++i) {
    layout[i] = panel_layout_of(&panels[i], t_min, t_max);
    for (size_t j = 0; j < panels[i].nseries; ++j)
      write_datablock(gp, id++, &panels[i].series[j], t_min, t_max, layout[i].scale);
  }
  int width = o->width > 0 ? o->width : 900;
  size_t panel_height = o->panel_height > 0 ? (size_t)o->panel_height : 220;
  size_t height = panel_height * npanels + (o->title ? 40 : 0);
  fprintf(gp, "set encoding utf8\nset terminal pngcairo size %d,%zu font 'Sans,9'\nset output ",
          width, height);
  fb_gnuplot_quoted(gp, png_name);
  /* Labels over curves (the shading's) on an opaque box, to be read. */
  fputs("\nset termoption noenhanced\nset grid\nset xlabel 't [s]'\n"
        "set style textbox opaque noborder\n",
        gp);
  fprintf(gp, "set xrange [%.10g:%.10g]\n", t_min, t_max);
  fprintf(gp, "set multiplot layout %zu,1", npanels);
  if (o->title) {
    fputs(" title ", gp);
    fb_gnuplot_quoted(gp, o->title);
  }
  fputc('\n', gp);
  id = 0;
  for (size_t i = 0; i < npanels; ++i) {
    write_yrange(gp, &panels[i], &layout[i], t_min, t_max);
    write_panel(gp, &panels[i], &layout[i], id);
    id += panels[i].nseries;
  }
  fputs("unset multiplot\nset output\n", gp);
}

/* FB_EINVAL unless every panel has curves, every column exists and every
 * curve has samples in [t_min, t_max]. */
static int check_panels(const fb_plot_panel *panels, size_t npanels, double t_min, double t_max,
                        const char *path, fb_err *err)
{
  if (npanels == 0)
    return fb_err_set(err, FB_EINVAL, "%s: nothing to plot", path);
  if (npanels > MAX_PANELS)
    return fb_err_set(err, FB_EINVAL, "%s: %zu panels, at most %d fit one figure", path,
                      npanels, MAX_PANELS);
  for (size_t i = 0; i < npanels; ++i) {
    if (panels[i].nseries == 0)
      return fb_err_set(err, FB_EINVAL, "%s: panel %zu has no curve", path, i + 1);
    for (size_t j = 0; j < panels[i].nseries; ++j) {
      const fb_plot_series *s = &panels[i].series[j];
      size_t first = 0, last = 0;
      if (s->col + 1 >= fb_result_ncols(s->result))
        return fb_err_set(err, FB_EINVAL, "%s: no output column %zu", path, s->col);
      if (!window_rows(s->result, t_min, t_max, &first, &last))
        return fb_err_set(err, FB_EINVAL, "%s: no sample of '%s' in t = %g..%g s", path,
                          fb_result_col_name(s->result, s->col + 1), t_min, t_max);
    }
  }
  return FB_OK;
}

/* Writes the script made by fn, drawing into png_name, to the file
 * script. A file rather than a pipe: gnuplot missing or failing early
 * cannot raise SIGPIPE in this process, and its exit status tells.
 * fb_out reports a full disk with its errno. */
static int write_script_file(const char *script, fb_gnuplot_script_fn fn, const void *ctx,
                             const char *png_name, const char *path, fb_err *err)
{
  fb_out *o = NULL;
  int rc = fb_out_open(script, &o, err);
  if (rc == FB_OK) {
    fn(fb_out_stream(o), ctx, png_name);
    rc = fb_out_commit(&o, err);
  }
  if (rc != FB_OK)
    fb_err_prefix(err, "%s: the gnuplot script: ", path);
  return rc;
}

/* The time-series figure as a gnuplot script writer. */
typedef struct panels_script {
  const fb_plot_panel *panels;
  size_t npanels;
  const fb_plot_opts *opts;
  double t_min, t_max;
} panels_script;

static void write_panels_script(FILE *gp, const void *ctx, const char *png_name)
{
  const panels_script *ps = ctx;
  fb_plot_panels_script(gp, ps->panels, ps->npanels, ps->opts, ps->t_min, ps->t_max, png_name);
}

int fb_plot_panels_png(const fb_plot_panel *panels, size_t npanels, const fb_plot_opts *opts,
                       const char *path, fb_err *err)
{
  fb_plot_opts o;
  fb_plot_opts_default(&o);
  if (opts)
    o = *opts;
  double t_min = o.t_min, t_max = o.t_max;
  if (npanels > 0 && panels[0].nseries > 0 && !(t_min < t_max)) {
    const fb_result *r = panels[0].series[0].result;
    size_t n = fb_result_nsamples(r);
    t_min = n ? fb_result_row(r, 0)[0] : 0;
    t_max = n ? fb_result_row(r, n - 1)[0] : 0;
  }
  int rc = check_panels(panels, npanels, t_min, t_max, path, err);
  if (rc != FB_OK)
    return rc;
  /* A run of one sample has an empty span; gnuplot needs a range. */
  if (!(t_min < t_max))
    t_max = t_min + 1;
  const panels_script ps = {panels, npanels, &o, t_min, t_max};
  return fb_gnuplot_png(write_panels_script, &ps, path, err);
}

/* The files of one gnuplot run, in its private directory: fixed names,
 * so that gnuplot, started there, never reads a path of the user's. */
static const char gp_script[] = "plot.gp", gp_log[] = "gnuplot.log";

/* Runs gnuplot on the script in dir and checks the image it drew. */
static int draw_in(const char *dir, const char *image_name, fb_child_check_fn check,
                   const char *path, fb_err *err)
{
  char program[] = "gnuplot", script[sizeof gp_script];
  memcpy(script, gp_script, sizeof gp_script);
  char *argv[] = {program, script, NULL};
  const fb_child_spec spec = {.program = program,
                              .argv = argv,
                              .cwd = dir,
                              .log = gp_log,
                              .timeout_s = FB_GNUPLOT_TIMEOUT_S};
  char *image = NULL;
  int rc = fb_child_make(&spec, image_name, check, path, &image, err);
  if (rc == FB_OK && rename(image, path) != 0)
    rc = fb_err_set(err, FB_EIO, "%s: cannot rename the plot into place: %s", path,
                    strerror(errno));
  free(image);
  return rc;
}

int fb_gnuplot_draw(fb_gnuplot_script_fn fn, const void *ctx, const char *image_name,
                    fb_child_check_fn check, const char *path, fb_err *err)
{
  /* A private directory beside path (the same file system, so the image
   * is renamed into place): nobody else can plant a file or a link at
   * the names gnuplot writes. */
  char *dir = NULL;
  const int e = fb_tmpdir_create(path, "plot", &dir);
  if (e != 0)
    return fb_err_set(err, e == ENOMEM ? FB_ENOMEM : FB_EIO,
                      "%s: cannot create a directory for gnuplot: %s", path, strerror(e));
  char *script = fb_path_join(dir, gp_script);
  int rc = script ? write_script_file(script, fn, ctx, image_name, path, err)
                  : fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  if (rc == FB_OK)
    rc = draw_in(dir, image_name, check, path, err);
  free(script);
  const char *const names[] = {gp_script, image_name, gp_log};
  fb_child_dir_remove(dir, names, sizeof names / sizeof names[0]);
  return rc;
}

int fb_gnuplot_png(fb_gnuplot_script_fn fn, const void *ctx, const char *path, fb_err *err)
{
  return fb_gnuplot_draw(fn, ctx, "plot.png", fb_png_check, path, err);
}

int fb_plot_png(const fb_result *r, const size_t *cols, size_t ncols, const char *title,
                const char *path, fb_err *err)
{
  if (ncols == 0)
    return fb_err_set(err, FB_EINVAL, "%s: nothing to plot", path);
  fb_plot_series *series = malloc(ncols * sizeof *series);
  fb_plot_panel *panels = malloc(ncols * sizeof *panels);
  int rc = FB_OK;
  if (!series || !panels)
    rc = fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  for (size_t j = 0; rc == FB_OK && j < ncols; ++j) {
    series[j] = (fb_plot_series){.result = r, .col = cols[j], .legend = NULL};
    panels[j] = (fb_plot_panel){.series = &series[j], .nseries = 1, .ylabel = NULL};
  }
  if (rc == FB_OK) {
    fb_plot_opts opts;
    fb_plot_opts_default(&opts);
    opts.title = title;
    rc = fb_plot_panels_png(panels, ncols, &opts, path, err);
  }
  free(panels);
  free(series);
  return rc;
}
