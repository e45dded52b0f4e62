/* Scenario files (docs/scenario-format.md): the sections read into an
 * fb_scenario with the model loader's YAML helpers, and the mapping of
 * fb_scenario_check's key paths back to the file. */
#include <ctype.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/util.h"
#include "io/scenario_internal.h"

/* ---- Small readers. */

/* A number field of a section and where it goes. */
typedef struct sc_field {
  const char *key;
  double *dst;
} sc_field;

/* Required number (or constant expression over the `parameters`). */
static int sc_number(const ml_ctx *c, struct fy_node *map, const char *key, double *out)
{
  struct fy_node *v = NULL;
  int rc = ml_require(c, map, key, &v);
  return rc ? rc : ml_number(c, v, c->globals, out);
}

/* Every field of f (n of them) is required in map. */
static int sc_fields(const ml_ctx *c, struct fy_node *map, const sc_field *f, size_t n)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < n; ++i)
    rc = sc_number(c, map, f[i].key, f[i].dst);
  return rc;
}

/* The required mapping `key` of map, holding only the keys allowed. */
static int sc_section(const ml_ctx *c, struct fy_node *map, const char *key, const char *what,
                      const char *const *allowed, struct fy_node **out)
{
  int rc = ml_require(c, map, key, out);
  if (!rc)
    rc = ml_expect_map(c, *out, what);
  if (!rc)
    rc = ml_check_keys(c, *out, allowed);
  return rc;
}

/* The required key of map names one of names (NULL-terminated): *out
 * gets its index. */
static int sc_choice(const ml_ctx *c, struct fy_node *map, const char *key,
                     const char *const *names, int *out)
{
  struct fy_node *v = NULL;
  const char *text = NULL;
  int rc = ml_require(c, map, key, &v);
  if (!rc)
    rc = ml_string(c, v, &text);
  if (rc)
    return rc;
  char list[128] = "";
  size_t len = 0;
  for (int i = 0; names[i]; ++i) {
    if (!strcmp(text, names[i])) {
      *out = i;
      return FB_OK;
    }
    int k = snprintf(list + len, sizeof list - len, "%s%s", i ? " | " : "", names[i]);
    len = (k > 0 && len + (size_t)k < sizeof list) ? len + (size_t)k : len;
  }
  const char *near = ml_suggest_list(text, names);
  char hint[96] = "";
  if (near)
    snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
  return ml_fail(c, v, FB_EPARSE, "unknown value '%s'%s; expected %s", text, hint, list);
}

/* ---- Sections. */

/* A required whole number in [lo, hi] of map. */
static int sc_int(const ml_ctx *c, struct fy_node *map, const char *key, size_t lo, size_t hi,
                  int *out)
{
  struct fy_node *v = NULL;
  size_t n = 0;
  int rc = ml_require(c, map, key, &v);
  if (!rc)
    rc = ml_count(c, v, c->globals, lo, hi, &n);
  *out = (int)n;
  return rc;
}

/* hull.mesh.generator: the fitted hull geometry (docs/hull-mesh.md). */
static int sc_generator(const ml_ctx *c, struct fy_node *mesh, fb_hull_mesh_params *p)
{
  static const char *const keys[] = {
      "width",       "height",    "x_rear",    "x_front",   "nose_length",
      "nose_height", "bulkheads", "side_rows", "nose_rows", "nose_rung_divisions",
      NULL};
  const sc_field f[] = {{"width", &p->width},
                        {"height", &p->height},
                        {"x_rear", &p->x_rear},
                        {"x_front", &p->x_front},
                        {"nose_length", &p->nose_length},
                        {"nose_height", &p->nose_height}};
  struct fy_node *gen = NULL, *bulk = NULL;
  int rc = sc_section(c, mesh, "generator", "the hull generator's geometry", keys, &gen);
  if (!rc)
    rc = sc_fields(c, gen, f, sizeof f / sizeof f[0]);
  double *x = NULL;
  size_t n = 0;
  if (!rc)
    rc = ml_require(c, gen, "bulkheads", &bulk);
  if (!rc && !ml_is_null(bulk) && fy_node_sequence_item_count(bulk) > 0)
    rc = ml_vector(c, bulk, c->globals, 0, 0, &x, &n);
  if (!rc && n > FB_HULL_MAX_BULKHEADS)
    rc =
        ml_fail(c, bulk, FB_EINVAL, "at most %d bulkheads (got %zu)", FB_HULL_MAX_BULKHEADS, n);
  for (size_t k = 0; !rc && k < n; ++k)
    p->bulkhead_x[k] = x[k];
  p->nbulkheads = rc ? 0 : n;
  free(x);
  if (!rc)
    rc = sc_int(c, gen, "side_rows", 1, 64, &p->side_rows);
  if (!rc)
    rc = sc_int(c, gen, "nose_rows", 1, 64, &p->nose_rows);
  if (!rc)
    rc = sc_int(c, gen, "nose_rung_divisions", 1, 64, &p->nose_rung_divisions);
  return rc;
}

