/* SPDX-License-Identifier: BSD-3-Clause */
/* One loader for diagram, causality and eig (see graph_input.h). */
#include "graph_input.h"

#include <string.h>

#include "../io/input_kind.h"
#include "cli.h"

int cli_system_option(const char *cmd, const char *text, fb_system *sys)
{
  static const char *const names[] = {"rigid", "flexible"};
  *sys = FB_SYSTEM_RIGID;
  if (!text)
    return CLI_EXIT_OK;
  int which = 0;
  int code = cli_choice(cmd, "--system", text, names, 2, &which);
  *sys = which == 1 ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID;
  return code;
}

static int load_model(const char *path, int system_given, cli_graph_input *in, fb_err *err)
{
  int rc = fb_model_load(path, &in->model, err);
  cli_report_warnings(in->model);
  if (rc == FB_OK && system_given) {
    rc = fb_err_set(err, FB_EINVAL,
                    "%s: --system chooses the hull of a vehicle scenario; this is a model "
                    "file (top-level key 'model')",
                    path);
    fb_err_set_source(err, FB_SOURCE_OPTION, "--system");
  }
  if (rc != FB_OK)
    return rc;
  in->graph = fb_model_graph(in->model);
  in->probes = fb_model_probes(in->model, &in->nprobes);
  in->opts = *fb_model_sim_opts(in->model);
  in->name = fb_model_name(in->model);
  return FB_OK;
}

static int load_scenario(const char *path, fb_system sys, cli_graph_input *in, fb_err *err)
{
  int rc = fb_scenario_load(path, &in->scenario, err);
  if (rc == FB_OK && (rc = fb_vehicle_graph(in->scenario, sys, &in->graph, &in->vehicle_probes,
                                            &in->nprobes, err)) != FB_OK)
    fb_scenario_locate(in->scenario, err); /* an error about one of its values */
  if (rc != FB_OK)
    return rc;
  in->probes = in->vehicle_probes;
  fb_vehicle_sim_opts(in->scenario, &in->opts);
  in->name = fb_bg_name(in->graph);
  return FB_OK;
}

int cli_graph_input_load(const char *path, fb_system sys, int system_given, cli_graph_input *in,
                         fb_err *err)
{
  memset(in, 0, sizeof *in);
  int rc = fb_input_kind_of(path) == FB_INPUT_SCENARIO
               ? load_scenario(path, sys, in, err)
               : load_model(path, system_given, in, err);
  if (rc != FB_OK)
    cli_graph_input_free(in);
  return rc;
}

int cli_graph_input_blame(const cli_graph_input *in, fb_err *err)
{
  /* A vehicle's graph is not written in a file: its messages name the
   * element and bond, which is all there is to locate. */
  if (in->model)
    return fb_model_blame(in->model, err);
  return err ? err->code : FB_OK;
}

void cli_graph_input_free(cli_graph_input *in)
{
  if (in->scenario) {
    fb_vehicle_probes_free(&in->vehicle_probes, in->nprobes);
    fb_bg_free(&in->graph);
    fb_scenario_free(&in->scenario);
  }
  fb_model_free(&in->model);
  memset(in, 0, sizeof *in);
}
