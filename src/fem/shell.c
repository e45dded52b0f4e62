/* SPDX-License-Identifier: BSD-3-Clause */
/* Flat shell elements with 6 DOF per node (fb_shell_element, see
 * flexbond/fem.h): the element's local frame, the membrane and bending
 * parts placed on the local DOFs, the rotation to global axes, and the
 * mass matrices.
 *
 * Local frame: origin at the centroid of the nodes, x along edge 1-2, z
 * along the normal (for a quadrilateral, the normal of its diagonals'
 * cross product, which averages a slight warp), y = z x x; node
 * coordinates are projected on the x-y plane. A warped quadrilateral's
 * nodes lie h_a off that plane (alternately above and below it): the flat
 * element acts at their projections, tied to the nodes by rigid links
 * along the normal, u_p = u_a + theta_a x (-h_a e_z), so that K = W^T K_flat W.
 * Without the links a rigid rotation of the nodes is not a rigid motion of
 * the projections, and a warped mesh stores energy under it (three of a
 * hull's six rigid-body modes become spurious ones near 0.02 Hz); with
 * them a rigid motion of the nodes is one of the flat element, exactly
 * (the rigid-link or projection correction of warped flat shell elements:
 * R. D. Cook, D. S. Malkus, M. E. Plesha & R. J. Witt, "Concepts and
 * Applications of Finite Element Analysis", 4th ed., 2002, the chapter on
 * plates and shells). Flat-element shells: the
 * membrane acts on (u, v, rz), the plate on (w, rx, ry), uncoupled in the
 * local frame (O. C. Zienkiewicz, R. L. Taylor & D. D. Fox, "The Finite
 * Element Method for Solid and Structural Mechanics", 7th ed., 2014, the
 * chapter "Shells as an assembly of flat elements"). Global = T^T local T
 * with T block-diagonal of the 3x3 rotation R (rows: local axes in global
 * components) for the translations and for the rotations of every node.
 *
 * Mass: consistent (default): the translational mass rho t int(N_a N_b) dA
 * of the linear (triangle) or bilinear (quadrilateral) shape functions for
 * u, v and w alike, which reproduces the rigid-body mass, first moments and
 * inertia of a thin plate exactly (those shape functions interpolate a
 * rigid motion exactly); rotary inertia (rho t^3 / 12) int(N_a N_b) dA for
 * rx and ry, the thickness term of the kinetic energy of a Kirchhoff plate
 * (the in-plane velocity z dtheta/dt integrated over the thickness gives
 * rho t^3 / 12 per unit area); and the same value for rz, where the plate
 * has no physical inertia: it keeps M positive definite and only adds
 * m t^2 / 12 to the inertia about the normal (1e-5 of it for the hull's
 * plates). Lumped: rho t A / nn for each translation of each node, rho t^3
 * A / (12 nn) for each rotation. Both are multiples of the 3x3 identity in
 * every node-pair block, so they are the same in local and global axes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem/shell_internal.h"
#include "fem/vec3.h"

/* A quadrilateral node may lie this far (relative to the longer diagonal)
 * off the element's mean plane: a guard for elements that fb_mesh_check
 * never saw, whose own limit (node 4 against the plane of nodes 1-3, about
 * twice the mean-plane distance) rejects warps half this size. */
#define WARP_LIMIT 1e-2
/* An offset from the mean plane at most this fraction of the longer
 * diagonal is the round-off of a flat element's coordinates (a generated
 * mesh's are off by ~1e-16): no link, which would change K in its last
 * digits only; what a warp this small leaves unlinked puts the rigid-body
 * modes near 1e-7 Hz. */
#define FLAT_OFFSET 1e-12
/* Relative area (to the squared longest edge or diagonal) below which an
 * element is degenerate: a sliver with an angle below about 1e-10 rad. */
#define DEGENERATE_AREA 1e-10

static int props_error(fb_err *err, const char *what, double value)
{
  return fb_err_set(err, FB_EINVAL, "shell properties: %s (got %g)", what, value);
}

