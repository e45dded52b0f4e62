/* SPDX-License-Identifier: BSD-3-Clause */
/* Couplings of attachment points to the finite-element hull (fb_hull_coupling,
 * flexbond/vehicle.h; docs/hull-mesh.md, "Couplings").
 *
 * A point at (x0, y0) in plan that carries a vertical force F meets the
 * hull through a row w over its nodal DOFs: the point's velocity is
 * w . v and the nodes take the forces w F. The row is power-conserving
 * (a transformer in the bond graph), so the coupling adds no stiffness.
 *
 * Distributing: vertical nodal forces f_i = w_i F on the candidate nodes,
 * in equilibrium with F at the point (sum w_i = 1, sum w_i x_i = x0,
 * sum w_i y_i = y0) and otherwise as even as possible (least sum of
 * w_i^2): w_i = 1/n + lambda . (p_i - p_mean), with the 2 x 2 system
 * S lambda = p0 - p_mean, S = sum (p_i - p_mean)(p_i - p_mean)'. This is
 * the distributing coupling of the Abaqus Analysis User's Guide (section
 * 35.3.2, "Distributing coupling") with uniform weights, for a force
 * normal to the plan. Nodes on one line cannot carry a moment about it: the
 * point must then lie on the line (within 1 mm), and the system is solved
 * on its span alone.
 *
 * Kinematic: a rigid lever from the nearest node n to the point, its
 * vertical velocity v_z + (y0 - y_n) omega_x - (x0 - x_n) omega_y (the
 * node's rotations; u = theta x r). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "vehicle/vehicle_internal.h"

/* Lever and line tolerance: the mesh check's 1 mm for points on nodes. */
#define COUPLING_TOL 1e-3

void fb_hull_coupling_free(fb_hull_coupling *c)
{
  free(c->dof);
  free(c->w);
  c->dof = NULL;
  c->w = NULL;
  c->n = 0;
}

static int coupling_alloc(fb_hull_coupling *c, size_t n, fb_err *err)
{
  c->dof = malloc(n * sizeof *c->dof);
  c->w = malloc(n * sizeof *c->w);
  c->n = n;
  if (c->dof && c->w)
    return FB_OK;
  fb_hull_coupling_free(c);
  return fb_err_set(err, FB_ENOMEM, "out of memory for a coupling");
}

int fb_hull_coupling_node(size_t node, fb_hull_coupling *c, fb_err *err)
{
  const int rc = coupling_alloc(c, 1, err);
  if (!rc) {
    c->dof[0] = 6 * node + 2;
    c->w[0] = 1.0;
  }
  return rc;
}

/* The candidate nearest (x0, y0) in plan (lowest index on a tie). */
static size_t nearest(const fb_mesh *m, const size_t *nodes, size_t n, double x0, double y0)
{
  size_t best = 0;
  double best_d2 = INFINITY;
  for (size_t i = 0; i < n; ++i) {
    const double *p = fb_mesh_node_xyz(m, nodes[i]);
    const double d2 = (p[0] - x0) * (p[0] - x0) + (p[1] - y0) * (p[1] - y0);
    if (d2 < best_d2) {
      best = i;
      best_d2 = d2;
    }
  }
  return best;
}

static int kinematic(const fb_mesh *m, size_t node, double x0, double y0, fb_hull_coupling *c,
                     fb_err *err)
{
  const double *p = fb_mesh_node_xyz(m, node);
  const int rc = coupling_alloc(c, 3, err);
  if (rc)
    return rc;
  c->dof[0] = 6 * node + 2;
  c->dof[1] = 6 * node + 3;
  c->dof[2] = 6 * node + 4;
  c->w[0] = 1.0;
  c->w[1] = y0 - p[1];
  c->w[2] = -(x0 - p[0]);
  return FB_OK;
}

/* lambda = S^+ r for the symmetric 2 x 2 S (pseudo-inverse on the
 * eigenvalues above 1e-12 of the largest). */
