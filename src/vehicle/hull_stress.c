/* SPDX-License-Identifier: BSD-3-Clause */
/* The stresses of System 2's hull over a run (flexbond/hull_stress.h):
 * modal stress recovery (the stress modes of fb_shell_stress_modes, as
 * Adams/Flex's and Simpack's; R. R. Craig & A. J. Kurdila, "Fundamentals
 * of Structural Dynamics", 2nd ed., 2006, ch. 11) applied to every
 * recorded sample, and the peaks and ranges per element. */
#include "flexbond/hull_stress.h"

#include <cblas.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "vehicle/vehicle_internal.h"

struct fb_hull_stress {
  const fb_mesh *mesh;  /* borrowed from the vehicle */
  fb_shell_stress *rec; /* owned */
  size_t ncoords;       /* the hull's coordinates: the basis's columns, or 6 nnodes */
  int modal;            /* 1: rec holds the stress modes of the basis */
  int threads;          /* the vehicle's (fb_vehicle_opts.threads): 2 tracks on two */
};

const char *fb_hull_surface_name(fb_hull_surface s)
{
  return s == FB_HULL_SURFACE_BOTTOM ? "bottom" : "top";
}

int fb_hull_stress_possible(const fb_vehicle *v)
{
  const fb_fe_hull *fe = fb_vehicle_fe_hull_of(v);
  return fe && fb_vehicle_hull_basis(v) && fb_mesh_nelements(fe->mesh) > 0;
}

