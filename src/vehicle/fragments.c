/* SPDX-License-Identifier: BSD-3-Clause */
/* The vehicle's subsystems as bond-graph fragments with ports (the paper's
 * Fig. 5). Each fragment is built from its own parameters only; the
 * assembly (assemble.c) connects them through ports.
 *
 * Sign conventions inside the fragments (all efforts are vertical forces
 * in N, flows vertical velocities in m/s, z up):
 *   - a 0-junction between a velocity coming in and one going out forms
 *     their difference: in - out - (to the spring's 1-junction) = 0;
 *   - spring and tire states are compressions (positive when shortened). */
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* One-port field with a scalar law (mass, stiffness or damping). */
int vehicle_add_scalar(fb_bg *bg, const char *name, fb_bg_kind kind, double v, fb_err *err)
{
  fb_mat *m = NULL;
  const size_t one = 1;
  int rc = fb_mat_new_scaled_identity(1, v, &m, err);
  return rc ? rc : fb_bg_add_field(bg, name, kind, 1, &one, &m, err);
}

static int add_constant_effort(fb_bg *bg, const char *name, double value, fb_err *err)
{
  fb_tfun *f = NULL;
  int rc = fb_tfun_new_const(value, &f, err);
  return rc ? rc : fb_bg_add_source(bg, name, FB_BG_SE, 1, &f, err);
}

/* Connects the bonds listed as {name, from, to} triples. */
static int connect_all(fb_bg *bg, const char *const (*bonds)[3], size_t n, fb_err *err)
{
  for (size_t i = 0; i < n; ++i) {
    int rc = fb_bg_connect(bg, bonds[i][0], bonds[i][1], bonds[i][2], err);
    if (rc)
      return rc;
  }
  return FB_OK;
}

/* The hull's coordinates (z, phi, theta) among vehicle_rigid_rows' six. */
enum { RIGID_FIRST = 2, RIGID_DOFS = 3 };

/* The row of the rigid-body map from (z, phi, theta) to the translation
 * of hull point r along axis: its vertical one is [1, y, -x]. */
static void rigid_axis_row(const double *r, int axis, double *row)
{
  double rows[18];
  vehicle_rigid_rows(r, rows);
  for (int j = 0; j < RIGID_DOFS; ++j)
    row[j] = rows[6 * axis + RIGID_FIRST + j];
}

/* Row [1, y, -x] of the rigid-body map from (z', phi', theta') to the
 * vertical velocity of hull point (x, y). */
static void rigid_row(double x, double y, double *row)
{
  const double r[3] = {x, y, 0.0};
  rigid_axis_row(r, 2, row);
}

/* The same row over the six rigid-body motions (x', y', z', phi',
 * theta', psi'): the third row of vehicle_rigid_transport, [0, 0, 1, y,
 * -x, 0] (a vertical velocity does not depend on the point's height). */
static void rigid_row6(double x, double y, double *row)
{
  memset(row, 0, 6 * sizeof *row);
  rigid_row(x, y, row + 2);
}

/* The hull's coordinates: 3 (bounce, roll, pitch) or, carrying mounted
 * rigid bodies, 6. */
static size_t rigid_ndof(const fb_scenario *s)
{
  return s->nbodies ? 6 : 3;
}

size_t fb_vehicle_free_motions(const fb_scenario *s)
{
  return rigid_ndof(s) - 3;
}

/* n x ndof matrix transformer from the hull's generalised velocities to n
 * points' vertical velocities. */
static int add_point_map(fb_bg *bg, const char *name, size_t ndof, size_t n, const double *x,
                         const double *y, fb_err *err)
{
  double *rows = malloc(ndof * n * sizeof *rows);
  if (!rows)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; i < n; ++i) {
    if (ndof == 6)
      rigid_row6(x[i], y[i], rows + 6 * i);
    else
      rigid_row(x[i], y[i], rows + 3 * i);
  }
  fb_mat *t = NULL;
  int rc = fb_mat_new_dense_rowmajor(n, ndof, rows, &t, err);
  free(rows);
  return rc ? rc : fb_bg_add_mtf(bg, name, &t, err);
}

/* Attachment points in "attach" port order: the corners, then the
 * mounts. x and y hold fb_scenario_nattach(s) entries each. */
static void attach_points(const fb_scenario *s, double *x, double *y)
{
  for (size_t c = 0; c < s->ncorners; ++c) {
    x[c] = s->corner[c].x;
    y[c] = s->corner[c].y;
  }
  for (size_t b = 0; b < s->nmounts; ++b) {
    x[s->ncorners + b] = s->mount[b].x;
    y[s->ncorners + b] = s->mount[b].y;
  }
}

/* Adds the point mass m at hull point (x, y) to the rigid inertia m33:
 * its kinetic energy 1/2 m (z' + y phi' - x theta')^2 adds m r r' with r
 * the rigid row of the point (full 3x3, consistent with the points). */
static void add_point_inertia(double m, double x, double y, double *m33)
{
  double r[3];
  rigid_row(x, y, r);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      m33[3 * i + j] += m * r[i] * r[j];
}

void fb_vehicle_rigid_inertia(const fb_scenario *s, double *m33)
{
  memset(m33, 0, 9 * sizeof *m33);
  m33[0] = s->hull_mass;
  m33[4] = s->hull_ixx;
  m33[8] = s->hull_iyy;
  for (size_t k = 0; k < s->npoint_masses; ++k)
    add_point_inertia(s->point_mass[k].mass, s->point_mass[k].x, s->point_mass[k].y, m33);
  if (s->payload != FB_PAYLOAD_LUMPED)
    return;
  double mp = fb_scenario_payload_mass(s) / (double)s->nload;
  for (size_t k = 0; k < s->nload; ++k)
    add_point_inertia(mp, s->load_x[k], s->load_y[k], m33);
}

