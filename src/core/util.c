/* Small internal helpers (see core/util.h). */
#include "core/util.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/error.h"

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
