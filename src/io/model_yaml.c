/* SPDX-License-Identifier: BSD-3-Clause */
/* YAML access for the model loader: parsing with captured diagnostics,
 * node locations and key paths for messages, and typed getters that
 * report "FILE:LINE:COL: KEY: message". */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/textfile.h"
#include "core/util.h"
#include "io/model_internal.h"

/* ---- Parsing. */

/* libfyaml prints some messages (not collected as errors) through the
 * output function; the library must stay silent, so they are dropped. */
static void ml_diag_discard(struct fy_diag *diag, void *user, const char *buf, size_t len)
{
  (void)diag;
  (void)user;
  (void)buf;
  (void)len;
}

/* What the user should do about some of libfyaml's terse messages (its
 * wording, matched by a fragment; "" when none matches). */
static const char *ml_yaml_hint(const char *msg)
{
  static const struct {
    const char *fragment, *hint;
  } hints[] = {
      {"tab character", " (indent with spaces; YAML does not allow tabs there)"},
      {"duplicate key", " (a key may appear only once in a mapping)"},
      {"flow", " (an unclosed '[' or '{' or a missing comma before this point?)"},
      {"UTF8", " (the file must be UTF-8 text)"},
      {"Max depth", " (lists and mappings may nest at most 64 levels deep)"},
      {"invalid alias", " (no anchor of that name in the file: an alias *NAME repeats the node "
                        "marked &NAME)"},
      {"cyclic reference", " (the alias is inside the node its anchor marks, so it would "
                           "repeat itself forever)"},
      {"max recursion depth", " (too many aliases in a row refer to anchors further down; "
                              "define each anchor before its aliases)"},
  };
  for (size_t i = 0; i < sizeof hints / sizeof hints[0]; ++i)
    if (strstr(msg, hints[i].fragment))
      return hints[i].hint;
  return "";
}

/* Records the first error libfyaml collected, with the token it names
 * (the repeated key of "duplicate key", the alias of "invalid alias") and
 * a hint; returns 1 if there was one. The token's text is formatted for
 * those messages only: libfyaml 0.7 (Debian bookworm) leaks its
 * formatting buffer on the token of some other errors (a malformed quoted
 * scalar; tests/fuzz/regressions/model). */
static int ml_yaml_first_error(struct fy_diag *diag, const char *file, fb_err *err)
{
  void *iter = NULL;
  const struct fy_diag_error *e = fy_diag_errors_iterate(diag, &iter);
  if (!e)
    return 0;
  const char *msg = e->msg ? e->msg : "syntax error";
  const int duplicate = strstr(msg, "duplicate key") != NULL;
  const int alias = strstr(msg, "invalid alias") != NULL;
  size_t toklen = 0;
  const char *tok = (duplicate || alias) && e->fyt ? fy_token_get_text(e->fyt, &toklen) : NULL;
  if (tok && toklen > 0 && toklen <= 64)
    fb_err_set(err, FB_EPARSE, "%s:%d:%d: YAML: %s '%s%.*s'%s", file, e->line, e->column, msg,
               alias ? "*" : "", (int)toklen, tok, ml_yaml_hint(msg));
  else
    fb_err_set(err, FB_EPARSE, "%s:%d:%d: YAML: %s%s", file, e->line, e->column, msg,
               ml_yaml_hint(msg));
  return 1;
}

/* YAML is UTF-8 text without control characters other than tab, line
 * feed and carriage return (YAML 1.2, section 5.1, c-printable). libfyaml
 * stops without a message at some such bytes (a NUL), which would then
 * read as an empty file, so binary data is reported here at its line and
 * column. */
static int ml_check_text(const char *text, size_t len, const char *file, fb_err *err)
{
  /* Well-formed UTF-8 only, too: libfyaml 0.7 loops forever on an
   * overlong form, a surrogate or a code point above U+10FFFF after a '%'
   * (tests/fuzz/regressions/model). */
  size_t line, col;
  const size_t at = fb_text_find_binary(text, len, 1, &line, &col);
  if (at < len)
    return fb_err_set(err, FB_EPARSE,
                      "%s:%zu:%zu: binary data (byte 0x%02x): not a YAML text file (expected "
                      "UTF-8 text)",
                      file, line, col, (unsigned char)text[at]);
  return FB_OK;
}

/* ---- Bounding alias expansion.
 *
 * Resolving replaces each alias by a copy of the node its anchor marks,
 * and the aliases inside that copy are copied in turn, so lines that each
 * list ten aliases of the line before ("billion laughs") grow tenfold a
 * line: a 4 KB model with seven such lines took 15 GB and a minute to
 * load, with eight it was killed for memory. The expanded size is
 * therefore counted on the unresolved tree first, without copying:
 * size(node) = 1 + its children's sizes, size(alias) = size of the
 * anchored node, each anchored node counted once (memoised). libfyaml 0.7
 * has no limit to use instead: its parse configuration bounds only the
 * nesting of the text (64 levels, "Max depth (64) exceeded";
 * FYPCF_DISABLE_DEPTH_LIMIT lifts it), not nodes or expansion; its
 * resolver stops only at a cycle and at aliases nested 16 deep in copies
 * not yet resolved ("max recursion depth exceeded (16)", forward
 * references), which the bomb's backward references never are.
 *
 * Bound: a document may expand to ML_EXPAND_NODES nodes, or to
 * ML_EXPAND_FACTOR times its written node count if that is more. The
 * example models and scenarios have at most 266 nodes, and their aliases
 * add 6; 100000 nodes take about 12 MB and 20 ms in libfyaml (some 125
 * bytes a node), and the factor lets a large generated file share blocks
 * as freely while keeping its memory within ten times what its text costs
 * without aliases. The expanded nesting is bounded as well: libfyaml
 * accepts forward references, so a chain of aliases to anchors further
 * down would otherwise make this count recurse once per link, and
 * backward chains nest libfyaml's recursive copies as deep; 256 levels is
 * four times what the parser allows the text itself and thirty times what
 * the examples use (8). */

enum {
  ML_EXPAND_NODES = 100000, /* nodes any document may expand to */
  ML_EXPAND_FACTOR = 10,    /* or this many times its written nodes */
  ML_EXPAND_DEPTH = 256     /* levels of nesting after expansion */
};

/* Why counting stopped. */
enum { ML_EXPAND_OK, ML_EXPAND_TOO_MANY, ML_EXPAND_TOO_DEEP, ML_EXPAND_CYCLE };

