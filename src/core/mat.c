/* SPDX-License-Identifier: BSD-3-Clause */
/* Real matrices, dense column-major or compressed sparse column (CSC); see
 * flexbond/mat.h. The LAPACK-based operations (inverse, definiteness) are
 * in mat_lapack.c, LU in lu.c and Matrix Market I/O in mtx.c; those use
 * only the public API.
 *
 * Invariant of every sparse matrix built here: row indices strictly
 * increase within each column and no stored value is exactly zero. The
 * sorted rows let fb_mat_get binary-search a column and make
 * fb_mat_foreach visit entries in (column, row) order. */
#include "flexbond/mat.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

struct fb_mat {
  size_t nrows;
  size_t ncols;
  int sparse;
  size_t nnz;     /* stored values: nrows*ncols when dense */
  double *vals;   /* dense: column-major nrows*ncols; sparse: nnz values */
  size_t *colptr; /* sparse only: ncols+1 offsets into rowidx/vals */
  size_t *rowidx; /* sparse only: row of each stored value */
};

/* malloc of count elements of size bytes, NULL on overflow or failure.
 * Never asks for 0 bytes, so NULL always means failure. */
static void *alloc_array(size_t count, size_t size)
{
  if (count == 0)
    count = 1;
  if (count > SIZE_MAX / size)
    return NULL;
  return malloc(count * size);
}

void fb_mat_free(fb_mat **m)
{
  if (!m || !*m)
    return;
  free((*m)->vals);
  free((*m)->colptr);
  free((*m)->rowidx);
  free(*m);
  *m = NULL;
}

static int oom(fb_err *err)
{
  return fb_err_set(err, FB_ENOMEM, "out of memory allocating a matrix");
}

/* Allocates a dense nrows x ncols matrix with uninitialised values. */
static int dense_alloc(size_t nrows, size_t ncols, fb_mat **out, fb_err *err)
{
  *out = NULL;
  if (ncols != 0 && nrows > SIZE_MAX / sizeof(double) / ncols)
    return fb_err_set(err, FB_EINVAL, "dense matrix %zu x %zu is too large", nrows, ncols);
  fb_mat *m = calloc(1, sizeof *m);
  if (!m)
    return oom(err);
  m->nrows = nrows;
  m->ncols = ncols;
  m->nnz = nrows * ncols;
  m->vals = alloc_array(m->nnz, sizeof *m->vals);
  if (!m->vals) {
    fb_mat_free(&m);
    return oom(err);
  }
  *out = m;
  return FB_OK;
}

/* Allocates a sparse matrix with room for cap entries, column pointers
 * zeroed and nnz 0. */
static int sparse_alloc(size_t nrows, size_t ncols, size_t cap, fb_mat **out, fb_err *err)
{
  *out = NULL;
  if (ncols == SIZE_MAX)
    return fb_err_set(err, FB_EINVAL, "sparse matrix with %zu columns is too large", ncols);
  fb_mat *m = calloc(1, sizeof *m);
  if (!m)
    return oom(err);
  m->nrows = nrows;
  m->ncols = ncols;
  m->sparse = 1;
  m->colptr = calloc(ncols + 1, sizeof *m->colptr);
  m->rowidx = alloc_array(cap, sizeof *m->rowidx);
  m->vals = alloc_array(cap, sizeof *m->vals);
  if (!m->colptr || !m->rowidx || !m->vals) {
    fb_mat_free(&m);
    return oom(err);
  }
  *out = m;
  return FB_OK;
}

static int check_out(fb_mat **out, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "matrix output pointer is NULL");
  *out = NULL;
  return FB_OK;
}

