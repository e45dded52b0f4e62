/* SPDX-License-Identifier: BSD-3-Clause */
/* The reference vehicle's layout (examples/apc6x6.yaml), for the tests
 * that check it against a second formulation of its own: the library
 * itself has no fixed layout (any corners and mounted bodies from the
 * file), so these tests first check that the scenario they load is laid
 * out as this header says (apc_layout_ok). */
#ifndef FLEXBOND_TESTS_APC_LAYOUT_H
#define FLEXBOND_TESTS_APC_LAYOUT_H

#include <string.h>

#include "flexbond/vehicle.h"

/* Corners in the file's order; mounts; the paper's seven outputs. */
enum { APC_LF, APC_RF, APC_LM, APC_RM, APC_LR, APC_RR, APC_NCORNERS };
enum { APC_MOUNT_DRIVER_INDEX, APC_MOUNT_ENGINE_INDEX, APC_NMOUNTS };
enum { APC_NOUTPUTS = 7 };

#define APC_DRIVER(s) (&(s)->mount[APC_MOUNT_DRIVER_INDEX])
#define APC_ENGINE(s) (&(s)->mount[APC_MOUNT_ENGINE_INDEX])

static inline const char *apc_corner_name(int c)
{
  static const char *const names[APC_NCORNERS] = {"LF", "RF", "LM", "RM", "LR", "RR"};
  return c >= 0 && c < APC_NCORNERS ? names[c] : "?";
}

static inline const char *apc_output_name(int k)
{
  static const char *const names[APC_NOUTPUTS] = {
      "tire_force_LF",  "spring_defl_RF", "torsion",      "driver_acc",
      "shock_power_LM", "tire_defl_RM",   "tire_power_LR"};
  return k >= 0 && k < APC_NOUTPUTS ? names[k] : "?";
}

static inline const char *apc_output_unit(int k)
{
  static const char *const units[APC_NOUTPUTS] = {"N", "m", "rad", "m/s^2", "W", "m", "W"};
  return k >= 0 && k < APC_NOUTPUTS ? units[k] : "?";
}

/* 1 when s has the reference layout: corners LF RF LM RM LR RR, mounts
 * driver and engine, and the paper's seven outputs in their CSV order. */
static inline int apc_layout_ok(const fb_scenario *s)
{
  if (s->ncorners != APC_NCORNERS || s->nmounts != APC_NMOUNTS || s->noutputs != APC_NOUTPUTS)
    return 0;
  for (int c = 0; c < APC_NCORNERS; ++c)
    if (strcmp(s->corner[c].name, apc_corner_name(c)) != 0)
      return 0;
  for (int k = 0; k < APC_NOUTPUTS; ++k)
    if (strcmp(s->output[k].name, apc_output_name(k)) != 0)
      return 0;
  return !strcmp(APC_DRIVER(s)->name, "driver") && !strcmp(APC_ENGINE(s)->name, "engine");
}

#endif
