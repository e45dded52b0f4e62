/* The scenario file format (docs/scenario-format.md) as one schema table
 * (io/schema.h), with the hooks for what a table cannot say: a value of
 * several shapes (the load points, a damper table), an axle that makes
 * two corners, the outputs' defaults from their signal kinds, and the
 * rules between keys of one section. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/io.h"

#include "core/util.h"
#include "io/scenario_internal.h"

/* What the hooks share while a document is read (sch_reader.user). */
typedef struct sc_reading {
  fb_scenario *s;
  fb_symtab *params;
  size_t corner_cap, mount_cap, output_cap;
} sc_reading;

/* ---- Conversions between the file's units and the struct's. */

static double sc_kmh_to_ms(double v)
{
  return v / 3.6;
}

static double sc_ms_to_kmh(double v)
{
  return v * 3.6;
}

/* Dividing by 180 first keeps 90 deg exactly pi / 2 (a power-of-two
 * scaling), so the "< 90 deg" bound is exact. */
static double sc_deg_to_rad(double v)
{
  return v / 180 * SC_PI;
}

static double sc_rad_to_deg(double v)
{
  return v * 180 / SC_PI;
}

static const sch_ops sc_kmh = {.to_struct = sc_kmh_to_ms, .from_struct = sc_ms_to_kmh};

/* ---- When a value is there (sch_ops.present). */

static int sc_has_fe_hull(const void *base)
{
  return ((const fb_scenario *)base)->has_fe_hull;
}

static int sc_has_generator(const void *base)
{
  const fb_scenario *s = base;
  return s->has_fe_hull && !s->hull_deck;
}

static int sc_has_frame(const void *base)
{
  return ((const fb_scenario *)base)->frame_origin != NULL;
}

static int sc_has_cg(const void *base)
{
  return ((const fb_scenario *)base)->hull_cg_given;
}

static int sc_has_mass(const void *base)
{
  return ((const fb_scenario *)base)->hull_mass_given;
}

static int sc_is_bump(const void *base)
{
  return ((const fb_scenario *)base)->road_kind == FB_ROAD_BUMP;
}

static int sc_is_iso(const void *base)
{
  return ((const fb_scenario *)base)->road_kind == FB_ROAD_ISO8608;
}

static int sc_is_profile(const void *base)
{
  return ((const fb_scenario *)base)->road_kind == FB_ROAD_PROFILE;
}

static int sc_linear_damper(const void *base)
{
  return ((const fb_corner_params *)base)->damper_npoints == 0;
}

static int sc_table_damper(const void *base)
{
  return ((const fb_corner_params *)base)->damper_npoints > 0;
}

static int sc_has_window(const void *base)
{
  const fb_output_spec *o = base;
  return o->window[0] != 0 || o->window[1] != 0;
}

static const sch_ops sc_frame_present = {.present = sc_has_frame};
static const sch_ops sc_mass_present = {.present = sc_has_mass};
static const sch_ops sc_linear_present = {.present = sc_linear_damper};

/* ---- parameters: evaluated first, seen by every expression after. */

static int sc_read_parameters(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)k;
  (void)base;
  sc_reading *rd = r->user;
  return ml_parameters(r->c, node, rd->params, NULL);
}

static const sch_ops sc_parameters = {.read = sc_read_parameters};

/* ---- hull. */

/* mass, Ixx and Iyy: all or none, and all without a finite-element hull;
 * hull.centre_of_mass only in a frame of the file's own. */
static int sc_hull_done(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)k;
  fb_scenario *s = base;
  static const char *const body[] = {"mass", "Ixx", "Iyy"};
  int given = 0, missing = -1;
  for (int i = 0; i < 3; ++i) {
    if (ml_get(node, body[i], NULL))
      ++given;
    else if (missing < 0)
      missing = i;
  }
  s->hull_mass_given = given == 3;
  if (given > 0 && given < 3)
    return ml_fail(r->c, node, FB_EPARSE,
                   "missing required key '%s': give mass, Ixx and Iyy together, or none of "
                   "them with a finite-element hull",
                   body[missing]);
  if (!given && !s->has_fe_hull)
    return ml_fail(r->c, node, FB_EPARSE,
                   "missing required key 'mass': a hull without hull.mesh and hull.fe needs "
                   "mass, Ixx and Iyy");
  struct fy_node *key = NULL;
  ml_get(node, "centre_of_mass", &key);
  s->hull_cg_given = key != NULL;
  if (key && !s->frame_origin)
    return ml_fail_key(r->c, node, key, FB_EPARSE,
                       "only with a frame (frame.origin): without one, positions are "
                       "relative to the hull's centre of mass");
  return FB_OK;
}

/* hull.mesh and hull.fe: both, or neither. */
static int sc_fe_done(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  fb_scenario *s = base;
  struct fy_node *hull = node ? fy_node_get_parent(node) : NULL;
  const char *other = !strcmp(k->path, "hull.mesh") ? "fe" : "mesh";
  if (node && !ml_get(hull, other, NULL))
    return ml_fail(r->c, hull, FB_EPARSE,
                   "missing required key '%s': hull.mesh and hull.fe go together", other);
  s->has_fe_hull = node != NULL;
  return FB_OK;
}

/* density refines the generator's mesh only. */
static int sc_mesh_done(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  struct fy_node *key = NULL;
  int rc = sc_fe_done(r, k, node, base);
  if (!rc && node && ml_get(node, "deck", NULL) && (ml_get(node, "density", &key), key))
    rc = ml_fail_key(r->c, node, key, FB_EPARSE,
                     "density refines the generator's mesh; a deck is used as it is");
  return rc;
}

static const sch_ops sc_hull_ops = {.done = sc_hull_done};
static const sch_ops sc_mesh_ops = {.done = sc_mesh_done, .present = sc_has_fe_hull};
static const sch_ops sc_fe_ops = {.done = sc_fe_done, .present = sc_has_fe_hull};
static const sch_ops sc_generator_present = {.present = sc_has_generator};
static const sch_ops sc_cg_present = {.present = sc_has_cg};

static int sc_store_bulkheads(sch_reader *r, const sch_key *k, struct fy_node *node,
                              const double *v, size_t n, void *base)
{
  (void)r;
  (void)k;
  (void)node;
  fb_hull_mesh_params *p = &((fb_scenario *)base)->hull_mesh;
  p->nbulkheads = n;
  memcpy(p->bulkhead_x, v, n * sizeof *v);
  return FB_OK;
}

/* "a, b, c" of n numbers. */
static void sc_format_numbers(const double *v, size_t n, char *buf, size_t size)
{
  size_t len = 0;
  buf[0] = '\0';
  for (size_t i = 0; i < n && len + 1 < size; ++i) {
    int w = snprintf(buf + len, size - len, "%s%.10g", i ? ", " : "", v[i]);
    len = w > 0 && len + (size_t)w < size ? len + (size_t)w : size - 1;
  }
}

static void sc_format_bulkheads(const sch_key *k, const void *base, char *buf, size_t size)
{
  (void)k;
  const fb_hull_mesh_params *p = &((const fb_scenario *)base)->hull_mesh;
  sc_format_numbers(p->bulkhead_x, p->nbulkheads, buf, size);
}

static const sch_ops sc_bulkheads = {.store_list = sc_store_bulkheads,
                                     .format = sc_format_bulkheads};

/* ---- load.points: a grid or a list of [x, y]. */

