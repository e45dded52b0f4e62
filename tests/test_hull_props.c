/* SPDX-License-Identifier: BSD-3-Clause */
/* One hull for both systems (fb_vehicle_hull_complete): System 1's mass,
 * inertias and centre of mass come from the finite-element mesh System 2
 * uses. Checked against the mesh's own mass properties
 * (fb_fem_mass_properties over the assembled mass matrix), computed here
 * independently of the loader. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "core/textfile.h"

/* text with the first `from` replaced by `to` (new). */
static char *replaced(const char *text, const char *from, const char *to)
{
  const char *at = strstr(text, from);
  if (!at)
    return NULL;
  const size_t head = (size_t)(at - text), nto = strlen(to);
  char *out = malloc(strlen(text) - strlen(from) + nto + 1);
  if (!out)
    return NULL;
  memcpy(out, text, head);
  memcpy(out + head, to, nto);
  strcpy(out + head + nto, at + strlen(from));
  return out;
}

/* The mesh's mass, centre of mass and inertia tensor, from the scenario's
 * finite-element hull. */
static int mesh_props(const fb_scenario *s, double *mass, double *cg, double *inertia)
{
  fb_err err;
  fb_fe_hull *h = NULL;
  fb_mat *M = NULL;
  int rc = fb_vehicle_fe_hull(s, &h, &err);
  if (!rc)
    rc = fb_fem_assemble(h->mesh, &h->props, h->mass_kind, NULL, &M, &err);
  if (!rc)
    rc = fb_fem_mass_properties(h->mesh, M, mass, cg, inertia, &err);
  if (rc)
    fprintf(stderr, "mesh properties: %s\n", err.msg);
  fb_mat_free(&M);
  fb_fe_hull_free(&h);
  return rc;
}

static fb_scenario *load(const char *text, fb_err *err)
{
  fb_scenario *s = NULL;
  fb_err_clear(err);
  if (fb_scenario_load_string(text, strlen(text), "hull.yaml", &s, err) != FB_OK)
    return NULL;
  return s;
}

/* The paper's typed values stand: they agree with the mesh fitted to
 * them (within 6e-6, far inside the 0.5 % allowed). */
static void test_typed_agree(const char *text)
{
  fb_err err;
  fb_scenario *s = load(text, &err);
  CHECK(s != NULL);
  double m = 0, cg[3], J[9];
  if (s && mesh_props(s, &m, cg, J) == FB_OK) {
    CHECK(s->hull_mass_given && s->hull_mass == 4041.72);
    CHECK(fabs(m - s->hull_mass) <= 6e-6 * m);
    CHECK(fabs(J[0] - s->hull_ixx) <= 6e-6 * J[0] && fabs(J[4] - s->hull_iyy) <= 6e-6 * J[4]);
  }
  fb_scenario_free(&s);
}

/* Without typed values, System 1 takes the mesh's. */
static void test_from_mesh(const char *text)
{
  char *a = replaced(text, "  mass: 4041.72", "  # mass");
  char *b = a ? replaced(a, "  Ixx: 4173.49", "  # Ixx") : NULL;
  char *c = b ? replaced(b, "  Iyy: 15175.96", "  # Iyy") : NULL;
  CHECK(c != NULL);
  fb_err err;
  fb_scenario *s = c ? load(c, &err) : NULL;
  CHECK(s != NULL);
  if (!s && c)
    fprintf(stderr, "from mesh: %s\n", err.msg);
  double m = 0, cg[3], J[9];
  if (s && mesh_props(s, &m, cg, J) == FB_OK) {
    CHECK(!s->hull_mass_given);
    /* The loader sums the elements' kinetic energies of rigid motions
     * (fb_fem_mesh_mass_properties), these come from the assembled M: the
     * same sums in another order, 1e-12 relative. */
    CHECK_NEAR(s->hull_mass, m, 1e-12 * m);
    CHECK_NEAR(s->hull_ixx, J[0], 1e-12 * J[0]);
    CHECK_NEAR(s->hull_iyy, J[4], 1e-12 * J[4]);
    fprintf(stderr, "from the mesh: %.9g kg, Ixx %.9g, Iyy %.9g kg m^2\n", m, J[0], J[4]);
  }
  fb_scenario_free(&s);
  free(a);
  free(b);
  free(c);
}

