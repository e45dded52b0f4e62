/* SPDX-License-Identifier: BSD-3-Clause */
/* What messages about a value say of it (core/util.h): its range, and
 * "did you mean" suggestions, the closest of a list of names to a word. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "core/util.h"

int fb_range_contains(unsigned bounds, double lo, double hi, double x)
{
  if ((bounds & FB_RANGE_LO) && !((bounds & FB_RANGE_LO_OPEN) ? x > lo : x >= lo))
    return 0;
  return !(bounds & FB_RANGE_HI) || ((bounds & FB_RANGE_HI_OPEN) ? x < hi : x <= hi);
}

void fb_range_text(unsigned bounds, double lo, double hi, char *buf, size_t size)
{
  const int has_lo = (bounds & FB_RANGE_LO) != 0, has_hi = (bounds & FB_RANGE_HI) != 0;
  const int lo_open = (bounds & FB_RANGE_LO_OPEN) != 0,
            hi_open = (bounds & FB_RANGE_HI_OPEN) != 0;
  if (has_lo && has_hi)
    snprintf(buf, size, "in %c%g, %g%c", lo_open ? '(' : '[', lo, hi, hi_open ? ')' : ']');
  else if (has_lo)
    snprintf(buf, size, "%s %g", lo_open ? ">" : ">=", lo);
  else if (has_hi)
    snprintf(buf, size, "%s %g", hi_open ? "<" : "<=", hi);
  else if (size)
    buf[0] = '\0';
}

int fb_is_identifier(const char *name)
{
  if (!name || !(isalpha((unsigned char)name[0]) || name[0] == '_'))
    return 0;
  for (const char *c = name + 1; *c; ++c)
    if (!(isalnum((unsigned char)*c) || *c == '_'))
      return 0;
  return 1;
}

enum { SUGGEST_MAX = 64 };

static size_t min3(size_t a, size_t b, size_t c)
{
  size_t m = a < b ? a : b;
  return m < c ? m : c;
}

/* The Damerau-Levenshtein distance (optimal string alignment: adjacent
 * transpositions count one edit; Damerau 1964), case-insensitive. */
static size_t edit_distance(const char *a, const char *b)
{
  size_t la = strlen(a), lb = strlen(b);
  size_t rows[3][SUGGEST_MAX + 1];
  size_t *prev2 = rows[0], *prev = rows[1], *cur = rows[2];
  for (size_t j = 0; j <= lb; ++j)
    prev[j] = j;
  for (size_t i = 1; i <= la; ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= lb; ++j) {
      int ca = tolower((unsigned char)a[i - 1]), cb = tolower((unsigned char)b[j - 1]);
      size_t cost = ca != cb;
      cur[j] = min3(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost);
      if (i > 1 && j > 1 && ca == tolower((unsigned char)b[j - 2]) &&
          tolower((unsigned char)a[i - 2]) == cb && prev2[j - 2] + 1 < cur[j])
        cur[j] = prev2[j - 2] + 1;
    }
    size_t *t = prev2;
    prev2 = prev;
    prev = cur;
    cur = t;
  }
  return prev[lb];
}

const char *fb_suggest(const char *word, size_t n, fb_name_fn name_at, const void *ctx)
{
  size_t lw = strlen(word);
  if (lw == 0 || lw > SUGGEST_MAX)
    return NULL;
  const char *best = NULL;
  size_t best_d = (size_t)-1;
  for (size_t i = 0; i < n; ++i) {
    const char *cand = name_at(ctx, i);
    size_t lc = cand ? strlen(cand) : 0;
    if (lc == 0 || lc > SUGGEST_MAX)
      continue;
    size_t d = edit_distance(word, cand);
    /* Close enough: about one edit per three characters, and never a
     * complete rewrite of a short word. */
    size_t longest = lw > lc ? lw : lc;
    if (d <= (lw + 2) / 3 && d < longest && d < best_d) {
      best = cand;
      best_d = d;
    }
  }
  return best;
}

static const char *list_at(const void *ctx, size_t i)
{
  return ((const char *const *)ctx)[i];
}

const char *fb_suggest_list(const char *word, const char *const *list)
{
  size_t n = 0;
  while (list[n])
    ++n;
  return fb_suggest(word, n, list_at, list);
}