/* The optional System 2 sections hull.mesh {generator | deck, density}
 * and hull.fe {mass_matrix, drill_factor, damping_ratio, modes}. */
static int sc_fe_hull(const ml_ctx *c, struct fy_node *hull, fb_scenario *s)
{
  static const char *const mesh_keys[] = {"generator", "deck", "density", NULL};
  static const char *const fe_keys[] = {"mass_matrix", "drill_factor", "damping_ratio", "modes",
                                        NULL};
  static const char *const masses[] = {"consistent", "lumped", NULL};
  struct fy_node *mesh = ml_get(hull, "mesh", NULL), *fe = ml_get(hull, "fe", NULL);
  if (!mesh && !fe)
    return FB_OK;
  struct fy_node *deck = NULL;
  int rc = sc_section(c, hull, "mesh", "the hull mesh {generator | deck, density}", mesh_keys,
                      &mesh);
  if (!rc)
    rc = sc_section(c, hull, "fe",
                    "the hull's finite elements {mass_matrix, drill_factor, "
                    "damping_ratio, modes}",
                    fe_keys, &fe);
  struct fy_node *density = NULL;
  if (!rc && (deck = ml_get(mesh, "deck", NULL)) && !ml_is_null(deck)) {
    const char *text = NULL;
    rc = ml_string(c, deck, &text);
    if (!rc)
      rc = ml_resolve_path(c, deck, text, &s->hull_deck);
    if (!rc && ml_get(mesh, "generator", NULL))
      rc = ml_fail(c, deck, FB_EPARSE, "give either a deck or a generator, not both");
    if (!rc && (density = ml_get(mesh, "density", NULL)))
      rc = ml_fail(c, density, FB_EPARSE,
                   "density refines the generator's mesh; a deck is used as it is");
  } else if (!rc) {
    rc = sc_generator(c, mesh, &s->hull_mesh);
    if (!rc)
      rc = sc_int(c, mesh, "density", 1, 64, &s->hull_mesh.density);
  }
  int mass = 0;
  if (!rc)
    rc = sc_choice(c, fe, "mass_matrix", masses, &mass);
  s->hull_mass_matrix = mass ? FB_MASS_LUMPED : FB_MASS_CONSISTENT;
  if (!rc)
    rc = sc_number(c, fe, "drill_factor", &s->hull_drill_factor);
  if (!rc)
    rc = sc_number(c, fe, "damping_ratio", &s->hull_damping_ratio);
  if (!rc && ml_get(fe, "modes", NULL))
    rc = sc_int(c, fe, "modes", 0, 100000, &s->hull_modes);
  s->has_fe_hull = !rc;
  return rc;
}

static int sc_hull(const ml_ctx *c, struct fy_node *root, fb_scenario *s)
{
  static const char *const keys[] = {"mass",  "Ixx",  "Iyy", "material",
                                     "edges", "mesh", "fe",  NULL};
  static const char *const material_keys[] = {"young", "poisson", "density", "thickness", NULL};
  static const char *const edge_keys[] = {"front_x", "rear_x", "left_y", "right_y", NULL};
  const sc_field body[] = {
      {"mass", &s->hull_mass}, {"Ixx", &s->hull_ixx}, {"Iyy", &s->hull_iyy}};
  const sc_field material[] = {{"young", &s->young},
                               {"poisson", &s->poisson},
                               {"density", &s->density},
                               {"thickness", &s->thickness}};
  const sc_field edges[] = {{"front_x", &s->edge_front_x},
                            {"rear_x", &s->edge_rear_x},
                            {"left_y", &s->edge_left_y},
                            {"right_y", &s->edge_right_y}};
  struct fy_node *hull = NULL, *mat = NULL, *edge = NULL;
  int rc =
      sc_section(c, root, "hull", "the hull {mass, Ixx, Iyy, material, edges}", keys, &hull);
  if (!rc)
    rc = sc_fields(c, hull, body, sizeof body / sizeof body[0]);
  if (!rc)
    rc = sc_section(c, hull, "material", "the material {young, poisson, density, thickness}",
                    material_keys, &mat);
  if (!rc)
    rc = sc_fields(c, mat, material, sizeof material / sizeof material[0]);
  if (!rc)
    rc = sc_section(c, hull, "edges", "the torsion edges {front_x, rear_x, left_y, right_y}",
                    edge_keys, &edge);
  if (!rc)
    rc = sc_fields(c, edge, edges, sizeof edges / sizeof edges[0]);
  if (!rc)
    rc = sc_fe_hull(c, hull, s);
  return rc;
}

