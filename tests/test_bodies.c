/* SPDX-License-Identifier: BSD-3-Clause */
/* Mounted rigid bodies as a description (flexbond/vehicle.h fb_body): made
 * by a program (fb_scenario_add_body) and read from a file's `bodies`
 * section; the checks' refusals name the body or bushing and, with a
 * file, its line and key; a copy of the description owns its bodies. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/io.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "core/textfile.h"
#include "vehicle_util.h"

#define EXAMPLE "../examples/apc6x6.yaml"

/* A turret on a roof ring of two bushings, a seat on the turret. */
static const char BODIES[] =
    "bodies:\n"
    "  - name: turret\n"
    "    mass: 1200\n"
    "    x: 0.2\n"
    "    y: 0\n"
    "    z: 1.1\n"
    "    Ixx: 400\n"
    "    Iyy: 500\n"
    "    Izz: 600\n"
    "    Ixy: 10\n"
    "    bushings:\n"
    "      - {x: 0.7, y: 0, z: 0.9, stiffness: [1e6, 1e6, 2e6, 1e5, 1e5, 1e5],\n"
    "         damping: [1e3, 1e3, 2e3, 10, 10, 10], surface: ROOF, radius: 1.2}\n"
    "      - {x: -0.3, y: 0, z: 0.9, stiffness: [1e6, 1e6, 2e6, 1e5, 1e5, 1e5],\n"
    "         node_set: LOAD}\n"
    "  - name: gunner\n"
    "    on: turret\n"
    "    mass: 110\n"
    "    x: 0.2\n"
    "    y: 0.3\n"
    "    z: 1.3\n"
    "    Ixx: 8\n"
    "    Iyy: 8\n"
    "    Izz: 4\n"
    "    bushings:\n"
    "      - x: 0.2\n"
    "        y: 0.3\n"
    "        z: 1.0\n"
    "        stiffness_matrix: [4e4, 0, 0, 0, 0, 0,   0, 4e4, 0, 0, 0, 0,   0, 0, 3e4, 0, 0, "
    "0,\n"
    "                           0, 0, 0, 5e3, 0, 0,  0, 0, 0, 0, 5e3, 0,   0, 0, 0, 0, 0, "
    "5e3]\n"
    "        damping: [800, 800, 1200, 50, 50, 50]\n";

/* The example's text with `bodies` (text) before its mounts; NULL and a
 * failed check when it does not load, err set. */
static fb_scenario *load_with(const char *bodies, fb_err *err)
{
  char *text = NULL;
  size_t len = 0;
  fb_scenario *s = NULL;
  if (fb_read_file(EXAMPLE, &text, &len, err) != FB_OK)
    return NULL;
  const char *at = strstr(text, "\nmounts:");
  const size_t head = at ? (size_t)(at - text) + 1 : 0;
  const size_t add = strlen(bodies);
  char *edited = malloc(len + add + 1);
  if (at && edited) {
    memcpy(edited, text, head);
    memcpy(edited + head, bodies, add);
    memcpy(edited + head + add, text + head, len - head + 1);
    if (fb_scenario_load_string(edited, strlen(edited), EXAMPLE, &s, err) != FB_OK)
      s = NULL;
  }
  free(edited);
  free(text);
  return s;
}

