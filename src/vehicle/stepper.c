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

#include "core/util.h"
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

/* ---- The inputs' layout in the held array: the load force, then per
 * corner the road's height and rate (fb_vehicle_opts.road_inputs). */

static size_t road_z_index(size_t c)
{
  return FB_VEHICLE_NINPUTS + 2 * c;
}

static size_t road_zdot_index(size_t c)
{
  return FB_VEHICLE_NINPUTS + 2 * c + 1;
}

static size_t held_count(const fb_scenario *s, const fb_vehicle_opts *o)
{
  return FB_VEHICLE_NINPUTS + (o->road_inputs ? 2 * s->ncorners : 0);
}

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

/* A held value as a time function's. */
static double held_value(double t, void *ctx)
{
  (void)t;
  return **(const double *const *)ctx;
}

/* The road's sources ("road.v_<CORNER>", fb_vehicle_road: the road's
 * vertical velocity under the wheel) made to read the held rates. */
static int hold_road(const fb_scenario *s, const double *held, fb_bg *graph, fb_err *err)
{
  int rc = FB_OK;
  for (size_t c = 0; !rc && c < s->ncorners; ++c) {
    const double *rate = &held[road_zdot_index(c)];
    char *name = fb_strdup_printf("road.v_%s", s->corner[c].name);
    fb_tfun *f = NULL;
    rc = name ? fb_tfun_new_callback_copy(held_value, &rate, sizeof rate, 0, NULL, &f, err)
              : fb_err_set(err, FB_ENOMEM, "out of memory");
    if (!rc)
      rc = fb_bg_set_source(graph, name, 0, &f, err);
    free(name);
  }
  return rc;
}

/* The load's source ("load.weights", fb_vehicle_load: one component per
 * load point, -total_weight / nload each) made to add its share of the
 * held load force, and with road inputs the road's sources to read the
 * held rates. */
int vehicle_hold_inputs(const fb_scenario *s, const fb_vehicle_opts *o, const double *held,
                        fb_bg *graph, fb_err *err)
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
  if (!rc && o->road_inputs)
    rc = hold_road(s, held, graph, err);
  return rc;
}

/* ---- The stepper. */

struct fb_vehicle_stepper {
  fb_scenario *s; /* owned copy */
  fb_system sys;
  fb_vehicle_opts opts;
  fb_vehicle *v;
  fb_sim_stepper *sim;
  size_t ninputs;
  double *held;     /* ninputs: the inputs, read by v's load and road */
  double *road_t;   /* per corner with road inputs: when its height was set, s */
  char **name;      /* ninputs input names */
  double *coupling; /* road inputs: nstates x ncorners, fb_vehicle_stepper_road_coupling */
  double *work;     /* 2 nstates + 1 */
};

/* B of fb_vehicle_stepper_road_coupling for v's diagram at (t, x): each
 * road rate's effect on the displacement states' rates, which is
 * kinematic (a flow junction's sum), so one difference is exact. The
 * momenta's share (through a tire damper) is a force, not a
 * displacement, and stays out. */
static int road_coupling(fb_vehicle_stepper *st, double t, const double *x, fb_err *err)
{
  fb_bd *bd = vehicle_diagram(st->v);
  const size_t n = fb_bd_nstates(bd), nc = st->s->ncorners;
  double *b = calloc(n * nc + 1, sizeof *b);
  double *base = st->work, *moved = st->work + n;
  if (!b)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the road's coupling");
  int rc = fb_bd_rhs(bd, t, x, base);
  for (size_t c = 0; !rc && c < nc; ++c) {
    double *rate = &st->held[road_zdot_index(c)];
    const double was = *rate;
    *rate = was + 1.0;
    rc = fb_bd_rhs(bd, t, x, moved);
    *rate = was;
    for (size_t i = 0; !rc && i < n; ++i)
      if (fb_bd_state_kind(bd, i) == FB_STATE_DISPLACEMENT)
        b[c * n + i] = moved[i] - base[i];
  }
  if (rc) {
    free(b);
    return fb_err_set(err, FB_ESOLVER,
                      "the road's coupling: the diagram failed at t = %g s: %s", t,
                      fb_bd_last_error(bd));
  }
  free(st->coupling);
  st->coupling = b;
  return FB_OK;
}

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

