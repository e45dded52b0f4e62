/* SPDX-License-Identifier: BSD-3-Clause */
/* Time-series figures (src/io/plot.c) without gnuplot: the SI prefix of
 * an axis (fb_plot_si_scale) and the script of a focused panel, whose
 * y range fits its focus window and whose time outside it is shaded
 * and labelled. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/io.h"
#include "flexbond/model.h"
#include "flexbond/sim.h"

#include "check.h"
#include "io/plot_internal.h"

static void expect_scale(double max_abs, const char *unit, double scale, const char *want)
{
  char out[64];
  const double got = fb_plot_si_scale(max_abs, unit, out, sizeof out);
  const int ok = got == scale && !strcmp(out, want);
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  %g %s: got %g '%s', wanted %g '%s'\n", max_abs, unit, got, out, scale,
            want);
}

static void test_si_scale(void)
{
  expect_scale(1.2e-5, "rad", 1e6, "\xc2\xb5rad"); /* the torsion angle */
  expect_scale(14150, "N", 1e-3, "kN");
  expect_scale(0.05, "m", 1e3, "mm");
  expect_scale(999.9, "m", 1, "m");
  expect_scale(1000, "m", 1e-3, "km");
  expect_scale(1.6, "m/s^2", 1, "m/s^2");
  expect_scale(5e-3, "m/s^2", 1e3, "mm/s^2");
  expect_scale(2.5e4, "N m", 1e-3, "kN m");
  expect_scale(5e-12, "N", 1e9, "nN"); /* beyond nano: nano */
  expect_scale(2e15, "W", 1e-9, "GW");
  /* No prefix: a mass in kg, an already prefixed or dimensionless unit,
   * a compound one in parentheses, nothing to scale. */
  expect_scale(1e-5, "kg", 1, "kg");
  expect_scale(1e-5, "mm", 1, "mm");
  expect_scale(1e-5, "1", 1, "1");
  expect_scale(1e-5, "(m/s^2)/m", 1, "(m/s^2)/m");
  expect_scale(0, "N", 1, "N");
  expect_scale(NAN, "N", 1, "N");
  expect_scale(1e-5, NULL, 1, "");
}

/* A flow of 1 rad/s until t = 1 s, then 1e-5 sin(2 pi t): the early part
 * would set the scale; the focus from 1.005 s (between samples, past the
 * step's last sample of 1 at t = 1 s) must not let it. */
static const char model_text[] =
    "model: focus\n"
    "domain: rotation\n"
    "elements:\n"
    "  - {name: S, type: Sf, value: 'step(1 - t) + 1e-5 * sin(2 * pi * t)'}\n"
    "  - {name: J, type: 1}\n"
    "  - {name: D, type: R, r: 1}\n"
    "bonds: [{name: b, from: S, to: J}, [J, D]]\n"
    "probes: [{name: w, flow: b}]\n"
    "simulation: {t_end: 2, sample_rate: 100}\n";

static fb_result *simulate(void)
{
  fb_err err;
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  fb_result *r = NULL;
  size_t np = 0;
  int rc = fb_model_load_string(model_text, strlen(model_text), "focus.yaml", NULL, &m, &err);
  const fb_probe_spec *probes = rc ? NULL : fb_model_probes(m, &np);
  if (!rc)
    rc = fb_bd_build(fb_model_graph(m), probes, np, &bd, &err);
  if (!rc)
    rc = fb_sim_run(bd, fb_model_sim_opts(m), &r, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  %s\n", err.msg);
  fb_bd_free(&bd);
  fb_model_free(&m);
  return r;
}

/* The script of one panel of r's column 0 as a string (new). */
static char *script_of(const fb_plot_panel *p)
{
  char *text = NULL;
  size_t len = 0;
  FILE *fp = open_memstream(&text, &len);
  if (!fp)
    return NULL;
  fb_plot_opts o;
  fb_plot_opts_default(&o);
  fb_plot_panels_script(fp, p, 1, &o, 0.0, 2.0, "plot.png");
  fclose(fp);
  return text;
}

static void test_focus(void)
{
  fb_result *r = simulate();
  CHECK(r && fb_result_ncols(r) == 2);
  if (!r || fb_result_ncols(r) != 2) {
    fb_result_free(&r);
    return;
  }
  const fb_plot_series s = {.result = r, .col = 0, .legend = NULL};
  fb_plot_panel p = {.series = &s,
                     .nseries = 1,
                     .ylabel = "w",
                     .unit = "rad/s",
                     .focus_t0 = 1.005,
                     .focus_t1 = INFINITY,
                     .outside_label = "early"};
  char *text = script_of(&p);
  CHECK(text != NULL);
  double lo = 0, hi = 0;
  const char *yrange = text ? strstr(text, "set yrange [") : NULL;
  CHECK(yrange && sscanf(yrange, "set yrange [%lf:%lf]", &lo, &hi) == 2);
  /* The samples in [1.005, 2] s reach +-1e-5 rad/s (sin at 100 samples per
   * period: within 5e-4 of its peak), drawn in urad/s with 5 % of the
   * range as margin: +-11. */
  CHECK_NEAR(hi, 11.0, 0.02);
  CHECK_NEAR(lo, -11.0, 0.02);
  CHECK(text && strstr(text, "set ylabel 'w'.' ['.'\xc2\xb5rad/s'.']'\n"));
  CHECK(text && strstr(text, "set object 1 rect from 0, graph 0 to 1.005, graph 1 behind"));
  CHECK(text && strstr(text, "set label 1 'early'.', off scale' at 0.5025, graph 0.9"));
  /* The data are drawn in urad/s: the sample at t = 1.25 s, 1e-5 rad/s. */
  CHECK(text && strstr(text, "\n1.25 10\n"));
  free(text);

  /* Without a focus: the whole run sets the range (autoscale), rad/s
   * unprefixed for values of 1, nothing shaded. */
  p.focus_t0 = p.focus_t1 = 0;
  text = script_of(&p);
  CHECK(text && strstr(text, "set autoscale y") && !strstr(text, "set object 1"));
  CHECK(text && strstr(text, "set ylabel 'w'.' ['.'rad/s'.']'\n"));
  free(text);

  /* A focus whose outside stays in range: shaded, labelled, not "off scale". */
  p.focus_t0 = 0.0;
  p.focus_t1 = 1.5;
  text = script_of(&p);
  CHECK(text && strstr(text, "set object 2 rect from 1.5, graph 0 to 2, graph 1"));
  CHECK(text && strstr(text, "set label 2 'early' at 1.75") && !strstr(text, "off scale"));
  free(text);
  fb_result_free(&r);
}

int main(void)
{
  test_si_scale();
  test_focus();
  return check_report("test_plot");
}
