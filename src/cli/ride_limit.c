/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond ride-limit: the ride-limiting speed of a vehicle scenario
 * against a scenario value (docs/ride-limit.md). For each --vary value
 * and system the study layer searches the speed at which the --metric of
 * an output reaches its limit (fb_study_ride_limit); its rounds of runs go
 * to the sweep's threads (ride_limit_cases.c), every finished run to
 * DIR/ride_limit.partial.csv for --resume; DIR/ride_limit.csv and
 * DIR/ride_limit.png are written at the end, all or nothing. */
#include "ride_limit.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "flexbond/escape.h"
#include "flexbond/io.h"

#include "../core/textfile.h"
#include "../core/util.h"
#include "cli.h"
#include "sweep.h"

static const char rl_usage[] =
    "usage: flexbond ride-limit SCENARIO.yaml --vary KEY=V1,V2,... --metric NAME -o DIR\n"
    "                           [--limit X] [--output COLUMN] [--speeds LO:HI]\n"
    "                           [--tolerance KMH] [--coarse-step KMH] [--refine K]\n"
    "                           [--course-length L] [--settle S]\n"
    "                           [--system rigid|flexible|both] [-j N] [--resume] [--mpi]\n"
    "                           [--no-figures] [-q]\n"
    "\n"
    "For each value of KEY, the ride-limiting speed: the highest speed below which\n"
    "the metric of the output stays under its limit (docs/ride-limit.md), found by\n"
    "a coarse grid of speeds and then bisection of the bracket it finds. Writes\n"
    "  DIR/ride_limit.csv   a row per value and system: the speed (km/h), the\n"
    "                       status (found, below, above, failed), the metric there\n"
    "                       and the number of runs\n"
    "  DIR/ride_limit.png   the speed against the value, a curve per system\n"
    "Finished runs are kept in DIR/ride_limit.partial.csv until the end, so that a\n"
    "killed or interrupted study can be resumed.\n"
    "\n"
    "  --vary KEY=V1,V2,...  a key of the scenario (as sweep's --set takes it:\n"
    "                        road.bump.height, road.iso8608.rms) and its values\n"
    "  --metric NAME         of a seat's acceleration: absorbed_power (limit 6 W),\n"
    "                        nrmm_peak (30 Hz low-pass, limit 2.5 g), se (ISO 2631-5,\n"
    "                        limit 0.5 MPa), dz, vdv_ratio (limit 1), a_w_rms, mtvv,\n"
    "                        vdv, crest_factor, jerk_peak; of any output: abs_peak\n"
    "                        (its largest |value|); over [first wheel on the\n"
    "                        feature, run's end]\n"
    "  --limit X             the metric's limit (default: the standard one, if any)\n"
    "  --output COLUMN       the output measured (default: the first mounted body's\n"
    "                        acceleration, driver_acc in the examples)\n"
    "  --speeds LO:HI        km/h searched (default 5:80)\n"
    "  --coarse-step KMH     the first grid's spacing (default 5 km/h)\n"
    "  --tolerance KMH       the final bracket's width (default 0.1 km/h)\n"
    "  --refine K            speeds per value and refining round (default 1)\n"
    "  --course-length L     m of road each wheel runs on a road that goes on\n"
    "                        (random, profile; default 200)\n"
    "  --settle S            s (> 0) after the last wheel leaves an obstacle\n"
    "                        (default 2)\n"
    "  --system S            rigid (default: System 1), flexible or both\n"
    "  -j, --jobs N          runs at once (default: the online CPUs)\n"
    "  --resume              run only the runs DIR/ride_limit.partial.csv lacks\n"
    "  --mpi                 hand each round's runs to the ranks of an MPI job, one\n"
    "                        per rank at a time (mpirun -np N flexbond ride-limit\n"
    "                        --mpi ...; an MPI build only, docs/cluster.md)\n"
    "  -o, --output-dir DIR  output directory (required)\n"
    "  --no-figures          no ride_limit.png\n"
    "  -q, --quiet           no progress lines on stderr\n"
    "  -h, --help            this text\n";

static const char *const status_words[] = {"found", "below", "above", "failed"};

/* ---- ride_limit.csv: a row per curve. */

/* A speed in km/h to 10 significant digits: the search ran in m/s, and
 * 62.265624999999986 is 62.265625 within 1e-15, far below its tolerance. */
