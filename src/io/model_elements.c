/* SPDX-License-Identifier: BSD-3-Clause */
/* Elements in model files: one mapping per element, dispatched on `type`
 * to the fb_bg constructor of that kind, or to a subsystem definition. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/util.h"
#include "io/model_internal.h"

/* Largest dimension or port count accepted, to catch typos like 1e9
 * before they become allocations. */
#define ML_MAX_DIM ((size_t)1000000)

/* Relative tolerance for the symmetry check of field matrices: laws are
 * written by hand or computed from the same parameters, so anything
 * above rounding is a modelling error. */
#define ML_SYM_TOL 1e-10

const ml_entry *ml_scope_find(const ml_scope *s, const char *name)
{
  for (size_t i = 0; i < s->nentries; ++i)
    if (!strcmp(s->entries[i].name, name))
      return &s->entries[i];
  return NULL;
}

int ml_scope_add(const ml_ctx *c, ml_scope *s, const ml_entry *e)
{
  if (fb_grow((void **)&s->entries, &s->capacity, s->nentries, sizeof *s->entries))
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  s->entries[s->nentries++] = *e;
  return FB_OK;
}

void ml_scope_release(ml_scope *s)
{
  free(s->entries);
  s->entries = NULL;
  s->nentries = s->capacity = 0;
}

/* ---- Ports of fields: `dim: n` (one port), `ports: N` (N ports of
 * dimension 1) or `ports: [d1, d2, ..]`. *nports is 0 when neither key
 * is present; *dims is malloc'd otherwise. */
static int ml_port_dims(const ml_ctx *c, const ml_scope *s, struct fy_node *el, size_t **dims,
                        size_t *nports)
{
  struct fy_node *dim_key = NULL, *ports_key = NULL;
  struct fy_node *dim = ml_get(el, "dim", &dim_key), *ports = ml_get(el, "ports", &ports_key);
  *dims = NULL;
  *nports = 0;
  if (dim_key && ports_key)
    return ml_fail_key(c, el, dim_key, FB_EPARSE, "give either 'dim' or 'ports', not both");
  if (!dim_key && !ports_key)
    return FB_OK;
  size_t count = 1;
  int rc = FB_OK;
  if (ports_key && fy_node_is_sequence(ports))
    count = (size_t)fy_node_sequence_item_count(ports);
  else if (ports_key)
    rc = ml_count(c, ports, s->syms, 1, ML_MAX_DIM, &count);
  if (!rc && count == 0)
    rc = ml_fail(c, ports, FB_EMODEL, "a field needs at least one port");
  if (rc)
    return rc;
  size_t *d = malloc(count * sizeof *d);
  if (!d)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; i < count; ++i)
    d[i] = 1;
  if (dim_key)
    rc = ml_count(c, dim, s->syms, 1, ML_MAX_DIM, &d[0]);
  for (size_t i = 0; !rc && ports_key && fy_node_is_sequence(ports) && i < count; ++i)
    rc = ml_count(c, fy_node_sequence_get_by_index(ports, (int)i), s->syms, 1, ML_MAX_DIM,
                  &d[i]);
  if (rc) {
    free(d);
    return rc;
  }
  *dims = d;
  *nports = count;
  return FB_OK;
}

/* Checks a field law against the kind's requirements (bg.h): M symmetric
 * positive definite, K and R symmetric positive semi-definite. */
static int ml_check_law(const ml_ctx *c, struct fy_node *at, fb_bg_kind kind, const fb_mat *law,
                        size_t n)
{
  size_t rows = fb_mat_nrows(law), cols = fb_mat_ncols(law);
  if (rows != cols)
    return ml_fail(c, at, FB_EMODEL, "matrix must be square (got %zux%zu)", rows, cols);
  if (rows != n)
    return ml_fail(c, at, FB_EMODEL,
                   "matrix is %zux%zu but the ports' dimensions add up to %zu", rows, cols, n);
  if (!fb_mat_all_finite(law))
    return ml_fail(c, at, FB_EINVAL, "matrix entries must be finite");
  if (!fb_mat_is_symmetric(law, ML_SYM_TOL))
    return ml_fail(c, at, FB_EINVAL, "matrix must be symmetric");
  if (kind == FB_BG_I && !fb_mat_is_spd(law, 0))
    return ml_fail(c, at, FB_EINVAL, "mass matrix must be positive definite");
  if (kind != FB_BG_I && !fb_mat_is_spd(law, 1))
    return ml_fail(c, at, FB_EINVAL, "%s matrix must be positive semi-definite",
                   kind == FB_BG_C ? "stiffness" : "resistance");
  return FB_OK;
}

