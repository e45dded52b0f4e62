/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of fb_symtab and fb_expr: grammar, precedence and associativity
 * against hand-computed values, every function against libm or a closed
 * form, parameter and time lookup, error messages and suggestions.
 *
 * Tolerances: results that are small integers or binary fractions are
 * exact in IEEE double (every intermediate is representable and + - * /
 * round exactly), so they are compared with tolerance 0. Calls of libm
 * functions are compared with the same libm call in the test, allowing
 * 1e-15 (about 4 ulp at magnitudes <= 2) because the compiler may fold the
 * reference with correctly rounded arithmetic. Identities such as
 * sin(pi/6) = 0.5 allow 1e-15 for the rounding of pi and of the call. */
#include <stdlib.h>
#include <string.h>

#include "flexbond/expr.h"

#include "check.h"

static const double LIBM_TOL = 1e-15;

/* k, ks, m, c_d, damping. */
static fb_symtab *make_syms(void)
{
  fb_symtab *syms = NULL;
  fb_err err;
  CHECK(fb_symtab_new(&syms, &err) == FB_OK);
  CHECK(fb_symtab_set(syms, "k", 2.5, &err) == FB_OK);
  CHECK(fb_symtab_set(syms, "ks", 3.0, &err) == FB_OK);
  CHECK(fb_symtab_set(syms, "m", 0.5, &err) == FB_OK);
  CHECK(fb_symtab_set(syms, "c_d", -1.25, &err) == FB_OK);
  CHECK(fb_symtab_set(syms, "damping", 40.0, &err) == FB_OK);
  return syms;
}

/* Parses and evaluates text at time t; NaN (failing any comparison) if the
 * parse fails. */
static double ev(const char *text, const fb_symtab *syms, double t)
{
  fb_expr *e = NULL;
  fb_err err;
  int status = fb_expr_parse(text, syms, &e, &err);
  CHECK(status == FB_OK);
  if (status != FB_OK) {
    fprintf(stderr, "  parse of '%s' failed: %s\n", text, err.msg);
    return NAN;
  }
  double v = fb_expr_eval(e, t);
  fb_expr_free(&e);
  CHECK(e == NULL);
  return v;
}

/* Expects parsing text to fail with FB_EPARSE and a message containing
 * want (and, if not NULL, not containing avoid). */
static void expect_parse_error(const char *text, const fb_symtab *syms, const char *want,
                               const char *avoid)
{
  fb_expr *e = (fb_expr *)&e; /* any non-NULL value: must be reset to NULL */
  fb_err err;
  fb_err_clear(&err);
  int status = fb_expr_parse(text, syms, &e, &err);
  CHECK(status == FB_EPARSE);
  CHECK(err.code == FB_EPARSE);
  CHECK(e == NULL);
  int ok = strstr(err.msg, want) != NULL && (!avoid || strstr(err.msg, avoid) == NULL);
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  '%s': got \"%s\", wanted \"%s\"\n", text, err.msg, want);
}

static void test_numbers(void)
{
  CHECK_NEAR(ev("42", NULL, 0), 42.0, 0);
  CHECK_NEAR(ev("1e-3", NULL, 0), 0.001, 0); /* same decimal, same correctly rounded strtod */
  CHECK_NEAR(ev(".5", NULL, 0), 0.5, 0);
  CHECK_NEAR(ev("2.", NULL, 0), 2.0, 0);
  CHECK_NEAR(ev("1.5E+2", NULL, 0), 150.0, 0);
  CHECK_NEAR(ev("3e2", NULL, 0), 300.0, 0);
  CHECK_NEAR(ev("2.5e-1", NULL, 0), 0.25, 0);
  CHECK_NEAR(ev("  \t7  ", NULL, 0), 7.0, 0);
  CHECK_NEAR(ev("1e-320", NULL, 0), 1e-320, 0); /* subnormal: accepted, not an overflow */
}

