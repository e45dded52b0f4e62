/* SPDX-License-Identifier: BSD-3-Clause */
/* The spring gallery (flexbond/spring.h): one conformance harness that
 * runs every law of the gallery through the same checks (the built
 * element held to the law's force, a closed form written here, a mass
 * released on the law conserving its energy, the static equilibrium of
 * a vehicle carrying its weight on the law, errors at their keys). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/sim.h"
#include "flexbond/spring.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "three_corner.h"
#include "vehicle_util.h"

/* Each law's example: the front corner's keys that give it, and its
 * force at travels by hand (the law's closed form written out here). */
typedef double (*hand_force)(double x);

/* linear, spring_k 100000 N/m, preload 2000 N: F = 2000 + 1e5 x. */
static double linear_hand(double x)
{
  return 2000.0 + 1e5 * x;
}

/* The table's knots: (-0.1, -8000), (0, 2000), (0.1, 12000), (0.2, 32000)
 * (a progressive spring preloaded by 2000 N). Hand values at the knots
 * (the interpolant passes through them) and on the tangent beyond the
 * last: Fritsch & Carlson's end slope is the end secant, 2e5 N/m. */
static double table_hand(double x)
{
  static const double kx[] = {-0.1, 0.0, 0.1, 0.2}, kf[] = {-8000.0, 2000.0, 12000.0, 32000.0};
  for (size_t i = 0; i < 4; ++i)
    if (x == kx[i])
      return kf[i];
  return x > 0.2 ? 32000.0 + 2e5 * (x - 0.2) : NAN;
}

static const struct {
  const char *law, *front;
  hand_force hand;
  double at[4]; /* travels where hand is known, m */
  double preload;
} example[] = {
    {"linear", ", spring_preload: 2000", linear_hand, {-0.05, 0.0, 0.03, 0.2}, 2000.0},
    {"table",
     ", spring_table: {points: [[-0.1, -8000], [0, 2000], [0.1, 12000], [0.2, 32000]]}",
     table_hand,
     {-0.1, 0.0, 0.1, 0.25},
     2000.0},
};

/* The force of the C element "spring" of bg at travel x: its matrix
 * times x, or its law. */
static double element_force(const fb_bg *bg, double x)
{
  const long e = fb_bg_find_element(bg, "spring");
  if (e < 0 || fb_bg_element_kind(bg, (size_t)e) != FB_BG_C)
    return NAN;
  const fb_mat *m = fb_bg_element_matrix(bg, (size_t)e);
  if (m)
    return fb_mat_get(m, 0, 0) * x;
  const void *ctx = NULL;
  const fb_law_ops *ops = fb_bg_element_law(bg, (size_t)e, &ctx);
  double f = NAN;
  const fb_law_in in = {.n = 1, .x = &x};
  if (ops && ops->eval((void *)ctx, &in, &f) != 0)
    return NAN;
  return f;
}

/* The element the corner's law builds against the law's force op over
 * travels of the suspension, and both against the hand values: the same
 * arithmetic on the same values, so 1e-12 of the largest force allows
 * round-off only. The preload is the force at zero travel. */
static void check_force(size_t i, const fb_spring_law *l, const fb_corner_params *c)
{
  const fb_spring_context ctx = fb_corner_spring_context(c);
  fb_err err;
  fb_bg *bg = NULL;
  CHECK(fb_vehicle_corner(c, 9.81, &bg, &err) == FB_OK);
  if (!bg)
    return;
  double largest = 0.0, worst = 0.0;
  for (double x = -0.15; x <= 0.3; x += 0.01)
    largest = fmax(largest, fabs(l->ops->force(c->spring.bytes, &ctx, x)));
  for (double x = -0.15; x <= 0.3; x += 0.01)
    worst = fmax(worst, fabs(element_force(bg, x) - l->ops->force(c->spring.bytes, &ctx, x)));
  for (size_t k = 0; k < 4; ++k) {
    const double x = example[i].at[k];
    worst = fmax(worst, fabs(element_force(bg, x) - example[i].hand(x)));
  }
  CHECK(worst <= 1e-12 * largest);
  CHECK(fabs(element_force(bg, 0.0) - example[i].preload) <= 1e-12 * largest);
  /* Monotone: a spring's force never falls as it is compressed. */
  for (double x = -0.15; x <= 0.3; x += 0.001)
    CHECK(element_force(bg, x + 0.001) >= element_force(bg, x));
  printf("  %s: built element vs force op and hand values to %.3g of %.6g N\n", l->name,
         worst / largest, largest);
  fb_bg_free(&bg);
}

