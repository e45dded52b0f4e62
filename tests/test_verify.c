/* SPDX-License-Identifier: BSD-3-Clause */
/* End-to-end verification through the solver: power balance of a quarter
 * car over a bump, and the same 2-DOF system built from scalar elements and
 * from 2-port fields giving the same trajectories. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/sim.h"

#include "bgtest_util.h"
#include "check.h"

/* Road velocity of a (1 - cos) bump of height h and duration T from t0:
 * z = h/2 (1 - cos(2 pi (t - t0) / T)), v = h pi / T sin(2 pi (t - t0) / T). */
typedef struct bump {
  double h, T, t0;
} bump;

static double bump_velocity(double t, void *ctx)
{
  const bump *b = ctx;
  if (t < b->t0 || t > b->t0 + b->T)
    return 0.0;
  return b->h * 3.14159265358979323846 / b->T *
         sin(2.0 * 3.14159265358979323846 * (t - b->t0) / b->T);
}

static fb_bg *quarter_car_bump(bump *bp, fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("qc", &bg, err), err);
  const double brk[2] = {bp->t0, bp->t0 + bp->T};
  fb_tfun *road = NULL;
  MUST(fb_tfun_new_callback(bump_velocity, bp, 2, brk, &road, err), err);
  MUST(fb_bg_add_source(bg, "road", FB_BG_SF, 1, &road, err), err);
  MUST(add_const_source(bg, "gs", FB_BG_SE, -250.0 * 9.81, err), err);
  MUST(add_const_source(bg, "gu", FB_BG_SE, -35.0 * 9.81, err), err);
  MUST(add_scalar(bg, "ms", FB_BG_I, 250.0, err), err);
  MUST(add_scalar(bg, "mu", FB_BG_I, 35.0, err), err);
  MUST(add_scalar(bg, "ks", FB_BG_C, 16000.0, err), err);
  MUST(add_scalar(bg, "cs", FB_BG_R, 1000.0, err), err);
  MUST(add_scalar(bg, "kt", FB_BG_C, 160000.0, err), err);
  MUST(add_scalar(bg, "ct", FB_BG_R, 150.0, err), err);
  const char *j1[] = {"Js", "Ju", "Jsus", "Jt"}, *j0[] = {"Jsus0", "Jt0"};
  for (int i = 0; i < 4; ++i)
    MUST(fb_bg_add_junction(bg, j1[i], FB_BG_J1, 1, err), err);
  for (int i = 0; i < 2; ++i)
    MUST(fb_bg_add_junction(bg, j0[i], FB_BG_J0, 1, err), err);
  const char *bonds[][3] = {
      {"b_road", "road", "Jt0"},  {"b_tu", "Jt0", "Ju"},   {"b_tire", "Jt0", "Jt"},
      {"b_kt", "Jt", "kt"},       {"b_ct", "Jt", "ct"},    {"b_mu", "Ju", "mu"},
      {"b_gu", "gu", "Ju"},       {"b_us", "Ju", "Jsus0"}, {"b_ss", "Jsus0", "Js"},
      {"b_sus", "Jsus0", "Jsus"}, {"b_ks", "Jsus", "ks"},  {"b_cs", "Jsus", "cs"},
      {"b_ms", "Js", "ms"},       {"b_gs", "gs", "Js"},
  };
  for (size_t i = 0; i < sizeof bonds / sizeof bonds[0]; ++i)
    MUST(fb_bg_connect(bg, bonds[i][0], bonds[i][1], bonds[i][2], err), err);
  return bg;
}

/* Energy balance: work of the sources = energy dissipated in the
 * resistors + change of stored energy, at every sample of a run that
 * starts from rest with gravity switched on and then crosses a bump. */
