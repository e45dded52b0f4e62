/* SPDX-License-Identifier: BSD-3-Clause */
/* The OpenCRG file reader (flexbond/crg.h), written from the ASAM
 * OpenCRG specification 1.2.0, chapter 3; section numbers below are its.
 *
 * A file is read whole into memory (fb_read_file; its size bounds every
 * allocation), then taken line by line: sections start with "$KEYWORD" and end at a
 * line starting with "$" (3.2); "*" in column 1 makes a comment line and
 * "!" starts an inline comment (3.3). The road data (3.4.7) follows a
 * line starting with "$$$$" (binary and formatted data), or, for the
 * formatted formats, starts at the first line outside a section after the
 * data definition. Referenced files (3.4.6) are read at the point of
 * their $ROAD_CRG_FILE section, so that what follows overrides them ("the
 * last definition takes precedence"). */
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "flexbond/crg.h"

#include "core/util.h"
#include "road/crg_internal.h"

/* Files referenced through files referenced ...: deeper is taken for a
 * cycle. */
enum { MAX_DEPTH = 8 };

/* ---- $ROAD_CRG keys (3.4.2), as the reader keeps them. */
enum {
  R_START_U,
  R_END_U,
  R_INCREMENT,
  R_V_RIGHT,
  R_V_LEFT,
  R_V_INCREMENT,
  R_START_S,
  R_END_S,
  R_START_B,
  R_END_B,
  R_START_X,
  R_START_Y,
  R_END_X,
  R_END_Y,
  R_OFFSET_X,
  R_OFFSET_Y,
  R_START_PHI,
  R_END_PHI,
  R_OFFSET_PHI,
  R_START_Z,
  R_END_Z,
  R_OFFSET_Z,
  R_START_LON,
  R_START_LAT,
  R_END_LON,
  R_END_LAT,
  R_START_ALT,
  R_END_ALT,
  NROAD
};
static const char *const ROAD_KEYS[NROAD] = {
    "REFERENCE_LINE_START_U",    "REFERENCE_LINE_END_U",     "REFERENCE_LINE_INCREMENT",
    "LONG_SECTION_V_RIGHT",      "LONG_SECTION_V_LEFT",      "LONG_SECTION_V_INCREMENT",
    "REFERENCE_LINE_START_S",    "REFERENCE_LINE_END_S",     "REFERENCE_LINE_START_B",
    "REFERENCE_LINE_END_B",      "REFERENCE_LINE_START_X",   "REFERENCE_LINE_START_Y",
    "REFERENCE_LINE_END_X",      "REFERENCE_LINE_END_Y",     "REFERENCE_LINE_OFFSET_X",
    "REFERENCE_LINE_OFFSET_Y",   "REFERENCE_LINE_START_PHI", "REFERENCE_LINE_END_PHI",
    "REFERENCE_LINE_OFFSET_PHI", "REFERENCE_LINE_START_Z",   "REFERENCE_LINE_END_Z",
    "REFERENCE_LINE_OFFSET_Z",   "REFERENCE_LINE_START_LON", "REFERENCE_LINE_START_LAT",
    "REFERENCE_LINE_END_LON",    "REFERENCE_LINE_END_LAT",   "REFERENCE_LINE_START_ALT",
    "REFERENCE_LINE_END_ALT"};

/* ---- $ROAD_CRG_MODS keys (3.4.5). */
enum {
  M_REFPOINT_U,
  M_REFPOINT_V,
  M_REFPOINT_U_FRACTION,
  M_REFPOINT_U_OFFSET,
  M_REFPOINT_V_FRACTION,
  M_REFPOINT_V_OFFSET,
  M_REFPOINT_X,
  M_REFPOINT_Y,
  M_REFPOINT_Z,
  M_REFPOINT_PHI,
  M_ROTCENTER_X,
  M_ROTCENTER_Y,
  M_OFFSET_PHI,
  M_OFFSET_X,
  M_OFFSET_Y,
  M_OFFSET_Z,
  M_SCALE_Z_GRID,
  M_SCALE_SLOPE,
  M_SCALE_BANKING,
  M_SCALE_LENGTH,
  M_SCALE_WIDTH,
  M_SCALE_CURVATURE,
  M_GRID_NAN_MODE,
  M_GRID_NAN_OFFSET,
  NMODS
};
static const char *const MOD_KEYS[NMODS] = {
    "REFPOINT_U",          "REFPOINT_V",        "REFPOINT_U_FRACTION", "REFPOINT_U_OFFSET",
    "REFPOINT_V_FRACTION", "REFPOINT_V_OFFSET", "REFPOINT_X",          "REFPOINT_Y",
    "REFPOINT_Z",          "REFPOINT_PHI",      "REFLINE_ROTCENTER_X", "REFLINE_ROTCENTER_Y",
    "REFLINE_OFFSET_PHI",  "REFLINE_OFFSET_X",  "REFLINE_OFFSET_Y",    "REFLINE_OFFSET_Z",
    "SCALE_Z_GRID",        "SCALE_SLOPE",       "SCALE_BANKING",       "SCALE_LENGTH",
    "SCALE_WIDTH",         "SCALE_CURVATURE",   "GRID_NAN_MODE",       "GRID_NAN_OFFSET"};

/* ---- $ROAD_CRG_OPTS keys (3.4.4) that change z(u, v); the others in
 * its table (and the tools' own, such as LOG_*) are accepted and unused. */
enum {
  O_BORDER_MODE_U,
  O_BORDER_MODE_V,
  O_BORDER_OFFSET_U,
  O_BORDER_OFFSET_V,
  O_SMOOTH_UBEG,
  O_SMOOTH_UEND,
  O_CONTINUATION,
  NOPTS
};
static const char *const OPT_KEYS[NOPTS] = {
    "BORDER_MODE_U",      "BORDER_MODE_V",      "BORDER_OFFSET_U",     "BORDER_OFFSET_V",
    "BORDER_SMOOTH_UBEG", "BORDER_SMOOTH_UEND", "REFLINE_CONTINUATION"};

/* A block of key = value settings: the values and which were given. */
typedef struct crg_keys {
  double value[NROAD]; /* NROAD is the largest block */
  unsigned char set[NROAD];
} crg_keys;