static int sc_set_points(const ml_ctx *c, fb_scenario *s, size_t n)
{
  if (n > SIZE_MAX / sizeof *s->load_x)
    return fb_err_set(c->err, FB_ENOMEM, "%zu load points are too many", n);
  s->load_x = malloc((n ? n : 1) * sizeof *s->load_x);
  s->load_y = malloc((n ? n : 1) * sizeof *s->load_y);
  if (!s->load_x || !s->load_y)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory for %zu load points", n);
  s->nload = n;
  return FB_OK;
}

/* {grid: {x: [...], y: [...]}}: every x with every y, x-major (point
 * i * ny + j is (x[i], y[j])). */
static int sc_grid(const ml_ctx *c, struct fy_node *points, fb_scenario *s)
{
  static const char *const keys[] = {"grid", NULL};
  static const char *const grid_keys[] = {"x", "y", NULL};
  struct fy_node *grid = NULL, *xn = NULL, *yn = NULL;
  double *xs = NULL, *ys = NULL;
  size_t nx = 0, ny = 0;
  int rc = ml_check_keys(c, points, keys);
  if (!rc)
    rc = ml_require(c, points, "grid", &grid);
  if (!rc)
    rc = ml_expect_map(c, grid, "a grid {x: [...], y: [...]}");
  if (!rc)
    rc = ml_check_keys(c, grid, grid_keys);
  if (!rc)
    rc = ml_require(c, grid, "x", &xn);
  if (!rc)
    rc = ml_vector(c, xn, c->globals, 0, 0, &xs, &nx);
  if (!rc)
    rc = ml_require(c, grid, "y", &yn);
  if (!rc)
    rc = ml_vector(c, yn, c->globals, 0, 0, &ys, &ny);
  if (!rc && ny && nx > SIZE_MAX / ny)
    rc = ml_fail(c, grid, FB_EINVAL, "too many load points (%zu x %zu)", nx, ny);
  if (!rc)
    rc = sc_set_points(c, s, nx * ny);
  for (size_t i = 0; !rc && i < nx; ++i)
    for (size_t j = 0; j < ny; ++j) {
      s->load_x[i * ny + j] = xs[i];
      s->load_y[i * ny + j] = ys[j];
    }
  free(xs);
  free(ys);
  return rc;
}

/* [[x, y], ...], each point recorded as load.points[i]. */
static int sc_point_list(sch_reader *r, struct fy_node *points, fb_scenario *s)
{
  const ml_ctx *c = r->c;
  size_t n = (size_t)fy_node_sequence_item_count(points);
  if (n == 0)
    return ml_fail(c, points, FB_EINVAL, "at least one load point is needed");
  int rc = sc_set_points(c, s, n);
  for (size_t i = 0; !rc && i < n; ++i) {
    struct fy_node *item = fy_node_sequence_get_by_index(points, (int)i);
    double *p = NULL;
    size_t len = 0;
    char key[64];
    snprintf(key, sizeof key, "load.points[%zu]", i);
    rc = ml_vector(c, item, c->globals, 2, 0, &p, &len);
    if (!rc) {
      s->load_x[i] = p[0];
      s->load_y[i] = p[1];
      rc = sch_record(r, key, item);
    }
    free(p);
  }
  return rc;
}

static int sc_read_points(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)k;
  if (fy_node_is_mapping(node))
    return sc_grid(r->c, node, base);
  if (fy_node_is_sequence(node))
    return sc_point_list(r, node, base);
  return ml_fail(
      r->c, node, FB_EPARSE,
      "expected the load points as {grid: {x: [...], y: [...]}} or a list of [x, y]");
}

static void sc_format_points(const sch_key *k, const void *base, char *buf, size_t size)
{
  (void)k;
  snprintf(buf, size, "%zu points", ((const fb_scenario *)base)->nload);
}

static const sch_ops sc_points = {.read = sc_read_points, .format = sc_format_points};

/* ---- Lists: mounts, corners (axles make two each), outputs. */

/* A new zeroed item at the end of *arr (n items, capacity *cap). */
static int sc_grow(const sch_reader *r, void **arr, size_t *n, size_t *cap, size_t size,
                   size_t add, void **item)
{
  for (size_t i = 0; i < add; ++i)
    if (fb_grow(arr, cap, *n + i, size))
      return fb_err_set(r->c->err, FB_ENOMEM, "out of memory for %zu items", *n + add);
  *item = (char *)*arr + *n * size;
  memset(*item, 0, add * size);
  *n += add;
  return FB_OK;
}

static int sc_mount_begin(sch_reader *r, const sch_key *k, size_t index, size_t count,
                          void *base, void **item)
{
  (void)k;
  (void)index;
  (void)count;
  fb_scenario *s = base;
  sc_reading *rd = r->user;
  return sc_grow(r, (void **)&s->mount, &s->nmounts, &rd->mount_cap, sizeof *s->mount, 1, item);
}

/* Renames the item's origins to its logical key: kind.name. */
static int sc_relabel(sch_reader *r, size_t mark, const char *item_path, const char *kind,
                      const char *name, int copy)
{
  char prefix[160];
  snprintf(prefix, sizeof prefix, "%s.%s", kind, name);
  return sch_origins_relabel(r, mark, item_path, prefix, copy);
}

static int sc_mount_end(sch_reader *r, const sch_key *k, struct fy_node *node,
                        const char *item_path, size_t mark, void *base, void *item)
{
  (void)k;
  (void)node;
  (void)base;
  return sc_relabel(r, mark, item_path, "mounts", ((fb_mount *)item)->name, 0);
}

static size_t sc_mount_count(const void *base)
{
  return ((const fb_scenario *)base)->nmounts;
}

static const void *sc_mount_at(const void *base, size_t i)
{
  return &((const fb_scenario *)base)->mount[i];
}

static const char *sc_mount_name(const void *item)
{
  return ((const fb_mount *)item)->name;
}

static const sch_ops sc_mounts = {.item_begin = sc_mount_begin,
                                  .item_end = sc_mount_end,
                                  .count = sc_mount_count,
                                  .item_at = sc_mount_at,
                                  .item_name = sc_mount_name};

/* A corner item: one corner, or an axle's two. */
static int sc_corner_begin(sch_reader *r, const sch_key *k, size_t index, size_t count,
                           void *base, void **item)
{
  (void)index;
  (void)count;
  fb_scenario *s = base;
  sc_reading *rd = r->user;
  const size_t add = !strcmp(k->path, "suspensions.axles") ? 2 : 1;
  return sc_grow(r, (void **)&s->corner, &s->ncorners, &rd->corner_cap, sizeof *s->corner, add,
                 item);
}

static int sc_corner_end(sch_reader *r, const sch_key *k, struct fy_node *node,
                         const char *item_path, size_t mark, void *base, void *item)
{
  (void)k;
  (void)node;
  (void)base;
  fb_corner_params *c = item;
  return sc_relabel(r, mark, item_path, "corners", c->name, 0);
}

/* "L" or "R" before name, as the corner's new name. */
static int sc_side_name(const sch_reader *r, char side, const char *name, char **out)
{
  const size_t n = strlen(name) + 2;
  *out = malloc(n);
  if (!*out)
    return fb_err_set(r->c->err, FB_ENOMEM, "out of memory naming a corner");
  snprintf(*out, n, "%c%s", side, name);
  return FB_OK;
}

/* An axle: its left corner L<name> at (x, y), y > 0, and its right one
 * R<name> at (x, -y), with the same values. */
