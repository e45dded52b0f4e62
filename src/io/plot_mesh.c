/* SPDX-License-Identifier: BSD-3-Clause */
/* A vehicle's mode shape as a 3-D picture (the paper's Figs. 3 and 4)
 * through gnuplot's splot: the hull's outline, its mounted bodies and
 * wheels at rest in grey; the same displaced and coloured by how far
 * each point moves. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/io.h"

#include "io/plot_internal.h"

typedef struct mode_script {
  const fb_plot_mode *pic; /* the frame being drawn */
  const fb_plot_mode *frames;
  size_t nframes;
  double frame_seconds; /* an animation's: how long each frame shows */
  size_t *outline;      /* the hull's outline, 2 nodes per edge (fb_mesh_outline) */
  size_t noutline;
  double umax;         /* largest displacement in the shape's units */
  double scale;        /* m drawn per unit of the shape */
  double lo[3], hi[3]; /* the drawing's extent, m */
} mode_script;

enum { WHEEL_SEGMENTS = 36 };
static const double PI = 3.14159265358979323846;

static void unit_normal(const fb_mesh *m, size_t e, double *n)
{
  fb_mesh_element_area_vector(m, e, n);
  const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (int k = 0; k < 3; ++k)
    n[k] = len > 0 ? n[k] / len : 0.0;
}

/* 1 if the element's normal is within 30 degrees of the y axis. */
static int is_side_wall(const fb_mesh *m, size_t e)
{
  double n[3];
  unit_normal(m, e, n);
  return fabs(n[1]) > cos(30.0 * PI / 180.0);
}

/* ---- Points, at rest (moved 0) or displaced (moved 1). */

static double node_motion(const fb_plot_mode *pic, size_t node)
{
  const double *u = pic->shape + 6 * node;
  return sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
}

static void node_point(const mode_script *ms, size_t node, int moved, double *p)
{
  const fb_plot_mode *pic = ms->pic;
  const double *x = fb_mesh_node_xyz(pic->mesh, node);
  for (int k = 0; k < 3; ++k)
    p[k] = x[k] + (moved ? ms->scale * pic->shape[6 * node + k] : 0.0);
}

/* Writes a point (of the mesh's frame, drawn in the picture's: moved by
 * the origin) and, displaced, its colour value. */
static void put(FILE *gp, const mode_script *ms, const double *p, int moved, double value)
{
  const double *o = ms->frames->origin;
  if (moved)
    fprintf(gp, "%.6g %.6g %.6g %.6g\n", o[0] + p[0], o[1] + p[1], o[2] + p[2], value);
  else
    fprintf(gp, "%.6g %.6g %.6g\n", o[0] + p[0], o[1] + p[1], o[2] + p[2]);
}

/* Two blank lines end each polyline: one would make splot join them as
 * the scans of a surface grid. */
static void end_line(FILE *gp)
{
  fputs("\n\n", gp);
}

static void put_node(FILE *gp, const mode_script *ms, size_t node, int moved)
{
  const fb_plot_mode *pic = ms->pic;
  double p[3];
  node_point(ms, node, moved, p);
  put(gp, ms, p, moved, node_motion(pic, node));
}

static void write_outline(FILE *gp, const mode_script *ms, int moved)
{
  for (size_t i = 0; i < ms->noutline; ++i) {
    put_node(gp, ms, ms->outline[2 * i], moved);
    put_node(gp, ms, ms->outline[2 * i + 1], moved);
    end_line(gp);
  }
}

static void write_elements(FILE *gp, const mode_script *ms)
{
  const fb_plot_mode *pic = ms->pic;
  for (size_t e = 0; e < fb_mesh_nelements(pic->mesh); ++e) {
    if (is_side_wall(pic->mesh, e))
      continue;
    const size_t *nd = fb_mesh_element_nodes(pic->mesh, e);
    const size_t nn = (size_t)fb_mesh_element_type(pic->mesh, e);
    for (size_t k = 0; k <= nn; ++k)
      put_node(gp, ms, nd[k % nn], 1);
    end_line(gp);
  }
}

