/* SPDX-License-Identifier: BSD-3-Clause */
/* Physical consistency of a vehicle scenario (fb_scenario_check): every
 * value against its range in the format's table (scenario_schema.c),
 * then the rules between values that a table cannot state. Each error
 * names its value's logical key (fb_err.key) and is located through the
 * scenario's origins (fb_scenario_locate), in the file's units (km/h,
 * degrees). */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "flexbond/sim.h"

#include "core/util.h"
#include "io/scenario_internal.h"

/* The error "KEY: message" about the value with logical key key, located. */
static int sc_fail(const fb_scenario *s, fb_err *err, const char *key, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static int sc_fail(const fb_scenario *s, fb_err *err, const char *key, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  fb_err_vset(err, FB_EINVAL, fmt, ap);
  va_end(ap);
  fb_err_set_key(err, "%s", key);
  return fb_scenario_locate(s, err);
}

/* ---- Every value in its range. */

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

static int sc_check_ranges(const fb_scenario *s, fb_err *err)
{
  sc_range_check c = {err, FB_OK};
  sch_each(&sc_schema, s, sc_check_one, &c);
  return c.rc ? fb_scenario_locate(s, err) : FB_OK;
}

/* ---- Rules between values. */

static int sc_check_hull(const fb_scenario *s, fb_err *err)
{
  /* The torsion angle divides by the edges' spans. */
  if (!(s->edge_front_x > s->edge_rear_x))
    return sc_fail(s, err, "hull.edges.front_x",
                   "must be > hull.edges.rear_x = %.10g m (got %.10g)", s->edge_rear_x,
                   s->edge_front_x);
  if (!(s->edge_left_y > s->edge_right_y))
    return sc_fail(s, err, "hull.edges.left_y",
                   "must be > hull.edges.right_y = %.10g m (got %.10g)", s->edge_right_y,
                   s->edge_left_y);
  return FB_OK;
}

static int sc_check_load(const fb_scenario *s, fb_err *err)
{
  if (s->nload < 1 || !s->load_x || !s->load_y)
    return sc_fail(s, err, "load.points", "at least one load point is needed (got %zu)",
                   s->nload);
  for (size_t i = 0; i < s->nload; ++i)
    if (!isfinite(s->load_x[i]) || !isfinite(s->load_y[i])) {
      char key[48];
      snprintf(key, sizeof key, "load.points[%zu]", i);
      return sc_fail(s, err, key, "must be finite (got x = %g, y = %g)", s->load_x[i],
                     s->load_y[i]);
    }
  /* The lumped model spreads the payload mass W / g - m_hull - the hull's
   * declared masses over the points (data sheet, "Load and gravity"): it
   * must be positive. A finite-element hull's own mass, when the file
   * gives none, is counted once its mesh is built
   * (fb_vehicle_hull_complete). */
  const double total_mass = s->total_weight / s->gravity;
  const double masses = fb_scenario_point_masses_total(s);
  if (s->payload != FB_PAYLOAD_LUMPED || fb_scenario_payload_mass(s) > 0)
    return FB_OK;
  char terms[128];
  if (!s->npoint_masses)
    snprintf(terms, sizeof terms, "hull.mass (%.10g kg)", s->hull_mass);
  else if (s->hull_mass > 0)
    snprintf(terms, sizeof terms, "hull.mass + hull.masses (%.10g + %.10g kg)", s->hull_mass,
             masses);
  else
    snprintf(terms, sizeof terms, "hull.masses (%.10g kg)", masses);
  return sc_fail(s, err, "load.payload",
                 "a lumped payload needs load.total_weight / gravity (%.10g kg) > %s",
                 total_mass, terms);
}

/* A table has 2 .. FB_DAMPER_MAX_POINTS knots (0: the linear damper). */
static int sc_check_dampers(const fb_scenario *s, fb_err *err)
{
  for (size_t k = 0; k < s->ncorners; ++k) {
    const fb_corner_params *c = &s->corner[k];
    if (c->damper_npoints == 1 || c->damper_npoints > FB_DAMPER_MAX_POINTS) {
      char key[160];
      snprintf(key, sizeof key, "corners.%s.damper_table", c->name);
      return sc_fail(s, err, key, "2 to %d points (got %zu)", (int)FB_DAMPER_MAX_POINTS,
                     c->damper_npoints);
    }
  }
  return FB_OK;
}

/* Points closer than this are one point (m): the 1 mm within which a
 * deck's node must sit at the scenario's point (docs/scenario-format.md). */
#define SC_SAME_POINT 1e-3

/* Attachment and load points lie on the hull's floor, the rectangle of
 * hull.edges (System 2 puts a node at each; on System 1 a point off the
 * hull is a lever arm no vehicle has, almost surely a typing error).
 * key: the point's logical key. */
static int sc_check_on_floor(const fb_scenario *s, const char *key, double x, double y,
                             fb_err *err)
{
  char at[192];
  if (x < s->edge_rear_x || x > s->edge_front_x) {
    snprintf(at, sizeof at, "%s.x", key);
    return sc_fail(s, err, at,
                   "must lie on the hull's floor, between hull.edges.rear_x = %.10g and "
                   "front_x = %.10g m (got %.10g)",
                   s->edge_rear_x, s->edge_front_x, x);
  }
  if (y < s->edge_right_y || y > s->edge_left_y) {
    snprintf(at, sizeof at, "%s.y", key);
    return sc_fail(s, err, at,
                   "must lie on the hull's floor, between hull.edges.right_y = %.10g and "
                   "left_y = %.10g m (got %.10g)",
                   s->edge_right_y, s->edge_left_y, y);
  }
  return FB_OK;
}

static int sc_check_load_points(const fb_scenario *s, fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < s->nload; ++i) {
    char key[48];
    snprintf(key, sizeof key, "load.points[%zu]", i);
    rc = sc_check_on_floor(s, key, s->load_x[i], s->load_y[i], err);
    /* Each point carries its share of the weight at its own node. */
    for (size_t j = 0; !rc && j < i; ++j)
      if (hypot(s->load_x[i] - s->load_x[j], s->load_y[i] - s->load_y[j]) < SC_SAME_POINT)
        rc = sc_fail(s, err, key,
                     "at (%.10g, %.10g) m, where load.points[%zu] already is (two load "
                     "points at one point)",
                     s->load_x[i], s->load_y[i], j);
  }
  return rc;
}

