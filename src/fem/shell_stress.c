/* SPDX-License-Identifier: BSD-3-Clause */
/* Stresses and strains of the flat shell elements (flexbond/fem.h): the
 * recovery of each element's centre state from its nodal displacements,
 * and modal stress recovery.
 *
 * Recovery: an element's generalised strains (eps0, kappa) at its centre
 * are G W T u_e, with T the rotation of its 6 nn global DOFs to local axes
 * and W the rigid links of a warped quadrilateral, both as in shell.c, and
 * G the strain-displacement rows its stiffness integrates (membrane:
 * fb_shell_membrane_strain, bending: fb_shell_bending_curvature), so the
 * recovered state is the one whose energy the stiffness stores. The
 * surface stresses follow from the Kirchhoff plate's linear strain through
 * the thickness, sigma(+-t/2) = C (eps0 +- t kappa / 2) (R. D. Cook, D. S.
 * Malkus, M. E. Plesha & R. J. Witt, "Concepts and Applications of Finite
 * Element Analysis", 4th ed., 2002, the chapters on plates and shells:
 * sigma = N / t +- 6 M / t^2). The six surface stresses of an element are
 * linear in u: D_e (6 x 6 nn) is formed once per element.
 *
 * Stress modes: the surface stresses of each column of a modal basis Phi,
 * S_e = D_e Phi_e, formed once, so that a response u = Phi q has the
 * stresses S_e q (modal stress recovery, as Adams/Flex's "modal stress"
 * and MSC Nastran's stress modes: the linear stress components superpose
 * over the modes; von Mises and principal stresses do not, and are formed
 * from the superposed components; R. R. Craig & A. J. Kurdila,
 * "Fundamentals of Structural Dynamics", 2nd ed., 2006, ch. 11 on mode
 * superposition of responses). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fem/shell_internal.h"

/* Components of an element's surface stresses: top x, y, xy, bottom x, y, xy. */
#define NSURF 6
/* Columns of the largest element's recovery matrix. */
#define MAX_DOF (6 * FB_SHELL_MAX_NODES)

typedef struct stress_element {
  double axes[9];
  double d[NSURF * MAX_DOF]; /* D_e, NSURF x 6 nn row-major */
  double thickness, young, poisson;
} stress_element;

struct fb_shell_stress {
  const fb_mesh *mesh; /* borrowed */
  size_t nelements;
  stress_element *elements; /* owned */
  size_t nmodes;
  double *modes; /* owned: S_e of every element, NSURF x nmodes row-major each */
};

/* Generalised strains (eps0: 3 rows, kappa: 3 rows) per unit local DOF
 * (u v w rx ry rz of each node, at the nodes' projections): g, 6 x 6 nn
 * row-major. */
static void local_strains(const fb_shell_frame *f, double *g)
{
  static const size_t membrane_dof[3] = {0, 1, 5}, bending_dof[3] = {2, 3, 4};
  const size_t nn = f->nn, n = 6 * nn, nsub = 3 * nn;
  double bm[3 * 3 * FB_SHELL_MAX_NODES], bb[3 * 3 * FB_SHELL_MAX_NODES];
  fb_shell_membrane_strain(nn, f->x, f->y, f->area, bm);
  fb_shell_bending_curvature(nn, f->x, f->y, bb);
  memset(g, 0, 6 * n * sizeof *g);
  for (size_t r = 0; r < 3; ++r)
    for (size_t c = 0; c < nsub; ++c) {
      g[r * n + 6 * (c / 3) + membrane_dof[c % 3]] = bm[r * nsub + c];
      g[(3 + r) * n + 6 * (c / 3) + bending_dof[c % 3]] = bb[r * nsub + c];
    }
}

/* g (6 x 6 nn) = g W T: the rigid links u_p = u - h ry, v_p = v + h rx of
 * shell.c (columns ry and rx gain -h and +h times columns u and v), then
 * each node's translations and rotations from global axes (local = R
 * global, so a 3-column block becomes block R). */
static void to_global_dofs(const fb_shell_frame *f, double *g)
{
  const size_t n = 6 * f->nn;
  for (size_t a = 0; a < f->nn; ++a) {
    const size_t u = 6 * a;
    for (size_t r = 0; r < 6; ++r) {
      g[r * n + u + 4] -= f->h[a] * g[r * n + u];
      g[r * n + u + 3] += f->h[a] * g[r * n + u + 1];
    }
  }
  for (size_t r = 0; r < 6; ++r)
    for (size_t b = 0; b < n; b += 3) {
      double out[3];
      for (size_t c = 0; c < 3; ++c) {
        out[c] = 0.0;
        for (size_t q = 0; q < 3; ++q)
          out[c] += g[r * n + b + q] * f->rot[q * 3 + c];
      }
      memcpy(g + r * n + b, out, sizeof out);
    }
}

