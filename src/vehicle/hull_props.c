/* SPDX-License-Identifier: BSD-3-Clause */
/* One hull for both systems (flexbond/vehicle.h, fb_vehicle_hull_complete):
 * with a finite-element hull, System 1's mass, inertias and centre of
 * mass come from the same mesh as System 2's, so the two systems compare
 * like with like; positions given in a declared vehicle frame are moved
 * to the hull's centre of mass, the frame of every fragment. */
#include <math.h>
#include <stdio.h>

#include "flexbond/hull_source.h"
#include "flexbond/vehicle.h"

#include "vehicle/vehicle_internal.h"

/* Largest relative gap between a typed rigid-body property and the mesh's
 * before the file is refused: the data sheet's values and the fitted
 * default mesh agree within 6e-6; 0.5 % is far above that round-off of a
 * fit and far below what a changed hull (a thicker plate, another
 * material, a bulkhead more) makes, which is what must not pass silently. */
#define PROPERTY_TOLERANCE 0.005

/* The structure's rigid-body properties: mass (kg), centre of mass (m)
 * and inertia tensor about it (kg m^2, row-major). */
typedef struct mesh_props {
  double mass, cg[3], inertia[9];
} mesh_props;

/* The hull's mesh, as System 2 builds it (fe_hull.c: the loaded mesh with
 * its sections and node sets), and its bare (structural) properties,
 * summed element by element: the declared hull masses are not the
 * structure's (hull.mass, Ixx and Iyy are the structure's alone), and no
 * finite-element matrix is assembled here (the vehicle assembles its
 * once). */
static int mesh_properties(const fb_scenario *s, mesh_props *mp, fb_err *err)
{
  fb_fe_hull *h = NULL;
  int rc = fb_vehicle_fe_hull(s, &h, err);
  if (!rc)
    rc = fb_fem_mesh_mass_properties(h->mesh, &h->props, h->mass_kind, &mp->mass, mp->cg,
                                     mp->inertia, err);
  fb_fe_hull_free(&h);
  return rc;
}

/* A typed value against the mesh's: FB_EINVAL with both beyond the
 * tolerance. */
static int check_property(const char *field, const char *what, double typed, double mesh,
                          const char *unit, fb_err *err)
{
  if (fabs(typed - mesh) <= PROPERTY_TOLERANCE * fabs(mesh))
    return FB_OK;
  fb_err_set(err, FB_EINVAL,
             "the hull's %s is given as %.6g %s, its finite-element mesh has %.6g %s "
             "(%+.2f %%, more than the %.1f %% allowed): System 1 and System 2 would not "
             "have the same hull. Leave out the hull's mass, Ixx and Iyy to take the mesh's, "
             "or correct them",
             what, typed, unit, mesh, unit, 100.0 * (typed - mesh) / mesh,
             100.0 * PROPERTY_TOLERANCE);
  return fb_err_set_part(err, FB_PART_VEHICLE, 0, FB_ERR_NO_ELEMENT, field), FB_EINVAL;
}

/* A lumped payload's mass, once the hull's is the mesh's: the loader's
 * check (scenario_check.c) could not count it. */
static int check_payload(const fb_scenario *s, fb_err *err)
{
  const double payload = fb_scenario_payload_mass(s);
  if (s->payload != FB_PAYLOAD_LUMPED || payload > 0)
    return FB_OK;
  char masses[64] = "";
  if (s->npoint_masses)
    snprintf(masses, sizeof masses, " + the hull's declared masses (%.10g kg)",
             fb_scenario_point_masses_total(s));
  fb_err_set(err, FB_EINVAL,
             "a lumped payload needs the total weight / gravity (%.10g kg) > the hull's "
             "finite-element mesh (%.10g kg)%s",
             s->total_weight / s->gravity, s->hull_mass, masses);
  return fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, payload)), FB_EINVAL;
}

