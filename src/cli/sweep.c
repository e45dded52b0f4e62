/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond sweep: a parameter study of a vehicle scenario (docs/sweep.md).
 * Every --set KEY=SPEC gives a key of the scenario file and its values;
 * the cases are their cartesian product. The study layer runs them
 * (fb_study_sweep: each case loaded through sweep_case.c, simulated and
 * measured, on a pool of threads) or, with --mpi in an MPI build, rank 0
 * hands them to the ranks (sweep_mpi.c). A case that fails leaves its
 * message in the `error` column and the others go on. Every finished
 * case is journaled in DIR/sweep.partial.csv (sweep_journal.c), which
 * --resume reads back after a kill; DIR/sweep.csv and DIR/sweep.png are
 * written at the end, all or nothing, and the journal is then removed. */
#include "sweep.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "flexbond/io.h"
#include "flexbond/vehicle.h"

#include "../core/textfile.h"
#include "../core/util.h"
#include "cli.h"

static const char sweep_usage[] =
    "usage: flexbond sweep SCENARIO.yaml --set KEY=SPEC [--set KEY=SPEC ...] -o DIR\n"
    "                      [--system rigid|flexible] [-j N] [--resume] [--mpi]\n"
    "                      [--plot METRIC ...] [--no-figures] [--plain-header] [-q]\n"
    "\n"
    "Simulates the scenario once per combination of the values given by the\n"
    "--set options (their cartesian product, the first key varying slowest) and\n"
    "writes, once every case has run (docs/sweep.md):\n"
    "  DIR/sweep.csv   one row per case: the keys' values, then the metrics (peak,\n"
    "                  min and RMS of the scenario's outputs as in summary.json,\n"
    "                  the smallest tire reaction, the contact-loss intervals, a\n"
    "                  mount's ride metrics, the solver's steps; every number\n"
    "                  to the last bit) and an `error` column\n"
    "  DIR/sweep.png   a panel per plotted metric (--plot) against the first key,\n"
    "                  a curve per combination of the other keys\n"
    "A case that fails does not stop the others; the exit status is then 4.\n"
    "Finished cases are kept in DIR/sweep.partial.csv until the end, so that a\n"
    "killed or interrupted sweep can be resumed.\n"
    "\n"
    "  --set KEY=SPEC   KEY: a dotted path into the scenario, written in the file\n"
    "                   or not (road.speed_kmh, suspensions.axles[0].spring_k,\n"
    "                   hull.mesh.generator.bulkheads[1], simulation.max_step)\n"
    "                   or a key name that names one key (speed_kmh);\n"
    "                   SPEC: start:step:stop (stop included, to step/1e9; at most\n"
    "                   10000 values) or a list v1,v2,... (numbers, expressions or\n"
    "                   words such as zero,static); numbers in decimal digits;\n"
    "                   repeat for a grid of at most 100000 cases\n"
    "  -o, --output DIR           output directory (required)\n"
    "  --system rigid|flexible    hull model (default rigid: System 1)\n"
    "  -j, --jobs N               cases run at once (default: the online CPUs)\n"
    "  --resume                   run only the cases DIR/sweep.partial.csv lacks\n"
    "  --mpi                      run across the ranks of an MPI job, one case per\n"
    "                             rank at a time (mpirun -np N flexbond sweep --mpi\n"
    "                             ...; an MPI build only, docs/cluster.md)\n"
    "  --plot METRIC              a panel of sweep.png; repeat for more (at most 16).\n"
    "                             METRIC: OUTPUT[:STAT], an output of the scenario\n"
    "                             and peak (default), min or rms (tire_force_LF:min),\n"
    "                             or a column of sweep.csv (min_tire_force,\n"
    "                             ride_a_w_rms, contact_loss_intervals, solver_steps).\n"
    "                             Default: the first output's peak, min_tire_force,\n"
    "                             ride_a_w_rms (with a mounted body's acceleration\n"
    "                             among the outputs) and contact_loss_intervals\n"
    "  --no-figures               no sweep.png\n"
    "  --plain-header             sweep.csv's header of names only, without the\n"
    "                             metrics' units ('tire_force_LF_peak [N]')\n"
    "  -q, --quiet                no progress lines on stderr\n"
    "  --strict                   refuse implausible values (the scenario's, a case's)\n"
    "  -h, --help                 this text\n";

/* Most threads -j accepts. */
enum { SWEEP_MAX_JOBS = 1024 };

/* ---- Output files. */

/* sweep.csv (a cli_writer over the sweep_args): the rows in grid
 * order, whichever order the cases finished in. */
static void write_csv(FILE *fp, const void *ctx)
{
  const sweep_args *a = ctx;
  sweep_csv_header(fp, a, a->header);
  for (size_t i = 0; i < a->ncases; ++i)
    sweep_csv_row(fp, a, i);
}

/* The figure's arrays: x per value of the first key, y per metric,
 * curve (combination of the other keys) and value, the curves, the
 * panels and the legends. */
