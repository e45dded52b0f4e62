/* SPDX-License-Identifier: BSD-3-Clause */
/* Frequency response (fb_descriptor_freq_response, the road inputs of
 * fb_vehicle_track_inputs) against independent answers:
 *   1. the quarter car of examples/quarter_car.yaml against its closed-form
 *      transmissibility (the 2-DOF harmonic equations solved by Cramer's
 *      rule), body displacement and acceleration, suspension deflection and
 *      tire force, 0.1 to 100 Hz;
 *   2. the same quarter car in the time domain: a sine road, simulated by
 *      flexbond's integrator to steady state, amplitude and phase fitted
 *      by least squares;
 *   3. System 1 of examples/apc6x6.yaml against a direct harmonic solve of
 *      the hand-derived equations of tests/apc_direct.h (M, K, C built by
 *      hand from the data sheet, the road at each tire with its wheel's
 *      delay), left and right tracks, at frequencies across the modes;
 *   4. linearisation (fb_bd_descriptor_at): of a linear diagram, the
 *      descriptor form itself; of the quarter car with a tabulated shock
 *      absorber at rest, the response to a small sine road in the time
 *      domain;
 *   5. the pencil's errors: a singular pencil named at its frequency. */
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/model.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "apc_direct.h"
#include "apc_harmonic.h"
#include "bgtest_util.h"
#include "check.h"

static const char *const quarter_car_path = "../examples/quarter_car.yaml";
static const char *const scenario_path = "../examples/apc6x6.yaml";

/* The quarter car's data (examples/quarter_car.yaml). */
static const double MS = 250, MU = 35, KS = 16000, CS = 1000, KT = 160000;

static size_t output_index(const fb_bd *bd, const char *name)
{
  size_t o = 0;
  while (o < fb_bd_noutputs(bd) && strcmp(fb_bd_output_name(bd, o), name) != 0)
    ++o;
  return o;
}

/* The road height e^{j omega t} as the quarter car's one input, the
 * road velocity j omega. */
static void unit_road(void *ctx, double omega, double *u)
{
  (void)ctx;
  u[0] = 0.0;
  u[1] = omega;
}

/* Body and wheel displacement per metre of road height: (-w^2 M + j w C
 * + K) z = (0, kt)^T, by Cramer's rule. */
static void quarter_car_exact(double omega, double complex *zs, double complex *zu)
{
  const double complex s = KS + I * omega * CS;
  const double complex a = -omega * omega * MS + s, b = -s;
  const double complex d = -omega * omega * MU + s + KT;
  const double complex det = a * d - b * b;
  *zs = -b * KT / det;
  *zu = a * KT / det;
}

static double complex h_at(const double *h, size_t k, size_t nrows, size_t row)
{
  return h[2 * (k * nrows + row)] + I * h[2 * (k * nrows + row) + 1];
}

/* |got - want| within tol of the largest of |want| and scale. */
static void check_complex(double complex got, double complex want, double scale, double tol,
                          const char *what, double f)
{
  const double err = cabs(got - want), ref = fmax(cabs(want), scale);
  ++check_count;
  if (!(err <= tol * ref)) {
    ++check_failures;
    fprintf(stderr, "%s at %g Hz: got %.10g%+.10gi, want %.10g%+.10gi (error %.3g of %.3g)\n",
            what, f, creal(got), cimag(got), creal(want), cimag(want), err / ref, tol);
  }
}

static int quarter_car(fb_model **m, fb_bd **bd, fb_descriptor **ds, fb_err *err)
{
  size_t np = 0;
  int rc = fb_model_load(quarter_car_path, m, err);
  const fb_probe_spec *p = rc ? NULL : fb_model_probes(*m, &np);
  if (!rc)
    rc = fb_bd_build(fb_model_graph(*m), p, np, bd, err);
  if (!rc)
    rc = fb_bd_descriptor(*bd, ds, err);
  return rc;
}

