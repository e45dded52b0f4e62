/* SPDX-License-Identifier: BSD-3-Clause */
/* Vehicle scenarios (flexbond/vehicle.h): loading, copying, freeing,
 * locating errors found after loading, and
 * the bump timing every wheel follows. The file format is declared in
 * scenario_schema.c and checked in scenario_check.c. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "io/scenario_internal.h"

/* ---- Bump timing. The bump's leading edge is a straight line at
 * bump_angle to the lateral (y) axis, left side first, through the first
 * corner's wheel's contact point at bump_time. Seen from the vehicle, the
 * road moves back at speed V, so the edge reaches a wheel at (x, y) when
 * it has travelled the wheel's distance behind the first corner,
 * x_0 - x, plus the edge's extra offset at that lateral position,
 * (y_0 - y) tan(angle) (data sheet, "Road and obstacle"). Along its path
 * the wheel then rolls over the bump's length L in L / V. */

/* Corner index corner of s, NULL if there is none. */
static const fb_corner_params *sc_corner(const fb_scenario *s, int corner)
{
  return s && corner >= 0 && (size_t)corner < s->ncorners ? &s->corner[corner] : NULL;
}

double fb_scenario_wheel_start(const fb_scenario *s, int corner)
{
  const fb_corner_params *w = sc_corner(s, corner);
  if (!w)
    return NAN;
  const fb_corner_params *first = &s->corner[0];
  if (s->road_kind != FB_ROAD_BUMP)
    return s->road_front_start - first->x + w->x;
  /* The bump's tracks (fb_road_new_oblique_bump): the leading edge at
   * s = 0 on the left track and at track_width tan(angle) on the right
   * one; each wheel reaches its track's edge at its own entry time, which
   * keeps its own lateral position (y) in the timing. */
  const double edge = w->y > 0.0 ? 0.0 : fb_scenario_track_width(s) * tan(s->bump_angle);
  return edge - s->speed * fb_scenario_bump_entry(s, corner);
}

double fb_scenario_bump_entry(const fb_scenario *s, int corner)
{
  const fb_corner_params *w = sc_corner(s, corner);
  if (!w)
    return NAN;
  if (s->road_kind != FB_ROAD_BUMP)
    return -fb_scenario_wheel_start(s, corner) / s->speed;
  const fb_corner_params *first = &s->corner[0];
  return s->bump_time + ((first->x - w->x) + (first->y - w->y) * tan(s->bump_angle)) / s->speed;
}

double fb_scenario_bump_exit(const fb_scenario *s, int corner)
{
  if (!sc_corner(s, corner))
    return NAN;
  if (s->road_kind != FB_ROAD_BUMP)
    return s->t_end;
  return fb_scenario_bump_entry(s, corner) + s->bump_length / s->speed;
}

/* ---- Ownership. */

static void sc_free_strings(char **v, size_t n)
{
  for (size_t i = 0; v && i < n; ++i)
    free(v[i]);
  free(v);
}

static void sc_free_output(fb_output_spec *o)
{
  free(o->name);
  free(o->signal);
  free(o->of);
  free(o->bond);
  free(o->unit);
  free(o->title);
  free(o->label);
}

static void sc_free_origin(fb_scenario_origin *o)
{
  free(o->key);
  free(o->path);
  free(o->override);
}

void fb_scenario_free(fb_scenario **s)
{
  if (!s || !*s)
    return;
  fb_scenario *p = *s;
  free(p->name);
  free(p->path);
  free(p->frame_origin);
  free(p->load_x);
  free(p->load_y);
  for (size_t i = 0; p->mount && i < p->nmounts; ++i)
    free(p->mount[i].name);
  free(p->mount);
  for (size_t i = 0; p->point_mass && i < p->npoint_masses; ++i)
    free(p->point_mass[i].name);
  free(p->point_mass);
  for (size_t i = 0; p->section && i < p->nsections; ++i)
    free(p->section[i].set);
  free(p->section);
  for (size_t i = 0; p->corner && i < p->ncorners; ++i)
    free(p->corner[i].name);
  free(p->corner);
  for (size_t i = 0; p->output && i < p->noutputs; ++i)
    sc_free_output(&p->output[i]);
  free(p->output);
  free(p->road_profile);
  fb_road_free(&p->road_profile_data);
  free(p->hull_deck);
  free(p->coupling_surface);
  fb_mesh_free(&p->hull_source_mesh);
  sc_free_strings(p->inputs, p->ninputs);
  for (size_t i = 0; p->origin && i < p->norigins; ++i)
    sc_free_origin(&p->origin[i]);
  free(p->origin);
  free(p->warning);
  free(p);
  *s = NULL;
}

