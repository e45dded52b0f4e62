/* SPDX-License-Identifier: BSD-3-Clause */
/* gmsh meshes, MSH file format version 4.1 in ASCII (see flexbond/fem.h;
 * the format is specified in the gmsh reference manual, section 9.1 "MSH
 * file format").
 *
 * Read: $MeshFormat (4.1, ASCII), $PhysicalNames, $Entities (each
 * entity's physical groups), $Nodes and $Elements; other sections are
 * skipped to their $End line. 3-node triangles (type 2) and 4-node
 * quadrilaterals (type 3) on surfaces become the mesh's elements; points
 * (type 15) and 2-node lines (type 1) only carry physical groups; any other
 * type is an error. Every physical group with a name becomes a node set of
 * the nodes of its elements (a point group: its points, as LOAD or
 * FRONT_EDGE; a surface group: the nodes of its surfaces, a coupling's
 * patch), and a surface group also an element set (FLOOR, for a section).
 * Node and element tags are the mesh's ids. Each triangle and
 * quadrilateral must pass fb_mesh_check's element tests (no repeated node,
 * an area, convex and plane), else it is an error at its own line, as in
 * an .inp deck.
 *
 * Errors are "path:line: message", the path and line also in the error's
 * location fields. The format is ASCII text: a NUL or another control byte
 * than tab (and the line's end) is refused at its line. Numbers are plain
 * decimals (fb_parse_decimal, as in .inp decks and CSV files: no
 * hexadecimal, inf or nan); tags and counts are digits with an optional
 * sign.
 *
 * Reading is linear in the size of the file. The physical names and the
 * entities are sorted by (dimension, tag) once, when $Elements begins
 * (gmsh writes both sections before $Nodes: the reference manual, section
 * 9.1, lists the sections in that order), and each entity's physical
 * tags resolved to its named groups then; an element block finds its
 * entity by binary search, its nodes through the mesh's hash table of
 * tags, and adds its members to its groups' sets at a cost of its own size
 * (fb_mesh_add_nset). A search through every entity and every name, and
 * (in the mesh's sets, then) a pass over every node, for each block once
 * made a file of 150000 point entities and as many blocks take 10 s.
 * Each block adds to each of its entity's named groups, which is why an
 * entity may be in at most MSH_MAX_GROUPS of them.
 *
 * This is a reader of its own rather than libgmsh: the library keeps one
 * process-wide model (gmsh::initialize, gmsh::open), which a sweep's
 * threads cannot share, and reports errors through its logger, not as a
 * file, line and value; the format itself is a few plain sections. */
#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/textfile.h"
#include "core/util.h"
#include "fem/mesh_internal.h"

/* Physical tags of one entity, as written. */
#define MSH_MAX_PHYS 1024
/* Named physical groups of one entity (docs/errors.md, "Limits"): every
 * element block on the entity adds its members to each, so the work of a
 * block is its size times this. A hull's point is in a few (LOAD,
 * FRONT_EDGE, SUSP_LF), a surface in its plate's group and FLOOR. */
#define MSH_MAX_GROUPS 16

/* A growing array of indices (fb_grow). */
typedef struct msh_list {
  size_t *v;
  size_t n, cap;
} msh_list;

/* An entity of $Entities: its physical tags, and the named groups among
 * them (indices into the sorted names, each once). */
typedef struct msh_entity {
  int dim;
  long tag;
  size_t line;
  long *phys;
  size_t nphys;
  msh_list groups;
} msh_entity;

typedef struct msh_name {
  int dim;
  long tag;
  size_t line;
  char *name;
  size_t stamp; /* 1 + the last entity that listed it, while indexing */
} msh_name;

typedef struct msh_reader {
  const char *path;
  char *text;
  size_t len, pos;
  char *line;
  size_t lineno;
  fb_err *err;
  fb_mesh *mesh;
  msh_name *names;
  size_t nnames, names_cap;
  msh_entity *ents;
  size_t nents, ents_cap;
  int indexed;         /* names and entities sorted ($Elements begun) */
  msh_list elem_lines; /* the line of each of the mesh's elements */
} msh_reader;

