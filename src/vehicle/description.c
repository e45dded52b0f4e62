/* SPDX-License-Identifier: BSD-3-Clause */
/* A vehicle description's own operations (flexbond/vehicle.h): its road
 * (the type's block, where each wheel runs on it), freeing and deep
 * copies. Where the
 * description came from (a file's origins and warnings) is its maker's,
 * behind fb_scenario_source's ops. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/hull_source.h"
#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* ---- The road's placement: its type places each wheel on its track
 * and says where the road's feature lies along it; seen from the
 * vehicle, the road moves back at speed V, so a wheel starting at s0
 * reaches s at (s - s0) / V. */

/* Corner index corner of s, NULL if there is none. */
static const fb_corner_params *desc_corner(const fb_scenario *s, int corner)
{
  return s && s->road_type && corner >= 0 && (size_t)corner < s->ncorners ? &s->corner[corner]
                                                                          : NULL;
}

fb_road_layout fb_scenario_road_layout(const fb_scenario *s)
{
  const fb_road_layout l = {s->speed, fb_scenario_track_width(s),
                            s->ncorners ? s->corner[0].x : 0.0,
                            s->ncorners ? s->corner[0].y : 0.0};
  return l;
}

double fb_scenario_wheel_start(const fb_scenario *s, int corner)
{
  const fb_corner_params *w = desc_corner(s, corner);
  if (!w)
    return NAN;
  const fb_road_layout l = fb_scenario_road_layout(s);
  return s->road_type->ops->wheel_start(s->road.bytes, &l, w->x, w->y);
}

/* Where the feature lies on the track of corner's wheel (from 0 on, for
 * a type without one). */
static void desc_feature(const fb_scenario *s, const fb_corner_params *w, double *begin,
                         double *end)
{
  *begin = 0.0;
  *end = INFINITY;
  const fb_road_layout l = fb_scenario_road_layout(s);
  if (s->road_type->ops->feature)
    s->road_type->ops->feature(s->road.bytes, &l, w->y > 0.0 ? FB_ROAD_LEFT : FB_ROAD_RIGHT,
                               begin, end);
}

int fb_scenario_converged_density(const fb_scenario *s)
{
  const int density = fb_scenario_hull_density(s);
  return density > 0 && s->hull_converged_density > density ? s->hull_converged_density : 0;
}

void fb_scenario_use_auto_basis(fb_scenario *s)
{
  if (s->hull_modes_kind != FB_HULL_MODES_AUTO || s->hull_coordinates != FB_HULL_MODAL)
    s->hull_cutoff_hz = 0.0;
  s->hull_coordinates = FB_HULL_MODAL;
  s->hull_modes_kind = FB_HULL_MODES_AUTO;
}

/* How far ahead of and behind its centre the corner's tire reads the
 * road, m: its envelope's reach (0 for point contact), by which the tire
 * meets a feature earlier and leaves it later than its centre does. */
static double corner_reach(const fb_scenario *s, int corner)
{
  const fb_corner_params loaded = vehicle_corner_loaded(s, (size_t)corner);
  const fb_envelope_model *m = fb_corner_envelope_model(&loaded);
  const fb_envelope_context ctx = fb_corner_envelope_context(&loaded);
  const double reach = m ? m->ops->reach(loaded.envelope.bytes, &ctx) : 0.0;
  return reach > 0.0 && isfinite(reach) ? reach : 0.0;
}

double fb_scenario_road_entry(const fb_scenario *s, int corner)
{
  const fb_corner_params *w = desc_corner(s, corner);
  if (!w)
    return NAN;
  double begin = 0.0, end = 0.0;
  desc_feature(s, w, &begin, &end);
  return (begin - corner_reach(s, corner) - fb_scenario_wheel_start(s, corner)) / s->speed;
}

double fb_scenario_road_exit(const fb_scenario *s, int corner)
{
  const fb_corner_params *w = desc_corner(s, corner);
  if (!w)
    return NAN;
  double begin = 0.0, end = 0.0;
  desc_feature(s, w, &begin, &end);
  return isfinite(end)
             ? (end + corner_reach(s, corner) - fb_scenario_wheel_start(s, corner)) / s->speed
             : s->t_end;
}