static void test_file(void)
{
  fb_err err;
  fb_scenario *s = load_with(BODIES, &err);
  CHECK(s != NULL);
  if (!s) {
    fprintf(stderr, "load: %s\n", err.msg);
    return;
  }
  CHECK(s->nbodies == 2 && fb_scenario_nbushings(s) == 3);
  const fb_body *t = &s->body[0], *g = &s->body[1];
  CHECK(!strcmp(t->name, "turret") && t->parent == NULL && t->nbushings == 2);
  CHECK(t->mass == 1200 && t->z == 1.1 && t->ixy == 10 && t->ixz == 0);
  /* A diagonal given per axis; no damping: none. */
  CHECK(t->bushing[0].k[0] == 1e6 && t->bushing[0].k[14] == 2e6 && t->bushing[0].k[35] == 1e5 &&
        t->bushing[0].k[1] == 0 && t->bushing[0].c[14] == 2e3);
  CHECK(t->bushing[1].c[0] == 0 && t->bushing[1].c[35] == 0);
  CHECK(!strcmp(g->parent, "turret") && g->bushing[0].k[14] == 3e4 &&
        g->bushing[0].k[21] == 5e3 && g->bushing[0].c[14] == 1200);
  CHECK(fb_scenario_body_find(s, "gunner") == 1 && fb_scenario_body_find(s, "x") == -1);
  size_t b = 9, j = 9;
  CHECK(fb_scenario_bushing_at(s, 2, &b, &j) && b == 1 && j == 0);
  CHECK(!fb_scenario_bushing_at(s, 3, &b, &j));
  /* The hull's yaw inertia and products, not given, are its mesh's
   * (its structure's, fb_fe_hull_mass_props; the same computation on the
   * same mesh, to rounding). */
  CHECK(!s->hull_izz_given);
  fb_fe_hull *h = NULL;
  fb_hull_mass_props mp;
  REQUIRE(fb_vehicle_fe_hull(s, &h, &err), &err);
  REQUIRE(fb_fe_hull_mass_props(h, 0, &mp, &err), &err);
  CHECK_NEAR(s->hull_izz / mp.inertia[8], 1.0, 1e-12);
  CHECK(s->hull_izz > s->hull_ixx && s->hull_izz > s->hull_iyy);
  CHECK(fabs(s->hull_ixy + mp.inertia[1]) <= 1e-12 * mp.inertia[8] &&
        fabs(s->hull_ixz + mp.inertia[2]) <= 1e-12 * mp.inertia[8]);
  fb_fe_hull_free(&h);
  /* A copy owns its own bodies. */
  fb_scenario *copy = NULL;
  CHECK(fb_scenario_clone(s, &copy, &err) == FB_OK);
  if (copy) {
    CHECK(copy->body != s->body && copy->body[1].bushing != s->body[1].bushing &&
          !strcmp(copy->body[1].parent, "turret") && copy->body[1].bushing[0].k[21] == 5e3);
    fb_scenario_free(&copy);
  }
  /* A check's error about a bushing is located at its line and key. */
  s->body[1].bushing[0].k[1] = 7; /* no longer symmetric */
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_BUSHING &&
        err.part.index == 2 && !strcmp(err.part.field, "k"));
  fb_scenario_locate(s, &err);
  CHECK(!strcmp(err.file, EXAMPLE) && err.line > 0 &&
        strstr(err.key, "bushings[0].stiffness_matrix") != NULL &&
        strstr(err.msg, "symmetric") != NULL);
  fb_scenario_free(&s);
}

/* A bad value in the file: an error at its line and key. */
static void expect_load_error(const char *bodies, const char *key, const char *words)
{
  fb_err err;
  fb_scenario *s = load_with(bodies, &err);
  CHECK(s == NULL && err.line > 0 && strstr(err.key, key) != NULL &&
        strstr(err.msg, words) != NULL);
  if (s || !strstr(err.key, key) || !strstr(err.msg, words))
    fprintf(stderr, "  expected %s (%s), got %s:%d: %s: %s\n", key, words, err.file, err.line,
            err.key, err.msg);
  fb_scenario_free(&s);
}

