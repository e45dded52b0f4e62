/* SPDX-License-Identifier: BSD-3-Clause */
/* The scenario file format (docs/scenario-format.md) as one schema table
 * (io/schema.h), with the hooks for what a table cannot say: a value of
 * several shapes (the load points, a damper table), an axle that makes
 * two corners, the outputs' defaults from their signal kinds, and the
 * rules between keys of one section. */
#include <errno.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/hull_source.h"
#include "flexbond/io.h"
#include "flexbond/spring.h"
#include "flexbond/stop.h"

#include "core/util.h"
#include "io/scenario_internal.h"

/* What the hooks share while a document is read (sch_reader.user). */
typedef struct sc_reading {
  fb_symtab *params;
  const sch_table *table; /* the format's, with the gallery's road types */
} sc_reading;

/* ---- Conversions between the file's units and the struct's. */

/* v in one unit, in the other. */
#define SC_CONVERT(name, expr)                                                                 \
  static double name(double v)                                                                 \
  {                                                                                            \
    return expr;                                                                               \
  }

SC_CONVERT(sc_kmh_to_ms, v / 3.6)
SC_CONVERT(sc_ms_to_kmh, v * 3.6)

static const sch_ops sc_kmh = {.to_struct = sc_kmh_to_ms, .from_struct = sc_ms_to_kmh};

/* ---- When a value is there (sch_ops.present). */

/* name(base) is expr over b, base as a const T *. */
#define SC_PRESENT(name, T, expr)                                                              \
  static int name(const sch_key *k, const void *base)                                          \
  {                                                                                            \
    (void)k;                                                                                   \
    const T *b = base;                                                                         \
    return expr;                                                                               \
  }

SC_PRESENT(sc_has_fe_hull, fb_scenario, b->has_fe_hull)
SC_PRESENT(sc_has_refinable, fb_scenario, b->has_fe_hull &&fb_scenario_hull_density(b) > 0)
SC_PRESENT(sc_has_frame, fb_scenario, b->frame_origin != NULL)
SC_PRESENT(sc_has_cg, fb_scenario, b->hull_cg_given)
SC_PRESENT(sc_has_coupling, fb_scenario, b->coupling != FB_COUPLING_NONE)
SC_PRESENT(sc_has_mass, fb_scenario, b->hull_mass_given)
SC_PRESENT(sc_has_izz, fb_scenario, b->hull_izz_given)
/* A damper law's key (its data the law) is there when it is the
 * corner's law. */
SC_PRESENT(sc_damper_present, fb_corner_params, fb_corner_damper_law(b) == k->data)
SC_PRESENT(sc_has_window, fb_output_spec, b->window[0] != 0 || b->window[1] != 0)
SC_PRESENT(sc_has_component, fb_output_spec, b->component != 0)
/* A hull point's signal has its point and axis written back; a hull
 * stress signal its element or point, its surface and its component. */
SC_PRESENT(sc_is_point, fb_output_spec,
           fb_vehicle_output_kind_find(b->signal) &&
               fb_vehicle_output_kind_find(b->signal)->subject == FB_OUTPUT_OF_HULL_POINT)
SC_PRESENT(sc_is_stress, fb_output_spec,
           fb_vehicle_output_kind_find(b->signal) &&
               fb_vehicle_output_kind_find(b->signal)->subject == FB_OUTPUT_OF_HULL_STRESS)
SC_PRESENT(sc_has_element, fb_output_spec, b->element != 0)
SC_PRESENT(sc_has_at, fb_output_spec,
           sc_is_point(k, b) || (sc_is_stress(k, b) && b->element == 0))
SC_PRESENT(sc_has_radius, fb_bushing, b->radius != 0)
SC_PRESENT(sc_has_tire_radius, fb_corner_params, b->tire_radius != 0)

static const sch_ops sc_frame_present = {.present = sc_has_frame};
static const sch_ops sc_mass_present = {.present = sc_has_mass};
static const sch_ops sc_izz_present = {.present = sc_has_izz};
static const sch_ops sc_law_present = {.present = sc_damper_present};
static const sch_ops sc_radius_present = {.present = sc_has_radius};
static const sch_ops sc_tire_radius_present = {.present = sc_has_tire_radius};

/* ---- parameters: evaluated first, seen by every expression after. */

static int sc_read_parameters(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)k, (void)base;
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
  s->hull_izz_given = ml_get(node, "Izz", NULL) != NULL;
  static const char *const products[] = {"Ixy", "Ixz", "Iyz"};
  for (int i = 0; i < 3; ++i) {
    struct fy_node *key = NULL;
    if (!s->hull_izz_given && (ml_get(node, products[i], &key), key))
      return ml_fail_key(r->c, node, key, FB_EPARSE,
                         "a product of inertia goes with Izz (the hull's full tensor)");
  }
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

/* The section hull.mesh.<source> is there when it names the
 * description's source. */
static int sc_has_source(const sch_key *k, const void *base)
{
  const fb_scenario *s = base;
  const char *name = strrchr(k->path, '.');
  return s->has_fe_hull && name && !strcmp(fb_scenario_hull_source(s)->name, name + 1);
}

/* The source whose name is a key of hull.mesh (the format's one_of
 * "mesh" makes it one at most; none: the generator's default). */
static int sc_mesh_source(sch_reader *r, struct fy_node *node, fb_scenario *s)
{
  fb_hull_source_gallery *g = NULL;
  int rc = fb_hull_source_gallery_new(&g, r->c->err);
  for (size_t i = 0; !rc && i < fb_hull_source_gallery_count(g); ++i) {
    const fb_hull_source *src = fb_hull_source_gallery_at(g, i);
    if (ml_get(node, src->name, NULL))
      rc = fb_scenario_set_hull_source(s, src, r->c->err);
  }
  fb_hull_source_gallery_free(&g);
  return rc;
}

/* density refines a mesh its source makes, not one used as it is. */
static int sc_mesh_done(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  struct fy_node *key = NULL;
  int rc = sc_fe_done(r, k, node, base);
  if (!rc && node)
    rc = sc_mesh_source(r, node, base);
  if (!rc && node && !fb_scenario_hull_density(base) && (ml_get(node, "density", &key), key))
    rc = ml_fail_key(r->c, node, key, FB_EPARSE,
                     "density refines the generator's mesh, or another its source makes; a "
                     "`%s` mesh is used as it is",
                     fb_scenario_hull_source(base)->name);
  return rc;
}

/* hull.fe.modes: `auto`, `all` or a whole number, the modes a modal hull
 * keeps (fb_hull_modes_kind); the number's range is the scenario check's
 * (at least the six rigid-body modes). 0, which once meant every mode, is
 * refused with the word that says so now. */
enum { SC_MAX_HULL_MODES = 100000 };

static int sc_read_hull_modes(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)k;
  fb_scenario *s = base;
  const char *text = NULL;
  int rc = ml_string(r->c, node, &text);
  if (rc)
    return rc;
  if (!strcmp(text, "auto")) {
    s->hull_modes_kind = FB_HULL_MODES_AUTO;
    return FB_OK;
  }
  if (!strcmp(text, "all")) {
    s->hull_modes_kind = FB_HULL_MODES_ALL;
    return FB_OK;
  }
  char *end = NULL;
  errno = 0;
  const long n = strtol(text, &end, 10);
  if (end == text || *end || errno == ERANGE || n < 0 || n > SC_MAX_HULL_MODES)
    return ml_fail(r->c, node, FB_EPARSE,
                   "expected auto, all or a whole number of modes in 6..%d (got '%s')",
                   SC_MAX_HULL_MODES, text);
  if (n == 0)
    return ml_fail(r->c, node, FB_EPARSE,
                   "0 no longer means every mode: write all for every mode (a dense "
                   "eigen-solve), or auto for the modes the excitation needs");
  s->hull_modes_kind = FB_HULL_MODES_COUNT;
  s->hull_modes = (int)n;
  return FB_OK;
}

static void sc_format_hull_modes(const sch_key *k, const void *base, char *buf, size_t size)
{
  (void)k;
  const fb_scenario *s = base;
  if (s->hull_modes_kind == FB_HULL_MODES_COUNT)
    snprintf(buf, size, "%d", s->hull_modes);
  else
    snprintf(buf, size, "%s", s->hull_modes_kind == FB_HULL_MODES_ALL ? "all" : "auto");
}

/* Optional values whose absence is a 0 in the scenario. */
static int sc_has_cutoff(const sch_key *k, const void *base)
{
  (void)k;
  return ((const fb_scenario *)base)->hull_cutoff_hz != 0;
}

static int sc_has_converged_density(const sch_key *k, const void *base)
{
  (void)k;
  return ((const fb_scenario *)base)->hull_converged_density != 0;
}

static const sch_ops sc_cutoff_present = {.present = sc_has_cutoff};
static const sch_ops sc_converged_present = {.present = sc_has_converged_density};
static const sch_ops sc_hull_modes = {.read = sc_read_hull_modes,
                                      .format = sc_format_hull_modes};
static const sch_ops sc_hull_ops = {.done = sc_hull_done};
static const sch_ops sc_mesh_ops = {.done = sc_mesh_done, .present = sc_has_fe_hull};
static const sch_ops sc_fe_ops = {.done = sc_fe_done, .present = sc_has_fe_hull};
static const sch_ops sc_refinable_present = {.present = sc_has_refinable};
static const sch_ops sc_source_present = {.present = sc_has_source};
static const sch_ops sc_cg_present = {.present = sc_has_cg};
static const sch_ops sc_coupling_present = {.present = sc_has_coupling};

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

/* Renames the item's origins to its logical key: kind.name. */
static int sc_relabel(sch_reader *r, size_t mark, const char *item_path, const char *kind,
                      const char *name, int copy)
{
  char prefix[160];
  snprintf(prefix, sizeof prefix, "%s.%s", kind, name);
  return sch_origins_relabel(r, mark, item_path, prefix, copy);
}

/* A mount, a hull mass or a single corner: its origins as view.name. */
static int sc_named_end(sch_reader *r, const sch_key *k, struct fy_node *node,
                        const char *item_path, size_t mark, void *base, void *item)
{
  (void)node, (void)base;
  return sc_relabel(r, mark, item_path, k->view, sch_item_name(k, item), 0);
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
  (void)k, (void)base;
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

/* A single corner: its tire, then its origins as corners.name. */
static int sc_corner_end(sch_reader *r, const sch_key *k, struct fy_node *node,
                         const char *item_path, size_t mark, void *base, void *item)
{
  int rc = sc_corner_tire(r, k, node, item_path, item);
  if (!rc)
    rc = sc_corner_envelope(r, k, node, item_path, item);
  return rc ? rc : sc_named_end(r, k, node, item_path, mark, base, item);
}

/* An axle: its tire, then its two corners. */
static int sc_axle_tire_end(sch_reader *r, const sch_key *k, struct fy_node *node,
                            const char *item_path, size_t mark, void *base, void *item)
{
  int rc = sc_corner_tire(r, k, node, item_path, item);
  if (!rc)
    rc = sc_corner_envelope(r, k, node, item_path, item);
  return rc ? rc : sc_axle_end(r, k, node, item_path, mark, base, item);
}

static const sch_ops sc_named = {.item_end = sc_named_end};
static const sch_ops sc_axles = {.item_end = sc_axle_tire_end};
static const sch_ops sc_corners = {.item_end = sc_corner_end};

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
  const ml_ctx *c = r->c;
  fb_damper_table_params *out = NULL;
  fb_table_law *law = NULL;
  int rc = ml_table_law(c, c->globals, node, &law);
  const double *v = NULL, *f = NULL;
  const size_t n = rc ? 0 : fb_table_law_knots(law, &v, &f);
  if (!rc && n > FB_DAMPER_MAX_POINTS)
    rc = ml_fail(c, node, FB_EINVAL, "a damper table has at most %d points (got %zu)",
                 (int)FB_DAMPER_MAX_POINTS, n);
  if (!rc && fb_table_law_check_passive(law, c->err))
    rc = ml_blame(c, node);
  if (!rc && fb_corner_set_damper(base, k->data, (void **)&out, c->err))
    rc = ml_blame(c, node);
  if (!rc) {
    out->npoints = n;
    memcpy(out->velocity, v, n * sizeof *v);
    memcpy(out->force, f, n * sizeof *f);
  }
  fb_table_law_free(&law);
  return rc;
}

