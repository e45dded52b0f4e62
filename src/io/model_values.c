/* SPDX-License-Identifier: BSD-3-Clause */
/* Values in model files: number lists, matrices (inline rows, diagonal,
 * Matrix Market file) and source time functions (expression of t, step,
 * sine, table). */
#include <stdlib.h>
#include <string.h>

#include "io/model_internal.h"

int ml_vector(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, size_t want,
              int allow_scalar, double **out, size_t *len)
{
  *out = NULL;
  *len = 0;
  if (allow_scalar && fy_node_is_scalar(n) && !ml_is_null(n)) {
    double v = 0;
    int rc = ml_number(c, n, syms, &v);
    if (rc)
      return rc;
    if (want > 1)
      return ml_fail(c, n, FB_EMODEL, "expected a list of %zu values, got one number", want);
    *out = malloc(sizeof **out);
    if (!*out)
      return fb_err_set(c->err, FB_ENOMEM, "out of memory");
    **out = v;
    *len = 1;
    return FB_OK;
  }
  int rc = ml_expect_seq(c, n, "a list of numbers");
  if (rc)
    return rc;
  size_t count = (size_t)fy_node_sequence_item_count(n);
  if (count == 0 || (want && count != want))
    return want ? ml_fail(c, n, FB_EMODEL, "expected %zu values, got %zu", want, count)
                : ml_fail(c, n, FB_EMODEL, "expected at least one value");
  /* calloc: no element is left undefined should libfyaml's count and iteration disagree. */
  double *v = calloc(count, sizeof *v);
  if (!v)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  void *iter = NULL;
  struct fy_node *item;
  size_t i = 0;
  while ((item = fy_node_sequence_iterate(n, &iter))) {
    rc = ml_number(c, item, syms, &v[i++]);
    if (rc) {
      free(v);
      return rc;
    }
  }
  *out = v;
  *len = count;
  return FB_OK;
}

/* Reads the rows of an inline matrix into a row-major array. */
static int ml_matrix_rows(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                          fb_mat **out)
{
  size_t nrows = (size_t)fy_node_sequence_item_count(n);
  if (nrows == 0)
    return ml_fail(c, n, FB_EMODEL, "a matrix needs at least one row");
  struct fy_node *first = fy_node_sequence_get_by_index(n, 0);
  if (!fy_node_is_sequence(first))
    return ml_fail(c, first, FB_EPARSE,
                   "expected a matrix row (a list of numbers); write rows as [[a, b], [c, d]]");
  size_t ncols = (size_t)fy_node_sequence_item_count(first);
  double *vals = malloc(nrows * (ncols ? ncols : 1) * sizeof *vals);
  if (!vals)
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  void *iter = NULL;
  struct fy_node *row;
  size_t i = 0;
  int rc = FB_OK;
  while (!rc && (row = fy_node_sequence_iterate(n, &iter))) {
    double *r = NULL;
    size_t len = 0;
    rc = ml_vector(c, row, syms, 0, 0, &r, &len);
    if (!rc && len != ncols)
      rc = ml_fail(c, row, FB_EMODEL, "row %zu has %zu entries, row 1 has %zu", i + 1, len,
                   ncols);
    if (!rc)
      memcpy(vals + i * ncols, r, ncols * sizeof *vals);
    free(r);
    ++i;
  }
  if (!rc && fb_mat_new_dense_rowmajor(nrows, ncols, vals, out, c->err))
    rc = ml_blame(c, n);
  free(vals);
  return rc;
}

static int ml_matrix_diag(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                          fb_mat **out)
{
  double *d = NULL;
  size_t len = 0;
  int rc = ml_vector(c, n, syms, 0, 0, &d, &len);
  if (!rc && fb_mat_new_diag(len, d, out, c->err))
    rc = ml_blame(c, n);
  free(d);
  return rc;
}

static int ml_matrix_file(const ml_ctx *c, struct fy_node *n, fb_mat **out)
{
  const char *name = NULL;
  char *path = NULL;
  int rc = ml_string(c, n, &name);
  if (!rc)
    rc = ml_resolve_path(c, n, name, &path);
  /* The reader's own "path:line" stays in the message after the YAML
   * location of the reference. */
  if (!rc && fb_mat_read_mtx(path, out, c->err))
    rc = ml_blame(c, n);
  free(path);
  return rc;
}

