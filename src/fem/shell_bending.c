/* SPDX-License-Identifier: BSD-3-Clause */
/* Plate bending stiffness of the flat shell elements (Kirchhoff plates), in
 * the element's local frame, on the DOFs (w, rx, ry) of each node.
 *
 * Both elements are discrete Kirchhoff elements: the rotations of the
 * normal (bx, by) = (ry, -rx) (so that b = -grad w where the Kirchhoff
 * hypothesis holds) are interpolated over 2 nn nodes, the nn corners and
 * the nn side midpoints, and the Kirchhoff hypothesis is imposed at
 * discrete points only:
 *  - at the corners, b equals the nodal rotations;
 *  - along each side, w is cubic (Hermite, from w and its tangential
 *    slope -b.s at the two corners), and the tangential rotation at the
 *    midpoint is b.s = -dw/ds of that cubic:
 *      b_s,mid = -3 (w_j - w_i) / (2 l) - (b_s,i + b_s,j) / 4;
 *  - the normal rotation b.n varies linearly along each side:
 *      b_n,mid = (b_n,i + b_n,j) / 2.
 * The curvatures are kappa = (bx,x, by,y, bx,y + by,x) and the stiffness
 * is the integral of kappa^T Db kappa, Db = E t^3 / (12 (1 - nu^2)) [1 nu
 * 0; nu 1 0; 0 0 (1 - nu)/2]; transverse shear strain energy is neglected.
 *
 * Triangle, DKT: J.-L. Batoz, K.-J. Bathe & L.-W. Ho, "A study of
 * three-node triangular plate bending elements", Int. J. Numer. Meth.
 * Engng 15 (1980) 1771-1812: b is quadratic over the six-node triangle;
 * its curvature is linear, so the three-point rule at the points (2/3,
 * 1/6, 1/6) of area coordinates integrates the energy exactly.
 *
 * Quadrilateral, DKQ: J.-L. Batoz & M. Ben Tahar, "Evaluation of a new
 * quadrilateral thin plate bending element", Int. J. Numer. Meth. Engng 18
 * (1982) 1655-1677: b is interpolated by the eight-node serendipity
 * functions over the bilinear geometry, integrated with 2x2 Gauss points
 * as in that paper.
 *
 * Both reproduce any linear field b exactly (a quadratic w is the cubic on
 * each side and its normal slope is linear along it), hence every
 * constant-curvature state: they pass the patch test on distorted meshes. */
#include <math.h>
#include <string.h>

#include "fem/shell_internal.h"

/* The discrete Kirchhoff constraints: g (2 nb x 3 nn, row-major) maps the
 * bending DOFs (w, rx, ry) of the nn corners to (bx, by) at the nb = 2 nn
 * rotation nodes (corners, then the midpoint of side i -> i+1 as node nn +
 * i). */
static void kirchhoff_constraints(size_t nn, const double *x, const double *y, double *g)
{
  const size_t ncol = 3 * nn;
  memset(g, 0, 2 * 2 * nn * ncol * sizeof *g);
  for (size_t a = 0; a < nn; ++a) {
    g[(2 * a) * ncol + 3 * a + 2] = 1.0;      /* bx = ry */
    g[(2 * a + 1) * ncol + 3 * a + 1] = -1.0; /* by = -rx */
  }
  for (size_t side = 0; side < nn; ++side) {
    const size_t i = side, j = (side + 1) % nn, mid = nn + side;
    const double dx = x[j] - x[i], dy = y[j] - y[i];
    const double len = hypot(dx, dy);
    const double tx = dx / len, ty = dy / len, nx = ty, ny = -tx;
    /* b_mid = -3 (w_j - w_i) / (2 l) s + P (b_i + b_j) with P = n n^T / 2 -
     * s s^T / 4, and b = S (rx, ry) with S = [0 1; -1 0]. */
    const double p00 = nx * nx / 2.0 - tx * tx / 4.0, p01 = nx * ny / 2.0 - tx * ty / 4.0;
    const double p11 = ny * ny / 2.0 - ty * ty / 4.0;
    const double ps[2][2] = {{-p01, p00}, {-p11, p01}};
    const double t[2] = {tx, ty};
    for (int r = 0; r < 2; ++r) {
      double *row = g + (2 * mid + (size_t)r) * ncol;
      row[3 * i] += 1.5 / len * t[r];
      row[3 * j] -= 1.5 / len * t[r];
      for (int c = 0; c < 2; ++c) {
        row[3 * i + 1 + (size_t)c] += ps[r][c];
        row[3 * j + 1 + (size_t)c] += ps[r][c];
      }
    }
  }
}

