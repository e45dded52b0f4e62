/* SPDX-License-Identifier: BSD-3-Clause */
/* Physical consistency of a vehicle description (fb_scenario_check):
 * every value a vehicle can be built from (a positive mass, a Poisson's
 * ratio below 1/2), then the rules between values. The description may
 * come from a file, a program or a binding: each error names the part of
 * the description it is about (fb_err.part) in SI units, and whoever made
 * the description says where that part came from (fb_scenario_locate for
 * a file). A file's own ranges, in its units, are its reader's. */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "flexbond/hull_source.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "core/textfile.h"
#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* The error about member field of part kind, index i: FB_EINVAL with the
 * message (returned also when err is NULL). */
static int fail(fb_err *err, int kind, size_t i, const char *field, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
static int fail(fb_err *err, int kind, size_t i, const char *field, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  fb_err_vset(err, FB_EINVAL, fmt, ap);
  va_end(ap);
  fb_err_set_part(err, kind, i, FB_ERR_NO_ELEMENT, field);
  return FB_EINVAL;
}

/* ---- Every value a vehicle can be built from. */

enum {
  LO = FB_RANGE_LO,
  LO_OPEN = FB_RANGE_LO_OPEN,
  HI = FB_RANGE_HI,
  HI_OPEN = FB_RANGE_HI_OPEN
};
typedef enum { REAL, WHOLE } value_type;

/* The values a member may take: bounds (LO, HI, open or closed), SI. */
typedef struct range {
  unsigned bounds;
  double lo, hi;
} range;

/* A member of a part's struct and the values it may take. when: the
 * member matters only if it returns 1 (NULL: always). */
typedef struct field {
  const char *member;
  size_t offset;
  value_type type; /* REAL: a double; WHOLE: an int */
  range range;
  const char *unit;
  int (*when)(const fb_scenario *s);
} field;

static int has_mass(const fb_scenario *s)
{
  return s->hull_mass_given;
}
static int has_fe(const fb_scenario *s)
{
  return s->has_fe_hull;
}
static int has_coupling(const fb_scenario *s)
{
  return s->has_fe_hull && s->coupling != FB_COUPLING_NONE;
}

#define F(T, m, t, r, u, w)                                                                    \
  {                                                                                            \
#m, offsetof(T, m), t, r, u, w                                                             \
  }
#define POSITIVE                                                                               \
  {                                                                                            \
    LO | LO_OPEN, 0, 0                                                                         \
  }
#define NONNEGATIVE                                                                            \
  {                                                                                            \
    LO, 0, 0                                                                                   \
  }
#define ANY                                                                                    \
  {                                                                                            \
    0, 0, 0                                                                                    \
  }
#define RATIO                                                                                  \
  {                                                                                            \
    LO | HI | HI_OPEN, 0, 0.5                                                                  \
  } /* Poisson's ratio, [0, 1/2) */
#define CLOSED(l, h)                                                                           \
  {                                                                                            \
    LO | HI, (l), (h)                                                                          \
  }
#define HALF_OPEN(l, h)                                                                        \
  {                                                                                            \
    LO | HI | HI_OPEN, (l), (h)                                                                \
  }
#define OPEN(l, h)                                                                             \
  {                                                                                            \
    LO | LO_OPEN | HI | HI_OPEN, (l), (h)                                                      \
  }

static const field vehicle_fields[] = {
    F(fb_scenario, gravity, REAL, POSITIVE, "m/s^2", NULL),
    F(fb_scenario, hull_mass, REAL, POSITIVE, "kg", has_mass),
    F(fb_scenario, hull_ixx, REAL, POSITIVE, "kg m^2", has_mass),
    F(fb_scenario, hull_iyy, REAL, POSITIVE, "kg m^2", has_mass),
    F(fb_scenario, young, REAL, POSITIVE, "Pa", NULL),
    F(fb_scenario, poisson, REAL, RATIO, NULL, NULL),
    F(fb_scenario, density, REAL, POSITIVE, "kg/m^3", NULL),
    F(fb_scenario, thickness, REAL, POSITIVE, "m", NULL),
    F(fb_scenario, edge_front_x, REAL, ANY, "m", NULL),
    F(fb_scenario, edge_rear_x, REAL, ANY, "m", NULL),
    F(fb_scenario, edge_left_y, REAL, ANY, "m", NULL),
    F(fb_scenario, edge_right_y, REAL, ANY, "m", NULL),
    F(fb_scenario, total_weight, REAL, POSITIVE, "N", NULL),
    F(fb_scenario, payload, WHOLE, CLOSED(FB_PAYLOAD_WEIGHT_ONLY, FB_PAYLOAD_LUMPED), NULL,
      NULL),
    F(fb_scenario, speed, REAL, POSITIVE, "m/s", NULL),
    F(fb_scenario, t_end, REAL, POSITIVE, "s", NULL),
    F(fb_scenario, rtol, REAL, OPEN(0, 1), NULL, NULL),
    F(fb_scenario, atol, REAL, POSITIVE, NULL, NULL),
    F(fb_scenario, max_step, REAL, NONNEGATIVE, "s", NULL),
    F(fb_scenario, sample_rate, REAL, POSITIVE, "Hz", NULL),
    F(fb_scenario, initial, WHOLE, CLOSED(FB_INITIAL_ZERO, FB_INITIAL_STATIC), NULL, NULL),
    F(fb_scenario, hull_mass_matrix, WHOLE, CLOSED(FB_MASS_CONSISTENT, FB_MASS_LUMPED), NULL,
      has_fe),
    F(fb_scenario, hull_drill_factor, REAL, POSITIVE, NULL, has_fe),
    F(fb_scenario, hull_damping_ratio, REAL, HALF_OPEN(0, 1), NULL, has_fe),
    F(fb_scenario, hull_coordinates, WHOLE, CLOSED(FB_HULL_NODAL, FB_HULL_MODAL), NULL, has_fe),
    F(fb_scenario, coupling_radius, REAL, POSITIVE, "m", has_coupling),
    F(fb_scenario, hull_cutoff_hz, REAL, NONNEGATIVE, "Hz", has_fe),
};

static const field corner_fields[] = {
    F(fb_corner_params, x, REAL, ANY, "m", NULL),
    F(fb_corner_params, y, REAL, ANY, "m", NULL),
    F(fb_corner_params, spring_k, REAL, POSITIVE, "N/m", NULL),
    F(fb_corner_params, motion_ratio, REAL, POSITIVE, NULL, NULL),
    F(fb_corner_params, wheel_mass, REAL, POSITIVE, "kg", NULL),
    F(fb_corner_params, tire_k, REAL, POSITIVE, "N/m", NULL),
    F(fb_corner_params, tire_c, REAL, NONNEGATIVE, "N s/m", NULL),
};

static const field mount_fields[] = {
    F(fb_mount, mass, REAL, POSITIVE, "kg", NULL),
    F(fb_mount, stiffness, REAL, POSITIVE, "N/m", NULL),
    F(fb_mount, damping, REAL, NONNEGATIVE, "N s/m", NULL),
    F(fb_mount, x, REAL, ANY, "m", NULL),
    F(fb_mount, y, REAL, ANY, "m", NULL),
};

static const field antiroll_bar_fields[] = {
    F(fb_antiroll_bar, stiffness, REAL, POSITIVE, "N/m", NULL),
    F(fb_antiroll_bar, damping, REAL, NONNEGATIVE, "N s/m", NULL),
};

static const field bogie_fields[] = {
    F(fb_bogie, pivot_x, REAL, ANY, "m", NULL),
    F(fb_bogie, beam_mass, REAL, POSITIVE, "kg", NULL),
    F(fb_bogie, beam_inertia, REAL, POSITIVE, "kg m^2", NULL),
    F(fb_bogie, spring_k, REAL, POSITIVE, "N/m", NULL),
    F(fb_bogie, damper_c, REAL, NONNEGATIVE, "N s/m", NULL),
};

static const field body_fields[] = {
    F(fb_body, mass, REAL, POSITIVE, "kg", NULL),
    F(fb_body, x, REAL, ANY, "m", NULL),
    F(fb_body, y, REAL, ANY, "m", NULL),
    F(fb_body, z, REAL, ANY, "m", NULL),
    F(fb_body, ixx, REAL, POSITIVE, "kg m^2", NULL),
    F(fb_body, iyy, REAL, POSITIVE, "kg m^2", NULL),
    F(fb_body, izz, REAL, POSITIVE, "kg m^2", NULL),
    F(fb_body, ixy, REAL, ANY, "kg m^2", NULL),
    F(fb_body, ixz, REAL, ANY, "kg m^2", NULL),
    F(fb_body, iyz, REAL, ANY, "kg m^2", NULL),
};

static const field bushing_fields[] = {
    F(fb_bushing, x, REAL, ANY, "m", NULL),
    F(fb_bushing, y, REAL, ANY, "m", NULL),
    F(fb_bushing, z, REAL, ANY, "m", NULL),
    F(fb_bushing, radius, REAL, NONNEGATIVE, "m", NULL),
};

static const field point_mass_fields[] = {
    F(fb_hull_point_mass, mass, REAL, POSITIVE, "kg", NULL),
    F(fb_hull_point_mass, x, REAL, ANY, "m", NULL),
    F(fb_hull_point_mass, y, REAL, ANY, "m", NULL),
};

static const field section_fields[] = {
    F(fb_hull_section, thickness, REAL, POSITIVE, "m", NULL),
    F(fb_hull_section, young, REAL, POSITIVE, "Pa", NULL),
    F(fb_hull_section, poisson, REAL, RATIO, NULL, NULL),
    F(fb_hull_section, density, REAL, POSITIVE, "kg/m^3", NULL),
    F(fb_hull_section, nonstructural_mass, REAL, NONNEGATIVE, "kg/m^2", NULL),
};

#undef F
#undef POSITIVE
#undef NONNEGATIVE
#undef ANY
#undef RATIO
#undef CLOSED
#undef HALF_OPEN
#undef OPEN

/* Member f of the item at base: finite, within its bounds. */
static int check_field(const field *f, const void *base, int kind, size_t i, fb_err *err)
{
  const unsigned char *at = (const unsigned char *)base + f->offset;
  double x;
  if (f->type == REAL)
    memcpy(&x, at, sizeof x);
  else {
    int v;
    memcpy(&v, at, sizeof v);
    x = v;
  }
  const range *r = &f->range;
  if (isfinite(x) && fb_range_contains(r->bounds, r->lo, r->hi, x))
    return FB_OK;
  char text[64];
  fb_range_text(r->bounds, r->lo, r->hi, text, sizeof text);
  if (!text[0])
    snprintf(text, sizeof text, "finite");
  if (f->type == WHOLE)
    return fail(err, kind, i, f->member, "unknown value %.0f", x);
  return fail(err, kind, i, f->member, "must be %s%s%s (got %.10g)", text, f->unit ? " " : "",
              f->unit ? f->unit : "", x);
}

/* Every field of n items of item_size bytes from base, of part kind. */
static int check_items(const fb_scenario *s, const field *fields, size_t nfields,
                       const void *base, size_t n, size_t item_size, int kind, fb_err *err)
{
  for (size_t i = 0; i < n; ++i)
    for (size_t k = 0; k < nfields; ++k) {
      if (fields[k].when && !fields[k].when(s))
        continue;
      const int rc =
          check_field(&fields[k], (const unsigned char *)base + i * item_size, kind, i, err);
      if (rc)
        return rc;
    }
  return FB_OK;
}

#define NFIELDS(a) (sizeof(a) / sizeof((a)[0]))

static int check_values(const fb_scenario *s, fb_err *err)
{
  int rc = check_items(s, vehicle_fields, NFIELDS(vehicle_fields), s, 1, sizeof *s,
                       FB_PART_VEHICLE, err);
  if (!rc)
    rc = check_items(s, corner_fields, NFIELDS(corner_fields), s->corner, s->ncorners,
                     sizeof *s->corner, FB_PART_CORNER, err);
  if (!rc)
    rc = check_items(s, mount_fields, NFIELDS(mount_fields), s->mount, s->nmounts,
                     sizeof *s->mount, FB_PART_MOUNT, err);
  if (!rc)
    rc = check_items(s, antiroll_bar_fields, NFIELDS(antiroll_bar_fields), s->antiroll_bar,
                     s->nantiroll_bars, sizeof *s->antiroll_bar, FB_PART_ANTIROLL_BAR, err);
  if (!rc)
    rc = check_items(s, bogie_fields, NFIELDS(bogie_fields), s->bogie, s->nbogies,
                     sizeof *s->bogie, FB_PART_BOGIE, err);
  if (!rc)
    rc = check_items(s, body_fields, NFIELDS(body_fields), s->body, s->nbodies, sizeof *s->body,
                     FB_PART_BODY, err);
  for (size_t b = 0, k = 0; !rc && b < s->nbodies; ++b)
    for (size_t j = 0; !rc && j < s->body[b].nbushings; ++j, ++k)
      for (size_t f = 0; !rc && f < NFIELDS(bushing_fields); ++f)
        rc = check_field(&bushing_fields[f], &s->body[b].bushing[j], FB_PART_BUSHING, k, err);
  if (!rc)
    rc = check_items(s, point_mass_fields, NFIELDS(point_mass_fields), s->point_mass,
                     s->npoint_masses, sizeof *s->point_mass, FB_PART_HULL_MASS, err);
  if (!rc)
    rc = check_items(s, section_fields, NFIELDS(section_fields), s->section, s->nsections,
                     sizeof *s->section, FB_PART_SECTION, err);
  return rc;
}

/* ---- Rules between values. */

static int check_hull(const fb_scenario *s, fb_err *err)
{
  /* The torsion angle divides by the edges' spans. */
  if (!(s->edge_front_x > s->edge_rear_x))
    return fail(err, FB_PART_VEHICLE, 0, "edge_front_x",
                "the front edge must be ahead of the rear edge, at x = %.10g m (got %.10g)",
                s->edge_rear_x, s->edge_front_x);
  if (!(s->edge_left_y > s->edge_right_y))
    return fail(err, FB_PART_VEHICLE, 0, "edge_left_y",
                "the edges' left end must be left of their right end, at y = %.10g m (got "
                "%.10g)",
                s->edge_right_y, s->edge_left_y);
  return FB_OK;
}

static int check_load(const fb_scenario *s, fb_err *err)
{
  if (s->nload < 1 || !s->load_x || !s->load_y)
    return fail(err, FB_PART_VEHICLE, 0, "load_x",
                "at least one load point is needed (got %zu)", s->nload);
  for (size_t i = 0; i < s->nload; ++i)
    if (!isfinite(s->load_x[i]) || !isfinite(s->load_y[i]))
      return fail(err, FB_PART_LOAD_POINT, i, "", "must be finite (got x = %g, y = %g)",
                  s->load_x[i], s->load_y[i]);
  /* The lumped model spreads the payload mass W / g - m_hull - the hull's
   * declared masses over the points (data sheet, "Load and gravity"): it
   * must be positive. A finite-element hull's own mass, when the
   * description gives none, is counted once its mesh is built
   * (fb_vehicle_hull_complete). */
  if (s->payload != FB_PAYLOAD_LUMPED || fb_scenario_payload_mass(s) > 0)
    return FB_OK;
  const double masses = fb_scenario_point_masses_total(s);
  return fail(err, FB_PART_VEHICLE, 0, "payload",
              "a lumped payload needs the total weight / gravity (%.10g kg) > the hull's "
              "structure (%.10g kg) + its declared masses (%.10g kg)",
              s->total_weight / s->gravity, s->hull_mass, masses);
}

/* An error rc of corner c's gallery entry: about one of its parameters
 * (err->part.field set by the entry), it is part kind param_kind of
 * corner c; otherwise the corner's member naming the entry. */
static int corner_entry_error(int rc, fb_err *err, fb_part_kind param_kind, size_t c,
                              const char *member)
{
  if (rc && err && err->part.field[0]) {
    err->part.kind = param_kind;
    err->part.index = c;
  } else if (rc) {
    fb_err_set_part(err, FB_PART_CORNER, c, FB_ERR_NO_ELEMENT, member);
  }
  return rc;
}

/* Each corner's shock absorber: a sound law, its block within the
 * declared ranges, and the law's own rules; errors name the corner's
 * damper parameter (FB_PART_DAMPER) or its law. */
static int check_dampers(const fb_scenario *s, fb_err *err)
{
  const char *const member = fb_part_member_(FB_PART_CORNER, damper_law);
  for (size_t c = 0; c < s->ncorners; ++c) {
    const fb_corner_params *corner = &s->corner[c];
    const fb_damper_law *l = fb_corner_damper_law(corner);
    int rc = fb_damper_law_check(l, err);
    if (rc)
      return fb_err_set_part(err, FB_PART_CORNER, c, FB_ERR_NO_ELEMENT, member), rc;
    rc = fb_params_check(l->param, l->nparams, corner->damper.bytes, err);
    if (!rc && l->ops->check)
      rc = l->ops->check(corner->damper.bytes, corner->name, err);
    if (rc)
      return corner_entry_error(rc, err, FB_PART_DAMPER, c, member);
  }
  return FB_OK;
}

/* Each corner's spring: a sound law, its block within the declared
 * ranges, and the law's own rules; errors name the corner's spring
 * parameter (FB_PART_SPRING) or its law. */
static int check_springs(const fb_scenario *s, fb_err *err)
{
  const char *const member = fb_part_member_(FB_PART_CORNER, spring_law);
  for (size_t c = 0; c < s->ncorners; ++c) {
    const fb_corner_params *corner = &s->corner[c];
    const fb_spring_law *l = fb_corner_spring_law(corner);
    int rc = fb_spring_law_check(l, err);
    if (rc)
      return fb_err_set_part(err, FB_PART_CORNER, c, FB_ERR_NO_ELEMENT, member), rc;
    const fb_spring_context ctx = fb_corner_spring_context(corner);
    rc = fb_params_check(l->param, l->nparams, corner->spring.bytes, err);
    if (!rc && l->ops->check)
      rc = l->ops->check(corner->spring.bytes, &ctx, err);
    if (rc)
      return corner_entry_error(rc, err, FB_PART_SPRING, c, member);
  }
  return FB_OK;
}

/* Each corner's stops (fb_stops_check); errors name the stop's member
 * (FB_PART_STOP). */
static int check_stops(const fb_scenario *s, fb_err *err)
{
  for (size_t c = 0; c < s->ncorners; ++c) {
    const int rc = fb_stops_check(&s->corner[c].stops, s->corner[c].name, err);
    if (rc)
      return corner_entry_error(rc, err, FB_PART_STOP, c,
                                fb_part_member_(FB_PART_CORNER, stops));
  }
  return FB_OK;
}

/* Points closer than this are one point (m): the 1 mm within which a
 * deck's node must sit at the description's point. */
#define SAME_POINT 1e-3

/* A point on the hull's floor, the rectangle of the torsion edges (System
 * 2 puts a node at each; on System 1 a point off the hull is a lever arm
 * no vehicle has, almost surely a typing error). kind, i: its part; the
 * members of its x and y ("" for a load point). */
static int check_on_floor(const fb_scenario *s, int kind, size_t i, const char *fx,
                          const char *fy, double x, double y, fb_err *err)
{
  if (x < s->edge_rear_x || x > s->edge_front_x)
    return fail(err, kind, i, fx,
                "must lie on the hull's floor, between the rear edge's x = %.10g and the front "
                "edge's x = %.10g m (got %.10g)",
                s->edge_rear_x, s->edge_front_x, x);
  if (y < s->edge_right_y || y > s->edge_left_y)
    return fail(err, kind, i, fy,
                "must lie on the hull's floor, between the right end's y = %.10g and the left "
                "end's y = %.10g m (got %.10g)",
                s->edge_right_y, s->edge_left_y, y);
  return FB_OK;
}

static int check_load_points(const fb_scenario *s, fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < s->nload; ++i) {
    rc = check_on_floor(s, FB_PART_LOAD_POINT, i, "", "", s->load_x[i], s->load_y[i], err);
    /* Each point carries its share of the weight at its own node. */
    for (size_t j = 0; !rc && j < i; ++j)
      if (hypot(s->load_x[i] - s->load_x[j], s->load_y[i] - s->load_y[j]) < SAME_POINT)
        rc = fail(err, FB_PART_LOAD_POINT, i, "",
                  "at (%.10g, %.10g) m, where load point %zu already is (two load points at "
                  "one point)",
                  s->load_x[i], s->load_y[i], j);
  }
  return rc;
}