static void sc_format_damper_table(const sch_key *k, const void *base, char *buf, size_t size)
{
  (void)k;
  const fb_corner_params *c = base;
  snprintf(buf, size, "%zu points",
           ((const fb_damper_table_params *)(const void *)c->damper.bytes)->npoints);
}

static const sch_ops sc_damper_table = {.read = sc_read_damper_table,
                                        .format = sc_format_damper_table,
                                        .present = sc_damper_present};

/* ---- A tire's force-deflection table. */

/* Checked as a table where it is written; the corner whose tire is the
 * key's model (its data) reads it into its block (sc_corner_tire). */
static int sc_read_tire_table(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)k, (void)base;
  fb_table_law *law = NULL;
  const int rc = ml_table_law(r->c, r->c->globals, node, &law);
  fb_table_law_free(&law);
  return rc;
}

static void sc_format_tire_table(const sch_key *k, const void *base, char *buf, size_t size)
{
  (void)k;
  const fb_corner_params *c = base;
  snprintf(buf, size, "%zu points",
           ((const fb_tire_table_params *)(const void *)c->tire.bytes)->npoints);
}

/* A corner's table is there when its tire is the table's model (the top
 * level's is only inherited: no such op). */
static int sc_tire_table_present(const sch_key *k, const void *base)
{
  return fb_corner_tire_model(base) == k->data;
}

static const sch_ops sc_tire_table_top = {.read = sc_read_tire_table};
static const sch_ops sc_tire_table = {.read = sc_read_tire_table,
                                      .format = sc_format_tire_table,
                                      .present = sc_tire_table_present};

/* ---- A corner's spring law and its stops. */

/* The knots of a spring table into the corner (copied), refusing a
 * table that decreases or is too long. */
static int sc_read_spring_table(sch_reader *r, const sch_key *k, struct fy_node *node,
                                void *base)
{
  const ml_ctx *c = r->c;
  fb_spring_table_params *out = NULL;
  fb_table_law *law = NULL;
  int rc = ml_table_law(c, c->globals, node, &law);
  const double *x = NULL, *f = NULL;
  const size_t n = rc ? 0 : fb_table_law_knots(law, &x, &f);
  if (!rc && n > FB_SPRING_MAX_POINTS)
    rc = ml_fail(c, node, FB_EINVAL, "a spring table has at most %d points (got %zu)",
                 (int)FB_SPRING_MAX_POINTS, n);
  if (!rc && fb_table_law_check_monotone(law, c->err))
    rc = ml_blame(c, node);
  if (!rc && fb_corner_set_spring(base, k->data, (void **)&out, c->err))
    rc = ml_blame(c, node);
  if (!rc) {
    out->npoints = n;
    memcpy(out->travel, x, n * sizeof *x);
    memcpy(out->force, f, n * sizeof *f);
  }
  fb_table_law_free(&law);
  return rc;
}

static void sc_format_spring_table(const sch_key *k, const void *base, char *buf, size_t size)
{
  (void)k;
  const fb_corner_params *c = base;
  snprintf(buf, size, "%zu points",
           ((const fb_spring_table_params *)(const void *)c->spring.bytes)->npoints);
}

/* A spring law's key (its data the law) is there when it is the corner's
 * law; the linear law's preload when it is not the paper's 0. */
static int sc_spring_present(const sch_key *k, const void *base)
{
  const fb_corner_params *c = base;
  if (fb_corner_spring_law(c) != k->data)
    return 0;
  return k->type != SCH_NUMBER ||
         ((const fb_spring_linear_params *)(const void *)c->spring.bytes)->preload != 0.0;
}

static const sch_ops sc_spring_table = {.read = sc_read_spring_table,
                                        .format = sc_format_spring_table,
                                        .present = sc_spring_present};
static const sch_ops sc_spring_preload = {.present = sc_spring_present};

/* Where a corner's stops are: a stop key's data. */
static const size_t sc_bump_at = offsetof(fb_corner_params, stops.bump);
static const size_t sc_rebound_at = offsetof(fb_corner_params, stops.rebound);

/* The stop of key k (its data the stop's offset) in the corner base. */
static const fb_stop *sc_stop_of(const sch_key *k, const void *base)
{
  return (const fb_stop *)(const void *)((const char *)base + *(const size_t *)k->data);
}

static fb_stop *sc_stop_at(const sch_key *k, void *base)
{
  return (fb_stop *)(void *)((char *)base + *(const size_t *)k->data);
}

/* A stop's section written: the stop is there, with its defaults. */
static int sc_stop_begin(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)r, (void)node;
  fb_stop *st = sc_stop_at(k, base);
  fb_stop_init(st);
  st->given = 1;
  return FB_OK;
}

static int sc_stop_present(const sch_key *k, const void *base)
{
  return sc_stop_of(k, base)->given;
}

/* A stop's force-deflection table, its knots copied (the corner's check
 * holds them to a stop's rules, at this key). */
static int sc_read_stop_table(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  const ml_ctx *c = r->c;
  fb_stop *st = sc_stop_at(k, base);
  fb_table_law *law = NULL;
  int rc = ml_table_law(c, c->globals, node, &law);
  const double *x = NULL, *f = NULL;
  const size_t n = rc ? 0 : fb_table_law_knots(law, &x, &f);
  if (!rc && n > FB_STOP_MAX_POINTS)
    rc = ml_fail(c, node, FB_EINVAL, "a stop's table has at most %d points (got %zu)",
                 (int)FB_STOP_MAX_POINTS, n);
  if (!rc) {
    st->npoints = n;
    memcpy(st->deflection, x, n * sizeof *x);
    memcpy(st->force, f, n * sizeof *f);
  }
  fb_table_law_free(&law);
  return rc;
}

static void sc_format_stop_table(const sch_key *k, const void *base, char *buf, size_t size)
{
  snprintf(buf, size, "%zu points", sc_stop_of(k, base)->npoints);
}

static int sc_stop_table_present(const sch_key *k, const void *base)
{
  const fb_stop *st = sc_stop_of(k, base);
  return st->given && st->npoints > 0;
}

static int sc_stop_rate_present(const sch_key *k, const void *base)
{
  const fb_stop *st = sc_stop_of(k, base);
  return st->given && st->npoints == 0;
}

static const sch_ops sc_stop_section = {.begin = sc_stop_begin, .present = sc_stop_present};
static const sch_ops sc_stop_table = {.read = sc_read_stop_table,
                                      .format = sc_format_stop_table,
                                      .present = sc_stop_table_present};
static const sch_ops sc_stop_rate = {.present = sc_stop_rate_present};

/* ---- bodies: a bushing's stiffness or damping per axis, the diagonal of
 * its 6x6 matrix (the member k or c its key's offset names). */

static int sc_store_diagonal(sch_reader *r, const sch_key *k, struct fy_node *node,
                             const double *v, size_t n, void *base)
{
  (void)r, (void)node;
  double *m = (double *)(void *)((char *)base + k->offset);
  memset(m, 0, 36 * sizeof *m);
  for (size_t i = 0; i < n && i < 6; ++i)
    m[7 * i] = v[i];
  return FB_OK;
}

static void sc_format_diagonal(const sch_key *k, const void *base, char *buf, size_t size)
{
  const double *m = (const double *)(const void *)((const char *)base + k->offset);
  snprintf(buf, size, "%.10g, %.10g, %.10g, %.10g, %.10g, %.10g", m[0], m[7], m[14], m[21],
           m[28], m[35]);
}

static const sch_ops sc_diagonal = {.store_list = sc_store_diagonal,
                                    .format = sc_format_diagonal};

/* ---- outputs. */

/* fb_name_fn over the signal kinds. */
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
  const char *near = fb_suggest(signal, n, sc_kind_signal, kinds);
  char hint[96] = "";
  if (near)
    snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
  return ml_fail(c, node, FB_EPARSE,
                 "unknown signal '%s'%s; the signals are in docs/vehicle-outputs.md", signal,
                 hint);
}

/* A hull stress signal's keys: `element` or `at` (one of them),
 * `surface` and `stress`; another signal has none of the last three. */
static int sc_output_stress(const ml_ctx *c, struct fy_node *node, const fb_output_spec *o,
                            const fb_output_kind *kind)
{
  const int wants_stress = kind->subject == FB_OUTPUT_OF_HULL_STRESS;
  static const char *const keys[3] = {"surface", "stress", "element"};
  static const char *const what[2] = {"the surface, top or bottom,",
                                      "the stress component, sx, sy or sxy,"};
  struct fy_node *key[3] = {NULL, NULL, NULL}, *at = NULL;
  for (int k = 0; k < 3; ++k) {
    ml_get(node, keys[k], &key[k]);
    if (wants_stress && k < 2 && !key[k])
      return ml_fail(c, node, FB_EPARSE, "missing required key '%s': %s a %s signal reads",
                     keys[k], what[k], o->signal);
    if (!wants_stress && key[k])
      return ml_fail_key(c, node, key[k], FB_EPARSE, "only a hull stress signal has %s",
                         keys[k]);
  }
  ml_get(node, "at", &at);
  if (wants_stress && !key[2] == !at)
    return at ? ml_fail_key(c, node, at, FB_EPARSE,
                            "a %s signal reads one element: give element or at, not both",
                            o->signal)
              : ml_fail(c, node, FB_EPARSE,
                        "missing required key 'element' or 'at': the shell element (by its "
                        "id) or the hull point `[x, y, z]` (m) whose element a %s signal reads",
                        o->signal);
  return FB_OK;
}

/* `at` and `direction` for a hull point's signal only (`at` also for a
 * hull stress signal's). */
static int sc_output_point(const ml_ctx *c, struct fy_node *node, const fb_output_spec *o,
                           const fb_output_kind *kind)
{
  const int wants_point = kind->subject == FB_OUTPUT_OF_HULL_POINT;
  const int stress = kind->subject == FB_OUTPUT_OF_HULL_STRESS;
  static const char *const keys[2] = {"at", "direction"};
  static const char *const what[2] = {"the hull point `[x, y, z]` (m)", "the axis, x, y or z,"};
  for (int k = 0; k < 2; ++k) {
    struct fy_node *key = NULL;
    const int given = (ml_get(node, keys[k], &key), key != NULL);
    if (wants_point && !given)
      return ml_fail(c, node, FB_EPARSE, "missing required key '%s': %s a %s signal measures",
                     keys[k], what[k], o->signal);
    if (!wants_point && given && !(stress && k == 0))
      return ml_fail_key(c, node, key, FB_EPARSE, "only a hull point's signal has %s", keys[k]);
  }
  return sc_output_stress(c, node, o, kind);
}