/* The twelve edges of body b's cube. */
static void write_cube(FILE *gp, const mode_script *ms, size_t b, int moved)
{
  const fb_plot_mode *pic = ms->pic;
  static const int corners[12][2][3] = {
      {{0, 0, 0}, {1, 0, 0}}, {{0, 1, 0}, {1, 1, 0}}, {{0, 0, 1}, {1, 0, 1}},
      {{0, 1, 1}, {1, 1, 1}}, {{0, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}},
      {{0, 0, 1}, {0, 1, 1}}, {{1, 0, 1}, {1, 1, 1}}, {{0, 0, 0}, {0, 0, 1}},
      {{1, 0, 0}, {1, 0, 1}}, {{0, 1, 0}, {0, 1, 1}}, {{1, 1, 0}, {1, 1, 1}}};
  const fb_plot_body *body = &pic->body[b];
  const double dz = moved ? ms->scale * body->dz : 0.0;
  for (int e = 0; e < 12; ++e) {
    for (int k = 0; k < 2; ++k) {
      const int *q = corners[e][k];
      const double p[3] = {body->xyz[0] + pic->body_side * (q[0] - 0.5),
                           body->xyz[1] + pic->body_side * (q[1] - 0.5),
                           body->xyz[2] + pic->body_side * (q[2] - 0.5) + dz};
      put(gp, ms, p, moved, fabs(body->dz));
    }
    end_line(gp);
  }
}

/* Wheel w's rim and the line from its suspension's attachment point to
 * its top. */
static void write_wheel(FILE *gp, const mode_script *ms, size_t w, int moved)
{
  const fb_plot_mode *pic = ms->pic;
  const fb_plot_wheel *wh = &pic->wheel[w];
  const double r = pic->wheel_radius;
  const double dz = moved ? ms->scale * wh->dz : 0.0;
  const double top[3] = {wh->top[0], wh->top[1],
                         wh->top[2] + (moved ? ms->scale * wh->top_dz : 0.0)};
  const double rim_top[3] = {wh->top[0], wh->top[1], wh->top[2] - 0.5 * r + dz};
  put(gp, ms, top, moved, fabs(wh->top_dz));
  put(gp, ms, rim_top, moved, fabs(wh->dz));
  end_line(gp);
  for (int k = 0; k <= WHEEL_SEGMENTS; ++k) {
    const double a = 2.0 * PI * k / WHEEL_SEGMENTS;
    const double p[3] = {wh->top[0] + r * sin(a), wh->top[1], rim_top[2] - r + r * cos(a)};
    put(gp, ms, p, moved, fabs(wh->dz));
  }
  end_line(gp);
}

static void write_parts(FILE *gp, const mode_script *ms, int moved)
{
  const fb_plot_mode *pic = ms->pic;
  for (size_t b = 0; b < pic->nbodies; ++b)
    write_cube(gp, ms, b, moved);
  for (size_t w = 0; w < pic->nwheels; ++w)
    write_wheel(gp, ms, w, moved);
}

/* ---- The drawing's extent and its axes. */

static void extend(mode_script *ms, const double *p)
{
  for (int k = 0; k < 3; ++k) {
    ms->lo[k] = fmin(ms->lo[k], ms->frames->origin[k] + p[k]);
    ms->hi[k] = fmax(ms->hi[k], ms->frames->origin[k] + p[k]);
  }
}

/* The largest displacement in the shape: hull node, body or wheel. */
static double largest_motion(const fb_plot_mode *pic)
{
  double big = 0.0;
  for (size_t i = 0; i < fb_mesh_nnodes(pic->mesh); ++i)
    big = fmax(big, node_motion(pic, i));
  for (size_t b = 0; b < pic->nbodies; ++b)
    big = fmax(big, fabs(pic->body[b].dz));
  for (size_t w = 0; w < pic->nwheels; ++w)
    big = fmax(big, fmax(fabs(pic->wheel[w].dz), fabs(pic->wheel[w].top_dz)));
  return big;
}

/* The extent of everything drawn in ms->pic, at rest and displaced. */
static void measure_frame(mode_script *ms)
{
  const fb_plot_mode *pic = ms->pic;
  for (size_t i = 0; i < fb_mesh_nnodes(pic->mesh); ++i)
    for (int moved = 0; moved < 2; ++moved) {
      double p[3];
      node_point(ms, i, moved, p);
      extend(ms, p);
    }
  const double h = 0.5 * pic->body_side, r = pic->wheel_radius;
  for (size_t b = 0; b < pic->nbodies; ++b) {
    const double *c = pic->body[b].xyz, dz = ms->scale * pic->body[b].dz;
    extend(ms, (double[3]){c[0] - h, c[1] - h, fmin(c[2], c[2] + dz) - h});
    extend(ms, (double[3]){c[0] + h, c[1] + h, fmax(c[2], c[2] + dz) + h});
  }
  for (size_t w = 0; w < pic->nwheels; ++w) {
    const fb_plot_wheel *wh = &pic->wheel[w];
    const double dz = ms->scale * wh->dz;
    extend(ms, (double[3]){wh->top[0] - r, wh->top[1], wh->top[2] - 2.5 * r + fmin(dz, 0.0)});
    extend(ms, (double[3]){wh->top[0] + r, wh->top[1],
                           fmax(wh->top[2] + ms->scale * wh->top_dz, wh->top[2] + dz)});
  }
}

