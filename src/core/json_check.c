/* SPDX-License-Identifier: BSD-3-Clause */
/* A recogniser of JSON text (RFC 8259, "The JavaScript Object Notation
 * (JSON) Data Interchange Format"), sections 2-8: the grammar's values,
 * strict numbers and strings, and UTF-8 (section 8.1). It builds nothing;
 * it says whether a file flexbond wrote is JSON before it is committed
 * (fb_json_check in flexbond/escape.h). */
#include <stddef.h>

#include "flexbond/escape.h"

/* Deepest nesting accepted: far beyond any file of ours (summary.json
 * nests 5 levels), and the recursion stays small. */
enum { JSON_MAX_DEPTH = 256 };

typedef struct json_in {
  const unsigned char *s;
  size_t n, at;
} json_in;

static int more(const json_in *in)
{
  return in->at < in->n;
}

static unsigned char peek(const json_in *in)
{
  return more(in) ? in->s[in->at] : 0;
}

/* Section 2: ws = *( %x20 / %x09 / %x0A / %x0D ). */
static void skip_ws(json_in *in)
{
  while (more(in) &&
         (peek(in) == ' ' || peek(in) == '\t' || peek(in) == '\n' || peek(in) == '\r'))
    ++in->at;
}

static int literal(json_in *in, const char *word)
{
  for (; *word; ++word, ++in->at)
    if (!more(in) || peek(in) != (unsigned char)*word)
      return 0;
  return 1;
}

static int digits(json_in *in)
{
  const size_t start = in->at;
  while (more(in) && peek(in) >= '0' && peek(in) <= '9')
    ++in->at;
  return in->at > start;
}

/* Section 6: [ minus ] int [ frac ] [ exp ], int without leading zeros. */
static int number(json_in *in)
{
  if (peek(in) == '-')
    ++in->at;
  if (peek(in) == '0')
    ++in->at;
  else if (!digits(in))
    return 0;
  if (peek(in) == '.') {
    ++in->at;
    if (!digits(in))
      return 0;
  }
  if (peek(in) == 'e' || peek(in) == 'E') {
    ++in->at;
    if (peek(in) == '+' || peek(in) == '-')
      ++in->at;
    if (!digits(in))
      return 0;
  }
  return 1;
}

static int hex(unsigned char c)
{
  return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

/* One UTF-8 sequence of 2 to 4 bytes led by c0 (RFC 3629, section 4:
 * no overlong forms, no surrogates, nothing above U+10FFFF). */
static int utf8_tail(json_in *in, unsigned char c0)
{
  size_t len = 0;
  unsigned char lo = 0x80, hi = 0xbf;
  if (c0 >= 0xc2 && c0 <= 0xdf)
    len = 1;
  else if (c0 >= 0xe0 && c0 <= 0xef) {
    len = 2;
    lo = c0 == 0xe0 ? 0xa0 : 0x80;
    hi = c0 == 0xed ? 0x9f : 0xbf;
  } else if (c0 >= 0xf0 && c0 <= 0xf4) {
    len = 3;
    lo = c0 == 0xf0 ? 0x90 : 0x80;
    hi = c0 == 0xf4 ? 0x8f : 0xbf;
  } else {
    return 0;
  }
  for (size_t k = 0; k < len; ++k, ++in->at) {
    const unsigned char c = peek(in);
    if (!more(in) || c < (k ? 0x80 : lo) || c > (k ? 0xbf : hi))
      return 0;
  }
  return 1;
}

/* Section 7: '"' *char '"', no unescaped control character. */
static int string(json_in *in)
{
  ++in->at; /* the opening quote */
  while (more(in)) {
    const unsigned char c = peek(in);
    ++in->at;
    if (c == '"')
      return 1;
    if (c < 0x20)
      return 0;
    if (c == '\\') {
      const unsigned char e = peek(in);
      ++in->at;
      if (e == 'u') {
        for (int k = 0; k < 4; ++k, ++in->at)
          if (!more(in) || !hex(peek(in)))
            return 0;
      } else if (!e || !(e == '"' || e == '\\' || e == '/' || e == 'b' || e == 'f' ||
                         e == 'n' || e == 'r' || e == 't')) {
        return 0;
      }
    } else if (c >= 0x80 && !utf8_tail(in, c)) {
      return 0;
    }
  }
  return 0;
}

static int value(json_in *in, int depth);

/* Sections 4 and 5: members or elements between open and close. */
static int container(json_in *in, int depth, unsigned char close, int members)
{
  ++in->at;
  skip_ws(in);
  if (peek(in) == close) {
    ++in->at;
    return 1;
  }
  for (;;) {
    if (members) {
      if (peek(in) != '"' || !string(in))
        return 0;
      skip_ws(in);
      if (peek(in) != ':')
        return 0;
      ++in->at;
    }
    if (!value(in, depth + 1))
      return 0;
    skip_ws(in);
    if (peek(in) == close) {
      ++in->at;
      return 1;
    }
    if (peek(in) != ',')
      return 0;
    ++in->at;
    skip_ws(in);
  }
}

/* Section 3, with the whitespace around it. */
static int value(json_in *in, int depth)
{
  if (depth >= JSON_MAX_DEPTH) /* depth 0 is the outermost value */
    return 0;
  skip_ws(in);
  int ok = 0;
  switch (peek(in)) {
  case '{': ok = container(in, depth, '}', 1); break;
  case '[': ok = container(in, depth, ']', 0); break;
  case '"': ok = string(in); break;
  case 't': ok = literal(in, "true"); break;
  case 'f': ok = literal(in, "false"); break;
  case 'n': ok = literal(in, "null"); break;
  default:
    ok = more(in) && (peek(in) == '-' || (peek(in) >= '0' && peek(in) <= '9')) && number(in);
  }
  skip_ws(in);
  return ok;
}

int fb_json_check(const char *text, size_t len, size_t *offset)
{
  json_in in = {(const unsigned char *)text, len, 0};
  const int ok = text && value(&in, 0) && in.at == len;
  if (offset)
    *offset = ok ? 0 : in.at;
  return ok ? 0 : -1;
}
