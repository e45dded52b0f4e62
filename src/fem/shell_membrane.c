/* SPDX-License-Identifier: BSD-3-Clause */
/* Membrane (in-plane) stiffness of the flat shell elements, in the
 * element's local frame, on the DOFs (u, v, rz) of each node.
 *
 * Triangle: the optimal ANDES membrane triangle "OPT" with corner drilling
 * freedoms, C. A. Felippa, "A study of optimal membrane triangles with
 * drilling freedoms", Comput. Methods Appl. Mech. Engrg. 192 (2003)
 * 2125-2168 (equation numbers below refer to it). Its stiffness is the
 * sum of a basic part (constant stress, Allman-type boundary displacement,
 * eq. 22) that alone passes the patch test, and a higher-order part on
 * the deviatoric corner rotations (eqs. 16, 29-32) tuned so that the
 * element is exact in pure in-plane bending of rectangular mesh units.
 * The drilling rotation is a real freedom: the element needs no
 * fictitious drilling stiffness.
 *
 * Quadrilateral: bilinear displacements plus the incompatible modes
 * 1 - xi^2, 1 - eta^2 (E. L. Wilson, R. L. Taylor, W. P. Doherty & J.
 * Ghaboussi, "Incompatible displacement models", in Numerical and
 * Computer Methods in Structural Mechanics, Academic Press 1973), with the derivatives of the
 * incompatible modes taken from the Jacobian at the element centre and
 * scaled by det J0 / det J so that they integrate to zero and the element
 * passes the patch test on any convex quadrilateral: QM6 of R. L. Taylor,
 * P. J. Beresford & E. L. Wilson, "A non-conforming element for stress
 * analysis", Int. J. Numer. Meth. Engng 10 (1976) 1211-1219. The four
 * internal parameters are condensed out. It is exact in pure in-plane
 * bending of rectangles, where the plain bilinear element locks. Its
 * nodes have no drilling stiffness of their own, so a fictitious one is
 * added as a penalty on the difference between each node's rotation rz and
 * the continuum rotation (v,x - u,y) / 2 of the element's displacement
 * field at that node (the idea of T. J. R. Hughes & F. Brezzi, "On
 * drilling degrees of freedom", Comput. Methods Appl. Mech. Engrg. 72
 * (1989) 105-121, here with nodal quadrature), with the stiffness
 * drill_factor E t A / 4 per node. The rotation includes the incompatible
 * modes (the penalty is added before they are condensed out), so in pure
 * in-plane bending of a rectangle, where that field is exact, the penalty
 * stores no energy and the element stays exact. It vanishes for
 * rigid-body motions too, which therefore remain exact. */
#include <math.h>
#include <string.h>

#include "fem/shell_internal.h"

const double fb_shell_quad_xi[4] = {-1.0, 1.0, 1.0, -1.0};
const double fb_shell_quad_eta[4] = {-1.0, -1.0, 1.0, 1.0};

void fb_shell_plane_stress(double young, double poisson, double s, double *c)
{
  const double f = s * young / (1.0 - poisson * poisson);
  const double vals[9] = {
      f, f * poisson, 0.0, f * poisson, f, 0.0, 0.0, 0.0, f * (1.0 - poisson) / 2.0};
  memcpy(c, vals, sizeof vals);
}

/* c (m x n, column-major, leading dimension ldc) += s * a^T b with a (r x
 * m) and b (r x n) row-major of r rows: the product form of B^T D B. */
static void add_atb(size_t r, size_t m, size_t n, const double *a, const double *b, double s,
                    double *c, size_t ldc)
{
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < m; ++i) {
      double sum = 0.0;
      for (size_t q = 0; q < r; ++q)
        sum += a[q * m + i] * b[q * n + j];
      c[j * ldc + i] += s * sum;
    }
}

