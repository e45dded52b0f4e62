/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond diagram: a model's or a vehicle's block diagram or multibond
 * graph (the paper's Figs. 6 and 5) as Graphviz DOT, to a file (written
 * atomically) or to stdout, or drawn by Graphviz into SVG or PNG. */
#include <stdio.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"

#include "../io/graphviz.h"
#include "cli.h"
#include "graph_input.h"

static const char diagram_usage[] =
    "usage: flexbond diagram FILE.yaml [--system rigid|flexible]\n"
    "                        [--kind block-diagram|bond-graph|flat] [-o FILE]\n"
    "\n"
    "Draws the graph of FILE, a model file or a vehicle scenario file (a\n"
    "scenario's vehicle is assembled for --system, default rigid), as\n"
    "Graphviz DOT (docs/diagrams.md):\n"
    "  block-diagram  the block diagram in two levels: one block per\n"
    "                 subsystem, then each subsystem's blocks (the paper's\n"
    "                 Fig. 6); the default for a scenario\n"
    "  bond-graph     the multibond graph with its causal strokes (Fig. 5)\n"
    "  flat           every block of the block diagram in one level; the\n"
    "                 default for a model file\n"
    "The output's extension gives its type: .svg or .png the picture\n"
    "Graphviz's `dot` draws, any other DOT. Without -o, DOT goes to\n"
    "stdout.\n"
    "\n"
    "options:\n"
    "  --system S            rigid (System 1) or flexible (System 2), scenarios only\n"
    "  --kind K              block-diagram, bond-graph or flat\n"
    "  -o, --output FILE     write to FILE (.svg, .png: drawn; else DOT)\n"
    "  -h, --help            this text\n";

/* What the DOT writer draws. */
typedef struct diagram_src {
  fb_bg *graph;
  fb_bd *bd; /* NULL for the bond graph */
  cli_diagram_kind kind;
} diagram_src;

/* An fb_graphviz_fn: the DOT of the diagram; a signal meanwhile fails
 * it, so that nothing is committed. */
static int write_diagram(FILE *fp, const void *ctx, fb_err *err)
{
  const diagram_src *d = ctx;
  int rc;
  switch (d->kind) {
  case CLI_DIAGRAM_BOND_GRAPH: rc = fb_bg_write_dot(d->graph, fp, err); break;
  case CLI_DIAGRAM_BLOCKS: rc = fb_bd_write_dot_hierarchy(d->bd, fp, err); break;
  default: rc = fb_bd_write_dot(d->bd, fp, err); break;
  }
  return rc == FB_OK ? cli_check_interrupt(err) : rc;
}

/* Causality for the bond graph, the block diagram for the others. */
static int prepare(diagram_src *d, const fb_probe_spec *p, size_t np, fb_err *err)
{
  if (d->kind == CLI_DIAGRAM_BOND_GRAPH)
    return fb_bg_assign_causality(d->graph, err);
  return fb_bd_build(d->graph, p, np, &d->bd, err);
}

int cli_diagram_file(fb_bg *g, const fb_probe_spec *p, size_t np, cli_diagram_kind kind,
                     const char *path, fb_err *err)
{
  diagram_src d = {g, NULL, kind};
  int rc = prepare(&d, p, np, err);
  if (rc == FB_OK)
    rc = fb_graphviz_write(write_diagram, &d, fb_graphviz_format_of(path), path, err);
  fb_bd_free(&d.bd);
  return rc;
}

static int run(const char *path, fb_system sys, int system_given, int kind, int kind_given,
               const char *out_path)
{
  fb_err err;
  fb_err_clear(&err);
  cli_graph_input in;
  int rc = cli_graph_input_load(path, sys, system_given, &in, &err);
  /* A model keeps its flat diagram, as before the two-level one existed. */
  diagram_src d = {in.graph, NULL, CLI_DIAGRAM_FLAT};
  if (kind_given)
    d.kind = (cli_diagram_kind)kind;
  else if (in.scenario)
    d.kind = CLI_DIAGRAM_BLOCKS;
  if (rc == FB_OK) {
    rc = prepare(&d, in.probes, in.nprobes, &err);
    cli_graph_input_blame(&in, &err); /* a causality error: at its element's or bond's line */
  }
  if (rc == FB_OK && out_path)
    rc = fb_graphviz_write(write_diagram, &d, fb_graphviz_format_of(out_path), out_path, &err);
  if (rc == FB_OK && !out_path) {
    rc = write_diagram(stdout, &d, &err);
    if (rc == FB_OK)
      rc = cli_flush_stdout(&err);
  }
  fb_bd_free(&d.bd);
  cli_graph_input_free(&in);
  return cli_report(rc, &err);
}

int cli_cmd_diagram(int argc, char **argv)
{
  enum { OPT_OUT, OPT_SYSTEM, OPT_KIND, OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {
      [OPT_OUT] = {"--output", "-o", 1, NULL},
      [OPT_SYSTEM] = {"--system", NULL, 1, NULL},
      [OPT_KIND] = {"--kind", NULL, 1, NULL},
      [OPT_HELP] = {"--help", "-h", 0, NULL},
  };
  const char *path;
  int code;
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, diagram_usage, "FILE", &path, &code))
    return code;
  const char *out_path = opts[OPT_OUT].value;
  if (out_path && !*out_path)
    return cli_usage_error(argv[0], "empty output file name");
  fb_system sys;
  code = cli_system_option(argv[0], opts[OPT_SYSTEM].value, &sys);
  if (code != CLI_EXIT_OK)
    return code;
  /* In cli_diagram_kind order. */
  static const char *const kinds[] = {"flat", "block-diagram", "bond-graph"};
  int kind = CLI_DIAGRAM_FLAT;
  if (opts[OPT_KIND].value && (code = cli_choice(argv[0], "--kind", opts[OPT_KIND].value, kinds,
                                                 3, &kind)) != CLI_EXIT_OK)
    return code;
  return run(path, sys, opts[OPT_SYSTEM].value != NULL, kind, opts[OPT_KIND].value != NULL,
             out_path);
}
