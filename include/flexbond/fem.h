/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: flat shell finite elements (6 DOF per node), meshes, sparse
 * assembly and modal analysis, for thin steel plates (Kirchhoff bending
 * plus membrane).
 *
 * Degrees of freedom per node, in global axes and in this order:
 * ux, uy, uz (m), rx, ry, rz (rad). Global DOF index = 6 * node + k. */
#ifndef FLEXBOND_FEM_H
#define FLEXBOND_FEM_H

#include <stddef.h>
#include <stdio.h>

#include "flexbond/error.h"
#include "flexbond/mat.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- Meshes. */

typedef enum fb_elem_type {
  FB_ELEM_TRI3 = 3, /* 3-node triangle (Abaqus S3) */
  FB_ELEM_QUAD4 = 4 /* 4-node quadrilateral (Abaqus S4), nodes counter-clockwise */
} fb_elem_type;

typedef struct fb_mesh fb_mesh;

int fb_mesh_new(fb_mesh **out, fb_err *err);
void fb_mesh_free(fb_mesh **m);
int fb_mesh_clone(const fb_mesh *m, fb_mesh **out, fb_err *err);

/* Adds a node with a user id (unique, > 0; used in files and messages) and
 * coordinates in m; its index (0-based, insertion order) in *index. */
int fb_mesh_add_node(fb_mesh *m, long id, double x, double y, double z, size_t *index,
                     fb_err *err);
/* Adds an element of the given type over node indices (3 or 4 of them),
 * with a user id (unique, > 0). */
int fb_mesh_add_element(fb_mesh *m, long id, fb_elem_type type, const size_t *nodes,
                        fb_err *err);
/* Adds (or extends) the node set `name` with node indices: those already in
 * it are skipped, in O(1) each, so a set can be built a few members at a
 * time; members keep the order they first came in. */
int fb_mesh_add_nset(fb_mesh *m, const char *name, size_t n, const size_t *nodes, fb_err *err);

size_t fb_mesh_nnodes(const fb_mesh *m);
size_t fb_mesh_nelements(const fb_mesh *m);
/* Number of elements of one type. */
size_t fb_mesh_count(const fb_mesh *m, fb_elem_type type);
const double *fb_mesh_node_xyz(const fb_mesh *m, size_t node);
long fb_mesh_node_id(const fb_mesh *m, size_t node);
/* Index of the node with user id, or -1. */
long fb_mesh_find_node_id(const fb_mesh *m, long id);
/* Moves every node by (dx, dy, dz) m. */
void fb_mesh_translate(fb_mesh *m, double dx, double dy, double dz);
/* Index of the element with user id, or -1. */
long fb_mesh_find_element_id(const fb_mesh *m, long id);
/* Index of the node within tol (m) of (x, y, z), or -1. */
long fb_mesh_find_node_at(const fb_mesh *m, double x, double y, double z, double tol);
fb_elem_type fb_mesh_element_type(const fb_mesh *m, size_t e);
long fb_mesh_element_id(const fb_mesh *m, size_t e);
/* Node indices of element e (3 or 4). */
const size_t *fb_mesh_element_nodes(const fb_mesh *m, size_t e);
/* Element e's centroid into c[3] (m): the mean of its nodes, in the
 * mesh's frame. */
void fb_mesh_element_centroid(const fb_mesh *m, size_t e, double *c);
/* Element e's area vector into v[3] (m^2): its area times its unit
 * normal (right-handed in the node order); a warped quadrilateral's
 * projected area, half the cross product of its diagonals. */
void fb_mesh_element_area_vector(const fb_mesh *m, size_t e, double *v);
/* The mesh's outline (*edges new, 2 node indices per edge, lower first,
 * in increasing order; free() it): every edge on one element (the
 * boundary), on more than two (where a bulkhead meets a wall), or between
 * two whose planes meet at more than angle (rad; the sign of their normals
 * does not count, as plates need not share an orientation). */
int fb_mesh_outline(const fb_mesh *m, double angle, size_t **edges, size_t *nedges,
                    fb_err *err);
size_t fb_mesh_nnsets(const fb_mesh *m);
const char *fb_mesh_nset_name(const fb_mesh *m, size_t i);
/* Node set by name (case-insensitive, as in Abaqus): 1 and its nodes, or 0. */
int fb_mesh_nset(const fb_mesh *m, const char *name, const size_t **nodes, size_t *n);
/* Element sets, as node sets: adds (or extends) the set `name` with
 * element indices; by name (case-insensitive) 1 and its elements, or 0. */