static void test_precedence(void)
{
  CHECK_NEAR(ev("1 + 2 * 3", NULL, 0), 7.0, 0);
  CHECK_NEAR(ev("(1 + 2) * 3", NULL, 0), 9.0, 0);
  CHECK_NEAR(ev("10 - 4 - 3", NULL, 0), 3.0, 0); /* left associative: (10-4)-3 */
  CHECK_NEAR(ev("64 / 4 / 2", NULL, 0), 8.0, 0); /* (64/4)/2, not 64/(4/2) = 32 */
  CHECK_NEAR(ev("6 / 2 * 3", NULL, 0), 9.0, 0);
  CHECK_NEAR(ev("2 * 3 ^ 2", NULL, 0), 18.0, 0);
  /* '^' is right associative: 2^(3^2) = 2^9, not (2^3)^2 = 64. */
  CHECK_NEAR(ev("2^3^2", NULL, 0), 512.0, 0);
  CHECK_NEAR(ev("(2^3)^2", NULL, 0), 64.0, 0);
  /* Unary minus binds looser than '^' (mathematical convention). */
  CHECK_NEAR(ev("-2^2", NULL, 0), -4.0, 0);
  CHECK_NEAR(ev("(-2)^2", NULL, 0), 4.0, 0);
  CHECK_NEAR(ev("2^-1", NULL, 0), 0.5, 0);
  CHECK_NEAR(ev("-2^-2", NULL, 0), -0.25, 0);
  CHECK_NEAR(ev("- -3", NULL, 0), 3.0, 0);
  CHECK_NEAR(ev("+3", NULL, 0), 3.0, 0);
  CHECK_NEAR(ev("2*-3", NULL, 0), -6.0, 0);
  CHECK_NEAR(ev("1 - -1", NULL, 0), 2.0, 0);
  CHECK_NEAR(ev("-3 * 2 + 1", NULL, 0), -5.0, 0);
  CHECK_NEAR(ev("((((1))))", NULL, 0), 1.0, 0);
  /* 1 + 2*1.5 + 3*2.25 - 3.375/4 = 1 + 3 + 6.75 - 0.84375 = 9.90625 */
  CHECK_NEAR(ev("1 + 2*t + 3*t^2 - t^3/4", NULL, 1.5), 9.90625, 0);
}

static void test_functions(void)
{
  const double x = 0.7;
  CHECK_NEAR(ev("sin(0.7)", NULL, 0), sin(x), LIBM_TOL);
  CHECK_NEAR(ev("cos(0.7)", NULL, 0), cos(x), LIBM_TOL);
  CHECK_NEAR(ev("tan(0.7)", NULL, 0), tan(x), LIBM_TOL);
  CHECK_NEAR(ev("asin(0.7)", NULL, 0), asin(x), LIBM_TOL);
  CHECK_NEAR(ev("acos(0.7)", NULL, 0), acos(x), LIBM_TOL);
  CHECK_NEAR(ev("atan(0.7)", NULL, 0), atan(x), LIBM_TOL);
  CHECK_NEAR(ev("exp(0.7)", NULL, 0), exp(x), LIBM_TOL);
  CHECK_NEAR(ev("log(0.7)", NULL, 0), log(x), LIBM_TOL);
  CHECK_NEAR(ev("log10(0.7)", NULL, 0), log10(x), LIBM_TOL);
  CHECK_NEAR(ev("sqrt(0.7)", NULL, 0), sqrt(x), LIBM_TOL);
  CHECK_NEAR(ev("atan2(0.7, -2)", NULL, 0), atan2(x, -2.0), LIBM_TOL);
  CHECK_NEAR(ev("pow(0.7, 2.5)", NULL, 0), pow(x, 2.5), LIBM_TOL);
  /* Closed forms, independent of the libm calls above. */
  CHECK_NEAR(ev("sin(pi/6)", NULL, 0), 0.5, LIBM_TOL);
  CHECK_NEAR(ev("cos(pi/3)", NULL, 0), 0.5, LIBM_TOL);
  CHECK_NEAR(ev("tan(pi/4)", NULL, 0), 1.0, LIBM_TOL);
  CHECK_NEAR(ev("atan2(1, -1)", NULL, 0), 0.75 * 3.14159265358979323846, LIBM_TOL);
  CHECK_NEAR(ev("exp(log(3))", NULL, 0), 3.0, 4 * LIBM_TOL); /* two roundings at magnitude 3 */
  CHECK_NEAR(ev("log10(1000)", NULL, 0), 3.0, LIBM_TOL);
  CHECK_NEAR(ev("sqrt(2)^2", NULL, 0), 2.0, 4 * LIBM_TOL);
  CHECK_NEAR(ev("pow(2, 10)", NULL, 0), 1024.0, 0); /* exact power of two */
  CHECK_NEAR(ev("abs(-4.5)", NULL, 0), 4.5, 0);
  CHECK_NEAR(ev("floor(-1.5)", NULL, 0), -2.0, 0);
  CHECK_NEAR(ev("ceil(-1.5)", NULL, 0), -1.0, 0);
  CHECK_NEAR(ev("min(3, -2)", NULL, 0), -2.0, 0);
  CHECK_NEAR(ev("max(3, -2)", NULL, 0), 3.0, 0);
  CHECK_NEAR(ev("max(3, -2, 7, 1)", NULL, 0), 7.0, 0);
  CHECK_NEAR(ev("min(5, 4, 6, 1, 2)", NULL, 0), 1.0, 0);
  CHECK_NEAR(ev("min(t, 2)", NULL, 5), 2.0, 0);
  CHECK_NEAR(ev("max(t, 2, 1)", NULL, 5), 5.0, 0);
  CHECK(isnan(ev("min(1, sqrt(-1))", NULL, 0))); /* NaN propagates, unlike fmin */
  CHECK_NEAR(ev("sign(-3)", NULL, 0), -1.0, 0);
  CHECK_NEAR(ev("sign(0)", NULL, 0), 0.0, 0);
  CHECK_NEAR(ev("sign(2)", NULL, 0), 1.0, 0);
  CHECK_NEAR(ev("step(-0.1)", NULL, 0), 0.0, 0);
  CHECK_NEAR(ev("step(0)", NULL, 0), 1.0, 0); /* 1 for x >= 0 */
  CHECK_NEAR(ev("step(2)", NULL, 0), 1.0, 0);
  CHECK_NEAR(ev("step(t - 1)", NULL, 0.5), 0.0, 0);
  CHECK_NEAR(ev("step(t - 1)", NULL, 1.0), 1.0, 0);
  CHECK_NEAR(ev("ramp(-2)", NULL, 0), 0.0, 0);
  CHECK_NEAR(ev("ramp(3)", NULL, 0), 3.0, 0);
  CHECK_NEAR(ev("ramp(t - 1)", NULL, 3.5), 2.5, 0);
  CHECK_NEAR(ev("sin (0.7)", NULL, 0), sin(x), LIBM_TOL); /* space before '(' */
}