int fb_hull_stress_new(const fb_vehicle *v, fb_hull_stress **out, fb_err *err)
{
  *out = NULL;
  const fb_fe_hull *fe = fb_vehicle_fe_hull_of(v);
  const fb_hull_basis *b = fb_vehicle_hull_basis(v);
  if (!fe || !b)
    return fb_err_set(err, FB_EINVAL, "hull stresses: System 1's hull is rigid");
  if (fb_mesh_nelements(fe->mesh) == 0)
    return fb_err_set(err, FB_EINVAL,
                      "hull stresses: the hull is a superelement, which has no shell elements");
  fb_hull_stress *hs = calloc(1, sizeof *hs);
  if (!hs)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  hs->mesh = fe->mesh;
  hs->ncoords = b->ncoords;
  hs->threads = vehicle_threads(v);
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

/* What the tracking keeps: per element its largest squared von Mises
 * stress (the root is taken once, at the end) and, per surface and plane,
 * the extremes of the normal stress. */
typedef struct tracker {
  planes pl;
  size_t ne;
  double *vm2, *time;       /* ne: the largest and its first time */
  fb_hull_surface *surface; /* ne: its surface */
  double *lo, *hi; /* 2 FB_HULL_STRESS_PLANES per element: the top's, then the bottom's */
} tracker;

/* The plane-stress von Mises stress squared, sx^2 - sx sy + sy^2 + 3
 * txy^2 (as fb_shell_stress_state's). */
static double von_mises2(const double *sv)
{
  return sv[0] * sv[0] - sv[0] * sv[1] + sv[1] * sv[1] + 3.0 * sv[2] * sv[2];
}

/* The normal stresses sigma_n = sx c^2 + sy s^2 + 2 txy s c (Cauchy's
 * formula in the plane) of surface stresses sv on every plane, into the
 * surface's extremes lo, hi (comparisons rather than fmin / fmax, which
 * the compiler vectorises: no stress is NaN). */
static void track_planes(const planes *restrict pl, const double *restrict sv,
                         double *restrict lo, double *restrict hi)
{
  for (int k = 0; k < FB_HULL_STRESS_PLANES; ++k) {
    const double sn = sv[0] * pl->cc[k] + sv[1] * pl->ss[k] + sv[2] * pl->sc2[k];
    lo[k] = sn < lo[k] ? sn : lo[k];
    hi[k] = sn > hi[k] ? sn : hi[k];
  }
}

/* Element e's surface stresses sv (top x, y, xy, then the bottom's) at
 * time t. */
static void track(tracker *tr, size_t e, const double *sv, double t)
{
  const double top = von_mises2(sv), bottom = von_mises2(sv + 3);
  const double vm2 = bottom > top ? bottom : top;
  if (vm2 > tr->vm2[e]) {
    tr->vm2[e] = vm2;
    tr->time[e] = t;
    tr->surface[e] = bottom > top ? FB_HULL_SURFACE_BOTTOM : FB_HULL_SURFACE_TOP;
  }
  double *lo = tr->lo + 2 * FB_HULL_STRESS_PLANES * e,
         *hi = tr->hi + 2 * FB_HULL_STRESS_PLANES * e;
  track_planes(&tr->pl, sv, lo, hi);
  track_planes(&tr->pl, sv + 3, lo + FB_HULL_STRESS_PLANES, hi + FB_HULL_STRESS_PLANES);
}

static int tracker_init(tracker *tr, size_t ne, fb_err *err)
{
  const size_t n = 2 * FB_HULL_STRESS_PLANES * (ne ? ne : 1);
  planes_make(&tr->pl);
  tr->ne = ne;
  tr->vm2 = malloc((ne ? ne : 1) * sizeof *tr->vm2);
  tr->time = calloc(ne ? ne : 1, sizeof *tr->time);
  tr->surface = calloc(ne ? ne : 1, sizeof *tr->surface);
  tr->lo = malloc(n * sizeof *tr->lo);
  tr->hi = malloc(n * sizeof *tr->hi);
  if (!tr->vm2 || !tr->time || !tr->surface || !tr->lo || !tr->hi)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the stresses of %zu elements", ne);
  for (size_t e = 0; e < ne; ++e)
    tr->vm2[e] = -1.0;
  for (size_t i = 0; i < n; ++i) {
    tr->lo[i] = INFINITY;
    tr->hi[i] = -INFINITY;
  }
  return FB_OK;
}

static void tracker_free(tracker *tr)
{
  free(tr->vm2);
  free(tr->time);
  free(tr->surface);
  free(tr->lo);
  free(tr->hi);
}

/* The tracking of later samples, from, into to: a peak that is no higher
 * than to's keeps to's (earlier) time. */
static void tracker_merge(tracker *to, const tracker *from)
{
  for (size_t e = 0; e < to->ne; ++e)
    if (from->vm2[e] > to->vm2[e]) {
      to->vm2[e] = from->vm2[e];
      to->time[e] = from->time[e];
      to->surface[e] = from->surface[e];
    }
  for (size_t i = 0; i < 2 * FB_HULL_STRESS_PLANES * to->ne; ++i) {
    to->lo[i] = from->lo[i] < to->lo[i] ? from->lo[i] : to->lo[i];
    to->hi[i] = from->hi[i] > to->hi[i] ? from->hi[i] : to->hi[i];
  }
}

/* The peaks from the extremes: von Mises' root, and the largest range
 * over each element's surfaces and planes (the top first among equals). */
static void finish(const tracker *tr, fb_hull_stress_peaks *p)
{
  for (size_t e = 0; e < p->nelements; ++e) {
    p->von_mises[e] = sqrt(tr->vm2[e]);
    p->time[e] = tr->time[e];
    p->surface[e] = tr->surface[e];
    p->range[e] = -INFINITY;
    for (size_t i = 0; i < 2 * FB_HULL_STRESS_PLANES; ++i) {
      const size_t at = 2 * FB_HULL_STRESS_PLANES * e + i;
      if (tr->hi[at] - tr->lo[at] > p->range[e]) {
        p->range[e] = tr->hi[at] - tr->lo[at];
        p->range_surface[e] =
            i < FB_HULL_STRESS_PLANES ? FB_HULL_SURFACE_TOP : FB_HULL_SURFACE_BOTTOM;
      }
    }
  }
}

/* Samples per product in modal coordinates: their stresses (6 nelements
 * each) are formed together. */
enum { BLOCK = 32 };

/* Modal coordinates, samples [k0, k1) into tr: the stresses of a block of
 * samples at once, S Q + S q0 (S all the stress modes, 6 nelements x m;
 * Q the block's coordinates, read in place from the samples; s0 = S q0),
 * one matrix product (BLAS dgemm) rather than a product per sample. */
typedef struct modal_job {
  const fb_hull_stress *hs;
  const fb_vehicle_motion *m;
  const double *s0;
  size_t k0, k1;
  tracker *tr;
  double *block; /* 6 nelements BLOCK */
} modal_job;

static void modal_range(const modal_job *job)
{
  const fb_vehicle_motion *m = job->m;
  const size_t ne = job->tr->ne, rows = 6 * ne, nm = job->hs->ncoords;
  const double *S = fb_shell_stress_mode_matrix(job->hs->rec, 0);
  for (size_t k = job->k0; k < job->k1; k += BLOCK) {
    size_t nb = BLOCK;
    if (job->k1 - k < nb)
      nb = job->k1 - k;
    for (size_t j = 0; j < nb; ++j)
      memcpy(job->block + j * rows, job->s0, rows * sizeof *job->block);
    /* S is row-major 6 ne x m: column-major, its transpose (m x 6 ne). */
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, (int)rows, (int)nb, (int)nm, 1.0, S,
                (int)nm, m->samples + k * m->width + 1, (int)m->width, 1.0, job->block,
                (int)rows);
    /* Element by element, so that its extremes stay in cache over the
     * block's samples. */
    for (size_t e = 0; e < ne; ++e)
      for (size_t j = 0; j < nb; ++j)
        track(job->tr, e, job->block + j * rows + 6 * e, m->samples[(k + j) * m->width]);
  }
}

