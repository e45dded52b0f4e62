/* SPDX-License-Identifier: BSD-3-Clause */
/* The signals a vehicle's outputs may name (docs/vehicle-outputs.md), and the
 * probes that measure them on the assembled graph (flexbond/vehicle.h).
 *
 * Each kind is one row: its subject, its unit and its default name,
 * title and label. How it is measured is its subject's to say: a corner's
 * or a mount's fragment declares the probe of each signal it offers on
 * its own bonds and elements (fragments.c), the hull its torsion
 * (fb_hull), and a bond signal is a probe on the bond named. A new
 * corner signal is one row here, one in the corner's declaration and one
 * line in docs/vehicle-outputs.md. */
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* How a bond signal is measured: the probe on the output's bond,
 * integrated for a displacement or a momentum. A corner's or a mount's
 * signal is its fragment's to measure (vehicle_fragment_signal); the
 * hull's torsion the hull's (fb_hull.torsion_*). */
typedef struct bond_probe {
  const char *signal;
  fb_probe_kind kind;
  int integrate;
} bond_probe;

static const bond_probe bond_probes[] = {
    {"effort", FB_PROBE_EFFORT, 0},   {"flow", FB_PROBE_FLOW, 0},
    {"power", FB_PROBE_POWER, 0},     {"displacement", FB_PROBE_FLOW, 1},
    {"momentum", FB_PROBE_EFFORT, 1},
};

/* Sign conventions are the fragments': compressions and forces pushing
 * the parts apart positive; powers positive into the dissipating element. */
