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

/* Locates an error raised after loading by the model's graph (causality,
 * unconnected ports, fb_bd_build): if err has an origin (fb_err.origin)
 * naming an element or bond of fb_model_graph(m), the message becomes
 * "FILE:LINE:COL: KEY: message", KEY the element's or bond's entry in the
 * file ("elements[3]", "subsystems.corner.bonds[1]"), followed by the
 * subsystem instances it was built in; the origin is then cleared, so a
 * second call changes nothing. m may be NULL. Returns err->code (FB_OK if
 * err is NULL). */
int fb_model_blame(const fb_model *m, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