/* Data channels (3.4.3). */
typedef enum chan_kind { CH_PHI, CH_SLOPE, CH_BANK, CH_LONG_AT, CH_LONG_N } chan_kind;
typedef struct crg_chan {
  chan_kind kind;
  double v; /* CH_LONG_AT: v, m; CH_LONG_N: the section's number */
  size_t line;
} crg_chan;

/* Road data formats (3.4.3): formatted (10 / 20 characters a number, 8 /
 * 4 a record) or binary big-endian IEEE (4 / 8 bytes, 20 / 10 a record). */
typedef enum crg_format { F_LRFI, F_LDFI, F_KRBI, F_KDBI } crg_format;
static const char *const FORMAT_NAMES[] = {"LRFI", "LDFI", "KRBI", "KDBI"};
enum { RECORD_BYTES = 80 };

/* What the files read so far say. */
typedef struct crg_state {
  fb_err *err;
  crg_keys road, mods, opts;
  int mods_given; /* a $ROAD_CRG_MODS section was read */
  /* The road data, from the one file that has it. */
  char *data_path;
  crg_chan *chan;
  size_t nch, nrows;
  double *values; /* nrows * nch, as read */
} crg_state;

/* One file being read. */
typedef struct crg_file {
  const char *path;
  char *text; /* the whole file */
  size_t size, pos, line_no;
  crg_state *st;
  int depth;
  /* Its data definition. */
  int has_kd, format_set;
  crg_format format;
  crg_chan *chan;
  size_t nch, chan_cap;
} crg_file;

static int fail_line(const crg_file *f, size_t line, const char *what, const char *detail)
{
  return fb_err_set(f->st->err, FB_EPARSE, "%s:%zu: %s%s%s", f->path, line, what,
                    detail ? ": " : "", detail ? detail : "");
}

/* The next line of f into buf (at most cap - 1 characters, '\r' and '\n'
 * removed), or 0 at the end. A longer header line is cut: no header key
 * of the specification comes near it. */
static int next_line(crg_file *f, char *buf, size_t cap)
{
  if (f->pos >= f->size)
    return 0;
  const char *start = f->text + f->pos, *end = memchr(start, '\n', f->size - f->pos);
  const size_t len = end ? (size_t)(end - start) : f->size - f->pos;
  f->pos += len + (end ? 1 : 0);
  ++f->line_no;
  size_t n = len < cap - 1 ? len : cap - 1;
  memcpy(buf, start, n);
  while (n > 0 && (buf[n - 1] == '\r' || buf[n - 1] == '\n'))
    --n;
  buf[n] = '\0';
  return 1;
}

/* Cuts an inline comment ("!", 3.3) and the blanks around text. */
static char *strip(char *text)
{
  char *bang = strchr(text, '!');
  if (bang)
    *bang = '\0';
  while (*text == ' ' || *text == '\t')
    ++text;
  char *end = text + strlen(text);
  while (end > text && isspace((unsigned char)end[-1]))
    --end;
  *end = '\0';
  return text;
}

/* A whole decimal number (fixed point or scientific) in text. */
static int parse_number(const char *text, double *out)
{
  char *end = NULL;
  while (*text == ' ')
    ++text;
  if (!*text)
    return 0;
  *out = strtod(text, &end);
  while (end && *end == ' ')
    ++end;
  return end && *end == '\0' && isfinite(*out);
}

/* "KEY = value" (3.4.2, 3.4.4, 3.4.5) of a key in names[0..n) into keys;
 * unknown keys: an error when strict, else skipped. */
static int read_setting(crg_file *f, char *text, const char *const *names, size_t n,
                        crg_keys *keys, int strict, const char *section)
{
  char *eq = strchr(text, '=');
  if (!eq)
    return fail_line(f, f->line_no, "expected KEY = value in", section);
  *eq = '\0';
  char *key = strip(text);
  double v;
  if (!parse_number(eq + 1, &v))
    return fb_err_set(f->st->err, FB_EPARSE, "%s:%zu: %s: not a number: '%s'", f->path,
                      f->line_no, key, strip(eq + 1));
  for (size_t k = 0; k < n; ++k)
    if (strcasecmp(key, names[k]) == 0) {
      keys->value[k] = v;
      keys->set[k] = 1;
      return FB_OK;
    }
  return strict ? fb_err_set(f->st->err, FB_EPARSE, "%s:%zu: %s: not a key of %s (%s)", f->path,
                             f->line_no, key, section,
                             strcmp(section, "$ROAD_CRG") ? "specification 3.4.5"
                                                          : "specification 3.4.2")
                : FB_OK;
}

/* A "D:" channel definition (3.4.3); "U:" virtual channels are skipped. */
static int read_channel(crg_file *f, const char *text)
{
  char name[128];
  const char *comma = strchr(text, ',');
  size_t len = comma ? (size_t)(comma - text) : strlen(text);
  if (len >= sizeof name)
    len = sizeof name - 1;
  memcpy(name, text, len);
  name[len] = '\0';
  char *nm = strip(name);
  crg_chan c = {.line = f->line_no};
  double v;
  if (strcasecmp(nm, "reference line phi") == 0)
    c.kind = CH_PHI;
  else if (strcasecmp(nm, "reference line slope") == 0)
    c.kind = CH_SLOPE;
  else if (strcasecmp(nm, "reference line banking") == 0)
    c.kind = CH_BANK;
  else if (strncasecmp(nm, "long section at v", 17) == 0 && strchr(nm, '=') &&
           parse_number(strchr(nm, '=') + 1, &v)) {
    c.kind = CH_LONG_AT;
    c.v = v;
  } else if (strncasecmp(nm, "long section ", 13) == 0 && parse_number(nm + 13, &v) &&
             v >= 1.0 && v == floor(v)) {
    c.kind = CH_LONG_N;
    c.v = v;
  } else {
    return fail_line(f, f->line_no,
                     "a channel this reader does not know (3.4.3: reference line phi, "
                     "slope or banking; long section at v = X; long section N)",
                     nm);
  }
  for (size_t k = 0; k < f->nch; ++k)
    if (c.kind == f->chan[k].kind && c.kind <= CH_BANK)
      return fail_line(f, f->line_no, "a second channel of the same kind", nm);
  if (fb_grow((void **)&f->chan, &f->chan_cap, f->nch, sizeof *f->chan))
    return fb_err_set(f->st->err, FB_ENOMEM, "%s: out of memory for its channels", f->path);
  f->chan[f->nch++] = c;
  return FB_OK;
}

