/* SPDX-License-Identifier: BSD-3-Clause */
/* The motion of a run's vehicle (flexbond/vehicle.h): probes on the
 * assembled graph that measure it, and its value at any time of the run
 * for an animation. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

void fb_vehicle_motion_free(fb_vehicle_motion **m)
{
  if (!m || !*m)
    return;
  fb_mesh_free(&(*m)->mesh);
  free((*m)->basis);
  free((*m)->samples);
  free((*m)->hull_q0);
  free(*m);
  *m = NULL;
}

size_t fb_vehicle_motion_nprobes(const fb_scenario *s, int hull_only)
{
  return hull_only ? 1 : 2 + s->nmounts + s->ncorners;
}

/* A probe of every component of target's integrated flow. The names
 * start with '#', which no output's name has (they are plain names), so
 * they never meet an output's. */
static fb_probe_spec displacement_probe(char *name, char *target)
{
  return (fb_probe_spec){name, FB_PROBE_FLOW, target, -1, 1, 1.0, "m", NULL, 0};
}

int fb_vehicle_motion_probes(const fb_scenario *s, const fb_hull *hull, int hull_only,
                             fb_probe_spec *p, fb_err *err)
{
  const vehicle_signal *body =
                           vehicle_fragment_signal(FB_OUTPUT_OF_MOUNT, VEHICLE_SIGNAL_MOTION),
                       *wheel =
                           vehicle_fragment_signal(FB_OUTPUT_OF_CORNER, VEHICLE_SIGNAL_MOTION);
  if (!body || !wheel)
    return fb_err_set(err, FB_EMODEL, "a fragment offers no motion");
  size_t k = 0;
  p[k] = (fb_probe_spec){fb_strdup("#hull"),
                         hull->torsion_kind,
                         fb_strdup_printf("hull.%s", hull->torsion_target),
                         -1,
                         hull->torsion_integrate,
                         1.0,
                         NULL,
                         NULL,
                         0};
  ++k;
  if (!hull_only)
    p[k++] = displacement_probe(fb_strdup("#attach"), fb_strdup("b_attach"));
  for (size_t b = 0; !hull_only && b < s->nmounts; ++b, ++k)
    p[k] = displacement_probe(fb_strdup_printf("#body_%s", s->mount[b].name),
                              vehicle_target(s, FB_OUTPUT_OF_MOUNT, b, body->target));
  for (size_t c = 0; !hull_only && c < s->ncorners; ++c, ++k)
    p[k] = displacement_probe(fb_strdup_printf("#wheel_%s", s->corner[c].name),
                              vehicle_target(s, FB_OUTPUT_OF_CORNER, c, wheel->target));
  for (size_t i = 0; i < k; ++i)
    if (!p[i].name || !p[i].target)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
  return FB_OK;
}

/* The rows of res that cover window: [*lo, *hi). */
static void window_rows(const fb_result *res, const double *window, size_t *lo, size_t *hi)
{
  const size_t n = fb_result_nsamples(res);
  *lo = 0;
  *hi = n;
  if (!window)
    return;
  while (*lo + 1 < n && fb_result_row(res, *lo + 1)[0] <= window[0])
    ++*lo;
  while (*hi > *lo + 1 && fb_result_row(res, *hi - 2)[0] >= window[1])
    --*hi;
}

int fb_vehicle_motion_take(const fb_scenario *s, fb_result *res, size_t first,
                           const double *window, int hull_only, fb_vehicle_motion *m,
                           fb_err *err)
{
  m->nattach = hull_only ? 0 : fb_scenario_nattach(s);
  m->nmounts = hull_only ? 0 : s->nmounts;
  m->ncorners = hull_only ? 0 : s->ncorners;
  m->width = 1 + m->ncoords + m->nattach + m->nmounts + m->ncorners;
  size_t lo, hi;
  window_rows(res, window, &lo, &hi);
  m->nsamples = hi - lo;
  const size_t ncols = fb_result_ncols(res);
  if (ncols != first + m->width - 1)
    return fb_err_set(err, FB_EINVAL,
                      "the run has %zu columns where the outputs and the motion make %zu",
                      ncols, first + m->width - 1);
  if (m->nsamples > SIZE_MAX / sizeof *m->samples / m->width)
    return fb_err_set(err, FB_ENOMEM, "motion of %zu samples is too large", m->nsamples);
  m->samples = malloc((m->nsamples ? m->nsamples : 1) * m->width * sizeof *m->samples);
  m->hull_q0 = malloc((m->ncoords ? m->ncoords : 1) * sizeof *m->hull_q0);
  if (!m->samples || !m->hull_q0)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the motion's %zu samples",
                      m->nsamples);
  /* The hull's coordinates from t = 0's, as every integrated
   * displacement is (System 2's q starts at the static state with
   * simulation.initial: static). */
  for (size_t j = 0; j < m->ncoords; ++j)
    m->hull_q0[j] = fb_result_nsamples(res) ? fb_result_row(res, 0)[first + j] : 0.0;
  for (size_t k = 0; k < m->nsamples; ++k) {
    const double *row = fb_result_row(res, lo + k), *q0 = fb_result_row(res, 0) + first;
    double *to = m->samples + k * m->width;
    to[0] = row[0];
    memcpy(to + 1, row + first, (m->width - 1) * sizeof *to);
    for (size_t j = 0; j < m->ncoords; ++j)
      to[1 + j] -= q0[j];
  }
  return fb_result_truncate(res, first, err);
}

