/* SPDX-License-Identifier: BSD-3-Clause */
/* What the FMU's exporter (src/fmu/export.c, in the library) and its
 * runtime (src/fmu/runtime.c, the FMU's binary) share: the build choices
 * the exporter writes into resources/ and the runtime reads back, and
 * the table of the model's variables both derive from one vehicle
 * stepper, so that modelDescription.xml and the binary cannot disagree
 * (the instantiation token is a digest of the table). */
#ifndef FLEXBOND_FMU_INTERNAL_H
#define FLEXBOND_FMU_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "flexbond/error.h"
#include "flexbond/vehicle.h"

/* The choices an FMU is built with (resources/flexbond-fmu.txt, one
 * "word value" per line: docs/fmi.md). All strings owned. */
typedef struct fmu_config {
  char *scenario; /* the scenario's path under resources/ */
  fb_system system;
  int road_inputs;  /* the road under each wheel is an input */
  char **parameter; /* the tunable parameters: full key paths */
  size_t nparameters;
  fb_scenario_override *set; /* fixed overrides (key and value owned) */
  size_t nsets;
  double t_end; /* s: the horizon the FMU can run to */
} fmu_config;

void fmu_config_release(fmu_config *c);
/* Writes c to fp. FB_EINVAL if a string holds a line break. */
int fmu_config_write(const fmu_config *c, FILE *fp, fb_err *err);
/* Reads what fmu_config_write wrote at path into *c (zeroed first).
 * FB_EIO, FB_EPARSE "PATH:LINE: ..." */
int fmu_config_read(const char *path, fmu_config *c, fb_err *err);

/* A unit as SI base-unit exponents with a factor and an offset
 * (value_SI = factor * value + offset), as FMI's BaseUnit says it. */
typedef struct fmu_unit {
  int kg, m, s, A, K, mol, cd, rad;
  double factor, offset;
} fmu_unit;
/* Parses flexbond's unit text ("N/m", "m/s^2", "kg*m^2", "km/h", "1/s",
 * "" for none). FB_EINVAL for a symbol it does not know. */
int fmu_unit_parse(const char *text, fmu_unit *u, fb_err *err);

/* What a variable is. */
typedef enum fmu_var_kind {
  FMU_VAR_TIME,      /* the independent variable */
  FMU_VAR_INPUT,     /* a stepper input, index into its inputs */
  FMU_VAR_OUTPUT,    /* a stepper output */
  FMU_VAR_PARAMETER, /* a tunable parameter, index into the config's */
  FMU_VAR_STATE,     /* a continuous state (model exchange) */
  FMU_VAR_DERIVATIVE,
  FMU_VAR_INDICATOR /* an event indicator: a switched law's guard */
} fmu_var_kind;

typedef struct fmu_var {
  char *name; /* owned */
  fmu_var_kind kind;
  size_t index;     /* within its kind */
  const char *unit; /* "" none; borrowed from a static table or the scenario */
  char *unit_owned; /* when the unit is the model's own copy */
  double start;     /* inputs and parameters */
  int fixed;        /* a parameter set before initialisation only */
  const char *doc;  /* one line, borrowed */
} fmu_var;

/* The variables of an FMU, in value-reference order (the value
 * reference of var[k] is k). */
typedef struct fmu_model {
  fmu_var *var;
  size_t nvars;
  size_t ninputs, noutputs, nparameters, nstates, nindicators;
  size_t first_input, first_output, first_parameter, first_state, first_derivative,
      first_indicator;
  char token[40]; /* instantiation token: "{flexbond-" digest "}" */
} fmu_model;

/* The table of st's vehicle (inputs, outputs, states, guards) with c's
 * parameters, whose values in the loaded scenario s are param_start and
 * units param_unit (nparameters each, borrowed: copied). *out new. */
int fmu_model_new(fb_vehicle_stepper *st, const fmu_config *c, const double *param_start,
                  const char *const *param_unit, fmu_model **out, fb_err *err);
void fmu_model_free(fmu_model **m);

/* The value and unit (as written in the file: "km/h") of the scenario
 * value at full key path key in s, which the file must write. FB_EINVAL
 * (err->key the key) for a key the file does not write or a value that
 * is not a number. *unit points into a static table ("" none). */
int fmu_parameter_value(const fb_scenario *s, const char *key, double *value, const char **unit,
                        fb_err *err);

/* 1 if the parameter at full key path key is variability "fixed" (set
 * before initialisation only), 0 if "tunable". The road's values are
 * fixed: the road is placed in time from t = 0 (flexbond/vehicle.h, the
 * stepper), so a new speed or obstacle mid-run would move the wheels
 * along the road at once, not carry them on from where they are. */
int fmu_parameter_fixed(const char *key);

/* Loads the scenario at path with c's fixed overrides and the
 * parameters at values (NULL: as the file has them), and the horizon
 * c->t_end (when > 0). */
int fmu_scenario_load(const char *path, const fmu_config *c, const double *values,
                      fb_scenario **out, fb_err *err);

/* The name of the file of resources/ that holds the config. */
#define FMU_CONFIG_NAME "flexbond-fmu.txt"

#endif
