/* SPDX-License-Identifier: BSD-3-Clause */
/* Road profiles (flexbond/road.h): the (1 - cos) bumps against their closed
 * form and the scenario's bump timing, ISO 8608 roads against the class's
 * PSD through a periodogram, CSV profiles against hand-computed PCHIP
 * values, and the error paths. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/road.h"
#include "flexbond/vehicle.h"

#include "apc_layout.h"
#include "check.h"
#include "road_util.h"
#include "tmpdir.h"

static const double PI = 3.14159265358979323846;

static int contains(const char *text, const char *part)
{
  return strstr(text, part) != NULL;
}

/* ---- Bumps ---- */

/* The data sheet's reference vehicle (docs/reference-vehicle.md):
 * corner positions, 10 km/h, a 0.10 m x 3.70 m bump at 45 deg, first
 * contact 5 s. */
static void reference_scenario(fb_scenario *sc, fb_corner_params *corners)
{
  static const double x[APC_NCORNERS] = {1.90, 1.90, 0.40, 0.40, -1.00, -1.00};
  static const double y[APC_NCORNERS] = {1.05, -1.05, 1.05, -1.05, 1.05, -1.05};
  memset(sc, 0, sizeof *sc);
  memset(corners, 0, APC_NCORNERS * sizeof *corners);
  sc->corner = corners;
  sc->ncorners = APC_NCORNERS;
  for (int c = 0; c < APC_NCORNERS; ++c) {
    sc->corner[c].name = (char *)apc_corner_name(c);
    sc->corner[c].x = x[c];
    sc->corner[c].y = y[c];
  }
  sc->speed = 10.0 / 3.6;
  CHECK(fb_scenario_set_road(sc, &fb_road_type_bump, NULL, NULL) == FB_OK);
  road_bump(sc)->height = 0.10;
  road_bump(sc)->length = 3.70;
  road_bump(sc)->angle = PI / 4.0;
  road_bump(sc)->first_contact = 5.0;
}

/* A wheel's track and start position for the scenario's convention: the
 * vehicle's origin at s = s_ref + V t with s_ref chosen so that the left
 * front wheel reaches the left track's leading edge (s = 0) at bump_time. */
static void scenario_wheel(const fb_scenario *sc, int c, int *track, double *s0)
{
  const double s_ref = -(sc->speed * road_bump(sc)->first_contact + sc->corner[APC_LF].x);
  *track = sc->corner[c].y > 0.0 ? FB_ROAD_LEFT : FB_ROAD_RIGHT;
  *s0 = s_ref + sc->corner[c].x;
}

/* Closed form of the bump under a wheel entering at t_in: z and dz/dt. */
static double bump_z(double h, double len, double v, double t_in, double t)
{
  const double u = v * (t - t_in);
  return u < 0.0 || u > len ? 0.0 : 0.5 * h * (1.0 - cos(2.0 * PI * u / len));
}

static double bump_v(double h, double len, double v, double t_in, double t)
{
  const double u = v * (t - t_in);
  return u < 0.0 || u > len ? 0.0 : PI * h * v / len * sin(2.0 * PI * u / len);
}

static void check_wheel_on_bump(const fb_road *road, const fb_scenario *sc, int c)
{
  int track;
  double s0;
  scenario_wheel(sc, c, &track, &s0);
  fb_tfun *z = NULL, *v = NULL;
  fb_err err;
  CHECK(fb_road_wheel_height(road, track, sc->speed, s0, &z, &err) == FB_OK);
  CHECK(fb_road_wheel_velocity(road, track, sc->speed, s0, &v, &err) == FB_OK);
  if (!z || !v)
    return;
  /* Entry and exit: the scenario's formula, computed in another order;
   * times of ~8 s agree to rounding (a few ulp, 1e-15 s): 1e-12 s. */
  double bp[4] = {0};
  CHECK(fb_tfun_breakpoints(v, bp, 4) == 2);
  CHECK_NEAR(bp[0], fb_scenario_road_entry(sc, c), 1e-12);
  CHECK_NEAR(bp[1], fb_scenario_road_exit(sc, c), 1e-12);
  CHECK(fb_tfun_breakpoints(z, NULL, 0) == 2);
  /* Height and velocity against the closed form at 37 times across the
   * bump and either side; arguments of cos/sin of at most ~20 rad carry
   * rounding of ~1e-15: 1e-13 m and m/s. */
  const double t_in = fb_scenario_road_entry(sc, c);
  const double h = road_bump(sc)->height, len = road_bump(sc)->length, V = sc->speed;
  for (int i = -2; i <= 34; ++i) {
    const double t = t_in + (double)i / 32.0 * len / V;
    CHECK_NEAR(fb_tfun_eval(z, t), bump_z(h, len, V, t_in, t), 1e-13);
    CHECK_NEAR(fb_tfun_eval(v, t), bump_v(h, len, V, t_in, t), 1e-13);
  }
  /* The velocity is the height's time derivative (second method: a
   * central difference with dt = 1e-5 s, truncation dt^2/6 |z'''| <=
   * 1e-10 / 6 * (2 pi V / L)^3 h / 2 ~ 1e-9, rounding 1e-16 * 0.1 / 1e-5
   * ~ 1e-12): 1e-8 m/s. */
  const double dt = 1e-5, t = t_in + 0.3 * len / V;
  CHECK_NEAR(fb_tfun_eval(v, t), (fb_tfun_eval(z, t + dt) - fb_tfun_eval(z, t - dt)) / (2 * dt),
             1e-8);
  fb_tfun_free(&z);
  fb_tfun_free(&v);
}

/* The paper's oblique bump reproduces the scenario's timing
 * (fb_scenario_road_entry / _exit) and the data sheet's hand-computed
 * entries: LF 5, LM 5 + 1.5 / V = 5.54, RF 5 + 2.1 / V = 5.756, LR 6.044,
 * RM 6.296, RR 6.8 s; RR leaves at 8.132 s (V = 25/9 m/s). */
