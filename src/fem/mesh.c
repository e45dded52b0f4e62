/* SPDX-License-Identifier: BSD-3-Clause */
/* Shell meshes (see flexbond/fem.h): nodes, elements, node and element
 * sets, and shell sections.
 *
 * Nodes and elements live in parallel arrays in insertion order. User ids
 * are found through open-addressing hash tables (linear probing, load
 * factor at most 1/2; Knuth, TAOCP vol. 3, section 6.4, algorithm L) whose
 * slots hold index + 1 into the id arrays, so a lookup costs O(1) on
 * average for meshes of 1e5 nodes and more. Node and element sets are
 * kept free of duplicates, in the order their members were first added;
 * the same kind of table finds a set by name and a member in its set, so
 * adding n members costs O(n) whatever the set's or the mesh's size (a
 * reader may add a set's members a few at a time).
 * A section is a copy of its element set's name and properties; each
 * element records the index of the last section given to it, or -1. */
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/util.h"
#include "fem/mesh_internal.h"
#include "fem/shell_internal.h"
#include "fem/vec3.h"

/* Hash table from user id to index; slot value 0 is empty, k is index
 * k - 1 of the id array the table was built over. */
typedef struct id_map {
  size_t *slots;
  size_t cap; /* power of two, or 0 */
} id_map;

/* A named set of node or element indices; members maps a member to its
 * position in items (slot value k: items[k - 1]). */
typedef struct mesh_set {
  char *name;
  size_t *items;
  size_t n;
  size_t cap;
  id_map members;
} mesh_set;

/* The sets of one kind; names maps a name, case-insensitively, to its set
 * (slot value k: sets[k - 1]). */
typedef struct set_list {
  mesh_set *sets;
  size_t n;
  size_t cap;
  id_map names;
} set_list;

typedef struct mesh_section {
  char *elset;
  fb_shell_props props;
} mesh_section;

/* A point mass on one node's translations. */
typedef struct mesh_point_mass {
  long id;
  size_t node;
  double mass;
} mesh_point_mass;

struct fb_mesh {
  double *xyz; /* 3 per node */
  long *node_ids;
  size_t nnodes;
  size_t node_cap;
  id_map node_map;

  fb_elem_type *elem_types;
  long *elem_ids;
  size_t *elem_nodes; /* 4 per element; the 4th is unused for triangles */
  size_t nelems;
  size_t elem_cap;
  size_t ntri; /* elements of each type */
  size_t nquad;
  id_map elem_map;
  long *elem_section; /* per element (NULL until the first section) */
  double *elem_nsm;   /* per element, kg/m^2 added (NULL until the first) */

  mesh_point_mass *pmass; /* point masses (MASS elements), in the order added */
  size_t npmass, pmass_cap;

  set_list nsets;
  set_list elsets;
  mesh_section *sections;
  size_t nsections;
  size_t section_cap;

  /* The superelement (fb_mesh_set_superelement): its nodes and its
   * matrices over their six DOFs each, dense column-major. */
  size_t *super_nodes;
  size_t nsuper;
  double *super_k, *super_m;
};

const char *fb_mesh_type_name(fb_elem_type type)
{
  switch (type) {
  case FB_ELEM_TRI3: return "S3";
  case FB_ELEM_QUAD4: return "S4";
  }
  return "?";
}

size_t fb_mesh_type_nodes(fb_elem_type type)
{
  switch (type) {
  case FB_ELEM_TRI3: return 3;
  case FB_ELEM_QUAD4: return 4;
  }
  return 0;
}

int fb_mesh_name_ok(const char *name)
{
  if (!name || !(isalpha((unsigned char)name[0]) || name[0] == '_'))
    return 0;
  size_t len = 0;
  for (const char *c = name; *c; ++c, ++len) {
    if (!isalnum((unsigned char)*c) && !strchr("_.-", *c))
      return 0;
  }
  return len <= FB_MESH_NAME_MAX;
}

/* ---- Id tables. */

/* Home slot of key in a table of cap (a power of two) slots: Fibonacci
 * hashing (Knuth, TAOCP vol. 3, section 6.4, multiplicative method). */
static size_t slot_home(uint64_t key, size_t cap)
{
  uint64_t h = key * UINT64_C(0x9E3779B97F4A7C15);
  h ^= h >> 32;
  return (size_t)h & (cap - 1);
}

/* Index of id among ids[] through map, or -1. */
static long id_map_find(const id_map *map, const long *ids, long id)
{
  if (map->cap == 0)
    return -1;
  for (size_t s = slot_home((uint64_t)id, map->cap);; s = (s + 1) & (map->cap - 1)) {
    const size_t v = map->slots[s];
    if (v == 0)
      return -1;
    if (ids[v - 1] == id)
      return (long)(v - 1);
  }
}

