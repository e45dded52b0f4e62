/* SPDX-License-Identifier: BSD-3-Clause */
/* A point of System 2's shell hull as an output reads it
 * (vehicle_internal.h): the element whose surface is nearest the point,
 * the element's shape functions at the point's foot on it, and the
 * weights over the nodal DOFs of the point's translation along an axis;
 * and the hull's rigid-body motion as the mass-weighted least-squares fit
 * of its nodal displacements (docs/vehicle-outputs.md). */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "vehicle/vehicle_internal.h"

/* Gauss-Newton steps of the quadrilateral's inverse map: each step's
 * size falls quadratically on a flat element (where the map is affine
 * along the steps it takes), so 50 leave room for a warped one. */
#define QUAD_ITERATIONS 50

static double dot3(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The point of triangle (a, b, c) nearest p, as barycentric weights n of
 * the three corners: Ericson, "Real-Time Collision Detection" (2005), sec.
 * 5.1.5, by the Voronoi region of p. */
static void triangle_nearest(const double *a, const double *b, const double *c, const double *p,
                             double *n)
{
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int i = 0; i < 3; ++i) {
    ab[i] = b[i] - a[i];
    ac[i] = c[i] - a[i];
    ap[i] = p[i] - a[i];
    bp[i] = p[i] - b[i];
    cp[i] = p[i] - c[i];
  }
  const double d1 = dot3(ab, ap), d2 = dot3(ac, ap), d3 = dot3(ab, bp), d4 = dot3(ac, bp);
  const double d5 = dot3(ab, cp), d6 = dot3(ac, cp);
  const double va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
  double v = 0.0, w = 0.0; /* the weights of b and c */
  if (d1 <= 0.0 && d2 <= 0.0) {
    /* corner a */
  } else if (d3 >= 0.0 && d4 <= d3) {
    v = 1.0;
  } else if (d6 >= 0.0 && d5 <= d6) {
    w = 1.0;
  } else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    v = d1 / (d1 - d3);
  } else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    w = d2 / (d2 - d6);
  } else if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    v = 1.0 - w;
  } else {
    const double den = 1.0 / (va + vb + vc);
    v = vb * den;
    w = vc * den;
  }
  n[0] = 1.0 - v - w;
  n[1] = v;
  n[2] = w;
}

/* The bilinear quadrilateral's shape functions at (xi, eta), corners
 * counter-clockwise from (-1, -1) (Zienkiewicz & Taylor, "The Finite
 * Element Method", vol. 1, 6th ed., sec. 8.5), and their derivatives. */
static void quad_shape(double xi, double eta, double *n, double *dxi, double *deta)
{
  static const double cx[4] = {-1, 1, 1, -1}, cy[4] = {-1, -1, 1, 1};
  for (int i = 0; i < 4; ++i) {
    n[i] = 0.25 * (1 + cx[i] * xi) * (1 + cy[i] * eta);
    dxi[i] = 0.25 * cx[i] * (1 + cy[i] * eta);
    deta[i] = 0.25 * cy[i] * (1 + cx[i] * xi);
  }
}

static double clamp1(double v)
{
  return v < -1.0 ? -1.0 : v > 1.0 ? 1.0 : v;
}

/* The point of the quadrilateral x[4] nearest p, as its shape functions
 * there: Gauss-Newton on |x(xi, eta) - p|^2 over the reference square,
 * each step kept in it (the isoparametric inverse map, projected). */
static void quad_nearest(const double *const *x, const double *p, double *n)
{
  double xi = 0.0, eta = 0.0, dxi[4], deta[4];
  for (int it = 0; it < QUAD_ITERATIONS; ++it) {
    quad_shape(xi, eta, n, dxi, deta);
    double r[3] = {0, 0, 0}, ja[3] = {0, 0, 0}, jb[3] = {0, 0, 0};
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        r[k] += n[i] * x[i][k];
        ja[k] += dxi[i] * x[i][k];
        jb[k] += deta[i] * x[i][k];
      }
    for (int k = 0; k < 3; ++k)
      r[k] = p[k] - r[k];
    const double aa = dot3(ja, ja), ab = dot3(ja, jb), bb = dot3(jb, jb);
    const double ra = dot3(ja, r), rb = dot3(jb, r), det = aa * bb - ab * ab;
    if (!(det > 0.0))
      break;
    const double sa = (bb * ra - ab * rb) / det, sb = (aa * rb - ab * ra) / det;
    const double nxi = clamp1(xi + sa), neta = clamp1(eta + sb);
    const double moved = fabs(nxi - xi) + fabs(neta - eta);
    xi = nxi;
    eta = neta;
    if (moved < 1e-14)
      break;
  }
  quad_shape(xi, eta, n, dxi, deta);
}

