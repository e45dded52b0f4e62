/* SPDX-License-Identifier: BSD-3-Clause */
/* Model files (flexbond/model.h): the top-level sections of a model and
 * the public API. The format is documented in docs/model-format.md. */
#include "flexbond/model.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/util.h"
#include "io/model_internal.h"

struct fb_model {
  char *name;
  fb_bg *bg;
  fb_probe_spec *probes;
  size_t nprobes, probe_capacity;
  char **strings;   /* owned probe names, targets and units (3 per probe) */
  double **weights; /* owned probe weights (one array per probe, or NULL) */
  fb_sim_opts opts;
  fb_model_initial initial; /* simulation.initial */
  double *breakpoints;      /* owned, opts.breakpoints points here */
  ml_sites sites;           /* where the graph's elements and bonds were written */
  ml_warnings warnings;     /* of the load (fb_model_warning) */
};

void fb_model_free(fb_model **m)
{
  if (!m || !*m)
    return;
  fb_model *p = *m;
  for (size_t i = 0; p->strings && i < 3 * p->probe_capacity; ++i)
    free(p->strings[i]);
  free(p->strings);
  for (size_t i = 0; p->weights && i < p->probe_capacity; ++i)
    free(p->weights[i]);
  free(p->weights);
  free(p->probes);
  free(p->breakpoints);
  ml_sites_release(&p->sites);
  ml_warnings_release(&p->warnings);
  fb_bg_free(&p->bg);
  free(p->name);
  free(p);
  *m = NULL;
}

const char *fb_model_name(const fb_model *m)
{
  return m->name;
}

fb_bg *fb_model_graph(fb_model *m)
{
  return m->bg;
}

const fb_probe_spec *fb_model_probes(const fb_model *m, size_t *nprobes)
{
  if (nprobes)
    *nprobes = m->nprobes;
  return m->probes;
}

const fb_sim_opts *fb_model_sim_opts(const fb_model *m)
{
  return &m->opts;
}

fb_model_initial fb_model_initial_choice(const fb_model *m)
{
  return m->initial;
}

int fb_model_initial_state(const fb_model *m, fb_bd *bd, double *x0, fb_err *err)
{
  const size_t n = fb_bd_nstates(bd);
  if (m->initial == FB_MODEL_INITIAL_ZERO) {
    for (size_t i = 0; i < n; ++i)
      x0[i] = 0.0;
    return FB_OK;
  }
  fb_bd_initial_state(bd, x0);
  if (m->initial != FB_MODEL_INITIAL_STATIC)
    return FB_OK;
  double *given = malloc((n + 1) * sizeof *given);
  if (!given)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; i < n; ++i)
    given[i] = x0[i];
  const int rc = fb_sim_static_state(bd, m->opts.t_start, given, x0, err);
  free(given);
  if (rc)
    fb_err_prefix(err, "simulation.initial: static: ");
  return rc;
}

int fb_model_blame(const fb_model *m, fb_err *err)
{
  if (!err)
    return FB_OK;
  const size_t i = err->origin_index;
  const char *name = NULL;
  if (m && err->code && err->origin == FB_ORIGIN_ELEMENT && i < fb_bg_nelements(m->bg))
    name = fb_bg_element_name(m->bg, i);
  else if (m && err->code && err->origin == FB_ORIGIN_BOND && i < fb_bg_nbonds(m->bg))
    name = fb_bg_bond_name(m->bg, i);
  const ml_site *site = m ? ml_sites_find(&m->sites, err->origin, name) : NULL;
  if (!site)
    return err->code;
  char head[1024];
  ml_site_head(&m->sites, site, head, sizeof head);
  fb_err_prefix(err, "%s", head);
  fb_err_append(err, "%s", site->tail);
  err->origin = FB_ORIGIN_NONE;
  ml_site_set_fields(&m->sites, site, err);
  return err->code;
}

