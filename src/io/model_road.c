/* SPDX-License-Identifier: BSD-3-Clause */
/* Road sources in model files: `value: {road: {...}}`, the vertical
 * velocity (or height) of the road under a wheel moving at constant speed
 * along a (1 - cos) bump, an ISO 8608 random road, a measured profile or
 * a piecewise track of obstacles (flexbond/road.h; docs/model-format.md, "Road sources"). The
 * function is rebuilt by fb_road_wheel_new, so it is the one a vehicle scenario makes,
 * breakpoints included. */
#include <stdlib.h>
#include <string.h>

#include "flexbond/road.h"

#include "io/model_internal.h"

/* Largest seed read exactly: seeds are numbers, read as doubles. */
#define ML_SEED_MAX ((size_t)1 << 53)

static int ml_road_bump(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                        fb_road_wheel_info *w)
{
  static const char *const keys[] = {"at", "height", "length", NULL};
  struct fy_node *v = NULL;
  w->kind = FB_ROAD_WHEEL_BUMP;
  int rc = ml_expect_map(c, n, "a bump {at, height, length}");
  if (!rc)
    rc = ml_check_keys(c, n, keys);
  if (!rc)
    rc = ml_require(c, n, "height", &v);
  if (!rc)
    rc = ml_number(c, v, syms, &w->bump_height);
  if (!rc)
    rc = ml_require(c, n, "length", &v);
  if (!rc)
    rc = ml_number(c, v, syms, &w->bump_length);
  if (!rc && !(w->bump_length > 0))
    rc = ml_fail(c, v, FB_EINVAL, "must be > 0 m (got %g)", w->bump_length);
  if (!rc)
    rc = ml_opt_number(c, n, "at", syms, &w->bump_start);
  return rc;
}

/* `track: left | right`. */
static int ml_road_track(const ml_ctx *c, struct fy_node *map, int *track)
{
  struct fy_node *v = ml_get(map, "track", NULL);
  const char *text = NULL;
  *track = FB_ROAD_LEFT;
  int rc = v ? ml_string(c, v, &text) : FB_OK;
  if (rc || !v)
    return rc;
  if (!strcmp(text, "left") || !strcmp(text, "right")) {
    *track = text[0] == 'l' ? FB_ROAD_LEFT : FB_ROAD_RIGHT;
    return FB_OK;
  }
  return ml_fail(c, v, FB_EPARSE, "expected left or right (got '%s')", text);
}

static int ml_road_iso(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                       fb_road_wheel_info *w)
{
  static const char *const keys[] = {"class",       "seed",  "n_min", "n_max", "harmonics",
                                     "fade_length", "track", "gd0",   NULL};
  struct fy_node *v = NULL;
  const char *cls = NULL;
  size_t count = 0;
  w->kind = FB_ROAD_WHEEL_ISO8608;
  fb_road_iso8608_defaults(&w->iso);
  int rc = ml_expect_map(c, n,
                         "an ISO 8608 road {class, seed, n_min, n_max, harmonics, "
                         "fade_length, track, gd0}");
  if (!rc)
    rc = ml_check_keys(c, n, keys);
  if (!rc)
    rc = ml_require(c, n, "class", &v);
  if (!rc)
    rc = ml_string(c, v, &cls);
  if (!rc && strlen(cls) != 1)
    rc = ml_fail(c, v, FB_EINVAL, "expected one letter A to H (got '%s')", cls);
  if (!rc)
    w->iso.road_class = cls[0];
  if (!rc && (v = ml_get(n, "seed", NULL)) &&
      !(rc = ml_count(c, v, syms, 0, ML_SEED_MAX, &count)))
    w->iso.seed = (uint64_t)count;
  if (!rc)
    rc = ml_opt_number(c, n, "n_min", syms, &w->iso.n_min);
  if (!rc)
    rc = ml_opt_number(c, n, "n_max", syms, &w->iso.n_max);
  if (!rc && (v = ml_get(n, "harmonics", NULL)))
    rc = ml_count(c, v, syms, 1, FB_ROAD_ISO8608_MAX_HARMONICS, &w->iso.nharmonics);
  if (!rc)
    rc = ml_opt_number(c, n, "fade_length", syms, &w->iso.fade_length);
  if (!rc)
    rc = ml_opt_number(c, n, "gd0", syms, &w->iso.gd0);
  if (!rc)
    rc = ml_road_track(c, n, &w->track);
  return rc;
}