static void solve_sym2(const double *S, const double *r, double *lambda)
{
  const double a = S[0], b = S[1], d = S[3];
  const double mean = 0.5 * (a + d), diff = 0.5 * (a - d), rad = hypot(diff, b);
  const double ev[2] = {mean + rad, mean - rad};
  /* Unit eigenvector of ev[0]; the other is its perpendicular. */
  const double theta = 0.5 * atan2(2.0 * b, a - d);
  const double u[2][2] = {{cos(theta), sin(theta)}, {-sin(theta), cos(theta)}};
  lambda[0] = lambda[1] = 0.0;
  for (int k = 0; k < 2; ++k) {
    if (!(ev[k] > 1e-12 * ev[0]))
      continue;
    const double proj = (u[k][0] * r[0] + u[k][1] * r[1]) / ev[k];
    lambda[0] += proj * u[k][0];
    lambda[1] += proj * u[k][1];
  }
}

static int distributing(const fb_mesh *m, const size_t *nodes, size_t n, double x0, double y0,
                        const char *what, fb_hull_coupling *c, fb_err *err)
{
  double mean[2] = {0.0, 0.0}, S[4] = {0.0, 0.0, 0.0, 0.0};
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 2; ++k)
      mean[k] += fb_mesh_node_xyz(m, nodes[i])[k] / (double)n;
  for (size_t i = 0; i < n; ++i) {
    const double *p = fb_mesh_node_xyz(m, nodes[i]);
    const double d[2] = {p[0] - mean[0], p[1] - mean[1]};
    S[0] += d[0] * d[0];
    S[1] += d[0] * d[1];
    S[3] += d[1] * d[1];
  }
  S[2] = S[1];
  const double r[2] = {x0 - mean[0], y0 - mean[1]};
  double lambda[2];
  solve_sym2(S, r, lambda);
  /* The offset the weights cannot reach: r - S lambda. */
  const double miss[2] = {r[0] - (S[0] * lambda[0] + S[1] * lambda[1]),
                          r[1] - (S[2] * lambda[0] + S[3] * lambda[1])};
  if (hypot(miss[0], miss[1]) > COUPLING_TOL)
    return fb_err_set(err, FB_EMODEL,
                      "%s: %s %.3g m from it, which cannot carry the moment of its force (a "
                      "distributing coupling needs nodes around it, or use kind: kinematic)",
                      what,
                      n == 1 ? "its one coupling node is" : "its coupling nodes lie on a line",
                      hypot(miss[0], miss[1]));
  const int rc = coupling_alloc(c, n, err);
  for (size_t i = 0; !rc && i < n; ++i) {
    const double *p = fb_mesh_node_xyz(m, nodes[i]);
    c->dof[i] = 6 * nodes[i] + 2;
    c->w[i] = 1.0 / (double)n + lambda[0] * (p[0] - mean[0]) + lambda[1] * (p[1] - mean[1]);
  }
  return rc;
}

/* The nodes of the element set surface within radius of (x0, y0) in plan,
 * each once, in index order; *out is new. */
static int nodes_within(const fb_mesh *m, const char *surface, double radius, double x0,
                        double y0, size_t **out, size_t *n, fb_err *err)
{
  const size_t *elems = NULL;
  size_t ne = 0, nn = fb_mesh_nnodes(m);
  *out = NULL;
  *n = 0;
  if (!fb_mesh_elset(m, surface, &elems, &ne))
    return fb_err_set(err, FB_EMODEL, "the hull mesh has no element set '%s'", surface);
  unsigned char *in = calloc(nn ? nn : 1, 1);
  size_t *list = malloc((nn ? nn : 1) * sizeof *list);
  if (!in || !list) {
    free(in);
    free(list);
    return fb_err_set(err, FB_ENOMEM, "out of memory for a coupling");
  }
  for (size_t k = 0; k < ne; ++k) {
    const size_t *nd = fb_mesh_element_nodes(m, elems[k]);
    const size_t count = fb_mesh_element_type(m, elems[k]) == FB_ELEM_QUAD4 ? 4 : 3;
    for (size_t j = 0; j < count; ++j) {
      const double *p = fb_mesh_node_xyz(m, nd[j]);
      if (hypot(p[0] - x0, p[1] - y0) <= radius)
        in[nd[j]] = 1;
    }
  }
  for (size_t i = 0; i < nn; ++i)
    if (in[i])
      list[(*n)++] = i;
  free(in);
  *out = list;
  return FB_OK;
}

