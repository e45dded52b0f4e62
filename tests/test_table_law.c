/* SPDX-License-Identifier: BSD-3-Clause */
/* Tabulated R laws (fb_table_law, src/bg/table_law.c) and their model
 * syntax `table:` (src/io/model_elements.c): the Fritsch-Carlson
 * interpolant against hand calculations, its C1 continuity, monotonicity,
 * Jacobian and co-content against second methods, passivity, CSV and
 * model-file errors, and the quarter car with a tabulated damper. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"
#include "flexbond/model.h"
#include "flexbond/sim.h"

#include "check.h"
#include "tmpdir.h"

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

static fb_table_law *make_law(size_t n, const double *x, const double *y)
{
  fb_err err;
  fb_table_law *law = NULL;
  int rc = fb_table_law_new(n, x, y, &law, &err);
  CHECK(rc == FB_OK && law != NULL);
  if (rc)
    fprintf(stderr, "  fb_table_law_new: %s\n", err.msg);
  return law;
}

static double max_abs(size_t n, const double *v)
{
  double m = 0;
  for (size_t i = 0; i < n; ++i)
    m = fmax(m, fabs(v[i]));
  return m;
}

/* Largest |secant| and smallest knot spacing of a table. */
static void table_scales(size_t n, const double *x, const double *y, double *delta_max,
                         double *h_min)
{
  *delta_max = 0;
  *h_min = INFINITY;
  for (size_t k = 0; k + 1 < n; ++k) {
    double h = x[k + 1] - x[k];
    *h_min = fmin(*h_min, h);
    *delta_max = fmax(*delta_max, fabs((y[k + 1] - y[k]) / h));
  }
}

/* A damper-like table (velocity m/s, force N): uneven spacing, rebound
 * stiffer than compression, degressive. */
static const double damper_v[] = {-1.0, -0.5, -0.25, -0.1, 0, 0.1, 0.25, 0.5, 1.0};
static const double damper_f[] = {-980, -580, -330, -150, 0, 50, 110, 190, 320};

/* Non-monotone data (a local maximum and minimum) with uneven spacing. */
static const double wavy_x[] = {-2, -1.3, -0.2, 0.4, 1.1, 2.5, 3};
static const double wavy_y[] = {-3, 1.5, 2.0, -0.5, -0.6, 4, 4.2};

/* ---- Hand calculations. */

/* Knots (0,0), (1,1), (2,3): secants 1 and 2, so Fritsch-Carlson's
 * derivatives are d = 1 (end secant), 1.5 (mean), 2 (end secant); alpha,
 * beta = (1, 1.5) and (0.75, 1) lie inside the circle of radius 3, no
 * limiting. Hermite basis at the midpoint of [0, 1] (h00 = h01 = 1/2,
 * h10 = 1/8, h11 = -1/8): phi(0.5) = 0.5 * 1 + 1/8 * 1 - 1/8 * 1.5 =
 * 0.4375. Beyond the ends the tangents: phi(3) = 3 + 2 * 1 = 5, phi(-1) =
 * 0 - 1 = -1. All values are dyadic, so only rounding of a few operations
 * separates them from the code's: tolerance 4 ulp. */
static void test_hand_values(void)
{
  const double x[] = {0, 1, 2}, y[] = {0, 1, 3};
  fb_table_law *law = make_law(3, x, y);
  if (!law)
    return;
  double slope = 0;
  CHECK_NEAR(fb_table_law_eval(law, 0.5, &slope), 0.4375, 4 * DBL_EPSILON);
  /* phi'(0.5) = y0 h00' + d0 h10' + y1 h01' + d1 h11' at t = 1/2 with
   * h00' = -1.5, h10' = -0.25, h01' = 1.5, h11' = -0.25: 1.5 - 0.25 - 0.375. */
  CHECK_NEAR(slope, 0.875, 4 * DBL_EPSILON);
  fb_table_law_eval(law, 1.0, &slope);
  CHECK_NEAR(slope, 1.5, 4 * DBL_EPSILON);
  CHECK_NEAR(fb_table_law_eval(law, 3.0, &slope), 5.0, 8 * DBL_EPSILON);
  CHECK_NEAR(slope, 2.0, 4 * DBL_EPSILON);
  CHECK_NEAR(fb_table_law_eval(law, -1.0, &slope), -1.0, 4 * DBL_EPSILON);
  CHECK_NEAR(slope, 1.0, 4 * DBL_EPSILON);
  fb_table_law_free(&law);
  CHECK(law == NULL);
  fb_table_law_free(&law); /* NULL is accepted */
  fb_table_law_free(NULL);
}

/* Knots (0,0), (1,0.1), (2,5): at x = 1 the mean of the secants 0.1 and
 * 4.9 is 2.5, so on [0, 1] alpha = 1, beta = 25, far outside the circle;
 * Fritsch-Carlson scale both by tau = 3 / sqrt(626): d0 = 0.3 / sqrt(626),
 * d1 = 7.5 / sqrt(626). [1, 2] then has alpha = 0.061, beta = 1 and stays.
 * Without the limiter the cubic on [0, 1] would dip to phi(0.3) = -0.10,
 * below both knots; with it phi stays in [0, 0.1] there. */