/* The extent of every frame. */
static void measure(mode_script *ms)
{
  for (int k = 0; k < 3; ++k) {
    ms->lo[k] = INFINITY;
    ms->hi[k] = -INFINITY;
  }
  for (size_t f = 0; f < ms->nframes; ++f) {
    ms->pic = &ms->frames[f];
    measure_frame(ms);
  }
  ms->pic = ms->frames;
}

/* A tic step of 1, 2 or 5 times a power of ten giving about four
 * intervals over span. */
static double tic_step(double span)
{
  const double raw = span / 4.0;
  const double mag = pow(10.0, floor(log10(raw)));
  const double r = raw / mag;
  return (r < 1.5 ? 1.0 : r < 3.5 ? 2.0 : r < 7.5 ? 5.0 : 10.0) * mag;
}

/* The axis' range, the extent with a margin of a tenth of the largest
 * extent, and tics that keep a third of a step from its ends: the ends
 * are where one axis' labels meet the next axis' in the 3-D view. */
static void write_axis(FILE *gp, char axis, double lo, double hi, double margin)
{
  lo -= margin;
  hi += margin;
  const double step = tic_step(hi - lo);
  double first = ceil(lo / step) * step, last = floor(hi / step) * step;
  if (first - lo < step / 3.0)
    first += step;
  if (hi - last < step / 3.0)
    last -= step;
  fprintf(gp, "set %crange [%.6g:%.6g]\n", axis, lo, hi);
  if (last >= first)
    fprintf(gp, "set %ctics %.6g, %.6g, %.6g\n", axis, first, step, last + 0.5 * step);
  else
    fprintf(gp, "set %ctics (%.6g)\n", axis, 0.5 * (lo + hi));
}

static void write_axes(FILE *gp, const mode_script *ms)
{
  double big = 0.0;
  for (int k = 0; k < 3; ++k)
    big = fmax(big, ms->hi[k] - ms->lo[k]);
  const double margin = 0.1 * big;
  for (int k = 0; k < 3; ++k)
    write_axis(gp, "xyz"[k], ms -> lo[k], ms -> hi[k], margin);
  fputs("set xyplane at ", gp);
  fprintf(gp, "%.6g\n", ms->lo[2] - margin);
  fputs("set xlabel 'x [m]' offset 0,-1\nset ylabel 'y [m]' offset 2,0\n"
        "set zlabel 'z [m]' rotate parallel offset 2,0\n",
        gp);
}

static void write_titles(FILE *gp, const char *title, const char *subtitle)
{
  if (title) {
    fputs("set title ", gp);
    fb_gnuplot_quoted(gp, title);
    fputs(" font 'Sans,12'\n", gp);
  }
  if (subtitle) {
    fputs("set label 1 ", gp);
    fb_gnuplot_quoted(gp, subtitle);
    fputs(" at screen 0.5, 0.915 center font 'Sans,10'\n", gp);
  }
}

/* Dark blue to dark red through green and orange, from 0 to top: every
 * colour stands out against the white ground and the grey of a hull at
 * rest. */
static void write_colours(FILE *gp, double top, const char *label)
{
  fputs("set palette defined (0 '#1f4e9a', 0.4 '#2ca25f', 0.7 '#f28e2b', 1 '#b2182b')\n", gp);
  fprintf(gp, "set cbrange [0:%.6g]\n", top > 0 ? top : 1.0);
  fputs("set cblabel ", gp);
  fb_gnuplot_quoted(gp, label);
  fputs("\nset colorbox vertical user origin 0.9, 0.25 size 0.02, 0.5\n", gp);
}

/* The settings every frame shares: view, axes, colours. */
static void write_view(FILE *gp, const mode_script *ms)
{
  fputs("set termoption noenhanced\nunset key\nset view equal xyz\nset view 62, 28, 1.45\n",
        gp);
  write_axes(gp, ms);
  write_colours(gp, ms->umax,
                ms->frames->colour_label ? ms->frames->colour_label
                                         : "displacement (shape units)");
}

/* Frame f's displaced parts as the datablock $movedF. */
static void write_moved(FILE *gp, mode_script *ms, size_t f)
{
  ms->pic = &ms->frames[f];
  fprintf(gp, "$moved%zu << EOD\n", f);
  write_elements(gp, ms);
  write_outline(gp, ms, 1);
  write_parts(gp, ms, 1);
  fputs("EOD\n", gp);
}

