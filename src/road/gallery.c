/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery (flexbond/road.h): the soundness of a road type, its
 * parameter blocks, and the set of types a description may name. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/road.h"

#include "core/registry.h"
#include "core/util.h"

/* The built-in types, one line each. */
static const fb_road_type *const gallery_builtin[] = {
    &fb_road_type_bump,      /* the paper's */
    &fb_road_type_iso8608,   /* random */
    &fb_road_type_profile,   /* measured */
    &fb_road_type_halfround, /* obstacles (obstacle.h) */
    &fb_road_type_step,      /* obstacle */
    &fb_road_type_cleat,     /* obstacle */
    &fb_road_type_trapezoid, /* obstacle */
    &fb_road_type_pothole,   /* obstacle */
    &fb_road_type_washboard, /* obstacle */
    &fb_road_type_course,    /* obstacles from a file */
    &fb_road_type_crg,       /* an OpenCRG surface */
};

struct fb_road_gallery {
  fb_registry reg; /* the types */
};

/* The registry reads an entry's name as its first member. */
_Static_assert(offsetof(fb_road_type, name) == 0, "a road type's name is its first member");

static int type_fail(fb_err *err, const fb_road_type *t, const char *what)
{
  return fb_err_set(err, FB_EINVAL, "road type %s: %s", t && t->name ? t->name : "(unnamed)",
                    what);
}

int fb_road_type_check(const fb_road_type *t, fb_err *err)
{
  const fb_registry_entry none = {.kind = "road type"};
  if (!t)
    return fb_registry_entry_check(&none, err);
  const char *ops = !t->ops || !t->ops->make || !t->ops->wheel_start
                        ? "a type makes its road and places its wheels (make, wheel_start)"
                    : !t->ops->copy != !t->ops->release
                        ? "a block that owns members is copied and released (both ops)"
                        : NULL;
  const fb_registry_entry e = {"road type",
                               t->name,
                               t->doc,
                               NULL,
                               0,
                               t->param,
                               t->nparams,
                               t->params_size,
                               FB_ROAD_PARAMS_MAX,
                               "FB_ROAD_PARAMS_MAX",
                               0,
                               ops};
  return fb_registry_entry_check(&e, err);
}

void fb_road_params_init(const fb_road_type *t, fb_road_params *p)
{
  memset(p, 0, sizeof *p);
  fb_params_defaults(t->param, t->nparams, p->bytes);
  if (t->ops->init)
    t->ops->init(p->bytes);
}

int fb_road_params_copy(const fb_road_type *t, fb_road_params *to, const fb_road_params *from,
                        fb_err *err)
{
  memcpy(to, from, sizeof *to);
  if (!t->ops->copy)
    return FB_OK;
  const int rc = t->ops->copy(to->bytes, from->bytes, err);
  if (rc) /* the copy's members are the original's until copy succeeds */
    memset(to, 0, sizeof *to);
  return rc;
}

void fb_road_params_release(const fb_road_type *t, fb_road_params *p)
{
  if (t && t->ops->release)
    t->ops->release(p->bytes);
  memset(p, 0, sizeof *p);
}

int fb_road_gallery_new(fb_road_gallery **out, fb_err *err)
{
  *out = NULL;
  fb_road_gallery *g = calloc(1, sizeof *g);
  if (!g)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a road gallery");
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < sizeof gallery_builtin / sizeof gallery_builtin[0]; ++i)
    rc = fb_road_gallery_add(g, gallery_builtin[i], err);
  if (rc)
    fb_road_gallery_free(&g);
  *out = g;
  return rc;
}

int fb_road_gallery_add(fb_road_gallery *g, const fb_road_type *t, fb_err *err)
{
  int rc = fb_road_type_check(t, err);
  if (rc)
    return rc;
  if (fb_road_gallery_find(g, t->name))
    return type_fail(err, t, "a type of that name is already in the gallery");
  return fb_registry_add(&g->reg, t, "road types", err);
}

size_t fb_road_gallery_count(const fb_road_gallery *g)
{
  return g ? g->reg.n : 0;
}

const fb_road_type *fb_road_gallery_at(const fb_road_gallery *g, size_t i)
{
  return fb_registry_at(g ? &g->reg : NULL, i);
}

const fb_road_type *fb_road_gallery_find(const fb_road_gallery *g, const char *name)
{
  return fb_registry_find(g ? &g->reg : NULL, name);
}

void fb_road_gallery_free(fb_road_gallery **g)
{
  if (!g || !*g)
    return;
  fb_registry_release(&(*g)->reg);
  free(*g);
  *g = NULL;
}

void fb_road_phrase(const fb_road_type *t, const fb_road_params *p, char *buf, size_t n)
{
  if (!t)
    snprintf(buf, n, "on no road");
  else if (t->ops->phrase)
    t->ops->phrase(p->bytes, buf, n);
  else
    snprintf(buf, n, "on the road");
}
