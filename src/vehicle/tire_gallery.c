/* SPDX-License-Identifier: BSD-3-Clause */
/* The tire gallery (flexbond/tire.h): the soundness of a tire model, its
 * parameter blocks, and the set of models a description may name. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/tire.h"

#include "core/registry.h"
#include "core/util.h"

/* The built-in models, one line each; the first is a corner's default. */
static const fb_tire_model *const gallery_builtin[] = {
    &fb_tire_model_bilateral,
    &fb_tire_model_unilateral,
    &fb_tire_model_hunt_crossley,
    &fb_tire_model_table,
};

struct fb_tire_gallery {
  fb_registry reg; /* the models */
};

/* The registry reads an entry's name as its first member. */
_Static_assert(offsetof(fb_tire_model, name) == 0, "a tire model's name is its first member");

static int model_fail(fb_err *err, const fb_tire_model *m, const char *what)
{
  return fb_err_set(err, FB_EINVAL, "tire model %s: %s", m && m->name ? m->name : "(unnamed)",
                    what);
}

int fb_tire_model_check(const fb_tire_model *m, fb_err *err)
{
  const fb_registry_entry none = {.kind = "tire model"};
  if (!m)
    return fb_registry_entry_check(&none, err);
  const char *ops = !m->ops || !m->ops->build ? "a model builds its tire (build)"
                    : m->in_contact == m      ? "in_contact names another model (NULL: itself)"
                                              : NULL;
  const fb_registry_entry e = {"tire model",
                               m->name,
                               m->doc,
                               m->meaning,
                               1,
                               m->param,
                               m->nparams,
                               m->params_size,
                               FB_TIRE_PARAMS_MAX,
                               "FB_TIRE_PARAMS_MAX",
                               1,
                               ops};
  return fb_registry_entry_check(&e, err);
}

void fb_tire_params_init(const fb_tire_model *m, fb_tire_params *p)
{
  memset(p, 0, sizeof *p);
  fb_params_defaults(m->param, m->nparams, p->bytes);
  if (m->ops->init)
    m->ops->init(p->bytes);
}

int fb_tire_gallery_new(fb_tire_gallery **out, fb_err *err)
{
  *out = NULL;
  fb_tire_gallery *g = calloc(1, sizeof *g);
  if (!g)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a tire gallery");
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < sizeof gallery_builtin / sizeof gallery_builtin[0]; ++i)
    rc = fb_tire_gallery_add(g, gallery_builtin[i], err);
  if (rc)
    fb_tire_gallery_free(&g);
  *out = g;
  return rc;
}

int fb_tire_gallery_add(fb_tire_gallery *g, const fb_tire_model *m, fb_err *err)
{
  int rc = fb_tire_model_check(m, err);
  if (rc)
    return rc;
  if (fb_tire_gallery_find(g, m->name))
    return model_fail(err, m, "a model of that name is already in the gallery");
  return fb_registry_add(&g->reg, m, "tire models", err);
}

size_t fb_tire_gallery_count(const fb_tire_gallery *g)
{
  return g ? g->reg.n : 0;
}

const fb_tire_model *fb_tire_gallery_at(const fb_tire_gallery *g, size_t i)
{
  return fb_registry_at(g ? &g->reg : NULL, i);
}

const fb_tire_model *fb_tire_gallery_find(const fb_tire_gallery *g, const char *name)
{
  return fb_registry_find(g ? &g->reg : NULL, name);
}

void fb_tire_gallery_free(fb_tire_gallery **g)
{
  if (!g || !*g)
    return;
  fb_registry_release(&(*g)->reg);
  free(*g);
  *g = NULL;
}