/* `of` for a corner's, a mount's or a bogie's signal only, `bond` for a
 * bond's. */
static int sc_output_subject(const ml_ctx *c, struct fy_node *node, const fb_output_spec *o,
                             const fb_output_kind *kind)
{
  const int wants_of =
      kind->subject == FB_OUTPUT_OF_CORNER || kind->subject == FB_OUTPUT_OF_MOUNT ||
      kind->subject == FB_OUTPUT_OF_BOGIE || kind->subject == FB_OUTPUT_OF_BODY;
  const int wants_bond = kind->subject == FB_OUTPUT_OF_BOND;
  const char *what = kind->subject == FB_OUTPUT_OF_CORNER  ? "corner"
                     : kind->subject == FB_OUTPUT_OF_MOUNT ? "mounted body"
                     : kind->subject == FB_OUTPUT_OF_BODY  ? "rigid body"
                                                           : "bogie";
  struct fy_node *key = NULL;
  if (wants_of && !o->of)
    return ml_fail(c, node, FB_EPARSE, "missing required key 'of': the %s a %s signal measures",
                   what, o->signal);
  if (!wants_of && o->of && (ml_get(node, "of", &key), key))
    return ml_fail_key(c, node, key, FB_EPARSE,
                       "a %s signal measures no corner, mount or bogie", o->signal);
  if (wants_bond && !o->bond)
    return ml_fail(c, node, FB_EPARSE,
                   "missing required key 'bond': the bond of the assembled graph whose %s "
                   "it records",
                   o->signal);
  if (!wants_bond && o->bond && (ml_get(node, "bond", &key), key))
    return ml_fail_key(c, node, key, FB_EPARSE, "only a bond signal names a bond");
  if (!wants_bond && o->component && (ml_get(node, "component", &key), key))
    return ml_fail_key(c, node, key, FB_EPARSE, "only a bond signal has a component");
  return sc_output_point(c, node, o, kind);
}

static int sc_output_end(sch_reader *r, const sch_key *k, struct fy_node *node,
                         const char *item_path, size_t mark, void *base, void *item)
{
  (void)k, (void)item_path, (void)mark, (void)base;
  fb_output_spec *o = item;
  const fb_output_kind *kind = NULL;
  int rc = sc_output_kind(r->c, ml_get(node, "signal", NULL), o->signal, &kind);
  if (!rc)
    rc = sc_output_subject(r->c, node, o, kind);
  return rc ? rc : fb_output_spec_complete(o, kind, r->c->err);
}

static const sch_ops sc_outputs = {.item_end = sc_output_end};

static const sch_ops sc_window = {.present = sc_has_window};

static const sch_ops sc_point = {.present = sc_is_point};

static const sch_ops sc_point_or_stress = {.present = sc_has_at};

static const sch_ops sc_stress = {.present = sc_is_stress};

static const sch_ops sc_element = {.present = sc_has_element};

static const sch_ops sc_has_component_ops = {.present = sc_has_component};

/* Without an outputs list: every corner's tire_force, in corner order. */
static int sc_default_outputs(sch_reader *r, fb_scenario *s)
{
  const fb_output_kind *kind = fb_vehicle_output_kind_find("tire_force");
  if (!kind)
    return fb_err_set(r->c->err, FB_EMODEL, "no signal kind 'tire_force' for the outputs");
  for (size_t i = 0; i < s->ncorners; ++i) {
    fb_output_spec *o = NULL;
    const sc_reading *rd = r->user;
    int rc = sch_list_add(r, sch_key_of(rd->table, "outputs"), s, (void **)&o);
    if (!rc &&
        (!(o->signal = fb_strdup(kind->signal)) || !(o->of = fb_strdup(s->corner[i].name))))
      rc = fb_err_set(r->c->err, FB_ENOMEM, "out of memory for an output");
    if (!rc)
      rc = fb_output_spec_complete(o, kind, r->c->err);
    if (rc)
      return rc;
  }
  return FB_OK;
}

static int sc_root_done(sch_reader *r, struct fy_node *node, void *base)
{
  const sc_reading *rd = r->user;
  int rc = sc_tire_sections_used(r, rd->table, node, base);
  if (!rc)
    rc = sc_envelope_sections_used(r, rd->table, node, base);
  if (rc)
    return rc;
  return ml_get(node, "outputs", NULL) ? FB_OK : sc_default_outputs(r, base);
}

/* ---- The table. */

/* One row per key, by type. Ranges, needs and stores are the macros after
 * these; after a NUMBER's, WHOLE's, CHOICE's or STRING's store (NO_STORE:
 * none) come any other fields. */
#define KEY(...)                                                                               \
  {                                                                                            \
    __VA_ARGS__                                                                                \
  }
#define NUMBER(p, u, r, n, d, ...)                                                             \
  KEY(.path = p, .type = SCH_NUMBER, .unit = u, r, n, .doc = d, __VA_ARGS__)
#define WHOLE(p, r, n, d, ...) KEY(.path = p, .type = SCH_WHOLE, r, n, .doc = d, __VA_ARGS__)
#define CHOICE(p, c, n, d, ...)                                                                \
  KEY(.path = p, .type = SCH_CHOICE, .choices = c, n, .doc = d, __VA_ARGS__)
/* SCH_NAME, SCH_TEXT or SCH_FILE: STRING(NAME, ...). */
#define STRING(t, p, n, d, ...) KEY(.path = p, .type = SCH_##t, n, .doc = d, __VA_ARGS__)
#define NUMBERS(p, u, lo, hi, n, d, ...)                                                       \
  KEY(.path = (p), .type = SCH_NUMBERS, .unit = (u), .min_items = (lo), .max_items = (hi), n,  \
      .doc = (d), __VA_ARGS__)
#define CUSTOM(p, u, t, n, d, o)                                                               \
  KEY(.path = (p), .type = SCH_CUSTOM, .unit = (u), .type_doc = (t), n, .doc = (d), .ops = (o))
/* A CUSTOM that stands for a member (S_IS, C_IS). */
#define CUSTOM_IS(p, u, t, n, d, o, m)                                                         \
  KEY(.path = (p), .type = SCH_CUSTOM, .unit = (u), .type_doc = (t), n, .doc = (d),            \
      .ops = (o), m)
#define SECTION(p, n, d, o) KEY(.path = (p), .type = SCH_SECTION, n, .doc = (d), .ops = (o))
/* A SECTION that stands for a member (S_IS). */
#define SECTION_IS(p, n, d, o, m)                                                              \
  KEY(.path = (p), .type = SCH_SECTION, n, .doc = (d), .ops = (o), m)
/* where: ITEMS or NAMED. */
#define LIST(p, n, d, t, v, o, where)                                                          \
  KEY(.path = (p), .type = SCH_LIST, n, .doc = (d), .items = (t), .view = (v), .ops = (o),     \
      where)

/* Ranges, in the file's unit. */
#define ANY .bounds = 0
#define POSITIVE .bounds = SCH_LO | SCH_LO_OPEN, .lo = 0
#define NONNEGATIVE .bounds = SCH_LO, .lo = 0
#define CLOSED(lo_, hi_) .bounds = SCH_LO | SCH_HI, .lo = (lo_), .hi = (hi_)
#define HALF_OPEN(lo_, hi_) .bounds = SCH_LO | SCH_HI | SCH_HI_OPEN, .lo = (lo_), .hi = (hi_)
#define OPEN(lo_, hi_)                                                                         \
  .bounds = SCH_LO | SCH_LO_OPEN | SCH_HI | SCH_HI_OPEN, .lo = (lo_), .hi = (hi_)

/* Needs. ONE_OF: required, of the keys with the group's label. */
/* What real vehicles have (sch_key.plausible_*): why says it, in words
 * and numbers, for the warning. */
#define PLAUSIBLE(lo_, hi_, why_)                                                              \
  .plausible_lo = (lo_), .plausible_hi = (hi_), .plausible_why = (why_)
/* The same, the warning also giving the value in unit_ (value * scale_):
 * the unit a slip most often means. */
#define PLAUSIBLE_IN(lo_, hi_, why_, unit_, scale_)                                            \
  PLAUSIBLE(lo_, hi_, why_), .plausible_unit = (unit_), .plausible_scale = (scale_)
/* A position along x, y or z, or a point [x, y, z] (sch_key.axis): a
 * report gives it in the file's frame. */
#define AXIS_X .axis = 1
#define AXIS_Y .axis = 2
#define AXIS_Z .axis = 3
#define AXIS_POINT .axis = SCH_AXIS_POINT
#define REQ .need = SCH_REQUIRED
#define OPT .need = SCH_OPTIONAL
#define DEF(v) .need = SCH_DEFAULT, .def = v
#define DEF_LIST(l) .need = SCH_DEFAULT, .def_list = l
#define INHERIT(k) .need = SCH_INHERIT, .inherit = k
#define ONE_OF(g) .need = SCH_REQUIRED, .one_of = g
/* At most one of the group, maybe none. */
#define OPT_ONE_OF(g) .need = SCH_OPTIONAL, .one_of = g

/* Stores: kind (DOUBLE, INT, ...) at a field of the scenario, a corner, a
 * mount or an output. */
#define NO_STORE .store = SCH_STORE_NONE
#define S_AT(kind, f)                                                                          \
  .store = SCH_STORE_##kind, .offset = offsetof(fb_scenario, f), .member = #f
#define C_AT(kind, f)                                                                          \
  .store = SCH_STORE_##kind, .offset = offsetof(fb_corner_params, f), .member = #f
#define M_AT(kind, f) .store = SCH_STORE_##kind, .offset = offsetof(fb_mount, f), .member = #f
#define B_AT(kind, f)                                                                          \
  .store = SCH_STORE_##kind, .offset = offsetof(fb_antiroll_bar, f), .member = #f
#define G_AT(kind, f) .store = SCH_STORE_##kind, .offset = offsetof(fb_bogie, f), .member = #f
#define Y_AT(kind, f) .store = SCH_STORE_##kind, .offset = offsetof(fb_body, f), .member = #f
#define U_AT(kind, f) .store = SCH_STORE_##kind, .offset = offsetof(fb_bushing, f), .member = #f
/* A bushing's 6x6 matrix f, given through the store_list hook. */
#define U_DIAG(f) .offset = offsetof(fb_bushing, f), .member = #f, .ops = &sc_diagonal
#define O_AT(kind, f)                                                                          \
  .store = SCH_STORE_##kind, .offset = offsetof(fb_output_spec, f), .member = #f
#define P_AT(kind, f)                                                                          \
  .store = SCH_STORE_##kind, .offset = offsetof(fb_hull_point_mass, f), .member = #f
#define H_AT(kind, f)                                                                          \
  .store = SCH_STORE_##kind, .offset = offsetof(fb_hull_section, f), .member = #f
/* A key that stores no member of its own (a section, a custom value)
 * but stands for member f of the scenario in errors (fb_err.part). */
#define S_IS(f) .member = (&#f[0 * offsetof(fb_scenario, f)])
#define C_IS(f) .member = (&#f[0 * offsetof(fb_corner_params, f)])
/* A list's items: the scenario's array arr, their number at count; an
 * item of the file makes per of them. NAMED: visited by their names. */
