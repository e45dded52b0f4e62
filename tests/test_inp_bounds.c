/* SPDX-License-Identifier: BSD-3-Clause */
/* Set references in Abaqus/CalculiX decks (src/fem/inp.c): a set that
 * names other sets holds each member once, in the order members first came,
 * however often the deck names them. A deck that names a large set
 * thousands of times ("ALL, ALL, ...") once expanded every reference before
 * removing the repeats: 1.7 GB for a 4.8 MB deck. The deck here is of that
 * shape, small enough that the old reader also finished; what is checked
 * is the sets' contents (CTest's TIMEOUT guards against a hang). Also the
 * mesh's sets themselves (src/fem/mesh.c): many sets found by name in any
 * case, repeats ignored, a clone that keeps doing so. And the bound on
 * System 2's hull at the generator (src/vehicle/hull_mesh.c) when its own
 * rows and divisions, not the density, make the mesh too large (the CLI's
 * schema caps them lower; tests/cli_limits.sh has the density and the
 * files). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "tmpdir.h"

/* The grid: NX x NY nodes, ids 1 .. NX NY, and its (NX - 1)(NY - 1) S4. */
#define NX 60
#define NY 50
#define NNODES (NX * NY)
#define NELEMS ((NX - 1) * (NY - 1))
/* Data lines of set references in each block, sixteen names a line. */
#define REF_LINES 200

static void write_grid(FILE *fp)
{
  fputs("*NODE, NSET=ALL\n", fp);
  for (int j = 0; j < NY; ++j)
    for (int i = 0; i < NX; ++i)
      fprintf(fp, "%d, %g, %g, 0\n", j * NX + i + 1, 0.01 * i, 0.01 * j);
  fputs("*ELEMENT, TYPE=S4, ELSET=EALL\n", fp);
  int e = 1;
  for (int j = 0; j + 1 < NY; ++j)
    for (int i = 0; i + 1 < NX; ++i) {
      const int a = j * NX + i + 1;
      fprintf(fp, "%d, %d, %d, %d, %d\n", e++, a, a + 1, a + 1 + NX, a + NX);
    }
}

/* REF_LINES lines of the names a and b in turn, sixteen a line. */
static void write_refs(FILE *fp, const char *a, const char *b)
{
  for (int l = 0; l < REF_LINES; ++l)
    for (int k = 0; k < 16; ++k)
      fprintf(fp, "%s%s", k % 2 ? b : a, k == 15 ? "\n" : ", ");
}

/* The deck: ALL and EALL name themselves over and over; BIG and EBIG name
 * ALL (EALL) and the first row EDGE (EEDGE) in turn, after ids of their
 * own (the last node, the last element) and across blocks; ROW names EDGE
 * before and after EDGE gains a member; GEN repeats GENERATE lines of the
 * odd ids, the even ones, then all. */
static int write_deck(const char *path)
{
  FILE *fp = fopen(path, "w");
  if (!fp)
    return 0;
  write_grid(fp);
  fprintf(fp, "*NSET, NSET=EDGE, GENERATE\n1, %d\n*ELSET, ELSET=EEDGE, GENERATE\n1, %d\n", NX,
          NX - 1);
  for (int block = 0; block < 3; ++block) {
    fputs("*NSET, NSET=ALL\n", fp);
    write_refs(fp, "ALL", "all");
    fputs("*ELSET, ELSET=EALL\n", fp);
    write_refs(fp, "EALL", "eall");
    fprintf(fp, "*NSET, NSET=BIG\n%d\n", NNODES);
    write_refs(fp, "EDGE", "ALL");
    fprintf(fp, "*ELSET, ELSET=EBIG\n%d\n", NELEMS);
    write_refs(fp, "EEDGE", "EALL");
  }
  fprintf(fp, "*NSET, NSET=ROW\nEDGE, EDGE\n*NSET, NSET=EDGE\n%d\n*NSET, NSET=ROW\nedge\n",
          NNODES);
  fputs("*NSET, NSET=GEN, GENERATE\n", fp);
  for (int k = 0; k < 3 * REF_LINES; ++k) {
    const int pass = k / REF_LINES; /* the odd ids, the even ones, all */
    fprintf(fp, "%d, %d, %d\n", pass == 1 ? 2 : 1, NNODES, pass == 2 ? 1 : 2);
  }
  return fclose(fp) == 0;
}

