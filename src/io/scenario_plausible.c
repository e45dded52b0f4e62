/* SPDX-License-Identifier: BSD-3-Clause */
/* Plausibility of a loaded scenario (sc_plausibility): values that are
 * legal but that a real vehicle almost never has, which are far more
 * often a slip (a unit, a digit) than a design. Each is a warning located
 * at its value ("FILE:LINE:COL: KEY: ..."), kept in the scenario; nothing
 * is refused here (the command line's --strict refuses, docs/errors.md).
 *
 * Two kinds: one value outside what its key's table entry declares
 * plausible (scenario_schema.c, PLAUSIBLE), and the consequence of several
 * values together, which no one value shows: the static deflections the
 * weight gives the tires and springs, the masses the total weight must
 * hold (and not hold many times over), and a coupling the hull's mesh
 * never uses. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/hull_source.h"
#include "flexbond/vehicle.h"

#include "core/util.h"
#include "io/scenario_internal.h"

/* A static tire deflection above this (m) is no tire's: a truck tire of
 * 0.5 m radius deflects some 3 to 5 cm under its load. */
#define SC_TIRE_DEFLECTION_MAX 0.25
/* A static suspension deflection (at the wheel) above this (m) is no
 * road vehicle's: their whole travel is some 0.1 to 0.6 m. */
#define SC_SPRING_DEFLECTION_MAX 1.0

typedef struct sc_warn_ctx {
  fb_scenario *s;
  int rc;
  fb_err *err;
} sc_warn_ctx;

/* Keeps w (an unlocated warning with its logical key) in s, located; a
 * warning already kept (the same value, inherited by several corners) is
 * not kept twice. */
static int sc_keep(fb_scenario *s, fb_err *w, fb_err *err)
{
  fb_scenario_locate(s, w);
  sc_source *src = sc_source_of(s);
  if (!src)
    return fb_err_set(err, FB_EINVAL, "a warning about a scenario the loader did not make");
  for (size_t i = 0; i < src->nwarnings; ++i)
    if (!strcmp(src->warning[i].msg, w->msg))
      return FB_OK;
  fb_err *grown = realloc(src->warning, (src->nwarnings + 1) * sizeof *grown);
  if (!grown)
    return fb_err_set(err, FB_ENOMEM, "out of memory keeping a warning");
  src->warning = grown;
  src->warning[src->nwarnings++] = *w;
  return FB_OK;
}

static int sc_warn_value(const sch_value *v, void *ctx)
{
  sc_warn_ctx *c = ctx;
  fb_err w;
  fb_err_clear(&w);
  if (sch_check_plausible(v, &w))
    c->rc = sc_keep(c->s, &w, c->err);
  return c->rc;
}

/* The static deflections of corner k's tire and spring under an equal
 * share of the weight (the static solution shares it by lever arms; an
 * equal share is what a reader checks a data sheet with). */
static int sc_warn_deflections(fb_scenario *s, size_t k, fb_err *err)
{
  const fb_corner_params *c = &s->corner[k];
  const double share = s->total_weight / (double)s->ncorners;
  const double tire = (share + c->wheel_mass * s->gravity) / c->tire_k;
  const double wheel_rate = c->spring_k * c->motion_ratio * c->motion_ratio;
  const double spring = share / wheel_rate;
  fb_err w;
  fb_err_clear(&w);
  if (tire > SC_TIRE_DEFLECTION_MAX) {
    fb_err_set(&w, FB_EINVAL,
               "%.10g N/m is implausible: the static tire deflection would be %.3g m (%.4g N "
               "on the tire), more than the %g m of any tire",
               c->tire_k, tire, share + c->wheel_mass * s->gravity, SC_TIRE_DEFLECTION_MAX);
    fb_err_set_key(&w, "corners.%s.wheel.tire_k", c->name);
    return sc_keep(s, &w, err);
  }
  if (spring > SC_SPRING_DEFLECTION_MAX) {
    fb_err_set(&w, FB_EINVAL,
               "%.10g N/m is implausible: the static suspension deflection would be %.3g m "
               "(%.4g N of the total weight's share over a wheel rate of %.4g N/m), more "
               "than the %g m of any suspension's travel",
               c->spring_k, spring, share, wheel_rate, SC_SPRING_DEFLECTION_MAX);
    fb_err_set_key(&w, "corners.%s.spring_k", c->name);
    return sc_keep(s, &w, err);
  }
  return FB_OK;
}