static void test_limiter(void)
{
  const double x[] = {0, 1, 2}, y[] = {0, 0.1, 5};
  fb_table_law *law = make_law(3, x, y);
  if (!law)
    return;
  double slope = 0;
  fb_table_law_eval(law, 0.0, &slope);
  CHECK_NEAR(slope, 0.3 / sqrt(626.0), 8 * DBL_EPSILON);
  fb_table_law_eval(law, 1.0, &slope);
  CHECK_NEAR(slope, 7.5 / sqrt(626.0), 8 * DBL_EPSILON);
  fb_table_law_eval(law, 2.0 + 1e-9, &slope); /* the end tangent */
  CHECK_NEAR(slope, 4.9, 1e-14 * 4.9);
  int inside = 1;
  for (int i = 0; i <= 1000; ++i) {
    double v = fb_table_law_eval(law, i / 1000.0, NULL);
    inside &= v >= 0 && v <= 0.1 + 1e-16;
  }
  CHECK(inside);
  fb_table_law_free(&law);
}

/* ---- Knots, continuity, monotonicity. */

/* phi(x_k) = y_k, and at every knot phi and phi' from the left (the
 * previous cubic, or the tangent line before the first knot, evaluated one
 * ulp below x_k) equal the values from the right. A jump in phi' would be
 * of the order of the secants; the tolerances are rounding: values and
 * slopes are sums of a few terms each bounded by 9 max|secant| (|d| <= 3
 * |secant| after limiting), so 1e-12 of the scale leaves room for the
 * ulp step times phi' or phi'' and many roundings. */
static void check_knots_c1(size_t n, const double *x, const double *y)
{
  fb_table_law *law = make_law(n, x, y);
  if (!law)
    return;
  double delta_max = 0, h_min = 0;
  table_scales(n, x, y, &delta_max, &h_min);
  double y_tol = 1e-12 * (max_abs(n, y) + delta_max);
  double d_tol = 1e-12 * delta_max;
  for (size_t k = 0; k < n; ++k) {
    double right_slope = 0, left_slope = 0;
    double right = fb_table_law_eval(law, x[k], &right_slope);
    double left = fb_table_law_eval(law, nextafter(x[k], -INFINITY), &left_slope);
    double after = 0, after_slope = 0;
    after = fb_table_law_eval(law, nextafter(x[k], INFINITY), &after_slope);
    CHECK_NEAR(right, y[k], y_tol);
    CHECK_NEAR(left, y[k], y_tol);
    CHECK_NEAR(after, y[k], y_tol);
    CHECK_NEAR(left_slope, right_slope, d_tol);
    CHECK_NEAR(after_slope, right_slope, d_tol);
  }
  fb_table_law_free(&law);
}

static void test_knots_c1(void)
{
  check_knots_c1(COUNT(damper_v), damper_v, damper_f);
  check_knots_c1(COUNT(wavy_x), wavy_x, wavy_y);
  const double two_x[] = {-1, 3}, two_y[] = {2, 7};
  check_knots_c1(2, two_x, two_y);
}

/* Monotone data give a non-decreasing phi on a fine grid spanning the
 * table and beyond (Fritsch & Carlson's theorem), and on every interval
 * phi stays between the interval's knot values. The step-like table is
 * the classic case where a C2 cubic spline overshoots. Tolerance: 4 ulp of
 * the largest value for rounding of the cubic. */
static void check_monotone(size_t n, const double *x, const double *y)
{
  fb_table_law *law = make_law(n, x, y);
  if (!law)
    return;
  double tol = 4 * DBL_EPSILON * max_abs(n, y);
  double lo = x[0] - 1, hi = x[n - 1] + 1, prev = -INFINITY;
  int increasing = 1, bounded = 1;
  size_t k = 0;
  for (int i = 0; i <= 20000; ++i) {
    double v = lo + (hi - lo) * i / 20000.0;
    double phi = fb_table_law_eval(law, v, NULL);
    increasing &= phi >= prev - tol;
    prev = phi;
    while (k + 1 < n && v > x[k + 1])
      ++k;
    if (v >= x[0] && v <= x[n - 1])
      bounded &= phi >= y[k] - tol && phi <= y[k + 1] + tol;
  }
  CHECK(increasing);
  CHECK(bounded);
  fb_table_law_free(&law);
}

static void test_monotone(void)
{
  check_monotone(COUNT(damper_v), damper_v, damper_f);
  const double step_x[] = {0, 1, 2, 3, 4, 5, 5.1};
  const double step_y[] = {0, 0, 1, 1, 1.0001, 10, 30};
  check_monotone(COUNT(step_x), step_x, step_y);
}

/* ---- Jacobian and co-content against second methods. */

/* phi' against the central difference (phi(x + h) - phi(x - h)) / 2h at
 * points at least h away from every knot, so the stencil stays on one
 * cubic. Its error is h^2/6 |phi'''| (truncation) + eps max|phi| / h
 * (rounding). On a piece phi''' = 6 c3 = 6 (d_k + d_k+1 - 2 delta_k) /
 * h_k^2 and |d| <= 3 |delta| after limiting, so |phi'''| <= 48 max|delta|
 * / min(h_k)^2. The tolerance is twice that bound. */
