/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal interfaces of the flat shell elements (shell.c, shell_membrane.c,
 * shell_bending.c). Everything here works in the element's local frame:
 * x along edge 1-2, z along the normal, nodes given by their in-plane
 * coordinates x[], y[] (counter-clockwise about z by construction). */
#ifndef FLEXBOND_FEM_SHELL_INTERNAL_H
#define FLEXBOND_FEM_SHELL_INTERNAL_H

#include <stddef.h>

#include "flexbond/fem.h"

/* Nodes of the largest element (the quadrilateral). */
#define FB_SHELL_MAX_NODES 4

/* An element's local frame (see shell.c): rot's rows are the local x, y,
 * z axes in global components; x[], y[] the nodes' in-plane coordinates
 * about their centroid, h[] their heights above the mean plane (a warped
 * quadrilateral's rigid links). */
typedef struct fb_shell_frame {
  size_t nn;
  double rot[9];
  double x[FB_SHELL_MAX_NODES];
  double y[FB_SHELL_MAX_NODES];
  double h[FB_SHELL_MAX_NODES];
  double area;
  double diagonal; /* a quadrilateral's longer diagonal, a triangle's longest edge */
} fb_shell_frame;

/* The local frame of an element of type (TRI3 or QUAD4) at xyz (3 nn):
 * FB_EINVAL for a degenerate, warped or non-convex element. */
int fb_shell_frame_make(fb_elem_type type, const double *xyz, fb_shell_frame *f, fb_err *err);

/* Drilling factor used when fb_shell_props.drill_factor is 0. */
#define FB_SHELL_DRILL_DEFAULT 1e-4

/* FB_EINVAL unless E > 0, -1 < nu < 0.5, density > 0, thickness > 0 (all
 * finite) and drill_factor >= 0, with a message naming the bad value. */
int fb_shell_check_props(const fb_shell_props *p, fb_err *err);

/* Plane-stress elasticity matrix times a thickness factor s (3x3,
 * row-major, engineering shear strain): s E / (1 - nu^2) [1 nu 0; nu 1 0;
 * 0 0 (1 - nu) / 2]. s = t gives the membrane rigidity, s = t^3 / 12 the
 * bending rigidity. */
void fb_shell_plane_stress(double young, double poisson, double s, double *c);

/* Membrane stiffness of the triangle on the local DOFs (u, v, rz) of each
 * node, 9x9 column-major: the optimal ANDES triangle OPT with drilling
 * freedoms (Felippa 2003). area: the triangle's area (> 0). */
void fb_shell_membrane_tri(const double *x, const double *y, double area,
                           const fb_shell_props *p, double *k);

/* The quadrilateral functions below need a strictly convex element (then
 * det J > 0 everywhere); fb_shell_element checks that first. */

/* Membrane stiffness of the quadrilateral on (u, v, rz) of each node,
 * 12x12 column-major: QM6 incompatible-mode quadrilateral (Taylor,
 * Beresford & Wilson 1976) plus the fictitious drilling stiffness
 * drill_factor E t A (area: the element's area). */
void fb_shell_membrane_quad(const double *x, const double *y, double area,
                            const fb_shell_props *p, double *k);

/* Plate bending stiffness on the local DOFs (w, rx, ry) of each node,
 * 3 nn x 3 nn column-major: DKT for nn = 3 (Batoz, Bathe & Ho 1980), DKQ
 * for nn = 4 (Batoz & Ben Tahar 1982). */
void fb_shell_bending(size_t nn, const double *x, const double *y, const fb_shell_props *p,
                      double *k);

/* Membrane strains (eps_x, eps_y, gamma_xy) at the element's centre per
 * unit membrane DOF (u, v, rz of each node): bm, 3 x 3 nn row-major,
 * from the strain field the membrane stiffness integrates (OPT's basic
 * constant strain; QM6's field, whose incompatible modes vanish there). */
void fb_shell_membrane_strain(size_t nn, const double *x, const double *y, double area,
                              double *bm);

/* Curvatures (kappa_x, kappa_y, kappa_xy) at the element's centre (the
 * centroid of a triangle, xi = eta = 0 of a quadrilateral) per unit
 * bending DOF (w, rx, ry of each node): bb, 3 x 3 nn row-major, the same
 * discrete Kirchhoff curvature matrix the stiffness integrates. */
void fb_shell_bending_curvature(size_t nn, const double *x, const double *y, double *bb);

/* Jacobian of the quadrilateral's bilinear map at (xi, eta): jac = (x,xi,
 * y,xi, x,eta, y,eta). */
void fb_shell_quad_jacobian(const double *x, const double *y, double xi, double eta,
                            double *jac);

/* Bilinear shape functions of the quadrilateral at (xi, eta), their
 * Cartesian derivatives for corner coordinates x[], y[] and the Jacobian
 * determinant. */
void fb_shell_quad_bilinear(const double *x, const double *y, double xi, double eta, double *n,
                            double *dndx, double *dndy, double *detj);

/* Corner parametric coordinates of the quadrilateral, counter-clockwise. */
extern const double fb_shell_quad_xi[4];
extern const double fb_shell_quad_eta[4];

#endif