static void write_mode_script(FILE *gp, const void *ctx, const char *image_name)
{
  mode_script ms = *(const mode_script *)ctx;
  fputs("$rest << EOD\n", gp);
  write_outline(gp, &ms, 0);
  write_parts(gp, &ms, 0);
  fputs("EOD\n", gp);
  for (size_t f = 0; f < ms.nframes; ++f)
    write_moved(gp, &ms, f);
  if (ms.frame_seconds > 0)
    /* gnuplot's delay is in hundredths of a second. */
    fprintf(gp, "set terminal gif animate delay %d optimize size 880,608 font 'Sans,9'\n",
            (int)fmax(1.0, round(100.0 * ms.frame_seconds)));
  else
    fputs("set terminal pngcairo size 1100,760 font 'Sans,10'\n", gp);
  fputs("set output ", gp);
  fb_gnuplot_quoted(gp, image_name);
  fputc('\n', gp);
  write_view(gp, &ms);
  for (size_t f = 0; f < ms.nframes; ++f) {
    write_titles(gp, ms.frames[f].title, ms.frames[f].subtitle);
    fprintf(gp,
            "splot $rest with lines lw 1 lc rgb '#a8a8a8', "
            "$moved%zu using 1:2:3:4 with lines lw 1.5 lc palette\n",
            f);
  }
  fputs("set output\n", gp);
}

/* Checks the frames' sizes and fills ms's common scale, outline and
 * extent (ms->outline new). */
static int prepare(mode_script *ms, const char *path, fb_err *err)
{
  const fb_plot_mode *pic = ms->frames;
  if (ms->nframes == 0)
    return fb_err_set(err, FB_EINVAL, "%s: no frame to draw", path);
  if (fb_mesh_nelements(pic->mesh) == 0)
    return fb_err_set(err, FB_EINVAL, "%s: the mesh has no elements to draw", path);
  if (!(pic->largest_drawn > 0) || !(pic->body_side >= 0) || !(pic->wheel_radius >= 0))
    return fb_err_set(err, FB_EINVAL,
                      "%s: largest displacement drawn %g m, body side %g m, wheel radius %g m",
                      path, pic->largest_drawn, pic->body_side, pic->wheel_radius);
  for (size_t f = 0; f < ms->nframes; ++f)
    ms->umax = fmax(ms->umax, largest_motion(&ms->frames[f]));
  if (!isfinite(ms->umax))
    return fb_err_set(err, FB_EINVAL, "%s: a displacement is not finite", path);
  /* A shape that does not move is drawn at rest. */
  ms->scale = ms->umax > 0 ? pic->largest_drawn / ms->umax : 0.0;
  int rc = fb_mesh_outline(pic->mesh, 20.0 * PI / 180.0, &ms->outline, &ms->noutline, err);
  if (!rc)
    measure(ms);
  return rc;
}

int fb_plot_mode_png(const fb_plot_mode *pic, const char *path, fb_err *err)
{
  mode_script ms = {.pic = pic, .frames = pic, .nframes = 1};
  int rc = prepare(&ms, path, err);
  if (!rc)
    rc = fb_gnuplot_png(write_mode_script, &ms, path, err);
  free(ms.outline);
  return rc;
}

int fb_plot_mode_gif(const fb_plot_mode *frames, size_t nframes, double frame_seconds,
                     const char *path, fb_err *err)
{
  if (!(frame_seconds > 0 && frame_seconds <= 60))
    return fb_err_set(err, FB_EINVAL, "%s: a frame lasts %g s, not in (0, 60]", path,
                      frame_seconds);
  mode_script ms = {
      .pic = frames, .frames = frames, .nframes = nframes, .frame_seconds = frame_seconds};
  for (size_t f = 1; f < nframes; ++f)
    if (frames[f].mesh != frames[0].mesh || frames[f].nbodies != frames[0].nbodies ||
        frames[f].nwheels != frames[0].nwheels)
      return fb_err_set(err, FB_EINVAL, "%s: frame %zu draws other parts than frame 1", path,
                        f + 1);
  int rc = prepare(&ms, path, err);
  if (!rc)
    rc = fb_gnuplot_draw(write_mode_script, &ms, "plot.gif", fb_gif_check, path, err);
  size_t drawn = 0;
  if (!rc)
    rc = fb_gif_frames(path, &drawn, err);
  if (!rc && drawn != nframes) {
    remove(path);
    rc =
        fb_err_set(err, FB_EIO, "%s: gnuplot drew %zu of the %zu frames", path, drawn, nframes);
  }
  free(ms.outline);
  return rc;
}

