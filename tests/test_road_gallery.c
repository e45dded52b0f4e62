/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery (flexbond/road.h): one conformance harness that runs
 * every type of a gallery through the same checks, and a road type a
 * program adds at run time (a plank across the road, the worked example
 * of docs/architecture.md), usable from a scenario file with its errors
 * located at its own keys. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/road.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "tmpdir.h"
#include "vehicle_util.h"

/* ---- The plank: a program's own road type. */

typedef struct plank_params {
  double height; /* m */
  double length; /* m, of its flat top */
  double ramp;   /* m, of each ramp */
  double ahead;  /* m, from the first corner's wheel to the plank at t = 0 */
} plank_params;

static const fb_param plank_param[] = {
    {.name = "height",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(plank_params, height),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "the plank's height",
     .plausible_hi = 0.5,
     .plausible_why = "a plank on a road is at most about 0.5 m high"},
    {.name = "length",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(plank_params, length),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "the length of its flat top along the tracks"},
    {.name = "ramp",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(plank_params, ramp),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_DEFAULT,
     .def = 0.05,
     .doc = "the length of each ramp, up and down"},
    {.name = "ahead",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(plank_params, ahead),
     .unit = "m",
     .range = FB_RANGE_LO,
     .need = FB_PARAM_DEFAULT,
     .def = 1.0,
     .doc = "the first corner's wheel's distance to the plank at t = 0"},
};

/* A rule the declared ranges cannot state. */
static int plank_check(const void *params, const fb_road_layout *l, fb_err *err)
{
  (void)l;
  const plank_params *p = params;
  if (p->ramp <= p->length)
    return FB_OK;
  return fb_err_set(err, FB_EINVAL, "a ramp (%g m) longer than the plank's top (%g m)", p->ramp,
                    p->length),
         fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "ramp"), FB_EINVAL;
}

/* The knots of the plank on either track: up, across, down. */
static void plank_knots(const plank_params *p, double s[4], double z[4])
{
  const double knot_s[4] = {0.0, p->ramp, p->ramp + p->length, 2 * p->ramp + p->length};
  const double knot_z[4] = {0.0, p->height, p->height, 0.0};
  memcpy(s, knot_s, sizeof knot_s);
  memcpy(z, knot_z, sizeof knot_z);
}

static int plank_make(const void *params, const fb_road_layout *l, fb_road **out, fb_err *err)
{
  (void)l;
  double s[4], z[4];
  plank_knots(params, s, z);
  return fb_road_new_profile(4, s, z, z, out, err);
}

static double plank_wheel_start(const void *params, const fb_road_layout *l, double x, double y)
{
  (void)y;
  return -((const plank_params *)params)->ahead + (x - l->first_x);
}

static void plank_feature(const void *params, const fb_road_layout *l, int track, double *begin,
                          double *end)
{
  (void)l, (void)track;
  const plank_params *p = params;
  *begin = 0.0;
  *end = 2 * p->ramp + p->length;
}

static const fb_road_type_ops plank_ops = {.check = plank_check,
                                           .make = plank_make,
                                           .wheel_start = plank_wheel_start,
                                           .feature = plank_feature};

static const fb_road_type plank = {.name = "plank",
                                   .doc = "a plank across both tracks",
                                   .param = plank_param,
                                   .nparams = sizeof plank_param / sizeof plank_param[0],
                                   .params_size = sizeof(plank_params),
                                   .ops = &plank_ops};

/* ---- Loading a road section into the reference scenario. */

static int load_road(const char *road, const fb_road_gallery *g, const fb_scenario_override *ov,
                     size_t nov, fb_scenario **out, fb_err *err)
{
  const fb_scenario_load_opts opts = {.roads = g, .overrides = ov, .noverrides = nov};
  return load_replaced_with("\nroad:\n", 1, "\nsimulation:\n", road, &opts, out, err);
}

/* An example of each type of the gallery, as a file gives it: the
 * harness refuses a type without one. */
typedef struct example {
  const char *type;
  char road[512];
} example;

