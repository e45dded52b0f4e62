/* SPDX-License-Identifier: BSD-3-Clause */
/* Diagrams through Graphviz (https://graphviz.org): DOT text written by
 * the caller, rendered to SVG or PNG by `dot`, the one way the library
 * runs it. */
#ifndef FLEXBOND_IO_GRAPHVIZ_H
#define FLEXBOND_IO_GRAPHVIZ_H

#include <stdio.h>

#include "flexbond/error.h"

typedef enum fb_graphviz_format {
  FB_GRAPHVIZ_DOT, /* the DOT text itself */
  FB_GRAPHVIZ_SVG, /* dot -Tsvg */
  FB_GRAPHVIZ_PNG  /* dot -Tpng */
} fb_graphviz_format;

/* Seconds `dot` may take before it is killed: a graph of a few hundred
 * nodes takes well under one. */
#define FB_GRAPHVIZ_TIMEOUT_S 120.0

/* Writes a DOT graph to fp; returns a status (err filled on failure). */
typedef int (*fb_graphviz_fn)(FILE *fp, const void *ctx, fb_err *err);

/* The format of path from its extension: ".svg" SVG, ".png" PNG (any
 * case), anything else (".dot", ".gv", none: /dev/null) DOT. */
fb_graphviz_format fb_graphviz_format_of(const char *path);

/* Writes the graph fn(ctx) to path in format fmt, all or nothing: DOT
 * straight through fb_out. SVG and PNG: the DOT into a private directory
 * made beside path (mode 0700, fixed file names, so that `dot`, started
 * there, is given no path of the user's), `dot -Tsvg|-Tpng -o graph.svg
 * graph.dot` run there through fb_child_run, the picture checked
 * (fb_png_check, fb_svg_check), then copied to path through fb_out
 * (fb_out_open, fb_out_commit: atomic). The directory is removed in every
 * case. FB_EIO when dot is missing, fails, times out or draws no complete
 * picture (its log's last lines in the message), or path cannot be
 * written; the callback's status if it fails. */
int fb_graphviz_write(fb_graphviz_fn fn, const void *ctx, fb_graphviz_format fmt,
                      const char *path, fb_err *err);

/* FB_OK if the file at path looks like a complete SVG document: not
 * empty, starts (after white space) with "<?xml" or "<svg", holds an
 * "<svg" start tag and ends (before white space) with "</svg>"; FB_EIO
 * "not a complete SVG image: ..." otherwise. A check for a truncated or
 * foreign file, not an XML parser. */
int fb_svg_check(const char *path, fb_err *err);

#endif
