/* SPDX-License-Identifier: BSD-3-Clause */
/* fb_result_diff (flexbond/sim.h): the difference of two simulations of
 * a linear mass-spring-damper under two constant forces is, by
 * superposition, the closed-form step response to the difference of the
 * forces; mismatched results are refused with a message naming the
 * mismatch. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "flexbond/model.h"
#include "flexbond/sim.h"

#include "check.h"

/* m x'' + c x' + k x = F from rest: omega_n = 5 rad/s, zeta = 0.15. */
#define MASS 2.0
#define STIFF 50.0
#define DAMP 3.0

/* The model, with the force (N), a probe name, more probes, the end time
 * and the sample rate filled in. */
static const char model_format[] =
    "model: msd\n"
    "parameters: {m: 2, k: 50, c: 3}\n"
    "elements:\n"
    "  - {name: F, type: Se, value: %g}\n"
    "  - {name: v, type: 1}\n"
    "  - {name: M, type: I, m: m}\n"
    "  - {name: K, type: C, k: k}\n"
    "  - {name: D, type: R, r: c}\n"
    "bonds:\n"
    "  - [F, v]\n"
    "  - {name: b_mass, from: v, to: M}\n"
    "  - [v, K]\n"
    "  - [v, D]\n"
    "probes:\n"
    "  - {name: %s, state: K}\n"
    "  - {name: vel, flow: b_mass}\n"
    "%s"
    "simulation: {t_end: %g, sample_rate: %g, rtol: 1e-8, atol: 1e-12}\n";

/* Unit step response over the static deflection: g(t) = 1 - e^(-zeta wn
 * t) (cos wd t + zeta wn / wd sin wd t) (Ogata, "Modern Control
 * Engineering", 5th ed., sec. 5-3). */
static double step_shape(double t)
{
  const double wn = sqrt(STIFF / MASS), zeta = DAMP / (2 * sqrt(STIFF * MASS));
  const double wd = wn * sqrt(1 - zeta * zeta), a = zeta * wn;
  return 1 - exp(-a * t) * (cos(wd * t) + a / wd * sin(wd * t));
}

/* Simulates the model for force, probe name x_name, t_end and rate. */
static int simulate_more(double force, const char *x_name, const char *more_probes,
                         double t_end, double rate, fb_result **res)
{
  char text[2048];
  snprintf(text, sizeof text, model_format, force, x_name, more_probes, t_end, rate);
  fb_err err;
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  size_t np = 0;
  *res = NULL;
  int rc = fb_model_load_string(text, strlen(text), "msd.yaml", NULL, &m, &err);
  if (rc == FB_OK) {
    const fb_probe_spec *p = fb_model_probes(m, &np);
    rc = fb_bd_build(fb_model_graph(m), p, np, &bd, &err);
  }
  if (rc == FB_OK)
    rc = fb_sim_run(bd, fb_model_sim_opts(m), res, &err);
  if (rc != FB_OK)
    fprintf(stderr, "simulate: %s\n", err.msg);
  fb_bd_free(&bd);
  fb_model_free(&m);
  return rc;
}

static int simulate(double force, const char *x_name, double t_end, double rate,
                    fb_result **res)
{
  return simulate_more(force, x_name, "", t_end, rate, res);
}

/* (F = 10 N) - (F = 4 N) is the response to a 6 N step: x = 6/k g(t). */
static void test_superposition(void)
{
  fb_result *a = NULL, *b = NULL, *d = NULL;
  fb_err err;
  CHECK(simulate(4.0, "x", 3.0, 100.0, &a) == FB_OK);
  CHECK(simulate(10.0, "x", 3.0, 100.0, &b) == FB_OK);
  if (!a || !b)
    goto done;
  CHECK(fb_result_diff(b, a, &d, &err) == FB_OK);
  if (!d)
    goto done;
  CHECK(fb_result_nsamples(d) == 301);
  CHECK(fb_result_ncols(d) == 3);
  CHECK(strcmp(fb_result_col_name(d, 1), "x") == 0);
  CHECK(strcmp(fb_result_col_unit(d, 1), fb_result_col_unit(a, 1)) == 0);
  CHECK(fb_result_stats(d)->steps == 0);
  double worst = 0;
  for (size_t k = 0; k < fb_result_nsamples(d); ++k) {
    const double t = fb_result_row(d, k)[0];
    CHECK(t == fb_result_row(a, k)[0]);
    worst = fmax(worst, fabs(fb_result_row(d, k)[1] - 6.0 / STIFF * step_shape(t)));
  }
  /* Each run's global error stays below about 100 rtol of the static
   * deflection (test_sim.c measured ~12 rtol at these tolerances); the
   * difference carries both runs' errors: 2 x 100 x 1e-8 x 10/50 m. A
   * wrong sign or column would be off by ~0.1 m. */
  CHECK_NEAR(worst, 0, 2 * 100 * 1e-8 * 10.0 / STIFF);
done:
  fb_result_free(&d);
  fb_result_free(&b);
  fb_result_free(&a);
}

/* fb_result_diff(b, a) must fail with FB_EINVAL, a NULL result and a
 * message containing phrase. */
static void check_refused(const fb_result *b, const fb_result *a, const char *phrase)
{
  fb_result *d = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_result_diff(b, a, &d, &err) == FB_EINVAL);
  CHECK(d == NULL);
  CHECK(strstr(err.msg, phrase) != NULL);
  if (!strstr(err.msg, phrase))
    fprintf(stderr, "  message: %s\n", err.msg);
}

static void test_mismatches(void)
{
  fb_result *base = NULL, *wider = NULL, *renamed = NULL, *longer = NULL, *coarser = NULL;
  CHECK(simulate(4.0, "x", 1.0, 100.0, &base) == FB_OK);
  CHECK(simulate_more(4.0, "x", "  - {name: f_mass, effort: b_mass}\n", 1.0, 100.0, &wider) ==
        FB_OK);
  CHECK(simulate(4.0, "y", 1.0, 100.0, &renamed) == FB_OK);
  CHECK(simulate(4.0, "x", 2.0, 100.0, &longer) == FB_OK);
  /* 2 s at 50 Hz: as many samples (101) as 1 s at 100 Hz, other times. */
  CHECK(simulate(4.0, "x", 2.0, 50.0, &coarser) == FB_OK);
  if (base && wider && renamed && longer && coarser) {
    check_refused(wider, base, "4 columns minus 3 columns");
    check_refused(renamed, base, "column 1 is 'y' minus 'x'");
    check_refused(longer, base, "201 samples minus 101 samples");
    check_refused(coarser, base, "sample 1 is at t = 0.02 s minus 0.01 s");
  }
  fb_result_free(&coarser);
  fb_result_free(&longer);
  fb_result_free(&renamed);
  fb_result_free(&wider);
  fb_result_free(&base);
}

int main(void)
{
  test_superposition();
  test_mismatches();
  return check_report("test_result_diff");
}
