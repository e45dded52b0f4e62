/* Scenario overrides (flexbond/vehicle.h, fb_scenario_load_overrides):
 * "--set KEY=VALUE" replaces one scalar of the scenario's YAML document
 * before the scenario reader sees it, so the value goes through every
 * check and unit conversion of the reader (scenario_read.c) and of
 * fb_scenario_check, exactly as if it had been written in the file.
 *
 * The replacement is made in the document's text: the key is looked up
 * in the parsed document, the scalar's token gives its byte range in the
 * text, the value is written there as a YAML double-quoted scalar (so no
 * value can change the document's structure) and the text is read again.
 * Editing the text rather than the libfyaml tree keeps what the reader
 * needs for its messages: nodes built with fy_node_create_scalar have no
 * location (they would be reported at 1:1) and no parent link (their key
 * path would be lost). The replaced value keeps the original's line and
 * column. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "io/scenario_internal.h"

/* Longest key path handled ("suspensions.axles[1].wheel.tire_k"). */
enum { OV_PATH_MAX = 256 };

/* ---- Key paths. */

/* The growing list of the key paths where a bare key name occurs. */
typedef struct ov_matches {
  char **paths;
  size_t n, cap;
} ov_matches;

static void ov_matches_free(ov_matches *m)
{
  for (size_t i = 0; i < m->n; ++i)
    free(m->paths[i]);
  free(m->paths);
}

static int ov_matches_add(ov_matches *m, const char *path, fb_err *err)
{
  char *copy = fb_strdup(path);
  if (!copy || fb_grow((void **)&m->paths, &m->cap, m->n, sizeof *m->paths) != FB_OK) {
    free(copy);
    return fb_err_set(err, FB_ENOMEM, "out of memory looking up a scenario key");
  }
  m->paths[m->n++] = copy;
  return FB_OK;
}

/* The path of every mapping key named name (every key when name is
 * NULL) below n (path: n's own key path, len bytes), in document order. */
static int ov_find_name(struct fy_node *n, const char *name, char *path, size_t len,
                        ov_matches *m, fb_err *err)
{
  void *iter = NULL;
  int rc = FB_OK;
  if (fy_node_is_sequence(n)) {
    struct fy_node *item;
    for (int i = 0; rc == FB_OK && (item = fy_node_sequence_iterate(n, &iter)); ++i) {
      int k = snprintf(path + len, OV_PATH_MAX - len, "[%d]", i);
      if (k > 0 && len + (size_t)k < OV_PATH_MAX)
        rc = ov_find_name(item, name, path, len + (size_t)k, m, err);
    }
  } else if (fy_node_is_mapping(n)) {
    struct fy_node_pair *pair;
    while (rc == FB_OK && (pair = fy_node_mapping_iterate(n, &iter))) {
      const char *key = fy_node_get_scalar0(fy_node_pair_key(pair));
      int k = key ? snprintf(path + len, OV_PATH_MAX - len, "%s%s", len ? "." : "", key) : -1;
      if (k <= 0 || len + (size_t)k >= OV_PATH_MAX)
        continue;
      if (!name || !strcmp(key, name))
        rc = ov_matches_add(m, path, err);
      if (rc == FB_OK)
        rc = ov_find_name(fy_node_pair_value(pair), name, path, len + (size_t)k, m, err);
    }
  }
  path[len] = '\0';
  return rc;
}

/* "a, b, c": the keys of mapping map into buf. */
static void ov_key_list(struct fy_node *map, char *buf, size_t size)
{
  void *iter = NULL;
  struct fy_node_pair *pair;
  size_t len = 0;
  buf[0] = '\0';
  while ((pair = fy_node_mapping_iterate(map, &iter)) && len + 1 < size) {
    const char *key = fy_node_get_scalar0(fy_node_pair_key(pair));
    int k = snprintf(buf + len, size - len, "%s%s", len ? ", " : "", key ? key : "?");
    len = k > 0 && len + (size_t)k < size ? len + (size_t)k : size - 1;
  }
}

