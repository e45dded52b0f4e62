/* SPDX-License-Identifier: BSD-3-Clause */
/* The damper gallery (flexbond/damper.h): the soundness of a damper law,
 * its parameter blocks, and the set of laws a description may name. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/damper.h"

#include "core/registry.h"
#include "core/util.h"

/* The built-in laws, one line each; the first is a corner's default. */
static const fb_damper_law *const gallery_builtin[] = {
    &fb_damper_law_linear,
    &fb_damper_law_table,
};

struct fb_damper_gallery {
  fb_registry reg; /* the laws */
};

/* The registry reads an entry's name as its first member. */
_Static_assert(offsetof(fb_damper_law, name) == 0, "a damper law's name is its first member");

static int law_fail(fb_err *err, const fb_damper_law *l, const char *what)
{
  return fb_err_set(err, FB_EINVAL, "damper law %s: %s", l && l->name ? l->name : "(unnamed)",
                    what);
}

int fb_damper_law_check(const fb_damper_law *l, fb_err *err)
{
  const fb_registry_entry none = {.kind = "damper law"};
  if (!l)
    return fb_registry_entry_check(&none, err);
  const fb_registry_entry e = {
      "damper law",
      l->name,
      l->doc,
      l->meaning,
      1,
      l->param,
      l->nparams,
      l->params_size,
      FB_DAMPER_PARAMS_MAX,
      "FB_DAMPER_PARAMS_MAX",
      1,
      l->ops && l->ops->build && l->ops->force
          ? NULL
          : "a law builds its element and gives its force (build, force)"};
  return fb_registry_entry_check(&e, err);
}

void fb_damper_params_init(const fb_damper_law *l, fb_damper_params *p)
{
  memset(p, 0, sizeof *p);
  fb_params_defaults(l->param, l->nparams, p->bytes);
  if (l->ops->init)
    l->ops->init(p->bytes);
}

int fb_damper_gallery_new(fb_damper_gallery **out, fb_err *err)
{
  *out = NULL;
  fb_damper_gallery *g = calloc(1, sizeof *g);
  if (!g)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a damper gallery");
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < sizeof gallery_builtin / sizeof gallery_builtin[0]; ++i)
    rc = fb_damper_gallery_add(g, gallery_builtin[i], err);
  if (rc)
    fb_damper_gallery_free(&g);
  *out = g;
  return rc;
}

int fb_damper_gallery_add(fb_damper_gallery *g, const fb_damper_law *l, fb_err *err)
{
  int rc = fb_damper_law_check(l, err);
  if (rc)
    return rc;
  if (fb_damper_gallery_find(g, l->name))
    return law_fail(err, l, "a law of that name is already in the gallery");
  return fb_registry_add(&g->reg, l, "damper laws", err);
}

size_t fb_damper_gallery_count(const fb_damper_gallery *g)
{
  return g ? g->reg.n : 0;
}

const fb_damper_law *fb_damper_gallery_at(const fb_damper_gallery *g, size_t i)
{
  return fb_registry_at(g ? &g->reg : NULL, i);
}

const fb_damper_law *fb_damper_gallery_find(const fb_damper_gallery *g, const char *name)
{
  return fb_registry_find(g ? &g->reg : NULL, name);
}

void fb_damper_gallery_free(fb_damper_gallery **g)
{
  if (!g || !*g)
    return;
  fb_registry_release(&(*g)->reg);
  free(*g);
  *g = NULL;
}
