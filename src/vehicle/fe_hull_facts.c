/* SPDX-License-Identifier: BSD-3-Clause */
/* What a finite-element hull is (flexbond/vehicle.h): its mass properties
 * and its sections' totals, computed once for the command's `mesh` and
 * the Python package. */
#include <math.h>

#include "flexbond/vehicle.h"

int fb_fe_hull_mass_props(const fb_fe_hull *h, int with_masses, fb_hull_mass_props *out,
                          fb_err *err)
{
  fb_mat *M = NULL;
  int rc = with_masses ? fb_fe_hull_mass_matrix(h, &M, err)
                       : fb_fem_assemble(h->mesh, &h->props, h->mass_kind, NULL, &M, err);
  if (rc == FB_OK)
    rc = fb_fem_mass_properties(h->mesh, M, &out->mass, out->cg, out->inertia, err);
  fb_mat_free(&M);
  return rc;
}

int fb_fe_hull_matrices(const fb_fe_hull *h, fb_mat **K, fb_mat **M, fb_err *err)
{
  return fb_fem_assemble(h->mesh, &h->props, h->mass_kind, K, M, err);
}

const fb_mesh *fb_fe_hull_mesh(const fb_fe_hull *h)
{
  return h->mesh;
}

size_t fb_fe_hull_npoint_masses(const fb_fe_hull *h)
{
  return h->npoint_masses;
}

/* Area of element e (its projected area if it is warped). */
static double element_area(const fb_mesh *m, size_t e)
{
  double v[3];
  fb_mesh_element_area_vector(m, e, v);
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

fb_hull_section_totals fb_fe_hull_section_totals(const fb_fe_hull *h, long sec)
{
  fb_hull_section_totals t = {0, 0.0, 0.0};
  for (size_t e = 0; e < fb_mesh_nelements(h->mesh); ++e)
    if (fb_mesh_element_section(h->mesh, e) == sec) {
      ++t.nelements;
      t.area += element_area(h->mesh, e);
    }
  const fb_shell_props *p = sec >= 0 ? fb_mesh_section_props(h->mesh, (size_t)sec) : &h->props;
  if (t.nelements && p)
    t.mass = (p->density * p->thickness + p->nonstructural_mass) * t.area;
  return t;
}
