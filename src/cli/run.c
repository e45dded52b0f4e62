/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond run: the vehicle study of Leite & Da Silva ("Modeling and
 * simulation of armored wheeled vehicles with flexible hulls using modular
 * procedures"; data sheet docs/reference-vehicle.md). Loads a
 * scenario, computes the modes of the systems asked for, simulates each
 * system once, and only then writes, all or nothing: DIR/systemN.csv, one
 * PNG per paper figure (Figs. 8-14; both systems overlaid above their
 * difference), System 2's mode pictures, DIR/summary.json and
 * DIR/report.md (report.c; the files are described in docs/report.md). */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "flexbond/escape.h"
#include "flexbond/fem.h"
#include "flexbond/hull_source.h"
#include "flexbond/io.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "../core/util.h"
#include "cli.h"

/* The help text in two literals, each within the 4095 characters C11
 * compilers must support, joined in cli_cmd_run. */
static const char run_usage_files[] =
    "usage: flexbond run SCENARIO.yaml -o DIR [options]\n"
    "\n"
    "Simulates the vehicle of the scenario (docs/scenario-format.md) on its\n"
    "road, with the rigid hull (System 1) and the finite-element hull (System 2),\n"
    "and writes, once every run succeeded (docs/report.md):\n"
    "  DIR/system1.csv, DIR/system2.csv\n"
    "                          t and the scenario's outputs, one row per\n"
    "                          sample (header: 't [s],tire_force_LF [N],...'; SI)\n"
    "  DIR/system2_converged.csv\n"
    "                          with both systems and hull.mesh.converged_density:\n"
    "                          System 2 again on the hull refined to it\n"
    "  DIR/figNN_OUTPUT.png    the paper's Figs. 8-14, one output each: both\n"
    "                          systems overlaid, their difference below\n"
    "  DIR/mode_NN.png         System 2's modes by kind (docs/report.md)\n"
    "  DIR/bode_OUTPUT.png     each output's frequency response to the road, both\n"
    "                          tracks and systems (as flexbond freq draws it)\n"
    "  DIR/summary.json        static value, peak, minimum and RMS on the road\n"
    "                          of every output, solver statistics, System 2's\n"
    "                          hull basis and its estimated error, and System 2\n"
    "                          against System 1 per output\n"
    "  DIR/report.md           scenario, assumptions, modes, figures, comparison\n"
    "                          table and conclusions\n"
    "  DIR/animation_systemN.pvd, DIR/animation_systemN_FFFF.vtu, DIR/animation_systemN.gif\n"
    "                          with --animate: each system's motion in the road's\n"
    "                          window, a ParaView time series and an animated GIF\n"
    "                          (System 2's frames with the von Mises stress per element)\n"
    "  DIR/stress_peaks.csv    System 2: per hull element its peak von Mises stress\n"
    "                          over the samples from the road window's start, its\n"
    "                          time and surface, and a stress range (docs/stresses.md)\n"
    "  DIR/stress_peak.vtu, DIR/stress_peak.png\n"
    "                          the same for ParaView, and the hull coloured by it\n"
    "DIR is created if missing; nothing is written if a run fails.\n"
    "\n";
static const char run_usage_options[] =
    "options (override the scenario):\n"
    "  -o, --output DIR            output directory (required)\n"
    "  --system rigid|flexible|both  hull model (default both; System 1 alone if\n"
    "                              the scenario has no finite-element hull, System 2\n"
    "                              alone if its outputs include hull stresses)\n"
    "  --initial zero|static       all states zero with gravity switched on at\n"
    "                              t = 0 (the paper), or static equilibrium\n"
    "  --payload weight-only|lumped  payload as force only (the paper), or\n"
    "                              as mass spread over the load points too\n"
    "  --hull-coordinates modal|nodal  System 2's hull states: its free-free modes\n"
    "                              or its nodal displacements (hull.fe.coordinates)\n"
    "  --hull-modes auto|all|N     System 2's hull in modal coordinates\n"
    "                              (hull.fe.modes): auto the rigid-body modes and\n"
    "                              load-dependent Ritz vectors, as many blocks as\n"
    "                              the excitation's band needs; all every mode (a\n"
    "                              dense eigen-solve); N the N lowest (N >= 6) with\n"
    "                              a static correction\n"
    "  --hull-cutoff HZ            with auto: the band's top, in place of the\n"
    "                              highest frequency reaching the hull\n"
    "                              (hull.fe.cutoff_hz)\n"
    "  --animate                   also the animation files (docs/animation.md)\n"
    "  --animate-fps HZ            its frames per second of the run's time, 1 to\n"
    "                              1000 (default 50; the GIF plays in real time\n"
    "                              up to 100, its delays being hundredths of a s)\n"
    "  --animate-scale F           draw the displacements F times (default: the\n"
    "                              largest 8 % of the hull's length)\n"
    "  --no-figures                no PNG or GIF; report.md with no images\n"
    "  --no-stress                 no hull stresses (System 2's stress files and the\n"
    "                              report's hot spots; by default they are written)\n"
    "  --picture-modes LIST        picture these modes (\"1,3,7\")\n"
    "  --plain-header              CSV headers of names only ('t,tire_force_LF,...',\n"
    "                              the paper's), without the units\n"
    "  -v, --verbose               also each hull's basis and eigen-solve, and what\n"
    "                              each vehicle computed (assemblies, factorisations,\n"
    "                              eigen-solves, simulations), on stderr\n"
    "  -q, --quiet                 no progress or summary lines on stderr\n"
    "  --strict                    refuse implausible values instead of warning\n"
    "  -h, --help                  this text\n";

/* Values of --system and the systems each asks for. */
enum { SYSTEM_RIGID, SYSTEM_FLEXIBLE, SYSTEM_BOTH };
static const char *const system_choices[] = {
    [SYSTEM_RIGID] = "rigid", [SYSTEM_FLEXIBLE] = "flexible", [SYSTEM_BOTH] = "both"};
static const struct {
  fb_system systems[CLI_MAX_SYSTEMS];
  size_t nsystems;
} system_sets[] = {[SYSTEM_RIGID] = {{FB_SYSTEM_RIGID}, 1},
                   [SYSTEM_FLEXIBLE] = {{FB_SYSTEM_FLEXIBLE}, 1},
                   [SYSTEM_BOTH] = {{FB_SYSTEM_RIGID, FB_SYSTEM_FLEXIBLE}, 2}};

/* Values of --initial, --payload and --hull-coordinates, indexed by the
 * enums' values. */
static const char *const initial_choices[] = {
    [FB_INITIAL_ZERO] = "zero", [FB_INITIAL_STATIC] = "static"};
static const char *const payload_choices[] = {
    [FB_PAYLOAD_WEIGHT_ONLY] = "weight-only", [FB_PAYLOAD_LUMPED] = "lumped"};
static const char *const coordinate_choices[] = {
    [FB_HULL_NODAL] = "nodal", [FB_HULL_MODAL] = "modal"};

/* The scenario's range of hull.fe.modes. */
enum { MAX_HULL_MODES = 100000 };
/* Modes computed for the report: the whole System 2's (as modes
 * --system flexible prints) and the free-free hull's, enough to pass its
 * six rigid-body modes. */
enum { VEHICLE_MODES = 20, HULL_FREE_MODES = 12 };

/* Command-line settings; an override is -1 when not given. */
typedef struct run_args {
  const char *scenario_path;
  const char *out_dir;
  int system;           /* index in system_choices */
  int initial;          /* fb_initial_state */
  int payload;          /* fb_payload_model */
  int hull_coordinates; /* s->hull_coordinates */
  int hull_modes_kind;  /* s->hull_modes_kind, -1 when --hull-modes is not given */
  int hull_modes;       /* s->hull_modes */
  double hull_cutoff;   /* s->hull_cutoff_hz, 0 when --hull-cutoff is not given */
  int quiet;
  int strict;           /* --strict: an implausible value is an error */
  int verbose;          /* the costs of eigen-solves and set-up too (-v) */
  int progress;         /* draw a progress line: stderr is a terminal, no -q */
  int figures;          /* 0 with --no-figures */
  int stress;           /* 0 with --no-stress: no hull stresses */
  fb_csv_header header; /* of systemN.csv: units, or names with --plain-header */
  cli_animate_opts animate;
  cli_mode_list pictured; /* --picture-modes */
} run_args;

/* ---- Figures. */

/* "Fig. 8. Normal reaction ...: System 1 (rigid hull)" (and " vs System 2
 * (flexible hull)" when overlaid) into buf. */
static void figure_title(const fb_output_spec *fig, const cli_run_outputs *o, char *buf,
                         size_t size)
{
  int n = fig->figure > 0
              ? snprintf(buf, size, "Fig. %d. %s: %s", fig->figure, fig->title,
                         cli_system_label(o->runs[0].sys))
              : snprintf(buf, size, "%s: %s", fig->title, cli_system_label(o->runs[0].sys));
  for (size_t i = 1; i < o->nruns && n > 0 && (size_t)n < size; ++i)
    n += snprintf(buf + n, size - (size_t)n, " vs %s", cli_system_label(o->runs[i].sys));
}

/* DIR/figNN_OUTPUT.png of output k: a panel with a curve per system and,
 * when both ran, a second panel with their difference; with the converged
 * mesh's run, its curve and its difference too. */
static int write_figure(cli_outdir *od, size_t k, const cli_run_outputs *o, fb_err *err)
{
  const fb_output_spec *fig = &o->scenario->output[k];
  fb_plot_series series[CLI_MAX_SYSTEMS + 1];
  size_t nseries = 0;
  for (size_t i = 0; i < o->nruns; ++i, ++nseries)
    /* A single curve needs no key: the title names its system. */
    series[i] =
        (fb_plot_series){.result = o->runs[i].res,
                         .col = fb_run_summary_column(o->runs[i].sum, k) - 1,
                         .legend = o->nruns > 1 ? cli_system_label(o->runs[i].sys) : NULL};
  char paper[48] = "";
  if (o->converged) {
    series[nseries++] = (fb_plot_series){.result = o->converged->res,
                                         .col = fb_run_summary_column(o->converged->sum, k) - 1,
                                         .legend = o->converged->label};
    snprintf(paper, sizeof paper, "System 2 at density %d",
             fb_scenario_hull_density(o->scenario));
  }
  /* fb_result_diff keeps System 1's columns. */
  const fb_plot_series diff[2] = {{.result = o->diff,
                                   .col = fb_run_summary_column(o->runs[0].sum, k) - 1,
                                   .legend = o->converged ? paper : NULL},
                                  {.result = o->diff_converged,
                                   .col = fb_run_summary_column(o->runs[0].sum, k) - 1,
                                   .legend = o->converged ? o->converged->label : NULL}};
  const char *unit =
      fb_result_col_unit(o->runs[0].res, fb_run_summary_column(o->runs[0].sum, k));
  char title[512], name[FB_ERR_KEY_MAX];
  figure_title(fig, o, title, sizeof title);
  cli_run_figure_file(fig, name, sizeof name);
  fb_plot_opts opts;
  fb_plot_opts_default(&opts);
  opts.title = title;
  opts.panel_height = o->diff ? 320 : 460;
  cli_run_figure_window(fig, o->runs[0].res, &opts.t_min, &opts.t_max);
  /* The difference over the bump: before it, the settling from the zero
   * start (the systems' static deflections differ) would set the scale
   * and flatten the bump's differences, which the comparison is about. */
  double bump[2];
  fb_study_response_window(o->scenario, bump);
  const fb_plot_panel panels[2] = {
      {.series = series, .nseries = nseries, .ylabel = fig->label, .unit = unit},
      {.series = diff,
       .nseries = o->diff_converged ? 2 : 1,
       .ylabel = "System 2 - System 1",
       .unit = unit,
       .focus_t0 = bump[0],
       .focus_t1 = INFINITY,
       .outside_label = o->scenario->initial == FB_INITIAL_ZERO ? "settling from the zero start"
                                                                : "before the road window"}};
  char *path = cli_outdir_path(od, name, err);
  if (!path)
    return err->code; /* out of memory, or no staging directory */
  int rc = fb_plot_panels_png(panels, o->diff ? 2 : 1, &opts, path, err);
  if (rc == FB_OK)
    return cli_outdir_keep(od, path, err);
  free(path);
  return rc;
}

/* ---- summary.json, written by hand: strings by cli_json_string,
 * numbers by fb_json_write_number (flexbond/escape.h: %.10g, null for a
 * non-finite number, which JSON cannot represent). The keys are this
 * file's own constants. */

/* A JSON object's numeric members. */
typedef struct json_field {
  const char *key;
  double value;
} json_field;

/* {"unit": unit, key: value, ...} */
static void json_object(FILE *fp, const char *unit, const json_field *fields, size_t nfields)
{
  fputs("{\"unit\": ", fp);
  cli_json_string(fp, unit);
  for (size_t i = 0; i < nfields; ++i) {
    fprintf(fp, ", \"%s\": ", fields[i].key);
    fb_json_write_number(fp, fields[i].value);
  }
  fputc('}', fp);
}

static void write_output_json(FILE *fp, const char *unit, const fb_output_stats *o)
{
  const json_field fields[] = {
      {"static", o->static_value}, {"peak", o->peak},        {"min", o->min}, {"rms", o->rms},
      {"peak_time", o->peak_time}, {"min_time", o->min_time}};
  json_object(fp, unit, fields, sizeof fields / sizeof fields[0]);
}

static void write_solver_json(FILE *fp, const fb_sim_stats *s)
{
  fprintf(fp,
          "{\"steps\": %ld, \"rhs_evals\": %ld, \"newton_setups\": %ld, "
          "\"factorizations\": %ld, \"newton_iters\": %ld, \"err_test_fails\": %ld, "
          "\"events\": %ld, \"wall_seconds\": ",
          s->steps, s->rhs_evals, s->newton_setups, s->factorizations, s->newton_iters,
          s->err_test_fails, s->events);
  fb_json_write_number(fp, s->wall_seconds);
  fputc('}', fp);
}

/* "systemN": {...} of one run. */
/* {"window": [t0, t1], "a_w_rms", ..., "crest_over_9"} or {"note": why}. */
static void write_ride_json(FILE *fp, const cli_run_system *run, const fb_scenario *s)
{
  fb_ride_metrics ride;
  double window[2];
  const char *note = NULL;
  if (!fb_run_summary_ride(run->sum, &ride, window, &note)) {
    fputs("{\"note\": ", fp);
    cli_json_string(fp, note);
    fputc('}', fp);
    return;
  }
  const fb_ride_metrics *m = &ride;
  const json_field fields[] = {{"a_w_rms", m->a_w_rms},
                               {"mtvv", m->mtvv},
                               {"vdv", m->vdv},
                               {"crest_factor", m->crest},
                               {"absorbed_power", m->absorbed_power},
                               {"jerk_peak", m->jerk_peak},
                               {"jerk_rms", m->jerk_rms},
                               {"nrmm_peak", m->nrmm_peak},
                               {"se", m->se},
                               {"dz", m->dz},
                               {"vdv_ratio", m->vdv_ratio},
                               {"crest_over_9", m->crest_over_9}};
  fputs("{\"output\": ", fp);
  cli_json_string(fp, s->output[fb_study_ride_output(s)].name);
  fputs(", \"window\": [", fp);
  fb_json_write_number(fp, window[0]);
  fputs(", ", fp);
  fb_json_write_number(fp, window[1]);
  fputc(']', fp);
  for (size_t f = 0; f < sizeof fields / sizeof fields[0]; ++f) {
    fprintf(fp, ", \"%s\": ", fields[f].key);
    fb_json_write_number(fp, fields[f].value);
  }
  fputc('}', fp);
}

/* {"model", "models": {tire: model, ...}, "min_force": {tire: {"value", "time"}, ...},
 * "contact_loss_intervals": [{"tire", "from", "to", "min_force", "at"},
 * ...]}. */
static void write_contact_json(FILE *fp, const cli_run_system *run, const fb_study_report *rep)
{
  const fb_scenario *s = fb_study_report_scenario(rep);
  /* One model for every tire, or "mixed" and each corner's in "models". */
  const int mixed =
      fb_study_report_tires_with(rep, fb_corner_tire_model(&s->corner[0])) != s->ncorners;
  fprintf(fp, "{\"model\": \"%s\", \"models\": {",
          mixed ? "mixed" : fb_corner_tire_model(&s->corner[0])->name);
  for (size_t c = 0; c < s->ncorners; ++c) {
    fputs(c ? ", " : "", fp);
    cli_json_string(fp, s->corner[c].name);
    fprintf(fp, ": \"%s\"", fb_corner_tire_model(&s->corner[c])->name);
  }
  fputs("}, \"min_force\": {", fp);
  for (size_t c = 0; c < s->ncorners; ++c) {
    fputs(c ? ", " : "", fp);
    cli_json_string(fp, s->corner[c].name);
    fputs(": {\"value\": ", fp);
    fb_json_write_number(fp, fb_run_summary_contact(run->sum, c)->min);
    fputs(", \"time\": ", fp);
    fb_json_write_number(fp, fb_run_summary_contact(run->sum, c)->min_time);
    fputc('}', fp);
  }
  fputs("}, \"peak_force\": {", fp);
  for (size_t c = 0; c < s->ncorners; ++c) {
    const json_field fields[] = {{"value", fb_run_summary_contact(run->sum, c)->peak},
                                 {"time", fb_run_summary_contact(run->sum, c)->peak_time},
                                 {"static", fb_run_summary_contact(run->sum, c)->static_value},
                                 {"ratio", fb_run_summary_contact_ratio(run->sum, c)}};
    fputs(c ? ", " : "", fp);
    cli_json_string(fp, s->corner[c].name);
    fputs(": ", fp);
    json_object(fp, "N", fields, sizeof fields / sizeof fields[0]);
  }
  fputs("}, \"spike_ratio_limit\": ", fp);
  fb_json_write_number(fp, FB_CONTACT_SPIKE_RATIO);
  fputs(", \"spikes\": [", fp);
  for (size_t c = 0, n = 0; c < s->ncorners; ++c)
    if (fb_run_summary_contact_spike(run->sum, c)) {
      fputs(n++ ? ", " : "", fp);
      cli_json_string(fp, s->corner[c].name);
    }
  fputs("], \"contact_loss_intervals\": [", fp);
  for (size_t i = 0; i < fb_run_summary_nlosses(run->sum); ++i) {
    const fb_contact_loss *t = fb_run_summary_loss(run->sum, i);
    const json_field fields[] = {
        {"from", t->t_start}, {"to", t->t_end}, {"min_force", t->min_force}, {"at", t->t_min}};
    fputs(i ? ", {\"tire\": " : "{\"tire\": ", fp);
    cli_json_string(fp, s->corner[t->corner].name);
    for (size_t f = 0; f < sizeof fields / sizeof fields[0]; ++f) {
      fprintf(fp, ", \"%s\": ", fields[f].key);
      fb_json_write_number(fp, fields[f].value);
    }
    fputc('}', fp);
  }
  fputs("]}", fp);
}

/* hull.fe.modes as the file writes it: "auto", "all" or the count N, and
 * null for nodal coordinates, which have no modes to choose. */
static void write_hull_modes_json(FILE *fp, const fb_scenario *s, const fb_hull_basis *b)
{
  if (b->coordinates != FB_HULL_MODAL)
    fputs("null", fp);
  else if (s->hull_modes_kind == FB_HULL_MODES_COUNT)
    fprintf(fp, "%d", s->hull_modes);
  else
    fputs(s->hull_modes_kind == FB_HULL_MODES_ALL ? "\"all\"" : "\"auto\"", fp);
}

/* "hull_basis": System 2's hull model and the estimated error of each
 * output from its basis (null where not estimated). */
static void write_basis_json(FILE *fp, const fb_scenario *s, const fb_hull_basis *b,
                             const cli_run_system *run, const double window[2])
{
  fprintf(fp, ",\n    \"hull_basis\": {\"coordinates\": \"%s\", \"modes\": ",
          coordinate_choices[b->coordinates]);
  write_hull_modes_json(fp, s, b);
  const json_field fields[] = {{"dofs", (double)b->ndof},
                               {"coordinates_count", (double)b->ncoords},
                               {"kept_modes", (double)b->nmodes},
                               {"rigid_modes", (double)b->nrigid},
                               {"static_vectors", (double)b->nstatic},
                               {"static_patterns", (double)b->npatterns},
                               {"ritz_blocks", (double)b->nblocks},
                               {"block_change", b->block_change},
                               {"cutoff_hz", b->cutoff_hz},
                               {"excitation_hz", b->excitation_hz},
                               {"first_elastic_hz", b->f1_hz},
                               {"beta", b->beta},
                               {"eigen_seconds", b->eig.seconds}};
  for (size_t f = 0; f < sizeof fields / sizeof fields[0]; ++f) {
    fprintf(fp, ", \"%s\": ", fields[f].key);
    fb_json_write_number(fp, fields[f].value);
  }
  fprintf(fp, ", \"eigen_solver\": \"%s\", \"estimated_error\": ",
          b->eig.method == FB_EIG_DENSE ? "dense LAPACK" : "block Lanczos");
  if (!run->basis_error) {
    fputs("null}", fp);
    return;
  }
  fputs("{\"window\": [", fp);
  fb_json_write_number(fp, window[0]);
  fputs(", ", fp);
  fb_json_write_number(fp, fb_result_row(run->res, fb_result_nsamples(run->res) - 1)[0]);
  fputs("], \"of_range\": {", fp);
  for (size_t k = 0; k < s->noutputs; ++k) {
    fputs(k ? ", " : "", fp);
    cli_json_string(fp, s->output[k].name);
    fputs(": ", fp);
    fb_json_write_number(fp, run->basis_error[k]);
  }
  fputs("}}}", fp);
}

/* "key": one system's run, with System 2's hull basis b (NULL for System
 * 1) and, at the converged mesh, its density. */
static void write_system_json(FILE *fp, const cli_run_outputs *o, const char *key,
                              const cli_run_system *run, const fb_hull_basis *b, int density)
{
  const fb_scenario *s = o->scenario;
  const double *window = o->bump_window;
  fprintf(fp, ",\n  \"%s\": {\n    \"label\": ", key);
  cli_json_string(fp, run->label ? run->label : cli_system_label(run->sys));
  if (density > 0)
    fprintf(fp, ",\n    \"mesh_density\": %d", density);
  if (b)
    write_basis_json(fp, s, b, run, window);
  fputs(",\n    \"outputs\": {", fp);
  for (size_t k = 0; k < s->noutputs; ++k) {
    fputs(k ? ",\n      " : "\n      ", fp);
    cli_json_string(fp, s->output[k].name);
    fputs(": ", fp);
    write_output_json(fp, fb_result_col_unit(run->res, fb_run_summary_column(run->sum, k)),
                      fb_run_summary_output(run->sum, k));
  }
  fputs("\n    },\n    \"ride\": ", fp);
  write_ride_json(fp, run, s);
  fputs(",\n    \"tire_contact\": ", fp);
  write_contact_json(fp, run, o->report);
  fputs(",\n    \"solver\": ", fp);
  write_solver_json(fp, fb_result_stats(run->res));
  fputs(",\n    \"bump_window\": [", fp);
  fb_json_write_number(fp, window[0]);
  fputs(", ", fp);
  fb_json_write_number(fp, window[1]);
  fputs("]\n  }", fp);
}

/* "key": {output: {...}, ...} of System 2's run2 (cmp) against System 1. */
static void write_comparison_json(FILE *fp, const cli_run_outputs *o, const char *key,
                                  const cli_run_system *run2, const fb_output_cmp *cmp)
{
  fprintf(fp, ",\n  \"%s\": {", key);
  for (size_t k = 0; k < o->scenario->noutputs; ++k) {
    const fb_output_stats *s1 = fb_run_summary_output(o->runs[0].sum, k),
                          *s2 = fb_run_summary_output(run2->sum, k);
    const fb_output_cmp *c = &cmp[k];
    const json_field fields[] = {{"peak_system1", s1->peak},
                                 {"peak_system2", s2->peak},
                                 {"rms_system1", s1->rms},
                                 {"rms_system2", s2->rms},
                                 {"max_abs_diff", c->max_diff},
                                 {"max_abs_diff_time", c->max_diff_time},
                                 {"range_system1", c->range1},
                                 {"max_abs_diff_rel", c->rel_diff},
                                 {"peak_change_rel", c->peak_change},
                                 {"rms_change_rel", c->rms_change}};
    fputs(k ? ",\n    " : "\n    ", fp);
    cli_json_string(fp, o->scenario->output[k].name);
    fputs(": ", fp);
    json_object(fp,
                fb_result_col_unit(o->runs[0].res, fb_run_summary_column(o->runs[0].sum, k)),
                fields, sizeof fields / sizeof fields[0]);
  }
  fputs("\n  }", fp);
}

static const char *const definitions[][2] = {
    {"static", "value at the last sample before bump_window[0] (the first wheel enters the "
               "road window); null if the run starts in it"},
    {"peak", "largest value from bump_window[0] to the end of the run: the response to the "
             "road, without the settling after t = 0"},
    {"peak_time", "time of peak (its first occurrence), s"},
    {"min", "smallest value from bump_window[0] to the end of the run"},
    {"min_time", "time of min (its first occurrence), s"},
    {"rms", "root mean square of the samples with t in bump_window (of the value itself, "
            "not of its deviation from static)"},
    {"bump_window", "the road window (a bump road's: its bump), [first wheel's entry, last "
                    "wheel's exit], s"},
    {"solver", "CVODE statistics of the run; events: restarts at contact changes "
               "(unilateral tires); wall_seconds is the integration's wall time"},
    {"ride",
     "ride metrics (docs/ride-metrics.md) of output, the first mounted body's acceleration "
     "among the scenario's outputs (the driver's in the paper's), over window = [first "
     "wheel's entry into the road window, end of the run] s: a_w_rms (ISO 2631-1 Wk-weighted "
     "r.m.s., m/s^2), mtvv "
     "(largest 1 s running r.m.s., m/s^2), vdv (m/s^1.75), crest_factor (max |a_w| / "
     "a_w_rms), absorbed_power (Pradko & Lee, W, against 6 W), jerk_peak and jerk_rms "
     "(of the unweighted acceleration, m/s^3), nrmm_peak (largest |a| low-passed at 30 Hz, "
     "m/s^2, against 2.5 g), dz and se (ISO 2631-5 vertical acceleration dose, m/s^2, and "
     "S_ed, MPa, the window as the day's exposure), vdv_ratio (vdv / 8.5, the ISO 2631-1 "
     "health guidance caution zone's lower bound) and crest_over_9 (1 when crest_factor > "
     "9); a note instead when they cannot be computed"},
    {"tire_contact",
     "model: bilateral (the paper's linear tire), unilateral (no tension: the wheel may "
     "leave the road), hunt_crossley (unilateral, damping growing with the deflection) or "
     "table (unilateral, its force a force-deflection table), "
     "or mixed when the corners differ; models: each tire's; "
     "min_force: each tire's smallest normal reaction from bump_window[0] "
     "to the end of the run (N, compression positive) and its time; contact_loss_intervals: "
     "every interval of the whole run where a reaction is not compressive (bilateral: "
     "tensile, the tire pulls the wheel down; unilateral: zero, the wheel is off the road): "
     "from, to (s, zero crossings interpolated between samples), min_force (N) at (s)"},
    {"hull_basis",
     "System 2's hull model: coordinates modal (its free-free modes) or nodal (its nodal "
     "displacements); modes as hull.fe.modes (\"auto\": the rigid-body modes and "
     "ritz_blocks blocks of load-dependent Ritz vectors, added until the next changed the "
     "receptances by block_change < 1e-3 of their scale over 0 to cutoff_hz, excitation_hz "
     "when the rule set it, the highest frequency reaching the hull; \"all\"; or a count; "
     "null with nodal coordinates); dofs the hull's nodal DOFs, coordinates_count its "
     "coordinates in the model, kept_modes (rigid_modes of them rigid-body) plus "
     "static_vectors more (auto: the Ritz vectors; a count: the residual flexibility) from "
     "static_patterns patterns (each attachment point, the load, each hull output); "
     "first_elastic_hz and beta its damping B = beta K; estimated_error: each output's "
     "largest difference from the same run with the basis's next block of Ritz vectors, "
     "over its range, from window[0] to window[1] s (null: not estimated, a full or nodal "
     "model)"},
    {"comparison", "System 2 against System 1 per output (when both ran): peak_systemN and "
                   "rms_systemN are each system's peak and rms; max_abs_diff is the largest "
                   "|System 2 - System 1| from bump_window[0] to the end of the run, at "
                   "max_abs_diff_time (first occurrence); range_system1 = System 1's peak - "
                   "min; max_abs_diff_rel = max_abs_diff / range_system1, peak_change_rel = "
                   "(peak_system2 - peak_system1) / |peak_system1|, rms_change_rel = "
                   "(rms_system2 - rms_system1) / rms_system1, as fractions, null when the "
                   "denominator is 0"},
    {"system2_converged",
     "System 2 again, on the hull refined to hull.mesh.converged_density (mesh_density; "
     "when the scenario gives it above hull.mesh.density and both systems ran): the same "
     "members as system2"},
    {"comparison_converged",
     "system2_converged against System 1, with the members of comparison (peak_system2 and "
     "rms_system2 are the converged run's)"},
    {"units", "SI, as the \"unit\" of each output; null stands for a non-finite value"},
};

/* summary.json (a cli_writer over a cli_run_outputs). */
static void write_summary_json(FILE *fp, const void *ctx)
{
  const cli_run_outputs *o = ctx;
  const fb_scenario *s = o->scenario;
  fputs("{\n  \"scenario\": ", fp);
  cli_json_string(fp, cli_scenario_name(s));
  fputs(",\n  \"initial\": ", fp);
  cli_json_string(fp, initial_choices[s->initial]);
  fputs(",\n  \"payload\": ", fp);
  cli_json_string(fp, payload_choices[s->payload]);
  fputs(",\n  \"definitions\": {", fp);
  for (size_t i = 0; i < sizeof definitions / sizeof definitions[0]; ++i) {
    fputs(i ? ",\n    " : "\n    ", fp);
    cli_json_string(fp, definitions[i][0]);
    fputs(": ", fp);
    cli_json_string(fp, definitions[i][1]);
  }
  fputs("\n  }", fp);
  for (size_t i = 0; i < o->nruns; ++i) {
    const cli_run_system *r = &o->runs[i];
    char key[16];
    snprintf(key, sizeof key, "system%d", (int)r->sys);
    write_system_json(fp, o, key, r, r->sys == FB_SYSTEM_FLEXIBLE ? o->basis : NULL, 0);
  }
  if (o->converged)
    write_system_json(fp, o, "system2_converged", o->converged, o->converged_basis,
                      o->converged_density);
  if (o->diff)
    write_comparison_json(fp, o, "comparison", &o->runs[1], o->cmp);
  if (o->cmp_converged)
    write_comparison_json(fp, o, "comparison_converged", o->converged, o->cmp_converged);
  fputs("\n}\n", fp);
}

/* One system's CSV: its run and how many outputs it has. */
typedef struct system_csv {
  const cli_run_system *run;
  size_t noutputs;
  fb_csv_header header;
} system_csv;

/* systemN.csv (a cli_writer over a system_csv). */
static void write_system_csv(FILE *fp, const void *ctx)
{
  const system_csv *c = ctx;
  /* The scenario's outputs; the contact forces go to the summary. */
  fb_result_print_csv_columns(fp, c->run->res, 1 + c->noutputs, c->header);
}

/* Both diagrams of vehicle v, drawn from the graph it ran. */
static int write_diagrams(cli_outdir *od, const fb_scenario *s, fb_vehicle *v, fb_err *err)
{
  const fb_system sys = fb_vehicle_system(v);
  fb_bg *g = fb_vehicle_bond_graph(v);
  size_t np = 0;
  const fb_probe_spec *p = fb_vehicle_probe_specs(v, &np);
  int rc = FB_OK;
  for (size_t k = 0; rc == FB_OK && k < CLI_RUN_NDIAGRAMS; ++k) {
    char name[64];
    cli_run_diagram_file(k, sys, name, sizeof name);
    char *path = cli_outdir_path(od, name, err);
    /* The outputs' meters; the tire-contact probes would only crowd it. */
    rc = path ? cli_diagram_file(g, p, s->noutputs, cli_run_diagram_kind(k), path, err)
              : err->code;
    if (rc == FB_OK)
      rc = cli_outdir_keep(od, path, err);
    else
      free(path);
  }
  return rc;
}

/* Stages every file in od; *nfiles is how many. The pictures go first:
 * they are the likeliest to fail (gnuplot); report.md, which links the
 * others, goes last. */
/* The pictures as jobs (cli_jobs_run), the longest first so that the two
 * threads finish together: each system's diagrams (two dot runs), the
 * Bode figures, the mode pictures, then one figure per output. */
typedef struct figure_job {
  const cli_run_outputs *o;
  size_t index; /* the output, or the run */
} figure_job;

static int diagrams_job(cli_outdir *od, const void *ctx, fb_err *err)
{
  const figure_job *j = ctx;
  return write_diagrams(od, j->o->scenario, j->o->vehicles[j->index], err);
}

static int bode_job(cli_outdir *od, const void *ctx, fb_err *err)
{
  return cli_bode_write_figures(od, ((const figure_job *)ctx)->o->freq, err);
}

static int mode_pictures_job(cli_outdir *od, const void *ctx, fb_err *err)
{
  const cli_run_outputs *o = ((const figure_job *)ctx)->o;
  return cli_write_mode_pictures(od, o->scenario, o->hull, o->modes2, err);
}

static int figure_job_run(cli_outdir *od, const void *ctx, fb_err *err)
{
  const figure_job *j = ctx;
  return write_figure(od, j->index, j->o, err);
}

static int write_pictures(cli_outdir *od, const cli_run_outputs *o, fb_err *err)
{
  const size_t most = CLI_MAX_SYSTEMS + 2 + o->scenario->noutputs;
  cli_job *jobs = malloc(most * sizeof *jobs);
  figure_job *ctx = malloc(most * sizeof *ctx);
  if (!jobs || !ctx) {
    free(jobs);
    free(ctx);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  size_t n = 0;
  for (size_t i = 0; i < o->nruns; ++i, ++n) {
    ctx[n] = (figure_job){o, i};
    jobs[n] = (cli_job){diagrams_job, &ctx[n]};
  }
  if (o->freq[0] || o->freq[1]) {
    ctx[n] = (figure_job){o, 0};
    jobs[n] = (cli_job){bode_job, &ctx[n]};
    ++n;
  }
  if (o->modes2) {
    ctx[n] = (figure_job){o, 0};
    jobs[n] = (cli_job){mode_pictures_job, &ctx[n]};
    ++n;
  }
  for (size_t k = 0; k < o->scenario->noutputs; ++k, ++n) {
    ctx[n] = (figure_job){o, k};
    jobs[n] = (cli_job){figure_job_run, &ctx[n]};
  }
  const int rc = cli_jobs_run(od, jobs, n, err);
  free(jobs);
  free(ctx);
  return rc;
}

static int write_outputs(cli_outdir *od, const cli_run_outputs *o, size_t *nfiles, fb_err *err)
{
  int rc = o->figures ? write_pictures(od, o, err) : FB_OK;
  for (size_t i = 0; i < o->nruns && rc == FB_OK; ++i) {
    char name[32];
    snprintf(name, sizeof name, "system%d.csv", (int)o->runs[i].sys);
    const system_csv csv = {&o->runs[i], o->scenario->noutputs, o->header};
    rc = cli_outdir_write(od, name, write_system_csv, &csv, err);
  }
  for (size_t i = 0; i < o->nruns && rc == FB_OK; ++i)
    if (o->runs[i].peaks)
      rc = cli_write_stress_files(od, o->scenario, &o->runs[i], o->figures, err);
  if (rc == FB_OK && o->converged) {
    const system_csv csv = {o->converged, o->scenario->noutputs, o->header};
    rc = cli_outdir_write(od, "system2_converged.csv", write_system_csv, &csv, err);
  }
  if (rc == FB_OK)
    rc = cli_outdir_write(od, "summary.json", write_summary_json, o, err);
  if (rc == FB_OK)
    rc = cli_outdir_write(od, "report.md", cli_write_report_md, o, err);
  *nfiles = od->nfiles;
  return rc;
}

/* ---- The vehicles, realised once each. */

/* One system's realised vehicle and what names its set-up's stages. */
typedef struct run_vehicle {
  fb_vehicle *v;
  cli_stage stage;
  char subject[FB_ERR_KEY_MAX];
} run_vehicle;

/* The vehicle of system sys, called label in messages (rv at its final
 * place: its stage is borrowed by the vehicle), probing the motion too
 * when motion (--animate). */
static int realise(const run_args *a, const fb_scenario *s, fb_system sys, const char *label,
                   int motion, run_vehicle *rv, fb_err *err)
{
  snprintf(rv->subject, sizeof rv->subject, "%s: %s", cli_scenario_name(s), label);
  rv->stage = (cli_stage){"run", rv->subject, a->quiet};
  fb_vehicle_opts o;
  fb_vehicle_opts_default(&o);
  /* The hull stresses need the hull's coordinates alone, which leave the
   * run's results as they are. */
  o.motion = motion                                   ? FB_VEHICLE_MOTION_ALL
             : a->stress && sys == FB_SYSTEM_FLEXIBLE ? FB_VEHICLE_MOTION_HULL
                                                      : FB_VEHICLE_MOTION_NONE;
  o.progress = (fb_progress){cli_stage_progress, &rv->stage};
  o.threads = cli_threads();
  return fb_vehicle_new(s, sys, &o, &rv->v, err);
}

/* The modes of the systems that run, for the report (owned). */
typedef struct run_modes {
  fb_mode *modes1;
  size_t nmodes1, nstatic1;
  fb_mode_set *modes2;
} run_modes;

/* System 1's undamped modes of its linearisation; System 2's whole
 * undamped vehicle's, with their shapes for the pictures. */
static int compute_modes(run_vehicle *vehicles, size_t n, run_modes *m, fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; i < n && rc == FB_OK; ++i)
    rc = fb_vehicle_system(vehicles[i].v) == FB_SYSTEM_RIGID
             ? fb_vehicle_linear_modes(vehicles[i].v, 1, &m->modes1, &m->nmodes1, &m->nstatic1,
                                       err)
             : fb_vehicle_structural_modes(vehicles[i].v, VEHICLE_MODES, 0, &m->modes2, err);
  return rc;
}

static void run_modes_free(run_modes *m)
{
  free(m->modes1);
  fb_mode_set_free(&m->modes2);
}

/* With -v: what realising and using the vehicle cost, counted where the
 * work was done (fb_vehicle_work). */
static void say_counts(const run_args *a, const run_vehicle *rv)
{
  if (!a->verbose)
    return;
  const fb_vehicle_work w = fb_vehicle_work_of(rv->v);
  cli_say("flexbond run: %s: work: set-up %.3g s, mesh generations %zu, hull assemblies %zu, "
          "factorisations %zu, hull eigen-solves %zu, vehicle eigen-solves %zu, linear "
          "eigen-solves %zu, block diagrams %zu, static equilibria %zu (%.3g s), simulations "
          "%zu",
          rv->subject, w.setup_seconds, w.mesh_generations, w.assemblies, w.factorisations,
          w.hull_eigensolves, w.vehicle_eigensolves, w.linear_eigensolves, w.diagrams,
          w.static_solves, w.static_seconds, w.simulations);
}

/* With -v: how the hull is represented, then say_counts. */
static void say_work(const run_args *a, const run_vehicle *rv)
{
  if (!a->verbose)
    return;
  const fb_hull_basis *b = fb_vehicle_hull_basis(rv->v);
  if (b && b->coordinates == FB_HULL_NODAL)
    cli_say_more("flexbond run: %s: hull of %zu DOFs in nodal coordinates; ", rv->subject,
                 b->ndof);
  else if (b && b->kind == FB_HULL_MODES_AUTO)
    cli_say_more(
        "flexbond run: %s: hull of %zu DOFs in %zu coordinates: %zu rigid-body modes and "
        "%zu load-dependent Ritz vectors in %zu blocks (the next changes the receptances "
        "by %.2g over 0 to %.4g Hz); ",
        rv->subject, b->ndof, b->ncoords, b->nrigid, b->nstatic, b->nblocks, b->block_change,
        b->cutoff_hz);
  else if (b)
    cli_say_more(
        "flexbond run: %s: hull of %zu DOFs in %zu coordinates: %zu free-free modes kept "
        "(%zu rigid), %zu static correction vectors; ",
        rv->subject, b->ndof, b->ncoords, b->nmodes, b->nrigid, b->nstatic);
  if (b)
    cli_say("eigen-solve %s, %zu lowest modes, %.3g s, factor %.3g MB",
            b->eig.method == FB_EIG_DENSE ? "dense LAPACK (dsygvd)"
                                          : "block Lanczos on a CHOLMOD factor",
            b->nfree, b->eig.seconds, (double)b->eig.factor_bytes / 1e6);
  say_counts(a, rv);
}

/* ---- Simulation. */

/* The "\r"-updated progress line of one run. */
typedef struct run_progress {
  const char *scenario, *system;
  double t_end; /* s */
  int percent;  /* last one drawn */
  int draw;     /* 0: only watch for an interruption */
} run_progress;

static void draw_progress_line(const run_progress *p)
{
  fputc('\r', stderr);
  cli_say_more("flexbond run: %s: simulating %s, t = 0..%g s: %3d%%", p->scenario, p->system,
               p->t_end, p->percent);
  fflush(stderr);
}

/* fb_sim_progress_fn: stops the run once interrupted; redraws only when
 * the whole percentage grows, so a run of a million steps writes at most
 * 100 lines. */
static int show_progress(void *ctx, double t, double t_end)
{
  run_progress *p = ctx;
  double fraction = t_end > 0 ? t / t_end : 1;
  int percent = (int)floor(100 * fmin(fmax(fraction, 0), 1));
  if (p->draw && percent > p->percent) {
    p->percent = percent;
    draw_progress_line(p);
  }
  return cli_interrupted();
}

/* The run's summary (flexbond/study.h): its outputs' and tires'
 * statistics over window, contact losses and ride metrics. */
static int run_columns(const fb_scenario *s, cli_run_system *run, const double window[2],
                       fb_err *err)
{
  return fb_run_summary_new(s, run->res, window, &run->sum, err);
}

static void run_system_free(cli_run_system *run)
{
  fb_result_free(&run->res);
  free(run->basis_error);
  fb_run_summary_free(&run->sum);
  fb_vehicle_motion_free(&run->motion);
  cli_run_stress_free(run);
}

/* Runs v into run, with its motion when motion (--animate, or the hull
 * stresses; v realised with it) kept over motion_window. */
static int simulate(const run_args *a, const fb_scenario *s, const double window[2],
                    const double motion_window[2], cli_run_system *run, fb_vehicle *v,
                    int motion, fb_err *err)
{
  run_progress p = {cli_scenario_name(s), run->label ? run->label : cli_system_label(run->sys),
                    s->t_end, 0, a->progress};
  if (a->progress)
    draw_progress_line(&p);
  else if (!a->quiet)
    cli_say("flexbond run: %s: simulating %s, t = 0..%g s ...", p.scenario, p.system, s->t_end);
  int rc = fb_vehicle_run(v, motion_window, show_progress, &p, &run->res,
                          motion ? &run->motion : NULL, err);
  /* End the progress line, also before an error message. */
  if (a->progress)
    fputc('\n', stderr);
  if (rc == FB_OK && a->verbose)
    cli_say("flexbond run: %s: %s: %ld Newton matrices, %ld factorisations", p.scenario,
            p.system, fb_result_stats(run->res)->newton_setups,
            fb_result_stats(run->res)->factorizations);
  if (rc == FB_OK && !a->quiet) {
    const fb_sim_stats *st = fb_result_stats(run->res);
    char events[48] = "";
    if (st->events)
      snprintf(events, sizeof events, ", %ld contact changes", st->events);
    cli_say("flexbond run: %s: %s: %zu samples, %ld steps, %ld rhs evals%s, %.3g s", p.scenario,
            p.system, fb_result_nsamples(run->res), st->steps, st->rhs_evals, events,
            st->wall_seconds);
  }
  return rc == FB_OK ? run_columns(s, run, window, err) : rc;
}

/* System 2's hull stresses over run (its motion taken) from the road
 * window's start w0 on (the last sample's time if the run ends before);
 * with -v, what they cost. */
static int run_stress(const run_args *a, const fb_scenario *s, double w0, const fb_vehicle *v,
                      cli_run_system *run, fb_err *err)
{
  const fb_vehicle_motion *m = run->motion;
  const double t_last = m->nsamples ? m->samples[(m->nsamples - 1) * m->width] : 0.0;
  run->stress_from = fmin(w0, t_last);
  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  const int rc = cli_run_stress(v, run->stress_from, run, err);
  if (rc == FB_OK && a->verbose)
    cli_say("flexbond run: %s: %s: hull stresses of %zu elements at %zu samples in %zu "
            "coordinates, %.3g s",
            cli_scenario_name(s), cli_system_label(run->sys), run->peaks->nelements,
            run->peaks->nsamples, m->ncoords, fb_seconds_since(&t0));
  return rc;
}

/* Why the run computes no hull stresses (NULL if it does): --no-stress,
 * only System 1 ran (v2, System 2's vehicle, NULL), or System 2's hull
 * has no shell elements. */
static const char *no_stress_reason(const run_args *a, const fb_vehicle *v2)
{
  if (!a->stress)
    return "the run had `--no-stress`";
  if (!v2)
    return "they are System 2's, and only System 1 (rigid hull) ran";
  return fb_hull_stress_possible(v2)
             ? NULL
             : "the hull is a superelement, which has no shell elements";
}

/* ---- The command. */

/* The systems to run: --system's, by default both, or (with *note saying
 * why) System 1 alone if the scenario has no finite-element hull, System 2
 * alone if it asks for an output System 1 cannot give. */
static size_t pick_systems(const run_args *a, const fb_scenario *s, fb_system *systems,
                           const char **note)
{
  int choice = a->system >= 0 ? a->system : SYSTEM_BOTH;
  *note = NULL;
  if (a->system < 0 && !s->has_fe_hull) {
    choice = SYSTEM_RIGID;
    *note = a->hull_modes_kind >= 0 || a->hull_cutoff > 0
                ? "the scenario has no finite-element hull (hull.mesh and hull.fe), so only "
                  "System 1 (rigid hull) ran and --hull-modes or --hull-cutoff had nothing to "
                  "set"
                : "the scenario has no finite-element hull (hull.mesh and hull.fe), so only "
                  "System 1 (rigid hull) ran";
  } else if (a->system < 0 && fb_vehicle_outputs_system2_only(s) < s->noutputs) {
    choice = SYSTEM_FLEXIBLE;
    *note = "the scenario's outputs include stresses of the shell hull, which System 1 (rigid "
            "hull) does not have, so only System 2 ran";
  }
  const size_t n = system_sets[choice].nsystems;
  for (size_t i = 0; i < n; ++i)
    systems[i] = system_sets[choice].systems[i];
  return n;
}

/* The report's data (flexbond/study.h) of the runs of o, with the
 * converged one when it ran, into *rep (new: the caller frees it with
 * fb_study_report_free after o's last use): its comparisons become o's
 * views. */
static int build_report(cli_run_outputs *o, fb_study_report **rep, fb_err *err)
{
  fb_study_run runs[CLI_MAX_SYSTEMS], conv = {0};
  for (size_t i = 0; i < o->nruns; ++i)
    runs[i] =
        (fb_study_run){o->runs[i].sys, o->runs[i].res, o->runs[i].sum, o->runs[i].basis_error};
  if (o->converged)
    conv = (fb_study_run){o->converged->sys, o->converged->res, o->converged->sum,
                          o->converged->basis_error};
  const int rc =
      fb_study_report_new(o->scenario, runs, o->nruns, o->converged ? &conv : NULL, rep, err);
  if (rc != FB_OK)
    return rc;
  o->report = *rep;
  o->diff = fb_study_report_diff(*rep, FB_STUDY_CMP_SYSTEM2);
  o->cmp = fb_study_report_cmp(*rep, FB_STUDY_CMP_SYSTEM2);
  o->diff_converged = fb_study_report_diff(*rep, FB_STUDY_CMP_CONVERGED);
  o->cmp_converged = fb_study_report_cmp(*rep, FB_STUDY_CMP_CONVERGED);
  return FB_OK;
}

/* Applies the command line's overrides to the scenario. */
static void override(const run_args *a, fb_scenario *s)
{
  if (a->initial >= 0)
    s->initial = (fb_initial_state)a->initial;
  if (a->payload >= 0)
    s->payload = (fb_payload_model)a->payload;
  if (a->hull_modes_kind >= 0) {
    s->hull_modes_kind = (fb_hull_modes_kind)a->hull_modes_kind;
    s->hull_modes = a->hull_modes;
  }
  if (a->hull_cutoff > 0 || a->hull_modes_kind >= 0)
    s->hull_cutoff_hz = a->hull_cutoff;
  /* A choice of modes is a modal hull's. */
  if (a->hull_modes_kind >= 0 || a->hull_cutoff > 0)
    s->hull_coordinates = FB_HULL_MODAL;
  if (a->hull_coordinates >= 0)
    s->hull_coordinates = (fb_hull_coordinates)a->hull_coordinates;
}

/* The frequency response of the systems that ran, for report.md's Bode
 * figures (flexbond freq's defaults: 301 frequencies from 0.1 to 100 Hz).
 * It is no part of the run's result: when it fails (a nonlinear vehicle
 * without a static equilibrium, say) the report says why instead. */
static void frequency_response(fb_vehicle *const *by_system, cli_run_outputs *o)
{
  fb_err err;
  fb_err_clear(&err);
  enum { POINTS = 301 };
  double freq_hz[POINTS];
  fb_study_freq_log_grid(0.1, 100.0, POINTS, freq_hz);
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys) {
    if (!by_system[sys] ||
        !fb_study_freq_new(by_system[sys], freq_hz, POINTS, &o->freq[sys], &err))
      continue;
    fb_err_prefix(&err, "%s: ", cli_system_label(sys ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID));
    snprintf(o->freq_note, sizeof o->freq_note, "%s", err.msg);
    fb_study_freq_free(&o->freq[0]);
    return;
  }
}

