/* SPDX-License-Identifier: BSD-3-Clause */
/* Tabulated one-port laws y = phi(x) (see flexbond/bg.h), e.g. a damper's
 * force-velocity curve used as an R element's law e = phi(f).
 *
 * Interpolation: the monotone piecewise cubic Hermite scheme of Fritsch &
 * Carlson (SIAM J. Numer. Anal. 17(2), 238-246, 1980). On [x_k, x_k+1]
 * with h = x_k+1 - x_k, s = x - x_k, secant delta_k and knot derivatives
 * d_k, d_k+1 the cubic is
 *   phi = y_k + s (d_k + s (c2 + s c3)),
 *   c2 = (3 delta_k - 2 d_k - d_k+1) / h,  c3 = (d_k + d_k+1 - 2 delta_k) / h^2,
 * which matches y and d at both ends, so phi is C1 at the knots whatever
 * the d_k are. The d_k follow the paper's algorithm: start from the
 * three-point average of the neighbouring secants (0 at a local extremum
 * of the data, the end secants at the ends), then scale the pair of each
 * interval onto the circle alpha^2 + beta^2 <= 9 (alpha = d_k / delta_k,
 * beta = d_k+1 / delta_k), one of the paper's sufficient conditions for
 * the cubic to be monotone on the interval. Scaling only shrinks
 * derivatives, which keeps the neighbouring interval inside the circle,
 * so one pass suffices. Beyond the ends phi continues along
 * its end tangents, which keeps phi and phi' continuous there too. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bg.h"

#include "core/textfile.h"
#include "core/util.h"

struct fb_table_law {
  size_t n;      /* number of knots, >= 2 */
  double *x;     /* knots, strictly increasing */
  double *y;     /* values at the knots */
  double *d;     /* derivatives phi'(x_k) */
  double *area;  /* area[k] = integral of phi from x_0 to x_k */
  double area0;  /* integral of phi from x_0 to 0 */
  double data[]; /* storage of x, y, d, area (4 n doubles) */
};

/* ---- Construction. */

/* n >= 2, finite, x strictly increasing; messages count knots from 1. */
static int check_knots(size_t n, const double *x, const double *y, fb_err *err)
{
  if (n < 2)
    return fb_err_set(err, FB_EINVAL, "table law needs at least 2 points (got %zu)", n);
  if (!x || !y)
    return fb_err_set(err, FB_EINVAL, "table law: NULL knots");
  for (size_t i = 0; i < n; ++i) {
    if (!isfinite(x[i]) || !isfinite(y[i]))
      return fb_err_set(err, FB_EINVAL, "table law: point %zu (%g, %g) is not finite", i + 1,
                        x[i], y[i]);
    if (i > 0 && !(x[i] > x[i - 1]))
      return fb_err_set(err, FB_EINVAL,
                        "table law: x must be strictly increasing, but point %zu (x = %g) "
                        "does not exceed point %zu (x = %g)",
                        i + 1, x[i], i, x[i - 1]);
  }
  return FB_OK;
}

static double secant(const fb_table_law *law, size_t k)
{
  return (law->y[k + 1] - law->y[k]) / (law->x[k + 1] - law->x[k]);
}

/* Fritsch & Carlson's initial derivatives: mean of the adjacent secants
 * where they agree in sign, 0 at a local extremum or flat spot (so each
 * interval's alpha and beta are >= 0), the end secants at the ends. */
static void initial_slopes(fb_table_law *law)
{
  const size_t n = law->n;
  law->d[0] = secant(law, 0);
  law->d[n - 1] = secant(law, n - 2);
  for (size_t k = 1; k + 1 < n; ++k) {
    double left = secant(law, k - 1), right = secant(law, k);
    law->d[k] = left * right > 0 ? 0.5 * (left + right) : 0.0;
  }
}

/* Scales each interval's derivative pair onto alpha^2 + beta^2 <= 9
 * (Fritsch & Carlson's circle of radius 3). */
