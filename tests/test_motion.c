/* SPDX-License-Identifier: BSD-3-Clause */
/* The vehicle's motion for an animation (fb_vehicle_run of a vehicle made with
 * fb_vehicle_opts.motion), against signals measured another way on the same run:
 *   1. the run's outputs are those of a run without it, within the
 *      solver's tolerance (the motion's integrated displacements are
 *      states the error test sees);
 *   2. each wheel's displacement minus its attachment point's is the
 *      wheel_travel output (the integrated flow of the suspension arm);
 *   3. each mounted body's attachment point minus the body is the
 *      mount's spring deflection (a state of its C element);
 *   4. the hull's nodes at the attachment points move as the attachment
 *      points do: System 1 through its rigid rows, System 2 through its
 *      coordinates (u = T q, T the free-free modes);
 *   5. interpolation between samples is linear and clamped to the run;
 *   6. a motion kept over a window is the whole run's rows that cover
 *      it, the same numbers (the same run, taken apart differently).
 * On the shortened crossing of test_system2_sim.c. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle_util.h"

/* Largest |a_k - b_k| over the samples, a and b read by fn. */
typedef double (*sample_fn)(const fb_vehicle_motion *m, const fb_result *r, size_t k, size_t i);

static double wheel_travel_motion(const fb_vehicle_motion *m, const fb_result *r, size_t k,
                                  size_t c)
{
  (void)r;
  const double *row = m->samples + k * m->width;
  return row[1 + m->ncoords + m->nattach + m->nmounts + c] - row[1 + m->ncoords + c];
}

static double mount_travel_motion(const fb_vehicle_motion *m, const fb_result *r, size_t k,
                                  size_t b)
{
  (void)r;
  const double *row = m->samples + k * m->width;
  return row[1 + m->ncoords + m->ncorners + b] - row[1 + m->ncoords + m->nattach + b];
}

/* max_k |fn(k) - r's column j at k| / range of column j. */
static double worst_against(const fb_vehicle_motion *m, const fb_result *r, const char *col,
                            sample_fn fn, size_t i)
{
  const long j = fb_result_find(r, col);
  CHECK(j > 0);
  if (j <= 0)
    return INFINITY;
  double worst = 0.0;
  for (size_t k = 0; k < fb_result_nsamples(r); ++k)
    worst = fmax(worst, fabs(fn(m, r, k, i) - fb_result_row(r, k)[j]));
  return worst / result_range(r, (size_t)j);
}

static void add_outputs(fb_scenario *s)
{
  const size_t n = s->noutputs + s->ncorners + 1;
  s->output = realloc(s->output, n * sizeof *s->output);
  for (size_t c = 0; c < s->ncorners; ++c) {
    fb_output_spec *o = &s->output[s->noutputs++];
    memset(o, 0, sizeof *o);
    char name[64];
    snprintf(name, sizeof name, "wt_%s", s->corner[c].name);
    o->name = strdup(name);
    o->signal = strdup("wheel_travel");
    o->of = strdup(s->corner[c].name);
    o->unit = strdup("m");
  }
  fb_output_spec *o = &s->output[s->noutputs++];
  memset(o, 0, sizeof *o);
  o->name = strdup("mt_driver");
  o->signal = strdup("travel");
  o->of = strdup(s->mount[0].name);
  o->unit = strdup("m");
}

/* A run of system sys of s with its motion over window (NULL: all),
 * from a vehicle realised for it. */
static int run_motion(const fb_scenario *s, fb_system sys, const double *window, fb_result **r,
                      fb_vehicle_motion **m, fb_err *err)
{
  fb_vehicle_opts o;
  fb_vehicle_opts_default(&o);
  o.motion = 1;
  fb_vehicle *v = NULL;
  int rc = fb_vehicle_new(s, sys, &o, &v, err);
  if (!rc)
    rc = fb_vehicle_run(v, window, NULL, NULL, r, m, err);
  fb_vehicle_free(&v);
  return rc;
}

