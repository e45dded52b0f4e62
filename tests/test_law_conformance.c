/* SPDX-License-Identifier: BSD-3-Clause */
/* Conformance of the library's element laws (fb_law_ops): every law id
 * of flexbond/bg.h but FB_LAW_CUSTOM, as its public constructor makes it
 * (fb_bg_add_r_table, fb_bg_add_unilateral_contact), goes through the
 * same checks at random inputs xu, in the mode its guards choose there:
 *   - a switched law settles in a mode (asked again with the same guard
 *     signs, it stays);
 *   - its Jacobian against central finite differences of its eval, column
 *     by column (modulating columns too), the mode held;
 *   - where it claims to be affine: f(a x + b y) = a f(x) + b f(y) +
 *     (1 - a - b) f(0) in the mode, and a Jacobian that does not change;
 *   - its power: where it has an energy (a storage law's energy, a
 *     resistor's co-content), d(energy)/dt along any rate v of its own
 *     input is y.v, the power it takes in; where it claims to be passive,
 *     y.x >= 0 (it dissipates).
 * A law id that no constructor here makes fails. Last, the harness must
 * bite: laws made wrong on purpose (a Jacobian off by 1e-4, an energy off
 * by 1e-3, a passive claim of a law that delivers power, an affine claim
 * of a curved one) must fail it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bg.h"

#include "bg/bg_internal.h"
#include "bgtest_util.h"
#include "check.h"
#include "conformance.h"

/* Inputs of up to this many values (own and modulating). */
enum { MAXIN = 8 };

/* One law as an element of a graph has it. */
typedef struct law_case {
  const fb_law_ops *ops;
  void *ctx;
  size_t n, m; /* own input and modulating values */
  const char *element;
} law_case;

static int quiet;       /* 1 while a broken law runs: its failures are expected */
static size_t failures; /* since the harness started */

static void fail(const law_case *c, const char *what, size_t i, double got, double want)
{
  failures++;
  if (!quiet)
    fprintf(stderr, "law '%s' of '%s': %s (at %zu: %.12g, expected %.12g)\n", c->ops->name,
            c->element, what, i, got, want);
}

static void eval_at(const law_case *c, const fb_law_in *in, const double *x, double *y)
{
  fb_law_in at = *in;
  at.x = x;
  if (c->ops->eval(c->ctx, &at, y))
    fail(c, "eval failed", 0, 0, 0);
}

static void jacobian_at(const law_case *c, const fb_law_in *in, const double *x, double *jac)
{
  fb_law_in at = *in;
  at.x = x;
  memset(jac, 0, c->n * (c->n + c->m) * sizeof *jac);
  if (c->ops->jacobian(c->ctx, &at, jac))
    fail(c, "jacobian failed", 0, 0, 0);
}

/* in->mode from the guards at in->x, as fb_bd_sync_modes settles it. */
static void settle(const law_case *c, fb_law_in *in)
{
  const size_t ng = c->ops->nguards;
  double g[MAXIN];
  int sign[MAXIN];
  if (ng > MAXIN || (ng && (!c->ops->guards || !c->ops->switch_mode))) {
    fail(c, "switched without guards and switch_mode (or too many guards)", 0, 0, 0);
    return;
  }
  for (int round = 0; ng && round < 16; ++round) {
    int mode = in->mode;
    if (c->ops->guards(c->ctx, in, g))
      fail(c, "guards failed", 0, 0, 0);
    for (size_t i = 0; i < ng; ++i)
      sign[i] = g[i] < 0.0 ? -1 : 1;
    if (c->ops->switch_mode(c->ctx, in, sign, &mode))
      fail(c, "switch_mode failed", 0, 0, 0);
    if (mode == in->mode)
      return;
    in->mode = mode;
  }
  if (ng)
    fail(c, "the mode does not settle", 0, 0, 0);
}