/* The input names and the held values' arrays for s. */
static int make_inputs(fb_vehicle_stepper *st, fb_err *err)
{
  st->ninputs = held_count(st->s, &st->opts);
  st->held = calloc(st->ninputs, sizeof *st->held);
  st->road_t = calloc(st->s->ncorners + 1, sizeof *st->road_t);
  st->name = calloc(st->ninputs, sizeof *st->name);
  if (!st->held || !st->road_t || !st->name)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the inputs");
  for (size_t i = 0; i < FB_VEHICLE_NINPUTS; ++i)
    st->name[i] = fb_strdup(input_names[i]);
  for (size_t c = 0; st->opts.road_inputs && c < st->s->ncorners; ++c) {
    st->name[road_z_index(c)] = fb_strdup_printf("road_z_%s", st->s->corner[c].name);
    st->name[road_zdot_index(c)] = fb_strdup_printf("road_zdot_%s", st->s->corner[c].name);
  }
  for (size_t i = 0; i < st->ninputs; ++i)
    if (!st->name[i])
      return fb_err_set(err, FB_ENOMEM, "out of memory for the inputs");
  return FB_OK;
}

/* The work array and, with road inputs, the coupling of the current
 * vehicle at the stepper's time and state. */
static int prepare(fb_vehicle_stepper *st, fb_err *err)
{
  const size_t n = fb_sim_stepper_nstates(st->sim);
  free(st->work);
  if (!(st->work = calloc(2 * n + 1, sizeof *st->work)))
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!st->opts.road_inputs || !n)
    return FB_OK;
  return road_coupling(st, fb_sim_stepper_time(st->sim), fb_sim_stepper_state(st->sim), err);
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
    rc = make_inputs(st, err);
  if (!rc)
    rc = vehicle_new_held(st->s, sys, &st->opts, st->held, &st->v, err);
  if (!rc)
    rc = start(st->s, st->v, 0.0, NULL, &st->sim, err);
  if (!rc)
    rc = prepare(st, err);
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
  fb_vehicle_stepper *p = *st;
  fb_sim_stepper_free(&p->sim);
  fb_vehicle_free(&p->v);
  for (size_t i = 0; p->name && i < p->ninputs; ++i)
    free(p->name[i]);
  free(p->name);
  free(p->held);
  free(p->road_t);
  free(p->coupling);
  free(p->work);
  fb_scenario_free(&p->s);
  free(p);
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

size_t fb_vehicle_stepper_ninputs(const fb_vehicle_stepper *st)
{
  return st->ninputs;
}

const char *fb_vehicle_stepper_input_name(const fb_vehicle_stepper *st, size_t i)
{
  return i < st->ninputs ? st->name[i] : NULL;
}

const char *fb_vehicle_stepper_input_unit(const fb_vehicle_stepper *st, size_t i)
{
  if (i >= st->ninputs)
    return NULL;
  if (i < FB_VEHICLE_NINPUTS)
    return "N";
  return (i - FB_VEHICLE_NINPUTS) % 2 ? "m/s" : "m";
}

long fb_vehicle_stepper_input_find(const fb_vehicle_stepper *st, const char *name)
{
  for (size_t i = 0; name && i < st->ninputs; ++i)
    if (strcmp(st->name[i], name) == 0)
      return (long)i;
  return -1;
}

double fb_vehicle_stepper_input(const fb_vehicle_stepper *st, size_t i)
{
  return i < st->ninputs ? st->held[i] : NAN;
}

/* The road's height under corner c's wheel at time t, as the model has
 * it: set at road_t, rising at the held rate since. */
static double road_height(const fb_vehicle_stepper *st, size_t c, double t)
{
  return st->held[road_z_index(c)] + st->held[road_zdot_index(c)] * (t - st->road_t[c]);
}