/* m T' T for a point mass m at floor point (x, y), taken at the centre
 * of mass's height: its kinetic energy 1/2 m |v + omega x r|^2. */
static void add_point_inertia6(double m, double x, double y, double *m66)
{
  const double r[3] = {x, y, 0.0};
  double t[36];
  vehicle_rigid_transport(r, t);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 3; ++k) /* the rows of the translations */
        m66[6 * i + j] += m * t[6 * k + i] * t[6 * k + j];
}

void vehicle_rigid_inertia6(const fb_scenario *s, double *m66)
{
  memset(m66, 0, 36 * sizeof *m66);
  double j[9];
  vehicle_hull_inertia(s, j);
  for (int i = 0; i < 3; ++i) {
    m66[7 * i] = s->hull_mass;
    for (int c = 0; c < 3; ++c)
      m66[6 * (3 + i) + 3 + c] = j[3 * i + c];
  }
  for (size_t k = 0; k < s->npoint_masses; ++k)
    add_point_inertia6(s->point_mass[k].mass, s->point_mass[k].x, s->point_mass[k].y, m66);
  if (s->payload != FB_PAYLOAD_LUMPED)
    return;
  double mp = fb_scenario_payload_mass(s) / (double)s->nload;
  for (size_t k = 0; k < s->nload; ++k)
    add_point_inertia6(mp, s->load_x[k], s->load_y[k], m66);
}

/* Torsion of a rigid hull: the roll of the front edge minus that of the
 * rear edge, over the integrated generalised velocities (z, phi, theta).
 * Each edge's roll is (z_left - z_right) / (y_left - y_right) with
 * z = r . (z, phi, theta); for a rigid body both equal phi, so the weights
 * cancel exactly (to zero, not to rounding). */
static void rigid_torsion_weights(const fb_scenario *s, double *w)
{
  double fl[3], fr[3], rl[3], rr[3];
  rigid_row(s->edge_front_x, s->edge_left_y, fl);
  rigid_row(s->edge_front_x, s->edge_right_y, fr);
  rigid_row(s->edge_rear_x, s->edge_left_y, rl);
  rigid_row(s->edge_rear_x, s->edge_right_y, rr);
  double dy = s->edge_left_y - s->edge_right_y;
  /* Over six coordinates the vertical ones are the third to fifth. */
  const size_t at = rigid_ndof(s) == 6 ? 2 : 0;
  memset(w, 0, rigid_ndof(s) * sizeof *w);
  for (int i = 0; i < 3; ++i)
    w[at + (size_t)i] = (fl[i] - fr[i]) / dy - (rl[i] - rr[i]) / dy;
}

/* The ports of the bodies' bushings on the hull (their parent NULL), at
 * their points from the hull's centre of mass, the origin. */
static int add_hull_bushings(const fb_scenario *s, fb_bg *bg, fb_err *err)
{
  int rc = FB_OK;
  size_t i = 0, j = 0;
  for (size_t k = 0; !rc && fb_scenario_bushing_at(s, k, &i, &j); ++k) {
    const fb_bushing *u = &s->body[i].bushing[j];
    const double r[3] = {u->x, u->y, u->z};
    if (!s->body[i].parent)
      rc = vehicle_add_bushing_port(bg, "J", k, r, err);
  }
  return rc;
}

static int rigid_hull_graph(const fb_scenario *s, fb_bg *bg, fb_err *err)
{
  const size_t na = fb_scenario_nattach(s), ndof = rigid_ndof(s);
  double inertia[36], *ax = calloc(2 * na + 1, sizeof *ax);
  if (!ax)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  double *ay = ax + na;
  if (ndof == 6)
    vehicle_rigid_inertia6(s, inertia);
  else
    fb_vehicle_rigid_inertia(s, inertia);
  attach_points(s, ax, ay);
  fb_mat *m = NULL;
  int rc = fb_mat_new_dense_rowmajor(ndof, ndof, inertia, &m, err);
  if (!rc)
    rc = fb_bg_add_field(bg, "body", FB_BG_I, 1, &ndof, &m, err);
  static const char *const rigid_motions[3] = {"hull bounce", "hull roll", "hull pitch"};
  static const char *const rigid_motions6[6] = {"hull surge", "hull sway",  "hull bounce",
                                                "hull roll",  "hull pitch", "hull yaw"};
  if (!rc)
    rc = fb_bg_set_labels(bg, "body", ndof == 6 ? rigid_motions6 : rigid_motions, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "J", FB_BG_J1, ndof, err);
  if (!rc)
    rc = add_point_map(bg, "to_attach", ndof, na, ax, ay, err);
  free(ax);
  if (!rc)
    rc = add_point_map(bg, "to_load", ndof, s->nload, s->load_x, s->load_y, err);
  if (!rc)
    rc = add_hull_bushings(s, bg, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "attach", FB_BG_J1, na, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "load", FB_BG_J1, s->nload, err);
  static const char *const bonds[][3] = {
      {"b_body", "J", "body"},
      {"b_attach_in", "J", "to_attach.1"},
      {"b_attach", "to_attach.2", "attach"},
      {"b_load_in", "J", "to_load.1"},
      {"b_load", "to_load.2", "load"},
  };
  if (!rc)
    rc = connect_all(bg, bonds, sizeof bonds / sizeof bonds[0], err);
  if (!rc)
    rc = fb_bg_add_port(bg, "attach", "attach", FB_PORT_IN, err);
  if (!rc)
    rc = fb_bg_add_port(bg, "load", "load", FB_PORT_IN, err);
  return rc;
}

/* Output o read from the rigid hull's motion: its row over the hull's
 * ndof coordinates (rigid_ndof: z, phi, theta, or the six of
 * vehicle_rigid_rows), the point's or the rigid coordinate's. The 3-DOF
 * hull moves in bounce, roll and pitch only: its longitudinal, lateral
 * and yaw motions are zero by the model's assumption, and so are their
 * rows. */
