/* SPDX-License-Identifier: BSD-3-Clause */
/* Scenario overrides (flexbond/vehicle.h, fb_scenario_load_overrides):
 * "--set KEY=VALUE" reads VALUE in place of the file's value at KEY. The
 * schema reader does it (sch_place, io/schema.c): it puts the value into
 * the parsed document at the key's path, so that every check and unit
 * conversion of the reader and of fb_scenario_check applies to it, and
 * its origin names the override. Here: the public functions, bare key
 * names resolved to full paths, and the errors that name overrides. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "io/scenario_internal.h"

/* ---- Bare key names. */

/* Appends a copy of path to p (ml_paths: key paths, in the order found). */
static int ov_paths_add(ml_paths *p, const char *path, fb_err *err)
{
  char *copy = fb_strdup(path);
  if (!copy || fb_grow((void **)&p->path, &p->cap, p->n, sizeof *p->path) != FB_OK) {
    free(copy);
    return fb_err_set(err, FB_ENOMEM, "out of memory looking up a scenario key");
  }
  p->path[p->n++] = copy;
  return FB_OK;
}

/* The last key name of a path ("mass" of "mounts[0].mass"). */
static const char *ov_name(const char *path)
{
  const char *dot = strrchr(path, '.');
  return dot ? dot + 1 : path;
}

/* fb_name_fn over an ml_paths: each path's last key name. */
static const char *ov_name_at(const void *ctx, size_t i)
{
  return ov_name(((const ml_paths *)ctx)->path[i]);
}

/* The path of every mapping key below n (path: n's own key path, len
 * bytes), in document order. */
static int ov_file_keys(struct fy_node *n, char *path, size_t len, ml_paths *p, fb_err *err)
{
  void *iter = NULL;
  int rc = FB_OK;
  struct fy_node *item;
  for (int i = 0; !rc && fy_node_is_sequence(n) && (item = fy_node_sequence_iterate(n, &iter));
       ++i) {
    int k = snprintf(path + len, SCH_PATH_MAX - len, "[%d]", i);
    if (k > 0 && len + (size_t)k < SCH_PATH_MAX)
      rc = ov_file_keys(item, path, len + (size_t)k, p, err);
  }
  struct fy_node_pair *pair;
  while (!rc && fy_node_is_mapping(n) && (pair = fy_node_mapping_iterate(n, &iter))) {
    const char *key = fy_node_get_scalar0(fy_node_pair_key(pair));
    int k = key ? snprintf(path + len, SCH_PATH_MAX - len, "%s%s", len ? "." : "", key) : -1;
    if (k > 0 && len + (size_t)k < SCH_PATH_MAX && !(rc = ov_paths_add(p, path, err)))
      rc = ov_file_keys(fy_node_pair_value(pair), path, len + (size_t)k, p, err);
  }
  path[len] = '\0';
  return rc;
}

/* The keys a bare name may name: the document's, in document order (the
 * first *in_file of p), then those of the format's table that the
 * document leaves out ("simulation.max_steps"), which can be set too. */
static int ov_keys(const sch_table *t, struct fy_node *root, ml_paths *p, size_t *in_file,
                   fb_err *err)
{
  char path[SCH_PATH_MAX] = "";
  int rc = ov_file_keys(root, path, 0, p, err);
  *in_file = p->n;
  for (size_t i = 0; !rc && i < t->n; ++i) {
    size_t j = 0;
    while (j < *in_file && strcmp(p->path[j], t->key[i].path) != 0)
      ++j;
    if (j == *in_file)
      rc = ov_paths_add(p, t->key[i].path, err);
  }
  return rc;
}

/* FB_EINVAL for a name that no key has: a key of a close name, or the
 * sections to start a path from. */
static int ov_no_name(const ml_ctx *c, const sch_table *t, const ml_paths *keys,
                      const char *name)
{
  const char *near = fb_suggest(name, keys->n, ov_name_at, keys);
  for (size_t i = 0; near && i < keys->n; ++i)
    if (ov_name(keys->path[i]) == near)
      return fb_err_set(c->err, FB_EINVAL,
                        "%s: no key '%s' in the scenario (did you mean '%s'?)", c->file, name,
                        keys->path[i]);
  char sections[512];
  sch_key_names(t, "", sections, sizeof sections);
  return fb_err_set(c->err, FB_EINVAL,
                    "%s: no key '%s' in the scenario (give a dotted path from one of its "
                    "sections: %s)",
                    c->file, name, sections);
}

/* The full path of the one key named name into full (SCH_PATH_MAX bytes):
 * the file's, if it has keys of that name (`first_contact` is the file's
 * road's, not every road type's the format has), else the format's. */
