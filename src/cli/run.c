/* flexbond run: the vehicle study of Leite & Da Silva ("Modeling and
 * simulation of armored wheeled vehicles with flexible hulls using modular
 * procedures"; data sheet ../shared/reference-vehicle.md). Loads a
 * scenario, simulates it, and only then writes DIR/system1.csv, one PNG
 * per paper figure (Figs. 8-14) and DIR/summary.json, all or nothing.
 *
 * The code handles a list of systems so that System 2 (flexible hull)
 * slots in as a second result: systemN.csv, "systemN" in the summary and
 * a second, dashed curve in every figure. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/io.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "cli.h"

static const char run_usage[] =
    "usage: flexbond run SCENARIO.yaml -o DIR [options]\n"
    "\n"
    "Simulates the vehicle of the scenario (docs/scenario-format.md) over the\n"
    "bump and writes, once the run succeeded:\n"
    "  DIR/system1.csv         t and the seven outputs of the paper, one row per\n"
    "                          sample (header: names only; SI units)\n"
    "  DIR/figNN_OUTPUT.png    the paper's Figs. 8-14, one output each\n"
    "  DIR/summary.json        static value, peak, minimum and RMS over the bump\n"
    "                          of every output, and solver statistics\n"
    "DIR is created if missing; nothing is written if the run fails.\n"
    "\n"
    "options (override the scenario):\n"
    "  -o, --output DIR            output directory (required)\n"
    "  --system rigid|flexible|both  hull model (default rigid: System 1)\n"
    "  --initial zero|static       all states zero with gravity switched on at\n"
    "                              t = 0 (the paper), or static equilibrium\n"
    "  --payload weight-only|lumped  payload as force only (the paper), or\n"
    "                              as mass spread over the load points too\n"
    "  --no-figures                CSV and summary only (no gnuplot)\n"
    "  -q, --quiet                 no progress or summary lines on stderr\n"
    "  -h, --help                  this text\n";

/* The paper's figures of the seven outputs (Leite & Da Silva, section 5,
 * Figs. 8-14). Figs. 12 and 14 show only 4-10 s. */
typedef struct run_figure {
  int number;
  const char *output;   /* fb_vehicle_output_name */
  const char *caption;  /* the paper's caption, the figure's title */
  const char *quantity; /* y axis label, without the unit */
  int crossing_only;    /* 1: the paper's 4-10 s window, 0: the whole run */
} run_figure;

static const run_figure figures[] = {
    {8, "tire_force_LF", "Normal reaction of the left front tire on the road",
     "LF tire normal reaction", 0},
    {9, "spring_defl_RF", "Right front suspension spring vertical deformation",
     "RF suspension spring deformation", 0},
    {10, "torsion", "Hull torsion angle", "hull torsion angle", 0},
    {11, "driver_acc", "Acceleration of the driver plus his seat",
     "driver plus seat acceleration", 0},
    {12, "shock_power_LM", "Power dissipated by the left middle shock absorber",
     "LM shock absorber dissipated power", 1},
    {13, "tire_defl_RM", "Right middle tire vertical deformation", "RM tire deformation", 0},
    {14, "tire_power_LR", "Power dissipated by the left rear tire", "LR tire dissipated power",
     1},
};
_Static_assert(sizeof figures / sizeof figures[0] == FB_NOUTPUTS, "one figure per output");

/* The window of Figs. 12 and 14, s. */
static const double crossing_window[2] = {4.0, 10.0};

/* Values of --system and the systems each asks for. */
enum { MAX_SYSTEMS = 2 };
static const char *const system_choices[] = {"rigid", "flexible", "both"};
static const struct {
  fb_system systems[MAX_SYSTEMS];
  size_t nsystems;
} system_sets[] = {{{FB_SYSTEM_RIGID}, 1},
                   {{FB_SYSTEM_FLEXIBLE}, 1},
                   {{FB_SYSTEM_RIGID, FB_SYSTEM_FLEXIBLE}, 2}};
enum { NSYSTEM_CHOICES = sizeof system_choices / sizeof system_choices[0] };

/* Values of --initial and --payload, indexed by the enums' values. */
static const char *const initial_choices[] = {
    [FB_INITIAL_ZERO] = "zero", [FB_INITIAL_STATIC] = "static"};
static const char *const payload_choices[] = {
    [FB_PAYLOAD_WEIGHT_ONLY] = "weight-only", [FB_PAYLOAD_LUMPED] = "lumped"};