/* 1-3 for system sys; returns the motion. */
static fb_vehicle_motion *check_run(const fb_scenario *s, fb_system sys)
{
  fb_err err;
  fb_result *plain = NULL, *r = NULL;
  fb_vehicle_motion *m = NULL;
  REQUIRE(fb_vehicle_simulate(s, sys, &plain, &err), &err);
  REQUIRE(run_motion(s, sys, NULL, &r, &m, &err), &err);
  CHECK(fb_result_ncols(r) == fb_result_ncols(plain));
  for (size_t j = 0; j < fb_result_ncols(r); ++j)
    CHECK(!strcmp(fb_result_col_name(r, j), fb_result_col_name(plain, j)));
  CHECK(m->nsamples == fb_result_nsamples(r));
  /* 1. rtol 1e-6 of the scenario; the runs' steps differ, so each
   * output differs by what the error control allows, the global error
   * of each run (which is commonly ten to a hundred times rtol): measured
   * up to 1.4e-5 of the range (System 1's RM tire force), 5e-7 in
   * System 2; bounded by a hundred times rtol. */
  check_close(plain, r, 1e-4,
              sys == FB_SYSTEM_RIGID ? "system 1 with motion"
                                     : "system 2 "
                                       "with motion");
  /* 2. Both sides are integrals, over the same steps, of velocities
   * whose difference is zero identically: they differ by round-off
   * (measured up to 1e-14 of the range), bounded by 1e-10. */
  for (size_t c = 0; c < s->ncorners; ++c) {
    char col[64];
    snprintf(col, sizeof col, "wt_%s", s->corner[c].name);
    const double w = worst_against(m, r, col, wheel_travel_motion, c);
    fprintf(stderr, "system %d: %s against wheel - attachment: %.3g of range\n", (int)sys, col,
            w);
    CHECK(w <= 1e-10);
  }
  /* 3. The spring's deflection is a state, the displacements integrals
   * of the flows that drive it: round-off again (measured 2e-14). */
  const double w = worst_against(m, r, "mt_driver", mount_travel_motion, 0);
  fprintf(stderr, "system %d: mt_driver against attachment - body: %.3g of range\n", (int)sys,
          w);
  CHECK(w <= 1e-10);
  fb_result_free(&plain);
  fb_result_free(&r);
  return m;
}

/* Attachment point a's node of System 2's mesh: its node set's one node
 * (SUSP_<CORNER>, the mount's name in capitals). */
static long attach_node(const fb_scenario *s, const fb_mesh *mesh, size_t a)
{
  char set[64];
  if (a < s->ncorners)
    snprintf(set, sizeof set, "SUSP_%s", s->corner[a].name);
  else {
    size_t i = 0;
    for (const char *p = s->mount[a - s->ncorners].name; *p && i + 1 < sizeof set; ++p)
      set[i++] = (char)toupper((unsigned char)*p);
    set[i] = '\0';
  }
  const size_t *nodes = NULL;
  size_t n = 0;
  if (!fb_mesh_nset(mesh, set, &nodes, &n) || n != 1)
    return -1;
  return (long)nodes[0];
}

/* 4. A mesh of the attachment points (System 1), or System 2's own mesh
 * at the nodes of the attachment points (the example couples each to
 * one node). */
static void check_nodes(const fb_scenario *s, const fb_vehicle_motion *m)
{
  fb_err err;
  const size_t na = fb_scenario_nattach(s);
  fb_mesh *own = NULL;
  const fb_mesh *mesh = m->mesh;
  if (!mesh) {
    REQUIRE(fb_mesh_new(&own, &err), &err);
    for (size_t a = 0; a < na; ++a) {
      const double x = a < s->ncorners ? s->corner[a].x : s->mount[a - s->ncorners].x;
      const double y = a < s->ncorners ? s->corner[a].y : s->mount[a - s->ncorners].y;
      size_t index = 0;
      REQUIRE(fb_mesh_add_node(own, (long)a + 1, x, y, 0.0, &index, &err), &err);
    }
    mesh = own;
  }
  double *u = malloc(6 * fb_mesh_nnodes(mesh) * sizeof *u), *dz = malloc(na * sizeof *dz);
  double worst = 0.0, big = 0.0;
  const double t_last = m->samples[(m->nsamples - 1) * m->width];
  size_t nchecked = 0;
  for (size_t i = 0; 0.05 * (double)i <= t_last; ++i) {
    const double t = 0.05 * (double)i;
    REQUIRE(fb_vehicle_motion_at(m, mesh, t, u, dz, NULL, NULL, &err), &err);
    for (size_t a = 0; a < na; ++a) {
      const long node = own ? (long)a : attach_node(s, mesh, a);
      if (node < 0)
        continue;
      ++nchecked;
      worst = fmax(worst, fabs(u[6 * (size_t)node + 2] - dz[a]));
      big = fmax(big, fabs(dz[a]));
    }
  }
  fprintf(stderr, "system %d: hull nodes against attachment points: %.3g m of %.3g m\n",
          (int)m->sys, worst, big);
  CHECK(nchecked > 0);
  CHECK(big > 0.01);
  /* Integrals against states (System 2) or against the rigid rows of
   * the same integrals (System 1, equal to round-off): 1e-4 of the
   * largest, as in 1-3. */
  CHECK(worst <= 1e-4 * big);
  free(u);
  free(dz);
  fb_mesh_free(&own);
}