int fb_mat_new_dense(size_t nrows, size_t ncols, const double *colmajor, fb_mat **out,
                     fb_err *err)
{
  int rc = check_out(out, err);
  if (rc)
    return rc;
  if (!colmajor && nrows && ncols)
    return fb_err_set(err, FB_EINVAL, "dense matrix values are NULL");
  fb_mat *m;
  rc = dense_alloc(nrows, ncols, &m, err);
  if (rc)
    return rc;
  if (m->nnz)
    memcpy(m->vals, colmajor, m->nnz * sizeof *m->vals);
  *out = m;
  return FB_OK;
}

int fb_mat_new_dense_rowmajor(size_t nrows, size_t ncols, const double *rowmajor, fb_mat **out,
                              fb_err *err)
{
  int rc = check_out(out, err);
  if (rc)
    return rc;
  if (!rowmajor && nrows && ncols)
    return fb_err_set(err, FB_EINVAL, "dense matrix values are NULL");
  fb_mat *m;
  rc = dense_alloc(nrows, ncols, &m, err);
  if (rc)
    return rc;
  for (size_t j = 0; j < ncols; ++j)
    for (size_t i = 0; i < nrows; ++i)
      m->vals[i + j * nrows] = rowmajor[i * ncols + j];
  *out = m;
  return FB_OK;
}

static int check_triplets(size_t nrows, size_t ncols, size_t nnz, const size_t *rows,
                          const size_t *cols, const double *vals, fb_err *err)
{
  if (nnz && (!rows || !cols || !vals))
    return fb_err_set(err, FB_EINVAL, "triplet arrays are NULL");
  for (size_t k = 0; k < nnz; ++k) {
    if (rows[k] >= nrows || cols[k] >= ncols)
      return fb_err_set(err, FB_EINVAL,
                        "triplet %zu: entry (%zu, %zu) outside a %zu x %zu matrix", k, rows[k],
                        cols[k], nrows, ncols);
  }
  return FB_OK;
}

/* Stable counting sort of the permutation `in` by key[in[k]] < nkeys
 * into `out`; count has nkeys+1 slots (Knuth TAOCP vol. 3, 5.2 Algorithm D
 * applied as one digit of an LSD radix sort). */
static void counting_sort(size_t n, const size_t *in, const size_t *key, size_t nkeys,
                          size_t *count, size_t *out)
{
  memset(count, 0, (nkeys + 1) * sizeof *count);
  for (size_t k = 0; k < n; ++k)
    ++count[key[in[k]] + 1];
  for (size_t c = 0; c < nkeys; ++c)
    count[c + 1] += count[c];
  for (size_t k = 0; k < n; ++k)
    out[count[key[in[k]]]++] = in[k];
}

/* Fills sparse m from triplets visited in (col, row) order via perm,
 * summing runs of equal (row, col) and keeping zero sums out. */
static void csc_from_sorted_triplets(fb_mat *m, size_t nnz, const size_t *perm,
                                     const size_t *rows, const size_t *cols, const double *vals)
{
  size_t k = 0;
  while (k < nnz) {
    const size_t r = rows[perm[k]], c = cols[perm[k]];
    double sum = 0.0;
    for (; k < nnz && rows[perm[k]] == r && cols[perm[k]] == c; ++k)
      sum += vals[perm[k]];
    if (sum != 0.0) {
      m->rowidx[m->nnz] = r;
      m->vals[m->nnz++] = sum;
      ++m->colptr[c + 1];
    }
  }
  for (size_t c = 0; c < m->ncols; ++c)
    m->colptr[c + 1] += m->colptr[c];
}

