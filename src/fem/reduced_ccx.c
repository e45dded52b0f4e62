/* SPDX-License-Identifier: BSD-3-Clause */
/* CalculiX's condensed substructure (flexbond/reduced.h), as ccx 2.20
 * writes it for *SUBSTRUCTURE MATRIX OUTPUT, OUTPUT FILE=USER DEFINED
 * (CalculiX CrunchiX User's Manual 2.20, "Substructure Generation"; the
 * layout read from its output, as Abaqus's *USER ELEMENT and *MATRIX
 * define it):
 *
 *   *USER ELEMENT,NODES=n,LINEAR
 *   ** ELEMENT NODES
 *   **  id1, id2, ... (n retained node ids, one per element "node")
 *   d                   the DOF of element node 1
 *   k, d                from element node k on, DOF d
 *   *MATRIX,TYPE=STIFFNESS
 *   the lower triangle row by row (row i has i values), comma-separated
 *
 * ccx gives every retained DOF an element node of its own; Abaqus's
 * general form (several DOFs per node, "k, d1, d2, ...") is read too.
 * *MATRIX,TYPE=MASS, which Abaqus allows, is read as M. */
#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "core/textfile.h"
#include "fem/reduced_internal.h"

typedef struct ccx_reader {
  fb_text_reader r;
  long *node; /* element node ids (n) */
  size_t n, nnode;
  unsigned *dofs; /* element node k's DOFs, a bit per component */
  size_t ndof;
  long *row_node; /* each matrix row's node id and component */
  int *row_comp;
} ccx_reader;

static int ccx_error(const ccx_reader *c, const char *what, const char *tok)
{
  fb_err_set(c->r.err, FB_EPARSE, "%s:%zu: %s", c->r.path, c->r.line_no, what);
  if (tok)
    fb_err_set_excerpt(c->r.err, tok, strlen(tok));
  return FB_EPARSE;
}

/* The first place needle (upper case) is in s, any case; NULL if none. */
static char *find_nocase(char *s, const char *needle)
{
  const size_t n = strlen(needle);
  for (; *s; ++s)
    if (!strncasecmp(s, needle, n))
      return s;
  return NULL;
}

/* The next comma-separated token of *p, trimmed (NULL at the end). */
static char *token(char **p)
{
  char *s = *p;
  while (*s == ' ' || *s == '\t')
    ++s;
  if (!*s)
    return NULL;
  char *end = strchr(s, ',');
  *p = end ? end + 1 : s + strlen(s);
  if (end)
    *end = '\0';
  char *e = s + strlen(s);
  while (e > s && (e[-1] == ' ' || e[-1] == '\t'))
    *--e = '\0';
  return s;
}

static int count(const char *tok, long *v)
{
  char *end;
  errno = 0;
  *v = strtol(tok, &end, 10);
  return !errno && end != tok && *end == '\0' && *v > 0;
}

/* NODES=n, checked against the file's size before anything is allocated:
 * the triangle's n (n + 1) / 2 numbers take at least 2 bytes each. */
static int user_element(ccx_reader *c, char *line)
{
  char *nodes = find_nocase(line, "NODES=");
  long n;
  char *p = nodes ? nodes + 6 : NULL;
  char *tok = p ? token(&p) : NULL;
  if (!tok || !count(tok, &n))
    return ccx_error(c, "*USER ELEMENT: expected NODES=n, n > 0", tok);
  struct stat st;
  if ((size_t)n > FB_REDUCED_MAX_DOFS)
    return ccx_error(c,
                     "*USER ELEMENT: more nodes than the 3000 DOFs a reduced structure may "
                     "have (docs/errors.md, \"Limits\")",
                     NULL);
  if (fstat(fileno(c->r.fp), &st) == 0 && (double)n * ((double)n + 1) > (double)st.st_size)
    return ccx_error(c, "*USER ELEMENT: NODES= gives a matrix larger than the file can hold",
                     NULL);
  c->n = (size_t)n;
  c->node = calloc(c->n, sizeof *c->node);
  c->dofs = calloc(c->n, sizeof *c->dofs);
  if (!c->node || !c->dofs)
    return fb_err_set(c->r.err, FB_ENOMEM, "out of memory reading %s", c->r.path);
  return FB_OK;
}

