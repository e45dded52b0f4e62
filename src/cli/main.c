/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: command-line front end of the library.
 *
 *   flexbond sim MODEL.yaml -o DIR [--t-end S] [--rtol X] [--sample-rate HZ] [--quiet]
 *   flexbond diagram FILE.yaml [--system rigid|flexible]
 *                    [--kind block-diagram|bond-graph|flat] [-o FILE.dot|.svg|.png]
 *   flexbond causality FILE.yaml [--system rigid|flexible]
 *   flexbond eig FILE.yaml [--system rigid|flexible]
 *   flexbond run SCENARIO.yaml -o DIR [--system rigid|flexible|both]
 *                [--initial zero|static] [--payload weight-only|lumped] [-q]
 *   flexbond modes SCENARIO.yaml [--system rigid|flexible]
 *   flexbond export SCENARIO.yaml -o DIR [--system rigid|flexible]
 *   flexbond model SCENARIO.yaml -o DIR [--system rigid|flexible]
 *   flexbond sweep SCENARIO.yaml --set KEY=SPEC [--set ...] -o DIR [--system rigid|flexible]
 *                  [-j N] [--no-figures] [-q]
 *   flexbond ride-limit SCENARIO.yaml --vary KEY=V1,V2,... --metric NAME -o DIR [--limit X]
 *                  [--output COLUMN] [--speeds LO:HI] [--system rigid|flexible|both] [-j N]
 *   flexbond --help | -h | --version,  flexbond COMMAND --help
 *
 * Exit codes:
 *   0  success
 *   1  usage error: unknown command or option, missing or extra argument,
 *      option value that is not a finite number > 0 or not one of the
 *      choices, a system that is not available yet
 *   2  input error: the model or scenario could not be parsed or is invalid
 *      (FB_EPARSE, FB_EINVAL, FB_EMODEL)
 *   3  causality error: conflict, derivative causality, algebraic loop
 *      (FB_ECAUSAL)
 *   4  solver failure (FB_ESOLVER)
 *   5  I/O error: a file could not be read or written (FB_EIO)
 *   6  out of memory (FB_ENOMEM)
 *   130  interrupted by SIGINT or SIGTERM (FB_EINTR); nothing was written
 * Errors are printed to stderr as "flexbond: <message>"; the library's
 * messages carry the file:line context themselves. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

typedef struct cli_command {
  const char *name;
  int (*run)(int argc, char **argv);
  const char *summary;
} cli_command;

static const cli_command commands[] = {
    {"sim", cli_cmd_sim, "simulate a model, write probes.csv and stats.json"},
    {"diagram", cli_cmd_diagram, "draw the block diagram or the bond graph (DOT, SVG, PNG)"},
    {"causality", cli_cmd_causality, "list the bonds with their causal strokes"},
    {"eig", cli_cmd_eig, "eigenvalues of the model linearised at its initial state"},
    {"run", cli_cmd_run, "simulate a vehicle scenario: CSV, the paper's Figs. 8-14, summary"},
    {"modes", cli_cmd_modes, "natural frequencies and damped modes of a vehicle scenario"},
    {"mesh", cli_cmd_mesh, "the finite-element hull mesh of a scenario; export to .inp / .vtu"},
    {"export", cli_cmd_export, "a vehicle scenario's linear model in descriptor form (.mtx)"},
    {"fmu", cli_cmd_fmu,
     "a vehicle scenario as an FMI 3.0 FMU (Model Exchange, Co-Simulation)"},
    {"freq", cli_cmd_freq, "frequency response of a vehicle scenario's outputs to the road"},
    {"model", cli_cmd_model, "write a vehicle scenario's bond graph as a model file"},
    {"sweep", cli_cmd_sweep, "parameter study of a vehicle scenario on all cores: CSV, figure"},
    {"ride-limit", cli_cmd_ride_limit,
     "ride-limiting speed against a scenario value: CSV, figure"},
};

static void print_usage(FILE *fp)
{
  fputs("usage: flexbond COMMAND [OPTIONS] MODEL.yaml|SCENARIO.yaml\n"
        "       flexbond --help | --version\n"
        "\ncommands:\n",
        fp);
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i)
    fprintf(fp, "  %-10s %s\n", commands[i].name, commands[i].summary);
  fputs("\n'flexbond COMMAND --help' describes a command's options.\n"
        "exit codes: 0 ok, 1 usage, 2 invalid input, 3 causality, 4 solver,\n"
        "            5 I/O, 6 out of memory, 130 interrupted\n",
        fp);
}

static const cli_command *find_command(const char *name)
{
  for (size_t i = 0; i < sizeof commands / sizeof commands[0]; ++i) {
    if (strcmp(commands[i].name, name) == 0)
      return &commands[i];
  }
  return NULL;
}

/* Exit code after printing to stdout: 5 if the output was lost. */
static int finish_stdout(void)
{
  fb_err err;
  fb_err_clear(&err);
  return cli_report(cli_flush_stdout(&err), &err);
}

int main(int argc, char **argv)
{
  if (argc < 2) {
    print_usage(stderr);
    return CLI_EXIT_USAGE;
  }
  const char *first = argv[1];
  if (strcmp(first, "--help") == 0 || strcmp(first, "-h") == 0) {
    print_usage(stdout);
    return finish_stdout();
  }
  if (strcmp(first, "--version") == 0) {
    puts("flexbond " CLI_VERSION);
    return finish_stdout();
  }
  const cli_command *cmd = find_command(first);
  if (!cmd) {
    cli_say("flexbond: unknown %s '%s'", first[0] == '-' ? "option" : "command", first);
    fputs("Try 'flexbond --help'.\n", stderr);
    return CLI_EXIT_USAGE;
  }
  /* One BLAS thread for every command. flexbond's parallelism is its
   * own: a sweep's cases, run's basis estimator beside its runs. Nested
   * OpenBLAS threads would only contend with it (their waiting spins:
   * System 2's run at density 3 took 1.03 s of wall time with OpenBLAS's
   * two threads, 0.93 s with one), and OpenBLAS sizes its pool from the
   * CPUs the process may use, which differ between a process on all
   * cores and an MPI rank bound to one: with another pool size a dense
   * eigen-solution rounds otherwise, and a result would depend on how it
   * ran (docs/sweep.md). OpenBLAS reads OPENBLAS_NUM_THREADS when it is
   * loaded, before main, so only its own call can do this. */
  openblas_set_num_threads(1);
  if (cli_interrupt_install() != 0)
    fputs("flexbond: warning: cannot catch SIGINT; an interrupted run may leave files "
          "behind\n",
          stderr);
  const int code = cmd->run(argc - 1, argv + 1);
  cli_interrupt_finish();
  return code;
}