/* out (r x n row-major) = d (r x r row-major) * b (r x n row-major). */
static void mul_rows(size_t r, size_t n, const double *d, const double *b, double *out)
{
  for (size_t i = 0; i < r; ++i)
    for (size_t j = 0; j < n; ++j) {
      double sum = 0.0;
      for (size_t q = 0; q < r; ++q)
        sum += d[i * r + q] * b[q * n + j];
      out[i * n + j] = sum;
    }
}

/* Inverse of a 3x3 row-major matrix (non-singular by the caller's
 * geometry: the three side directions of a triangle are distinct). */
static void inverse3(const double *a, double *inv)
{
  const double c00 = a[4] * a[8] - a[5] * a[7];
  const double c01 = a[5] * a[6] - a[3] * a[8];
  const double c02 = a[3] * a[7] - a[4] * a[6];
  const double det = a[0] * c00 + a[1] * c01 + a[2] * c02;
  inv[0] = c00 / det;
  inv[1] = (a[2] * a[7] - a[1] * a[8]) / det;
  inv[2] = (a[1] * a[5] - a[2] * a[4]) / det;
  inv[3] = c01 / det;
  inv[4] = (a[0] * a[8] - a[2] * a[6]) / det;
  inv[5] = (a[2] * a[3] - a[0] * a[5]) / det;
  inv[6] = c02 / det;
  inv[7] = (a[1] * a[6] - a[0] * a[7]) / det;
  inv[8] = (a[0] * a[4] - a[1] * a[3]) / det;
}

/* ---- OPT triangle. */

/* Parameters of OPT for an isotropic material (Felippa 2003): alpha_b =
 * 3/2, beta_1..9 below, and beta_0 = (1 - 4 nu^2) / 2, kept at least
 * 0.01. With them two triangles forming a rectangle store the exact energy
 * of pure in-plane bending at any aspect ratio and Poisson's ratio, the
 * property the parameters were chosen for (test_shell checks it). */
#define OPT_ALPHA_B 1.5
static const double opt_beta[9] = {1.0, 2.0, 1.0, 0.0, 1.0, -1.0, -1.0, -1.0, -2.0};

/* Which beta (0-based) stands in each entry of Q1, Q2, Q3 (eq. 29, row-major):
 * Q2 and Q3 follow from Q1 by the cyclic permutation of the corners. */
static const int opt_q_index[3][9] = {
    {0, 1, 2, 3, 4, 5, 6, 7, 8}, {8, 6, 7, 2, 0, 1, 5, 3, 4}, {4, 5, 3, 7, 8, 6, 1, 2, 0}};

/* Force-lumping matrix L / t (9x3 row-major) of eq. 22: nodal forces and
 * couples from a constant stress (sx, sy, sxy). Translational rows are
 * those of the constant-strain triangle. The drilling rows follow from
 * the Allman-type boundary displacement: along a side a->b of length l the
 * outward normal displacement gains alpha_b s (l - s) (rz_b - rz_a) / (2 l)
 * (D. J. Allman, Comput. Struct. 19 (1984) 1-8), whose work against the
 * normal traction sn is alpha_b l^2 sn (rz_b - rz_a) / 12, with l^2 sn =
 * dy^2 sx + dx^2 sy - 2 dx dy sxy for the side (dx, dy) = b - a. */
static void opt_lumping(const double *x, const double *y, double *lump)
{
  memset(lump, 0, 27 * sizeof *lump);
  for (int a = 0; a < 3; ++a) {
    const int j = (a + 1) % 3, k = (a + 2) % 3;
    const double b = y[j] - y[k], c = x[k] - x[j];
    lump[(3 * a) * 3 + 0] = b / 2.0;
    lump[(3 * a) * 3 + 2] = c / 2.0;
    lump[(3 * a + 1) * 3 + 1] = c / 2.0;
    lump[(3 * a + 1) * 3 + 2] = b / 2.0;
  }
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3;
    const double dx = x[b] - x[a], dy = y[b] - y[a];
    const double work[3] = {dy * dy, dx * dx, -2.0 * dx * dy};
    for (int q = 0; q < 3; ++q) {
      lump[(3 * a + 2) * 3 + q] -= OPT_ALPHA_B / 12.0 * work[q];
      lump[(3 * b + 2) * 3 + q] += OPT_ALPHA_B / 12.0 * work[q];
    }
  }
}