/* The next segment of a dotted key: a name (*name, *name_len; may be
 * empty before an index) and an optional sequence index (*index, -1 when
 * none). Advances *key past it and its '.'. 0 if malformed. */
static int ov_segment(const char **key, const char **name, size_t *name_len, long *index)
{
  const char *k = *key;
  const size_t len = strcspn(k, ".[]");
  *name = k;
  *name_len = len;
  *index = -1;
  k += len;
  if (*k == '[') {
    char *end = NULL;
    *index = strtol(k + 1, &end, 10);
    if (end == k + 1 || *end != ']' || *index < 0)
      return 0;
    k = end + 1;
  }
  if (len == 0 && *index < 0)
    return 0;
  if (*k == '.')
    ++k;
  else if (*k != '\0' && *k != '[')
    return 0;
  *key = k;
  return **key != '\0' || k[-1] != '.';
}

/* The child of n named by one segment, or an error naming what n has. */
static int ov_step(const ml_ctx *c, struct fy_node *n, const char *name, size_t name_len,
                   long index, struct fy_node **out)
{
  if (name_len > 0) {
    char key[OV_PATH_MAX], keys[512];
    snprintf(key, sizeof key, "%.*s", (int)name_len, name);
    if (!fy_node_is_mapping(n))
      return ml_fail(c, n, FB_EINVAL, "has no key '%s' (it is not a mapping)", key);
    *out = ml_get(n, key, NULL);
    if (*out)
      return FB_OK;
    ov_key_list(n, keys, sizeof keys);
    return ml_fail(c, n, FB_EINVAL, "has no key '%s' (its keys: %s)", key, keys);
  }
  if (!fy_node_is_sequence(n))
    return ml_fail(c, n, FB_EINVAL, "is not a list: no item [%ld]", index);
  int count = fy_node_sequence_item_count(n);
  if (index >= count)
    return ml_fail(c, n, FB_EINVAL, "has no item [%ld] (it has %d)", index, count);
  *out = fy_node_sequence_get_by_index(n, (int)index);
  return FB_OK;
}

/* The node at the dotted key ("road.bump.height", "x[2]") below root. */
static int ov_walk(const ml_ctx *c, struct fy_node *root, const char *key, struct fy_node **out)
{
  struct fy_node *n = root;
  const char *rest = key;
  int rc = FB_OK;
  while (rc == FB_OK && *rest) {
    const char *name = NULL;
    size_t name_len = 0;
    long index = -1;
    if (!ov_segment(&rest, &name, &name_len, &index))
      return fb_err_set(c->err, FB_EINVAL,
                        "%s: malformed key '%s': expected names joined by '.', each "
                        "optionally followed by [index] (e.g. road.bump.height)",
                        c->file, key);
    /* "x[1][2]": the name, then the index as a segment of its own. */
    if (name_len > 0 && index >= 0) {
      rc = ov_step(c, n, name, name_len, -1, &n);
      name_len = 0;
    }
    if (rc == FB_OK)
      rc = ov_step(c, n, name, name_len, index, &n);
  }
  *out = n;
  return rc;
}

/* ml_name_fn over the key paths of an ov_matches: the key itself. */
static const char *ov_match_key(const void *ctx, size_t i)
{
  const char *path = ((const ov_matches *)ctx)->paths[i];
  const char *dot = strrchr(path, '.');
  return dot ? dot + 1 : path;
}

/* FB_EINVAL for a key name found nowhere, with the path of a key whose
 * name is close to it, or the sections to start a path from. */
