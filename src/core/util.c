/* Small internal helpers (see core/util.h). */
#include "core/util.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

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

FILE *fb_open_input(const char *path, const char *mode, fb_err *err)
{
  struct stat st;
  if (stat(path, &st) != 0) {
    fb_err_set(err, FB_EIO, "%s: cannot open: %s", path, strerror(errno));
    return NULL;
  }
  if (!S_ISREG(st.st_mode)) {
    fb_err_set(err, FB_EIO, "%s: cannot read: %s", path,
               S_ISDIR(st.st_mode) ? "Is a directory"
                                   : "not a regular file (a device, pipe or socket)");
    return NULL;
  }
  FILE *fp = fopen(path, mode);
  if (!fp)
    fb_err_set(err, FB_EIO, "%s: cannot open: %s", path, strerror(errno));
  return fp;
}

int fb_read_file(const char *path, char **text, size_t *len, fb_err *err)
{
  FILE *fp = fb_open_input(path, "rb", err);
  if (!fp)
    return FB_EIO;
  size_t cap = 4096, n = 0;
  char *buf = malloc(cap);
  int rc = buf ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  while (!rc) {
    if (n + 1 >= cap) {
      char *grown = realloc(buf, cap * 2);
      if (!grown) {
        rc = fb_err_set(err, FB_ENOMEM, "out of memory reading %s", path);
        break;
      }
      buf = grown;
      cap *= 2;
    }
    size_t got = fread(buf + n, 1, cap - 1 - n, fp);
    n += got;
    if (got == 0 && ferror(fp))
      rc = fb_err_set(err, FB_EIO, "%s: cannot read: %s", path, strerror(errno));
    else if (got == 0)
      break;
  }
  fclose(fp);
  if (rc) {
    free(buf);
    return rc;
  }
  buf[n] = '\0';
  *text = buf;
  *len = n;
  return FB_OK;
}