static int read_kd_line(crg_file *f, char *raw)
{
  char *text = strip(raw);
  if (!*text)
    return FB_OK;
  if (text[0] == '#' && text[1] == ':') {
    const char *fmt = strip(text + 2);
    for (int k = 0; k < 4; ++k)
      if (strcasecmp(fmt, FORMAT_NAMES[k]) == 0) {
        f->format = (crg_format)k;
        f->format_set = 1;
        return FB_OK;
      }
    return fail_line(f, f->line_no, "a data format other than LRFI, LDFI, KRBI, KDBI (3.4.3)",
                     fmt);
  }
  if ((text[0] == 'D' || text[0] == 'd') && text[1] == ':')
    return read_channel(f, text + 2);
  if ((text[0] == 'U' || text[0] == 'u') && text[1] == ':')
    return FB_OK; /* 3.4.3: virtual channels may safely be ignored */
  return fail_line(f, f->line_no, "expected #:FORMAT, D:channel or U:channel in $KD_DEFINITION",
                   text);
}

static int read_file_at(const char *path, crg_state *st, int depth, const char *from,
                        size_t from_line);

/* The path a $ROAD_CRG_FILE line names (3.4.6): "$NAME/rest" takes NAME
 * from the environment; a relative path is taken from the referencing
 * file's directory. */
static int resolve_reference(crg_file *f, const char *name, char **out)
{
  *out = NULL;
  char *expanded = NULL;
  if (name[0] == '$') {
    const char *slash = strchr(name, '/');
    const size_t len = slash ? (size_t)(slash - name - 1) : strlen(name + 1);
    char var[128];
    if (len == 0 || len >= sizeof var)
      return fail_line(f, f->line_no, "a file reference with a bad variable name", name);
    memcpy(var, name + 1, len);
    var[len] = '\0';
    const char *value = getenv(var);
    if (!value)
      return fb_err_set(f->st->err, FB_EIO,
                        "%s:%zu: the environment variable %s of '%s' is not set", f->path,
                        f->line_no, var, name);
    expanded = fb_strdup_printf("%s%s", value, slash ? slash : "");
  } else {
    expanded = fb_strdup(name);
  }
  if (!expanded)
    return fb_err_set(f->st->err, FB_ENOMEM, "out of memory for a file reference");
  if (expanded[0] == '/') {
    *out = expanded;
    return FB_OK;
  }
  char *dir = fb_dirname(f->path);
  *out = dir ? fb_path_join(dir, expanded) : NULL;
  free(dir);
  free(expanded);
  return *out ? FB_OK : fb_err_set(f->st->err, FB_ENOMEM, "out of memory for a file reference");
}

/* One line of a $ROAD_CRG_FILE section: a path, or a part of one. The
 * specification lets a path run over several lines (3.4.6); a reference
 * is taken as complete at a line that ends in ".crg". */
static int read_file_ref_line(crg_file *f, char *raw, char *acc, size_t cap)
{
  const char *text = strip(raw);
  if (!*text)
    return FB_OK;
  const size_t had = strlen(acc), add = strlen(text);
  if (had + add >= cap)
    return fail_line(f, f->line_no, "a file reference too long", text);
  memcpy(acc + had, text, add + 1);
  const size_t n = had + add;
  if (n < 4 || strcasecmp(acc + n - 4, ".crg") != 0)
    return FB_OK;
  char *path = NULL;
  int rc = resolve_reference(f, acc, &path);
  if (!rc)
    rc = read_file_at(path, f->st, f->depth + 1, f->path, f->line_no);
  free(path);
  acc[0] = '\0';
  return rc;
}

/* ---- Road data (3.4.7). */

/* IEEE big-endian 4- or 8-byte number at p. */
static double big_endian(const unsigned char *p, int bytes)
{
  uint64_t bits = 0;
  for (int k = 0; k < bytes; ++k)
    bits = bits << 8 | p[k];
  if (bytes == 4) {
    const uint32_t b32 = (uint32_t)bits;
    float v;
    memcpy(&v, &b32, sizeof v);
    return (double)v;
  }
  double v;
  memcpy(&v, &bits, sizeof v);
  return v;
}

/* Rows the definition asks for when REFERENCE_LINE_END_U is given, else 0. */
static int declared_rows(const crg_file *f, size_t *rows)
{
  const crg_keys *r = &f->st->road;
  *rows = 0;
  if (!r->set[R_END_U] || !r->set[R_INCREMENT])
    return FB_OK;
  const double u0 = r->set[R_START_U] ? r->value[R_START_U] : 0.0;
  const double n = (r->value[R_END_U] - u0) / r->value[R_INCREMENT];
  if (!(n >= 1.0) || fabs(n - floor(n + 0.5)) > 1e-6 * fmax(1.0, n) || n > 1e12)
    return fb_err_set(f->st->err, FB_EPARSE,
                      "%s: REFERENCE_LINE_END_U - START_U = %g is not a positive whole "
                      "number of increments %g (3.4.2)",
                      f->path, r->value[R_END_U] - u0, r->value[R_INCREMENT]);
  *rows = (size_t)floor(n + 0.5) + 1;
  return FB_OK;
}

static int alloc_values(crg_file *f, size_t nrows)
{
  crg_state *st = f->st;
  st->values = malloc(nrows * f->nch * sizeof *st->values);
  if (!st->values)
    return fb_err_set(st->err, FB_ENOMEM, "%s: out of memory for %zu x %zu values", f->path,
                      nrows, f->nch);
  st->nrows = nrows;
  return FB_OK;
}

static int row_all_nan(const double *v, size_t n)
{
  for (size_t k = 0; k < n; ++k)
    if (!isnan(v[k]))
      return 0;
  return 1;
}

/* Binary data from f->pos: records of 80 bytes filled in sequence, the
 * last padded with NaN (3.4.7). The size must be the records the rows
 * need exactly: a shorter or longer section means the rows would be
 * read out of step (a text-mode line-end conversion, for one, removes
 * bytes 0x0D). */