int fb_mesh_add_elset(fb_mesh *m, const char *name, size_t n, const size_t *elements,
                      fb_err *err);
size_t fb_mesh_nelsets(const fb_mesh *m);
const char *fb_mesh_elset_name(const fb_mesh *m, size_t i);
int fb_mesh_elset(const fb_mesh *m, const char *name, const size_t **elements, size_t *n);

/* Validates the mesh: every node used by an element; no degenerate element
 * (area below 1e-12 of the mesh's bounding-box diagonal squared, repeated
 * node); no warped quadrilateral (distance of a node from the plane of
 * the other three above 1e-2 of the element's longer diagonal; below it
 * the shell element's rigid links keep a warped element's rigid-body
 * motions exact, src/fem/shell.c); no
 * quadrilateral that is not strictly convex; at least one element; node
 * sets non-empty. FB_EMODEL naming the element or node by user id. */
int fb_mesh_check(const fb_mesh *m, fb_err *err);

/* ---- Shell elements. */

typedef struct fb_shell_props {
  double young;     /* Pa */
  double poisson;   /* - */
  double density;   /* kg/m^3 */
  double thickness; /* m */
  /* Fictitious drilling stiffness of the quadrilaterals: k_rz =
   * drill_factor * E t A (per element, shared by its nodes), a penalty on
   * rz minus the membrane's own rotation (v,x - u,y)/2, so rigid-body
   * motions stay exact. 0 selects the default 1e-4, small enough that it
   * does not move the low frequencies (tested: a factor of 10 changes them
   * < 0.1% on a folded box, where it couples to the bending of the adjacent
   * plates). Must be >= 0. Triangles ignore it: their membrane (OPT) has a
   * real drilling freedom. */
  double drill_factor;
  /* Non-structural mass per area (kg/m^2, >= 0: lining, paint, equipment
   * spread over a plate), smeared through the thickness: the mass is that
   * of density + nonstructural_mass / thickness (translational mass per
   * area density * thickness + nonstructural_mass, rotary inertia that
   * times thickness^2 / 12), which an Abaqus or CalculiX deck writes as
   * the material's density. Stiffness ignores it. */
  double nonstructural_mass;
} fb_shell_props;

/* ---- Added masses: a deck's MASS elements and non-structural masses
 * (Abaqus *MASS, *NONSTRUCTURAL MASS), part of the mesh: fb_fem_assemble
 * and fb_fem_mesh_mass_properties count them, fb_mesh_write_inp writes
 * them, fb_mesh_clone copies them. */

/* Adds a point mass (kg, >= 0, finite) on the three translations of
 * node (no rotary inertia, as a CalculiX MASS element), with a user id
 * (> 0) that no element or other point mass has. */
int fb_mesh_add_point_mass(fb_mesh *m, long id, size_t node, double mass, fb_err *err);
size_t fb_mesh_npoint_masses(const fb_mesh *m);
/* Point mass i (in the order added): its id, node index and mass (kg). */
long fb_mesh_point_mass_id(const fb_mesh *m, size_t i);
size_t fb_mesh_point_mass_node(const fb_mesh *m, size_t i);
double fb_mesh_point_mass(const fb_mesh *m, size_t i);
/* Index of the point mass with user id, or -1. */
long fb_mesh_find_point_mass_id(const fb_mesh *m, long id);
/* Adds per_area (kg/m^2, >= 0, finite) to element e's non-structural
 * mass, on top of its section's (fb_mesh_element_props sums them). */
int fb_mesh_add_element_nonstructural(fb_mesh *m, size_t e, double per_area, fb_err *err);
/* The non-structural mass per area added to element e (0 if none). */
double fb_mesh_element_nonstructural(const fb_mesh *m, size_t e);

/* ---- Shell sections: per element set properties. */

/* Gives the elements of the element set elset the properties *p (copied;
 * checked as fb_shell_check_props does), replacing any section they had;
 * the set must exist. Elements outside every section take the properties
 * the caller of fb_fem_assemble passes; the drilling factor is always the
 * caller's. */
int fb_mesh_set_section(fb_mesh *m, const char *elset, const fb_shell_props *p, fb_err *err);
/* Sections in the order they were set (a later one may have taken every
 * element of an earlier one): their element set's name and properties. */