static void test_power_balance(void)
{
  fb_err err;
  fb_err_clear(&err);
  bump bp = {0.1, 0.5, 2.0};
  fb_bg *bg = quarter_car_bump(&bp, &err);
  enum { W_ROAD, W_GS, W_GU, D_CS, D_CT, E_MS, E_MU, E_KS, E_KT, NP };
  const fb_probe_spec probes[NP] = {
      {"w_road", FB_PROBE_POWER, "b_road", -1, 1, 1.0, NULL, NULL, 0},
      {"w_gs", FB_PROBE_POWER, "b_gs", -1, 1, 1.0, NULL, NULL, 0},
      {"w_gu", FB_PROBE_POWER, "b_gu", -1, 1, 1.0, NULL, NULL, 0},
      {"d_cs", FB_PROBE_POWER, "b_cs", -1, 1, 1.0, NULL, NULL, 0},
      {"d_ct", FB_PROBE_POWER, "b_ct", -1, 1, 1.0, NULL, NULL, 0},
      {"e_ms", FB_PROBE_ENERGY, "ms", -1, 0, 1.0, NULL, NULL, 0},
      {"e_mu", FB_PROBE_ENERGY, "mu", -1, 0, 1.0, NULL, NULL, 0},
      {"e_ks", FB_PROBE_ENERGY, "ks", -1, 0, 1.0, NULL, NULL, 0},
      {"e_kt", FB_PROBE_ENERGY, "kt", -1, 0, 1.0, NULL, NULL, 0},
  };
  fb_bd *bd = NULL;
  fb_result *res = NULL;
  MUST(fb_bd_build(bg, probes, NP, &bd, &err), &err);
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 5.0;
  o.rtol = 1e-9;
  o.atol = 1e-10;
  o.sample_rate = 200.0;
  if (bd)
    MUST(fb_sim_run(bd, &o, &res, &err), &err);
  if (res) {
    double worst = 0.0, scale = 0.0;
    for (size_t k = 0; k < fb_result_nsamples(res); ++k) {
      const double *y = fb_result_row(res, k) + 1;
      double work = y[W_ROAD] + y[W_GS] + y[W_GU];
      double balance = work - (y[D_CS] + y[D_CT]) - (y[E_MS] + y[E_MU] + y[E_KS] + y[E_KT]);
      worst = fmax(worst, fabs(balance));
      scale = fmax(scale, fabs(y[W_GS]));
    }
    /* Each integral carries a local error ~ rtol of its size (~300 J);
     * 1e-6 relative leaves a margin of 1000 over rtol, and a sign or
     * factor-2 error in any term would be of order 1. */
    fprintf(stderr, "power balance: worst %.3g J of %.3g J\n", worst, scale);
    CHECK(scale > 100.0);
    CHECK_NEAR(worst / scale, 0.0, 1e-6);
  }
  fb_result_free(&res);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

/* Scalar 2-DOF (masses m1, m2; spring k1 and damper r1 to ground on m1;
 * k2, r2 between them; force on m2) vs the same with 2-port fields. */
static const double m1 = 3.0, m2 = 1.5, k1 = 400.0, k2 = 250.0, r1 = 4.0, r2 = 2.5;

static fb_bg *scalar_2dof(fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("scalar", &bg, err), err);
  fb_tfun *f = NULL;
  MUST(fb_tfun_new_step(0.2, 0.0, 10.0, &f, err), err);
  MUST(fb_bg_add_source(bg, "F", FB_BG_SE, 1, &f, err), err);
  MUST(add_scalar(bg, "m1", FB_BG_I, m1, err), err);
  MUST(add_scalar(bg, "m2", FB_BG_I, m2, err), err);
  MUST(add_scalar(bg, "k1", FB_BG_C, k1, err), err);
  MUST(add_scalar(bg, "k2", FB_BG_C, k2, err), err);
  MUST(add_scalar(bg, "r1", FB_BG_R, r1, err), err);
  MUST(add_scalar(bg, "r2", FB_BG_R, r2, err), err);
  MUST(fb_bg_add_junction(bg, "J1", FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "J2", FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "J12", FB_BG_J0, 1, err), err);
  MUST(fb_bg_add_junction(bg, "Jr", FB_BG_J1, 1, err), err);
  const char *bonds[][3] = {
      {"bF", "F", "J2"},   {"bm1", "J1", "m1"},  {"bm2", "J2", "m2"},  {"bk1", "J1", "k1"},
      {"br1", "J1", "r1"}, {"b21", "J2", "J12"}, {"b12", "J12", "J1"}, {"brel", "J12", "Jr"},
      {"bk2", "Jr", "k2"}, {"br2", "Jr", "r2"},
  };
  for (size_t i = 0; i < sizeof bonds / sizeof bonds[0]; ++i)
    MUST(fb_bg_connect(bg, bonds[i][0], bonds[i][1], bonds[i][2], err), err);
  return bg;
}

static void add_2x2(fb_bg *bg, const char *name, fb_bg_kind kind, double a, double b, double c,
                    fb_err *err)
{
  fb_mat *m = NULL;
  const double v[4] = {a, b, b, c};
  const size_t dims[2] = {1, 1};
  MUST(fb_mat_new_dense_rowmajor(2, 2, v, &m, err), err);
  MUST(fb_bg_add_field(bg, name, kind, 2, dims, &m, err), err);
}