static void test_file_errors(void)
{
  /* A parent listed after its child. */
  expect_load_error("bodies:\n"
                    "  - {name: seat, on: turret, mass: 90, x: 0, y: 0, z: 1, Ixx: 5, Iyy: 5,\n"
                    "     Izz: 3, bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, "
                    "1], node_set: LOAD}]}\n"
                    "  - {name: turret, mass: 900, x: 0, y: 0, z: 1, Ixx: 300, Iyy: 300,\n"
                    "     Izz: 400, bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, "
                    "1], node_set: LOAD}]}\n",
                    "on", "no body listed before seat");
  /* Five stiffnesses. */
  expect_load_error(
      "bodies:\n"
      "  - {name: box, mass: 90, x: 0, y: 0, z: 1, Ixx: 5, Iyy: 5, Izz: 3,\n"
      "     bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1], node_set: LOAD}]}\n",
      "stiffness", "6");
  /* Both ways of a stiffness. */
  expect_load_error(
      "bodies:\n"
      "  - {name: box, mass: 90, x: 0, y: 0, z: 1, Ixx: 5, Iyy: 5, Izz: 3,\n"
      "     bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, 1],\n"
      "                 stiffness_matrix: [1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1,\n"
      "                   0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1]}]}\n",
      "stiffness", "");
  /* Principal moments no body has (a rod: Izz > Ixx + Iyy). */
  expect_load_error(
      "bodies:\n"
      "  - {name: box, mass: 90, x: 0, y: 0, z: 1, Ixx: 1, Iyy: 1, Izz: 3,\n"
      "     bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, 1], node_set: LOAD}]}\n",
      "Izz", "triangle inequality");
  /* The same rod along x: the error is at the moment that is too large,
   * Ixx, the value to change (a sweep of Ixx must see its own key). */
  expect_load_error(
      "bodies:\n"
      "  - {name: box, mass: 90, x: 0, y: 0, z: 1, Ixx: 3, Iyy: 1, Izz: 1,\n"
      "     bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, 1], node_set: LOAD}]}\n",
      "Ixx", "triangle inequality");
  /* A tensor that is not positive definite through its product Iyz: the
   * error is at Iyz. */
  expect_load_error(
      "bodies:\n"
      "  - {name: box, mass: 90, x: 0, y: 0, z: 1, Ixx: 5, Iyy: 5, Izz: 5, Iyz: 6,\n"
      "     bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, 1], node_set: LOAD}]}\n",
      "Iyz", "positive definite");
  /* No bushing. */
  expect_load_error("bodies:\n"
                    "  - {name: box, mass: 90, x: 0, y: 0, z: 1, Ixx: 5, Iyy: 5, Izz: 3,\n"
                    "     bushings: []}\n",
                    "bushings", "at least 1");
  /* A bushing on the finite-element hull without its nodes. */
  expect_load_error("bodies:\n"
                    "  - {name: box, mass: 90, x: 0, y: 0, z: 1, Ixx: 5, Iyy: 5, Izz: 3,\n"
                    "     bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, 1]}]}\n",
                    "bushings[0]", "node_set");
  /* A node set the mesh does not have. */
  expect_load_error("bodies:\n"
                    "  - {name: box, mass: 90, x: 0, y: 0, z: 1, Ixx: 5, Iyy: 5, Izz: 3,\n"
                    "     bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, 1],\n"
                    "                 node_set: NOWHERE}]}\n",
                    "node_set", "NOWHERE");
  /* A body named as one of the vehicle's own parts. */
  expect_load_error(
      "bodies:\n"
      "  - {name: road, mass: 90, x: 0, y: 0, z: 1, Ixx: 5, Iyy: 5, Izz: 3,\n"
      "     bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, 1], node_set: LOAD}]}\n",
      "name", "another");
  /* A body named as a mount. */
  expect_load_error(
      "bodies:\n"
      "  - {name: driver, mass: 90, x: 0, y: 0, z: 1, Ixx: 5, Iyy: 5, Izz: 3,\n"
      "     bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, 1], node_set: LOAD}]}\n",
      "name", "unique");
  /* A body named as an anti-roll bar's part of the assembled vehicle. */
  expect_load_error(
      "anti_roll_bars:\n"
      "  - {name: front, left: LF, right: RF, stiffness: 60000}\n"
      "bodies:\n"
      "  - {name: arb_front, mass: 90, x: 0, y: 0, z: 1, Ixx: 5, Iyy: 5, Izz: 3,\n"
      "     bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, 1], node_set: LOAD}]}\n",
      "bodies[0].name", "arb_<bar>");
}

/* A mount named as a bogie's or a bar's part of the assembled vehicle
 * ("bogie_<name>", "arb_<name>"): refused at its name, not by the graph
 * (whose clash has no place in the file). */