/* The animation of every system that ran, with --animate. */
static int write_animations(cli_outdir *od, const run_args *a, const fb_scenario *s,
                            const double window[2], cli_run_system *runs, size_t nruns,
                            fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; a->animate.enabled && i < nruns && rc == FB_OK; ++i) {
    if (!a->quiet)
      cli_say("flexbond run: %s: %s: drawing the animation ...", cli_scenario_name(s),
              cli_system_label(runs[i].sys));
    rc = cli_write_animation(od, s, runs[i].motion, runs[i].stress, window, &a->animate,
                             &runs[i].anim, err);
  }
  return rc;
}

/* 1 if err is about the scenario's member field (fb_err.part). */
static int about_member(const fb_err *err, const char *field)
{
  return err->part.kind == FB_PART_VEHICLE && !strcmp(err->part.field, field);
}

/* cli_report, except that an error about the hull's modes after
 * --hull-modes replaced them (overridden: more modes than the hull has) is
 * the option's: a usage error; likewise --hull-cutoff. The file's own
 * value was checked, and located, when the scenario was loaded; any other
 * error about a value of the scenario is located in its file
 * (fb_scenario_locate). */
static int report(const run_args *a, const fb_scenario *s, int rc, fb_err *err)
{
  if (rc != FB_OK && s && a->hull_modes_kind >= 0 && about_member(err, "hull_modes"))
    return cli_usage_error("run", "option '--hull-modes': %s", err->msg);
  if (rc != FB_OK && s && a->hull_cutoff > 0 && about_member(err, "hull_cutoff_hz"))
    return cli_usage_error("run", "option '--hull-cutoff': %s", err->msg);
  if (rc != FB_OK && s)
    fb_scenario_locate(s, err);
  return cli_report(rc, err);
}

