/* The schema engine (io/schema.h): a YAML document read, a struct
 * checked and visited, and the reference tables written, all from one
 * table of keys. */
#include "io/schema.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/textfile.h"
#include "core/util.h"

/* Longest key path, and most keys one mapping may have. */
enum { SCH_PATH_MAX = 256, SCH_MAX_CHILDREN = 48 };

/* ---- Paths. */

/* The name of k if it is a direct child of the mapping at table path
 * pre ("" the table's root), else NULL. */
static const char *sch_child_name(const sch_key *k, const char *pre)
{
  const size_t n = strlen(pre);
  const char *rest = k->path;
  if (n) {
    if (strncmp(rest, pre, n) != 0 || rest[n] != '.')
      return NULL;
    rest += n + 1;
  }
  return strchr(rest, '.') ? NULL : rest;
}

/* "a.b" from "a" and "b" ("b" alone when a is empty) into buf. */
static void sch_join(char *buf, size_t size, const char *a, const char *b)
{
  snprintf(buf, size, "%s%s%s", a, *a ? "." : "", b);
}

/* ---- Origins. */

static void sch_origin_release(sch_origin *o)
{
  free(o->key);
  free(o->path);
}

void sch_reader_release(sch_reader *r)
{
  for (size_t i = 0; i < r->norigins; ++i)
    sch_origin_release(&r->origin[i]);
  free(r->origin);
  r->origin = NULL;
  r->norigins = r->cap = 0;
}

/* Appends an origin (key and path copied). */
static int sch_add(sch_reader *r, const char *key, const char *path, int line, int column,
                   int given, double number)
{
  sch_origin o = {fb_strdup(key), fb_strdup(path), line, column, given, number};
  if (!o.key || !o.path || fb_grow((void **)&r->origin, &r->cap, r->norigins, sizeof o)) {
    sch_origin_release(&o);
    return fb_err_set(r->c->err, FB_ENOMEM, "out of memory recording where '%s' is", path);
  }
  r->origin[r->norigins++] = o;
  return FB_OK;
}

/* Appends the origin of the value at node, path its key and path. */
static int sch_add_at(sch_reader *r, const char *path, struct fy_node *node, int given,
                      double number)
{
  int line = 0, column = 0;
  ml_mark(node, &line, &column);
  return sch_add(r, path, path, line, column, given, number);
}

int sch_record(sch_reader *r, const char *key, struct fy_node *node)
{
  return sch_add_at(r, key, node, 1, 0.0);
}

const sch_origin *sch_origin_find(const sch_reader *r, const char *key)
{
  for (size_t i = r->norigins; i-- > 0;)
    if (!strcmp(r->origin[i].key, key))
      return &r->origin[i];
  return NULL;
}

int sch_origins_relabel(sch_reader *r, size_t mark, const char *item_path, const char *prefix,
                        int copy)
{
  const size_t n = strlen(item_path), end = r->norigins;
  for (size_t i = mark; i < end; ++i) {
    const char *key = r->origin[i].key;
    if (strncmp(key, item_path, n) != 0 || (key[n] && key[n] != '.' && key[n] != '['))
      continue;
    char renamed[SCH_PATH_MAX];
    snprintf(renamed, sizeof renamed, "%s%s", prefix, key + n);
    if (copy) {
      const sch_origin *o = &r->origin[i];
      int rc = sch_add(r, renamed, o->path, o->line, o->column, o->given, o->number);
      if (rc)
        return rc;
      continue;
    }
    char *dup = fb_strdup(renamed);
    if (!dup)
      return fb_err_set(r->c->err, FB_ENOMEM, "out of memory naming '%s'", renamed);
    free(r->origin[i].key);
    r->origin[i].key = dup;
  }
  return FB_OK;
}

/* ---- Reading. */

/* A mapping being read: where it is in the table and in the file. */
typedef struct sch_frame {
  const sch_table *t;
  const char *pre;       /* its table path, "" for the table's root */
  struct fy_node *map;   /* NULL: left out (its keys take their defaults) */
  struct fy_node *where; /* the nearest mapping written, for defaults */
  const char *file_path; /* its key path in the file, "" for the root */
  void *base;
} sch_frame;