static int read_binary(crg_file *f)
{
  const int bytes = f->format == F_KRBI ? 4 : 8;
  const size_t start = f->pos, have = f->size - f->pos, per_rec = RECORD_BYTES / (size_t)bytes;
  size_t rows;
  int rc = declared_rows(f, &rows);
  if (rc)
    return rc;
  const int declared = rows > 0;
  const size_t nvalues = have / (size_t)bytes;
  if (!declared)
    rows = nvalues / f->nch;
  /* Checked before anything is allocated: the rows must be in the file,
   * in whole records, the padding less than a record (in double: a
   * declared row count may be any size). */
  const double records = ceil((double)rows * (double)f->nch / (double)per_rec);
  if (rows < 2 || rows > nvalues / f->nch || (double)have != records * RECORD_BYTES)
    return fb_err_set(f->st->err, FB_EPARSE,
                      "%s: byte %zu: the binary road data (%s) is %zu bytes; %zu rows of %zu "
                      "channels take %.0f records of %d bytes, %.0f bytes (3.4.7)",
                      f->path, start, FORMAT_NAMES[f->format], have, rows, f->nch, records,
                      RECORD_BYTES, records * RECORD_BYTES);
  rc = alloc_values(f, rows);
  if (rc)
    return rc;
  const unsigned char *p = (const unsigned char *)f->text + start;
  for (size_t k = 0; k < rows * f->nch; ++k)
    f->st->values[k] = big_endian(p + k * (size_t)bytes, bytes);
  for (size_t k = rows * f->nch; k < nvalues; ++k)
    if (!isnan(big_endian(p + k * (size_t)bytes, bytes)))
      return fb_err_set(f->st->err, FB_EPARSE,
                        "%s: byte %zu: the last record's padding is not NaN (3.4.7): the "
                        "data is out of step with its definition",
                        f->path, start + k * (size_t)bytes);
  /* Without REFERENCE_LINE_END_U, rows of NaN inside the last record are
   * its padding, not data. */
  const size_t last_record = ((size_t)records - 1) * per_rec;
  while (!declared && f->st->nrows > 2 && (f->st->nrows - 1) * f->nch >= last_record &&
         row_all_nan(f->st->values + (f->st->nrows - 1) * f->nch, f->nch))
    --f->st->nrows;
  f->pos = f->size;
  return FB_OK;
}

/* One formatted number (10 or 20 characters; a leading "*" is NaN). */
static int formatted_value(crg_file *f, const char *field, size_t width, size_t col,
                           double *out)
{
  char buf[32];
  memcpy(buf, field, width);
  buf[width] = '\0';
  const char *t = buf;
  while (*t == ' ')
    ++t;
  if (*t == '*') {
    *out = NAN;
    return FB_OK;
  }
  if (!parse_number(t, out))
    return fb_err_set(f->st->err, FB_EPARSE,
                      "%s:%zu: column %zu: not a number in %zu characters (3.4.7): '%s'",
                      f->path, f->line_no, col, width, buf);
  return FB_OK;
}

/* Formatted data from f->pos: each row starts a record and takes
 * ceil(nch / per record) of them (3.4.7). */
static int read_formatted(crg_file *f)
{
  const size_t width = f->format == F_LRFI ? 10 : 20, per_rec = RECORD_BYTES / width;
  const size_t recs_per_row = (f->nch + per_rec - 1) / per_rec;
  /* Count the records first (no allocation beyond the file's size). */
  size_t records = 0, last_nonblank = 0;
  for (size_t p = f->pos; p < f->size;) {
    const char *nl = memchr(f->text + p, '\n', f->size - p);
    const size_t end = nl ? (size_t)(nl - f->text) : f->size;
    ++records;
    for (size_t k = p; k < end; ++k)
      if (!isspace((unsigned char)f->text[k])) {
        last_nonblank = records;
        break;
      }
    p = end + 1;
  }
  records = last_nonblank; /* blank lines at the end are no records */
  const size_t first_line = f->line_no + 1;
  if (records % recs_per_row != 0 || records / recs_per_row < 2)
    return fb_err_set(f->st->err, FB_EPARSE,
                      "%s:%zu: %zu data records from line %zu; a row of %zu channels takes %zu "
                      "(%s, 3.4.7) and at least 2 rows are needed",
                      f->path, first_line + (records ? records - 1 : 0), records, first_line,
                      f->nch, recs_per_row, FORMAT_NAMES[f->format]);
  size_t rows = records / recs_per_row, want;
  int rc = declared_rows(f, &want);
  if (rc)
    return rc;
  if (want && want != rows)
    return fb_err_set(f->st->err, FB_EPARSE,
                      "%s:%zu: %zu data rows, REFERENCE_LINE_START_U, _END_U and _INCREMENT "
                      "give %zu (3.4.2)",
                      f->path, first_line, rows, want);
  rc = alloc_values(f, rows);
  if (rc)
    return rc;
  char line[512];
  size_t k = 0;
  for (size_t r = 0; r < records; ++r) {
    next_line(f, line, sizeof line);
    const size_t in_rec = (r % recs_per_row == recs_per_row - 1)
                              ? f->nch - (recs_per_row - 1) * per_rec
                              : per_rec;
    const size_t len = strlen(line);
    if (len < in_rec * width)
      return fb_err_set(f->st->err, FB_EPARSE,
                        "%s:%zu: %zu characters, %zu numbers of %zu characters expected (%s, "
                        "3.4.7)",
                        f->path, f->line_no, len, in_rec, width, FORMAT_NAMES[f->format]);
    for (size_t c = 0; c < in_rec; ++c, ++k) {
      rc = formatted_value(f, line + c * width, width, c * width + 1, &f->st->values[k]);
      if (rc)
        return rc;
    }
    for (size_t c = in_rec * width; c < len; ++c)
      if (!isspace((unsigned char)line[c]))
        return fb_err_set(f->st->err, FB_EPARSE,
                          "%s:%zu: column %zu: more than %zu numbers in the record (3.4.7)",
                          f->path, f->line_no, c + 1, in_rec);
  }
  f->pos = f->size;
  return FB_OK;
}

