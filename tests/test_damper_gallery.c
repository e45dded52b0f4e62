/* SPDX-License-Identifier: BSD-3-Clause */
/* The damper gallery (flexbond/damper.h): one conformance harness that
 * runs every law of a gallery through the same checks, and a damper law
 * a program adds at run time (a quadratic damper F = c2 v |v|, the
 * worked example of docs/architecture.md), usable from a scenario file
 * with its errors located at its own keys. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/damper.h"
#include "flexbond/io.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "energy_balance.h"
#include "vehicle_util.h"

/* ---- The quadratic damper: a program's own law. */

typedef struct quadratic_params {
  double c2; /* N s^2/m^2 */
} quadratic_params;

static const fb_param quadratic_param[] = {
    {.name = "c2",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(quadratic_params, c2),
     .unit = "N s^2/m^2",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "the force over the travel rate squared"},
};

/* y = c2 x |x|, its slope 2 c2 |x| and co-content c2 |x|^3 / 3. */
static int quadratic_eval(void *ctx, const fb_law_in *in, double *y)
{
  const double c2 = *(const double *)ctx, x = in->x[0];
  y[0] = c2 * x * fabs(x);
  return 0;
}

static int quadratic_jacobian(void *ctx, const fb_law_in *in, double *jac)
{
  jac[0] = 2.0 * *(const double *)ctx * fabs(in->x[0]);
  return 0;
}

static double quadratic_energy(void *ctx, size_t n, const double *x)
{
  (void)n;
  return *(const double *)ctx * fabs(x[0]) * x[0] * x[0] / 3.0;
}

static const fb_law_ops quadratic_law = {.name = "quadratic",
                                         .eval = quadratic_eval,
                                         .jacobian = quadratic_jacobian,
                                         .energy = quadratic_energy,
                                         .free = free,
                                         .passive = 1};

static int quadratic_build(const void *params, fb_bg *bg, fb_err *err)
{
  double *c2 = malloc(sizeof *c2);
  if (!c2)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a quadratic damper");
  *c2 = ((const quadratic_params *)params)->c2;
  const size_t one = 1;
  return fb_bg_add_field_law(bg, "damper", FB_BG_R, 1, &one, &quadratic_law, c2, err);
}

static double quadratic_force(const void *params, double v)
{
  return ((const quadratic_params *)params)->c2 * v * fabs(v);
}

static const fb_damper_law_ops quadratic_ops = {.build = quadratic_build,
                                                .force = quadratic_force};

static const fb_damper_law quadratic = {
    .name = "quadratic",
    .doc = "a quadratic damper, F = c2 v |v|",
    .meaning = "quadratic in the travel rate",
    .param = quadratic_param,
    .nparams = sizeof quadratic_param / sizeof quadratic_param[0],
    .params_size = sizeof(quadratic_params),
    .ops = &quadratic_ops,
};

/* ---- A law without parameters: the front shock of the paper, fixed. */

static int fixed_build(const void *params, fb_bg *bg, fb_err *err)
{
  (void)params;
  const fb_damper_linear_params front = {25744.0};
  return fb_damper_law_linear.ops->build(&front, bg, err);
}

static double fixed_force(const void *params, double v)
{
  (void)params;
  return 25744.0 * v;
}

static int fixed_linear(const void *params)
{
  (void)params;
  return 1;
}

static const fb_damper_law_ops fixed_ops = {
    .build = fixed_build, .force = fixed_force, .linear = fixed_linear};

static const fb_damper_law fixed = {
    .name = "fixed",
    .doc = "the paper's front shock absorber, 25744 N s/m, nothing to give",
    .meaning = "linear, 25744 N s/m",
    .ops = &fixed_ops,
};

/* ---- Loading the reference scenario with dampers of its own. */

/* ../examples/apc6x6.yaml with every axle's "damper_c: <value>" replaced
 * by fmt (a printf format taking the value), loaded as bad.yaml with the
 * gallery g and the overrides ov. */
static int load_dampers(const char *fmt, const fb_damper_gallery *g,
                        const fb_scenario_override *ov, size_t nov, fb_scenario **out,
                        fb_err *err)
{
  char *file = read_text("../examples/apc6x6.yaml");
  const size_t size = file ? 2 * strlen(file) + 1 : 0;
  char *yaml = file ? calloc(1, size) : NULL;
  int rc = FB_EIO;
  if (yaml) {
    const char *at = file;
    size_t n = 0;
    for (const char *d; (d = strstr(at, "damper_c: ")); at = strchr(d, '\n')) {
      const double value = strtod(d + strlen("damper_c: "), NULL);
      n += (size_t)snprintf(yaml + n, size - n, "%.*s", (int)(d - at), at);
      n += (size_t)snprintf(yaml + n, size - n, fmt, value);
    }
    snprintf(yaml + n, size - n, "%s", at);
    const fb_scenario_load_opts opts = {.dampers = g, .overrides = ov, .noverrides = nov};
    rc = load_text_with(yaml, &opts, out, err);
  }
  free(yaml);
  free(file);
  return rc;
}

