/* SPDX-License-Identifier: BSD-3-Clause */
/* Graphviz rendering (see io/graphviz.h), with the discipline of the
 * gnuplot figures (io/plot.c): a private directory, fixed names inside
 * it, the child run through fb_child_run, the picture checked before it
 * reaches its destination. */
#include "io/graphviz.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "flexbond/io.h"

#include "core/tmpfile.h"
#include "core/util.h"
#include "io/child.h"
#include "io/plot_internal.h"

/* The files of one dot run, in its private directory. */
static const char gv_dot[] = "graph.dot", gv_svg[] = "graph.svg", gv_png[] = "graph.png",
                  gv_log[] = "dot.log";

fb_graphviz_format fb_graphviz_format_of(const char *path)
{
  const char *dot = strrchr(path, '.');
  const char *slash = strrchr(path, '/');
  if (!dot || (slash && dot < slash))
    return FB_GRAPHVIZ_DOT;
  if (strcasecmp(dot, ".svg") == 0)
    return FB_GRAPHVIZ_SVG;
  if (strcasecmp(dot, ".png") == 0)
    return FB_GRAPHVIZ_PNG;
  return FB_GRAPHVIZ_DOT;
}

/* The DOT of fn(ctx) into the file at path, through fb_out. */
static int write_dot(fb_graphviz_fn fn, const void *ctx, const char *path, fb_err *err)
{
  fb_out *out = NULL;
  int rc = fb_out_open(path, &out, err);
  if (rc != FB_OK)
    return rc;
  rc = fn(fb_out_stream(out), ctx, err);
  if (rc != FB_OK) {
    fb_out_abort(&out);
    return rc;
  }
  return fb_out_commit(&out, err);
}

/* Copies the file src to path through fb_out (atomic; a link, a FIFO or a
 * device at path is treated as for every output). */
static int copy_out(const char *src, const char *path, fb_err *err)
{
  FILE *in = fopen(src, "rb");
  if (!in)
    return fb_err_set(err, FB_EIO, "%s: cannot read the picture dot drew: %s", path,
                      strerror(errno));
  fb_out *out = NULL;
  int rc = fb_out_open(path, &out, err);
  char buf[65536];
  size_t n;
  while (rc == FB_OK && (n = fread(buf, 1, sizeof buf, in)) > 0)
    if (fwrite(buf, 1, n, fb_out_stream(out)) != n)
      rc = fb_err_set(err, FB_EIO, "%s: write error: %s", path, strerror(errno));
  if (rc == FB_OK && ferror(in))
    rc = fb_err_set(err, FB_EIO, "%s: cannot read the picture dot drew", path);
  fclose(in);
  if (out && rc != FB_OK)
    fb_out_abort(&out);
  else if (out)
    rc = fb_out_commit(&out, err);
  return rc;
}

/* Runs dot on graph.dot in dir, checks the picture and copies it out. */
static int draw_in(const char *dir, fb_graphviz_format fmt, const char *path, fb_err *err)
{
  const int png = fmt == FB_GRAPHVIZ_PNG;
  char program[] = "dot", type[] = "-Tsvg", opt_o[] = "-o", input[sizeof gv_dot];
  /* The two names have the same length ("graph.png", "graph.svg"). */
  _Static_assert(sizeof gv_svg == sizeof gv_png, "picture names of one length");
  char output[sizeof gv_svg];
  if (png)
    memcpy(type, "-Tpng", sizeof type);
  memcpy(input, gv_dot, sizeof gv_dot);
  memcpy(output, png ? gv_png : gv_svg, sizeof output);
  char *argv[] = {program, type, opt_o, output, input, NULL};
  const fb_child_spec spec = {.program = program,
                              .argv = argv,
                              .cwd = dir,
                              .log = gv_log,
                              .timeout_s = FB_GRAPHVIZ_TIMEOUT_S};
  char *pic = NULL;
  int rc = fb_child_make(&spec, output, png ? fb_png_check : fb_svg_check, path, &pic, err);
  if (rc == FB_OK)
    rc = copy_out(pic, path, err);
  free(pic);
  return rc;
}

