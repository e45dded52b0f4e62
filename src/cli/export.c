/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond export: the vehicle of a scenario, assembled (fb_vehicle_build)
 * and written as the linear descriptor system of its block diagram
 * (fb_bd_descriptor, flexbond/bd.h):
 *     E x' = A x + Bu u(t) + f,      y = C x + D u,
 * as Matrix Market files and a model.json that names the variables, the
 * inputs and the outputs (docs/export.md). The inputs are each wheel's
 * road height and road rate, u = [h_<corner> ..., hdot_<corner> ...]. The
 * model sees only the rates (each tire spring's state integrates its
 * wheel's rate), so the height columns of Bu and D are zero. */
#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/vehicle.h"

#include "cli.h"

static const char export_usage[] =
    "usage: flexbond export SCENARIO.yaml -o DIR [--system rigid|flexible]\n"
    "\n"
    "Writes the vehicle of the scenario, assembled, as the linear descriptor\n"
    "system of its block diagram\n"
    "    E x' = A x + Bu u(t) + f,   y = C x + D u\n"
    "  DIR/E.mtx A.mtx Bu.mtx f.mtx C.mtx D.mtx  Matrix Market, coordinate real\n"
    "                          general (f is an n x 1 matrix)\n"
    "  DIR/model.json          the variables x (states first; which are\n"
    "                          differential), the inputs, the outputs and\n"
    "                          which rows of C make each\n"
    "Inputs u = [h_LF h_RF ..., hdot_LF hdot_RF ...], in corner order: each wheel's\n"
    "road height (m; its columns are zero: the tire springs integrate the\n"
    "rates) and road rate (m/s). f holds gravity and the payload. Outputs: the\n"
    "scenario's; a power output is the product of its two rows of C.\n"
    "Unilateral tires (wheel.tire_contact) are exported in contact, their linear\n"
    "branch. A nonlinear law (a damper table) makes the model a linearisation at\n"
    "the static equilibrium (every variable a deviation, f zero; model.json says\n"
    "\"linearised\": true). DIR is created if missing; nothing is written if the\n"
    "export fails.\n"
    "\n"
    "options:\n"
    "  -o, --output DIR          output directory (required)\n"
    "  --system rigid|flexible   hull model (default flexible: System 2)\n"
    "  --strict                  refuse implausible values instead of warning\n"
    "  -h, --help                this text\n";

static const char *const system_choices[] = {"rigid", "flexible"};
static const fb_system systems[] = {FB_SYSTEM_RIGID, FB_SYSTEM_FLEXIBLE};

/* What the command writes. */
typedef struct export_model {
  const fb_scenario *s;
  fb_system sys;
  fb_bd *bd;
  fb_descriptor *ds;
  fb_mat *bu, *d;     /* B and D with the height columns */
  size_t *rate_input; /* per corner: descriptor input of its wheel's rate */
  size_t ninputs;     /* 2 ncorners: u = [heights, rates]; wheel c's rate is
                         column ncorners + c */
} export_model;

/* The descriptor's input that is wheel c's road velocity source. */
static int find_rate_inputs(export_model *m, fb_err *err)
{
  const size_t nc = m->s->ncorners;
  m->ninputs = 2 * nc;
  m->rate_input = calloc(nc + 1, sizeof *m->rate_input);
  if (!m->rate_input)
    return fb_err_set(err, FB_ENOMEM, "export: out of memory");
  const int rc = fb_vehicle_rate_inputs(m->s, m->ds, m->rate_input, err);
  return rc ? fb_err_prefix(err, "export: ") : FB_OK;
}

/* Bu (n x 12) from B, D (rows of C x 12) zero. */
static int widen_inputs(export_model *m, fb_err *err)
{
  const fb_descriptor *ds = m->ds;
  const size_t nc = m->s->ncorners;
  size_t *to = malloc(nc * sizeof *to);
  if (!to)
    return fb_err_set(err, FB_ENOMEM, "export: out of memory");
  for (size_t c = 0; c < nc; ++c)
    to[m->rate_input[c]] = nc + c;
  const size_t nnz = fb_mat_nnz(ds->B) + 1;
  size_t *rows = malloc(nnz * sizeof *rows), *cols = malloc(nnz * sizeof *cols);
  double *vals = malloc(nnz * sizeof *vals);
  int rc = rows && cols && vals ? FB_OK : fb_err_set(err, FB_ENOMEM, "export: out of memory");
  if (!rc) {
    /* B's entries, moved to the rate columns. */
    const size_t n = fb_mat_triplets(ds->B, rows, cols, vals);
    for (size_t k = 0; k < n; ++k)
      cols[k] = to[cols[k]];
    rc = fb_mat_new_triplets(ds->n, m->ninputs, n, rows, cols, vals, &m->bu, err);
  }
  if (!rc)
    rc = fb_mat_new_triplets(ds->nrows_c, m->ninputs, 0, NULL, NULL, NULL, &m->d, err);
  free(to);
  free(rows);
  free(cols);
  free(vals);
  return rc;
}

static int build_model(export_model *m, fb_bg **graph, fb_err *err)
{
  int rc = fb_vehicle_build(m->s, m->sys, graph, &m->bd, err);
  if (!rc)
    rc = fb_vehicle_diagram_descriptor(m->bd, &m->ds, err);
  if (!rc)
    rc = find_rate_inputs(m, err);
  if (!rc)
    rc = widen_inputs(m, err);
  return rc;
}

/* ---- model.json, written by hand (strings: cli_json_string). */

static const char *variable_kind(const export_model *m, size_t i)
{
  if (i >= m->ds->nstates)
    return "algebraic";
  switch (fb_bd_state_kind(m->bd, i)) {
  case FB_STATE_MOMENTUM: return "momentum";
  case FB_STATE_DISPLACEMENT: return "displacement";
  case FB_STATE_PROBE: return "probe integral";
  }
  return "state";
}

static void write_variables(FILE *fp, const export_model *m)
{
  const fb_descriptor *ds = m->ds;
  fputs("  \"variables\": [\n", fp);
  for (size_t i = 0; i < ds->n; ++i) {
    fputs("    {\"name\": ", fp);
    cli_json_string(fp, ds->var_names[i]);
    fprintf(fp, ", \"differential\": %s, \"kind\": \"%s\"}%s\n",
            i < ds->nstates ? "true" : "false", variable_kind(m, i), i + 1 < ds->n ? "," : "");
  }
  fputs("  ],\n", fp);
}

static void write_inputs(FILE *fp, const export_model *m)
{
  fputs("  \"inputs\": [\n", fp);
  const size_t nc = m->s->ncorners;
  for (size_t c = 0; c < nc; ++c) {
    const char *name = m->s->corner[c].name;
    char input[FB_ERR_KEY_MAX];
    snprintf(input, sizeof input, "h_%s", name);
    fputs("    {\"name\": ", fp);
    cli_json_string(fp, input);
    fputs(", \"wheel\": ", fp);
    cli_json_string(fp, name);
    fputs(", \"quantity\": \"road height\", \"unit\": \"m\", \"enters\": false},\n", fp);
  }
  for (size_t c = 0; c < nc; ++c) {
    const size_t j = m->rate_input[c];
    const char *name = m->s->corner[c].name;
    char input[FB_ERR_KEY_MAX];
    snprintf(input, sizeof input, "hdot_%s", name);
    fputs("    {\"name\": ", fp);
    cli_json_string(fp, input);
    fputs(", \"wheel\": ", fp);
    cli_json_string(fp, name);
    fputs(", \"quantity\": \"road vertical velocity\", \"unit\": \"m/s\", \"enters\": true, "
          "\"source\": ",
          fp);
    cli_json_string(fp, m->ds->input_names[j]);
    fprintf(fp, ", \"defines_variable\": %zu}%s\n", m->ds->input_var[j], c + 1 < nc ? "," : "");
  }
  fputs("  ],\n", fp);
}

static void write_outputs(FILE *fp, const export_model *m)
{
  const fb_descriptor *ds = m->ds;
  fputs("  \"outputs\": [\n", fp);
  for (size_t o = 0; o < ds->noutputs; ++o) {
    const size_t r = ds->output_row[o];
    fputs("    {\"name\": ", fp);
    cli_json_string(fp, fb_bd_output_name(m->bd, o));
    fputs(", \"unit\": ", fp);
    cli_json_string(fp, fb_bd_output_unit(m->bd, o));
    if (ds->output_is_product[o])
      fprintf(fp,
              ", \"rows\": [%zu, %zu], \"product\": true, \"row_quantities\": [\"effort\", "
              "\"flow\"]}",
              r, r + 1);
    else
      fprintf(fp, ", \"rows\": [%zu], \"product\": false}", r);
    fputs(o + 1 < ds->noutputs ? ",\n" : "\n", fp);
  }
  fputs("  ],\n", fp);
}

static const char *const notes[] = {
    "Indices (variables, rows of C, defines_variable) are 0-based: add 1 for Matrix Market "
    "and Octave.",
    "E is the identity at the differential variables (the first ndifferential) and zero "
    "elsewhere; the other rows are algebraic relations. The pencil (A, E) has index 1.",
    "x = 0 is every spring at free length and every mass at rest; f holds the weights of "
    "the masses and the payload (gravity switched on at t = 0, the paper's protocol).",
    "The road heights h_* do not enter the model: each tire spring's state integrates its "
    "wheel's road rate, so their columns of Bu and D are zero.",
    "D is zero: every output reads descriptor variables (a road rate is a variable defined "
    "by its row 0 = -x_k + hdot).",
    "An output with product: true is the product (C[rows[0]] x) * (C[rows[1]] x) of the "
    "effort and the flow of its bond (a dissipated power); the other outputs are C[row] x.",
};

/* Said only when there are such variables (System 1's torsion). */
static const char probe_note[] =
    "Differential variables of kind 'probe integral' are kept by integrating probes (System "
    "1's torsion angle integrates the hull's velocities); they feed nothing back (zero "
    "eigenvalues).";

static int has_probe_integrals(const export_model *m)
{
  for (size_t i = 0; i < m->ds->nstates; ++i)
    if (fb_bd_state_kind(m->bd, i) == FB_STATE_PROBE)
      return 1;
  return 0;
}

/* model.json (a cli_writer over an export_model). */
static void write_model_json(FILE *fp, const void *ctx)
{
  const export_model *m = ctx;
  const fb_descriptor *ds = m->ds;
  fputs("{\n  \"format\": \"flexbond descriptor\",\n  \"version\": 1,\n  \"scenario\": ", fp);
  cli_json_string(fp, m->s->name ? m->s->name : "");
  fprintf(fp,
          ",\n  \"system\": \"%s\",\n"
          "  \"form\": \"E x' = A x + Bu u(t) + f,  y = C x + D u\",\n"
          "  \"files\": {\"E\": \"E.mtx\", \"A\": \"A.mtx\", \"Bu\": \"Bu.mtx\", \"f\": "
          "\"f.mtx\", \"C\": \"C.mtx\", \"D\": \"D.mtx\"},\n"
          "  \"n\": %zu,\n  \"ndifferential\": %zu,\n  \"ninputs\": %zu,\n"
          "  \"noutputs\": %zu,\n  \"output_rows\": %zu,\n  \"linearised\": %s,\n",
          m->sys == FB_SYSTEM_RIGID ? "rigid" : "flexible", ds->n, ds->nstates, m->ninputs,
          ds->noutputs, ds->nrows_c, ds->linearised ? "true" : "false");
  write_variables(fp, m);
  write_inputs(fp, m);
  write_outputs(fp, m);
  fputs("  \"notes\": [\n", fp);
  for (size_t i = 0; i < sizeof notes / sizeof notes[0]; ++i) {
    fputs(i ? ",\n    " : "    ", fp);
    cli_json_string(fp, notes[i]);
  }
  if (has_probe_integrals(m)) {
    fputs(",\n    ", fp);
    cli_json_string(fp, probe_note);
  }
  fputs("\n  ]\n}\n", fp);
}

/* ---- Writing. */

/* A Matrix Market file (a cli_writer over an fb_mat). */
static void write_mtx(FILE *fp, const void *a)
{
  fb_mat_print_mtx(fp, a);
}

static int write_matrix(cli_outdir *od, const char *name, const fb_mat *a, fb_err *err)
{
  return cli_outdir_write(od, name, write_mtx, a, err);
}

static int write_all(cli_outdir *od, const export_model *m, fb_err *err)
{
  const struct {
    const char *name;
    const fb_mat *a;
  } files[] = {{"E.mtx", m->ds->E}, {"A.mtx", m->ds->A}, {"Bu.mtx", m->bu},
               {"f.mtx", m->ds->f}, {"C.mtx", m->ds->C}, {"D.mtx", m->d}};
  int rc = FB_OK;
  for (size_t i = 0; rc == FB_OK && i < sizeof files / sizeof files[0]; ++i)
    rc = write_matrix(od, files[i].name, files[i].a, err);
  if (rc == FB_OK)
    rc = cli_outdir_write(od, "model.json", write_model_json, m, err);
  return rc;
}

static int run(const char *path, fb_system sys, const char *dir, int strict)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  fb_bg *graph = NULL;
  export_model m = {.sys = sys};
  int rc = cli_scenario_load(path, strict, &s, &err);
  assert(rc != FB_OK || s); /* for the static analyzer: s is set on success */
  /* A tire model that names its branch in contact (a unilateral tire's,
   * at rest) is exported as that branch (fb_scenario_tires_in_contact). */
  if (s)
    fb_scenario_tires_in_contact(s);
  m.s = s;
  /* The directory is held (locked) from here to the end. */
  cli_outdir od;
  const int opened = rc == FB_OK && (rc = cli_outdir_open(&od, dir, "export", &err)) == FB_OK;
  if (rc == FB_OK)
    rc = build_model(&m, &graph, &err);
  if (rc == FB_OK)
    rc = write_all(&od, &m, &err);
  if (opened)
    rc = cli_outdir_close(&od, rc, &err);
  if (rc == FB_OK) {
    printf("%s: wrote %s: %zu variables (%zu differential), %zu inputs, %zu outputs (%zu rows "
           "of C)%s\n",
           s->name ? s->name : path, dir, m.ds->n, m.ds->nstates, m.ninputs, m.ds->noutputs,
           m.ds->nrows_c,
           m.ds->linearised ? "; a nonlinear law made it a linearisation at the static "
                              "equilibrium (every variable a deviation, f zero)"
                            : "");
    rc = cli_flush_stdout(&err);
  }
  fb_mat_free(&m.bu);
  fb_mat_free(&m.d);
  fb_descriptor_free(&m.ds);
  free(m.rate_input);
  fb_bd_free(&m.bd);
  fb_bg_free(&graph);
  rc = cli_report_scenario(s, rc, &err);
  fb_scenario_free(&s);
  return rc;
}

int cli_cmd_export(int argc, char **argv)
{
  enum { OPT_SYSTEM, OPT_OUT, OPT_STRICT, OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {[OPT_SYSTEM] = {"--system", NULL, 1, NULL},
                            [OPT_OUT] = {"--output", "-o", 1, NULL},
                            [OPT_STRICT] = {"--strict", NULL, 0, NULL},
                            [OPT_HELP] = {"--help", "-h", 0, NULL}};
  const char *path;
  int rc;
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, export_usage, "SCENARIO", &path, &rc))
    return rc;
  int choice = 1; /* flexible */
  if (opts[OPT_SYSTEM].value)
    rc = cli_choice(argv[0], "--system", opts[OPT_SYSTEM].value, system_choices,
                    sizeof system_choices / sizeof system_choices[0], &choice);
  if (rc != CLI_EXIT_OK)
    return rc;
  if (!opts[OPT_OUT].value)
    return cli_usage_error(argv[0], "missing output directory (-o DIR)");
  return run(path, systems[choice], opts[OPT_OUT].value, opts[OPT_STRICT].value != NULL);
}