/* 1 if a and b are one name (a missing name is no name). */
static int sc_same(const char *a, const char *b)
{
  return a && b && !strcmp(a, b);
}

/* Names unique among the corners and among the mounts: they name the
 * subsystem instances, mesh node sets and outputs. The later one is
 * blamed (its origins are the last of that key). */
static int sc_check_names(const fb_scenario *s, fb_err *err)
{
  for (size_t k = 0; k < s->ncorners; ++k)
    if (!s->corner[k].name)
      return fb_err_set(err, FB_EINVAL, "corners[%zu]: has no name", k),
             fb_err_set_key(err, "corners[%zu]", k);
  for (size_t k = 0; k < s->nmounts; ++k)
    if (!s->mount[k].name)
      return fb_err_set(err, FB_EINVAL, "mounts[%zu]: has no name", k),
             fb_err_set_key(err, "mounts[%zu]", k);
  for (size_t k = 0; k < s->ncorners; ++k)
    for (size_t j = 0; j < k; ++j)
      if (sc_same(s->corner[k].name, s->corner[j].name)) {
        char key[160];
        snprintf(key, sizeof key, "corners.%s", s->corner[k].name);
        return sc_fail(s, err, key, "a second corner named %s (corner names are unique)",
                       s->corner[k].name);
      }
  for (size_t k = 0; k < s->nmounts; ++k)
    for (size_t j = 0; j < k; ++j)
      if (sc_same(s->mount[k].name, s->mount[j].name)) {
        char key[160];
        snprintf(key, sizeof key, "mounts.%s", s->mount[k].name);
        return sc_fail(s, err, key, "a second mount named %s (mount names are unique)",
                       s->mount[k].name);
      }
  return FB_OK;
}

/* A hull mass's name: unique among the hull masses (in capitals too:
 * its mesh node set is MASS_<NAME>), the mounts and the corners. */
static int sc_check_point_mass_name(const fb_scenario *s, size_t k, fb_err *err)
{
  const char *name = s->point_mass[k].name;
  char key[160];
  snprintf(key, sizeof key, "hull.masses.%s", name);
  for (size_t j = 0; j < k; ++j) {
    const char *other = s->point_mass[j].name;
    if (sc_same(name, other))
      return sc_fail(s, err, key, "a second hull mass named %s (hull mass names are unique)",
                     name);
    if (other && !strcasecmp(name, other)) {
      char set[128];
      snprintf(set, sizeof set, "%s", name);
      for (char *c = set; *c; ++c)
        *c = (char)toupper((unsigned char)*c);
      return sc_fail(s, err, key,
                     "hull mass %s's name in other capitals: both would be the mesh's node set "
                     "MASS_%s",
                     other, set);
    }
  }
  const char *kind = fb_scenario_mount_find(s, name) >= 0    ? "mount"
                     : fb_scenario_corner_find(s, name) >= 0 ? "corner"
                                                             : NULL;
  if (kind)
    return sc_fail(s, err, key,
                   "a %s is named %s already (the names of hull masses, mounts and corners "
                   "are unique)",
                   kind, name);
  return FB_OK;
}

