/* SPDX-License-Identifier: BSD-3-Clause */
/* result_compare OLD.csv NEW.csv: checks that a result CSV written by
 * `flexbond run` (a header line, then one row per sample: t, then the
 * outputs) reproduces a reference one, sample by sample.
 *
 * The two files must have the same header line, the same number of rows
 * and the same time column (the same doubles: both are printed from one
 * sample grid). Then, for every output column j of OLD, with range
 * R_j = max(old_j) - min(old_j) over all samples,
 *
 *   max_k |new_kj - old_kj| <= REL_TOL * R_j          if R_j > 0,
 *   max_k |new_kj - old_kj| <= ZERO_RANGE_ABS_TOL     if R_j = 0.
 *
 * One line per column gives the worst difference relative to the range,
 * the row (1-based sample number; the file line is one more, after the
 * header) and time where it occurs, and both values. A failing column
 * also says how many samples exceed the tolerance.
 *
 * Exit status: 0 all columns within tolerance, 1 some column is not (or
 * the header, row count or time column differ), 2 bad usage or a file that
 * cannot be read or parsed. fb_result_diff (flexbond/sim.h) does not serve
 * here: it takes simulated results, not CSV files, and accepts sample times
 * that differ by up to 1e-9 s. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A reference column that varies: the new one may differ from it by at
 * most 1e-4 of its range at every sample. The reference and a correct
 * build are each an integration at the scenario's tolerances (rtol 1e-6,
 * atol 1e-8) of the same model, each within its global error of the
 * exact solution, and never closer than that: other BLAS kernels, thread
 * counts, step sequences or eigen-solvers move the result within it.
 * Measured on the APC (tests/data/apc6x6_5b32e25/README.md): the
 * reference lies within 9.0e-6 of a column's range of a run at rtol
 * 1e-10, atol 1e-12 (the converged solution), and the build within
 * 5.3e-6 of the reference; 1e-4 allows five times their sum. A change
 * of the model shows above it: a tire stiffness 1 % stiffer moves every
 * column of either system by 1.7e-4 (driver_acc) to 8.0e-3 (tire_defl_RM)
 * of its range; a change of 0.5 % or less would pass. */
#define REL_TOL 1e-4
/* A reference column that is constant (range 0) has no scale to be
 * relative to: the rigid hull's torsion angle is exactly zero at every
 * sample, as that hull cannot twist. An absolute bound is used instead;
 * 1e-12 (rad, for the torsion) allows a round-off-sized nonzero and is
 * seven orders of magnitude below the flexible hull's torsion (~1e-5 rad),
 * so any real twist fails. */
#define ZERO_RANGE_ABS_TOL 1e-12

typedef struct table {
  const char *path;
  char *header; /* first line, without its line end */
  size_t ncols; /* fields in the header */
  size_t nrows; /* data rows */
  double *data; /* nrows x ncols, row-major */
  char **names; /* ncols header fields (pointers into names_buf) */
  char *names_buf;
} table;

static void strip_eol(char *s)
{
  size_t n = strlen(s);
  while (n > 0 && (s[n - 1] == '\n' || s[n - 1] == '\r'))
    s[--n] = '\0';
}

static void table_free(table *t)
{
  free(t->header);
  free(t->data);
  free(t->names);
  free(t->names_buf);
}

/* Reads path into t; on failure prints why and returns -1. */
static int table_read(const char *path, table *t)
{
  memset(t, 0, sizeof *t);
  t->path = path;
  FILE *fp = fopen(path, "r");
  if (!fp) {
    fprintf(stderr, "result_compare: %s: %s\n", path, strerror(errno));
    return -1;
  }
  char *line = NULL;
  size_t cap = 0;
  int rc = -1;
  if (getline(&line, &cap, fp) < 0) {
    fprintf(stderr, "result_compare: %s: no header line\n", path);
    goto done;
  }
  strip_eol(line);
  t->header = strdup(line);
  t->names_buf = strdup(line);
  if (!t->header || !t->names_buf)
    goto oom;
  t->ncols = 1;
  for (const char *p = line; *p; ++p)
    t->ncols += *p == ',';
  t->names = malloc(t->ncols * sizeof *t->names);
  if (!t->names)
    goto oom;
  char *field = t->names_buf;
  for (size_t j = 0; j < t->ncols; ++j) {
    t->names[j] = field;
    char *comma = strchr(field, ',');
    if (comma) {
      *comma = '\0';
      field = comma + 1;
    }
  }
  size_t rows_cap = 0;
  for (size_t lineno = 2; getline(&line, &cap, fp) >= 0; ++lineno) {
    strip_eol(line);
    if (t->nrows == rows_cap) {
      rows_cap = rows_cap ? 2 * rows_cap : 1024;
      double *d = realloc(t->data, rows_cap * t->ncols * sizeof *d);
      if (!d)
        goto oom;
      t->data = d;
    }
    double *row = t->data + t->nrows * t->ncols;
    const char *p = line;
    for (size_t j = 0; j < t->ncols; ++j) {
      char *end;
      errno = 0;
      row[j] = strtod(p, &end);
      /* ERANGE on underflow still gives the nearest double (a subnormal
       * or zero), which is what the file says; overflow does not. */
      if (end == p || (*end != (j + 1 < t->ncols ? ',' : '\0')) ||
          (errno == ERANGE && isinf(row[j]))) {
        fprintf(stderr, "result_compare: %s:%zu: field %zu ('%s') is not a number%s\n", path,
                lineno, j + 1, t->names[j],
                j + 1 < t->ncols ? " followed by ','" : " ending the line");
        goto done;
      }
      p = end + 1;
    }
    ++t->nrows;
  }
  if (ferror(fp)) {
    fprintf(stderr, "result_compare: %s: read error\n", path);
    goto done;
  }
  rc = 0;
  goto done;
oom:
  fprintf(stderr, "result_compare: %s: out of memory\n", path);
done:
  free(line);
  fclose(fp);
  if (rc)
    table_free(t);
  return rc;
}

