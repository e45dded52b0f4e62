/* SPDX-License-Identifier: BSD-3-Clause */
/* Reduced structures (flexbond/reduced.h): the object, its nodes file,
 * and the building of K and M from the entries a reader found. The checks
 * are in reduced_check.c, the file formats in reduced_dmig.c and
 * reduced_ccx.c. */
#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/textfile.h"
#include "core/util.h"
#include "fem/reduced_internal.h"
#include "fem/reduced_struct.h"

void reduced_nodes_free(reduced_nodes *nodes)
{
  free(nodes->id);
  free(nodes->xyz);
  free(nodes->comps);
  free(nodes->line);
  free(nodes->sorted);
  *nodes = (reduced_nodes){0};
}

void reduced_list_free(reduced_list *l)
{
  free(l->e);
  l->e = NULL;
  l->n = l->cap = 0;
}

size_t reduced_list_cap(const reduced_nodes *nodes)
{
  const size_t d = 6 * nodes->n < FB_REDUCED_MAX_DOFS ? 6 * nodes->n : FB_REDUCED_MAX_DOFS;
  return d * d;
}

int reduced_list_push(reduced_list *l, const reduced_entry *e, fb_err *err)
{
  if (l->max && l->n >= l->max)
    return fb_err_set(err, FB_EPARSE,
                      "%s:%zu: %s: more than the %zu entries a matrix over the interface "
                      "nodes' DOFs can have",
                      l->path, e->line, l->name, l->max);
  if (fb_grow((void **)&l->e, &l->cap, l->n, sizeof *l->e))
    return fb_err_set(err, FB_ENOMEM, "out of memory reading %s", l->path);
  l->e[l->n++] = *e;
  return FB_OK;
}

int reduced_digits(const char *text)
{
  int digits = 0, leading = 1;
  for (const char *p = text; *p && !strchr("eEdD", *p); ++p) {
    if (p != text && (*p == '+' || *p == '-'))
      break; /* Nastran's exponent without its letter: "1.5+6" */
    if (!isdigit((unsigned char)*p))
      continue;
    if (*p == '0' && leading)
      continue;
    leading = 0;
    ++digits;
  }
  return digits;
}

double reduced_precision(int digits)
{
  double p = 0.5;
  for (int d = 1; d < (digits < 4 ? 4 : digits); ++d)
    p /= 10.0;
  return p;
}

/* A component list such as "123456": each digit 1..6 at most once. */
static int parse_components(const char *tok, unsigned *comps)
{
  *comps = 0;
  if (!*tok)
    return 0;
  for (const char *p = tok; *p; ++p) {
    if (*p < '1' || *p > '6' || (*comps & (1u << (*p - '1'))))
      return 0;
    *comps |= 1u << (*p - '1');
  }
  return 1;
}

static int nodes_error(const fb_text_reader *r, const char *what, const char *tok)
{
  fb_err_set(r->err, FB_EPARSE, "%s:%zu: %s", r->path, r->line_no, what);
  if (tok)
    fb_err_set_excerpt(r->err, tok, strlen(tok));
  return FB_EPARSE;
}

/* Splits line at commas into at most max trimmed fields; their count. */
static size_t split_fields(char *line, char **field, size_t max)
{
  size_t n = 0;
  char *p = line;
  for (;;) {
    char *comma = strchr(p, ',');
    if (comma)
      *comma = '\0';
    while (*p == ' ' || *p == '\t')
      ++p;
    char *end = p + strlen(p);
    while (end > p && (end[-1] == ' ' || end[-1] == '\t'))
      *--end = '\0';
    if (n < max)
      field[n] = p;
    ++n;
    if (!comma)
      return n;
    p = comma + 1;
  }
}

static int parse_id(const char *tok, long *id)
{
  char *end;
  errno = 0;
  const long v = strtol(tok, &end, 10);
  if (errno || end == tok || *end || v <= 0)
    return 0;
  *id = v;
  return 1;
}