static void make_examples(example *ex, size_t *n)
{
  char csv[TEST_PATH_MAX];
  test_tmp_path("profile.csv", csv, sizeof csv);
  FILE *fp = fopen(csv, "w");
  CHECK(fp != NULL);
  if (fp) {
    fprintf(fp, "s,z\n0,0\n1,0.05\n2,0.02\n3,0.08\n4,0\n");
    fclose(fp);
  }
  static const char head[] = "road:\n  speed_kmh: 10\n";
  size_t k = 0;
  ex[k].type = "bump";
  snprintf(ex[k++].road, sizeof ex[0].road,
           "%s  bump:\n    height: 0.1\n    length: 3.7\n    angle_deg: 45\n"
           "    first_contact: 5\n",
           head);
  ex[k].type = "iso8608";
  snprintf(ex[k++].road, sizeof ex[0].road, "%s  iso8608:\n    class: C\n    seed: 7\n", head);
  ex[k].type = "profile";
  snprintf(ex[k++].road, sizeof ex[0].road, "%s  profile:\n    file: %s\n    front_start: -2\n",
           head, csv);
  /* The obstacles: on both tracks or one, oblique or square, one or a
   * series, within the [0, 5] m the slope is checked over. */
  static const struct {
    const char *type, *values;
  } obstacles[] = {
      {"halfround", "height: 0.2, angle_deg: 30, track: left"},
      {"step", "height: 0.1, ramp_length: 0.2, count: 2, spacing: 1.5"},
      {"cleat", "height: 0.05, length: 0.3, edge_radius: 0.01, angle_deg: 45"},
      {"trapezoid", "height: 0.1, top_length: 0.5, ramp_length: 0.3, track: right"},
      {"pothole", "depth: 0.08, length: 0.6, count: 3, spacing: 1"},
      {"washboard", "amplitude: 0.02, wavelength: 0.7, waves: 3, angle_deg: 10"},
  };
  for (size_t i = 0; i < sizeof obstacles / sizeof obstacles[0]; ++i) {
    /* Block style, one key a line, as check_located adds one. */
    char values[256];
    size_t at = 0;
    for (const char *v = obstacles[i].values; *v && at + 8 < sizeof values; ++v)
      at += *v == ',' ? (size_t)snprintf(values + at, sizeof values - at, "\n   ")
                      : (size_t)snprintf(values + at, sizeof values - at, "%c", *v);
    ex[k].type = obstacles[i].type;
    snprintf(ex[k++].road, sizeof ex[0].road, "%s  %s:\n    %s\n    first_contact: 5\n", head,
             obstacles[i].type, values);
  }
  char course[TEST_PATH_MAX];
  test_tmp_path("course.txt", course, sizeof course);
  fp = fopen(course, "w");
  CHECK(fp != NULL);
  if (fp) {
    fprintf(fp, "# type at parameters\nhalfround at=0 height=0.1 track=left\n"
                "step at=1 height=-0.05 ramp_length=0.3 track=right\n"
                "pothole at=2 depth=0.05 length=0.4\n");
    fclose(fp);
  }
  ex[k].type = "course";
  snprintf(ex[k++].road, sizeof ex[0].road,
           "%s  course:\n    file: %s\n    angle_deg: 20\n    first_contact: 5\n", head,
           course);
  char crg[TEST_PATH_MAX];
  test_tmp_path("surface.crg", crg, sizeof crg);
  fp = fopen(crg, "w");
  CHECK(fp != NULL);
  if (fp) { /* 6 cross sections 1 m apart, 3 long sections 1 m apart */
    fprintf(fp, "$CT\nconformance example\n$ROAD_CRG\nREFERENCE_LINE_INCREMENT = 1.0\n"
                "LONG_SECTION_V_INCREMENT = 1.0\n$\n$KD_DEFINITION\n#:LRFI\n"
                "D:long section 1,m\nD:long section 2,m\nD:long section 3,m\n$\n$$$$\n");
    for (int i = 0; i < 6; ++i)
      fprintf(fp, "%10.7f%10.7f%10.7f\n", 0.01 * (i % 3), 0.02 * (i % 2), 0.005 * i);
    fclose(fp);
  }
  ex[k].type = "crg";
  snprintf(ex[k++].road, sizeof ex[0].road, "%s  crg:\n    file: %s\n    front_start: -2\n",
           head, crg);
  ex[k].type = "plank";
  snprintf(ex[k++].road, sizeof ex[0].road, "%s  plank:\n    height: 0.1\n    length: 1.0\n",
           head);
  *n = k;
}

/* ---- The conformance harness: every type, the same checks. */

