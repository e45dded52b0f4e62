/* Physical consistency of a vehicle scenario (fb_scenario_check). Each
 * message starts with the key path of docs/scenario-format.md the value
 * comes from and quotes it in the file's unit (km/h, degrees), so the
 * loader can point at the value in the file. */
#include <math.h>
#include <stdio.h>

#include "flexbond/sim.h"

#include "io/scenario_internal.h"

typedef enum sc_rule { SC_FINITE, SC_POSITIVE, SC_NONNEGATIVE } sc_rule;

/* One value under a rule: finite always, and > 0 or >= 0 if asked. */
typedef struct sc_value {
  const char *key; /* below the prefix */
  double value;    /* in the file's unit */
  sc_rule rule;
  const char *unit; /* for the message, "" for none */
} sc_value;

static int sc_check_values(const char *prefix, const sc_value *v, size_t n, fb_err *err)
{
  for (size_t i = 0; i < n; ++i) {
    const char *space = v[i].unit[0] ? " " : "";
    if (!isfinite(v[i].value))
      return fb_err_set(err, FB_EINVAL, "%s%s: must be finite (got %g)", prefix, v[i].key,
                        v[i].value);
    if (v[i].rule == SC_POSITIVE && !(v[i].value > 0))
      return fb_err_set(err, FB_EINVAL, "%s%s: must be > 0%s%s (got %.10g)", prefix, v[i].key,
                        space, v[i].unit, v[i].value);
    if (v[i].rule == SC_NONNEGATIVE && !(v[i].value >= 0))
      return fb_err_set(err, FB_EINVAL, "%s%s: must be >= 0%s%s (got %.10g)", prefix, v[i].key,
                        space, v[i].unit, v[i].value);
  }
  return FB_OK;
}

static int sc_check_hull(const fb_scenario *s, fb_err *err)
{
  const sc_value v[] = {
      {"mass", s->hull_mass, SC_POSITIVE, "kg"},
      {"Ixx", s->hull_ixx, SC_POSITIVE, "kg m^2"},
      {"Iyy", s->hull_iyy, SC_POSITIVE, "kg m^2"},
      {"material.young", s->young, SC_POSITIVE, "Pa"},
      {"material.poisson", s->poisson, SC_FINITE, ""},
      {"material.density", s->density, SC_POSITIVE, "kg/m^3"},
      {"material.thickness", s->thickness, SC_POSITIVE, "m"},
      {"edges.front_x", s->edge_front_x, SC_FINITE, "m"},
      {"edges.rear_x", s->edge_rear_x, SC_FINITE, "m"},
      {"edges.left_y", s->edge_left_y, SC_FINITE, "m"},
      {"edges.right_y", s->edge_right_y, SC_FINITE, "m"},
  };
  int rc = sc_check_values("hull.", v, sizeof v / sizeof v[0], err);
  if (rc)
    return rc;
  /* Isotropic elasticity needs -1 < nu < 0.5; a negative ratio is no
   * steel, so the scenario keeps to [0, 0.5). */
  if (!(s->poisson >= 0 && s->poisson < 0.5))
    return fb_err_set(err, FB_EINVAL, "hull.material.poisson: must be in [0, 0.5) (got %.10g)",
                      s->poisson);
  /* The torsion angle divides by the edges' spans. */
  if (!(s->edge_front_x > s->edge_rear_x))
    return fb_err_set(err, FB_EINVAL,
                      "hull.edges.front_x: must be > hull.edges.rear_x = %.10g m (got %.10g)",
                      s->edge_rear_x, s->edge_front_x);
  if (!(s->edge_left_y > s->edge_right_y))
    return fb_err_set(err, FB_EINVAL,
                      "hull.edges.left_y: must be > hull.edges.right_y = %.10g m (got %.10g)",
                      s->edge_right_y, s->edge_left_y);
  return FB_OK;
}