/* `profile: {points: [[s, z], ...]}`; the knots go into *s (s then z,
 * owned by the caller). */
static int ml_road_profile(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                           fb_road_wheel_info *w, double **knots)
{
  static const char *const keys[] = {"points", NULL};
  struct fy_node *pts = NULL;
  w->kind = FB_ROAD_WHEEL_PROFILE;
  int rc = ml_expect_map(c, n, "a profile {points: [[s, z], ...]}");
  if (!rc)
    rc = ml_check_keys(c, n, keys);
  if (!rc)
    rc = ml_require(c, n, "points", &pts);
  if (!rc)
    rc = ml_expect_seq(c, pts, "a list of [s, z] pairs");
  const size_t count = rc ? 0 : (size_t)fy_node_sequence_item_count(pts);
  if (!rc && count < 2)
    rc = ml_fail(c, pts, FB_EMODEL, "a profile needs at least 2 points (got %zu)", count);
  if (rc)
    return rc;
  if (!(*knots = malloc(2 * count * sizeof **knots)))
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; !rc && i < count; ++i) {
    double *pt = NULL;
    size_t len = 0;
    rc = ml_vector(c, fy_node_sequence_get_by_index(pts, (int)i), syms, 2, 0, &pt, &len);
    if (!rc) {
      (*knots)[i] = pt[0];
      (*knots)[count + i] = pt[1];
    }
    free(pt);
  }
  w->nknots = count;
  w->knot_s = *knots;
  w->knot_z = *knots + count;
  return rc;
}

/* The written kinds of piecewise pieces, and how many numbers each
 * takes: s_begin, s_end, then its parameters (fb_road_piece_kind). */
static const struct {
  const char *name;
  size_t count;
} ml_piece_kinds[] = {[FB_ROAD_PIECE_LINE] = {"line", 4},
                      [FB_ROAD_PIECE_ARC] = {"arc", 5},
                      [FB_ROAD_PIECE_WAVE] = {"wave", 7}};

/* One piece: `{line: [s_begin, s_end, z0, slope]}`, `{arc: [s_begin,
 * s_end, s_centre, z_centre, radius]}` or `{wave: [s_begin, s_end, z0,
 * a0, a1, k, phase]}`. */
static int ml_road_piece(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                         fb_road_piece *p)
{
  static const char *const keys[] = {"line", "arc", "wave", NULL};
  int rc = ml_expect_map(c, n, "a piece {line|arc|wave: [s_begin, s_end, ...]}");
  if (!rc)
    rc = ml_check_keys(c, n, keys);
  if (!rc && fy_node_mapping_item_count(n) != 1)
    rc = ml_fail(c, n, FB_EPARSE, "give exactly one of 'line', 'arc' or 'wave'");
  for (int k = 0; !rc && k <= FB_ROAD_PIECE_WAVE; ++k) {
    struct fy_node *v = ml_get(n, ml_piece_kinds[k].name, NULL);
    double *x = NULL;
    size_t len = 0;
    if (!v)
      continue;
    rc = ml_vector(c, v, syms, ml_piece_kinds[k].count, 0, &x, &len);
    if (!rc) {
      memset(p, 0, sizeof *p);
      p->kind = (fb_road_piece_kind)k;
      p->s_begin = x[0];
      p->s_end = x[1];
      memcpy(p->p, x + 2, (len - 2) * sizeof *x);
    }
    free(x);
  }
  return rc;
}