static void test_oblique_bump(void)
{
  fb_scenario sc;
  fb_corner_params corners[APC_NCORNERS];
  reference_scenario(&sc, corners);
  fb_road *road = NULL;
  fb_err err;
  const double width = sc.corner[APC_LF].y - sc.corner[APC_RF].y;
  CHECK(fb_road_new_oblique_bump(road_bump(&sc)->height, road_bump(&sc)->length,
                                 road_bump(&sc)->angle, width, &road, &err) == FB_OK);
  if (!road)
    return;
  for (int c = 0; c < APC_NCORNERS; ++c)
    check_wheel_on_bump(road, &sc, c);
  static const double entry[APC_NCORNERS] = {5.0, 5.756, 5.54, 6.296, 6.044, 6.8};
  for (int c = 0; c < APC_NCORNERS; ++c) {
    int track;
    double s0, bp[2] = {0};
    fb_tfun *v = NULL;
    scenario_wheel(&sc, c, &track, &s0);
    CHECK(fb_road_wheel_velocity(road, track, sc.speed, s0, &v, &err) == FB_OK);
    CHECK(v && fb_tfun_breakpoints(v, bp, 2) == 2);
    /* Decimal hand values, rounding of the times only: 1e-12 s. */
    CHECK_NEAR(bp[0], entry[c], 1e-12);
    if (c == APC_RR)
      CHECK_NEAR(bp[1], 8.132, 1e-12);
    fb_tfun_free(&v);
  }
  /* Tracks: left bump over [0, 3.7], right over [2.1, 5.8] (tan 45 deg =
   * 1 to an ulp); breaks there. */
  double br[2] = {0};
  CHECK(fb_road_breaks(road, FB_ROAD_RIGHT, br, 2) == 2);
  CHECK_NEAR(br[0], 2.1, 1e-15);
  CHECK_NEAR(br[1], 5.8, 4e-15);
  CHECK(fb_road_breaks(road, FB_ROAD_LEFT, br, 2) == 2);
  CHECK(br[0] == 0.0 && br[1] == 3.7);
  CHECK(fb_road_breaks(road, 2, br, 2) == 0);
  CHECK(isnan(fb_road_height(road, -1, 1.0)) && isnan(fb_road_slope(road, 2, 1.0)));
  fb_road_free(&road);
  CHECK(road == NULL);
  fb_road_free(&road); /* NULL is accepted */
  fb_road_free(NULL);
}

/* Brazilian speed bumps: their dimensions, and the (1 - cos) shape's top
 * (h at L/2: cos(pi) = -1 exactly) and steepest slope (pi h / L at L/4,
 * sin(pi/2) = 1) on a square bump (both tracks at s = 10 m). */
static void test_speed_bumps(void)
{
  fb_err err;
  double h = 0.0, len = 0.0;
  CHECK(fb_road_speed_bump("I", &h, &len, &err) == FB_OK);
  CHECK(h == 0.08 && len == 1.50);
  CHECK(fb_road_speed_bump("II", &h, &len, &err) == FB_OK);
  CHECK(h == 0.10 && len == 3.70);
  CHECK(fb_road_speed_bump("A", &h, &len, &err) == FB_OK);
  CHECK(h == 0.10 && len == 3.70);
  CHECK(fb_road_speed_bump("B", &h, &len, &err) == FB_OK);
  CHECK(h == 0.08 && len == 1.50);
  CHECK(fb_road_speed_bump("III", &h, &len, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "'III'") && contains(DESCRIBED(&err), "expected I"));
  CHECK(fb_road_speed_bump(NULL, &h, &len, &err) == FB_EINVAL);

  CHECK(fb_road_speed_bump("I", &h, &len, &err) == FB_OK);
  fb_road *road = NULL;
  CHECK(fb_road_new_bump(h, len, 10.0, 10.0, &road, &err) == FB_OK);
  if (!road)
    return;
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k) {
    CHECK_NEAR(fb_road_height(road, k, 10.0 + 0.5 * len), 0.08, 1e-17);
    CHECK_NEAR(fb_road_slope(road, k, 10.0 + 0.25 * len), PI * 0.08 / 1.5, 1e-16);
    CHECK(fb_road_height(road, k, 10.0) == 0.0 && fb_road_slope(road, k, 9.0) == 0.0);
    CHECK(fb_road_height(road, k, 11.6) == 0.0 && fb_road_slope(road, k, 11.6) == 0.0);
    /* Slope continuous (0) at both ends to rounding: sin(2 pi) ~ 2e-16. */
    CHECK_NEAR(fb_road_slope(road, k, 10.0 + len), 0.0, 1e-15);
  }
  fb_road_free(&road);
}

static void test_bump_errors(void)
{
  fb_err err;
  fb_road *road = NULL;
  CHECK(fb_road_new_bump(0.1, -3.7, 0.0, 0.0, &road, &err) == FB_EINVAL);
  CHECK(road == NULL && contains(DESCRIBED(&err), "length must be > 0") &&
        contains(DESCRIBED(&err), "-3.7"));
  CHECK(fb_road_new_bump(NAN, 3.7, 0.0, 0.0, &road, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "height"));
  CHECK(fb_road_new_bump(0.1, 3.7, 0.0, INFINITY, &road, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "right start"));
  CHECK(fb_road_new_oblique_bump(0.1, 3.7, PI / 2, 2.1, &road, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "angle") && contains(DESCRIBED(&err), "90"));
  CHECK(fb_road_new_oblique_bump(0.1, 3.7, 0.5, 0.0, &road, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "track width"));
  CHECK(fb_road_new_bump(0.1, 3.7, 0.0, 0.0, NULL, &err) == FB_EINVAL);

  CHECK(fb_road_new_bump(0.1, 3.7, 0.0, 0.0, &road, &err) == FB_OK);
  fb_tfun *f = NULL;
  CHECK(fb_road_wheel_velocity(road, FB_ROAD_LEFT, 0.0, 0.0, &f, &err) == FB_EINVAL);
  CHECK(f == NULL && contains(DESCRIBED(&err), "speed must be > 0"));
  CHECK(fb_road_wheel_height(road, 2, 1.0, 0.0, &f, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "track must be"));
  CHECK(fb_road_wheel_height(road, FB_ROAD_RIGHT, 1.0, NAN, &f, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "s0"));
  CHECK(fb_road_wheel_height(NULL, FB_ROAD_RIGHT, 1.0, 0.0, &f, &err) == FB_EINVAL);
  fb_road_free(&road);
}