static void test_quarter_car_closed_form(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  fb_descriptor *ds = NULL;
  MUST(quarter_car(&m, &bd, &ds, &err), &err);
  enum { NF = 61 };
  double f[NF], *h = ds ? malloc(2 * NF * ds->nrows_c * sizeof *h) : NULL;
  for (int k = 0; k < NF; ++k)
    f[k] = 0.1 * pow(1000.0, k / (NF - 1.0));
  if (h)
    MUST(fb_descriptor_freq_response(ds, f, NF, 1, unit_road, NULL, h, &err), &err);
  const size_t x = output_index(bd, "x_body"), a = output_index(bd, "a_body");
  const size_t q = output_index(bd, "deflection"), t = output_index(bd, "tire_force");
  CHECK(h && x < ds->noutputs && a < ds->noutputs && q < ds->noutputs && t < ds->noutputs);
  /* The descriptor's solve and Cramer's rule differ by round-off in a
   * matrix of condition ~1e6 (kt / (mu w^2) spans 1e-2 .. 1e4): 2e-13
   * observed, 1e-11 allowed. */
  for (int k = 0; h && k < NF; ++k) {
    const double w = 2.0 * 3.14159265358979323846 * f[k];
    double complex zs, zu;
    quarter_car_exact(w, &zs, &zu);
    const size_t n = ds->nrows_c;
    check_complex(h_at(h, (size_t)k, n, ds->output_row[x]), zs, 1e-12, 1e-11, "x_body", f[k]);
    check_complex(h_at(h, (size_t)k, n, ds->output_row[a]), -w * w * zs, 1e-9, 1e-11, "a_body",
                  f[k]);
    check_complex(h_at(h, (size_t)k, n, ds->output_row[q]), zu - zs, 1e-12, 1e-11, "deflection",
                  f[k]);
    check_complex(h_at(h, (size_t)k, n, ds->output_row[t]), KT * (1.0 - zu), 1e-6, 1e-11,
                  "tire_force", f[k]);
  }
  /* The body's transmissibility peaks near its natural frequency
   * sqrt(ks kt / (ks + kt) / ms) / 2 pi = 1.20 Hz at 1.5 or more. */
  double big = 0.0, at = 0.0;
  for (int k = 0; h && k < NF; ++k)
    if (cabs(h_at(h, (size_t)k, ds->nrows_c, ds->output_row[x])) > big) {
      big = cabs(h_at(h, (size_t)k, ds->nrows_c, ds->output_row[x]));
      at = f[k];
    }
  CHECK(big > 1.5 && at > 1.0 && at < 1.5);
  free(h);
  fb_descriptor_free(&ds);
  fb_bd_free(&bd);
  fb_model_free(&m);
}

/* ---- The time domain. */

/* The quarter car on a road h(t) = h0 sin(w t) from t = 0; printf
 * arguments: h0, then the damper's law. */
static const char sine_model[] =
    "model: quarter_car_sine\n"
    "parameters: {ms: 250, mu: 35, ks: 16000, cs: 1000, kt: 160000, g: 9.81, h0: %.17g,\n"
    "             w: 9.42477796076938}\n"
    "elements:\n"
    "  - {name: Ms, type: I, m: ms}\n"
    "  - {name: Mu, type: I, m: mu}\n"
    "  - {name: Ks, type: C, k: ks, initial: ms * g / ks}\n"
    "  - {name: Cs, type: R, %s}\n"
    "  - {name: Kt, type: C, k: kt, initial: (ms + mu) * g / kt}\n"
    "  - {name: grav_body, type: Se, value: -ms * g}\n"
    "  - {name: grav_wheel, type: Se, value: -mu * g}\n"
    "  - {name: road, type: Sf, value: h0 * w * cos(w * t)}\n"
    "  - {name: body, type: 1}\n"
    "  - {name: wheel, type: 1}\n"
    "  - {name: susp, type: 0}\n"
    "  - {name: defl, type: 1}\n"
    "  - {name: tire, type: 0}\n"
    "bonds:\n"
    "  - {name: b_body, from: body, to: Ms}\n"
    "  - {name: b_wheel, from: wheel, to: Mu}\n"
    "  - [grav_body, body]\n"
    "  - [grav_wheel, wheel]\n"
    "  - [wheel, susp]\n"
    "  - [susp, body]\n"
    "  - [susp, defl]\n"
    "  - {name: b_spring, from: defl, to: Ks}\n"
    "  - {name: b_damper, from: defl, to: Cs}\n"
    "  - [road, tire]\n"
    "  - [tire, wheel]\n"
    "  - {name: b_tire, from: tire, to: Kt}\n"
    "probes:\n"
    "  - {name: a_body, effort: b_body, gain: 1 / ms, unit: m/s^2}\n"
    "  - {name: tire_force, effort: b_tire}\n";