/* `pieces: [piece, ...]` (none: a flat track); the pieces go into *out
 * (owned by the caller). */
static int ml_road_pieces(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                          fb_road_wheel_info *w, fb_road_piece **out)
{
  w->kind = FB_ROAD_WHEEL_PIECES;
  int rc = ml_expect_seq(c, n, "a list of pieces {line|arc|wave: [...]}");
  const size_t count = rc ? 0 : (size_t)fy_node_sequence_item_count(n);
  if (rc || count == 0)
    return rc;
  if (!(*out = calloc(count, sizeof **out)))
    return fb_err_set(c->err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; !rc && i < count; ++i)
    rc = ml_road_piece(c, fy_node_sequence_get_by_index(n, (int)i), syms, &(*out)[i]);
  w->npieces = count;
  w->pieces = *out;
  return rc;
}

/* `output: velocity | height`. */
static int ml_road_output(const ml_ctx *c, struct fy_node *map, int *velocity)
{
  struct fy_node *v = ml_get(map, "output", NULL);
  const char *text = NULL;
  *velocity = 1;
  int rc = v ? ml_string(c, v, &text) : FB_OK;
  if (rc || !v)
    return rc;
  if (!strcmp(text, "velocity") || !strcmp(text, "height")) {
    *velocity = text[0] == 'v';
    return FB_OK;
  }
  return ml_fail(c, v, FB_EPARSE, "expected velocity or height (got '%s')", text);
}

/* What a road's shape reads into the caller's arrays (owned by it). */
typedef struct ml_road_data {
  double *knots;
  fb_road_piece *pieces;
} ml_road_data;

/* The road's shape: exactly one of bump, iso8608, profile and pieces. */
static int ml_road_shape(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms,
                         fb_road_wheel_info *w, ml_road_data *data)
{
  struct fy_node *bump = ml_get(n, "bump", NULL), *iso = ml_get(n, "iso8608", NULL),
                 *profile = ml_get(n, "profile", NULL), *pieces = ml_get(n, "pieces", NULL);
  if (!!bump + !!iso + !!profile + !!pieces != 1)
    return ml_fail(c, n, FB_EPARSE,
                   "give exactly one of 'bump', 'iso8608', 'profile' or 'pieces'");
  if (bump)
    return ml_road_bump(c, bump, syms, w);
  if (iso)
    return ml_road_iso(c, iso, syms, w);
  if (pieces)
    return ml_road_pieces(c, pieces, syms, w, &data->pieces);
  return ml_road_profile(c, profile, syms, w, &data->knots);
}

int ml_tfun_road(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, fb_tfun **out)
{
  static const char *const keys[] = {"speed",   "s0",      "output", "bump",
                                     "iso8608", "profile", "pieces", NULL};
  fb_road_wheel_info w;
  memset(&w, 0, sizeof w);
  ml_road_data data = {NULL, NULL};
  struct fy_node *v = NULL;
  int rc = ml_expect_map(c, n, "a road {speed, s0, output, bump|iso8608|profile|pieces}");
  if (!rc)
    rc = ml_check_keys(c, n, keys);
  if (!rc)
    rc = ml_require(c, n, "speed", &v);
  if (!rc)
    rc = ml_number(c, v, syms, &w.speed);
  if (!rc && !(w.speed > 0))
    rc = ml_fail(c, v, FB_EINVAL, "must be > 0 m/s (got %g)", w.speed);
  if (!rc)
    rc = ml_opt_number(c, n, "s0", syms, &w.s0);
  if (!rc)
    rc = ml_road_output(c, n, &w.velocity);
  if (!rc)
    rc = ml_road_shape(c, n, syms, &w, &data);
  if (!rc && fb_road_wheel_new(&w, out, c->err))
    rc = ml_blame(c, n);
  free(data.knots);
  free(data.pieces);
  return rc;
}
