/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: a suspension's shock absorber, as a gallery of damper laws.
 *
 * A damper law is content plus ops, like a tire model (flexbond/tire.h):
 * its name, one line of documentation, a phrase for a report, its own
 * parameters declared in its own words (flexbond/param.h), and ops that
 * check its values, build the corner's R element "damper" (force against
 * the spring's travel rate, compression positive) and give its force at
 * a velocity. The built-in laws are the paper's linear damper
 * (fb_damper_law_linear) and a passive force-velocity table
 * (fb_damper_law_table, fb_table_law); a program adds its own to an
 * fb_damper_gallery. Nothing outside a law's own file asks which law it
 * is: a caller reads its content and calls its ops. */
#ifndef FLEXBOND_DAMPER_H
#define FLEXBOND_DAMPER_H

#include <stddef.h>

#include "flexbond/bg.h"
#include "flexbond/error.h"
#include "flexbond/param.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most points of a shock absorber's force-velocity table. */
enum { FB_DAMPER_MAX_POINTS = 64 };

/* The largest parameter block of a damper law, bytes: room for a table
 * of FB_DAMPER_MAX_POINTS knots. */
#define FB_DAMPER_PARAMS_MAX ((size_t)(2 * FB_DAMPER_MAX_POINTS + 2) * sizeof(double))

/* The parameter block a corner holds for its damper law; its bytes are
 * the law's own struct. A block owns nothing: a corner is copied by
 * value. */
typedef union fb_damper_params {
  max_align_t align_;
  unsigned char bytes[FB_DAMPER_PARAMS_MAX];
} fb_damper_params;

typedef struct fb_damper_law fb_damper_law;

/* The ops of a damper law. params is the law's block. Errors about one
 * parameter name it in err->part.field (fb_err_set_part with kind 0: the
 * description's checker adds its own kind). */
typedef struct fb_damper_law_ops {
  /* Fills a new block after the declared defaults are written. NULL:
   * nothing more. */
  void (*init)(void *params);
  /* The rules between values that declared ranges cannot state (a
   * table's knots); corner names the corner for messages. NULL: none. */
  int (*check)(const void *params, const char *corner, fb_err *err);
  /* Adds the one-port R element "damper" to bg: its effort the force
   * (N), its flow the travel rate (m/s), compression positive. */
  int (*build)(const void *params, fb_bg *bg, fb_err *err);
  /* The force (N) at travel rate v (m/s): the law's closed form, for a
   * report and for a harness to hold the built element to. */
  double (*force)(const void *params, double v);
  /* 1 when the force is linear in the velocity with these values, so
   * that a linear analysis (modes, frequency response, export) uses the
   * law as it is; 0 when the analysis linearises it at the static
   * equilibrium. NULL: never linear. */
  int (*linear)(const void *params);
  /* One line for a report describing these values ("25744 N s/m"),
   * into buf of size bytes. NULL: the law's meaning alone. */
  void (*describe)(const void *params, char *buf, size_t size);
} fb_damper_law_ops;

struct fb_damper_law {
  const char *name;    /* letters, digits and '_', not from a digit: "linear" */
  const char *doc;     /* one line */
  const char *meaning; /* what the law is, a report's phrase */
  /* Its parameters, scalars only (REAL, WHOLE, CHOICE): what a front end
   * reads into the block by name. A law with values of another shape (a
   * table's knots) declares none and documents its block's struct. */
  const fb_param *param;
  size_t nparams;
  size_t params_size; /* <= FB_DAMPER_PARAMS_MAX */
  const fb_damper_law_ops *ops;
};

/* 0 if l is a sound damper law: a well-formed name, documentation and
 * meaning, sound scalar parameter declarations in a block that fits,
 * and build and force ops. FB_EINVAL naming the fault otherwise. */
int fb_damper_law_check(const fb_damper_law *l, fb_err *err);
/* A new block of law l in *p: zeroed, the declared defaults, then l's
 * init. */
void fb_damper_params_init(const fb_damper_law *l, fb_damper_params *p);

extern const fb_damper_law fb_damper_law_linear;
extern const fb_damper_law fb_damper_law_table;

/* The linear law's block: F = c v. */
typedef struct fb_damper_linear_params {
  double c; /* N s/m, >= 0 */
} fb_damper_linear_params;

/* The table law's block: force (N) against velocity (m/s, compression
 * positive) at npoints knots (2 .. FB_DAMPER_MAX_POINTS, velocities
 * increasing), a passive law interpolated with a continuous slope
 * (fb_table_law). */
typedef struct fb_damper_table_params {
  size_t npoints;
  double velocity[FB_DAMPER_MAX_POINTS], force[FB_DAMPER_MAX_POINTS];
} fb_damper_table_params;

/* A set of damper laws: the built-in ones, and those a program adds. */
typedef struct fb_damper_gallery fb_damper_gallery;

/* A gallery of the built-in laws, linear first (*out new). FB_ENOMEM. */
int fb_damper_gallery_new(fb_damper_gallery **out, fb_err *err);
/* Adds l (borrowed: it must outlive the gallery and every description
 * that names it). FB_EINVAL when l is not sound (fb_damper_law_check) or
 * its name is taken. */
int fb_damper_gallery_add(fb_damper_gallery *g, const fb_damper_law *l, fb_err *err);
size_t fb_damper_gallery_count(const fb_damper_gallery *g);
/* Law i in the order added (built-ins first), NULL out of range. */
const fb_damper_law *fb_damper_gallery_at(const fb_damper_gallery *g, size_t i);
/* The law named name, NULL if none. */
const fb_damper_law *fb_damper_gallery_find(const fb_damper_gallery *g, const char *name);
void fb_damper_gallery_free(fb_damper_gallery **g);

#ifdef __cplusplus
}
#endif
#endif