static const fb_output_kind kinds[] = {
    {"tire_force", FB_OUTPUT_OF_CORNER, "N", "tire_force_%s",
     "Normal reaction of the %s tire on the road", "%s tire normal reaction",
     "normal reaction of the tire on the road, compression positive"},
    {"tire_defl", FB_OUTPUT_OF_CORNER, "m", "tire_defl_%s", "%s tire vertical deformation",
     "%s tire deformation", "tire deflection, compression positive"},
    {"tire_power", FB_OUTPUT_OF_CORNER, "W", "tire_power_%s", "Power dissipated by the %s tire",
     "%s tire dissipated power", "power dissipated by the tire's damper"},
    {"spring_defl", FB_OUTPUT_OF_CORNER, "m", "spring_defl_%s",
     "%s suspension spring vertical deformation", "%s suspension spring deformation",
     "suspension spring deflection, compression positive"},
    {"spring_force", FB_OUTPUT_OF_CORNER, "N", "spring_force_%s", "%s suspension spring force",
     "%s spring force", "suspension spring force, compression positive"},
    {"shock_force", FB_OUTPUT_OF_CORNER, "N", "shock_force_%s", "%s shock absorber force",
     "%s shock absorber force", "shock absorber force, resisting compression positive"},
    {"shock_power", FB_OUTPUT_OF_CORNER, "W", "shock_power_%s",
     "Power dissipated by the %s shock absorber", "%s shock absorber dissipated power",
     "power dissipated by the shock absorber"},
    {"stop_force", FB_OUTPUT_OF_CORNER, "N", "stop_force_%s", "%s bump and rebound stop force",
     "%s stop force",
     "bump stop force less rebound stop force, compression positive (a corner with stops)"},
    {"wheel_travel", FB_OUTPUT_OF_CORNER, "m", "wheel_travel_%s",
     "%s wheel travel relative to the hull", "%s wheel travel",
     "wheel displacement towards the hull from the start, bump positive"},
    {"acc", FB_OUTPUT_OF_MOUNT, "m/s^2", "%s_acc", "Acceleration of the %s", "%s acceleration",
     "vertical acceleration of the mounted body, up positive"},
    {"travel", FB_OUTPUT_OF_MOUNT, "m", "%s_travel", "Deflection of the %s mount",
     "%s mount deflection", "mount spring deflection, compression positive"},
    {"force", FB_OUTPUT_OF_MOUNT, "N", "%s_force", "Force of the %s mount on the hull",
     "%s mount force", "spring plus damper force of the mount, tension positive"},
    {"beam_pitch", FB_OUTPUT_OF_BOGIE, "rad", "beam_pitch_%s", "Beam pitch of bogie %s",
     "bogie %s beam pitch", "the bogie's beam's pitch from the start, nose down positive"},
    {"pivot_force", FB_OUTPUT_OF_BOGIE, "N", "pivot_force_%s",
     "Spring force at the pivot of bogie %s", "bogie %s pivot spring force",
     "the bogie's pivot spring's force, compression positive"},
    {"body_acc_x", FB_OUTPUT_OF_BODY, "m/s^2", "%s_acc_x", "Acceleration of the %s, x",
     "%s x acceleration",
     "acceleration of the rigid body's centre of mass along x, forward positive"},
    {"body_acc_y", FB_OUTPUT_OF_BODY, "m/s^2", "%s_acc_y", "Acceleration of the %s, y",
     "%s y acceleration",
     "acceleration of the rigid body's centre of mass along y, left positive"},
    {"body_acc_z", FB_OUTPUT_OF_BODY, "m/s^2", "%s_acc_z", "Acceleration of the %s, z",
     "%s z acceleration",
     "acceleration of the rigid body's centre of mass along z, up positive"},
    {"body_acc_roll", FB_OUTPUT_OF_BODY, "rad/s^2", "%s_acc_roll",
     "Acceleration of the %s, roll", "%s roll acceleration",
     "acceleration of the rigid body's centre of mass about x"},
    {"body_acc_pitch", FB_OUTPUT_OF_BODY, "rad/s^2", "%s_acc_pitch",
     "Acceleration of the %s, pitch", "%s pitch acceleration",
     "acceleration of the rigid body's centre of mass about y"},
    {"body_acc_yaw", FB_OUTPUT_OF_BODY, "rad/s^2", "%s_acc_yaw", "Acceleration of the %s, yaw",
     "%s yaw acceleration", "acceleration of the rigid body's centre of mass about z"},
    {"body_disp_x", FB_OUTPUT_OF_BODY, "m", "%s_disp_x", "Displacement of the %s, x",
     "%s x displacement",
     "displacement of the rigid body's centre of mass along x, forward positive, from the "
     "start"},
    {"body_disp_y", FB_OUTPUT_OF_BODY, "m", "%s_disp_y", "Displacement of the %s, y",
     "%s y displacement",
     "displacement of the rigid body's centre of mass along y, left positive, from the start"},
    {"body_disp_z", FB_OUTPUT_OF_BODY, "m", "%s_disp_z", "Displacement of the %s, z",
     "%s z displacement",
     "displacement of the rigid body's centre of mass along z, up positive, from the start"},
    {"body_disp_roll", FB_OUTPUT_OF_BODY, "rad", "%s_disp_roll", "Displacement of the %s, roll",
     "%s roll displacement",
     "displacement of the rigid body's centre of mass about x, from the start"},
    {"body_disp_pitch", FB_OUTPUT_OF_BODY, "rad", "%s_disp_pitch",
     "Displacement of the %s, pitch", "%s pitch displacement",
     "displacement of the rigid body's centre of mass about y, from the start"},
    {"body_disp_yaw", FB_OUTPUT_OF_BODY, "rad", "%s_disp_yaw", "Displacement of the %s, yaw",
     "%s yaw displacement",
     "displacement of the rigid body's centre of mass about z, from the start"},
    {"torsion", FB_OUTPUT_OF_HULL, "rad", "torsion", "Hull torsion angle", "hull torsion angle",
     "roll of the front edge minus roll of the rear edge (the torsion edges, Fig. 10)"},
    {"torsion_fit", FB_OUTPUT_OF_HULL, "rad", "torsion_fit", "Hull torsion angle (fitted)",
     "hull torsion angle, fitted",
     "as torsion, each edge's roll that of its whole transverse section, least squares"},
    {"hull_displacement", FB_OUTPUT_OF_HULL_POINT, "m", "hull_displacement_%s",
     "Hull point displacement along %s", "hull point displacement %s",
     "displacement of the hull point `at` along `direction` from t = 0"},
    {"hull_velocity", FB_OUTPUT_OF_HULL_POINT, "m/s", "hull_velocity_%s",
     "Hull point velocity along %s", "hull point velocity %s",
     "velocity of the hull point `at` along `direction`"},
    {"hull_acceleration", FB_OUTPUT_OF_HULL_POINT, "m/s^2", "hull_acceleration_%s",
     "Hull point acceleration along %s", "hull point acceleration %s",
     "acceleration of the hull point `at` along `direction`, from the equations of motion"},
    {"hull_stress", FB_OUTPUT_OF_HULL_STRESS, "Pa", "hull_stress_%s", "Hull stress %s",
     "hull stress %s",
     "a surface stress of a shell element of System 2's hull, in the element's axes"},
    {"hull_longitudinal", FB_OUTPUT_OF_HULL, "m", "hull_longitudinal",
     "Hull longitudinal displacement", "hull longitudinal displacement",
     "the hull's rigid-body translation along x from t = 0 (0 in System 1 unless its hull "
     "carries rigid bodies)"},
    {"hull_lateral", FB_OUTPUT_OF_HULL, "m", "hull_lateral", "Hull lateral displacement",
     "hull lateral displacement",
     "the hull's rigid-body translation along y from t = 0 (0 in System 1 unless its hull "
     "carries rigid bodies)"},
    {"hull_bounce", FB_OUTPUT_OF_HULL, "m", "hull_bounce", "Hull bounce", "hull bounce",
     "the hull's rigid-body translation along z from t = 0"},
    {"hull_roll", FB_OUTPUT_OF_HULL, "rad", "hull_roll", "Hull roll angle", "hull roll angle",
     "the hull's rigid-body rotation about x from t = 0"},
    {"hull_pitch", FB_OUTPUT_OF_HULL, "rad", "hull_pitch", "Hull pitch angle",
     "hull pitch angle", "the hull's rigid-body rotation about y from t = 0"},
    {"hull_yaw", FB_OUTPUT_OF_HULL, "rad", "hull_yaw", "Hull yaw angle", "hull yaw angle",
     "the hull's rigid-body rotation about z from t = 0 (0 in System 1 unless its hull carries "
     "rigid bodies)"},
    {"effort", FB_OUTPUT_OF_BOND, NULL, "effort_%s", "Effort of bond %s", "%s effort",
     "effort of any bond of the assembled graph"},
    {"flow", FB_OUTPUT_OF_BOND, NULL, "flow_%s", "Flow of bond %s", "%s flow",
     "flow of any bond"},
    {"power", FB_OUTPUT_OF_BOND, NULL, "power_%s", "Power of bond %s", "%s power",
     "power of any bond, positive along its half arrow"},
    {"displacement", FB_OUTPUT_OF_BOND, NULL, "displacement_%s", "Displacement of bond %s",
     "%s displacement", "time integral of a bond's flow from t = 0"},
    {"momentum", FB_OUTPUT_OF_BOND, NULL, "momentum_%s", "Momentum of bond %s", "%s momentum",
     "time integral of a bond's effort from t = 0"},
};