/* ---- ISO 8608 ---- */

/* Gd(n0) of classes A .. H, 1e-6 m^3 (ISO 8608's classification:
 * geometric means 16, 64, ..., 262144). */
static const double CLASS_GD0[8] = {16, 64, 256, 1024, 4096, 16384, 65536, 262144};

static double class_psd(int c, double n)
{
  return CLASS_GD0[c] * 1e-6 * (0.1 / n) * (0.1 / n);
}

static void test_iso_classes(void)
{
  fb_err err;
  for (int c = 0; c < 8; ++c) {
    double gd0 = 0.0;
    CHECK(fb_road_iso8608_gd0((char)('A' + c), &gd0, &err) == FB_OK);
    CHECK_NEAR(gd0, CLASS_GD0[c] * 1e-6, 1e-15 * CLASS_GD0[c] * 1e-6);
    CHECK(fb_road_iso8608_gd0((char)('a' + c), &gd0, &err) == FB_OK);
  }
  double gd0 = 0.0;
  CHECK(fb_road_iso8608_gd0('I', &gd0, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "'I'") && contains(DESCRIBED(&err), "A to H"));
  CHECK(fb_road_iso8608_gd0('3', &gd0, &err) == FB_EINVAL);
  CHECK(fb_road_iso8608_gd0('\0', &gd0, &err) == FB_EINVAL);
}

/* A periodogram over one exact period of a road whose harmonics sit on the
 * bins: band [0.011, 2.831] cycles/m split into 1410 sub-bands of
 * dn = 0.002, midpoints n_k = 0.012 + 0.002 k = (6 + k) / P, so the
 * profile repeats every P = 500 m. M = 4096 samples over P resolve every
 * bin up to M/2 = 2048 > 1415 (no aliasing), and the DFT of one period has
 * no leakage: each harmonic a cos(2 pi j m / M + p) lands in bin j alone
 * as c_j = (a/2) e^(i p). The PSD estimate 2 |c_j|^2 / dn then equals
 * Gd(n_j) exactly; the estimator has no statistical error here (the
 * amplitudes are deterministic, only phases are random), so the tolerance
 * covers rounding alone: the cos arguments (up to 2 pi 2.83 * 500 = 9e3
 * rad) carry ~2e-12 rad of error, which spreads ~1e-13 m into the samples
 * and ~1e-15 m into every bin, relative to the smallest harmonic's
 * coefficient (~5e-6 m for class A) ~2e-10: relative tolerance 1e-6. */
enum { PERIOD_SAMPLES = 4096, PERIOD_HARMONICS = 1410, PERIOD_FIRST_BIN = 6 };
static const double PERIOD_LENGTH = 500.0, PERIOD_DN = 0.002; /* m, cycles/m */

typedef struct periodogram {
  double re[PERIOD_HARMONICS + PERIOD_FIRST_BIN + 200];
  double im[PERIOD_HARMONICS + PERIOD_FIRST_BIN + 200];
  double mean, mean_square;
} periodogram;

enum { PERIOD_BINS = PERIOD_HARMONICS + PERIOD_FIRST_BIN + 200 };

/* DFT bins 0 .. PERIOD_BINS - 1 of track k over s in [0, P), and the
 * mean and mean square (exact for a trigonometric polynomial of degree
 * below M: trapezoid rule on a period). */
static void road_periodogram(const fb_road *road, int track, const double *cosine,
                             const double *sine, periodogram *p)
{
  double *z = malloc(PERIOD_SAMPLES * sizeof *z);
  if (!z)
    return;
  p->mean = p->mean_square = 0.0;
  for (int m = 0; m < PERIOD_SAMPLES; ++m) {
    z[m] = fb_road_height(road, track, PERIOD_LENGTH * m / PERIOD_SAMPLES);
    p->mean += z[m] / PERIOD_SAMPLES;
    p->mean_square += z[m] * z[m] / PERIOD_SAMPLES;
  }
  for (int j = 0; j < PERIOD_BINS; ++j) {
    double re = 0.0, im = 0.0;
    for (long m = 0; m < PERIOD_SAMPLES; ++m) {
      const long idx = ((long)j * m) % PERIOD_SAMPLES;
      re += z[m] * cosine[idx];
      im -= z[m] * sine[idx];
    }
    p->re[j] = re / PERIOD_SAMPLES;
    p->im[j] = im / PERIOD_SAMPLES;
  }
  free(z);
}

/* Checks the bins of one track against class c's PSD; returns the
 * harmonics' phases in phase[PERIOD_HARMONICS]. */
static void check_psd(const periodogram *p, int c, double *phase)
{
  const double dn = PERIOD_DN;
  const double gd_min = class_psd(c, 2.83);
  int bad = 0, leak = 0;
  for (int j = 0; j < PERIOD_BINS; ++j) {
    const double power = 2.0 * (p->re[j] * p->re[j] + p->im[j] * p->im[j]) / dn;
    const int k = j - PERIOD_FIRST_BIN;
    if (k >= 0 && k < PERIOD_HARMONICS) {
      const double gd = class_psd(c, j * dn);
      bad += !(fabs(power - gd) <= 1e-6 * gd);
      phase[k] = atan2(p->im[j], p->re[j]);
    } else {
      /* Bins outside the band: nothing but rounding (power ratio of
       * (1e-9)^2 below the smallest harmonic's). */
      leak += !(power <= 1e-12 * gd_min);
    }
  }
  CHECK(bad == 0);
  CHECK(leak == 0);
  /* Mean 0 (no harmonic at n = 0), to rounding of the sum. */
  CHECK_NEAR(p->mean, 0.0, 1e-12 * sqrt(p->mean_square));
}

/* Phases uniform on the circle: the means of cos p, sin p, cos 2p, sin 2p
 * over N independent uniform phases have standard deviation 1/sqrt(2N)
 * (0.019 for N = 1410); 5 sigma: 0.094 (a false alarm below 1e-6). */
