/* SPDX-License-Identifier: BSD-3-Clause */
/* Helpers of the vehicle tests (test_contact.c, test_shock_table.c,
 * test_road_scenario.c, test_antiroll_bar.c, test_bogie.c): simulate
 * System 1, compare two runs output by output, load the example scenario
 * with part of its text replaced, and compare the two systems' modes in
 * the rigid limit.
 * Header-only test helper (static inline functions); include after
 * check.h. */
#ifndef FLEXBOND_TESTS_VEHICLE_UTIL_H
#define FLEXBOND_TESTS_VEHICLE_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "road_util.h"

/* Stops the test at a failed call, printing the library's message. */
#define REQUIRE(call, err)                                                                     \
  do {                                                                                         \
    if ((call) != FB_OK) {                                                                     \
      fprintf(stderr, "%s:%d: %s\n", __FILE__, __LINE__, (err)->msg);                          \
      CHECK(0);                                                                                \
      exit(check_report(__FILE__));                                                            \
    }                                                                                          \
  } while (0)

/* The scenario at path (the reference one or a variant of it) on a
 * shortened crossing (bump at 1 s, 0.5 m long, 3 s in all), so that
 * full-order System 2 runs take seconds; the physics is the scenario's. */
static inline fb_scenario *load_short_from(const char *path)
{
  fb_err err;
  fb_scenario *s = NULL;
  REQUIRE(fb_scenario_load(path, &s, &err), &err);
  road_bump(s)->first_contact = 1.0;
  road_bump(s)->length = 0.5;
  s->t_end = 3.0;
  return s;
}

/* The reference scenario on that shortened crossing. */
static inline fb_scenario *load_short(void)
{
  return load_short_from("../examples/apc6x6.yaml");
}

/* Peak-to-peak range of column col of r. */
static inline double result_range(const fb_result *r, size_t col)
{
  double lo = INFINITY, hi = -INFINITY;
  for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
    lo = fmin(lo, fb_result_row(r, k)[col]);
    hi = fmax(hi, fb_result_row(r, k)[col]);
  }
  return hi - lo;
}

/* The largest |b - a| of column name over the run, as a share of a's
 * range (the two results on one grid, with the column at one place). */
static inline double result_relative_difference(const fb_result *a, const fb_result *b,
                                                const char *name)
{
  const long col = fb_result_find(a, name);
  CHECK(col > 0 && fb_result_find(b, name) == col);
  if (col <= 0 || fb_result_nsamples(a) != fb_result_nsamples(b))
    return INFINITY;
  double worst = 0.0;
  for (size_t k = 0; k < fb_result_nsamples(a); ++k)
    worst = fmax(worst, fabs(fb_result_row(a, k)[col] - fb_result_row(b, k)[col]));
  return worst / result_range(a, (size_t)col);
}

/* System 1 of s; a failure prints the library's message and fails. */
static inline fb_result *simulate_rigid(const fb_scenario *s)
{
  fb_err err;
  fb_result *r = NULL;
  if (fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err) != FB_OK) {
    fprintf(stderr, "simulate: %s\n", err.msg);
    CHECK(0);
  }
  return r;
}

/* Every output of b within tol of a's peak-to-peak range (printed with
 * what), and exactly equal where a is constant. */
static inline void check_close(const fb_result *a, const fb_result *b, double tol,
                               const char *what)
{
  CHECK(fb_result_nsamples(a) == fb_result_nsamples(b));
  for (size_t col = 1; col < fb_result_ncols(a); ++col) {
    double lo = INFINITY, hi = -INFINITY, worst = 0.0;
    for (size_t k = 0; k < fb_result_nsamples(a); ++k) {
      const double va = fb_result_row(a, k)[col];
      lo = fmin(lo, va);
      hi = fmax(hi, va);
      worst = fmax(worst, fabs(va - fb_result_row(b, k)[col]));
    }
    if (hi > lo) {
      fprintf(stderr, "%s: %-16s %.3g of range\n", what, fb_result_col_name(a, col),
              worst / (hi - lo));
      CHECK(worst <= tol * (hi - lo));
    } else {
      CHECK(worst == 0.0);
    }
  }
}

/* The whole file at path (up to 1 MB) in fresh memory, NULL if unreadable. */
static inline char *read_text(const char *path)
{
  FILE *fp = fopen(path, "rb");
  if (!fp)
    return NULL;
  char *buf = malloc(1 << 20);
  size_t n = buf ? fread(buf, 1, (1 << 20) - 1, fp) : 0;
  fclose(fp);
  if (buf)
    buf[n] = '\0';
  return buf;
}

/* The scenario text yaml, as the file "bad.yaml", with the loader's
 * options (NULL: none); into *out, or freed when out is NULL. */
static inline int load_text_with(const char *yaml, const fb_scenario_load_opts *opts,
                                 fb_scenario **out, fb_err *err)
{
  fb_scenario *s = NULL;
  const int rc = fb_scenario_load_string_with(yaml, strlen(yaml), "bad.yaml", opts, &s, err);
  if (out)
    *out = s;
  else
    fb_scenario_free(&s);
  return rc;
}

/* ../examples/apc6x6.yaml with the text from the first occurrence of
 * start (after its first skip characters) up to the next occurrence of
 * end (kept) replaced by text, loaded as bad.yaml into *out (may be NULL:
 * the scenario is only checked). FB_EIO when the file or the markers are
 * missing. */
