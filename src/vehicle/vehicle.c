/* SPDX-License-Identifier: BSD-3-Clause */
/* A realised vehicle (fb_vehicle, flexbond/vehicle.h): one system of a
 * scenario built once, its hull (hull_model.c), graph, diagram and probes,
 * and what is done with it: runs, the modes of its linearisation and of
 * its structure, its descriptor form, the error of its modal basis.
 *
 * The analyses that need a vehicle other than the one simulated (no
 * dampers, a flat road, tires held in contact, a richer basis) build a
 * diagram of their own, cheaply, around a fragment of the same realised
 * hull: no hull is assembled and no eigenproblem solved twice. */
#include "flexbond/vehicle.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

struct fb_vehicle {
  const fb_scenario *s; /* borrowed */
  fb_system sys;
  fb_vehicle_opts opts;
  vehicle_hull *hull; /* System 2 */
  int hull_borrowed;  /* an estimator's: the hull is the vehicle's it estimates */
  int enriched;       /* the hull's fragment in the estimator's basis */
  fb_bg *graph;
  fb_probe_spec *probes;
  size_t nprobes;
  fb_bd *bd;
  size_t ncoords; /* the hull's coordinates (the motion's first probe) */
  /* The inputs a stepper holds (FB_VEHICLE_NINPUTS values, borrowed from
   * it), which the load reads; NULL: the load is the constant weight. */
  const double *held;
  fb_vehicle_work work;
};

int vehicle_threads(const fb_vehicle *v)
{
  return v->opts.threads;
}

void fb_vehicle_opts_default(fb_vehicle_opts *o)
{
  *o = (fb_vehicle_opts){0, 0, {NULL, NULL}, 1, 0, 0};
}

void fb_vehicle_free(fb_vehicle **v)
{
  if (!v || !*v)
    return;
  fb_bd_free(&(*v)->bd);
  fb_vehicle_probes_free(&(*v)->probes, (*v)->nprobes);
  fb_bg_free(&(*v)->graph);
  if (!(*v)->hull_borrowed)
    vehicle_hull_free(&(*v)->hull);
  free(*v);
  *v = NULL;
}

fb_system fb_vehicle_system(const fb_vehicle *v)
{
  return v->sys;
}

const fb_scenario *fb_vehicle_scenario(const fb_vehicle *v)
{
  return v->s;
}

fb_vehicle_work fb_vehicle_work_of(const fb_vehicle *v)
{
  return v->work;
}

const fb_hull_basis *fb_vehicle_hull_basis(const fb_vehicle *v)
{
  return v->hull ? vehicle_hull_basis(v->hull) : NULL;
}

size_t fb_vehicle_hull_free_modes(const fb_vehicle *v, const double **freq_hz, size_t *nrigid)
{
  const fb_hull_basis *b = fb_vehicle_hull_basis(v);
  *freq_hz = b ? b->free_hz : NULL;
  *nrigid = b ? b->nfree_rigid : 0;
  return b ? b->nfree : 0;
}

fb_bg *fb_vehicle_bond_graph(fb_vehicle *v)
{
  return v->graph;
}

const fb_probe_spec *fb_vehicle_probe_specs(const fb_vehicle *v, size_t *nprobes)
{
  *nprobes = v->nprobes;
  return v->probes;
}

const fb_fe_hull *fb_vehicle_fe_hull_of(const fb_vehicle *v)
{
  return v->hull ? vehicle_hull_fe(v->hull) : NULL;
}

const double *vehicle_coordinate_basis(const fb_vehicle *v, size_t *nb)
{
  *nb = 0;
  return v->hull ? vehicle_hull_coordinate_basis(v->hull, nb) : NULL;
}

/* ---- Diagrams. */

/* The hull fragment of v's system for scenario s (v's own or a variant of
 * it): System 1's rigid body, or System 2's realised hull in its
 * coordinates (enriched: the estimator's). */