static void check_phases_uniform(const double *phase, int n)
{
  double c1 = 0, s1 = 0, c2 = 0, s2 = 0;
  for (int k = 0; k < n; ++k) {
    c1 += cos(phase[k]) / n;
    s1 += sin(phase[k]) / n;
    c2 += cos(2 * phase[k]) / n;
    s2 += sin(2 * phase[k]) / n;
  }
  const double tol = 5.0 / sqrt(2.0 * n);
  CHECK(fabs(c1) < tol && fabs(s1) < tol && fabs(c2) < tol && fabs(s2) < tol);
}

static void test_iso_psd_class(int c, const double *cosine, const double *sine)
{
  fb_road_iso8608_params prm;
  fb_road_iso8608_defaults(&prm);
  prm.road_class = (char)('A' + c);
  prm.seed = 20240601u + (unsigned)c;
  prm.n_min = 0.011;
  prm.n_max = 0.011 + PERIOD_DN * PERIOD_HARMONICS;
  prm.nharmonics = PERIOD_HARMONICS;
  fb_road *road = NULL;
  fb_err err;
  CHECK(fb_road_new_iso8608(&prm, &road, &err) == FB_OK);
  periodogram *p = malloc(sizeof *p);
  double *phase = malloc(2 * PERIOD_HARMONICS * sizeof *phase);
  if (!road || !p || !phase) {
    free(p);
    free(phase);
    fb_road_free(&road);
    return;
  }
  double mean_square[2];
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k) {
    road_periodogram(road, k, cosine, sine, p);
    check_psd(p, c, phase + k * PERIOD_HARMONICS);
    check_phases_uniform(phase + k * PERIOD_HARMONICS, PERIOD_HARMONICS);
    mean_square[k] = p->mean_square;
  }
  /* Independent tracks: cos(p_left - p_right) averages to 0, standard
   * deviation 1/sqrt(2N); 5 sigma. */
  double corr = 0.0;
  for (int k = 0; k < PERIOD_HARMONICS; ++k)
    corr += cos(phase[k] - phase[PERIOD_HARMONICS + k]) / PERIOD_HARMONICS;
  CHECK(fabs(corr) < 5.0 / sqrt(2.0 * PERIOD_HARMONICS));
  /* Variance: the sum of the harmonics' variances Gd(n_k) dn (to rounding,
   * 1e-9 relative), and the integral of Gd over the band, Gd0 n0^2
   * (1/n_min - 1/n_max); the midpoint rule's error for n^-2 is about
   * (dn / n_min)^2 / 12 = 2.8e-3 relative (it underestimates: convex):
   * 4e-3. */
  double sum = 0.0;
  for (int k = 0; k < PERIOD_HARMONICS; ++k)
    sum += class_psd(c, (PERIOD_FIRST_BIN + k) * PERIOD_DN) * PERIOD_DN;
  const double integral = CLASS_GD0[c] * 1e-6 * 0.01 * (1.0 / prm.n_min - 1.0 / prm.n_max);
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k) {
    CHECK_NEAR(mean_square[k], sum, 1e-9 * sum);
    CHECK_NEAR(mean_square[k], integral, 4e-3 * integral);
    CHECK(mean_square[k] < integral);
  }
  free(p);
  free(phase);
  fb_road_free(&road);
}

static void test_iso_psd(void)
{
  double *cosine = malloc(PERIOD_SAMPLES * sizeof *cosine);
  double *sine = malloc(PERIOD_SAMPLES * sizeof *sine);
  if (cosine && sine) {
    for (int m = 0; m < PERIOD_SAMPLES; ++m) {
      cosine[m] = cos(2.0 * PI * m / PERIOD_SAMPLES);
      sine[m] = sin(2.0 * PI * m / PERIOD_SAMPLES);
    }
    test_iso_psd_class(0, cosine, sine); /* A */
    test_iso_psd_class(2, cosine, sine); /* C */
    test_iso_psd_class(4, cosine, sine); /* E */
  }
  free(cosine);
  free(sine);
}

/* The default road (class C, 1024 harmonics over 0.011 .. 2.83
 * cycles/m): its mean square over a 10 km stretch sampled every 0.5 m
 * against the
 * integral of Gd over the band, 256e-6 * 0.01 * (1/0.011 - 1/2.83). The
 * harmonics are not periodic over the stretch: the cross term of the
 * two lowest (20 % and 13 % of the variance, dn = 0.00275 apart) averages
 * to at most 4 sqrt(0.2 * 0.13) / (2 pi dn L) = 0.4 % of the mean square,
 * the others less (smaller harmonics, wider gaps), and the midpoint rule
 * is low by about (dn / n_min)^2 / 12 = 0.5 %; on the RMS these halve
 * (0.5 % in all, with margin for the smaller cross terms): 1 %. Sampling every 0.5 m aliases
 * only products of harmonics whose frequencies add up to 2 cycles/m or more, whose variance
 * shares are below 1e-4. */
static void test_iso_rms(void)
{
  fb_road_iso8608_params prm;
  fb_road_iso8608_defaults(&prm);
  CHECK(prm.road_class == 'C' && prm.nharmonics == 1024);
  fb_road *road = NULL;
  fb_err err;
  CHECK(fb_road_new_iso8608(&prm, &road, &err) == FB_OK);
  if (!road)
    return;
  const double integral = 256e-6 * 0.01 * (1.0 / 0.011 - 1.0 / 2.83);
  const int n = 20000;
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k) {
    double ms = 0.0;
    for (int i = 0; i < n; ++i) {
      const double z = fb_road_height(road, k, 0.5 * i);
      ms += z * z / n;
    }
    CHECK_NEAR(sqrt(ms), sqrt(integral), 0.01 * sqrt(integral));
  }
  fb_road_free(&road);
}

/* Same seed: the same road, bit for bit; another seed: another road; the
 * two tracks differ. */
