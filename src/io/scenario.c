/* SPDX-License-Identifier: BSD-3-Clause */
/* Vehicle scenario files (flexbond/vehicle.h): loading, where each value
 * came from (the description's source: its origins and the plausibility
 * warnings) and locating errors found after loading. The file format is
 * declared in scenario_schema.c. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/hull_source.h"
#include "flexbond/vehicle.h"

#include "core/util.h"
#include "io/scenario_internal.h"

/* ---- The source: where each value was written. */

static void sc_source_free(fb_scenario_source *base)
{
  sc_source *src = (sc_source *)base;
  for (size_t i = 0; src->origin && i < src->norigins; ++i) {
    free(src->origin[i].key);
    free(src->origin[i].path);
    free(src->origin[i].override);
  }
  free(src->origin);
  free(src->warning);
  sc_schema_release(&src->schema);
  free(src);
}

/* *dst = copy of the string src (NULL stays NULL); 0 when out of memory. */
static int sc_copy_string(const char *src, char **dst)
{
  *dst = src ? fb_strdup(src) : NULL;
  return !src || *dst;
}

static int sc_source_clone(const fb_scenario_source *base, fb_scenario_source **out);

static const fb_scenario_source_ops sc_source_ops = {sc_source_clone, sc_source_free};

/* The origins, not the warnings: a copy is edited and checked again. */
static int sc_source_clone(const fb_scenario_source *base, fb_scenario_source **out)
{
  const sc_source *from = (const sc_source *)base;
  sc_source *to = calloc(1, sizeof *to);
  *out = NULL;
  if (!to)
    return FB_ENOMEM;
  to->base.ops = &sc_source_ops;
  to->schema = sc_schema_share(from->schema);
  to->origin = calloc(from->norigins ? from->norigins : 1, sizeof *to->origin);
  int ok = to->origin != NULL;
  for (size_t i = 0; ok && i < from->norigins; ++i) {
    const sc_value_origin *o = &from->origin[i];
    sc_value_origin *c = &to->origin[to->norigins++];
    c->line = o->line;
    c->column = o->column;
    ok = sc_copy_string(o->key, &c->key);
    ok = sc_copy_string(o->path, &c->path) && ok;
    ok = sc_copy_string(o->override, &c->override) && ok;
  }
  if (!ok) {
    sc_source_free(&to->base);
    return FB_ENOMEM;
  }
  *out = &to->base;
  return FB_OK;
}

/* The loader's own sources are recognised by their ops, as a law
 * recognises its own kind (docs/architecture.md). */
sc_source *sc_source_of(const fb_scenario *s)
{
  return s && s->source && s->source->ops == &sc_source_ops ? (sc_source *)s->source : NULL;
}

int sc_source_new(fb_scenario *s, fb_err *err)
{
  sc_source *src = calloc(1, sizeof *src);
  if (!src)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a scenario's origins");
  src->base.ops = &sc_source_ops;
  s->source = &src->base;
  return FB_OK;
}

/* ---- Locating errors found after loading. */

/* 1 if key is prefix followed by a '.' or '[' segment. */
static int sc_encloses(const char *prefix, const char *key, size_t n)
{
  return !strncmp(key, prefix, n) && (key[n] == '.' || key[n] == '[');
}

const sc_value_origin *sc_origin_find(const fb_scenario *s, const char *key, const char **rest)
{
  const sc_value_origin *best = NULL;
  size_t best_len = 0;
  const sc_source *src = sc_source_of(s);
  /* The last of a key is the one blamed: a second corner of one name. */
  for (size_t i = src ? src->norigins : 0; i-- > 0;) {
    const sc_value_origin *o = &src->origin[i];
    const size_t n = strlen(o->key);
    if (!strcmp(o->key, key)) {
      *rest = key + n;
      return o;
    }
    if (n > best_len && sc_encloses(o->key, key, n)) {
      best = o;
      best_len = n;
    }
  }
  *rest = key + best_len;
  return best;
}

int sc_locate(const fb_scenario *s, fb_err *err, int named)
{
  if (!err)
    return FB_EINVAL;
  /* Located already, in this scenario's file (a kept warning made an
   * error): its message has the location. */
  if (err->line > 0 && s && s->path && !strcmp(err->file, s->path))
    return err->code;
  /* An error about a part of the description: the key that gave it, or,
   * where none did, the part in the description's words. */
  if (err->part.kind) {
    char key[FB_ERR_KEY_MAX];
    const sc_source *src = sc_source_of(s);
    if (src && src->norigins && sc_part_key(s, &err->part, key, sizeof key)) {
      fb_err_set_key(err, "%s", key);
    } else {
      char text[FB_ERR_KEY_MAX];
      return fb_err_prefix_location(
          err, "%s: ", fb_scenario_part_text(s, &err->part, text, sizeof text));
    }
  }
  const char *rest = NULL;
  const sc_value_origin *o = s && err->key[0] ? sc_origin_find(s, err->key, &rest) : NULL;
  if (!o) {
    if (!named && err->key[0])
      fb_err_prefix_location(err, "%s: ", err->key);
    return err->code;
  }
  char path[FB_ERR_KEY_MAX];
  snprintf(path, sizeof path, "%s%s", o->path, rest);
  const char *file = s->path ? s->path : "<string>";
  fb_err_set_location(err, file, o->line, o->column);
  fb_err_set_key(err, "%s", path);
  if (o->override)
    fb_err_set_source(err, FB_SOURCE_OVERRIDE, o->override);
  if (named)
    fb_err_prefix_location(err, "%s:%d:%d: ", file, o->line, o->column);
  else
    fb_err_prefix_location(err, "%s:%d:%d: %s: ", file, o->line, o->column, path);
  if (o->override)
    fb_err_prefix(err, "%s: ", o->override);
  return err->code;
}

