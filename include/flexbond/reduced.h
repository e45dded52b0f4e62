/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: structures reduced in another finite-element tool
 * (superelements): a symmetric stiffness K and, when the file gives one, a
 * mass M over the retained degrees of freedom of interface nodes, read
 * from Matrix Market files, a Nastran DMIG punch file or CalculiX's
 * condensed substructure file, and checked before anything is computed
 * from them (docs/reduced-hulls.md).
 *
 * A DOF is a node (by its user id) and a component 1..6: ux, uy, uz (m),
 * rx, ry, rz (rad), in global axes. Node positions come from the nodes
 * file, a text file of lines "id, x, y, z" (m) and, for Matrix Market
 * matrices only, a fifth field naming the node's DOFs as Nastran
 * components do ("123456", "123"): the matrices' rows are the nodes' DOFs
 * in the file's order, each node's components in increasing order. Blank
 * lines and lines starting with '#' are skipped. */
#ifndef FLEXBOND_REDUCED_H
#define FLEXBOND_REDUCED_H

#include <stddef.h>

#include "flexbond/error.h"
#include "flexbond/mat.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fb_reduced fb_reduced;

/* Most DOFs a reduced structure may have: its checks are dense
 * eigen-solves (FB_DENSE_EIG_MAX, O(n^3)), and a superelement's interface
 * is a few hundred DOFs. */
#define FB_REDUCED_MAX_DOFS ((size_t)3000)

/* Matrix Market K and M (m_path may be NULL: no mass), of the order the
 * nodes file's DOFs give (checked on the size line, before allocation;
 * fb_mat_read_mtx_dims). Errors "path:line: message" (FB_EPARSE), FB_EIO
 * for a file that cannot be read. *out new (fb_reduced_free). */
int fb_reduced_read_mtx(const char *k_path, const char *m_path, const char *nodes_path,
                        fb_reduced **out, fb_err *err);

/* A Nastran DMIG punch or bulk file: the matrices named k_name and m_name
 * (m_name NULL: no mass), each a header entry (NAME, "0", IFO 1 or 6, TIN
 * 1 or 2) and column entries (GJ, CJ, then GI, CI, A triples), in small
 * (8-character), large (16-character, "DMIG*") or free (comma-separated)
 * field format; IFO 6 gives one triangle, IFO 1 every entry. Other DMIG
 * matrices and other entries are skipped. The DOFs are those the matrices
 * name, ordered by the nodes file's order, then component; every node
 * must be in the nodes file. */
int fb_reduced_read_dmig(const char *path, const char *k_name, const char *m_name,
                         const char *nodes_path, fb_reduced **out, fb_err *err);

/* CalculiX's condensed stiffness (*SUBSTRUCTURE MATRIX OUTPUT,
 * OUTPUT FILE=USER DEFINED): a *USER ELEMENT with one DOF per element
 * "node" (the retained node's id in the "** ELEMENT NODES" comment, its
 * component in the DOF lines) and *MATRIX,TYPE=STIFFNESS, the lower
 * triangle row by row. No mass (ccx 2.20 writes none). */
int fb_reduced_read_ccx(const char *path, const char *nodes_path, fb_reduced **out,
                        fb_err *err);

void fb_reduced_free(fb_reduced **r);

size_t fb_reduced_ndofs(const fb_reduced *r);
/* DOF i's node id and component (1..6). */
long fb_reduced_dof_node(const fb_reduced *r, size_t i);
int fb_reduced_dof_component(const fb_reduced *r, size_t i);
/* The index of (node id, component), or -1. */
long fb_reduced_find_dof(const fb_reduced *r, long node, int component);
size_t fb_reduced_nnodes(const fb_reduced *r);
long fb_reduced_node_id(const fb_reduced *r, size_t node);
const double *fb_reduced_node_xyz(const fb_reduced *r, size_t node);
/* The matrices (borrowed from r); M NULL when the files give none. */
const fb_mat *fb_reduced_stiffness(const fb_reduced *r);
const fb_mat *fb_reduced_mass(const fb_reduced *r);

/* The checks a superelement must pass before anything is computed from
 * it, each FB_EMODEL naming the file and the line of the entry where the
 * format keeps one (DMIG, CalculiX), else the entry by its DOFs: K and M
 * symmetric (|a_ij - a_ji| at most 2 p max(|a_ij|, |a_ji|) + 1e-8
 * sqrt(|a_ii a_jj|), p the relative precision of the file's numbers:
 * half a unit of the fewest significant digits it writes, at least 4);
 * M positive semi-definite with a positive mass for each rigid
 * translation; and K free-free: on K^ = D^-1 K D^-1 (D = sqrt(diag K)),
 * the six rigid-body motions of the interface nodes' positions with
 * |K^ r^| <= z (r^ = D r normalised) and no other eigenvalue of K^ within
 * z of zero once they are projected out, z = max(2 p, 1e-9) ||K^||_F
 * (the bound p ||K^||_F of the rounding's effect, twice).
 * docs/reduced-hulls.md derives the tolerances. */
int fb_reduced_check(const fb_reduced *r, fb_err *err);

/* K with the interface's six rigid-body motions R made exact null
 * vectors, *out = P' K P with the projector P = I - R (R' M R)^-1 R' M
 * (M's when the files give one, else the identity): the rigid-body modes
 * of (K, M) are then exactly R and the elastic ones M-orthogonal to them,
 * and an elastic mode x (P x = x) sees the same rounding x' dK x as in K.
 * For a file whose numbers are too short to keep K R = 0 (8-column DMIG
 * fields: a rigid-body eigenvalue of -734 s^-2 on a beam whose highest is
 * 1e8), after fb_reduced_check has found K R zero to the file's
 * precision. *out new, dense. */
int fb_reduced_stiffness_projected(const fb_reduced *r, fb_mat **out, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
