/* SPDX-License-Identifier: BSD-3-Clause */
/* A vehicle on three corners whose static loads are known by hand, for
 * the spring and stop tests: a rigid hull with its centre of mass at the
 * origin, its whole weight W = THREE_CORNER_WEIGHT at the one load point
 * (0, 0); the front corner F at (2, 0), the rear ones LR and RR at
 * (-1, +-0.9). Moments about the centre: W_F 2 = (W_LR + W_RR) 1 and
 * W_LR = W_RR, with W_F + W_LR + W_RR = W: each spring carries W / 3
 * (motion ratio 1; the wheels' own weight rests on the tires).
 * Header-only test helper (static functions). */
#ifndef FLEXBOND_TESTS_THREE_CORNER_H
#define FLEXBOND_TESTS_THREE_CORNER_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/io.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle/vehicle_internal.h"

#define THREE_CORNER_WEIGHT 30000.0

/* The scenario's text with front, rear: text inside the front corner's
 * and the rear corners' flow mappings (", spring_preload: 100", or ""),
 * bump: the road's bump height (m), initial: "zero" or "static", more:
 * outputs' lines after the four of the springs; new, NULL when out of
 * memory. */
static char *three_corner_text(const char *front, const char *rear, double bump,
                               const char *initial, const char *more)
{
  const char *fmt =
      "scenario: three_corner\n"
      "gravity: 9.81\n"
      "hull:\n  mass: 2500\n  Ixx: 2000\n  Iyy: 6000\n"
      "  material: {young: 200e9, poisson: 0.3, density: 7860, thickness: 0.008}\n"
      "  edges: {front_x: 2.5, rear_x: -1.5, left_y: 1.0, right_y: -1.0}\n"
      "load:\n  total_weight: %.17g\n  payload: weight-only\n  points: [[0, 0]]\n"
      "wheel: {mass: 60, tire_k: 400000, tire_c: 1500}\n"
      "suspensions:\n  corners:\n"
      "    - {name: F, x: 2.0, y: 0, spring_k: 100000, damper_c: 3000%s}\n"
      "    - {name: LR, x: -1.0, y: 0.9, spring_k: 100000, damper_c: 3000%s}\n"
      "    - {name: RR, x: -1.0, y: -0.9, spring_k: 100000, damper_c: 3000%s}\n"
      "road:\n  speed_kmh: 20\n"
      "  bump: {height: %.17g, length: 1.0, angle_deg: 0, first_contact: 0.5}\n"
      "outputs:\n"
      "  - {signal: spring_defl, of: F}\n  - {signal: spring_force, of: F}\n"
      "  - {signal: spring_defl, of: LR}\n  - {signal: spring_force, of: LR}\n%s"
      "simulation: {t_end: 2.5, rtol: 1e-8, atol: 1e-10, sample_rate: 200, initial: %s}\n";
  const size_t size = strlen(fmt) + strlen(front) + 2 * strlen(rear) + strlen(more) + 128;
  char *t = malloc(size);
  if (t)
    snprintf(t, size, fmt, THREE_CORNER_WEIGHT, front, rear, rear, bump, more, initial);
  return t;
}

/* The scenario of three_corner_text loaded as three_corner.yaml into
 * *out; err's message on failure. */
static int three_corner_load(const char *front, const char *rear, double bump,
                             const char *initial, const char *more, fb_scenario **out,
                             fb_err *err)
{
  *out = NULL;
  char *t = three_corner_text(front, rear, bump, initial, more);
  if (!t)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  const int rc = fb_scenario_load_string(t, strlen(t), "three_corner.yaml", out, err);
  free(t);
  return rc;
}

/* The scenario with front's text in its front corner is refused with
 * a message holding want (printed when it does not). */
static void three_corner_refused(const char *front, const char *want)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(three_corner_load(front, "", 0.0, "zero", "", &s, &err) != FB_OK && !s);
  CHECK(strstr(err.msg, want) != NULL);
  if (!strstr(err.msg, want))
    fprintf(stderr, "  want: %s\n  got:  %s\n", want, err.msg);
  fb_scenario_free(&s);
}

/* A mass of m kg on corner c's spring (and its stops, if any) alone: the
 * I "mass", the corner's C "spring" and R "stops" on one 1-junction, no
 * gravity; probes x (the travel), v (the mass's velocity) and U (the
 * spring's stored energy). Released from travel x0 with momentum p0:
 * its run to t_end at rtol, atol 1e-2 rtol, in *out. */
static int mass_on_corner_spring(const fb_corner_params *c, double m, double x0, double p0,
                                 double t_end, double rtol, fb_result **out, fb_err *err)
{
  *out = NULL;
  const fb_spring_context ctx = fb_corner_spring_context(c);
  fb_bg *bg = NULL;
  fb_mat *mass = NULL;
  const size_t one = 1;
  int rc = fb_bg_new("mass_on_spring", &bg, err);
  if (!rc)
    rc = fb_mat_new_scaled_identity(1, m, &mass, err);
  if (!rc)
    rc = fb_bg_add_field(bg, "mass", FB_BG_I, 1, &one, &mass, err);
  if (!rc)
    rc = fb_corner_spring_law(c)->ops->build(c->spring.bytes, &ctx, bg, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "J", FB_BG_J1, 1, err);
  if (!rc)
    rc = fb_bg_connect(bg, "b_mass", "J", "mass", err);
  if (!rc)
    rc = fb_bg_connect(bg, "b_spring", "J", "spring", err);
  if (!rc && fb_stops_any(&c->stops))
    rc = vehicle_add_stops(&c->stops, "stops", "spring", bg, err);
  if (!rc && fb_stops_any(&c->stops))
    rc = fb_bg_connect(bg, "b_stops", "J", "stops", err);
  const fb_probe_spec probes[3] = {{"x", FB_PROBE_STATE, "spring", 0, 0, 1.0, NULL, NULL, 0},
                                   {"v", FB_PROBE_FLOW, "b_mass", 0, 0, 1.0, NULL, NULL, 0},
                                   {"U", FB_PROBE_ENERGY, "spring", 0, 0, 1.0, NULL, NULL, 0}};
  fb_bd *bd = NULL;
  if (!rc)
    rc = fb_bd_build(bg, probes, 3, &bd, err);
  double x_init[2] = {0.0, 0.0};
  for (size_t k = 0; bd && k < 2; ++k)
    x_init[k] = !strcmp(fb_bd_state_name(bd, k), "spring.q") ? x0 : p0;
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = t_end;
  o.rtol = rtol;
  o.atol = 1e-2 * rtol;
  o.x0 = x_init;
  if (!rc)
    rc = fb_sim_run(bd, &o, out, err);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
  return rc;
}

#endif
