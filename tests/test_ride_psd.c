/* SPDX-License-Identifier: BSD-3-Clause */
/* Ride from a road spectrum against the time domain, on System 1 of
 * examples/apc6x6_iso_road.yaml (ISO 8608 class C at 30 km/h):
 *   the PSD route: the frequency response over the road's band
 *   (fb_descriptor_freq_response with fb_vehicle_track_inputs), the road's
 *   temporal PSD (fb_ride_road_psd) on each of the tracks, combined by
 *   fb_ride_two_track_psd (the command's own combination), the
 *   driver's Wk-weighted mean square (fb_ride_wk_magnitude) and the LF
 *   tire force's, integrated over the band (fb_ride_psd_integral);
 *   the time route: the same vehicle simulated on NSEEDS roads of the
 *   class (the ISO 8608 generator, seeds 1 .. NSEEDS), a_w and the tire
 *   force's r.m.s. about its mean over the record after the fade-in
 *   (fb_ride_metrics_window and the samples).
 * Each seed's record is one random estimate of the mean square; their
 * mean must agree with the PSD route within three standard errors of the
 * mean, computed from the seeds' own scatter. A check that the PSD
 * route is not trivially inside: with the tracks taken as identical (a
 * different road) it must fall outside. Also the road PSD against ISO
 * 8608's closed form. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/ride.h"
#include "flexbond/road.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "bgtest_util.h"
#include "check.h"
#include "road_util.h"

static const char *const scenario_path = "../examples/apc6x6_iso_road.yaml";

enum { NSEEDS = 8, NPSD = 600 };
/* Record length and the start of the evaluated part: the fade-in ends at
 * s = 10 m, which the last wheel (5 m before the road at t = 0, 3.2 m
 * behind the first) reaches after 2.2 s at 8.33 m/s; the slowest mode
 * (pitch, 1.4 Hz, damping ratio ~0.3) has decayed by e^-5 a second later. */
static const double T_END = 40.0, T_START = 4.0;

typedef struct route {
  double aw2, force2; /* mean squares: driver's a_w, LF tire force */
} route;

typedef struct track_ctx {
  const fb_scenario *s;
  size_t rate_input[16];
} track_ctx;

static void track_input(void *ctx, double omega, double *u)
{
  const track_ctx *t = ctx;
  fb_vehicle_track_inputs(t->s, t->rate_input, omega, u);
}

static size_t output_index(const fb_scenario *s, const char *name)
{
  size_t o = 0;
  while (o < s->noutputs && strcmp(s->output[o].name, name) != 0)
    ++o;
  return o;
}

/* The PSD route's mean squares, the tracks independent or identical. */
static int psd_route(const fb_scenario *s, int identical, route *out, fb_err *err)
{
  fb_bg *graph = NULL;
  fb_bd *bd = NULL;
  fb_descriptor *ds = NULL;
  track_ctx ctx = {s, {0}};
  double f[NPSD], aw[NPSD], force[NPSD], gd0 = 0.0, *h = NULL;
  fb_road_iso8608_params iso;
  CHECK(fb_scenario_road_random(s, &iso));
  const double lo = s->speed * iso.n_min, hi = s->speed * iso.n_max;
  for (int k = 0; k < NPSD; ++k)
    f[k] = lo * pow(hi / lo, k / (NPSD - 1.0));
  int rc = fb_road_iso8608_gd0(iso.road_class, &gd0, err);
  if (!rc)
    rc = fb_vehicle_build(s, FB_SYSTEM_RIGID, &graph, &bd, err);
  if (!rc)
    rc = fb_bd_descriptor(bd, &ds, err);
  if (!rc && s->ncorners <= 16)
    rc = fb_vehicle_rate_inputs(s, ds, ctx.rate_input, err);
  if (!rc) {
    h = malloc(2 * 2 * ds->nrows_c * NPSD * sizeof *h);
    rc = h ? fb_descriptor_freq_response(ds, f, NPSD, 2, track_input, &ctx, h, err) : FB_ENOMEM;
  }
  const size_t acc = output_index(s, "driver_acc"), tire = output_index(s, "tire_force_LF");
  for (int k = 0; !rc && k < NPSD; ++k) {
    const double road = fb_ride_road_psd(gd0, s->speed, f[k]);
    double power[2];
    for (int i = 0; i < 2; ++i) {
      const size_t row = ds->output_row[i ? tire : acc];
      const double *l = h + 2 * ((2 * (size_t)k) * ds->nrows_c + row);
      const double *r = h + 2 * ((2 * (size_t)k + 1) * ds->nrows_c + row);
      power[i] = fb_ride_two_track_psd(l, r, 1.0, identical);
    }
    const double w = fb_ride_wk_magnitude(f[k]);
    aw[k] = w * w * power[0] * road;
    force[k] = power[1] * road;
  }
  if (!rc) {
    out->aw2 = fb_ride_psd_integral(f, aw, NPSD);
    out->force2 = fb_ride_psd_integral(f, force, NPSD);
  }
  free(h);
  fb_descriptor_free(&ds);
  fb_bd_free(&bd);
  fb_bg_free(&graph);
  return rc;
}

