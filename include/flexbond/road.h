/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: road profiles for the wheeled-vehicle study (docs/roads.md).
 *
 * A road is two vertical profiles z(s), m, of the distance s, m, along a
 * LEFT and a RIGHT track (the paths of the left and right wheels). Every
 * profile but a piecewise one (whose height may jump: fb_road_edges) is
 * continuous, with a continuous slope dz/ds except at the ends
 * of a CSV profile whose end slopes are not 0 (it is held at its end
 * values outside its samples); where its second derivative jumps (bump
 * ends, the ends of a CSV profile, fade-in ends) the road reports a
 * breakpoint so an integrator can stop there. A CSV profile's interior
 * knots are not breakpoints: its slope is continuous there and only the
 * curvature jumps (docs/roads.md).
 *
 * Time convention (constant speed V > 0, straight line): a wheel is at
 * s(t) = s0 + V t on its track, where s0 is its position at t = 0. With
 * the vehicle's reference point (x = 0) at s_ref + V t, a wheel at
 * longitudinal position x (vehicle axes, forward positive) has
 * s0 = s_ref + x, so the wheels of one side meet a feature at s_f at
 * t = (s_f - s_ref - x) / V: the rear wheels later by their spacing.
 *
 * A road is immutable after construction; the time functions it makes
 * hold their own copy of the profile, so the road may be freed first. */
#ifndef FLEXBOND_ROAD_H
#define FLEXBOND_ROAD_H

#include <stddef.h>
#include <stdint.h>

#include "flexbond/error.h"
#include "flexbond/expr.h"
#include "flexbond/param.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The two tracks. */
enum { FB_ROAD_LEFT = 0, FB_ROAD_RIGHT = 1, FB_ROAD_NTRACKS = 2 };

typedef struct fb_road fb_road;

/* ---- (1 - cos) bumps. */

/* One bump per track: z(s) = (h/2)(1 - cos(2 pi (s - s_k) / L)) for
 * s_k <= s <= s_k + L, else 0, where s_k is the track's start (leading
 * edge). height finite (negative: a dip), length > 0, starts finite;
 * FB_EINVAL naming the parameter otherwise. */
int fb_road_new_bump(double height, double length, double start_left, double start_right,
                     fb_road **out, fb_err *err);

/* The paper's oblique bump: the leading edge is a straight line at angle
 * (rad, in (-pi/2, pi/2)) to the lateral axis, crossing the left track at
 * s = 0 and the right track, track_width (> 0, m) to its right, at
 * s = track_width tan(angle): left first for angle > 0. With track_width
 * = y_LF - y_RF this reproduces fb_scenario_road_entry. */
int fb_road_new_oblique_bump(double height, double length, double angle, double track_width,
                             fb_road **out, fb_err *err);

/* Dimensions of a Brazilian speed bump at its maximum height: CONTRAN
 * resolution 39/1998, art. 3, types "I" (1.50 m long, up to 0.08 m high)
 * and "II" (3.70 m, up to 0.10 m); resolution 600/2016 keeps the lengths
 * and maximum heights as its types "B" and "A" (accepted as aliases).
 * FB_EINVAL for any other name. */
int fb_road_speed_bump(const char *type, double *height, double *length, fb_err *err);

/* ---- ISO 8608:2016 random roads. */

/* Most harmonics per track (docs/roads.md, "Limits"). Every road height
 * sums them all, for both tracks at every wheel and every evaluation of
 * the right-hand side, so a run's time grows with them: the reference
 * random-road run takes about 2 s at the default 1024 and 30 s at 16384,
 * and would take hours at a million. 16384 already spaces the default
 * band's harmonics 1.7e-4 cycles/m apart, a road that repeats only after
 * some 6 km. */
#define FB_ROAD_ISO8608_MAX_HARMONICS ((size_t)16384)

typedef struct fb_road_iso8608_params {
  char road_class;    /* 'A' .. 'H' (lower case accepted) */
  uint64_t seed;      /* any value; the same seed gives the same road */
  double n_min;       /* cycles/m, lower end of the band, > 0 */
  double n_max;       /* cycles/m, upper end of the band, > n_min */
  size_t nharmonics;  /* harmonics per track, 1 .. FB_ROAD_ISO8608_MAX_HARMONICS */
  double fade_length; /* m, >= 0: z is 0 for s <= 0 and faded in over
                         [0, fade_length]; 0: no fade, z defined for all s */
  double gd0;         /* m^3: Gd(n0) itself when > 0 (a road given by its
                         r.m.s.: fb_road_iso8608_rms_gd0), else 0: the class's */
} fb_road_iso8608_params;