/* An anchored node and, once counted, its expanded size. */
typedef struct ml_anchored {
  struct fy_node *node;
  size_t size; /* nodes after expansion */
  int height;  /* levels after expansion, 1 for a scalar */
  enum { ML_UNCOUNTED, ML_COUNTING, ML_COUNTED } state;
} ml_anchored;

typedef struct ml_expand {
  struct fy_document *doc;
  ml_anchored *anchored; /* sorted by node address */
  size_t nanchored;
  size_t limit;       /* most nodes the expanded document may have */
  size_t total;       /* written nodes other than aliases, plus the
                         expansions of the aliases walked so far */
  struct fy_node *at; /* the alias where counting stopped */
  size_t at_size;     /* its expanded size (ML_EXPAND_TOO_MANY), 0 if above limit */
} ml_expand;

/* Children of a collection in document order: items, or each pair's key
 * then value (either may be absent). */
typedef struct ml_children {
  struct fy_node *node;
  void *iter;
  struct fy_node *value; /* of the pair whose key came last */
} ml_children;

static struct fy_node *ml_next_child(ml_children *it)
{
  if (fy_node_is_sequence(it->node))
    return fy_node_sequence_iterate(it->node, &it->iter);
  if (!fy_node_is_mapping(it->node))
    return NULL;
  for (;;) {
    struct fy_node *child = it->value;
    it->value = NULL;
    if (child)
      return child;
    struct fy_node_pair *pair = fy_node_mapping_iterate(it->node, &it->iter);
    if (!pair)
      return NULL;
    it->value = fy_node_pair_value(pair);
    child = fy_node_pair_key(pair);
    if (child)
      return child;
  }
}

/* Nodes of the tree as written, an alias being one, and (added to
 * *aliases) how many are aliases; the recursion is as deep as the text
 * nests, which the parser limits to 64. */
static size_t ml_written_nodes(struct fy_node *n, size_t *aliases)
{
  size_t count = 1;
  *aliases += fy_node_is_alias(n);
  ml_children it = {n, NULL, NULL};
  for (struct fy_node *c; (c = ml_next_child(&it));)
    count += ml_written_nodes(c, aliases);
  return count;
}

static int ml_anchored_cmp(const void *a, const void *b)
{
  uintptr_t x = (uintptr_t)((const ml_anchored *)a)->node;
  uintptr_t y = (uintptr_t)((const ml_anchored *)b)->node;
  return (x > y) - (x < y);
}

static ml_anchored *ml_anchored_find(const ml_expand *x, struct fy_node *n)
{
  ml_anchored key = {n, 0, 0, ML_UNCOUNTED};
  return bsearch(&key, x->anchored, x->nanchored, sizeof key, ml_anchored_cmp);
}

/* The node an alias stands for, found as libfyaml's resolver finds it
 * (0.7: the last anchor of that name before the alias, else one after);
 * NULL if none, which the resolver then reports as an invalid alias. */
static struct fy_node *ml_alias_target(const ml_expand *x, struct fy_node *alias)
{
  struct fy_token *tok = fy_node_get_scalar_token(alias);
  struct fy_anchor *a = tok ? fy_document_lookup_anchor_by_token(x->doc, tok) : NULL;
  struct fy_node *target = a ? fy_anchor_node(a) : NULL;
  /* The parser refuses an anchor on an alias; following one could loop. */
  return target && !fy_node_is_alias(target) ? target : NULL;
}

/* *size and *height of n after expansion, n being at nesting level
 * `level` of the expanded document (the root is 1); ML_EXPAND_OK or why
 * not (x->at is set for a cycle: the alias inside its anchor's node). */
static int ml_expanded(ml_expand *x, struct fy_node *n, int level, size_t *size, int *height)
{
  if (level > ML_EXPAND_DEPTH)
    return ML_EXPAND_TOO_DEEP;
  if (fy_node_is_alias(n)) {
    struct fy_node *target = ml_alias_target(x, n);
    const ml_anchored *a = target ? ml_anchored_find(x, target) : NULL;
    if (a && a->state == ML_COUNTING) {
      x->at = n;
      return ML_EXPAND_CYCLE;
    }
    if (!target) {
      *size = 1;
      *height = 1;
      return ML_EXPAND_OK;
    }
    return ml_expanded(x, target, level, size, height); /* the copy takes the alias's place */
  }
  ml_anchored *a = ml_anchored_find(x, n);
  if (a && a->state == ML_COUNTED) {
    *size = a->size;
    *height = a->height;
    return level - 1 + a->height > ML_EXPAND_DEPTH ? ML_EXPAND_TOO_DEEP : ML_EXPAND_OK;
  }
  if (a)
    a->state = ML_COUNTING;
  size_t sum = 1;
  int tallest = 0;
  ml_children it = {n, NULL, NULL};
  for (struct fy_node *c; (c = ml_next_child(&it));) {
    size_t s = 0;
    int h = 0;
    int why = ml_expanded(x, c, level + 1, &s, &h);
    if (why)
      return why;
    if (s > x->limit - sum) /* sum <= limit throughout, so this cannot overflow */
      return ML_EXPAND_TOO_MANY;
    sum += s;
    tallest = h > tallest ? h : tallest;
  }
  if (a) {
    a->size = sum;
    a->height = tallest + 1;
    a->state = ML_COUNTED;
  }
  *size = sum;
  *height = tallest + 1;
  return ML_EXPAND_OK;
}

/* Walks the written tree in document order, adding each alias's expanded
 * size to x->total (which starts with the other written nodes), so that a
 * failure names the first alias that crosses the bound. */
static int ml_expand_walk(ml_expand *x, struct fy_node *n, int level)
{
  if (fy_node_is_alias(n)) {
    size_t size = 0;
    int height = 0;
    int why = ml_expanded(x, n, level, &size, &height);
    if (why != ML_EXPAND_CYCLE)
      x->at = n;
    if (!why && size > x->limit - x->total)
      why = ML_EXPAND_TOO_MANY;
    x->at_size = why == ML_EXPAND_TOO_MANY ? size : 0;
    x->total += why ? 0 : size;
    return why;
  }
  ml_children it = {n, NULL, NULL};
  for (struct fy_node *c; (c = ml_next_child(&it));) {
    int why = ml_expand_walk(x, c, level + 1);
    if (why)
      return why;
  }
  return ML_EXPAND_OK;
}

static int ml_own_mark(struct fy_node *n, int *line, int *col);

