/* SPDX-License-Identifier: BSD-3-Clause */
/* Matrix Market reader and writer (see flexbond/mat.h). Format: Boisvert,
 * Pozo & Remington, "The Matrix Market Exchange Formats: Initial Design",
 * NISTIR 5935, 1996. Supported: matrix coordinate|array real|integer
 * general|symmetric (the header promises real arrays; integer ones cost
 * nothing more); symmetric
 * files hold the lower triangle only (the spec's rule, enforced here so an
 * entry and its mirror are never summed twice). Comment lines (starting
 * with %) and blank lines may appear anywhere after the header. Values are
 * plain decimals (fb_parse_decimal): strtod's hexadecimal, "inf" and "nan"
 * are refused. */
#include <assert.h>
#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "flexbond/mat.h"

#include "core/textfile.h"
#include "core/tmpfile.h"

typedef struct mtx_header {
  int coordinate; /* coordinate (sparse) or array (dense) format */
  int integer;    /* integer field, else real */
  int symmetric;  /* lower triangle stored, mirrored on reading */
} mtx_header;

typedef struct mtx_size {
  size_t nrows;
  size_t ncols;
  size_t entries; /* data lines the size line announces */
} mtx_size;

/* The dimensions the caller expects, 0 where it does not know. */
typedef struct mtx_expect {
  size_t nrows;
  size_t ncols;
} mtx_expect;

/* The shortest data line of each format, with its line end: "1 1 1\n"
 * (coordinate) and "1\n" (array). A file of B bytes holds at most B / 6
 * or B / 2 entries, whatever its size line says. */
#define MTX_MIN_COORDINATE_LINE 6
#define MTX_MIN_ARRAY_LINE 2

/* The file (path, err) and its current line (line, line_no). */
typedef fb_text_reader mtx_reader;

/* Entries read so far; rows/cols stay NULL for the array format. */
typedef struct mtx_entries {
  size_t *rows;
  size_t *cols;
  double *vals;
  size_t count;
  size_t cap;
} mtx_entries;