static int hull_fragment(fb_vehicle *v, const fb_scenario *s, int enriched, fb_hull **out,
                         fb_err *err)
{
  if (v->sys != FB_SYSTEM_FLEXIBLE)
    return fb_vehicle_rigid_hull(s, out, err);
  return vehicle_hull_fragment(s, v->hull, enriched || v->enriched, out, err);
}

/* A diagram of s around v's hull, probing the outputs and extras:
 * *graph, *probes and *bd new. */
static int build_diagram(fb_vehicle *v, const fb_scenario *s, int enriched, unsigned extras,
                         fb_bg **graph, fb_probe_spec **probes, size_t *nprobes, fb_bd **bd,
                         fb_err *err)
{
  *bd = NULL;
  fb_hull *hull = NULL;
  int rc = hull_fragment(v, s, enriched, &hull, err);
  if (!rc)
    rc = vehicle_graph_around(s, &hull, extras, &v->ncoords, graph, probes, nprobes, err);
  if (!rc && v->held)
    rc = vehicle_hold_inputs(s, &v->opts, v->held, *graph, err);
  if (!rc)
    rc = fb_bd_build(*graph, *probes, *nprobes, bd, err);
  if (!rc)
    v->work.diagrams++;
  if (rc) {
    fb_vehicle_probes_free(probes, *nprobes);
    *nprobes = 0;
    fb_bg_free(graph);
  }
  return rc;
}

/* A variant's diagram with the outputs' probes alone (graph and probes
 * kept by the caller for the variant's life). */
typedef struct variant {
  fb_scenario *s;
  fb_bg *graph;
  fb_probe_spec *probes;
  size_t nprobes;
  fb_bd *bd;
} variant;

static void variant_free(variant *x)
{
  fb_bd_free(&x->bd);
  fb_vehicle_probes_free(&x->probes, x->nprobes);
  fb_bg_free(&x->graph);
  fb_scenario_free(&x->s);
}

/* v's scenario changed by change (NULL: none), and its diagram. */
static int variant_new(fb_vehicle *v, void (*change)(fb_scenario *),
                       void (*change2)(fb_scenario *), int enriched, variant *x, fb_err *err)
{
  memset(x, 0, sizeof *x);
  int rc = fb_scenario_clone(v->s, &x->s, err);
  if (!rc && change)
    change(x->s);
  if (!rc && change2)
    change2(x->s);
  if (!rc)
    rc = build_diagram(v, x->s, enriched, 0, &x->graph, &x->probes, &x->nprobes, &x->bd, err);
  if (rc)
    variant_free(x);
  return rc;
}

/* ---- Realisation. */

/* fb_scenario_check of s but for its road, which a vehicle whose road is
 * an input does not drive on: a copy checked on a flat road (the run
 * made as long as that road needs). */
static int check_without_road(const fb_scenario *s, fb_err *err)
{
  fb_scenario *flat = NULL;
  int rc = fb_scenario_clone(s, &flat, err);
  if (!rc) {
    vehicle_flatten_road(flat);
    rc = fb_scenario_check(flat, err);
  }
  fb_scenario_free(&flat);
  return rc;
}

int vehicle_new_held(const fb_scenario *s, fb_system sys, const fb_vehicle_opts *o,
                     const double *held, fb_vehicle **out, fb_err *err)
{
  *out = NULL;
  if (!s)
    return fb_err_set(err, FB_EINVAL, "fb_vehicle_new: the scenario is NULL");
  if (sys != FB_SYSTEM_RIGID && sys != FB_SYSTEM_FLEXIBLE)
    return fb_err_set(err, FB_EINVAL, "fb_vehicle_new: no system %d", (int)sys);
  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  fb_vehicle *v = calloc(1, sizeof *v);
  if (!v)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  v->s = s;
  v->sys = sys;
  v->held = held;
  if (o)
    v->opts = *o;
  else
    fb_vehicle_opts_default(&v->opts);
  if (!v->opts.memory_limit)
    v->opts.memory_limit = FB_VEHICLE_MEMORY_LIMIT;
  int rc = v->opts.road_inputs ? check_without_road(s, err) : fb_scenario_check(s, err);
  if (!rc && sys == FB_SYSTEM_FLEXIBLE)
    rc = vehicle_hull_new(s, &v->opts, &v->work, &v->hull, err);
  const unsigned extras =
      VEHICLE_PROBE_CONTACT | (v->opts.motion ? VEHICLE_PROBE_MOTION : 0) |
      (v->opts.motion == FB_VEHICLE_MOTION_HULL ? VEHICLE_PROBE_HULL_ONLY : 0);
  if (!rc)
    rc = build_diagram(v, s, 0, extras, &v->graph, &v->probes, &v->nprobes, &v->bd, err);
  if (rc) {
    fb_vehicle_free(&v);
    return rc;
  }
  v->work.setup_seconds = fb_seconds_since(&t0);
  *out = v;
  return FB_OK;
}