int fb_corner_set_damper(fb_corner_params *c, const fb_damper_law *l, void **params,
                         fb_err *err)
{
  const int rc = fb_damper_law_check(l, err);
  if (rc)
    return rc;
  c->damper_law = l;
  fb_damper_params_init(l, &c->damper);
  if (params)
    *params = c->damper.bytes;
  return FB_OK;
}

const fb_damper_law *fb_corner_damper_law(const fb_corner_params *c)
{
  return c->damper_law ? c->damper_law : &fb_damper_law_linear;
}

int fb_corner_damper_linear(const fb_corner_params *c)
{
  const fb_damper_law *l = fb_corner_damper_law(c);
  return l->ops->linear && l->ops->linear(c->damper.bytes);
}

int fb_corner_set_spring(fb_corner_params *c, const fb_spring_law *l, void **params,
                         fb_err *err)
{
  const int rc = fb_spring_law_check(l, err);
  if (rc)
    return rc;
  c->spring_law = l;
  fb_spring_params_init(l, &c->spring);
  if (params)
    *params = c->spring.bytes;
  return FB_OK;
}

const fb_spring_law *fb_corner_spring_law(const fb_corner_params *c)
{
  return c->spring_law ? c->spring_law : &fb_spring_law_linear;
}

fb_spring_context fb_corner_spring_context(const fb_corner_params *c)
{
  return (fb_spring_context){c->name, c->spring_k};
}

int fb_corner_set_tire(fb_corner_params *c, const fb_tire_model *m, void **params, fb_err *err)
{
  const int rc = fb_tire_model_check(m, err);
  if (rc)
    return rc;
  c->tire_model = m;
  fb_tire_params_init(m, &c->tire);
  if (params)
    *params = c->tire.bytes;
  return FB_OK;
}

const fb_tire_model *fb_corner_tire_model(const fb_corner_params *c)
{
  return c->tire_model ? c->tire_model : &fb_tire_model_bilateral;
}

fb_tire_context fb_corner_tire_context(const fb_corner_params *c)
{
  return (fb_tire_context){c->name, c->tire_k, c->tire_c, c->tire_static_deflection};
}

int fb_corner_set_envelope(fb_corner_params *c, const fb_envelope_model *m, void **params,
                           fb_err *err)
{
  const int rc = fb_envelope_model_check(m, err);
  if (rc)
    return rc;
  c->envelope_model = m;
  fb_envelope_params_init(m, &c->envelope);
  if (params)
    *params = c->envelope.bytes;
  return FB_OK;
}

const fb_envelope_model *fb_corner_envelope_model(const fb_corner_params *c)
{
  return c->envelope_model ? c->envelope_model : &fb_envelope_model_point;
}

fb_envelope_context fb_corner_envelope_context(const fb_corner_params *c)
{
  return (fb_envelope_context){c->name, c->tire_radius, c->tire_static_deflection};
}

int fb_scenario_set_road(fb_scenario *s, const fb_road_type *t, void **params, fb_err *err)
{
  const int rc = fb_road_type_check(t, err);
  if (rc)
    return rc;
  fb_road_params_release(s->road_type, &s->road);
  s->road_type = t;
  fb_road_params_init(t, &s->road);
  if (params)
    *params = s->road.bytes;
  return FB_OK;
}

int fb_scenario_prepare_road(fb_scenario *s, fb_err *err)
{
  if (!s->road_type)
    return fb_err_set(err, FB_EINVAL, "the description has no road"),
           fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, road_type)), FB_EINVAL;
  const fb_road_type_ops *ops = s->road_type->ops;
  return ops->prepare ? vehicle_road_error(ops->prepare(s->road.bytes, err), err) : FB_OK;
}

int fb_scenario_road_random(const fb_scenario *s, fb_road_iso8608_params *out)
{
  return s->road_type && s->road_type->ops->random &&
         s->road_type->ops->random(s->road.bytes, out);
}

/* ---- Ownership. */

static void desc_free_strings(char **v, size_t n)
{
  for (size_t i = 0; v && i < n; ++i)
    free(v[i]);
  free(v);
}

void vehicle_output_release(fb_output_spec *o)
{
  free(o->name);
  free(o->signal);
  free(o->of);
  free(o->bond);
  free(o->unit);
  free(o->title);
  free(o->label);
}

