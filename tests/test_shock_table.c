/* SPDX-License-Identifier: BSD-3-Clause */
/* Nonlinear shock absorbers in the vehicle (scenario damper_table, the
 * corner fragment's table law):
 *   - a table that is the linear damper itself (F = c v at its knots)
 *     reproduces the damper_c vehicle;
 *   - the example scenario's digressive tables load with their knots;
 *   - bad tables are refused at their YAML location. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "apc_layout.h"
#include "check.h"
#include "damper_util.h"
#include "vehicle_util.h"

/* Both runs at rtol 1e-9: their global errors are a few 1e-9 of each
 * range, and the two paths (a matrix R against a table law whose Newton
 * matrix is re-evaluated) may step differently; they agree to ~2e-10,
 * so 1e-8 of each output's range leaves a margin of 50, while a table
 * that missed the motion ratio or the sign would be off by tens of
 * percent. */
static void test_linear_table(const fb_scenario *s0)
{
  fb_err err;
  fb_scenario *lin = NULL, *tab = NULL;
  CHECK(fb_scenario_clone(s0, &lin, &err) == FB_OK);
  CHECK(fb_scenario_clone(s0, &tab, &err) == FB_OK);
  if (!lin || !tab)
    goto done;
  lin->rtol = tab->rtol = 1e-9;
  lin->atol = tab->atol = 1e-12;
  for (int c = 0; c < APC_NCORNERS; ++c) {
    fb_corner_params *p = &tab->corner[c];
    const double v[3] = {-2.0, 0.0, 2.0};
    fb_damper_table_params *t = NULL;
    CHECK(fb_corner_set_damper(p, &fb_damper_law_table, (void **)&t, &err) == FB_OK);
    t->npoints = 3;
    for (int i = 0; i < 3; ++i) {
      t->velocity[i] = v[i];
      t->force[i] = du_damper_c(&lin->corner[c]) * v[i];
    }
  }
  fb_result *a = simulate_rigid(lin), *b = simulate_rigid(tab);
  if (a && b)
    check_close(a, b, 1e-8, "linear table vs damper_c");
  fb_result_free(&a);
  fb_result_free(&b);
done:
  fb_scenario_free(&lin);
  fb_scenario_free(&tab);
}

/* examples/shock_front.csv and shock_rear.csv, as the example uses them. */
static void test_example(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load("../examples/apc6x6_shock_table.yaml", &s, &err) == FB_OK);
  if (!s) {
    fprintf(stderr, "%s\n", err.msg);
    return;
  }
  for (int c = 0; c < APC_NCORNERS; ++c) {
    const fb_corner_params *p = &s->corner[c];
    const int rear = c >= APC_LR;
    const fb_damper_table_params *t = du_damper_table(p);
    CHECK(t && t->npoints == 9);
    CHECK(t && t->velocity[0] == -1.0 && t->velocity[8] == 1.0 && t->velocity[4] == 0.0);
    CHECK(t && t->force[0] == (rear ? -32201.0 : -20904.0));
    CHECK(t && t->force[8] == (rear ? 13800.0 : 8959.0));
  }
  fb_result *r = simulate_rigid(s);
  CHECK(r != NULL);
  fb_result_free(&r);
  fb_scenario_free(&s);
}

/* A YAML variant of the example with the front axle's damper replaced
 * (the first damper_c line is the front axle's, of corners LF and RF),
 * only checked. */
static int load_with_lf(const char *lf_damper, fb_err *err)
{
  return load_replaced("      damper_c: 25744", 0, "\n", lf_damper, NULL, err);
}

static void expect_refused(const char *lf_damper, const char *phrase)
{
  fb_err err;
  fb_err_clear(&err);
  CHECK(load_with_lf(lf_damper, &err) != FB_OK);
  CHECK(strstr(err.msg, phrase) != NULL);
  CHECK(strstr(err.msg, "bad.yaml:") != NULL);
  if (!strstr(err.msg, phrase))
    fprintf(stderr, "  message: %s\n", err.msg);
}

static void test_errors(void)
{
  fb_err err;
  /* The replacement itself loads when it is good. */
  CHECK(load_with_lf("      damper_table: {points: [[-1, -30000], [0, 0], [1, 20000]]}",
                     &err) == FB_OK);
  expect_refused("      damper_c: 1\n      damper_table: {points: [[-1, -1], [1, 1]]}",
                 "give either 'damper_c' or 'damper_table'");
  /* Pushing when extended: a damper that delivers power. */
  expect_refused("      damper_table: {points: [[-1, 100], [0, 0], [1, 20000]]}", "passive");
  expect_refused("      damper_table: {points: [[1, 100], [0, 0]]}", "strictly increasing");
  expect_refused("      damper_table: {file: missing.csv, force: F}", "missing.csv");
}

int main(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &s, &err) == FB_OK);
  if (s)
    test_linear_table(s);
  fb_scenario_free(&s);
  test_example();
  test_errors();
  return check_report("test_shock_table");
}
