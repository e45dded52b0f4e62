/* SPDX-License-Identifier: BSD-3-Clause */
/* Energy balance of an assembled vehicle, for the System 1 and System 2
 * tests: one probe per power port of every source and resistor
 * (integrated power) and per storage element (its stored energy), and at
 * every sample work in = dissipated + (stored - stored at t = 0).
 * Header-only test helper (static functions). */
#ifndef FLEXBOND_TESTS_ENERGY_BALANCE_H
#define FLEXBOND_TESTS_ENERGY_BALANCE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/bd.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "apc_layout.h"

enum { ENERGY_WORK, ENERGY_DISSIPATED, ENERGY_STORED };

typedef struct energy_probe {
  char name[48];
  const char *target; /* borrowed from the graph */
  fb_probe_kind kind;
  int category;
  double sign;
  size_t ncols;
} energy_probe;

typedef struct energy_report {
  size_t nwork, ndissipative, nstorage; /* source ports, resistor ports, storages */
  double worst;                         /* largest |work - dissipated - stored change|, J */
  double worst_t;                       /* its time, s */
  double work_scale;                    /* largest |work|, J */
  double dissipated;                    /* at the end, J */
  double smallest;                      /* smallest |energy| one port exchanged by the end, J */
} energy_report;

/* One probe per power port of every source and resistor (integrated
 * power, signed so that positive is work into the system or energy into
 * the resistor) and per storage element (its energy). */
static size_t energy_probes(const fb_bg *g, energy_probe *p, size_t max)
{
  size_t n = 0;
  for (size_t e = 0; e < fb_bg_nelements(g); ++e) {
    const fb_bg_kind kind = fb_bg_element_kind(g, e);
    if (kind == FB_BG_I || kind == FB_BG_C) {
      if (n < max)
        p[n] = (energy_probe){"", fb_bg_element_name(g, e), FB_PROBE_ENERGY, ENERGY_STORED, 1.0,
                              1};
      ++n;
      continue;
    }
    if (kind != FB_BG_SE && kind != FB_BG_SF && kind != FB_BG_R)
      continue;
    for (size_t b = 0; b < fb_bg_nbonds(g); ++b) {
      const int from = fb_bg_bond_from(g, b) == e, to = fb_bg_bond_to(g, b) == e;
      if (!from && !to)
        continue;
      if (n < max) {
        const int source = kind != FB_BG_R;
        /* A source delivers e.f when it is the bond's tail; a resistor
         * absorbs it when it is the head. */
        const double sign = (source ? from : to) ? 1.0 : -1.0;
        p[n] = (energy_probe){"",
                              fb_bg_bond_name(g, b),
                              FB_PROBE_POWER,
                              source ? ENERGY_WORK : ENERGY_DISSIPATED,
                              sign,
                              fb_bg_bond_dim(g, b)};
      }
      ++n;
    }
  }
  for (size_t i = 0; i < n && i < max; ++i)
    snprintf(p[i].name, sizeof p[i].name, "energy_probe_%zu", i);
  return n;
}

/* The balance over a run and the smallest port's energy at its end. */
static void energy_sums(const fb_result *res, const energy_probe *ep, size_t n,
                        energy_report *rep)
{
  double stored0 = 0.0;
  for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
    const double *y = fb_result_row(res, k) + 1;
    double sum[3] = {0.0, 0.0, 0.0};
    size_t col = 0;
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < ep[i].ncols; ++j)
        sum[ep[i].category] += ep[i].sign * y[col++];
    if (k == 0)
      stored0 = sum[ENERGY_STORED];
    const double balance =
        sum[ENERGY_WORK] - sum[ENERGY_DISSIPATED] - (sum[ENERGY_STORED] - stored0);
    if (fabs(balance) > rep->worst) {
      rep->worst = fabs(balance);
      rep->worst_t = fb_result_row(res, k)[0];
    }
    rep->work_scale = fmax(rep->work_scale, fabs(sum[ENERGY_WORK]));
    rep->dissipated = sum[ENERGY_DISSIPATED];
  }
  /* Storage elements end where they started near rest: only work and
   * dissipation count for the smallest port. */
  const double *last = fb_result_row(res, fb_result_nsamples(res) - 1) + 1;
  size_t col = 0;
  rep->smallest = INFINITY;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < ep[i].ncols; ++j, ++col)
      if (ep[i].category != ENERGY_STORED)
        rep->smallest = fmin(rep->smallest, fabs(last[col]));
}

