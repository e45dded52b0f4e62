/* SPDX-License-Identifier: BSD-3-Clause */
/* The descriptor form E z' = A z + B u + f, y = C z (fb_bd_descriptor)
 * against independent computations, on the quarter car of
 * examples/quarter_car.yaml and on System 1 of examples/apc6x6.yaml:
 *   1. the rows against the diagram's own evaluation: given states x and
 *      inputs u, solving the algebraic rows for the other variables and
 *      applying the state rows gives fb_bd_rhs, and C (times the second
 *      row for power outputs) gives fb_bd_outputs;
 *   2. the finite generalised eigenvalues of (A, E) (LAPACK dggev) are the
 *      eigenvalues of fb_bd_jacobian_dense (dgeev), and the others are
 *      infinite (index 1);
 *   3. the block of A over the Newton signals z is E - P0 - P1 from the
 *      public fb_bd_aug_pattern / fb_bd_aug_values;
 *   4. statics 0 = A z + f with u = 0: the quarter car's spring forces by
 *      hand, System 1's six tire forces summing to the vehicle's weight;
 *   5. errors: NULL arguments, nonlinear diagrams refused by name. */
#include <float.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/model.h"
#include "flexbond/vehicle.h"

#include "apc_layout.h"
#include "bgtest_util.h"
#include "check.h"
#include "road_util.h"

static const char *const quarter_car_path = "../examples/quarter_car.yaml";
static const char *const scenario_path = "../examples/apc6x6.yaml";

/* ---- Dense copies (column-major) of the sparse matrices. */

typedef struct dense_visit {
  double *a;
  size_t nrows;
} dense_visit;

static void put_dense(void *ctx, size_t r, size_t c, double v)
{
  dense_visit *d = ctx;
  d->a[c * d->nrows + r] = v;
}

static double *dense_of(const fb_mat *m)
{
  size_t nr = fb_mat_nrows(m), nc = fb_mat_ncols(m);
  dense_visit d = {calloc(nr * nc + 1, sizeof(double)), nr};
  if (d.a)
    fb_mat_foreach(m, put_dense, &d);
  return d.a;
}

typedef struct dense_desc {
  size_t n, ns, nu, nc;
  double *E, *A, *B, *f, *C;
} dense_desc;

static int dense_desc_new(const fb_descriptor *d, dense_desc *out)
{
  *out = (dense_desc){d->n,           d->nstates,     d->ninputs,
                      d->nrows_c,     dense_of(d->E), dense_of(d->A),
                      dense_of(d->B), dense_of(d->f), dense_of(d->C)};
  return out->E && out->A && out->B && out->f && out->C;
}

static void dense_desc_free(dense_desc *d)
{
  free(d->E);
  free(d->A);
  free(d->B);
  free(d->f);
  free(d->C);
}

/* Checks the shapes and E: identity at the state rows, zero elsewhere. */
static void check_shapes(const fb_descriptor *d, const fb_bd *bd)
{
  CHECK(d->nstates == fb_bd_nstates(bd));
  CHECK(d->n >= fb_bd_aug_size(bd));
  CHECK(d->noutputs == fb_bd_noutputs(bd));
  CHECK(fb_mat_nrows(d->A) == d->n && fb_mat_ncols(d->A) == d->n);
  CHECK(fb_mat_nrows(d->B) == d->n && fb_mat_ncols(d->B) == d->ninputs);
  CHECK(fb_mat_nrows(d->f) == d->n && fb_mat_ncols(d->f) == 1);
  CHECK(fb_mat_nrows(d->C) == d->nrows_c && fb_mat_ncols(d->C) == d->n);
  CHECK(fb_mat_nrows(d->D) == d->nrows_c && fb_mat_ncols(d->D) == d->ninputs);
  CHECK(fb_mat_nnz(d->D) == 0);
  CHECK(fb_mat_nnz(d->E) == d->nstates);
  for (size_t i = 0; i < d->nstates; ++i)
    CHECK(fb_mat_get(d->E, i, i) == 1.0);
  size_t rows = 0;
  for (size_t o = 0; o < d->noutputs; ++o) {
    CHECK(d->output_row[o] == rows);
    rows += d->output_is_product[o] ? 2 : 1;
  }
  CHECK(rows == d->nrows_c);
  for (size_t j = 0; j < d->ninputs; ++j)
    CHECK(d->input_var[j] < d->n && fb_mat_get(d->B, d->input_var[j], j) == 1.0);
  for (size_t i = 0; i < d->nstates; ++i)
    CHECK(strcmp(d->var_names[i], fb_bd_state_name(bd, i)) == 0);
}

