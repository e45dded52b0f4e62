/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond sim: load a model, build its block diagram, integrate it, and
 * only then write DIR/probes.csv and DIR/stats.json, so a failed run
 * leaves no output behind. */
#include "flexbond/sim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/io.h"
#include "flexbond/model.h"

#include "cli.h"

static const char sim_usage[] =
    "usage: flexbond sim MODEL.yaml -o DIR [options]\n"
    "\n"
    "Simulates the model and writes DIR/probes.csv (time and every probe,\n"
    "one row per sample) and DIR/stats.json (solver statistics). DIR is\n"
    "created if missing; nothing is written if the run fails.\n"
    "\n"
    "options (override the model's `simulation` section):\n"
    "  -o, --output DIR      output directory (required)\n"
    "  --t-end S             end time in seconds\n"
    "  --rtol X              relative tolerance\n"
    "  --sample-rate HZ      output samples per second\n"
    "  --plot                also write DIR/probes.png (gnuplot), a panel per probe\n"
    "  -q, --quiet           no summary line on stderr\n"
    "  -h, --help            this text\n";

/* Command-line settings of one run. Overrides are 0 when not given (every
 * given value is > 0). */
typedef struct sim_args {
  const char *model_path;
  const char *out_dir;
  double t_end;
  double rtol;
  double sample_rate;
  int quiet;
  int plot;
} sim_args;

/* What stats.json reports. */
typedef struct stats_source {
  const fb_result *res;
  const fb_bd *bd;
} stats_source;

/* stats.json from a stats_source (a cli_writer). */
static void write_stats_json(FILE *fp, const void *ctx)
{
  const stats_source *src = ctx;
  const fb_sim_stats *s = fb_result_stats(src->res);
  fprintf(fp,
          "{\n"
          "  \"steps\": %ld,\n"
          "  \"rhs_evals\": %ld,\n"
          "  \"newton_setups\": %ld,\n"
          "  \"factorizations\": %ld,\n"
          "  \"newton_iters\": %ld,\n"
          "  \"newton_conv_fails\": %ld,\n"
          "  \"err_test_fails\": %ld,\n"
          "  \"last_order\": %d,\n"
          "  \"wall_seconds\": %.6g,\n"
          "  \"nstates\": %zu,\n"
          "  \"nblocks\": %zu\n"
          "}\n",
          s->steps, s->rhs_evals, s->newton_setups, s->factorizations, s->newton_iters,
          s->newton_conv_fails, s->err_test_fails, s->last_order, s->wall_seconds,
          fb_bd_nstates(src->bd), fb_bd_nblocks(src->bd));
}

/* DIR/probes.png: every probe against time, a panel each. */
static int write_plot(cli_outdir *od, const fb_result *res, fb_err *err)
{
  size_t nout = fb_result_ncols(res) - 1;
  if (nout == 0)
    return FB_OK;
  char *path = cli_outdir_path(od, "probes.png", err);
  if (!path)
    return err->code; /* out of memory, or no staging directory */
  size_t *cols = malloc(nout * sizeof *cols);
  int rc = cols ? FB_OK : fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  for (size_t j = 0; cols && j < nout; ++j)
    cols[j] = j;
  if (rc == FB_OK)
    rc = fb_plot_png(res, cols, nout, NULL, path, err);
  free(cols);
  if (rc == FB_OK)
    return cli_outdir_keep(od, path, err);
  free(path);
  return rc;
}

/* probes.csv (a cli_writer). */
static void write_probes_csv(FILE *fp, const void *res)
{
  fb_result_print_csv(fp, res, FB_CSV_HEADER_UNITS);
}

/* Stages the files in od. */
static int write_outputs(cli_outdir *od, const fb_result *res, const fb_bd *bd, int plot,
                         fb_err *err)
{
  int rc = FB_OK;
  if (plot)
    rc = write_plot(od, res, err);
  if (rc == FB_OK)
    rc = cli_outdir_write(od, "probes.csv", write_probes_csv, res, err);
  const stats_source stats = {res, bd};
  if (rc == FB_OK)
    rc = cli_outdir_write(od, "stats.json", write_stats_json, &stats, err);
  return rc;
}

static void print_summary(const sim_args *a, const fb_model *m, const fb_sim_opts *opts,
                          const fb_result *res)
{
  const fb_sim_stats *s = fb_result_stats(res);
  cli_say("flexbond sim: %s: t = %g..%g s, %zu samples x %zu outputs, %ld steps, "
          "%ld rhs evals, %.3g s -> %s",
          fb_model_name(m), opts->t_start, opts->t_end, fb_result_nsamples(res),
          fb_result_ncols(res) - 1, s->steps, s->rhs_evals, s->wall_seconds, a->out_dir);
}

