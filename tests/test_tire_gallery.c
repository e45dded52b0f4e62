/* SPDX-License-Identifier: BSD-3-Clause */
/* The tire gallery (flexbond/tire.h): one conformance harness that runs
 * every model of a gallery through the same checks, and a tire model a
 * program adds at run time (a linear tire of scaled stiffness, the worked
 * example of docs/architecture.md), usable from a scenario file, per
 * corner too, with its errors located at its own keys. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/tire.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle_util.h"

/* ---- The scaled tire: a program's own model. */

typedef struct scaled_params {
  double k_scale; /* the spring is k_scale tire_k */
} scaled_params;

static const fb_param scaled_param[] = {
    {.name = "k_scale",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(scaled_params, k_scale),
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_DEFAULT,
     .def = 1.0,
     .doc = "the tire spring's stiffness over `tire_k`"},
};

/* A rule between its value and the corner's the range cannot state. */
static int scaled_check(const void *params, const fb_tire_context *ctx, fb_err *err)
{
  const scaled_params *p = params;
  if (p->k_scale * ctx->tire_k <= 1e8)
    return FB_OK;
  return fb_err_set(err, FB_EINVAL, "a tire stiffer than 1e8 N/m (%g N/m)",
                    p->k_scale * ctx->tire_k),
         fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "k_scale"), FB_EINVAL;
}

/* The bilateral pair with a spring k_scale tire_k: the test's own
 * builder, from public calls only. */
static int scaled_build(const void *params, const fb_tire_context *ctx, fb_bg *bg, fb_err *err)
{
  const scaled_params *p = params;
  fb_tire_context scaled = *ctx;
  scaled.tire_k *= p->k_scale;
  return fb_tire_model_bilateral.ops->build(NULL, &scaled, bg, err);
}

static const fb_tire_model_ops scaled_ops = {.check = scaled_check, .build = scaled_build};

static const fb_tire_model scaled = {
    .name = "scaled",
    .doc = "the paper's linear tire, its spring scaled",
    .meaning = "linear, its spring k_scale times tire_k",
    .pulls = 1,
    .param = scaled_param,
    .nparams = sizeof scaled_param / sizeof scaled_param[0],
    .params_size = sizeof(scaled_params),
    .ops = &scaled_ops,
};

/* The table tire's example: the paper's tire as a table, a line of
 * slope tire_k = 500000 N/m through (0, 0). */
#define TIRE_TABLE_LINE "\n  tire_table: {points: [[0, 0], [0.1, 50000]]}"

/* ---- Loading the reference scenario with wheel keys of its own. */

/* The example with text after the top-level wheel's tire_c line, and
 * corner text after the front axle's damper_c line; the overrides ov. */
static int load_wheel(const char *wheel, const char *front, const fb_tire_gallery *g,
                      const fb_scenario_override *ov, size_t nov, fb_scenario **out,
                      fb_err *err)
{
  char *file = read_text("../examples/apc6x6.yaml");
  const char *tire = file ? strstr(file, "  tire_c: 140000") : NULL;
  const char *axle = tire ? strstr(tire, "      damper_c: 25744") : NULL;
  const char *tire_end = tire ? strchr(tire, '\n') : NULL;
  const char *axle_end = axle ? strchr(axle, '\n') : NULL;
  const size_t size = file ? strlen(file) + strlen(wheel) + strlen(front) + 1 : 0;
  char *yaml = axle_end ? malloc(size) : NULL;
  int rc = FB_EIO;
  if (yaml) {
    snprintf(yaml, size, "%.*s%s%.*s%s%s", (int)(tire_end - file), file, wheel,
             (int)(axle_end - tire_end), tire_end, front, axle_end);
    const fb_scenario_load_opts opts = {.tires = g, .overrides = ov, .noverrides = nov};
    rc = load_text_with(yaml, &opts, out, err);
  }
  free(yaml);
  free(file);
  return rc;
}

/* The shortened crossing of load_short (vehicle_util.h): its bump at
 * 1 s, 0.5 m long, 3 s in all, height m high. */
static void shorten(fb_scenario *s, double height)
{
  road_bump(s)->first_contact = 1.0;
  road_bump(s)->length = 0.5;
  road_bump(s)->height = height;
  s->t_end = 3.0;
}

