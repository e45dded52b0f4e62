/* SPDX-License-Identifier: BSD-3-Clause */
/* Declared non-structural hull masses (hull.masses) in both systems,
 * each against an answer of its own:
 *   1. System 1's I field is diag(m, Ixx, Iyy) + sum m r r' with r = [1,
 *      y, -x], written out here entry by entry;
 *   2. System 2's mass matrix, projected on the hull's six rigid-body
 *      modes, has the structure's mass plus the masses' on every
 *      translation, and each mass's m (x^2 + z^2) more pitch inertia; the
 *      two systems' rigid-body properties agree (mass to rounding, pitch
 *      inertia about the centre of mass up to the masses' height term
 *      that a rigid hull moving points vertically leaves out);
 *   3. statics: System 2's tires still carry the whole weight;
 *   4. a heavy mass lowers the hull's free-free frequencies (Rayleigh:
 *      more mass, no more stiffness), and beta follows the first one;
 *   5. a clone keeps the masses, a declared frame moves them, a mass too
 *      close to a node line is refused at its key. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "bgtest_util.h"
#include "check.h"
#include "vehicle_util.h"

/* Two masses on the paper's load lines and one off every line of the
 * generated mesh (x = 0.25, y = 0.20 make lines of their own). */
#define MASSES                                                                                 \
  "  masses:\n"                                                                                \
  "    - {name: battery, mass: 400, x: -2.00, y: 0.55}\n"                                      \
  "    - {name: ballast, mass: 1200, x: 1.30, y: -0.55}\n"                                     \
  "    - {name: plate, mass: 250, x: 0.25, y: 0.20}\n"

static const double mass_m[3] = {400, 1200, 250}, mass_x[3] = {-2.00, 1.30, 0.25},
                    mass_y[3] = {0.55, -0.55, 0.20};

/* The reference scenario with masses (inserted before hull.material),
 * and with typed hull mass, Ixx and Iyy unless from_mesh is set. */
static fb_scenario *load_masses(const char *masses, int from_mesh)
{
  fb_err err;
  fb_scenario *s = NULL;
  int rc = from_mesh ? load_replaced("  mass: 4041.72", 0, "  material:", masses, &s, &err)
                     : load_replaced("  material:", 0, "  material:", masses, &s, &err);
  if (rc)
    fprintf(stderr, "load: %s\n", err.msg);
  CHECK(rc == FB_OK && s);
  return s;
}

/* A scenario with MASSES and what the tests look at of its two hulls. */
typedef struct built {
  fb_scenario *s;
  fb_fe_hull *h;
  fb_hull *flex, *rigid;
} built;

static void built_free(built *b)
{
  fb_hull_free(&b->flex);
  fb_hull_free(&b->rigid);
  fb_fe_hull_free(&b->h);
  fb_scenario_free(&b->s);
}

/* Loads MASSES (as load_masses) with the payload model payload and
 * builds both hulls; 1 when everything was built. */
static int build(built *b, int from_mesh, fb_payload_model payload)
{
  fb_err err;
  *b = (built){load_masses(MASSES, from_mesh), NULL, NULL, NULL};
  if (!b->s)
    return 0;
  b->s->payload = payload;
  /* Nodal coordinates: the flexible hull's I field is then the mass
   * matrix the tests project on the rigid-body modes. */
  b->s->hull_coordinates = FB_HULL_NODAL;
  MUST(fb_vehicle_rigid_hull(b->s, &b->rigid, &err), &err);
  MUST(fb_vehicle_fe_hull(b->s, &b->h, &err), &err);
  if (b->h)
    MUST(fb_vehicle_flexible_hull(b->s, b->h, &b->flex, &err), &err);
  return b->rigid && b->h && b->flex;
}

/* The matrix of the element called name in g, NULL if none. */
static const fb_mat *element_matrix(const fb_bg *g, const char *name)
{
  const long e = fb_bg_find_element(g, name);
  return e < 0 ? NULL : fb_bg_element_matrix(g, (size_t)e);
}