static int ml_expand_report(const ml_expand *x, int why, size_t written, const char *file,
                            fb_err *err)
{
  int line = 1, col = 1;
  ml_own_mark(x->at, &line, &col);
  size_t len = 0;
  struct fy_token *tok = fy_node_get_scalar_token(x->at);
  const char *name = tok ? fy_token_get_text(tok, &len) : NULL;
  if (!name || len > 64) {
    name = "...";
    len = 3;
  }
  if (why == ML_EXPAND_CYCLE)
    return fb_err_set(err, FB_EPARSE, "%s:%d:%d: YAML: cyclic reference detected '*%.*s'%s",
                      file, line, col, (int)len, name, ml_yaml_hint("cyclic reference"));
  if (why == ML_EXPAND_TOO_DEEP)
    return fb_err_set(err, FB_EPARSE,
                      "%s:%d:%d: YAML: aliases would nest the document more than %d levels "
                      "deep (*%.*s here copies a node that nests too deep)",
                      file, line, col, ML_EXPAND_DEPTH, (int)len, name);
  char copies[64];
  if (x->at_size)
    snprintf(copies, sizeof copies, "%zu", x->at_size);
  else
    snprintf(copies, sizeof copies, "more than %zu", x->limit);
  return fb_err_set(err, FB_EPARSE,
                    "%s:%d:%d: YAML: aliases would expand the document to more than %zu nodes "
                    "(the file has %zu as written; *%.*s here copies %s, counting the aliases "
                    "inside the copy)",
                    file, line, col, x->limit, written, (int)len, name, copies);
}

/* FB_EPARSE, located at the alias that crosses the bound, if resolving the
 * aliases of doc would exceed the bounds above; FB_ENOMEM. */
static int ml_check_aliases(struct fy_document *doc, const char *file, fb_err *err)
{
  size_t n = 0;
  void *iter = NULL;
  while (fy_document_anchor_iterate(doc, &iter))
    ++n;
  if (n == 0)
    return FB_OK; /* nothing an alias could copy */
  ml_expand x;
  memset(&x, 0, sizeof x);
  x.doc = doc;
  x.anchored = calloc(n, sizeof *x.anchored);
  if (!x.anchored)
    return fb_err_set(err, FB_ENOMEM, "out of memory checking the YAML aliases");
  iter = NULL;
  struct fy_anchor *a;
  while (x.nanchored < n && (a = fy_document_anchor_iterate(doc, &iter)))
    if ((x.anchored[x.nanchored].node = fy_anchor_node(a)))
      ++x.nanchored;
  qsort(x.anchored, x.nanchored, sizeof *x.anchored, ml_anchored_cmp);
  struct fy_node *root = fy_document_root(doc);
  size_t aliases = 0;
  const size_t written = ml_written_nodes(root, &aliases);
  x.limit = written > (size_t)-1 / ML_EXPAND_FACTOR ? (size_t)-1 : written * ML_EXPAND_FACTOR;
  x.limit = x.limit < ML_EXPAND_NODES ? ML_EXPAND_NODES : x.limit;
  x.total = written - aliases;
  const int why = ml_expand_walk(&x, root, 1);
  const int rc = why ? ml_expand_report(&x, why, written, file, err) : FB_OK;
  free(x.anchored);
  return rc;
}

void ml_yaml_release(ml_yaml *y)
{
  if (y->doc)
    fy_parse_document_destroy(y->parser, y->doc);
  if (y->parser)
    fy_parser_destroy(y->parser);
  if (y->diag)
    fy_diag_destroy(y->diag);
  y->doc = NULL;
  y->parser = NULL;
  y->diag = NULL;
}

static int ml_yaml_open(const char *text, size_t len, ml_yaml *y, fb_err *err)
{
  struct fy_diag_cfg dcfg;
  fy_diag_cfg_default(&dcfg);
  dcfg.fp = NULL;
  dcfg.output_fn = ml_diag_discard;
  dcfg.user = NULL;
  dcfg.colorize = false;
  y->diag = fy_diag_create(&dcfg);
  if (!y->diag)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating the YAML diagnostics");
  fy_diag_set_collect_errors(y->diag, true);

  struct fy_parse_cfg pcfg;
  memset(&pcfg, 0, sizeof pcfg);
  /* No FYPCF_RESOLVE_DOCUMENT: ml_yaml_parse resolves aliases and "<<"
   * merge keys itself, once ml_check_aliases has bounded their expansion. */
  pcfg.flags = FYPCF_QUIET;
  pcfg.diag = y->diag;
  y->parser = fy_parser_create(&pcfg);
  if (!y->parser || fy_parser_set_string(y->parser, text, len) != 0)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating the YAML parser");
  return FB_OK;
}

static int ml_check_scalars(const ml_ctx *c, struct fy_node *n);

int ml_yaml_parse(const char *text, size_t len, const char *file, ml_yaml *y, fb_err *err)
{
  memset(y, 0, sizeof *y);
  int rc = ml_check_text(text, len, file, err);
  if (!rc)
    rc = ml_yaml_open(text, len, y, err);
  if (rc)
    return rc;
  y->doc = fy_parse_load_document(y->parser);
  if (ml_yaml_first_error(y->diag, file, err))
    return FB_EPARSE;
  /* "---" alone starts a document whose root is an empty scalar without
   * a token, so nothing in it has a location: the file is as empty. */
  struct fy_node *root = y->doc ? fy_document_root(y->doc) : NULL;
  if (!root || (fy_node_is_scalar(root) && !fy_node_get_scalar_token(root)))
    return fb_err_set(err, FB_EPARSE, "%s:1:1: the file is empty (no YAML document)", file);
  /* Before resolving: each written scalar once, however often aliases
   * would copy it. */
  ml_ctx c;
  memset(&c, 0, sizeof c);
  c.file = file;
  c.err = err;
  rc = ml_check_scalars(&c, root);
  /* Resolving makes the loader see only plain mappings, sequences and
   * scalars. */
  if (!rc)
    rc = ml_check_aliases(y->doc, file, err);
  if (rc)
    return rc;
  if (fy_document_resolve(y->doc) != 0) {
    if (ml_yaml_first_error(y->diag, file, err))
      return FB_EPARSE;
    /* libfyaml reports every failure but a failed allocation. */
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory resolving the YAML aliases", file);
  }
  struct fy_document *second = fy_parse_load_document(y->parser);
  if (second) {
    /* The "---" that starts it (its root may be empty). */
    const struct fy_mark *m =
        fy_document_state_start_mark(fy_document_get_document_state(second));
    int line = m ? m->line + 1 : 1, col = m ? m->column + 1 : 1;
    fy_parse_document_destroy(y->parser, second);
    return fb_err_set(err, FB_EPARSE,
                      "%s:%d:%d: YAML: a second document ('---'); a file holds one", file, line,
                      col);
  }
  if (ml_yaml_first_error(y->diag, file, err))
    return FB_EPARSE;
  return FB_OK;
}