/* The scalar parameter of a one-port field and the diagonal value of its
 * law: I takes m (or i), C takes k (stiffness) or c (compliance, law 1/c),
 * R takes r. */
static int ml_field_scalar(const ml_ctx *c, const ml_scope *s, struct fy_node *el,
                           fb_bg_kind kind, double *law_value)
{
  const char *a = kind == FB_BG_I ? "m" : kind == FB_BG_C ? "k" : "r";
  const char *b = kind == FB_BG_I ? "i" : kind == FB_BG_C ? "c" : NULL;
  struct fy_node *ka = NULL, *kb = NULL;
  struct fy_node *va = ml_get(el, a, &ka), *vb = b ? ml_get(el, b, &kb) : NULL;
  if (ka && kb)
    return ml_fail_key(c, el, kb, FB_EPARSE, "give either '%s' or '%s', not both", a, b);
  if (!ka && !kb)
    return b ? ml_fail(c, el, FB_EPARSE, "missing required key '%s' (or '%s', or 'matrix')", a,
                       b)
             : ml_fail(c, el, FB_EPARSE, "missing required key '%s' (or 'matrix' or 'table')",
                       a);
  struct fy_node *v = ka ? va : vb;
  double x = 0;
  int rc = ml_number(c, v, s->syms, &x);
  if (rc)
    return rc;
  if (kind == FB_BG_R && x < 0)
    return ml_fail(c, v, FB_EINVAL, "must be >= 0 (got %g)", x);
  if (kind != FB_BG_R && x <= 0)
    return ml_fail(c, v, FB_EINVAL, "must be > 0 (got %g)", x);
  *law_value = (kind == FB_BG_C && kb) ? 1.0 / x : x;
  if (!isfinite(*law_value))
    return ml_fail(c, v, FB_EINVAL, "stiffness 1/c is not finite (c = %g)", x);
  return FB_OK;
}

/* A single port of dimension n, for fields given without dim/ports. */
static int ml_default_port(const ml_ctx *c, size_t n, size_t **dims, size_t *nports)
{
  *dims = malloc(sizeof **dims);
  if (!*dims)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  (*dims)[0] = n;
  *nports = 1;
  return FB_OK;
}

/* The law of a field: the matrix, or scalar * identity for a one-port.
 * On success *dims and *nports describe the ports. */
static int ml_field_law(const ml_ctx *c, const ml_scope *s, struct fy_node *el, fb_bg_kind kind,
                        size_t **dims, size_t *nports, fb_mat **law)
{
  struct fy_node *mkey = NULL;
  struct fy_node *matrix = ml_get(el, "matrix", &mkey);
  if (!mkey) {
    double value = 0;
    int rc = ml_field_scalar(c, s, el, kind, &value);
    if (!rc && *nports > 1)
      rc = ml_fail(c, el, FB_EMODEL, "a field with %zu ports needs 'matrix'", *nports);
    if (!rc && *nports == 0)
      rc = ml_default_port(c, 1, dims, nports);
    if (!rc && fb_mat_new_scaled_identity((*dims)[0], value, law, c->err))
      rc = ml_blame(c, el);
    return rc;
  }
  static const char *const scalars[] = {"m", "i", "k", "c", "r", NULL};
  for (size_t i = 0; scalars[i]; ++i) {
    struct fy_node *k = NULL;
    ml_get(el, scalars[i], &k);
    if (k)
      return ml_fail_key(c, el, k, FB_EPARSE, "give either 'matrix' or '%s', not both",
                         scalars[i]);
  }
  int rc = ml_matrix(c, matrix, s->syms, law);
  if (!rc && *nports == 0)
    rc = ml_default_port(c, fb_mat_nrows(*law), dims, nports);
  if (rc)
    return rc;
  size_t total = 0;
  for (size_t i = 0; i < *nports; ++i)
    total += (*dims)[i];
  return ml_check_law(c, matrix, kind, *law, total);
}

