/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of fb_tfun: values of each kind against hand calculations or the
 * defining formula, breakpoint lists, CSV tables from temporary files
 * (good and bad), clones against their originals.
 *
 * Tolerances: table values at and between knots chosen as binary fractions
 * are exact (the interpolation weight and the products are representable),
 * so they compare with 0. The sine is compared with the same formula
 * written out with a different grouping, allowing 1e-14 for the rounding of
 * the phase argument (|arg| < 10, ulp 2e-15, times |amplitude| = 2). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/expr.h"

#include "check.h"
#include "tmpdir.h"

static const double PI = 3.14159265358979323846;

static void test_const_and_step(void)
{
  fb_tfun *f = NULL;
  fb_err err;
  double bp[4] = {-1, -1, -1, -1};
  CHECK(fb_tfun_new_const(3.25, &f, &err) == FB_OK);
  CHECK_NEAR(fb_tfun_eval(f, -10.0), 3.25, 0);
  CHECK_NEAR(fb_tfun_eval(f, 1e6), 3.25, 0);
  CHECK(fb_tfun_breakpoints(f, bp, 4) == 0);
  CHECK(bp[0] == -1); /* nothing written */
  fb_tfun_free(&f);
  CHECK(f == NULL);
  CHECK(fb_tfun_new_const(NAN, &f, &err) == FB_EINVAL);
  CHECK(strstr(DESCRIBED(&err), "not finite") != NULL);

  CHECK(fb_tfun_new_step(1.0, 2.0, 5.0, &f, &err) == FB_OK);
  CHECK_NEAR(fb_tfun_eval(f, 0.0), 2.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 0.999999), 2.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 1.0), 5.0, 0); /* the after value from t0 on */
  CHECK_NEAR(fb_tfun_eval(f, 7.0), 5.0, 0);
  CHECK(fb_tfun_breakpoints(f, bp, 4) == 1);
  CHECK(bp[0] == 1.0);
  CHECK(fb_tfun_breakpoints(f, NULL, 0) == 1); /* count only */
  fb_tfun_free(&f);
  CHECK(fb_tfun_new_step(INFINITY, 0, 1, &f, &err) == FB_EINVAL);
  CHECK(strstr(DESCRIBED(&err), "step time") != NULL);
}

static void test_sine(void)
{
  fb_tfun *f = NULL;
  fb_err err;
  const double amplitude = 2.0, freq = 0.5, phase = 0.3, offset = 1.0;
  CHECK(fb_tfun_new_sine(amplitude, freq, phase, offset, &f, &err) == FB_OK);
  for (int i = 0; i <= 10; ++i) {
    double t = 0.37 * i;
    double omega = 2.0 * PI * freq; /* rad/s */
    CHECK_NEAR(fb_tfun_eval(f, t), offset + amplitude * sin(omega * t + phase), 1e-14);
  }
  /* Hand values: at t = 0.5 s the phase is pi/2 + 0.3 -> 1 + 2 cos(0.3). */
  CHECK_NEAR(fb_tfun_eval(f, 0.5), 1.0 + 2.0 * cos(0.3), 1e-14);
  CHECK(fb_tfun_breakpoints(f, NULL, 0) == 0);
  fb_tfun_free(&f);
  CHECK(fb_tfun_new_sine(1, NAN, 0, 0, &f, &err) == FB_EINVAL);
  CHECK(f == NULL);
}