/* The estimator of System 2's modal basis (reduced modal coordinates
 * only: fb_vehicle_new_estimator), integrated on a thread of its own
 * beside the runs: its result, compared with System 2's afterwards, is the
 * estimate of each output's error from the basis. */
typedef struct run_estimator {
  fb_vehicle *v; /* System 2's vehicle; NULL: no estimate */
  fb_vehicle *e; /* its estimator, made on the thread */
  pthread_t thread;
  int started;
  fb_result *res;
  int rc;
  fb_err err;
} run_estimator;

/* fb_sim_progress_fn of the estimator: it draws nothing (the runs do),
 * and stops once interrupted. */
static int estimator_progress(void *ctx, double t, double t_end)
{
  (void)ctx;
  (void)t;
  (void)t_end;
  return cli_interrupted();
}

/* The estimator made (its enriched basis from v's eigen-solve) and run,
 * beside what the main thread does with v meanwhile (fb_vehicle_new_estimator
 * allows it). */
static void *estimator_thread(void *arg)
{
  run_estimator *x = arg;
  fb_err_clear(&x->err);
  x->rc = fb_vehicle_new_estimator(x->v, &x->e, &x->err);
  if (x->rc == FB_OK)
    x->rc = fb_vehicle_run(x->e, NULL, estimator_progress, NULL, &x->res, NULL, &x->err);
  return NULL;
}