size_t fb_model_nwarnings(const fb_model *m)
{
  return m ? m->warnings.n : 0;
}

const fb_err *fb_model_warning(const fb_model *m, size_t i)
{
  return m && i < m->warnings.n ? &m->warnings.warning[i] : NULL;
}

/* ---- Probes. */

static const char *const ml_probe_kinds[] = {"effort", "flow",   "power",
                                             "state",  "energy", NULL};

static const char *ml_bond_name_at(const void *ctx, size_t i)
{
  return fb_bg_bond_name(ctx, i);
}

static const char *ml_element_name_at(const void *ctx, size_t i)
{
  return fb_bg_element_name(ctx, i);
}

/* Which of effort/flow/... the probe has (exactly one). */
static int ml_probe_kind(const ml_ctx *c, struct fy_node *p, fb_probe_kind *kind,
                         struct fy_node **target)
{
  int found = 0;
  for (size_t k = 0; ml_probe_kinds[k]; ++k) {
    struct fy_node *key = NULL;
    struct fy_node *v = ml_get(p, ml_probe_kinds[k], &key);
    if (!key)
      continue;
    if (found++)
      return ml_fail_key(c, p, key, FB_EPARSE,
                         "a probe measures one thing: give only one of effort, flow, power, "
                         "state, energy");
    *kind = (fb_probe_kind)k;
    *target = v;
  }
  if (!found)
    return ml_fail(c, p, FB_EPARSE,
                   "a probe needs one of the keys effort, flow, power (a bond name) or state, "
                   "energy (an I or C element name)");
  return FB_OK;
}

/* The probe's target exists in the graph with the right kind; *dim gets
 * its dimension. */
static int ml_probe_target(const ml_ctx *c, const fb_bg *bg, struct fy_node *at,
                           fb_probe_kind kind, const char *target, size_t *dim)
{
  int on_bond = kind == FB_PROBE_EFFORT || kind == FB_PROBE_FLOW || kind == FB_PROBE_POWER;
  long i = on_bond ? fb_bg_find_bond(bg, target) : fb_bg_find_element(bg, target);
  if (i < 0) {
    const char *near = on_bond
                           ? fb_suggest(target, fb_bg_nbonds(bg), ml_bond_name_at, bg)
                           : fb_suggest(target, fb_bg_nelements(bg), ml_element_name_at, bg);
    char hint[256] = "";
    if (near)
      snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
    return ml_fail(c, at, FB_EMODEL, "unknown %s '%s'%s", on_bond ? "bond" : "element", target,
                   hint);
  }
  if (on_bond) {
    *dim = fb_bg_bond_dim(bg, (size_t)i);
    return FB_OK;
  }
  fb_bg_kind k = fb_bg_element_kind(bg, (size_t)i);
  if (k != FB_BG_I && k != FB_BG_C)
    return ml_fail(c, at, FB_EMODEL, "%s probes need an I or C element; '%s' is of kind %s",
                   ml_probe_kinds[kind], target, fb_bg_kind_name(k));
  *dim = kind == FB_PROBE_ENERGY ? 1 : fb_bg_element_dim(bg, (size_t)i);
  return FB_OK;
}

/* `component` (1-based in the file) to the spec's 0-based index, -1 for
 * all components when absent. */
static int ml_probe_component(const ml_ctx *c, struct fy_node *p, fb_probe_kind kind,
                              size_t dim, long *component)
{
  struct fy_node *key = NULL;
  struct fy_node *v = ml_get(p, "component", &key);
  *component = -1;
  if (!key)
    return FB_OK;
  if (kind == FB_PROBE_ENERGY)
    return ml_fail_key(c, p, key, FB_EPARSE, "an energy probe is a scalar: no component");
  size_t k = 0;
  int rc = ml_count(c, v, c->globals, 1, dim, &k);
  if (!rc)
    *component = (long)k - 1;
  return rc;
}