/* fb_sim_progress_fn: stops the simulation once interrupted. */
static int stop_when_interrupted(void *ctx, double t, double t_end)
{
  (void)ctx;
  (void)t;
  (void)t_end;
  return cli_interrupted();
}

/* The option of a that set the solver setting an fb_sim_opts_check
 * error is about (err->key, the setting's name), NULL if the model's own
 * value did. The sample count is sample_rate's, but --t-end may have
 * raised it. */
static const char *overriding_option(const sim_args *a, const char *key)
{
  static const struct {
    const char *key;
    const char *option;
    size_t field; /* 0 t_end, 1 rtol, 2 sample_rate */
  } map[] = {{"t_end", "--t-end", 0},
             {"rtol", "--rtol", 1},
             {"sample_rate", "--sample-rate", 2},
             {"sample_rate", "--t-end", 0}};
  const double given[3] = {a->t_end, a->rtol, a->sample_rate};
  for (size_t i = 0; i < sizeof map / sizeof map[0]; ++i)
    if (!strcmp(key, map[i].key) && given[map[i].field] > 0)
      return map[i].option;
  return NULL;
}

static int run(const sim_args *a)
{
  fb_err err;
  fb_err_clear(&err);
  fb_model *m = NULL;
  fb_model_sim *ms = NULL;
  fb_result *res = NULL;
  fb_sim_opts opts;
  int rc = fb_model_load(a->model_path, &m, &err);
  cli_report_warnings(m);
  if (rc == FB_OK) {
    /* The result's columns counted, so that the memory it would take is
     * checked here, where an option that raised it is named. */
    opts = fb_model_sim_opts_with(m, a->t_end, a->rtol, a->sample_rate);
    opts.progress = stop_when_interrupted;
    rc = fb_sim_opts_check(&opts, &err);
    /* The model's settings were checked where it was loaded: a failure
     * here is an option's, a usage error. */
    const char *option = rc == FB_OK ? NULL : overriding_option(a, err.key);
    if (option) {
      fb_model_free(&m);
      return cli_usage_error("sim", "option '%s': %s", option, err.msg);
    }
  }
  if (rc == FB_OK)
    rc = fb_model_sim_new(m, &ms, &err);
  /* The directory is held (locked) from here to the end. */
  cli_outdir od;
  const int opened =
      rc == FB_OK && (rc = cli_outdir_open(&od, a->out_dir, "sim", &err)) == FB_OK;
  if (rc == FB_OK)
    rc = fb_model_sim_run(ms, &opts, &res, &err);
  if (rc == FB_OK)
    rc = write_outputs(&od, res, fb_model_sim_diagram(ms), a->plot, &err);
  if (opened)
    rc = cli_outdir_close(&od, rc, &err);
  if (rc == FB_OK && !a->quiet)
    print_summary(a, m, &opts, res);
  fb_result_free(&res);
  fb_model_sim_free(&ms);
  fb_model_free(&m);
  return cli_report(rc, &err);
}

int cli_cmd_sim(int argc, char **argv)
{
  enum { OPT_OUT, OPT_T_END, OPT_RTOL, OPT_SAMPLE_RATE, OPT_PLOT, OPT_QUIET, OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {
      [OPT_OUT] = {"--output", "-o", 1, NULL},
      [OPT_T_END] = {"--t-end", NULL, 1, NULL},
      [OPT_RTOL] = {"--rtol", NULL, 1, NULL},
      [OPT_SAMPLE_RATE] = {"--sample-rate", NULL, 1, NULL},
      [OPT_PLOT] = {"--plot", NULL, 0, NULL},
      [OPT_QUIET] = {"--quiet", "-q", 0, NULL},
      [OPT_HELP] = {"--help", "-h", 0, NULL},
  };
  sim_args a = {0};
  int rc;
  if (!cli_parse_model_command(argc, argv, opts, NOPTS, sim_usage, &a.model_path, &rc))
    return rc;
  a.out_dir = opts[OPT_OUT].value;
  if (!a.out_dir || !*a.out_dir)
    return cli_usage_error(argv[0], "missing output directory (-o DIR)");
  a.quiet = opts[OPT_QUIET].value != NULL;
  a.plot = opts[OPT_PLOT].value != NULL;
  const struct {
    size_t opt;
    double *dest;
  } numbers[] = {{OPT_T_END, &a.t_end}, {OPT_RTOL, &a.rtol}, {OPT_SAMPLE_RATE, &a.sample_rate}};
  for (size_t i = 0; i < sizeof numbers / sizeof numbers[0] && rc == CLI_EXIT_OK; ++i) {
    const cli_option *o = &opts[numbers[i].opt];
    if (o->value)
      rc = cli_positive_number(argv[0], o->name, o->value, numbers[i].dest);
  }
  return rc == CLI_EXIT_OK ? run(&a) : rc;
}
