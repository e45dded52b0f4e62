/* SPDX-License-Identifier: BSD-3-Clause */
/* The checks of a reduced structure (fb_reduced_check): symmetry, a
 * positive semi-definite mass, and a free-free stiffness with exactly the
 * six rigid-body motions of its interface as zero-energy modes.
 *
 * Tolerances come from the file's own precision p (the relative rounding
 * of its numbers): each entry of the diagonally scaled K^ = D^-1 K D^-1
 * (D = sqrt(diag K), so |K^_ij| <= 1) is off by at most p |K^_ij|, so the
 * perturbation E has ||E||_2 <= ||E||_F <= p ||K^||_F, which bounds both
 * the residual |K^ r^| of an exact rigid-body motion and the shift of any
 * eigenvalue (Weyl's inequality; Golub & Van Loan, "Matrix
 * Computations", 4th ed., theorem 8.1.6). The threshold z = max(2 p, 1e-9)
 * ||K^||_F is twice that bound; 1e-9 covers the writer's own round-off in
 * the condensation (eps times K_oo's condition number, 1e7 and more for a
 * stiff shell). */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem/reduced_struct.h"

static const char *const comp_name[7] = {"", "ux", "uy", "uz", "rx", "ry", "rz"};
static const char *const motion_name[6] = {"translation along x", "translation along y",
                                           "translation along z", "rotation about x",
                                           "rotation about y",    "rotation about z"};

/* "node 12 uz" */
static void dof_text(const fb_reduced *r, size_t i, char *buf, size_t size)
{
  snprintf(buf, size, "node %ld %s", r->nodes.id[r->dof_node[i]], comp_name[r->dof_comp[i]]);
}

/* The line entry (i, j) (or its mirror, in a one-triangle file) was
 * written on, 0 when not known. */
static size_t entry_line(const fb_reduced *r, int k, size_t i, size_t j)
{
  for (size_t e = 0; r->where[k] && e < r->nwhere[k]; ++e)
    if ((r->where[k][e].i == i && r->where[k][e].j == j))
      return r->where[k][e].line;
  return 0;
}

/* "FILE:LINE: " or "FILE: " */
static void where_text(const fb_reduced *r, int k, size_t i, size_t j, char *buf, size_t size)
{
  const size_t line = entry_line(r, k, i, j);
  if (line)
    snprintf(buf, size, "%s:%zu: ", r->path[k], line);
  else
    snprintf(buf, size, "%s: ", r->path[k]);
}

static double *dense(const fb_mat *a, size_t n)
{
  double *d = malloc((n ? n * n : 1) * sizeof *d);
  if (!d)
    return NULL;
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < n; ++i)
      d[i + j * n] = fb_mat_get(a, i, j);
  return d;
}

static int check_symmetric(const fb_reduced *r, int k, const double *a, fb_err *err)
{
  const size_t n = r->ndof;
  const double p = r->precision[k];
  const char *name = k ? "M" : "K";
  for (size_t j = 0; j < n; ++j) {
    for (size_t i = j + 1; i < n; ++i) {
      const double x = a[i + j * n], y = a[j + i * n];
      const double scale = fabs(x) > fabs(y) ? fabs(x) : fabs(y);
      const double tol = 2.0 * p * scale + 1e-8 * sqrt(fabs(a[i + i * n] * a[j + j * n]));
      if (fabs(x - y) <= tol)
        continue;
      char wi[64], wj[64], at[FB_ERR_FILE_MAX + 32], mirror[32] = "";
      dof_text(r, i, wi, sizeof wi);
      dof_text(r, j, wj, sizeof wj);
      const size_t line_i = entry_line(r, k, i, j), line_j = entry_line(r, k, j, i);
      where_text(r, k, line_i ? i : j, line_i ? j : i, at, sizeof at);
      if (line_i && line_j)
        snprintf(mirror, sizeof mirror, " (line %zu)", line_j);
      return fb_err_set(err, FB_EMODEL,
                        "%s%s is not symmetric: %s(%s, %s) = %g but %s(%s, %s) = %g%s, "
                        "a difference of %.3g of the larger, more than the %.3g the file's "
                        "numbers allow",
                        at, name, name, wi, wj, x, name, wj, wi, y, mirror,
                        fabs(x - y) / (scale > 0 ? scale : 1.0),
                        tol / (scale > 0 ? scale : 1.0));
    }
  }
  return FB_OK;
}