int fb_mat_new_triplets(size_t nrows, size_t ncols, size_t nnz, const size_t *rows,
                        const size_t *cols, const double *vals, fb_mat **out, fb_err *err)
{
  int rc = check_out(out, err);
  if (!rc)
    rc = check_triplets(nrows, ncols, nnz, rows, cols, vals, err);
  if (rc)
    return rc;
  fb_mat *m;
  rc = sparse_alloc(nrows, ncols, nnz, &m, err);
  if (rc)
    return rc;
  const size_t nkeys = nrows > ncols ? nrows : ncols;
  size_t *ident = alloc_array(nnz, sizeof *ident);
  size_t *by_row = alloc_array(nnz, sizeof *by_row);
  size_t *by_col = alloc_array(nnz, sizeof *by_col);
  size_t *count = nkeys < SIZE_MAX ? alloc_array(nkeys + 1, sizeof *count) : NULL;
  if (ident && by_row && by_col && count) {
    for (size_t k = 0; k < nnz; ++k)
      ident[k] = k;
    /* Radix sort: by row, then stably by column, gives (col, row) order. */
    counting_sort(nnz, ident, rows, nrows, count, by_row);
    counting_sort(nnz, by_row, cols, ncols, count, by_col);
    csc_from_sorted_triplets(m, nnz, by_col, rows, cols, vals);
  } else {
    fb_mat_free(&m);
    rc = oom(err);
  }
  free(ident);
  free(by_row);
  free(by_col);
  free(count);
  *out = m;
  return rc;
}

int fb_mat_new_csc(size_t nrows, size_t ncols, const size_t *colptr, const size_t *rowidx,
                   const double *vals, fb_mat **out, fb_err *err)
{
  int rc = check_out(out, err);
  if (!rc && (!colptr || colptr[0] != 0))
    rc =
        fb_err_set(err, FB_EINVAL, "compressed columns: colptr is NULL or does not start at 0");
  const size_t nnz = rc ? 0 : colptr[ncols];
  if (!rc && nnz && (!rowidx || !vals))
    rc = fb_err_set(err, FB_EINVAL, "compressed columns: NULL arrays");
  for (size_t j = 0; !rc && j < ncols; ++j) {
    if (colptr[j + 1] < colptr[j])
      rc =
          fb_err_set(err, FB_EINVAL, "compressed columns: column %zu ends before it starts", j);
    for (size_t k = colptr[j]; !rc && k < colptr[j + 1]; ++k)
      if (rowidx[k] >= nrows || (k > colptr[j] && rowidx[k] <= rowidx[k - 1]))
        rc = fb_err_set(err, FB_EINVAL,
                        "compressed columns: column %zu's row %zu is out of range or order", j,
                        rowidx[k]);
  }
  if (rc)
    return rc;
  fb_mat *m;
  rc = sparse_alloc(nrows, ncols, nnz, &m, err);
  if (rc)
    return rc;
  memcpy(m->colptr, colptr, (ncols + 1) * sizeof *colptr);
  if (nnz) {
    memcpy(m->rowidx, rowidx, nnz * sizeof *rowidx);
    memcpy(m->vals, vals, nnz * sizeof *vals);
  }
  m->nnz = nnz;
  *out = m;
  return FB_OK;
}

/* Diagonal matrix with entries diag[i], or s everywhere when diag is NULL;
 * zero entries are not stored. */
static int new_diag_or_scaled(size_t n, const double *diag, double s, fb_mat **out, fb_err *err)
{
  int rc = check_out(out, err);
  if (rc)
    return rc;
  fb_mat *m;
  rc = sparse_alloc(n, n, n, &m, err);
  if (rc)
    return rc;
  for (size_t j = 0; j < n; ++j) {
    const double v = diag ? diag[j] : s;
    if (v != 0.0) {
      m->rowidx[m->nnz] = j;
      m->vals[m->nnz++] = v;
    }
    m->colptr[j + 1] = m->nnz;
  }
  *out = m;
  return FB_OK;
}

int fb_mat_new_diag(size_t n, const double *diag, fb_mat **out, fb_err *err)
{
  if (!diag && n)
    return fb_err_set(err, FB_EINVAL, "diagonal values are NULL");
  return new_diag_or_scaled(n, diag, 0.0, out, err);
}

int fb_mat_new_scaled_identity(size_t n, double s, fb_mat **out, fb_err *err)
{
  return new_diag_or_scaled(n, NULL, s, out, err);
}

