/* SPDX-License-Identifier: BSD-3-Clause */
/* A hull reduced elsewhere in System 2 (the hull source `reduced`,
 * docs/reduced-hulls.md) against the shell mesh it came from.
 *
 * The mesh: examples/apc6x6_reduced.yaml with the density-1 generated
 * hull of examples/apc6x6.yaml (its "twin"). The superelement: flexbond's
 * own Guyan condensation (fb_fem_guyan) of that hull's K and M onto the
 * six DOFs of its twelve interface nodes (the suspension points, which
 * are also the load points, the mounts and the edge ends), written as
 * Matrix Market with 17 digits (and as a DMIG punch file) and read back
 * through the scenario.
 *
 * - Statics: Guyan is exact for loads at the kept DOFs, so the stiffness
 *   a point sees with the suspension points held is the mesh's to the
 *   file's precision.
 * - Dynamics: Guyan's subspace holds the rigid-body motions exactly (mass,
 *   centre of mass, inertia equal) and is a Rayleigh-Ritz subspace of the
 *   mesh's, so each free-free frequency of the reduced hull is an upper
 *   bound of the mesh's.
 * - The vehicle: its modes below the hull's first elastic mode, and a run
 *   over a bump, on both hulls.
 *
 * `test_reduced_hull --write-example DIR` writes the example's matrices
 * and nodes file into DIR (how examples/apc6x6_reduced_*.{mtx,csv} were
 * made). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/hull_source.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "road_util.h"
#include "tmpdir.h"
#include "vehicle_util.h"

static const char *const EXAMPLE = "../examples/apc6x6_reduced.yaml";

/* text with [from, to) between the markers start and end (end kept)
 * replaced by with; NULL when a marker is missing (text freed). */
static char *splice(char *text, const char *start, const char *end, const char *with)
{
  char *from = text ? strstr(text, start) : NULL;
  char *to = from ? strstr(from, end) : NULL;
  char *out = to ? malloc(strlen(text) + strlen(with) + 1) : NULL;
  if (out) {
    memcpy(out, text, (size_t)(from - text));
    strcpy(out + (from - text), with);
    strcat(out, to);
  }
  free(text);
  return out;
}

/* The example with apc6x6.yaml's generated mesh in place of the
 * superelement. */
static char *twin_yaml(void)
{
  char *apc = read_text("../examples/apc6x6.yaml");
  const char *a = apc ? strstr(apc, "  # System 2: the finite-element hull") : NULL;
  const char *b = a ? strstr(a, "  fe:\n") : NULL;
  char *mesh = b ? strndup(a, (size_t)(b - a)) : NULL;
  char *yaml = mesh ? splice(read_text(EXAMPLE), "  # System 2: a structure reduced elsewhere",
                             "  fe:\n", mesh)
                    : NULL;
  free(mesh);
  free(apc);
  return yaml;
}

/* The example with its files in dir (absolute paths: a scenario loaded
 * from text has no directory of its own), as Matrix Market or as DMIG. */
static char *reduced_yaml(const char *dir, int dmig)
{
  char with[4096];
  if (dmig)
    snprintf(with, sizeof with,
             "  mesh:\n    reduced:\n      format: dmig\n      k: %s/apc6x6_reduced.pch\n"
             "      nodes: %s/apc6x6_reduced_grids.csv\n",
             dir, dir);
  else
    snprintf(with, sizeof with,
             "  mesh:\n    reduced:\n      k: %s/apc6x6_reduced_K.mtx\n"
             "      m: %s/apc6x6_reduced_M.mtx\n      nodes: %s/apc6x6_reduced_nodes.csv\n",
             dir, dir, dir);
  return splice(read_text(EXAMPLE), "  mesh:\n    reduced:", "  fe:\n", with);
}

static fb_scenario *load_yaml(const char *yaml)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(yaml != NULL);
  REQUIRE(load_text_with(yaml, NULL, &s, &err), &err);
  return s;
}

/* The interface: the distinct nodes the vehicle meets (attachment, load,
 * edge nodes), increasing. */