/* The curvature matrix Bb = Bbeta g (3 x 3 nn row-major) at one point,
 * where dndx, dndy are the derivatives of the nb = 2 nn rotation-node
 * shape functions there. */
static void curvature_matrix(size_t nn, const double *g, const double *dndx, const double *dndy,
                             double *bb)
{
  const size_t nb = 2 * nn, ncol = 3 * nn;
  memset(bb, 0, 3 * ncol * sizeof *bb);
  for (size_t a = 0; a < nb; ++a)
    for (size_t c = 0; c < ncol; ++c) {
      const double gx = g[(2 * a) * ncol + c], gy = g[(2 * a + 1) * ncol + c];
      bb[0 * ncol + c] += dndx[a] * gx;
      bb[1 * ncol + c] += dndy[a] * gy;
      bb[2 * ncol + c] += dndy[a] * gx + dndx[a] * gy;
    }
}

/* Adds w Bb^T Db Bb to k (3 nn square, column-major) for the curvature
 * matrix at one integration point. */
static void add_point(size_t nn, const double *g, const double *dndx, const double *dndy,
                      const double *db, double w, double *k)
{
  const size_t ncol = 3 * nn;
  double bb[3 * 3 * FB_SHELL_MAX_NODES], dbb[3 * 3 * FB_SHELL_MAX_NODES];
  curvature_matrix(nn, g, dndx, dndy, bb);
  for (size_t r = 0; r < 3; ++r)
    for (size_t c = 0; c < ncol; ++c)
      dbb[r * ncol + c] =
          db[r * 3] * bb[c] + db[r * 3 + 1] * bb[ncol + c] + db[r * 3 + 2] * bb[2 * ncol + c];
  for (size_t j = 0; j < ncol; ++j)
    for (size_t i = 0; i < ncol; ++i)
      k[j * ncol + i] += w * (bb[i] * dbb[j] + bb[ncol + i] * dbb[ncol + j] +
                              bb[2 * ncol + i] * dbb[2 * ncol + j]);
}

/* DKT: derivatives of the six-node quadratic triangle at the area
 * coordinates l[3]: corners l_a (2 l_a - 1), midside of a -> b 4 l_a l_b. */
static void dkt_derivatives(const double *x, const double *y, double area, const double *l,
                            double *dndx, double *dndy)
{
  double lx[3], ly[3];
  for (int a = 0; a < 3; ++a) {
    const int j = (a + 1) % 3, k = (a + 2) % 3;
    lx[a] = (y[j] - y[k]) / (2.0 * area);
    ly[a] = (x[k] - x[j]) / (2.0 * area);
  }
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3;
    dndx[a] = (4.0 * l[a] - 1.0) * lx[a];
    dndy[a] = (4.0 * l[a] - 1.0) * ly[a];
    dndx[3 + a] = 4.0 * (lx[a] * l[b] + l[a] * lx[b]);
    dndy[3 + a] = 4.0 * (ly[a] * l[b] + l[a] * ly[b]);
  }
}

