/* SPDX-License-Identifier: BSD-3-Clause */
/* Scalar functions of time u(t) for modulated sources (see flexbond/expr.h).
 *
 * One struct with a kind tag; each kind keeps its data in its own member
 * of a union. Breakpoints are reported so the integrator can stop at
 * discontinuities of u or u' instead of stepping across them. */
#include <assert.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/expr.h"

#include "core/textfile.h"

typedef enum tfun_kind {
  TFUN_CONST,
  TFUN_STEP,
  TFUN_SINE,
  TFUN_TABLE,
  TFUN_EXPR,
  TFUN_CALLBACK
} tfun_kind;

struct fb_tfun {
  tfun_kind kind;
  union {
    double value;
    struct {
      double t0, before, after;
    } step;
    struct {
      double amplitude, freq_hz, phase_rad, offset;
    } sine;
    struct {
      size_t n;
      double *times, *values;
    } table;
    fb_expr *expr;
    struct {
      fb_tfun_fn fn;
      void *ctx;
      size_t ctx_size; /* > 0: ctx is the function's own copy */
      size_t nbreak;
      double *breaks;
    } callback;
  } u;
};

static const double TWO_PI = 6.28318530717958647693;

static int tfun_alloc(tfun_kind kind, fb_tfun **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "time function: out is NULL");
  *out = calloc(1, sizeof **out);
  if (!*out)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating a time function");
  (*out)->kind = kind;
  return FB_OK;
}

static int check_finite(double x, const char *what, fb_err *err)
{
  if (!isfinite(x))
    return fb_err_set(err, FB_EINVAL, "%s is not finite (got %g)", what, x);
  return FB_OK;
}

int fb_tfun_new_const(double value, fb_tfun **out, fb_err *err)
{
  int status = check_finite(value, "constant value", err);
  if (status == FB_OK)
    status = tfun_alloc(TFUN_CONST, out, err);
  if (status == FB_OK)
    (*out)->u.value = value;
  return status;
}

int fb_tfun_new_step(double t0, double before, double after, fb_tfun **out, fb_err *err)
{
  int status = check_finite(t0, "step time", err);
  if (status == FB_OK)
    status = check_finite(before, "step value before", err);
  if (status == FB_OK)
    status = check_finite(after, "step value after", err);
  if (status == FB_OK)
    status = tfun_alloc(TFUN_STEP, out, err);
  if (status == FB_OK) {
    (*out)->u.step.t0 = t0;
    (*out)->u.step.before = before;
    (*out)->u.step.after = after;
  }
  return status;
}

int fb_tfun_new_sine(double amplitude, double freq_hz, double phase_rad, double offset,
                     fb_tfun **out, fb_err *err)
{
  int status = check_finite(amplitude, "sine amplitude", err);
  if (status == FB_OK)
    status = check_finite(freq_hz, "sine frequency", err);
  if (status == FB_OK)
    status = check_finite(phase_rad, "sine phase", err);
  if (status == FB_OK)
    status = check_finite(offset, "sine offset", err);
  if (status == FB_OK)
    status = tfun_alloc(TFUN_SINE, out, err);
  if (status == FB_OK) {
    (*out)->u.sine.amplitude = amplitude;
    (*out)->u.sine.freq_hz = freq_hz;
    (*out)->u.sine.phase_rad = phase_rad;
    (*out)->u.sine.offset = offset;
  }
  return status;
}

/* n >= 1, finite entries, strictly increasing times; the message names the
 * first offending index. */
static int check_table(size_t n, const double *times, const double *values, fb_err *err)
{
  if (n == 0)
    return fb_err_set(err, FB_EINVAL, "table needs at least 1 point (got 0)");
  if (!times || !values)
    return fb_err_set(err, FB_EINVAL, "table times or values is NULL");
  for (size_t i = 0; i < n; ++i) {
    if (!isfinite(times[i]))
      return fb_err_set(err, FB_EINVAL, "table times[%zu] is not finite (got %g)", i, times[i]);
    if (!isfinite(values[i]))
      return fb_err_set(err, FB_EINVAL, "table values[%zu] is not finite (got %g)", i,
                        values[i]);
    if (i > 0 && !(times[i] > times[i - 1]))
      return fb_err_set(err, FB_EINVAL,
                        "table times must be strictly increasing: times[%zu] = %g is not "
                        "greater than times[%zu] = %g",
                        i, times[i], i - 1, times[i - 1]);
  }
  return FB_OK;
}