static void test_table(void)
{
  double times[] = {0.0, 1.0, 3.0, 4.0};
  double values[] = {0.0, 2.0, -2.0, -2.0};
  fb_tfun *f = NULL;
  fb_err err;
  CHECK(fb_tfun_new_table(4, times, values, &f, &err) == FB_OK);
  times[1] = 99.0; /* the table must have copied the arrays */
  values[1] = 99.0;
  /* At the knots: the knot values. */
  CHECK_NEAR(fb_tfun_eval(f, 0.0), 0.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 1.0), 2.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 3.0), -2.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 4.0), -2.0, 0);
  /* Between: by hand, v0 + (v1 - v0) (t - t0) / (t1 - t0). */
  CHECK_NEAR(fb_tfun_eval(f, 0.5), 1.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 0.25), 0.5, 0);
  CHECK_NEAR(fb_tfun_eval(f, 2.0), 0.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 2.5), -1.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 3.5), -2.0, 0);
  /* Outside: held at the end values. */
  CHECK_NEAR(fb_tfun_eval(f, -5.0), 0.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 10.0), -2.0, 0);
  double bp[4] = {-1, -1, -1, -1};
  CHECK(fb_tfun_breakpoints(f, bp, 4) == 2); /* interior knots 1 and 3 */
  CHECK(bp[0] == 1.0 && bp[1] == 3.0 && bp[2] == -1);
  bp[0] = bp[1] = -1;
  CHECK(fb_tfun_breakpoints(f, bp, 1) == 2); /* count, but only max written */
  CHECK(bp[0] == 1.0 && bp[1] == -1);
  fb_tfun_free(&f);

  /* One point: constant, no breakpoints. Two: no interior knots. */
  double t1[] = {2.0}, v1[] = {7.0};
  CHECK(fb_tfun_new_table(1, t1, v1, &f, &err) == FB_OK);
  CHECK_NEAR(fb_tfun_eval(f, 0.0), 7.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 2.0), 7.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 9.0), 7.0, 0);
  CHECK(fb_tfun_breakpoints(f, NULL, 0) == 0);
  fb_tfun_free(&f);
  double t2[] = {0.0, 2.0}, v2[] = {1.0, 2.0};
  CHECK(fb_tfun_new_table(2, t2, v2, &f, &err) == FB_OK);
  CHECK_NEAR(fb_tfun_eval(f, 1.5), 1.75, 0);
  CHECK(fb_tfun_breakpoints(f, NULL, 0) == 0);
  fb_tfun_free(&f);
}

/* Reference interpolation by linear search, independent of the binary
 * search in the library. */
static double table_linear_search(size_t n, const double *t, const double *v, double x)
{
  if (x <= t[0])
    return v[0];
  for (size_t i = 1; i < n; ++i)
    if (x <= t[i])
      return v[i - 1] + (v[i] - v[i - 1]) * (x - t[i - 1]) / (t[i] - t[i - 1]);
  return v[n - 1];
}

static void test_table_long(void)
{
  enum { N = 1000 };
  double *t = malloc(N * sizeof *t), *v = malloc(N * sizeof *v);
  for (size_t i = 0; i < N; ++i) {
    t[i] = 1e-3 * (double)(i * i); /* non-uniform spacing */
    v[i] = sin(0.37 * (double)i);
  }
  fb_tfun *f = NULL;
  fb_err err;
  CHECK(fb_tfun_new_table(N, t, v, &f, &err) == FB_OK);
  for (int k = 0; k < 500; ++k) {
    double x = -10.0 + 1030.0 * k / 499.0;
    /* The two methods agree up to rounding of the weight (values <= 1). */
    CHECK_NEAR(fb_tfun_eval(f, x), table_linear_search(N, t, v, x), 1e-14);
  }
  for (size_t i = 0; i < N; i += 37)
    CHECK_NEAR(fb_tfun_eval(f, t[i]), v[i], 0); /* knots exactly */
  CHECK(fb_tfun_breakpoints(f, NULL, 0) == N - 2);
  fb_tfun_free(&f);
  free(t);
  free(v);
}

static void test_table_errors(void)
{
  fb_tfun *f = NULL;
  fb_err err;
  double t_equal[] = {0.0, 1.0, 1.0}, t_down[] = {0.0, 2.0, 1.0}, v[] = {1.0, 2.0, 3.0};
  CHECK(fb_tfun_new_table(0, t_equal, v, &f, &err) == FB_EINVAL);
  CHECK(strstr(DESCRIBED(&err), "at least 1") != NULL);
  CHECK(fb_tfun_new_table(3, t_equal, v, &f, &err) == FB_EINVAL);
  CHECK(strstr(DESCRIBED(&err),
               "strictly increasing: times[2] = 1 is not greater than times[1] = 1") != NULL);
  CHECK(fb_tfun_new_table(3, t_down, v, &f, &err) == FB_EINVAL);
  CHECK(strstr(DESCRIBED(&err), "times[2]") != NULL);
  double t_ok[] = {0.0, 1.0, 2.0}, v_nan[] = {0.0, NAN, 1.0};
  CHECK(fb_tfun_new_table(3, t_ok, v_nan, &f, &err) == FB_EINVAL);
  CHECK(strstr(DESCRIBED(&err), "values[1] is not finite") != NULL);
  CHECK(fb_tfun_new_table(3, t_ok, NULL, &f, &err) == FB_EINVAL);
  CHECK(f == NULL);
}

