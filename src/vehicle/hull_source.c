/* SPDX-License-Identifier: BSD-3-Clause */
/* The hull-source gallery (flexbond/hull_source.h): the soundness of a
 * source, a description's source and the set of sources a program may
 * name. */
#include "flexbond/hull_source.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "core/registry.h"
#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* The built-in sources, one line each; the first is a description's
 * default. */
static const fb_hull_source *const source_builtin[] = {
    &fb_hull_source_generator,
    &fb_hull_source_deck,
    &fb_hull_source_reduced,
};

struct fb_hull_source_gallery {
  fb_registry reg; /* the sources */
};

/* The registry reads an entry's name as its first member. */
_Static_assert(offsetof(fb_hull_source, name) == 0, "a hull source's name is its first member");

static int source_fail(fb_err *err, const fb_hull_source *src, const char *what)
{
  return fb_err_set(err, FB_EINVAL, "hull source %s: %s",
                    src && src->name ? src->name : "(unnamed)", what);
}

int fb_hull_source_check(const fb_hull_source *src, fb_err *err)
{
  const fb_registry_entry none = {.kind = "hull source"};
  if (!src)
    return fb_registry_entry_check(&none, err);
  const fb_hull_source_ops *o = src->ops;
  const char *ops = !o || !o->describe ? "a source describes itself (describe)"
                    : !o->read == !o->make
                        ? "a source either reads its mesh (read) or makes it (make)"
                    : o->make && (!o->key || !o->centroid)
                        ? "a source that makes its mesh says from what (key) and where its "
                          "centre of mass is (centroid)"
                        : NULL;
  const fb_registry_entry e = {"hull source", src->name, src->doc, NULL, 0, src->param,
                               src->nparams, src->params_size, FB_HULL_SOURCE_PARAMS_MAX,
                               "FB_HULL_SOURCE_PARAMS_MAX",
                               /* files too: a description copies and frees
                                * its block's paths (vehicle_hull_params_copy) */
                               0, ops};
  return fb_registry_entry_check(&e, err);
}

const fb_hull_source *fb_scenario_hull_source(const fb_scenario *s)
{
  return s->hull_source ? s->hull_source : source_builtin[0];
}

int fb_scenario_set_hull_source(fb_scenario *s, const fb_hull_source *src, fb_err *err)
{
  const int rc = fb_hull_source_check(src, err);
  if (rc)
    return rc;
  if (fb_scenario_hull_source(s) != src) {
    fb_mesh_free(&s->hull_source_mesh);
    vehicle_hull_params_release(s);
    memset(&s->hull_params, 0, sizeof s->hull_params);
    fb_params_defaults(src->param, src->nparams, s->hull_params.bytes);
  }
  s->hull_source = src;
  return FB_OK;
}

/* The block's file paths (FB_PARAM_FILE, a string the block owns), each
 * in turn. */
static char **hull_param_path(const fb_scenario *s, fb_hull_source_params *block, size_t *i)
{
  const fb_hull_source *src = fb_scenario_hull_source(s);
  for (; *i < src->nparams; ++*i)
    if (src->param[*i].store == FB_PARAM_STRING)
      return (char **)(void *)(block->bytes + src->param[(*i)++].offset);
  return NULL;
}

void vehicle_hull_params_release(fb_scenario *s)
{
  size_t i = 0;
  for (char **p; (p = hull_param_path(s, &s->hull_params, &i));) {
    free(*p);
    *p = NULL;
  }
}

int vehicle_hull_params_copy(fb_scenario *copy)
{
  int ok = 1;
  size_t i = 0;
  for (char **p; (p = hull_param_path(copy, &copy->hull_params, &i));) {
    const char *original = *p; /* the block was copied byte for byte */
    *p = original ? fb_strdup(original) : NULL;
    ok = ok && (*p || !original);
  }
  return ok;
}

int fb_scenario_read_hull(fb_scenario *s, fb_err *err)
{
  const fb_hull_source *src = fb_scenario_hull_source(s);
  if (!s->has_fe_hull || !src->ops->read)
    return FB_OK;
  fb_mesh *mesh = NULL;
  const int rc = src->ops->read(s, &mesh, err);
  if (rc)
    return rc;
  fb_mesh_free(&s->hull_source_mesh);
  s->hull_source_mesh = mesh;
  return FB_OK;
}

int fb_scenario_hull_read_in_own_frame(const fb_scenario *s)
{
  return s->has_fe_hull && fb_scenario_hull_source(s)->ops->read != NULL;
}

int fb_scenario_hull_density(const fb_scenario *s)
{
  const fb_hull_source *src = fb_scenario_hull_source(s);
  return src->ops->density ? src->ops->density(s) : 0;
}

void fb_scenario_hull_describe(const fb_scenario *s, char *buf, size_t n)
{
  if (n)
    buf[0] = '\0';
  fb_scenario_hull_source(s)->ops->describe(s, buf, n);
}

int fb_hull_source_gallery_new(fb_hull_source_gallery **out, fb_err *err)
{
  *out = NULL;
  fb_hull_source_gallery *g = calloc(1, sizeof *g);
  if (!g)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a hull-source gallery");
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < sizeof source_builtin / sizeof source_builtin[0]; ++i)
    rc = fb_hull_source_gallery_add(g, source_builtin[i], err);
  if (rc)
    fb_hull_source_gallery_free(&g);
  *out = g;
  return rc;
}

int fb_hull_source_gallery_add(fb_hull_source_gallery *g, const fb_hull_source *src,
                               fb_err *err)
{
  const int rc = fb_hull_source_check(src, err);
  if (rc)
    return rc;
  if (fb_hull_source_gallery_find(g, src->name))
    return source_fail(err, src, "a source of that name is already in the gallery");
  return fb_registry_add(&g->reg, src, "hull sources", err);
}

size_t fb_hull_source_gallery_count(const fb_hull_source_gallery *g)
{
  return g ? g->reg.n : 0;
}

const fb_hull_source *fb_hull_source_gallery_at(const fb_hull_source_gallery *g, size_t i)
{
  return fb_registry_at(g ? &g->reg : NULL, i);
}

const fb_hull_source *fb_hull_source_gallery_find(const fb_hull_source_gallery *g,
                                                  const char *name)
{
  return fb_registry_find(g ? &g->reg : NULL, name);
}

void fb_hull_source_gallery_free(fb_hull_source_gallery **g)
{
  if (!g || !*g)
    return;
  fb_registry_release(&(*g)->reg);
  free(*g);
  *g = NULL;
}