/* The example at rest on a flat road, from its static equilibrium:
 * every tire in contact. */
static void at_rest(fb_scenario *s)
{
  shorten(s, 0.0);
  s->initial = FB_INITIAL_STATIC;
}

/* a and b on the shortened crossing of a bump height m high: every
 * output of b within tol of a's range (check_close); then both freed.
 * The pairs compared here build the same graph in two ways, so their
 * numbers are equal (0 measured): tol 1e-12 allows round-off only. */
static void compare_runs(fb_scenario **a, fb_scenario **b, double height, double tol,
                         const char *what)
{
  shorten(*a, height);
  shorten(*b, height);
  fb_result *ra = simulate_rigid(*a), *rb = simulate_rigid(*b);
  if (ra && rb)
    check_close(ra, rb, tol, what);
  fb_result_free(&ra);
  fb_result_free(&rb);
  fb_scenario_free(a);
  fb_scenario_free(b);
}

/* ---- The conformance harness. */

/* The sum of the tires' reactions at every sample equals the weight they
 * carry, load.total_weight plus every mounted body's and every wheel's
 * (closed form): at rest, a
 * tire model must carry the vehicle whatever its law. The static
 * equilibrium is solved directly and the run stays there: the sums agree
 * to round-off (2.3e-14 of the weight measured for each built-in model);
 * 1e-9 leaves room for a nonlinear model's Newton tolerance and is far
 * below a model that loses or invents load. */
static void check_weight_carried(const fb_tire_model *m, const fb_scenario *s)
{
  fb_result *r = simulate_rigid(s);
  if (!r)
    return;
  double weight = s->total_weight;
  for (size_t b = 0; b < s->nmounts; ++b)
    weight += s->mount[b].mass * s->gravity;
  for (size_t c = 0; c < s->ncorners; ++c)
    weight += s->corner[c].wheel_mass * s->gravity;
  double worst = 0.0;
  for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
    double sum = 0.0;
    for (size_t c = 0; c < s->ncorners; ++c) {
      char name[32];
      snprintf(name, sizeof name, "contact_force_%s", s->corner[c].name);
      const long col = fb_result_find(r, name);
      CHECK(col > 0);
      sum += col > 0 ? fb_result_row(r, k)[col] : 0.0;
    }
    worst = fmax(worst, fabs(sum - weight) / weight);
  }
  CHECK(worst < 1e-9);
  printf("  %s: the tires carry the weight (%.6g N) to %.3g of it\n", m->name, weight, worst);
  fb_result_free(&r);
}

/* Its two elements, built for a corner alone with the tire block of
 * the loaded example's corner from. */
static void check_built(const fb_tire_model *m, const fb_corner_params *from)
{
  fb_corner_params c = {.name = "X",
                        .spring_k = 1e5,
                        .motion_ratio = 1,
                        .wheel_mass = 100,
                        .tire_k = 5e5,
                        .tire_c = 1e4,
                        .tire_static_deflection = 0.04};
  fb_err err;
  CHECK(fb_corner_set_tire(&c, m, NULL, &err) == FB_OK);
  c.tire = from->tire;
  fb_bg *bg = NULL;
  CHECK(fb_vehicle_corner(&c, 9.81, &bg, &err) == FB_OK);
  CHECK(bg && fb_bg_find_element(bg, "tire_spring") >= 0 &&
        fb_bg_find_element(bg, "tire_damper") >= 0);
  fb_bg_free(&bg);
}

/* Every parameter's value outside its range, written at the top-level
 * wheel, is refused at that key. */
static void check_located(const fb_tire_model *m, const fb_tire_gallery *g)
{
  char wheel[128];
  snprintf(wheel, sizeof wheel, "\n  tire_contact: %s", m->name);
  for (size_t i = 0; i < m->nparams; ++i) {
    const fb_param *p = &m->param[i];
    if (!(p->range & FB_RANGE_LO))
      continue;
    char key[128], value[64];
    snprintf(key, sizeof key, "wheel.%s.%s", m->name, p->name);
    snprintf(value, sizeof value, "%.17g", p->range & FB_RANGE_LO_OPEN ? p->lo : p->lo - 1);
    const fb_scenario_override ov = {.key = key, .value = value};
    fb_err err;
    fb_scenario *s = NULL;
    CHECK(load_wheel(wheel, "", g, &ov, 1, &s, &err) != FB_OK && !s);
    check_refused_at(&err, key, value);
  }
}

