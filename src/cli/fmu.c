/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond fmu: a scenario's vehicle as an FMI 3.0 FMU, Model Exchange
 * and Co-Simulation in one archive (fb_fmu_export, flexbond/fmu.h;
 * docs/fmi.md). */
#include "flexbond/fmu.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char fmu_usage[] =
    "usage: flexbond fmu SCENARIO.yaml -o VEHICLE.fmu [--system rigid|flexible]\n"
    "                    [--road scenario|inputs] [--parameters KEY[,KEY...]]\n"
    "                    [--t-end S] [--model-identifier NAME]\n"
    "\n"
    "Writes the vehicle of the scenario as an FMI 3.0 FMU with both the Model\n"
    "Exchange and the Co-Simulation interfaces, for Simulink, OpenModelica,\n"
    "Dymola, FMPy or a test rig (docs/fmi.md). The FMU holds the scenario and\n"
    "every file it names, the binary for x86_64-linux with flexbond linked in,\n"
    "and the shared libraries the binary needs beside it: it runs where flexbond\n"
    "is not installed.\n"
    "Inputs: load_force (N, on the load, up positive); with --road inputs, each\n"
    "wheel's road height road_z_<CORNER> (m) and rate road_zdot_<CORNER> (m/s)\n"
    "in place of the scenario's road. Outputs: the scenario's, then every tire's\n"
    "contact_force_<CORNER> (N). Co-Simulation steps with flexbond's own stiff\n"
    "solver, the road's kinks and the tires' lift-off handled inside a step.\n"
    "\n"
    "options:\n"
    "  -o, --output FILE            the FMU to write (required; .fmu)\n"
    "  --system rigid|flexible      hull model (default flexible: System 2)\n"
    "  --road scenario|inputs       the scenario's road (default) or the road\n"
    "                               under each wheel as inputs\n"
    "  --parameters KEY[,KEY...]    scenario values the FMU takes as tunable\n"
    "                               parameters (keys as sweep's --set takes them;\n"
    "                               the file must write each)\n"
    "  --t-end S                    the longest run the FMU allows, s (default\n"
    "                               the scenario's t_end)\n"
    "  --model-identifier NAME      the binary's name (default from the\n"
    "                               scenario's name)\n"
    "  -q, --quiet                  say nothing while it works\n"
    "  -h, --help                   this text\n";

static const char *const system_choices[] = {"rigid", "flexible"};
static const fb_system systems[] = {FB_SYSTEM_RIGID, FB_SYSTEM_FLEXIBLE};
static const char *const road_choices[] = {"scenario", "inputs"};

/* The comma-separated keys of text, in a new array of pointers into the
 * copy *buf (both freed by the caller). */
static size_t split_keys(const char *text, char **buf, const char ***keys)
{
  *keys = NULL;
  if (!text || !(*buf = strdup(text)))
    return 0;
  size_t n = 1;
  for (const char *p = *buf; *p; ++p)
    n += *p == ',';
  *keys = calloc(n, sizeof **keys);
  if (!*keys)
    return 0;
  size_t k = 0;
  for (char *save = NULL, *t = strtok_r(*buf, ",", &save); t; t = strtok_r(NULL, ",", &save))
    (*keys)[k++] = t;
  return k;
}

static int run(const char *path, const fb_fmu_export_opts *o, const char *out, int quiet)
{
  fb_err err;
  fb_err_clear(&err);
  fb_fmu_info info;
  const int rc = fb_fmu_export(path, o, out, &info, &err);
  if (rc == FB_OK && !quiet) {
    printf("%s: wrote %s (%.1f MB): %s, %zu states, %zu event indicator%s, %zu input%s, "
           "%zu output%s, %zu parameter%s; %zu libraries bundled\n",
           path, out, (double)info.bytes / 1e6, info.model_identifier, info.nstates,
           info.nindicators, info.nindicators == 1 ? "" : "s", info.ninputs,
           info.ninputs == 1 ? "" : "s", info.noutputs, info.noutputs == 1 ? "" : "s",
           info.nparameters, info.nparameters == 1 ? "" : "s", info.nlibraries);
    return cli_report(cli_flush_stdout(&err), &err);
  }
  return cli_report(rc, &err);
}