int fb_mat_clone(const fb_mat *a, fb_mat **out, fb_err *err)
{
  int rc = check_out(out, err);
  if (rc)
    return rc;
  if (!a)
    return fb_err_set(err, FB_EINVAL, "matrix is NULL");
  if (!a->sparse)
    return fb_mat_new_dense(a->nrows, a->ncols, a->vals, out, err);
  fb_mat *m;
  rc = sparse_alloc(a->nrows, a->ncols, a->nnz, &m, err);
  if (rc)
    return rc;
  m->nnz = a->nnz;
  memcpy(m->colptr, a->colptr, (a->ncols + 1) * sizeof *m->colptr);
  if (a->nnz) {
    memcpy(m->rowidx, a->rowidx, a->nnz * sizeof *m->rowidx);
    memcpy(m->vals, a->vals, a->nnz * sizeof *m->vals);
  }
  *out = m;
  return FB_OK;
}

/* Sparse transpose by counting sort on the row index; scanning the source
 * columns in order leaves the rows of each result column sorted, whatever
 * the row order of the source (Davis, Direct Methods for Sparse Linear
 * Systems, SIAM 2006, section 2.5). */
static int sparse_transpose(const fb_mat *a, fb_mat **out, fb_err *err)
{
  fb_mat *t;
  int rc = sparse_alloc(a->ncols, a->nrows, a->nnz, &t, err);
  if (rc)
    return rc;
  size_t *next = alloc_array(a->nrows, sizeof *next);
  if (!next) {
    fb_mat_free(&t);
    return oom(err);
  }
  for (size_t p = 0; p < a->nnz; ++p)
    ++t->colptr[a->rowidx[p] + 1];
  for (size_t i = 0; i < a->nrows; ++i) {
    t->colptr[i + 1] += t->colptr[i];
    next[i] = t->colptr[i];
  }
  for (size_t j = 0; j < a->ncols; ++j) {
    for (size_t p = a->colptr[j]; p < a->colptr[j + 1]; ++p) {
      const size_t q = next[a->rowidx[p]]++;
      t->rowidx[q] = j;
      t->vals[q] = a->vals[p];
    }
  }
  t->nnz = a->nnz;
  free(next);
  *out = t;
  return FB_OK;
}

int fb_mat_transpose(const fb_mat *a, fb_mat **out, fb_err *err)
{
  int rc = check_out(out, err);
  if (rc)
    return rc;
  if (!a)
    return fb_err_set(err, FB_EINVAL, "matrix is NULL");
  if (a->sparse)
    return sparse_transpose(a, out, err);
  fb_mat *t;
  rc = dense_alloc(a->ncols, a->nrows, &t, err);
  if (rc)
    return rc;
  for (size_t j = 0; j < a->ncols; ++j)
    for (size_t i = 0; i < a->nrows; ++i)
      t->vals[j + i * a->ncols] = a->vals[i + j * a->nrows];
  *out = t;
  return FB_OK;
}

/* Sparse copy of a dense matrix keeping its nonzero values. */
static int dense_to_sparse(const fb_mat *a, fb_mat **out, fb_err *err)
{
  size_t nonzeros = 0;
  for (size_t p = 0; p < a->nnz; ++p)
    nonzeros += a->vals[p] != 0.0;
  fb_mat *s;
  int rc = sparse_alloc(a->nrows, a->ncols, nonzeros, &s, err);
  if (rc)
    return rc;
  for (size_t j = 0; j < a->ncols; ++j) {
    for (size_t i = 0; i < a->nrows; ++i) {
      const double v = a->vals[i + j * a->nrows];
      if (v != 0.0) {
        s->rowidx[s->nnz] = i;
        s->vals[s->nnz++] = v;
      }
    }
    s->colptr[j + 1] = s->nnz;
  }
  *out = s;
  return FB_OK;
}

