/* SPDX-License-Identifier: BSD-3-Clause */
/* Stepping a vehicle (fb_vehicle_stepper, flexbond/vehicle.h), System 1
 * of examples/apc6x6.yaml: advanced in 0.1 s steps it gives
 * fb_vehicle_run's outputs, also with tires that leave the ground
 * (examples/apc6x6_liftoff.yaml: contact events between the stops); a held load force and a
 * heavier load set on the way move the tires' reactions by what statics says once the vehicle
 * has settled (Newton's second law at rest); a scenario whose vehicle has other states is
 * refused. With the road under each wheel as inputs: a height step under one wheel moves its
 * tire's reaction at once by the tire's stiffness times the step (the deflection jumps, the
 * rate is zero); the whole road raised smoothly leaves the reactions, once settled, at their
 * values of the same vehicle settled on its unmoved road (it rides up rigidly); a state set
 * back to an earlier time and state goes on as it did, to the bit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "bgtest_util.h"
#include "check.h"
#include "road_util.h"

static const char *const apc_path = "../examples/apc6x6.yaml";

/* s at speed (m/s), its left front wheel meeting the bump at bump_time
 * (s), its run ending on the first 0.1 s after the last wheel has left
 * the bump. */
static void fit_bump(fb_scenario *s, double speed, double bump_time)
{
  s->speed = speed;
  road_bump(s)->first_contact = bump_time;
  double last_exit = 0;
  for (size_t c = 0; c < s->ncorners; ++c)
    last_exit = fmax(last_exit, fb_scenario_road_exit(s, (int)c));
  s->t_end = ceil(10 * last_exit + 1) / 10;
}

/* The largest |step - run| of every output over its range in the run,
 * at every 0.1 s of the run of s (taken over: freed once the stepper
 * has its copy). with_events: the run must have switched a tire's
 * contact (events the stepper meets between its stop times). */
static void check_steps_equal_run(fb_scenario *s, int with_events)
{
  fb_err err;
  const int nsteps = (int)lround(10 * s->t_end);
  fb_result *res = NULL;
  fb_vehicle_stepper *st = NULL;
  MUST(fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &res, &err), &err);
  MUST(fb_vehicle_stepper_new(s, FB_SYSTEM_RIGID, NULL, &st, &err), &err);
  fb_scenario_free(&s); /* the stepper keeps its own copy */
  if (!res || !st)
    goto done;
  CHECK(!with_events || fb_result_stats(res)->events > 0);
  const size_t nout = fb_vehicle_stepper_noutputs(st);
  CHECK(nout + 1 == fb_result_ncols(res));
  for (size_t k = 0; k < nout && k + 1 < fb_result_ncols(res); ++k) {
    CHECK(!strcmp(fb_vehicle_stepper_output_name(st, k), fb_result_col_name(res, k + 1)));
    CHECK(!strcmp(fb_vehicle_stepper_output_unit(st, k), fb_result_col_unit(res, k + 1)));
    CHECK(fb_vehicle_stepper_output_find(st, fb_result_col_name(res, k + 1)) == (long)k);
  }
  CHECK(fb_vehicle_stepper_output_find(st, "no_such_output") == -1);
  double *y = calloc(nout + 1, sizeof *y), worst = 0;
  const char *worst_name = "";
  for (int i = 1; y && i <= nsteps; ++i) {
    const double t = 0.1 * i;
    MUST(fb_vehicle_stepper_advance(st, t, &err), &err);
    MUST(fb_vehicle_stepper_outputs(st, y, &err), &err);
    const double *row = fb_result_row(res, (size_t)i * 100); /* 1000 Hz sampling */
    CHECK(fabs(row[0] - t) < 1e-12);
    for (size_t k = 0; k < nout; ++k) {
      double lo = INFINITY, hi = -INFINITY;
      for (size_t r = 0; r < fb_result_nsamples(res); ++r) {
        lo = fmin(lo, fb_result_row(res, r)[k + 1]);
        hi = fmax(hi, fb_result_row(res, r)[k + 1]);
      }
      const double rel = fabs(y[k] - row[k + 1]) / fmax(hi - lo, 1e-300);
      if (rel > worst) {
        worst = rel;
        worst_name = fb_vehicle_stepper_output_name(st, k);
      }
    }
  }
  /* Both integrate with the scenario's rtol 1e-6 and take CVODE's own
   * steps, the stepper reading the state at each stop from the
   * interpolant as the run samples it; they differ by rounding in the
   * calls (measured 1.5e-7 of an output's range, the driver's
   * acceleration; 9e-13 with the lift-off events), far below the runs'
   * own global error (1.7e-6 when the stepper still shortened its steps
   * to land on each stop). 1e-5 keeps a margin of 60 over that; a
   * stepper that lost the state at a stop, or read the outputs at
   * another time (1 ms off moves an acceleration by a percent of its
   * range over the bump), fails it. */
  fprintf(stderr, "vehicle steps vs run%s: worst |difference| / range %.3g (%s)\n",
          with_events ? " (tires leaving the ground)" : "", worst, worst_name);
  CHECK(worst <= 1e-5);
  free(y);
