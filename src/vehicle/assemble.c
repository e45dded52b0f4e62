/* SPDX-License-Identifier: BSD-3-Clause */
/* Assembly of the vehicle from its fragments, the paper's seven outputs,
 * and the simulation protocol (see flexbond/vehicle.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* Adopts a fragment built by a constructor under instance name inst. */
static int adopt(fb_bg *bg, int rc, fb_bg **frag, const char *inst, fb_err *err)
{
  if (rc) {
    fb_err_prefix(err, "%s: ", inst);
    return rc;
  }
  return fb_bg_adopt(bg, frag, inst, err);
}

/* The weight each tire carries at rest if all carry the same: the load
 * (hull, payload and mounted bodies: load.total_weight) and the wheels
 * themselves, shared by the corners (N). */
static double mean_tire_load(const fb_scenario *s)
{
  double weight = s->total_weight;
  for (size_t c = 0; c < s->ncorners; ++c)
    weight += s->corner[c].wheel_mass * s->gravity;
  return s->ncorners ? weight / (double)s->ncorners : 0.0;
}

fb_corner_params vehicle_corner_loaded(const fb_scenario *s, size_t c)
{
  fb_corner_params corner = s->corner[c];
  corner.tire_static_deflection = mean_tire_load(s) / corner.tire_k;
  return corner;
}

/* The one place the fragments' instance names are made: a mount's is its
 * name ("driver"), a corner's "susp_" and its name (so "LF" may be both
 * a corner and a mount's name without a clash), the hull's "hull", an
 * anti-roll bar's "arb_" and its name, a bogie's "bogie_" and its name. */
long vehicle_corner_bogie(const fb_scenario *s, size_t c, int *rear)
{
  const long b = fb_scenario_corner_bogie(s, c);
  if (b >= 0 && rear)
    *rear = strcmp(s->bogie[b].front, s->corner[c].name) != 0;
  return b;
}

char *vehicle_bogie_instance(const fb_bogie *b)
{
  return fb_strdup_printf("bogie_%s", b->name);
}

/* A corner's instance: its own fragment's, or, for a bogie's wheel, that
 * wheel's inside the bogie's ("bogie_<name>.front"). */
static char *corner_instance(const fb_scenario *s, size_t c)
{
  int rear = 0;
  const long b = vehicle_corner_bogie(s, c, &rear);
  if (b < 0)
    return fb_strdup_printf("susp_%s", s->corner[c].name);
  return fb_strdup_printf("bogie_%s.%s", s->bogie[b].name, rear ? "rear" : "front");
}

char *vehicle_instance(const fb_scenario *s, fb_output_subject subject, size_t i)
{
  switch (subject) {
  case FB_OUTPUT_OF_CORNER: return corner_instance(s, i);
  case FB_OUTPUT_OF_MOUNT: return fb_strdup(s->mount[i].name);
  case FB_OUTPUT_OF_BOGIE: return vehicle_bogie_instance(&s->bogie[i]);
  default: return fb_strdup("hull");
  }
}

char *vehicle_antiroll_bar_instance(const fb_antiroll_bar *b)
{
  return fb_strdup_printf("arb_%s", b->name);
}

/* 1 if an anti-roll bar ends at the corner named name. */
static int corner_has_bar(const fb_scenario *s, const char *name)
{
  for (size_t i = 0; i < s->nantiroll_bars; ++i)
    if (!strcmp(s->antiroll_bar[i].left, name) || !strcmp(s->antiroll_bar[i].right, name))
      return 1;
  return 0;
}

char *vehicle_target(const fb_scenario *s, fb_output_subject subject, size_t i,
                     const char *local)
{
  char *inst = vehicle_instance(s, subject, i);
  char *full = inst ? fb_strdup_printf("%s.%s", inst, local) : NULL;
  free(inst);
  return full;
}