/* load.total_weight is the hull's weight (its declared masses included)
 * plus the payload (docs/scenario-format.md): below the masses it must
 * include, some of the vehicle is counted twice or a unit slipped. */
static int sc_warn_masses(fb_scenario *s, fb_err *err)
{
  const double total = s->total_weight / s->gravity;
  const double declared = s->hull_mass + fb_scenario_point_masses_total(s);
  if (!(declared > total))
    return FB_OK;
  fb_err w;
  fb_err_clear(&w);
  fb_err_set(&w, FB_EINVAL,
             "%.10g N is implausible: %.4g kg, less than the %.4g kg of the hull (%.4g kg) "
             "and its masses (%.4g kg) that it includes",
             s->total_weight, total, declared, s->hull_mass, fb_scenario_point_masses_total(s));
  fb_err_set_key(&w, "load.total_weight");
  return sc_keep(s, &w, err);
}

/* A payload above this multiple of the hull's own masses is no road
 * vehicle's: trucks carry up to some 2 to 3 times their structure, the
 * paper's vehicle 1.9 times its hull; 10 times is what a weight given
 * twice times g (or in the wrong unit) makes of it. */
#define SC_PAYLOAD_RATIO_MAX 10.0

/* load.total_weight far above the masses it includes: what is left for
 * the payload would be many times the vehicle. */
static int sc_warn_payload(fb_scenario *s, fb_err *err)
{
  const double total = s->total_weight / s->gravity;
  const double declared = s->hull_mass + fb_scenario_point_masses_total(s);
  if (!(total - declared > SC_PAYLOAD_RATIO_MAX * declared))
    return FB_OK;
  fb_err w;
  fb_err_clear(&w);
  fb_err_set(&w, FB_EINVAL,
             "%.10g N is implausible: %.4g kg, which leaves %.4g kg of payload, more than %g "
             "times the %.4g kg of the hull (%.4g kg) and its masses (%.4g kg); trucks "
             "carry some 2 to 3 times their structure",
             s->total_weight, total, total - declared, SC_PAYLOAD_RATIO_MAX, declared,
             s->hull_mass, fb_scenario_point_masses_total(s));
  fb_err_set_key(&w, "load.total_weight");
  return sc_keep(s, &w, err);
}

/* A coupling where the hull's source puts a node at every point: each
 * point meets its own node, and the coupling is never used. */
static int sc_warn_coupling(fb_scenario *s, fb_err *err)
{
  if (!s->has_fe_hull || s->coupling == FB_COUPLING_NONE ||
      !fb_scenario_hull_source(s)->nodes_at_points)
    return FB_OK;
  fb_err w;
  fb_err_clear(&w);
  fb_err_set(&w, FB_EINVAL,
             "changes nothing: the hull's source, %s, puts a node at every attachment point, "
             "which each point "
             "meets without a coupling (leave hull.mesh.coupling out)",
             fb_scenario_hull_source(s)->name);
  fb_err_set_key(&w, "hull.mesh.coupling");
  return sc_keep(s, &w, err);
}

/* A body's bushing on one node of the finite-element hull: its force
 * bends the plate at a point, a local mode no real mount has (a mount
 * spreads its load over a flange). The plate's point stiffness there
 * (fb_fe_hull_point_stiffness: a static solve of the hull held at its
 * suspension points) in series with the bushing's vertical stiffness,
 * under the body's whole mass, gives that mode's frequency, which the
 * warning names. */
