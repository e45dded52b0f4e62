/* Vehicle scenarios (flexbond/vehicle.h): loading, copying, freeing, and
 * the bump timing every wheel follows. The file format is read in
 * scenario_read.c and checked in scenario_check.c. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "io/scenario_internal.h"

const char *fb_corner_name(int corner)
{
  static const char *const names[FB_NCORNERS] = {"LF", "RF", "LM", "RM", "LR", "RR"};
  return (corner >= 0 && corner < FB_NCORNERS) ? names[corner] : NULL;
}

/* ---- Bump timing. The bump's leading edge is a straight line at
 * bump_angle to the lateral (y) axis, left side first, through the left
 * front wheel's contact point at bump_time. Seen from the vehicle, the
 * road moves back at speed V, so the edge reaches a wheel at (x, y) when
 * it has travelled the wheel's distance behind LF, x_LF - x, plus the
 * edge's extra offset at that lateral position, (y_LF - y) tan(angle)
 * (data sheet, "Road and obstacle"). Along its path the wheel then rolls
 * over the bump's length L in L / V. */

double fb_scenario_wheel_start(const fb_scenario *s, int corner)
{
  if (!s || corner < 0 || corner >= FB_NCORNERS)
    return NAN;
  const fb_corner_params *lf = &s->corner[FB_LF], *w = &s->corner[corner];
  if (s->road_kind != FB_ROAD_BUMP)
    return s->road_front_start - lf->x + w->x;
  /* The bump's tracks (fb_road_new_oblique_bump): the leading edge at
   * s = 0 on the left track and at (y_LF - y_RF) tan(angle) on the right
   * one; each wheel reaches its track's edge at its own entry time, which
   * keeps its own lateral position (y) in the timing. */
  const double edge = w->y > 0.0 ? 0.0 : (lf->y - s->corner[FB_RF].y) * tan(s->bump_angle);
  return edge - s->speed * fb_scenario_bump_entry(s, corner);
}

double fb_scenario_bump_entry(const fb_scenario *s, int corner)
{
  if (!s || corner < 0 || corner >= FB_NCORNERS)
    return NAN;
  if (s->road_kind != FB_ROAD_BUMP)
    return -fb_scenario_wheel_start(s, corner) / s->speed;
  const fb_corner_params *lf = &s->corner[FB_LF], *w = &s->corner[corner];
  return s->bump_time + ((lf->x - w->x) + (lf->y - w->y) * tan(s->bump_angle)) / s->speed;
}

double fb_scenario_bump_exit(const fb_scenario *s, int corner)
{
  if (s && s->road_kind != FB_ROAD_BUMP)
    return corner >= 0 && corner < FB_NCORNERS ? s->t_end : NAN;
  return fb_scenario_bump_entry(s, corner) + (s ? s->bump_length / s->speed : NAN);
}

/* ---- Ownership. */

static void sc_free_strings(char **v, size_t n)
{
  for (size_t i = 0; v && i < n; ++i)
    free(v[i]);
  free(v);
}

