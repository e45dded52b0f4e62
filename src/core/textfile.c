/* SPDX-License-Identifier: BSD-3-Clause */
/* Text data files read line by line (see core/textfile.h). */
#include "core/textfile.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "flexbond/error.h"

#include "core/util.h"

/* The size of a file in the message: MB, or bytes for a small one. */
static void describe_size(double bytes, char *buf, size_t size)
{
  if (bytes >= 1e6)
    snprintf(buf, size, "%.1f MB", bytes / 1e6);
  else
    snprintf(buf, size, "%.0f bytes", bytes);
}

static int too_large(const char *path, double bytes, fb_err *err)
{
  char got[32];
  describe_size(bytes, got, sizeof got);
  return fb_err_set(err, FB_EIO,
                    "%s: cannot read: %s, more than the %zu MiB an input file may hold "
                    "(docs/errors.md, \"Limits\")",
                    path, got, FB_INPUT_MAX_BYTES >> 20);
}

int fb_input_check_fd(int fd, const char *path, fb_err *err)
{
  struct stat st;
  if (fstat(fd, &st) != 0)
    return fb_err_set(err, FB_EIO, "%s: cannot read: %s", path, strerror(errno));
  if (!S_ISREG(st.st_mode))
    return fb_err_set(err, FB_EIO, "%s: cannot read: %s", path,
                      S_ISDIR(st.st_mode) ? "Is a directory"
                                          : "not a regular file (a device, pipe or socket)");
  if ((uintmax_t)st.st_size > FB_INPUT_MAX_BYTES)
    return too_large(path, (double)st.st_size, err);
  return FB_OK;
}

FILE *fb_open_input(const char *path, const char *mode, fb_err *err)
{
  /* O_NONBLOCK: opening a FIFO would otherwise wait for a writer before
   * it could be refused; it changes nothing for a regular file. */
  const int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    fb_err_set(err, FB_EIO, "%s: cannot open: %s", path, strerror(errno));
    return NULL;
  }
  if (fb_input_check_fd(fd, path, err) != FB_OK) {
    close(fd);
    return NULL;
  }
  FILE *fp = fdopen(fd, mode);
  if (!fp) {
    fb_err_set(err, FB_EIO, "%s: cannot open: %s", path, strerror(errno));
    close(fd);
  }
  return fp;
}

/* Appends what is left of fp to buf (*n bytes of *cap used), growing it
 * up to FB_INPUT_MAX_BYTES + 2 bytes, so that a file that grew past the
 * bound is seen to have. */
static int read_rest(FILE *fp, const char *path, char **buf, size_t *cap, size_t *n,
                     fb_err *err)
{
  for (;;) {
    if (*n + 1 >= *cap) {
      if (*cap > FB_INPUT_MAX_BYTES)
        return too_large(path, (double)*n, err);
      const size_t grown_cap =
          *cap * 2 < FB_INPUT_MAX_BYTES + 2 ? *cap * 2 : FB_INPUT_MAX_BYTES + 2;
      char *grown = realloc(*buf, grown_cap);
      if (!grown)
        return fb_err_set(err, FB_ENOMEM, "out of memory reading %s", path);
      *buf = grown;
      *cap = grown_cap;
    }
    const size_t got = fread(*buf + *n, 1, *cap - 1 - *n, fp);
    *n += got;
    if (got == 0)
      return ferror(fp) ? fb_err_set(err, FB_EIO, "%s: cannot read: %s", path,
                                     strerror(errno ? errno : EIO))
                        : FB_OK;
  }
}

