/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond eig: eigenvalues of the model linearised at its initial state,
 * A = dF/dx (t0, x0), from LAPACK's dgeev (Hessenberg QR; Anderson et al.,
 * LAPACK Users' Guide, 3rd ed., SIAM 1999, section 2.4.8).
 *
 * For a complex pair lambda = sigma +/- j omega_d of a second-order mode
 * s^2 + 2 zeta omega_n s + omega_n^2, omega_n = |lambda| and
 * zeta = -sigma / |lambda| (Ogata, "Modern Control Engineering", 5th ed.,
 * section 5.3); the natural frequency in Hz is omega_n / (2 pi). */
#include <float.h>
#include <lapacke.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/bd.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "../core/util.h"
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

typedef struct eigenvalue {
  double re, im;
} eigenvalue;

/* By |imag|, then real, then the positive member of a pair first. */
static int compare_eigenvalues(const void *pa, const void *pb)
{
  const eigenvalue *a = pa, *b = pb;
  double ia = fabs(a->im), ib = fabs(b->im);
  if (ia != ib)
    return ia < ib ? -1 : 1;
  if (a->re != b->re)
    return a->re < b->re ? -1 : 1;
  return (a->im < b->im) - (a->im > b->im);
}

/* Eigenvalues of the column-major n x n matrix a (overwritten) into ev. */
static int eigenvalues(size_t n, double *a, eigenvalue *ev, fb_err *err)
{
  if (n > (size_t)INT_MAX)
    return fb_err_set(err, FB_EINVAL, "eig: %zu states are too many for LAPACK", n);
  double *wr = malloc(2 * n * sizeof *wr);
  if (!wr)
    return fb_err_set(err, FB_ENOMEM, "eig: out of memory (%zu states)", n);
  double *wi = wr + n;
  lapack_int ln = (lapack_int)n;
  lapack_int info =
      LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', ln, a, ln, wr, wi, NULL, 1, NULL, 1);
  int rc = FB_OK;
  if (info != 0)
    rc = fb_err_set(err, FB_ESOLVER, "eig: LAPACK dgeev failed (info %d): %s", (int)info,
                    info > 0 ? "the QR algorithm did not converge" : "invalid argument");
  for (size_t i = 0; i < n && rc == FB_OK; ++i)
    ev[i] = (eigenvalue){wr[i], wi[i]};
  free(wr);
  return rc;
}

static int all_finite(const double *v, size_t n)
{
  for (size_t i = 0; i < n; ++i) {
    if (!isfinite(v[i]))
      return 0;
  }
  return 1;
}

/* Jacobian at the input's start time and initial state into jac (n x n). */
static int linearise(const cli_graph_input *in, fb_bd *bd, size_t n, double *jac, fb_err *err)
{
  const fb_sim_opts *opts = &in->opts;
  double *x0 = malloc(n * sizeof *x0);
  if (!x0)
    return fb_err_set(err, FB_ENOMEM, "eig: out of memory (%zu states)", n);
  if (opts->x0) {
    for (size_t i = 0; i < n; ++i)
      x0[i] = opts->x0[i];
  } else {
    fb_bd_initial_state(bd, x0);
  }
  int rc = fb_bd_jacobian_dense(bd, opts->t_start, x0, jac, err);
  free(x0);
  if (rc == FB_OK && !all_finite(jac, n * n))
    rc = fb_err_set(err, FB_ESOLVER, "eig: the Jacobian at t = %g s has non-finite entries",
                    opts->t_start);
  return rc;
}

/* The Frobenius norm of the n x n matrix a. */
static double frobenius(size_t n, const double *a)
{
  double sum = 0.0;
  for (size_t k = 0; k < n * n; ++k)
    sum += a[k] * a[k];
  return sqrt(sum);
}

/* Moves the eigenvalues with |lambda| <= zero_tol to the end of ev (the
 * order of the others kept); returns how many are left before them. A
 * backward-stable eigen-solver finds the eigenvalues of A + E with
 * ||E||_F about n eps ||A||_F (Golub & Van Loan, "Matrix Computations",
 * 4th ed., 2013, sec. 7.5.6): a zero eigenvalue comes out anywhere in
 * that radius, with any sign and a spurious imaginary part. */
static size_t drop_zeros(eigenvalue *ev, size_t n, double zero_tol)
{
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i)
    if (hypot(ev[i].re, ev[i].im) > zero_tol)
      ev[kept++] = ev[i];
  return kept;
}

static void print_table(const cli_graph_input *in, const fb_bd *bd, const eigenvalue *ev,
                        size_t n, double zero_tol)
{
  size_t npairs = 0;
  for (size_t i = 0; i < n; ++i)
    npairs += ev[i].im > 0;
  const size_t nzero = fb_bd_nstates(bd) - n;
  printf("%s: %zu states, %zu real eigenvalues, %zu complex pairs (at t = %g s, initial "
         "state)\n",
         in->name, fb_bd_nstates(bd), n - 2 * npairs, npairs, in->opts.t_start);
  if (nzero)
    printf("%zu zero eigenvalue%s (|lambda| <= %.3g = n eps ||A||_F: round-off) left out\n",
           nzero, nzero == 1 ? "" : "s", zero_tol);
  printf("%4s  %15s  %19s  %13s  %10s\n", "#", "real [1/s]", "imag [rad/s]", "f_n [Hz]",
         "zeta");
  size_t row = 0;
  for (size_t i = 0; i < n; ++i) {
    /* dgeev returns pairs as exact conjugates: print the upper member. */
    if (ev[i].im < 0)
      continue;
    printf("%4zu  %15.8g", ++row, ev[i].re);
    if (ev[i].im == 0) {
      printf("  %19s\n", "0");
      continue;
    }
    double modulus = hypot(ev[i].re, ev[i].im);
    printf("  +/- %15.8g  %13.6g  %10.4g\n", ev[i].im, modulus / TWO_PI, -ev[i].re / modulus);
  }
}

static int analyse(const cli_graph_input *in, fb_bd *bd, fb_err *err)
{
  size_t n = fb_bd_nstates(bd);
  if (n == 0) {
    printf("%s: no states, no eigenvalues\n", in->name);
    return cli_flush_stdout(err);
  }
  /* The Jacobian and the matrix dgeev overwrites. */
  int rc = fb_check_dense_eig(n, 2, FB_VEHICLE_MEMORY_LIMIT, err, "eig: %s (%zu states)",
                              in->name, n);
  if (rc)
    return rc;
  double *jac = malloc(n * n * sizeof *jac);
  eigenvalue *ev = malloc(n * sizeof *ev);
  if (!jac || !ev)
    rc = fb_err_set(err, FB_ENOMEM, "eig: out of memory (%zu states)", n);
  if (rc == FB_OK)
    rc = linearise(in, bd, n, jac, err);
  const double zero_tol = rc == FB_OK ? (double)n * DBL_EPSILON * frobenius(n, jac) : 0.0;
  if (rc == FB_OK)
    rc = eigenvalues(n, jac, ev, err);
  if (rc == FB_OK) {
    const size_t kept = drop_zeros(ev, n, zero_tol);
    qsort(ev, kept, sizeof *ev, compare_eigenvalues);
    print_table(in, bd, ev, kept, zero_tol);
    rc = cli_flush_stdout(err);
  }
  free(ev);
  free(jac);
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