/* T_theta_u (3x9 row-major, eq. 16): deviatoric corner rotations, the
 * corner rotation minus the constant rotation (v,x - u,y) / 2 of the
 * linear displacement field. */
static void opt_deviatoric(const double *x, const double *y, double area, double *t)
{
  memset(t, 0, 27 * sizeof *t);
  for (int i = 0; i < 3; ++i) {
    for (int a = 0; a < 3; ++a) {
      const int j = (a + 1) % 3, k = (a + 2) % 3;
      t[i * 9 + 3 * a] = (x[k] - x[j]) / (4.0 * area);
      t[i * 9 + 3 * a + 1] = -(y[j] - y[k]) / (4.0 * area);
    }
    t[i * 9 + 3 * i + 2] = 1.0;
  }
}

/* Elasticity in natural (side-direction) strains, Enat = Te^T C Te (eq.
 * 12): Te inverts the strain-gauge rosette relation eps_side = (dx^2 ex +
 * dy^2 ey + dx dy gxy) / l^2 over the sides 1-2, 2-3, 3-1. Also returns the
 * squared side lengths in that order. */
static void opt_natural_elasticity(const double *x, const double *y, const double *c,
                                   double *enat, double *len2)
{
  double rosette[9], te[9], cte[9];
  for (int s = 0; s < 3; ++s) {
    const int b = (s + 1) % 3;
    const double dx = x[b] - x[s], dy = y[b] - y[s];
    len2[s] = dx * dx + dy * dy;
    rosette[3 * s] = dx * dx / len2[s];
    rosette[3 * s + 1] = dy * dy / len2[s];
    rosette[3 * s + 2] = dx * dy / len2[s];
  }
  inverse3(rosette, te);
  mul_rows(3, 3, c, te, cte);
  memset(enat, 0, 9 * sizeof *enat);
  add_atb(3, 3, 3, te, cte, 1.0, enat, 3);
}

/* Higher-order stiffness on the deviatoric rotations (3x3 column-major):
 * (3/4) beta_0 A t sum over the side midpoints of Q^T Enat Q, with Q the
 * mean of the two corner matrices Q_i (eqs. 29-32; the midpoint rule
 * integrates the quadratic energy density exactly). */
static void opt_higher_order(const double *x, const double *y, double area,
                             const fb_shell_props *p, double *kth)
{
  double c[9], enat[9], len2[3], q[3][9];
  fb_shell_plane_stress(p->young, p->poisson, 1.0, c);
  opt_natural_elasticity(x, y, c, enat, len2);
  for (int i = 0; i < 3; ++i)
    for (int e = 0; e < 9; ++e)
      q[i][e] = 2.0 * area / 3.0 * opt_beta[opt_q_index[i][e]] / len2[e / 3];
  double beta0 = (1.0 - 4.0 * p->poisson * p->poisson) / 2.0;
  beta0 = beta0 > 0.01 ? beta0 : 0.01;
  memset(kth, 0, 9 * sizeof *kth);
  for (int m = 0; m < 3; ++m) {
    double qm[9], eq[9];
    for (int e = 0; e < 9; ++e)
      qm[e] = (q[m][e] + q[(m + 1) % 3][e]) / 2.0;
    mul_rows(3, 3, enat, qm, eq);
    add_atb(3, 3, 3, qm, eq, 0.75 * beta0 * area * p->thickness, kth, 3);
  }
}