static int sc_check_point_masses(const fb_scenario *s, fb_err *err)
{
  int rc = FB_OK;
  for (size_t k = 0; !rc && k < s->npoint_masses; ++k) {
    const fb_hull_point_mass *m = &s->point_mass[k];
    if (!m->name)
      return fb_err_set(err, FB_EINVAL, "hull.masses[%zu]: has no name", k),
             fb_err_set_key(err, "hull.masses[%zu]", k);
    rc = sc_check_point_mass_name(s, k, err);
    char key[160];
    snprintf(key, sizeof key, "hull.masses.%s", m->name);
    if (!rc)
      rc = sc_check_on_floor(s, key, m->x, m->y, err);
  }
  return rc;
}

/* Every attachment point on the floor, no two corners (two wheels cannot
 * stand in one place) at one point. */
static int sc_check_points(const fb_scenario *s, fb_err *err)
{
  int rc = FB_OK;
  for (size_t k = 0; !rc && k < s->nmounts; ++k) {
    char key[160];
    snprintf(key, sizeof key, "mounts.%s", s->mount[k].name);
    rc = sc_check_on_floor(s, key, s->mount[k].x, s->mount[k].y, err);
  }
  if (!rc)
    rc = sc_check_load_points(s, err);
  for (size_t k = 0; !rc && k < s->ncorners; ++k) {
    const fb_corner_params *c = &s->corner[k];
    char key[160];
    snprintf(key, sizeof key, "corners.%s", c->name);
    rc = sc_check_on_floor(s, key, c->x, c->y, err);
    for (size_t j = 0; !rc && j < k; ++j)
      if (hypot(c->x - s->corner[j].x, c->y - s->corner[j].y) < SC_SAME_POINT)
        rc = sc_fail(s, err, key,
                     "at (%.10g, %.10g) m, where corner %s already is (two corners at one "
                     "point)",
                     c->x, c->y, s->corner[j].name);
  }
  return rc;
}

/* A random road or a profile: its own constructor checks its parameters
 * (the file, read again: it may have changed since the scenario was). */
static int sc_check_other_road(const fb_scenario *s, fb_err *err)
{
  const char *key = s->road_kind == FB_ROAD_ISO8608 ? "road.iso8608" : "road.profile.file";
  fb_road *road = NULL;
  int rc = FB_OK;
  if (s->road_kind == FB_ROAD_ISO8608)
    rc = fb_road_new_iso8608(&s->road_iso, &road, err);
  else if (!s->road_profile || !s->road_profile_data)
    return sc_fail(s, err, key, "missing (the loader reads the profile's file)");
  /* A profile was checked when its file was read, once. */
  fb_road_free(&road);
  /* The road's own messages name its parameter, not the key. */
  if (rc && rc != FB_ENOMEM) {
    fb_err_set_key(err, "%s", key);
    return fb_scenario_locate(s, err);
  }
  return rc;
}

/* The solver's own limits (fb_sim_opts_check: sample count, the result's
 * memory, the steps that max_step forces), whose messages name their
 * key. */
static int sc_check_simulation(const fb_scenario *s, fb_err *err)
{
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_start = 0;
  o.t_end = s->t_end;
  o.rtol = s->rtol;
  o.atol = s->atol;
  o.max_step = s->max_step;
  o.max_steps = s->max_steps;
  o.sample_rate = s->sample_rate;
  /* What a run records: the outputs and, for the contact intervals, a
   * tire force per corner. */
  o.noutputs = s->noutputs + s->ncorners;
  int rc = fb_sim_opts_check(&o, err);
  /* The sim names the setting (err->key, "sample_rate"); in the scenario
   * file it is simulation.KEY, located and named by sc_locate. */
  if (rc && err && err->key[0]) {
    char key[FB_ERR_KEY_MAX];
    snprintf(key, sizeof key, "%s", err->key);
    fb_err_set_key(err, "simulation.%s", key);
  }
  return rc ? sc_locate(s, err, 0) : FB_OK;
}

/* Every wheel meets the bump at t >= 0 and has left it before t_end (the
 * run must show the whole crossing). */