static int nodes_line(fb_text_reader *r, char *line, reduced_nodes *nodes, size_t *cap)
{
  char *f[5];
  const size_t nf = split_fields(line, f, 5);
  if (nf != 4 && nf != 5)
    return nodes_error(r, "expected 'id, x, y, z' or 'id, x, y, z, components'", NULL);
  long id;
  if (!parse_id(f[0], &id))
    return nodes_error(r, "node id: not an integer > 0", f[0]);
  double xyz[3];
  for (int k = 0; k < 3; ++k)
    if (fb_parse_decimal_field(f[1 + k], &xyz[k], r->err)) {
      fb_err_set_excerpt(r->err, f[1 + k], strlen(f[1 + k]));
      return fb_err_prefix(r->err, "%s:%zu: %c: ", r->path, r->line_no, "xyz"[k]);
    }
  unsigned comps = 0;
  if (nf == 5 && !parse_components(f[4], &comps))
    return nodes_error(r, "components: expected digits 1 to 6, each once (\"123456\")", f[4]);
  if (nodes->n == FB_REDUCED_MAX_DOFS)
    return nodes_error(r,
                       "more nodes than the 3000 DOFs a reduced structure may have "
                       "(docs/errors.md, \"Limits\")",
                       NULL);
  const size_t n = nodes->n;
  if (n == *cap) {
    const size_t nc = n ? 2 * n : 16;
    long *id2 = realloc(nodes->id, nc * sizeof *id2);
    if (id2)
      nodes->id = id2;
    unsigned *c2 = realloc(nodes->comps, nc * sizeof *c2);
    if (c2)
      nodes->comps = c2;
    size_t *l2 = realloc(nodes->line, nc * sizeof *l2);
    if (l2)
      nodes->line = l2;
    double *x2 = realloc(nodes->xyz, 3 * nc * sizeof *x2);
    if (x2)
      nodes->xyz = x2;
    if (!id2 || !c2 || !l2 || !x2)
      return fb_err_set(r->err, FB_ENOMEM, "out of memory reading %s", r->path);
    *cap = nc;
  }
  nodes->id[n] = id;
  nodes->comps[n] = comps;
  nodes->line[n] = r->line_no;
  memcpy(nodes->xyz + 3 * n, xyz, sizeof xyz);
  nodes->n = n + 1;
  return FB_OK;
}

static int node_key_cmp(const void *a, const void *b)
{
  const reduced_node_key *x = a, *y = b;
  return (x->id > y->id) - (x->id < y->id);
}

/* The ids sorted for lookup; an id given twice is an error at the later
 * line. */
static int sort_nodes(reduced_nodes *nodes, fb_err *err)
{
  nodes->sorted = malloc(nodes->n * sizeof *nodes->sorted);
  if (!nodes->sorted)
    return fb_err_set(err, FB_ENOMEM, "out of memory reading %s", nodes->path);
  for (size_t i = 0; i < nodes->n; ++i)
    nodes->sorted[i] = (reduced_node_key){nodes->id[i], i};
  qsort(nodes->sorted, nodes->n, sizeof *nodes->sorted, node_key_cmp);
  for (size_t i = 1; i < nodes->n; ++i)
    if (nodes->sorted[i].id == nodes->sorted[i - 1].id) {
      size_t a = nodes->sorted[i - 1].index, b = nodes->sorted[i].index;
      if (a > b) {
        const size_t t = a;
        a = b;
        b = t;
      }
      return fb_err_set(err, FB_EPARSE, "%s:%zu: node %ld given twice (first on line %zu)",
                        nodes->path, nodes->line[b], nodes->id[b], nodes->line[a]);
    }
  return FB_OK;
}

int reduced_nodes_read(const char *path, reduced_nodes *nodes, fb_err *err)
{
  *nodes = (reduced_nodes){0};
  nodes->path = path;
  fb_text_reader r;
  if (fb_text_open(&r, path, "nodes", err)) {
    fb_text_close(&r);
    return FB_EIO;
  }
  size_t cap = 0;
  int rc = FB_OK;
  for (;;) {
    char *line = NULL;
    rc = fb_text_next_data_line(&r, '#', &line);
    if (rc || !line)
      break;
    rc = nodes_line(&r, line, nodes, &cap);
    if (rc)
      break;
  }
  if (!rc && nodes->n == 0)
    rc = fb_err_set(err, FB_EPARSE, "%s:%zu: no node: expected lines 'id, x, y, z'", path,
                    r.line_no ? r.line_no : 1);
  if (!rc)
    rc = sort_nodes(nodes, err);
  fb_text_close(&r);
  if (rc) {
    reduced_nodes_free(nodes);
    nodes->path = path;
  }
  return rc;
}

int reduced_nodes_read_plain(const char *path, const char *format, reduced_nodes *nodes,
                             fb_err *err)
{
  int rc = reduced_nodes_read(path, nodes, err);
  for (size_t i = 0; !rc && i < nodes->n; ++i)
    if (nodes->comps[i]) {
      rc = fb_err_set(err, FB_EPARSE,
                      "%s:%zu: a %s matrix names its own components: the nodes file gives "
                      "'id, x, y, z' only",
                      path, nodes->line[i], format);
      reduced_nodes_free(nodes);
    }
  return rc;
}

