/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of the vehicle scenario loader (fb_scenario_* in
 * flexbond/vehicle.h): examples/apc6x6.yaml against every number of the
 * data sheet (docs/reference-vehicle.md), the bump timing against
 * hand calculation, deep copies, fb_scenario_check on hand-built
 * scenarios, a table of bad scenarios with the status, the
 * "bad.yaml:LINE:COL:" and the key path each must report, and the
 * values' origins and visit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/io.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "damper_util.h"
#include "io/scenario_internal.h"
#include "road_util.h"
#include "tmpdir.h"

#define EXAMPLE "../examples/apc6x6.yaml"

/* Values typed from the data sheet are compared exactly as decimals read
 * by strtod: the loader must not change them. Derived values (km/h to
 * m/s, degrees to radians, time sums) round once or twice: 1e-12
 * relative is far above that and far below any data error. */
#define TIGHT 1e-12

/* ---- The example against the data sheet. */

static void check_hull(const fb_scenario *s)
{
  CHECK(s->name && !strcmp(s->name, "apc6x6"));
  CHECK(s->path && !strcmp(s->path, EXAMPLE));
  CHECK(s->gravity == 9.81);
  CHECK(s->hull_mass == 4041.72);
  CHECK(s->hull_ixx == 4173.49);
  CHECK(s->hull_iyy == 15175.96);
  CHECK(s->young == 200e9);
  CHECK(s->poisson == 0.3);
  CHECK(s->density == 7860);
  CHECK(s->thickness == 0.0085);
  /* The torsion edges and System 2's hull: docs/hull-mesh.md. */
  CHECK(s->edge_front_x == 2.47813311938948 && s->edge_rear_x == -2.65798412344113);
  CHECK(s->edge_left_y == 1.05 && s->edge_right_y == -1.05);
  CHECK(s->has_fe_hull && s->hull_deck == NULL && s->hull_mesh.density == 1);
  CHECK(s->hull_mesh.width == 2.10 && s->hull_mesh.height == 1.74083494988748);
  CHECK(s->hull_mesh.nbulkheads == 3 && s->hull_mesh.bulkhead_x[1] == -1.00);
  CHECK(s->hull_mesh.side_rows == 2 && s->hull_mesh.nose_rows == 3 &&
        s->hull_mesh.nose_rung_divisions == 3);
  CHECK(s->hull_mass_matrix == FB_MASS_CONSISTENT && s->hull_drill_factor == 1.0e-4 &&
        s->hull_damping_ratio == 0.02);
}

/* 56 points on the assumed 14 x 4 grid of System 2's hull floor lines
 * (examples/apc6x6.yaml, docs/hull-mesh.md), x-major, centroid at the
 * origin, 117720 / 56 = 2102.142857 N each. */
static void check_load(const fb_scenario *s)
{
  static const double grid_x[14] = {-2.00, -1.70, -1.35, -1.00, -0.75, -0.45, -0.15,
                                    0.10,  0.40,  0.65,  0.95,  1.30,  1.90,  2.10};
  static const double grid_y[4] = {-1.05, -0.55, 0.55, 1.05};
  CHECK(s->total_weight == 117720);
  CHECK(s->payload == FB_PAYLOAD_WEIGHT_ONLY);
  CHECK(s->nload == 56);
  if (s->nload != 56)
    return;
  double sx = 0, sy = 0;
  for (size_t i = 0; i < 14; ++i)
    for (size_t j = 0; j < 4; ++j) {
      /* The loader keeps strtod's value of the literal: exact. */
      CHECK(s->load_x[i * 4 + j] == grid_x[i]);
      CHECK(s->load_y[i * 4 + j] == grid_y[j]);
      sx += s->load_x[i * 4 + j];
      sy += s->load_y[i * 4 + j];
    }
  /* The values sum to zero in decimal; the binary sums cancel up to the
   * rounding of 56 additions of numbers below 2.1. */
  CHECK_NEAR(sx / 56, 0, TIGHT);
  CHECK_NEAR(sy / 56, 0, TIGHT);
  /* The data sheet quotes the share to 6 decimals. */
  CHECK_NEAR(s->total_weight / (double)s->nload, 2102.142857, 5e-7);
}

static void check_mounts(const fb_scenario *s)
{
  CHECK(s->nmounts == 2);
  if (s->nmounts != 2)
    return;
  const fb_mount *driver = &s->mount[0], *engine = &s->mount[1];
  CHECK(!strcmp(driver->name, "driver") && !strcmp(engine->name, "engine"));
  CHECK(driver->mass == 100 && driver->stiffness == 19620 && driver->damping == 1400);
  CHECK(driver->x == 2.10 && driver->y == 0.55);
  CHECK(engine->mass == 500 && engine->stiffness == 122625 && engine->damping == 24761);
  CHECK(engine->x == 1.70 && engine->y == -0.55);
  CHECK(fb_scenario_mount_find(s, "engine") == 1 && fb_scenario_mount_find(s, "cargo") == -1);
  CHECK(fb_scenario_nattach(s) == 8);
}

/* Data sheet, Table 4 and the attachment points. */
static void check_corners(const fb_scenario *s)
{
  static const double spring_k[] = {145300, 145300, 345550, 345550, 602100, 602100};
  static const double damper_c[] = {25744, 25744, 25744, 25744, 39656, 39656};
  static const double x[] = {1.90, 1.90, 0.40, 0.40, -1.00, -1.00};
  static const double y[] = {1.05, -1.05, 1.05, -1.05, 1.05, -1.05};
  static const char *const names[] = {"LF", "RF", "LM", "RM", "LR", "RR"};
  CHECK(s->ncorners == 6);
  for (size_t k = 0; k < 6 && k < s->ncorners; ++k) {
    const fb_corner_params *c = &s->corner[k];
    CHECK(!strcmp(c->name, names[k]) && fb_scenario_corner_find(s, names[k]) == (long)k);
    CHECK(c->spring_k == spring_k[k] && du_damper_c(c) == damper_c[k]);
    CHECK(c->x == x[k] && c->y == y[k]);
    CHECK(c->motion_ratio == 1);
    CHECK(c->wheel_mass == 175 && c->tire_k == 500000 && c->tire_c == 140000);
    CHECK(fb_corner_tire_model(c) ==
          &fb_tire_model_bilateral); /* the paper's linear tire by default */
  }
  CHECK(fb_scenario_corner_find(s, "LX") == -1);
}

/* The paper's seven outputs, Figs. 8 to 14, their defaults from the
 * signal kinds where the file gives none. */
static void check_outputs(const fb_scenario *s)
{
  static const char *const names[] = {"tire_force_LF", "spring_defl_RF", "torsion",
                                      "driver_acc",    "shock_power_LM", "tire_defl_RM",
                                      "tire_power_LR"};
  CHECK(s->noutputs == 7);
  for (size_t i = 0; i < 7 && i < s->noutputs; ++i) {
    const fb_output_spec *o = &s->output[i];
    CHECK(o->name && !strcmp(o->name, names[i]));
    CHECK(o->figure == (int)(8 + i) && o->title && o->label && o->unit);
  }
  if (s->noutputs != 7)
    return;
  CHECK(!strcmp(s->output[0].unit, "N") && !strcmp(s->output[3].unit, "m/s^2"));
  CHECK(s->output[2].of == NULL && !strcmp(s->output[3].of, "driver"));
  CHECK(!strcmp(s->output[0].label, "LF tire normal reaction"));
  CHECK(s->output[4].window[0] == 4 && s->output[4].window[1] == 10);
  CHECK(s->output[0].window[0] == 0 && s->output[0].window[1] == 0);
}