/* *dst = copy of the string src (NULL stays NULL); 0 when out of memory. */
static int sc_copy_string(const char *src, char **dst)
{
  *dst = src ? fb_strdup(src) : NULL;
  return !src || *dst;
}

/* *dst = a copy of the n strings at src (NULL stays NULL), NULL entries
 * where memory ran out; 0 when it did. */
static int sc_copy_strings(char *const *src, size_t n, char ***dst)
{
  *dst = src && n ? calloc(n, sizeof **dst) : NULL;
  int ok = !src || !n || *dst;
  for (size_t i = 0; *dst && i < n; ++i)
    ok = sc_copy_string(src[i], &(*dst)[i]) && ok;
  return ok;
}

/* *dst = a byte copy of the n items of size bytes at src (NULL stays
 * NULL), its owned strings to be copied next; 0 when out of memory. The
 * copy is zeroed until then, so that a failure frees nothing twice. */
static int sc_copy_items(const void *src, size_t n, size_t size, void **dst, void **shallow)
{
  *dst = NULL;
  *shallow = NULL;
  if (!src)
    return 1;
  if (n > SIZE_MAX / size)
    return 0;
  *dst = calloc(n ? n : 1, size);
  *shallow = malloc((n ? n : 1) * size);
  if (*shallow && n)
    memcpy(*shallow, src, n * size);
  return *dst && *shallow;
}

/* *dst = copy of the n doubles at src (NULL stays NULL); 0 when out of
 * memory. */
static int sc_copy_array(const double *src, size_t n, double **dst)
{
  *dst = NULL;
  if (!src)
    return 1;
  if (n > SIZE_MAX / sizeof **dst)
    return 0;
  *dst = malloc((n ? n : 1) * sizeof **dst);
  if (*dst && n)
    memcpy(*dst, src, n * sizeof **dst);
  return *dst != NULL;
}

static int sc_copy_mounts(const fb_scenario *s, fb_scenario *copy)
{
  fb_mount *m = NULL;
  int ok = sc_copy_items(s->mount, s->nmounts, sizeof *m, (void **)&copy->mount, (void **)&m);
  for (size_t i = 0; ok && m && i < s->nmounts; ++i) { /* no m: no mounts */
    copy->mount[i] = m[i];
    ok = sc_copy_string(s->mount[i].name, &copy->mount[i].name);
  }
  free(m);
  return ok;
}

/* The copy's items are zeroed until each is copied, so that a failure
 * frees nothing twice. */
static int sc_copy_point_masses(const fb_scenario *s, fb_scenario *copy)
{
  const size_t n = s->npoint_masses;
  if (!s->point_mass)
    return 1;
  copy->point_mass = calloc(n ? n : 1, sizeof *copy->point_mass);
  int ok = copy->point_mass != NULL;
  for (size_t i = 0; ok && i < n; ++i) {
    copy->point_mass[i] = s->point_mass[i];
    copy->point_mass[i].name = NULL;
    ok = sc_copy_string(s->point_mass[i].name, &copy->point_mass[i].name);
  }
  return ok;
}

static int sc_copy_sections(const fb_scenario *s, fb_scenario *copy)
{
  const size_t n = s->nsections;
  if (!s->section)
    return 1;
  copy->section = calloc(n ? n : 1, sizeof *copy->section);
  int ok = copy->section != NULL;
  for (size_t i = 0; ok && i < n; ++i) {
    copy->section[i] = s->section[i];
    copy->section[i].set = NULL;
    ok = sc_copy_string(s->section[i].set, &copy->section[i].set);
  }
  return ok;
}

static int sc_copy_corners(const fb_scenario *s, fb_scenario *copy)
{
  fb_corner_params *c = NULL;
  int ok =
      sc_copy_items(s->corner, s->ncorners, sizeof *c, (void **)&copy->corner, (void **)&c);
  for (size_t i = 0; ok && c && i < s->ncorners; ++i) { /* no c: no corners */
    copy->corner[i] = c[i];
    ok = sc_copy_string(s->corner[i].name, &copy->corner[i].name);
  }
  free(c);
  return ok;
}