static void write_speed(FILE *fp, double speed)
{
  if (isfinite(speed))
    fprintf(fp, "%.10g", speed * 3.6);
}

static void write_number(FILE *fp, double x)
{
  if (isfinite(x)) {
    char text[32];
    sweep_format_double(x, text, sizeof text);
    fputs(text, fp);
  }
}

static void write_csv(FILE *fp, const void *ctx)
{
  const rl_args *a = ctx;
  const char *metric = fb_study_ride_limit_metric_name(a->metric);
  const char *unit = fb_study_ride_limit_metric_unit(a->metric);
  if (!unit)
    unit = a->base->output[a->output].unit;
  const char *key_unit = fb_scenario_key_unit(a->vary_path);
  char cell[FB_ERR_KEY_MAX + 64];
  if (key_unit)
    snprintf(cell, sizeof cell, "%s [%s]", a->vary_key, key_unit);
  else
    snprintf(cell, sizeof cell, "%s", a->vary_key);
  fb_csv_write_field(fp, cell, FB_CSV_TEXT);
  fputs(",system,speed_kmh [km/h],status,", fp);
  const int has_unit = unit && strcmp(unit, "-") != 0;
  snprintf(cell, sizeof cell, has_unit ? "%s [%s]" : "%s", metric, unit);
  fb_csv_write_field(fp, cell, FB_CSV_TEXT);
  fputs(",speed_over_kmh [km/h],", fp);
  snprintf(cell, sizeof cell, has_unit ? "%s_over [%s]" : "%s_over", metric, unit);
  fb_csv_write_field(fp, cell, FB_CSV_TEXT);
  fputs(",runs,error\n", fp);
  for (size_t c = 0; c < rl_ncurves(a); ++c) {
    const fb_study_ride_limit_curve *r = &a->curves[c];
    fb_csv_write_field(fp, a->values[c % a->nvalues], 0);
    fprintf(fp, ",%s,", a->systems[c / a->nvalues] == FB_SYSTEM_RIGID ? "rigid" : "flexible");
    /* below: v_lo's metric in the metric column; above: v_hi's. */
    const int found = r->status == FB_RIDE_LIMIT_FOUND;
    write_speed(fp, found ? r->speed : NAN);
    fprintf(fp, ",%s,", status_words[r->status]);
    write_number(fp, r->status == FB_RIDE_LIMIT_BELOW ? r->metric_over : r->metric);
    fputc(',', fp);
    write_speed(fp, found ? r->speed_over : NAN);
    fputc(',', fp);
    write_number(fp, found ? r->metric_over : NAN);
    fprintf(fp, ",%zu,", r->nruns);
    if (a->curve_error[c])
      fb_csv_write_field(fp, a->curve_error[c], 0);
    fputc('\n', fp);
  }
}

/* ---- ride_limit.png: the speed against the value, a curve per system. */

static int write_figure(cli_outdir *od, const rl_args *a, fb_err *err)
{
  const size_t n = a->nvalues;
  double *x = malloc(n * sizeof *x), *y = malloc(a->nsystems * n * sizeof *y);
  char *path = x && y ? cli_outdir_path(od, "ride_limit.png", err) : NULL;
  int rc = !x || !y ? fb_err_set(err, FB_ENOMEM, "out of memory for the figure")
           : !path  ? err->code
                    : FB_OK;
  int categorical = 0;
  for (size_t v = 0; rc == FB_OK && v < n; ++v)
    categorical |= !sweep_numeric_value(a->values[v], &x[v]);
  for (size_t v = 0; rc == FB_OK && categorical && v < n; ++v)
    x[v] = (double)v;
  fb_plot_xy_series series[2];
  for (size_t s = 0; rc == FB_OK && s < a->nsystems; ++s) {
    for (size_t v = 0; v < n; ++v) {
      const fb_study_ride_limit_curve *c = &a->curves[s * n + v];
      y[s * n + v] = c->status == FB_RIDE_LIMIT_FOUND ? c->speed * 3.6 : NAN;
    }
    series[s] =
        (fb_plot_xy_series){.x = x,
                            .y = &y[s * n],
                            .n = n,
                            .legend = a->nsystems > 1 ? cli_system_label(a->systems[s]) : NULL};
  }
  if (rc == FB_OK) {
    char title[512], ylabel[256], xlabel[FB_ERR_KEY_MAX + 64];
    const char *unit = fb_study_ride_limit_metric_unit(a->metric);
    if (!unit)
      unit = a->base->output[a->output].unit;
    snprintf(title, sizeof title, "flexbond ride-limit: %s, %s of %s = %g %s", a->scenario_name,
             fb_study_ride_limit_metric_name(a->metric), a->base->output[a->output].name,
             a->opts.limit, unit && strcmp(unit, "-") != 0 ? unit : "");
    snprintf(ylabel, sizeof ylabel, "ride-limiting speed [km/h]");
    const char *key_unit = fb_scenario_key_unit(a->vary_path);
    if (key_unit)
      snprintf(xlabel, sizeof xlabel, "%s [%s]", a->vary_key, key_unit);
    else
      snprintf(xlabel, sizeof xlabel, "%s", a->vary_key);
    const fb_plot_xy_panel panel = {.series = series, .nseries = a->nsystems, .ylabel = ylabel};
    fb_plot_xy_opts opts;
    fb_plot_xy_opts_default(&opts);
    opts.title = title;
    opts.xlabel = xlabel;
    opts.xtic_labels = categorical ? (const char *const *)a->values : NULL;
    opts.nxtics = categorical ? n : 0;
    opts.panel_width = 640;
    opts.panel_height = 420;
    rc = fb_plot_xy_png(&panel, 1, &opts, path, err);
    if (rc == FB_OK) {
      rc = cli_outdir_keep(od, path, err);
      path = NULL;
    }
  }
  free(path);
  free(x);
  free(y);
  return rc;
}