/* One seed's time-domain mean squares. */
static int time_route(const fb_scenario *base, uint64_t seed, route *out, fb_err *err)
{
  fb_scenario *s = NULL;
  fb_result *r = NULL;
  int rc = fb_scenario_clone(base, &s, err);
  if (!rc) {
    road_random(s)->seed = seed;
    s->t_end = T_END;
    rc = fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, err);
  }
  fb_ride_metrics m;
  fb_ride_opts opts;
  fb_ride_opts_default(&opts);
  if (!rc)
    rc = fb_ride_metrics_result(r, "driver_acc", T_START, T_END, &opts, &m, err);
  if (!rc) {
    const long col = fb_result_find(r, "tire_force_LF");
    double sum = 0.0, sum2 = 0.0;
    size_t n = 0;
    for (size_t k = 0; col > 0 && k < fb_result_nsamples(r); ++k) {
      const double *row = fb_result_row(r, k);
      if (row[0] < T_START)
        continue;
      sum += row[col];
      sum2 += row[col] * row[col];
      ++n;
    }
    out->aw2 = m.a_w_rms * m.a_w_rms;
    /* About the mean: the static load is no part of the response. */
    out->force2 = n ? sum2 / (double)n - (sum / (double)n) * (sum / (double)n) : NAN;
  }
  fb_result_free(&r);
  fb_scenario_free(&s);
  return rc;
}

/* Mean and standard error of the mean of v[0..n). */
static void mean_se(const double *v, size_t n, double *mean, double *se)
{
  double m = 0.0, ss = 0.0;
  for (size_t i = 0; i < n; ++i)
    m += v[i] / (double)n;
  for (size_t i = 0; i < n; ++i)
    ss += (v[i] - m) * (v[i] - m);
  *mean = m;
  *se = sqrt(ss / (double)(n - 1) / (double)n);
}

static void test_road_psd(void)
{
  /* Class C: Gd(n0) = 256e-6 m^3 at 0.1 cycles/m; at 10 m/s the
   * wavenumber 0.2 cycles/m is 2 Hz, where Gd = 64e-6 m^3, so the
   * temporal PSD is 6.4e-6 m^2/Hz. */
  CHECK_NEAR(fb_ride_road_psd(256e-6, 10.0, 2.0), 6.4e-6, 1e-18);
  CHECK(isnan(fb_ride_road_psd(256e-6, 0.0, 2.0)));
  /* Its integral over a band is the profile's variance, Gd(n0) n0^2
   * (1/n_min - 1/n_max) (docs/roads.md): to 1e-5 on 2000 log points. */
  enum { N = 2000 };
  double f[N], p[N];
  for (int k = 0; k < N; ++k) {
    f[k] = 0.11 * pow(28.3 / 0.11, k / (N - 1.0));
    p[k] = fb_ride_road_psd(256e-6, 10.0, f[k]);
  }
  const double want = 256e-6 * 0.01 * (1 / 0.011 - 1 / 2.83);
  CHECK_NEAR(fb_ride_psd_integral(f, p, N), want, 1e-5 * want);
}