#define ITEMS(arr, count, per)                                                                 \
  .offset = offsetof(fb_scenario, arr), .count_at = offsetof(fb_scenario, count),              \
  .item_size = sizeof(((fb_scenario *)0)->arr[0]), .per_item = (per)
#define NAMED(arr, count, per) ITEMS(arr, count, per), .named = 1
#define S_OFF(f) S_AT(DOUBLE, f)
#define C_OFF(f) C_AT(DOUBLE, f)
#define M_OFF(f) M_AT(DOUBLE, f)

#define TABLE(keys, done)                                                                      \
  {                                                                                            \
    keys, sizeof(keys) / sizeof((keys)[0]), done                                               \
  }

static const char *const sc_payloads[] = {"weight-only", "lumped", NULL};
static const char *const sc_masses[] = {"consistent", "lumped", NULL};
static const char *const sc_initials[] = {"zero", "static", NULL};
static const char *const sc_coordinates[] = {"nodal", "modal", NULL};
static const char *const sc_couplings[] = {"none", "distributing", "kinematic", NULL};
static const char *const sc_switch[] = {"false", "true", NULL};
static const char *const sc_axes[] = {"x", "y", "z", NULL};
/* A hull stress signal's surfaces (FB_STRESS_TOP, FB_STRESS_BOTTOM) and
 * components (fb_output_stress). */
static const char *const sc_surfaces[] = {"top", "bottom", NULL};
static const char *const sc_stresses[] = {"sx", "sy", "sxy", NULL};

/* Plausible ranges shared by several keys. */
/* Plates of ground vehicles: body panels of trucks and light armoured
 * vehicles from some 3 mm, the paper's hull 8.5 mm, rolled homogeneous
 * armour up to some 100 mm. A thickness meant in mm is 1000 times
 * that; the warning gives it in mm. */
#define SC_THICKNESS_PLAUSIBLE                                                                 \
  PLAUSIBLE_IN(3e-3, 0.1,                                                                      \
               "plates of ground vehicles are 3-100 mm (was it meant in mm? thicknesses are "  \
               "in m)",                                                                        \
               "mm", 1e3)
/* Structural metals and composites: from some 900 kg/m^3 (polyethylene
 * and aramid armour laminates 970 to 1400, magnesium 1740, CFRP 1550,
 * aluminium 2700, titanium 4500, steel 7850) to 20000 (tungsten alloys
 * 17000 to 19300). A density in g/cm^3 (7.85) is 1000 times below. */
#define SC_DENSITY_PLAUSIBLE                                                                   \
  PLAUSIBLE_IN(900, 2e4,                                                                       \
               "structural metals and composites are 900 kg/m^3 (polyethylene armour "         \
               "laminates) to 20000 kg/m^3 (tungsten alloys); steel 7850, aluminium 2700",     \
               "g/cm^3", 1e-3)
#define SC_WHY_WHEEL_MASS "a wheel (tire, rim, hub) weighs 1 kg to 5 t"
#define SC_WHY_TIRE_RADIUS                                                                     \
  "a road vehicle's tire is 0.2 m (a small car's) to 1 m (a large truck's) in radius"
#define SC_WHY_TIRE_K "a tire's radial stiffness is 1e4 to 1e8 N/m (a truck tire about 1e6)"

/* A mounted body: suspensions' and mounts' items. */
static const sch_key sc_mount_keys[] = {
    STRING(NAME, "name", REQ, "its name, unique among the mounts", M_AT(STRING, name)),
    NUMBER(
        "mass", "kg", POSITIVE, REQ, "body mass", M_OFF(mass),
        PLAUSIBLE(1, 1e5, "a mounted body (a seat, an engine, a turret) weighs 1 kg to 100 t")),
    NUMBER("stiffness", "N/m", POSITIVE, REQ, "spring stiffness", M_OFF(stiffness),
           PLAUSIBLE(1e2, 1e9, "a mount's spring is 1e2 to 1e9 N/m")),
    NUMBER("damping", "N s/m", NONNEGATIVE, REQ, "damper coefficient", M_OFF(damping)),
    NUMBER("x", "m", ANY, REQ, "hull attachment point", M_OFF(x), AXIS_X),
    NUMBER("y", "m", ANY, REQ, "hull attachment point", M_OFF(y), AXIS_Y),
};
static const sch_table sc_mount_table = TABLE(sc_mount_keys, NULL);

/* An anti-roll bar between two corners: anti_roll_bars' items. */
static const sch_key sc_antiroll_bar_keys[] = {
    STRING(NAME, "name", REQ, "its name, unique among the anti-roll bars", B_AT(STRING, name)),
    STRING(NAME, "left", REQ, "the corner at its left end (y > 0)", B_AT(STRING, left)),
    STRING(NAME, "right", REQ, "the corner at its right end (y < 0), across from `left`",
           B_AT(STRING, right)),
    NUMBER("stiffness", "N/m", POSITIVE, REQ,
           "its rate at each wheel in roll (equal and opposite travels): it adds "
           "stiffness * track^2 / 2 to the axle's roll stiffness; a wheel lifted alone meets "
           "half of it",
           B_AT(DOUBLE, stiffness),
           PLAUSIBLE(1e3, 1e7, "an anti-roll bar's rate at the wheel is 1e3 to 1e7 N/m")),
    NUMBER("damping", "N s/m", NONNEGATIVE, DEF(0),
           "damping on its twist, at each wheel in roll as `stiffness`", B_AT(DOUBLE, damping)),
};
static const sch_table sc_antiroll_bar_table = TABLE(sc_antiroll_bar_keys, NULL);

/* A walking-beam bogie on two corners: bogies' items. */
static const sch_key sc_bogie_keys[] = {
    STRING(NAME, "name", REQ, "its name, unique among the bogies", G_AT(STRING, name)),
    STRING(NAME, "front", REQ, "the corner whose wheel rides at the beam's front end",
           G_AT(STRING, front)),
    STRING(NAME, "rear", REQ,
           "the corner whose wheel rides at its rear end, on the front one's side (same y)",
           G_AT(STRING, rear)),
    NUMBER("pivot_x", "m", ANY, REQ,
           "the beam's pivot, strictly between the two corners' x; the hull takes its load at "
           "their attachment points in the lever's proportions",
           G_AT(DOUBLE, pivot_x), AXIS_X),
    NUMBER("beam_mass", "kg", POSITIVE, REQ, "the beam's mass, at the pivot",
           G_AT(DOUBLE, beam_mass), PLAUSIBLE(1, 5e3, "a bogie's beam weighs 1 kg to 5 t")),
    NUMBER("beam_inertia", "kg m^2", POSITIVE, REQ, "the beam's pitch inertia about the pivot",
           G_AT(DOUBLE, beam_inertia)),
    NUMBER("spring_k", "N/m", POSITIVE, REQ, "the pivot's spring to the hull",
           G_AT(DOUBLE, spring_k)),
    NUMBER("damper_c", "N s/m", NONNEGATIVE, DEF(0), "the pivot's damper to the hull",
           G_AT(DOUBLE, damper_c)),
};
static const sch_table sc_bogie_table = TABLE(sc_bogie_keys, NULL);

/* A bushing of a mounted rigid body: bodies[].bushings' items. */
static const sch_key sc_bushing_keys[] = {
    NUMBER("x", "m", ANY, REQ, "its point", U_AT(DOUBLE, x), AXIS_X),
    NUMBER("y", "m", ANY, REQ, "its point", U_AT(DOUBLE, y), AXIS_Y),
    NUMBER("z", "m", ANY, REQ, "its point", U_AT(DOUBLE, z), AXIS_Z),
    KEY(.path = "stiffness", .type = SCH_NUMBERS, .unit = "N/m, N m/rad", NONNEGATIVE,
        .min_items = 6, .max_items = 6, ONE_OF("stiffness"),
        .doc = "stiffness along x, y, z (N/m) and about x, y, z (N m/rad): a diagonal matrix",
        U_DIAG(k)),
    NUMBERS("stiffness_matrix", "SI", 36, 36, ONE_OF("stiffness"),
            "the full symmetric 6x6 stiffness, row by row (translations then rotations)",
            U_AT(DOUBLE, k)),
    KEY(.path = "damping", .type = SCH_NUMBERS, .unit = "N s/m, N m s/rad", NONNEGATIVE,
        .min_items = 6, .max_items = 6, OPT_ONE_OF("damping"),
        .doc = "damping along x, y, z (N s/m) and about x, y, z (N m s/rad): a diagonal "
               "matrix; none: no damping",
        U_DIAG(c)),
    NUMBERS("damping_matrix", "SI", 36, 36, OPT_ONE_OF("damping"),
            "the full symmetric 6x6 damping, row by row", U_AT(DOUBLE, c)),
    STRING(NAME, "node_set", OPT,
           "System 2, a bushing on the hull: the mesh's node set its hull side is coupled to "
           "(a distributing coupling in all six components)",
           U_AT(STRING, node_set)),
    STRING(NAME, "surface", OPT,
           "System 2, a bushing on the hull without `node_set`: the element set whose nodes "
           "around it in plan it is coupled to (default: `hull.mesh.coupling.surface`)",
           U_AT(STRING, surface)),
    NUMBER("radius", "m", POSITIVE, OPT,
           "with `surface`: the nodes within this radius in plan (default: "
           "`hull.mesh.coupling.radius`)",
           U_AT(DOUBLE, radius), .ops = &sc_radius_present),
};
static const sch_table sc_bushing_table = TABLE(sc_bushing_keys, NULL);

/* A mounted rigid body in six degrees of freedom: bodies' items. */
static const sch_key sc_body_keys[] = {
    STRING(NAME, "name", REQ,
           "its name, unique among the bodies, mounts, hull masses and corners",
           Y_AT(STRING, name)),
    STRING(NAME, "on", OPT, "the body it is mounted on, listed before it; left out: the hull",
           Y_AT(STRING, parent)),
    NUMBER(
        "mass", "kg", POSITIVE, REQ, "its mass", Y_AT(DOUBLE, mass),
        PLAUSIBLE(1, 1e5, "a mounted body (a seat, an engine, a turret) weighs 1 kg to 100 t")),
    NUMBER("x", "m", ANY, REQ, "its centre of mass", Y_AT(DOUBLE, x), AXIS_X),
    NUMBER("y", "m", ANY, REQ, "its centre of mass", Y_AT(DOUBLE, y), AXIS_Y),
    NUMBER("z", "m", ANY, REQ, "its centre of mass (height in the vehicle axes)",
           Y_AT(DOUBLE, z), AXIS_Z),
    NUMBER("Ixx", "kg m^2", POSITIVE, REQ,
           "moment of inertia about x through its centre of mass", Y_AT(DOUBLE, ixx)),
    NUMBER("Iyy", "kg m^2", POSITIVE, REQ, "moment of inertia about y", Y_AT(DOUBLE, iyy)),
    NUMBER("Izz", "kg m^2", POSITIVE, REQ, "moment of inertia about z", Y_AT(DOUBLE, izz)),
    NUMBER("Ixy", "kg m^2", ANY, DEF(0), "product of inertia, the integral of x y dm",
           Y_AT(DOUBLE, ixy)),
    NUMBER("Ixz", "kg m^2", ANY, DEF(0), "product of inertia, the integral of x z dm",
           Y_AT(DOUBLE, ixz)),
    NUMBER("Iyz", "kg m^2", ANY, DEF(0), "product of inertia, the integral of y z dm",
           Y_AT(DOUBLE, iyz)),
    KEY(.path = "bushings", .type = SCH_LIST, REQ, .min_items = 1,
        .max_items = FB_BODY_MAX_BUSHINGS,
        .doc = "the bushings that carry it to its parent (six-component springs and dampers)",
        .items = &sc_bushing_table, .view = "bushings", .offset = offsetof(fb_body, bushing),
        .count_at = offsetof(fb_body, nbushings), .item_size = sizeof(fb_bushing),
        .per_item = 1, .member = "bushing"),
};
static const sch_table sc_body_table = TABLE(sc_body_keys, NULL);