/* Writes content to a fresh file in /tmp; path receives its name. */
/* Writes len bytes of content (NUL bytes included) to a new temporary file. */
static void write_temp_n(char path[TEST_PATH_MAX], const char *content, size_t len)
{
  test_tmp_path("fb_test_tfun_XXXXXX", path, TEST_PATH_MAX);
  int fd = mkstemp(path);
  CHECK(fd >= 0);
  FILE *fp = fdopen(fd, "w");
  CHECK(fp != NULL);
  CHECK(fwrite(content, 1, len, fp) == len);
  fclose(fp);
}

static void write_temp(char path[TEST_PATH_MAX], const char *content)
{
  write_temp_n(path, content, strlen(content));
}

static void test_csv(void)
{
  char path[TEST_PATH_MAX];
  write_temp(path, "# recorded road profile\n"
                   " time , force, other\n"
                   "0, 1, 9\n"
                   "# a comment between rows\n"
                   "1,3,9\n"
                   "\n"
                   "  2 , 2 ,9  \n"
                   "4,2,x\n"); /* non-numeric unused column is fine */
  fb_tfun *f = NULL;
  fb_err err;
  CHECK(fb_tfun_new_table_csv(path, "time", "force", &f, &err) == FB_OK);
  CHECK_NEAR(fb_tfun_eval(f, 0.0), 1.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 0.5), 2.0, 0); /* (1 + 3) / 2 */
  CHECK_NEAR(fb_tfun_eval(f, 1.5), 2.5, 0); /* (3 + 2) / 2 */
  CHECK_NEAR(fb_tfun_eval(f, 3.0), 2.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 9.0), 2.0, 0);
  double bp[3];
  CHECK(fb_tfun_breakpoints(f, bp, 3) == 2);
  CHECK(bp[0] == 1.0 && bp[1] == 2.0);
  fb_tfun_free(&f);
  /* Columns may come in any order. */
  CHECK(fb_tfun_new_table_csv(path, "time", "other", &f, &err) == FB_EPARSE);
  CHECK(strstr(DESCRIBED(&err), ":8: column 'other': not a number (read: 'x')") != NULL);
  unlink(path);

  write_temp(path, "t,u\r\n0,1e-3\r\n2,-1.5e-3\r\n"); /* CRLF line ends */
  CHECK(fb_tfun_new_table_csv(path, "t", "u", &f, &err) == FB_OK);
  CHECK_NEAR(fb_tfun_eval(f, 1.0), -0.25e-3, 1e-18); /* midpoint; rounding of 1e-3 */
  fb_tfun_free(&f);
  unlink(path);
}

/* Loads content as a CSV table and expects failure code with a message
 * containing "path:line: " (line > 0) and want. */
static void expect_csv_error(const char *content, const char *time_col, const char *value_col,
                             int code, int line, const char *want)
{
  char path[TEST_PATH_MAX], where[TEST_PATH_MAX + 32];
  write_temp(path, content);
  fb_tfun *f = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_tfun_new_table_csv(path, time_col, value_col, &f, &err) == code);
  CHECK(f == NULL);
  snprintf(where, sizeof where, "%s:%d: ", path, line);
  const char *shown = DESCRIBED(&err);
  int ok = strncmp(shown, where, strlen(where)) == 0 && strstr(shown, want) != NULL;
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  got \"%s\", wanted \"%s...%s\"\n", shown, where, want);
  unlink(path);
}

