/* SPDX-License-Identifier: BSD-3-Clause */
/* The stresses of System 2's hull over a run (flexbond/hull_stress.h),
 * on the shortened crossing of test_motion.c:
 *   1. the peaks, their times and the ranges against a brute-force
 *      recomputation: per sample u = basis (q0 + q) formed explicitly,
 *      the nodal recovery fb_shell_stress_eval_nodal of a recovery built
 *      separately, the planes' normal stresses in Mohr's double-angle
 *      form, and max / min over the samples by hand;
 *   2. the field at a time: at a sample the sample's, halfway between
 *      two the mean of their stress components (linear in q);
 *   3. the run in nodal coordinates (every DOF a state): the same peak
 *      element, its peak within the modal basis's convergence;
 *   4. a vehicle at rest (static initial state, a flat road):
 *      the peak field is the static field, which is not zero;
 *   5. System 1 has no hull stresses (FB_EINVAL);
 *   6. recording the hull's coordinates alone leaves the run's results
 *      as they are, bit for bit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/hull_stress.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle_util.h"

/* A run of System 2 of s with its motion and the vehicle's recovery. */
typedef struct stress_run {
  fb_vehicle *v;
  fb_vehicle_motion *m;
  fb_hull_stress *hs;
  fb_hull_stress_peaks *p;
} stress_run;

/* kind: FB_VEHICLE_MOTION_ALL or _HULL; the run's result into *res
 * unless res is NULL. */
static void stress_run_threads(const fb_scenario *s, int kind, int threads, stress_run *r,
                               fb_result **out)
{
  fb_err err;
  fb_vehicle_opts o;
  fb_vehicle_opts_default(&o);
  o.motion = kind;
  o.threads = threads;
  fb_result *res = NULL;
  memset(r, 0, sizeof *r);
  REQUIRE(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, &o, &r->v, &err), &err);
  REQUIRE(fb_vehicle_run(r->v, NULL, NULL, NULL, &res, &r->m, &err), &err);
  REQUIRE(fb_hull_stress_new(r->v, &r->hs, &err), &err);
  REQUIRE(fb_hull_stress_peaks_of(r->hs, r->m, 0.0, &r->p, &err), &err);
  if (out)
    *out = res;
  else
    fb_result_free(&res);
}

static void stress_run_kind(const fb_scenario *s, int kind, stress_run *r, fb_result **out)
{
  stress_run_threads(s, kind, 1, r, out);
}

static void stress_run_of(const fb_scenario *s, stress_run *r)
{
  stress_run_kind(s, FB_VEHICLE_MOTION_ALL, r, NULL);
}

static void stress_run_free(stress_run *r)
{
  fb_hull_stress_peaks_free(&r->p);
  fb_hull_stress_free(&r->hs);
  fb_vehicle_motion_free(&r->m);
  fb_vehicle_free(&r->v);
}

/* u = basis (q0 + sample k's q), formed column by column. */
static void nodal_of_sample(const fb_vehicle_motion *m, size_t k, double *u)
{
  const size_t n = 6 * fb_mesh_nnodes(m->mesh);
  const double *row = m->samples + k * m->width;
  memset(u, 0, n * sizeof *u);
  for (size_t j = 0; j < m->ncoords; ++j) {
    const double qj = m->hull_q0[j] + row[1 + j];
    for (size_t i = 0; i < n; ++i)
      u[i] += m->basis[j * n + i] * qj;
  }
}

/* The normal stress on the plane whose normal is at angle a from the
 * local x, in the double-angle form of Mohr's circle (the library uses
 * Cauchy's cos^2, sin^2 form). */
static double normal_stress(const double *sv, double a)
{
  return 0.5 * (sv[0] + sv[1]) + 0.5 * (sv[0] - sv[1]) * cos(2 * a) + sv[2] * sin(2 * a);
}