static int dense_multiply(const fb_mat *a, const fb_mat *b, fb_mat **out, fb_err *err)
{
  fb_mat *c;
  int rc = dense_alloc(a->nrows, b->ncols, &c, err);
  if (rc)
    return rc;
  for (size_t j = 0; j < b->ncols; ++j) {
    double *cj = c->vals + j * c->nrows;
    for (size_t i = 0; i < c->nrows; ++i)
      cj[i] = 0.0;
    for (size_t k = 0; k < a->ncols; ++k) {
      const double bkj = b->vals[k + j * b->nrows];
      const double *ak = a->vals + k * a->nrows;
      for (size_t i = 0; i < a->nrows; ++i)
        cj[i] += ak[i] * bkj;
    }
  }
  *out = c;
  return FB_OK;
}

/* Grows the entry arrays of sparse c to hold at least need entries. */
static int sparse_reserve(fb_mat *c, size_t *cap, size_t need, fb_err *err)
{
  if (need <= *cap)
    return FB_OK;
  size_t grown = *cap > SIZE_MAX / 2 ? need : 2 * *cap;
  if (grown < need)
    grown = need;
  if (grown > SIZE_MAX / sizeof(double))
    return oom(err);
  size_t *rowidx = realloc(c->rowidx, grown * sizeof *rowidx);
  if (rowidx)
    c->rowidx = rowidx;
  double *vals = realloc(c->vals, grown * sizeof *vals);
  if (vals)
    c->vals = vals;
  if (!rowidx || !vals)
    return oom(err);
  *cap = grown;
  return FB_OK;
}

/* Workspace of the column-by-column sparse product. */
typedef struct spgemm_work {
  double *acc;  /* accumulated values of the current column, by row */
  size_t *mark; /* mark[i] == j+1 when row i is already in column j */
} spgemm_work;

/* Appends column j of a*b to c (rows unsorted; exact cancellations are
 * dropped so the no-stored-zero invariant holds). */
static int spgemm_column(const fb_mat *a, const fb_mat *b, size_t j, spgemm_work *w, fb_mat *c,
                         size_t *cap, fb_err *err)
{
  size_t bound = 0;
  for (size_t p = b->colptr[j]; p < b->colptr[j + 1]; ++p) {
    const size_t k = b->rowidx[p];
    bound += a->colptr[k + 1] - a->colptr[k];
  }
  if (bound > c->nrows)
    bound = c->nrows;
  int rc = sparse_reserve(c, cap, c->nnz + bound, err);
  if (rc)
    return rc;
  const size_t start = c->nnz;
  for (size_t p = b->colptr[j]; p < b->colptr[j + 1]; ++p) {
    const size_t k = b->rowidx[p];
    for (size_t q = a->colptr[k]; q < a->colptr[k + 1]; ++q) {
      const size_t i = a->rowidx[q];
      if (w->mark[i] != j + 1) {
        w->mark[i] = j + 1;
        w->acc[i] = 0.0;
        c->rowidx[c->nnz++] = i;
      }
      w->acc[i] += a->vals[q] * b->vals[p];
    }
  }
  size_t kept = start;
  for (size_t p = start; p < c->nnz; ++p) {
    const size_t i = c->rowidx[p];
    if (w->acc[i] != 0.0) {
      c->rowidx[kept] = i;
      c->vals[kept++] = w->acc[i];
    }
  }
  c->nnz = kept;
  c->colptr[j + 1] = kept;
  return FB_OK;
}

/* Sparse product by Gustavson's column algorithm (ACM TOMS 4(3), 1978);
 * rows come out unsorted, so the result is transposed twice to sort them. */
