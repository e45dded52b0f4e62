/* SPDX-License-Identifier: BSD-3-Clause */
/* An ISO 8608 road given by its r.m.s. (road.iso8608.rms):
 *   - Gd(n0) from the r.m.s. against the closed form of the PSD's
 *     integral, and class C's known r.m.s. over the default band;
 *   - a generated road's sample r.m.s. over a long distance against the
 *     requested one, within the two bounds derived below;
 *   - the scenario key: exactly one of class and rms, and the road it
 *     makes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/road.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "road_util.h"
#include "vehicle_util.h"

static const double N0 = 0.1; /* cycles/m, ISO 8608's reference */

/* rms^2 = Gd(n0) n0^2 (1/n_min - 1/n_max): class C (256e-6 m^3) over
 * 0.011 .. 2.83 cycles/m is 15.23 mm (docs/roads.md: 15.2 mm). */
static void test_closed_form(void)
{
  const double gd0_c = 256e-6, n_min = 0.011, n_max = 2.83;
  const double rms_c = sqrt(gd0_c * N0 * N0 * (1 / n_min - 1 / n_max));
  CHECK_NEAR(rms_c, 0.0152257, 1e-7); /* sqrt(2.56e-6 x 90.5557) by hand */
  CHECK_NEAR(fb_road_iso8608_rms_gd0(rms_c, n_min, n_max), gd0_c, 1e-15);
  /* The class nearest on a log scale: C, and the limits halfway. */
  CHECK(fb_road_iso8608_class_of(gd0_c) == 'C');
  CHECK(fb_road_iso8608_class_of(gd0_c * 1.99) == 'C');
  CHECK(fb_road_iso8608_class_of(gd0_c * 2.01) == 'D');
  CHECK(fb_road_iso8608_class_of(1e-9) == 'A' && fb_road_iso8608_class_of(1) == 'H');
}

/* A track z(s) = sum_k a_k cos(2 pi n_k s + p_k), a_k^2 = 2 Gd(n_k) dn,
 * n_k the midpoints of the band's K sub-bands (flexbond/road.h), sampled
 * at N = P M points s_i = i ds, ds = 1 / (dn M): P whole periods of every
 * difference n_j - n_k = (j - k) dn. Its sample mean square is
 *   (1/N) sum_i z^2 = S + (1/2) sum_jk a_j a_k C_jk,
 *   S = sum_k a_k^2 / 2 (the harmonics' own power),
 * since cos x cos y = (cos(x - y) + cos(x + y)) / 2, and the mean of
 * cos(2 pi (j - k) i / M + p) over P M points is exactly 0 for
 * 0 < |j - k| < M; C_jk, the mean of cos(2 pi (n_j + n_k) s_i + p), is
 * bounded by 1 / (N |sin(pi (n_j + n_k) ds)|) (the geometric sum): the
 * sampling bound B. And S itself is the midpoint rule of the PSD's
 * integral rms^2: for Gd ~ n^-2 (convex) it is below rms^2 by at most
 * sum_k Gd0 n0^2 dn^3 / (4 n_lo,k^4) (the midpoint rule's error
 * h^3 f''/24 with f'' = 6 n^-4 at the sub-band's low end): the bias M. */