/* 1 if a and b are one name (a missing name is no name). */
static int same(const char *a, const char *b)
{
  return a && b && !strcmp(a, b);
}

/* 1 if rest is bogie's name followed by suffix. */
static int bogie_named(const char *rest, const char *bogie, const char *suffix)
{
  const size_t n = bogie ? strlen(bogie) : 0;
  return bogie && !strncmp(rest, bogie, n) && !strcmp(rest + n, suffix);
}

/* 1 if name is an anti-roll bar's or a bogie's part of the assembled
 * graph ("arb_<bar>", "bogie_<bogie>", its saddle "saddle_<bogie>" and
 * the saddle's "_front" and "_rear" levers: fb_vehicle_assemble), which
 * a mount's or a body's instance, its own name, would clash with. */
static int names_bar_or_bogie(const fb_scenario *s, const char *name)
{
  for (size_t i = 0; i < s->nantiroll_bars; ++i)
    if (!strncmp(name, "arb_", 4) && same(name + 4, s->antiroll_bar[i].name))
      return 1;
  static const char *const suffixes[3] = {"", "_front", "_rear"};
  for (size_t i = 0; i < s->nbogies; ++i) {
    if (!strncmp(name, "bogie_", 6) && same(name + 6, s->bogie[i].name))
      return 1;
    for (int k = 0; k < 3; ++k)
      if (!strncmp(name, "saddle_", 7) && bogie_named(name + 7, s->bogie[i].name, suffixes[k]))
        return 1;
  }
  return 0;
}