void fb_scenario_free(fb_scenario **s)
{
  if (!s || !*s)
    return;
  free((*s)->name);
  free((*s)->path);
  free((*s)->load_x);
  free((*s)->load_y);
  free((*s)->hull_deck);
  sc_free_strings((*s)->inputs, (*s)->ninputs);
  sc_free_strings((*s)->set_path, (*s)->nset);
  sc_free_strings((*s)->set_label, (*s)->nset);
  free((*s)->road_profile);
  free(*s);
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

/* *dst = copy of the n doubles at src (NULL stays NULL); 0 when out of
 * memory. */
static int sc_copy_array(const double *src, size_t n, double **dst)
{
  *dst = NULL;
  if (!src)
    return 1;
  *dst = malloc((n ? n : 1) * sizeof **dst);
  if (*dst && n)
    memcpy(*dst, src, n * sizeof **dst);
  return *dst != NULL;
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
  int ok = sc_copy_string(s->name, &copy->name);
  ok = sc_copy_string(s->path, &copy->path) && ok;
  ok = sc_copy_array(s->load_x, s->nload, &copy->load_x) && ok;
  ok = sc_copy_array(s->load_y, s->nload, &copy->load_y) && ok;
  ok = sc_copy_string(s->hull_deck, &copy->hull_deck) && ok;
  ok = sc_copy_strings(s->inputs, s->ninputs, &copy->inputs) && ok;
  ok = sc_copy_strings(s->set_path, s->nset, &copy->set_path) && ok;
  ok = sc_copy_strings(s->set_label, s->nset, &copy->set_label) && ok;
  ok = sc_copy_string(s->road_profile, &copy->road_profile) && ok;
  if (!ok) {
    fb_scenario_free(&copy);
    return fb_err_set(err, FB_ENOMEM, "out of memory copying a scenario");
  }
  *out = copy;
  return FB_OK;
}

/* ---- Loading. */

/* Parses, reads and checks the document; a check failure is reported at
 * the value it names. */
static int sc_load_document(ml_ctx *c, const char *text, size_t len, fb_scenario *s)
{
  ml_yaml y;
  fb_symtab *params = NULL;
  memset(&y, 0, sizeof y);
  int rc = fb_symtab_new(&params, c->err);
  if (!rc)
    rc = ml_yaml_parse(text, len, c->file, &y, c->err);
  struct fy_node *root = rc ? NULL : fy_document_root(y.doc);
  if (!rc)
    rc = sc_read(c, root, params, s);
  if (!rc && fb_scenario_check(s, c->err) != FB_OK)
    rc = sc_blame_check(c, root);
  c->globals = NULL;
  fb_symtab_free(&params);
  ml_yaml_release(&y);
  return rc;
}

/* The "--set KEY=VALUE" that replaced the value msg starts with ("PATH:
 * ..."), NULL if none did. */
static const char *sc_set_label(const fb_scenario *s, const char *msg)
{
  for (size_t i = 0; i < s->nset; ++i) {
    const size_t n = strlen(s->set_path[i]);
    if (!strncmp(msg, s->set_path[i], n) && msg[n] == ':')
      return s->set_label[i];
  }
  return NULL;
}

/* "FILE:LINE:COL: " before err's message when it starts with one of the
 * file's key paths. On the error path only: the file is read and parsed
 * again (it holds the positions; the scenario keeps values). Any failure
 * here leaves the message as it was. */
static void sc_locate_late(const fb_scenario *s, fb_err *err)
{
  const size_t plen = strlen(s->path);
  if (!strncmp(err->msg, s->path, plen) && err->msg[plen] == ':')
    return;
  char *text = NULL;
  size_t len = 0;
  fb_err scratch;
  fb_err_clear(&scratch);
  ml_yaml y;
  memset(&y, 0, sizeof y);
  int rc = fb_read_file(s->path, &text, &len, &scratch);
  if (!rc)
    rc = ml_yaml_parse(text, len, s->path, &y, &scratch);
  if (!rc) {
    ml_ctx c;
    memset(&c, 0, sizeof c);
    c.file = s->path;
    c.err = &scratch;
    scratch = *err;
    sc_blame_late(&c, fy_document_root(y.doc));
    *err = scratch;
  }
  ml_yaml_release(&y);
  free(text);
}

int fb_scenario_blame(const fb_scenario *s, fb_err *err)
{
  if (!err || err->code == FB_OK || !s)
    return err ? err->code : FB_EINVAL;
  /* A value an override replaced is the override's, as when loading:
   * "--set KEY=VALUE: FILE:LINE:COL: KEY: ...". */
  const char *label = sc_set_label(s, err->msg);
  if (s->path)
    sc_locate_late(s, err);
  if (label)
    fb_err_prefix(err, "%s: ", label);
  return err->code;
}

/* fb_scenario_load_string with relative file references (a hull deck, a
 * damper table) resolved from base_dir. */
static int load_string_in(const char *text, size_t len, const char *display_name,
                          const char *base_dir, fb_scenario **out, fb_err *err);

int fb_scenario_load_string(const char *text, size_t len, const char *display_name,
                            fb_scenario **out, fb_err *err)
{
  return load_string_in(text, len, display_name, ".", out, err);
}

static int load_string_in(const char *text, size_t len, const char *display_name,
                          const char *base_dir, fb_scenario **out, fb_err *err)
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
  int rc = s ? sc_load_document(&c, text, len, s)
             : fb_err_set(e, FB_ENOMEM, "out of memory for a scenario");
  if (s) {
    s->inputs = inputs.path;
    s->ninputs = inputs.n;
  } else {
    ml_paths_release(&inputs);
  }
  if (!rc && display_name && !(s->path = fb_strdup(display_name)))
    rc = fb_err_set(e, FB_ENOMEM, "out of memory for a scenario");
  if (rc) {
    fb_scenario_free(&s);
    return rc;
  }
  *out = s;
  return FB_OK;
}

int fb_scenario_load(const char *path, fb_scenario **out, fb_err *err)
{
  fb_err_clear(err);
  if (!path || !out)
    return fb_err_set(err, FB_EINVAL, "fb_scenario_load: path and out must not be NULL");
  *out = NULL;
  char *text = NULL;
  size_t len = 0;
  int rc = fb_read_file(path, &text, &len, err);
  /* Relative references are resolved from the scenario's own directory. */
  char *dir = rc ? NULL : fb_dirname(path);
  if (!rc && !dir)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = load_string_in(text, len, path, dir, out, err);
  free(dir);
  free(text);
  return rc;
}

/* ---- Hook of the overrides (scenario_override.c, flexbond sweep's
 * --set): text edited from the file at path is loaded as that file, so
 * that its relative references (a hull deck, a damper table) resolve from
 * the file's directory, as fb_scenario_load's do. */
int sc_load_edited_file(const char *text, size_t len, const char *path, fb_scenario **out,
                        fb_err *err)
{
  char *dir = fb_dirname(path);
  if (!dir)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  int rc = load_string_in(text, len, path, dir, out, err);
  free(dir);
  return rc;
}