/* Eigenvalues (ascending) and, in place of s, eigenvectors of the
 * symmetric n x n s. */
static int eig(double *s, size_t n, double *w, const char *what, fb_err *err)
{
  if (LAPACKE_dsyev(LAPACK_COL_MAJOR, 'V', 'U', (int)n, s, (int)n, w))
    return fb_err_set(err, FB_ESOLVER, "%s: the eigen-solve failed", what);
  return FB_OK;
}

/* The DOF with the largest component of column c of v. */
static size_t largest(const double *v, size_t n, size_t c)
{
  size_t best = 0;
  for (size_t i = 1; i < n; ++i)
    if (fabs(v[i + c * n]) > fabs(v[best + c * n]))
      best = i;
  return best;
}

/* The six rigid-body motions of the DOFs about the nodes' centroid c:
 * translation t and rotation theta move the node at x by t + theta x
 * (x - c) and turn it by theta (small displacements). */
static void rigid_motions(const fb_reduced *r, double *R)
{
  const size_t n = r->ndof;
  double c[3] = {0, 0, 0};
  for (size_t a = 0; a < r->nodes.n; ++a)
    for (int k = 0; k < 3; ++k)
      c[k] += r->nodes.xyz[3 * a + k] / (double)r->nodes.n;
  memset(R, 0, 6 * n * sizeof *R);
  for (size_t i = 0; i < n; ++i) {
    const double *x = r->nodes.xyz + 3 * r->dof_node[i];
    const double d[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
    const int comp = r->dof_comp[i];
    if (comp <= 3) {
      const int a = comp - 1, b = (a + 1) % 3, e = (a + 2) % 3;
      R[i + (size_t)a * n] = 1.0;
      /* (theta x d)_a = theta_b d_e - theta_e d_b */
      R[i + (size_t)(3 + b) * n] = d[e];
      R[i + (size_t)(3 + e) * n] = -d[b];
    } else {
      R[i + (size_t)(comp - 1) * n] = 1.0;
    }
  }
}

static double norm(const double *v, size_t n)
{
  double s = 0.0;
  for (size_t i = 0; i < n; ++i)
    s += v[i] * v[i];
  return sqrt(s);
}

/* K^ = D^-1 K D^-1 in place, D = sqrt(diag K). A diagonal entry below
 * -1e-9 of the largest is an error naming its DOF; one within 1e-9 of it
 * of zero is a DOF that a rigid-body motion may move alone (a corner of
 * a flat plate whose three other retained nodes are on a line) or a
 * mechanism, which the eigenvalues tell apart: it is scaled by the
 * largest diagonal. */
static int scale_stiffness(const fb_reduced *r, double *a, double *dsq, fb_err *err)
{
  const size_t n = r->ndof;
  double big = 0.0;
  for (size_t i = 0; i < n; ++i)
    big = a[i + i * n] > big ? a[i + i * n] : big;
  for (size_t i = 0; i < n; ++i) {
    const double kii = a[i + i * n];
    if (kii < -1e-9 * big || big <= 0.0) {
      char wi[64], at[FB_ERR_FILE_MAX + 32];
      dof_text(r, i, wi, sizeof wi);
      where_text(r, 0, i, i, at, sizeof at);
      return fb_err_set(err, FB_EMODEL,
                        "%sK(%s, %s) = %g: a stiffness's diagonal must not be negative (or "
                        "all zero)",
                        at, wi, wi, kii);
    }
    dsq[i] = sqrt(kii > 1e-9 * big ? kii : big);
  }
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < n; ++i)
      a[i + j * n] /= dsq[i] * dsq[j];
  return FB_OK;
}

