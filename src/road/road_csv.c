/* SPDX-License-Identifier: BSD-3-Clause */
/* Measured road profiles read from CSV files (format: flexbond/road.h,
 * docs/roads.md), interpolated by PCHIP (pchip.c). */
#include <stdlib.h>
#include <string.h>

#include "flexbond/road.h"

#include "core/textfile.h"
#include "road/road_internal.h"

/* Columns a profile file may have, in the order of the values a row
 * stores. */
enum { COL_S, COL_Z, COL_ZL, COL_ZR, NCOLS };
static const char *const COLUMN_NAMES[NCOLS] = {"s", "z", "z_left", "z_right"};
static const char *const EXPECTED = "expected columns s, z or s, z_left, z_right";

typedef struct profile_reader {
  fb_text_reader text;  /* the file, its line number and error context */
  size_t ncols;         /* fields per line */
  int column[NCOLS];    /* field index of each column, -1 if absent */
  size_t n, capacity;   /* rows read, room */
  double *value[NCOLS]; /* value[c][row], for the columns present */
} profile_reader;

/* Spaces and tabs cut from both ends of a field, in place. */
static char *trim(char *text)
{
  while (*text == ' ' || *text == '\t')
    ++text;
  char *end = text + strlen(text);
  while (end > text && (end[-1] == ' ' || end[-1] == '\t'))
    --end;
  *end = '\0';
  return text;
}

/* Cuts the next comma-separated field off *cursor (NULL after the last). */
static char *next_field(char **cursor)
{
  char *start = *cursor, *comma = strchr(start, ',');
  *cursor = comma ? comma + 1 : NULL;
  if (comma)
    *comma = '\0';
  return trim(start);
}

static int column_of(const char *name)
{
  for (int c = 0; c < NCOLS; ++c)
    if (strcmp(name, COLUMN_NAMES[c]) == 0)
      return c;
  return -1;
}

/* The set of columns must be {s, z} or {s, z_left, z_right}. */
static int check_column_set(const profile_reader *r)
{
  const int *col = r->column;
  const int single = col[COL_Z] >= 0, pair = col[COL_ZL] >= 0 && col[COL_ZR] >= 0;
  const int any_side = col[COL_ZL] >= 0 || col[COL_ZR] >= 0;
  if (col[COL_S] < 0)
    return fb_err_set(r->text.err, FB_EPARSE, "%s:%zu: no column 's' (%s)", r->text.path,
                      r->text.line_no, EXPECTED);
  if (single && any_side)
    return fb_err_set(r->text.err, FB_EPARSE, "%s:%zu: both 'z' and 'z_left'/'z_right' (%s)",
                      r->text.path, r->text.line_no, EXPECTED);
  if (!single && !pair)
    return fb_err_set(r->text.err, FB_EPARSE, "%s:%zu: no height column%s (%s)", r->text.path,
                      r->text.line_no, any_side ? " for each side" : "", EXPECTED);
  return FB_OK;
}

static int read_header(profile_reader *r)
{
  char *text = NULL;
  int rc = fb_text_next_data_line(&r->text, '#', &text);
  if (rc)
    return rc;
  if (!text)
    return fb_err_set(r->text.err, FB_EPARSE, "%s:%zu: no header line (%s)", r->text.path,
                      r->text.line_no ? r->text.line_no : 1, EXPECTED);
  for (int c = 0; c < NCOLS; ++c)
    r->column[c] = -1;
  for (char *cursor = text; cursor; ++r->ncols) {
    const char *name = next_field(&cursor);
    const int c = column_of(name);
    if (c < 0) {
      fb_err_set(r->text.err, FB_EPARSE, "%s:%zu: unknown column %zu (%s)", r->text.path,
                 r->text.line_no, r->ncols + 1, EXPECTED);
      fb_err_set_excerpt(r->text.err, name, strlen(name));
      return FB_EPARSE;
    }
    if (r->column[c] >= 0)
      return fb_err_set(r->text.err, FB_EPARSE, "%s:%zu: column '%s' appears twice",
                        r->text.path, r->text.line_no, name);
    r->column[c] = (int)r->ncols;
  }
  return check_column_set(r);
}

