/* SPDX-License-Identifier: BSD-3-Clause */
/* A vehicle described by a program, without any text
 * (src/vehicle/builder.c): the paper's 6x6 APC made part by part from the
 * data sheet (docs/reference-vehicle.md) runs as the same vehicle read
 * from examples/apc6x6.yaml; the builder's refusals name what is wrong;
 * and a description it makes owns its parts. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "check.h"
#include "damper_util.h"
#include "road_util.h"
#include "vehicle_util.h"

static const double PI = 3.14159265358979323846;

/* The data sheet's axles: x, y of the left corner (the right one at -y),
 * spring rate, damper rate. */
static const struct {
  const char *left, *right;
  double x, y, spring_k, damper_c;
} axles[] = {
    {"LF", "RF", 1.90, 1.05, 145300, 25744},
    {"LM", "RM", 0.40, 1.05, 345550, 25744},
    {"LR", "RR", -1.00, 1.05, 602100, 39656},
};

static int add_corners(fb_scenario *s, fb_err *err)
{
  int rc = FB_OK;
  for (size_t a = 0; !rc && a < sizeof axles / sizeof axles[0]; ++a)
    for (int side = 0; !rc && side < 2; ++side) {
      fb_corner_params c = {.name = (char *)(side ? axles[a].right : axles[a].left),
                            .spring_k = axles[a].spring_k,
                            .motion_ratio = 1,
                            .x = axles[a].x,
                            .y = side ? -axles[a].y : axles[a].y,
                            .wheel_mass = 175,
                            .tire_k = 500000,
                            .tire_c = 140000};
      du_set_damper_c(&c, axles[a].damper_c);
      rc = fb_scenario_add_corner(s, &c, err);
    }
  return rc;
}

static int add_mounts_and_load(fb_scenario *s, fb_err *err)
{
  const fb_mount driver = {"driver", 100, 19620, 1400, 2.10, 0.55};
  const fb_mount engine = {"engine", 500, 122625, 24761, 1.70, -0.55};
  int rc = fb_scenario_add_mount(s, &driver, err);
  if (!rc)
    rc = fb_scenario_add_mount(s, &engine, err);
  static const double gx[] = {-2.00, -1.70, -1.35, -1.00, -0.75, -0.45, -0.15,
                              0.10,  0.40,  0.65,  0.95,  1.30,  1.90,  2.10};
  static const double gy[] = {-1.05, -0.55, 0.55, 1.05};
  for (size_t i = 0; !rc && i < sizeof gx / sizeof gx[0]; ++i)
    for (size_t j = 0; !rc && j < sizeof gy / sizeof gy[0]; ++j)
      rc = fb_scenario_add_load_point(s, gx[i], gy[j], err);
  s->total_weight = 117720;
  s->payload = FB_PAYLOAD_WEIGHT_ONLY;
  return rc;
}

static int add_outputs(fb_scenario *s, fb_err *err)
{
  const fb_output_spec out[] = {
      {.signal = "tire_force", .of = "LF"},
      {.signal = "spring_defl", .of = "RF"},
      {.signal = "torsion"},
      {.signal = "acc", .of = "driver", .name = "driver_acc"},
      {.signal = "shock_power", .of = "LM"},
      {.signal = "tire_defl", .of = "RM"},
      {.signal = "tire_power", .of = "LR"},
  };
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < sizeof out / sizeof out[0]; ++i)
    rc = fb_scenario_add_output(s, &out[i], err);
  return rc;
}

/* The paper's vehicle and bump, from the data sheet. */
static fb_scenario *build_apc(fb_err *err)
{
  fb_scenario *s = NULL;
  int rc = fb_scenario_new("apc6x6", &s, err);
  if (rc)
    return NULL;
  s->gravity = 9.81;
  fb_scenario_set_rigid_hull(s, 4041.72, 4173.49, 15175.96);
  s->young = 200e9;
  s->poisson = 0.3;
  s->density = 7860;
  s->thickness = 0.0085;
  s->edge_front_x = 2.47813311938948;
  s->edge_rear_x = -2.65798412344113;
  s->edge_left_y = 1.05;
  s->edge_right_y = -1.05;
  rc = add_corners(s, err);
  if (!rc)
    rc = add_mounts_and_load(s, err);
  if (!rc)
    rc = add_outputs(s, err);
  s->speed = 10 / 3.6;
  fb_road_bump_params *bump = NULL;
  if (!rc)
    rc = fb_scenario_set_road(s, &fb_road_type_bump, (void **)&bump, err);
  if (!rc) {
    *bump = (fb_road_bump_params){.height = 0.10,
                                  .length = 3.70,
                                  .type = -1,
                                  .angle = 45 * (PI / 180),
                                  .first_contact = 5};
    rc = fb_scenario_prepare_road(s, err);
  }
  s->t_end = 15;
  s->rtol = 1e-6;
  s->atol = 1e-8;
  s->sample_rate = 1000;
  s->initial = FB_INITIAL_ZERO;
  if (rc)
    fb_scenario_free(&s);
  return s;
}

