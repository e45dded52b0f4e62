/* SPDX-License-Identifier: BSD-3-Clause */
/* A corner's bump and rebound stops (flexbond/stop.h): their checks and
 * their element, one modulated resistor on the spring's travel. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/stop.h"

#include "vehicle/vehicle_internal.h"

void fb_stop_init(fb_stop *st)
{
  memset(st, 0, sizeof *st);
  st->damping_depth = FB_STOP_DAMPING_DEPTH;
}

int fb_stops_any(const fb_stops *s)
{
  return s->bump.given || s->rebound.given;
}

/* err's message already set: names member of stop which. */
static int stop_fail(fb_err *err, const char *which, const char *member)
{
  char field[64];
  snprintf(field, sizeof field, "%s.%s", which, member);
  fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, field);
  return FB_EINVAL;
}

/* The table's rules beyond fb_table_law's own: from (0, 0), forces not
 * decreasing. */
static int check_table(const fb_stop *st, const char *corner, const char *which, fb_err *err)
{
  if (st->npoints < 2 || st->npoints > FB_STOP_MAX_POINTS)
    return fb_err_set(err, FB_EINVAL,
                      "corner '%s': a stop's table has 2 to %d points (got %zu)", corner,
                      (int)FB_STOP_MAX_POINTS, st->npoints),
           stop_fail(err, which, "table");
  if (st->deflection[0] != 0.0 || st->force[0] != 0.0)
    return fb_err_set(err, FB_EINVAL,
                      "corner '%s': a stop's table starts at (0, 0), where the stop is touched "
                      "(got (%g, %g))",
                      corner, st->deflection[0], st->force[0]),
           stop_fail(err, which, "table");
  fb_table_law *law = NULL;
  int rc = fb_table_law_new(st->npoints, st->deflection, st->force, &law, err);
  if (!rc)
    rc = fb_table_law_check_monotone(law, err);
  fb_table_law_free(&law);
  if (rc) {
    fb_err_prefix(err, "corner '%s': a stop's ", corner);
    return stop_fail(err, which, "table");
  }
  return FB_OK;
}

static int check_stop(const fb_stop *st, const char *corner, const char *which, fb_err *err)
{
  if (!st->given)
    return FB_OK;
  if (!(isfinite(st->gap) && st->gap >= 0.0))
    return fb_err_set(err, FB_EINVAL, "corner '%s': must be >= 0 m (got %g)", corner, st->gap),
           stop_fail(err, which, "gap");
  if (st->npoints && st->rate != 0.0)
    return fb_err_set(err, FB_EINVAL, "corner '%s': a stop has a rate or a table, not both",
                      corner),
           stop_fail(err, which, "rate");
  if (!st->npoints && !(isfinite(st->rate) && st->rate > 0.0))
    return fb_err_set(err, FB_EINVAL, "corner '%s': must be > 0 N/m (got %g)", corner,
                      st->rate),
           stop_fail(err, which, "rate");
  if (!(isfinite(st->damping) && st->damping >= 0.0))
    return fb_err_set(err, FB_EINVAL, "corner '%s': must be >= 0 N s/m (got %g)", corner,
                      st->damping),
           stop_fail(err, which, "damping");
  if (!(isfinite(st->damping_depth) && st->damping_depth > 0.0))
    return fb_err_set(err, FB_EINVAL, "corner '%s': must be > 0 m (got %g)", corner,
                      st->damping_depth),
           stop_fail(err, which, "damping_depth");
  return st->npoints ? check_table(st, corner, which, err) : FB_OK;
}

int fb_stops_check(const fb_stops *s, const char *corner, fb_err *err)
{
  corner = corner ? corner : "?";
  int rc = check_stop(&s->bump, corner, "bump_stop", err);
  if (!rc)
    rc = check_stop(&s->rebound, corner, "rebound_stop", err);
  return rc;
}

/* ---- The element. */

/* One stop as its law reads it: sign +1 for the bump stop (compressed by
 * x - gap), -1 for the rebound stop (by -x - gap). */
typedef struct stop_law {
  int given;
  double sign, gap, rate, damping, depth;
  fb_table_law *table; /* owned; NULL: the linear rate */
} stop_law;

typedef struct stops_law {
  stop_law stop[2];
} stops_law;

/* The stop's force (>= 0, pushing back) at travel x and rate v, and its
 * derivatives with respect to x and v (the sign's square is 1). */
static double stop_force(const stop_law *st, double x, double v, double *dx, double *dv)
{
  *dx = *dv = 0.0;
  const double delta = st->sign * x - st->gap, rate = st->sign * v;
  if (!st->given || delta <= 0.0)
    return 0.0;
  double slope = st->rate;
  const double elastic =
      st->table ? fb_table_law_eval(st->table, delta, &slope) : st->rate * delta;
  const double ramp = delta < st->depth ? delta / st->depth : 1.0;
  const double ramp_slope = delta < st->depth ? 1.0 / st->depth : 0.0;
  const double force = elastic + st->damping * ramp * rate;
  if (force <= 0.0)
    return 0.0; /* a stop never pulls */
  *dx = slope + st->damping * ramp_slope * rate;
  *dv = st->damping * ramp;
  return force;
}

/* xu = [v, x]: the travel rate, then the spring's travel. */
static int stops_eval(void *ctx, const fb_law_in *in, double *y)
{
  const stops_law *l = ctx;
  double dx, dv;
  y[0] = 0.0;
  for (int i = 0; i < 2; ++i)
    y[0] += l->stop[i].sign * stop_force(&l->stop[i], in->x[1], in->x[0], &dx, &dv);
  return 0;
}

static int stops_jacobian(void *ctx, const fb_law_in *in, double *jac)
{
  const stops_law *l = ctx;
  jac[0] = jac[1] = 0.0;
  for (int i = 0; i < 2; ++i) {
    double dx, dv;
    stop_force(&l->stop[i], in->x[1], in->x[0], &dx, &dv);
    jac[0] += dv;
    jac[1] += dx;
  }
  return 0;
}

static void stops_free(void *ctx)
{
  stops_law *l = ctx;
  for (int i = 0; l && i < 2; ++i)
    fb_table_law_free(&l->stop[i].table);
  free(l);
}

/* Not passive: the elastic part stores what it takes and gives it back;
 * its power probe integrates to that energy. */
static const fb_law_ops stops_ops = {
    .name = "bump and rebound stops",
    .eval = stops_eval,
    .jacobian = stops_jacobian,
    .free = stops_free,
};

static int stop_law_of(const fb_stop *st, double sign, stop_law *out, fb_err *err)
{
  *out = (stop_law){st->given, sign, st->gap, st->rate, st->damping, st->damping_depth, NULL};
  return st->given && st->npoints
             ? fb_table_law_new(st->npoints, st->deflection, st->force, &out->table, err)
             : FB_OK;
}

int vehicle_add_stops(const fb_stops *s, const char *name, const char *spring, fb_bg *bg,
                      fb_err *err)
{
  static const size_t one_port[1] = {1};
  stops_law *l = calloc(1, sizeof *l);
  if (!l)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  int rc = stop_law_of(&s->bump, 1.0, &l->stop[0], err);
  if (!rc)
    rc = stop_law_of(&s->rebound, -1.0, &l->stop[1], err);
  if (rc) {
    stops_free(l);
    return rc;
  }
  rc = fb_bg_add_field_law(bg, name, FB_BG_R, 1, one_port, &stops_ops, l, err);
  return rc ? rc : fb_bg_modulate(bg, name, 1, &spring, err);
}
