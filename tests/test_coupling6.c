/* SPDX-License-Identifier: BSD-3-Clause */
/* The six-component distributing coupling of a bushing's hull side
 * (fb_hull_coupling6_build, src/vehicle/coupling.c) on a patch of plate
 * nodes around a point above them:
 *  - a rigid motion of the nodes moves the point by exactly that motion
 *    (the least-squares fit of a motion it can represent is the motion);
 *  - the nodal forces, the rows' transpose times a force and moment at
 *    the point, have that force and moment as their resultant about the
 *    point (equilibrium);
 *  - by hand, four nodes at (+-a, +-b) in the point's plane: a vertical
 *    force F puts F / 4 on each, a moment M_x about x the forces
 *    M_x y_i / sum y_i^2 (the least-squares split of a couple);
 *  - one node, or nodes on a line, are refused.
 * All to 1e-12 of the quantities' scale: a 6x6 solve of a well
 * conditioned G (the patch spans 0.2 m; its entries are 1 and r^2 ~ 0.01
 * to 0.1) loses a few digits at most. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "check.h"

/* A patch of nodes: 3 x 3 on z = 0, one off the plane (a stiffener). */
static fb_mesh *patch(size_t *nodes, size_t *n)
{
  fb_err err;
  fb_mesh *m = NULL;
  CHECK(fb_mesh_new(&m, &err) == FB_OK);
  *n = 0;
  for (int i = 0; m && i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      CHECK(fb_mesh_add_node(m, (long)*n + 1, 0.4 + 0.1 * i, -0.1 + 0.1 * j, 0.0, &nodes[*n],
                             &err) == FB_OK);
      ++*n;
    }
  if (m) {
    CHECK(fb_mesh_add_node(m, 10, 0.5, 0.05, 0.08, &nodes[*n], &err) == FB_OK);
    ++*n;
  }
  return m;
}

/* The point's motion from nodal displacements u (6 per node). */
static void point_motion(const fb_hull_coupling *rows, const double *u, double *q)
{
  for (int k = 0; k < 6; ++k) {
    q[k] = 0.0;
    for (size_t i = 0; i < rows[k].n; ++i)
      q[k] += rows[k].w[i] * u[rows[k].dof[i]];
  }
}

static void test_rigid_and_equilibrium(void)
{
  fb_err err;
  size_t nodes[16], n = 0;
  fb_mesh *m = patch(nodes, &n);
  if (!m)
    return;
  const double x0[3] = {0.52, 0.03, 0.3};
  fb_hull_coupling rows[6];
  CHECK(fb_hull_coupling6_build(m, nodes, n, x0, "test", rows, &err) == FB_OK);
  /* A rigid motion q0 about the point: u_i = u + theta x r_i. */
  const double q0[6] = {1e-3, -2e-3, 3e-3, 4e-3, -5e-3, 6e-3};
  double *u = calloc(6 * n, sizeof *u), q[6];
  for (size_t i = 0; u && i < n; ++i) {
    const double *p = fb_mesh_node_xyz(m, nodes[i]);
    const double r[3] = {p[0] - x0[0], p[1] - x0[1], p[2] - x0[2]};
    double *ui = u + 6 * nodes[i];
    ui[0] = q0[0] + q0[4] * r[2] - q0[5] * r[1];
    ui[1] = q0[1] + q0[5] * r[0] - q0[3] * r[2];
    ui[2] = q0[2] + q0[3] * r[1] - q0[4] * r[0];
    ui[3] = q0[3]; /* the nodes' rotations take no share */
    ui[4] = -q0[4];
    ui[5] = 7.0;
  }
  if (u) {
    point_motion(rows, u, q);
    for (int k = 0; k < 6; ++k)
      CHECK(fabs(q[k] - q0[k]) <= 1e-12 * 6e-3);
  }
  /* A force and moment at the point, as nodal forces f = R' F: their
   * resultant about the point is F again. */
  const double F[6] = {100, -200, 3000, 40, -50, 60};
  double *f = calloc(6 * n, sizeof *f);
  for (int k = 0; f && k < 6; ++k)
    for (size_t i = 0; i < rows[k].n; ++i)
      f[rows[k].dof[i]] += rows[k].w[i] * F[k];
  double res[6] = {0};
  for (size_t i = 0; f && i < n; ++i) {
    const double *p = fb_mesh_node_xyz(m, nodes[i]);
    const double r[3] = {p[0] - x0[0], p[1] - x0[1], p[2] - x0[2]};
    const double *fi = f + 6 * nodes[i];
    CHECK(fi[3] == 0 && fi[4] == 0 && fi[5] == 0);
    for (int c = 0; c < 3; ++c)
      res[c] += fi[c];
    res[3] += r[1] * fi[2] - r[2] * fi[1];
    res[4] += r[2] * fi[0] - r[0] * fi[2];
    res[5] += r[0] * fi[1] - r[1] * fi[0];
  }
  for (int k = 0; f && k < 6; ++k)
    CHECK(fabs(res[k] - F[k]) <= 1e-12 * 3000);
  free(u);
  free(f);
  for (int k = 0; k < 6; ++k)
    fb_hull_coupling_free(&rows[k]);
  fb_mesh_free(&m);
}

static void test_by_hand(void)
{
  fb_err err;
  fb_mesh *m = NULL;
  size_t nodes[4];
  const double a = 0.2, b = 0.1;
  CHECK(fb_mesh_new(&m, &err) == FB_OK);
  for (int i = 0; m && i < 4; ++i)
    CHECK(fb_mesh_add_node(m, i + 1, (i & 1) ? a : -a, (i & 2) ? b : -b, 0.0, &nodes[i],
                           &err) == FB_OK);
  const double x0[3] = {0, 0, 0};
  fb_hull_coupling rows[6];
  CHECK(m && fb_hull_coupling6_build(m, nodes, 4, x0, "test", rows, &err) == FB_OK);
  /* Row 2 (u_z) and row 3 (theta_x) over each node's u_z. */
  for (size_t i = 0; m && i < 4; ++i) {
    const double y = fb_mesh_node_xyz(m, nodes[i])[1];
    CHECK(fabs(rows[2].w[3 * i + 2] - 0.25) < 1e-12);
    CHECK(fabs(rows[3].w[3 * i + 2] - y / (4 * b * b)) < 1e-12 / b);
  }
  for (int k = 0; m && k < 6; ++k)
    fb_hull_coupling_free(&rows[k]);
  /* One node; three on a line. */
  CHECK(m && fb_hull_coupling6_build(m, nodes, 1, x0, "one", rows, &err) == FB_EMODEL &&
        strstr(err.msg, "one:") == err.msg);
  size_t line[3];
  fb_mesh *l = NULL;
  CHECK(fb_mesh_new(&l, &err) == FB_OK);
  for (int i = 0; l && i < 3; ++i)
    CHECK(fb_mesh_add_node(l, i + 1, 0.1 * i, 0.0, 0.0, &line[i], &err) == FB_OK);
  CHECK(l && fb_hull_coupling6_build(l, line, 3, x0, "line", rows, &err) == FB_EMODEL);
  fb_mesh_free(&l);
  fb_mesh_free(&m);
}

int main(void)
{
  test_rigid_and_equilibrium();
  test_by_hand();
  return check_report(__FILE__);
}