static int sc_axle_end(sch_reader *r, const sch_key *k, struct fy_node *node,
                       const char *item_path, size_t mark, void *base, void *item)
{
  (void)k;
  (void)base;
  fb_corner_params *left = item, *right = left + 1;
  if (!(left->y > 0))
    return ml_fail(r->c, ml_get(node, "y", NULL), FB_EINVAL,
                   "must be > 0 m: an axle's y is its left wheel's, the right one is at -y "
                   "(got %.10g)",
                   left->y);
  char *name = left->name;
  *right = *left;
  right->y = -left->y;
  right->name = NULL;
  int rc = sc_side_name(r, 'L', name, &left->name);
  if (!rc)
    rc = sc_side_name(r, 'R', name, &right->name);
  free(name);
  if (!rc)
    rc = sc_relabel(r, mark, item_path, "corners", right->name, 1);
  if (!rc)
    rc = sc_relabel(r, mark, item_path, "corners", left->name, 0);
  return rc;
}

static size_t sc_corner_count(const void *base)
{
  return ((const fb_scenario *)base)->ncorners;
}

static const void *sc_corner_at(const void *base, size_t i)
{
  return &((const fb_scenario *)base)->corner[i];
}

static const char *sc_corner_name(const void *item)
{
  return ((const fb_corner_params *)item)->name;
}

static const sch_ops sc_axles = {.item_begin = sc_corner_begin,
                                 .item_end = sc_axle_end,
                                 .count = sc_corner_count,
                                 .item_at = sc_corner_at,
                                 .item_name = sc_corner_name};
static const sch_ops sc_single_corners = {.item_begin = sc_corner_begin,
                                          .item_end = sc_corner_end,
                                          .count = sc_corner_count,
                                          .item_at = sc_corner_at,
                                          .item_name = sc_corner_name};

/* At least three corners (a hull on fewer wheels has no static
 * equilibrium). */
static int sc_suspensions_done(sch_reader *r, const sch_key *k, struct fy_node *node,
                               void *base)
{
  (void)k;
  const fb_scenario *s = base;
  if (node && s->ncorners < 3)
    return ml_fail(r->c, node, FB_EINVAL,
                   "at least 3 corners are needed (got %zu): give them as axles (two each) or "
                   "corners",
                   s->ncorners);
  return FB_OK;
}

static const sch_ops sc_suspensions = {.done = sc_suspensions_done};

/* The knots of a damper table into the corner (copied: the scenario is
 * plain data), refusing a table that is not passive or too long. */
static int sc_read_damper_table(sch_reader *r, const sch_key *k, struct fy_node *node,
                                void *base)
{
  (void)k;
  const ml_ctx *c = r->c;
  fb_corner_params *out = base;
  fb_table_law *law = NULL;
  int rc = ml_table_law(c, c->globals, node, &law);
  const double *v = NULL, *f = NULL;
  const size_t n = rc ? 0 : fb_table_law_knots(law, &v, &f);
  if (!rc && n > FB_DAMPER_MAX_POINTS)
    rc = ml_fail(c, node, FB_EINVAL, "a damper table has at most %d points (got %zu)",
                 (int)FB_DAMPER_MAX_POINTS, n);
  if (!rc && fb_table_law_check_passive(law, c->err))
    rc = ml_blame(c, node);
  if (!rc) {
    out->damper_npoints = n;
    memcpy(out->damper_v, v, n * sizeof *v);
    memcpy(out->damper_f, f, n * sizeof *f);
  }
  fb_table_law_free(&law);
  return rc;
}

static void sc_format_damper_table(const sch_key *k, const void *base, char *buf, size_t size)
{
  (void)k;
  snprintf(buf, size, "%zu points", ((const fb_corner_params *)base)->damper_npoints);
}

static const sch_ops sc_damper_table = {
    .read = sc_read_damper_table, .format = sc_format_damper_table, .present = sc_table_damper};

/* ---- outputs. */

static int sc_output_begin(sch_reader *r, const sch_key *k, size_t index, size_t count,
                           void *base, void **item)
{
  (void)k;
  (void)index;
  (void)count;
  fb_scenario *s = base;
  sc_reading *rd = r->user;
  return sc_grow(r, (void **)&s->output, &s->noutputs, &rd->output_cap, sizeof *s->output, 1,
                 item);
}

/* pattern with its "%s" replaced by subject, into *out (new) unless
 * *out is set already (the file gave it). */
static int sc_pattern(const char *pattern, const char *subject, char **out)
{
  if (*out || !pattern)
    return FB_OK;
  const char *at = strstr(pattern, "%s");
  const size_t n = strlen(pattern) + strlen(subject) + 1;
  *out = malloc(n);
  if (!*out)
    return FB_ENOMEM;
  if (at)
    snprintf(*out, n, "%.*s%s%s", (int)(at - pattern), pattern, subject, at + 2);
  else
    snprintf(*out, n, "%s", pattern);
  return FB_OK;
}

/* A bond signal's column: signal_bond, the bond's '.' made '_'. */
static int sc_bond_column(const fb_output_spec *o, char **out)
{
  if (*out)
    return FB_OK;
  const size_t n = strlen(o->signal) + strlen(o->bond) + 2;
  *out = malloc(n);
  if (!*out)
    return FB_ENOMEM;
  snprintf(*out, n, "%s_%s", o->signal, o->bond);
  for (char *p = *out; *p; ++p)
    *p = *p == '.' ? '_' : *p;
  return FB_OK;
}

/* The name, title, label and unit an output takes from its kind. */
static int sc_output_defaults(const ml_ctx *c, fb_output_spec *o, const fb_output_kind *kind)
{
  const int bond = kind->subject == FB_OUTPUT_OF_BOND;
  const char *subject = bond ? o->bond : o->of ? o->of : "";
  int rc = bond ? sc_bond_column(o, &o->name) : sc_pattern(kind->name, subject, &o->name);
  if (!rc)
    rc = sc_pattern(kind->title, subject, &o->title);
  if (!rc)
    rc = sc_pattern(kind->label, subject, &o->label);
  if (!rc)
    rc = sc_pattern(kind->unit, "", &o->unit);
  return rc ? fb_err_set(c->err, FB_ENOMEM, "out of memory for an output") : FB_OK;
}

/* ml_name_fn over the signal kinds. */
static const char *sc_kind_signal(const void *ctx, size_t i)
{
  return ((const fb_output_kind *)ctx)[i].signal;
}

/* The kind of the signal written at node, or an error naming a close one. */
static int sc_output_kind(const ml_ctx *c, struct fy_node *node, const char *signal,
                          const fb_output_kind **out)
{
  *out = fb_vehicle_output_kind_find(signal);
  if (*out)
    return FB_OK;
  size_t n = 0;
  const fb_output_kind *kinds = fb_vehicle_output_kinds(&n);
  const char *near = ml_suggest(signal, n, sc_kind_signal, kinds);
  char hint[96] = "";
  if (near)
    snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
  return ml_fail(c, node, FB_EPARSE,
                 "unknown signal '%s'%s; the signals are in docs/vehicle-outputs.md", signal,
                 hint);
}

