/* SPDX-License-Identifier: BSD-3-Clause */
/* Exclusive temporary files and directories (see core/tmpfile.h).
 *
 * Safety comes from exclusive creation alone (O_CREAT | O_EXCL, which
 * refuses a name that exists, a symbolic link included), not from the
 * name being hard to guess; the random letters only keep a name planted
 * in advance from blocking the creation: each try draws a fresh name.
 * mkstemp(3) would do the same, but it makes mode 0600 files, and the
 * outputs renamed into place must get the mode fopen gives a new file.
 * A random source with no state of its own: the clock, the process and
 * the try mixed by SplitMix64 (Steele, Lea & Flood, "Fast splittable
 * pseudorandom number generators", OOPSLA 2014). */
#include "core/tmpfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* Tries before giving up with EEXIST: names are 62^6 letters apart, so
 * only a directory flooded with planted names runs out. */
enum { TMP_TRIES = 1000, TMP_LETTERS = 6 };

static uint64_t splitmix64(uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/* Overwrites the TMP_LETTERS characters at x with letters and digits
 * drawn from the clock, the process, the stack address and try. */
static void fill_random(char *x, unsigned try)
{
  static const char alphabet[] =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  struct timespec ts = {0, 0};
  clock_gettime(CLOCK_REALTIME, &ts);
  uint64_t seed = (uint64_t)ts.tv_nsec ^ ((uint64_t)ts.tv_sec << 30) ^
                  ((uint64_t)getpid() << 16) ^ (uint64_t)(uintptr_t)&ts ^ try;
  uint64_t r = splitmix64(seed);
  for (int i = 0; i < TMP_LETTERS; ++i) {
    x[i] = alphabet[r % (sizeof alphabet - 1)];
    r /= sizeof alphabet - 1;
  }
}

/* "DIR/.BASE.XXXXXX.tmp" for path in fresh memory (NULL when out of it);
 * *x points at the Xs. */
static char *tmp_template(const char *path, char **x)
{
  const char *slash = strrchr(path, '/');
  const size_t dir_len = slash ? (size_t)(slash - path) + 1 : 0;
  const char *base = path + dir_len;
  const size_t n = strlen(path) + TMP_LETTERS + sizeof "...tmp"; /* ".", ".", ".tmp", NUL */
  char *t = malloc(n);
  if (!t)
    return NULL;
  snprintf(t, n, "%.*s.%s.%.*s.tmp", (int)dir_len, path, base, TMP_LETTERS, "XXXXXXXXXXXX");
  *x = t + dir_len + 1 + strlen(base) + 1;
  return t;
}

int fb_tmpfile_create(const char *path, int *fd, char **tmp_path)
{
  *fd = -1;
  *tmp_path = NULL;
  char *x = NULL;
  char *t = tmp_template(path, &x);
  if (!t)
    return ENOMEM;
  for (unsigned try = 0; try < TMP_TRIES; ++try) {
    fill_random(x, try);
    const int f = open(t, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (f >= 0) {
      *fd = f;
      *tmp_path = t;
      return 0;
    }
    if (errno != EEXIST) {
      const int e = errno;
      free(t);
      return e;
    }
  }
  free(t);
  return EEXIST;
}

int fb_tmpdir_create(const char *path, const char *tag, char **dir)
{
  *dir = NULL;
  const char *slash = strrchr(path, '/');
  const int dir_len = slash ? (int)(slash - path) + 1 : 0;
  const size_t n = (size_t)dir_len + strlen(tag) + sizeof ".flexbond--XXXXXX";
  char *d = malloc(n);
  if (!d)
    return ENOMEM;
  snprintf(d, n, "%.*s.flexbond-%s-XXXXXX", dir_len, path, tag);
  if (!mkdtemp(d)) {
    const int e = errno;
    free(d);
    return e;
  }
  *dir = d;
  return 0;
}