/* The first empty slot from key's home on (the table has one: its load is
 * at most 1/2). */
static size_t *free_slot(const id_map *map, uint64_t key)
{
  size_t s = slot_home(key, map->cap);
  while (map->slots[s] != 0)
    s = (s + 1) & (map->cap - 1);
  return &map->slots[s];
}

/* Makes room for count + 1 entries (load at most 1/2). A table that grows
 * is empty (*grown = 1): the caller puts its count entries back. */
static int map_grow(id_map *map, size_t count, int *grown)
{
  *grown = 0;
  if (2 * (count + 1) <= map->cap)
    return FB_OK;
  size_t cap = map->cap ? map->cap : 16;
  while (2 * (count + 1) > cap) {
    if (cap > SIZE_MAX / 2 / sizeof(size_t))
      return FB_ENOMEM;
    cap *= 2;
  }
  size_t *slots = calloc(cap, sizeof *slots);
  if (!slots)
    return FB_ENOMEM;
  free(map->slots);
  map->slots = slots;
  map->cap = cap;
  *grown = 1;
  return FB_OK;
}

static void id_map_put(id_map *map, const long *ids, size_t index)
{
  *free_slot(map, (uint64_t)ids[index]) = index + 1;
}

/* Makes room for count + 1 entries, rebuilding the table over
 * ids[0 .. count) when it grows. */
static int id_map_reserve(id_map *map, const long *ids, size_t count)
{
  int grown = 0;
  const int rc = map_grow(map, count, &grown);
  for (size_t i = 0; grown && i < count; ++i)
    id_map_put(map, ids, i);
  return rc;
}

static int id_map_copy(const id_map *src, id_map *dst)
{
  dst->cap = src->cap;
  dst->slots = NULL;
  if (src->cap == 0)
    return FB_OK;
  dst->slots = malloc(src->cap * sizeof *dst->slots);
  if (!dst->slots)
    return FB_ENOMEM;
  memcpy(dst->slots, src->slots, src->cap * sizeof *dst->slots);
  return FB_OK;
}

/* ---- Life cycle. */

int fb_mesh_new(fb_mesh **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_new: out is NULL");
  *out = calloc(1, sizeof **out);
  if (!*out)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating a mesh");
  return FB_OK;
}

static void set_list_free(set_list *l)
{
  for (size_t i = 0; i < l->n; ++i) {
    free(l->sets[i].name);
    free(l->sets[i].items);
    free(l->sets[i].members.slots);
  }
  free(l->sets);
  free(l->names.slots);
}

void fb_mesh_free(fb_mesh **m)
{
  if (!m || !*m)
    return;
  fb_mesh *mesh = *m;
  free(mesh->xyz);
  free(mesh->node_ids);
  free(mesh->node_map.slots);
  free(mesh->elem_types);
  free(mesh->elem_ids);
  free(mesh->elem_nodes);
  free(mesh->elem_map.slots);
  free(mesh->elem_section);
  free(mesh->elem_nsm);
  free(mesh->pmass);
  set_list_free(&mesh->nsets);
  set_list_free(&mesh->elsets);
  for (size_t i = 0; i < mesh->nsections; ++i)
    free(mesh->sections[i].elset);
  free(mesh->sections);
  free(mesh->super_nodes);
  free(mesh->super_k);
  free(mesh->super_m);
  free(mesh);
  *m = NULL;
}

/* Fresh copy of n bytes of src in *dst (NULL stays NULL). */
static int copy_bytes(void **dst, const void *src, size_t n)
{
  *dst = NULL;
  if (!src || n == 0)
    return FB_OK;
  *dst = malloc(n);
  if (!*dst)
    return FB_ENOMEM;
  memcpy(*dst, src, n);
  return FB_OK;
}

static int copy_nodes(const fb_mesh *m, fb_mesh *c)
{
  c->nnodes = c->node_cap = m->nnodes;
  int rc = copy_bytes((void **)&c->xyz, m->xyz, 3 * m->nnodes * sizeof *m->xyz);
  if (!rc)
    rc = copy_bytes((void **)&c->node_ids, m->node_ids, m->nnodes * sizeof *m->node_ids);
  return rc ? rc : id_map_copy(&m->node_map, &c->node_map);
}