/* "**  id, id, ..." after "** ELEMENT NODES". */
static int node_comment(ccx_reader *c, char *line)
{
  char *p = line + 2, *tok;
  while ((tok = token(&p)) != NULL) {
    long id;
    if (!count(tok, &id))
      return ccx_error(c, "element node: not an integer > 0", tok);
    if (c->nnode == c->n)
      return ccx_error(c, "more element nodes than NODES= gives", NULL);
    c->node[c->nnode++] = id;
  }
  return FB_OK;
}

/* "d" (the first line) or "k, d, ...": from element node k on. */
static int dof_line(ccx_reader *c, char *line, int first)
{
  char *p = line, *tok;
  long k = 1, d;
  if (!first) {
    tok = token(&p);
    if (!tok || !count(tok, &k) || (size_t)k > c->n)
      return ccx_error(c, "DOF line: element node out of range", tok);
  }
  unsigned set = 0;
  while ((tok = token(&p)) != NULL) {
    if (!count(tok, &d) || d > 6)
      return ccx_error(c, "DOF line: a component from 1 to 6", tok);
    set |= 1u << (d - 1);
  }
  if (!set)
    return ccx_error(c, "DOF line: no component", NULL);
  for (size_t e = (size_t)k - 1; e < c->n; ++e)
    c->dofs[e] = set;
  return FB_OK;
}

/* The matrix's rows: each element node's DOFs in order. */
static int rows(ccx_reader *c)
{
  if (c->nnode != c->n)
    return ccx_error(c, "the ELEMENT NODES comment lists fewer nodes than NODES= gives", NULL);
  c->ndof = 0;
  for (size_t e = 0; e < c->n; ++e)
    c->ndof += (size_t)__builtin_popcount(c->dofs[e]);
  if (c->ndof > FB_REDUCED_MAX_DOFS)
    return ccx_error(c, "more than the 3000 DOFs a reduced structure may have", NULL);
  c->row_node = calloc(c->ndof ? c->ndof : 1, sizeof *c->row_node);
  c->row_comp = calloc(c->ndof ? c->ndof : 1, sizeof *c->row_comp);
  if (!c->row_node || !c->row_comp)
    return fb_err_set(c->r.err, FB_ENOMEM, "out of memory reading %s", c->r.path);
  size_t i = 0;
  for (size_t e = 0; e < c->n; ++e)
    for (int d = 1; d <= 6; ++d)
      if (c->dofs[e] & (1u << (d - 1))) {
        c->row_node[i] = c->node[e];
        c->row_comp[i++] = d;
      }
  return FB_OK;
}

/* The triangle's values into l until the next keyword (left in *next). */
static int triangle(ccx_reader *c, reduced_list *l, char **next)
{
  size_t i = 0, j = 0, count_read = 0;
  const size_t want = c->ndof * (c->ndof + 1) / 2;
  int digits = 99;
  *next = NULL;
  for (;;) {
    char *line = NULL;
    int rc = fb_text_next_line(&c->r, &line);
    if (rc)
      return rc;
    if (!line || line[0] == '*') {
      if (line && line[1] == '*')
        continue;
      *next = line;
      break;
    }
    char *p = line, *tok;
    while ((tok = token(&p)) != NULL) {
      if (count_read == want)
        return ccx_error(c, "more values than the matrix's lower triangle holds", NULL);
      reduced_entry e = {.node_i = c->row_node[i],
                         .comp_i = c->row_comp[i],
                         .node_j = c->row_node[j],
                         .comp_j = c->row_comp[j],
                         .line = c->r.line_no};
      if (fb_parse_decimal_field(tok, &e.val, c->r.err)) {
        fb_err_set_excerpt(c->r.err, tok, strlen(tok));
        return fb_err_prefix(c->r.err, "%s:%zu: value: ", c->r.path, c->r.line_no);
      }
      const int d = reduced_digits(tok);
      if (e.val != 0.0 && d < digits)
        digits = d;
      ++count_read;
      const int diagonal = i == j;
      if (++j > i) {
        ++i;
        j = 0;
      }
      /* Zeros off the diagonal are no entries; a diagonal's names its DOF. */
      if ((e.val != 0.0 || diagonal) && (rc = reduced_list_push(l, &e, c->r.err)) != FB_OK)
        return rc;
    }
  }
  if (count_read < want)
    return fb_err_set(c->r.err, FB_EPARSE,
                      "%s:%zu: the matrix ends after %zu of its %zu lower-triangle values",
                      c->r.path, c->r.line_no, count_read, want);
  l->one_triangle = 1;
  l->precision = reduced_precision(digits == 99 ? 17 : digits);
  return FB_OK;
}

