/* SPDX-License-Identifier: BSD-3-Clause */
/* The input of the commands that look at a graph (diagram, causality,
 * eig): a model file or a vehicle scenario file, loaded into one bond
 * graph with its probes and solver settings, by one code path. */
#ifndef FLEXBOND_CLI_GRAPH_INPUT_H
#define FLEXBOND_CLI_GRAPH_INPUT_H

#include <stddef.h>

#include "flexbond/bg.h"
#include "flexbond/model.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

/* What cli_graph_input_load made. Free it with cli_graph_input_free. */
typedef struct cli_graph_input {
  fb_model *model;             /* owned: the model, for a model file; else NULL */
  fb_scenario *scenario;       /* owned: the scenario, for a scenario file; else NULL */
  fb_bg *graph;                /* the graph: the model's (borrowed from model) or the
                                  vehicle's (owned) */
  const fb_probe_spec *probes; /* the model's or the vehicle's every probe */
  size_t nprobes;
  fb_probe_spec *vehicle_probes; /* owned: probes of a scenario (fb_vehicle_probes_free) */
  fb_sim_opts opts;              /* solver settings: pointers inside borrowed from model */
  const char *name;              /* the graph's name (borrowed) */
} cli_graph_input;

/* Parses the --system option's text (NULL: not given, rigid) into *sys;
 * a usage error of command cmd otherwise. Returns the exit code. */
int cli_system_option(const char *cmd, const char *text, fb_system *sys);

/* Loads path into *in: a vehicle scenario (a top-level key `scenario`,
 * io/input_kind.h) is assembled for system sys (fb_vehicle_graph), any
 * other file is loaded as a model (fb_model_load), whose loader reports
 * what is wrong with it. system_given: --system was on the command line,
 * which a model file has no use for (FB_EINVAL, source the option). *in is
 * cleared first; on failure it holds nothing. */
int cli_graph_input_load(const char *path, fb_system sys, int system_given, cli_graph_input *in,
                         fb_err *err);

/* For an error raised by the graph after loading (causality, the block
 * diagram's build): with a model, the file's line and key of the element
 * or bond at fault (fb_model_blame). Returns err->code. */
int cli_graph_input_blame(const cli_graph_input *in, fb_err *err);

void cli_graph_input_free(cli_graph_input *in);

#endif
