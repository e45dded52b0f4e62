/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: a suspension's spring, as a gallery of spring laws.
 *
 * A spring law is content plus ops, like a damper law
 * (flexbond/damper.h): its name, one line of documentation, a phrase for
 * a report, its own parameters declared in its own words
 * (flexbond/param.h), and ops that check its values, build the corner's
 * C element "spring" (force against the spring's travel, compression
 * positive, its state the travel) and give its force at a travel. The
 * built-in laws are the paper's linear spring with an optional preload
 * (fb_spring_law_linear) and a force-travel table (fb_spring_law_table,
 * fb_table_law); a program adds its own to an fb_spring_gallery. Nothing
 * outside a law's own file asks which law it is.
 *
 * The travel is the C element's state: 0 at the start of a run from
 * FB_INITIAL_ZERO, where the force is the law's preload (its value at 0),
 * and the static equilibrium's travel under FB_INITIAL_STATIC, where the
 * law's force balances the corner's share of the weight. */
#ifndef FLEXBOND_SPRING_H
#define FLEXBOND_SPRING_H

#include <stddef.h>

#include "flexbond/bg.h"
#include "flexbond/error.h"
#include "flexbond/param.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most points of a spring's force-travel table. */
enum { FB_SPRING_MAX_POINTS = 64 };

/* The largest parameter block of a spring law, bytes: room for a table
 * of FB_SPRING_MAX_POINTS knots. */
#define FB_SPRING_PARAMS_MAX ((size_t)(2 * FB_SPRING_MAX_POINTS + 2) * sizeof(double))

/* The parameter block a corner holds for its spring law; its bytes are
 * the law's own struct. A block owns nothing: a corner is copied by
 * value. */
typedef union fb_spring_params {
  max_align_t align_;
  unsigned char bytes[FB_SPRING_PARAMS_MAX];
} fb_spring_params;

/* What a spring law knows of its corner: its name (for messages) and its
 * rate spring_k (N/m), the linear law's stiffness. */
typedef struct fb_spring_context {
  const char *corner;
  double spring_k;
} fb_spring_context;

typedef struct fb_spring_law fb_spring_law;

/* The ops of a spring law. params is the law's block. Errors about one
 * parameter name it in err->part.field (fb_err_set_part with kind 0: the
 * description's checker adds its own kind). */
typedef struct fb_spring_law_ops {
  /* Fills a new block after the declared defaults are written. NULL:
   * nothing more. */
  void (*init)(void *params);
  /* The rules between values that declared ranges cannot state (a
   * table's knots). NULL: none. */
  int (*check)(const void *params, const fb_spring_context *ctx, fb_err *err);
  /* Adds the one-port C element "spring" to bg: its effort the force
   * (N), its state the travel (m), compression positive. */
  int (*build)(const void *params, const fb_spring_context *ctx, fb_bg *bg, fb_err *err);
  /* The force (N) at travel x (m): the law's closed form, for a report
   * and for a harness to hold the built element to. */
  double (*force)(const void *params, const fb_spring_context *ctx, double x);
  /* One line for a report describing these values, into buf of size
   * bytes. NULL: the law's meaning alone. */
  void (*describe)(const void *params, const fb_spring_context *ctx, char *buf, size_t size);
} fb_spring_law_ops;

struct fb_spring_law {
  const char *name;    /* letters, digits and '_', not from a digit: "linear" */
  const char *doc;     /* one line */
  const char *meaning; /* what the law is, a report's phrase */
  /* Its parameters, scalars only (REAL, WHOLE, CHOICE). A law with values
   * of another shape (a table's knots) declares none and documents its
   * block's struct. */
  const fb_param *param;
  size_t nparams;
  size_t params_size; /* <= FB_SPRING_PARAMS_MAX */
  const fb_spring_law_ops *ops;
};

/* 0 if l is a sound spring law: a well-formed name, documentation and
 * meaning, sound scalar parameter declarations in a block that fits,
 * and build and force ops. FB_EINVAL naming the fault otherwise. */
int fb_spring_law_check(const fb_spring_law *l, fb_err *err);
/* A new block of law l in *p: zeroed, the declared defaults, then l's
 * init. */
void fb_spring_params_init(const fb_spring_law *l, fb_spring_params *p);

extern const fb_spring_law fb_spring_law_linear;
extern const fb_spring_law fb_spring_law_table;

/* The linear law's block: F = preload + spring_k x. */
typedef struct fb_spring_linear_params {
  double preload; /* N, the force at zero travel */
} fb_spring_linear_params;

/* The table law's block: force (N) against travel (m, compression
 * positive) at npoints knots (2 .. FB_SPRING_MAX_POINTS, travels
 * increasing, forces not decreasing), interpolated monotonically with a
 * continuous slope (fb_table_law) and continued along its end tangents.
 * Its preload is its value at zero travel. */
typedef struct fb_spring_table_params {
  size_t npoints;
  double travel[FB_SPRING_MAX_POINTS], force[FB_SPRING_MAX_POINTS];
} fb_spring_table_params;

/* A set of spring laws: the built-in ones, and those a program adds. */
typedef struct fb_spring_gallery fb_spring_gallery;

/* A gallery of the built-in laws, linear first (*out new). FB_ENOMEM. */
int fb_spring_gallery_new(fb_spring_gallery **out, fb_err *err);
/* Adds l (borrowed: it must outlive the gallery and every description
 * that names it). FB_EINVAL when l is not sound (fb_spring_law_check) or
 * its name is taken. */
int fb_spring_gallery_add(fb_spring_gallery *g, const fb_spring_law *l, fb_err *err);
size_t fb_spring_gallery_count(const fb_spring_gallery *g);
/* Law i in the order added (built-ins first), NULL out of range. */
const fb_spring_law *fb_spring_gallery_at(const fb_spring_gallery *g, size_t i);
/* The law named name, NULL if none. */
const fb_spring_law *fb_spring_gallery_find(const fb_spring_gallery *g, const char *name);
void fb_spring_gallery_free(fb_spring_gallery **g);

#ifdef __cplusplus
}
#endif
#endif
