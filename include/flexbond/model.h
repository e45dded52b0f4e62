/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: bond-graph model files (YAML, format in docs/model-format.md).
 *
 * A model file declares parameters, elements, bonds, reusable subsystems
 * with ports, sources as time functions, probes and solver settings. Every
 * error names the file, line and column and the offending key, e.g.
 * "quarter_car.yaml:14:9: elements[3].m: must be > 0 (got -250)". */
#ifndef FLEXBOND_MODEL_H
#define FLEXBOND_MODEL_H

#include <stddef.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"
#include "flexbond/error.h"
#include "flexbond/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fb_model fb_model;

/* Loads and validates the model at path. Relative file references inside
 * it (tables, Matrix Market files) are resolved from its directory. */
int fb_model_load(const char *path, fb_model **out, fb_err *err);
/* Same from a string; display_name is used in messages, base_dir (may be
 * NULL for ".") resolves relative file references. */
int fb_model_load_string(const char *text, size_t len, const char *display_name,
                         const char *base_dir, fb_model **out, fb_err *err);
void fb_model_free(fb_model **m);

const char *fb_model_name(const fb_model *m);
/* The graph, owned by the model. */
fb_bg *fb_model_graph(fb_model *m);
/* Probe specifications, owned by the model. */
const fb_probe_spec *fb_model_probes(const fb_model *m, size_t *nprobes);
/* Solver settings from the model's `simulation` section (defaults where
 * absent); borrowed pointers inside stay valid while m lives. */
const fb_sim_opts *fb_model_sim_opts(const fb_model *m);

/* Warnings of the load: what the file may legally say but almost never
 * means, each located as an error would be (fb_err.file, line, column,
 * key; msg "FILE:LINE:COL: KEY: ..."; code the status it would have as an
 * error). Today one kind: a bond whose from end is an I, C or R element:
 * the motion is the same, but the element's state and the bond's effort
 * and power read with the opposite sign to the usual drawing, or, for
 * a nonlinear law (a table, a contact), compression and extension swap
 * and the motion differs (docs/model-format.md, "Power direction"); the
 * bonds of
 * all instances of one subsystem definition make one warning. The CLI
 * prints them to stderr and goes on. fb_model_warning returns NULL for
 * i >= fb_model_nwarnings(m); the value is owned by m. */
size_t fb_model_nwarnings(const fb_model *m);
const fb_err *fb_model_warning(const fb_model *m, size_t i);

/* The initial state a model's run starts from (`simulation.initial`). */
typedef enum fb_model_initial {
  FB_MODEL_INITIAL_GIVEN, /* the elements' `initial` values, 0 where absent (default) */
  FB_MODEL_INITIAL_ZERO,  /* every state 0, whatever the elements say */
  FB_MODEL_INITIAL_STATIC /* the static equilibrium reached from the given state at
                             t_start (fb_sim_static_state) */
} fb_model_initial;
fb_model_initial fb_model_initial_choice(const fb_model *m);
/* Fills x0 (fb_bd_nstates(bd) values) with the state a run of bd, built
 * from m's graph and probes, starts from; pass it as fb_sim_opts.x0.
 * FB_ESOLVER (prefixed "simulation.initial: static: ") when the
 * equilibrium is not found. */
int fb_model_initial_state(const fb_model *m, fb_bd *bd, double *x0, fb_err *err);

/* Writes graph bg, its probes and solver settings as one model file,
 * DIR/NAME.yaml (docs/model-format.md), and every field or MTF matrix
 * with more than FB_MODEL_INLINE_MAX entries as a Matrix Market file
 * beside it (DIR/NAME.ELEMENT.mtx, ELEMENT's dots made '-'), numbers in
 * %.17g so that loading the file (fb_model_load) rebuilds the same graph
 * value for value. Subsystem instances of bg (elements "inst.x") become
 * `subsystems` definitions, one per distinct content, instantiated under
 * their instance names, so every element and bond keeps its name and the
 * probes their targets. name must be a model name (letters, digits, '_',
 * not starting with a digit); dir must exist. Each file is written
 * atomically; on failure the files already written are removed. On
 * success *files (if not NULL) gets the names written, relative to dir
 * (fresh memory: free each and the array), *nfiles their count.
 * Expressions of t are written back with fb_expr_write. FB_EINVAL naming
 * the element or probe for what the format cannot hold: a source that is
 * a C callback other than a road wheel,
 * a nonlinear law other than a table or contact, a name or text with a
 * control character, an unnamed bond whose name cannot be remade; FB_EIO
 * on write errors. opts: t_start, t_end, rtol, atol, max_step,
 * sample_rate, max_order, max_steps, breakpoints (x0 and callbacks are
 * not written). */
#define FB_MODEL_INLINE_MAX 16
int fb_model_write(const fb_bg *bg, const fb_probe_spec *probes, size_t nprobes,
                   const fb_sim_opts *opts, fb_model_initial initial, const char *dir,
                   const char *name, char ***files, size_t *nfiles, fb_err *err);

/* Locates an error raised after loading by the model's graph (causality,
 * unconnected ports, fb_bd_build): if err has an origin (fb_err.origin)
 * naming an element or bond of fb_model_graph(m), the message becomes
 * "FILE:LINE:COL: KEY: message", KEY the element's or bond's entry in the
 * file ("elements[3]", "subsystems.corner.bonds[1]"), followed by the
 * subsystem instances it was built in; the origin is then cleared, so a
 * second call changes nothing. m may be NULL. Returns err->code (FB_OK if
 * err is NULL). */
int fb_model_blame(const fb_model *m, fb_err *err);

/* ---- A model file's simulation (src/io/model_sim.c), as `flexbond sim`
 * runs it and the Python package: the block diagram of its graph with its
 * probes as the result's columns, started from simulation.initial. */
typedef struct fb_model_sim fb_model_sim;

/* The block diagram of m's graph and probes and the state its runs start
 * from (fb_model_initial_state). Assigns the graph's causality, which
 * changes m; an error of the graph is located in m's file
 * (fb_model_blame). m must outlive *out (new; fb_model_sim_free). */
int fb_model_sim_new(fb_model *m, fb_model_sim **out, fb_err *err);
void fb_model_sim_free(fb_model_sim **ms);
/* The block diagram (owned by ms). */
const fb_bd *fb_model_sim_diagram(const fb_model_sim *ms);
/* m's solver settings (fb_model_sim_opts) with t_end, rtol and
 * sample_rate replaced by those given above 0, and noutputs its probes'
 * count, so that fb_sim_opts_check bounds the result's memory. */
fb_sim_opts fb_model_sim_opts_with(const fb_model *m, double t_end, double rtol,
                                   double sample_rate);
/* Runs ms's diagram with opts (its x0 replaced by the model's initial
 * state) into *res (new; fb_result_free); errors as fb_sim_run's. */
int fb_model_sim_run(fb_model_sim *ms, const fb_sim_opts *opts, fb_result **res, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