static void limit_slopes(fb_table_law *law)
{
  for (size_t k = 0; k + 1 < law->n; ++k) {
    double delta = secant(law, k);
    if (delta == 0)
      continue; /* both derivatives are already 0 */
    double alpha = law->d[k] / delta, beta = law->d[k + 1] / delta;
    double radius2 = alpha * alpha + beta * beta;
    if (radius2 > 9) {
      double tau = 3 / sqrt(radius2);
      law->d[k] = tau * alpha * delta;
      law->d[k + 1] = tau * beta * delta;
    }
  }
}

/* Index k of the interval [x_k, x_k+1] holding x, clamped to 0 .. n-2. */
static size_t find_interval(const fb_table_law *law, double x)
{
  size_t lo = 0, hi = law->n - 1; /* invariant: x_lo <= x < x_hi unless clamped */
  while (hi - lo > 1) {
    size_t mid = lo + (hi - lo) / 2;
    if (x < law->x[mid])
      hi = mid;
    else
      lo = mid;
  }
  return lo;
}

/* Cubic coefficients c2, c3 of interval k (see the top of the file). */
static void cubic(const fb_table_law *law, size_t k, double *c2, double *c3)
{
  double h = law->x[k + 1] - law->x[k], delta = secant(law, k);
  double dl = law->d[k], dr = law->d[k + 1];
  *c2 = (3 * delta - 2 * dl - dr) / h;
  *c3 = (dl + dr - 2 * delta) / (h * h);
}

/* Integral of phi from x_0 to x. Inside the table: area of the whole
 * intervals plus the integral of the cubic over [x_k, x]; outside: the
 * integral of the tangent line. */
static double area_from_start(const fb_table_law *law, double x)
{
  const size_t last = law->n - 1;
  if (x <= law->x[0]) {
    double s = x - law->x[0];
    return s * (law->y[0] + 0.5 * law->d[0] * s);
  }
  if (x >= law->x[last]) {
    double s = x - law->x[last];
    return law->area[last] + s * (law->y[last] + 0.5 * law->d[last] * s);
  }
  size_t k = find_interval(law, x);
  double c2, c3, s = x - law->x[k];
  cubic(law, k, &c2, &c3);
  return law->area[k] + s * (law->y[k] + s * (law->d[k] / 2 + s * (c2 / 3 + s * c3 / 4)));
}

/* Cumulative areas at the knots: the Hermite cubic integrates exactly to
 * h (y_k + y_k+1) / 2 + h^2 (d_k - d_k+1) / 12 (Simpson-like closed form,
 * obtained by integrating the cubic term by term). */
static void cumulative_areas(fb_table_law *law)
{
  law->area[0] = 0;
  for (size_t k = 0; k + 1 < law->n; ++k) {
    double h = law->x[k + 1] - law->x[k];
    law->area[k + 1] = law->area[k] + h * (law->y[k] + law->y[k + 1]) / 2 +
                       h * h * (law->d[k] - law->d[k + 1]) / 12;
  }
  law->area0 = area_from_start(law, 0.0);
}

int fb_table_law_new(size_t n, const double *x, const double *y, fb_table_law **out,
                     fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "fb_table_law_new: NULL out");
  *out = NULL;
  int rc = check_knots(n, x, y, err);
  if (rc)
    return rc;
  fb_table_law *law = malloc(sizeof *law + 4 * n * sizeof law->data[0]);
  if (!law)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a table law of %zu points", n);
  law->n = n;
  law->x = law->data;
  law->y = law->data + n;
  law->d = law->data + 2 * n;
  law->area = law->data + 3 * n;
  memcpy(law->x, x, n * sizeof *x);
  memcpy(law->y, y, n * sizeof *y);
  initial_slopes(law);
  limit_slopes(law);
  cumulative_areas(law);
  *out = law;
  return FB_OK;
}

void fb_table_law_free(fb_table_law **law)
{
  if (!law)
    return;
  free(*law);
  *law = NULL;
}

/* ---- Evaluation. */