done:
  fb_vehicle_stepper_free(&st);
  fb_result_free(&res);
}

/* The sum of the tires' reactions (N). */
static double total_reaction(fb_vehicle_stepper *st, const fb_scenario *s, fb_err *err)
{
  double *y = calloc(fb_vehicle_stepper_noutputs(st) + 1, sizeof *y), sum = 0;
  if (!y || fb_vehicle_stepper_outputs(st, y, err) != FB_OK) {
    free(y);
    return NAN;
  }
  for (size_t c = 0; c < s->ncorners; ++c) {
    char name[64];
    snprintf(name, sizeof name, "contact_force_%s", s->corner[c].name);
    const long k = fb_vehicle_stepper_output_find(st, name);
    sum += k >= 0 ? y[k] : NAN;
  }
  free(y);
  return sum;
}

/* From the static equilibrium, the bump far away: a load force of 20 kN
 * up from t = 0.5 s, then a load 30 kN heavier from t = 4 s (a new
 * scenario, the state carried over). Once the vehicle has settled the
 * tires carry the weight less the force, then 30 kN more: at rest the
 * forces on the vehicle balance, whatever its springs. */
static void test_inputs_and_parameters(const fb_scenario *s0)
{
  fb_err err;
  fb_scenario *s = NULL, *heavier = NULL;
  MUST(fb_scenario_clone(s0, &s, &err), &err);
  MUST(fb_scenario_clone(s0, &heavier, &err), &err);
  if (!s || !heavier)
    goto done;
  /* The wheels meet the bump after 7.6 s: after the checks. */
  fit_bump(s, 20.0, 7.6);
  fit_bump(heavier, 20.0, 7.6);
  s->initial = heavier->initial = FB_INITIAL_STATIC;
  heavier->total_weight += 30e3;
  fb_vehicle_stepper *st = NULL;
  MUST(fb_vehicle_stepper_new(s, FB_SYSTEM_RIGID, NULL, &st, &err), &err);
  if (!st)
    goto done;
  const double n0 = total_reaction(st, s, &err);
  CHECK(fb_vehicle_input_find("load_force") == 0 && fb_vehicle_input_name(0) &&
        !fb_vehicle_input_name(1));
  CHECK(fb_vehicle_stepper_input(st, 0) == 0.0);
  MUST(fb_vehicle_stepper_advance(st, 0.5, &err), &err);
  MUST(fb_vehicle_stepper_set_input(st, "load_force", 20e3, &err), &err);
  CHECK(fb_vehicle_stepper_input(st, 0) == 20e3);
  MUST(fb_vehicle_stepper_advance(st, 4.0, &err), &err);
  const double n1 = total_reaction(st, s, &err);
  MUST(fb_vehicle_stepper_set_scenario(st, heavier, &err), &err);
  CHECK(fb_vehicle_stepper_time(st) == 4.0);
  CHECK(fb_vehicle_stepper_scenario(st) != heavier &&
        fb_vehicle_stepper_scenario(st)->total_weight == heavier->total_weight);
  MUST(fb_vehicle_stepper_advance(st, 7.5, &err), &err);
  const double n2 = total_reaction(st, s, &err);
  /* 3.5 s of settling: the slowest mode (the hull's heave and pitch
   * near 1.5 Hz, damping ratio about 0.3) decays as exp(-0.3 2 pi 1.5
   * 3.5) = 5e-5 of the 20 and 30 kN steps (1 N; measured 0.002 N); the
   * bound is 10 N, 5e-4 of the change. Without the force the reactions would not move;
   * a force applied at a load point twice, or the weight's share lost,
   * moves them by kilonewtons. */
  fprintf(stderr, "load force: reactions %.3f N -> %.3f N (-20 kN) -> %.3f N (+30 kN)\n", n0,
          n1, n2);
  CHECK(fabs(n1 - (n0 - 20e3)) <= 10.0);
  CHECK(fabs(n2 - (n1 + 30e3)) <= 10.0);
  CHECK(fb_vehicle_stepper_set_input(st, "road_height", 1.0, &err) == FB_EINVAL &&
        !strcmp(err.key, "road_height"));
  CHECK(fb_vehicle_stepper_set_input(st, "load_force", NAN, &err) == FB_EINVAL);
  fb_vehicle_stepper_free(&st);
done:
  fb_scenario_free(&heavier);
  fb_scenario_free(&s);
}