typedef struct sweep_figure {
  double *x, *y;
  fb_plot_xy_series *series;
  fb_plot_xy_panel panels[SWEEP_MAX_PLOTS];
  char (*legends)[256];
  char (*ylabels)[FB_ERR_KEY_MAX + 32];
  int categorical; /* the first key's values are not all numbers */
} sweep_figure;

static void sweep_figure_free(sweep_figure *f)
{
  free(f->x);
  free(f->y);
  free(f->series);
  free(f->legends);
  free(f->ylabels);
}

/* Fills f from the cases; FB_ENOMEM. */
static int build_figure(const sweep_args *a, sweep_figure *f, fb_err *err)
{
  const size_t nx = a->keys[0].nvalues, ncurves = a->ncases / nx;
  f->x = malloc(nx * sizeof *f->x);
  f->y = malloc(a->nplots * a->ncases * sizeof *f->y);
  f->series = malloc(a->nplots * ncurves * sizeof *f->series);
  f->legends = malloc(ncurves * sizeof *f->legends);
  f->ylabels = malloc(a->nplots * sizeof *f->ylabels);
  if (!f->x || !f->y || !f->series || !f->legends || !f->ylabels)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the figure of %zu cases", a->ncases);
  f->categorical = 0;
  for (size_t v = 0; v < nx; ++v)
    f->categorical |= !sweep_numeric_value(a->keys[0].values[v], &f->x[v]);
  for (size_t v = 0; f->categorical && v < nx; ++v)
    f->x[v] = (double)v;
  for (size_t r = 0; r < ncurves; ++r)
    /* Case r of the first value: the other keys' values of curve r. */
    sweep_case_label(a, r, 1, f->legends[r], sizeof f->legends[r]);
  for (size_t m = 0; m < a->nplots; ++m) {
    char name[FB_ERR_KEY_MAX];
    fb_study_sweep_metric_name(a->study, a->plot[m], name, sizeof name);
    snprintf(f->ylabels[m], sizeof f->ylabels[m], "%s", name);
    for (size_t r = 0; r < ncurves; ++r) {
      double *y = &f->y[(m * ncurves + r) * nx];
      for (size_t v = 0; v < nx; ++v) {
        fb_study_sweep_case c;
        fb_study_sweep_case_get(a->study, v * ncurves + r, &c);
        y[v] = c.metric[a->plot[m]];
      }
      /* The key once, in the first panel; none for a single curve. */
      f->series[m * ncurves + r] = (fb_plot_xy_series){
          .x = f->x, .y = y, .n = nx, .legend = m == 0 && ncurves > 1 ? f->legends[r] : NULL};
    }
    f->panels[m] = (fb_plot_xy_panel){.series = &f->series[m * ncurves],
                                      .nseries = ncurves,
                                      .ylabel = f->ylabels[m],
                                      .unit = fb_study_sweep_metric_unit(a->study, a->plot[m])};
  }
  return FB_OK;
}

/* DIR/sweep.png: every metric against the first key. */
static int write_figure(cli_outdir *od, const sweep_args *a, fb_err *err)
{
  sweep_figure f = {0};
  char title[512];
  snprintf(title, sizeof title, "flexbond sweep: %s, %s, %zu cases", a->scenario_name,
           cli_system_label(a->sys), a->ncases);
  int rc = build_figure(a, &f, err);
  char *path = rc == FB_OK ? cli_outdir_path(od, "sweep.png", err) : NULL;
  if (rc == FB_OK && !path)
    rc = err->code; /* out of memory, or no staging directory */
  if (rc == FB_OK) {
    fb_plot_xy_opts opts;
    fb_plot_xy_opts_default(&opts);
    opts.title = title;
    char xlabel[FB_ERR_KEY_MAX + 64];
    sweep_key_label(a, 0, xlabel, sizeof xlabel);
    opts.xlabel = xlabel;
    opts.xtic_labels = f.categorical ? (const char *const *)a->keys[0].values : NULL;
    opts.nxtics = f.categorical ? a->keys[0].nvalues : 0;
    /* A few panels, larger: the figure stays about 1100 pixels wide. */
    if (a->nplots <= 4) {
      opts.panel_width = 560;
      opts.panel_height = 380;
    }
    rc = fb_plot_xy_png(f.panels, a->nplots, &opts, path, err);
    if (rc == FB_OK) {
      rc = cli_outdir_keep(od, path, err);
      path = NULL;
    }
  }
  free(path);
  sweep_figure_free(&f);
  return rc;
}

/* The figure first (gnuplot is the likelier failure), then the CSV, into
 * od (the output directory the sweep holds for its whole run). */
static int write_outputs(cli_outdir *od, const sweep_args *a, fb_err *err)
{
  int rc = FB_OK;
  if (a->figures)
    rc = write_figure(od, a, err);
  if (rc == FB_OK)
    rc = cli_outdir_write(od, "sweep.csv", write_csv, a, err);
  return rc;
}

/* ---- The command line. */

/* Appends value text to key k (copied). */
static int add_value(sweep_key *k, const char *text, size_t len)
{
  char **values = realloc(k->values, (k->nvalues + 1) * sizeof *values);
  if (!values)
    return 0;
  k->values = values;
  k->values[k->nvalues] = malloc(len + 1);
  if (!k->values[k->nvalues])
    return 0;
  memcpy(k->values[k->nvalues], text, len);
  k->values[k->nvalues++][len] = '\0';
  return 1;
}

