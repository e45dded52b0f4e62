/* SPDX-License-Identifier: BSD-3-Clause */
/* The serial vectors of src/sim/nvector.c against SUNDIALS' own serial
 * module: every replaced operation, on the same data, must give the same
 * bits (the integrator's steps, and so every result, depend on them to
 * the last rounding), for each special coefficient N_VLinearSum
 * distinguishes and each way its output may alias an input. */
#include <math.h>
#include <nvector/nvector_serial.h>
#include <string.h>

#include "check.h"
#include "sim/nvector.h"

#define N 37

/* A vector pair with the same entries: SUNDIALS' serial one and ours. */
typedef struct pair {
  N_Vector ref, ours;
} pair;

static pair pair_new(SUNContext ctx, const double *values)
{
  pair p = {N_VNew_Serial(N, ctx), fb_sim_nvector_new(N, ctx)};
  if (p.ref && p.ours) {
    memcpy(NV_DATA_S(p.ref), values, N * sizeof *values);
    memcpy(NV_DATA_S(p.ours), values, N * sizeof *values);
  }
  return p;
}

static void pair_free(pair *p)
{
  N_VDestroy(p->ref);
  N_VDestroy(p->ours);
}

static int same_bits(const pair *p)
{
  return memcmp(NV_DATA_S(p->ref), NV_DATA_S(p->ours), N * sizeof(double)) == 0;
}

/* Entries of several magnitudes and signs, none exactly 0 unless zero_at
 * < N; a fixed linear congruential sequence, so that a failure repeats. */
static void fill(double *v, unsigned seed, size_t zero_at)
{
  unsigned s = seed;
  for (size_t i = 0; i < N; ++i) {
    s = s * 1103515245u + 12345u;
    const double u = (double)(s >> 8) / (double)(1u << 24) - 0.5;
    v[i] = u * pow(10.0, (double)((int)(i % 7) - 3));
    if (v[i] == 0.0)
      v[i] = 1e-3;
  }
  if (zero_at < N)
    v[zero_at] = 0.0;
}

/* z = a x + b y on both sides, z a third vector or x or y itself. */
static void check_linear_sum(SUNContext ctx, double a, double b, int alias)
{
  double vx[N], vy[N], vz[N];
  fill(vx, 1u, N);
  fill(vy, 2u, N);
  fill(vz, 3u, N);
  pair x = pair_new(ctx, vx), y = pair_new(ctx, vy), z = pair_new(ctx, vz);
  const pair *out = alias == 1 ? &x : alias == 2 ? &y : &z;
  N_VLinearSum(a, x.ref, b, y.ref, out->ref);
  N_VLinearSum(a, x.ours, b, y.ours, out->ours);
  CHECK(same_bits(out));
  if (!same_bits(out))
    fprintf(stderr, "  N_VLinearSum(a = %g, b = %g, alias %d) differs\n", a, b, alias);
  pair_free(&x);
  pair_free(&y);
  pair_free(&z);
}

static void test_linear_sum(SUNContext ctx)
{
  /* Each case of the serial module: +-1 on either side, equal and
   * opposite coefficients, the general form, and 0. */
  static const double coef[] = {1.0, -1.0, 0.3, -0.3, 2.5, 0.0};
  const size_t nc = sizeof coef / sizeof coef[0];
  for (size_t i = 0; i < nc; ++i)
    for (size_t j = 0; j < nc; ++j)
      for (int alias = 0; alias < 3; ++alias)
        check_linear_sum(ctx, coef[i], coef[j], alias);
}