size_t fb_mesh_nsections(const fb_mesh *m);
const char *fb_mesh_section_elset(const fb_mesh *m, size_t i);
const fb_shell_props *fb_mesh_section_props(const fb_mesh *m, size_t i);
/* The section of element e, or -1 for none. */
long fb_mesh_element_section(const fb_mesh *m, size_t e);
/* A superelement: a structure reduced elsewhere (flexbond/reduced.h)
 * over the six DOFs of each of nodes[0 .. n) (indices, distinct), its
 * stiffness k and mass (NULL: none) dense column-major 6n x 6n, row
 * 6 i + c the node nodes[i]'s component c (ux, uy, uz, rx, ry, rz), in
 * global axes (copied). fb_fem_assemble adds it to the shells' matrices;
 * its nodes count as used (fb_mesh_check). One per mesh: a second
 * replaces the first. */
int fb_mesh_set_superelement(fb_mesh *m, size_t n, const size_t *nodes, const double *k,
                             const double *mass, fb_err *err);
/* The superelement's node count (0: none) and its arrays (borrowed from
 * m; any pointer may be NULL). */
size_t fb_mesh_superelement(const fb_mesh *m, const size_t **nodes, const double **k,
                            const double **mass);

/* The number of elements whose section is sec (-1: those with none). */
size_t fb_mesh_section_nelements(const fb_mesh *m, long sec);
/* The properties element e is assembled with: its section's with base's
 * drilling factor, or *base (not NULL) when it has none, its own added
 * non-structural mass (fb_mesh_add_element_nonstructural) on top. */
fb_shell_props fb_mesh_element_props(const fb_mesh *m, size_t e, const fb_shell_props *base);

typedef enum fb_mass_kind {
  FB_MASS_CONSISTENT, /* default */
  FB_MASS_LUMPED      /* diagonal: translational mass per node, rotary from the
                         plate's thickness */
} fb_mass_kind;

/* Stiffness and mass matrices of one element in global coordinates,
 * column-major n x n with n = 6 * (3 or 4); ke or me may be NULL.
 * FB_EINVAL if the element is degenerate. */
int fb_shell_element(fb_elem_type type, const double *xyz, const fb_shell_props *p,
                     fb_mass_kind mass, double *ke, double *me, fb_err *err);

/* Assembles K and M (6 nnodes square, sparse CSC, symmetric); either
 * output may be NULL (not both). Each element takes
 * fb_mesh_element_props(m, e, p); M has the mesh's point masses on their
 * nodes' translations. An element's error is prefixed with
 * "element <id>: ". */
int fb_fem_assemble(const fb_mesh *m, const fb_shell_props *p, fb_mass_kind mass, fb_mat **K,
                    fb_mat **M, fb_err *err);

/* The mesh's six rigid-body motions about the point o (m) into r (6
 * columns of 6 nnodes, column-major): translations along x, y, z, then
 * rotations about x, y, z through o, each node's rotation the motion's.
 * Null vectors of the shell elements' K (src/fem/shell.c keeps rigid-body
 * motions exact), for fb_eig_opts.null_vectors. */
void fb_mesh_rigid_modes(const fb_mesh *m, const double *o, double *r);

/* Total mass, centre of mass and inertia tensor about it (row-major 3x3,
 * kg m^2) of a mass matrix over the mesh, from its rigid-body modes. */
int fb_fem_mass_properties(const fb_mesh *m, const fb_mat *M, double *mass, double *cg,
                           double *inertia, fb_err *err);

/* The same properties of the structure itself, element by element
 * (r_e' M_e r_e over each element's rigid-body motions, M_e assembled with
 * fb_mesh_element_props(m, e, p) and kind; the point masses' m r r' over
 * their nodes' translations): no global matrix is built, for
 * a program that needs a mesh's mass, centre and inertia before (or
 * instead of) its finite-element model. */
int fb_fem_mesh_mass_properties(const fb_mesh *m, const fb_shell_props *p, fb_mass_kind kind,
                                double *mass, double *cg, double *inertia, fb_err *err);

/* The DOFs kept after fixing the listed ones: keep[] receives the
 * n - nfixed indices in increasing order. The fixed DOFs must be distinct
 * and below n (FB_EINVAL otherwise: merge overlapping node sets first). */
int fb_fem_free_dofs(size_t n, const size_t *fixed, size_t nfixed, size_t *keep, fb_err *err);
/* Rows and columns keep[0 .. nkeep) of the square a (the constrained
 * matrix), keep strictly increasing; same storage kind as a. */