static void sweep_key_free(sweep_key *k)
{
  for (size_t v = 0; v < k->nvalues; ++v)
    free(k->values[v]);
  free(k->values);
  free(k->path);
}

/* The refusal of a number of a spec: one message for every kind (not a
 * number, hexadecimal, inf, nan, beyond a double), as the other numeric
 * options give (cli_positive_number). */
static int spec_number_error(const char *cmd, const char *set, const char *text)
{
  return cli_usage_error(cmd,
                         "--set %s: '%s' is not a finite number in decimal digits (as 16, 0.5 "
                         "or 1e-3; hexadecimal, inf and nan are not read)",
                         set, text);
}

/* A finite decimal number, the whole text (sweep_numeric_value: as the
 * data files and the other options read numbers). */
static int spec_number(const char *cmd, const char *set, const char *text, double *out)
{
  if (sweep_numeric_value(text, out))
    return CLI_EXIT_OK;
  return spec_number_error(cmd, set, text);
}

/* 1 if a list value is meant as a number: strtod reads all of it ("0x10",
 * "inf", "nan(1)", "1e999" too), or it is one of YAML's special floats
 * (".inf", "-.Inf", ".NaN"). Anything else is an expression or a word,
 * which the scenario reader judges. */
static int looks_numeric(const char *text)
{
  char *end = NULL;
  (void)strtod(text, &end);
  if (end != text && *end == '\0')
    return 1;
  const char *t = text + (*text == '+' || *text == '-');
  return t[0] == '.' && (!strcasecmp(t + 1, "inf") || !strcasecmp(t + 1, "nan"));
}

/* start:step:stop: start + i step for i = 0, 1, ... while it does not
 * pass stop by more than step/1e9 (so 0.1:0.1:0.3 includes 0.3 despite
 * rounding). Each value is printed to 15 significant digits, which
 * removes that rounding (0.30000000000000004 becomes 0.3) and keeps
 * every decimal the user typed. */
static int parse_range(const char *cmd, const char *set, char *spec, sweep_key *k)
{
  char *parts[3] = {spec, NULL, NULL};
  parts[1] = strchr(spec, ':');
  parts[2] = parts[1] ? strchr(parts[1] + 1, ':') : NULL;
  if (!parts[2] || strchr(parts[2] + 1, ':'))
    return cli_usage_error(cmd, "--set %s: a range is start:step:stop", set);
  *parts[1]++ = '\0';
  *parts[2]++ = '\0';
  double v[3];
  for (int i = 0; i < 3; ++i) {
    int rc = spec_number(cmd, set, parts[i], &v[i]);
    if (rc != CLI_EXIT_OK)
      return rc;
  }
  const double start = v[0], step = v[1], stop = v[2];
  const double steps = step != 0 ? (stop - start) / step : -1;
  if (!(steps >= -1e-9))
    return cli_usage_error(cmd, "--set %s: step %g does not lead from %g to %g", set, step,
                           start, stop);
  if (!(steps + 1e-9 < SWEEP_MAX_VALUES))
    return cli_usage_error(cmd, "--set %s: more than %d values", set, SWEEP_MAX_VALUES);
  const size_t n = (size_t)floor(steps + 1e-9) + 1;
  for (size_t i = 0; i < n; ++i) {
    double x = start + (double)i * step;
    /* A sum that should be 0 (-0.1 + 0.1) prints as 0, not 1.4e-17. */
    if (fabs(x) < 1e-9 * fabs(step))
      x = 0;
    char text[32];
    snprintf(text, sizeof text, "%.15g", x + 0.0);
    if (!add_value(k, text, strlen(text)))
      return cli_usage_error(cmd, "out of memory");
  }
  return CLI_EXIT_OK;
}

/* v1,v2,...: each value's text, spaces around it removed. */
static int parse_list(const char *cmd, const char *set, const char *spec, sweep_key *k)
{
  const char *p = spec;
  for (;;) {
    size_t len = strcspn(p, ",");
    const char *item = p;
    while (len > 0 && *item == ' ') {
      ++item;
      --len;
    }
    while (len > 0 && item[len - 1] == ' ')
      --len;
    if (len == 0)
      return cli_usage_error(cmd, "--set %s: empty value in the list", set);
    if (k->nvalues == SWEEP_MAX_VALUES)
      return cli_usage_error(cmd, "--set %s: more than %d values", set, SWEEP_MAX_VALUES);
    if (!add_value(k, item, len))
      return cli_usage_error(cmd, "out of memory");
    /* A number is read as a range's are: a hexadecimal or infinite one
     * is refused here, for the whole study, not by each of its cases. */
    double x;
    const char *value = k->values[k->nvalues - 1];
    if (looks_numeric(value) && !sweep_numeric_value(value, &x))
      return spec_number_error(cmd, set, value);
    p = item + len;
    p += strspn(p, " ");
    if (*p == '\0')
      return CLI_EXIT_OK;
    ++p; /* the comma */
  }
}