static int read_data(crg_file *f)
{
  crg_state *st = f->st;
  if (!f->has_kd || f->nch == 0)
    return fail_line(f, f->line_no,
                     "road data without a $KD_DEFINITION of its channels before it (3.4.3)",
                     NULL);
  if (st->values)
    return fail_line(f, f->line_no, "road data in a second file", st->data_path);
  if (!(st->data_path = fb_strdup(f->path)))
    return fb_err_set(st->err, FB_ENOMEM, "out of memory");
  st->chan = f->chan; /* the state owns the channels from here */
  st->nch = f->nch;
  f->chan = NULL;
  return f->format == F_KRBI || f->format == F_KDBI ? read_binary(f) : read_formatted(f);
}

/* ---- Sections. */

typedef enum crg_section {
  S_NONE,
  S_CT,
  S_ROAD,
  S_MPRO,
  S_KD,
  S_OPTS,
  S_MODS,
  S_FILE
} crg_section;

static int section_of(crg_file *f, const char *kw, crg_section *out)
{
  static const struct {
    const char *name;
    crg_section s;
  } names[] = {{"CT", S_CT},
               {"ROAD_CRG", S_ROAD},
               {"ROAD_CRG_MPRO", S_MPRO},
               {"KD_DEFINITION", S_KD},
               {"ROAD_CRG_OPTS", S_OPTS},
               {"ROAD_CRG_MODS", S_MODS},
               {"ROAD_CRG_FILE", S_FILE}};
  for (size_t k = 0; k < sizeof names / sizeof names[0]; ++k)
    if (strcasecmp(kw, names[k].name) == 0) {
      *out = names[k].s;
      return FB_OK;
    }
  return fail_line(f, f->line_no, "a section this reader does not know (3.2)", kw);
}

/* The start of a section: what replaces what was read before. */
static void open_section(crg_file *f, crg_section s)
{
  crg_state *st = f->st;
  if (s == S_MODS) { /* 3.4.5: the file's block replaces every earlier one */
    memset(&st->mods, 0, sizeof st->mods);
    st->mods_given = 1;
  } else if (s == S_OPTS) { /* 3.4.6 (fileref examples): the whole block */
    memset(&st->opts, 0, sizeof st->opts);
  } else if (s == S_KD) {
    f->has_kd = 1;
  }
}

static int read_section_line(crg_file *f, crg_section s, char *line, char *ref, size_t refcap)
{
  crg_state *st = f->st;
  char *text = strip(line);
  if (s == S_CT || s == S_MPRO || (!*text && s != S_KD))
    return FB_OK;
  switch (s) {
  case S_ROAD: return read_setting(f, text, ROAD_KEYS, NROAD, &st->road, 1, "$ROAD_CRG");
  case S_MODS: return read_setting(f, text, MOD_KEYS, NMODS, &st->mods, 1, "$ROAD_CRG_MODS");
  case S_OPTS: return read_setting(f, text, OPT_KEYS, NOPTS, &st->opts, 0, "$ROAD_CRG_OPTS");
  case S_KD: return read_kd_line(f, line);
  case S_FILE: return read_file_ref_line(f, line, ref, refcap);
  default: return FB_OK;
  }
}

/* In a $ROAD_CRG_FILE section, "$NAME/rest" is a path from the
 * environment (3.4.6), not a section: a keyword has no "/". */
static int is_env_path(crg_section s, const char *line)
{
  const char *slash = strchr(line, '/'), *bang = strchr(line, '!');
  return s == S_FILE && slash && (!bang || slash < bang);
}

static int read_lines(crg_file *f)
{
  char line[512], ref[1024] = "";
  crg_section s = S_NONE;
  int rc = FB_OK;
  size_t line_start = f->pos;
  while (!rc && next_line(f, line, sizeof line)) {
    if (line[0] == '*' && s != S_CT) {
      line_start = f->pos;
      continue; /* 3.3: a block comment */
    }
    if (line[0] == '$' && !is_env_path(s, line)) {
      if (strncmp(line, "$$$$", 4) == 0)
        return read_data(f);
      if (s == S_FILE && ref[0])
        return fail_line(f, f->line_no - 1, "a file reference not ending in .crg", ref);
      char *kw = strip(line + 1);
      s = S_NONE;
      if (*kw && (rc = section_of(f, kw, &s)) == FB_OK)
        open_section(f, s);
    } else if (s != S_NONE) {
      rc = read_section_line(f, s, line, ref, sizeof ref);
    } else if (*strip(line)) {
      if (f->has_kd && (f->format == F_LRFI || f->format == F_LDFI)) {
        /* Formatted data without a "$$$$" line starts here (3.4.7). */
        f->pos = line_start;
        --f->line_no;
        return read_data(f);
      }
      rc = fail_line(f, f->line_no, "text outside a section (3.2)", strip(line));
    }
    line_start = f->pos;
  }
  if (!rc && s == S_FILE && ref[0])
    rc = fail_line(f, f->line_no, "a file reference not ending in .crg", ref);
  return rc;
}

static int read_file_at(const char *path, crg_state *st, int depth, const char *from,
                        size_t from_line)
{
  if (depth > MAX_DEPTH)
    return fb_err_set(st->err, FB_EPARSE,
                      "%s:%zu: file references nested deeper than %d (a cycle?)", from,
                      from_line, MAX_DEPTH);
  crg_file f = {.path = path, .st = st, .depth = depth, .format = F_KRBI};
  /* The whole file, as every input (a regular file of at most
   * FB_INPUT_MAX_BYTES): its size bounds what is allocated after it. */
  int rc = fb_read_file(path, &f.text, &f.size, st->err);
  if (rc && from) {
    char msg[FB_ERR_MSG_MAX];
    snprintf(msg, sizeof msg, "%s", st->err->msg);
    fb_err_set(st->err, rc, "%s:%zu: referenced file: %s", from, from_line, msg);
  }
  if (!rc && f.size > 0 && f.text[0] != '$')
    rc = fb_err_set(st->err, FB_EPARSE,
                    "%s:1: not an OpenCRG file: it must start with a section ($CT, 3.2)", path);
  if (!rc)
    rc = read_lines(&f);
  free(f.text);
  free(f.chan);
  return rc;
}

/* ---- From what was read to the surface as evaluated. */