static void check_model(const fb_tire_model *m, const fb_tire_gallery *g)
{
  fb_err err;
  CHECK(fb_tire_model_check(m, &err) == FB_OK);
  /* A linear analysis's model is a sound one that names no other. */
  CHECK(!m->in_contact ||
        (fb_tire_model_check(m->in_contact, &err) == FB_OK && !m->in_contact->in_contact));
  fb_tire_params p;
  fb_tire_params_init(m, &p);
  CHECK(fb_params_check(m->param, m->nparams, p.bytes, &err) == FB_OK);
  char wheel[192];
  snprintf(wheel, sizeof wheel, "\n  tire_contact: %s%s", m->name,
           m == &fb_tire_model_table ? TIRE_TABLE_LINE : "");
  fb_scenario *s = NULL;
  CHECK(load_wheel(wheel, "", g, NULL, 0, &s, &err) == FB_OK);
  if (!s) {
    fprintf(stderr, "  %s: %s\n", m->name, err.msg);
    return;
  }
  check_built(m, &s->corner[0]);
  for (size_t c = 0; c < s->ncorners; ++c)
    CHECK(fb_corner_tire_model(&s->corner[c]) == m);
  at_rest(s);
  check_weight_carried(m, s);
  fb_scenario_free(&s);
  check_located(m, g);
}

static void test_conformance(const fb_tire_gallery *g)
{
  CHECK(fb_tire_gallery_count(g) >= 5);
  for (size_t i = 0; i < fb_tire_gallery_count(g); ++i)
    check_model(fb_tire_gallery_at(g, i), g);
}

/* ---- The scaled tire from a program and a file. */

static void test_registration(fb_tire_gallery *g)
{
  fb_err err;
  /* Unknown to a gallery without it, at its key. */
  CHECK(load_wheel("\n  tire_contact: scaled", "", NULL, NULL, 0, NULL, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "bad.yaml:90:17: wheel.tire_contact: unknown value 'scaled'"));
  CHECK(fb_tire_gallery_add(g, &scaled, &err) == FB_OK);
  CHECK(fb_tire_gallery_add(g, &scaled, &err) == FB_EINVAL && strstr(err.msg, "already"));
  CHECK(fb_tire_gallery_find(g, "scaled") == &scaled);
  /* Unsound models are refused. */
  static const fb_tire_model_ops no_build = {.check = scaled_check};
  fb_tire_model bad = scaled;
  bad.name = "bad";
  bad.ops = &no_build;
  CHECK(fb_tire_gallery_add(g, &bad, &err) == FB_EINVAL && strstr(err.msg, "build"));
  bad.ops = &scaled_ops;
  bad.in_contact = &bad;
  CHECK(fb_tire_gallery_add(g, &bad, &err) == FB_EINVAL && strstr(err.msg, "in_contact"));
  bad.in_contact = NULL;
  bad.meaning = NULL;
  CHECK(fb_tire_gallery_add(g, &bad, &err) == FB_EINVAL && strstr(err.msg, "undocumented"));
}

/* The top level's value for every corner, the front axle's its own. */
static void test_inheritance(const fb_tire_gallery *g)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(load_wheel("\n  tire_contact: scaled\n  scaled: {k_scale: 2}",
                   "\n      wheel: {scaled: {k_scale: 3}}", g, NULL, 0, &s, &err) == FB_OK);
  if (!s) {
    fprintf(stderr, "  %s\n", err.msg);
    return;
  }
  for (size_t c = 0; c < s->ncorners; ++c) {
    const scaled_params *p = (const void *)s->corner[c].tire.bytes;
    CHECK(fb_corner_tire_model(&s->corner[c]) == &scaled);
    CHECK(p->k_scale == (c < 2 ? 3.0 : 2.0));
  }
  fb_scenario_free(&s);
  /* A corner of its own model keeps the model's defaults. */
  CHECK(load_wheel("\n  tire_contact: scaled\n  scaled: {k_scale: 2}",
                   "\n      wheel: {tire_contact: bilateral}", g, NULL, 0, &s, &err) == FB_OK);
  if (s) {
    CHECK(fb_corner_tire_model(&s->corner[0]) == &fb_tire_model_bilateral);
    CHECK(fb_corner_tire_model(&s->corner[2]) == &scaled);
  }
  fb_scenario_free(&s);
}