/* Starts the estimator of System 2's vehicle v (called label), if its
 * basis is a reduced one. */
static int start_estimator(const run_args *a, const fb_scenario *s, const char *label,
                           fb_vehicle *v, run_estimator *x, fb_err *err)
{
  if (!fb_vehicle_basis_reduced(v))
    return FB_OK;
  x->v = v;
  if (!a->quiet)
    cli_say("flexbond run: %s: estimating the modal basis's error beside the runs: %s with "
            "the basis's next block of Ritz vectors, t = 0..%g s ...",
            cli_scenario_name(s), label, s->t_end);
  if (pthread_create(&x->thread, NULL, estimator_thread, x) != 0)
    return fb_err_set(err, FB_ENOMEM, "could not start the estimator's thread");
  x->started = 1;
  return FB_OK;
}

/* Waits for the estimator and, when System 2's run succeeded, compares:
 * run->basis_error (new). */
static int finish_estimator(const double window[2], run_estimator *x, cli_run_system *run,
                            int rc, fb_err *err)
{
  if (x->started)
    pthread_join(x->thread, NULL);
  x->started = 0;
  if (!x->v || rc != FB_OK)
    return rc;
  if (x->rc != FB_OK) {
    *err = x->err;
    return fb_err_prefix(err, "the basis's error estimator: ");
  }
  run->basis_error = calloc(fb_result_ncols(run->res), sizeof *run->basis_error);
  if (!run->basis_error)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  return fb_result_rel_diff(run->res, x->res, window[0], run->basis_error, err);
}