static int list_push(msh_list *l, size_t x)
{
  if (fb_grow((void **)&l->v, &l->cap, l->n, sizeof *l->v))
    return FB_ENOMEM;
  l->v[l->n++] = x;
  return FB_OK;
}

/* Records FB_EPARSE as "path:line: message", with the path and line as
 * the error's location (line 0 stands for 1: an empty file). */
static int msh_error(const msh_reader *r, size_t line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int msh_error(const msh_reader *r, size_t line, const char *fmt, ...)
{
  char msg[FB_ERR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  line = line ? line : 1;
  fb_err_set(r->err, FB_EPARSE, "%s:%zu: %s", r->path, line, msg);
  fb_err_set_location(r->err, r->path, line <= INT_MAX ? (int)line : 0, 0);
  return FB_EPARSE;
}
#if defined(__clang_analyzer__)
/* For the static analyzer only, which does not follow calls to variadic functions. */
#define msh_error(r, line, ...) (msh_error((r), (line), __VA_ARGS__), FB_EPARSE)
#endif

static int msh_nomem(const msh_reader *r)
{
  return fb_err_set(r->err, FB_ENOMEM, "out of memory reading %s", r->path);
}

/* A failure of a mesh call (message in sub) reported at line; out of
 * memory keeps its code. */
static int msh_mesh_error(const msh_reader *r, size_t line, const fb_err *sub)
{
  if (sub->code == FB_ENOMEM)
    return msh_nomem(r);
  const int rc = msh_error(r, line, "%s", sub->msg);
  fb_err_set_excerpt(r->err, sub->excerpt, sizeof sub->excerpt);
  return rc;
}

/* rc, after recording the file's text the error just set is about as its
 * excerpt: a mesh file's text goes there, never into the message. */
static int msh_quoting(const msh_reader *r, const char *text, int rc)
{
  fb_err_set_excerpt(r->err, text, strlen(text));
  return rc;
}

/* ---- Lines and fields. */

/* The next line into r->line (its end of line cut); *got is 0 at the end.
 * A control byte other than tab marks binary data: the format is ASCII
 * text (gmsh reference manual, section 9.1). */
static int next_line(msh_reader *r, int *got)
{
  *got = r->pos < r->len;
  if (!*got)
    return FB_OK;
  const size_t col = fb_text_split_line(r->text, r->len, &r->pos, &r->line);
  ++r->lineno;
  if (!col)
    return FB_OK;
  msh_error(r, r->lineno, "binary data (byte 0x%02x in column %zu): not an ASCII .msh file",
            (unsigned char)r->line[col - 1], col);
  fb_err_set_location(r->err, r->path, r->lineno <= INT_MAX ? (int)r->lineno : 0,
                      col <= INT_MAX ? (int)col : 0);
  return FB_EPARSE;
}

/* The next line, which must exist (what says what it should hold). */
static int need_line(msh_reader *r, const char *what)
{
  int got = 0;
  const int rc = next_line(r, &got);
  if (!rc && !got)
    return msh_error(r, r->lineno, "the file ends where %s should be", what);
  return rc;
}

/* The next field of the line at *p (the format separates them by
 * blanks), cut off in place: the text is the reader's own copy. NULL when
 * the line has no more. */
static char *next_field(char **p)
{
  char *s = *p + strspn(*p, " \t");
  char *end = s + strcspn(s, " \t");
  *p = *end ? end + 1 : end;
  *end = '\0';
  return *s ? s : NULL;
}

/* 1 if field is an integer as gmsh writes tags and counts: an optional
 * sign, then decimal digits only. */
static int is_integer(const char *field)
{
  const char *d = field + (field[0] == '+' || field[0] == '-');
  return d[0] != '\0' && d[strspn(d, "0123456789")] == '\0';
}

/* Integer fields of the current line from *p: n of them into v. */
static int ints(msh_reader *r, char **p, long *v, size_t n, const char *what)
{
  for (size_t k = 0; k < n; ++k) {
    const char *f = next_field(p);
    if (!f)
      return msh_error(r, r->lineno, "%s: expected %zu integers", what, n);
    if (!is_integer(f))
      return msh_quoting(r, f, msh_error(r, r->lineno, "%s: not an integer", what));
    errno = 0;
    v[k] = strtol(f, NULL, 10);
    if (errno)
      return msh_quoting(r, f, msh_error(r, r->lineno, "%s: an integer out of range", what));
  }
  return FB_OK;
}

/* Real fields: n plain decimal numbers into v. */
static int reals(msh_reader *r, char **p, double *v, size_t n, const char *what)
{
  fb_err sub;
  fb_err_clear(&sub);
  for (size_t k = 0; k < n; ++k) {
    const char *f = next_field(p);
    if (!f)
      return msh_error(r, r->lineno, "%s: expected %zu numbers", what, n);
    if (fb_parse_decimal_field(f, &v[k], &sub))
      return msh_quoting(r, f, msh_error(r, r->lineno, "%s: %s", what, sub.msg));
  }
  return FB_OK;
}

/* Nothing but blanks left on the line. */
static int line_done(msh_reader *r, const char *p, const char *what)
{
  p += strspn(p, " \t");
  return *p ? msh_quoting(r, p, msh_error(r, r->lineno, "%s: unexpected text", what)) : FB_OK;
}

/* A count read from a file, bounded by what the rest of the text could
 * hold (each item at least two bytes), so that no allocation follows a
 * wrong count. */
static int count_ok(msh_reader *r, long n, const char *what)
{
  if (n < 0 || (size_t)n > (r->len - r->pos) / 2 + 1)
    return msh_error(r, r->lineno, "%s %ld is not a count this file can hold", what, n);
  return FB_OK;
}

static int expect_end(msh_reader *r, const char *section)
{
  const int rc = need_line(r, section);
  if (!rc && (strncmp(r->line, "$End", 4) != 0 || strcmp(r->line + 4, section + 1) != 0))
    return msh_error(r, r->lineno, "expected $End%s", section + 1);
  return rc;
}

/* ---- Sections before $Nodes. */

static int read_format(msh_reader *r)
{
  int rc = need_line(r, "the format line");
  char *p = r->line;
  double version = 0.0;
  long rest[2] = {0, 0};
  if (!rc)
    rc = reals(r, &p, &version, 1, "$MeshFormat");
  if (!rc)
    rc = ints(r, &p, rest, 2, "$MeshFormat");
  if (!rc && version != 4.1)
    return msh_error(r, r->lineno,
                     "MSH format %g is not supported: write version 4.1 (gmsh -format msh41)",
                     version);
  if (!rc && rest[0] != 0)
    return msh_error(r, r->lineno,
                     "a binary .msh file is not supported: write it in ASCII (gmsh -bin 0)");
  return rc ? rc : expect_end(r, "$MeshFormat");
}

/* One line of $PhysicalNames: dimension, tag and a quoted name. */
static int read_name(msh_reader *r)
{
  long dt[2] = {0, 0};
  int rc = need_line(r, "a physical name");
  char *p = r->line;
  if (!rc)
    rc = ints(r, &p, dt, 2, "physical name");
  char *q1 = rc ? NULL : strchr(p, '"'), *q2 = q1 ? strchr(q1 + 1, '"') : NULL;
  if (!rc && !q2)
    return msh_error(r, r->lineno, "physical name: expected dimension, tag and a quoted name");
  if (rc)
    return rc;
  *q2 = '\0';
  if (!fb_mesh_name_ok(q1 + 1))
    return msh_quoting(r, q1 + 1,
                       msh_error(r, r->lineno,
                                 "the physical name cannot name a set (1 to %d characters from "
                                 "A-Z a-z 0-9 _ . -, starting with a letter or _)",
                                 FB_MESH_NAME_MAX));
  if (fb_grow((void **)&r->names, &r->names_cap, r->nnames, sizeof *r->names))
    return msh_nomem(r);
  msh_name *nm = &r->names[r->nnames];
  memset(nm, 0, sizeof *nm);
  nm->dim = (int)dt[0];
  nm->tag = dt[1];
  nm->line = r->lineno;
  nm->name = fb_strdup(q1 + 1);
  if (!nm->name)
    return msh_nomem(r);
  ++r->nnames;
  return FB_OK;
}

static int read_names(msh_reader *r)
{
  long n = 0;
  int rc = need_line(r, "the number of physical names");
  char *p = r->line;
  if (!rc)
    rc = ints(r, &p, &n, 1, "$PhysicalNames");
  if (!rc)
    rc = count_ok(r, n, "physical name count");
  for (long i = 0; !rc && i < n; ++i)
    rc = read_name(r);
  return rc ? rc : expect_end(r, "$PhysicalNames");
}

/* One entity line of dimension dim: tag, its position or bounding box,
 * its physical tags (the bounding entities after them are not needed). */
static int read_entity(msh_reader *r, int dim)
{
  long tag = 0, nphys = 0;
  int rc = need_line(r, "an entity");
  char *p = r->line;
  if (!rc)
    rc = ints(r, &p, &tag, 1, "entity");
  if (!rc) {
    double box[6]; /* its point, or its bounding box: not needed */
    rc = reals(r, &p, box, dim == 0 ? 3 : 6, "entity");
  }
  if (!rc)
    rc = ints(r, &p, &nphys, 1, "entity");
  if (!rc && (nphys < 0 || nphys > MSH_MAX_PHYS))
    return msh_error(r, r->lineno, "entity %ld: %ld physical tags", tag, nphys);
  if (rc)
    return rc;
  if (fb_grow((void **)&r->ents, &r->ents_cap, r->nents, sizeof *r->ents))
    return msh_nomem(r);
  msh_entity *e = &r->ents[r->nents];
  *e = (msh_entity){.dim = dim, .tag = tag, .line = r->lineno, .nphys = (size_t)nphys};
  e->phys = malloc(((size_t)nphys + 1) * sizeof *e->phys);
  if (!e->phys)
    return msh_nomem(r);
  ++r->nents;
  return ints(r, &p, e->phys, (size_t)nphys, "entity's physical tags");
}

static int read_entities(msh_reader *r)
{
  long n[4] = {0, 0, 0, 0};
  int rc = need_line(r, "the entity counts");
  char *p = r->line;
  if (!rc)
    rc = ints(r, &p, n, 4, "$Entities");
  for (int d = 0; d < 4 && !rc; ++d) {
    rc = count_ok(r, n[d], "entity count");
    for (long i = 0; !rc && i < n[d]; ++i)
      rc = read_entity(r, d);
  }
  return rc ? rc : expect_end(r, "$Entities");
}

/* ---- The index of names and entities. */

static int key_cmp(int da, long ta, int db, long tb)
{
  if (da != db)
    return da < db ? -1 : 1;
  return ta < tb ? -1 : ta > tb;
}

static int name_key(const void *a, const void *b)
{
  const msh_name *x = a, *y = b;
  return key_cmp(x->dim, x->tag, y->dim, y->tag);
}

/* By key, then by line: a key given twice sorts its repeat second. */
static int name_order(const void *a, const void *b)
{
  const msh_name *x = a, *y = b;
  const int c = name_key(a, b);
  return c ? c : (x->line > y->line) - (x->line < y->line);
}

static int entity_key(const void *a, const void *b)
{
  const msh_entity *x = a, *y = b;
  return key_cmp(x->dim, x->tag, y->dim, y->tag);
}

static int entity_order(const void *a, const void *b)
{
  const msh_entity *x = a, *y = b;
  const int c = entity_key(a, b);
  return c ? c : (x->line > y->line) - (x->line < y->line);
}

static msh_name *find_name(const msh_reader *r, int dim, long tag)
{
  const msh_name key = {.dim = dim, .tag = tag};
  return r->nnames ? bsearch(&key, r->names, r->nnames, sizeof *r->names, name_key) : NULL;
}

static msh_entity *find_entity(const msh_reader *r, int dim, long tag)
{
  const msh_entity key = {.dim = dim, .tag = tag};
  return r->nents ? bsearch(&key, r->ents, r->nents, sizeof *r->ents, entity_key) : NULL;
}

/* A physical name, for sorting by its text. */
typedef struct name_ref {
  const msh_name *name;
} name_ref;

static int by_name(const void *a, const void *b)
{
  const msh_name *x = ((const name_ref *)a)->name, *y = ((const name_ref *)b)->name;
  const int c = strcasecmp(x->name, y->name);
  return c ? c : (x->line > y->line) - (x->line < y->line);
}

/* FB_EPARSE at the second of two physical groups with one name (set names
 * are case-insensitive): their sets would merge, silently. */
static int check_names_unique(msh_reader *r)
{
  if (r->nnames < 2)
    return FB_OK;
  name_ref *by = malloc(r->nnames * sizeof *by);
  if (!by)
    return msh_nomem(r);
  for (size_t i = 0; i < r->nnames; ++i)
    by[i].name = &r->names[i];
  qsort(by, r->nnames, sizeof *by, by_name);
  int rc = FB_OK;
  for (size_t i = 1; !rc && i < r->nnames; ++i) {
    const msh_name *first = by[i - 1].name, *second = by[i].name;
    if (!strcasecmp(first->name, second->name))
      rc = msh_error(r, second->line,
                     "physical group %ld of dimension %d has the name of group %ld of "
                     "dimension %d (line %zu): each group needs its own, or their sets merge",
                     second->tag, second->dim, first->tag, first->dim, first->line);
  }
  free(by);
  return rc;
}

/* Sorts names and entities by (dimension, tag), refusing a key given
 * twice at its second line (the format gives each once), and a name given
 * to two groups. */
static int sort_keys(msh_reader *r)
{
  const int unique = check_names_unique(r);
  if (unique)
    return unique;
  if (r->nnames)
    qsort(r->names, r->nnames, sizeof *r->names, name_order);
  for (size_t i = 1; i < r->nnames; ++i)
    if (!name_key(&r->names[i - 1], &r->names[i]))
      return msh_error(r, r->names[i].line,
                       "physical group %ld of dimension %d is named twice (first at line %zu)",
                       r->names[i].tag, r->names[i].dim, r->names[i - 1].line);
  if (r->nents)
    qsort(r->ents, r->nents, sizeof *r->ents, entity_order);
  for (size_t i = 1; i < r->nents; ++i)
    if (!entity_key(&r->ents[i - 1], &r->ents[i]))
      return msh_error(r, r->ents[i].line,
                       "entity %ld of dimension %d is defined twice (first at line %zu)",
                       r->ents[i].tag, r->ents[i].dim, r->ents[i - 1].line);
  return FB_OK;
}

/* Entity i's named groups, each once (a physical tag may repeat). */
static int resolve_entity(msh_reader *r, size_t i)
{
  msh_entity *e = &r->ents[i];
  for (size_t k = 0; k < e->nphys; ++k) {
    msh_name *nm = find_name(r, e->dim, e->phys[k]);
    if (!nm || nm->stamp == i + 1)
      continue;
    if (e->groups.n == MSH_MAX_GROUPS)
      return msh_error(r, e->line,
                       "entity %ld is in more than %d named physical groups (docs/errors.md, "
                       "\"Limits\")",
                       e->tag, MSH_MAX_GROUPS);
    nm->stamp = i + 1;
    if (list_push(&e->groups, (size_t)(nm - r->names)))
      return msh_nomem(r);
  }
  return FB_OK;
}

/* Indexes names and entities, once, as $Elements begins: the blocks
 * name entities, which must come before them. */
static int index_groups(msh_reader *r)
{
  r->indexed = 1;
  int rc = sort_keys(r);
  for (size_t i = 0; !rc && i < r->nents; ++i)
    rc = resolve_entity(r, i);
  return rc;
}

/* ---- Nodes. */

static int read_node_block(msh_reader *r)
{
  long head[4] = {0, 0, 0, 0};
  int rc = need_line(r, "a node block");
  char *p = r->line;
  if (!rc)
    rc = ints(r, &p, head, 4, "node block");
  if (!rc)
    rc = count_ok(r, head[3], "node count");
  if (rc)
    return rc;
  long *tags = malloc(((size_t)head[3] + 1) * sizeof *tags);
  if (!tags)
    return msh_nomem(r);
  for (long i = 0; !rc && i < head[3]; ++i) {
    rc = need_line(r, "a node tag");
    p = r->line;
    if (!rc)
      rc = ints(r, &p, &tags[i], 1, "node tag");
    if (!rc)
      rc = line_done(r, p, "node tag");
  }
  fb_err sub;
  fb_err_clear(&sub);
  for (long i = 0; !rc && i < head[3]; ++i) {
    double x[3];
    rc = need_line(r, "node coordinates");
    p = r->line;
    if (!rc) /* x y z, and u v of a parametric block: not needed */
      rc = reals(r, &p, x, 3, "node coordinates");
    if (!rc && fb_mesh_add_node(r->mesh, tags[i], x[0], x[1], x[2], NULL, &sub))
      rc = msh_mesh_error(r, r->lineno, &sub);
  }
  free(tags);
  return rc;
}

static int read_nodes(msh_reader *r)
{
  long head[4] = {0, 0, 0, 0};
  int rc = need_line(r, "the node counts");
  char *p = r->line;
  if (!rc)
    rc = ints(r, &p, head, 4, "$Nodes");
  if (!rc)
    rc = count_ok(r, head[0], "node block count");
  for (long b = 0; !rc && b < head[0]; ++b)
    rc = read_node_block(r);
  return rc ? rc : expect_end(r, "$Nodes");
}

/* ---- Elements. */

/* Nodes per element of a type this reader takes (2, 3: surfaces; 1, 15:
 * group members), else 0. */
static size_t type_nodes(long type)
{
  switch (type) {
  case 15: return 1;
  case 1: return 2;
  case 2: return 3;
  case 3: return 4;
  default: return 0;
  }
}

/* The node indices of an element line's node tags. */
static int element_nodes(msh_reader *r, char **p, size_t nn, size_t *idx)
{
  long tags[4];
  int rc = ints(r, p, tags, nn, "element");
  for (size_t k = 0; !rc && k < nn; ++k) {
    const long i = fb_mesh_find_node_id(r->mesh, tags[k]);
    if (i < 0)
      return msh_error(r, r->lineno, "the element names node %ld, which is not defined",
                       tags[k]);
    idx[k] = (size_t)i;
  }
  return rc;
}

/* A triangle or quadrilateral into the mesh, its line kept for the shape
 * checks. */
static int add_surface_element(msh_reader *r, long tag, size_t nn, const size_t *nodes)
{
  fb_err sub;
  fb_err_clear(&sub);
  if (list_push(&r->elem_lines, r->lineno))
    return msh_nomem(r);
  if (fb_mesh_add_element(r->mesh, tag, nn == 3 ? FB_ELEM_TRI3 : FB_ELEM_QUAD4, nodes, &sub))
    return msh_mesh_error(r, r->lineno, &sub);
  return FB_OK;
}

/* One element line of a block of nn-node elements: its node indices into
 * nodes, its index in the mesh into *index (for a surface element). */
static int read_element(msh_reader *r, size_t nn, size_t *nodes, size_t *index)
{
  long tag = 0;
  int rc = need_line(r, "an element");
  char *p = r->line;
  if (!rc)
    rc = ints(r, &p, &tag, 1, "element");
  if (!rc)
    rc = element_nodes(r, &p, nn, nodes);
  if (!rc)
    rc = line_done(r, p, "element");
  *index = fb_mesh_nelements(r->mesh);
  if (!rc && nn >= 3)
    rc = add_surface_element(r, tag, nn, nodes);
  return rc;
}

/* The block's members into the sets of its entity's named groups: its
 * nodes (all kinds) and, for surface elements, the elements. */
static int add_to_groups(msh_reader *r, const msh_entity *ent, const size_t *nodes, size_t n,
                         const size_t *elems, size_t ne)
{
  fb_err sub;
  fb_err_clear(&sub);
  for (size_t k = 0; k < ent->groups.n; ++k) {
    const char *name = r->names[ent->groups.v[k]].name;
    if (fb_mesh_add_nset(r->mesh, name, n, nodes, &sub) ||
        (ne && fb_mesh_add_elset(r->mesh, name, ne, elems, &sub)))
      return msh_mesh_error(r, r->lineno, &sub);
  }
  return FB_OK;
}

static int read_element_block(msh_reader *r)
{
  long head[4] = {0, 0, 0, 0};
  int rc = need_line(r, "an element block");
  char *p = r->line;
  if (!rc)
    rc = ints(r, &p, head, 4, "element block");
  if (!rc)
    rc = count_ok(r, head[3], "element count");
  const size_t nn = type_nodes(head[2]);
  if (!rc && nn == 0)
    return msh_error(r, r->lineno,
                     "element type %ld is not supported: flexbond takes 3-node triangles and "
                     "4-node quadrilaterals (gmsh -order 1)",
                     head[2]);
  if (!rc && (head[0] == 2) != (nn >= 3))
    return msh_error(r, r->lineno, "element type %ld on an entity of dimension %ld", head[2],
                     head[0]);
  if (rc)
    return rc;
  const msh_entity *ent = find_entity(r, (int)head[0], head[1]);
  const size_t count = (size_t)head[3];
  size_t *nodes = malloc((count * nn + 1) * sizeof *nodes);
  size_t *elems = malloc((count + 1) * sizeof *elems);
  if (!nodes || !elems)
    rc = msh_nomem(r);
  for (size_t i = 0; !rc && i < count; ++i)
    rc = read_element(r, nn, &nodes[i * nn], &elems[i]);
  if (!rc && ent)
    rc = add_to_groups(r, ent, nodes, count * nn, elems, nn >= 3 ? count : 0);
  free(nodes);
  free(elems);
  return rc;
}

static int read_elements(msh_reader *r)
{
  long head[4] = {0, 0, 0, 0};
  int rc = r->indexed ? FB_OK : index_groups(r);
  if (!rc)
    rc = need_line(r, "the element counts");
  char *p = r->line;
  if (!rc)
    rc = ints(r, &p, head, 4, "$Elements");
  if (!rc)
    rc = count_ok(r, head[0], "element block count");
  for (long b = 0; !rc && b < head[0]; ++b)
    rc = read_element_block(r);
  return rc ? rc : expect_end(r, "$Elements");
}

/* ---- The whole file. */

/* Skips an unknown section to its $End line. */
static int skip_section(msh_reader *r, const char *name)
{
  for (;;) {
    const int rc = need_line(r, "the section's end");
    if (rc)
      return rc;
    if (strncmp(r->line, "$End", 4) == 0 && strcmp(r->line + 4, name + 1) == 0)
      return FB_OK;
  }
}

/* One section, from its name line on. */
static int read_section(msh_reader *r, const char *name, int *have_nodes)
{
  const int names = !strcmp(name, "$PhysicalNames"), ents = !strcmp(name, "$Entities");
  if ((names || ents) && r->indexed)
    return msh_error(r, r->lineno,
                     "%s after $Elements: it must come before $Elements, as gmsh writes it",
                     name);
  if (names)
    return read_names(r);
  if (ents)
    return read_entities(r);
  if (!strcmp(name, "$MeshFormat"))
    return read_format(r);
  if (!strcmp(name, "$Nodes")) {
    *have_nodes = 1;
    return read_nodes(r);
  }
  if (!strcmp(name, "$Elements"))
    return *have_nodes ? read_elements(r) : msh_error(r, r->lineno, "$Elements before $Nodes");
  return skip_section(r, name);
}

static int read_sections(msh_reader *r)
{
  int got = 0, have_format = 0, have_nodes = 0;
  for (;;) {
    int rc = next_line(r, &got);
    if (rc)
      return rc;
    if (!got)
      break;
    char *name = r->line + strspn(r->line, " \t");
    if (*name == '\0')
      continue;
    if (*name != '$')
      return msh_quoting(r, name,
                         msh_error(r, r->lineno, "expected a section ($Name) on this line"));
    if (!have_format && strcmp(name, "$MeshFormat") != 0)
      return msh_error(r, r->lineno, "not a .msh file: it does not start with $MeshFormat");
    have_format = 1;
    rc = read_section(r, name, &have_nodes);
    if (rc)
      return rc;
  }
  if (!have_format)
    return msh_error(r, r->lineno, "empty file: not a .msh file");
  if (fb_mesh_nelements(r->mesh) == 0)
    return msh_error(r, r->lineno, "the file has no triangles or quadrilaterals");
  return FB_OK;
}

/* An element that no shell can integrate (fb_mesh_check's element tests)
 * is reported at its own line, where it must be fixed, as in .inp decks. */
static int check_element_shapes(const msh_reader *r)
{
  fb_err sub;
  fb_err_clear(&sub);
  size_t bad = 0;
  if (fb_mesh_check_elements(r->mesh, &bad, &sub) == FB_OK)
    return FB_OK;
  return msh_mesh_error(r, r->elem_lines.v[bad], &sub);
}

static void reader_free(msh_reader *r)
{
  for (size_t i = 0; i < r->nnames; ++i)
    free(r->names[i].name);
  free(r->names);
  for (size_t i = 0; i < r->nents; ++i) {
    free(r->ents[i].phys);
    free(r->ents[i].groups.v);
  }
  free(r->ents);
  free(r->elem_lines.v);
  free(r->text);
}

/* Takes text (NUL-terminated, len bytes before it; freed here). */
static int read_msh_buffer(char *text, size_t len, const char *name, fb_mesh **out, fb_err *err)
{
  msh_reader r;
  memset(&r, 0, sizeof r);
  r.path = name;
  r.text = text;
  r.len = len;
  r.err = err;
  int rc = fb_mesh_new(&r.mesh, err);
  if (!rc)
    rc = read_sections(&r);
  if (!rc)
    rc = check_element_shapes(&r);
  if (rc)
    fb_mesh_free(&r.mesh);
  *out = r.mesh;
  reader_free(&r);
  return rc;
}

int fb_mesh_read_file(const char *path, fb_mesh **out, fb_err *err)
{
  const size_t n = path ? strlen(path) : 0;
  if (n > 4 && strcasecmp(path + n - 4, ".msh") == 0)
    return fb_mesh_read_msh(path, out, err);
  return fb_mesh_read_inp(path, out, NULL, err);
}

int fb_mesh_read_msh(const char *path, fb_mesh **out, fb_err *err)
{
  if (!out || !path)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_read_msh: NULL argument");
  *out = NULL;
  char *text = NULL;
  size_t len = 0;
  const int rc = fb_read_file(path, &text, &len, err);
  return rc ? rc : read_msh_buffer(text, len, path, out, err);
}

int fb_mesh_read_msh_string(const char *text, size_t len, const char *display_name,
                            fb_mesh **out, fb_err *err)
{
  if (!out || !text)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_read_msh_string: NULL argument");
  *out = NULL;
  const char *name = display_name ? display_name : "<string>";
  char *copy;
  const int rc = fb_text_copy(text, len, name, &copy, err);
  return rc ? rc : read_msh_buffer(copy, len, name, out, err);
}
