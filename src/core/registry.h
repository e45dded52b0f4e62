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
#include "flexbond/param.h"

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

/* What every gallery entry declares, as fb_registry_entry_check reads it:
 * the gallery's words for an entry ("damper law"), the entry's name,
 * documentation and parameters, and the fault its gallery finds in its
 * ops by its own rule (NULL: none). */
typedef struct fb_registry_entry {
  const char *kind;
  const char *name, *doc, *meaning;
  int wants_meaning; /* a report's phrase (meaning) is required */
  const fb_param *param;
  size_t nparams, params_size;
  size_t params_max;           /* the gallery's block size */
  const char *params_max_name; /* its macro, for the message */
  int scalar_only;             /* numbers and choices only (no files, no lists) */
  const char *ops_fault;
} fb_registry_entry;

/* 0 if e is a sound entry: a well-formed name, documentation, a block
 * that fits, declared parameters that are sound (fb_params_declared) and
 * scalar where asked, and no ops fault. FB_EINVAL "KIND NAME: what"
 * otherwise: the first fault in that order. */
int fb_registry_entry_check(const fb_registry_entry *e, fb_err *err);

#endif