double vehicle_hull_point_nearest(const fb_mesh *m, const double *p, size_t *elem, double *n,
                                  double *foot)
{
  /* No element: infinitely far, the foot the point itself. */
  double best = INFINITY;
  *elem = 0;
  memset(n, 0, 4 * sizeof *n);
  memcpy(foot, p, 3 * sizeof *foot);
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    const size_t *nodes = fb_mesh_element_nodes(m, e);
    const int nn = fb_mesh_element_type(m, e) == FB_ELEM_QUAD4 ? 4 : 3;
    const double *x[4];
    for (int i = 0; i < nn; ++i)
      x[i] = fb_mesh_node_xyz(m, nodes[i]);
    double w[4] = {0, 0, 0, 0}, f[3] = {0, 0, 0};
    if (nn == 4)
      quad_nearest(x, p, w);
    else
      triangle_nearest(x[0], x[1], x[2], p, w);
    for (int i = 0; i < nn; ++i)
      for (int k = 0; k < 3; ++k)
        f[k] += w[i] * x[i][k];
    const double d = sqrt((p[0] - f[0]) * (p[0] - f[0]) + (p[1] - f[1]) * (p[1] - f[1]) +
                          (p[2] - f[2]) * (p[2] - f[2]));
    if (d < best) {
      best = d;
      *elem = e;
      memcpy(n, w, sizeof w);
      memcpy(foot, f, sizeof f);
    }
  }
  return best;
}

/* A superelement's point (a mesh of interface nodes, no elements): an
 * interface node within the tolerance, its motion the node's own
 * transported by the rigid lever to the point; anywhere else the
 * superelement does not know the structure's motion. */
static int superelement_point_weights(const fb_mesh *m, const fb_output_spec *o, size_t index,
                                      double *w, fb_err *err)
{
  size_t best = 0;
  double d = INFINITY;
  for (size_t i = 0; i < fb_mesh_nnodes(m); ++i) {
    const double *x = fb_mesh_node_xyz(m, i);
    const double di = hypot(hypot(x[0] - o->at[0], x[1] - o->at[1]), x[2] - o->at[2]);
    if (di < d) {
      d = di;
      best = i;
    }
  }
  if (!(d <= VEHICLE_HULL_POINT_TOL))
    return fb_err_set(err, FB_EINVAL,
                      "the hull is a superelement, whose motion is known at its interface "
                      "nodes only: the nearest, node %ld, is %.3g m from the point (at most "
                      "%g m)",
                      fb_mesh_node_id(m, best), d, VEHICLE_HULL_POINT_TOL),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, at)), FB_EINVAL;
  const double *x = fb_mesh_node_xyz(m, best);
  const double lever[3] = {o->at[0] - x[0], o->at[1] - x[1], o->at[2] - x[2]};
  double rows[18];
  vehicle_rigid_rows(lever, rows);
  memset(w, 0, 6 * fb_mesh_nnodes(m) * sizeof *w);
  for (int j = 0; j < 6; ++j)
    w[6 * best + j] = rows[6 * o->direction + j];
  return FB_OK;
}

int vehicle_hull_point_on(const fb_mesh *m, const fb_output_spec *o, size_t index, size_t *e,
                          double *n, double *foot, fb_err *err)
{
  if (fb_mesh_nelements(m) == 0)
    return fb_err_set(err, FB_EINVAL,
                      "the hull is a superelement: it has no elements for the point to lie on"),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, at)), FB_EINVAL;
  const double d = vehicle_hull_point_nearest(m, o->at, e, n, foot);
  if (!(d <= VEHICLE_HULL_POINT_TOL))
    return fb_err_set(err, FB_EINVAL,
                      "the point is %.3g m from the hull's nearest element (at most %g m: a "
                      "point of the hull's plates)",
                      d, VEHICLE_HULL_POINT_TOL),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, at)), FB_EINVAL;
  return FB_OK;
}

