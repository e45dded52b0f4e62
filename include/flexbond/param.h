/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: the parameters a gallery entry declares (a road type,
 * flexbond/road.h), in its own words.
 *
 * An entry of a gallery reads its values from a parameter block of its
 * own (a struct it defines). It declares each value once: a name, what
 * kind of value it is, the unit it is written in, its range, whether it
 * must be given or what it defaults to, one line of documentation, and
 * where it goes in the block. A front end maps these declarations to its
 * own format (a scenario file's keys under the entry's section, a
 * Python dict's keys) and fills the block; the library checks the block
 * against them (fb_params_check) and the entry checks the rules between
 * values. Nothing here knows a file format. */
#ifndef FLEXBOND_PARAM_H
#define FLEXBOND_PARAM_H

#include <stddef.h>

#include "flexbond/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The bounds of a value's range: FB_RANGE_LO (lo) and FB_RANGE_HI (hi),
 * each closed or open (_OPEN); none: any finite value. */
enum { FB_RANGE_LO = 1, FB_RANGE_HI = 2, FB_RANGE_LO_OPEN = 4, FB_RANGE_HI_OPEN = 8 };

typedef enum fb_param_kind {
  FB_PARAM_REAL,   /* a finite number; stored as a double */
  FB_PARAM_WHOLE,  /* a whole number in the range; stored as size_t or uint64_t */
  FB_PARAM_CHOICE, /* one of choices; its index is stored as an int */
  FB_PARAM_FILE,   /* a file's path; stored as a char * the block owns */
  FB_PARAM_REALS   /* count finite numbers; stored as count consecutive doubles */
} fb_param_kind;

/* The C type at fb_param.offset. */
typedef enum fb_param_store {
  FB_PARAM_DOUBLE, /* REAL, REALS */
  FB_PARAM_INT,    /* CHOICE */
  FB_PARAM_SIZE,   /* WHOLE */
  FB_PARAM_U64,    /* WHOLE */
  FB_PARAM_STRING  /* FILE */
} fb_param_store;

typedef enum fb_param_need {
  FB_PARAM_REQUIRED, /* must be given */
  FB_PARAM_OPTIONAL, /* may be left out: the entry's defaults op says what that means */
  FB_PARAM_DEFAULT   /* left out: def (or def_list for REALS) */
} fb_param_need;

typedef struct fb_param {
  const char *name; /* letters, digits and '_', not starting with a digit */
  fb_param_kind kind;
  fb_param_store store;
  size_t offset;    /* in the entry's parameter block */
  const char *unit; /* the unit the value is written in, NULL for none */
  /* The stored value is the written one times scale (degrees written,
   * radians stored: pi / 180); 0 means 1. Ranges, defaults and plausible
   * ranges are in the written unit. */
  double scale;
  unsigned range; /* FB_RANGE_* over lo, hi; 0: any finite value */
  double lo, hi;
  fb_param_need need;
  double def;                 /* FB_PARAM_DEFAULT: number, whole or choice index */
  const double *def_list;     /* FB_PARAM_DEFAULT of REALS: count numbers */
  const char *const *choices; /* CHOICE, NULL-terminated */
  size_t count;               /* REALS */
  const char *doc;            /* one line */
  const char *why;            /* why the range is what it is; NULL: not said */
  /* What real vehicles have (a value outside is legal but almost never
   * meant: a warning); plausible_why NULL: no such range. */
  double plausible_lo, plausible_hi;
  const char *plausible_why;
} fb_param;

/* 0 if the declarations p[0 .. n) are sound for a block of block_size
 * bytes: names well formed and unique, each store fits its kind and lies
 * inside the block, every value documented, choices given, defaults
 * inside their ranges. FB_EINVAL naming the first fault otherwise
 * (err->part.field: the parameter's name). */
int fb_params_declared(const fb_param *p, size_t n, size_t block_size, fb_err *err);

/* 1 if every value of p[0 .. n) is a scalar that owns nothing (REAL,
 * WHOLE, CHOICE): a block of them is copied by value and read as one
 * number per key (a corner's tire or damper). */
int fb_params_scalar(const fb_param *p, size_t n);
/* Writes the declared defaults (FB_PARAM_DEFAULT) into block; leaves the
 * other values as they are. */
void fb_params_defaults(const fb_param *p, size_t n, void *block);

/* Checks every number of block against its declared range (finite, and
 * within it in the written unit), every choice against its choices, and
 * every REQUIRED file for a name. FB_EINVAL at the first value outside
 * ("must be > 0, got -1"), its name in err->part.field (kind and index
 * are the caller's to set). */
int fb_params_check(const fb_param *p, size_t n, const void *block, fb_err *err);

#ifdef __cplusplus
}
#endif

#endif