static void test_constants_and_parameters(void)
{
  fb_symtab *syms = make_syms();
  CHECK_NEAR(ev("pi", NULL, 0), 4.0 * atan(1.0), 4e-16); /* 1 ulp of pi */
  CHECK_NEAR(ev("e", NULL, 0), exp(1.0), 4e-16);
  CHECK_NEAR(ev("k * ks", syms, 0), 7.5, 0);
  CHECK_NEAR(ev("c_d / m", syms, 0), -2.5, 0);
  CHECK_NEAR(ev("damping * t", syms, 0.25), 10.0, 0);
  /* Values are taken when parsing: redefining afterwards has no effect. */
  fb_expr *e = NULL;
  fb_err err;
  CHECK(fb_expr_parse("2 * k", syms, &e, &err) == FB_OK);
  CHECK(fb_symtab_set(syms, "k", 100.0, &err) == FB_OK);
  CHECK_NEAR(fb_expr_eval(e, 0), 5.0, 0);
  fb_expr_free(&e);
  CHECK_NEAR(ev("2 * k", syms, 0), 200.0, 0);
  /* Table entries named like constants win over them. */
  CHECK(fb_symtab_set(syms, "pi", 3.0, &err) == FB_OK);
  CHECK(fb_symtab_set(syms, "e", 2.0, &err) == FB_OK);
  CHECK_NEAR(ev("pi + e", syms, 0), 5.0, 0);
  /* ... but a parameter named like a function does not hide the function. */
  CHECK(fb_symtab_set(syms, "sin", 9.0, &err) == FB_OK);
  CHECK_NEAR(ev("sin(0) + sin", syms, 0), 9.0, 0);
  fb_symtab_free(&syms);
}

static void test_time(void)
{
  fb_symtab *syms = make_syms();
  fb_expr *e = NULL;
  fb_err err;
  CHECK(fb_expr_parse("2*t + 1", syms, &e, &err) == FB_OK);
  CHECK(fb_expr_uses_time(e) == 1);
  CHECK_NEAR(fb_expr_eval(e, 3.0), 7.0, 0);
  CHECK_NEAR(fb_expr_eval(e, -0.5), 0.0, 0);
  fb_expr_free(&e);
  CHECK(fb_expr_parse("k * 2", syms, &e, &err) == FB_OK);
  CHECK(fb_expr_uses_time(e) == 0);
  fb_expr_free(&e);
  /* t*0 is still a use of t: the flag is syntactic. */
  CHECK(fb_expr_parse("t * 0", syms, &e, &err) == FB_OK);
  CHECK(fb_expr_uses_time(e) == 1);
  fb_expr_free(&e);
  CHECK_NEAR(ev("sin(t)", NULL, 1.3), sin(1.3), LIBM_TOL);
  /* A parameter named t is a constant. */
  CHECK(fb_symtab_set(syms, "t", 5.0, &err) == FB_OK);
  CHECK(fb_expr_parse("t + 1", syms, &e, &err) == FB_OK);
  CHECK(fb_expr_uses_time(e) == 0);
  CHECK_NEAR(fb_expr_eval(e, 100.0), 6.0, 0);
  fb_expr_free(&e);
  fb_symtab_free(&syms);
}