/* NaN fails every test below. */
int fb_shell_check_props(const fb_shell_props *p, fb_err *err)
{
  if (!p)
    return fb_err_set(err, FB_EINVAL, "shell properties: NULL");
  if (!(p->young > 0.0 && isfinite(p->young)))
    return props_error(err, "Young's modulus must be positive and finite", p->young);
  if (!(p->poisson > -1.0 && p->poisson < 0.5))
    return props_error(err, "Poisson's ratio must lie in (-1, 0.5)", p->poisson);
  if (!(p->density > 0.0 && isfinite(p->density)))
    return props_error(err, "density must be positive and finite", p->density);
  if (!(p->thickness > 0.0 && isfinite(p->thickness)))
    return props_error(err, "thickness must be positive and finite", p->thickness);
  if (!(p->drill_factor >= 0.0 && isfinite(p->drill_factor)))
    return props_error(err, "drilling factor must be >= 0 and finite", p->drill_factor);
  if (!(p->nonstructural_mass >= 0.0 && isfinite(p->nonstructural_mass)))
    return props_error(err, "non-structural mass must be >= 0 and finite",
                       p->nonstructural_mass);
  return FB_OK;
}

/* Completes the frame from its normal (unit, rot[6..8]) and the nodes:
 * local x along edge 1-2 projected on the plane, coordinates relative to
 * the centroid. Returns the largest distance of a node from the plane. */
static double frame_axes(const double *xyz, fb_shell_frame *f)
{
  double *ex = f->rot, *ey = f->rot + 3, *ez = f->rot + 6, d12[3], c[3] = {0.0, 0.0, 0.0};
  fb_sub3(xyz + 3, xyz, d12);
  const double along = fb_dot3(d12, ez);
  for (int k = 0; k < 3; ++k)
    ex[k] = d12[k] - along * ez[k];
  const double len = sqrt(fb_dot3(ex, ex));
  for (int k = 0; k < 3; ++k)
    ex[k] /= len;
  fb_cross3(ez, ex, ey);
  for (size_t a = 0; a < f->nn; ++a)
    for (int k = 0; k < 3; ++k)
      c[k] += xyz[3 * a + (size_t)k] / (double)f->nn;
  double warp = 0.0;
  for (size_t a = 0; a < f->nn; ++a) {
    double d[3];
    fb_sub3(xyz + 3 * a, c, d);
    f->x[a] = fb_dot3(d, ex);
    f->y[a] = fb_dot3(d, ey);
    f->h[a] = fb_dot3(d, ez);
    warp = fmax(warp, fabs(f->h[a]));
  }
  return warp;
}

static int degenerate(fb_err *err, const char *shape)
{
  return fb_err_set(err, FB_EINVAL, "degenerate %s (zero area or repeated node)", shape);
}

static int triangle_frame(const double *xyz, fb_shell_frame *f, fb_err *err)
{
  double d12[3], d13[3], d23[3], normal[3];
  fb_sub3(xyz + 3, xyz, d12);
  fb_sub3(xyz + 6, xyz, d13);
  fb_sub3(xyz + 6, xyz + 3, d23);
  fb_cross3(d12, d13, normal);
  const double twice_area = sqrt(fb_dot3(normal, normal));
  const double longest2 = fmax(fb_dot3(d12, d12), fmax(fb_dot3(d13, d13), fb_dot3(d23, d23)));
  if (!(twice_area > 2.0 * DEGENERATE_AREA * longest2))
    return degenerate(err, "triangle");
  f->nn = 3;
  f->area = twice_area / 2.0;
  f->diagonal = sqrt(longest2);
  for (int k = 0; k < 3; ++k)
    f->rot[6 + k] = normal[k] / twice_area;
  (void)frame_axes(xyz, f);
  return FB_OK;
}

/* A quadrilateral must be flat (up to WARP_LIMIT) and strictly convex
 * with its nodes in order around it, so that the bilinear map has det J > 0
 * everywhere. */