/* 1. */
static void check_brute_force(const stress_run *r)
{
  fb_err err;
  const fb_vehicle_motion *m = r->m;
  const fb_fe_hull *fe = fb_vehicle_fe_hull_of(r->v);
  fb_shell_stress *rec = NULL;
  REQUIRE(fb_shell_stress_new(fe->mesh, &fe->props, &rec, &err), &err);
  const size_t ne = fb_shell_stress_nelements(rec), n = 6 * fb_mesh_nnodes(m->mesh);
  CHECK(ne == r->p->nelements && r->p->nsamples == m->nsamples);
  double *u = malloc(n * sizeof *u), *peak = calloc(ne, sizeof *peak);
  const size_t np = FB_HULL_STRESS_PLANES, nx = 2 * ne * np;
  double *lo = malloc(nx * sizeof *lo), *hi = malloc(nx * sizeof *hi);
  fb_shell_stress_state *st = malloc(ne * sizeof *st);
  /* vM of every element at every sample, to look up the peak's time. */
  double *vm = malloc(m->nsamples * ne * sizeof *vm);
  for (size_t i = 0; i < nx; ++i) {
    lo[i] = INFINITY;
    hi[i] = -INFINITY;
  }
  for (size_t k = 0; k < m->nsamples; ++k) {
    nodal_of_sample(m, k, u);
    fb_shell_stress_eval_nodal(rec, u, st);
    for (size_t e = 0; e < ne; ++e) {
      vm[k * ne + e] = fmax(st[e].von_mises_top, st[e].von_mises_bottom);
      peak[e] = fmax(peak[e], vm[k * ne + e]);
      for (size_t i = 0; i < 2 * np; ++i) {
        const double a = 3.14159265358979323846 * (double)(i % np) / (double)np;
        const double sn = normal_stress(i < np ? st[e].top : st[e].bottom, a);
        lo[2 * np * e + i] = fmin(lo[2 * np * e + i], sn);
        hi[2 * np * e + i] = fmax(hi[2 * np * e + i], sn);
      }
    }
  }
  double scale = 0.0;
  for (size_t e = 0; e < ne; ++e)
    scale = fmax(scale, peak[e]);
  /* S_e q against D_e (Phi q): the same sums associated differently,
   * round-off of a few eps times the number of terms (m coordinates, 24
   * DOFs) of the largest stress: 1e-12 of the largest peak. */
  const double tol = 1e-12 * scale;
  double worst_peak = 0.0, worst_time = 0.0, worst_range = 0.0;
  for (size_t e = 0; e < ne; ++e) {
    worst_peak = fmax(worst_peak, fabs(r->p->von_mises[e] - peak[e]));
    /* The reported time is a sample at which the peak is reached. */
    size_t k = 0;
    while (k < m->nsamples && m->samples[k * m->width] != r->p->time[e])
      ++k;
    CHECK(k < m->nsamples);
    if (k < m->nsamples)
      worst_time = fmax(worst_time, fabs(vm[k * ne + e] - peak[e]));
    double range = 0.0;
    for (size_t i = 2 * np * e; i < 2 * np * (e + 1); ++i)
      range = fmax(range, hi[i] - lo[i]);
    worst_range = fmax(worst_range, fabs(r->p->range[e] - range));
  }
  fprintf(stderr,
          "brute force, %zu elements x %zu samples: largest peak %.6g Pa; |peak diff| %.3g, "
          "|vM at the peak's time - peak| %.3g, |range diff| %.3g Pa (tol %.3g)\n",
          ne, m->nsamples, scale, worst_peak, worst_time, worst_range, tol);
  CHECK(scale > 1e5);
  CHECK(worst_peak <= tol && worst_time <= tol && worst_range <= tol);
  free(u);
  free(peak);
  free(lo);
  free(hi);
  free(st);
  free(vm);
  fb_shell_stress_free(&rec);
}