int fb_graphviz_write(fb_graphviz_fn fn, const void *ctx, fb_graphviz_format fmt,
                      const char *path, fb_err *err)
{
  if (fmt == FB_GRAPHVIZ_DOT)
    return write_dot(fn, ctx, path, err);
  char *dir = NULL;
  const int e = fb_tmpdir_create(path, "graphviz", &dir);
  if (e != 0)
    return fb_err_set(err, e == ENOMEM ? FB_ENOMEM : FB_EIO,
                      "%s: cannot create a directory for Graphviz: %s", path, strerror(e));
  char *dot = fb_path_join(dir, gv_dot);
  int rc = dot ? write_dot(fn, ctx, dot, err)
               : fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  if (rc == FB_OK)
    rc = draw_in(dir, fmt, path, err);
  free(dot);
  const char *const names[] = {gv_dot, gv_svg, gv_png, gv_log};
  fb_child_dir_remove(dir, names, sizeof names / sizeof names[0]);
  return rc;
}

/* The first byte of [s, end) that is not white space (end if none). */
static const char *skip_space(const char *s, const char *end)
{
  while (s < end && isspace((unsigned char)*s))
    ++s;
  return s;
}

/* 1 if [s, end) starts with the text of prefix. */
static int starts_with(const char *s, const char *end, const char *prefix)
{
  size_t n = strlen(prefix);
  return (size_t)(end - s) >= n && memcmp(s, prefix, n) == 0;
}

int fb_svg_check(const char *path, fb_err *err)
{
  FILE *fp = fopen(path, "rb");
  if (!fp)
    return fb_err_set(err, FB_EIO, "%s: not a complete SVG image: cannot open: %s", path,
                      strerror(errno));
  size_t cap = 1 << 16, n = 0;
  char *buf = malloc(cap);
  int rc = buf ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory reading %s", path);
  for (size_t got = 1; rc == FB_OK && got > 0;) {
    if (n == cap) {
      char *bigger = cap < ((size_t)1 << 30) ? realloc(buf, 2 * cap) : NULL;
      if (!bigger) {
        rc = fb_err_set(err, FB_EIO, "%s: not a complete SVG image: too large", path);
        break;
      }
      buf = bigger;
      cap *= 2;
    }
    got = fread(buf + n, 1, cap - n, fp);
    n += got;
  }
  if (rc == FB_OK && ferror(fp))
    rc = fb_err_set(err, FB_EIO, "%s: not a complete SVG image: read error", path);
  fclose(fp);
  if (rc != FB_OK) {
    free(buf);
    return rc;
  }
  const char *end = buf + n, *s = skip_space(buf, end);
  const char *e = end;
  while (e > s && isspace((unsigned char)e[-1]))
    --e;
  const char *why = NULL;
  static const char close_tag[] = "</svg>";
  const size_t nclose = sizeof close_tag - 1;
  if (s == end)
    why = "the file is empty";
  else if (!starts_with(s, e, "<?xml") && !starts_with(s, e, "<svg"))
    why = "it does not start with <?xml or <svg";
  else if ((size_t)(e - s) < nclose || memcmp(e - nclose, close_tag, nclose) != 0)
    why = "it does not end with </svg> (truncated?)";
  else {
    /* An <svg start tag somewhere: buf holds no NUL from dot, but check
     * with a bounded search all the same. */
    int found = 0;
    for (const char *p = s; p + 4 <= e && !found; ++p)
      found = memcmp(p, "<svg", 4) == 0;
    if (!found)
      why = "it has no <svg> element";
  }
  free(buf);
  if (why)
    return fb_err_set(err, FB_EIO, "%s: not a complete SVG image: %s", path, why);
  return FB_OK;
}