/* Row r of the dense m x n matrix a times v, and the sum of the
 * magnitudes of its terms (the scale of its rounding error). */
static double row_dot(const double *a, size_t m, size_t n, size_t r, const double *v,
                      double *scale)
{
  double s = 0.0, mag = 0.0;
  for (size_t j = 0; j < n; ++j) {
    s += a[j * m + r] * v[j];
    mag += fabs(a[j * m + r] * v[j]);
  }
  if (scale)
    *scale = mag;
  return s;
}

/* Solves the algebraic rows for z[ns .. n) given z[0 .. ns) = x and u:
 * A_aa z_a = -(A_ax x + B_a u + f_a). Returns the LAPACK status. */
static int solve_algebraic(const dense_desc *d, const double *u, double *z)
{
  const size_t n = d->n, ns = d->ns, na = n - ns;
  double *m = malloc((na * na + 1) * sizeof *m), *r = malloc((na + 1) * sizeof *r);
  lapack_int *piv = malloc((na + 1) * sizeof *piv);
  lapack_int info = -1;
  if (m && r && piv) {
    for (size_t i = 0; i < na; ++i) {
      r[i] = -(row_dot(d->A, n, ns, ns + i, z, NULL) +
               row_dot(d->B, n, d->nu, ns + i, u, NULL) + d->f[ns + i]);
      for (size_t j = 0; j < na; ++j)
        m[j * na + i] = d->A[(ns + j) * n + ns + i];
    }
    info = LAPACKE_dgesv(LAPACK_COL_MAJOR, (lapack_int)na, 1, m, (lapack_int)na, piv, r,
                         (lapack_int)na);
    if (info == 0)
      memcpy(z + ns, r, na * sizeof *r);
  }
  free(m);
  free(r);
  free(piv);
  return (int)info;
}

/* Output o of the descriptor at z: a row of C, or the product of two. */
static double desc_output(const fb_descriptor *ds, const dense_desc *d, size_t o,
                          const double *z, double *scale)
{
  double s1 = 0.0, s2 = 1.0;
  const size_t r = ds->output_row[o];
  double y = row_dot(d->C, d->nc, d->n, r, z, &s1);
  if (ds->output_is_product[o])
    y *= row_dot(d->C, d->nc, d->n, r + 1, z, &s2);
  *scale = s1 * s2;
  return y;
}

/* Test 1: with the algebraic rows solved, the state rows give x' of the
 * diagram and C its outputs. Both sides do the same sums in another order
 * and one side solves a linear system of condition number well below
 * 1e4 here (unit-diagonal sums, gains and the mass matrices' solves): 1e-10
 * of the magnitude of the terms summed leaves a wide margin over that
 * rounding (observed below 1e-14). */