/* ---- The command line. */

/* V1,V2,...: each value's text, spaces around it removed; a value that
 * reads as a number must be a plain decimal one (as sweep's lists). */
static int parse_values(const char *cmd, const char *vary, rl_args *a)
{
  const char *eq = strchr(vary, '=');
  unsigned code = 0;
  const size_t bad = fb_text_find_control(vary, strlen(vary), 0, &code);
  if (vary[bad])
    return cli_usage_error(cmd,
                           "--vary: a control character (U+%04X) at byte %zu; keys and "
                           "values are one line of printable text",
                           code, bad + 1);
  if (!eq || eq == vary || !eq[1])
    return cli_usage_error(cmd, "--vary needs KEY=V1,V2,... (got '%s')", vary);
  a->vary_key = fb_strdup(vary);
  if (!a->vary_key)
    return cli_usage_error(cmd, "out of memory");
  ((char *)a->vary_key)[eq - vary] = '\0';
  a->values = calloc(RL_MAX_VALUES, sizeof *a->values);
  if (!a->values)
    return cli_usage_error(cmd, "out of memory");
  for (const char *p = eq + 1;;) {
    size_t len = strcspn(p, ",");
    const char *item = p;
    while (len > 0 && *item == ' ')
      ++item, --len;
    while (len > 0 && item[len - 1] == ' ')
      --len;
    if (len == 0)
      return cli_usage_error(cmd, "--vary %s: an empty value in the list", vary);
    if (a->nvalues == RL_MAX_VALUES)
      return cli_usage_error(cmd, "--vary %s: more than %d values", vary, RL_MAX_VALUES);
    char *v = fb_strdup_printf("%.*s", (int)len, item);
    if (!v)
      return cli_usage_error(cmd, "out of memory");
    a->values[a->nvalues++] = v;
    char *end = NULL;
    double x;
    (void)strtod(v, &end);
    if (end != v && *end == '\0' && !sweep_numeric_value(v, &x))
      return cli_usage_error(cmd,
                             "--vary %s: '%s' is not a finite number in decimal digits (as "
                             "16, 0.5 or 1e-3; hexadecimal, inf and nan are not read)",
                             vary, v);
    p = item + len + strspn(item + len, " ");
    if (!*p)
      return CLI_EXIT_OK;
    ++p;
  }
}

/* LO:HI km/h into the options (m/s). */
static int parse_speeds(const char *cmd, const char *text, fb_study_ride_limit_opts *o)
{
  const char *colon = text ? strchr(text, ':') : NULL;
  if (!text)
    return CLI_EXIT_OK;
  double lo = 0, hi = 0;
  char *lo_text = colon ? fb_strdup_printf("%.*s", (int)(colon - text), text) : NULL;
  const int ok = colon && lo_text && sweep_numeric_value(lo_text, &lo) &&
                 sweep_numeric_value(colon + 1, &hi) && lo > 0 && hi > lo;
  free(lo_text);
  if (!ok)
    return cli_usage_error(cmd, "--speeds needs LO:HI in km/h with 0 < LO < HI (got '%s')",
                           text);
  o->v_lo = lo / 3.6;
  o->v_hi = hi / 3.6;
  return CLI_EXIT_OK;
}