static int sch_read_map(sch_reader *r, const sch_frame *f);

/* Every key of the mapping is one the table gives it. */
static int sch_check_children(const sch_reader *r, const sch_frame *f)
{
  const char *names[SCH_MAX_CHILDREN + 1];
  size_t n = 0;
  for (size_t i = 0; i < f->t->n && n < SCH_MAX_CHILDREN; ++i) {
    const char *name = sch_child_name(&f->t->key[i], f->pre);
    if (name)
      names[n++] = name;
  }
  names[n] = NULL;
  return ml_check_keys(r->c, f->map, names);
}

/* At most one key of each one_of group written; one if all are required. */
static int sch_check_groups(const sch_reader *r, const sch_frame *f)
{
  for (size_t i = 0; i < f->t->n; ++i) {
    const sch_key *k = &f->t->key[i];
    const char *name = sch_child_name(k, f->pre);
    if (!name || !k->one_of)
      continue;
    const char *first = NULL, *list[8];
    size_t n = 0;
    int required = 1;
    for (size_t j = 0; j < f->t->n; ++j) {
      const sch_key *o = &f->t->key[j];
      const char *other = sch_child_name(o, f->pre);
      if (!other || !o->one_of || strcmp(o->one_of, k->one_of) != 0)
        continue;
      if (j < i)
        break; /* the group was checked at its first key */
      required = required && o->need == SCH_REQUIRED;
      if (n < 8)
        list[n++] = other;
      struct fy_node *key = NULL;
      ml_get(f->map, other, &key);
      if (key && first)
        return ml_fail_key(r->c, f->map, key, FB_EPARSE, "give either '%s' or '%s', not both",
                           first, other);
      if (key)
        first = other;
    }
    if (!first && required && n > 0) {
      char names[256] = "";
      size_t len = 0;
      for (size_t j = 0; j < n; ++j) {
        int w = snprintf(names + len, sizeof names - len, "%s'%s'", j ? ", " : "", list[j]);
        len = w > 0 && len + (size_t)w < sizeof names ? len + (size_t)w : len;
      }
      return ml_fail(r->c, f->map, FB_EPARSE, "missing one of %s", names);
    }
  }
  return FB_OK;
}

static void *sch_at(void *base, size_t offset)
{
  return (char *)base + offset;
}

/* Stores a number (in the file's unit) as k says. */
static void sch_store_number(const sch_key *k, double v, void *base)
{
  void *p = sch_at(base, k->offset);
  switch (k->store) {
  case SCH_STORE_DOUBLE:
    *(double *)p = k->ops && k->ops->to_struct ? k->ops->to_struct(v) : v;
    break;
  case SCH_STORE_INT: *(int *)p = (int)v; break;
  case SCH_STORE_LONG: *(long *)p = (long)v; break;
  case SCH_STORE_SIZE: *(size_t *)p = (size_t)v; break;
  case SCH_STORE_U64: *(uint64_t *)p = (uint64_t)v; break;
  default: break;
  }
}

/* Stores a copy of text (NULL stores NULL). */
static int sch_store_text(const sch_reader *r, const sch_key *k, const char *text, void *base)
{
  if (k->store != SCH_STORE_STRING)
    return FB_OK;
  char **p = sch_at(base, k->offset);
  char *copy = text ? fb_strdup(text) : NULL;
  if (text && !copy)
    return fb_err_set(r->c->err, FB_ENOMEM, "out of memory reading %s", k->path);
  free(*p);
  *p = copy;
  return FB_OK;
}