static int ml_field_initial(const ml_ctx *c, const ml_scope *s, struct fy_node *el,
                            const char *name, size_t n)
{
  struct fy_node *key = NULL;
  struct fy_node *v = ml_get(el, "initial", &key);
  if (!key)
    return FB_OK;
  double *x0 = NULL;
  size_t len = 0;
  int rc = ml_vector(c, v, s->syms, n, n == 1, &x0, &len);
  if (!rc && fb_bg_set_initial(s->bg, name, len, x0, c->err))
    rc = ml_blame(c, v);
  free(x0);
  return rc;
}

/* ---- R with a tabulated force-velocity law (fb_table_law): `table:
 * {file, velocity, force}` or `table: {points: [[v, F], ..]}`. */

/* Inline [velocity, force] points; a velocity that does not increase is
 * reported at its own point. */
static int ml_table_points(const ml_ctx *c, const fb_symtab *syms, struct fy_node *n,
                           fb_table_law **law)
{
  int rc = ml_expect_seq(c, n, "a list of [velocity, force] pairs");
  size_t count = rc ? 0 : (size_t)fy_node_sequence_item_count(n);
  if (!rc && count < 2)
    rc = ml_fail(c, n, FB_EMODEL, "a table needs at least 2 points (got %zu)", count);
  if (rc)
    return rc;
  double *v = malloc(count * sizeof *v), *f = malloc(count * sizeof *f);
  if (!v || !f)
    rc = fb_err_set(c->err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; !rc && i < count; ++i) {
    struct fy_node *item = fy_node_sequence_get_by_index(n, (int)i);
    double *pt = NULL;
    size_t len = 0;
    rc = ml_vector(c, item, syms, 2, 0, &pt, &len);
    if (!rc) {
      v[i] = pt[0];
      f[i] = pt[1];
    }
    free(pt);
    if (!rc && i > 0 && !(v[i] > v[i - 1]))
      rc = ml_fail(c, item, FB_EINVAL,
                   "velocities must be strictly increasing: %g does not exceed the previous "
                   "point's %g",
                   v[i], v[i - 1]);
  }
  if (!rc && fb_table_law_new(count, v, f, law, c->err))
    rc = ml_blame(c, n);
  free(v);
  free(f);
  return rc;
}

/* A CSV file with a header line; `velocity` (default "v") and `force`
 * (required) name its columns. The reader's "path:line" follows the YAML
 * location of `file`. */
static int ml_table_file(const ml_ctx *c, struct fy_node *n, fb_table_law **law)
{
  struct fy_node *file = NULL, *force = NULL, *velocity = ml_get(n, "velocity", NULL);
  const char *name = NULL, *velocity_col = "v", *force_col = NULL;
  char *path = NULL;
  int rc = ml_require(c, n, "file", &file);
  if (!rc)
    rc = ml_require(c, n, "force", &force);
  if (!rc)
    rc = ml_string(c, force, &force_col);
  if (!rc && velocity)
    rc = ml_string(c, velocity, &velocity_col);
  if (!rc)
    rc = ml_string(c, file, &name);
  if (!rc)
    rc = ml_resolve_path(c, file, name, &path);
  if (!rc && fb_table_law_read_csv(path, velocity_col, force_col, law, c->err))
    rc = ml_blame(c, file);
  free(path);
  return rc;
}

int ml_table_law(const ml_ctx *c, const fb_symtab *syms, struct fy_node *table,
                 fb_table_law **law)
{
  static const char *const keys[] = {"file", "velocity", "force", "points", NULL};
  *law = NULL;
  int rc = ml_expect_map(c, table, "a table {file, velocity, force} or {points}");
  if (!rc)
    rc = ml_check_keys(c, table, keys);
  if (rc)
    return rc;
  struct fy_node *points = ml_get(table, "points", NULL);
  if (points && fy_node_mapping_item_count(table) != 1)
    return ml_fail(c, table, FB_EPARSE,
                   "a table has either 'points' or 'file' (with its columns)");
  return points ? ml_table_points(c, syms, points, law) : ml_table_file(c, table, law);
}