/* Least-squares fit of y = a sin(w t) + b cos(w t) + c to the samples of
 * column col from row k0 on; returns a + j b, the complex amplitude of
 * Im(A e^{j w t}). */
static double complex fit_sine(const fb_result *r, size_t col, size_t k0, double w)
{
  double ata[9] = {0}, aty[3] = {0};
  for (size_t k = k0; k < fb_result_nsamples(r); ++k) {
    const double *row = fb_result_row(r, k);
    const double basis[3] = {sin(w * row[0]), cos(w * row[0]), 1.0};
    for (int i = 0; i < 3; ++i) {
      aty[i] += basis[i] * row[col];
      for (int j = 0; j < 3; ++j)
        ata[3 * i + j] += basis[i] * basis[j];
    }
  }
  lapack_int ipiv[3];
  if (LAPACKE_dgesv(LAPACK_ROW_MAJOR, 3, 1, ata, 3, ipiv, aty, 1) != 0)
    return NAN;
  return aty[0] + I * aty[1];
}

/* The quarter car of sine_model with road amplitude h0 and damper law,
 * simulated over 23 s; its descriptor form, linearised at rest when
 * linearise is 1. */
static int sine_run(double h0, const char *law, int linearise, fb_model **m, fb_bd **bd,
                    fb_descriptor **ds, fb_result **r, fb_err *err)
{
  char text[sizeof sine_model + 256];
  snprintf(text, sizeof text, sine_model, h0, law);
  size_t np = 0;
  int rc = fb_model_load_string(text, strlen(text), "sine.yaml", NULL, m, err);
  const fb_probe_spec *p = rc ? NULL : fb_model_probes(*m, &np);
  if (!rc)
    rc = fb_bd_build(fb_model_graph(*m), p, np, bd, err);
  if (!rc && linearise) {
    /* The springs start at their static compressions: at rest. */
    double x0[8];
    fb_bd_initial_state(*bd, x0);
    rc = fb_bd_nstates(*bd) <= 8 ? fb_bd_descriptor_at(*bd, 0.0, x0, ds, err) : FB_EINVAL;
  } else if (!rc) {
    rc = fb_bd_descriptor(*bd, ds, err);
  }
  /* 1.5 Hz, above the body's resonance. The slowest transient, the body
   * mode (damping ratio about 0.25 at 7.5 rad/s), has decayed by e^-40
   * after 20 s; the fit takes the last 4.5 periods. */
  fb_sim_opts opts;
  fb_sim_opts_default(&opts);
  opts.t_end = 23.0;
  opts.rtol = 1e-10;
  opts.atol = 1e-12 * h0 / 0.01;
  opts.sample_rate = 200.0;
  if (!rc)
    rc = fb_sim_run(*bd, &opts, r, err);
  return rc;
}

/* Complex amplitude per metre of road of output name: from the time
 * domain (fitted) into *time, from the frequency response into *freq. */
