/* SPDX-License-Identifier: BSD-3-Clause */
/* A mounted rigid body in six degrees of freedom as a bond-graph fragment
 * (fb_vehicle_body), and the 6-dimensional ports where a parent (the
 * rigid hull or another body) carries a bushing.
 *
 * Every 6-vector is (v_x, v_y, v_z, omega_x, omega_y, omega_z) on the
 * flow side and (F_x, F_y, F_z, M_x, M_y, M_z) on the effort side, in
 * the vehicle axes (ISO 8855: x forward, y left, z up). The body's
 * generalised velocity is its centre of mass's; a point at r from it
 * moves with T(r) of vehicle_rigid_transport (small motion), and its
 * force and moment there act on the centre of mass as T(r)' (the
 * transformer's effort relation, which keeps power: Karnopp, Margolis &
 * Rosenberg, "System Dynamics", 5th ed., sec. 9.2, multiport
 * transformers for rigid-body kinematics). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* A 6x6 field (one port of dimension 6) with the row-major law m. */
static int add_field6(fb_bg *bg, const char *name, fb_bg_kind kind, const double *m,
                      fb_err *err)
{
  fb_mat *law = NULL;
  const size_t six = 6;
  const int rc = fb_mat_new_dense_rowmajor(6, 6, m, &law, err);
  return rc ? rc : fb_bg_add_field(bg, name, kind, 1, &six, &law, err);
}

/* The 6x6 transformer T(r) named name. */
static int add_transport(fb_bg *bg, const char *name, const double *r, fb_err *err)
{
  double t[36];
  vehicle_rigid_transport(r, t);
  fb_mat *m = NULL;
  const int rc = fb_mat_new_dense_rowmajor(6, 6, t, &m, err);
  return rc ? rc : fb_bg_add_mtf(bg, name, &m, err);
}

int vehicle_wire_bushing_port(fb_bg *bg, const char *junction, size_t k, fb_err *err)
{
  char mtf[48], port[48], b_in[48], b_out[48], from[64], to[64];
  snprintf(mtf, sizeof mtf, "to_bushing_%zu", k);
  snprintf(port, sizeof port, "bushing_%zu", k);
  snprintf(b_in, sizeof b_in, "b_to_bushing_%zu", k);
  snprintf(b_out, sizeof b_out, "b_bushing_%zu", k);
  snprintf(to, sizeof to, "%s.1", mtf);
  snprintf(from, sizeof from, "%s.2", mtf);
  int rc = fb_bg_add_junction(bg, port, FB_BG_J1, 6, err);
  if (!rc)
    rc = fb_bg_connect(bg, b_in, junction, to, err);
  if (!rc)
    rc = fb_bg_connect(bg, b_out, from, port, err);
  if (!rc)
    rc = fb_bg_add_port(bg, port, port, FB_PORT_IN, err);
  return rc;
}

int vehicle_add_bushing_port(fb_bg *bg, const char *junction, size_t k, const double *r,
                             fb_err *err)
{
  char mtf[48];
  snprintf(mtf, sizeof mtf, "to_bushing_%zu", k);
  const int rc = add_transport(bg, mtf, r, err);
  return rc ? rc : vehicle_wire_bushing_port(bg, junction, k, err);
}

/* The body's inertia at its centre of mass: m I3 and its tensor. */
void vehicle_body_inertia6(const fb_body *b, double *m)
{
  double j[9];
  vehicle_body_inertia(b, j);
  memset(m, 0, 36 * sizeof *m);
  for (int i = 0; i < 3; ++i) {
    m[7 * i] = b->mass;
    for (int c = 0; c < 3; ++c)
      m[6 * (3 + i) + 3 + c] = j[3 * i + c];
  }
}