static void check_rows_against_eval(fb_bd *bd, const fb_descriptor *ds, double t,
                                    const double *x, const double *u)
{
  dense_desc d;
  const size_t n = ds->n, ns = ds->nstates, ny = ds->noutputs;
  double *z = calloc(n + 1, sizeof *z), *xdot = calloc(ns + 1, sizeof *xdot);
  double *y = calloc(ny + 1, sizeof *y);
  if (!dense_desc_new(ds, &d) || !z || !xdot || !y) {
    CHECK(!"out of memory");
    goto out;
  }
  memcpy(z, x, ns * sizeof *x);
  CHECK(solve_algebraic(&d, u, z) == 0);
  CHECK(fb_bd_rhs(bd, t, x, xdot) == 0);
  double worst = 0.0;
  for (size_t i = 0; i < ns; ++i) {
    double sa = 0.0, sb = 0.0;
    const double v = row_dot(d.A, n, n, i, z, &sa) + row_dot(d.B, n, d.nu, i, u, &sb) + d.f[i];
    const double scale = sa + sb + fabs(d.f[i]) + DBL_MIN;
    CHECK_NEAR(v, xdot[i], 1e-10 * scale);
    worst = fmax(worst, fabs(v - xdot[i]) / scale);
  }
  CHECK(fb_bd_outputs(bd, t, x, y) == 0);
  for (size_t o = 0; o < ny; ++o) {
    double scale = 0.0;
    const double v = desc_output(ds, &d, o, z, &scale);
    CHECK_NEAR(v, y[o], 1e-10 * (scale + DBL_MIN));
    worst = fmax(worst, fabs(v - y[o]) / (scale + DBL_MIN));
  }
  fprintf(stderr, "rows vs evaluation at t = %g: largest relative deviation %.3g\n", t, worst);
out:
  dense_desc_free(&d);
  free(z);
  free(xdot);
  free(y);
}

/* ---- Test 2: eigenvalues. */

typedef struct eig_set {
  double *re, *im;
  size_t n;
} eig_set;

/* Eigenvalues of the dense Jacobian at x = 0, t = 0. */
static int jacobian_eigenvalues(fb_bd *bd, eig_set *ev, double *radius)
{
  fb_err err;
  const size_t n = fb_bd_nstates(bd);
  double *j = malloc((n * n + 1) * sizeof *j), *x = calloc(n + 1, sizeof *x);
  ev->re = malloc((n + 1) * sizeof *ev->re);
  ev->im = malloc((n + 1) * sizeof *ev->im);
  ev->n = n;
  int rc = j && x && ev->re && ev->im ? fb_bd_jacobian_dense(bd, 0.0, x, j, &err) : -1;
  if (!rc)
    rc = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', (lapack_int)n, j, (lapack_int)n, ev->re,
                       ev->im, NULL, 1, NULL, 1);
  *radius = 0.0;
  for (size_t i = 0; !rc && i < n; ++i)
    *radius = fmax(*radius, hypot(ev->re[i], ev->im[i]));
  free(j);
  free(x);
  return rc;
}

typedef struct pencil_eig {
  double re, im, finiteness; /* |beta| / (|alpha| + |beta|) */
} pencil_eig;

static int by_finiteness(const void *a, const void *b)
{
  const double x = ((const pencil_eig *)a)->finiteness, y = ((const pencil_eig *)b)->finiteness;
  return (x < y) - (x > y);
}

/* Generalised eigenvalues of (A, E), most finite first. */
static int pencil_eigenvalues(const dense_desc *d, pencil_eig *pe)
{
  const size_t n = d->n;
  double *a = malloc((n * n + 1) * sizeof *a), *e = malloc((n * n + 1) * sizeof *e);
  double *ar = malloc((n + 1) * sizeof *ar), *ai = malloc((n + 1) * sizeof *ai);
  double *be = malloc((n + 1) * sizeof *be), *ls = malloc((n + 1) * sizeof *ls);
  double *rs = malloc((n + 1) * sizeof *rs);
  int rc = -1;
  if (a && e && ar && ai && be && ls && rs) {
    memcpy(a, d->A, n * n * sizeof *a);
    memcpy(e, d->E, n * n * sizeof *e);
    lapack_int ilo = 0, ihi = 0;
    double abnrm = 0.0, bbnrm = 0.0;
    rc = LAPACKE_dggevx(LAPACK_COL_MAJOR, 'B', 'N', 'N', 'N', (lapack_int)n, a, (lapack_int)n,
                        e, (lapack_int)n, ar, ai, be, NULL, 1, NULL, 1, &ilo, &ihi, ls, rs,
                        &abnrm, &bbnrm, NULL, NULL);
  }
  for (size_t i = 0; rc == 0 && i < n; ++i) {
    const double mag = hypot(ar[i], ai[i]);
    pe[i].finiteness = fabs(be[i]) / (mag + fabs(be[i]));
    pe[i].re = be[i] != 0.0 ? ar[i] / be[i] : INFINITY;
    pe[i].im = be[i] != 0.0 ? ai[i] / be[i] : INFINITY;
  }
  if (rc == 0)
    qsort(pe, n, sizeof *pe, by_finiteness);
  free(a);
  free(e);
  free(ar);
  free(ai);
  free(be);
  free(ls);
  free(rs);
  return rc;
}