static int copy_elements(const fb_mesh *m, fb_mesh *c)
{
  c->nelems = c->elem_cap = m->nelems;
  c->ntri = m->ntri;
  c->nquad = m->nquad;
  int rc =
      copy_bytes((void **)&c->elem_types, m->elem_types, m->nelems * sizeof *m->elem_types);
  if (!rc)
    rc = copy_bytes((void **)&c->elem_ids, m->elem_ids, m->nelems * sizeof *m->elem_ids);
  if (!rc)
    rc = copy_bytes((void **)&c->elem_nodes, m->elem_nodes,
                    4 * m->nelems * sizeof *m->elem_nodes);
  if (!rc && m->elem_section)
    rc = copy_bytes((void **)&c->elem_section, m->elem_section,
                    m->nelems * sizeof *m->elem_section);
  if (!rc && m->elem_nsm)
    rc = copy_bytes((void **)&c->elem_nsm, m->elem_nsm, m->nelems * sizeof *m->elem_nsm);
  if (!rc)
    rc = copy_bytes((void **)&c->pmass, m->pmass, m->npmass * sizeof *m->pmass);
  if (!rc)
    c->npmass = c->pmass_cap = m->npmass;
  return rc ? rc : id_map_copy(&m->elem_map, &c->elem_map);
}

static int copy_sets(const set_list *l, set_list *c)
{
  if (l->n == 0)
    return FB_OK;
  c->sets = calloc(l->n, sizeof *c->sets);
  if (!c->sets || id_map_copy(&l->names, &c->names) != FB_OK)
    return FB_ENOMEM;
  c->cap = l->n;
  for (size_t i = 0; i < l->n; ++i) {
    const mesh_set *s = &l->sets[i];
    mesh_set *d = &c->sets[i];
    ++c->n; /* counted first so that a failure below frees it */
    d->name = fb_strdup(s->name);
    if (!d->name ||
        copy_bytes((void **)&d->items, s->items, s->n * sizeof *s->items) != FB_OK ||
        id_map_copy(&s->members, &d->members) != FB_OK)
      return FB_ENOMEM;
    d->n = d->cap = s->n;
  }
  return FB_OK;
}

static int copy_sections(const fb_mesh *m, fb_mesh *c)
{
  if (m->nsections == 0)
    return FB_OK;
  c->sections = calloc(m->nsections, sizeof *c->sections);
  if (!c->sections)
    return FB_ENOMEM;
  c->section_cap = m->nsections;
  for (size_t i = 0; i < m->nsections; ++i) {
    ++c->nsections; /* counted first so that a failure below frees it */
    c->sections[i].props = m->sections[i].props;
    c->sections[i].elset = fb_strdup(m->sections[i].elset);
    if (!c->sections[i].elset)
      return FB_ENOMEM;
  }
  return FB_OK;
}

int fb_mesh_clone(const fb_mesh *m, fb_mesh **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_clone: out is NULL");
  *out = NULL;
  if (!m)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_clone: mesh is NULL");
  fb_mesh *c = calloc(1, sizeof *c);
  int rc = c ? copy_nodes(m, c) : FB_ENOMEM;
  if (!rc)
    rc = copy_elements(m, c);
  if (!rc)
    rc = copy_sets(&m->nsets, &c->nsets);
  if (!rc)
    rc = copy_sets(&m->elsets, &c->elsets);
  if (!rc)
    rc = copy_sections(m, c);
  if (!rc && m->nsuper)
    rc = fb_mesh_set_superelement(c, m->nsuper, m->super_nodes, m->super_k, m->super_m, NULL);
  if (rc) {
    fb_mesh_free(&c);
    return fb_err_set(err, FB_ENOMEM, "out of memory copying a mesh");
  }
  *out = c;
  return FB_OK;
}

/* ---- Building. */

int fb_mesh_set_superelement(fb_mesh *m, size_t n, const size_t *nodes, const double *k,
                             const double *mass, fb_err *err)
{
  for (size_t i = 0; i < n; ++i)
    if (nodes[i] >= m->nnodes)
      return fb_err_set(err, FB_EINVAL, "superelement node index %zu: the mesh has %zu nodes",
                        nodes[i], m->nnodes);
  const size_t d = 6 * n;
  size_t *nd = malloc((n ? n : 1) * sizeof *nd);
  double *kk = malloc((d ? d * d : 1) * sizeof *kk);
  double *mm = calloc(d ? d * d : 1, sizeof *mm);
  if (!nd || !kk || !mm) {
    free(nd);
    free(kk);
    free(mm);
    return fb_err_set(err, FB_ENOMEM, "out of memory for a superelement of %zu nodes", n);
  }
  memcpy(nd, nodes, n * sizeof *nd);
  memcpy(kk, k, d * d * sizeof *kk);
  if (mass)
    memcpy(mm, mass, d * d * sizeof *mm);
  free(m->super_nodes);
  free(m->super_k);
  free(m->super_m);
  m->super_nodes = nd;
  m->super_k = kk;
  m->super_m = mm;
  m->nsuper = n;
  return FB_OK;
}