/* The index of text among k's choices, or an error naming them. */
static int sch_choice(const sch_reader *r, const sch_key *k, struct fy_node *node, double *out)
{
  const char *text = NULL;
  int rc = ml_string(r->c, node, &text);
  if (rc)
    return rc;
  char list[256] = "";
  size_t len = 0;
  for (size_t i = 0; k->choices[i]; ++i) {
    if (!strcmp(text, k->choices[i])) {
      *out = (double)i;
      return FB_OK;
    }
    int w = snprintf(list + len, sizeof list - len, "%s%s", i ? " | " : "", k->choices[i]);
    len = w > 0 && len + (size_t)w < sizeof list ? len + (size_t)w : len;
  }
  const char *near = ml_suggest_list(text, k->choices);
  char hint[96] = "";
  if (near)
    snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
  return ml_fail(r->c, node, FB_EPARSE, "unknown value '%s'%s; expected %s", text, hint, list);
}

/* k's whole-number range as [lo, hi]. */
static void sch_whole_range(const sch_key *k, size_t *lo, size_t *hi)
{
  *lo = k->bounds & SCH_LO ? (size_t)k->lo + (k->bounds & SCH_LO_OPEN ? 1 : 0) : 0;
  *hi = k->bounds & SCH_HI ? (size_t)k->hi - (k->bounds & SCH_HI_OPEN ? 1 : 0) : SIZE_MAX;
}

/* A list of numbers: empty allowed when min_items is 0. */
static int sch_numbers(const sch_reader *r, const sch_key *k, struct fy_node *node, double **v,
                       size_t *n)
{
  *v = NULL;
  *n = 0;
  if (fy_node_is_sequence(node) && fy_node_sequence_item_count(node) == 0 && !k->min_items)
    return FB_OK;
  const size_t want = k->min_items == k->max_items ? k->min_items : 0;
  int rc = ml_vector(r->c, node, r->c->globals, want, 0, v, n);
  if (!rc && k->max_items && *n > k->max_items)
    rc = ml_fail(r->c, node, FB_EINVAL, "at most %zu numbers (got %zu)", k->max_items, *n);
  if (!rc && *n < k->min_items)
    rc = ml_fail(r->c, node, FB_EINVAL, "at least %zu numbers (got %zu)", k->min_items, *n);
  return rc;
}

/* A value written at node: read, recorded, stored. */
/* Appends " (why)" to a range error's message: why the range is so. */
static void sch_add_why(fb_err *err, const char *why)
{
  if (!err)
    return;
  const size_t len = strlen(err->msg);
  snprintf(err->msg + len, sizeof err->msg - len, " (%s)", why);
}

static int sch_read_value(sch_reader *r, const sch_key *k, struct fy_node *node,
                          const char *path, void *base)
{
  ml_ctx *c = r->c;
  double number = 0.0;
  const char *text = NULL;
  char *resolved = NULL;
  int rc = FB_OK;
  switch (k->type) {
  case SCH_NUMBER: rc = ml_number(c, node, c->globals, &number); break;
  case SCH_WHOLE: {
    size_t lo = 0, hi = 0, v = 0;
    sch_whole_range(k, &lo, &hi);
    rc = ml_count(c, node, c->globals, lo, hi, &v);
    if (rc == FB_EINVAL && k->why)
      sch_add_why(c->err, k->why);
    number = (double)v;
    break;
  }
  case SCH_CHOICE: rc = sch_choice(r, k, node, &number); break;
  case SCH_NAME: rc = ml_name(c, node, k->doc, &text); break;
  case SCH_TEXT: rc = k->lines ? ml_text(c, node, &text) : ml_string(c, node, &text); break;
  case SCH_FILE:
    rc = ml_string(c, node, &text);
    if (!rc)
      rc = ml_resolve_path(c, node, text, &resolved);
    text = resolved;
    break;
  default: break;
  }
  if (!rc)
    rc = sch_add_at(r, path, node, 1, number);
  if (!rc && (k->type == SCH_CHOICE || k->type == SCH_NUMBER || k->type == SCH_WHOLE))
    sch_store_number(k, number, base);
  else if (!rc)
    rc = sch_store_text(r, k, text, base);
  free(resolved);
  if (!rc && k->type == SCH_NUMBERS) {
    double *v = NULL;
    size_t n = 0;
    rc = sch_numbers(r, k, node, &v, &n);
    if (!rc && k->ops && k->ops->store_list)
      rc = k->ops->store_list(r, k, node, v, n, base);
    free(v);
  }
  if (!rc && k->type == SCH_CUSTOM && k->ops && k->ops->read)
    rc = k->ops->read(r, k, node, base);
  return rc;
}