/* Each column of the Jacobian against the central difference of eval. */
static void check_jacobian(const law_case *c, const fb_law_in *in)
{
  const size_t n = c->n, w = c->n + c->m;
  double jac[MAXIN * MAXIN], y[MAXIN], yp[MAXIN], ym[MAXIN], xp[MAXIN], xm[MAXIN];
  eval_at(c, in, in->x, y);
  jacobian_at(c, in, in->x, jac);
  for (size_t j = 0; j < w; ++j) {
    memcpy(xp, in->x, w * sizeof *xp);
    memcpy(xm, in->x, w * sizeof *xm);
    xp[j] += FD_STEP;
    xm[j] -= FD_STEP;
    eval_at(c, in, xp, yp);
    eval_at(c, in, xm, ym);
    for (size_t i = 0; i < n; ++i) {
      const double fd = (yp[i] - ym[i]) / (2.0 * FD_STEP), d = jac[j * n + i];
      if (!(fabs(fd - d) <= FD_TOL * (1.0 + fabs(d) + fabs(y[i]))))
        fail(c, "Jacobian differs from the central difference", j * n + i, d, fd);
    }
  }
}

/* An affine law, in the mode of in: affine in xu, a Jacobian that does
 * not change. */
static void check_affine(const law_case *c, const fb_law_in *in)
{
  const size_t n = c->n, w = c->n + c->m;
  const double a = 2.0 * urand(), b = 2.0 * urand();
  double y[MAXIN], zero[MAXIN] = {0}, mix[MAXIN], fx[MAXIN], fy[MAXIN], f0[MAXIN], fm[MAXIN];
  double jx[MAXIN * MAXIN], jy[MAXIN * MAXIN];
  randomize(y, w);
  for (size_t i = 0; i < w; ++i)
    mix[i] = a * in->x[i] + b * y[i];
  eval_at(c, in, in->x, fx);
  eval_at(c, in, y, fy);
  eval_at(c, in, zero, f0);
  eval_at(c, in, mix, fm);
  for (size_t i = 0; i < n; ++i) {
    const double want = a * fx[i] + b * fy[i] + (1.0 - a - b) * f0[i];
    const double scale = fabs(a * fx[i]) + fabs(b * fy[i]) + fabs((1.0 - a - b) * f0[i]);
    if (!(fabs(fm[i] - want) <= EXACT_TOL * (scale + fabs(fm[i]))))
      fail(c, "claims to be affine, but f(a x + b y) differs", i, fm[i], want);
  }
  jacobian_at(c, in, in->x, jx);
  jacobian_at(c, in, y, jy);
  for (size_t k = 0; k < n * w; ++k)
    if (jx[k] != jy[k])
      fail(c, "claims to be affine, but its Jacobian changes with xu", k, jy[k], jx[k]);
}

/* d(energy)/dt along a rate v of the own input is y.v (the energy
 * depends on the own input alone, not on the mode); a passive law takes
 * in y.x >= 0. */
static void check_power(const law_case *c, const fb_law_in *in)
{
  const size_t n = c->n;
  double y[MAXIN], v[MAXIN], xp[MAXIN], xm[MAXIN];
  eval_at(c, in, in->x, y);
  double power = 0.0, mag = 0.0;
  for (size_t i = 0; i < n; ++i) {
    power += y[i] * in->x[i];
    mag += fabs(y[i] * in->x[i]);
  }
  if (c->ops->passive && !(power >= -EXACT_TOL * mag))
    fail(c, "claims to be passive, but delivers power: y.x", 0, power, 0.0);
  if (!c->ops->energy)
    return;
  randomize(v, n);
  double rate = 0.0;
  for (size_t i = 0; i < n; ++i) {
    rate += y[i] * v[i];
    xp[i] = in->x[i] + FD_STEP * v[i];
    xm[i] = in->x[i] - FD_STEP * v[i];
  }
  const double e = c->ops->energy(c->ctx, n, in->x);
  const double fd =
      (c->ops->energy(c->ctx, n, xp) - c->ops->energy(c->ctx, n, xm)) / (2.0 * FD_STEP);
  if (!(fabs(fd - rate) <= FD_TOL * (1.0 + fabs(rate) + fabs(e))))
    fail(c, "d(energy)/dt differs from the power y.v it takes in", 0, fd, rate);
}

/* Every check at NSAMPLES random inputs, 1.5 times wider than the
 * table's knots so that its linear continuations are met too. */
static void check_law(const law_case *c)
{
  if (c->n + c->m > MAXIN) {
    fail(c, "more inputs than the harness holds", 0, (double)(c->n + c->m), MAXIN);
    return;
  }
  for (int s = 0; s < NSAMPLES; ++s) {
    double x[MAXIN];
    randomize(x, c->n + c->m);
    for (size_t i = 0; i < c->n + c->m; ++i)
      x[i] *= 1.5;
    fb_law_in in = {c->n, c->m, x, 0};
    settle(c, &in);
    check_jacobian(c, &in);
    if (c->ops->affine)
      check_affine(c, &in);
    check_power(c, &in);
  }
}

