/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of shell meshes (flexbond/fem.h): building and accessors, ids,
 * node sets, fb_mesh_check, clone, the Abaqus deck reader and writer, and
 * the VTK XML writer. Files go to a fresh mkdtemp directory, removed at
 * the end. Expected values are hand-built meshes and hand-computed
 * geometry; comparisons of coordinates that went through %.17g are exact
 * (IEEE 754-2008, section 5.12.2: 17 significant digits round-trip every
 * binary64). */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "flexbond/fem.h"

#include "check.h"
#include "tmpdir.h"

static const char *root; /* the private directory (tmpdir.h) */

static const char *in_root(char *buf, size_t size, const char *name)
{
  snprintf(buf, size, "%s/%s", root, name);
  return buf;
}

static void write_bytes(const char *path, const char *data, size_t n)
{
  FILE *fp = fopen(path, "wb");
  if (!fp) {
    perror(path);
    return;
  }
  fwrite(data, 1, n, fp);
  fclose(fp);
}

static void write_text(const char *path, const char *text)
{
  write_bytes(path, text, strlen(text));
}

/* The whole file in fresh memory (NUL-terminated), or NULL. */
static char *slurp(const char *path)
{
  FILE *fp = fopen(path, "rb");
  if (!fp)
    return NULL;
  fseek(fp, 0, SEEK_END);
  const long n = ftell(fp);
  fseek(fp, 0, SEEK_SET);
  char *buf = malloc((size_t)n + 1);
  if (buf) {
    buf[fread(buf, 1, (size_t)n, fp)] = '\0';
  }
  fclose(fp);
  return buf;
}

/* Number of entries of root (a stray "*.tmp.PID" shows up here). */
static int count_entries(void)
{
  int n = 0;
  DIR *d = opendir(root);
  for (struct dirent *e = d ? readdir(d) : NULL; e; e = readdir(d))
    n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
  if (d)
    closedir(d);
  return n;
}

/* The message contains expect; prints it otherwise. */
static void check_msg(const fb_err *err, const char *expect)
{
  const char *shown = DESCRIBED(err);
  const int ok = strstr(shown, expect) != NULL;
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  expected \"%s\" in: %s\n", expect, shown);
}

/* A 2 x 1 strip of unit quads plus a triangle at its end, in the z = 0
 * plane, with user ids ten times the (1-based) position:
 *
 *   40 ---- 50 ---- 60
 *    |  E1  |  E2  |  \  E3
 *   10 ---- 20 ---- 30 - 70  (70 at (3, 0.5))
 */
static fb_mesh *strip_mesh(void)
{
  static const double xy[7][2] = {{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}, {3, 0.5}};
  fb_mesh *m = NULL;
  fb_err err;
  int rc = fb_mesh_new(&m, &err);
  for (size_t i = 0; i < 7 && !rc; ++i)
    rc = fb_mesh_add_node(m, 10 * (long)(i + 1), xy[i][0], xy[i][1], 0.0, NULL, &err);
  const size_t q1[4] = {0, 1, 4, 3}, q2[4] = {1, 2, 5, 4}, t3[3] = {2, 6, 5};
  if (!rc)
    rc = fb_mesh_add_element(m, 1, FB_ELEM_QUAD4, q1, &err);
  if (!rc)
    rc = fb_mesh_add_element(m, 2, FB_ELEM_QUAD4, q2, &err);
  if (!rc)
    rc = fb_mesh_add_element(m, 3, FB_ELEM_TRI3, t3, &err);
  CHECK(rc == FB_OK);
  return m;
}

/* ---- Building and accessors. */

static void test_build(void)
{
  fb_mesh *m = strip_mesh();
  CHECK(fb_mesh_nnodes(m) == 7);
  CHECK(fb_mesh_nelements(m) == 3);
  CHECK(fb_mesh_count(m, FB_ELEM_QUAD4) == 2);
  CHECK(fb_mesh_count(m, FB_ELEM_TRI3) == 1);
  const double *p = fb_mesh_node_xyz(m, 6);
  CHECK(p && p[0] == 3.0 && p[1] == 0.5 && p[2] == 0.0);
  CHECK(fb_mesh_node_id(m, 4) == 50);
  CHECK(fb_mesh_find_node_id(m, 50) == 4);
  CHECK(fb_mesh_find_node_id(m, 55) == -1);
  CHECK(fb_mesh_element_type(m, 2) == FB_ELEM_TRI3);
  CHECK(fb_mesh_element_id(m, 1) == 2);
  const size_t *nd = fb_mesh_element_nodes(m, 1);
  CHECK(nd && nd[0] == 1 && nd[1] == 2 && nd[2] == 5 && nd[3] == 4);
  /* Out of range. */
  CHECK(fb_mesh_node_xyz(m, 7) == NULL);
  CHECK(fb_mesh_node_id(m, 7) == -1);
  CHECK(fb_mesh_element_nodes(m, 3) == NULL);
  CHECK(fb_mesh_element_id(m, 3) == -1);
  CHECK(fb_mesh_nset_name(m, 0) == NULL);
  CHECK(fb_mesh_check(m, NULL) == FB_OK);

  size_t index = 99;
  CHECK(fb_mesh_add_node(m, 80, 4, 0, 0, &index, NULL) == FB_OK);
  CHECK(index == 7);
  fb_mesh_free(&m);
  CHECK(m == NULL);
  fb_mesh_free(&m);
  fb_mesh_free(NULL);
}

static void test_bad_arguments(void)
{
  fb_mesh *m = strip_mesh();
  fb_err err;
  CHECK(fb_mesh_add_node(m, 20, 5, 5, 5, NULL, &err) == FB_EINVAL);
  check_msg(&err, "node id 20 is defined twice");
  CHECK(fb_mesh_add_node(m, 0, 5, 5, 5, NULL, &err) == FB_EINVAL);
  check_msg(&err, "node id 0 is not positive");
  CHECK(fb_mesh_add_node(m, 90, 5, NAN, 5, NULL, &err) == FB_EINVAL);
  check_msg(&err, "node 90: coordinates");
  CHECK(fb_mesh_nnodes(m) == 7);
  CHECK(fb_mesh_find_node_id(m, 90) == -1);

  const size_t tri[3] = {0, 1, 4}, far[3] = {0, 1, 7};
  CHECK(fb_mesh_add_element(m, 2, FB_ELEM_TRI3, tri, &err) == FB_EINVAL);
  check_msg(&err, "element id 2 is defined twice");
  CHECK(fb_mesh_add_element(m, 9, FB_ELEM_TRI3, far, &err) == FB_EINVAL);
  check_msg(&err, "element 9: node index 7 out of range (the mesh has 7 nodes)");
  CHECK(fb_mesh_add_element(m, 9, (fb_elem_type)5, tri, &err) == FB_EINVAL);
  check_msg(&err, "invalid element type 5");
  CHECK(fb_mesh_add_element(m, -4, FB_ELEM_TRI3, tri, &err) == FB_EINVAL);
  CHECK(fb_mesh_add_element(m, 9, FB_ELEM_TRI3, NULL, &err) == FB_EINVAL);
  CHECK(fb_mesh_nelements(m) == 3);
  CHECK(fb_mesh_count(m, FB_ELEM_TRI3) == 1);
  fb_mesh_free(&m);
}

/* 1e5 nodes with scattered ids added in a scrambled order: every id is
 * found at its index and absent ids are not (exercises the table's
 * growth and collisions). */
static void test_many_ids(void)
{
  enum { N = 100000 };
  fb_mesh *m = NULL;
  fb_err err;
  const clock_t start = clock();
  int rc = fb_mesh_new(&m, &err);
  /* i -> (i * 7919) mod N is a permutation since 7919 is prime to N. */
  for (long i = 0; i < N && !rc; ++i) {
    const long k = (i * 7919) % N;
    rc = fb_mesh_add_node(m, 1000 + 64 * k, (double)k, 0, 0, NULL, &err);
  }
  CHECK(rc == FB_OK);
  int wrong = 0;
  for (long i = 0; i < N; ++i) {
    const long index = fb_mesh_find_node_id(m, 1000 + 64 * ((i * 7919) % N));
    wrong += index != i;
    wrong += fb_mesh_find_node_id(m, 1001 + 64 * i) != -1;
  }
  CHECK(wrong == 0);
  /* Hashing keeps this linear: about 0.05 s here even under the
   * sanitizers, while a table whose ids all collide degrades to quadratic
   * probing and takes some 30 s. 5 s separates the two safely. */
  const double seconds = (double)(clock() - start) / CLOCKS_PER_SEC;
  CHECK(seconds < 5.0);
  CHECK(fb_mesh_add_node(m, 1000 + 64 * 777, 0, 0, 0, NULL, &err) == FB_EINVAL);
  fb_mesh_free(&m);
}

static void test_find_node_at(void)
{
  fb_mesh *m = strip_mesh();
  /* (2.004, 0.003, 0) is 0.005 from node 30 (index 2), 0.999 from 20. */
  CHECK(fb_mesh_find_node_at(m, 2.004, 0.003, 0.0, 0.01) == 2);
  CHECK(fb_mesh_find_node_at(m, 2.004, 0.003, 0.0, 0.004) == -1);
  /* Within a wide tolerance, the nearest wins: (0.9, 0.9, 0) is
   * 0.141 from node 50 and 0.906 from node 40. */
  CHECK(fb_mesh_find_node_at(m, 0.9, 0.9, 0.0, 2.0) == 4);
  /* (0.5, 0, 0) is equally far from nodes 10 and 20: the lower index. */
  CHECK(fb_mesh_find_node_at(m, 0.5, 0.0, 0.0, 0.5) == 0);
  CHECK(fb_mesh_find_node_at(m, 0.0, 0.0, 0.0, 0.0) == 0);
  CHECK(fb_mesh_find_node_at(m, 0.0, 0.0, 0.0, -1.0) == -1);
  CHECK(fb_mesh_find_node_at(m, 0.0, 0.0, 0.0, NAN) == -1);
  fb_mesh_free(&m);
}