/* Room for one more row in every present column. */
static int grow(profile_reader *r)
{
  if (r->n < r->capacity)
    return FB_OK;
  const size_t capacity = r->capacity ? 2 * r->capacity : 256;
  for (int c = 0; c < NCOLS; ++c) {
    if (r->column[c] < 0)
      continue;
    double *v = realloc(r->value[c], capacity * sizeof *v);
    if (!v)
      return fb_err_set(r->text.err, FB_ENOMEM, "out of memory reading %s", r->text.path);
    r->value[c] = v;
  }
  r->capacity = capacity;
  return FB_OK;
}

static int parse_number(const profile_reader *r, int c, const char *text, double *v)
{
  const int rc = fb_parse_decimal_field(text, v, r->text.err);
  if (rc)
    fb_err_prefix(r->text.err, "%s:%zu: column '%s': ", r->text.path, r->text.line_no,
                  COLUMN_NAMES[c]);
  return rc;
}

/* Parses one data line into row r->n (room already made). */
static int read_row(profile_reader *r, char *text)
{
  size_t count = 0;
  int rc = FB_OK;
  for (char *cursor = text; cursor && !rc; ++count) {
    const char *field = next_field(&cursor);
    for (int c = 0; c < NCOLS && !rc && count < r->ncols; ++c)
      if (r->column[c] == (int)count)
        rc = parse_number(r, c, field, &r->value[c][r->n]);
  }
  if (!rc && count != r->ncols)
    rc = fb_err_set(r->text.err, FB_EPARSE,
                    "%s:%zu: expected %zu fields as in the header, found %zu", r->text.path,
                    r->text.line_no, r->ncols, count);
  const double *s = r->value[COL_S];
  if (!rc && r->n > 0 && !(s[r->n] > s[r->n - 1]))
    rc = fb_err_set(r->text.err, FB_EPARSE,
                    "%s:%zu: s = %g is not greater than the previous s = %g (s must be "
                    "strictly increasing)",
                    r->text.path, r->text.line_no, s[r->n], s[r->n - 1]);
  return rc;
}

static int read_rows(profile_reader *r)
{
  for (;;) {
    char *text = NULL;
    int rc = fb_text_next_data_line(&r->text, '#', &text);
    if (!rc && !text)
      break;
    if (!rc)
      rc = grow(r);
    if (!rc)
      rc = read_row(r, text);
    if (rc)
      return rc;
    ++r->n;
  }
  if (r->n < 2)
    return fb_err_set(r->text.err, FB_EPARSE,
                      "%s:%zu: %zu data row%s, need at least 2 (a row per position: s, then "
                      "the heights, in m)",
                      r->text.path, r->text.line_no, r->n, r->n == 1 ? "" : "s");
  return FB_OK;
}

/* Fills a PCHIP track's data (s, z, slopes) from the rows. */
static void fill_track(const profile_reader *r, const double *z, double *data)
{
  const size_t n = r->n;
  memcpy(data, r->value[COL_S], n * sizeof *data);
  memcpy(data + n, z, n * sizeof *data);
  road_pchip_slopes(n, data, data + n, data + 2 * n);
}

static int build_road(const profile_reader *r, fb_road **out, fb_err *err)
{
  const road_track track = {ROAD_PCHIP, r->n, {0.0, 0.0, 0.0}};
  int rc = road_alloc(&track, &track, out, err);
  if (rc)
    return rc;
  const int single = r->column[COL_Z] >= 0;
  fill_track(r, r->value[single ? COL_Z : COL_ZL], (*out)->data[FB_ROAD_LEFT]);
  fill_track(r, r->value[single ? COL_Z : COL_ZR], (*out)->data[FB_ROAD_RIGHT]);
  return FB_OK;
}

int fb_road_new_csv(const char *path, fb_road **out, fb_err *err)
{
  if (!path || !out)
    return fb_err_set(err, FB_EINVAL, "road CSV: NULL argument");
  *out = NULL;
  profile_reader r = {.ncols = 0};
  if (fb_text_open(&r.text, path, "CSV", err))
    return FB_EIO;
  int rc = read_header(&r);
  if (!rc)
    rc = read_rows(&r);
  if (!rc)
    rc = build_road(&r, out, err);
  fb_text_close(&r.text);
  for (int c = 0; c < NCOLS; ++c)
    free(r.value[c]);
  return rc;
}
