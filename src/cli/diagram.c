/* flexbond diagram: the model's block diagram as Graphviz DOT, to a file
 * (written atomically) or to stdout. */
#include <stdio.h>

#include "flexbond/bd.h"
#include "flexbond/io.h"
#include "flexbond/model.h"

#include "cli.h"

static const char diagram_usage[] =
    "usage: flexbond diagram MODEL.yaml [-o FILE.dot]\n"
    "\n"
    "Builds the model's block diagram (probes included) and writes it as\n"
    "Graphviz DOT, e.g. for `dot -Tsvg FILE.dot > FILE.svg`.\n"
    "\n"
    "options:\n"
    "  -o, --output FILE     write to FILE instead of stdout\n"
    "  -h, --help            this text\n";

static int write_dot_file(const fb_bd *bd, const char *path, fb_err *err)
{
  fb_out *out = NULL;
  int rc = fb_out_open(path, &out, err);
  if (rc != FB_OK)
    return rc;
  rc = fb_bd_write_dot(bd, fb_out_stream(out), err);
  /* A signal meanwhile: the file stays as it was. */
  if (rc == FB_OK)
    rc = cli_check_interrupt(err);
  if (rc != FB_OK) {
    fb_out_abort(&out);
    return rc;
  }
  return fb_out_commit(&out, err);
}

static int run(const char *model_path, const char *out_path)
{
  fb_err err;
  fb_err_clear(&err);
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  int rc = fb_model_load(model_path, &m, &err);
  if (rc == FB_OK) {
    size_t nprobes = 0;
    const fb_probe_spec *probes = fb_model_probes(m, &nprobes);
    rc = fb_bd_build(fb_model_graph(m), probes, nprobes, &bd, &err);
    fb_model_blame(m, &err); /* a causality error: at its element's or bond's line */
  }
  if (rc == FB_OK && out_path)
    rc = write_dot_file(bd, out_path, &err);
  if (rc == FB_OK && !out_path) {
    rc = fb_bd_write_dot(bd, stdout, &err);
    if (rc == FB_OK)
      rc = cli_flush_stdout(&err);
  }
  fb_bd_free(&bd);
  fb_model_free(&m);
  return cli_report(rc, &err);
}

int cli_cmd_diagram(int argc, char **argv)
{
  enum { OPT_OUT, OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {
      [OPT_OUT] = {"--output", "-o", 1, NULL},
      [OPT_HELP] = {"--help", "-h", 0, NULL},
  };
  const char *model_path;
  int code;
  if (!cli_parse_model_command(argc, argv, opts, NOPTS, diagram_usage, &model_path, &code))
    return code;
  const char *out_path = opts[OPT_OUT].value;
  if (out_path && !*out_path)
    return cli_usage_error(argv[0], "empty output file name");
  return run(model_path, out_path);
}