static int sc_copy_output(const fb_output_spec *src, fb_output_spec *dst)
{
  *dst = (fb_output_spec){.figure = src->figure, .window = {src->window[0], src->window[1]}};
  int ok = sc_copy_string(src->name, &dst->name);
  ok = sc_copy_string(src->signal, &dst->signal) && ok;
  ok = sc_copy_string(src->of, &dst->of) && ok;
  ok = sc_copy_string(src->bond, &dst->bond) && ok;
  ok = sc_copy_string(src->unit, &dst->unit) && ok;
  ok = sc_copy_string(src->title, &dst->title) && ok;
  return sc_copy_string(src->label, &dst->label) && ok;
}

static int sc_copy_outputs(const fb_scenario *s, fb_scenario *copy)
{
  fb_output_spec *o = NULL;
  int ok =
      sc_copy_items(s->output, s->noutputs, sizeof *o, (void **)&copy->output, (void **)&o);
  free(o);
  for (size_t i = 0; ok && i < s->noutputs; ++i)
    ok = sc_copy_output(&s->output[i], &copy->output[i]);
  return ok;
}

static int sc_copy_origins(const fb_scenario *s, fb_scenario *copy)
{
  fb_scenario_origin *o = NULL;
  int ok =
      sc_copy_items(s->origin, s->norigins, sizeof *o, (void **)&copy->origin, (void **)&o);
  for (size_t i = 0; ok && i < s->norigins; ++i) {
    const fb_scenario_origin *from = &s->origin[i];
    fb_scenario_origin *to = &copy->origin[i];
    to->line = from->line;
    to->column = from->column;
    ok = sc_copy_string(from->key, &to->key);
    ok = sc_copy_string(from->path, &to->path) && ok;
    ok = sc_copy_string(from->override, &to->override) && ok;
  }
  free(o);
  return ok;
}

int fb_scenario_clone(const fb_scenario *s, fb_scenario **out, fb_err *err)
{
  if (!s || !out)
    return fb_err_set(err, FB_EINVAL, "fb_scenario_clone: scenario and out must not be NULL");
  *out = NULL;
  fb_scenario *copy = malloc(sizeof *copy);
  if (!copy)
    return fb_err_set(err, FB_ENOMEM, "out of memory copying a scenario");
  *copy = *s;
  /* Nothing of s's is owned by the copy until copied below. */
  copy->name = copy->path = copy->frame_origin = copy->road_profile = copy->hull_deck = NULL;
  copy->coupling_surface = NULL;
  copy->load_x = copy->load_y = NULL;
  copy->mount = NULL;
  copy->point_mass = NULL;
  copy->section = NULL;
  copy->corner = NULL;
  copy->output = NULL;
  copy->inputs = NULL;
  copy->origin = NULL;
  copy->warning = NULL;
  copy->nwarnings = 0; /* a copy is edited and checked again: no warnings of s's */
  copy->road_profile_data = NULL;
  copy->hull_source_mesh = NULL;
  int ok = sc_copy_string(s->name, &copy->name);
  ok = sc_copy_string(s->path, &copy->path) && ok;
  ok = sc_copy_string(s->frame_origin, &copy->frame_origin) && ok;
  ok = sc_copy_array(s->load_x, s->nload, &copy->load_x) && ok;
  ok = sc_copy_array(s->load_y, s->nload, &copy->load_y) && ok;
  ok = sc_copy_mounts(s, copy) && ok;
  ok = sc_copy_point_masses(s, copy) && ok;
  ok = sc_copy_sections(s, copy) && ok;
  ok = sc_copy_corners(s, copy) && ok;
  ok = sc_copy_outputs(s, copy) && ok;
  ok = sc_copy_string(s->road_profile, &copy->road_profile) && ok;
  ok = (!s->road_profile_data ||
        fb_road_clone(s->road_profile_data, &copy->road_profile_data, NULL) == FB_OK) &&
       ok;
  ok = sc_copy_string(s->hull_deck, &copy->hull_deck) && ok;
  ok = sc_copy_string(s->coupling_surface, &copy->coupling_surface) && ok;
  ok = (!s->hull_source_mesh ||
        fb_mesh_clone(s->hull_source_mesh, &copy->hull_source_mesh, NULL) == FB_OK) &&
       ok;
  ok = sc_copy_strings(s->inputs, s->ninputs, &copy->inputs) && ok;
  ok = sc_copy_origins(s, copy) && ok;
  if (!ok) {
    fb_scenario_free(&copy);
    return fb_err_set(err, FB_ENOMEM, "out of memory copying a scenario");
  }
  *out = copy;
  return FB_OK;
}