int fb_fem_submatrix(const fb_mat *a, const size_t *keep, size_t nkeep, fb_mat **out,
                     fb_err *err);

/* Guyan's static condensation of K (and M) onto the DOFs keep[0 ..
 * nkeep), strictly increasing: with T = [I; -K_oo^-1 K_or] (the other
 * DOFs' static response to each kept DOF's unit motion), kr = T' K T =
 * K_rr - K_ro K_oo^-1 K_or and mr = T' M T (either NULL), dense
 * column-major nkeep x nkeep, symmetrised. Exact statically for loads at
 * the kept DOFs; M's condensation keeps the rigid-body motions' mass
 * exactly when the kept DOFs can show them (Guyan, "Reduction of
 * stiffness and mass matrices", AIAA J. 3(2), 1965). K_oo must be
 * positive definite: the kept DOFs hold every rigid-body motion.
 * FB_EINVAL, FB_ENOMEM, or the factorisation's error. */
int fb_fem_guyan(const fb_mat *K, const fb_mat *M, const size_t *keep, size_t nkeep, double *kr,
                 double *mr, fb_err *err);

/* ---- Modes and reduced bases of a structure (src/fem/modal.c,
 * src/fem/lanczos.c). K symmetric positive semi-definite (a free
 * structure's has six zero eigenvalues), M symmetric positive definite. */

/* How an eigen-solve runs. */
typedef enum fb_eig_method {
  /* LAPACK for every mode (nmodes >= n - 1) or a model of at most
   * FB_EIG_DENSE_AUTO_DOFS, block Lanczos otherwise. */
  FB_EIG_AUTO = 0,
  /* LAPACK dsygvd: every mode, O(n^3) time and 4 n^2 doubles. */
  FB_EIG_DENSE = 1,
  /* Spectral transformation block Lanczos on a CHOLMOD factor of K + s M
   * (fem_lanczos): the lowest modes only, memory and time about linear in
   * the DOFs and the modes. */
  FB_EIG_LANCZOS = 2
} fb_eig_method;

/* The largest model FB_EIG_AUTO solves densely whatever it asks (measured:
 * below it LAPACK is as fast as the Lanczos set-up). */
#define FB_EIG_DENSE_AUTO_DOFS 200

typedef struct fb_eig_opts {
  fb_eig_method method;
  /* Bytes the solve may allocate for its own work (the dense matrices, the
   * Cholesky factor, the Lanczos basis, the modes): each is checked before
   * it is allocated (FB_ENOMEM naming the megabytes it needs); 0: no
   * limit. */
  size_t memory_limit;
  fb_progress progress; /* every step of a long solve; may stop it */
  /* 1: frequencies only, no shapes (LAPACK's eigenvalue-only path; the
   * Lanczos vectors are made anyway). */
  int values_only;
  /* Known eigenvectors of eigenvalue 0 (a free structure's rigid-body
   * motions: fb_mesh_rigid_modes), n x nnull, borrowed for the solves:
   * block Lanczos keeps its iteration orthogonal to them, which spares it
   * the steps a sixfold eigenvalue would take, and returns them
   * M-orthonormalised as the first modes. Each must be a null vector of K
   * to |K v| <= 1e-10 max|K_ii| |v| (FB_EINVAL otherwise); the dense
   * solver needs no help and ignores them. */
  const double *null_vectors;
  size_t nnull;
  /* Threads a Lanczos step's solves may use (fb_chol_set_threads): 1 (the
   * default) or 2. */
  int threads;
} fb_eig_opts;

/* method AUTO, no memory limit, no progress. */
void fb_eig_opts_default(fb_eig_opts *o);

/* The modal model of a structure: K and M (borrowed: they must outlive
 * it), the Cholesky factor of K + s M with a small shift s (made when a
 * solve or a static response first needs it, then reused), and its lowest
 * modes once solved. Built once, asked many times. */
typedef struct fb_fem_modal fb_fem_modal;

/* Checks K and M (square, of one order, finite, symmetric to 1e-10 of
 * their largest entry: FB_EINVAL) and chooses the shift. o NULL: the
 * defaults. Nothing is factorised yet. */
int fb_fem_modal_new(const fb_mat *K, const fb_mat *M, const fb_eig_opts *o, fb_fem_modal **out,
                     fb_err *err);
void fb_fem_modal_free(fb_fem_modal **fm);