/* Set name of a kind holds exactly the ids want[0 .. n), in that order. */
static int set_is(const fb_mesh *m, int elements, const char *name, const long *want, size_t n)
{
  const size_t *items = NULL;
  size_t count = 0;
  if (!(elements ? fb_mesh_elset(m, name, &items, &count)
                 : fb_mesh_nset(m, name, &items, &count)))
    return 0;
  if (count != n)
    return 0;
  for (size_t k = 0; k < n; ++k) {
    const long id = elements ? fb_mesh_element_id(m, items[k]) : fb_mesh_node_id(m, items[k]);
    if (id != want[k])
      return 0;
  }
  return 1;
}

/* ids first, first + 1, ..., first + n - 1 into v. */
static long *id_run(long *v, long first, size_t n)
{
  for (size_t k = 0; k < n; ++k)
    v[k] = first + (long)k;
  return v;
}

static void test_repeated_references(void)
{
  char path[TEST_PATH_MAX];
  CHECK(write_deck(test_tmp_path("refs.inp", path, sizeof path)));
  fb_err err;
  fb_mesh *m = NULL;
  CHECK(fb_mesh_read_inp(path, &m, NULL, &err) == FB_OK);
  if (!m) {
    fprintf(stderr, "%s\n", err.msg);
    return;
  }
  long *want = malloc((NNODES + 1) * sizeof *want);
  if (!want) {
    fb_mesh_free(&m);
    CHECK(0);
    return;
  }
  CHECK(fb_mesh_nnsets(m) == 5 && fb_mesh_nelsets(m) == 3);
  CHECK(set_is(m, 0, "ALL", id_run(want, 1, NNODES), NNODES));
  CHECK(set_is(m, 1, "EALL", id_run(want, 1, NELEMS), NELEMS));
  /* BIG: its own id, then EDGE's, then the rest of ALL's, each once. */
  want[0] = NNODES;
  id_run(want + 1, 1, NNODES - 1);
  CHECK(set_is(m, 0, "BIG", want, NNODES));
  want[0] = NELEMS;
  id_run(want + 1, 1, NELEMS - 1);
  CHECK(set_is(m, 1, "EBIG", want, NELEMS));
  /* ROW took EDGE's new member when it named EDGE again. */
  id_run(want, 1, NX);
  want[NX] = NNODES;
  CHECK(set_is(m, 0, "EDGE", want, NX + 1));
  CHECK(set_is(m, 0, "ROW", want, NX + 1));
  for (size_t k = 0; k < NNODES; ++k)
    want[k] = k < NNODES / 2 ? 2 * (long)k + 1 : 2 * (long)(k - NNODES / 2) + 2;
  CHECK(set_is(m, 0, "GEN", want, NNODES));
  free(want);
  fb_mesh_free(&m);
}

/* A deck from a string; the message of a refusal into msg. */
static int read_deck(const char *deck, fb_mesh **m, char *msg, size_t size)
{
  fb_err err;
  const int rc = fb_mesh_read_inp_string(deck, strlen(deck), "x.inp", m, NULL, &err);
  snprintf(msg, size, "%s", rc ? err.msg : "");
  return rc;
}

#define QUAD                                                                                   \
  "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n5, 2, 0, 0\n"                        \
  "*ELEMENT, TYPE=S4\n1, 1, 2, 3, 4\n"

/* A set names only sets defined before it, itself included: its own name
 * in its first block is an error, as any set not defined yet; in a later
 * block it adds nothing. Members keep the order they first came in, across
 * the reader's batches of ids. */
