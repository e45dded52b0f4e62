/* SPDX-License-Identifier: BSD-3-Clause */
/* A vehicle description made by a program (flexbond/vehicle.h): a new
 * description with the library's defaults, and its parts added by copy,
 * so that the description owns everything fb_scenario_free frees. Scalars
 * are the program's to set in the struct; the parts with memory of their
 * own (names, lists) come in here. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* Standard gravity (CGPM 1901; ISO 80000-3): the default where a program
 * gives none. */
static const double STANDARD_GRAVITY = 9.80665;

int fb_scenario_new(const char *name, fb_scenario **out, fb_err *err)
{
  *out = NULL;
  fb_scenario *s = calloc(1, sizeof *s);
  if (!s || !(s->name = fb_strdup(name ? name : "vehicle"))) {
    free(s);
    return fb_err_set(err, FB_ENOMEM, "out of memory for a description");
  }
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  s->gravity = STANDARD_GRAVITY;
  s->payload = FB_PAYLOAD_WEIGHT_ONLY;
  s->t_end = o.t_end;
  s->rtol = o.rtol;
  s->atol = o.atol;
  s->max_step = o.max_step;
  s->sample_rate = o.sample_rate;
  s->max_steps = o.max_steps;
  s->stability_limit_detection = o.stability_limit_detection;
  s->initial = FB_INITIAL_STATIC;
  s->hull_coordinates = FB_HULL_MODAL;
  s->hull_modes_kind = FB_HULL_MODES_AUTO;
  *out = s;
  return FB_OK;
}

void fb_scenario_set_rigid_hull(fb_scenario *s, double mass, double ixx, double iyy)
{
  s->hull_mass_given = 1;
  s->hull_mass = mass;
  s->hull_ixx = ixx;
  s->hull_iyy = iyy;
}

/* One more item of size bytes at the end of *items (n of them): zeroed,
 * in *item. 0 when memory runs out (the list unchanged). */
static int builder_grow(void **items, size_t n, size_t size, void **item)
{
  char *grown = n < SIZE_MAX / size - 1 ? realloc(*items, (n + 1) * size) : NULL;
  if (!grown)
    return 0;
  *items = grown;
  *item = grown + n * size;
  memset(*item, 0, size);
  return 1;
}

/* A copy of name into *copy, refusing what no part may be called. */
static int builder_name(const char *name, const char *what, char **copy, fb_err *err)
{
  if (!name || !name[0])
    return fb_err_set(err, FB_EINVAL, "a %s needs a name", what);
  if (!(*copy = fb_strdup(name)))
    return fb_err_set(err, FB_ENOMEM, "out of memory for a %s", what);
  return FB_OK;
}

int fb_scenario_add_corner(fb_scenario *s, const fb_corner_params *c, fb_err *err)
{
  char *name = NULL;
  int rc = builder_name(c->name, "corner", &name, err);
  fb_corner_params *to = NULL;
  if (!rc && !builder_grow((void **)&s->corner, s->ncorners, sizeof *to, (void **)&to))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for a corner");
  if (rc) {
    free(name);
    return rc;
  }
  *to = *c;
  to->name = name;
  ++s->ncorners;
  return FB_OK;
}

int fb_scenario_add_mount(fb_scenario *s, const fb_mount *m, fb_err *err)
{
  char *name = NULL;
  int rc = builder_name(m->name, "mounted body", &name, err);
  fb_mount *to = NULL;
  if (!rc && !builder_grow((void **)&s->mount, s->nmounts, sizeof *to, (void **)&to))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for a mounted body");
  if (rc) {
    free(name);
    return rc;
  }
  *to = *m;
  to->name = name;
  ++s->nmounts;
  return FB_OK;
}

int fb_scenario_add_antiroll_bar(fb_scenario *s, const fb_antiroll_bar *b, fb_err *err)
{
  fb_antiroll_bar copy = *b;
  copy.name = copy.left = copy.right = NULL;
  int rc = builder_name(b->name, "bar between corners", &copy.name, err);
  if (!rc)
    rc = builder_name(b->left, "bar's left corner", &copy.left, err);
  if (!rc)
    rc = builder_name(b->right, "bar's right corner", &copy.right, err);
  fb_antiroll_bar *to = NULL;
  if (!rc &&
      !builder_grow((void **)&s->antiroll_bar, s->nantiroll_bars, sizeof *to, (void **)&to))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for an anti-roll bar");
  if (rc) {
    vehicle_antiroll_bar_release(&copy);
    return rc;
  }
  *to = copy;
  ++s->nantiroll_bars;
  return FB_OK;
}

int fb_scenario_add_bogie(fb_scenario *s, const fb_bogie *b, fb_err *err)
{
  fb_bogie copy = *b;
  copy.name = copy.front = copy.rear = NULL;
  int rc = builder_name(b->name, "bogie", &copy.name, err);
  if (!rc)
    rc = builder_name(b->front, "bogie's front corner", &copy.front, err);
  if (!rc)
    rc = builder_name(b->rear, "bogie's rear corner", &copy.rear, err);
  fb_bogie *to = NULL;
  if (!rc && !builder_grow((void **)&s->bogie, s->nbogies, sizeof *to, (void **)&to))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for a bogie");
  if (rc) {
    vehicle_bogie_release(&copy);
    return rc;
  }
  *to = copy;
  ++s->nbogies;
  return FB_OK;
}