/* 2. */
static void check_field_at(const stress_run *r)
{
  fb_err err;
  const fb_vehicle_motion *m = r->m;
  const size_t ne = fb_hull_stress_nelements(r->hs), k = m->nsamples / 2;
  fb_shell_stress_state *a = malloc(ne * sizeof *a), *b = malloc(ne * sizeof *b),
                        *mid = malloc(ne * sizeof *mid);
  const double ta = m->samples[k * m->width], tb = m->samples[(k + 1) * m->width];
  REQUIRE(fb_hull_stress_at(r->hs, m, ta, a, &err), &err);
  REQUIRE(fb_hull_stress_at(r->hs, m, tb, b, &err), &err);
  REQUIRE(fb_hull_stress_at(r->hs, m, 0.5 * (ta + tb), mid, &err), &err);
  double worst = 0.0, scale = 0.0;
  for (size_t e = 0; e < ne; ++e)
    for (int c = 0; c < 3; ++c) {
      worst = fmax(worst, fabs(mid[e].top[c] - 0.5 * (a[e].top[c] + b[e].top[c])));
      worst = fmax(worst, fabs(mid[e].bottom[c] - 0.5 * (a[e].bottom[c] + b[e].bottom[c])));
      scale = fmax(scale, fabs(a[e].top[c]));
    }
  /* Linear in q: round-off (1e-12 of the largest component). */
  CHECK(worst <= 1e-12 * scale);
  /* At the peak's sample, the peak (to round-off: a sum per sample here,
   * a product of blocks of samples there). */
  size_t top = 0;
  REQUIRE(fb_hull_stress_peaks_top(r->p, 1, &top, &err), &err);
  REQUIRE(fb_hull_stress_at(r->hs, m, r->p->time[top], a, &err), &err);
  CHECK_NEAR(a[top].von_mises_max, r->p->von_mises[top], 1e-12 * r->p->von_mises[top]);
  free(a);
  free(b);
  free(mid);
}

/* 3. */
static void check_nodal(fb_scenario *s, const stress_run *modal)
{
  fb_err err;
  stress_run nodal;
  const fb_hull_coordinates was = s->hull_coordinates;
  s->hull_coordinates = FB_HULL_NODAL;
  stress_run_of(s, &nodal);
  s->hull_coordinates = was;
  CHECK(!nodal.m->basis && nodal.m->ncoords == 6 * fb_mesh_nnodes(nodal.m->mesh));
  size_t em = 0, en = 0;
  REQUIRE(fb_hull_stress_peaks_top(modal->p, 1, &em, &err), &err);
  REQUIRE(fb_hull_stress_peaks_top(nodal.p, 1, &en, &err), &err);
  const double pm = modal->p->von_mises[em], pn = nodal.p->von_mises[en];
  fprintf(stderr,
          "peak element: modal %ld (%.6g Pa at %.4g s), nodal %ld (%.6g Pa at %.4g s): "
          "%.3g relative\n",
          fb_mesh_element_id(modal->m->mesh, em), pm, modal->p->time[em],
          fb_mesh_element_id(nodal.m->mesh, en), pn, nodal.p->time[en], fabs(pm - pn) / pn);
  CHECK(em == en);
  /* The auto basis holds the exact static response to every force the
   * vehicle puts on the hull (its first block, the residual flexibility),
   * so the stresses of a quasi-static load are exact; what it leaves out
   * is the dynamic remainder beyond the block whose change in the
   * receptances is under FB_HULL_BLOCK_TOL (1e-3 of their scale). A peak
   * stress is a sum over those receptances' responses, so its error is of
   * that order times the dynamic share: 1e-2 allows ten times the basis's
   * own tolerance for the stress, a derived (differentiated) quantity. */
  CHECK(fabs(pm - pn) <= 1e-2 * pn);
  stress_run_free(&nodal);
}

/* 4. */
static void check_at_rest(fb_scenario *s)
{
  fb_err err;
  fb_road_bump_params *bump = road_bump(s);
  const fb_road_bump_params was = *bump;
  const fb_initial_state initial = s->initial;
  bump->height = 0.0;
  bump->type = -1;
  s->initial = FB_INITIAL_STATIC;
  stress_run r;
  stress_run_of(s, &r);
  const size_t ne = r.p->nelements;
  fb_shell_stress_state *st = malloc(ne * sizeof *st);
  REQUIRE(fb_hull_stress_at(r.hs, r.m, 0.0, st, &err), &err);
  double scale = 0.0, worst = 0.0;
  for (size_t e = 0; e < ne; ++e) {
    scale = fmax(scale, st[e].von_mises_max);
    worst = fmax(worst, fabs(r.p->von_mises[e] - st[e].von_mises_max));
  }
  fprintf(stderr, "at rest: static field up to %.6g Pa, peaks differ by up to %.3g Pa\n", scale,
          worst);
  /* The weight stresses the hull (MPa at least for steel plates). */
  CHECK(scale > 1e5);
  /* At equilibrium the run stays where it began, but for the integrator's
   * error control (rtol 1e-6 of the scenario, a global error ten to a
   * hundred times that): 1e-4 of the static field. */
  CHECK(worst <= 1e-4 * scale);
  free(st);
  stress_run_free(&r);
  *bump = was;
  s->initial = initial;
}