static void test_nsets(void)
{
  fb_mesh *m = strip_mesh();
  fb_err err;
  const size_t a[2] = {0, 3}, b[3] = {3, 2, 0};
  CHECK(fb_mesh_add_nset(m, "Fixed", 2, a, &err) == FB_OK);
  CHECK(fb_mesh_add_nset(m, "FIXED", 3, b, &err) == FB_OK);
  CHECK(fb_mesh_nnsets(m) == 1);
  CHECK(strcmp(fb_mesh_nset_name(m, 0), "Fixed") == 0);
  const size_t *nodes = NULL;
  size_t n = 0;
  CHECK(fb_mesh_nset(m, "fixed", &nodes, &n) == 1);
  /* Extension adds only the new node 2, after the first two. */
  CHECK(n == 3 && nodes[0] == 0 && nodes[1] == 3 && nodes[2] == 2);
  CHECK(fb_mesh_nset(m, "fix", &nodes, &n) == 0);

  CHECK(fb_mesh_add_nset(m, "empty_1", 0, NULL, &err) == FB_OK);
  CHECK(fb_mesh_nset(m, "EMPTY_1", &nodes, &n) == 1 && n == 0);
  CHECK(fb_mesh_nnsets(m) == 2);

  static const char *const bad[] = {"", "1abc", "a b", "a,b", "a\"b", "<x>"};
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
    CHECK(fb_mesh_add_nset(m, bad[k], 2, a, &err) == FB_EINVAL);
    check_msg(&err, "is invalid");
  }
  char long_name[90];
  memset(long_name, 'a', 81);
  long_name[81] = '\0';
  CHECK(fb_mesh_add_nset(m, long_name, 2, a, &err) == FB_EINVAL);
  long_name[80] = '\0';
  CHECK(fb_mesh_add_nset(m, long_name, 2, a, &err) == FB_OK);
  const size_t out_of_range[1] = {7};
  CHECK(fb_mesh_add_nset(m, "other", 1, out_of_range, &err) == FB_EINVAL);
  check_msg(&err, "node set 'other': node index 7 out of range");
  CHECK(fb_mesh_nset(m, "other", NULL, NULL) == 0);
  CHECK(fb_mesh_nnsets(m) == 3);
  fb_mesh_free(&m);
}

/* ---- fb_mesh_check. */

/* A mesh of nodes (ids 1..n) and one element over all of them (id 5). */
static fb_mesh *one_element(const double (*xyz)[3], size_t n, const size_t *nodes)
{
  fb_mesh *m = NULL;
  int rc = fb_mesh_new(&m, NULL);
  for (size_t i = 0; i < n && !rc; ++i)
    rc = fb_mesh_add_node(m, (long)i + 1, xyz[i][0], xyz[i][1], xyz[i][2], NULL, NULL);
  if (!rc)
    rc = fb_mesh_add_element(m, 5, n == 3 ? FB_ELEM_TRI3 : FB_ELEM_QUAD4, nodes, NULL);
  CHECK(rc == FB_OK);
  return m;
}

static void expect_check(fb_mesh *m, const char *expect)
{
  fb_err err;
  fb_err_clear(&err);
  const int rc = fb_mesh_check(m, &err);
  if (expect) {
    CHECK(rc == FB_EMODEL);
    check_msg(&err, expect);
    CHECK(strstr(err.msg, "nan") == NULL && strstr(err.msg, "inf") == NULL);
  } else {
    CHECK(rc == FB_OK);
    if (rc)
      fprintf(stderr, "  unexpected: %s\n", err.msg);
  }
  fb_mesh_free(&m);
}

static void test_check(void)
{
  static const size_t q[4] = {0, 1, 2, 3};
  const double square[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  expect_check(one_element(square, 4, q), NULL);

  fb_mesh *m = one_element(square, 4, q);
  fb_mesh_add_node(m, 17, 5, 5, 5, NULL, NULL);
  expect_check(m, "node 17 is used by no element");

  const size_t repeated[4] = {0, 1, 1, 3};
  expect_check(one_element(square, 4, repeated), "element 5 (S4) is degenerate: node 2 is "
                                                 "repeated");

  const double line[4][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  expect_check(one_element(line, 4, q), "element 5 (S4) is degenerate: area 0 m^2");

  /* Nodes all at one point: the whole mesh has a zero bounding box, so no
   * area limit but DBL_MIN (the warp test once printed "-nan mm"). */
  const double point[4][3] = {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {1, 2, 3}};
  expect_check(one_element(point, 4, q), "element 5 (S4) is degenerate: its nodes coincide");
  expect_check(one_element(point, 3, q), "element 5 (S3) is degenerate: its nodes coincide");
  /* Beyond 1e154 m an area overflows a double. */
  const double huge[4][3] = {{0, 0, 0}, {1e160, 0, 0}, {1e160, 1e160, 0}, {0, 1e160, 0}};
  expect_check(one_element(huge, 4, q), "element 5 (S4) is too large: its area overflows");

  /* An arrowhead: node 3 at (0.3, 0.3) makes the corner at it reentrant
   * while the diagonals still give a positive area 0.5 * |(c-a) x (d-b)|
   * = 0.5 * (0.3 * 1 + 0.3 * 1) = 0.3. */
  const double arrow[4][3] = {{0, 0, 0}, {1, 0, 0}, {0.3, 0.3, 0}, {0, 1, 0}};
  expect_check(one_element(arrow, 4, q), "element 5 (S4) is degenerate: not convex at node 3");
  /* A bow tie (nodes 3 and 4 swapped): area 0 by the diagonals. */
  const double bowtie[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  expect_check(one_element(bowtie, 4, q), "element 5 (S4) is degenerate: area 0 m^2");

  /* Warp: node 4 lifted 15 mm above the plane z = 0 of nodes 1-3; the
   * limit is 1e-2 * sqrt(2) m = 14.1 mm. A 14 mm lift passes. */
  const double warped[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.015}};
  expect_check(one_element(warped, 4, q),
               "element 5 (S4) is warped: node 4 is 15 mm off the plane of the other three");
  const double slight[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.014}};
  expect_check(one_element(slight, 4, q), NULL);

  /* Area limit 1e-12 * diag^2 = 2e-12 m^2 (the bounding box is the unit
   * square: diag^2 = 2): a sliver triangle of base 1 and height h has area
   * h / 2, so h = 1e-13 fails (5e-14) and h = 1e-11 passes (5e-12). */
  for (int pass = 0; pass < 2; ++pass) {
    const double h = pass ? 1e-11 : 1e-13;
    const double pts[7][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},  {0, 1, 0},
                              {0, 0, 0}, {1, 0, 0}, {0.5, h, 0}};
    fb_mesh *s = one_element(pts, 4, q);
    size_t t[3];
    for (int k = 0; k < 3; ++k)
      fb_mesh_add_node(s, 10 + k, pts[4 + k][0], pts[4 + k][1], pts[4 + k][2], &t[k], NULL);
    fb_mesh_add_element(s, 12, FB_ELEM_TRI3, t, NULL);
    expect_check(s, pass ? NULL : "element 12 (S3) is degenerate: area 5e-14 m^2");
  }

  m = one_element(square, 4, q);
  fb_mesh_add_nset(m, "EMPTY", 0, NULL, NULL);
  expect_check(m, "node set 'EMPTY' is empty");

  fb_mesh_new(&m, NULL);
  expect_check(m, "the mesh has no elements");
}

/* A warped element's user ids in the message: element 12 over nodes
 * 41-44, node 44 31 mm off the plane, in a mesh where it is the second
 * element. */
static void test_check_warp_ids(void)
{
  fb_mesh *m = strip_mesh();
  size_t nd[4];
  const double xyz[4][3] = {{0, 2, 0}, {1, 2, 0}, {1, 3, 0}, {0, 3, -0.031}};
  for (int k = 0; k < 4; ++k)
    fb_mesh_add_node(m, 41 + k, xyz[k][0], xyz[k][1], xyz[k][2], &nd[k], NULL);
  fb_mesh_add_element(m, 12, FB_ELEM_QUAD4, nd, NULL);
  expect_check(m, "element 12 (S4) is warped: node 44 is 31 mm off the plane of the other "
                  "three");
}

static void test_clone(void)
{
  fb_mesh *m = strip_mesh();
  const size_t a[2] = {0, 3};
  fb_mesh_add_nset(m, "LEFT", 2, a, NULL);
  fb_mesh *c = NULL;
  fb_err err;
  CHECK(fb_mesh_clone(m, &c, &err) == FB_OK);
  CHECK(fb_mesh_nnodes(c) == 7 && fb_mesh_nelements(c) == 3 && fb_mesh_nnsets(c) == 1);
  int same = 1;
  for (size_t i = 0; i < 7; ++i) {
    same &= fb_mesh_node_id(c, i) == fb_mesh_node_id(m, i);
    same &= memcmp(fb_mesh_node_xyz(c, i), fb_mesh_node_xyz(m, i), 3 * sizeof(double)) == 0;
  }
  for (size_t e = 0; e < 3; ++e) {
    same &= fb_mesh_element_id(c, e) == fb_mesh_element_id(m, e);
    same &= fb_mesh_element_type(c, e) == fb_mesh_element_type(m, e);
    same &= memcmp(fb_mesh_element_nodes(c, e), fb_mesh_element_nodes(m, e),
                   (size_t)fb_mesh_element_type(m, e) * sizeof(size_t)) == 0;
  }
  CHECK(same);
  CHECK(fb_mesh_find_node_id(c, 70) == 6);
  CHECK(fb_mesh_count(c, FB_ELEM_TRI3) == 1);

  /* Independent copies: changes to the clone leave the original alone. */
  const size_t more[1] = {6};
  CHECK(fb_mesh_add_nset(c, "left", 1, more, &err) == FB_OK);
  CHECK(fb_mesh_add_node(c, 80, 9, 9, 9, NULL, &err) == FB_OK);
  const size_t t[3] = {0, 1, 7};
  CHECK(fb_mesh_add_element(c, 4, FB_ELEM_TRI3, t, &err) == FB_OK);
  size_t n = 0;
  CHECK(fb_mesh_nset(m, "LEFT", NULL, &n) == 1 && n == 2);
  CHECK(fb_mesh_nset(c, "LEFT", NULL, &n) == 1 && n == 3);
  CHECK(fb_mesh_nnodes(m) == 7 && fb_mesh_find_node_id(m, 80) == -1);
  CHECK(fb_mesh_nelements(m) == 3);
  CHECK(fb_mesh_element_id(c, 3) == 4);

  fb_mesh *empty = NULL, *c2 = NULL;
  fb_mesh_new(&empty, NULL);
  CHECK(fb_mesh_clone(empty, &c2, &err) == FB_OK && fb_mesh_nnodes(c2) == 0);
  fb_mesh_free(&c2);
  CHECK(fb_mesh_clone(NULL, &c2, &err) == FB_EINVAL && c2 == NULL);
  fb_mesh_free(&empty);
  fb_mesh_free(&c);
  fb_mesh_free(&m);
}

