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

/* Each element's mass from its own properties: a deck's non-structural
 * mass may differ from element to element of a section. */
fb_hull_section_totals fb_fe_hull_section_totals(const fb_fe_hull *h, long sec)
{
  fb_hull_section_totals t = {0, 0.0, 0.0};
  for (size_t e = 0; e < fb_mesh_nelements(h->mesh); ++e)
    if (fb_mesh_element_section(h->mesh, e) == sec) {
      const fb_shell_props p = fb_mesh_element_props(h->mesh, e, &h->props);
      const double area = element_area(h->mesh, e);
      ++t.nelements;
      t.area += area;
      t.mass += (p.density * p.thickness + p.nonstructural_mass) * area;
    }
  return t;
}

/* The declared masses take the ids after every element's and point
 * mass's, so that they clash with none. */
int fb_fe_hull_mesh_as_built(const fb_fe_hull *h, fb_mesh **out, fb_err *err)
{
  int rc = fb_mesh_clone(h->mesh, out, err);
  long id = 0;
  for (size_t e = 0; !rc && e < fb_mesh_nelements(*out); ++e)
    id = fb_mesh_element_id(*out, e) > id ? fb_mesh_element_id(*out, e) : id;
  for (size_t i = 0; !rc && i < fb_mesh_npoint_masses(*out); ++i)
    id = fb_mesh_point_mass_id(*out, i) > id ? fb_mesh_point_mass_id(*out, i) : id;
  for (size_t k = 0; !rc && k < h->npoint_masses; ++k)
    rc = fb_mesh_add_point_mass(*out, id + 1 + (long)k, h->point_mass_node[k], h->point_mass[k],
                                err);
  if (rc)
    fb_mesh_free(out);
  return rc;
}