/* A non-structural mass on the hull's floor: hull.masses' items. */
static const sch_key sc_point_mass_keys[] = {
    STRING(NAME, "name", REQ,
           "its name, unique among the hull masses, mounts and corners; its mesh node set is "
           "`MASS_<NAME>`, the name in capitals",
           P_AT(STRING, name)),
    NUMBER("mass", "kg", POSITIVE, REQ, "its mass", P_AT(DOUBLE, mass),
           PLAUSIBLE(0.1, 1e5, "a mass carried by the hull weighs 0.1 kg to 100 t")),
    NUMBER("x", "m", ANY, REQ, "where it is on the floor", P_AT(DOUBLE, x), AXIS_X),
    NUMBER("y", "m", ANY, REQ, "where it is on the floor", P_AT(DOUBLE, y), AXIS_Y),
};
static const sch_table sc_point_mass_table = TABLE(sc_point_mass_keys, NULL);

/* A shell section of the finite-element hull: hull.sections' items. */
static const sch_key sc_section_keys[] = {
    STRING(NAME, "set", REQ,
           "the element set: a part of the generated hull (`FLOOR`, `ROOF`, `SIDES`, "
           "`REAR_WALL`, `GLACIS`, `BULKHEADS`, `BULKHEAD_<k>`) or a deck's `*ELSET`; "
           "case-insensitive",
           H_AT(STRING, set)),
    NUMBER("thickness", "m", POSITIVE, INHERIT("hull.material.thickness"), "plate thickness",
           H_AT(DOUBLE, thickness), SC_THICKNESS_PLAUSIBLE),
    NUMBER("young", "Pa", POSITIVE, INHERIT("hull.material.young"), "Young's modulus",
           H_AT(DOUBLE, young)),
    NUMBER("poisson", NULL, HALF_OPEN(0, 0.5), INHERIT("hull.material.poisson"),
           "Poisson's ratio", H_AT(DOUBLE, poisson)),
    NUMBER("density", "kg/m^3", POSITIVE, INHERIT("hull.material.density"), "density",
           H_AT(DOUBLE, density), SC_DENSITY_PLAUSIBLE),
    NUMBER("nonstructural_mass", "kg/m^2", NONNEGATIVE, DEF(0),
           "mass per area carried by the plates (lining, equipment), smeared through their "
           "thickness",
           H_AT(DOUBLE, nonstructural_mass)),
};
static const sch_table sc_section_table = TABLE(sc_section_keys, NULL);

/* A stop's section and keys: name its key, m its member of fb_stops,
 * at the offset variable where, touched in travel (compression or
 * extension). */
#define STOP_KEYS(name, m, where, travel)                                                      \
  KEY(.path = (name), .type = SCH_SECTION, OPT,                                                \
      .doc = "the " #m " stop, touched at a spring " travel " of `gap`",                       \
      .ops = &sc_stop_section, C_IS(stops), .data = &(where)),                                 \
      KEY(.path = name ".gap", .type = SCH_NUMBER, .unit = "m", NONNEGATIVE, REQ,              \
          .doc = "the spring's " travel " at which the stop is touched, from zero travel",     \
          C_OFF(stops.m.gap), PLAUSIBLE(1e-3, 0.5, SC_WHY_STOP_GAP)),                          \
      KEY(.path = name ".rate", .type = SCH_NUMBER, .unit = "N/m", POSITIVE, ONE_OF(name),     \
          .doc = "a linear stop's rate", C_OFF(stops.m.rate), .ops = &sc_stop_rate,            \
          .data = &(where), PLAUSIBLE(1e4, 1e8, SC_WHY_STOP_RATE)),                            \
      KEY(.path = name ".table", .type = SCH_CUSTOM,                                           \
          .type_doc = "`{points: [[d, F], ...]}` or `{file, velocity, force}`", ONE_OF(name),  \
          .doc = "force (N) against the stop's own compression (m) from (0, 0), 2 to 32 "      \
                 "points, forces not decreasing",                                              \
          .ops = &sc_stop_table, C_IS(stops), .data = &(where)),                               \
      KEY(.path = name ".damping", .type = SCH_NUMBER, .unit = "N s/m", NONNEGATIVE, DEF(0),   \
          .doc = "damping while in contact, never pulling", C_OFF(stops.m.damping),            \
          PLAUSIBLE(0, 1e6, SC_WHY_STOP_DAMPING)),                                             \
      KEY(.path = name ".damping_depth", .type = SCH_NUMBER, .unit = "m", POSITIVE,            \
          DEF(FB_STOP_DAMPING_DEPTH),                                                          \
          .doc = "the stop's compression over which its damping grows from 0 to `damping`",    \
          C_OFF(stops.m.damping_depth))

#define SC_WHY_PRELOAD "a suspension spring's preload is at most a few hundred kN"
#define SC_WHY_STOP_GAP "a suspension's travel to its stops is 1 mm to 0.5 m"
#define SC_WHY_STOP_RATE "a bump or rebound stop is 1e4 to 1e8 N/m"
#define SC_WHY_STOP_DAMPING "a stop's damping is at most a shock absorber's, 1e6 N s/m"

static const sch_key sc_corner_keys[] = {
    STRING(NAME, "name", REQ,
           "a corner's name; an axle's corners are L and R before it (F: LF, RF)",
           C_AT(STRING, name)),
    NUMBER("x", "m", ANY, REQ, "hull attachment point", C_OFF(x), AXIS_X),
    NUMBER("y", "m", ANY, REQ,
           "hull attachment point; an axle's left one, > 0 (the right one is at -y)", C_OFF(y),
           AXIS_Y),
    NUMBER("spring_k", "N/m", POSITIVE, REQ, "suspension spring stiffness", C_OFF(spring_k),
           PLAUSIBLE(1e3, 1e8, "a suspension spring is 1e3 to 1e8 N/m")),
    NUMBER("damper_c", "N s/m", NONNEGATIVE, ONE_OF("damper"),
           "linear shock absorber coefficient (the `linear` damper law's `c`)",
           .store = SCH_STORE_DOUBLE,
           .offset = offsetof(fb_corner_params, damper) + offsetof(fb_damper_linear_params, c),
           .ops = &sc_law_present, .data = &fb_damper_law_linear, C_IS(damper_law)),
    KEY(.path = "damper_table", .type = SCH_CUSTOM,
        .type_doc = "`{file, velocity, force}` or `{points: [[v, F], ...]}`", ONE_OF("damper"),
        .doc =
            "a nonlinear shock absorber (the `table` damper law): force (N) against velocity "
            "(m/s, compression positive), 2 to 64 points, passive",
        .ops = &sc_damper_table, .data = &fb_damper_law_table, C_IS(damper_law)),
    /* Its sections are a damper gallery's laws (scenario_gallery.c). */
    SECTION_IS(SC_DAMPER_SECTION, ONE_OF("damper"),
               "a damper law of the gallery and its parameters, `{<law>: {<parameter>: "
               "value, ...}}`: exactly one law's section",
               NULL, C_IS(damper_law)),
    NUMBER("spring_preload", "N", ANY, OPT,
           "the linear spring's force at zero travel (the `linear` spring law's `preload`; "
           "default 0, the paper's)",
           .store = SCH_STORE_DOUBLE,
           .offset =
               offsetof(fb_corner_params, spring) + offsetof(fb_spring_linear_params, preload),
           .one_of = "spring", .ops = &sc_spring_preload, .data = &fb_spring_law_linear,
           C_IS(spring_law), PLAUSIBLE(-1e6, 1e6, SC_WHY_PRELOAD)),
    KEY(.path = "spring_table", .type = SCH_CUSTOM,
        .type_doc = "`{file, velocity, force}` or `{points: [[x, F], ...]}`", OPT,
        .one_of = "spring",
        .doc = "a nonlinear spring (the `table` spring law): force (N) against travel (m, "
               "compression positive), 2 to 64 points, forces not decreasing; `spring_k` "
               "stays the rate estimates use",
        .ops = &sc_spring_table, .data = &fb_spring_law_table, C_IS(spring_law)),
    STOP_KEYS("bump_stop", bump, sc_bump_at, "compression"),
    STOP_KEYS("rebound_stop", rebound, sc_rebound_at, "extension"),
    NUMBER("motion_ratio", NULL, POSITIVE, INHERIT("suspensions.motion_ratio"),
           "spring travel / wheel travel relative to the hull", C_OFF(motion_ratio)),
    SECTION("wheel", OPT, "this corner's wheel, where it differs from the top-level `wheel`",
            NULL),
    NUMBER("wheel.mass", "kg", POSITIVE, INHERIT("wheel.mass"), "wheel mass", C_OFF(wheel_mass),
           PLAUSIBLE(1, 5e3, SC_WHY_WHEEL_MASS)),
    NUMBER("wheel.tire_k", "N/m", POSITIVE, INHERIT("wheel.tire_k"), "tire stiffness",
           C_OFF(tire_k), PLAUSIBLE(1e4, 1e8, SC_WHY_TIRE_K)),
    NUMBER("wheel.tire_c", "N s/m", NONNEGATIVE, INHERIT("wheel.tire_c"), "tire damping",
           C_OFF(tire_c)),
    /* Its choices are a tire gallery's models (scenario_gallery.c), each
     * with a section wheel.<model> of its parameters after it. */
    CHOICE(SC_TIRE_CHOICE, NULL, INHERIT(SC_TIRE_CHOICE), "how the tire meets the road",
           NO_STORE, C_IS(tire_model)),
    KEY(.path = SC_TIRE_TABLE, .type = SCH_CUSTOM,
        .type_doc = "`{points: [[d, F], ...]}` or `{file, velocity, force}`", OPT,
        .doc = "this corner's tire table, where it differs from the top-level `wheel`'s",
        .ops = &sc_tire_table, .data = &fb_tire_model_table, C_IS(tire_model)),
    NUMBER(SC_TIRE_RADIUS, "m", POSITIVE, OPT,
           "this tire's free (unloaded) radius, where it differs from the top-level `wheel`'s",
           C_OFF(tire_radius), PLAUSIBLE(0.2, 1.0, SC_WHY_TIRE_RADIUS),
           .ops = &sc_tire_radius_present),
    /* Its choices are an envelope gallery's models (scenario_gallery.c),
     * each with a section wheel.<model> of its parameters after it. */
    CHOICE(SC_ENVELOPE_CHOICE, NULL, INHERIT(SC_ENVELOPE_CHOICE),
           "how the tire envelops the road", NO_STORE, C_IS(envelope_model)),
};
const sch_table sc_corner_format = TABLE(sc_corner_keys, NULL);