static void run_estimator_free(run_estimator *x)
{
  if (x->started)
    pthread_join(x->thread, NULL);
  fb_result_free(&x->res);
  fb_vehicle_free(&x->e);
}

/* With -v: the work of the estimator e (NULL: none) of the vehicle
 * called label. */
static void say_estimator_work(const run_args *a, const fb_scenario *s, const char *label,
                               fb_vehicle *e)
{
  if (!e)
    return;
  run_vehicle est = {e, {0}, {0}};
  snprintf(est.subject, sizeof est.subject, "%s: the basis estimator of %s",
           cli_scenario_name(s), label);
  say_counts(a, &est);
}

/* ---- System 2 again at the converged mesh. */

typedef struct run_converged {
  fb_scenario *s; /* the file loaded again at hull.mesh.converged_density */
  run_vehicle rv;
  run_estimator est;
  cli_run_system run;
  char label[64]; /* "System 2 at density 3" */
} run_converged;

/* With both systems, when the scenario names a density above its own for
 * its generated hull. */
static int wants_converged(const fb_scenario *s, const cli_run_outputs *o)
{
  return o->nruns == CLI_MAX_SYSTEMS && fb_scenario_converged_density(s) > 0;
}

/* Loads the file again with hull.mesh.density at the converged density
 * (so that the mesh, the hull's mass properties and every check are that
 * mesh's, as if the user had written it), and runs its System 2, in the
 * automatic modal basis (fb_scenario_use_auto_basis), with its basis's
 * error estimate. */