/* Records FB_EPARSE with "path:line: " before the formatted message. */
static int parse_error(const mtx_reader *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static int parse_error(const mtx_reader *r, const char *fmt, ...)
{
  char msg[FB_ERR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  /* An empty file has no line 0: the missing header belongs on line 1. */
  const size_t line = r->line_no ? r->line_no : 1;
  return fb_err_set(r->err, FB_EPARSE, "%s:%zu: %s", r->path, line, msg);
}

/* rc, after recording tok (may be NULL) as the error's excerpt: a
 * matrix file's text goes there, never into the message. */
static int quoting(const mtx_reader *r, const char *tok, int rc)
{
  if (tok)
    fb_err_set_excerpt(r->err, tok, strlen(tok));
  return rc;
}
#if defined(__clang_analyzer__)
/* For the static analyzer only, which does not follow calls to variadic functions. */
#define parse_error(r, ...) (parse_error((r), __VA_ARGS__), FB_EPARSE)
#endif

/* Next whitespace-separated token of *cursor (NUL-terminated in place),
 * or NULL when none is left. */
static char *next_token(char **cursor)
{
  char *p = *cursor + strspn(*cursor, " \t");
  if (*p == '\0')
    return NULL;
  char *end = p + strcspn(p, " \t");
  if (*end != '\0')
    *end++ = '\0';
  *cursor = end;
  return p;
}

/* Parses an unsigned decimal integer (no sign) filling the whole token. */
static int parse_count(const char *tok, size_t *out)
{
  if (!tok || !isdigit((unsigned char)tok[0]))
    return 0;
  errno = 0;
  char *end;
  const unsigned long long v = strtoull(tok, &end, 10);
  if (errno || *end != '\0' || v > SIZE_MAX)
    return 0;
  *out = (size_t)v;
  return 1;
}

static int parse_value(const mtx_reader *r, const mtx_header *h, const char *tok, double *out)
{
  if (!tok)
    return parse_error(r, "missing value");
  if (h->integer) {
    char *end;
    errno = 0;
    const long long v = strtoll(tok, &end, 10);
    if (errno || end == tok || *end != '\0')
      return quoting(r, tok, parse_error(r, "invalid integer value"));
    *out = (double)v;
    return FB_OK;
  }
  const int rc = fb_parse_decimal_field(tok, out, r->err);
  if (rc)
    fb_err_prefix(r->err, "%s:%zu: value: ", r->path, r->line_no);
  return rc;
}

static int no_more_tokens(const mtx_reader *r, char **cursor)
{
  const char *extra = next_token(cursor);
  return extra ? quoting(r, extra, parse_error(r, "unexpected text at the end of the line"))
               : FB_OK;
}

/* Matches tok case-insensitively against choices[0..n); index or -1. */
static int choose(const char *tok, const char *const *choices, int n)
{
  for (int k = 0; tok && k < n; ++k)
    if (strcasecmp(tok, choices[k]) == 0)
      return k;
  return -1;
}

static int read_header(mtx_reader *r, mtx_header *h)
{
  static const char *const formats[] = {"array", "coordinate"};
  static const char *const fields[] = {"real", "integer"};
  static const char *const symmetries[] = {"general", "symmetric"};
  char *cursor = NULL;
  int rc = fb_text_next_line(r, &cursor);
  if (rc)
    return rc;
  if (!cursor)
    return parse_error(r, "empty file, expected a '%%%%MatrixMarket matrix ...' header");
  const char *banner = next_token(&cursor);
  const char *object = next_token(&cursor);
  if (!banner || strcasecmp(banner, "%%MatrixMarket") != 0 || !object ||
      strcasecmp(object, "matrix") != 0)
    return parse_error(r, "expected a '%%%%MatrixMarket matrix ...' header");
  const char *format = next_token(&cursor);
  const char *field = next_token(&cursor);
  const char *symmetry = next_token(&cursor);
  h->coordinate = choose(format, formats, 2);
  h->integer = choose(field, fields, 2);
  h->symmetric = choose(symmetry, symmetries, 2);
  if (h->coordinate < 0)
    return quoting(r, format,
                   parse_error(r, "unsupported format: expected array or coordinate"));
  if (h->integer < 0)
    return quoting(r, field, parse_error(r, "unsupported field: expected real or integer"));
  if (h->symmetric < 0)
    return quoting(r, symmetry,
                   parse_error(r, "unsupported symmetry: expected general or symmetric"));
  return no_more_tokens(r, &cursor);
}

/* Number of data lines of the array format: n(n+1)/2 for symmetric. */
static int array_entries(const mtx_reader *r, const mtx_header *h, mtx_size *s)
{
  /* Bounding rows*cols*sizeof(double) also keeps n*(n+1) from overflowing. */
  if (s->ncols != 0 && s->nrows > SIZE_MAX / sizeof(double) / s->ncols)
    return parse_error(r, "matrix %zu x %zu is too large", s->nrows, s->ncols);
  s->entries = h->symmetric ? s->ncols * (s->ncols + 1) / 2 : s->nrows * s->ncols;
  return FB_OK;
}

/* One declared dimension against the expected one (0: any up to
 * FB_MTX_MAX_DIM). */
static int check_dim(const mtx_reader *r, const char *what, size_t declared, size_t expected)
{
  if (expected && declared != expected)
    return parse_error(r, "the matrix has %zu %s, expected %zu", declared, what, expected);
  if (!expected && declared > FB_MTX_MAX_DIM)
    return parse_error(r,
                       "%zu %s, more than the %zu a Matrix Market file may declare "
                       "(docs/errors.md, \"Limits\")",
                       declared, what, FB_MTX_MAX_DIM);
  return FB_OK;
}

/* The size line against the caller's dimensions and the file's size,
 * before anything is allocated for it: a 62-byte file must not make the
 * reader allocate gigabytes. */
static int check_size(const mtx_reader *r, const mtx_header *h, const mtx_size *s,
                      const mtx_expect *x)
{
  int rc = check_dim(r, "rows", s->nrows, x->nrows);
  if (!rc)
    rc = check_dim(r, "columns", s->ncols, x->ncols);
  if (rc)
    return rc;
  /* In doubles: a caller's rows x columns may overflow size_t. */
  const double cells = (double)s->nrows * (double)s->ncols;
  const double most = h->symmetric ? 0.5 * cells + 0.5 * (double)s->ncols : cells;
  if ((double)s->entries > most)
    return parse_error(r, "%zu entries declared, more than the %.0f of a %zu x %zu%s matrix",
                       s->entries, most, s->nrows, s->ncols,
                       h->symmetric ? " symmetric (lower triangle)" : "");
  struct stat st;
  const size_t line = h->coordinate ? MTX_MIN_COORDINATE_LINE : MTX_MIN_ARRAY_LINE;
  if (fstat(fileno(r->fp), &st) == 0 && (double)s->entries > (double)st.st_size / (double)line)
    return parse_error(r,
                       "%zu entries declared, more than the file's %lld bytes can hold (each "
                       "takes at least %zu)",
                       s->entries, (long long)st.st_size, line);
  return FB_OK;
}

static int read_size(mtx_reader *r, const mtx_header *h, mtx_size *s)
{
  *s = (mtx_size){0, 0, 0}; /* defined on every path, a failing one too */
  char *cursor = NULL;
  int rc = fb_text_next_data_line(r, '%', &cursor);
  if (rc)
    return rc;
  if (!cursor)
    return parse_error(r, "missing size line");
  const char *rows = next_token(&cursor);
  const char *cols = next_token(&cursor);
  const char *entries = h->coordinate ? next_token(&cursor) : NULL;
  if (!parse_count(rows, &s->nrows) || !parse_count(cols, &s->ncols) ||
      (h->coordinate && !parse_count(entries, &s->entries)))
    return parse_error(r, "expected size line '%s'",
                       h->coordinate ? "rows columns entries" : "rows columns");
  rc = no_more_tokens(r, &cursor);
  if (rc)
    return rc;
  if (h->symmetric && s->nrows != s->ncols)
    return parse_error(r, "symmetric matrix must be square, not %zu x %zu", s->nrows, s->ncols);
  return h->coordinate ? FB_OK : array_entries(r, h, s);
}

static int push_entry(const mtx_reader *r, mtx_entries *e, size_t row, size_t col, double val)
{
  assert(!e->rows == !e->cols); /* both for the coordinate format, neither for array */
  if (e->count == e->cap) {
    const size_t cap = e->cap ? 2 * e->cap : 64;
    if (cap > SIZE_MAX / sizeof(double) / 2)
      return fb_err_set(r->err, FB_ENOMEM, "out of memory reading %s", r->path);
    double *vals = realloc(e->vals, cap * sizeof *vals);
    if (vals)
      e->vals = vals;
    size_t *rows = e->rows ? realloc(e->rows, cap * sizeof *rows) : NULL;
    if (rows)
      e->rows = rows;
    size_t *cols = e->cols ? realloc(e->cols, cap * sizeof *cols) : NULL;
    if (cols)
      e->cols = cols;
    if (!vals || (e->rows && !rows) || (e->cols && !cols))
      return fb_err_set(r->err, FB_ENOMEM, "out of memory reading %s", r->path);
    e->cap = cap;
  }
  if (e->rows) {
    e->rows[e->count] = row;
    e->cols[e->count] = col;
  }
  e->vals[e->count++] = val;
  return FB_OK;
}

/* Parses a 1-based index token into 0-based *out, checking 1..n. */
static int parse_index(const mtx_reader *r, const char *what, const char *tok, size_t n,
                       size_t *out)
{
  size_t v;
  if (!tok)
    return parse_error(r, "missing %s index", what);
  if (!parse_count(tok, &v))
    return quoting(r, tok, parse_error(r, "invalid %s index", what));
  if (v < 1 || v > n)
    return parse_error(r, "%s index %zu out of range 1..%zu", what, v, n);
  *out = v - 1;
  return FB_OK;
}

/* One "i j value" line; a symmetric off-diagonal entry is also mirrored. */
static int read_coordinate_entry(const mtx_reader *r, char *cursor, const mtx_header *h,
                                 const mtx_size *s, mtx_entries *e)
{
  size_t i = 0, j = 0;
  double v = 0.0;
  int rc = parse_index(r, "row", next_token(&cursor), s->nrows, &i);
  if (!rc)
    rc = parse_index(r, "column", next_token(&cursor), s->ncols, &j);
  if (!rc)
    rc = parse_value(r, h, next_token(&cursor), &v);
  if (!rc)
    rc = no_more_tokens(r, &cursor);
  if (!rc && h->symmetric && i < j)
    rc = parse_error(r, "entry (%zu, %zu) is above the diagonal of a symmetric matrix", i + 1,
                     j + 1);
  if (!rc)
    rc = push_entry(r, e, i, j, v);
  if (!rc && h->symmetric && i != j)
    rc = push_entry(r, e, j, i, v);
  return rc;
}

static int read_array_entry(const mtx_reader *r, char *cursor, const mtx_header *h,
                            mtx_entries *e)
{
  double v = 0.0;
  int rc = parse_value(r, h, next_token(&cursor), &v);
  if (!rc)
    rc = no_more_tokens(r, &cursor);
  return rc ? rc : push_entry(r, e, 0, 0, v);
}

static int read_entries(mtx_reader *r, const mtx_header *h, const mtx_size *s, mtx_entries *e)
{
  size_t nread = 0;
  for (;;) {
    char *line = NULL;
    int rc = fb_text_next_data_line(r, '%', &line);
    if (rc)
      return rc;
    if (!line)
      break;
    if (nread == s->entries)
      return parse_error(r, "more entries than the %zu declared", s->entries);
    rc = h->coordinate ? read_coordinate_entry(r, line, h, s, e)
                       : read_array_entry(r, line, h, e);
    if (rc)
      return rc;
    ++nread;
  }
  if (nread < s->entries)
    return parse_error(r, "file ends after %zu of the %zu declared entries", nread, s->entries);
  return FB_OK;
}

/* Dense matrix from the lower triangle listed column by column. */
static int symmetric_array(const mtx_reader *r, size_t n, const double *lower, fb_mat **out)
{
  double *full = malloc((n ? n * n : 1) * sizeof *full);
  if (!full)
    return fb_err_set(r->err, FB_ENOMEM, "out of memory reading %s", r->path);
  size_t k = 0;
  for (size_t j = 0; j < n; ++j) {
    for (size_t i = j; i < n; ++i) {
      full[i + j * n] = lower[k];
      full[j + i * n] = lower[k++];
    }
  }
  const int rc = fb_mat_new_dense(n, n, full, out, r->err);
  free(full);
  return rc;
}

static int read_mtx(mtx_reader *r, const mtx_expect *x, mtx_entries *e, fb_mat **out)
{
  mtx_header h;
  mtx_size s;
  int rc = read_header(r, &h);
  if (!rc)
    rc = read_size(r, &h, &s);
  if (!rc)
    rc = check_size(r, &h, &s, x);
  if (rc)
    return rc;
  if (h.coordinate) {
    /* Empty arrays that push_entry grows alongside vals. */
    e->rows = malloc(sizeof *e->rows);
    e->cols = malloc(sizeof *e->cols);
    if (!e->rows || !e->cols)
      return fb_err_set(r->err, FB_ENOMEM, "out of memory reading %s", r->path);
  }
  rc = read_entries(r, &h, &s, e);
  if (rc)
    return rc;
  if (h.coordinate)
    return fb_mat_new_triplets(s.nrows, s.ncols, e->count, e->rows, e->cols, e->vals, out,
                               r->err);
  if (h.symmetric)
    return symmetric_array(r, s.ncols, e->vals, out);
  return fb_mat_new_dense(s.nrows, s.ncols, e->vals, out, r->err);
}

int fb_mat_read_mtx(const char *path, fb_mat **out, fb_err *err)
{
  return fb_mat_read_mtx_dims(path, 0, 0, out, err);
}

int fb_mat_read_mtx_dims(const char *path, size_t nrows, size_t ncols, fb_mat **out,
                         fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "matrix output pointer is NULL");
  *out = NULL;
  if (!path)
    return fb_err_set(err, FB_EINVAL, "Matrix Market path is NULL");
  mtx_reader r;
  if (fb_text_open(&r, path, "Matrix Market", err))
    return FB_EIO;
  mtx_entries e = {NULL, NULL, NULL, 0, 0};
  const mtx_expect x = {nrows, ncols};
  const int rc = read_mtx(&r, &x, &e, out);
  fb_text_close(&r);
  free(e.rows);
  free(e.cols);
  free(e.vals);
  return rc;
}

static void count_entry(void *ctx, size_t row, size_t col, double val)
{
  (void)row;
  (void)col;
  (void)val;
  ++*(size_t *)ctx;
}

static void write_entry(void *ctx, size_t row, size_t col, double val)
{
  fprintf(ctx, "%zu %zu %.17g\n", row + 1, col + 1, val);
}

/* A dense matrix in the array format, column by column: read back, it is
 * dense again, so a model written and reloaded computes with the same
 * storage and in the same order as the one assembled. */
static void print_array(FILE *fp, const fb_mat *a)
{
  const size_t nr = fb_mat_nrows(a), nc = fb_mat_ncols(a);
  fprintf(fp, "%%%%MatrixMarket matrix array real general\n%zu %zu\n", nr, nc);
  for (size_t j = 0; j < nc; ++j)
    for (size_t i = 0; i < nr; ++i)
      fprintf(fp, "%.17g\n", fb_mat_get(a, i, j));
}

/* %.17g makes every double round-trip exactly through strtod (IEEE
 * 754-2008, section 5.12.2: 17 significant digits suffice for binary64). */
void fb_mat_print_mtx(FILE *fp, const fb_mat *a)
{
  if (!fb_mat_is_sparse(a)) {
    print_array(fp, a);
    return;
  }
  size_t entries = 0;
  fb_mat_foreach(a, count_entry, &entries);
  fprintf(fp, "%%%%MatrixMarket matrix coordinate real general\n%zu %zu %zu\n", fb_mat_nrows(a),
          fb_mat_ncols(a), entries);
  fb_mat_foreach(a, write_entry, fp);
}

/* Through a temporary file beside path, created exclusively
 * (core/tmpfile.h), renamed over path once complete. */
int fb_mat_write_mtx(const fb_mat *a, const char *path, fb_err *err)
{
  if (!a || !path)
    return fb_err_set(err, FB_EINVAL, "matrix or path is NULL");
  int fd = -1;
  char *tmp = NULL;
  const int e = fb_tmpfile_create(path, &fd, &tmp);
  FILE *fp = e == 0 ? fdopen(fd, "w") : NULL;
  if (!fp) {
    const int why = e ? e : errno;
    if (fd >= 0)
      close(fd);
    if (tmp)
      remove(tmp);
    free(tmp);
    return fb_err_set(err, why == ENOMEM ? FB_ENOMEM : FB_EIO,
                      "%s: cannot open for writing: %s", path, strerror(why));
  }
  errno = 0;
  fb_mat_print_mtx(fp, a);
  const int write_failed = ferror(fp) || fflush(fp) != 0;
  const int saved = errno;
  const int close_failed = fclose(fp) != 0;
  int rc = FB_OK;
  if (write_failed || close_failed)
    rc = fb_err_set(err, FB_EIO, "%s: write failed: %s", path,
                    strerror(saved   ? saved
                             : errno ? errno
                                     : EIO));
  else if (rename(tmp, path) != 0)
    rc = fb_err_set(err, FB_EIO, "%s: cannot move into place: %s", path, strerror(errno));
  if (rc != FB_OK)
    remove(tmp);
  free(tmp);
  return rc;
}
