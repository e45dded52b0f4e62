/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond causality: assigns causality to the model's bond graph and
 * lists every bond with the end that carries its causal stroke. The stroke
 * sits at the end of the element that receives the effort (Karnopp,
 * Margolis & Rosenberg, "System Dynamics", 5th ed., section 5.1). */
#include <stdio.h>
#include <string.h>

#include "flexbond/bg.h"

#include "cli.h"
#include "graph_input.h"

static const char causality_usage[] =
    "usage: flexbond causality FILE.yaml [--system rigid|flexible]\n"
    "\n"
    "FILE is a model file or a vehicle scenario file, whose vehicle is\n"
    "assembled for --system (default rigid). Assigns causality (sequential causality "
    "assignment procedure) and\n"
    "prints one line per bond: name, power direction from -> to, dimension,\n"
    "domain, and the end with the causal stroke (the element that receives\n"
    "the effort; the other end receives the flow).\n"
    "\n"
    "options:\n"
    "  --system S            rigid (System 1) or flexible (System 2), scenarios only\n"
    "  -h, --help            this text\n";

static const char *domain_name(fb_bg_domain d)
{
  switch (d) {
  case FB_DOMAIN_TRANSLATION: return "translation";
  case FB_DOMAIN_ROTATION: return "rotation";
  case FB_DOMAIN_ELECTRICAL: return "electrical";
  case FB_DOMAIN_HYDRAULIC: return "hydraulic";
  case FB_DOMAIN_GENERIC: return "generic";
  }
  return "?";
}

/* Column widths, so the table lines up. */
typedef struct table_widths {
  int bond, from, to, domain;
} table_widths;

static int max_int(int a, size_t b)
{
  return (size_t)a > b ? a : (int)b;
}

static table_widths measure(const fb_bg *g)
{
  table_widths w = {0, 0, 0, 0};
  for (size_t i = 0; i < fb_bg_nbonds(g); ++i) {
    w.bond = max_int(w.bond, strlen(fb_bg_bond_name(g, i)));
    w.from = max_int(w.from, strlen(fb_bg_element_name(g, fb_bg_bond_from(g, i))));
    w.to = max_int(w.to, strlen(fb_bg_element_name(g, fb_bg_bond_to(g, i))));
    w.domain = max_int(w.domain, strlen(domain_name(fb_bg_bond_domain(g, i))));
  }
  return w;
}

/* e.g. "b3  J1 -> Ms  dim 1  translation  stroke at Ms (Ms receives effort)" */
static void print_bond(const fb_bg *g, size_t i, const table_widths *w)
{
  const char *from = fb_bg_element_name(g, fb_bg_bond_from(g, i));
  const char *to = fb_bg_element_name(g, fb_bg_bond_to(g, i));
  printf("%-*s  %-*s -> %-*s  dim %zu  %-*s  ", w->bond, fb_bg_bond_name(g, i), w->from, from,
         w->to, to, fb_bg_bond_dim(g, i), w->domain, domain_name(fb_bg_bond_domain(g, i)));
  int to_head = fb_bg_bond_effort_to_head(g, i);
  if (to_head < 0) {
    puts("no stroke (causality unassigned)");
    return;
  }
  const char *receiver = to_head ? to : from;
  printf("stroke at %s (%s receives effort)\n", receiver, receiver);
}

static int run(const char *path, fb_system sys, int system_given)
{
  fb_err err;
  fb_err_clear(&err);
  cli_graph_input in;
  int rc = cli_graph_input_load(path, sys, system_given, &in, &err);
  if (rc == FB_OK)
    rc = fb_bg_assign_causality(in.graph, &err);
  /* The graph names the element or bond at fault; a model knows where
   * the file wrote it. */
  if (rc != FB_OK)
    cli_graph_input_blame(&in, &err);
  if (rc == FB_OK) {
    const fb_bg *g = in.graph;
    table_widths w = measure(g);
    for (size_t i = 0; i < fb_bg_nbonds(g); ++i)
      print_bond(g, i, &w);
    rc = cli_flush_stdout(&err);
  }
  cli_graph_input_free(&in);
  return cli_report(rc, &err);
}

int cli_cmd_causality(int argc, char **argv)
{
  enum { OPT_SYSTEM, OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {
      [OPT_SYSTEM] = {"--system", NULL, 1, NULL}, [OPT_HELP] = {"--help", "-h", 0, NULL}};
  const char *path;
  int code;
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, causality_usage, "FILE", &path, &code))
    return code;
  fb_system sys;
  code = cli_system_option(argv[0], opts[OPT_SYSTEM].value, &sys);
  if (code != CLI_EXIT_OK)
    return code;
  return run(path, sys, opts[OPT_SYSTEM].value != NULL);
}