/* Names unique among the corners and among the mounts: they name the
 * subsystem instances, mesh node sets and outputs. The later one is
 * blamed. */
static int check_names(const fb_scenario *s, fb_err *err)
{
  for (size_t k = 0; k < s->ncorners; ++k)
    if (!s->corner[k].name)
      return fail(err, FB_PART_CORNER, k, "name", "has no name");
  for (size_t k = 0; k < s->nmounts; ++k)
    if (!s->mount[k].name)
      return fail(err, FB_PART_MOUNT, k, "name", "has no name");
  for (size_t k = 0; k < s->ncorners; ++k)
    for (size_t j = 0; j < k; ++j)
      if (same(s->corner[k].name, s->corner[j].name))
        return fail(err, FB_PART_CORNER, k, "",
                    "a second corner named %s (corner names are unique)", s->corner[k].name);
  for (size_t k = 0; k < s->nmounts; ++k)
    for (size_t j = 0; j < k; ++j)
      if (same(s->mount[k].name, s->mount[j].name))
        return fail(err, FB_PART_MOUNT, k, "",
                    "a second mount named %s (mount names are unique)", s->mount[k].name);
  for (size_t k = 0; k < s->nmounts; ++k)
    if (names_bar_or_bogie(s, s->mount[k].name))
      return fail(err, FB_PART_MOUNT, k, "name",
                  "%s is the name of an anti-roll bar's or a bogie's part of the assembled "
                  "vehicle (arb_<bar>, bogie_<bogie>, saddle_<bogie>): give the mount another",
                  s->mount[k].name);
  return FB_OK;
}