static int check_rigid(const fb_reduced *r, const double *kh, const double *dsq, double z,
                       double *R, fb_err *err)
{
  const size_t n = r->ndof;
  double *y = malloc(n * sizeof *y);
  if (!y)
    return fb_err_set(err, FB_ENOMEM, "out of memory checking %s", r->path[0]);
  int rc = FB_OK;
  for (int m = 0; m < 6 && !rc; ++m) {
    double *q = R + (size_t)m * n;
    for (size_t i = 0; i < n; ++i)
      q[i] *= dsq[i];
    const double len = norm(q, n);
    for (size_t i = 0; len > 0 && i < n; ++i)
      q[i] /= len;
    for (size_t i = 0; i < n; ++i) {
      double s = 0.0;
      for (size_t j = 0; j < n; ++j)
        s += kh[i + j * n] * q[j];
      y[i] = s;
    }
    const double res = norm(y, n);
    if (len == 0.0 || res > z) {
      char wi[64];
      dof_text(r, largest(y, n, 0), wi, sizeof wi);
      rc = fb_err_set(err, FB_EMODEL,
                      "%s: K is not free-free: its %s has energy (|K r| = %.3g of the scaled "
                      "stiffness, more than the %.3g the file's precision allows; largest at "
                      "%s): a support or a grounded spring left in the superelement",
                      r->path[0], motion_name[m], res, z, wi);
    }
  }
  free(y);
  if (rc)
    return rc;
  /* Gram-Schmidt, twice (Giraud et al., Numer. Math. 101, 2005): an
   * orthonormal basis of the six motions, or an error when the interface
   * cannot tell some of them apart. */
  for (int m = 0; m < 6; ++m) {
    double *q = R + (size_t)m * n;
    const double before = norm(q, n);
    for (int pass = 0; pass < 2; ++pass)
      for (int l = 0; l < m; ++l) {
        const double *o = R + (size_t)l * n;
        double s = 0.0;
        for (size_t i = 0; i < n; ++i)
          s += o[i] * q[i];
        for (size_t i = 0; i < n; ++i)
          q[i] -= s * o[i];
      }
    const double after = norm(q, n);
    if (after <= 1e-8 * before)
      return fb_err_set(err, FB_EMODEL,
                        "%s: the interface's DOFs cannot tell the %s from the other rigid-body "
                        "motions (nodes on a line with translations only?): a free-free "
                        "superelement needs all six",
                        r->path[0], motion_name[m]);
    for (size_t i = 0; i < n; ++i)
      q[i] /= after;
  }
  return FB_OK;
}

/* P K^ P with P = I - Q Q' (Q the six orthonormal motions), in place. */
static void project_out(double *kh, const double *Q, size_t n)
{
  double *t = malloc(n * sizeof *t);
  if (!t)
    return;
  for (int pass = 0; pass < 2; ++pass) {
    for (int m = 0; m < 6; ++m) {
      const double *q = Q + (size_t)m * n;
      /* kh <- (I - q q') kh, then transposed by the second pass */
      for (size_t j = 0; j < n; ++j) {
        double s = 0.0;
        for (size_t i = 0; i < n; ++i)
          s += q[i] * kh[i + j * n];
        t[j] = s;
      }
      for (size_t j = 0; j < n; ++j)
        for (size_t i = 0; i < n; ++i)
          kh[i + j * n] -= q[i] * t[j];
    }
    for (size_t j = 0; j < n; ++j)
      for (size_t i = j + 1; i < n; ++i) {
        const double x = kh[i + j * n];
        kh[i + j * n] = kh[j + i * n];
        kh[j + i * n] = x;
      }
  }
  free(t);
}

/* The length that weighs a rotation against a translation: the interface
 * nodes' extent (1 m for a single node). */
static double extent(const fb_reduced *r)
{
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k)
    lo[k] = hi[k] = r->nodes.xyz[k];
  for (size_t a = 1; a < r->nodes.n; ++a)
    for (int k = 0; k < 3; ++k) {
      const double x = r->nodes.xyz[3 * a + k];
      lo[k] = x < lo[k] ? x : lo[k];
      hi[k] = x > hi[k] ? x : hi[k];
    }
  const double d = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                        (hi[2] - lo[2]) * (hi[2] - lo[2]));
  return d > 0.0 ? d : 1.0;
}