/* The same vehicle as the file's, so the same run: the same values give
 * the same model and CVODE takes the same steps, so the results agree to
 * the last digits (1e-12 of each output's range allows a different order
 * of the same sums; a different number anywhere in the vehicle moves
 * some output by far more). */
static void test_same_as_file(void)
{
  fb_err err;
  fb_scenario *built = build_apc(&err), *file = NULL;
  CHECK(built != NULL);
  if (!built)
    fprintf(stderr, "  %s\n", err.msg);
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &file, &err) == FB_OK);
  if (!built || !file) {
    fb_scenario_free(&built);
    fb_scenario_free(&file);
    return;
  }
  CHECK(fb_scenario_check(built, &err) == FB_OK);
  CHECK(built->ncorners == file->ncorners && built->noutputs == file->noutputs);
  for (size_t c = 0; c < built->ncorners && c < file->ncorners; ++c)
    CHECK(!strcmp(built->corner[c].name, file->corner[c].name));
  for (size_t o = 0; o < built->noutputs && o < file->noutputs; ++o)
    CHECK(!strcmp(built->output[o].name, file->output[o].name) &&
          !strcmp(built->output[o].unit, file->output[o].unit));
  fb_result *a = simulate_rigid(file), *b = simulate_rigid(built);
  if (a && b)
    check_close(a, b, 1e-12, "built vs file");
  fb_result_free(&a);
  fb_result_free(&b);
  fb_scenario_free(&built);
  fb_scenario_free(&file);
}

/* What a program leaves wrong is named in the description's words. */
static void test_refusals(void)
{
  fb_err err;
  fb_scenario *s = build_apc(&err);
  if (!s)
    return;
  const fb_corner_params nameless = {.spring_k = 1};
  CHECK(fb_scenario_add_corner(s, &nameless, &err) == FB_EINVAL && strstr(err.msg, "name"));
  const fb_output_spec unknown = {.signal = "tyre_force", .of = "LF"};
  CHECK(fb_scenario_add_output(s, &unknown, &err) == FB_EINVAL &&
        strstr(err.msg, "tyre_force"));
  const fb_output_spec nowhere = {.signal = "tire_force", .of = "XX"};
  CHECK(fb_scenario_add_output(s, &nowhere, &err) == FB_EINVAL && strstr(err.msg, "XX"));
  const fb_output_spec hull_of = {.signal = "torsion", .of = "LF"};
  CHECK(fb_scenario_add_output(s, &hull_of, &err) == FB_EINVAL);
  const fb_output_spec again = {.signal = "tire_force", .of = "LF"};
  CHECK(fb_scenario_add_output(s, &again, &err) == FB_EINVAL &&
        strstr(err.msg, "tire_force_LF"));
  CHECK(s->ncorners == 6 && s->noutputs == 7); /* refused: nothing added */
  s->corner[5].tire_k = -1;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL);
  char part[128];
  CHECK(
      !strcmp(fb_scenario_part_text(s, &err.part, part, sizeof part), "corner[5] (RR).tire_k"));
  fb_scenario_free(&s);
  /* A new description needs its parts before it can be checked. */
  CHECK(fb_scenario_new(NULL, &s, &err) == FB_OK);
  CHECK(s && fb_scenario_check(s, &err) == FB_EINVAL);
  fb_scenario_free(&s);
}

/* The description owns copies: the caller's arguments may go away, and
 * a copy of the description is a description of its own. */
