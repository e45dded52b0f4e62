/* SPDX-License-Identifier: BSD-3-Clause */
/* An independent model of System 1 (rigid hull) of the reference vehicle,
 * written by hand from the data sheet (docs/reference-vehicle.md)
 * as a plain second-order system M q'' = Q(t, q, q'), for verifying
 * flexbond's bond-graph vehicle. It takes only the parameters from the
 * scenario; no bond graph, block diagram or solver of flexbond is used.
 *
 * Degrees of freedom (11): hull bounce z, roll phi, pitch theta; the six
 * wheel heights (LF .. RR); the driver and the engine heights. A hull
 * point (x, y) moves vertically by a = z + y phi - x theta = J(x, y) . q
 * with J = [1, y, -x] (data sheet, "Axes and signs").
 *
 * Every spring-damper pair is an element with a compression-positive
 * deflection d = b . q + u(t) (u the road height for a tire, else 0), force
 * F = k d + c d' along its own axis, and, by virtual work, generalised
 * force -b F on the degrees of freedom (potential energy k d^2 / 2):
 *   suspension: d = r (z_w - a)  (spring travel, motion ratio r; the force
 *               on wheel and hull is r F, i.e. r^2 k_s times wheel travel)
 *   tire:       d = z_road - z_w
 *   mount:      d = a - z_m       (driver plus seat, engine)
 * Gravity: m g down on driver, engine and wheels; the hull plus payload
 * weight as nload equal forces at the load points. Payload lumped: the
 * payload mass spread equally over the load points, each a point mass
 * moving vertically by J . q, so the hull block gains (m_p / n) sum J J^T. */
#ifndef FLEXBOND_TEST_APC_DIRECT_H
#define FLEXBOND_TEST_APC_DIRECT_H

#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "apc_layout.h"
#include "damper_util.h"
#include "road_util.h"

#define APC_PI 3.14159265358979323846

enum {
  APC_HULL_Z,
  APC_HULL_PHI,
  APC_HULL_THETA,
  APC_WHEEL = 3, /* + corner */
  APC_DRIVER = APC_WHEEL + APC_NCORNERS,
  APC_ENGINE,
  APC_NDOF,
  APC_NX = 2 * APC_NDOF /* positions then velocities */
};

/* Elements: suspension of corner i is i, its tire APC_TIRE + i. */
enum {
  APC_TIRE = APC_NCORNERS,
  APC_MOUNT_DRIVER = 2 * APC_NCORNERS,
  APC_MOUNT_ENGINE,
  APC_NELEM
};

typedef struct apc_elem {
  double b[APC_NDOF]; /* deflection = b . q (+ road) */
  double k, c;        /* N/m, N s/m along the element's axis */
  int road_corner;    /* corner whose road height adds to d, -1 for none */
} apc_elem;

typedef struct apc_model {
  double mass[APC_NDOF * APC_NDOF];     /* M, symmetric */
  double mass_inv[APC_NDOF * APC_NDOF]; /* M^-1, symmetric */
  double gravity_force[APC_NDOF];       /* generalised weights */
  apc_elem elem[APC_NELEM];
  double entry[APC_NCORNERS], exit[APC_NCORNERS]; /* bump times, s */
  double speed, bump_height, bump_length;
} apc_model;

/* Output indices as in fb_vehicle_output_name. */
enum {
  APC_OUT_TIRE_FORCE_LF,
  APC_OUT_SPRING_DEFL_RF,
  APC_OUT_TORSION,
  APC_OUT_DRIVER_ACC,
  APC_OUT_SHOCK_POWER_LM,
  APC_OUT_TIRE_DEFL_RM,
  APC_OUT_TIRE_POWER_LR,
  APC_NOUT
};

static inline void apc_hull_vector(double x, double y, double *b, double scale)
{
  b[APC_HULL_Z] += scale;
  b[APC_HULL_PHI] += scale * y;
  b[APC_HULL_THETA] -= scale * x;
}