/* Solves for the lowest modes: the nmodes lowest (nmodes > 0), or with
 * nmodes 0 every mode at or below cutoff_hz and the first one above it
 * (the one that shows the cut-off was passed). Rigid-body modes come out
 * at exactly 0 Hz (fb_fem_rigid_threshold_hz tells them). Replaces the
 * modes of an earlier solve. FB_EINVAL for nmodes above n or a cut-off
 * that is not a finite number >= 0; FB_ESOLVER when K is not positive
 * semi-definite (an eigenvalue below -s) or the solver fails; FB_ENOMEM
 * beyond the memory limit; FB_EINTR when the progress callback stops
 * it. */
int fb_fem_modal_solve(fb_fem_modal *fm, size_t nmodes, double cutoff_hz, fb_err *err);
size_t fb_fem_modal_ndof(const fb_fem_modal *fm);
/* The solved modes: their number, how many are rigid-body modes (the
 * first ones), their frequencies (Hz) and eigenvalues ((rad/s)^2, the
 * rigid ones exactly 0), and their shapes (ndof x nmodes, column-major,
 * M-orthonormal). NULL before a solve. */
size_t fb_fem_modal_nmodes(const fb_fem_modal *fm);
size_t fb_fem_modal_nrigid(const fb_fem_modal *fm);
const double *fb_fem_modal_freq_hz(const fb_fem_modal *fm);
const double *fb_fem_modal_lambda(const fb_fem_modal *fm);
const double *fb_fem_modal_shapes(const fb_fem_modal *fm);

/* What the last solve did. */
typedef struct fb_eig_info {
  fb_eig_method method; /* DENSE or LANCZOS, as chosen */
  size_t block;         /* Lanczos block size (0 dense) */
  size_t factor_bytes;  /* the Cholesky factor's (0 when none was made) */
  double seconds;       /* wall time of the solve, the factorisation included */
} fb_eig_info;
fb_eig_info fb_fem_modal_info(const fb_fem_modal *fm);

/* A reduced basis (Craig & Kurdila, "Fundamentals of Structural
 * Dynamics", 2nd ed., ch. 17-18): the nkeep lowest solved modes (every
 * rigid-body mode among them: FB_EINVAL otherwise, or nkeep above the
 * modes solved) and, for the nf force patterns F (ndof x nf,
 * column-major), the residual flexibility those modes miss (MacNeal,
 * "A hybrid method of component mode synthesis", Comput. Struct. 1,
 * 1971): the static response with inertia relief, u = K^+ (f - M Phi_r
 * Phi_r' f), less its part along the kept modes. order > 1 adds the
 * next order - 1 blocks of the load-dependent Ritz sequence u_{j+1} =
 * K^+ M u_j (E. L. Wilson, M.-W. Yuan & J. M. Dickens, "Dynamic analysis
 * by direct superposition of Ritz vectors", Earthq. Eng. Struct. Dyn.
 * 10, 1982), each freed of the kept modes and of the blocks before it:
 * the inertia forces of the static shapes, the next term of what
 * truncation misses (order 0 or 1: the static correction alone). Vectors
 * that add nothing new (M-norm below 1e-8 of theirs before projection)
 * are dropped. A Rayleigh-Ritz solve on the added vectors makes the
 * whole basis M-orthonormal and K-orthogonal: T' M T = I, T' K T =
 * diag(lambda), the kept modes unchanged and first, the added vectors
 * after them by ascending lambda. A static load in the span of F is
 * reproduced exactly. *T (ndof x *nbasis) and *lambda ((rad/s)^2,
 * *nbasis) are new; *nstatic counts the vectors of the first block
 * (the static correction), the rest are higher order. */
int fb_fem_modal_basis(fb_fem_modal *fm, size_t nkeep, const double *F, size_t nf, size_t order,
                       double **T, double **lambda, size_t *nbasis, size_t *nstatic,
                       fb_err *err);

/* fb_fem_modal_basis in steps, for bases of several orders from the same
 * vectors: fb_fem_modal_extend appends a block to the added vectors *A
 * (ndof x *nadded, new or grown; M-orthonormal, orthogonal to the nkeep
 * kept modes): with *nadded 0 the static correction of the nf patterns F,
 * else the next load-dependent Ritz block of the last *nlast vectors (by
 * the shifted factor, (K + s M)^-1 M u in place of K^+ M u: a Krylov
 * sequence of the inertia terms all the same, which needs no exact
 * static solve); the new block's size goes to *nlast (0: nothing new). fb_fem_modal_ritz
 * makes the basis of the kept modes and the nadded vectors A (*T, *lambda
 * new). */