static int ov_resolve_name(const ml_ctx *c, const sch_table *t, struct fy_node *root,
                           const char *name, char *full)
{
  ml_paths keys = {0};
  char list[1024] = "";
  size_t n = 0, len = 0, in_file = 0, from = 0, to = 0;
  int rc = ov_keys(t, root, &keys, &in_file, c->err);
  for (size_t i = 0; !rc && i < in_file; ++i)
    n += !strcmp(ov_name(keys.path[i]), name);
  from = n ? 0 : in_file;
  to = n ? in_file : keys.n;
  n = 0;
  for (size_t i = from; !rc && i < to; ++i)
    if (!strcmp(ov_name(keys.path[i]), name) && n++ == 0)
      snprintf(full, SCH_PATH_MAX, "%s", keys.path[i]);
  for (size_t i = from; !rc && n > 1 && i < to && len + 1 < sizeof list; ++i)
    if (!strcmp(ov_name(keys.path[i]), name))
      len = fb_text_append(list, sizeof list, len, "%s%s", len ? ", " : "", keys.path[i]);
  if (!rc && n == 0)
    rc = ov_no_name(c, t, &keys, name);
  if (!rc && n > 1)
    rc = fb_err_set(c->err, FB_EINVAL,
                    "%s: key '%s' is ambiguous: it occurs %zu times (%s); give the dotted path",
                    c->file, name, n, list);
  ml_paths_release(&keys);
  return rc;
}

/* ---- Resolving and blaming. */

/* 1 if text has a control character: it would end a YAML scalar. */
static int ov_has_control(const char *text)
{
  for (const unsigned char *t = (const unsigned char *)text; *t; ++t)
    if (*t < 0x20 || *t == 0x7f)
      return 1;
  return 0;
}

/* o's path in full (o->path holds the key as given). */
static int ov_resolve(const ml_ctx *c, const sch_table *t, struct fy_node *root,
                      sch_override *o)
{
  char name[SCH_PATH_MAX];
  if (!o->path[0])
    return fb_err_set(c->err, FB_EINVAL, "%s: empty key", c->file);
  if (ov_has_control(o->value))
    return fb_err_set(c->err, FB_EINVAL, "%s: the value has a control character or line break",
                      c->file);
  if (strpbrk(o->path, ".[]"))
    return FB_OK;
  snprintf(name, sizeof name, "%s", o->path);
  return ov_resolve_name(c, t, root, name, o->path);
}

int sc_overrides_resolve(const ml_ctx *c, const sch_table *t, struct fy_node *root,
                         sch_override *ov, size_t n)
{
  for (size_t i = 0; i < n; ++i) {
    int rc = ov_resolve(c, t, root, &ov[i]);
    for (size_t j = 0; !rc && j < i; ++j)
      if (!strcmp(ov[j].path, ov[i].path))
        rc = fb_err_set(c->err, FB_EINVAL, "%s: sets %s, which %s sets too", c->file,
                        ov[i].path, ov[j].label);
    if (rc) {
      sch_blame_override(c->err, &ov[i]);
      return rc;
    }
  }
  return FB_OK;
}

void sc_overrides_blame(fb_err *err, const sch_override *ov, size_t n)
{
  int placed = 0;
  for (size_t i = 0; i < n; ++i)
    placed = placed || ov[i].node;
  if (!placed || err->source == FB_SOURCE_OVERRIDE)
    return;
  for (size_t i = n; i-- > 0;)
    fb_err_prefix(err, "%s%s", ov[i].label, i + 1 < n ? " " : ": ");
}

/* ---- Public functions. */

/* Loads text (path NULL) or the file at path with the overrides; fn names
 * the public function for a NULL argument. */
static int ov_load(const char *fn, const char *text, size_t len, const char *name,
                   const char *path, const fb_scenario_load_opts *opts, fb_scenario **out,
                   fb_err *err)
{
  fb_err local;
  /* cppcheck-suppress uninitvar ; only the address of local is taken (false positive) */
  fb_err *e = err ? err : &local;
  fb_err_clear(e);
  const fb_scenario_override *ov = opts ? opts->overrides : NULL;
  const size_t n = opts ? opts->noverrides : 0;
  if (!(text || path) || !out || (n > 0 && !ov))
    return fb_err_set(e, FB_EINVAL, "%s: NULL argument", fn);
  *out = NULL;
  sch_override *o = calloc(n ? n : 1, sizeof *o);
  int rc = o ? FB_OK : fb_err_set(e, FB_ENOMEM, "out of memory for %zu overrides", n);
  for (size_t i = 0; !rc && i < n; ++i) {
    if (!ov[i].key || !ov[i].value)
      rc = fb_err_set(e, FB_EINVAL, "%s: an override without key or value", fn);
    else if (strlen(ov[i].key) >= sizeof o[i].path)
      rc = fb_err_set(e, FB_EINVAL, "%s: key longer than %d bytes", fn, SCH_PATH_MAX - 1);
    if (rc)
      break;
    o[i].value = ov[i].value;
    snprintf(o[i].path, sizeof o[i].path, "%s", ov[i].key);
    if (ov[i].label)
      snprintf(o[i].label, sizeof o[i].label, "%s", ov[i].label);
    else
      snprintf(o[i].label, sizeof o[i].label, "--set %s=%s", ov[i].key, ov[i].value);
  }
  if (!rc)
    rc = path ? sc_load_file(path, opts, o, n, out, e)
              : sc_load(text, len, name, ".", opts, o, n, out, e);
  free(o);
  return rc;
}

