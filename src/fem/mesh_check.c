/* SPDX-License-Identifier: BSD-3-Clause */
/* Mesh validation (fb_mesh_check, see flexbond/fem.h).
 *
 * Checks, in this order, reporting the first failure (FB_EMODEL, by user
 * id): the mesh has elements; each element in turn is not degenerate (a
 * repeated node; nodes that all coincide; an area below 1e-12 of the
 * squared bounding-box diagonal, and never below the smallest normal
 * double; for a quadrilateral, a corner that is not strictly convex) and,
 * for a quadrilateral, not warped (node 4 farther from the plane of nodes
 * 1-3 than WARP_MAX of the longer diagonal); every node is used by an element;
 * no node set is empty. An element whose area or warp a double cannot hold
 * (coordinates beyond about 1e154 m) is "too large", rather than given an
 * area or a warp of inf or NaN.
 *
 * The convexity test goes beyond the header's list because a reentrant or
 * flat corner gives a bilinear quadrilateral a Jacobian that vanishes or
 * changes sign inside the element (Zienkiewicz, Taylor & Zhu, "The Finite
 * Element Method: Its Basis and Fundamentals", 7th ed., section 6.5), which
 * the shell element cannot integrate; it also guarantees that nodes 1-3 of
 * a quadrilateral span a plane for the warp test. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* The warp a quadrilateral may have, relative to its longer diagonal. The
 * shell element ties a warped quadrilateral's nodes to their projections
 * on its mean plane by rigid links (src/fem/shell.c), so its rigid-body
 * motions stay exact at any warp; what the limit bounds is the error of
 * treating the element as flat. Measured on the reference hull's exported
 * deck with its nodes moved at random in each coordinate: by up to 0.1 mm,
 * its first ten elastic free-free frequencies move by at most 0.01 %; by up
 * to 1 mm (warps up to 2e-3 of a diagonal), by at most 0.4 %. That shift is
 * the perturbed geometry's: the same deck with each quadrilateral split
 * into two triangles, flat by construction, stiffens by 0.7 % to 1.7 %
 * under the same perturbation (tests/test_system2_modes.c measures the
 * quadrilaterals). 1 % is the warping factor common pre-processors warn
 * at. */
#define WARP_MAX 1e-2

#include "fem/mesh_internal.h"
#include "fem/vec3.h"

/* Squared diagonal of the bounding box of all nodes. */
static double bbox_diag2(const fb_mesh *m)
{
  double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {0.0, 0.0, 0.0};
  for (size_t i = 0; i < fb_mesh_nnodes(m); ++i) {
    const double *p = fb_mesh_node_xyz(m, i);
    for (int k = 0; k < 3; ++k) {
      lo[k] = i == 0 || p[k] < lo[k] ? p[k] : lo[k];
      hi[k] = i == 0 || p[k] > hi[k] ? p[k] : hi[k];
    }
  }
  double d[3];
  fb_sub3(hi, lo, d);
  return fb_dot3(d, d);
}

static int element_error(const fb_mesh *m, size_t e, fb_err *err, const char *what)
{
  return fb_err_set(err, FB_EMODEL, "element %ld (%s) is %s", fb_mesh_element_id(m, e),
                    fb_mesh_type_name(fb_mesh_element_type(m, e)), what);
}

static int check_repeated(const fb_mesh *m, size_t e, fb_err *err)
{
  const size_t *nd = fb_mesh_element_nodes(m, e);
  const size_t nn = fb_mesh_type_nodes(fb_mesh_element_type(m, e));
  for (size_t i = 0; i < nn; ++i) {
    for (size_t j = i + 1; j < nn; ++j) {
      if (nd[i] != nd[j])
        continue;
      char what[96];
      snprintf(what, sizeof what, "degenerate: node %ld is repeated",
               fb_mesh_node_id(m, nd[i]));
      return element_error(m, e, err, what);
    }
  }
  return FB_OK;
}

/* An element too large for its area or warp to be computed in doubles
 * (coordinates beyond about 1e154 m): they would be inf or NaN. */
static int too_large(const fb_mesh *m, size_t e, fb_err *err)
{
  return element_error(m, e, err, "too large: its area overflows a double");
}

/* 1 if the nodes of element e are all at one point. */
static int nodes_coincide(const fb_mesh *m, size_t e)
{
  const size_t *nd = fb_mesh_element_nodes(m, e);
  const double *p = fb_mesh_node_xyz(m, nd[0]);
  for (size_t k = 1; k < fb_mesh_type_nodes(fb_mesh_element_type(m, e)); ++k) {
    const double *q = fb_mesh_node_xyz(m, nd[k]);
    if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2])
      return 0;
  }
  return 1;
}

/* A quadrilateral's corners must each span a triangle of at least
 * min_area on the positive side of its normal (unit). */
static int check_corners(const fb_mesh *m, size_t e, const double *unit, double min_area,
                         fb_err *err)
{
  const size_t *nd = fb_mesh_element_nodes(m, e);
  for (size_t k = 0; k < 4; ++k) {
    double in[3], out[3], c[3];
    fb_sub3(fb_mesh_node_xyz(m, nd[k]), fb_mesh_node_xyz(m, nd[(k + 3) % 4]), in);
    fb_sub3(fb_mesh_node_xyz(m, nd[(k + 1) % 4]), fb_mesh_node_xyz(m, nd[k]), out);
    fb_cross3(in, out, c);
    const double corner = 0.5 * fb_dot3(c, unit);
    if (!isfinite(corner))
      return too_large(m, e, err);
    if (corner < min_area) {
      char what[96];
      snprintf(what, sizeof what, "degenerate: not convex at node %ld",
               fb_mesh_node_id(m, nd[k]));
      return element_error(m, e, err, what);
    }
  }
  return FB_OK;
}