/* The DOF a mechanism moves most. Every eigenvector of the projected K^
 * with a zero eigenvalue is a null vector of K^ (the projection only
 * subtracts rigid-body motions, which K^ does not feel), so x = D^-1 v
 * is one of K. Its rigid-body part is taken out by least squares in
 * displacements (rotations weighed by the interface's extent L, so that
 * metres meet metres); the vector with the most left names the DOF where
 * that remainder is largest. */
static size_t mechanism_dof(const fb_reduced *r, const double *v, const double *w, double z,
                            const double *dsq)
{
  const size_t n = r->ndof;
  const double len = extent(r);
  double *R = malloc(6 * n * sizeof *R), *x = malloc(n * sizeof *x);
  double best = -1.0;
  size_t at = 0;
  if (R)
    rigid_motions(r, R);
  for (size_t c = 0; R && x && c < n; ++c) {
    if (fabs(w[c]) > z)
      continue;
    double g[36], b[6], total = 0.0;
    for (size_t i = 0; i < n; ++i) {
      const double wt = r->dof_comp[i] > 3 ? len * len : 1.0;
      x[i] = v[i + c * n] / dsq[i];
      total += wt * x[i] * x[i];
    }
    for (int p = 0; p < 6; ++p) {
      b[p] = 0.0;
      for (int q = 0; q < 6; ++q)
        g[p + 6 * q] = 0.0;
      for (size_t i = 0; i < n; ++i) {
        const double wt = r->dof_comp[i] > 3 ? len * len : 1.0;
        b[p] += R[i + (size_t)p * n] * wt * x[i];
        for (int q = 0; q < 6; ++q)
          g[p + 6 * q] += R[i + (size_t)p * n] * wt * R[i + (size_t)q * n];
      }
    }
    if (LAPACKE_dposv(LAPACK_COL_MAJOR, 'U', 6, 1, g, 6, b, 6))
      continue;
    double left = 0.0, most = -1.0;
    size_t where = 0;
    for (size_t i = 0; i < n; ++i) {
      double rigid = 0.0;
      for (int p = 0; p < 6; ++p)
        rigid += R[i + (size_t)p * n] * b[p];
      const double d = (x[i] - rigid) * (r->dof_comp[i] > 3 ? len : 1.0);
      left += d * d;
      if (fabs(d) > most) {
        most = fabs(d);
        where = i;
      }
    }
    if (total > 0.0 && left / total > best) {
      best = left / total;
      at = where;
    }
  }
  free(R);
  free(x);
  return at;
}

static int check_stiffness(const fb_reduced *r, double *a, fb_err *err)
{
  const size_t n = r->ndof;
  const double p = r->precision[0];
  double *dsq = malloc(n * sizeof *dsq), *R = malloc(6 * n * sizeof *R),
         *w = malloc(n * sizeof *w);
  int rc = (!dsq || !R || !w)
               ? fb_err_set(err, FB_ENOMEM, "out of memory checking %s", r->path[0])
               : FB_OK;
  if (!rc && n < 6)
    rc = fb_err_set(err, FB_EMODEL,
                    "%s: K has %zu DOFs: a free-free superelement needs at least the six of "
                    "its rigid-body motions",
                    r->path[0], n);
  if (!rc)
    rc = scale_stiffness(r, a, dsq, err);
  double fro = 0.0;
  for (size_t i = 0; !rc && i < n * n; ++i)
    fro += a[i] * a[i];
  const double z = (2.0 * p > 1e-9 ? 2.0 * p : 1e-9) * sqrt(fro);
  if (!rc) {
    rigid_motions(r, R);
    rc = check_rigid(r, a, dsq, z, R, err);
  }
  if (!rc) {
    project_out(a, R, n);
    rc = eig(a, n, w, r->path[0], err);
  }
  if (!rc) {
    /* The projection leaves six zeros; others below z are mechanisms. */
    size_t nzero = 0;
    for (size_t i = 0; i < n; ++i)
      if (w[i] < -z) {
        char wi[64];
        dof_text(r, largest(a, n, i), wi, sizeof wi);
        rc = fb_err_set(err, FB_EMODEL,
                        "%s: K is not positive semi-definite: an eigenvalue %.3g of the "
                        "scaled stiffness (its mode largest at %s)",
                        r->path[0], w[i], wi);
        break;
      } else if (fabs(w[i]) <= z) {
        ++nzero;
      }
    if (!rc && nzero > 6) {
      char wi[64];
      dof_text(r, mechanism_dof(r, a, w, z, dsq), wi, sizeof wi);
      rc = fb_err_set(err, FB_EMODEL,
                      "%s: K has %zu zero-energy mode%s besides its 6 rigid-body motions (a "
                      "mechanism or a DOF without stiffness, largest at %s): below %.3g of "
                      "the scaled stiffness",
                      r->path[0], nzero - 6, nzero == 7 ? "" : "s", wi, z);
    }
  }
  free(dsq);
  free(R);
  free(w);
  return rc;
}

