/* SPDX-License-Identifier: BSD-3-Clause */
/* Serial N_Vectors whose per-element operations are compiled with this
 * project's flags (see nvector.h).
 *
 * Why: Debian bookworm's SUNDIALS 6.4.1 (6.4.1+dfsg1-3) is built without
 * optimisation. Its libraries are -O0 code: in N_VWSqrSumLocal_Serial the
 * sum, the index and both pointers go through the stack at every element
 * (objdump), and a weighted r.m.s. norm of 2622 entries takes 21 us, a
 * linear sum 7 us. Before SUNDIALS 7 its CMake set no optimisation flags
 * unless CMAKE_BUILD_TYPE was given (llnl/sundials pull request 422). With
 * System 2's hull in modal coordinates those loops were a third of the run.
 *
 * An N_Vector is content plus an ops table (SUNDIALS user guide, "Description
 * of the NVECTOR module"), so the serial vector keeps its content, clone and
 * destroy, and only the operations CVODE calls at every step are replaced.
 * Each computes every element with the same floating-point operations in the
 * same order as the serial module's, case for case (N_VLinearSum's special
 * coefficients and aliasing; the norm's sequential sum), so results do not
 * move by a rounding: test_nvector checks each one bit for bit against
 * SUNDIALS' own. Clones copy the ops table (N_VCloneEmpty), so CVODE's
 * internal vectors get them too. */
#include "sim/nvector.h"

#include <math.h>
#include <nvector/nvector_serial.h>

/* The elements and length of a serial vector. */
#define DATA(v) NV_DATA_S(v)
#define LEN(v) ((size_t)NV_LENGTH_S(v))

/* y += a x, the serial module's axpy: a = 1 and a = -1 add or subtract
 * without the product (the same values: a product by +-1 is exact). */
static void nv_axpy(double a, N_Vector x, N_Vector y)
{
  const double *xd = DATA(x);
  double *yd = DATA(y);
  const size_t n = LEN(x);
  if (a == 1.0) {
    for (size_t i = 0; i < n; ++i)
      yd[i] += xd[i];
  } else if (a == -1.0) {
    for (size_t i = 0; i < n; ++i)
      yd[i] -= xd[i];
  } else {
    for (size_t i = 0; i < n; ++i)
      yd[i] += a * xd[i];
  }
}

/* z = a u + sign v, sign = +-1: the serial module's a x + y and a x - y. */
static void nv_lin(double a, N_Vector u, double sign, N_Vector v, N_Vector z)
{
  const double *ud = DATA(u), *vd = DATA(v);
  double *zd = DATA(z);
  const size_t n = LEN(u);
  if (sign > 0) {
    for (size_t i = 0; i < n; ++i)
      zd[i] = a * ud[i] + vd[i];
  } else {
    for (size_t i = 0; i < n; ++i)
      zd[i] = a * ud[i] - vd[i];
  }
}

/* z = c (x + sign y), sign = +-1: a x + b y for b = a and b = -a. */
static void nv_scaled(double c, N_Vector x, double sign, N_Vector y, N_Vector z)
{
  const double *xd = DATA(x), *yd = DATA(y);
  double *zd = DATA(z);
  const size_t n = LEN(x);
  if (sign > 0) {
    for (size_t i = 0; i < n; ++i)
      zd[i] = c * (xd[i] + yd[i]);
  } else {
    for (size_t i = 0; i < n; ++i)
      zd[i] = c * (xd[i] - yd[i]);
  }
}

/* z = a x + b y, by the serial module's cases in its order: an axpy in
 * place, a sum, a difference, one coefficient +-1, equal or opposite
 * coefficients, then the general form. */
static void nv_linear_sum(double a, N_Vector x, double b, N_Vector y, N_Vector z)
{
  if (b == 1.0 && z == y) {
    nv_axpy(a, x, y);
  } else if (a == 1.0 && z == x) {
    nv_axpy(b, y, x);
  } else if (a == 1.0 && b == 1.0) {
    nv_lin(1.0, x, 1.0, y, z); /* 1 * x is exact: x + y */
  } else if ((a == 1.0 && b == -1.0) || (a == -1.0 && b == 1.0)) {
    /* the positive one minus the other */
    if (a == 1.0)
      nv_lin(1.0, x, -1.0, y, z);
    else
      nv_lin(1.0, y, -1.0, x, z);
  } else if (a == 1.0 || b == 1.0) {
    if (a == 1.0)
      nv_lin(b, y, 1.0, x, z);
    else
      nv_lin(a, x, 1.0, y, z);
  } else if (a == -1.0 || b == -1.0) {
    if (a == -1.0)
      nv_lin(b, y, -1.0, x, z);
    else
      nv_lin(a, x, -1.0, y, z);
  } else if (a == b) {
    nv_scaled(a, x, 1.0, y, z);
  } else if (a == -b) {
    nv_scaled(a, x, -1.0, y, z);
  } else {
    const double *xd = DATA(x), *yd = DATA(y);
    double *zd = DATA(z);
    const size_t n = LEN(x);
    for (size_t i = 0; i < n; ++i)
      zd[i] = a * xd[i] + b * yd[i];
  }
}