static void check_road_and_run(const fb_scenario *s)
{
  CHECK_NEAR(s->speed, 10 / 3.6, TIGHT);
  CHECK(road_bump(s)->height == 0.10 && road_bump(s)->length == 3.70 &&
        road_bump(s)->first_contact == 5.0);
  CHECK_NEAR(road_bump(s)->angle, 0.7853981633974483, TIGHT); /* pi / 4 */
  CHECK(s->t_end == 15 && s->rtol == 1e-6 && s->atol == 1e-8);
  CHECK(s->max_step == 0 && s->sample_rate == 1000);
  CHECK(s->initial == FB_INITIAL_ZERO);
}

/* With V = 10 km/h = 25/9 m/s, a distance d takes 0.36 d seconds and
 * tan 45 deg = 1, so by hand (x_LF, y_LF) = (1.90, 1.05):
 *   LF 5 + 0.36 (0   + 0  ) = 5
 *   RF 5 + 0.36 (0   + 2.1) = 5.756
 *   LM 5 + 0.36 (1.5 + 0  ) = 5.54
 *   RM 5 + 0.36 (1.5 + 2.1) = 6.296
 *   LR 5 + 0.36 (2.9 + 0  ) = 6.044
 *   RR 5 + 0.36 (2.9 + 2.1) = 6.8
 * and each leaves 0.36 * 3.7 = 1.332 s later: RR at 8.132 s, "about
 * 8.13 s" in the data sheet. */
static void check_bump_timing(const fb_scenario *s)
{
  static const double entry[] = {5, 5.756, 5.54, 6.296, 6.044, 6.8};
  for (int k = 0; k < 6; ++k) {
    CHECK_NEAR(fb_scenario_road_entry(s, k), entry[k], TIGHT);
    CHECK_NEAR(fb_scenario_road_exit(s, k), entry[k] + 1.332, TIGHT);
  }
  double rr_exit = 5 + 0.36 * (2.9 + 2.1) + 0.36 * 3.7;
  CHECK_NEAR(fb_scenario_road_exit(s, 5), rr_exit, TIGHT);
  CHECK_NEAR(fb_scenario_road_exit(s, 5), 8.13, 0.005); /* the data sheet's rounding */
  CHECK(isnan(fb_scenario_road_entry(s, 6)));
  CHECK(isnan(fb_scenario_road_exit(NULL, 0)));
}

/* Every line of the example that gives a number says where it comes
 * from: "# paper" or "# assumed" (names and titles are no data). */
static void check_example_sources(void)
{
  FILE *fp = fopen(EXAMPLE, "r");
  CHECK(fp != NULL);
  if (!fp)
    return;
  char line[512];
  int values = 0, unsourced = 0;
  while (fgets(line, sizeof line, fp)) {
    const char *p = line + strspn(line, " ");
    const char *colon = strchr(p, ':');
    if (*p == '#' || !colon || !strncmp(p, "scenario:", 9) || !strncmp(p, "description:", 12))
      continue;
    const char *value = colon + 1 + strspn(colon + 1, " ");
    if (*value == '#' || *value == '\n' || *value == '\0')
      continue; /* a section heading */
    if (!strchr("-0123456789.[", *value))
      continue; /* a name, a choice, a title */
    ++values;
    if (!strstr(value, "# paper") && !strstr(value, "# assumed")) {
      ++unsourced;
      fprintf(stderr, "no source for: %s", line);
    }
  }
  fclose(fp);
  CHECK(values >= 60);
  CHECK(unsourced == 0);
}

static void test_example(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  int rc = fb_scenario_load(EXAMPLE, &s, &err);
  CHECK(rc == FB_OK);
  if (rc) {
    fprintf(stderr, "%s\n", err.msg);
    return;
  }
  check_hull(s);
  check_load(s);
  check_mounts(s);
  check_corners(s);
  check_outputs(s);
  check_road_and_run(s);
  check_bump_timing(s);
  CHECK(fb_scenario_check(s, &err) == FB_OK);
  fb_scenario_free(&s);
  CHECK(s == NULL);
  fb_scenario_free(&s); /* NULL is accepted */
  fb_scenario_free(NULL);
  check_example_sources();
}

/* ---- Copies. */

static int strings_equal(const char *a, const char *b);

static int corners_equal(const fb_corner_params *a, const fb_corner_params *b)
{
  return a->spring_k == b->spring_k && du_damper_c(a) == du_damper_c(b) &&
         a->motion_ratio == b->motion_ratio && a->x == b->x && a->y == b->y &&
         a->wheel_mass == b->wheel_mass && a->tire_k == b->tire_k && a->tire_c == b->tire_c &&
         fb_corner_tire_model(a) == fb_corner_tire_model(b) &&
         !memcmp(a->tire.bytes, b->tire.bytes, sizeof a->tire.bytes) &&
         strings_equal(a->name, b->name);
}

static int mounts_equal(const fb_mount *a, const fb_mount *b)
{
  return strings_equal(a->name, b->name) && a->mass == b->mass &&
         a->stiffness == b->stiffness && a->damping == b->damping && a->x == b->x &&
         a->y == b->y;
}

static int strings_equal(const char *a, const char *b)
{
  return (!a && !b) || (a && b && !strcmp(a, b));
}

/* Field by field, arrays by value. */
static int scenarios_equal(const fb_scenario *a, const fb_scenario *b)
{
  int eq = strings_equal(a->name, b->name) && strings_equal(a->path, b->path) &&
           a->gravity == b->gravity && a->hull_mass == b->hull_mass &&
           a->hull_ixx == b->hull_ixx && a->hull_iyy == b->hull_iyy && a->young == b->young &&
           a->poisson == b->poisson && a->density == b->density &&
           a->thickness == b->thickness && a->edge_front_x == b->edge_front_x &&
           a->edge_rear_x == b->edge_rear_x && a->edge_left_y == b->edge_left_y &&
           a->edge_right_y == b->edge_right_y && a->total_weight == b->total_weight &&
           a->payload == b->payload && a->nload == b->nload && a->nmounts == b->nmounts &&
           a->ncorners == b->ncorners && a->speed == b->speed &&
           road_bump(a)->height == road_bump(b)->height &&
           road_bump(a)->length == road_bump(b)->length &&
           road_bump(a)->angle == road_bump(b)->angle &&
           road_bump(a)->first_contact == road_bump(b)->first_contact && a->t_end == b->t_end &&
           a->rtol == b->rtol && a->atol == b->atol && a->max_step == b->max_step &&
           a->sample_rate == b->sample_rate && a->initial == b->initial;
  for (size_t k = 0; eq && k < a->nmounts; ++k)
    eq = mounts_equal(&a->mount[k], &b->mount[k]);
  for (size_t k = 0; eq && k < a->ncorners; ++k)
    eq = corners_equal(&a->corner[k], &b->corner[k]);
  for (size_t i = 0; eq && i < a->nload; ++i)
    eq = a->load_x[i] == b->load_x[i] && a->load_y[i] == b->load_y[i];
  return eq;
}

static void test_clone(void)
{
  fb_err err;
  fb_scenario *s = NULL, *c = NULL;
  CHECK(fb_scenario_load(EXAMPLE, &s, &err) == FB_OK);
  if (!s)
    return;
  CHECK(fb_scenario_clone(s, &c, &err) == FB_OK);
  CHECK(c && scenarios_equal(s, c));
  /* A deep copy: nothing shared, so changing one leaves the other. */
  CHECK(c && c->name != s->name && c->path != s->path && c->load_x != s->load_x &&
        c->load_y != s->load_y);
  if (c) {
    c->load_x[3] = 99;
    c->corner[5].tire_k = 1;
    CHECK(!scenarios_equal(s, c));
    CHECK(s->load_x[3] == -2.00 && s->corner[5].tire_k == 500000);
    CHECK(c->corner[0].name != s->corner[0].name && c->mount[0].name != s->mount[0].name &&
          c->output[0].title != s->output[0].title);
    /* The source is copied, its origins with it; not the warnings. */
    const sc_source *a = sc_source_of(s), *b = sc_source_of(c);
    CHECK(a && b && a != b && b->norigins == a->norigins &&
          b->origin[0].key != a->origin[0].key && !strcmp(b->origin[0].key, a->origin[0].key) &&
          b->nwarnings == 0);
  }
  fb_scenario_free(&c);
  /* Strings and arrays may be NULL in a hand-built scenario. */
  free(s->path);
  s->path = NULL;
  CHECK(fb_scenario_clone(s, &c, &err) == FB_OK);
  CHECK(c && c->path == NULL && scenarios_equal(s, c));
  fb_scenario_free(&c);
  CHECK(fb_scenario_clone(NULL, &c, &err) == FB_EINVAL && c == NULL);
  fb_scenario_free(&s);
}