int vehicle_bushing_nodes(const fb_scenario *s, const fb_mesh *m, const fb_bushing *u,
                          size_t **nodes, size_t *n, fb_err *err)
{
  *nodes = NULL;
  *n = 0;
  if (u->node_set) {
    const size_t *own = NULL;
    if (!fb_mesh_nset(m, u->node_set, &own, n))
      return fb_err_set(err, FB_EMODEL, "the hull mesh has no node set '%s'", u->node_set);
    *nodes = malloc((*n ? *n : 1) * sizeof **nodes);
    if (!*nodes)
      return fb_err_set(err, FB_ENOMEM, "out of memory for a coupling");
    memcpy(*nodes, own, *n * sizeof **nodes);
    return FB_OK;
  }
  const double radius = u->radius > 0 ? u->radius : s->coupling_radius;
  const char *surface = u->surface ? u->surface : s->coupling_surface;
  if (!surface || !(radius > 0))
    return fb_err_set(err, FB_EMODEL,
                      "a bushing on System 2's hull needs its node set, or a radius and a "
                      "surface (its own or the scenario's coupling surface)");
  const int rc = nodes_within(m, surface, radius, u->x, u->y, nodes, n, err);
  if (!rc && *n == 0)
    return fb_err_set(err, FB_EMODEL,
                      "no node of the element set '%s' lies within %g m of (%.6g, %.6g) m in "
                      "plan",
                      surface, radius, u->x, u->y);
  return rc;
}

int fb_hull_coupling_build(const fb_scenario *s, const fb_mesh *m, const char *set, double x0,
                           double y0, fb_hull_coupling *c, size_t *node, fb_err *err)
{
  const size_t *own = NULL;
  size_t n = 0, *found = NULL;
  int rc = FB_OK;
  if (!fb_mesh_nset(m, set, &own, &n)) {
    rc = nodes_within(m, s->coupling_surface, s->coupling_radius, x0, y0, &found, &n, err);
    own = found;
    if (!rc && n == 0)
      rc = fb_err_set(err, FB_EMODEL,
                      "%s: no node of the element set '%s' lies within %g m of (%.6g, %.6g) m "
                      "in plan, and the mesh has no node set %s",
                      set, s->coupling_surface, s->coupling_radius, x0, y0, set);
  } else if (n == 0) {
    rc = fb_err_set(err, FB_EMODEL, "the mesh's node set %s is empty", set);
  }
  if (!rc) {
    const size_t k = nearest(m, own, n, x0, y0);
    *node = own[k];
    rc = s->coupling == FB_COUPLING_KINEMATIC ? kinematic(m, own[k], x0, y0, c, err)
                                              : distributing(m, own, n, x0, y0, set, c, err);
  }
  free(found);
  return rc;
}

/* ---- A six-component distributing coupling (a bushing's hull side).
 *
 * The reference point x0 moves as the rigid motion q = (u, theta) that
 * fits the candidate nodes' translations u_i best in the least-squares
 * sense, u_i ~ A_i q with A_i = [I, -[r_i]x], r_i = x_i - x0 (small
 * rotations): q = G^-1 sum A_i' u_i, G = sum A_i' A_i (uniform weights).
 * Its force and moment F go to the nodes by the transpose, f_i = A_i
 * G^-1 F, so the coupling is power-conserving, its nodal forces are in
 * equilibrium with F (sum A_i' f_i = F), and a rigid motion of the nodes
 * moves the point by exactly that motion (R A q = q). This is MSC
 * Nastran's RBE3 element (its reference point's motion the weighted
 * least-squares average of the nodes'; MSC Nastran Quick Reference
 * Guide, bulk data entry RBE3) and the distributing coupling of the
 * Abaqus Analysis User's Guide (section 35.3.2, as above) for a point
 * with rotational degrees of freedom, with uniform weights. The nodes'
 * rotational DOFs take no share (as RBE3's usual components 123): a
 * shell's drilling rotation has no stiffness of its own. */