static void check_jacobian_fd(size_t n, const double *x, const double *y)
{
  fb_table_law *law = make_law(n, x, y);
  if (!law)
    return;
  double delta_max = 0, h_min = 0;
  table_scales(n, x, y, &delta_max, &h_min);
  const double h = 1e-5 * h_min;
  double ymax = max_abs(n, y) + delta_max * (x[n - 1] - x[0] + 2);
  double tol = 2 * (h * h / 6 * 48 * delta_max / (h_min * h_min) + DBL_EPSILON * ymax / h);
  int checked = 0;
  for (int i = 0; i <= 997; ++i) {
    double v = x[0] - 1 + (x[n - 1] - x[0] + 2) * i / 997.0;
    int near_knot = 0;
    for (size_t k = 0; k < n; ++k)
      near_knot |= fabs(v - x[k]) < 2 * h;
    if (near_knot)
      continue;
    double slope = 0;
    fb_table_law_eval(law, v, &slope);
    double fd =
        (fb_table_law_eval(law, v + h, NULL) - fb_table_law_eval(law, v - h, NULL)) / (2 * h);
    CHECK_NEAR(slope, fd, tol);
    ++checked;
  }
  CHECK(checked > 900);
  fb_table_law_free(&law);
}

static void test_jacobian_fd(void)
{
  check_jacobian_fd(COUNT(damper_v), damper_v, damper_f);
  check_jacobian_fd(COUNT(wavy_x), wavy_x, wavy_y);
}

/* Simpson's rule on [a, b] (exact for cubics). */
static double simpson(const fb_table_law *law, double a, double b)
{
  return (b - a) / 6 *
         (fb_table_law_eval(law, a, NULL) + 4 * fb_table_law_eval(law, (a + b) / 2, NULL) +
          fb_table_law_eval(law, b, NULL));
}

/* Integral of phi from 0 to v by Simpson's rule on every piece between
 * 0, the knots and v: exact for the cubic pieces and the tangent lines,
 * so it differs from the closed form only by rounding. */
static double simpson_from_zero(const fb_table_law *law, size_t n, const double *x, double v)
{
  double lo = fmin(0, v), hi = fmax(0, v), sum = 0, a = lo;
  for (size_t k = 0; k < n; ++k) {
    if (x[k] > a && x[k] < hi) {
      sum += simpson(law, a, x[k]);
      a = x[k];
    }
  }
  sum += simpson(law, a, hi);
  return v >= 0 ? sum : -sum;
}

/* The co-content against Simpson's rule, inside the table, at knots and
 * beyond both ends; 1e-12 of |v| max|phi| covers the rounding of both
 * sums. For the damper table it is >= 0 (a passive law's co-content). */
static void check_integral(size_t n, const double *x, const double *y)
{
  fb_table_law *law = make_law(n, x, y);
  if (!law)
    return;
  const double probes[] = {-3.1, -1.0, -0.7, -0.1, -1e-3, 0, 0.05, 0.3, 1.0, 1.7, 4.0};
  for (size_t i = 0; i < COUNT(probes); ++i) {
    double v = probes[i];
    double scale = fabs(v) * (fabs(fb_table_law_eval(law, v, NULL)) + max_abs(n, y));
    CHECK_NEAR(fb_table_law_integral(law, v), simpson_from_zero(law, n, x, v),
               1e-12 * scale + 1e-300);
  }
  fb_table_law_free(&law);
}

static void test_integral(void)
{
  check_integral(COUNT(damper_v), damper_v, damper_f);
  check_integral(COUNT(wavy_x), wavy_x, wavy_y);
}

/* ---- A linear damper table is the linear law. */

/* F = c v at uneven knots: every secant is c, so every d is c (the mean of
 * equal secants), c2 = c3 = 0 and phi is c v, also beyond the ends, with
 * phi' = c and co-content c v^2 / 2. Rounding only: 1e-14 relative. */
static void test_linear_law(void)
{
  const double c = 1000;
  const double v[] = {-2, -0.5, 0, 0.3, 0.7, 2};
  double f[COUNT(v)];
  for (size_t i = 0; i < COUNT(v); ++i)
    f[i] = c * v[i];
  fb_table_law *law = make_law(COUNT(v), v, f);
  if (!law)
    return;
  for (int i = 0; i <= 400; ++i) {
    double s = -4 + 8 * i / 400.0, slope = 0;
    CHECK_NEAR(fb_table_law_eval(law, s, &slope), c * s, 1e-14 * c * 4);
    CHECK_NEAR(slope, c, 1e-14 * c);
    CHECK_NEAR(fb_table_law_integral(law, s), c * s * s / 2, 1e-14 * c * 16);
  }
  fb_err err;
  CHECK(fb_table_law_check_passive(law, &err) == FB_OK);
  fb_table_law_free(&law);
}

/* ---- Passivity. */

static void check_passive(size_t n, const double *x, const double *y, int want,
                          const char *phrase)
{
  fb_table_law *law = make_law(n, x, y);
  if (!law)
    return;
  fb_err err;
  fb_err_clear(&err);
  int rc = fb_table_law_check_passive(law, &err);
  CHECK(rc == want);
  CHECK(!phrase || strstr(DESCRIBED(&err), phrase));
  if (rc != want || (phrase && !strstr(DESCRIBED(&err), phrase)))
    fprintf(stderr, "  passivity: rc %d, message: %s\n", rc, err.msg);
  fb_table_law_free(&law);
}