/* A fresh block holds the declared defaults. */
static void check_defaults(const fb_road_type *t)
{
  fb_road_params p;
  fb_road_params_init(t, &p);
  for (size_t i = 0; i < t->nparams; ++i) {
    const fb_param *d = &t->param[i];
    if (d->need != FB_PARAM_DEFAULT || d->store != FB_PARAM_DOUBLE)
      continue;
    const double *v = (const double *)(const void *)(p.bytes + d->offset);
    const double scale = d->scale != 0 ? d->scale : 1.0;
    for (size_t e = 0; e < (d->kind == FB_PARAM_REALS ? d->count : 1); ++e)
      CHECK(v[e] == (d->kind == FB_PARAM_REALS ? d->def_list[e] : d->def) * scale);
  }
  fb_road_params_release(t, &p);
}

/* The road's slope is its height's derivative: between two breaks
 * (fb_road_breaks: where the second derivative jumps, and where an
 * obstacle's pieces meet, its height perhaps jumping) its integral is the
 * height's change from the first to just before the second (one ulp
 * before: the left limit). The integral is two-point Gauss-Legendre
 * after s = a + (b - a)(1 - cos th) / 2, th in [0, pi], on 1e-3 rad
 * steps: ds = (b - a) sin th / 2 cancels the 1 / sqrt(distance) of an
 * arc's slope at a vertical tangent (a half-round's base), leaving a
 * smooth integrand, for which the rule errs by O(h^4); a step across an
 * interior knot of a PCHIP profile (where z'' jumps) errs by some
 * h^3 |jump z''| < 1e-9 m for these roads, and the left limit one ulp
 * short of an arc's vertical tangent by sqrt(2 R ulp) < 1e-8 m. A slope
 * off by a factor or a sign misses by the height change itself (some
 * 0.05 m). */
static double slope_integral(const fb_road *road, int track, double a, double b)
{
  const double g = 0.5 / sqrt(3.0), pi = 3.14159265358979323846;
  const int n = (int)ceil(pi / 1e-3);
  const double h = pi / n, half = 0.5 * (b - a);
  double sum = 0.0;
  for (int k = 0; k < n; ++k)
    for (int side = -1; side <= 1; side += 2) {
      const double th = (k + 0.5 + side * g) * h;
      sum += 0.5 * h * fb_road_slope(road, track, a + half * (1.0 - cos(th))) * half * sin(th);
    }
  return sum;
}

static void check_slope(const fb_road *road, const char *type)
{
  enum { MAX_BREAKS = 64 };
  for (int track = 0; track < FB_ROAD_NTRACKS; ++track) {
    double cut[MAX_BREAKS + 2] = {0.0};
    size_t n = 1;
    double br[MAX_BREAKS];
    const size_t nb = fb_road_breaks(road, track, br, MAX_BREAKS);
    for (size_t i = 0; i < nb && i < MAX_BREAKS; ++i)
      if (br[i] > cut[n - 1] && br[i] < 5.0)
        cut[n++] = br[i];
    cut[n++] = 5.0;
    for (size_t i = 0; i + 1 < n; ++i) {
      const double integral = slope_integral(road, track, cut[i], cut[i + 1]);
      const double change = fb_road_height(road, track, nextafter(cut[i + 1], -INFINITY)) -
                            fb_road_height(road, track, cut[i]);
      CHECK_NEAR(integral, change, 1e-8);
      if (fabs(integral - change) > 1e-8)
        fprintf(stderr,
                "  %s track %d on [%g, %g]: integral of the slope %g, height change %g\n", type,
                track, cut[i], cut[i + 1], integral, change);
    }
  }
}

/* Wheels of one side follow one track, those behind by their spacing;
 * each wheel function has its model-file form. */
static void check_wheels(const fb_scenario *s, const fb_road *road)
{
  fb_err err;
  for (int c = 0; c < (int)s->ncorners; ++c) {
    const int track = s->corner[c].y > 0 ? FB_ROAD_LEFT : FB_ROAD_RIGHT;
    int lead = 0;
    while (lead < c && (s->corner[lead].y > 0) != (track == FB_ROAD_LEFT))
      ++lead;
    CHECK_NEAR(fb_scenario_wheel_start(s, c) - fb_scenario_wheel_start(s, lead),
               s->corner[c].x - s->corner[lead].x, 1e-12);
    CHECK(fb_scenario_road_entry(s, c) <= fb_scenario_road_exit(s, c));
    fb_tfun *f = NULL, *g = NULL;
    CHECK(fb_road_wheel_height(road, track, s->speed, fb_scenario_wheel_start(s, c), &f,
                               &err) == FB_OK);
    fb_road_wheel_info info;
    CHECK(f && fb_road_wheel_describe(f, &info) == 1);
    CHECK(f && fb_road_wheel_new(&info, &g, &err) == FB_OK);
    for (double t = 0; f && g && t < 10; t += 0.37)
      CHECK(fb_tfun_eval(f, t) == fb_tfun_eval(g, t));
    fb_tfun_free(&f);
    fb_tfun_free(&g);
  }
}

