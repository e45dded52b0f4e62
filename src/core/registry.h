/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal: the set of named entries behind a gallery (a road gallery,
 * a tire gallery): borrowed entries in the order added, found by name.
 * An entry's first member is its name (const char *), as every gallery
 * entry of flexbond's headers declares it; the registry reads nothing
 * else of it. */
#ifndef FLEXBOND_CORE_REGISTRY_H
#define FLEXBOND_CORE_REGISTRY_H

#include <stddef.h>

#include "flexbond/error.h"

typedef struct fb_registry {
  const void **entry; /* borrowed entries, owned array */
  size_t n, cap;
} fb_registry;

/* Appends entry (borrowed); FB_ENOMEM, naming what, leaves r as it was.
 * The caller has checked the entry and that its name is free. */
int fb_registry_add(fb_registry *r, const void *entry, const char *what, fb_err *err);
/* Entry i, NULL out of range (r may be NULL). */
const void *fb_registry_at(const fb_registry *r, size_t i);
/* The entry named name, NULL if none (r may be NULL). */
const void *fb_registry_find(const fb_registry *r, const char *name);
/* Frees the array; r is empty again. */
void fb_registry_release(fb_registry *r);

#endif