/* ---- Abaqus decks. */

/* Meshes a and b hold the same nodes, elements and node sets; b's
 * coordinates are a's as a deck writes them: to 15 significant digits
 * (within 5e-15 relative, 1e-14 allowed), those at most 1e-12 of the
 * largest as 0 (1e-17 in the test mesh). */
static void check_same_mesh(const fb_mesh *a, const fb_mesh *b)
{
  CHECK(fb_mesh_nnodes(a) == fb_mesh_nnodes(b));
  CHECK(fb_mesh_nelements(a) == fb_mesh_nelements(b));
  CHECK(fb_mesh_nnsets(a) == fb_mesh_nnsets(b));
  if (fb_mesh_nnodes(a) != fb_mesh_nnodes(b) || fb_mesh_nelements(a) != fb_mesh_nelements(b) ||
      fb_mesh_nnsets(a) != fb_mesh_nnsets(b))
    return;
  int diffs = 0;
  for (size_t i = 0; i < fb_mesh_nnodes(a); ++i) {
    const double *p = fb_mesh_node_xyz(a, i), *q = fb_mesh_node_xyz(b, i);
    diffs += fb_mesh_node_id(a, i) != fb_mesh_node_id(b, i);
    for (int k = 0; k < 3; ++k)
      diffs += fabs(p[k]) <= 1e-12 ? q[k] != 0.0 : !(fabs(q[k] - p[k]) <= 1e-14 * fabs(p[k]));
  }
  for (size_t e = 0; e < fb_mesh_nelements(a); ++e) {
    const fb_elem_type t = fb_mesh_element_type(a, e);
    diffs += fb_mesh_element_id(a, e) != fb_mesh_element_id(b, e);
    diffs += t != fb_mesh_element_type(b, e);
    for (size_t k = 0; k < (size_t)t; ++k)
      diffs += fb_mesh_element_nodes(a, e)[k] != fb_mesh_element_nodes(b, e)[k];
  }
  for (size_t s = 0; s < fb_mesh_nnsets(a); ++s) {
    const char *name = fb_mesh_nset_name(a, s);
    const size_t *na = NULL, *nb = NULL;
    size_t ka = 0, kb = 0;
    diffs += strcmp(name, fb_mesh_nset_name(b, s)) != 0;
    diffs += fb_mesh_nset(b, name, &nb, &kb) != 1;
    fb_mesh_nset(a, name, &na, &ka);
    diffs += ka != kb;
    for (size_t k = 0; k < ka && k < kb; ++k)
      diffs += na[k] != nb[k];
  }
  CHECK(diffs == 0);
}

static void test_inp_round_trip(void)
{
  /* Ids out of order, coordinates that need all 17 digits (written to
   * 15) or are the round-off of 0 (1e-17), elements of both types
   * interleaved, a set longer than one 16-id line, an empty set. */
  fb_mesh *m = NULL;
  fb_err err;
  fb_mesh_new(&m, &err);
  size_t idx[24];
  for (size_t i = 0; i < 24; ++i) {
    const double x = (double)(i % 6) / 3.0, y = (double)(i / 6) * 0.1 + 1e-17;
    fb_mesh_add_node(m, 1000 - 7 * (long)i, x, y, -2.0 / 7.0 * x, &idx[i], &err);
  }
  long eid = 500;
  for (size_t r = 0; r < 3; ++r) {
    for (size_t c = 0; c < 5; ++c) {
      const size_t a = 6 * r + c;
      const size_t quad[4] = {a, a + 1, a + 7, a + 6}, t1[3] = {a, a + 1, a + 7},
                   t2[3] = {a, a + 7, a + 6};
      if ((r + c) % 2 == 0) {
        fb_mesh_add_element(m, eid--, FB_ELEM_QUAD4, quad, &err);
      } else {
        fb_mesh_add_element(m, eid--, FB_ELEM_TRI3, t1, &err);
        fb_mesh_add_element(m, eid--, FB_ELEM_TRI3, t2, &err);
      }
    }
  }
  const size_t bottom[6] = {5, 4, 3, 2, 1, 0};
  fb_mesh_add_nset(m, "Bottom", 6, bottom, &err);
  fb_mesh_add_nset(m, "ALL_NODES", 24, idx, &err);
  fb_mesh_add_nset(m, "nothing", 0, NULL, &err);
  CHECK(fb_mesh_check(m, NULL) == FB_EMODEL); /* the empty set */

  const fb_shell_props p = {2.1e11, 0.3, 7850.0, 0.1 / 3.0, 1e-3, 0.0};
  char path[512];
  in_root(path, sizeof path, "round.inp");
  CHECK(fb_mesh_write_inp(m, &p, path, &err) == FB_OK);
  CHECK(count_entries() == 1);
  fb_mesh *back = NULL;
  fb_shell_props q = {-1, -1, -1, -1, 0.25, 0.0};
  CHECK(fb_mesh_read_inp(path, &back, &q, &err) == FB_OK);
  if (back)
    check_same_mesh(m, back);
  /* Rounded, not just close: node 4's y is 1e-17 and comes back 0, node
   * 6's y, 0.1 + 1e-17, comes back 0.1 itself. */
  CHECK(back && fb_mesh_node_xyz(back, 4)[1] == 0.0 && fb_mesh_node_xyz(back, 6)[1] == 0.1);
  /* At most 16 data fields per line (the Abaqus limit for *NSET data). */
  char *deck = slurp(path);
  size_t widest = 0, commas = 0;
  for (const char *c = deck ? deck : ""; *c; ++c) {
    commas = *c == '\n' ? 0 : commas + (*c == ',');
    widest = commas > widest ? commas : widest;
  }
  CHECK(deck && widest == 15);
  free(deck);
  CHECK(q.young == p.young && q.poisson == p.poisson && q.density == p.density &&
        q.thickness == p.thickness);
  CHECK(q.drill_factor == 0.25); /* not an Abaqus quantity: untouched */
  fb_mesh_free(&back);

  /* Without props: no material or section, and props stay untouched. */
  CHECK(fb_mesh_write_inp(m, NULL, path, &err) == FB_OK);
  char *text = slurp(path);
  CHECK(text && !strstr(text, "*MATERIAL") && !strstr(text, "*SHELL SECTION"));
  free(text);
  fb_shell_props r = {-1, -1, -1, -1, 0.25, 0.0};
  CHECK(fb_mesh_read_inp(path, &back, &r, &err) == FB_OK);
  CHECK(r.young == -1 && r.poisson == -1 && r.density == -1 && r.thickness == -1);
  if (back)
    check_same_mesh(m, back);
  fb_mesh_free(&back);
  remove(path);

  /* A directory that does not exist: FB_EIO, nothing left behind. */
  in_root(path, sizeof path, "no/such.inp");
  CHECK(fb_mesh_write_inp(m, &p, path, &err) == FB_EIO);
  check_msg(&err, path);
  CHECK(count_entries() == 0);
  fb_mesh_free(&m);
}

static const char hand_deck[] =
    "** A hand-written deck: lowercase and mixed-case keywords, comments,\n"
    "** CRLF line ends, a continued element line, GENERATE, set references.\n"
    "*Heading\n"
    " hull panel test\n"
    "*node, nset=nall\n"
    "1, 0.0, 0.0, 0.0\n"
    "2, 1.0, 0.0, 0.0\n"
    "  3 , 2. , 0 , 0\n"
    "4, 0, 1, 0\n"
    "\n"
    "5, 1.0, 1.0, 0.0\n"
    "6, 2.0, 1.0, 0.0\n"
    "7, 3.0, 0.5, 0.0\n"
    "** elements\n"
    "*element, type=s4r, elset=plate\n"
    "1, 1, 2, 5,\n"
    "4\n"
    "2, 2, 3, 6, 5\n"
    "*Element, Type=S3, Elset=tip\n"
    "3, 3, 7, 6\n"
    "*elset, elset=plate\n"
    "1, 2\n"
    "*ELSET, ELSET=all\n"
    "plate, tip\n"
    "*nset, nset=left\n"
    "1, 4\n"
    "*Nset, nset=bottom, generate\n"
    "1, 3, 1\n"
    "*NSET, NSET=Odd, GENERATE\n"
    "1, 7, 2\n"
    "*nset, nset=Corners\n"
    "left, 7\n"
    "*NSET, NSET=LEFT\n"
    "4, 1,\n"
    "*material, name=steel\n"
    "*elastic\n"
    "2.1e11, 0.3\n"
    "*density\n"
    "7850.\n"
    "*shell section, elset=ALL, material=STEEL\n"
    "0.005, 5\n"
    "*step\n"
    "*static\n"
    "*boundary\n"
    "left, 1, 6\n"
    "*end step\n";

/* The node set name holds exactly the nodes with these user ids. */
static void check_set_ids(const fb_mesh *m, const char *name, const long *ids, size_t n)
{
  const size_t *nodes = NULL;
  size_t k = 0;
  CHECK(fb_mesh_nset(m, name, &nodes, &k) == 1);
  CHECK(k == n);
  int diffs = 0;
  for (size_t i = 0; i < n && i < k; ++i)
    diffs += fb_mesh_node_id(m, nodes[i]) != ids[i];
  CHECK(diffs == 0);
}