static inline void apc_set_elem(apc_elem *e, double k, double c, int road_corner)
{
  memset(e->b, 0, sizeof e->b);
  e->k = k;
  e->c = c;
  e->road_corner = road_corner;
}

/* Bump entry time of a wheel, from the data sheet's formula (not from
 * fb_scenario_road_entry, which is checked against this one). */
static inline double apc_entry_time(const fb_scenario *s, int corner)
{
  const fb_corner_params *lf = &s->corner[APC_LF], *c = &s->corner[corner];
  return road_bump(s)->first_contact +
         ((lf->x - c->x) + (lf->y - c->y) * tan(road_bump(s)->angle)) / s->speed;
}

static inline void apc_build_mass(apc_model *m, const fb_scenario *s)
{
  double *M = m->mass;
  memset(M, 0, sizeof m->mass);
  M[APC_HULL_Z * (APC_NDOF + 1)] = s->hull_mass;
  M[APC_HULL_PHI * (APC_NDOF + 1)] = s->hull_ixx;
  M[APC_HULL_THETA * (APC_NDOF + 1)] = s->hull_iyy;
  if (s->payload == FB_PAYLOAD_LUMPED) {
    const double point_mass = (s->total_weight / s->gravity - s->hull_mass) / (double)s->nload;
    for (size_t l = 0; l < s->nload; ++l) {
      double J[APC_NDOF] = {0};
      apc_hull_vector(s->load_x[l], s->load_y[l], J, 1.0);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          M[i + APC_NDOF * j] += point_mass * J[i] * J[j];
    }
  }
  for (int c = 0; c < APC_NCORNERS; ++c)
    M[(APC_WHEEL + c) * (APC_NDOF + 1)] = s->corner[c].wheel_mass;
  M[APC_DRIVER * (APC_NDOF + 1)] = APC_DRIVER(s)->mass;
  M[APC_ENGINE * (APC_NDOF + 1)] = APC_ENGINE(s)->mass;
}

static inline void apc_build_elements(apc_model *m, const fb_scenario *s)
{
  for (int c = 0; c < APC_NCORNERS; ++c) {
    const fb_corner_params *p = &s->corner[c];
    apc_elem *susp = &m->elem[c], *tire = &m->elem[APC_TIRE + c];
    apc_set_elem(susp, p->spring_k, du_damper_c(p), -1);
    susp->b[APC_WHEEL + c] = p->motion_ratio;
    apc_hull_vector(p->x, p->y, susp->b, -p->motion_ratio);
    apc_set_elem(tire, p->tire_k, p->tire_c, c);
    tire->b[APC_WHEEL + c] = -1.0;
  }
  const fb_mount *mounts[2] = {APC_DRIVER(s), APC_ENGINE(s)};
  for (int i = 0; i < 2; ++i) {
    apc_elem *e = &m->elem[APC_MOUNT_DRIVER + i];
    apc_set_elem(e, mounts[i]->stiffness, mounts[i]->damping, -1);
    apc_hull_vector(mounts[i]->x, mounts[i]->y, e->b, 1.0);
    e->b[APC_DRIVER + i] = -1.0;
  }
}

static inline void apc_build_gravity(apc_model *m, const fb_scenario *s)
{
  double *Q = m->gravity_force;
  memset(Q, 0, sizeof m->gravity_force);
  for (size_t l = 0; l < s->nload; ++l)
    apc_hull_vector(s->load_x[l], s->load_y[l], Q, -s->total_weight / (double)s->nload);
  for (int c = 0; c < APC_NCORNERS; ++c)
    Q[APC_WHEEL + c] = -s->corner[c].wheel_mass * s->gravity;
  Q[APC_DRIVER] = -APC_DRIVER(s)->mass * s->gravity;
  Q[APC_ENGINE] = -APC_ENGINE(s)->mass * s->gravity;
}

/* Fills m from s. Returns 0, or the LAPACK status if M is not positive
 * definite. */