/* ---- Locating errors found after loading. */

/* 1 if key is prefix followed by a '.' or '[' segment. */
static int sc_encloses(const char *prefix, const char *key, size_t n)
{
  return !strncmp(key, prefix, n) && (key[n] == '.' || key[n] == '[');
}

const fb_scenario_origin *sc_origin_find(const fb_scenario *s, const char *key,
                                         const char **rest)
{
  const fb_scenario_origin *best = NULL;
  size_t best_len = 0;
  /* The last of a key is the one blamed: a second corner of one name. */
  for (size_t i = s->norigins; i-- > 0;) {
    const fb_scenario_origin *o = &s->origin[i];
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
  const char *rest = NULL;
  const fb_scenario_origin *o = s && err->key[0] ? sc_origin_find(s, err->key, &rest) : NULL;
  if (!o) {
    if (!named && err->key[0])
      fb_err_prefix(err, "%s: ", err->key);
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
    fb_err_prefix(err, "%s:%d:%d: ", file, o->line, o->column);
  else
    fb_err_prefix(err, "%s:%d:%d: %s: ", file, o->line, o->column, path);
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
  ml_yaml y;
  fb_symtab *params = NULL;
  memset(&y, 0, sizeof y);
  int rc = fb_symtab_new(&params, c->err);
  if (!rc)
    rc = ml_yaml_parse(text, len, c->file, &y, c->err);
  if (!rc)
    rc = ml_refuse_other_format(c, fy_document_root(y.doc), "scenario");
  if (!rc && nov)
    rc = sc_overrides_resolve(c, fy_document_root(y.doc), ov, nov);
  if (!rc)
    rc = sc_read(c, fy_document_root(y.doc), params, ov, nov, s);
  if (!rc)
    rc = sc_plausible_values(s, c->err);
  if (!rc)
    rc = fb_scenario_check(s, c->err);
  /* A hull deck is read here, once: the builder takes the mesh from the
   * scenario. Its errors are at hull.mesh.deck, then at the deck's line. */
  if (!rc && s->hull_deck && fb_mesh_read_file(s->hull_deck, &s->hull_source_mesh, c->err)) {
    fb_err_set_key(c->err, "hull.mesh.deck");
    rc = fb_scenario_locate(s, c->err);
  }
  /* Last: the frame's positions moved to the hull's centre of mass, a
   * finite-element hull's mass properties (src/vehicle/hull_props.c). */
  if (!rc && fb_vehicle_hull_complete(s, c->err))
    rc = fb_scenario_locate(s, c->err);
  if (!rc)
    rc = sc_plausible_rules(s, c->err);
  /* An implausible value is often the cause of the error (a thickness in
   * mm against the hull's mass): the error names the first. */
  if (rc && rc != FB_ENOMEM && s->nwarnings)
    fb_err_append(c->err, " (the scenario also has an implausible value: %s)",
                  s->warning[0].msg);
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
  return sc_load(text, len, display_name, ".", NULL, 0, out, err);
}

int sc_load(const char *text, size_t len, const char *display_name, const char *base_dir,
            sch_override *ov, size_t nov, fb_scenario **out, fb_err *err)
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
  /* The path first: the check locates its errors in that file. */
  int rc = s && (!display_name || (s->path = fb_strdup(display_name)))
               ? sc_load_document(&c, text, len, ov, nov, s)
               : fb_err_set(e, FB_ENOMEM, "out of memory for a scenario");
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

int sc_load_file(const char *path, sch_override *ov, size_t nov, fb_scenario **out, fb_err *err)
{
  char *text = NULL;
  size_t len = 0;
  int rc = fb_read_file(path, &text, &len, err);
  /* Relative references are resolved from the scenario's own directory. */
  char *dir = rc ? NULL : fb_dirname(path);
  if (!rc && !dir)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = sc_load(text, len, path, dir, ov, nov, out, err);
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
  return sc_load_file(path, NULL, 0, out, err);
}
