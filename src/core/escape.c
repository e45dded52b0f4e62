/* SPDX-License-Identifier: BSD-3-Clause */
/* The escaping writers of flexbond/escape.h: one walk over the UTF-8 text
 * (write_utf8) and, per language, what each ASCII character becomes. */
#include "flexbond/escape.h"

#include <ctype.h>
#include <math.h>
#include <string.h>

#include "core/textfile.h"

/* U+FFFD REPLACEMENT CHARACTER in UTF-8, for a malformed byte or a
 * character the language cannot hold. */
static const char replacement[] = "\xEF\xBF\xBD";

/* Length of the well-formed UTF-8 sequence of a non-ASCII character at
 * s[0..n) (RFC 3629, section 4: the table of well-formed byte sequences),
 * its code point in *cp; 0 if the bytes there are not one. */
static size_t utf8_sequence(const unsigned char *s, size_t n, unsigned long *cp)
{
  size_t len;
  unsigned char lo = 0x80, hi = 0xBF; /* range of the second byte */
  if (s[0] >= 0xC2 && s[0] <= 0xDF)
    len = 2;
  else if (s[0] >= 0xE0 && s[0] <= 0xEF)
    len = 3;
  else if (s[0] >= 0xF0 && s[0] <= 0xF4)
    len = 4;
  else
    return 0;
  if (s[0] == 0xE0)
    lo = 0xA0; /* no overlong form */
  else if (s[0] == 0xED)
    hi = 0x9F; /* no surrogate */
  else if (s[0] == 0xF0)
    lo = 0x90; /* no overlong form */
  else if (s[0] == 0xF4)
    hi = 0x8F; /* no code point above U+10FFFF */
  if (n < len || s[1] < lo || s[1] > hi)
    return 0;
  *cp = s[0] & (0x7F >> len);
  for (size_t k = 1; k < len; ++k) {
    if ((s[k] & 0xC0) != 0x80)
      return 0;
    *cp = (*cp << 6) | (s[k] & 0x3F);
  }
  return len;
}

/* Writes what ASCII character c becomes in the language; next is the
 * byte after it (0 at the end). */
typedef void put_ascii_fn(FILE *fp, unsigned char c, unsigned char next);

/* Writes s[0..n) (up to its NUL): ASCII through put, well-formed UTF-8 as
 * it is, a malformed byte (and, with xml_chars, U+FFFE and U+FFFF, which
 * XML 1.0 section 2.2 leaves out of Char) as U+FFFD. */
static void write_utf8(FILE *fp, const char *s, size_t n, put_ascii_fn *put, int xml_chars)
{
  const unsigned char *u = (const unsigned char *)s;
  for (size_t i = 0; s && i < n && u[i];) {
    if (u[i] < 0x80) {
      put(fp, u[i], i + 1 < n ? u[i + 1] : 0);
      ++i;
      continue;
    }
    unsigned long cp = 0;
    size_t len = utf8_sequence(u + i, n - i, &cp);
    if (len == 0 || (xml_chars && (cp == 0xFFFE || cp == 0xFFFF)))
      fputs(replacement, fp);
    else
      fwrite(u + i, 1, len, fp);
    i += len ? len : 1;
  }
}

/* A control character of ASCII: C0 and DEL. */
static int is_control(unsigned char c)
{
  return c < 0x20 || c == 0x7F;
}

/* ---- JSON */

static void json_put(FILE *fp, unsigned char c, unsigned char next)
{
  (void)next;
  /* RFC 8259 section 7: the two-character escapes where there is one. */
  static const char shorthand[][2] = {{'"', '"'},  {'\\', '\\'}, {'\b', 'b'}, {'\f', 'f'},
                                      {'\n', 'n'}, {'\r', 'r'},  {'\t', 't'}};
  for (size_t k = 0; k < sizeof shorthand / sizeof shorthand[0]; ++k)
    if (c == (unsigned char)shorthand[k][0]) {
      fputc('\\', fp);
      fputc(shorthand[k][1], fp);
      return;
    }
  if (c < 0x20)
    fprintf(fp, "\\u%04x", c);
  else
    fputc(c, fp);
}

void fb_json_write_string(FILE *fp, const char *s)
{
  if (!s) {
    fputs("null", fp);
    return;
  }
  fputc('"', fp);
  write_utf8(fp, s, (size_t)-1, json_put, 0);
  fputc('"', fp);
}

void fb_json_write_number(FILE *fp, double v)
{
  if (isfinite(v))
    fprintf(fp, "%.10g", v);
  else
    fputs("null", fp);
}

/* ---- DOT */

static void dot_put(FILE *fp, unsigned char c, unsigned char next)
{
  if (c == '"' || c == '\\') {
    fputc('\\', fp);
    fputc(c, fp);
  } else if (c == '\n' || (c == '\r' && next != '\n')) {
    fputs("\\n", fp);
  } else if (c == '\r') {
    /* CR LF: the LF makes the line break. */
  } else if (is_control(c)) {
    fputs(replacement, fp);
  } else {
    fputc(c, fp);
  }
}

void fb_dot_write_text_n(FILE *fp, const char *s, size_t n)
{
  write_utf8(fp, s, n, dot_put, 0);
}

void fb_dot_write_text(FILE *fp, const char *s)
{
  fb_dot_write_text_n(fp, s, (size_t)-1);
}

/* ---- Markdown */