static int sc_warn_single_nodes(fb_scenario *s, fb_err *err)
{
  int named = 0;
  for (size_t b = 0; b < s->nbodies && !named; ++b)
    for (size_t j = 0; j < s->body[b].nbushings; ++j)
      named |= !s->body[b].parent && s->body[b].bushing[j].node_set != NULL;
  if (!named || !s->has_fe_hull)
    return FB_OK;
  fb_fe_hull *h = NULL;
  int rc = fb_vehicle_fe_hull(s, &h, err);
  for (size_t i = 0; !rc && i < h->nbushings; ++i) {
    const size_t node = h->bushing_single_node[i];
    size_t b = 0, j = 0;
    if (node == (size_t)-1 || !fb_scenario_bushing_at(s, h->bushing_index[i], &b, &j))
      continue;
    double kp = 0.0;
    rc = fb_fe_hull_point_stiffness(h, s->ncorners, node, &kp, err);
    if (rc)
      break;
    const fb_body *body = &s->body[b];
    const double kz = body->bushing[j].k[14], ks = kz > 0 ? 1.0 / (1.0 / kp + 1.0 / kz) : kp;
    const double f = sqrt(ks / body->mass) / (2.0 * 3.14159265358979323846);
    fb_err w;
    fb_err_clear(&w);
    fb_err_set(&w, FB_EINVAL,
               "%s hangs body %s on the single node %ld of the hull: the plate's point "
               "stiffness there is %.3g N/m (a static solve with the hull held at its "
               "suspension points), which in series with the bushing's %.3g N/m under the "
               "body's %.4g kg makes a local mode at %.3g Hz that a real mount, spread over "
               "its flange, does not have; couple it to several nodes",
               body->bushing[j].node_set, body->name, fb_mesh_node_id(h->mesh, node), kp, kz,
               body->mass, f);
    fb_err_set_key(&w, "bodies.%s.bushings[%zu].node_set", body->name, j);
    rc = sc_keep(s, &w, err);
  }
  fb_fe_hull_free(&h);
  return rc;
}

/* 1 if a warning about the value with logical key key is kept. */
static int sc_warned(const fb_scenario *s, const char *key)
{
  const sc_source *src = sc_source_of(s);
  for (size_t i = 0; src && i < src->nwarnings; ++i)
    if (!strcmp(src->warning[i].key, key))
      return 1;
  return 0;
}

int sc_plausible_values(fb_scenario *s, fb_err *err)
{
  sc_schema *sc = NULL;
  int rc = sc_schema_of(s, &sc, err);
  if (rc)
    return rc;
  sc_warn_ctx c = {s, FB_OK, err};
  sch_each(sc_schema_table(sc), s, sc_warn_value, &c);
  sc_schema_release(&sc);
  return c.rc;
}

int sc_plausible_rules(fb_scenario *s, fb_err *err)
{
  int rc = sc_warn_coupling(s, err);
  if (rc == FB_OK)
    rc = sc_warn_single_nodes(s, err);
  /* The rules between values start from the total weight: when it is
   * itself implausible, they would only repeat that warning elsewhere. */
  if (rc || sc_warned(s, "load.total_weight"))
    return rc;
  rc = sc_warn_masses(s, err);
  if (rc == FB_OK && !sc_warned(s, "load.total_weight"))
    rc = sc_warn_payload(s, err);
  if (rc || sc_warned(s, "load.total_weight"))
    return rc;
  for (size_t k = 0; rc == FB_OK && k < s->ncorners; ++k)
    rc = sc_warn_deflections(s, k, err);
  return rc;
}

size_t fb_scenario_nwarnings(const fb_scenario *s)
{
  const sc_source *src = sc_source_of(s);
  return src ? src->nwarnings : 0;
}

const fb_err *fb_scenario_warning(const fb_scenario *s, size_t i)
{
  const sc_source *src = sc_source_of(s);
  return src && i < src->nwarnings ? &src->warning[i] : NULL;
}
