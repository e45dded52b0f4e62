/* SPDX-License-Identifier: BSD-3-Clause */
/* Vehicles as data: vehicles of 4, 6, 8 and 10 corners (and one, two or
 * three mounted bodies) built from scenario text alone, each started at
 * its static equilibrium. The independent answer is statics: the tires'
 * normal reactions carry the whole weight (hull plus payload, the
 * mounted bodies, the wheels) and its pitch and roll moments about the
 * hull's centre of mass (the rigid hull's equilibrium: sum of forces and
 * of moments zero, whatever the springs' stiffnesses, which only decide
 * how a statically indeterminate vehicle shares the load). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "check.h"

/* Appends printf text to buf (of size cap) at *len. */
static void add(char *buf, size_t cap, size_t *len, const char *fmt, double a, double b,
                double c)
{
  int n = snprintf(buf + *len, cap - *len, fmt, a, b, c);
  if (n > 0 && *len + (size_t)n < cap)
    *len += (size_t)n;
}

/* A scenario of naxles axles 1.2 m apart (front axle at x = 2.0 m),
 * track 2.0 m, springs stiffer towards the rear, and nmounts bodies. */
static char *scenario_text(int naxles, int nmounts)
{
  const size_t cap = 8192;
  char *t = malloc(cap);
  if (!t)
    return NULL;
  size_t len = 0;
  add(t, cap, &len,
      "scenario: layout\n"
      "gravity: 9.81\n"
      "hull:\n  mass: %.17g\n  Ixx: %.17g\n  Iyy: %.17g\n"
      "  material: {young: 200e9, poisson: 0.3, density: 7860, thickness: 0.008}\n"
      "  edges: {front_x: 2.5, rear_x: -3.0, left_y: 1.0, right_y: -1.0}\n",
      3000.0, 3500.0, 12000.0);
  /* The load's centroid is off the centre of mass: its moments count. */
  add(t, cap, &len,
      "load:\n  total_weight: %.17g\n  payload: weight-only\n"
      "  points: [[%.17g, 0.3], [-1.5, -0.4], [0.4, 0.5]]\n",
      60000.0, 1.1, 0.0);
  static const char *const names[3] = {"driver", "engine", "commander"};
  static const double mx[3] = {1.8, 1.2, -0.6}, my[3] = {0.5, -0.4, 0.6},
                      mm[3] = {100.0, 450.0, 95.0};
  if (nmounts > 0) {
    add(t, cap, &len, "mounts:\n", 0, 0, 0);
    for (int b = 0; b < nmounts; ++b) {
      int n = snprintf(t + len, cap - len,
                       "  - {name: %s, mass: %.17g, stiffness: 20000, damping: 1500, x: %.17g, "
                       "y: %.17g}\n",
                       names[b], mm[b], mx[b], my[b]);
      len += n > 0 ? (size_t)n : 0;
    }
  }
  add(t, cap, &len,
      "wheel: {mass: %.17g, tire_k: 600000, tire_c: 2000}\n"
      "suspensions:\n  axles:\n",
      150.0, 0, 0);
  for (int a = 0; a < naxles; ++a) {
    int n = snprintf(t + len, cap - len,
                     "    - {name: A%d, x: %.17g, y: 1.0, spring_k: %.17g, damper_c: 20000}\n",
                     a + 1, 2.0 - 1.2 * a, 150000.0 + 60000.0 * a);
    len += n > 0 ? (size_t)n : 0;
  }
  add(t, cap, &len,
      "road:\n  speed_kmh: 20\n"
      "  bump: {height: 0.05, length: 1.0, angle_deg: 0, first_contact: %.17g}\n"
      "simulation: {t_end: %.17g, rtol: 1e-8, atol: 1e-10, sample_rate: 100, initial: "
      "static}\n",
      0.3, 1.5, 0);
  return t;
}

/* The static reactions of the vehicle of text, at t = 0 (before the
 * bump), against its weights' sum and moments. */
static void check_statics(int naxles, int nmounts)
{
  char *text = scenario_text(naxles, nmounts);
  CHECK(text != NULL);
  if (!text)
    return;
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load_string(text, strlen(text), "layout.yaml", &s, &err) == FB_OK);
  if (!s) {
    fprintf(stderr, "layout: %s\n%s\n", err.msg, text);
    free(text);
    return;
  }
  CHECK(s->ncorners == (size_t)(2 * naxles) && s->nmounts == (size_t)nmounts);
  /* Without an outputs list, every tire's reaction is recorded. */
  CHECK(s->noutputs == s->ncorners);
  fb_result *r = NULL;
  CHECK(fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err) == FB_OK);
  if (!r)
    fprintf(stderr, "layout %d axles: %s\n", naxles, err.msg);
  /* Weights and their moments about the centre of mass: the load points
   * (equal shares), the mounted bodies, the wheels (at their corners). */
  double weight = s->total_weight, mx = 0.0, my = 0.0;
  for (size_t k = 0; k < s->nload; ++k) {
    mx += s->total_weight / (double)s->nload * s->load_x[k];
    my += s->total_weight / (double)s->nload * s->load_y[k];
  }
  for (size_t b = 0; b < s->nmounts; ++b) {
    const double w = s->mount[b].mass * s->gravity;
    weight += w;
    mx += w * s->mount[b].x;
    my += w * s->mount[b].y;
  }
  double sum = 0.0, fx = 0.0, fy = 0.0;
  for (size_t c = 0; r && c < s->ncorners; ++c) {
    const fb_corner_params *p = &s->corner[c];
    const double w = p->wheel_mass * s->gravity;
    weight += w;
    mx += w * p->x;
    my += w * p->y;
    char name[64];
    snprintf(name, sizeof name, "contact_force_%s", p->name);
    const long col = fb_result_find(r, name);
    CHECK(col > 0);
    if (col <= 0)
      continue;
    const double f = fb_result_row(r, 0)[col];
    sum += f;
    fx += f * p->x;
    fy += f * p->y;
  }
  /* The static solve is a linear solve of the equilibrium to round-off:
   * 1e-9 of the weight (and of weight x track for the moments) is far
   * above its 1e-13 and far below any lost load (a wheel's weight is
   * 2e-2 of the total). */
  if (r) {
    fprintf(stderr, "layout %zu corners, %zu mounts: reactions %.10g N, weight %.10g N\n",
            s->ncorners, s->nmounts, sum, weight);
    CHECK(fabs(sum - weight) <= 1e-9 * weight);
    CHECK(fabs(fx - mx) <= 1e-9 * weight * 2.0);
    CHECK(fabs(fy - my) <= 1e-9 * weight * 2.0);
  }
  fb_result_free(&r);
  fb_scenario_free(&s);
  free(text);
}

int main(void)
{
  check_statics(2, 1);
  check_statics(3, 2);
  check_statics(4, 3);
  check_statics(5, 2);
  return check_report("test_layouts");
}