/* A value left out: its default or inherited value, or nothing. */
static int sch_read_absent(sch_reader *r, const sch_frame *f, const sch_key *k,
                           const char *name, const char *path)
{
  int line = 0, column = 0;
  ml_mark(f->where, &line, &column);
  if (k->need == SCH_REQUIRED && f->map)
    return ml_fail(r->c, f->map, FB_EPARSE, "missing required key '%s'", name);
  if (k->need == SCH_DEFAULT) {
    int rc = sch_add(r, path, path, line, column, 0, k->def);
    if (!rc && k->type == SCH_NUMBERS && k->ops && k->ops->store_list)
      rc = k->ops->store_list(r, k, NULL, k->def_list, k->min_items, f->base);
    if (!rc && k->type != SCH_NUMBERS)
      sch_store_number(k, k->def, f->base);
    return rc;
  }
  if (k->need != SCH_INHERIT)
    return FB_OK;
  const sch_origin *from = sch_origin_find(r, k->inherit);
  if (!from)
    return ml_fail(r->c, f->map ? f->map : f->where, FB_EPARSE,
                   "missing required key '%s' (nor is there a %s to take it from)", path,
                   k->inherit);
  const sch_origin o = *from; /* sch_add may move the array */
  int rc = sch_add(r, path, o.path, o.line, o.column, o.given, o.number);
  if (!rc)
    sch_store_number(k, o.number, f->base);
  return rc;
}

/* The items of a list written at node. */
static int sch_read_list(sch_reader *r, const sch_frame *f, const sch_key *k,
                         struct fy_node *node, const char *path)
{
  int rc = ml_expect_seq(r->c, node, k->doc);
  const size_t count = rc ? 0 : (size_t)fy_node_sequence_item_count(node);
  if (!rc && count < k->min_items)
    rc = ml_fail(r->c, node, FB_EINVAL, "at least %zu items (got %zu)", k->min_items, count);
  if (!rc && k->max_items && count > k->max_items)
    rc = ml_fail(r->c, node, FB_EINVAL, "at most %zu items (got %zu)", k->max_items, count);
  for (size_t i = 0; !rc && i < count; ++i) {
    struct fy_node *item = fy_node_sequence_get_by_index(node, (int)i);
    char item_path[SCH_PATH_MAX + 24];
    snprintf(item_path, sizeof item_path, "%s[%zu]", path, i);
    void *item_base = NULL;
    const size_t mark = r->norigins;
    rc = ml_expect_map(r->c, item, k->doc);
    if (!rc)
      rc = k->ops->item_begin(r, k, i, count, f->base, &item_base);
    if (!rc)
      rc = sch_add_at(r, item_path, item, 1, 0.0);
    const sch_frame in = {k->items, "", item, item, item_path, item_base};
    if (!rc)
      rc = sch_read_map(r, &in);
    if (!rc && k->items->done)
      rc = k->items->done(r, item, item_base);
    if (!rc && k->ops->item_end)
      rc = k->ops->item_end(r, k, item, item_path, mark, f->base, item_base);
  }
  return rc;
}