static void test_clone(void)
{
  fb_symtab *syms = make_syms();
  fb_expr *e = NULL, *copy = NULL;
  fb_err err;
  CHECK(fb_expr_parse("k*sin(t) + max(t, ks, 1)^2 / (1 + t*t)", syms, &e, &err) == FB_OK);
  CHECK(fb_expr_clone(e, &copy, &err) == FB_OK);
  double want[5];
  for (int i = 0; i < 5; ++i)
    want[i] = fb_expr_eval(e, 0.9 * i);
  fb_expr_free(&e); /* the copy must not share storage with the original */
  for (int i = 0; i < 5; ++i) {
    double t = 0.9 * i, mx = t > 3.0 ? t : 3.0;
    CHECK_NEAR(fb_expr_eval(copy, t), want[i], 0); /* same code, same operations */
    /* and against the formula evaluated directly in C */
    CHECK_NEAR(want[i], 2.5 * sin(t) + mx * mx / (1 + t * t), 1e-14);
  }
  CHECK(fb_expr_uses_time(copy) == 1);
  fb_expr_free(&copy);
  fb_expr_free(&copy); /* second free of NULL is harmless */
  fb_expr_free(NULL);
  fb_symtab_free(&syms);
}

/* Builds "t+(t+(...(t)...))" with levels '+' signs; it needs levels + 1
 * stack slots and evaluates to (levels + 1) * t. */
static char *nested_sum(int levels)
{
  char *s = malloc((size_t)levels * 4 + 2);
  char *p = s;
  for (int i = 0; i < levels; ++i)
    p += sprintf(p, "t+(");
  *p++ = 't';
  for (int i = 0; i < levels; ++i)
    *p++ = ')';
  *p = '\0';
  return s;
}

static void test_limits(void)
{
  char *ok = nested_sum(60); /* 61 slots, within the 64 the evaluator has */
  CHECK_NEAR(ev(ok, NULL, 2.0), 122.0, 0);
  free(ok);
  char *deep = nested_sum(70);
  expect_parse_error(deep, NULL, "expression too complex", NULL);
  free(deep);
  char parens[700], minus[400];
  memset(parens, '(', 300);
  strcpy(parens + 300, "1");
  memset(parens + 301, ')', 300);
  parens[601] = '\0';
  expect_parse_error(parens, NULL, "nested too deeply", NULL);
  memset(minus, '-', 300);
  strcpy(minus + 300, "1");
  expect_parse_error(minus, NULL, "nested too deeply", NULL);
  memset(minus, '-', 100); /* 100 levels are fine; even count gives +1 */
  strcpy(minus + 100, "1");
  CHECK_NEAR(ev(minus, NULL, 0), 1.0, 0);
}