/* The same header, row count and time column; prints the first mismatch. */
static int same_grid(const table *a, const table *b)
{
  if (strcmp(a->header, b->header) != 0) {
    fprintf(stderr, "result_compare: FAIL: header differs:\n  old: %s\n  new: %s\n", a->header,
            b->header);
    return 0;
  }
  if (a->nrows != b->nrows) {
    fprintf(stderr, "result_compare: FAIL: %zu rows in %s, %zu in %s\n", a->nrows, a->path,
            b->nrows, b->path);
    return 0;
  }
  for (size_t k = 0; k < a->nrows; ++k) {
    double ta = a->data[k * a->ncols], tb = b->data[k * b->ncols];
    if (ta != tb) {
      fprintf(stderr,
              "result_compare: FAIL: column '%s' (time), row %zu (line %zu): old %.17g, new "
              "%.17g\n",
              a->names[0], k + 1, k + 2, ta, tb);
      return 0;
    }
  }
  return 1;
}

int main(int argc, char **argv)
{
  if (argc != 3) {
    fprintf(stderr, "usage: result_compare OLD.csv NEW.csv\n");
    return 2;
  }
  table old, new;
  if (table_read(argv[1], &old))
    return 2;
  if (table_read(argv[2], &new)) {
    table_free(&old);
    return 2;
  }
  int failed = 0;
  if (old.ncols < 2 || old.nrows == 0) {
    fprintf(stderr, "result_compare: %s: no output column or no sample\n", old.path);
    failed = 2;
  } else if (!same_grid(&old, &new)) {
    failed = 1;
  }
  if (!failed)
    printf("result_compare: %s vs %s: %zu rows, %zu outputs; tolerance %.0e x range, or "
           "%.0e absolute for a constant reference column\n",
           old.path, new.path, old.nrows, old.ncols - 1, REL_TOL, ZERO_RANGE_ABS_TOL);
  /* Every column is checked and listed, failing or not. */
  int differs = 0;
  for (size_t j = 1; !failed && j < old.ncols; ++j) {
    const size_t n = old.ncols;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t k = 0; k < old.nrows; ++k) {
      double v = old.data[k * n + j];
      if (!isfinite(v)) {
        fprintf(stderr, "result_compare: %s: row %zu of '%s' is %g\n", old.path, k + 1,
                old.names[j], v);
        failed = 2;
      }
      lo = fmin(lo, v);
      hi = fmax(hi, v);
    }
    if (failed)
      break;
    const double range = hi - lo;
    const double tol = range > 0 ? REL_TOL * range : ZERO_RANGE_ABS_TOL;
    double worst = 0;
    size_t worst_k = 0, nbad = 0;
    for (size_t k = 0; k < old.nrows; ++k) {
      double d = fabs(new.data[k * n + j] - old.data[k * n + j]);
      if (isnan(d))
        d = INFINITY; /* a NaN in the new file is as far off as can be */
      if (d > worst) {
        worst = d;
        worst_k = k;
      }
      nbad += !(d <= tol);
    }
    const double t = old.data[worst_k * n], vo = old.data[worst_k * n + j],
                 vn = new.data[worst_k * n + j];
    if (range > 0)
      printf("  %-16s range %-12.6g max|diff| %-12.6g = %9.3e x range", old.names[j], range,
             worst, worst / range);
    else
      printf("  %-16s range 0 (constant %.6g): max|diff| %.6g absolute", old.names[j], lo,
             worst);
    if (worst > 0)
      printf("  at row %zu, t = %.10g: old %.17g, new %.17g", worst_k + 1, t, vo, vn);
    printf("%s\n", nbad ? "  FAIL" : "");
    if (nbad) {
      char what[64];
      if (range > 0)
        snprintf(what, sizeof what, "%g x the reference's range", REL_TOL);
      else
        snprintf(what, sizeof what, "absolute: the reference is constant");
      fprintf(stderr,
              "result_compare: FAIL: column '%s': %zu of %zu samples differ by more than %.6g "
              "(%s); worst at row %zu (line %zu), t = %.10g s: old %.17g, new %.17g, |diff| "
              "%.6g\n",
              old.names[j], nbad, old.nrows, tol, what, worst_k + 1, worst_k + 2, t, vo, vn,
              worst);
      differs = 1;
    }
  }
  if (!failed && differs)
    failed = 1;
  table_free(&old);
  table_free(&new);
  return failed;
}