/* Offset of the first control character of text, as the scenario
 * reader refuses them in one-line text (fb_text_find_control: tab and
 * line breaks included), with its code point in *c; strlen(text) if
 * none. */
static size_t find_control(const char *text, unsigned *c)
{
  return fb_text_find_control(text, strlen(text), 0, c);
}

/* A --set option with a control character in its key or values is a
 * usage error, for the whole study: a line break in a value would end
 * its scalar in the scenario's text, and the key and values go into
 * sweep.csv, the journal and the messages, each one line. */
static int check_controls(const char *cmd, const char *set)
{
  unsigned c = 0;
  const size_t at = find_control(set, &c);
  if (!set[at])
    return CLI_EXIT_OK;
  const char *eq = strchr(set, '=');
  const char *what = c == '\n'   ? "a line break"
                     : c == '\r' ? "a carriage return"
                     : c == '\t' ? "a tab"
                                 : "a control character";
  char one[3] = {set[at], '\0', '\0'};
  if (c >= 0x80) /* a C1 control: two bytes of UTF-8 */
    one[1] = set[at + 1];
  /* The message shows both escaped, as every message (fb_err_escape). */
  return cli_usage_error(cmd,
                         "--set %s: the %s has %s (%s, U+%04X) at byte %zu of the option; keys "
                         "and values are one line of printable text",
                         set, eq && set + at > eq ? "value" : "key", what, one, c, at + 1);
}

/* KEY=SPEC of one --set into k (k->key points into set). */
static int parse_set(const char *cmd, char *set, sweep_key *k)
{
  const int controls = check_controls(cmd, set);
  if (controls != CLI_EXIT_OK)
    return controls;
  char *eq = strchr(set, '=');
  if (!eq || eq == set || eq[1] == '\0')
    return cli_usage_error(cmd, "--set needs KEY=SPEC (got '%s')", set);
  /* Messages name the whole option: copy the spec before splitting. */
  char spec[1024];
  if (strlen(eq + 1) >= sizeof spec)
    return cli_usage_error(cmd, "--set %s: the spec is too long", set);
  snprintf(spec, sizeof spec, "%s", eq + 1);
  int rc = strchr(spec, ':') ? parse_range(cmd, set, spec, k) : parse_list(cmd, set, spec, k);
  *eq = '\0';
  k->key = set;
  return rc;
}

/* Takes the --set options out of argv (they repeat, which cli_parse
 * does not keep) into sets; the other arguments go to rest. Options
 * that take a value are skipped with it, so a value is never read as an
 * option. */
/* The value of the repeatable option name ("--set") at argv[*i], as
 * "--set V" or "--set=V", appended to values; 0 if argv[*i] is not it, 1
 * if it is, -1 if its value is missing. */
static int take_repeated(int argc, char **argv, int *i, const char *name, char **values,
                         size_t *n)
{
  const size_t len = strlen(name);
  if (!strncmp(argv[*i], name, len) && argv[*i][len] == '=') {
    values[(*n)++] = argv[*i] + len + 1;
    return 1;
  }
  if (strcmp(argv[*i], name) != 0)
    return 0;
  /* No key or metric starts with '-': "--plot -o DIR" lacks its value. */
  if (*i + 1 == argc || argv[*i + 1][0] == '-')
    return -1;
  values[(*n)++] = argv[++*i];
  return 1;
}

/* Takes the repeatable --set and --plot options out of argv. */
static int split_sets(int argc, char **argv, char **rest, int *nrest, char **sets,
                      size_t *nsets, char **plots, size_t *nplots)
{
  static const char *const with_value[] = {"-o", "--output", "--system", "-j", "--jobs"};
  *nrest = 0;
  *nsets = *nplots = 0;
  int i = 0;
  for (; i < argc && strcmp(argv[i], "--") != 0; ++i) {
    const int set = take_repeated(argc, argv, &i, "--set", sets, nsets);
    const int plot = set ? 0 : take_repeated(argc, argv, &i, "--plot", plots, nplots);
    if (set < 0)
      return cli_usage_error(argv[0], "option '--set' needs a value (KEY=SPEC)");
    if (plot < 0)
      return cli_usage_error(argv[0], "option '--plot' needs a value (METRIC)");
    if (set || plot)
      continue;
    rest[(*nrest)++] = argv[i];
    for (size_t o = 0; o < sizeof with_value / sizeof with_value[0]; ++o)
      if (!strcmp(argv[i], with_value[o]) && i + 1 < argc) {
        rest[(*nrest)++] = argv[++i];
        break;
      }
  }
  for (; i < argc; ++i)
    rest[(*nrest)++] = argv[i];
  return CLI_EXIT_OK;
}