/* ---- Locations and key paths. */

/* Start mark of n itself (no fallback), via its scalar token or, for a
 * collection, the first event a document iterator makes for it (libfyaml
 * 0.7 has no public accessor for a collection's start token). */
static int ml_own_mark(struct fy_node *n, int *line, int *col)
{
  if (fy_node_is_scalar(n)) {
    struct fy_token *tok = fy_node_get_scalar_token(n);
    const struct fy_mark *m = tok ? fy_token_start_mark(tok) : NULL;
    if (!m)
      return 0;
    *line = m->line + 1;
    *col = m->column + 1;
    return 1;
  }
  struct fy_document_iterator *it = fy_document_iterator_create();
  if (!it)
    return 0;
  int found = 0;
  fy_document_iterator_node_start(it, n);
  struct fy_event *ev = fy_document_iterator_body_next(it);
  const struct fy_mark *m = ev ? fy_event_start_mark(ev) : NULL;
  if (m) {
    *line = m->line + 1;
    *col = m->column + 1;
    found = 1;
  }
  if (ev)
    fy_document_iterator_event_free(it, ev);
  fy_document_iterator_destroy(it);
  return found;
}

/* Nodes copied by alias resolution have no marks: use the nearest
 * ancestor that has one. */
int ml_mark(struct fy_node *n, int *line, int *col)
{
  for (; n; n = fy_node_get_parent(n))
    if (ml_own_mark(n, line, col))
      return 1;
  return 0;
}

int ml_line(struct fy_node *n)
{
  int line = 0, col = 0;
  return ml_mark(n, &line, &col) ? line : 0;
}