/* Command-line settings; an override is -1 when not given. */
typedef struct run_args {
  const char *scenario_path;
  const char *out_dir;
  int initial; /* fb_initial_state */
  int payload; /* fb_payload_model */
  int quiet;
  int figures; /* 0 with --no-figures */
} run_args;

/* One simulated system and its result. */
typedef struct run_system {
  fb_system sys;
  fb_result *res;
} run_system;

/* What the files are made of. */
typedef struct run_outputs {
  const fb_scenario *scenario;
  const run_system *runs;
  size_t nruns;
  double bump_window[2]; /* first wheel's bump entry, last wheel's exit, s */
  int figures;           /* write the PNG figures */
} run_outputs;

static const char *system_label(fb_system sys)
{
  return sys == FB_SYSTEM_RIGID ? "System 1 (rigid hull)" : "System 2 (flexible hull)";
}

static const char *scenario_name(const fb_scenario *s)
{
  return s->name ? s->name : s->path ? s->path : "scenario";
}

/* Column of output name in r (>= 1), or FB_EINVAL: fb_vehicle_simulate
 * promises every output. */
static int output_column(const fb_result *r, const char *name, size_t *col, fb_err *err)
{
  long j = fb_result_find(r, name);
  if (j < 1)
    return fb_err_set(err, FB_EINVAL, "run: the result has no output '%s'", name);
  *col = (size_t)j;
  return FB_OK;
}

/* ---- Figures. */

/* The plotting window of fig over the run of r: the whole run, or the
 * paper's 4-10 s clipped to it (the whole run if they do not overlap). */
static void figure_window(const run_figure *fig, const fb_result *r, double *t_min,
                          double *t_max)
{
  /* fb_plot_opts: t_min >= t_max means the result's span. */
  *t_min = *t_max = 0;
  size_t n = fb_result_nsamples(r);
  if (!fig->crossing_only || n == 0)
    return;
  double lo = fmax(crossing_window[0], fb_result_row(r, 0)[0]);
  double hi = fmin(crossing_window[1], fb_result_row(r, n - 1)[0]);
  if (lo < hi) {
    *t_min = lo;
    *t_max = hi;
  }
}

/* "Fig. 8. Normal reaction ...: System 1 (rigid hull)" (and " vs System 2
 * (flexible hull)" when overlaid) into buf. */
static void figure_title(const run_figure *fig, const run_outputs *o, char *buf, size_t size)
{
  int n = snprintf(buf, size, "Fig. %d. %s: %s", fig->number, fig->caption,
                   system_label(o->runs[0].sys));
  for (size_t i = 1; i < o->nruns && n > 0 && (size_t)n < size; ++i)
    n += snprintf(buf + n, size - (size_t)n, " vs %s", system_label(o->runs[i].sys));
}

/* DIR/figNN_OUTPUT.png: one panel, a curve per system. */
static int write_figure(cli_outdir *od, const run_figure *fig, const run_outputs *o,
                        fb_err *err)
{
  fb_plot_series series[MAX_SYSTEMS];
  size_t col = 0;
  int rc = FB_OK;
  for (size_t i = 0; i < o->nruns; ++i) {
    rc = output_column(o->runs[i].res, fig->output, &col, err);
    if (rc != FB_OK)
      return rc;
    /* A single curve needs no key: the title names its system. */
    series[i] = (fb_plot_series){.result = o->runs[i].res,
                                 .col = col - 1,
                                 .legend = o->nruns > 1 ? system_label(o->runs[i].sys) : NULL};
  }
  char ylabel[160], title[256], name[96];
  snprintf(ylabel, sizeof ylabel, "%s [%s]", fig->quantity,
           fb_result_col_unit(o->runs[0].res, col));
  figure_title(fig, o, title, sizeof title);
  snprintf(name, sizeof name, "fig%02d_%s.png", fig->number, fig->output);
  const fb_plot_panel panel = {.series = series, .nseries = o->nruns, .ylabel = ylabel};
  fb_plot_opts opts;
  fb_plot_opts_default(&opts);
  opts.title = title;
  opts.panel_height = 460;
  figure_window(fig, o->runs[0].res, &opts.t_min, &opts.t_max);
  char *path = cli_outdir_path(od, name, err);
  if (!path)
    return FB_ENOMEM;
  rc = fb_plot_panels_png(&panel, 1, &opts, path, err);
  if (rc == FB_OK)
    return cli_outdir_keep(od, path, err);
  free(path);
  return rc;
}