static size_t interface_nodes(const fb_fe_hull *h, size_t *nodes)
{
  size_t n = 0;
  const size_t total = h->nattach + h->nload + 4;
  for (size_t k = 0; k < total; ++k) {
    const size_t node = k < h->nattach              ? h->attach_node[k]
                        : k < h->nattach + h->nload ? h->load_node[k - h->nattach]
                                                    : h->edge_node[k - h->nattach - h->nload];
    size_t i = 0;
    while (i < n && nodes[i] < node)
      ++i;
    if (i < n && nodes[i] == node)
      continue;
    memmove(nodes + i + 1, nodes + i, (n - i) * sizeof *nodes);
    nodes[i] = node;
    ++n;
  }
  return n;
}

/* a (d x d, symmetric) as the DMIG matrix name in Nastran's free field:
 * IFO 6, one triangle (rows up to the column), TIN 2, 17 digits; DOF i
 * node ids[i / 6]'s component i % 6 + 1. */
static void write_dmig_free(FILE *fp, const char *name, const double *a, size_t d,
                            const long *ids)
{
  fprintf(fp, "DMIG,%s,0,6,2,0\n", name);
  for (size_t j = 0; j < d; ++j) {
    fprintf(fp, "DMIG,%s,%ld,%zu,", name, ids[j / 6], j % 6 + 1);
    for (size_t i = 0; i <= j; ++i)
      if (a[j * d + i] != 0.0)
        fprintf(fp, "\n,%ld,%zu,%.17g", ids[i / 6], i % 6 + 1, a[j * d + i]);
    fputc('\n', fp);
  }
}

/* The interface's nodes file at path: "id, x, y, z", with the components
 * after them when components is not NULL (Matrix Market: DMIG names its
 * own). */
static void write_nodes(const char *path, const fb_mesh *mesh, const size_t *nodes, size_t nn,
                        const char *components)
{
  FILE *fp = fopen(path, "w");
  CHECK(fp != NULL);
  if (!fp)
    return;
  fprintf(fp,
          "# The interface of examples/apc6x6_reduced.yaml (tests/test_reduced_hull.c)\n"
          "# id, x, y, z (m)%s\n",
          components ? ", components" : "");
  for (size_t i = 0; i < nn; ++i) {
    const double *x = fb_mesh_node_xyz(mesh, nodes[i]);
    fprintf(fp, "%ld, %.17g, %.17g, %.17g%s%s\n", fb_mesh_node_id(mesh, nodes[i]), x[0], x[1],
            x[2], components ? ", " : "", components ? components : "");
  }
  CHECK(fclose(fp) == 0);
}

/* K and M of the twin's hull condensed onto the interface, written into
 * dir as the example's three files, and as a DMIG punch file
 * (apc6x6_reduced.pch, KAAX and MAAX) with its nodes file
 * (apc6x6_reduced_grids.csv). */
static void write_reduced(const char *dir, int with_dmig)
{
  fb_err err;
  char *yaml = twin_yaml();
  fb_scenario *s = load_yaml(yaml);
  free(yaml);
  fb_fe_hull *h = NULL;
  fb_mat *K = NULL, *M = NULL, *kr = NULL, *mr = NULL;
  REQUIRE(fb_vehicle_fe_hull(s, &h, &err), &err);
  REQUIRE(fb_fem_assemble(h->mesh, &h->props, h->mass_kind, &K, &M, &err), &err);
  size_t nodes[64];
  CHECK(h->nattach + h->nload + 4 <= 64);
  const size_t nn = interface_nodes(h, nodes), d = 6 * nn;
  size_t *keep = malloc(d * sizeof *keep);
  double *k = malloc(d * d * sizeof *k), *m = malloc(d * d * sizeof *m);
  for (size_t i = 0; i < d; ++i)
    keep[i] = 6 * nodes[i / 6] + i % 6;
  REQUIRE(fb_fem_guyan(K, M, keep, d, k, m, &err), &err);
  char path[4096];
  snprintf(path, sizeof path, "%s/apc6x6_reduced_K.mtx", dir);
  REQUIRE(fb_mat_new_dense(d, d, k, &kr, &err), &err);
  REQUIRE(fb_mat_write_mtx(kr, path, &err), &err);
  snprintf(path, sizeof path, "%s/apc6x6_reduced_M.mtx", dir);
  REQUIRE(fb_mat_new_dense(d, d, m, &mr, &err), &err);
  REQUIRE(fb_mat_write_mtx(mr, path, &err), &err);
  snprintf(path, sizeof path, "%s/apc6x6_reduced_nodes.csv", dir);
  write_nodes(path, h->mesh, nodes, nn, "123456");
  if (with_dmig) {
    snprintf(path, sizeof path, "%s/apc6x6_reduced_grids.csv", dir);
    write_nodes(path, h->mesh, nodes, nn, NULL);
    long ids[64];
    for (size_t i = 0; i < nn; ++i)
      ids[i] = fb_mesh_node_id(h->mesh, nodes[i]);
    snprintf(path, sizeof path, "%s/apc6x6_reduced.pch", dir);
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (fp) {
      write_dmig_free(fp, "KAAX", k, d, ids);
      write_dmig_free(fp, "MAAX", m, d, ids);
      CHECK(fclose(fp) == 0);
    }
  }
  fprintf(stderr, "wrote the superelement of %zu nodes (%zu DOFs) into %s\n", nn, d, dir);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mat_free(&kr);
  fb_mat_free(&mr);
  free(keep);
  free(k);
  free(m);
  fb_fe_hull_free(&h);
  fb_scenario_free(&s);
}

