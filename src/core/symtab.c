/* SPDX-License-Identifier: BSD-3-Clause */
/* Table of named parameters for expressions (see flexbond/expr.h).
 *
 * Entries are kept in definition order in one growable array and looked up
 * by linear search: models have tens of parameters, and the order is needed
 * by fb_symtab_name anyway. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/expr.h"

#include "core/util.h"

typedef struct symtab_entry {
  char *name;
  double value;
} symtab_entry;

struct fb_symtab {
  symtab_entry *entries;
  size_t count;
  size_t capacity;
};

int fb_symtab_new(fb_symtab **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "fb_symtab_new: out is NULL");
  *out = calloc(1, sizeof **out);
  if (!*out)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating a symbol table");
  return FB_OK;
}

void fb_symtab_free(fb_symtab **tab)
{
  if (!tab || !*tab)
    return;
  for (size_t i = 0; i < (*tab)->count; ++i)
    free((*tab)->entries[i].name);
  free((*tab)->entries);
  free(*tab);
  *tab = NULL;
}

/* Index of name in tab, or tab->count if absent. */
static size_t symtab_find(const fb_symtab *tab, const char *name)
{
  size_t i = 0;
  while (i < tab->count && strcmp(tab->entries[i].name, name) != 0)
    ++i;
  return i;
}

/* Makes room for one more entry. */
static int symtab_reserve(fb_symtab *tab, fb_err *err)
{
  if (tab->count < tab->capacity)
    return FB_OK;
  size_t capacity = tab->capacity ? 2 * tab->capacity : 8;
  symtab_entry *entries = realloc(tab->entries, capacity * sizeof *entries);
  if (!entries)
    return fb_err_set(err, FB_ENOMEM, "out of memory growing a symbol table");
  tab->entries = entries;
  tab->capacity = capacity;
  return FB_OK;
}

/* Names must be identifiers (otherwise no expression could refer to them)
 * and values finite (a NaN parameter would silently poison every result). */
int fb_symtab_set(fb_symtab *tab, const char *name, double value, fb_err *err)
{
  if (!tab || !name)
    return fb_err_set(err, FB_EINVAL, "fb_symtab_set: table or name is NULL");
  if (!fb_is_identifier(name))
    return fb_err_set(err, FB_EINVAL,
                      "invalid parameter name '%s' (use letters, digits and '_', "
                      "not starting with a digit)",
                      name);
  if (!isfinite(value))
    return fb_err_set(err, FB_EINVAL, "parameter '%s' is not finite (got %g)", name, value);
  size_t i = symtab_find(tab, name);
  if (i < tab->count) {
    tab->entries[i].value = value;
    return FB_OK;
  }
  int status = symtab_reserve(tab, err);
  if (status != FB_OK)
    return status;
  char *copy = strdup(name);
  if (!copy)
    return fb_err_set(err, FB_ENOMEM, "out of memory defining parameter '%s'", name);
  tab->entries[tab->count].name = copy;
  tab->entries[tab->count].value = value;
  ++tab->count;
  return FB_OK;
}

/* tab may be NULL (an empty table). */
int fb_symtab_get(const fb_symtab *tab, const char *name, double *value)
{
  if (!tab || !name)
    return 0;
  size_t i = symtab_find(tab, name);
  if (i == tab->count)
    return 0;
  if (value)
    *value = tab->entries[i].value;
  return 1;
}

int fb_symtab_merge(fb_symtab *dst, const fb_symtab *src, fb_err *err)
{
  if (!dst)
    return fb_err_set(err, FB_EINVAL, "fb_symtab_merge: destination is NULL");
  size_t n = fb_symtab_size(src);
  for (size_t i = 0; i < n; ++i) {
    int status = fb_symtab_set(dst, src->entries[i].name, src->entries[i].value, err);
    if (status != FB_OK)
      return status;
  }
  return FB_OK;
}

size_t fb_symtab_size(const fb_symtab *tab)
{
  return tab ? tab->count : 0;
}

const char *fb_symtab_name(const fb_symtab *tab, size_t i)
{
  return i < fb_symtab_size(tab) ? tab->entries[i].name : NULL;
}