int vehicle_hull_point_weights(const fb_mesh *m, const fb_output_spec *o, size_t index,
                               double *w, fb_err *err)
{
  if (fb_mesh_nelements(m) == 0)
    return superelement_point_weights(m, o, index, w, err);
  size_t e = 0;
  double n[4], foot[3];
  const int rc = vehicle_hull_point_on(m, o, index, &e, n, foot, err);
  if (rc)
    return rc;
  /* The foot's motion u_f = sum N_i u_i, and the point's its rigid lever
   * from the foot through the nodes' rotations: sum N_i (u_i + theta_i x
   * (p - foot)), exact for a rigid motion wherever the point is. */
  const double lever[3] = {o->at[0] - foot[0], o->at[1] - foot[1], o->at[2] - foot[2]};
  double rows[18];
  vehicle_rigid_rows(lever, rows);
  memset(w, 0, 6 * fb_mesh_nnodes(m) * sizeof *w);
  const size_t *nodes = fb_mesh_element_nodes(m, e);
  const int nn = fb_mesh_element_type(m, e) == FB_ELEM_QUAD4 ? 4 : 3;
  for (int i = 0; i < nn; ++i)
    for (int j = 0; j < 6; ++j)
      w[6 * nodes[i] + j] += n[i] * rows[6 * o->direction + j];
  return FB_OK;
}

int vehicle_hull_rigid_fit(const fb_mesh *m, const fb_mat *M, int coordinate, double *w,
                           fb_err *err)
{
  const size_t ndof = 6 * fb_mesh_nnodes(m);
  const double origin[3] = {0, 0, 0};
  double *r = malloc(6 * ndof * sizeof *r), *mr = malloc(6 * ndof * sizeof *mr);
  if (!r || !mr) {
    free(r);
    free(mr);
    return fb_err_set(err, FB_ENOMEM, "out of memory for the hull's rigid-body motions");
  }
  /* The rigid motion a (6) nearest u in the norm of M: R' M R a = R' M u,
   * so a_k = w' u with w = M R (R' M R)^-1 e_k (G = R' M R is symmetric). */
  fb_mesh_rigid_modes(m, origin, r);
  for (int j = 0; j < 6; ++j)
    fb_mat_gemv(M, 1.0, r + (size_t)j * ndof, 0.0, mr + (size_t)j * ndof);
  double g[36], e[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      double sum = 0.0;
      for (size_t k = 0; k < ndof; ++k)
        sum += r[(size_t)i * ndof + k] * mr[(size_t)j * ndof + k];
      g[j * 6 + i] = sum;
    }
  e[coordinate] = 1.0;
  const lapack_int info = LAPACKE_dposv(LAPACK_COL_MAJOR, 'L', 6, 1, g, 6, e, 6);
  int rc = info ? fb_err_set(err, FB_EMODEL,
                             "the hull's mass matrix does not resolve its rigid-body motions "
                             "(LAPACK dposv info %d)",
                             (int)info)
                : FB_OK;
  for (size_t k = 0; !rc && k < ndof; ++k) {
    double sum = 0.0;
    for (int j = 0; j < 6; ++j)
      sum += mr[(size_t)j * ndof + k] * e[j];
    w[k] = sum;
  }
  free(r);
  free(mr);
  return rc;
}

/* Each hull stress output of s names an element of its finite-element
 * hull's mesh m (NULL: not read yet), or is refused without such a hull. */
static int hull_stresses_check(const fb_scenario *s, const fb_mesh *m, fb_err *err)
{
  for (size_t o = 0; o < s->noutputs; ++o) {
    if (!vehicle_output_hull_stress(&s->output[o]))
      continue;
    if (!s->has_fe_hull)
      return fb_err_set(err, FB_EINVAL,
                        "a %s signal reads a shell element of System 2's finite-element hull, "
                        "and this vehicle's hull has no mesh",
                        s->output[o].signal),
             fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, o, signal)), FB_EINVAL;
    size_t e = 0;
    const int rc = m ? vehicle_hull_stress_element(m, &s->output[o], o, &e, err) : FB_OK;
    if (rc)
      return rc;
  }
  return FB_OK;
}

int vehicle_hull_points_check(const fb_scenario *s, fb_err *err)
{
  const fb_mesh *m = s->hull_source_mesh;
  int rc = hull_stresses_check(s, s->has_fe_hull ? m : NULL, err);
  if (rc || !s->has_fe_hull || !m)
    return rc;
  double *w = malloc((6 * fb_mesh_nnodes(m) + 1) * sizeof *w);
  if (!w)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  vehicle_hull_motion how;
  for (size_t o = 0; !rc && o < s->noutputs; ++o)
    if (vehicle_output_hull_motion(&s->output[o], &how) && how.coordinate < 0)
      rc = vehicle_hull_point_weights(m, &s->output[o], o, w, err);
  free(w);
  return rc;
}
