/* SPDX-License-Identifier: BSD-3-Clause */
/* Abaqus/CalculiX input decks for shell meshes (see flexbond/fem.h).
 *
 * Syntax follows the Abaqus Analysis User's Guide, section 1.2.1 "Input
 * syntax rules": keyword lines start with '*', comment lines with "**";
 * keywords, parameter names and parameter values are case-insensitive and
 * blanks in them are insignificant; data fields are separated by commas.
 *
 * Reading (what this reader accepts and how):
 * - *NODE [, NSET=name]: "id, x, y, z", all three coordinates required.
 * - *ELEMENT, TYPE=t [, ELSET=name]: "id, n1, n2, n3[, n4]"; a data line
 *   ending with a comma continues on the next line. t is S3 or S4; S3R and
 *   S4R are read as S3 and S4 (the R, reduced integration, is a choice of
 *   formulation that flexbond makes itself; the geometry is the same).
 *   Other types are errors. Elements may name nodes defined later in the
 *   deck: ids are resolved once the whole deck is read. Each element must
 *   then pass fb_mesh_check's element tests (no repeated node, an area, a
 *   convex and plane quadrilateral); a failure is an error at its line.
 * - *NSET, NSET=name [, GENERATE] [, INTERNAL] [, UNSORTED]: node ids and
 *   names of node sets defined earlier (by an earlier block: the set as it
 *   stands there), or "first, last[, step]" lines with GENERATE; every node
 *   named, generated ones included, must exist. A repeated *NSET of the
 *   same name (any case) extends the set. A set holds each node once, in
 *   the order first named, however often the deck names it (resolve_sets).
 * - *ELSET, ELSET=name [, GENERATE] [, INTERNAL] [, UNSORTED]: element
 *   ids and names of element sets, as *NSET; ELSET= on *ELEMENT adds the
 *   block's elements to that set.
 * - *MATERIAL, NAME=m with *ELASTIC (isotropic: "E, nu") and *DENSITY
 *   ("rho"), which apply to the most recent *MATERIAL.
 * - *SHELL SECTION, ELSET=s, MATERIAL=m: "thickness", a section of the
 *   mesh (fb_mesh_set_section) once the deck is read; an element in two
 *   sections is an error at the second. props receives the only section's
 *   values when one section covers every element, or the only material's
 *   when the deck has no section. Values are taken as SI.
 * - *ELEMENT, TYPE=MASS [, ELSET=name]: "id, node", a point mass on one
 *   node (CalculiX's MASS element: the three translations, no rotary
 *   inertia); more than one node is an error. Its set is the block's
 *   ELSET=, which *MASS names; the mesh's element sets hold shells only,
 *   so a *ELSET that names a MASS element's id leaves it out.
 * - *MASS, ELSET=s: "mass" (kg, >= 0), the mass of each MASS element of
 *   s (ELSET= is the parameter CalculiX 2.20 reads). Every MASS element
 *   needs one *MASS, exactly one.
 * - *NONSTRUCTURAL MASS, ELSET=s, UNITS=MASS PER AREA | MASS PER VOLUME |
 *   TOTAL MASS [, DISTRIBUTION=MASS PROPORTIONAL | VOLUME PROPORTIONAL]:
 *   "mass" (>= 0), added to the non-structural mass per area of each
 *   shell of s (fb_mesh_add_element_nonstructural), smeared through the
 *   thickness as a section's (fem.h); a MASS PER VOLUME times the
 *   element's section's thickness (an element in no section is an
 *   error); a TOTAL MASS is spread in proportion to the elements' areas,
 *   which is either DISTRIBUTION when the elements share one section (a
 *   set over several is an error). MASS PER LENGTH (beams) is an error. Abaqus's keyword:
 * CalculiX 2.20 has none (its keyword table has no such entry), so the writer smears it into
 *   the density.
 * - *HEADING and every other keyword are skipped with their data
 *   lines, except those that generate or move mesh data (*INCLUDE, *NGEN,
 *   *NFILL, *NCOPY, *NMAP, *ELGEN, *ELCOPY), which are errors rather than
 *   silently lost geometry. Unknown parameters of *NODE, *ELEMENT and
 *   *NSET (e.g. SYSTEM=, INPUT=, ELSET= on *NSET) are errors too.
 * The drilling factor has no Abaqus keyword: it is neither written nor
 * read.
 *
 * Writing: *NODE, *ELEMENT S3/S4, the sets, one *MATERIAL and *SHELL
 * SECTION per group of elements of one section and one added
 * non-structural mass (that mass smeared into the density, which both
 * programs read), and each point mass as a MASS element of a set of its
 * own with its *MASS: a deck CalculiX 2.20 reads as the same mass. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/out.h"

#include "core/textfile.h"
#include "core/util.h"
#include "fem/mesh_internal.h"

#define INP_MAX_PARAMS 16

/* A keyword line split in place: parameter values are NULL when absent. */
typedef struct inp_keyword {
  const char *name;
  size_t nparams;
  const char *param_names[INP_MAX_PARAMS];
  const char *param_values[INP_MAX_PARAMS];
} inp_keyword;

/* An element whose node ids are resolved at the end of the deck. */
typedef struct inp_element {
  long id;
  fb_elem_type type;
  long nodes[4];
  size_t line;
} inp_element;

typedef enum inp_item_kind {
  ITEM_ID,      /* node id a */
  ITEM_RANGE,   /* GENERATE: ids a, a + step, ... up to b */
  ITEM_SET,     /* all nodes of the set named ref */
  ITEM_INDICES, /* node indices a .. b - 1 (the nodes of *NODE, NSET=) */
} inp_item_kind;

typedef struct inp_item {
  inp_item_kind kind;
  long a, b, step;
  const char *ref;
  size_t line;
} inp_item;

/* One *NSET or *ELSET block (or *NODE, NSET=; *ELEMENT, ELSET=): items
 * [first, first + count). */
typedef struct inp_set_block {
  const char *name;
  int elements; /* 1: an element set, 0: a node set */
  size_t first;
  size_t count;
} inp_set_block;

typedef struct inp_section {
  const char *elset, *material;
  double thickness;
  size_t line;
} inp_section;

typedef struct inp_material {
  const char *name;
  double young, poisson, density;
  int has_elastic, has_density;
} inp_material;

/* A MASS element (a point mass on one node), resolved at the end. */
typedef struct inp_mass_element {
  long id, node;
  const char *elset; /* its *ELEMENT block's ELSET=, or NULL */
  size_t line;
  double mass;
  size_t mass_line; /* of the *MASS that gave it its mass, 0 before */
} inp_mass_element;

/* What a *NONSTRUCTURAL MASS's value is (its UNITS=). */
typedef enum inp_nsm_units {
  NSM_PER_AREA,   /* kg/m^2 (also *MASS's: kg per MASS element) */
  NSM_TOTAL,      /* kg over the set */
  NSM_PER_VOLUME, /* kg/m^3 of the shell's volume */
} inp_nsm_units;

/* A *MASS (the mass of each MASS element of elset) or a *NONSTRUCTURAL
 * MASS (over the shells of elset, as units says). */
typedef struct inp_mass {
  const char *elset;
  double value;
  inp_nsm_units units;
  size_t line;
} inp_mass;

typedef struct inp_reader {
  const char *path;
  char *text; /* whole file, split into lines in place */
  size_t len;
  size_t pos;    /* start of the next unread line */
  char *line;    /* current significant line */
  size_t lineno; /* its 1-based number */
  int have_line; /* line is read but not consumed */
  fb_err *err;

  char **fields; /* fields of the current data line (into text) */
  size_t nfields, fields_cap;

  fb_mesh *mesh;
  inp_element *elems;
  size_t nelems, elems_cap;
  inp_item *items;
  size_t nitems, items_cap;
  inp_set_block *blocks;
  size_t nblocks, blocks_cap;
  inp_material *materials;
  size_t nmaterials, materials_cap;
  inp_section *sections;
  size_t nsections, sections_cap;
  inp_mass_element *mass_elems;
  size_t nmass_elems, mass_elems_cap;
  inp_mass *masses; /* *MASS */
  size_t nmasses, masses_cap;
  inp_mass *nsms; /* *NONSTRUCTURAL MASS */
  size_t nnsms, nsms_cap;
} inp_reader;

