/* SPDX-License-Identifier: BSD-3-Clause */
/* The vehicle's layout as data: its attachment points, its subsystem
 * instances by name, the road's tracks (flexbond/vehicle.h). */
#include <stdio.h>
#include <string.h>

#include "flexbond/hull_source.h"
#include "flexbond/vehicle.h"

#include "core/textfile.h"

/* The name of item i of part kind kind of s, NULL if it has none. */
static const char *part_name(const fb_scenario *s, int kind, size_t i)
{
  switch (kind) {
  case FB_PART_CORNER:
  case FB_PART_TIRE:
  case FB_PART_DAMPER:
  case FB_PART_SPRING:
  case FB_PART_ENVELOPE:
  case FB_PART_STOP: return i < s->ncorners ? s->corner[i].name : NULL;
  case FB_PART_MOUNT: return i < s->nmounts ? s->mount[i].name : NULL;
  case FB_PART_HULL_MASS: return i < s->npoint_masses ? s->point_mass[i].name : NULL;
  case FB_PART_BODY: return i < s->nbodies ? s->body[i].name : NULL;
  case FB_PART_BUSHING: {
    size_t b = 0, j = 0;
    return fb_scenario_bushing_at(s, i, &b, &j) ? s->body[b].name : NULL;
  }
  case FB_PART_SECTION: return i < s->nsections ? s->section[i].set : NULL;
  case FB_PART_OUTPUT: return i < s->noutputs ? s->output[i].name : NULL;
  case FB_PART_ANTIROLL_BAR: return i < s->nantiroll_bars ? s->antiroll_bar[i].name : NULL;
  case FB_PART_BOGIE: return i < s->nbogies ? s->bogie[i].name : NULL;
  case FB_PART_ROAD: return s->road_type ? s->road_type->name : NULL;
  case FB_PART_HULL_SOURCE: return s->hull_source ? s->hull_source->name : NULL;
  default: return NULL;
  }
}

char *fb_scenario_part_text(const fb_scenario *s, const fb_err_part *p, char *buf, size_t size)
{
  static const char *const list[FB_PART_KINDS] = {
      "",           "",        "corner",       "mount",       "point_mass", "section", "output",
      "load point", "road",    "corner",       "hull source", "corner",     "corner",  "corner",
      "body",       "bushing", "antiroll_bar", "bogie",       "corner"};
  const int kind =
      p->kind > 0 && p->kind < FB_PART_KINDS && list[p->kind] ? p->kind : FB_PART_NONE;
  const char *name = s ? part_name(s, kind, p->index) : NULL;
  size_t n = 0;
  buf[0] = '\0';
  if (kind == FB_PART_LOAD_POINT)
    n = fb_text_append(buf, size, n, "load point %zu", p->index);
  else if (kind == FB_PART_ROAD || kind == FB_PART_HULL_SOURCE) /* one of each, named */
    n = fb_text_append(buf, size, n, "%s", list[kind]);
  else if (kind > FB_PART_VEHICLE)
    n = fb_text_append(buf, size, n, "%s[%zu]", list[kind], p->index);
  if (name)
    n = fb_text_append(buf, size, n, " (%s)", name);
  if (p->field[0]) /* a tire's (damper's) parameter is its model's (law's) */
    n = fb_text_append(buf, size, n, "%s%s%s", n ? "." : "",
                       kind == FB_PART_TIRE       ? "tire."
                       : kind == FB_PART_DAMPER   ? "damper."
                       : kind == FB_PART_SPRING   ? "spring."
                       : kind == FB_PART_ENVELOPE ? "envelope."
                                                  : "",
                       p->field);
  if (p->element != FB_ERR_NO_ELEMENT)
    fb_text_append(buf, size, n, "[%zu]", p->element);
  return buf;
}

size_t fb_scenario_nattach(const fb_scenario *s)
{
  return s->ncorners + s->nmounts;
}

size_t fb_scenario_noutputs(const fb_scenario *s)
{
  return s->noutputs;
}

const char *fb_scenario_output_name(const fb_scenario *s, size_t o)
{
  return o < s->noutputs ? s->output[o].name : NULL;
}

const char *fb_scenario_output_unit(const fb_scenario *s, size_t o)
{
  return o < s->noutputs ? s->output[o].unit : NULL;
}

size_t fb_scenario_ncorners(const fb_scenario *s)
{
  return s->ncorners;
}

const char *fb_scenario_corner_name(const fb_scenario *s, size_t c)
{
  return c < s->ncorners ? s->corner[c].name : NULL;
}

const char *fb_scenario_corner_tire(const fb_scenario *s, size_t c)
{
  return c < s->ncorners ? fb_corner_tire_model(&s->corner[c])->name : NULL;
}

void fb_scenario_corner_position(const fb_scenario *s, size_t c, double *x, double *y)
{
  if (c >= s->ncorners)
    return;
  /* Inside, relative to the hull's centre of mass; returned as written. */
  double o[3];
  fb_scenario_frame_offset(s, o);
  *x = s->corner[c].x + o[0];
  *y = s->corner[c].y + o[1];
}

double fb_scenario_speed(const fb_scenario *s)
{
  return s->speed;
}

long fb_scenario_corner_find(const fb_scenario *s, const char *name)
{
  for (size_t c = 0; name && c < s->ncorners; ++c)
    if (!strcmp(s->corner[c].name, name))
      return (long)c;
  return -1;
}

long fb_scenario_mount_find(const fb_scenario *s, const char *name)
{
  for (size_t b = 0; name && b < s->nmounts; ++b)
    if (!strcmp(s->mount[b].name, name))
      return (long)b;
  return -1;
}

long fb_scenario_bogie_find(const fb_scenario *s, const char *name)
{
  for (size_t b = 0; name && b < s->nbogies; ++b)
    if (!strcmp(s->bogie[b].name, name))
      return (long)b;
  return -1;
}

long fb_scenario_corner_bogie(const fb_scenario *s, size_t c)
{
  for (size_t b = 0; c < s->ncorners && b < s->nbogies; ++b)
    if (!strcmp(s->bogie[b].front, s->corner[c].name) ||
        !strcmp(s->bogie[b].rear, s->corner[c].name))
      return (long)b;
  return -1;
}

double fb_scenario_track_width(const fb_scenario *s)
{
  /* The first corner leads the left track (y > 0); the right track is the
   * first corner on the other side of the centre line. */
  for (size_t c = 1; c < s->ncorners; ++c)
    if (s->corner[c].y <= 0.0)
      return s->corner[0].y - s->corner[c].y;
  return 0.0;
}

double fb_scenario_point_masses_total(const fb_scenario *s)
{
  double sum = 0.0;
  for (size_t k = 0; k < s->npoint_masses; ++k)
    sum += s->point_mass[k].mass;
  return sum;
}

double fb_scenario_payload_mass(const fb_scenario *s)
{
  return s->total_weight / s->gravity - s->hull_mass - fb_scenario_point_masses_total(s);
}