size_t fb_mesh_superelement(const fb_mesh *m, const size_t **nodes, const double **k,
                            const double **mass)
{
  if (nodes)
    *nodes = m->super_nodes;
  if (k)
    *k = m->super_k;
  if (mass)
    *mass = m->super_m;
  return m->nsuper;
}

static int grow_nodes(fb_mesh *m)
{
  if (m->nnodes < m->node_cap)
    return FB_OK;
  size_t cap = m->node_cap;
  int rc = fb_grow((void **)&m->node_ids, &cap, m->nnodes, sizeof *m->node_ids);
  if (!rc) {
    double *xyz = realloc(m->xyz, 3 * cap * sizeof *xyz);
    if (!xyz)
      return FB_ENOMEM; /* node_ids keeps its larger size: harmless */
    m->xyz = xyz;
    m->node_cap = cap;
  }
  return rc;
}

/* Adds a node; index may be NULL. Coordinates must be finite. */
int fb_mesh_add_node(fb_mesh *m, long id, double x, double y, double z, size_t *index,
                     fb_err *err)
{
  if (!m)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_add_node: mesh is NULL");
  if (id <= 0)
    return fb_err_set(err, FB_EINVAL, "node id %ld is not positive", id);
  if (!isfinite(x) || !isfinite(y) || !isfinite(z))
    return fb_err_set(err, FB_EINVAL, "node %ld: coordinates (%g, %g, %g) are not finite", id,
                      x, y, z);
  if (id_map_find(&m->node_map, m->node_ids, id) >= 0)
    return fb_err_set(err, FB_EINVAL, "node id %ld is defined twice", id);
  if (grow_nodes(m) || id_map_reserve(&m->node_map, m->node_ids, m->nnodes))
    return fb_err_set(err, FB_ENOMEM, "out of memory adding node %ld", id);
  const size_t k = m->nnodes;
  m->node_ids[k] = id;
  m->xyz[3 * k] = x;
  m->xyz[3 * k + 1] = y;
  m->xyz[3 * k + 2] = z;
  id_map_put(&m->node_map, m->node_ids, k);
  ++m->nnodes;
  if (index)
    *index = k;
  return FB_OK;
}

static int grow_elements(fb_mesh *m)
{
  if (m->nelems < m->elem_cap)
    return FB_OK;
  size_t cap = m->elem_cap;
  if (fb_grow((void **)&m->elem_ids, &cap, m->nelems, sizeof *m->elem_ids))
    return FB_ENOMEM;
  fb_elem_type *types = realloc(m->elem_types, cap * sizeof *types);
  if (types)
    m->elem_types = types;
  size_t *nodes = realloc(m->elem_nodes, 4 * cap * sizeof *nodes);
  if (nodes)
    m->elem_nodes = nodes;
  if (!types || !nodes)
    return FB_ENOMEM;
  if (m->elem_section) {
    long *section = realloc(m->elem_section, cap * sizeof *section);
    if (!section)
      return FB_ENOMEM;
    m->elem_section = section;
  }
  if (m->elem_nsm) {
    double *nsm = realloc(m->elem_nsm, cap * sizeof *nsm);
    if (!nsm)
      return FB_ENOMEM;
    m->elem_nsm = nsm;
  }
  m->elem_cap = cap;
  return FB_OK;
}

/* Checks an element's arguments (repeated nodes are allowed here:
 * fb_mesh_check reports them). */
static int check_element_args(const fb_mesh *m, long id, fb_elem_type type, const size_t *nodes,
                              fb_err *err)
{
  const size_t nn = fb_mesh_type_nodes(type);
  if (nn == 0)
    return fb_err_set(err, FB_EINVAL, "element %ld: invalid element type %d", id, (int)type);
  if (id <= 0)
    return fb_err_set(err, FB_EINVAL, "element id %ld is not positive", id);
  if (!nodes)
    return fb_err_set(err, FB_EINVAL, "element %ld: node list is NULL", id);
  for (size_t k = 0; k < nn; ++k) {
    if (nodes[k] >= m->nnodes)
      return fb_err_set(err, FB_EINVAL,
                        "element %ld: node index %zu out of range (the mesh has %zu nodes)", id,
                        nodes[k], m->nnodes);
  }
  if (id_map_find(&m->elem_map, m->elem_ids, id) >= 0 || fb_mesh_find_point_mass_id(m, id) >= 0)
    return fb_err_set(err, FB_EINVAL, "element id %ld is defined twice", id);
  return FB_OK;
}

