/* SPDX-License-Identifier: BSD-3-Clause */
/* Graph structure in model files: parameters, subsystem definitions and
 * their instances, exported ports, bonds and port references.
 *
 * An instance is built like a 20-sim submodel: its definition's elements
 * and bonds go into a fresh graph, its ports are declared on that graph
 * with fb_bg_add_port, and the graph is adopted into the parent under the
 * instance name (fb_bg_adopt), so "front.Ks" names the element Ks of the
 * instance front. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/util.h"
#include "io/model_internal.h"

/* ---- Parameters. */

static int ml_param_name(const ml_ctx *c, struct fy_node *map, struct fy_node *key,
                         const char **name)
{
  static const char *const reserved[] = {"t", "pi", "e", NULL};
  *name = fy_node_is_scalar(key) ? fy_node_get_scalar0(key) : NULL;
  if (!*name || !ml_is_identifier(*name))
    return ml_fail_key(c, map, key, FB_EPARSE,
                       "parameter names start with a letter or '_' and contain only letters, "
                       "digits and '_'");
  for (size_t i = 0; reserved[i]; ++i)
    if (!strcmp(*name, reserved[i]))
      return ml_fail_key(c, map, key, FB_EPARSE, "'%s' is reserved (%s) in expressions", *name,
                         i == 0 ? "time" : "a constant");
  return FB_OK;
}

/* Every override must name a declared parameter. */
static int ml_check_override(const ml_ctx *c, struct fy_node *defaults,
                             struct fy_node *overrides, struct fy_node *key, const char *owner)
{
  const char *name = fy_node_is_scalar(key) ? fy_node_get_scalar0(key) : NULL;
  if (name && defaults && ml_get(defaults, name, NULL))
    return FB_OK;
  if (!defaults)
    return ml_fail_key(c, overrides, key, FB_EMODEL, "subsystem '%s' has no parameters", owner);
  size_t n = (size_t)fy_node_mapping_item_count(defaults);
  const char **names = malloc((n + 1) * sizeof *names);
  if (!names)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; i < n; ++i)
    names[i] =
        fy_node_get_scalar0(fy_node_pair_key(fy_node_mapping_get_by_index(defaults, (int)i)));
  names[n] = NULL;
  const char *near = name ? fb_suggest_list(name, names) : NULL;
  char hint[256] = "";
  if (near)
    snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
  free(names);
  return ml_fail_key(c, overrides, key, FB_EMODEL, "subsystem '%s' has no parameter '%s'%s",
                     owner, name ? name : "?", hint);
}

/* Evaluates an instance's `parameters` overrides in the parent's table
 * outer into given (new table); every one must be declared in defaults. */
static int ml_overrides(const ml_ctx *c, struct fy_node *defaults, struct fy_node *overrides,
                        const fb_symtab *outer, const char *owner, fb_symtab **given)
{
  int rc = fb_symtab_new(given, c->err);
  if (rc || ml_is_null(overrides))
    return rc;
  if (ml_is_null(defaults))
    defaults = NULL;
  else if ((rc = ml_expect_map(c, defaults, "parameters {name: value, ...}")))
    return rc;
  rc = ml_expect_map(c, overrides, "parameter overrides {name: value, ...}");
  void *iter = NULL;
  struct fy_node_pair *pair;
  while (!rc && (pair = fy_node_mapping_iterate(overrides, &iter))) {
    struct fy_node *key = fy_node_pair_key(pair);
    double v = 0;
    rc = ml_check_override(c, defaults, overrides, key, owner);
    if (!rc)
      rc = ml_number(c, fy_node_pair_value(pair), outer, &v);
    if (!rc && fb_symtab_set(*given, fy_node_get_scalar0(key), v, c->err))
      rc = ml_blame(c, overrides);
  }
  return rc;
}

int ml_parameters(const ml_ctx *c, struct fy_node *defaults, fb_symtab *tab,
                  const fb_symtab *given)
{
  if (ml_is_null(defaults)) /* absent, or `parameters:` with nothing after it */
    defaults = NULL;
  int rc = defaults ? ml_expect_map(c, defaults, "parameters {name: value, ...}") : FB_OK;
  void *iter = NULL;
  struct fy_node_pair *pair;
  while (!rc && defaults && (pair = fy_node_mapping_iterate(defaults, &iter))) {
    const char *name = NULL;
    double v = 0;
    rc = ml_param_name(c, defaults, fy_node_pair_key(pair), &name);
    if (!rc && !(given && fb_symtab_get(given, name, &v)))
      rc = ml_number(c, fy_node_pair_value(pair), tab, &v);
    if (!rc && fb_symtab_set(tab, name, v, c->err))
      rc = ml_blame(c, defaults);
  }
  return rc;
}