/* -j N: 1 .. SWEEP_MAX_JOBS; default: the online CPUs. */
int sweep_parse_jobs(const char *cmd, const char *text, size_t *jobs)
{
  if (!text) {
    const long n = sysconf(_SC_NPROCESSORS_ONLN);
    *jobs = n > 0 ? (size_t)n : 1;
    return CLI_EXIT_OK;
  }
  char *end = NULL;
  errno = 0;
  const long n = strtol(text, &end, 10);
  if (end == text || *end != '\0' || errno == ERANGE || n < 1 || n > SWEEP_MAX_JOBS)
    return cli_usage_error(cmd, "option '-j' needs an integer in 1..%d (got '%s')",
                           SWEEP_MAX_JOBS, text);
  *jobs = (size_t)n;
  return CLI_EXIT_OK;
}

/* The cases of the keys in a->ncases: their product, refused (a usage
 * error naming each key's count) above SWEEP_MAX_CASES before anything
 * is allocated for them; sweep.h says why the bound is what it is. The
 * product is formed in a double, which holds 16 keys of SWEEP_MAX_VALUES
 * values (1e64) where a size_t would wrap. */
static int count_cases(const char *cmd, sweep_args *a)
{
  double cases = 1;
  char sizes[1024] = "";
  size_t len = 0;
  for (size_t k = 0; k < a->nkeys; ++k) {
    cases *= (double)a->keys[k].nvalues;
    if (len < sizeof sizes)
      len += (size_t)snprintf(sizes + len, sizeof sizes - len, "%s%s: %zu value%s",
                              k ? " x " : "", a->keys[k].key, a->keys[k].nvalues,
                              a->keys[k].nvalues == 1 ? "" : "s");
  }
  if (cases > SWEEP_MAX_CASES)
    return cli_usage_error(cmd,
                           "the --set options give %.*g cases (%s), more than the %d a "
                           "study may have (docs/sweep.md, \"Limits\"): sweep fewer values, "
                           "or split the study into several",
                           cases < 1e15 ? 15 : 3, cases, sizes, SWEEP_MAX_CASES);
  a->ncases = (size_t)cases;
  return CLI_EXIT_OK;
}

/* Parses every --set into a->keys and counts the cases. */
static int parse_keys(const char *cmd, char **sets, size_t nsets, sweep_args *a)
{
  if (nsets == 0)
    return cli_usage_error(cmd, "nothing to sweep: give at least one --set KEY=SPEC");
  if (nsets > SWEEP_MAX_KEYS)
    return cli_usage_error(cmd, "at most %d --set options", SWEEP_MAX_KEYS);
  for (size_t k = 0; k < nsets; ++k) {
    a->nkeys = k + 1;
    int rc = parse_set(cmd, sets[k], &a->keys[k]);
    if (rc != CLI_EXIT_OK)
      return rc;
  }
  return count_cases(cmd, a);
}

/* Each key names one replaceable value of the scenario, and no two keys
 * the same one: usage errors naming the candidates otherwise. */
static int resolve_keys(const char *cmd, sweep_args *a)
{
  fb_err err;
  for (size_t k = 0; k < a->nkeys; ++k) {
    int rc = fb_scenario_override_key(a->scenario_path, a->keys[k].key, &a->keys[k].path, &err);
    if (rc == FB_EINVAL)
      return cli_usage_error(cmd, "--set %s: %s", a->keys[k].key, err.msg);
    if (rc != FB_OK)
      return cli_report(rc, &err);
    for (size_t j = 0; j < k; ++j)
      if (!strcmp(a->keys[j].path, a->keys[k].path))
        return cli_usage_error(cmd, "--set %s and --set %s both set %s", a->keys[j].key,
                               a->keys[k].key, a->keys[k].path);
  }
  return CLI_EXIT_OK;
}

/* The scenario as it is must load (an input error otherwise), and have a
 * finite-element hull for --system flexible. */
static int check_scenario(const char *cmd, sweep_args *a, char **name)
{
  fb_err err;
  fb_scenario *s = NULL;
  int rc = cli_scenario_load(a->scenario_path, a->strict, &s, &err);
  if (rc != FB_OK)
    return cli_report(rc, &err);
  int exit_code = CLI_EXIT_OK;
  if (a->sys == FB_SYSTEM_FLEXIBLE && !s->has_fe_hull)
    exit_code = cli_usage_error(cmd, "--system flexible: the scenario has no finite-element "
                                     "hull (hull.mesh and hull.fe)");
  if (exit_code == CLI_EXIT_OK && s->noutputs > SWEEP_MAX_OUTPUTS)
    exit_code = cli_usage_error(cmd,
                                "the scenario lists %zu outputs; a sweep takes at most %d "
                                "(each adds three columns to every case)",
                                s->noutputs, SWEEP_MAX_OUTPUTS);
  const char *n = cli_scenario_name(s);
  *name = malloc(strlen(n) + 1);
  if (*name)
    memcpy(*name, n, strlen(n) + 1);
  a->scenario_name = *name ? *name : "scenario";
  /* Kept to the end (cli_cmd_sweep frees it): its outputs name the metrics. */
  a->base = s;
  return exit_code;
}

/* Counts what the run left: cases not done, failed, and failed on an
 * input none of their values touches. */
