/* SPDX-License-Identifier: BSD-3-Clause */
/* The block diagram in two levels, as Leite & Da Silva's Fig. 6: (a), (b)
 * the top level, where each subsystem is one block, a mux stacks the
 * efforts the subsystems impart to the hull and a demux splits the
 * hull's flows back to them (the horizontal line of Fig. 5), and meters
 * collect the signals to store; (c)-(f) one level down, the contents of
 * each subsystem block. Here both levels are clusters of one DOT graph:
 * "cluster_top" and one cluster per instance, its signals from and to the
 * other blocks drawn as in- and out-ports (Simulink's Inport and Outport
 * blocks), so no edge crosses from one level to the other. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/escape.h"

#include "bd/bd_internal.h"

/* Fills of the instances' blocks and panels, cycled (the paper colours
 * each subsystem: green, orange, yellow, blue). */
static const char *const fills[] = {"#d9f0d3", "#fde0c5", "#fff6bf",
                                    "#d6e6f5", "#eadcf2", "#f2f2f2"};
enum { NFILLS = sizeof fills / sizeof fills[0] };

typedef struct hier {
  const fb_bd *bd;
  fb_bg_groups g;
  size_t *top;    /* per block: its outermost instance, FB_NONE at the top level */
  size_t *inner;  /* per block: its innermost instance */
  size_t *rep;    /* per group: the first instance alike (itself if none) */
  size_t *colour; /* per top-level group: its fill */
  FILE *fp;
} hier;

static size_t sig_producer_top(const hier *h, size_t s)
{
  return h->top[h->bd->sigs[s].producer];
}

/* The position of block b among the blocks of top-level instance t. */
static size_t block_pos(const hier *h, size_t t, size_t b)
{
  size_t pos = 0;
  for (size_t i = 0; i < b; ++i)
    pos += h->top[i] == t;
  return pos;
}

/* 1 if instances t and u (top level) have the same blocks in the same
 * order (kind, label, element name within the instance, dimensions) and
 * the same wiring inside, so one drawing shows both. */
static int alike(const hier *h, size_t t, size_t u)
{
  const fb_bd *bd = h->bd;
  size_t i = 0, j = 0;
  for (;;) {
    while (i < bd->nblocks && h->top[i] != t)
      ++i;
    while (j < bd->nblocks && h->top[j] != u)
      ++j;
    if (i == bd->nblocks || j == bd->nblocks)
      return i == bd->nblocks && j == bd->nblocks;
    const bd_block *a = &bd->blocks[i], *b = &bd->blocks[j];
    if (a->ops != b->ops || a->nin != b->nin || a->odim != b->odim ||
        strcmp(a->label, b->label) != 0 ||
        strcmp(fb_bg_groups_strip(&h->g, t, bd->bg->elems[a->elem].name),
               fb_bg_groups_strip(&h->g, u, bd->bg->elems[b->elem].name)) != 0)
      return 0;
    for (size_t k = 0; k < a->nin; ++k) {
      size_t sa = a->in[k].id, sb = b->in[k].id;
      size_t pa = bd->sigs[sa].producer, pb = bd->sigs[sb].producer;
      int ina = h->top[pa] == t, inb = h->top[pb] == u;
      if (ina != inb || bd->sigs[sa].dim != bd->sigs[sb].dim)
        return 0;
      if (ina && block_pos(h, t, pa) != block_pos(h, u, pb))
        return 0;
    }
    ++i;
    ++j;
  }
}

static int hier_make(hier *h, const fb_bd *bd, FILE *fp, fb_err *err)
{
  memset(h, 0, sizeof *h);
  int rc = fb_bg_groups_make(bd->bg, &h->g, err);
  if (rc != FB_OK)
    return rc;
  /* Set after the call: the analyzer takes a call given &h->g to overwrite all of *h. */
  h->bd = bd;
  h->fp = fp;
  h->top = malloc((bd->nblocks + 1) * sizeof *h->top);
  h->inner = malloc((bd->nblocks + 1) * sizeof *h->inner);
  h->rep = malloc((h->g.n + 1) * sizeof *h->rep);
  h->colour = malloc((h->g.n + 1) * sizeof *h->colour);
  if (!h->top || !h->inner || !h->rep || !h->colour)
    return fb_err_set(err, FB_ENOMEM, "out of memory drawing the block diagram");
  for (size_t i = 0; i < bd->nblocks; ++i) {
    size_t e = bd->blocks[i].elem;
    h->inner[i] = e == FB_NONE ? FB_NONE : h->g.of_elem[e];
    h->top[i] = fb_bg_groups_top(&h->g, h->inner[i]);
  }
  size_t ntop = 0;
  for (size_t t = 0; t < h->g.n; ++t) {
    h->rep[t] = t;
    if (h->g.parent[t] != FB_NONE)
      continue;
    h->colour[t] = ntop++ % NFILLS;
    for (size_t u = 0; u < t && h->rep[t] == t; ++u)
      if (h->g.parent[u] == FB_NONE && h->rep[u] == u && alike(h, u, t)) {
        h->rep[t] = u;
        h->colour[t] = h->colour[u];
      }
  }
  return FB_OK;
}