static const sch_key sc_output_keys[] = {
    STRING(NAME, "signal", REQ, "what it records: a signal kind (docs/vehicle-outputs.md)",
           O_AT(STRING, signal)),
    STRING(NAME, "of", OPT,
           "the corner, mount or bogie it measures (a corner's, a mount's or a bogie's signal "
           "only)",
           O_AT(STRING, of)),
    STRING(TEXT, "bond", OPT, "a bond signal's bond in the assembled graph (`susp_LF.b_tire`)",
           O_AT(STRING, bond)),
    STRING(NAME, "name", OPT, "its CSV column, unique (default: the kind's, `tire_force_LF`)",
           O_AT(STRING, name)),
    STRING(TEXT, "title", OPT, "its figure's title (default: the kind's)", O_AT(STRING, title)),
    STRING(TEXT, "label", OPT, "its short label (default: the kind's)", O_AT(STRING, label)),
    WHOLE("figure", CLOSED(0, 9999), DEF(0), "the number of its figure, unique; 0: none",
          O_AT(INT, figure)),
    NUMBERS("window", "s", 2, 2, OPT,
            "the time window its figure shows, `[t0, t1]` (default: the run)",
            O_AT(DOUBLE, window), .ops = &sc_window),
    NUMBERS("at", "m", 3, 3, OPT,
            "a hull point's signal: the point `[x, y, z]` in the file's frame, as every "
            "position (a deck's: in the deck's frame); a hull stress signal's without "
            "`element`: a point of the element it reads",
            O_AT(DOUBLE, at), .ops = &sc_point_or_stress, AXIS_POINT),
    WHOLE("component", CLOSED(1, 1e9), OPT,
          "a bond signal on a multibond: the component it records, 1 to the bond's "
          "dimension (`flexbond causality` lists the bonds)",
          O_AT(LONG, component), .ops = &sc_has_component_ops),
    CHOICE("direction", sc_axes, OPT,
           "a hull point's signal: the axis of the translation it measures (ISO 8855: x "
           "forward, y left, z up)",
           O_AT(INT, direction), .ops = &sc_point),
    WHOLE("element", CLOSED(1, 1e15), OPT,
          "a hull stress signal: the shell element it reads, by its id in the hull's mesh "
          "(`flexbond mesh --export` writes them; else `at` picks the element)",
          O_AT(LONG, element), .ops = &sc_element),
    CHOICE("surface", sc_surfaces, OPT,
           "a hull stress signal: the element's surface, `top` the side its normal points "
           "to (docs/stresses.md)",
           O_AT(INT, surface), .ops = &sc_stress),
    CHOICE("stress", sc_stresses, OPT,
           "a hull stress signal: the stress component in the element's axes, `sx`, `sy` "
           "or `sxy` (Pa)",
           O_AT(INT, stress), .ops = &sc_stress),
};
static const sch_table sc_output_table = TABLE(sc_output_keys, NULL);

