/* SPDX-License-Identifier: BSD-3-Clause */
/* An output read from a surface stress of System 2's shell hull
 * (vehicle_internal.h, docs/stresses.md "Stress outputs"): the element
 * it reads, by its id or as the element nearest a point (the nearest-
 * element search of a hull point's output, hull_point.c), and its
 * component's row of the element's recovery matrix D_e as weights over
 * the nodal DOFs. A surface stress component is linear in the nodal
 * displacements, so the hull reads it as it reads a torsion: a weighted
 * probe of its stiffness field's state, a pattern of its modal basis. */
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "vehicle/vehicle_internal.h"

int vehicle_hull_stress_element(const fb_mesh *m, const fb_output_spec *o, size_t index,
                                size_t *e, fb_err *err)
{
  *e = 0;
  const size_t n = fb_mesh_nelements(m);
  if (n == 0)
    return fb_err_set(err, FB_EINVAL,
                      "the hull is a superelement: it has no shell elements, whose stresses a "
                      "%s signal reads",
                      o->signal),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, signal)), FB_EINVAL;
  if (o->element) {
    const long found = fb_mesh_find_element_id(m, o->element);
    long lo = 0, hi = 0;
    for (size_t k = 0; found < 0 && k < n; ++k) {
      const long id = fb_mesh_element_id(m, k);
      lo = k && lo < id ? lo : id;
      hi = k && hi > id ? hi : id;
    }
    if (found < 0)
      return fb_err_set(err, FB_EINVAL,
                        "the hull's mesh has no element %ld (its %zu elements' ids are %ld to "
                        "%ld)",
                        o->element, n, lo, hi),
             fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, element)), FB_EINVAL;
    *e = (size_t)found;
    return FB_OK;
  }
  double shape[4], foot[3];
  return vehicle_hull_point_on(m, o, index, e, shape, foot, err);
}

int vehicle_hull_stress_weights(const fb_mesh *m, const fb_shell_props *props,
                                const fb_output_spec *o, size_t index, double *w, fb_err *err)
{
  size_t e = 0;
  int rc = vehicle_hull_stress_element(m, o, index, &e, err);
  fb_shell_stress *recovery = NULL;
  if (!rc)
    rc = fb_shell_stress_new(m, props, &recovery, err);
  if (rc)
    return rc;
  /* D_e's row of the surface's component: top rows 0..2, bottom 3..5,
   * over the element's nodes' 6 DOFs each. */
  const double *d = fb_shell_stress_recovery(recovery, e);
  const size_t *nodes = fb_mesh_element_nodes(m, e);
  const size_t nn = fb_mesh_element_type(m, e) == FB_ELEM_QUAD4 ? 4 : 3;
  const size_t row = 3 * (size_t)o->surface + (size_t)o->stress, ncols = 6 * nn;
  memset(w, 0, 6 * fb_mesh_nnodes(m) * sizeof *w);
  for (size_t a = 0; a < nn; ++a)
    for (size_t j = 0; j < 6; ++j)
      w[6 * nodes[a] + j] += d[row * ncols + 6 * a + j];
  fb_shell_stress_free(&recovery);
  return FB_OK;
}
