/* SPDX-License-Identifier: BSD-3-Clause */
/* A deck's added masses (src/fem/inp.c): MASS elements with *MASS and
 * *NONSTRUCTURAL MASS, each against an answer of its own:
 *   1. a two-element plate with point masses and non-structural masses
 *      per area and in total: its mass, centre of mass and inertia from
 *      the matrix and element by element, against the sums written out
 *      here (plates of uniform areal density, point masses m r r');
 *   2. the deck written back (MASS elements, the non-structural mass
 *      smeared into the density) reads as the same K and M;
 *   3. the hull of examples/truck4x4.yaml as built (its structure and
 *      its battery, hull.masses) written as a deck and read back: the
 *      same K and M, mass, centre of mass and inertia as the hull's;
 *   4. a mass per volume as the same mass per area times the thickness;
 *   5. bad decks refused at the line that is wrong. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "tmpdir.h"

/* Nodes 1-6 on a 2 m x 1 m plate in z = 0, two 1 m x 1 m S4 elements;
 * 10 mm steel. Element 2 (set RIGHT) carries 20 kg/m^2, both (EALL) a
 * total of 10 kg (5 kg/m^2 each); MASS element 11 (set TIP) has 100 kg on
 * node 1, elements 12 and 13 (set END) 25 kg each on nodes 3 and 6. */
static const char plate_deck[] = "*NODE\n"
                                 "1, 0, 0, 0\n"
                                 "2, 1, 0, 0\n"
                                 "3, 2, 0, 0\n"
                                 "4, 0, 1, 0\n"
                                 "5, 1, 1, 0\n"
                                 "6, 2, 1, 0\n"
                                 "*ELEMENT, TYPE=S4, ELSET=EALL\n"
                                 "1, 1, 2, 5, 4\n"
                                 "2, 2, 3, 6, 5\n"
                                 "*ELSET, ELSET=RIGHT\n"
                                 "2\n"
                                 "*ELEMENT, TYPE=MASS, ELSET=TIP\n"
                                 "11, 1\n"
                                 "*ELEMENT, TYPE=MASS, ELSET=END\n"
                                 "12, 3\n"
                                 "13, 6\n"
                                 "*MATERIAL, NAME=STEEL\n"
                                 "*ELASTIC\n"
                                 "210e9, 0.3\n"
                                 "*DENSITY\n"
                                 "7850\n"
                                 "*SHELL SECTION, ELSET=EALL, MATERIAL=STEEL\n"
                                 "0.01\n"
                                 "*MASS, ELSET=TIP\n"
                                 "100\n"
                                 "*MASS, ELSET=END\n"
                                 "25\n"
                                 "*NONSTRUCTURAL MASS, ELSET=RIGHT, UNITS=MASS PER AREA\n"
                                 "20\n"
                                 "*NONSTRUCTURAL MASS, ELSET=EALL, UNITS=TOTAL MASS\n"
                                 "10\n";

static const fb_shell_props base = {210e9, 0.3, 7850, 0.01, 0.0, 0.0};

/* The plate's properties by hand: two squares of areal density s1, s2
 * (kg/m^2; centroids (0.5, 0.5), (1.5, 0.5)), each with the rotary
 * inertia s t^2 / 12 per area (the smeared mass's, fem.h) on each of its
 * nodes' three rotations (src/fem/shell.c's mass matrix gives the
 * drilling rotation the same), and three point masses. Inertia about the
 * centre of mass c: a unit square of density s about its centroid has
 * s / 12 about x and y, s / 6 about z (Ixx = int y^2 dA = 1/12). The
 * consistent mass matrix of the bilinear shape functions reproduces
 * these: rigid-body fields are linear. */