int fb_scenario_add_body(fb_scenario *s, const fb_body *b, fb_err *err)
{
  if (!b->name || !b->name[0])
    return fb_err_set(err, FB_EINVAL, "a mounted rigid body needs a name");
  if (b->nbushings < 1 || !b->bushing || b->nbushings > FB_BODY_MAX_BUSHINGS)
    return fb_err_set(err, FB_EINVAL, "body %s needs 1 to %d bushings (got %zu)", b->name,
                      FB_BODY_MAX_BUSHINGS, b->bushing ? b->nbushings : 0);
  fb_body *to = NULL;
  if (!builder_grow((void **)&s->body, s->nbodies, sizeof *to, (void **)&to))
    return fb_err_set(err, FB_ENOMEM, "out of memory for a mounted rigid body");
  if (!vehicle_body_copy(b, to))
    return fb_err_set(err, FB_ENOMEM, "out of memory for body %s", b->name);
  ++s->nbodies;
  return FB_OK;
}

int fb_scenario_add_point_mass(fb_scenario *s, const fb_hull_point_mass *m, fb_err *err)
{
  char *name = NULL;
  int rc = builder_name(m->name, "hull mass", &name, err);
  fb_hull_point_mass *to = NULL;
  if (!rc && !builder_grow((void **)&s->point_mass, s->npoint_masses, sizeof *to, (void **)&to))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for a hull mass");
  if (rc) {
    free(name);
    return rc;
  }
  *to = *m;
  to->name = name;
  ++s->npoint_masses;
  return FB_OK;
}

int fb_scenario_add_load_point(fb_scenario *s, double x, double y, fb_err *err)
{
  double *to_x = NULL, *to_y = NULL;
  if (!builder_grow((void **)&s->load_x, s->nload, sizeof *to_x, (void **)&to_x))
    return fb_err_set(err, FB_ENOMEM, "out of memory for a load point");
  if (!builder_grow((void **)&s->load_y, s->nload, sizeof *to_y, (void **)&to_y))
    return fb_err_set(err, FB_ENOMEM, "out of memory for a load point");
  *to_x = x;
  *to_y = y;
  ++s->nload;
  return FB_OK;
}

/* pattern with its "%s" replaced by subject, into *out unless set. */
static int builder_pattern(const char *pattern, const char *subject, char **out)
{
  if (*out || !pattern)
    return FB_OK;
  const char *at = strstr(pattern, "%s");
  *out = at ? fb_strdup_printf("%.*s%s%s", (int)(at - pattern), pattern, subject, at + 2)
            : fb_strdup(pattern);
  return *out ? FB_OK : FB_ENOMEM;
}

/* A bond signal's column: the signal and the bond's name, '.' as '_'
 * ("effort_susp_LF_b_tire"), and a multibond's component
 * ("effort_hull_b_attach_3"). */
static int builder_bond_column(const fb_output_spec *o, char **out)
{
  if (*out)
    return FB_OK;
  *out = o->component > 0 ? fb_strdup_printf("%s_%s_%ld", o->signal, o->bond, o->component)
                          : fb_strdup_printf("%s_%s", o->signal, o->bond);
  if (!*out)
    return FB_ENOMEM;
  for (char *p = *out; *p; ++p)
    if (*p == '.')
      *p = '_';
  return FB_OK;
}

/* A hull stress signal's subject in its default name: its component and
 * surface ("sx_top"); "" for values out of range (which the check refuses). */
static void builder_stress_subject(const fb_output_spec *o, char *buf, size_t size)
{
  static const char *const component[3] = {"sx", "sy", "sxy"}, *const surface[2] = {"top",
                                                                                    "bottom"};
  if (o->stress >= 0 && o->stress < 3 && o->surface >= 0 && o->surface < 2)
    snprintf(buf, size, "%s_%s", component[o->stress], surface[o->surface]);
  else
    buf[0] = '\0';
}

int fb_output_spec_complete(fb_output_spec *o, const fb_output_kind *kind, fb_err *err)
{
  static const char *const axes[3] = {"x", "y", "z"};
  const int bond = kind->subject == FB_OUTPUT_OF_BOND;
  const int point = kind->subject == FB_OUTPUT_OF_HULL_POINT;
  char stress[16];
  builder_stress_subject(o, stress, sizeof stress);
  const char *subject = bond                                             ? o->bond
                        : point && o->direction >= 0 && o->direction < 3 ? axes[o->direction]
                        : kind->subject == FB_OUTPUT_OF_HULL_STRESS      ? stress
                        : o->of                                          ? o->of
                                                                         : "";
  int rc =
      bond ? builder_bond_column(o, &o->name) : builder_pattern(kind->name, subject, &o->name);
  if (!rc)
    rc = builder_pattern(kind->title, subject, &o->title);
  if (!rc)
    rc = builder_pattern(kind->label, subject, &o->label);
  if (!rc)
    rc = builder_pattern(kind->unit, "", &o->unit);
  return rc ? fb_err_set(err, FB_ENOMEM, "out of memory for an output") : FB_OK;
}