static void test_iso_seed(void)
{
  fb_road_iso8608_params prm;
  fb_road_iso8608_defaults(&prm);
  prm.seed = 42;
  prm.nharmonics = 200;
  fb_road *a = NULL, *b = NULL, *c = NULL;
  fb_err err;
  CHECK(fb_road_new_iso8608(&prm, &a, &err) == FB_OK);
  CHECK(fb_road_new_iso8608(&prm, &b, &err) == FB_OK);
  prm.seed = 43;
  CHECK(fb_road_new_iso8608(&prm, &c, &err) == FB_OK);
  if (!a || !b || !c) {
    fb_road_free(&a);
    fb_road_free(&b);
    fb_road_free(&c);
    return;
  }
  int same = 1;
  double diff_seed = 0.0, diff_track = 0.0;
  for (int i = 0; i < 500; ++i) {
    const double s = 0.37 * i - 20.0;
    for (int k = 0; k < FB_ROAD_NTRACKS; ++k)
      same &= fb_road_height(a, k, s) == fb_road_height(b, k, s) &&
              fb_road_slope(a, k, s) == fb_road_slope(b, k, s);
    diff_seed = fmax(diff_seed, fabs(fb_road_height(a, 0, s) - fb_road_height(c, 0, s)));
    diff_track = fmax(diff_track, fabs(fb_road_height(a, 0, s) - fb_road_height(a, 1, s)));
  }
  CHECK(same);
  /* Independent tracks of sigma ~ 15 mm differ by centimetres somewhere
   * along 185 m; 1 mm is far below that. */
  CHECK(diff_seed > 1e-3);
  CHECK(diff_track > 1e-3);
  fb_road_free(&a);
  fb_road_free(&b);
  fb_road_free(&c);
}

/* Slope against a central difference of the height (h = 1e-4 m); the
 * truncation error h^2/6 |z'''| is bounded with |z'''| <= sum a_k
 * (2 pi n_k)^3 computed from the class's PSD; rounding 1e-16 * |z| / h
 * ~ 1e-13. Also through a fade-in of 20 m: 0 before, the unfaded road
 * after, C1 at both ends (breaks there). */
static void test_iso_slope_and_fade(void)
{
  fb_road_iso8608_params prm;
  fb_road_iso8608_defaults(&prm);
  prm.road_class = 'E';
  prm.nharmonics = 300;
  fb_road *plain = NULL, *faded = NULL;
  fb_err err;
  CHECK(fb_road_new_iso8608(&prm, &plain, &err) == FB_OK);
  prm.fade_length = 20.0;
  CHECK(fb_road_new_iso8608(&prm, &faded, &err) == FB_OK);
  if (!plain || !faded) {
    fb_road_free(&plain);
    fb_road_free(&faded);
    return;
  }
  const double dn = (prm.n_max - prm.n_min) / (double)prm.nharmonics;
  double third = 0.0;
  for (size_t k = 0; k < prm.nharmonics; ++k) {
    const double nk = prm.n_min + (k + 0.5) * dn, w = 2 * PI * nk;
    /* Fade adds terms with w', w'' (<= 6/F^2 and 6/F^3 relative): a factor
     * 2 covers them for F = 20 m. */
    third += 2.0 * sqrt(2.0 * class_psd(4, nk) * dn) * (w * w * w + 3 * w * w + 1);
  }
  const double h = 1e-4, tol = h * h / 6.0 * third + 1e-12;
  int bad = 0;
  for (int i = 0; i < 400; ++i) {
    const double s = -5.0 + 0.1371 * i;
    for (int k = 0; k < FB_ROAD_NTRACKS; ++k) {
      const fb_road *r = (i % 2) ? plain : faded;
      const double fd = (fb_road_height(r, k, s + h) - fb_road_height(r, k, s - h)) / (2 * h);
      bad += !(fabs(fb_road_slope(r, k, s) - fd) <= tol);
    }
  }
  CHECK(bad == 0);
  CHECK(fb_road_height(faded, 0, -1.0) == 0.0 && fb_road_height(faded, 1, 0.0) == 0.0);
  CHECK(fb_road_slope(faded, 0, -1.0) == 0.0);
  CHECK(fb_road_height(faded, 0, 20.0) == fb_road_height(plain, 0, 20.0));
  CHECK(fb_road_height(faded, 1, 33.0) == fb_road_height(plain, 1, 33.0));
  CHECK(fb_road_height(faded, 0, 10.0) == 0.5 * fb_road_height(plain, 0, 10.0));
  /* C1 at the fade's ends: one-sided slopes 1e-9 m apart agree within
   * |z''| 1e-9 (|z''| < 10 for class E here). */
  CHECK_NEAR(fb_road_slope(faded, 0, 20.0 - 1e-9), fb_road_slope(faded, 0, 20.0 + 1e-9), 1e-8);
  CHECK_NEAR(fb_road_slope(faded, 0, 1e-9), 0.0, 1e-8);
  double br[3] = {0};
  CHECK(fb_road_breaks(faded, 1, br, 3) == 2 && br[0] == 0.0 && br[1] == 20.0);
  CHECK(fb_road_breaks(plain, 1, br, 3) == 0);

  /* The velocity function: V dz/ds at s0 + V t, with its own copy of the
   * profile (the road is freed before it is evaluated); breakpoints at
   * the fade's ends (-s0/V, (20 - s0)/V). */
  fb_tfun *v = NULL, *copy = NULL;
  const double speed = 5.0, s0 = -10.0;
  CHECK(fb_road_wheel_velocity(faded, FB_ROAD_RIGHT, speed, s0, &v, &err) == FB_OK);
  double expect[5];
  for (int i = 0; i < 5; ++i)
    expect[i] = speed * fb_road_slope(faded, FB_ROAD_RIGHT, s0 + speed * (1.3 * i));
  fb_road_free(&faded);
  CHECK(v && fb_tfun_clone(v, &copy, &err) == FB_OK);
  if (v && copy) {
    for (int i = 0; i < 5; ++i) {
      /* The same arithmetic, up to the compiler's contraction of
       * s0 + V t into a fused multiply-add (1 ulp of s ~ 2e-15 m, times
       * V |z''| < 50): 1e-12 m/s. */
      CHECK_NEAR(fb_tfun_eval(v, 1.3 * i), expect[i], 1e-12);
      CHECK_NEAR(fb_tfun_eval(copy, 1.3 * i), expect[i], 1e-12);
    }
    double bp[2] = {0};
    CHECK(fb_tfun_breakpoints(v, bp, 2) == 2 && bp[0] == 2.0 && bp[1] == 6.0);
  }
  fb_tfun_free(&v);
  fb_tfun_free(&copy);
  fb_road_free(&plain);
}