static void rigid_reading_row(const fb_output_spec *o, const vehicle_hull_motion *how,
                              size_t ndof, double *row)
{
  const int first = ndof == 6 ? 0 : RIGID_FIRST;
  memset(row, 0, ndof * sizeof *row);
  const int j = how->coordinate - first;
  if (how->coordinate < 0 && ndof == 6) {
    double rows[18];
    vehicle_rigid_rows(o->at, rows);
    memcpy(row, rows + 6 * o->direction, 6 * sizeof *row);
  } else if (how->coordinate < 0) {
    rigid_axis_row(o->at, o->direction, row);
  } else if (j >= 0 && (size_t)j < ndof) {
    row[j] = 1.0;
  }
}

/* The rigid hull's outputs read from its motion: a displacement is the
 * integrated flow of b_body (the velocities of its coordinates) on its
 * row, a velocity the flow, an acceleration the effort on the inertia M
 * over M: q'' = M^-1 p' (p' the effort on b_body), so the row r weighs
 * the effort by M^-1 r (M symmetric). */
static int rigid_readings(const fb_scenario *s, fb_hull *h, fb_err *err)
{
  int rc = vehicle_hull_readings_new(s, h, err);
  const size_t ndof = rigid_ndof(s);
  double inertia[36];
  if (ndof == 6)
    vehicle_rigid_inertia6(s, inertia);
  else
    fb_vehicle_rigid_inertia(s, inertia);
  vehicle_hull_motion how;
  for (size_t o = 0; !rc && o < s->noutputs; ++o) {
    if (!vehicle_output_hull_motion(&s->output[o], &how))
      continue;
    double row[6];
    rigid_reading_row(&s->output[o], &how, ndof, row);
    if (how.derivative == 2) {
      double m[36];
      memcpy(m, inertia, ndof * ndof * sizeof *m);
      const lapack_int n = (lapack_int)ndof;
      const lapack_int info = LAPACKE_dposv(LAPACK_ROW_MAJOR, 'L', n, 1, m, n, row, 1);
      if (info)
        rc = fb_err_set(err, FB_EMODEL, "the rigid hull's inertia is not positive definite");
    }
    if (!rc)
      rc = vehicle_hull_reading_set(&h->reading[o], "b_body",
                                    how.derivative == 2 ? FB_PROBE_EFFORT : FB_PROBE_FLOW,
                                    how.derivative == 0, row, ndof, err);
  }
  return rc;
}

void fb_hull_free(fb_hull **h)
{
  if (!h || !*h)
    return;
  vehicle_hull_readings_free(*h);
  fb_bg_free(&(*h)->graph);
  free((*h)->torsion_target);
  free((*h)->torsion_weights);
  free((*h)->torsion_fit_weights);
  free(*h);
  *h = NULL;
}

int fb_vehicle_rigid_hull(const fb_scenario *s, fb_hull **out, fb_err *err)
{
  *out = NULL;
  fb_hull *h = calloc(1, sizeof *h);
  if (!h)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  h->torsion_kind = FB_PROBE_FLOW;
  h->torsion_integrate = 1;
  h->ntorsion = rigid_ndof(s);
  h->carries_bodies = 1;
  h->torsion_target = fb_strdup("b_body");
  h->torsion_weights = malloc(h->ntorsion * sizeof *h->torsion_weights);
  h->torsion_fit_weights = malloc(h->ntorsion * sizeof *h->torsion_fit_weights);
  int rc = h->torsion_target && h->torsion_weights && h->torsion_fit_weights
               ? FB_OK
               : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = fb_bg_new("rigid_hull", &h->graph, err);
  if (!rc)
    rc = rigid_hull_graph(s, h->graph, err);
  if (rc) {
    fb_hull_free(&h);
    fb_err_prefix(err, "rigid hull: ");
    return rc;
  }
  rc = rigid_readings(s, h, err);
  if (rc) {
    fb_hull_free(&h);
    return rc;
  }
  /* A rigid edge is a straight line: the fit and its end nodes agree. */
  rigid_torsion_weights(s, h->torsion_weights);
  memcpy(h->torsion_fit_weights, h->torsion_weights, h->ntorsion * sizeof *h->torsion_weights);
  *out = h;
  return FB_OK;
}

/* Mass on a spring and damper to a hull point. The relative velocity
 * v_rel = v_hull - v_mass (compression rate) comes out of the 0-junction
 * "force" (mass in, hull out, spring in), whose common effort is the
 * spring-damper force with the sign of tension. */
int fb_vehicle_mount(const fb_mount *mnt, double gravity, fb_bg **out, fb_err *err)
{
  *out = NULL;
  fb_bg *bg = NULL;
  int rc = fb_bg_new("mount", &bg, err);
  if (!rc)
    rc = vehicle_add_scalar(bg, "mass", FB_BG_I, mnt->mass, err);
  /* The body a mode of the vehicle may move: the mount itself. */
  const char *const body[1] = {mnt->name ? mnt->name : "mounted body"};
  if (!rc)
    rc = fb_bg_set_labels(bg, "mass", body, err);
  if (!rc)
    rc = add_constant_effort(bg, "weight", -mnt->mass * gravity, err);
  if (!rc)
    rc = vehicle_add_scalar(bg, "spring", FB_BG_C, mnt->stiffness, err);
  if (!rc)
    rc = vehicle_add_scalar(bg, "damper", FB_BG_R, mnt->damping, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "Jm", FB_BG_J1, 1, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "force", FB_BG_J0, 1, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "Jrel", FB_BG_J1, 1, err);
  static const char *const bonds[][3] = {
      {"b_mass", "Jm", "mass"},       {"b_weight", "weight", "Jm"},
      {"b_up", "Jm", "force"},        {"b_rel", "Jrel", "force"},
      {"b_spring", "Jrel", "spring"}, {"b_damper", "Jrel", "damper"},
  };
  if (!rc)
    rc = connect_all(bg, bonds, sizeof bonds / sizeof bonds[0], err);
  if (!rc)
    rc = fb_bg_add_port(bg, "hull", "force", FB_PORT_OUT, err);
  if (rc) {
    fb_bg_free(&bg);
    return rc;
  }
  *out = bg;
  return FB_OK;
}