static void test_inp_hand_deck(void)
{
  /* Written with CRLF line ends. */
  char crlf[sizeof hand_deck * 2];
  size_t n = 0;
  for (const char *c = hand_deck; *c; ++c) {
    if (*c == '\n')
      crlf[n++] = '\r';
    crlf[n++] = *c;
  }
  char path[512];
  in_root(path, sizeof path, "hand.inp");
  write_bytes(path, crlf, n);
  fb_mesh *m = NULL;
  fb_err err;
  fb_shell_props p = {0, 0, 0, 0, 0.5, 0.0};
  const int rc = fb_mesh_read_inp(path, &m, &p, &err);
  CHECK(rc == FB_OK);
  if (rc) {
    fprintf(stderr, "  %s\n", err.msg);
    return;
  }
  CHECK(fb_mesh_nnodes(m) == 7 && fb_mesh_nelements(m) == 3);
  CHECK(fb_mesh_count(m, FB_ELEM_QUAD4) == 2 && fb_mesh_count(m, FB_ELEM_TRI3) == 1);
  const double *x3 = fb_mesh_node_xyz(m, 2);
  CHECK(fb_mesh_node_id(m, 2) == 3 && x3[0] == 2.0 && x3[1] == 0.0 && x3[2] == 0.0);
  const size_t *e1 = fb_mesh_element_nodes(m, 0);
  CHECK(fb_mesh_element_id(m, 0) == 1 && fb_mesh_element_type(m, 0) == FB_ELEM_QUAD4);
  CHECK(e1[0] == 0 && e1[1] == 1 && e1[2] == 4 && e1[3] == 3);
  const size_t *e3 = fb_mesh_element_nodes(m, 2);
  CHECK(fb_mesh_element_type(m, 2) == FB_ELEM_TRI3);
  CHECK(e3[0] == 2 && e3[1] == 6 && e3[2] == 5);

  CHECK(fb_mesh_nnsets(m) == 5);
  const long nall[7] = {1, 2, 3, 4, 5, 6, 7}, left[2] = {1, 4}, bottom[3] = {1, 2, 3},
             odd[4] = {1, 3, 5, 7}, corners[3] = {1, 4, 7};
  check_set_ids(m, "NALL", nall, 7);
  check_set_ids(m, "Left", left, 2);
  check_set_ids(m, "BOTTOM", bottom, 3);
  check_set_ids(m, "odd", odd, 4);
  check_set_ids(m, "corners", corners, 3);
  CHECK(strcmp(fb_mesh_nset_name(m, 1), "left") == 0);

  CHECK(fb_mesh_nelsets(m) == 3 && strcmp(fb_mesh_elset_name(m, 2), "all") == 0);
  const size_t *elems = NULL;
  size_t ne = 0;
  CHECK(fb_mesh_elset(m, "PLATE", &elems, &ne) && ne == 2 && elems[0] == 0 && elems[1] == 1);
  CHECK(fb_mesh_elset(m, "tip", &elems, &ne) && ne == 1 && elems[0] == 2);
  CHECK(fb_mesh_elset(m, "all", &elems, &ne) && ne == 3);
  CHECK(fb_mesh_nsections(m) == 1 && strcmp(fb_mesh_section_elset(m, 0), "all") == 0);
  for (size_t e = 0; e < 3; ++e)
    CHECK(fb_mesh_element_section(m, e) == 0);
  CHECK(fb_mesh_section_props(m, 0)->thickness == 0.005);
  /* The one section covers every element: props receives it. */
  CHECK(p.young == 2.1e11 && p.poisson == 0.3 && p.density == 7850.0 && p.thickness == 0.005);
  CHECK(p.drill_factor == 0.5);
  CHECK(fb_mesh_check(m, NULL) == FB_OK);
  fb_mesh_free(&m);

  /* With props NULL the material is read and dropped. */
  CHECK(fb_mesh_read_inp(path, &m, NULL, &err) == FB_OK);
  fb_mesh_free(&m);
  remove(path);
}

/* A deck that fails: FB_EPARSE, "path:line: " then expect; no mesh, and
 * props untouched. */
static void bad_deck(const char *name, const char *text, int line, const char *expect)
{
  char path[512], prefix[600];
  in_root(path, sizeof path, name);
  write_text(path, text);
  fb_mesh *sentinel = NULL;
  fb_mesh_new(&sentinel, NULL);
  fb_mesh *m = sentinel;
  fb_shell_props p = {1, 2, 3, 4, 5, 0.0};
  fb_err err;
  fb_err_clear(&err);
  const int rc = fb_mesh_read_inp(path, &m, &p, &err);
  CHECK(rc == FB_EPARSE);
  CHECK(m == NULL);
  CHECK(p.young == 1 && p.poisson == 2 && p.density == 3 && p.thickness == 4 &&
        p.drill_factor == 5);
  snprintf(prefix, sizeof prefix, "%s:%d: ", path, line);
  const int ok = strncmp(err.msg, prefix, strlen(prefix)) == 0;
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  expected prefix \"%s\" in: %s\n", prefix, err.msg);
  check_msg(&err, expect);
  fb_mesh_free(&sentinel);
  fb_mesh_free(&m);
  remove(path);
}

#define NODES4 "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n"

static void test_inp_bad_decks(void)
{
  bad_deck("c3d8.inp", NODES4 "*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4, 1, 2, 3, 4\n", 6,
           "element type 'C3D8' is not a shell (S3, S4)");
  bad_deck("s8r.inp", NODES4 "*ELEMENT, TYPE=S8R\n", 6,
           "shell element type 'S8R' is not supported (S3, S4)");
  bad_deck("missing_node.inp", NODES4 "*ELEMENT, TYPE=S3\n1, 1, 2, 3\n2, 1, 3, 99\n", 8,
           "element 2 refers to node 99, which is not defined");
  bad_deck("bad_number.inp", "*NODE\n1, 0, 0, 0\n2, 1, 1.0x, 0\n", 3,
           "y of node 2: not a number (read: '1.0x')");
  bad_deck("nan.inp", "*NODE\n1, 0, 0, nan\n", 2,
           "z of node 1: not a finite number (read: 'nan')");
  bad_deck("hex.inp", "*NODE\n1, 0, 0x1, 0\n", 2,
           "y of node 1: not a decimal number (read: '0x1')");
  bad_deck("bad_id.inp", NODES4 "*ELEMENT, TYPE=S4\n1.5, 1, 2, 3, 4\n", 7,
           "element id: not a positive integer (read: '1.5')");
  bad_deck("short_s4.inp", NODES4 "*ELEMENT, TYPE=S4\n1, 1, 2, 3\n", 7,
           "element 1 (S4) has 3 nodes, not 4");
  bad_deck("long_s3.inp", NODES4 "*ELEMENT, TYPE=S3\n1, 1, 2, 3, 4\n", 7,
           "element 1 (S3) has 4 nodes, not 3");
  bad_deck("nset_missing.inp",
           NODES4 "*ELEMENT, TYPE=S4\n1, 1, 2, 3, 4\n*NSET, NSET=FIX\n1, 2,\n3, 77\n", 10,
           "node set 'FIX' names node 77, which is not defined");
  bad_deck("generate_missing.inp",
           NODES4 "*ELEMENT, TYPE=S4\n1, 1, 2, 3, 4\n*NSET, NSET=G, GENERATE\n1, 5, 2\n", 9,
           "node set 'G' names node 5, which is not defined");
  bad_deck("set_ref.inp", NODES4 "*ELEMENT, TYPE=S4\n1, 1, 2, 3, 4\n*NSET, NSET=A\nB, 1\n", 9,
           "node set 'A' names node set 'B', which is not defined");
  bad_deck("empty.inp", "", 1, "empty file");
  bad_deck("truncated.inp", "*NODE\n1, 0, 0, 0\n2, 1.0, 2.0\n", 3,
           "node line needs 'id, x, y, z', not 3 fields");
  bad_deck("dangling.inp", NODES4 "*ELEMENT, TYPE=S4\n1, 1, 2,\n", 7,
           "element data ends with a comma but does not continue");
  bad_deck("dup_node.inp", NODES4 "2, 5, 5, 5\n", 6, "node id 2 is defined twice");
  bad_deck("dup_elem.inp",
           NODES4 "*ELEMENT, TYPE=S3\n1, 1, 2, 3\n1, 1, 3, 4\n*NSET, NSET=N\n1\n", 8,
           "element id 1 is defined twice");
  bad_deck("before.inp", "1, 0, 0, 0\n*NODE\n", 1, "data line before any keyword");
  bad_deck("no_type.inp", NODES4 "*element, elset=x\n", 6, "*element needs TYPE=");
  bad_deck("include.inp", NODES4 "*INCLUDE, INPUT=more.inp\n", 6, "*INCLUDE is not supported");
  bad_deck("system.inp", "*NODE, SYSTEM=C\n1, 1, 0, 0\n", 1,
           "parameter 'SYSTEM' of *NODE is not supported");
  bad_deck("empty_field.inp", "*NODE\n1, , 0, 0\n", 2, "empty data field");
  bad_deck("no_elements.inp", NODES4 "** nothing else\n", 6, "no elements");
  bad_deck("comments_only.inp", "** just\n** comments\n", 2, "no nodes");
  bad_deck("no_material.inp",
           NODES4 "*ELEMENT, TYPE=S4\n1, 1, 2, 3, 4\n*SHELL SECTION, ELSET=E, MATERIAL=ALU\n"
                  "0.002\n",
           8, "*SHELL SECTION names material 'ALU', which is not defined");
  bad_deck("thickness.inp",
           NODES4 "*MATERIAL, NAME=S\n*SHELL SECTION, ELSET=E, MATERIAL=S\n-0.002\n", 8,
           "shell thickness -0.002 is not positive");
  bad_deck("temperature.inp",
           NODES4 "*MATERIAL, NAME=S\n*ELASTIC\n2e11, 0.3, 20\n"
                  "1.9e11, 0.3, 300\n",
           9, "a second *ELASTIC data line");
  bad_deck("poisson.inp", NODES4 "*MATERIAL, NAME=S\n*ELASTIC\n2e11, 0.5\n", 8,
           "Poisson's ratio 0.5 is outside (-1, 0.5)");
  bad_deck("orphan_elastic.inp", NODES4 "*ELASTIC\n2e11, 0.3\n", 6,
           "*ELASTIC outside a *MATERIAL");
#define QUAD_STEEL                                                                             \
  NODES4 "*ELEMENT, TYPE=S4, ELSET=E\n1, 1, 2, 3, 4\n*MATERIAL, NAME=S\n*ELASTIC\n2e11, 0.3\n" \
         "*DENSITY\n7800\n"
  bad_deck("two_sections.inp",
           QUAD_STEEL "*SHELL SECTION, ELSET=E, MATERIAL=S\n0.1\n"
                      "*SHELL SECTION, ELSET=E, MATERIAL=S\n0.2\n",
           15, "element 1 is in two *SHELL SECTIONs (this one and line 13's)");
  bad_deck("section_no_set.inp", QUAD_STEEL "*SHELL SECTION, MATERIAL=S\n0.1\n", 13,
           "*SHELL SECTION needs ELSET=");
  bad_deck("section_unknown_set.inp", QUAD_STEEL "*SHELL SECTION, ELSET=F, MATERIAL=S\n0.1\n",
           13, "*SHELL SECTION names element set 'F', which is not defined");
  bad_deck("section_no_density.inp",
           NODES4 "*ELEMENT, TYPE=S4, ELSET=E\n1, 1, 2, 3, 4\n*MATERIAL, NAME=S\n*ELASTIC\n"
                  "2e11, 0.3\n*SHELL SECTION, ELSET=E, MATERIAL=S\n0.1\n",
           11, "*SHELL SECTION's material 'S' has no *DENSITY");
  bad_deck("elset_unknown_element.inp", QUAD_STEEL "*ELSET, ELSET=F\n1, 2\n", 14,
           "element set 'F' names element 2, which is not defined");
#undef QUAD_STEEL
  bad_deck("bad_name.inp", NODES4 "*NSET, NSET=\"two words\"\n1\n", 6,
           "node set name is invalid");
  bad_deck("backwards.inp", NODES4 "*NSET, NSET=G, GENERATE\n4, 1\n", 7,
           "GENERATE range 4, 1 runs backwards");

  /* Binary garbage: an ELF header. */
  char path[512];
  in_root(path, sizeof path, "garbage.inp");
  static const char elf[] = "\x7f"
                            "ELF\x02\x01\x01\0\0\0\0\0\0\0\0\0";
  write_bytes(path, elf, sizeof elf - 1);
  fb_mesh *m = NULL;
  fb_err err;
  CHECK(fb_mesh_read_inp(path, &m, NULL, &err) == FB_EPARSE && m == NULL);
  check_msg(&err, ":1: binary data (byte 0x7f in column 1)");
  CHECK(strncmp(err.msg, path, strlen(path)) == 0);
  remove(path);
  /* A NUL byte inside an otherwise good deck, on line 3. */
  static const char nul[] = "*NODE\n1, 0, 0, 0\n2, 1\0, 0, 0\n";
  write_bytes(path, nul, sizeof nul - 1);
  CHECK(fb_mesh_read_inp(path, &m, NULL, &err) == FB_EPARSE);
  check_msg(&err, ":3: binary data (byte 0x00 in column 5)");
  remove(path);

  /* A directory and a missing file: FB_EIO naming the path and reason. */
  CHECK(fb_mesh_read_inp(root, &m, NULL, &err) == FB_EIO && m == NULL);
  check_msg(&err, root);
  check_msg(&err, strerror(EISDIR));
  in_root(path, sizeof path, "absent.inp");
  CHECK(fb_mesh_read_inp(path, &m, NULL, &err) == FB_EIO);
  check_msg(&err, strerror(ENOENT));
  CHECK(fb_mesh_read_inp(path, NULL, NULL, &err) == FB_EINVAL);
  CHECK(count_entries() == 0);
}