/* An optional positive number (km/h converted to m/s with scale 1/3.6). */
static int opt_number(const char *cmd, const char *name, const char *text, double scale,
                      double *out)
{
  if (!text)
    return CLI_EXIT_OK;
  double x = 0;
  const int rc = cli_positive_number(cmd, name, text, &x);
  if (rc == CLI_EXIT_OK)
    *out = x * scale;
  return rc;
}

/* The metric, its limit and the output. */
static int parse_metric(const char *cmd, const char *metric, const char *limit,
                        const char *output, rl_args *a)
{
  if (!metric || fb_study_ride_limit_metric_find(metric, &a->metric) != 0) {
    char names[512] = "";
    size_t len = 0;
    for (size_t m = 0; m < fb_study_ride_limit_nmetrics(); ++m)
      len = fb_text_append(names, sizeof names, len, "%s%s", m ? ", " : "",
                           fb_study_ride_limit_metric_name(m));
    return metric ? cli_usage_error(cmd, "--metric %s: no such metric (the metrics: %s)",
                                    metric, names)
                  : cli_usage_error(cmd, "missing --metric NAME (one of: %s)", names);
  }
  a->opts.limit = fb_study_ride_limit_metric_limit(a->metric);
  if (limit && !sweep_numeric_value(limit, &a->opts.limit))
    return cli_usage_error(cmd, "--limit needs a finite decimal number (got '%s')", limit);
  if (!isfinite(a->opts.limit))
    return cli_usage_error(cmd, "--metric %s has no standard limit: give --limit X", metric);
  const fb_scenario *s = a->base;
  a->output = output ? 0 : fb_study_ride_output(s);
  while (output && a->output < s->noutputs && strcmp(s->output[a->output].name, output) != 0)
    ++a->output;
  if (a->output == s->noutputs)
    return output ? cli_usage_error(cmd, "--output %s: the scenario has no such output", output)
                  : cli_usage_error(cmd, "the scenario's outputs have no mounted body's "
                                         "acceleration (signal acc): give --output COLUMN");
  const char *unit = s->output[a->output].unit;
  if (fb_study_ride_limit_metric_of_acceleration(a->metric) &&
      (!unit || strcmp(unit, "m/s^2") != 0))
    return cli_usage_error(cmd,
                           "--metric %s is of a vertical acceleration in m/s^2; output %s is "
                           "in %s (abs_peak takes any output)",
                           metric, s->output[a->output].name, unit ? unit : "no unit");
  return CLI_EXIT_OK;
}

enum {
  OPT_DIR,
  OPT_VARY,
  OPT_METRIC,
  OPT_LIMIT,
  OPT_OUTPUT,
  OPT_SPEEDS,
  OPT_STEP,
  OPT_TOL,
  OPT_REFINE,
  OPT_COURSE,
  OPT_SETTLE,
  OPT_SYSTEM,
  OPT_JOBS,
  OPT_RESUME,
  OPT_MPI,
  OPT_NO_FIGURES,
  OPT_QUIET,
  OPT_HELP,
  NOPTS
};

/* The scenario, the systems and the key. */
static int load_base(const char *cmd, const cli_option *opts, rl_args *a)
{
  static const char *const systems[] = {"rigid", "flexible", "both"};
  int system = 0;
  int rc = opts[OPT_SYSTEM].value
               ? cli_choice(cmd, "--system", opts[OPT_SYSTEM].value, systems, 3, &system)
               : CLI_EXIT_OK;
  if (rc != CLI_EXIT_OK)
    return rc;
  a->nsystems = system == 2 ? 2 : 1;
  a->systems[0] = system == 1 ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID;
  a->systems[1] = FB_SYSTEM_FLEXIBLE;
  fb_err err;
  rc = cli_scenario_load(a->scenario_path, 0, &a->base, &err);
  if (rc != FB_OK)
    return cli_report(rc, &err);
  a->scenario_name = cli_scenario_name(a->base);
  if (system > 0 && !a->base->has_fe_hull)
    return cli_usage_error(cmd,
                           "--system %s: the scenario has no finite-element hull "
                           "(hull.mesh and hull.fe)",
                           systems[system]);
  rc = fb_scenario_override_key(a->scenario_path, a->vary_key, &a->vary_path, &err);
  if (rc == FB_EINVAL)
    return cli_usage_error(cmd, "--vary %s: %s", a->vary_key, err.msg);
  if (rc != FB_OK)
    return cli_report(rc, &err);
  if (!strcmp(a->vary_path, "road.speed_kmh") || !strcmp(a->vary_path, "simulation.t_end"))
    return cli_usage_error(cmd, "--vary %s: the search sets %s itself", a->vary_key,
                           a->vary_path);
  return CLI_EXIT_OK;
}