/* ---- The laws, made by their constructors. */

static fb_bg *law_graph(fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("laws", &bg, err), err);
  MUST(conformance_add_laws(bg, err), err);
  return bg;
}

/* The law of element e as a case. */
static law_case case_of(const fb_bg *bg, size_t e)
{
  const fb_bg_elem *el = &bg->elems[e];
  law_case c = {el->law_ops, el->law_ctx, el->dim, 0, el->name};
  for (size_t k = 0; k < el->nmod; ++k)
    c.m += bg->elems[el->mod_src[k]].dim;
  return c;
}

/* ---- Broken laws: a real law's ops with one part made wrong. */

static const law_case *real; /* the law under a broken part */

static int jacobian_off(void *ctx, const fb_law_in *in, double *jac)
{
  int rc = real->ops->jacobian(ctx, in, jac);
  jac[0] += 1e-4 * (1.0 + fabs(jac[0]));
  return rc;
}

static double energy_off(void *ctx, size_t n, const double *x)
{
  return 1.001 * real->ops->energy(ctx, n, x);
}

static int eval_negated(void *ctx, const fb_law_in *in, double *y)
{
  int rc = real->ops->eval(ctx, in, y);
  for (size_t i = 0; i < in->n; ++i)
    y[i] = -y[i];
  return rc;
}

static int jacobian_negated(void *ctx, const fb_law_in *in, double *jac)
{
  int rc = real->ops->jacobian(ctx, in, jac);
  for (size_t i = 0; i < in->n * (in->n + in->m); ++i)
    jac[i] = -jac[i];
  return rc;
}

/* Runs c with ops in place of its own; the harness must find it wrong. */
static void check_bites(const law_case *c, const fb_law_ops *ops, const char *how)
{
  law_case broken = *c;
  broken.ops = ops;
  real = c;
  const size_t before = failures;
  quiet = 1;
  check_law(&broken);
  quiet = 0;
  const size_t found = failures - before;
  failures = before;
  fprintf(stderr, "law '%s' %s: %zu failures found%s\n", c->ops->name, how, found,
          found ? "" : ": THE HARNESS DOES NOT BITE");
  CHECK(found > 0);
}

static void check_broken(const law_case *c)
{
  fb_law_ops ops = *c->ops;
  ops.jacobian = jacobian_off;
  check_bites(c, &ops, "with a Jacobian off by 1e-4");
  if (c->ops->energy) {
    ops = *c->ops;
    ops.energy = energy_off;
    check_bites(c, &ops, "with an energy off by 1e-3");
  }
  if (c->ops->passive) {
    ops = *c->ops;
    ops.eval = eval_negated;
    ops.jacobian = jacobian_negated;
    check_bites(c, &ops, "negated, still claiming to be passive");
  }
  if (!c->ops->affine) {
    ops = *c->ops;
    ops.affine = 1;
    check_bites(c, &ops, "claiming to be affine");
  }
}

int main(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = law_graph(&err);
  unsigned char seen[FB_LAW_NIDS] = {0};
  for (size_t e = 0; bg && e < fb_bg_nelements(bg); ++e) {
    const law_case c = case_of(bg, e);
    if (!c.ops)
      continue;
    CHECK(c.ops->id > FB_LAW_CUSTOM && c.ops->id < FB_LAW_NIDS);
    if (c.ops->id < FB_LAW_NIDS)
      seen[c.ops->id] = 1;
    check_law(&c);
  }
  fprintf(stderr, "test_law_conformance: %zu failures of the real laws\n", failures);
  CHECK(failures == 0);
  for (int id = FB_LAW_CUSTOM + 1; id < FB_LAW_NIDS; ++id) {
    if (!seen[id])
      fprintf(stderr, "law id %d: no constructor of the harness makes it\n", id);
    CHECK(seen[id]);
  }
  for (size_t e = 0; bg && e < fb_bg_nelements(bg); ++e) {
    const law_case c = case_of(bg, e);
    if (c.ops)
      check_broken(&c);
  }
  fb_bg_free(&bg);
  return check_report("test_law_conformance");
}