/* ---- VTK. */

/* The numbers of the DataArray named name (or, for name NULL, of the
 * Points array) in xml; count of them in *n (up to max). */
static void vtu_array(const char *xml, const char *name, double *v, size_t max, size_t *n)
{
  char key[128];
  *n = 0;
  const char *p = NULL;
  if (name) {
    snprintf(key, sizeof key, "Name=\"%s\"", name);
    p = strstr(xml, key);
  } else {
    p = strstr(xml, "<Points>");
    p = p ? strstr(p, "<DataArray") : NULL;
  }
  p = p ? strchr(p, '>') : NULL;
  if (!p)
    return;
  ++p;
  for (;;) {
    char *end;
    const double x = strtod(p, &end);
    if (end == p)
      break;
    if (*n < max)
      v[*n] = x;
    ++*n;
    p = end;
  }
  /* The numbers must run up to the closing tag. */
  if (strncmp(p + strspn(p, " \n"), "</DataArray>", 12) != 0)
    *n = (size_t)-1;
}

static size_t count_str(const char *text, const char *s)
{
  size_t n = 0;
  for (const char *p = strstr(text, s); p; p = strstr(p + 1, s))
    ++n;
  return n;
}

static void check_array(const char *xml, const char *name, const double *expect, size_t n)
{
  double v[64];
  size_t got = 0;
  vtu_array(xml, name, v, 64, &got);
  CHECK(got == n);
  int diffs = 0;
  for (size_t i = 0; i < n && i < got; ++i)
    diffs += v[i] != expect[i];
  CHECK(diffs == 0);
  if (got != n || diffs)
    fprintf(stderr, "  array %s: %zu values, %d differ\n", name ? name : "Points", got, diffs);
}

static void test_vtu(void)
{
  fb_mesh *m = strip_mesh();
  const size_t left[2] = {0, 3}, tip[1] = {6};
  fb_mesh_add_nset(m, "LEFT", 2, left, NULL);
  fb_mesh_add_nset(m, "Tip", 1, tip, NULL);
  /* DOF values k + i / 8 for node i, DOF k: exact in %.10g. */
  double dof[42];
  for (size_t i = 0; i < 7; ++i)
    for (size_t k = 0; k < 6; ++k)
      dof[6 * i + k] = (double)k + (double)i / 8.0;
  char path[512];
  in_root(path, sizeof path, "strip.vtu");
  fb_err err;
  CHECK(fb_mesh_write_vtu(m, dof, path, &err) == FB_OK);
  CHECK(count_entries() == 1);
  char *xml = slurp(path);
  CHECK(xml != NULL);
  if (!xml) {
    fb_mesh_free(&m);
    return;
  }
  CHECK(strncmp(xml, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\"", 54) == 0);
  CHECK(strstr(xml, "<Piece NumberOfPoints=\"7\" NumberOfCells=\"3\">") != NULL);
  CHECK(count_str(xml, "<DataArray") == count_str(xml, "</DataArray>"));
  /* node_id, displacement, rotation, 2 sets, element_id, points, 3 cell
   * arrays. */
  CHECK(count_str(xml, "<DataArray") == 10);
  CHECK(strstr(xml, "</VTKFile>\n") != NULL);

  const double conn[11] = {0, 1, 4, 3, 1, 2, 5, 4, 2, 6, 5};
  const double offsets[3] = {4, 8, 11}, types[3] = {9, 9, 5};
  check_array(xml, "connectivity", conn, 11);
  check_array(xml, "offsets", offsets, 3);
  check_array(xml, "types", types, 3);
  const double points[21] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 3, 0.5, 0};
  check_array(xml, NULL, points, 21);
  double disp[21], rot[21];
  for (size_t i = 0; i < 7; ++i)
    for (size_t k = 0; k < 3; ++k) {
      disp[3 * i + k] = dof[6 * i + k];
      rot[3 * i + k] = dof[6 * i + 3 + k];
    }
  check_array(xml, "displacement", disp, 21);
  check_array(xml, "rotation", rot, 21);
  CHECK(strstr(xml, "Name=\"displacement\" NumberOfComponents=\"3\"") != NULL);
  const double ids[7] = {10, 20, 30, 40, 50, 60, 70}, eids[3] = {1, 2, 3};
  check_array(xml, "node_id", ids, 7);
  check_array(xml, "element_id", eids, 3);
  const double left_flags[7] = {1, 0, 0, 1, 0, 0, 0}, tip_flags[7] = {0, 0, 0, 0, 0, 0, 1};
  check_array(xml, "nset_LEFT", left_flags, 7);
  check_array(xml, "nset_Tip", tip_flags, 7);
  CHECK(strstr(xml, "<DataArray type=\"Int32\" Name=\"nset_Tip\" format=\"ascii\">") != NULL);
  free(xml);

  /* Without DOF values: no fields, the rest unchanged. */
  CHECK(fb_mesh_write_vtu(m, NULL, path, &err) == FB_OK);
  xml = slurp(path);
  CHECK(xml && !strstr(xml, "displacement") && !strstr(xml, "rotation"));
  if (xml)
    check_array(xml, "connectivity", conn, 11);
  free(xml);
  remove(path);

  /* Field data of the grid (a mode's frequency), before the piece; a
   * non-finite value is refused like a DOF. */
  const fb_vtu_field fields[2] = {{"frequency_hz", 10.303047717}, {"other", -0.5}};
  CHECK(fb_mesh_write_vtu_fields(m, dof, fields, 2, path, &err) == FB_OK);
  xml = slurp(path);
  const double f0[1] = {10.303047717}, f1[1] = {-0.5};
  if (xml) {
    check_array(xml, "frequency_hz", f0, 1);
    check_array(xml, "other", f1, 1);
    const char *fd = strstr(xml, "<FieldData>"), *piece = strstr(xml, "<Piece");
    CHECK(fd && piece && fd < piece);
  }
  free(xml);
  remove(path);
  const fb_vtu_field bad = {"frequency_hz", INFINITY};
  CHECK(fb_mesh_write_vtu_fields(m, dof, &bad, 1, path, &err) == FB_EINVAL);
  check_msg(&err, "field 0 has no name or is not finite");
  CHECK(count_entries() == 0);

  /* An animation's frame: points at X + warp u, two markers after the
   * nodes with a vertex cell each, their displacement (0, 0, dz), the
   * part array telling them apart, -1 ids. */
  const fb_vtu_marker markers[2] = {{{0.5, 0.5, 1.0}, 0.25, 1}, {{2.0, 0.0, -1.0}, -0.5, 2}};
  /* A cell array: the elements' values, then 0 for the markers' cells. */
  const double vm[3] = {1.5e8, 2.5, 3.5};
  const fb_vtu_cell_array cells = {"von_mises", vm};
  const fb_vtu_frame frame = {dof, 2.0, markers, 2, fields, 1, {0.0, 0.0, 0.0}, &cells, 1};
  CHECK(fb_mesh_write_vtu_frame(m, &frame, path, &err) == FB_OK);
  xml = slurp(path);
  if (xml) {
    CHECK(strstr(xml, "<Piece NumberOfPoints=\"9\" NumberOfCells=\"5\">") != NULL);
    double warped[27];
    for (size_t i = 0; i < 7; ++i)
      for (size_t k = 0; k < 3; ++k)
        warped[3 * i + k] = points[3 * i + k] + 2.0 * dof[6 * i + k];
    const double mk[6] = {0.5, 0.5, 1.5, 2.0, 0.0, -2.0};
    memcpy(warped + 21, mk, sizeof mk);
    check_array(xml, NULL, warped, 27);
    double mdisp[27];
    memcpy(mdisp, disp, sizeof disp);
    const double md[6] = {0, 0, 0.25, 0, 0, -0.5};
    memcpy(mdisp + 21, md, sizeof md);
    check_array(xml, "displacement", mdisp, 27);
    const double part[9] = {0, 0, 0, 0, 0, 0, 0, 1, 2};
    check_array(xml, "part", part, 9);
    const double conn2[13] = {0, 1, 4, 3, 1, 2, 5, 4, 2, 6, 5, 7, 8};
    const double off2[5] = {4, 8, 11, 12, 13}, types2[5] = {9, 9, 5, 1, 1};
    check_array(xml, "connectivity", conn2, 13);
    check_array(xml, "offsets", off2, 5);
    check_array(xml, "types", types2, 5);
    const double ids2[9] = {10, 20, 30, 40, 50, 60, 70, -1, -1}, eids2[5] = {1, 2, 3, -1, -1};
    check_array(xml, "node_id", ids2, 9);
    check_array(xml, "element_id", eids2, 5);
    const double vm2[5] = {1.5e8, 2.5, 3.5, 0, 0};
    check_array(xml, "von_mises", vm2, 5);
    const double tip2[9] = {0, 0, 0, 0, 0, 0, 1, 0, 0};
    check_array(xml, "nset_Tip", tip2, 9);
  }
  free(xml);
  remove(path);
  const fb_vtu_marker bad_marker = {{0, 0, NAN}, 0, 1};
  const fb_vtu_frame bad_frame = {dof, 1.0, &bad_marker, 1, NULL, 0, {0.0, 0.0, 0.0}, NULL, 0};
  CHECK(fb_mesh_write_vtu_frame(m, &bad_frame, path, &err) == FB_EINVAL);
  check_msg(&err, "marker 0 is not finite");
  CHECK(count_entries() == 0);
  const double vm_bad[3] = {1.0, NAN, 2.0};
  const fb_vtu_cell_array bad_cells = {"von_mises", vm_bad};
  const fb_vtu_frame bad_cell_frame = {dof,        1.0, NULL, 0, NULL, 0, {0.0, 0.0, 0.0},
                                       &bad_cells, 1};
  CHECK(fb_mesh_write_vtu_frame(m, &bad_cell_frame, path, &err) == FB_EINVAL);
  check_msg(&err, "cell array von_mises is not finite at element 2");
  CHECK(count_entries() == 0);

  /* A NaN is refused before any file exists. */
  dof[6 * 2 + 4] = NAN;
  CHECK(fb_mesh_write_vtu(m, dof, path, &err) == FB_EINVAL);
  check_msg(&err, "DOF value 16 (ry of node 30) is not finite");
  CHECK(count_entries() == 0);
  fb_mesh_free(&m);
}

