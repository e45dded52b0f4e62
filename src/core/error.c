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
  vsnprintf(err->msg, sizeof err->msg, fmt, ap);
  err->code = code;
  err->origin = FB_ORIGIN_NONE;
  err->origin_index = 0;
  err->key[0] = '\0';
  err->file[0] = '\0';
  err->line = err->column = 0;
  err->source = FB_SOURCE_NONE;
  err->source_text[0] = '\0';
  return code;
}

int fb_err_set_key(fb_err *err, const char *fmt, ...)
{
  if (!err)
    return FB_OK;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err->key, sizeof err->key, fmt, ap);
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

int fb_err_prefix(fb_err *err, const char *fmt, ...)
{
  if (!err)
    return FB_OK;
  char head[FB_ERR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(head, sizeof head, fmt, ap);
  va_end(ap);
  /* Truncation keeps the head (the context) and cuts the tail. */
  size_t hlen = strlen(head);
  size_t mlen = strlen(err->msg);
  if (hlen + mlen >= sizeof err->msg)
    mlen = sizeof err->msg - 1 - hlen;
  memmove(err->msg + hlen, err->msg, mlen);
  memcpy(err->msg, head, hlen);
  err->msg[hlen + mlen] = '\0';
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