static inline int load_replaced_with(const char *start, size_t skip, const char *end,
                                     const char *text, const fb_scenario_load_opts *opts,
                                     fb_scenario **out, fb_err *err)
{
  char *file = read_text("../examples/apc6x6.yaml");
  char *from = file ? strstr(file, start) : NULL;
  char *to = from ? strstr(from + skip, end) : NULL;
  char *yaml = to ? malloc(strlen(file) + strlen(text) + 1) : NULL;
  int rc = FB_EIO;
  if (yaml) {
    const size_t head = (size_t)(from - file) + skip;
    memcpy(yaml, file, head);
    strcpy(yaml + head, text);
    strcat(yaml, to);
    rc = load_text_with(yaml, opts, out, err);
  }
  free(yaml);
  free(file);
  return rc;
}

/* load_replaced with the loader's options (NULL: none). */
static inline int load_replaced(const char *start, size_t skip, const char *end,
                                const char *text, fb_scenario **out, fb_err *err)
{
  return load_replaced_with(start, skip, end, text, NULL, out, err);
}

/* The weight the tires carry at rest: the load, the mounted bodies, the
 * wheels (N). */
static inline double vehicle_weight(const fb_scenario *s)
{
  double w = s->total_weight;
  for (size_t b = 0; b < s->nmounts; ++b)
    w += s->mount[b].mass * s->gravity;
  for (size_t c = 0; c < s->ncorners; ++c)
    w += s->corner[c].wheel_mass * s->gravity;
  return w;
}

/* The sum of the tire spring forces at state x of the vehicle's block
 * diagram bd: each tire's deflection is its spring's state, k_t times it
 * (compression positive). */
static inline double tire_spring_sum(const fb_scenario *s, const fb_bd *bd, const double *x)
{
  double sum = 0.0;
  for (size_t c = 0; c < s->ncorners; ++c) {
    char want[64];
    snprintf(want, sizeof want, "susp_%s.tire_spring.q", s->corner[c].name);
    for (size_t i = 0; i < fb_bd_nstates(bd); ++i)
      if (!strcmp(fb_bd_state_name(bd, i), want))
        sum += s->corner[c].tire_k * x[i];
  }
  return sum;
}

/* At the static state x of bd, the tires carry the whole weight: the
 * force balance holds to 1e-10 of the weight per DOF (the static
 * solver's tolerance), so 1e-8 relative for the sum over the tires. */
static inline void check_tires_carry_weight(const fb_scenario *s, const fb_bd *bd,
                                            const double *x, const char *what)
{
  const double sum = tire_spring_sum(s, bd, x), expect = vehicle_weight(s);
  fprintf(stderr, "%s: sum of tire spring forces %.10g N, weight %.10g N\n", what, sum, expect);
  CHECK_NEAR(sum, expect, 1e-8 * expect);
}

/* err's message holds want; else both are shown. */
static inline void check_message(const fb_err *err, const char *want)
{
  const int found = strstr(err->msg, want) != NULL;
  CHECK(found);
  if (!found)
    fprintf(stderr, "  want %s\n  got  %s\n", want, err->msg);
}

/* The value of an override key=value out of its range, refused at that
 * key of the file (a line, then ": <key>: must be"). */
static inline void check_refused_at(const fb_err *err, const char *key, const char *value)
{
  char want[200];
  snprintf(want, sizeof want, ": %s: must be", key);
  const int located = strstr(err->msg, want) && err->line > 0;
  CHECK(located);
  if (!located)
    fprintf(stderr, "  %s=%s: %s\n", key, value, err->msg);
}

/* System 2's undamped modes of s in the rigid limit (its hull 100 times
 * stiffer; s->young restored) against System 1's, both the exact ones
 * (the whole sparse matrices) and the modal basis's (at least nreduced of
 * them: the basis keeps the modes its band covers): ratio 1 within 5e-4,
 * test_system2_modes.c's bound for the paper's 6x6 (the hull's
 * flexibility moves them by ~1.3e-4 at 100 E). */
static inline void check_rigid_limit(fb_scenario *s, size_t nreduced)
{
  fb_err err;
  fb_mode *rigid = NULL;
  size_t nr = 0, nstatic = 0;
  REQUIRE(fb_vehicle_modes(s, FB_SYSTEM_RIGID, 1, &rigid, &nr, &nstatic, &err), &err);
  const double young = s->young;
  s->young *= 100.0;
  fb_vehicle *v = NULL;
  REQUIRE(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, NULL, &v, &err), &err);
  s->young = young;
  for (int exact = 1; exact >= 0; --exact) {
    fb_mode_set *m = NULL;
    REQUIRE(fb_vehicle_structural_modes(v, nr, exact, &m, &err), &err);
    CHECK(exact ? m->nmodes == nr : m->nmodes >= nreduced);
    for (size_t k = 0; k < nr && k < m->nmodes; ++k) {
      fprintf(stderr, "%s %zu: System 1 %.8g Hz (%s), System 2 at 100 E %.8g Hz\n",
              exact ? "exact" : "reduced", k + 1, rigid[k].freq_hz, rigid[k].description,
              m->freq_hz[k]);
      CHECK_NEAR(m->freq_hz[k] / rigid[k].freq_hz, 1.0, 5e-4);
    }
    fb_mode_set_free(&m);
  }
  fb_vehicle_free(&v);
  free(rigid);
}

#endif
