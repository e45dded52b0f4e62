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

#include "check.h"

static fb_result *simulate(const fb_scenario *s)
{
  fb_err err;
  fb_result *r = NULL;
  if (fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err) != FB_OK) {
    fprintf(stderr, "simulate: %s\n", err.msg);
    CHECK(0);
  }
  return r;
}

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
  for (int c = 0; c < FB_NCORNERS; ++c) {
    fb_corner_params *p = &tab->corner[c];
    const double v[3] = {-2.0, 0.0, 2.0};
    p->damper_npoints = 3;
    for (int i = 0; i < 3; ++i) {
      p->damper_v[i] = v[i];
      p->damper_f[i] = lin->corner[c].damper_c * v[i];
    }
    p->damper_c = 0.0;
  }
  fb_result *a = simulate(lin), *b = simulate(tab);
  if (a && b) {
    CHECK(fb_result_nsamples(a) == fb_result_nsamples(b));
    for (size_t col = 1; col < fb_result_ncols(a); ++col) {
      double lo = INFINITY, hi = -INFINITY, worst = 0.0;
      for (size_t k = 0; k < fb_result_nsamples(a); ++k) {
        const double va = fb_result_row(a, k)[col], vb = fb_result_row(b, k)[col];
        lo = fmin(lo, va);
        hi = fmax(hi, va);
        worst = fmax(worst, fabs(va - vb));
      }
      const double range = hi - lo;
      if (range > 0.0) {
        fprintf(stderr, "linear table vs damper_c: %-16s %.3g of range\n",
                fb_result_col_name(a, col), worst / range);
        CHECK(worst <= 1e-8 * range);
      } else {
        CHECK(worst == 0.0);
      }
    }
  }
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
  for (int c = 0; c < FB_NCORNERS; ++c) {
    const fb_corner_params *p = &s->corner[c];
    const int rear = c >= FB_LR;
    CHECK(p->damper_npoints == 9);
    CHECK(p->damper_v[0] == -1.0 && p->damper_v[8] == 1.0 && p->damper_v[4] == 0.0);
    CHECK(p->damper_f[0] == (rear ? -32201.0 : -20904.0));
    CHECK(p->damper_f[8] == (rear ? 13800.0 : 8959.0));
  }
  fb_result *r = simulate(s);
  CHECK(r != NULL);
  fb_result_free(&r);
  fb_scenario_free(&s);
}

/* A YAML variant of the example with the LF corner's damper replaced. */
static int load_with_lf(const char *lf_damper, fb_err *err)
{
  FILE *fp = fopen("../examples/apc6x6.yaml", "rb");
  if (!fp)
    return FB_EIO;
  char *text = calloc(1, 1 << 16);
  const size_t len = text ? fread(text, 1, (1 << 16) - 1, fp) : 0;
  fclose(fp);
  if (!text)
    return FB_ENOMEM;
  text[len] = '\0';
  /* The first damper_c line is the LF corner's. */
  char *at = strstr(text, "    damper_c: 25744");
  char *eol = at ? strchr(at, '\n') : NULL;
  int rc = FB_EINVAL;
  if (at && eol) {
    char *out = malloc(len + strlen(lf_damper) + 2);
    if (out) {
      const size_t head = (size_t)(at - text);
      memcpy(out, text, head);
      strcpy(out + head, lf_damper);
      strcat(out, eol);
      fb_scenario *s = NULL;
      rc = fb_scenario_load_string(out, strlen(out), "bad.yaml", &s, err);
      fb_scenario_free(&s);
      free(out);
    }
  }
  free(text);
  return rc;
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
  CHECK(load_with_lf("    damper_table: {points: [[-1, -30000], [0, 0], [1, 20000]]}", &err) ==
        FB_OK);
  expect_refused("    damper_c: 1\n    damper_table: {points: [[-1, -1], [1, 1]]}",
                 "either damper_c or damper_table");
  /* Pushing when extended: a damper that delivers power. */
  expect_refused("    damper_table: {points: [[-1, 100], [0, 0], [1, 20000]]}", "passive");
  expect_refused("    damper_table: {points: [[1, 100], [0, 0]]}", "strictly increasing");
  expect_refused("    damper_table: {file: missing.csv, force: F}", "missing.csv");
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
