/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond run's hull stresses (System 2; docs/stresses.md "Over a run"):
 * the peak per element over the run's samples in the road's window
 * (flexbond/hull_stress.h), as DIR/stress_peaks.csv, DIR/stress_peak.vtu
 * (ParaView), DIR/stress_peak.png, and the report's table of hot spots. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/escape.h"
#include "flexbond/hull_stress.h"
#include "flexbond/io.h"
#include "flexbond/vehicle.h"

#include "cli.h"

int cli_run_stress(const fb_vehicle *v, double t_from, cli_run_system *run, fb_err *err)
{
  int rc = fb_hull_stress_new(v, &run->stress, err);
  if (!rc)
    rc = fb_hull_stress_peaks_of(run->stress, run->motion, t_from, &run->peaks, err);
  return rc;
}

void cli_run_stress_free(cli_run_system *run)
{
  fb_hull_stress_peaks_free(&run->peaks);
  fb_hull_stress_free(&run->stress);
}

/* Element e's centroid (the mean of its nodes) in the file's frame. */
static void centroid(const fb_scenario *s, const fb_mesh *m, size_t e, double *c)
{
  double offset[3];
  fb_scenario_frame_offset(s, offset);
  fb_mesh_element_centroid(m, e, c);
  for (int k = 0; k < 3; ++k)
    c[k] += offset[k];
}

/* Element e's section (its element set's name), "" for none. */
static const char *section_of(const fb_mesh *m, size_t e)
{
  const long sec = fb_mesh_element_section(m, e);
  return sec >= 0 ? fb_mesh_section_elset(m, (size_t)sec) : "";
}

typedef struct stress_csv {
  const fb_scenario *s;
  const cli_run_system *run;
} stress_csv;

static void write_peaks_csv(FILE *fp, const void *ctx)
{
  const stress_csv *c = ctx;
  const fb_hull_stress_peaks *p = c->run->peaks;
  const fb_mesh *m = fb_hull_stress_mesh(c->run->stress);
  const int sections = fb_mesh_nsections(m) > 0;
  fprintf(fp,
          "element_id,%sx [m],y [m],z [m],von_mises_peak [Pa],time [s],surface,"
          "range [Pa],range_surface\n",
          sections ? "section," : "");
  for (size_t e = 0; e < p->nelements; ++e) {
    double x[3];
    centroid(c->s, m, e, x);
    fprintf(fp, "%ld,", fb_mesh_element_id(m, e));
    if (sections) {
      fb_csv_write_field(fp, section_of(m, e), FB_CSV_TEXT);
      fputc(',', fp);
    }
    fprintf(fp, "%.10g,%.10g,%.10g,%.10g,%.10g,%s,%.10g,%s\n", x[0], x[1], x[2],
            p->von_mises[e], p->time[e], fb_hull_surface_name(p->surface[e]), p->range[e],
            fb_hull_surface_name(p->range_surface[e]));
  }
}

static int write_peaks_vtu(cli_outdir *od, const fb_scenario *s, const cli_run_system *run,
                           fb_err *err)
{
  const fb_hull_stress_peaks *p = run->peaks;
  const fb_vtu_cell_array cells[3] = {
      {"von_mises_peak", p->von_mises}, {"time_of_peak", p->time}, {"stress_range", p->range}};
  fb_vtu_frame frame = {.cell_arrays = cells, .ncell_arrays = 3};
  fb_scenario_frame_offset(s, frame.origin);
  char *path = cli_outdir_path(od, CLI_STRESS_VTU, err);
  int rc = path ? fb_mesh_write_vtu_frame(fb_hull_stress_mesh(run->stress), &frame, path, err)
                : err->code;
  if (!rc)
    return cli_outdir_keep(od, path, err);
  free(path);
  return rc;
}

static int write_peaks_png(cli_outdir *od, const fb_scenario *s, const cli_run_system *run,
                           fb_err *err)
{
  const fb_hull_stress_peaks *p = run->peaks;
  double *mpa = malloc((p->nelements ? p->nelements : 1) * sizeof *mpa);
  if (!mpa)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t e = 0; e < p->nelements; ++e)
    mpa[e] = p->von_mises[e] / 1e6;
  char title[200], subtitle[200], road[160];
  fb_road_phrase(s->road_type, &s->road, road, sizeof road);
  snprintf(title, sizeof title, "%s %s: peak von Mises stress", cli_system_label(run->sys),
           road);
  snprintf(subtitle, sizeof subtitle,
           "per element, the larger surface's, over %zu samples from t = %.3f s", p->nsamples,
           run->stress_from);
  fb_plot_field pic = {.mesh = fb_hull_stress_mesh(run->stress),
                       .values = mpa,
                       .title = title,
                       .subtitle = subtitle,
                       .colour_label = "peak von Mises stress [MPa]"};
  fb_scenario_frame_offset(s, pic.origin);
  char *path = cli_outdir_path(od, CLI_STRESS_PNG, err);
  int rc = path ? fb_plot_field_png(&pic, path, err) : err->code;
  if (!rc)
    rc = cli_outdir_keep(od, path, err);
  else
    free(path);
  free(mpa);
  return rc;
}