/* A hull mass's name: unique among the hull masses (in capitals too:
 * its mesh node set is MASS_<NAME>), the mounts and the corners. */
static int check_point_mass_name(const fb_scenario *s, size_t k, fb_err *err)
{
  const char *name = s->point_mass[k].name;
  for (size_t j = 0; j < k; ++j) {
    const char *other = s->point_mass[j].name;
    if (same(name, other))
      return fail(err, FB_PART_HULL_MASS, k, "",
                  "a second hull mass named %s (hull mass names are unique)", name);
    if (other && !strcasecmp(name, other)) {
      char set[128];
      snprintf(set, sizeof set, "%s", name);
      for (char *c = set; *c; ++c)
        *c = (char)toupper((unsigned char)*c);
      return fail(err, FB_PART_HULL_MASS, k, "",
                  "hull mass %s's name in other capitals: both would be the mesh's node set "
                  "MASS_%s",
                  other, set);
    }
  }
  const char *kind = fb_scenario_mount_find(s, name) >= 0    ? "mount"
                     : fb_scenario_corner_find(s, name) >= 0 ? "corner"
                                                             : NULL;
  if (kind)
    return fail(err, FB_PART_HULL_MASS, k, "",
                "a %s is named %s already (the names of hull masses, mounts and corners are "
                "unique)",
                kind, name);
  return FB_OK;
}

static int check_point_masses(const fb_scenario *s, fb_err *err)
{
  int rc = FB_OK;
  for (size_t k = 0; !rc && k < s->npoint_masses; ++k) {
    const fb_hull_point_mass *m = &s->point_mass[k];
    if (!m->name)
      return fail(err, FB_PART_HULL_MASS, k, "name", "has no name");
    rc = check_point_mass_name(s, k, err);
    if (!rc)
      rc = check_on_floor(s, FB_PART_HULL_MASS, k, "x", "y", m->x, m->y, err);
  }
  return rc;
}

/* Every attachment point on the floor, no two corners (two wheels cannot
 * stand in one place) at one point. */
static int check_points(const fb_scenario *s, fb_err *err)
{
  int rc = FB_OK;
  for (size_t k = 0; !rc && k < s->nmounts; ++k)
    rc = check_on_floor(s, FB_PART_MOUNT, k, "x", "y", s->mount[k].x, s->mount[k].y, err);
  if (!rc)
    rc = check_load_points(s, err);
  for (size_t k = 0; !rc && k < s->ncorners; ++k) {
    const fb_corner_params *c = &s->corner[k];
    rc = check_on_floor(s, FB_PART_CORNER, k, "x", "y", c->x, c->y, err);
    for (size_t j = 0; !rc && j < k; ++j)
      if (hypot(c->x - s->corner[j].x, c->y - s->corner[j].y) < SAME_POINT)
        rc = fail(err, FB_PART_CORNER, k, "",
                  "at (%.10g, %.10g) m, where corner %s already is (two corners at one point)",
                  c->x, c->y, s->corner[j].name);
  }
  return rc;
}

/* ---- Mounted rigid bodies. */

/* 1 if the symmetric n x n a (row major) is positive definite, or semi-
 * definite when allow_singular (fb_mat_is_spd's tolerances); 0 also for
 * a matrix that is not symmetric or not finite. */
static int is_spd(size_t n, const double *a, int allow_singular)
{
  fb_mat *m = NULL;
  if (fb_mat_new_dense_rowmajor(n, n, a, &m, NULL))
    return 0;
  const int spd = fb_mat_is_spd(m, allow_singular);
  fb_mat_free(&m);
  return spd;
}

/* The field of b's inertia an error about it names: the product with the
 * largest |I_ab| / sqrt(I_aa I_bb) for a tensor that is not positive
 * definite (the diagonal is > 0: the reader's range), else the largest
 * moment, the one a triangle inequality fails on when the products are 0
 * (the value to change, and a sweep's swept key). */
