/* SPDX-License-Identifier: BSD-3-Clause */
/* The stresses of System 2's hull over a run (flexbond/hull_stress.h):
 * modal stress recovery (the stress modes of fb_shell_stress_modes, as
 * Adams/Flex's and Simpack's; R. R. Craig & A. J. Kurdila, "Fundamentals
 * of Structural Dynamics", 2nd ed., 2006, ch. 11) applied to every
 * recorded sample, and the peaks and ranges per element. */
#include "flexbond/hull_stress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "vehicle/vehicle_internal.h"

struct fb_hull_stress {
  const fb_mesh *mesh;  /* borrowed from the vehicle */
  fb_shell_stress *rec; /* owned */
  size_t ncoords;       /* the hull's coordinates: the basis's columns, or 6 nnodes */
  int modal;            /* 1: rec holds the stress modes of the basis */
};

const char *fb_hull_surface_name(fb_hull_surface s)
{
  return s == FB_HULL_SURFACE_BOTTOM ? "bottom" : "top";
}

int fb_hull_stress_new(const fb_vehicle *v, fb_hull_stress **out, fb_err *err)
{
  *out = NULL;
  const fb_fe_hull *fe = fb_vehicle_fe_hull_of(v);
  const fb_hull_basis *b = fb_vehicle_hull_basis(v);
  if (!fe || !b)
    return fb_err_set(err, FB_EINVAL, "hull stresses: System 1's hull is rigid");
  fb_hull_stress *hs = calloc(1, sizeof *hs);
  if (!hs)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  hs->mesh = fe->mesh;
  hs->ncoords = b->ncoords;
  int rc = fb_shell_stress_new(fe->mesh, &fe->props, &hs->rec, err);
  size_t nb = 0;
  const double *phi = vehicle_coordinate_basis(v, &nb);
  if (!rc && phi) {
    hs->modal = 1;
    hs->ncoords = nb;
    rc = fb_shell_stress_modes(hs->rec, phi, b->ndof, nb, err);
  }
  if (rc) {
    fb_hull_stress_free(&hs);
    return rc;
  }
  *out = hs;
  return FB_OK;
}

void fb_hull_stress_free(fb_hull_stress **hs)
{
  if (!hs || !*hs)
    return;
  fb_shell_stress_free(&(*hs)->rec);
  free(*hs);
  *hs = NULL;
}

size_t fb_hull_stress_nelements(const fb_hull_stress *hs)
{
  return fb_shell_stress_nelements(hs->rec);
}

const fb_mesh *fb_hull_stress_mesh(const fb_hull_stress *hs)
{
  return hs->mesh;
}

/* The run's hull must be the recovery's: System 2, the same coordinates. */
static int check_motion(const fb_hull_stress *hs, const fb_vehicle_motion *m, fb_err *err)
{
  if (m->sys != FB_SYSTEM_FLEXIBLE || m->ncoords != hs->ncoords ||
      (m->basis != NULL) != hs->modal)
    return fb_err_set(err, FB_EINVAL,
                      "hull stresses: the run's hull has %zu coordinates where the recovery's "
                      "has %zu",
                      m->ncoords, hs->ncoords);
  return FB_OK;
}

/* The states of the hull's coordinates q (total). */
static void eval(const fb_hull_stress *hs, const double *q, fb_shell_stress_state *states)
{
  if (hs->modal) {
    fb_err ignored;
    /* Cannot fail: the stress modes were formed in fb_hull_stress_new. */
    (void)fb_shell_stress_eval_modal(hs->rec, q, states, &ignored);
  } else {
    fb_shell_stress_eval_nodal(hs->rec, q, states);
  }
}

int fb_hull_stress_at(const fb_hull_stress *hs, const fb_vehicle_motion *m, double t,
                      fb_shell_stress_state *states, fb_err *err)
{
  int rc = check_motion(hs, m, err);
  if (rc)
    return rc;
  double *q = malloc((m->ncoords ? m->ncoords : 1) * sizeof *q);
  if (!q)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  rc = fb_vehicle_motion_coords_at(m, t, q, err);
  if (!rc)
    eval(hs, q, states);
  free(q);
  return rc;
}