long reduced_node_index(const reduced_nodes *nodes, long id)
{
  const reduced_node_key k = {id, 0};
  const reduced_node_key *hit =
      nodes->sorted ? bsearch(&k, nodes->sorted, nodes->n, sizeof k, node_key_cmp) : NULL;
  return hit ? (long)hit->index : -1;
}

void fb_reduced_free(fb_reduced **r)
{
  if (!r || !*r)
    return;
  fb_reduced *s = *r;
  reduced_nodes_free(&s->nodes);
  free(s->dof_node);
  free(s->dof_comp);
  fb_mat_free(&s->K);
  fb_mat_free(&s->M);
  for (int k = 0; k < 2; ++k) {
    free(s->where[k]);
    free(s->path[k]);
  }
  free(s);
  *r = NULL;
}

static int reduced_alloc(reduced_nodes *nodes, size_t ndof, fb_reduced **out, fb_err *err)
{
  fb_reduced *s = calloc(1, sizeof *s);
  if (s) {
    s->dof_node = calloc(ndof ? ndof : 1, sizeof *s->dof_node);
    s->dof_comp = calloc(ndof ? ndof : 1, sizeof *s->dof_comp);
  }
  if (!s || !s->dof_node || !s->dof_comp) {
    if (s) {
      free(s->dof_node);
      free(s->dof_comp);
    }
    free(s);
    return fb_err_set(err, FB_ENOMEM, "out of memory for a reduced structure");
  }
  s->nodes = *nodes;
  s->nodes.path = NULL; /* the caller's string: not kept */
  *nodes = (reduced_nodes){0};
  s->ndof = ndof;
  *out = s;
  return FB_OK;
}

int reduced_adopt(reduced_nodes *nodes, fb_mat *K, fb_mat *M, const char *k_path,
                  const char *m_path, double precision, fb_reduced **out, fb_err *err)
{
  size_t ndof = 0;
  for (size_t i = 0; i < nodes->n; ++i)
    ndof += (size_t)__builtin_popcount(nodes->comps[i] ? nodes->comps[i] : 077u);
  int rc = reduced_alloc(nodes, ndof, out, err);
  if (rc) {
    fb_mat_free(&K);
    fb_mat_free(&M);
    return rc;
  }
  fb_reduced *s = *out;
  size_t d = 0;
  for (size_t i = 0; i < s->nodes.n; ++i)
    for (int c = 1; c <= 6; ++c)
      if ((s->nodes.comps[i] ? s->nodes.comps[i] : 077u) & (1u << (c - 1))) {
        s->dof_node[d] = i;
        s->dof_comp[d++] = c;
      }
  s->K = K;
  s->M = M;
  s->precision[0] = s->precision[1] = precision;
  s->path[0] = fb_strdup(k_path);
  s->path[1] = m_path ? fb_strdup(m_path) : NULL;
  if (!s->path[0] || (m_path && !s->path[1])) {
    fb_reduced_free(out);
    return fb_err_set(err, FB_ENOMEM, "out of memory for a reduced structure");
  }
  return FB_OK;
}

/* Orders DOFs by node index, then component. */
typedef struct dof_key {
  size_t node;
  int comp;
} dof_key;

static int dof_key_cmp(const void *a, const void *b)
{
  const dof_key *x = a, *y = b;
  if (x->node != y->node)
    return x->node < y->node ? -1 : 1;
  return (x->comp > y->comp) - (x->comp < y->comp);
}

static long dof_find(const dof_key *keys, size_t n, size_t node, int comp)
{
  const dof_key k = {node, comp};
  const dof_key *hit = bsearch(&k, keys, n, sizeof k, dof_key_cmp);
  return hit ? (long)(hit - keys) : -1;
}

/* Every DOF the entries of l name, their nodes' indices checked. */
static int collect_dofs(const reduced_nodes *nodes, const reduced_list *l, dof_key **keys,
                        size_t *n, size_t *cap, fb_err *err)
{
  for (size_t e = 0; e < l->n; ++e) {
    for (int side = 0; side < 2; ++side) {
      const long id = side ? l->e[e].node_j : l->e[e].node_i;
      const int comp = side ? l->e[e].comp_j : l->e[e].comp_i;
      const long ni = reduced_node_index(nodes, id);
      if (ni < 0)
        return fb_err_set(err, FB_EMODEL,
                          "%s:%zu: %s: node %ld is not among the interface nodes of %s",
                          l->path, l->e[e].line, l->name, id, nodes->path);
      if (fb_grow((void **)keys, cap, *n, sizeof **keys))
        return fb_err_set(err, FB_ENOMEM, "out of memory reading %s", l->path);
      (*keys)[(*n)++] = (dof_key){(size_t)ni, comp};
    }
  }
  return FB_OK;
}