static int parse_args(int argc, char **argv, rl_args *a, int *go)
{
  cli_option opts[NOPTS] = {
      [OPT_DIR] = {"--output-dir", "-o", 1, NULL},
      [OPT_VARY] = {"--vary", NULL, 1, NULL},
      [OPT_METRIC] = {"--metric", NULL, 1, NULL},
      [OPT_LIMIT] = {"--limit", NULL, 1, NULL},
      [OPT_OUTPUT] = {"--output", NULL, 1, NULL},
      [OPT_SPEEDS] = {"--speeds", NULL, 1, NULL},
      [OPT_STEP] = {"--coarse-step", NULL, 1, NULL},
      [OPT_TOL] = {"--tolerance", NULL, 1, NULL},
      [OPT_REFINE] = {"--refine", NULL, 1, NULL},
      [OPT_COURSE] = {"--course-length", NULL, 1, NULL},
      [OPT_SETTLE] = {"--settle", NULL, 1, NULL},
      [OPT_SYSTEM] = {"--system", NULL, 1, NULL},
      [OPT_JOBS] = {"--jobs", "-j", 1, NULL},
      [OPT_RESUME] = {"--resume", NULL, 0, NULL},
      [OPT_MPI] = {"--mpi", NULL, 0, NULL},
      [OPT_NO_FIGURES] = {"--no-figures", NULL, 0, NULL},
      [OPT_QUIET] = {"--quiet", "-q", 0, NULL},
      [OPT_HELP] = {"--help", "-h", 0, NULL},
  };
  int rc;
  *go = cli_parse_file_command(argc, argv, opts, NOPTS, rl_usage, "SCENARIO", &a->scenario_path,
                               &rc);
  if (!*go)
    return rc;
  const char *cmd = argv[0];
  a->out_dir = opts[OPT_DIR].value;
  if (!a->out_dir || !*a->out_dir)
    return cli_usage_error(cmd, "missing output directory (-o DIR)");
  if (opts[OPT_MPI].value && opts[OPT_JOBS].value)
    return cli_usage_error(cmd, "--mpi runs one run per rank at a time: instead of -j, "
                                "start more ranks (docs/cluster.md)");
  if (!opts[OPT_VARY].value)
    return cli_usage_error(cmd, "missing --vary KEY=V1,V2,...");
  a->quiet = opts[OPT_QUIET].value != NULL;
  a->figures = opts[OPT_NO_FIGURES].value == NULL;
  a->resume = opts[OPT_RESUME].value != NULL;
  a->course_length = 200;
  a->settle = 2;
  fb_study_ride_limit_opts_default(&a->opts);
  double refine = 1, settle = 0;
  rc = parse_values(cmd, opts[OPT_VARY].value, a);
  if (rc == CLI_EXIT_OK)
    rc = parse_speeds(cmd, opts[OPT_SPEEDS].value, &a->opts);
  if (rc == CLI_EXIT_OK)
    rc = opt_number(cmd, "--coarse-step", opts[OPT_STEP].value, 1 / 3.6, &a->opts.coarse_step);
  if (rc == CLI_EXIT_OK)
    rc = opt_number(cmd, "--tolerance", opts[OPT_TOL].value, 1 / 3.6, &a->opts.tol);
  if (rc == CLI_EXIT_OK)
    rc = opt_number(cmd, "--course-length", opts[OPT_COURSE].value, 1, &a->course_length);
  if (rc == CLI_EXIT_OK && opts[OPT_SETTLE].value &&
      !(sweep_numeric_value(opts[OPT_SETTLE].value, &settle) && settle > 0 && isfinite(settle)))
    rc = cli_usage_error(cmd, "--settle needs a number of seconds > 0 (got '%s')",
                         opts[OPT_SETTLE].value);
  if (rc == CLI_EXIT_OK && opts[OPT_SETTLE].value)
    a->settle = settle;
  if (rc == CLI_EXIT_OK)
    rc = opt_number(cmd, "--refine", opts[OPT_REFINE].value, 1, &refine);
  if (rc == CLI_EXIT_OK && (refine != floor(refine) || refine > 100))
    rc = cli_usage_error(cmd, "--refine needs a whole number in 1..100 (got '%s')",
                         opts[OPT_REFINE].value);
  a->opts.refine_points = (size_t)refine;
  if (rc == CLI_EXIT_OK)
    rc = sweep_parse_jobs(cmd, opts[OPT_JOBS].value, &a->jobs);
  if (rc == CLI_EXIT_OK)
    rc = load_base(cmd, opts, a);
  if (rc == CLI_EXIT_OK)
    rc = parse_metric(cmd, opts[OPT_METRIC].value, opts[OPT_LIMIT].value,
                      opts[OPT_OUTPUT].value, a);
  fb_err err;
  if (rc == CLI_EXIT_OK && fb_study_ride_limit(0, &a->opts, rl_eval, a, NULL, NULL, &err))
    rc = cli_usage_error(cmd, "%s", err.msg);
  const int loaded = rc == CLI_EXIT_OK ? rl_check_values(a, &err) : FB_OK;
  if (loaded != FB_OK)
    rc = cli_report_scenario(a->base, loaded, &err);
  return rc;
}