enum { NKINDS = sizeof kinds / sizeof kinds[0] };

const fb_output_kind *fb_vehicle_output_kinds(size_t *n)
{
  *n = NKINDS;
  return kinds;
}

/* Index of the kind called signal, -1 if none. */
static long find_kind(const char *signal)
{
  for (size_t k = 0; signal && k < NKINDS; ++k)
    if (!strcmp(kinds[k].signal, signal))
      return (long)k;
  return -1;
}

const fb_output_kind *fb_vehicle_output_kind_find(const char *signal)
{
  const long k = find_kind(signal);
  return k < 0 ? NULL : &kinds[k];
}

/* The hull's torsions: the edges' end nodes (0) or the least-squares
 * rotation of their transverse sections (1), of fb_hull's weights; -1 for
 * the hull's other signals. */
static int hull_fit(const char *signal)
{
  return !strcmp(signal, "torsion_fit") ? 1 : !strcmp(signal, "torsion") ? 0 : -1;
}

/* What each signal read from the hull's motion measures: a derivative of
 * the point's translation (coordinate -1) or of a rigid-body coordinate
 * (vehicle_rigid_rows' order: x, y, z, roll, pitch, yaw). */
typedef struct hull_motion_row {
  const char *signal;
  vehicle_hull_motion how;
} hull_motion_row;

static const hull_motion_row hull_motions[] = {
    {"hull_displacement", {0, -1}}, {"hull_velocity", {1, -1}}, {"hull_acceleration", {2, -1}},
    {"hull_longitudinal", {0, 0}},  {"hull_lateral", {0, 1}},   {"hull_bounce", {0, 2}},
    {"hull_roll", {0, 3}},          {"hull_pitch", {0, 4}},     {"hull_yaw", {0, 5}},
};

