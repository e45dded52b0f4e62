/* SPDX-License-Identifier: BSD-3-Clause */
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

/* The scenario format's own keys (scenario_schema.c), without the road
 * types: a format's table is these and a gallery's types, an sc_schema. */
extern const sch_table sc_format;
/* The key of sc_format after which the road types' sections go. */
#define SC_ROAD_TYPES_AFTER "road.speed_kmh"
/* The key of sc_format after which the hull sources' sections go: the
 * last of the generator's (a source's section hull.mesh.<source> joins
 * hull.mesh.deck and hull.mesh.generator, one of them). */
#define SC_HULL_SOURCES_AFTER "hull.mesh.generator.nose_rung_divisions"
/* The key of sc_format, and of its corners' items, after which the tire
 * models' sections go; its choices are the models' names. */
#define SC_TIRE_CHOICE "wheel.tire_contact"
/* The key of sc_format, and of its corners' items, after which the
 * envelope models' sections go; its choices are the models' names. */
#define SC_ENVELOPE_CHOICE "wheel.envelope"
/* The tire's free radius, which an enveloping tire reads. */
#define SC_TIRE_RADIUS "wheel.radius"
/* The force-deflection table of a tire whose model is the table one. */
#define SC_TIRE_TABLE "wheel.tire_table"
/* The top level's section wheel.<model> of a model no corner's tire is
 * (its values would reach no corner, and a sweep over them would change
 * nothing) refused at its key, once the corners are read (t: the table
 * read with, root: the document). */
int sc_tire_sections_used(sch_reader *r, const sch_table *t, struct fy_node *root,
                          const fb_scenario *s);
/* As sc_tire_sections_used for the envelope models' sections. */
int sc_envelope_sections_used(sch_reader *r, const sch_table *t, struct fy_node *root,
                              const fb_scenario *s);
/* The section of sc_corner_format after which the damper laws' sections
 * go (damper.<law>, for a law with no key of its own). */
#define SC_DAMPER_SECTION "damper"
/* The corners' items (scenario_schema.c), without the tire models. */
extern const sch_table sc_corner_format;
/* After a corner's keys are read (item at node, under item_path): its
 * tire model (the choice's value, given or inherited) and that model's
 * parameters, the corner's own else the top-level wheel's
 * (scenario_gallery.c). FB_EPARSE at a section of another model. */
int sc_corner_tire(sch_reader *r, const sch_key *list, struct fy_node *node,
                   const char *item_path, fb_corner_params *c);
/* As sc_corner_tire for the corner's envelope (the choice and sections
 * of SC_ENVELOPE_CHOICE) and its tire's free radius (wheel.radius, the
 * corner's own else the top level's). */
int sc_corner_envelope(sch_reader *r, const sch_key *list, struct fy_node *node,
                       const char *item_path, fb_corner_params *c);
/* The format's table with the road types of a gallery
 * (scenario_gallery.c): sc_format's keys and, for each type, a section
 * road.<type> of its declared parameters. Immutable once made, shared by
 * count (the scenarios read with it, their copies). */
typedef struct sc_schema sc_schema;
/* The table for the galleries of o (its road types, tire models, hull
 * sources and damper laws; borrowed for the call, their entries must
 * outlive the schema), the built-in ones where o (or o itself) names
 * none. *out new. FB_ENOMEM. */
int sc_schema_new(const fb_scenario_load_opts *o, sc_schema **out, fb_err *err);
/* sc again, one more holder. */
sc_schema *sc_schema_share(sc_schema *sc);
void sc_schema_release(sc_schema **sc);
const sch_table *sc_schema_table(const sc_schema *sc);
/* The schema s was read with, shared; or, for a description without a
 * file, one of the built-in types and s's own (*out new). FB_ENOMEM. */
int sc_schema_of(const fb_scenario *s, sc_schema **out, fb_err *err);

/* Reads the document root into s (zeroed by the caller), `parameters`
 * evaluated into params (empty) for the expressions, the nov overrides
 * (full paths) read in place of the file's values, and moves the values'
 * origins into s. On failure s may hold allocations, which
 * fb_scenario_free releases. Ranges are sc_check_ranges', the rules between
 * values fb_scenario_check's. */
int sc_read(ml_ctx *c, const sch_table *t, struct fy_node *root, fb_symtab *params,
            sch_override *ov, size_t nov, fb_scenario *s);