static int quad_frame(const double *xyz, fb_shell_frame *f, fb_err *err)
{
  double d13[3], d24[3], normal[3];
  fb_sub3(xyz + 6, xyz, d13);
  fb_sub3(xyz + 9, xyz + 3, d24);
  fb_cross3(d13, d24, normal);
  const double twice_area = sqrt(fb_dot3(normal, normal));
  const double diag2 = fmax(fb_dot3(d13, d13), fb_dot3(d24, d24));
  if (!(twice_area > 2.0 * DEGENERATE_AREA * diag2))
    return degenerate(err, "quadrilateral");
  for (int a = 0; a < 4; ++a) {
    double side[3];
    fb_sub3(xyz + 3 * ((a + 1) % 4), xyz + 3 * a, side);
    if (!(fb_dot3(side, side) > DEGENERATE_AREA * diag2))
      return degenerate(err, "quadrilateral");
  }
  f->nn = 4;
  f->area = twice_area / 2.0;
  f->diagonal = sqrt(diag2);
  for (int k = 0; k < 3; ++k)
    f->rot[6 + k] = normal[k] / twice_area;
  const double warp = frame_axes(xyz, f);
  if (warp > WARP_LIMIT * sqrt(diag2))
    return fb_err_set(
        err, FB_EINVAL,
        "warped quadrilateral: a node lies %g m off the mean plane (diagonal %g m)", warp,
        sqrt(diag2));
  for (int a = 0; a < 4; ++a) {
    const int prev = (a + 3) % 4, next = (a + 1) % 4;
    const double turn = (f->x[a] - f->x[prev]) * (f->y[next] - f->y[a]) -
                        (f->y[a] - f->y[prev]) * (f->x[next] - f->x[a]);
    if (!(turn > DEGENERATE_AREA * diag2))
      return fb_err_set(err, FB_EINVAL,
                        "quadrilateral not strictly convex at its node %d (or nodes not in "
                        "order around it)",
                        a + 1);
  }
  return FB_OK;
}

int fb_shell_frame_make(fb_elem_type type, const double *xyz, fb_shell_frame *f, fb_err *err)
{
  return type == FB_ELEM_TRI3 ? triangle_frame(xyz, f, err) : quad_frame(xyz, f, err);
}

/* Places the membrane (u, v, rz) and bending (w, rx, ry) stiffness of the
 * element into its local 6 nn square stiffness (column-major). */
static void local_stiffness(const fb_shell_frame *f, const fb_shell_props *p, double *kl)
{
  static const size_t membrane_dof[3] = {0, 1, 5}, bending_dof[3] = {2, 3, 4};
  const size_t nn = f->nn, n = 6 * nn, nsub = 3 * nn;
  double km[144], kb[144];
  if (nn == 3)
    fb_shell_membrane_tri(f->x, f->y, f->area, p, km);
  else
    fb_shell_membrane_quad(f->x, f->y, f->area, p, km);
  fb_shell_bending(nn, f->x, f->y, p, kb);
  memset(kl, 0, n * n * sizeof *kl);
  for (size_t j = 0; j < nsub; ++j)
    for (size_t i = 0; i < nsub; ++i) {
      const size_t ni = i / 3, nj = j / 3;
      kl[(6 * nj + membrane_dof[j % 3]) * n + 6 * ni + membrane_dof[i % 3]] = km[j * nsub + i];
      kl[(6 * nj + bending_dof[j % 3]) * n + 6 * ni + bending_dof[i % 3]] = kb[j * nsub + i];
    }
}

/* kl = W^T kl W for the rigid links from the nodes to their projections
 * on the plane (local DOFs u v w rx ry rz): the projection of node a moves
 * by u - h_a ry, v + h_a rx, w, so W is the identity plus -h_a at (u_a,
 * ry_a) and +h_a at (v_a, rx_a). Columns first (kl W), then rows. */
static void link_offsets(const fb_shell_frame *f, double *kl)
{
  const size_t n = 6 * f->nn;
  for (size_t a = 0; a < f->nn; ++a) {
    const double h = f->h[a];
    if (fabs(h) <= FLAT_OFFSET * f->diagonal)
      continue;
    const size_t u = 6 * a, v = u + 1, rx = u + 3, ry = u + 4;
    for (size_t i = 0; i < n; ++i) {
      kl[ry * n + i] -= h * kl[u * n + i];
      kl[rx * n + i] += h * kl[v * n + i];
    }
    for (size_t j = 0; j < n; ++j) {
      kl[j * n + ry] -= h * kl[j * n + u];
      kl[j * n + rx] += h * kl[j * n + v];
    }
  }
}