/* 1. System 1's I field, with the file's hull.mass, Ixx and Iyy (the
 * structure's: the check against the mesh passes with the masses). Each entry is a sum of four
 * products of numbers of about 1e3 .. 1e4: a few ulps of the entry's size apart from the
 * library's loop at most, 1e-13 relative. */
static void test_rigid_inertia(void)
{
  built b;
  if (!build(&b, 0, FB_PAYLOAD_WEIGHT_ONLY)) {
    built_free(&b);
    return;
  }
  const fb_scenario *s = b.s;
  CHECK(s->npoint_masses == 3 && !strcmp(s->point_mass[1].name, "ballast"));
  CHECK(s->hull_mass == 4041.72);
  const fb_mat *I = element_matrix(b.rigid->graph, "body");
  CHECK(I != NULL);
  if (I) {
    double want[9] = {4041.72, 0, 0, 0, 4173.49, 0, 0, 0, 15175.96};
    for (int k = 0; k < 3; ++k) {
      const double m = mass_m[k], x = mass_x[k], y = mass_y[k];
      want[0] += m;         /* z z */
      want[1] += m * y;     /* z phi */
      want[2] += -m * x;    /* z theta */
      want[4] += m * y * y; /* phi phi */
      want[5] += -m * x * y;
      want[8] += m * x * x; /* theta theta */
    }
    want[3] = want[1];
    want[6] = want[2];
    want[7] = want[5];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        CHECK_NEAR(fb_mat_get(I, (size_t)i, (size_t)j), want[3 * i + j], 1e-13 * 2e4);
  }
  built_free(&b);
}

/* R' M R over the hull's six rigid-body modes about the origin
 * (translations x, y, z, rotations about x, y, z; the node's rotations
 * follow a rotation too), into g (6 x 6, row-major). */
static void rigid_projection(const fb_mesh *mesh, const fb_mat *M, double *g)
{
  const size_t nn = fb_mesh_nnodes(mesh), n = 6 * nn;
  double *r = calloc(6 * n, sizeof *r), *mr = malloc(n * sizeof *mr);
  CHECK(r && mr);
  for (size_t i = 0; r && i < nn; ++i) {
    const double *p = fb_mesh_node_xyz(mesh, i);
    for (int k = 0; k < 3; ++k) {
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      double *col = r + (size_t)(3 + k) * n + 6 * i;
      r[(size_t)k * n + 6 * i + (size_t)k] = 1.0;
      col[a] = -p[b]; /* e_k x p */
      col[b] = p[a];
      col[3 + k] = 1.0;
    }
  }
  for (int j = 0; r && mr && j < 6; ++j) {
    fb_mat_gemv(M, 1.0, r + (size_t)j * n, 0.0, mr);
    for (int i = 0; i < 6; ++i) {
      double sum = 0.0;
      for (size_t d = 0; d < n; ++d)
        sum += r[(size_t)i * n + d] * mr[d];
      g[6 * i + j] = sum;
    }
  }
  free(r);
  free(mr);
}

/* z of the node of hull mass k (the floor, below the centre of mass). */
static double mass_node_z(const fb_fe_hull *h, size_t k)
{
  return fb_mesh_node_xyz(h->mesh, h->point_mass_node[k])[2];
}