void fb_shell_membrane_tri(const double *x, const double *y, double area,
                           const fb_shell_props *p, double *k)
{
  double c[9], lump[27], lc[27];
  fb_shell_plane_stress(p->young, p->poisson, 1.0, c);
  opt_lumping(x, y, lump);
  /* Basic stiffness L C L^T / (A t) with L = t lump (eq. 22). */
  double lump_t[27];
  for (int i = 0; i < 9; ++i)
    for (int q = 0; q < 3; ++q)
      lump_t[q * 9 + i] = lump[i * 3 + q];
  mul_rows(3, 9, c, lump_t, lc);
  memset(k, 0, 81 * sizeof *k);
  add_atb(3, 9, 9, lump_t, lc, p->thickness / area, k, 9);

  double tdev[27], kth[9], kt[27];
  opt_deviatoric(x, y, area, tdev);
  opt_higher_order(x, y, area, p, kth);
  /* kth is symmetric, so its column-major storage reads as row-major. */
  mul_rows(3, 9, kth, tdev, kt);
  add_atb(3, 9, 9, tdev, kt, 1.0, k, 9);
}

/* OPT's membrane strain at the centroid is the basic part's constant
 * strain lump^T u / A (its higher-order strains, sum of the corner
 * matrices Q_i over the three corners, vanish there: each entry of
 * Q1 + Q2 + Q3 is a sum of betas that is 0). */
static void opt_centre_strain(const double *x, const double *y, double area, double *bm)
{
  double lump[27];
  opt_lumping(x, y, lump);
  for (int q = 0; q < 3; ++q)
    for (int i = 0; i < 9; ++i)
      bm[q * 9 + i] = lump[i * 3 + q] / area;
}

/* ---- QM6 quadrilateral. */

void fb_shell_quad_jacobian(const double *x, const double *y, double xi, double eta,
                            double *jac)
{
  jac[0] = jac[1] = jac[2] = jac[3] = 0.0;
  for (int a = 0; a < 4; ++a) {
    const double dxi = fb_shell_quad_xi[a] * (1.0 + eta * fb_shell_quad_eta[a]) / 4.0;
    const double deta = fb_shell_quad_eta[a] * (1.0 + xi * fb_shell_quad_xi[a]) / 4.0;
    jac[0] += dxi * x[a];
    jac[1] += dxi * y[a];
    jac[2] += deta * x[a];
    jac[3] += deta * y[a];
  }
}

void fb_shell_quad_bilinear(const double *x, const double *y, double xi, double eta, double *n,
                            double *dndx, double *dndy, double *detj)
{
  double jac[4];
  fb_shell_quad_jacobian(x, y, xi, eta, jac);
  *detj = jac[0] * jac[3] - jac[1] * jac[2];
  for (int a = 0; a < 4; ++a) {
    const double xa = fb_shell_quad_xi[a], ea = fb_shell_quad_eta[a];
    const double dxi = xa * (1.0 + eta * ea) / 4.0, deta = ea * (1.0 + xi * xa) / 4.0;
    n[a] = (1.0 + xi * xa) * (1.0 + eta * ea) / 4.0;
    dndx[a] = (jac[3] * dxi - jac[1] * deta) / *detj;
    dndy[a] = (-jac[2] * dxi + jac[0] * deta) / *detj;
  }
}

/* Number of DOFs of the uncondensed QM6 element: (u, v, rz) at the four
 * nodes, then the four incompatible parameters (u of 1 - xi^2, u of
 * 1 - eta^2, v of 1 - xi^2, v of 1 - eta^2). */
#define QM6_EXT 12
#define QM6_ALL 16

/* Derivatives of the displacement field at (xi, eta) per unit DOF:
 * dux[i] = d/dx of u per unit value of DOF i, and so on, over QM6_ALL
 * DOFs. The incompatible modes' derivatives are QM6's: the parametric
 * ones mapped by the Jacobian at the centre j0 and scaled by det J0 /
 * det J, which makes them integrate to zero (det J0 cancels against
 * J0^-1's denominator). Returns det J. */