/* Area limit min_area (m^2, positive). Nodes that all coincide are said
 * to rather than compared with the limit: for a mesh of nothing else it is
 * DBL_MIN, a number that would tell the reader nothing. */
static int check_area(const fb_mesh *m, size_t e, double min_area, fb_err *err)
{
  double v[3];
  fb_mesh_element_area_vector(m, e, v);
  const double area = fb_norm3(v);
  if (!isfinite(area))
    return too_large(m, e, err);
  if (area < min_area && nodes_coincide(m, e))
    return element_error(m, e, err, "degenerate: its nodes coincide (zero area)");
  if (area < min_area) {
    char what[160];
    snprintf(what, sizeof what, "degenerate: area %g m^2 below the limit %g m^2", area,
             min_area);
    return element_error(m, e, err, what);
  }
  if (fb_mesh_element_type(m, e) != FB_ELEM_QUAD4)
    return FB_OK;
  const double unit[3] = {v[0] / area, v[1] / area, v[2] / area};
  return check_corners(m, e, unit, min_area, err);
}

/* Node 4 of a quadrilateral against the plane of nodes 1-3 (which span a
 * plane once check_area passed). */
static int check_warp(const fb_mesh *m, size_t e, fb_err *err)
{
  const size_t *nd = fb_mesh_element_nodes(m, e);
  const double *p[4];
  for (int k = 0; k < 4; ++k)
    p[k] = fb_mesh_node_xyz(m, nd[k]);
  double u[3], w[3], n[3], d[3], diag2[3];
  fb_sub3(p[1], p[0], u);
  fb_sub3(p[2], p[0], w);
  fb_cross3(u, w, n);
  fb_sub3(p[3], p[0], d);
  const double offset = fabs(fb_dot3(d, n)) / fb_norm3(n);
  fb_sub3(p[2], p[0], u);
  fb_sub3(p[3], p[1], diag2);
  const double diagonal = fmax(fb_norm3(u), fb_norm3(diag2));
  if (!isfinite(offset) || !isfinite(diagonal))
    return too_large(m, e, err);
  if (offset <= WARP_MAX * diagonal)
    return FB_OK;
  char what[160];
  snprintf(what, sizeof what, "warped: node %ld is %.3g mm off the plane of the other three",
           fb_mesh_node_id(m, nd[3]), offset * 1e3);
  return element_error(m, e, err, what);
}

int fb_mesh_check_elements(const fb_mesh *m, size_t *bad, fb_err *err)
{
  /* At least DBL_MIN: a zero area never passes, and a quadrilateral's
   * corners then span a plane for check_warp (a mesh whose nodes all
   * coincide has a zero bounding box, and once made check_warp divide 0
   * by 0 and print "-nan mm"). */
  const double min_area = fmax(1e-12 * bbox_diag2(m), DBL_MIN);
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    int rc = check_repeated(m, e, err);
    if (!rc)
      rc = check_area(m, e, min_area, err);
    if (!rc && fb_mesh_element_type(m, e) == FB_ELEM_QUAD4)
      rc = check_warp(m, e, err);
    if (rc) {
      *bad = e;
      return rc;
    }
  }
  return FB_OK;
}

static int check_used(const fb_mesh *m, fb_err *err)
{
  const size_t nnodes = fb_mesh_nnodes(m);
  unsigned char *used = calloc(nnodes ? nnodes : 1, 1);
  if (!used)
    return fb_err_set(err, FB_ENOMEM, "out of memory checking a mesh");
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    const size_t *nd = fb_mesh_element_nodes(m, e);
    for (size_t k = 0; k < fb_mesh_type_nodes(fb_mesh_element_type(m, e)); ++k)
      used[nd[k]] = 1;
  }
  const size_t *super = NULL;
  for (size_t k = 0; k < fb_mesh_superelement(m, &super, NULL, NULL); ++k)
    used[super[k]] = 1;
  size_t unused = 0;
  while (unused < nnodes && used[unused])
    ++unused;
  free(used);
  if (unused < nnodes)
    return fb_err_set(err, FB_EMODEL, "node %ld is used by no element",
                      fb_mesh_node_id(m, unused));
  return FB_OK;
}

static int check_nsets(const fb_mesh *m, fb_err *err)
{
  for (size_t i = 0; i < fb_mesh_nnsets(m); ++i) {
    const char *name = fb_mesh_nset_name(m, i);
    size_t n = 0;
    fb_mesh_nset(m, name, NULL, &n);
    if (n == 0)
      return fb_err_set(err, FB_EMODEL, "node set '%s' is empty", name);
  }
  return FB_OK;
}

int fb_mesh_check(const fb_mesh *m, fb_err *err)
{
  if (!m)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_check: mesh is NULL");
  if (fb_mesh_nelements(m) == 0 && !fb_mesh_superelement(m, NULL, NULL, NULL))
    return fb_err_set(err, FB_EMODEL, "the mesh has no elements");
  size_t bad = 0;
  int rc = fb_mesh_check_elements(m, &bad, err);
  if (!rc)
    rc = check_used(m, err);
  if (!rc)
    rc = check_nsets(m, err);
  return rc;
}