static void test_errors(void)
{
  fb_symtab *syms = make_syms();
  expect_parse_error("", syms, "column 1: empty expression", NULL);
  expect_parse_error("   ", syms, "empty expression", NULL);
  expect_parse_error("(1 + 2", syms, "column 7: expected ')' to close '(' at column 1", NULL);
  expect_parse_error("atan2(1, 2", syms, "column 11: expected ')' after argument list", NULL);
  expect_parse_error("sin(1 2)", syms, "column 7: expected ')' after argument list", NULL);
  expect_parse_error("kss + 1", syms, "column 1: unknown name 'kss' (did you mean 'ks'?)",
                     NULL);
  expect_parse_error("2 * kss", syms, "column 5: unknown name 'kss'", NULL);
  /* Swapped adjacent letters count as one edit; two edits are still suggested. */
  expect_parse_error("dampnig", syms, "unknown name 'dampnig' (did you mean 'damping'?)", NULL);
  expect_parse_error("ksss", syms, "unknown name 'ksss' (did you mean 'ks'?)", NULL);
  expect_parse_error("dampxnig", syms, "(did you mean 'damping'?)", NULL);
  expect_parse_error("xyzzy", syms, "unknown name 'xyzzy'", "did you mean");
  /* A one-letter name is not "corrected" to another one-letter name. */
  expect_parse_error("x", syms, "column 1: unknown name 'x'", "did you mean");
  /* Function names are candidates for plain names too. */
  expect_parse_error("sqr + 1", syms, "unknown name 'sqr' (did you mean 'sqrt'?)", NULL);
  expect_parse_error("sinn(1)", syms, "column 1: unknown function 'sinn' (did you mean 'sin'?)",
                     NULL);
  expect_parse_error("1 + frobnicate(1)", syms, "column 5: unknown function 'frobnicate'",
                     "did you mean");
  expect_parse_error("k(2)", syms, "column 1: 'k' is a parameter, not a function", NULL);
  expect_parse_error("sin + 1", syms, "column 5: expected '(' after function name 'sin'", NULL);
  expect_parse_error("atan2(1)", syms,
                     "column 1: wrong number of arguments to 'atan2' (expected 2, got 1)",
                     NULL);
  expect_parse_error("1+pow(1,2,3)", syms,
                     "column 3: wrong number of arguments to 'pow' (expected 2, got 3)", NULL);
  expect_parse_error("sin(1, 2)", syms,
                     "wrong number of arguments to 'sin' (expected 1, got 2)", NULL);
  expect_parse_error("sin()", syms, "(expected 1, got 0)", NULL);
  expect_parse_error("min(1)", syms, "to 'min' (expected at least 2, got 1)", NULL);
  expect_parse_error("1 2", syms,
                     "column 3: expected an operator or end of expression, found '2'", NULL);
  expect_parse_error("sin(1))", syms, "column 7: expected an operator or end of expression",
                     NULL);
  expect_parse_error("1 + ", syms,
                     "column 5: expected a number, name or '(', found end of expression", NULL);
  expect_parse_error("1 + * 2", syms, "column 5: expected a number, name or '(', found '*'",
                     NULL);
  expect_parse_error("1 $ 2", syms,
                     "column 3: expected an operator or end of expression, found '$'", NULL);
  expect_parse_error("()", syms, "column 2: expected a number, name or '(', found ')'", NULL);
  expect_parse_error("1e", syms, "column 1: expected digits in the exponent of number '1e'",
                     NULL);
  expect_parse_error("2 * 3e+", syms, "column 5: expected digits in the exponent", NULL);
  expect_parse_error("1e999", syms, "column 1: number '1e999' is too large", NULL);
  expect_parse_error("0x10", syms, "column 2: expected an operator", NULL); /* no hex */
  expect_parse_error("2 ^ . 5", syms, "column 5: expected a number, name or '('", NULL);
  /* A very long unknown name gets no suggestion, and no overflow. */
  char longname[200];
  memset(longname, 'a', sizeof longname - 1);
  longname[sizeof longname - 1] = '\0';
  expect_parse_error(longname, syms, "unknown name 'aaaa", "did you mean");

  fb_expr *e = NULL;
  fb_err err;
  CHECK(fb_expr_parse(NULL, syms, &e, &err) == FB_EINVAL);
  CHECK(fb_expr_parse("1", syms, NULL, &err) == FB_EINVAL);
  CHECK(fb_expr_parse("1 +", syms, &e, NULL) == FB_EPARSE); /* err may be NULL */
  fb_symtab_free(&syms);
}

static void test_eval_const(void)
{
  fb_symtab *syms = make_syms();
  fb_err err;
  double v = -1.0;
  CHECK(fb_expr_eval_const("2*k + 1", syms, &v, &err) == FB_OK);
  CHECK_NEAR(v, 6.0, 0);
  CHECK(fb_expr_eval_const("sqrt(ks^2 + 4^2)", syms, &v, &err) == FB_OK);
  CHECK_NEAR(v, 5.0, 0); /* 3-4-5 triangle; sqrt(25) is exact */

  v = -1.0;
  CHECK(fb_expr_eval_const("k + t", syms, &v, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "column 5: expression depends on time t") != NULL);
  CHECK(v == -1.0); /* untouched on failure */
  CHECK(fb_expr_eval_const("1/0", syms, &v, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "value is not finite") != NULL);
  CHECK(strstr(err.msg, "division by zero") != NULL);
  CHECK(fb_expr_eval_const("0/0", syms, &v, &err) == FB_EINVAL);
  CHECK(fb_expr_eval_const("sqrt(-k)", syms, &v, &err) == FB_EINVAL);
  CHECK(fb_expr_eval_const("log(0)", syms, &v, &err) == FB_EINVAL);
  CHECK(fb_expr_eval_const("10^400", syms, &v, &err) == FB_EINVAL);
  CHECK(fb_expr_eval_const("k +", syms, &v, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "column 4:") != NULL);
  CHECK(fb_expr_eval_const("kk", syms, &v, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "did you mean 'k'?") != NULL);
  CHECK(fb_expr_eval_const("1", syms, NULL, &err) == FB_EINVAL);
  fb_symtab_free(&syms);
}

