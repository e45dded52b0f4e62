/* SPDX-License-Identifier: BSD-3-Clause */
/* Status codes and error messages (see flexbond/error.h). */
#include "flexbond/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void fb_err_clear(fb_err *err)
{
  if (!err)
    return;
  err->code = FB_OK;
  err->msg[0] = '\0';
  err->origin = FB_ORIGIN_NONE;
  err->origin_index = 0;
  err->key[0] = '\0';
  err->file[0] = '\0';
  err->line = err->column = 0;
  err->source = FB_SOURCE_NONE;
  err->source_text[0] = '\0';
  err->excerpt[0] = '\0';
  err->part = (fb_err_part){0, 0, FB_ERR_NO_ELEMENT, ""};
  err->text_start = 0;
}

/* The length of the well-formed UTF-8 sequence at t (The Unicode
 * Standard, Table 3-7: no overlong forms, surrogates or code points above
 * U+10FFFF), 1 for ASCII, 0 if the bytes are not one. */
static size_t utf8_length(const unsigned char *t)
{
  if (t[0] < 0x80)
    return 1;
  unsigned lo = 0x80, hi = 0xbf;
  size_t n;
  if (t[0] >= 0xc2 && t[0] <= 0xdf)
    n = 2;
  else if (t[0] >= 0xe0 && t[0] <= 0xef) {
    n = 3;
    lo = t[0] == 0xe0 ? 0xa0 : 0x80;
    hi = t[0] == 0xed ? 0x9f : 0xbf;
  } else if (t[0] >= 0xf0 && t[0] <= 0xf4) {
    n = 4;
    lo = t[0] == 0xf0 ? 0x90 : 0x80;
    hi = t[0] == 0xf4 ? 0x8f : 0xbf;
  } else {
    return 0;
  }
  if (t[1] < lo || t[1] > hi)
    return 0;
  for (size_t k = 2; k < n; ++k)
    if (t[k] < 0x80 || t[k] > 0xbf)
      return 0;
  return n;
}

/* What the text at t is written as (into esc, NUL-terminated): a control
 * character (C0, DEL, C1) as a C escape (\n, \r, \t, \xHH, \u00HH), a
 * byte that is not UTF-8 as \xHH, anything else as it is (a whole UTF-8
 * sequence, never a part). Returns the bytes of t it stands for. */
static size_t escaped_at(const unsigned char *t, char *esc, size_t size)
{
  const size_t n = utf8_length(t);
  if (n == 0 || t[0] < 0x20 || t[0] == 0x7f) {
    if (t[0] == '\n')
      snprintf(esc, size, "\\n");
    else if (t[0] == '\r')
      snprintf(esc, size, "\\r");
    else if (t[0] == '\t')
      snprintf(esc, size, "\\t");
    else
      snprintf(esc, size, "\\x%02x", t[0]);
    return 1;
  }
  if (n == 2 && t[0] == 0xc2 && t[1] <= 0x9f) {
    snprintf(esc, size, "\\u%04x", t[1]);
    return 2;
  }
  memcpy(esc, t, n);
  esc[n] = '\0';
  return n;
}

/* fb_err_escape's work; returns how many bytes of text it wrote out. */
static size_t escape_into(char *out, size_t size, const char *text)
{
  size_t n = 0;
  const unsigned char *t = (const unsigned char *)(text ? text : "");
  const unsigned char *start = t;
  while (*t) {
    char esc[16]; /* the longest: "\\u00HH", or a 4-byte character */
    const size_t len = escaped_at(t, esc, sizeof esc);
    const size_t w = strlen(esc);
    if (n + w >= size)
      break;
    memcpy(out + n, esc, w);
    n += w;
    t += len;
  }
  out[n] = '\0';
  return (size_t)(t - start);
}

void fb_err_escape(char *out, size_t size, const char *text)
{
  if (out && size)
    escape_into(out, size, text);
}

/* vsnprintf into dst (size bytes) as fb_err_escape writes it. */
static void escaped_vprintf(char *dst, size_t size, const char *fmt, va_list ap)
{
  char raw[FB_ERR_MSG_MAX];
  vsnprintf(raw, sizeof raw, fmt, ap);
  fb_err_escape(dst, size, raw);
}

int(fb_err_set_origin)(fb_err *err, int origin, size_t index, int code)
{
  if (err) {
    err->origin = origin;
    err->origin_index = index;
  }
  return code;
}

/* The parentheses keep the analyzer-only macro of error.h from expanding here. */
int(fb_err_set)(fb_err *err, int code, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  fb_err_vset(err, code, fmt, ap);
  va_end(ap);
  return code;
}

int fb_err_vset(fb_err *err, int code, const char *fmt, va_list ap)
{
  if (!err)
    return code;
  escaped_vprintf(err->msg, sizeof err->msg, fmt, ap);
  err->code = code;
  err->origin = FB_ORIGIN_NONE;
  err->origin_index = 0;
  err->key[0] = '\0';
  err->file[0] = '\0';
  err->line = err->column = 0;
  err->source = FB_SOURCE_NONE;
  err->source_text[0] = '\0';
  err->excerpt[0] = '\0';
  err->part = (fb_err_part){0, 0, FB_ERR_NO_ELEMENT, ""};
  err->text_start = 0;
  return code;
}