static int sc_check_load(const fb_scenario *s, fb_err *err)
{
  const sc_value v[] = {{"total_weight", s->total_weight, SC_POSITIVE, "N"}};
  int rc = sc_check_values("load.", v, 1, err);
  if (rc)
    return rc;
  if (s->payload != FB_PAYLOAD_WEIGHT_ONLY && s->payload != FB_PAYLOAD_LUMPED)
    return fb_err_set(err, FB_EINVAL, "load.payload: unknown payload model %d",
                      (int)s->payload);
  if (s->nload < 1 || !s->load_x || !s->load_y)
    return fb_err_set(err, FB_EINVAL,
                      "load.points: at least one load point is needed (got %zu)", s->nload);
  for (size_t i = 0; i < s->nload; ++i)
    if (!isfinite(s->load_x[i]) || !isfinite(s->load_y[i]))
      return fb_err_set(err, FB_EINVAL, "load.points[%zu]: must be finite (got x = %g, y = %g)",
                        i, s->load_x[i], s->load_y[i]);
  /* The lumped model spreads the payload mass W / g - m_hull over the
   * points (data sheet, "Load and gravity"): it must be positive. */
  const double total_mass = s->total_weight / s->gravity;
  if (s->payload == FB_PAYLOAD_LUMPED && !(total_mass > s->hull_mass))
    return fb_err_set(err, FB_EINVAL,
                      "load.payload: a lumped payload needs load.total_weight / gravity "
                      "(%.10g kg) > hull.mass (%.10g kg)",
                      total_mass, s->hull_mass);
  return FB_OK;
}

/* driver or engine; prefix is "driver." or "engine.". */
static int sc_check_mount(const char *prefix, const fb_mount *m, fb_err *err)
{
  const sc_value v[] = {
      {"mass", m->mass, SC_POSITIVE, "kg"},
      {"stiffness", m->stiffness, SC_POSITIVE, "N/m"},
      {"damping", m->damping, SC_NONNEGATIVE, "N s/m"},
      {"x", m->x, SC_FINITE, "m"},
      {"y", m->y, SC_FINITE, "m"},
  };
  return sc_check_values(prefix, v, sizeof v / sizeof v[0], err);
}

static int sc_check_corner(const fb_corner_params *c, int corner, fb_err *err)
{
  char prefix[32];
  snprintf(prefix, sizeof prefix, "suspensions.%s.", fb_corner_name(corner));
  const sc_value v[] = {
      {"spring_k", c->spring_k, SC_POSITIVE, "N/m"},
      {"damper_c", c->damper_c, SC_NONNEGATIVE, "N s/m"},
      {"motion_ratio", c->motion_ratio, SC_POSITIVE, ""},
      {"x", c->x, SC_FINITE, "m"},
      {"y", c->y, SC_FINITE, "m"},
      {"wheel_mass", c->wheel_mass, SC_POSITIVE, "kg"},
      {"tire_k", c->tire_k, SC_POSITIVE, "N/m"},
      {"tire_c", c->tire_c, SC_NONNEGATIVE, "N s/m"},
  };
  int rc = sc_check_values(prefix, v, sizeof v / sizeof v[0], err);
  /* A table has 2 .. FB_DAMPER_MAX_POINTS knots (0: the linear damper). */
  if (!rc && (c->damper_npoints == 1 || c->damper_npoints > FB_DAMPER_MAX_POINTS))
    rc = fb_err_set(err, FB_EINVAL, "%sdamper_table: 2 to %d points (got %zu)", prefix,
                    (int)FB_DAMPER_MAX_POINTS, c->damper_npoints);
  return rc;
}

/* Points closer than this are one point (m): the 1 mm within which a
 * deck's node must sit at the scenario's point (docs/scenario-format.md). */
#define SC_SAME_POINT 1e-3

/* Attachment and load points lie on the hull's floor, the rectangle of
 * hull.edges (System 2 puts a node at each; on System 1 a point off the
 * hull is a lever arm no vehicle has, almost surely a typing error).
 * key: the point's key path, for the message. */
static int sc_check_on_floor(const fb_scenario *s, const char *key, double x, double y,
                             fb_err *err)
{
  if (x < s->edge_rear_x || x > s->edge_front_x)
    return fb_err_set(
        err, FB_EINVAL,
        "%s.x: must lie on the hull's floor, between hull.edges.rear_x = %.10g and "
        "front_x = %.10g m (got %.10g)",
        key, s->edge_rear_x, s->edge_front_x, x);
  if (y < s->edge_right_y || y > s->edge_left_y)
    return fb_err_set(
        err, FB_EINVAL,
        "%s.y: must lie on the hull's floor, between hull.edges.right_y = %.10g and "
        "left_y = %.10g m (got %.10g)",
        key, s->edge_right_y, s->edge_left_y, y);
  return FB_OK;
}