/* `of` for a corner's or a mount's signal only, `bond` for a bond's. */
static int sc_output_subject(const ml_ctx *c, struct fy_node *node, const fb_output_spec *o,
                             const fb_output_kind *kind)
{
  const int wants_of =
      kind->subject == FB_OUTPUT_OF_CORNER || kind->subject == FB_OUTPUT_OF_MOUNT;
  const int wants_bond = kind->subject == FB_OUTPUT_OF_BOND;
  const char *what = kind->subject == FB_OUTPUT_OF_CORNER ? "corner" : "mounted body";
  struct fy_node *key = NULL;
  if (wants_of && !o->of)
    return ml_fail(c, node, FB_EPARSE, "missing required key 'of': the %s a %s signal measures",
                   what, o->signal);
  if (!wants_of && o->of && (ml_get(node, "of", &key), key))
    return ml_fail_key(c, node, key, FB_EPARSE, "a %s signal measures no corner or mount",
                       o->signal);
  if (wants_bond && !o->bond)
    return ml_fail(c, node, FB_EPARSE,
                   "missing required key 'bond': the bond of the assembled graph whose %s "
                   "it records",
                   o->signal);
  if (!wants_bond && o->bond && (ml_get(node, "bond", &key), key))
    return ml_fail_key(c, node, key, FB_EPARSE, "only a bond signal names a bond");
  return FB_OK;
}

static int sc_output_end(sch_reader *r, const sch_key *k, struct fy_node *node,
                         const char *item_path, size_t mark, void *base, void *item)
{
  (void)k;
  (void)item_path;
  (void)mark;
  (void)base;
  fb_output_spec *o = item;
  const fb_output_kind *kind = NULL;
  int rc = sc_output_kind(r->c, ml_get(node, "signal", NULL), o->signal, &kind);
  if (!rc)
    rc = sc_output_subject(r->c, node, o, kind);
  return rc ? rc : sc_output_defaults(r->c, o, kind);
}

static size_t sc_output_count(const void *base)
{
  return ((const fb_scenario *)base)->noutputs;
}

static const void *sc_output_at(const void *base, size_t i)
{
  return &((const fb_scenario *)base)->output[i];
}

static const sch_ops sc_outputs = {.item_begin = sc_output_begin,
                                   .item_end = sc_output_end,
                                   .count = sc_output_count,
                                   .item_at = sc_output_at};

static int sc_store_window(sch_reader *r, const sch_key *k, struct fy_node *node,
                           const double *v, size_t n, void *base)
{
  (void)r;
  (void)k;
  (void)node;
  (void)n;
  fb_output_spec *o = base;
  o->window[0] = v[0];
  o->window[1] = v[1];
  return FB_OK;
}

static void sc_format_window(const sch_key *k, const void *base, char *buf, size_t size)
{
  (void)k;
  sc_format_numbers(((const fb_output_spec *)base)->window, 2, buf, size);
}

static const sch_ops sc_window = {
    .store_list = sc_store_window, .format = sc_format_window, .present = sc_has_window};

/* Without an outputs list: every corner's tire_force, in corner order. */
static int sc_default_outputs(sch_reader *r, fb_scenario *s)
{
  const fb_output_kind *kind = fb_vehicle_output_kind_find("tire_force");
  if (!kind)
    return fb_err_set(r->c->err, FB_EMODEL, "no signal kind 'tire_force' for the outputs");
  sc_reading *rd = r->user;
  for (size_t i = 0; i < s->ncorners; ++i) {
    fb_output_spec *o = NULL;
    int rc = sc_grow(r, (void **)&s->output, &s->noutputs, &rd->output_cap, sizeof *s->output,
                     1, (void **)&o);
    if (!rc &&
        (!(o->signal = fb_strdup(kind->signal)) || !(o->of = fb_strdup(s->corner[i].name))))
      rc = fb_err_set(r->c->err, FB_ENOMEM, "out of memory for an output");
    if (!rc)
      rc = sc_output_defaults(r->c, o, kind);
    if (rc)
      return rc;
  }
  return FB_OK;
}

static int sc_root_done(sch_reader *r, struct fy_node *node, void *base)
{
  return ml_get(node, "outputs", NULL) ? FB_OK : sc_default_outputs(r, base);
}

/* ---- road. */

/* The bump: height and length, or a Brazilian type instead. */
static int sc_bump_done(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)k;
  fb_scenario *s = base;
  if (!node)
    return FB_OK;
  s->road_kind = FB_ROAD_BUMP;
  struct fy_node *type_key = NULL, *type = ml_get(node, "type", &type_key);
  const int height = ml_get(node, "height", NULL) != NULL;
  const int length = ml_get(node, "length", NULL) != NULL;
  if (type_key && (height || length))
    return ml_fail_key(r->c, node, type_key, FB_EPARSE,
                       "give either a type or height and length, not both");
  if (!type_key && !(height && length))
    return ml_fail(r->c, node, FB_EPARSE, "missing required key '%s' (or give a type)",
                   height ? "length" : "height");
  const char *name = NULL;
  int rc = type_key ? ml_string(r->c, type, &name) : FB_OK;
  if (!rc && type_key && fb_road_speed_bump(name, &s->bump_height, &s->bump_length, r->c->err))
    rc = ml_blame(r->c, type);
  return rc;
}

static int sc_iso_done(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)r;
  (void)k;
  if (node)
    ((fb_scenario *)base)->road_kind = FB_ROAD_ISO8608;
  return FB_OK;
}

/* Read once here, so that a bad file is reported at its key. */
static int sc_profile_done(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)k;
  fb_scenario *s = base;
  if (!node)
    return FB_OK;
  s->road_kind = FB_ROAD_PROFILE;
  fb_road *road = NULL;
  int rc = fb_road_new_csv(s->road_profile, &road, r->c->err);
  fb_road_free(&road);
  return rc ? ml_blame(r->c, ml_get(node, "file", NULL)) : FB_OK;
}

static const sch_ops sc_bump = {.done = sc_bump_done, .present = sc_is_bump};
static const sch_ops sc_iso = {.done = sc_iso_done, .present = sc_is_iso};
static const sch_ops sc_profile = {.done = sc_profile_done, .present = sc_is_profile};
static const sch_ops sc_deg = {.to_struct = sc_deg_to_rad, .from_struct = sc_rad_to_deg};

/* The road class: one letter A .. H, either case. */
static int sc_read_class(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)k;
  const char *letter = NULL;
  int rc = ml_string(r->c, node, &letter);
  if (!rc && (strlen(letter) != 1 || !strchr("ABCDEFGHabcdefgh", letter[0])))
    rc = ml_fail(r->c, node, FB_EINVAL, "the class is a letter A .. H (got '%s')", letter);
  if (!rc)
    ((fb_scenario *)base)->road_iso.road_class = letter[0];
  return rc;
}

static void sc_format_class(const sch_key *k, const void *base, char *buf, size_t size)
{
  (void)k;
  snprintf(buf, size, "%c", ((const fb_scenario *)base)->road_iso.road_class);
}

static const sch_ops sc_class = {.read = sc_read_class, .format = sc_format_class};

static int sc_store_band(sch_reader *r, const sch_key *k, struct fy_node *node, const double *v,
                         size_t n, void *base)
{
  (void)r;
  (void)k;
  (void)node;
  (void)n;
  fb_road_iso8608_params *p = &((fb_scenario *)base)->road_iso;
  p->n_min = v[0];
  p->n_max = v[1];
  return FB_OK;
}

static void sc_format_band(const sch_key *k, const void *base, char *buf, size_t size)
{
  (void)k;
  const fb_road_iso8608_params *p = &((const fb_scenario *)base)->road_iso;
  snprintf(buf, size, "%.10g, %.10g", p->n_min, p->n_max);
}

static const sch_ops sc_band = {.store_list = sc_store_band, .format = sc_format_band};

/* ---- The table. */