/* The spring, the C element "spring", as the corner's spring law builds
 * it (flexbond/spring.h). */
static int add_spring(fb_bg *bg, const fb_corner_params *c, fb_err *err)
{
  const fb_spring_context ctx = fb_corner_spring_context(c);
  return fb_corner_spring_law(c)->ops->build(c->spring.bytes, &ctx, bg, err);
}

/* The shock absorber, the R element "damper", as the corner's damper
 * law builds it (flexbond/damper.h). */
static int add_shock_absorber(fb_bg *bg, const fb_corner_params *c, fb_err *err)
{
  return fb_corner_damper_law(c)->ops->build(c->damper.bytes, bg, err);
}

/* The tire's spring and damper, in parallel on the 1-junction "Jt", as
 * the corner's tire model builds them (flexbond/tire.h). */
static int add_tire(fb_bg *bg, const fb_corner_params *c, fb_err *err)
{
  const fb_tire_model *m = fb_corner_tire_model(c);
  const fb_tire_context ctx = fb_corner_tire_context(c);
  return m->ops->build(c->tire.bytes, &ctx, bg, err);
}

/* Suspension, wheel and tire. The 0-junction "susp" forms the wheel's
 * velocity relative to the hull (compression rate of the suspension),
 * the arm (a TF of the motion ratio) turns it into the spring's rate; the
 * 0-junction "tire" forms road minus wheel velocity (tire compression
 * rate). coupled: a 1-junction "Jrel" between "susp" and the arm carries
 * that relative velocity to a port "travel" (OUT), where a force in
 * parallel with the suspension's (an anti-roll bar's) joins it; without
 * it the graph is the paper's, bond for bond. */
static int corner_graph(const fb_corner_params *c, double gravity, int coupled, fb_bg *bg,
                        fb_err *err)
{
  int rc = vehicle_add_scalar(bg, "wheel", FB_BG_I, c->wheel_mass, err);
  /* The wheel's mode: its hop. */
  char hop[96];
  snprintf(hop, sizeof hop, "wheel hop %s", c->name ? c->name : "");
  const char *const body[1] = {hop};
  if (!rc)
    rc = fb_bg_set_labels(bg, "wheel", body, err);
  if (!rc)
    rc = add_constant_effort(bg, "weight", -c->wheel_mass * gravity, err);
  if (!rc)
    rc = add_spring(bg, c, err);
  if (!rc)
    rc = add_shock_absorber(bg, c, err);
  if (!rc && fb_stops_any(&c->stops))
    rc = vehicle_add_stops(&c->stops, "stops", "spring", bg, err);
  if (!rc)
    rc = fb_bg_add_tf(bg, "arm", FB_BG_TF, 1, c->motion_ratio, err);
  if (!rc)
    rc = add_tire(bg, c, err);
  const char *const junctions[][2] = {
      {"Jw", "1"}, {"susp", "0"}, {"Jsp", "1"}, {"tire", "0"}, {"Jt", "1"}};
  for (size_t i = 0; !rc && i < sizeof junctions / sizeof junctions[0]; ++i)
    rc = fb_bg_add_junction(bg, junctions[i][0],
                            junctions[i][1][0] == '0' ? FB_BG_J0 : FB_BG_J1, 1, err);
  static const char *const bonds[][3] = {
      {"b_wheel", "Jw", "wheel"},
      {"b_weight", "weight", "Jw"},
      {"b_up", "Jw", "susp"},
      {"b_travel", "arm.2", "Jsp"},
      {"b_spring", "Jsp", "spring"},
      {"b_damper", "Jsp", "damper"},
      {"b_contact", "tire", "Jw"},
      {"b_tire", "tire", "Jt"},
      {"b_tire_spring", "Jt", "tire_spring"},
      {"b_tire_damper", "Jt", "tire_damper"},
  };
  /* The arm's bond: straight from "susp", or through "Jrel". */
  static const char *const plain[][3] = {{"b_arm", "susp", "arm.1"}};
  static const char *const through[][3] = {{"b_arm", "susp", "Jrel"},
                                           {"b_rel", "Jrel", "arm.1"}};
  if (!rc && coupled)
    rc = fb_bg_add_junction(bg, "Jrel", FB_BG_J1, 1, err);
  /* The paper's order of bonds: the arm's after the wheel's first three. */
  if (!rc)
    rc = connect_all(bg, bonds, 3, err);
  if (!rc)
    rc = coupled ? connect_all(bg, through, 2, err) : connect_all(bg, plain, 1, err);
  if (!rc)
    rc = connect_all(bg, bonds + 3, sizeof bonds / sizeof bonds[0] - 3, err);
  /* The stops share the spring's travel, compression positive. */
  if (!rc && fb_stops_any(&c->stops))
    rc = fb_bg_connect(bg, "b_stops", "Jsp", "stops", err);
  if (!rc)
    rc = fb_bg_add_port(bg, "hull", "susp", FB_PORT_OUT, err);
  if (!rc)
    rc = fb_bg_add_port(bg, "road", "tire", FB_PORT_IN, err);
  if (!rc && coupled)
    rc = fb_bg_add_port(bg, "travel", "Jrel", FB_PORT_OUT, err);
  return rc;
}