/* The subject o's kind needs: a corner's or a mount's name, a bond. */
static int builder_subject(const fb_scenario *s, const fb_output_kind *kind,
                           const fb_output_spec *o, fb_err *err)
{
  switch (kind->subject) {
  case FB_OUTPUT_OF_CORNER:
    return o->of && fb_scenario_corner_find(s, o->of) >= 0
               ? FB_OK
               : fb_err_set(err, FB_EINVAL, "a %s signal measures a corner of the vehicle (%s)",
                            kind->signal, o->of ? o->of : "none given");
  case FB_OUTPUT_OF_MOUNT:
    return o->of && fb_scenario_mount_find(s, o->of) >= 0
               ? FB_OK
               : fb_err_set(err, FB_EINVAL,
                            "a %s signal measures a mounted body of the vehicle (%s)",
                            kind->signal, o->of ? o->of : "none given");
  case FB_OUTPUT_OF_BOGIE:
    return o->of && fb_scenario_bogie_find(s, o->of) >= 0
               ? FB_OK
               : fb_err_set(err, FB_EINVAL, "a %s signal measures a bogie of the vehicle (%s)",
                            kind->signal, o->of ? o->of : "none given");
  case FB_OUTPUT_OF_BODY:
    return o->of && fb_scenario_body_find(s, o->of) >= 0
               ? FB_OK
               : fb_err_set(err, FB_EINVAL,
                            "a %s signal measures a mounted rigid body of the vehicle (%s)",
                            kind->signal, o->of ? o->of : "none given");
  case FB_OUTPUT_OF_HULL:
    return o->of ? fb_err_set(err, FB_EINVAL,
                              "a %s signal measures the hull, no corner or mount", kind->signal)
                 : FB_OK;
  case FB_OUTPUT_OF_BOND:
    return o->bond ? FB_OK
                   : fb_err_set(err, FB_EINVAL, "a %s signal names the bond it records",
                                kind->signal);
  case FB_OUTPUT_OF_HULL_STRESS:
    return o->surface >= 0 && o->surface < 2 && o->stress >= 0 && o->stress < 3 && !o->of &&
                   !o->bond && o->element >= 0
               ? FB_OK
               : fb_err_set(err, FB_EINVAL,
                            "a %s signal reads a shell element's (element >= 0; 0: the one "
                            "nearest at) surface stress (surface 0 or 1, stress 0, 1 or 2), "
                            "no corner, mount or bond",
                            kind->signal);
  case FB_OUTPUT_OF_HULL_POINT:
    return o->direction >= 0 && o->direction < 3 && !o->of && !o->bond
               ? FB_OK
               : fb_err_set(err, FB_EINVAL,
                            "a %s signal measures a hull point along x, y or z (direction 0, "
                            "1 or 2), no corner, mount or bond",
                            kind->signal);
  }
  return FB_OK;
}

int fb_scenario_add_output(fb_scenario *s, const fb_output_spec *o, fb_err *err)
{
  const fb_output_kind *kind = fb_vehicle_output_kind_find(o->signal);
  if (!kind)
    return fb_err_set(err, FB_EINVAL, "no signal '%s' (fb_vehicle_output_kinds)",
                      o->signal ? o->signal : "(none)");
  int rc = builder_subject(s, kind, o, err);
  if (rc)
    return rc;
  fb_output_spec copy = {.figure = o->figure,
                         .window = {o->window[0], o->window[1]},
                         .at = {o->at[0], o->at[1], o->at[2]},
                         .direction = o->direction,
                         .component = o->component,
                         .element = o->element,
                         .surface = o->surface,
                         .stress = o->stress};
  const char *const from[] = {o->name, o->signal, o->of, o->bond, o->unit, o->title, o->label};
  char **const to[] = {&copy.name, &copy.signal, &copy.of,   &copy.bond,
                       &copy.unit, &copy.title,  &copy.label};
  for (size_t i = 0; !rc && i < sizeof to / sizeof to[0]; ++i)
    if (from[i] && !(*to[i] = fb_strdup(from[i])))
      rc = fb_err_set(err, FB_ENOMEM, "out of memory for an output");
  if (!rc)
    rc = fb_output_spec_complete(&copy, kind, err);
  for (size_t i = 0; !rc && i < s->noutputs; ++i)
    if (!strcmp(s->output[i].name, copy.name))
      rc = fb_err_set(err, FB_EINVAL, "an output named %s is there already (names are unique)",
                      copy.name);
  fb_output_spec *item = NULL;
  if (!rc && !builder_grow((void **)&s->output, s->noutputs, sizeof *item, (void **)&item))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for an output");
  if (rc) {
    vehicle_output_release(&copy);
    return rc;
  }
  *item = copy;
  ++s->noutputs;
  return FB_OK;
}