/* The implausible values of s (scenario_plausible.c), each kept as a
 * located warning in s->warning: sc_plausible_values, each value against
 * its key's plausible range, as soon as s is read (so that an error found
 * later can name them too: a thickness in mm makes the hull's mass wrong);
 * sc_plausible_rules, the consequences of several values, once s is
 * checked and completed. FB_ENOMEM only. */
int sc_plausible_values(fb_scenario *s, fb_err *err);
int sc_plausible_rules(fb_scenario *s, fb_err *err);

/* Where a value of a scenario was written, for errors found after
 * loading. key is the value's logical key path, the one an error's part
 * maps to (sc_part_key): "corners.LF.x", "mounts.driver.mass", "outputs[2]", and
 * for every other value its path in the file ("hull.mass",
 * "road.bump.height"); path is where in the file it was written
 * ("suspensions.axles[0].y", "wheel.mass" for an inherited default).
 * Strings owned by the scenario. */
typedef struct sc_value_origin {
  char *key;
  char *path;
  int line, column; /* 1-based */
  char *override;   /* "--set KEY=VALUE" when an override replaced it, else NULL */
} sc_value_origin;

/* A loaded scenario's source (fb_scenario_source): where each value was
 * written, in reading order, and the values a real vehicle almost never
 * has, each located at its value (fb_scenario_warning). A copy of the
 * scenario copies the origins, not the warnings: it is edited and checked
 * again. */
typedef struct sc_source {
  fb_scenario_source base;
  sc_value_origin *origin;
  size_t norigins;
  fb_err *warning;
  size_t nwarnings;
  sc_schema *schema; /* the table it was read with, shared */
} sc_source;

/* s's source as the loader made it; NULL when it has none or another's. */
sc_source *sc_source_of(const fb_scenario *s);
/* A new, empty source for s (its s->source); FB_ENOMEM. */
int sc_source_new(fb_scenario *s, fb_err *err);

/* The origin of the value with logical key key, or of the nearest value
 * enclosing it ("corners.LF" for "corners.LF.damper_table[2]"), NULL if
 * none; *rest gets the part of key below the origin's. */
const sc_value_origin *sc_origin_find(const fb_scenario *s, const char *key, const char **rest);

/* Every value of s against its key's range in the format's table, in
 * the file's units; the first error located (fb_scenario_locate). */
int sc_check_ranges(const fb_scenario *s, fb_err *err);

/* The logical key of the part of s an error is about (fb_err.part: a
 * member of the scenario, of a corner, ...) into key: the key of the
 * format's table that gives that member, under its item's key
 * ("corners.LF.spring_k", "hull.mesh.generator.bulkheads[1]",
 * "load.points[3]"). 0 when no key gives it, or s has no such item. */
int sc_part_key(const fb_scenario *s, const fb_err_part *p, char *key, size_t size);

/* fb_scenario_locate; with named set, for a message that names its key
 * already (the solver's limits): only "FILE:LINE:COL: " is prefixed. */
int sc_locate(const fb_scenario *s, fb_err *err, int named);

/* Writes the format's key tables (what docs/scenario-format.md holds
 * between its schema:begin and schema:end markers). */
int fb_scenario_schema_markdown(FILE *fp, fb_err *err);

/* Loads a scenario from text as fb_scenario_load_string does, relative
 * file references (a hull deck, a damper table) resolved from base_dir,
 * the galleries of opts (NULL: the built-in ones), with the nov
 * overrides (scenario_override.c; NULL and 0 for none). */
int sc_load(const char *text, size_t len, const char *display_name, const char *base_dir,
            const fb_scenario_load_opts *opts, sch_override *ov, size_t nov, fb_scenario **out,
            fb_err *err);
/* The same for the file at path, its references resolved from its
 * directory. */
int sc_load_file(const char *path, const fb_scenario_load_opts *opts, sch_override *ov,
                 size_t nov, fb_scenario **out, fb_err *err);

/* ---- scenario_override.c. */

/* Each override's path in full: a bare key name ("speed_kmh") becomes
 * the path of the one key of that name the document root has, or the
 * scenario format's table; two overrides of one value are an error. */
int sc_overrides_resolve(const ml_ctx *c, const sch_table *t, struct fy_node *root,
                         sch_override *ov, size_t n);
/* An error of a load with overrides that names none of them (a
 * consequence of their values together) is prefixed with all of them. */
void sc_overrides_blame(fb_err *err, const sch_override *ov, size_t n);

#endif
