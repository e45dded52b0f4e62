/* SPDX-License-Identifier: BSD-3-Clause */
/* Graphviz DOT picture of a multibond graph (the paper's Fig. 5; Leite &
 * Da Silva draw the vehicle's subsystems as separate graphs joined by
 * bonds, multibonds labelled with their dimension in brackets, and the
 * composition of the attachment bonds as a horizontal line).
 *
 * Bond-graph conventions (Karnopp, Margolis & Rosenberg, "System
 * Dynamics", 5th ed., sections 3.1 and 5.1): the half arrow points in the
 * direction of positive power; the causal stroke sits at the end of the
 * bond whose element receives the effort. In Graphviz the half arrow is
 * the arrow shape "lvee" at the edge's head, the stroke a "tee" at the end
 * concerned: at the head it comes first ("teelvee": the first shape of a
 * multi-shape arrow touches the node). docs/diagrams.md has the legend. */
#include <stdio.h>
#include <string.h>

#include "flexbond/escape.h"

#include "bg/bg_internal.h"

/* The symbol of an element kind in a picture: the junctions are "0" and
 * "1" (a bond graph writes no more), the rest their usual names. */
static const char *kind_symbol(fb_bg_kind kind)
{
  switch (kind) {
  case FB_BG_J0: return "0";
  case FB_BG_J1: return "1";
  default: return fb_bg_kind_name(kind);
  }
}

/* "NAME" as a quoted DOT ID: the element's full name, unique in bg. */
static void write_id(FILE *fp, const char *name)
{
  fputc('"', fp);
  fb_dot_write_text(fp, name);
  fputc('"', fp);
}

static void write_element(const fb_bg *bg, const fb_bg_groups *g, size_t e, FILE *fp)
{
  const fb_bg_elem *el = &bg->elems[e];
  const char *local = fb_bg_groups_strip(g, g->of_elem[e], el->name);
  fputs("    ", fp);
  write_id(fp, el->name);
  if (el->kind == FB_BG_COMPOSITE) {
    /* The paper's horizontal line: a bar across the part bonds (upright
     * here, as the picture runs left to right), named beside it. */
    fputs(" [shape=box, style=filled, fillcolor=black, fixedsize=true, width=0.06, "
          "height=0.9, label=\"\", xlabel=\"",
          fp);
    fb_dot_write_text(fp, local);
    fputs("\"];\n", fp);
    return;
  }
  if (el->kind == FB_BG_J0 || el->kind == FB_BG_J1) {
    fprintf(fp, " [label=\"%s\", fontsize=14, xlabel=\"", kind_symbol(el->kind));
    fb_dot_write_text(fp, local);
    fputs("\"];\n", fp);
    return;
  }
  fprintf(fp, " [label=\"%s : ", kind_symbol(el->kind));
  fb_dot_write_text(fp, local);
  fputs("\"];\n", fp);
}

/* The elements directly in group `group` (FB_NONE: the top level), then
 * a cluster for each group it holds, recursively. */
static void write_group(const fb_bg *bg, const fb_bg_groups *g, size_t group, int depth,
                        FILE *fp)
{
  for (size_t e = 0; e < bg->nelems; ++e)
    if (g->of_elem[e] == group)
      write_element(bg, g, e, fp);
  for (size_t i = 0; i < g->n; ++i) {
    if (g->parent[i] != group)
      continue;
    fprintf(fp, "  %*ssubgraph \"cluster_", 2 * depth, "");
    fb_dot_write_text_n(fp, g->name[i], g->len[i]);
    fputs("\" {\n    label=\"", fp);
    fb_dot_write_text_n(fp, g->name[i], g->len[i]);
    fputs("\";\n", fp);
    write_group(bg, g, i, depth + 1, fp);
    fprintf(fp, "  %*s}\n", 2 * depth, "");
  }
}

/* The bond's name within the innermost group that holds both its ends
 * (a bond of one subsystem is named there without the prefix). */
static const char *bond_label(const fb_bg *bg, const fb_bg_groups *g, size_t b)
{
  const fb_bg_bond *bd = &bg->bonds[b];
  size_t gf = g->of_elem[bd->from], gt = g->of_elem[bd->to];
  return gf == gt ? fb_bg_groups_strip(g, gf, bd->name) : bd->name;
}

static void write_bond(const fb_bg *bg, const fb_bg_groups *g, size_t b, FILE *fp)
{
  const fb_bg_bond *bd = &bg->bonds[b];
  fputs("  ", fp);
  write_id(fp, bg->elems[bd->from].name);
  fputs(" -> ", fp);
  write_id(fp, bg->elems[bd->to].name);
  /* Strokes only where assigned: a graph without causality has none. */
  const int at_to = bg->causal && bd->stroke == FB_STROKE_AT_TO;
  const int at_from = bg->causal && bd->stroke == FB_STROKE_AT_FROM;
  fprintf(fp, " [arrowhead=\"%s\", arrowtail=\"%s\", label=\"", at_to ? "teelvee" : "lvee",
          at_from ? "tee" : "none");
  fb_dot_write_text(fp, bond_label(bg, g, b));
  if (bd->dim > 1)
    fprintf(fp, " [%zu]\", penwidth=2.2];\n", bd->dim);
  else
    fputs("\"];\n", fp);
}

/* Constant text: the conventions, drawn beside the graph. */
static void write_legend(const fb_bg *bg, FILE *fp)
{
  fputs("  legend [shape=note, fontsize=9, label=\"bond graph conventions\\l"
        "half arrow: positive power flows that way\\l",
        fp);
  if (bg->causal)
    fputs("| at a bond end: causal stroke, that element receives the effort\\l", fp);
  else
    fputs("causality not assigned: no strokes\\l", fp);
  fputs("[n]: multibond of n components (thick)\\l"
        "black bar: composite, the parts stacked into one multibond\\l"
        "box: subsystem instance\\l\"];\n",
        fp);
}

int fb_bg_write_dot(const fb_bg *bg, FILE *fp, fb_err *err)
{
  fb_bg_groups g;
  int rc = fb_bg_groups_make(bg, &g, err);
  if (rc != FB_OK)
    return rc;
  fputs("digraph \"", fp);
  fb_dot_write_text(fp, bg->name);
  fputs("\" {\n  rankdir=LR;\n  label=\"", fp);
  fb_dot_write_text(fp, bg->name);
  fputs(": multibond graph\";\n  labelloc=t;\n"
        "  node [shape=plaintext, fontname=\"Helvetica\", fontsize=11];\n"
        "  edge [dir=both, fontname=\"Helvetica\", fontsize=8];\n",
        fp);
  write_legend(bg, fp);
  write_group(bg, &g, FB_NONE, 0, fp);
  for (size_t b = 0; b < bg->nbonds; ++b)
    write_bond(bg, &g, b, fp);
  fputs("}\n", fp);
  fb_bg_groups_free(&g);
  if (ferror(fp))
    return fb_err_set(err, FB_EIO, "error writing the DOT bond graph");
  return FB_OK;
}