/* One key of the mapping f. */
static int sch_read_key(sch_reader *r, const sch_frame *f, const sch_key *k, const char *name)
{
  struct fy_node *key = NULL;
  struct fy_node *node = f->map ? ml_get(f->map, name, &key) : NULL;
  char path[SCH_PATH_MAX];
  sch_join(path, sizeof path, f->file_path, name);
  /* An alternative not written is not read at all. */
  if (k->one_of && !key)
    return FB_OK;
  if (key && ml_is_null(node))
    return ml_fail_key(r->c, f->map, key, FB_EPARSE, "missing value");
  if (k->type == SCH_SECTION) {
    int rc = !key && k->need == SCH_REQUIRED && f->map
                 ? ml_fail(r->c, f->map, FB_EPARSE, "missing required key '%s'", name)
                 : FB_OK;
    if (!rc && key)
      rc = ml_expect_map(r->c, node, k->doc);
    if (!rc && key)
      rc = sch_add_at(r, path, node, 1, 0.0);
    const sch_frame in = {f->t, k->path, key ? node : NULL, key ? node : f->where,
                          path, f->base};
    if (!rc)
      rc = sch_read_map(r, &in);
    if (!rc && k->ops && k->ops->done)
      rc = k->ops->done(r, k, key ? node : NULL, f->base);
    return rc;
  }
  if (k->type == SCH_LIST) {
    if (key)
      return sch_read_list(r, f, k, node, path);
    return k->need == SCH_REQUIRED && f->map
               ? ml_fail(r->c, f->map, FB_EPARSE, "missing required key '%s'", name)
               : FB_OK;
  }
  return key ? sch_read_value(r, k, node, path, f->base) : sch_read_absent(r, f, k, name, path);
}

static int sch_read_map(sch_reader *r, const sch_frame *f)
{
  int rc = FB_OK;
  if (f->map)
    rc = sch_check_children(r, f);
  if (!rc && f->map)
    rc = sch_check_groups(r, f);
  for (size_t i = 0; !rc && i < f->t->n; ++i) {
    const char *name = sch_child_name(&f->t->key[i], f->pre);
    if (name)
      rc = sch_read_key(r, f, &f->t->key[i], name);
  }
  return rc;
}

int sch_read(sch_reader *r, const sch_table *t, struct fy_node *root, void *base)
{
  int rc = ml_expect_map(r->c, root, "a mapping of keys");
  const sch_frame f = {t, "", root, root, "", base};
  if (!rc)
    rc = sch_read_map(r, &f);
  if (!rc && t->done)
    rc = t->done(r, root, base);
  return rc;
}

/* ---- Values of a struct. */

static const void *sch_at_const(const void *base, size_t offset)
{
  return (const char *)base + offset;
}

/* The stored value of k in the file's unit. */
static double sch_load_number(const sch_key *k, const void *base)
{
  const void *p = sch_at_const(base, k->offset);
  switch (k->store) {
  case SCH_STORE_DOUBLE: {
    const double v = *(const double *)p;
    return k->ops && k->ops->from_struct ? k->ops->from_struct(v) : v;
  }
  case SCH_STORE_INT: return *(const int *)p;
  case SCH_STORE_LONG: return (double)*(const long *)p;
  case SCH_STORE_SIZE: return (double)*(const size_t *)p;
  case SCH_STORE_U64: return (double)*(const uint64_t *)p;
  default: return 0.0;
  }
}

/* The number of choices of k. */
static size_t sch_nchoices(const sch_key *k)
{
  size_t n = 0;
  while (k->choices && k->choices[n])
    ++n;
  return n;
}

/* The value of k in base as an sch_value; 0 if k stores nothing to see. */
static int sch_value_of(const sch_key *k, const void *base, const char *path, sch_value *v)
{
  *v = (sch_value){k, path, base, 0.0, NULL};
  if (k->type == SCH_CUSTOM || k->type == SCH_NUMBERS)
    return k->ops && k->ops->format;
  if (k->store == SCH_STORE_NONE)
    return 0;
  if (k->store == SCH_STORE_STRING) {
    v->text = *(char *const *)sch_at_const(base, k->offset);
    return v->text != NULL;
  }
  v->number = sch_load_number(k, base);
  if (k->type == SCH_CHOICE && v->number >= 0 && v->number < (double)sch_nchoices(k))
    v->text = k->choices[(size_t)v->number];
  return 1;
}

static int sch_each_in(const sch_table *t, const char *pre, const void *base, const char *lp,
                       sch_value_fn fn, void *ctx);

