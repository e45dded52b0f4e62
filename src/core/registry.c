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