/* Class 'C', seed 1, band 0.011 .. 2.83 cycles/m, 1024 harmonics, no
 * fade. */
void fb_road_iso8608_defaults(fb_road_iso8608_params *p);

/* The class's geometric-mean displacement PSD at n0 = 0.1 cycles/m,
 * Gd(n0) in m^3: 16e-6 for class A, times 4 for each class after it.
 * FB_EINVAL for a letter outside A .. H. */
int fb_road_iso8608_gd0(char road_class, double *gd0, fb_err *err);

/* p's Gd(n0), m^3: p->gd0 when > 0, else its class's (fb_road_iso8608_gd0). */
int fb_road_iso8608_params_gd0(const fb_road_iso8608_params *p, double *gd0, fb_err *err);

/* The Gd(n0) (m^3) whose PSD Gd(n) = Gd(n0) (n / n0)^-2 holds the mean
 * square rms^2 (rms in m) over [n_min, n_max] (cycles/m):
 * rms^2 = Gd(n0) n0^2 (1 / n_min - 1 / n_max). */
double fb_road_iso8608_rms_gd0(double rms, double n_min, double n_max);

/* The class ('A' .. 'H') whose geometric-mean Gd(n0) is nearest to gd0 on
 * a log scale (ISO 8608's class limits lie halfway between the means on
 * it); 'A' below class A's range, 'H' above class H's. */
char fb_road_iso8608_class_of(double gd0);

/* A random road whose one-sided displacement PSD is the class's
 * Gd(n) = Gd(n0) (n / 0.1)^-2 over [n_min, n_max]: each track is a sum of
 * nharmonics cosines at the midpoints n_k of equal sub-bands of width dn,
 * amplitude sqrt(2 Gd(n_k) dn), and phases uniform in [0, 2 pi) drawn
 * from xoshiro256** seeded through splitmix64 (left track first, then
 * right: independent tracks). FB_EINVAL naming the bad parameter. */
int fb_road_new_iso8608(const fb_road_iso8608_params *p, fb_road **out, fb_err *err);

/* ---- Measured profiles. */

/* Reads a CSV file: a header line naming the columns, then rows of
 * numbers; blank lines and lines starting with '#' are skipped. Columns
 * "s" and "z" (both tracks alike) or "s", "z_left" and "z_right", in any
 * order, no others; s strictly increasing, at least 2 rows. Between knots
 * the profile is the monotone piecewise cubic Hermite interpolant (PCHIP,
 * Fritsch & Carlson 1980), C1; outside [s_first, s_last] it is held at the
 * end value. Errors say "path:line: ..." (FB_EIO: cannot open; FB_EPARSE:
 * malformed content). */
int fb_road_new_csv(const char *path, fb_road **out, fb_err *err);

/* A deep copy of road (*out new). */
int fb_road_clone(const fb_road *road, fb_road **out, fb_err *err);
void fb_road_free(fb_road **road);

/* ---- Piecewise tracks: obstacles of lines, circular arcs and waves
 * (docs/roads.md, "Obstacles").
 *
 * A piecewise track is a list of pieces, each beginning where the one
 * before ends; between pieces the height may jump (a vertical face). The
 * height and slope are exact; every joint is a break. Before the first
 * piece and after the last the track is held at its end heights (slope
 * 0); a track of no pieces is flat at z = 0. At a joint, the piece that
 * begins there holds. */
typedef enum fb_road_piece_kind {
  FB_ROAD_PIECE_LINE, /* z = p[0] + p[1] (s - s_begin) */
  FB_ROAD_PIECE_ARC,  /* a circle of centre (p[0], p[1]) and radius |p[2]|, its upper half
                         (z = p[1] + sqrt(p[2]^2 - (s - p[0])^2)) for p[2] > 0, its lower
                         half for p[2] < 0; the piece lies within p[0] -+ |p[2]| */
  FB_ROAD_PIECE_WAVE  /* z = p[0] + (p[1] + p[2] u) cos(p[3] u + p[4]), u = s - s_begin:
                         a sinusoid of linearly growing amplitude */
} fb_road_piece_kind;