/* 2. System 2's mass matrix, the one its hull fragment simulates with. */
static void test_fe_projection(void)
{
  fb_err err;
  built b;
  fb_mat *Ms = NULL;
  if (!build(&b, 1, FB_PAYLOAD_WEIGHT_ONLY) || b.h->npoint_masses != 3) {
    CHECK(0);
    built_free(&b);
    return;
  }
  const fb_scenario *s = b.s;
  const fb_fe_hull *h = b.h;
  const fb_mat *M = element_matrix(b.flex->graph, "mass");
  const fb_mat *I = element_matrix(b.rigid->graph, "body");
  CHECK(M && I);
  if (!M || !I)
    goto done;
  /* The structure alone, assembled here (fb_fem_assemble knows no
   * masses), and its properties: System 1's hull.mass and Iyy. */
  double ms = 0, cs[3], Js[9];
  MUST(fb_fem_assemble(h->mesh, &h->props, h->mass_kind, NULL, &Ms, &err), &err);
  MUST(fb_fem_mass_properties(h->mesh, Ms, &ms, cs, Js, &err), &err);
  /* The loader's are the same kinetic energies summed element by
   * element (fb_fem_mesh_mass_properties): rounding, 1e-12 relative. */
  CHECK_NEAR(s->hull_mass, ms, 1e-12 * ms);
  CHECK_NEAR(s->hull_iyy, Js[4], 1e-12 * Js[4]);
  double g[36], gs[36], sum_m = 0, sum_mz = 0, sum_mz2 = 0, dpitch = 0;
  rigid_projection(h->mesh, M, g);
  rigid_projection(h->mesh, Ms, gs);
  for (size_t k = 0; k < 3; ++k) {
    const double z = mass_node_z(h, k);
    /* Each mass on the floor, at its node. */
    CHECK(fabs(fb_mesh_node_xyz(h->mesh, h->point_mass_node[k])[0] - mass_x[k]) < 1e-9);
    CHECK(z < -0.5);
    sum_m += mass_m[k];
    sum_mz += mass_m[k] * z;
    sum_mz2 += mass_m[k] * z * z;
    dpitch += mass_m[k] * (mass_x[k] * mass_x[k] + z * z);
  }
  /* The projections sum some 1300 products: 1e-10 relative is a
   * thousand times their rounding and far below any mass left out. */
  for (int t = 0; t < 3; ++t)
    CHECK_NEAR(g[7 * t], ms + sum_m, 1e-10 * (ms + sum_m));
  /* About y through the origin a mass at (x, z) moves by (z, 0, -x). */
  CHECK_NEAR(g[7 * 4] - gs[7 * 4], dpitch, 1e-10 * gs[7 * 4]);
  /* System 1 against System 2: the same mass (System 1's hull mass is
   * the same mesh's: rounding only). */
  const double m1 = fb_mat_get(I, 0, 0);
  CHECK_NEAR(m1, g[0], 1e-10 * m1);
  /* Pitch inertia about the centre of mass of hull and masses: System 1
   * the (z, theta) block's Schur complement, System 2 the as-built mass
   * properties. They differ by the masses' height below the structure's
   * centre of mass, sum m z^2 - (sum m z)^2 / m_total (System 1 moves
   * points vertically only); the structure's centre of mass is the
   * origin to 1e-12 m. */
  double mt = 0, ct[3], Jt[9];
  fb_mat *Mt = NULL;
  MUST(fb_fe_hull_mass_matrix(h, &Mt, &err), &err);
  if (Mt)
    MUST(fb_fem_mass_properties(h->mesh, Mt, &mt, ct, Jt, &err), &err);
  fb_mat_free(&Mt);
  const double i_zt = fb_mat_get(I, 0, 2), pitch1 = fb_mat_get(I, 2, 2) - i_zt * i_zt / m1;
  const double height = sum_mz2 - sum_mz * sum_mz / mt;
  fprintf(stderr, "pitch about the centre of mass: System 1 %.9g, System 2 %.9g kg m^2\n",
          pitch1, Jt[4]);
  CHECK_NEAR(mt, m1, 1e-10 * m1);
  CHECK_NEAR(Jt[4], pitch1 + height, 1e-9 * Jt[4]);
  /* Its centre of mass in x: System 1's -I_z,theta / m. */
  CHECK_NEAR(ct[0], -i_zt / m1, 1e-9);
done:
  fb_mat_free(&Ms);
  built_free(&b);
}