static void test_symtab(void)
{
  fb_symtab *a = NULL, *b = NULL;
  fb_err err;
  CHECK(fb_symtab_new(&a, &err) == FB_OK);
  CHECK(fb_symtab_new(&b, &err) == FB_OK);
  CHECK(fb_symtab_size(a) == 0);
  CHECK(fb_symtab_name(a, 0) == NULL);
  double v = 0.0;
  CHECK(fb_symtab_get(a, "x", &v) == 0);

  /* Names are copied: changing the caller's buffer changes nothing. */
  char name[8] = "mass";
  CHECK(fb_symtab_set(a, name, 1.5, &err) == FB_OK);
  strcpy(name, "zzzz");
  CHECK(fb_symtab_set(a, "k_1", 2.0, &err) == FB_OK);
  CHECK(fb_symtab_set(a, "mass", 4.0, &err) == FB_OK); /* redefinition keeps position */
  CHECK(fb_symtab_size(a) == 2);
  CHECK(fb_symtab_get(a, "mass", &v) == 1);
  CHECK_NEAR(v, 4.0, 0);
  CHECK(strcmp(fb_symtab_name(a, 0), "mass") == 0);
  CHECK(strcmp(fb_symtab_name(a, 1), "k_1") == 0);
  CHECK(fb_symtab_name(a, 2) == NULL);
  CHECK(fb_symtab_get(a, "zzzz", &v) == 0);

  CHECK(fb_symtab_set(b, "k_1", -3.0, &err) == FB_OK);
  CHECK(fb_symtab_set(b, "_c", 7.0, &err) == FB_OK);
  CHECK(fb_symtab_merge(a, b, &err) == FB_OK);
  CHECK(fb_symtab_size(a) == 3);
  CHECK(fb_symtab_get(a, "k_1", &v) == 1);
  CHECK_NEAR(v, -3.0, 0); /* src replaces dst's entry */
  CHECK(fb_symtab_get(a, "_c", &v) == 1);
  CHECK_NEAR(v, 7.0, 0);
  CHECK(strcmp(fb_symtab_name(a, 2), "_c") == 0);
  CHECK(fb_symtab_size(b) == 2); /* src unchanged */
  CHECK(fb_symtab_merge(a, NULL, &err) == FB_OK);
  CHECK(fb_symtab_size(a) == 3);

  /* Many entries: growth keeps all of them. */
  for (int i = 0; i < 100; ++i) {
    char n[16];
    snprintf(n, sizeof n, "p%d", i);
    CHECK(fb_symtab_set(b, n, i, &err) == FB_OK);
  }
  CHECK(fb_symtab_size(b) == 102);
  CHECK(fb_symtab_get(b, "p73", &v) == 1);
  CHECK_NEAR(v, 73.0, 0);

  CHECK(fb_symtab_set(a, "2x", 1.0, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "invalid parameter name '2x'") != NULL);
  CHECK(fb_symtab_set(a, "a.b", 1.0, &err) == FB_EINVAL);
  CHECK(fb_symtab_set(a, "", 1.0, &err) == FB_EINVAL);
  CHECK(fb_symtab_set(a, "y", NAN, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "parameter 'y' is not finite") != NULL);
  CHECK(fb_symtab_set(a, "y", INFINITY, &err) == FB_EINVAL);
  CHECK(fb_symtab_size(a) == 3);
  CHECK(fb_symtab_get(NULL, "x", &v) == 0);
  CHECK(fb_symtab_size(NULL) == 0);

  fb_symtab_free(&a);
  CHECK(a == NULL);
  fb_symtab_free(&a);
  fb_symtab_free(NULL);
  fb_symtab_free(&b);
}

int main(void)
{
  test_numbers();
  test_precedence();
  test_functions();
  test_constants_and_parameters();
  test_time();
  test_clone();
  test_limits();
  test_errors();
  test_eval_const();
  test_symtab();
  return check_report("test_expr");
}
