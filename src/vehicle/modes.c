/* SPDX-License-Identifier: BSD-3-Clause */
/* Modes of the linearised vehicle (flexbond/vehicle.h): eigenvalues of
 * the block diagram's exact Jacobian at the static equilibrium (LAPACK
 * dgeev), each described by the body that holds the largest share of its
 * kinetic energy. */
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* Mass (or inertia) and name of the body behind momentum state i: the
 * diagonal entry of its I field's matrix, and the label its fragment
 * declared for that component (fb_bg_set_labels; the element's name when
 * it declared none, the finite-element hull's coordinates). */
static double body_of_state(const fb_bg *g, const fb_bd *bd, size_t i, char *name, size_t size)
{
  size_t comp = 0;
  const long e = fb_bd_state_element(bd, i, &comp);
  const char *label = fb_bg_element_label(g, (size_t)e, comp);
  snprintf(name, size, "%s", label ? label : fb_bg_element_name(g, (size_t)e));
  const fb_mat *m = fb_bg_element_matrix(g, (size_t)e);
  const double mass = m ? fb_mat_get(m, comp, comp) : 0.0;
  return mass > 0 ? mass : 1.0;
}

/* Describes eigenvector v (complex, states idx[0..n)) by the largest
 * kinetic-energy share |p|^2 / m among the momentum states. */
static void describe(const fb_bg *g, const fb_bd *bd, const size_t *idx, size_t n,
                     const double *vre, const double *vim, char *out, size_t size)
{
  double total = 0.0, best = -1.0;
  char best_name[64] = "?";
  for (size_t k = 0; k < n; ++k) {
    if (fb_bd_state_kind(bd, idx[k]) != FB_STATE_MOMENTUM)
      continue;
    char name[64];
    double m = body_of_state(g, bd, idx[k], name, sizeof name);
    double ke = (vre[k] * vre[k] + (vim ? vim[k] * vim[k] : 0.0)) / m;
    total += ke;
    if (ke > best) {
      best = ke;
      snprintf(best_name, sizeof best_name, "%s", name);
    }
  }
  snprintf(out, size, "%s (%.0f%%)", best_name, total > 0 ? 100.0 * best / total : 0.0);
}

static int cmp_mode(const void *a, const void *b)
{
  const fb_mode *x = a, *y = b;
  int ox = x->im > 0, oy = y->im > 0;
  if (ox != oy)
    return oy - ox; /* oscillatory first */
  return (x->freq_hz > y->freq_hz) - (x->freq_hz < y->freq_hz);
}

typedef struct eig_work {
  size_t n;
  size_t *idx;
  double *a, *wr, *wi, *vr;
} eig_work;

static void eig_free(eig_work *w)
{
  free(w->idx);
  free(w->a);
  free(w->wr);
  free(w->wi);
  free(w->vr);
}

/* Jacobian restricted to the physical states (probe integrals left out). */
static int physical_jacobian(fb_bd *bd, const double *x, eig_work *w, fb_err *err)
{
  size_t nall = fb_bd_nstates(bd);
  double *jac = malloc((nall * nall + 1) * sizeof *jac);
  w->idx = malloc((nall + 1) * sizeof *w->idx);
  if (!jac || !w->idx) {
    free(jac);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  int rc = fb_bd_jacobian_dense(bd, 0.0, x, jac, err);
  w->n = 0;
  for (size_t i = 0; i < nall; ++i)
    if (fb_bd_state_kind(bd, i) != FB_STATE_PROBE)
      w->idx[w->n++] = i;
  size_t n = w->n;
  w->a = malloc((n * n + 1) * sizeof *w->a);
  w->wr = malloc((n + 1) * sizeof *w->wr);
  w->wi = malloc((n + 1) * sizeof *w->wi);
  w->vr = malloc((n * n + 1) * sizeof *w->vr);
  if (!rc && (!w->a || !w->wr || !w->wi || !w->vr))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t c = 0; !rc && c < n; ++c)
    for (size_t r = 0; r < n; ++r)
      w->a[c * n + r] = jac[w->idx[c] * nall + w->idx[r]];
  free(jac);
  if (rc)
    return rc;
  lapack_int info = LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'V', (lapack_int)n, w->a,
                                  (lapack_int)n, w->wr, w->wi, NULL, 1, w->vr, (lapack_int)n);
  if (info != 0)
    return fb_err_set(err, FB_ESOLVER, "eigenvalues: LAPACK dgeev failed (info %d)", (int)info);
  return FB_OK;
}