/* ---- summary.json, written by hand: strings escaped per RFC 8259
 * section 7, numbers in %.10g, non-finite numbers (which JSON cannot
 * represent) as null. */

static void json_string(FILE *fp, const char *s)
{
  fputc('"', fp);
  for (const unsigned char *c = (const unsigned char *)s; *c; ++c) {
    if (*c == '"' || *c == '\\')
      fprintf(fp, "\\%c", *c);
    else if (*c < 0x20)
      fprintf(fp, "\\u%04x", *c);
    else
      fputc(*c, fp);
  }
  fputc('"', fp);
}

static void json_number(FILE *fp, double v)
{
  if (isfinite(v))
    fprintf(fp, "%.10g", v);
  else
    fputs("null", fp);
}

/* Figures of one output over a run (see the "definitions" of summary.json). */
typedef struct output_summary {
  double static_value, peak, peak_time, min, min_time, rms;
} output_summary;

/* The summary of column col of r per the "definitions" of summary.json,
 * window being the bump window: one pass over the samples. */
static output_summary summarise(const fb_result *r, size_t col, const double window[2])
{
  output_summary o = {NAN, -INFINITY, NAN, INFINITY, NAN, NAN};
  double sum_sq = 0;
  size_t nwindow = 0;
  for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
    const double *row = fb_result_row(r, k);
    double t = row[0], v = row[col];
    if (t < window[0]) {
      o.static_value = v;
      continue;
    }
    /* Comparisons with NaN are false: NaN samples never become extremes. */
    if (v > o.peak) {
      o.peak = v;
      o.peak_time = t;
    }
    if (v < o.min) {
      o.min = v;
      o.min_time = t;
    }
    if (t <= window[1]) {
      sum_sq += v * v;
      ++nwindow;
    }
  }
  if (nwindow > 0)
    o.rms = sqrt(sum_sq / (double)nwindow);
  return o;
}

static void write_output_json(FILE *fp, const fb_result *r, size_t col, const double window[2])
{
  output_summary o = summarise(r, col, window);
  const struct {
    const char *key;
    double value;
  } fields[] = {
      {"static", o.static_value}, {"peak", o.peak},        {"min", o.min}, {"rms", o.rms},
      {"peak_time", o.peak_time}, {"min_time", o.min_time}};
  fputs("{\"unit\": ", fp);
  json_string(fp, fb_result_col_unit(r, col));
  for (size_t i = 0; i < sizeof fields / sizeof fields[0]; ++i) {
    fprintf(fp, ", \"%s\": ", fields[i].key);
    json_number(fp, fields[i].value);
  }
  fputc('}', fp);
}

static void write_solver_json(FILE *fp, const fb_sim_stats *s)
{
  fprintf(fp,
          "{\"steps\": %ld, \"rhs_evals\": %ld, \"newton_setups\": %ld, "
          "\"factorizations\": %ld, \"newton_iters\": %ld, \"err_test_fails\": %ld, "
          "\"wall_seconds\": ",
          s->steps, s->rhs_evals, s->newton_setups, s->factorizations, s->newton_iters,
          s->err_test_fails);
  json_number(fp, s->wall_seconds);
  fputc('}', fp);
}

/* "systemN": {...} of one run. Outputs missing from the result were
 * caught by write_figure before summary.json is written. */
static void write_system_json(FILE *fp, const run_system *run, const double window[2])
{
  fprintf(fp, ",\n  \"system%d\": {\n    \"label\": ", (int)run->sys);
  json_string(fp, system_label(run->sys));
  fputs(",\n    \"outputs\": {", fp);
  for (size_t k = 0; k < FB_NOUTPUTS; ++k) {
    const char *name = figures[k].output;
    fputs(k ? ",\n      " : "\n      ", fp);
    json_string(fp, name);
    fputs(": ", fp);
    write_output_json(fp, run->res, (size_t)fb_result_find(run->res, name), window);
  }
  fputs("\n    },\n    \"solver\": ", fp);
  write_solver_json(fp, fb_result_stats(run->res));
  fputs(",\n    \"bump_window\": [", fp);
  json_number(fp, window[0]);
  fputs(", ", fp);
  json_number(fp, window[1]);
  fputs("]\n  }", fp);
}