/* ---- fb_scenario_check on hand-built scenarios (no file to point at). */

/* Drops s's source, as a scenario built without a file has none. */
static void drop_origins(fb_scenario *s)
{
  if (s->source)
    s->source->ops->free(s->source);
  s->source = NULL;
}

/* Applies change to a copy of base and expects FB_EINVAL with phrase. */
static void expect_check(const fb_scenario *base, void (*change)(fb_scenario *),
                         const char *phrase)
{
  /* Not loaded from a file: no origins; located, a message names the
   * part of the description in its own words (fb_scenario_part_text). */
  fb_err err;
  fb_scenario *s = NULL;
  if (fb_scenario_clone(base, &s, &err) != FB_OK)
    return;
  change(s);
  drop_origins(s);
  int rc = fb_scenario_check(s, &err);
  CHECK(err.part.kind != FB_PART_NONE);
  fb_scenario_locate(s, &err);
  CHECK(rc == FB_EINVAL);
  CHECK(strstr(err.msg, phrase) != NULL);
  if (rc != FB_EINVAL || !strstr(err.msg, phrase))
    fprintf(stderr, "  wanted '%s', got: %s\n", phrase, err.msg);
  fb_scenario_free(&s);
}

static void set_rr_tire_k(fb_scenario *s)
{
  s->corner[5].tire_k = -1;
}
static void set_no_load(fb_scenario *s)
{
  s->nload = 0;
}
static void set_nan_point(fb_scenario *s)
{
  s->load_y[3] = NAN;
}
static void set_angle_right(fb_scenario *s)
{
  road_bump(s)->angle = 2 * atan(1.0); /* 90 deg */
}
static void set_inf_speed(fb_scenario *s)
{
  s->speed = INFINITY;
}
static void set_bad_payload(fb_scenario *s)
{
  s->payload = (fb_payload_model)7;
}
static void set_rr_ahead(fb_scenario *s)
{
  s->corner[5].x = 20;  /* meets the bump at 5 + 0.36 ((1.9 - 20) + 2.1) = -0.76 s */
  s->edge_front_x = 21; /* on the floor still */
}
static void set_lumped_light(fb_scenario *s)
{
  s->payload = FB_PAYLOAD_LUMPED;
  s->total_weight = 39000; /* 3976 kg < 4041.72 kg */
}
static void set_many_samples(fb_scenario *s)
{
  s->sample_rate = 1e9; /* 1.5e10 samples */
}
static void set_lumped(fb_scenario *s)
{
  s->payload = FB_PAYLOAD_LUMPED;
}
static void set_three_modes(fb_scenario *s)
{
  s->hull_modes_kind = FB_HULL_MODES_COUNT;
  s->hull_modes = 3;
}
static void set_nodal_reduced(fb_scenario *s)
{
  s->hull_coordinates = FB_HULL_NODAL;
  s->hull_modes_kind = FB_HULL_MODES_COUNT;
  s->hull_modes = 80;
}
static void set_nodal_cutoff(fb_scenario *s)
{
  s->hull_coordinates = FB_HULL_NODAL;
  s->hull_cutoff_hz = 50.0;
}
static void set_count_cutoff(fb_scenario *s)
{
  s->hull_modes_kind = FB_HULL_MODES_COUNT;
  s->hull_modes = 40;
  s->hull_cutoff_hz = 50.0;
}
static void set_coarser_converged(fb_scenario *s)
{
  s->hull_mesh.density = 3;
  s->hull_converged_density = 2;
}
static void set_flat_bump(fb_scenario *s)
{
  road_bump(s)->height = 0;
}

static void test_check(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load(EXAMPLE, &s, &err) == FB_OK);
  if (!s)
    return;
  /* SI units, the description's members: a file's keys and units are its
   * reader's (test_scenario_errors). */
  expect_check(s, set_rr_tire_k, "corner[5] (RR).tire_k: must be > 0 N/m (got -1)");
  expect_check(s, set_no_load, "load_x: at least one load point");
  expect_check(s, set_nan_point, "load point 3: must be finite");
  expect_check(s, set_angle_right, "road (bump).angle_deg: must be in [0, 90) deg (got 90)");
  expect_check(s, set_inf_speed, "speed: must be > 0 m/s (got inf)");
  expect_check(s, set_bad_payload, "payload: unknown value 7");
  expect_check(s, set_rr_ahead, "road (bump): the RR wheel would meet the road's bump");
  expect_check(s, set_lumped_light, "payload: a lumped payload needs");
  expect_check(s, set_many_samples, "sample_rate: ");
  expect_check(s, set_three_modes, "hull_modes: auto, all or at least the 6 rigid");
  expect_check(s, set_nodal_reduced,
               "hull_modes: a choice of modes (a count) is for modal coordinates");
  expect_check(s, set_nodal_cutoff, "hull_cutoff_hz: a cut-off sets which modes");
  expect_check(s, set_count_cutoff, "not with a count of modes");
  /* Allowed: the lumped payload of the data sheet (7958.28 kg), a flat bump. */
  fb_scenario *c = NULL;
  CHECK(fb_scenario_clone(s, &c, &err) == FB_OK);
  if (c) {
    set_lumped(c);
    CHECK(fb_scenario_check(c, &err) == FB_OK);
    CHECK_NEAR(c->total_weight / c->gravity - c->hull_mass, 7958.28,
               0.005); /* quoted to 2 dp */
    set_flat_bump(c);
    CHECK(fb_scenario_check(c, &err) == FB_OK);
    /* A mesh already finer than the converged density: no second mesh
     * runs (flexbond run says so), which is no error. */
    set_coarser_converged(c);
    CHECK(fb_scenario_check(c, &err) == FB_OK);
  }
  fb_scenario_free(&c);
  CHECK(fb_scenario_check(NULL, &err) == FB_EINVAL);
  /* Loaded: the same error at the value every corner takes, in the
   * error's fields too. */
  s->corner[5].tire_k = -1;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL);
  CHECK(PART_IS(&err, FB_PART_CORNER, 5, "tire_k"));
  fb_scenario_locate(s, &err);
  CHECK(strstr(err.msg, EXAMPLE ":") == err.msg &&
        strstr(err.msg, ": wheel.tire_k: must be > 0 N/m (got -1)"));
  CHECK(!strcmp(err.key, "wheel.tire_k") && !strcmp(err.file, EXAMPLE) && err.line > 0 &&
        err.source == FB_SOURCE_FILE);
  fb_scenario_free(&s);
}

/* ---- Bad scenario files: a compact copy of the example with one or two
 * replacements. Line numbers below refer to this text. */