/* ---- A field over the elements. */

typedef struct field_script {
  const fb_plot_field *pic;
  mode_script extent; /* lo, hi: the mesh's, for the axes */
  double top;         /* the largest value */
} field_script;

/* Element e as a pm3d patch of two scans of two points (a triangle's
 * third node twice), each point with e's value: pm3d colours the patch
 * by its corners' mean, the value. Two blank lines start the next. */
static void write_patch(FILE *gp, const fb_plot_field *pic, size_t e)
{
  const size_t *nd = fb_mesh_element_nodes(pic->mesh, e);
  const int quad = fb_mesh_element_type(pic->mesh, e) == FB_ELEM_QUAD4;
  const size_t scan[4] = {nd[0], nd[1], quad ? nd[3] : nd[2], nd[2]};
  for (int k = 0; k < 4; ++k) {
    const double *x = fb_mesh_node_xyz(pic->mesh, scan[k]);
    fprintf(gp, "%.6g %.6g %.6g %.6g\n", pic->origin[0] + x[0], pic->origin[1] + x[1],
            pic->origin[2] + x[2], pic->values[e]);
    if (k == 1)
      fputc('\n', gp);
  }
  end_line(gp);
}

static void write_field_script(FILE *gp, const void *ctx, const char *image_name)
{
  const field_script *fs = ctx;
  const fb_plot_field *pic = fs->pic;
  fputs("$cells << EOD\n", gp);
  for (size_t e = 0; e < fb_mesh_nelements(pic->mesh); ++e)
    write_patch(gp, pic, e);
  fputs("EOD\nset terminal pngcairo size 1600,700 font 'Sans,10'\nset output ", gp);
  fb_gnuplot_quoted(gp, image_name);
  fputs("\nset termoption noenhanced\nunset key\nset view equal xyz\n", gp);
  write_axes(gp, &fs->extent);
  write_colours(gp, fs->top, pic->colour_label);
  if (pic->title) {
    fputs("set label 2 ", gp);
    fb_gnuplot_quoted(gp, pic->title);
    fputs(" at screen 0.5, 0.96 center font 'Sans,12'\n", gp);
  }
  write_titles(gp, NULL, pic->subtitle);
  /* Two panels, the hull seen from above and from below (a floor's
   * stresses are on its underside's view), one colour bar for both. */
  fputs("set pm3d depthorder border lc rgb '#404040' lw 0.4\nset pm3d corners2color mean\n"
        "set multiplot\nset size 0.47, 0.88\n"
        "set origin 0.0, 0.02\nunset colorbox\nset title 'from above'\nset view 62, 28, 1.45\n"
        "splot $cells using 1:2:3:4 with pm3d\nunset label\n"
        "set origin 0.44, 0.02\nset colorbox vertical user origin 0.93, 0.25 size 0.012, 0.5\n"
        "set cblabel offset 3, 0\n"
        "set title 'from below'\nset view 118, 28, 1.45\n"
        "splot $cells using 1:2:3:4 with pm3d\nunset multiplot\nset output\n",
        gp);
}

int fb_plot_field_png(const fb_plot_field *pic, const char *path, fb_err *err)
{
  const fb_mesh *m = pic->mesh;
  if (!m || fb_mesh_nelements(m) == 0 || !pic->values || !pic->colour_label)
    return fb_err_set(err, FB_EINVAL, "%s: no mesh, values or colour label to draw", path);
  field_script fs = {.pic = pic};
  for (int k = 0; k < 3; ++k) {
    fs.extent.lo[k] = INFINITY;
    fs.extent.hi[k] = -INFINITY;
  }
  for (size_t i = 0; i < fb_mesh_nnodes(m); ++i)
    for (int k = 0; k < 3; ++k) {
      const double x = pic->origin[k] + fb_mesh_node_xyz(m, i)[k];
      fs.extent.lo[k] = fmin(fs.extent.lo[k], x);
      fs.extent.hi[k] = fmax(fs.extent.hi[k], x);
    }
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    if (!isfinite(pic->values[e]) || pic->values[e] < 0)
      return fb_err_set(err, FB_EINVAL, "%s: element %ld's value %g is not finite and >= 0",
                        path, fb_mesh_element_id(m, e), pic->values[e]);
    fs.top = fmax(fs.top, pic->values[e]);
  }
  return fb_gnuplot_png(write_field_script, &fs, path, err);
}
