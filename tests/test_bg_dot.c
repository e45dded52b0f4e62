/* SPDX-License-Identifier: BSD-3-Clause */
/* The multibond-graph picture (fb_bg_write_dot) and the two-level block
 * diagram (fb_bd_write_dot_hierarchy) of small graphs whose causality is
 * worked out by hand below: each stroke is checked at its end, clusters
 * against the instances built, names against their escaped text. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"

#include "bgtest_util.h"
#include "check.h"

/* The text fp received, NUL-terminated (new). */
static char *slurp(FILE *fp)
{
  long n = ftell(fp);
  char *s = malloc((size_t)n + 1);
  rewind(fp);
  if (s && fread(s, 1, (size_t)n, fp) != (size_t)n)
    n = 0;
  if (s)
    s[n] = '\0';
  return s;
}

/* The line of dot holding the edge "from" -> "to" (IDs as written,
 * quotes included), copied into buf; 0 if there is none. */
static int edge_line(const char *dot, const char *from, const char *to, char *buf, size_t size)
{
  char key[256];
  snprintf(key, sizeof key, "  %s -> %s [", from, to);
  const char *at = strstr(dot, key);
  if (!at)
    return 0;
  const char *end = strchr(at, '\n');
  size_t n = end ? (size_t)(end - at) : strlen(at);
  n = n < size - 1 ? n : size - 1;
  memcpy(buf, at, n);
  buf[n] = '\0';
  return 1;
}

/* 1 if the edge from -> to has its stroke at the head (to) when at_head,
 * at the tail (from) otherwise, and the half arrow at the head. */
static int stroke_at(const char *dot, const char *from, const char *to, int at_head)
{
  char line[512];
  if (!edge_line(dot, from, to, line, sizeof line)) {
    fprintf(stderr, "no edge %s -> %s\n", from, to);
    return 0;
  }
  const char *want = at_head ? "arrowhead=\"teelvee\", arrowtail=\"none\""
                             : "arrowhead=\"lvee\", arrowtail=\"tee\"";
  if (!strstr(line, want)) {
    fprintf(stderr, "edge %s -> %s: want %s in: %s\n", from, to, want, line);
    return 0;
  }
  return 1;
}

static size_t count(const char *s, const char *what)
{
  size_t n = 0;
  for (const char *p = strstr(s, what); p; p = strstr(p + 1, what))
    ++n;
  return n;
}

/* A subsystem: 1-junction j with an inertia m on it, its port p at j
 * (power in). */
static fb_bg *mass_subsystem(const char *name, fb_err *err)
{
  fb_bg *c = NULL;
  MUST(fb_bg_new(name, &c, err), err);
  MUST(add_scalar(c, "m", FB_BG_I, 2.0, err), err);
  MUST(fb_bg_add_junction(c, "j", FB_BG_J1, 1, err), err);
  MUST(fb_bg_connect(c, "b_m", "j", "m", err), err);
  MUST(fb_bg_add_port(c, "p", "j", FB_PORT_IN, err), err);
  return c;
}

/* The test graph, named with DOT's special characters:
 *   Se src -> 1 J -> I mass, C spring, R damper        (scalar)
 *   Sf v -> 0 n -> C k2                                (scalar)
 *   Se e3 [3] -> 1 J3 [3] -> I M3 [3]                  (a multibond)
 *   Se f2 -> sub.p (sub: 1 j -> I m)
 *   Se f3 -> outer.p (outer holds inner: 1 j -> I m)
 * Causality by hand (Karnopp et al., section 5.2): a source of effort
 * gives its effort to its junction (stroke at J, the head); a flow source
 * takes it (stroke at v, the tail). Storage in integral causality: an I
 * receives effort (stroke at the I, the head), a C gives it (stroke at the
 * junction, the tail). On 1-junction J the inertia sets the common flow,
 * so J gives no other bond its effort: the R's stroke is at J too (the
 * tail), resistance causality e = R f. On 0-junction n the C k2 sets the
 * effort, the flow source's bond takes it from n (tail, as above). */
