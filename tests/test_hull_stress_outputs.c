/* SPDX-License-Identifier: BSD-3-Clause */
/* Outputs read from the stresses of System 2's shell elements
 * (docs/stresses.md, "Stress outputs"): the columns of a run against the
 * element stress recovery applied to the run's own motion, in nodal and
 * in modal coordinates, and the von Mises and principal stresses formed
 * from three of them; the two coordinates against each other, within
 * the modal basis's estimated error; each stress output one more pattern
 * of the basis; and the refusals about the output's keys (an element the
 * mesh has not, a point off the plates, System 1, a vehicle without a
 * finite-element hull). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle_util.h"

/* The elements the outputs read: the one whose centre is nearest the
 * driver's floor point (under its mount: large stresses), and one of the
 * roof's. */
typedef struct picked {
  size_t floor, other;
  double floor_centre[3];
} picked;

static size_t nearest_centre(const fb_mesh *m, const double *p)
{
  size_t best = 0;
  double dbest = INFINITY;
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    double c[3];
    fb_mesh_element_centroid(m, e, c);
    const double d = hypot(hypot(c[0] - p[0], c[1] - p[1]), c[2] - p[2]);
    if (d < dbest) {
      dbest = d;
      best = e;
    }
  }
  return best;
}

static picked pick(const fb_scenario *s)
{
  const fb_mesh *m = s->hull_source_mesh;
  const double floor_point[3] = {2.10, 0.55, -0.86306}, roof_point[3] = {-1.0, -0.3, 0.9};
  picked p = {0, 0, {0, 0, 0}};
  CHECK(m != NULL);
  if (!m)
    exit(check_report("test_hull_stress_outputs"));
  p.floor = nearest_centre(m, floor_point);
  p.other = nearest_centre(m, roof_point);
  fb_mesh_element_centroid(m, p.floor, p.floor_centre);
  return p;
}

static void add_stress(fb_scenario *s, const char *name, long element, const double *at,
                       int surface, fb_output_stress stress)
{
  fb_err err;
  fb_output_spec o = {.signal = "hull_stress",
                      .name = (char *)name,
                      .element = element,
                      .surface = surface,
                      .stress = stress};
  if (at)
    memcpy(o.at, at, sizeof o.at);
  REQUIRE(fb_scenario_add_output(s, &o, &err), &err);
}

/* The outputs: (element, surface, component) of each, in the order
 * add_outputs adds them. */
typedef struct stress_column {
  const char *name;
  int use_floor;
  int surface;
  fb_output_stress stress;
} stress_column;

static const stress_column columns[] = {
    {"floor_sx_top", 1, FB_STRESS_TOP, FB_STRESS_SX},
    {"floor_sy_top", 1, FB_STRESS_TOP, FB_STRESS_SY},
    {"floor_sxy_top", 1, FB_STRESS_TOP, FB_STRESS_SXY},
    {"floor_sy_bottom", 1, FB_STRESS_BOTTOM, FB_STRESS_SY},
    {"roof_sx_bottom", 0, FB_STRESS_BOTTOM, FB_STRESS_SX},
};
enum { NCOLUMNS = sizeof columns / sizeof columns[0] };

/* The floor element by its point (its centre: inside it, 0 m from it and
 * off every other element's surface), the roof's by its id. */
static void add_outputs(fb_scenario *s, const picked *p)
{
  const fb_mesh *m = s->hull_source_mesh;
  for (size_t k = 0; k < NCOLUMNS; ++k)
    add_stress(s, columns[k].name, columns[k].use_floor ? 0 : fb_mesh_element_id(m, p->other),
               columns[k].use_floor ? p->floor_centre : NULL, columns[k].surface,
               columns[k].stress);
}

/* The shortened crossing with the stress outputs, System 2's hull in
 * coordinates coords (hull.fe.coordinates). */
static fb_scenario *load_with(const char *coords, picked *p)
{
  fb_err err;
  fb_scenario *s = NULL;
  const fb_scenario_override ov = {.key = "hull.fe.coordinates", .value = coords};
  REQUIRE(fb_scenario_load_overrides("../examples/apc6x6.yaml", &ov, 1, &s, &err), &err);
  road_bump(s)->first_contact = 1.0;
  road_bump(s)->length = 0.5;
  s->t_end = 3.0;
  *p = pick(s);
  add_outputs(s, p);
  return s;
}