/* A mass of m = 300 kg on the law alone (no gravity, no damping),
 * released at rest from a travel of 0.15 m: its energy m v^2 / 2 + U(x),
 * U the element's stored energy (the probe), stays what it was. For the
 * linear law U is checked against the hand form preload x + k x^2 / 2.
 * The integrator's local errors are rtol = 1e-10 of the state; over the
 * run's ~4 periods the energy drifts by a few hundred times rtol of it
 * (measured below), so 1e-7 of the energy is the bound, and a law whose
 * energy op were not its force's integral (a factor of 2 in k: 50 %) or
 * an element that lost energy fails it. */
static void check_energy(const fb_spring_law *l, const fb_corner_params *c)
{
  const double m = 300.0, x0 = 0.15;
  const fb_spring_context ctx = fb_corner_spring_context(c);
  fb_err err;
  fb_result *r = NULL;
  CHECK(mass_on_corner_spring(c, m, x0, 0.0, 2.0, 1e-10, &r, &err) == FB_OK);
  if (r) {
    const long cx = fb_result_find(r, "x"), cv = fb_result_find(r, "v"),
               cu = fb_result_find(r, "U");
    const double *row0 = fb_result_row(r, 0);
    const double e0 = row0[cu];
    double worst = 0.0, scale = fabs(e0), hand = 0.0, xmin = x0;
    for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
      const double *row = fb_result_row(r, k);
      const double e = 0.5 * m * row[cv] * row[cv] + row[cu];
      worst = fmax(worst, fabs(e - e0));
      scale = fmax(scale, 0.5 * m * row[cv] * row[cv]);
      xmin = fmin(xmin, row[cx]);
      if (l == &fb_spring_law_linear) {
        const double x = row[cx];
        hand = fmax(hand, fabs(row[cu] - (2000.0 * x + 0.5 * ctx.spring_k * x * x)));
      }
    }
    CHECK(xmin < 0.0); /* it swung through its travel */
    CHECK(worst <= 1e-7 * scale);
    CHECK(hand <= 1e-12 * scale);
    printf("  %s: energy of a mass on the law kept to %.3g of %.6g J\n", l->name, worst / scale,
           scale);
  }
  fb_result_free(&r);
}

/* The vehicle of three_corner.h at rest from its static equilibrium,
 * the front spring the example's law: its force is W / 3 (statics, by
 * hand) and its travel the law's inverse there: F(x) = W / 3. The
 * static solver's Newton tolerance and the run's rtol 1e-8 allow 1e-7
 * of the load; a spring that carried the preload twice (2000 N, 0.2 of
 * it) fails. */
static void check_static(const fb_spring_law *l, const fb_scenario *s)
{
  fb_result *r = simulate_rigid(s);
  CHECK(r != NULL);
  if (!r)
    return;
  const fb_corner_params *c = &s->corner[0];
  const fb_spring_context ctx = fb_corner_spring_context(c);
  const double share = THREE_CORNER_WEIGHT / 3.0;
  const double *row = fb_result_row(r, 0);
  const double x = row[fb_result_find(r, "spring_defl_F")];
  const double f = row[fb_result_find(r, "spring_force_F")];
  CHECK(fabs(f - share) <= 1e-7 * share);
  CHECK(fabs(l->ops->force(c->spring.bytes, &ctx, x) - share) <= 1e-7 * share);
  if (l == &fb_spring_law_linear) /* (W / 3 - preload) / k by hand */
    CHECK(fabs(x - (share - 2000.0) / 1e5) <= 1e-7 * x);
  printf("  %s: static travel %.6g m, force %.6g N (W / 3 = %.6g N)\n", l->name, x, f, share);
  fb_result_free(&r);
}