/* Collects the modes from the eigen-decomposition in w. */
static int collect(const fb_bg *g, const fb_bd *bd, const eig_work *w, fb_mode **modes,
                   size_t *nmodes, size_t *nstatic, fb_err *err)
{
  size_t n = w->n;
  double scale = 0.0;
  for (size_t k = 0; k < n; ++k)
    scale = fmax(scale, hypot(w->wr[k], w->wi[k]));
  fb_mode *m = calloc(n + 1, sizeof *m);
  if (!m)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  size_t count = 0, zeros = 0;
  const double two_pi = 6.28318530717958647693;
  for (size_t k = 0; k < n; ++k) {
    double mag = hypot(w->wr[k], w->wi[k]);
    /* Zero eigenvalues (self-stress of the indeterminate support) sit at
     * rounding level, ~n eps times the largest eigenvalue. */
    if (mag <= 1e-9 * scale) {
      zeros++;
      continue;
    }
    if (w->wi[k] < 0)
      continue; /* the conjugate of a mode already listed */
    fb_mode *md = &m[count++];
    md->re = w->wr[k];
    md->im = w->wi[k];
    md->freq_hz = mag / two_pi;
    md->damping_ratio = -md->re / mag;
    const double *vre = w->vr + k * n;
    const double *vim = w->wi[k] > 0 ? w->vr + (k + 1) * n : NULL;
    describe(g, bd, w->idx, n, vre, vim, md->description, sizeof md->description);
  }
  qsort(m, count, sizeof *m, cmp_mode);
  *modes = m;
  *nmodes = count;
  *nstatic = zeros;
  return FB_OK;
}

void vehicle_remove_damping(fb_scenario *s)
{
  for (size_t b = 0; b < s->nmounts; ++b)
    s->mount[b].damping = 0.0;
  for (size_t c = 0; c < s->ncorners; ++c) {
    /* The built-in law is sound; its block's c is 0. */
    (void)fb_corner_set_damper(&s->corner[c], &fb_damper_law_linear, NULL, NULL);
    s->corner[c].tire_c = 0.0;
    s->corner[c].stops.bump.damping = 0.0;
    s->corner[c].stops.rebound.damping = 0.0;
  }
  for (size_t b = 0; b < s->nantiroll_bars; ++b)
    s->antiroll_bar[b].damping = 0.0;
  for (size_t b = 0; b < s->nbogies; ++b)
    s->bogie[b].damper_c = 0.0;
}

void vehicle_flatten_road(fb_scenario *s)
{
  fb_road_bump_params *flat = NULL;
  if (fb_scenario_set_road(s, &fb_road_type_bump, (void **)&flat, NULL))
    return; /* the built-in type is sound */
  flat->height = 0.0;
  flat->length = 1.0;
  flat->angle = 0.0;
  /* Every wheel meets the (flat) bump at t >= 0: the rearmost one at
   * first_contact + (x_first - x) / V. */
  flat->first_contact = 0.0;
  for (size_t c = 0; c < s->ncorners; ++c)
    flat->first_contact =
        fmax(flat->first_contact, (s->corner[c].x - s->corner[0].x) / s->speed);
  double last = 0.0;
  for (size_t c = 0; c < s->ncorners; ++c)
    last = fmax(last, fb_scenario_road_exit(s, (int)c));
  s->t_end = fmax(s->t_end, last + 1.0);
}

int vehicle_linear_modes(const fb_bg *g, fb_bd *bd, size_t memory_limit, fb_mode **modes,
                         size_t *nmodes, size_t *nstatic, fb_err *err)
{
  *modes = NULL;
  *nmodes = *nstatic = 0;
  /* The Jacobian, the matrix dgeev overwrites and its eigenvectors. */
  const size_t n = fb_bd_nstates(bd);
  int rc =
      fb_check_dense_eig(n, 3, memory_limit, err,
                         "the vehicle's modes (%zu states; the hull's automatic basis or a "
                         "count of modes keeps them few)",
                         n);
  if (rc)
    return rc;
  eig_work w = {0};
  double *x = calloc(n + 1, sizeof *x);
  double *zero = calloc(n + 1, sizeof *zero);
  rc = x && zero ? fb_sim_static_state(bd, 0.0, zero, x, err)
                 : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = physical_jacobian(bd, x, &w, err);
  if (!rc)
    rc = collect(g, bd, &w, modes, nmodes, nstatic, err);
  eig_free(&w);
  free(x);
  free(zero);
  return rc;
}