static void test_ownership(void)
{
  fb_err err;
  fb_scenario *s = build_apc(&err);
  if (!s)
    return;
  char name[] = "XL";
  fb_corner_params c = s->corner[0];
  c.name = name;
  c.y = 3.0;
  CHECK(fb_scenario_add_corner(s, &c, &err) == FB_OK);
  name[0] = 'Q';
  CHECK(!strcmp(s->corner[6].name, "XL"));
  fb_scenario *copy = NULL;
  CHECK(fb_scenario_clone(s, &copy, &err) == FB_OK);
  fb_scenario_free(&s);
  CHECK(copy && copy->ncorners == 7 && !strcmp(copy->corner[6].name, "XL") &&
        !strcmp(copy->output[3].name, "driver_acc"));
  fb_scenario_free(&copy);
}

/* Column name of r, row k; NaN when r lacks it. */
static double value(const fb_result *r, const char *name, size_t k)
{
  const long col = fb_result_find(r, name);
  return col > 0 ? fb_result_row(r, k)[col] : NAN;
}

/* Every signal kind is measurable on the vehicle (System 1: a hull
 * stress, System 2's, in test_hull_stress_outputs.c): each corner kind by
 * the corner's fragment, each mount kind by the mount's, the hull's and the
 * bond kinds; and their values obey the fragments' laws: the tire force
 * is the tire bond's effort and the contact force, the spring force is
 * k times its deflection (linear springs: to rounding, 1e-9 of the
 * force), the shock absorber's power is its force times its rate, which
 * for the linear damper is force^2 / c (1e-9 of the power). */
static void test_every_signal(void)
{
  fb_err err;
  fb_scenario *s = build_apc(&err);
  if (!s)
    return;
  road_bump(s)->first_contact = 0.5; /* the whole crossing within 4 s */
  s->t_end = 4;
  /* LF offers every corner signal: stops too (far: never touched). */
  fb_stop_init(&s->corner[0].stops.bump);
  s->corner[0].stops.bump.given = 1;
  s->corner[0].stops.bump.gap = 0.5;
  s->corner[0].stops.bump.rate = 1e6;
  size_t nkinds = 0;
  const fb_output_kind *kinds = fb_vehicle_output_kinds(&nkinds);
  for (size_t k = 0; k < nkinds; ++k) {
    fb_output_spec o = {.signal = (char *)kinds[k].signal};
    if (kinds[k].subject == FB_OUTPUT_OF_BOGIE)
      continue;                                /* the APC has none: test_bogie.c */
    if (kinds[k].subject == FB_OUTPUT_OF_BODY) /* the APC has none: tests/test_body_vehicle.c */
      continue;
    if (kinds[k].subject == FB_OUTPUT_OF_HULL_STRESS)
      continue; /* System 1 has no shell elements: tests/test_hull_stress_outputs.c */
    if (kinds[k].subject == FB_OUTPUT_OF_CORNER)
      o.of = "LF";
    else if (kinds[k].subject == FB_OUTPUT_OF_MOUNT)
      o.of = "driver";
    else if (kinds[k].subject == FB_OUTPUT_OF_BOND)
      o.bond = "susp_LF.b_tire";
    const int rc = fb_scenario_add_output(s, &o, &err);
    CHECK(rc == FB_OK || strstr(err.msg, "name")); /* a name the paper's outputs took */
  }
  fb_result *r = simulate_rigid(s);
  for (size_t o = 0; r && o < s->noutputs; ++o) {
    const long col = fb_result_find(r, s->output[o].name);
    CHECK(col > 0);
    for (size_t k = 0; col > 0 && k < fb_result_nsamples(r); k += 100)
      CHECK(isfinite(fb_result_row(r, k)[col]));
  }
  const double k_s = s->corner[0].spring_k, c_d = du_damper_c(&s->corner[0]);
  for (size_t k = 0; r && k < fb_result_nsamples(r); k += 50) {
    const double tire = value(r, "tire_force_LF", k);
    CHECK(tire == value(r, "effort_susp_LF_b_tire", k) &&
          tire == value(r, "contact_force_LF", k));
    const double spring = value(r, "spring_force_LF", k);
    CHECK_NEAR(spring, k_s * value(r, "spring_defl_LF", k), 1e-9 * (1 + fabs(spring)));
    const double shock = value(r, "shock_force_LF", k), power = value(r, "shock_power_LF", k);
    CHECK_NEAR(power, shock * shock / c_d, 1e-9 * (1 + fabs(power)));
  }
  fb_result_free(&r);
  fb_scenario_free(&s);
}

int main(void)
{
  test_same_as_file();
  test_every_signal();
  test_refusals();
  test_ownership();
  return check_report("test_builder");
}