/* Row interpolation: the sample at or before t and the weight of the
 * next. */
static void locate(const fb_vehicle_motion *m, double t, size_t *k, double *w)
{
  const double *t0 = m->samples, *tn = m->samples + (m->nsamples - 1) * m->width;
  *w = 0.0;
  if (m->nsamples < 2 || t <= t0[0]) {
    *k = 0;
    return;
  }
  if (t >= tn[0]) {
    *k = m->nsamples - 1;
    return;
  }
  size_t lo = 0, hi = m->nsamples - 1; /* t in [t_lo, t_hi) */
  while (hi - lo > 1) {
    const size_t mid = lo + (hi - lo) / 2;
    if (m->samples[mid * m->width] <= t)
      lo = mid;
    else
      hi = mid;
  }
  const double ta = m->samples[lo * m->width], tb = m->samples[hi * m->width];
  *k = lo;
  *w = tb > ta ? (t - ta) / (tb - ta) : 0.0;
}

/* Columns first .. first + n of the interpolated row into out. */
static void row_values(const fb_vehicle_motion *m, size_t k, double w, size_t first, size_t n,
                       double *out)
{
  const double *a = m->samples + k * m->width + first;
  const double *b = w > 0 ? a + m->width : a;
  for (size_t j = 0; j < n; ++j)
    out[j] = (1.0 - w) * a[j] + w * b[j];
}

/* System 1's hull: node (x, y) rises by z + y phi - x theta; carrying
 * mounted rigid bodies, its six coordinates (x, y, z, phi, theta, psi)
 * move node r by T(r) q (small motion, vehicle_rigid_transport). */
static void rigid_nodes(const fb_mesh *mesh, size_t ncoords, const double *q, double *u)
{
  for (size_t i = 0; i < fb_mesh_nnodes(mesh); ++i) {
    const double *x = fb_mesh_node_xyz(mesh, i);
    double *ui = u + 6 * i;
    memset(ui, 0, 6 * sizeof *ui);
    if (ncoords == 6) {
      double t[36];
      vehicle_rigid_transport(x, t);
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c)
          ui[r] += t[6 * r + c] * q[c];
      continue;
    }
    ui[2] = q[0] + x[1] * q[1] - x[0] * q[2];
    ui[3] = q[1];
    ui[4] = q[2];
  }
}

/* System 2's hull: u = T q, or q itself in nodal coordinates. */
static void flexible_nodes(const fb_vehicle_motion *m, const double *q, double *u)
{
  const size_t n = 6 * fb_mesh_nnodes(m->mesh);
  if (!m->basis) {
    memcpy(u, q, n * sizeof *u);
    return;
  }
  memset(u, 0, n * sizeof *u);
  for (size_t j = 0; j < m->ncoords; ++j) {
    const double *col = m->basis + j * n;
    for (size_t i = 0; i < n; ++i)
      u[i] += col[i] * q[j];
  }
}

int fb_vehicle_motion_at(const fb_vehicle_motion *m, const fb_mesh *mesh, double t,
                         double *node_u, double *attach_dz, double *body_dz, double *wheel_dz,
                         fb_err *err)
{
  const int flexible = m->sys == FB_SYSTEM_FLEXIBLE;
  if (node_u && flexible && mesh != m->mesh)
    return fb_err_set(err, FB_EINVAL, "System 2's hull moves its own mesh only");
  if (node_u && !flexible && m->ncoords != 3 && m->ncoords != 6)
    return fb_err_set(err, FB_EINVAL, "System 1's hull has 3 or 6 coordinates, not %zu",
                      m->ncoords);
  if (m->nsamples == 0)
    return fb_err_set(err, FB_EINVAL, "the run has no samples");
  size_t k = 0;
  double w = 0.0;
  locate(m, t, &k, &w);
  size_t col = 1;
  if (node_u) {
    double *q = malloc((m->ncoords ? m->ncoords : 1) * sizeof *q);
    if (!q)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    row_values(m, k, w, col, m->ncoords, q);
    if (flexible)
      flexible_nodes(m, q, node_u);
    else
      rigid_nodes(mesh, m->ncoords, q, node_u);
    free(q);
  }
  col += m->ncoords;
  if (attach_dz)
    row_values(m, k, w, col, m->nattach, attach_dz);
  col += m->nattach;
  if (body_dz)
    row_values(m, k, w, col, m->nmounts, body_dz);
  col += m->nmounts;
  if (wheel_dz)
    row_values(m, k, w, col, m->ncorners, wheel_dz);
  return FB_OK;
}

int fb_vehicle_motion_coords_at(const fb_vehicle_motion *m, double t, double *q, fb_err *err)
{
  if (m->nsamples == 0)
    return fb_err_set(err, FB_EINVAL, "the run has no samples");
  size_t k = 0;
  double w = 0.0;
  locate(m, t, &k, &w);
  row_values(m, k, w, 1, m->ncoords, q);
  for (size_t j = 0; j < m->ncoords; ++j)
    q[j] += m->hull_q0[j];
  return FB_OK;
}