int fb_fem_modal_extend(fb_fem_modal *fm, size_t nkeep, const double *F, size_t nf, double **A,
                        size_t *nadded, size_t *nlast, fb_err *err);
int fb_fem_modal_ritz(fb_fem_modal *fm, size_t nkeep, const double *A, size_t nadded,
                      double **T, double **lambda, fb_err *err);

/* The nmodes lowest modes of (K, M) in one call (a modal model made,
 * solved and freed): frequencies (Hz) and, if vectors is not NULL, shapes
 * (n x nmodes, M-orthonormal). o NULL: the defaults. */
int fb_fem_modes(const fb_mat *K, const fb_mat *M, size_t nmodes, const fb_eig_opts *o,
                 double *freq_hz, double *vectors, fb_err *err);

/* Frequency (Hz) at or below which a computed mode of (K, M) is a
 * rigid-body mode. Rigid-body modes come out as round-off, ~sqrt(eps)
 * times the model's own frequency scale sqrt(trace K / trace M) / 2 pi
 * (~1e4 Hz for steel shells, so ~1e-4 Hz); an elastic mode is above 1e-6
 * of that scale (0.01 Hz there). */
double fb_fem_rigid_threshold_hz(const fb_mat *K, const fb_mat *M);

/* ---- Stresses and strains of the shell elements (src/fem/shell_stress.c).
 *
 * Recovered at each element's centre (a triangle's centroid, a
 * quadrilateral's xi = eta = 0) from the strain fields its stiffness
 * integrates: the membrane's (OPT's constant strain, QM6's field, whose
 * incompatible modes vanish at the centre) and the discrete Kirchhoff
 * plate's curvatures (DKT, DKQ). Everything is in the element's local
 * axes (fb_shell_stress_axes: x along edge 1-2, z the normal, right-handed
 * in the node order, y = z x x), in SI units. Through the thickness the
 * strain is eps(z) = eps0 + z kappa (Kirchhoff), z along the local normal,
 * with curvatures kappa = (bx,x, by,y, bx,y + by,x) of the normal's
 * rotations (bx, by) = (ry, -rx) (local rotations), so the in-plane
 * displacement at height z is z (bx, by) and kappa_x = -w,xx. Resultants:
 * N = t C eps0 (N/m), M = (t^3 / 12) C kappa (N m / m), C the plane-stress
 * elasticity; then the stress sigma(z) = N / t + 12 M z / t^3, at the top
 * (z = +t/2, the side the normal points to) N / t + 6 M / t^2, at the
 * bottom N / t - 6 M / t^2. Shear strains are engineering (gamma_xy). A
 * warped quadrilateral is recovered at its nodes' projections on its mean
 * plane, through the rigid links its stiffness uses. */

/* The state of one element. Components (x, y, xy) in its local axes. */
typedef struct fb_shell_stress_state {
  double strain[3];                             /* mid-surface eps_x, eps_y, gamma_xy (-) */
  double curvature[3];                          /* kappa_x, kappa_y, kappa_xy (1/m) */
  double force[3];                              /* membrane resultants N_x, N_y, N_xy (N/m) */
  double moment[3];                             /* bending moments M_x, M_y, M_xy (N m / m) */
  double top[3];                                /* sigma_x, sigma_y, tau_xy at z = +t/2 (Pa) */
  double bottom[3];                             /* the same at z = -t/2 (Pa) */
  double principal_top[2], principal_bottom[2]; /* in-plane, larger first (Pa) */
  double von_mises_top, von_mises_bottom;       /* plane stress (Pa) */
  double von_mises_max;                         /* the larger of the two (Pa) */
} fb_shell_stress_state;

/* Stress recovery of a mesh, built once, applied many times: per element
 * its axes, thickness, elasticity and the recovery matrix from its 6 nn
 * global DOFs to its surface stresses; optionally stress modes. */
typedef struct fb_shell_stress fb_shell_stress;

/* Builds the recovery of mesh m (borrowed: must outlive *out, and not
 * change) with each element's fb_mesh_element_props(m, e, p). An element
 * that is degenerate or warped beyond the element's limit: FB_EINVAL
 * prefixed "element <id>: " (as fb_fem_assemble); FB_ENOMEM. */