/* Stores n points (x[i], y[i]) as the load points. */
static int sc_set_points(const ml_ctx *c, fb_scenario *s, size_t n)
{
  s->load_x = malloc(n * sizeof *s->load_x);
  s->load_y = malloc(n * sizeof *s->load_y);
  if (!s->load_x || !s->load_y)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory for %zu load points", n);
  s->nload = n;
  return FB_OK;
}

/* points: {grid: {x: [...], y: [...]}}: every x with every y, x-major
 * (point i * ny + j is (x[i], y[j])). */
static int sc_grid(const ml_ctx *c, struct fy_node *points, fb_scenario *s)
{
  static const char *const keys[] = {"grid", NULL};
  static const char *const grid_keys[] = {"x", "y", NULL};
  struct fy_node *grid = NULL, *xn = NULL, *yn = NULL;
  double *xs = NULL, *ys = NULL;
  size_t nx = 0, ny = 0;
  int rc = ml_check_keys(c, points, keys);
  if (!rc)
    rc = sc_section(c, points, "grid", "a grid {x: [...], y: [...]}", grid_keys, &grid);
  if (!rc)
    rc = ml_require(c, grid, "x", &xn);
  if (!rc)
    rc = ml_vector(c, xn, c->globals, 0, 0, &xs, &nx);
  if (!rc)
    rc = ml_require(c, grid, "y", &yn);
  if (!rc)
    rc = ml_vector(c, yn, c->globals, 0, 0, &ys, &ny);
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

/* points: [[x, y], ...]. */
static int sc_point_list(const ml_ctx *c, struct fy_node *points, fb_scenario *s)
{
  size_t n = (size_t)fy_node_sequence_item_count(points);
  if (n == 0)
    return ml_fail(c, points, FB_EINVAL, "at least one load point is needed");
  int rc = sc_set_points(c, s, n);
  for (size_t i = 0; !rc && i < n; ++i) {
    double *p = NULL;
    size_t len = 0;
    rc =
        ml_vector(c, fy_node_sequence_get_by_index(points, (int)i), c->globals, 2, 0, &p, &len);
    if (!rc) {
      s->load_x[i] = p[0];
      s->load_y[i] = p[1];
    }
    free(p);
  }
  return rc;
}

static int sc_load(const ml_ctx *c, struct fy_node *root, fb_scenario *s)
{
  static const char *const keys[] = {"total_weight", "payload", "points", NULL};
  static const char *const payloads[] = {"weight-only", "lumped", NULL};
  struct fy_node *load = NULL, *points = NULL;
  int payload = 0;
  int rc = sc_section(c, root, "load", "the load {total_weight, payload, points}", keys, &load);
  if (!rc)
    rc = sc_number(c, load, "total_weight", &s->total_weight);
  if (!rc)
    rc = sc_choice(c, load, "payload", payloads, &payload);
  s->payload = payload ? FB_PAYLOAD_LUMPED : FB_PAYLOAD_WEIGHT_ONLY;
  if (!rc)
    rc = ml_require(c, load, "points", &points);
  if (rc)
    return rc;
  if (fy_node_is_mapping(points))
    return sc_grid(c, points, s);
  if (fy_node_is_sequence(points))
    return sc_point_list(c, points, s);
  return ml_fail(
      c, points, FB_EPARSE,
      "expected the load points as {grid: {x: [...], y: [...]}} or a list of [x, y]");
}

/* driver or engine. */
static int sc_mount(const ml_ctx *c, struct fy_node *root, const char *key, fb_mount *m)
{
  static const char *const keys[] = {"mass", "stiffness", "damping", "x", "y", NULL};
  const sc_field f[] = {{"mass", &m->mass},
                        {"stiffness", &m->stiffness},
                        {"damping", &m->damping},
                        {"x", &m->x},
                        {"y", &m->y}};
  struct fy_node *sec = NULL;
  int rc = sc_section(c, root, key, "a mount {mass, stiffness, damping, x, y}", keys, &sec);
  return rc ? rc : sc_fields(c, sec, f, sizeof f / sizeof f[0]);
}

/* The `wheel` section: what every corner has unless it overrides it. */
static int sc_wheel(const ml_ctx *c, struct fy_node *root, fb_corner_params *shared)
{
  static const char *const keys[] = {"mass", "tire_k", "tire_c", "tire_contact", NULL};
  static const char *const contacts[] = {"bilateral", "unilateral", NULL};
  const sc_field f[] = {
      {"mass", &shared->wheel_mass}, {"tire_k", &shared->tire_k}, {"tire_c", &shared->tire_c}};
  struct fy_node *sec = NULL;
  int rc = sc_section(c, root, "wheel", "the wheels {mass, tire_k, tire_c[, tire_contact]}",
                      keys, &sec);
  if (!rc)
    rc = sc_fields(c, sec, f, sizeof f / sizeof f[0]);
  /* Optional: the paper's linear tire unless told otherwise. */
  int contact = 0;
  if (!rc && fy_node_mapping_lookup_by_string(sec, "tire_contact", FY_NT))
    rc = sc_choice(c, sec, "tire_contact", contacts, &contact);
  shared->tire_contact = contact ? FB_TIRE_UNILATERAL : FB_TIRE_BILATERAL;
  return rc;
}

/* Keys of `suspensions`: the shared motion_ratio and the six corners; an
 * unknown corner is named with the valid ones. */
static int sc_corner_keys(const ml_ctx *c, struct fy_node *susp)
{
  static const char *const keys[] = {"motion_ratio", "LF", "RF", "LM", "RM", "LR", "RR", NULL};
  void *iter = NULL;
  struct fy_node_pair *pair;
  while ((pair = fy_node_mapping_iterate(susp, &iter))) {
    struct fy_node *key = fy_node_pair_key(pair);
    const char *text = fy_node_is_scalar(key) ? fy_node_get_scalar0(key) : NULL;
    if (!text)
      return ml_fail(c, susp, FB_EPARSE, "keys must be plain names");
    size_t i = 0;
    while (keys[i] && strcmp(keys[i], text) != 0)
      ++i;
    if (keys[i])
      continue;
    const char *near = ml_suggest_list(text, keys);
    char hint[96] = "";
    if (near)
      snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
    return ml_fail_key(c, susp, key, FB_EPARSE,
                       "unknown suspension '%s'%s; the corners are LF, RF, LM, RM, LR, RR "
                       "(besides them: motion_ratio)",
                       text, hint);
  }
  return FB_OK;
}

/* The knots of a damper table into the corner (copied: the scenario is
 * plain data), refusing a table that is not passive or too long. */
static int sc_damper_knots(const ml_ctx *c, struct fy_node *table, const fb_table_law *law,
                           fb_corner_params *out)
{
  const double *v = NULL, *f = NULL;
  const size_t n = fb_table_law_knots(law, &v, &f);
  if (n > FB_DAMPER_MAX_POINTS)
    return ml_fail(c, table, FB_EINVAL, "a damper table has at most %d points (got %zu)",
                   (int)FB_DAMPER_MAX_POINTS, n);
  if (fb_table_law_check_passive(law, c->err))
    return ml_blame(c, table);
  out->damper_npoints = n;
  memcpy(out->damper_v, v, n * sizeof *v);
  memcpy(out->damper_f, f, n * sizeof *f);
  return FB_OK;
}

/* The shock absorber: damper_c (N s/m) or damper_table (force against
 * velocity, see docs/scenario-format.md), exactly one of them. */
static int sc_shock_absorber(const ml_ctx *c, struct fy_node *node, fb_corner_params *out)
{
  struct fy_node *c_key = NULL, *t_key = NULL;
  ml_get(node, "damper_c", &c_key);
  struct fy_node *table = ml_get(node, "damper_table", &t_key);
  out->damper_npoints = 0;
  if (c_key && t_key)
    return ml_fail_key(c, node, t_key, FB_EPARSE,
                       "give either damper_c or damper_table, not both");
  if (!t_key)
    return sc_number(c, node, "damper_c", &out->damper_c);
  fb_table_law *law = NULL;
  int rc = ml_table_law(c, c->globals, table, &law);
  if (!rc)
    rc = sc_damper_knots(c, table, law, out);
  fb_table_law_free(&law);
  out->damper_c = 0.0;
  return rc;
}

/* One corner: its own spring, damper and attachment point, and optional
 * overrides of the shared values. */
static int sc_corner(const ml_ctx *c, struct fy_node *susp, int k,
                     const fb_corner_params *shared, fb_corner_params *out)
{
  static const char *const keys[] = {
      "spring_k",     "damper_c",   "damper_table", "x",      "y",
      "motion_ratio", "wheel_mass", "tire_k",       "tire_c", NULL};
  const sc_field own[] = {{"spring_k", &out->spring_k}, {"x", &out->x}, {"y", &out->y}};
  const sc_field overrides[] = {{"motion_ratio", &out->motion_ratio},
                                {"wheel_mass", &out->wheel_mass},
                                {"tire_k", &out->tire_k},
                                {"tire_c", &out->tire_c}};
  const char *name = fb_corner_name(k);
  struct fy_node *key = NULL;
  struct fy_node *node = ml_get(susp, name, &key);
  *out = *shared;
  if (!key)
    return ml_fail(c, susp, FB_EPARSE,
                   "missing corner '%s' (the six corners are LF, RF, LM, RM, LR, RR)", name);
  if (ml_is_null(node))
    return ml_fail_key(c, susp, key, FB_EPARSE, "missing value");
  int rc = ml_expect_map(c, node, "a suspension {spring_k, damper_c | damper_table, x, y}");
  if (!rc)
    rc = ml_check_keys(c, node, keys);
  if (!rc)
    rc = sc_fields(c, node, own, sizeof own / sizeof own[0]);
  if (!rc)
    rc = sc_shock_absorber(c, node, out);
  for (size_t i = 0; !rc && i < sizeof overrides / sizeof overrides[0]; ++i)
    rc = ml_opt_number(c, node, overrides[i].key, c->globals, overrides[i].dst);
  return rc;
}

static int sc_suspensions(const ml_ctx *c, struct fy_node *root, fb_scenario *s)
{
  fb_corner_params shared;
  memset(&shared, 0, sizeof shared);
  struct fy_node *susp = NULL;
  int rc = sc_wheel(c, root, &shared);
  if (!rc)
    rc = ml_require(c, root, "suspensions", &susp);
  if (!rc)
    rc = ml_expect_map(c, susp, "the suspensions {motion_ratio, LF, RF, LM, RM, LR, RR}");
  if (!rc)
    rc = sc_corner_keys(c, susp);
  if (!rc)
    rc = sc_number(c, susp, "motion_ratio", &shared.motion_ratio);
  for (int k = 0; !rc && k < FB_NCORNERS; ++k)
    rc = sc_corner(c, susp, k, &shared, &s->corner[k]);
  return rc;
}

/* road.bump: height and length, or a Brazilian type (I, II; CONTRAN),
 * then angle_deg and first_contact. */
static int sc_bump(const ml_ctx *c, struct fy_node *bump, fb_scenario *s)
{
  static const char *const keys[] = {"height",    "length",        "type",
                                     "angle_deg", "first_contact", NULL};
  double angle_deg = 0;
  const sc_field own[] = {{"angle_deg", &angle_deg}, {"first_contact", &s->bump_time}};
  const sc_field size[] = {{"height", &s->bump_height}, {"length", &s->bump_length}};
  struct fy_node *type_key = NULL, *type = NULL;
  int rc = ml_expect_map(c, bump, "the bump {height, length | type, angle_deg, first_contact}");
  if (!rc)
    rc = ml_check_keys(c, bump, keys);
  if (!rc)
    type = ml_get(bump, "type", &type_key);
  if (!rc && type_key) {
    const char *name = NULL;
    if (ml_get(bump, "height", NULL) || ml_get(bump, "length", NULL))
      return ml_fail_key(c, bump, type_key, FB_EPARSE,
                         "give either a type or height and length, not both");
    rc = ml_string(c, type, &name);
    if (!rc && fb_road_speed_bump(name, &s->bump_height, &s->bump_length, c->err))
      rc = ml_blame(c, type);
  } else if (!rc) {
    rc = sc_fields(c, bump, size, sizeof size / sizeof size[0]);
  }
  if (!rc)
    rc = sc_fields(c, bump, own, sizeof own / sizeof own[0]);
  /* Dividing by 180 first keeps 90 deg exactly pi / 2 (a power-of-two
   * scaling), so the check's "< 90 deg" bound is exact. */
  s->bump_angle = angle_deg / 180 * SC_PI;
  return rc;
}

/* An optional whole number >= 0 of map into *out (kept when absent). */
static int sc_opt_count(const ml_ctx *c, struct fy_node *map, const char *key, size_t hi,
                        size_t *out)
{
  struct fy_node *v = ml_get(map, key, NULL);
  return v ? ml_count(c, v, c->globals, 0, hi, out) : FB_OK;
}

/* road.iso8608: class (A .. H), seed, and optional band, harmonics,
 * fade_in (m) and front_start (m); checked by fb_road_new_iso8608. YAML
 * numbers are read as doubles, so the seed is a whole number up to 2^53,
 * where every integer is exact. */
static int sc_iso8608(const ml_ctx *c, struct fy_node *iso, fb_scenario *s)
{
  static const char *const keys[] = {"class",   "seed",        "band", "harmonics",
                                     "fade_in", "front_start", NULL};
  fb_road_iso8608_params *p = &s->road_iso;
  fb_road_iso8608_defaults(p);
  struct fy_node *cls = NULL, *band = NULL;
  const char *letter = NULL;
  size_t seed = 0, harmonics = p->nharmonics;
  int rc = ml_expect_map(c, iso,
                         "an ISO 8608 road {class, seed, band, harmonics, fade_in, "
                         "front_start}");
  if (!rc)
    rc = ml_check_keys(c, iso, keys);
  if (!rc)
    rc = ml_require(c, iso, "class", &cls);
  if (!rc)
    rc = ml_string(c, cls, &letter);
  if (!rc && (strlen(letter) != 1 || !strchr("ABCDEFGHabcdefgh", letter[0])))
    rc = ml_fail(c, cls, FB_EINVAL, "the class is a letter A .. H (got '%s')", letter);
  if (!rc)
    p->road_class = letter[0];
  struct fy_node *seed_node = NULL;
  if (!rc)
    rc = ml_require(c, iso, "seed", &seed_node);
  if (!rc)
    rc = ml_count(c, seed_node, c->globals, 0, (size_t)1 << 53, &seed);
  p->seed = (uint64_t)seed;
  if (!rc)
    rc = sc_opt_count(c, iso, "harmonics", 1000000, &harmonics);
  p->nharmonics = harmonics;
  if (!rc && (band = ml_get(iso, "band", NULL))) {
    double *b = NULL;
    size_t len = 0;
    rc = ml_vector(c, band, c->globals, 2, 0, &b, &len);
    if (!rc) {
      p->n_min = b[0];
      p->n_max = b[1];
    }
    free(b);
  }
  if (!rc)
    rc = ml_opt_number(c, iso, "fade_in", c->globals, &p->fade_length);
  if (!rc)
    rc = ml_opt_number(c, iso, "front_start", c->globals, &s->road_front_start);
  s->road_kind = FB_ROAD_ISO8608;
  return rc;
}

/* road.profile: a CSV file (s, z or s, z_left, z_right) and front_start. */
static int sc_profile(const ml_ctx *c, struct fy_node *prof, fb_scenario *s)
{
  static const char *const keys[] = {"file", "front_start", NULL};
  struct fy_node *file = NULL;
  const char *name = NULL;
  int rc = ml_expect_map(c, prof, "a road profile {file, front_start}");
  if (!rc)
    rc = ml_check_keys(c, prof, keys);
  if (!rc)
    rc = ml_require(c, prof, "file", &file);
  if (!rc)
    rc = ml_string(c, file, &name);
  if (!rc)
    rc = ml_resolve_path(c, file, name, &s->road_profile);
  /* Read once here so that a bad file is reported at its YAML key. */
  fb_road *road = NULL;
  if (!rc && fb_road_new_csv(s->road_profile, &road, c->err))
    rc = ml_blame(c, file);
  fb_road_free(&road);
  if (!rc)
    rc = ml_opt_number(c, prof, "front_start", c->globals, &s->road_front_start);
  s->road_kind = FB_ROAD_PROFILE;
  return rc;
}

static int sc_road(const ml_ctx *c, struct fy_node *root, fb_scenario *s)
{
  static const char *const keys[] = {"speed_kmh", "bump", "iso8608", "profile", NULL};
  static const char *const kinds[] = {"bump", "iso8608", "profile"};
  struct fy_node *road = NULL, *kind = NULL;
  double speed_kmh = 0;
  int rc = sc_section(c, root, "road", "the road {speed_kmh, bump | iso8608 | profile}", keys,
                      &road);
  if (!rc)
    rc = sc_number(c, road, "speed_kmh", &speed_kmh);
  s->speed = speed_kmh / 3.6;
  int which = -1;
  for (int k = 0; !rc && k < 3; ++k) {
    struct fy_node *key = NULL, *v = ml_get(road, kinds[k], &key);
    if (!key)
      continue;
    if (which >= 0)
      return ml_fail_key(c, road, key, FB_EPARSE, "give one road: '%s' or '%s', not both",
                         kinds[which], kinds[k]);
    which = k;
    kind = v;
  }
  if (!rc && which < 0)
    return ml_fail(c, road, FB_EPARSE, "missing road: one of 'bump', 'iso8608', 'profile'");
  s->road_kind = FB_ROAD_BUMP;
  if (!rc)
    rc = which == 0   ? sc_bump(c, kind, s)
         : which == 1 ? sc_iso8608(c, kind, s)
                      : sc_profile(c, kind, s);
  return rc;
}

static int sc_simulation(const ml_ctx *c, struct fy_node *root, fb_scenario *s)
{
  static const char *const keys[] = {"t_end",       "rtol",    "atol",      "max_step",
                                     "sample_rate", "initial", "max_steps", NULL};
  static const char *const initials[] = {"zero", "static", NULL};
  const sc_field f[] = {{"t_end", &s->t_end},
                        {"rtol", &s->rtol},
                        {"atol", &s->atol},
                        {"sample_rate", &s->sample_rate}};
  struct fy_node *sim = NULL;
  int initial = 0;
  int rc = sc_section(c, root, "simulation",
                      "the simulation settings {t_end, rtol, atol, sample_rate, initial}", keys,
                      &sim);
  if (!rc)
    rc = sc_fields(c, sim, f, sizeof f / sizeof f[0]);
  s->max_step = 0; /* no limit */
  if (!rc)
    rc = ml_opt_number(c, sim, "max_step", c->globals, &s->max_step);
  /* The solver's budget of internal steps, as a model's (fb_sim_opts). */
  s->max_steps = FB_SIM_DEFAULT_MAX_STEPS;
  struct fy_node *v = NULL;
  size_t count = 0;
  if (!rc && (v = ml_get(sim, "max_steps", NULL)) &&
      !(rc = ml_count(c, v, c->globals, 1, (size_t)LONG_MAX, &count)))
    s->max_steps = (long)count;
  if (!rc)
    rc = sc_choice(c, sim, "initial", initials, &initial);
  s->initial = initial ? FB_INITIAL_STATIC : FB_INITIAL_ZERO;
  return rc;
}

/* `scenario` (name) and the optional `description`. */
static int sc_name(const ml_ctx *c, struct fy_node *root, fb_scenario *s)
{
  struct fy_node *v = NULL;
  const char *name = NULL, *description = NULL;
  int rc = ml_require(c, root, "scenario", &v);
  if (!rc)
    rc = ml_name(c, v, "scenario name", &name);
  if (!rc && (v = ml_get(root, "description", NULL)))
    rc = ml_text(c, v, &description);
  if (rc)
    return rc;
  s->name = fb_strdup(name);
  if (!s->name)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  return FB_OK;
}

int sc_read(ml_ctx *c, struct fy_node *root, fb_symtab *params, fb_scenario *s)
{
  static const char *const keys[] = {
      "scenario", "description", "parameters",  "gravity", "hull",       "load", "driver",
      "engine",   "wheel",       "suspensions", "road",    "simulation", NULL};
  int rc = ml_expect_map(c, root, "a scenario {scenario, gravity, hull, load, ...}");
  if (!rc)
    rc = ml_check_keys(c, root, keys);
  if (!rc)
    rc = sc_name(c, root, s);
  if (!rc)
    rc = ml_parameters(c, ml_get(root, "parameters", NULL), params, NULL);
  c->globals = params;
  if (!rc)
    rc = sc_number(c, root, "gravity", &s->gravity);
  if (!rc)
    rc = sc_hull(c, root, s);
  if (!rc)
    rc = sc_load(c, root, s);
  if (!rc)
    rc = sc_mount(c, root, "driver", &s->driver);
  if (!rc)
    rc = sc_mount(c, root, "engine", &s->engine);
  if (!rc)
    rc = sc_suspensions(c, root, s);
  if (!rc)
    rc = sc_road(c, root, s);
  if (!rc)
    rc = sc_simulation(c, root, s);
  return rc;
}

/* ---- Check messages back to the file. */

/* The node at path ("a.b[2].c") below root; *whole is 1 if every segment
 * exists, else the deepest node found is returned. */
static struct fy_node *sc_walk(struct fy_node *root, const char *path, int *whole)
{
  struct fy_node *n = root;
  *whole = 0;
  while (*path) {
    struct fy_node *next = NULL;
    size_t len = strcspn(path, ".[");
    if (len > 0 && len < 64 && fy_node_is_mapping(n)) {
      char key[64];
      memcpy(key, path, len);
      key[len] = '\0';
      next = ml_get(n, key, NULL);
    } else if (len == 0 && fy_node_is_sequence(n)) {
      char *end = NULL;
      long i = strtol(path + 1, &end, 10);
      next = (*end == ']' && i >= 0 && i < fy_node_sequence_item_count(n))
                 ? fy_node_sequence_get_by_index(n, (int)i)
                 : NULL;
      len = (size_t)(end - path) + 1;
    }
    if (!next)
      return n;
    n = next;
    path += len;
    path += *path == '.';
  }
  *whole = 1;
  return n;
}

/* Per-corner values the file may give once for all corners: the shared
 * key a "suspensions.XX.key" comes from when the corner has no override. */
static struct fy_node *sc_shared_source(struct fy_node *root, const char *path)
{
  static const char *const from[][2] = {{"wheel_mass", "wheel.mass"},
                                        {"tire_k", "wheel.tire_k"},
                                        {"tire_c", "wheel.tire_c"},
                                        {"motion_ratio", "suspensions.motion_ratio"}};
  const char *last = strrchr(path, '.');
  if (strncmp(path, "suspensions.", 12) != 0 || !last)
    return NULL;
  for (size_t i = 0; i < sizeof from / sizeof from[0]; ++i)
    if (!strcmp(last + 1, from[i][0])) {
      int whole = 0;
      struct fy_node *n = sc_walk(root, from[i][1], &whole);
      return whole ? n : NULL;
    }
  return NULL;
}

int sc_blame_check(const ml_ctx *c, struct fy_node *root)
{
  const char *msg = c->err->msg;
  const char *sep = strstr(msg, ": ");
  char key[256], rest[FB_ERR_MSG_MAX];
  size_t klen = sep ? (size_t)(sep - msg) : 0;
  if (!sep || klen == 0 || klen >= sizeof key)
    return ml_blame_located(c, root);
  memcpy(key, msg, klen);
  key[klen] = '\0';
  snprintf(rest, sizeof rest, "%s", sep + 2);
  int whole = 0;
  struct fy_node *at = sc_walk(root, key, &whole);
  struct fy_node *shared = whole ? NULL : sc_shared_source(root, key);
  /* Found in the file: the message names the key as written there. */
  if (whole || shared)
    return ml_fail(c, shared ? shared : at, c->err->code, "%s", rest);
  return ml_blame_located(c, at);
}

/* A key path as the check messages write it: a name, then ".name" or
 * "[i]" segments; no spaces (a context such as "hull mesh" is none). */
static int sc_is_key_path(const char *text, size_t len)
{
  if (len == 0 || !(isalpha((unsigned char)text[0]) || text[0] == '_'))
    return 0;
  for (size_t i = 0; i < len; ++i)
    if (!(isalnum((unsigned char)text[i]) || strchr("_.[]", text[i])))
      return 0;
  return 1;
}

int sc_blame_late(const ml_ctx *c, struct fy_node *root)
{
  const char *msg = c->err->msg;
  const char *sep = strstr(msg, ": ");
  if (!sep || !sc_is_key_path(msg, (size_t)(sep - msg)) || (size_t)(sep - msg) >= 256)
    return c->err->code;
  char key[256];
  memcpy(key, msg, (size_t)(sep - msg));
  key[sep - msg] = '\0';
  int whole = 0;
  /* Only a key whose first segment is in the file: "driver" or
   * "load.points[3]" (a grid: at load.points), never the root. */
  if (sc_walk(root, key, &whole) == root)
    return c->err->code;
  return sc_blame_check(c, root);
}