/* Largest |a_ij - b_ij| over the largest |a_ij| of two square matrices. */
static double mat_rel_diff(const fb_mat *a, const fb_mat *b)
{
  double d = 0.0, scale = 0.0;
  const size_t n = fb_mat_nrows(a);
  for (size_t j = 0; j < n; ++j)
    for (size_t i = 0; i < n; ++i) {
      const double x = fb_mat_get(a, i, j), y = fb_mat_get(b, i, j);
      d = fmax(d, fabs(x - y));
      scale = fmax(scale, fabs(x));
    }
  return d / scale;
}

/* Sections: element 1 of the strip in a 20 mm section with a lining,
 * element 3 in an aluminium one, element 2 with the caller's
 * properties. The element props, K and M follow them; a deck carries them
 * (the lining smeared into the density) so that reading it back gives the
 * same K and M, to the 17 digits written. */
static void test_sections(void)
{
  fb_mesh *m = strip_mesh();
  fb_err err;
  const size_t e1 = 0, e3 = 2, e13[2] = {0, 2};
  const fb_shell_props base = {2.1e11, 0.3, 7850.0, 0.0085, 2e-4, 0.0};
  const fb_shell_props thick = {2.1e11, 0.3, 7850.0, 0.020, 0.0, 12.0};
  const fb_shell_props alu = {7e10, 0.33, 2700.0, 0.006, 0.0, 0.0};
  CHECK(fb_mesh_set_section(m, "FLOOR", &thick, &err) == FB_EINVAL);
  check_msg(&err, "element set 'FLOOR' is not defined");
  CHECK(fb_mesh_add_elset(m, "Floor", 1, &e1, &err) == FB_OK);
  CHECK(fb_mesh_add_elset(m, "ends", 2, e13, &err) == FB_OK);
  CHECK(fb_mesh_add_elset(m, "tip", 1, &e3, &err) == FB_OK);
  const size_t beyond = 3;
  CHECK(fb_mesh_add_elset(m, "bad", 1, &beyond, &err) == FB_EINVAL);
  check_msg(&err, "element index 3 out of range");
  const fb_shell_props negative = {2.1e11, 0.3, 7850.0, 0.01, 0.0, -1.0};
  CHECK(fb_mesh_set_section(m, "tip", &negative, &err) == FB_EINVAL);
  check_msg(&err, "non-structural mass must be >= 0");
  /* "ends" then "FLOOR": element 1 ends in the later section. */
  CHECK(fb_mesh_set_section(m, "ends", &alu, &err) == FB_OK);
  CHECK(fb_mesh_set_section(m, "FLOOR", &thick, &err) == FB_OK);
  CHECK(fb_mesh_nsections(m) == 2 && strcmp(fb_mesh_section_elset(m, 1), "Floor") == 0);
  CHECK(fb_mesh_element_section(m, 0) == 1 && fb_mesh_element_section(m, 1) == -1 &&
        fb_mesh_element_section(m, 2) == 0);
  const fb_shell_props p0 = fb_mesh_element_props(m, 0, &base);
  const fb_shell_props p1 = fb_mesh_element_props(m, 1, &base);
  CHECK(p0.thickness == 0.020 && p0.nonstructural_mass == 12.0 && p0.drill_factor == 2e-4);
  CHECK(p1.thickness == 0.0085 && p1.density == 7850.0);

  /* Mass: sum of (rho t + nsm) A over the elements, by hand. */
  fb_mat *K = NULL, *M = NULL;
  CHECK(fb_fem_assemble(m, &base, FB_MASS_CONSISTENT, &K, &M, &err) == FB_OK);
  double mass = 0.0, cg[3], inertia[9];
  CHECK(fb_fem_mass_properties(m, M, &mass, cg, inertia, &err) == FB_OK);
  const double areal[3] = {7850.0 * 0.020 + 12.0, 7850.0 * 0.0085, 2700.0 * 0.006};
  const double area[3] = {1.0, 1.0, 0.5}; /* the triangle (2,0) (3,0.5) (2,1) */
  const double expect = areal[0] * area[0] + areal[1] * area[1] + areal[2] * area[2];
  CHECK_NEAR(mass, expect, 1e-12 * expect);

  /* Cloned: the sections come along. */
  fb_mesh *c = NULL;
  CHECK(fb_mesh_clone(m, &c, &err) == FB_OK);
  CHECK(c && fb_mesh_nsections(c) == 2 && fb_mesh_element_section(c, 2) == 0 &&
        fb_mesh_nelsets(c) == 3);
  fb_mesh_free(&c);

  /* Written and read back: three sections (the base's as SECTION_1, since
   * no set holds just element 2), the same K and M. */
  char path[512];
  in_root(path, sizeof path, "sections.inp");
  CHECK(fb_mesh_write_inp(m, &base, path, &err) == FB_OK);
  fb_mesh *back = NULL;
  const int rc = fb_mesh_read_inp(path, &back, NULL, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  %s\n", err.msg);
  char *deck = slurp(path);
  CHECK(deck && strstr(deck, "*ELSET, ELSET=SECTION_1\n2\n") &&
        strstr(deck, "*SHELL SECTION, ELSET=tip, MATERIAL=MAT_2") &&
        strstr(deck, "*SHELL SECTION, ELSET=Floor, MATERIAL=MAT_3"));
  free(deck);
  fb_mat *K2 = NULL, *M2 = NULL;
  const fb_shell_props unused = {1.0, 0.0, 1.0, 1.0, 2e-4, 0.0}; /* every element has one */
  CHECK(back && fb_mesh_nsections(back) == 3 &&
        fb_fem_assemble(back, &unused, FB_MASS_CONSISTENT, &K2, &M2, &err) == FB_OK);
  /* 17 significant digits reproduce every double; the smeared density
   * rho + nsm / t is one rounding away (1e-16) from the split form. */
  CHECK(K2 && mat_rel_diff(K, K2) < 1e-15);
  CHECK(M2 && mat_rel_diff(M, M2) < 1e-14);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mat_free(&K2);
  fb_mat_free(&M2);
  fb_mesh_free(&back);
  remove(path);
  fb_mesh_free(&m);
}

/* A gmsh MSH 4.1 text: one quadrilateral on surface 1 (physical group
 * PLATE) and a physical point CORNER at node 3; MSH_QUAD_AT gives the
 * coordinates of nodes 3, 1, 2 and 4 (element 8 is 1 2 3 4). */
#define MSH_HEAD "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
#define MSH_QUAD_AT(n3, n1, n2, n4)                                                            \
  MSH_HEAD                                                                                     \
  "$PhysicalNames\n2\n2 1 \"PLATE\"\n0 2 \"CORNER\"\n$EndPhysicalNames\n"                      \
  "$Entities\n1 0 1 0\n9 1 1 0 1 2\n1 0 0 0 1 1 0 1 1 0\n$EndEntities\n"                       \
  "$Nodes\n2 4 1 4\n0 9 0 1\n3\n" n3 "\n2 1 0 3\n1\n2\n4\n" n1 "\n" n2 "\n" n4                 \
  "\n$EndNodes\n$Elements\n2 2 1 8\n0 9 15 1\n1 3\n2 1 3 1\n8 1 2 3 4\n$EndElements\n"
#define MSH_QUAD MSH_QUAD_AT("1 1 0", "0 0 0", "1 0 0", "0 1 0")

/* The 1-based number of the line of text that starts with line. */
static int line_of(const char *text, const char *line)
{
  int n = 1;
  for (const char *p = text; *p; ++p) {
    if ((p == text || p[-1] == '\n') && strncmp(p, line, strlen(line)) == 0)
      return n;
    n += *p == '\n';
  }
  return 0;
}

static void expect_msh_error(const char *text, const char *expect)
{
  fb_mesh *m = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_mesh_read_msh_string(text, strlen(text), "x.msh", &m, &err) == FB_EPARSE && !m);
  check_msg(&err, expect);
  CHECK(strncmp(err.msg, "x.msh:", 6) == 0);
}