static void hier_free(hier *h)
{
  fb_bg_groups_free(&h->g);
  free(h->top);
  free(h->inner);
  free(h->rep);
  free(h->colour);
}

/* A signal's name without instance t's prefix: "e:susp_LF.b_tire" in
 * susp_LF is "e:b_tire". */
static void write_signal_name(const hier *h, size_t t, const char *name)
{
  const char *colon = strchr(name, ':');
  if (t != FB_NONE && colon && colon - name == 1) {
    fb_dot_write_text_n(h->fp, name, 2);
    fb_dot_write_text(h->fp, fb_bg_groups_strip(&h->g, t, colon + 1));
  } else {
    fb_dot_write_text(h->fp, fb_bg_groups_strip(&h->g, t, name));
  }
}

static void write_block(const hier *h, size_t i, const char *indent)
{
  const fb_bd *bd = h->bd;
  const bd_block *b = &bd->blocks[i];
  int state = b->ops->state;
  fprintf(h->fp, "%sb%zu [label=\"", indent, i);
  if (b->elem != FB_NONE) {
    fprintf(h->fp, "%s ", fb_bg_kind_name(bd->bg->elems[b->elem].kind));
    fb_dot_write_text(h->fp,
                      fb_bg_groups_strip(&h->g, h->inner[i], bd->bg->elems[b->elem].name));
    fputs("\\n", h->fp);
  } else {
    fputs("probe\\n", h->fp);
  }
  fb_dot_write_text(h->fp, b->ops->symbol ? b->ops->symbol : b->label);
  fprintf(h->fp, " [%zu]\"%s];\n", b->odim,
          state ? ", style=\"rounded,filled\", fillcolor=\"#dde8f8\"" : "");
}

/* The blocks directly in group grp, then its nested groups as clusters. */
static void write_panel_group(const hier *h, size_t grp, int depth)
{
  char indent[64];
  snprintf(indent, sizeof indent, "%*s", 2 * depth + 4, "");
  for (size_t i = 0; i < h->bd->nblocks; ++i)
    if (h->inner[i] == grp)
      write_block(h, i, indent);
  for (size_t k = 0; k < h->g.n; ++k) {
    if (h->g.parent[k] != grp)
      continue;
    fprintf(h->fp, "%ssubgraph \"cluster_", indent);
    fb_dot_write_text_n(h->fp, h->g.name[k], h->g.len[k]);
    fprintf(h->fp, "\" {\n%s  label=\"", indent);
    fb_dot_write_text_n(h->fp, h->g.name[k], h->g.len[k]);
    fputs("\";\n", h->fp);
    write_panel_group(h, k, depth + 1);
    fprintf(h->fp, "%s}\n", indent);
  }
}

/* 1 if signal s is read by a meter (an output). */
static int metered(const fb_bd *bd, size_t s)
{
  for (size_t i = 0; i < bd->nouts; ++i)
    if (bd->outs[i].signal == s)
      return 1;
  return 0;
}

/* 1 if signal s, produced in instance t, is read outside it. */
static int leaves(const hier *h, size_t t, size_t s)
{
  const fb_bd *bd = h->bd;
  if (metered(bd, s))
    return 1;
  for (size_t i = 0; i < bd->nblocks; ++i)
    for (size_t k = 0; k < bd->blocks[i].nin; ++k)
      if (bd->blocks[i].in[k].id == s && h->top[i] != t)
        return 1;
  return 0;
}

/* 1 if block i's input k is the first of the blocks of instance t (up to
 * block i, input k) to read signal s: an in-port is drawn once. */