/* ---- The conformance harness. */

/* Each law's example: how a file gives it (fmt for load_dampers; NULL:
 * the example file path as it is) and the key of its first declared
 * parameter in the front axle's item (NULL: none). A law of the gallery
 * without an example fails the harness. */
static const struct {
  const char *law, *fmt, *path, *key;
  const char *values; /* corner LF's damper values as fb_scenario_each_value lists them */
} example[] = {
    {"linear", "damper_c: %.17g", NULL, "suspensions.axles[0].damper_c",
     "corners.LF.damper_c=25744;"},
    {"table", NULL, "../examples/apc6x6_shock_table.yaml", NULL,
     "corners.LF.damper_table=9 points;"},
    {"quadratic", "damper: {quadratic: {c2: %.17g}}", NULL,
     "suspensions.axles[0].damper.quadratic.c2", "corners.LF.damper.quadratic.c2=25744;"},
    {"fixed", "damper: {fixed: {}}  # %g", NULL, NULL, ""},
};

/* Appends "key=value;" of corner LF's damper values to the buffer ctx. */
static int damper_value(const fb_scenario_value *v, void *ctx)
{
  char *buf = ctx;
  const size_t n = strlen(buf);
  if (!strncmp(v->key, "corners.LF.damper", strlen("corners.LF.damper")) && v->value[0])
    snprintf(buf + n, 512 - n, "%s=%s;", v->key, v->value);
  return 0;
}

static int load_example(size_t i, const fb_damper_gallery *g, const fb_scenario_override *ov,
                        size_t nov, fb_scenario **out, fb_err *err)
{
  if (example[i].fmt)
    return load_dampers(example[i].fmt, g, ov, nov, out, err);
  const fb_scenario_load_opts opts = {.dampers = g, .overrides = ov, .noverrides = nov};
  return fb_scenario_load_with(example[i].path, &opts, out, err);
}

/* The force of the R element "damper" of corner c's fragment at travel
 * rate v: its matrix times v, or its law. */
static double element_force(const fb_bg *bg, double v)
{
  const long e = fb_bg_find_element(bg, "damper");
  if (e < 0 || fb_bg_element_kind(bg, (size_t)e) != FB_BG_R)
    return NAN;
  const fb_mat *m = fb_bg_element_matrix(bg, (size_t)e);
  if (m)
    return fb_mat_get(m, 0, 0) * v;
  const void *ctx = NULL;
  const fb_law_ops *ops = fb_bg_element_law(bg, (size_t)e, &ctx);
  double f = NAN;
  const fb_law_in in = {.n = 1, .x = &v};
  if (ops && ops->eval((void *)ctx, &in, &f) != 0)
    return NAN;
  return f;
}

/* The element a corner's law builds against the law's force op at
 * sample velocities, and passive (F v >= 0 there). The two are the same
 * arithmetic on the same values (0 measured for the built-in laws and
 * the quadratic one): 1e-12 of the largest force allows round-off only.
 * A law that says it is linear has F(2 v) = 2 F(v), F(-v) = -F(v). */
static void check_force(const fb_damper_law *l, const fb_corner_params *c)
{
  static const double v[] = {-1.5, -1.0, -0.3, -0.05, 0.0, 0.05, 0.3, 1.0, 1.5};
  fb_err err;
  fb_bg *bg = NULL;
  CHECK(fb_vehicle_corner(c, 9.81, &bg, &err) == FB_OK);
  if (!bg)
    return;
  double largest = 0.0, worst = 0.0;
  for (size_t i = 0; i < sizeof v / sizeof v[0]; ++i)
    largest = fmax(largest, fabs(l->ops->force(c->damper.bytes, v[i])));
  CHECK(largest > 0.0);
  for (size_t i = 0; i < sizeof v / sizeof v[0]; ++i) {
    const double f = element_force(bg, v[i]);
    worst = fmax(worst, fabs(f - l->ops->force(c->damper.bytes, v[i])) / largest);
    CHECK(f * v[i] >= 0.0);
  }
  CHECK(worst <= 1e-12);
  if (l->ops->linear && l->ops->linear(c->damper.bytes)) {
    const double f = element_force(bg, 0.3);
    CHECK(fabs(element_force(bg, 0.6) - 2.0 * f) <= 1e-12 * fabs(f));
    CHECK(fabs(element_force(bg, -0.3) + f) <= 1e-12 * fabs(f));
  }
  printf("  %s (%s): built element vs force op to %.3g of %.6g N\n", l->name, c->name, worst,
         largest);
  fb_bg_free(&bg);
}