int ml_matrix(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, fb_mat **out)
{
  static const char *const keys[] = {"diagonal", "mtx", NULL};
  *out = NULL;
  if (fy_node_is_sequence(n))
    return ml_matrix_rows(c, n, syms, out);
  if (!fy_node_is_mapping(n))
    return ml_fail(c, n, FB_EPARSE,
                   "expected a matrix: a list of rows, {diagonal: [..]} or {mtx: file}");
  int rc = ml_check_keys(c, n, keys);
  if (rc)
    return rc;
  if (fy_node_mapping_item_count(n) != 1)
    return ml_fail(c, n, FB_EPARSE, "give exactly one of 'diagonal' or 'mtx'");
  struct fy_node *v = ml_get(n, "diagonal", NULL);
  if (v)
    return ml_matrix_diag(c, v, syms, out);
  return ml_matrix_file(c, ml_get(n, "mtx", NULL), out);
}

/* ---- Time functions. */

static int ml_tfun_step(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                        fb_tfun **out)
{
  static const char *const keys[] = {"time", "before", "after", NULL};
  double t0 = 0, before = 0, after = 0;
  struct fy_node *v = NULL;
  int rc = ml_expect_map(c, n, "a step {time, before, after}");
  if (!rc)
    rc = ml_check_keys(c, n, keys);
  if (!rc)
    rc = ml_require(c, n, "time", &v);
  if (!rc)
    rc = ml_number(c, v, syms, &t0);
  if (!rc)
    rc = ml_require(c, n, "after", &v);
  if (!rc)
    rc = ml_number(c, v, syms, &after);
  if (!rc)
    rc = ml_opt_number(c, n, "before", syms, &before);
  if (!rc && fb_tfun_new_step(t0, before, after, out, c->err))
    rc = ml_blame(c, n);
  return rc;
}

static int ml_tfun_sine(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                        fb_tfun **out)
{
  static const char *const keys[] = {"amplitude", "frequency", "phase", "offset", NULL};
  double amplitude = 0, freq = 0, phase = 0, offset = 0;
  struct fy_node *v = NULL;
  int rc = ml_expect_map(c, n, "a sine {amplitude, frequency, phase, offset}");
  if (!rc)
    rc = ml_check_keys(c, n, keys);
  if (!rc)
    rc = ml_require(c, n, "amplitude", &v);
  if (!rc)
    rc = ml_number(c, v, syms, &amplitude);
  if (!rc)
    rc = ml_require(c, n, "frequency", &v);
  if (!rc)
    rc = ml_number(c, v, syms, &freq);
  if (!rc && freq < 0)
    rc = ml_fail(c, v, FB_EINVAL, "must be >= 0 Hz (got %g)", freq);
  if (!rc)
    rc = ml_opt_number(c, n, "phase", syms, &phase);
  if (!rc)
    rc = ml_opt_number(c, n, "offset", syms, &offset);
  if (!rc && fb_tfun_new_sine(amplitude, freq, phase, offset, out, c->err))
    rc = ml_blame(c, n);
  return rc;
}

/* Inline table points: [[t0, v0], [t1, v1], ...]. */
static int ml_tfun_points(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                          fb_tfun **out)
{
  int rc = ml_expect_seq(c, n, "a list of [time, value] pairs");
  size_t count = rc ? 0 : (size_t)fy_node_sequence_item_count(n);
  if (!rc && count == 0)
    rc = ml_fail(c, n, FB_EMODEL, "a table needs at least one point");
  if (rc)
    return rc;
  double *times = malloc(count * sizeof *times), *values = malloc(count * sizeof *values);
  if (!times || !values)
    rc = fb_err_set(c->err, FB_ENOMEM, "out of memory");
  void *iter = NULL;
  struct fy_node *item;
  size_t i = 0;
  while (!rc && (item = fy_node_sequence_iterate(n, &iter))) {
    double *pt = NULL;
    size_t len = 0;
    rc = ml_vector(c, item, syms, 2, 0, &pt, &len);
    if (!rc) {
      times[i] = pt[0];
      values[i] = pt[1];
    }
    free(pt);
    ++i;
  }
  if (!rc && fb_tfun_new_table(count, times, values, out, c->err))
    rc = ml_blame(c, n);
  free(times);
  free(values);
  return rc;
}

