/* Helpers of the vehicle tests (test_contact.c, test_shock_table.c,
 * test_road_scenario.c): simulate System 1, compare two runs output by
 * output, and load the example scenario with part of its text replaced.
 * Header-only test helper (static inline functions); include after
 * check.h. */
#ifndef FLEXBOND_TESTS_VEHICLE_UTIL_H
#define FLEXBOND_TESTS_VEHICLE_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

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

/* ../examples/apc6x6.yaml with the text from the first occurrence of
 * start (after its first skip characters) up to the next occurrence of
 * end (kept) replaced by text, loaded as bad.yaml into *out (may be NULL:
 * the scenario is only checked). FB_EIO when the file or the markers are
 * missing. */
static inline int load_replaced(const char *start, size_t skip, const char *end,
                                const char *text, fb_scenario **out, fb_err *err)
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
    fb_scenario *s = NULL;
    rc = fb_scenario_load_string(yaml, strlen(yaml), "bad.yaml", &s, err);
    if (out)
      *out = s;
    else
      fb_scenario_free(&s);
  }
  free(yaml);
  free(file);
  return rc;
}

#endif
