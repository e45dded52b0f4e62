/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: how a tire envelops the road, as a gallery of envelope
 * models (docs/tire-envelope.md).
 *
 * A tire of radius 0.5 m does not feel a 0.1 m step as a step: it
 * envelops it over its contact length. An envelope model turns the road
 * under a tire into the effective road the tire's spring meets: from the
 * road sampled on a uniform grid, the effective height w and slope beta
 * at the grid's points. The built-in models are point contact
 * (fb_envelope_model_point: the road as it is), Schmeitz's tandem
 * elliptical cams (fb_envelope_model_cams) and the geometric overlap of
 * the tire's free circle with the road (fb_envelope_model_overlap). A
 * model is content plus ops, as a tire model is (flexbond/tire.h);
 * nothing outside a model's own file asks which model it is.
 *
 * fb_envelope_road_new makes the effective road as a road of its own: a
 * measured profile (fb_road_new_profile) through the effective heights,
 * so that an enveloped road keeps a model-file form. */
#ifndef FLEXBOND_ENVELOPE_H
#define FLEXBOND_ENVELOPE_H

#include <stddef.h>

#include "flexbond/error.h"
#include "flexbond/param.h"
#include "flexbond/road.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The largest parameter block of an envelope model, bytes. */
#define FB_ENVELOPE_PARAMS_MAX ((size_t)8 * sizeof(double))

/* The parameter block a corner holds for its envelope model; its bytes
 * are the model's own struct. A block owns nothing: a corner is copied
 * by value. */
typedef union fb_envelope_params {
  max_align_t align_;
  unsigned char bytes[FB_ENVELOPE_PARAMS_MAX];
} fb_envelope_params;

/* What an envelope model knows of its tire: its free (unloaded) radius
 * (m; > 0 for a model that reaches along the road) and its static
 * deflection under an equal share of the weight (m; 0 when the caller
 * knows none). */
typedef struct fb_envelope_context {
  const char *corner; /* the corner's name, for messages */
  double radius;
  double static_deflection;
} fb_envelope_context;

typedef struct fb_envelope_model fb_envelope_model;

/* The ops of an envelope model. params is the model's block. Errors
 * about one parameter name it in err->part.field (fb_err_set_part with
 * kind 0: the description's checker adds its own kind). */
typedef struct fb_envelope_model_ops {
  /* Fills a new block after the declared defaults are written (NaN for
   * an optional value left out). NULL: nothing more. */
  void (*init)(void *params);
  /* The rules between values (and the tire's radius and deflection)
   * that declared ranges cannot state. NULL: none. */
  int (*check)(const void *params, const fb_envelope_context *ctx, fb_err *err);
  /* How far ahead of and behind its centre the tire reads the road, m:
   * the effective height at s depends on the road over
   * [s - reach, s + reach] only. 0: point contact (the road as it is). */
  double (*reach)(const void *params, const fb_envelope_context *ctx);
  /* The effective road on samples: z[j] is the road's height at
   * s_j = s_0 + j ds (j < n, ds > 0); writes w[i] (effective height, m)
   * and, when beta is not NULL, beta[i] (effective slope, -) at least
   * for every i whose window [s_i - reach, s_i + reach] lies inside the
   * samples (m <= i < n - m, m = ceil(reach / ds)). FB_ENOMEM. */
  int (*filter)(const void *params, const fb_envelope_context *ctx, const double *z, size_t n,
                double ds, double *w, double *beta, fb_err *err);
} fb_envelope_model_ops;

struct fb_envelope_model {
  const char *name; /* letters, digits and '_', not from a digit: "cams" */
  const char *doc;  /* one line */
  /* 1 if it reads the tire's free radius (fb_envelope_context.radius),
   * which a description must then give. */
  int needs_radius;
  /* Its parameters: scalars only (REAL, WHOLE, CHOICE). */
  const fb_param *param;
  size_t nparams;
  size_t params_size; /* <= FB_ENVELOPE_PARAMS_MAX */
  const fb_envelope_model_ops *ops;
};

/* 0 if m is a sound envelope model: a well-formed name and
 * documentation, sound scalar parameter declarations in a block that
 * fits, and reach and filter ops. FB_EINVAL naming the fault
 * otherwise. */
int fb_envelope_model_check(const fb_envelope_model *m, fb_err *err);
/* A new block of model m in *p: zeroed, the declared defaults, then m's
 * init. */