int fb_mesh_add_element(fb_mesh *m, long id, fb_elem_type type, const size_t *nodes,
                        fb_err *err)
{
  if (!m)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_add_element: mesh is NULL");
  int rc = check_element_args(m, id, type, nodes, err);
  if (rc)
    return rc;
  if (grow_elements(m) || id_map_reserve(&m->elem_map, m->elem_ids, m->nelems))
    return fb_err_set(err, FB_ENOMEM, "out of memory adding element %ld", id);
  const size_t e = m->nelems;
  const size_t nn = fb_mesh_type_nodes(type);
  m->elem_ids[e] = id;
  m->elem_types[e] = type;
  for (size_t k = 0; k < 4; ++k)
    m->elem_nodes[4 * e + k] = k < nn ? nodes[k] : 0;
  id_map_put(&m->elem_map, m->elem_ids, e);
  if (m->elem_section)
    m->elem_section[e] = -1;
  if (m->elem_nsm)
    m->elem_nsm[e] = 0.0;
  ++m->nelems;
  if (type == FB_ELEM_TRI3)
    ++m->ntri;
  else
    ++m->nquad;
  return FB_OK;
}

/* FNV-1a (G. Fowler, L. C. Noll & K.-P. Vo) of the upper case, so that
 * names equal but for case have one key. */
uint64_t fb_mesh_name_key(const char *name)
{
  uint64_t h = UINT64_C(14695981039346656037);
  for (const char *c = name; *c; ++c) {
    h ^= (unsigned char)toupper((unsigned char)*c);
    h *= UINT64_C(1099511628211);
  }
  return h;
}

/* Index of the set called name (case-insensitive), or -1. */
static long find_set(const set_list *l, const char *name)
{
  const id_map *map = &l->names;
  if (map->cap == 0)
    return -1;
  for (size_t s = slot_home(fb_mesh_name_key(name), map->cap);; s = (s + 1) & (map->cap - 1)) {
    const size_t v = map->slots[s];
    if (v == 0)
      return -1;
    if (strcasecmp(l->sets[v - 1].name, name) == 0)
      return (long)(v - 1);
  }
}

/* A new empty set called name, at the end of l. */
static int new_set(set_list *l, const char *name, mesh_set **out)
{
  int grown = 0;
  if (fb_grow((void **)&l->sets, &l->cap, l->n, sizeof *l->sets) ||
      map_grow(&l->names, l->n, &grown))
    return FB_ENOMEM;
  for (size_t i = 0; grown && i < l->n; ++i)
    *free_slot(&l->names, fb_mesh_name_key(l->sets[i].name)) = i + 1;
  mesh_set *s = &l->sets[l->n];
  memset(s, 0, sizeof *s);
  s->name = fb_strdup(name);
  if (!s->name)
    return FB_ENOMEM;
  *free_slot(&l->names, fb_mesh_name_key(name)) = ++l->n;
  *out = s;
  return FB_OK;
}

static int is_member(const mesh_set *s, size_t index)
{
  const id_map *map = &s->members;
  if (map->cap == 0)
    return 0;
  for (size_t k = slot_home(index, map->cap);; k = (k + 1) & (map->cap - 1)) {
    const size_t v = map->slots[k];
    if (v == 0)
      return 0;
    if (s->items[v - 1] == index)
      return 1;
  }
}

/* Appends index, not a member yet, to s. */
static int append_member(mesh_set *s, size_t index)
{
  int grown = 0;
  if (fb_grow((void **)&s->items, &s->cap, s->n, sizeof *s->items) ||
      map_grow(&s->members, s->n, &grown))
    return FB_ENOMEM;
  for (size_t i = 0; grown && i < s->n; ++i)
    *free_slot(&s->members, s->items[i]) = i + 1;
  s->items[s->n] = index;
  *free_slot(&s->members, index) = ++s->n;
  return FB_OK;
}

/* Appends the members of list not yet in s: O(n) on average through the
 * member table, however large s and the mesh are, so that a reader can
 * add a set's members as it meets them instead of collecting them first. */
static int extend_set(mesh_set *s, size_t n, const size_t *list)
{
  int rc = FB_OK;
  for (size_t i = 0; i < n && !rc; ++i)
    if (!is_member(s, list[i]))
      rc = append_member(s, list[i]);
  return rc;
}

/* Creates the set if needed (keeping the first spelling of its name) and
 * adds the members not already in it; n may be 0 (items then may be
 * NULL), which creates an empty set. what is "node" or "element". */
