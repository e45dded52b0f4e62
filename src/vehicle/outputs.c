/* SPDX-License-Identifier: BSD-3-Clause */
/* The signals a vehicle's outputs may name (docs/vehicle-outputs.md), and the
 * probes that measure them on the assembled graph (flexbond/vehicle.h).
 *
 * Each kind is one row: what it measures (a probe kind on a bond or an
 * element of its subject's fragment, fragments.c), its unit and its
 * default name, title and label. A new kind is one row here and one line
 * in docs/vehicle-outputs.md; nothing else names a kind. */
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* How a kind is measured: probe kind, target inside the subject's fragment
 * (for bond signals: the output's bond), integrate, whether the value
 * is divided by the subject's mass (a mount's acceleration: the effort on
 * its mass over the mass, the paper's gain block 1/m on e7), and for the
 * hull's torsion which of its weights (fb_hull: 0 the edges' end nodes,
 * 1 the least-squares rotation of their transverse sections). */
typedef struct output_probe {
  fb_probe_kind kind;
  const char *target;
  int integrate;
  int per_mass;
  int fit;
} output_probe;

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
    {"wheel_travel", FB_OUTPUT_OF_CORNER, "m", "wheel_travel_%s",
     "%s wheel travel relative to the hull", "%s wheel travel",
     "wheel displacement towards the hull from the start, bump positive"},
    {"acc", FB_OUTPUT_OF_MOUNT, "m/s^2", "%s_acc", "Acceleration of the %s", "%s acceleration",
     "vertical acceleration of the mounted body, up positive"},
    {"travel", FB_OUTPUT_OF_MOUNT, "m", "%s_travel", "Deflection of the %s mount",
     "%s mount deflection", "mount spring deflection, compression positive"},
    {"force", FB_OUTPUT_OF_MOUNT, "N", "%s_force", "Force of the %s mount on the hull",
     "%s mount force", "spring plus damper force of the mount, tension positive"},
    {"torsion", FB_OUTPUT_OF_HULL, "rad", "torsion", "Hull torsion angle", "hull torsion angle",
     "roll of the front edge minus roll of the rear edge (the torsion edges, Fig. 10)"},
    {"torsion_fit", FB_OUTPUT_OF_HULL, "rad", "torsion_fit", "Hull torsion angle (fitted)",
     "hull torsion angle, fitted",
     "as torsion, each edge's roll that of its whole transverse section, least squares"},
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

/* How each kind of `kinds` is measured, in the same order. */
static const output_probe probes[] = {
    {FB_PROBE_EFFORT, "b_tire", 0, 0, 0},
    {FB_PROBE_STATE, "tire_spring", 0, 0, 0},
    {FB_PROBE_POWER, "b_tire_damper", 0, 0, 0},
    {FB_PROBE_STATE, "spring", 0, 0, 0},
    {FB_PROBE_EFFORT, "b_spring", 0, 0, 0},
    {FB_PROBE_EFFORT, "b_damper", 0, 0, 0},
    {FB_PROBE_POWER, "b_damper", 0, 0, 0},
    {FB_PROBE_FLOW, "b_arm", 1, 0, 0},
    {FB_PROBE_EFFORT, "b_mass", 0, 1, 0},
    {FB_PROBE_STATE, "spring", 0, 0, 0},
    {FB_PROBE_EFFORT, "b_up", 0, 0, 0},
    {FB_PROBE_FLOW, NULL, 0, 0, 0},
    {FB_PROBE_FLOW, NULL, 0, 0, 1},
    {FB_PROBE_EFFORT, NULL, 0, 0, 0},
    {FB_PROBE_FLOW, NULL, 0, 0, 0},
    {FB_PROBE_POWER, NULL, 0, 0, 0},
    {FB_PROBE_FLOW, NULL, 1, 0, 0},
    {FB_PROBE_EFFORT, NULL, 1, 0, 0},
};

enum { NKINDS = sizeof kinds / sizeof kinds[0] };
_Static_assert(sizeof probes / sizeof probes[0] == NKINDS, "one probe per kind");

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

/* The probe of output o on the assembled graph (instance names of
 * assemble.c: "susp_<corner>", the mount's name, "hull"). p's target and
 * weights are new. */
int fb_vehicle_output_probe(const fb_scenario *s, const fb_hull *hull, size_t index,
                            fb_probe_spec *p, fb_err *err)
{
  const fb_output_spec *o = &s->output[index];
  const long k = find_kind(o->signal);
  memset(p, 0, sizeof *p);
  if (k < 0)
    return fb_err_set(err, FB_EINVAL, "unknown signal '%s'", o->signal),
           fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, signal)), FB_EINVAL;
  const fb_output_kind *info = &kinds[k];
  const output_probe *how = &probes[k];
  p->name = fb_strdup(o->name);
  if (!p->name)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  p->kind = how->kind;
  p->component = -1;
  p->gain = 1.0;
  p->unit = info->unit;
  p->integrate = how->integrate;
  switch (info->subject) {
  case FB_OUTPUT_OF_CORNER:
    p->target = fb_strdup_printf("susp_%s.%s", o->of, how->target);
    break;
  case FB_OUTPUT_OF_MOUNT: {
    const long b = fb_scenario_mount_find(s, o->of);
    if (b < 0)
      return fb_err_set(err, FB_EINVAL, "no mount '%s'", o->of),
             fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, of)), FB_EINVAL;
    if (how->per_mass)
      p->gain = 1.0 / s->mount[b].mass;
    p->target = fb_strdup_printf("%s.%s", o->of, how->target);
    break;
  }
  case FB_OUTPUT_OF_HULL: {
    p->kind = hull->torsion_kind;
    p->integrate = hull->torsion_integrate;
    p->target = fb_strdup_printf("hull.%s", hull->torsion_target);
    double *w = malloc(hull->ntorsion * sizeof *w);
    if (!w)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    memcpy(w, how->fit ? hull->torsion_fit_weights : hull->torsion_weights,
           hull->ntorsion * sizeof *w);
    p->weights = w;
    p->nweights = hull->ntorsion;
    break;
  }
  case FB_OUTPUT_OF_BOND: p->target = fb_strdup(o->bond); break;
  }
  return p->target ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
}

int fb_vehicle_output_hull_fit(const fb_output_spec *o)
{
  const long k = find_kind(o->signal);
  return k >= 0 && kinds[k].subject == FB_OUTPUT_OF_HULL ? probes[k].fit : -1;
}