/* Records FB_EPARSE as "path:line: message". */
static int inp_error(const inp_reader *r, size_t line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int inp_error(const inp_reader *r, size_t line, const char *fmt, ...)
{
  char msg[FB_ERR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return fb_err_set(r->err, FB_EPARSE, "%s:%zu: %s", r->path, line ? line : 1, msg);
}
#if defined(__clang_analyzer__)
/* For the static analyzer only, which does not follow calls to variadic functions. */
#define inp_error(r, line, ...) (inp_error((r), (line), __VA_ARGS__), FB_EPARSE)
#endif

static int inp_nomem(const inp_reader *r)
{
  return fb_err_set(r->err, FB_ENOMEM, "out of memory reading %s", r->path);
}

/* A failure of a mesh call (message in sub) reported at line; out of
 * memory keeps its code. */
static int inp_mesh_error(const inp_reader *r, size_t line, const fb_err *sub)
{
  if (sub->code == FB_ENOMEM)
    return inp_nomem(r);
  const int rc = inp_error(r, line, "%s", sub->msg);
  fb_err_set_excerpt(r->err, sub->excerpt, sizeof sub->excerpt);
  return rc;
}

/* rc, after recording the deck's text the error just set is about as its
 * excerpt: a deck's text goes there, never into the message (errors.md). */
static int inp_quoting(const inp_reader *r, const char *text, int rc)
{
  fb_err_set_excerpt(r->err, text, strlen(text));
  return rc;
}

/* ---- Lines and fields. */

/* Splits off the next line (without its end of line) into r->line;
 * control characters other than tab mark a binary file. */
static int split_line(inp_reader *r)
{
  const size_t col = fb_text_split_line(r->text, r->len, &r->pos, &r->line);
  ++r->lineno;
  if (col)
    return inp_error(r, r->lineno,
                     "binary data (byte 0x%02x in column %zu): not an Abaqus input deck",
                     (unsigned char)r->line[col - 1], col);
  return FB_OK;
}

static const char *skip_blanks(const char *s)
{
  return s + strspn(s, " \t");
}

static int is_keyword(const char *line)
{
  const char *p = skip_blanks(line);
  return p[0] == '*' && p[1] != '*';
}

/* The next line that is neither blank nor a comment, left unconsumed
 * (peek); *got is 0 at the end of the file. */
static int peek_line(inp_reader *r, int *got)
{
  *got = 1;
  while (!r->have_line) {
    if (r->pos >= r->len) {
      *got = 0;
      return FB_OK;
    }
    const int rc = split_line(r);
    if (rc)
      return rc;
    const char *p = skip_blanks(r->line);
    r->have_line = *p != '\0' && !(p[0] == '*' && p[1] == '*');
  }
  return FB_OK;
}

/* The next data line of the current keyword, consumed; *got is 0 at the
 * next keyword (left for the caller) or at the end of the file. */
static int next_data_line(inp_reader *r, int *got)
{
  int rc = peek_line(r, got);
  if (rc || !*got)
    return rc;
  if (is_keyword(r->line)) {
    *got = 0;
    return FB_OK;
  }
  r->have_line = 0;
  return FB_OK;
}

/* s without leading and trailing blanks, trimmed in place. */
static char *trim(char *s)
{
  s += strspn(s, " \t");
  size_t n = strlen(s);
  while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t'))
    s[--n] = '\0';
  return s;
}

/* Appends the comma-separated fields of line to r->fields (split in
 * place). A trailing comma adds no empty field; *continued tells whether
 * there was one. Empty fields elsewhere are errors. */
static int append_fields(inp_reader *r, char *line, int *continued)
{
  char *p = line;
  for (;;) {
    char *comma = strchr(p, ',');
    if (comma)
      *comma = '\0';
    char *field = trim(p);
    const int last = !comma || *skip_blanks(comma + 1) == '\0';
    *continued = comma && last;
    if (*field == '\0' && !(last && comma))
      return inp_error(r, r->lineno, "empty data field");
    if (*field != '\0') {
      if (fb_grow((void **)&r->fields, &r->fields_cap, r->nfields, sizeof *r->fields))
        return inp_nomem(r);
      r->fields[r->nfields++] = field;
    }
    if (last)
      return FB_OK;
    p = comma + 1;
  }
}

static int line_fields(inp_reader *r, int *continued)
{
  r->nfields = 0;
  return append_fields(r, r->line, continued);
}

/* Compares two words case-insensitively, ignoring blanks. */
static int same_word(const char *a, const char *b)
{
  for (;;) {
    a = skip_blanks(a);
    b = skip_blanks(b);
    if (toupper((unsigned char)*a) != toupper((unsigned char)*b))
      return 0;
    if (*a == '\0')
      return 1;
    ++a;
    ++b;
  }
}

/* ---- Numbers. */

/* A positive integer filling the whole field. */
static int parse_id(const inp_reader *r, const char *field, const char *what, long *out)
{
  char *end;
  errno = 0;
  const long v = strtol(field, &end, 10);
  if (errno || end == field || *end != '\0' || v <= 0 || !isdigit((unsigned char)field[0]))
    return inp_quoting(r, field, inp_error(r, r->lineno, "%s: not a positive integer", what));
  *out = v;
  return FB_OK;
}

/* A finite real number filling the whole field; what says which one. */
/* A plain decimal, as in every data file (core/textfile.h): hexadecimal,
 * inf and nan are refused. */
static int parse_real(const inp_reader *r, const char *field, const char *what, double *out)
{
  fb_err sub;
  fb_err_clear(&sub);
  if (fb_parse_decimal_field(field, out, &sub))
    return inp_quoting(r, field, inp_error(r, r->lineno, "%s: %s", what, sub.msg));
  return FB_OK;
}

/* ---- Keyword lines. */

static int parse_keyword(inp_reader *r, inp_keyword *kw)
{
  char *p = r->line + strspn(r->line, " \t") + 1; /* past the '*' */
  kw->nparams = 0;
  char *comma = strchr(p, ',');
  if (comma)
    *comma = '\0';
  kw->name = trim(p);
  if (*kw->name == '\0')
    return inp_error(r, r->lineno, "keyword line without a keyword");
  while (comma) {
    p = comma + 1;
    comma = strchr(p, ',');
    if (comma)
      *comma = '\0';
    if (*skip_blanks(p) == '\0')
      continue; /* "*NODE," or doubled commas */
    if (kw->nparams == INP_MAX_PARAMS)
      return inp_error(r, r->lineno, "more than %d parameters on *%s", INP_MAX_PARAMS,
                       kw->name);
    char *eq = strchr(p, '=');
    if (eq)
      *eq = '\0';
    kw->param_names[kw->nparams] = trim(p);
    kw->param_values[kw->nparams++] = eq ? trim(eq + 1) : NULL;
  }
  return FB_OK;
}

/* Value of parameter name ("" when given without one), or NULL. */
static const char *param(const inp_keyword *kw, const char *name)
{
  for (size_t i = 0; i < kw->nparams; ++i)
    if (same_word(kw->param_names[i], name))
      return kw->param_values[i] ? kw->param_values[i] : "";
  return NULL;
}

/* Every parameter of kw is one of allowed (NULL-terminated). */
static int only_params(const inp_reader *r, const inp_keyword *kw, const char *const *allowed)
{
  for (size_t i = 0; i < kw->nparams; ++i) {
    size_t k = 0;
    while (allowed[k] && !same_word(kw->param_names[i], allowed[k]))
      ++k;
    if (!allowed[k])
      return inp_error(r, r->lineno, "parameter '%s' of *%s is not supported",
                       kw->param_names[i], kw->name);
  }
  return FB_OK;
}

/* A required parameter with a value. */
static int need_param(const inp_reader *r, const inp_keyword *kw, const char *name,
                      const char **value)
{
  *value = param(kw, name);
  if (!*value || **value == '\0')
    return inp_error(r, r->lineno, "*%s needs %s=", kw->name, name);
  return FB_OK;
}

/* Consumes the data lines of a skipped keyword. */
static int skip_data(inp_reader *r)
{
  int got = 1, rc = FB_OK;
  while (!rc && got)
    rc = next_data_line(r, &got);
  return rc;
}

/* ---- Node sets. */

/* 1 if the block's last item is this one: a set holds each member once,
 * so a name or a GENERATE line repeated ("ALL, ALL, ...") is kept once. */
static int repeats_last_item(const inp_reader *r, inp_item_kind kind, long a, long b, long step,
                             const char *ref)
{
  const inp_item *last = r->blocks[r->nblocks - 1].count ? &r->items[r->nitems - 1] : NULL;
  return last && last->kind == kind && last->a == a && last->b == b && last->step == step &&
         (!ref || same_word(last->ref, ref));
}

static int add_item(inp_reader *r, inp_item_kind kind, long a, long b, long step,
                    const char *ref)
{
  if (repeats_last_item(r, kind, a, b, step, ref))
    return FB_OK;
  if (fb_grow((void **)&r->items, &r->items_cap, r->nitems, sizeof *r->items))
    return inp_nomem(r);
  r->items[r->nitems++] = (inp_item){kind, a, b, step, ref, r->lineno};
  r->blocks[r->nblocks - 1].count++;
  return FB_OK;
}

static const char *set_kind(int elements)
{
  return elements ? "element" : "node";
}

static int begin_block(inp_reader *r, const char *name, int elements)
{
  if (!fb_mesh_name_ok(name))
    return inp_quoting(r, name,
                       inp_error(r, r->lineno,
                                 "%s set name is invalid (1 to %d characters from A-Z a-z 0-9 "
                                 "_ . -, starting with a letter or _)",
                                 set_kind(elements), FB_MESH_NAME_MAX));
  if (fb_grow((void **)&r->blocks, &r->blocks_cap, r->nblocks, sizeof *r->blocks))
    return inp_nomem(r);
  r->blocks[r->nblocks++] = (inp_set_block){name, elements, r->nitems, 0};
  return FB_OK;
}

/* "first, last[, step]" of a GENERATE line. */
static int read_generate_line(inp_reader *r, int elements)
{
  long v[3] = {0, 0, 1};
  if (r->nfields < 2 || r->nfields > 3)
    return inp_error(r, r->lineno, "GENERATE line needs 'first, last[, step]', not %zu fields",
                     r->nfields);
  const char *const what[2][3] = {{"first node id", "last node id", "step"},
                                  {"first element id", "last element id", "step"}};
  for (size_t k = 0; k < r->nfields; ++k) {
    const int rc = parse_id(r, r->fields[k], what[elements][k], &v[k]);
    if (rc)
      return rc;
  }
  if (v[1] < v[0])
    return inp_error(r, r->lineno, "GENERATE range %ld, %ld runs backwards", v[0], v[1]);
  return add_item(r, ITEM_RANGE, v[0], v[1], v[2], NULL);
}

/* Ids and set names of a plain *NSET or *ELSET line. */
static int read_set_line(inp_reader *r, int elements)
{
  int rc = FB_OK;
  for (size_t k = 0; k < r->nfields && !rc; ++k) {
    const char *f = r->fields[k];
    long id = 0;
    if (fb_mesh_name_ok(f))
      rc = add_item(r, ITEM_SET, 0, 0, 0, f);
    else if (!(rc = parse_id(r, f, elements ? "element id" : "node id", &id)))
      rc = add_item(r, ITEM_ID, id, 0, 0, NULL);
  }
  return rc;
}

/* *NSET (elements 0) or *ELSET (elements 1). */
static int read_set(inp_reader *r, const inp_keyword *kw, int elements)
{
  const char *const key = elements ? "ELSET" : "NSET";
  const char *const allowed[] = {key, "GENERATE", "INTERNAL", "UNSORTED", NULL};
  const char *name = NULL;
  int rc = only_params(r, kw, allowed);
  if (!rc)
    rc = need_param(r, kw, key, &name);
  if (!rc)
    rc = begin_block(r, name, elements);
  const int generate = param(kw, "GENERATE") != NULL;
  int got = 1, continued = 0;
  while (!rc && got) {
    rc = next_data_line(r, &got);
    if (!rc && got)
      rc = line_fields(r, &continued);
    if (!rc && got)
      rc = generate ? read_generate_line(r, elements) : read_set_line(r, elements);
  }
  return rc;
}

/* ---- Nodes and elements. */

static int read_node_line(inp_reader *r)
{
  int continued = 0;
  int rc = line_fields(r, &continued);
  if (rc)
    return rc;
  if (r->nfields != 4)
    return inp_error(r, r->lineno, "node line needs 'id, x, y, z', not %zu fields", r->nfields);
  long id = 0;
  double xyz[3];
  rc = parse_id(r, r->fields[0], "node id", &id);
  for (int k = 0; k < 3 && !rc; ++k) {
    char what[64];
    snprintf(what, sizeof what, "%c of node %ld", "xyz"[k], id);
    rc = parse_real(r, r->fields[1 + k], what, &xyz[k]);
  }
  if (rc)
    return rc;
  fb_err sub;
  fb_err_clear(&sub);
  if (fb_mesh_add_node(r->mesh, id, xyz[0], xyz[1], xyz[2], NULL, &sub))
    return inp_mesh_error(r, r->lineno, &sub);
  return FB_OK;
}

static int read_nodes(inp_reader *r, const inp_keyword *kw)
{
  static const char *const allowed[] = {"NSET", NULL};
  int rc = only_params(r, kw, allowed);
  const char *nset = param(kw, "NSET");
  if (!rc && nset)
    rc = need_param(r, kw, "NSET", &nset);
  if (!rc && nset)
    rc = begin_block(r, nset, 0);
  const long first = (long)fb_mesh_nnodes(r->mesh);
  int got = 1;
  while (!rc && got) {
    rc = next_data_line(r, &got);
    if (!rc && got)
      rc = read_node_line(r);
  }
  if (!rc && nset)
    rc = add_item(r, ITEM_INDICES, first, (long)fb_mesh_nnodes(r->mesh), 0, NULL);
  return rc;
}

/* Element type of a TYPE= value. */
static int element_type(const inp_reader *r, const char *name, fb_elem_type *type)
{
  if (same_word(name, "S3") || same_word(name, "S3R")) {
    *type = FB_ELEM_TRI3;
    return FB_OK;
  }
  if (same_word(name, "S4") || same_word(name, "S4R")) {
    *type = FB_ELEM_QUAD4;
    return FB_OK;
  }
  const char *p = skip_blanks(name);
  if (toupper((unsigned char)p[0]) == 'S' && isdigit((unsigned char)p[1]))
    return inp_error(r, r->lineno, "shell element type '%s' is not supported (S3, S4)", name);
  return inp_error(r, r->lineno, "element type '%s' is not a shell (S3, S4)", name);
}

/* One element, its data continued over lines that end with a comma. */
static int read_element_line(inp_reader *r, fb_elem_type type)
{
  int continued = 0, got = 1;
  const size_t first_line = r->lineno;
  int rc = line_fields(r, &continued);
  while (!rc && continued) {
    rc = next_data_line(r, &got);
    if (!rc && !got)
      return inp_error(r, first_line, "element data ends with a comma but does not continue");
    if (!rc)
      rc = append_fields(r, r->line, &continued);
  }
  inp_element el = {0, type, {0, 0, 0, 0}, first_line};
  if (!rc && r->nfields == 0)
    return inp_error(r, first_line, "element line without an element id");
  if (!rc)
    rc = parse_id(r, r->fields[0], "element id", &el.id);
  if (rc)
    return rc;
  const size_t nn = fb_mesh_type_nodes(type);
  if (r->nfields - 1 != nn)
    return inp_error(r, first_line, "element %ld (%s) has %zu nodes, not %zu", el.id,
                     fb_mesh_type_name(type), r->nfields - 1, nn);
  for (size_t k = 0; k < nn && !rc; ++k)
    rc = parse_id(r, r->fields[1 + k], "node id", &el.nodes[k]);
  if (rc)
    return rc;
  if (fb_grow((void **)&r->elems, &r->elems_cap, r->nelems, sizeof *r->elems))
    return inp_nomem(r);
  r->elems[r->nelems++] = el;
  return FB_OK;
}

/* "id, node" of a MASS element. */
static int read_mass_element_line(inp_reader *r, const char *elset)
{
  int continued = 0;
  int rc = line_fields(r, &continued);
  inp_mass_element el = {0, 0, elset, r->lineno, 0.0, 0};
  if (!rc && r->nfields == 0)
    return inp_error(r, r->lineno, "element line without an element id");
  if (!rc)
    rc = parse_id(r, r->fields[0], "element id", &el.id);
  if (!rc && continued)
    return inp_error(r, r->lineno,
                     "MASS element %ld's line ends with a comma: a point mass is 'id, node'",
                     el.id);
  if (!rc && r->nfields != 2)
    return inp_error(r, r->lineno,
                     "MASS element %ld has %zu nodes, not 1 (a point mass is on one node)",
                     el.id, r->nfields - 1);
  if (!rc)
    rc = parse_id(r, r->fields[1], "node id", &el.node);
  if (!rc && fb_grow((void **)&r->mass_elems, &r->mass_elems_cap, r->nmass_elems,
                     sizeof *r->mass_elems))
    rc = inp_nomem(r);
  if (!rc)
    r->mass_elems[r->nmass_elems++] = el;
  return rc;
}

/* *ELEMENT, TYPE=MASS [, ELSET=name]: point masses, which *MASS gives
 * their mass through the block's set (CalculiX's form). They stay out of
 * the mesh's element sets, which hold shells. */
static int read_mass_elements(inp_reader *r, const inp_keyword *kw)
{
  const char *elset = param(kw, "ELSET");
  int rc = elset ? need_param(r, kw, "ELSET", &elset) : FB_OK;
  if (!rc && elset && !fb_mesh_name_ok(elset))
    rc = inp_quoting(r, elset, inp_error(r, r->lineno, "element set name is invalid"));
  int got = 1;
  while (!rc && got) {
    rc = next_data_line(r, &got);
    if (!rc && got)
      rc = read_mass_element_line(r, elset);
  }
  return rc;
}

static int read_elements(inp_reader *r, const inp_keyword *kw)
{
  static const char *const allowed[] = {"TYPE", "ELSET", NULL};
  const char *type_name = NULL;
  fb_elem_type type = FB_ELEM_TRI3;
  int rc = only_params(r, kw, allowed);
  if (!rc)
    rc = need_param(r, kw, "TYPE", &type_name);
  if (!rc && same_word(type_name, "MASS"))
    return read_mass_elements(r, kw);
  if (!rc)
    rc = element_type(r, type_name, &type);
  const char *elset = param(kw, "ELSET");
  if (!rc && elset)
    rc = need_param(r, kw, "ELSET", &elset);
  if (!rc && elset)
    rc = begin_block(r, elset, 1);
  const long first = (long)r->nelems;
  int got = 1;
  while (!rc && got) {
    rc = next_data_line(r, &got);
    if (!rc && got)
      rc = read_element_line(r, type);
  }
  if (!rc && elset)
    rc = add_item(r, ITEM_INDICES, first, (long)r->nelems, 0, NULL);
  return rc;
}

/* ---- Material and section. */

static inp_material *find_material(const inp_reader *r, const char *name)
{
  for (size_t i = 0; i < r->nmaterials; ++i)
    if (same_word(r->materials[i].name, name))
      return &r->materials[i];
  return NULL;
}

static int read_material(inp_reader *r, const inp_keyword *kw)
{
  const char *name = NULL;
  int rc = need_param(r, kw, "NAME", &name);
  if (rc)
    return rc;
  if (find_material(r, name))
    return inp_error(r, r->lineno, "material '%s' is defined twice", name);
  if (fb_grow((void **)&r->materials, &r->materials_cap, r->nmaterials, sizeof *r->materials))
    return inp_nomem(r);
  r->materials[r->nmaterials++] = (inp_material){name, 0.0, 0.0, 0.0, 0, 0};
  return skip_data(r);
}

/* Reads the data line of a material option (*ELASTIC, *DENSITY) into
 * r->fields, with min to max fields. */
static int option_line(inp_reader *r, const char *keyword, size_t min, size_t max)
{
  int got = 0, continued = 0;
  const size_t kw_line = r->lineno;
  if (r->nmaterials == 0)
    return inp_error(r, kw_line, "*%s outside a *MATERIAL", keyword);
  int rc = next_data_line(r, &got);
  if (!rc && !got)
    return inp_error(r, kw_line, "*%s has no data line", keyword);
  if (!rc)
    rc = line_fields(r, &continued);
  if (!rc && (r->nfields < min || r->nfields > max))
    return inp_error(r, r->lineno, "*%s data line needs %zu to %zu fields, not %zu", keyword,
                     min, max, r->nfields);
  return rc;
}

/* After the data line of a material option: a second line would be
 * temperature-dependent data, which a single-material shell cannot use. */
static int no_second_line(inp_reader *r, const char *keyword)
{
  const size_t data_line = r->lineno;
  int got = 0;
  const int rc = peek_line(r, &got);
  if (!rc && got && !is_keyword(r->line))
    return inp_error(r, r->lineno,
                     "a second *%s data line (temperature-dependent data) is not supported;"
                     " the first is line %zu",
                     keyword, data_line);
  return rc;
}

static int read_elastic(inp_reader *r, const inp_keyword *kw)
{
  const char *type = param(kw, "TYPE");
  if (type && !same_word(type, "ISOTROPIC"))
    return inp_error(r, r->lineno, "*ELASTIC, TYPE=%s is not supported (isotropic only)", type);
  int rc = option_line(r, "ELASTIC", 2, 3);
  if (rc)
    return rc;
  inp_material *m = &r->materials[r->nmaterials - 1];
  rc = parse_real(r, r->fields[0], "Young's modulus", &m->young);
  if (!rc)
    rc = parse_real(r, r->fields[1], "Poisson's ratio", &m->poisson);
  if (!rc && !(m->young > 0.0))
    rc = inp_error(r, r->lineno, "Young's modulus %g is not positive", m->young);
  if (!rc && !(m->poisson > -1.0 && m->poisson < 0.5))
    rc = inp_error(r, r->lineno, "Poisson's ratio %g is outside (-1, 0.5)", m->poisson);
  m->has_elastic = 1;
  return rc ? rc : no_second_line(r, "ELASTIC");
}

static int read_density(inp_reader *r)
{
  int rc = option_line(r, "DENSITY", 1, 2);
  if (rc)
    return rc;
  inp_material *m = &r->materials[r->nmaterials - 1];
  rc = parse_real(r, r->fields[0], "density", &m->density);
  if (!rc && !(m->density > 0.0))
    rc = inp_error(r, r->lineno, "density %g is not positive", m->density);
  m->has_density = 1;
  return rc ? rc : no_second_line(r, "DENSITY");
}

static int read_section(inp_reader *r, const inp_keyword *kw)
{
  if (param(kw, "COMPOSITE"))
    return inp_error(r, r->lineno, "composite shell sections are not supported");
  inp_section sec = {NULL, NULL, 0.0, r->lineno};
  int rc = need_param(r, kw, "ELSET", &sec.elset);
  if (!rc)
    rc = need_param(r, kw, "MATERIAL", &sec.material);
  int got = 0, continued = 0;
  if (!rc)
    rc = next_data_line(r, &got);
  if (!rc && !got)
    return inp_error(r, sec.line, "*SHELL SECTION has no data line (thickness)");
  if (!rc)
    rc = line_fields(r, &continued);
  if (!rc && r->nfields == 0)
    return inp_error(r, r->lineno, "*SHELL SECTION data line has no thickness");
  if (!rc)
    rc = parse_real(r, r->fields[0], "shell thickness", &sec.thickness);
  if (!rc && !(sec.thickness > 0.0))
    return inp_error(r, r->lineno, "shell thickness %g is not positive", sec.thickness);
  if (!rc &&
      fb_grow((void **)&r->sections, &r->sections_cap, r->nsections, sizeof *r->sections))
    rc = inp_nomem(r);
  if (!rc)
    r->sections[r->nsections++] = sec;
  return rc ? rc : skip_data(r);
}

/* ---- Added masses. */

/* The one data line of *MASS or *NONSTRUCTURAL MASS: a mass >= 0 (kg,
 * or kg/m^2 per area). */
static int read_mass_value(inp_reader *r, const char *keyword, size_t kw_line, double *value)
{
  int got = 0, continued = 0;
  int rc = next_data_line(r, &got);
  if (!rc && !got)
    return inp_error(r, kw_line, "*%s has no data line (the mass)", keyword);
  if (!rc)
    rc = line_fields(r, &continued);
  if (!rc && r->nfields != 1)
    return inp_error(r, r->lineno, "*%s data line needs 1 field (the mass), not %zu", keyword,
                     r->nfields);
  if (!rc)
    rc = parse_real(r, r->fields[0], "mass", value);
  if (!rc && !(*value >= 0.0))
    return inp_error(r, r->lineno, "*%s: mass %g is negative", keyword, *value);
  return rc ? rc : no_second_line(r, keyword);
}

static int push_mass(inp_reader *r, inp_mass **list, size_t *n, size_t *cap, const inp_mass *m)
{
  if (fb_grow((void **)list, cap, *n, sizeof **list))
    return inp_nomem(r);
  (*list)[(*n)++] = *m;
  return FB_OK;
}

/* *MASS, ELSET=s: the mass of each MASS element of s (CalculiX reads
 * ELSET= alone). */
static int read_mass(inp_reader *r, const inp_keyword *kw)
{
  static const char *const allowed[] = {"ELSET", NULL};
  inp_mass m = {NULL, 0.0, NSM_PER_AREA, r->lineno};
  int rc = only_params(r, kw, allowed);
  if (!rc)
    rc = need_param(r, kw, "ELSET", &m.elset);
  if (!rc)
    rc = read_mass_value(r, "MASS", m.line, &m.value);
  return rc ? rc : push_mass(r, &r->masses, &r->nmasses, &r->masses_cap, &m);
}

/* *NONSTRUCTURAL MASS, ELSET=s, UNITS=MASS PER AREA | MASS PER VOLUME |
 * TOTAL MASS [, DISTRIBUTION=MASS PROPORTIONAL | VOLUME PROPORTIONAL] (Abaqus
 * Keywords Reference; CalculiX 2.20 has no such keyword). */
static int read_nonstructural(inp_reader *r, const inp_keyword *kw)
{
  static const char *const allowed[] = {"ELSET", "UNITS", "DISTRIBUTION", NULL};
  inp_mass m = {NULL, 0.0, NSM_PER_AREA, r->lineno};
  const char *units = NULL, *dist = param(kw, "DISTRIBUTION");
  int rc = only_params(r, kw, allowed);
  if (!rc)
    rc = need_param(r, kw, "ELSET", &m.elset);
  if (!rc)
    rc = need_param(r, kw, "UNITS", &units);
  if (rc)
    return rc;
  m.units = same_word(units, "TOTAL MASS")        ? NSM_TOTAL
            : same_word(units, "MASS PER VOLUME") ? NSM_PER_VOLUME
                                                  : NSM_PER_AREA;
  if (m.units == NSM_PER_AREA && !same_word(units, "MASS PER AREA"))
    return inp_quoting(r, units,
                       inp_error(r, r->lineno,
                                 "*NONSTRUCTURAL MASS, UNITS=%s is not supported for shells "
                                 "(MASS PER AREA, MASS PER VOLUME, TOTAL MASS)",
                                 units));
  if (dist && !same_word(dist, "MASS PROPORTIONAL") && !same_word(dist, "VOLUME PROPORTIONAL"))
    return inp_error(r, r->lineno,
                     "*NONSTRUCTURAL MASS, DISTRIBUTION=%s is not one of MASS PROPORTIONAL, "
                     "VOLUME PROPORTIONAL",
                     dist);
  rc = read_mass_value(r, "NONSTRUCTURAL MASS", m.line, &m.value);
  return rc ? rc : push_mass(r, &r->nsms, &r->nnsms, &r->nsms_cap, &m);
}

/* ---- The deck. */

static int is_one_of(const char *name, const char *const *list)
{
  for (size_t k = 0; list[k]; ++k)
    if (same_word(name, list[k]))
      return 1;
  return 0;
}

static int read_keyword(inp_reader *r)
{
  static const char *const refused[] = {"INCLUDE", "NGEN",  "NFILL",  "NCOPY",
                                        "NMAP",    "ELGEN", "ELCOPY", NULL};
  inp_keyword kw;
  int rc = parse_keyword(r, &kw);
  if (rc)
    return rc;
  if (same_word(kw.name, "NODE"))
    return read_nodes(r, &kw);
  if (same_word(kw.name, "ELEMENT"))
    return read_elements(r, &kw);
  if (same_word(kw.name, "NSET"))
    return read_set(r, &kw, 0);
  if (same_word(kw.name, "ELSET"))
    return read_set(r, &kw, 1);
  if (same_word(kw.name, "MATERIAL"))
    return read_material(r, &kw);
  if (same_word(kw.name, "ELASTIC"))
    return read_elastic(r, &kw);
  if (same_word(kw.name, "DENSITY"))
    return read_density(r);
  if (same_word(kw.name, "SHELL SECTION"))
    return read_section(r, &kw);
  if (same_word(kw.name, "MASS"))
    return read_mass(r, &kw);
  if (same_word(kw.name, "NONSTRUCTURAL MASS"))
    return read_nonstructural(r, &kw);
  if (is_one_of(kw.name, refused))
    return inp_error(r, r->lineno,
                     "*%s is not supported (it would bring in or generate mesh data)", kw.name);
  return skip_data(r);
}

static int read_deck(inp_reader *r)
{
  if (r->len == 0)
    return inp_error(r, 1, "empty file: not an Abaqus input deck");
  int got = 0;
  for (;;) {
    int rc = peek_line(r, &got);
    if (rc || !got)
      return rc;
    if (!is_keyword(r->line))
      return inp_error(r, r->lineno, "data line before any keyword");
    r->have_line = 0;
    rc = read_keyword(r);
    if (rc)
      return rc;
  }
}

/* ---- Resolving ids once the deck is read. */

static int resolve_node(const inp_reader *r, const inp_element *el, size_t k, size_t *index)
{
  const long i = fb_mesh_find_node_id(r->mesh, el->nodes[k]);
  if (i < 0)
    return inp_error(r, el->line, "element %ld refers to node %ld, which is not defined",
                     el->id, el->nodes[k]);
  *index = (size_t)i;
  return FB_OK;
}

static int resolve_elements(const inp_reader *r)
{
  fb_err sub;
  fb_err_clear(&sub);
  for (size_t e = 0; e < r->nelems; ++e) {
    const inp_element *el = &r->elems[e];
    size_t nodes[4] = {0, 0, 0, 0};
    int rc = FB_OK;
    for (size_t k = 0; k < fb_mesh_type_nodes(el->type) && !rc; ++k)
      rc = resolve_node(r, el, k, &nodes[k]);
    if (rc)
      return rc;
    if (fb_mesh_add_element(r->mesh, el->id, el->type, nodes, &sub))
      return inp_mesh_error(r, el->line, &sub);
  }
  return FB_OK;
}

/* ---- Sets, once the deck is read.
 *
 * A set's data lines may name other sets besides ids (Abaqus Keywords
 * Reference and CalculiX CrunchiX User's Manual, *NSET and *ELSET: node or
 * element numbers and the names of sets defined before), and a deck may
 * name a large set over and over ("ALL, ALL, ..." on every line). Members go into the mesh's
 * set as they are met, where one already there costs O(1) (fb_mesh_add_nset), so a set takes
 * memory for its members only: expanding a whole block before removing repeats once took 1.7 GB
 * for a 4.8 MB deck. A set named again adds only what it gained since it was last merged into
 * the same set (inp_merge: sets only grow, their members in the order they came), so the time
 * is linear in the deck and the sets' sizes. Blocks are resolved in the deck's order: a set may
 * name the sets defined before it, as they stand at that point. */

/* Members collected before they are added to the mesh's set, in order. */
#define FILL_CHUNK 256

/* The block being resolved. */
typedef struct set_fill {
  const inp_set_block *blk;
  int existed; /* an earlier block defined the set */
  size_t line; /* of the block's first item (1 if none) */
  size_t pending[FILL_CHUNK];
  size_t npending;
} set_fill;

/* How much of set x is in set t already (both of one kind): x's first
 * merged members, as in x's member list. */
typedef struct inp_merge {
  const char *t, *x; /* NULL t: an empty slot */
  uint64_t key;
  size_t merged;
} inp_merge;

/* Open addressing, linear probing, load at most 1/2 (as mesh.c's tables). */
typedef struct merge_table {
  inp_merge *slots;
  size_t cap, n; /* cap a power of two, or 0 */
} merge_table;

static uint64_t merge_key(const char *t, const char *x)
{
  const uint64_t k = fb_mesh_name_key(t) ^ (fb_mesh_name_key(x) * UINT64_C(0x9E3779B97F4A7C15));
  return k ^ (k >> 32);
}

static inp_merge *merge_slot(const merge_table *tb, const char *t, const char *x, uint64_t key)
{
  for (size_t s = (size_t)key & (tb->cap - 1);; s = (s + 1) & (tb->cap - 1)) {
    inp_merge *e = &tb->slots[s];
    if (!e->t || (e->key == key && same_word(e->t, t) && same_word(e->x, x)))
      return e;
  }
}

/* Room for one entry more. */
static int merge_reserve(merge_table *tb)
{
  if (2 * (tb->n + 1) <= tb->cap)
    return FB_OK;
  merge_table grown = {NULL, tb->cap ? 2 * tb->cap : 16, tb->n};
  grown.slots = calloc(grown.cap, sizeof *grown.slots);
  if (!grown.slots)
    return FB_ENOMEM;
  for (size_t s = 0; s < tb->cap; ++s)
    if (tb->slots[s].t)
      *merge_slot(&grown, tb->slots[s].t, tb->slots[s].x, tb->slots[s].key) = tb->slots[s];
  free(tb->slots);
  *tb = grown;
  return FB_OK;
}

/* The entry of (t, x), new with nothing merged if there was none; NULL
 * when out of memory. */
static inp_merge *merge_entry(merge_table *tb, const char *t, const char *x)
{
  if (merge_reserve(tb))
    return NULL;
  const uint64_t key = merge_key(t, x);
  inp_merge *e = merge_slot(tb, t, x, key);
  if (!e->t) {
    *e = (inp_merge){t, x, key, 0};
    ++tb->n;
  }
  return e;
}

/* Set name of the block's kind: 1 and its members, or 0. */
static int find_set(const inp_reader *r, int elements, const char *name, const size_t **items,
                    size_t *n)
{
  return elements ? fb_mesh_elset(r->mesh, name, items, n)
                  : fb_mesh_nset(r->mesh, name, items, n);
}

/* Adds the n members at v to the block's set (n = 0 makes it exist). */
static int add_members(const inp_reader *r, const set_fill *f, size_t n, const size_t *v)
{
  fb_err sub;
  fb_err_clear(&sub);
  const inp_set_block *blk = f->blk;
  const int rc = blk->elements ? fb_mesh_add_elset(r->mesh, blk->name, n, v, &sub)
                               : fb_mesh_add_nset(r->mesh, blk->name, n, v, &sub);
  return rc ? inp_mesh_error(r, f->line, &sub) : FB_OK;
}

static int flush(const inp_reader *r, set_fill *f)
{
  const int rc = add_members(r, f, f->npending, f->pending);
  f->npending = 0;
  return rc;
}

static int push_index(const inp_reader *r, set_fill *f, size_t i)
{
  const int rc = f->npending == FILL_CHUNK ? flush(r, f) : FB_OK;
  if (!rc)
    f->pending[f->npending++] = i;
  return rc;
}

/* 1 if id is a MASS element's (a linear search, on the path of a set
 * that names an id no shell has: a deck has a few point masses). */
static int is_mass_element(const inp_reader *r, long id)
{
  for (size_t i = 0; i < r->nmass_elems; ++i)
    if (r->mass_elems[i].id == id)
      return 1;
  return 0;
}

static int push_id(const inp_reader *r, set_fill *f, const inp_item *it, long id)
{
  const inp_set_block *blk = f->blk;
  const long i =
      blk->elements ? fb_mesh_find_element_id(r->mesh, id) : fb_mesh_find_node_id(r->mesh, id);
  if (i < 0 && blk->elements && is_mass_element(r, id))
    return FB_OK; /* element sets of the mesh hold shells only */
  if (i < 0)
    return inp_error(r, it->line, "%s set '%s' names %s %ld, which is not defined",
                     set_kind(blk->elements), blk->name, set_kind(blk->elements), id);
  return push_index(r, f, (size_t)i);
}

/* The members of the set it names that are not in the block's set yet. */
static int merge_set(const inp_reader *r, merge_table *memo, set_fill *f, const inp_item *it)
{
  const inp_set_block *blk = f->blk;
  const size_t *items = NULL;
  size_t n = 0;
  const int self = same_word(it->ref, blk->name);
  if (!(self ? f->existed : find_set(r, blk->elements, it->ref, &items, &n)))
    return inp_error(r, it->line, "%s set '%s' names %s set '%s', which is not defined",
                     set_kind(blk->elements), blk->name, set_kind(blk->elements), it->ref);
  if (self) /* a set holds its own members already */
    return FB_OK;
  inp_merge *e = merge_entry(memo, blk->name, it->ref);
  if (!e)
    return inp_nomem(r);
  if (e->merged == n)
    return FB_OK;
  int rc = flush(r, f); /* the members named before come first */
  if (!rc)
    rc = add_members(r, f, n - e->merged, items + e->merged);
  if (!rc)
    e->merged = n;
  return rc;
}

static int resolve_item(const inp_reader *r, merge_table *memo, set_fill *f, const inp_item *it)
{
  int rc = FB_OK;
  switch (it->kind) {
  case ITEM_ID: return push_id(r, f, it, it->a);
  case ITEM_RANGE:
    /* Stepping this way cannot overflow past it->b. */
    for (long id = it->a; !rc; id += it->step) {
      rc = push_id(r, f, it, id);
      if (it->b - id < it->step)
        break;
    }
    return rc;
  case ITEM_SET: return merge_set(r, memo, f, it);
  case ITEM_INDICES:
    for (long k = it->a; k < it->b && !rc; ++k)
      rc = push_index(r, f, (size_t)k);
    return rc;
  }
  return rc;
}

/* One block; memo holds the merges of its kind of sets. */
static int resolve_block(const inp_reader *r, merge_table *memo, const inp_set_block *blk)
{
  set_fill f;
  f.blk = blk;
  f.existed = find_set(r, blk->elements, blk->name, NULL, NULL);
  f.line = blk->count ? r->items[blk->first].line : 1;
  f.npending = 0;
  int rc = FB_OK;
  for (size_t k = 0; k < blk->count && !rc; ++k)
    rc = resolve_item(r, memo, &f, &r->items[blk->first + k]);
  return rc ? rc : flush(r, &f);
}

/* Node and element sets, in the deck's order. */
static int resolve_sets(const inp_reader *r)
{
  merge_table memo[2] = {{NULL, 0, 0}, {NULL, 0, 0}}; /* node sets, element sets */
  int rc = FB_OK;
  for (size_t b = 0; b < r->nblocks && !rc; ++b)
    rc = resolve_block(r, &memo[r->blocks[b].elements], &r->blocks[b]);
  free(memo[0].slots);
  free(memo[1].slots);
  return rc;
}

/* The properties of section sec: its material's, with a default of 0
 * (fb_mesh_set_section refuses it) for what the material leaves out. */
static int section_props(const inp_reader *r, const inp_section *sec, fb_shell_props *p)
{
  const inp_material *mat = find_material(r, sec->material);
  if (!mat)
    return inp_error(r, sec->line, "*SHELL SECTION names material '%s', which is not defined",
                     sec->material);
  if (!mat->has_elastic || !mat->has_density)
    return inp_error(r, sec->line, "*SHELL SECTION's material '%s' has no %s", sec->material,
                     mat->has_elastic ? "*DENSITY" : "*ELASTIC");
  *p = (fb_shell_props){mat->young, mat->poisson, mat->density, sec->thickness, 0.0, 0.0};
  return FB_OK;
}

/* An element already in a section: the error names both lines. */
static int check_overlap(const inp_reader *r, const inp_section *sec)
{
  const size_t *elems = NULL;
  size_t n = 0;
  if (!fb_mesh_elset(r->mesh, sec->elset, &elems, &n))
    return inp_error(r, sec->line,
                     "*SHELL SECTION names element set '%s', which is not defined", sec->elset);
  for (size_t k = 0; k < n; ++k) {
    const long prev = fb_mesh_element_section(r->mesh, elems[k]);
    if (prev >= 0)
      return inp_error(r, sec->line,
                       "element %ld is in two *SHELL SECTIONs (this one and line %zu's)",
                       fb_mesh_element_id(r->mesh, elems[k]), r->sections[prev].line);
  }
  return FB_OK;
}

/* The sections, in the deck's order: mesh section i is r->sections[i]. */
static int resolve_sections(const inp_reader *r)
{
  fb_err sub;
  fb_err_clear(&sub);
  int rc = FB_OK;
  for (size_t i = 0; i < r->nsections && !rc; ++i) {
    const inp_section *sec = &r->sections[i];
    fb_shell_props p;
    rc = section_props(r, sec, &p);
    if (!rc)
      rc = check_overlap(r, sec);
    if (!rc && fb_mesh_set_section(r->mesh, sec->elset, &p, &sub))
      rc = inp_mesh_error(r, sec->line, &sub);
  }
  return rc;
}

/* props from the only section when it covers every element, else from
 * the only material when there is no section. */
static void deck_props(const inp_reader *r, fb_shell_props *props)
{
  const fb_mesh *m = r->mesh;
  if (r->nsections == 1) {
    for (size_t e = 0; e < fb_mesh_nelements(m); ++e)
      if (fb_mesh_element_section(m, e) != 0)
        return;
    const fb_shell_props *p = fb_mesh_section_props(m, 0);
    props->young = p->young;
    props->poisson = p->poisson;
    props->density = p->density;
    props->thickness = p->thickness;
  } else if (r->nsections == 0 && r->nmaterials == 1) {
    const inp_material *mat = &r->materials[0];
    if (mat->has_elastic) {
      props->young = mat->young;
      props->poisson = mat->poisson;
    }
    if (mat->has_density)
      props->density = mat->density;
  }
}

/* An element that no shell can integrate (a repeated node, no area, a
 * reentrant corner, a warped quadrilateral: fb_mesh_check's element tests)
 * is reported at its own line of the deck, where it must be fixed. The
 * mesh's elements are in the deck's order (resolve_elements). */
static int check_element_shapes(const inp_reader *r)
{
  fb_err sub;
  fb_err_clear(&sub);
  size_t bad = 0;
  if (fb_mesh_check_elements(r->mesh, &bad, &sub) == FB_OK)
    return FB_OK;
  return inp_mesh_error(r, r->elems[bad].line, &sub);
}

/* ---- Added masses, once the sets and sections are resolved. */

/* Gives the MASS elements of *MASS m's set their mass; the set must hold
 * MASS elements, each given its mass once. */
static int assign_mass(const inp_reader *r, const inp_mass *m)
{
  size_t n = 0;
  for (size_t i = 0; i < r->nmass_elems; ++i) {
    inp_mass_element *el = &r->mass_elems[i];
    if (!el->elset || !same_word(el->elset, m->elset))
      continue;
    if (el->mass_line)
      return inp_error(r, m->line,
                       "MASS element %ld is given its mass twice (here and line %zu)", el->id,
                       el->mass_line);
    el->mass = m->value;
    el->mass_line = m->line;
    ++n;
  }
  if (n > 0)
    return FB_OK;
  if (fb_mesh_elset(r->mesh, m->elset, NULL, NULL))
    return inp_error(r, m->line,
                     "*MASS names element set '%s', which holds no MASS elements (shells take "
                     "*NONSTRUCTURAL MASS)",
                     m->elset);
  return inp_error(r, m->line, "*MASS names element set '%s', which is not defined", m->elset);
}

/* The MASS elements as the mesh's point masses, each with a *MASS. */
static int resolve_point_masses(const inp_reader *r)
{
  int rc = FB_OK;
  for (size_t k = 0; k < r->nmasses && !rc; ++k)
    rc = assign_mass(r, &r->masses[k]);
  fb_err sub;
  fb_err_clear(&sub);
  for (size_t i = 0; i < r->nmass_elems && !rc; ++i) {
    const inp_mass_element *el = &r->mass_elems[i];
    const long node = fb_mesh_find_node_id(r->mesh, el->node);
    if (!el->mass_line)
      return inp_error(r, el->line, "MASS element %ld has no *MASS%s%s%s", el->id,
                       el->elset ? " (for its element set '" : " (nor an ELSET= to give one)",
                       el->elset ? el->elset : "", el->elset ? "')" : "");
    if (node < 0)
      return inp_error(r, el->line, "element %ld refers to node %ld, which is not defined",
                       el->id, el->node);
    if (fb_mesh_add_point_mass(r->mesh, el->id, (size_t)node, el->mass, &sub))
      rc = inp_mesh_error(r, el->line, &sub);
  }
  return rc;
}

/* Area of element e (its projected area if it is warped). */
static double element_area(const fb_mesh *m, size_t e)
{
  double v[3];
  fb_mesh_element_area_vector(m, e, v);
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

/* A total mass over the shells of a set, per area: in proportion to
 * each element's area, which is Abaqus's distribution in proportion to
 * mass or to volume alike when the elements share one section (one
 * density and thickness); a set over several sections is refused. */
static int total_per_area(const inp_reader *r, const inp_mass *m, const size_t *elems, size_t n,
                          double *per_area)
{
  double area = 0.0;
  for (size_t k = 0; k < n; ++k) {
    if (fb_mesh_element_section(r->mesh, elems[k]) !=
        fb_mesh_element_section(r->mesh, elems[0]))
      return inp_error(r, m->line,
                       "*NONSTRUCTURAL MASS, UNITS=TOTAL MASS over element set '%s', whose "
                       "elements are in more than one *SHELL SECTION, is not supported",
                       m->elset);
    area += element_area(r->mesh, elems[k]);
  }
  *per_area = m->value / area;
  return FB_OK;
}

/* 1 if name is the set of a block of MASS elements. */
static int is_mass_set(const inp_reader *r, const char *name)
{
  for (size_t i = 0; i < r->nmass_elems; ++i)
    if (r->mass_elems[i].elset && same_word(r->mass_elems[i].elset, name))
      return 1;
  return 0;
}

/* A mass per volume of element e's shell as a mass per area: times its
 * section's thickness, which an element outside every *SHELL SECTION
 * does not have yet (the program that reads the deck gives it). */
static int volume_per_area(const inp_reader *r, const inp_mass *m, size_t e, double *per_area)
{
  const long sec = fb_mesh_element_section(r->mesh, e);
  if (sec < 0)
    return inp_error(r, m->line,
                     "*NONSTRUCTURAL MASS, UNITS=MASS PER VOLUME: element %ld of set '%s' is "
                     "in no *SHELL SECTION (the thickness it needs)",
                     fb_mesh_element_id(r->mesh, e), m->elset);
  *per_area = m->value * fb_mesh_section_props(r->mesh, (size_t)sec)->thickness;
  return FB_OK;
}

/* Each *NONSTRUCTURAL MASS as its elements' added mass per area. */
static int resolve_nonstructural(const inp_reader *r)
{
  fb_err sub;
  fb_err_clear(&sub);
  for (size_t i = 0; i < r->nnsms; ++i) {
    const inp_mass *m = &r->nsms[i];
    const size_t *elems = NULL;
    size_t n = 0;
    if (!fb_mesh_elset(r->mesh, m->elset, &elems, &n))
      return inp_error(
          r, m->line, "*NONSTRUCTURAL MASS names element set '%s', which %s", m->elset,
          is_mass_set(r, m->elset) ? "holds MASS elements, not shells (they take *MASS)"
                                   : "is not defined");
    double per_area = m->value;
    int rc = m->units == NSM_TOTAL ? total_per_area(r, m, elems, n, &per_area) : FB_OK;
    for (size_t k = 0; k < n && !rc; ++k) {
      if (m->units == NSM_PER_VOLUME && (rc = volume_per_area(r, m, elems[k], &per_area)))
        break;
      if (fb_mesh_add_element_nonstructural(r->mesh, elems[k], per_area, &sub))
        rc = inp_mesh_error(r, m->line, &sub);
    }
    if (rc)
      return rc;
  }
  return FB_OK;
}

static int finish(const inp_reader *r, fb_shell_props *props)
{
  if (fb_mesh_nnodes(r->mesh) == 0)
    return inp_error(r, r->lineno, "the deck defines no nodes (*NODE)");
  if (r->nelems == 0)
    return inp_error(r, r->lineno, "the deck defines no elements (*ELEMENT)");
  int rc = resolve_elements(r);
  if (!rc)
    rc = check_element_shapes(r);
  if (!rc)
    rc = resolve_sets(r);
  if (!rc)
    rc = resolve_sections(r);
  if (!rc)
    rc = resolve_point_masses(r);
  if (!rc)
    rc = resolve_nonstructural(r);
  if (!rc && props)
    deck_props(r, props);
  return rc;
}

static void reader_free(inp_reader *r)
{
  free(r->text);
  free(r->fields);
  free(r->elems);
  free(r->items);
  free(r->blocks);
  free(r->materials);
  free(r->sections);
  free(r->mass_elems);
  free(r->masses);
  free(r->nsms);
}

/* The parser shared by both readers: takes the NUL-terminated buffer text
 * (len bytes before the NUL, owned: freed here) and reports errors as
 * "name:line: ...". */
static int read_inp_buffer(char *text, size_t len, const char *name, fb_mesh **out,
                           fb_shell_props *props, fb_err *err)
{
  inp_reader r;
  memset(&r, 0, sizeof r);
  r.path = name;
  r.err = err;
  r.text = text;
  r.len = len;
  int rc = fb_mesh_new(&r.mesh, err);
  if (!rc)
    rc = read_deck(&r);
  if (!rc)
    rc = finish(&r, props);
  if (rc)
    fb_mesh_free(&r.mesh);
  *out = r.mesh;
  reader_free(&r);
  return rc;
}

int fb_mesh_read_inp(const char *path, fb_mesh **out, fb_shell_props *props, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_read_inp: out is NULL");
  *out = NULL;
  if (!path)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_read_inp: path is NULL");
  char *text = NULL;
  size_t len = 0;
  const int rc = fb_read_file(path, &text, &len, err);
  return rc ? rc : read_inp_buffer(text, len, path, out, props, err);
}

/* The parser splits lines in place and relies on a NUL after the last
 * byte, so it works on a terminated copy; a NUL byte inside the text is
 * reported as binary data by split_line. */
int fb_mesh_read_inp_string(const char *text, size_t len, const char *display_name,
                            fb_mesh **out, fb_shell_props *props, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_read_inp_string: out is NULL");
  *out = NULL;
  if (!text)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_read_inp_string: text is NULL");
  const char *name = display_name ? display_name : "<string>";
  char *copy;
  const int rc = fb_text_copy(text, len, name, &copy, err);
  return rc ? rc : read_inp_buffer(copy, len, name, out, props, err);
}

/* ---- Writing. */

/* A coordinate at most this fraction of the mesh's largest one is the
 * round-off of a zero (a generated mesh has -2.8e-17 for 0) and is written
 * as 0: other programs take it at its word (CalculiX's expansion of S8R
 * shells refused such a deck with "nonpositive jacobian"). */
#define ZERO_COORDINATE 1e-12

/* One coordinate, to 15 significant digits (0.3 for 0.30000000000000004;
 * 1e-15 relative, far below any mesh's accuracy). */
static void write_coordinate(FILE *fp, double v, double scale)
{
  fprintf(fp, ", %.15g", fabs(v) <= ZERO_COORDINATE * scale ? 0.0 : v);
}

static void write_nodes(FILE *fp, const fb_mesh *m)
{
  double scale = 0.0;
  for (size_t i = 0; i < fb_mesh_nnodes(m); ++i)
    for (int k = 0; k < 3; ++k)
      scale = fmax(scale, fabs(fb_mesh_node_xyz(m, i)[k]));
  fputs("*NODE\n", fp);
  for (size_t i = 0; i < fb_mesh_nnodes(m); ++i) {
    const double *p = fb_mesh_node_xyz(m, i);
    fprintf(fp, "%ld", fb_mesh_node_id(m, i));
    for (int k = 0; k < 3; ++k)
      write_coordinate(fp, p[k], scale);
    fputc('\n', fp);
  }
}

/* One *ELEMENT block per run of equal types, so that reading the deck
 * back gives the elements in the same order. */
static void write_elements(FILE *fp, const fb_mesh *m)
{
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    const fb_elem_type type = fb_mesh_element_type(m, e);
    if (e == 0 || type != fb_mesh_element_type(m, e - 1))
      fprintf(fp, "*ELEMENT, TYPE=%s\n", fb_mesh_type_name(type));
    const size_t *nd = fb_mesh_element_nodes(m, e);
    fprintf(fp, "%ld", fb_mesh_element_id(m, e));
    for (size_t k = 0; k < fb_mesh_type_nodes(type); ++k)
      fprintf(fp, ", %ld", fb_mesh_node_id(m, nd[k]));
    fputc('\n', fp);
  }
}

/* The members of a set as ids, sixteen per data line (the Abaqus limit
 * for *NSET and *ELSET lines). */
static void write_ids(FILE *fp, const size_t *items, size_t n, const fb_mesh *m, int elements)
{
  for (size_t k = 0; k < n; ++k)
    fprintf(fp, "%ld%s",
            elements ? fb_mesh_element_id(m, items[k]) : fb_mesh_node_id(m, items[k]),
            k + 1 == n || k % 16 == 15 ? "\n" : ", ");
}

static void write_sets(FILE *fp, const fb_mesh *m)
{
  for (size_t s = 0; s < fb_mesh_nnsets(m); ++s) {
    const char *name = fb_mesh_nset_name(m, s);
    const size_t *nodes = NULL;
    size_t n = 0;
    fb_mesh_nset(m, name, &nodes, &n);
    fprintf(fp, "*NSET, NSET=%s\n", name);
    write_ids(fp, nodes, n, m, 0);
  }
  for (size_t s = 0; s < fb_mesh_nelsets(m); ++s) {
    const char *name = fb_mesh_elset_name(m, s);
    const size_t *elems = NULL;
    size_t n = 0;
    fb_mesh_elset(m, name, &elems, &n);
    fprintf(fp, "*ELSET, ELSET=%s\n", name);
    write_ids(fp, elems, n, m, 1);
  }
}

/* A group of elements written with one material and section: those of
 * section sec (-1: none) whose own added non-structural mass is nsm (a
 * deck has no keyword CalculiX reads for it: fem.h). */
typedef struct deck_group {
  long sec;
  double nsm;
  size_t n;   /* its elements */
  size_t sub; /* 0 for the section's first group, then 1, 2, ... */
} deck_group;

static int in_group(const fb_mesh *m, size_t e, const deck_group *g)
{
  return fb_mesh_element_section(m, e) == g->sec &&
         fb_mesh_element_nonstructural(m, e) == g->nsm;
}

/* The ids of the group's elements, sixteen per line. */
static void write_group_ids(FILE *fp, const fb_mesh *m, const deck_group *g)
{
  size_t k = 0;
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e)
    if (in_group(m, e, g)) {
      fprintf(fp, "%ld%s", fb_mesh_element_id(m, e),
              k + 1 == g->n || k % 16 == 15 ? "\n" : ", ");
      ++k;
    }
}

/* 1 if the element set name holds exactly the group's elements. */
static int set_is(const fb_mesh *m, const char *name, const deck_group *g)
{
  const size_t *elems = NULL;
  size_t count = 0;
  if (!name || !fb_mesh_elset(m, name, &elems, &count) || count != g->n)
    return 0;
  for (size_t k = 0; k < g->n; ++k)
    if (!in_group(m, elems[k], g))
      return 0;
  return 1;
}

/* A name for the set of a written group: the section's own set or
 * another that holds just its elements, EALL for every element, or the
 * first SECTION_<k> (SECTION_<k>_<sub> for a section's later groups)
 * that names no set. */
static void group_set_name(const fb_mesh *m, const deck_group *g, char *name, size_t size)
{
  const char *own = g->sec >= 0 ? fb_mesh_section_elset(m, (size_t)g->sec) : NULL;
  for (size_t i = 0; !set_is(m, own, g) && i < fb_mesh_nelsets(m); ++i)
    own = fb_mesh_elset_name(m, i);
  if (set_is(m, own, g)) {
    snprintf(name, size, "%s", own);
    return;
  }
  if (g->n == fb_mesh_nelements(m) && !fb_mesh_elset(m, "EALL", NULL, NULL)) {
    snprintf(name, size, "EALL");
    return;
  }
  for (long k = g->sec + 2;; ++k) {
    if (g->sub)
      snprintf(name, size, "SECTION_%ld_%zu", k, g->sub + 1);
    else
      snprintf(name, size, "SECTION_%ld", k);
    if (!fb_mesh_elset(m, name, NULL, NULL))
      return;
  }
}

/* Material MAT_<k> (MAT_<k>_<sub>) and the section of the group's
 * elements, whose properties are p with the group's non-structural mass
 * added, all of it smeared into the density (fem.h). */
static void write_group(FILE *fp, const fb_mesh *m, const deck_group *g,
                        const fb_shell_props *p)
{
  char name[FB_MESH_NAME_MAX + 1], mat[48];
  group_set_name(m, g, name, sizeof name);
  if (!set_is(m, name, g)) {
    fprintf(fp, "*ELSET, ELSET=%s\n", name);
    write_group_ids(fp, m, g);
  }
  if (g->sub)
    snprintf(mat, sizeof mat, "MAT_%ld_%zu", g->sec + 2, g->sub + 1);
  else
    snprintf(mat, sizeof mat, "MAT_%ld", g->sec + 2);
  const double nsm = p->nonstructural_mass + g->nsm;
  fprintf(fp,
          "*MATERIAL, NAME=%s\n*ELASTIC\n%.17g, %.17g\n*DENSITY\n%.17g\n"
          "*SHELL SECTION, ELSET=%s, MATERIAL=%s\n%.17g\n",
          mat, p->young, p->poisson, p->density + nsm / p->thickness, name, mat, p->thickness);
}

/* The groups of section sec, one per distinct added non-structural mass,
 * in increasing order of it: each pass finds the smallest value above the
 * last group's (O(elements x groups); a deck has a few). */
static void write_section(FILE *fp, const fb_mesh *m, long sec, const fb_shell_props *p)
{
  deck_group g = {sec, 0.0, 0, 0};
  for (;; ++g.sub) {
    double next = 0.0;
    size_t n = 0;
    for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
      const double v = fb_mesh_element_nonstructural(m, e);
      if (fb_mesh_element_section(m, e) != sec || (g.sub > 0 && !(v > g.nsm)))
        continue;
      if (n == 0 || v < next) {
        next = v;
        n = 0;
      }
      n += v == next;
    }
    if (n == 0)
      return;
    g.nsm = next;
    g.n = n;
    write_group(fp, m, &g, p);
  }
}