/* G's inverse (6x6, row major, symmetric positive definite) by Gauss-
 * Jordan elimination with partial pivoting; 0 when a pivot falls below
 * 1e-12 of G's largest entry (G singular: nodes on one line). */
static int invert6(const double *g, double *inv)
{
  double a[6][12];
  double scale = 0.0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 12; ++j) {
      a[i][j] = j < 6 ? g[6 * i + j] : (j - 6 == i);
      if (j < 6)
        scale = fmax(scale, fabs(g[6 * i + j]));
    }
  for (int c = 0; c < 6; ++c) {
    int p = c;
    for (int r = c + 1; r < 6; ++r)
      if (fabs(a[r][c]) > fabs(a[p][c]))
        p = r;
    if (!(fabs(a[p][c]) > 1e-12 * scale))
      return 0;
    for (int j = 0; j < 12; ++j) {
      const double t = a[c][j];
      a[c][j] = a[p][j];
      a[p][j] = t;
    }
    const double d = a[c][c];
    for (int j = 0; j < 12; ++j)
      a[c][j] /= d;
    for (int r = 0; r < 6; ++r) {
      const double f = a[r][c];
      for (int j = 0; r != c && j < 12; ++j)
        a[r][j] -= f * a[c][j];
    }
  }
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      inv[6 * i + j] = a[i][6 + j];
  return 1;
}

/* A_i (3x6, row major) of the node at r from the reference point: the
 * translations' rows of the rigid transport. */
static void rigid_rows(const double *r, double *a)
{
  double t[36];
  vehicle_rigid_transport(r, t);
  memcpy(a, t, 18 * sizeof *a);
}

int fb_hull_coupling6_build(const fb_mesh *m, const size_t *nodes, size_t n, const double *x0,
                            const char *what, fb_hull_coupling *rows, fb_err *err)
{
  double g[36] = {0}, ginv[36], a[18];
  memset(rows, 0, 6 * sizeof *rows);
  for (size_t i = 0; i < n; ++i) {
    const double *p = fb_mesh_node_xyz(m, nodes[i]);
    const double r[3] = {p[0] - x0[0], p[1] - x0[1], p[2] - x0[2]};
    rigid_rows(r, a);
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k)
        for (int l = 0; l < 3; ++l)
          g[6 * j + k] += a[6 * l + j] * a[6 * l + k];
  }
  if (n == 0 || !invert6(g, ginv))
    return fb_err_set(err, FB_EMODEL,
                      "%s: %s cannot carry a force and a moment in every direction (a "
                      "six-component distributing coupling needs nodes not on one line)",
                      what, n == 1 ? "its one coupling node" : "its coupling nodes");
  int rc = FB_OK;
  for (int k = 0; !rc && k < 6; ++k)
    rc = coupling_alloc(&rows[k], 3 * n, err);
  for (int k = 0; rc && k < 6; ++k)
    fb_hull_coupling_free(&rows[k]);
  for (size_t i = 0; !rc && i < n; ++i) {
    const double *p = fb_mesh_node_xyz(m, nodes[i]);
    const double r[3] = {p[0] - x0[0], p[1] - x0[1], p[2] - x0[2]};
    rigid_rows(r, a);
    for (int k = 0; k < 6; ++k) /* row k of G^-1 A_i' */
      for (int l = 0; l < 3; ++l) {
        double v = 0.0;
        for (int j = 0; j < 6; ++j)
          v += ginv[6 * k + j] * a[6 * l + j];
        rows[k].dof[3 * i + (size_t)l] = 6 * nodes[i] + (size_t)l;
        rows[k].w[3 * i + (size_t)l] = v;
      }
  }
  return rc;
}