typedef struct fb_road_piece {
  fb_road_piece_kind kind;
  double s_begin, s_end; /* m, s_begin < s_end */
  double p[5];           /* see fb_road_piece_kind; unused ones 0 */
} fb_road_piece;

/* A road of piecewise tracks (n_left pieces left, n_right right; 0: a
 * flat track), copied. FB_EINVAL naming the first piece that is not
 * finite, does not begin where the one before ends, or (an arc) leaves
 * its circle. */
int fb_road_new_pieces(size_t n_left, const fb_road_piece *left, size_t n_right,
                       const fb_road_piece *right, fb_road **out, fb_err *err);

/* Distances s on track where the height jumps or the slope is infinite
 * (a vertical face, a half-round's base), ascending: a point-contact tire
 * cannot follow the road there (its road velocity would be a Dirac or
 * infinite). Returns how many there are; writes at most max of them to s
 * (s may be NULL). 0 for every road that is not piecewise, and for a bad
 * track. */
size_t fb_road_edges(const fb_road *road, int track, double *s, size_t max);

/* ---- Evaluation. track is FB_ROAD_LEFT or FB_ROAD_RIGHT (NaN otherwise). */

/* Height z(s), m. */
double fb_road_height(const fb_road *road, int track, double s);
/* Slope dz/ds, -. */
double fb_road_slope(const fb_road *road, int track, double s);
/* The shortest wavelength of the road's two tracks (m): half a bump's
 * length (the (1 - cos) pulse's spectrum is down 98 % at 2 / length
 * cycles/m), the shortest of a random road's harmonics, twice a profile's
 * closest knot spacing (its Nyquist wavelength). A wheel at speed V meets
 * nothing faster than V / this. */
double fb_road_shortest_wavelength(const fb_road *road);
/* Distances s where the track's second derivative jumps (a CSV profile:
 * its first and last knots, and the knots where a flat stretch meets one
 * that is not; a piecewise track: every joint), ascending.
 * Returns how many there are; writes at most max of them to s (s may be
 * NULL). 0 for a bad track. */
size_t fb_road_breaks(const fb_road *road, int track, double *s, size_t max);

/* Time functions of one wheel on track at s(t) = s0 + speed t (speed > 0,
 * s0 finite): its road height z(s(t)), m, or its road velocity
 * speed * dz/ds(s(t)), m/s (the flow of a road source). Breakpoints at the
 * times the wheel passes the track's breaks. *out is new and holds its own
 * copy of the profile (the road may be freed before it). FB_EINVAL for a
 * bad track, speed or s0. */
int fb_road_wheel_height(const fb_road *road, int track, double speed, double s0, fb_tfun **out,
                         fb_err *err);
int fb_road_wheel_velocity(const fb_road *road, int track, double speed, double s0,
                           fb_tfun **out, fb_err *err);

/* ---- Profiles from data, and wheel functions as data (for model files,
 * docs/model-format.md, "Road sources"). */

/* A measured profile from n >= 2 knots (s[i], z_left[i], z_right[i]),
 * copied: as fb_road_new_csv without the file. FB_EINVAL naming the first
 * knot that is not finite or whose s does not increase. */
int fb_road_new_profile(size_t n, const double *s, const double *z_left, const double *z_right,
                        fb_road **out, fb_err *err);

typedef enum fb_road_wheel_kind {
  FB_ROAD_WHEEL_BUMP,    /* one (1 - cos) bump on the track */
  FB_ROAD_WHEEL_ISO8608, /* a track of an ISO 8608 random road */
  FB_ROAD_WHEEL_PROFILE, /* a measured profile (PCHIP through knots) */
  FB_ROAD_WHEEL_PIECES   /* a piecewise track (fb_road_new_pieces) */
} fb_road_wheel_kind;

/* Everything a wheel function of fb_road_wheel_height or
 * fb_road_wheel_velocity is made of. Pointers borrowed (from the time
 * function described, or the caller's for fb_road_wheel_new). */
typedef struct fb_road_wheel_info {
  int velocity;     /* 1: the road velocity, 0: the height */
  double speed, s0; /* m/s, m: the wheel is at s0 + speed t */
  fb_road_wheel_kind kind;
  double bump_start, bump_height, bump_length; /* BUMP, m */
  fb_road_iso8608_params iso;                  /* ISO8608 */
  int track;                                   /* ISO8608: FB_ROAD_LEFT or FB_ROAD_RIGHT */
  size_t nknots;                               /* PROFILE */
  const double *knot_s, *knot_z;               /* PROFILE, m */
  size_t npieces;                              /* PIECES */
  const fb_road_piece *pieces;                 /* PIECES */
} fb_road_wheel_info;