static void test_generated_rms(void)
{
  const double rms = 0.025, n_min = 0.011, n_max = 2.83;
  const size_t K = 1024, M = 8192, P = 64, N = P * M;
  fb_road_iso8608_params p;
  fb_road_iso8608_defaults(&p);
  p.n_min = n_min;
  p.n_max = n_max;
  p.nharmonics = K;
  p.seed = 11;
  p.gd0 = fb_road_iso8608_rms_gd0(rms, n_min, n_max);
  fb_road *road = NULL;
  fb_err err;
  CHECK(fb_road_new_iso8608(&p, &road, &err) == FB_OK);
  if (!road)
    return;
  const double dn = (n_max - n_min) / (double)K, ds = 1 / (dn * (double)M);
  double *a = malloc(K * sizeof *a);
  double S = 0, bias = 0, bound = 0;
  for (size_t k = 0; a && k < K; ++k) {
    const double nk = n_min + ((double)k + 0.5) * dn, lo = n_min + (double)k * dn;
    a[k] = sqrt(2 * p.gd0 * (N0 / nk) * (N0 / nk) * dn);
    S += a[k] * a[k] / 2;
    bias += p.gd0 * N0 * N0 * dn * dn * dn / (4 * pow(lo, 4));
  }
  for (size_t j = 0; a && j < K; ++j)
    for (size_t k = 0; k < K; ++k) {
      const double f = 2 * n_min + ((double)j + (double)k + 1) * dn;
      bound += 0.5 * a[j] * a[k] / ((double)N * fabs(sin(3.14159265358979323846 * f * ds)));
    }
  for (int track = FB_ROAD_LEFT; track <= FB_ROAD_RIGHT; ++track) {
    double ms = 0;
    for (size_t i = 0; i < N; ++i) {
      const double z = fb_road_height(road, track, (double)i * ds);
      ms += z * z / (double)N;
    }
    /* The generator's own power within the sampling bound, */
    CHECK(fabs(ms - S) <= bound);
    /* and the requested r.m.s. within the bias and that bound. */
    CHECK(rms * rms - S >= 0 && rms * rms - S <= bias);
    CHECK(fabs(ms - rms * rms) <= bias + bound);
    fprintf(stderr,
            "track %d: sample r.m.s. %.6g m, requested %.6g m; |ms - S| = %.3g <= B = %.3g, "
            "rms^2 - S = %.3g <= M = %.3g (m^2)\n",
            track, sqrt(ms), rms, fabs(ms - S), bound, rms * rms - S, bias);
  }
  free(a);
  fb_road_free(&road);
}

/* The example's road section with its ISO 8608 road given so. */
static int load_iso(const char *iso, fb_scenario **s, fb_err *err)
{
  char road[512];
  snprintf(road, sizeof road,
           "road:\n  speed_kmh: 10\n  iso8608:\n%s    seed: 3\n    front_start: -5\n", iso);
  return load_replaced("\nroad:\n", 1, "\nsimulation:\n", road, s, err);
}

static void test_scenario_key(void)
{
  fb_scenario *s = NULL;
  fb_err err;
  CHECK(load_iso("    rms: 0.02\n", &s, &err) == FB_OK);
  fb_road_iso8608_params iso;
  if (s) {
    CHECK(fb_scenario_road_random(s, &iso));
    CHECK_NEAR(iso.gd0, fb_road_iso8608_rms_gd0(0.02, 0.011, 2.83), 1e-18);
    /* 0.02 m over the band: Gd0 = 4.4e-4 m^3, nearest class C (256e-6 .. x2). */
    CHECK(iso.road_class == 'C');
    CHECK(road_random(s)->road_class == -1);
  }
  fb_scenario_free(&s);
  CHECK(load_iso("    rms: 0.02\n    class: C\n", &s, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "exactly one of class and rms") != NULL);
  CHECK(strstr(err.msg, "bad.yaml:") != NULL);
  CHECK(load_iso("", &s, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "neither is given") != NULL);
  CHECK(load_iso("    rms: -0.01\n", &s, &err) == FB_EINVAL);
  /* A class road is as before: its own Gd(n0) is the class's. */
  CHECK(load_iso("    class: D\n", &s, &err) == FB_OK);
  if (s) {
    CHECK(fb_scenario_road_random(s, &iso) && iso.gd0 == 0 && iso.road_class == 'D');
    double gd0 = 0;
    CHECK(fb_road_iso8608_params_gd0(&iso, &gd0, &err) == FB_OK && gd0 == 1024e-6);
  }
  fb_scenario_free(&s);
}

int main(void)
{
  test_closed_form();
  test_generated_rms();
  test_scenario_key();
  return check_report("test_road_rms");
}