int fb_vehicle_new(const fb_scenario *s, fb_system sys, const fb_vehicle_opts *o,
                   fb_vehicle **out, fb_err *err)
{
  return vehicle_new_held(s, sys, o, NULL, out, err);
}

fb_bd *vehicle_diagram(fb_vehicle *v)
{
  return v->bd;
}

/* ---- Runs. */

int vehicle_initial_state(fb_vehicle *v, fb_bd *bd, double **x0, fb_err *err)
{
  const size_t n = fb_bd_nstates(bd);
  *x0 = calloc(n + 1, sizeof **x0);
  if (!*x0)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  if (v->s->initial != FB_INITIAL_STATIC)
    return FB_OK;
  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  double *zero = calloc(n + 1, sizeof *zero);
  int rc = zero ? fb_sim_static_state(bd, 0.0, zero, *x0, err)
                : fb_err_set(err, FB_ENOMEM, "out of memory");
  free(zero);
  v->work.static_solves++;
  v->work.static_seconds += fb_seconds_since(&t0);
  return rc;
}

static int integrate(fb_vehicle *v, fb_bd *bd, fb_sim_progress_fn fn, void *ctx,
                     fb_result **out, fb_err *err)
{
  double *x0 = NULL;
  int rc = vehicle_initial_state(v, bd, &x0, err);
  fb_sim_opts o;
  fb_vehicle_sim_opts(v->s, &o);
  o.x0 = x0;
  o.progress = fn;
  o.progress_ctx = ctx;
  if (!rc)
    rc = fb_sim_run(bd, &o, out, err);
  if (!rc)
    v->work.simulations++;
  free(x0);
  return rc;
}

/* The run's motion (*out new) from the columns after the contact forces. */
static int take_motion(fb_vehicle *v, fb_result *res, const double *window,
                       fb_vehicle_motion **out, fb_err *err)
{
  fb_vehicle_motion *m = calloc(1, sizeof *m);
  if (!m)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  m->sys = v->sys;
  m->ncoords = v->ncoords;
  int rc = FB_OK;
  if (v->hull) {
    size_t nb = 0;
    const double *T = vehicle_hull_coordinate_basis(v->hull, &nb);
    const size_t ndof = vehicle_hull_basis(v->hull)->ndof;
    rc = fb_mesh_clone(vehicle_hull_fe(v->hull)->mesh, &m->mesh, err);
    if (!rc && T) {
      m->basis = malloc(ndof * nb * sizeof *m->basis);
      if (m->basis)
        memcpy(m->basis, T, ndof * nb * sizeof *m->basis);
      else
        rc = fb_err_set(err, FB_ENOMEM, "out of memory for the motion's basis");
    }
  }
  if (!rc)
    rc = fb_vehicle_motion_take(v->s, res, 1 + v->s->noutputs + v->s->ncorners, window,
                                v->opts.motion == FB_VEHICLE_MOTION_HULL, m, err);
  if (rc) {
    fb_vehicle_motion_free(&m);
    return rc;
  }
  *out = m;
  return FB_OK;
}