static int first_reader(const hier *h, size_t t, size_t i, size_t k)
{
  size_t s = h->bd->blocks[i].in[k].id;
  for (size_t j = 0; j <= i; ++j) {
    if (h->top[j] != t)
      continue;
    const bd_block *b = &h->bd->blocks[j];
    for (size_t m = 0; m < (j == i ? k : b->nin); ++m)
      if (b->in[m].id == s)
        return 0;
  }
  return 1;
}

static void write_port(const hier *h, size_t t, const char *dir, size_t s)
{
  fprintf(h->fp, "    %s%zu_%zu [shape=cds, style=filled, fillcolor=\"#eeeeee\", label=\"", dir,
          t, s);
  write_signal_name(h, t, h->bd->sigs[s].name);
  fprintf(h->fp, " [%zu]\"];\n", h->bd->sigs[s].dim);
}

static void write_edge_label(const hier *h, size_t t, size_t s)
{
  fputs(" [label=\"", h->fp);
  write_signal_name(h, t, h->bd->sigs[s].name);
  fprintf(h->fp, " [%zu]\"%s];\n", h->bd->sigs[s].dim,
          h->bd->sigs[s].dim > 1 ? ", penwidth=2" : "");
}

/* One level down: instance t's cluster, its ports and its edges. */
static void write_panel(const hier *h, size_t t)
{
  const fb_bd *bd = h->bd;
  FILE *fp = h->fp;
  fputs("  subgraph \"cluster_", fp);
  fb_dot_write_text_n(fp, h->g.name[t], h->g.len[t]);
  fputs("\" {\n    label=\"", fp);
  fb_dot_write_text_n(fp, h->g.name[t], h->g.len[t]);
  size_t nalike = 0;
  for (size_t u = t + 1; u < h->g.n; ++u)
    if (h->g.parent[u] == FB_NONE && h->rep[u] == t) {
      fputs(nalike++ ? ", " : " (drawn once for it and ", fp);
      fb_dot_write_text_n(fp, h->g.name[u], h->g.len[u]);
    }
  fprintf(fp, "%s\";\n    style=filled;\n    fillcolor=\"%s\";\n", nalike ? ": alike)" : "",
          fills[h->colour[t]]);
  write_panel_group(h, t, 0);
  for (size_t i = 0; i < bd->nblocks; ++i) {
    if (h->top[i] != t)
      continue;
    const bd_block *b = &bd->blocks[i];
    for (size_t k = 0; k < b->nin; ++k)
      if (sig_producer_top(h, b->in[k].id) != t && first_reader(h, t, i, k))
        write_port(h, t, "in", b->in[k].id);
    if (leaves(h, t, b->out))
      write_port(h, t, "out", b->out);
  }
  fputs("  }\n", fp);
  for (size_t i = 0; i < bd->nblocks; ++i) {
    if (h->top[i] != t)
      continue;
    const bd_block *b = &bd->blocks[i];
    for (size_t k = 0; k < b->nin; ++k) {
      size_t s = b->in[k].id, p = bd->sigs[s].producer;
      if (h->top[p] == t)
        fprintf(fp, "  b%zu -> b%zu", p, i);
      else
        fprintf(fp, "  in%zu_%zu -> b%zu", t, s, i);
      write_edge_label(h, t, s);
    }
    if (leaves(h, t, b->out)) {
      fprintf(fp, "  b%zu -> out%zu_%zu", i, t, b->out);
      write_edge_label(h, t, b->out);
    }
  }
}

/* The top-level node of block i: its instance's block, or the block. */
static void write_top_node(const hier *h, size_t i)
{
  if (h->top[i] == FB_NONE)
    fprintf(h->fp, "b%zu", i);
  else
    fprintf(h->fp, "t%zu", h->top[i]);
}

/* 1 if an earlier input (block j < i, or input m < k of block i) already
 * drew the top-level edge of signal s into the same node as block i. */
static int top_edge_drawn(const hier *h, size_t i, size_t k)
{
  const fb_bd *bd = h->bd;
  size_t s = bd->blocks[i].in[k].id;
  for (size_t j = 0; j <= i; ++j) {
    if (h->top[j] != h->top[i] || (h->top[i] == FB_NONE && j != i))
      continue;
    const bd_block *b = &bd->blocks[j];
    for (size_t m = 0; m < (j == i ? k : b->nin); ++m)
      if (b->in[m].id == s)
        return 1;
  }
  return 0;
}