void fb_envelope_params_init(const fb_envelope_model *m, fb_envelope_params *p);

extern const fb_envelope_model fb_envelope_model_point;
extern const fb_envelope_model fb_envelope_model_cams;
extern const fb_envelope_model fb_envelope_model_overlap;

/* The cams' block (Schmeitz 2004; docs/tire-envelope.md). Each cam is
 * the lower half of |x / a_e|^c_e + |z / b_e|^c_e = 1, with
 * a_e = length r0 and b_e = height r0; the two cams stand
 * l_s = shift * contact length apart. */
typedef struct fb_envelope_cams_params {
  double length, height; /* -, of the free radius r0 */
  double order;          /* c_e, - */
  double shift;          /* -, of the contact length */
  double contact_length; /* m; NaN: the chord of the free circle at the static deflection */
} fb_envelope_cams_params;

/* The overlap's block: the reference deflection (m, NaN: the static
 * deflection) at which the free circle's overlap with a flat road is the
 * overlap it keeps on any road. */
typedef struct fb_envelope_overlap_params {
  double deflection;
} fb_envelope_overlap_params;

/* The chord of a circle of radius r cut d above its lowest point,
 * 2 sqrt(2 r d - d^2): the contact length of a rigid circle pressed d
 * into a flat road (d in [0, r]). */
double fb_envelope_chord(double r, double d);

/* The grid an effective road is sampled on, for model m with block
 * params: spacing (m) a 256th of the tire's footprint (2 reach), no
 * coarser than an eighth of the road's shortest wavelength, no finer
 * than a 4096th of the footprint. 0 for point contact. */
double fb_envelope_spacing(const fb_envelope_model *m, const void *params,
                           const fb_envelope_context *ctx, const fb_road *road);

/* Most samples per track of an enveloped road (80 bytes each): 2 km of
 * road at the finest spacing of a 1.2 m footprint. */
#define FB_ENVELOPE_MAX_SAMPLES ((size_t)8000000)

/* The effective road of both tracks of road under a tire of model m
 * with block params, over [s_min, s_max] (m, s_min < s_max) widened to
 * multiples of 64 samples of fb_envelope_spacing, a grid fixed in s (so
 * the same road and tire give the same profile over a stretch whatever
 * the range): a profile (fb_road_new_profile)
 * through the effective heights on the grid of fb_envelope_spacing, held
 * at its end values outside. Point contact
 * (reach 0) gives a copy of road (fb_road_clone). *out new. FB_EINVAL for
 * a bad range or one of more than FB_ENVELOPE_MAX_SAMPLES samples,
 * FB_ENOMEM, and the model's check. */
int fb_envelope_road_new(const fb_road *road, const fb_envelope_model *m, const void *params,
                         const fb_envelope_context *ctx, double s_min, double s_max,
                         fb_road **out, fb_err *err);

/* The effective height w[i] and slope beta[i] (beta may be NULL) of
 * track at s_min + i ds, i < n (ds > 0), under the model: the road
 * sampled at the same spacing around them and the model's filter
 * (point contact: the road's height and slope). FB_ENOMEM. */
int fb_envelope_sample(const fb_road *road, int track, const fb_envelope_model *m,
                       const void *params, const fb_envelope_context *ctx, double s_min,
                       double ds, size_t n, double *w, double *beta, fb_err *err);

/* A set of envelope models: the built-in ones, and those a program adds. */
typedef struct fb_envelope_gallery fb_envelope_gallery;

/* A gallery of the built-in models, point first (*out new). FB_ENOMEM. */
int fb_envelope_gallery_new(fb_envelope_gallery **out, fb_err *err);
/* Adds m (borrowed: it must outlive the gallery and every description
 * that names it). FB_EINVAL when m is not sound (fb_envelope_model_check)
 * or its name is taken. */
int fb_envelope_gallery_add(fb_envelope_gallery *g, const fb_envelope_model *m, fb_err *err);
size_t fb_envelope_gallery_count(const fb_envelope_gallery *g);
/* Model i in the order added (built-ins first), NULL out of range. */
const fb_envelope_model *fb_envelope_gallery_at(const fb_envelope_gallery *g, size_t i);
/* The model named name, NULL if none. */
const fb_envelope_model *fb_envelope_gallery_find(const fb_envelope_gallery *g,
                                                  const char *name);
void fb_envelope_gallery_free(fb_envelope_gallery **g);

#ifdef __cplusplus
}
#endif
#endif