static int add_to_set(set_list *l, const char *what, size_t universe, const char *name,
                      size_t n, const size_t *items, fb_err *err)
{
  if (!fb_mesh_name_ok(name)) {
    /* The name may be a file's text: in the excerpt, not the message. */
    fb_err_set(err, FB_EINVAL,
               "%s set name is invalid (1 to %d characters from A-Z a-z 0-9 _ . -, starting "
               "with a letter or _)",
               what, FB_MESH_NAME_MAX);
    fb_err_set_excerpt(err, name ? name : "(null)", name ? strlen(name) : 6);
    return FB_EINVAL;
  }
  if (n > 0 && !items)
    return fb_err_set(err, FB_EINVAL, "%s set '%s': the list is NULL", what, name);
  for (size_t i = 0; i < n; ++i) {
    if (items[i] >= universe)
      return fb_err_set(err, FB_EINVAL,
                        "%s set '%s': %s index %zu out of range (the mesh has %zu)", what, name,
                        what, items[i], universe);
  }
  const long found = find_set(l, name);
  mesh_set *s = found >= 0 ? &l->sets[found] : NULL;
  if ((!s && new_set(l, name, &s)) || extend_set(s, n, items))
    return fb_err_set(err, FB_ENOMEM, "out of memory adding to %s set '%s'", what, name);
  return FB_OK;
}

int fb_mesh_add_nset(fb_mesh *m, const char *name, size_t n, const size_t *nodes, fb_err *err)
{
  if (!m)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_add_nset: mesh is NULL");
  return add_to_set(&m->nsets, "node", m->nnodes, name, n, nodes, err);
}

int fb_mesh_add_elset(fb_mesh *m, const char *name, size_t n, const size_t *elements,
                      fb_err *err)
{
  if (!m)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_add_elset: mesh is NULL");
  return add_to_set(&m->elsets, "element", m->nelems, name, n, elements, err);
}

/* The section's copy of p at the end of m->sections. */
static int push_section(fb_mesh *m, const char *elset, const fb_shell_props *p)
{
  if (!m->elem_section) {
    m->elem_section = malloc((m->elem_cap ? m->elem_cap : 1) * sizeof *m->elem_section);
    if (!m->elem_section)
      return FB_ENOMEM;
    for (size_t e = 0; e < m->nelems; ++e)
      m->elem_section[e] = -1;
  }
  if (fb_grow((void **)&m->sections, &m->section_cap, m->nsections, sizeof *m->sections))
    return FB_ENOMEM;
  mesh_section *sec = &m->sections[m->nsections];
  sec->elset = fb_strdup(elset);
  if (!sec->elset)
    return FB_ENOMEM;
  sec->props = *p;
  ++m->nsections;
  return FB_OK;
}

int fb_mesh_set_section(fb_mesh *m, const char *elset, const fb_shell_props *p, fb_err *err)
{
  if (!m || !elset || !p)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_set_section: NULL argument");
  const long i = find_set(&m->elsets, elset);
  if (i < 0)
    return fb_err_set(err, FB_EINVAL, "element set '%s' is not defined", elset);
  int rc = fb_shell_check_props(p, err);
  if (rc) {
    fb_err_prefix(err, "section of element set '%s': ", elset);
    return rc;
  }
  if (push_section(m, m->elsets.sets[i].name, p))
    return fb_err_set(err, FB_ENOMEM, "out of memory adding a section");
  const mesh_set *s = &m->elsets.sets[i];
  for (size_t k = 0; k < s->n; ++k)
    m->elem_section[s->items[k]] = (long)m->nsections - 1;
  return FB_OK;
}

/* ---- Accessors. Out-of-range arguments give NULL, 0 or -1 as noted. */

size_t fb_mesh_nnodes(const fb_mesh *m)
{
  return m ? m->nnodes : 0;
}

size_t fb_mesh_nelements(const fb_mesh *m)
{
  return m ? m->nelems : 0;
}

size_t fb_mesh_count(const fb_mesh *m, fb_elem_type type)
{
  if (!m)
    return 0;
  switch (type) {
  case FB_ELEM_TRI3: return m->ntri;
  case FB_ELEM_QUAD4: return m->nquad;
  }
  return 0;
}

/* x, y, z of a node, or NULL if node is out of range. */
const double *fb_mesh_node_xyz(const fb_mesh *m, size_t node)
{
  return m && node < m->nnodes ? &m->xyz[3 * node] : NULL;
}

/* User id of a node, or -1 if node is out of range. */
long fb_mesh_node_id(const fb_mesh *m, size_t node)
{
  return m && node < m->nnodes ? m->node_ids[node] : -1;
}

long fb_mesh_find_node_id(const fb_mesh *m, long id)
{
  return m ? id_map_find(&m->node_map, m->node_ids, id) : -1;
}