/* 1 and *out filled when f was made by fb_road_wheel_height or
 * fb_road_wheel_velocity, 0 for any other time function. */
int fb_road_wheel_describe(const fb_tfun *f, fb_road_wheel_info *out);
/* The wheel function that info describes: the same function, value for
 * value and breakpoint for breakpoint, as the one it was described from.
 * *out is new. FB_EINVAL naming a bad parameter. */
int fb_road_wheel_new(const fb_road_wheel_info *info, fb_tfun **out, fb_err *err);

/* ---- The road gallery: road types a vehicle description can name.
 *
 * A road type is content plus ops: its name, one line of documentation,
 * the parameters it reads (flexbond/param.h) from a parameter block of
 * its own (at most FB_ROAD_PARAMS_MAX bytes, held in the description),
 * and what it does with them: check them, make the road (from the
 * primitives above, so that every road has a model-file form), and say
 * where each wheel starts on its track and when it meets the road's
 * feature. Built-in types: fb_road_type_bump, fb_road_type_iso8608,
 * fb_road_type_profile, fb_road_type_crg (docs/roads.md); a program adds its own to a
 * gallery (fb_road_gallery_add) and names them in its descriptions
 * (docs/architecture.md, "Adding a road type"). */

/* Most bytes of a road type's parameter block. */
#define FB_ROAD_PARAMS_MAX ((size_t)256)

/* The parameter block a vehicle description holds for its road type;
 * its bytes are the type's own struct (fb_road_bump_params, ...). */
typedef union fb_road_params {
  max_align_t align_;
  unsigned char bytes[FB_ROAD_PARAMS_MAX];
} fb_road_params;

/* What a road type needs of the vehicle to place the road under it: the
 * speed (m/s, > 0), the track width (m, the first corner's y less that of
 * the first corner on the other side) and the first corner's wheel
 * position (m, vehicle axes). A wheel at y > 0 runs on FB_ROAD_LEFT, else
 * on FB_ROAD_RIGHT. */
typedef struct fb_road_layout {
  double speed;
  double track_width;
  double first_x, first_y;
} fb_road_layout;

typedef struct fb_road_type fb_road_type;

/* The ops of a road type. params is the type's block. Errors about one
 * parameter name it in err->part.field (fb_err_set_part with kind 0: the
 * description's maker adds its own kind). NULL ops are noted. */
typedef struct fb_road_type_ops {
  /* Fills a new block before its maker sets any value (after the
   * declared defaults are written; NULL: nothing more): e.g. NaN for an
   * optional value left out. */
  void (*init)(void *params);
  /* After the maker has set the values: reads what they name (a file)
   * and resolves alternatives (a named bump type into its height and
   * length). NULL: nothing to do. */
  int (*prepare)(void *params, fb_err *err);
  /* The rules between values that declared ranges cannot state, for the
   * vehicle's layout. NULL: none. */
  int (*check)(const void *params, const fb_road_layout *layout, fb_err *err);
  /* The road under the vehicle (*out new). */
  int (*make)(const void *params, const fb_road_layout *layout, fb_road **out, fb_err *err);
  /* Where the wheel at (x, y) is on its track at t = 0, m. */
  double (*wheel_start)(const void *params, const fb_road_layout *layout, double x, double y);
  /* Where the road's feature begins and ends on track, m: a wheel meets
   * it when it reaches *begin and leaves it at *end (INFINITY: never).
   * NULL: from 0 on. */
  void (*feature)(const void *params, const fb_road_layout *layout, int track, double *begin,
                  double *end);
  /* The highest frequency the road puts into a wheel at speed, Hz, when
   * the road knows it better than the speed over its shortest wavelength
   * (fb_road_shortest_wavelength); NULL: that. */
  double (*top_hz)(const void *params, double speed);
  /* The stationary random road it is, for spectral ride analysis: 1 and
   * *out filled, or 0 for a road that is none. NULL: none. */
  int (*random)(const void *params, fb_road_iso8608_params *out);
  /* After a byte copy of a block into to: makes to's owned members its
   * own (strings, data). NULL: the block owns nothing. */
  int (*copy)(void *to, const void *from, fb_err *err);
  /* Frees the block's owned members (the block itself is the holder's).
   * NULL: it owns nothing. */
  void (*release)(void *params);
  /* The road in a report's words: a phrase with its preposition, for
   * "the vehicle ...", "... System 2 departs from System 1" ("over the
   * bump", "on the ISO 8608 class C road"), into buf (n bytes,
   * truncated; it may hold a file's name: escape it for the document).
   * NULL: "on the road". */
  void (*phrase)(const void *params, char *buf, size_t n);
  /* What would let a point-contact tire follow the road where it has
   * edges (fb_road_edges: a vertical face, an infinite slope), for the
   * error that refuses it: "give the step a ramp (ramp_length > 0)".
   * NULL, or a NULL text: the road has no edges. */
  const char *(*edge_hint)(const void *params);
} fb_road_type_ops;