/* The corner's fragment, with the port "travel" or without. */
static int corner_fragment(const fb_corner_params *c, double gravity, int coupled, fb_bg **out,
                           fb_err *err)
{
  *out = NULL;
  fb_bg *bg = NULL;
  int rc = fb_bg_new("corner", &bg, err);
  if (!rc)
    rc = corner_graph(c, gravity, coupled, bg, err);
  if (rc) {
    fb_bg_free(&bg);
    return rc;
  }
  *out = bg;
  return FB_OK;
}

int fb_vehicle_corner(const fb_corner_params *c, double gravity, fb_bg **out, fb_err *err)
{
  return corner_fragment(c, gravity, 0, out, err);
}

int fb_vehicle_corner_coupled(const fb_corner_params *c, double gravity, fb_bg **out,
                              fb_err *err)
{
  return corner_fragment(c, gravity, 1, out, err);
}

/* An anti-roll bar between two corners' "travel" ports, "left" and
 * "right" (both IN). The 0-junction "twist" forms v_left - v_right, the
 * bar's twist rate at the wheels; the spring and damper on it (half the
 * rates in roll: fb_antiroll_bar) give the force F that "twist" carries,
 * a compression force +F on the left corner's suspension and, through
 * the 1-junction "Jr", -F on the right one's. */
int fb_vehicle_antiroll_bar(const fb_antiroll_bar *b, fb_bg **out, fb_err *err)
{
  *out = NULL;
  fb_bg *bg = NULL;
  int rc = fb_bg_new("antiroll_bar", &bg, err);
  if (!rc)
    rc = vehicle_add_scalar(bg, "spring", FB_BG_C, 0.5 * b->stiffness, err);
  if (!rc)
    rc = vehicle_add_scalar(bg, "damper", FB_BG_R, 0.5 * b->damping, err);
  const char *const junctions[][2] = {{"Jl", "1"}, {"Jr", "1"}, {"twist", "0"}, {"Jbar", "1"}};
  for (size_t i = 0; !rc && i < sizeof junctions / sizeof junctions[0]; ++i)
    rc = fb_bg_add_junction(bg, junctions[i][0],
                            junctions[i][1][0] == '0' ? FB_BG_J0 : FB_BG_J1, 1, err);
  static const char *const bonds[][3] = {
      {"b_left", "Jl", "twist"},      {"b_right", "twist", "Jr"},
      {"b_twist", "twist", "Jbar"},   {"b_spring", "Jbar", "spring"},
      {"b_damper", "Jbar", "damper"},
  };
  if (!rc)
    rc = connect_all(bg, bonds, sizeof bonds / sizeof bonds[0], err);
  if (!rc)
    rc = fb_bg_add_port(bg, "left", "Jl", FB_PORT_IN, err);
  if (!rc)
    rc = fb_bg_add_port(bg, "right", "Jr", FB_PORT_IN, err);
  if (rc) {
    fb_bg_free(&bg);
    return rc;
  }
  *out = bg;
  return FB_OK;
}

/* A bogie's wheel: the wheel's point (1-junction "Jw", its velocity from
 * the beam through port "wheel", IN, and the bond "b_wheel"), its weight,
 * and its tire to the road (port "road", IN) as the corner's model builds
 * it. The wheel's mass is
 * the beam's (it rides rigidly at the beam's end). */
static int bogie_wheel(const fb_corner_params *c, double gravity, fb_bg **out, fb_err *err)
{
  *out = NULL;
  fb_bg *bg = NULL;
  int rc = fb_bg_new("bogie_wheel", &bg, err);
  if (!rc)
    rc = add_constant_effort(bg, "weight", -c->wheel_mass * gravity, err);
  if (!rc)
    rc = add_tire(bg, c, err);
  const char *const junctions[][2] = {{"Jp", "1"}, {"Jw", "1"}, {"tire", "0"}, {"Jt", "1"}};
  for (size_t i = 0; !rc && i < sizeof junctions / sizeof junctions[0]; ++i)
    rc = fb_bg_add_junction(bg, junctions[i][0],
                            junctions[i][1][0] == '0' ? FB_BG_J0 : FB_BG_J1, 1, err);
  static const char *const bonds[][3] = {
      {"b_wheel", "Jp", "Jw"},
      {"b_weight", "weight", "Jw"},
      {"b_contact", "tire", "Jw"},
      {"b_tire", "tire", "Jt"},
      {"b_tire_spring", "Jt", "tire_spring"},
      {"b_tire_damper", "Jt", "tire_damper"},
  };
  if (!rc)
    rc = connect_all(bg, bonds, sizeof bonds / sizeof bonds[0], err);
  if (!rc)
    rc = fb_bg_add_port(bg, "wheel", "Jp", FB_PORT_IN, err);
  if (!rc)
    rc = fb_bg_add_port(bg, "road", "tire", FB_PORT_IN, err);
  if (rc) {
    fb_bg_free(&bg);
    return rc;
  }
  *out = bg;
  return FB_OK;
}

/* The beam with its wheels as one rigid body in (v, w), the pivot's
 * vertical velocity and the beam's pitch rate: a point at x ahead of the
 * pivot moves at v - x w (nose down positive, as the hull's pitch), so each
 * wheel of mass m adds m r r' with r = [1, -x] (kinetic energy
 * 1/2 m (v - x w)^2), to diag(beam mass, beam inertia); and the beam's
 * weight. */