/* Its errors at its keys: a declared range (top level, corner), a rule
 * of its own, another model's parameters in a corner. */
static void test_errors(const fb_tire_gallery *g)
{
  static const struct {
    const char *wheel, *front, *want;
  } bad[] = {
      {"\n  tire_contact: scaled\n  scaled: {k_scale: -1}", "",
       "bad.yaml:91:21: wheel.scaled.k_scale: must be > 0 (got -1)"},
      {"\n  tire_contact: scaled", "\n      wheel: {scaled: {k_scale: 0}}",
       "bad.yaml:101:33: suspensions.axles[0].wheel.scaled.k_scale: must be > 0 (got 0)"},
      {"\n  tire_contact: scaled\n  scaled: {k_scale: 300}", "",
       "bad.yaml:91:21: wheel.scaled.k_scale: a tire stiffer than 1e8 N/m (1.5e+08 N/m)"},
      {"\n  tire_contact: scaled", "\n      wheel: {hunt_crossley: {deflection_ref: 0.01}}",
       "bad.yaml:101:15: suspensions.axles[0].wheel.hunt_crossley: the parameters of a "
       "`hunt_crossley` tire, but this corner's tire is `scaled`"},
      {"\n  tire_contact: hunt_crossley\n  hunt_crossley: {deflection_ref: -0.01}", "",
       "bad.yaml:91:35: wheel.hunt_crossley.deflection_ref: must be > 0 m (got -0.01)"},
      {"\n  tire_contact: table", "",
       "bad.yaml:96:7: suspensions.axles[0]: missing required key 'wheel.tire_table': a "
       "`table` tire's force-deflection table, here or at the top-level wheel"},
      {"\n  tire_contact: table\n  tire_table: {points: [[0, 0], [0.1, 5000], [0.2, 4000]]}",
       "",
       "bad.yaml:91:15: wheel.tire_table: table law decreases: at point 3 phi(0.2) = 4000 "
       "is below point 2's 5000"},
      {"\n  tire_contact: table\n  tire_table: {points: [[0.01, 0], [0.1, 5000]]}", "",
       "bad.yaml:91:15: wheel.tire_table: corner 'LF': a tire table starts at (0, 0)"},
      {TIRE_TABLE_LINE, "",
       "bad.yaml:90:3: wheel.tire_table: no corner's tire is table (wheel.tire_contact "
       "chooses the tires): the table would reach none"},
      {"\n  tire_contact: table" TIRE_TABLE_LINE,
       "\n      wheel: {tire_contact: bilateral, tire_table: {points: [[0, 0], [1, 1]]}}",
       "bad.yaml:102:40: suspensions.axles[0].wheel.tire_table: the table of a `table` tire, "
       "but this corner's tire is `bilateral`"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    fb_err err;
    CHECK(load_wheel(bad[i].wheel, bad[i].front, g, NULL, 0, NULL, &err) != FB_OK);
    check_message(&err, bad[i].want);
  }
  /* The same rule from a program: the description's own words. */
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(load_wheel("\n  tire_contact: scaled", "", g, NULL, 0, &s, &err) == FB_OK);
  if (!s)
    return;
  ((scaled_params *)(void *)s->corner[3].tire.bytes)->k_scale = 400;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_TIRE &&
        err.part.index == 3 && !strcmp(err.part.field, "k_scale"));
  fb_scenario_free(&s);
}

/* The scaled tire at k_scale 2 is the paper's tire of twice its
 * stiffness: the same graph, so the same numbers (an independent path:
 * the built-in model with tire_k doubled). */
