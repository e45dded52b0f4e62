/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of scenario overrides (fb_scenario_load_overrides and friends in
 * flexbond/vehicle.h, the "--set KEY=VALUE" of flexbond sweep): values
 * replaced by dotted path, by a unique bare key name, in a list and
 * several on one line, read through the reader's own conversions
 * (km/h, degrees, expressions, choices); every other value untouched;
 * keys the file leaves out (defaults, optional keys, a section of their
 * own), set as if the file had them; and the errors: absent, unknown,
 * ambiguous and non-scalar keys, items beyond a list's, values the
 * reader rejects (with the "--set KEY=VALUE: " prefix, the override as
 * the error's source and the original value's FILE:LINE:COL, or its
 * section's), consequences of several values together, two overrides of
 * one value, and values that try to change the YAML structure. Expected
 * positions are found in the example's text here, independently of
 * libfyaml. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "check.h"
#include "damper_util.h"
#include "io/scenario_internal.h"
#include "road_util.h"
#include "vehicle_util.h"

#define EXAMPLE "../examples/apc6x6.yaml"

/* A value written as decimal text and read by strtod in both the file
 * and the override is the same double: exact comparisons. Derived values
 * (km/h to m/s, degrees to radians) are computed here by a different
 * formula than the reader's and agree to a few ulps: 1e-12 relative. */
#define TIGHT 1e-12

/* "LINE:COL" (1-based) of the first occurrence of needle in text, plus
 * offset bytes, into buf. */
static void position_of(const char *text, const char *needle, size_t offset, char *buf,
                        size_t size)
{
  const char *at = strstr(text, needle);
  if (!at) {
    snprintf(buf, size, "(%s not found)", needle);
    return;
  }
  at += offset;
  int line = 1;
  const char *line_start = text;
  for (const char *p = text; p < at; ++p)
    if (*p == '\n') {
      ++line;
      line_start = p + 1;
    }
  snprintf(buf, size, "%d:%d", line, (int)(at - line_start) + 1);
}

/* Loads EXAMPLE with the n overrides; returns the status, message in err. */
static int load(const fb_scenario_override *ov, size_t n, fb_scenario **s, fb_err *err)
{
  return fb_scenario_load_overrides(EXAMPLE, ov, n, s, err);
}

static void test_number_and_nested(void)
{
  fb_scenario *base = NULL, *s = NULL;
  fb_err err;
  CHECK(fb_scenario_load(EXAMPLE, &base, &err) == FB_OK);
  const fb_scenario_override ov[] = {
      {.key = "road.speed_kmh", .value = "20"},
      {.key = "suspensions.axles[0].spring_k", .value = "200000"},
      {.key = "angle_deg", .value = "30"},
      {.key = "hull.mesh.generator.bulkheads[1]", .value = "-2 * 0.5"},
      {.key = "simulation.initial", .value = "static"}};
  int rc = load(ov, sizeof ov / sizeof ov[0], &s, &err);
  CHECK(rc == FB_OK);
  if (rc != FB_OK || !base) {
    fprintf(stderr, "  %s\n", err.msg);
    fb_scenario_free(&base);
    return;
  }
  /* 20 km/h = 50/9 m/s; 30 deg = pi/6. */
  CHECK_NEAR(s->speed, 50.0 / 9.0, TIGHT * 50.0 / 9.0);
  CHECK(s->corner[0].spring_k == 200000 && s->corner[1].spring_k == 200000);
  CHECK_NEAR(road_bump(s)->angle, atan(1.0) * 4 / 6, TIGHT);
  CHECK(s->hull_mesh.bulkhead_x[1] == -1.0); /* the same wall: the mesh must still fit */
  CHECK(s->initial == FB_INITIAL_STATIC);
  /* The front axle's value is both its corners'; everything else as in
   * the file: the middle axle's springs. */
  CHECK(s->corner[2].spring_k == base->corner[2].spring_k);
  CHECK(s->corner[3].spring_k == 345550);
  CHECK(s->hull_mesh.bulkhead_x[0] == base->hull_mesh.bulkhead_x[0]);
  CHECK(s->hull_mesh.bulkhead_x[2] == base->hull_mesh.bulkhead_x[2]);
  CHECK(road_bump(s)->height == road_bump(base)->height && s->t_end == base->t_end);
  CHECK(s->nload == base->nload && s->load_x[55] == base->load_x[55]);
  CHECK(s->path && !strcmp(s->path, EXAMPLE));
  fb_scenario_free(&s);
  fb_scenario_free(&base);
}

/* A bare name, an expression, two items of one flow list on one line
 * (the second edit after the first shifts the text), and n = 0. */
static void test_name_expression_list(void)
{
  fb_scenario *s = NULL;
  fb_err err;
  const fb_scenario_override ov[] = {{.key = "speed_kmh", .value = "2 * 18"},
                                     {.key = "load.points.grid.x[1]", .value = "-1.75"},
                                     {.key = "load.points.grid.x[0]", .value = "-2.05"}};
  int rc = load(ov, sizeof ov / sizeof ov[0], &s, &err);
  CHECK(rc == FB_OK);
  if (rc == FB_OK) {
    CHECK_NEAR(s->speed, 10.0, TIGHT * 10); /* 36 km/h */
    /* x-major grid of 4 y values: point 4 i + j is (x[i], y[j]). */
    CHECK(s->load_x[0] == -2.05 && s->load_x[3] == -2.05);
    CHECK(s->load_x[4] == -1.75 && s->load_x[7] == -1.75);
    CHECK(s->load_x[8] == -1.35 && s->load_y[0] == -1.05);
  }
  fb_scenario_free(&s);
  rc = load(NULL, 0, &s, &err);
  CHECK(rc == FB_OK && s && fabs(s->speed - 10 / 3.6) < TIGHT);
  fb_scenario_free(&s);
}

/* A quoted value in the file is replaced with its quotes. */
static void test_quoted_original(const char *text)
{
  char *copy = malloc(strlen(text) + 8);
  const char *at = strstr(text, "speed_kmh: 10 ");
  CHECK(copy && at);
  if (!copy || !at) {
    free(copy);
    return;
  }
  size_t head = (size_t)(at - text) + strlen("speed_kmh: ");
  snprintf(copy, strlen(text) + 8, "%.*s'10'%s", (int)head, text, at + strlen("speed_kmh: 10"));
  fb_scenario *s = NULL;
  fb_err err;
  const fb_scenario_override ov = {.key = "speed_kmh", .value = "72"};
  int rc =
      fb_scenario_load_string_overrides(copy, strlen(copy), "quoted.yaml", &ov, 1, &s, &err);
  CHECK(rc == FB_OK && s && fabs(s->speed - 20.0) < TIGHT * 20); /* 72 km/h */
  if (rc != FB_OK)
    fprintf(stderr, "  %s\n", err.msg);
  fb_scenario_free(&s);
  free(copy);
}

/* The edited text loads as the file: its relative references (damper
 * tables next to it in examples/, while this test runs in tests/)
 * resolve from its directory, as with fb_scenario_load. */
static void test_relative_references(void)
{
  const char *path = "../examples/apc6x6_shock_table.yaml";
  fb_scenario *base = NULL, *s = NULL;
  fb_err err;
  const fb_scenario_override ov = {.key = "speed_kmh", .value = "20"};
  int rc = fb_scenario_load(path, &base, &err);
  CHECK(rc == FB_OK);
  rc = fb_scenario_load_overrides(path, &ov, 1, &s, &err);
  CHECK(rc == FB_OK);
  if (rc != FB_OK)
    fprintf(stderr, "  %s\n", err.msg);
  CHECK(s && base && fabs(s->speed - 50.0 / 9.0) < TIGHT * 50.0 / 9.0 &&
        du_damper_table(&s->corner[4]) && du_damper_table(&s->corner[4])->npoints > 1 &&
        du_damper_table(&s->corner[4])->npoints == du_damper_table(&base->corner[4])->npoints &&
        du_damper_table(&s->corner[4])->force[1] ==
            du_damper_table(&base->corner[4])->force[1]);
  fb_scenario_free(&s);
  fb_scenario_free(&base);
}

/* Loading must fail with code (0: any failure) and a message that
 * starts with prefix and contains every one of the NULL-terminated
 * parts. */
static void expect_error(const fb_scenario_override *ov, size_t n, int code, const char *prefix,
                         const char *const *parts)
{
  fb_scenario *s = NULL;
  fb_err err;
  int rc = load(ov, n, &s, &err);
  CHECK(rc != FB_OK && s == NULL);
  CHECK(code == 0 || rc == code);
  CHECK(err.code == rc);
  int ok = !strncmp(err.msg, prefix, strlen(prefix));
  for (size_t i = 0; parts[i]; ++i)
    ok = ok && strstr(err.msg, parts[i]) != NULL;
  CHECK(ok);
  if (!ok || rc == FB_OK)
    fprintf(stderr, "  message: %s\n  expected prefix: %s\n", err.msg, prefix);
  /* Without an fb_err: the same failure, no message to blame. */
  CHECK(load(ov, n, &s, NULL) == rc && s == NULL);
  fb_scenario_free(&s);
}

static void test_bad_keys(const char *text)
{
  char road[32], where[128];
  /* A bad path names the deepest mapping found, at its position, and
   * the keys it has. */
  position_of(text, "\nroad:", 1, road, sizeof road);
  const fb_scenario_override missing = {.key = "road.speedkmh", .value = "5"};
  snprintf(where, sizeof where, "--set road.speedkmh=5: " EXAMPLE ":");
  expect_error(&missing, 1, FB_EINVAL, where,
               (const char *const[]){"has no key 'speedkmh'", "speed_kmh, bump", NULL});
  /* The road mapping's own position: its first key, "speed_kmh". */
  position_of(text, "\nroad:\n  speed_kmh", 9, road, sizeof road);
  snprintf(where, sizeof where, "--set road.speedkmh=5: " EXAMPLE ":%s: road: ", road);
  expect_error(&missing, 1, FB_EINVAL, where, (const char *const[]){NULL});

  const fb_scenario_override ambiguous = {.key = "mass", .value = "1"};
  expect_error(&ambiguous, 1, FB_EINVAL, "--set mass=1: " EXAMPLE ": key 'mass' is ambiguous",
               (const char *const[]){"hull.mass", "mounts[0].mass", "mounts[1].mass",
                                     "wheel.mass", "give the dotted path", NULL});
  /* A name the file has none of names one of the format's keys: here
   * several road types' (the file's own `angle_deg` is the bump's alone,
   * test_number_and_nested). */
  const fb_scenario_override elsewhere = {.key = "ramp_length", .value = "1"};
  expect_error(&elsewhere, 1, FB_EINVAL,
               "--set ramp_length=1: " EXAMPLE ": key 'ramp_length' is ambiguous",
               (const char *const[]){"road.step.ramp_length", "road.cleat.ramp_length",
                                     "road.trapezoid.ramp_length", NULL});
  const fb_scenario_override absent = {.key = "velocity", .value = "1"};
  expect_error(&absent, 1, FB_EINVAL, "--set velocity=1: " EXAMPLE ": no key 'velocity'",
               (const char *const[]){"road", "simulation", NULL});
  const fb_scenario_override typo = {.key = "sped_kmh", .value = "1"};
  expect_error(&typo, 1, FB_EINVAL, "--set sped_kmh=1: " EXAMPLE ": no key 'sped_kmh'",
               (const char *const[]){"did you mean 'road.speed_kmh'?", NULL});
  const fb_scenario_override mapping = {.key = "road.bump", .value = "1"};
  expect_error(&mapping, 1, FB_EINVAL, "--set road.bump=1: " EXAMPLE ":",
               (const char *const[]){"road.bump: is a mapping", "height, length", NULL});
  const fb_scenario_override list = {.key = "bulkheads", .value = "1"};
  expect_error(&list, 1, FB_EINVAL, "--set bulkheads=1: " EXAMPLE ":",
               (const char *const[]){"is a list", "hull.mesh.generator.bulkheads[0]", NULL});
  const fb_scenario_override past_end = {.key = "hull.mesh.generator.bulkheads[3]",
                                         .value = "1"};
  expect_error(&past_end, 1, FB_EINVAL, "--set hull.mesh.generator.bulkheads[3]=1: ",
               (const char *const[]){"has no item [3] (it has 3)", NULL});
  const fb_scenario_override malformed = {.key = "road..speed_kmh", .value = "1"};
  expect_error(&malformed, 1, FB_EINVAL,
               "--set road..speed_kmh=1: ", (const char *const[]){"malformed key", NULL});
  const fb_scenario_override twice[] = {{.key = "speed_kmh", .value = "5"},
                                        {.key = "road.speed_kmh", .value = "6"}};
  expect_error(
      twice, 2, FB_EINVAL, "--set road.speed_kmh=6: ",
      (const char *const[]){"sets road.speed_kmh, which --set speed_kmh=5 sets too", NULL});

  char *full = NULL;
  fb_err err;
  CHECK(fb_scenario_override_key(EXAMPLE, "speed_kmh", &full, &err) == FB_OK && full &&
        !strcmp(full, "road.speed_kmh"));
  free(full);
  CHECK(fb_scenario_override_key(EXAMPLE, "mass", &full, &err) == FB_EINVAL && !full &&
        strstr(err.msg, "hull.mass, mounts[0].mass"));
  CHECK(fb_scenario_override_key("no/such/file.yaml", "mass", &full, &err) == FB_EIO);
}

static void test_bad_values(const char *text)
{
  char value[32], prefix[160];
  /* The reader's own message for the new value, at the original value's
   * line and column. */
  position_of(text, "speed_kmh: 10", strlen("speed_kmh: "), value, sizeof value);
  const fb_scenario_override word = {.key = "road.speed_kmh", .value = "fast"};
  snprintf(prefix, sizeof prefix,
           "--set road.speed_kmh=fast: " EXAMPLE ":%s: road.speed_kmh: ", value);
  expect_error(&word, 1, 0, prefix, (const char *const[]){"fast", NULL});
  /* Text that would be YAML structure stays one value, at the value's
   * place. */
  const fb_scenario_override structure = {.key = "speed_kmh", .value = "1, x: \"2\"\\"};
  position_of(text, "speed_kmh: 10", strlen("speed_kmh: "), value, sizeof value);
  snprintf(prefix, sizeof prefix,
           "--set speed_kmh=1, x: \"2\"\\: " EXAMPLE ":%s: road.speed_kmh: ", value);
  expect_error(&structure, 1, 0, prefix, (const char *const[]){NULL});
  const fb_scenario_override newline = {.key = "speed_kmh", .value = "1\n2"};
  expect_error(&newline, 1, FB_EINVAL, "--set speed_kmh=1\\n2: " EXAMPLE ": ",
               (const char *const[]){"control character", NULL});
  /* fb_scenario_check's message, blamed at the new value. */
  position_of(text, "spring_k: 145300", strlen("spring_k: "), value, sizeof value);
  const fb_scenario_override negative = {.key = "suspensions.axles[0].spring_k", .value = "-1"};
  snprintf(prefix, sizeof prefix,
           "--set suspensions.axles[0].spring_k=-1: " EXAMPLE
           ":%s: suspensions.axles[0].spring_k: ",
           value);
  expect_error(&negative, 1, FB_EINVAL, prefix, (const char *const[]){"> 0", NULL});
  /* A consequence of the values: at 2 km/h the last wheel leaves the bump
   * at 5 + 8.7 m / (2/3.6 m/s) = 20.7 s, after t_end = 15 s. The message
   * names the bump's length, which no override set, so every override is
   * named. */
  const fb_scenario_override slow[] = {{.key = "speed_kmh", .value = "2"},
                                       {.key = "road.bump.height", .value = "0.2"}};
  expect_error(slow, 1, FB_EINVAL, "--set speed_kmh=2: " EXAMPLE ":",
               (const char *const[]){"simulation.t_end: the run ends", "20.66", NULL});
  expect_error(slow, 2, FB_EINVAL, "--set speed_kmh=2 --set road.bump.height=0.2: " EXAMPLE ":",
               (const char *const[]){"simulation.t_end: the run ends", NULL});
}

/* The origin of the value the file names path, NULL if none. */
static const sc_value_origin *origin_at(const fb_scenario *s, const char *path)
{
  const sc_source *src = sc_source_of(s);
  for (size_t i = 0; src && i < src->norigins; ++i)
    if (!strcmp(src->origin[i].path, path))
      return &src->origin[i];
  return NULL;
}

/* o is at "LINE:COL" where and names the override label. */
static int origin_is(const sc_value_origin *o, const char *where, const char *label)
{
  char at[32];
  snprintf(at, sizeof at, "%d:%d", o ? o->line : 0, o ? o->column : 0);
  return o && o->override && !strcmp(o->override, label) && !strcmp(at, where);
}

/* Keys the file leaves out: a default of every corner (the top-level
 * wheel.tire_contact), one by its bare name (max_steps), an optional key
 * (an output's column) and a key in a section the file leaves out (the
 * middle axle's own wheel), each read as if the file had it, its origin
 * at the section it goes into and naming the override. */
static void test_keys_left_out(const char *text)
{
  const fb_scenario_override ov[] = {
      {.key = "wheel.tire_contact", .value = "unilateral"},
      {.key = "max_steps", .value = "12345"},
      {.key = "outputs[0].name", .value = "lf_force"},
      {.key = "suspensions.axles[1].wheel.tire_k", .value = "600000"}};
  fb_scenario *s = NULL;
  fb_err err;
  int rc = load(ov, sizeof ov / sizeof ov[0], &s, &err);
  CHECK(rc == FB_OK && s);
  if (rc != FB_OK || !s) {
    fprintf(stderr, "  %s\n", err.msg);
    return;
  }
  for (size_t i = 0; i < s->ncorners; ++i)
    CHECK(fb_corner_tire_model(&s->corner[i]) == &fb_tire_model_unilateral);
  CHECK(s->max_steps == 12345);
  CHECK(!strcmp(s->output[0].name, "lf_force") && strcmp(s->output[1].name, "lf_force") != 0);
  CHECK(s->corner[2].tire_k == 600000 && s->corner[3].tire_k == 600000);
  CHECK(s->corner[0].tire_k == 500000 && s->corner[5].tire_k == 500000);
  char sim[32], wheel[32], axle[32], want[256];
  position_of(text, "\nsimulation:\n  t_end", strlen("\nsimulation:\n  "), sim, sizeof sim);
  position_of(text, "  mass: 175", 2, wheel, sizeof wheel);
  position_of(text, "- name: M ", 2, axle, sizeof axle);
  CHECK(origin_is(origin_at(s, "simulation.max_steps"), sim, "--set max_steps=12345"));
  CHECK(origin_is(origin_at(s, "wheel.tire_contact"), wheel,
                  "--set wheel.tire_contact=unilateral"));
  CHECK(origin_is(origin_at(s, "suspensions.axles[1].wheel.tire_k"), axle,
                  "--set suspensions.axles[1].wheel.tire_k=600000"));
  /* An error found later is the override's, at its section. */
  fb_err_set(&err, FB_EINVAL, "too many");
  fb_err_set_key(&err, "simulation.max_steps");
  fb_scenario_locate(s, &err);
  snprintf(want, sizeof want,
           "--set max_steps=12345: " EXAMPLE ":%s: simulation.max_steps: too many", sim);
  CHECK(!strcmp(err.msg, want) && err.source == FB_SOURCE_OVERRIDE);
  if (strcmp(err.msg, want))
    fprintf(stderr, "  wanted '%s', got '%s'\n", want, err.msg);
  fb_scenario_free(&s);
}

/* Loading with ov fails at key (the file's path), LINE:COL where, the
 * override as the error's source and its message prefix. */
static void expect_source(const fb_scenario_override *ov, const char *key, const char *where,
                          const char *phrase)
{
  fb_scenario *s = NULL;
  fb_err err;
  char label[160], prefix[256], at[32];
  snprintf(label, sizeof label, "--set %s=%s", ov->key, ov->value);
  snprintf(prefix, sizeof prefix, "%s: " EXAMPLE ":%s: %s: ", label, where, key);
  CHECK(load(ov, 1, &s, &err) != FB_OK && !s);
  snprintf(at, sizeof at, "%d:%d", err.line, err.column);
  int ok = !strncmp(err.msg, prefix, strlen(prefix)) && strstr(err.msg, phrase) &&
           err.source == FB_SOURCE_OVERRIDE && !strcmp(err.source_text, label) &&
           !strcmp(err.key, key) && !strcmp(err.file, EXAMPLE) && !strcmp(at, where);
  CHECK(ok);
  if (!ok)
    fprintf(stderr,
            "  message: %s\n  expected prefix: %s and '%s' (source %d '%s', key %s, %s)\n",
            err.msg, prefix, phrase, err.source, err.source_text, err.key, at);
}

/* Paths that name no value of the format or the file, and values of the
 * wrong type, at a key the file has and at one it leaves out. */
static void test_bad_paths(const char *text)
{
  char sim[32], initial[32], bump[32], where[160];
  position_of(text, "\nsimulation:\n  t_end", strlen("\nsimulation:\n  "), sim, sizeof sim);
  position_of(text, "initial: zero", strlen("initial: "), initial, sizeof initial);
  position_of(text, "  bump:\n    height", strlen("  bump:\n    "), bump, sizeof bump);
  const fb_scenario_override typo = {.key = "simulation.max_stpes", .value = "1"};
  snprintf(where, sizeof where,
           "--set simulation.max_stpes=1: " EXAMPLE ":%s: simulation: ", sim);
  expect_error(
      &typo, 1, FB_EINVAL, where,
      (const char *const[]){"has no key 'max_stpes' (did you mean 'max_steps'?", NULL});
  /* Each set to 1: after "--set KEY=1: FILE", the message has part. */
  static const struct {
    const char *key, *part;
  } refused[] = {
      {"max_stpes",
       "no key 'max_stpes' in the scenario (did you mean 'simulation.max_steps'?)"},
      {"suspensions.axles[3].spring_k", "suspensions.axles: has no item [3] (it has 3)"},
      {"hull.masses[0].mass", "hull.masses: has no item [0] (it has 0)"},
      {"mounts[1]", "mounts[1]: is a mapping, not a single value (its keys: name, mass"},
      {"mounts", "mounts: is a list, not a single value; set a key of one item, e.g. "
                 "mounts[0].name"},
  };
  for (size_t i = 0; i < sizeof refused / sizeof refused[0]; ++i) {
    const fb_scenario_override o = {.key = refused[i].key, .value = "1"};
    snprintf(where, sizeof where, "--set %s=1: " EXAMPLE, refused[i].key);
    expect_error(&o, 1, FB_EINVAL, where, (const char *const[]){refused[i].part, NULL});
  }
  const fb_scenario_override initial_typo = {.key = "simulation.initial", .value = "sttic"};
  expect_source(&initial_typo, "simulation.initial", initial, "did you mean 'static'?");
  const fb_scenario_override steps = {.key = "simulation.max_steps", .value = "many"};
  expect_source(&steps, "simulation.max_steps", sim, "many");
  /* A key the file leaves out that its section's rule refuses: the
   * bump's type with its height and length. */
  const fb_scenario_override type = {.key = "road.bump.type", .value = "II"};
  expect_source(&type, "road.bump.type", bump, "give either a type or height and length");

  char *full = NULL;
  fb_err err;
  CHECK(fb_scenario_override_key(EXAMPLE, "max_steps", &full, &err) == FB_OK && full &&
        !strcmp(full, "simulation.max_steps"));
  free(full);
  CHECK(fb_scenario_override_key(EXAMPLE, "mounts[2].mass", &full, &err) == FB_EINVAL &&
        !full && strstr(err.msg, "mounts: has no item [2] (it has 2)") &&
        err.source != FB_SOURCE_OVERRIDE);
}

/* An error found after loading (fb_scenario_locate) about a value that
 * an override replaced names the override, then the value's place in the
 * file, as a loading error does, and records it in fb_err's fields; one
 * about another value is located only, and one whose key the scenario
 * does not have gets that key alone. A clone keeps the origins. */
static void test_late_locate(const char *text)
{
  const fb_scenario_override ov[] = {{.key = "modes", .value = "99999"}};
  fb_scenario *s = NULL, *c = NULL;
  fb_err err;
  CHECK(load(ov, 1, &s, &err) == FB_OK && s);
  if (!s)
    return;
  CHECK(fb_scenario_clone(s, &c, &err) == FB_OK && c && sc_source_of(c) &&
        sc_source_of(c)->norigins == sc_source_of(s)->norigins);
  char modes[32], driver[32], want[256];
  position_of(text, "    modes: auto", 11, modes, sizeof modes);
  position_of(text, "    x: 2.10", 7, driver, sizeof driver);
  fb_err_set(&err, FB_EINVAL, "too many");
  fb_err_set_key(&err, "hull.fe.modes");
  CHECK(fb_scenario_locate(c, &err) == FB_EINVAL);
  snprintf(want, sizeof want, "--set modes=99999: " EXAMPLE ":%s: hull.fe.modes: too many",
           modes);
  CHECK(!strcmp(err.msg, want));
  if (strcmp(err.msg, want))
    fprintf(stderr, "  wanted '%s', got '%s'\n", want, err.msg);
  CHECK(err.source == FB_SOURCE_OVERRIDE && !strcmp(err.source_text, "--set modes=99999"));
  CHECK(!strcmp(err.file, EXAMPLE) && !strcmp(err.key, "hull.fe.modes") && err.line > 0);
  fb_err_set(&err, FB_EINVAL, "off the floor");
  fb_err_set_key(&err, "mounts.driver.x");
  fb_scenario_locate(s, &err);
  snprintf(want, sizeof want, EXAMPLE ":%s: mounts[0].x: off the floor", driver);
  CHECK(!strcmp(err.msg, want));
  if (strcmp(err.msg, want))
    fprintf(stderr, "  wanted '%s', got '%s'\n", want, err.msg);
  CHECK(err.source == FB_SOURCE_FILE);
  fb_err_set(&err, FB_EMODEL, "no node there");
  fb_err_set_key(&err, "hull mesh");
  CHECK(fb_scenario_locate(s, &err) == FB_EMODEL &&
        !strcmp(err.msg, "hull mesh: no node there"));
  fb_scenario_free(&c);
  fb_scenario_free(&s);
}

int main(void)
{
  char *text = read_text(EXAMPLE);
  CHECK(text != NULL);
  if (!text)
    return check_report("test_overrides");
  test_number_and_nested();
  test_name_expression_list();
  test_quoted_original(text);
  test_relative_references();
  test_bad_keys(text);
  test_bad_values(text);
  test_keys_left_out(text);
  test_bad_paths(text);
  test_late_locate(text);
  free(text);
  return check_report("test_overrides");
}