/* Every declared parameter's value outside its range, at its key in
 * the front axle, is refused at that key. */
static void check_located(size_t i, const fb_damper_law *l, const fb_damper_gallery *g)
{
  for (size_t k = 0; example[i].key && k < l->nparams; ++k) {
    const fb_param *p = &l->param[k];
    if (!(p->range & FB_RANGE_LO))
      continue;
    char key[160], value[64];
    snprintf(key, sizeof key, "%s", example[i].key);
    if (k) /* a law's further parameters beside its first */
      snprintf(strrchr(key, '.') + 1, sizeof key - (size_t)(strrchr(key, '.') + 1 - key), "%s",
               p->name);
    snprintf(value, sizeof value, "%.17g", p->range & FB_RANGE_LO_OPEN ? p->lo : p->lo - 1);
    const fb_scenario_override ov = {.key = key, .value = value};
    fb_err err;
    fb_scenario *s = NULL;
    CHECK(load_example(i, g, &ov, 1, &s, &err) != FB_OK && !s);
    check_refused_at(&err, key, value);
  }
}

/* Linear analyses take the law as it is when it says it is linear, and
 * linearise it otherwise (the descriptor's linearised flag). */
static void check_linear_analysis(const fb_damper_law *l, const fb_scenario *s)
{
  int linear = 1;
  for (size_t c = 0; c < s->ncorners; ++c)
    linear &= fb_corner_damper_linear(&s->corner[c]);
  fb_err err;
  fb_descriptor *ds = NULL;
  CHECK(fb_vehicle_descriptor(s, FB_SYSTEM_RIGID, &ds, &err) == FB_OK);
  CHECK(ds && ds->linearised == !linear);
  if (ds)
    printf("  %s: linear %d, descriptor linearised %d\n", l->name, linear, ds->linearised);
  fb_descriptor_free(&ds);
}

/* Work in = dissipated + stored - stored(0) at every sample of a bump
 * crossing (10 cm, 0.5 m long, from 1 s to 3 s) at rtol 1e-9: the law's
 * element exchanges power with the rest as an R does, whatever its law.
 * As tests/test_system1.c argues, each integral carries a few rtol of its
 * size, so 1e-7 of the work scale is a wide margin, while a damper whose
 * element delivered power or was missed by the probes (its dissipation
 * is ~1e2 J and more) fails at 1e-4. */
static void check_energy(const fb_damper_law *l, fb_scenario *s)
{
  road_bump(s)->first_contact = 1.0;
  road_bump(s)->length = 0.5;
  road_bump(s)->height = 0.1;
  s->t_end = 3.0;
  fb_err err;
  energy_report rep;
  CHECK(energy_balance_rigid(s, 1e-9, &rep, &err) == FB_OK);
  /* 6 shocks, 6 tire dampers, 2 mounts */
  CHECK(rep.ndissipative == 2 * APC_NCORNERS + APC_NMOUNTS);
  CHECK(rep.work_scale > 100.0 && rep.dissipated > 100.0);
  CHECK(rep.worst <= 1e-7 * rep.work_scale);
  printf("  %s: energy balance to %.3g of the work (%.6g J)\n", l->name,
         rep.worst / rep.work_scale, rep.work_scale);
}

static void check_law(size_t i, const fb_damper_law *l, const fb_damper_gallery *g)
{
  fb_err err;
  CHECK(fb_damper_law_check(l, &err) == FB_OK);
  fb_damper_params p;
  fb_damper_params_init(l, &p);
  CHECK(fb_params_check(l->param, l->nparams, p.bytes, &err) == FB_OK ||
        l->param[0].need == FB_PARAM_REQUIRED);
  fb_scenario *s = NULL;
  CHECK(load_example(i, g, NULL, 0, &s, &err) == FB_OK);
  if (!s) {
    fprintf(stderr, "  %s: %s\n", l->name, err.msg);
    return;
  }
  CHECK(fb_scenario_check(s, &err) == FB_OK);
  int seen = 0;
  for (size_t c = 0; c < s->ncorners; ++c)
    if (fb_corner_damper_law(&s->corner[c]) == l) {
      s->corner[c].tire_static_deflection = 0.04;
      check_force(l, &s->corner[c]);
      seen = 1;
    }
  CHECK(seen);
  if (l->ops->describe) { /* a report's line for the front axle's values */
    char line[128] = "";
    l->ops->describe(s->corner[0].damper.bytes, line, sizeof line);
    CHECK(line[0] != '\0');
    printf("  %s: \"%s\"\n", l->name, line);
  }
  /* The values a description lists are its law's only. */
  char values[512] = "";
  CHECK(fb_scenario_each_value(s, damper_value, values) == FB_OK);
  CHECK(!strcmp(values, example[i].values));
  if (strcmp(values, example[i].values))
    fprintf(stderr, "  %s: values %s\n", l->name, values);
  check_linear_analysis(l, s);
  check_energy(l, s);
  fb_scenario_free(&s);
  check_located(i, l, g);
}