double fb_table_law_eval(const fb_table_law *law, double x, double *slope)
{
  const size_t last = law->n - 1;
  /* Tangent lines beyond the ends. */
  size_t end = x < law->x[0] ? 0 : x > law->x[last] ? last : law->n;
  if (end < law->n) {
    if (slope)
      *slope = law->d[end];
    return law->y[end] + law->d[end] * (x - law->x[end]);
  }
  size_t k = find_interval(law, x);
  double c2, c3, s = x - law->x[k];
  cubic(law, k, &c2, &c3);
  if (slope)
    *slope = law->d[k] + s * (2 * c2 + 3 * s * c3);
  return law->y[k] + s * (law->d[k] + s * (c2 + s * c3));
}

double fb_table_law_integral(const fb_table_law *law, double x)
{
  return area_from_start(law, x) - law->area0;
}

/* Each interval's cubic is monotone (see the top of the file) and the
 * continuations are straight lines, so phi(x) x >= 0 everywhere exactly
 * when it holds at the knots and at 0 (which split the real line into
 * monotone pieces that keep one sign of x) and the end tangents do not
 * turn back towards the wrong sign. */
int fb_table_law_check_passive(const fb_table_law *law, fb_err *err)
{
  const size_t last = law->n - 1;
  double ymax = 0;
  for (size_t k = 0; k < law->n; ++k) {
    ymax = fmax(ymax, fabs(law->y[k]));
    if (law->x[k] * law->y[k] < 0)
      return fb_err_set(err, FB_EINVAL,
                        "table law is not passive: at point %zu phi(%g) = %g has the sign "
                        "opposite to x (phi(x) x must be >= 0)",
                        k + 1, law->x[k], law->y[k]);
  }
  /* 16 ulp of the largest value: rounding of the cubic at x = 0. */
  double y0 = fb_table_law_eval(law, 0.0, NULL);
  if (fabs(y0) > 16 * DBL_EPSILON * ymax)
    return fb_err_set(err, FB_EINVAL,
                      "table law is not passive: phi(0) = %g, not 0, so phi(x) x < 0 on one "
                      "side of 0 (add the point (0, 0))",
                      y0);
  if (law->d[0] < 0 || law->d[last] < 0)
    return fb_err_set(err, FB_EINVAL,
                      "table law is not passive: it decreases %s the table (slope %g), so its "
                      "linear continuation changes sign (end the table with rising values)",
                      law->d[0] < 0 ? "before the first point of" : "after the last point of",
                      law->d[0] < 0 ? law->d[0] : law->d[last]);
  return FB_OK;
}

/* ---- CSV files. */

static char *trim(char *s)
{
  while (*s == ' ' || *s == '\t')
    ++s;
  char *end = s + strlen(s);
  while (end > s && (end[-1] == ' ' || end[-1] == '\t'))
    --end;
  *end = '\0';
  return s;
}

/* Cuts the next comma-separated field from *cursor, trimmed; *cursor
 * becomes NULL after the last field. */
static char *next_field(char **cursor)
{
  char *start = *cursor, *comma = strchr(start, ',');
  *cursor = comma ? comma + 1 : NULL;
  if (comma)
    *comma = '\0';
  return trim(start);
}

/* Positions of the wanted columns among the header's fields. */
typedef struct csv_layout {
  size_t nfields;
  size_t col[2]; /* x, y; SIZE_MAX until found */
  const char *name[2];
} csv_layout;

/* Each wanted column must appear once: with two, which to read is unclear. */
static int read_header(fb_text_reader *t, csv_layout *lay, fb_err *err)
{
  char *line = NULL;
  int rc = fb_text_next_data_line(t, '#', &line);
  if (rc)
    return rc;
  if (!line)
    return fb_err_set(err, FB_EPARSE, "%s:%zu: no header line (file is empty or all comments)",
                      t->path, t->line_no ? t->line_no : 1);
  lay->col[0] = lay->col[1] = SIZE_MAX;
  lay->nfields = 0;
  for (char *cursor = line; cursor; ++lay->nfields) {
    const char *field = next_field(&cursor);
    for (int j = 0; j < 2; ++j) {
      if (strcmp(field, lay->name[j]) != 0)
        continue;
      if (lay->col[j] != SIZE_MAX && lay->col[j] != lay->nfields)
        return fb_err_set(err, FB_EPARSE, "%s:%zu: column '%s' appears twice", t->path,
                          t->line_no, field);
      lay->col[j] = lay->nfields;
    }
  }
  for (int j = 0; j < 2; ++j)
    if (lay->col[j] == SIZE_MAX)
      return fb_err_set(err, FB_EPARSE, "%s:%zu: no column '%s' among the header's %zu field%s",
                        t->path, t->line_no, lay->name[j], lay->nfields,
                        lay->nfields == 1 ? "" : "s");
  return FB_OK;
}