/* Every point on the floor, and no two suspensions (two wheels cannot
 * stand in one place) or load points at one point. */
static int sc_check_points(const fb_scenario *s, fb_err *err)
{
  int rc = sc_check_on_floor(s, "driver", s->driver.x, s->driver.y, err);
  if (!rc)
    rc = sc_check_on_floor(s, "engine", s->engine.x, s->engine.y, err);
  for (size_t i = 0; !rc && i < s->nload; ++i) {
    char key[48];
    snprintf(key, sizeof key, "load.points[%zu]", i);
    rc = sc_check_on_floor(s, key, s->load_x[i], s->load_y[i], err);
    /* Each point carries its share of the weight at its own node. */
    for (size_t j = 0; !rc && j < i; ++j)
      if (hypot(s->load_x[i] - s->load_x[j], s->load_y[i] - s->load_y[j]) < SC_SAME_POINT)
        rc = fb_err_set(err, FB_EINVAL,
                        "%s: at (%.10g, %.10g) m, where load.points[%zu] already is (two load "
                        "points at one point)",
                        key, s->load_x[i], s->load_y[i], j);
  }
  for (int k = 0; !rc && k < FB_NCORNERS; ++k) {
    char key[32];
    snprintf(key, sizeof key, "suspensions.%s", fb_corner_name(k));
    const fb_corner_params *c = &s->corner[k];
    rc = sc_check_on_floor(s, key, c->x, c->y, err);
    for (int j = 0; !rc && j < k; ++j)
      if (hypot(c->x - s->corner[j].x, c->y - s->corner[j].y) < SC_SAME_POINT)
        rc = fb_err_set(err, FB_EINVAL,
                        "%s: at (%.10g, %.10g) m, where suspensions.%s already is (two "
                        "suspensions at one point)",
                        key, c->x, c->y, fb_corner_name(j));
  }
  return rc;
}

/* A random road or a profile: its own constructor checks its parameters
 * (the file, read again: it may have changed since the scenario was). */
static int sc_check_other_road(const fb_scenario *s, fb_err *err)
{
  const sc_value v[] = {{"speed_kmh", s->speed * 3.6, SC_POSITIVE, "km/h"}};
  int rc = sc_check_values("road.", v, 1, err);
  const char *key = s->road_kind == FB_ROAD_ISO8608 ? "road.iso8608" : "road.profile";
  if (!rc && !isfinite(s->road_front_start))
    rc = fb_err_set(err, FB_EINVAL, "%s.front_start: must be finite", key);
  if (rc)
    return rc;
  /* Checked here too, to point at the key: the road's own message names
   * its parameter. */
  if (s->road_kind == FB_ROAD_ISO8608 && s->road_iso.nharmonics > FB_ROAD_ISO8608_MAX_HARMONICS)
    return fb_err_set(err, FB_EINVAL,
                      "road.iso8608.harmonics: at most %zu (got %zu): every road height sums "
                      "them all, so the run's time grows with them (docs/roads.md, "
                      "\"Limits\")",
                      FB_ROAD_ISO8608_MAX_HARMONICS, s->road_iso.nharmonics);
  fb_road *road = NULL;
  if (s->road_kind == FB_ROAD_ISO8608)
    rc = fb_road_new_iso8608(&s->road_iso, &road, err);
  else if (!s->road_profile)
    rc = fb_err_set(err, FB_EINVAL, "road.profile.file: missing");
  else
    rc = fb_road_new_csv(s->road_profile, &road, err);
  fb_road_free(&road);
  /* The road's own messages name its parameter, not the key. */
  if (rc && rc != FB_ENOMEM)
    fb_err_prefix(err, "%s: ", key);
  return rc;
}