static const char *const definitions[][2] = {
    {"static", "value at the last sample before bump_window[0] (the first wheel meets the "
               "bump); null if the run starts on the bump"},
    {"peak", "largest value from bump_window[0] to the end of the run: the response to the "
             "bump, without the settling after t = 0"},
    {"peak_time", "time of peak (its first occurrence), s"},
    {"min", "smallest value from bump_window[0] to the end of the run"},
    {"min_time", "time of min (its first occurrence), s"},
    {"rms", "root mean square of the samples with t in bump_window (of the value itself, "
            "not of its deviation from static)"},
    {"bump_window", "[first wheel's bump entry, last wheel's bump exit], s"},
    {"solver", "CVODE statistics of the run; wall_seconds is the integration's wall time"},
    {"units", "SI, as the \"unit\" of each output; null stands for a non-finite value"},
};

/* summary.json (a cli_writer over a run_outputs). */
static void write_summary_json(FILE *fp, const void *ctx)
{
  const run_outputs *o = ctx;
  const fb_scenario *s = o->scenario;
  fputs("{\n  \"scenario\": ", fp);
  json_string(fp, scenario_name(s));
  fputs(",\n  \"initial\": ", fp);
  json_string(fp, initial_choices[s->initial]);
  fputs(",\n  \"payload\": ", fp);
  json_string(fp, payload_choices[s->payload]);
  fputs(",\n  \"definitions\": {", fp);
  for (size_t i = 0; i < sizeof definitions / sizeof definitions[0]; ++i) {
    fputs(i ? ",\n    " : "\n    ", fp);
    json_string(fp, definitions[i][0]);
    fputs(": ", fp);
    json_string(fp, definitions[i][1]);
  }
  fputs("\n  }", fp);
  for (size_t i = 0; i < o->nruns; ++i)
    write_system_json(fp, &o->runs[i], o->bump_window);
  fputs("\n}\n", fp);
}

/* systemN.csv (a cli_writer over a run_system). */
static void write_system_csv(FILE *fp, const void *ctx)
{
  const run_system *run = ctx;
  fb_result_print_csv(fp, run->res, FB_CSV_HEADER_NAMES);
}

/* Creates dir if needed and writes every file into it, all or nothing.
 * The figures go first: they are the likeliest to fail (gnuplot). */
static int write_outputs(const char *dir, const run_outputs *o, fb_err *err)
{
  cli_outdir od;
  int rc = cli_outdir_open(&od, dir, err);
  for (size_t k = 0; o->figures && k < FB_NOUTPUTS && rc == FB_OK; ++k)
    rc = write_figure(&od, &figures[k], o, err);
  for (size_t i = 0; i < o->nruns && rc == FB_OK; ++i) {
    char name[32];
    snprintf(name, sizeof name, "system%d.csv", (int)o->runs[i].sys);
    rc = cli_outdir_write(&od, name, write_system_csv, &o->runs[i], err);
  }
  if (rc == FB_OK)
    rc = cli_outdir_write(&od, "summary.json", write_summary_json, o, err);
  return cli_outdir_close(&od, rc);
}

/* [first wheel's bump entry, last wheel's bump exit]. */
static void bump_window(const fb_scenario *s, double window[2])
{
  window[0] = INFINITY;
  window[1] = -INFINITY;
  for (int c = 0; c < FB_NCORNERS; ++c) {
    window[0] = fmin(window[0], fb_scenario_bump_entry(s, c));
    window[1] = fmax(window[1], fb_scenario_bump_exit(s, c));
  }
}

static int simulate(const run_args *a, const fb_scenario *s, run_system *run, fb_err *err)
{
  if (!a->quiet)
    fprintf(stderr, "flexbond run: %s: simulating %s, t = 0..%g s ...\n", scenario_name(s),
            system_label(run->sys), s->t_end);
  int rc = fb_vehicle_simulate(s, run->sys, &run->res, err);
  if (rc == FB_OK && !a->quiet) {
    const fb_sim_stats *st = fb_result_stats(run->res);
    fprintf(stderr, "flexbond run: %s: %s: %zu samples, %ld steps, %ld rhs evals, %.3g s\n",
            scenario_name(s), system_label(run->sys), fb_result_nsamples(run->res), st->steps,
            st->rhs_evals, st->wall_seconds);
  }
  return rc;
}