int fb_scenario_locate(const fb_scenario *s, fb_err *err)
{
  return sc_locate(s, err, 0);
}

/* ---- Loading. */

/* Parses, reads (the overrides in place of the file's values), checks
 * and completes the document; the errors found after reading are located
 * through the values' origins. */
static int sc_load_document(ml_ctx *c, const char *text, size_t len, sch_override *ov,
                            size_t nov, fb_scenario *s)
{
  const sch_table *t = sc_schema_table(sc_source_of(s)->schema);
  ml_yaml y;
  fb_symtab *params = NULL;
  memset(&y, 0, sizeof y);
  int rc = fb_symtab_new(&params, c->err);
  if (!rc)
    rc = ml_yaml_parse(text, len, c->file, &y, c->err);
  if (!rc)
    rc = ml_refuse_other_format(c, fy_document_root(y.doc), "scenario");
  if (!rc && nov)
    rc = sc_overrides_resolve(c, t, fy_document_root(y.doc), ov, nov);
  if (!rc)
    rc = sc_read(c, t, fy_document_root(y.doc), params, ov, nov, s);
  if (!rc)
    rc = sc_plausible_values(s, c->err);
  if (!rc)
    rc = sc_check_ranges(s, c->err);
  if (!rc && fb_scenario_check(s, c->err))
    rc = fb_scenario_locate(s, c->err);
  /* A source that reads its mesh (a deck) reads it here, once: the
   * builder takes the mesh from the scenario. Its errors are at its key
   * hull.mesh.<source>, then at the file's line. */
  if (!rc && fb_scenario_read_hull(s, c->err)) {
    fb_err_set_key(c->err, "hull.mesh.%s", fb_scenario_hull_source(s)->name);
    rc = fb_scenario_locate(s, c->err);
  }
  /* Last: the frame's positions moved to the hull's centre of mass, a
   * finite-element hull's mass properties (src/vehicle/hull_props.c). */
  if (!rc && fb_vehicle_hull_complete(s, c->err))
    rc = fb_scenario_locate(s, c->err);
  /* Then the outputs, where the points and the mesh are final: a hull
   * point on the mesh, a bond in the graph. */
  if (!rc && fb_vehicle_outputs_check(s, c->err))
    rc = fb_scenario_locate(s, c->err);
  if (!rc)
    rc = sc_plausible_rules(s, c->err);
  /* An implausible value is often the cause of the error (a thickness in
   * mm against the hull's mass): the error names the first. */
  if (rc && rc != FB_ENOMEM && fb_scenario_nwarnings(s)) {
    /* Named by its key: the error names the file already. */
    const fb_err *w = fb_scenario_warning(s, 0);
    fb_err_append(c->err, " (the scenario also has an implausible value: %s%s%s)", w->key,
                  w->key[0] ? ": " : "", w->msg + w->text_start);
  }
  if (rc)
    sc_overrides_blame(c->err, ov, nov);
  c->globals = NULL;
  fb_symtab_free(&params);
  ml_yaml_release(&y);
  return rc;
}

int fb_scenario_load_string(const char *text, size_t len, const char *display_name,
                            fb_scenario **out, fb_err *err)
{
  return sc_load(text, len, display_name, ".", NULL, NULL, 0, out, err);
}

int sc_load(const char *text, size_t len, const char *display_name, const char *base_dir,
            const fb_scenario_load_opts *opts, sch_override *ov, size_t nov, fb_scenario **out,
            fb_err *err)
{
  fb_err local;
  /* cppcheck-suppress uninitvar ; only the address of local is taken (false positive) */
  fb_err *e = err ? err : &local;
  fb_err_clear(e);
  if (!out || !text)
    return fb_err_set(e, FB_EINVAL, "fb_scenario_load_string: text and out must not be NULL");
  *out = NULL;
  ml_ctx c;
  memset(&c, 0, sizeof c);
  c.file = display_name ? display_name : "<string>";
  c.base_dir = base_dir;
  c.err = e;
  c.domain = FB_DOMAIN_TRANSLATION;
  ml_paths inputs = {0};
  c.inputs = &inputs;
  fb_scenario *s = calloc(1, sizeof *s);
  /* The path and the source first: errors are located in that file. */
  int rc = s && (!display_name || (s->path = fb_strdup(display_name)))
               ? sc_source_new(s, e)
               : fb_err_set(e, FB_ENOMEM, "out of memory for a scenario");
  if (!rc)
    rc = sc_schema_new(opts, &sc_source_of(s)->schema, e);
  if (!rc)
    rc = sc_load_document(&c, text, len, ov, nov, s);
  if (s) {
    s->inputs = inputs.path;
    s->ninputs = inputs.n;
  } else {
    ml_paths_release(&inputs);
  }
  if (rc) {
    fb_scenario_free(&s);
    return rc;
  }
  *out = s;
  return FB_OK;
}

int sc_load_file(const char *path, const fb_scenario_load_opts *opts, sch_override *ov,
                 size_t nov, fb_scenario **out, fb_err *err)
{
  char *text = NULL;
  size_t len = 0;
  int rc = fb_read_file(path, &text, &len, err);
  /* Relative references are resolved from the scenario's own directory. */
  char *dir = rc ? NULL : fb_dirname(path);
  if (!rc && !dir)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = sc_load(text, len, path, dir, opts, ov, nov, out, err);
  free(dir);
  free(text);
  return rc;
}

int fb_scenario_load(const char *path, fb_scenario **out, fb_err *err)
{
  fb_err_clear(err);
  if (!path || !out)
    return fb_err_set(err, FB_EINVAL, "fb_scenario_load: path and out must not be NULL");
  *out = NULL;
  return sc_load_file(path, NULL, NULL, 0, out, err);
}
