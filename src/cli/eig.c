/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond eig: eigenvalues of the model linearised at its initial state,
 * A = dF/dx (t0, x0), as the library computes them (fb_bd_eigen_new).
 *
 * For a complex pair lambda = sigma +/- j omega_d of a second-order mode
 * s^2 + 2 zeta omega_n s + omega_n^2, omega_n = |lambda| and
 * zeta = -sigma / |lambda| (Ogata, "Modern Control Engineering", 5th ed.,
 * section 5.3); the natural frequency in Hz is omega_n / (2 pi). */
#include <math.h>
#include <stdio.h>

#include "flexbond/bd.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "cli.h"
#include "graph_input.h"

static const char eig_usage[] =
    "usage: flexbond eig FILE.yaml [--system rigid|flexible]\n"
    "\n"
    "FILE is a model file or a vehicle scenario file, whose vehicle is\n"
    "assembled for --system (default rigid) and linearised at its graph's\n"
    "initial state (`flexbond modes` linearises at the static equilibrium).\n"
    "Prints the eigenvalues of the Jacobian dF/dx of the model's state\n"
    "equations x' = F(t, x) at the start time and initial state, sorted by\n"
    "|imaginary part| then real part. A complex pair is printed once, with\n"
    "its natural frequency f_n = |lambda| / (2 pi) and damping ratio\n"
    "zeta = -Re(lambda) / |lambda|. Eigenvalues within round-off of zero,\n"
    "|lambda| <= n eps ||A||_F, are zero eigenvalues (a free body, a statically\n"
    "indeterminate support): counted, and left out of the table.\n"
    "\n"
    "options:\n"
    "  --system S            rigid (System 1) or flexible (System 2), scenarios only\n"
    "  -h, --help            this text\n";

/* 2 pi; M_PI is not in C11. */
#define TWO_PI 6.283185307179586476925

static void print_table(const cli_graph_input *in, const fb_bd_eigen *e)
{
  size_t npairs = 0;
  for (size_t i = 0; i < e->n; ++i)
    npairs += e->im[i] > 0;
  const size_t nzero = e->nstates - e->n;
  printf("%s: %zu states, %zu real eigenvalues, %zu complex pairs (at t = %g s, initial "
         "state)\n",
         in->name, e->nstates, e->n - 2 * npairs, npairs, in->opts.t_start);
  if (nzero)
    printf("%zu zero eigenvalue%s (|lambda| <= %.3g = n eps ||A||_F: round-off) left out\n",
           nzero, nzero == 1 ? "" : "s", e->zero_tol);
  printf("%4s  %15s  %19s  %13s  %10s\n", "#", "real [1/s]", "imag [rad/s]", "f_n [Hz]",
         "zeta");
  size_t row = 0;
  for (size_t i = 0; i < e->n; ++i) {
    /* dgeev returns pairs as exact conjugates: print the upper member. */
    if (e->im[i] < 0)
      continue;
    printf("%4zu  %15.8g", ++row, e->re[i]);
    if (e->im[i] == 0) {
      printf("  %19s\n", "0");
      continue;
    }
    double modulus = hypot(e->re[i], e->im[i]);
    printf("  +/- %15.8g  %13.6g  %10.4g\n", e->im[i], modulus / TWO_PI, -e->re[i] / modulus);
  }
}

static int analyse(const cli_graph_input *in, fb_bd *bd, fb_err *err)
{
  if (fb_bd_nstates(bd) == 0) {
    printf("%s: no states, no eigenvalues\n", in->name);
    return cli_flush_stdout(err);
  }
  char what[FB_ERR_KEY_MAX];
  snprintf(what, sizeof what, "eig: %s", in->name);
  fb_bd_eigen *e = NULL;
  int rc = fb_bd_eigen_new(bd, in->opts.t_start, in->opts.x0, FB_VEHICLE_MEMORY_LIMIT, what, &e,
                           err);
  if (rc == FB_OK) {
    print_table(in, e);
    rc = cli_flush_stdout(err);
  }
  fb_bd_eigen_free(&e);
  return rc;
}

static int run(const char *path, fb_system sys, int system_given)
{
  fb_err err;
  fb_err_clear(&err);
  cli_graph_input in;
  fb_bd *bd = NULL;
  int rc = cli_graph_input_load(path, sys, system_given, &in, &err);
  /* Probes do not change the state equations; none are built. */
  if (rc == FB_OK) {
    rc = fb_bd_build(in.graph, NULL, 0, &bd, &err);
    cli_graph_input_blame(&in, &err); /* a causality error: at its element's or bond's line */
  }
  if (rc == FB_OK)
    rc = analyse(&in, bd, &err);
  fb_bd_free(&bd);
  cli_graph_input_free(&in);
  return cli_report(rc, &err);
}

int cli_cmd_eig(int argc, char **argv)
{
  enum { OPT_SYSTEM, OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {
      [OPT_SYSTEM] = {"--system", NULL, 1, NULL}, [OPT_HELP] = {"--help", "-h", 0, NULL}};
  const char *path;
  int code;
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, eig_usage, "FILE", &path, &code))
    return code;
  fb_system sys;
  code = cli_system_option(argv[0], opts[OPT_SYSTEM].value, &sys);
  if (code != CLI_EXIT_OK)
    return code;
  return run(path, sys, opts[OPT_SYSTEM].value != NULL);
}