void vehicle_antiroll_bar_release(fb_antiroll_bar *b)
{
  free(b->name);
  free(b->left);
  free(b->right);
}

void vehicle_bogie_release(fb_bogie *b)
{
  free(b->name);
  free(b->front);
  free(b->rear);
}

void fb_scenario_free(fb_scenario **s)
{
  if (!s || !*s)
    return;
  fb_scenario *p = *s;
  free(p->name);
  free(p->path);
  free(p->frame_origin);
  free(p->load_x);
  free(p->load_y);
  for (size_t i = 0; p->mount && i < p->nmounts; ++i)
    free(p->mount[i].name);
  free(p->mount);
  for (size_t i = 0; p->body && i < p->nbodies; ++i)
    vehicle_body_release(&p->body[i]);
  free(p->body);
  for (size_t i = 0; p->point_mass && i < p->npoint_masses; ++i)
    free(p->point_mass[i].name);
  free(p->point_mass);
  for (size_t i = 0; p->section && i < p->nsections; ++i)
    free(p->section[i].set);
  free(p->section);
  for (size_t i = 0; p->corner && i < p->ncorners; ++i)
    free(p->corner[i].name);
  free(p->corner);
  for (size_t i = 0; p->antiroll_bar && i < p->nantiroll_bars; ++i)
    vehicle_antiroll_bar_release(&p->antiroll_bar[i]);
  free(p->antiroll_bar);
  for (size_t i = 0; p->bogie && i < p->nbogies; ++i)
    vehicle_bogie_release(&p->bogie[i]);
  free(p->bogie);
  for (size_t i = 0; p->output && i < p->noutputs; ++i)
    vehicle_output_release(&p->output[i]);
  free(p->output);
  fb_road_params_release(p->road_type, &p->road);
  vehicle_hull_params_release(p);
  free(p->hull_deck);
  free(p->coupling_surface);
  fb_mesh_free(&p->hull_source_mesh);
  desc_free_strings(p->inputs, p->ninputs);
  if (p->source)
    p->source->ops->free(p->source);
  free(p);
  *s = NULL;
}

/* *dst = copy of the string src (NULL stays NULL); 0 when out of memory. */
static int desc_copy_string(const char *src, char **dst)
{
  *dst = src ? fb_strdup(src) : NULL;
  return !src || *dst;
}

/* *dst = a copy of the n strings at src (NULL stays NULL), NULL entries
 * where memory ran out; 0 when it did. */
static int desc_copy_strings(char *const *src, size_t n, char ***dst)
{
  *dst = src && n ? calloc(n, sizeof **dst) : NULL;
  int ok = !src || !n || *dst;
  for (size_t i = 0; *dst && i < n; ++i)
    ok = desc_copy_string(src[i], &(*dst)[i]) && ok;
  return ok;
}

/* *dst = a byte copy of the n items of size bytes at src (NULL stays
 * NULL), its owned strings to be copied next; 0 when out of memory. The
 * copy is zeroed until then, so that a failure frees nothing twice. */
static int desc_copy_items(const void *src, size_t n, size_t size, void **dst, void **shallow)
{
  *dst = NULL;
  *shallow = NULL;
  if (!src)
    return 1;
  if (n > SIZE_MAX / size)
    return 0;
  *dst = calloc(n ? n : 1, size);
  *shallow = malloc((n ? n : 1) * size);
  if (*shallow && n)
    memcpy(*shallow, src, n * size);
  return *dst && *shallow;
}

/* *dst = copy of the n doubles at src (NULL stays NULL); 0 when out of
 * memory. */
static int desc_copy_array(const double *src, size_t n, double **dst)
{
  *dst = NULL;
  if (!src)
    return 1;
  if (n > SIZE_MAX / sizeof **dst)
    return 0;
  *dst = malloc((n ? n : 1) * sizeof **dst);
  if (*dst && n)
    memcpy(*dst, src, n * sizeof **dst);
  return *dst != NULL;
}

static int desc_copy_mounts(const fb_scenario *s, fb_scenario *copy)
{
  fb_mount *m = NULL;
  int ok = desc_copy_items(s->mount, s->nmounts, sizeof *m, (void **)&copy->mount, (void **)&m);
  for (size_t i = 0; ok && m && i < s->nmounts; ++i) { /* no m: no mounts */
    copy->mount[i] = m[i];
    ok = desc_copy_string(s->mount[i].name, &copy->mount[i].name);
  }
  free(m);
  return ok;
}