/* Where each stored entry was written, sorted by (i, j). */
static int where_cmp(const void *a, const void *b)
{
  const reduced_where *x = a, *y = b;
  if (x->i != y->i)
    return x->i < y->i ? -1 : 1;
  return (x->j > y->j) - (x->j < y->j);
}

/* The matrix of l over the DOFs keys; duplicates are errors at their
 * line. */
static int build_matrix(const reduced_list *l, const dof_key *keys, size_t ndof,
                        const reduced_nodes *nodes, fb_mat **out, reduced_where **where,
                        fb_err *err)
{
  const size_t cap = l->n ? l->n : 1;
  reduced_where *w = malloc(cap * sizeof *w);
  size_t *ri = malloc(2 * cap * sizeof *ri), *ci = malloc(2 * cap * sizeof *ci);
  double *v = malloc(2 * cap * sizeof *v);
  int rc = (!w || !ri || !ci || !v)
               ? fb_err_set(err, FB_ENOMEM, "out of memory reading %s", l->path)
               : FB_OK;
  size_t nt = 0;
  for (size_t e = 0; !rc && e < l->n; ++e) {
    const reduced_entry *x = &l->e[e];
    const size_t i =
        (size_t)dof_find(keys, ndof, (size_t)reduced_node_index(nodes, x->node_i), x->comp_i);
    const size_t j =
        (size_t)dof_find(keys, ndof, (size_t)reduced_node_index(nodes, x->node_j), x->comp_j);
    /* One triangle: the entry and its mirror are the same entry. */
    w[e] = l->one_triangle && i < j ? (reduced_where){j, i, x->line}
                                    : (reduced_where){i, j, x->line};
    ri[nt] = i;
    ci[nt] = j;
    v[nt++] = x->val;
    if (l->one_triangle && i != j) {
      ri[nt] = j;
      ci[nt] = i;
      v[nt++] = x->val;
    }
  }
  if (!rc) {
    qsort(w, l->n, sizeof *w, where_cmp);
    for (size_t e = 1; e < l->n && !rc; ++e)
      if (w[e].i == w[e - 1].i && w[e].j == w[e - 1].j) {
        const size_t first = w[e].line < w[e - 1].line ? w[e].line : w[e - 1].line;
        const size_t again = w[e].line < w[e - 1].line ? w[e - 1].line : w[e].line;
        rc =
            fb_err_set(err, FB_EMODEL,
                       "%s:%zu: %s: entry (node %ld component %d, node %ld "
                       "component %d) given again (first on line %zu)%s",
                       l->path, again, l->name, nodes->id[keys[w[e].i].node], keys[w[e].i].comp,
                       nodes->id[keys[w[e].j].node], keys[w[e].j].comp, first,
                       l->one_triangle ? ", or with its mirror in a symmetric matrix" : "");
      }
  }
  if (!rc)
    rc = fb_mat_new_triplets(ndof, ndof, nt, ri, ci, v, out, err);
  free(ri);
  free(ci);
  free(v);
  if (rc)
    free(w);
  else
    *where = w;
  return rc;
}