int vehicle_output_hull_motion(const fb_output_spec *o, vehicle_hull_motion *how)
{
  for (size_t i = 0; o->signal && i < sizeof hull_motions / sizeof hull_motions[0]; ++i)
    if (!strcmp(hull_motions[i].signal, o->signal)) {
      *how = hull_motions[i].how;
      return 1;
    }
  return 0;
}

/* Index of the item of subject named name in s, -1 if none. */
static long subject_find(const fb_scenario *s, fb_output_subject subject, const char *name)
{
  switch (subject) {
  case FB_OUTPUT_OF_CORNER: return fb_scenario_corner_find(s, name);
  case FB_OUTPUT_OF_MOUNT: return fb_scenario_mount_find(s, name);
  case FB_OUTPUT_OF_BOGIE: return fb_scenario_bogie_find(s, name);
  default: return -1;
  }
}

/* A corner's, a mount's or a bogie's output o: its fragment's probe of
 * the signal, in the instance of o's subject. */
static int body_probe(const fb_scenario *s, const fb_output_kind *info, size_t index,
                      fb_probe_spec *p, fb_err *err)
{
  const fb_output_spec *o = &s->output[index];
  const int corner = info->subject == FB_OUTPUT_OF_CORNER;
  const char *what = corner                                ? "corner"
                     : info->subject == FB_OUTPUT_OF_MOUNT ? "mount"
                                                           : "bogie";
  const long i = subject_find(s, info->subject, o->of);
  if (i < 0)
    return fb_err_set(err, FB_EINVAL, "no %s '%s'", what, o->of ? o->of : ""),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, of)), FB_EINVAL;
  const vehicle_signal *how = corner ? vehicle_corner_signal(s, (size_t)i, o->signal)
                                     : vehicle_fragment_signal(info->subject, o->signal);
  if (!how)
    return fb_err_set(err, FB_EMODEL, "the %s fragment offers no %s", what, o->signal),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, signal)), FB_EMODEL;
  p->kind = how->kind;
  p->integrate = how->integrate;
  if (how->per_mass)
    p->gain = 1.0 / s->mount[i].mass;
  p->target = vehicle_target(s, info->subject, (size_t)i, how->target);
  return FB_OK;
}

/* An output read from the hull's motion: the hull's probe of it. */
static int hull_reading_probe(const fb_hull *hull, size_t index, fb_probe_spec *p, fb_err *err)
{
  const fb_hull_reading *r = index < hull->nreading ? &hull->reading[index] : NULL;
  if (!r || !r->target)
    return fb_err_set(err, FB_EMODEL, "the hull made no probe for output %zu", index);
  p->kind = r->kind;
  p->integrate = r->integrate;
  p->target = fb_strdup_printf("hull.%s", r->target);
  double *w = malloc(r->nweights * sizeof *w);
  if (!w)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  memcpy(w, r->weights, r->nweights * sizeof *w);
  p->weights = w;
  p->nweights = r->nweights;
  return FB_OK;
}

/* A surface stress of a shell element: the finite-element hull's
 * reading of it (hull_stress_output.c); the rigid hull has no elements and
 * makes none. */
static int hull_stress_probe(const fb_hull *hull, const fb_output_spec *o, size_t index,
                             fb_probe_spec *p, fb_err *err)
{
  if (index < hull->nreading && !hull->reading[index].target)
    return fb_err_set(err, FB_EINVAL,
                      "System 1's hull is a rigid body: it has no shell elements, whose "
                      "stresses a %s signal reads: only System 2 gives it",
                      o->signal),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, signal)), FB_EINVAL;
  return hull_reading_probe(hull, index, p, err);
}

/* The hull's torsion: the hull says where and with which weights. */
static int hull_probe(const fb_hull *hull, const fb_output_spec *o, size_t index,
                      fb_probe_spec *p, fb_err *err)
{
  vehicle_hull_motion how;
  if (vehicle_output_hull_motion(o, &how))
    return hull_reading_probe(hull, index, p, err);
  p->kind = hull->torsion_kind;
  p->integrate = hull->torsion_integrate;
  p->target = fb_strdup_printf("hull.%s", hull->torsion_target);
  double *w = malloc(hull->ntorsion * sizeof *w);
  if (!w)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  memcpy(w, hull_fit(o->signal) > 0 ? hull->torsion_fit_weights : hull->torsion_weights,
         hull->ntorsion * sizeof *w);
  p->weights = w;
  p->nweights = hull->ntorsion;
  return FB_OK;
}