/* kg = T^T kl T, 3x3 block by 3x3 block: kg_IJ = R^T kl_IJ R. */
static void to_global(size_t n, const double *rot, const double *kl, double *kg)
{
  for (size_t bj = 0; bj < n; bj += 3)
    for (size_t bi = 0; bi < n; bi += 3) {
      double tmp[9]; /* kl_IJ R, row-major */
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          double s = 0.0;
          for (int q = 0; q < 3; ++q)
            s += kl[(bj + (size_t)q) * n + bi + (size_t)r] * rot[q * 3 + c];
          tmp[r * 3 + c] = s;
        }
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          double s = 0.0;
          for (int q = 0; q < 3; ++q)
            s += rot[q * 3 + r] * tmp[q * 3 + c];
          kg[(bj + (size_t)c) * n + bi + (size_t)r] = s;
        }
    }
}

/* int(N_a N_b) dA over the element (nn x nn, symmetric): exact for the
 * linear triangle (A (1 + delta_ab) / 12) and, by 2x2 Gauss points, for
 * the bilinear quadrilateral (integrand of degree 3 in each of xi, eta). */
static void shape_products(const fb_shell_frame *f, double *s)
{
  const size_t nn = f->nn;
  if (nn == 3) {
    for (size_t b = 0; b < 3; ++b)
      for (size_t a = 0; a < 3; ++a)
        s[b * 3 + a] = f->area * (a == b ? 2.0 : 1.0) / 12.0;
    return;
  }
  static const double gauss = 0.57735026918962576451; /* 1 / sqrt(3) */
  memset(s, 0, 16 * sizeof *s);
  for (int gp = 0; gp < 4; ++gp) {
    double nsh[4], dndx[4], dndy[4], detj;
    fb_shell_quad_bilinear(f->x, f->y, fb_shell_quad_xi[gp] * gauss,
                           fb_shell_quad_eta[gp] * gauss, nsh, dndx, dndy, &detj);
    for (size_t b = 0; b < 4; ++b)
      for (size_t a = 0; a < 4; ++a)
        s[b * 4 + a] += nsh[a] * nsh[b] * detj;
  }
}

static void mass_matrix(const fb_shell_frame *f, const fb_shell_props *p, fb_mass_kind kind,
                        double *me)
{
  const size_t nn = f->nn, n = 6 * nn;
  /* A non-structural mass is smeared through the thickness: the plate's
   * density becomes density + nonstructural_mass / t (fem.h). */
  const double t = p->thickness, translational = p->density * t + p->nonstructural_mass;
  const double rotary = p->density * t * t * t / 12.0 + p->nonstructural_mass * t * t / 12.0;
  double s[16];
  memset(me, 0, n * n * sizeof *me);
  if (kind == FB_MASS_LUMPED) {
    for (size_t a = 0; a < nn; ++a)
      for (size_t k = 0; k < 6; ++k)
        me[(6 * a + k) * n + 6 * a + k] =
            (k < 3 ? translational : rotary) * f->area / (double)nn;
    return;
  }
  shape_products(f, s);
  for (size_t b = 0; b < nn; ++b)
    for (size_t a = 0; a < nn; ++a)
      for (size_t k = 0; k < 6; ++k)
        me[(6 * b + k) * n + 6 * a + k] = (k < 3 ? translational : rotary) * s[b * nn + a];
}

int fb_shell_element(fb_elem_type type, const double *xyz, const fb_shell_props *p,
                     fb_mass_kind mass, double *ke, double *me, fb_err *err)
{
  if (type != FB_ELEM_TRI3 && type != FB_ELEM_QUAD4)
    return fb_err_set(err, FB_EINVAL, "unknown shell element type %d", (int)type);
  if (mass != FB_MASS_CONSISTENT && mass != FB_MASS_LUMPED)
    return fb_err_set(err, FB_EINVAL, "unknown mass kind %d", (int)mass);
  if (!xyz)
    return fb_err_set(err, FB_EINVAL, "shell element: NULL coordinates");
  int rc = fb_shell_check_props(p, err);
  if (rc)
    return rc;
  fb_shell_frame f;
  rc = fb_shell_frame_make(type, xyz, &f, err);
  if (rc)
    return rc;
  const size_t n = 6 * f.nn;
  if (ke) {
    double kl[24 * 24];
    local_stiffness(&f, p, kl);
    link_offsets(&f, kl);
    to_global(n, f.rot, kl, ke);
  }
  if (me)
    mass_matrix(&f, p, mass, me);
  return FB_OK;
}
