/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal: simulation results and the output sample grid. */
#ifndef FLEXBOND_SIM_INTERNAL_H
#define FLEXBOND_SIM_INTERNAL_H

#include <stddef.h>

#include "flexbond/sim.h"

#include "core/util.h"

struct fb_result {
  size_t nsamples, ncols;
  double *data; /* nsamples x ncols, row-major */
  char **names; /* ncols column names (owned copies) */
  char **units; /* ncols units (owned copies) */
  fb_sim_stats stats;
};

/* Allocates a result for nsamples rows with column 0 "t" [s] and one
 * column per output of bd (names and units copied). */
int fb_result_alloc(const fb_bd *bd, size_t nsamples, fb_result **out, fb_err *err);

/* Output times t_k = t_start + k / rate, k = 0 .. n - 1. When
 * (t_end - t_start) rate is an integer up to a relative 1e-9, the last
 * sample is t_end exactly; otherwise it is the last t_k <= t_end. */
typedef struct fb_sample_grid {
  double t_start, t_end, rate;
  size_t n;
  int last_is_end;
} fb_sample_grid;

/* opts must have passed fb_sim_opts_check. */
void fb_sample_grid_init(fb_sample_grid *g, const fb_sim_opts *opts);
double fb_sample_grid_time(const fb_sample_grid *g, size_t k);

/* Two times closer than this are one (100 roundoffs of the larger):
 * breakpoints that close to each other or to the ends of the run are
 * merged, and a run must be longer (fb_sim_opts_check). */
double fb_sim_same_time_tol(double a, double b);

/* ---- Non-finite values (nonfinite.c). */

/* fb_first_nonfinite and fb_printable: core/util.h. */

/* Room for one description of a non-finite value. */
#define FB_SIM_NONFINITE_MAX 1024

/* buf = "<what>; the non-finite value starts at <where>; hint: <hint>",
 * where what says what was not finite ("the derivative of state Ms.p is
 * nan"), where is fb_bd_explain_nonfinite(bd, t, x, jacobian) and hint
 * suits what it found. Re-evaluates the diagram. Returns the kind. */
fb_bd_nonfinite_kind fb_sim_explain_nonfinite(fb_bd *bd, double t, const double *x,
                                              int jacobian, const char *what, char *buf,
                                              size_t size);

#endif