static int add_beam(fb_bg *bg, const fb_bogie_params *p, double mf, double mr, double gravity,
                    fb_err *err)
{
  const double m22[4] = {p->beam_mass + mf + mr, -mf * p->a + mr * p->b, -mf * p->a + mr * p->b,
                         p->beam_inertia + mf * p->a * p->a + mr * p->b * p->b};
  fb_mat *m = NULL;
  const size_t two = 2;
  int rc = fb_mat_new_dense_rowmajor(2, 2, m22, &m, err);
  if (!rc)
    rc = fb_bg_add_field(bg, "beam", FB_BG_I, 1, &two, &m, err);
  char bounce[96], pitch[96];
  snprintf(bounce, sizeof bounce, "bogie bounce %s", p->name ? p->name : "");
  snprintf(pitch, sizeof pitch, "bogie pitch %s", p->name ? p->name : "");
  const char *const motions[2] = {bounce, pitch};
  if (!rc)
    rc = fb_bg_set_labels(bg, "beam", motions, err);
  /* Rows [1, -x] from (v, w) to the pivot's (x = 0) and the wheels'
   * vertical velocities, and [0, 1] to the pitch rate alone. */
  const double rows[4][2] = {{1.0, 0.0}, {1.0, -p->a}, {1.0, p->b}, {0.0, 1.0}};
  static const char *const names[4] = {"to_pivot", "to_front", "to_rear", "to_pitch"};
  for (size_t i = 0; !rc && i < 4; ++i) {
    fb_mat *t = NULL;
    rc = fb_mat_new_dense_rowmajor(1, 2, rows[i], &t, err);
    if (!rc)
      rc = fb_bg_add_mtf(bg, names[i], &t, err);
  }
  /* The beam's weight, at the pivot: a generalised force on (v, w). */
  fb_tfun *w[2] = {NULL, NULL};
  if (!rc)
    rc = fb_tfun_new_const(-p->beam_mass * gravity, &w[0], err);
  if (!rc)
    rc = fb_tfun_new_const(0.0, &w[1], err);
  if (!rc)
    rc = fb_bg_add_source(bg, "beam_weight", FB_BG_SE, 2, w, err);
  fb_tfun_free(&w[0]);
  fb_tfun_free(&w[1]);
  return rc;
}

/* The beam (1-junction "Jb" of its two motions), its pivot on the spring
 * and damper of the 0-junction "susp" (as a corner's: pivot velocity in,
 * hull out, spring's 1-junction out, common effort the spring-damper
 * force), and the two wheels as adopted fragments "front" and "rear". */
static int bogie_graph(const fb_bogie_params *p, const fb_corner_params *front,
                       const fb_corner_params *rear, double gravity, fb_bg *bg, fb_err *err)
{
  int rc = add_beam(bg, p, front->wheel_mass, rear->wheel_mass, gravity, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "Jb", FB_BG_J1, 2, err);
  if (!rc)
    rc = vehicle_add_scalar(bg, "spring", FB_BG_C, p->spring_k, err);
  if (!rc)
    rc = vehicle_add_scalar(bg, "damper", FB_BG_R, p->damper_c, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "susp", FB_BG_J0, 1, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "Jsp", FB_BG_J1, 1, err);
  /* The pitch rate's own scalar bond "b_pitch", to measure (its effort is
   * zero: nothing acts through it). */
  if (!rc)
    rc = fb_bg_add_junction(bg, "Jpitch", FB_BG_J1, 1, err);
  const fb_corner_params *wheel[2] = {front, rear};
  static const char *const inst[2] = {"front", "rear"};
  for (size_t i = 0; !rc && i < 2; ++i) {
    fb_bg *frag = NULL;
    rc = bogie_wheel(wheel[i], gravity, &frag, err);
    if (!rc)
      rc = fb_bg_adopt(bg, &frag, inst[i], err);
    fb_bg_free(&frag);
  }
  static const char *const bonds[][3] = {
      {"b_beam", "Jb", "beam"},
      {"b_beam_weight", "beam_weight", "Jb"},
      {"b_pivot", "Jb", "to_pivot.1"},
      {"b_up", "to_pivot.2", "susp"},
      {"b_travel", "susp", "Jsp"},
      {"b_spring", "Jsp", "spring"},
      {"b_damper", "Jsp", "damper"},
      {"b_front_arm", "Jb", "to_front.1"},
      {"b_front", "to_front.2", "front.wheel"},
      {"b_rear_arm", "Jb", "to_rear.1"},
      {"b_rear", "to_rear.2", "rear.wheel"},
      {"b_pitch_arm", "Jb", "to_pitch.1"},
      {"b_pitch", "to_pitch.2", "Jpitch"},
  };
  if (!rc)
    rc = connect_all(bg, bonds, sizeof bonds / sizeof bonds[0], err);
  if (!rc)
    rc = fb_bg_add_port(bg, "hull", "susp", FB_PORT_OUT, err);
  if (!rc)
    rc = fb_bg_add_port(bg, "road_front", "front.road", FB_PORT_IN, err);
  if (!rc)
    rc = fb_bg_add_port(bg, "road_rear", "rear.road", FB_PORT_IN, err);
  return rc;
}

int fb_vehicle_bogie(const fb_bogie_params *p, const fb_corner_params *front,
                     const fb_corner_params *rear, double gravity, fb_bg **out, fb_err *err)
{
  *out = NULL;
  fb_bg *bg = NULL;
  int rc = fb_bg_new("bogie", &bg, err);
  if (!rc)
    rc = bogie_graph(p, front, rear, gravity, bg, err);
  if (rc) {
    fb_bg_free(&bg);
    return rc;
  }
  *out = bg;
  return FB_OK;
}

/* The scenario's road, as its type makes it. */
static int scenario_road(const fb_scenario *s, fb_road **out, fb_err *err)
{
  if (!s->road_type)
    return fb_err_set(err, FB_EINVAL, "the description has no road"),
           fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, road_type)), FB_EINVAL;
  const fb_road_layout layout = fb_scenario_road_layout(s);
  return vehicle_road_error(s->road_type->ops->make(s->road.bytes, &layout, out, err), err);
}

