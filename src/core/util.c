/* SPDX-License-Identifier: BSD-3-Clause */
/* Small internal helpers (see core/util.h). */
#include "core/util.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "flexbond/error.h"

size_t fb_first_nonfinite(const double *v, size_t n)
{
  for (size_t i = 0; i < n; ++i)
    if (!isfinite(v[i]))
      return i;
  return n;
}

double fb_printable(double v)
{
  return isnan(v) ? fabs(v) : v;
}

char *fb_strdup(const char *s)
{
  size_t n = strlen(s) + 1;
  char *d = malloc(n);
  if (d)
    memcpy(d, s, n);
  return d;
}

char *fb_strdup_printf(const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  const int n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  char *out = n >= 0 ? malloc((size_t)n + 1) : NULL;
  if (!out)
    return NULL;
  va_start(ap, fmt);
  vsnprintf(out, (size_t)n + 1, fmt, ap);
  va_end(ap);
  return out;
}

int fb_grow(void **arr, size_t *cap, size_t n, size_t elsize)
{
  if (n < *cap)
    return FB_OK;
  size_t ncap = *cap ? *cap : 8;
  while (ncap <= n) {
    if (ncap > SIZE_MAX / 2 / elsize)
      return FB_ENOMEM;
    ncap *= 2;
  }
  void *p = realloc(*arr, ncap * elsize);
  if (!p)
    return FB_ENOMEM;
  *arr = p;
  *cap = ncap;
  return FB_OK;
}

char *fb_path_join(const char *dir, const char *name)
{
  const size_t n = strlen(dir) + strlen(name) + 2;
  char *p = malloc(n);
  if (p)
    snprintf(p, n, "%s/%s", dir, name);
  return p;
}

char *fb_dirname(const char *path)
{
  const char *slash = strrchr(path, '/');
  const char *src = !slash ? "." : slash == path ? "/" : path;
  const size_t len = (!slash || slash == path) ? 1 : (size_t)(slash - path);
  char *dir = malloc(len + 1);
  if (dir) {
    memcpy(dir, src, len);
    dir[len] = '\0';
  }
  return dir;
}

double fb_seconds_since(const struct timespec *t0)
{
  struct timespec t1;
  clock_gettime(CLOCK_MONOTONIC, &t1);
  return (double)(t1.tv_sec - t0->tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0->tv_nsec);
}

const char *fb_bytes_text(double bytes, char *buf, size_t size)
{
  static const char *const unit[] = {"B", "kB", "MB", "GB", "TB"};
  size_t u = 0;
  while (bytes >= 999.5 && u + 1 < sizeof unit / sizeof unit[0]) {
    bytes /= 1e3;
    ++u;
  }
  snprintf(buf, size, u ? "%.3g %s" : "%.0f %s", bytes, unit[u]);
  return buf;
}

int fb_check_dense_eig(size_t n, size_t nmatrices, size_t limit, fb_err *err, const char *fmt,
                       ...)
{
  char what[FB_ERR_MSG_MAX / 2];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  if (n > FB_DENSE_EIG_MAX) {
    /* 20 s at FB_DENSE_EIG_MAX, n^3 beyond. */
    const double seconds = 20.0 * pow((double)n / FB_DENSE_EIG_MAX, 3.0);
    return fb_err_set(err, FB_ENOMEM,
                      "%s: a dense eigen-solve of order %zu, more than the %d it may take "
                      "(its time grows as the cube of the order: some %.0f %s here, which "
                      "nothing could interrupt)",
                      what, n, FB_DENSE_EIG_MAX, seconds < 120 ? seconds : seconds / 60,
                      seconds < 120 ? "s" : "minutes");
  }
  const double bytes = (double)nmatrices * (double)n * (double)n * sizeof(double);
  return fb_check_memory(bytes, limit, err, "%s", what);
}

int fb_check_memory(double bytes, size_t limit, fb_err *err, const char *fmt, ...)
{
  if (!limit || bytes <= (double)limit)
    return FB_OK;
  char what[FB_ERR_MSG_MAX / 2], need[32], allowed[32];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  return fb_err_set(err, FB_ENOMEM, "%s needs %s, more than the %s allowed", what,
                    fb_bytes_text(bytes, need, sizeof need),
                    fb_bytes_text((double)limit, allowed, sizeof allowed));
}