/* With the lumped payload, its mass is what the hull and its masses
 * leave of load.total_weight / gravity: both systems' total translational
 * mass is that total (to rounding: 1e-12 of System 1's single sum, 1e-10
 * of System 2's projection). */
static void test_lumped_total(void)
{
  built b;
  if (build(&b, 1, FB_PAYLOAD_LUMPED)) {
    const double total = b.s->total_weight / b.s->gravity;
    double g[36];
    CHECK_NEAR(fb_scenario_payload_mass(b.s), total - b.s->hull_mass - 1850.0, 1e-12 * total);
    CHECK_NEAR(fb_mat_get(element_matrix(b.rigid->graph, "body"), 0, 0), total, 1e-12 * total);
    rigid_projection(b.h->mesh, element_matrix(b.flex->graph, "mass"), g);
    CHECK_NEAR(g[14], total, 1e-10 * total);
  }
  built_free(&b);
}

/* 3. System 2's static equilibrium with the masses: the masses carry no
 * weight of their own (theirs is in load.total_weight), so the tire
 * springs carry the load, the mounted bodies and the wheels. */
static void test_static_weight(void)
{
  fb_scenario *s = load_masses(MASSES, 0);
  fb_err err;
  fb_bg *g = NULL;
  fb_bd *bd = NULL;
  /* Nodal, for the static solver's 1e-10 balance per DOF (test_system2_sim,
   * test 1, on modal coordinates). */
  if (s)
    s->hull_coordinates = FB_HULL_NODAL;
  if (s)
    MUST(fb_vehicle_build(s, FB_SYSTEM_FLEXIBLE, &g, &bd, &err), &err);
  const size_t nx = bd ? fb_bd_nstates(bd) : 0;
  double *x0 = calloc(nx + 1, sizeof *x0), *xeq = calloc(nx + 1, sizeof *xeq);
  if (bd && x0 && xeq) {
    MUST(fb_sim_static_state(bd, 0.0, x0, xeq, &err), &err);
    check_tires_carry_weight(s, bd, xeq, "System 2 static with masses");
  }
  free(x0);
  free(xeq);
  fb_bd_free(&bd);
  fb_bg_free(&g);
  fb_scenario_free(&s);
}

/* 4. Free-free frequencies with and without the masses, on one mesh.
 * Adding mass and no stiffness lowers every eigenvalue or keeps it
 * (Courant-Fischer: each Rayleigh quotient only falls). 1.6 t on a 4 t
 * hull lowers the first elastic mode by more than 5 %; by much more here,
 * since 1.2 t on one node of the 8.5 mm floor, away from the bulkheads,
 * makes a local mode of the floor under it (the direction is what is
 * checked). */
static void test_frequencies(void)
{
  fb_err err;
  built b;
  if (!build(&b, 0, FB_PAYLOAD_WEIGHT_ONLY)) {
    built_free(&b);
    return;
  }
  fb_fe_hull *h = b.h;
  enum { N = 14 };
  double with[N], bare[N], beta = 0.0;
  size_t nrigid_with = 0, nrigid_bare = 0;
  MUST(fb_fe_hull_free_modes(h, N, with, &nrigid_with, &err), &err);
  MUST(fb_fe_hull_damping(h, 0.02, &beta, NULL, &err), &err);
  const size_t n = h->npoint_masses;
  h->npoint_masses = 0; /* the same mesh, bare */
  MUST(fb_fe_hull_free_modes(h, N, bare, &nrigid_bare, &err), &err);
  h->npoint_masses = n;
  CHECK(nrigid_with == 6 && nrigid_bare == 6);
  fprintf(stderr, "first elastic free-free mode: %.6g Hz bare, %.6g Hz with the masses\n",
          bare[6], with[6]);
  for (int k = 6; k < N; ++k)
    CHECK(with[k] <= bare[k] * (1 + 1e-9));
  CHECK(with[6] < 0.95 * bare[6]);
  /* beta = 2 zeta / omega_1 of the hull as built. The damping's solve
   * (7 modes) and these modes' (14) are two block Lanczos solves of the
   * same pencil: each stops with residuals below 1e-6 of the Ritz value,
   * which bounds omega_1^2's error by residual^2 / gap (Parlett, Thm.
   * 11.7.1), some 1e-12 relative, and its rounding depends on the BLAS
   * kernels the CPU selects and on the block size the count asks for
   * (1.5e-9 relative measured at most between two solves of one hull by
   * different methods). 1e-8 keeps a margin and still catches a beta of
   * another mode or another mass matrix (percents off). */
  CHECK_NEAR(beta, 0.02 / (3.14159265358979324 * with[6]), 1e-8 * beta);
  built_free(&b);
}

