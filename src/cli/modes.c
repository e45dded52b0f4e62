/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond modes: natural frequencies and damped modes of the vehicle of
 * a scenario, linearised at its static equilibrium (fb_vehicle_modes).
 *
 * The undamped table lists f_n = omega_n / (2 pi) with every damper
 * removed; the damped one the eigenvalues lambda = re +/- j im of the full
 * model with f = |lambda| / (2 pi) and zeta = -re / |lambda| (Ogata,
 * "Modern Control Engineering", 5th ed., section 5.3). */
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/vehicle.h"

#include "cli.h"

static const char modes_usage[] =
    "usage: flexbond modes SCENARIO.yaml [--system rigid|flexible] [-o DIR]\n"
    "\n"
    "Prints the modes of the vehicle linearised at its static equilibrium:\n"
    "first the undamped natural frequencies (every damper removed), then the\n"
    "damped eigenvalues with their damping ratios, each with the part of the\n"
    "vehicle that holds most of the mode's kinetic energy. Zero eigenvalues\n"
    "of the statically indeterminate support (self-stress of the springs)\n"
    "and of the free surge, sway and yaw of a vehicle with rigid bodies\n"
    "are counted, not listed. With --system flexible: the free-free hull's\n"
    "modes and the undamped System 2's (the finite-element hull with the\n"
    "mounted bodies, suspensions and tires), each normalised so that its\n"
    "largest displacement over the mounted bodies and the hull is 1.\n"
    "\n"
    "options:\n"
    "  --system rigid|flexible  hull model (default rigid: System 1)\n"
    "  -o, --output DIR         (flexible) also write hull_modes.csv, modes.csv,\n"
    "                           mode_NN.vtu and the pictures mode_NN.png of the\n"
    "                           modes chosen by kind (the hull's bounce, roll and\n"
    "                           pitch, each mounted body's, the first wheel hop,\n"
    "                           the first two elastic) or listed (report.mode_pictures)\n"
    "  --picture-modes LIST     (flexible, -o) picture these modes instead: \"1,3,7\"\n"
    "  --strict                 refuse implausible values instead of warning\n"
    "  -h, --help               this text\n";

static const char *const system_choices[] = {"rigid", "flexible"};
static const fb_system systems[] = {FB_SYSTEM_RIGID, FB_SYSTEM_FLEXIBLE};

/* "N static zero mode(s)" line ending of a table's heading: nfree of them
 * the vehicle's free horizontal motions (fb_vehicle_free_motions), the
 * others the support's self-stress. */
static void print_static_count(size_t nstatic, size_t nfree)
{
  const size_t nself = nstatic > nfree ? nstatic - nfree : 0;
  printf("%zu static zero mode%s (self-stress)", nself, nself == 1 ? "" : "s");
  if (nstatic > nself)
    printf(" and %zu free motion%s (surge, sway, yaw)", nstatic - nself,
           nstatic - nself == 1 ? "" : "s");
  printf(" left out\n");
}

static void print_undamped(const fb_mode *m, size_t n, size_t nstatic, size_t nfree)
{
  printf("undamped natural frequencies: %zu modes, ", n);
  print_static_count(nstatic, nfree);
  printf("%4s  %12s  %s\n", "#", "f_n [Hz]", "description");
  for (size_t i = 0; i < n; ++i)
    printf("%4zu  %12.6g  %s\n", i + 1, m[i].freq_hz, m[i].description);
}

static void print_damped(const fb_mode *m, size_t n, size_t nstatic, size_t nfree)
{
  size_t nreal = 0;
  for (size_t i = 0; i < n; ++i)
    nreal += m[i].im == 0;
  printf("damped eigenvalues: %zu oscillatory, %zu real, ", n - nreal, nreal);
  print_static_count(nstatic, nfree);
  printf("%4s  %12s  %14s  %8s  %s\n", "#", "f_n [Hz]", "real [1/s]", "zeta", "description");
  for (size_t i = 0; i < n; ++i) {
    /* A real eigenvalue is a decay, not an oscillation: no frequency. */
    if (m[i].im == 0)
      printf("%4zu  %12s  %14.8g  %8s  (real) %s\n", i + 1, "-", m[i].re, "-",
             m[i].description);
    else
      printf("%4zu  %12.6g  %14.8g  %8.4g  %s\n", i + 1, m[i].freq_hz, m[i].re,
             m[i].damping_ratio, m[i].description);
  }
}