static const char base_text[] =
    "scenario: bad\n"                                                              /* 1 */
    "gravity: 9.81\n"                                                              /* 2 */
    "hull:\n"                                                                      /* 3 */
    "  mass: 4041.72\n"                                                            /* 4 */
    "  Ixx: 4173.49\n"                                                             /* 5 */
    "  Iyy: 15175.96\n"                                                            /* 6 */
    "  material: {young: 200e9, poisson: 0.3, density: 7860, thickness: 0.0085}\n" /* 7 */
    "  edges: {front_x: 2.47813311938948, rear_x: -2.65798412344113, left_y: 1.05, right_y: "
    "-1.05}\n"                 /* 8 */
    "load:\n"                  /* 9 */
    "  total_weight: 117720\n" /* 10 */
    "  payload: weight-only\n" /* 11 */
    "  points: {grid: {x: [-2.00, -1.70, -1.35, -1.00, -0.75, -0.45, -0.15, 0.10, 0.40, 0.65, "
    "0.95, 1.30, 1.90, 2.10],"
    " y: [-1.05, -0.55, 0.55, 1.05]}}\n" /* 12 */
    "mounts:\n"                          /* 13 */
    "  - {name: driver, mass: 100, stiffness: 19620, damping: 1400, x: 2.10, y: 0.55}\n" /* 14
                                                                                          */
    "  - {name: engine, mass: 500, stiffness: 122625, damping: 24761, x: 1.70, y: -0.55}\n"
    "wheel: {mass: 175, tire_k: 500000, tire_c: 140000}\n"                      /* 16 */
    "suspensions:\n"                                                            /* 17 */
    "  motion_ratio: 1\n"                                                       /* 18 */
    "  axles:\n"                                                                /* 19 */
    "    - {name: F, spring_k: 145300, damper_c: 25744, x: 1.90, y: 1.05}\n"    /* 20 */
    "    - {name: M, spring_k: 345550, damper_c: 25744, x: 0.40, y: 1.05}\n"    /* 21 */
    "    - {name: R, spring_k: 602100, damper_c: 39656, x: -1.00, y: 1.05}\n"   /* 22 */
    "road:\n"                                                                   /* 23 */
    "  speed_kmh: 10\n"                                                         /* 24 */
    "  bump: {height: 0.10, length: 3.70, angle_deg: 45, first_contact: 5.0}\n" /* 25 */
    "simulation: {t_end: 15, rtol: 1e-6, atol: 1e-8, sample_rate: 1000, initial: zero}\n";

typedef struct bad_case {
  const char *from, *to;   /* replace the (unique) text from by to */
  const char *from2, *to2; /* and a second one (may be NULL) */
  int code;
  const char *where;   /* "bad.yaml:LINE:COL:" the message must start with */
  const char *phrase;  /* and contain (the key path and what is wrong) */
  const char *phrase2; /* and this too (may be NULL) */
} bad_case;

#define EDGES_LINE                                                                             \
  "  edges: {front_x: 2.47813311938948, rear_x: -2.65798412344113, left_y: 1.05, right_y: "    \
  "-1.05}\n"
#define FE_OK "  fe: {mass_matrix: consistent, drill_factor: 1e-4, damping_ratio: 0.02}\n"

/* hull.masses with one mass of name and mass at (x, 0). */
#define HULL_MASS(name, mass, x)                                                               \
  "  masses: [{name: " name ", mass: " mass ", x: " x ", y: 0}]\n"