/* Appends formatted text to buf (size bytes, *len used), truncating. */
static void ml_append(char *buf, size_t size, size_t *len, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
static void ml_append(char *buf, size_t size, size_t *len, const char *fmt, ...)
{
  if (*len + 1 >= size)
    return;
  va_list ap;
  va_start(ap, fmt);
  int k = vsnprintf(buf + *len, size - *len, fmt, ap);
  va_end(ap);
  if (k > 0)
    *len = (*len + (size_t)k < size) ? *len + (size_t)k : size - 1;
}

/* Segment of n inside its parent: "[i]" in a sequence, ".key" (no dot
 * at the start) in a mapping. */
static void ml_path_segment(struct fy_node *parent, const struct fy_node *n, char *buf,
                            size_t size, size_t *len)
{
  void *iter = NULL;
  if (fy_node_is_sequence(parent)) {
    int index = 0;
    struct fy_node *item;
    while ((item = fy_node_sequence_iterate(parent, &iter)) && item != n)
      ++index;
    ml_append(buf, size, len, "[%d]", index);
    return;
  }
  struct fy_node_pair *pair;
  while ((pair = fy_node_mapping_iterate(parent, &iter)))
    if (fy_node_pair_value(pair) == n) {
      const char *key = fy_node_get_scalar0(fy_node_pair_key(pair));
      ml_append(buf, size, len, "%s%s", *len ? "." : "", key ? key : "?");
      return;
    }
}

static void ml_path(struct fy_node *n, char *buf, size_t size, size_t *len)
{
  struct fy_node *parent = n ? fy_node_get_parent(n) : NULL;
  if (!parent)
    return;
  ml_path(parent, buf, size, len);
  ml_path_segment(parent, n, buf, size, len);
}

/* Appends "FILE:LINE:COL: KEY: " to where: the position of loc (or the
 * file alone) and the key path of path_node, extended by key. */
static void ml_locate(const ml_ctx *c, struct fy_node *loc, struct fy_node *path_node,
                      const char *key, char *where, size_t size, size_t *len)
{
  int line = 0, col = 0;
  if (ml_mark(loc, &line, &col))
    ml_append(where, size, len, "%s:%d:%d: ", c->file, line, col);
  else
    ml_append(where, size, len, "%s: ", c->file);
  char path[512];
  size_t plen = 0;
  path[0] = '\0';
  ml_path(path_node, path, sizeof path, &plen);
  if (key)
    ml_append(path, sizeof path, &plen, "%s%s", plen ? "." : "", key);
  if (plen)
    ml_append(where, size, len, "%s: ", path);
}

/* The fields of the error just recorded (fb_err.key, file, line,
 * column), as its message's "FILE:LINE:COL: KEY: " names them. */
static void ml_set_fields(const ml_ctx *c, struct fy_node *loc, struct fy_node *path_node,
                          const char *key)
{
  int line = 0, col = 0;
  ml_mark(loc, &line, &col);
  fb_err_set_location(c->err, c->file, line, col);
  char path[512];
  size_t plen = 0;
  path[0] = '\0';
  ml_path(path_node, path, sizeof path, &plen);
  if (key)
    ml_append(path, sizeof path, &plen, "%s%s", plen ? "." : "", key);
  if (plen)
    fb_err_set_key(c->err, "%s", path);
}

/* " (in instance 'a' at FILE:LINE:COL, in 'b' at ...)" of the instances
 * being built, innermost first, into chain (size bytes); "" at top level. */
static void ml_chain(const ml_ctx *c, char *chain, size_t size)
{
  size_t clen = 0;
  chain[0] = '\0';
  for (const ml_frame *f = c->frames; f; f = f->outer) {
    int fl = 0, fc = 0;
    ml_mark(f->at, &fl, &fc);
    ml_append(chain, size, &clen, "%s'%s' at %s:%d:%d",
              f == c->frames ? " (in instance " : ", in ", f->instance, c->file, fl, fc);
  }
  if (clen)
    ml_append(chain, size, &clen, ")");
}

/* The message proper, then the chain of instances being built. */
static int ml_report(const ml_ctx *c, struct fy_node *loc, struct fy_node *path_node,
                     const char *key, int code, const char *msg)
{
  char where[1024];
  size_t len = 0;
  where[0] = '\0';
  ml_locate(c, loc, path_node, key, where, sizeof where, &len);
  char chain[1024];
  ml_chain(c, chain, sizeof chain);
  /* The location as a prefix: fb_err.text_start marks the message. */
  fb_err_set(c->err, code, "%s%s", msg, chain);
  fb_err_prefix_location(c->err, "%s", where);
  ml_set_fields(c, loc, path_node, key);
  return code;
}

/* ---- Sites of graph parts, for errors raised after loading. */

void ml_sites_release(ml_sites *s)
{
  for (size_t i = 0; i < s->n; ++i) {
    free(s->site[i].name);
    free(s->site[i].tail);
    free(s->site[i].key);
  }
  free(s->site);
  free(s->file);
  *s = (ml_sites){0};
}

const ml_site *ml_sites_find(const ml_sites *s, int kind, const char *name)
{
  for (size_t i = 0; s && name && i < s->n; ++i)
    if (s->site[i].kind == kind && !strcmp(s->site[i].name, name))
      return &s->site[i];
  return NULL;
}

void ml_site_head(const ml_sites *sites, const ml_site *site, char *buf, size_t size)
{
  /* As ml_locate writes it. */
  const char *file = sites->file ? sites->file : "";
  size_t len = 0;
  buf[0] = '\0';
  if (site->line)
    ml_append(buf, size, &len, "%s:%d:%d: ", file, site->line, site->column);
  else
    ml_append(buf, size, &len, "%s: ", file);
  if (site->key[0])
    ml_append(buf, size, &len, "%s: ", site->key);
}

void ml_site_set_fields(const ml_sites *sites, const ml_site *site, fb_err *err)
{
  fb_err_set_location(err, sites->file ? sites->file : "", site->line, site->column);
  if (site->key[0])
    fb_err_set_key(err, "%s", site->key);
}

/* "outer.inner." of the instances being built (fb_bg_adopt prefixes each
 * adopted name with its instance's), outermost first. */
static void ml_frame_prefix(const ml_frame *f, char *buf, size_t size, size_t *len)
{
  if (!f)
    return;
  ml_frame_prefix(f->outer, buf, size, len);
  ml_append(buf, size, len, "%s.", f->instance);
}

int ml_site_record(const ml_ctx *c, int kind, const char *name, struct fy_node *at)
{
  ml_sites *s = c->sites;
  if (!s)
    return FB_OK;
  char full[1024], tail[1024], key[512];
  size_t flen = 0, klen = 0;
  full[0] = key[0] = '\0';
  ml_frame_prefix(c->frames, full, sizeof full, &flen);
  ml_append(full, sizeof full, &flen, "%s", name);
  ml_chain(c, tail, sizeof tail);
  ml_path(at, key, sizeof key, &klen);
  ml_site site = {kind, fb_strdup(full), fb_strdup(tail), fb_strdup(key), 0, 0};
  ml_mark(at, &site.line, &site.column);
  if (!s->file)
    s->file = fb_strdup(c->file);
  if (!site.name || !site.tail || !site.key || !s->file ||
      fb_grow((void **)&s->site, &s->cap, s->n, sizeof *s->site) != FB_OK) {
    free(site.name);
    free(site.tail);
    free(site.key);
    return fb_err_set(c->err, FB_ENOMEM, "out of memory recording where '%s' is", full);
  }
  s->site[s->n++] = site;
  return FB_OK;
}

/* The parentheses keep the analyzer-only macros of model_internal.h from expanding. */
int(ml_fail)(const ml_ctx *c, struct fy_node *at, int code, const char *fmt, ...)
{
  char msg[FB_ERR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return ml_report(c, at, at, NULL, code, msg);
}

int(ml_fail_key)(const ml_ctx *c, struct fy_node *map, struct fy_node *key, int code,
                 const char *fmt, ...)
{
  char msg[FB_ERR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  const char *text = fy_node_is_scalar(key) ? fy_node_get_scalar0(key) : NULL;
  return ml_report(c, key ? key : map, map, text ? text : "?", code, msg);
}

/* The error just recorded, reported again at at (key_at: the key to name,
 * NULL for none): its message behind the location, its data-file excerpt
 * kept. */
static int blame(const ml_ctx *c, struct fy_node *at, struct fy_node *key_at)
{
  char msg[FB_ERR_MSG_MAX], excerpt[FB_ERR_EXCERPT_MAX];
  int code = c->err->code ? c->err->code : FB_EMODEL;
  snprintf(msg, sizeof msg, "%s", c->err->msg);
  snprintf(excerpt, sizeof excerpt, "%s", c->err->excerpt);
  const int rc = ml_report(c, at, key_at, NULL, code, msg);
  snprintf(c->err->excerpt, sizeof c->err->excerpt, "%s", excerpt);
  return rc;
}

int ml_blame(const ml_ctx *c, struct fy_node *at)
{
  return blame(c, at, at);
}

int ml_blame_located(const ml_ctx *c, struct fy_node *at)
{
  return blame(c, at, NULL);
}

/* ---- Text of scalars.
 *
 * libfyaml decodes escapes of double-quoted scalars, so "\0" puts a NUL
 * into a scalar's text and "\n" a line break, as a block scalar ('|')
 * does. The C strings the loader takes would end at the NUL ("140000\0junk"
 * read as 140000), so no scalar may hold one. Names, units and the other
 * one-line text become CSV headers, JSON, DOT, Markdown and gnuplot
 * lines, where a line break would start a line of the file's own syntax
 * (a gnuplot line starting with '!' runs a shell command), so the
 * loader's string getter refuses control characters in them. */

/* What the control character c is, for messages. */
static void ml_control_name(unsigned c, char *buf, size_t size)
{
  static const struct {
    unsigned c;
    const char *name;
  } names[] = {
      {'\0', "a NUL (\\0)"}, {'\n', "a line break (\\n)"}, {'\r', "a carriage return (\\r)"},
      {'\t', "a tab (\\t)"}, {0x1b, "an escape (\\e)"},    {0x7f, "a delete character (0x7f)"}};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
    if (names[i].c == c) {
      snprintf(buf, size, "%s", names[i].name);
      return;
    }
  snprintf(buf, size, "control character 0x%02x", c);
}

/* The decoded text of scalar n in fresh memory (*len bytes, then a NUL;
 * the caller frees it), read through a token iterator: libfyaml 0.7.12
 * (bookworm) leaks the buffer in which fy_node_get_scalar decodes a
 * quoted scalar whose text comes out shorter than written ('a''b'; its
 * fy_atom_format_text, fixed upstream later; docs/fuzzing.md). NULL for
 * a scalar without a token, or out of memory. */
static char *ml_scalar_copy(struct fy_node *n, size_t *len)
{
  *len = 0;
  struct fy_token *tok = fy_node_get_scalar_token(n);
  struct fy_token_iter *it = tok ? fy_token_iter_create(tok) : NULL;
  if (!it)
    return NULL;
  char *text = NULL;
  size_t cap = 0;
  int failed = 0;
  const struct fy_iter_chunk *ch = NULL;
  int ierr = 0;
  while (!failed && (ch = fy_token_iter_chunk_next(it, ch, &ierr)) != NULL) {
    if (*len + ch->len + 1 > cap) {
      const size_t want = 2 * (*len + ch->len + 1);
      char *grown = realloc(text, want);
      failed = !grown;
      if (grown) {
        text = grown;
        cap = want;
      }
    }
    if (!failed) {
      memcpy(text + *len, ch->str, ch->len);
      *len += ch->len;
    }
  }
  fy_token_iter_destroy(it);
  if (!failed && !text)
    text = calloc(1, 1); /* an empty scalar */
  if (failed || ierr || !text) {
    free(text);
    return NULL;
  }
  text[*len] = '\0';
  return text;
}

/* FB_EPARSE at n unless libfyaml's two readings of its text agree: the
 * decoded length len against the length the scanner recorded for it.
 * libfyaml 0.7.12 (bookworm) decodes two '' escapes in a row of a
 * single-quoted scalar as three quotes ('x''''y' as x'''y), and
 * fy_node_get_scalar then returns the text cut to the recorded length
 * (x''') or, past its first few escapes, NULL and a leaked buffer; fixed
 * upstream in 0.9.5. Refusing it here, before any value is read, keeps
 * every later fy_node_get_scalar0 away from the defect
 * (docs/fuzzing.md). */
static int ml_check_decoding(const ml_ctx *c, struct fy_node *map, struct fy_node *n,
                             size_t len)
{
  const size_t recorded = fy_token_get_text_length(fy_node_get_scalar_token(n));
  if (recorded == len)
    return FB_OK;
  char msg[320];
  snprintf(msg, sizeof msg,
           "the YAML library (libfyaml %s) cannot read this quoted text reliably (it decodes "
           "%zu bytes where it recorded %zu: two '' escapes in a row inside single quotes); "
           "write the text in double quotes",
           fy_library_version(), len, recorded);
  return ml_report(c, n, map ? map : n, NULL, FB_EPARSE, msg);
}

/* A NUL in the text of scalar n is an error; in a key (map is its
 * mapping), which is always a name, so is any control character. Text
 * that libfyaml decodes inconsistently is an error too. */
static int ml_check_scalar(const ml_ctx *c, struct fy_node *map, struct fy_node *n)
{
  size_t len = 0;
  char *text = ml_scalar_copy(n, &len);
  if (text && ml_check_decoding(c, map, n, len)) {
    free(text);
    return FB_EPARSE;
  }
  unsigned code = 0;
  const int clean =
      !text || (map ? fb_text_find_control(text, len, 0, &code) == len : !memchr(text, 0, len));
  free(text);
  if (clean)
    return FB_OK;
  char what[64], msg[256];
  ml_control_name(code, what, sizeof what);
  if (!map) {
    snprintf(msg, sizeof msg,
             "the value has %s in its text (a '\\0' escape of a double-quoted scalar?); "
             "no value may hold one (the text would end there)",
             what);
    return ml_report(c, n, n, NULL, FB_EPARSE, msg);
  }
  snprintf(msg, sizeof msg,
           "a key has %s in its text; keys are names, one line of printable text", what);
  /* The key's own text stays out of the key path: it is what is wrong. */
  return ml_report(c, n, map, NULL, FB_EPARSE, msg);
}

/* ml_check_scalar on every scalar below n as written (aliases are not
 * followed: what they copy is checked where it is written); the
 * recursion is as deep as the text nests, which the parser limits to 64. */
static int ml_check_scalars(const ml_ctx *c, struct fy_node *n)
{
  if (fy_node_is_alias(n))
    return FB_OK;
  if (fy_node_is_scalar(n))
    return ml_check_scalar(c, NULL, n);
  void *iter = NULL;
  int rc = FB_OK;
  if (fy_node_is_sequence(n)) {
    struct fy_node *item;
    while (!rc && (item = fy_node_sequence_iterate(n, &iter)))
      rc = ml_check_scalars(c, item);
    return rc;
  }
  struct fy_node_pair *pair;
  while (!rc && fy_node_is_mapping(n) && (pair = fy_node_mapping_iterate(n, &iter))) {
    struct fy_node *key = fy_node_pair_key(pair), *value = fy_node_pair_value(pair);
    if (key && fy_node_is_scalar(key) && !fy_node_is_alias(key))
      rc = ml_check_scalar(c, n, key);
    else if (key)
      rc = ml_check_scalars(c, key);
    if (!rc && value)
      rc = ml_check_scalars(c, value);
  }
  return rc;
}

/* FB_EPARSE at n if text holds a control character: any for one-line
 * text, any but tab and line breaks for free text (layout 1). */
static int ml_check_line(const ml_ctx *c, struct fy_node *n, const char *text, int layout)
{
  unsigned code = 0;
  const size_t len = strlen(text);
  const size_t at = fb_text_find_control(text, len, layout, &code);
  if (at == len)
    return FB_OK;
  size_t chars = 1; /* UTF-8 characters up to it: the bytes that start one */
  for (size_t i = 0; i < at; ++i)
    chars += ((unsigned char)text[i] & 0xc0) != 0x80;
  char what[64];
  ml_control_name(code, what, sizeof what);
  return ml_fail(c, n, FB_EPARSE,
                 "has %s (character %zu of the text); names, units, labels, file names and "
                 "the other text values are one line of printable text, without control "
                 "characters (they go into CSV headers, JSON, DOT, Markdown and gnuplot files)",
                 what, chars);
}

/* ---- Suggestions: optimal string alignment distance (Levenshtein with
 * adjacent transpositions; Damerau, CACM 7(3), 1964), case-insensitive. */

/* ---- Typed getters. */

static const char *ml_kind_word(struct fy_node *n)
{
  if (fy_node_is_mapping(n))
    return "a mapping";
  if (fy_node_is_sequence(n))
    return "a list";
  return "a scalar";
}

int ml_is_null(struct fy_node *n)
{
  if (!n || fy_node_is_null(n))
    return 1;
  if (!fy_node_is_scalar(n) || fy_node_get_style(n) != FYNS_PLAIN)
    return 0;
  const char *t = fy_node_get_scalar0(n);
  return !t || !strcmp(t, "") || !strcmp(t, "~") || !strcmp(t, "null") || !strcmp(t, "Null") ||
         !strcmp(t, "NULL");
}

int ml_refuse_other_format(const ml_ctx *c, struct fy_node *root, const char *own)
{
  const int model = strcmp(own, "model") == 0;
  struct fy_node *other = NULL;
  if (!root || !fy_node_is_mapping(root) || ml_get(root, own, NULL))
    return FB_OK;
  ml_get(root, model ? "scenario" : "model", &other);
  if (!other)
    return FB_OK;
  if (model)
    return ml_fail_key(c, root, other, FB_EPARSE,
                       "this is a scenario file (docs/scenario-format.md), not a model file: "
                       "flexbond run, modes, mesh, export, freq, model and sweep read it, "
                       "and diagram, causality and eig read either kind");
  return ml_fail_key(c, root, other, FB_EPARSE,
                     "this is a model file (docs/model-format.md), not a scenario file: "
                     "flexbond sim, diagram, causality and eig read it");
}

struct fy_node *ml_get(struct fy_node *map, const char *key, struct fy_node **key_node)
{
  struct fy_node_pair *pair = fy_node_mapping_lookup_pair_by_string(map, key, (size_t)-1);
  if (key_node)
    *key_node = pair ? fy_node_pair_key(pair) : NULL;
  return pair ? fy_node_pair_value(pair) : NULL;
}

int ml_require(const ml_ctx *c, struct fy_node *map, const char *key, struct fy_node **out)
{
  struct fy_node *key_node = NULL;
  *out = ml_get(map, key, &key_node);
  if (!key_node)
    return ml_fail(c, map, FB_EPARSE, "missing required key '%s'", key);
  if (ml_is_null(*out))
    return ml_fail_key(c, map, key_node, FB_EPARSE, "missing value");
  return FB_OK;
}

int ml_expect_map(const ml_ctx *c, struct fy_node *n, const char *what)
{
  if (fy_node_is_mapping(n))
    return FB_OK;
  return ml_fail(c, n, FB_EPARSE, "expected %s (a mapping), got %s", what, ml_kind_word(n));
}

int ml_expect_seq(const ml_ctx *c, struct fy_node *n, const char *what)
{
  if (fy_node_is_sequence(n))
    return FB_OK;
  return ml_fail(c, n, FB_EPARSE, "expected %s (a list), got %s", what, ml_kind_word(n));
}

/* "a, b, c" of a NULL-terminated list, into buf. */
static void ml_join(const char *const *list, char *buf, size_t size)
{
  size_t len = 0;
  buf[0] = '\0';
  for (size_t i = 0; list[i]; ++i)
    ml_append(buf, size, &len, "%s%s", i ? ", " : "", list[i]);
}

int ml_check_keys(const ml_ctx *c, struct fy_node *map, const char *const *allowed)
{
  void *iter = NULL;
  struct fy_node_pair *pair;
  while ((pair = fy_node_mapping_iterate(map, &iter))) {
    struct fy_node *key = fy_node_pair_key(pair);
    const char *text = fy_node_is_scalar(key) ? fy_node_get_scalar0(key) : NULL;
    if (!text)
      return ml_fail(c, map, FB_EPARSE, "keys must be plain names");
    size_t i = 0;
    while (allowed[i] && strcmp(allowed[i], text) != 0)
      ++i;
    if (allowed[i])
      continue;
    const char *near = fb_suggest_list(text, allowed);
    if (near)
      return ml_fail_key(c, map, key, FB_EPARSE, "unknown key '%s' (did you mean '%s'?)", text,
                         near);
    if (!allowed[0])
      return ml_fail_key(c, map, key, FB_EPARSE, "unknown key '%s': this mapping takes no key",
                         text);
    char list[512];
    ml_join(allowed, list, sizeof list);
    return ml_fail_key(c, map, key, FB_EPARSE, "unknown key '%s'; allowed keys: %s", text,
                       list);
  }
  return FB_OK;
}

/* The text of scalar n, checked by ml_check_line. */
static int ml_scalar_text(const ml_ctx *c, struct fy_node *n, int layout, const char **out)
{
  *out = NULL;
  if (ml_is_null(n))
    return ml_fail(c, n, FB_EPARSE, "expected a string, got nothing");
  if (!fy_node_is_scalar(n))
    return ml_fail(c, n, FB_EPARSE, "expected a string, got %s", ml_kind_word(n));
  const char *text = fy_node_get_scalar0(n);
  if (!text)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory reading a YAML scalar");
  int rc = ml_check_line(c, n, text, layout);
  if (!rc)
    *out = text;
  return rc;
}

int ml_string(const ml_ctx *c, struct fy_node *n, const char **out)
{
  return ml_scalar_text(c, n, 0, out);
}

int ml_text(const ml_ctx *c, struct fy_node *n, const char **out)
{
  return ml_scalar_text(c, n, 1, out);
}

int ml_is_identifier(const char *s)
{
  int ok = isalpha((unsigned char)s[0]) || s[0] == '_';
  for (size_t i = 0; ok && s[i]; ++i)
    ok = isalnum((unsigned char)s[i]) || s[i] == '_';
  return ok;
}

int ml_name(const ml_ctx *c, struct fy_node *n, const char *what, const char **out)
{
  int rc = ml_string(c, n, out);
  if (rc)
    return rc;
  if (!ml_is_identifier(*out))
    return ml_fail(c, n, FB_EPARSE,
                   "%s '%s' must start with a letter or '_' and contain only letters, "
                   "digits and '_'",
                   what, *out);
  if (strlen(*out) > ML_NAME_MAX)
    return ml_fail(c, n, FB_EINVAL,
                   "a name of %zu characters, more than %d (names become mesh node sets, "
                   "whose labels have at most 80)",
                   strlen(*out), ML_NAME_MAX);
  return FB_OK;
}

int ml_bool(const ml_ctx *c, struct fy_node *n, int *out)
{
  static const char *const yes[] = {"true", "True", "TRUE", "yes", "Yes", "on", NULL};
  static const char *const no[] = {"false", "False", "FALSE", "no", "No", "off", NULL};
  const char *t = NULL;
  int rc = ml_string(c, n, &t);
  if (rc)
    return rc;
  for (size_t i = 0; yes[i]; ++i)
    if (!strcmp(t, yes[i]) || !strcmp(t, no[i])) {
      *out = !strcmp(t, yes[i]);
      return FB_OK;
    }
  return ml_fail(c, n, FB_EPARSE, "expected true or false, got '%s'", t);
}

/* A whole-text decimal number, as strtod reads it. */
static int ml_parse_plain_number(const char *text, double *out)
{
  char *end = NULL;
  double v = strtod(text, &end);
  if (end == text)
    return 0;
  while (isspace((unsigned char)*end))
    ++end;
  if (*end)
    return 0;
  *out = v;
  return 1;
}

/* YAML's spellings of infinity and not-a-number (.inf, -.Inf, .NaN, ...;
 * the core schema of YAML 1.2, section 10.3.2), which strtod does not read. */
static int ml_is_yaml_special_float(const char *text)
{
  static const char *const words[] = {".inf", ".Inf", ".INF", ".nan", ".NaN", ".NAN", NULL};
  const char *t = (text[0] == '+' || text[0] == '-') ? text + 1 : text;
  for (size_t i = 0; words[i]; ++i)
    if (!strcmp(t, words[i]))
      return 1;
  return 0;
}

/* 1 if text is a number followed by a word, such as "10 km/h" or "2kg": a
 * unit written into the value, which no expression can be (a number
 * and a name are never next to each other in the grammar, expr.h). */
static int ml_number_with_unit(const char *text)
{
  const char *digits = text + (text[0] == '-' || text[0] == '+');
  if (!isdigit((unsigned char)digits[0]) && digits[0] != '.')
    return 0; /* strtod would also take "inf" of a name such as "info" */
  char *end = NULL;
  strtod(text, &end);
  if (end == text)
    return 0;
  while (*end == ' ')
    ++end;
  return isalpha((unsigned char)*end) || *end == '%';
}

/* FB_OK if text, which strtod read whole as a finite number, is a plain
 * decimal (fb_parse_decimal, as the CSV, mtx and deck readers take
 * numbers); strtod alone also reads hexadecimal ("0x10", "0x1p-3"). */
static int ml_check_decimal(const ml_ctx *c, struct fy_node *n, const char *text)
{
  char trimmed[128];
  size_t skip = strspn(text, " \t"), len = strlen(text + skip);
  while (len > 0 && isspace((unsigned char)text[skip + len - 1]))
    --len;
  if (len >= sizeof trimmed)
    return FB_OK; /* strtod read it whole: hexadecimal is never this long in a file */
  memcpy(trimmed, text + skip, len);
  trimmed[len] = '\0';
  fb_err why;
  double v = 0;
  if (fb_parse_decimal(trimmed, &v, &why) == FB_OK)
    return FB_OK;
  return ml_fail(c, n, FB_EPARSE,
                 "%s: numbers are written in decimal digits (as 16, 0.5 or 1e-3; hexadecimal "
                 "is not read)",
                 why.msg);
}

int ml_number(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, double *out)
{
  if (ml_is_null(n))
    return ml_fail(c, n, FB_EPARSE, "expected a number or expression, got nothing");
  if (!fy_node_is_scalar(n))
    return ml_fail(c, n, FB_EPARSE, "expected a number or expression, got %s", ml_kind_word(n));
  const char *text = fy_node_get_scalar0(n);
  if (!text)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory reading a YAML scalar");
  double v = 0;
  if (ml_is_yaml_special_float(text))
    return ml_fail(c, n, FB_EINVAL, "must be finite (got %s)", text);
  if (ml_parse_plain_number(text, &v)) {
    if (!isfinite(v))
      return ml_fail(c, n, FB_EINVAL, "must be finite (got %s)", text);
    fb_err why;
    if (fb_decimal_check_exact(text, v, &why) != FB_OK)
      return ml_fail(c, n, FB_EINVAL, "%s", why.msg);
    int rc = ml_check_decimal(c, n, text);
    if (!rc)
      *out = v;
    return rc;
  }
  if (ml_number_with_unit(text))
    return ml_fail(c, n, FB_EPARSE,
                   "expected a number, got '%s': write the number alone; values are in SI "
                   "units unless the key's name gives the unit (speed_kmh: km/h, angle_deg: "
                   "degrees)",
                   text);
  if (fb_expr_eval_const(text, syms, &v, c->err) != FB_OK) {
    char why[FB_ERR_MSG_MAX];
    snprintf(why, sizeof why, "%s", c->err->msg);
    fb_err_set(c->err, c->err->code,
               "expression '%s': %s; expected a number or an expression of the parameters",
               text, why);
    return ml_blame(c, n);
  }
  *out = v;
  return FB_OK;
}

int ml_opt_number(const ml_ctx *c, struct fy_node *map, const char *key, const fb_symtab *syms,
                  double *out)
{
  struct fy_node *key_node = NULL;
  struct fy_node *v = ml_get(map, key, &key_node);
  if (!key_node)
    return FB_OK;
  if (ml_is_null(v))
    return ml_fail_key(c, map, key_node, FB_EPARSE, "missing value");
  return ml_number(c, v, syms, out);
}

int ml_count(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, size_t lo, size_t hi,
             size_t *out)
{
  double v = 0;
  int rc = ml_number(c, n, syms, &v);
  if (rc)
    return rc;
  if (v != floor(v) || v < (double)lo || v > (double)hi) {
    char got[32];
    fb_format_shortest(v, 15, got, sizeof got);
    return ml_fail(c, n, FB_EINVAL, "must be an integer from %zu to %zu (got %s)", lo, hi, got);
  }
  *out = (size_t)v;
  return FB_OK;
}

void ml_paths_release(ml_paths *p)
{
  for (size_t i = 0; i < p->n; ++i)
    free(p->path[i]);
  free(p->path);
  *p = (ml_paths){0};
}

/* Adds a copy of path to p unless it is there; 0 when out of memory. */
static int ml_paths_add(ml_paths *p, const char *path)
{
  for (size_t i = 0; i < p->n; ++i)
    if (!strcmp(p->path[i], path))
      return 1;
  char *copy = fb_strdup(path);
  if (!copy || fb_grow((void **)&p->path, &p->cap, p->n, sizeof *p->path) != FB_OK) {
    free(copy);
    return 0;
  }
  p->path[p->n++] = copy;
  return 1;
}

int ml_resolve_path(const ml_ctx *c, struct fy_node *at, const char *path, char **out)
{
  *out = NULL;
  if (!path[0])
    return ml_fail(c, at, FB_EPARSE, "empty file name");
  const char *dir = (path[0] == '/' || !c->base_dir || !c->base_dir[0]) ? NULL : c->base_dir;
  char *s = dir ? fb_path_join(dir, path) : fb_strdup(path);
  if (!s)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory joining a file path");
  if (c->inputs && !ml_paths_add(c->inputs, s)) {
    free(s);
    return fb_err_set(c->err, FB_ENOMEM, "out of memory listing the files a document names");
  }
  *out = s;
  return FB_OK;
}