void fb_mesh_translate(fb_mesh *m, double dx, double dy, double dz)
{
  for (size_t i = 0; m && i < m->nnodes; ++i) {
    m->xyz[3 * i] += dx;
    m->xyz[3 * i + 1] += dy;
    m->xyz[3 * i + 2] += dz;
  }
}

long fb_mesh_find_element_id(const fb_mesh *m, long id)
{
  return m ? id_map_find(&m->elem_map, m->elem_ids, id) : -1;
}

/* The nearest node within tol (lowest index on a tie), by a linear scan:
 * the function serves to locate a few attachment points, and one O(n)
 * scan costs well under a millisecond at 1e5 nodes, so a spatial index
 * would not pay for its upkeep. -1 also if tol is negative or NaN. */
long fb_mesh_find_node_at(const fb_mesh *m, double x, double y, double z, double tol)
{
  if (!m || !(tol >= 0.0))
    return -1;
  long best = -1;
  double best_d2 = tol * tol;
  for (size_t i = 0; i < m->nnodes; ++i) {
    const double *p = &m->xyz[3 * i];
    const double dx = p[0] - x, dy = p[1] - y, dz = p[2] - z;
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 <= best_d2 && (best < 0 || d2 < best_d2)) {
      best = (long)i;
      best_d2 = d2;
    }
  }
  return best;
}

/* Type of element e, or 0 (no type) if e is out of range. */
fb_elem_type fb_mesh_element_type(const fb_mesh *m, size_t e)
{
  return m && e < m->nelems ? m->elem_types[e] : (fb_elem_type)0;
}

/* User id of element e, or -1 if e is out of range. */
long fb_mesh_element_id(const fb_mesh *m, size_t e)
{
  return m && e < m->nelems ? m->elem_ids[e] : -1;
}

/* Node indices of element e, or NULL if e is out of range. */
const size_t *fb_mesh_element_nodes(const fb_mesh *m, size_t e)
{
  return m && e < m->nelems ? &m->elem_nodes[4 * e] : NULL;
}

void fb_mesh_element_centroid(const fb_mesh *m, size_t e, double *c)
{
  const size_t *nd = fb_mesh_element_nodes(m, e);
  const size_t nn = fb_mesh_element_type(m, e) == FB_ELEM_QUAD4 ? 4 : 3;
  c[0] = c[1] = c[2] = 0.0;
  for (size_t i = 0; i < nn; ++i)
    for (int k = 0; k < 3; ++k)
      c[k] += fb_mesh_node_xyz(m, nd[i])[k] / (double)nn;
}

/* Half of (b - a) x (c - a) for a triangle; for a quadrilateral half
 * the cross product of its diagonals, (c - a) x (d - b), which is its
 * area vector when it is plane and the projected area vector of a warped
 * one. */
void fb_mesh_element_area_vector(const fb_mesh *m, size_t e, double *v)
{
  const size_t *nd = fb_mesh_element_nodes(m, e);
  const double *a = fb_mesh_node_xyz(m, nd[0]);
  const double *b = fb_mesh_node_xyz(m, nd[1]);
  const double *c = fb_mesh_node_xyz(m, nd[2]);
  double u[3], w[3];
  if (fb_mesh_element_type(m, e) == FB_ELEM_TRI3) {
    fb_sub3(b, a, u);
    fb_sub3(c, a, w);
  } else {
    fb_sub3(c, a, u);
    fb_sub3(fb_mesh_node_xyz(m, nd[3]), b, w);
  }
  fb_cross3(u, w, v);
  for (int k = 0; k < 3; ++k)
    v[k] *= 0.5;
}

size_t fb_mesh_nnsets(const fb_mesh *m)
{
  return m ? m->nsets.n : 0;
}

/* Name of node set i as first given, or NULL if i is out of range. */
const char *fb_mesh_nset_name(const fb_mesh *m, size_t i)
{
  return m && i < m->nsets.n ? m->nsets.sets[i].name : NULL;
}

static int get_set(const set_list *l, const char *name, const size_t **items, size_t *n)
{
  const long i = name ? find_set(l, name) : -1;
  if (i < 0)
    return 0;
  if (items)
    *items = l->sets[i].items;
  if (n)
    *n = l->sets[i].n;
  return 1;
}

int fb_mesh_nset(const fb_mesh *m, const char *name, const size_t **nodes, size_t *n)
{
  return m ? get_set(&m->nsets, name, nodes, n) : 0;
}

size_t fb_mesh_nelsets(const fb_mesh *m)
{
  return m ? m->elsets.n : 0;
}

/* Name of element set i as first given, or NULL if i is out of range. */
const char *fb_mesh_elset_name(const fb_mesh *m, size_t i)
{
  return m && i < m->elsets.n ? m->elsets.sets[i].name : NULL;
}