/* The von Mises and principal stresses formed from the floor element's
 * three top columns (plane stress: sqrt(sx^2 - sx sy + sy^2 + 3 txy^2);
 * (sx + sy) / 2 +- sqrt(((sx - sy) / 2)^2 + txy^2), docs/stresses.md)
 * against the recovery's of the run's motion: the columns equal its
 * components to rounding, and so do these (1e-9 of the peak, as the
 * columns). u and st are scratch for the mesh's DOFs and elements. */
static void check_von_mises(const fb_result *r, const fb_vehicle_motion *motion,
                            const fb_shell_stress *recovery, size_t e, double *u,
                            fb_shell_stress_state *st)
{
  fb_err err;
  const long sx = fb_result_find(r, "floor_sx_top"), sy = fb_result_find(r, "floor_sy_top"),
             txy = fb_result_find(r, "floor_sxy_top");
  CHECK(sx > 0 && sy > 0 && txy > 0);
  if (sx <= 0 || sy <= 0 || txy <= 0 || !u || !st)
    return;
  double peak = 0.0, worst = 0.0;
  for (size_t i = 0; i < motion->nsamples; i += 25) {
    const double *row = fb_result_row(r, i);
    const double a = row[sx], b = row[sy], c = row[txy];
    const double vm = sqrt(a * a - a * b + b * b + 3.0 * c * c);
    const double mid = 0.5 * (a + b), radius = hypot(0.5 * (a - b), c);
    REQUIRE(fb_vehicle_motion_at(motion, motion->mesh, row[0], u, NULL, NULL, NULL, &err),
            &err);
    fb_shell_stress_eval_nodal(recovery, u, st);
    peak = fmax(peak, st[e].von_mises_top);
    worst = fmax(worst, fabs(vm - st[e].von_mises_top));
    worst = fmax(worst, fabs(mid + radius - st[e].principal_top[0]));
    worst = fmax(worst, fabs(mid - radius - st[e].principal_top[1]));
  }
  printf("floor von Mises (top): peak %.4g Pa; from the columns - recovered %.3g of it\n", peak,
         worst / peak);
  CHECK(peak > 1e4 && worst <= 1e-9 * peak);
}

/* The run's column of each stress output against the recovery of the
 * element (fb_shell_stress_eval_nodal) from the run's own nodal
 * displacements (fb_vehicle_motion_at: the hull's coordinates from t = 0,
 * the state itself from the scenario's zero initial state; u = T q in
 * modal coordinates). The column is w' q with w = T' D_e's row, the
 * recovery D_e (T q): the same sums in another order, equal to rounding
 * of the sums of a few thousand terms (1e-9 of the column's largest value
 * leaves a margin of 1e3 over the 1e-12 measured). Returns the result
 * (new). */