int cli_cmd_fmu(int argc, char **argv)
{
  enum {
    OPT_SYSTEM,
    OPT_OUT,
    OPT_ROAD,
    OPT_PARAMS,
    OPT_T_END,
    OPT_ID,
    OPT_QUIET,
    OPT_HELP,
    NOPTS
  };
  cli_option opts[NOPTS] = {[OPT_SYSTEM] = {"--system", NULL, 1, NULL},
                            [OPT_OUT] = {"--output", "-o", 1, NULL},
                            [OPT_ROAD] = {"--road", NULL, 1, NULL},
                            [OPT_PARAMS] = {"--parameters", NULL, 1, NULL},
                            [OPT_T_END] = {"--t-end", NULL, 1, NULL},
                            [OPT_ID] = {"--model-identifier", NULL, 1, NULL},
                            [OPT_QUIET] = {"--quiet", "-q", 0, NULL},
                            [OPT_HELP] = {"--help", "-h", 0, NULL}};
  const char *path;
  int rc;
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, fmu_usage, "SCENARIO", &path, &rc))
    return rc;
  int sys = 1, road = 0;
  if (opts[OPT_SYSTEM].value)
    rc = cli_choice(argv[0], "--system", opts[OPT_SYSTEM].value, system_choices, 2, &sys);
  if (rc == CLI_EXIT_OK && opts[OPT_ROAD].value)
    rc = cli_choice(argv[0], "--road", opts[OPT_ROAD].value, road_choices, 2, &road);
  double t_end = 0.0;
  if (rc == CLI_EXIT_OK && opts[OPT_T_END].value)
    rc = cli_positive_number(argv[0], "--t-end", opts[OPT_T_END].value, &t_end);
  if (rc != CLI_EXIT_OK)
    return rc;
  const char *out = opts[OPT_OUT].value;
  const size_t len = out ? strlen(out) : 0;
  if (!out)
    return cli_usage_error(argv[0], "missing the FMU to write (-o VEHICLE.fmu)");
  if (len < 5 || strcmp(out + len - 4, ".fmu") != 0)
    return cli_usage_error(argv[0], "-o '%s': an FMU's file name ends in .fmu", out);
  if (opts[OPT_ID].value && !fb_fmu_model_identifier_valid(opts[OPT_ID].value))
    return cli_usage_error(argv[0],
                           "--model-identifier '%s': a C identifier (letters, digits and '_', "
                           "not first a digit) of at most 127 characters",
                           opts[OPT_ID].value);
  char *buf = NULL;
  const char **keys = NULL;
  const size_t nkeys = split_keys(opts[OPT_PARAMS].value, &buf, &keys);
  int twice = 0;
  for (size_t i = 0; i < nkeys; ++i)
    for (size_t j = 0; j < i; ++j)
      twice |= !strcmp(keys[i], keys[j]);
  if ((opts[OPT_PARAMS].value && !nkeys) || twice) {
    free(buf);
    free(keys);
    return cli_usage_error(argv[0], twice ? "--parameters: a key twice"
                                          : "--parameters: expected KEY[,KEY...]");
  }
  const int quiet = opts[OPT_QUIET].value != NULL;
  cli_stage stage = {"fmu", path, quiet};
  const fb_fmu_export_opts o = {.system = systems[sys],
                                .road_inputs = road,
                                .parameters = keys,
                                .nparameters = nkeys,
                                .t_end = t_end,
                                .model_identifier = opts[OPT_ID].value,
                                .progress = {cli_stage_progress, &stage}};
  rc = run(path, &o, opts[OPT_OUT].value, quiet);
  free(keys);
  free(buf);
  return rc;
}