/* Adopts the mounts' and corners' fragments, under their instance names. */
static int add_bodies(const fb_scenario *s, fb_bg *bg, fb_err *err)
{
  fb_bg *frag = NULL;
  int rc = FB_OK;
  for (size_t b = 0; !rc && b < s->nmounts; ++b) {
    char *inst = vehicle_instance(s, FB_OUTPUT_OF_MOUNT, b);
    rc = inst ? adopt(bg, fb_vehicle_mount(&s->mount[b], s->gravity, &frag, err), &frag, inst,
                      err)
              : fb_err_set(err, FB_ENOMEM, "out of memory");
    free(inst);
    fb_bg_free(&frag);
  }
  for (size_t c = 0; !rc && c < s->ncorners; ++c) {
    if (vehicle_corner_bogie(s, c, NULL) >= 0)
      continue; /* the bogie's fragment holds its wheel */
    char *inst = vehicle_instance(s, FB_OUTPUT_OF_CORNER, c);
    const fb_corner_params corner = vehicle_corner_loaded(s, c);
    const int coupled = corner_has_bar(s, corner.name);
    rc = inst ? adopt(bg,
                      coupled ? fb_vehicle_corner_coupled(&corner, s->gravity, &frag, err)
                              : fb_vehicle_corner(&corner, s->gravity, &frag, err),
                      &frag, inst, err)
              : fb_err_set(err, FB_ENOMEM, "out of memory");
    free(inst);
    fb_bg_free(&frag);
  }
  return rc;
}

/* Bogie i's fragment, its wheels the corners it names (fb_scenario_check
 * found them, the pivot between). */
static int adopt_bogie(const fb_scenario *s, fb_bg *bg, size_t i, const char *inst, fb_err *err)
{
  const fb_bogie *b = &s->bogie[i];
  const long f = fb_scenario_corner_find(s, b->front), r = fb_scenario_corner_find(s, b->rear);
  if (f < 0 || r < 0)
    return fb_err_set(err, FB_EINVAL, "no corner named '%s'", f < 0 ? b->front : b->rear);
  const fb_corner_params front = vehicle_corner_loaded(s, (size_t)f);
  const fb_corner_params rear = vehicle_corner_loaded(s, (size_t)r);
  const fb_bogie_params p = {b->name,      front.x - b->pivot_x, b->pivot_x - rear.x,
                             b->beam_mass, b->beam_inertia,      b->spring_k,
                             b->damper_c};
  fb_bg *frag = NULL;
  int rc =
      adopt(bg, fb_vehicle_bogie(&p, &front, &rear, s->gravity, &frag, err), &frag, inst, err);
  fb_bg_free(&frag);
  return rc;
}

/* The saddle of bogie i: its pivot's force F on the hull at the two
 * corners' attachment points, as a lever between them takes it, b/(a+b) F
 * at the front one and a/(a+b) F at the rear one (the pivot's velocity
 * on the hull is their average with those weights, exact for a rigid
 * hull, the pivot on the line between them). The 0-junction
 * "saddle_<name>" and one TF of modulus 1/weight to each attachment. */
static int add_saddle(const fb_scenario *s, fb_bg *bg, size_t i, const char *inst, fb_err *err)
{
  const fb_bogie *b = &s->bogie[i];
  const long end[2] = {fb_scenario_corner_find(s, b->front),
                       fb_scenario_corner_find(s, b->rear)};
  const double a = s->corner[end[0]].x - b->pivot_x, bb = b->pivot_x - s->corner[end[1]].x;
  const double weight[2] = {bb / (a + bb), a / (a + bb)};
  char *saddle = fb_strdup_printf("saddle_%s", b->name);
  char *pivot = fb_strdup_printf("%s.hull", inst);
  int rc = saddle && pivot ? fb_bg_add_junction(bg, saddle, FB_BG_J0, 1, err)
                           : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = fb_bg_connect(bg, NULL, pivot, saddle, err);
  static const char *const side[2] = {"front", "rear"};
  for (int k = 0; !rc && k < 2; ++k) {
    char *tf = fb_strdup_printf("%s_%s", saddle, side[k]);
    char *in = fb_strdup_printf("%s.1", tf ? tf : "");
    char *outp = fb_strdup_printf("%s.2", tf ? tf : "");
    char *to = fb_strdup_printf("attach.%ld", end[k] + 1);
    rc = tf && in && outp && to ? fb_bg_add_tf(bg, tf, FB_BG_TF, 1, 1.0 / weight[k], err)
                                : fb_err_set(err, FB_ENOMEM, "out of memory");
    if (!rc)
      rc = fb_bg_connect(bg, NULL, saddle, in, err);
    if (!rc)
      rc = fb_bg_connect(bg, NULL, outp, to, err);
    free(tf);
    free(in);
    free(outp);
    free(to);
  }
  free(saddle);
  free(pivot);
  return rc;
}