/* Test 2. Exactly nstates generalised eigenvalues are finite (beta of
 * the others below 1e-12 of alpha: rounding of an exact zero), and each
 * matches an eigenvalue of the Jacobian. Both LAPACK drivers are backward
 * stable after balancing (dgeev balances; dggevx is asked to: the
 * vehicle's entries span 1e-4 (1 / Iyy) to 6e5 (tire stiffness), and
 * unbalanced QZ moves its slow eigenvalues by 1e-6), so a (semisimple, as
 * here) eigenvalue moves by about eps times the balanced matrices' norm
 * times its condition number: 1e-9 of the spectral radius plus 1e-9
 * relative leaves room for condition numbers up to 1e5 (observed: below
 * 1e-13 of the radius). */
static void check_eigenvalues(fb_bd *bd, const fb_descriptor *ds)
{
  dense_desc d;
  eig_set ev = {NULL, NULL, 0};
  pencil_eig *pe = malloc((ds->n + 1) * sizeof *pe);
  unsigned char *used = calloc(ds->n + 1, 1);
  double radius = 0.0;
  if (!dense_desc_new(ds, &d) || !pe || !used) {
    CHECK(!"out of memory");
    goto out;
  }
  CHECK(jacobian_eigenvalues(bd, &ev, &radius) == 0);
  CHECK(pencil_eigenvalues(&d, pe) == 0);
  const size_t ns = ds->nstates;
  CHECK(ns < ds->n && pe[ns].finiteness < 1e-12 && pe[ns - 1].finiteness > 1e-9);
  double worst = 0.0;
  for (size_t i = 0; i < ns; ++i) {
    size_t best = ns;
    double dist = INFINITY;
    for (size_t k = 0; k < ns; ++k) {
      const double dk = hypot(pe[k].re - ev.re[i], pe[k].im - ev.im[i]);
      if (!used[k] && dk < dist) {
        dist = dk;
        best = k;
      }
    }
    CHECK(best < ns);
    if (best < ns)
      used[best] = 1;
    CHECK_NEAR(dist, 0.0, 1e-9 * (radius + hypot(ev.re[i], ev.im[i])));
    worst = fmax(worst, dist / radius);
  }
  fprintf(
      stderr,
      "eigenvalues: %zu finite of %zu, spectral radius %.6g, largest deviation %.3g of it\n",
      ns, ds->n, radius, worst);
out:
  dense_desc_free(&d);
  free(ev.re);
  free(ev.im);
  free(pe);
  free(used);
}

/* Test 3: over the Newton signals, A = E - P0 - P1 with P from the public
 * augmented pattern. Both sides sum the same triplets (in the same order,
 * duplicates in pattern order), so they agree to the last bit; 4 eps of
 * the entry's magnitude allows for a different order. */