/* Fresh copy of n doubles (n may be 0: returns NULL without error). */
static int copy_doubles(size_t n, const double *src, double **dst, fb_err *err)
{
  *dst = NULL;
  if (n == 0)
    return FB_OK;
  *dst = malloc(n * sizeof **dst);
  if (!*dst)
    return fb_err_set(err, FB_ENOMEM, "out of memory copying %zu values", n);
  memcpy(*dst, src, n * sizeof **dst);
  return FB_OK;
}

int fb_tfun_new_table(size_t n, const double *times, const double *values, fb_tfun **out,
                      fb_err *err)
{
  int status = check_table(n, times, values, err);
  if (status == FB_OK)
    status = tfun_alloc(TFUN_TABLE, out, err);
  if (status != FB_OK)
    return status;
  fb_tfun *f = *out;
  f->u.table.n = n;
  status = copy_doubles(n, times, &f->u.table.times, err);
  if (status == FB_OK)
    status = copy_doubles(n, values, &f->u.table.values, err);
  if (status != FB_OK)
    fb_tfun_free(out);
  return status;
}

/* Takes ownership of *e and sets it to NULL, also on failure. */
int fb_tfun_new_expr(fb_expr **e, fb_tfun **out, fb_err *err)
{
  if (!e || !*e)
    return fb_err_set(err, FB_EINVAL, "fb_tfun_new_expr: expression is NULL");
  int status = tfun_alloc(TFUN_EXPR, out, err);
  if (status != FB_OK) {
    fb_expr_free(e);
    return status;
  }
  (*out)->u.expr = *e;
  *e = NULL;
  return FB_OK;
}