static void plate_by_hand(double *mass, double *cg, double *inertia)
{
  const double t = 0.01, rho_t = 7850 * t;
  const double s[2] = {rho_t + 5.0, rho_t + 20.0 + 5.0},
               sc[2][3] = {{0.5, 0.5, 0}, {1.5, 0.5, 0}};
  const double pm[3] = {100, 25, 25}, px[3][3] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}};
  double m = 0, first[3] = {0, 0, 0};
  for (int k = 0; k < 2; ++k) {
    m += s[k];
    for (int a = 0; a < 3; ++a)
      first[a] += s[k] * sc[k][a];
  }
  for (int k = 0; k < 3; ++k) {
    m += pm[k];
    for (int a = 0; a < 3; ++a)
      first[a] += pm[k] * px[k][a];
  }
  for (int a = 0; a < 3; ++a)
    cg[a] = first[a] / m;
  memset(inertia, 0, 9 * sizeof *inertia);
  /* Parallel axes: each part's own inertia plus m (|d|^2 I - d d'). */
  for (int k = 0; k < 5; ++k) {
    const double mk = k < 2 ? s[k] : pm[k - 2];
    const double *x = k < 2 ? sc[k] : px[k - 2];
    const double d[3] = {x[0] - cg[0], x[1] - cg[1], x[2] - cg[2]};
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        inertia[3 * i + j] += mk * ((i == j ? dd : 0.0) - d[i] * d[j]);
    if (k < 2) {
      const double rotary = mk * t * t / 12.0;
      inertia[0] += mk / 12.0 + rotary;
      inertia[4] += mk / 12.0 + rotary;
      inertia[8] += mk / 6.0 + rotary;
    }
  }
  *mass = m;
}

/* Relative agreement of two sets of mass properties. */
static void check_props(const double *m1, const double *c1, const double *i1, const double *m2,
                        const double *c2, const double *i2, double tol)
{
  CHECK_NEAR(*m1, *m2, tol * *m2);
  double scale = 0.0;
  for (int k = 0; k < 9; ++k)
    scale = fmax(scale, fabs(i2[k]));
  for (int k = 0; k < 3; ++k)
    CHECK_NEAR(c1[k], c2[k], tol * (1.0 + fabs(c2[k])));
  for (int k = 0; k < 9; ++k)
    CHECK_NEAR(i1[k], i2[k], tol * scale);
}

typedef struct mat_cmp {
  const fb_mat *other;
  double worst;
} mat_cmp;

static void visit(void *ctx, size_t i, size_t j, double v)
{
  mat_cmp *c = ctx;
  c->worst = fmax(c->worst, fabs(v - fb_mat_get(c->other, i, j)));
}

/* max |a - b| over both patterns, relative to max |a|. */
static double mat_difference(const fb_mat *a, const fb_mat *b)
{
  if (fb_mat_nrows(a) != fb_mat_nrows(b) || fb_mat_ncols(a) != fb_mat_ncols(b))
    return INFINITY;
  mat_cmp ab = {b, 0.0}, ba = {a, 0.0}, scale = {NULL, 0.0};
  fb_mat_foreach(a, visit, &ab);
  fb_mat_foreach(b, visit, &ba);
  const size_t n = fb_mat_nnz(a);
  size_t *r = malloc(n * sizeof *r), *c = malloc(n * sizeof *c);
  double *v = malloc(n * sizeof *v);
  CHECK(r && c && v);
  if (r && c && v)
    for (size_t k = 0, got = fb_mat_triplets(a, r, c, v); k < got; ++k)
      scale.worst = fmax(scale.worst, fabs(v[k]));
  free(r);
  free(c);
  free(v);
  return fmax(ab.worst, ba.worst) / scale.worst;
}

static fb_mesh *read_deck(const char *text, fb_err *err)
{
  fb_mesh *m = NULL;
  const int rc = fb_mesh_read_inp_string(text, strlen(text), "deck.inp", &m, NULL, err);
  if (rc)
    fprintf(stderr, "read: %s\n", err->msg);
  return m;
}

/* 1 and 2: the plate against the hand sums, and written back. Round-off
 * of sums of a few dozen terms: 1e-12 relative. */