/* 5. A clone copies the masses, names and all. */
static void test_clone(void)
{
  fb_err err;
  fb_scenario *s = load_masses(MASSES, 0), *c = NULL;
  if (!s)
    return;
  MUST(fb_scenario_clone(s, &c, &err), &err);
  CHECK(c && c->npoint_masses == 3 && c->point_mass != s->point_mass);
  for (size_t k = 0; c && k < 3; ++k)
    CHECK(c->point_mass[k].name != s->point_mass[k].name &&
          !strcmp(c->point_mass[k].name, s->point_mass[k].name) &&
          c->point_mass[k].mass == mass_m[k] && c->point_mass[k].x == mass_x[k] &&
          c->point_mass[k].y == mass_y[k]);
  fb_scenario_free(&c);
  fb_scenario_free(&s);
}

/* The truck (examples/truck4x4.yaml) declares a frame: its battery is
 * moved to the hull's centre of mass with every other position, and its
 * node is where the file puts it, on the cab's back wall (x = -0.80). */
static void test_frame(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  fb_fe_hull *h = NULL;
  MUST(fb_scenario_load("../examples/truck4x4.yaml", &s, &err), &err);
  if (s)
    MUST(fb_vehicle_fe_hull(s, &h, &err), &err);
  if (!h) {
    fb_scenario_free(&s);
    return;
  }
  CHECK(s->npoint_masses == 1 && !strcmp(s->point_mass[0].name, "battery"));
  CHECK(s->point_mass[0].x == -0.80 - s->hull_cg_x && s->point_mass[0].y == -0.50);
  CHECK(h->npoint_masses == 1 && h->point_mass[0] == 300);
  const double *p = fb_mesh_node_xyz(h->mesh, h->point_mass_node[0]);
  CHECK(fabs(p[0] - s->point_mass[0].x) < 1e-9 && fabs(p[1] + 0.50) < 1e-9);
  fb_fe_hull_free(&h);
  fb_scenario_free(&s);
}

/* A mass 0.5 mm from the 0.40 m load line would make a sliver element:
 * refused at its x (line 17 of the edited file), naming both lines. */
static void test_too_close(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  const int rc = load_replaced(
      "  material:", 0,
      "  material:", "  masses: [{name: plate, mass: 250, x: 0.4005, y: 0.20}]\n", &s, &err);
  CHECK(rc == FB_EINVAL && !s);
  CHECK(strstr(err.msg, "bad.yaml:20:") == err.msg);
  CHECK(strstr(err.msg, "hull.masses[0].x: at x = ") != NULL);
  CHECK(strstr(err.msg, " m from ") != NULL);
  if (!strstr(err.msg, "hull.masses[0].x"))
    fprintf(stderr, "too close: %s\n", err.msg);
  fb_scenario_free(&s);
}

int main(void)
{
  test_rigid_inertia();
  test_fe_projection();
  test_lumped_total();
  test_static_weight();
  test_frequencies();
  test_clone();
  test_frame();
  test_too_close();
  return check_report("test_hull_masses");
}