/* A thicker hull keeps the typed 4041.72 kg no more: refused with both
 * values, at hull.mass. 9.5 mm plates weigh 9.5 / 8.5 as much. */
static void test_typed_disagree(const char *text)
{
  char *t = replaced(text, "thickness: 0.0085", "thickness: 0.0095");
  CHECK(t != NULL);
  fb_err err;
  fb_scenario *s = t ? load(t, &err) : NULL;
  CHECK(s == NULL && err.code == FB_EINVAL);
  CHECK(!strcmp(err.key, "hull.mass") && err.line == 17);
  const double mesh = 4041.72 * 9.5 / 8.5;
  char want[64];
  snprintf(want, sizeof want, "%.6g kg", mesh);
  CHECK(strstr(err.msg, "4041.72 kg") != NULL && strstr(err.msg, want) != NULL);
  if (!strstr(err.msg, want))
    fprintf(stderr, "  wanted %s in: %s\n", want, err.msg);
  fb_scenario_free(&s);
  free(t);
}

/* A lumped payload heavier than nothing: with the hull's mass from the
 * mesh (4041.72 kg within 6e-6), 30000 N / 9.81 = 3058 kg leaves none,
 * refused at load.payload (line 59) once the mesh is built. */
static void test_lumped_from_mesh(const char *text)
{
  char *a = replaced(text, "  mass: 4041.72", "  # mass");
  char *b = a ? replaced(a, "  Ixx: 4173.49", "  # Ixx") : NULL;
  char *c = b ? replaced(b, "  Iyy: 15175.96", "  # Iyy") : NULL;
  char *d = c ? replaced(c, "total_weight: 117720", "total_weight: 30000") : NULL;
  char *e = d ? replaced(d, "payload: weight-only", "payload: lumped") : NULL;
  CHECK(e != NULL);
  fb_err err;
  fb_scenario *s = e ? load(e, &err) : NULL;
  CHECK(s == NULL && err.code == FB_EINVAL && !strcmp(err.key, "load.payload"));
  CHECK(strstr(err.msg, "hull.yaml:59:") == err.msg);
  CHECK(strstr(err.msg, "3058.103976 kg) > the hull's finite-element mesh (4041.7") != NULL);
  if (!strstr(err.msg, "finite-element mesh"))
    fprintf(stderr, "lumped from mesh: %s\n", err.msg);
  fb_scenario_free(&s);
  free(a);
  free(b);
  free(c);
  free(d);
  free(e);
}

/* Positions in a declared frame (the truck: origin at its front axle)
 * are moved to the mesh's centre of mass, which then sits at the
 * origin of the mesh System 2 builds. */
static void test_frame(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load("../examples/truck4x4.yaml", &s, &err) == FB_OK);
  if (!s) {
    fprintf(stderr, "truck: %s\n", err.msg);
    return;
  }
  double m = 0, cg[3], J[9];
  CHECK(mesh_props(s, &m, cg, J) == FB_OK);
  /* The mesh is centred on its centre of mass to round-off of its 6 m. */
  CHECK(fabs(cg[0]) < 1e-9 && fabs(cg[1]) < 1e-9);
  CHECK(s->hull_cg_x < 0.0 && s->hull_cg_x > -3.4);
  /* The front axle is at x = 0 in the file. */
  CHECK(fabs(s->corner[0].x + s->hull_cg_x) < 1e-12);
  CHECK_NEAR(s->hull_mass, m, 1e-12 * m);
  fb_scenario_free(&s);
}

/* A hull point's `at` is in the file's frame as every position: moved
 * with the frame (the truck's front axle, x = 0 in the file, at
 * -hull_cg_x from the centre of mass; its floor, z = 0 in the file, the
 * mesh's lowest nodes inside); on the mesh, or refused at its key when
 * the same point is 0.3 m above the floor (0.15 m from the side wall). */
