/* SPDX-License-Identifier: BSD-3-Clause */
/* The built-in generator as a hull source (flexbond/hull_source.h): the
 * paper's hull made from the description's points and its hull_mesh
 * parameters (fb_hull_mesh_generate, hull_mesh.c), refined by their
 * density. */
#include <stdio.h>

#include "flexbond/hull_source.h"

#include "vehicle/vehicle_internal.h"

/* The rules between the geometry's values; the generator checks the
 * geometry against the points itself, when it builds the mesh. */
static int generator_check(const fb_scenario *s, fb_err *err)
{
  const fb_hull_mesh_params *g = &s->hull_mesh;
  if (!(g->x_front > g->x_rear))
    return fb_err_set(err, FB_EINVAL, "must be > the rear wall's x_rear = %.10g m (got %.10g)",
                      g->x_rear, g->x_front),
           fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_mesh.x_front)), FB_EINVAL;
  if (!(g->nose_height < g->height))
    return fb_err_set(err, FB_EINVAL, "must be < the hull's height = %.10g m (got %.10g)",
                      g->height, g->nose_height),
           fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_mesh.nose_height)),
           FB_EINVAL;
  for (size_t k = 0; k < g->nbulkheads; ++k)
    if (!(g->bulkhead_x[k] > g->x_rear && g->bulkhead_x[k] < g->x_front))
      return fb_err_set(err, FB_EINVAL, "must lie between x_rear and x_front (got %.10g m)",
                        g->bulkhead_x[k]),
             fb_err_set_part(err, FB_PART_ELEMENT(FB_PART_VEHICLE, 0, hull_mesh.bulkhead_x, k)),
             FB_EINVAL;
  return FB_OK;
}

static int generator_make(const fb_scenario *s, fb_mesh **out, fb_err *err)
{
  return fb_hull_mesh_generate(s, &s->hull_mesh, out, err);
}

static uint64_t generator_key(const fb_scenario *s)
{
  return fb_hull_mesh_key(s, &s->hull_mesh);
}

/* Its plates are symmetric about y = 0: x and the height above the
 * floor. */
static void generator_centroid(const fb_scenario *s, double *x, double *z, double *length)
{
  fb_hull_mesh_centroid(s, &s->hull_mesh, x, z);
  *length = s->hull_mesh.x_front + s->hull_mesh.nose_length - s->hull_mesh.x_rear;
}

static int generator_density(const fb_scenario *s)
{
  return s->hull_mesh.density;
}

static void generator_describe(const fb_scenario *s, char *buf, size_t n)
{
  snprintf(buf, n, "the built-in generator at density %d", s->hull_mesh.density);
}

static const fb_hull_source_ops generator_ops = {.check = generator_check,
                                                 .make = generator_make,
                                                 .key = generator_key,
                                                 .centroid = generator_centroid,
                                                 .density = generator_density,
                                                 .describe = generator_describe};

const fb_hull_source fb_hull_source_generator = {
    .name = "generator",
    .doc = "the paper's hull (floor, roof, walls, bulkheads, a wedge nose) from its geometry "
           "and the vehicle's points (docs/hull-mesh.md)",
    .ops = &generator_ops,
    /* fb_hull_mesh_generate puts a line of nodes through every point. */
    .nodes_at_points = 1};