static const bond_probe *find_bond_probe(const char *signal)
{
  for (size_t i = 0; i < sizeof bond_probes / sizeof bond_probes[0]; ++i)
    if (!strcmp(bond_probes[i].signal, signal))
      return &bond_probes[i];
  return NULL;
}

/* A bond signal: a probe on the bond o names. */
static int bond_probe_of(const fb_output_spec *o, fb_probe_spec *p, fb_err *err)
{
  const bond_probe *how = find_bond_probe(o->signal);
  if (!how)
    return fb_err_set(err, FB_EMODEL, "no probe for the bond signal %s", o->signal);
  p->kind = how->kind;
  p->integrate = how->integrate;
  p->target = fb_strdup(o->bond);
  p->component = o->component - 1;
  return FB_OK;
}

int fb_vehicle_output_probe(const fb_scenario *s, const fb_hull *hull, size_t index,
                            fb_probe_spec *p, fb_err *err)
{
  const fb_output_spec *o = &s->output[index];
  const long k = find_kind(o->signal);
  memset(p, 0, sizeof *p);
  p->component = -1;
  if (k < 0)
    return fb_err_set(err, FB_EINVAL, "unknown signal '%s'", o->signal),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, signal)), FB_EINVAL;
  const fb_output_kind *info = &kinds[k];
  p->name = fb_strdup(o->name);
  if (!p->name)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  p->gain = 1.0;
  p->unit = info->unit;
  int rc = FB_OK;
  switch (info->subject) {
  case FB_OUTPUT_OF_CORNER:
  case FB_OUTPUT_OF_MOUNT:
  case FB_OUTPUT_OF_BOGIE: rc = body_probe(s, info, index, p, err); break;
  case FB_OUTPUT_OF_BODY: rc = vehicle_body_probe(s, index, p, err); break;
  case FB_OUTPUT_OF_HULL: rc = hull_probe(hull, o, index, p, err); break;
  case FB_OUTPUT_OF_HULL_POINT: rc = hull_reading_probe(hull, index, p, err); break;
  case FB_OUTPUT_OF_HULL_STRESS: rc = hull_stress_probe(hull, o, index, p, err); break;
  case FB_OUTPUT_OF_BOND: rc = bond_probe_of(o, p, err); break;
  }
  return rc ? rc : p->target ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
}

int vehicle_output_hull_stress(const fb_output_spec *o)
{
  const long k = find_kind(o->signal);
  return k >= 0 && kinds[k].subject == FB_OUTPUT_OF_HULL_STRESS;
}

size_t fb_vehicle_outputs_system2_only(const fb_scenario *s)
{
  size_t i = 0;
  while (i < s->noutputs && !vehicle_output_hull_stress(&s->output[i]))
    ++i;
  return i;
}

int fb_vehicle_output_hull_fit(const fb_output_spec *o)
{
  const long k = find_kind(o->signal);
  return k >= 0 && kinds[k].subject == FB_OUTPUT_OF_HULL ? hull_fit(o->signal) : -1;
}

int vehicle_hull_readings_new(const fb_scenario *s, fb_hull *hull, fb_err *err)
{
  hull->reading = calloc(s->noutputs + 1, sizeof *hull->reading);
  hull->nreading = s->noutputs;
  return hull->reading ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
}

int vehicle_hull_reading_set(fb_hull_reading *r, const char *target, fb_probe_kind kind,
                             int integrate, const double *weights, size_t nweights, fb_err *err)
{
  r->target = fb_strdup(target);
  r->weights = malloc((nweights + 1) * sizeof *r->weights);
  if (!r->target || !r->weights)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  memcpy(r->weights, weights, nweights * sizeof *weights);
  r->nweights = nweights;
  r->kind = kind;
  r->integrate = integrate;
  return FB_OK;
}

void vehicle_hull_readings_free(fb_hull *hull)
{
  for (size_t o = 0; hull->reading && o < hull->nreading; ++o) {
    free(hull->reading[o].target);
    free(hull->reading[o].weights);
  }
  free(hull->reading);
  hull->reading = NULL;
  hull->nreading = 0;
}
