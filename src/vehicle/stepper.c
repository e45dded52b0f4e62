/* SPDX-License-Identifier: BSD-3-Clause */
/* A vehicle simulation the caller steps (fb_vehicle_stepper,
 * flexbond/vehicle.h): a realised vehicle whose load reads the inputs
 * the stepper holds, and an fb_sim_stepper over its diagram.
 *
 * An input is a time function that returns the value held now
 * (fb_tfun_new_callback over the stepper's array): between two changes
 * it is constant, and a change happens at the stepper's current time,
 * where the integration restarts (fb_sim_stepper_reset), so the hold is
 * exact, with no smoothing for the integrator to resolve. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "vehicle/vehicle_internal.h"

enum { INPUT_LOAD_FORCE = 0 };

static const char *const input_names[FB_VEHICLE_NINPUTS] = {"load_force"};

const char *fb_vehicle_input_name(size_t i)
{
  return i < FB_VEHICLE_NINPUTS ? input_names[i] : NULL;
}

long fb_vehicle_input_find(const char *name)
{
  for (size_t i = 0; name && i < FB_VEHICLE_NINPUTS; ++i)
    if (strcmp(input_names[i], name) == 0)
      return (long)i;
  return -1;
}

/* ---- The load as an input. */

/* One load point's vertical force: its share of the weight (constant)
 * and of the held load force. */
typedef struct load_point_force {
  double weight;       /* N, up positive (negative) */
  double share;        /* of the held force: 1 / nload */
  const double *force; /* the held load force, N, up positive */
} load_point_force;

static double load_point_value(double t, void *ctx)
{
  (void)t;
  const load_point_force *f = ctx;
  return f->weight + f->share * *f->force;
}

/* The load's source ("load.weights", fb_vehicle_load: one component per
 * load point, -total_weight / nload each) made to add its share of the
 * held load force. */
int vehicle_hold_inputs(const fb_scenario *s, const double *held, fb_bg *graph, fb_err *err)
{
  const load_point_force each = {-s->total_weight / (double)s->nload, 1.0 / (double)s->nload,
                                 &held[INPUT_LOAD_FORCE]};
  int rc = FB_OK;
  for (size_t k = 0; !rc && k < s->nload; ++k) {
    fb_tfun *f = NULL;
    rc = fb_tfun_new_callback_copy(load_point_value, &each, sizeof each, 0, NULL, &f, err);
    if (!rc)
      rc = fb_bg_set_source(graph, "load.weights", k, &f, err);
  }
  return rc;
}

/* ---- The stepper. */

struct fb_vehicle_stepper {
  fb_scenario *s; /* owned copy */
  fb_system sys;
  fb_vehicle_opts opts;
  fb_vehicle *v;
  fb_sim_stepper *sim;
  double held[FB_VEHICLE_NINPUTS]; /* the inputs, read by v's load */
};

/* A stepper over v's diagram (v realised from s) from (t0, x0) (*sim
 * new); x0 NULL: the scenario's initial state at 0. */
static int start(const fb_scenario *s, fb_vehicle *v, double t0, const double *x0,
                 fb_sim_stepper **sim, fb_err *err)
{
  *sim = NULL;
  double *initial = NULL;
  int rc = x0 ? FB_OK : vehicle_initial_state(v, vehicle_diagram(v), &initial, err);
  fb_sim_opts o;
  fb_vehicle_sim_opts(s, &o);
  o.t_start = t0;
  o.x0 = x0 ? x0 : initial;
  if (!rc)
    rc = fb_sim_stepper_create(vehicle_diagram(v), &o, sim, err);
  free(initial);
  return rc;
}

int fb_vehicle_stepper_new(const fb_scenario *s, fb_system sys, const fb_vehicle_opts *o,
                           fb_vehicle_stepper **out, fb_err *err)
{
  *out = NULL;
  if (!s)
    return fb_err_set(err, FB_EINVAL, "fb_vehicle_stepper_new: the scenario is NULL");
  fb_vehicle_stepper *st = calloc(1, sizeof *st);
  if (!st)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  st->sys = sys;
  if (o)
    st->opts = *o;
  else
    fb_vehicle_opts_default(&st->opts);
  st->opts.motion = 0; /* the outputs and the contact forces alone */
  int rc = fb_scenario_clone(s, &st->s, err);
  if (!rc)
    rc = vehicle_new_held(st->s, sys, &st->opts, st->held, &st->v, err);
  if (!rc)
    rc = start(st->s, st->v, 0.0, NULL, &st->sim, err);
  if (rc) {
    fb_vehicle_stepper_free(&st);
    return rc;
  }
  *out = st;
  return FB_OK;
}

void fb_vehicle_stepper_free(fb_vehicle_stepper **st)
{
  if (!st || !*st)
    return;
  fb_sim_stepper_free(&(*st)->sim);
  fb_vehicle_free(&(*st)->v);
  fb_scenario_free(&(*st)->s);
  free(*st);
  *st = NULL;
}