/* The table makes a one-port of dimension 1 and replaces `r`/`matrix`. */
static int ml_r_table(ml_ctx *c, ml_scope *s, struct fy_node *el, struct fy_node *table,
                      const char *name, ml_entry *e)
{
  static const char *const exclusive[] = {"r", "matrix", "dim", "ports", NULL};
  e->nports = 1;
  for (size_t i = 0; exclusive[i]; ++i) {
    struct fy_node *k = NULL;
    ml_get(el, exclusive[i], &k);
    if (k)
      return ml_fail_key(c, el, k, FB_EPARSE,
                         "'table' makes a one-port of dimension 1: give either 'table' or "
                         "'%s', not both",
                         exclusive[i]);
  }
  fb_table_law *law = NULL;
  int rc = ml_table_law(c, s->syms, table, &law);
  /* A table that is not passive is refused here (see bg.h). */
  if (!rc && fb_bg_add_r_table(s->bg, name, &law, c->err))
    rc = ml_blame(c, table);
  fb_table_law_free(&law);
  return rc;
}

static int ml_field(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *name, ml_entry *e)
{
  struct fy_node *table_key = NULL;
  struct fy_node *table = ml_get(el, "table", &table_key);
  if (table_key) /* only R elements accept the key */
    return ml_r_table(c, s, el, table, name, e);
  size_t *dims = NULL, nports = 0, total = 0;
  fb_mat *law = NULL;
  int rc = ml_port_dims(c, s, el, &dims, &nports);
  if (!rc)
    rc = ml_field_law(c, s, el, e->kind, &dims, &nports, &law);
  for (size_t i = 0; !rc && i < nports; ++i)
    total += dims[i];
  if (!rc && fb_bg_add_field(s->bg, name, e->kind, nports, dims, &law, c->err))
    rc = ml_blame(c, el);
  if (!rc && (e->kind == FB_BG_I || e->kind == FB_BG_C))
    rc = ml_field_initial(c, s, el, name, total);
  fb_mat_free(&law);
  free(dims);
  e->nports = nports;
  return rc;
}

/* ---- Sources: `value` is one source value, a list of them (one per
 * component), or one value broadcast to all `dim` components. */
static int ml_source(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *name, ml_entry *e)
{
  struct fy_node *value = NULL, *dim_key = NULL;
  struct fy_node *dim_node = ml_get(el, "dim", &dim_key);
  size_t dim = 0;
  int rc = ml_require(c, el, "value", &value);
  if (!rc && dim_key)
    rc = ml_count(c, dim_node, s->syms, 1, ML_MAX_DIM, &dim);
  if (rc)
    return rc;
  int is_list = fy_node_is_sequence(value);
  size_t count = is_list ? (size_t)fy_node_sequence_item_count(value) : 1;
  if (count == 0)
    return ml_fail(c, value, FB_EMODEL, "expected at least one value");
  if (!dim)
    dim = count;
  if (is_list && count != dim)
    return ml_fail(c, value, FB_EMODEL, "%zu values given for a source of dim %zu", count, dim);
  /* NOLINTNEXTLINE(bugprone-sizeof-expression): an array of pointers, sized by its element */
  fb_tfun **f = calloc(dim, sizeof *f);
  if (!f)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; !rc && i < dim; ++i) {
    if (is_list)
      rc = ml_tfun(c, fy_node_sequence_get_by_index(value, (int)i), s->syms, &f[i]);
    else if (i == 0)
      rc = ml_tfun(c, value, s->syms, &f[i]);
    else if (fb_tfun_clone(f[0], &f[i], c->err))
      rc = ml_blame(c, value);
  }
  if (!rc && fb_bg_add_source(s->bg, name, e->kind, dim, f, c->err))
    rc = ml_blame(c, el);
  for (size_t i = 0; i < dim; ++i)
    fb_tfun_free(&f[i]);
  free(f);
  e->nports = 1;
  return rc;
}

/* Optional `dim` (default 1). */
static int ml_opt_dim(const ml_ctx *c, const ml_scope *s, struct fy_node *el, size_t *dim)
{
  struct fy_node *key = NULL;
  struct fy_node *v = ml_get(el, "dim", &key);
  *dim = 1;
  return key ? ml_count(c, v, s->syms, 1, ML_MAX_DIM, dim) : FB_OK;
}

/* TF (`ratio`) and GY (`r`): a nonzero finite modulus. */
static int ml_tf_gy(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *name, ml_entry *e)
{
  struct fy_node *v = NULL;
  double modulus = 0;
  size_t dim = 1;
  int rc = ml_require(c, el, e->kind == FB_BG_TF ? "ratio" : "r", &v);
  if (!rc)
    rc = ml_number(c, v, s->syms, &modulus);
  if (!rc && modulus == 0)
    rc = ml_fail(c, v, FB_EINVAL, "must be nonzero");
  if (!rc)
    rc = ml_opt_dim(c, s, el, &dim);
  if (!rc && fb_bg_add_tf(s->bg, name, e->kind, dim, modulus, c->err))
    rc = ml_blame(c, el);
  e->nports = 2;
  return rc;
}