static void test_frame_point(void)
{
  fb_err err;
  char *text = NULL;
  size_t len = 0;
  CHECK(fb_read_file("../examples/truck4x4.yaml", &text, &len, NULL) == FB_OK);
  fb_scenario *s = NULL;
  CHECK(text && fb_scenario_load_string(text, len, "truck.yaml", &s, &err) == FB_OK);
  if (!s) {
    free(text);
    return;
  }
  double floor = INFINITY;
  for (size_t i = 0; i < fb_mesh_nnodes(s->hull_source_mesh); ++i)
    floor = fmin(floor, fb_mesh_node_xyz(s->hull_source_mesh, i)[2]);
  const double cg_x = s->hull_cg_x;
  fb_scenario_free(&s);
  for (int above = 0; above < 2; ++above) {
    char line[160];
    snprintf(line, sizeof line,
             "outputs:\n  - {signal: hull_displacement, at: [0, 0.95, %.1f], direction: z}\n",
             0.3 * above);
    char *t = replaced(text, "outputs:\n", line);
    CHECK(t != NULL);
    s = NULL;
    const int rc = t ? fb_scenario_load_string(t, strlen(t), "truck.yaml", &s, &err) : -1;
    CHECK(rc == (above ? FB_EINVAL : FB_OK));
    if (!above && s) {
      CHECK(!strcmp(s->output[0].signal, "hull_displacement"));
      CHECK(fabs(s->output[0].at[0] + cg_x) < 1e-12 && s->output[0].at[1] == 0.95);
      CHECK_NEAR(s->output[0].at[2], floor, 1e-9);
    }
    if (above)
      CHECK(!strcmp(err.key, "outputs[0].at") && strstr(err.msg, "m from the hull's nearest"));
    fb_scenario_free(&s);
    free(t);
  }
  free(text);
}

/* A mounted rigid body's and its bushing's heights are in the file's
 * frame as their x and y (the truck's floor at z = 0): inside, from the
 * centre of mass, hull_cg_z (the mesh's, above the floor) below them. */
static void test_frame_body_height(void)
{
  char *text = NULL;
  size_t len = 0;
  CHECK(fb_read_file("../examples/truck4x4.yaml", &text, &len, NULL) == FB_OK);
  char *t =
      text ? replaced(text, "outputs:\n",
                      "bodies: [{name: box, mass: 50, x: -2, y: 0, z: 1.9, Ixx: 2, Iyy: 2,\n"
                      "          Izz: 3, bushings: [{x: -2, y: 0, z: 1.6,\n"
                      "          stiffness: [1e5, 1e5, 1e5, 1e4, 1e4, 1e4],\n          "
                      "surface: ROOF, radius: 1.2}]}]\noutputs:\n")
           : NULL;
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(t && fb_scenario_load_string(t, strlen(t), "truck.yaml", &s, &err) == FB_OK);
  if (!s)
    fprintf(stderr, "%s\n", err.msg);
  if (s) {
    /* The generated hull's centre of mass is above its floor, inside it. */
    CHECK(s->hull_cg_z > 0.1 && s->hull_cg_z < 1.5);
    CHECK_NEAR(s->body[0].z, 1.9 - s->hull_cg_z, 1e-12);
    CHECK_NEAR(s->body[0].bushing[0].z, 1.6 - s->hull_cg_z, 1e-12);
    CHECK_NEAR(s->body[0].x, -2.0 - s->hull_cg_x, 1e-12);
  }
  fb_scenario_free(&s);
  free(t);
  free(text);
}

int main(void)
{
  char *text = NULL;
  size_t text_len = 0;
  CHECK(fb_read_file("../examples/apc6x6.yaml", &text, &text_len, NULL) == FB_OK);
  if (text) {
    test_typed_agree(text);
    test_from_mesh(text);
    test_typed_disagree(text);
    test_lumped_from_mesh(text);
  }
  test_frame();
  test_frame_point();
  test_frame_body_height();
  free(text);
  return check_report("test_hull_props");
}