static int sc_check_bump_timing(const fb_scenario *s, fb_err *err)
{
  int first = 0, last = 0;
  for (int k = 1; k < (int)s->ncorners; ++k) {
    if (fb_scenario_bump_entry(s, k) < fb_scenario_bump_entry(s, first))
      first = k;
    if (fb_scenario_bump_exit(s, k) > fb_scenario_bump_exit(s, last))
      last = k;
  }
  const double t_in = fb_scenario_bump_entry(s, first), t_out = fb_scenario_bump_exit(s, last);
  if (!(t_in >= 0))
    return sc_fail(s, err, "road.bump.first_contact",
                   "the %s wheel would meet the bump at %.6g s, before the run starts at 0 s",
                   s->corner[first].name, t_in);
  if (!(t_out < s->t_end))
    return sc_fail(s, err, "road.bump",
                   "bump longer than the run: the last wheel (%s) leaves it at %.6g s, not "
                   "before simulation.t_end = %.10g s",
                   s->corner[last].name, t_out, s->t_end);
  return FB_OK;
}

/* System 2's hull sections, when present. The generator checks the
 * geometry against the points itself, when the mesh is built. */
static int sc_check_fe_hull(const fb_scenario *s, fb_err *err)
{
  if (!s->has_fe_hull)
    return FB_OK;
  const fb_hull_mesh_params *g = &s->hull_mesh;
  const int count = s->hull_modes_kind == FB_HULL_MODES_COUNT;
  /* A reduced hull needs its six rigid-body modes at least. */
  if (count && s->hull_modes < 6)
    return sc_fail(s, err, "hull.fe.modes",
                   "auto, all or at least the 6 rigid-body modes (got %d)", s->hull_modes);
  if (s->hull_modes_kind != FB_HULL_MODES_AUTO && s->hull_coordinates == FB_HULL_NODAL)
    return sc_fail(s, err, "hull.fe.modes",
                   "a choice of modes (%s) is for modal coordinates, not nodal ones",
                   count ? "a count" : "all");
  if (s->hull_cutoff_hz != 0 &&
      (s->hull_modes_kind != FB_HULL_MODES_AUTO || s->hull_coordinates == FB_HULL_NODAL))
    return sc_fail(s, err, "hull.fe.cutoff_hz",
                   "a cut-off sets which modes hull.fe.modes: auto keeps, in modal "
                   "coordinates; not with %s",
                   s->hull_coordinates == FB_HULL_NODAL ? "nodal coordinates"
                   : count                              ? "a count of modes"
                                                        : "every mode");
  if (s->hull_deck)
    return FB_OK;
  if (!(g->x_front > g->x_rear))
    return sc_fail(s, err, "hull.mesh.generator.x_front",
                   "must be > x_rear = %.10g m (got %.10g)", g->x_rear, g->x_front);
  if (!(g->nose_height < g->height))
    return sc_fail(s, err, "hull.mesh.generator.nose_height",
                   "must be < height = %.10g m (got %.10g)", g->height, g->nose_height);
  for (size_t k = 0; k < g->nbulkheads; ++k)
    if (!(g->bulkhead_x[k] > g->x_rear && g->bulkhead_x[k] < g->x_front)) {
      char key[64];
      snprintf(key, sizeof key, "hull.mesh.generator.bulkheads[%zu]", k);
      return sc_fail(s, err, key, "must lie between x_rear and x_front (got %.10g m)",
                     g->bulkhead_x[k]);
    }
  return FB_OK;
}

/* ---- Outputs. */

static const char *sc_corner_name_at(const void *ctx, size_t i)
{
  return ((const fb_scenario *)ctx)->corner[i].name;
}

static const char *sc_mount_name_at(const void *ctx, size_t i)
{
  return ((const fb_scenario *)ctx)->mount[i].name;
}

/* For an unknown name: " (did you mean 'LF'?)" when one is close, then
 * "; the corners are LF, RF, ..." (what: "corners"), into buf. */
static void sc_names_hint(const fb_scenario *s, const char *word, size_t n, ml_name_fn name_at,
                          const char *what, char *buf, size_t size)
{
  const char *near = word && *word ? ml_suggest(word, n, name_at, s) : NULL;
  size_t len = 0;
  buf[0] = '\0';
  if (near)
    len = fb_text_append(buf, size, len, " (did you mean '%s'?)", near);
  len = fb_text_append(buf, size, len, n ? "; the %s are " : "; there are no %s", what);
  for (size_t k = 0; k < n && len + 1 < size; ++k) {
    len = fb_text_append(buf, size, len, "%s", k ? ", " : "");
    len = fb_text_append(buf, size, len, "%s", name_at(s, k));
  }
}

