/* SPDX-License-Identifier: BSD-3-Clause */
/* Graphviz DOT export of a block diagram (the paper's Fig. 6): one node
 * per block, one edge per signal use, one cluster per subsystem. Every
 * name inside the quoted IDs and labels goes through fb_dot_write_text
 * (flexbond/escape.h), so none can end its string or its statement. */
#include <stdio.h>
#include <string.h>

#include "flexbond/escape.h"

#include "bd/bd_internal.h"

/* Length of the subsystem prefix of an element name ("a.b.x" -> 3), 0
 * for top-level elements. */
static size_t prefix_len(const char *name)
{
  const char *dot = strrchr(name, '.');
  return dot ? (size_t)(dot - name) : 0;
}

static const char *block_group(const fb_bd *bd, size_t i, size_t *len)
{
  const bd_block *b = &bd->blocks[i];
  if (b->elem == FB_NONE) {
    *len = 0;
    return "";
  }
  const char *name = bd->bg->elems[b->elem].name;
  *len = prefix_len(name);
  return name;
}

static void write_node(const fb_bd *bd, size_t i, FILE *fp)
{
  const bd_block *b = &bd->blocks[i];
  int state = b->ops->state;
  fprintf(fp, "  n%zu [label=\"", i);
  if (b->elem != FB_NONE) {
    fprintf(fp, "%s ", fb_bg_kind_name(bd->bg->elems[b->elem].kind));
    fb_dot_write_text(fp, bd->bg->elems[b->elem].name);
    fputs("\\n", fp);
  } else {
    fputs("probe\\n", fp);
  }
  fb_dot_write_text(fp, b->ops->symbol ? b->ops->symbol : b->label);
  fprintf(fp, " [%zu]\"%s];\n", b->odim,
          state ? ", shape=box, style=\"rounded,filled\", fillcolor=\"#dde8f8\"" : "");
}

int fb_bd_write_dot(const fb_bd *bd, FILE *fp, fb_err *err)
{
  fputs("digraph \"", fp);
  fb_dot_write_text(fp, bd->bg->name);
  fputs("\" {\n  rankdir=LR;\n  node [shape=box, fontname=\"Helvetica\", fontsize=10];\n"
        "  edge [fontname=\"Helvetica\", fontsize=8];\n",
        fp);
  /* Blocks grouped by subsystem prefix; top-level ones outside clusters. */
  for (size_t i = 0; i < bd->nblocks; ++i) {
    size_t len;
    const char *g = block_group(bd, i, &len);
    int first = 1;
    for (size_t j = 0; j < i && first; ++j) {
      size_t lj;
      const char *gj = block_group(bd, j, &lj);
      first = !(lj == len && strncmp(g, gj, len) == 0);
    }
    if (!first)
      continue;
    if (len) {
      fputs("  subgraph \"cluster_", fp);
      fb_dot_write_text_n(fp, g, len);
      fputs("\" {\n  label=\"", fp);
      fb_dot_write_text_n(fp, g, len);
      fputs("\";\n", fp);
    }
    for (size_t j = i; j < bd->nblocks; ++j) {
      size_t lj;
      const char *gj = block_group(bd, j, &lj);
      if (lj == len && strncmp(g, gj, len) == 0)
        write_node(bd, j, fp);
    }
    if (len)
      fputs("  }\n", fp);
  }
  for (size_t i = 0; i < bd->nblocks; ++i) {
    const bd_block *b = &bd->blocks[i];
    for (size_t k = 0; k < b->nin; ++k) {
      const bd_signal *s = &bd->sigs[b->in[k].id];
      fprintf(fp, "  n%zu -> n%zu [label=\"", s->producer, i);
      fb_dot_write_text(fp, s->name);
      fprintf(fp, " [%zu]\"];\n", s->dim);
    }
  }
  fputs("}\n", fp);
  if (ferror(fp))
    return fb_err_set(err, FB_EIO, "error writing the DOT diagram");
  return FB_OK;
}