static int sine_amplitudes(const fb_bd *bd, const fb_descriptor *ds, const fb_result *r,
                           double h0, const char *name, double complex *time,
                           double complex *freq, fb_err *err)
{
  const double w = 9.42477796076938, f = w / (2.0 * 3.14159265358979323846);
  double h[2 * 8];
  const size_t o = output_index(bd, name);
  const long col = fb_result_find(r, name);
  if (o >= ds->noutputs || col <= 0 || ds->nrows_c > 8)
    return FB_EINVAL;
  const int rc = fb_descriptor_freq_response(ds, &f, 1, 1, unit_road, NULL, h, err);
  *time = fit_sine(r, (size_t)col, 20 * 200, w) / h0;
  *freq = h_at(h, 0, ds->nrows_c, ds->output_row[o]);
  return rc;
}

static void test_quarter_car_time_domain(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  fb_descriptor *ds = NULL;
  fb_result *r = NULL;
  const double h0 = 0.01, f = 9.42477796076938 / (2.0 * 3.14159265358979323846);
  MUST(sine_run(h0, "r: cs", 0, &m, &bd, &ds, &r, &err), &err);
  const char *names[2] = {"a_body", "tire_force"};
  for (int i = 0; r && i < 2; ++i) {
    double complex got = 0, want = 0;
    MUST(sine_amplitudes(bd, ds, r, h0, names[i], &got, &want, &err), &err);
    /* The complex amplitude to 1e-7 (1.1e-9 observed): the integration's
     * error at rtol 1e-10, what is left of the transient (e^-40) and the
     * fit over samples, not a continuous record. */
    check_complex(got, want, 0.0, 1e-7, names[i], f);
    fprintf(stderr,
            "sine road at %.4g Hz, %s: |H| %.8g from the time domain, %.8g from the "
            "frequency response; phase %.6f and %.6f deg\n",
            f, names[i], cabs(got), cabs(want), carg(got) * 180 / 3.14159265358979323846,
            carg(want) * 180 / 3.14159265358979323846);
  }
  fb_result_free(&r);
  fb_descriptor_free(&ds);
  fb_bd_free(&bd);
  fb_model_free(&m);
}

/* fb_bd_descriptor_at of a linear diagram is its descriptor form, with
 * no constant term. */
static void test_linearise_linear(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  fb_descriptor *ds = NULL, *lin = NULL;
  MUST(quarter_car(&m, &bd, &ds, &err), &err);
  double x[8] = {30.0, -4.0, 0.12, 0.02, 0.3, 0.0, 0.0, 0.0};
  if (ds && fb_bd_nstates(bd) <= 8)
    MUST(fb_bd_descriptor_at(bd, 0.55, x, &lin, &err), &err);
  CHECK(lin && lin->linearised && !ds->linearised);
  if (lin) {
    CHECK(lin->n == ds->n && lin->ninputs == ds->ninputs && lin->nrows_c == ds->nrows_c);
    const fb_mat *a[4] = {ds->E, ds->A, ds->B, ds->C}, *b[4] = {lin->E, lin->A, lin->B, lin->C};
    for (int k = 0; k < 4; ++k) {
      CHECK(fb_mat_nnz(a[k]) == fb_mat_nnz(b[k]));
      for (size_t i = 0; i < fb_mat_nrows(a[k]); ++i)
        for (size_t j = 0; j < fb_mat_ncols(a[k]); ++j)
          if (fb_mat_get(a[k], i, j) != fb_mat_get(b[k], i, j))
            CHECK(!"linearised entry differs");
    }
    CHECK(fb_mat_nnz(lin->f) == 0 && fb_mat_nnz(ds->f) > 0);
  }
  fb_descriptor_free(&lin);
  fb_descriptor_free(&ds);
  fb_bd_free(&bd);
  fb_model_free(&m);
}

/* A tabulated shock absorber, stiffer in compression than in rebound:
 * refused by the descriptor form, linearised at rest by
 * fb_bd_descriptor_at, and the linearisation is the small-signal
 * response: a 0.1 mm sine road in the time domain. */
/* Relative gap between the small-signal response in time (a sine road of
 * amplitude h0) and the linearisation, for output name; -1 on an error. */