static void test_plate(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_mesh *m = read_deck(plate_deck, &err);
  CHECK(m && fb_mesh_npoint_masses(m) == 3 && fb_mesh_nelements(m) == 2);
  if (!m)
    return;
  CHECK(fb_mesh_point_mass_id(m, 0) == 11 && fb_mesh_point_mass(m, 0) == 100.0);
  CHECK(fb_mesh_element_nonstructural(m, 0) == 5.0 &&
        fb_mesh_element_nonstructural(m, 1) == 25.0);
  double mh, ch[3], ih[9], mm, cm[3], im[9], me, ce[3], ie[9];
  plate_by_hand(&mh, ch, ih);
  fb_mat *K = NULL, *M = NULL;
  CHECK(fb_fem_assemble(m, &base, FB_MASS_CONSISTENT, &K, &M, &err) == FB_OK);
  CHECK(fb_fem_mass_properties(m, M, &mm, cm, im, &err) == FB_OK);
  CHECK(fb_fem_mesh_mass_properties(m, &base, FB_MASS_CONSISTENT, &me, ce, ie, &err) == FB_OK);
  check_props(&mm, cm, im, &mh, ch, ih, 1e-12);
  check_props(&me, ce, ie, &mh, ch, ih, 1e-12);

  char path[512];
  test_tmp_path("plate.inp", path, sizeof path);
  CHECK(fb_mesh_write_inp(m, NULL, path, &err) == FB_OK);
  fb_mesh *back = NULL;
  CHECK(fb_mesh_read_inp(path, &back, NULL, &err) == FB_OK);
  fb_mat *K2 = NULL, *M2 = NULL;
  CHECK(back && fb_fem_assemble(back, &base, FB_MASS_CONSISTENT, &K2, &M2, &err) == FB_OK);
  CHECK(back && fb_mesh_npoint_masses(back) == 3 &&
        fb_mesh_element_nonstructural(back, 1) == 0.0);
  /* The density written to 17 digits: rho + nsm / t reads back as the
   * same mass to round-off. */
  CHECK(K2 && mat_difference(K, K2) <= 1e-14);
  CHECK(M2 && mat_difference(M, M2) <= 1e-14);
  fb_mat_free(&K2);
  fb_mat_free(&M2);
  fb_mesh_free(&back);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mesh_free(&m);
}

/* 3: the truck's hull as built, through a deck. The deck's coordinates
 * are written to 15 significant digits: 1e-12 relative covers them. */
static void test_hull_round_trip(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  fb_fe_hull *h = NULL;
  fb_mesh *built = NULL, *back = NULL;
  CHECK(fb_scenario_load("../examples/truck4x4.yaml", &s, &err) == FB_OK);
  CHECK(s && fb_vehicle_fe_hull(s, &h, &err) == FB_OK);
  CHECK(h && h->npoint_masses == 1 && fb_fe_hull_mesh_as_built(h, &built, &err) == FB_OK);
  char path[512];
  test_tmp_path("hull.inp", path, sizeof path);
  CHECK(built && fb_mesh_write_inp(built, &h->props, path, &err) == FB_OK);
  CHECK(fb_mesh_read_inp(path, &back, NULL, &err) == FB_OK);
  fb_mat *K = NULL, *M0 = NULL, *M = NULL, *K2 = NULL, *M2 = NULL;
  CHECK(h && fb_fe_hull_matrices(h, &K, &M0, &err) == FB_OK);
  CHECK(h && fb_fe_hull_mass_matrix(h, &M, &err) == FB_OK);
  CHECK(back && fb_fem_assemble(back, &h->props, h->mass_kind, &K2, &M2, &err) == FB_OK);
  CHECK(K && K2 && mat_difference(K, K2) <= 1e-12);
  CHECK(M && M2 && mat_difference(M, M2) <= 1e-12);
  fb_hull_mass_props p = {0};
  double m2 = 0.0, c2[3] = {0}, i2[9] = {0};
  CHECK(h && fb_fe_hull_mass_props(h, 1, &p, &err) == FB_OK);
  CHECK(back &&
        fb_fem_mesh_mass_properties(back, &h->props, h->mass_kind, &m2, c2, i2, &err) == FB_OK);
  check_props(&m2, c2, i2, &p.mass, p.cg, p.inertia, 1e-12);
  /* The battery is in: 300 kg more than the structure. */
  fb_hull_mass_props p0 = {0};
  CHECK(h && fb_fe_hull_mass_props(h, 0, &p0, &err) == FB_OK);
  CHECK_NEAR(m2 - p0.mass, 300.0, 1e-9 * m2);
  fb_mat_free(&K);
  fb_mat_free(&M0);
  fb_mat_free(&M);
  fb_mat_free(&K2);
  fb_mat_free(&M2);
  fb_mesh_free(&back);
  fb_mesh_free(&built);
  fb_fe_hull_free(&h);
  fb_scenario_free(&s);
}