static void test_mount_instance_name(void)
{
  fb_err err;
  fb_scenario *s = load_with("anti_roll_bars:\n"
                             "  - {name: front, left: LF, right: RF, stiffness: 60000}\n",
                             &err);
  CHECK(s != NULL);
  if (!s)
    return;
  free(s->mount[1].name);
  s->mount[1].name = strdup("arb_front");
  fb_err_clear(&err);
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_MOUNT &&
        err.part.index == 1 && !strcmp(err.part.field, "name") &&
        strstr(err.msg, "arb_front") != NULL);
  fprintf(stderr, "mount named arb_front: %s\n", err.msg);
  fb_scenario_free(&s);
  /* A bogie's saddle's lever (saddle_<bogie>_rear), on the bogie example. */
  REQUIRE(fb_scenario_load("../examples/truck6x6_bogie.yaml", &s, &err), &err);
  free(s->mount[0].name);
  s->mount[0].name = strdup("saddle_left_rear");
  fb_err_clear(&err);
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_MOUNT &&
        err.part.index == 0 && !strcmp(err.part.field, "name"));
  fprintf(stderr, "mount named saddle_left_rear: %s\n", err.msg);
  fb_scenario_free(&s);
}

/* A body on the builder's description: each refusal names its part. */
static void test_builder(void)
{
  fb_err err;
  fb_scenario *s = load_with("", &err);
  CHECK(s != NULL);
  if (!s)
    return;
  /* System 1 alone: the hull's whole tensor given. */
  s->has_fe_hull = 0;
  s->hull_izz_given = 1;
  s->hull_izz = 2e4;
  fb_bushing u = {.x = 0, .y = 0, .z = 1};
  const double k6[6] = {1e5, 1e5, 1e5, 1e4, 1e4, 1e4}, c6[6] = {0};
  fb_bushing_set_diagonal(&u, k6, c6);
  fb_body b = {.name = "box",
               .mass = 50,
               .z = 1.2,
               .ixx = 2,
               .iyy = 2,
               .izz = 3,
               .bushing = &u,
               .nbushings = 1};
  CHECK(fb_scenario_add_body(s, &b, &err) == FB_OK && s->nbodies == 1);
  CHECK(s->body[0].bushing != &u && s->body[0].name != b.name);
  REQUIRE(fb_scenario_check(s, &err), &err);
  /* Products of inertia making the tensor indefinite. */
  s->body[0].ixy = 3;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_BODY &&
        err.part.index == 0 && strstr(err.msg, "positive definite"));
  s->body[0].ixy = 0;
  /* A bushing with no rotational stiffness leaves a body on one bushing
   * free to turn. */
  for (int i = 3; i < 6; ++i)
    s->body[0].bushing[0].k[7 * i] = 0;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_BODY &&
        !strcmp(err.part.field, "bushing") && strstr(err.msg, "free to move"));
  /* Two such bushings apart hold it in pitch and yaw but not in roll
   * about the line through them (x here)... */
  fb_bushing two[2] = {s->body[0].bushing[0], s->body[0].bushing[0]};
  two[0].x = 0.5;
  two[1].x = -0.5;
  fb_body c = b;
  c.name = "pair";
  c.bushing = two;
  c.nbushings = 2;
  CHECK(fb_scenario_add_body(s, &c, &err) == FB_OK);
  for (int i = 3; i < 6; ++i)
    s->body[0].bushing[0].k[7 * i] = 1e4;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_BODY &&
        err.part.index == 1 && strstr(err.msg, "free to move"));
  /* ... which a torsional stiffness of one of them about x takes. */
  s->body[1].bushing[1].k[21] = 1e3;
  REQUIRE(fb_scenario_check(s, &err), &err);
  /* A negative damping. */
  s->body[1].bushing[1].c[0] = -1;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_BUSHING &&
        err.part.index == 2 && !strcmp(err.part.field, "c"));
  s->body[1].bushing[1].c[0] = 0;
  /* A node set only for System 2's hull, and only for a body on the hull. */
  s->body[1].parent = strdup("box");
  s->body[1].bushing[1].radius = 0.1;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_BUSHING &&
        !strcmp(err.part.field, "radius") && strstr(err.msg, "on another body"));
  s->body[1].bushing[1].radius = 0;
  REQUIRE(fb_scenario_check(s, &err), &err);
  /* A parent that is the body itself. */
  free(s->body[1].parent);
  s->body[1].parent = strdup("pair");
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_BODY &&
        err.part.index == 1 && !strcmp(err.part.field, "parent"));
  char text[256];
  fb_scenario_part_text(s, &err.part, text, sizeof text);
  CHECK(!strcmp(text, "body[1] (pair).parent"));
  /* A parent misspelt: the body before it is suggested. */
  free(s->body[1].parent);
  s->body[1].parent = strdup("bx");
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL && err.part.kind == FB_PART_BODY &&
        !strcmp(err.part.field, "parent") && strstr(err.msg, "did you mean 'box'?"));
  free(s->body[1].parent);
  s->body[1].parent = strdup("pair");
  /* The builder refuses a body without a bushing or a name. */
  c.nbushings = 0;
  CHECK(fb_scenario_add_body(s, &c, &err) == FB_EINVAL && s->nbodies == 2);
  c.nbushings = 1;
  c.name = NULL;
  CHECK(fb_scenario_add_body(s, &c, &err) == FB_EINVAL && s->nbodies == 2);
  fb_scenario_free(&s);
}