static int read_ccx(ccx_reader *c, reduced_list *k, reduced_list *m)
{
  enum { START, NODES, DOFS, DONE } state = START;
  int first_dof = 1, rc = FB_OK;
  char *line = NULL;
  while (!rc) {
    if (!line && (rc = fb_text_next_line(&c->r, &line)) != FB_OK)
      break;
    if (!line)
      break;
    char *cur = line;
    line = NULL;
    if (!strncasecmp(cur, "*USER ELEMENT", 13)) {
      if (state != START)
        rc = ccx_error(c, "a second *USER ELEMENT", NULL);
      else if (!(rc = user_element(c, cur)))
        state = NODES;
    } else if (!strncasecmp(cur, "*MATRIX", 7)) {
      const int mass = find_nocase(cur, "TYPE=MASS") != NULL;
      if (state == START)
        rc = ccx_error(c, "*MATRIX before *USER ELEMENT", NULL);
      else if (!mass && !find_nocase(cur, "TYPE=STIFFNESS"))
        rc = ccx_error(c, "*MATRIX: expected TYPE=STIFFNESS or TYPE=MASS", NULL);
      else if ((mass ? m : k)->n || (mass ? m : k)->one_triangle)
        rc = ccx_error(c, "the matrix is given twice", NULL);
      if (!rc && state != DONE && !(rc = rows(c)))
        state = DONE;
      if (!rc)
        rc = triangle(c, mass ? m : k, &line);
    } else if (!strncmp(cur, "**", 2)) {
      if (state == NODES && c->nnode == 0 && find_nocase(cur, "ELEMENT NODES"))
        state = NODES; /* the ids follow */
      else if (state == NODES && isdigit((unsigned char)cur[2 + strspn(cur + 2, " ")]))
        rc = node_comment(c, cur);
    } else if (cur[0] == '*') {
      continue; /* another keyword: nothing of the matrix */
    } else if (state == NODES || state == DOFS) {
      if (cur[strspn(cur, " \t")] == '\0')
        continue;
      state = DOFS;
      rc = dof_line(c, cur, first_dof);
      first_dof = 0;
    } else if (cur[strspn(cur, " \t")] != '\0') {
      rc = ccx_error(c, "data outside a *USER ELEMENT or *MATRIX", NULL);
    }
  }
  if (!rc && !k->one_triangle)
    rc = fb_err_set(c->r.err, FB_EPARSE, "%s:%zu: no *MATRIX,TYPE=STIFFNESS", c->r.path,
                    c->r.line_no ? c->r.line_no : 1);
  return rc;
}

int fb_reduced_read_ccx(const char *path, const char *nodes_path, fb_reduced **out, fb_err *err)
{
  if (!out || !path || !nodes_path)
    return fb_err_set(err, FB_EINVAL, "reduced structure: a path or the output is NULL");
  *out = NULL;
  reduced_nodes nodes;
  int rc = reduced_nodes_read_plain(nodes_path, "CalculiX", &nodes, err);
  if (rc)
    return rc;
  ccx_reader c = {0};
  reduced_list k = {.path = path, .name = "K"}, m = {.path = path, .name = "M"};
  rc = fb_text_open(&c.r, path, "CalculiX matrix", err);
  if (!rc)
    rc = read_ccx(&c, &k, &m);
  fb_text_close(&c.r);
  if (!rc)
    rc = reduced_build(&nodes, &k, m.one_triangle ? &m : NULL, out, err);
  free(c.node);
  free(c.dofs);
  free(c.row_node);
  free(c.row_comp);
  reduced_list_free(&k);
  reduced_list_free(&m);
  reduced_nodes_free(&nodes);
  return rc;
}