/* Assembles the vehicle around *hull (taken over), probes every energy
 * flow, runs the scenario with rtol (atol 1e-10 or the scenario's, if
 * smaller) and fills rep; prints one line of it on stderr. */
static int energy_balance(const fb_scenario *s, fb_hull **hull, double rtol, energy_report *rep,
                          fb_err *err)
{
  *rep = (energy_report){0};
  fb_bg *g = NULL;
  fb_bd *bd = NULL;
  fb_probe_spec *std = NULL, *specs = NULL;
  size_t nstd = 0, n = 0;
  energy_probe *ep = NULL;
  fb_result *res = NULL;
  int rc = fb_vehicle_assemble(s, hull, &g, &std, &nstd, err);
  fb_vehicle_probes_free(&std, nstd);
  if (!rc) {
    n = energy_probes(g, NULL, 0);
    ep = calloc(n ? n : 1, sizeof *ep);
    specs = calloc(n ? n : 1, sizeof *specs);
    rc = ep && specs ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  if (!rc) {
    energy_probes(g, ep, n);
    for (size_t i = 0; i < n; ++i) {
      specs[i] = (fb_probe_spec){
          ep[i].name, ep[i].kind, ep[i].target, -1, ep[i].kind == FB_PROBE_POWER,
          1.0,        NULL,       NULL,         0};
      rep->nwork += ep[i].category == ENERGY_WORK;
      rep->ndissipative += ep[i].category == ENERGY_DISSIPATED;
      rep->nstorage += ep[i].category == ENERGY_STORED;
    }
    rc = fb_bd_build(g, specs, n, &bd, err);
  }
  size_t ncols = 0;
  for (size_t i = 0; !rc && i < n; ++i)
    ncols += ep[i].ncols;
  if (!rc && fb_bd_noutputs(bd) != ncols)
    rc = fb_err_set(err, FB_EINVAL, "energy balance: %zu output columns for %zu probe columns",
                    fb_bd_noutputs(bd), ncols);
  if (!rc) {
    fb_sim_opts o;
    /* Each wheel's road entry and exit, for a vehicle of up to the
     * APC's corners. */
    double bp[2 * APC_NCORNERS];
    const int ncorners = s->ncorners < APC_NCORNERS ? (int)s->ncorners : APC_NCORNERS;
    for (int c = 0; c < ncorners; ++c) {
      bp[2 * c] = fb_scenario_road_entry(s, c);
      bp[2 * c + 1] = fb_scenario_road_exit(s, c);
    }
    fb_sim_opts_default(&o);
    o.t_end = s->t_end;
    o.rtol = rtol;
    o.atol = fmin(s->atol, 1e-10);
    o.max_step = s->max_step;
    o.sample_rate = s->sample_rate;
    o.breakpoints = bp;
    o.nbreakpoints = 2 * (size_t)ncorners;
    rc = fb_sim_run(bd, &o, &res, err);
  }
  if (!rc && fb_result_nsamples(res) == 0)
    rc = fb_err_set(err, FB_EINVAL, "energy balance: the run has no samples");
  if (!rc) {
    energy_sums(res, ep, n, rep);
    fprintf(stderr,
            "energy balance over %.1f s (%zu source ports, %zu resistor ports, %zu storage "
            "elements): worst |work - dissipated - stored| = %.3g J at t = %.3f s, work scale "
            "%.6g J (ratio %.2g), dissipated at the end %.6g J, smallest port %.3g J\n",
            s->t_end, rep->nwork, rep->ndissipative, rep->nstorage, rep->worst, rep->worst_t,
            rep->work_scale, rep->worst / rep->work_scale, rep->dissipated, rep->smallest);
  }
  fb_result_free(&res);
  fb_bd_free(&bd);
  fb_bg_free(&g);
  free(ep);
  free(specs);
  return rc;
}

/* energy_balance of System 1 (the rigid hull) of s at rtol. */
static inline int energy_balance_rigid(const fb_scenario *s, double rtol, energy_report *rep,
                                       fb_err *err)
{
  fb_hull *hull = NULL;
  *rep = (energy_report){0};
  int rc = fb_vehicle_rigid_hull(s, &hull, err);
  return rc ? rc : energy_balance(s, &hull, rtol, rep, err);
}

#endif