static int check_mass(const fb_reduced *r, double *a, fb_err *err)
{
  const size_t n = r->ndof;
  for (size_t i = 0; i < n; ++i)
    if (a[i + i * n] < 0.0) {
      char wi[64], at[FB_ERR_FILE_MAX + 32];
      dof_text(r, i, wi, sizeof wi);
      where_text(r, 1, i, i, at, sizeof at);
      return fb_err_set(err, FB_EMODEL, "%sM(%s, %s) = %g: a mass must not be negative", at, wi,
                        wi, a[i + i * n]);
    }
  double *R = malloc(6 * n * sizeof *R), *w = malloc(n * sizeof *w), *d = malloc(n * sizeof *d);
  int rc = (!R || !w || !d)
               ? fb_err_set(err, FB_ENOMEM, "out of memory checking %s", r->path[1])
               : FB_OK;
  if (!rc) {
    /* The total mass: a rigid translation's kinetic energy. */
    rigid_motions(r, R);
    for (int m = 0; m < 3 && !rc; ++m) {
      double s = 0.0;
      const double *q = R + (size_t)m * n;
      for (size_t j = 0; j < n; ++j)
        for (size_t i = 0; i < n; ++i)
          s += q[i] * a[i + j * n] * q[j];
      if (!(s > 0.0))
        rc = fb_err_set(err, FB_EMODEL,
                        "%s: M gives the %s no mass (r' M r = %g): a superelement needs its "
                        "mass on the interface",
                        r->path[1], motion_name[m], s);
    }
  }
  if (!rc) {
    /* Scaled by the diagonal (1 where it is 0), so that translations and
     * rotations weigh alike; semi-definite to the file's precision. */
    for (size_t i = 0; i < n; ++i)
      d[i] = a[i + i * n] > 0 ? sqrt(a[i + i * n]) : 1.0;
    double fro = 0.0;
    for (size_t j = 0; j < n; ++j)
      for (size_t i = 0; i < n; ++i) {
        a[i + j * n] /= d[i] * d[j];
        fro += a[i + j * n] * a[i + j * n];
      }
    const double p = r->precision[1];
    const double z = (2.0 * p > 1e-9 ? 2.0 * p : 1e-9) * sqrt(fro);
    rc = eig(a, n, w, r->path[1], err);
    if (!rc && w[0] < -z) {
      char wi[64];
      dof_text(r, largest(a, n, 0), wi, sizeof wi);
      rc = fb_err_set(err, FB_EMODEL,
                      "%s: M is not positive semi-definite: an eigenvalue %.3g of the scaled "
                      "mass, below -%.3g (its mode largest at %s)",
                      r->path[1], w[0], z, wi);
    }
  }
  free(R);
  free(w);
  free(d);
  return rc;
}

int fb_reduced_check(const fb_reduced *r, fb_err *err)
{
  if (!r)
    return fb_err_set(err, FB_EINVAL, "reduced structure is NULL");
  const size_t n = r->ndof;
  if (n == 0)
    return fb_err_set(err, FB_EMODEL, "%s: no DOF", r->path[0]);
  for (int k = 0; k < 2; ++k) {
    const fb_mat *m = k ? r->M : r->K;
    if (!m)
      continue;
    if (!fb_mat_all_finite(m))
      return fb_err_set(err, FB_EMODEL, "%s: %s has an entry that is not finite", r->path[k],
                        k ? "M" : "K");
    double *a = dense(m, n);
    if (!a)
      return fb_err_set(err, FB_ENOMEM, "out of memory checking %s", r->path[k]);
    int rc = check_symmetric(r, k, a, err);
    if (!rc)
      rc = k ? check_mass(r, a, err) : check_stiffness(r, a, err);
    free(a);
    if (rc)
      return rc;
  }
  return FB_OK;
}

