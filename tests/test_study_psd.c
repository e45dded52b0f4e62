/* SPDX-License-Identifier: BSD-3-Clause */
/* The study layer's frequency response (fb_study_freq) and ride from a
 * road spectrum (fb_study_ride_psd) against independent answers, on
 * System 1 of examples/apc6x6.yaml driven at 30 km/h:
 *   1. the response at frequencies across the modes against the direct
 *      harmonic solve of the hand-derived equations (tests/apc_harmonic.h:
 *      M, K, C from the data sheet, no descriptor form), through the
 *      study's accessors: every output and track where it belongs, powers
 *      without a response, the peak where the largest |H| is;
 *   2. the ride on an ISO 8608 class C road, independent and identical
 *      tracks: each output's r.m.s. and the driver's a_w against the
 *      integral of |H|^2 G over the band from the hand model's H, the
 *      road's PSD in ISO 8608's closed form, and Simpson's rule in ln f on
 *      a grid seven times finer than the study's;
 *   3. the road a ride is on: a class named, the scenario's own ISO 8608
 *      road, none, and a class outside A .. H refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/ride.h"
#include "flexbond/road.h"
#include "flexbond/study.h"
#include "flexbond/vehicle.h"

#include "apc_harmonic.h"
#include "bgtest_util.h"
#include "check.h"
#include "road_util.h"

static const char *const scenario_path = "../examples/apc6x6.yaml";
static const char *const iso_road_path = "../examples/apc6x6_iso_road.yaml";

static const double PI = 3.14159265358979323846;
/* 30 km/h: the band 0.011 .. 2.83 cycles/m then spans 0.09 .. 23.6 Hz,
 * over the pitch (1.4 Hz), bounce (3.2 Hz) and wheel hop (9.7 .. 12.8
 * Hz) modes. */
static const double SPEED = 30.0 / 3.6;
/* ISO 8608:2016, Table 3: class C's geometric mean Gd(n0) at n0 = 0.1
 * cycles/m, and the spatial PSD Gd(n) = Gd(n0) (n / n0)^-2. */
static const double GD0_C = 256e-6, N0 = 0.1;

/* The outputs with a response (apc_layout.h), and the scale of their |H|
 * for the comparisons: a tire's force per metre some kt = 1e6 N/m, a
 * deflection some 1 m/m, the driver's acceleration omega^2 m/m. */
static const int responding[] = {APC_OUT_TIRE_FORCE_LF, APC_OUT_SPRING_DEFL_RF,
                                 APC_OUT_DRIVER_ACC, APC_OUT_TIRE_DEFL_RM};
enum { NRESPONDING = sizeof responding / sizeof responding[0] };

typedef struct fixture {
  fb_scenario *s;
  apc_model m;
  fb_vehicle *v;
} fixture;

static int fixture_open(fixture *fx, fb_err *err)
{
  memset(fx, 0, sizeof *fx);
  int rc = fb_scenario_load(scenario_path, &fx->s, err);
  if (rc)
    return rc;
  fx->s->speed = SPEED;
  if (!apc_layout_ok(fx->s) || apc_model_init(&fx->m, fx->s) != 0)
    return fb_err_set(err, FB_EINVAL, "%s: not the reference vehicle", scenario_path);
  return fb_vehicle_new(fx->s, FB_SYSTEM_RIGID, NULL, &fx->v, err);
}

static void fixture_close(fixture *fx)
{
  fb_vehicle_free(&fx->v);
  fb_scenario_free(&fx->s);
}

/* ---- 1. The response through the study's accessors. */