/* D_e from the element's frame and properties. */
static void element_recovery(const fb_shell_frame *f, const fb_shell_props *p, double *d)
{
  const size_t n = 6 * f->nn;
  double g[6 * MAX_DOF], c[9];
  local_strains(f, g);
  to_global_dofs(f, g);
  fb_shell_plane_stress(p->young, p->poisson, 1.0, c);
  const double half = p->thickness / 2.0;
  for (size_t side = 0; side < 2; ++side) {
    const double z = side == 0 ? half : -half;
    for (size_t r = 0; r < 3; ++r)
      for (size_t j = 0; j < n; ++j) {
        double s = 0.0;
        for (size_t q = 0; q < 3; ++q)
          s += c[r * 3 + q] * (g[q * n + j] + z * g[(3 + q) * n + j]);
        d[(3 * side + r) * n + j] = s;
      }
  }
}

int fb_shell_stress_new(const fb_mesh *m, const fb_shell_props *p, fb_shell_stress **out,
                        fb_err *err)
{
  *out = NULL;
  const size_t ne = fb_mesh_nelements(m);
  fb_shell_stress *s = calloc(1, sizeof *s);
  stress_element *el = ne ? malloc(ne * sizeof *el) : NULL;
  if (!s || (ne && !el)) {
    free(s);
    free(el);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  s->mesh = m;
  s->nelements = ne;
  s->elements = el;
  for (size_t e = 0; e < ne; ++e) {
    const size_t *nodes = fb_mesh_element_nodes(m, e);
    const fb_elem_type type = fb_mesh_element_type(m, e);
    const fb_shell_props props = fb_mesh_element_props(m, e, p);
    double xyz[3 * FB_SHELL_MAX_NODES];
    fb_shell_frame f;
    for (size_t a = 0; a < (size_t)type; ++a)
      memcpy(xyz + 3 * a, fb_mesh_node_xyz(m, nodes[a]), 3 * sizeof *xyz);
    int rc = fb_shell_check_props(&props, err);
    if (!rc)
      rc = fb_shell_frame_make(type, xyz, &f, err);
    if (rc) {
      fb_err_prefix(err, "element %ld: ", fb_mesh_element_id(m, e));
      fb_shell_stress_free(&s);
      return rc;
    }
    memcpy(el[e].axes, f.rot, sizeof f.rot);
    el[e].thickness = props.thickness;
    el[e].young = props.young;
    el[e].poisson = props.poisson;
    element_recovery(&f, &props, el[e].d);
  }
  *out = s;
  return FB_OK;
}

void fb_shell_stress_free(fb_shell_stress **s)
{
  if (!s || !*s)
    return;
  free((*s)->elements);
  free((*s)->modes);
  free(*s);
  *s = NULL;
}

size_t fb_shell_stress_nelements(const fb_shell_stress *s)
{
  return s->nelements;
}

const double *fb_shell_stress_axes(const fb_shell_stress *s, size_t e)
{
  return s->elements[e].axes;
}

const double *fb_shell_stress_recovery(const fb_shell_stress *s, size_t e)
{
  return s->elements[e].d;
}

void fb_shell_stress_state_from_surfaces(const double *top, const double *bottom, double t,
                                         double young, double poisson,
                                         fb_shell_stress_state *st)
{
  memcpy(st->top, top, 3 * sizeof *top);
  memcpy(st->bottom, bottom, 3 * sizeof *bottom);
  for (int k = 0; k < 3; ++k) {
    const double mean = (top[k] + bottom[k]) / 2.0, diff = top[k] - bottom[k];
    st->force[k] = t * mean;             /* N = integral of sigma dz */
    st->moment[k] = t * t * diff / 12.0; /* M = integral of sigma z dz */
  }
  /* Plane-stress compliance: eps = (sx - nu sy) / E, ..., gamma = 2 (1 +
   * nu) tau / E; the mid-surface strain from the mean stress, the
   * curvature from the gradient (top - bottom) / t. */
  const double mx = (top[0] + bottom[0]) / 2.0, my = (top[1] + bottom[1]) / 2.0;
  const double mxy = (top[2] + bottom[2]) / 2.0;
  const double gx = (top[0] - bottom[0]) / t, gy = (top[1] - bottom[1]) / t;
  const double gxy = (top[2] - bottom[2]) / t;
  st->strain[0] = (mx - poisson * my) / young;
  st->strain[1] = (my - poisson * mx) / young;
  st->strain[2] = 2.0 * (1.0 + poisson) * mxy / young;
  st->curvature[0] = (gx - poisson * gy) / young;
  st->curvature[1] = (gy - poisson * gx) / young;
  st->curvature[2] = 2.0 * (1.0 + poisson) * gxy / young;
  const double *surf[2] = {top, bottom};
  double *principal[2] = {st->principal_top, st->principal_bottom};
  double vm[2];
  for (int k = 0; k < 2; ++k) {
    const double sx = surf[k][0], sy = surf[k][1], txy = surf[k][2];
    const double centre = (sx + sy) / 2.0, radius = hypot((sx - sy) / 2.0, txy);
    principal[k][0] = centre + radius;
    principal[k][1] = centre - radius;
    /* Plane-stress von Mises, sqrt(s1^2 - s1 s2 + s2^2) written in the
     * components so that it stays >= 0 under round-off. */
    vm[k] = sqrt(fmax(sx * sx - sx * sy + sy * sy + 3.0 * txy * txy, 0.0));
  }
  st->von_mises_top = vm[0];
  st->von_mises_bottom = vm[1];
  st->von_mises_max = fmax(vm[0], vm[1]);
}

static void finish(const stress_element *el, const double *surf, fb_shell_stress_state *st)
{
  fb_shell_stress_state_from_surfaces(surf, surf + 3, el->thickness, el->young, el->poisson,
                                      st);
}

void fb_shell_stress_eval_nodal(const fb_shell_stress *s, const double *u,
                                fb_shell_stress_state *states)
{
  for (size_t e = 0; e < s->nelements; ++e) {
    const stress_element *el = s->elements + e;
    const size_t *nodes = fb_mesh_element_nodes(s->mesh, e);
    const size_t nn = (size_t)fb_mesh_element_type(s->mesh, e), n = 6 * nn;
    double surf[NSURF];
    for (size_t r = 0; r < NSURF; ++r) {
      double sum = 0.0;
      for (size_t j = 0; j < n; ++j)
        sum += el->d[r * n + j] * u[6 * nodes[j / 6] + j % 6];
      surf[r] = sum;
    }
    finish(el, surf, states + e);
  }
}

int fb_shell_stress_modes(fb_shell_stress *s, const double *phi, size_t ndof, size_t nmodes,
                          fb_err *err)
{
  const size_t nnodes = fb_mesh_nnodes(s->mesh);
  if (nmodes == 0 || ndof != 6 * nnodes)
    return fb_err_set(err, FB_EINVAL,
                      "stress modes: %zu modes of %zu DOFs for a mesh of %zu DOFs", nmodes,
                      ndof, 6 * nnodes);
  if (s->nelements > (size_t)-1 / sizeof(double) / NSURF / nmodes)
    return fb_err_set(err, FB_ENOMEM, "stress modes: out of memory");
  double *modes = malloc(s->nelements * NSURF * nmodes * sizeof *modes);
  if (!modes && s->nelements)
    return fb_err_set(err, FB_ENOMEM, "stress modes: out of memory");
  for (size_t e = 0; e < s->nelements; ++e) {
    const stress_element *el = s->elements + e;
    const size_t *nodes = fb_mesh_element_nodes(s->mesh, e);
    const size_t n = 6 * (size_t)fb_mesh_element_type(s->mesh, e);
    double *se = modes + e * NSURF * nmodes;
    for (size_t k = 0; k < nmodes; ++k) {
      const double *col = phi + k * ndof;
      for (size_t r = 0; r < NSURF; ++r) {
        double sum = 0.0;
        for (size_t j = 0; j < n; ++j)
          sum += el->d[r * n + j] * col[6 * nodes[j / 6] + j % 6];
        se[r * nmodes + k] = sum;
      }
    }
  }
  free(s->modes);
  s->modes = modes;
  s->nmodes = nmodes;
  return FB_OK;
}

size_t fb_shell_stress_nmodes(const fb_shell_stress *s)
{
  return s->nmodes;
}

const double *fb_shell_stress_mode_matrix(const fb_shell_stress *s, size_t e)
{
  return s->modes ? s->modes + e * NSURF * s->nmodes : NULL;
}

int fb_shell_stress_eval_modal(const fb_shell_stress *s, const double *q,
                               fb_shell_stress_state *states, fb_err *err)
{
  if (!s->modes)
    return fb_err_set(err, FB_EINVAL, "stress modes: none computed");
  for (size_t e = 0; e < s->nelements; ++e) {
    const double *se = s->modes + e * NSURF * s->nmodes;
    double surf[NSURF];
    for (size_t r = 0; r < NSURF; ++r) {
      double sum = 0.0;
      for (size_t k = 0; k < s->nmodes; ++k)
        sum += se[r * s->nmodes + k] * q[k];
      surf[r] = sum;
    }
    finish(s->elements + e, surf, states + e);
  }
  return FB_OK;
}