/* Rigid-body properties from the mesh's, or the typed ones checked
 * against them. Within the tolerance the typed values stand (they are
 * what the mesh was fitted to: the paper's Table 2). */
static int complete_properties(fb_scenario *s, const mesh_props *mp, fb_err *err)
{
  if (!s->hull_izz_given) { /* the tensor's entries are minus the products */
    s->hull_izz = mp->inertia[8];
    s->hull_ixy = -mp->inertia[1];
    s->hull_ixz = -mp->inertia[2];
    s->hull_iyz = -mp->inertia[5];
  }
  if (!s->hull_mass_given) {
    s->hull_mass = mp->mass;
    s->hull_ixx = mp->inertia[0];
    s->hull_iyy = mp->inertia[4];
    return check_payload(s, err);
  }
  int rc = check_property(fb_part_member_(FB_PART_VEHICLE, hull_mass), "mass", s->hull_mass,
                          mp->mass, "kg", err);
  if (!rc)
    rc = check_property(fb_part_member_(FB_PART_VEHICLE, hull_ixx), "roll inertia Ixx",
                        s->hull_ixx, mp->inertia[0], "kg m^2", err);
  if (!rc)
    rc = check_property(fb_part_member_(FB_PART_VEHICLE, hull_iyy), "pitch inertia Iyy",
                        s->hull_iyy, mp->inertia[4], "kg m^2", err);
  return rc;
}

/* Every position of s moved by (-dx, -dy, -dz): the positions in the
 * plane, and the heights of those that have one. */
static void shift_positions(fb_scenario *s, double dx, double dy, double dz)
{
  for (size_t c = 0; c < s->ncorners; ++c) {
    s->corner[c].x -= dx;
    s->corner[c].y -= dy;
  }
  for (size_t b = 0; b < s->nmounts; ++b) {
    s->mount[b].x -= dx;
    s->mount[b].y -= dy;
  }
  for (size_t k = 0; k < s->nload; ++k) {
    s->load_x[k] -= dx;
    s->load_y[k] -= dy;
  }
  for (size_t k = 0; k < s->npoint_masses; ++k) {
    s->point_mass[k].x -= dx;
    s->point_mass[k].y -= dy;
  }
  vehicle_hull_motion how;
  for (size_t o = 0; o < s->noutputs; ++o)
    if (vehicle_output_hull_motion(&s->output[o], &how) && how.coordinate < 0) {
      s->output[o].at[0] -= dx;
      s->output[o].at[1] -= dy;
      s->output[o].at[2] -= dz;
    }
  for (size_t k = 0; k < s->nbogies; ++k)
    s->bogie[k].pivot_x -= dx;
  for (size_t b = 0; b < s->nbodies; ++b) {
    fb_body *body = &s->body[b];
    body->x -= dx;
    body->y -= dy;
    body->z -= dz;
    for (size_t j = 0; j < body->nbushings; ++j) {
      body->bushing[j].x -= dx;
      body->bushing[j].y -= dy;
      body->bushing[j].z -= dz;
    }
  }
  s->edge_front_x -= dx;
  s->edge_rear_x -= dx;
  s->edge_left_y -= dy;
  s->edge_right_y -= dy;
}

/* The hull's centre of mass in the declared frame: the made mesh's (its
 * source's centroid), else the typed one. */