int cli_write_stress_files(cli_outdir *od, const fb_scenario *s, const cli_run_system *run,
                           int figures, fb_err *err)
{
  const stress_csv csv = {s, run};
  int rc = cli_outdir_write(od, CLI_STRESS_CSV, write_peaks_csv, &csv, err);
  if (!rc)
    rc = write_peaks_vtu(od, s, run, err);
  if (!rc && figures)
    rc = write_peaks_png(od, s, run, err);
  return rc;
}

/* ---- report.md's hot spots. */

static void write_hot_spot_row(FILE *fp, const fb_scenario *s, const cli_run_system *run,
                               size_t e, int sections)
{
  const fb_hull_stress_peaks *p = run->peaks;
  const fb_mesh *m = fb_hull_stress_mesh(run->stress);
  double x[3];
  centroid(s, m, e, x);
  fprintf(fp, "| %ld | ", fb_mesh_element_id(m, e));
  if (sections) {
    fb_md_write_text(fp, section_of(m, e));
    fputs(" | ", fp);
  }
  /* A coordinate within round-off of 0 prints as 0.000, not -0.000. */
  for (int k = 0; k < 3; ++k)
    x[k] = fabs(x[k]) < 5e-4 ? 0.0 : x[k];
  fprintf(fp, "%.3f, %.3f, %.3f | %.4g | %.4f | %s | %.4g |\n", x[0], x[1], x[2],
          p->von_mises[e] / 1e6, p->time[e], fb_hull_surface_name(p->surface[e]),
          p->range[e] / 1e6);
}

void cli_write_stress_report(FILE *fp, const cli_run_outputs *o)
{
  const cli_run_system *run = NULL;
  for (size_t i = 0; i < o->nruns; ++i)
    if (o->runs[i].peaks)
      run = &o->runs[i];
  if (!run) {
    if (o->no_stress)
      fprintf(fp, "\nNo hull stresses: %s.\n", o->no_stress);
    return;
  }
  const fb_hull_stress_peaks *p = run->peaks;
  const fb_mesh *m = fb_hull_stress_mesh(run->stress);
  enum { HOT_SPOTS = 10 };
  size_t order[HOT_SPOTS];
  size_t n = HOT_SPOTS;
  if (p->nelements < n)
    n = p->nelements;
  fb_err err;
  if (fb_hull_stress_peaks_top(p, n, order, &err) != FB_OK)
    return;
  const int sections = fb_mesh_nsections(m) > 0;
  fprintf(fp,
          "\n## Hull stresses\n\nSystem 2's peak von Mises stress per element (at its centre, "
          "the larger of its two surfaces; the total stress, the weight's included) over the "
          "run's %zu output samples from t = %.3f s (the first wheel's entry into the road "
          "window) to the end: a peak between two samples is missed, a higher "
          "`simulation.sample_rate` samples closer (docs/stresses.md). The range, a fatigue "
          "input, is the largest over both surfaces and %d planes of the range of the "
          "normal stress on a plane. Stresses at element centres converge with the mesh more "
          "slowly than displacements and frequencies: compare a finer mesh "
          "(`hull.mesh.density`, or a refined deck) before trusting a hot spot's value. "
          "Every element's values are in `%s` and `%s` (ParaView). "
          "The %zu elements "
          "of highest peak:\n\n",
          p->nsamples, run->stress_from, FB_HULL_STRESS_PLANES, CLI_STRESS_CSV, CLI_STRESS_VTU,
          n);
  fprintf(fp,
          "| element | %scentroid x, y, z [m] | peak von Mises [MPa] | time [s] | "
          "surface | range [MPa] |\n|---|%s---|---|---|---|---|\n",
          sections ? "section | " : "", sections ? "---|" : "");
  for (size_t i = 0; i < n; ++i)
    write_hot_spot_row(fp, o->scenario, run, order[i], sections);
  if (o->figures)
    fprintf(fp, "\n![System 2: peak von Mises stress per element](%s)\n", CLI_STRESS_PNG);
}