static void md_put(FILE *fp, unsigned char c, unsigned char next)
{
  (void)next;
  if (c == '&')
    fputs("&amp;", fp);
  else if (c == '<')
    fputs("&lt;", fp);
  else if (c == '>')
    fputs("&gt;", fp);
  else if (is_control(c))
    fputc(' ', fp);
  else if (strchr("\\`*_[]#|~", c))
    fprintf(fp, "\\%c", c);
  else
    fputc(c, fp);
}

void fb_md_write_text(FILE *fp, const char *s)
{
  write_utf8(fp, s, (size_t)-1, md_put, 0);
}

/* ---- CSV */

/* Characters that make a spreadsheet read a text field as a formula when
 * they start it (OWASP, "CSV Injection"). */
static int starts_formula(unsigned char c)
{
  return c != '\0' && strchr("=+-@\t\r", c) != NULL;
}

/* The first byte of the concatenation of parts (0 if it is empty). */
static unsigned char first_byte(const char *const *parts, size_t nparts)
{
  for (size_t k = 0; k < nparts; ++k)
    if (parts[k] && *parts[k])
      return (unsigned char)*parts[k];
  return 0;
}

static int parts_need_quotes(const char *const *parts, size_t nparts)
{
  for (size_t k = 0; k < nparts; ++k)
    if (parts[k] && strpbrk(parts[k], ",\"\r\n"))
      return 1;
  return 0;
}

/* Inside a quoted field: a quote doubled, everything else as it is (CR
 * and LF are field data there, RFC 4180 section 2, rule 6). */
static void csv_put_quoted(FILE *fp, unsigned char c, unsigned char next)
{
  (void)next;
  if (c == '"')
    fputc('"', fp);
  fputc(c, fp);
}

/* Unquoted: the field holds no comma, quote or line break. */
static void csv_put_plain(FILE *fp, unsigned char c, unsigned char next)
{
  (void)next;
  fputc(c, fp);
}

void fb_csv_write_field_parts(FILE *fp, const char *const *parts, size_t nparts, unsigned flags)
{
  const int quoted = (flags & FB_CSV_QUOTE_ALWAYS) || parts_need_quotes(parts, nparts);
  if (quoted)
    fputc('"', fp);
  if ((flags & FB_CSV_TEXT) && starts_formula(first_byte(parts, nparts)))
    fputc('\'', fp);
  for (size_t k = 0; k < nparts; ++k)
    write_utf8(fp, parts[k], (size_t)-1, quoted ? csv_put_quoted : csv_put_plain, 0);
  if (quoted)
    fputc('"', fp);
}

void fb_csv_write_field(FILE *fp, const char *s, unsigned flags)
{
  fb_csv_write_field_parts(fp, &s, 1, flags);
}

/* ---- XML */

/* c in character data (attr 0) or in an attribute value (attr 1). */
static void xml_put(FILE *fp, unsigned char c, int attr)
{
  static const struct {
    char c;
    const char *text;
    int attr_only;
  } refs[] = {{'&', "&amp;", 0},  {'<', "&lt;", 0},    {'>', "&gt;", 0},  {'\r', "&#13;", 0},
              {'"', "&quot;", 1}, {'\'', "&apos;", 1}, {'\t', "&#9;", 1}, {'\n', "&#10;", 1}};
  for (size_t k = 0; k < sizeof refs / sizeof refs[0]; ++k)
    if (c == (unsigned char)refs[k].c && (attr || !refs[k].attr_only)) {
      fputs(refs[k].text, fp);
      return;
    }
  /* XML 1.0 section 2.2: Char holds no other C0 control (DEL is allowed). */
  if (c < 0x20 && c != '\t' && c != '\n')
    fputs(replacement, fp);
  else
    fputc(c, fp);
}

static void xml_put_text(FILE *fp, unsigned char c, unsigned char next)
{
  (void)next;
  xml_put(fp, c, 0);
}

static void xml_put_attr(FILE *fp, unsigned char c, unsigned char next)
{
  (void)next;
  xml_put(fp, c, 1);
}

void fb_xml_write_text(FILE *fp, const char *s)
{
  write_utf8(fp, s, (size_t)-1, xml_put_text, 1);
}

void fb_xml_write_attr(FILE *fp, const char *s)
{
  write_utf8(fp, s, (size_t)-1, xml_put_attr, 1);
}

/* ---- YAML. */

static void yaml_put(FILE *fp, unsigned char c, unsigned char next)
{
  (void)next;
  if (c == '"' || c == '\\')
    fputc('\\', fp);
  fputc(c, fp);
}

int fb_yaml_write_string(FILE *fp, const char *s)
{
  const char *text = s ? s : "";
  const size_t len = strlen(text);
  unsigned code = 0;
  if (fb_text_find_control(text, len, 0, &code) != len)
    return -1;
  fputc('"', fp);
  write_utf8(fp, text, len, yaml_put, 0);
  fputc('"', fp);
  return 0;
}

int fb_yaml_is_plain(const char *s)
{
  /* YAML 1.1's boolean and null words (yaml.org/type/bool.html,
   * null.html), compared without case: a reader of either version keeps
   * the rest as strings. */
  static const char *const words[] = {"y",     "n",  "yes", "no",   "true",
                                      "false", "on", "off", "null", NULL};
  if (!s || !(isalpha((unsigned char)s[0]) || s[0] == '_'))
    return 0;
  for (const char *p = s; *p; ++p)
    if (!(isalnum((unsigned char)*p) || *p == '_' || *p == '.'))
      return 0;
  for (size_t i = 0; words[i]; ++i) {
    size_t k = 0;
    while (s[k] && words[i][k] && tolower((unsigned char)s[k]) == words[i][k])
      ++k;
    if (!s[k] && !words[i][k])
      return 0;
  }
  return 1;
}