static const bad_case bad_cases[] = {
    /* System 2's optional hull sections (lines 9 and 10 when added). */
    {EDGES_LINE, EDGES_LINE "  mesh: {deck: h.inp, generator: {}}\n" FE_OK, NULL, NULL,
     FB_EPARSE, "bad.yaml:9:", "give either 'deck' or 'generator', not both", NULL},
    {EDGES_LINE, EDGES_LINE "  mesh: {density: 2, deck: h.inp}\n" FE_OK, NULL, NULL, FB_EPARSE,
     "bad.yaml:9:", "density refines the generator's mesh", NULL},
    {EDGES_LINE,
     EDGES_LINE "  mesh: {deck: h.inp}\n"
                "  fe: {mass_matrix: consistent, drill_factor: 1e-4, damping_ratio: 1.5}\n",
     NULL, NULL, FB_EINVAL,
     "bad.yaml:10:", "hull.fe.damping_ratio: must be in [0, 1) (got 1.5)", NULL},
    {EDGES_LINE,
     EDGES_LINE "  mesh: {deck: h.inp}\n"
                "  fe: {mass_matrix: diagonal, drill_factor: 1e-4, damping_ratio: 0.02}\n",
     NULL, NULL, FB_EPARSE, "bad.yaml:10:", "unknown value 'diagonal'", "consistent | lumped"},
    {EDGES_LINE, EDGES_LINE "  mesh: {deck: h.inp}\n", NULL, NULL, FB_EPARSE, "bad.yaml:", "fe",
     NULL},
    /* Physical checks, reported at the value. */
    {"F, spring_k: 145300", "F, spring_k: -145300", NULL, NULL, FB_EINVAL,
     "bad.yaml:20:", "suspensions.axles[0].spring_k: must be > 0 N/m (got -145300)", NULL},
    {"driver, mass: 100", "driver, mass: 0", NULL, NULL, FB_EINVAL,
     "bad.yaml:14:", "mounts[0].mass: must be > 0 kg (got 0)", NULL},
    {"damping: 24761", "damping: -1", NULL, NULL, FB_EINVAL,
     "bad.yaml:15:", "mounts[1].damping: must be >= 0 N s/m (got -1)", NULL},
    {"  Ixx: 4173.49", "  Ixx: .nan", NULL, NULL, FB_EINVAL,
     "bad.yaml:5:8:", "hull.Ixx: must be finite (got .nan)", NULL},
    {"density: 7860", "density: -.inf", NULL, NULL, FB_EINVAL,
     "bad.yaml:7:", "hull.material.density: must be finite (got -.inf)", NULL},
    {"poisson: 0.3", "poisson: 0.5", NULL, NULL, FB_EINVAL,
     "bad.yaml:7:", "hull.material.poisson: must be in [0, 0.5) (got 0.5)", NULL},
    {"young: 200e9", "young: 0", NULL, NULL, FB_EINVAL,
     "bad.yaml:7:", "hull.material.young: must be > 0 Pa", NULL},
    {"front_x: 2.47813311938948", "front_x: -4", NULL, NULL, FB_EINVAL,
     "bad.yaml:8:", "hull.edges.front_x: the front edge must be ahead of the rear edge", NULL},
    {"gravity: 9.81", "gravity: 0", NULL, NULL, FB_EINVAL,
     "bad.yaml:2:10:", "gravity: must be > 0 m/s^2", NULL},
    {"total_weight: 117720", "total_weight: -1", NULL, NULL, FB_EINVAL,
     "bad.yaml:10:17:", "load.total_weight: must be > 0 N", NULL},
    /* A shared value: reported where the file gives it. */
    {"wheel: {mass: 175", "wheel: {mass: -175", NULL, NULL, FB_EINVAL,
     "bad.yaml:16:15:", "wheel.mass: must be > 0 kg (got -175)", NULL},
    {"tire_c: 140000}", "tire_c: 140000, tire_contact: unilaterl}", NULL, NULL, FB_EPARSE,
     "bad.yaml:16:", "unknown value 'unilaterl' (did you mean 'unilateral'?)",
     "bilateral | unilateral"},
    {"tire_c: 140000}", "tire_c: 140000, tire_contact: [1]}", NULL, NULL, FB_EPARSE,
     "bad.yaml:16:", "tire_contact", NULL},
    {"motion_ratio: 1", "motion_ratio: 0", NULL, NULL, FB_EINVAL,
     "bad.yaml:18:17:", "suspensions.motion_ratio: must be > 0 (got 0)", NULL},
    /* A corner's override: reported there. */
    {"x: 0.40, y: 1.05}", "x: 0.40, y: 1.05, wheel: {tire_c: -5}}", NULL, NULL, FB_EINVAL,
     "bad.yaml:21:", "suspensions.axles[1].wheel.tire_c: must be >= 0 N s/m (got -5)", NULL},
    /* An axle's y is its left corner's. */
    {"x: 0.40, y: 1.05}", "x: 0.40, y: -1.05}", NULL, NULL, FB_EINVAL, "bad.yaml:21:",
     "suspensions.axles[1].y: must be > 0 m: an axle's y is its left wheel's", NULL},
    /* Without a top-level wheel, every item gives its own. */
    {"wheel: {mass: 175, tire_k: 500000, tire_c: 140000}\n", "", NULL, NULL, FB_EPARSE,
     "bad.yaml:19:", "suspensions.axles[0]: missing required key", "wheel.mass"},
    {"speed_kmh: 10", "speed_kmh: 0", NULL, NULL, FB_EINVAL,
     "bad.yaml:24:14:", "road.speed_kmh: must be > 0 km/h (got 0)", NULL},
    {"height: 0.10", "height: -0.1", NULL, NULL, FB_EINVAL,
     "bad.yaml:25:", "road.bump.height: must be >= 0 m", NULL},
    {"length: 3.70", "length: 0", NULL, NULL, FB_EINVAL,
     "bad.yaml:25:", "road.bump.length: must be > 0 m", NULL},
    {"angle_deg: 45", "angle_deg: 90", NULL, NULL, FB_EINVAL,
     "bad.yaml:25:", "road.bump.angle_deg: must be in [0, 90) deg (got 90)", NULL},
    {"angle_deg: 45", "angle_deg: -1", NULL, NULL, FB_EINVAL,
     "bad.yaml:25:", "road.bump.angle_deg: must be in [0, 90) deg (got -1)", NULL},
    {"first_contact: 5.0", "first_contact: -1", NULL, NULL, FB_EINVAL,
     "bad.yaml:25:", "road.bump.first_contact: must be >= 0 s", NULL},
    /* Bump timing: RR leaves at 8.132 s (see check_road_timing). */
    {"t_end: 15", "t_end: 8", NULL, NULL, FB_EINVAL,
     "bad.yaml:", "simulation.t_end: the run ends at 8 s",
     "before the last wheel (RR) leaves the road's bump at 8.132 s"},
    /* A single corner X 0.5 m ahead of LF meets a square bump (0 deg) at
     * 0 + 0.36 (1.9 - 2.4) = -0.18 s. */
    {"angle_deg: 45, first_contact: 5.0", "angle_deg: 0, first_contact: 0", "road:\n",
     "  corners: [{name: X, spring_k: 1e5, damper_c: 1e4, x: 2.40, y: 0}]\nroad:\n", FB_EINVAL,
     "bad.yaml:26:", "road.bump: the X wheel would meet the road's bump at -0.18 s", NULL},
    /* Points off the floor (hull.edges), and two suspensions at one point. */
    {"x: 2.10, y: 0.55}", "x: 2.10, y: 1.55}", NULL, NULL, FB_EINVAL, "bad.yaml:14:",
     "mounts[0].y: must lie on the hull's floor, between the right end's y = -1.05 and the "
     "left "
     "end's y = 1.05 m (got 1.55)",
     NULL},
    {"x: -1.00, y: 1.05}", "x: -3.00, y: 1.05}", NULL, NULL, FB_EINVAL, "bad.yaml:22:",
     "suspensions.axles[2].x: must lie on the hull's floor, between the rear edge's x = "
     "-2.657984123 and the front edge's x = 2.478133119 m (got -3)",
     NULL},
    {"y: [-1.05, -0.55, 0.55, 1.05]", "y: [-1.05, -0.55, 0.55, 1.25]", NULL, NULL, FB_EINVAL,
     "bad.yaml:12:", "load.points[3]: must lie on the hull's floor", NULL},
    {"x: [-2.00, -1.70,", "x: [-2.00, -2.00,", NULL, NULL, FB_EINVAL,
     "bad.yaml:12:", "load.points[4]: at (-2, -1.05) m, where load point 0 already is", NULL},
    {"road:\n",
     "  corners: [{name: X, spring_k: 1e5, damper_c: 1e4, x: 0.40, y: 1.05}]\nroad:\n", NULL,
     NULL, FB_EINVAL, "bad.yaml:23:",
     "suspensions.corners[0]: at (0.4, 1.05) m, where corner LM already is", NULL},
    /* Names: unique, and the corners count. */
    {"road:\n", "  corners: [{name: LM, spring_k: 1e5, damper_c: 1e4, x: 0, y: 0}]\nroad:\n",
     NULL, NULL, FB_EINVAL, "bad.yaml:23:", "suspensions.corners[0]: a second corner named LM",
     NULL},
    {"name: engine", "name: driver", NULL, NULL, FB_EINVAL,
     "bad.yaml:15:", "mounts[1]: a second mount named driver", NULL},
    {"    - {name: M, spring_k: 345550, damper_c: 25744, x: 0.40, y: 1.05}\n"
     "    - {name: R, spring_k: 602100, damper_c: 39656, x: -1.00, y: 1.05}\n",
     "", NULL, NULL, FB_EINVAL, "bad.yaml:18:", "suspensions: at least 3 corners", NULL},
    {"F, spring_k: 145300, damper_c: 25744,",
     "F, spring_k: 145300, damper_c: 25744, "
     "damper_table: {points: [[0, 0], [1, 1]]},",
     NULL, NULL, FB_EPARSE, "bad.yaml:20:",
     "suspensions.axles[0].damper_table: give either 'damper_c' or 'damper_table', not both",
     NULL},
    /* Outputs. */
    {"road:\n", "outputs: [{signal: tire_forse, of: LF}]\nroad:\n", NULL, NULL, FB_EPARSE,
     "bad.yaml:23:",
     "outputs[0].signal: unknown signal 'tire_forse' (did you mean "
     "'tire_force'?)",
     NULL},
    {"road:\n", "outputs: [{signal: tire_force}]\nroad:\n", NULL, NULL, FB_EPARSE,
     "bad.yaml:23:", "outputs[0]: missing required key 'of'", NULL},
    {"road:\n", "outputs: [{signal: tire_force, of: XX}]\nroad:\n", NULL, NULL, FB_EINVAL,
     "bad.yaml:23:", "outputs[0].of: no corner named 'XX'", NULL},
    {"road:\n", "outputs: [{signal: torsion, of: LF}]\nroad:\n", NULL, NULL, FB_EPARSE,
     "bad.yaml:23:", "outputs[0].of: a torsion signal measures no corner, mount or bogie",
     NULL},
    {"road:\n", "outputs: [{signal: acc, of: driver}, {signal: acc, of: driver}]\nroad:\n",
     NULL, NULL, FB_EINVAL,
     "bad.yaml:23:", "outputs[1].name: 'driver_acc' is output 0's name already", NULL},
    {"road:\n", "outputs: [{signal: torsion, name: t}]\nroad:\n", NULL, NULL, FB_EINVAL,
     "bad.yaml:23:", "outputs[0].name: 't' is a column of its own", NULL},
    {"road:\n", "outputs: [{signal: torsion, figure: 3, window: [20, 10]}]\nroad:\n", NULL,
     NULL, FB_EINVAL, "bad.yaml:23:",
     "outputs[0].window: must be [t0, t1] with 0 <= t0 < t1 (got [20, 10])", NULL},
    {"t_end: 15", "t_end: 0", NULL, NULL, FB_EINVAL,
     "bad.yaml:26:", "simulation.t_end: must be > 0 s", NULL},
    {"rtol: 1e-6", "rtol: 1", NULL, NULL, FB_EINVAL,
     "bad.yaml:26:", "simulation.rtol: must be in (0, 1) (got 1)", NULL},
    {"atol: 1e-8", "atol: 0", NULL, NULL, FB_EINVAL,
     "bad.yaml:26:", "simulation.atol: must be > 0", NULL},
    {"sample_rate: 1000", "sample_rate: -1000", NULL, NULL, FB_EINVAL,
     "bad.yaml:26:", "simulation.sample_rate: must be > 0 Hz", NULL},
    {"initial: zero}", "initial: zero, max_step: -1}", NULL, NULL, FB_EINVAL,
     "bad.yaml:26:", "simulation.max_step: must be >= 0 s", NULL},
    /* 30000 N / 9.81 = 3058 kg is less than the hull alone. */
    {"payload: weight-only", "payload: lumped", "total_weight: 117720", "total_weight: 30000",
     FB_EINVAL, "bad.yaml:11:12:", "load.payload: a lumped payload needs", NULL},
    /* Hull masses (line 7 when added): on the floor, named uniquely among
     * themselves (in capitals too: their node sets), the mounts and the
     * corners, counted in a lumped payload's mass. */
    {"  Iyy: 15175.96\n", "  Iyy: 15175.96\n" HULL_MASS("battery", "300", "3.5"), NULL, NULL,
     FB_EINVAL, "bad.yaml:7:",
     "hull.masses[0].x: must lie on the hull's floor, between the rear edge's x = "
     "-2.657984123 and the front edge's x = 2.478133119 m (got 3.5)",
     NULL},
    {"  Iyy: 15175.96\n",
     "  Iyy: 15175.96\n  masses:\n    - {name: battery, mass: 300, x: 0, y: 0}\n"
     "    - {name: battery, mass: 100, x: 1, y: 0}\n",
     NULL, NULL, FB_EINVAL, "bad.yaml:9:",
     "hull.masses[1]: a second hull mass named battery (hull mass names are unique)", NULL},
    {"  Iyy: 15175.96\n",
     "  Iyy: 15175.96\n  masses:\n    - {name: battery, mass: 300, x: 0, y: 0}\n"
     "    - {name: Battery, mass: 100, x: 1, y: 0}\n",
     NULL, NULL, FB_EINVAL, "bad.yaml:9:",
     "hull.masses[1]: hull mass battery's name in other capitals", "node set MASS_BATTERY"},
    {"  Iyy: 15175.96\n", "  Iyy: 15175.96\n" HULL_MASS("engine", "300", "0"), NULL, NULL,
     FB_EINVAL, "bad.yaml:7:", "hull.masses[0]: a mount is named engine already", NULL},
    {"  Iyy: 15175.96\n", "  Iyy: 15175.96\n" HULL_MASS("LF", "300", "0"), NULL, NULL,
     FB_EINVAL, "bad.yaml:7:", "hull.masses[0]: a corner is named LF already", NULL},
    {"  Iyy: 15175.96\n", "  Iyy: 15175.96\n" HULL_MASS("battery", "0", "0"), NULL, NULL,
     FB_EINVAL, "bad.yaml:7:", "hull.masses[0].mass: must be > 0 kg (got 0)", NULL},
    {"  Iyy: 15175.96\n", "  Iyy: 15175.96\n  masses: [{mass: 300, x: 0, y: 0}]\n", NULL, NULL,
     FB_EPARSE, "bad.yaml:7:", "hull.masses[0]: missing required key 'name'", NULL},
    /* 117720 N / 9.81 = 12000 kg, less than the hull and its 8 t. */
    {"payload: weight-only", "payload: lumped", "  Iyy: 15175.96\n",
     "  Iyy: 15175.96\n" HULL_MASS("ballast", "8000", "0"), FB_EINVAL, "bad.yaml:12:12:",
     "load.payload: a lumped payload needs the total weight / gravity (12000 kg) > the hull's "
     "structure (4041.72 kg) + its declared masses (8000 kg)",
     NULL},
    /* Structure: corners. */
    {"  axles:", "  axels:", NULL, NULL, FB_EPARSE,
     "bad.yaml:19:3:", "suspensions.axels: unknown key 'axels' (did you mean 'axles'?)", NULL},
    {"F, spring_k", "F, sprng_k", NULL, NULL, FB_EPARSE, "bad.yaml:20:",
     "suspensions.axles[0].sprng_k: unknown key 'sprng_k' (did you mean 'spring_k'?)", NULL},
    {"    - {name: M, spring_k: 345550, damper_c: 25744, x: 0.40, y: 1.05}", "    - 7", NULL,
     NULL, FB_EPARSE, "bad.yaml:21:7:", "suspensions.axles[1]: expected", "a mapping"},
    /* Missing keys and sections, unknown keys. */
    {"  Iyy: 15175.96\n", "", NULL, NULL, FB_EPARSE,
     "bad.yaml:4:3:", "hull: missing required key 'Iyy'", NULL},
    {"gravity: 9.81\n", "", NULL, NULL, FB_EPARSE,
     "bad.yaml:1:1:", "missing required key 'gravity'", NULL},
    {"gravity: 9.81", "gravty: 9.81", NULL, NULL, FB_EPARSE,
     "bad.yaml:2:1:", "gravty: unknown key 'gravty' (did you mean 'gravity'?)", NULL},
    {"speed_kmh: 10", "speed: 10", NULL, NULL, FB_EPARSE,
     "bad.yaml:24:3:", "road.speed: unknown key 'speed'", NULL},
    /* Types and enumerations. */
    {"tire_k: 500000", "tire_k: [500000]", NULL, NULL, FB_EPARSE,
     "bad.yaml:16:28:", "wheel.tire_k: expected a number or expression, got a list", NULL},
    {"driver, mass: 100", "driver, mass: heavy", NULL, NULL, FB_EPARSE,
     "bad.yaml:14:", "mounts[0].mass: expression 'heavy'", "unknown name 'heavy'"},
    {"edges: {front_x: 2.47813311938948, rear_x: -2.65798412344113, left_y: 1.05, right_y: "
     "-1.05}",
     "edges: [3.0, -3.0, 1.25, -1.25]", NULL, NULL, FB_EPARSE,
     "bad.yaml:8:10:", "hull.edges: expected the edge lines", "got a list"},
    {"payload: weight-only", "payload: weightonly", NULL, NULL, FB_EPARSE, "bad.yaml:11:12:",
     "load.payload: unknown value 'weightonly' (did you mean 'weight-only'?)",
     "weight-only | lumped"},
    {"initial: zero", "initial: rest", NULL, NULL, FB_EPARSE,
     "bad.yaml:26:", "simulation.initial: unknown value 'rest'", "zero | static"},
    {"scenario: bad", "scenario: a b", NULL, NULL, FB_EPARSE,
     "bad.yaml:1:11:", "scenario: the name 'a b' must start", NULL},
    /* Load points. */
    {"points: {grid:", "points: {grd:", NULL, NULL, FB_EPARSE,
     "bad.yaml:12:", "load.points.grd: unknown key 'grd' (did you mean 'grid'?)", NULL},
    {"y: [-1.05, -0.55, 0.55, 1.05]", "y: []", NULL, NULL, FB_EMODEL,
     "bad.yaml:12:", "load.points.grid.y: expected at least one value", NULL},
    {"points: {grid: {x: [-2.00, -1.70, -1.35, -1.00, -0.75, -0.45, -0.15, 0.10, 0.40, 0.65, "
     "0.95, 1.30, 1.90, 2.10],"
     " y: [-1.05, -0.55, 0.55, 1.05]}}",
     "points: [[0, 0], [1, 2, 3]]", NULL, NULL, FB_EMODEL,
     "bad.yaml:12:", "load.points[1]: expected 2 values, got 3", NULL},
    {"points: {grid: {x: [-2.00, -1.70, -1.35, -1.00, -0.75, -0.45, -0.15, 0.10, 0.40, 0.65, "
     "0.95, 1.30, 1.90, 2.10],"
     " y: [-1.05, -0.55, 0.55, 1.05]}}",
     "points: []", NULL, NULL, FB_EINVAL,
     "bad.yaml:12:11:", "load.points: at least one load point is needed", NULL},
    /* Parameters and YAML itself. */
    {"scenario: bad\n", "scenario: bad\nparameters: {v: 10, t: 1}\n", NULL, NULL, FB_EPARSE,
     "bad.yaml:2:21:", "parameters.t: 't' is reserved", NULL},
    {"gravity: 9.81", "gravity: [9.81", NULL, NULL, FB_EPARSE, "bad.yaml:", "YAML:", NULL},
    {"gravity: 9.81", "gravity: 9.81\ngravity: 9.8", NULL, NULL, FB_EPARSE,
     "bad.yaml:3:", "duplicate key", NULL},
    {"simulation: {", "---\nsimulation: {", NULL, NULL, FB_EPARSE,
     "bad.yaml:26:1:", "second document", NULL},
    /* Text of scalars (model_yaml.c): a NUL, control characters in
     * one-line text and in a description; integers beyond 2^53. */
    {"tire_c: 140000}", "tire_c: \"140000\\0junk\"}", NULL, NULL, FB_EPARSE,
     "bad.yaml:", "wheel.tire_c: the value has a NUL", NULL},
    {"scenario: bad\n", "scenario: \"bad\\x01\"\n", NULL, NULL, FB_EPARSE,
     "bad.yaml:1:", "scenario: has control character 0x01", NULL},
    {"scenario: bad\n", "scenario: bad\ndescription: \"a\\x1bb\"\n", NULL, NULL, FB_EPARSE,
     "bad.yaml:2:", "description: has an escape", NULL},
    {"payload: weight-only", "payload: \"weight-only\\n\"", NULL, NULL, FB_EPARSE,
     "bad.yaml:", "payload: has a line break", NULL},
    {"speed_kmh: 10", "speed_kmh: 10000000000000000000", NULL, NULL, FB_EINVAL,
     "bad.yaml:", "road.speed_kmh: the integer 10000000000000000000 is beyond 2^53", NULL},
};