#define S_OFF(f) .store = SCH_STORE_DOUBLE, .offset = offsetof(fb_scenario, f)
#define C_OFF(f) .store = SCH_STORE_DOUBLE, .offset = offsetof(fb_corner_params, f)
#define M_OFF(f) .store = SCH_STORE_DOUBLE, .offset = offsetof(fb_mount, f)
#define O_STR(f) .store = SCH_STORE_STRING, .offset = offsetof(fb_output_spec, f)
#define POSITIVE .bounds = SCH_LO | SCH_LO_OPEN, .lo = 0
#define NONNEGATIVE .bounds = SCH_LO, .lo = 0
#define ROWS(lo_, hi_) .bounds = SCH_LO | SCH_HI, .lo = lo_, .hi = hi_

static const char *const sc_payloads[] = {"weight-only", "lumped", NULL};
static const char *const sc_contacts[] = {"bilateral", "unilateral", NULL};
static const char *const sc_masses[] = {"consistent", "lumped", NULL};
static const char *const sc_initials[] = {"zero", "static", NULL};
static const char *const sc_bump_types[] = {"I", "II", "A", "B", NULL};
static const double sc_band_default[] = {0.011, 2.83};

/* A mounted body: suspensions' and mounts' items. */
static const sch_key sc_mount_keys[] = {
    {.path = "name",
     .type = SCH_NAME,
     .doc = "its name, unique among the mounts",
     .store = SCH_STORE_STRING,
     .offset = offsetof(fb_mount, name)},
    {.path = "mass",
     .type = SCH_NUMBER,
     .unit = "kg",
     POSITIVE,
     .doc = "body mass",
     M_OFF(mass)},
    {.path = "stiffness",
     .type = SCH_NUMBER,
     .unit = "N/m",
     POSITIVE,
     .doc = "spring stiffness",
     M_OFF(stiffness)},
    {.path = "damping",
     .type = SCH_NUMBER,
     .unit = "N s/m",
     NONNEGATIVE,
     .doc = "damper coefficient",
     M_OFF(damping)},
    {.path = "x", .type = SCH_NUMBER, .unit = "m", .doc = "hull attachment point", M_OFF(x)},
    {.path = "y", .type = SCH_NUMBER, .unit = "m", .doc = "hull attachment point", M_OFF(y)},
};
static const sch_table sc_mount_table = {sc_mount_keys,
                                         sizeof sc_mount_keys / sizeof sc_mount_keys[0], NULL};

static const sch_key sc_corner_keys[] = {
    {.path = "name",
     .type = SCH_NAME,
     .doc = "a corner's name; an axle's corners are L and R before it (F: LF, RF)",
     .store = SCH_STORE_STRING,
     .offset = offsetof(fb_corner_params, name)},
    {.path = "x", .type = SCH_NUMBER, .unit = "m", .doc = "hull attachment point", C_OFF(x)},
    {.path = "y",
     .type = SCH_NUMBER,
     .unit = "m",
     .doc = "hull attachment point; an axle's left one, > 0 (the right one is at -y)",
     C_OFF(y)},
    {.path = "spring_k",
     .type = SCH_NUMBER,
     .unit = "N/m",
     POSITIVE,
     .doc = "suspension spring stiffness",
     C_OFF(spring_k)},
    {.path = "damper_c",
     .type = SCH_NUMBER,
     .unit = "N s/m",
     NONNEGATIVE,
     .one_of = "damper",
     .doc = "linear shock absorber coefficient",
     C_OFF(damper_c),
     .ops = &sc_linear_present},
    {.path = "damper_table",
     .type = SCH_CUSTOM,
     .one_of = "damper",
     .type_doc = "`{file, velocity, force}` or `{points: [[v, F], ...]}`",
     .doc = "a nonlinear shock absorber: force (N) against velocity (m/s, compression "
            "positive), 2 to 64 points, passive",
     .ops = &sc_damper_table},
    {.path = "motion_ratio",
     .type = SCH_NUMBER,
     POSITIVE,
     .need = SCH_INHERIT,
     .inherit = "suspensions.motion_ratio",
     .doc = "spring travel / wheel travel relative to the hull",
     C_OFF(motion_ratio)},
    {.path = "wheel",
     .type = SCH_SECTION,
     .need = SCH_OPTIONAL,
     .doc = "this corner's wheel, where it differs from the top-level `wheel`"},
    {.path = "wheel.mass",
     .type = SCH_NUMBER,
     .unit = "kg",
     POSITIVE,
     .need = SCH_INHERIT,
     .inherit = "wheel.mass",
     .doc = "wheel mass",
     C_OFF(wheel_mass)},
    {.path = "wheel.tire_k",
     .type = SCH_NUMBER,
     .unit = "N/m",
     POSITIVE,
     .need = SCH_INHERIT,
     .inherit = "wheel.tire_k",
     .doc = "tire stiffness",
     C_OFF(tire_k)},
    {.path = "wheel.tire_c",
     .type = SCH_NUMBER,
     .unit = "N s/m",
     NONNEGATIVE,
     .need = SCH_INHERIT,
     .inherit = "wheel.tire_c",
     .doc = "tire damping",
     C_OFF(tire_c)},
    {.path = "wheel.tire_contact",
     .type = SCH_CHOICE,
     .need = SCH_INHERIT,
     .inherit = "wheel.tire_contact",
     .choices = sc_contacts,
     .doc = "how the tire meets the road",
     .store = SCH_STORE_INT,
     .offset = offsetof(fb_corner_params, tire_contact)},
};
static const sch_table sc_corner_table = {
    sc_corner_keys, sizeof sc_corner_keys / sizeof sc_corner_keys[0], NULL};

static const sch_key sc_output_keys[] = {
    {.path = "signal",
     .type = SCH_NAME,
     .doc = "what it records: a signal kind (docs/vehicle-outputs.md)",
     O_STR(signal)},
    {.path = "of",
     .type = SCH_NAME,
     .need = SCH_OPTIONAL,
     .doc = "the corner or mount it measures (a corner's or a mount's signal only)",
     O_STR(of)},
    {.path = "bond",
     .type = SCH_TEXT,
     .need = SCH_OPTIONAL,
     .doc = "a bond signal's bond in the assembled graph (`susp_LF.b_tire`)",
     O_STR(bond)},
    {.path = "name",
     .type = SCH_NAME,
     .need = SCH_OPTIONAL,
     .doc = "its CSV column, unique (default: the kind's, `tire_force_LF`)",
     O_STR(name)},
    {.path = "title",
     .type = SCH_TEXT,
     .need = SCH_OPTIONAL,
     .doc = "its figure's title (default: the kind's)",
     O_STR(title)},
    {.path = "label",
     .type = SCH_TEXT,
     .need = SCH_OPTIONAL,
     .doc = "its short label (default: the kind's)",
     O_STR(label)},
    {.path = "figure",
     .type = SCH_WHOLE,
     ROWS(0, 9999),
     .need = SCH_DEFAULT,
     .def = 0,
     .doc = "the number of its figure, unique; 0: none",
     .store = SCH_STORE_INT,
     .offset = offsetof(fb_output_spec, figure)},
    {.path = "window",
     .type = SCH_NUMBERS,
     .unit = "s",
     .need = SCH_OPTIONAL,
     .min_items = 2,
     .max_items = 2,
     .doc = "the time window its figure shows, `[t0, t1]` (default: the run)",
     .ops = &sc_window},
};
static const sch_table sc_output_table = {
    sc_output_keys, sizeof sc_output_keys / sizeof sc_output_keys[0], NULL};