/* `of` names a corner or a mount, as the signal's kind asks. */
static int sc_check_output_subject(const fb_scenario *s, size_t i, fb_err *err)
{
  const fb_output_spec *o = &s->output[i];
  const fb_output_kind *kind = o->signal ? fb_vehicle_output_kind_find(o->signal) : NULL;
  char key[64];
  snprintf(key, sizeof key, "outputs[%zu].of", i);
  if (!kind)
    return sc_fail(s, err, key, "unknown signal '%s'", o->signal ? o->signal : "(none)");
  char hint[512];
  if (kind->subject == FB_OUTPUT_OF_CORNER &&
      (!o->of || fb_scenario_corner_find(s, o->of) < 0)) {
    sc_names_hint(s, o->of, s->ncorners, sc_corner_name_at, "corners", hint, sizeof hint);
    return sc_fail(s, err, key, "no corner named '%s' (a %s signal measures a corner)%s",
                   o->of ? o->of : "", o->signal, hint);
  }
  if (kind->subject == FB_OUTPUT_OF_MOUNT && (!o->of || fb_scenario_mount_find(s, o->of) < 0)) {
    sc_names_hint(s, o->of, s->nmounts, sc_mount_name_at, "mounts", hint, sizeof hint);
    return sc_fail(s, err, key, "no mount named '%s' (a %s signal measures a mounted body)%s",
                   o->of ? o->of : "", o->signal, hint);
  }
  return FB_OK;
}

/* A CSV column of its own: not the time's, not a contact force's. */
static int sc_check_output_name(const fb_scenario *s, size_t i, fb_err *err)
{
  const char *name = s->output[i].name;
  char key[64];
  snprintf(key, sizeof key, "outputs[%zu].name", i);
  if (!name || !strcmp(name, "t") || !strncmp(name, "contact_force_", 14))
    return sc_fail(s, err, key,
                   "'%s' is a column of its own (t, contact_force_<CORNER>): give another name",
                   name ? name : "");
  for (size_t j = 0; j < i; ++j)
    if (sc_same(s->output[j].name, name))
      return sc_fail(s, err, key, "'%s' is outputs[%zu]'s name already (names are unique)",
                     name, j);
  return FB_OK;
}

static int sc_check_output_figure(const fb_scenario *s, size_t i, fb_err *err)
{
  const fb_output_spec *o = &s->output[i];
  char key[64];
  snprintf(key, sizeof key, "outputs[%zu].figure", i);
  for (size_t j = 0; o->figure && j < i; ++j)
    if (s->output[j].figure == o->figure)
      return sc_fail(s, err, key, "figure %d is outputs[%zu]'s already", o->figure, j);
  snprintf(key, sizeof key, "outputs[%zu].window", i);
  /* Not bounded by t_end: a shorter run (--set simulation.t_end) shows
   * the part of the window it covers, or the whole run (run.c). */
  const double *w = o->window;
  if ((w[0] != 0 || w[1] != 0) && !(w[0] >= 0 && w[0] < w[1]))
    return sc_fail(s, err, key, "must be [t0, t1] with 0 <= t0 < t1 (got [%.10g, %.10g])", w[0],
                   w[1]);
  return FB_OK;
}

static int sc_check_outputs(const fb_scenario *s, fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < s->noutputs; ++i) {
    rc = sc_check_output_subject(s, i, err);
    if (!rc)
      rc = sc_check_output_name(s, i, err);
    if (!rc)
      rc = sc_check_output_figure(s, i, err);
  }
  return rc;
}

int fb_scenario_check(const fb_scenario *s, fb_err *err)
{
  if (!s)
    return fb_err_set(err, FB_EINVAL, "fb_scenario_check: the scenario is NULL");
  if (s->ncorners < 3 || !s->corner)
    return fb_err_set(err, FB_EINVAL, "suspensions: at least 3 corners are needed (got %zu)",
                      s->ncorners),
           fb_err_set_key(err, "suspensions");
  int rc = sc_check_names(s, err);
  if (!rc)
    rc = sc_check_ranges(s, err);
  if (!rc)
    rc = sc_check_hull(s, err);
  if (!rc)
    rc = sc_check_load(s, err);
  if (!rc)
    rc = sc_check_dampers(s, err);
  if (!rc)
    rc = sc_check_points(s, err);
  if (!rc)
    rc = sc_check_point_masses(s, err);
  if (!rc && s->road_kind != FB_ROAD_BUMP)
    rc = sc_check_other_road(s, err);
  if (!rc)
    rc = sc_check_simulation(s, err);
  if (!rc && s->road_kind == FB_ROAD_BUMP)
    rc = sc_check_bump_timing(s, err);
  if (!rc)
    rc = sc_check_fe_hull(s, err);
  if (!rc)
    rc = sc_check_outputs(s, err);
  return rc;
}