int fb_shell_stress_new(const fb_mesh *m, const fb_shell_props *p, fb_shell_stress **out,
                        fb_err *err);
/* Accepts NULL and sets *s to NULL. */
void fb_shell_stress_free(fb_shell_stress **s);
size_t fb_shell_stress_nelements(const fb_shell_stress *s);
/* Element e's local axes: 9 values, rows x, y, z in global components. */
const double *fb_shell_stress_axes(const fb_shell_stress *s, size_t e);
/* Element e's recovery matrix D_e (borrowed): its surface stresses
 * (sigma_x, sigma_y, tau_xy at the top, then the bottom's, local axes)
 * per unit nodal DOF, 6 x 6 nn row-major, the columns the 6 DOFs of each
 * of its nn nodes in fb_mesh_element_nodes' order (global axes): what
 * fb_shell_stress_eval_nodal applies, for a caller that reads one
 * component as weights over the nodal DOFs. */
const double *fb_shell_stress_recovery(const fb_shell_stress *s, size_t e);

/* The states of every element (states: nelements) from nodal values u
 * (6 nnodes, global axes, fem.h's DOF order; borrowed). */
void fb_shell_stress_eval_nodal(const fb_shell_stress *s, const double *u,
                                fb_shell_stress_state *states);

/* Stress modes (modal stress recovery): for the basis phi (6 nnodes x
 * nmodes, column-major; read, not kept) each element's surface stresses
 * of each mode, S_e (6 x nmodes: sigma_x, sigma_y, tau_xy at the top,
 * then the bottom), computed once, so that the stresses of u = phi q are
 * S_e q. Replaces earlier stress modes. FB_EINVAL for nmodes 0 or ndof
 * other than 6 nnodes, FB_ENOMEM. */
int fb_shell_stress_modes(fb_shell_stress *s, const double *phi, size_t ndof, size_t nmodes,
                          fb_err *err);
/* The number of stress modes (0 before fb_shell_stress_modes). */
size_t fb_shell_stress_nmodes(const fb_shell_stress *s);
/* S_e, 6 x nmodes row-major (borrowed; NULL before fb_shell_stress_modes).
 * The elements' follow one another: element 0's is the 6 nelements x
 * nmodes row-major matrix of them all (for a product over many q). */
const double *fb_shell_stress_mode_matrix(const fb_shell_stress *s, size_t e);
/* The states of every element for modal coordinates q (nmodes): S_e q,
 * then the same derived values as fb_shell_stress_eval_nodal. FB_EINVAL
 * before fb_shell_stress_modes. */
int fb_shell_stress_eval_modal(const fb_shell_stress *s, const double *q,
                               fb_shell_stress_state *states, fb_err *err);

/* The state of an element of thickness t and material (young, poisson)
 * whose surface stresses are top and bottom (3 each, local axes): the
 * strains, resultants, principal stresses and von Mises stresses
 * sqrt(s1^2 - s1 s2 + s2^2) that follow. */
void fb_shell_stress_state_from_surfaces(const double *top, const double *bottom, double t,
                                         double young, double poisson,
                                         fb_shell_stress_state *st);

/* ---- Mesh exchange. */

/* Abaqus/CalculiX input deck: *NODE, *ELEMENT TYPE=S3 and TYPE=S4,
 * *NSET and *ELSET for every set, and for each group of elements with the
 * same properties (one section and one added non-structural mass; with
 * p for the elements without a section, which are left out when p is
 * NULL) a *MATERIAL (*ELASTIC, *DENSITY, the non-structural mass smeared
 * into it: CalculiX has no *NONSTRUCTURAL MASS) and a *SHELL SECTION over
 * its element set: the section's own when it has exactly the group's
 * elements, else EALL (every element) or a new SECTION_<k>
 * (SECTION_<k>_<j> for a section's later groups); then each point mass
 * as *ELEMENT, TYPE=MASS, ELSET=PMASS_<id> and *MASS over that set.
 * Written atomically. */
int fb_mesh_write_inp(const fb_mesh *m, const fb_shell_props *p, const char *path, fb_err *err);
/* The deck's text into fp (p finite, or NULL for none); coordinates to 15
 * significant digits, those below 1e-12 of the largest as 0. */