static const sch_key sc_keys[] = {
    {.path = "scenario",
     .type = SCH_NAME,
     .doc = "the scenario's name",
     .store = SCH_STORE_STRING,
     .offset = offsetof(fb_scenario, name)},
    {.path = "description",
     .type = SCH_TEXT,
     .lines = 1,
     .need = SCH_OPTIONAL,
     .doc = "free text, ignored"},
    {.path = "parameters",
     .type = SCH_CUSTOM,
     .need = SCH_OPTIONAL,
     .type_doc = "mapping name: number",
     .doc = "named numbers for the expressions after it, each may use the ones before it; "
            "`t`, `pi`, `e` are reserved",
     .ops = &sc_parameters},
    {.path = "gravity",
     .type = SCH_NUMBER,
     .unit = "m/s^2",
     POSITIVE,
     .doc = "gravitational acceleration",
     S_OFF(gravity)},
    {.path = "frame",
     .type = SCH_SECTION,
     .need = SCH_OPTIONAL,
     .doc = "positions in a frame of the file's own, not the hull's centre of mass",
     .ops = &sc_frame_present},
    {.path = "frame.origin",
     .type = SCH_TEXT,
     .doc = "what the origin of the positions is (`front axle, floor`)",
     .store = SCH_STORE_STRING,
     .offset = offsetof(fb_scenario, frame_origin)},
    {.path = "hull", .type = SCH_SECTION, .doc = "the hull", .ops = &sc_hull_ops},
    {.path = "hull.mass",
     .type = SCH_NUMBER,
     .unit = "kg",
     POSITIVE,
     .need = SCH_OPTIONAL,
     .doc = "hull mass; with mass, Ixx and Iyy left out, the finite-element hull's",
     S_OFF(hull_mass),
     .ops = &sc_mass_present},
    {.path = "hull.Ixx",
     .type = SCH_NUMBER,
     .unit = "kg m^2",
     POSITIVE,
     .need = SCH_OPTIONAL,
     .doc = "roll inertia about the hull's centre of mass",
     S_OFF(hull_ixx),
     .ops = &sc_mass_present},
    {.path = "hull.Iyy",
     .type = SCH_NUMBER,
     .unit = "kg m^2",
     POSITIVE,
     .need = SCH_OPTIONAL,
     .doc = "pitch inertia about the hull's centre of mass",
     S_OFF(hull_iyy),
     .ops = &sc_mass_present},
    {.path = "hull.centre_of_mass",
     .type = SCH_SECTION,
     .need = SCH_OPTIONAL,
     .doc = "the hull's centre of mass in the frame (only with `frame`; default: the mesh's)",
     .ops = &sc_cg_present},
    {.path = "hull.centre_of_mass.x",
     .type = SCH_NUMBER,
     .unit = "m",
     .doc = "its x",
     S_OFF(hull_cg_x)},
    {.path = "hull.centre_of_mass.y",
     .type = SCH_NUMBER,
     .unit = "m",
     .doc = "its y",
     S_OFF(hull_cg_y)},
    {.path = "hull.material", .type = SCH_SECTION, .doc = "the plates' steel (System 2)"},
    {.path = "hull.material.young",
     .type = SCH_NUMBER,
     .unit = "Pa",
     POSITIVE,
     .doc = "Young's modulus",
     S_OFF(young)},
    {.path = "hull.material.poisson",
     .type = SCH_NUMBER,
     .bounds = SCH_LO | SCH_HI | SCH_HI_OPEN,
     .lo = 0,
     .hi = 0.5,
     .doc = "Poisson's ratio",
     S_OFF(poisson)},
    {.path = "hull.material.density",
     .type = SCH_NUMBER,
     .unit = "kg/m^3",
     POSITIVE,
     .doc = "density",
     S_OFF(density)},
    {.path = "hull.material.thickness",
     .type = SCH_NUMBER,
     .unit = "m",
     POSITIVE,
     .doc = "wall thickness",
     S_OFF(thickness)},
    {.path = "hull.edges",
     .type = SCH_SECTION,
     .doc = "the edge lines whose roll difference is the torsion angle"},
    {.path = "hull.edges.front_x",
     .type = SCH_NUMBER,
     .unit = "m",
     .doc = "x of the front edge line, > `rear_x`",
     S_OFF(edge_front_x)},
    {.path = "hull.edges.rear_x",
     .type = SCH_NUMBER,
     .unit = "m",
     .doc = "x of the rear edge line",
     S_OFF(edge_rear_x)},
    {.path = "hull.edges.left_y",
     .type = SCH_NUMBER,
     .unit = "m",
     .doc = "y of each edge's left end, > `right_y`",
     S_OFF(edge_left_y)},
    {.path = "hull.edges.right_y",
     .type = SCH_NUMBER,
     .unit = "m",
     .doc = "y of each edge's right end",
     S_OFF(edge_right_y)},
    {.path = "hull.mesh",
     .type = SCH_SECTION,
     .need = SCH_OPTIONAL,
     .doc = "System 2's hull mesh (with `hull.fe`)",
     .ops = &sc_mesh_ops},
    {.path = "hull.mesh.deck",
     .type = SCH_FILE,
     .one_of = "mesh",
     .doc = "an Abaqus/CalculiX deck with the scenario's node sets",
     .store = SCH_STORE_STRING,
     .offset = offsetof(fb_scenario, hull_deck)},
    {.path = "hull.mesh.density",
     .type = SCH_WHOLE,
     ROWS(1, 64),
     .need = SCH_DEFAULT,
     .def = 1,
     .doc = "refinement of the generator's mesh: d x d elements for each",
     .store = SCH_STORE_INT,
     .offset = offsetof(fb_scenario, hull_mesh.density),
     .ops = &sc_generator_present},
    {.path = "hull.mesh.generator",
     .type = SCH_SECTION,
     .one_of = "mesh",
     .doc = "the built-in generator's geometry (docs/hull-mesh.md)",
     .ops = &sc_generator_present},
    {.path = "hull.mesh.generator.width",
     .type = SCH_NUMBER,
     .unit = "m",
     POSITIVE,
     .doc = "between the side walls",
     S_OFF(hull_mesh.width)},
    {.path = "hull.mesh.generator.height",
     .type = SCH_NUMBER,
     .unit = "m",
     POSITIVE,
     .doc = "floor to roof",
     S_OFF(hull_mesh.height)},
    {.path = "hull.mesh.generator.x_rear",
     .type = SCH_NUMBER,
     .unit = "m",
     .doc = "rear wall",
     S_OFF(hull_mesh.x_rear)},
    {.path = "hull.mesh.generator.x_front",
     .type = SCH_NUMBER,
     .unit = "m",
     .doc = "front end of the box, > `x_rear`",
     S_OFF(hull_mesh.x_front)},
    {.path = "hull.mesh.generator.nose_length",
     .type = SCH_NUMBER,
     .unit = "m",
     POSITIVE,
     .doc = "wedge nose ahead of `x_front`",
     S_OFF(hull_mesh.nose_length)},
    {.path = "hull.mesh.generator.nose_height",
     .type = SCH_NUMBER,
     .unit = "m",
     POSITIVE,
     .doc = "nose tip line above the floor, < `height`",
     S_OFF(hull_mesh.nose_height)},
    {.path = "hull.mesh.generator.bulkheads",
     .type = SCH_NUMBERS,
     .unit = "m",
     .max_items = FB_HULL_MAX_BULKHEADS,
     .doc = "x of the transverse bulkheads, each between `x_rear` and `x_front`",
     .ops = &sc_bulkheads},
    {.path = "hull.mesh.generator.side_rows",
     .type = SCH_WHOLE,
     ROWS(1, 64),
     .doc = "element rows up the walls and bulkheads",
     .store = SCH_STORE_INT,
     .offset = offsetof(fb_scenario, hull_mesh.side_rows)},
    {.path = "hull.mesh.generator.nose_rows",
     .type = SCH_WHOLE,
     ROWS(1, 64),
     .doc = "element rows along each glacis plate",
     .store = SCH_STORE_INT,
     .offset = offsetof(fb_scenario, hull_mesh.nose_rows)},
    {.path = "hull.mesh.generator.nose_rung_divisions",
     .type = SCH_WHOLE,
     ROWS(1, 64),
     .doc = "divisions of the side walls' nose rung",
     .store = SCH_STORE_INT,
     .offset = offsetof(fb_scenario, hull_mesh.nose_rung_divisions)},
    {.path = "hull.fe",
     .type = SCH_SECTION,
     .need = SCH_OPTIONAL,
     .doc = "System 2's finite elements (with `hull.mesh`)",
     .ops = &sc_fe_ops},
    {.path = "hull.fe.mass_matrix",
     .type = SCH_CHOICE,
     .choices = sc_masses,
     .doc = "mass matrix",
     .store = SCH_STORE_INT,
     .offset = offsetof(fb_scenario, hull_mass_matrix)},
    {.path = "hull.fe.drill_factor",
     .type = SCH_NUMBER,
     POSITIVE,
     .doc = "fictitious drilling stiffness of the quadrilaterals (fem.h)",
     S_OFF(hull_drill_factor)},
    {.path = "hull.fe.damping_ratio",
     .type = SCH_NUMBER,
     .bounds = SCH_LO | SCH_HI | SCH_HI_OPEN,
     .lo = 0,
     .hi = 1,
     .doc = "damping ratio of the bare hull's first elastic free-free mode (B = beta K)",
     S_OFF(hull_damping_ratio)},
    {.path = "hull.fe.modes",
     .type = SCH_WHOLE,
     ROWS(0, 100000),
     .need = SCH_DEFAULT,
     .def = 0,
     .doc = "0: full order; N >= 6: N free-free modes and a static correction",
     .store = SCH_STORE_INT,
     .offset = offsetof(fb_scenario, hull_modes)},
    {.path = "load", .type = SCH_SECTION, .doc = "hull plus payload"},
    {.path = "load.total_weight",
     .type = SCH_NUMBER,
     .unit = "N",
     POSITIVE,
     .doc = "weight of hull plus payload, in equal shares over the load points",
     S_OFF(total_weight)},
    {.path = "load.payload",
     .type = SCH_CHOICE,
     .choices = sc_payloads,
     .doc = "payload mass model",
     .store = SCH_STORE_INT,
     .offset = offsetof(fb_scenario, payload)},
    {.path = "load.points",
     .type = SCH_CUSTOM,
     .type_doc = "`{grid: {x: [...], y: [...]}}` or `[[x, y], ...]`",
     .unit = "m",
     .doc = "the load points, on the floor, 1 mm apart at least",
     .ops = &sc_points},
    {.path = "mounts",
     .type = SCH_LIST,
     .need = SCH_OPTIONAL,
     .doc = "bodies on a spring and a damper to a hull point (driver, engine)",
     .items = &sc_mount_table,
     .view = "mounts",
     .ops = &sc_mounts},
    {.path = "wheel",
     .type = SCH_SECTION,
     .need = SCH_OPTIONAL,
     .doc = "every corner's wheel and tire unless the corner gives its own"},
    {.path = "wheel.mass",
     .type = SCH_NUMBER,
     .unit = "kg",
     POSITIVE,
     .need = SCH_OPTIONAL,
     .doc = "wheel mass"},
    {.path = "wheel.tire_k",
     .type = SCH_NUMBER,
     .unit = "N/m",
     POSITIVE,
     .need = SCH_OPTIONAL,
     .doc = "tire stiffness"},
    {.path = "wheel.tire_c",
     .type = SCH_NUMBER,
     .unit = "N s/m",
     NONNEGATIVE,
     .need = SCH_OPTIONAL,
     .doc = "tire damping"},
    {.path = "wheel.tire_contact",
     .type = SCH_CHOICE,
     .choices = sc_contacts,
     .need = SCH_DEFAULT,
     .def = 0,
     .doc = "`bilateral`: the paper's linear tire; `unilateral`: it never pulls, the wheel "
            "may leave the road"},
    {.path = "suspensions",
     .type = SCH_SECTION,
     .doc = "the corners (wheel stations)",
     .ops = &sc_suspensions},
    {.path = "suspensions.motion_ratio",
     .type = SCH_NUMBER,
     POSITIVE,
     .need = SCH_DEFAULT,
     .def = 1,
     .doc = "every corner's spring travel / wheel travel unless it gives its own"},
    {.path = "suspensions.axles",
     .type = SCH_LIST,
     .need = SCH_OPTIONAL,
     .doc = "axles, each two corners: L<name> at (x, y) and R<name> at (x, -y)",
     .items = &sc_corner_table,
     .view = "corners",
     .ops = &sc_axles},
    {.path = "suspensions.corners",
     .type = SCH_LIST,
     .need = SCH_OPTIONAL,
     .doc = "single corners, after the axles' ones",
     .items = &sc_corner_table,
     .view = "corners",
     .ops = &sc_single_corners},
    {.path = "outputs",
     .type = SCH_LIST,
     .need = SCH_OPTIONAL,
     .doc = "the signals recorded, in CSV column order (default: every corner's tire_force)",
     .items = &sc_output_table,
     .view = "outputs",
     .ops = &sc_outputs},
    {.path = "road", .type = SCH_SECTION, .doc = "the road under the wheels"},
    {.path = "road.speed_kmh",
     .type = SCH_NUMBER,
     .unit = "km/h",
     POSITIVE,
     .doc = "constant forward speed on a straight line",
     S_OFF(speed),
     .ops = &sc_kmh},
    {.path = "road.bump",
     .type = SCH_SECTION,
     .one_of = "road",
     .doc = "the paper's oblique (1 - cos) bump",
     .ops = &sc_bump},
    {.path = "road.bump.height",
     .type = SCH_NUMBER,
     .unit = "m",
     NONNEGATIVE,
     .need = SCH_OPTIONAL,
     .doc = "bump height h, with `length` (0: a flat road)",
     S_OFF(bump_height)},
    {.path = "road.bump.length",
     .type = SCH_NUMBER,
     .unit = "m",
     POSITIVE,
     .need = SCH_OPTIONAL,
     .doc = "bump length L along each wheel's path, with `height`",
     S_OFF(bump_length)},
    {.path = "road.bump.type",
     .type = SCH_CHOICE,
     .choices = sc_bump_types,
     .need = SCH_OPTIONAL,
     .doc = "a Brazilian speed bump instead of height and length: I 1.50 x 0.08 m, II 3.70 x "
            "0.10 m (B, A: aliases)"},
    {.path = "road.bump.angle_deg",
     .type = SCH_NUMBER,
     .unit = "deg",
     .bounds = SCH_LO | SCH_HI | SCH_HI_OPEN,
     .lo = 0,
     .hi = 90,
     .doc = "angle of the leading edge to the lateral axis, left side first",
     S_OFF(bump_angle),
     .ops = &sc_deg},
    {.path = "road.bump.first_contact",
     .type = SCH_NUMBER,
     .unit = "s",
     NONNEGATIVE,
     .doc = "time the first corner's wheel meets the leading edge",
     S_OFF(bump_time)},
    {.path = "road.iso8608",
     .type = SCH_SECTION,
     .one_of = "road",
     .doc = "an ISO 8608 random road (docs/roads.md)",
     .ops = &sc_iso},
    {.path = "road.iso8608.class",
     .type = SCH_CUSTOM,
     .type_doc = "letter `A` .. `H`",
     .doc = "road class: Gd(n0) = 16e-6 m^3 for A, times 4 per class",
     .ops = &sc_class},
    {.path = "road.iso8608.seed",
     .type = SCH_WHOLE,
     ROWS(0, 9007199254740992.0),
     .doc = "the same seed gives the same road",
     .store = SCH_STORE_U64,
     .offset = offsetof(fb_scenario, road_iso.seed)},
    {.path = "road.iso8608.band",
     .type = SCH_NUMBERS,
     .unit = "cycles/m",
     .min_items = 2,
     .max_items = 2,
     .need = SCH_DEFAULT,
     .def_list = sc_band_default,
     .doc = "spatial frequency band `[n_min, n_max]` of the harmonics",
     .ops = &sc_band},
    {.path = "road.iso8608.harmonics",
     .type = SCH_WHOLE,
     ROWS(1, (double)FB_ROAD_ISO8608_MAX_HARMONICS),
     .need = SCH_DEFAULT,
     .def = 1024,
     .doc = "harmonics per track (the run's time grows with them)",
     .store = SCH_STORE_SIZE,
     .offset = offsetof(fb_scenario, road_iso.nharmonics)},
    {.path = "road.iso8608.fade_in",
     .type = SCH_NUMBER,
     .unit = "m",
     NONNEGATIVE,
     .need = SCH_DEFAULT,
     .def = 0,
     .doc = "the height fades in over the first metres",
     S_OFF(road_iso.fade_length)},
    {.path = "road.iso8608.front_start",
     .type = SCH_NUMBER,
     .unit = "m",
     .need = SCH_DEFAULT,
     .def = 0,
     .doc = "the first corner's wheel's position on its track at t = 0",
     S_OFF(road_front_start)},
    {.path = "road.profile",
     .type = SCH_SECTION,
     .one_of = "road",
     .doc = "a measured profile (docs/roads.md)",
     .ops = &sc_profile},
    {.path = "road.profile.file",
     .type = SCH_FILE,
     .doc = "CSV with columns `s, z` or `s, z_left, z_right`",
     .store = SCH_STORE_STRING,
     .offset = offsetof(fb_scenario, road_profile)},
    {.path = "road.profile.front_start",
     .type = SCH_NUMBER,
     .unit = "m",
     .need = SCH_DEFAULT,
     .def = 0,
     .doc = "the first corner's wheel's position on its track at t = 0",
     S_OFF(road_front_start)},
    {.path = "simulation", .type = SCH_SECTION, .doc = "the run"},
    {.path = "simulation.t_end",
     .type = SCH_NUMBER,
     .unit = "s",
     POSITIVE,
     .doc = "end of the run (it starts at 0)",
     S_OFF(t_end)},
    {.path = "simulation.rtol",
     .type = SCH_NUMBER,
     .bounds = SCH_LO | SCH_LO_OPEN | SCH_HI | SCH_HI_OPEN,
     .lo = 0,
     .hi = 1,
     .doc = "relative tolerance",
     S_OFF(rtol)},
    {.path = "simulation.atol",
     .type = SCH_NUMBER,
     POSITIVE,
     .doc = "absolute tolerance (all states)",
     S_OFF(atol)},
    {.path = "simulation.max_step",
     .type = SCH_NUMBER,
     .unit = "s",
     NONNEGATIVE,
     .need = SCH_DEFAULT,
     .def = 0,
     .doc = "largest step, 0: no limit",
     S_OFF(max_step)},
    {.path = "simulation.max_steps",
     .type = SCH_WHOLE,
     ROWS(1, (double)FB_SIM_MAX_STEPS),
     .need = SCH_DEFAULT,
     .def = (double)FB_SIM_DEFAULT_MAX_STEPS,
     .doc = "internal steps allowed in the whole run",
     .store = SCH_STORE_LONG,
     .offset = offsetof(fb_scenario, max_steps)},
    {.path = "simulation.sample_rate",
     .type = SCH_NUMBER,
     .unit = "Hz",
     POSITIVE,
     .doc = "outputs at k / sample_rate",
     S_OFF(sample_rate)},
    {.path = "simulation.initial",
     .type = SCH_CHOICE,
     .choices = sc_initials,
     .doc = "`zero`: every state zero, gravity on at t = 0; `static`: the static equilibrium",
     .store = SCH_STORE_INT,
     .offset = offsetof(fb_scenario, initial)},
};

