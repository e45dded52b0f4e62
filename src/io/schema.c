/* SPDX-License-Identifier: BSD-3-Clause */
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

/* Most keys one mapping may have. */
enum { SCH_MAX_CHILDREN = 48 };

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

/* The names of t's keys in its mapping at table path pre, in table order,
 * into names (NULL-terminated, SCH_MAX_CHILDREN at most). */
static void sch_children(const sch_table *t, const char *pre, const char **names)
{
  size_t n = 0;
  for (size_t i = 0; i < t->n && n < SCH_MAX_CHILDREN; ++i) {
    const char *name = sch_child_name(&t->key[i], pre);
    if (name)
      names[n++] = name;
  }
  names[n] = NULL;
}

void sch_key_names(const sch_table *t, const char *pre, char *buf, size_t size)
{
  const char *names[SCH_MAX_CHILDREN + 1];
  size_t len = 0;
  sch_children(t, pre, names);
  buf[0] = '\0';
  for (size_t i = 0; names[i] && len + 1 < size; ++i)
    len = fb_text_append(buf, size, len, "%s%s", i ? ", " : "", names[i]);
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

/* Appends an origin (key and path copied; override, a label, borrowed). */
static int sch_add(sch_reader *r, const char *key, const char *path, int line, int column,
                   int given, double number, const char *override)
{
  sch_origin o = {fb_strdup(key), fb_strdup(path), line, column, given, number, override};
  if (!o.key || !o.path || fb_grow((void **)&r->origin, &r->cap, r->norigins, sizeof o)) {
    sch_origin_release(&o);
    return fb_err_set(r->c->err, FB_ENOMEM, "out of memory recording where '%s' is", path);
  }
  r->origin[r->norigins++] = o;
  return FB_OK;
}

/* Appends the origin of the value at node, path its key and path. */
static int sch_add_at(sch_reader *r, const char *path, struct fy_node *node, int given,
                      double number, const char *override)
{
  int line = 0, column = 0;
  ml_mark(node, &line, &column);
  return sch_add(r, path, path, line, column, given, number, override);
}

int sch_record(sch_reader *r, const char *key, struct fy_node *node)
{
  return sch_add_at(r, key, node, 1, 0.0, NULL);
}

const sch_origin *sch_origin_find(const sch_reader *r, const char *key)
{
  for (size_t i = r->norigins; i-- > 0;)
    if (!strcmp(r->origin[i].key, key))
      return &r->origin[i];
  return NULL;
}

int sch_origin_inherit(sch_reader *r, const char *key, const char *from)
{
  const sch_origin *o = sch_origin_find(r, from);
  if (!o)
    return fb_err_set(r->c->err, FB_EINVAL, "no value at %s to inherit", from);
  const sch_origin copy = *o; /* sch_add may move the array */
  return sch_add(r, key, copy.path, copy.line, copy.column, copy.given, copy.number,
                 copy.override);
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
      int rc =
          sch_add(r, renamed, o->path, o->line, o->column, o->given, o->number, o->override);
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

/* ---- Overrides. */

/* The key of t named name in its mapping at table path pre, or NULL. */
static const sch_key *sch_find(const sch_table *t, const char *pre, const char *name)
{
  for (size_t i = 0; i < t->n; ++i) {
    const char *child = sch_child_name(&t->key[i], pre);
    if (child && !strcmp(child, name))
      return &t->key[i];
  }
  return NULL;
}

/* The label of the override at path, marking it and every override below
 * it (an item of a list of numbers, a part of a custom value) read; NULL
 * if none is at path. */
static const char *sch_take(sch_reader *r, const char *path)
{
  const char *label = NULL;
  const size_t n = strlen(path);
  for (size_t i = 0; i < r->nov; ++i) {
    sch_override *o = &r->ov[i];
    const char next = o->path[n];
    if (strncmp(o->path, path, n) != 0 || (next && next != '.' && next != '['))
      continue;
    o->read = 1;
    if (!next && o->label[0])
      label = o->label;
  }
  return label;
}

void sch_blame_override(fb_err *err, const sch_override *o)
{
  if (!o->label[0])
    return;
  fb_err_set_source(err, FB_SOURCE_OVERRIDE, o->label);
  fb_err_prefix(err, "%s: ", o->label);
}

/* An error the reader raised at an override's value (fb_err.key is its
 * path) names the override. */
static void sch_blame(const sch_reader *r, int rc)
{
  fb_err *err = r->c->err;
  for (size_t i = 0; rc && err->source != FB_SOURCE_OVERRIDE && i < r->nov; ++i)
    if (r->ov[i].node && !strcmp(err->key, r->ov[i].path))
      sch_blame_override(err, &r->ov[i]);
}

/* FB_EINVAL "FILE:LINE:COL: KEY: message" for override o, at node (NULL
 * or without a place: the file alone) and key path key. */
static int sch_refuse_at(const sch_reader *r, const sch_override *o, struct fy_node *node,
                         const char *key, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
static int sch_refuse_at(const sch_reader *r, const sch_override *o, struct fy_node *node,
                         const char *key, const char *fmt, ...)
{
  char msg[FB_ERR_MSG_MAX / 2];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  fb_err *err = r->c->err;
  int line = 0, column = 0;
  if (node && ml_mark(node, &line, &column))
    fb_err_set(err, FB_EINVAL, "%s:%d:%d: %s%s%s", r->c->file, line, column, key,
               *key ? ": " : "", msg);
  else
    fb_err_set(err, FB_EINVAL, "%s: %s%s%s", r->c->file, key, *key ? ": " : "", msg);
  fb_err_set_location(err, r->c->file, line, column);
  fb_err_set_key(err, "%s", key);
  sch_blame_override(err, o);
  return FB_EINVAL;
}

/* Every override was read: one that no step took would be ignored. */
static int sch_all_read(const sch_reader *r)
{
  for (size_t i = 0; i < r->nov; ++i)
    if (!r->ov[i].read)
      return sch_refuse_at(r, &r->ov[i], r->ov[i].node, r->ov[i].path,
                           "no step of the reader took this value");
  return FB_OK;
}

/* A scalar of text (an empty mapping when NULL) in the document of at,
 * parsed from text that puts it at at's line and column: libfyaml places
 * the nodes it creates at 1:1, and the reader's messages and origins take
 * the node's place. A text of letters, digits and '_' is written plain,
 * any other double-quoted, so that it stays one scalar whatever it holds
 * (libfyaml marks a quoted scalar inside its quotes, hence the quote one
 * column before; at column 1, the text one column on). NULL when out of
 * memory. */
static struct fy_node *sch_node_at(struct fy_node *at, const char *text)
{
  static const char plain[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_";
  const char *t = text ? text : "{}";
  const int quote = text && (!*text || strspn(text, plain) < strlen(text));
  int line = 1, column = 1;
  ml_mark(at, &line, &column);
  const size_t pad = (size_t)line - 1 + (size_t)(column > 1 + quote ? column - 1 - quote : 0);
  char *buf = malloc(pad + 2 * strlen(t) + 3);
  if (!buf)
    return NULL;
  size_t n = 0;
  for (int i = 1; i < line; ++i)
    buf[n++] = '\n';
  while (n < pad)
    buf[n++] = ' ';
  if (quote)
    buf[n++] = '"';
  for (; *t; ++t) {
    if (quote && (*t == '"' || *t == '\\'))
      buf[n++] = '\\';
    buf[n++] = *t;
  }
  if (quote)
    buf[n++] = '"';
  buf[n] = '\0';
  struct fy_node *node = fy_node_build_from_malloc_string(fy_node_document(at), buf, n);
  if (!node)
    free(buf);
  /* NOLINTNEXTLINE(clang-analyzer-unix.Malloc): on success the node's document owns buf */
  return node;
}

/* map's value at key becomes value, the pairs' order kept (a parameter
 * may use the ones before it): libfyaml 0.7's fy_node_pair_set_value
 * leaves the new value without a parent, and key paths are made from
 * parents, so this pair and the ones after it are appended again. */
static int sch_swap_value(struct fy_node *map, const struct fy_node *key, struct fy_node *value)
{
  const int n = fy_node_mapping_item_count(map);
  int at = 0;
  while (at < n && fy_node_pair_key(fy_node_mapping_get_by_index(map, at)) != key)
    ++at;
  for (int i = at; i < n; ++i) {
    struct fy_node *k = fy_node_pair_key(fy_node_mapping_get_by_index(map, at));
    struct fy_node *copy = fy_node_copy(fy_node_document(map), k);
    struct fy_node *v = copy ? fy_node_mapping_remove_by_key(map, k) : NULL;
    if (v && i == at) {
      fy_node_free(v);
      v = value;
    }
    if (!v || fy_node_mapping_append(map, copy, v) != 0)
      return FB_ENOMEM;
  }
  return FB_OK;
}

/* An override's walk down its key path: where it has got to in the
 * table (t NULL below it, in a list of numbers or a custom value) and in
 * the file. */
typedef struct sch_walk {
  const sch_reader *r;
  sch_override *o;
  const sch_table *t;
  const char *pre;       /* the section's path in t, "" for its root */
  struct fy_node *node;  /* the file's node there; a mapping while t is set */
  char at[SCH_PATH_MAX]; /* its key path */
} sch_walk;

#define sch_refuse(w, ...) sch_refuse_at((w)->r, (w)->o, (w)->node, (w)->at, __VA_ARGS__)

/* One step down: to key name ("" for none) and then item index (-1 for
 * none), at node to (NULL, left out of the file: the node stays, the
 * place of a message about it). */
static void sch_walk_down(sch_walk *w, struct fy_node *to, const char *name, long index)
{
  /* w->at is a prefix of the override's key written again, which is
   * shorter than SCH_PATH_MAX (fb_scenario_load_overrides checks it), so
   * the bounded appends never cut it. */
  size_t len = strlen(w->at);
  if (*name)
    len = fb_text_append(w->at, sizeof w->at, len, "%s%s", len ? "." : "", name);
  if (index >= 0)
    fb_text_append(w->at, sizeof w->at, len, "[%ld]", index);
  w->node = to ? to : w->node;
}

/* Appends key name with value to map, the key at the mapping's place. */
static int sch_append(struct fy_node *map, const char *name, struct fy_node *value)
{
  struct fy_node *key = sch_node_at(map, name);
  return key && fy_node_mapping_append(map, key, value) == 0 ? FB_OK : FB_ENOMEM;
}

/* seq's item old becomes value. */
static int sch_swap_item(struct fy_node *seq, struct fy_node *old, struct fy_node *value)
{
  if (fy_node_sequence_insert_after(seq, old, value) != 0 || !fy_node_sequence_remove(seq, old))
    return FB_ENOMEM;
  fy_node_free(old);
  return FB_OK;
}

/* Puts the value at key name of the mapping here, or at its item index
 * (name NULL): where the file's value is, or at the mapping's place when
 * the file leaves the key out. */
static int sch_put(sch_walk *w, const char *name, long index)
{
  struct fy_node *key = NULL;
  struct fy_node *old =
      name ? ml_get(w->node, name, &key) : fy_node_sequence_get_by_index(w->node, (int)index);
  struct fy_node *value = sch_node_at(old ? old : w->node, w->o->value);
  int rc = value ? FB_OK : FB_ENOMEM;
  if (!rc && !name)
    rc = sch_swap_item(w->node, old, value);
  else if (!rc && key)
    rc = sch_swap_value(w->node, key, value);
  else if (!rc)
    rc = sch_append(w->node, name, value);
  if (rc)
    return fb_err_set(w->r->c->err, FB_ENOMEM, "out of memory setting %s", w->o->path);
  w->o->node = value;
  return FB_OK;
}

/* Into section k of the mapping here (child, made when the file leaves
 * it out). */
static int sch_walk_section(sch_walk *w, const sch_key *k, const char *name,
                            struct fy_node *child)
{
  if (!child && (!(child = sch_node_at(w->node, NULL)) || sch_append(w->node, name, child)))
    return fb_err_set(w->r->c->err, FB_ENOMEM, "out of memory setting %s", w->o->path);
  sch_walk_down(w, child, name, -1);
  if (!fy_node_is_mapping(child))
    return sch_refuse(w, "is not a mapping in the file");
  w->pre = k->path;
  return FB_OK;
}

/* Into item index of list k (list: the file's). */
static int sch_walk_item(sch_walk *w, const sch_key *k, const char *name, struct fy_node *list,
                         long index)
{
  sch_walk_down(w, list, name, -1);
  if (index < 0)
    return sch_refuse(w, "is a list, not a single value; set a key of one item, e.g. %s[0].%s",
                      w->at, k->items->key[0].path);
  const int count = list && fy_node_is_sequence(list) ? fy_node_sequence_item_count(list) : 0;
  if (index >= count)
    return sch_refuse(w, "has no item [%ld] (it has %d)", index, count);
  sch_walk_down(w, fy_node_sequence_get_by_index(list, (int)index), "", index);
  if (!fy_node_is_mapping(w->node))
    return sch_refuse(w, "is not a mapping in the file");
  w->t = k->items;
  w->pre = "";
  return FB_OK;
}

/* FB_EINVAL for key name that the table does not have here. */
static int sch_no_key(sch_walk *w, const char *name)
{
  const char *names[SCH_MAX_CHILDREN + 1];
  char keys[512], hint[SCH_PATH_MAX + 32] = "";
  sch_children(w->t, w->pre, names);
  sch_key_names(w->t, w->pre, keys, sizeof keys);
  const char *near = fb_suggest_list(name, names);
  if (near)
    snprintf(hint, sizeof hint, "did you mean '%s'? ", near);
  return sch_refuse(w, "has no key '%s' (%s%s%s)", name, hint,
                    keys[0] ? "its keys: " : "it has none", keys);
}

/* One segment of the path below the table: key name ("" for none) of a
 * mapping of the file, then item index of a list (-1: none). */
static int sch_walk_file(sch_walk *w, const char *name, long index, int last)
{
  struct fy_node *child = *name ? ml_get(w->node, name, NULL) : NULL;
  if (*name && !child)
    return sch_refuse(w, "has no key '%s'%s", name,
                      fy_node_is_mapping(w->node) ? "" : " (it is not a mapping)");
  if (*name && last && index < 0 && fy_node_is_scalar(child))
    return sch_put(w, name, -1);
  if (*name)
    sch_walk_down(w, child, name, -1);
  if (index < 0)
    return FB_OK;
  if (!fy_node_is_sequence(w->node))
    return sch_refuse(w, "is not a list: no item [%ld]", index);
  const int count = fy_node_sequence_item_count(w->node);
  if (index >= count)
    return sch_refuse(w, "has no item [%ld] (it has %d)", index, count);
  struct fy_node *item = fy_node_sequence_get_by_index(w->node, (int)index);
  if (last && fy_node_is_scalar(item))
    return sch_put(w, NULL, index);
  sch_walk_down(w, item, "", index);
  return FB_OK;
}

/* One segment of the path in a mapping of the table: name, then item
 * index (-1: none); last when the path ends there. */
static int sch_walk_table(sch_walk *w, const char *name, long index, int last)
{
  const sch_key *k = *name ? sch_find(w->t, w->pre, name) : NULL;
  if (!k)
    return *name ? sch_no_key(w, name)
                 : sch_refuse(w, "is a mapping, not a list: no item [%ld]", index);
  const int many = k->type == SCH_SECTION || k->type == SCH_LIST || k->type == SCH_NUMBERS;
  if (last && index < 0 && !many)
    return sch_put(w, name, -1);
  struct fy_node *child = ml_get(w->node, name, NULL);
  if (k->type == SCH_LIST)
    return sch_walk_item(w, k, name, child, index);
  if (k->type == SCH_SECTION && index < 0)
    return sch_walk_section(w, k, name, child);
  sch_walk_down(w, child, name, -1);
  if (k->type == SCH_SECTION)
    return sch_refuse(w, "is a mapping, not a list: no item [%ld]", index);
  if (k->type == SCH_NUMBERS && last && index < 0)
    return sch_refuse(w, "is a list, not a single value; set one item, e.g. %s[0]", w->at);
  if (!child)
    return sch_refuse(w, "is not in the file: it has no %s to set", index < 0 ? "key" : "item");
  w->t = NULL; /* the rest is the file's: a list of numbers, a custom value */
  return index < 0 ? FB_OK : sch_walk_file(w, "", index, last);
}

/* The next segment of key path *p: a name (may be empty after an index:
 * "x[1][2]") and an index (-1: none). 1 if there is one, 0 at the end,
 * -1 if malformed. */
static int sch_segment(const char **p, char *name, size_t size, long *index)
{
  const char *s = *p;
  const size_t n = strcspn(s, ".[]");
  *index = -1;
  if (!*s)
    return 0;
  if (n >= size)
    return -1;
  memcpy(name, s, n);
  name[n] = '\0';
  s += n;
  if (*s == '[') {
    char *end = NULL;
    if (s[1] < '0' || s[1] > '9')
      return -1;
    *index = strtol(s + 1, &end, 10);
    if (*end != ']')
      return -1;
    s = end + 1;
  }
  if ((n == 0 && *index < 0) || (*s && *s != '.' && *s != '['))
    return -1;
  if (*s == '.' && (*++s == '\0' || *s == '.' || *s == '['))
    return -1;
  *p = s;
  return 1;
}

/* FB_EINVAL for a path that ends at a mapping or a list. */
static int sch_not_value(sch_walk *w)
{
  char keys[512] = "";
  if (fy_node_is_sequence(w->node))
    return sch_refuse(w, "is a list, not a single value; set one item, e.g. %s[0]", w->at);
  if (w->t)
    sch_key_names(w->t, w->pre, keys, sizeof keys);
  return sch_refuse(w, "is a mapping, not a single value%s%s%s", *keys ? " (its keys: " : "",
                    keys, *keys ? ")" : "");
}

static int sch_place_one(const sch_reader *r, const sch_table *t, struct fy_node *root,
                         sch_override *o)
{
  sch_walk w = {r, o, t, "", root, ""};
  const char *p = o->path;
  char name[SCH_PATH_MAX];
  long index = -1;
  int rc = FB_OK, seg = 0;
  while (!rc && !o->node && (seg = sch_segment(&p, name, sizeof name, &index)) == 1)
    rc = w.t ? sch_walk_table(&w, name, index, !*p) : sch_walk_file(&w, name, index, !*p);
  if (seg < 0)
    return sch_refuse_at(r, o, NULL, "",
                         "malformed key '%s': expected names joined by '.', each optionally "
                         "followed by [index] (e.g. road.bump.height)",
                         o->path);
  return rc || o->node ? rc : sch_not_value(&w);
}

int sch_place(sch_reader *r, const sch_table *t, struct fy_node *root)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < r->nov; ++i)
    rc = sch_place_one(r, t, root, &r->ov[i]);
  return rc;
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
  sch_children(f->t, f->pre, names);
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

static const void *sch_at_const(const void *base, size_t offset)
{
  return (const char *)base + offset;
}

/* Stores a number (in the file's unit) as k says. */
static void sch_store_number(const sch_key *k, double v, void *base)
{
  void *p = sch_at(base, k->offset);
  switch (k->store) {
  case SCH_STORE_DOUBLE:
    *(double *)p = (k->ops && k->ops->to_struct ? k->ops->to_struct(v) : v) *
                   (k->scale != 0.0 ? k->scale : 1.0);
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
  const char *near = fb_suggest_list(text, k->choices);
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

/* Stores the n numbers read (at node; NULL for the default) as k says. */
static int sch_store_numbers(sch_reader *r, const sch_key *k, struct fy_node *node,
                             const double *v, size_t n, void *base)
{
  if (k->store != SCH_STORE_DOUBLE)
    return k->ops && k->ops->store_list ? k->ops->store_list(r, k, node, v, n, base) : FB_OK;
  if (n) /* an empty list may come as NULL */
    memcpy(sch_at(base, k->offset), v, n * sizeof *v);
  if (k->min_items != k->max_items)
    *(size_t *)sch_at(base, k->count_at) = n;
  return FB_OK;
}

/* Appends " (why)" to a range error's message: why the range is so. */
static void sch_add_why(fb_err *err, const char *why)
{
  fb_err_append(err, " (%s)", why);
}

/* A value written at node: read, recorded, stored. */
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
  case SCH_NAME: rc = ml_name(c, node, "the name", &text); break;
  case SCH_TEXT: rc = k->lines ? ml_text(c, node, &text) : ml_string(c, node, &text); break;
  case SCH_FILE:
    rc = ml_string(c, node, &text);
    if (!rc)
      rc = ml_resolve_path(c, node, text, &resolved);
    text = resolved;
    break;
  default: break;
  }
  if (!rc && k->type == SCH_NUMBER && k->store == SCH_STORE_NONE) {
    /* A value kept by no struct (read to be inherited or only checked)
     * is never visited by sch_check: its range is checked here. */
    const sch_value v = {k, path, NULL, number, NULL};
    if (sch_check_value(&v, c->err))
      rc = ml_blame(c, node);
  }
  if (!rc)
    rc = sch_add_at(r, path, node, 1, number, sch_take(r, path));
  if (!rc && (k->type == SCH_CHOICE || k->type == SCH_NUMBER || k->type == SCH_WHOLE))
    sch_store_number(k, number, base);
  else if (!rc)
    rc = sch_store_text(r, k, text, base);
  free(resolved);
  if (!rc && k->type == SCH_NUMBERS) {
    double *v = NULL;
    size_t n = 0;
    rc = sch_numbers(r, k, node, &v, &n);
    if (!rc)
      rc = sch_store_numbers(r, k, node, v, n, base);
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
    int rc = sch_add(r, path, path, line, column, 0, k->def, NULL);
    if (!rc && k->type == SCH_NUMBERS)
      rc = sch_store_numbers(r, k, NULL, k->def_list, k->min_items, f->base);
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
  int rc = sch_add(r, path, o.path, o.line, o.column, o.given, o.number, o.override);
  if (!rc)
    sch_store_number(k, o.number, f->base);
  return rc;
}

int sch_list_add(const sch_reader *r, const sch_key *k, void *base, void **item)
{
  char **items = sch_at(base, k->offset);
  size_t *n = sch_at(base, k->count_at);
  const size_t add = k->per_item ? k->per_item : 1;
  char *grown =
      *n < SIZE_MAX / k->item_size - add ? realloc(*items, (*n + add) * k->item_size) : NULL;
  if (!grown)
    return fb_err_set(r->c->err, FB_ENOMEM, "out of memory for %zu items", *n + add);
  *items = grown;
  *item = grown + *n * k->item_size;
  memset(*item, 0, add * k->item_size);
  *n += add;
  return FB_OK;
}

const sch_key *sch_key_of(const sch_table *t, const char *path)
{
  for (size_t i = 0; i < t->n; ++i)
    if (!strcmp(t->key[i].path, path))
      return &t->key[i];
  return NULL;
}

const sch_key *sch_key_at_path(const sch_table *t, const char *path)
{
  const char *open = strchr(path, '[');
  if (!open)
    return sch_key_of(t, path);
  char head[SCH_PATH_MAX];
  const size_t n = (size_t)(open - path);
  if (n >= sizeof head)
    return NULL;
  memcpy(head, path, n);
  head[n] = '\0';
  const sch_key *k = sch_key_of(t, head);
  const char *close = strchr(open, ']');
  if (!k || !close)
    return NULL;
  if (close[1] == '\0')
    return k; /* an item of a list of numbers */
  return close[1] == '.' && k->items ? sch_key_at_path(k->items, close + 2) : NULL;
}

const char *sch_item_name(const sch_key *k, const void *item)
{
  const sch_key *name = k->named ? sch_key_of(k->items, "name") : NULL;
  return name ? *(char *const *)sch_at_const(item, name->offset) : NULL;
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
      rc = sch_list_add(r, k, f->base, &item_base);
    if (!rc)
      rc = sch_add_at(r, item_path, item, 1, 0.0, NULL);
    const sch_frame in = {k->items, "", item, item, item_path, item_base};
    if (!rc)
      rc = sch_read_map(r, &in);
    if (!rc && k->items->done)
      rc = k->items->done(r, item, item_base);
    if (!rc && k->ops && k->ops->item_end)
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
      rc = sch_add_at(r, path, node, 1, 0.0, NULL);
    if (!rc && key && k->ops && k->ops->begin)
      rc = k->ops->begin(r, k, node, f->base);
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
    rc = sch_place(r, t, root);
  if (!rc)
    rc = sch_read_map(r, &f);
  if (!rc && t->done)
    rc = t->done(r, root, base);
  if (!rc)
    rc = sch_all_read(r);
  sch_blame(r, rc);
  return rc;
}

/* ---- Values of a struct. */

/* The stored value of k in the file's unit. */
static double sch_load_number(const sch_key *k, const void *base)
{
  const void *p = sch_at_const(base, k->offset);
  switch (k->store) {
  case SCH_STORE_DOUBLE: {
    const double v = *(const double *)p / (k->scale != 0.0 ? k->scale : 1.0);
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
  if (k->type == SCH_CUSTOM || (k->type == SCH_NUMBERS && k->store != SCH_STORE_DOUBLE))
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
                       const char *item_lp, sch_value_fn fn, void *ctx);

/* The items of the list k (the first of its view in t), under the
 * logical path lp of the item holding the list ("" at the top: a view
 * names its items in full, "hull.masses"). */
static int sch_each_item(const sch_table *t, const sch_key *k, const void *base, const char *lp,
                         sch_value_fn fn, void *ctx)
{
  for (const sch_key *o = t->key; o < k; ++o)
    if (o->type == SCH_LIST && o->view && k->view && !strcmp(o->view, k->view))
      return 0; /* visited with the first list of the view */
  const size_t n = *(const size_t *)sch_at_const(base, k->count_at);
  const char *items = *(char *const *)sch_at_const(base, k->offset);
  int stop = 0;
  for (size_t i = 0; !stop && i < n; ++i) {
    const void *item = items + i * k->item_size;
    const char *name = sch_item_name(k, item);
    char at[SCH_PATH_MAX];
    if (name)
      snprintf(at, sizeof at, "%s%s%s.%s", lp, lp[0] ? "." : "", k->view, name);
    else
      snprintf(at, sizeof at, "%s%s%s[%zu]", lp, lp[0] ? "." : "", k->view, i);
    stop = sch_each_in(k->items, "", item, at, at, fn, ctx);
  }
  return stop;
}

/* The values of t's keys under pre, at logical path lp; item_lp: that of
 * the list item t fills ("" for the root table). */
static int sch_each_in(const sch_table *t, const char *pre, const void *base, const char *lp,
                       const char *item_lp, sch_value_fn fn, void *ctx)
{
  int stop = 0;
  for (size_t i = 0; !stop && i < t->n; ++i) {
    const sch_key *k = &t->key[i];
    const char *name = sch_child_name(k, pre);
    if (!name || (k->ops && k->ops->present && !k->ops->present(k, base)))
      continue;
    char path[SCH_PATH_MAX];
    sch_join(path, sizeof path, lp, name);
    sch_value v;
    if (k->type == SCH_SECTION)
      stop = sch_each_in(t, k->path, base, path, item_lp, fn, ctx);
    else if (k->type == SCH_LIST)
      stop = sch_each_item(t, k, base, item_lp, fn, ctx);
    else if (sch_value_of(k, base, path, &v))
      stop = fn(&v, ctx);
  }
  return stop;
}

int sch_each(const sch_table *t, const void *base, sch_value_fn fn, void *ctx)
{
  return sch_each_in(t, "", base, "", "", fn, ctx);
}

/* "> 0", "in [0, 0.5)" of k's range into buf. */
static void sch_range_text(const sch_key *k, char *buf, size_t size)
{
  fb_range_text(k->bounds, k->lo, k->hi, buf, size);
}

/* 1 if the stored value x is inside k's range (bounds converted to the
 * stored unit, so a bound the conversion maps exactly is exact). */
static int sch_in_range(const sch_key *k, const void *base, double x)
{
  double (*to)(double) = k->ops ? k->ops->to_struct : NULL;
  if (k->store == SCH_STORE_DOUBLE && to)
    x = *(const double *)sch_at_const(base, k->offset);
  const double lo = to ? to(k->lo) : k->lo, hi = to ? to(k->hi) : k->hi;
  return fb_range_contains(k->bounds, lo, hi, x);
}

int sch_check_value(const sch_value *v, fb_err *err)
{
  const sch_key *k = v->key;
  if (k->type == SCH_CHOICE && !v->text)
    return fb_err_set(err, FB_EINVAL, "unknown value %.0f", v->number),
           fb_err_set_key(err, "%s", v->path), FB_EINVAL;
  if (k->type != SCH_NUMBER && k->type != SCH_WHOLE)
    return FB_OK;
  if (!isfinite(v->number))
    return fb_err_set(err, FB_EINVAL, "must be finite (got %g)", v->number),
           fb_err_set_key(err, "%s", v->path), FB_EINVAL;
  if (sch_in_range(k, v->base, v->number))
    return FB_OK;
  char range[96];
  sch_range_text(k, range, sizeof range);
  fb_err_set(err, FB_EINVAL, "must be %s%s%s (got %.10g)%s%s%s", range, k->unit ? " " : "",
             k->unit ? k->unit : "", v->number, k->why ? " (" : "", k->why ? k->why : "",
             k->why ? ")" : "");
  return fb_err_set_key(err, "%s", v->path), FB_EINVAL;
}

int sch_check_plausible(const sch_value *v, fb_err *w)
{
  const sch_key *k = v->key;
  if (!k->plausible_why || (k->type != SCH_NUMBER && k->type != SCH_WHOLE) ||
      (v->number >= k->plausible_lo && v->number <= k->plausible_hi))
    return 0;
  const char *unit = k->unit ? k->unit : "";
  const char *sep = k->unit ? " " : "";
  if (k->plausible_unit)
    fb_err_set(w, FB_EINVAL, "%.10g%s%s is implausible: %.10g%s%s = %.10g %s; %s", v->number,
               sep, unit, v->number, sep, unit, v->number * k->plausible_scale,
               k->plausible_unit, k->plausible_why);
  else
    fb_err_set(w, FB_EINVAL, "%.10g%s%s is implausible: %s", v->number, sep, unit,
               k->plausible_why);
  fb_err_set_key(w, "%s", v->path);
  return 1;
}

/* 1 if k stores a number in another unit than the file's (a conversion
 * or a scale), so that its stored value reads back with round-off. */
static int sch_converted(const sch_key *k)
{
  return k->store == SCH_STORE_DOUBLE &&
         ((k->ops && k->ops->to_struct) || (k->scale != 0.0 && k->scale != 1.0));
}

/* "a, b, c": the numbers list k stores in base. */
static void sch_format_numbers(const sch_key *k, const void *base, char *buf, size_t size)
{
  const double *x = sch_at_const(base, k->offset);
  const size_t n = k->min_items == k->max_items
                       ? k->min_items
                       : *(const size_t *)sch_at_const(base, k->count_at);
  size_t len = 0;
  buf[0] = '\0';
  for (size_t i = 0; i < n && len + 1 < size; ++i)
    len = fb_text_append(buf, size, len, "%s%.10g", i ? ", " : "", x[i]);
}

void sch_format(const sch_value *v, char *buf, size_t size)
{
  const sch_key *k = v->key;
  if (k->type == SCH_NUMBERS && k->store == SCH_STORE_DOUBLE)
    sch_format_numbers(k, v->base, buf, size);
  else if ((k->type == SCH_CUSTOM || k->type == SCH_NUMBERS) && k->ops && k->ops->format)
    k->ops->format(k, v->base, buf, size);
  else if (v->text)
    snprintf(buf, size, "%s", v->text);
  else if (sch_converted(k))
    /* Stored in another unit and converted back: ten digits hide the
     * round-off of the way there and back (30 degrees, not
     * 29.999999999999996), as positions moved to another frame do. */
    snprintf(buf, size, "%.10g", v->number);
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