static int sc_check_road(const fb_scenario *s, fb_err *err)
{
  if (s->road_kind != FB_ROAD_BUMP)
    return sc_check_other_road(s, err);
  const sc_value v[] = {
      {"speed_kmh", s->speed * 3.6, SC_POSITIVE, "km/h"},
      {"bump.height", s->bump_height, SC_NONNEGATIVE, "m"},
      {"bump.length", s->bump_length, SC_POSITIVE, "m"},
      {"bump.angle_deg", s->bump_angle * 180 / SC_PI, SC_FINITE, "deg"},
      {"bump.first_contact", s->bump_time, SC_NONNEGATIVE, "s"},
  };
  int rc = sc_check_values("road.", v, sizeof v / sizeof v[0], err);
  /* At 90 deg the edge runs along the path: no wheel would meet it. */
  if (!rc && !(s->bump_angle >= 0 && s->bump_angle < 0.5 * SC_PI))
    rc = fb_err_set(err, FB_EINVAL, "road.bump.angle_deg: must be in [0, 90) deg (got %.10g)",
                    s->bump_angle * 180 / SC_PI);
  return rc;
}

/* The scenario's tolerances and grid, then the solver's own limits
 * (fb_sim_opts_check: sample count, the result's memory, the steps that
 * max_step forces). */
static int sc_check_simulation(const fb_scenario *s, fb_err *err)
{
  const sc_value v[] = {
      {"t_end", s->t_end, SC_POSITIVE, "s"},
      {"rtol", s->rtol, SC_POSITIVE, ""},
      {"atol", s->atol, SC_POSITIVE, ""},
      {"max_step", s->max_step, SC_NONNEGATIVE, "s"},
      {"sample_rate", s->sample_rate, SC_POSITIVE, "Hz"},
  };
  int rc = sc_check_values("simulation.", v, sizeof v / sizeof v[0], err);
  if (rc)
    return rc;
  if (!(s->rtol < 1))
    return fb_err_set(err, FB_EINVAL, "simulation.rtol: must be in (0, 1) (got %.10g)",
                      s->rtol);
  if (s->initial != FB_INITIAL_ZERO && s->initial != FB_INITIAL_STATIC)
    return fb_err_set(err, FB_EINVAL, "simulation.initial: unknown initial state %d",
                      (int)s->initial);
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_start = 0;
  o.t_end = s->t_end;
  o.rtol = s->rtol;
  o.atol = s->atol;
  o.max_step = s->max_step;
  o.max_steps = s->max_steps;
  o.sample_rate = s->sample_rate;
  /* What fb_vehicle_build records: the seven outputs and, for the contact
   * intervals, a tire force per corner (the most a run has). */
  o.noutputs = FB_NOUTPUTS + FB_NCORNERS;
  rc = fb_sim_opts_check(&o, err);
  /* The sim names the setting (err->key, "sample_rate"); in the scenario
   * file it is simulation.KEY. */
  if (rc && err && err->key[0]) {
    char key[FB_ERR_KEY_MAX];
    snprintf(key, sizeof key, "%s", err->key);
    fb_err_prefix(err, "simulation.%s: ", key);
    fb_err_set_key(err, "simulation.%s", key);
  }
  return rc;
}

/* Every wheel meets the bump at t >= 0 and has left it before t_end (the
 * run must show the whole crossing). */
static int sc_check_bump_timing(const fb_scenario *s, fb_err *err)
{
  int first = FB_LF, last = FB_LF;
  for (int k = 1; k < FB_NCORNERS; ++k) {
    if (fb_scenario_bump_entry(s, k) < fb_scenario_bump_entry(s, first))
      first = k;
    if (fb_scenario_bump_exit(s, k) > fb_scenario_bump_exit(s, last))
      last = k;
  }
  const double t_in = fb_scenario_bump_entry(s, first), t_out = fb_scenario_bump_exit(s, last);
  if (!(t_in >= 0))
    return fb_err_set(err, FB_EINVAL,
                      "road.bump.first_contact: the %s wheel would meet the bump at %.6g s, "
                      "before the run starts at 0 s",
                      fb_corner_name(first), t_in);
  if (!(t_out < s->t_end))
    return fb_err_set(err, FB_EINVAL,
                      "road.bump: bump longer than the run: the last wheel (%s) leaves it at "
                      "%.6g s, not before simulation.t_end = %.10g s",
                      fb_corner_name(last), t_out, s->t_end);
  return FB_OK;
}