static const char *body_inertia_field(const fb_body *b, int definite)
{
  const double d[3] = {b->ixx, b->iyy, b->izz};
  if (!definite) {
    const double p[3] = {b->ixy, b->ixz, b->iyz};
    static const int pair[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    static const char *const products[3] = {"ixy", "ixz", "iyz"};
    int worst = 0;
    for (int k = 1; k < 3; ++k)
      if (fabs(p[k]) / sqrt(d[pair[k][0]] * d[pair[k][1]]) >
          fabs(p[worst]) / sqrt(d[pair[worst][0]] * d[pair[worst][1]]))
        worst = k;
    return products[worst];
  }
  static const char *const moments[3] = {"ixx", "iyy", "izz"};
  int largest = 0;
  for (int k = 1; k < 3; ++k)
    if (d[k] >= d[largest])
      largest = k;
  return moments[largest];
}

/* A body's inertia tensor: positive definite, and its principal moments
 * obey the triangle inequalities I1 + I2 >= I3 (each is the sum of two
 * second moments of the mass, e.g. Ixx + Iyy - Izz = 2 integral z^2 dm:
 * Goldstein, Poole & Safko, "Classical Mechanics", 3rd ed., sec. 5.3),
 * to 1e-9 of the trace (a thin plate meets one with equality). */
static int check_body_inertia(const fb_body *b, size_t i, fb_err *err)
{
  double j[9];
  vehicle_body_inertia(b, j);
  if (!is_spd(3, j, 0))
    return fail(err, FB_PART_BODY, i, body_inertia_field(b, 0),
                "the inertia tensor [[Ixx, -Ixy, -Ixz], [-Ixy, Iyy, -Iyz], [-Ixz, -Iyz, Izz]] "
                "must be positive definite (got Ixx %.6g, Iyy %.6g, Izz %.6g, Ixy %.6g, Ixz "
                "%.6g, Iyz %.6g kg m^2)",
                b->ixx, b->iyy, b->izz, b->ixy, b->ixz, b->iyz);
  double p[3];
  if (vehicle_sym3_eigenvalues(j, p))
    return fail(err, FB_PART_BODY, i, "ixx", "the inertia tensor's principal moments failed");
  const double slack = 1e-9 * (p[0] + p[1] + p[2]);
  if (p[0] + p[1] < p[2] - slack)
    return fail(err, FB_PART_BODY, i, body_inertia_field(b, 1),
                "the principal moments of inertia %.6g, %.6g and %.6g kg m^2 break the "
                "triangle inequality (%.6g + %.6g < %.6g): no body has them",
                p[0], p[1], p[2], p[0], p[1], p[2]);
  return FB_OK;
}

/* Bushing k (body b's j-th): symmetric positive semi-definite K and C. */
static int check_bushing(const fb_scenario *s, size_t b, size_t j, size_t k, fb_err *err)
{
  if (!s->body[b].bushing || j >= s->body[b].nbushings)
    return fail(err, FB_PART_BODY, b, "bushing", "has no bushing %zu", j);
  const fb_bushing *u = &s->body[b].bushing[j];
  if (!is_spd(6, u->k, 1))
    return fail(err, FB_PART_BUSHING, k, "k",
                "the stiffness matrix must be symmetric and positive semi-definite");
  if (!is_spd(6, u->c, 1))
    return fail(err, FB_PART_BUSHING, k, "c",
                "the damping matrix must be symmetric and positive semi-definite");
  const int on_hull = s->body[b].parent == NULL;
  if (on_hull && s->has_fe_hull && !u->node_set && !u->surface && !s->coupling_surface)
    return fail(err, FB_PART_BUSHING, k, "node_set",
                "a bushing on the finite-element hull is coupled to its nodes: give its "
                "node set, or a surface and a radius (or the scenario's coupling surface)");
  if ((u->node_set || u->surface || u->radius > 0) && !(on_hull && s->has_fe_hull))
    return fail(err, FB_PART_BUSHING, k,
                u->node_set  ? "node_set"
                : u->surface ? "surface"
                             : "radius",
                "a node set, surface or radius couples a bushing to the hull's mesh: only for "
                "a body on the hull (%s) with a finite-element hull",
                on_hull ? "this one is" : "this one is on another body");
  return FB_OK;
}

/* The bushings together hold the body in all six components: their
 * stiffnesses carried to its centre of mass (T' K T) sum to a positive
 * definite matrix, else a static load moves it without bound. */
static int check_body_support(const fb_body *b, size_t i, fb_err *err)
{
  double sum[36] = {0};
  for (size_t j = 0; j < b->nbushings; ++j)
    vehicle_bushing_add_at_centre(b, &b->bushing[j], b->bushing[j].k, sum);
  if (is_spd(6, sum, 0))
    return FB_OK;
  return fail(err, FB_PART_BODY, i, "bushing",
              "its bushings leave it free to move in some direction (their stiffness at its "
              "centre of mass is singular): give a stiffness in every direction");
}

/* Names unique among the bodies, mounts, hull masses and corners (they
 * name instances and outputs); a parent named before the body: the
 * hull, or an earlier body (so that no chain of parents is a cycle). */
static const char *body_name_at(const void *ctx, size_t i);
static void names_hint(const fb_scenario *s, const char *word, size_t n, fb_name_fn name_at,
                       const char *what, char *buf, size_t size);

static int check_body_names(const fb_scenario *s, size_t i, fb_err *err)
{
  const fb_body *b = &s->body[i];
  if (!b->name)
    return fail(err, FB_PART_BODY, i, "name", "has no name");
  const long same_body = fb_scenario_body_find(s, b->name);
  if (same_body >= 0 && (size_t)same_body < i)
    return fail(err, FB_PART_BODY, i, "name", "a second body named %s (names are unique)",
                b->name);
  int taken =
      fb_scenario_mount_find(s, b->name) >= 0 || fb_scenario_corner_find(s, b->name) >= 0;
  for (size_t k = 0; !taken && k < s->npoint_masses; ++k)
    taken = same(s->point_mass[k].name, b->name);
  if (taken)
    return fail(err, FB_PART_BODY, i, "name",
                "%s names a mount, corner or hull mass already (the names of bodies, mounts, "
                "hull masses and corners are unique)",
                b->name);
  /* A body's fragment is an instance of the assembled graph beside
   * these (fb_vehicle_assemble). */
  static const char *const instances[] = {"hull", "road", "load", "attach"};
  for (size_t k = 0; k < sizeof instances / sizeof instances[0]; ++k)
    if (!strcmp(b->name, instances[k]) || !strncmp(b->name, "susp_", 5) ||
        names_bar_or_bogie(s, b->name))
      return fail(
          err, FB_PART_BODY, i, "name",
          "%s is a name of the assembled vehicle's own (hull, road, load, attach, "
          "susp_<corner>, arb_<bar>, bogie_<bogie>, saddle_<bogie>): give the body another",
          b->name);
  if (!b->parent)
    return FB_OK;
  const long parent = fb_scenario_body_find(s, b->parent);
  if (parent >= 0 && (size_t)parent < i)
    return FB_OK;
  /* The bodies before it are those it may be on. */
  char hint[512];
  names_hint(s, b->parent, i, body_name_at, "bodies before it", hint, sizeof hint);
  return fail(err, FB_PART_BODY, i, "parent",
              "%s is no body listed before %s (a body is mounted on the hull or on a body "
              "before it)%s",
              b->parent, b->name, hint);
}

/* A hull carrying bodies moves in six degrees of freedom: its whole
 * inertia tensor, positive definite. */
static int check_hull_tensor(const fb_scenario *s, fb_err *err)
{
  if (!s->nbodies || (!s->hull_izz_given && s->has_fe_hull))
    return FB_OK; /* the mesh's, once it is built */
  if (!s->hull_izz_given)
    return fail(err, FB_PART_VEHICLE, 0, "hull_izz",
                "a hull carrying mounted rigid bodies moves in six degrees of freedom: give "
                "its yaw inertia Izz (and its products of inertia, 0 by default)");
  double j[9];
  vehicle_hull_inertia(s, j);
  if (!(s->hull_izz > 0) || !is_spd(3, j, 0))
    return fail(err, FB_PART_VEHICLE, 0, "hull_izz",
                "the hull's inertia tensor (Ixx %.6g, Iyy %.6g, Izz %.6g, Ixy %.6g, Ixz %.6g, "
                "Iyz %.6g kg m^2) must be positive definite",
                s->hull_ixx, s->hull_iyy, s->hull_izz, s->hull_ixy, s->hull_ixz, s->hull_iyz);
  return FB_OK;
}

static int check_bodies(const fb_scenario *s, fb_err *err)
{
  int rc = check_hull_tensor(s, err);
  for (size_t i = 0, k = 0; !rc && i < s->nbodies; ++i) {
    const fb_body *b = &s->body[i];
    rc = check_body_names(s, i, err);
    if (!rc && (b->nbushings < 1 || !b->bushing))
      rc = fail(err, FB_PART_BODY, i, "bushing", "needs at least one bushing");
    for (size_t j = 0; !rc && j < b->nbushings; ++j, ++k)
      rc = check_bushing(s, i, j, k, err);
    if (!rc)
      rc = check_body_inertia(b, i, err);
    if (!rc)
      rc = check_body_support(b, i, err);
  }
  return rc;
}

/* The road: its type's declared ranges, then its own rules. */
static int check_road(const fb_scenario *s, fb_err *err)
{
  const fb_road_type *t = s->road_type;
  if (!t)
    return fail(err, FB_PART_VEHICLE, 0, "road_type", "no road (fb_scenario_set_road)");
  int rc = fb_road_type_check(t, err);
  if (rc)
    return fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, road_type)), rc;
  rc = fb_params_check(t->param, t->nparams, s->road.bytes, err);
  const fb_road_layout layout = fb_scenario_road_layout(s);
  if (!rc && t->ops->check)
    rc = t->ops->check(s->road.bytes, &layout, err);
  return vehicle_road_error(rc, err);
}

/* Each corner's tire: a sound model, its block within the declared
 * ranges, and the model's own rules for the loaded corner; errors name
 * the corner's tire parameter (FB_PART_TIRE) or its model. */
