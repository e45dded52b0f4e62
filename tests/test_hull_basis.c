/* SPDX-License-Identifier: BSD-3-Clause */
/* System 2's modal basis under hull.fe.modes: auto (fb_vehicle), against
 * the same vehicle with every free-free mode and in nodal coordinates:
 *   1. the default basis keeps every output within 1e-3 of its range of
 *      both references, and its error estimate (fb_vehicle_basis_error)
 *      is within a factor of 3 of the error measured against every mode;
 *   2. one vehicle assembles its hull once and solves each eigenproblem
 *      once, whatever it is asked (runs, modes, the estimator);
 *   3. the vehicle's modes in the reduced basis agree with the nodal
 *      model's within the band the basis converged over;
 *   4. bad requests: a cut-off below the first elastic mode, more modes
 *      than the mesh has, a factorisation over the memory limit.
 * The crossing is the reference scenario's (3.7 m bump at 10 km/h, from a
 * zero start) with the bump met at 2 s, so that the nodal run takes
 * seconds; the outputs are compared from the bump on. (The settling from
 * the zero start excites every mode of the hull, which no truncated basis
 * follows: the report says so. Met at 1 s, the bump finds the hull still
 * ringing and the driver's acceleration 1.6e-3 off; at 2 s 1.3e-4, as at
 * the scenario's 5 s.) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "check.h"
#include "road_util.h"
#include "vehicle_util.h"

/* The reference scenario with the first wheel meeting the bump at 2 s and
 * the run ending 0.4 s after the last leaves it. */
static fb_scenario *load_crossing(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  REQUIRE(fb_scenario_load("../examples/apc6x6.yaml", &s, &err), &err);
  road_bump(s)->first_contact = 2.0;
  double last = 0.0;
  for (size_t c = 0; c < s->ncorners; ++c)
    last = fmax(last, fb_scenario_road_exit(s, (int)c));
  s->t_end = ceil((last + 0.4) * 10.0) / 10.0;
  return s;
}

/* A vehicle of s's System 2 with the given coordinates and modes. */
static fb_vehicle *realise(fb_scenario *s, fb_hull_coordinates coordinates,
                           fb_hull_modes_kind kind, const fb_vehicle_opts *o)
{
  fb_err err;
  s->hull_coordinates = coordinates;
  s->hull_modes_kind = kind;
  fb_vehicle *v = NULL;
  REQUIRE(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, o, &v, &err), &err);
  return v;
}

static fb_result *run(fb_vehicle *v)
{
  fb_err err;
  fb_result *r = NULL;
  REQUIRE(fb_vehicle_run(v, NULL, NULL, NULL, &r, NULL, &err), &err);
  return r;
}

/* The largest |a - ref| of output column col from t0 on, over ref's range
 * there. */
static double error_of_range(const fb_result *a, const fb_result *ref, size_t col, double t0)
{
  double lo = INFINITY, hi = -INFINITY, worst = 0.0;
  for (size_t k = 0; k < fb_result_nsamples(ref); ++k) {
    const double *r = fb_result_row(ref, k);
    if (r[0] < t0)
      continue;
    lo = fmin(lo, r[col]);
    hi = fmax(hi, r[col]);
    worst = fmax(worst, fabs(fb_result_row(a, k)[col] - r[col]));
  }
  return hi > lo ? worst / (hi - lo) : worst;
}

/* The two runs of one model still differ by their integrations' errors:
 * every mode against nodal coordinates (the same model, test_system2_sim)
 * differs by up to 1.3e-5 of a range at the scenario's rtol 1e-6
 * (measured on this crossing and on the 15 s one). Below 5e-5 a measured
 * basis error is mostly that, and a ratio to it says nothing about the
 * estimator: there only the bound is checked. */
#define INTEGRATION_FLOOR 5e-5

/* 1. */
static void test_accuracy(fb_scenario *s)
{
  fb_err err;
  fb_vehicle *v = realise(s, FB_HULL_MODAL, FB_HULL_MODES_AUTO, NULL);
  fb_vehicle *all = realise(s, FB_HULL_MODAL, FB_HULL_MODES_ALL, NULL);
  fb_vehicle *nodal = realise(s, FB_HULL_NODAL, FB_HULL_MODES_AUTO, NULL);
  s->hull_coordinates = FB_HULL_MODAL;
  s->hull_modes_kind = FB_HULL_MODES_AUTO;
  fb_result *r = run(v), *r_all = run(all), *r_nodal = run(nodal);
  const double window[2] = {road_bump(s)->first_contact, s->t_end};
  double *est = malloc(s->noutputs * sizeof *est);
  CHECK(est != NULL);
  if (est)
    REQUIRE(fb_vehicle_basis_error(v, r, window, NULL, NULL, est, &err), &err);
  const fb_hull_basis *b = fb_vehicle_hull_basis(v);
  fprintf(stderr,
          "auto basis: %zu coordinates (%zu rigid-body modes, %zu Ritz vectors in %zu blocks, "
          "converged over 0 to %.4g Hz)\n",
          b->ncoords, b->nmodes, b->nstatic, b->nblocks, b->cutoff_hz);
  CHECK(b->ncoords < b->ndof && b->nstatic > 0 && b->nblocks >= 2);
  CHECK(b->block_change <= FB_HULL_BLOCK_TOL);
  size_t nratio = 0;
  for (size_t o = 0; est && o < s->noutputs; ++o) {
    const size_t col = o + 1;
    const double e_all = error_of_range(r, r_all, col, window[0]);
    const double e_nodal = error_of_range(r, r_nodal, col, window[0]);
    fprintf(stderr, "  %-15s vs every mode %.2e, vs nodal %.2e, estimated %.2e\n",
            fb_result_col_name(r, col), e_all, e_nodal, est[o]);
    CHECK(e_all <= 1e-3 && e_nodal <= 1e-3);
    CHECK(est[o] <= 1e-3);
    if (e_all > INTEGRATION_FLOOR) {
      ++nratio;
      CHECK(est[o] <= 3.0 * e_all && est[o] >= e_all / 3.0);
    }
  }
  /* The driver's acceleration, the output with the most content above the
   * cut-off, is above the floor: the ratio is checked at least there. */
  CHECK(nratio >= 1);
  free(est);
  fb_result_free(&r);
  fb_result_free(&r_all);
  fb_result_free(&r_nodal);
  fb_vehicle_free(&v);
  fb_vehicle_free(&all);
  fb_vehicle_free(&nodal);
}