/* The items of the list k (the first of its view in t). */
static int sch_each_item(const sch_table *t, const sch_key *k, const void *base,
                         sch_value_fn fn, void *ctx)
{
  for (const sch_key *o = t->key; o < k; ++o)
    if (o->type == SCH_LIST && o->view && k->view && !strcmp(o->view, k->view))
      return 0; /* visited with the first list of the view */
  if (!k->ops)
    return 0; /* a list's items are reached only through its ops */
  const size_t n = k->ops->count(base);
  int stop = 0;
  for (size_t i = 0; !stop && i < n; ++i) {
    const void *item = k->ops->item_at(base, i);
    const char *name = k->ops->item_name ? k->ops->item_name(item) : NULL;
    char lp[SCH_PATH_MAX];
    if (name)
      snprintf(lp, sizeof lp, "%s.%s", k->view, name);
    else
      snprintf(lp, sizeof lp, "%s[%zu]", k->view, i);
    stop = sch_each_in(k->items, "", item, lp, fn, ctx);
  }
  return stop;
}

static int sch_each_in(const sch_table *t, const char *pre, const void *base, const char *lp,
                       sch_value_fn fn, void *ctx)
{
  int stop = 0;
  for (size_t i = 0; !stop && i < t->n; ++i) {
    const sch_key *k = &t->key[i];
    const char *name = sch_child_name(k, pre);
    if (!name || (k->ops && k->ops->present && !k->ops->present(base)))
      continue;
    char path[SCH_PATH_MAX];
    sch_join(path, sizeof path, lp, name);
    sch_value v;
    if (k->type == SCH_SECTION)
      stop = sch_each_in(t, k->path, base, path, fn, ctx);
    else if (k->type == SCH_LIST)
      stop = sch_each_item(t, k, base, fn, ctx);
    else if (sch_value_of(k, base, path, &v))
      stop = fn(&v, ctx);
  }
  return stop;
}

int sch_each(const sch_table *t, const void *base, sch_value_fn fn, void *ctx)
{
  return sch_each_in(t, "", base, "", fn, ctx);
}

/* "> 0 N/m", "in [0, 0.5)" of k's range into buf. */
static void sch_range_text(const sch_key *k, char *buf, size_t size)
{
  const int lo = (k->bounds & SCH_LO) != 0, hi = (k->bounds & SCH_HI) != 0;
  const int lo_open = (k->bounds & SCH_LO_OPEN) != 0, hi_open = (k->bounds & SCH_HI_OPEN) != 0;
  if (lo && hi)
    snprintf(buf, size, "in %c%g, %g%c", lo_open ? '(' : '[', k->lo, k->hi,
             hi_open ? ')' : ']');
  else if (lo)
    snprintf(buf, size, "%s %g", lo_open ? ">" : ">=", k->lo);
  else if (hi)
    snprintf(buf, size, "%s %g", hi_open ? "<" : "<=", k->hi);
  else
    buf[0] = '\0';
}

/* 1 if the stored value x is inside k's range (bounds converted to the
 * stored unit, so a bound the conversion maps exactly is exact). */
static int sch_in_range(const sch_key *k, const void *base, double x)
{
  double (*to)(double) = k->ops ? k->ops->to_struct : NULL;
  if (k->store == SCH_STORE_DOUBLE && to)
    x = *(const double *)sch_at_const(base, k->offset);
  const double lo = to ? to(k->lo) : k->lo, hi = to ? to(k->hi) : k->hi;
  if ((k->bounds & SCH_LO) && !((k->bounds & SCH_LO_OPEN) ? x > lo : x >= lo))
    return 0;
  if ((k->bounds & SCH_HI) && !((k->bounds & SCH_HI_OPEN) ? x < hi : x <= hi))
    return 0;
  return 1;
}