static void test_csv_errors(void)
{
  expect_csv_error("time, a\n0,1\n", "time", "x", FB_EPARSE, 1,
                   "no column 'x' among the header's 2 fields");
  expect_csv_error("# c\n\nq,v\n0,1\n", "t", "v", FB_EPARSE, 3,
                   "no column 't' among the header's 2 fields");
  expect_csv_error("t,v\n0,1\n1,abc\n", "t", "v", FB_EPARSE, 3,
                   "column 'v': not a number (read: 'abc')");
  expect_csv_error("t,v\n0,1\n1,2.5.1\n", "t", "v", FB_EPARSE, 3,
                   "not a number (read: '2.5.1')");
  expect_csv_error("t,v\n0,1\n,2\n", "t", "v", FB_EPARSE, 3, "column 't': not a number");
  expect_csv_error("t,v\n0,1\n1,inf\n", "t", "v", FB_EPARSE, 3,
                   "column 'v': not a finite number (read: 'inf')");
  expect_csv_error("t,v\n0,1\n1,1e999\n", "t", "v", FB_EPARSE, 3,
                   "column 'v': not a finite number (read: '1e999')");
  expect_csv_error("t,v\n0,1\n1,2\n1,3\n", "t", "v", FB_EPARSE, 4,
                   "time 1 is not greater than the previous time 1");
  expect_csv_error("t,v\n0,1\n2,2\n1,3\n", "t", "v", FB_EPARSE, 4, "strictly increasing");
  expect_csv_error("t,v\n# only a comment\n", "t", "v", FB_EPARSE, 2, "too few rows");
  expect_csv_error("t,v\n0\n", "t", "v", FB_EPARSE, 2,
                   "expected 2 fields as in the header, found 1");
  expect_csv_error("t,v\n0,1,2\n", "t", "v", FB_EPARSE, 2, "found 3");
  expect_csv_error("", "t", "v", FB_EPARSE, 1, "no header line");
  expect_csv_error("# c\n\n# d\n", "t", "v", FB_EPARSE, 3, "no header line");

  fb_tfun *f = NULL;
  fb_err err;
  char missing[TEST_PATH_MAX], dir_colon[TEST_PATH_MAX + 1];
  test_tmp_path("does_not_exist.csv", missing, sizeof missing);
  snprintf(dir_colon, sizeof dir_colon, "%s:", test_tmpdir());
  CHECK(fb_tfun_new_table_csv(missing, "t", "v", &f, &err) == FB_EIO);
  CHECK(strstr(err.msg, missing) == err.msg);
  CHECK(strstr(DESCRIBED(&err), strerror(ENOENT)) != NULL);
  CHECK(fb_tfun_new_table_csv(test_tmpdir(), "t", "v", &f, &err) == FB_EIO); /* a directory */
  CHECK(strstr(err.msg, dir_colon) == err.msg);
  CHECK(f == NULL);
}

/* Loads len bytes of content as a table of columns t, v and expects
 * FB_EPARSE with exactly the message "path:line: want". */
static void expect_csv_message(const char *content, size_t len, const char *time_col,
                               const char *value_col, int line, const char *want)
{
  char path[TEST_PATH_MAX], msg[FB_ERR_MSG_MAX];
  write_temp_n(path, content, len);
  fb_tfun *f = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_tfun_new_table_csv(path, time_col, value_col, &f, &err) == FB_EPARSE);
  CHECK(f == NULL);
  snprintf(msg, sizeof msg, "%s:%d: %s", path, line, want);
  const int ok = strcmp(DESCRIBED(&err), msg) == 0;
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  got    \"%s\"\n  wanted \"%s\"\n", err.msg, msg);
  fb_tfun_free(&f);
  unlink(path);
}

#define EXPECT_CSV(text, time_col, value_col, line, want)                                      \
  expect_csv_message(text, sizeof text - 1, time_col, value_col, line, want)

/* Files that are not text are refused at the first bad byte, also in a
 * comment (a NUL would otherwise cut its line short and drop the rest,
 * as the damper table below once lost the row "0,0" after its NUL). */