static void test_iso_errors(void)
{
  fb_road_iso8608_params prm;
  fb_road *road = NULL;
  fb_err err;
  fb_road_iso8608_defaults(&prm);
  prm.road_class = 'J';
  CHECK(fb_road_new_iso8608(&prm, &road, &err) == FB_EINVAL);
  CHECK(road == NULL && contains(DESCRIBED(&err), "'J'"));
  fb_road_iso8608_defaults(&prm);
  prm.n_min = 0.0;
  CHECK(fb_road_new_iso8608(&prm, &road, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "n_min"));
  fb_road_iso8608_defaults(&prm);
  prm.n_max = 0.01;
  CHECK(fb_road_new_iso8608(&prm, &road, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "n_max"));
  fb_road_iso8608_defaults(&prm);
  prm.nharmonics = 0;
  CHECK(fb_road_new_iso8608(&prm, &road, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "nharmonics"));
  /* Only slow, but hours slow: bounded (flexbond/road.h). */
  prm.nharmonics = FB_ROAD_ISO8608_MAX_HARMONICS + 1;
  CHECK(fb_road_new_iso8608(&prm, &road, &err) == FB_EINVAL);
  CHECK(road == NULL &&
        contains(DESCRIBED(&err), "nharmonics must be in 1 .. 16384 (got 16385)"));
  prm.nharmonics = FB_ROAD_ISO8608_MAX_HARMONICS;
  CHECK(fb_road_new_iso8608(&prm, &road, &err) == FB_OK);
  fb_road_free(&road);
  fb_road_iso8608_defaults(&prm);
  prm.fade_length = -1.0;
  CHECK(fb_road_new_iso8608(&prm, &road, &err) == FB_EINVAL);
  CHECK(contains(DESCRIBED(&err), "fade_length"));
  CHECK(fb_road_new_iso8608(NULL, &road, &err) == FB_EINVAL);
}

/* ---- CSV profiles ---- */

static const char *tmp_dir; /* the private directory (tmpdir.h) */

/* Writes len bytes of text (NUL bytes included) to tmp_dir/name. */
static const char *write_file_n(const char *name, const char *text, size_t len)
{
  static char path[TEST_PATH_MAX];
  snprintf(path, sizeof path, "%s/%s", tmp_dir, name);
  FILE *fp = fopen(path, "w");
  if (fp) {
    CHECK(fwrite(text, 1, len, fp) == len);
    fclose(fp);
  }
  return path;
}

static const char *write_file(const char *name, const char *text)
{
  return write_file_n(name, text, strlen(text));
}

/* z = s^2 at s = 0, 1, 2, 3. PCHIP slopes by hand: secants 1, 3, 5;
 * interior (equal widths: harmonic mean) d1 = 2 / (1/1 + 1/3) = 1.5,
 * d2 = 2 / (1/3 + 1/5) = 3.75; ends (three-point formula) d0 = (3 * 1 -
 * 3) / 2 = 0, d3 = (3 * 5 - 3) / 2 = 6. At s = 1.5 the Hermite cubic
 * gives (z1 + z2)/2 + h (d1 - d2)/8 = 2.5 - 2.25/8 = 2.21875. */
static void test_csv_values(void)
{
  const char *path = write_file("square.csv", "# z = s^2\ns, z\n0, 0\n\n1, 1\n2, 4\n3, 9\n");
  fb_road *road = NULL;
  fb_err err;
  CHECK(fb_road_new_csv(path, &road, &err) == FB_OK);
  if (!road)
    return;
  static const double knot_z[4] = {0, 1, 4, 9}, knot_d[4] = {0, 1.5, 3.75, 6};
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k) {
    for (int i = 0; i < 4; ++i)
      CHECK(fb_road_height(road, k, i) == knot_z[i]);
    /* Slopes from inside each interval next to the knots (|z''| <= 20
     * here, 1e-9 away: 2e-8). */
    for (int i = 0; i < 4; ++i) {
      if (i > 0)
        CHECK_NEAR(fb_road_slope(road, k, i - 1e-9), knot_d[i], 2e-8);
      if (i < 3)
        CHECK_NEAR(fb_road_slope(road, k, i + 1e-9), knot_d[i], 2e-8);
    }
    CHECK_NEAR(fb_road_height(road, k, 1.5), 2.21875, 1e-15);
    /* Held outside, slope 0. */
    CHECK(fb_road_height(road, k, -2.0) == 0.0 && fb_road_height(road, k, 7.0) == 9.0);
    CHECK(fb_road_slope(road, k, -2.0) == 0.0 && fb_road_slope(road, k, 7.0) == 0.0);
  }
  /* Breaks at the ends only (the slope is continuous at interior knots). */
  double br[4] = {0};
  CHECK(fb_road_breaks(road, FB_ROAD_LEFT, br, 4) == 2 && br[0] == 0 && br[1] == 3);
  /* Wheel at s0 = -2 m, 2 m/s: the ends at t = 1 and 2.5 s. */
  fb_tfun *v = NULL;
  CHECK(fb_road_wheel_velocity(road, FB_ROAD_LEFT, 2.0, -2.0, &v, &err) == FB_OK);
  double bp[4] = {0};
  CHECK(v && fb_tfun_breakpoints(v, bp, 4) == 2);
  CHECK(bp[0] == 1.0 && bp[1] == 2.5);
  if (v)
    CHECK_NEAR(fb_tfun_eval(v, 1.75), 2.0 * fb_road_slope(road, 0, 1.5), 1e-15);
  fb_tfun_free(&v);
  fb_road_free(&road);
}

/* A profile flat for 10 m, then a bump, flat again, then a dip: the
 * knots where a flat stretch meets the bump or the dip are breaks (a
 * wheel at rest on the flat would let the integrator step over the
 * feature), the knots inside the bump are not. Knots: s = 0, 5, 10 flat
 * at 0; 10.5 at 0.1; 11 back at 0 (PCHIP gives 10.5 slope 0, so [10, 11]
 * is not flat); 11, 15 flat; 16 at -0.05; 17, 20 flat at 0. Expected
 * breaks: 0 (end), 10 (flat -> bump), 11 (bump -> flat), 15 (flat ->
 * dip), 17 (dip -> flat), 20 (end). */