static int desc_copy_antiroll_bars(const fb_scenario *s, fb_scenario *copy)
{
  fb_antiroll_bar *b = NULL;
  int ok = desc_copy_items(s->antiroll_bar, s->nantiroll_bars, sizeof *b,
                           (void **)&copy->antiroll_bar, (void **)&b);
  for (size_t i = 0; ok && b && i < s->nantiroll_bars; ++i) { /* no b: no bars */
    copy->antiroll_bar[i] = b[i];
    copy->antiroll_bar[i].name = copy->antiroll_bar[i].left = copy->antiroll_bar[i].right =
        NULL;
    ok = desc_copy_string(b[i].name, &copy->antiroll_bar[i].name) &&
         desc_copy_string(b[i].left, &copy->antiroll_bar[i].left) &&
         desc_copy_string(b[i].right, &copy->antiroll_bar[i].right);
  }
  free(b);
  return ok;
}

static int desc_copy_bogies(const fb_scenario *s, fb_scenario *copy)
{
  fb_bogie *b = NULL;
  int ok = desc_copy_items(s->bogie, s->nbogies, sizeof *b, (void **)&copy->bogie, (void **)&b);
  for (size_t i = 0; ok && b && i < s->nbogies; ++i) { /* no b: no bogies */
    copy->bogie[i] = b[i];
    copy->bogie[i].name = copy->bogie[i].front = copy->bogie[i].rear = NULL;
    ok = desc_copy_string(b[i].name, &copy->bogie[i].name) &&
         desc_copy_string(b[i].front, &copy->bogie[i].front) &&
         desc_copy_string(b[i].rear, &copy->bogie[i].rear);
  }
  free(b);
  return ok;
}

/* The copy's bodies are zeroed until each is copied. */
static int desc_copy_bodies(const fb_scenario *s, fb_scenario *copy)
{
  const size_t n = s->nbodies;
  if (!s->body)
    return 1;
  copy->body = calloc(n ? n : 1, sizeof *copy->body);
  int ok = copy->body != NULL;
  for (size_t i = 0; ok && i < n; ++i)
    ok = vehicle_body_copy(&s->body[i], &copy->body[i]);
  return ok;
}

/* The copy's items are zeroed until each is copied, so that a failure
 * frees nothing twice. */
static int desc_copy_point_masses(const fb_scenario *s, fb_scenario *copy)
{
  const size_t n = s->npoint_masses;
  if (!s->point_mass)
    return 1;
  copy->point_mass = calloc(n ? n : 1, sizeof *copy->point_mass);
  int ok = copy->point_mass != NULL;
  for (size_t i = 0; ok && i < n; ++i) {
    copy->point_mass[i] = s->point_mass[i];
    copy->point_mass[i].name = NULL;
    ok = desc_copy_string(s->point_mass[i].name, &copy->point_mass[i].name);
  }
  return ok;
}

static int desc_copy_sections(const fb_scenario *s, fb_scenario *copy)
{
  const size_t n = s->nsections;
  if (!s->section)
    return 1;
  copy->section = calloc(n ? n : 1, sizeof *copy->section);
  int ok = copy->section != NULL;
  for (size_t i = 0; ok && i < n; ++i) {
    copy->section[i] = s->section[i];
    copy->section[i].set = NULL;
    ok = desc_copy_string(s->section[i].set, &copy->section[i].set);
  }
  return ok;
}

static int desc_copy_corners(const fb_scenario *s, fb_scenario *copy)
{
  fb_corner_params *c = NULL;
  int ok =
      desc_copy_items(s->corner, s->ncorners, sizeof *c, (void **)&copy->corner, (void **)&c);
  for (size_t i = 0; ok && c && i < s->ncorners; ++i) { /* no c: no corners */
    copy->corner[i] = c[i];
    ok = desc_copy_string(s->corner[i].name, &copy->corner[i].name);
  }
  free(c);
  return ok;
}