/* base_text with from -> to (from must occur exactly once); NULL if not. */
static char *replace_once(const char *text, const char *from, const char *to)
{
  const char *at = strstr(text, from);
  if (!at || strstr(at + 1, from))
    return NULL;
  size_t head = (size_t)(at - text), nfrom = strlen(from), nto = strlen(to);
  char *out = malloc(strlen(text) - nfrom + nto + 1);
  if (!out)
    return NULL;
  memcpy(out, text, head);
  memcpy(out + head, to, nto);
  strcpy(out + head + nto, at + nfrom);
  return out;
}

static void run_bad_case(size_t i, const bad_case *b)
{
  char *text = replace_once(base_text, b->from, b->to);
  char *text2 = (text && b->from2) ? replace_once(text, b->from2, b->to2) : NULL;
  const char *use = b->from2 ? text2 : text;
  CHECK(use != NULL); /* the case's replacement applies */
  if (use) {
    fb_err err;
    fb_scenario *s = NULL;
    int rc = fb_scenario_load_string(use, strlen(use), "bad.yaml", &s, &err);
    int ok = rc == b->code && s == NULL && !strncmp(err.msg, b->where, strlen(b->where)) &&
             strstr(err.msg, b->phrase) && (!b->phrase2 || strstr(err.msg, b->phrase2));
    CHECK(ok);
    if (!ok)
      fprintf(stderr, "  bad case %zu: got %s: %s\n  wanted %s: %s ... %s\n", i,
              fb_status_name(rc), err.msg, fb_status_name(b->code), b->where, b->phrase);
    fb_scenario_free(&s);
  }
  free(text);
  free(text2);
}