/* The body's mass and its weight on the 1-junction "J". */
static int add_inertia(fb_bg *bg, const fb_body *b, double gravity, fb_err *err)
{
  double m[36];
  vehicle_body_inertia6(b, m);
  int rc = add_field6(bg, "inertia", FB_BG_I, m, err);
  /* The motions a mode of the vehicle may move: the body's own. */
  static const char *const axes[6] = {"x", "y", "z", "roll", "pitch", "yaw"};
  char text[6][96];
  const char *labels[6];
  for (int i = 0; i < 6; ++i) {
    snprintf(text[i], sizeof text[i], "%s %s", b->name, axes[i]);
    labels[i] = text[i];
  }
  if (!rc)
    rc = fb_bg_set_labels(bg, "inertia", labels, err);
  fb_tfun *w[6] = {NULL};
  for (int i = 0; !rc && i < 6; ++i)
    rc = fb_tfun_new_const(i == 2 ? -b->mass * gravity : 0.0, &w[i], err);
  if (!rc)
    rc = fb_bg_add_source(bg, "weight", FB_BG_SE, 6, w, err);
  for (int i = 0; i < 6; ++i)
    fb_tfun_free(&w[i]);
  if (!rc)
    rc = fb_bg_add_junction(bg, "J", FB_BG_J1, 6, err);
  if (!rc)
    rc = fb_bg_connect(bg, "b_inertia", "J", "inertia", err);
  if (!rc)
    rc = fb_bg_connect(bg, "b_weight", "weight", "J", err);
  return rc;
}

/* Bushing j of b: the body's point through T(r) into the 0-junction
 * "rel_<j>", whose port "parent_<j>" (OUT) meets the parent's point; the
 * relative motion, parent minus body (a compression, as a mount's),
 * drives the 6x6 spring and damper on the 1-junction "Jb_<j>". Their
 * effort on the body is K d + C d' with d that relative motion. */
static int add_bushing(fb_bg *bg, const fb_body *b, size_t j, fb_err *err)
{
  const fb_bushing *u = &b->bushing[j];
  const double r[3] = {u->x - b->x, u->y - b->y, u->z - b->z};
  char mtf[32], rel[32], jb[32], spring[32], damper[32], port[32];
  snprintf(mtf, sizeof mtf, "to_point_%zu", j);
  snprintf(rel, sizeof rel, "rel_%zu", j);
  snprintf(jb, sizeof jb, "Jb_%zu", j);
  snprintf(spring, sizeof spring, "spring_%zu", j);
  snprintf(damper, sizeof damper, "damper_%zu", j);
  snprintf(port, sizeof port, "parent_%zu", j);
  int rc = add_transport(bg, mtf, r, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, rel, FB_BG_J0, 6, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, jb, FB_BG_J1, 6, err);
  if (!rc)
    rc = add_field6(bg, spring, FB_BG_C, u->k, err);
  if (!rc)
    rc = add_field6(bg, damper, FB_BG_R, u->c, err);
  char names[5][48], ends[5][2][48];
  snprintf(names[0], 48, "b_to_point_%zu", j);
  snprintf(ends[0][0], 48, "J");
  snprintf(ends[0][1], 48, "%s.1", mtf);
  snprintf(names[1], 48, "b_point_%zu", j);
  snprintf(ends[1][0], 48, "%s.2", mtf);
  snprintf(ends[1][1], 48, "%s", rel);
  snprintf(names[2], 48, "b_rel_%zu", j);
  snprintf(ends[2][0], 48, "%s", jb);
  snprintf(ends[2][1], 48, "%s", rel);
  snprintf(names[3], 48, "b_spring_%zu", j);
  snprintf(ends[3][0], 48, "%s", jb);
  snprintf(ends[3][1], 48, "%s", spring);
  snprintf(names[4], 48, "b_damper_%zu", j);
  snprintf(ends[4][0], 48, "%s", jb);
  snprintf(ends[4][1], 48, "%s", damper);
  for (int i = 0; !rc && i < 5; ++i)
    rc = fb_bg_connect(bg, names[i], ends[i][0], ends[i][1], err);
  if (!rc)
    rc = fb_bg_add_port(bg, port, rel, FB_PORT_OUT, err);
  return rc;
}