static int check_tires(const fb_scenario *s, fb_err *err)
{
  for (size_t c = 0; c < s->ncorners; ++c) {
    const fb_tire_model *m = fb_corner_tire_model(&s->corner[c]);
    int rc = fb_tire_model_check(m, err);
    if (rc)
      return fb_err_set_part(err, FB_PART_AT(FB_PART_CORNER, c, tire_model)), rc;
    const fb_corner_params loaded = vehicle_corner_loaded(s, c);
    const fb_tire_context ctx = fb_corner_tire_context(&loaded);
    rc = fb_params_check(m->param, m->nparams, loaded.tire.bytes, err);
    if (!rc && m->ops->check)
      rc = m->ops->check(loaded.tire.bytes, &ctx, err);
    if (rc)
      return corner_entry_error(rc, err, FB_PART_TIRE, c,
                                fb_part_member_(FB_PART_CORNER, tire_model));
  }
  return FB_OK;
}

/* Each corner's envelope: a sound model, the tire's free radius where
 * the model reads it, its block within the declared ranges, and the
 * model's own rules for the loaded corner; errors name the corner's
 * envelope parameter (FB_PART_ENVELOPE), its radius or its model. */
static int check_envelopes(const fb_scenario *s, fb_err *err)
{
  for (size_t c = 0; c < s->ncorners; ++c) {
    const fb_envelope_model *m = fb_corner_envelope_model(&s->corner[c]);
    int rc = fb_envelope_model_check(m, err);
    if (rc)
      return fb_err_set_part(err, FB_PART_AT(FB_PART_CORNER, c, envelope_model)), rc;
    const double r = s->corner[c].tire_radius;
    if (m->needs_radius && !(r > 0.0 && isfinite(r))) {
      if (r == 0.0) /* never given: 0 is the description's "none" */
        fb_err_set(err, FB_EINVAL,
                   "a `%s` envelope needs the tire's free radius (m, > 0), and none is given",
                   m->name);
      else
        fb_err_set(err, FB_EINVAL,
                   "a `%s` envelope needs the tire's free radius, > 0 m (got %g)", m->name, r);
      return fb_err_set_part(err, FB_PART_AT(FB_PART_CORNER, c, tire_radius)), FB_EINVAL;
    }
    const fb_corner_params loaded = vehicle_corner_loaded(s, c);
    const fb_envelope_context ctx = fb_corner_envelope_context(&loaded);
    rc = fb_params_check(m->param, m->nparams, loaded.envelope.bytes, err);
    if (!rc && m->ops->check)
      rc = m->ops->check(loaded.envelope.bytes, &ctx, err);
    if (rc)
      return corner_entry_error(rc, err, FB_PART_ENVELOPE, c,
                                fb_part_member_(FB_PART_CORNER, envelope_model));
  }
  return FB_OK;
}

/* The solver's own limits (fb_sim_opts_check: sample count, the result's
 * memory, the steps that max_step forces), whose errors name their
 * setting: the description's member of the same name. */
/* The modes listed for pictures are mode numbers: whole, from 1. */
static int check_pictured_modes(const fb_scenario *s, fb_err *err)
{
  for (size_t k = 0; k < s->npictured_modes; ++k) {
    const double m = s->pictured_modes[k];
    if (!(m >= 1.0 && m == floor(m) && m <= 1e6)) {
      fb_err_set(err, FB_EINVAL, "must be a mode number: a whole number from 1 (got %.10g)", m);
      fb_err_set_part(err, FB_PART_ELEMENT(FB_PART_VEHICLE, 0, pictured_modes, k));
      return FB_EINVAL;
    }
  }
  return FB_OK;
}

static int check_simulation(const fb_scenario *s, fb_err *err)
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
  const int rc = fb_sim_opts_check(&o, err);
  if (rc && err && err->key[0])
    fb_err_set_part(err, FB_PART_VEHICLE, 0, FB_ERR_NO_ELEMENT, err->key);
  return rc;
}

/* A road with a feature of finite length (a bump): every wheel meets it
 * at t >= 0 and has left it before t_end (the run must show the whole
 * crossing). */
static int check_road_timing(const fb_scenario *s, fb_err *err)
{
  double begin = 0.0, end = INFINITY;
  const fb_road_layout layout = fb_scenario_road_layout(s);
  if (s->road_type->ops->feature)
    s->road_type->ops->feature(s->road.bytes, &layout, FB_ROAD_LEFT, &begin, &end);
  if (!isfinite(end)) /* a road that goes on */
    return FB_OK;
  int first = 0, last = 0;
  for (int k = 1; k < (int)s->ncorners; ++k) {
    if (fb_scenario_road_entry(s, k) < fb_scenario_road_entry(s, first))
      first = k;
    if (fb_scenario_road_exit(s, k) > fb_scenario_road_exit(s, last))
      last = k;
  }
  const double t_in = fb_scenario_road_entry(s, first), t_out = fb_scenario_road_exit(s, last);
  if (!(t_in >= 0))
    return fail(err, FB_PART_ROAD, 0, "",
                "the %s wheel would meet the road's %s at %.6g s, before the run starts at 0 s",
                s->corner[first].name, s->road_type->name, t_in);
  if (!(t_out < s->t_end))
    return fail(err, FB_PART_VEHICLE, 0, "t_end",
                "the run ends at %.10g s, before the last wheel (%s) leaves the road's %s at "
                "%.6g s",
                s->t_end, s->corner[last].name, s->road_type->name, t_out);
  return FB_OK;
}

/* System 2's hull, when present: its basis, then its source's declared
 * ranges and rules (FB_PART_HULL_SOURCE names a parameter of its block). */
static int check_fe_hull(const fb_scenario *s, fb_err *err)
{
  if (!s->has_fe_hull)
    return FB_OK;
  const int count = s->hull_modes_kind == FB_HULL_MODES_COUNT;
  /* A reduced hull needs its six rigid-body modes at least. */
  if (count && s->hull_modes < 6)
    return fail(err, FB_PART_VEHICLE, 0, "hull_modes",
                "auto, all or at least the 6 rigid-body modes (got %d)", s->hull_modes);
  if (s->hull_modes_kind != FB_HULL_MODES_AUTO && s->hull_coordinates == FB_HULL_NODAL)
    return fail(err, FB_PART_VEHICLE, 0, "hull_modes",
                "a choice of modes (%s) is for modal coordinates, not nodal ones",
                count ? "a count" : "all");
  if (s->hull_cutoff_hz != 0 &&
      (s->hull_modes_kind != FB_HULL_MODES_AUTO || s->hull_coordinates == FB_HULL_NODAL))
    return fail(err, FB_PART_VEHICLE, 0, "hull_cutoff_hz",
                "a cut-off sets which modes the automatic basis keeps, in modal coordinates; "
                "not with %s",
                s->hull_coordinates == FB_HULL_NODAL ? "nodal coordinates"
                : count                              ? "a count of modes"
                                                     : "every mode");
  const fb_hull_source *src = fb_scenario_hull_source(s);
  int rc = fb_params_check(src->param, src->nparams, s->hull_params.bytes, err);
  if (!rc && src->ops->check)
    rc = src->ops->check(s, err);
  if (rc && err && !err->part.kind && err->part.field[0]) /* a parameter of its block */
    err->part.kind = FB_PART_HULL_SOURCE;
  return rc;
}

/* ---- Outputs. */

static const char *corner_name_at(const void *ctx, size_t i)
{
  return ((const fb_scenario *)ctx)->corner[i].name;
}

static const char *mount_name_at(const void *ctx, size_t i)
{
  return ((const fb_scenario *)ctx)->mount[i].name;
}

static const char *bogie_name_at(const void *ctx, size_t i)
{
  return ((const fb_scenario *)ctx)->bogie[i].name;
}