int reduced_build(reduced_nodes *nodes, reduced_list *k, reduced_list *m, fb_reduced **out,
                  fb_err *err)
{
  *out = NULL;
  dof_key *keys = NULL;
  size_t n = 0, cap = 0;
  int rc = collect_dofs(nodes, k, &keys, &n, &cap, err);
  if (!rc && m)
    rc = collect_dofs(nodes, m, &keys, &n, &cap, err);
  size_t ndof = 0;
  if (!rc && !keys) {
    rc = fb_err_set(err, FB_EMODEL, "%s: %s has no entry", k->path, k->name);
  } else if (!rc) {
    qsort(keys, n, sizeof *keys, dof_key_cmp);
    for (size_t i = 0; i < n; ++i)
      if (ndof == 0 || dof_key_cmp(&keys[i], &keys[ndof - 1]) != 0)
        keys[ndof++] = keys[i];
    if (ndof == 0)
      rc = fb_err_set(err, FB_EMODEL, "%s: %s has no entry", k->path, k->name);
    else if (ndof > FB_REDUCED_MAX_DOFS)
      rc = fb_err_set(err, FB_EMODEL,
                      "%s: %zu DOFs, more than the %zu a reduced structure may have "
                      "(docs/errors.md, \"Limits\")",
                      k->path, ndof, FB_REDUCED_MAX_DOFS);
  }
  fb_mat *K = NULL, *M = NULL;
  reduced_where *wk = NULL, *wm = NULL;
  if (!rc)
    rc = build_matrix(k, keys, ndof, nodes, &K, &wk, err);
  if (!rc && m)
    rc = build_matrix(m, keys, ndof, nodes, &M, &wm, err);
  if (!rc)
    rc = reduced_alloc(nodes, ndof, out, err);
  if (!rc) {
    fb_reduced *s = *out;
    for (size_t d = 0; d < ndof; ++d) {
      s->dof_node[d] = keys[d].node;
      s->dof_comp[d] = keys[d].comp;
    }
    s->K = K;
    s->M = M;
    K = M = NULL;
    s->where[0] = wk;
    s->where[1] = wm;
    s->nwhere[0] = k->n;
    s->nwhere[1] = m ? m->n : 0;
    wk = wm = NULL;
    s->precision[0] = k->precision;
    s->precision[1] = m ? m->precision : 0.0;
    s->path[0] = fb_strdup(k->path);
    s->path[1] = m ? fb_strdup(m->path) : NULL;
    if (!s->path[0] || (m && !s->path[1])) {
      fb_reduced_free(out);
      rc = fb_err_set(err, FB_ENOMEM, "out of memory for a reduced structure");
    }
  }
  fb_mat_free(&K);
  fb_mat_free(&M);
  free(wk);
  free(wm);
  free(keys);
  return rc;
}

int fb_reduced_read_mtx(const char *k_path, const char *m_path, const char *nodes_path,
                        fb_reduced **out, fb_err *err)
{
  if (!out || !k_path || !nodes_path)
    return fb_err_set(err, FB_EINVAL, "reduced structure: a path or the output is NULL");
  *out = NULL;
  reduced_nodes nodes;
  int rc = reduced_nodes_read(nodes_path, &nodes, err);
  if (rc)
    return rc;
  size_t ndof = 0;
  for (size_t i = 0; i < nodes.n; ++i)
    ndof += (size_t)__builtin_popcount(nodes.comps[i] ? nodes.comps[i] : 077u);
  if (ndof > FB_REDUCED_MAX_DOFS) {
    reduced_nodes_free(&nodes);
    return fb_err_set(err, FB_EMODEL,
                      "%s: %zu DOFs, more than the %zu a reduced structure may have "
                      "(docs/errors.md, \"Limits\")",
                      nodes_path, ndof, FB_REDUCED_MAX_DOFS);
  }
  fb_mat *K = NULL, *M = NULL;
  rc = fb_mat_read_mtx_dims(k_path, ndof, ndof, &K, err);
  if (!rc && m_path)
    rc = fb_mat_read_mtx_dims(m_path, ndof, ndof, &M, err);
  if (rc) {
    fb_mat_free(&K);
    reduced_nodes_free(&nodes);
    return rc;
  }
  /* A Matrix Market file's writer is not known: printf's %g, the fewest
   * digits a common one writes, gives 6. */
  return reduced_adopt(&nodes, K, M, k_path, m_path, reduced_precision(6), out, err);
}

size_t fb_reduced_ndofs(const fb_reduced *r)
{
  return r->ndof;
}

long fb_reduced_dof_node(const fb_reduced *r, size_t i)
{
  return i < r->ndof ? r->nodes.id[r->dof_node[i]] : -1;
}

int fb_reduced_dof_component(const fb_reduced *r, size_t i)
{
  return i < r->ndof ? r->dof_comp[i] : 0;
}

long fb_reduced_find_dof(const fb_reduced *r, long node, int component)
{
  for (size_t i = 0; i < r->ndof; ++i)
    if (r->nodes.id[r->dof_node[i]] == node && r->dof_comp[i] == component)
      return (long)i;
  return -1;
}

size_t fb_reduced_nnodes(const fb_reduced *r)
{
  return r->nodes.n;
}

long fb_reduced_node_id(const fb_reduced *r, size_t node)
{
  return node < r->nodes.n ? r->nodes.id[node] : -1;
}

const double *fb_reduced_node_xyz(const fb_reduced *r, size_t node)
{
  return node < r->nodes.n ? r->nodes.xyz + 3 * node : NULL;
}

const fb_mat *fb_reduced_stiffness(const fb_reduced *r)
{
  return r->K;
}

const fb_mat *fb_reduced_mass(const fb_reduced *r)
{
  return r->M;
}
