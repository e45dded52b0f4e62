/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: a vehicle scenario as an FMI 3.0 FMU (Functional Mock-up
 * Unit) with both the Model Exchange and the Co-Simulation interfaces,
 * for Simulink, OpenModelica, Dymola, FMPy or a HIL bench (docs/fmi.md).
 *
 * The FMU is a ZIP archive: modelDescription.xml (the variables, their
 * units, the default experiment), binaries/x86_64-linux/ (the FMU's
 * binary, flexbond linked in, and the shared libraries it needs that are
 * not the C library's, found through its run path $ORIGIN), resources/
 * (the scenario and every file it names, and the choices below) and
 * sources/ (buildDescription.xml and the binary's sources). */
#ifndef FLEXBOND_FMU_H
#define FLEXBOND_FMU_H

#include <stddef.h>

#include "flexbond/error.h"
#include "flexbond/vehicle.h"

#ifdef __cplusplus
extern "C" {
#endif

/* What to build. Initialise by member names: members may be added. */
typedef struct fb_fmu_export_opts {
  fb_system system; /* FB_SYSTEM_RIGID (System 1) or FB_SYSTEM_FLEXIBLE */
  /* 1: the road under each wheel is an input (road_z_<CORNER>,
   * road_zdot_<CORNER>); 0: the scenario's road, a function of time. */
  int road_inputs;
  /* Scenario keys (as fb_scenario_override.key; the file must write
   * each) made tunable parameters, in this order; borrowed. */
  const char *const *parameters;
  size_t nparameters;
  /* Values replaced in the scenario for good (flexbond fmu --set). */
  const fb_scenario_override *overrides;
  size_t noverrides;
  /* s: the horizon the FMU can run to (its DefaultExperiment's stop
   * time); 0: the scenario's t_end. */
  double t_end;
  /* The model identifier (the binary's name): a C identifier; NULL: made
   * from the scenario's name. */
  const char *model_identifier;
  /* The FMU's binary to package; NULL: fb_fmu_runtime_path's. */
  const char *runtime;
  /* Hears of each stage (the vehicle's realisation, the packaging). */
  fb_progress progress;
} fb_fmu_export_opts;

/* What was built. */
typedef struct fb_fmu_info {
  char model_identifier[128];
  size_t nstates, ninputs, noutputs, nparameters, nindicators;
  size_t nlibraries; /* shared libraries bundled beside the binary */
  size_t bytes;      /* the FMU's size */
} fb_fmu_info;

/* Writes the FMU of the scenario at scenario_path to fmu_path (through a
 * temporary file renamed into place: no half-written FMU is ever there).
 * It realises the vehicle once (System 2: the hull's eigen-solve) to
 * list the variables, copies the scenario and the files it names into
 * resources/ (each below the folder they share; a copy loaded from there
 * must read nothing outside it), and bundles the binary's libraries
 * (found by ldd). info may be NULL. Errors: the scenario's (located),
 * FB_EINVAL about an option (err->key "parameters", "model_identifier",
 * "t_end"), FB_EIO about a file or a child. */
int fb_fmu_export(const char *scenario_path, const fb_fmu_export_opts *o, const char *fmu_path,
                  fb_fmu_info *info, fb_err *err);

/* 1 if id may be an FMU's model identifier: a C identifier of at most
 * 127 characters (it names the binary and, in a source FMU, prefixes
 * the functions). */
int fb_fmu_model_identifier_valid(const char *id);

/* The FMU binary flexbond built or installed: $FLEXBOND_FMU_RUNTIME if
 * set, else the installed one, else the build tree's; NULL if none
 * exists. Static storage or the environment's. */
const char *fb_fmu_runtime_path(void);

#ifdef __cplusplus
}
#endif
#endif