int fb_scenario_load_string_overrides(const char *text, size_t len, const char *display_name,
                                      const fb_scenario_override *ov, size_t n,
                                      fb_scenario **out, fb_err *err)
{
  const fb_scenario_load_opts o = {.overrides = ov, .noverrides = n};
  return ov_load("fb_scenario_load_string_overrides", text, len, display_name, NULL, &o, out,
                 err);
}

int fb_scenario_load_string_with(const char *text, size_t len, const char *display_name,
                                 const fb_scenario_load_opts *o, fb_scenario **out, fb_err *err)
{
  return ov_load("fb_scenario_load_string_with", text, len, display_name, NULL, o, out, err);
}

int fb_scenario_load_with(const char *path, const fb_scenario_load_opts *o, fb_scenario **out,
                          fb_err *err)
{
  return ov_load("fb_scenario_load_with", NULL, 0, NULL, path, o, out, err);
}

int fb_scenario_load_overrides(const char *path, const fb_scenario_override *ov, size_t n,
                               fb_scenario **out, fb_err *err)
{
  const fb_scenario_load_opts o = {.overrides = ov, .noverrides = n};
  return ov_load("fb_scenario_load_overrides", NULL, 0, NULL, path, &o, out, err);
}

/* fb_scenario_override_key in the parsed document root of path (the
 * built-in road types). */
static int ov_check_key(const char *path, struct fy_node *root, sch_override *o, fb_err *err)
{
  ml_ctx c;
  memset(&c, 0, sizeof c);
  c.file = path;
  c.err = err;
  sch_reader r = {.c = &c, .ov = o, .nov = 1};
  sc_schema *sc = NULL;
  int rc = ml_expect_map(&c, root, "a mapping of keys");
  if (!rc)
    rc = sc_schema_new(NULL, &sc, err);
  if (!rc)
    rc = sc_overrides_resolve(&c, sc_schema_table(sc), root, o, 1);
  if (!rc)
    rc = sch_place(&r, sc_schema_table(sc), root);
  sc_schema_release(&sc);
  return rc;
}

const char *fb_scenario_key_unit(const char *full_path)
{
  sc_schema *sc = NULL;
  if (!full_path || sc_schema_new(NULL, &sc, NULL))
    return NULL;
  /* Units are the tables' static text: they outlive the schema. */
  const sch_key *k = sch_key_at_path(sc_schema_table(sc), full_path);
  const char *unit = k ? k->unit : NULL;
  sc_schema_release(&sc);
  return unit;
}

int fb_scenario_override_key(const char *path, const char *key, char **full, fb_err *err)
{
  fb_err local;
  /* cppcheck-suppress uninitvar ; only the address of local is taken (false positive) */
  fb_err *e = err ? err : &local;
  fb_err_clear(e);
  if (!path || !key || !full)
    return fb_err_set(e, FB_EINVAL, "fb_scenario_override_key: NULL argument");
  *full = NULL;
  /* Unlabelled: the caller names the key itself. */
  sch_override o = {.value = "0"};
  if (strlen(key) >= sizeof o.path)
    return fb_err_set(e, FB_EINVAL, "%s: key longer than %d bytes", path, SCH_PATH_MAX - 1);
  snprintf(o.path, sizeof o.path, "%s", key);
  char *text = NULL;
  size_t len = 0;
  ml_yaml y;
  memset(&y, 0, sizeof y);
  int rc = fb_read_file(path, &text, &len, e);
  if (!rc)
    rc = ml_yaml_parse(text, len, path, &y, e);
  if (!rc)
    rc = ov_check_key(path, fy_document_root(y.doc), &o, e);
  if (!rc && !(*full = fb_strdup(o.path)))
    rc = fb_err_set(e, FB_ENOMEM, "out of memory");
  ml_yaml_release(&y);
  free(text);
  return rc;
}