int sch_check_value(const sch_value *v, fb_err *err)
{
  const sch_key *k = v->key;
  if (k->type == SCH_CHOICE && !v->text)
    return fb_err_set(err, FB_EINVAL, "unknown value %.0f", v->number),
           fb_err_set_key(err, "%s", v->path);
  if (k->type != SCH_NUMBER && k->type != SCH_WHOLE)
    return FB_OK;
  if (!isfinite(v->number))
    return fb_err_set(err, FB_EINVAL, "must be finite (got %g)", v->number),
           fb_err_set_key(err, "%s", v->path);
  if (sch_in_range(k, v->base, v->number))
    return FB_OK;
  char range[96];
  sch_range_text(k, range, sizeof range);
  fb_err_set(err, FB_EINVAL, "must be %s%s%s (got %.10g)%s%s%s", range, k->unit ? " " : "",
             k->unit ? k->unit : "", v->number, k->why ? " (" : "", k->why ? k->why : "",
             k->why ? ")" : "");
  return fb_err_set_key(err, "%s", v->path);
}

void sch_format(const sch_value *v, char *buf, size_t size)
{
  const sch_key *k = v->key;
  if ((k->type == SCH_CUSTOM || k->type == SCH_NUMBERS) && k->ops && k->ops->format)
    k->ops->format(k, v->base, buf, size);
  else if (v->text)
    snprintf(buf, size, "%s", v->text);
  else
    /* The shortest decimal that reads back as v: what the file wrote. */
    fb_format_shortest(v->number, 6, buf, size);
}

/* ---- Documentation. */

static const char *const sch_type_words[] = {
    [SCH_NUMBER] = "number",   [SCH_WHOLE] = "whole number", [SCH_CHOICE] = "choice",
    [SCH_NAME] = "name",       [SCH_TEXT] = "text",          [SCH_FILE] = "file",
    [SCH_NUMBERS] = "numbers", [SCH_SECTION] = "section",    [SCH_LIST] = "list",
    [SCH_CUSTOM] = "value"};

/* The type column: choices spelt out, a list's length. */
static void sch_type_text(const sch_key *k, char *buf, size_t size)
{
  buf[0] = '\0';
  if (k->type == SCH_CHOICE) {
    size_t len = 0;
    for (size_t i = 0; k->choices[i] && len + 1 < size; ++i) {
      len = fb_text_append(buf, size, len, "%s`%s`", i ? " \\| " : "", k->choices[i]);
    }
  } else if (k->type == SCH_CUSTOM && k->type_doc) {
    snprintf(buf, size, "%s", k->type_doc);
  } else if ((k->type == SCH_NUMBERS || k->type == SCH_LIST) && k->min_items == k->max_items &&
             k->min_items) {
    snprintf(buf, size, "%zu %s", k->min_items, sch_type_words[k->type]);
  } else if ((k->type == SCH_NUMBERS || k->type == SCH_LIST) &&
             (k->max_items || k->min_items)) {
    char hi[32] = "";
    if (k->max_items)
      snprintf(hi, sizeof hi, "%zu", k->max_items);
    snprintf(buf, size, "%s, %zu .. %s", sch_type_words[k->type], k->min_items,
             k->max_items ? hi : "any");
  } else {
    snprintf(buf, size, "%s", sch_type_words[k->type]);
  }
}

/* "exactly one of `a`, `b`": the keys of k's one_of group in t. */
static void sch_group_text(const sch_table *t, const sch_key *k, char *buf, size_t size)
{
  const char *dot = strrchr(k->path, '.');
  const size_t parent = dot ? (size_t)(dot - k->path) + 1 : 0;
  buf[0] = '\0';
  size_t len = fb_text_append(buf, size, 0, "exactly one of ");
  for (size_t i = 0, n = 0; i < t->n && len + 1 < size; ++i) {
    const sch_key *o = &t->key[i];
    if (!o->one_of || strcmp(o->one_of, k->one_of) != 0 ||
        strncmp(o->path, k->path, parent) != 0 || strchr(o->path + parent, '.'))
      continue;
    len = fb_text_append(buf, size, len, "%s`%s`", n++ ? ", " : "", o->path + parent);
  }
}