static int run(const run_args *a, const fb_system *systems, size_t nsystems)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  run_system runs[MAX_SYSTEMS] = {{0}};
  int rc = fb_scenario_load(a->scenario_path, &s, &err);
  if (rc == FB_OK) {
    if (a->initial >= 0)
      s->initial = (fb_initial_state)a->initial;
    if (a->payload >= 0)
      s->payload = (fb_payload_model)a->payload;
  }
  for (size_t i = 0; i < nsystems && rc == FB_OK; ++i) {
    runs[i].sys = systems[i];
    rc = simulate(a, s, &runs[i], &err);
  }
  if (rc == FB_OK) {
    run_outputs o = {.scenario = s, .runs = runs, .nruns = nsystems, .figures = a->figures};
    bump_window(s, o.bump_window);
    rc = write_outputs(a->out_dir, &o, &err);
  }
  if (rc == FB_OK && !a->quiet)
    fprintf(stderr, "flexbond run: %s: wrote %zu files -> %s\n", scenario_name(s),
            (a->figures ? FB_NOUTPUTS : 0) + nsystems + 1, a->out_dir);
  for (size_t i = 0; i < nsystems; ++i)
    fb_result_free(&runs[i].res);
  fb_scenario_free(&s);
  return cli_report(rc, &err);
}

/* The systems --system asks for (rigid when absent). A usage error for
 * System 2 while the flexible hull does not exist. */
static int parse_systems(const char *cmd, const char *text, fb_system *systems,
                         size_t *nsystems)
{
  int choice = 0;
  int rc = text ? cli_choice(cmd, "--system", text, system_choices, NSYSTEM_CHOICES, &choice)
                : CLI_EXIT_OK;
  *nsystems = 0;
  for (size_t i = 0; rc == CLI_EXIT_OK && i < system_sets[choice].nsystems; ++i) {
    systems[i] = system_sets[choice].systems[i];
    if (systems[i] == FB_SYSTEM_FLEXIBLE)
      rc = cli_usage_error(cmd, "System 2 (flexible hull) is not available yet");
  }
  if (rc == CLI_EXIT_OK)
    *nsystems = system_sets[choice].nsystems;
  return rc;
}

int cli_cmd_run(int argc, char **argv)
{
  enum {
    OPT_OUT,
    OPT_SYSTEM,
    OPT_INITIAL,
    OPT_PAYLOAD,
    OPT_NO_FIGURES,
    OPT_QUIET,
    OPT_HELP,
    NOPTS
  };
  cli_option opts[NOPTS] = {
      [OPT_OUT] = {"--output", "-o", 1, NULL},
      [OPT_SYSTEM] = {"--system", NULL, 1, NULL},
      [OPT_INITIAL] = {"--initial", NULL, 1, NULL},
      [OPT_PAYLOAD] = {"--payload", NULL, 1, NULL},
      [OPT_NO_FIGURES] = {"--no-figures", NULL, 0, NULL},
      [OPT_QUIET] = {"--quiet", "-q", 0, NULL},
      [OPT_HELP] = {"--help", "-h", 0, NULL},
  };
  run_args a = {.initial = -1, .payload = -1};
  int rc;
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, run_usage, "SCENARIO", &a.scenario_path,
                              &rc))
    return rc;
  a.out_dir = opts[OPT_OUT].value;
  if (!a.out_dir || !*a.out_dir)
    return cli_usage_error(argv[0], "missing output directory (-o DIR)");
  a.quiet = opts[OPT_QUIET].value != NULL;
  a.figures = opts[OPT_NO_FIGURES].value == NULL;
  fb_system systems[MAX_SYSTEMS];
  size_t nsystems = 0;
  rc = parse_systems(argv[0], opts[OPT_SYSTEM].value, systems, &nsystems);
  if (rc == CLI_EXIT_OK && opts[OPT_INITIAL].value)
    rc = cli_choice(argv[0], "--initial", opts[OPT_INITIAL].value, initial_choices,
                    sizeof initial_choices / sizeof initial_choices[0], &a.initial);
  if (rc == CLI_EXIT_OK && opts[OPT_PAYLOAD].value)
    rc = cli_choice(argv[0], "--payload", opts[OPT_PAYLOAD].value, payload_choices,
                    sizeof payload_choices / sizeof payload_choices[0], &a.payload);
  return rc == CLI_EXIT_OK ? run(&a, systems, nsystems) : rc;
}