/* The 6 x 6 system (R' W R) y = b, by Cholesky (W positive definite on
 * R: fb_reduced_check's total mass, or the identity). */
static int solve6(double *g, double *rhs, size_t nrhs)
{
  return LAPACKE_dposv(LAPACK_COL_MAJOR, 'U', 6, (int)nrhs, g, 6, rhs, 6) ? FB_ESOLVER : FB_OK;
}

int fb_reduced_stiffness_projected(const fb_reduced *r, fb_mat **out, fb_err *err)
{
  if (!r || !out)
    return fb_err_set(err, FB_EINVAL, "reduced structure or output is NULL");
  *out = NULL;
  const size_t n = r->ndof;
  double *k = dense(r->K, n), *w = r->M ? dense(r->M, n) : NULL;
  double *R = malloc(6 * n * sizeof *R), *WR = malloc(6 * n * sizeof *WR),
         *A = malloc(6 * n * sizeof *A), *KP = malloc(n * n * sizeof *KP);
  int rc = (!k || (r->M && !w) || !R || !WR || !A || !KP)
               ? fb_err_set(err, FB_ENOMEM, "out of memory projecting %s", r->path[0])
               : FB_OK;
  if (!rc) {
    rigid_motions(r, R);
    /* WR = W R; G = R' W R; A = G^-1 (W R)' (6 x n) */
    for (int m = 0; m < 6; ++m)
      for (size_t i = 0; i < n; ++i) {
        double s = R[i + (size_t)m * n];
        if (w) {
          s = 0.0;
          for (size_t j = 0; j < n; ++j)
            s += w[i + j * n] * R[j + (size_t)m * n];
        }
        WR[i + (size_t)m * n] = s;
      }
    double g[36];
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) {
        double s = 0.0;
        for (size_t i = 0; i < n; ++i)
          s += R[i + (size_t)a * n] * WR[i + (size_t)b * n];
        g[a + 6 * b] = s;
      }
    for (size_t i = 0; i < n; ++i)
      for (int m = 0; m < 6; ++m)
        A[m + 6 * i] = WR[i + (size_t)m * n];
    if (solve6(g, A, n))
      rc = fb_err_set(err, FB_ESOLVER,
                      "%s: the interface's rigid-body motions are not independent", r->path[0]);
  }
  if (!rc) {
    /* K P = K - (K R) A, then P' (K P) = K P - A' (R' K P); the last is
     * zero for an exact K, kept for a rounded one. */
    for (int pass = 0; pass < 2; ++pass) {
      for (size_t j = 0; j < n; ++j) {
        double kr[6];
        for (int m = 0; m < 6; ++m) {
          double s = 0.0;
          for (size_t i = 0; i < n; ++i)
            s += k[j + i * n] * R[i + (size_t)m * n]; /* (K R)_jm, K^T for pass 2 */
          kr[m] = s;
        }
        for (size_t i = 0; i < n; ++i) {
          double s = 0.0;
          for (int m = 0; m < 6; ++m)
            s += kr[m] * A[m + 6 * i];
          KP[i + j * n] = k[j + i * n] - s; /* (K P)^T: row j of K P as column j */
        }
      }
      memcpy(k, KP, n * n * sizeof *k);
    }
    /* Symmetric to round-off; made exactly so. */
    for (size_t j = 0; j < n; ++j)
      for (size_t i = j + 1; i < n; ++i)
        k[i + j * n] = k[j + i * n] = 0.5 * (k[i + j * n] + k[j + i * n]);
    rc = fb_mat_new_dense(n, n, k, out, err);
  }
  free(k);
  free(w);
  free(R);
  free(WR);
  free(A);
  free(KP);
  return rc;
}