static void test_profile_flat_breaks(void)
{
  static const double s_k[] = {0, 5, 10, 10.5, 11, 15, 16, 17, 20};
  static const double z_k[] = {0, 0, 0, 0.1, 0, 0, -0.05, 0, 0};
  static const double want[] = {0, 10, 11, 15, 17, 20};
  const size_t n = sizeof s_k / sizeof s_k[0], nwant = sizeof want / sizeof want[0];
  fb_err err;
  fb_road *road = NULL;
  CHECK(fb_road_new_profile(n, s_k, z_k, z_k, &road, &err) == FB_OK);
  if (!road)
    return;
  double br[16] = {0};
  CHECK(fb_road_breaks(road, FB_ROAD_RIGHT, NULL, 0) == nwant);
  CHECK(fb_road_breaks(road, FB_ROAD_RIGHT, br, 16) == nwant);
  for (size_t i = 0; i < nwant; ++i)
    CHECK(br[i] == want[i]);
  /* A wheel 5 m before the profile at 2 m/s passes them at (s + 5) / 2. */
  fb_tfun *v = NULL;
  CHECK(fb_road_wheel_velocity(road, FB_ROAD_RIGHT, 2.0, -5.0, &v, &err) == FB_OK);
  double bp[16] = {0};
  CHECK(v && fb_tfun_breakpoints(v, bp, 16) == nwant);
  for (size_t i = 0; v && i < nwant; ++i)
    CHECK(bp[i] == (want[i] + 5.0) / 2.0);
  fb_tfun_free(&v);
  fb_road_free(&road);
}

/* PCHIP slopes by hand on unequal widths and at a sharp turn.
 * Left, (0, 0), (1, 2), (3, 3): widths 1, 2, secants 2, 0.5; interior
 * d1 = (w0 + w1) / (w0/2 + w1/0.5) with w0 = 2*2 + 1 = 5, w1 = 2 + 2*1 = 4:
 * 9 / 10.5 = 6/7; ends d0 = ((2 + 2) 2 - 0.5) / 3 = 2.5, d2 = ((4 + 1)
 * 0.5 - 2 * 2) / 3 = -0.5, sign opposite to its secant: 0.
 * Right, (0, 0), (1, 1), (3, -15): secants 1, -8; d1 = 0 (extremum);
 * d0 = (4 * 1 + 8) / 3 = 4 > 3 * 1 where the data turn: limited to 3;
 * d2 = (5 * -8 - 2 * 1) / 3 = -14 (|d2| < 3 * 8: kept).
 * One-sided slopes 1e-9 m inside the knots: |z''| <= 30 here, 3e-8; 1e-7. */
static void test_csv_hand_slopes(void)
{
  const char *path = write_file("hand.csv", "s,z_left,z_right\n0,0,0\n1,2,1\n3,3,-15\n");
  fb_road *road = NULL;
  fb_err err;
  CHECK(fb_road_new_csv(path, &road, &err) == FB_OK);
  if (!road)
    return;
  CHECK_NEAR(fb_road_slope(road, FB_ROAD_LEFT, 1e-9), 2.5, 1e-7);
  CHECK_NEAR(fb_road_slope(road, FB_ROAD_LEFT, 1.0), 6.0 / 7.0, 1e-15);
  CHECK_NEAR(fb_road_slope(road, FB_ROAD_LEFT, 3.0 - 1e-9), 0.0, 1e-7);
  CHECK_NEAR(fb_road_slope(road, FB_ROAD_RIGHT, 1e-9), 3.0, 1e-7);
  CHECK_NEAR(fb_road_slope(road, FB_ROAD_RIGHT, 1.0), 0.0, 1e-15);
  CHECK_NEAR(fb_road_slope(road, FB_ROAD_RIGHT, 3.0 - 1e-9), -14.0, 1e-7);
  fb_road_free(&road);
}

/* Two tracks: a straight line z = 2 s + 1 on the left (PCHIP reproduces
 * it: every slope formula returns the common secant), a step-like
 * monotone profile on the right (no overshoot: stays in [0, 0.05]), on
 * unequal knot spacing (the line to rounding of secants over 0.2 m
 * widths: 1e-13 m, 1e-12); C1 at every knot (one-sided slopes 1e-9 m apart
 * agree within |z''| 1e-9 < 1e-6). */
static void test_csv_two_tracks(void)
{
  const char *path = write_file("tracks.csv", "z_right,s,z_left\n"
                                              "0,-1,-1\n0,0.5,2\n0,0.7,2.4\n0.05,1.5,4\n"
                                              "0.05,4,9\n0.05,4.2,9.4\n");
  fb_road *road = NULL;
  fb_err err;
  CHECK(fb_road_new_csv(path, &road, &err) == FB_OK);
  if (!road)
    return;
  int bad_line = 0, overshoot = 0;
  for (int i = 1; i < 520; ++i) { /* inside (-1, 4.2): the slope is 0 outside */
    const double s = -1.0 + 0.01 * i;
    bad_line += !(fabs(fb_road_height(road, FB_ROAD_LEFT, s) - (2 * s + 1)) <= 1e-13);
    bad_line += !(fabs(fb_road_slope(road, FB_ROAD_LEFT, s) - 2.0) <= 1e-12);
    const double zr = fb_road_height(road, FB_ROAD_RIGHT, s);
    overshoot += !(zr >= 0.0 && zr <= 0.05 + 1e-17); /* rounding of h00 + h01 = 1 */
  }
  CHECK(bad_line == 0);
  CHECK(overshoot == 0);
  static const double knots[] = {0.5, 0.7, 1.5, 4.0};
  for (size_t i = 0; i < sizeof knots / sizeof knots[0]; ++i) {
    const double s = knots[i];
    CHECK_NEAR(fb_road_slope(road, FB_ROAD_RIGHT, s - 1e-9),
               fb_road_slope(road, FB_ROAD_RIGHT, s + 1e-9), 1e-6);
    CHECK_NEAR(fb_road_height(road, FB_ROAD_RIGHT, s - 1e-12),
               fb_road_height(road, FB_ROAD_RIGHT, s + 1e-12), 1e-12);
  }
  fb_road_free(&road);
}