struct fb_road_type {
  const char *name; /* letters, digits and '_', not from a digit: "bump" */
  const char *doc;  /* one line */
  const fb_param *param;
  size_t nparams;
  size_t params_size; /* <= FB_ROAD_PARAMS_MAX */
  const fb_road_type_ops *ops;
};

/* The road of type t with block p in a report's words (t's phrase op,
 * else "on the road"; "on no road" for a NULL t), into buf (n bytes). */
void fb_road_phrase(const fb_road_type *t, const fb_road_params *p, char *buf, size_t n);

/* 0 if t is a sound road type: a well-formed name and documentation,
 * sound parameter declarations (fb_params_declared) in a block that
 * fits, the ops every type must have (make, wheel_start), and copy and
 * release given together. FB_EINVAL naming the fault otherwise. */
int fb_road_type_check(const fb_road_type *t, fb_err *err);

/* A new block of type t in *p: zeroed, the declared defaults, then
 * t's init. */
void fb_road_params_init(const fb_road_type *t, fb_road_params *p);
/* A deep copy of from into *to (a block of type t). FB_ENOMEM. */
int fb_road_params_copy(const fb_road_type *t, fb_road_params *to, const fb_road_params *from,
                        fb_err *err);
/* Frees the owned members of a block of type t (NULL: a block of no
 * type), and zeroes it. A type's release must accept a zeroed block. */
void fb_road_params_release(const fb_road_type *t, fb_road_params *p);

/* The paper's oblique (1 - cos) bump (fb_road_new_oblique_bump), or a
 * Brazilian speed bump of a named type (fb_road_speed_bump). */
typedef struct fb_road_bump_params {
  double height;        /* m, >= 0; NaN: from type */
  double length;        /* m, > 0; NaN: from type */
  int type;             /* index into fb_road_bump_types, -1: height and length given */
  double angle;         /* rad, of the leading edge to the lateral axis, in [0, pi/2) */
  double first_contact; /* s, when the first corner's wheel meets the leading edge */
} fb_road_bump_params;
/* The names fb_road_speed_bump knows, NULL-terminated. */
extern const char *const fb_road_bump_types[];

/* An ISO 8608 random road (fb_road_new_iso8608); the first corner's
 * wheel at front_start on its track at t = 0. */
typedef struct fb_road_random_params {
  int road_class;     /* 0 .. 7: class A .. H; -1: given by rms */
  double rms;         /* m over the band, in place of a class; NaN: by class */
  uint64_t seed;      /* the same seed gives the same road */
  double band[2];     /* cycles/m: n_min, n_max */
  size_t harmonics;   /* per track */
  double fade_in;     /* m */
  double front_start; /* m */
} fb_road_random_params;

/* A measured profile from a CSV file (fb_road_new_csv), read once by
 * prepare; the first corner's wheel at front_start at t = 0. */
typedef struct fb_road_profile_params {
  char *file;         /* owned */
  fb_road *profile;   /* owned, as read */
  double front_start; /* m */
} fb_road_profile_params;

/* An ASAM OpenCRG surface (flexbond/crg.h) read once by prepare: its
 * tracks at v_left and v_right (NaN: +- track_width / 2), sampled along u
 * from u_start (NaN: the surface's first u) at its u increment, z_offset
 * added; the first corner's wheel at front_start at t = 0. */