static void test_csv_binary(void)
{
  EXPECT_CSV("v,F\n-1.0,-980\n-0.5,-580\n0,0\0\n0.5,300\n1.0,500\n", "v", "F", 4,
             "binary data (byte 0x00 in column 4): not a CSV text file (expected UTF-8 text)");
  EXPECT_CSV("t,v\n0,1\n\0\n1,2\n", "t", "v", 3,
             "binary data (byte 0x00 in column 1): not a CSV text file (expected UTF-8 text)");
  EXPECT_CSV("# made by \0\nt,v\n0,1\n1,2\n", "t", "v", 1,
             "binary data (byte 0x00 in column 11): not a CSV text file (expected UTF-8 text)");
  /* A PNG's signature: refused before its header could be quoted. */
  EXPECT_CSV("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", "v", "F", 1,
             "binary data (byte 0x89 in column 1): not a CSV text file (expected UTF-8 text)");
  /* Columns count characters: the stray continuation byte follows "é". */
  EXPECT_CSV("t,v\n# \xc3\xa9\x80\n0,1\n", "t", "v", 2,
             "binary data (byte 0x80 in column 4): not a CSV text file (expected UTF-8 text)");
  EXPECT_CSV("t,v\n0,1\n1,\xff\n", "t", "v", 3,
             "binary data (byte 0xff in column 3): not a CSV text file (expected UTF-8 text)");
  EXPECT_CSV("t,v\n0,1\x01\n", "t", "v", 2,
             "binary data (byte 0x01 in column 4): not a CSV text file (expected UTF-8 text)");
  EXPECT_CSV("t,v\n0\r,1\n", "t", "v", 2,
             "binary data (byte 0x0d in column 2): not a CSV text file (expected UTF-8 text)");
  /* An overlong "/" (C0 AF) and a surrogate (ED A0 80) are not UTF-8. */
  EXPECT_CSV("t,v\n0,1 # \xc0\xaf\n", "t", "v", 2,
             "binary data (byte 0xc0 in column 7): not a CSV text file (expected UTF-8 text)");
  EXPECT_CSV("t,v\n#\xed\xa0\x80\n", "t", "v", 2,
             "binary data (byte 0xed in column 2): not a CSV text file (expected UTF-8 text)");
}

/* Numbers are plain decimals: strtod's other spellings are refused. */
static void test_csv_numbers(void)
{
  EXPECT_CSV("t,v\n0,1\n1,0x10\n", "t", "v", 3,
             "column 'v': not a decimal number (read: '0x10')");
  EXPECT_CSV("t,v\n0x1p3,1\n", "t", "v", 2, "column 't': not a decimal number (read: '0x1p3')");
  EXPECT_CSV("t,v\n0,1\n1,infinity\n", "t", "v", 3,
             "column 'v': not a finite number (read: 'infinity')");
  EXPECT_CSV("t,v\n0,-INF\n", "t", "v", 2, "column 'v': not a finite number (read: '-INF')");
  EXPECT_CSV("t,v\n0,nan\n", "t", "v", 2, "column 'v': not a finite number (read: 'nan')");
  EXPECT_CSV("t,v\n0,1e\n", "t", "v", 2, "column 'v': not a number (read: '1e')");
  EXPECT_CSV("t,v\n0,.\n", "t", "v", 2, "column 'v': not a number (read: '.')");
  EXPECT_CSV("t,v\n0,1 2\n", "t", "v", 2, "column 'v': not a number (read: '1 2')");

  /* Every decimal form is still read, to the value strtod gives. */
  char path[TEST_PATH_MAX];
  fb_tfun *f = NULL;
  fb_err err;
  write_temp(path, "t,v\n-1,+2\n.5,-.25\n1.,1E+2\n2.5e+1,-7.5e-3\n");
  CHECK(fb_tfun_new_table_csv(path, "t", "v", &f, &err) == FB_OK);
  CHECK(f && fb_tfun_eval(f, -1.0) == 2.0 && fb_tfun_eval(f, 0.5) == -0.25);
  CHECK(f && fb_tfun_eval(f, 1.0) == 100.0 && fb_tfun_eval(f, 25.0) == -7.5e-3);
  fb_tfun_free(&f);
  unlink(path);
}

/* A byte-order mark (as Excel writes it) is skipped; one repeated
 * column the table reads is refused, as in road profiles. */
