/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of the YAML model loader (flexbond/model.h): a table of bad models
 * with the status and the "FILE:LINE:" + key/phrase each must report, and
 * good models whose graphs, parameters, subsystem instances, probes and
 * solver settings are checked, partly through the block diagram built
 * from them (x' at a known state against hand calculation). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "flexbond/bd.h"
#include "flexbond/model.h"
#include "flexbond/sim.h"

#include "check.h"
#include "tmpdir.h"

/* ---- Bad models. */

typedef struct bad_case {
  const char *text;
  int code;
  const char *where;   /* "bad.yaml:LINE:" the message must contain */
  const char *phrase;  /* and this key path or phrase */
  const char *phrase2; /* and this one (may be NULL) */
} bad_case;

#define HEAD "model: m\n"

static const bad_case bad_cases[] = {
    /* YAML syntax: libfyaml's first diagnostic with its line:col. */
    {HEAD "elements: [\n  {name: a, type: 0}\n", FB_EPARSE, "bad.yaml:4:", "YAML:", NULL},
    {HEAD "model: n\nelements: []\n", FB_EPARSE, "bad.yaml:2:", "duplicate key", NULL},
    {HEAD "elements:\n\t- {name: a, type: 0}\n", FB_EPARSE, "bad.yaml:3:", "YAML:", NULL},
    {"", FB_EPARSE, "bad.yaml:1:1:", "empty", NULL},
    {HEAD "elements: []\n---\nmodel: other\n", FB_EPARSE, "bad.yaml:3:1:", "second document",
     NULL},
    /* Aliases: each libfyaml message gets its hint, the alias its name. */
    /* Text of scalars: a NUL anywhere, control characters in one-line
     * text (C0, DEL, C1) and keys; integers beyond 2^53; hexadecimal. */
    {HEAD "parameters: {k: \"5\\0junk\"}\nelements: []\n", FB_EPARSE,
     "bad.yaml:2:", "parameters.k: the value has a NUL (\\0)", NULL},
    {HEAD "parameters: {\"k\\0x\": 5}\nelements: []\n", FB_EPARSE,
     "bad.yaml:2:", "parameters: a key has a NUL", NULL},
    {HEAD "subsystems:\n  \"s\\tt\": {elements: []}\nelements: []\n", FB_EPARSE,
     "bad.yaml:3:", "subsystems: a key has a tab", NULL},
    {HEAD "elements:\n  - {name: J, type: 1}\n  - {name: M, type: I, m: 1}\nbonds:\n"
          "  - {name: b1, from: J, to: M}\nprobes:\n  - {flow: b1, unit: \"m\\u009b2J\"}\n",
     FB_EPARSE, "bad.yaml:8:", "probes[0].unit: has control character 0x9b", NULL},
    {HEAD "elements:\n  - {name: J, type: 1}\n  - {name: M, type: I, m: 1}\nbonds:\n"
          "  - {name: b1, from: \"J\\r\", to: M}\n",
     FB_EPARSE, "bad.yaml:6:", "bonds[0].from: has a carriage return", NULL},
    /* Two '' escapes in a row, which libfyaml 0.7 decodes as three quotes:
     * as a value, as a key, and past the escapes that make it leak. */
    {"model: 'x''''y'\nelements: []\n", FB_EPARSE, "bad.yaml:1:", "model: the YAML library",
     "decodes 5 bytes where it recorded 4"},
    {HEAD "parameters: {'k''''': 5}\nelements: []\n", FB_EPARSE,
     "bad.yaml:2:", "parameters: the YAML library", "write the text in double quotes"},
    {HEAD "elements: []\nprobes: [{flow: b, unit: 'm''''''''''''''''''''''s'}]\n", FB_EPARSE,
     "bad.yaml:3:", "probes[0].unit: the YAML library", NULL},
    {HEAD "elements: []\nsimulation: {max_steps: 9007199254740993}\n", FB_EINVAL,
     "bad.yaml:3:25:", "simulation.max_steps: the integer 9007199254740993 is beyond 2^53",
     NULL},
    {HEAD "parameters: {k: -000009007199254740993}\nelements: []\n", FB_EINVAL,
     "bad.yaml:2:", "parameters.k: the integer", "beyond 2^53"},
    {HEAD "parameters: {k: 0X1P4}\nelements: []\n", FB_EPARSE,
     "bad.yaml:2:17:", "parameters.k: '0X1P4' is not a decimal number", NULL},
    {"---\n", FB_EPARSE, "bad.yaml:1:1:", "the file is empty (no YAML document)", NULL},
    {HEAD "elements: *nope\n", FB_EPARSE, "bad.yaml:2:12:", "YAML: invalid alias '*nope'",
     "no anchor of that name"},
    {HEAD "parameters: &p {a: *p}\nelements: []\n", FB_EPARSE, "bad.yaml:2:21:",
     "YAML: cyclic reference detected '*p'", "inside the node its anchor marks"},
    {HEAD "elements: [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]\n",
     FB_EPARSE, "bad.yaml:2:", "YAML: Max depth (64) exceeded", "nest at most 64 levels deep"},
    {HEAD
     "parameters: {a: &a [*b], b: &b [*c], c: &c [*d], d: &d [*e], e: &e [*f], f: &f [*g],\n"
     "  g: &g [*h], h: &h [*i], i: &i [*j], j: &j [*k], k: &k [*l], l: &l [*m],\n"
     "  m: &m [*n], n: &n [*o], o: &o [*p], p: &p [*q], q: &q 1}\nelements: []\n",
     FB_EPARSE, "bad.yaml:", "YAML: max recursion depth exceeded", "define each anchor before"},
    /* Shape of the file. */
    {"- model\n- elements\n", FB_EPARSE, "bad.yaml:1:1:", "expected a model", NULL},
    {"elements: []\n", FB_EPARSE, "bad.yaml:1:", "missing required key 'model'", NULL},
    {HEAD "element: []\n", FB_EPARSE, "bad.yaml:2:1:", "element: unknown key 'element'",
     "did you mean 'elements'?"},
    {HEAD "elements: {a: 1}\n", FB_EPARSE, "bad.yaml:2:", "elements: expected a list", NULL},
    {HEAD "domain: translaton\nelements: []\n", FB_EPARSE,
     "bad.yaml:2:9:", "did you mean 'translation'?", NULL},
    /* Parameters. */
    {HEAD "parameters:\n  a: 2\n  b: a * cc\nelements: []\n", FB_EPARSE,
     "bad.yaml:4:6:", "parameters.b: expression 'a * cc'", "unknown name 'cc'"},
    {HEAD "parameters:\n  t: 1\nelements: []\n", FB_EPARSE,
     "bad.yaml:3:3:", "parameters.t: 't' is reserved", NULL},
    {HEAD "parameters:\n  a: 2 * t\nelements: []\n", FB_EPARSE,
     "bad.yaml:3:6:", "parameters.a:", NULL},
    /* Elements. */
    {HEAD "elements:\n  - {name: q, type: Q}\n", FB_EMODEL, "bad.yaml:3:", "elements[0].type",
     "unknown element type 'Q'; valid types: Se, Sf, I, C, R"},
    {HEAD "elements:\n  - {name: s, type: SE, value: 1}\n", FB_EMODEL,
     "bad.yaml:3:21:", "did you mean 'Se'?", NULL},
    {HEAD "elements:\n  - {name: Ms, type: I, m: -250}\n", FB_EINVAL,
     "bad.yaml:3:28:", "elements[0].m: must be > 0 (got -250)", NULL},
    {HEAD "elements:\n  - {name: K, type: C, c: 0}\n", FB_EINVAL,
     "bad.yaml:3:", "elements[0].c: must be > 0", NULL},
    {HEAD "elements:\n  - {name: D, type: R, r: -1}\n", FB_EINVAL,
     "bad.yaml:3:", "elements[0].r: must be >= 0", NULL},
    {HEAD "parameters: {z: 0}\nelements:\n  - {name: M, type: I, m: 1 / z}\n", FB_EINVAL,
     "bad.yaml:4:", "elements[0].m: expression '1 / z'", NULL},
    {HEAD "elements:\n  - {name: M, type: I, mm: 2}\n", FB_EPARSE,
     "bad.yaml:3:", "elements[0].mm: unknown key 'mm' (did you mean 'm'?)", NULL},
    {HEAD "elements:\n  - {name: M, type: I}\n", FB_EPARSE,
     "bad.yaml:3:", "elements[0]: missing required key 'm'", NULL},
    {HEAD "elements:\n  - {name: M, type: I, m: 1}\n  - {name: J, type: 1}\n"
          "  - {name: M, type: 0}\n",
     FB_EMODEL, "bad.yaml:5:", "elements[2].name: duplicate element name 'M'",
     "first defined at line 3"},
    {HEAD "elements:\n  - {name: a.b, type: 0}\n", FB_EPARSE,
     "bad.yaml:3:", "element name 'a.b'", NULL},
    {HEAD "elements:\n  - {name: M, type: I, ports: 2, matrix: [[1, 0.5], [0.4, 1]]}\n",
     FB_EINVAL, "bad.yaml:3:", "elements[0].matrix: matrix must be symmetric", NULL},
    {HEAD "elements:\n  - {name: M, type: I, ports: 2, matrix: [[1, 2], [2, 1]]}\n", FB_EINVAL,
     "bad.yaml:3:", "mass matrix must be positive definite", NULL},
    {HEAD "elements:\n  - {name: K, type: C, ports: 2, matrix: [[-1, 0], [0, 1]]}\n", FB_EINVAL,
     "bad.yaml:3:", "stiffness matrix must be positive semi-definite", NULL},
    {HEAD "elements:\n  - {name: K, type: C, matrix: [[1, 2]]}\n", FB_EMODEL,
     "bad.yaml:3:", "must be square (got 1x2)", NULL},
    {HEAD "elements:\n  - {name: K, type: C, ports: 3, matrix: [[2, 0], [0, 2]]}\n", FB_EMODEL,
     "bad.yaml:3:", "ports' dimensions add up to 3", NULL},
    {HEAD "elements:\n  - {name: K, type: C, matrix: [[2, 0], [0]]}\n", FB_EMODEL,
     "bad.yaml:3:", "elements[0].matrix[1]: row 2 has 1 entries", NULL},
    {HEAD "elements:\n  - {name: F, type: Se, dim: 2, value: [1, 2, 3]}\n", FB_EMODEL,
     "bad.yaml:3:", "elements[0].value: 3 values given for a source of dim 2", NULL},
    {HEAD "elements:\n  - {name: F, type: Se, value: {ramp: 1}}\n", FB_EPARSE,
     "bad.yaml:3:", "elements[0].value.ramp: unknown key 'ramp'", NULL},
    {HEAD "elements:\n  - {name: F, type: Se, value: {step: {time: 1}}}\n", FB_EPARSE,
     "bad.yaml:3:", "elements[0].value.step: missing required key 'after'", NULL},
    {HEAD "elements:\n  - {name: T, type: TF, ratio: 0}\n", FB_EINVAL,
     "bad.yaml:3:", "elements[0].ratio: must be nonzero", NULL},
    {HEAD "elements:\n  - {name: F, type: Sf, value: {table: {file: nope.csv, value: v}}}\n",
     FB_EIO, "bad.yaml:3:", "elements[0].value.table.file:", "nope.csv"},
    /* Bonds and port references. */
    {HEAD "elements:\n  - {name: J, type: 1}\nbonds:\n  - [J, X]\n", FB_EMODEL,
     "bad.yaml:5:", "bonds[0][1]: unknown element 'X'", NULL},
    {HEAD "elements:\n  - {name: Ms, type: I, m: 1}\n  - {name: J, type: 1}\nbonds:\n"
          "  - {from: J, to: Mss}\n",
     FB_EMODEL, "bad.yaml:6:", "bonds[0].to: unknown element 'Mss' (did you mean 'Ms'?)", NULL},
    {HEAD "elements:\n  - {name: T, type: TF, ratio: 2}\n  - {name: J, type: 1}\nbonds:\n"
          "  - [J, T.3]\n",
     FB_EMODEL, "bad.yaml:6:", "element 'T' has ports T.1 to T.2", NULL},
    {HEAD "elements:\n  - {name: J, type: 1}\n  - {name: K, type: 0}\nbonds:\n  - [J.1, K]\n",
     FB_EMODEL, "bad.yaml:6:", "junction 'J' is connected by its name alone", NULL},
    {HEAD "elements:\n  - {name: J, type: 1, dim: 2}\n  - {name: M, type: I, m: 1}\nbonds:\n"
          "  - {name: b, from: J, to: M}\n",
     FB_EMODEL, "bad.yaml:6:", "bonds[0]: ", NULL},
    {HEAD "elements:\n  - {name: J, type: 1}\n  - {name: K, type: 0}\nbonds:\n"
          "  - [J, K, b]\n  - [K, J, b]\n",
     FB_EMODEL, "bad.yaml:7:", "bonds[1][2]: duplicate bond name 'b'", NULL},
    {HEAD "elements:\n  - {name: J, type: 1}\nbonds:\n  - [J]\n", FB_EPARSE,
     "bad.yaml:5:", "bonds[0]: a bond list is [from, to]", NULL},
    {HEAD "elements:\n  - {name: J, type: 1}\n  - {name: K, type: 0}\nbonds:\n"
          "  - {from: J, to: K, domain: magnetic}\n",
     FB_EPARSE, "bad.yaml:6:", "bonds[0].domain: unknown domain 'magnetic'", NULL},
    /* Subsystems. */
    {HEAD "subsystems:\n  a:\n    elements:\n      - {name: x, type: b}\n  b:\n"
          "    elements:\n      - {name: y, type: a}\nelements: []\n",
     FB_EMODEL, "bad.yaml:8:25:", "subsystems.b.elements[0].type",
     "recursive subsystem definition: a -> b -> a"},
    {HEAD "subsystems:\n  a:\n    elements:\n      - {name: x, type: a}\nelements: []\n",
     FB_EMODEL, "bad.yaml:5:", "recursive subsystem definition: a -> a", NULL},
    {HEAD "subsystems:\n  I:\n    elements: []\nelements: []\n", FB_EMODEL,
     "bad.yaml:3:", "subsystem name 'I' is a built-in element type", NULL},
    {HEAD "subsystems:\n  corner:\n    parameters: {k: 1000}\n    elements:\n"
          "      - {name: K, type: C, k: k}\n      - {name: J, type: 1}\n"
          "    bonds: [[J, K]]\n    ports:\n      - {name: top, at: J}\n"
          "elements:\n  - {name: front, type: corner, parameters: {kk: 2}}\n",
     FB_EMODEL, "bad.yaml:12:",
     "elements[0].parameters.kk: subsystem 'corner' has no parameter "
     "'kk' (did you mean 'k'?)",
     NULL},
    {HEAD "subsystems:\n  corner:\n    parameters: {k: 1000}\n    elements:\n"
          "      - {name: K, type: C, k: k}\n      - {name: J, type: 1}\n"
          "    bonds: [[J, K]]\n    ports:\n      - {name: top, at: J}\n"
          "elements:\n  - {name: front, type: corner, parameters: {k: -5}}\n",
     FB_EINVAL, "bad.yaml:6:", "subsystems.corner.elements[0].k: must be > 0 (got -5)",
     "in instance 'front' at bad.yaml:12:"},
    {HEAD "subsystems:\n  corner:\n    elements:\n      - {name: J, type: 1}\n    ports:\n"
          "      - {name: top, at: J}\nelements:\n  - {name: front, type: corner}\n"
          "  - {name: J, type: 0}\nbonds:\n  - [front.topp, J]\n",
     FB_EMODEL, "bad.yaml:12:", "has no port 'topp' (did you mean 'top'?); ports: top", NULL},
    {HEAD "subsystems:\n  corner:\n    elements:\n      - {name: J, type: 1}\n    ports:\n"
          "      - {name: top, at: J}\nelements:\n  - {name: front, type: corner}\n"
          "  - {name: J, type: 0}\nbonds:\n  - [front, J]\n",
     FB_EMODEL, "bad.yaml:12:", "'front' is a subsystem instance", NULL},
    {HEAD "subsystems:\n  corner:\n    elements:\n      - {name: J, type: 1}\n    ports:\n"
          "      - {name: top, at: JJ}\nelements: []\n",
     FB_EMODEL, "bad.yaml:7:", "subsystems.corner.ports[0].at: unknown element 'JJ'", NULL},
    {HEAD "subsystems:\n  corner:\n    elements:\n      - {name: J, type: 1}\n    ports:\n"
          "      - {name: top, at: J, direction: sideways}\nelements: []\n",
     FB_EPARSE, "bad.yaml:7:", "direction must be 'in' or 'out'", NULL},
    {HEAD "subsystems:\n  inner:\n    parameters: {k: 1}\n"
          "    elements: [{name: K, type: C, k: k}]\n  outer:\n    parameters: {kk: 1}\n"
          "    elements: [{name: w, type: inner, parameters: {k: kk}}]\n"
          "elements:\n  - {name: o, type: outer, parameters: {kk: -1}}\n",
     FB_EINVAL, "bad.yaml:5:", "subsystems.inner.elements[0].k: must be > 0 (got -1)",
     "(in instance 'w' at bad.yaml:8:16, in 'o' at bad.yaml:10:5)"},
    {HEAD "subsystems:\n  unused:\n    elements:\n      - {name: M, type: I, m: 0}\n"
          "elements: []\n",
     FB_EINVAL, "bad.yaml:5:", "subsystems.unused.elements[0].m: must be > 0", NULL},
    {HEAD "subsystems:\n  s:\n    parameters: [1]\n    elements: []\n"
          "elements:\n  - {name: a, type: s, parameters: {x: 1}}\n",
     FB_EPARSE, "bad.yaml:4:", "subsystems.s.parameters: expected parameters", NULL},
    /* Probes. */
    {HEAD "elements:\n  - {name: J, type: 1}\n  - {name: M, type: I, m: 1}\nbonds:\n"
          "  - {name: b1, from: J, to: M}\nprobes:\n  - {name: v, flow: b2}\n",
     FB_EMODEL, "bad.yaml:8:", "probes[0].flow: unknown bond 'b2' (did you mean 'b1'?)", NULL},
    {HEAD "elements:\n  - {name: J, type: 1}\n  - {name: M, type: I, m: 1}\nbonds:\n"
          "  - {name: b1, from: J, to: M}\nprobes:\n  - {name: v, flow: b1, component: 2}\n",
     FB_EINVAL, "bad.yaml:8:", "probes[0].component: must be an integer from 1 to 1", NULL},
    {HEAD "elements:\n  - {name: J, type: 1}\n  - {name: D, type: R, r: 1}\nbonds:\n"
          "  - {name: b1, from: J, to: D}\nprobes:\n  - {state: D}\n",
     FB_EMODEL, "bad.yaml:8:", "state probes need an I or C element", NULL},
    {HEAD "elements:\n  - {name: J, type: 1}\n  - {name: M, type: I, m: 1}\nbonds:\n"
          "  - {name: b1, from: J, to: M}\nprobes:\n  - {name: v, flow: b1, effort: b1}\n",
     FB_EPARSE, "bad.yaml:8:", "give only one of effort, flow", NULL},
    {HEAD "elements:\n  - {name: J, type: 1}\n  - {name: M, type: I, m: 1}\nbonds:\n"
          "  - {name: b1, from: J, to: M}\nprobes:\n  - {name: v, flow: b1, gain: 2}\n",
     FB_EMODEL, "bad.yaml:8:31:", "probes[0].gain: a gain changes the unit", NULL},
    /* Simulation. */
    {HEAD "elements: []\nsimulation: {t_ned: 3}\n", FB_EPARSE,
     "bad.yaml:3:", "simulation.t_ned: unknown key 't_ned' (did you mean 't_end'?)", NULL},
    {HEAD "elements: []\nsimulation:\n  t_start: 0\n  t_end: -1\n", FB_EINVAL,
     "bad.yaml:5:10:", "simulation.t_end: must be finite and greater than t_start", NULL},
    {HEAD "elements: []\nsimulation: {stability_limit_detection: 1}\n", FB_EPARSE,
     "bad.yaml:3:", "simulation.stability_limit_detection: expected true or false", NULL},
    {HEAD "elements: []\nsimulation: {max_order: 7}\n", FB_EINVAL,
     "bad.yaml:3:", "simulation.max_order: must be an integer from 1 to 5", NULL},
};

static void test_bad_models(void)
{
  size_t n = sizeof bad_cases / sizeof bad_cases[0];
  for (size_t i = 0; i < n; ++i) {
    const bad_case *bc = &bad_cases[i];
    fb_err err;
    fb_model *m = NULL;
    int rc = fb_model_load_string(bc->text, strlen(bc->text), "bad.yaml", ".", &m, &err);
    int ok = rc == bc->code && rc == err.code && m == NULL && strstr(err.msg, bc->where) &&
             strstr(err.msg, bc->phrase) && (!bc->phrase2 || strstr(err.msg, bc->phrase2));
    CHECK(ok);
    if (!ok)
      fprintf(stderr, "  bad case %zu: rc %s (want %s), message:\n    %s\n", i,
              fb_status_name(rc), fb_status_name(bc->code), err.msg);
    fb_model_free(&m);
  }
}

/* ---- Helpers for good models. */

static fb_model *load_ok(const char *text, const char *base_dir)
{
  fb_err err;
  fb_model *m = NULL;
  int rc = fb_model_load_string(text, strlen(text), "good.yaml", base_dir, &m, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  unexpected failure: %s\n", err.msg);
  return m;
}

static int has_element(const fb_bg *bg, const char *name, fb_bg_kind kind, size_t dim)
{
  long i = fb_bg_find_element(bg, name);
  return i >= 0 && fb_bg_element_kind(bg, (size_t)i) == kind &&
         fb_bg_element_dim(bg, (size_t)i) == dim;
}

/* Index of the diagram state called name, or -1. */
static long state_index(const fb_bd *bd, const char *name)
{
  for (size_t i = 0; i < fb_bd_nstates(bd); ++i)
    if (!strcmp(fb_bd_state_name(bd, i), name))
      return (long)i;
  return -1;
}

/* ---- Parameters and expressions. */

static const char params_model[] =
    "model: params\n"
    "parameters:\n"
    "  a: 2\n"
    "  b: a * 3          # 6\n"
    "  m: sqrt(b + 3)    # 3 kg\n"
    "  k: 2 ^ 5 * 10     # 320 N/m\n"
    "elements:\n"
    "  - {name: F, type: Se, value: b - 1}     # 5 N\n"
    "  - {name: J, type: 1}\n"
    "  - {name: M, type: I, m: m, initial: a / 4}\n"
    "  - {name: K, type: C, k: k, initial: 1 / 64}\n"
    "bonds:\n"
    "  - [F, J]\n"
    "  - {name: bm, from: J, to: M}\n"
    "  - [J, K, bk]\n"
    "probes:\n"
    "  - {name: v, flow: bm, gain: 1 / b, unit: 1/s}\n"
    "  - {effort: bk}\n"
    "simulation: {t_end: a * 5, sample_rate: 100 * b, max_order: a + 1, breakpoints: [a, b],\n"
    "             stability_limit_detection: false}\n";

static void test_parameters(void)
{
  fb_model *m = load_ok(params_model, NULL);
  if (!m)
    return;
  CHECK(!strcmp(fb_model_name(m), "params"));
  size_t np = 0;
  const fb_probe_spec *p = fb_model_probes(m, &np);
  CHECK(np == 2);
  /* gain 1/b with b = 6 (exact to rounding of one division). */
  CHECK_NEAR(p[0].gain, 1.0 / 6.0, 1e-15);
  CHECK(p[0].kind == FB_PROBE_FLOW && !strcmp(p[0].target, "bm") && p[0].component == -1);
  CHECK(!strcmp(p[1].name, "bk.effort") && p[1].kind == FB_PROBE_EFFORT && p[1].gain == 1.0);
  const fb_sim_opts *o = fb_model_sim_opts(m);
  CHECK(o->t_end == 10.0 && o->sample_rate == 600.0 && o->max_order == 3);
  CHECK(o->nbreakpoints == 2 && o->breakpoints[0] == 2.0 && o->breakpoints[1] == 6.0);
  CHECK(o->rtol == 1e-6 && o->atol == 1e-9); /* defaults of fb_sim_opts_default */
  CHECK(o->stability_limit_detection == 0);

  /* The laws through the diagram: with p(0) = 1/2, q(0) = 1/64,
   * p' = F - k q = 5 - 320/64 = 0 and q' = p/m = 1/6; sums of a few exact
   * binary fractions, so only the division 0.5/3 rounds. */
  fb_err err;
  fb_bd *bd = NULL;
  fb_bg *bg = fb_model_graph(m);
  int rc = fb_bd_build(bg, p, np, &bd, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  %s\n", err.msg);
  long ip = bd ? state_index(bd, "M.p") : -1, iq = bd ? state_index(bd, "K.q") : -1;
  CHECK(ip >= 0 && iq >= 0 && fb_bd_nstates(bd) == 2);
  if (ip >= 0 && iq >= 0) {
    double x0[2], xdot[2];
    fb_bd_initial_state(bd, x0);
    CHECK_NEAR(x0[ip], 0.5, 0.0);
    CHECK_NEAR(x0[iq], 1.0 / 64.0, 0.0);
    CHECK(fb_bd_rhs(bd, 0.0, x0, xdot) == 0);
    CHECK_NEAR(xdot[ip], 0.0, 1e-14);
    CHECK_NEAR(xdot[iq], 0.5 / 3.0, 1e-15);
    /* Probe v = flow of bm / b = (p/m)/6 = 1/36; bk.effort = k q = 5. */
    double y[2];
    CHECK(fb_bd_outputs(bd, 0.0, x0, y) == 0);
    CHECK_NEAR(y[0], 1.0 / 36.0, 1e-15);
    CHECK_NEAR(y[1], 5.0, 1e-14);
  }
  fb_bd_free(&bd);
  fb_model_free(&m);
}

/* ---- Subsystems: one definition instantiated twice with different
 * parameters, and nested in another definition. */

static const char subsys_model[] =
    "model: corners\n"
    "parameters: {q0: 0.01, kbase: 1000}\n"
    "subsystems:\n"
    "  corner:\n"
    "    parameters:\n"
    "      k: kbase         # N/m, sees the global parameters\n"
    "      m: 10            # kg\n"
    "      c: 2 * sqrt(k * m)  # critical damping, from the (possibly overridden) k\n"
    "    ports:\n"
    "      - {name: top, at: J, direction: in}\n"
    "    elements:\n"
    "      - {name: J, type: 1}\n"
    "      - {name: Mu, type: I, m: m}\n"
    "      - {name: K, type: C, k: k, initial: q0}\n"
    "      - {name: D, type: R, r: c}\n"
    "      - {name: tyre, type: tyre_def}\n"
    "    bonds:\n"
    "      - {name: bm, from: J, to: Mu}\n"
    "      - [J, K]\n"
    "      - [J, D]\n"
    "      - [J, tyre.p]\n"
    "  tyre_def:\n"
    "    ports: [{name: p, at: Kt}]\n"
    "    elements:\n"
    "      - {name: Kt, type: C, k: 1e5}\n"
    "  unused:\n"
    "    elements: [{name: J, type: 0}]\n"
    "elements:\n"
    "  - {name: front, type: corner, parameters: {k: 2 * kbase}}\n"
    "  - {name: rear, type: corner}\n"
    "  - {name: F1, type: Se, value: 0}\n"
    "  - {name: F2, type: Se, value: 0}\n"
    "bonds:\n"
    "  - [F1, front.top]\n"
    "  - [F2, rear.top]\n"
    "probes:\n"
    "  - {name: vf, flow: front.bm}\n";

static void test_subsystems(void)
{
  fb_model *m = load_ok(subsys_model, NULL);
  if (!m)
    return;
  const fb_bg *bg = fb_model_graph(m);
  CHECK(has_element(bg, "front.J", FB_BG_J1, 1));
  CHECK(has_element(bg, "front.Mu", FB_BG_I, 1));
  CHECK(has_element(bg, "front.K", FB_BG_C, 1));
  CHECK(has_element(bg, "front.D", FB_BG_R, 1));
  CHECK(has_element(bg, "front.tyre.Kt", FB_BG_C, 1));
  CHECK(has_element(bg, "rear.K", FB_BG_C, 1));
  CHECK(has_element(bg, "rear.tyre.Kt", FB_BG_C, 1));
  CHECK(fb_bg_find_element(bg, "unused.J") < 0); /* checked, but not part of the model */
  CHECK(fb_bg_nelements(bg) == 2 * 5 + 2);
  CHECK(fb_bg_find_bond(bg, "front.bm") >= 0 && fb_bg_find_bond(bg, "rear.bm") >= 0);

  /* Different laws per instance: at x0 (p = 0, q = q0 in K, 0 in Kt) the
   * momentum rate is p' = -k q0: front k = 2000, rear k = 1000, so
   * -20 N and -10 N (exact: products of small binary-exact numbers and
   * 0.01, one rounding). */
  size_t np = 0;
  const fb_probe_spec *p = fb_model_probes(m, &np);
  fb_err err;
  fb_bd *bd = NULL;
  CHECK(fb_bd_build(fb_model_graph(m), p, np, &bd, &err) == FB_OK);
  long pf = bd ? state_index(bd, "front.Mu.p") : -1,
       pr = bd ? state_index(bd, "rear.Mu.p") : -1;
  CHECK(pf >= 0 && pr >= 0);
  if (pf >= 0 && pr >= 0) {
    size_t n = fb_bd_nstates(bd);
    double *x = calloc(n, sizeof *x), *xdot = calloc(n, sizeof *xdot);
    if (x && xdot) {
      fb_bd_initial_state(bd, x);
      CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
      CHECK_NEAR(xdot[pf], -20.0, 1e-12);
      CHECK_NEAR(xdot[pr], -10.0, 1e-12);
      /* With velocity 1 m/s (p = m = 10), the damper adds -c: critical
       * damping 2 sqrt(k m) = 2 sqrt(20000) front, 200 rear. */
      x[pf] = 10.0;
      x[pr] = 10.0;
      CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
      CHECK_NEAR(xdot[pf], -20.0 - 2.0 * sqrt(20000.0), 1e-10);
      CHECK_NEAR(xdot[pr], -10.0 - 200.0, 1e-10);
    }
    free(x);
    free(xdot);
  }
  fb_bd_free(&bd);
  fb_model_free(&m);
}

/* A definition re-exporting the port of an instance inside it. */
static void test_reexport(void)
{
  fb_model *m = load_ok("model: nest\n"
                        "subsystems:\n"
                        "  inner:\n"
                        "    ports: [{name: p, at: J}]\n"
                        "    elements: [{name: J, type: 1}, {name: M, type: I, m: 2}]\n"
                        "    bonds: [[J, M]]\n"
                        "  outer:\n"
                        "    ports: [{name: top, at: w.p}]\n"
                        "    elements: [{name: w, type: inner}]\n"
                        "elements:\n"
                        "  - {name: o, type: outer}\n"
                        "  - {name: F, type: Se, value: 4}\n"
                        "bonds:\n"
                        "  - [F, o.top]\n",
                        NULL);
  if (!m)
    return;
  const fb_bg *bg = fb_model_graph(m);
  CHECK(has_element(bg, "o.w.M", FB_BG_I, 1) && has_element(bg, "o.w.J", FB_BG_J1, 1));
  long b = fb_bg_find_bond(bg, "F->o.top");
  CHECK(b >= 0 && fb_bg_bond_to(bg, (size_t)b) == (size_t)fb_bg_find_element(bg, "o.w.J"));
  fb_model_free(&m);
}

/* ---- Every element type, short bond forms, bond domains. */

static const char kinds_model[] =
    "model: kinds\n"
    "domain: rotation\n"
    "elements:\n"
    "  - {name: g, type: Se, dim: 3, value: [0, -9.81, sin(t)]}\n"
    "  - {name: s, type: Sf, dim: 2, value: {sine: {amplitude: 1, frequency: 2}}}\n"
    "  - {name: h, type: composite, parts: [1, 2]}\n"
    "  - {name: J3, type: one, dim: 3}\n"
    "  - {name: Z2, type: zero, dim: 2}\n"
    "  - {name: A, type: MTF, matrix: [[1, 0, 0], [1, 2.1, -0.5]]}\n"
    "  - {name: T, type: TF, ratio: 2}\n"
    "  - {name: G, type: GY, r: 0.5, dim: 2}\n"
    "  - {name: M3, type: I, dim: 3, m: 2}\n"
    "  - {name: F, type: I, ports: [2, 1], matrix: {diagonal: [1, 2, 3]}}\n"
    "  - {name: E, type: Se, value: {step: {time: 1, after: 3}}}\n"
    "  - {name: J, type: 0}\n"
    "  - {name: Rb, type: R, r: 0}\n"
    "bonds:\n"
    "  - [g, J3]\n"
    "  - {from: J3, to: M3, domain: electrical}\n"
    "  - [E, J, e_j]\n"
    "  - [J, Rb]\n";

static void test_kinds(void)
{
  fb_model *m = load_ok(kinds_model, NULL);
  if (!m)
    return;
  const fb_bg *bg = fb_model_graph(m);
  CHECK(has_element(bg, "g", FB_BG_SE, 3));
  CHECK(has_element(bg, "s", FB_BG_SF, 2));
  CHECK(has_element(bg, "J3", FB_BG_J1, 3));
  CHECK(has_element(bg, "Z2", FB_BG_J0, 2));
  CHECK(has_element(bg, "M3", FB_BG_I, 3));
  CHECK(has_element(bg, "F", FB_BG_I, 3));
  CHECK(has_element(bg, "Rb", FB_BG_R, 1));
  CHECK(fb_bg_find_element(bg, "h") >= 0 && fb_bg_find_element(bg, "A") >= 0);
  CHECK(fb_bg_find_element(bg, "T") >= 0 && fb_bg_find_element(bg, "G") >= 0);
  long b0 = fb_bg_find_bond(bg, "g->J3"), b1 = fb_bg_find_bond(bg, "J3->M3");
  CHECK(b0 >= 0 && b1 >= 0 && fb_bg_find_bond(bg, "e_j") >= 0);
  if (b0 >= 0 && b1 >= 0) {
    CHECK(fb_bg_bond_dim(bg, (size_t)b0) == 3);
    CHECK(fb_bg_bond_domain(bg, (size_t)b0) == FB_DOMAIN_ROTATION);
    CHECK(fb_bg_bond_domain(bg, (size_t)b1) == FB_DOMAIN_ELECTRICAL);
  }
  const fb_sim_opts *o = fb_model_sim_opts(m);
  CHECK(o->t_end == 1.0 && o->nbreakpoints == 0); /* defaults without `simulation` */
  fb_model_free(&m);
}

/* ---- Files referenced by the model: resolved from base_dir, their own
 * path:line kept in messages. */

static int write_file(const char *dir, const char *name, const char *text)
{
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *fp = fopen(path, "w");
  if (!fp)
    return 0;
  fputs(text, fp);
  return fclose(fp) == 0;
}

static void remove_file(const char *dir, const char *name)
{
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  remove(path);
}

static const char files_model[] =
    "model: files\n"
    "elements:\n"
    "  - {name: road, type: Sf, value: {table: {file: road.csv, time: time, value: v}}}\n"
    "  - {name: K, type: C, ports: 2, matrix: {mtx: K.mtx}}\n"
    "  - {name: J, type: 0}\n"
    "  - {name: Kt, type: C, k: 4}\n"
    "  - {name: s1, type: Sf, value: 0}\n"
    "  - {name: s2, type: Sf, value: 0}\n"
    "bonds:\n"
    "  - {name: br, from: road, to: J}\n"
    "  - [J, Kt]\n"
    "  - [s1, K.1]\n"
    "  - [s2, K.2]\n"
    "probes:\n"
    "  - {name: vr, flow: br}\n";

static void test_files(void)
{
  char dir[TEST_PATH_MAX];
  test_tmp_path("test_model_XXXXXX", dir, sizeof dir);
  if (!mkdtemp(dir)) {
    CHECK(!"mkdtemp failed");
    return;
  }
  CHECK(write_file(dir, "road.csv", "time,v\n0,0\n1,2\n3,2\n"));
  CHECK(write_file(dir, "K.mtx",
                   "%%MatrixMarket matrix coordinate real symmetric\n"
                   "2 2 3\n1 1 3\n2 1 -1\n2 2 1\n"));
  fb_model *m = load_ok(files_model, dir);
  if (m) {
    const fb_bg *bg = fb_model_graph(m);
    CHECK(has_element(bg, "K", FB_BG_C, 2));
    /* The table interpolates linearly: v(0.5) = 1, v(2) = 2. */
    size_t np = 0;
    const fb_probe_spec *p = fb_model_probes(m, &np);
    fb_err err;
    fb_bd *bd = NULL;
    int rc = fb_bd_build(fb_model_graph(m), p, np, &bd, &err);
    CHECK(rc == FB_OK);
    if (rc)
      fprintf(stderr, "  %s\n", err.msg);
    CHECK(!bd || fb_bd_nstates(bd) == 3);
    if (bd && fb_bd_nstates(bd) == 3) {
      double x[3] = {0, 0, 0}, y = 0;
      CHECK(fb_bd_outputs(bd, 0.5, x, &y) == 0);
      CHECK_NEAR(y, 1.0, 1e-15);
      CHECK(fb_bd_outputs(bd, 2.0, x, &y) == 0);
      CHECK_NEAR(y, 2.0, 1e-15);
    }
    fb_bd_free(&bd);
    fb_model_free(&m);
  }
  /* fb_model_load resolves the same references from the file's own
   * directory, wherever the caller runs. */
  char path[512];
  snprintf(path, sizeof path, "%s/model.yaml", dir);
  CHECK(write_file(dir, "model.yaml", files_model));
  fb_err err;
  CHECK(fb_model_load(path, &m, &err) == FB_OK);
  CHECK(m && has_element(fb_model_graph(m), "road", FB_BG_SF, 1));
  fb_model_free(&m);
  remove_file(dir, "model.yaml");
  /* A bad CSV line: the YAML location of the reference, then the CSV's
   * own path:line. */
  CHECK(write_file(dir, "road.csv", "time,v\n0,0\n1,x\n"));
  int rc = fb_model_load_string(files_model, strlen(files_model), "bad.yaml", dir, &m, &err);
  CHECK(rc != FB_OK && m == NULL);
  CHECK(strstr(err.msg, "bad.yaml:3:") && strstr(err.msg, "road.csv:3"));
  /* A missing .mtx file is an I/O error naming the resolved path. */
  remove_file(dir, "K.mtx");
  CHECK(write_file(dir, "road.csv", "time,v\n0,0\n"));
  rc = fb_model_load_string(files_model, strlen(files_model), "bad.yaml", dir, &m, &err);
  CHECK(rc == FB_EIO && strstr(err.msg, "bad.yaml:4:") && strstr(err.msg, "K.mtx"));
  remove_file(dir, "road.csv");
  rmdir(dir);
}

/* ---- The examples. */

static void test_quarter_car(void)
{
  fb_err err;
  fb_model *m = NULL;
  int rc = fb_model_load("../examples/quarter_car.yaml", &m, &err);
  CHECK(rc == FB_OK);
  if (rc) {
    fprintf(stderr, "  %s\n", err.msg);
    return;
  }
  const fb_bg *bg = fb_model_graph(m);
  CHECK(!strcmp(fb_model_name(m), "quarter_car"));
  CHECK(has_element(bg, "Ms", FB_BG_I, 1) && has_element(bg, "Mu", FB_BG_I, 1));
  CHECK(has_element(bg, "Ks", FB_BG_C, 1) && has_element(bg, "Kt", FB_BG_C, 1));
  CHECK(has_element(bg, "Cs", FB_BG_R, 1) && has_element(bg, "road", FB_BG_SF, 1));
  size_t np = 0;
  const fb_probe_spec *p = fb_model_probes(m, &np);
  CHECK(np == 5);
  const fb_sim_opts *o = fb_model_sim_opts(m);
  CHECK(o->t_end == 5.0 && o->sample_rate == 1000.0 && o->nbreakpoints == 2);
  CHECK(o->stability_limit_detection == 1); /* the default */

  /* Before the bump (t < 0.5 s) the car must rest in static equilibrium:
   * body displacement 0, suspension compression ms g / ks, tire force
   * (ms + mu) g (closed form). The tolerances allow for the solver's
   * rtol = 1e-6 on states of size 0.15 m and 3 kN. */
  fb_bd *bd = NULL;
  rc = fb_bd_build(fb_model_graph(m), p, np, &bd, &err);
  CHECK(rc == FB_OK);
  fb_sim_opts short_run = *o;
  short_run.t_end = 0.4;
  fb_result *r = NULL;
  if (!rc)
    rc = fb_sim_run(bd, &short_run, &r, &err);
  CHECK(rc == FB_OK);
  if (r) {
    const double *last = fb_result_row(r, fb_result_nsamples(r) - 1);
    long x = fb_result_find(r, "x_body"), defl = fb_result_find(r, "deflection");
    long tf = fb_result_find(r, "tire_force");
    CHECK(x > 0 && defl > 0 && tf > 0);
    if (x > 0 && defl > 0 && tf > 0) {
      CHECK_NEAR(last[0], 0.4, 1e-12);
      CHECK_NEAR(last[x], 0.0, 1e-9);
      CHECK_NEAR(last[defl], 250.0 * 9.81 / 16000.0, 1e-7);
      CHECK_NEAR(last[tf], 285.0 * 9.81, 1e-3);
    }
  }
  fb_result_free(&r);
  fb_bd_free(&bd);
  fb_model_free(&m);
}

static void test_two_dof(void)
{
  fb_err err;
  fb_model *m = NULL;
  int rc = fb_model_load("../examples/two_dof_fields.yaml", &m, &err);
  CHECK(rc == FB_OK);
  if (rc) {
    fprintf(stderr, "  %s\n", err.msg);
    return;
  }
  const fb_bg *bg = fb_model_graph(m);
  CHECK(has_element(bg, "M", FB_BG_I, 2));
  CHECK(has_element(bg, "K", FB_BG_C, 2));
  CHECK(has_element(bg, "D", FB_BG_R, 2));
  /* The stacked laws: at x1 = 0.01, x2 = 0, rest, F = 0 (t < 1 s):
   * p' = -K q = -[1500 * 0.01, -500 * 0.01] = [-15, 5] N, and q' = 0. */
  size_t np = 0;
  const fb_probe_spec *p = fb_model_probes(m, &np);
  fb_bd *bd = NULL;
  rc = fb_bd_build(fb_model_graph(m), p, np, &bd, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  %s\n", err.msg);
  long p1 = bd ? state_index(bd, "M.p[1]") : -1, p2 = bd ? state_index(bd, "M.p[2]") : -1;
  CHECK(p1 >= 0 && p2 >= 0 && fb_bd_nstates(bd) == 4);
  if (p1 >= 0 && p2 >= 0 && fb_bd_nstates(bd) == 4) {
    double x[4], xdot[4];
    fb_bd_initial_state(bd, x);
    CHECK(fb_bd_rhs(bd, 0.0, x, xdot) == 0);
    CHECK_NEAR(xdot[p1], -15.0, 1e-12);
    CHECK_NEAR(xdot[p2], 5.0, 1e-12);
  }
  fb_bd_free(&bd);
  fb_model_free(&m);
}

/* ---- Documentation: every complete model in docs/model-format.md (a
 * ```yaml block starting with "model:") must load. */

static void test_doc_examples(void)
{
  FILE *fp = fopen("../docs/model-format.md", "r");
  CHECK(fp != NULL);
  if (!fp)
    return;
  char line[1024], *text = NULL;
  size_t len = 0, cap = 0;
  int in_block = 0, nmodels = 0;
  while (fgets(line, sizeof line, fp)) {
    if (!in_block) {
      in_block = !strncmp(line, "```yaml", 7);
      len = 0;
      continue;
    }
    if (strncmp(line, "```", 3)) {
      size_t n = strlen(line);
      if (len + n + 1 > cap) {
        cap = 2 * (len + n + 1);
        char *grown = realloc(text, cap);
        if (!grown)
          break;
        text = grown;
      }
      memcpy(text + len, line, n + 1);
      len += n;
      continue;
    }
    in_block = 0;
    if (len == 0 || strncmp(text, "model:", 6))
      continue;
    ++nmodels;
    fb_model *m = load_ok(text, "../examples");
    /* The documented models draw every bond the usual way. */
    CHECK(m && fb_model_nwarnings(m) == 0);
    fb_model_free(&m);
  }
  fclose(fp);
  free(text);
  CHECK(nmodels >= 2);
}

/* Empty sections, anchors and merge keys. */
static void test_yaml_features(void)
{
  fb_model *m =
      load_ok("model: empty\nparameters:\nelements:\nbonds:\nprobes:\nsimulation:\n", NULL);
  CHECK(m && fb_bg_nelements(fb_model_graph(m)) == 0);
  fb_model_free(&m);
  m = load_ok("model: anchors\n"
              "parameters: {k: 5}\n"
              "elements:\n"
              "  - &spring {name: K1, type: C, k: k, initial: 0.5}\n"
              "  - {<<: *spring, name: K2}\n"
              "  - {name: J, type: 1}\n",
              NULL);
  CHECK(m && has_element(fb_model_graph(m), "K2", FB_BG_C, 1));
  fb_model_free(&m);
  /* One '' escape per run decodes right in every libfyaml, and so does
   * any number of quotes in double quotes. */
  static const char *const units[][2] = {{"'it''s'", "it's"}, {"\"x''y\"", "x''y"}};
  for (size_t i = 0; i < 2; ++i) {
    char text[256];
    snprintf(text, sizeof text,
             "model: quotes\nelements:\n  - {name: J, type: 1}\n  - {name: M, type: I, m: 1}\n"
             "bonds:\n  - {name: b1, from: J, to: M}\nprobes:\n  - {flow: b1, unit: %s}\n",
             units[i][0]);
    m = load_ok(text, NULL);
    size_t nprobes = 0;
    const fb_probe_spec *probes = m ? fb_model_probes(m, &nprobes) : NULL;
    CHECK(nprobes == 1 && probes && probes[0].unit && !strcmp(probes[0].unit, units[i][1]));
    fb_model_free(&m);
  }
}

/* ---- Alias expansion bound (model_yaml.c, "Bounding alias expansion"). */

/* A growing text; the tests stop at the first allocation failure. */
typedef struct text_buf {
  char *s;
  size_t len, cap;
} text_buf;

static void text_add(text_buf *t, const char *piece, size_t times)
{
  size_t n = strlen(piece);
  for (size_t i = 0; i < times; ++i) {
    if (t->len + n + 1 > t->cap) {
      size_t cap = 2 * (t->len + n + 1);
      char *s = realloc(t->s, cap);
      if (!s) {
        fprintf(stderr, "out of memory building a test text\n");
        exit(1);
      }
      t->s = s;
      t->cap = cap;
    }
    memcpy(t->s + t->len, piece, n + 1);
    t->len += n;
  }
}

/* Loads text as "bomb.yaml": its status, message and CPU time. */
static int load_timed(const char *text, fb_err *err, double *seconds)
{
  fb_model *m = NULL;
  clock_t start = clock();
  int rc = fb_model_load_string(text, strlen(text), "bomb.yaml", NULL, &m, err);
  *seconds = (double)(clock() - start) / CLOCKS_PER_SEC;
  CHECK(rc ? m == NULL : m != NULL);
  fb_model_free(&m);
  return rc;
}

/* The reviewer's "billion laughs": aN lists ten *a(N-1), so aN expands to
 * about 10^(N+1) nodes; unchecked, depth 7 took 15 GB and a minute, depth
 * 8 was killed for memory. Refused before anything is copied, at the
 * eighth *a3 of a4 (where the count passes 100000), in milliseconds. */
static void test_alias_bomb(void)
{
  for (int depth = 7; depth <= 9; ++depth) {
    text_buf t = {NULL, 0, 0};
    text_add(&t, "model: bomb\nparameters:\n  a0: &a0 [x,x,x,x,x,x,x,x,x,x]\n", 1);
    for (int n = 1; n <= depth; ++n) {
      char line[128];
      int k = snprintf(line, sizeof line, "  a%d: &a%d [", n, n);
      for (int i = 0; i < 10 && k > 0 && (size_t)k < sizeof line; ++i)
        k += snprintf(line + k, sizeof line - (size_t)k, "%s*a%d", i ? "," : "", n - 1);
      text_add(&t, line, 1);
      text_add(&t, "]\n", 1);
    }
    text_add(&t, "elements: []\n", 1);
    fb_err err;
    double seconds = 0;
    int rc = load_timed(t.s, &err, &seconds);
    CHECK(rc == FB_EPARSE);
    CHECK(strstr(err.msg, "bomb.yaml:7:41: YAML: aliases would expand the document to more "
                          "than 100000 nodes (the file has ") != NULL);
    CHECK(strstr(err.msg, "*a3 here copies 11111") != NULL);
    CHECK(seconds < 1.0);
    if (rc != FB_EPARSE || seconds >= 1.0)
      fprintf(stderr, "  bomb of depth %d: %s, %.2f s: %s\n", depth, fb_status_name(rc),
              seconds, err.msg);
    free(t.s);
  }
}

/* "[x, ... (p), &a [x, ... (k)], *a, ... (m)]": written nodes 1 + p + 1 + k
 * + m, expanded 1 + p + (1 + k)(1 + m). The bound is 100000 nodes or 10
 * times the written count, whichever is more; at it the document passes
 * the check (and is then refused as no model), one node past it not. */
static void test_alias_bound_edge(void)
{
  static const struct {
    size_t p, k, m;
    int over;
  } cases[] = {
      {99, 99, 998, 0},    /* 1198 written, 100000 expanded: at the bound */
      {100, 99, 998, 1},   /* 1199 written, 100001 expanded */
      {9089, 100, 909, 0}, /* 10100 written, 101000 expanded: at 10 times */
      {9099, 100, 910, 1}, /* 10111 written, 101111 expanded: 10 times + 1 */
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
    const size_t p = cases[i].p, k = cases[i].k, m = cases[i].m;
    const size_t written = 1 + p + 1 + k + m, expanded = 1 + p + (1 + k) * (1 + m);
    const size_t bound = 10 * written > 100000 ? 10 * written : 100000;
    CHECK(expanded == bound + (size_t)cases[i].over); /* the case is at the edge */
    text_buf t = {NULL, 0, 0};
    text_add(&t, "[", 1);
    text_add(&t, "x, ", p);
    text_add(&t, "&a [x", 1);
    text_add(&t, ", x", k - 1);
    text_add(&t, "]", 1);
    text_add(&t, ", *a", m);
    text_add(&t, "]\n", 1);
    fb_err err;
    double seconds = 0;
    int rc = load_timed(t.s, &err, &seconds);
    char want[128];
    snprintf(want, sizeof want,
             "bomb.yaml:1:%zu: YAML: aliases would expand the document to "
             "more than %zu nodes (the file has %zu as written",
             t.len - 2, bound, written);
    int ok = rc == FB_EPARSE &&
             (cases[i].over ? strstr(err.msg, want) != NULL
                            : strstr(err.msg, "bomb.yaml:1:1: expected a model") != NULL);
    CHECK(ok);
    if (!ok)
      fprintf(stderr, "  edge case %zu (%zu expanded, bound %zu): %s\n  want %s\n", i, expanded,
              bound, err.msg, cases[i].over ? want : "expected a model");
    free(t.s);
  }
}

/* Nesting through aliases is bounded too, whichever way they point:
 * backwards (each anchor nests the previous one 60 levels deeper) and
 * forwards (a chain of 1000 aliases to the next anchor, which the count
 * must not follow into a recursion 1000 deep). */
static void test_alias_depth(void)
{
  text_buf t = {NULL, 0, 0};
  text_add(&t, "model: deep\nparameters:\n  p:\n    - &a0 x\n", 1);
  for (int n = 1; n <= 5; ++n) {
    char item[64];
    snprintf(item, sizeof item, "    - &a%d ", n);
    text_add(&t, item, 1);
    text_add(&t, "[", 60);
    snprintf(item, sizeof item, "*a%d", n - 1);
    text_add(&t, item, 1);
    text_add(&t, "]", 60);
    text_add(&t, "\n", 1);
  }
  fb_err err;
  double seconds = 0;
  CHECK(load_timed(t.s, &err, &seconds) == FB_EPARSE);
  CHECK(strstr(err.msg, "bomb.yaml:9:") != NULL);
  CHECK(strstr(err.msg, "YAML: aliases would nest the document more than 256 levels deep") !=
        NULL);
  free(t.s);

  t.s = NULL;
  t.len = t.cap = 0;
  text_add(&t, "model: forward\nparameters:\n  p:\n", 1);
  for (int n = 1; n < 1000; ++n) {
    char item[64];
    snprintf(item, sizeof item, "    - &a%d [*a%d]\n", n, n + 1);
    text_add(&t, item, 1);
  }
  text_add(&t, "    - &a1000 x\n", 1);
  CHECK(load_timed(t.s, &err, &seconds) == FB_EPARSE);
  CHECK(strstr(err.msg, "bomb.yaml:4:") != NULL);
  CHECK(strstr(err.msg, "more than 256 levels deep (*a2 here") != NULL);
  free(t.s);
}

/* Sharing a few blocks, as models do, stays far inside the bound. */
static void test_alias_sharing(void)
{
  fb_model *m = load_ok("model: shared\n"
                        "parameters: {k: 5, m: 2}\n"
                        "elements:\n"
                        "  - &spring {name: K1, type: C, k: k, initial: &q0 0.5}\n"
                        "  - {<<: *spring, name: K2}\n"
                        "  - {<<: *spring, name: K3, k: 2 * k}\n"
                        "  - &mass {name: M1, type: I, m: m, initial: *q0}\n"
                        "  - {<<: *mass, name: M2}\n"
                        "  - {name: J, type: 1}\n"
                        "bonds: [[J, K1], [J, K2], [J, K3], [J, M1], [J, M2]]\n",
                        NULL);
  const fb_bg *bg = m ? fb_model_graph(m) : NULL;
  CHECK(bg && has_element(bg, "K3", FB_BG_C, 1) && has_element(bg, "M2", FB_BG_I, 1));
  CHECK(bg && fb_bg_nbonds(bg) == 5);
  fb_model_free(&m);
}

/* ---- Errors of the graph after loading, located by fb_model_blame. */

/* Loads text, assigns causality, which must fail with code, and checks
 * that fb_model_blame located the message at where (and phrase). */
static void expect_blamed(const char *text, int code, const char *where, const char *phrase)
{
  fb_model *m = load_ok(text, NULL);
  fb_err err;
  fb_err_clear(&err);
  int rc = m ? fb_bg_assign_causality(fb_model_graph(m), &err) : FB_OK;
  CHECK(rc == code && err.origin != FB_ORIGIN_NONE);
  fb_model_blame(m, &err);
  int ok = !strncmp(err.msg, where, strlen(where)) && strstr(err.msg, phrase);
  CHECK(ok && err.origin == FB_ORIGIN_NONE);
  if (!ok)
    fprintf(stderr, "  wanted %s ... %s, got:\n    %s\n", where, phrase, err.msg);
  /* The fields say what the message's head says. */
  char head[FB_ERR_MSG_MAX];
  snprintf(head, sizeof head, "%s:%d:%d: %s: ", err.file, err.line, err.column, err.key);
  CHECK(err.source == FB_SOURCE_FILE && !strncmp(where, head, strlen(head)));
  /* A second call changes nothing. */
  char once[FB_ERR_MSG_MAX];
  snprintf(once, sizeof once, "%s", err.msg);
  CHECK(fb_model_blame(m, &err) == code && !strcmp(once, err.msg));
  fb_model_free(&m);
}

static void test_blame(void)
{
  expect_blamed("model: m\nelements:\n  - {name: F, type: Se, value: 1}\n"
                "  - {name: T, type: TF, ratio: 2}\nbonds:\n  - [F, T.1]\n",
                FB_EMODEL, "good.yaml:4:5: elements[1]: TF 'T': port 2 is not connected", "");
  expect_blamed("model: m\nelements:\n  - {name: F1, type: Sf, value: 1}\n"
                "  - {name: F2, type: Sf, value: 2}\n  - {name: J, type: 1}\nbonds:\n"
                "  - [F1, J]\n  - [F2, J]\n",
                FB_ECAUSAL, "good.yaml:8:5: bonds[1]: causal conflict", "");
  expect_blamed("model: m\nsubsystems:\n  two:\n    ports: [{name: a, at: j}]\n"
                "    elements:\n      - {name: j, type: 1}\n      - {name: M1, type: I, m: 1}\n"
                "      - {name: M2, type: I, m: 1}\n    bonds:\n      - [j, M1]\n"
                "      - [j, M2]\nelements:\n  - {name: F, type: Se, value: 1}\n"
                "  - {name: q, type: two}\nbonds:\n  - [F, q.a]\n",
                FB_ECAUSAL,
                "good.yaml:8:9: subsystems.two.elements[2]: I 'q.M2' is in derivative",
                "(in instance 'q' at good.yaml:14:5)");
  /* No model, or an error without an origin: unchanged. */
  fb_err err;
  fb_err_set(&err, FB_EINVAL, "plain");
  CHECK(fb_model_blame(NULL, &err) == FB_EINVAL && !strcmp(err.msg, "plain"));
  CHECK(fb_model_blame(NULL, NULL) == FB_OK);
}

/* ---- Warnings: a bond out of an I, C or R. */

/* A model whose bonds are all drawn the usual way has none; one drawn out
 * of a C, an R or port 2 of a field has one each, located like an error;
 * the three instances of one definition share one. */
static void test_power_out_warnings(void)
{
  fb_model *m = load_ok("model: m\nelements:\n  - {name: F, type: Se, value: 1}\n"
                        "  - {name: J, type: 1}\n  - {name: K, type: C, k: 1}\n"
                        "bonds: [[F, J], [J, K]]\n",
                        NULL);
  CHECK(m && fb_model_nwarnings(m) == 0 && fb_model_warning(m, 0) == NULL);
  fb_model_free(&m);

  m = load_ok("model: m\nsubsystems:\n  corner:\n    elements:\n"
              "      - {name: K, type: C, k: 1000}\n      - {name: J, type: 1}\n"
              "    bonds: [[K, J]]\n    ports:\n      - {name: top, at: J}\n"
              "elements:\n  - {name: F, type: Se, value: 1}\n  - {name: J0, type: 0}\n"
              "  - {name: a, type: corner}\n  - {name: b, type: corner}\n"
              "  - {name: c, type: corner}\n"
              "  - {name: D, type: R, matrix: [[1, 0], [0, 1]], ports: 2}\n"
              "  - {name: J1, type: 1}\n"
              "bonds:\n  - [F, J0]\n  - [J0, a.top]\n  - [J0, b.top]\n  - [J0, c.top]\n"
              "  - [J0, D.1]\n  - {name: back, from: D.2, to: J1}\n  - [J1, J0]\n",
              NULL);
  CHECK(m && fb_model_nwarnings(m) == 2);
  const fb_err *w = fb_model_warning(m, 0);
  CHECK(w && w->code == FB_EMODEL && !strcmp(w->file, "good.yaml") && w->line == 7 &&
        w->column == 13 && !strcmp(w->key, "subsystems.corner.bonds[0]"));
  static const char head[] =
      "good.yaml:7:13: subsystems.corner.bonds[0]: bond 'a.K->J' points out of C 'a.K'";
  CHECK(w && !strncmp(w->msg, head, strlen(head)) &&
        strstr(w->msg, "write the bond with 'K' at its 'to' end"));
  CHECK(w && strstr(w->msg, "(in instance 'a' at good.yaml:13:5) (and 2 more instances)"));
  w = fb_model_warning(m, 1);
  CHECK(w && w->line == 24 && !strcmp(w->key, "bonds[5]") &&
        strstr(w->msg, "bond 'back' points out of port 2 of R 'D'") &&
        strstr(w->msg, "write the bond with 'D' at its 'to' end"));
  fb_model_free(&m);

  /* A nonlinear law reversed is no mere sign: its warning says the motion
   * changes. */
  m = load_ok("model: m\nelements:\n  - {name: J, type: 1}\n"
              "  - {name: K, type: contact, k: 1000, c: 10, damper: D}\n"
              "bonds: [[K, J], [J, D]]\n",
              NULL);
  w = fb_model_warning(m, 0);
  CHECK(m && fb_model_nwarnings(m) == 1 && w &&
        strstr(w->msg, "bond 'K->J' points out of C 'K': its law (unilateral spring)") &&
        strstr(w->msg, "compression and extension swap, and the motion differs"));
  fb_model_free(&m);
}

/* A contact with Hunt-Crossley damping: lambda reaches the law; c and
 * lambda together are refused at lambda. */
static void test_contact_lambda(void)
{
  fb_model *m = load_ok("model: m\nelements:\n  - {name: J, type: 1}\n"
                        "  - {name: K, type: contact, k: 1000, lambda: 2e4, damper: D}\n"
                        "bonds: [[J, K], [J, D]]\n",
                        NULL);
  fb_bg_contact contact;
  const fb_bg *bg = m ? fb_model_graph(m) : NULL;
  CHECK(bg && fb_bg_element_contact(bg, (size_t)fb_bg_find_element(bg, "D"), &contact) &&
        contact.k == 1000 && contact.c == 0 && contact.lambda == 2e4);
  fb_model_free(&m);
  static const char both[] = "model: m\nelements:\n"
                             "  - {name: K, type: contact, k: 1, c: 2, lambda: 3, damper: D}\n";
  fb_err err;
  CHECK(fb_model_load_string(both, strlen(both), "bad.yaml", NULL, &m, &err) == FB_EPARSE);
  CHECK(!strncmp(err.msg, "bad.yaml:3:42: elements[0].lambda: give the damping as c", 56));
}

/* An expression is no one-line text: a block scalar's line breaks are
 * blanks in it, where a unit or name with one is refused. */
static void test_multiline_expression(void)
{
  fb_model *m = load_ok("model: m\nelements:\n  - name: F\n    type: Se\n    value: |\n"
                        "      1 +\n      2 * t\n  - {name: M, type: I, m: 1}\nbonds:\n"
                        "  - [F, M]\n",
                        NULL);
  CHECK(m != NULL);
  fb_model_free(&m);
}

/* ---- API edges. */

static void test_api(void)
{
  fb_err err;
  fb_model *m = (fb_model *)&err; /* must be reset to NULL on failure */
  CHECK(fb_model_load("no/such/model.yaml", &m, &err) == FB_EIO && m == NULL);
  CHECK(strstr(err.msg, "no/such/model.yaml") != NULL);
  /* err may be NULL. */
  CHECK(fb_model_load_string("model: [", 8, "x.yaml", NULL, &m, NULL) == FB_EPARSE);
  m = load_ok("model: tiny\nelements: []\n", NULL);
  CHECK(m && fb_bg_nelements(fb_model_graph(m)) == 0);
  size_t np = 7;
  CHECK(m && fb_model_probes(m, &np) == NULL && np == 0);
  fb_model_free(&m);
  CHECK(m == NULL);
  fb_model_free(&m);
  fb_model_free(NULL);
}

int main(void)
{
  test_bad_models();
  test_blame();
  test_power_out_warnings();
  test_contact_lambda();
  test_multiline_expression();
  test_parameters();
  test_subsystems();
  test_reexport();
  test_kinds();
  test_files();
  test_quarter_car();
  test_two_dof();
  test_doc_examples();
  test_yaml_features();
  test_alias_bomb();
  test_alias_bound_edge();
  test_alias_depth();
  test_alias_sharing();
  test_api();
  return check_report("test_model");
}