/* ---- Definitions. */

static struct fy_node_pair *ml_def_pair(const ml_ctx *c, size_t i)
{
  return fy_node_mapping_get_by_index(c->defs, (int)i);
}

const char *ml_def_name(const ml_ctx *c, size_t i)
{
  return fy_node_get_scalar0(fy_node_pair_key(ml_def_pair(c, i)));
}

static struct fy_node *ml_def_body(const ml_ctx *c, size_t i)
{
  return fy_node_pair_value(ml_def_pair(c, i));
}

long ml_def_find(const ml_ctx *c, const char *name)
{
  for (size_t i = 0; i < c->ndefs; ++i) {
    const char *n = ml_def_name(c, i);
    if (n && !strcmp(n, name))
      return (long)i;
  }
  return -1;
}

static int ml_def_shape(const ml_ctx *c, size_t i)
{
  static const char *const keys[] = {"description", "parameters", "domain", "ports",
                                     "elements",    "bonds",      NULL};
  struct fy_node *key = fy_node_pair_key(ml_def_pair(c, i));
  const char *name = ml_def_name(c, i);
  if (!name || !ml_is_identifier(name))
    return ml_fail_key(c, c->defs, key, FB_EPARSE,
                       "subsystem names start with a letter or '_' and contain only letters, "
                       "digits and '_'");
  if (ml_is_builtin_type(name))
    return ml_fail_key(c, c->defs, key, FB_EMODEL,
                       "subsystem name '%s' is a built-in element type", name);
  struct fy_node *body = ml_def_body(c, i);
  int rc =
      ml_expect_map(c, body, "a subsystem definition {parameters, ports, elements, bonds}");
  if (!rc)
    rc = ml_check_keys(c, body, keys);
  return rc;
}

/* Depth-first search over "definition uses definition" edges; a grey
 * definition met again closes a cycle, reported along the stack. */
static int ml_defs_visit(const ml_ctx *c, size_t d, unsigned char *color, size_t *stack,
                         size_t depth)
{
  color[d] = 1;
  stack[depth] = d;
  struct fy_node *elements = ml_get(ml_def_body(c, d), "elements", NULL);
  void *iter = NULL;
  struct fy_node *el;
  while (fy_node_is_sequence(elements) && (el = fy_node_sequence_iterate(elements, &iter))) {
    struct fy_node *type = fy_node_is_mapping(el) ? ml_get(el, "type", NULL) : NULL;
    const char *name = fy_node_is_scalar(type) ? fy_node_get_scalar0(type) : NULL;
    long k = name ? ml_def_find(c, name) : -1;
    if (k < 0 || color[k] == 2)
      continue;
    if (color[k] == 0) {
      int rc = ml_defs_visit(c, (size_t)k, color, stack, depth + 1);
      if (rc)
        return rc;
      continue;
    }
    char chain[1024];
    size_t len = 0, start = 0;
    while (stack[start] != (size_t)k)
      ++start;
    chain[0] = '\0';
    for (size_t j = start; j <= depth && len + 1 < sizeof chain; ++j) {
      int w = snprintf(chain + len, sizeof chain - len, "%s -> ", ml_def_name(c, stack[j]));
      len += w > 0 ? (size_t)w : 0;
    }
    return ml_fail(c, type, FB_EMODEL, "recursive subsystem definition: %s%s", chain,
                   ml_def_name(c, (size_t)k));
  }
  color[d] = 2;
  return FB_OK;
}

int ml_defs_check(ml_ctx *c)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < c->ndefs; ++i)
    rc = ml_def_shape(c, i);
  if (rc || c->ndefs == 0)
    return rc;
  unsigned char *color = calloc(c->ndefs, 1);
  size_t *stack = malloc(c->ndefs * sizeof *stack);
  if (!color || !stack)
    rc = fb_err_set(c->err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; !rc && i < c->ndefs; ++i)
    if (color[i] == 0)
      rc = ml_defs_visit(c, i, color, stack, 0);
  free(color);
  free(stack);
  return rc;
}