static void tally(const sweep_args *a, size_t *not_done, size_t *failed, size_t *input_errors)
{
  *not_done = *failed = *input_errors = 0;
  for (size_t i = 0; i < a->ncases; ++i) {
    fb_study_sweep_case c;
    const int done = fb_study_sweep_case_get(a->study, i, &c);
    *not_done += !done;
    *failed += done && c.status != FB_OK;
    /* An input error at a swept value belongs to its case. */
    const int code = cli_exit_code(c.status);
    *input_errors += done && !c.at_value && (code == CLI_EXIT_INPUT || code == CLI_EXIT_IO);
  }
}

/* The first case's message, or the first failed one's with failed. */
static size_t first_case(const sweep_args *a, int failed, fb_study_sweep_case *c)
{
  size_t i = 0;
  while (failed && i + 1 < a->ncases &&
         !(fb_study_sweep_case_get(a->study, i, c) && c->status != FB_OK))
    ++i;
  fb_study_sweep_case_get(a->study, i, c);
  return i;
}

/* Runs the cases not done, on threads or (mpi_size > 0) across ranks;
 * the status of the study as a whole. */
static int run_cases(const sweep_args *a, int mpi_size, double *seconds, fb_err *err)
{
  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
#ifdef FLEXBOND_MPI
  int rc = mpi_size > 0 ? sweep_mpi_coordinate(a, mpi_size, err)
                        : fb_study_sweep_run(a->study, a->jobs, err);
#else
  (void)mpi_size; /* 0: there are no ranks */
  int rc = fb_study_sweep_run(a->study, a->jobs, err);
#endif
  *seconds = fb_seconds_since(&t0);
  size_t not_done, failed, input_errors;
  tally(a, &not_done, &failed, &input_errors);
  /* Stopped by an interruption: the command's words for it. */
  if (rc == FB_OK || rc == FB_EINTR)
    rc = cli_check_interrupt(err);
  /* Cases left over without an interruption here: one on another rank. */
  if (rc == FB_OK && not_done > 0)
    rc = fb_err_set(err, FB_EINTR, "%zu case%s did not run (a rank was interrupted)", not_done,
                    not_done == 1 ? "" : "s");
  /* Every case refused for an input none of its values touches (a bad
   * deck all cases share, say): the study is at fault, not its cases. */
  fb_study_sweep_case c;
  first_case(a, 0, &c);
  if (rc == FB_OK && input_errors == a->ncases)
    rc = fb_err_set(err, c.status, "every case failed on its input; the first: %s",
                    c.error ? c.error : "(out of memory)");
  return rc;
}

/* What a failed or interrupted sweep leaves: the journal when it holds
 * cases worth resuming (not when the study itself is at fault), said in
 * err; else nothing, as before. */
static int leave_journal(const sweep_args *a, sweep_journal **journal, fb_err *err)
{
  size_t not_done, failed, input_errors;
  tally(a, &not_done, &failed, &input_errors);
  /* What the file holds, not what ran: after a failed write they differ. */
  const size_t kept = sweep_journal_rows(*journal);
  const int keep = kept > 0 && input_errors < a->ncases;
  sweep_journal_close(journal, !keep);
  if (!keep)
    return 0;
  char *path = sweep_journal_path(a->out_dir);
  fb_err_append(err,
                "; %zu of %zu cases are done and kept in %s: run the same command with "
                "--resume to run the others",
                kept, a->ncases, path ? path : "the journal");
  free(path);
  return 1;
}

/* The message of a study that ran with failed cases (failed of them)
 * into err: how many, where their messages are, and the first. */
static void failed_cases_error(const sweep_args *a, size_t failed, fb_err *err)
{
  fb_study_sweep_case c;
  const size_t i = first_case(a, 1, &c);
  char label[512];
  sweep_case_label(a, i, 0, label, sizeof label);
  fb_err_set(err, FB_ESOLVER,
             "%zu of %zu case%s failed (each has its message in the error column of "
             "%s/sweep.csv); the first, case %zu (%s): %s",
             failed, a->ncases, a->ncases == 1 ? "" : "s", a->out_dir, i + 1, label,
             c.error ? c.error : "out of memory");
}

/* Runs the study (on rank 0 of mpi_size ranks, or alone when mpi_size is
 * 0); the exit code. */