/* The default column. */
static void sch_default_text(const sch_table *t, const sch_key *k, char *buf, size_t size)
{
  if (k->one_of && k->need == SCH_REQUIRED)
    sch_group_text(t, k, buf, size);
  else if (k->need == SCH_REQUIRED)
    snprintf(buf, size, "required");
  else if (k->need == SCH_OPTIONAL)
    snprintf(buf, size, "optional");
  else if (k->need == SCH_INHERIT)
    snprintf(buf, size, "`%s`", k->inherit);
  else if (k->type == SCH_CHOICE)
    snprintf(buf, size, "`%s`", k->choices[(size_t)k->def]);
  else if (k->type == SCH_NUMBERS) {
    size_t len = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < k->min_items && len + 1 < size; ++i) {
      len = fb_text_append(buf, size, len, "%s%g", i ? ", " : "", k->def_list[i]);
    }
  } else
    snprintf(buf, size, "%g", k->def);
}

static void sch_markdown_head(FILE *fp, const char *title)
{
  fprintf(fp, "\n#### %s\n\n", title);
  fputs("| key | type | unit | range | default | meaning |\n", fp);
  fputs("|---|---|---|---|---|---|\n", fp);
}

static void sch_markdown_row(FILE *fp, const sch_table *t, const sch_key *k)
{
  char type[256], range[96], def[256];
  sch_type_text(k, type, sizeof type);
  sch_range_text(k, range, sizeof range);
  sch_default_text(t, k, def, sizeof def);
  fprintf(fp, "| `%s` | %s | %s | %s | %s | %s |\n", k->path, type, k->unit ? k->unit : "",
          range, def, k->doc);
}

/* 1 if the item table of list k was written with an earlier list's. */
static int sch_items_written(const sch_table *t, const sch_key *k)
{
  for (const sch_key *o = t->key; o < k; ++o)
    if (o->type == SCH_LIST && o->items == k->items)
      return 1;
  return 0;
}

/* The item table of list k (and of every list of t sharing it). */
static void sch_markdown_items(const sch_table *t, const sch_key *k, FILE *fp)
{
  char title[512] = "Each item of ";
  size_t len = strlen(title);
  for (const sch_key *o = k; o < t->key + t->n; ++o)
    if (o->type == SCH_LIST && o->items == k->items) {
      int w =
          snprintf(title + len, sizeof title - len, "%s`%s`", o == k ? "" : " and ", o->path);
      len = w > 0 && len + (size_t)w < sizeof title ? len + (size_t)w : len;
    }
  sch_markdown_head(fp, title);
  for (size_t i = 0; i < k->items->n; ++i)
    sch_markdown_row(fp, k->items, &k->items->key[i]);
  for (size_t i = 0; i < k->items->n; ++i) {
    const sch_key *in = &k->items->key[i];
    if (in->type == SCH_LIST && !sch_items_written(k->items, in))
      sch_markdown_items(k->items, in, fp);
  }
}

void sch_markdown(const sch_table *t, FILE *fp)
{
  sch_markdown_head(fp, "Top level");
  for (size_t i = 0; i < t->n; ++i)
    if (sch_child_name(&t->key[i], ""))
      sch_markdown_row(fp, t, &t->key[i]);
  for (size_t i = 0; i < t->n; ++i) {
    const sch_key *top = &t->key[i];
    if (top->type != SCH_SECTION || !sch_child_name(top, ""))
      continue;
    char title[128];
    snprintf(title, sizeof title, "`%s`", top->path);
    sch_markdown_head(fp, title);
    const size_t n = strlen(top->path);
    for (size_t j = 0; j < t->n; ++j)
      if (!strncmp(t->key[j].path, top->path, n) && t->key[j].path[n] == '.')
        sch_markdown_row(fp, t, &t->key[j]);
  }
  for (size_t i = 0; i < t->n; ++i)
    if (t->key[i].type == SCH_LIST && !sch_items_written(t, &t->key[i]))
      sch_markdown_items(t, &t->key[i], fp);
}