static int run_converged_system(const run_args *a, const fb_scenario *s, const double window[2],
                                run_converged *c, fb_err *err)
{
  char density[16];
  snprintf(density, sizeof density, "%d", s->hull_converged_density);
  snprintf(c->label, sizeof c->label, "System 2 at density %d", s->hull_converged_density);
  const fb_scenario_override ov = {.key = "hull.mesh.density", .value = density};
  int rc = fb_scenario_load_overrides(a->scenario_path, &ov, 1, &c->s, err);
  if (rc == FB_OK) {
    override(a, c->s);
    fb_scenario_use_auto_basis(c->s);
    rc = realise(a, c->s, FB_SYSTEM_FLEXIBLE, c->label, 0, &c->rv, err);
  }
  if (rc == FB_OK)
    rc = start_estimator(a, c->s, c->label, c->rv.v, &c->est, err);
  c->run.sys = FB_SYSTEM_FLEXIBLE;
  c->run.label = c->label;
  if (rc == FB_OK)
    rc = simulate(a, c->s, window, window, &c->run, c->rv.v, 0, err);
  return finish_estimator(window, &c->est, &c->run, rc, err);
}

/* The converged run into o; the report compares it with System 1. */
static void use_converged(const run_converged *c, cli_run_outputs *o)
{
  o->converged = &c->run;
  o->converged_basis = fb_vehicle_hull_basis(c->rv.v);
  o->converged_density = fb_scenario_hull_density(c->s);
}