static void nv_const(double c, N_Vector z)
{
  double *zd = DATA(z);
  const size_t n = LEN(z);
  for (size_t i = 0; i < n; ++i)
    zd[i] = c;
}

static void nv_prod(N_Vector x, N_Vector y, N_Vector z)
{
  const double *xd = DATA(x), *yd = DATA(y);
  double *zd = DATA(z);
  const size_t n = LEN(x);
  for (size_t i = 0; i < n; ++i)
    zd[i] = xd[i] * yd[i];
}

static void nv_div(N_Vector x, N_Vector y, N_Vector z)
{
  const double *xd = DATA(x), *yd = DATA(y);
  double *zd = DATA(z);
  const size_t n = LEN(x);
  for (size_t i = 0; i < n; ++i)
    zd[i] = xd[i] / yd[i];
}

/* z = c x; c = 1 copies and c = -1 negates (the same values). */
static void nv_scale(double c, N_Vector x, N_Vector z)
{
  const double *xd = DATA(x);
  double *zd = DATA(z);
  const size_t n = LEN(x);
  for (size_t i = 0; i < n; ++i)
    zd[i] = c * xd[i];
}

static void nv_abs(N_Vector x, N_Vector z)
{
  const double *xd = DATA(x);
  double *zd = DATA(z);
  const size_t n = LEN(x);
  for (size_t i = 0; i < n; ++i)
    zd[i] = fabs(xd[i]);
}

static void nv_inv(N_Vector x, N_Vector z)
{
  const double *xd = DATA(x);
  double *zd = DATA(z);
  const size_t n = LEN(x);
  for (size_t i = 0; i < n; ++i)
    zd[i] = 1.0 / xd[i];
}

static void nv_add_const(N_Vector x, double b, N_Vector z)
{
  const double *xd = DATA(x);
  double *zd = DATA(z);
  const size_t n = LEN(x);
  for (size_t i = 0; i < n; ++i)
    zd[i] = xd[i] + b;
}

/* sum of (x_i w_i)^2, in index order as the serial module sums. */
static double nv_wsqr_sum(N_Vector x, N_Vector w)
{
  const double *xd = DATA(x), *wd = DATA(w);
  const size_t n = LEN(x);
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double p = xd[i] * wd[i];
    sum += p * p;
  }
  return sum;
}

static double nv_wrms_norm(N_Vector x, N_Vector w)
{
  return sqrt(nv_wsqr_sum(x, w) / (double)NV_LENGTH_S(x));
}

static double nv_max_norm(N_Vector x)
{
  const double *xd = DATA(x);
  const size_t n = LEN(x);
  double max = 0.0;
  for (size_t i = 0; i < n; ++i)
    if (fabs(xd[i]) > max)
      max = fabs(xd[i]);
  return max;
}

/* z_i = 1 where |x_i| >= c, else 0. */
static void nv_compare(double c, N_Vector x, N_Vector z)
{
  const double *xd = DATA(x);
  double *zd = DATA(z);
  const size_t n = LEN(x);
  for (size_t i = 0; i < n; ++i)
    zd[i] = fabs(xd[i]) >= c ? 1.0 : 0.0;
}

/* z = 1 / x where x != 0; false if some x_i is 0 (its z_i is left). */
static booleantype nv_inv_test(N_Vector x, N_Vector z)
{
  const double *xd = DATA(x);
  double *zd = DATA(z);
  const size_t n = LEN(x);
  booleantype all = SUNTRUE;
  for (size_t i = 0; i < n; ++i) {
    if (xd[i] == 0.0)
      all = SUNFALSE;
    else
      zd[i] = 1.0 / xd[i];
  }
  return all;
}

N_Vector fb_sim_nvector_new(size_t n, SUNContext ctx)
{
  N_Vector v = N_VNew_Serial((sunindextype)n, ctx);
  if (!v)
    return NULL;
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = nv_linear_sum;
  ops->nvconst = nv_const;
  ops->nvprod = nv_prod;
  ops->nvdiv = nv_div;
  ops->nvscale = nv_scale;
  ops->nvabs = nv_abs;
  ops->nvinv = nv_inv;
  ops->nvaddconst = nv_add_const;
  ops->nvwrmsnorm = nv_wrms_norm;
  ops->nvwsqrsumlocal = nv_wsqr_sum;
  ops->nvmaxnorm = nv_max_norm;
  ops->nvcompare = nv_compare;
  ops->nvinvtest = nv_inv_test;
  return v;
}