static void test_passivity(void)
{
  /* Passive: the damper; a line through 0 without a knot there (phi(0) =
   * -2 + 1 * 2 = 0); a table of positive velocities whose left tangent
   * line passes through 0 (slope 2); a saturating end (slope 0). */
  check_passive(COUNT(damper_v), damper_v, damper_f, FB_OK, NULL);
  const double line_x[] = {-1, 1}, line_y[] = {-2, 2};
  check_passive(2, line_x, line_y, FB_OK, NULL);
  const double pos_x[] = {0.5, 1}, pos_y[] = {1, 2};
  check_passive(2, pos_x, pos_y, FB_OK, NULL);
  const double sat_x[] = {-1, 0, 1, 2}, sat_y[] = {-1, 0, 1, 1};
  check_passive(4, sat_x, sat_y, FB_OK, NULL);
  /* Not passive: a knot pushing along the motion; phi(0) = 1 (a preload,
   * the line through (-1, -1) and (1, 3)); a rebound end whose force falls
   * off, so the tangent line reaches positive forces at large rebound. */
  const double sign_x[] = {-1, 0, 0.5, 1}, sign_y[] = {-1, 0, -0.2, 1};
  check_passive(4, sign_x, sign_y, FB_EINVAL, "at point 3 phi(0.5) = -0.2");
  const double pre_x[] = {-1, 1}, pre_y[] = {-1, 3};
  check_passive(2, pre_x, pre_y, FB_EINVAL, "phi(0) = 1");
  const double fall_x[] = {-2, -1, 0, 1}, fall_y[] = {-1, -2, 0, 1};
  check_passive(4, fall_x, fall_y, FB_EINVAL, "before the first point");
  const double fall2_x[] = {-1, 0, 1, 2}, fall2_y[] = {-1, 0, 2, 1.5};
  check_passive(4, fall2_x, fall2_y, FB_EINVAL, "after the last point");

  /* fb_bg_add_r_table refuses it and frees the law. */
  fb_err err;
  fb_bg *bg = NULL;
  CHECK(fb_bg_new("g", &bg, &err) == FB_OK);
  fb_table_law *law = make_law(2, pre_x, pre_y);
  CHECK(fb_bg_add_r_table(bg, "D", &law, &err) == FB_EINVAL && law == NULL);
  CHECK(strstr(DESCRIBED(&err), "R 'D': table law is not passive") != NULL);
  CHECK(fb_bg_find_element(bg, "D") < 0);
  law = make_law(COUNT(damper_v), damper_v, damper_f);
  CHECK(fb_bg_add_r_table(bg, "D", &law, &err) == FB_OK && law == NULL);
  long e = fb_bg_find_element(bg, "D");
  CHECK(e >= 0 && fb_bg_element_kind(bg, (size_t)e) == FB_BG_R &&
        fb_bg_element_dim(bg, (size_t)e) == 1);
  /* A duplicate name fails in the graph, which still frees the law. */
  law = make_law(COUNT(damper_v), damper_v, damper_f);
  CHECK(fb_bg_add_r_table(bg, "D", &law, &err) != FB_OK && law == NULL);
  CHECK(fb_bg_add_r_table(bg, "E", NULL, &err) == FB_EINVAL);
  fb_bg_free(&bg);
}

/* ---- Construction errors. */

static void test_new_errors(void)
{
  fb_err err;
  fb_table_law *law = NULL;
  const double x[] = {0, 1, 1, 2}, y[] = {0, 1, 2, NAN};
  CHECK(fb_table_law_new(1, x, y, &law, &err) == FB_EINVAL && law == NULL);
  CHECK(strstr(DESCRIBED(&err), "at least 2 points (got 1)") != NULL);
  CHECK(fb_table_law_new(3, x, y, &law, &err) == FB_EINVAL && law == NULL);
  CHECK(strstr(DESCRIBED(&err), "point 3 (x = 1) does not exceed point 2 (x = 1)") != NULL);
  const double x2[] = {0, 1, 2, 3};
  CHECK(fb_table_law_new(4, x2, y, &law, &err) == FB_EINVAL && law == NULL);
  CHECK(strstr(DESCRIBED(&err), "point 4 (3, nan) is not finite") != NULL);
  CHECK(fb_table_law_new(2, NULL, y, &law, &err) == FB_EINVAL);
  CHECK(fb_table_law_new(2, x, y, NULL, &err) == FB_EINVAL);
}

/* ---- CSV files. */

static const char *tmp_dir; /* the private directory (tmpdir.h) */

static const char *tmp_path(const char *name)
{
  static char path[TEST_PATH_MAX];
  snprintf(path, sizeof path, "%s/%s", tmp_dir, name);
  return path;
}

static int write_file(const char *name, const char *text)
{
  FILE *fp = fopen(tmp_path(name), "w");
  if (!fp)
    return 0;
  fputs(text, fp);
  return fclose(fp) == 0;
}