static size_t count_blocks(const hier *h, size_t t)
{
  size_t n = 0;
  for (size_t i = 0; i < h->bd->nblocks; ++i)
    n += h->top[i] == t;
  return n;
}

/* A meter per metered signal, named by its first output and unit. */
static void write_meters(const hier *h)
{
  const fb_bd *bd = h->bd;
  for (size_t o = 0; o < bd->nouts; ++o) {
    size_t s = bd->outs[o].signal, more = 0, first = 1;
    for (size_t q = 0; q < bd->nouts; ++q) {
      if (bd->outs[q].signal != s)
        continue;
      first = first && q >= o;
      more += q > o;
    }
    if (!first)
      continue;
    fprintf(h->fp,
            "    m%zu [shape=note, style=filled, fillcolor=\"#ffffff\", label=\"meter\\n", s);
    fb_dot_write_text(h->fp, bd->outs[o].name);
    if (bd->outs[o].unit && *bd->outs[o].unit) {
      fputs(" [", h->fp);
      fb_dot_write_text(h->fp, bd->outs[o].unit);
      fputc(']', h->fp);
    }
    if (more)
      fprintf(h->fp, "\\n+ %zu more output%s", more, more > 1 ? "s" : "");
    fputs("\"];\n", h->fp);
  }
}

static void write_meter_edges(const hier *h)
{
  const fb_bd *bd = h->bd;
  for (size_t o = 0; o < bd->nouts; ++o) {
    size_t s = bd->outs[o].signal, q = 0;
    while (bd->outs[q].signal != s)
      ++q;
    if (q != o)
      continue;
    fputs("  ", h->fp);
    write_top_node(h, bd->sigs[s].producer);
    fprintf(h->fp, " -> m%zu", s);
    write_edge_label(h, FB_NONE, s);
  }
}

/* The top level: instances as blocks, top-level blocks, meters. */
static void write_top(const hier *h)
{
  const fb_bd *bd = h->bd;
  FILE *fp = h->fp;
  fputs("  subgraph \"cluster_top\" {\n    label=\"top level\";\n", fp);
  for (size_t t = 0; t < h->g.n; ++t) {
    if (h->g.parent[t] != FB_NONE)
      continue;
    fprintf(fp, "    t%zu [shape=box3d, style=filled, fillcolor=\"%s\", label=\"", t,
            fills[h->colour[t]]);
    fb_dot_write_text_n(fp, h->g.name[t], h->g.len[t]);
    fprintf(fp, "\\n(subsystem, %zu blocks)\"];\n", count_blocks(h, t));
  }
  for (size_t i = 0; i < bd->nblocks; ++i)
    if (h->top[i] == FB_NONE)
      write_block(h, i, "    ");
  write_meters(h);
  fputs("  }\n", fp);
  for (size_t i = 0; i < bd->nblocks; ++i) {
    const bd_block *b = &bd->blocks[i];
    for (size_t k = 0; k < b->nin; ++k) {
      size_t s = b->in[k].id, p = bd->sigs[s].producer;
      if ((h->top[i] != FB_NONE && h->top[p] == h->top[i]) || top_edge_drawn(h, i, k))
        continue;
      fputs("  ", fp);
      write_top_node(h, p);
      fputs(" -> ", fp);
      write_top_node(h, i);
      write_edge_label(h, FB_NONE, s);
    }
  }
  write_meter_edges(h);
}

int fb_bd_write_dot_hierarchy(const fb_bd *bd, FILE *fp, fb_err *err)
{
  hier h;
  int rc = hier_make(&h, bd, fp, err);
  if (rc == FB_OK) {
    fputs("digraph \"", fp);
    fb_dot_write_text(fp, bd->bg->name);
    fputs("\" {\n  rankdir=LR;\n  label=\"", fp);
    fb_dot_write_text(fp, bd->bg->name);
    fputs(": block diagram, top level and one level down\";\n  labelloc=t;\n"
          "  node [shape=box, fontname=\"Helvetica\", fontsize=10];\n"
          "  edge [fontname=\"Helvetica\", fontsize=8];\n",
          fp);
    write_top(&h);
    for (size_t t = 0; t < h.g.n; ++t)
      if (h.g.parent[t] == FB_NONE && h.rep[t] == t)
        write_panel(&h, t);
    fputs("}\n", fp);
    if (ferror(fp))
      rc = fb_err_set(err, FB_EIO, "error writing the DOT block diagram");
  }
  hier_free(&h);
  return rc;
}