static fb_bg *test_graph(fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("g\"q\\{x}", &bg, err), err);
  MUST(add_const_source(bg, "src", FB_BG_SE, 1.0, err), err);
  MUST(fb_bg_add_junction(bg, "J", FB_BG_J1, 1, err), err);
  MUST(add_scalar(bg, "mass", FB_BG_I, 3.0, err), err);
  MUST(add_scalar(bg, "spring", FB_BG_C, 100.0, err), err);
  MUST(add_scalar(bg, "damper", FB_BG_R, 5.0, err), err);
  MUST(fb_bg_connect(bg, "b_src", "src", "J", err), err);
  MUST(fb_bg_connect(bg, "b_mass", "J", "mass", err), err);
  MUST(fb_bg_connect(bg, "b_spring", "J", "spring", err), err);
  MUST(fb_bg_connect(bg, "b_damper", "J", "damper", err), err);
  MUST(add_const_source(bg, "v", FB_BG_SF, 0.5, err), err);
  MUST(fb_bg_add_junction(bg, "n", FB_BG_J0, 1, err), err);
  MUST(add_scalar(bg, "k2", FB_BG_C, 10.0, err), err);
  MUST(fb_bg_connect(bg, "b_v", "v", "n", err), err);
  MUST(fb_bg_connect(bg, "b_k2", "n", "k2", err), err);
  /* A multibond of 3: the source's three components and a 3x3 inertia. */
  fb_tfun *f[3] = {NULL, NULL, NULL};
  for (int i = 0; i < 3; ++i)
    MUST(fb_tfun_new_const(1.0 + i, &f[i], err), err);
  MUST(fb_bg_add_source(bg, "e3", FB_BG_SE, 3, f, err), err);
  MUST(fb_bg_add_junction(bg, "J3", FB_BG_J1, 3, err), err);
  fb_mat *M = NULL;
  const size_t three = 3;
  MUST(fb_mat_new_scaled_identity(3, 4.0, &M, err), err);
  MUST(fb_bg_add_field(bg, "M3", FB_BG_I, 1, &three, &M, err), err);
  MUST(fb_bg_connect(bg, "b_e3", "e3", "J3", err), err);
  MUST(fb_bg_connect(bg, "b_M3", "J3", "M3", err), err);
  /* Subsystems: sub, and outer holding inner (instances "outer",
   * "outer.inner"). */
  fb_bg *sub = mass_subsystem("mass_sub", err);
  MUST(fb_bg_adopt(bg, &sub, "sub", err), err);
  MUST(add_const_source(bg, "f2", FB_BG_SE, 1.0, err), err);
  MUST(fb_bg_connect(bg, "b_f2", "f2", "sub.p", err), err);
  fb_bg *outer = NULL, *inner = mass_subsystem("inner_sub", err);
  MUST(fb_bg_new("outer_sub", &outer, err), err);
  MUST(fb_bg_adopt(outer, &inner, "inner", err), err);
  MUST(fb_bg_add_port(outer, "p", "inner.p", FB_PORT_IN, err), err);
  MUST(fb_bg_adopt(bg, &outer, "outer", err), err);
  MUST(add_const_source(bg, "f3", FB_BG_SE, 1.0, err), err);
  MUST(fb_bg_connect(bg, "b_f3", "f3", "outer.p", err), err);
  return bg;
}

static char *bond_graph_dot(const fb_bg *bg, fb_err *err)
{
  FILE *fp = tmpfile();
  CHECK(fp != NULL);
  if (!fp)
    return NULL;
  MUST(fb_bg_write_dot(bg, fp, err), err);
  char *s = slurp(fp);
  fclose(fp);
  return s;
}

static void test_strokes(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = test_graph(&err);
  /* Before causality: no stroke anywhere. */
  char *dot = bond_graph_dot(bg, &err);
  CHECK(dot && count(dot, "tee") == 0);
  CHECK(dot && strstr(dot, "causality not assigned"));
  free(dot);
  MUST(fb_bg_assign_causality(bg, &err), &err);
  dot = bond_graph_dot(bg, &err);
  CHECK(dot != NULL);
  if (!dot) {
    fb_bg_free(&bg);
    return;
  }
  CHECK(stroke_at(dot, "\"src\"", "\"J\"", 1));
  CHECK(stroke_at(dot, "\"J\"", "\"mass\"", 1));
  CHECK(stroke_at(dot, "\"J\"", "\"spring\"", 0));
  CHECK(stroke_at(dot, "\"J\"", "\"damper\"", 0));
  CHECK(stroke_at(dot, "\"v\"", "\"n\"", 0));
  CHECK(stroke_at(dot, "\"n\"", "\"k2\"", 0));
  CHECK(stroke_at(dot, "\"e3\"", "\"J3\"", 1));
  CHECK(stroke_at(dot, "\"J3\"", "\"M3\"", 1));
  CHECK(stroke_at(dot, "\"f2\"", "\"sub.j\"", 1));
  CHECK(stroke_at(dot, "\"sub.j\"", "\"sub.m\"", 1));
  CHECK(stroke_at(dot, "\"outer.inner.j\"", "\"outer.inner.m\"", 1));
  /* Every bond is one edge; the multibond says its dimension once. */
  CHECK(count(dot, " -> ") == fb_bg_nbonds(bg));
  CHECK(count(dot, "[3]") == 2);
  /* One cluster per instance: sub, outer, outer.inner; nested. */
  CHECK(count(dot, "subgraph \"cluster_") == 3);
  const char *o = strstr(dot, "subgraph \"cluster_outer\"");
  const char *oi = strstr(dot, "subgraph \"cluster_outer.inner\"");
  CHECK(o && oi && oi > o);
  CHECK(strstr(dot, "label=\"outer.inner\";"));
  /* Kinds and names: "I : m" inside its cluster, junctions as 0 and 1. */
  CHECK(strstr(dot, "\"sub.m\" [label=\"I : m\"]"));
  CHECK(strstr(dot, "\"n\" [label=\"0\""));
  CHECK(strstr(dot, "\"J\" [label=\"1\""));
  /* The graph's name, with " \ { }: escaped in the ID, braces kept. */
  CHECK(strstr(dot, "digraph \"g\\\"q\\\\{x}\" {"));
  free(dot);
  fb_bg_free(&bg);
}