int fb_read_file(const char *path, char **text, size_t *len, fb_err *err)
{
  FILE *fp = fb_open_input(path, "rb", err);
  if (!fp)
    return FB_EIO;
  /* Sized from the file (fb_open_input bounded it), plus the NUL and one
   * byte to see the end without growing. */
  struct stat st;
  size_t cap = fstat(fileno(fp), &st) == 0 ? (size_t)st.st_size + 2 : 4096;
  size_t n = 0;
  char *buf = malloc(cap);
  int rc = buf ? read_rest(fp, path, &buf, &cap, &n, err)
               : fb_err_set(err, FB_ENOMEM, "out of memory reading %s", path);
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

int fb_text_open(fb_text_reader *r, const char *path, const char *format, fb_err *err)
{
  *r = (fb_text_reader){.path = path, .format = format, .err = err};
  r->fp = fb_open_input(path, "r", err);
  return r->fp ? FB_OK : FB_EIO;
}

void fb_text_close(fb_text_reader *r)
{
  if (r->fp)
    fclose(r->fp);
  free(r->line);
  r->fp = NULL;
  r->line = NULL;
  r->cap = 0;
}

size_t fb_utf8_length(const unsigned char *s, size_t n)
{
  size_t len = 0;
  if (s[0] < 0x80)
    len = 1;
  else if (s[0] >= 0xC2 && s[0] < 0xE0)
    len = 2;
  else if (s[0] >= 0xE0 && s[0] < 0xF0)
    len = 3;
  else if (s[0] >= 0xF0 && s[0] < 0xF5)
    len = 4;
  if (len == 0 || len > n)
    return 0;
  /* The lead bytes E0, ED, F0 and F4 allow only a narrower second byte:
   * the others would spell an overlong form, a surrogate or a code point
   * above U+10FFFF. */
  const unsigned char lo = s[0] == 0xE0 ? 0xA0 : s[0] == 0xF0 ? 0x90 : 0x80;
  const unsigned char hi = s[0] == 0xED ? 0x9F : s[0] == 0xF4 ? 0x8F : 0xBF;
  if (len > 1 && (s[1] < lo || s[1] > hi))
    return 0;
  for (size_t k = 2; k < len; ++k)
    if ((s[k] & 0xC0) != 0x80)
      return 0;
  return len;
}

int fb_text_copy(const char *text, size_t len, const char *name, char **copy, fb_err *err)
{
  *copy = len < SIZE_MAX ? malloc(len + 1) : NULL;
  if (!*copy)
    return fb_err_set(err, FB_ENOMEM, "out of memory reading %s", name);
  memcpy(*copy, text, len);
  (*copy)[len] = '\0';
  return FB_OK;
}

size_t fb_text_split_line(char *text, size_t len, size_t *pos, char **line)
{
  char *start = text + *pos;
  char *nl = memchr(start, '\n', len - *pos);
  size_t n = nl ? (size_t)(nl - start) : len - *pos;
  *pos += nl ? n + 1 : n;
  start[n] = '\0';
  if (n > 0 && start[n - 1] == '\r')
    start[--n] = '\0';
  *line = start;
  for (size_t i = 0; i < n; ++i) {
    const unsigned char c = (unsigned char)start[i];
    if ((c < 0x20 && c != '\t') || c == 0x7f)
      return i + 1;
  }
  return 0;
}

size_t fb_text_find_binary(const char *text, size_t len, int line_ends, size_t *line,
                           size_t *col)
{
  const unsigned char *s = (const unsigned char *)text;
  *line = 1;
  *col = 1;
  for (size_t i = 0; i < len; ++*col) {
    const unsigned char b = s[i];
    const size_t n = fb_utf8_length(s + i, len - i);
    const int line_end = line_ends && (b == '\n' || b == '\r');
    if (n == 0 || (b < 0x20 && b != '\t' && !line_end) || b == 0x7F)
      return i;
    if (line_end && b == '\n') {
      ++*line;
      *col = 0;
    }
    i += n;
  }
  return len;
}

/* The end of line is already cut, so a carriage return left inside a line
 * is refused too (it would otherwise end the line for some readers and
 * not others). */
static int check_text(const fb_text_reader *r, const char *text, size_t len)
{
  size_t line, col;
  const size_t at = fb_text_find_binary(text, len, 0, &line, &col);
  if (at < len)
    return fb_err_set(r->err, FB_EPARSE,
                      "%s:%zu: binary data (byte 0x%02x in column %zu): not a %s text file "
                      "(expected UTF-8 text)",
                      r->path, r->line_no, (unsigned char)text[at], col, r->format);
  return FB_OK;
}

int fb_text_next_line(fb_text_reader *r, char **line)
{
  *line = NULL;
  errno = 0;
  const ssize_t got = getline(&r->line, &r->cap, r->fp);
  if (got < 0) {
    if (ferror(r->fp))
      return fb_err_set(r->err, FB_EIO, "%s:%zu: read error: %s", r->path, r->line_no + 1,
                        strerror(errno ? errno : EIO));
    return errno == ENOMEM ? fb_err_set(r->err, FB_ENOMEM, "out of memory reading %s", r->path)
                           : FB_OK;
  }
  ++r->line_no;
  size_t len = (size_t)got;
  /* fb_open_input bounded the file's size; this bounds one that grows. */
  r->bytes += len;
  if (r->bytes > FB_INPUT_MAX_BYTES)
    return too_large(r->path, (double)r->bytes, r->err);
  if (len > 0 && r->line[len - 1] == '\n')
    --len;
  if (len > 0 && r->line[len - 1] == '\r')
    --len;
  r->line[len] = '\0';
  char *start = r->line;
  /* Excel and Notepad write a byte-order mark, which no editor shows; left
   * in, it would become part of the first column's name. */
  if (r->line_no == 1 && len >= 3 && memcmp(start, "\xEF\xBB\xBF", 3) == 0) {
    start += 3;
    len -= 3;
  }
  const int rc = check_text(r, start, len);
  if (rc)
    return rc;
  *line = start;
  return FB_OK;
}

int fb_text_next_data_line(fb_text_reader *r, char comment, char **line)
{
  for (;;) {
    char *s = NULL;
    const int rc = fb_text_next_line(r, &s);
    *line = NULL;
    if (rc || !s)
      return rc;
    s += strspn(s, " \t");
    if (*s == '\0' || *s == comment)
      continue;
    char *end = s + strlen(s);
    while (end[-1] == ' ' || end[-1] == '\t')
      --end;
    *end = '\0';
    *line = s;
    return FB_OK;
  }
}

static int is_digit(char c)
{
  return c >= '0' && c <= '9';
}

/* 1 if the whole of s is [+-] digits [. digits] [(e|E) [+-] digits] with
 * at least one digit before the exponent. */
static int is_decimal(const char *s)
{
  size_t digits = 0;
  if (*s == '+' || *s == '-')
    ++s;
  for (; is_digit(*s); ++s)
    ++digits;
  if (*s == '.')
    for (++s; is_digit(*s); ++s)
      ++digits;
  if (digits == 0)
    return 0;
  if (*s == 'e' || *s == 'E') {
    ++s;
    if (*s == '+' || *s == '-')
      ++s;
    if (!is_digit(*s))
      return 0;
    while (is_digit(*s))
      ++s;
  }
  return *s == '\0';
}

/* strtod alone would also take "0x10" (16), "infinity" and "nan(...)";
 * it is asked only for the value, and to tell those apart in the message. */
/* Every integer up to 2^53 is a double exactly, not every one above
 * (IEEE 754 binary64 has a 53-bit significand): 2^53 + 1 would read as
 * 2^53. */
static const char exact_int_max[] = "9007199254740992";

/* 1 if text is an integer ([+-]digits, no point or exponent) whose
 * magnitude is above 2^53. */
static int integer_inexact(const char *text)
{
  const char *d = text + (text[0] == '+' || text[0] == '-');
  const size_t len = strlen(d);
  if (len == 0 || strspn(d, "0123456789") != len)
    return 0;
  while (d[0] == '0' && d[1])
    ++d;
  const size_t n = strlen(d), max = sizeof exact_int_max - 1;
  return n > max || (n == max && strcmp(d, exact_int_max) > 0);
}

/* 1 if a digit before the exponent of text is not 0. */
static int has_nonzero_digit(const char *text)
{
  for (; *text && *text != 'e' && *text != 'E'; ++text)
    if (*text >= '1' && *text <= '9')
      return 1;
  return 0;
}

/* fb_decimal_check_exact, the text quoted in the message or (quote 0, a
 * data file's field) only in fb_err.excerpt. */
static int check_exact(const char *text, double v, int quote, fb_err *err)
{
  int rc = FB_OK;
  if (integer_inexact(text))
    rc = fb_err_set(err, FB_EINVAL,
                    "the integer %s%sis beyond 2^53 = %s, above which a double cannot hold "
                    "every integer: it would be read as a different number; write it with "
                    "an exponent (as 1.5e16) if a rounded value is meant",
                    quote ? text : "", quote ? " " : "", exact_int_max);
  else if (v == 0 && has_nonzero_digit(text))
    rc = fb_err_set(err, FB_EINVAL,
                    "%s is too small for a double (below about 4.9e-324): it would be read "
                    "as 0; write 0 if 0 is meant",
                    quote ? text : "the number");
  if (rc && !quote)
    fb_err_set_excerpt(err, text, strlen(text));
  return rc;
}

int fb_decimal_check_exact(const char *text, double v, fb_err *err)
{
  return check_exact(text, v, 1, err);
}

size_t fb_text_find_control(const char *text, size_t len, int layout, unsigned *code)
{
  const unsigned char *t = (const unsigned char *)text;
  for (size_t i = 0; i < len; ++i) {
    const int blank = t[i] == '\t' || t[i] == '\n' || t[i] == '\r';
    if ((t[i] < 0x20 && !(layout && blank)) || t[i] == 0x7f) {
      *code = t[i];
      return i;
    }
    if (t[i] == 0xc2 && i + 1 < len && t[i + 1] >= 0x80 && t[i + 1] <= 0x9f) {
      *code = t[i + 1];
      return i;
    }
  }
  return len;
}

static int parse_decimal(const char *text, double *out, int quote, fb_err *err)
{
  char *end = NULL;
  const double v = strtod(text, &end);
  const char *why = NULL;
  if (end == text || *end != '\0')
    why = "not a number";
  else if (!isfinite(v))
    why = "not a finite number";
  else if (!is_decimal(text))
    why = "not a decimal number";
  if (why && quote)
    return fb_err_set(err, FB_EPARSE, "'%s' is %s", text, why);
  if (why) {
    fb_err_set(err, FB_EPARSE, "%s", why);
    fb_err_set_excerpt(err, text, strlen(text));
    return FB_EPARSE;
  }
  const int rc = check_exact(text, v, quote, err);
  if (rc == FB_OK)
    *out = v;
  return rc;
}

int fb_parse_decimal(const char *text, double *out, fb_err *err)
{
  return parse_decimal(text, out, 1, err);
}

int fb_parse_decimal_field(const char *text, double *out, fb_err *err)
{
  return parse_decimal(text, out, 0, err);
}

void fb_format_shortest(double v, int min_digits, char *buf, size_t size)
{
  for (int digits = min_digits; digits <= 17; ++digits) {
    snprintf(buf, size, "%.*g", digits, v);
    if (strtod(buf, NULL) == v)
      return;
  }
}

size_t fb_text_append(char *buf, size_t size, size_t len, const char *fmt, ...)
{
  if (len + 1 >= size)
    return size ? size - 1 : 0;
  va_list ap;
  va_start(ap, fmt);
  const int w = vsnprintf(buf + len, size - len, fmt, ap);
  va_end(ap);
  return w >= 0 && len + (size_t)w < size ? len + (size_t)w : size - 1;
}