static void check_against_augmented(fb_bd *bd, const fb_descriptor *ds)
{
  const size_t nz = fb_bd_aug_size(bd), nnz = fb_bd_aug_nnz(bd), ns = ds->nstates;
  size_t *rows = malloc((nnz + 1) * sizeof *rows), *cols = malloc((nnz + 1) * sizeof *cols);
  double *v0 = malloc((nnz + 1) * sizeof *v0), *v1 = malloc((nnz + 1) * sizeof *v1);
  double *p = calloc(nz * nz + 1, sizeof *p), *x = calloc(ns + 1, sizeof *x);
  double *a = dense_of(ds->A);
  if (rows && cols && v0 && v1 && p && x && a) {
    fb_bd_aug_pattern(bd, rows, cols);
    CHECK(fb_bd_aug_values(bd, 0.0, x, v0, v1) == 0);
    for (size_t k = 0; k < nnz; ++k)
      p[cols[k] * nz + rows[k]] += v0[k] + v1[k];
    for (size_t i = 0; i < ns; ++i)
      CHECK(fb_bd_state_row(bd, i) == i);
    size_t bad = 0;
    for (size_t j = 0; j < nz; ++j)
      for (size_t i = 0; i < nz; ++i) {
        const double want = (i == j && i < ns ? 1.0 : 0.0) - p[j * nz + i];
        bad += fabs(a[j * ds->n + i] - want) > 4 * DBL_EPSILON * fabs(want);
      }
    CHECK(bad == 0);
  } else {
    CHECK(!"out of memory");
  }
  free(rows);
  free(cols);
  free(v0);
  free(v1);
  free(p);
  free(x);
  free(a);
}

/* Test 4 helper: a solution of 0 = A z + f (u = 0). A is singular where
 * variables are free at rest: the integrals of integrating probes (zero
 * columns of A) and the self-stress of a statically indeterminate
 * support. LAPACK dgelsy (QR with column pivoting) pivots those columns
 * last and gives them 0 ("basic" solution); columns whose pivot falls
 * below 1e-12 of the largest count as free: the others' are at least
 * ~1e-9 of it here. *residual is |A z + f| over |A| |z| + |f| (infinity
 * norms), a backward error: of the order of n eps for a stable solver. */
static int solve_statics(const fb_descriptor *ds, double *z, double *residual)
{
  const size_t n = ds->n;
  double *a = dense_of(ds->A), *a2 = dense_of(ds->A), *f = dense_of(ds->f);
  lapack_int *jpvt = calloc(n + 1, sizeof *jpvt);
  lapack_int rank = 0, info = -1;
  if (a && a2 && f && jpvt) {
    for (size_t i = 0; i < n; ++i)
      z[i] = -f[i];
    info = LAPACKE_dgelsy(LAPACK_COL_MAJOR, (lapack_int)n, (lapack_int)n, 1, a, (lapack_int)n,
                          z, (lapack_int)n, jpvt, 1e-12, &rank);
  }
  double rmax = 0.0, anorm = 0.0, zmax = 0.0, fmaxv = 0.0;
  for (size_t i = 0; info == 0 && i < n; ++i) {
    double arow = 0.0;
    const double r = row_dot(a2, n, n, i, z, NULL) + f[i];
    for (size_t j = 0; j < n; ++j)
      arow += fabs(a2[j * n + i]);
    rmax = fmax(rmax, fabs(r));
    anorm = fmax(anorm, arow);
    zmax = fmax(zmax, fabs(z[i]));
    fmaxv = fmax(fmaxv, fabs(f[i]));
  }
  *residual = rmax / (anorm * zmax + fmaxv);
  fprintf(stderr, "statics: rank %d of %zu, backward error %.3g\n", (int)rank, n, *residual);
  free(a);
  free(a2);
  free(f);
  free(jpvt);
  return (int)info;
}

/* ---- The quarter car. */

static int build_model_with(fb_model *m, const fb_probe_spec *extra, size_t nextra, fb_bd **bd,
                            fb_err *err)
{
  size_t np = 0;
  const fb_probe_spec *p = fb_model_probes(m, &np);
  fb_probe_spec *all = malloc((np + nextra + 1) * sizeof *all);
  if (!all)
    return FB_ENOMEM;
  memcpy(all, p, np * sizeof *p);
  if (nextra)
    memcpy(all + np, extra, nextra * sizeof *extra);
  int rc = fb_bd_build(fb_model_graph(m), all, np + nextra, bd, err);
  free(all);
  return rc;
}

/* Output index by name, or the number of outputs. */
static size_t output_index(const fb_bd *bd, const char *name)
{
  size_t o = 0;
  while (o < fb_bd_noutputs(bd) && strcmp(fb_bd_output_name(bd, o), name) != 0)
    ++o;
  return o;
}

