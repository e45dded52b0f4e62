/* Tire contact verdict (fb_vehicle_tension_intervals, src/vehicle/contact.c)
 * on System 1: the paper's crossing keeps every tire in compression; a
 * 0.20 m bump at 30 km/h makes five tires pull their wheels down, and the
 * intervals must agree with a brute-force scan of the samples. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/model.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle_util.h"

static long column(const fb_result *r, const char *prefix, int corner)
{
  char name[32];
  snprintf(name, sizeof name, "%s%s", prefix, fb_corner_name(corner));
  return fb_result_find(r, name);
}

/* Every sample with a negative reaction lies in an interval of its tire,
 * every interval holds one at least, and its minimum is the samples'. */
static void check_against_scan(const fb_result *r, const fb_tension_interval *iv, size_t n)
{
  for (int c = 0; c < FB_NCORNERS; ++c) {
    const long col = column(r, "contact_force_", c);
    CHECK(col > 0);
    if (col < 1)
      return;
    size_t negative = 0, covered = 0;
    for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
      const double *row = fb_result_row(r, k);
      if (!(row[col] < 0.0))
        continue;
      ++negative;
      for (size_t i = 0; i < n; ++i)
        if (iv[i].corner == c && row[0] >= iv[i].t_start && row[0] <= iv[i].t_end) {
          ++covered;
          CHECK(row[col] >= iv[i].min_force);
          break;
        }
    }
    CHECK(covered == negative);
    for (size_t i = 0; i < n; ++i) {
      if (iv[i].corner != c)
        continue;
      CHECK(iv[i].t_start < iv[i].t_min && iv[i].t_min < iv[i].t_end);
      CHECK(iv[i].min_force < 0.0);
      /* The minimum is a sample's value at its time. */
      const size_t k = (size_t)llround(iv[i].t_min * 1000.0);
      CHECK(fb_result_row(r, k)[col] == iv[i].min_force);
    }
  }
}

static void test_paper_crossing(const fb_scenario *s)
{
  fb_result *r = simulate_rigid(s);
  if (!r)
    return;
  /* The seven outputs, then the six reactions; LF is the paper's Fig. 8. */
  const long lf = column(r, "contact_force_", FB_LF), fig8 = fb_result_find(r, "tire_force_LF");
  CHECK(lf == 1 + FB_NOUTPUTS && fig8 == 1);
  for (size_t k = 0; lf > 0 && fig8 > 0 && k < fb_result_nsamples(r); k += 97)
    CHECK(fb_result_row(r, k)[lf] == fb_result_row(r, k)[fig8]);
  fb_err err;
  fb_tension_interval *iv = NULL;
  size_t n = 99;
  CHECK(fb_vehicle_tension_intervals(r, &iv, &n, &err) == FB_OK);
  CHECK(n == 0 && iv == NULL);
  check_against_scan(r, iv, n);
  free(iv);
  fb_result_free(&r);
}

static void test_lift_off(fb_scenario *s)
{
  s->bump_height = 0.20;
  s->speed = 30.0 / 3.6;
  fb_result *r = simulate_rigid(s);
  if (!r)
    return;
  fb_err err;
  fb_tension_interval *iv = NULL;
  size_t n = 0;
  CHECK(fb_vehicle_tension_intervals(r, &iv, &n, &err) == FB_OK);
  fprintf(stderr, "0.20 m bump at 30 km/h: %zu tensile intervals\n", n);
  for (size_t i = 0; i < n; ++i)
    fprintf(stderr, "  %s %.4f .. %.4f s, down to %.1f N at %.3f s\n",
            fb_corner_name(iv[i].corner), iv[i].t_start, iv[i].t_end, iv[i].min_force,
            iv[i].t_min);
  CHECK(n >= 4);
  check_against_scan(r, iv, n);
  free(iv);
  fb_result_free(&r);
}

/* A result without the reactions (a model's own probes) is refused. */
static void test_missing_columns(void)
{
  static const char text[] = "model: m\n"
                             "elements:\n"
                             "  - {name: F, type: Se, value: 1}\n"
                             "  - {name: v, type: 1}\n"
                             "  - {name: M, type: I, m: 1}\n"
                             "  - {name: D, type: R, r: 1}\n"
                             "bonds:\n"
                             "  - [F, v]\n"
                             "  - {name: b, from: v, to: M}\n"
                             "  - [v, D]\n"
                             "probes:\n"
                             "  - {name: vel, flow: b}\n"
                             "simulation: {t_end: 0.1}\n";
  fb_err err;
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  fb_result *r = NULL;
  size_t np = 0;
  CHECK(fb_model_load_string(text, strlen(text), "m.yaml", NULL, &m, &err) == FB_OK);
  if (!m)
    fprintf(stderr, "model: %s\n", err.msg);
  if (m) {
    const fb_probe_spec *p = fb_model_probes(m, &np);
    CHECK(fb_bd_build(fb_model_graph(m), p, np, &bd, &err) == FB_OK);
  }
  if (bd)
    CHECK(fb_sim_run(bd, fb_model_sim_opts(m), &r, &err) == FB_OK);
  if (r) {
    fb_tension_interval *iv = NULL;
    size_t n = 0;
    CHECK(fb_vehicle_tension_intervals(r, &iv, &n, &err) == FB_EINVAL);
    CHECK(strstr(err.msg, "contact_force_LF") != NULL);
    CHECK(iv == NULL && n == 0);
  }
  fb_result_free(&r);
  fb_bd_free(&bd);
  fb_model_free(&m);
}

int main(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &s, &err) == FB_OK);
  if (s) {
    test_paper_crossing(s);
    test_lift_off(s);
  }
  test_missing_columns();
  fb_scenario_free(&s);
  return check_report("test_contact");
}
