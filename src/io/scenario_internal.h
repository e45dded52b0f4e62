/* flexbond: internals of the vehicle scenario loader (src/io/scenario*.c).
 *
 * The scenario file (docs/scenario-format.md) is read with the model
 * loader's YAML helpers (io/model_internal.h), so its messages have the
 * same "FILE:LINE:COL: KEY: message" form. fb_scenario_check names the
 * offending value by its key path in the file ("suspensions.LF.spring_k",
 * "road.bump"); sc_blame_check turns such a message into a located one. */
#ifndef FLEXBOND_IO_SCENARIO_INTERNAL_H
#define FLEXBOND_IO_SCENARIO_INTERNAL_H

#include "flexbond/vehicle.h"

#include "io/model_internal.h"

/* pi; M_PI is not in C11. */
#define SC_PI 3.14159265358979323846

/* Reads the document root into s (zeroed by the caller): evaluates the
 * `parameters` section into params (empty) and makes it c->globals for
 * the expressions that follow. On failure s may hold allocations, which
 * fb_scenario_free releases. Values are not checked for physical
 * consistency here (see fb_scenario_check). */
int sc_read(ml_ctx *c, struct fy_node *root, fb_symtab *params, fb_scenario *s);

/* c->err holds "KEY: message" from fb_scenario_check: reports it at the
 * value KEY comes from (the corner's override or the shared default for
 * per-corner values), else at the nearest enclosing node present in the
 * file, keeping the key. Returns the error code. */
int sc_blame_check(const ml_ctx *c, struct fy_node *root);

/* As sc_blame_check for a message raised after loading (the hull mesh's
 * checks, say): only one that starts with a key path whose first segment
 * is in the file is located; any other is left as it is. */
int sc_blame_late(const ml_ctx *c, struct fy_node *root);

/* Loads text edited from the scenario file at path (flexbond sweep's
 * --set) as that file: relative references resolved from its directory.
 * In scenario.c, next to the loader it shares. */
int sc_load_edited_file(const char *text, size_t len, const char *path, fb_scenario **out,
                        fb_err *err);

#endif