static void dkt_stiffness(const double *x, const double *y, const double *db, double *k)
{
  double g[2 * 6 * 9]; /* (bx, by) at 6 rotation nodes from 9 DOFs */
  const double area = ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0])) / 2.0;
  kirchhoff_constraints(3, x, y, g);
  for (int gp = 0; gp < 3; ++gp) {
    double l[3] = {1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0}, dndx[6], dndy[6];
    l[gp] = 2.0 / 3.0;
    dkt_derivatives(x, y, area, l, dndx, dndy);
    add_point(3, g, dndx, dndy, db, area / 3.0, k);
  }
}

/* DKQ: derivatives of the eight-node serendipity functions at (xi, eta),
 * mapped through the bilinear geometry of the corners; det J in *detj. */
static void dkq_derivatives(const double *x, const double *y, double xi, double eta,
                            double *dndx, double *dndy, double *detj)
{
  double dxi[8], deta[8], jac[4];
  for (int a = 0; a < 4; ++a) {
    const double xa = fb_shell_quad_xi[a], ea = fb_shell_quad_eta[a];
    dxi[a] = xa * (1.0 + eta * ea) * (2.0 * xi * xa + eta * ea) / 4.0;
    deta[a] = ea * (1.0 + xi * xa) * (xi * xa + 2.0 * eta * ea) / 4.0;
    const int b = (a + 1) % 4;
    const double xm = (xa + fb_shell_quad_xi[b]) / 2.0, em = (ea + fb_shell_quad_eta[b]) / 2.0;
    if (xm == 0.0) { /* (1 - xi^2) (1 + eta em) / 2 */
      dxi[4 + a] = -xi * (1.0 + eta * em);
      deta[4 + a] = (1.0 - xi * xi) * em / 2.0;
    } else { /* (1 + xi xm) (1 - eta^2) / 2 */
      dxi[4 + a] = xm * (1.0 - eta * eta) / 2.0;
      deta[4 + a] = -eta * (1.0 + xi * xm);
    }
  }
  fb_shell_quad_jacobian(x, y, xi, eta, jac);
  *detj = jac[0] * jac[3] - jac[1] * jac[2];
  for (int a = 0; a < 8; ++a) {
    dndx[a] = (jac[3] * dxi[a] - jac[1] * deta[a]) / *detj;
    dndy[a] = (-jac[2] * dxi[a] + jac[0] * deta[a]) / *detj;
  }
}

static void dkq_stiffness(const double *x, const double *y, const double *db, double *k)
{
  static const double gauss = 0.57735026918962576451; /* 1 / sqrt(3) */
  double g[2 * 8 * 12]; /* (bx, by) at 8 rotation nodes from 12 DOFs */
  kirchhoff_constraints(4, x, y, g);
  for (int gp = 0; gp < 4; ++gp) {
    double dndx[8], dndy[8], detj;
    dkq_derivatives(x, y, fb_shell_quad_xi[gp] * gauss, fb_shell_quad_eta[gp] * gauss, dndx,
                    dndy, &detj);
    add_point(4, g, dndx, dndy, db, detj, k);
  }
}

void fb_shell_bending_curvature(size_t nn, const double *x, const double *y, double *bb)
{
  double g[2 * 8 * 12], dndx[8], dndy[8];
  kirchhoff_constraints(nn, x, y, g);
  if (nn == 3) {
    const double area = ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0])) / 2.0;
    const double l[3] = {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0};
    dkt_derivatives(x, y, area, l, dndx, dndy);
  } else {
    double detj;
    dkq_derivatives(x, y, 0.0, 0.0, dndx, dndy, &detj);
  }
  curvature_matrix(nn, g, dndx, dndy, bb);
}

void fb_shell_bending(size_t nn, const double *x, const double *y, const fb_shell_props *p,
                      double *k)
{
  double db[9];
  const double t = p->thickness;
  fb_shell_plane_stress(p->young, p->poisson, t * t * t / 12.0, db);
  memset(k, 0, 9 * nn * nn * sizeof *k);
  if (nn == 3)
    dkt_stiffness(x, y, db, k);
  else
    dkq_stiffness(x, y, db, k);
}