/* The variant of plate_deck (to NULL: to its end) refused with a message
 * that has want (its "deck.inp:LINE: " included). */
/* plate_deck with the text from `from` up to `to` replaced by with,
 * into text (size bytes); 0 if from or to is not there. */
static int variant(const char *from, const char *to, const char *with, char *text, size_t size)
{
  const char *a = strstr(plate_deck, from);
  const char *b = a ? (to ? strstr(a, to) : a + strlen(a)) : NULL;
  CHECK(a && b);
  if (!a || !b)
    return 0;
  snprintf(text, size, "%.*s%s%s", (int)(a - plate_deck), plate_deck, with, b);
  return 1;
}

static void check_bad(const char *from, const char *to, const char *with, const char *want)
{
  char text[4096];
  if (!variant(from, to, with, text, sizeof text))
    return;
  fb_err err;
  fb_err_clear(&err);
  fb_mesh *m = NULL;
  CHECK(fb_mesh_read_inp_string(text, strlen(text), "deck.inp", &m, NULL, &err) == FB_EPARSE);
  CHECK(m == NULL);
  if (!strstr(err.msg, want)) {
    fprintf(stderr, "want '%s', got '%s'\n", want, err.msg);
    CHECK(0);
  }
  fb_mesh_free(&m);
}

/* 5: line numbers counted in plate_deck (line 14 is "11, 1", 25
 * "*MASS, ELSET=TIP", 29 the first *NONSTRUCTURAL MASS). */
static void test_errors(void)
{
  check_bad("11, 1\n", "*ELEMENT, TYPE=MASS, ELSET=END", "11, 1, 2\n",
            "deck.inp:14: MASS element 11 has 2 nodes, not 1");
  check_bad("*MASS, ELSET=TIP\n100", "\n*MASS, ELSET=END", "*MASS, ELSET=TIP\n-100",
            "deck.inp:26: *MASS: mass -100 is negative");
  check_bad("*MASS, ELSET=TIP\n", "100", "*MASS, ELSET=TOP\n",
            "deck.inp:25: *MASS names element set 'TOP', which is not defined");
  check_bad("*MASS, ELSET=TIP\n", "100", "*MASS, ELSET=RIGHT\n",
            "deck.inp:25: *MASS names element set 'RIGHT', which holds no MASS elements");
  check_bad("*MASS, ELSET=END\n25\n", "*NONSTRUCTURAL", "",
            "deck.inp:16: MASS element 12 has no *MASS");
  check_bad("*MASS, ELSET=END\n25\n", "*NONSTRUCTURAL",
            "*MASS, ELSET=END\n25\n*MASS, ELSET=END\n1\n",
            "deck.inp:29: MASS element 12 is given its mass twice (here and line 27)");
  check_bad("13, 6\n", "*MATERIAL", "13, 60\n",
            "deck.inp:17: element 13 refers to node 60, which is not defined");
  check_bad("13, 6\n", "*MATERIAL", "2, 6\n", "deck.inp:17: element id 2 is defined twice");
  check_bad("*MASS, ELSET=END\n", "*NONSTRUCTURAL", "*MASS, ELSET=END, ALPHA=1\n",
            "deck.inp:27: parameter 'ALPHA' of *MASS is not supported");
  check_bad("ELSET=RIGHT, UNITS=MASS PER AREA\n20", "\n*NONSTRUCTURAL",
            "ELSET=RIGHT, UNITS=MASS PER AREA\n-20",
            "deck.inp:30: *NONSTRUCTURAL MASS: mass -20 is negative");
  check_bad("ELSET=RIGHT, UNITS=MASS PER AREA", "\n20", "ELSET=LEFT, UNITS=MASS PER AREA",
            "deck.inp:29: *NONSTRUCTURAL MASS names element set 'LEFT', which is not defined");
  check_bad(
      "ELSET=RIGHT, UNITS=MASS PER AREA", "\n20", "ELSET=TIP, UNITS=MASS PER AREA",
      "deck.inp:29: *NONSTRUCTURAL MASS names element set 'TIP', which holds MASS elements");
  check_bad(
      "UNITS=MASS PER AREA\n20", "\n*NONSTRUCTURAL",
      "UNITS=MASS PER AREA\n1e308\n*NONSTRUCTURAL MASS, ELSET=RIGHT, UNITS=MASS PER AREA\n"
      "1e308",
      "deck.inp:31: element 2: non-structural mass 1e+308 kg/m^2 (inf in all) is not >= 0");
  check_bad("ELSET=RIGHT, UNITS=MASS PER AREA", "\n20", "ELSET=RIGHT, UNITS=MASS PER LENGTH",
            "deck.inp:29: *NONSTRUCTURAL MASS, UNITS=MASS PER LENGTH is not supported");
  check_bad("ELSET=RIGHT, UNITS=MASS PER AREA", "\n20", "ELSET=RIGHT",
            "deck.inp:29: *NONSTRUCTURAL MASS needs UNITS=");
  /* A mass per volume needs the section's thickness: without the section
   * (two lines less), at the keyword's line. */
  check_bad(
      "*SHELL SECTION, ELSET=EALL", "*NONSTRUCTURAL MASS, ELSET=EALL",
      "*MASS, ELSET=TIP\n100\n*MASS, ELSET=END\n25\n"
      "*NONSTRUCTURAL MASS, ELSET=RIGHT, UNITS=MASS PER VOLUME\n2000\n",
      "deck.inp:27: *NONSTRUCTURAL MASS, UNITS=MASS PER VOLUME: element 2 of set 'RIGHT' is "
      "in no *SHELL SECTION");
}