static void test_bad_files(void)
{
  size_t n = sizeof bad_cases / sizeof bad_cases[0];
  CHECK(n >= 20);
  for (size_t i = 0; i < n; ++i)
    run_bad_case(i, &bad_cases[i]);
}

/* ---- Good variants of the compact text. */

static fb_scenario *load_text(const char *text, const char *name)
{
  fb_err err;
  fb_scenario *s = NULL;
  int rc = fb_scenario_load_string(text, strlen(text), name, &s, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  unexpected error: %s\n", err.msg);
  return s;
}

static void test_good_variants(void)
{
  fb_err err;
  fb_scenario *base = load_text(base_text, NULL), *ex = NULL;
  CHECK(fb_scenario_load(EXAMPLE, &ex, &err) == FB_OK);
  if (base && ex) {
    /* The compact form reads to the example's values (name and path aside). */
    free(base->name);
    base->name = ex->name;
    base->path = ex->path;
    CHECK(scenarios_equal(base, ex));
    base->name = NULL;
    base->path = NULL;
  }
  fb_scenario_free(&ex);
  fb_scenario_free(&base);

  /* Parameters and expressions; overrides per corner; explicit points;
   * a flat bump and the options. */
  char *t1 = replace_once(base_text, "scenario: bad\n",
                          "scenario: good\nparameters: {v: 36, deg: 30}\n");
  char *t2 = t1 ? replace_once(t1, "speed_kmh: 10", "speed_kmh: v / 2") : NULL;
  char *t3 = t2 ? replace_once(t2, "angle_deg: 45", "angle_deg: deg") : NULL;
  char *t4 = t3 ? replace_once(t3, "x: -1.00, y: 1.05}",
                               "x: -1.00, y: 1.05, wheel: {mass: 200, tire_k: 4e5, tire_c: 0}, "
                               "motion_ratio: 0.8}")
                : NULL;
  char *t5 = t4 ? replace_once(t4, "height: 0.10", "height: 0") : NULL;
  char *t6 = t5 ? replace_once(t5,
                               "points: {grid: {x: [-2.00, -1.70, -1.35, -1.00, -0.75, -0.45, "
                               "-0.15, 0.10, 0.40, 0.65, 0.95, 1.30, 1.90, 2.10],"
                               " y: [-1.05, -0.55, 0.55, 1.05]}}",
                               "points: [[1, 0.5], [-1, -0.5]]")
                : NULL;
  char *t7 = t6 ? replace_once(t6, "payload: weight-only", "payload: lumped") : NULL;
  char *t8 = t7 ? replace_once(t7, "initial: zero}", "initial: static, max_step: 0.01}") : NULL;
  char *t9 =
      t8 ? replace_once(t8, "tire_c: 140000}", "tire_c: 140000, tire_contact: unilateral}")
         : NULL;
  CHECK(t9 != NULL);
  fb_scenario *s = t9 ? load_text(t9, NULL) : NULL;
  if (s) {
    CHECK(s->path == NULL && !strcmp(s->name, "good"));
    CHECK_NEAR(s->speed, 5, TIGHT);                             /* 18 km/h */
    CHECK_NEAR(road_bump(s)->angle, 0.5235987755982988, TIGHT); /* pi / 6 */
    /* The rear axle's own wheels, both its corners; the middle's shared. */
    const fb_corner_params *rr = &s->corner[5], *lr = &s->corner[4], *lm = &s->corner[2];
    CHECK(rr->wheel_mass == 200 && rr->tire_k == 4e5 && rr->tire_c == 0);
    CHECK(rr->motion_ratio == 0.8 && lr->motion_ratio == 0.8 && lr->wheel_mass == 200);
    CHECK(lm->wheel_mass == 175 && lm->tire_k == 500000 && lm->motion_ratio == 1);
    CHECK(road_bump(s)->height == 0);
    CHECK(s->nload == 2 && s->load_x[0] == 1 && s->load_y[0] == 0.5 && s->load_x[1] == -1 &&
          s->load_y[1] == -0.5);
    CHECK(s->payload == FB_PAYLOAD_LUMPED && s->initial == FB_INITIAL_STATIC);
    CHECK(s->max_step == 0.01);
    for (size_t c = 0; c < s->ncorners; ++c)
      CHECK(fb_corner_tire_model(&s->corner[c]) == &fb_tire_model_unilateral);
    /* RR by hand at 5 m/s, tan 30 deg = 1/sqrt(3): 5 + (2.9 + 2.1/sqrt 3)/5. */
    CHECK_NEAR(fb_scenario_road_entry(s, 5), 5 + (2.9 + 2.1 / sqrt(3.0)) / 5, TIGHT);
  }
  fb_scenario_free(&s);
  free(t1);
  free(t2);
  free(t3);
  free(t4);
  free(t5);
  free(t6);
  free(t7);
  free(t8);
  free(t9);
}

/* A deck is resolved from the scenario's directory and read when the
 * scenario is loaded (its mesh gives the hull's properties), so a deck
 * that cannot be read fails the load at the line that names it: line 9
 * (the mesh line added after line 8), column 16. A clone keeps the files
 * a scenario names. */
static void test_deck_reference(void)
{
  char *text = replace_once(base_text, EDGES_LINE, EDGES_LINE "  mesh: {deck: h.inp}\n" FE_OK);
  fb_scenario *s = NULL, *c = NULL;
  fb_err err;
  CHECK(text && fb_scenario_load_string(text, strlen(text), "deck.yaml", &s, &err) == FB_EIO);
  CHECK(!s &&
        strstr(err.msg, "deck.yaml:9:16: hull.mesh.deck: ./h.inp: cannot open") == err.msg);
  CHECK(!strcmp(err.key, "hull.mesh.deck") && err.line == 9 && err.column == 16);
  /* In a private directory, so that no h.inp beside it exists. */
  char path[TEST_PATH_MAX];
  test_tmp_path("deck.yaml", path, sizeof path);
  FILE *fp = text ? fopen(path, "w") : NULL;
  CHECK(fp && fputs(text, fp) >= 0 && fclose(fp) == 0);
  if (fp) {
    char want[TEST_PATH_MAX + 64];
    snprintf(want, sizeof want, "%s:9:16: hull.mesh.deck: %s/h.inp: cannot open", path,
             test_tmpdir());
    CHECK(fb_scenario_load(path, &s, &err) == FB_EIO && !s && strstr(err.msg, want) == err.msg);
    if (strstr(err.msg, want) != err.msg)
      fprintf(stderr, "  wanted '%s...', got '%s'\n", want, err.msg);
  }
  free(text);
  /* The generator's scenario names no deck, nor any other file. */
  CHECK(fb_scenario_load(EXAMPLE, &s, NULL) == FB_OK && s && !s->hull_deck);
  CHECK(s && s->ninputs == 0 && s->inputs == NULL);
  fb_scenario_free(&s);
  /* The tables of the shock-absorber example, each once (four corners
   * share the front one), resolved from the scenario's directory. */
  CHECK(fb_scenario_load("../examples/apc6x6_shock_table.yaml", &s, NULL) == FB_OK && s);
  CHECK(s && s->ninputs == 2 && !strcmp(s->inputs[0], "../examples/shock_front.csv") &&
        !strcmp(s->inputs[1], "../examples/shock_rear.csv"));
  CHECK(s && fb_scenario_clone(s, &c, &err) == FB_OK && c && c->ninputs == 2 &&
        c->inputs[0] != s->inputs[0] && !strcmp(c->inputs[0], s->inputs[0]));
  CHECK(c && du_damper_table(&c->corner[0]) && du_damper_table(&c->corner[0])->npoints > 1 &&
        du_damper_table(&c->corner[0])->force[1] == du_damper_table(&s->corner[0])->force[1]);
  fb_scenario_free(&c);
  fb_scenario_free(&s);
}

/* Every value visited once, with its key, unit, where it was written,
 * and its text. */
typedef struct visit_log {
  int n, spring_lf, wheel_rr, driver_mass, output_title;
} visit_log;

static int visit(const fb_scenario_value *v, void *ctx)
{
  visit_log *log = ctx;
  ++log->n;
  if (!strcmp(v->key, "corners.LF.spring_k"))
    log->spring_lf = !strcmp(v->value, "145300") && !strcmp(v->unit, "N/m") && v->path &&
                     !strcmp(v->path, "suspensions.axles[0].spring_k");
  if (!strcmp(v->key, "corners.RR.wheel.mass"))
    log->wheel_rr = !strcmp(v->value, "175") && v->path && !strcmp(v->path, "wheel.mass");
  if (!strcmp(v->key, "mounts.driver.mass"))
    log->driver_mass = !strcmp(v->value, "100") && !strcmp(v->unit, "kg") && v->doc;
  if (!strcmp(v->key, "outputs[2].title"))
    log->output_title = !strcmp(v->value, "Hull torsion angle");
  return 0;
}

static int stop_at_first(const fb_scenario_value *v, void *ctx)
{
  (void)v;
  ++*(int *)ctx;
  return 7;
}

static void test_each_value(void)
{
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load(EXAMPLE, &s, NULL) == FB_OK && s);
  if (!s)
    return;
  visit_log log = {0};
  CHECK(fb_scenario_each_value(s, visit, &log) == FB_OK);
  CHECK(log.n > 100 && log.spring_lf && log.wheel_rr && log.driver_mass && log.output_title);
  int calls = 0;
  CHECK(fb_scenario_each_value(s, stop_at_first, &calls) == 7 && calls == 1);
  CHECK(fb_scenario_each_value(NULL, visit, &log) == FB_EINVAL);
  fb_scenario_free(&s);
}