static void *modal_thread(void *arg)
{
  modal_range(arg);
  return NULL;
}

/* The samples from k0 on, split in two halves on two threads (the later
 * half's tracking merged into tr's) when hs may use two, on this thread
 * alone when it may not or the second cannot start. */
static int track_modal(const fb_hull_stress *hs, const fb_vehicle_motion *m, size_t k0,
                       tracker *tr, fb_hull_stress_peaks *p, fb_err *err)
{
  const size_t ne = p->nelements, rows = 6 * ne;
  double *s0 = malloc(rows * sizeof *s0), *block = malloc(2 * rows * BLOCK * sizeof *block);
  if (!s0 || !block) {
    free(s0);
    free(block);
    return fb_err_set(err, FB_ENOMEM, "out of memory for the stresses of %zu elements", ne);
  }
  const double *S = fb_shell_stress_mode_matrix(hs->rec, 0);
  cblas_dgemv(CblasColMajor, CblasTrans, (int)hs->ncoords, (int)rows, 1.0, S, (int)hs->ncoords,
              m->hull_q0, 1, 0.0, s0, 1);
  modal_job mine = {hs, m, s0, k0, m->nsamples, tr, block};
  tracker later = {0};
  modal_job half = {hs, m, s0, 0, m->nsamples, &later, block + rows * BLOCK};
  pthread_t thread;
  int started = 0;
  fb_err ignored;
  if (hs->threads > 1 && m->nsamples - k0 >= 2 * BLOCK &&
      tracker_init(&later, ne, &ignored) == FB_OK) {
    half.k0 = k0 + (m->nsamples - k0) / 2;
    started = pthread_create(&thread, NULL, modal_thread, &half) == 0;
  }
  if (started)
    mine.k1 = half.k0;
  modal_range(&mine);
  if (started) {
    pthread_join(thread, NULL);
    tracker_merge(tr, &later);
  }
  tracker_free(&later);
  p->nsamples += m->nsamples - k0;
  free(s0);
  free(block);
  return FB_OK;
}

/* Nodal coordinates: each sample's recovery. */
static int track_nodal(const fb_hull_stress *hs, const fb_vehicle_motion *m, size_t k0,
                       tracker *tr, fb_hull_stress_peaks *p, fb_err *err)
{
  const size_t ne = p->nelements;
  fb_shell_stress_state *states = malloc((ne ? ne : 1) * sizeof *states);
  double *q = malloc((m->ncoords ? m->ncoords : 1) * sizeof *q);
  if (!states || !q) {
    free(states);
    free(q);
    return fb_err_set(err, FB_ENOMEM, "out of memory for the stresses of %zu elements", ne);
  }
  for (size_t k = k0; k < m->nsamples; ++k) {
    const double *row = m->samples + k * m->width;
    for (size_t j = 0; j < m->ncoords; ++j)
      q[j] = m->hull_q0[j] + row[1 + j];
    eval(hs, q, states);
    for (size_t e = 0; e < ne; ++e) {
      double sv[6];
      memcpy(sv, states[e].top, 3 * sizeof *sv);
      memcpy(sv + 3, states[e].bottom, 3 * sizeof *sv);
      track(tr, e, sv, row[0]);
    }
    p->nsamples++;
  }
  free(states);
  free(q);
  return FB_OK;
}

int fb_hull_stress_peaks_of(const fb_hull_stress *hs, const fb_vehicle_motion *m, double t_from,
                            fb_hull_stress_peaks **out, fb_err *err)
{
  *out = NULL;
  int rc = check_motion(hs, m, err);
  if (rc)
    return rc;
  /* The first sample at or after t_from (the samples are in time order). */
  size_t k0 = 0;
  while (k0 < m->nsamples && m->samples[k0 * m->width] < t_from)
    ++k0;
  if (k0 == m->nsamples)
    return fb_err_set(err, FB_EINVAL, "hull stresses: the run has no sample at or after %g s",
                      t_from);
  fb_hull_stress_peaks *p = NULL;
  tracker tr = {0};
  rc = peaks_alloc(fb_hull_stress_nelements(hs), &p, err);
  if (!rc)
    rc = tracker_init(&tr, p->nelements, err);
  if (!rc)
    rc = hs->modal ? track_modal(hs, m, k0, &tr, p, err) : track_nodal(hs, m, k0, &tr, p, err);
  if (!rc)
    finish(&tr, p);
  tracker_free(&tr);
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