static double key_or(const crg_keys *k, int key, double dflt)
{
  return k->set[key] ? k->value[key] : dflt;
}

/* The v of each long section (3.4.3): given ("long section at v = X",
 * ascending), or numbered ("long section N", in order) on the lateral
 * grid of LONG_SECTION_V_RIGHT / _LEFT / _INCREMENT, centred on the
 * reference line when neither border is given (3.4.2: "calculated from
 * road data"). Scaled by SCALE_WIDTH (3.4.5). */
static int long_sections(const crg_state *st, fb_crg *c, double scale_width)
{
  const crg_keys *r = &st->road;
  const char *path = st->data_path;
  size_t nv = 0, nat = 0;
  for (size_t k = 0; k < st->nch; ++k)
    if (st->chan[k].kind >= CH_LONG_AT) {
      nat += st->chan[k].kind == CH_LONG_AT;
      ++nv;
    }
  if (nv < 2)
    return fb_err_set(st->err, FB_EPARSE,
                      "%s: %zu long sections; at least 2 are needed (3.4.3)", path, nv);
  if (nat && nat != nv)
    return fb_err_set(st->err, FB_EPARSE,
                      "%s: long sections given both by v and by number (3.4.3)", path);
  if (!(c->v = malloc(nv * sizeof *c->v)))
    return fb_err_set(st->err, FB_ENOMEM, "out of memory");
  c->nv = nv;
  double right = NAN, inc = NAN;
  if (!nat) {
    const double n1 = (double)(nv - 1);
    inc = key_or(r, R_V_INCREMENT, NAN);
    if (isnan(inc) && r->set[R_V_RIGHT] && r->set[R_V_LEFT])
      inc = (r->value[R_V_LEFT] - r->value[R_V_RIGHT]) / n1;
    if (!(inc > 0.0))
      return fb_err_set(st->err, FB_EPARSE,
                        "%s: numbered long sections need LONG_SECTION_V_INCREMENT > 0 or both "
                        "borders (3.4.3)",
                        path);
    right = r->set[R_V_RIGHT]  ? r->value[R_V_RIGHT]
            : r->set[R_V_LEFT] ? r->value[R_V_LEFT] - n1 * inc
                               : -0.5 * n1 * inc;
  }
  size_t j = 0;
  for (size_t k = 0; k < st->nch; ++k) {
    const crg_chan *ch = &st->chan[k];
    if (ch->kind < CH_LONG_AT)
      continue;
    if (ch->kind == CH_LONG_N && ch->v != (double)(j + 1))
      return fb_err_set(st->err, FB_EPARSE, "%s:%zu: long section %g where %zu is due (3.4.3)",
                        path, ch->line, ch->v, j + 1);
    c->v[j] = ch->kind == CH_LONG_AT ? ch->v : right + (double)j * inc;
    if (j > 0 && !(c->v[j] > c->v[j - 1]))
      return fb_err_set(st->err, FB_EPARSE,
                        "%s:%zu: long section at v = %g after v = %g: they must ascend (3.4.3)",
                        path, ch->line, c->v[j], c->v[j - 1]);
    ++j;
  }
  /* The borders, when given, must be the outer sections. */
  const double width = c->v[nv - 1] - c->v[0], tol = 1e-6 * fmax(1.0, width);
  if ((r->set[R_V_RIGHT] && fabs(r->value[R_V_RIGHT] - c->v[0]) > tol) ||
      (r->set[R_V_LEFT] && fabs(r->value[R_V_LEFT] - c->v[nv - 1]) > tol))
    return fb_err_set(st->err, FB_EPARSE,
                      "%s: LONG_SECTION_V_RIGHT / _LEFT (%g, %g) are not the outer long "
                      "sections (%g, %g) (3.4.2)",
                      path, key_or(r, R_V_RIGHT, c->v[0]), key_or(r, R_V_LEFT, c->v[nv - 1]),
                      c->v[0], c->v[nv - 1]);
  for (size_t q = 0; q < nv; ++q)
    c->v[q] *= scale_width;
  return FB_OK;
}

/* GRID_NAN_MODE (3.4.5): NaN at the borders of a cross section (before
 * its first or after its last value) kept (0), set to 0 (1) or to the
 * nearest value of the section (2), plus GRID_NAN_OFFSET when replaced.
 * NaN between values is the data's own and stays. */
static void fill_border_nan(fb_crg *c, int mode, double offset)
{
  if (mode == 0)
    return;
  for (size_t i = 0; i < c->nu; ++i) {
    double *row = c->z + i * c->nv;
    size_t a = 0, b = c->nv;
    while (a < c->nv && isnan(row[a]))
      ++a;
    while (b > a && isnan(row[b - 1]))
      --b;
    if (a == c->nv)
      continue; /* a section without a value: nothing to keep */
    for (size_t j = 0; j < a; ++j)
      row[j] = (mode == 1 ? 0.0 : row[a]) + offset;
    for (size_t j = b; j < c->nv; ++j)
      row[j] = (mode == 1 ? 0.0 : row[b - 1]) + offset;
  }
}

/* A reference-line channel at section i (NaN allowed in the first:
 * a channel's value at section i > 0 is that of the step from i - 1 to
 * i, the first one's is not used). */
static int channel_values(const crg_state *st, chan_kind kind, double start, double end,
                          int end_given, double *out, size_t n, int *present)
{
  *present = 0;
  for (size_t k = 0; k < st->nch; ++k)
    if (st->chan[k].kind == kind) {
      *present = 1;
      for (size_t i = 0; i < n; ++i) {
        out[i] = st->values[i * st->nch + k];
        if (isnan(out[i]) && i > 0)
          return fb_err_set(st->err, FB_EPARSE,
                            "%s:%zu: its channel has no value (NaN) at cross section %zu",
                            st->data_path, st->chan[k].line, i + 1);
      }
      if (isnan(out[0]))
        out[0] = kind == CH_PHI ? start : out[1];
      return FB_OK;
    }
  /* No channel: the start value, or linear from start to end (3.4.2). */
  for (size_t i = 0; i < n; ++i)
    out[i] = end_given ? start + (end - start) * (double)i / (double)(n - 1) : start;
  return FB_OK;
}