/* A bushing on a node set of one node (ENGINE: the engine mount's floor
 * node) hangs the body on one point of the floor plate: the loader warns,
 * at the bushing's node_set, of the local mode it makes, its frequency
 * sqrt(k_s / m) / 2 pi with 1/k_s = 1/k_p + 1/k_z (k_p the plate's point
 * stiffness). Checks: the warning names the frequency those values give
 * (to its 3 printed digits), and k_p, a linear elastic static solve,
 * doubles exactly with Young's modulus (to 1e-9: a Cholesky solve of the
 * same pattern). */
static void test_single_node(void)
{
  fb_err err;
  fb_scenario *s =
      load_with("bodies:\n"
                "  - {name: box, mass: 300, x: 1.7, y: -0.55, z: 0.2, Ixx: 5, Iyy: 5, Izz: 3,\n"
                "     bushings: [{x: 1.7, y: -0.55, z: 0.1, node_set: ENGINE,\n"
                "                 stiffness: [1e6, 1e6, 5e5, 1e5, 1e5, 1e5]}]}\n",
                &err);
  CHECK(s != NULL);
  if (!s)
    return;
  const fb_err *w = NULL;
  for (size_t i = 0; i < fb_scenario_nwarnings(s); ++i)
    if (strstr(fb_scenario_warning(s, i)->key, "bodies[0].bushings[0].node_set"))
      w = fb_scenario_warning(s, i);
  CHECK(w != NULL && w->line > 0 && strstr(w->msg, "local mode"));
  fb_fe_hull *h = NULL;
  double kp = 0.0, kp2 = 0.0;
  REQUIRE(fb_vehicle_fe_hull(s, &h, &err), &err);
  CHECK(h->nbushings == 1 && h->bushing_single_node[0] != (size_t)-1);
  REQUIRE(fb_fe_hull_point_stiffness(h, s->ncorners, h->bushing_single_node[0], &kp, &err),
          &err);
  h->props.young *= 2.0;
  REQUIRE(fb_fe_hull_point_stiffness(h, s->ncorners, h->bushing_single_node[0], &kp2, &err),
          &err);
  CHECK_NEAR(kp2 / kp, 2.0, 1e-9);
  const double ks = 1.0 / (1.0 / kp + 1.0 / 5e5);
  char hz[32];
  snprintf(hz, sizeof hz, "at %.3g Hz", sqrt(ks / 300.0) / (2.0 * 3.14159265358979323846));
  CHECK(w && strstr(w->msg, hz));
  fb_fe_hull_free(&h);
  fb_scenario_free(&s);
}

int main(void)
{
  test_single_node();
  test_file();
  test_file_errors();
  test_mount_instance_name();
  test_builder();
  return check_report(__FILE__);
}