/* A composite is drawn as a bar; the two-level block diagram has the
 * instances' clusters and the top level's. */
static void test_block_levels(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = test_graph(&err);
  fb_bd *bd = NULL;
  const fb_probe_spec probe = {.name = "x\"y\\z{}",
                               .kind = FB_PROBE_EFFORT,
                               .target = "sub.b_m",
                               .component = -1,
                               .gain = 1.0,
                               .unit = "N\"}"};
  MUST(fb_bd_build(bg, &probe, 1, &bd, &err), &err);
  FILE *fp = tmpfile();
  CHECK(fp != NULL);
  if (bd && fp) {
    MUST(fb_bd_write_dot_hierarchy(bd, fp, &err), &err);
    char *dot = slurp(fp);
    CHECK(dot != NULL);
    /* cluster_top, sub, outer, outer.inner; "sub" and "outer" are not
     * alike (outer's blocks sit one instance deeper), so both are drawn. */
    CHECK(dot && count(dot, "subgraph \"cluster_") == 4);
    CHECK(dot && strstr(dot, "subgraph \"cluster_top\""));
    /* The meter: the probe's name and unit, escaped. */
    CHECK(dot && strstr(dot, "meter\\nx\\\"y\\\\z{} [N\\\"}]"));
    /* Signals carry their dimension: the multibond's effort is one edge. */
    CHECK(dot && strstr(dot, "[3]\", penwidth=2]"));
    free(dot);
  }
  if (fp)
    fclose(fp);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

static void test_composite_bar(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  const size_t parts[2] = {1, 1};
  MUST(fb_bg_new("mux", &bg, &err), &err);
  MUST(add_const_source(bg, "a", FB_BG_SE, 1.0, &err), &err);
  MUST(add_const_source(bg, "b", FB_BG_SE, 2.0, &err), &err);
  MUST(fb_bg_add_composite(bg, "line", 2, parts, &err), &err);
  MUST(fb_bg_add_junction(bg, "J", FB_BG_J1, 2, &err), &err);
  fb_mat *M = NULL;
  const size_t two = 2;
  MUST(fb_mat_new_scaled_identity(2, 1.0, &M, &err), &err);
  MUST(fb_bg_add_field(bg, "M", FB_BG_I, 1, &two, &M, &err), &err);
  MUST(fb_bg_connect(bg, NULL, "a", "line.1", &err), &err);
  MUST(fb_bg_connect(bg, NULL, "b", "line.2", &err), &err);
  MUST(fb_bg_connect(bg, "whole", "line.whole", "J", &err), &err);
  MUST(fb_bg_connect(bg, "b_M", "J", "M", &err), &err);
  MUST(fb_bg_assign_causality(bg, &err), &err);
  char *dot = bond_graph_dot(bg, &err);
  CHECK(dot && strstr(dot, "\"line\" [shape=box, style=filled, fillcolor=black"));
  /* The sources give their efforts to the composite, which gives the
   * stacked effort to J, which gives it to the inertia. */
  CHECK(dot && stroke_at(dot, "\"a\"", "\"line\"", 1));
  CHECK(dot && stroke_at(dot, "\"line\"", "\"J\"", 1));
  CHECK(dot && stroke_at(dot, "\"J\"", "\"M\"", 1));
  CHECK(dot && strstr(dot, "label=\"whole [2]\""));
  free(dot);
  fb_bg_free(&bg);
}

int main(void)
{
  test_strokes();
  test_block_levels();
  test_composite_bar();
  return check_report("test_bg_dot");
}