int fb_vehicle_run(fb_vehicle *v, const double *window, fb_sim_progress_fn fn, void *ctx,
                   fb_result **out, fb_vehicle_motion **motion, fb_err *err)
{
  *out = NULL;
  if (motion)
    *motion = NULL;
  if (motion && !v->opts.motion)
    return fb_err_set(err, FB_EINVAL,
                      "fb_vehicle_run: the motion needs a vehicle made with "
                      "fb_vehicle_opts.motion");
  int rc = integrate(v, v->bd, fn, ctx, out, err);
  if (!rc && v->opts.motion)
    rc = motion ? take_motion(v, *out, window, motion, err)
                : fb_result_truncate(*out, 1 + v->s->noutputs + v->s->ncorners, err);
  if (rc)
    fb_result_free(out);
  return rc;
}

int fb_vehicle_basis_reduced(const fb_vehicle *v)
{
  const fb_hull_basis *b = fb_vehicle_hull_basis(v);
  return b && b->coordinates == FB_HULL_MODAL && b->ncoords < b->ndof;
}

int fb_vehicle_new_estimator(fb_vehicle *v, fb_vehicle **out, fb_err *err)
{
  *out = NULL;
  if (!fb_vehicle_basis_reduced(v))
    return fb_err_set(err, FB_EINVAL,
                      "the basis error is estimated for System 2 in reduced modal coordinates");
  fb_vehicle *e = calloc(1, sizeof *e);
  if (!e)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  e->s = v->s;
  e->sys = v->sys;
  e->opts = v->opts;
  e->opts.motion = 0;
  e->hull = v->hull;
  e->hull_borrowed = 1;
  e->enriched = 1;
  /* The same probes as v's run: its results compare column by column. */
  int rc = build_diagram(e, e->s, 1, VEHICLE_PROBE_CONTACT, &e->graph, &e->probes, &e->nprobes,
                         &e->bd, err);
  if (rc) {
    fb_vehicle_free(&e);
    return rc;
  }
  *out = e;
  return FB_OK;
}

int fb_vehicle_basis_error(fb_vehicle *v, const fb_result *r, const double window[2],
                           fb_sim_progress_fn fn, void *ctx, double *est, fb_err *err)
{
  fb_vehicle *e = NULL;
  fb_result *rich = NULL;
  int rc = fb_vehicle_new_estimator(v, &e, err);
  if (!rc)
    rc = fb_vehicle_run(e, NULL, fn, ctx, &rich, NULL, err);
  double *rel = rc ? NULL : malloc(fb_result_ncols(r) * sizeof *rel);
  if (!rc && !rel)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = fb_result_rel_diff(r, rich, window[0], rel, err);
  if (!rc)
    memcpy(est, rel, v->s->noutputs * sizeof *est);
  free(rel);
  fb_result_free(&rich);
  fb_vehicle_free(&e);
  return rc;
}

/* ---- Linear analyses. */

int fb_vehicle_linear_modes(fb_vehicle *v, int undamped, fb_mode **modes, size_t *nmodes,
                            size_t *nstatic, fb_err *err)
{
  *modes = NULL;
  *nmodes = *nstatic = 0;
  variant x;
  int rc = variant_new(v, undamped ? vehicle_remove_damping : NULL, vehicle_flatten_road, 0, &x,
                       err);
  if (!rc) {
    rc = vehicle_linear_modes(x.graph, x.bd, v->opts.memory_limit, modes, nmodes, nstatic, err);
    v->work.static_solves++;
    v->work.linear_eigensolves += rc == FB_OK;
    variant_free(&x);
  }
  return rc;
}

int fb_vehicle_linearise(fb_vehicle *v, fb_descriptor **out, fb_err *err)
{
  *out = NULL;
  variant x;
  int rc = variant_new(v, fb_scenario_tires_in_contact, NULL, 0, &x, err);
  if (!rc) {
    rc = fb_vehicle_diagram_descriptor(x.bd, out, err);
    variant_free(&x);
  }
  return rc;
}