/* 6. The hull's coordinates alone: no state added, so the run is a run
 * without motion to the bit, and the peaks are the whole motion's within
 * the solver's tolerance (that run's states differ; rtol 1e-6, a global
 * error ten to a hundred times it: 1e-4 of the largest peak). */
static void check_hull_only(const fb_scenario *s, const stress_run *all)
{
  fb_err err;
  fb_result *plain = NULL, *res = NULL;
  stress_run r;
  REQUIRE(fb_vehicle_simulate(s, FB_SYSTEM_FLEXIBLE, &plain, &err), &err);
  stress_run_kind(s, FB_VEHICLE_MOTION_HULL, &r, &res);
  CHECK(r.m->nattach == 0 && r.m->nmounts == 0 && r.m->ncorners == 0);
  CHECK(fb_result_nsamples(res) == fb_result_nsamples(plain) &&
        fb_result_ncols(res) == fb_result_ncols(plain));
  size_t differ = 0;
  for (size_t k = 0; k < fb_result_nsamples(res) && k < fb_result_nsamples(plain); ++k)
    differ += memcmp(fb_result_row(res, k), fb_result_row(plain, k),
                     fb_result_ncols(res) * sizeof(double)) != 0;
  CHECK(differ == 0);
  double scale = 0.0, worst = 0.0;
  for (size_t e = 0; e < r.p->nelements; ++e) {
    scale = fmax(scale, all->p->von_mises[e]);
    worst = fmax(worst, fabs(r.p->von_mises[e] - all->p->von_mises[e]));
  }
  fprintf(stderr,
          "hull coordinates alone: %zu rows differ from a plain run; peaks within %.3g "
          "of the largest\n",
          differ, worst / scale);
  CHECK(worst <= 1e-4 * scale);
  fb_result_free(&plain);
  fb_result_free(&res);
  stress_run_free(&r);
}

/* 5. */
static void check_rigid(const fb_scenario *s)
{
  fb_err err;
  fb_vehicle *v = NULL;
  fb_hull_stress *hs = NULL;
  REQUIRE(fb_vehicle_new(s, FB_SYSTEM_RIGID, NULL, &v, &err), &err);
  CHECK(fb_hull_stress_new(v, &hs, &err) == FB_EINVAL && !hs);
  fb_vehicle_free(&v);
}

/* Two threads, each tracking half the samples, merged: the same peaks,
 * times, surfaces and ranges as one (the products are the same sums; the
 * merge keeps the earlier time of an equal peak). */
static void check_threads(const fb_scenario *s, const stress_run *one)
{
  stress_run two;
  stress_run_threads(s, FB_VEHICLE_MOTION_ALL, 2, &two, NULL);
  const fb_hull_stress_peaks *a = one->p, *b = two.p;
  CHECK(a->nelements == b->nelements && a->nsamples == b->nsamples);
  double top = 0.0, worst = 0.0;
  size_t other_time = 0, other_surface = 0;
  for (size_t e = 0; e < a->nelements && e < b->nelements; ++e) {
    top = fmax(top, fmax(a->von_mises[e], a->range[e]));
    worst = fmax(
        worst, fmax(fabs(a->von_mises[e] - b->von_mises[e]), fabs(a->range[e] - b->range[e])));
    other_time += a->time[e] != b->time[e];
    other_surface +=
        a->surface[e] != b->surface[e] || a->range_surface[e] != b->range_surface[e];
  }
  /* 1e-12: the two runs' matrix products may round differently in their
   * last bits (a block's columns are formed alike, but the blocks start
   * at other samples). */
  CHECK(worst <= 1e-12 * top);
  CHECK(other_time == 0 && other_surface == 0);
  printf("two threads against one: largest difference %.3g of %.3g Pa, %zu times and %zu "
         "surfaces differ\n",
         worst, top, other_time, other_surface);
  stress_run_free(&two);
}

int main(void)
{
  fb_scenario *s = load_short();
  stress_run r;
  stress_run_of(s, &r);
  CHECK(r.m->basis != NULL);
  check_brute_force(&r);
  check_field_at(&r);
  check_nodal(s, &r);
  check_hull_only(s, &r);
  check_threads(s, &r);
  stress_run_free(&r);
  check_at_rest(s);
  check_rigid(s);
  fb_scenario_free(&s);
  return check_report("test_hull_stress");
}