/* The unary, binary and reduction operations CVODE calls per step. */
static void test_elementwise(SUNContext ctx)
{
  double vx[N], vy[N], vw[N];
  fill(vx, 4u, N);
  fill(vy, 5u, N);
  fill(vw, 6u, N);
  pair x = pair_new(ctx, vx), y = pair_new(ctx, vy), w = pair_new(ctx, vw),
       z = pair_new(ctx, vw);
  static const double scales[] = {1.0, -1.0, 0.7};
  for (size_t k = 0; k < 3; ++k) {
    N_VScale(scales[k], x.ref, z.ref);
    N_VScale(scales[k], x.ours, z.ours);
    CHECK(same_bits(&z));
  }
  N_VScale(0.7, z.ref, z.ref); /* in place */
  N_VScale(0.7, z.ours, z.ours);
  CHECK(same_bits(&z));
  N_VConst(-2.25, z.ref);
  N_VConst(-2.25, z.ours);
  CHECK(same_bits(&z));
  N_VProd(x.ref, y.ref, z.ref);
  N_VProd(x.ours, y.ours, z.ours);
  CHECK(same_bits(&z));
  N_VDiv(x.ref, y.ref, z.ref);
  N_VDiv(x.ours, y.ours, z.ours);
  CHECK(same_bits(&z));
  N_VAbs(x.ref, z.ref);
  N_VAbs(x.ours, z.ours);
  CHECK(same_bits(&z));
  N_VInv(x.ref, z.ref);
  N_VInv(x.ours, z.ours);
  CHECK(same_bits(&z));
  N_VAddConst(x.ref, 1e-9, z.ref);
  N_VAddConst(x.ours, 1e-9, z.ours);
  CHECK(same_bits(&z));
  N_VCompare(2e-3, x.ref, z.ref);
  N_VCompare(2e-3, x.ours, z.ours);
  CHECK(same_bits(&z));
  /* Reductions: equal as doubles, bit for bit. */
  const double norm_ref = N_VWrmsNorm(x.ref, w.ref), norm = N_VWrmsNorm(x.ours, w.ours);
  CHECK(memcmp(&norm_ref, &norm, sizeof norm) == 0);
  const double sum_ref = N_VWSqrSumLocal(x.ref, w.ref), sum = N_VWSqrSumLocal(x.ours, w.ours);
  CHECK(memcmp(&sum_ref, &sum, sizeof sum) == 0);
  const double max_ref = N_VMaxNorm(x.ref), max = N_VMaxNorm(x.ours);
  CHECK(memcmp(&max_ref, &max, sizeof max) == 0);
  pair_free(&x);
  pair_free(&y);
  pair_free(&w);
  pair_free(&z);
}

/* 1 / x with and without a zero entry: the verdict and the entries. */
static void test_inv_test(SUNContext ctx)
{
  for (size_t zero_at = 0; zero_at <= N; zero_at += N) {
    double vx[N], vz[N];
    fill(vx, 7u, zero_at);
    fill(vz, 8u, N);
    pair x = pair_new(ctx, vx), z = pair_new(ctx, vz);
    const booleantype ok_ref = N_VInvTest(x.ref, z.ref), ok = N_VInvTest(x.ours, z.ours);
    CHECK(ok_ref == ok && ok == (zero_at == N ? SUNTRUE : SUNFALSE));
    CHECK(same_bits(&z));
    pair_free(&x);
    pair_free(&z);
  }
}

/* Clones carry the replaced operations (CVODE clones every vector it
 * keeps from the state vector), and the generic linear combination,
 * which the serial module leaves to N_VScale and N_VLinearSum, agrees. */
static void test_clones(SUNContext ctx)
{
  double v[N];
  fill(v, 9u, N);
  pair x = pair_new(ctx, v);
  N_Vector clone = N_VClone(x.ours);
  CHECK(clone && clone->ops->nvlinearsum == x.ours->ops->nvlinearsum);
  CHECK(clone && clone->ops->nvwrmsnorm == x.ours->ops->nvwrmsnorm);
  CHECK(x.ours->ops->nvlinearsum != x.ref->ops->nvlinearsum);
  double v1[N], v2[N];
  fill(v1, 10u, N);
  fill(v2, 11u, N);
  pair a = pair_new(ctx, v1), b = pair_new(ctx, v2);
  double c[3] = {1.5, -1.0, 0.25};
  N_Vector ref_vecs[3] = {x.ref, a.ref, b.ref}, our_vecs[3] = {x.ours, a.ours, b.ours};
  pair z = pair_new(ctx, v);
  CHECK(N_VLinearCombination(3, c, ref_vecs, z.ref) == 0);
  CHECK(N_VLinearCombination(3, c, our_vecs, z.ours) == 0);
  CHECK(same_bits(&z));
  N_VDestroy(clone);
  pair_free(&x);
  pair_free(&a);
  pair_free(&b);
  pair_free(&z);
}

int main(void)
{
  SUNContext ctx = NULL;
  CHECK(SUNContext_Create(NULL, &ctx) == 0);
  if (!ctx)
    return check_report("test_nvector");
  test_linear_sum(ctx);
  test_elementwise(ctx);
  test_inv_test(ctx);
  test_clones(ctx);
  SUNContext_Free(&ctx);
  return check_report("test_nvector");
}