/* A valid file with comments, blank lines, spaces and an extra column:
 * the law reproduces its knots. */
static void test_csv_read(void)
{
  CHECK(write_file("ok.csv", "# damper\n\n  F , extra, v\n-100, 7, -0.5\n# mid\n 0,7,0\n"
                             "40 ,7, 0.25\r\n90, 7, 1\n"));
  fb_err err;
  fb_table_law *law = NULL;
  int rc = fb_table_law_read_csv(tmp_path("ok.csv"), "v", "F", &law, &err);
  CHECK(rc == FB_OK);
  if (rc) {
    fprintf(stderr, "  %s\n", err.msg);
    remove(tmp_path("ok.csv"));
    return;
  }
  CHECK_NEAR(fb_table_law_eval(law, -0.5, NULL), -100, 0);
  CHECK_NEAR(fb_table_law_eval(law, 0, NULL), 0, 0);
  CHECK_NEAR(fb_table_law_eval(law, 0.25, NULL), 40, 0);
  CHECK_NEAR(fb_table_law_eval(law, 1, NULL), 90, 1e-12 * 90);
  fb_table_law_free(&law);
  remove(tmp_path("ok.csv"));
}

typedef struct csv_case {
  const char *text; /* NULL: the file does not exist */
  int code;
  const char *phrase; /* expected in the message after "PATH" */
} csv_case;

static void test_csv_errors(void)
{
  static const csv_case cases[] = {
      {NULL, FB_EIO, ""},
      {"# only a comment\n\n", FB_EPARSE, ":2: no header line"},
      {"v, G\n0, 0\n1, 1\n", FB_EPARSE, ":1: no column 'F' among the header's 2 fields"},
      {"v, F\n0, 0\n1, x\n", FB_EPARSE, ":3: column 'F': not a number (read: 'x')"},
      {"v, F\n0, 0\n1, inf\n", FB_EPARSE, ":3: column 'F': not a finite number (read: 'inf')"},
      {"v, F\n0, 0\n1, 0x10\n", FB_EPARSE,
       ":3: column 'F': not a decimal number (read: '0x10')"},
      {"v,F,F\n-1,-100,0\n0,0,0\n1,100,0\n", FB_EPARSE, ":1: column 'F' appears twice"},
      {"v, F\n0, 0\n1\n", FB_EPARSE, ":3: expected 2 fields as in the header, found 1"},
      {"v, F\n0, 0\n# c\n0.5, 1\n0.5, 2\n", FB_EPARSE,
       ":5: column 'v': 0.5 does not exceed the previous row's 0.5"},
      {"v, F\n0, 0\n", FB_EPARSE, ":2: a table law needs at least 2 rows (got 1)"},
  };
  for (size_t i = 0; i < COUNT(cases); ++i) {
    const csv_case *cc = &cases[i];
    char name[32];
    snprintf(name, sizeof name, "bad%zu.csv", i);
    if (cc->text)
      CHECK(write_file(name, cc->text));
    char want[1024];
    snprintf(want, sizeof want, "%s%s", tmp_path(name), cc->phrase);
    fb_err err;
    fb_table_law *law = NULL;
    int rc = fb_table_law_read_csv(tmp_path(name), "v", "F", &law, &err);
    int ok = rc == cc->code && law == NULL && strstr(DESCRIBED(&err), want);
    CHECK(ok);
    if (!ok)
      fprintf(stderr, "  csv case %zu: rc %s, message: %s\n", i, fb_status_name(rc), err.msg);
    remove(tmp_path(name));
  }
}

/* Bytes that are no text: a NUL inside a line used to end it there, so
 * the rest of the table was silently dropped; a UTF-8 byte-order mark
 * (spreadsheets write one) is skipped. */
static void test_csv_bytes(void)
{
  static const char nul[] = "v,F\n-1.0,-980\n-0.5,-580\n0,0\0\n0.5,300\n1.0,500\n";
  FILE *fp = fopen(tmp_path("nul.csv"), "wb");
  CHECK(fp && fwrite(nul, 1, sizeof nul - 1, fp) == sizeof nul - 1 && fclose(fp) == 0);
  fb_err err;
  fb_table_law *law = NULL;
  CHECK(fb_table_law_read_csv(tmp_path("nul.csv"), "v", "F", &law, &err) == FB_EPARSE);
  CHECK(law == NULL &&
        strstr(DESCRIBED(&err), ":4: binary data (byte 0x00 in column 4): not a CSV text "
                                "file (expected UTF-8 text)"));
  remove(tmp_path("nul.csv"));
  CHECK(write_file("bom.csv", "\xEF\xBB\xBFv,F\n-1,-2\n0,0\n1,2\n"));
  CHECK(fb_table_law_read_csv(tmp_path("bom.csv"), "v", "F", &law, &err) == FB_OK);
  const double *v = NULL, *f = NULL;
  CHECK(law && fb_table_law_knots(law, &v, &f) == 3 && v[0] == -1 && f[2] == 2);
  fb_table_law_free(&law);
  remove(tmp_path("bom.csv"));
}

/* ---- Model files. */

typedef struct model_case {
  const char *element; /* the line after "elements:\n" */
  int code;
  const char *col_of; /* the message locates line 3 at this text of the line */
  const char *phrase; /* expected in the message */
} model_case;