/* The two-track combination on responses whose sums are known: equal
 * responses double the power when independent and quadruple it when
 * identical; opposite ones (a roll-only output) cancel when identical. */
static void test_two_track_psd(void)
{
  const double h[2] = {3.0, -4.0}, minus_h[2] = {-3.0, 4.0}, j[2] = {0.0, 5.0};
  CHECK_NEAR(fb_ride_two_track_psd(h, h, 2.0, 0), 100.0, 1e-12);
  CHECK_NEAR(fb_ride_two_track_psd(h, h, 2.0, 1), 200.0, 1e-12);
  CHECK_NEAR(fb_ride_two_track_psd(h, minus_h, 2.0, 0), 100.0, 1e-12);
  CHECK_NEAR(fb_ride_two_track_psd(h, minus_h, 2.0, 1), 0.0, 1e-12);
  /* |(3 - 4i) + 5i|^2 = |3 + i|^2 = 10, against 25 + 25 independent. */
  CHECK_NEAR(fb_ride_two_track_psd(h, j, 1.0, 1), 10.0, 1e-12);
  CHECK_NEAR(fb_ride_two_track_psd(h, j, 1.0, 0), 50.0, 1e-12);
}

static void test_against_time_domain(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  MUST(fb_scenario_load(scenario_path, &s, &err), &err);
  if (!s)
    return;
  CHECK(s->road_type == &fb_road_type_iso8608);
  route psd = {0, 0}, same = {0, 0}, run[NSEEDS];
  MUST(psd_route(s, 0, &psd, &err), &err);
  MUST(psd_route(s, 1, &same, &err), &err);
  double aw2[NSEEDS], force2[NSEEDS];
  for (int k = 0; k < NSEEDS; ++k) {
    MUST(time_route(s, (uint64_t)k + 1, &run[k], &err), &err);
    aw2[k] = run[k].aw2;
    force2[k] = run[k].force2;
  }
  double m_aw, se_aw, m_f, se_f;
  mean_se(aw2, NSEEDS, &m_aw, &se_aw);
  mean_se(force2, NSEEDS, &m_f, &se_f);
  fprintf(stderr,
          "a_w: PSD route %.4f m/s^2 (identical tracks %.4f), time route %.4f +- %.4f "
          "(%d seeds of %.0f s; mean square %.5f +- %.5f against %.5f)\n",
          sqrt(psd.aw2), sqrt(same.aw2), sqrt(m_aw), 0.5 * se_aw / sqrt(m_aw), NSEEDS,
          T_END - T_START, m_aw, se_aw, psd.aw2);
  fprintf(stderr,
          "LF tire force r.m.s.: PSD route %.1f N (identical %.1f), time route %.1f "
          "+- %.1f N\n",
          sqrt(psd.force2), sqrt(same.force2), sqrt(m_f), 0.5 * se_f / sqrt(m_f));
  /* Three standard errors: the seeds' mean square is a mean of NSEEDS
   * independent records, within 3 SE of its expectation but for 0.3 % of
   * draws (t distribution with 7 degrees of freedom: 2 %). */
  CHECK(fabs(m_aw - psd.aw2) <= 3.0 * se_aw);
  CHECK(fabs(m_f - psd.force2) <= 3.0 * se_f);
  /* Identical tracks are another road, well outside. */
  CHECK(fabs(m_aw - same.aw2) > 3.0 * se_aw || fabs(m_f - same.force2) > 3.0 * se_f);
  fb_scenario_free(&s);
}

int main(void)
{
  test_road_psd();
  test_two_track_psd();
  test_against_time_domain();
  return check_report("test_ride_psd");
}