static fb_result *check_against_recovery(const char *coords)
{
  fb_err err;
  picked p;
  fb_scenario *s = load_with(coords, &p);
  fb_vehicle_opts opts;
  fb_vehicle_opts_default(&opts);
  opts.motion = 1;
  fb_vehicle *v = NULL;
  REQUIRE(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, &opts, &v, &err), &err);
  fb_result *r = NULL;
  fb_vehicle_motion *motion = NULL;
  REQUIRE(fb_vehicle_run(v, NULL, NULL, NULL, &r, &motion, &err), &err);
  const fb_fe_hull *fe = fb_vehicle_fe_hull_of(v);
  fb_shell_stress *recovery = NULL;
  REQUIRE(fb_shell_stress_new(motion->mesh, &fe->props, &recovery, &err), &err);
  const size_t nel = fb_mesh_nelements(motion->mesh);
  double *u = malloc(6 * fb_mesh_nnodes(motion->mesh) * sizeof *u);
  fb_shell_stress_state *st = malloc(nel * sizeof *st);
  CHECK(u && st);
  for (size_t k = 0; k < NCOLUMNS; ++k) {
    const long col = fb_result_find(r, columns[k].name);
    CHECK(col > 0 && !strcmp(fb_result_col_unit(r, (size_t)col), "Pa"));
    if (col <= 0 || !u || !st)
      continue;
    double peak = 0.0, worst = 0.0;
    for (size_t i = 0; i < fb_result_nsamples(r); ++i)
      peak = fmax(peak, fabs(fb_result_row(r, i)[col]));
    const size_t e = columns[k].use_floor ? p.floor : p.other;
    for (size_t i = 0; i < motion->nsamples; i += 25) {
      const double t = motion->samples[i * motion->width];
      REQUIRE(fb_vehicle_motion_at(motion, motion->mesh, t, u, NULL, NULL, NULL, &err), &err);
      fb_shell_stress_eval_nodal(recovery, u, st);
      const double *surface = columns[k].surface == FB_STRESS_TOP ? st[e].top : st[e].bottom;
      worst = fmax(worst, fabs(fb_result_row(r, i)[col] - surface[columns[k].stress]));
    }
    printf("%s %s: peak %.4g Pa, column - recovery of the motion %.3g of it\n", coords,
           columns[k].name, peak, worst / peak);
    CHECK(peak > 1e4);
    CHECK(worst <= 1e-9 * peak);
  }
  check_von_mises(r, motion, recovery, p.floor, u, st);
  free(u);
  free(st);
  fb_shell_stress_free(&recovery);
  fb_vehicle_motion_free(&motion);
  fb_vehicle_free(&v);
  fb_scenario_free(&s);
  return r;
}

/* The modal runs against the nodal reference. With every mode the two
 * are one model: equal within the integrators' tolerances, 1e-4 of the
 * range (as test_hull_outputs' accelerations). With the default basis
 * (rigid-body modes and load-dependent Ritz vectors of the patterns, each
 * stress output's row among them) the difference is the basis's
 * truncation, which its estimator (the run again with the next block of
 * Ritz vectors, fb_vehicle_basis_error) measures: the two within a factor
 * 1.5 of each other (0.99 to 1.10 measured; the run from t = 0, where
 * gravity switched on excites the hull's fast modes, which the stresses
 * see most: 3 to 9 % of the range). */
static void check_modal_nodal(const fb_result *nodal, const fb_result *modal)
{
  fb_err err;
  picked p;
  fb_scenario *s = load_with("modal", &p), *every = NULL;
  fb_vehicle *v = NULL;
  REQUIRE(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, NULL, &v, &err), &err);
  double est[16];
  const double window[2] = {0.0, s->t_end};
  CHECK(s->noutputs <= 16);
  REQUIRE(fb_vehicle_basis_error(v, modal, window, NULL, NULL, est, &err), &err);
  REQUIRE(fb_scenario_clone(s, &every, &err), &err);
  every->hull_modes_kind = FB_HULL_MODES_ALL;
  fb_result *all = NULL;
  REQUIRE(fb_vehicle_simulate(every, FB_SYSTEM_FLEXIBLE, &all, &err), &err);
  for (size_t k = 0; k < NCOLUMNS; ++k) {
    const double d = result_relative_difference(nodal, modal, columns[k].name);
    const double d_all = result_relative_difference(nodal, all, columns[k].name);
    const long o = fb_result_find(modal, columns[k].name) - 1;
    const double e = o >= 0 && (size_t)o < 16 ? est[o] : NAN;
    printf("%s: modal - nodal %.3g of the range (every mode: %.3g); the basis's estimated "
           "error %.3g\n",
           columns[k].name, d, d_all, e);
    CHECK(d_all < 1e-4);
    CHECK(d < 1.5 * e && e < 1.5 * d);
  }
  fb_result_free(&all);
  fb_vehicle_free(&v);
  fb_scenario_free(&every);
  fb_scenario_free(&s);
}

/* Each stress output is one more pattern of the basis: npatterns grows
 * by the number of stress outputs. */