static int sweep(sweep_args *a, int mpi_size)
{
  fb_err err;
  fb_err_clear(&err);
  size_t resumed = 0;
  /* The output directory is held (locked) from the start: the journal
   * is written there as the cases finish. */
  cli_outdir od;
  int rc = cli_outdir_open(&od, a->out_dir, "sweep", &err), journal_rc = FB_OK;
  const int opened = rc == FB_OK;
  /* Stopped early by a signal, a sweep leaves its journal. */
  char *journal_path = opened ? sweep_journal_path(a->out_dir) : NULL;
  char note[FB_ERR_MSG_MAX];
  if (journal_path) {
    snprintf(note, sizeof note,
             "the finished cases are kept in %s: run the same command with --resume to run "
             "the others",
             journal_path);
    od.interrupt_note = note;
  }
  free(journal_path);
  if (rc == FB_OK)
    rc = journal_rc = sweep_journal_open(a, a->out_dir, &resumed, &a->journal, &err);
#ifdef FLEXBOND_MPI
  /* The other ranks wait for this verdict before they wait for cases. */
  if (mpi_size > 0)
    sweep_mpi_go(rc == FB_OK);
#endif
  double seconds = 0;
  if (rc == FB_OK) {
    if (resumed > 0 && !a->quiet)
      cli_say("flexbond sweep: resuming: %zu of %zu cases are done", resumed, a->ncases);
    rc = run_cases(a, mpi_size, &seconds, &err);
    if (rc == FB_OK)
      rc = write_outputs(&od, a, &err);
    if (rc == FB_OK)
      rc = cli_outdir_close(&od, rc, &err);
    if (rc == FB_OK) {
      sweep_journal_close(&a->journal, 1);
    } else {
      od.failure_noted = leave_journal(a, &a->journal, &err);
      cli_outdir_close(&od, rc, &err);
    }
  } else if (opened) {
    cli_outdir_close(&od, rc, &err);
  }
  size_t not_done = 0, failed = 0, input_errors = 0;
  tally(a, &not_done, &failed, &input_errors);
  if (rc == FB_OK && !a->quiet)
    cli_say("flexbond sweep: %s: %zu cases (%zu resumed), %zu failed, %.3g s -> %s",
            a->scenario_name, a->ncases, resumed, failed, seconds, a->out_dir);
  /* Failed cases are a failure of the command, said in one message like
   * any other (docs/errors.md), -q or not: -q silences the progress. */
  if (rc == FB_OK && failed > 0)
    failed_cases_error(a, failed, &err);
  /* A journal of another study, or one left without --resume: a matter
   * of the command line. */
  if (journal_rc == FB_EINVAL)
    return cli_usage_error("sweep", "%s", err.msg);
  if (rc != FB_OK)
    return cli_report(rc, &err);
  return failed ? cli_report(FB_ESOLVER, &err) : CLI_EXIT_OK;
}

/* The options after the --set ones are taken out. */
static int parse_options(int argc, char **argv, sweep_args *a, int *go)
{
  enum {
    OPT_OUT,
    OPT_SYSTEM,
    OPT_JOBS,
    OPT_RESUME,
    OPT_MPI,
    OPT_NO_FIGURES,
    OPT_PLAIN_HEADER,
    OPT_QUIET,
    OPT_STRICT,
    OPT_HELP,
    NOPTS
  };
  cli_option opts[NOPTS] = {
      [OPT_OUT] = {"--output", "-o", 1, NULL},
      [OPT_SYSTEM] = {"--system", NULL, 1, NULL},
      [OPT_JOBS] = {"--jobs", "-j", 1, NULL},
      [OPT_RESUME] = {"--resume", NULL, 0, NULL},
      [OPT_MPI] = {"--mpi", NULL, 0, NULL},
      [OPT_NO_FIGURES] = {"--no-figures", NULL, 0, NULL},
      [OPT_PLAIN_HEADER] = {"--plain-header", NULL, 0, NULL},
      [OPT_QUIET] = {"--quiet", "-q", 0, NULL},
      [OPT_STRICT] = {"--strict", NULL, 0, NULL},
      [OPT_HELP] = {"--help", "-h", 0, NULL},
  };
  static const char *const systems[] = {"rigid", "flexible"};
  int rc;
  *go = cli_parse_file_command(argc, argv, opts, NOPTS, sweep_usage, "SCENARIO",
                               &a->scenario_path, &rc);
  if (!*go)
    return rc;
  a->out_dir = opts[OPT_OUT].value;
  if (!a->out_dir || !*a->out_dir)
    return cli_usage_error(argv[0], "missing output directory (-o DIR)");
  a->quiet = a->quiet || opts[OPT_QUIET].value != NULL;
  a->strict = opts[OPT_STRICT].value != NULL;
  a->figures = opts[OPT_NO_FIGURES].value == NULL;
  a->header = opts[OPT_PLAIN_HEADER].value ? FB_CSV_HEADER_NAMES : FB_CSV_HEADER_UNITS;
  a->resume = opts[OPT_RESUME].value != NULL;
  if (a->mpi && opts[OPT_JOBS].value)
    return cli_usage_error(argv[0], "--mpi runs one case per rank at a time: instead of -j, "
                                    "start more ranks (docs/cluster.md)");
  int system = 0;
  rc = opts[OPT_SYSTEM].value
           ? cli_choice(argv[0], "--system", opts[OPT_SYSTEM].value, systems, 2, &system)
           : CLI_EXIT_OK;
  a->sys = system ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID;
  return rc == CLI_EXIT_OK ? sweep_parse_jobs(argv[0], opts[OPT_JOBS].value, &a->jobs) : rc;
}