static inline int apc_model_init(apc_model *m, const fb_scenario *s)
{
  apc_build_mass(m, s);
  apc_build_elements(m, s);
  apc_build_gravity(m, s);
  for (int c = 0; c < APC_NCORNERS; ++c) {
    m->entry[c] = apc_entry_time(s, c);
    m->exit[c] = m->entry[c] + road_bump(s)->length / s->speed;
  }
  m->speed = s->speed;
  m->bump_height = road_bump(s)->height;
  m->bump_length = road_bump(s)->length;
  double A[APC_NDOF * APC_NDOF];
  memcpy(A, m->mass, sizeof A);
  memset(m->mass_inv, 0, sizeof m->mass_inv);
  for (int i = 0; i < APC_NDOF; ++i)
    m->mass_inv[i * (APC_NDOF + 1)] = 1.0;
  return LAPACKE_dposv(LAPACK_COL_MAJOR, 'L', APC_NDOF, APC_NDOF, A, APC_NDOF, m->mass_inv,
                       APC_NDOF);
}

/* Road height and vertical velocity under a wheel: the data sheet's bump
 * z(s) = h/2 (1 - cos(2 pi s / L)), 0 <= s <= L, s = V (t - t_entry). */
static inline void apc_road(const apc_model *m, int corner, double t, double *z, double *v)
{
  const double s = m->speed * (t - m->entry[corner]);
  if (s <= 0.0 || s >= m->bump_length) {
    *z = 0.0;
    *v = 0.0;
    return;
  }
  const double w = 2.0 * APC_PI / m->bump_length;
  *z = 0.5 * m->bump_height * (1.0 - cos(w * s));
  *v = 0.5 * m->bump_height * w * m->speed * sin(w * s);
}

/* Deflection and its rate of element e in state x at time t. */
static inline void apc_deflection(const apc_model *m, int e, double t, const double *x,
                                  double *d, double *ddot)
{
  const apc_elem *el = &m->elem[e];
  double dq = 0.0, dv = 0.0;
  for (int i = 0; i < APC_NDOF; ++i) {
    dq += el->b[i] * x[i];
    dv += el->b[i] * x[APC_NDOF + i];
  }
  if (el->road_corner >= 0) {
    double zr, vr;
    apc_road(m, el->road_corner, t, &zr, &vr);
    dq += zr;
    dv += vr;
  }
  *d = dq;
  *ddot = dv;
}

/* x' = f(t, x): q' = v, v' = M^-1 (Q_gravity - sum_e b_e F_e). */
static inline void apc_rhs(const apc_model *m, double t, const double *x, double *xdot)
{
  double Q[APC_NDOF];
  memcpy(Q, m->gravity_force, sizeof Q);
  for (int e = 0; e < APC_NELEM; ++e) {
    double d, dd;
    apc_deflection(m, e, t, x, &d, &dd);
    const double F = m->elem[e].k * d + m->elem[e].c * dd;
    for (int i = 0; i < APC_NDOF; ++i)
      Q[i] -= m->elem[e].b[i] * F;
  }
  for (int i = 0; i < APC_NDOF; ++i) {
    xdot[i] = x[APC_NDOF + i];
    double a = 0.0;
    for (int j = 0; j < APC_NDOF; ++j)
      a += m->mass_inv[i + APC_NDOF * j] * Q[j];
    xdot[APC_NDOF + i] = a;
  }
}

/* The seven outputs (data sheet, "The seven outputs"). */
static inline void apc_outputs(const apc_model *m, double t, const double *x, double *y)
{
  double d, dd, xdot[APC_NX];
  apc_deflection(m, APC_TIRE + APC_LF, t, x, &d, &dd);
  y[APC_OUT_TIRE_FORCE_LF] =
      m->elem[APC_TIRE + APC_LF].k * d + m->elem[APC_TIRE + APC_LF].c * dd;
  apc_deflection(m, APC_RF, t, x, &d, &dd);
  y[APC_OUT_SPRING_DEFL_RF] = d;
  y[APC_OUT_TORSION] = 0.0;
  apc_rhs(m, t, x, xdot);
  y[APC_OUT_DRIVER_ACC] = xdot[APC_NDOF + APC_DRIVER];
  apc_deflection(m, APC_LM, t, x, &d, &dd);
  y[APC_OUT_SHOCK_POWER_LM] = m->elem[APC_LM].c * dd * dd;
  apc_deflection(m, APC_TIRE + APC_RM, t, x, &d, &dd);
  y[APC_OUT_TIRE_DEFL_RM] = d;
  apc_deflection(m, APC_TIRE + APC_LR, t, x, &d, &dd);
  y[APC_OUT_TIRE_POWER_LR] = m->elem[APC_TIRE + APC_LR].c * dd * dd;
}