static const sch_key sc_keys[] = {
    STRING(NAME, "scenario", REQ, "the scenario's name", S_AT(STRING, name)),
    STRING(TEXT, "description", OPT, "free text, ignored", .lines = 1),
    CUSTOM("parameters", NULL, "mapping name: number", OPT,
           "named numbers for the expressions after it, each may use the ones before it; "
           "`t`, `pi`, `e` are reserved",
           &sc_parameters),
    NUMBER("gravity", "m/s^2", POSITIVE, REQ, "gravitational acceleration", S_OFF(gravity)),
    SECTION("frame", OPT,
            "positions in a frame of the file's own, not the hull's centre of mass",
            &sc_frame_present),
    STRING(TEXT, "frame.origin", REQ,
           "what the origin of the positions is (`front axle, floor`)",
           S_AT(STRING, frame_origin)),
    SECTION_IS("hull", REQ, "the hull", &sc_hull_ops, S_IS(hull_mass_given)),
    NUMBER("hull.mass", "kg", POSITIVE, OPT,
           "the hull structure's mass (`masses` aside); with mass, Ixx and Iyy left out, the "
           "finite-element hull's",
           S_OFF(hull_mass), .ops = &sc_mass_present,
           PLAUSIBLE(10, 2e5, "a hull structure weighs 10 kg to 200 t")),
    NUMBER("hull.Ixx", "kg m^2", POSITIVE, OPT,
           "the structure's roll inertia about its centre of mass", S_OFF(hull_ixx),
           .ops = &sc_mass_present),
    NUMBER("hull.Iyy", "kg m^2", POSITIVE, OPT,
           "the structure's pitch inertia about its centre of mass", S_OFF(hull_iyy),
           .ops = &sc_mass_present),
    NUMBER("hull.Izz", "kg m^2", POSITIVE, OPT,
           "the structure's yaw inertia about its centre of mass, for `bodies` (a hull "
           "carrying them moves in six degrees of freedom); left out: the finite-element "
           "hull's",
           S_OFF(hull_izz), .ops = &sc_izz_present),
    NUMBER("hull.Ixy", "kg m^2", ANY, OPT,
           "the structure's product of inertia, the integral of x y dm, with `Izz` (default 0)",
           S_OFF(hull_ixy), .ops = &sc_izz_present),
    NUMBER("hull.Ixz", "kg m^2", ANY, OPT, "the integral of x z dm, with `Izz` (default 0)",
           S_OFF(hull_ixz), .ops = &sc_izz_present),
    NUMBER("hull.Iyz", "kg m^2", ANY, OPT, "the integral of y z dm, with `Izz` (default 0)",
           S_OFF(hull_iyz), .ops = &sc_izz_present),
    SECTION_IS("hull.centre_of_mass", OPT,
               "the hull's centre of mass in the frame (only with `frame`; default: the "
               "mesh's)",
               &sc_cg_present, S_IS(hull_cg_given)),
    NUMBER("hull.centre_of_mass.x", "m", ANY, REQ, "its x", S_OFF(hull_cg_x)),
    NUMBER("hull.centre_of_mass.y", "m", ANY, REQ, "its y", S_OFF(hull_cg_y)),
    NUMBER("hull.centre_of_mass.z", "m", ANY, DEF(0),
           "its height above the frame's origin (what a hull's rigid bodies and points are "
           "measured from: docs/scenario-format.md, \"One vehicle frame\")",
           S_OFF(hull_cg_z)),
    LIST("hull.masses", OPT,
         "non-structural masses fixed to the floor (battery, ballast), inertia only: their "
         "weight is in `load.total_weight`",
         &sc_point_mass_table, "hull.masses", &sc_named, NAMED(point_mass, npoint_masses, 1)),
    SECTION("hull.material", REQ,
            "the plates' steel (System 2), where `hull.sections` give none", NULL),
    NUMBER("hull.material.young", "Pa", POSITIVE, REQ, "Young's modulus", S_OFF(young),
           PLAUSIBLE(1e8, 1e12, "structural materials are 1e8 to 1e12 Pa (steel 2.1e11)")),
    NUMBER("hull.material.poisson", NULL, HALF_OPEN(0, 0.5), REQ, "Poisson's ratio",
           S_OFF(poisson)),
    NUMBER("hull.material.density", "kg/m^3", POSITIVE, REQ, "density", S_OFF(density),
           SC_DENSITY_PLAUSIBLE),
    NUMBER("hull.material.thickness", "m", POSITIVE, REQ, "wall thickness", S_OFF(thickness),
           SC_THICKNESS_PLAUSIBLE),
    LIST("hull.sections", OPT,
         "plates of other thicknesses or materials, per element set (System 2; System 1 "
         "takes the mesh's mass); a later item takes the elements it shares with an earlier "
         "one",
         &sc_section_table, "hull.sections", NULL, ITEMS(section, nsections, 1)),
    SECTION("hull.edges", REQ, "the edge lines whose roll difference is the torsion angle",
            NULL),
    NUMBER("hull.edges.front_x", "m", ANY, REQ, "x of the front edge line, > `rear_x`",
           S_OFF(edge_front_x), AXIS_X),
    NUMBER("hull.edges.rear_x", "m", ANY, REQ, "x of the rear edge line", S_OFF(edge_rear_x),
           AXIS_X),
    NUMBER("hull.edges.left_y", "m", ANY, REQ, "y of each edge's left end, > `right_y`",
           S_OFF(edge_left_y), AXIS_Y),
    NUMBER("hull.edges.right_y", "m", ANY, REQ, "y of each edge's right end",
           S_OFF(edge_right_y), AXIS_Y),
    SECTION("hull.mesh", OPT, "System 2's hull mesh (with `hull.fe`)", &sc_mesh_ops),
    STRING(FILE, "hull.mesh.deck", ONE_OF("mesh"),
           "an Abaqus/CalculiX deck (.inp) or a gmsh mesh (.msh, format 4.1) with the "
           "scenario's node sets",
           S_AT(STRING, hull_deck)),
    WHOLE("hull.mesh.density", CLOSED(1, 64), DEF(1),
          "refinement of the generator's mesh: d x d elements for each",
          S_AT(INT, hull_mesh.density), .ops = &sc_refinable_present),
    WHOLE("hull.mesh.converged_density", CLOSED(2, 64), OPT,
          "a density of the generator at which the hull's modes have converged: `flexbond "
          "run` with both systems runs System 2 there too and compares, when it is above "
          "hull.mesh.density and the hull is generated (docs/hull-mesh.md)",
          S_AT(INT, hull_converged_density), .ops = &sc_converged_present),
    SECTION("hull.mesh.coupling", OPT,
            "how attachment points that are not nodes meet the mesh (docs/hull-mesh.md)",
            &sc_coupling_present),
    CHOICE("hull.mesh.coupling.kind", sc_couplings, REQ,
           "`distributing`: force spread, motion averaged; `kinematic`: a rigid lever to the "
           "nearest node",
           S_AT(INT, coupling)),
    NUMBER("hull.mesh.coupling.radius", "m", POSITIVE, REQ,
           "a point without a node set of its own takes the nodes within this distance in plan",
           S_OFF(coupling_radius)),
    STRING(NAME, "hull.mesh.coupling.surface", REQ,
           "the element set whose nodes those are (`FLOOR`)", S_AT(STRING, coupling_surface)),
    SECTION_IS("hull.mesh.generator", ONE_OF("mesh"),
               "the built-in generator's geometry (docs/hull-mesh.md)", &sc_source_present,
               S_IS(hull_mesh)),
    NUMBER("hull.mesh.generator.width", "m", POSITIVE, REQ, "between the side walls",
           S_OFF(hull_mesh.width)),
    NUMBER("hull.mesh.generator.height", "m", POSITIVE, REQ, "floor to roof",
           S_OFF(hull_mesh.height)),
    NUMBER("hull.mesh.generator.x_rear", "m", ANY, REQ, "rear wall", S_OFF(hull_mesh.x_rear)),
    NUMBER("hull.mesh.generator.x_front", "m", ANY, REQ, "front end of the box, > `x_rear`",
           S_OFF(hull_mesh.x_front)),
    NUMBER("hull.mesh.generator.nose_length", "m", POSITIVE, REQ,
           "wedge nose ahead of `x_front`", S_OFF(hull_mesh.nose_length)),
    NUMBER("hull.mesh.generator.nose_height", "m", POSITIVE, REQ,
           "nose tip line above the floor, < `height`", S_OFF(hull_mesh.nose_height)),
    NUMBERS("hull.mesh.generator.bulkheads", "m", 0, FB_HULL_MAX_BULKHEADS, REQ,
            "x of the transverse bulkheads, each between `x_rear` and `x_front`",
            S_OFF(hull_mesh.bulkhead_x),
            .count_at = offsetof(fb_scenario, hull_mesh.nbulkheads)),
    WHOLE("hull.mesh.generator.side_rows", CLOSED(1, 64), REQ,
          "element rows up the walls and bulkheads", S_AT(INT, hull_mesh.side_rows)),
    WHOLE("hull.mesh.generator.nose_rows", CLOSED(1, 64), REQ,
          "element rows along each glacis plate", S_AT(INT, hull_mesh.nose_rows)),
    WHOLE("hull.mesh.generator.nose_rung_divisions", CLOSED(1, 64), REQ,
          "divisions of the side walls' nose rung", S_AT(INT, hull_mesh.nose_rung_divisions)),
    SECTION_IS("hull.fe", OPT, "System 2's finite elements (with `hull.mesh`)", &sc_fe_ops,
               S_IS(has_fe_hull)),
    CHOICE("hull.fe.mass_matrix", sc_masses, REQ, "mass matrix", S_AT(INT, hull_mass_matrix)),
    NUMBER("hull.fe.drill_factor", NULL, POSITIVE, REQ,
           "fictitious drilling stiffness of the quadrilaterals (fem.h)",
           S_OFF(hull_drill_factor)),
    NUMBER("hull.fe.damping_ratio", NULL, HALF_OPEN(0, 1), REQ,
           "damping ratio of the hull's first elastic free-free mode, with its `masses` (B = "
           "beta K)",
           S_OFF(hull_damping_ratio)),
    CHOICE("hull.fe.coordinates", sc_coordinates, DEF(1),
           "`modal`: the hull's free-free modes (diagonal fields); `nodal`: its nodal "
           "displacements (sparse fields, the reference)",
           S_AT(INT, hull_coordinates)),
    CUSTOM_IS(
        "hull.fe.modes", NULL, "`auto`, `all` or N", OPT,
        "modal only: `auto` (the default) the rigid-body modes and blocks of "
        "load-dependent Ritz vectors from every attachment point, the load and every hull "
        "output, as many as the excitation's band needs; `all` every mode (a dense "
        "eigen-solve); N >= 6 the N lowest with the static correction of those patterns",
        &sc_hull_modes, S_IS(hull_modes)),
    NUMBER("hull.fe.cutoff_hz", "Hz", POSITIVE, OPT,
           "with `modes: auto`: the top of the band the basis must converge over, in place "
           "of the highest frequency that reaches the hull",
           S_OFF(hull_cutoff_hz), .ops = &sc_cutoff_present),
    SECTION("load", REQ, "hull plus payload", NULL),
    NUMBER("load.total_weight", "N", POSITIVE, REQ,
           "weight of hull (its `masses` included) plus payload, in equal shares over the load "
           "points",
           S_OFF(total_weight),
           PLAUSIBLE(1e3, 2e6, "a road vehicle weighs 1 kN to 2 MN (0.1 to 200 t)")),
    CHOICE("load.payload", sc_payloads, REQ, "payload mass model", S_AT(INT, payload)),
    CUSTOM_IS("load.points", "m", "`{grid: {x: [...], y: [...]}}` or `[[x, y], ...]`", REQ,
              "the load points, on the floor, 1 mm apart at least", &sc_points, S_IS(load_x)),
    LIST("mounts", OPT, "bodies on a spring and a damper to a hull point (driver, engine)",
         &sc_mount_table, "mounts", &sc_named, NAMED(mount, nmounts, 1)),
    LIST("bodies", OPT,
         "rigid bodies in six degrees of freedom on bushings, to the hull or to another body "
         "(a turret, its seats)",
         &sc_body_table, "bodies", &sc_named, NAMED(body, nbodies, 1)),
    SECTION("wheel", OPT, "every corner's wheel and tire unless the corner gives its own",
            NULL),
    NUMBER("wheel.mass", "kg", POSITIVE, OPT, "wheel mass", NO_STORE,
           PLAUSIBLE(1, 5e3, SC_WHY_WHEEL_MASS)),
    NUMBER("wheel.tire_k", "N/m", POSITIVE, OPT, "tire stiffness", NO_STORE,
           PLAUSIBLE(1e4, 1e8, SC_WHY_TIRE_K)),
    NUMBER("wheel.tire_c", "N s/m", NONNEGATIVE, OPT, "tire damping", NO_STORE),
    CHOICE(SC_TIRE_CHOICE, NULL, DEF(0), "how every tire meets the road (the tire models')",
           NO_STORE),
    KEY(.path = SC_TIRE_TABLE, .type = SCH_CUSTOM,
        .type_doc = "`{points: [[d, F], ...]}` or `{file, velocity, force}`", OPT,
        .doc = "a `table` tire's force (N) against its deflection (m) from (0, 0), 2 to 64 "
               "points, forces not decreasing; every such corner's unless it gives its own",
        .ops = &sc_tire_table_top, .data = &fb_tire_model_table),
    NUMBER(SC_TIRE_RADIUS, "m", POSITIVE, OPT,
           "every tire's free (unloaded) radius, which an enveloping tire needs "
           "(`wheel.envelope`)",
           NO_STORE, PLAUSIBLE(0.2, 1.0, SC_WHY_TIRE_RADIUS)),
    CHOICE(SC_ENVELOPE_CHOICE, NULL, DEF(0),
           "how every tire envelops the road (the envelope models')", NO_STORE),
    SECTION_IS("suspensions", REQ, "the corners (wheel stations)", &sc_suspensions,
               S_IS(corner)),
    NUMBER("suspensions.motion_ratio", NULL, POSITIVE, DEF(1),
           "every corner's spring travel / wheel travel unless it gives its own", NO_STORE),
    LIST("suspensions.axles", OPT,
         "axles, each two corners: L<name> at (x, y) and R<name> at (x, -y)", &sc_corner_format,
         "corners", &sc_axles, NAMED(corner, ncorners, 2)),
    LIST("suspensions.corners", OPT, "single corners, after the axles' ones", &sc_corner_format,
         "corners", &sc_corners, NAMED(corner, ncorners, 1)),
    LIST("anti_roll_bars", OPT,
         "anti-roll bars, each between a left and a right corner (docs/scenario-format.md, "
         "\"Anti-roll bars\")",
         &sc_antiroll_bar_table, "anti_roll_bars", &sc_named,
         NAMED(antiroll_bar, nantiroll_bars, 1)),
    LIST("bogies", OPT,
         "walking-beam bogies, each carrying two corners' wheels (docs/scenario-format.md, "
         "\"Walking-beam bogies\")",
         &sc_bogie_table, "bogies", &sc_named, NAMED(bogie, nbogies, 1)),
    LIST("outputs", OPT,
         "the signals recorded, in CSV column order (default: every corner's tire_force)",
         &sc_output_table, "outputs", &sc_outputs, ITEMS(output, noutputs, 1)),
    SECTION_IS("road", REQ, "the road under the wheels", NULL, S_IS(road_type)),
    NUMBER("road.speed_kmh", "km/h", POSITIVE, REQ, "constant forward speed on a straight line",
           S_OFF(speed), .ops = &sc_kmh,
           PLAUSIBLE(0, 200, "wheeled vehicles drive at most about 200 km/h")),
    SECTION("report", OPT, "what the report shows", NULL),
    NUMBERS("report.mode_pictures", NULL, 1, FB_PICTURED_MODES_MAX, OPT,
            "System 2's modes pictured, by number (1: the lowest); default: chosen by what "
            "they are (the hull's bounce, roll and pitch, each mounted body's, the first "
            "wheel hop, the first two elastic modes)",
            S_OFF(pictured_modes), .count_at = offsetof(fb_scenario, npictured_modes)),
    SECTION("simulation", REQ, "the run", NULL),
    NUMBER("simulation.t_end", "s", POSITIVE, REQ, "end of the run (it starts at 0)",
           S_OFF(t_end)),
    NUMBER("simulation.rtol", NULL, OPEN(0, 1), REQ, "relative tolerance", S_OFF(rtol)),
    NUMBER("simulation.atol", NULL, POSITIVE, REQ, "absolute tolerance (all states)",
           S_OFF(atol)),
    NUMBER("simulation.max_step", "s", NONNEGATIVE, DEF(0), "largest step, 0: no limit",
           S_OFF(max_step)),
    WHOLE("simulation.max_steps", CLOSED(1, (double)FB_SIM_MAX_STEPS),
          DEF((double)FB_SIM_DEFAULT_MAX_STEPS), "internal steps allowed in the whole run",
          S_AT(LONG, max_steps),
          .why = "about a day of solver steps at 0.1 ms each; docs/errors.md, \"Limits\""),
    NUMBER("simulation.sample_rate", "Hz", POSITIVE, REQ, "outputs at k / sample_rate",
           S_OFF(sample_rate)),
    CHOICE("simulation.stability_limit_detection", sc_switch, DEF(1),
           "CVODE's BDF stability limit detection (fewer steps for a flexible hull, the same "
           "accuracy); `false`: CVODE's plain step selection",
           S_AT(INT, stability_limit_detection)),
    CHOICE("simulation.initial", sc_initials, REQ,
           "`zero`: every state zero, gravity on at t = 0; `static`: the static equilibrium",
           S_AT(INT, initial)),
};

const sch_table sc_format = TABLE(sc_keys, sc_root_done);

/* ---- Every value in its range, in the file's units (scenario_internal.h). */

typedef struct sc_range_check {
  fb_err *err;
  int rc;
} sc_range_check;

static int sc_check_one(const sch_value *v, void *ctx)
{
  sc_range_check *c = ctx;
  c->rc = sch_check_value(v, c->err);
  return c->rc;
}

int sc_check_ranges(const fb_scenario *s, fb_err *err)
{
  sc_schema *sc = NULL;
  int rc = sc_schema_of(s, &sc, err);
  if (rc)
    return rc;
  sc_range_check c = {err, FB_OK};
  sch_each(sc_schema_table(sc), s, sc_check_one, &c);
  sc_schema_release(&sc);
  return c.rc ? fb_scenario_locate(s, err) : FB_OK;
}

/* ---- A part of the description as its key (fb_err.part). */

/* The table of part kind kind's items, and the logical key of item i of
 * s ("corners.LF", "outputs[2]"; "" for the scenario itself) into
 * prefix; NULL when s has no such item. */