static int frame_centre(const fb_scenario *s, double *x, double *y, double *z, fb_err *err)
{
  *z = 0.0;
  if (s->has_fe_hull) {
    double length = 0.0;
    fb_scenario_hull_source(s)->ops->centroid(s, x, z, &length);
    *y = 0.0;
    if (!s->hull_cg_given)
      return FB_OK;
    /* A height left at its default 0 is the mesh's. */
    if (fabs(s->hull_cg_x - *x) <= PROPERTY_TOLERANCE * length && fabs(s->hull_cg_y) <= 1e-3 &&
        (s->hull_cg_z == 0.0 || fabs(s->hull_cg_z - *z) <= PROPERTY_TOLERANCE * length))
      return FB_OK;
    fb_err_set(err, FB_EINVAL,
               "the hull's centre of mass is given at (%.6g, %.6g, %.6g) m, its generated "
               "mesh's is at (%.6g, 0, %.6g) m (they must agree within %.1f %% of the hull's "
               "%.4g m length): leave it out to take the mesh's",
               s->hull_cg_x, s->hull_cg_y, s->hull_cg_z, *x, *z, 100.0 * PROPERTY_TOLERANCE,
               length);
    return fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_cg_given)), FB_EINVAL;
  }
  if (!s->hull_cg_given) {
    fb_err_set(err, FB_EINVAL,
               "with a declared frame, a hull without a finite-element mesh needs its "
               "centre of mass in that frame");
    return fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, frame_origin)), FB_EINVAL;
  }
  *x = s->hull_cg_x;
  *y = s->hull_cg_y;
  *z = s->hull_cg_z;
  return FB_OK;
}

/* A mesh read from a file (a deck) and the file's positions share the
 * deck's frame: both move to the structure's centre of mass there, the
 * frame of every fragment (System 1's rigid hull turns about it). A deck
 * written by flexbond is centred already (to round-off). The mass and the inertia
 * about the centre of mass (*mp) do not change in the move, which keeps
 * every node set on its point. */
static int centre_deck(fb_scenario *s, mesh_props *mp, fb_err *err)
{
  if (s->hull_cg_given) {
    fb_err_set(err, FB_EINVAL,
               "a hull deck's centre of mass is its mesh's: leave the hull's out");
    return fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_cg_given)), FB_EINVAL;
  }
  const int rc = mesh_properties(s, mp, err);
  if (rc)
    return rc;
  const double *cg = mp->cg;
  fb_mesh_translate(s->hull_source_mesh, -cg[0], -cg[1], -cg[2]);
  s->hull_cg_x = cg[0];
  s->hull_cg_y = cg[1];
  s->hull_cg_z = cg[2];
  shift_positions(s, cg[0], cg[1], cg[2]);
  return FB_OK;
}

int fb_vehicle_hull_complete(fb_scenario *s, fb_err *err)
{
  int rc = FB_OK;
  mesh_props mp = {0};
  /* A source that reads its mesh has it in a frame of its own; one that
   * makes it knows where its centre of mass will be. */
  const fb_hull_source *src = fb_scenario_hull_source(s);
  const int made = src->ops->make != NULL;
  if (s->has_fe_hull && !made) {
    rc = centre_deck(s, &mp, err);
    if (rc)
      return rc;
  } else if (s->frame_origin) {
    double x = 0.0, y = 0.0, z = 0.0;
    rc = frame_centre(s, &x, &y, &z, err);
    if (rc)
      return rc;
    s->hull_cg_x = x;
    s->hull_cg_y = y;
    s->hull_cg_z = z;
    shift_positions(s, x, y, z);
  }
  if (s->has_fe_hull) {
    /* A source that makes its mesh makes it here, once, where the
     * positions are final: the vehicle copies it. */
    if (made && !vehicle_source_mesh_current(s)) {
      fb_mesh_free(&s->hull_source_mesh);
      rc = src->ops->make(s, &s->hull_source_mesh, err);
      s->hull_source_key = src->ops->key(s);
    }
    if (!rc && made)
      rc = mesh_properties(s, &mp, err);
    if (!rc)
      rc = complete_properties(s, &mp, err);
  } else if (!s->hull_mass_given) {
    fb_err_set(err, FB_EINVAL,
               "a hull without a finite-element model needs its mass, Ixx and Iyy");
    fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_mass_given));
    rc = FB_EINVAL;
  }
  return rc;
}

void fb_scenario_frame_offset(const fb_scenario *s, double o[3])
{
  o[0] = s->hull_cg_x;
  o[1] = s->hull_cg_y;
  o[2] = s->hull_cg_z;
}
