/* SPDX-License-Identifier: BSD-3-Clause */
/* Mounted rigid bodies as data (flexbond/vehicle.h fb_body): their
 * bushings, lookups by name and over every body's bushings, and the
 * deep copy and release the description's owners share. */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

void fb_bushing_set_diagonal(fb_bushing *b, const double *k6, const double *c6)
{
  memset(b->k, 0, sizeof b->k);
  memset(b->c, 0, sizeof b->c);
  for (int i = 0; i < 6; ++i) {
    b->k[7 * i] = k6[i];
    b->c[7 * i] = c6[i];
  }
}

long fb_scenario_body_find(const fb_scenario *s, const char *name)
{
  for (size_t b = 0; name && b < s->nbodies; ++b)
    if (s->body[b].name && !strcmp(s->body[b].name, name))
      return (long)b;
  return -1;
}

size_t fb_scenario_nbushings(const fb_scenario *s)
{
  size_t n = 0;
  for (size_t b = 0; b < s->nbodies; ++b)
    n += s->body[b].nbushings;
  return n;
}

int fb_scenario_bushing_at(const fb_scenario *s, size_t k, size_t *body, size_t *bushing)
{
  for (size_t b = 0; b < s->nbodies; ++b) {
    if (k < s->body[b].nbushings) {
      *body = b;
      *bushing = k;
      return 1;
    }
    k -= s->body[b].nbushings;
  }
  return 0;
}

void vehicle_body_release(fb_body *b)
{
  free(b->name);
  free(b->parent);
  for (size_t j = 0; b->bushing && j < b->nbushings; ++j) {
    free(b->bushing[j].node_set);
    free(b->bushing[j].surface);
  }
  free(b->bushing);
  memset(b, 0, sizeof *b);
}

/* *dst = copy of src (NULL stays NULL); 0 when out of memory. */
static int body_copy_string(const char *src, char **dst)
{
  *dst = src ? fb_strdup(src) : NULL;
  return !src || *dst;
}

int vehicle_body_copy(const fb_body *src, fb_body *dst)
{
  *dst = *src;
  dst->name = dst->parent = NULL;
  dst->bushing = NULL;
  dst->nbushings = 0;
  const size_t n = src->nbushings;
  int ok = body_copy_string(src->name, &dst->name);
  ok = body_copy_string(src->parent, &dst->parent) && ok;
  if (ok && src->bushing && n)
    ok = (dst->bushing = calloc(n, sizeof *dst->bushing)) != NULL;
  for (size_t j = 0; ok && dst->bushing && j < n; ++j) {
    dst->bushing[j] = src->bushing[j];
    dst->bushing[j].node_set = dst->bushing[j].surface = NULL;
    dst->nbushings = j + 1;
    ok = body_copy_string(src->bushing[j].node_set, &dst->bushing[j].node_set);
    ok = body_copy_string(src->bushing[j].surface, &dst->bushing[j].surface) && ok;
  }
  if (!ok)
    vehicle_body_release(dst);
  return ok;
}

void vehicle_body_inertia(const fb_body *b, double *j)
{
  const double t[9] = {b->ixx,  -b->ixy, -b->ixz, -b->ixy, b->iyy,
                       -b->iyz, -b->ixz, -b->iyz, b->izz};
  memcpy(j, t, sizeof t);
}

double vehicle_body_top_hz(const fb_body *b)
{
  double k[36] = {0}, m[36], w[6];
  for (size_t j = 0; j < b->nbushings; ++j)
    vehicle_bushing_add_at_centre(b, &b->bushing[j], b->bushing[j].k, k);
  vehicle_body_inertia6(b, m);
  /* K v = lambda M v (symmetric-definite: LAPACK's dsygv), ascending. */
  if (LAPACKE_dsygv(LAPACK_ROW_MAJOR, 1, 'N', 'U', 6, k, 6, m, 6, w))
    return 0.0;
  return sqrt(fmax(w[5], 0.0)) / (2.0 * 3.14159265358979323846);
}

void vehicle_hull_inertia(const fb_scenario *s, double *j)
{
  const fb_body hull = {.ixx = s->hull_ixx,
                        .iyy = s->hull_iyy,
                        .izz = s->hull_izz,
                        .ixy = s->hull_ixy,
                        .ixz = s->hull_ixz,
                        .iyz = s->hull_iyz};
  vehicle_body_inertia(&hull, j);
}

int vehicle_sym3_eigenvalues(const double *a, double *w)
{
  double s[9];
  memcpy(s, a, sizeof s);
  return LAPACKE_dsyev(LAPACK_ROW_MAJOR, 'N', 'U', 3, s, 3, w) ? FB_ESOLVER : FB_OK;
}

/* Small-motion kinematics of a rigid body (Shabana, "Dynamics of
 * Multibody Systems", 4th ed., sec. 2.7): a point at r from the
 * reference moves with v_P = v + omega x r = v - [r]x omega, and turns
 * with omega. */
void vehicle_rigid_transport(const double *r, double *t)
{
  /* The translation's rows [I, -[r]x] are the point's (vehicle_rigid_rows);
   * the rotation is the same at every point, [0, I]. */
  memset(t, 0, 36 * sizeof *t);
  vehicle_rigid_rows(r, t);
  for (int i = 3; i < 6; ++i)
    t[7 * i] = 1.0;
}

void vehicle_bushing_add_at_centre(const fb_body *b, const fb_bushing *u, const double *k,
                                   double *sum)
{
  const double r[3] = {u->x - b->x, u->y - b->y, u->z - b->z};
  double t[36], kt[36];
  vehicle_rigid_transport(r, t);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      double v = 0.0;
      for (int m = 0; m < 6; ++m)
        v += k[6 * i + m] * t[6 * m + j];
      kt[6 * i + j] = v;
    }
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      double v = 0.0;
      for (int m = 0; m < 6; ++m)
        v += t[6 * m + i] * kt[6 * m + j];
      sum[6 * i + j] += v;
    }
}