/* Classical fourth-order Runge-Kutta, n equal steps from t0 to t1. */
static inline void apc_rk4(const apc_model *m, double t0, double t1, size_t n, double *x)
{
  const double h = (t1 - t0) / (double)n;
  double k1[APC_NX], k2[APC_NX], k3[APC_NX], k4[APC_NX], xs[APC_NX];
  for (size_t step = 0; step < n; ++step) {
    const double t = t0 + (double)step * h;
    apc_rhs(m, t, x, k1);
    for (int i = 0; i < APC_NX; ++i)
      xs[i] = x[i] + 0.5 * h * k1[i];
    apc_rhs(m, t + 0.5 * h, xs, k2);
    for (int i = 0; i < APC_NX; ++i)
      xs[i] = x[i] + 0.5 * h * k2[i];
    apc_rhs(m, t + 0.5 * h, xs, k3);
    for (int i = 0; i < APC_NX; ++i)
      xs[i] = x[i] + h * k3[i];
    apc_rhs(m, t + h, xs, k4);
    for (int i = 0; i < APC_NX; ++i)
      x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
}

/* Integrates over [a, b] in steps of at most dt, stopping exactly at every
 * bump entry and exit inside, where the road's acceleration jumps (the
 * RK4 error expansion needs a smooth right-hand side within each step). */
static inline void apc_advance(const apc_model *m, double a, double b, double dt, double *x)
{
  while (a < b) {
    double stop = b;
    for (int c = 0; c < APC_NCORNERS; ++c) {
      if (m->entry[c] > a && m->entry[c] < stop)
        stop = m->entry[c];
      if (m->exit[c] > a && m->exit[c] < stop)
        stop = m->exit[c];
    }
    const size_t n = (size_t)ceil((stop - a) / dt * (1.0 - 1e-12));
    apc_rk4(m, a, stop, n ? n : 1, x);
    a = stop;
  }
}

/* Samples the outputs at t_k = k / rate, k = 0 .. nsamples-1, from the
 * state x0 at t = 0; y is nsamples x APC_NOUT, row-major. */
static inline void apc_simulate(const apc_model *m, const double *x0, double rate,
                                size_t nsamples, double dt, double *y)
{
  double x[APC_NX];
  memcpy(x, x0, sizeof x);
  for (size_t k = 0; k < nsamples; ++k) {
    const double t = (double)k / rate;
    if (k > 0)
      apc_advance(m, (double)(k - 1) / rate, t, dt, x);
    apc_outputs(m, t, x, y + APC_NOUT * k);
  }
}

/* Stiffness and damping matrices K = sum k b b^T, C = sum c b b^T. */
static inline void apc_stiffness_damping(const apc_model *m, double *K, double *C)
{
  memset(K, 0, sizeof(double) * APC_NDOF * APC_NDOF);
  memset(C, 0, sizeof(double) * APC_NDOF * APC_NDOF);
  for (int e = 0; e < APC_NELEM; ++e)
    for (int i = 0; i < APC_NDOF; ++i)
      for (int j = 0; j < APC_NDOF; ++j) {
        const double bb = m->elem[e].b[i] * m->elem[e].b[j];
        K[i + APC_NDOF * j] += m->elem[e].k * bb;
        C[i + APC_NDOF * j] += m->elem[e].c * bb;
      }
}

#endif