/* The bogies' fragments and saddles (after the hull's attachment
 * composite, before the roads' bonds to their tires). */
static int add_bogies(const fb_scenario *s, fb_bg *bg, fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < s->nbogies; ++i) {
    char *inst = vehicle_bogie_instance(&s->bogie[i]);
    rc = inst ? adopt_bogie(s, bg, i, inst, err) : fb_err_set(err, FB_ENOMEM, "out of memory");
    if (!rc)
      rc = add_saddle(s, bg, i, inst, err);
    if (rc && err && !err->part.kind)
      fb_err_set_part(err, FB_PART_BOGIE, i, FB_ERR_NO_ELEMENT, "");
    free(inst);
  }
  return rc;
}

/* Bond from the corner named corner's "travel" to the bar's port. */
static int connect_bar_end(const fb_scenario *s, fb_bg *bg, const char *bar, const char *corner,
                           const char *port, fb_err *err)
{
  const long c = fb_scenario_corner_find(s, corner);
  if (c < 0)
    return fb_err_set(err, FB_EINVAL, "no corner named '%s'", corner);
  char *from = vehicle_target(s, FB_OUTPUT_OF_CORNER, (size_t)c, "travel");
  char *to = fb_strdup_printf("%s.%s", bar, port);
  int rc = from && to ? fb_bg_connect(bg, NULL, from, to, err)
                      : fb_err_set(err, FB_ENOMEM, "out of memory");
  free(from);
  free(to);
  return rc;
}

/* The anti-roll bars' fragments and their bonds to their corners. */
static int add_antiroll_bars(const fb_scenario *s, fb_bg *bg, fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < s->nantiroll_bars; ++i) {
    const fb_antiroll_bar *b = &s->antiroll_bar[i];
    fb_bg *frag = NULL;
    char *inst = vehicle_antiroll_bar_instance(b);
    rc = inst ? adopt(bg, fb_vehicle_antiroll_bar(b, &frag, err), &frag, inst, err)
              : fb_err_set(err, FB_ENOMEM, "out of memory");
    if (!rc)
      rc = connect_bar_end(s, bg, inst, b->left, "left", err);
    if (!rc)
      rc = connect_bar_end(s, bg, inst, b->right, "right", err);
    if (rc && err && !err->part.kind)
      fb_err_set_part(err, FB_PART_ANTIROLL_BAR, i, FB_ERR_NO_ELEMENT, "");
    free(inst);
    fb_bg_free(&frag);
  }
  return rc;
}

/* Bond from the road's port of corner c to its bogie's tire. */
static int connect_bogie_road(const fb_scenario *s, fb_bg *bg, size_t c, size_t bogie, int rear,
                              fb_err *err)
{
  char *road = fb_strdup_printf("road.%s", s->corner[c].name);
  char *tire =
      fb_strdup_printf("bogie_%s.road_%s", s->bogie[bogie].name, rear ? "rear" : "front");
  int rc = road && tire ? fb_bg_connect(bg, NULL, road, tire, err)
                        : fb_err_set(err, FB_ENOMEM, "out of memory");
  free(road);
  free(tire);
  return rc;
}