/* A copy holds a road of its own, the same. */
static void check_clone(const fb_scenario *s, const fb_road *road)
{
  fb_err err;
  fb_scenario *copy = NULL;
  CHECK(fb_scenario_clone(s, &copy, &err) == FB_OK);
  fb_road *again = NULL;
  const fb_road_layout l = fb_scenario_road_layout(s);
  CHECK(copy && copy->road_type == s->road_type &&
        copy->road_type->ops->make(copy->road.bytes, &l, &again, &err) == FB_OK);
  for (double x = -3; again && x < 20; x += 0.29)
    for (int track = 0; track < FB_ROAD_NTRACKS; ++track)
      CHECK(fb_road_height(again, track, x) == fb_road_height(road, track, x));
  fb_road_free(&again);
  fb_scenario_free(&copy);
  CHECK(fb_scenario_check(s, &err) == FB_OK); /* the original's block is still its own */
}

/* A value outside parameter d's declared range, as text; NULL for a
 * parameter any value suits. */
static const char *outside(const fb_param *d, char *buf, size_t size)
{
  switch (d->kind) {
  case FB_PARAM_CHOICE: return "no_such_choice";
  case FB_PARAM_FILE: return "no_such_file.csv";
  case FB_PARAM_REALS: snprintf(buf, size, "[-1, -2]"); return d->range ? buf : NULL;
  default: break;
  }
  if (d->range & FB_RANGE_LO)
    snprintf(buf, size, "%.17g", (d->range & FB_RANGE_LO_OPEN) ? d->lo : d->lo - 1);
  else if (d->range & FB_RANGE_HI)
    snprintf(buf, size, "%.17g", (d->range & FB_RANGE_HI_OPEN) ? d->hi : d->hi + 1);
  else
    return NULL;
  return buf;
}

/* Each parameter's bad value is refused at its key, and an unknown key
 * of the type's section at that key. */
static void check_located(const fb_road_type *t, const example *ex, const fb_road_gallery *g)
{
  for (size_t i = 0; i < t->nparams; ++i) {
    char value[64], key[128], want[160];
    if (!outside(&t->param[i], value, sizeof value))
      continue;
    snprintf(key, sizeof key, "road.%s.%s", t->name, t->param[i].name);
    const fb_scenario_override ov = {.key = key, .value = value};
    fb_err err;
    fb_scenario *s = NULL;
    CHECK(load_road(ex->road, g, &ov, 1, &s, &err) != FB_OK && !s);
    snprintf(want, sizeof want, ": %s: ", key);
    const int located = strstr(err.msg, want) && strstr(err.msg, "bad.yaml:") && err.line > 0;
    CHECK(located);
    if (!located)
      fprintf(stderr, "  %s=%s: %s\n", key, value, err.msg);
  }
  char road[600], want[64];
  snprintf(road, sizeof road, "%s    no_such_key: 1\n", ex->road);
  snprintf(want, sizeof want, "road.%s.no_such_key: unknown key", t->name);
  fb_err err;
  CHECK(load_road(road, g, NULL, 0, NULL, &err) == FB_EPARSE && strstr(err.msg, want));
}

static void check_type(const fb_road_type *t, const example *ex, const fb_road_gallery *g)
{
  fb_err err;
  CHECK(fb_road_type_check(t, &err) == FB_OK);
  check_defaults(t);
  fb_scenario *s = NULL;
  CHECK(load_road(ex->road, g, NULL, 0, &s, &err) == FB_OK);
  if (!s) {
    fprintf(stderr, "  %s: %s\n", t->name, err.msg);
    return;
  }
  CHECK(s->road_type == t && fb_scenario_check(s, &err) == FB_OK);
  fb_road *road = NULL;
  const fb_road_layout l = fb_scenario_road_layout(s);
  CHECK(t->ops->make(s->road.bytes, &l, &road, &err) == FB_OK);
  if (road) {
    check_slope(road, t->name);
    check_wheels(s, road);
    check_clone(s, road);
  }
  CHECK(isfinite(fb_hull_excitation_hz(s)) && fb_hull_excitation_hz(s) > 0);
  fb_road_free(&road);
  fb_scenario_free(&s);
  check_located(t, ex, g);
}