/* ---- API misuse and files. */

static void test_api_errors(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load("no/such/file.yaml", &s, &err) == FB_EIO && s == NULL);
  CHECK(strstr(err.msg, "no/such/file.yaml") != NULL);
  CHECK(fb_scenario_load(NULL, &s, &err) == FB_EINVAL);
  CHECK(fb_scenario_load_string(NULL, 0, "x", &s, &err) == FB_EINVAL);
  CHECK(fb_scenario_load_string("", 0, "empty.yaml", &s, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "empty.yaml:1:1:") == err.msg && strstr(err.msg, "empty"));
  /* Without a display name, messages say <string>. */
  const char *text = "scenario: x\n";
  CHECK(fb_scenario_load_string(text, strlen(text), NULL, &s, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "<string>:1:1:") == err.msg);
  CHECK(fb_scenario_load_string(text, strlen(text), NULL, &s, NULL) == FB_EPARSE && s == NULL);
}

/* A description is free text: tabs and line breaks (a block scalar) are
 * kept, where a name or choice would be refused. */
static void test_description_lines(void)
{
  char *t = replace_once(base_text, "scenario: bad\n",
                         "scenario: good\ndescription: |\n  two\tcolumns\n  and lines\n");
  CHECK(t != NULL);
  fb_scenario *s = t ? load_text(t, "good.yaml") : NULL;
  CHECK(s && !strcmp(s->name, "good"));
  fb_scenario_free(&s);
  free(t);
}

/* The unit of a key by its full path, through lists of items and of
 * numbers (fb_scenario_key_unit). */
static void expect_unit(const char *path, const char *unit)
{
  const char *got = fb_scenario_key_unit(path);
  const int ok = unit ? got && !strcmp(got, unit) : got == NULL;
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  %s: got %s, wanted %s\n", path ? path : "NULL", got ? got : "NULL",
            unit ? unit : "NULL");
}

static void test_key_unit(void)
{
  expect_unit("road.speed_kmh", "km/h");
  expect_unit("gravity", "m/s^2");
  expect_unit("suspensions.axles[0].spring_k", "N/m");
  expect_unit("suspensions.axles[2].wheel.tire_c", "N s/m");
  expect_unit("hull.mesh.generator.bulkheads[1]", "m");
  expect_unit("simulation.initial", NULL); /* a choice */
  expect_unit("suspensions.axles", NULL);  /* a list */
  expect_unit("road.no_such_key", NULL);
  expect_unit("suspensions.axles[0", NULL);
  expect_unit("suspensions.axles[0]x", NULL);
  expect_unit(NULL, NULL);
}

int main(void)
{
  test_key_unit();
  test_example();
  test_clone();
  test_check();
  test_bad_files();
  test_good_variants();
  test_description_lines();
  test_deck_reference();
  test_each_value();
  test_api_errors();
  return check_report("test_scenario");
}