/* Adopts the mounted rigid bodies' fragments under their names, and
 * bonds each bushing's port "parent_<j>" to its parent's (the hull's or
 * a body's) port "bushing_<k>". */
static int add_rigid_bodies(const fb_scenario *s, fb_bg *bg, fb_err *err)
{
  int rc = FB_OK;
  for (size_t b = 0; !rc && b < s->nbodies; ++b) {
    fb_bg *frag = NULL;
    rc = adopt(bg, fb_vehicle_body(s, b, &frag, err), &frag, s->body[b].name, err);
    fb_bg_free(&frag);
  }
  size_t b = 0, j = 0;
  for (size_t k = 0; !rc && fb_scenario_bushing_at(s, k, &b, &j); ++k) {
    const fb_body *body = &s->body[b];
    char *from = fb_strdup_printf("%s.parent_%zu", body->name, j);
    char *to = fb_strdup_printf("%s.bushing_%zu", body->parent ? body->parent : "hull", k);
    rc = from && to ? fb_bg_connect(bg, NULL, from, to, err)
                    : fb_err_set(err, FB_ENOMEM, "out of memory");
    free(from);
    free(to);
  }
  return rc;
}

/* Bond from attachment a's fragment port "hull" into "attach.<a+1>", and
 * for a corner from the road's port to its wheel's. */
static int connect_attachment(const fb_scenario *s, fb_bg *bg, size_t a, fb_err *err)
{
  int rear = 0;
  const long bogie = a < s->ncorners ? vehicle_corner_bogie(s, a, &rear) : -1;
  if (bogie >= 0) /* its hull bond is the saddle's; its road is the bogie's */
    return connect_bogie_road(s, bg, a, (size_t)bogie, rear, err);
  const int corner = a < s->ncorners;
  const fb_output_subject subject = corner ? FB_OUTPUT_OF_CORNER : FB_OUTPUT_OF_MOUNT;
  const size_t i = corner ? a : a - s->ncorners;
  char *from = vehicle_target(s, subject, i, "hull");
  char *to = fb_strdup_printf("attach.%zu", a + 1);
  char *road = corner ? fb_strdup_printf("road.%s", s->corner[a].name) : NULL;
  char *wheel = corner ? vehicle_target(s, subject, i, "road") : NULL;
  int rc = from && to && (!corner || (road && wheel))
               ? fb_bg_connect(bg, NULL, from, to, err)
               : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc && corner)
    rc = fb_bg_connect(bg, NULL, road, wheel, err);
  free(from);
  free(to);
  free(road);
  free(wheel);
  return rc;
}

/* The fragments around the hull and the bonds between them. */
static int add_subsystems(const fb_scenario *s, fb_bg *bg, fb_err *err)
{
  fb_bg *frag = NULL;
  int rc = add_bodies(s, bg, err);
  if (!rc)
    rc = add_antiroll_bars(s, bg, err);
  if (!rc)
    rc = add_rigid_bodies(s, bg, err);
  if (!rc)
    rc = adopt(bg, fb_vehicle_road(s, &frag, err), &frag, "road", err);
  if (!rc)
    rc = adopt(bg, fb_vehicle_load(s, &frag, err), &frag, "load", err);
  /* The horizontal line of Fig. 5: one scalar bond per attachment point
   * stacked into the hull's multibond. */
  const size_t na = fb_scenario_nattach(s);
  size_t *ones = malloc(na * sizeof *ones);
  if (!rc && !ones)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t a = 0; !rc && a < na; ++a)
    ones[a] = 1;
  if (!rc)
    rc = fb_bg_add_composite(bg, "attach", na, ones, err);
  free(ones);
  if (!rc)
    rc = add_bogies(s, bg, err);
  for (size_t a = 0; !rc && a < na; ++a)
    rc = connect_attachment(s, bg, a, err);
  if (!rc)
    rc = fb_bg_connect(bg, "b_attach", "attach.whole", "hull.attach", err);
  if (!rc)
    rc = fb_bg_connect(bg, "b_load", "load.load", "hull.load", err);
  return rc;
}

