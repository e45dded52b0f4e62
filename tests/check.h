/* SPDX-License-Identifier: BSD-3-Clause */
/* Minimal test harness: CHECK records a failure and goes on; a test
 * program returns check_report() from main. */
#ifndef FLEXBOND_TEST_CHECK_H
#define FLEXBOND_TEST_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_failures;
static int check_count;

#define CHECK(cond)                                                                            \
  do {                                                                                         \
    ++check_count;                                                                             \
    if (!(cond)) {                                                                             \
      ++check_failures;                                                                        \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);                 \
    }                                                                                          \
  } while (0)

/* |a - b| <= tol, with both values printed on failure. */
#define CHECK_NEAR(a, b, tol)                                                                  \
  do {                                                                                         \
    ++check_count;                                                                             \
    double check_a_ = (a), check_b_ = (b), check_t_ = (tol);                                   \
    if (!(fabs(check_a_ - check_b_) <= check_t_)) {                                            \
      ++check_failures;                                                                        \
      fprintf(stderr, "%s:%d: CHECK_NEAR failed: %s = %.12g, %s = %.12g, tol %.3g\n",          \
              __FILE__, __LINE__, #a, check_a_, #b, check_b_, check_t_);                       \
    }                                                                                          \
  } while (0)

static inline int check_report(const char *name)
{
  fprintf(stderr, "%s: %d checks, %d failed\n", name, check_count, check_failures);
  return check_failures ? 1 : 0;
}

/* The message as the user reads it (fb_err_describe: with a data file's
 * excerpt), in a buffer of its own per call site's statement. */
#define DESCRIBED(err)                                                                         \
  fb_err_describe((err), (char[FB_ERR_MSG_MAX + FB_ERR_EXCERPT_MAX + 16]){0},                  \
                  FB_ERR_MSG_MAX + FB_ERR_EXCERPT_MAX + 16)

/* 1 if err is about member field of the part kind kind, item index, of
 * a description (fb_err.part; "" the whole item), with no element. */
#define PART_IS(err, kind_, index_, field_)                                                    \
  ((err)->part.kind == (kind_) && (err)->part.index == (index_) &&                             \
   (err)->part.element == FB_ERR_NO_ELEMENT && !strcmp((err)->part.field, (field_)))

#endif