static fb_bg *field_2dof(fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("fields", &bg, err), err);
  fb_tfun *f = NULL;
  MUST(fb_tfun_new_step(0.2, 0.0, 10.0, &f, err), err);
  MUST(fb_bg_add_source(bg, "F", FB_BG_SE, 1, &f, err), err);
  add_2x2(bg, "M", FB_BG_I, m1, 0.0, m2, err);
  add_2x2(bg, "K", FB_BG_C, k1 + k2, -k2, k2, err);
  add_2x2(bg, "R", FB_BG_R, r1 + r2, -r2, r2, err);
  MUST(fb_bg_add_junction(bg, "J1", FB_BG_J1, 1, err), err);
  MUST(fb_bg_add_junction(bg, "J2", FB_BG_J1, 1, err), err);
  const char *bonds[][3] = {
      {"bF", "F", "J2"},    {"bm1", "J1", "M.1"}, {"bm2", "J2", "M.2"}, {"bk1", "J1", "K.1"},
      {"bk2", "J2", "K.2"}, {"br1", "J1", "R.1"}, {"br2", "J2", "R.2"},
  };
  for (size_t i = 0; i < sizeof bonds / sizeof bonds[0]; ++i)
    MUST(fb_bg_connect(bg, bonds[i][0], bonds[i][1], bonds[i][2], err), err);
  return bg;
}

static fb_result *run_xy(fb_bg *bg, fb_err *err)
{
  const fb_probe_spec probes[2] = {
      {"x1", FB_PROBE_FLOW, "bm1", -1, 1, 1.0, NULL, NULL, 0},
      {"x2", FB_PROBE_FLOW, "bm2", -1, 1, 1.0, NULL, NULL, 0},
  };
  fb_bd *bd = NULL;
  fb_result *res = NULL;
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_end = 3.0;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  MUST(fb_bd_build(bg, probes, 2, &bd, err), err);
  if (bd)
    MUST(fb_sim_run(bd, &o, &res, err), err);
  fb_bd_free(&bd);
  return res;
}

static void test_fields_trajectories(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *g1 = scalar_2dof(&err), *g2 = field_2dof(&err);
  fb_result *a = run_xy(g1, &err), *b = run_xy(g2, &err);
  if (a && b) {
    CHECK(fb_result_nsamples(a) == fb_result_nsamples(b));
    double worst = 0.0, peak = 0.0;
    for (size_t k = 0; k < fb_result_nsamples(a); ++k)
      for (int j = 1; j <= 2; ++j) {
        worst = fmax(worst, fabs(fb_result_row(a, k)[j] - fb_result_row(b, k)[j]));
        peak = fmax(peak, fabs(fb_result_row(a, k)[j]));
      }
    /* Static x2 = F (1/k1 + 1/k2) = 0.065 m. The runs take different
     * steps; each is within ~rtol * peak * (number of periods) of the
     * exact answer, so 1e-6 relative is a safe bound for both. */
    fprintf(stderr, "fields vs scalars: worst %.3g m of %.3g m\n", worst, peak);
    CHECK(peak > 0.05);
    CHECK_NEAR(worst / peak, 0.0, 1e-6);
  }
  fb_result_free(&a);
  fb_result_free(&b);
  fb_bg_free(&g1);
  fb_bg_free(&g2);
}

/* Static equilibrium from rest: the springs carry the weights,
 * q_ks = ms g / ks and q_kt = (ms + mu) g / kt, momenta zero. */
static void test_static_state(void)
{
  fb_err err;
  fb_err_clear(&err);
  bump bp = {0.1, 0.5, 2.0};
  fb_bg *bg = quarter_car_bump(&bp, &err);
  fb_bd *bd = NULL;
  MUST(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  if (bd) {
    size_t n = fb_bd_nstates(bd);
    double x0[8] = {0}, x[8], f[8];
    CHECK(n == 4);
    MUST(fb_sim_static_state(bd, 0.0, x0, x, &err), &err);
    for (size_t i = 0; i < n; ++i) {
      const char *name = fb_bd_state_name(bd, i);
      if (strcmp(name, "ks.q") == 0)
        CHECK_NEAR(x[i], 250.0 * 9.81 / 16000.0, 1e-12);
      else if (strcmp(name, "kt.q") == 0)
        CHECK_NEAR(x[i], 285.0 * 9.81 / 160000.0, 1e-12);
      else
        CHECK(x[i] == 0.0);
    }
    /* At rest: every state derivative vanishes to rounding of ~3000 N. */
    CHECK(fb_bd_rhs(bd, 0.0, x, f) == 0);
    for (size_t i = 0; i < n; ++i)
      CHECK_NEAR(f[i], 0.0, 1e-9);
    /* During the bump the road moves: no equilibrium, and it says so. */
    CHECK(fb_sim_static_state(bd, 2.1, x0, x, &err) == FB_ESOLVER);
    CHECK(strstr(err.msg, "flow sources") != NULL);
  }
  fb_bd_free(&bd);
  fb_bg_free(&bg);
}

int main(void)
{
  test_static_state();
  test_power_balance();
  test_fields_trajectories();
  return check_report("test_verify");
}