static void check_law(size_t i, const fb_spring_law *l)
{
  fb_err err;
  CHECK(fb_spring_law_check(l, &err) == FB_OK);
  fb_scenario *s = NULL;
  CHECK(three_corner_load(example[i].front, "", 0.0, "static", "", &s, &err) == FB_OK);
  if (!s) {
    fprintf(stderr, "  %s: %s\n", l->name, err.msg);
    return;
  }
  CHECK(fb_scenario_check(s, &err) == FB_OK);
  CHECK(fb_corner_spring_law(&s->corner[0]) == l);
  CHECK(fb_corner_spring_law(&s->corner[1]) == &fb_spring_law_linear);
  check_force(i, l, &s->corner[0]);
  check_energy(l, &s->corner[0]);
  check_static(l, s);
  if (l->ops->describe) {
    char line[160] = "";
    const fb_spring_context ctx = fb_corner_spring_context(&s->corner[0]);
    l->ops->describe(s->corner[0].spring.bytes, &ctx, line, sizeof line);
    CHECK(line[0] != '\0');
    printf("  %s: \"%s\"\n", l->name, line);
  }
  fb_scenario_free(&s);
}

static void test_conformance(const fb_spring_gallery *g)
{
  for (size_t j = 0; j < fb_spring_gallery_count(g); ++j) {
    const fb_spring_law *l = fb_spring_gallery_at(g, j);
    size_t i = 0;
    while (i < sizeof example / sizeof example[0] && strcmp(example[i].law, l->name))
      ++i;
    CHECK(i < sizeof example / sizeof example[0]); /* every law has an example */
    if (i < sizeof example / sizeof example[0])
      check_law(i, l);
  }
}

/* Without spring keys a corner's spring is the paper's: the linear law,
 * no preload, the very C element of rate spring_k (a matrix, no law). */
static void test_paper_default(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(three_corner_load("", "", 0.0, "zero", "", &s, &err) == FB_OK);
  if (!s)
    return;
  const fb_corner_params *c = &s->corner[0];
  CHECK(fb_corner_spring_law(c) == &fb_spring_law_linear);
  CHECK(((const fb_spring_linear_params *)(const void *)c->spring.bytes)->preload == 0.0);
  CHECK(!fb_stops_any(&c->stops));
  fb_bg *bg = NULL;
  CHECK(fb_vehicle_corner(c, 9.81, &bg, &err) == FB_OK);
  const long e = bg ? fb_bg_find_element(bg, "spring") : -1;
  CHECK(e >= 0 && fb_bg_element_matrix(bg, (size_t)e) != NULL);
  CHECK(bg && fb_bg_find_element(bg, "stops") < 0);
  fb_bg_free(&bg);
  fb_scenario_free(&s);
}

/* Errors at their keys: a table that decreases, one and the other law
 * at once, a preload of text. */
static void test_errors(void)
{
  static const struct {
    const char *front, *want;
  } bad[] = {
      {", spring_table: {points: [[0, 0], [0.1, 5000], [0.2, 4000]]}",
       "three_corner.yaml:16:79: suspensions.corners[0].spring_table: table law decreases: at "
       "point 3 phi(0.2) = 4000 is below point 2's 5000"},
      {", spring_preload: 10, spring_table: {points: [[0, 0], [0.1, 5000]]}",
       "three_corner.yaml:16:85: suspensions.corners[0].spring_table: give either "
       "'spring_preload' or 'spring_table', not both"},
      {", spring_preload: abc", "suspensions.corners[0].spring_preload"},
  };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i)
    three_corner_refused(bad[i].front, bad[i].want);
  /* A spring block broken by a program: the checker names the corner's
   * spring parameter (FB_PART_SPRING), the key that gave the law. */
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(three_corner_load(", spring_table: {points: [[0, 0], [0.1, 5000]]}", "", 0.0, "zero",
                          "", &s, &err) == FB_OK);
  if (!s)
    return;
  ((fb_spring_table_params *)(void *)s->corner[0].spring.bytes)->force[1] = -1.0;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_SPRING &&
        err.part.index == 0);
  CHECK(!strcmp(err.part.field, "table") && strstr(err.msg, "corner 'F': a spring's table"));
  char where[128];
  CHECK(strstr(fb_scenario_part_text(s, &err.part, where, sizeof where), "spring.table"));
  fb_scenario_free(&s);
}

int main(void)
{
  fb_err err;
  fb_spring_gallery *g = NULL;
  CHECK(fb_spring_gallery_new(&g, &err) == FB_OK);
  if (!g)
    return check_report("test_spring_gallery");
  CHECK(fb_spring_gallery_count(g) == 2);
  CHECK(fb_spring_gallery_at(g, 0) == &fb_spring_law_linear);
  CHECK(fb_spring_gallery_add(g, &fb_spring_law_table, &err) == FB_EINVAL);
  test_conformance(g);
  test_paper_default();
  test_errors();
  fb_spring_gallery_free(&g);
  return check_report("test_spring_gallery");
}