int fb_mesh_elset(const fb_mesh *m, const char *name, const size_t **elements, size_t *n)
{
  return m ? get_set(&m->elsets, name, elements, n) : 0;
}

size_t fb_mesh_nsections(const fb_mesh *m)
{
  return m ? m->nsections : 0;
}

const char *fb_mesh_section_elset(const fb_mesh *m, size_t i)
{
  return m && i < m->nsections ? m->sections[i].elset : NULL;
}

const fb_shell_props *fb_mesh_section_props(const fb_mesh *m, size_t i)
{
  return m && i < m->nsections ? &m->sections[i].props : NULL;
}

long fb_mesh_element_section(const fb_mesh *m, size_t e)
{
  return m && m->elem_section && e < m->nelems ? m->elem_section[e] : -1;
}

size_t fb_mesh_section_nelements(const fb_mesh *m, long sec)
{
  size_t n = 0;
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e)
    n += fb_mesh_element_section(m, e) == sec;
  return n;
}

fb_shell_props fb_mesh_element_props(const fb_mesh *m, size_t e, const fb_shell_props *base)
{
  const long i = fb_mesh_element_section(m, e);
  fb_shell_props p = *base;
  if (i >= 0) {
    p = m->sections[i].props;
    p.drill_factor = base->drill_factor;
  }
  p.nonstructural_mass += fb_mesh_element_nonstructural(m, e);
  return p;
}

/* ---- Added masses. */

int fb_mesh_add_element_nonstructural(fb_mesh *m, size_t e, double per_area, fb_err *err)
{
  if (!m || e >= m->nelems)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_add_element_nonstructural: no element %zu", e);
  /* The sum too: two huge masses on one element must not make inf. */
  const double sum = fb_mesh_element_nonstructural(m, e) + per_area;
  if (!(per_area >= 0.0 && isfinite(sum)))
    return fb_err_set(err, FB_EINVAL,
                      "element %ld: non-structural mass %g kg/m^2 (%g in all) is not >= 0 and "
                      "finite",
                      m->elem_ids[e], per_area, sum);
  if (!m->elem_nsm) {
    m->elem_nsm = calloc(m->elem_cap ? m->elem_cap : 1, sizeof *m->elem_nsm);
    if (!m->elem_nsm)
      return fb_err_set(err, FB_ENOMEM, "out of memory for non-structural masses");
  }
  m->elem_nsm[e] += per_area;
  return FB_OK;
}

double fb_mesh_element_nonstructural(const fb_mesh *m, size_t e)
{
  return m && m->elem_nsm && e < m->nelems ? m->elem_nsm[e] : 0.0;
}

int fb_mesh_add_point_mass(fb_mesh *m, long id, size_t node, double mass, fb_err *err)
{
  if (!m || node >= m->nnodes)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_add_point_mass: no node %zu", node);
  if (id <= 0)
    return fb_err_set(err, FB_EINVAL, "point mass id %ld is not positive", id);
  if (!(mass >= 0.0 && isfinite(mass)))
    return fb_err_set(err, FB_EINVAL, "point mass %ld: mass %g kg is not >= 0 and finite", id,
                      mass);
  if (id_map_find(&m->elem_map, m->elem_ids, id) >= 0 || fb_mesh_find_point_mass_id(m, id) >= 0)
    return fb_err_set(err, FB_EINVAL, "element id %ld is defined twice", id);
  if (fb_grow((void **)&m->pmass, &m->pmass_cap, m->npmass, sizeof *m->pmass))
    return fb_err_set(err, FB_ENOMEM, "out of memory adding point mass %ld", id);
  m->pmass[m->npmass++] = (mesh_point_mass){id, node, mass};
  return FB_OK;
}

size_t fb_mesh_npoint_masses(const fb_mesh *m)
{
  return m ? m->npmass : 0;
}

long fb_mesh_point_mass_id(const fb_mesh *m, size_t i)
{
  return m && i < m->npmass ? m->pmass[i].id : -1;
}

size_t fb_mesh_point_mass_node(const fb_mesh *m, size_t i)
{
  return m && i < m->npmass ? m->pmass[i].node : 0;
}

double fb_mesh_point_mass(const fb_mesh *m, size_t i)
{
  return m && i < m->npmass ? m->pmass[i].mass : 0.0;
}

/* A linear search: a hull carries a handful of point masses. */
long fb_mesh_find_point_mass_id(const fb_mesh *m, long id)
{
  for (size_t i = 0; m && i < m->npmass; ++i)
    if (m->pmass[i].id == id)
      return (long)i;
  return -1;
}