static void run_converged_free(run_converged *c)
{
  run_estimator_free(&c->est);
  run_system_free(&c->run);
  fb_vehicle_free(&c->rv.v);
  fb_scenario_free(&c->s);
}

static int run(const run_args *a)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  cli_run_system runs[CLI_MAX_SYSTEMS] = {{0}};
  run_vehicle vehicles[CLI_MAX_SYSTEMS];
  memset(vehicles, 0, sizeof vehicles);
  fb_system systems[CLI_MAX_SYSTEMS] = {FB_SYSTEM_RIGID};
  run_modes modes = {0};
  fb_study_report *rep = NULL;
  cli_run_outputs o = {
      .runs = runs, .figures = a->figures, .header = a->header, .animate = &a->animate};
  size_t nfiles = 0;
  cli_outdir od;
  int rc = cli_scenario_load(a->scenario_path, a->strict, &s, &err);
  /* The directory is held from here (its lock: no other command writes
   * there meanwhile) to the end. */
  if (rc == FB_OK)
    rc = cli_outdir_open(&od, a->out_dir, "run", &err);
  const int opened = rc == FB_OK;
  if (rc == FB_OK) {
    override(a, s);
    cli_mode_list_apply(&a->pictured, s);
    o.scenario = s;
    o.nruns = pick_systems(a, s, systems, &o.note);
    o.hull_modes_source =
        a->hull_modes_kind >= 0 || a->hull_coordinates >= 0 || a->hull_cutoff > 0
            ? "the command line (`--hull-modes`, `--hull-cutoff`, `--hull-coordinates`)"
            : "the scenario (`hull.fe.coordinates`, `hull.fe.modes`, `hull.fe.cutoff_hz`)";
    fb_study_response_window(s, o.bump_window);
    size_t nframes = 0;
    if (a->animate.enabled)
      rc =
          cli_animate_frame_count(o.bump_window, 0.0, s->t_end, a->animate.fps, &nframes, &err);
  }
  if (rc == FB_OK && o.note && !a->quiet)
    cli_say("flexbond run: %s: %s", cli_scenario_name(s), o.note);
  /* Each system realised once: everything below takes its vehicle. */
  for (size_t i = 0; i < o.nruns && rc == FB_OK; ++i)
    rc = realise(a, s, systems[i], cli_system_label(systems[i]), a->animate.enabled,
                 &vehicles[i], &err);
  fb_vehicle *by_system[CLI_MAX_SYSTEMS] = {NULL, NULL};
  for (size_t i = 0; i < o.nruns; ++i)
    by_system[systems[i] == FB_SYSTEM_FLEXIBLE] = vehicles[i].v;
  run_estimator estimator = {0};
  if (rc == FB_OK && by_system[1])
    rc = start_estimator(a, s, cli_system_label(FB_SYSTEM_FLEXIBLE), by_system[1], &estimator,
                         &err);

  for (size_t i = 0; i < o.nruns && rc == FB_OK; ++i) {
    runs[i].sys = systems[i];
    const int stress = a->stress && fb_hull_stress_possible(vehicles[i].v);
    /* The hull stresses' samples run from the window's start to the end. */
    const double motion_window[2] = {o.bump_window[0], stress ? s->t_end : o.bump_window[1]};
    rc = simulate(a, s, o.bump_window, motion_window, &runs[i], vehicles[i].v,
                  a->animate.enabled || stress, &err);
    if (rc == FB_OK && stress)
      rc = run_stress(a, s, o.bump_window[0], vehicles[i].v, &runs[i], &err);
  }
  /* The modes while the estimator finishes. */
  if (rc == FB_OK) {
    o.no_stress = no_stress_reason(a, by_system[1]);
    /* Said on stderr unless the user asked for none. */
    if (o.no_stress && a->stress && !a->quiet)
      cli_say("flexbond run: %s: no hull stresses (%s): %s", cli_scenario_name(s),
              CLI_STRESS_CSV, o.no_stress);
    rc = compute_modes(vehicles, o.nruns, &modes, &err);
  }
  for (size_t i = 0; i < o.nruns; ++i)
    if (systems[i] == FB_SYSTEM_FLEXIBLE)
      rc = finish_estimator(o.bump_window, &estimator, &runs[i], rc, &err);
  run_converged conv = {0};
  if (rc == FB_OK && wants_converged(s, &o))
    rc = run_converged_system(a, s, o.bump_window, &conv, &err);
  if (rc == FB_OK) {
    o.modes1 = modes.modes1;
    o.nmodes1 = modes.nmodes1;
    o.nstatic1 = modes.nstatic1;
    if (by_system[1]) {
      o.hull = fb_vehicle_fe_hull_of(by_system[1]);
      o.basis = fb_vehicle_hull_basis(by_system[1]);
    }
    o.modes2 = modes.modes2;
    for (size_t i = 0; i < o.nruns; ++i)
      o.vehicles[i] = vehicles[i].v;
    if (conv.rv.v)
      use_converged(&conv, &o);
    rc = build_report(&o, &rep, &err);
  }
  if (rc == FB_OK && o.figures)
    frequency_response(by_system, &o);
  if (rc == FB_OK)
    rc = write_animations(&od, a, s, o.bump_window, runs, o.nruns, &err);
  if (rc == FB_OK)
    rc = write_outputs(&od, &o, &nfiles, &err);
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys)
    fb_study_freq_free(&o.freq[sys]);
  if (opened)
    rc = cli_outdir_close(&od, rc, &err);
  for (size_t i = 0; i < o.nruns && rc == FB_OK; ++i)
    say_work(a, &vehicles[i]);
  if (rc == FB_OK && conv.rv.v)
    say_work(a, &conv.rv);
  if (rc == FB_OK)
    say_estimator_work(a, s, cli_system_label(FB_SYSTEM_FLEXIBLE), estimator.e);
  if (rc == FB_OK && conv.rv.v)
    say_estimator_work(a, s, conv.label, conv.est.e);
  if (rc == FB_OK && !a->quiet)
    cli_say("flexbond run: %s: wrote %zu files -> %s", cli_scenario_name(s), nfiles,
            a->out_dir);
  fb_study_report_free(&rep);
  run_converged_free(&conv);
  for (size_t i = 0; i < CLI_MAX_SYSTEMS; ++i)
    run_system_free(&runs[i]);
  run_modes_free(&modes);
  run_estimator_free(&estimator);
  for (size_t i = 0; i < CLI_MAX_SYSTEMS; ++i)
    fb_vehicle_free(&vehicles[i].v);
  rc = report(a, s, rc, &err);
  fb_scenario_free(&s);
  return rc;
}