/* The two scenarios and their hulls. */
typedef struct pair {
  fb_scenario *s[2]; /* the mesh, the superelement */
  fb_fe_hull *h[2];
} pair;

static void pair_free(pair *p)
{
  for (int i = 0; i < 2; ++i) {
    fb_fe_hull_free(&p->h[i]);
    fb_scenario_free(&p->s[i]);
  }
}

/* The structure's mass properties (fb_fem_mesh_mass_properties: the
 * shells' element by element, the superelement's r' M r): Guyan keeps
 * the rigid-body motions in its subspace (T r_kept = r exactly, as
 * K r = 0), so r' M_red r = r' M r, equal to the rounding of the file's
 * 17 digits and of the sums: 1e-9 of the mass, of the hull's length
 * (5 m) for the centre, of the largest inertia for the tensor. */
static void test_mass(const pair *p)
{
  fb_err err;
  double mass[2], cg[2][3], in[2][9];
  for (int i = 0; i < 2; ++i)
    REQUIRE(fb_fem_mesh_mass_properties(p->h[i]->mesh, &p->h[i]->props, p->h[i]->mass_kind,
                                        &mass[i], cg[i], in[i], &err),
            &err);
  fprintf(stderr, "mass %.10g / %.10g kg, Ixx %.10g / %.10g, Iyy %.10g / %.10g kg m^2\n",
          mass[0], mass[1], in[0][0], in[1][0], in[0][4], in[1][4]);
  CHECK(fabs(mass[0] - mass[1]) <= 1e-9 * mass[0]);
  for (int k = 0; k < 3; ++k)
    CHECK(fabs(cg[0][k] - cg[1][k]) <= 1e-9 * 5.0);
  for (int k = 0; k < 9; ++k)
    CHECK(fabs(in[0][k] - in[1][k]) <= 1e-9 * in[0][8]);
}

/* The stiffness each interface point off the suspension sees (a mount's,
 * an edge end's: vertical, the suspension points' nodes held), mesh
 * against superelement. Guyan's K_red is the exact Schur complement, so
 * the two differ only by the file's 17 digits and the solves' rounding,
 * amplified by the condition number of the held structure (about 1e6 for
 * a steel box of 8.5 mm plates meshed at 0.3 m): 1e-7 relative. */
static void test_statics(const pair *p)
{
  fb_err err;
  double worst = 0.0;
  for (size_t a = p->s[0]->ncorners; a < p->h[0]->nattach + 4; ++a) {
    const size_t n0 = a < p->h[0]->nattach ? p->h[0]->attach_node[a]
                                           : p->h[0]->edge_node[a - p->h[0]->nattach];
    const size_t n1 = a < p->h[1]->nattach ? p->h[1]->attach_node[a]
                                           : p->h[1]->edge_node[a - p->h[1]->nattach];
    double k0 = 0, k1 = 0;
    REQUIRE(fb_fe_hull_point_stiffness(p->h[0], p->s[0]->ncorners, n0, &k0, &err), &err);
    REQUIRE(fb_fe_hull_point_stiffness(p->h[1], p->s[1]->ncorners, n1, &k1, &err), &err);
    fprintf(stderr, "point %zu: node %ld: %.10g N/m (mesh) vs %.10g N/m (superelement)\n", a,
            fb_mesh_node_id(p->h[0]->mesh, n0), k0, k1);
    CHECK(fb_mesh_node_id(p->h[0]->mesh, n0) == fb_mesh_node_id(p->h[1]->mesh, n1));
    worst = fmax(worst, fabs(k1 - k0) / k0);
  }
  fprintf(stderr, "statics: largest relative difference %.3g\n", worst);
  CHECK(worst <= 1e-7);
}