int fb_vehicle_stepper_advance(fb_vehicle_stepper *st, double t, fb_err *err)
{
  return fb_sim_stepper_advance(st->sim, t, err);
}

double fb_vehicle_stepper_time(const fb_vehicle_stepper *st)
{
  return fb_sim_stepper_time(st->sim);
}

size_t fb_vehicle_stepper_noutputs(const fb_vehicle_stepper *st)
{
  return fb_bd_noutputs(vehicle_diagram(st->v));
}

const char *fb_vehicle_stepper_output_name(const fb_vehicle_stepper *st, size_t k)
{
  return k < fb_vehicle_stepper_noutputs(st) ? fb_bd_output_name(vehicle_diagram(st->v), k)
                                             : NULL;
}

const char *fb_vehicle_stepper_output_unit(const fb_vehicle_stepper *st, size_t k)
{
  return k < fb_vehicle_stepper_noutputs(st) ? fb_bd_output_unit(vehicle_diagram(st->v), k)
                                             : NULL;
}

long fb_vehicle_stepper_output_find(const fb_vehicle_stepper *st, const char *name)
{
  for (size_t k = 0; name && k < fb_vehicle_stepper_noutputs(st); ++k)
    if (strcmp(fb_vehicle_stepper_output_name(st, k), name) == 0)
      return (long)k;
  return -1;
}

int fb_vehicle_stepper_outputs(fb_vehicle_stepper *st, double *y, fb_err *err)
{
  return fb_sim_stepper_outputs(st->sim, y, err);
}

int fb_vehicle_stepper_set_input(fb_vehicle_stepper *st, const char *name, double value,
                                 fb_err *err)
{
  const long i = fb_vehicle_input_find(name);
  int rc = FB_OK;
  if (i < 0)
    rc = fb_err_set(err, FB_EINVAL, "no input '%s' (the inputs: %s)", name ? name : "(null)",
                    input_names[0]);
  else if (!isfinite(value))
    rc = fb_err_set(err, FB_EINVAL, "input %s: must be finite, got %g", name, value);
  if (rc) {
    fb_err_set_key(err, "%s", name ? name : "");
    return rc;
  }
  st->held[i] = value;
  /* The diagram reads the new value from now on: a restart here. */
  return fb_sim_stepper_reset(st->sim, err);
}

double fb_vehicle_stepper_input(const fb_vehicle_stepper *st, size_t i)
{
  return i < FB_VEHICLE_NINPUTS ? st->held[i] : NAN;
}

/* FB_OK if diagram b has a's states, by name and in order. */
static int same_states(const fb_bd *a, const fb_bd *b, fb_err *err)
{
  const size_t na = fb_bd_nstates(a), nb = fb_bd_nstates(b);
  for (size_t i = 0; i < na && i < nb; ++i)
    if (strcmp(fb_bd_state_name(a, i), fb_bd_state_name(b, i)) != 0)
      return fb_err_set(err, FB_EINVAL,
                        "the new scenario's vehicle has other states: state %zu is %s, was %s; "
                        "a change that adds or removes states needs a new simulation",
                        i + 1, fb_bd_state_name(b, i), fb_bd_state_name(a, i));
  if (na != nb)
    return fb_err_set(err, FB_EINVAL,
                      "the new scenario's vehicle has %zu states, the simulation %zu; a change "
                      "that adds or removes states needs a new simulation",
                      nb, na);
  return FB_OK;
}

int fb_vehicle_stepper_set_scenario(fb_vehicle_stepper *st, const fb_scenario *s, fb_err *err)
{
  if (!s)
    return fb_err_set(err, FB_EINVAL, "fb_vehicle_stepper_set_scenario: the scenario is NULL");
  const double t = fb_sim_stepper_time(st->sim);
  if (!(s->t_end > t)) {
    fb_err_set(err, FB_EINVAL, "the new scenario ends at t_end = %g s, not after now (%g s)",
               s->t_end, t);
    fb_err_set_key(err, "t_end");
    return FB_EINVAL;
  }
  fb_scenario *copy = NULL;
  fb_vehicle *v = NULL;
  fb_sim_stepper *sim = NULL;
  int rc = fb_scenario_clone(s, &copy, err);
  if (!rc)
    rc = vehicle_new_held(copy, st->sys, &st->opts, st->held, &v, err);
  if (!rc)
    rc = same_states(vehicle_diagram(st->v), vehicle_diagram(v), err);
  if (!rc)
    rc = start(copy, v, t, fb_sim_stepper_state(st->sim), &sim, err);
  if (rc) {
    fb_vehicle_free(&v);
    fb_scenario_free(&copy);
    return rc;
  }
  fb_sim_stepper_free(&st->sim);
  fb_vehicle_free(&st->v);
  fb_scenario_free(&st->s);
  st->s = copy;
  st->v = v;
  st->sim = sim;
  return FB_OK;
}

const fb_scenario *fb_vehicle_stepper_scenario(const fb_vehicle_stepper *st)
{
  return st->s;
}