void fb_hull_stress_peaks_free(fb_hull_stress_peaks **p)
{
  if (!p || !*p)
    return;
  free((*p)->von_mises);
  free((*p)->time);
  free((*p)->surface);
  free((*p)->range);
  free((*p)->range_surface);
  free(*p);
  *p = NULL;
}

static int peaks_alloc(size_t n, fb_hull_stress_peaks **out, fb_err *err)
{
  fb_hull_stress_peaks *p = calloc(1, sizeof *p);
  const size_t k = n ? n : 1;
  if (p) {
    p->nelements = n;
    p->von_mises = malloc(k * sizeof *p->von_mises);
    p->time = malloc(k * sizeof *p->time);
    p->surface = malloc(k * sizeof *p->surface);
    p->range = malloc(k * sizeof *p->range);
    p->range_surface = malloc(k * sizeof *p->range_surface);
  }
  if (!p || !p->von_mises || !p->time || !p->surface || !p->range || !p->range_surface) {
    fb_hull_stress_peaks_free(&p);
    return fb_err_set(err, FB_ENOMEM, "out of memory for the peaks of %zu elements", n);
  }
  *out = p;
  return FB_OK;
}

/* The planes' normals at angles k pi / FB_HULL_STRESS_PLANES from the
 * element's local x: cos^2, sin^2 and 2 sin cos of each. */
typedef struct planes {
  double cc[FB_HULL_STRESS_PLANES], ss[FB_HULL_STRESS_PLANES], sc2[FB_HULL_STRESS_PLANES];
} planes;

static void planes_make(planes *pl)
{
  const double pi = 3.14159265358979323846;
  for (int k = 0; k < FB_HULL_STRESS_PLANES; ++k) {
    const double a = pi * k / FB_HULL_STRESS_PLANES, c = cos(a), s = sin(a);
    pl->cc[k] = c * c;
    pl->ss[k] = s * s;
    pl->sc2[k] = 2.0 * s * c;
  }
}

/* Index of element e's surface s's plane k in the extremes. */
static size_t plane_at(size_t e, int s, int k)
{
  return (2 * e + (size_t)s) * FB_HULL_STRESS_PLANES + (size_t)k;
}

/* The normal stresses sigma_n = sx c^2 + sy s^2 + 2 txy s c (Cauchy's
 * formula in the plane) of surface stresses sv on every plane, into the
 * extremes lo, hi of the surface. */
static void track_planes(const planes *pl, const double *sv, int first, double *lo, double *hi)
{
  for (int k = 0; k < FB_HULL_STRESS_PLANES; ++k) {
    const double sn = sv[0] * pl->cc[k] + sv[1] * pl->ss[k] + sv[2] * pl->sc2[k];
    lo[k] = first ? sn : fmin(lo[k], sn);
    hi[k] = first ? sn : fmax(hi[k], sn);
  }
}

/* Per element the peak von Mises stress and, per surface and plane, the
 * extremes of the normal stress. */
static void track(const planes *pl, const fb_shell_stress_state *states, double t, int first,
                  fb_hull_stress_peaks *p, double *lo, double *hi)
{
  for (size_t e = 0; e < p->nelements; ++e) {
    const fb_shell_stress_state *st = states + e;
    const int bottom = st->von_mises_bottom > st->von_mises_top;
    const double vm = bottom ? st->von_mises_bottom : st->von_mises_top;
    if (first || vm > p->von_mises[e]) {
      p->von_mises[e] = vm;
      p->time[e] = t;
      p->surface[e] = bottom ? FB_HULL_SURFACE_BOTTOM : FB_HULL_SURFACE_TOP;
    }
    track_planes(pl, st->top, first, lo + plane_at(e, 0, 0), hi + plane_at(e, 0, 0));
    track_planes(pl, st->bottom, first, lo + plane_at(e, 1, 0), hi + plane_at(e, 1, 0));
  }
}