/* `weights`: one scalar output sum_k w_k v_k over the dim components of
 * the (integrated) signal v, e.g. a torsion angle from a hull's nodal
 * displacements; the array goes into *out (owned by the caller). */
static int ml_probe_weights(const ml_ctx *c, struct fy_node *p, fb_probe_kind kind, size_t dim,
                            fb_probe_spec *spec, double **out)
{
  struct fy_node *key = NULL;
  struct fy_node *v = ml_get(p, "weights", &key);
  *out = NULL;
  if (!key)
    return FB_OK;
  if (kind == FB_PROBE_ENERGY || spec->component >= 0)
    return ml_fail_key(c, p, key, FB_EPARSE,
                       "weights combine all components of a signal: not with %s",
                       kind == FB_PROBE_ENERGY ? "an energy probe" : "'component'");
  size_t len = 0;
  int rc = ml_vector(c, v, c->globals, dim, dim == 1, out, &len);
  spec->weights = *out;
  spec->nweights = rc ? 0 : len;
  return rc;
}

/* Probe names are CSV column headers: no separators or quotes. */
static int ml_probe_name_ok(const char *s)
{
  if (!*s)
    return 0;
  for (; *s; ++s)
    if (*s == ',' || *s == '"' || *s == ' ' || (unsigned char)*s < 0x20)
      return 0;
  return 1;
}

/* The probe's name: given, or "target.kind". */
static int ml_probe_name(const ml_ctx *c, const fb_model *m, struct fy_node *p,
                         const char *target, fb_probe_kind kind, char **out)
{
  struct fy_node *nv = ml_get(p, "name", NULL);
  const char *given = NULL;
  *out = NULL;
  if (nv) {
    int rc = ml_string(c, nv, &given);
    if (rc)
      return rc;
    if (!ml_probe_name_ok(given))
      return ml_fail(c, nv, FB_EPARSE,
                     "probe name '%s' must be non-empty, without spaces, commas or quotes",
                     given);
  }
  size_t need = given ? strlen(given) + 1 : strlen(target) + 8;
  char *name = malloc(need);
  if (!name)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  if (given)
    snprintf(name, need, "%s", given);
  else
    snprintf(name, need, "%s.%s", target, ml_probe_kinds[kind]);
  for (size_t i = 0; i < m->nprobes; ++i)
    if (!strcmp(m->probes[i].name, name)) {
      int rc = ml_fail(c, nv ? nv : p, FB_EMODEL, "duplicate probe name '%s'%s", name,
                       given ? "" : " (give this probe a name)");
      free(name);
      return rc;
    }
  *out = name;
  return FB_OK;
}

/* Fills spec (strings go into m->strings[3i..3i+2]). */
static int ml_probe(const ml_ctx *c, fb_model *m, struct fy_node *p)
{
  static const char *const keys[] = {"name",    "effort",      "flow",      "power", "state",
                                     "energy",  "component",   "integrate", "gain",  "unit",
                                     "weights", "description", NULL};
  fb_probe_spec spec = {NULL, FB_PROBE_EFFORT, NULL, -1, 0, 1.0, NULL, NULL, 0};
  struct fy_node *tv = NULL, *iv = ml_get(p, "integrate", NULL), *uv = ml_get(p, "unit", NULL);
  const char *target = NULL, *unit = NULL;
  size_t dim = 0;
  char **own = m->strings + 3 * m->nprobes;
  int rc = ml_expect_map(c, p, "a probe {name, effort|flow|power|state|energy, ...}");
  if (!rc)
    rc = ml_check_keys(c, p, keys);
  if (!rc)
    rc = ml_probe_kind(c, p, &spec.kind, &tv);
  if (!rc)
    rc = ml_string(c, tv, &target);
  if (!rc)
    rc = ml_probe_target(c, m->bg, tv, spec.kind, target, &dim);
  if (!rc)
    rc = ml_probe_component(c, p, spec.kind, dim, &spec.component);
  if (!rc)
    rc = ml_probe_weights(c, p, spec.kind, dim, &spec, &m->weights[m->nprobes]);
  if (!rc && iv)
    rc = ml_bool(c, iv, &spec.integrate);
  if (!rc)
    rc = ml_opt_number(c, p, "gain", c->globals, &spec.gain);
  if (!rc && uv)
    rc = ml_string(c, uv, &unit);
  /* The domain's unit no longer applies to a scaled value. */
  if (!rc && spec.gain != 1.0 && !unit)
    rc = ml_fail(c, ml_get(p, "gain", NULL), FB_EMODEL,
                 "a gain changes the unit: give 'unit' too");
  if (!rc)
    rc = ml_probe_name(c, m, p, target, spec.kind, &own[0]);
  if (rc)
    return rc;
  own[1] = fb_strdup(target);
  own[2] = unit ? fb_strdup(unit) : NULL;
  if (!own[1] || (unit && !own[2]))
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  spec.name = own[0];
  spec.target = own[1];
  spec.unit = own[2];
  m->probes[m->nprobes++] = spec;
  return FB_OK;
}