/* 5. Halfway between two samples, each value is their mean; before the
 * run its first sample, after it its last. */
static void check_interpolation(const fb_vehicle_motion *m)
{
  fb_err err;
  double *mid = malloc(m->ncorners * sizeof *mid);
  const size_t k = m->nsamples / 2;
  const double *a = m->samples + k * m->width, *b = a + m->width;
  REQUIRE(fb_vehicle_motion_at(m, NULL, 0.5 * (a[0] + b[0]), NULL, NULL, NULL, mid, &err),
          &err);
  const size_t first = 1 + m->ncoords + m->nattach + m->nmounts;
  for (size_t c = 0; c < m->ncorners; ++c)
    CHECK_NEAR(mid[c], 0.5 * (a[first + c] + b[first + c]), 1e-15);
  const double *last = m->samples + (m->nsamples - 1) * m->width;
  REQUIRE(fb_vehicle_motion_at(m, NULL, last[0] + 10.0, NULL, NULL, NULL, mid, &err), &err);
  for (size_t c = 0; c < m->ncorners; ++c)
    CHECK(mid[c] == last[first + c]);
  REQUIRE(fb_vehicle_motion_at(m, NULL, -1.0, NULL, NULL, NULL, mid, &err), &err);
  for (size_t c = 0; c < m->ncorners; ++c)
    CHECK(mid[c] == m->samples[first + c]);
  free(mid);
}

/* 6. The run again, its motion kept over [0.3, 0.7] of its span: the
 * rows from the last at or before the window's start to the first at or
 * after its end, bit for bit those of the whole run's motion m (the same
 * steps; the hull's coordinates from the same t = 0 row). */
static void check_window(const fb_scenario *s, const fb_vehicle_motion *m)
{
  fb_err err;
  fb_result *r = NULL;
  fb_vehicle_motion *w = NULL;
  const double t_end = m->samples[(m->nsamples - 1) * m->width];
  /* Between samples, so that each end brackets. */
  const double window[2] = {0.3 * t_end + 1e-4, 0.7 * t_end + 1e-4};
  REQUIRE(run_motion(s, m->sys, window, &r, &w, &err), &err);
  size_t lo = 0;
  while (m->samples[(lo + 1) * m->width] <= window[0])
    ++lo;
  size_t hi = lo;
  while (m->samples[hi * m->width] < window[1])
    ++hi;
  CHECK(w->nsamples == hi - lo + 1);
  CHECK(w->width == m->width);
  CHECK(w->samples[0] <= window[0] && w->samples[(w->nsamples - 1) * w->width] >= window[1]);
  if (w->nsamples == hi - lo + 1 && w->width == m->width)
    CHECK(!memcmp(w->samples, m->samples + lo * m->width,
                  w->nsamples * w->width * sizeof *w->samples));
  CHECK(fb_result_nsamples(r) == m->nsamples);
  fb_vehicle_motion_free(&w);
  fb_result_free(&r);
}

int main(void)
{
  fb_scenario *s = load_short();
  add_outputs(s);
  for (int sys = FB_SYSTEM_RIGID; sys <= FB_SYSTEM_FLEXIBLE; ++sys) {
    fb_vehicle_motion *m = check_run(s, (fb_system)sys);
    CHECK(m->sys == (fb_system)sys);
    /* System 1's (z, phi, theta); System 2's reduced modal basis (the
     * default hull.fe.modes: auto), which the motion maps to the nodes. */
    if (sys == FB_SYSTEM_RIGID)
      CHECK(m->ncoords == 3u && !m->basis);
    else
      CHECK(m->basis && m->ncoords > 6 && m->ncoords < 6 * fb_mesh_nnodes(m->mesh));
    CHECK((sys == FB_SYSTEM_FLEXIBLE) == (m->mesh != NULL));
    check_nodes(s, m);
    check_interpolation(m);
    check_window(s, m);
    fb_vehicle_motion_free(&m);
  }
  fb_scenario_free(&s);
  return check_report("test_motion");
}