/* The largest range over each element's surfaces and planes (the top
 * first among equals). */
static void finish_ranges(const double *lo, const double *hi, fb_hull_stress_peaks *p)
{
  for (size_t e = 0; e < p->nelements; ++e) {
    p->range[e] = -INFINITY;
    for (int s = 0; s < 2; ++s)
      for (int k = 0; k < FB_HULL_STRESS_PLANES; ++k) {
        const size_t i = plane_at(e, s, k);
        if (hi[i] - lo[i] > p->range[e]) {
          p->range[e] = hi[i] - lo[i];
          p->range_surface[e] = s ? FB_HULL_SURFACE_BOTTOM : FB_HULL_SURFACE_TOP;
        }
      }
  }
}

int fb_hull_stress_peaks_of(const fb_hull_stress *hs, const fb_vehicle_motion *m, double t_from,
                            fb_hull_stress_peaks **out, fb_err *err)
{
  *out = NULL;
  int rc = check_motion(hs, m, err);
  if (rc)
    return rc;
  const size_t ne = fb_hull_stress_nelements(hs);
  fb_hull_stress_peaks *p = NULL;
  rc = peaks_alloc(ne, &p, err);
  if (rc)
    return rc;
  fb_shell_stress_state *states = malloc((ne ? ne : 1) * sizeof *states);
  double *q = malloc((m->ncoords ? m->ncoords : 1) * sizeof *q);
  /* Extremes of the normal stress per element, surface and plane. */
  const size_t nplanes = 2 * (ne ? ne : 1) * FB_HULL_STRESS_PLANES;
  double *lo = malloc(nplanes * sizeof *lo), *hi = malloc(nplanes * sizeof *hi);
  planes pl;
  planes_make(&pl);
  if (!states || !q || !lo || !hi)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for the stresses of %zu elements", ne);
  for (size_t k = 0; rc == FB_OK && k < m->nsamples; ++k) {
    const double *row = m->samples + k * m->width;
    if (row[0] < t_from)
      continue;
    for (size_t j = 0; j < m->ncoords; ++j)
      q[j] = m->hull_q0[j] + row[1 + j];
    eval(hs, q, states);
    track(&pl, states, row[0], p->nsamples == 0, p, lo, hi);
    p->nsamples++;
  }
  if (rc == FB_OK && p->nsamples == 0)
    rc = fb_err_set(err, FB_EINVAL, "hull stresses: the run has no sample at or after %g s",
                    t_from);
  if (rc == FB_OK)
    finish_ranges(lo, hi, p);
  free(states);
  free(q);
  free(lo);
  free(hi);
  if (rc) {
    fb_hull_stress_peaks_free(&p);
    return rc;
  }
  *out = p;
  return FB_OK;
}

/* Sorting indices by peak, largest first, the lower index first among
 * equals (qsort is not stable: the index breaks ties). */
typedef struct ranked {
  double value;
  size_t index;
} ranked;

static int by_peak(const void *a, const void *b)
{
  const ranked *x = a, *y = b;
  if (x->value != y->value)
    return x->value > y->value ? -1 : 1;
  return x->index < y->index ? -1 : x->index > y->index;
}

int fb_hull_stress_peaks_top(const fb_hull_stress_peaks *p, size_t n, size_t *order,
                             fb_err *err)
{
  ranked *r = malloc((p->nelements ? p->nelements : 1) * sizeof *r);
  if (!r)
    return fb_err_set(err, FB_ENOMEM, "out of memory ranking %zu elements", p->nelements);
  for (size_t e = 0; e < p->nelements; ++e)
    r[e] = (ranked){p->von_mises[e], e};
  qsort(r, p->nelements, sizeof *r, by_peak);
  for (size_t i = 0; i < n && i < p->nelements; ++i)
    order[i] = r[i].index;
  free(r);
  return FB_OK;
}