/* Statics of the quarter car by hand: at rest the suspension spring
 * carries the body's weight, the tire both masses'; the momenta are 0.
 * The body displacement (an integrated probe) is free at rest, so the
 * least-norm solution gives 0. The weight probe reads a folded constant
 * (an output made a variable of its own). Exact solves of a matrix of
 * condition ~1e6 (k / m spans 1e-3 .. 5e3): 1e-9 relative. */
static void check_quarter_car_statics(fb_bd *bd, const fb_descriptor *ds)
{
  const double ms = 250, mu = 35, ks = 16000, kt = 160000, g = 9.81;
  double *z = calloc(ds->n + 1, sizeof *z), residual = 1.0;
  dense_desc d;
  if (!dense_desc_new(ds, &d) || !z) {
    CHECK(!"out of memory");
    goto out;
  }
  CHECK(solve_statics(ds, z, &residual) == 0);
  CHECK(residual < 1e-13);
  const struct {
    const char *name;
    double want, scale;
  } expect[] = {{"x_body", 0.0, ms * g / ks},
                {"a_body", 0.0, g},
                {"deflection", ms * g / ks, ms * g / ks},
                {"tire_force", (ms + mu) * g, (ms + mu) * g},
                {"damper_power", 0.0, 1.0},
                {"weight_body", -ms * g, ms * g}};
  for (size_t k = 0; k < sizeof expect / sizeof expect[0]; ++k) {
    const size_t o = output_index(bd, expect[k].name);
    CHECK(o < ds->noutputs);
    double scale = 0.0;
    if (o < ds->noutputs)
      CHECK_NEAR(desc_output(ds, &d, o, z, &scale), expect[k].want, 1e-9 * expect[k].scale);
  }
  /* The Kt spring's state is the tire compression (mu + ms) g / kt. */
  CHECK_NEAR(z[3], (ms + mu) * g / kt, 1e-9 * (ms + mu) * g / kt);
  CHECK(strcmp(ds->var_names[3], "Kt.q") == 0);
out:
  dense_desc_free(&d);
  free(z);
}

static void test_quarter_car(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_model *m = NULL;
  fb_bd *bd = NULL;
  fb_descriptor *ds = NULL;
  /* The body's weight: the effort of the (constant) gravity source's
   * bond, an output on a folded constant. */
  const fb_probe_spec weight = {
      "weight_body", FB_PROBE_EFFORT, "grav_body->body", -1, 0, 1.0, NULL, NULL, 0};
  MUST(fb_model_load(quarter_car_path, &m, &err), &err);
  if (m)
    MUST(build_model_with(m, &weight, 1, &bd, &err), &err);
  if (bd)
    MUST(fb_bd_descriptor(bd, &ds, &err), &err);
  if (!ds)
    goto out;
  check_shapes(ds, bd);
  /* One input, the road velocity source; the power probe takes two rows. */
  CHECK(ds->ninputs == 1 && strcmp(ds->input_names[0], "road") == 0);
  CHECK(ds->nstates == 5 && ds->nrows_c == ds->noutputs + 1);
  if (ds->nstates != 5)
    goto out;
  CHECK(ds->output_is_product[output_index(bd, "damper_power")]);
  /* Mid-bump (model: h = 0.05 m over 0.2 s from t = 0.5 s), the road
   * velocity is h pi / T sin(2 pi (t - t0) / T) = 0.25 pi at t = 0.55. */
  const double t = 0.55, u = 0.05 * 3.14159265358979323846 / 0.2;
  const double x[5] = {30.0, -4.0, 0.12, 0.02, 0.3};
  check_rows_against_eval(bd, ds, t, x, &u);
  check_eigenvalues(bd, ds);
  check_against_augmented(bd, ds);
  check_quarter_car_statics(bd, ds);
out:
  fb_descriptor_free(&ds);
  CHECK(ds == NULL);
  fb_bd_free(&bd);
  fb_model_free(&m);
}

/* ---- System 1 of the reference vehicle. */

