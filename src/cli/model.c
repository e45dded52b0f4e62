/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond model: a vehicle scenario's assembled bond graph written as a
 * model file (fb_model_write), so that everything `flexbond run` builds
 * in C can be read, changed and simulated with `flexbond sim`. */
#include "flexbond/model.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "cli.h"

static const char model_usage[] =
    "usage: flexbond model SCENARIO.yaml [--system rigid|flexible] -o DIR\n"
    "\n"
    "Assembles the scenario's vehicle (System 1, rigid hull, or System 2,\n"
    "finite-element hull) and writes it as one model file, DIR/NAME.yaml\n"
    "(NAME the scenario's name; docs/model-format.md), with its large\n"
    "matrices as Matrix Market files beside it (DIR/NAME.ELEMENT.mtx). The\n"
    "model has the scenario's outputs and tire contact forces as probes and\n"
    "its solver settings, so `flexbond sim DIR/NAME.yaml` reproduces\n"
    "`flexbond run`. DIR is created if missing; nothing is written if a\n"
    "part cannot be written.\n"
    "\n"
    "options:\n"
    "  -o, --output DIR      output directory (required)\n"
    "  --system S            rigid (System 1, default) or flexible (System 2)\n"
    "  -q, --quiet           no summary line on stderr\n"
    "  --strict              refuse implausible values instead of warning\n"
    "  -h, --help            this text\n";

typedef struct model_args {
  const char *path, *out_dir;
  fb_system sys;
  int quiet;
  int strict; /* --strict */
} model_args;

/* Writes the model into od's staging directory and records its files. */
static int stage_model(cli_outdir *od, const fb_scenario *s, fb_system sys, size_t *nwritten,
                       fb_err *err)
{
  fb_bg *graph = NULL;
  fb_probe_spec *probes = NULL;
  size_t nprobes = 0, nfiles = 0;
  char **files = NULL;
  fb_sim_opts opts;
  fb_vehicle_sim_opts(s, &opts);
  const fb_model_initial initial =
      s->initial == FB_INITIAL_STATIC ? FB_MODEL_INITIAL_STATIC : FB_MODEL_INITIAL_ZERO;
  int rc = fb_vehicle_graph(s, sys, &graph, &probes, &nprobes, err);
  if (!rc)
    rc = cli_check_interrupt(err);
  /* The first staged path makes the staging directory. */
  char *first = rc ? NULL : cli_outdir_path(od, "model.yaml", err);
  if (!rc && !first)
    rc = err->code;
  free(first);
  if (!rc)
    rc = fb_model_write(graph, probes, nprobes, &opts, initial, od->stage, s->name, &files,
                        &nfiles, err);
  for (size_t i = 0; i < nfiles; ++i) {
    char *path = rc ? NULL : cli_outdir_path(od, files[i], err);
    if (!rc && !path)
      rc = err->code;
    if (!rc)
      rc = cli_outdir_keep(od, path, err);
    free(files[i]);
  }
  free(files);
  *nwritten = nfiles;
  fb_vehicle_probes_free(&probes, nprobes);
  fb_bg_free(&graph);
  return rc;
}

static int run(const model_args *a)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  size_t nfiles = 0;
  int rc = cli_scenario_load(a->path, a->strict, &s, &err);
  cli_outdir od;
  const int opened =
      rc == FB_OK && (rc = cli_outdir_open(&od, a->out_dir, "model", &err)) == FB_OK;
  if (rc == FB_OK)
    rc = stage_model(&od, s, a->sys, &nfiles, &err);
  if (opened)
    rc = cli_outdir_close(&od, rc, &err);
  if (rc == FB_OK && !a->quiet)
    cli_say("flexbond model: %s (%s hull): %zu files -> %s/%s.yaml", s->name,
            a->sys == FB_SYSTEM_FLEXIBLE ? "flexible" : "rigid", nfiles, a->out_dir, s->name);
  rc = cli_report_scenario(s, rc, &err);
  fb_scenario_free(&s);
  return rc;
}

int cli_cmd_model(int argc, char **argv)
{
  enum { OPT_OUT, OPT_SYSTEM, OPT_QUIET, OPT_STRICT, OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {
      [OPT_OUT] = {"--output", "-o", 1, NULL},  [OPT_SYSTEM] = {"--system", NULL, 1, NULL},
      [OPT_QUIET] = {"--quiet", "-q", 0, NULL}, [OPT_STRICT] = {"--strict", NULL, 0, NULL},
      [OPT_HELP] = {"--help", "-h", 0, NULL},
  };
  model_args a = {NULL, NULL, FB_SYSTEM_RIGID, 0, 0};
  int rc;
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, model_usage, "SCENARIO", &a.path, &rc))
    return rc;
  a.out_dir = opts[OPT_OUT].value;
  if (!a.out_dir || !*a.out_dir)
    return cli_usage_error(argv[0], "missing output directory (-o DIR)");
  a.quiet = opts[OPT_QUIET].value != NULL;
  a.strict = opts[OPT_STRICT].value != NULL;
  if (opts[OPT_SYSTEM].value) {
    static const char *const systems[] = {"rigid", "flexible"};
    int which = 0;
    rc = cli_choice(argv[0], "--system", opts[OPT_SYSTEM].value, systems, 2, &which);
    if (rc != CLI_EXIT_OK)
      return rc;
    a.sys = which ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID;
  }
  return run(&a);
}