static int compare_doubles(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Sorts the n values in place and drops repeats; returns the new count. */
static size_t sort_unique(double *v, size_t n)
{
  if (n == 0)
    return 0;
  qsort(v, n, sizeof v[0], compare_doubles);
  size_t kept = 1;
  for (size_t i = 1; i < n; ++i)
    if (v[i] != v[kept - 1])
      v[kept++] = v[i];
  return kept;
}

int fb_tfun_new_callback(fb_tfun_fn fn, void *ctx, size_t nbreak, const double *breakpoints,
                         fb_tfun **out, fb_err *err)
{
  if (!fn)
    return fb_err_set(err, FB_EINVAL, "fb_tfun_new_callback: function is NULL");
  if (nbreak > 0 && !breakpoints)
    return fb_err_set(err, FB_EINVAL, "fb_tfun_new_callback: %zu breakpoints but array is NULL",
                      nbreak);
  for (size_t i = 0; i < nbreak; ++i)
    if (!isfinite(breakpoints[i]))
      return fb_err_set(err, FB_EINVAL, "callback breakpoints[%zu] is not finite (got %g)", i,
                        breakpoints[i]);
  int status = tfun_alloc(TFUN_CALLBACK, out, err);
  if (status != FB_OK)
    return status;
  fb_tfun *f = *out;
  f->u.callback.fn = fn;
  f->u.callback.ctx = ctx;
  status = copy_doubles(nbreak, breakpoints, &f->u.callback.breaks, err);
  if (status != FB_OK) {
    fb_tfun_free(out);
    return status;
  }
  f->u.callback.nbreak = sort_unique(f->u.callback.breaks, nbreak);
  return FB_OK;
}

int fb_tfun_new_callback_copy(fb_tfun_fn fn, const void *ctx, size_t ctx_size, size_t nbreak,
                              const double *breakpoints, fb_tfun **out, fb_err *err)
{
  if (!ctx || ctx_size == 0)
    return fb_err_set(err, FB_EINVAL, "fb_tfun_new_callback_copy: no context to copy");
  void *own = malloc(ctx_size);
  if (!own)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating a time function");
  memcpy(own, ctx, ctx_size);
  int status = fb_tfun_new_callback(fn, own, nbreak, breakpoints, out, err);
  if (status != FB_OK) {
    /* Not freed by fb_tfun_new_callback: ctx_size is still 0 there (the analyzer does not
     * track that field through the union). */
    free(own); /* NOLINT(clang-analyzer-unix.Malloc) */
    return status;
  }
  (*out)->u.callback.ctx_size = ctx_size;
  return FB_OK;
}

/* Deep copy; a callback's fn and ctx are copied as pointers (the caller
 * owns ctx and must keep it alive for the clone too), unless the function
 * holds its own copy of the context, which is copied again. */
int fb_tfun_clone(const fb_tfun *f, fb_tfun **out, fb_err *err)
{
  if (!f)
    return fb_err_set(err, FB_EINVAL, "fb_tfun_clone: function is NULL");
  switch (f->kind) {
  case TFUN_TABLE:
    return fb_tfun_new_table(f->u.table.n, f->u.table.times, f->u.table.values, out, err);
  case TFUN_CALLBACK:
    if (f->u.callback.ctx_size)
      return fb_tfun_new_callback_copy(f->u.callback.fn, f->u.callback.ctx,
                                       f->u.callback.ctx_size, f->u.callback.nbreak,
                                       f->u.callback.breaks, out, err);
    return fb_tfun_new_callback(f->u.callback.fn, f->u.callback.ctx, f->u.callback.nbreak,
                                f->u.callback.breaks, out, err);
  case TFUN_EXPR: {
    fb_expr *e = NULL;
    int status = fb_expr_clone(f->u.expr, &e, err);
    return status != FB_OK ? status : fb_tfun_new_expr(&e, out, err);
  }
  case TFUN_CONST:
  case TFUN_STEP:
  case TFUN_SINE: break;
  }
  int status = tfun_alloc(f->kind, out, err);
  if (status == FB_OK)
    **out = *f; /* plain values, nothing owned */
  return status;
}

void fb_tfun_free(fb_tfun **f)
{
  if (!f || !*f)
    return;
  switch ((*f)->kind) {
  case TFUN_TABLE:
    free((*f)->u.table.times);
    free((*f)->u.table.values);
    break;
  case TFUN_EXPR: fb_expr_free(&(*f)->u.expr); break;
  case TFUN_CALLBACK:
    free((*f)->u.callback.breaks);
    if ((*f)->u.callback.ctx_size)
      free((*f)->u.callback.ctx);
    break;
  case TFUN_CONST:
  case TFUN_STEP:
  case TFUN_SINE: break;
  }
  free(*f);
  *f = NULL;
}

/* Linear interpolation in the table, held at the end values outside it.
 * Binary search keeps the cost O(log n) for long measured tables. */
static double table_eval(size_t n, const double *times, const double *values, double t)
{
  if (t <= times[0])
    return values[0];
  if (t >= times[n - 1])
    return values[n - 1];
  size_t lo = 0, hi = n - 1; /* invariant: times[lo] < t < times[hi] or t == times[lo] */
  while (hi - lo > 1) {
    size_t mid = lo + (hi - lo) / 2;
    if (times[mid] <= t)
      lo = mid;
    else
      hi = mid;
  }
  double w = (t - times[lo]) / (times[hi] - times[lo]);
  return values[lo] + w * (values[hi] - values[lo]);
}

int fb_tfun_is_constant(const fb_tfun *f)
{
  return f->kind == TFUN_CONST || (f->kind == TFUN_EXPR && !fb_expr_uses_time(f->u.expr));
}

double fb_tfun_eval(const fb_tfun *f, double t)
{
  switch (f->kind) {
  case TFUN_CONST: return f->u.value;
  case TFUN_STEP: return t < f->u.step.t0 ? f->u.step.before : f->u.step.after;
  case TFUN_SINE:
    return f->u.sine.offset +
           f->u.sine.amplitude * sin(TWO_PI * f->u.sine.freq_hz * t + f->u.sine.phase_rad);
  case TFUN_TABLE: return table_eval(f->u.table.n, f->u.table.times, f->u.table.values, t);
  case TFUN_EXPR: return fb_expr_eval(f->u.expr, t);
  case TFUN_CALLBACK: return f->u.callback.fn(t, f->u.callback.ctx);
  }
  return NAN;
}

size_t fb_tfun_breakpoints(const fb_tfun *f, double *bp, size_t max)
{
  const double *src = NULL;
  size_t count = 0;
  switch (f->kind) {
  case TFUN_STEP:
    src = &f->u.step.t0;
    count = 1;
    break;
  case TFUN_TABLE:
    src = f->u.table.times + 1; /* interior knots: slope changes there */
    count = f->u.table.n >= 2 ? f->u.table.n - 2 : 0;
    break;
  case TFUN_CALLBACK:
    src = f->u.callback.breaks;
    count = f->u.callback.nbreak;
    break;
  case TFUN_CONST:
  case TFUN_SINE:
  case TFUN_EXPR: break;
  }
  if (bp && count > 0)
    memcpy(bp, src, (count < max ? count : max) * sizeof *bp);
  return count;
}

/* ---- CSV tables ---- */

static char *trim(char *s)
{
  while (*s == ' ' || *s == '\t')
    ++s;
  char *end = s + strlen(s);
  while (end > s && (end[-1] == ' ' || end[-1] == '\t'))
    --end;
  *end = '\0';
  return s;
}

/* Cuts the next comma-separated field from *cursor, trimmed; *cursor becomes
 * NULL after the last field. */
static char *next_field(char **cursor)
{
  char *start = *cursor;
  char *comma = strchr(start, ',');
  if (comma) {
    *comma = '\0';
    *cursor = comma + 1;
  } else {
    *cursor = NULL;
  }
  return trim(start);
}

typedef struct csv_columns {
  size_t count;      /* fields in the header */
  size_t time_index; /* SIZE_MAX until found */
  size_t value_index;
} csv_columns;

/* The header names the columns; time_col and value_col must each appear
 * exactly once (a second one would leave it unclear which to read). */
static int csv_read_header(fb_text_reader *r, const char *time_col, const char *value_col,
                           csv_columns *cols)
{
  char *text;
  int status = fb_text_next_data_line(r, '#', &text);
  if (status != FB_OK)
    return status;
  if (!text)
    return fb_err_set(r->err, FB_EPARSE,
                      "%s:%zu: no header line (file is empty or all comments)", r->path,
                      r->line_no ? r->line_no : 1);
  cols->count = 0;
  cols->time_index = cols->value_index = SIZE_MAX;
  for (char *cursor = text; cursor; ++cols->count) {
    const char *name = next_field(&cursor);
    const int is_time = strcmp(name, time_col) == 0, is_value = strcmp(name, value_col) == 0;
    if ((is_time && cols->time_index != SIZE_MAX) ||
        (is_value && cols->value_index != SIZE_MAX))
      return fb_err_set(r->err, FB_EPARSE, "%s:%zu: column '%s' appears twice", r->path,
                        r->line_no, name);
    if (is_time)
      cols->time_index = cols->count;
    if (is_value)
      cols->value_index = cols->count;
  }
  const char *missing = cols->time_index == SIZE_MAX    ? time_col
                        : cols->value_index == SIZE_MAX ? value_col
                                                        : NULL;
  if (missing)
    return fb_err_set(r->err, FB_EPARSE,
                      "%s:%zu: no column '%s' among the header's %zu field%s", r->path,
                      r->line_no, missing, cols->count, cols->count == 1 ? "" : "s");
  return FB_OK;
}

/* Parses field text of column name as a finite decimal number. */
static int csv_number(const fb_text_reader *r, const char *name, const char *text,
                      double *value)
{
  const int rc = fb_parse_decimal_field(text, value, r->err);
  if (rc)
    fb_err_prefix(r->err, "%s:%zu: column '%s': ", r->path, r->line_no, name);
  return rc;
}

/* Splits a data line and extracts its time and value. */
static int csv_parse_row(const fb_text_reader *r, char *text, const csv_columns *cols,
                         const char *time_col, const char *value_col, double *time,
                         double *value)
{
  const char *time_text = NULL, *value_text = NULL;
  size_t count = 0;
  for (char *cursor = text; cursor; ++count) {
    const char *field = next_field(&cursor);
    if (count == cols->time_index)
      time_text = field;
    if (count == cols->value_index)
      value_text = field;
  }
  if (count != cols->count)
    return fb_err_set(r->err, FB_EPARSE,
                      "%s:%zu: expected %zu fields as in the header, found %zu", r->path,
                      r->line_no, cols->count, count);
  assert(time_text && value_text); /* the header had both columns and as many fields */
  int status = csv_number(r, time_col, time_text, time);
  return status != FB_OK ? status : csv_number(r, value_col, value_text, value);
}

typedef struct csv_data {
  size_t n, capacity;
  double *times, *values;
} csv_data;

static int csv_data_push(csv_data *d, double time, double value, fb_err *err)
{
  if (d->n == d->capacity) {
    size_t capacity = d->capacity ? 2 * d->capacity : 64;
    double *times = realloc(d->times, capacity * sizeof *times);
    if (times)
      d->times = times;
    double *values = times ? realloc(d->values, capacity * sizeof *values) : NULL;
    if (!values)
      return fb_err_set(err, FB_ENOMEM, "out of memory reading a table");
    d->values = values;
    d->capacity = capacity;
  }
  d->times[d->n] = time;
  d->values[d->n] = value;
  ++d->n;
  return FB_OK;
}

/* Reads the header and all data rows of an open file into d. */
static int csv_read(fb_text_reader *r, const char *time_col, const char *value_col, csv_data *d)
{
  csv_columns cols = {0};
  int status = csv_read_header(r, time_col, value_col, &cols);
  for (;;) {
    char *text = NULL;
    if (status == FB_OK)
      status = fb_text_next_data_line(r, '#', &text);
    if (status != FB_OK || !text)
      break;
    double time, value;
    status = csv_parse_row(r, text, &cols, time_col, value_col, &time, &value);
    if (status == FB_OK && d->n > 0 && !(time > d->times[d->n - 1]))
      status = fb_err_set(r->err, FB_EPARSE,
                          "%s:%zu: time %g is not greater than the previous time %g (times "
                          "must be strictly increasing)",
                          r->path, r->line_no, time, d->times[d->n - 1]);
    if (status == FB_OK)
      status = csv_data_push(d, time, value, r->err);
  }
  if (status == FB_OK && d->n == 0)
    status = fb_err_set(r->err, FB_EPARSE, "%s:%zu: too few rows: no data after the header",
                        r->path, r->line_no);
  return status;
}

/* Format: a header line of comma-separated column names, then rows of
 * numbers; spaces around fields, blank lines and '#' comment lines are
 * ignored, and so is a byte-order mark at the start. Quoted fields are not
 * supported; numbers are plain decimals (fb_parse_decimal). */
int fb_tfun_new_table_csv(const char *path, const char *time_col, const char *value_col,
                          fb_tfun **out, fb_err *err)
{
  if (!path || !time_col || !value_col || !out)
    return fb_err_set(err, FB_EINVAL, "fb_tfun_new_table_csv: NULL argument");
  *out = NULL;
  fb_text_reader r;
  if (fb_text_open(&r, path, "CSV", err))
    return FB_EIO;
  csv_data d = {0};
  int status = csv_read(&r, time_col, value_col, &d);
  if (status == FB_OK)
    status = fb_tfun_new_table(d.n, d.times, d.values, out, err);
  fb_text_close(&r);
  free(d.times);
  free(d.values);
  return status;
}

void fb_tfun_describe(const fb_tfun *f, fb_tfun_info *out)
{
  memset(out, 0, sizeof *out);
  switch (f->kind) {
  case TFUN_CONST:
    out->kind = FB_TFUN_CONST;
    out->value = f->u.value;
    break;
  case TFUN_STEP:
    out->kind = FB_TFUN_STEP;
    out->t0 = f->u.step.t0;
    out->before = f->u.step.before;
    out->after = f->u.step.after;
    break;
  case TFUN_SINE:
    out->kind = FB_TFUN_SINE;
    out->amplitude = f->u.sine.amplitude;
    out->freq_hz = f->u.sine.freq_hz;
    out->phase_rad = f->u.sine.phase_rad;
    out->offset = f->u.sine.offset;
    break;
  case TFUN_TABLE:
    out->kind = FB_TFUN_TABLE;
    out->n = f->u.table.n;
    out->times = f->u.table.times;
    out->values = f->u.table.values;
    break;
  case TFUN_EXPR:
    out->kind = FB_TFUN_EXPR;
    out->expr = f->u.expr;
    break;
  case TFUN_CALLBACK:
    out->kind = FB_TFUN_CALLBACK;
    out->fn = f->u.callback.fn;
    out->ctx = f->u.callback.ctx;
    break;
  }
}