/* The modes of one linearisation: undamped or damped. */
typedef struct mode_table {
  fb_mode *modes;
  size_t nmodes, nstatic;
} mode_table;

/* Both tables are computed before anything is printed, so a failure
 * prints no half table. */
static int run(const char *path, fb_system sys, int strict)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  mode_table undamped = {0}, damped = {0};
  fb_vehicle *v = NULL;
  int rc = cli_scenario_load(path, strict, &s, &err);
  cli_stage stage = {"modes", cli_system_label(sys), 0};
  fb_vehicle_opts vo;
  fb_vehicle_opts_default(&vo);
  vo.progress = (fb_progress){cli_stage_progress, &stage};
  /* One vehicle, both linearisations. */
  if (rc == FB_OK)
    rc = fb_vehicle_new(s, sys, &vo, &v, &err);
  if (rc == FB_OK)
    rc = fb_vehicle_linear_modes(v, 1, &undamped.modes, &undamped.nmodes, &undamped.nstatic,
                                 &err);
  if (rc == FB_OK)
    rc = fb_vehicle_linear_modes(v, 0, &damped.modes, &damped.nmodes, &damped.nstatic, &err);
  fb_vehicle_free(&v);
  if (rc == FB_OK) {
    printf("%s: %s, linearised at the static equilibrium\n\n", s->name ? s->name : path,
           sys == FB_SYSTEM_RIGID ? "System 1 (rigid hull)" : "System 2 (flexible hull)");
    print_undamped(undamped.modes, undamped.nmodes, undamped.nstatic,
                   fb_vehicle_free_motions(s));
    putchar('\n');
    print_damped(damped.modes, damped.nmodes, damped.nstatic, fb_vehicle_free_motions(s));
    rc = cli_flush_stdout(&err);
  }
  free(damped.modes);
  free(undamped.modes);
  rc = cli_report_scenario(s, rc, &err);
  fb_scenario_free(&s);
  return rc;
}

int cli_cmd_modes(int argc, char **argv)
{
  enum { OPT_SYSTEM, OPT_OUT, OPT_PICTURE_MODES, OPT_STRICT, OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {[OPT_SYSTEM] = {"--system", NULL, 1, NULL},
                            [OPT_OUT] = {"--output", "-o", 1, NULL},
                            [OPT_PICTURE_MODES] = {"--picture-modes", NULL, 1, NULL},
                            [OPT_STRICT] = {"--strict", NULL, 0, NULL},
                            [OPT_HELP] = {"--help", "-h", 0, NULL}};
  const char *path;
  int rc;
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, modes_usage, "SCENARIO", &path, &rc))
    return rc;
  int choice = 0;
  if (opts[OPT_SYSTEM].value)
    rc = cli_choice(argv[0], "--system", opts[OPT_SYSTEM].value, system_choices,
                    sizeof system_choices / sizeof system_choices[0], &choice);
  cli_mode_list pictured = {0};
  if (rc == CLI_EXIT_OK && opts[OPT_PICTURE_MODES].value)
    rc = cli_picture_modes_option(argv[0], opts[OPT_PICTURE_MODES].value, &pictured);
  if (rc != CLI_EXIT_OK)
    return rc;
  if (systems[choice] == FB_SYSTEM_FLEXIBLE)
    return cli_modes_flexible(path, opts[OPT_OUT].value, opts[OPT_STRICT].value != NULL,
                              &pictured);
  if (opts[OPT_OUT].value)
    return cli_usage_error(argv[0], "-o DIR goes with --system flexible");
  if (opts[OPT_PICTURE_MODES].value)
    return cli_usage_error(argv[0], "--picture-modes goes with --system flexible");
  return run(path, systems[choice], opts[OPT_STRICT].value != NULL);
}
