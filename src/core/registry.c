/* SPDX-License-Identifier: BSD-3-Clause */
/* The set of named entries behind a gallery (core/registry.h). */
#include "core/registry.h"

#include <stdlib.h>
#include <string.h>

#include "core/util.h"

/* An entry's name: its first member. */
static const char *registry_name(const void *entry)
{
  return *(const char *const *)entry;
}

int fb_registry_add(fb_registry *r, const void *entry, const char *what, fb_err *err)
{
  if (fb_grow((void **)&r->entry, &r->cap, r->n, sizeof *r->entry))
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu %s", r->n + 1, what);
  r->entry[r->n++] = entry;
  return FB_OK;
}

const void *fb_registry_at(const fb_registry *r, size_t i)
{
  return r && i < r->n ? r->entry[i] : NULL;
}

const void *fb_registry_find(const fb_registry *r, const char *name)
{
  for (size_t i = 0; r && name && i < r->n; ++i)
    if (!strcmp(registry_name(r->entry[i]), name))
      return r->entry[i];
  return NULL;
}

void fb_registry_release(fb_registry *r)
{
  free((void *)r->entry);
  r->entry = NULL;
  r->n = r->cap = 0;
}

static int entry_fail(const fb_registry_entry *e, const char *what, fb_err *err)
{
  return fb_err_set(err, FB_EINVAL, "%s %s: %s", e->kind, e->name ? e->name : "(unnamed)",
                    what);
}

int fb_registry_entry_check(const fb_registry_entry *e, fb_err *err)
{
  if (!fb_is_identifier(e->name))
    return entry_fail(e, "a name is letters, digits and '_', not from a digit", err);
  if (!e->doc || !e->doc[0] || (e->wants_meaning && (!e->meaning || !e->meaning[0])))
    return entry_fail(
        e, e->wants_meaning ? "undocumented (doc and meaning)" : "undocumented (doc)", err);
  if (e->params_size > e->params_max) {
    fb_err_set(err, FB_EINVAL, "%s %s: its parameter block exceeds %s", e->kind, e->name,
               e->params_max_name);
    return FB_EINVAL;
  }
  if (e->nparams && !e->param)
    return entry_fail(e, "parameters counted but not declared", err);
  if (e->ops_fault)
    return entry_fail(e, e->ops_fault, err);
  if (e->scalar_only && !fb_params_scalar(e->param, e->nparams))
    return entry_fail(e, "its parameters are numbers or choices (no files, no lists)", err);
  if (fb_params_declared(e->param, e->nparams, e->params_size, err))
    return fb_err_prefix(err, "%s %s: ", e->kind, e->name), FB_EINVAL;
  return FB_OK;
}