/* System 1 with the seven outputs and the six tire forces after them. */
static int build_system1(const fb_scenario *s, fb_bg **graph, fb_bd **bd, fb_err *err)
{
  char names[APC_NCORNERS][32], targets[APC_NCORNERS][48];
  fb_probe_spec *std = NULL, *all = NULL;
  size_t nstd = 0;
  fb_hull *hull = NULL;
  int rc = fb_vehicle_rigid_hull(s, &hull, err);
  if (!rc)
    rc = fb_vehicle_assemble(s, &hull, graph, &std, &nstd, err);
  if (!rc && !(all = malloc((nstd + APC_NCORNERS) * sizeof *all)))
    rc = FB_ENOMEM;
  if (!rc) {
    memcpy(all, std, nstd * sizeof *all);
    for (int c = 0; c < APC_NCORNERS; ++c) {
      snprintf(names[c], sizeof names[c], "tire_force_all_%s", apc_corner_name(c));
      snprintf(targets[c], sizeof targets[c], "susp_%s.b_tire", apc_corner_name(c));
      all[nstd + (size_t)c] =
          (fb_probe_spec){names[c], FB_PROBE_EFFORT, targets[c], -1, 0, 1.0, NULL, NULL, 0};
    }
    rc = fb_bd_build(*graph, all, nstd + APC_NCORNERS, bd, err);
  }
  free(all);
  fb_vehicle_probes_free(&std, nstd);
  fb_hull_free(&hull);
  return rc;
}

/* Road velocity under the wheel of corner c at time t (data sheet: the
 * bump z(s) = h/2 (1 - cos(2 pi s / L)), s = V (t - t_entry)). */
static double road_rate(const fb_scenario *s, int c, double t)
{
  const double pi = 3.14159265358979323846, entry = fb_scenario_road_entry(s, c);
  const double dist = s->speed * (t - entry);
  if (dist < 0.0 || dist > road_bump(s)->length)
    return 0.0;
  return pi * road_bump(s)->height * s->speed / road_bump(s)->length *
         sin(2 * pi * dist / road_bump(s)->length);
}

/* Statics of System 1: the six tire forces (the extra outputs) carry the
 * hull plus payload, the driver, the engine and the six wheels; the
 * power outputs are zero at rest. The least-norm solution picks one
 * self-stress of the indeterminate support, which changes the single
 * tire forces but not their sum (vertical force balance). The matrix's
 * condition number is ~1e8 (1 / Iyy to tire stiffness): 1e-9 of the
 * weight, observed ~1e-13. */
static void check_system1_statics(const fb_scenario *s, fb_bd *bd, const fb_descriptor *ds)
{
  double *z = calloc(ds->n + 1, sizeof *z), residual = 1.0;
  dense_desc d;
  if (!dense_desc_new(ds, &d) || !z) {
    CHECK(!"out of memory");
    goto out;
  }
  CHECK(solve_statics(ds, z, &residual) == 0);
  CHECK(residual < 1e-13);
  double sum = 0.0, scale = 0.0;
  double expect = s->total_weight + (APC_DRIVER(s)->mass + APC_ENGINE(s)->mass) * s->gravity;
  for (int c = 0; c < APC_NCORNERS; ++c) {
    char name[32];
    snprintf(name, sizeof name, "tire_force_all_%s", apc_corner_name(c));
    const size_t o = output_index(bd, name);
    CHECK(o < ds->noutputs);
    if (o < ds->noutputs)
      sum += desc_output(ds, &d, o, z, &scale);
    expect += s->corner[c].wheel_mass * s->gravity;
  }
  fprintf(stderr, "System 1 statics: sum of tire forces %.12g N, weight %.12g N\n", sum,
          expect);
  CHECK_NEAR(sum, expect, 1e-9 * expect);
  for (int k = 0; k < APC_NOUTPUTS; ++k) {
    const size_t o = output_index(bd, apc_output_name(k));
    CHECK(o < ds->noutputs);
    if (o < ds->noutputs && ds->output_is_product[o])
      CHECK_NEAR(desc_output(ds, &d, o, z, &scale), 0.0, 1e-9);
  }
out:
  dense_desc_free(&d);
  free(z);
}

