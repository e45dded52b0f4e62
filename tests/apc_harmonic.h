/* SPDX-License-Identifier: BSD-3-Clause */
/* The hand model of tests/apc_direct.h in steady harmonic motion: its
 * response to a road height e^{j omega t} on one track, each wheel seeing
 * it delayed by its distance behind the leading wheel, solved directly
 * (no descriptor form, no flexbond solver), for the frequency-response
 * tests. Include it before any other header that includes lapacke.h:
 * lapack_complex_double must be C99's double complex. */
#ifndef FLEXBOND_TEST_APC_HARMONIC_H
#define FLEXBOND_TEST_APC_HARMONIC_H

#include <complex.h>

#include "apc_direct.h"

/* Each tire's road height for a unit height on track (0 left, 1 right) at
 * the leading wheel, with its wheel's delay from the positions. */
static inline void apc_road_heights(const fb_scenario *s, int track, double omega,
                                    double complex *hc)
{
  double lead = -INFINITY;
  for (int c = 0; c < APC_NCORNERS; ++c)
    lead = fmax(lead, s->corner[c].x);
  for (int c = 0; c < APC_NCORNERS; ++c) {
    const int left = s->corner[c].y > 0;
    const double tau = (lead - s->corner[c].x) / s->speed;
    hc[c] = left == (track == 0) ? cexp(-I * omega * tau) : 0.0;
  }
}

/* The hand model's steady state q (APC_NDOF complex) under road heights
 * hc: (K + j w C - w^2 M) q = -sum over tires b_e (k_e + j w c_e) h_e. */
static inline int apc_harmonic_solve(const apc_model *m, double omega, const double complex *hc,
                                     double complex *q)
{
  double K[APC_NDOF * APC_NDOF], C[APC_NDOF * APC_NDOF];
  apc_stiffness_damping(m, K, C);
  lapack_complex_double a[APC_NDOF * APC_NDOF], b[APC_NDOF];
  for (int i = 0; i < APC_NDOF * APC_NDOF; ++i)
    a[i] = K[i] + I * omega * C[i] - omega * omega * m->mass[i];
  for (int i = 0; i < APC_NDOF; ++i)
    b[i] = 0.0;
  for (int c = 0; c < APC_NCORNERS; ++c) {
    const apc_elem *e = &m->elem[APC_TIRE + c];
    for (int i = 0; i < APC_NDOF; ++i)
      b[i] -= e->b[i] * (e->k + I * omega * e->c) * hc[c];
  }
  lapack_int ipiv[APC_NDOF];
  if (LAPACKE_zgesv(LAPACK_COL_MAJOR, APC_NDOF, 1, a, APC_NDOF, ipiv, b, APC_NDOF) != 0)
    return -1;
  memcpy(q, b, sizeof b);
  return 0;
}

static inline double complex apc_harmonic_deflection(const apc_model *m, int e,
                                                     const double complex *q,
                                                     const double complex *hc)
{
  double complex d = 0.0;
  for (int i = 0; i < APC_NDOF; ++i)
    d += m->elem[e].b[i] * q[i];
  return m->elem[e].road_corner >= 0 ? d + hc[m->elem[e].road_corner] : d;
}

/* The hand model's outputs (those of apc_layout.h with a response; the
 * torsion of a rigid hull is 0, the powers are left 0) per metre of road
 * height on track (0 left, 1 right) at omega (rad/s), into want. Returns
 * 0, or -1 when the harmonic system is singular. */
static inline int apc_harmonic_outputs(const apc_model *m, const fb_scenario *s, double omega,
                                       int track, double complex want[APC_NOUTPUTS])
{
  double complex hc[APC_NCORNERS] = {0}, q[APC_NDOF] = {0};
  apc_road_heights(s, track, omega, hc);
  if (apc_harmonic_solve(m, omega, hc, q) != 0)
    return -1;
  const apc_elem *tire = &m->elem[APC_TIRE + APC_LF];
  want[APC_OUT_TIRE_FORCE_LF] =
      (tire->k + I * omega * tire->c) * apc_harmonic_deflection(m, APC_TIRE, q, hc);
  want[APC_OUT_SPRING_DEFL_RF] = apc_harmonic_deflection(m, APC_RF, q, hc);
  want[APC_OUT_DRIVER_ACC] = -omega * omega * q[APC_DRIVER];
  want[APC_OUT_TIRE_DEFL_RM] = apc_harmonic_deflection(m, APC_TIRE + APC_RM, q, hc);
  return 0;
}

#endif