/* One section per group of elements with the same section (-1: p's). */
static void write_sections(FILE *fp, const fb_mesh *m, const fb_shell_props *p)
{
  for (long sec = p ? -1 : 0; sec < (long)fb_mesh_nsections(m); ++sec)
    write_section(fp, m, sec, sec >= 0 ? fb_mesh_section_props(m, (size_t)sec) : p);
}

/* Each point mass as a MASS element of its own element set PMASS_<id>
 * (or the first PMASS_<id>_<k> that names no set) with its *MASS, the
 * form CalculiX reads (its *MASS gives every element of the set the
 * mass). */
static void write_point_masses(FILE *fp, const fb_mesh *m)
{
  for (size_t i = 0; i < fb_mesh_npoint_masses(m); ++i) {
    const long id = fb_mesh_point_mass_id(m, i);
    char name[FB_MESH_NAME_MAX + 1];
    snprintf(name, sizeof name, "PMASS_%ld", id);
    for (int k = 2; fb_mesh_elset(m, name, NULL, NULL); ++k)
      snprintf(name, sizeof name, "PMASS_%ld_%d", id, k);
    fprintf(fp, "*ELEMENT, TYPE=MASS, ELSET=%s\n%ld, %ld\n*MASS, ELSET=%s\n%.17g\n", name, id,
            fb_mesh_node_id(m, fb_mesh_point_mass_node(m, i)), name, fb_mesh_point_mass(m, i));
  }
}

