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
 * Node and element tags are the mesh's ids.
 *
 * This is a reader of its own rather than libgmsh: the library keeps one
 * process-wide model (gmsh::initialize, gmsh::open), which a sweep's
 * threads cannot share, and reports errors through its logger, not as a
 * file, line and value; the format itself is a few plain sections. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/textfile.h"
#include "core/util.h"
#include "fem/mesh_internal.h"

/* An entity's physical groups, as (dim, tag) keys into the names. */
typedef struct msh_entity {
  int dim;
  long tag;
  long *phys;
  size_t nphys;
} msh_entity;

typedef struct msh_name {
  int dim;
  long tag;
  char *name;
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
} msh_reader;

static int msh_error(const msh_reader *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

static int msh_error(const msh_reader *r, const char *fmt, ...)
{
  char msg[FB_ERR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return fb_err_set(r->err, FB_EPARSE, "%s:%zu: %s", r->path, r->lineno ? r->lineno : 1, msg);
}
#if defined(__clang_analyzer__)
#define msh_error(r, ...) (msh_error((r), __VA_ARGS__), FB_EPARSE)
#endif

static int msh_nomem(const msh_reader *r)
{
  return fb_err_set(r->err, FB_ENOMEM, "out of memory reading %s", r->path);
}

/* The next line into r->line (its end of line cut); 0 at the end. A
 * control byte other than tab marks binary data. */
static int next_line(msh_reader *r, int *got)
{
  *got = r->pos < r->len;
  if (!*got)
    return FB_OK;
  const size_t col = fb_text_split_line(r->text, r->len, &r->pos, &r->line);
  ++r->lineno;
  if (col)
    return msh_error(r, "binary data (byte 0x%02x in column %zu): not an ASCII .msh file",
                     (unsigned char)r->line[col - 1], col);
  return FB_OK;
}

/* The next line, which must exist (what says what it should hold). */
static int need_line(msh_reader *r, const char *what)
{
  int got = 0;
  const int rc = next_line(r, &got);
  if (!rc && !got)
    return msh_error(r, "the file ends where %s should be", what);
  return rc;
}

/* Integer fields of the current line from *p: n of them into v. */
static int ints(msh_reader *r, char **p, long *v, size_t n, const char *what)
{
  for (size_t k = 0; k < n; ++k) {
    char *end = NULL;
    errno = 0;
    v[k] = strtol(*p, &end, 10);
    if (end == *p || errno)
      return msh_error(r, "%s: expected %zu integers", what, n);
    *p = end;
  }
  return FB_OK;
}

static int reals(msh_reader *r, char **p, double *v, size_t n, const char *what)
{
  for (size_t k = 0; k < n; ++k) {
    char *end = NULL;
    errno = 0;
    v[k] = strtod(*p, &end);
    if (end == *p || errno || !isfinite(v[k]))
      return msh_error(r, "%s: expected %zu finite numbers", what, n);
    *p = end;
  }
  return FB_OK;
}

/* Nothing but blanks left on the line. */
static int line_done(msh_reader *r, const char *p, const char *what)
{
  p += strspn(p, " \t");
  return *p ? msh_error(r, "%s: unexpected '%s'", what, p) : FB_OK;
}

/* A count read from a file, bounded by what the rest of the text could
 * hold (each item at least two bytes), so that no allocation follows a
 * wrong count. */
static int count_ok(msh_reader *r, long n, const char *what)
{
  if (n < 0 || (size_t)n > (r->len - r->pos) / 2 + 1)
    return msh_error(r, "%s %ld is not a count this file can hold", what, n);
  return FB_OK;
}

static int expect_end(msh_reader *r, const char *section)
{
  const int rc = need_line(r, section);
  if (!rc && (strncmp(r->line, "$End", 4) != 0 || strcmp(r->line + 4, section + 1) != 0))
    return msh_error(r, "expected $End%s", section + 1);
  return rc;
}

/* ---- Sections. */

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
    return msh_error(
        r, "MSH format %g is not supported: write version 4.1 (gmsh -format msh41)", version);
  if (!rc && rest[0] != 0)
    return msh_error(r, "a binary .msh file is not supported: write it in ASCII (gmsh -bin 0)");
  return rc ? rc : expect_end(r, "$MeshFormat");
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
  for (long i = 0; !rc && i < n; ++i) {
    long dt[2] = {0, 0};
    rc = need_line(r, "a physical name");
    p = r->line;
    if (!rc)
      rc = ints(r, &p, dt, 2, "physical name");
    char *q1 = rc ? NULL : strchr(p, '"'), *q2 = q1 ? strchr(q1 + 1, '"') : NULL;
    if (!rc && !q2)
      return msh_error(r, "physical name: expected dimension, tag and a quoted name");
    if (rc)
      return rc;
    *q2 = '\0';
    if (!fb_mesh_name_ok(q1 + 1))
      return msh_error(
          r,
          "physical name \"%s\" cannot name a set (1 to %d characters from A-Z a-z "
          "0-9 _ . -, starting with a letter or _)",
          q1 + 1, FB_MESH_NAME_MAX);
    if (fb_grow((void **)&r->names, &r->names_cap, r->nnames, sizeof *r->names))
      return msh_nomem(r);
    msh_name *nm = &r->names[r->nnames];
    nm->dim = (int)dt[0];
    nm->tag = dt[1];
    nm->name = fb_strdup(q1 + 1);
    if (!nm->name)
      return msh_nomem(r);
    ++r->nnames;
  }
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
  if (!rc && (nphys < 0 || nphys > 1024))
    return msh_error(r, "entity %ld: %ld physical tags", tag, nphys);
  if (rc)
    return rc;
  if (fb_grow((void **)&r->ents, &r->ents_cap, r->nents, sizeof *r->ents))
    return msh_nomem(r);
  msh_entity *e = &r->ents[r->nents];
  *e = (msh_entity){dim, tag, malloc(((size_t)nphys + 1) * sizeof *e->phys), (size_t)nphys};
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

static const msh_entity *find_entity(const msh_reader *r, int dim, long tag)
{
  for (size_t i = 0; i < r->nents; ++i)
    if (r->ents[i].dim == dim && r->ents[i].tag == tag)
      return &r->ents[i];
  return NULL;
}

static const char *phys_name(const msh_reader *r, int dim, long tag)
{
  for (size_t i = 0; i < r->nnames; ++i)
    if (r->names[i].dim == dim && r->names[i].tag == tag)
      return r->names[i].name;
  return NULL;
}

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
    if (!rc)
      rc = reals(r, &p, x, 3, "node coordinates");
    if (!rc && fb_mesh_add_node(r->mesh, tags[i], x[0], x[1], x[2], NULL, &sub))
      rc = sub.code == FB_ENOMEM ? msh_nomem(r) : msh_error(r, "%s", sub.msg);
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

/* The node indices of an element line's node tags. */
static int element_nodes(msh_reader *r, char **p, size_t nn, size_t *idx)
{
  long tags[4];
  int rc = ints(r, p, tags, nn, "element");
  for (size_t k = 0; !rc && k < nn; ++k) {
    const long i = fb_mesh_find_node_id(r->mesh, tags[k]);
    if (i < 0)
      return msh_error(r, "the element names node %ld, which is not defined", tags[k]);
    idx[k] = (size_t)i;
  }
  return rc;
}

/* The block's members into the sets of its entity's named physical
 * groups: its nodes (all kinds) and, for surface elements, the elements. */
static int add_to_groups(msh_reader *r, const msh_entity *ent, const size_t *nodes, size_t n,
                         const size_t *elems, size_t ne)
{
  fb_err sub;
  fb_err_clear(&sub);
  for (size_t k = 0; ent && k < ent->nphys; ++k) {
    const char *name = phys_name(r, ent->dim, ent->phys[k]);
    if (!name)
      continue;
    if (fb_mesh_add_nset(r->mesh, name, n, nodes, &sub) ||
        (ne && fb_mesh_add_elset(r->mesh, name, ne, elems, &sub)))
      return sub.code == FB_ENOMEM ? msh_nomem(r) : msh_error(r, "%s", sub.msg);
  }
  return FB_OK;
}

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
    return msh_error(r,
                     "element type %ld is not supported: flexbond takes 3-node triangles and "
                     "4-node quadrilaterals (gmsh -order 1)",
                     head[2]);
  if (!rc && (head[0] == 2) != (nn >= 3))
    return msh_error(r, "element type %ld on an entity of dimension %ld", head[2], head[0]);
  if (rc)
    return rc;
  const msh_entity *ent = find_entity(r, (int)head[0], head[1]);
  size_t *nodes = malloc(((size_t)head[3] * nn + 1) * sizeof *nodes);
  size_t *elems = malloc(((size_t)head[3] + 1) * sizeof *elems);
  if (!nodes || !elems)
    rc = msh_nomem(r);
  fb_err sub;
  fb_err_clear(&sub);
  for (long i = 0; !rc && i < head[3]; ++i) {
    long tag = 0;
    rc = need_line(r, "an element");
    p = r->line;
    if (!rc)
      rc = ints(r, &p, &tag, 1, "element");
    if (!rc)
      rc = element_nodes(r, &p, nn, &nodes[(size_t)i * nn]);
    if (!rc)
      rc = line_done(r, p, "element");
    elems[i] = fb_mesh_nelements(r->mesh);
    if (!rc && nn >= 3 &&
        fb_mesh_add_element(r->mesh, tag, nn == 3 ? FB_ELEM_TRI3 : FB_ELEM_QUAD4,
                            &nodes[(size_t)i * nn], &sub))
      rc = sub.code == FB_ENOMEM ? msh_nomem(r) : msh_error(r, "%s", sub.msg);
  }
  if (!rc)
    rc = add_to_groups(r, ent, nodes, (size_t)head[3] * nn, elems,
                       nn >= 3 ? (size_t)head[3] : 0);
  free(nodes);
  free(elems);
  return rc;
}

static int read_elements(msh_reader *r)
{
  long head[4] = {0, 0, 0, 0};
  int rc = need_line(r, "the element counts");
  char *p = r->line;
  if (!rc)
    rc = ints(r, &p, head, 4, "$Elements");
  if (!rc)
    rc = count_ok(r, head[0], "element block count");
  for (long b = 0; !rc && b < head[0]; ++b)
    rc = read_element_block(r);
  return rc ? rc : expect_end(r, "$Elements");
}

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

static int read_sections(msh_reader *r)
{
  int got = 0, have_format = 0, have_nodes = 0;
  for (;;) {
    int rc = next_line(r, &got);
    if (rc || !got)
      break;
    char *name = r->line + strspn(r->line, " \t");
    if (*name == '\0')
      continue;
    if (*name != '$')
      return msh_error(r, "expected a section ($Name), got '%.40s'", name);
    if (!have_format && strcmp(name, "$MeshFormat") != 0)
      return msh_error(r, "not a .msh file: it does not start with $MeshFormat");
    if (!strcmp(name, "$MeshFormat"))
      rc = read_format(r), have_format = 1;
    else if (!strcmp(name, "$PhysicalNames"))
      rc = read_names(r);
    else if (!strcmp(name, "$Entities"))
      rc = read_entities(r);
    else if (!strcmp(name, "$Nodes"))
      rc = read_nodes(r), have_nodes = 1;
    else if (!strcmp(name, "$Elements"))
      rc = have_nodes ? read_elements(r) : msh_error(r, "$Elements before $Nodes");
    else
      rc = skip_section(r, name);
    if (rc)
      return rc;
  }
  if (!have_format)
    return msh_error(r, "empty file: not a .msh file");
  if (fb_mesh_nelements(r->mesh) == 0)
    return msh_error(r, "the file has no triangles or quadrilaterals");
  return FB_OK;
}

static void reader_free(msh_reader *r)
{
  for (size_t i = 0; i < r->nnames; ++i)
    free(r->names[i].name);
  free(r->names);
  for (size_t i = 0; i < r->nents; ++i)
    free(r->ents[i].phys);
  free(r->ents);
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