/* ---- Port references. */

static const char *ml_entry_name_at(const void *ctx, size_t i)
{
  return ((const ml_scope *)ctx)->entries[i].name;
}

/* Exported port names of definition def, for messages and checks. */
static const char *ml_def_port_name(const ml_ctx *c, size_t def, size_t i)
{
  struct fy_node *ports = ml_get(ml_def_body(c, def), "ports", NULL);
  struct fy_node *p =
      fy_node_is_sequence(ports) ? fy_node_sequence_get_by_index(ports, (int)i) : NULL;
  struct fy_node *name = fy_node_is_mapping(p) ? ml_get(p, "name", NULL) : NULL;
  return fy_node_is_scalar(name) ? fy_node_get_scalar0(name) : NULL;
}

static size_t ml_def_nports(const ml_ctx *c, size_t def)
{
  struct fy_node *ports = ml_get(ml_def_body(c, def), "ports", NULL);
  return fy_node_is_sequence(ports) ? (size_t)fy_node_sequence_item_count(ports) : 0;
}

typedef struct ml_port_list {
  const ml_ctx *c;
  size_t def;
} ml_port_list;

static const char *ml_port_name_at(const void *ctx, size_t i)
{
  const ml_port_list *pl = ctx;
  return ml_def_port_name(pl->c, pl->def, i);
}

static int ml_check_instance_port(const ml_ctx *c, struct fy_node *at, const ml_entry *e,
                                  const char *port)
{
  size_t def = (size_t)e->def, n = ml_def_nports(c, def);
  char list[512];
  size_t len = 0;
  list[0] = '\0';
  for (size_t i = 0; i < n && len + 1 < sizeof list; ++i) {
    const char *p = ml_def_port_name(c, def, i);
    if (port && p && !strcmp(p, port))
      return FB_OK;
    int w = snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", p ? p : "?");
    len += w > 0 ? (size_t)w : 0;
  }
  const char *dname = ml_def_name(c, def);
  if (n == 0)
    return ml_fail(c, at, FB_EMODEL, "subsystem '%s' (instance '%s') exports no ports", dname,
                   e->name);
  if (!port)
    return ml_fail(c, at, FB_EMODEL,
                   "'%s' is a subsystem instance: name one of its ports as '%s.PORT' (%s)",
                   e->name, e->name, list);
  ml_port_list pl = {c, def};
  const char *near = fb_suggest(port, n, ml_port_name_at, &pl);
  char hint[256] = "";
  if (near)
    snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
  return ml_fail(c, at, FB_EMODEL, "subsystem instance '%s' (%s) has no port '%s'%s; ports: %s",
                 e->name, dname, port, hint, list);
}

/* "E.k" with 1 <= k <= n. */
static int ml_port_number(const char *tail, size_t n)
{
  char *end = NULL;
  unsigned long k = strtoul(tail, &end, 10);
  return tail[0] >= '0' && tail[0] <= '9' && !*end && k >= 1 && k <= n;
}

static int ml_check_element_port(const ml_ctx *c, struct fy_node *at, const ml_entry *e,
                                 const char *tail)
{
  const char *name = e->name;
  if (e->kind == FB_BG_J0 || e->kind == FB_BG_J1) {
    if (!tail)
      return FB_OK;
    return ml_fail(c, at, FB_EMODEL,
                   "junction '%s' is connected by its name alone (each bond adds a port)",
                   name);
  }
  if (e->kind == FB_BG_COMPOSITE && tail && !strcmp(tail, "whole"))
    return FB_OK;
  if (tail ? ml_port_number(tail, e->nports) : e->nports == 1)
    return FB_OK;
  if (e->nports == 1)
    return ml_fail(c, at, FB_EMODEL, "'%s' is a one-port element: write '%s'", name, name);
  return ml_fail(c, at, FB_EMODEL, "element '%s' has ports %s.1 to %s.%zu%s", name, name, name,
                 e->nports, e->kind == FB_BG_COMPOSITE ? " and .whole" : "");
}

/* Checks that ref names an element or instance of s and one of its ports;
 * deeper references ("a.b.p") are left to fb_bg. */
