/* Internal representation of road tracks, shared by the road's
 * constructors (bump.c, iso8608.c, road_csv.c) and its evaluation and time
 * functions (road.c).
 *
 * A track is a small header plus an array of doubles whose layout depends
 * on the kind. Both are plain data, so a wheel's time function can copy a
 * whole track into one contiguous block (fb_tfun_new_callback_copy). */
#ifndef FLEXBOND_ROAD_INTERNAL_H
#define FLEXBOND_ROAD_INTERNAL_H

#include <stddef.h>

#include "flexbond/road.h"

typedef enum road_kind {
  ROAD_BUMP,      /* param: start, height, length; no data */
  ROAD_HARMONICS, /* param[0]: fade length, param[1]: wavenumber of harmonic
                     0, param[2]: wavenumber step (rad/m; harmonic k has
                     param[1] + k param[2]); data: A_k cos(phi_k)[n],
                     A_k sin(phi_k)[n] (m) */
  ROAD_PCHIP      /* data: s[n], z[n], dz/ds[n] at the knots, n >= 2 */
} road_kind;

typedef struct road_track {
  road_kind kind;
  size_t n;        /* harmonics or knots; 0 for a bump */
  double param[3]; /* see road_kind */
} road_track;

struct fb_road {
  road_track track[FB_ROAD_NTRACKS];
  double *data[FB_ROAD_NTRACKS]; /* owned; NULL for a bump */
};

/* Number of doubles in a track's data array. */
size_t road_track_ndata(const road_track *t);

/* A new road with data arrays of the sizes the two track headers imply
 * (headers copied; data left for the caller to fill). FB_ENOMEM. */
int road_alloc(const road_track *left, const road_track *right, fb_road **out, fb_err *err);

double road_track_height(const road_track *t, const double *data, double s);
double road_track_slope(const road_track *t, const double *data, double s);

/* Cubic Hermite interpolation on knots (s, z) with slopes d (n >= 2),
 * held at the end values outside [s[0], s[n-1]]. */
double road_pchip_height(size_t n, const double *s, const double *z, const double *d, double x);
double road_pchip_slope(size_t n, const double *s, const double *z, const double *d, double x);
/* Fills d[n] with the monotone (Fritsch-Carlson) slopes for knots (s, z),
 * n >= 2, s strictly increasing. */
void road_pchip_slopes(size_t n, const double *s, const double *z, double *d);

#endif