static int mod_scale(const crg_state *st, int key, double *scale)
{
  *scale = 1.0;
  if (!st->mods.set[key])
    return FB_OK;
  const double s = st->mods.value[key];
  const int positive = key == M_SCALE_LENGTH || key == M_SCALE_WIDTH;
  if (positive && !(s > 0.0))
    return fb_err_set(st->err, FB_EPARSE, "%s = %g: only factors > 0 are valid (3.4.5)",
                      MOD_KEYS[key], s);
  if (key == M_SCALE_CURVATURE && !(s >= 0.0))
    return fb_err_set(st->err, FB_EPARSE, "SCALE_CURVATURE = %g: >= 0 (3.4.5)", s);
  /* 3.4.5: a factor of 0 for elevation data is ignored; for the curvature
   * it makes the line straight. */
  if (s != 0.0 || key == M_SCALE_CURVATURE)
    *scale = s;
  return FB_OK;
}

static int check_opts(const crg_state *st, crg_opts *o)
{
  const crg_keys *k = &st->opts;
  o->border_mode_u = (int)key_or(k, O_BORDER_MODE_U, FB_CRG_BORDER_KEEP);
  o->border_mode_v = (int)key_or(k, O_BORDER_MODE_V, FB_CRG_BORDER_KEEP);
  o->border_offset_u = key_or(k, O_BORDER_OFFSET_U, 0.0);
  o->border_offset_v = key_or(k, O_BORDER_OFFSET_V, 0.0);
  o->smooth_ubeg = key_or(k, O_SMOOTH_UBEG, 0.0);
  o->smooth_uend = key_or(k, O_SMOOTH_UEND, 0.0);
  for (int q = O_BORDER_MODE_U; q <= O_BORDER_MODE_V; ++q) {
    const double m = key_or(k, q, 2.0);
    if (m != floor(m) || m < 0.0 || m > 4.0)
      return fb_err_set(st->err, FB_EPARSE, "%s = %g: one of 0, 1, 2, 3, 4 (3.4.4)",
                        OPT_KEYS[q], m);
  }
  const double cont = key_or(k, O_CONTINUATION, 0.0);
  if (cont != 0.0 && cont != 1.0)
    return fb_err_set(st->err, FB_EPARSE, "REFLINE_CONTINUATION = %g: 0 or 1 (3.4.4)", cont);
  o->refline_continuation = (int)cont;
  if (o->smooth_ubeg < 0.0 || o->smooth_uend < 0.0)
    return fb_err_set(st->err, FB_EPARSE, "BORDER_SMOOTH_UBEG / _UEND: >= 0 (3.4.4)");
  return FB_OK;
}

/* The reference point's (u, v) (3.4.5): REFPOINT_U or REFPOINT_U_FRACTION
 * of the u range, plus REFPOINT_U_OFFSET; v likewise; within the grid. */
static void refpoint_uv(const crg_state *st, const fb_crg *c, double *u_out, double *v_out)
{
  const crg_keys *m = &st->mods;
  const double u_last = c->u0 + (double)(c->nu - 1) * c->du;
  double u = m->set[M_REFPOINT_U]
                 ? m->value[M_REFPOINT_U]
                 : c->u0 + key_or(m, M_REFPOINT_U_FRACTION, 0.0) * (u_last - c->u0);
  double v = m->set[M_REFPOINT_V] ? m->value[M_REFPOINT_V]
                                  : c->v[0] + key_or(m, M_REFPOINT_V_FRACTION, 0.0) *
                                                  (c->v[c->nv - 1] - c->v[0]);
  u += key_or(m, M_REFPOINT_U_OFFSET, 0.0);
  v += key_or(m, M_REFPOINT_V_OFFSET, 0.0);
  *u_out = fmin(u_last, fmax(c->u0, u));
  *v_out = fmin(c->v[c->nv - 1], fmax(c->v[0], v));
}

/* The modifiers' z shift (3.4.5): by reference point when any REFPOINT_*
 * is given (the reference line's height at (u, v) of the point moves to
 * REFPOINT_Z), else REFLINE_OFFSET_Z; REFERENCE_LINE_OFFSET_Z (3.4.2)
 * adds to either. */
static double z_shift(const crg_state *st, const fb_crg *c)
{
  const crg_keys *m = &st->mods;
  double shift = key_or(&st->road, R_OFFSET_Z, 0.0);
  int refpoint = 0;
  for (int k = M_REFPOINT_U; k <= M_REFPOINT_PHI; ++k)
    refpoint |= m->set[k];
  if (!refpoint)
    return shift + key_or(m, M_OFFSET_Z, 0.0);
  double u, v;
  refpoint_uv(st, c, &u, &v);
  double f = (u - c->u0) / c->du;
  size_t i = f <= 0.0 ? 0 : (size_t)f;
  if (i > c->nu - 2)
    i = c->nu - 2;
  f -= (double)i;
  const double zr = c->zref[i] + f * (c->zref[i + 1] - c->zref[i]);
  const double b = c->bank[i] + f * (c->bank[i + 1] - c->bank[i]);
  return shift + key_or(m, M_REFPOINT_Z, 0.0) - (zr + b * v);
}

/* The x/y placement the keys give (crg_xy.c). */
static crg_place place_of(const crg_state *st, const fb_crg *c, double scale_curvature)
{
  const crg_keys *r = &st->road, *m = &st->mods;
  crg_place p = {
      .start_x = key_or(r, R_START_X, 0.0),
      .start_y = key_or(r, R_START_Y, 0.0),
      .start_phi = key_or(r, R_START_PHI, 0.0),
      .end_phi = key_or(r, R_END_PHI, 0.0),
      .end_phi_given = r->set[R_END_PHI],
      .end_xy_given = r->set[R_END_X] && r->set[R_END_Y],
      .end_x = key_or(r, R_END_X, 0.0),
      .end_y = key_or(r, R_END_Y, 0.0),
      .offset_x = key_or(r, R_OFFSET_X, 0.0),
      .offset_y = key_or(r, R_OFFSET_Y, 0.0),
      .offset_phi = key_or(r, R_OFFSET_PHI, 0.0),
      .scale_curvature = scale_curvature,
      .ref_x = key_or(m, M_REFPOINT_X, 0.0),
      .ref_y = key_or(m, M_REFPOINT_Y, 0.0),
      .ref_phi = key_or(m, M_REFPOINT_PHI, 0.0),
      .rotcenter_given = {m->set[M_ROTCENTER_X], m->set[M_ROTCENTER_Y]},
      .rot_x = key_or(m, M_ROTCENTER_X, 0.0),
      .rot_y = key_or(m, M_ROTCENTER_Y, 0.0),
      .rot_phi = key_or(m, M_OFFSET_PHI, 0.0),
      .move_x = key_or(m, M_OFFSET_X, 0.0),
      .move_y = key_or(m, M_OFFSET_Y, 0.0),
  };
  for (int k = M_REFPOINT_U; k <= M_REFPOINT_PHI; ++k)
    p.by_refpoint |= m->set[k];
  refpoint_uv(st, c, &p.ref_u, &p.ref_v);
  return p;
}