int fb_vehicle_structural_modes(fb_vehicle *v, size_t nmodes, int exact, fb_mode_set **out,
                                fb_err *err)
{
  *out = NULL;
  if (!v->hull)
    return fb_err_set(err, FB_EINVAL, "modes with shapes are System 2's");
  return vehicle_hull_structural_modes(v->s, v->hull, nmodes, exact, &v->work, out, err);
}

/* ---- For a single use. */

int fb_vehicle_simulate_progress(const fb_scenario *s, fb_system sys, fb_sim_progress_fn fn,
                                 void *ctx, fb_result **out, fb_err *err)
{
  *out = NULL;
  fb_vehicle *v = NULL;
  int rc = fb_vehicle_new(s, sys, NULL, &v, err);
  if (!rc)
    rc = fb_vehicle_run(v, NULL, fn, ctx, out, NULL, err);
  fb_vehicle_free(&v);
  return rc;
}

int fb_vehicle_simulate(const fb_scenario *s, fb_system sys, fb_result **out, fb_err *err)
{
  return fb_vehicle_simulate_progress(s, sys, NULL, NULL, out, err);
}

int fb_vehicle_modes(const fb_scenario *s, fb_system sys, int undamped, fb_mode **modes,
                     size_t *nmodes, size_t *nstatic, fb_err *err)
{
  *modes = NULL;
  *nmodes = *nstatic = 0;
  fb_vehicle *v = NULL;
  int rc = fb_vehicle_new(s, sys, NULL, &v, err);
  if (!rc)
    rc = fb_vehicle_linear_modes(v, undamped, modes, nmodes, nstatic, err);
  fb_vehicle_free(&v);
  return rc;
}

int fb_vehicle_descriptor(const fb_scenario *s, fb_system sys, fb_descriptor **out, fb_err *err)
{
  *out = NULL;
  fb_vehicle *v = NULL;
  int rc = fb_vehicle_new(s, sys, NULL, &v, err);
  if (!rc)
    rc = fb_vehicle_linearise(v, out, err);
  fb_vehicle_free(&v);
  return rc;
}

/* The graph and probes of s's system sys with extras, its hull realised
 * for the purpose: v's fields, which the caller takes. */
static int graph_once(const fb_scenario *s, fb_system sys, unsigned extras, fb_vehicle *v,
                      fb_err *err)
{
  v->s = s;
  v->sys = sys;
  int rc = fb_scenario_check(s, err);
  if (!rc && sys == FB_SYSTEM_FLEXIBLE)
    rc = vehicle_hull_new(s, NULL, &v->work, &v->hull, err);
  fb_hull *hull = NULL;
  if (!rc)
    rc = hull_fragment(v, s, 0, &hull, err);
  if (!rc)
    rc = vehicle_graph_around(s, &hull, extras, NULL, &v->graph, &v->probes, &v->nprobes, err);
  vehicle_hull_free(&v->hull);
  return rc;
}

int fb_vehicle_graph(const fb_scenario *s, fb_system sys, fb_bg **graph, fb_probe_spec **probes,
                     size_t *nprobes, fb_err *err)
{
  fb_vehicle v = {0};
  int rc = graph_once(s, sys, VEHICLE_PROBE_CONTACT, &v, err);
  *graph = rc ? NULL : v.graph;
  *probes = rc ? NULL : v.probes;
  *nprobes = rc ? 0 : v.nprobes;
  if (rc) {
    fb_vehicle_probes_free(&v.probes, v.nprobes);
    fb_bg_free(&v.graph);
  }
  return rc;
}

int fb_vehicle_build(const fb_scenario *s, fb_system sys, fb_bg **graph, fb_bd **bd,
                     fb_err *err)
{
  *graph = NULL;
  *bd = NULL;
  fb_vehicle v = {0};
  int rc = graph_once(s, sys, 0, &v, err);
  if (!rc)
    rc = fb_bd_build(v.graph, v.probes, v.nprobes, bd, err);
  fb_vehicle_probes_free(&v.probes, v.nprobes);
  if (rc)
    fb_bg_free(&v.graph);
  *graph = v.graph;
  return rc;
}
