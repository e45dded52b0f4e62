/* flexbond causality: assigns causality to the model's bond graph and
 * lists every bond with the end that carries its causal stroke. The stroke
 * sits at the end of the element that receives the effort (Karnopp,
 * Margolis & Rosenberg, "System Dynamics", 5th ed., section 5.1). */
#include <stdio.h>
#include <string.h>

#include "flexbond/bg.h"
#include "flexbond/model.h"

#include "cli.h"

static const char causality_usage[] =
    "usage: flexbond causality MODEL.yaml\n"
    "\n"
    "Assigns causality (sequential causality assignment procedure) and\n"
    "prints one line per bond: name, power direction from -> to, dimension,\n"
    "domain, and the end with the causal stroke (the element that receives\n"
    "the effort; the other end receives the flow).\n"
    "\n"
    "options:\n"
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

static int run(const char *model_path)
{
  fb_err err;
  fb_err_clear(&err);
  fb_model *m = NULL;
  int rc = fb_model_load(model_path, &m, &err);
  if (rc == FB_OK)
    rc = fb_bg_assign_causality(fb_model_graph(m), &err);
  /* The graph names the element or bond at fault; the model knows where
   * the file wrote it. */
  if (rc != FB_OK)
    fb_model_blame(m, &err);
  if (rc == FB_OK) {
    const fb_bg *g = fb_model_graph(m);
    table_widths w = measure(g);
    for (size_t i = 0; i < fb_bg_nbonds(g); ++i)
      print_bond(g, i, &w);
    rc = cli_flush_stdout(&err);
  }
  fb_model_free(&m);
  return cli_report(rc, &err);
}

int cli_cmd_causality(int argc, char **argv)
{
  enum { OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {[OPT_HELP] = {"--help", "-h", 0, NULL}};
  const char *model_path;
  int code;
  if (!cli_parse_model_command(argc, argv, opts, NOPTS, causality_usage, &model_path, &code))
    return code;
  return run(model_path);
}