static void test_conformance(const fb_road_gallery *g)
{
  example ex[16];
  size_t nex = 0;
  make_examples(ex, &nex);
  for (size_t i = 0; i < fb_road_gallery_count(g); ++i) {
    const fb_road_type *t = fb_road_gallery_at(g, i);
    const example *e = NULL;
    for (size_t k = 0; k < nex; ++k)
      if (!strcmp(ex[k].type, t->name))
        e = &ex[k];
    CHECK(e != NULL); /* every type has an example here */
    if (e)
      check_type(t, e, g);
  }
}

/* ---- The plank, registered at run time. */

static void test_registration(fb_road_gallery *g)
{
  fb_err err;
  CHECK(fb_road_gallery_find(g, "plank") == NULL);
  /* Not yet known: the file's plank is an unknown key. */
  CHECK(load_road("road:\n  speed_kmh: 10\n  plank: {height: 0.1, length: 1}\n", g, NULL, 0,
                  NULL, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "bad.yaml:") && strstr(err.msg, "road.plank: unknown key"));
  CHECK(fb_road_gallery_add(g, &plank, &err) == FB_OK);
  CHECK(fb_road_gallery_find(g, "plank") == &plank);
  CHECK(fb_road_gallery_add(g, &plank, &err) == FB_EINVAL && strstr(err.msg, "already"));
  /* A type that cannot make its road is refused. */
  static const fb_road_type_ops no_make = {.wheel_start = plank_wheel_start};
  const fb_road_type broken = {.name = "broken",
                               .doc = "no road",
                               .param = plank_param,
                               .nparams = 1,
                               .params_size = sizeof(plank_params),
                               .ops = &no_make};
  CHECK(fb_road_gallery_add(g, &broken, &err) == FB_EINVAL && strstr(err.msg, "make"));
  /* Nor a parameter stored outside its block. */
  const fb_road_type spills = {.name = "spills",
                               .doc = "too small a block",
                               .param = plank_param,
                               .nparams = 4,
                               .params_size = sizeof(double),
                               .ops = &plank_ops};
  CHECK(fb_road_gallery_add(g, &spills, &err) == FB_EINVAL &&
        !strcmp(err.part.field, "length"));
}

/* Its errors, at its keys: a declared range, a rule of its own (found by
 * fb_scenario_check, after reading), a missing value. */
static void test_plank_errors(const fb_road_gallery *g)
{
  static const struct {
    const char *road, *want;
  } bad[] = {
      {"  plank:\n    height: -0.1\n    length: 1\n",
       "bad.yaml:154:13: road.plank.height: must be > 0 m (got -0.1)"},
      {"  plank:\n    height: 0.1\n    length: 0.2\n    ramp: 0.5\n",
       "bad.yaml:156:11: road.plank.ramp: a ramp (0.5 m) longer than the plank's top (0.2 m)"},
      {"  plank:\n    height: 0.1\n", "bad.yaml:154:5: road.plank: missing required key "
                                      "'length'"},
      {"  plank:\n    height: 0.1\n    length: 1\n    ahead: -2\n",
       "bad.yaml:156:12: road.plank.ahead: must be >= 0 m (got -2)"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    char road[256];
    snprintf(road, sizeof road, "road:\n  speed_kmh: 10\n%s", bad[i].road);
    fb_err err;
    CHECK(load_road(road, g, NULL, 0, NULL, &err) != FB_OK);
    CHECK(strstr(err.msg, bad[i].want) != NULL);
    if (!strstr(err.msg, bad[i].want))
      fprintf(stderr, "  want %s\n  got  %s\n", bad[i].want, err.msg);
  }
  /* The same value from a program: the description's own words. */
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(load_road("road:\n  speed_kmh: 10\n  plank: {height: 0.1, length: 1}\n", g, NULL, 0, &s,
                  &err) == FB_OK);
  if (!s)
    return;
  plank_params *p = (plank_params *)(void *)s->road.bytes;
  p->ramp = 2.0;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL);
  char part[128];
  CHECK(err.part.kind == FB_PART_ROAD &&
        !strcmp(fb_scenario_part_text(s, &err.part, part, sizeof part), "road (plank).ramp"));
  fb_scenario_free(&s);
}

/* The plank's heights are the trapezoid's: PCHIP through its knots keeps
 * the flat top flat (Fritsch & Carlson's slopes are 0 where the data
 * turn) and every piece monotone, so the road is 0 before and after, h on
 * the top (to the rounding of the Hermite basis, whose two value weights
 * sum to 1 within a few ulp) and within [0, h] on the ramps. */