/* The wanted fields of a data line as finite decimal numbers v[0] (x),
 * v[1] (y). */
static int read_row(const fb_text_reader *t, char *line, const csv_layout *lay, double v[2],
                    fb_err *err)
{
  const char *text[2] = {NULL, NULL};
  size_t count = 0;
  for (char *cursor = line; cursor; ++count) {
    const char *field = next_field(&cursor);
    for (int j = 0; j < 2; ++j)
      if (count == lay->col[j])
        text[j] = field;
  }
  if (count != lay->nfields)
    return fb_err_set(err, FB_EPARSE, "%s:%zu: expected %zu fields as in the header, found %zu",
                      t->path, t->line_no, lay->nfields, count);
  int rc = FB_OK;
  for (int j = 0; j < 2 && !rc; ++j)
    if ((rc = fb_parse_decimal_field(text[j], &v[j], err)))
      fb_err_prefix(err, "%s:%zu: column '%s': ", t->path, t->line_no, lay->name[j]);
  return rc;
}

/* Growing knot arrays. */
typedef struct knots {
  double *x, *y;
  size_t n, cap_x, cap_y;
} knots;

static int knots_push(knots *k, const double v[2], fb_err *err)
{
  if (fb_grow((void **)&k->x, &k->cap_x, k->n, sizeof *k->x) ||
      fb_grow((void **)&k->y, &k->cap_y, k->n, sizeof *k->y))
    return fb_err_set(err, FB_ENOMEM, "out of memory reading a table");
  k->x[k->n] = v[0];
  k->y[k->n] = v[1];
  ++k->n;
  return FB_OK;
}

/* All data rows after the header, x strictly increasing, at least 2. */
static int read_rows(fb_text_reader *t, const csv_layout *lay, knots *k, fb_err *err)
{
  int rc = FB_OK;
  char *line = NULL;
  while (!rc && !(rc = fb_text_next_data_line(t, '#', &line)) && line) {
    double v[2];
    rc = read_row(t, line, lay, v, err);
    if (!rc && k->n > 0 && !(v[0] > k->x[k->n - 1]))
      rc = fb_err_set(err, FB_EPARSE,
                      "%s:%zu: column '%s': %g does not exceed the previous row's %g (it must "
                      "be strictly increasing)",
                      t->path, t->line_no, lay->name[0], v[0], k->x[k->n - 1]);
    if (!rc)
      rc = knots_push(k, v, err);
  }
  if (!rc && k->n < 2)
    rc = fb_err_set(err, FB_EPARSE, "%s:%zu: a table law needs at least 2 rows (got %zu)",
                    t->path, t->line_no, k->n);
  return rc;
}

int fb_table_law_read_csv(const char *path, const char *x_col, const char *y_col,
                          fb_table_law **out, fb_err *err)
{
  if (!path || !x_col || !y_col || !out)
    return fb_err_set(err, FB_EINVAL, "fb_table_law_read_csv: NULL argument");
  *out = NULL;
  fb_text_reader t;
  int rc = fb_text_open(&t, path, "CSV", err);
  if (rc)
    return rc;
  csv_layout lay = {0, {SIZE_MAX, SIZE_MAX}, {x_col, y_col}};
  knots k = {NULL, NULL, 0, 0, 0};
  rc = read_header(&t, &lay, err);
  if (!rc)
    rc = read_rows(&t, &lay, &k, err);
  if (!rc)
    rc = fb_table_law_new(k.n, k.x, k.y, out, err);
  free(k.x);
  free(k.y);
  fb_text_close(&t);
  return rc;
}

/* ---- As the law of an R element. */

/* The fb_law_ops of fb_bg_add_r_table, whose element has one port of
 * dimension 1 and no modulation: in->n is always 1 and in->m 0. */
