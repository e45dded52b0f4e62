/* SPDX-License-Identifier: BSD-3-Clause */
/* The XML documents of a flexbond FMU (src/fmu/description.c). */
#ifndef FLEXBOND_FMU_DESCRIPTION_H
#define FLEXBOND_FMU_DESCRIPTION_H

#include <stdio.h>

#include "fmu/fmu_internal.h"

typedef struct fmu_description {
  const fmu_model *model;
  const char *model_name;
  const char *model_identifier;
  const char *description;
  const char *version;         /* the model's: the scenario's */
  double stop_time, step_size; /* s: the default experiment */
  double tolerance;            /* its relative tolerance: the scenario's */
  const char *const *sources;  /* sources/ files the build compiles */
  size_t nsources;
} fmu_description;

/* modelDescription.xml of d to fp. FB_EIO on a write error. */
int fmu_write_model_description(FILE *fp, const fmu_description *d, fb_err *err);
/* sources/buildDescription.xml of d to fp. */
int fmu_write_build_description(FILE *fp, const fmu_description *d, fb_err *err);

#endif