static void test_reference_rules(void)
{
  char msg[FB_ERR_MSG_MAX];
  fb_mesh *m = NULL;
  CHECK(read_deck(QUAD "*NSET, NSET=A\n1, A\n", &m, msg, sizeof msg) == FB_EPARSE && !m);
  CHECK(strcmp(msg, "x.inp:10: node set 'A' names node set 'A', which is not defined") == 0);
  CHECK(read_deck(QUAD "*NSET, NSET=A\n2\n*NSET, NSET=T\n3, a, 1\n*NSET, NSET=a\n5, A, 4\n", &m,
                  msg, sizeof msg) == FB_OK);
  const long t[] = {3, 2, 1}, a[] = {2, 5, 4};
  CHECK(set_is(m, 0, "T", t, 3) && set_is(m, 0, "A", a, 3));
  fb_mesh_free(&m);

  /* 600 ids (more than one batch) of five nodes, then a set, then ids. */
  char *deck = malloc(4096);
  CHECK(deck != NULL);
  if (!deck)
    return;
  size_t len = (size_t)snprintf(deck, 4096, "%s*NSET, NSET=P\n4, 2\n*NSET, NSET=Q\n", QUAD);
  for (int k = 0; k < 600; ++k)
    len +=
        (size_t)snprintf(deck + len, 4096 - len, "%d%s", 5 - k % 3, k % 16 == 15 ? "\n" : ",");
  snprintf(deck + len, 4096 - len, "\nP, 1, 2\n");
  CHECK(read_deck(deck, &m, msg, sizeof msg) == FB_OK);
  const long q[] = {5, 4, 3, 2, 1};
  CHECK(set_is(m, 0, "Q", q, 5));
  free(deck);
  fb_mesh_free(&m);
}

/* The mesh's own sets: 1000 names found in another case, repeats within
 * and across calls ignored, and the same in a clone. */
static void test_mesh_sets(void)
{
  fb_err err;
  fb_mesh *m = NULL;
  CHECK(fb_mesh_new(&m, &err) == FB_OK);
  if (!m)
    return;
  for (long i = 0; i < 4; ++i)
    CHECK(fb_mesh_add_node(m, i + 1, (double)i, 0.0, 0.0, NULL, &err) == FB_OK);
  char name[32];
  for (size_t k = 0; k < 1000; ++k) {
    const size_t nodes[3] = {k % 4, (k + 1) % 4, k % 4};
    snprintf(name, sizeof name, "Set_%zu", k);
    CHECK(fb_mesh_add_nset(m, name, 3, nodes, &err) == FB_OK);
  }
  fb_mesh *c = NULL;
  CHECK(fb_mesh_clone(m, &c, &err) == FB_OK);
  const size_t more[4] = {3, 2, 1, 0};
  for (int pass = 0; pass < 2; ++pass) {
    fb_mesh *x = pass ? c : m;
    CHECK(fb_mesh_nnsets(x) == 1000);
    CHECK(fb_mesh_add_nset(x, "SET_7", 4, more, &err) == FB_OK);
    const long seven[] = {4, 1, 3, 2};
    CHECK(set_is(x, 0, "set_7", seven, 4));
    const long last[] = {4, 1};
    CHECK(set_is(x, 0, "SET_999", last, 2));
    CHECK(!fb_mesh_nset(x, "Set_1000", NULL, NULL));
  }
  fb_mesh_free(&c);
  fb_mesh_free(&m);
}

/* Rows and divisions of 150 make 97602 elements at density 1: refused
 * before anything is built on them, at the generator's key. */
static void test_generator_rows(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &s, &err) == FB_OK);
  if (!s)
    return;
  fb_hull_mesh_params p = s->hull_mesh;
  p.side_rows = p.nose_rows = p.nose_rung_divisions = 150;
  p.density = 1;
  fb_mesh *m = NULL;
  CHECK(fb_hull_mesh_generate(s, &p, &m, &err) == FB_EINVAL && !m);
  CHECK(PART_IS(&err, FB_PART_VEHICLE, 0, "hull_mesh"));
  CHECK(strstr(err.msg, "the generated mesh has 97602 elements, which would need about 6.4 GB "
                        "of memory for System 2 (about 64 KiB per element), more than the 4.3 "
                        "GB allowed (at most 65536 elements; ") == err.msg);
  fb_scenario_free(&s);
}

int main(void)
{
  test_repeated_references();
  test_reference_rules();
  test_mesh_sets();
  test_generator_rows();
  return check_report("test_inp_bounds");
}