int fb_err_set_part(fb_err *err, int kind, size_t index, size_t element, const char *field)
{
  if (!err)
    return FB_OK;
  err->part.kind = kind;
  err->part.index = index;
  err->part.element = element;
  snprintf(err->part.field, sizeof err->part.field, "%s", field ? field : "");
  return err->code;
}

int fb_err_set_key(fb_err *err, const char *fmt, ...)
{
  if (!err)
    return FB_OK;
  va_list ap;
  va_start(ap, fmt);
  escaped_vprintf(err->key, sizeof err->key, fmt, ap);
  va_end(ap);
  return err->code;
}

void fb_err_set_location(fb_err *err, const char *file, int line, int column)
{
  if (!err)
    return;
  snprintf(err->file, sizeof err->file, "%s", file ? file : "");
  err->line = line;
  err->column = column;
  err->source = FB_SOURCE_FILE;
}

void fb_err_set_source(fb_err *err, int source, const char *text)
{
  if (!err)
    return;
  err->source = source;
  snprintf(err->source_text, sizeof err->source_text, "%s", text ? text : "");
}

/* Prepends head (formatted, escaped) to err's message; a location moves
 * fb_err.text_start past it, any other head only keeps it on the same
 * text once a location is there. */
static int prefix(fb_err *err, int location, const char *fmt, va_list ap)
{
  char head[FB_ERR_MSG_MAX];
  escaped_vprintf(head, sizeof head, fmt, ap);
  /* Truncation keeps the head (the context) and cuts the tail. */
  size_t hlen = strlen(head);
  size_t mlen = strlen(err->msg);
  if (hlen + mlen >= sizeof err->msg)
    mlen = sizeof err->msg - 1 - hlen;
  memmove(err->msg + hlen, err->msg, mlen);
  memcpy(err->msg, head, hlen);
  err->msg[hlen + mlen] = '\0';
  if (location || err->text_start > 0) {
    const size_t start = err->text_start + hlen;
    err->text_start = start < hlen + mlen ? start : hlen + mlen;
  }
  return err->code;
}

int fb_err_prefix(fb_err *err, const char *fmt, ...)
{
  if (!err)
    return FB_OK;
  va_list ap;
  va_start(ap, fmt);
  const int rc = prefix(err, 0, fmt, ap);
  va_end(ap);
  return rc;
}

int fb_err_prefix_location(fb_err *err, const char *fmt, ...)
{
  if (!err)
    return FB_OK;
  va_list ap;
  va_start(ap, fmt);
  const int rc = prefix(err, 1, fmt, ap);
  va_end(ap);
  return rc;
}

/* The bytes of a data file's text an excerpt keeps (fb_err.excerpt). */
#define EXCERPT_BYTES 64

void fb_err_set_excerpt(fb_err *err, const char *text, size_t n)
{
  if (!err || !text)
    return;
  char raw[EXCERPT_BYTES + 1];
  /* Counted to one byte past what is kept: whether anything is left out. */
  const size_t len = strnlen(text, n < EXCERPT_BYTES + 1 ? n : EXCERPT_BYTES + 1);
  size_t kept = len < EXCERPT_BYTES ? len : EXCERPT_BYTES;
  /* A cut inside a UTF-8 sequence would leave a part of a character. */
  while (kept > 0 && kept < len && ((unsigned char)text[kept] & 0xc0) == 0x80)
    --kept;
  memcpy(raw, text, kept);
  raw[kept] = '\0';
  /* Escapes may not all fit: "..." says when anything is left out. */
  const size_t written = escape_into(err->excerpt, sizeof err->excerpt - 3, raw);
  /* cppcheck-suppress knownConditionTrueFalse ; false only for a caller's empty field */
  if (len > kept || written < kept)
    memcpy(err->excerpt + strlen(err->excerpt), "...", sizeof "...");
}

char *fb_err_describe(const fb_err *err, char *buf, size_t size)
{
  if (!buf || !size)
    return buf;
  if (!err)
    buf[0] = '\0';
  else if (err->excerpt[0])
    snprintf(buf, size, "%s (read: '%s')", err->msg, err->excerpt);
  else
    snprintf(buf, size, "%s", err->msg);
  return buf;
}

int fb_err_append(fb_err *err, const char *fmt, ...)
{
  if (!err)
    return FB_OK;
  const size_t len = strlen(err->msg);
  va_list ap;
  va_start(ap, fmt);
  escaped_vprintf(err->msg + len, sizeof err->msg - len, fmt, ap);
  va_end(ap);
  return err->code;
}

const char *fb_status_name(int code)
{
  switch (code) {
  case FB_OK: return "FB_OK";
  case FB_ENOMEM: return "FB_ENOMEM";
  case FB_EINVAL: return "FB_EINVAL";
  case FB_EPARSE: return "FB_EPARSE";
  case FB_EMODEL: return "FB_EMODEL";
  case FB_ECAUSAL: return "FB_ECAUSAL";
  case FB_ESOLVER: return "FB_ESOLVER";
  case FB_EIO: return "FB_EIO";
  case FB_EINTR: return "FB_EINTR";
  default: return "FB_E?";
  }
}

int fb_progress_report(const fb_progress *p, const char *stage, double fraction, fb_err *err)
{
  if (!p || !p->fn || p->fn(p->ctx, stage, fraction) == 0)
    return FB_OK;
  return fb_err_set(err, FB_EINTR, "interrupted during %s", stage);
}