/* ---- Running the study. */

static size_t count_status(const rl_args *a, fb_ride_limit_status st)
{
  size_t n = 0;
  for (size_t c = 0; c < rl_ncurves(a); ++c)
    n += a->curves[c].status == st;
  return n;
}

/* The search, then the files; the status. */
static int run_study(rl_args *a, cli_outdir *od, size_t *rounds, fb_err *err)
{
  int rc = rl_journal_open(a, err);
  if (rc == FB_OK && a->nresumed > 0 && !a->quiet)
    cli_say("flexbond ride-limit: resuming: %zu runs are done", a->nresumed);
  if (rc == FB_OK)
    rc = fb_study_ride_limit(rl_ncurves(a), &a->opts, rl_eval, a, a->curves, rounds, err);
  if (rc == FB_OK && a->figures)
    rc = write_figure(od, a, err);
  if (rc == FB_OK)
    rc = cli_outdir_write(od, "ride_limit.csv", write_csv, a, err);
  return rc;
}

static int ride_limit(rl_args *a)
{
  fb_err err;
  fb_err_clear(&err);
  cli_outdir od;
  int rc = cli_outdir_open(&od, a->out_dir, "ride-limit", &err);
  char note[FB_ERR_MSG_MAX] = "";
  char *journal = rc == FB_OK ? rl_journal_path(a) : NULL;
  if (journal) {
    snprintf(note, sizeof note,
             "the finished runs are kept in %s: run the same command with --resume to go on",
             journal);
    od.interrupt_note = note;
  }
  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  size_t rounds = 0;
  const int opened = rc == FB_OK;
  if (rc == FB_OK)
    rc = run_study(a, &od, &rounds, &err);
  const int bad_journal = rc == FB_EINVAL && a->ndone == 0 && !a->journal;
  if (rc == FB_OK)
    rc = cli_outdir_close(&od, rc, &err);
  else if (opened) {
    /* Kept for --resume when it holds runs and the study was not refused. */
    const int keep = a->journal && a->ndone > 0;
    rl_journal_close(a, !keep && a->journal);
    if (keep) {
      fb_err_append(&err,
                    "; %zu runs are kept in %s: run the same command with --resume to go on",
                    a->ndone, journal);
      od.failure_noted = 1;
    }
    cli_outdir_close(&od, rc, &err);
  }
  if (rc == FB_OK)
    rl_journal_close(a, 1);
  free(journal);
  if (bad_journal)
    return cli_usage_error("ride-limit", "%s", err.msg);
  if (rc != FB_OK)
    return cli_report(rc, &err);
  const size_t failed = count_status(a, FB_RIDE_LIMIT_FAILED);
  if (!a->quiet)
    cli_say("flexbond ride-limit: %s: %zu curve%s (%zu found, %zu below, %zu above, %zu "
            "failed), %zu runs (%zu resumed) in %zu rounds, %.3g s -> %s",
            a->scenario_name, rl_ncurves(a), rl_ncurves(a) == 1 ? "" : "s",
            count_status(a, FB_RIDE_LIMIT_FOUND), count_status(a, FB_RIDE_LIMIT_BELOW),
            count_status(a, FB_RIDE_LIMIT_ABOVE), failed, a->ndone, a->nresumed, rounds,
            fb_seconds_since(&t0), a->out_dir);
  if (failed > 0) {
    fb_err_set(&err, FB_ESOLVER,
               "%zu of %zu curves failed (each has its message in the error column of "
               "%s/ride_limit.csv)",
               failed, rl_ncurves(a), a->out_dir);
    return cli_report(FB_ESOLVER, &err);
  }
  return CLI_EXIT_OK;
}

