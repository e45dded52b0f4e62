/* SPDX-License-Identifier: BSD-3-Clause */
/* Which loader a YAML input file is for: a model (fb_model_load) or a
 * vehicle scenario (fb_scenario_load). */
#ifndef FLEXBOND_IO_INPUT_KIND_H
#define FLEXBOND_IO_INPUT_KIND_H

typedef enum fb_input_kind {
  FB_INPUT_MODEL,   /* top-level key `model:` (docs/model-format.md) */
  FB_INPUT_SCENARIO /* top-level key `scenario:` (docs/scenario-format.md) */
} fb_input_kind;

/* The kind of the file at path, from its parsed document (the same
 * parser, with the same bounds, as both loaders): FB_INPUT_SCENARIO when
 * its root is a mapping with a key `scenario`, FB_INPUT_MODEL otherwise,
 * also when the file cannot be read or parsed, so that the model loader,
 * run next, reports why as it always has. Nothing is printed. */
fb_input_kind fb_input_kind_of(const char *path);

#endif