static int ml_probes(const ml_ctx *c, fb_model *m, struct fy_node *root)
{
  struct fy_node *key = NULL;
  struct fy_node *list = ml_get(root, "probes", &key);
  if (!key || ml_is_null(list))
    return FB_OK;
  int rc = ml_expect_seq(c, list, "a list of probes");
  size_t n = rc ? 0 : (size_t)fy_node_sequence_item_count(list);
  if (rc || n == 0)
    return rc;
  m->probes = calloc(n, sizeof *m->probes);
  m->strings = calloc(3 * n, sizeof *m->strings);
  m->weights = calloc(n, sizeof *m->weights);
  if (!m->probes || !m->strings || !m->weights)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  m->probe_capacity = n;
  for (size_t i = 0; !rc && i < n; ++i)
    rc = ml_probe(c, m, fy_node_sequence_get_by_index(list, (int)i));
  return rc;
}

/* ---- Simulation settings. */

static int ml_breakpoints(const ml_ctx *c, fb_model *m, struct fy_node *sim)
{
  struct fy_node *key = NULL;
  struct fy_node *v = ml_get(sim, "breakpoints", &key);
  if (!key || ml_is_null(v) || (fy_node_is_sequence(v) && fy_node_sequence_item_count(v) == 0))
    return FB_OK;
  size_t n = 0;
  int rc = ml_vector(c, v, c->globals, 0, 1, &m->breakpoints, &n);
  m->opts.breakpoints = m->breakpoints;
  m->opts.nbreakpoints = n;
  return rc;
}

/* fb_sim_opts_check names the setting in err->key ("rtol"): the message
 * becomes "FILE:LINE:COL: simulation.rtol: ..." at that key's value when
 * the file has it, else at the section (or the top of the file when the
 * section is absent: the default is at fault). */
static int ml_blame_option(const ml_ctx *c, struct fy_node *sim, struct fy_node *root)
{
  char key[FB_ERR_KEY_MAX], base[FB_ERR_KEY_MAX];
  snprintf(key, sizeof key, "%s", c->err->key);
  /* "breakpoints[1]": the value is the list's. */
  snprintf(base, sizeof base, "%.*s", (int)strcspn(key, "["), key);
  struct fy_node *v = (sim && *base) ? ml_get(sim, base, NULL) : NULL;
  if (*key)
    fb_err_prefix(c->err, "simulation.%s: ", key);
  const int rc = ml_blame_located(c, v ? v : sim ? sim : root);
  if (*key)
    fb_err_set_key(c->err, "simulation.%s", key);
  return rc;
}