static int ml_tfun_csv(const ml_ctx *c, struct fy_node *n, fb_tfun **out)
{
  struct fy_node *file = NULL, *value = NULL, *time = ml_get(n, "time", NULL);
  const char *name = NULL, *time_col = "t", *value_col = NULL;
  char *path = NULL;
  int rc = ml_require(c, n, "file", &file);
  if (!rc)
    rc = ml_require(c, n, "value", &value);
  if (!rc)
    rc = ml_string(c, value, &value_col);
  if (!rc && time)
    rc = ml_string(c, time, &time_col);
  if (!rc)
    rc = ml_string(c, file, &name);
  if (!rc)
    rc = ml_resolve_path(c, file, name, &path);
  if (!rc && fb_tfun_new_table_csv(path, time_col, value_col, out, c->err))
    rc = ml_blame(c, file);
  free(path);
  return rc;
}

static int ml_tfun_table(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                         fb_tfun **out)
{
  static const char *const keys[] = {"file", "time", "value", "points", NULL};
  int rc = ml_expect_map(c, n, "a table {file, time, value} or {points}");
  if (!rc)
    rc = ml_check_keys(c, n, keys);
  if (rc)
    return rc;
  struct fy_node *points = ml_get(n, "points", NULL);
  if (points && fy_node_mapping_item_count(n) != 1)
    return ml_fail(c, n, FB_EPARSE, "a table has either 'points' or 'file' (with its columns)");
  if (points)
    return ml_tfun_points(c, points, syms, out);
  return ml_tfun_csv(c, n, out);
}

/* A scalar source value: a number, or an expression that may use t. */
static int ml_tfun_scalar(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                          fb_tfun **out)
{
  const char *text = NULL;
  /* An expression may span lines (a block scalar): line breaks and tabs
   * are blanks to the parser, as in every other number's expression. */
  int rc = ml_text(c, n, &text);
  if (rc)
    return rc;
  fb_expr *e = NULL;
  if (fb_expr_parse(text, syms, &e, c->err)) {
    fb_err_prefix(c->err, "expression '%s': ", text);
    return ml_blame(c, n);
  }
  if (!fb_expr_uses_time(e)) {
    /* Time-independent: evaluate once so a non-finite value is caught
     * here rather than in the solver. */
    fb_expr_free(&e);
    double v = 0;
    rc = ml_number(c, n, syms, &v);
    if (!rc && fb_tfun_new_const(v, out, c->err))
      rc = ml_blame(c, n);
    return rc;
  }
  if (fb_tfun_new_expr(&e, out, c->err))
    return ml_blame(c, n);
  return FB_OK;
}

int ml_tfun(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, fb_tfun **out)
{
  static const char *const kinds[] = {"step", "sine", "table", "road", NULL};
  *out = NULL;
  if (ml_is_null(n))
    return ml_fail(c, n, FB_EPARSE, "expected a source value, got nothing");
  if (fy_node_is_scalar(n))
    return ml_tfun_scalar(c, n, syms, out);
  if (!fy_node_is_mapping(n))
    return ml_fail(c, n, FB_EPARSE,
                   "expected a source value: a number, an expression of t, or one of "
                   "{step: ..}, {sine: ..}, {table: ..}, {road: ..}");
  int rc = ml_check_keys(c, n, kinds);
  if (rc)
    return rc;
  if (fy_node_mapping_item_count(n) != 1)
    return ml_fail(c, n, FB_EPARSE, "give exactly one of 'step', 'sine', 'table' or 'road'");
  struct fy_node *v = NULL;
  if ((v = ml_get(n, "step", NULL)))
    return ml_tfun_step(c, v, syms, out);
  if ((v = ml_get(n, "sine", NULL)))
    return ml_tfun_sine(c, v, syms, out);
  if ((v = ml_get(n, "road", NULL)))
    return ml_tfun_road(c, v, syms, out);
  return ml_tfun_table(c, ml_get(n, "table", NULL), syms, out);
}