/* The stretch of road the wheels cover in a run, [*lo, *hi]: from the
 * rearmost wheel's start to the foremost's position at t_end, a metre
 * beyond at either end (and the envelope's reach, which the enveloped
 * road adds itself). */
static void road_covered(const fb_scenario *s, double *lo, double *hi)
{
  *lo = INFINITY;
  *hi = -INFINITY;
  for (size_t c = 0; c < s->ncorners; ++c) {
    const double s0 = fb_scenario_wheel_start(s, (int)c);
    *lo = fmin(*lo, s0 - 1.0);
    *hi = fmax(*hi, s0 + s->speed * s->t_end + 1.0);
  }
}

/* 1 if corners a and b envelop the road alike: one model, one block, one
 * radius and one static deflection (the same load), so one effective road
 * serves both. */
static int same_envelope(const fb_corner_params *a, const fb_corner_params *b)
{
  const fb_envelope_model *m = fb_corner_envelope_model(a);
  return m == fb_corner_envelope_model(b) &&
         !memcmp(a->envelope.bytes, b->envelope.bytes, m->params_size) &&
         a->tire_radius == b->tire_radius && a->tire_k == b->tire_k;
}

/* The road under a corner's tire: the road it reads, and the one it
 * owns when that is its own effective road (NULL when the road is the
 * scenario's or an earlier corner's, borrowed). */
typedef struct corner_road {
  const fb_road *road;
  fb_road *owned;
} corner_road;

/* The road under each corner's tire (cr[0 .. s->ncorners)): the road
 * itself under a point contact, else its effective road over the
 * stretch the run covers, made once for corners that envelop it
 * alike. */
static int corner_roads(const fb_scenario *s, const fb_road *road, corner_road *cr, fb_err *err)
{
  double lo, hi;
  road_covered(s, &lo, &hi);
  int rc = FB_OK;
  for (size_t c = 0; !rc && c < s->ncorners; ++c) {
    const fb_corner_params loaded = vehicle_corner_loaded(s, c);
    const fb_envelope_model *m = fb_corner_envelope_model(&loaded);
    const fb_envelope_context ctx = fb_corner_envelope_context(&loaded);
    cr[c].road = road;
    if (!(m->ops->reach(loaded.envelope.bytes, &ctx) > 0.0))
      continue;
    for (size_t k = 0; k < c && cr[c].road == road; ++k)
      if (cr[k].owned && same_envelope(&s->corner[k], &s->corner[c]))
        cr[c].road = cr[k].road;
    if (cr[c].road != road)
      continue;
    /* The description's check has held the model's rules already. */
    rc = fb_envelope_road_new(road, m, loaded.envelope.bytes, &ctx, lo, hi, &cr[c].owned, err);
    cr[c].road = cr[c].owned;
  }
  return rc;
}

/* Refuses a road that corner's wheel cannot follow as a point: one with
 * edges on its track (fb_road_edges: a height jump or an infinite slope,
 * where its road velocity would be a Dirac or infinite), at the road's
 * key, in the road type's words (its edge_hint). */
static int road_followable(const fb_scenario *s, const fb_road *road, size_t corner,
                           fb_err *err)
{
  const int track = s->corner[corner].y > 0.0 ? FB_ROAD_LEFT : FB_ROAD_RIGHT;
  double at = 0.0;
  if (!fb_road_edges(road, track, &at, 1))
    return FB_OK;
  const char *hint =
      s->road_type->ops->edge_hint ? s->road_type->ops->edge_hint(s->road.bytes) : NULL;
  if (!hint)
    hint = "the road's vertical face or infinite slope cannot be followed by a point-contact "
           "tire: give the tires an envelope";
  fb_err_set(err, FB_EINVAL, "%s (the %s wheel meets it at s = %.6g m on the %s track)", hint,
             s->corner[corner].name, at, track == FB_ROAD_LEFT ? "left" : "right");
  return fb_err_set_part(err, FB_PART_ROAD, 0, FB_ERR_NO_ELEMENT, ""), FB_EINVAL;
}

int fb_vehicle_road(const fb_scenario *s, fb_bg **out, fb_err *err)
{
  *out = NULL;
  fb_bg *bg = NULL;
  fb_road *road = NULL;
  corner_road *cr = calloc(s->ncorners + 1, sizeof *cr);
  int rc = cr ? scenario_road(s, &road, err)
              : fb_err_set(err, FB_ENOMEM, "out of memory for the corners' roads");
  if (!rc)
    rc = corner_roads(s, road, cr, err);
  if (!rc)
    rc = fb_bg_new("road", &bg, err);
  /* Left wheels (y > 0) on the left track; each source is the road's
   * vertical velocity under its wheel, with its kinks as breakpoints. */
  for (size_t c = 0; !rc && c < s->ncorners; ++c) {
    const int track = s->corner[c].y > 0.0 ? FB_ROAD_LEFT : FB_ROAD_RIGHT;
    fb_tfun *f = NULL;
    char *name = NULL;
    /* An enveloped road has no edges: only a point contact can be refused. */
    rc = road_followable(s, cr[c].road, c, err);
    if (!rc && !(name = fb_strdup_printf("v_%s", s->corner[c].name)))
      rc = fb_err_set(err, FB_ENOMEM, "out of memory");
    if (!rc)
      rc = fb_road_wheel_velocity(cr[c].road, track, s->speed,
                                  fb_scenario_wheel_start(s, (int)c), &f, err);
    if (!rc)
      rc = fb_bg_add_source(bg, name, FB_BG_SF, 1, &f, err);
    if (!rc)
      rc = fb_bg_add_port(bg, s->corner[c].name, name, FB_PORT_OUT, err);
    free(name);
  }
  for (size_t c = 0; cr && c < s->ncorners; ++c)
    fb_road_free(&cr[c].owned);
  free(cr);
  fb_road_free(&road);
  if (rc) {
    fb_bg_free(&bg);
    return rc;
  }
  *out = bg;
  return FB_OK;
}