/* `initial: given | zero | static`. */
static int ml_initial(const ml_ctx *c, fb_model *m, struct fy_node *sim)
{
  static const char *const names[] = {"given", "zero", "static", NULL};
  struct fy_node *v = ml_get(sim, "initial", NULL);
  const char *text = NULL;
  int rc = v ? ml_string(c, v, &text) : FB_OK;
  for (size_t i = 0; !rc && v && names[i]; ++i)
    if (!strcmp(text, names[i])) {
      m->initial = (fb_model_initial)i;
      return FB_OK;
    }
  if (!rc && v)
    rc = ml_fail(c, v, FB_EPARSE, "expected given, zero or static (got '%s')", text);
  return rc;
}

/* The keys of a `simulation` mapping over the defaults in m->opts. */
static int ml_sim_settings(const ml_ctx *c, fb_model *m, struct fy_node *sim)
{
  static const char *const keys[] = {"t_start",
                                     "t_end",
                                     "rtol",
                                     "atol",
                                     "max_step",
                                     "sample_rate",
                                     "max_order",
                                     "max_steps",
                                     "breakpoints",
                                     "initial",
                                     "stability_limit_detection",
                                     NULL};
  fb_sim_opts *o = &m->opts;
  double *const reals[] = {&o->t_start, &o->t_end,    &o->rtol,
                           &o->atol,    &o->max_step, &o->sample_rate};
  int rc = ml_expect_map(c, sim, "simulation settings");
  if (!rc)
    rc = ml_check_keys(c, sim, keys);
  for (size_t i = 0; !rc && i < sizeof reals / sizeof reals[0]; ++i)
    rc = ml_opt_number(c, sim, keys[i], c->globals, reals[i]);
  struct fy_node *v = NULL;
  size_t count = 0;
  if (!rc && (v = ml_get(sim, "max_order", NULL)) &&
      !(rc = ml_count(c, v, c->globals, 1, 5, &count)))
    o->max_order = (int)count;
  if (!rc && (v = ml_get(sim, "max_steps", NULL)) &&
      !(rc = ml_count(c, v, c->globals, 1, (size_t)LONG_MAX, &count)))
    o->max_steps = (long)count;
  if (!rc && (v = ml_get(sim, "stability_limit_detection", NULL)))
    rc = ml_bool(c, v, &o->stability_limit_detection);
  if (!rc)
    rc = ml_breakpoints(c, m, sim);
  if (!rc)
    rc = ml_initial(c, m, sim);
  return rc;
}

static int ml_simulation(const ml_ctx *c, fb_model *m, struct fy_node *root)
{
  struct fy_node *key = NULL;
  struct fy_node *sim = ml_get(root, "simulation", &key);
  fb_sim_opts_default(&m->opts);
  int rc = (key && !ml_is_null(sim)) ? ml_sim_settings(c, m, sim) : FB_OK;
  if (!rc && fb_sim_opts_check(&m->opts, c->err))
    rc = ml_blame_option(c, key ? sim : NULL, root);
  return rc;
}

/* ---- The model. */

static int ml_model_name(const ml_ctx *c, fb_model *m, struct fy_node *root)
{
  struct fy_node *v = NULL;
  const char *name = NULL;
  int rc = ml_require(c, root, "model", &v);
  if (!rc)
    rc = ml_name(c, v, "model name", &name);
  if (rc)
    return rc;
  m->name = fb_strdup(name);
  if (!m->name)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  if (fb_bg_new(name, &m->bg, c->err))
    return ml_blame(c, v);
  return FB_OK;
}

/* The `subsystems` mapping, checked for shape and recursion. */
static int ml_subsystems(ml_ctx *c, struct fy_node *root)
{
  struct fy_node *key = NULL;
  struct fy_node *defs = ml_get(root, "subsystems", &key);
  if (!key || ml_is_null(defs))
    return FB_OK;
  int rc = ml_expect_map(c, defs, "subsystem definitions {name: {...}, ...}");
  if (rc)
    return rc;
  c->defs = defs;
  c->ndefs = (size_t)fy_node_mapping_item_count(defs);
  c->used = calloc(c->ndefs ? c->ndefs : 1, 1);
  if (!c->used)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  return ml_defs_check(c);
}