static int ml_check_ref(const ml_ctx *c, const ml_scope *s, struct fy_node *at, const char *ref)
{
  char head[256];
  const char *dot = strchr(ref, '.');
  size_t hlen = dot ? (size_t)(dot - ref) : strlen(ref);
  if (hlen == 0 || hlen >= sizeof head)
    return ml_fail(c, at, FB_EMODEL, "malformed port reference '%s'", ref);
  memcpy(head, ref, hlen);
  head[hlen] = '\0';
  const ml_entry *e = ml_scope_find(s, head);
  if (!e) {
    const char *near = fb_suggest(head, s->nentries, ml_entry_name_at, s);
    char hint[256] = "";
    if (near)
      snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
    return ml_fail(c, at, FB_EMODEL, "unknown element '%s'%s", head, hint);
  }
  const char *tail = dot ? dot + 1 : NULL;
  if (e->def < 0)
    return ml_check_element_port(c, at, e, tail);
  if (tail && strchr(tail, '.'))
    return FB_OK;
  return ml_check_instance_port(c, at, e, tail);
}

/* ---- Exported ports of a definition. */

static int ml_port_dir(const ml_ctx *c, struct fy_node *p, fb_bg_dir *dir)
{
  struct fy_node *key = NULL;
  struct fy_node *v = ml_get(p, "direction", &key);
  const char *text = NULL;
  *dir = FB_PORT_IN;
  if (!key)
    return FB_OK;
  int rc = ml_string(c, v, &text);
  if (rc)
    return rc;
  if (!strcmp(text, "in") || !strcmp(text, "out")) {
    *dir = text[0] == 'i' ? FB_PORT_IN : FB_PORT_OUT;
    return FB_OK;
  }
  return ml_fail(c, v, FB_EPARSE,
                 "direction must be 'in' or 'out' (power into or out of the "
                 "subsystem), got '%s'",
                 text);
}

static int ml_def_port(const ml_ctx *c, const ml_scope *cs, struct fy_node *ports,
                       struct fy_node *p, size_t index)
{
  static const char *const keys[] = {"name", "at", "direction", "description", NULL};
  struct fy_node *nv = NULL, *at = NULL;
  const char *name = NULL, *target = NULL;
  fb_bg_dir dir = FB_PORT_IN;
  int rc = ml_expect_map(c, p, "a port {name, at, direction}");
  if (!rc)
    rc = ml_check_keys(c, p, keys);
  if (!rc)
    rc = ml_require(c, p, "name", &nv);
  if (!rc)
    rc = ml_name(c, nv, "port name", &name);
  for (size_t i = 0; !rc && i < index; ++i) {
    struct fy_node *q = fy_node_sequence_get_by_index(ports, (int)i);
    struct fy_node *qn = ml_get(q, "name", NULL);
    const char *other = fy_node_is_scalar(qn) ? fy_node_get_scalar0(qn) : NULL;
    if (other && !strcmp(other, name))
      rc = ml_fail(c, nv, FB_EMODEL, "duplicate port name '%s' (first defined at line %d)",
                   name, ml_line(q));
  }
  if (!rc)
    rc = ml_require(c, p, "at", &at);
  if (!rc)
    rc = ml_string(c, at, &target);
  if (!rc)
    rc = ml_check_ref(c, cs, at, target);
  if (!rc)
    rc = ml_port_dir(c, p, &dir);
  if (!rc && fb_bg_add_port(cs->bg, name, target, dir, c->err))
    rc = ml_blame(c, p);
  return rc;
}

static int ml_def_ports(const ml_ctx *c, const ml_scope *cs, struct fy_node *body)
{
  struct fy_node *key = NULL;
  struct fy_node *ports = ml_get(body, "ports", &key);
  if (!key || ml_is_null(ports))
    return FB_OK;
  int rc = ml_expect_seq(c, ports, "a list of ports");
  size_t n = rc ? 0 : (size_t)fy_node_sequence_item_count(ports);
  for (size_t i = 0; !rc && i < n; ++i)
    rc = ml_def_port(c, cs, ports, fy_node_sequence_get_by_index(ports, (int)i), i);
  return rc;
}

/* ---- Instances. */

/* Builds definition def into *out, named instance. el is the instance's
 * element (NULL when checking an unused definition with its defaults) and
 * outer the parameter table its overrides are evaluated in. */