static double qm6_gradients(const double *x, const double *y, const double *j0, double xi,
                            double eta, double *dux, double *duy, double *dvx, double *dvy)
{
  double n[4], dndx[4], dndy[4], detj;
  fb_shell_quad_bilinear(x, y, xi, eta, n, dndx, dndy, &detj);
  memset(dux, 0, QM6_ALL * sizeof *dux);
  memset(duy, 0, QM6_ALL * sizeof *duy);
  memset(dvx, 0, QM6_ALL * sizeof *dvx);
  memset(dvy, 0, QM6_ALL * sizeof *dvy);
  for (int a = 0; a < 4; ++a) {
    dux[3 * a] = dndx[a];
    duy[3 * a] = dndy[a];
    dvx[3 * a + 1] = dndx[a];
    dvy[3 * a + 1] = dndy[a];
  }
  const double pxi[2] = {-2.0 * xi, 0.0}, peta[2] = {0.0, -2.0 * eta};
  for (int m = 0; m < 2; ++m) {
    const double px = (j0[3] * pxi[m] - j0[1] * peta[m]) / detj;
    const double py = (-j0[2] * pxi[m] + j0[0] * peta[m]) / detj;
    dux[QM6_EXT + m] = px;
    duy[QM6_EXT + m] = py;
    dvx[QM6_EXT + 2 + m] = px;
    dvy[QM6_EXT + 2 + m] = py;
  }
  return detj;
}

/* Adds w g g^T to the QM6_ALL square k (column-major). */
static void add_outer(const double *g, double w, double *k)
{
  for (int j = 0; j < QM6_ALL; ++j)
    for (int i = 0; i < QM6_ALL; ++i)
      k[j * QM6_ALL + i] += w * g[i] * g[j];
}

/* Uncondensed QM6 stiffness (2x2 Gauss points) plus the drilling penalty,
 * QM6_ALL square, column-major. The penalty ties each node's rz to the
 * rotation (v,x - u,y) / 2 of the element's whole field at that node,
 * incompatible modes included: in pure in-plane bending of a rectangle
 * that field is exact, so the penalty then stores no energy and does not
 * stiffen the element. */
static void qm6_full(const double *x, const double *y, double area, const fb_shell_props *p,
                     double *k)
{
  static const double gauss = 0.57735026918962576451; /* 1 / sqrt(3) */
  double c[9], j0[4], dux[QM6_ALL], duy[QM6_ALL], dvx[QM6_ALL], dvy[QM6_ALL];
  fb_shell_plane_stress(p->young, p->poisson, p->thickness, c);
  fb_shell_quad_jacobian(x, y, 0.0, 0.0, j0);
  memset(k, 0, QM6_ALL * QM6_ALL * sizeof *k);
  for (int gp = 0; gp < 4; ++gp) {
    const double detj = qm6_gradients(x, y, j0, fb_shell_quad_xi[gp] * gauss,
                                      fb_shell_quad_eta[gp] * gauss, dux, duy, dvx, dvy);
    double b[3 * QM6_ALL], cb[3 * QM6_ALL];
    for (int i = 0; i < QM6_ALL; ++i) {
      b[i] = dux[i];
      b[QM6_ALL + i] = dvy[i];
      b[2 * QM6_ALL + i] = duy[i] + dvx[i];
    }
    mul_rows(3, QM6_ALL, c, b, cb);
    add_atb(3, QM6_ALL, QM6_ALL, b, cb, detj, k, QM6_ALL);
  }
  const double factor = p->drill_factor > 0.0 ? p->drill_factor : FB_SHELL_DRILL_DEFAULT;
  const double k_node = factor * p->young * p->thickness * area / 4.0;
  for (int node = 0; node < 4; ++node) {
    double g[QM6_ALL];
    (void)qm6_gradients(x, y, j0, fb_shell_quad_xi[node], fb_shell_quad_eta[node], dux, duy,
                        dvx, dvy);
    for (int i = 0; i < QM6_ALL; ++i)
      g[i] = (duy[i] - dvx[i]) / 2.0; /* rz - (v,x - u,y) / 2 */
    g[3 * node + 2] = 1.0;
    add_outer(g, k_node, k);
  }
}