static void test_system1(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  fb_bg *graph = NULL;
  fb_bd *bd = NULL;
  fb_descriptor *ds = NULL;
  double *x = NULL;
  MUST(fb_scenario_load(scenario_path, &s, &err), &err);
  if (s)
    MUST(build_system1(s, &graph, &bd, &err), &err);
  if (bd)
    MUST(fb_bd_descriptor(bd, &ds, &err), &err);
  if (!ds || !(x = calloc(ds->nstates, sizeof *x)))
    goto out;
  check_shapes(ds, bd);
  /* The road is the only time-varying source: six inputs, one per wheel;
   * the two power outputs take two rows each. */
  CHECK(ds->ninputs == APC_NCORNERS && ds->nrows_c == ds->noutputs + 2);
  /* Midway through the crossing (several wheels on the bump), with a
   * state away from rest. */
  const double t = 6.2;
  double u[APC_NCORNERS];
  for (size_t j = 0; j < ds->ninputs && j < APC_NCORNERS; ++j) {
    char want[32];
    snprintf(want, sizeof want, "road.v_%s", apc_corner_name((int)j));
    CHECK(strcmp(ds->input_names[j], want) == 0);
    u[j] = road_rate(s, (int)j, t);
  }
  CHECK(u[APC_LF] != 0.0 && u[APC_LM] != 0.0 && u[APC_RR] == 0.0);
  for (size_t i = 0; i < ds->nstates; ++i)
    x[i] = 1e-3 * (double)((i * 7919) % 23) - 0.011;
  check_rows_against_eval(bd, ds, t, x, u);
  check_eigenvalues(bd, ds);
  check_against_augmented(bd, ds);
  check_system1_statics(s, bd, ds);
out:
  free(x);
  fb_descriptor_free(&ds);
  fb_bd_free(&bd);
  fb_bg_free(&graph);
  fb_scenario_free(&s);
}

/* ---- Errors. */

/* The quarter car with one extra probe must be refused, naming it. */
static void check_refused(fb_model *m, const fb_probe_spec *extra)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bd *bd = NULL;
  fb_descriptor dummy, *ds = &dummy; /* must be reset to NULL */
  MUST(build_model_with(m, extra, 1, &bd, &err), &err);
  if (!bd)
    return;
  CHECK(fb_bd_descriptor(bd, &ds, &err) == FB_EINVAL);
  CHECK(ds == NULL);
  CHECK(strstr(err.msg, "not linear") != NULL);
  CHECK(strstr(err.msg, extra->name) != NULL);
  fprintf(stderr, "refused as expected: %s\n", err.msg);
  fb_bd_free(&bd);
}

static void test_errors(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_descriptor *ds = NULL;
  CHECK(fb_bd_descriptor(NULL, &ds, &err) == FB_EINVAL && ds == NULL);
  CHECK(strstr(err.msg, "NULL") != NULL);
  fb_model *m = NULL;
  MUST(fb_model_load(quarter_car_path, &m, &err), &err);
  if (!m)
    return;
  fb_bd *bd = NULL;
  MUST(build_model_with(m, NULL, 0, &bd, &err), &err);
  CHECK(fb_bd_descriptor(bd, NULL, &err) == FB_EINVAL);
  fb_bd_free(&bd);
  /* The dissipated energy integrates a power: a product drives a state. */
  const fb_probe_spec energy = {
      "damper_energy", FB_PROBE_POWER, "b_damper", -1, 1, 1.0, NULL, NULL, 0};
  check_refused(m, &energy);
  /* A weighted power: the product feeds another block, so it cannot be
   * split into two rows of C. */
  const double two = 2.0;
  const fb_probe_spec weighted = {
      "weighted_power", FB_PROBE_POWER, "b_damper", -1, 0, 1.0, NULL, &two, 1};
  check_refused(m, &weighted);
  fb_model_free(&m);
  fb_descriptor_free(NULL);
  fb_descriptor_free(&ds);
  CHECK(ds == NULL);
}

int main(void)
{
  test_quarter_car();
  test_system1();
  test_errors();
  return check_report("test_descriptor");
}