static int ops_eval(void *ctx, const fb_law_in *in, double *y)
{
  y[0] = fb_table_law_eval(ctx, in->x[0], NULL);
  return 0;
}

static int ops_jacobian(void *ctx, const fb_law_in *in, double *jac)
{
  fb_table_law_eval(ctx, in->x[0], &jac[0]);
  return 0;
}

static double ops_energy(void *ctx, size_t n, const double *x)
{
  (void)n;
  return fb_table_law_integral(ctx, x[0]);
}

static void ops_free(void *ctx)
{
  fb_table_law *law = ctx;
  fb_table_law_free(&law);
}

/* Passive: fb_bg_add_r_table refuses a law that is not. */
static const fb_law_ops table_law_ops = {.name = "table",
                                         .id = FB_LAW_TABLE,
                                         .eval = ops_eval,
                                         .jacobian = ops_jacobian,
                                         .energy = ops_energy,
                                         .free = ops_free,
                                         .passive = 1};

int fb_bg_add_r_table(fb_bg *bg, const char *name, fb_table_law **law, fb_err *err)
{
  static const size_t one_port[1] = {1};
  if (!law || !*law)
    return fb_err_set(err, FB_EINVAL, "'%s': NULL table law", name ? name : "(null)");
  int rc = fb_table_law_check_passive(*law, err);
  if (rc) {
    fb_table_law_free(law);
    fb_err_prefix(err, "R '%s': ", name ? name : "(null)");
    return rc;
  }
  fb_table_law *ctx = *law;
  *law = NULL;
  return fb_bg_add_field_law(bg, name, FB_BG_R, 1, one_port, &table_law_ops, ctx, err);
}

size_t fb_table_law_knots(const fb_table_law *law, const double **x, const double **y)
{
  *x = law->x;
  *y = law->y;
  return law->n;
}

const fb_table_law *fb_bg_element_table_law(const fb_bg *bg, size_t i)
{
  const void *ctx = NULL;
  const fb_law_ops *law = fb_bg_element_law(bg, i, &ctx);
  return law && law->id == FB_LAW_TABLE ? ctx : NULL;
}

/* ---- As the law of a C element. */

/* Fritsch & Carlson's interpolant of non-decreasing data is
 * non-decreasing on every interval, and its end tangents are the end
 * secants (>= 0 then), so phi' >= 0 everywhere exactly when the values
 * do not decrease from knot to knot: the stored energy, phi's integral,
 * is convex. */
int fb_table_law_check_monotone(const fb_table_law *law, fb_err *err)
{
  for (size_t k = 1; k < law->n; ++k)
    if (law->y[k] < law->y[k - 1])
      return fb_err_set(err, FB_EINVAL,
                        "table law decreases: at point %zu phi(%g) = %g is below point %zu's "
                        "%g (values must not decrease)",
                        k + 1, law->x[k], law->y[k], k, law->y[k - 1]);
  return FB_OK;
}

/* A C element's law e = phi(q): its stored energy the integral of phi
 * from q = 0 (where a preloaded spring already pushes: the energy then
 * is signed, only its changes matter). Not recognised as FB_LAW_TABLE,
 * which names the R of fb_bg_add_r_table. */
static const fb_law_ops c_table_law_ops = {.name = "table spring",
                                           .eval = ops_eval,
                                           .jacobian = ops_jacobian,
                                           .energy = ops_energy,
                                           .free = ops_free};

int fb_bg_add_c_table(fb_bg *bg, const char *name, fb_table_law **law, fb_err *err)
{
  static const size_t one_port[1] = {1};
  if (!law || !*law)
    return fb_err_set(err, FB_EINVAL, "'%s': NULL table law", name ? name : "(null)");
  int rc = fb_table_law_check_monotone(*law, err);
  if (rc) {
    fb_table_law_free(law);
    fb_err_prefix(err, "C '%s': ", name ? name : "(null)");
    return rc;
  }
  fb_table_law *ctx = *law;
  *law = NULL;
  return fb_bg_add_field_law(bg, name, FB_BG_C, 1, one_port, &c_table_law_ops, ctx, err);
}