/* A scenario with another vehicle (four corners, not six) cannot go on
 * from this one's state; the stepper is left as it was. */
static void test_other_states_refused(const fb_scenario *s0)
{
  fb_err err;
  fb_scenario *truck = NULL;
  fb_vehicle_stepper *st = NULL;
  MUST(fb_scenario_load("../examples/truck4x4.yaml", &truck, &err), &err);
  MUST(fb_vehicle_stepper_new(s0, FB_SYSTEM_RIGID, NULL, &st, &err), &err);
  if (truck && st) {
    MUST(fb_vehicle_stepper_advance(st, 0.2, &err), &err);
    CHECK(fb_vehicle_stepper_set_scenario(st, truck, &err) == FB_EINVAL);
    CHECK(strstr(err.msg, "states") != NULL);
    CHECK(fb_vehicle_stepper_scenario(st)->ncorners == s0->ncorners);
    MUST(fb_vehicle_stepper_advance(st, 0.3, &err), &err);
  }
  fb_vehicle_stepper_free(&st);
  fb_scenario_free(&truck);
}

/* System 1 of examples/apc6x6.yaml over the bump, and of
 * examples/apc6x6_liftoff.yaml, whose unilateral tires leave the
 * ground. */
static void test_steps_equal_run(const fb_scenario *apc)
{
  fb_err err;
  fb_scenario *s = NULL, *liftoff = NULL;
  MUST(fb_scenario_clone(apc, &s, &err), &err);
  if (s) {
    fit_bump(s, 10.0, 0.5);
    check_steps_equal_run(s, 0);
  }
  MUST(fb_scenario_load("../examples/apc6x6_liftoff.yaml", &liftoff, &err), &err);
  if (liftoff)
    check_steps_equal_run(liftoff, 1);
}

/* The reaction of corner c (N) now. */
static double reaction(fb_vehicle_stepper *st, const fb_scenario *s, size_t c, fb_err *err)
{
  char name[64];
  snprintf(name, sizeof name, "contact_force_%s", s->corner[c].name);
  const long k = fb_vehicle_stepper_output_find(st, name);
  double *y = calloc(fb_vehicle_stepper_noutputs(st) + 1, sizeof *y);
  const double f = y && k >= 0 && fb_vehicle_stepper_outputs(st, y, err) == FB_OK ? y[k] : NAN;
  free(y);
  return f;
}