/* The len bytes of text (NULs allowed) are refused at line (column col,
 * 0: not known) with expect: "x.msh:LINE: " leads the message, and the
 * error's location says the same. */
static void expect_msh_error_at(const char *text, size_t len, int line, int col,
                                const char *expect)
{
  fb_mesh *m = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_mesh_read_msh_string(text, len, "x.msh", &m, &err) == FB_EPARSE && !m);
  char head[256];
  snprintf(head, sizeof head, "x.msh:%d: %s", line, expect);
  check_msg(&err, head);
  CHECK(strncmp(DESCRIBED(&err), head, strlen(head)) == 0);
  CHECK(strcmp(err.file, "x.msh") == 0 && err.line == line && err.column == col);
  CHECK(strstr(err.msg, "nan") == NULL);
}

static void test_msh(void)
{
  fb_mesh *m = NULL;
  fb_err err;
  const char *text = MSH_QUAD;
  const int rc = fb_mesh_read_msh_string(text, strlen(text), "quad.msh", &m, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  %s\n", err.msg);
  CHECK(fb_mesh_nnodes(m) == 4 && fb_mesh_nelements(m) == 1);
  CHECK(fb_mesh_element_id(m, 0) == 8 && fb_mesh_element_type(m, 0) == FB_ELEM_QUAD4);
  const size_t *nd = fb_mesh_element_nodes(m, 0);
  CHECK(nd && fb_mesh_node_id(m, nd[2]) == 3 && fb_mesh_node_xyz(m, nd[2])[1] == 1.0);
  const size_t *items = NULL;
  size_t n = 0;
  CHECK(fb_mesh_elset(m, "PLATE", &items, &n) && n == 1);
  CHECK(fb_mesh_nset(m, "PLATE", &items, &n) && n == 4);
  CHECK(fb_mesh_nset(m, "CORNER", &items, &n) && n == 1 && fb_mesh_node_id(m, items[0]) == 3);
  CHECK(!fb_mesh_elset(m, "CORNER", NULL, NULL));
  CHECK(fb_mesh_check(m, NULL) == FB_OK);
  fb_mesh_free(&m);

  expect_msh_error("", "empty file");
  expect_msh_error("$Nodes\n", "does not start with $MeshFormat");
  expect_msh_error("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n", "MSH format 2.2 is not supported");
  expect_msh_error("$MeshFormat\n4.1 1 8\n$EndMeshFormat\n", "a binary .msh file");
  expect_msh_error(MSH_HEAD "$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n"
                            "$EndNodes\n$Elements\n1 1 1 1\n2 1 9 1\n1 1 2 3 1 2 3\n",
                   "x.msh:16: element type 9 is not supported");
  expect_msh_error(MSH_HEAD "$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 0 0\n$EndNodes\n$Elements\n"
                            "1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n",
                   "x.msh:13: the element names node 2, which is not defined");
  expect_msh_error(MSH_HEAD "$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 0 nan\n$EndNodes\n",
                   "x.msh:8: node coordinates: not a finite number (read: 'nan')");
  expect_msh_error(MSH_HEAD "$Nodes\n1 99999999 1 1\n", "x.msh:5:");
  expect_msh_error(MSH_HEAD "$PhysicalNames\n1\n2 1 \"two words\"\n$EndPhysicalNames\n",
                   "the physical name cannot name a set");
  expect_msh_error(MSH_HEAD "$Nodes\n1 1 1 1\n2 1 0 1\n1\n", "the file ends where");
  expect_msh_error(MSH_HEAD "$Comments\nanything\n$EndComments\n", "no triangles or quad");
}

/* A NUL or another control byte is refused at its line and column
 * wherever it is: on a section's name line after the elements (the read
 * once ended there, silently, with the mesh), before them (once "no
 * triangles"), or in data. Tabs, and CR LF line ends, are the format's. */
static void test_msh_control_bytes(void)
{
  static const char after[] = MSH_QUAD "$Extra\0\n$EndExtra\n";
  expect_msh_error_at(after, sizeof after - 1, line_of(after, "$Extra"), 7,
                      "binary data (byte 0x00 in column 7)");
  static const char before[] = MSH_HEAD "$Nodes\x01\n";
  expect_msh_error_at(before, sizeof before - 1, 4, 7, "binary data (byte 0x01 in column 7)");
  static const char data[] = MSH_HEAD "$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 0\0 0\n";
  expect_msh_error_at(data, sizeof data - 1, 8, 4, "binary data (byte 0x00 in column 4)");
  static const char cr[] = MSH_HEAD "$Nodes\n1 1 1 1\r2 1 0 1\n";
  expect_msh_error_at(cr, sizeof cr - 1, 5, 8, "binary data (byte 0x0d in column 8)");

  char crlf[1024];
  size_t n = 0;
  for (const char *p = MSH_QUAD; *p && n + 2 < sizeof crlf; ++p) {
    if (*p == '\n')
      crlf[n++] = '\r';
    crlf[n++] = *p == ' ' ? '\t' : *p;
  }
  fb_mesh *m = NULL;
  fb_err err;
  CHECK(fb_mesh_read_msh_string(crlf, n, "crlf.msh", &m, &err) == FB_OK);
  CHECK(fb_mesh_nelements(m) == 1 && fb_mesh_nset(m, "CORNER", NULL, NULL));
  fb_mesh_free(&m);
}

/* Every number is a plain decimal, as in .inp decks and CSV files: strtod
 * once read the hexadecimal -0x2.8p0 as -2.5. */
static void test_msh_numbers(void)
{
  static const char coord[] = MSH_HEAD "$Nodes\n1 1 1 1\n2 1 0 1\n1\n-0x2.8p0 0 0\n";
  expect_msh_error_at(coord, sizeof coord - 1, 8, 0,
                      "node coordinates: not a decimal number (read: '-0x2.8p0')");
  static const char box[] = MSH_HEAD "$Entities\n0 0 1 0\n1 0 0 0 0x1 1 0 0 0\n";
  expect_msh_error_at(box, sizeof box - 1, 6, 0, "entity: not a decimal number (read: '0x1')");
  static const char version[] = "$MeshFormat\n4.1e0x 0 8\n";
  expect_msh_error_at(version, sizeof version - 1, 2, 0,
                      "$MeshFormat: not a number (read: '4.1e0x')");
  static const char tag[] = MSH_HEAD "$Nodes\n1 1 1 1\n2 1 0 1\n0x1\n";
  expect_msh_error_at(tag, sizeof tag - 1, 7, 0, "node tag: not an integer (read: '0x1')");
  static const char count[] = MSH_HEAD "$Nodes\n1 1 1 1e0\n";
  expect_msh_error_at(count, sizeof count - 1, 5, 0, "$Nodes: not an integer (read: '1e0')");
  static const char inf[] = MSH_HEAD "$Nodes\n1 1 1 1\n2 1 0 1\n1\n0 inf 0\n";
  expect_msh_error_at(inf, sizeof inf - 1, 8, 0,
                      "node coordinates: not a finite number (read: 'inf')");
}

/* An element no shell can integrate is refused at its own line, as in an
 * .inp deck; nodes that all coincide say so (the warp test once divided 0
 * by 0 for them: "node 1 is -nan mm off the plane"). */
static void test_msh_shapes(void)
{
  static const char same[] = MSH_QUAD_AT("0 0 0", "0 0 0", "0 0 0", "0 0 0");
  expect_msh_error_at(same, sizeof same - 1, line_of(same, "8 1 2 3 4"), 0,
                      "element 8 (S4) is degenerate: its nodes coincide (zero area)");
  static const char warped[] = MSH_QUAD_AT("1 1 0", "0 0 0", "1 0 0", "0 1 0.5");
  expect_msh_error_at(warped, sizeof warped - 1, line_of(warped, "8 1 2 3 4"), 0,
                      "element 8 (S4) is warped: node 4 is 500 mm off the plane");
  static const char line[] = MSH_QUAD_AT("2 0 0", "0 0 0", "1 0 0", "3 0 0");
  expect_msh_error_at(line, sizeof line - 1, line_of(line, "8 1 2 3 4"), 0,
                      "element 8 (S4) is degenerate: area 0 m^2 below the limit");
}

/* Entities and names are found whatever their order in the file; an
 * entity that lists a group twice adds to it once; a group's nodes come in
 * the order of its blocks, its sets in the order the groups are met. */
static void test_msh_groups(void)
{
  static const char text[] =
      MSH_HEAD "$PhysicalNames\n3\n0 2 \"B\"\n2 5 \"PLATE\"\n0 1 \"A\"\n$EndPhysicalNames\n"
               "$Entities\n3 0 1 0\n30 0 0 0 1 1\n10 0 0 0 3 1 7 1\n20 0 0 0 1 2\n"
               "5 0 0 0 1 1 0 1 5 0\n$EndEntities\n"
               "$Nodes\n1 4 1 4\n2 5 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n"
               "$Elements\n4 4 1 4\n0 20 15 1\n1 2\n0 30 15 1\n2 3\n2 5 3 1\n3 1 2 3 4\n"
               "0 10 15 1\n4 1\n$EndElements\n";
  fb_mesh *m = NULL;
  fb_err err;
  const int rc = fb_mesh_read_msh_string(text, strlen(text), "groups.msh", &m, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  %s\n", err.msg);
  const size_t *items = NULL;
  size_t n = 0;
  CHECK(fb_mesh_nset(m, "A", &items, &n) && n == 2 && fb_mesh_node_id(m, items[0]) == 3 &&
        fb_mesh_node_id(m, items[1]) == 1);
  CHECK(fb_mesh_nset(m, "B", &items, &n) && n == 1 && fb_mesh_node_id(m, items[0]) == 2);
  CHECK(fb_mesh_nset(m, "PLATE", &items, &n) && n == 4);
  CHECK(fb_mesh_elset(m, "PLATE", &items, &n) && n == 1 &&
        fb_mesh_elset(m, "PLATE", NULL, NULL));
  CHECK(fb_mesh_nnsets(m) == 3 && !strcmp(fb_mesh_nset_name(m, 0), "B") &&
        !strcmp(fb_mesh_nset_name(m, 1), "A") && !strcmp(fb_mesh_nset_name(m, 2), "PLATE"));
  CHECK(fb_mesh_nelsets(m) == 1);
  fb_mesh_free(&m);
}

/* Keys given twice, the bound on an entity's named groups, and the
 * sections that must come before $Elements. */
#define MSH_ONE_NODE                                                                           \
  "$Nodes\n1 1 1 1\n0 1 0 1\n1\n0 0 0\n$EndNodes\n$Elements\n0 0 1 0\n$EndElements\n"
static void test_msh_group_errors(void)
{
  static const char ent[] =
      MSH_HEAD "$Entities\n2 0 0 0\n1 0 0 0 0\n1 0 0 0 0\n$EndEntities\n" MSH_ONE_NODE;
  expect_msh_error_at(ent, sizeof ent - 1, 7, 0,
                      "entity 1 of dimension 0 is defined twice (first at line 6)");
  static const char name[] =
      MSH_HEAD "$PhysicalNames\n2\n0 1 \"A\"\n0 1 \"B\"\n$EndPhysicalNames\n" MSH_ONE_NODE;
  expect_msh_error_at(name, sizeof name - 1, 7, 0,
                      "physical group 1 of dimension 0 is named twice (first at line 6)");
  /* One name for two groups (any case, any dimension) would merge their sets. */
  static const char same[] = MSH_HEAD
      "$PhysicalNames\n2\n2 1 \"FLOOR\"\n2 4 \"floor\"\n$EndPhysicalNames\n" MSH_ONE_NODE;
  expect_msh_error_at(same, sizeof same - 1, 7, 0,
                      "physical group 4 of dimension 2 has the name of group 1 of dimension 2 "
                      "(line 6)");
  static const char late[] = MSH_QUAD "$Entities\n0 0 0 0\n$EndEntities\n";
  expect_msh_error_at(late, sizeof late - 1, line_of(late, "$Entities\n0 0 0 0"), 0,
                      "$Entities after $Elements");

  char text[4096];
  size_t n = (size_t)snprintf(text, sizeof text, MSH_HEAD "$PhysicalNames\n17\n");
  for (int g = 1; g <= 17; ++g)
    n += (size_t)snprintf(text + n, sizeof text - n, "0 %d \"G%d\"\n", g, g);
  n += (size_t)snprintf(text + n, sizeof text - n,
                        "$EndPhysicalNames\n$Entities\n1 0 0 0\n1 0 0 0 17");
  for (int g = 1; g <= 17; ++g)
    n += (size_t)snprintf(text + n, sizeof text - n, " %d", g);
  n += (size_t)snprintf(text + n, sizeof text - n, "\n$EndEntities\n" MSH_ONE_NODE);
  expect_msh_error_at(text, n, line_of(text, "1 0 0 0 17"), 0,
                      "entity 1 is in more than 16 named physical groups");
  text[strstr(text, "1 0 0 0 17") - text + 9] = '6'; /* 16 groups: fine (no triangles) */
  fb_mesh *m = NULL;
  fb_err err;
  CHECK(fb_mesh_read_msh_string(text, n, "x.msh", &m, &err) == FB_EPARSE);
  check_msg(&err, "no triangles or quadrilaterals");
}

/* ---- Outline. */

/* nplates strips of n unit quadrilaterals sharing the edge from (0, 0, 0)
 * to (n, 0, 0), plate p turned by phi[p] (degrees) about the x axis:
 * nodes 0 .. n on the shared edge, then each plate's outer row. */
static fb_mesh *fan_mesh(const double *phi, size_t nplates, size_t n)
{
  fb_mesh *m = NULL;
  fb_err err;
  int rc = fb_mesh_new(&m, &err);
  for (size_t p = 0; p <= nplates && !rc; ++p)
    for (size_t x = 0; x <= n && !rc; ++x) {
      const double a = p ? phi[p - 1] * 3.14159265358979323846 / 180.0 : 0.0;
      rc = fb_mesh_add_node(m, (long)(p * (n + 1) + x + 1), (double)x, p ? cos(a) : 0.0,
                            p ? sin(a) : 0.0, NULL, &err);
    }
  for (size_t p = 0; p < nplates && !rc; ++p)
    for (size_t x = 0; x < n && !rc; ++x) {
      const size_t o = (p + 1) * (n + 1) + x, q[4] = {x, x + 1, o + 1, o};
      rc = fb_mesh_add_element(m, (long)(p * n + x + 1), FB_ELEM_QUAD4, q, &err);
    }
  CHECK(rc == FB_OK);
  return m;
}

/* Edges in the outline at angle (degrees); -1 on an error. Checks that
 * they come once each, lower node first, in increasing order. */
static long outline_count(const fb_mesh *m, double angle, size_t a, size_t b, int *has_ab)
{
  size_t *edge = NULL, n = 0;
  fb_err err;
  if (fb_mesh_outline(m, angle * 3.14159265358979323846 / 180.0, &edge, &n, &err))
    return -1;
  *has_ab = 0;
  for (size_t i = 0; i < n; ++i) {
    CHECK(edge[2 * i] < edge[2 * i + 1]);
    if (i)
      CHECK(edge[2 * i - 2] < edge[2 * i] ||
            (edge[2 * i - 2] == edge[2 * i] && edge[2 * i - 1] < edge[2 * i + 1]));
    *has_ab |= edge[2 * i] == a && edge[2 * i + 1] == b;
  }
  free(edge);
  return (long)n;
}

static void test_outline(void)
{
  /* A plate of three quads alone: its 8 edges are all on its boundary.
   * With others, each has 5 free edges (its outer row and its two ends);
   * the shared edge's three pieces count where the plates fold by more
   * than the angle, or where three plates meet. */
  int fold;
  fb_mesh *m = fan_mesh((const double[]){180.0}, 1, 3);
  CHECK(outline_count(m, 20.0, 0, 1, &fold) == 8 && fold);
  fb_mesh_free(&m);
  m = fan_mesh((const double[]){0.0, 180.0}, 2, 3); /* one flat plate */
  CHECK(outline_count(m, 20.0, 0, 1, &fold) == 10 && !fold);
  fb_mesh_free(&m);
  m = fan_mesh((const double[]){0.0, 150.0}, 2, 3); /* folded by 30 degrees */
  CHECK(outline_count(m, 20.0, 0, 1, &fold) == 13 && fold);
  CHECK(outline_count(m, 35.0, 0, 1, &fold) == 10 && !fold);
  fb_mesh_free(&m);
  m = fan_mesh((const double[]){0.0, 170.0}, 2, 3); /* by 10 */
  CHECK(outline_count(m, 20.0, 0, 1, &fold) == 10 && !fold);
  CHECK(outline_count(m, 5.0, 0, 1, &fold) == 13 && fold);
  fb_mesh_free(&m);
  /* A plate turned over (normals opposite) folds by 30 degrees, not 150. */
  m = fan_mesh((const double[]){0.0, -30.0}, 2, 3);
  CHECK(outline_count(m, 20.0, 0, 1, &fold) == 13 && fold);
  CHECK(outline_count(m, 35.0, 0, 1, &fold) == 10 && !fold);
  fb_mesh_free(&m);
  m = fan_mesh((const double[]){0.0, 90.0, 180.0}, 3, 3); /* a T: three plates meet */
  CHECK(outline_count(m, 89.0, 0, 1, &fold) == 18 && fold);
  CHECK(outline_count(m, 91.0, 0, 1, &fold) == 18 && fold);
  /* The area vector: a unit square in the plane z = 0, normal +z by its
   * node order (0, 1, outer 1, outer 0); the turned plate's along -y. */
  double v[3];
  fb_mesh_element_area_vector(m, 0, v);
  CHECK_NEAR(v[0], 0.0, 1e-15);
  CHECK_NEAR(v[1], 0.0, 1e-15);
  CHECK_NEAR(v[2], 1.0, 1e-15);
  fb_mesh_element_area_vector(m, 3, v);
  CHECK_NEAR(v[1], -1.0, 1e-15);
  CHECK_NEAR(v[2], 0.0, 1e-15);
  fb_mesh_free(&m);
}

int main(void)
{
  root = test_tmpdir();
  test_build();
  test_bad_arguments();
  test_many_ids();
  test_find_node_at();
  test_nsets();
  test_check();
  test_check_warp_ids();
  test_clone();
  test_inp_round_trip();
  test_inp_hand_deck();
  test_inp_bad_decks();
  test_sections();
  test_msh();
  test_msh_control_bytes();
  test_msh_numbers();
  test_msh_shapes();
  test_msh_groups();
  test_msh_group_errors();
  test_outline();
  test_vtu();
  return check_report("test_mesh");
}