static int build(crg_state *st, fb_crg *c)
{
  const crg_keys *r = &st->road;
  if (!st->values)
    return fb_err_set(st->err, FB_EPARSE,
                      "%s: no road data in it or in the files it references (3.4.7)",
                      st->data_path ? st->data_path : "");
  if (!(r->set[R_INCREMENT] && r->value[R_INCREMENT] > 0.0))
    return fb_err_set(st->err, FB_EPARSE,
                      "%s: REFERENCE_LINE_INCREMENT > 0 is required (3.4.2)", st->data_path);
  if (!st->mods_given) { /* the application's default modifiers: keep the last value */
    st->mods.set[M_GRID_NAN_MODE] = 1;
    st->mods.value[M_GRID_NAN_MODE] = 2;
  }
  double s_len, s_width, s_z, s_slope, s_bank, s_curv;
  int rc = mod_scale(st, M_SCALE_LENGTH, &s_len);
  rc = rc ? rc : mod_scale(st, M_SCALE_WIDTH, &s_width);
  rc = rc ? rc : mod_scale(st, M_SCALE_Z_GRID, &s_z);
  rc = rc ? rc : mod_scale(st, M_SCALE_SLOPE, &s_slope);
  rc = rc ? rc : mod_scale(st, M_SCALE_BANKING, &s_bank);
  rc = rc ? rc : mod_scale(st, M_SCALE_CURVATURE, &s_curv);
  rc = rc ? rc : check_opts(st, &c->opts);
  if (rc)
    return rc;
  const double nan_mode = key_or(&st->mods, M_GRID_NAN_MODE, 0.0);
  if (nan_mode != 0.0 && nan_mode != 1.0 && nan_mode != 2.0)
    return fb_err_set(st->err, FB_EPARSE, "GRID_NAN_MODE = %g: one of 0, 1, 2 (3.4.5)",
                      nan_mode);
  c->nu = st->nrows;
  c->u0 = key_or(r, R_START_U, 0.0) * s_len;
  c->du = r->value[R_INCREMENT] * s_len;
  rc = long_sections(st, c, s_width);
  if (rc)
    return rc;
  const size_t nu = c->nu, nv = c->nv;
  c->z = calloc(nu * nv, sizeof *c->z);
  c->zref = malloc(nu * sizeof *c->zref);
  c->bank = malloc(nu * sizeof *c->bank);
  double *slope = malloc(nu * sizeof *slope), *phi = malloc(nu * sizeof *phi);
  if (!c->z || !c->zref || !c->bank || !slope || !phi) {
    free(slope);
    free(phi);
    return fb_err_set(st->err, FB_ENOMEM, "out of memory for an OpenCRG surface");
  }
  for (size_t i = 0, j = 0; i < nu; ++i, j = 0)
    for (size_t k = 0; k < st->nch; ++k)
      if (st->chan[k].kind >= CH_LONG_AT)
        c->z[i * nv + j++] = st->values[i * st->nch + k] * s_z;
  fill_border_nan(c, (int)nan_mode, key_or(&st->mods, M_GRID_NAN_OFFSET, 0.0));
  int has_phi = 0;
  rc = channel_values(st, CH_SLOPE, key_or(r, R_START_S, 0.0), key_or(r, R_END_S, 0.0),
                      r->set[R_END_S], slope, nu, &c->has_slope);
  rc = rc ? rc
          : channel_values(st, CH_BANK, key_or(r, R_START_B, 0.0), key_or(r, R_END_B, 0.0),
                           r->set[R_END_B], c->bank, nu, &c->has_banking);
  rc = rc ? rc
          : channel_values(st, CH_PHI, key_or(r, R_START_PHI, 0.0), 0.0, 0, phi, nu, &has_phi);
  if (!rc) {
    /* The reference line's height: REFERENCE_LINE_START_Z at the start,
     * then each step's slope over the increment. */
    c->zref[0] = key_or(r, R_START_Z, 0.0);
    for (size_t i = 1; i < nu; ++i)
      c->zref[i] = c->zref[i - 1] + s_slope * slope[i] * c->du;
    for (size_t i = 0; i < nu; ++i)
      c->bank[i] *= s_bank;
    const double shift = z_shift(st, c);
    for (size_t i = 0; i < nu; ++i)
      c->zref[i] += shift;
    const crg_place place = place_of(st, c, s_curv);
    rc = crg_refline_build(c, has_phi ? phi : NULL, &place, st->err);
  }
  free(slope);
  if (has_phi && !rc)
    c->phi = phi;
  else
    free(phi);
  return rc;
}

int fb_crg_read(const char *path, fb_crg **out, fb_err *err)
{
  *out = NULL;
  fb_err local;
  if (!err)
    err = &local;
  crg_state st = {.err = err};
  fb_crg *c = calloc(1, sizeof *c);
  int rc = c ? read_file_at(path, &st, 0, NULL, 0)
             : fb_err_set(err, FB_ENOMEM, "out of memory for an OpenCRG surface");
  if (!rc && !st.data_path)
    rc = fb_err_set(err, FB_EPARSE,
                    "%s: no road data in it or in the files it references (3.4.7)", path);
  if (!rc)
    rc = build(&st, c);
  free(st.data_path);
  free(st.chan);
  free(st.values);
  if (rc) {
    fb_crg_free(&c);
    return rc;
  }
  *out = c;
  return FB_OK;
}