static const char *body_name_at(const void *ctx, size_t i)
{
  return ((const fb_scenario *)ctx)->body[i].name;
}

/* For an unknown name: " (did you mean 'LF'?)" when one is close, then
 * "; the corners are LF, RF, ..." (what: "corners"), into buf. */
static void names_hint(const fb_scenario *s, const char *word, size_t n, fb_name_fn name_at,
                       const char *what, char *buf, size_t size)
{
  const char *near = word && *word ? fb_suggest(word, n, name_at, s) : NULL;
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

/* A hull stress output's element (an id, or 0 and a finite point),
 * surface and component; whether the element is in the hull's mesh is
 * the outputs' check's (fb_vehicle_outputs_check). */
static int check_output_stress(const fb_output_spec *o, size_t i, fb_err *err)
{
  if (o->element < 0)
    return fail(err, FB_PART_OUTPUT, i, "element",
                "an element's id is positive (0: the element nearest at) (got %ld)",
                o->element);
  if (!o->element && !(isfinite(o->at[0]) && isfinite(o->at[1]) && isfinite(o->at[2])))
    return fail(err, FB_PART_OUTPUT, i, "at", "a hull point's coordinates must be finite");
  if (o->surface != FB_STRESS_TOP && o->surface != FB_STRESS_BOTTOM)
    return fail(err, FB_PART_OUTPUT, i, "surface",
                "a stress's surface is 0 (top) or 1 (bottom) (got %d)", o->surface);
  if (o->stress < FB_STRESS_SX || o->stress > FB_STRESS_SXY)
    return fail(err, FB_PART_OUTPUT, i, "stress",
                "a stress's component is 0 (sx), 1 (sy) or 2 (sxy) (got %d)", o->stress);
  return FB_OK;
}

/* The output's subject names a corner or a mount, as its signal asks. */
static int check_output_subject(const fb_scenario *s, size_t i, fb_err *err)
{
  const fb_output_spec *o = &s->output[i];
  const fb_output_kind *kind = o->signal ? fb_vehicle_output_kind_find(o->signal) : NULL;
  if (!kind)
    return fail(err, FB_PART_OUTPUT, i, "signal", "unknown signal '%s'",
                o->signal ? o->signal : "(none)");
  char hint[512];
  if (kind->subject == FB_OUTPUT_OF_CORNER &&
      (!o->of || fb_scenario_corner_find(s, o->of) < 0)) {
    names_hint(s, o->of, s->ncorners, corner_name_at, "corners", hint, sizeof hint);
    return fail(err, FB_PART_OUTPUT, i, "of",
                "no corner named '%s' (a %s signal measures a corner)%s", o->of ? o->of : "",
                o->signal, hint);
  }
  const long c = kind->subject == FB_OUTPUT_OF_CORNER ? fb_scenario_corner_find(s, o->of) : -1;
  const vehicle_signal *how = c >= 0 ? vehicle_corner_signal(s, (size_t)c, o->signal) : NULL;
  if (c >= 0 && !how)
    return fail(err, FB_PART_OUTPUT, i, "signal",
                "corner %s is a bogie's wheel, which has no %s: a bogie's wheel offers "
                "tire_force, tire_defl and tire_power",
                o->of, o->signal);
  if (how && how->offered && !how->offered(&s->corner[c]))
    return fail(err, FB_PART_OUTPUT, i, "of", "corner '%s' has no %s for %s to measure", o->of,
                how->needs, o->signal);
  if (kind->subject == FB_OUTPUT_OF_BOGIE && (!o->of || fb_scenario_bogie_find(s, o->of) < 0)) {
    names_hint(s, o->of, s->nbogies, bogie_name_at, "bogies", hint, sizeof hint);
    return fail(err, FB_PART_OUTPUT, i, "of",
                "no bogie named '%s' (a %s signal measures a bogie)%s", o->of ? o->of : "",
                o->signal, hint);
  }
  if (kind->subject == FB_OUTPUT_OF_BODY && (!o->of || fb_scenario_body_find(s, o->of) < 0)) {
    names_hint(s, o->of, s->nbodies, body_name_at, "bodies", hint, sizeof hint);
    return fail(err, FB_PART_OUTPUT, i, "of",
                "no body named '%s' (a %s signal measures a mounted rigid body)%s",
                o->of ? o->of : "", o->signal, hint);
  }
  if (kind->subject == FB_OUTPUT_OF_MOUNT && (!o->of || fb_scenario_mount_find(s, o->of) < 0)) {
    names_hint(s, o->of, s->nmounts, mount_name_at, "mounts", hint, sizeof hint);
    return fail(err, FB_PART_OUTPUT, i, "of",
                "no mount named '%s' (a %s signal measures a mounted body)%s",
                o->of ? o->of : "", o->signal, hint);
  }
  if (kind->subject == FB_OUTPUT_OF_HULL_POINT && (o->direction < 0 || o->direction > 2))
    return fail(err, FB_PART_OUTPUT, i, "direction",
                "a hull point's direction is 0 (x), 1 (y) or 2 (z) (got %d)", o->direction);
  if (kind->subject == FB_OUTPUT_OF_HULL_POINT &&
      !(isfinite(o->at[0]) && isfinite(o->at[1]) && isfinite(o->at[2])))
    return fail(err, FB_PART_OUTPUT, i, "at", "a hull point's coordinates must be finite");
  return kind->subject == FB_OUTPUT_OF_HULL_STRESS ? check_output_stress(o, i, err) : FB_OK;
}

/* A column of its own: not the time's, not a contact force's. */
static int check_output_name(const fb_scenario *s, size_t i, fb_err *err)
{
  const char *name = s->output[i].name;
  if (!name || !strcmp(name, "t") || !strncmp(name, "contact_force_", 14))
    return fail(err, FB_PART_OUTPUT, i, "name",
                "'%s' is a column of its own (t, contact_force_<CORNER>): give another name",
                name ? name : "");
  for (size_t j = 0; j < i; ++j)
    if (same(s->output[j].name, name))
      return fail(err, FB_PART_OUTPUT, i, "name",
                  "'%s' is output %zu's name already (names are unique)", name, j);
  return FB_OK;
}

static int check_output_figure(const fb_scenario *s, size_t i, fb_err *err)
{
  const fb_output_spec *o = &s->output[i];
  for (size_t j = 0; o->figure && j < i; ++j)
    if (s->output[j].figure == o->figure)
      return fail(err, FB_PART_OUTPUT, i, "figure", "figure %d is output %zu's already",
                  o->figure, j);
  /* Not bounded by t_end: a shorter run shows the part of the window it
   * covers, or the whole run. */
  const double *w = o->window;
  if ((w[0] != 0 || w[1] != 0) && !(w[0] >= 0 && w[0] < w[1]))
    return fail(err, FB_PART_OUTPUT, i, "window",
                "must be [t0, t1] with 0 <= t0 < t1 (got [%.10g, %.10g])", w[0], w[1]);
  return FB_OK;
}

static int check_outputs(const fb_scenario *s, fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < s->noutputs; ++i) {
    rc = check_output_subject(s, i, err);
    if (!rc)
      rc = check_output_name(s, i, err);
    if (!rc)
      rc = check_output_figure(s, i, err);
  }
  return rc;
}

/* ---- Anti-roll bars. */

/* The bar's end member ("left" or "right"), named corner: a corner of s
 * on that side (y > 0 on the left), in *c. */