void fb_mesh_print_inp(FILE *fp, const fb_mesh *m, const fb_shell_props *p)
{
  fprintf(fp,
          "** flexbond shell mesh: %zu nodes, %zu elements, %zu node sets\n*HEADING\n"
          "flexbond shell mesh\n",
          fb_mesh_nnodes(m), fb_mesh_nelements(m), fb_mesh_nnsets(m));
  write_nodes(fp, m);
  write_elements(fp, m);
  write_sets(fp, m);
  write_sections(fp, m, p);
  write_point_masses(fp, m);
}

static int finite_props(const fb_shell_props *p)
{
  return isfinite(p->young) && isfinite(p->poisson) && isfinite(p->density) &&
         isfinite(p->thickness) && p->thickness > 0.0 && isfinite(p->nonstructural_mass);
}

/* p may be NULL: the deck then has sections only for the elements with
 * one. */
int fb_mesh_write_inp(const fb_mesh *m, const fb_shell_props *p, const char *path, fb_err *err)
{
  if (!m || !path)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_write_inp: mesh or path is NULL");
  if (p && !finite_props(p))
    return fb_err_set(err, FB_EINVAL, "%s: shell properties are not finite", path);
  fb_out *out = NULL;
  const int rc = fb_out_open(path, &out, err);
  if (rc)
    return rc;
  fb_mesh_print_inp(fb_out_stream(out), m, p);
  return fb_out_commit(&out, err);
}