static int ml_mtf(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *name, ml_entry *e)
{
  struct fy_node *v = NULL;
  fb_mat *t = NULL;
  int rc = ml_require(c, el, "matrix", &v);
  if (!rc)
    rc = ml_matrix(c, v, s->syms, &t);
  if (!rc && !fb_mat_all_finite(t))
    rc = ml_fail(c, v, FB_EINVAL, "matrix entries must be finite");
  if (!rc && fb_bg_add_mtf(s->bg, name, &t, c->err))
    rc = ml_blame(c, el);
  fb_mat_free(&t);
  e->nports = 2;
  return rc;
}

static int ml_junction(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *name,
                       ml_entry *e)
{
  size_t dim = 1;
  int rc = ml_opt_dim(c, s, el, &dim);
  if (!rc && fb_bg_add_junction(s->bg, name, e->kind, dim, c->err))
    rc = ml_blame(c, el);
  e->nports = 0;
  return rc;
}

static int ml_composite(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *name,
                        ml_entry *e)
{
  struct fy_node *v = NULL;
  int rc = ml_require(c, el, "parts", &v);
  if (!rc)
    rc = ml_expect_seq(c, v, "a list of part dimensions");
  size_t nparts = rc ? 0 : (size_t)fy_node_sequence_item_count(v);
  if (!rc && nparts == 0)
    rc = ml_fail(c, v, FB_EMODEL, "a composite needs at least one part");
  if (rc)
    return rc;
  size_t *dims = malloc(nparts * sizeof *dims);
  if (!dims)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; !rc && i < nparts; ++i)
    rc =
        ml_count(c, fy_node_sequence_get_by_index(v, (int)i), s->syms, 1, ML_MAX_DIM, &dims[i]);
  if (!rc && fb_bg_add_composite(s->bg, name, nparts, dims, c->err))
    rc = ml_blame(c, el);
  free(dims);
  e->nports = nparts;
  return rc;
}

/* ---- Dispatch on `type`. */

typedef int (*ml_build_fn)(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *name,
                           ml_entry *e);

typedef struct ml_type {
  const char *name; /* spelling in `type:` */
  fb_bg_kind kind;
  ml_build_fn build;
  const char *const *keys; /* allowed keys */
} ml_type;

#define ML_COMMON_KEYS "name", "type", "description"
static const char *const ml_keys_i[] = {ML_COMMON_KEYS, "m",      "i",       "dim",
                                        "ports",        "matrix", "initial", NULL};
static const char *const ml_keys_c[] = {ML_COMMON_KEYS, "k",      "c",       "dim",
                                        "ports",        "matrix", "initial", NULL};
static const char *const ml_keys_r[] = {ML_COMMON_KEYS, "r",     "dim", "ports",
                                        "matrix",       "table", NULL};
static const char *const ml_keys_source[] = {ML_COMMON_KEYS, "value", "dim", NULL};
static const char *const ml_keys_tf[] = {ML_COMMON_KEYS, "ratio", "dim", NULL};
static const char *const ml_keys_gy[] = {ML_COMMON_KEYS, "r", "dim", NULL};
static const char *const ml_keys_mtf[] = {ML_COMMON_KEYS, "matrix", NULL};
static const char *const ml_keys_junction[] = {ML_COMMON_KEYS, "dim", NULL};
static const char *const ml_keys_composite[] = {ML_COMMON_KEYS, "parts", NULL};
static const char *const ml_keys_contact[] = {ML_COMMON_KEYS, "k",      "c",
                                              "lambda",       "damper", NULL};
static const char *const ml_keys_instance[] = {ML_COMMON_KEYS, "parameters", NULL};