/* 2000 kg/m^3 of the 10 mm section is the 20 kg/m^2 of plate_deck. */
static void test_per_volume(void)
{
  char text[4096];
  if (!variant("UNITS=MASS PER AREA\n20", "\n*NONSTRUCTURAL", "UNITS=MASS PER VOLUME\n2000",
               text, sizeof text))
    return;
  fb_err err;
  fb_err_clear(&err);
  fb_mesh *m = read_deck(text, &err);
  CHECK(m && fabs(fb_mesh_element_nonstructural(m, 1) - 25.0) <= 1e-13 * 25.0);
  CHECK(m && fb_mesh_element_nonstructural(m, 0) == 5.0);
  fb_mesh_free(&m);
}

/* A total mass over elements of two sections is refused at its line. */
static void test_total_over_sections(void)
{
  const char *deck =
      "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 2, 0, 0\n4, 0, 1, 0\n5, 1, 1, 0\n"
      "6, 2, 1, 0\n*ELEMENT, TYPE=S4, ELSET=EALL\n1, 1, 2, 5, 4\n2, 2, 3, 6, 5\n"
      "*ELSET, ELSET=A\n1\n*ELSET, ELSET=B\n2\n*MATERIAL, NAME=STEEL\n*ELASTIC\n"
      "210e9, 0.3\n*DENSITY\n7850\n*SHELL SECTION, ELSET=A, MATERIAL=STEEL\n0.01\n"
      "*SHELL SECTION, ELSET=B, MATERIAL=STEEL\n0.02\n"
      "*NONSTRUCTURAL MASS, ELSET=EALL, UNITS=TOTAL MASS\n10\n";
  fb_err err;
  fb_err_clear(&err);
  fb_mesh *m = NULL;
  CHECK(fb_mesh_read_inp_string(deck, strlen(deck), "deck.inp", &m, NULL, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "deck.inp:24: *NONSTRUCTURAL MASS, UNITS=TOTAL MASS over element set "
                        "'EALL', whose elements are in more than one *SHELL SECTION") != NULL);
  fb_mesh_free(&m);
}

int main(void)
{
  test_plate();
  test_hull_round_trip();
  test_errors();
  test_per_volume();
  test_total_over_sections();
  test_tmpdir_remove();
  return check_report("test_inp_masses");
}