static void test_conformance(const fb_damper_gallery *g)
{
  CHECK(fb_damper_gallery_count(g) >= 4);
  for (size_t j = 0; j < fb_damper_gallery_count(g); ++j) {
    const fb_damper_law *l = fb_damper_gallery_at(g, j);
    size_t i = 0;
    while (i < sizeof example / sizeof example[0] && strcmp(example[i].law, l->name))
      ++i;
    CHECK(i < sizeof example / sizeof example[0]); /* every law has an example */
    if (i < sizeof example / sizeof example[0])
      check_law(i, l, g);
  }
}

/* ---- The quadratic damper from a program and a file. */

static void test_registration(fb_damper_gallery *g)
{
  fb_err err;
  /* Unknown to a gallery without it, at its key. */
  CHECK(load_dampers("damper: {quadratic: {c2: %g}}", NULL, NULL, 0, NULL, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "bad.yaml:99:16: suspensions.axles[0].damper.quadratic: unknown key "
                        "'quadratic'"));
  CHECK(fb_damper_gallery_add(g, &quadratic, &err) == FB_OK);
  CHECK(fb_damper_gallery_add(g, &quadratic, &err) == FB_EINVAL && strstr(err.msg, "already"));
  CHECK(fb_damper_gallery_find(g, "quadratic") == &quadratic);
  CHECK(fb_damper_gallery_add(g, &fixed, &err) == FB_OK);
  /* Unsound laws are refused. */
  static const fb_damper_law_ops no_force = {.build = quadratic_build};
  fb_damper_law bad = quadratic;
  bad.name = "bad";
  bad.ops = &no_force;
  CHECK(fb_damper_gallery_add(g, &bad, &err) == FB_EINVAL && strstr(err.msg, "force"));
  bad.ops = &quadratic_ops;
  bad.meaning = NULL;
  CHECK(fb_damper_gallery_add(g, &bad, &err) == FB_EINVAL && strstr(err.msg, "undocumented"));
  bad.meaning = "x";
  bad.params_size = FB_DAMPER_PARAMS_MAX + 1;
  CHECK(fb_damper_gallery_add(g, &bad, &err) == FB_EINVAL && strstr(err.msg, "exceeds"));
}

/* Its errors at its keys: a declared range, two laws for one corner, a
 * law's section left empty; the same from a program. */
static void test_errors(const fb_damper_gallery *g)
{
  static const struct {
    const char *fmt, *want;
  } bad[] = {
      {"damper: {quadratic: {c2: -%g}}",
       "bad.yaml:99:32: suspensions.axles[0].damper.quadratic.c2: must be > 0 N s^2/m^2 "
       "(got -25744)"},
      {"damper: {quadratic: {c2: %g}}\n      damper_c: 1",
       "bad.yaml:99:7: suspensions.axles[0].damper: give either 'damper_c' or 'damper', not "
       "both"},
      {"damper: {quadratic: {}}  # %g",
       "bad.yaml:99:27: suspensions.axles[0].damper.quadratic: missing required key 'c2'"},
      {"damper_c: -%g", "bad.yaml:99:17: suspensions.axles[0].damper_c: must be >= 0"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    fb_err err;
    CHECK(load_dampers(bad[i].fmt, g, NULL, 0, NULL, &err) != FB_OK);
    check_message(&err, bad[i].want);
  }
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(load_dampers("damper: {quadratic: {c2: %.17g}}", g, NULL, 0, &s, &err) == FB_OK);
  if (!s)
    return;
  ((quadratic_params *)(void *)s->corner[3].damper.bytes)->c2 = -1;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_DAMPER &&
        err.part.index == 3 && !strcmp(err.part.field, "c2"));
  char where[128];
  CHECK(strstr(fb_scenario_part_text(s, &err.part, where, sizeof where), "damper.c2"));
  fb_scenario_free(&s);
}

int main(void)
{
  fb_err err;
  fb_damper_gallery *g = NULL;
  CHECK(fb_damper_gallery_new(&g, &err) == FB_OK);
  if (!g)
    return check_report("test_damper_gallery");
  CHECK(fb_damper_gallery_count(g) == 2);
  CHECK(fb_damper_gallery_at(g, 0) == &fb_damper_law_linear);
  test_registration(g);
  test_conformance(g);
  test_errors(g);
  fb_damper_gallery_free(&g);
  return check_report("test_damper_gallery");
}