static const ml_type ml_types[] = {
    {"Se", FB_BG_SE, ml_source, ml_keys_source},
    {"Sf", FB_BG_SF, ml_source, ml_keys_source},
    {"I", FB_BG_I, ml_field, ml_keys_i},
    {"C", FB_BG_C, ml_field, ml_keys_c},
    {"R", FB_BG_R, ml_field, ml_keys_r},
    {"TF", FB_BG_TF, ml_tf_gy, ml_keys_tf},
    {"GY", FB_BG_GY, ml_tf_gy, ml_keys_gy},
    {"MTF", FB_BG_MTF, ml_mtf, ml_keys_mtf},
    {"0", FB_BG_J0, ml_junction, ml_keys_junction},
    {"1", FB_BG_J1, ml_junction, ml_keys_junction},
    {"zero", FB_BG_J0, ml_junction, ml_keys_junction},
    {"one", FB_BG_J1, ml_junction, ml_keys_junction},
    {"composite", FB_BG_COMPOSITE, ml_composite, ml_keys_composite},
    {"contact", FB_BG_C, ml_contact, ml_keys_contact},
};
#define ML_NTYPES (sizeof ml_types / sizeof ml_types[0])

static const ml_type *ml_type_find(const char *name)
{
  for (size_t i = 0; i < ML_NTYPES; ++i)
    if (!strcmp(ml_types[i].name, name))
      return &ml_types[i];
  return NULL;
}

int ml_is_builtin_type(const char *name)
{
  return ml_type_find(name) != NULL;
}

/* Built-in type names, then definition names, for suggestions. */
static const char *ml_type_name_at(const void *ctx, size_t i)
{
  return i < ML_NTYPES ? ml_types[i].name : ml_def_name(ctx, i - ML_NTYPES);
}

static int ml_unknown_type(const ml_ctx *c, struct fy_node *at, const char *type)
{
  const char *near = fb_suggest(type, ML_NTYPES + c->ndefs, ml_type_name_at, c);
  char hint[256] = "";
  if (near)
    snprintf(hint, sizeof hint, " (did you mean '%s'?)", near);
  char defs[1024];
  size_t len = 0;
  defs[0] = '\0';
  for (size_t i = 0; i < c->ndefs && len + 1 < sizeof defs; ++i) {
    int k = snprintf(defs + len, sizeof defs - len, "%s%s", i ? ", " : "", ml_def_name(c, i));
    len += k > 0 ? (size_t)k : 0;
  }
  return ml_fail(c, at, FB_EMODEL,
                 "unknown element type '%s'%s; valid types: Se, Sf, I, C, R, TF, GY, MTF, 0 "
                 "(zero), 1 (one), composite, contact%s%s",
                 type, hint, c->ndefs ? ", or a subsystem: " : "", defs);
}

/* Name of the element: unique among the scope's elements and instances. */
static int ml_element_name(const ml_ctx *c, const ml_scope *s, struct fy_node *el,
                           const char **name)
{
  struct fy_node *v = NULL;
  int rc = ml_require(c, el, "name", &v);
  if (!rc)
    rc = ml_name(c, v, "element name", name);
  if (rc)
    return rc;
  const ml_entry *first = ml_scope_find(s, *name);
  if (first)
    return ml_fail(c, v, FB_EMODEL, "duplicate element name '%s' (first defined at line %d)",
                   *name, ml_line(first->node));
  return FB_OK;
}

int ml_add_element(ml_ctx *c, ml_scope *s, struct fy_node *el)
{
  const char *name = NULL, *type = NULL;
  struct fy_node *tv = NULL;
  int rc = ml_expect_map(c, el, "an element {name, type, ...}");
  if (!rc)
    rc = ml_element_name(c, s, el, &name);
  if (!rc)
    rc = ml_require(c, el, "type", &tv);
  if (!rc)
    rc = ml_string(c, tv, &type);
  if (rc)
    return rc;
  ml_entry e = {name, FB_BG_J0, 0, -1, el};
  const ml_type *t = ml_type_find(type);
  long def = t ? -1 : ml_def_find(c, type);
  if (!t && def < 0)
    return ml_unknown_type(c, tv, type);
  rc = ml_check_keys(c, el, t ? t->keys : ml_keys_instance);
  if (!rc && t) {
    e.kind = t->kind;
    rc = t->build(c, s, el, name, &e);
  } else if (!rc) {
    e.def = def;
    rc = ml_instantiate(c, s, el, name, (size_t)def);
  }
  if (!rc)
    rc = ml_scope_add(c, s, &e);
  /* An instance is no element of the graph: its parts record themselves. */
  if (!rc && t)
    rc = ml_site_record(c, FB_ORIGIN_ELEMENT, name, el);
  return rc;
}