static void test_model_errors(void)
{
  CHECK(write_file("d.csv", "v, F\n-1, -10\n0, 0\n1, 5\n"));
  CHECK(write_file("dup.csv", "v, F\n-1, -10\n0, 0\n# c\n0, 5\n"));
  static const model_case cases[] = {
      {"  - {name: D, type: R, table: {file: none.csv, force: F}}", FB_EIO, "none.csv",
       "none.csv"},
      {"  - {name: D, type: R, table: {file: d.csv, velocity: vel, force: F}}", FB_EPARSE,
       "d.csv", "d.csv:1: no column 'vel' among the header's 2 fields"},
      {"  - {name: D, type: R, table: {file: d.csv}}", FB_EPARSE, "{file",
       "missing required key 'force'"},
      {"  - {name: D, type: R, table: {file: dup.csv, force: F}}", FB_EPARSE, "dup.csv",
       "dup.csv:5: column 'v': 0 does not exceed the previous row's 0"},
      {"  - {name: D, type: R, table: {points: [[-1, -2], [1, 2], [0.5, 3]]}}", FB_EINVAL,
       "[0.5", "table.points[2]: velocities must be strictly increasing: 0.5 does not exceed"},
      {"  - {name: D, type: R, table: {points: [[0, 0]]}}", FB_EMODEL, "[[0",
       "a table needs at least 2 points (got 1)"},
      {"  - {name: D, type: R, table: {points: [[0, 0], [1]]}}", FB_EMODEL, "[1]",
       "expected 2 values, got 1"},
      {"  - {name: D, type: R, table: {points: [[-1, -1], [1, 3]]}}", FB_EINVAL, "{points",
       "R 'D': table law is not passive: phi(0) = 1"},
      {"  - {name: D, type: R, r: 5, table: {points: [[0, 0], [1, 1]]}}", FB_EPARSE, "r: 5",
       "give either 'table' or 'r', not both"},
      {"  - {name: D, type: R, dim: 2, table: {points: [[0, 0], [1, 1]]}}", FB_EPARSE, "dim",
       "give either 'table' or 'dim', not both"},
      {"  - {name: D, type: R, table: {points: [[0, 0], [1, 1]], file: d.csv}}", FB_EPARSE,
       "{points", "a table has either 'points' or 'file'"},
      {"  - {name: D, type: R, table: {file: d.csv, forse: F}}", FB_EPARSE, "forse",
       "unknown key 'forse' (did you mean 'force'?)"},
      {"  - {name: D, type: C, table: {file: d.csv, force: F}}", FB_EPARSE, "table",
       "unknown key 'table'"},
      {"  - {name: D, type: R}", FB_EPARSE, "{name",
       "missing required key 'r' (or 'matrix' or 'table')"},
  };
  for (size_t i = 0; i < COUNT(cases); ++i) {
    const model_case *mc = &cases[i];
    char text[512], want[64];
    snprintf(text, sizeof text, "model: bad\nelements:\n%s\n", mc->element);
    snprintf(want, sizeof want,
             "bad.yaml:3:%d:", (int)(strstr(mc->element, mc->col_of) - mc->element + 1));
    fb_err err;
    fb_model *m = NULL;
    int rc = fb_model_load_string(text, strlen(text), "bad.yaml", tmp_dir, &m, &err);
    int ok = rc == mc->code && m == NULL && strstr(DESCRIBED(&err), want) &&
             strstr(DESCRIBED(&err), mc->phrase);
    CHECK(ok);
    if (!ok)
      fprintf(stderr, "  model case %zu: rc %s (want %s), want '%s', message:\n    %s\n", i,
              fb_status_name(rc), fb_status_name(mc->code), want, err.msg);
    fb_model_free(&m);
  }
  /* An inline table and a file table both load as one-port R elements. */
  const char good[] =
      "model: good\nparameters: {c: 800}\nelements:\n"
      "  - {name: A, type: R, table: {points: [[-1, -c], [0, 0], [2, 1.5 * c]]}}\n"
      "  - {name: B, type: R, table: {file: d.csv, force: F}}\n";
  fb_err err;
  fb_model *m = NULL;
  int rc = fb_model_load_string(good, strlen(good), "good.yaml", tmp_dir, &m, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  %s\n", err.msg);
  for (int i = 0; m && i < 2; ++i) {
    long e = fb_bg_find_element(fb_model_graph(m), i ? "B" : "A");
    CHECK(e >= 0 && fb_bg_element_kind(fb_model_graph(m), (size_t)e) == FB_BG_R &&
          fb_bg_element_dim(fb_model_graph(m), (size_t)e) == 1);
  }
  fb_model_free(&m);
  remove(tmp_path("d.csv"));
  remove(tmp_path("dup.csv"));
}

/* ---- The quarter car. */

/* Reads examples/quarter_car.yaml (tests run from tests/) with its damper
 * line replaced by damper (NULL: unchanged); caller frees. */
static char *quarter_car_text(const char *damper)
{
  static const char line[] = "{name: Cs, type: R, r: cs}";
  FILE *fp = fopen("../examples/quarter_car.yaml", "r");
  char *text = calloc(1, 65536);
  size_t len = fp && text ? fread(text, 1, 65535, fp) : 0;
  if (fp)
    fclose(fp);
  char *at = len ? strstr(text, line) : NULL;
  CHECK(at != NULL);
  if (!at) {
    free(text);
    return NULL;
  }
  if (damper) {
    size_t tail = strlen(at + strlen(line));
    char *out = malloc((size_t)(at - text) + strlen(damper) + tail + 1);
    if (out)
      sprintf(out, "%.*s%s%s", (int)(at - text), text, damper, at + strlen(line));
    free(text);
    text = out;
  }
  return text;
}

typedef struct run {
  fb_model *model;
  fb_bd *bd;
  fb_result *result;
} run;

static void run_release(run *r)
{
  fb_result_free(&r->result);
  fb_bd_free(&r->bd);
  fb_model_free(&r->model);
}

/* Loads text (or the file path when text is NULL) and simulates it with
 * the model's settings, tolerances overridden when rtol > 0. */
static int simulate(const char *text, const char *path, double rtol, double atol, run *r)
{
  fb_err err;
  *r = (run){NULL, NULL, NULL};
  int rc =
      text ? fb_model_load_string(text, strlen(text), "qc.yaml", "../examples", &r->model, &err)
           : fb_model_load(path, &r->model, &err);
  size_t np = 0;
  const fb_probe_spec *p = rc ? NULL : fb_model_probes(r->model, &np);
  if (!rc)
    rc = fb_bd_build(fb_model_graph(r->model), p, np, &r->bd, &err);
  if (!rc) {
    fb_sim_opts o = *fb_model_sim_opts(r->model);
    if (rtol > 0) {
      o.rtol = rtol;
      o.atol = atol;
    }
    rc = fb_sim_run(r->bd, &o, &r->result, &err);
  }
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  quarter car: %s\n", err.msg);
  return rc;
}

/* Extremes of probe name over the run. */
static void probe_range(const fb_result *r, const char *name, double *lo, double *hi)
{
  long j = fb_result_find(r, name);
  CHECK(j > 0);
  *lo = INFINITY;
  *hi = -INFINITY;
  for (size_t k = 0; j > 0 && k < fb_result_nsamples(r); ++k) {
    *lo = fmin(*lo, fb_result_row(r, k)[j]);
    *hi = fmax(*hi, fb_result_row(r, k)[j]);
  }
}

/* A table of the linear damper F = cs v (uneven knots, one of them
 * non-dyadic, velocities beyond +-2 m/s extrapolated) must give the
 * trajectories of the scalar `r: cs`. Both runs are solved to rtol 1e-11,
 * atol 1e-13 (states of 0.01..10), so each is within about 1e-10
 * relative of the exact solution (global error a few times the local
 * tolerance over the 5 s run); they may take different steps (the scalar
 * model's Newton matrix is constant, the table's is refreshed like any
 * nonlinear law's), so their difference is bounded by the sum: 1e-9 of
 * each probe's range. A wrong table (a slope off by 1e-6) moves the
 * probes by about 1e-6 relative and fails. */
static void test_quarter_car_linear(void)
{
  char *scalar = quarter_car_text(NULL);
  char *table = quarter_car_text("{name: Cs, type: R, table: {points: [[-2, -2 * cs], "
                                 "[-0.5, -0.5 * cs], [0, 0], [0.3, 0.3 * cs], [2, 2 * cs]]}}");
  run a, b;
  if (scalar && table && !simulate(scalar, NULL, 1e-11, 1e-13, &a)) {
    if (!simulate(table, NULL, 1e-11, 1e-13, &b)) {
      const char *const names[] = {"x_body", "a_body", "deflection", "tire_force",
                                   "damper_power"};
      CHECK(fb_result_nsamples(a.result) == fb_result_nsamples(b.result));
      for (size_t i = 0; i < COUNT(names); ++i) {
        long ja = fb_result_find(a.result, names[i]), jb = fb_result_find(b.result, names[i]);
        double lo, hi, worst = 0;
        probe_range(a.result, names[i], &lo, &hi);
        for (size_t k = 0; ja > 0 && jb > 0 && k < fb_result_nsamples(a.result); ++k)
          worst = fmax(worst,
                       fabs(fb_result_row(a.result, k)[ja] - fb_result_row(b.result, k)[jb]));
        CHECK(worst <= 1e-9 * (hi - lo));
        if (worst > 1e-9 * (hi - lo))
          fprintf(stderr, "  %s differs by %g (range %g)\n", names[i], worst, hi - lo);
      }
      run_release(&b);
    }
    run_release(&a);
  }
  free(scalar);
  free(table);
}

/* examples/quarter_car_table.yaml (examples/damper_fv.csv: 1500 N s/m in
 * rebound and 500 in compression near 0, degressive) against the linear
 * 1000 N s/m of examples/quarter_car.yaml over the same bump. Expected
 * directions: the soft compression side transmits less of the bump to the
 * body (smaller body rise and acceleration) and lets the suspension
 * compress further; the stiff rebound side holds the extension back (the
 * smallest deflection, i.e. the largest extension, stays higher). Margins
 * of 5 % keep the checks clear of solver noise (rtol 1e-6).
 * Newton: with the exact Jacobian CVODE needs about one iteration per
 * step and no convergence failures, as in the linear model (which has 0);
 * a wrong Jacobian shows up as failures and more iterations per step. */
static void test_quarter_car_asymmetric(void)
{
  run lin, tab;
  if (simulate(NULL, "../examples/quarter_car.yaml", 0, 0, &lin))
    return;
  if (!simulate(NULL, "../examples/quarter_car_table.yaml", 0, 0, &tab)) {
    double lo_l, hi_l, lo_t, hi_t;
    probe_range(lin.result, "x_body", &lo_l, &hi_l);
    probe_range(tab.result, "x_body", &lo_t, &hi_t);
    CHECK(hi_t < 0.95 * hi_l);
    probe_range(lin.result, "a_body", &lo_l, &hi_l);
    probe_range(tab.result, "a_body", &lo_t, &hi_t);
    CHECK(hi_t < 0.95 * hi_l);
    probe_range(lin.result, "deflection", &lo_l, &hi_l);
    probe_range(tab.result, "deflection", &lo_t, &hi_t);
    double static_defl = 250 * 9.81 / 16000; /* ms g / ks, m */
    CHECK(hi_t - static_defl > 1.05 * (hi_l - static_defl));
    CHECK(static_defl - lo_t < 0.95 * (static_defl - lo_l));

    const fb_sim_stats *sl = fb_result_stats(lin.result), *st = fb_result_stats(tab.result);
    CHECK(st->newton_conv_fails <= sl->newton_conv_fails + 2);
    double iters_l = (double)sl->newton_iters / (double)sl->steps;
    double iters_t = (double)st->newton_iters / (double)st->steps;
    CHECK(iters_t < 1.5 * iters_l);
    run_release(&tab);
  }
  run_release(&lin);
}

/* The diagram's Jacobian (the tabulated law's exact derivative, as the
 * Newton matrix uses it) against central differences of the right-hand
 * side, at a state where the suspension moves at 0.37 m/s (inside the
 * table's cubic piece [0.25, 0.5]). The quarter car is linear apart from
 * the damper, so the difference is the damper's truncation error: with
 * v = p / m, h^2/6 |d^3 phi(p/m)/dp^3| = h^2/6 |phi'''| / m^3 <= 2.8e-5
 * for h = 1e-3, m >= 35 kg and |phi'''| <= 48 * 1500 / 0.1^2 (the bound of
 * check_jacobian_fd), plus rounding eps |F| / h with |F| < 1e5: 2e-8.
 * (The springs and masses are linear: no truncation error.) Tolerance
 * 1e-4. A slope off by 10 N s/m moves an entry by >= 10 / 250 = 0.04. */
static void test_quarter_car_jacobian(void)
{
  fb_err err;
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  int rc = fb_model_load("../examples/quarter_car_table.yaml", &m, &err);
  size_t np = 0;
  const fb_probe_spec *p = rc ? NULL : fb_model_probes(m, &np);
  if (!rc)
    rc = fb_bd_build(fb_model_graph(m), p, np, &bd, &err);
  CHECK(rc == FB_OK);
  size_t n = rc ? 0 : fb_bd_nstates(bd);
  double *x = calloc(n + 1, sizeof *x), *jac = calloc(n * n + 1, sizeof *jac);
  double *fp = calloc(n + 1, sizeof *fp), *fm = calloc(n + 1, sizeof *fm);
  if (!rc && x && jac && fp && fm) {
    fb_bd_initial_state(bd, x);
    /* Body still, wheel rising at 0.37 m/s: p = m v. */
    for (size_t i = 0; i < n; ++i) {
      long e = fb_bd_state_element(bd, i, NULL);
      const char *name = e >= 0 ? fb_bg_element_name(fb_model_graph(m), (size_t)e) : "";
      if (!strcmp(name, "Mu"))
        x[i] = 35 * 0.37;
    }
    CHECK(fb_bd_jacobian_dense(bd, 0.0, x, jac, &err) == FB_OK);
    const double h = 1e-3;
    for (size_t j = 0; j < n; ++j) {
      double xj = x[j];
      x[j] = xj + h;
      CHECK(fb_bd_rhs(bd, 0.0, x, fp) == 0);
      x[j] = xj - h;
      CHECK(fb_bd_rhs(bd, 0.0, x, fm) == 0);
      x[j] = xj;
      for (size_t i = 0; i < n; ++i)
        CHECK_NEAR(jac[i + j * n], (fp[i] - fm[i]) / (2 * h), 1e-4);
    }
  }
  free(x);
  free(jac);
  free(fp);
  free(fm);
  fb_bd_free(&bd);
  fb_model_free(&m);
}

int main(void)
{
  test_hand_values();
  test_limiter();
  test_knots_c1();
  test_monotone();
  test_jacobian_fd();
  test_integral();
  test_linear_law();
  test_passivity();
  test_new_errors();
  tmp_dir = test_tmpdir();
  test_csv_read();
  test_csv_errors();
  test_csv_bytes();
  test_model_errors();
  test_quarter_car_linear();
  test_quarter_car_asymmetric();
  test_quarter_car_jacobian();
  return check_report("test_table_law");
}