const sch_table sc_schema = {sc_keys, sizeof sc_keys / sizeof sc_keys[0], sc_root_done};

/* ---- Reading, visiting, documenting. */

/* The reader's origins, given ones only, moved into s. */
static int sc_keep_origins(sch_reader *r, fb_scenario *s)
{
  size_t n = 0;
  for (size_t i = 0; i < r->norigins; ++i)
    n += r->origin[i].given;
  s->origin = calloc(n ? n : 1, sizeof *s->origin);
  if (!s->origin)
    return fb_err_set(r->c->err, FB_ENOMEM, "out of memory for %zu origins", n);
  for (size_t i = 0; i < r->norigins; ++i) {
    sch_origin *o = &r->origin[i];
    if (!o->given)
      continue;
    s->origin[s->norigins++] = (fb_scenario_origin){o->key, o->path, o->line, o->column, NULL};
    o->key = o->path = NULL;
  }
  return FB_OK;
}

int sc_read(ml_ctx *c, struct fy_node *root, fb_symtab *params, fb_scenario *s)
{
  sc_reading rd = {s, params, 0, 0, 0};
  sch_reader r = {c, &rd, NULL, 0, 0};
  c->globals = params;
  int rc = sch_read(&r, &sc_schema, root, s);
  if (!rc)
    rc = sc_keep_origins(&r, s);
  sch_reader_release(&r);
  return rc;
}

void fb_scenario_schema_markdown(FILE *fp)
{
  sch_markdown(&sc_schema, fp);
}

/* fb_scenario_each_value's visit of one value. */
typedef struct sc_visit {
  const fb_scenario *s;
  fb_scenario_value_fn fn;
  void *ctx;
} sc_visit;

static int sc_visit_value(const sch_value *v, void *ctx)
{
  const sc_visit *visit = ctx;
  char text[256];
  sch_format(v, text, sizeof text);
  const char *rest = NULL;
  const fb_scenario_origin *o = sc_origin_find(visit->s, v->path, &rest);
  const fb_scenario_value value = {v->path, o && !*rest ? o->path : NULL,
                                   v->key->unit ? v->key->unit : "", v->key->doc, text};
  return visit->fn(&value, visit->ctx);
}

int fb_scenario_each_value(const fb_scenario *s, fb_scenario_value_fn fn, void *ctx)
{
  if (!s || !fn)
    return FB_EINVAL;
  sc_visit visit = {s, fn, ctx};
  return sch_each(&sc_schema, s, sc_visit_value, &visit);
}