void fb_vehicle_probes_free(fb_probe_spec **probes, size_t nprobes)
{
  if (!probes || !*probes)
    return;
  for (size_t i = 0; i < nprobes; ++i) {
    free((char *)(*probes)[i].name);
    free((char *)(*probes)[i].target);
    free((double *)(*probes)[i].weights);
  }
  free(*probes);
  *probes = NULL;
}

/* The scenario's outputs as probes on the assembled graph (targets and
 * weights owned). An error is about its output (fb_err.part). */
static int make_probes(const fb_scenario *s, const fb_hull *hull, fb_probe_spec **out,
                       fb_err *err)
{
  fb_probe_spec *p = calloc(s->noutputs ? s->noutputs : 1, sizeof *p);
  if (!p)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  int rc = FB_OK;
  for (size_t k = 0; !rc && k < s->noutputs; ++k) {
    rc = fb_vehicle_output_probe(s, hull, k, &p[k], err);
    if (rc && err && !err->part.kind)
      fb_err_set_part(err, FB_PART_OUTPUT, k, FB_ERR_NO_ELEMENT, "");
  }
  if (rc) {
    fb_vehicle_probes_free(&p, s->noutputs);
    return rc;
  }
  *out = p;
  return FB_OK;
}

/* fb_name_fn over the graph's bonds. */
static const char *bond_name_at(const void *ctx, size_t i)
{
  return fb_bg_bond_name(ctx, i);
}

/* Output k's bond, of dim components: a scalar bond without a
 * component, a multibond with one of its components (a multibond's
 * effort is a vector, which one output column cannot hold). */
static int check_bond_dim(const fb_output_spec *o, size_t k, size_t dim, fb_err *err)
{
  if (dim != 1 && !o->component)
    return fb_err_set(err, FB_EINVAL,
                      "bond '%s' is a multibond of %zu components: an output records one of "
                      "them, chosen with component (1 to %zu)",
                      o->bond, dim, dim),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, k, bond)), FB_EINVAL;
  if (dim == 1 && o->component)
    return fb_err_set(err, FB_EINVAL, "bond '%s' is a scalar bond: it has no component",
                      o->bond),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, k, component)), FB_EINVAL;
  if (o->component < 0 || (size_t)o->component > dim)
    return fb_err_set(err, FB_EINVAL, "bond '%s' has components 1 to %zu (got %ld)", o->bond,
                      dim, o->component),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, k, component)), FB_EINVAL;
  return FB_OK;
}

/* Output k's bond is not in bg: the closest name bg has. */
static int no_such_bond(const fb_output_spec *o, size_t k, const fb_bg *bg, fb_err *err)
{
  const char *near = fb_suggest(o->bond, fb_bg_nbonds(bg), bond_name_at, bg);
  return fb_err_set(err, FB_EINVAL, "no bond named '%s' in the assembled graph%s%s%s", o->bond,
                    near ? " (did you mean '" : "", near ? near : "", near ? "'?)" : ""),
         fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, k, bond)), FB_EINVAL;
}

/* Each bond output's bond is a bond of the assembled graph, with its
 * component where it is a multibond: said before any run, at the
 * output's key. */
static int check_bond_outputs(const fb_scenario *s, const fb_bg *bg, fb_err *err)
{
  int rc = FB_OK;
  for (size_t k = 0; !rc && k < s->noutputs; ++k) {
    const fb_output_spec *o = &s->output[k];
    if (!o->bond)
      continue;
    const long b = fb_bg_find_bond(bg, o->bond);
    rc = b < 0 ? no_such_bond(o, k, bg, err)
               : check_bond_dim(o, k, fb_bg_bond_dim(bg, (size_t)b), err);
  }
  return rc;
}

/* The vehicle's graph around hull (its graph taken over): the hull's
 * instance, the other fragments' and their bonds (*out new). */