/* Road inputs on the flat APC (the bump far beyond the run). */
static void test_road_inputs(const fb_scenario *apc)
{
  fb_err err;
  fb_scenario *s = NULL;
  fb_vehicle_stepper *st = NULL;
  fb_vehicle_opts o;
  fb_vehicle_opts_default(&o);
  o.road_inputs = 1;
  MUST(fb_scenario_clone(apc, &s, &err), &err);
  if (s) {
    s->t_end = 6.0;
    MUST(fb_vehicle_stepper_new(s, FB_SYSTEM_RIGID, &o, &st, &err), &err);
  }
  if (!st) {
    fb_scenario_free(&s);
    return;
  }
  const size_t ni = fb_vehicle_stepper_ninputs(st), nc = s->ncorners;
  CHECK(ni == FB_VEHICLE_NINPUTS + 2 * nc);
  char name[64];
  snprintf(name, sizeof name, "road_zdot_%s", s->corner[nc - 1].name);
  CHECK(fb_vehicle_stepper_input_find(st, name) == (long)ni - 1);
  CHECK(!strcmp(fb_vehicle_stepper_input_unit(st, ni - 1), "m/s"));
  CHECK(!strcmp(fb_vehicle_stepper_input_unit(st, ni - 2), "m"));
  CHECK(fb_vehicle_stepper_road_coupling(st) != NULL);
  double *u = calloc(ni, sizeof *u);
  /* A 10 mm step under the first wheel at t = 0.1 s: its tire is 10 mm
   * more compressed at once, the rest not yet moved (the step is taken
   * in the same instant), so its reaction rises by tire_k * 0.01 and no
   * other changes. Round-off of the reaction's sum only: 1e-9 of it. */
  MUST(fb_vehicle_stepper_advance(st, 0.1, &err), &err);
  const double before = reaction(st, s, 0, &err), other = reaction(st, s, 1, &err);
  u[FB_VEHICLE_NINPUTS] = 0.01;
  MUST(fb_vehicle_stepper_set_inputs(st, u, &err), &err);
  const double jump = reaction(st, s, 0, &err) - before;
  fprintf(stderr, "road step 10 mm under %s: reaction +%.6g N, tire_k * 0.01 = %.6g N\n",
          s->corner[0].name, jump, s->corner[0].tire_k * 0.01);
  CHECK(fabs(jump - s->corner[0].tire_k * 0.01) <= 1e-9 * fabs(before) + 1e-9);
  CHECK(fabs(reaction(st, s, 1, &err) - other) <= 1e-9 * fabs(other));
  /* Every wheel's road up to 10 mm, ramped over 0.5 s as height and rate
   * together, then held: settled, the vehicle has ridden up with it and
   * the reactions are those of the vehicle settled on its unmoved road.
   * What is left is the ramp's transient, 4.4 s after it: measured
   * 1.4e-10 of a wheel's load. 1e-6 keeps a wide margin; a coupling of
   * the wrong sign or size leaves the tires 10 mm off their deflection,
   * k_t * 0.01 = 5 kN, a fifth of a wheel's load. */
  for (int i = 1; i <= 500; ++i) {
    const double t = 0.1 + 1e-3 * i;
    for (size_t c = 0; c < nc; ++c) {
      u[FB_VEHICLE_NINPUTS + 2 * c] = 0.01 * (double)i / 500.0;
      u[FB_VEHICLE_NINPUTS + 2 * c + 1] = i < 500 ? 0.01 / 0.5 : 0.0;
    }
    /* The first wheel's road is already at 10 mm: it stays there. */
    u[FB_VEHICLE_NINPUTS] = 0.01;
    u[FB_VEHICLE_NINPUTS + 1] = 0.0;
    MUST(fb_vehicle_stepper_set_inputs(st, u, &err), &err);
    MUST(fb_vehicle_stepper_advance(st, t, &err), &err);
  }
  MUST(fb_vehicle_stepper_advance(st, 5.0, &err), &err);
  /* The same vehicle on its unmoved road, settled as long. */
  fb_vehicle_stepper *still = NULL;
  MUST(fb_vehicle_stepper_new(s, FB_SYSTEM_RIGID, &o, &still, &err), &err);
  if (still)
    MUST(fb_vehicle_stepper_advance(still, 5.0, &err), &err);
  double worst = still ? 0 : INFINITY;
  for (size_t c = 0; still && c < nc; ++c) {
    const double ref = reaction(still, s, c, &err);
    worst = fmax(worst, fabs(reaction(st, s, c, &err) - ref) / fabs(ref));
  }
  fb_vehicle_stepper_free(&still);
  fprintf(
      stderr,
      "road raised 10 mm, settled: reactions vs the unmoved road's, worst %.3g of the load\n",
      worst);
  CHECK(worst <= 1e-6);
  free(u);
  fb_vehicle_stepper_free(&st);
  fb_scenario_free(&s);
}