static double table_gap(const char *law, double h0, const char *name)
{
  fb_err err;
  fb_err_clear(&err);
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  fb_descriptor *ds = NULL;
  fb_result *r = NULL;
  double gap = -1.0;
  MUST(sine_run(h0, law, 1, &m, &bd, &ds, &r, &err), &err);
  fb_descriptor *refused = NULL;
  CHECK(bd && fb_bd_descriptor(bd, &refused, &err) == FB_EINVAL && !refused);
  double complex got = 0, want = 0;
  if (r && sine_amplitudes(bd, ds, r, h0, name, &got, &want, &err) == FB_OK)
    gap = cabs(got - want) / cabs(want);
  fprintf(stderr,
          "tabulated damper, %g m sine road, %s: |H| %.8g in time, %.8g linearised "
          "(%.2g apart)\n",
          h0, name, cabs(got), cabs(want), gap);
  fb_result_free(&r);
  fb_descriptor_free(&ds);
  fb_bd_free(&bd);
  fb_model_free(&m);
  return gap;
}

/* A tabulated shock absorber, stiffer in compression than in rebound:
 * refused by the descriptor form, linearised at rest by
 * fb_bd_descriptor_at, and the linearisation is the small-signal
 * response: the gap to a sine road in the time domain is the table's
 * curvature, proportional to the amplitude (0.9e-3 at 0.1 mm, 0.9e-4 at
 * 0.01 mm), which a wrong slope would not be. */
static void test_linearise_table(void)
{
  static const char law[] = "table: {points: [[-1, -600], [0, 0], [0.5, 700], [1, 1200]]}";
  const char *names[2] = {"a_body", "tire_force"};
  for (int i = 0; i < 2; ++i) {
    const double big = table_gap(law, 1e-4, names[i]), small = table_gap(law, 1e-5, names[i]);
    CHECK(big > 0 && big < 2e-3);
    CHECK(small > 0 && small < 0.15 * big);
  }
}

/* ---- System 1 against the hand-derived equations. */

typedef struct sys1 {
  const fb_scenario *s;
  size_t rate_input[APC_NCORNERS];
} sys1;

static void sys1_input(void *ctx, double omega, double *u)
{
  const sys1 *c = ctx;
  fb_vehicle_track_inputs(c->s, c->rate_input, omega, u);
}

static void compare_system1(const fb_scenario *s, const fb_descriptor *ds, const apc_model *m,
                            double f, const double *h)
{
  const double w = 2.0 * 3.14159265358979323846 * f;
  for (int track = 0; track < 2; ++track) {
    double complex want[APC_NOUTPUTS] = {0};
    CHECK(apc_harmonic_outputs(m, s, w, track, want) == 0);
    const apc_elem *tire = &m->elem[APC_TIRE + APC_LF];
    /* Scales: a tire's force per metre is some kt = 1e6 N/m, a deflection
     * some 1 m/m, the driver's acceleration w^2 m/m. */
    const double scale[APC_NOUTPUTS] = {[APC_OUT_TIRE_FORCE_LF] = tire->k,
                                        [APC_OUT_SPRING_DEFL_RF] = 1.0,
                                        [APC_OUT_DRIVER_ACC] = w * w,
                                        [APC_OUT_TIRE_DEFL_RM] = 1.0};
    const int outs[4] = {APC_OUT_TIRE_FORCE_LF, APC_OUT_SPRING_DEFL_RF, APC_OUT_DRIVER_ACC,
                         APC_OUT_TIRE_DEFL_RM};
    for (int i = 0; i < 4; ++i) {
      const int o = outs[i];
      const double *z = h + 2 * ((size_t)track * ds->nrows_c + ds->output_row[o]);
      char what[64];
      snprintf(what, sizeof what, "System 1 %s, %s track", apc_output_name(o),
               track ? "right" : "left");
      /* Two exact solves of systems of condition up to ~1e8 (wheel and
       * hull masses against tire stiffness): 1.7e-13 of the scale
       * observed, 1e-10 allowed. */
      check_complex(z[0] + I * z[1], want[o], 1e-3 * scale[o], 1e-10, what, f);
    }
    /* The rigid hull does not twist. */
    const double *z = h + 2 * ((size_t)track * ds->nrows_c + ds->output_row[APC_OUT_TORSION]);
    CHECK(z[0] == 0.0 && z[1] == 0.0);
  }
}

