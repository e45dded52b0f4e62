/* SPDX-License-Identifier: BSD-3-Clause */
/* Tire enveloping in a vehicle (docs/tire-envelope.md): the paper's 6x6
 * with point contact written out runs to the same numbers, bit for bit;
 * with enveloping tires its tire deflection over a bump shorter than
 * the tire's footprint is lower than point contact's (and the overlap's
 * peak force), and over a long gentle bump the peak force is the same
 * within the bound the effective road's distance from the road gives. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/envelope.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle_util.h"

static const double RADIUS = 0.55; /* m, the 6x6's tire (14.00 R20) */
static const double PI = 3.14159265358979323846;

/* Every corner of s with envelope model m and the tire's radius. */
static void envelop(fb_scenario *s, const fb_envelope_model *m)
{
  fb_err err = {0};
  for (size_t c = 0; c < s->ncorners; ++c) {
    REQUIRE(fb_corner_set_envelope(&s->corner[c], m, NULL, &err), &err);
    s->corner[c].tire_radius = RADIUS;
  }
}

/* The peak of column name of r from time t0 on (column 0 is time). */
static double peak(const fb_result *r, const char *name, double t0)
{
  const long col = fb_result_find(r, name);
  CHECK(col >= 0);
  double top = -INFINITY;
  for (size_t k = 0; col >= 0 && k < fb_result_nsamples(r); ++k)
    if (fb_result_row(r, k)[0] >= t0)
      top = fmax(top, fb_result_row(r, k)[col]);
  return top;
}

/* Point contact written out: every sample the same as without it. */
static void test_point_unchanged(void)
{
  fb_scenario *s = load_short();
  fb_result *plain = simulate_rigid(s);
  envelop(s, &fb_envelope_model_point);
  fb_result *point = simulate_rigid(s);
  CHECK(fb_result_nsamples(plain) == fb_result_nsamples(point));
  int same = fb_result_nsamples(plain) == fb_result_nsamples(point);
  for (size_t k = 0; same && k < fb_result_nsamples(plain); ++k)
    same = !memcmp(fb_result_row(plain, k), fb_result_row(point, k),
                   (size_t)(fb_result_find(plain, "tire_force_LF") + 1) * sizeof(double));
  CHECK(same);
  fb_result_free(&point);
  fb_result_free(&plain);
  fb_scenario_free(&s);
}

/* A 0.5 m bump, 0.1 m high, shorter than the cams' reach (2 a_e + l_s
 * = 1.44 m) and the circle's diameter: the tire envelops it, so the
 * effective bump is lower (its crest 0.06 to 0.07 m) and longer, and
 * every tire's spring is compressed less (the deflection's peak). The
 * overlap's effective road has a continuous slope and the tire's peak
 * force falls with it. The cams' effective road has a kink where a cam
 * first touches the bump from the side (the maximum of the cam's two
 * contacts, flat road and bump, changes branch; Schmeitz's cams are rigid
 * there), so its slope, the wheel's road velocity, jumps: through the
 * paper's tire damper (140000 N s/m) that is a force step of c_t V
 * times the jump, which the peak force shows (docs/tire-envelope.md,
 * "Limits"). */
static void test_short_bump(void)
{
  fb_scenario *s = load_short();
  /* An enveloping tire leaves the bump its reach (0.6 to 0.7 m) later
   * than its centre: RR at 3.24 s. */
  s->t_end = 3.5;
  fb_result *point = simulate_rigid(s);
  const double t0 = 0.5; /* the run's start settled, before the bump (at 1 s) */
  const double f_point = peak(point, "tire_force_LF", t0);
  const double d_point = peak(point, "tire_defl_RM", t0);
  const fb_envelope_model *const models[] = {&fb_envelope_model_cams,
                                             &fb_envelope_model_overlap};
  for (size_t k = 0; k < 2; ++k) {
    envelop(s, models[k]);
    fb_result *env = simulate_rigid(s);
    const double f_env = peak(env, "tire_force_LF", t0), d_env = peak(env, "tire_defl_RM", t0);
    printf("0.5 m bump, %s: peak LF tire force %.1f N (point contact %.1f N, %+.1f %%), peak "
           "RM tire deflection %.5f m (point contact %.5f m)\n",
           models[k]->name, f_env, f_point, 100.0 * (f_env - f_point) / f_point, d_env,
           d_point);
    CHECK(d_env < d_point);
    if (models[k] == &fb_envelope_model_overlap)
      CHECK(f_env < f_point);
    fb_result_free(&env);
  }
  fb_result_free(&point);
  fb_scenario_free(&s);
}

/* A 20 m (1 - cos) bump, 0.1 m high: the effective road is the road
 * within B (test_envelope.c, "The long-wavelength limit": for the cams
 * k2 l_s^2 / 8 + a k1 (k1 a / b)^(1 / (c - 1)) plus the grid's ds k1,
 * with k1 = pi h / L and k2 = 2 pi^2 h / L^2 the bump's greatest slope
 * and curvature), so each tire's force moves by at most its spring's
 * k_t B and its damper's c_t V (2 pi / L) B, the road's error being a
 * wave no shorter than the bump; twice that covers the wheel's own
 * response, which only attenuates a road input this slow. */
static void test_long_bump(void)
{
  fb_scenario *s = load_short();
  const double h = 0.1, len = 20.0;
  road_bump(s)->length = len;
  road_bump(s)->height = h;
  s->t_end = 1.0 + (len + 3.0) / s->speed + 1.0;
  fb_result *point = simulate_rigid(s);
  const double t0 = 0.5; /* as for the short bump */
  const double f_point = peak(point, "tire_force_LF", t0);
  envelop(s, &fb_envelope_model_cams);
  fb_result *env = simulate_rigid(s);
  const double f_env = peak(env, "tire_force_LF", t0);
  const fb_corner_params *c = &s->corner[0];
  /* The static deflection the library gives the cams: the load and the
   * wheels shared by the corners. */
  const double load = (s->total_weight + 6.0 * c->wheel_mass * s->gravity) / 6.0;
  CHECK(s->ncorners == 6);
  const double defl = load / c->tire_k;
  fb_envelope_params p;
  fb_envelope_params_init(&fb_envelope_model_cams, &p);
  const fb_envelope_cams_params *cp = (const void *)p.bytes;
  const double a = cp->length * RADIUS, b = cp->height * RADIUS, ce = cp->order;
  const double ls = cp->shift * fb_envelope_chord(RADIUS, defl);
  const double k1 = PI * h / len, k2 = 2.0 * PI * PI * h / (len * len);
  const double ds = 2.0 * (a + 0.5 * ls) / 256.0;
  const double bound =
      k2 * ls * ls / 8.0 + a * k1 * pow(k1 * a / b, 1.0 / (ce - 1.0)) + ds * k1;
  const double tol = 2.0 * (c->tire_k * bound + c->tire_c * s->speed * 2.0 * PI / len * bound);
  printf("20 m bump: peak LF tire force %.1f N with point contact, %.1f N with cams "
         "(difference %.1f N, bound %.1f N)\n",
         f_point, f_env, fabs(f_env - f_point), tol);
  CHECK(fabs(f_env - f_point) <= tol);
  fb_result_free(&env);
  fb_result_free(&point);
  fb_scenario_free(&s);
}

int main(void)
{
  test_point_unchanged();
  test_short_bump();
  test_long_bump();
  return check_report("test_envelope_vehicle");
}