/* A state set back: from (t1, x1) the stepper goes on as it did from
 * there after the same restart, to the bit (the same integrator from the
 * same start). */
static void test_state_set_back(const fb_scenario *apc)
{
  fb_err err;
  fb_scenario *s = NULL;
  fb_vehicle_stepper *st = NULL;
  MUST(fb_scenario_clone(apc, &s, &err), &err);
  if (s) {
    fit_bump(s, 10.0, 0.3);
    MUST(fb_vehicle_stepper_new(s, FB_SYSTEM_RIGID, NULL, &st, &err), &err);
  }
  if (!st) {
    fb_scenario_free(&s);
    return;
  }
  const size_t n = fb_vehicle_stepper_nstates(st), ny = fb_vehicle_stepper_noutputs(st);
  double *x1 = calloc(n, sizeof *x1), *ya = calloc(ny, sizeof *ya),
         *yb = calloc(ny, sizeof *yb);
  MUST(fb_vehicle_stepper_advance(st, 0.5, &err), &err);
  /* The restart at t1 that a taken state implies, then the first way on. */
  MUST(fb_vehicle_stepper_set_state(st, 0.5, fb_vehicle_stepper_state(st), &err), &err);
  memcpy(x1, fb_vehicle_stepper_state(st), n * sizeof *x1);
  MUST(fb_vehicle_stepper_advance(st, 1.0, &err), &err);
  MUST(fb_vehicle_stepper_outputs(st, ya, &err), &err);
  MUST(fb_vehicle_stepper_set_state(st, 0.5, x1, &err), &err);
  CHECK(fb_vehicle_stepper_time(st) == 0.5);
  MUST(fb_vehicle_stepper_advance(st, 1.0, &err), &err);
  MUST(fb_vehicle_stepper_outputs(st, yb, &err), &err);
  CHECK(memcmp(ya, yb, ny * sizeof *ya) == 0);
  /* Refused: a time outside the run, a state that is not finite. */
  CHECK(fb_vehicle_stepper_set_state(st, -1.0, x1, &err) == FB_EINVAL);
  CHECK(fb_vehicle_stepper_set_state(st, s->t_end + 1.0, x1, &err) == FB_EINVAL);
  x1[0] = NAN;
  CHECK(fb_vehicle_stepper_set_state(st, 0.5, x1, &err) == FB_EINVAL);
  free(x1);
  free(ya);
  free(yb);
  fb_vehicle_stepper_free(&st);
  fb_scenario_free(&s);
}

int main(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  MUST(fb_scenario_load(apc_path, &s, &err), &err);
  if (s) {
    test_steps_equal_run(s);
    test_inputs_and_parameters(s);
    test_other_states_refused(s);
    test_road_inputs(s);
    test_state_set_back(s);
  }
  fb_scenario_free(&s);
  return check_report("test_vehicle_stepper");
}