static int desc_copy_output(const fb_output_spec *src, fb_output_spec *dst)
{
  *dst = (fb_output_spec){.figure = src->figure,
                          .window = {src->window[0], src->window[1]},
                          .at = {src->at[0], src->at[1], src->at[2]},
                          .direction = src->direction,
                          .component = src->component,
                          .element = src->element,
                          .surface = src->surface,
                          .stress = src->stress};
  int ok = desc_copy_string(src->name, &dst->name);
  ok = desc_copy_string(src->signal, &dst->signal) && ok;
  ok = desc_copy_string(src->of, &dst->of) && ok;
  ok = desc_copy_string(src->bond, &dst->bond) && ok;
  ok = desc_copy_string(src->unit, &dst->unit) && ok;
  ok = desc_copy_string(src->title, &dst->title) && ok;
  return desc_copy_string(src->label, &dst->label) && ok;
}

static int desc_copy_outputs(const fb_scenario *s, fb_scenario *copy)
{
  fb_output_spec *o = NULL;
  int ok =
      desc_copy_items(s->output, s->noutputs, sizeof *o, (void **)&copy->output, (void **)&o);
  free(o);
  for (size_t i = 0; ok && i < s->noutputs; ++i)
    ok = desc_copy_output(&s->output[i], &copy->output[i]);
  return ok;
}

int fb_scenario_clone(const fb_scenario *s, fb_scenario **out, fb_err *err)
{
  if (!s || !out)
    return fb_err_set(err, FB_EINVAL, "fb_scenario_clone: scenario and out must not be NULL");
  *out = NULL;
  fb_scenario *copy = malloc(sizeof *copy);
  if (!copy)
    return fb_err_set(err, FB_ENOMEM, "out of memory copying a scenario");
  *copy = *s;
  /* Nothing of s's is owned by the copy until copied below. */
  copy->name = copy->path = copy->frame_origin = copy->hull_deck = NULL;
  copy->coupling_surface = NULL;
  copy->load_x = copy->load_y = NULL;
  copy->mount = NULL;
  copy->body = NULL;
  copy->point_mass = NULL;
  copy->section = NULL;
  copy->corner = NULL;
  copy->antiroll_bar = NULL;
  copy->bogie = NULL;
  copy->output = NULL;
  copy->inputs = NULL;
  copy->source = NULL;
  memset(&copy->road, 0, sizeof copy->road);
  copy->hull_source_mesh = NULL;
  int ok = vehicle_hull_params_copy(copy);
  ok = desc_copy_string(s->name, &copy->name) && ok;
  ok = desc_copy_string(s->path, &copy->path) && ok;
  ok = desc_copy_string(s->frame_origin, &copy->frame_origin) && ok;
  ok = desc_copy_array(s->load_x, s->nload, &copy->load_x) && ok;
  ok = desc_copy_array(s->load_y, s->nload, &copy->load_y) && ok;
  ok = desc_copy_mounts(s, copy) && ok;
  ok = desc_copy_bodies(s, copy) && ok;
  ok = desc_copy_point_masses(s, copy) && ok;
  ok = desc_copy_sections(s, copy) && ok;
  ok = desc_copy_corners(s, copy) && ok;
  ok = desc_copy_antiroll_bars(s, copy) && ok;
  ok = desc_copy_bogies(s, copy) && ok;
  ok = desc_copy_outputs(s, copy) && ok;
  ok = (!s->road_type ||
        fb_road_params_copy(s->road_type, &copy->road, &s->road, NULL) == FB_OK) &&
       ok;
  ok = desc_copy_string(s->hull_deck, &copy->hull_deck) && ok;
  ok = desc_copy_string(s->coupling_surface, &copy->coupling_surface) && ok;
  ok = (!s->hull_source_mesh ||
        fb_mesh_clone(s->hull_source_mesh, &copy->hull_source_mesh, NULL) == FB_OK) &&
       ok;
  ok = desc_copy_strings(s->inputs, s->ninputs, &copy->inputs) && ok;
  ok = (!s->source || s->source->ops->clone(s->source, &copy->source) == FB_OK) && ok;
  if (!ok) {
    fb_scenario_free(&copy);
    return fb_err_set(err, FB_ENOMEM, "out of memory copying a scenario");
  }
  *out = copy;
  return FB_OK;
}

int vehicle_road_error(int rc, fb_err *err)
{
  if (rc && err && err->part.field[0] && !err->part.kind)
    err->part.kind = FB_PART_ROAD;
  return rc;
}
