/* SPDX-License-Identifier: BSD-3-Clause */
/* A mounted rigid body's fragment (fb_vehicle_body) on a test-only
 * ground, against answers derived here: the six frequencies of a body on
 * one bushing at its centre of mass, the coupled surge-pitch pair of a
 * body standing above its bushing, the static sag, the lever split of
 * two bushings, and the energy a seat on a turret keeps without damping. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "vehicle_util.h"

static const double G = 9.81;

/* A ground: a 6-dimensional flow source of zero velocity, whose bond
 * the body's port "parent_<j>" ends on. */
static int add_ground(fb_bg *bg, const char *name, fb_err *err)
{
  fb_tfun *f[6] = {NULL};
  int rc = FB_OK;
  for (int i = 0; !rc && i < 6; ++i)
    rc = fb_tfun_new_const(0.0, &f[i], err);
  if (!rc)
    rc = fb_bg_add_source(bg, name, FB_BG_SF, 6, f, err);
  for (int i = 0; i < 6; ++i)
    fb_tfun_free(&f[i]);
  return rc;
}

/* The bodies of s on the ground (those on the hull) and on each other,
 * as the vehicle's assembly connects them: a graph with its causality. */
static fb_bg *rig(const fb_scenario *s)
{
  fb_err err;
  fb_bg *bg = NULL;
  REQUIRE(fb_bg_new("rig", &bg, &err), &err);
  for (size_t i = 0; i < s->nbodies; ++i) {
    fb_bg *frag = NULL;
    REQUIRE(fb_vehicle_body(s, i, &frag, &err), &err);
    REQUIRE(fb_bg_adopt(bg, &frag, s->body[i].name, &err), &err);
  }
  for (size_t k = 0, i = 0, j = 0; fb_scenario_bushing_at(s, k, &i, &j); ++k) {
    char from[96], to[96];
    snprintf(from, sizeof from, "%s.parent_%zu", s->body[i].name, j);
    if (s->body[i].parent) {
      snprintf(to, sizeof to, "%s.bushing_%zu", s->body[i].parent, k);
    } else {
      snprintf(to, sizeof to, "ground_%zu", k);
      REQUIRE(add_ground(bg, to, &err), &err);
    }
    REQUIRE(fb_bg_connect(bg, NULL, from, to, &err), &err);
  }
  REQUIRE(fb_bg_assign_causality(bg, &err), &err);
  return bg;
}

static fb_scenario *with_body(const fb_body *b, const fb_bushing *u, size_t nu)
{
  fb_err err;
  fb_scenario *s = NULL;
  REQUIRE(fb_scenario_new("rig", &s, &err), &err);
  s->gravity = G;
  fb_body copy = *b;
  copy.bushing = (fb_bushing *)u;
  copy.nbushings = nu;
  REQUIRE(fb_scenario_add_body(s, &copy, &err), &err);
  return s;
}

/* The undamped natural frequencies (rad/s) of bg's diagram, ascending,
 * into w; their number. */