static void test_plank_road(const fb_road_gallery *g)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(load_road("road:\n  speed_kmh: 10\n  plank: {height: 0.1, length: 1, ramp: 0.2}\n", g,
                  NULL, 0, &s, &err) == FB_OK);
  if (!s)
    return;
  fb_road *road = NULL;
  const fb_road_layout l = fb_scenario_road_layout(s);
  CHECK(plank.ops->make(s->road.bytes, &l, &road, &err) == FB_OK);
  for (double x = -1; road && x < 3; x += 0.01) {
    const double z = fb_road_height(road, FB_ROAD_LEFT, x);
    if (x <= 0 || x >= 1.4)
      CHECK(z == 0);
    else if (x >= 0.2 && x <= 1.2)
      CHECK_NEAR(z, 0.1, 1e-15);
    else
      CHECK(z >= 0 && z <= 0.1);
    CHECK(z == fb_road_height(road, FB_ROAD_RIGHT, x));
  }
  fb_road_free(&road);
  /* The first wheel reaches the plank `ahead` (1 m) away at 1 / V. */
  CHECK_NEAR(fb_scenario_road_entry(s, 0), 1.0 / s->speed, 1e-12);
  fb_scenario_free(&s);
}

/* A run over the plank is a run over the same knots as a measured
 * profile: the same road from the same primitive, through the gallery's
 * path rather than the file's. The two place the wheels with different
 * roundings ((x - x_0) - 1 against (-1 - x_0) + x, 1e-16 m apart), so
 * their breakpoints differ by as much and CVODE's steps part ways: the
 * results agree to the solver's tolerance, not to the last digit
 * (measured 3.6e-6 of a range at most; 1e-4 of each range is the bound
 * the regression test justifies for the same model under other
 * roundings, tests/cli_regression.sh). A plank 1 cm higher moves the
 * tire forces by some 10 %. */
static void test_plank_run(const fb_road_gallery *g)
{
  char csv[TEST_PATH_MAX], road[512];
  test_tmp_path("plank.csv", csv, sizeof csv);
  FILE *fp = fopen(csv, "w");
  CHECK(fp != NULL);
  if (!fp)
    return;
  fprintf(fp, "s,z\n0,0\n0.05,0.08\n0.85,0.08\n0.9,0\n");
  fclose(fp);
  fb_err err;
  fb_scenario *a = NULL, *b = NULL;
  const fb_scenario_override t_end = {.key = "simulation.t_end", .value = "4"};
  CHECK(load_road("road:\n  speed_kmh: 10\n  plank: {height: 0.08, length: 0.8}\n", g, &t_end,
                  1, &a, &err) == FB_OK);
  snprintf(road, sizeof road,
           "road:\n  speed_kmh: 10\n  profile: {file: %s, front_start: -1}\n", csv);
  CHECK(load_road(road, g, &t_end, 1, &b, &err) == FB_OK);
  fb_result *ra = a ? simulate_rigid(a) : NULL, *rb = b ? simulate_rigid(b) : NULL;
  if (ra && rb)
    check_close(ra, rb, 1e-4, "plank vs profile");
  /* The plank lifts the first wheel's tire force while it is on it. */
  const long col = ra ? fb_result_find(ra, "tire_force_LF") : -1;
  double lo = INFINITY, hi = -INFINITY;
  for (size_t k = 0; col > 0 && k < fb_result_nsamples(ra); ++k) {
    lo = fmin(lo, fb_result_row(ra, k)[col]);
    hi = fmax(hi, fb_result_row(ra, k)[col]);
  }
  CHECK(col > 0 && hi - lo > 1e3); /* N: a 8 cm step under a wheel of some 30 kN */
  fb_result_free(&ra);
  fb_result_free(&rb);
  fb_scenario_free(&a);
  fb_scenario_free(&b);
}

int main(void)
{
  fb_err err;
  fb_road_gallery *g = NULL;
  CHECK(fb_road_gallery_new(&g, &err) == FB_OK);
  if (!g)
    return check_report("test_road_gallery");
  CHECK(fb_road_gallery_count(g) == 11);
  test_registration(g);
  test_conformance(g);
  test_plank_errors(g);
  test_plank_road(g);
  test_plank_run(g);
  fb_road_gallery_free(&g);
  return check_report("test_road_gallery");
}