static int assemble_graph(const fb_scenario *s, fb_hull *hull, fb_bg **out, fb_err *err)
{
  fb_bg *bg = NULL;
  int rc = fb_bg_new(s->name ? s->name : "vehicle", &bg, err);
  if (!rc)
    rc = fb_bg_adopt(bg, &hull->graph, "hull", err);
  if (!rc)
    rc = add_subsystems(s, bg, err);
  if (rc)
    fb_bg_free(&bg);
  *out = bg;
  return rc;
}

int fb_vehicle_assemble(const fb_scenario *s, fb_hull **hullp, fb_bg **out,
                        fb_probe_spec **probes, size_t *nprobes, fb_err *err)
{
  *out = NULL;
  *probes = NULL;
  *nprobes = 0;
  fb_hull *hull = *hullp;
  *hullp = NULL;
  fb_bg *bg = NULL;
  /* A hull that carries no bodies (a program's own) refuses them rather
   * than leave them out of the vehicle. */
  int rc = s->nbodies && !hull->carries_bodies
               ? fb_err_set(err, FB_EINVAL,
                            "this hull does not carry mounted rigid bodies (body %s)",
                            s->body[0].name)
               : FB_OK;
  if (rc)
    fb_err_set_part(err, FB_PART_AT(FB_PART_BODY, 0, name));
  if (!rc)
    rc = make_probes(s, hull, probes, err);
  if (!rc)
    rc = assemble_graph(s, hull, &bg, err);
  if (!rc)
    rc = check_bond_outputs(s, bg, err);
  fb_hull_free(&hull);
  if (rc) {
    fb_vehicle_probes_free(probes, s->noutputs);
    fb_bg_free(&bg);
    return rc;
  }
  *out = bg;
  *nprobes = s->noutputs;
  return FB_OK;
}

/* 1 if name is a bond of the finite-element hull's fragment in the
 * assembly (its instance "hull"): those are multibonds of dimensions the
 * realised hull sets (its coordinates, its points). */
static int flexible_hull_bond(const char *name)
{
  int found = 0;
  for (size_t i = 0; !found && vehicle_flexible_hull_bond(i); ++i) {
    char *full = fb_strdup_printf("hull.%s", vehicle_flexible_hull_bond(i));
    found = full && !strcmp(full, name);
    free(full);
  }
  return found;
}

/* Output k's bond when the scenario is loaded, against System 1's
 * assembled graph bg, or System 2's hull: one of its multibonds with a
 * component (whose range the realised hull checks). */
static int check_bond_at_load(const fb_scenario *s, size_t k, const fb_bg *bg, fb_err *err)
{
  const fb_output_spec *o = &s->output[k];
  const long b = fb_bg_find_bond(bg, o->bond);
  if (b >= 0)
    return check_bond_dim(o, k, fb_bg_bond_dim(bg, (size_t)b), err);
  if (!s->has_fe_hull || !flexible_hull_bond(o->bond))
    return no_such_bond(o, k, bg, err);
  if (!o->component)
    return fb_err_set(err, FB_EINVAL,
                      "bond '%s' is a multibond of System 2's hull: an output records one of "
                      "its components, chosen with component",
                      o->bond),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, k, bond)), FB_EINVAL;
  return FB_OK;
}

int fb_vehicle_outputs_check(const fb_scenario *s, fb_err *err)
{
  int rc = vehicle_hull_points_check(s, err);
  size_t nbond = 0;
  for (size_t k = 0; k < s->noutputs; ++k)
    nbond += s->output[k].bond != NULL;
  if (rc || !nbond)
    return rc;
  /* System 1's graph is cheap to assemble: the vehicle's fragments and
   * the rigid hull's, whose bonds a rigid hull's outputs may name. */
  fb_hull *hull = NULL;
  fb_bg *bg = NULL;
  rc = fb_vehicle_rigid_hull(s, &hull, err);
  if (!rc)
    rc = assemble_graph(s, hull, &bg, err);
  fb_hull_free(&hull);
  for (size_t k = 0; !rc && k < s->noutputs; ++k)
    if (s->output[k].bond)
      rc = check_bond_at_load(s, k, bg, err);
  fb_bg_free(&bg);
  return rc;
}