static int sparse_multiply(const fb_mat *a, const fb_mat *b, fb_mat **out, fb_err *err)
{
  fb_mat *c = NULL, *ct = NULL;
  size_t cap = a->nnz + b->nnz;
  spgemm_work w = {alloc_array(a->nrows, sizeof *w.acc), calloc(a->nrows + 1, sizeof *w.mark)};
  int rc = sparse_alloc(a->nrows, b->ncols, cap, &c, err);
  if (!rc && (!w.acc || !w.mark))
    rc = oom(err);
  for (size_t j = 0; !rc && j < b->ncols; ++j)
    rc = spgemm_column(a, b, j, &w, c, &cap, err);
  if (!rc)
    rc = sparse_transpose(c, &ct, err);
  if (!rc)
    rc = sparse_transpose(ct, out, err);
  fb_mat_free(&c);
  fb_mat_free(&ct);
  free(w.acc);
  free(w.mark);
  return rc;
}

int fb_mat_multiply(const fb_mat *a, const fb_mat *b, fb_mat **out, fb_err *err)
{
  int rc = check_out(out, err);
  if (rc)
    return rc;
  if (!a || !b)
    return fb_err_set(err, FB_EINVAL, "matrix is NULL");
  if (a->ncols != b->nrows)
    return fb_err_set(err, FB_EINVAL, "cannot multiply a %zu x %zu matrix by a %zu x %zu one",
                      a->nrows, a->ncols, b->nrows, b->ncols);
  if (!a->sparse && !b->sparse)
    return dense_multiply(a, b, out, err);
  fb_mat *as = NULL, *bs = NULL;
  if (!a->sparse)
    rc = dense_to_sparse(a, &as, err);
  if (!rc && !b->sparse)
    rc = dense_to_sparse(b, &bs, err);
  if (!rc)
    rc = sparse_multiply(as ? as : a, bs ? bs : b, out, err);
  fb_mat_free(&as);
  fb_mat_free(&bs);
  return rc;
}

size_t fb_mat_nrows(const fb_mat *a)
{
  return a->nrows;
}

size_t fb_mat_ncols(const fb_mat *a)
{
  return a->ncols;
}

int fb_mat_is_sparse(const fb_mat *a)
{
  return a->sparse;
}

size_t fb_mat_nnz(const fb_mat *a)
{
  return a->nnz;
}

/* Entry (i, j); 0 when not stored, including indices out of range. */
double fb_mat_get(const fb_mat *a, size_t i, size_t j)
{
  if (i >= a->nrows || j >= a->ncols)
    return 0.0;
  if (!a->sparse)
    return a->vals[i + j * a->nrows];
  size_t lo = a->colptr[j], hi = a->colptr[j + 1];
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    if (a->rowidx[mid] < i)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < a->colptr[j + 1] && a->rowidx[lo] == i ? a->vals[lo] : 0.0;
}

void fb_mat_foreach(const fb_mat *a, fb_mat_visit_fn fn, void *ctx)
{
  for (size_t j = 0; j < a->ncols; ++j) {
    if (a->sparse) {
      for (size_t p = a->colptr[j]; p < a->colptr[j + 1]; ++p)
        fn(ctx, a->rowidx[p], j, a->vals[p]);
      continue;
    }
    for (size_t i = 0; i < a->nrows; ++i) {
      const double v = a->vals[i + j * a->nrows];
      if (v != 0.0)
        fn(ctx, i, j, v);
    }
  }
}

typedef struct triplet_sink {
  size_t *row, *col;
  double *val;
  size_t n;
} triplet_sink;

static void add_triplet(void *ctx, size_t row, size_t col, double val)
{
  triplet_sink *t = ctx;
  t->row[t->n] = row;
  t->col[t->n] = col;
  t->val[t->n++] = val;
}

size_t fb_mat_triplets(const fb_mat *a, size_t *row, size_t *col, double *val)
{
  triplet_sink t = {row, col, val, 0};
  fb_mat_foreach(a, add_triplet, &t);
  return t.n;
}

/* y = beta * y with beta == 0 meaning "overwrite", as in BLAS dgemv. */
static void scale_y(size_t n, double beta, double *y)
{
  for (size_t i = 0; i < n; ++i)
    y[i] = beta == 0.0 ? 0.0 : beta * y[i];
}