/* Each malformed file fails with the status and a message holding the
 * expected "path:line:" and text. */
static void check_csv_error(const char *name, const char *text, int status, int line,
                            const char *part)
{
  const char *path = write_file(name, text);
  char where[160];
  snprintf(where, sizeof where, "%s:%d:", path, line);
  fb_road *road = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_road_new_csv(path, &road, &err) == status);
  CHECK(road == NULL);
  const int ok = contains(DESCRIBED(&err), where) && contains(DESCRIBED(&err), part);
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  message was: %s\n", err.msg);
}

static void test_csv_errors(void)
{
  check_csv_error("bad_number.csv", "# profile\ns,z\n0,0\n1,abc\n", FB_EPARSE, 4,
                  "not a number (read: 'abc')");
  check_csv_error("unknown.csv", "s,q\n0,0\n1,1\n", FB_EPARSE, 1,
                  "unknown column 2 (expected columns s, z or s, z_left, z_right) (read: 'q')");
  check_csv_error("order.csv", "s,z\n0,0\n2,1\n\n2,3\n", FB_EPARSE, 5,
                  "not greater than the previous");
  check_csv_error("fields.csv", "s,z\n0,0\n1,1,2\n", FB_EPARSE, 3, "expected 2 fields");
  check_csv_error("short.csv", "s,z\n0,0\n1\n", FB_EPARSE, 3, "expected 2 fields");
  check_csv_error("both.csv", "s,z,z_left\n0,0,0\n", FB_EPARSE, 1, "both 'z'");
  check_csv_error("one_side.csv", "s,z_left\n0,0\n", FB_EPARSE, 1, "for each side");
  check_csv_error("no_s.csv", "z\n0\n", FB_EPARSE, 1, "no column 's'");
  check_csv_error("twice.csv", "s,z,s\n", FB_EPARSE, 1, "appears twice");
  check_csv_error("one_row.csv", "s,z\n0,0\n", FB_EPARSE, 2, "need at least 2");
  check_csv_error("empty.csv", "# nothing\n", FB_EPARSE, 1, "no header");
  check_csv_error("inf.csv", "s,z\n0,0\n1,inf\n", FB_EPARSE, 3,
                  "not a finite number (read: 'inf')");

  fb_road *road = NULL;
  fb_err err;
  char missing[TEST_PATH_MAX];
  snprintf(missing, sizeof missing, "%s/does_not_exist.csv", tmp_dir);
  CHECK(fb_road_new_csv(missing, &road, &err) == FB_EIO);
  CHECK(contains(DESCRIBED(&err), missing) && contains(DESCRIBED(&err), "cannot open"));
  CHECK(fb_road_new_csv(NULL, &road, &err) == FB_EINVAL);
}

/* Reading len bytes of text as tmp_dir/name fails with FB_EPARSE and
 * exactly the message "path:line: want". */
static void check_csv_message(const char *name, const char *text, size_t len, int line,
                              const char *want)
{
  const char *path = write_file_n(name, text, len);
  char msg[FB_ERR_MSG_MAX];
  snprintf(msg, sizeof msg, "%s:%d: %s", path, line, want);
  fb_road *road = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_road_new_csv(path, &road, &err) == FB_EPARSE);
  CHECK(road == NULL);
  const int ok = strcmp(DESCRIBED(&err), msg) == 0;
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  got    \"%s\"\n  wanted \"%s\"\n", err.msg, msg);
  fb_road_free(&road);
}

#define CHECK_CSV(name, text, line, want)                                                      \
  check_csv_message(name, text, sizeof text - 1, line, want)

/* Binary data, strtod's non-decimal numbers and repeated columns are
 * refused with the line; a byte-order mark is skipped. */
static void test_csv_strict(void)
{
  /* A NUL at the start of a line once made it read as blank, and skipped. */
  CHECK_CSV("nul_start.csv", "s,z\n0,0\n\0001,0.01\n2,0\n", 3,
            "binary data (byte 0x00 in column 1): not a CSV text file (expected UTF-8 text)");
  CHECK_CSV("nul_mid.csv", "s,z\n0,0\n1,0.01\0005\n2,0\n", 3,
            "binary data (byte 0x00 in column 7): not a CSV text file (expected UTF-8 text)");
  CHECK_CSV("latin1.csv", "# h\xf6he\ns,z\n0,0\n1,0\n", 1,
            "binary data (byte 0xf6 in column 4): not a CSV text file (expected UTF-8 text)");
  CHECK_CSV("hex.csv", "s,z\n0,0\n0x10,0\n", 3,
            "column 's': not a decimal number (read: '0x10')");
  CHECK_CSV("nan.csv", "s,z_left,z_right\n0,0,0\n1,0,NaN\n", 3,
            "column 'z_right': not a finite number (read: 'NaN')");
  CHECK_CSV("repeated.csv", "s,z,z\n0,0,0\n1,0,0\n", 1, "column 'z' appears twice");

  const char *path = write_file("bom.csv", "\xef\xbb\xbfs,z\r\n0,0\r\n1,0.25\r\n2,0.5\r\n");
  fb_road *road = NULL;
  fb_err err;
  CHECK(fb_road_new_csv(path, &road, &err) == FB_OK);
  if (!road)
    return;
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k)
    CHECK(fb_road_height(road, k, 1.0) == 0.25 && fb_road_height(road, k, 2.0) == 0.5);
  fb_road_free(&road);
}

int main(void)
{
  test_oblique_bump();
  test_speed_bumps();
  test_bump_errors();
  test_iso_classes();
  test_iso_psd();
  test_iso_rms();
  test_iso_seed();
  test_iso_slope_and_fade();
  test_iso_errors();
  tmp_dir = test_tmpdir();
  test_csv_values();
  test_csv_hand_slopes();
  test_profile_flat_breaks();
  test_csv_two_tracks();
  test_csv_errors();
  test_csv_strict();
  return check_report("test_road");
}