static int ml_build_def(ml_ctx *c, size_t def, struct fy_node *el, const fb_symtab *outer,
                        const char *instance, fb_bg **out)
{
  struct fy_node *body = ml_def_body(c, def), *dkey = NULL;
  struct fy_node *dnode = ml_get(body, "domain", &dkey);
  struct fy_node *defaults = ml_get(body, "parameters", NULL);
  fb_bg_domain domain = c->domain;
  fb_symtab *given = NULL, *syms = NULL;
  fb_bg *bg = NULL;
  ml_scope cs = {NULL, NULL, NULL, 0, 0};
  ml_frame frame = {instance, el, c->frames};
  c->used[def] = 1;
  /* Overrides belong to the parent: evaluated before entering the frame. */
  int rc = ml_overrides(c, defaults, el ? ml_get(el, "parameters", NULL) : NULL, outer,
                        ml_def_name(c, def), &given);
  if (el)
    c->frames = &frame;
  if (!rc)
    rc = fb_symtab_new(&syms, c->err);
  if (!rc && fb_symtab_merge(syms, c->globals, c->err))
    rc = ml_blame(c, body);
  if (!rc)
    rc = ml_parameters(c, defaults, syms, given);
  if (!rc && dkey)
    rc = ml_domain(c, dnode, &domain);
  if (!rc && fb_bg_new(instance, &bg, c->err))
    rc = ml_blame(c, el ? el : body);
  if (!rc) {
    fb_bg_set_domain(bg, domain);
    cs.bg = bg;
    cs.syms = syms;
    rc = ml_build_body(c, &cs, body);
  }
  if (!rc)
    rc = ml_def_ports(c, &cs, body);
  c->frames = frame.outer;
  ml_scope_release(&cs);
  fb_symtab_free(&syms);
  fb_symtab_free(&given);
  if (rc)
    fb_bg_free(&bg);
  *out = bg;
  return rc;
}

int ml_instantiate(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *instance, size_t def)
{
  fb_bg *child = NULL;
  int rc = ml_build_def(c, def, el, s->syms, instance, &child);
  if (!rc && fb_bg_adopt(s->bg, &child, instance, c->err))
    rc = ml_blame(c, el);
  fb_bg_free(&child);
  return rc;
}

int ml_defs_validate_unused(ml_ctx *c)
{
  /* The scratch graphs are not the model's: their parts have no site. */
  ml_sites *sites = c->sites;
  int rc = FB_OK;
  c->sites = NULL;
  for (size_t i = 0; !rc && i < c->ndefs; ++i) {
    if (c->used[i])
      continue;
    fb_bg *scratch = NULL;
    rc = ml_build_def(c, i, NULL, NULL, ml_def_name(c, i), &scratch);
    fb_bg_free(&scratch);
  }
  c->sites = sites;
  return rc;
}

/* ---- Bonds. */

int ml_domain(const ml_ctx *c, struct fy_node *n, fb_bg_domain *out)
{
  static const char *const names[] = {"translation", "rotation", "electrical",
                                      "hydraulic",   "generic",  NULL};
  static const fb_bg_domain values[] = {FB_DOMAIN_TRANSLATION, FB_DOMAIN_ROTATION,
                                        FB_DOMAIN_ELECTRICAL, FB_DOMAIN_HYDRAULIC,
                                        FB_DOMAIN_GENERIC};
  const char *text = NULL;
  int rc = ml_string(c, n, &text);
  if (rc)
    return rc;
  for (size_t i = 0; names[i]; ++i)
    if (!strcmp(text, names[i])) {
      *out = values[i];
      return FB_OK;
    }
  const char *near = fb_suggest_list(text, names);
  char hint[256] = "";
  if (near)
    snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
  return ml_fail(c, n, FB_EPARSE,
                 "unknown domain '%s'%s; domains: translation, rotation, electrical, "
                 "hydraulic, generic",
                 text, hint);
}

/* The parts of a bond: from its mapping form or its list form
 * [from, to] / [from, to, name]. */
typedef struct ml_bond_spec {
  struct fy_node *from, *to, *name, *domain;
} ml_bond_spec;