/* Solves the 4x4 symmetric positive definite system a x = b for nrhs
 * right-hand sides (b column-major 4 x nrhs, overwritten with x) by
 * Cholesky; a is overwritten. */
static void solve_spd4(double *a, double *b, size_t nrhs)
{
  for (int j = 0; j < 4; ++j) {
    double d = a[j * 4 + j];
    for (int q = 0; q < j; ++q)
      d -= a[j * 4 + q] * a[j * 4 + q];
    a[j * 4 + j] = sqrt(d);
    for (int i = j + 1; i < 4; ++i) {
      double s = a[i * 4 + j];
      for (int q = 0; q < j; ++q)
        s -= a[i * 4 + q] * a[j * 4 + q];
      a[i * 4 + j] = s / a[j * 4 + j];
    }
  }
  for (size_t r = 0; r < nrhs; ++r) {
    double *v = b + 4 * r;
    for (int i = 0; i < 4; ++i) {
      for (int q = 0; q < i; ++q)
        v[i] -= a[i * 4 + q] * v[q];
      v[i] /= a[i * 4 + i];
    }
    for (int i = 3; i >= 0; --i) {
      for (int q = i + 1; q < 4; ++q)
        v[i] -= a[q * 4 + i] * v[q];
      v[i] /= a[i * 4 + i];
    }
  }
}

void fb_shell_membrane_quad(const double *x, const double *y, double area,
                            const fb_shell_props *p, double *k)
{
  double full[QM6_ALL * QM6_ALL], kii[16], kie[4 * QM6_EXT], sol[4 * QM6_EXT];
  qm6_full(x, y, area, p, full);
  /* Static condensation of the internal parameters: K = Kee - Kei Kii^-1 Kie. */
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      kii[j * 4 + i] = full[(QM6_EXT + j) * QM6_ALL + QM6_EXT + i];
  for (int j = 0; j < QM6_EXT; ++j)
    for (int i = 0; i < 4; ++i)
      kie[j * 4 + i] = full[j * QM6_ALL + QM6_EXT + i];
  memcpy(sol, kie, sizeof sol);
  solve_spd4(kii, sol, QM6_EXT);
  for (int j = 0; j < QM6_EXT; ++j)
    for (int i = 0; i < QM6_EXT; ++i) {
      double s = full[j * QM6_ALL + i];
      for (int q = 0; q < 4; ++q)
        s -= kie[i * 4 + q] * sol[j * 4 + q];
      k[j * QM6_EXT + i] = s;
    }
}

/* QM6's incompatible modes have zero derivatives at xi = eta = 0, so the
 * strain there is the bilinear field's alone: no condensed parameter is
 * needed to recover it. The drilling rotations do not enter it. */
static void qm6_centre_strain(const double *x, const double *y, double *bm)
{
  double n[4], dndx[4], dndy[4], detj;
  fb_shell_quad_bilinear(x, y, 0.0, 0.0, n, dndx, dndy, &detj);
  memset(bm, 0, 36 * sizeof *bm);
  for (int a = 0; a < 4; ++a) {
    bm[0 * 12 + 3 * a] = dndx[a];
    bm[1 * 12 + 3 * a + 1] = dndy[a];
    bm[2 * 12 + 3 * a] = dndy[a];
    bm[2 * 12 + 3 * a + 1] = dndx[a];
  }
}

void fb_shell_membrane_strain(size_t nn, const double *x, const double *y, double area,
                              double *bm)
{
  if (nn == 3)
    opt_centre_strain(x, y, area, bm);
  else
    qm6_centre_strain(x, y, bm);
}