static void test_scaled_run(const fb_tire_gallery *g)
{
  fb_err err;
  fb_scenario *a = NULL, *b = NULL;
  CHECK(load_wheel("\n  tire_contact: scaled\n  scaled: {k_scale: 2}", "", g, NULL, 0, &a,
                   &err) == FB_OK);
  CHECK(load_wheel("", "", g, NULL, 0, &b, &err) == FB_OK);
  if (!a || !b) {
    fb_scenario_free(&a);
    fb_scenario_free(&b);
    return;
  }
  for (size_t c = 0; c < b->ncorners; ++c)
    b->corner[c].tire_k *= 2;
  compare_runs(&b, &a, 0.1, 1e-12, "scaled tire vs a stiffer bilateral one");
}

/* A Hunt-Crossley tire given the static deflection as its reference is
 * the one that defaults to it: the same numbers. */
static void test_hunt_crossley_reference(const fb_tire_gallery *g)
{
  fb_err err;
  fb_scenario *a = NULL, *b = NULL;
  CHECK(load_wheel("\n  tire_contact: hunt_crossley", "", g, NULL, 0, &a, &err) == FB_OK);
  if (!a)
    return;
  double weight = a->total_weight;
  for (size_t c = 0; c < a->ncorners; ++c)
    weight += a->corner[c].wheel_mass * a->gravity;
  const double ref = weight / (double)a->ncorners / a->corner[0].tire_k;
  CHECK(fabs(ref - 0.0427) < 5e-5); /* docs/scenario-format.md: 0.0427 m for the APC */
  char wheel[160];
  snprintf(wheel, sizeof wheel,
           "\n  tire_contact: hunt_crossley\n  hunt_crossley: {deflection_ref: %.17g}", ref);
  CHECK(load_wheel(wheel, "", g, NULL, 0, &b, &err) == FB_OK);
  if (b) {
    const fb_tire_hunt_crossley_params *p = (const void *)b->corner[0].tire.bytes;
    CHECK(p->deflection_ref == ref);
    compare_runs(&a, &b, 0.2, 1e-12, "Hunt-Crossley at its default reference vs given");
  }
  fb_scenario_free(&a);
  fb_scenario_free(&b);
}

/* The table tire whose table is the line tire_k x (TIRE_TABLE_LINE)
 * against the unilateral tire of that rate, on a bump high enough (0.3
 * m) for wheels to leave the road and land again: the same forces on
 * both sides of every event. The two build different laws (a tabulated
 * one, not marked affine, against the affine pair), so the integrator's
 * Newton matrices and steps differ and the runs agree to its tolerances,
 * not to round-off: 4.2e-8 of a signal's range measured at
 * simulate_rigid's rtol 1e-6; 1e-6 of it is rtol's own size, and fails a
 * table whose rate is off by 0.1 %. */
static void test_table_as_line(const fb_tire_gallery *g)
{
  fb_err err;
  fb_scenario *a = NULL, *b = NULL;
  CHECK(load_wheel("\n  tire_contact: unilateral", "", g, NULL, 0, &a, &err) == FB_OK);
  CHECK(load_wheel("\n  tire_contact: table" TIRE_TABLE_LINE, "", g, NULL, 0, &b, &err) ==
        FB_OK);
  if (a && b) {
    const fb_tire_table_params *p = (const void *)b->corner[0].tire.bytes;
    CHECK(p->npoints == 2 && p->force[1] / p->deflection[1] == a->corner[0].tire_k);
    compare_runs(&a, &b, 0.3, 1e-6, "table tire as a line vs unilateral");
  }
  fb_scenario_free(&a);
  fb_scenario_free(&b);
}

int main(void)
{
  fb_err err;
  fb_tire_gallery *g = NULL;
  CHECK(fb_tire_gallery_new(&g, &err) == FB_OK);
  if (!g)
    return check_report("test_tire_gallery");
  CHECK(fb_tire_gallery_count(g) == 4);
  CHECK(fb_tire_gallery_at(g, 0) == &fb_tire_model_bilateral);
  test_registration(g);
  test_conformance(g);
  test_inheritance(g);
  test_errors(g);
  test_scaled_run(g);
  test_hunt_crossley_reference(g);
  test_table_as_line(g);
  fb_tire_gallery_free(&g);
  return check_report("test_tire_gallery");
}