static void rl_args_free(rl_args *a)
{
  for (size_t v = 0; a->values && v < a->nvalues; ++v)
    free(a->values[v]);
  free(a->values);
  free((char *)a->vary_key);
  free(a->vary_path);
  for (size_t i = 0; i < a->ndone; ++i)
    free(a->done[i].error);
  free(a->done);
  for (size_t c = 0; a->curve_error && c < rl_ncurves(a); ++c)
    free(a->curve_error[c]);
  free(a->curve_error);
  free(a->curves);
  fb_scenario_free(&a->base);
}

/* Parses and sets up the study into a; the exit code (go: 0 after --help). */
static int set_up(int argc, char **argv, rl_args *a, int *go)
{
  int rc = parse_args(argc, argv, a, go);
  if (rc == CLI_EXIT_OK && *go) {
    a->curves = calloc(rl_ncurves(a), sizeof *a->curves);
    a->curve_error = calloc(rl_ncurves(a), sizeof *a->curve_error);
    if (!a->curves || !a->curve_error)
      rc = cli_usage_error(argv[0], "out of memory");
  }
  return rc;
}

#ifdef FLEXBOND_MPI
/* The study across the ranks of an MPI job, as sweep's (sweep.c): every
 * rank sets it up, only rank 0 speaking; all go on only if all succeeded
 * on the same scenario file; rank 0 searches and hands the runs out. */
static int ride_limit_mpi(int argc, char **argv, rl_args *a)
{
  int rank = 0, size = 1, go = 0;
  fb_err err;
  int rc = sweep_mpi_init(&rank, &size, &err);
  if (rc != FB_OK)
    return cli_report(rc, &err);
  cli_interrupt_polled_only();
  const int saved = sweep_mpi_silence(rank);
  rc = set_up(argc, argv, a, &go);
  a->quiet = a->quiet || rank != 0;
  a->jobs = 1;
  a->mpi_size = size;
  a->mpi_round = rl_mpi_round;
  char *text = NULL;
  size_t len = 0;
  uint64_t fingerprint = 0;
  if (rc == CLI_EXIT_OK && go && fb_read_file(a->scenario_path, &text, &len, &err) == FB_OK)
    fingerprint = sweep_fnv1a(UINT64_C(14695981039346656037), text, len);
  free(text);
  sweep_mpi_unsilence(saved);
  const int agreed =
      sweep_mpi_agreed(rank, fingerprint, "another scenario file than rank 0", &rc);
  if (agreed && go && rank == 0) {
    rc = ride_limit(a);
    rl_mpi_stop(size);
  } else if (agreed && go) {
    rl_mpi_work(a);
  }
  return sweep_mpi_finish(rc);
}
#endif

int cli_cmd_ride_limit(int argc, char **argv)
{
  rl_args a = {0};
  pthread_mutex_init(&a.lock, NULL);
  int go = 0, rc;
  if (sweep_wants_mpi(argc, argv)) {
#ifdef FLEXBOND_MPI
    rc = ride_limit_mpi(argc, argv, &a);
#else
    rc = cli_usage_error(argv[0], "--mpi: this flexbond was built without MPI (configure with "
                                  "cmake -DFLEXBOND_MPI=ON; docs/cluster.md)");
#endif
  } else {
    rc = set_up(argc, argv, &a, &go);
    if (rc == CLI_EXIT_OK && go)
      rc = ride_limit(&a);
  }
  rl_args_free(&a);
  pthread_mutex_destroy(&a.lock);
  return rc;
}