/* Free-free frequencies: six rigid-body modes on each, and each elastic
 * one of the superelement at or above the mesh's (Rayleigh-Ritz: Guyan's
 * T spans a subspace of the mesh's motions; Courant-Fischer), to the
 * solvers' 1e-9. */
static void test_free_modes(const pair *p, double *first_elastic)
{
  fb_err err;
  enum { N = 14 };
  double f[2][N];
  size_t nrigid[2];
  for (int i = 0; i < 2; ++i)
    REQUIRE(fb_fe_hull_free_modes(p->h[i], N, f[i], &nrigid[i], &err), &err);
  CHECK(nrigid[0] == 6 && nrigid[1] == 6);
  for (size_t k = 6; k < N; ++k) {
    fprintf(stderr, "free-free mode %zu: %.6g Hz (mesh) <= %.6g Hz (superelement)\n", k + 1,
            f[0][k], f[1][k]);
    CHECK(f[1][k] >= f[0][k] * (1 - 1e-9));
  }
  *first_elastic = f[0][6];
}

/* The first fixed-interface frequency of the mesh: (K_oo, M_oo) with the
 * interface's DOFs held; Guyan's error in a mode at f is of the order of
 * (f / f_c)^2 (Geradin & Rixen, Mechanical Vibrations, 3rd ed., sec.
 * 6.4: the static modes omit the inertia of the condensed DOFs, whose
 * dynamic response departs from the static by (f / f_c)^2). */
static double fixed_interface_hz(const pair *p)
{
  fb_err err;
  fb_mat *K = NULL, *M = NULL, *koo = NULL, *moo = NULL;
  const fb_fe_hull *h = p->h[0];
  REQUIRE(fb_fem_assemble(h->mesh, &h->props, h->mass_kind, &K, &M, &err), &err);
  size_t nodes[64];
  const size_t nn = interface_nodes(h, nodes), n = fb_mat_nrows(K);
  size_t *fixed = malloc(6 * nn * sizeof *fixed), *keep = malloc(n * sizeof *keep);
  for (size_t i = 0; i < 6 * nn; ++i)
    fixed[i] = 6 * nodes[i / 6] + i % 6;
  REQUIRE(fb_fem_free_dofs(n, fixed, 6 * nn, keep, &err), &err);
  REQUIRE(fb_fem_submatrix(K, keep, n - 6 * nn, &koo, &err), &err);
  REQUIRE(fb_fem_submatrix(M, keep, n - 6 * nn, &moo, &err), &err);
  double f = 0;
  size_t nrigid = 0;
  REQUIRE(fb_fe_hull_frequencies(koo, moo, 1, NULL, &f, &nrigid, NULL, &err), &err);
  CHECK(nrigid == 0);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mat_free(&koo);
  fb_mat_free(&moo);
  free(fixed);
  free(keep);
  return f;
}

/* The vehicle's undamped modes below the hull's first elastic one: the
 * same modes, each at most (f / f_c)^2 higher on the superelement
 * (fixed_interface_hz), and never lower beyond the solvers' 1e-6
 * (the vehicle's modes come from the block diagram's Jacobian). */
static void test_vehicle_modes(const pair *p, double hull_hz, double fc)
{
  fb_err err;
  fb_mode *m[2] = {NULL, NULL};
  size_t n[2], nstatic[2];
  for (int i = 0; i < 2; ++i)
    REQUIRE(fb_vehicle_modes(p->s[i], FB_SYSTEM_FLEXIBLE, 1, &m[i], &n[i], &nstatic[i], &err),
            &err);
  size_t compared = 0;
  for (size_t k = 0; k < n[0] && k < n[1] && m[0][k].freq_hz < hull_hz; ++k) {
    const double f0 = m[0][k].freq_hz, f1 = m[1][k].freq_hz, bound = (f0 / fc) * (f0 / fc);
    fprintf(stderr,
            "vehicle mode %zu %-28s %.6g Hz (mesh), %.6g Hz (superelement): %+.2e, "
            "bound %.2e\n",
            k + 1, m[0][k].description, f0, f1, (f1 - f0) / f0, bound);
    CHECK(f1 >= f0 * (1 - 1e-6) && f1 - f0 <= bound * f0 + 1e-6 * f0);
    ++compared;
  }
  CHECK(compared >= 6);
  free(m[0]);
  free(m[1]);
}