static void check_frequency(const fixture *fx, const fb_study_freq *f, size_t k)
{
  const double w = 2.0 * PI * fb_study_freq_hz(f)[k];
  const double scale[APC_NOUTPUTS] = {[APC_OUT_TIRE_FORCE_LF] = 1e6,
                                      [APC_OUT_SPRING_DEFL_RF] = 1.0,
                                      [APC_OUT_DRIVER_ACC] = w * w,
                                      [APC_OUT_TIRE_DEFL_RM] = 1.0};
  for (int t = 0; t < FB_ROAD_NTRACKS; ++t) {
    double complex want[APC_NOUTPUTS] = {0};
    CHECK(apc_harmonic_outputs(&fx->m, fx->s, w, t, want) == 0);
    for (int i = 0; i < NRESPONDING; ++i) {
      const int o = responding[i];
      const double *z = fb_study_freq_at(f, (size_t)o, t, k);
      CHECK(z != NULL);
      /* Two exact solves (test_freq.c: 1.7e-13 of the scale observed). */
      if (z && cabs(z[0] + I * z[1] - want[o]) > 1e-10 * scale[o]) {
        fprintf(stderr, "%s, track %d, %g Hz: (%g, %g) against (%g, %g)\n", apc_output_name(o),
                t, w / (2 * PI), z[0], z[1], creal(want[o]), cimag(want[o]));
        CHECK(0);
      }
    }
    const double *torsion = fb_study_freq_at(f, APC_OUT_TORSION, t, k);
    CHECK(torsion && torsion[0] == 0.0 && torsion[1] == 0.0);
  }
}

static void test_freq(void)
{
  fb_err err;
  fb_err_clear(&err);
  fixture fx;
  MUST(fixture_open(&fx, &err), &err);
  const double freq[] = {0.1, 0.7, 1.4, 2.2, 3.18, 6.0, 9.7, 12.7, 30.0, 100.0};
  const size_t nf = sizeof freq / sizeof freq[0];
  fb_study_freq *f = NULL;
  if (fx.v)
    MUST(fb_study_freq_new(fx.v, freq, nf, &f, &err), &err);
  if (f) {
    CHECK(fb_study_freq_nfreq(f) == nf && fb_study_freq_scenario(f) == fx.s);
    CHECK(!fb_study_freq_linearised(f));
    for (size_t k = 0; k < nf; ++k)
      check_frequency(&fx, f, k);
    /* Powers have none; indices out of range neither. */
    CHECK(!fb_study_freq_has_output(f, APC_OUT_SHOCK_POWER_LM));
    CHECK(fb_study_freq_at(f, APC_OUT_TIRE_POWER_LR, 0, 0) == NULL);
    CHECK(isnan(fb_study_freq_peak(f, APC_OUT_SHOCK_POWER_LM, NULL, NULL)));
    CHECK(fb_study_freq_at(f, APC_OUT_DRIVER_ACC, 2, 0) == NULL);
    CHECK(fb_study_freq_at(f, APC_OUT_DRIVER_ACC, 0, nf) == NULL);
    CHECK(fb_study_freq_at(f, APC_NOUT, 0, 0) == NULL);
    /* The peak is the largest |H| of the table, where it is. */
    size_t kmax = nf;
    int tmax = -1;
    const double peak = fb_study_freq_peak(f, APC_OUT_DRIVER_ACC, &kmax, &tmax);
    CHECK(kmax < nf && (tmax == 0 || tmax == 1));
    for (size_t k = 0; kmax < nf && k < nf; ++k)
      for (int t = 0; t < FB_ROAD_NTRACKS; ++t) {
        const double *z = fb_study_freq_at(f, APC_OUT_DRIVER_ACC, t, k);
        CHECK(hypot(z[0], z[1]) <= peak);
      }
    if (kmax < nf) {
      const double *z = fb_study_freq_at(f, APC_OUT_DRIVER_ACC, tmax, kmax);
      CHECK(hypot(z[0], z[1]) == peak);
    }
  }
  fb_study_freq_free(&f);
  CHECK(f == NULL);
  fixture_close(&fx);
}

/* ---- 2. The ride against the integral of |H|^2 G. */

/* Reference grid: Simpson's rule in u = ln f needs an even number of
 * intervals; 4200 is seven times the study's 600 points. */
enum { NREF = 4201 };

typedef struct reference {
  double ms[APC_NOUTPUTS]; /* mean squares over the band */
  double aw2;              /* the driver's Wk-weighted mean square */
} reference;