void fb_mat_gemv(const fb_mat *a, double alpha, const double *x, double beta, double *y)
{
  scale_y(a->nrows, beta, y);
  for (size_t j = 0; j < a->ncols; ++j) {
    const double axj = alpha * x[j];
    if (a->sparse) {
      for (size_t p = a->colptr[j]; p < a->colptr[j + 1]; ++p)
        y[a->rowidx[p]] += a->vals[p] * axj;
      continue;
    }
    const double *aj = a->vals + j * a->nrows;
    for (size_t i = 0; i < a->nrows; ++i)
      y[i] += aj[i] * axj;
  }
}

void fb_mat_gemv_t(const fb_mat *a, double alpha, const double *x, double beta, double *y)
{
  for (size_t j = 0; j < a->ncols; ++j) {
    double dot = 0.0;
    if (a->sparse) {
      for (size_t p = a->colptr[j]; p < a->colptr[j + 1]; ++p)
        dot += a->vals[p] * x[a->rowidx[p]];
    } else {
      const double *aj = a->vals + j * a->nrows;
      for (size_t i = 0; i < a->nrows; ++i)
        dot += aj[i] * x[i];
    }
    y[j] = alpha * dot + (beta == 0.0 ? 0.0 : beta * y[j]);
  }
}

int fb_mat_all_finite(const fb_mat *a)
{
  for (size_t p = 0; p < a->nnz; ++p)
    if (!isfinite(a->vals[p]))
      return 0;
  return 1;
}

static double max_abs(const fb_mat *a)
{
  double m = 0.0;
  for (size_t p = 0; p < a->nnz; ++p)
    m = fmax(m, fabs(a->vals[p]));
  return m;
}

/* Checking each stored (i, j) against a_ji covers all pairs: a pair with
 * only a_ji stored is checked when (j, i) is visited. NaN entries fail. */
int fb_mat_is_symmetric(const fb_mat *a, double tol)
{
  if (a->nrows != a->ncols)
    return 0;
  const double bound = tol * max_abs(a);
  for (size_t j = 0; j < a->ncols; ++j) {
    const size_t begin = a->sparse ? a->colptr[j] : 0;
    const size_t end = a->sparse ? a->colptr[j + 1] : a->nrows;
    for (size_t p = begin; p < end; ++p) {
      const size_t i = a->sparse ? a->rowidx[p] : p;
      const double aij = a->sparse ? a->vals[p] : a->vals[i + j * a->nrows];
      if (!(fabs(aij - fb_mat_get(a, j, i)) <= bound))
        return 0;
    }
  }
  return 1;
}

int fb_mat_axpby(double alpha, const fb_mat *a, double beta, const fb_mat *b, fb_mat **out,
                 fb_err *err)
{
  *out = NULL;
  if (b && (b->nrows != a->nrows || b->ncols != a->ncols))
    return fb_err_set(err, FB_EINVAL, "fb_mat_axpby: %zu x %zu plus %zu x %zu", a->nrows,
                      a->ncols, b->nrows, b->ncols);
  const size_t cap = a->nnz + (b ? b->nnz : 0) + 1;
  size_t *rows = malloc(cap * sizeof(size_t)), *cols = malloc(cap * sizeof(size_t));
  double *vals = malloc(cap * sizeof(double));
  int rc = rows && cols && vals ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc) {
    const size_t na = fb_mat_triplets(a, rows, cols, vals);
    const size_t nb = b ? fb_mat_triplets(b, rows + na, cols + na, vals + na) : 0;
    for (size_t k = 0; k < na + nb; ++k)
      vals[k] *= k < na ? alpha : beta;
    rc = fb_mat_new_triplets(a->nrows, a->ncols, na + nb, rows, cols, vals, out, err);
  }
  free(rows);
  free(cols);
  free(vals);
  return rc;
}