/* A run over a shortened bump (bump at 1 s, 0.5 m long, 3 s): each
 * output of the superelement's run within tol of the mesh's range, tol
 * Guyan's error at the bump's frequency V / L, (V / L / f_c)^2
 * (fixed_interface_hz): the vehicle's response is in that band, and
 * the superelement's modes there are off by at most that much. */
static void test_run(const pair *p, double fc)
{
  fb_err err;
  const double band = p->s[0]->speed / 0.5, tol = (band / fc) * (band / fc);
  fprintf(stderr, "run: the bump's frequency %.3g Hz, tolerance %.3g of each range\n", band,
          tol);
  fb_result *r[2] = {NULL, NULL};
  for (int i = 0; i < 2; ++i) {
    fb_scenario *s = NULL;
    REQUIRE(fb_scenario_clone(p->s[i], &s, &err), &err);
    road_bump(s)->first_contact = 1.0;
    road_bump(s)->length = 0.5;
    s->t_end = 3.0;
    REQUIRE(fb_vehicle_simulate(s, FB_SYSTEM_FLEXIBLE, &r[i], &err), &err);
    fb_scenario_free(&s);
  }
  check_close(r[0], r[1], tol, "run, superelement vs mesh");
  fb_result_free(&r[0]);
  fb_result_free(&r[1]);
}

/* The same matrices as a DMIG punch file (free field, 17 digits): the
 * same hull, its free-free frequencies equal the Matrix Market files' to
 * the solver's 1e-9. */
static void test_dmig(const char *dir)
{
  fb_err err;
  fb_scenario *s[2];
  fb_fe_hull *h[2] = {NULL, NULL};
  double f[2][12];
  size_t nrigid[2];
  for (int i = 0; i < 2; ++i) {
    char *yaml = reduced_yaml(dir, i);
    s[i] = load_yaml(yaml);
    free(yaml);
    REQUIRE(fb_vehicle_fe_hull(s[i], &h[i], &err), &err);
    REQUIRE(fb_fe_hull_free_modes(h[i], 12, f[i], &nrigid[i], &err), &err);
  }
  double worst = 0;
  for (size_t k = 6; k < 12; ++k)
    worst = fmax(worst, fabs(f[1][k] - f[0][k]) / f[0][k]);
  fprintf(stderr, "DMIG against Matrix Market: free-free frequencies within %.2g\n", worst);
  CHECK(nrigid[1] == 6 && worst <= 1e-9);
  char what[512];
  fb_scenario_hull_describe(s[1], what, sizeof what);
  CHECK(strstr(what, "DMIG") != NULL);
  for (int i = 0; i < 2; ++i) {
    fb_fe_hull_free(&h[i]);
    fb_scenario_free(&s[i]);
  }
}

int main(int argc, char **argv)
{
  if (argc == 3 && !strcmp(argv[1], "--write-example")) {
    write_reduced(argv[2], 0);
    return check_report(__FILE__);
  }
  const char *dir = test_tmpdir();
  write_reduced(dir, 1);
  pair p = {{NULL, NULL}, {NULL, NULL}};
  char *yaml = twin_yaml();
  p.s[0] = load_yaml(yaml);
  free(yaml);
  yaml = reduced_yaml(dir, 0);
  p.s[1] = load_yaml(yaml);
  free(yaml);
  test_dmig(dir);
  fb_err err;
  for (int i = 0; i < 2; ++i)
    REQUIRE(fb_vehicle_fe_hull(p.s[i], &p.h[i], &err), &err);
  CHECK(fb_scenario_hull_source(p.s[1]) == &fb_hull_source_reduced);
  test_mass(&p);
  test_statics(&p);
  double hull_hz = 0;
  test_free_modes(&p, &hull_hz);
  const double fc = fixed_interface_hz(&p);
  fprintf(stderr, "first fixed-interface mode of the mesh: %.6g Hz\n", fc);
  test_vehicle_modes(&p, hull_hz, fc);
  test_run(&p, fc);
  pair_free(&p);
  return check_report(__FILE__);
}