static int ov_no_name(const ml_ctx *c, struct fy_node *root, const char *name)
{
  ov_matches all = {0};
  char path[OV_PATH_MAX] = "", keys[512];
  int rc = ov_find_name(root, NULL, path, 0, &all, c->err);
  if (rc != FB_OK) {
    ov_matches_free(&all);
    return rc;
  }
  const char *near = ml_suggest(name, all.n, ov_match_key, &all);
  size_t i = 0;
  while (near && ov_match_key(&all, i) != near)
    ++i;
  if (near)
    rc = fb_err_set(c->err, FB_EINVAL, "%s: no key '%s' in the scenario (did you mean '%s'?)",
                    c->file, name, all.paths[i]);
  ov_matches_free(&all);
  if (near)
    return rc;
  ov_key_list(root, keys, sizeof keys);
  return fb_err_set(c->err, FB_EINVAL,
                    "%s: no key '%s' in the scenario (give a dotted path from one of its "
                    "sections: %s)",
                    c->file, name, keys);
}

/* The full path of a bare key name that occurs exactly once below root
 * into full (OV_PATH_MAX bytes; "" on error). */
static int ov_unique_name(const ml_ctx *c, struct fy_node *root, const char *name, char *full)
{
  full[0] = '\0';
  ov_matches m = {0};
  char path[OV_PATH_MAX] = "";
  int rc = ov_find_name(root, name, path, 0, &m, c->err);
  if (rc == FB_OK && m.n == 1)
    snprintf(full, OV_PATH_MAX, "%s", m.paths[0]);
  if (rc == FB_OK && m.n == 0)
    rc = ov_no_name(c, root, name);
  if (rc == FB_OK && m.n > 1) {
    char list[1024];
    size_t len = 0;
    list[0] = '\0';
    for (size_t i = 0; i < m.n && len + 1 < sizeof list; ++i) {
      len = fb_text_append(list, sizeof list, len, "%s%s", i ? ", " : "", m.paths[i]);
    }
    rc = fb_err_set(c->err, FB_EINVAL,
                    "%s: key '%s' is ambiguous: it occurs %zu times (%s); give the dotted path",
                    c->file, name, m.n, list);
  }
  ov_matches_free(&m);
  return rc;
}

/* A key's scalar in the document: the node and its full dotted path. */
static int ov_locate(const ml_ctx *c, struct fy_node *root, const char *key,
                     struct fy_node **node, char *full)
{
  int rc = FB_OK;
  if (!*key)
    return fb_err_set(c->err, FB_EINVAL, "%s: empty key", c->file);
  if (strpbrk(key, ".[]"))
    snprintf(full, OV_PATH_MAX, "%s", key);
  else
    rc = ov_unique_name(c, root, key, full);
  if (rc == FB_OK)
    rc = ov_walk(c, root, full, node);
  if (rc != FB_OK)
    return rc;
  if (fy_node_is_mapping(*node)) {
    char keys[512];
    ov_key_list(*node, keys, sizeof keys);
    return ml_fail(c, *node, FB_EINVAL, "is a mapping, not a single value (its keys: %s)",
                   keys);
  }
  if (fy_node_is_sequence(*node))
    return ml_fail(c, *node, FB_EINVAL,
                   "is a list, not a single value; set one item, e.g. %s[0]", full);
  return FB_OK;
}

/* ---- Replacing values in the text. */

/* Where an override's value goes: bytes [start, end) of the text. */
typedef struct ov_edit {
  size_t start, end;
  size_t index; /* in the override array */
  char path[OV_PATH_MAX];
} ov_edit;

/* The byte range of scalar n's text, quotes included. */
static int ov_range(const ml_ctx *c, struct fy_node *n, size_t len, size_t *start, size_t *end)
{
  struct fy_token *tok = fy_node_get_scalar_token(n);
  const struct fy_mark *s = tok ? fy_token_start_mark(tok) : NULL;
  const struct fy_mark *e = tok ? fy_token_end_mark(tok) : NULL;
  if (!s || !e || ml_is_null(n))
    return ml_fail(c, n, FB_EINVAL, "has no value in the file to replace");
  const enum fy_node_style style = fy_node_get_style(n);
  if (style == FYNS_LITERAL || style == FYNS_FOLDED)
    return ml_fail(c, n, FB_EINVAL,
                   "is a block scalar ('|' or '>'); only a plain or quoted "
                   "value can be replaced");
  /* libfyaml's marks of a quoted scalar lie inside the quotes. */
  const size_t quote = style == FYNS_SINGLE_QUOTED || style == FYNS_DOUBLE_QUOTED;
  if (s->input_pos < quote || e->input_pos + quote > len || e->input_pos < s->input_pos)
    return ml_fail(c, n, FB_EINVAL, "cannot find the value's text in the file");
  *start = s->input_pos - quote;
  *end = e->input_pos + quote;
  return FB_OK;
}