static void check_patterns(void)
{
  fb_err err;
  picked p;
  fb_scenario *s = load_with("modal", &p), *plain = NULL;
  const fb_scenario_override ov = {.key = "hull.fe.coordinates", .value = "modal"};
  REQUIRE(fb_scenario_load_overrides("../examples/apc6x6.yaml", &ov, 1, &plain, &err), &err);
  fb_vehicle *v = NULL, *w = NULL;
  REQUIRE(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, NULL, &v, &err), &err);
  REQUIRE(fb_vehicle_new(plain, FB_SYSTEM_FLEXIBLE, NULL, &w, &err), &err);
  const fb_hull_basis *a = fb_vehicle_hull_basis(v), *b = fb_vehicle_hull_basis(w);
  CHECK(a && b && a->npatterns == b->npatterns + NCOLUMNS);
  fb_vehicle_free(&v);
  fb_vehicle_free(&w);
  fb_scenario_free(&s);
  fb_scenario_free(&plain);
}

/* Refusals about the output's keys (fb_err.part: the output and its
 * member): an element id the mesh has not (at `element`), a point 0.3 m
 * off the plates (at `at`, naming the distance), System 1 (at `signal`),
 * and a vehicle without a finite-element hull (at `signal`). */
static void check_refusals(void)
{
  fb_err err;
  picked p;
  fb_scenario *s = load_with("modal", &p);
  const size_t last = s->noutputs;
  add_stress(s, "nowhere", 99999999, NULL, FB_STRESS_TOP, FB_STRESS_SX);
  CHECK(fb_vehicle_outputs_check(s, &err) == FB_EINVAL);
  CHECK(err.part.kind == FB_PART_OUTPUT && err.part.index == last &&
        !strcmp(err.part.field, "element"));
  CHECK(strstr(err.msg, "no element 99999999") != NULL);
  fb_scenario_free(&s);

  s = load_with("modal", &p);
  const double off[3] = {p.floor_centre[0], p.floor_centre[1], p.floor_centre[2] - 0.3};
  add_stress(s, "off", 0, off, FB_STRESS_TOP, FB_STRESS_SX);
  CHECK(fb_vehicle_outputs_check(s, &err) == FB_EINVAL);
  CHECK(err.part.kind == FB_PART_OUTPUT && err.part.index == last &&
        !strcmp(err.part.field, "at"));
  CHECK(strstr(err.msg, "0.3 m from the hull's nearest element") != NULL);
  fb_scenario_free(&s);

  s = load_with("modal", &p);
  const size_t first = s->noutputs - NCOLUMNS;
  fb_result *r = NULL;
  CHECK(fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err) == FB_EINVAL && !r);
  CHECK(err.part.kind == FB_PART_OUTPUT && err.part.index == first &&
        !strcmp(err.part.field, "signal"));
  CHECK(strstr(err.msg, "no shell elements") != NULL);
  s->has_fe_hull = 0;
  CHECK(fb_vehicle_outputs_check(s, &err) == FB_EINVAL);
  CHECK(err.part.kind == FB_PART_OUTPUT && err.part.index == first &&
        !strcmp(err.part.field, "signal"));
  CHECK(strstr(err.msg, "has no mesh") != NULL);
  fb_scenario_free(&s);
}

/* examples/apc6x6_stresses.yaml (shortened crossing) runs System 2, its
 * floor columns those of element 48, as its comment says: the same column
 * given by the element's id is equal, bit for bit (the same weights). */
static void check_example(void)
{
  fb_err err;
  fb_scenario *s = load_short_from("../examples/apc6x6_stresses.yaml");
  add_stress(s, "element_48", 48, NULL, FB_STRESS_TOP, FB_STRESS_SX);
  fb_result *r = NULL;
  REQUIRE(fb_vehicle_simulate(s, FB_SYSTEM_FLEXIBLE, &r, &err), &err);
  const long a = fb_result_find(r, "floor_sx"), b = fb_result_find(r, "element_48");
  CHECK(a > 0 && b > 0 && result_range(r, (size_t)a) > 1e6);
  for (size_t k = 0; a > 0 && b > 0 && k < fb_result_nsamples(r); ++k)
    CHECK(fb_result_row(r, k)[a] == fb_result_row(r, k)[b]);
  fb_result_free(&r);
  fb_scenario_free(&s);
}

int main(void)
{
  fb_result *nodal = check_against_recovery("nodal");
  fb_result *modal = check_against_recovery("modal");
  if (nodal && modal)
    check_modal_nodal(nodal, modal);
  check_patterns();
  check_refusals();
  check_example();
  fb_result_free(&nodal);
  fb_result_free(&modal);
  return check_report("test_hull_stress_outputs");
}
