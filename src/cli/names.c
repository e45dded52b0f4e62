/* SPDX-License-Identifier: BSD-3-Clause */
/* What the command's outputs call things: the systems, the scenario, and
 * the files of run's figures and diagrams, which run writes and report.md
 * links to. One place, so that no command reaches into another for them. */
#include <math.h>
#include <stdio.h>

#include "cli.h"

const char *cli_system_label(fb_system sys)
{
  return sys == FB_SYSTEM_RIGID ? "System 1 (rigid hull)" : "System 2 (flexible hull)";
}

const char *cli_scenario_name(const fb_scenario *s)
{
  return s->name ? s->name : s->path ? s->path : "scenario";
}

void cli_run_figure_file(const fb_output_spec *o, char *buf, size_t size)
{
  if (o->figure > 0)
    snprintf(buf, size, "fig%02d_%s.png", o->figure, o->name);
  else
    snprintf(buf, size, "fig_%s.png", o->name);
}

void cli_run_figure_window(const fb_output_spec *o, const fb_result *r, double *t_min,
                           double *t_max)
{
  /* fb_plot_opts: t_min >= t_max means the result's span. */
  *t_min = *t_max = 0;
  size_t n = fb_result_nsamples(r);
  if (!(o->window[0] < o->window[1]) || n == 0)
    return;
  double lo = fmax(o->window[0], fb_result_row(r, 0)[0]);
  double hi = fmin(o->window[1], fb_result_row(r, n - 1)[0]);
  if (lo < hi) {
    *t_min = lo;
    *t_max = hi;
  }
}

/* The paper's Figs. 5 and 6 of system sys: its multibond graph and its
 * block diagram, "figNN_KIND_systemN.png". */
static const struct {
  int number;
  cli_diagram_kind kind;
  const char *what;
} diagram_kinds[] = {{5, CLI_DIAGRAM_BOND_GRAPH, "bond_graph"},
                     {6, CLI_DIAGRAM_BLOCKS, "block_diagram"}};
_Static_assert(sizeof diagram_kinds / sizeof diagram_kinds[0] == CLI_RUN_NDIAGRAMS,
               "one row per diagram");

void cli_run_diagram_file(size_t k, fb_system sys, char *buf, size_t size)
{
  snprintf(buf, size, "fig%02d_%s_system%d.png", diagram_kinds[k].number, diagram_kinds[k].what,
           (int)sys);
}

cli_diagram_kind cli_run_diagram_kind(size_t k)
{
  return diagram_kinds[k].kind;
}
