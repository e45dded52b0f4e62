/* Wireframe pictures of deformed shell meshes (the paper's Figs. 3 and 4)
 * through gnuplot's splot. */
#include <math.h>
#include <stdio.h>

#include "flexbond/io.h"

#include "io/plot_internal.h"

typedef struct mesh_script {
  const fb_mesh *m;
  const double *u;
  double scale;
  const double *cubes;
  size_t ncubes;
  double side;
  const char *title;
} mesh_script;

static void node_position(const mesh_script *ms, size_t node, double *p)
{
  const double *x = fb_mesh_node_xyz(ms->m, node);
  for (int k = 0; k < 3; ++k)
    p[k] = x[k] + (ms->u ? ms->scale * ms->u[6 * node + k] : 0.0);
}

/* 1 if the element's normal is within 30 degrees of the y axis. */
static int is_side_wall(const fb_mesh *m, size_t e)
{
  const size_t *n = fb_mesh_element_nodes(m, e);
  const double *a = fb_mesh_node_xyz(m, n[0]), *b = fb_mesh_node_xyz(m, n[1]);
  const double *c = fb_mesh_node_xyz(m, n[2]);
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  double nx = u[1] * v[2] - u[2] * v[1], ny = u[2] * v[0] - u[0] * v[2];
  double nz = u[0] * v[1] - u[1] * v[0];
  double len = sqrt(nx * nx + ny * ny + nz * nz);
  return len > 0 && fabs(ny) / len > cos(30.0 * 3.14159265358979323846 / 180.0);
}

/* Each element's outline as a closed polyline. Two blank lines end each
 * one: a single blank line would make splot join the outlines as the
 * scans of a surface grid. */
static void write_edges(FILE *gp, const mesh_script *ms)
{
  fputs("$edges << EOD\n", gp);
  for (size_t e = 0; e < fb_mesh_nelements(ms->m); ++e) {
    if (is_side_wall(ms->m, e))
      continue;
    const size_t *n = fb_mesh_element_nodes(ms->m, e);
    size_t nn = (size_t)fb_mesh_element_type(ms->m, e);
    for (size_t k = 0; k <= nn; ++k) {
      double p[3];
      node_position(ms, n[k % nn], p);
      fprintf(gp, "%.6g %.6g %.6g\n", p[0], p[1], p[2]);
    }
    fputs("\n\n", gp);
  }
  fputs("EOD\n", gp);
}

/* The twelve edges of each cube. */
static void write_cubes(FILE *gp, const mesh_script *ms)
{
  static const int corners[12][2][3] = {
      {{0, 0, 0}, {1, 0, 0}}, {{0, 1, 0}, {1, 1, 0}}, {{0, 0, 1}, {1, 0, 1}},
      {{0, 1, 1}, {1, 1, 1}}, {{0, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}},
      {{0, 0, 1}, {0, 1, 1}}, {{1, 0, 1}, {1, 1, 1}}, {{0, 0, 0}, {0, 0, 1}},
      {{1, 0, 0}, {1, 0, 1}}, {{0, 1, 0}, {0, 1, 1}}, {{1, 1, 0}, {1, 1, 1}}};
  fputs("$cubes << EOD\n", gp);
  for (size_t c = 0; c < ms->ncubes; ++c)
    for (int e = 0; e < 12; ++e) {
      for (int k = 0; k < 2; ++k) {
        const int *q = corners[e][k];
        fprintf(gp, "%.6g %.6g %.6g\n", ms->cubes[3 * c] + ms->side * (q[0] - 0.5),
                ms->cubes[3 * c + 1] + ms->side * (q[1] - 0.5),
                ms->cubes[3 * c + 2] + ms->side * (q[2] - 0.5));
      }
      fputs("\n\n", gp);
    }
  fputs("EOD\n", gp);
}

static void write_mesh_script(FILE *gp, const void *ctx, const char *png_name)
{
  const mesh_script *ms = ctx;
  write_edges(gp, ms);
  if (ms->ncubes)
    write_cubes(gp, ms);
  fputs("set terminal pngcairo size 1000,700 font 'Sans,10'\nset output ", gp);
  fb_gnuplot_quoted(gp, png_name);
  fputs("\nset termoption noenhanced\nunset key\nset view equal xyz\nset view 62, 28\n"
        "set xlabel 'x [m]'\nset ylabel 'y [m]'\nset zlabel 'z [m]'\n",
        gp);
  if (ms->title) {
    fputs("set title ", gp);
    fb_gnuplot_quoted(gp, ms->title);
    fputs("\n", gp);
  }
  fputs("splot $edges with lines lw 1 lc rgb '#1f4e9a'", gp);
  if (ms->ncubes)
    fputs(", $cubes with lines lw 2 lc rgb '#b22222'", gp);
  fputs("\nset output\n", gp);
}

int fb_plot_mesh_png(const fb_mesh *m, const double *dof_values, double scale,
                     const double *cube_xyz, size_t ncubes, double cube_side, const char *title,
                     const char *path, fb_err *err)
{
  if (fb_mesh_nelements(m) == 0)
    return fb_err_set(err, FB_EINVAL, "%s: the mesh has no elements to draw", path);
  const mesh_script ms = {m, dof_values, scale, cube_xyz, ncubes, cube_side, title};
  return fb_gnuplot_png(write_mesh_script, &ms, path, err);
}