int fb_vehicle_body(const fb_scenario *s, size_t i, fb_bg **out, fb_err *err)
{
  *out = NULL;
  if (i >= s->nbodies)
    return fb_err_set(err, FB_EINVAL, "no body %zu (the vehicle has %zu)", i, s->nbodies);
  const fb_body *b = &s->body[i];
  fb_bg *bg = NULL;
  int rc = fb_bg_new("body", &bg, err);
  if (!rc)
    rc = add_inertia(bg, b, s->gravity, err);
  for (size_t j = 0; !rc && j < b->nbushings; ++j)
    rc = add_bushing(bg, b, j, err);
  /* The bushings of the bodies mounted on this one. */
  const size_t nk = fb_scenario_nbushings(s);
  for (size_t k = 0; !rc && k < nk; ++k) {
    size_t c = 0, j = 0;
    fb_scenario_bushing_at(s, k, &c, &j);
    const fb_body *child = &s->body[c];
    if (!child->parent || strcmp(child->parent, b->name) != 0)
      continue;
    const fb_bushing *u = &child->bushing[j];
    const double r[3] = {u->x - b->x, u->y - b->y, u->z - b->z};
    rc = vehicle_add_bushing_port(bg, "J", k, r, err);
  }
  if (rc) {
    fb_bg_free(&bg);
    fb_err_prefix(err, "body %s: ", b->name);
    return rc;
  }
  *out = bg;
  return FB_OK;
}

/* ---- What the body offers to measure (outputs.c): its centre of mass's
 * acceleration or displacement along or about one axis. */
typedef struct body_signal {
  const char *signal;
  int axis;  /* 0..5: x, y, z, roll, pitch, yaw */
  int accel; /* 1: acceleration, M^-1 times the effort on the inertia; 0:
                displacement, the integrated flow */
} body_signal;

static const body_signal body_signals[] = {
    {"body_acc_x", 0, 1},     {"body_acc_y", 1, 1},      {"body_acc_z", 2, 1},
    {"body_acc_roll", 3, 1},  {"body_acc_pitch", 4, 1},  {"body_acc_yaw", 5, 1},
    {"body_disp_x", 0, 0},    {"body_disp_y", 1, 0},     {"body_disp_z", 2, 0},
    {"body_disp_roll", 3, 0}, {"body_disp_pitch", 4, 0}, {"body_disp_yaw", 5, 0},
};

/* Row a of the inverse of b's 6x6 inertia: 1/m along a translation, the
 * inverse tensor's row about a rotation (adjugate over determinant). */
static void inverse_inertia_row(const fb_body *b, int a, double *w)
{
  memset(w, 0, 6 * sizeof *w);
  if (a < 3) {
    w[a] = 1.0 / b->mass;
    return;
  }
  double j[9];
  vehicle_body_inertia(b, j);
  const double det = j[0] * (j[4] * j[8] - j[5] * j[7]) - j[1] * (j[3] * j[8] - j[5] * j[6]) +
                     j[2] * (j[3] * j[7] - j[4] * j[6]);
  const int r = a - 3, r1 = (r + 1) % 3, r2 = (r + 2) % 3;
  for (int c = 0; c < 3; ++c) { /* inverse[r][c] = cofactor[c][r] / det */
    const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
    w[3 + c] = (j[3 * c1 + r1] * j[3 * c2 + r2] - j[3 * c1 + r2] * j[3 * c2 + r1]) / det;
  }
}

int vehicle_body_probe(const fb_scenario *s, size_t index, fb_probe_spec *p, fb_err *err)
{
  const fb_output_spec *o = &s->output[index];
  const long b = fb_scenario_body_find(s, o->of);
  const body_signal *how = NULL;
  for (size_t i = 0; i < sizeof body_signals / sizeof body_signals[0]; ++i)
    if (o->signal && !strcmp(body_signals[i].signal, o->signal))
      how = &body_signals[i];
  if (b < 0 || !how) {
    fb_err_set(err, FB_EINVAL, "no rigid body '%s' measuring %s", o->of ? o->of : "",
               o->signal ? o->signal : "");
    return fb_err_set_part(err, FB_PART_AT(FB_PART_OUTPUT, index, of)), FB_EINVAL;
  }
  double *w = malloc(6 * sizeof *w);
  if (!w)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  if (how->accel)
    inverse_inertia_row(&s->body[b], how->axis, w);
  else {
    memset(w, 0, 6 * sizeof *w);
    w[how->axis] = 1.0;
  }
  p->kind = how->accel ? FB_PROBE_EFFORT : FB_PROBE_FLOW;
  p->integrate = !how->accel;
  p->weights = w;
  p->nweights = 6;
  p->target = fb_strdup_printf("%s.b_inertia", s->body[b].name);
  return FB_OK;
}