/* The integrand's values at one frequency: each output's PSD (and the
 * weighted driver's) times f, as d f = f d(ln f). */
static void psd_times_f(const fixture *fx, double f, int identical, double *y, double *yw)
{
  const double w = 2.0 * PI * f;
  /* The temporal PSD of a road driven at speed v: G(f) = Gd(f / v) / v. */
  const double road = GD0_C * pow(f / SPEED / N0, -2.0) / SPEED;
  double complex h[FB_ROAD_NTRACKS][APC_NOUTPUTS] = {{0}};
  for (int t = 0; t < FB_ROAD_NTRACKS; ++t)
    CHECK(apc_harmonic_outputs(&fx->m, fx->s, w, t, h[t]) == 0);
  for (int i = 0; i < NRESPONDING; ++i) {
    const int o = responding[i];
    /* Independent tracks add powers, identical ones amplitudes. */
    const double gain2 = identical ? pow(cabs(h[0][o] + h[1][o]), 2)
                                   : pow(cabs(h[0][o]), 2) + pow(cabs(h[1][o]), 2);
    y[o] = gain2 * road * f;
  }
  const double wk = fb_ride_wk_magnitude(f);
  *yw = wk * wk * y[APC_OUT_DRIVER_ACC];
}

static reference integrate(const fixture *fx, double n_min, double n_max, int identical)
{
  reference r;
  memset(&r, 0, sizeof r);
  const double u0 = log(SPEED * n_min), u1 = log(SPEED * n_max), du = (u1 - u0) / (NREF - 1);
  for (int k = 0; k < NREF; ++k) {
    const double c = (k == 0 || k == NREF - 1) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    double y[APC_NOUTPUTS] = {0}, yw = 0.0;
    psd_times_f(fx, exp(u0 + k * du), identical, y, &yw);
    for (int o = 0; o < APC_NOUTPUTS; ++o)
      r.ms[o] += c * y[o] * du / 3.0;
    r.aw2 += c * yw * du / 3.0;
  }
  return r;
}

/* The study's trapezoidal rule on 600 points against Simpson's on 4201:
 * 5e-8 (the deflections) to 1.8e-5 (the driver's acceleration, whose PSD
 * rises to the wheel hop at the band's top) relative in the r.m.s.
 * observed; 2e-4 allowed. */
static const double RMS_TOL = 2e-4;

static void check_ride(const fb_study_ride_psd *r, const reference *ref, const char *tracks)
{
  for (int i = 0; i < NRESPONDING; ++i) {
    const int o = responding[i];
    const double got = fb_study_ride_psd_rms(r, (size_t)o), want = sqrt(ref->ms[o]);
    printf("%s tracks: %-14s r.m.s. %.6g, reference %.6g (%.2g relative)\n", tracks,
           apc_output_name(o), got, want, fabs(got / want - 1.0));
    CHECK(fabs(got / want - 1.0) < RMS_TOL);
  }
  const double aw = fb_study_ride_psd_a_w(r), aw_ref = sqrt(ref->aw2);
  printf("%s tracks: a_w %.6g m/s^2, reference %.6g (%.2g relative)\n", tracks, aw, aw_ref,
         fabs(aw / aw_ref - 1.0));
  CHECK(fabs(aw / aw_ref - 1.0) < RMS_TOL);
  CHECK(fb_study_ride_psd_a_w_output(r) == APC_OUT_DRIVER_ACC);
  CHECK(fb_study_ride_psd_output(r, APC_OUT_SHOCK_POWER_LM) == NULL);
  CHECK(isnan(fb_study_ride_psd_rms(r, APC_OUT_TIRE_POWER_LR)));
}