/* The value of --hull-modes, as hull.fe.modes: auto, all or an integer in
 * 6 .. MAX_HULL_MODES (the six rigid-body modes at least). */
static int parse_hull_modes(const char *cmd, const char *text, run_args *a)
{
  if (!strcmp(text, "auto")) {
    a->hull_modes_kind = FB_HULL_MODES_AUTO;
    return CLI_EXIT_OK;
  }
  if (!strcmp(text, "all")) {
    a->hull_modes_kind = FB_HULL_MODES_ALL;
    return CLI_EXIT_OK;
  }
  char *end = NULL;
  errno = 0;
  long v = strtol(text, &end, 10);
  if (end == text || *end != '\0' || errno == ERANGE || v < 6 || v > MAX_HULL_MODES)
    return cli_usage_error(cmd,
                           "option '--hull-modes' needs auto, all (every mode) or an integer "
                           "in 6..%d (got '%s')",
                           MAX_HULL_MODES, text);
  a->hull_modes_kind = FB_HULL_MODES_COUNT;
  a->hull_modes = (int)v;
  return CLI_EXIT_OK;
}

/* The options' values into a (after the output directory). */
static int parse_settings(const char *cmd, const cli_option *system, const cli_option *initial,
                          const cli_option *payload, const cli_option *hull_modes,
                          const cli_option *cutoff, const cli_option *coordinates, run_args *a)
{
  int rc = CLI_EXIT_OK;
  if (system->value)
    rc = cli_choice(cmd, "--system", system->value, system_choices,
                    sizeof system_choices / sizeof system_choices[0], &a->system);
  if (rc == CLI_EXIT_OK && initial->value)
    rc = cli_choice(cmd, "--initial", initial->value, initial_choices,
                    sizeof initial_choices / sizeof initial_choices[0], &a->initial);
  if (rc == CLI_EXIT_OK && payload->value)
    rc = cli_choice(cmd, "--payload", payload->value, payload_choices,
                    sizeof payload_choices / sizeof payload_choices[0], &a->payload);
  if (rc == CLI_EXIT_OK && hull_modes->value)
    rc = parse_hull_modes(cmd, hull_modes->value, a);
  if (rc == CLI_EXIT_OK && cutoff->value)
    rc = cli_positive_number(cmd, "--hull-cutoff", cutoff->value, &a->hull_cutoff);
  if (rc == CLI_EXIT_OK && cutoff->value && a->hull_modes_kind > FB_HULL_MODES_AUTO)
    rc = cli_usage_error(cmd, "--hull-cutoff sets which modes --hull-modes auto keeps: not "
                              "with --hull-modes all or a count");
  if (rc == CLI_EXIT_OK && coordinates->value)
    rc = cli_choice(cmd, "--hull-coordinates", coordinates->value, coordinate_choices,
                    sizeof coordinate_choices / sizeof coordinate_choices[0],
                    &a->hull_coordinates);
  if (rc == CLI_EXIT_OK && (hull_modes->value || cutoff->value || coordinates->value) &&
      a->system == SYSTEM_RIGID)
    rc = cli_usage_error(cmd, "--hull-modes, --hull-cutoff and --hull-coordinates set System "
                              "2's hull: not with --system rigid");
  if (rc == CLI_EXIT_OK && (hull_modes->value || cutoff->value) &&
      a->hull_coordinates == FB_HULL_NODAL)
    rc = cli_usage_error(cmd, "--hull-modes and --hull-cutoff choose a modal hull's modes: not "
                              "with --hull-coordinates nodal");
  return rc;
}

/* --animate and its settings into a->animate. */
static int parse_animate(const char *cmd, const cli_option *animate, const cli_option *fps,
                         const cli_option *scale, run_args *a)
{
  a->animate = (cli_animate_opts){animate->value != NULL, 50.0, 0.0, a->figures};
  if (!a->animate.enabled && (fps->value || scale->value))
    return cli_usage_error(cmd, "--animate-fps and --animate-scale set the animation: give "
                                "--animate too");
  int rc = CLI_EXIT_OK;
  if (fps->value)
    rc = cli_positive_number(cmd, "--animate-fps", fps->value, &a->animate.fps);
  if (rc == CLI_EXIT_OK && scale->value)
    rc = cli_positive_number(cmd, "--animate-scale", scale->value, &a->animate.scale);
  /* A frame at least every second, at most a thousand per second (the
   * default sample rate). */
  if (rc == CLI_EXIT_OK && (a->animate.fps < 1.0 || a->animate.fps > 1000.0))
    rc = cli_usage_error(
        cmd, "option '--animate-fps' needs 1..1000 frames per second (got '%s')", fps->value);
  return rc;
}

int cli_cmd_run(int argc, char **argv)
{
  enum {
    OPT_OUT,
    OPT_SYSTEM,
    OPT_INITIAL,
    OPT_PAYLOAD,
    OPT_HULL_MODES,
    OPT_HULL_CUTOFF,
    OPT_HULL_COORDINATES,
    OPT_ANIMATE,
    OPT_ANIMATE_FPS,
    OPT_ANIMATE_SCALE,
    OPT_NO_FIGURES,
    OPT_NO_STRESS,
    OPT_PICTURE_MODES,
    OPT_PLAIN_HEADER,
    OPT_QUIET,
    OPT_VERBOSE,
    OPT_STRICT,
    OPT_HELP,
    NOPTS
  };
  cli_option opts[NOPTS] = {
      [OPT_OUT] = {"--output", "-o", 1, NULL},
      [OPT_SYSTEM] = {"--system", NULL, 1, NULL},
      [OPT_INITIAL] = {"--initial", NULL, 1, NULL},
      [OPT_PAYLOAD] = {"--payload", NULL, 1, NULL},
      [OPT_HULL_MODES] = {"--hull-modes", NULL, 1, NULL},
      [OPT_HULL_CUTOFF] = {"--hull-cutoff", NULL, 1, NULL},
      [OPT_HULL_COORDINATES] = {"--hull-coordinates", NULL, 1, NULL},
      [OPT_ANIMATE] = {"--animate", NULL, 0, NULL},
      [OPT_ANIMATE_FPS] = {"--animate-fps", NULL, 1, NULL},
      [OPT_ANIMATE_SCALE] = {"--animate-scale", NULL, 1, NULL},
      [OPT_NO_FIGURES] = {"--no-figures", NULL, 0, NULL},
      [OPT_NO_STRESS] = {"--no-stress", NULL, 0, NULL},
      [OPT_PICTURE_MODES] = {"--picture-modes", NULL, 1, NULL},
      [OPT_PLAIN_HEADER] = {"--plain-header", NULL, 0, NULL},
      [OPT_QUIET] = {"--quiet", "-q", 0, NULL},
      [OPT_VERBOSE] = {"--verbose", "-v", 0, NULL},
      [OPT_STRICT] = {"--strict", NULL, 0, NULL},
      [OPT_HELP] = {"--help", "-h", 0, NULL},
  };
  run_args a = {.system = -1,
                .initial = -1,
                .payload = -1,
                .hull_coordinates = -1,
                .hull_modes_kind = -1};
  int rc;
  char run_usage[sizeof run_usage_files + sizeof run_usage_options];
  snprintf(run_usage, sizeof run_usage, "%s%s", run_usage_files, run_usage_options);
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, run_usage, "SCENARIO", &a.scenario_path,
                              &rc))
    return rc;
  a.out_dir = opts[OPT_OUT].value;
  if (!a.out_dir || !*a.out_dir)
    return cli_usage_error(argv[0], "missing output directory (-o DIR)");
  a.quiet = opts[OPT_QUIET].value != NULL;
  a.strict = opts[OPT_STRICT].value != NULL;
  a.verbose = !a.quiet && opts[OPT_VERBOSE].value != NULL;
  a.progress = !a.quiet && isatty(STDERR_FILENO);
  a.figures = opts[OPT_NO_FIGURES].value == NULL;
  a.stress = opts[OPT_NO_STRESS].value == NULL;
  a.header = opts[OPT_PLAIN_HEADER].value ? FB_CSV_HEADER_NAMES : FB_CSV_HEADER_UNITS;
  rc = parse_settings(argv[0], &opts[OPT_SYSTEM], &opts[OPT_INITIAL], &opts[OPT_PAYLOAD],
                      &opts[OPT_HULL_MODES], &opts[OPT_HULL_CUTOFF],
                      &opts[OPT_HULL_COORDINATES], &a);
  if (rc == CLI_EXIT_OK)
    rc = parse_animate(argv[0], &opts[OPT_ANIMATE], &opts[OPT_ANIMATE_FPS],
                       &opts[OPT_ANIMATE_SCALE], &a);
  if (rc == CLI_EXIT_OK && opts[OPT_PICTURE_MODES].value)
    rc = cli_picture_modes_option(argv[0], opts[OPT_PICTURE_MODES].value, &a.pictured);
  return rc == CLI_EXIT_OK ? run(&a) : rc;
}