static size_t frequencies(fb_bg *bg, double *w, size_t max)
{
  fb_err err;
  fb_bd *bd = NULL;
  fb_bd_eigen *e = NULL;
  REQUIRE(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  REQUIRE(fb_bd_eigen_new(bd, 0, NULL, 0, "rig", &e, &err), &err);
  size_t n = 0;
  for (size_t i = 0; i < e->n; ++i)
    if (e->im[i] > 0 && n < max)
      w[n++] = e->im[i];
  for (size_t i = 1; i < n; ++i) /* insertion sort */
    for (size_t j = i; j > 0 && w[j] < w[j - 1]; --j) {
      const double t = w[j];
      w[j] = w[j - 1];
      w[j - 1] = t;
    }
  fb_bd_eigen_free(&e);
  fb_bd_free(&bd);
  return n;
}

static int ascending(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* One bushing at the centre of mass, diagonal stiffness, no damping: six
 * uncoupled oscillators, sqrt(k_i / m) and sqrt(k_ri / I_i). dgeev's
 * eigenvalues of a 12 x 12 real matrix are within a few n eps ||A|| of
 * the exact ones; 1e-9 relative is far above that and far below any
 * modelling error. */
static void test_six_frequencies(void)
{
  const fb_body b = {
      .name = "box", .mass = 80, .x = 0.3, .y = -0.2, .z = 1.0, .ixx = 6, .iyy = 9, .izz = 11};
  fb_bushing u = {.x = 0.3, .y = -0.2, .z = 1.0};
  const double k[6] = {4e5, 5e5, 6e5, 7e4, 8e4, 9e4}, c[6] = {0};
  fb_bushing_set_diagonal(&u, k, c);
  fb_scenario *s = with_body(&b, &u, 1);
  fb_bg *bg = rig(s);
  double w[12], want[6] = {sqrt(k[0] / b.mass), sqrt(k[1] / b.mass), sqrt(k[2] / b.mass),
                           sqrt(k[3] / b.ixx),  sqrt(k[4] / b.iyy),  sqrt(k[5] / b.izz)};
  qsort(want, 6, sizeof *want, ascending);
  const size_t n = frequencies(bg, w, 12);
  CHECK(n == 6);
  for (size_t i = 0; i < 6 && i < n; ++i)
    CHECK_NEAR(w[i] / want[i], 1.0, 1e-9);
  fb_bg_free(&bg);
  fb_scenario_free(&s);
}

/* The centre of mass h above the bushing: the bushing point moves by
 * x - h theta along x (v + omega x r, r = (0, 0, -h)), so surge and pitch
 * couple through K = [[kx, -h kx], [-h kx, kry + h^2 kx]] with M =
 * diag(m, Iyy): omega^2 = (a + d) / 2 +- sqrt(((a - d) / 2)^2 + b c), a
 * = kx / m, d = (kry + h^2 kx) / Iyy, b c = (h kx)^2 / (m Iyy). The other
 * four: sway-roll likewise with ky, krx, Ixx (the point moves by y + h
 * phi), bounce sqrt(kz / m), yaw sqrt(krz / Izz). Tolerance as above. */
static void test_surge_pitch(void)
{
  const double h = 0.6;
  const fb_body b = {.name = "tower", .mass = 150, .z = h, .ixx = 20, .iyy = 30, .izz = 25};
  fb_bushing u = {0};
  const double k[6] = {3e5, 2e5, 9e5, 4e4, 5e4, 6e4}, c[6] = {0};
  fb_bushing_set_diagonal(&u, k, c);
  fb_scenario *s = with_body(&b, &u, 1);
  fb_bg *bg = rig(s);
  double want[6];
  const double kx[2] = {k[0], k[1]}, kr[2] = {k[4], k[3]}, in[2] = {b.iyy, b.ixx};
  for (int p = 0; p < 2; ++p) {
    const double a = kx[p] / b.mass, d = (kr[p] + h * h * kx[p]) / in[p];
    const double bc = h * kx[p] * h * kx[p] / (b.mass * in[p]);
    const double mid = 0.5 * (a + d), rad = sqrt(0.25 * (a - d) * (a - d) + bc);
    want[2 * p] = sqrt(mid - rad);
    want[2 * p + 1] = sqrt(mid + rad);
  }
  want[4] = sqrt(k[2] / b.mass);
  want[5] = sqrt(k[5] / b.izz);
  qsort(want, 6, sizeof *want, ascending);
  double w[12];
  const size_t n = frequencies(bg, w, 12);
  CHECK(n == 6);
  for (size_t i = 0; i < 6 && i < n; ++i)
    CHECK_NEAR(w[i] / want[i], 1.0, 1e-9);
  fb_bg_free(&bg);
  fb_scenario_free(&s);
}

/* The static equilibrium's spring states of bg: component c (0-based) of
 * element name's q. */
static double static_q(fb_bd *bd, const double *x, const char *name, int c)
{
  char want[96];
  snprintf(want, sizeof want, "%s.q[%d]", name, c + 1);
  for (size_t i = 0; i < fb_bd_nstates(bd); ++i)
    if (!strcmp(fb_bd_state_name(bd, i), want))
      return x[i];
  CHECK(0);
  fprintf(stderr, "  no state %s\n", want);
  return NAN;
}

static double *equilibrium(fb_bd *bd)
{
  fb_err err;
  const size_t n = fb_bd_nstates(bd);
  double *x0 = calloc(n, sizeof *x0), *x = calloc(n, sizeof *x);
  fb_bd_initial_state(bd, x0);
  REQUIRE(fb_sim_static_state(bd, 0, x0, x, &err), &err);
  free(x0);
  return x;
}

/* Static sag m g / kz on one bushing; and two bushings at x = a and x =
 * -b either side of the centre of mass, at its height, carrying no
 * pitch moment themselves: the lever rule, F_front = m g b / (a + b) and
 * F_rear = m g a / (a + b), whatever their stiffnesses. The equilibrium
 * is a linear solve: 1e-9 relative. */
static void test_statics(void)
{
  fb_err err;
  const fb_body b = {.name = "box", .mass = 80, .z = 0.5, .ixx = 6, .iyy = 9, .izz = 11};
  fb_bushing u = {.z = 0.5};
  const double k[6] = {4e5, 5e5, 6e5, 7e4, 8e4, 9e4}, c[6] = {1e3, 1e3, 1e3, 10, 10, 10};
  fb_bushing_set_diagonal(&u, k, c);
  fb_scenario *s = with_body(&b, &u, 1);
  fb_bg *bg = rig(s);
  fb_bd *bd = NULL;
  REQUIRE(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  double *x = equilibrium(bd);
  CHECK_NEAR(static_q(bd, x, "box.spring_0", 2) / (b.mass * G / k[2]), 1.0, 1e-9);
  CHECK(fabs(static_q(bd, x, "box.spring_0", 0)) < 1e-15 &&
        fabs(static_q(bd, x, "box.spring_0", 4)) < 1e-15);
  free(x);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
  fb_scenario_free(&s);

  const double a = 0.7, bb = 0.3;
  fb_bushing two[2] = {{.x = a, .z = 0.5}, {.x = -bb, .z = 0.5}};
  const double k1[6] = {4e5, 5e5, 6e5, 7e4, 0, 0}, k2[6] = {2e5, 3e5, 9e5, 1e4, 0, 0};
  fb_bushing_set_diagonal(&two[0], k1, c);
  fb_bushing_set_diagonal(&two[1], k2, c);
  s = with_body(&b, two, 2);
  bg = rig(s);
  REQUIRE(fb_bd_build(bg, NULL, 0, &bd, &err), &err);
  x = equilibrium(bd);
  const double f_front = k1[2] * static_q(bd, x, "box.spring_0", 2);
  const double f_rear = k2[2] * static_q(bd, x, "box.spring_1", 2);
  CHECK_NEAR(f_front / (b.mass * G * bb / (a + bb)), 1.0, 1e-9);
  CHECK_NEAR(f_rear / (b.mass * G * a / (a + bb)), 1.0, 1e-9);
  free(x);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
  fb_scenario_free(&s);
}

int main(void)
{
  test_six_frequencies();
  test_surge_pitch();
  test_statics();
  return check_report(__FILE__);
}