static void check_band(const fb_study_ride_psd *r, const fb_road_iso8608_params *iso)
{
  const size_t n = fb_study_ride_psd_nfreq(r);
  const double *f = fb_study_ride_psd_hz(r), *road = fb_study_ride_psd_road_psd(r);
  CHECK(n == FB_STUDY_RIDE_PSD_POINTS);
  CHECK_NEAR(f[0], SPEED * iso->n_min, 1e-12 * f[0]);
  CHECK_NEAR(f[n - 1], SPEED * iso->n_max, 1e-12 * f[n - 1]);
  const double want = GD0_C * pow(f[n / 2] / SPEED / N0, -2.0) / SPEED;
  CHECK_NEAR(road[n / 2], want, 1e-12 * want);
  /* The weighted PSD is the driver's times |Wk|^2. */
  const double wk = fb_ride_wk_magnitude(f[n / 2]);
  CHECK_NEAR(fb_study_ride_psd_weighted(r)[n / 2],
             wk * wk * fb_study_ride_psd_output(r, APC_OUT_DRIVER_ACC)[n / 2],
             1e-12 * fb_study_ride_psd_weighted(r)[n / 2]);
}

static void test_ride(void)
{
  fb_err err;
  fb_err_clear(&err);
  fixture fx;
  MUST(fixture_open(&fx, &err), &err);
  fb_study_freq *lin = NULL;
  if (fx.v)
    MUST(fb_study_freq_new(fx.v, NULL, 0, &lin, &err), &err);
  fb_road_iso8608_params iso;
  CHECK(fx.s && fb_study_ride_psd_iso8608(fx.s, 'c', &iso) == 1);
  for (int identical = 0; lin && identical < 2; ++identical) {
    fb_study_ride_psd *r = NULL;
    MUST(fb_study_ride_psd_new(lin, &iso, identical, &r, &err), &err);
    if (!r)
      continue;
    const fb_study_psd_road *road = fb_study_ride_psd_road(r);
    CHECK(road->road_class == 'C' && road->gd0 == GD0_C && road->speed == SPEED);
    CHECK(road->identical == identical && !fb_study_ride_psd_linearised(r));
    check_band(r, &iso);
    const reference ref = integrate(&fx, iso.n_min, iso.n_max, identical);
    check_ride(r, &ref, identical ? "identical" : "independent");
    fb_study_ride_psd_free(&r);
    CHECK(r == NULL);
  }
  fb_study_freq_free(&lin);
  fixture_close(&fx);
}

/* ---- 3. The road. */

static void test_road(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *bump = NULL, *random = NULL;
  MUST(fb_scenario_load(scenario_path, &bump, &err), &err);
  MUST(fb_scenario_load(iso_road_path, &random, &err), &err);
  fb_road_iso8608_params iso;
  if (bump)
    CHECK(fb_study_ride_psd_iso8608(bump, 0, &iso) == 0);
  if (random) {
    CHECK(fb_study_ride_psd_iso8608(random, 0, &iso) == 1);
    const fb_road_random_params *own = road_random(random);
    CHECK(iso.road_class == 'A' + own->road_class && iso.n_min == own->band[0] &&
          iso.seed == own->seed);
    /* A class named replaces the scenario's, with ISO 8608's band. */
    CHECK(fb_study_ride_psd_iso8608(random, 'E', &iso) == 1 && iso.road_class == 'E');
    CHECK(iso.n_min == 0.011 && iso.n_max == 2.83);
  }
  fixture fx;
  MUST(fixture_open(&fx, &err), &err);
  fb_study_freq *lin = NULL;
  if (fx.v)
    MUST(fb_study_freq_new(fx.v, NULL, 0, &lin, &err), &err);
  fb_study_ride_psd *r = (fb_study_ride_psd *)&err; /* set to NULL on failure */
  iso.road_class = 'Z';
  if (lin) {
    CHECK(fb_study_ride_psd_new(lin, &iso, 0, &r, &err) == FB_EINVAL && r == NULL);
    iso.road_class = 'C';
    iso.n_max = iso.n_min;
    CHECK(fb_study_ride_psd_new(lin, &iso, 0, &r, &err) == FB_EINVAL && r == NULL);
    CHECK(strstr(err.msg, "band") != NULL);
  }
  fb_study_freq_free(&lin);
  fixture_close(&fx);
  fb_scenario_free(&random);
  fb_scenario_free(&bump);
}

int main(void)
{
  test_freq();
  test_ride();
  test_road();
  return check_report("test_study_psd");
}