/* System 2's hull sections, when present. The generator checks the
 * geometry against the points itself, when the mesh is built. */
static int sc_check_fe_hull(const fb_scenario *s, fb_err *err)
{
  if (!s->has_fe_hull)
    return FB_OK;
  const fb_hull_mesh_params *g = &s->hull_mesh;
  const sc_value fe[] = {{"drill_factor", s->hull_drill_factor, SC_POSITIVE, ""},
                         {"damping_ratio", s->hull_damping_ratio, SC_NONNEGATIVE, ""}};
  int rc = sc_check_values("hull.fe.", fe, sizeof fe / sizeof fe[0], err);
  if (!rc && !(s->hull_damping_ratio < 1))
    rc = fb_err_set(err, FB_EINVAL, "hull.fe.damping_ratio: must be < 1 (got %.10g)",
                    s->hull_damping_ratio);
  /* A reduced hull needs its six rigid-body modes at least. */
  if (!rc && s->hull_modes != 0 && s->hull_modes < 6)
    rc = fb_err_set(err, FB_EINVAL,
                    "hull.fe.modes: 0 (full order) or at least the 6 rigid-body modes (got %d)",
                    s->hull_modes);
  if (rc || s->hull_deck)
    return rc;
  const sc_value gen[] = {{"width", g->width, SC_POSITIVE, "m"},
                          {"height", g->height, SC_POSITIVE, "m"},
                          {"x_rear", g->x_rear, SC_FINITE, "m"},
                          {"x_front", g->x_front, SC_FINITE, "m"},
                          {"nose_length", g->nose_length, SC_POSITIVE, "m"},
                          {"nose_height", g->nose_height, SC_POSITIVE, "m"}};
  rc = sc_check_values("hull.mesh.generator.", gen, sizeof gen / sizeof gen[0], err);
  if (!rc && !(g->x_front > g->x_rear))
    rc = fb_err_set(err, FB_EINVAL,
                    "hull.mesh.generator.x_front: must be > x_rear = %.10g m (got %.10g)",
                    g->x_rear, g->x_front);
  if (!rc && !(g->nose_height < g->height))
    rc = fb_err_set(err, FB_EINVAL,
                    "hull.mesh.generator.nose_height: must be < height = %.10g m (got %.10g)",
                    g->height, g->nose_height);
  for (size_t k = 0; !rc && k < g->nbulkheads; ++k)
    if (!(g->bulkhead_x[k] > g->x_rear && g->bulkhead_x[k] < g->x_front))
      rc = fb_err_set(err, FB_EINVAL,
                      "hull.mesh.generator.bulkheads[%zu]: must lie between x_rear and "
                      "x_front (got %.10g m)",
                      k, g->bulkhead_x[k]);
  return rc;
}

int fb_scenario_check(const fb_scenario *s, fb_err *err)
{
  if (!s)
    return fb_err_set(err, FB_EINVAL, "fb_scenario_check: the scenario is NULL");
  const sc_value gravity[] = {{"gravity", s->gravity, SC_POSITIVE, "m/s^2"}};
  int rc = sc_check_values("", gravity, 1, err);
  if (!rc)
    rc = sc_check_hull(s, err);
  if (!rc)
    rc = sc_check_load(s, err);
  if (!rc)
    rc = sc_check_mount("driver.", &s->driver, err);
  if (!rc)
    rc = sc_check_mount("engine.", &s->engine, err);
  for (int k = 0; !rc && k < FB_NCORNERS; ++k)
    rc = sc_check_corner(&s->corner[k], k, err);
  if (!rc)
    rc = sc_check_points(s, err);
  if (!rc)
    rc = sc_check_road(s, err);
  if (!rc)
    rc = sc_check_simulation(s, err);
  if (!rc && s->road_kind == FB_ROAD_BUMP)
    rc = sc_check_bump_timing(s, err);
  if (!rc)
    rc = sc_check_fe_hull(s, err);
  return rc;
}
