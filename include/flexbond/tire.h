/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: how a tire meets the road, as a gallery of tire models.
 *
 * A tire model is content plus ops, like a road type (flexbond/road.h):
 * its name, one line of documentation, a phrase for a report, its own
 * parameters declared in its own words (flexbond/param.h), and ops that
 * check its values and build the tire's two elements into a corner's
 * bond graph. The built-in models are the paper's linear tire
 * (fb_tire_model_bilateral), the same pair unable to pull
 * (fb_tire_model_unilateral), a Hunt-Crossley tire whose damping grows
 * with the deflection (fb_tire_model_hunt_crossley) and a unilateral tire
 * of a force-deflection table (fb_tire_model_table); a program adds its
 * own to an fb_tire_gallery. Nothing outside a model's own file asks
 * which model it is: a caller reads its content and calls its ops. */
#ifndef FLEXBOND_TIRE_H
#define FLEXBOND_TIRE_H

#include <stddef.h>

#include "flexbond/bg.h"
#include "flexbond/error.h"
#include "flexbond/param.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most points of a tire's force-deflection table. */
enum { FB_TIRE_MAX_POINTS = 64 };

/* The largest parameter block of a tire model, bytes: room for a table
 * of FB_TIRE_MAX_POINTS knots. */
#define FB_TIRE_PARAMS_MAX ((size_t)(2 * FB_TIRE_MAX_POINTS + 2) * sizeof(double))

/* The parameter block a corner holds for its tire model; its bytes are
 * the model's own struct. A block owns nothing: a corner is copied by
 * value. */
typedef union fb_tire_params {
  max_align_t align_;
  unsigned char bytes[FB_TIRE_PARAMS_MAX];
} fb_tire_params;

/* What a tire model knows of its corner: the tire's stiffness and
 * damping (N/m, N s/m) and its static deflection under an equal share
 * of the weight on the tires (m; 0 when the caller knows none). */
typedef struct fb_tire_context {
  const char *corner; /* the corner's name, for messages */
  double tire_k, tire_c;
  double static_deflection;
} fb_tire_context;

typedef struct fb_tire_model fb_tire_model;

/* The ops of a tire model. params is the model's block. Errors about one
 * parameter name it in err->part.field (fb_err_set_part with kind 0: the
 * description's checker adds its own kind). NULL ops are noted. */
typedef struct fb_tire_model_ops {
  /* Fills a new block after the declared defaults are written (NaN for
   * an optional value left out). NULL: nothing more. */
  void (*init)(void *params);
  /* The rules between values that declared ranges cannot state. NULL:
   * none. */
  int (*check)(const void *params, const fb_tire_context *ctx, fb_err *err);
  /* Adds the C element "tire_spring" and the R element "tire_damper" to
   * bg (the corner's fragment bonds them in parallel on the tire's
   * 1-junction: compression positive). */
  int (*build)(const void *params, const fb_tire_context *ctx, fb_bg *bg, fb_err *err);
} fb_tire_model_ops;

struct fb_tire_model {
  const char *name;    /* letters, digits and '_', not from a digit: "unilateral" */
  const char *doc;     /* one line */
  const char *meaning; /* what a reaction of this tire means, a report's phrase */
  /* 1 if the tire can pull the wheel down: its reaction may be tensile
   * where another tire would have left the road. */
  int pulls;
  /* 1 if its damping is zero at first contact, so that a landing wheel
   * meets no damper force at once. */
  int soft_landing;
  /* The model a linear analysis uses in its place (its branch while in
   * contact, at rest), with a block of defaults; NULL: this model. */
  const fb_tire_model *in_contact;
  /* Its parameters: scalars only (REAL, WHOLE, CHOICE). */
  const fb_param *param;
  size_t nparams;
  size_t params_size; /* <= FB_TIRE_PARAMS_MAX */
  const fb_tire_model_ops *ops;
};

/* 0 if m is a sound tire model: a well-formed name, documentation and
 * meaning, sound scalar parameter declarations (fb_params_declared) in
 * a block that fits, and a build op. FB_EINVAL naming the fault
 * otherwise. */
int fb_tire_model_check(const fb_tire_model *m, fb_err *err);
/* A new block of model m in *p: zeroed, the declared defaults, then m's
 * init. */
void fb_tire_params_init(const fb_tire_model *m, fb_tire_params *p);

extern const fb_tire_model fb_tire_model_bilateral;
extern const fb_tire_model fb_tire_model_unilateral;
extern const fb_tire_model fb_tire_model_hunt_crossley;
extern const fb_tire_model fb_tire_model_table;

/* Hunt-Crossley's block: the deflection at which the damping is tire_c
 * (m, > 0; NaN: the static deflection). */
typedef struct fb_tire_hunt_crossley_params {
  double deflection_ref;
} fb_tire_hunt_crossley_params;

/* The table model's block: the tire's force (N) against its deflection
 * (m) at npoints knots (2 .. FB_TIRE_MAX_POINTS) from (0, 0),
 * deflections increasing and forces not decreasing, interpolated
 * monotonically (fb_table_law) and continued along its last tangent;
 * unilateral as fb_tire_model_unilateral, damped by tire_c in contact. */
typedef struct fb_tire_table_params {
  size_t npoints;
  double deflection[FB_TIRE_MAX_POINTS], force[FB_TIRE_MAX_POINTS];
} fb_tire_table_params;

/* A set of tire models: the built-in ones, and those a program adds. */
typedef struct fb_tire_gallery fb_tire_gallery;

/* A gallery of the built-in models, bilateral first (*out new).
 * FB_ENOMEM. */
int fb_tire_gallery_new(fb_tire_gallery **out, fb_err *err);
/* Adds m (borrowed: it must outlive the gallery and every description
 * that names it). FB_EINVAL when m is not sound (fb_tire_model_check) or
 * its name is taken. */
int fb_tire_gallery_add(fb_tire_gallery *g, const fb_tire_model *m, fb_err *err);
size_t fb_tire_gallery_count(const fb_tire_gallery *g);
/* Model i in the order added (built-ins first), NULL out of range. */
const fb_tire_model *fb_tire_gallery_at(const fb_tire_gallery *g, size_t i);
/* The model named name, NULL if none. */
const fb_tire_model *fb_tire_gallery_find(const fb_tire_gallery *g, const char *name);
void fb_tire_gallery_free(fb_tire_gallery **g);

#ifdef __cplusplus
}
#endif
#endif