static void test_system1(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  fb_bg *graph = NULL;
  fb_bd *bd = NULL;
  fb_descriptor *ds = NULL;
  MUST(fb_scenario_load(scenario_path, &s, &err), &err);
  CHECK(s && apc_layout_ok(s));
  if (!s || !apc_layout_ok(s)) {
    fb_scenario_free(&s);
    return;
  }
  apc_model m;
  CHECK(apc_model_init(&m, s) == 0);
  MUST(fb_vehicle_build(s, FB_SYSTEM_RIGID, &graph, &bd, &err), &err);
  if (bd)
    MUST(fb_bd_descriptor(bd, &ds, &err), &err);
  sys1 ctx = {s, {0}};
  if (ds)
    MUST(fb_vehicle_rate_inputs(s, ds, ctx.rate_input, &err), &err);
  /* Below, at and between the modes: pitch 1.4, bounce 3.2, wheel hop
   * 9.7-12.8 Hz, and far above. */
  const double freq[] = {0.1, 0.7, 1.4, 2.2, 3.18, 6.0, 9.7, 12.7, 30.0, 100.0};
  const size_t nf = sizeof freq / sizeof freq[0];
  double *h = ds ? malloc(2 * 2 * ds->nrows_c * nf * sizeof *h) : NULL;
  if (h)
    MUST(fb_descriptor_freq_response(ds, freq, nf, 2, sys1_input, &ctx, h, &err), &err);
  for (size_t k = 0; h && k < nf; ++k)
    compare_system1(s, ds, &m, freq[k], h + 2 * 2 * ds->nrows_c * k);
  free(h);
  fb_descriptor_free(&ds);
  fb_bd_free(&bd);
  fb_bg_free(&graph);
  fb_scenario_free(&s);
}

/* ---- Errors. */

static void test_singular(void)
{
  fb_err err;
  fb_err_clear(&err);
  /* x' = 0 x: j w - 0 is singular at w = 0 only. */
  const size_t r[1] = {0}, c[1] = {0};
  const double one[1] = {1.0};
  fb_mat *E = NULL, *A = NULL;
  fb_pencil *p = NULL;
  MUST(fb_mat_new_triplets(1, 1, 1, r, c, one, &E, &err), &err);
  MUST(fb_mat_new_triplets(1, 1, 0, NULL, NULL, NULL, &A, &err), &err);
  MUST(fb_pencil_new(E, A, &p, &err), &err);
  if (p) {
    CHECK(fb_pencil_factor(p, 0.0, &err) == FB_ESOLVER);
    CHECK(strstr(err.msg, "singular at omega = 0") != NULL);
    MUST(fb_pencil_factor(p, 2.0, &err), &err);
    double b[2] = {1.0, 0.0}; /* 1 / (2j) = -0.5j */
    MUST(fb_pencil_solve(p, b, 1, &err), &err);
    CHECK_NEAR(b[0], 0.0, 1e-15);
    CHECK_NEAR(b[1], -0.5, 1e-15);
    CHECK(fb_pencil_factor(p, -1.0, &err) == FB_EINVAL);
  }
  fb_mat *wide = NULL;
  MUST(fb_mat_new_triplets(1, 2, 0, NULL, NULL, NULL, &wide, &err), &err);
  fb_pencil *q = NULL;
  CHECK(fb_pencil_new(E, wide, &q, &err) == FB_EINVAL && q == NULL);
  fb_pencil_free(&p);
  fb_mat_free(&wide);
  fb_mat_free(&E);
  fb_mat_free(&A);
}

int main(void)
{
  test_quarter_car_closed_form();
  test_quarter_car_time_domain();
  test_linearise_linear();
  test_linearise_table();
  test_system1();
  test_singular();
  return check_report("test_freq");
}