static void test_csv_header(void)
{
  char path[TEST_PATH_MAX];
  write_temp(path, "\xef\xbb\xbfv,F\r\n-1.0,-980\r\n0,0\r\n1.0,500\r\n");
  fb_tfun *f = NULL;
  fb_err err;
  CHECK(fb_tfun_new_table_csv(path, "v", "F", &f, &err) == FB_OK);
  CHECK(f && fb_tfun_eval(f, -1.0) == -980.0 && fb_tfun_eval(f, 0.5) == 250.0);
  fb_tfun_free(&f);
  unlink(path);
  /* Only at the very start: elsewhere U+FEFF is text like any other. */
  EXPECT_CSV("v,F\n\xef\xbb\xbf"
             "0,1\n",
             "v", "F", 2,
             "column 'v': not a number (read: '\xef\xbb\xbf"
             "0')");

  EXPECT_CSV("v,F,F\n-1,-980,1\n0,0,1\n1,500,1\n", "v", "F", 1, "column 'F' appears twice");
  EXPECT_CSV("# table\nv, F, v\n0,0,0\n", "v", "F", 2, "column 'v' appears twice");
  /* Repeats among the columns the table does not read do not matter. */
  write_temp(path, "t,note,v,note\n0,a,1,b\n1,c,2,d\n");
  CHECK(fb_tfun_new_table_csv(path, "t", "v", &f, &err) == FB_OK);
  CHECK(f && fb_tfun_eval(f, 1.0) == 2.0);
  fb_tfun_free(&f);
  unlink(path);
}

static void test_expr_tfun(void)
{
  fb_expr *e = NULL;
  fb_tfun *f = NULL;
  fb_err err;
  CHECK(fb_expr_parse("2*t + step(t - 1)", NULL, &e, &err) == FB_OK);
  CHECK(fb_tfun_new_expr(&e, &f, &err) == FB_OK);
  CHECK(e == NULL); /* ownership taken */
  CHECK_NEAR(fb_tfun_eval(f, 0.5), 1.0, 0);
  CHECK_NEAR(fb_tfun_eval(f, 3.0), 7.0, 0);
  CHECK(fb_tfun_breakpoints(f, NULL, 0) == 0);
  fb_tfun_free(&f);
  CHECK(fb_tfun_new_expr(&e, &f, &err) == FB_EINVAL); /* *e is NULL now */
}

typedef struct ramp_ctx {
  double slope;
  int calls;
} ramp_ctx;

static double ramp_fn(double t, void *ctx)
{
  ramp_ctx *c = ctx;
  ++c->calls;
  return c->slope * t;
}

static void test_callback(void)
{
  ramp_ctx ctx = {.slope = 1.5, .calls = 0};
  const double given[] = {3.0, 1.0, 2.0, 1.0};
  fb_tfun *f = NULL;
  fb_err err;
  CHECK(fb_tfun_new_callback(ramp_fn, &ctx, 4, given, &f, &err) == FB_OK);
  CHECK_NEAR(fb_tfun_eval(f, 2.0), 3.0, 0);
  CHECK(ctx.calls == 1);
  double bp[4] = {-1, -1, -1, -1};
  CHECK(fb_tfun_breakpoints(f, bp, 4) == 3); /* sorted, repeat of 1 dropped */
  CHECK(bp[0] == 1.0 && bp[1] == 2.0 && bp[2] == 3.0 && bp[3] == -1);
  fb_tfun_free(&f);
  CHECK(fb_tfun_new_callback(ramp_fn, &ctx, 0, NULL, &f, &err) == FB_OK);
  CHECK(fb_tfun_breakpoints(f, bp, 4) == 0);
  fb_tfun_free(&f);
  CHECK(fb_tfun_new_callback(NULL, &ctx, 0, NULL, &f, &err) == FB_EINVAL);
  CHECK(fb_tfun_new_callback(ramp_fn, &ctx, 2, NULL, &f, &err) == FB_EINVAL);
  const double bad[] = {1.0, NAN};
  CHECK(fb_tfun_new_callback(ramp_fn, &ctx, 2, bad, &f, &err) == FB_EINVAL);
  CHECK(strstr(DESCRIBED(&err), "breakpoints[1]") != NULL);
}

/* Clones f, frees f (so shared storage would show under ASan), and checks
 * values on a grid and breakpoints against those recorded beforehand. */
