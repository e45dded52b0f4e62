/* flexbond: internals of the vehicle scenario loader (src/io/scenario*.c).
 *
 * The scenario file (docs/scenario-format.md) is declared once, as the
 * schema table of scenario_schema.c (io/schema.h): it reads the file,
 * checks the values' ranges, visits them, and writes the format's key
 * tables. Errors found after reading name their value by its logical key
 * (fb_err.key: "corners.LF.spring_k") and are located through the
 * scenario's origins (fb_scenario_locate), never by reading the file
 * again. */
#ifndef FLEXBOND_IO_SCENARIO_INTERNAL_H
#define FLEXBOND_IO_SCENARIO_INTERNAL_H

#include <stdio.h>

#include "flexbond/vehicle.h"

#include "io/model_internal.h"
#include "io/schema.h"

/* pi; M_PI is not in C11. */
#define SC_PI 3.14159265358979323846

/* The scenario format's table. */
extern const sch_table sc_schema;

/* Reads the document root into s (zeroed by the caller), `parameters`
 * evaluated into params (empty) for the expressions, and moves the
 * values' origins into s. On failure s may hold allocations, which
 * fb_scenario_free releases. Cross-field rules are fb_scenario_check's. */
int sc_read(ml_ctx *c, struct fy_node *root, fb_symtab *params, fb_scenario *s);

/* The origin of the value with logical key key, or of the nearest value
 * enclosing it ("corners.LF" for "corners.LF.damper_table[2]"), NULL if
 * none; *rest gets the part of key below the origin's. */
const fb_scenario_origin *sc_origin_find(const fb_scenario *s, const char *key,
                                         const char **rest);

/* fb_scenario_locate; with named set, for a message that names its key
 * already (the solver's limits): only "FILE:LINE:COL: " is prefixed. */
int sc_locate(const fb_scenario *s, fb_err *err, int named);

/* Writes the format's key tables (what docs/scenario-format.md holds
 * between its schema:begin and schema:end markers). */
void fb_scenario_schema_markdown(FILE *fp);

/* Loads text edited from the scenario file at path (flexbond sweep's
 * --set) as that file: relative references resolved from its directory.
 * In scenario.c, next to the loader it shares. */
int sc_load_edited_file(const char *text, size_t len, const char *path, fb_scenario **out,
                        fb_err *err);

#endif