void fb_mesh_print_inp(FILE *fp, const fb_mesh *m, const fb_shell_props *p);
/* Reads such a deck (keywords case-insensitive, comments "**", GENERATE
 * sets, sets that name the sets before them, each member kept once in
 * memory for the members alone however often the deck names a set; one
 * mesh section per *SHELL SECTION, an element in at most one; MASS
 * elements with *MASS as point masses, *NONSTRUCTURAL MASS as the
 * elements' added non-structural mass: src/fem/inp.c);
 * props, if not NULL, receives the material and thickness of a section
 * that covers every element, or the only material of a deck without
 * sections (fields left untouched otherwise).
 * Errors are "path:line: message" (unknown element type, missing node,
 * malformed numbers, and an element that is degenerate or warped, as
 * fb_mesh_check finds, at its own line). */
int fb_mesh_read_inp(const char *path, fb_mesh **out, fb_shell_props *props, fb_err *err);
/* Same from the len bytes at text, which need not be NUL-terminated:
 * errors are "display_name:line: message" (display_name NULL:
 * "<string>"), and a NUL or other control byte (tab aside) anywhere in
 * the text is FB_EPARSE "binary data (byte 0x00 in column c)" at its
 * line; no byte past len is read. *out is NULL on failure. */
int fb_mesh_read_inp_string(const char *text, size_t len, const char *display_name,
                            fb_mesh **out, fb_shell_props *props, fb_err *err);
/* A gmsh mesh: MSH format 4.1, ASCII (src/fem/msh.c). Its 3-node
 * triangles and 4-node quadrilaterals are the elements (tags as ids);
 * every named physical group is a node set of its elements' nodes, and a
 * surface group also an element set. Other element types of a surface
 * (second order), binary files and other versions are FB_EPARSE
 * "path:line: message"; *out is NULL on failure. */
int fb_mesh_read_msh(const char *path, fb_mesh **out, fb_err *err);
/* The same from len bytes at text (not NUL-terminated). */
int fb_mesh_read_msh_string(const char *text, size_t len, const char *display_name,
                            fb_mesh **out, fb_err *err);
/* A .msh file (by its name, any case) with fb_mesh_read_msh, anything
 * else as an Abaqus/CalculiX deck (fb_mesh_read_inp, no props). */
int fb_mesh_read_file(const char *path, fb_mesh **out, fb_err *err);

/* VTK XML unstructured grid (.vtu) for ParaView, with an optional nodal
 * displacement field (6 per node; translations as a vector "displacement",
 * rotations as "rotation") and the node sets as point data flags. */
int fb_mesh_write_vtu(const fb_mesh *m, const double *dof_values, const char *path,
                      fb_err *err);
/* A named value of a whole grid (a mode's frequency), as VTK FieldData. */
typedef struct fb_vtu_field {
  const char *name;
  double value;
} fb_vtu_field;
/* A point drawn beside the mesh in an animation's frame (a mounted body,
 * a wheel): where it is at rest (m), its vertical displacement (m) and
 * the part it belongs to (> 0; the mesh's nodes are part 0). */
typedef struct fb_vtu_marker {
  double xyz[3];
  double dz;
  int part;
} fb_vtu_marker;
/* A value per element of the mesh (a stress), as VTK CellData: name,
 * and nelements values (finite; borrowed). A frame's markers get 0. */
typedef struct fb_vtu_cell_array {
  const char *name;
  const double *values;
} fb_vtu_cell_array;
/* One grid of an animation (or a mode): the mesh's nodal displacements
 * (6 per node as in fb_mesh_write_vtu, or NULL), the points drawn at
 * origin + X + warp u (warp 0: at rest, as fb_mesh_write_vtu), markers,
 * cell arrays and field data. origin (m) is where the mesh's origin lies in the frame
 * the file is written in (a vehicle's: fb_scenario_frame_offset); the
 * markers' positions are the mesh's. */
typedef struct fb_vtu_frame {
  const double *dof_values;
  double warp;
  const fb_vtu_marker *markers;
  size_t nmarkers;
  const fb_vtu_field *fields;
  size_t nfields;
  double origin[3];
  const fb_vtu_cell_array *cell_arrays;
  size_t ncell_arrays;
} fb_vtu_frame;
int fb_mesh_write_vtu_frame(const fb_mesh *m, const fb_vtu_frame *f, const char *path,
                            fb_err *err);
/* fb_mesh_write_vtu with nfields values of the grid (finite, named). */
int fb_mesh_write_vtu_fields(const fb_mesh *m, const double *dof_values,
                             const fb_vtu_field *fields, size_t nfields, const char *path,
                             fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