/* Every tire's normal reaction (compression positive), contact_force_<CORNER>,
 * into cp[0 .. ncorners) (names and targets new): the corner's
 * tire_force. */
static int contact_probes(const fb_scenario *s, fb_probe_spec *cp, fb_err *err)
{
  const vehicle_signal *tire = vehicle_fragment_signal(FB_OUTPUT_OF_CORNER, "tire_force");
  if (!tire)
    return fb_err_set(err, FB_EMODEL, "the corner offers no tire_force");
  for (size_t c = 0; c < s->ncorners; ++c) {
    cp[c] = (fb_probe_spec){NULL, tire->kind, NULL, -1, tire->integrate, 1.0, "N", NULL, 0};
    cp[c].name = fb_strdup_printf("contact_force_%s", s->corner[c].name);
    cp[c].target = vehicle_target(s, FB_OUTPUT_OF_CORNER, c, tire->target);
    if (!cp[c].name || !cp[c].target)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  return FB_OK;
}

/* The probes after the outputs: the tires' contact forces, then the
 * motion's. */
static int extra_probes(const fb_scenario *s, const fb_hull *hull, unsigned extras,
                        fb_probe_spec *p, fb_err *err)
{
  int rc = extras & VEHICLE_PROBE_CONTACT ? contact_probes(s, p, err) : FB_OK;
  if (!rc && (extras & VEHICLE_PROBE_MOTION))
    rc = fb_vehicle_motion_probes(s, hull, (extras & VEHICLE_PROBE_HULL_ONLY) != 0,
                                  p + (extras & VEHICLE_PROBE_CONTACT ? s->ncorners : 0), err);
  return rc;
}

int vehicle_graph_around(const fb_scenario *s, fb_hull **hullp, unsigned extras,
                         size_t *ncoords, fb_bg **graph, fb_probe_spec **probes,
                         size_t *nprobes, fb_err *err)
{
  *graph = NULL;
  *probes = NULL;
  *nprobes = 0;
  fb_hull *hull = *hullp;
  fb_probe_spec *outputs = NULL;
  size_t nout = 0;
  const size_t nextra =
      (extras & VEHICLE_PROBE_CONTACT ? s->ncorners : 0) +
      (extras & VEHICLE_PROBE_MOTION
           ? fb_vehicle_motion_nprobes(s, (extras & VEHICLE_PROBE_HULL_ONLY) != 0)
           : 0);
  if (ncoords)
    *ncoords = hull->ntorsion;
  fb_probe_spec *extra = calloc(nextra + 1, sizeof *extra);
  int rc = extra ? extra_probes(s, hull, extras, extra, err)
                 : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = fb_vehicle_assemble(s, hullp, graph, &outputs, &nout, err);
  fb_hull_free(hullp);
  fb_probe_spec *all = rc ? NULL : calloc(nout + nextra + 1, sizeof *all);
  if (!rc && !all)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc) {
    /* The strings move to all. */
    memcpy(all, outputs, nout * sizeof *all);
    memcpy(all + nout, extra, nextra * sizeof *all);
    free(outputs);
    free(extra);
    outputs = extra = NULL;
    *probes = all;
    *nprobes = nout + nextra;
  }
  fb_vehicle_probes_free(&outputs, nout);
  fb_vehicle_probes_free(&extra, nextra);
  if (rc)
    fb_bg_free(graph);
  return rc;
}

void fb_vehicle_sim_opts(const fb_scenario *s, fb_sim_opts *o)
{
  fb_sim_opts_default(o);
  o->t_end = s->t_end;
  o->rtol = s->rtol;
  o->atol = s->atol;
  o->max_step = s->max_step;
  o->max_steps = s->max_steps;
  o->stability_limit_detection = s->stability_limit_detection;
  o->sample_rate = s->sample_rate;
}