/* The --plot values into a->plot (the default without any). */
static int parse_plots(const char *cmd, char **plots, size_t nplots, sweep_args *a)
{
  if (nplots == 0) {
    sweep_default_plots(a);
    return CLI_EXIT_OK;
  }
  if (nplots > SWEEP_MAX_PLOTS)
    return cli_usage_error(cmd, "%zu --plot options; sweep.png takes at most %d panels", nplots,
                           SWEEP_MAX_PLOTS);
  a->nplots = 0;
  for (size_t i = 0; i < nplots; ++i) {
    size_t m = 0;
    if (sweep_metric_find(a, plots[i], &m) != 0) {
      char outputs[512];
      size_t len = 0;
      outputs[0] = '\0';
      for (size_t k = 0; k < a->base->noutputs && len + 1 < sizeof outputs; ++k)
        len = fb_text_append(outputs, sizeof outputs, len, "%s%s", k ? ", " : "",
                             a->base->output[k].name);
      return cli_usage_error(cmd,
                             "--plot %s: no such metric; give OUTPUT[:peak|min|rms] with an "
                             "output of the scenario (%s) or a column of sweep.csv such as "
                             "min_tire_force",
                             plots[i], outputs);
    }
    a->plot[a->nplots++] = m;
  }
  return CLI_EXIT_OK;
}

/* The study layer's sweep of a (sweep_study_new); the exit code. */
static int make_study(sweep_args *a)
{
  fb_err err;
  const int rc = sweep_study_new(a, &err);
  return rc == FB_OK ? CLI_EXIT_OK : cli_report(rc, &err);
}

/* Parses and checks the study into a; the exit code (go: 0 after --help). */
static int set_up(int argc, char **argv, sweep_args *a, char **name, int *go)
{
  char **rest = malloc((size_t)argc * sizeof *rest),
       **sets = malloc((size_t)argc * sizeof *sets),
       **plots = malloc((size_t)argc * sizeof *plots);
  size_t nsets = 0, nplots = 0;
  int nrest = 0;
  *go = 0;
  int rc = rest && sets && plots
               ? split_sets(argc, argv, rest, &nrest, sets, &nsets, plots, &nplots)
               : cli_usage_error(argv[0], "out of memory");
  if (rc == CLI_EXIT_OK)
    rc = parse_options(nrest, rest, a, go);
  if (rc == CLI_EXIT_OK && *go)
    rc = parse_keys(argv[0], sets, nsets, a);
  if (rc == CLI_EXIT_OK && *go)
    rc = check_scenario(argv[0], a, name);
  if (rc == CLI_EXIT_OK && *go)
    rc = resolve_keys(argv[0], a);
  if (rc == CLI_EXIT_OK && *go)
    rc = make_study(a);
  if (rc == CLI_EXIT_OK && *go)
    rc = parse_plots(argv[0], plots, nplots, a);
  free(plots);
  free(sets);
  free(rest);
  return rc;
}

int sweep_wants_mpi(int argc, char **argv)
{
  for (int i = 1; i < argc && strcmp(argv[i], "--") != 0; ++i)
    if (!strcmp(argv[i], "--mpi"))
      return 1;
  return 0;
}

#ifdef FLEXBOND_MPI
/* The study across the ranks of an MPI job. Every rank sets it up (the
 * same files, the same checks); only rank 0 speaks while it does, and
 * all go on only if all succeeded. */
static int sweep_mpi(int argc, char **argv, sweep_args *a, char **name)
{
  int rank = 0, size = 1, go = 0;
  fb_err err;
  int rc = sweep_mpi_init(&rank, &size, &err);
  if (rc != FB_OK)
    return cli_report(rc, &err);
  /* Every rank must reach MPI_Finalize, or mpirun aborts the job: the
   * ranks stop when their cases do, not earlier (docs/cluster.md). */
  cli_interrupt_polled_only();
  a->mpi = 1;
  a->quiet = rank != 0;
  const int saved = sweep_mpi_silence(rank);
  rc = set_up(argc, argv, a, name, &go);
  uint64_t fingerprint = 0;
  if (rc == CLI_EXIT_OK && go && sweep_study_fingerprint(a, &fingerprint, NULL, &err) != FB_OK)
    rc = cli_report(err.code, &err);
  sweep_mpi_unsilence(saved);
  const int agreed = sweep_mpi_agreed(
      rank, fingerprint, "another scenario file than rank 0 or other files it names", &rc);
  if (agreed && go && rank == 0)
    rc = sweep(a, size);
  else if (agreed && go && sweep_mpi_go(0))
    sweep_mpi_work(a);
  return sweep_mpi_finish(rc);
}
#endif

int cli_cmd_sweep(int argc, char **argv)
{
  sweep_args a = {0};
  char *name = NULL;
  int go = 0, rc;
  if (sweep_wants_mpi(argc, argv)) {
#ifdef FLEXBOND_MPI
    rc = sweep_mpi(argc, argv, &a, &name);
#else
    rc = cli_usage_error(argv[0], "--mpi: this flexbond was built without MPI (configure with "
                                  "cmake -DFLEXBOND_MPI=ON; docs/cluster.md)");
#endif
  } else {
    rc = set_up(argc, argv, &a, &name, &go);
    if (rc == CLI_EXIT_OK && go)
      rc = sweep(&a, 0);
  }
  fb_study_sweep_free(&a.study);
  for (size_t k = 0; k < a.nkeys; ++k)
    sweep_key_free(&a.keys[k]);
  fb_scenario_free(&a.base);
  free(name);
  return rc;
}