typedef struct fb_road_crg_params {
  char *file;             /* owned */
  struct fb_crg *crg;     /* owned, as read */
  double front_start;     /* m */
  double z_offset;        /* m */
  double u_start;         /* m */
  double v_left, v_right; /* m */
} fb_road_crg_params;

extern const fb_road_type fb_road_type_bump;
extern const fb_road_type fb_road_type_iso8608;
extern const fb_road_type fb_road_type_profile;
extern const fb_road_type fb_road_type_crg;

/* The obstacles (docs/roads.md, "Obstacles"): a shape on the left track,
 * the right one or both (the other flat), crossed obliquely as the
 * paper's bump (its angle and first_contact), count of them spacing
 * apart. One block for every shape; each type reads the values it
 * declares. */
typedef struct fb_road_obstacle_params {
  double angle;         /* rad, of the leading edge to the lateral axis */
  double first_contact; /* s, when the first corner's wheel meets the leading edge */
  int track;            /* index into fb_road_obstacle_tracks: both, left, right */
  size_t count;         /* obstacles in the series, >= 1 */
  double spacing;       /* m, from one leading edge to the next along a track */
  double height;        /* m: a half-round's, step's (< 0: down), cleat's, trapezoid's */
  double length;        /* m: a cleat's or pothole's length, a trapezoid's top */
  double ramp_length;   /* m, horizontal: a step's, cleat's, trapezoid's (up) ramp */
  double ramp_down;     /* m: a trapezoid's down ramp; NaN: ramp_length */
  double ramp_angle;    /* rad: a trapezoid's ramps instead of lengths; NaN: none */
  double edge_radius;   /* m: a cleat's or trapezoid's top edges rounded */
  double depth;         /* m: a pothole's */
  int shape;            /* a pothole's: index into fb_road_pothole_shapes */
  double amplitude;     /* m: a washboard's */
  double wavelength;    /* m: a washboard's */
  size_t waves;         /* a washboard's full-amplitude waves */
  size_t ramp_waves;    /* waves over which a washboard's amplitude grows, and falls */
} fb_road_obstacle_params;
/* "both", "left", "right", NULL-terminated. */
extern const char *const fb_road_obstacle_tracks[];
/* "rectangular" (vertical walls), "rounded" (a circular dip). */
extern const char *const fb_road_pothole_shapes[];

extern const fb_road_type fb_road_type_halfround;
extern const fb_road_type fb_road_type_step;
extern const fb_road_type fb_road_type_cleat;
extern const fb_road_type fb_road_type_trapezoid;
extern const fb_road_type fb_road_type_pothole;
extern const fb_road_type fb_road_type_washboard;

/* A course: obstacles of the types above, read from a file by prepare
 * (docs/roads.md, "Courses"), one a line: the type's name, `at=` the
 * distance (m) of its leading edge along the course, then its own
 * parameters as key=value by their declared names. The course is crossed
 * obliquely as one, as the bump. */
typedef struct fb_road_course_item fb_road_course_item;
typedef struct fb_road_course_params {
  char *file;                /* owned */
  double angle;              /* rad, of the leading edges to the lateral axis */
  double first_contact;      /* s, when the first corner's wheel meets the course's start */
  fb_road_course_item *item; /* owned, as read */
  size_t nitems;
  char edge_hint[192]; /* the first obstacle with edges' advice, with its line; "" none */
} fb_road_course_params;

extern const fb_road_type fb_road_type_course;

/* A set of road types: the built-in ones, and those a program adds. */
typedef struct fb_road_gallery fb_road_gallery;

/* A gallery of the built-in types (*out new). FB_ENOMEM. */
int fb_road_gallery_new(fb_road_gallery **out, fb_err *err);
/* Adds t (borrowed: it must outlive the gallery and every description
 * that names it). FB_EINVAL when t is not sound (fb_road_type_check) or
 * its name is taken. */
int fb_road_gallery_add(fb_road_gallery *g, const fb_road_type *t, fb_err *err);
size_t fb_road_gallery_count(const fb_road_gallery *g);
/* Type i in the order added (built-ins first), NULL out of range. */
const fb_road_type *fb_road_gallery_at(const fb_road_gallery *g, size_t i);
/* The type named name, NULL if none. */
const fb_road_type *fb_road_gallery_find(const fb_road_gallery *g, const char *name);
void fb_road_gallery_free(fb_road_gallery **g);

#ifdef __cplusplus
}
#endif
#endif
