/* SPDX-License-Identifier: BSD-3-Clause */
/* Roads in the scenario (road.bump | road.iso8608 | road.profile) and in
 * the vehicle's road fragment (src/road through fb_vehicle_road):
 *   - a profile file holding the paper's bump, sampled every 2 cm, drives
 *     the vehicle as the analytic bump does;
 *   - the ISO 8608 example loads, runs, and is reproducible from its seed;
 *   - wheel start positions follow the documented convention;
 *   - bad roads are refused at their YAML location. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "check.h"
#include "road_util.h"
#include "vehicle_util.h"

/* The example scenario with its road section replaced by `road` (the text
 * from "road:" up to "simulation:"), loaded from a string named bad.yaml. */
static int load_with_road(const char *road, fb_scenario **out, fb_err *err)
{
  return load_replaced("\nroad:\n", 1, "\nsimulation:\n", road, out, err);
}

/* The paper's bump as a measured profile: z_left(s) the (1 - cos) bump
 * from s = 0, z_right the same from s = (y_LF - y_RF) tan(45 deg) = 2.1 m,
 * sampled every 5 mm, with the left front wheel at -V first_contact at
 * t = 0. PCHIP's slopes are first-order accurate next to the bump's ends,
 * where z'' jumps: the road velocity is off by up to about h max|z''| / 2
 * = 0.005 x 0.144 / 2 = 3.6e-4 against a largest slope of 0.085, 0.4 %.
 * The tire forces and the tire damper's power take the road velocity
 * directly through the tire damper (measured 0.18 % of their range); the
 * other outputs are filtered by the suspension (7.4e-5 at most). 5e-3 of each range
 * bounds the first, while the tracks swapped (the right wheels meeting
 * the bump 0.76 s early) would put tens of percent on RF, RM and RR. */
static void test_profile_equals_bump(const fb_scenario *bump)
{
  const char *csv = "road_profile_test.csv";
  FILE *fp = fopen(csv, "w");
  CHECK(fp != NULL);
  if (!fp)
    return;
  const double pi = 3.14159265358979323846, h = 0.10, len = 3.70, offset = 2.1, ds = 0.005;
  fprintf(fp, "# the paper's bump, left and right tracks\ns,z_left,z_right\n");
  for (int i = 0; i <= 2000; ++i) {
    const double s = -1.0 + ds * i,
                 zl = s >= 0 && s <= len ? h / 2 * (1 - cos(2 * pi * s / len)) : 0;
    const double sr = s - offset;
    const double zr = sr >= 0 && sr <= len ? h / 2 * (1 - cos(2 * pi * sr / len)) : 0;
    fprintf(fp, "%.6f,%.12g,%.12g\n", s, zl, zr);
  }
  fclose(fp);
  char road[256];
  snprintf(road, sizeof road,
           "road:\n  speed_kmh: 10\n  profile:\n    file: %s\n    front_start: %.12g\n", csv,
           -10.0 / 3.6 * 5.0);
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(load_with_road(road, &s, &err) == FB_OK);
  if (!s)
    fprintf(stderr, "%s\n", err.msg);
  if (s) {
    CHECK(s->road_type == &fb_road_type_profile);
    /* The bump window starts when the LF wheel reaches s = 0, at 5 s. */
    CHECK_NEAR(fb_scenario_road_entry(s, 0), 5.0, 1e-9);
    fb_result *a = simulate_rigid(bump), *b = simulate_rigid(s);
    if (a && b)
      check_close(a, b, 5e-3, "profile vs bump");
    fb_result_free(&a);
    fb_result_free(&b);
  }
  fb_scenario_free(&s);
  remove(csv);
}

static void test_iso_example(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load("../examples/apc6x6_iso_road.yaml", &s, &err) == FB_OK);
  if (!s) {
    fprintf(stderr, "%s\n", err.msg);
    return;
  }
  const fb_road_random_params *iso = road_random(s);
  CHECK(iso->road_class == 'C' - 'A' && iso->seed == 2026 && iso->fade_in == 10.0);
  /* Wheel starts: LF at front_start, the others behind it by x_LF - x. */
  for (int c = 0; c < (int)s->ncorners; ++c)
    CHECK_NEAR(fb_scenario_wheel_start(s, c), -5.0 - (s->corner[0].x - s->corner[c].x), 1e-12);
  s->t_end = 3.0;
  fb_result *a = simulate_rigid(s), *b = simulate_rigid(s);
  if (a && b)
    check_close(a, b, 0.0, "same seed");
  road_random(s)->seed = 2027;
  fb_result *c = simulate_rigid(s);
  if (a && c) {
    const long col = fb_result_find(a, "driver_acc");
    double diff = 0.0;
    for (size_t k = 0; col > 0 && k < fb_result_nsamples(a); ++k)
      diff = fmax(diff, fabs(fb_result_row(a, k)[col] - fb_result_row(c, k)[col]));
    CHECK(diff > 0.01); /* another road: another ride (m/s^2) */
  }
  fb_result_free(&a);
  fb_result_free(&b);
  fb_result_free(&c);
  fb_scenario_free(&s);
}

static void expect_refused(const char *road, const char *phrase)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  CHECK(load_with_road(road, &s, &err) != FB_OK);
  CHECK(s == NULL);
  CHECK(strstr(err.msg, phrase) != NULL && strstr(err.msg, "bad.yaml:") != NULL);
  if (!strstr(err.msg, phrase))
    fprintf(stderr, "  message: %s\n", err.msg);
  fb_scenario_free(&s);
}

static void test_errors(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  /* A Brazilian type I bump instead of height and length. */
  CHECK(load_with_road("road:\n  speed_kmh: 10\n  bump: {type: I, angle_deg: 45, "
                       "first_contact: 5}\n",
                       &s, &err) == FB_OK);
  if (s)
    CHECK(road_bump(s)->height == 0.08 && road_bump(s)->length == 1.50);
  fb_scenario_free(&s);
  expect_refused(
      "road:\n  speed_kmh: 10\n  bump: {type: III, angle_deg: 45, first_contact: 5}\n", "III");
  expect_refused("road:\n  speed_kmh: 10\n  bump: {type: I, height: 0.1, angle_deg: 45, "
                 "first_contact: 5}\n",
                 "either a type or height and length");
  expect_refused("road:\n  speed_kmh: 10\n  bump: {height: 0.1, length: 3.7, angle_deg: 45, "
                 "first_contact: 5}\n  iso8608: {class: C, seed: 1}\n",
                 "give either 'bump' or 'iso8608', not both");
  expect_refused("road:\n  speed_kmh: 10\n", "missing one of 'bump', 'iso8608', 'profile'");
  expect_refused("road:\n  speed_kmh: 10\n  iso8608: {class: K, seed: 1}\n",
                 "road.iso8608.class: unknown value 'K'; expected A | B");
  expect_refused(
      "road:\n  speed_kmh: 10\n  bump: {height: 0.1, angle_deg: 45, first_contact: 5}\n",
      "road.bump: a bump needs its length (or a type)");
  expect_refused("road:\n  speed_kmh: 10\n  profile: {file: no_such_road.csv}\n",
                 "no_such_road.csv");
}

int main(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &s, &err) == FB_OK);
  if (s) {
    /* Wheel starts of the bump: LF at -V first_contact. */
    CHECK_NEAR(fb_scenario_wheel_start(s, 0), -s->speed * road_bump(s)->first_contact, 1e-12);
    test_profile_equals_bump(s);
  }
  fb_scenario_free(&s);
  test_iso_example();
  test_errors();
  return check_report("test_road_scenario");
}