/* 2. and 3. */
static void test_once_and_modes(fb_scenario *s)
{
  fb_err err;
  fb_vehicle *v = realise(s, FB_HULL_MODAL, FB_HULL_MODES_AUTO, NULL);
  fb_vehicle *nodal = realise(s, FB_HULL_NODAL, FB_HULL_MODES_AUTO, NULL);
  s->hull_coordinates = FB_HULL_MODAL;
  if (!v || !nodal)
    goto done;
  fb_result *r1 = run(v), *r2 = run(v);
  fb_vehicle *est = NULL;
  REQUIRE(fb_vehicle_new_estimator(v, &est, &err), &err);
  fb_result *r3 = run(est);
  fb_mode_set *m = NULL, *mn = NULL;
  REQUIRE(fb_vehicle_structural_modes(v, 20, 0, &m, &err), &err);
  const fb_vehicle_work w = fb_vehicle_work_of(v), we = fb_vehicle_work_of(est);
  /* The scenario brought its mesh; the hull is assembled, factorised and
   * solved once; two runs and the modes reuse it, and so does the
   * estimator, which only builds its own diagram. */
  CHECK(w.mesh_generations == 0 && w.assemblies == 1 && w.factorisations == 1);
  CHECK(w.hull_eigensolves == 1 && w.vehicle_eigensolves == 1 && w.simulations == 2);
  CHECK(we.assemblies == 0 && we.factorisations == 0 && we.hull_eigensolves == 0);
  CHECK(we.simulations == 1);
  /* The same runs twice: the vehicle keeps nothing of a run. */
  if (r1 && r2)
    check_close(r1, r2, 0.0, "second run of one vehicle");
  REQUIRE(fb_vehicle_structural_modes(nodal, 20, 0, &mn, &err), &err);
  if (m && mn) {
    /* Within its band the basis holds each vehicle mode to the second
     * order of what it misses (Rayleigh-Ritz: the frequency's error is the
     * square of the shape's): 1e-4 relative bounds the worst measured,
     * 9.7e-6 (the hull's first elastic mode), with a margin; just above
     * the band the error is 0.5 % and grows, and a mode missing from the
     * basis would be percents off. The reference vehicle has ten modes in
     * its band: five of the bodies, four wheel hops, the hull's first
     * elastic one. */
    const double cutoff = fb_vehicle_hull_basis(v)->cutoff_hz;
    size_t compared = 0;
    for (size_t k = 0; k < m->nmodes && k < mn->nmodes; ++k) {
      if (mn->freq_hz[k] > cutoff)
        break;
      ++compared;
      CHECK(fabs(m->freq_hz[k] - mn->freq_hz[k]) <= 1e-4 * mn->freq_hz[k]);
    }
    fprintf(stderr, "vehicle modes below %.4g Hz: %zu agree with the nodal model's\n", cutoff,
            compared);
    CHECK(compared == 10 && m->nmodes == 10);
  }
  fb_mode_set_free(&m);
  fb_mode_set_free(&mn);
  fb_result_free(&r1);
  fb_result_free(&r2);
  fb_result_free(&r3);
  fb_vehicle_free(&est);
done:
  fb_vehicle_free(&v);
  fb_vehicle_free(&nodal);
}

/* 4. */
static void test_refusals(fb_scenario *s)
{
  fb_err err;
  fb_vehicle *v = NULL;
  /* A band below the first elastic mode (10.3 Hz) has no dynamics of the
   * hull's own. */
  s->hull_modes_kind = FB_HULL_MODES_AUTO;
  s->hull_cutoff_hz = 2.0;
  CHECK(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, NULL, &v, &err) == FB_EINVAL && !v);
  CHECK(PART_IS(&err, FB_PART_VEHICLE, 0, "hull_cutoff_hz"));
  CHECK(strstr(err.msg, "is below the hull's first elastic mode") != NULL);
  s->hull_cutoff_hz = 0.0;
  /* More modes than the mesh has degrees of freedom. */
  s->hull_modes_kind = FB_HULL_MODES_COUNT;
  s->hull_modes = 99999;
  CHECK(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, NULL, &v, &err) == FB_EINVAL && !v);
  CHECK(PART_IS(&err, FB_PART_VEHICLE, 0, "hull_modes"));
  s->hull_modes_kind = FB_HULL_MODES_AUTO;
  /* A memory limit below the factor: refused before it is made, saying
   * what it needs. */
  fb_vehicle_opts o;
  fb_vehicle_opts_default(&o);
  o.memory_limit = 100000;
  CHECK(fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, &o, &v, &err) == FB_ENOMEM && !v);
  CHECK(strstr(err.msg, "needs") != NULL);
  fprintf(stderr, "over the memory limit: %s\n", err.msg);
}

int main(void)
{
  fb_scenario *s = load_crossing();
  if (s) {
    test_accuracy(s);
    test_once_and_modes(s);
    test_refusals(s);
  }
  fb_scenario_free(&s);
  return check_report("test_hull_basis");
}