int fb_vehicle_load(const fb_scenario *s, fb_bg **out, fb_err *err)
{
  *out = NULL;
  fb_bg *bg = NULL;
  /* NOLINTNEXTLINE(bugprone-sizeof-expression): an array of pointers, sized by its element */
  fb_tfun **f = calloc(s->nload, sizeof *f);
  int rc = f ? fb_bg_new("load", &bg, err) : fb_err_set(err, FB_ENOMEM, "out of memory");
  const double each = -s->total_weight / (double)s->nload;
  for (size_t k = 0; !rc && k < s->nload; ++k)
    rc = fb_tfun_new_const(each, &f[k], err);
  if (!rc)
    rc = fb_bg_add_source(bg, "weights", FB_BG_SE, s->nload, f, err);
  if (!rc)
    rc = fb_bg_add_port(bg, "load", "weights", FB_PORT_OUT, err);
  for (size_t k = 0; f && k < s->nload; ++k)
    fb_tfun_free(&f[k]);
  free(f);
  if (rc) {
    fb_bg_free(&bg);
    return rc;
  }
  *out = bg;
  return FB_OK;
}

/* ---- What the fragments offer to measure (outputs.c, motion.c): each
 * signal's probe on one of the fragment's own bonds or elements, named
 * as the fragment above names them. */

static int corner_has_stops(const fb_corner_params *c)
{
  return fb_stops_any(&c->stops);
}

/* The corner's (fb_vehicle_corner). Compressions and forces pushing the
 * parts apart positive, powers into the dissipating element. */
static const vehicle_signal corner_signals[] = {
    {"tire_force", FB_PROBE_EFFORT, "b_tire", 0, 0, NULL, NULL},
    {"tire_defl", FB_PROBE_STATE, "tire_spring", 0, 0, NULL, NULL},
    {"tire_power", FB_PROBE_POWER, "b_tire_damper", 0, 0, NULL, NULL},
    {"spring_defl", FB_PROBE_STATE, "spring", 0, 0, NULL, NULL},
    {"spring_force", FB_PROBE_EFFORT, "b_spring", 0, 0, NULL, NULL},
    {"shock_force", FB_PROBE_EFFORT, "b_damper", 0, 0, NULL, NULL},
    {"shock_power", FB_PROBE_POWER, "b_damper", 0, 0, NULL, NULL},
    {"stop_force", FB_PROBE_EFFORT, "b_stops", 0, 0, corner_has_stops,
     "stop (bump_stop or rebound_stop)"},
    {"wheel_travel", FB_PROBE_FLOW, "b_arm", 1, 0, NULL, NULL},
    {VEHICLE_SIGNAL_MOTION, FB_PROBE_FLOW, "b_wheel", 1, 0, NULL, NULL},
};

/* A bogie's wheel's (bogie_wheel, in fb_vehicle_bogie): its tire's, and
 * its motion. */
static const vehicle_signal bogie_wheel_signals[] = {
    {"tire_force", FB_PROBE_EFFORT, "b_tire", 0, 0, NULL, NULL},
    {"tire_defl", FB_PROBE_STATE, "tire_spring", 0, 0, NULL, NULL},
    {"tire_power", FB_PROBE_POWER, "b_tire_damper", 0, 0, NULL, NULL},
    {VEHICLE_SIGNAL_MOTION, FB_PROBE_FLOW, "b_wheel", 1, 0, NULL, NULL},
};

/* The bogie's (fb_vehicle_bogie): its beam's pitch and its pivot's
 * spring force. */
static const vehicle_signal bogie_signals[] = {
    {"beam_pitch", FB_PROBE_FLOW, "b_pitch", 1, 0, NULL, NULL},
    {"pivot_force", FB_PROBE_EFFORT, "b_spring", 0, 0, NULL, NULL},
};

/* The mounted body's (fb_vehicle_mount): its acceleration is the effort
 * on its mass over the mass (the paper's gain block 1/m on e7). */
static const vehicle_signal mount_signals[] = {
    {"acc", FB_PROBE_EFFORT, "b_mass", 0, 1, NULL, NULL},
    {"travel", FB_PROBE_STATE, "spring", 0, 0, NULL, NULL},
    {"force", FB_PROBE_EFFORT, "b_up", 0, 0, NULL, NULL},
    {VEHICLE_SIGNAL_MOTION, FB_PROBE_FLOW, "b_mass", 1, 0, NULL, NULL},
};

static const vehicle_signal *signal_in(const vehicle_signal *list, size_t n, const char *signal)
{
  for (size_t i = 0; signal && i < n; ++i)
    if (!strcmp(list[i].signal, signal))
      return &list[i];
  return NULL;
}

const vehicle_signal *vehicle_corner_signal(const fb_scenario *s, size_t c, const char *signal)
{
  if (vehicle_corner_bogie(s, c, NULL) < 0)
    return vehicle_fragment_signal(FB_OUTPUT_OF_CORNER, signal);
  return signal_in(bogie_wheel_signals,
                   sizeof bogie_wheel_signals / sizeof bogie_wheel_signals[0], signal);
}

const vehicle_signal *vehicle_fragment_signal(fb_output_subject subject, const char *signal)
{
  switch (subject) {
  case FB_OUTPUT_OF_CORNER:
    return signal_in(corner_signals, sizeof corner_signals / sizeof corner_signals[0], signal);
  case FB_OUTPUT_OF_MOUNT:
    return signal_in(mount_signals, sizeof mount_signals / sizeof mount_signals[0], signal);
  case FB_OUTPUT_OF_BOGIE:
    return signal_in(bogie_signals, sizeof bogie_signals / sizeof bogie_signals[0], signal);
  default: return NULL;
  }
}