static int ml_bond_spec_read(const ml_ctx *c, struct fy_node *b, ml_bond_spec *spec)
{
  static const char *const keys[] = {"name", "from", "to", "domain", "description", NULL};
  memset(spec, 0, sizeof *spec);
  if (fy_node_is_sequence(b)) {
    int n = fy_node_sequence_item_count(b);
    if (n != 2 && n != 3)
      return ml_fail(c, b, FB_EPARSE,
                     "a bond list is [from, to] or [from, to, name], got %d "
                     "items",
                     n);
    spec->from = fy_node_sequence_get_by_index(b, 0);
    spec->to = fy_node_sequence_get_by_index(b, 1);
    spec->name = n == 3 ? fy_node_sequence_get_by_index(b, 2) : NULL;
    return FB_OK;
  }
  if (!fy_node_is_mapping(b))
    return ml_fail(c, b, FB_EPARSE, "expected a bond {from, to, name} or [from, to]");
  int rc = ml_check_keys(c, b, keys);
  if (!rc)
    rc = ml_require(c, b, "from", &spec->from);
  if (!rc)
    rc = ml_require(c, b, "to", &spec->to);
  spec->name = ml_get(b, "name", NULL);
  spec->domain = ml_get(b, "domain", NULL);
  return rc;
}

/* A bond's name: given, or "from->to" as fb_bg would make it (made here
 * so that a duplicate gets a clear message and `domain` can name it). */
static int ml_bond_name(const ml_ctx *c, const ml_scope *s, struct fy_node *b,
                        const ml_bond_spec *spec, const char *from, const char *to, char **out)
{
  const char *given = NULL;
  *out = NULL;
  if (spec->name) {
    int rc = ml_name(c, spec->name, "bond name", &given);
    if (rc)
      return rc;
  }
  size_t need = given ? strlen(given) + 1 : strlen(from) + strlen(to) + 3;
  char *name = malloc(need);
  if (!name)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  if (given)
    snprintf(name, need, "%s", given);
  else
    snprintf(name, need, "%s->%s", from, to);
  if (fb_bg_find_bond(s->bg, name) >= 0) {
    int rc =
        ml_fail(c, spec->name ? spec->name : b, FB_EMODEL, "duplicate bond name '%s'%s", name,
                given ? ""
                      : " (a bond without a name is called 'from->to'; give "
                        "this one a name)");
    free(name);
    return rc;
  }
  *out = name;
  return FB_OK;
}

static int ml_bond(const ml_ctx *c, const ml_scope *s, struct fy_node *b)
{
  ml_bond_spec spec;
  const char *from = NULL, *to = NULL;
  char *name = NULL;
  fb_bg_domain domain = FB_DOMAIN_GENERIC;
  int rc = ml_bond_spec_read(c, b, &spec);
  if (!rc)
    rc = ml_string(c, spec.from, &from);
  if (!rc)
    rc = ml_check_ref(c, s, spec.from, from);
  if (!rc)
    rc = ml_string(c, spec.to, &to);
  if (!rc)
    rc = ml_check_ref(c, s, spec.to, to);
  if (!rc && spec.domain)
    rc = ml_domain(c, spec.domain, &domain);
  if (!rc)
    rc = ml_bond_name(c, s, b, &spec, from, to, &name);
  if (!rc && fb_bg_connect(s->bg, name, from, to, c->err))
    rc = ml_blame(c, b);
  if (!rc)
    rc = ml_site_record(c, FB_ORIGIN_BOND, name, b);
  if (!rc && spec.domain && fb_bg_set_bond_domain(s->bg, name, domain, c->err))
    rc = ml_blame(c, spec.domain);
  free(name);
  return rc;
}

int ml_build_body(ml_ctx *c, ml_scope *s, struct fy_node *body)
{
  struct fy_node *ekey = NULL, *bkey = NULL;
  struct fy_node *elements = ml_get(body, "elements", &ekey);
  int rc = FB_OK;
  if (!ekey)
    rc = ml_fail(c, body, FB_EPARSE, "missing required key 'elements'");
  else if (!ml_is_null(elements)) /* `elements:` alone is an empty list */
    rc = ml_expect_seq(c, elements, "a list of elements");
  void *iter = NULL;
  struct fy_node *item;
  while (!rc && !ml_is_null(elements) && (item = fy_node_sequence_iterate(elements, &iter)))
    rc = ml_add_element(c, s, item);
  struct fy_node *bonds = ml_get(body, "bonds", &bkey);
  if (rc || !bkey || ml_is_null(bonds))
    return rc;
  rc = ml_expect_seq(c, bonds, "a list of bonds");
  iter = NULL;
  while (!rc && (item = fy_node_sequence_iterate(bonds, &iter)))
    rc = ml_bond(c, s, item);
  return rc;
}