static const sch_table *sc_part_table(const fb_scenario *s, const sch_table *format, int kind,
                                      size_t i, char *prefix, size_t size)
{
  prefix[0] = '\0';
  switch (kind) {
  case FB_PART_VEHICLE: return format;
  case FB_PART_CORNER:
    if (i >= s->ncorners || !s->corner[i].name)
      return NULL;
    snprintf(prefix, size, "corners.%s", s->corner[i].name);
    return &sc_corner_format;
  case FB_PART_MOUNT:
    if (i >= s->nmounts || !s->mount[i].name)
      return NULL;
    snprintf(prefix, size, "mounts.%s", s->mount[i].name);
    return &sc_mount_table;
  case FB_PART_ANTIROLL_BAR:
    if (i >= s->nantiroll_bars || !s->antiroll_bar[i].name)
      return NULL;
    snprintf(prefix, size, "anti_roll_bars.%s", s->antiroll_bar[i].name);
    return &sc_antiroll_bar_table;
  case FB_PART_BOGIE:
    if (i >= s->nbogies || !s->bogie[i].name)
      return NULL;
    snprintf(prefix, size, "bogies.%s", s->bogie[i].name);
    return &sc_bogie_table;
  case FB_PART_BODY:
    if (i >= s->nbodies || !s->body[i].name)
      return NULL;
    snprintf(prefix, size, "bodies.%s", s->body[i].name);
    return &sc_body_table;
  case FB_PART_BUSHING: {
    size_t b = 0, j = 0;
    if (!fb_scenario_bushing_at(s, i, &b, &j) || !s->body[b].name)
      return NULL;
    snprintf(prefix, size, "bodies.%s.bushings[%zu]", s->body[b].name, j);
    return &sc_bushing_table;
  }
  case FB_PART_HULL_MASS:
    if (i >= s->npoint_masses || !s->point_mass[i].name)
      return NULL;
    snprintf(prefix, size, "hull.masses.%s", s->point_mass[i].name);
    return &sc_point_mass_table;
  case FB_PART_SECTION:
    if (i >= s->nsections)
      return NULL;
    snprintf(prefix, size, "hull.sections[%zu]", i);
    return &sc_section_table;
  case FB_PART_OUTPUT:
    if (i >= s->noutputs)
      return NULL;
    snprintf(prefix, size, "outputs[%zu]", i);
    return &sc_output_table;
  default: return NULL;
  }
}

/* 1 if s has an origin at exactly key. */
static int sc_has_origin(const fb_scenario *s, const char *key)
{
  const char *rest = NULL;
  return sc_origin_find(s, key, &rest) && rest && !*rest;
}

/* The key of the road type's parameter p->field. */
static int sc_road_part_key(const fb_scenario *s, const fb_err_part *p, char *key, size_t size)
{
  if (!s->road_type)
    return 0;
  int n =
      snprintf(key, size, "road.%s%s%s", s->road_type->name, p->field[0] ? "." : "", p->field);
  if (p->element != FB_ERR_NO_ELEMENT && n > 0 && (size_t)n < size)
    snprintf(key + n, size - (size_t)n, "[%zu]", p->element);
  return 1;
}

/* The key of member p->field of t's part, under prefix. */
static int sc_member_key(const fb_scenario *s, const sch_table *t, const char *prefix,
                         const fb_err_part *p, char *key, size_t size)
{
  /* Two keys may give one member: the one the file wrote, else the
   * first. */
  int found = 0;
  for (size_t k = 0; k < t->n; ++k) {
    const sch_key *sk = &t->key[k];
    if (!sk->member || strcmp(sk->member, p->field) != 0)
      continue;
    char full[SCH_PATH_MAX];
    int n = snprintf(full, sizeof full, "%s%s%s", prefix, prefix[0] ? "." : "", sk->path);
    if (p->element != FB_ERR_NO_ELEMENT && n > 0 && (size_t)n < sizeof full)
      snprintf(full + n, sizeof full - (size_t)n, "[%zu]", p->element);
    const int written = sc_has_origin(s, full);
    if (!found || written)
      snprintf(key, size, "%s", full);
    found = 1;
    if (written)
      break;
  }
  return found;
}

/* A damper law's parameter p: its generated key
 * corners.<name>.damper.<law>.<parameter> where the file wrote it, else
 * the corner's key that gave the law (damper_c, damper_table). */
static int sc_damper_part_key(const fb_scenario *s, const fb_err_part *p, char *key,
                              size_t size)
{
  if (p->index >= s->ncorners || !s->corner[p->index].name)
    return 0;
  const fb_corner_params *c = &s->corner[p->index];
  if (snprintf(key, size, "corners.%s.damper.%s.%s", c->name, fb_corner_damper_law(c)->name,
               p->field) > 0 &&
      sc_has_origin(s, key))
    return 1;
  fb_err_part q = {.kind = FB_PART_CORNER, .index = p->index, .element = FB_ERR_NO_ELEMENT};
  snprintf(q.field, sizeof q.field, "%s", fb_part_member_(FB_PART_CORNER, damper_law));
  return sc_part_key(s, &q, key, size);
}

/* A tire model's parameter p: its generated key, or a key of the wheel
 * of the same name written for it (wheel.tire_table). */
static int sc_tire_part_key(const fb_scenario *s, const fb_err_part *p, char *key, size_t size)
{
  if (p->index >= s->ncorners || !s->corner[p->index].name || !p->field[0])
    return 0;
  const char *name = s->corner[p->index].name;
  if (snprintf(key, size, "corners.%s.wheel.%s", name, p->field) > 0 && sc_has_origin(s, key))
    return 1;
  return snprintf(key, size, "corners.%s.wheel.%s.%s", name,
                  fb_corner_tire_model(&s->corner[p->index])->name, p->field) > 0;
}

/* A spring law's parameter p: the corner's key that gave the law
 * (spring_preload, spring_table). */
static int sc_spring_part_key(const fb_scenario *s, const fb_err_part *p, char *key,
                              size_t size)
{
  if (p->index >= s->ncorners || !s->corner[p->index].name)
    return 0;
  fb_err_part q = {.kind = FB_PART_CORNER, .index = p->index, .element = FB_ERR_NO_ELEMENT};
  snprintf(q.field, sizeof q.field, "%s", fb_part_member_(FB_PART_CORNER, spring_law));
  return sc_part_key(s, &q, key, size);
}

int sc_part_key(const fb_scenario *s, const fb_err_part *p, char *key, size_t size)
{
  char prefix[SCH_PATH_MAX];
  if (p->kind == FB_PART_LOAD_POINT) {
    if (p->index >= s->nload)
      return 0;
    snprintf(key, size, "load.points[%zu]", p->index);
    return 1;
  }
  if (p->kind == FB_PART_ROAD)
    return sc_road_part_key(s, p, key, size);
  if (p->kind == FB_PART_HULL_SOURCE) /* hull.mesh.<source>.<parameter> */
    return p->field[0] && snprintf(key, size, "hull.mesh.%s.%s",
                                   fb_scenario_hull_source(s)->name, p->field) > 0;
  if (p->kind == FB_PART_STOP) /* corners.<name>.bump_stop.<member> */
    return p->index < s->ncorners && s->corner[p->index].name && p->field[0] &&
           snprintf(key, size, "corners.%s.%s", s->corner[p->index].name, p->field) > 0;
  if (p->kind == FB_PART_SPRING) /* the key the corner's spring law was given by */
    return sc_spring_part_key(s, p, key, size);
  if (p->kind == FB_PART_DAMPER) /* the key the corner's damper law was given by */
    return sc_damper_part_key(s, p, key, size);
  if (p->kind == FB_PART_ENVELOPE) /* corners.<name>.wheel.<model>.<parameter> */
    return p->index < s->ncorners && s->corner[p->index].name && p->field[0] &&
           snprintf(key, size, "corners.%s.wheel.%s.%s", s->corner[p->index].name,
                    fb_corner_envelope_model(&s->corner[p->index])->name, p->field) > 0;
  if (p->kind == FB_PART_TIRE) /* corners.<name>.wheel.<model>.<parameter>, else */
    return sc_tire_part_key(s, p, key, size); /* corners.<name>.wheel.<its own key> */
  sc_schema *sc = NULL;
  if (sc_schema_of(s, &sc, NULL))
    return 0;
  const sch_table *t =
      sc_part_table(s, sc_schema_table(sc), p->kind, p->index, prefix, sizeof prefix);
  int found = 0;
  if (t && !p->field[0] && prefix[0]) {
    snprintf(key, size, "%s", prefix);
    found = 1;
  } else if (t && p->field[0]) {
    found = sc_member_key(s, t, prefix, p, key, size);
  }
  sc_schema_release(&sc);
  return found;
}

/* ---- Reading, visiting, documenting. */

/* The reader's origins, given ones only, moved into s. */
static int sc_keep_origins(sch_reader *r, fb_scenario *s)
{
  size_t n = 0;
  for (size_t i = 0; i < r->norigins; ++i)
    n += r->origin[i].given;
  sc_source *src = sc_source_of(s);
  if (!src)
    return fb_err_set(r->c->err, FB_EINVAL, "a scenario without the loader's source");
  src->origin = calloc(n ? n : 1, sizeof *src->origin);
  if (!src->origin)
    return fb_err_set(r->c->err, FB_ENOMEM, "out of memory for %zu origins", n);
  for (size_t i = 0; i < r->norigins; ++i) {
    sch_origin *o = &r->origin[i];
    if (!o->given)
      continue;
    sc_value_origin *to = &src->origin[src->norigins++];
    *to = (sc_value_origin){o->key, o->path, o->line, o->column, NULL};
    o->key = o->path = NULL;
    if (o->override && !(to->override = fb_strdup(o->override)))
      return fb_err_set(r->c->err, FB_ENOMEM, "out of memory for %zu origins", n);
  }
  return FB_OK;
}

int sc_read(ml_ctx *c, const sch_table *t, struct fy_node *root, fb_symtab *params,
            sch_override *ov, size_t nov, fb_scenario *s)
{
  sc_reading rd = {params, t};
  sch_reader r = {.c = c, .user = &rd, .ov = ov, .nov = nov};
  c->globals = params;
  int rc = sch_read(&r, t, root, s);
  if (!rc)
    rc = sc_keep_origins(&r, s);
  sch_reader_release(&r);
  return rc;
}

int fb_scenario_schema_markdown(FILE *fp, fb_err *err)
{
  sc_schema *sc = NULL;
  const int rc = sc_schema_new(NULL, &sc, err);
  if (!rc)
    sch_markdown(sc_schema_table(sc), fp);
  sc_schema_release(&sc);
  return rc;
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
  double frame[3];
  fb_scenario_frame_offset(visit->s, frame);
  /* Stored from the centre of mass; given as the file wrote it, to the
   * ten digits that hide the round-off of the move there and back. */
  if (v->key->axis == SCH_AXIS_POINT) {
    const double *p = (const double *)(const void *)((const char *)v->base + v->key->offset);
    snprintf(text, sizeof text, "%.10g, %.10g, %.10g", p[0] + frame[0], p[1] + frame[1],
             p[2] + frame[2]);
  } else if (v->key->axis) {
    snprintf(text, sizeof text, "%.10g", v->number + frame[v->key->axis - 1]);
  } else {
    sch_format(v, text, sizeof text);
  }
  const char *rest = NULL;
  const sc_value_origin *o = sc_origin_find(visit->s, v->path, &rest);
  const fb_scenario_value value = {v->path, o && !*rest ? o->path : NULL,
                                   v->key->unit ? v->key->unit : "", v->key->doc, text};
  return visit->fn(&value, visit->ctx);
}

int fb_scenario_each_value(const fb_scenario *s, fb_scenario_value_fn fn, void *ctx)
{
  if (!s || !fn)
    return FB_EINVAL;
  sc_schema *sc = NULL;
  if (sc_schema_of(s, &sc, NULL))
    return FB_ENOMEM;
  sc_visit visit = {s, fn, ctx};
  const int stop = sch_each(sc_schema_table(sc), s, sc_visit_value, &visit);
  sc_schema_release(&sc);
  return stop;
}
