/* SPDX-License-Identifier: BSD-3-Clause */
/* Subsystem instances of a graph from its element names (see
 * fb_bg_groups in bg_internal.h): the clusters of its pictures. */
#include <stdlib.h>
#include <string.h>

#include "bg/bg_internal.h"

void fb_bg_groups_free(fb_bg_groups *g)
{
  free(g->name);
  free(g->len);
  free(g->parent);
  free(g->of_elem);
  *g = (fb_bg_groups){0, NULL, NULL, NULL, NULL};
}

/* Index of the group name[0 .. len), FB_NONE if there is none yet. */
static size_t find_group(const fb_bg_groups *g, const char *name, size_t len)
{
  for (size_t i = 0; i < g->n; ++i)
    if (g->len[i] == len && strncmp(g->name[i], name, len) == 0)
      return i;
  return FB_NONE;
}

/* The group of name[0 .. len) and its enclosing ones, added where new;
 * returns its index. Capacity is there (at most one group per '.'). */
static size_t add_group(fb_bg_groups *g, const char *name, size_t len)
{
  size_t at = find_group(g, name, len);
  if (at != FB_NONE)
    return at;
  size_t parent = FB_NONE;
  for (size_t k = len; k-- > 0;)
    if (name[k] == '.') {
      parent = add_group(g, name, k);
      break;
    }
  g->name[g->n] = name;
  g->len[g->n] = len;
  g->parent[g->n] = parent;
  return g->n++;
}

int fb_bg_groups_make(const fb_bg *bg, fb_bg_groups *g, fb_err *err)
{
  g->n = 0; /* each array is set below, before any use */
  size_t cap = 1;
  for (size_t e = 0; e < bg->nelems; ++e)
    for (const char *s = bg->elems[e].name; *s; ++s)
      cap += *s == '.';
  g->name = malloc(cap * sizeof *g->name);
  g->len = malloc(cap * sizeof *g->len);
  g->parent = malloc(cap * sizeof *g->parent);
  g->of_elem = malloc((bg->nelems + 1) * sizeof *g->of_elem);
  if (!g->name || !g->len || !g->parent || !g->of_elem) {
    fb_bg_groups_free(g);
    return fb_err_set(err, FB_ENOMEM, "out of memory grouping the elements of '%s'", bg->name);
  }
  for (size_t e = 0; e < bg->nelems; ++e) {
    const char *name = bg->elems[e].name, *dot = strrchr(name, '.');
    g->of_elem[e] = dot ? add_group(g, name, (size_t)(dot - name)) : FB_NONE;
  }
  return FB_OK;
}

size_t fb_bg_groups_top(const fb_bg_groups *g, size_t i)
{
  while (i != FB_NONE && g->parent[i] != FB_NONE)
    i = g->parent[i];
  return i;
}

const char *fb_bg_groups_strip(const fb_bg_groups *g, size_t i, const char *name)
{
  if (i == FB_NONE || strncmp(name, g->name[i], g->len[i]) != 0 || name[g->len[i]] != '.')
    return name;
  return name + g->len[i] + 1;
}