static void check_clone(fb_tfun **f)
{
  enum { NT = 25 };
  double want[NT], want_bp[8], got_bp[8];
  for (int i = 0; i < NT; ++i)
    want[i] = fb_tfun_eval(*f, -1.0 + 0.25 * i);
  size_t nbp = fb_tfun_breakpoints(*f, want_bp, 8);
  fb_tfun *copy = NULL;
  fb_err err;
  CHECK(fb_tfun_clone(*f, &copy, &err) == FB_OK);
  fb_tfun_free(f);
  for (int i = 0; i < NT; ++i)
    CHECK_NEAR(fb_tfun_eval(copy, -1.0 + 0.25 * i), want[i], 0); /* same data, same code */
  CHECK(fb_tfun_breakpoints(copy, got_bp, 8) == nbp);
  for (size_t i = 0; i < nbp && i < 8; ++i)
    CHECK(got_bp[i] == want_bp[i]);
  fb_tfun_free(&copy);
}

static void test_clone(void)
{
  fb_tfun *f = NULL;
  fb_err err;
  fb_expr *e = NULL;
  ramp_ctx ctx = {.slope = -2.0, .calls = 0};
  const double times[] = {0.0, 0.5, 1.5, 4.0}, values[] = {1.0, -1.0, 0.0, 2.0};
  const double breaks[] = {2.0, 0.5};

  CHECK(fb_tfun_new_const(-0.75, &f, &err) == FB_OK);
  check_clone(&f);
  CHECK(fb_tfun_new_step(0.5, 1.0, 2.0, &f, &err) == FB_OK);
  check_clone(&f);
  CHECK(fb_tfun_new_sine(1.0, 2.0, 0.1, -1.0, &f, &err) == FB_OK);
  check_clone(&f);
  CHECK(fb_tfun_new_table(4, times, values, &f, &err) == FB_OK);
  check_clone(&f);
  CHECK(fb_expr_parse("t^2 - ramp(t)", NULL, &e, &err) == FB_OK);
  CHECK(fb_tfun_new_expr(&e, &f, &err) == FB_OK);
  check_clone(&f);
  CHECK(fb_tfun_new_callback(ramp_fn, &ctx, 2, breaks, &f, &err) == FB_OK);
  check_clone(&f);
  CHECK(ctx.calls == 50); /* the clone called the same function with the same ctx */
  CHECK(fb_tfun_clone(NULL, &f, &err) == FB_EINVAL);
  fb_tfun_free(NULL);
  fb_tfun_free(&f);
}

/* A callback that keeps its own copy of a plain-data context. */
typedef struct affine {
  double a, b;
} affine;

static double affine_eval(double t, void *ctx)
{
  const affine *p = ctx;
  return p->a * t + p->b;
}

static void test_callback_copy(void)
{
  fb_err err;
  fb_err_clear(&err);
  affine ctx = {2.0, -1.0};
  const double kink = 0.5;
  fb_tfun *f = NULL, *g = NULL;
  CHECK(fb_tfun_new_callback_copy(affine_eval, &ctx, sizeof ctx, 1, &kink, &f, &err) == FB_OK);
  ctx.a = 100.0; /* the function does not see later changes of the caller's copy */
  CHECK(fb_tfun_eval(f, 3.0) == 5.0);
  CHECK(fb_tfun_clone(f, &g, &err) == FB_OK);
  fb_tfun_free(&f);
  /* The clone holds a copy of its own, valid after the original is gone. */
  CHECK(fb_tfun_eval(g, 1.0) == 1.0);
  double bp = 0.0;
  CHECK(fb_tfun_breakpoints(g, &bp, 1) == 1 && bp == 0.5);
  fb_tfun_free(&g);
  CHECK(fb_tfun_new_callback_copy(affine_eval, NULL, 0, 0, NULL, &f, &err) == FB_EINVAL);
  CHECK(f == NULL);
}

int main(void)
{
  test_callback_copy();
  test_const_and_step();
  test_sine();
  test_table();
  test_table_long();
  test_table_errors();
  test_csv();
  test_csv_errors();
  test_csv_binary();
  test_csv_numbers();
  test_csv_header();
  test_expr_tfun();
  test_callback();
  test_clone();
  return check_report("test_tfun");
}