static int ml_load_root(ml_ctx *c, fb_model *m, struct fy_node *root, fb_symtab *globals)
{
  static const char *const keys[] = {"model",      "description", "domain", "parameters",
                                     "subsystems", "elements",    "bonds",  "probes",
                                     "simulation", NULL};
  struct fy_node *dkey = NULL;
  struct fy_node *dnode = NULL;
  int rc = ml_expect_map(c, root, "a model {model, parameters, elements, bonds, ...}");
  if (!rc)
    rc = ml_check_keys(c, root, keys);
  if (!rc)
    rc = ml_model_name(c, m, root);
  if (!rc && (dnode = ml_get(root, "domain", &dkey), dkey))
    rc = ml_domain(c, dnode, &c->domain);
  if (!rc)
    rc = ml_parameters(c, ml_get(root, "parameters", NULL), globals, NULL);
  if (!rc)
    rc = ml_subsystems(c, root);
  if (rc)
    return rc;
  fb_bg_set_domain(m->bg, c->domain);
  ml_scope top = {m->bg, globals, NULL, 0, 0};
  rc = ml_build_body(c, &top, root);
  ml_scope_release(&top);
  if (!rc)
    rc = ml_defs_validate_unused(c);
  if (!rc)
    rc = ml_probes(c, m, root);
  if (!rc)
    rc = ml_simulation(c, m, root);
  if (!rc)
    rc = ml_warn_power_out(m->bg, &m->sites, &m->warnings, c->err);
  return rc;
}

int fb_model_load_string(const char *text, size_t len, const char *display_name,
                         const char *base_dir, fb_model **out, fb_err *err)
{
  fb_err local;
  /* cppcheck-suppress uninitvar ; only the address of local is taken (false positive) */
  fb_err *e = err ? err : &local;
  fb_err_clear(e);
  if (!out || !text)
    return fb_err_set(e, FB_EINVAL, "fb_model_load_string: text and out must not be NULL");
  *out = NULL;
  ml_ctx c;
  memset(&c, 0, sizeof c);
  c.file = display_name ? display_name : "<string>";
  c.base_dir = base_dir ? base_dir : ".";
  c.err = e;
  c.domain = FB_DOMAIN_TRANSLATION;

  ml_yaml y;
  fb_symtab *globals = NULL;
  fb_model *m = calloc(1, sizeof *m);
  int rc = m ? FB_OK : fb_err_set(e, FB_ENOMEM, "out of memory");
  c.sites = m ? &m->sites : NULL;
  if (!rc)
    rc = fb_symtab_new(&globals, e);
  c.globals = globals;
  /* ml_yaml_parse always initialises y, so it is released on every path. */
  int prc = ml_yaml_parse(text, len, c.file, &y, e);
  if (!rc)
    rc = prc;
  if (!rc)
    rc = ml_refuse_other_format(&c, fy_document_root(y.doc), "model");
  if (!rc)
    rc = ml_load_root(&c, m, fy_document_root(y.doc), globals);
  ml_yaml_release(&y);
  free(c.used);
  fb_symtab_free(&globals);
  if (rc) {
    fb_model_free(&m);
    return rc;
  }
  *out = m;
  return FB_OK;
}

int fb_model_load(const char *path, fb_model **out, fb_err *err)
{
  if (!out || !path)
    return fb_err_set(err, FB_EINVAL, "fb_model_load: path and out must not be NULL");
  *out = NULL;
  char *text = NULL;
  size_t len = 0;
  int rc = fb_read_file(path, &text, &len, err);
  if (rc)
    return rc;
  /* Relative references are resolved from the model's own directory. */
  char *dir = fb_dirname(path);
  if (!dir) {
    free(text);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  rc = fb_model_load_string(text, len, path, dir, out, err);
  free(dir);
  free(text);
  return rc;
}