int fb_vehicle_stepper_set_inputs(fb_vehicle_stepper *st, const double *u, fb_err *err)
{
  for (size_t i = 0; i < st->ninputs; ++i)
    if (!isfinite(u[i])) {
      fb_err_set(err, FB_EINVAL, "input %s: must be finite, got %g", st->name[i], u[i]);
      fb_err_set_key(err, "%s", st->name[i]);
      return FB_EINVAL;
    }
  const double t = fb_sim_stepper_time(st->sim);
  const size_t n = fb_sim_stepper_nstates(st->sim);
  double *x = st->work;
  if (n)
    memcpy(x, fb_sim_stepper_state(st->sim), n * sizeof *x);
  int changed = 0, moved = 0;
  for (size_t c = 0; st->opts.road_inputs && c < st->s->ncorners; ++c) {
    /* A height other than the road's own moves the tire's deflection. */
    const double jump = u[road_z_index(c)] - road_height(st, c, t);
    for (size_t i = 0; jump != 0.0 && i < n; ++i)
      x[i] += st->coupling[c * n + i] * jump;
    moved |= jump != 0.0;
    st->road_t[c] = t;
  }
  for (size_t i = 0; i < st->ninputs; ++i) {
    changed |= st->held[i] != u[i];
    st->held[i] = u[i];
  }
  /* The diagram reads the new values from now on: a restart here. */
  if (moved)
    return fb_sim_stepper_set_state(st->sim, t, x, err);
  return changed ? fb_sim_stepper_reset(st->sim, err) : FB_OK;
}

int fb_vehicle_stepper_set_input(fb_vehicle_stepper *st, const char *name, double value,
                                 fb_err *err)
{
  const long i = fb_vehicle_stepper_input_find(st, name);
  if (i < 0) {
    fb_err_set(err, FB_EINVAL, "no input '%s' (the inputs: %s%s)", name ? name : "(null)",
               input_names[0],
               st->opts.road_inputs ? ", road_z_<CORNER>, road_zdot_<CORNER>" : "");
    fb_err_set_key(err, "%s", name ? name : "");
    return FB_EINVAL;
  }
  double *all = malloc(st->ninputs * sizeof *all);
  if (!all)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t k = 0; k < st->ninputs; ++k)
    all[k] = st->held[k];
  /* The road's height set now: the others' heights are where the road is. */
  const double t = fb_sim_stepper_time(st->sim);
  for (size_t c = 0; st->opts.road_inputs && c < st->s->ncorners; ++c)
    all[road_z_index(c)] = road_height(st, c, t);
  all[i] = value;
  const int rc = fb_vehicle_stepper_set_inputs(st, all, err);
  free(all);
  return rc;
}

fb_bd *fb_vehicle_stepper_diagram(fb_vehicle_stepper *st)
{
  return vehicle_diagram(st->v);
}

void fb_vehicle_stepper_hold_inputs(fb_vehicle_stepper *st, const double *u)
{
  memcpy(st->held, u, st->ninputs * sizeof *u);
  const double now = fb_sim_stepper_time(st->sim);
  for (size_t c = 0; st->opts.road_inputs && c < st->s->ncorners; ++c)
    st->road_t[c] = now;
}

const double *fb_vehicle_stepper_road_coupling(const fb_vehicle_stepper *st)
{
  return st->opts.road_inputs ? st->coupling : NULL;
}

size_t fb_vehicle_stepper_nstates(const fb_vehicle_stepper *st)
{
  return fb_sim_stepper_nstates(st->sim);
}

const double *fb_vehicle_stepper_state(const fb_vehicle_stepper *st)
{
  return fb_sim_stepper_state(st->sim);
}

int fb_vehicle_stepper_set_state(fb_vehicle_stepper *st, double t, const double *x, fb_err *err)
{
  /* The road's heights where it is now, then taken as at t. */
  const double now = fb_sim_stepper_time(st->sim);
  for (size_t c = 0; st->opts.road_inputs && c < st->s->ncorners; ++c) {
    st->held[road_z_index(c)] = road_height(st, c, now);
    st->road_t[c] = now;
  }
  const int rc = fb_sim_stepper_set_state(st->sim, t, x, err);
  for (size_t c = 0; !rc && st->opts.road_inputs && c < st->s->ncorners; ++c)
    st->road_t[c] = t;
  return rc;
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
  if (held_count(s, &st->opts) != st->ninputs) {
    fb_err_set(err, FB_EINVAL,
               "the new scenario has %zu corners, the simulation %zu: a change that adds or "
               "removes corners needs a new simulation",
               s->ncorners, st->s->ncorners);
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
  return prepare(st, err);
}

const fb_scenario *fb_vehicle_stepper_scenario(const fb_vehicle_stepper *st)
{
  return st->s;
}