static int check_bar_end(const fb_scenario *s, size_t i, const char *member, const char *corner,
                         int left, long *c, fb_err *err)
{
  *c = corner ? fb_scenario_corner_find(s, corner) : -1;
  if (*c < 0) {
    char hint[512];
    names_hint(s, corner, s->ncorners, corner_name_at, "corners", hint, sizeof hint);
    return fail(err, FB_PART_ANTIROLL_BAR, i, member, "no corner named '%s'%s",
                corner ? corner : "", hint);
  }
  const double y = s->corner[*c].y;
  if (left ? !(y > 0) : !(y < 0))
    return fail(err, FB_PART_ANTIROLL_BAR, i, member,
                "corner %s is on the %s (y = %.10g m): a bar's %s corner has y %s 0", corner,
                y > 0   ? "left"
                : y < 0 ? "right"
                        : "centre line",
                y, member, left ? ">" : "<");
  return FB_OK;
}

/* Each bar: a unique name, two corners facing each other across the
 * vehicle, each corner under one bar at most (one "travel" port). */
static int check_antiroll_bars(const fb_scenario *s, fb_err *err)
{
  for (size_t i = 0; i < s->nantiroll_bars; ++i) {
    const fb_antiroll_bar *b = &s->antiroll_bar[i];
    if (!b->name)
      return fail(err, FB_PART_ANTIROLL_BAR, i, "name", "has no name");
    for (size_t j = 0; j < i; ++j)
      if (same(b->name, s->antiroll_bar[j].name))
        return fail(err, FB_PART_ANTIROLL_BAR, i, "name",
                    "a second anti-roll bar named %s (bar names are unique)", b->name);
    if (same(b->left, b->right))
      return fail(err, FB_PART_ANTIROLL_BAR, i, "right",
                  "the bar's two ends are one corner, %s: a bar joins a left and a right "
                  "corner",
                  b->right);
    long l = -1, r = -1;
    int rc = check_bar_end(s, i, "left", b->left, 1, &l, err);
    if (!rc)
      rc = check_bar_end(s, i, "right", b->right, 0, &r, err);
    if (rc)
      return rc;
    for (size_t j = 0; j < i; ++j) {
      const fb_antiroll_bar *o = &s->antiroll_bar[j];
      const char *shared = same(b->left, o->left) || same(b->left, o->right)     ? b->left
                           : same(b->right, o->left) || same(b->right, o->right) ? b->right
                                                                                 : NULL;
      if (shared)
        return fail(err, FB_PART_ANTIROLL_BAR, i, shared == b->left ? "left" : "right",
                    "corner %s is under bar %s already (a corner carries one bar)", shared,
                    o->name);
    }
  }
  return FB_OK;
}

/* ---- Bogies. */

/* The bogie's end member ("front" or "rear") names a corner, in *c, of
 * no other bogie before it, under no anti-roll bar and without stops (its
 * wheel has no travel of its own). */
static int check_bogie_end(const fb_scenario *s, size_t i, const char *member,
                           const char *corner, long *c, fb_err *err)
{
  *c = corner ? fb_scenario_corner_find(s, corner) : -1;
  if (*c < 0) {
    char hint[512];
    names_hint(s, corner, s->ncorners, corner_name_at, "corners", hint, sizeof hint);
    return fail(err, FB_PART_BOGIE, i, member, "no corner named '%s'%s", corner ? corner : "",
                hint);
  }
  for (size_t j = 0; j < i; ++j)
    if (same(corner, s->bogie[j].front) || same(corner, s->bogie[j].rear))
      return fail(err, FB_PART_BOGIE, i, member,
                  "corner %s is on bogie %s already (a wheel rides on one bogie)", corner,
                  s->bogie[j].name);
  for (size_t j = 0; j < s->nantiroll_bars; ++j)
    if (same(corner, s->antiroll_bar[j].left) || same(corner, s->antiroll_bar[j].right))
      return fail(err, FB_PART_BOGIE, i, member,
                  "corner %s carries anti-roll bar %s: a bogie's wheel has no suspension "
                  "travel of its own for a bar",
                  corner, s->antiroll_bar[j].name);
  if (fb_stops_any(&s->corner[*c].stops))
    return fail(err, FB_PART_BOGIE, i, member,
                "corner %s has bump or rebound stops: a bogie's wheel rides on the beam, "
                "with no suspension travel of its own for them",
                corner);
  return FB_OK;
}

/* Each bogie: a unique name, two corners on one side (one y), the front
 * one ahead of the rear one, the pivot strictly between them. */
static int check_bogies(const fb_scenario *s, fb_err *err)
{
  for (size_t i = 0; i < s->nbogies; ++i) {
    const fb_bogie *b = &s->bogie[i];
    if (!b->name)
      return fail(err, FB_PART_BOGIE, i, "name", "has no name");
    for (size_t j = 0; j < i; ++j)
      if (same(b->name, s->bogie[j].name))
        return fail(err, FB_PART_BOGIE, i, "name",
                    "a second bogie named %s (bogie names are unique)", b->name);
    if (same(b->front, b->rear))
      return fail(err, FB_PART_BOGIE, i, "rear",
                  "the bogie's two ends are one corner, %s: a bogie carries two wheels",
                  b->rear);
    long f = -1, r = -1;
    int rc = check_bogie_end(s, i, "front", b->front, &f, err);
    if (!rc)
      rc = check_bogie_end(s, i, "rear", b->rear, &r, err);
    if (rc)
      return rc;
    const fb_corner_params *cf = &s->corner[f], *cr = &s->corner[r];
    if (fabs(cf->y - cr->y) > SAME_POINT)
      return fail(err, FB_PART_BOGIE, i, "rear",
                  "corner %s is at y = %.10g m, the front corner %s at y = %.10g m: a bogie's "
                  "wheels are on one line along the vehicle",
                  cr->name, cr->y, cf->name, cf->y);
    if (!(cr->x < b->pivot_x && b->pivot_x < cf->x))
      return fail(err, FB_PART_BOGIE, i, "pivot_x",
                  "must lie between the rear corner %s's x = %.10g m and the front corner %s's "
                  "x = %.10g m (got %.10g)",
                  cr->name, cr->x, cf->name, cf->x, b->pivot_x);
  }
  return FB_OK;
}

int fb_scenario_check(const fb_scenario *s, fb_err *err)
{
  if (!s)
    return fb_err_set(err, FB_EINVAL, "fb_scenario_check: the scenario is NULL");
  if (s->ncorners < 3 || !s->corner)
    return fail(err, FB_PART_VEHICLE, 0, "corner", "at least 3 corners are needed (got %zu)",
                s->ncorners);
  int rc = check_names(s, err);
  if (!rc)
    rc = check_values(s, err);
  if (!rc)
    rc = check_hull(s, err);
  if (!rc)
    rc = check_load(s, err);
  if (!rc)
    rc = check_dampers(s, err);
  if (!rc)
    rc = check_springs(s, err);
  if (!rc)
    rc = check_stops(s, err);
  if (!rc)
    rc = check_points(s, err);
  if (!rc)
    rc = check_point_masses(s, err);
  if (!rc)
    rc = check_bodies(s, err);
  if (!rc)
    rc = check_tires(s, err);
  if (!rc)
    rc = check_envelopes(s, err);
  if (!rc)
    rc = check_road(s, err);
  if (!rc)
    rc = check_simulation(s, err);
  if (!rc)
    rc = check_pictured_modes(s, err);
  if (!rc)
    rc = check_road_timing(s, err);
  if (!rc)
    rc = check_fe_hull(s, err);
  if (!rc)
    rc = check_antiroll_bars(s, err);
  if (!rc)
    rc = check_bogies(s, err);
  if (!rc) /* a corner's signals are its bogie's wheel's, if it has one */
    rc = check_outputs(s, err);
  return rc;
}