/* "--set KEY=VALUE: " before the message in err; returns rc. */
static int ov_blame(int rc, fb_err *err, const fb_scenario_override *o)
{
  fb_err_prefix(err, "--set %s=%s: ", o->key, o->value);
  return rc;
}

/* 1 if value can stand as a plain YAML scalar in a block or flow
 * context and reads back as the same text (YAML 1.2, section 7.3.3):
 * letters, digits, spaces inside and the characters of numbers and
 * expressions (_ . + - * / ^ parentheses), with no indicator at the
 * start. The reader then reports it at the original value's column. */
static int ov_is_plain(const char *value)
{
  static const char allowed[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                "0123456789_.+-*/^() ";
  const size_t n = strlen(value);
  return n > 0 && strspn(value, allowed) == n && value[0] != ' ' && value[n - 1] != ' ' &&
         !(value[0] == '-' && (n == 1 || value[1] == ' ')) && strcmp(value, "---") != 0;
}

/* Bytes a value takes in the text, plain or double-quoted; 0 if it has
 * a control character (a line break would end the scalar). */
static size_t ov_written_length(const char *value)
{
  if (ov_is_plain(value))
    return strlen(value);
  size_t n = 2;
  for (const unsigned char *v = (const unsigned char *)value; *v; ++v) {
    if (*v < 0x20 || *v == 0x7f)
      return 0;
    n += (*v == '"' || *v == '\\') ? 2 : 1;
  }
  return n;
}

/* Writes value at out (ov_written_length bytes): plain when it can be,
 * else double-quoted with '"' and '\' escaped (YAML 1.2, section 7.3.1). */
static void ov_write_value(const char *value, char *out)
{
  if (ov_is_plain(value)) {
    /* Spliced into the document's text: no terminator. */
    memcpy(out, value, strlen(value)); /* NOLINT(bugprone-not-null-terminated-result) */
    return;
  }
  size_t at = 0;
  out[at++] = '"';
  for (const char *v = value; *v; ++v) {
    if (*v == '"' || *v == '\\')
      out[at++] = '\\';
    out[at++] = *v;
  }
  out[at] = '"';
}

static int ov_edit_order(const void *a, const void *b)
{
  const ov_edit *x = a, *y = b;
  return (x->start > y->start) - (x->start < y->start);
}

/* Finds every override's value in the parsed document (edits[i]), sorted
 * by position; two overrides of one value are an error. */
static int ov_find_edits(const ml_ctx *c, struct fy_node *root, size_t len,
                         const fb_scenario_override *ov, size_t n, ov_edit *edits)
{
  for (size_t i = 0; i < n; ++i) {
    struct fy_node *node = NULL;
    int rc =
        !ov[i].key || !ov[i].value
            ? fb_err_set(c->err, FB_EINVAL, "%s: an override without key or value", c->file)
            : ov_locate(c, root, ov[i].key, &node, edits[i].path);
    if (rc == FB_OK && ov_written_length(ov[i].value) == 0)
      rc = fb_err_set(c->err, FB_EINVAL, "%s: the value has a control character or line break",
                      c->file);
    if (rc == FB_OK)
      rc = ov_range(c, node, len, &edits[i].start, &edits[i].end);
    if (rc != FB_OK)
      return ov_blame(rc, c->err, &ov[i]);
    edits[i].index = i;
  }
  qsort(edits, n, sizeof *edits, ov_edit_order);
  for (size_t i = 1; i < n; ++i)
    if (edits[i].start < edits[i - 1].end) {
      const fb_scenario_override *o = &ov[edits[i].index], *p = &ov[edits[i - 1].index];
      fb_err_set(c->err, FB_EINVAL, "%s: sets %s, which --set %s=%s sets too", c->file,
                 edits[i].path, p->key, p->value);
      return ov_blame(FB_EINVAL, c->err, o);
    }
  return FB_OK;
}

/* The text with every edit's range replaced by its value. */
static char *ov_apply(const char *text, size_t len, const fb_scenario_override *ov,
                      const ov_edit *edits, size_t n, size_t *new_len)
{
  size_t size = len + 1;
  for (size_t i = 0; i < n; ++i)
    size += ov_written_length(ov[edits[i].index].value);
  char *out = malloc(size);
  if (!out)
    return NULL;
  size_t at = 0, from = 0;
  for (size_t i = 0; i < n; ++i) {
    memcpy(out + at, text + from, edits[i].start - from);
    at += edits[i].start - from;
    ov_write_value(ov[edits[i].index].value, out + at);
    at += ov_written_length(ov[edits[i].index].value);
    from = edits[i].end;
  }
  memcpy(out + at, text + from, len - from);
  at += len - from;
  out[at] = '\0';
  *new_len = at;
  return out;
}

/* The text with the overrides applied (*out new, *out_len bytes). */
static int ov_rewrite(const char *text, size_t len, const char *file,
                      const fb_scenario_override *ov, size_t n, ov_edit *edits, char **out,
                      size_t *out_len, fb_err *err)
{
  ml_ctx c;
  memset(&c, 0, sizeof c);
  c.file = file;
  c.err = err;
  ml_yaml y;
  int rc = ml_yaml_parse(text, len, file, &y, err);
  if (rc == FB_OK)
    rc = ov_find_edits(&c, fy_document_root(y.doc), len, ov, n, edits);
  ml_yaml_release(&y);
  if (rc == FB_OK && !(*out = ov_apply(text, len, ov, edits, n, out_len)))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory applying scenario overrides");
  return rc;
}

/* "--set KEY=VALUE" of o into buf. */
static void ov_label(const fb_scenario_override *o, char *buf, size_t size)
{
  snprintf(buf, size, "--set %s=%s", o->key, o->value);
}

/* Prefixes a reader error with the override whose value it is about
 * (fb_err.key, the value's path in the file), recording it as the
 * error's source, or with every override when it is about another value
 * (a consequence of the values together, such as a bump that no longer
 * ends inside the run). */
static void ov_blame_reader(fb_err *err, const fb_scenario_override *ov, const ov_edit *edits,
                            size_t n)
{
  char label[FB_ERR_SOURCE_MAX];
  for (size_t i = 0; i < n; ++i)
    if (!strcmp(err->key, edits[i].path)) {
      ov_label(&ov[edits[i].index], label, sizeof label);
      fb_err_set_source(err, FB_SOURCE_OVERRIDE, label);
      ov_blame(err->code, err, &ov[edits[i].index]);
      return;
    }
  for (size_t i = n; i-- > 0;)
    fb_err_prefix(err, "--set %s=%s%s", ov[i].key, ov[i].value, i + 1 < n ? " " : ": ");
}

/* Records in s's origins which values the overrides replaced, for the
 * errors found after loading (fb_scenario_locate). */
static int ov_remember(fb_scenario *s, const fb_scenario_override *ov, const ov_edit *edits,
                       size_t n, fb_err *err)
{
  char label[FB_ERR_SOURCE_MAX];
  for (size_t i = 0; i < n; ++i) {
    ov_label(&ov[edits[i].index], label, sizeof label);
    for (size_t k = 0; k < s->norigins; ++k) {
      fb_scenario_origin *o = &s->origin[k];
      if (strcmp(o->path, edits[i].path) != 0)
        continue;
      free(o->override);
      if (!(o->override = fb_strdup(label)))
        return fb_err_set(err, FB_ENOMEM, "out of memory for %zu scenario overrides", n);
    }
  }
  return FB_OK;
}

/* ---- Public functions. */

/* Applies the overrides to text and loads the result: as the file
 * display_name when as_file (fb_scenario_load's relative references),
 * else as fb_scenario_load_string does. */
static int ov_load(const char *text, size_t len, const char *display_name, int as_file,
                   const fb_scenario_override *ov, size_t n, fb_scenario **out, fb_err *e)
{
  const char *file = display_name ? display_name : "<string>";
  ov_edit *edits = calloc(n ? n : 1, sizeof *edits);
  char *edited = NULL;
  size_t edited_len = 0;
  int rc = edits ? ov_rewrite(text, len, file, ov, n, edits, &edited, &edited_len, e)
                 : fb_err_set(e, FB_ENOMEM, "out of memory for %zu scenario overrides", n);
  if (rc == FB_OK)
    rc = as_file ? sc_load_edited_file(edited, edited_len, display_name, out, e)
                 : fb_scenario_load_string(edited, edited_len, display_name, out, e);
  if (rc != FB_OK && edited && n > 0)
    ov_blame_reader(e, ov, edits, n);
  if (rc == FB_OK && n > 0 && (rc = ov_remember(*out, ov, edits, n, e)) != FB_OK)
    fb_scenario_free(out);
  free(edited);
  free(edits);
  return rc;
}

int fb_scenario_load_string_overrides(const char *text, size_t len, const char *display_name,
                                      const fb_scenario_override *ov, size_t n,
                                      fb_scenario **out, fb_err *err)
{
  fb_err local;
  /* cppcheck-suppress uninitvar ; only the address of local is taken (false positive) */
  fb_err *e = err ? err : &local;
  fb_err_clear(e);
  if (!text || !out || (n > 0 && !ov))
    return fb_err_set(e, FB_EINVAL,
                      "fb_scenario_load_string_overrides: text, out and ov must not be NULL");
  *out = NULL;
  return ov_load(text, len, display_name, 0, ov, n, out, e);
}

int fb_scenario_load_overrides(const char *path, const fb_scenario_override *ov, size_t n,
                               fb_scenario **out, fb_err *err)
{
  fb_err local;
  /* cppcheck-suppress uninitvar ; only the address of local is taken (false positive) */
  fb_err *e = err ? err : &local;
  fb_err_clear(e);
  if (!path || !out || (n > 0 && !ov))
    return fb_err_set(e, FB_EINVAL,
                      "fb_scenario_load_overrides: path, out and ov must not be NULL");
  *out = NULL;
  char *text = NULL;
  size_t len = 0;
  int rc = fb_read_file(path, &text, &len, e);
  if (rc == FB_OK)
    rc = ov_load(text, len, path, 1, ov, n, out, e);
  free(text);
  return rc;
}

int fb_scenario_override_key(const char *path, const char *key, char **full, fb_err *err)
{
  fb_err_clear(err);
  if (!path || !key || !full)
    return fb_err_set(err, FB_EINVAL, "fb_scenario_override_key: NULL argument");
  *full = NULL;
  char *text = NULL, buf[OV_PATH_MAX];
  size_t len = 0;
  ml_yaml y;
  memset(&y, 0, sizeof y);
  ml_ctx c;
  memset(&c, 0, sizeof c);
  c.file = path;
  c.err = err;
  struct fy_node *node = NULL;
  int rc = fb_read_file(path, &text, &len, err);
  if (rc == FB_OK)
    rc = ml_yaml_parse(text, len, path, &y, err);
  if (rc == FB_OK)
    rc = ov_locate(&c, fy_document_root(y.doc), key, &node, buf);
  if (rc == FB_OK)
    rc = ov_range(&c, node, len, &(size_t){0}, &(size_t){0});
  if (rc == FB_OK && !(*full = fb_strdup(buf)))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  ml_yaml_release(&y);
  free(text);
  return rc;
}
