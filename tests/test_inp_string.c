/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of fb_mesh_read_inp_string (flexbond/fem.h): the Abaqus deck reader on a buffer
 * in memory. Each deck is passed in a heap block of exactly its length, without a NUL
 * (so the sanitizer builds catch a read past the end), with more text after it where the
 * contract says the reader must stop. The reference answers are the deck's own numbers
 * (decimal literals read by strtod and by the compiler round the same way: both
 * correctly rounded, C11 6.4.4.2 with IEEE 754 binary64) and fb_mesh_read_inp on the
 * same text written to a file, a second path through the shared parser. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/fem.h"

#include "check.h"
#include "tmpdir.h"

/* Two S4 and one S3 over six nodes, a GENERATE set, a material and a section. */
static const char plate_deck[] = "** plate\n"
                                 "*NODE, NSET=ALL\n"
                                 "1, 0, 0, 0\n"
                                 "2, 0.5, 0, 0\n"
                                 "3, 1.0, 0, 0\n"
                                 "4, 0, 0.25, 0\n"
                                 "5, 0.5, 0.25, 0\n"
                                 "6, 1.0, 0.25, 0.125\n"
                                 "*ELEMENT, TYPE=S4, ELSET=E\n"
                                 "10, 1, 2, 5, 4\n"
                                 "*ELEMENT, TYPE=S3R, ELSET=E\n"
                                 "11, 2, 3, 6\n"
                                 "12, 2, 6, 5\n"
                                 "*NSET, NSET=ODD, GENERATE\n"
                                 "1, 5, 2\n"
                                 "*MATERIAL, NAME=STEEL\n"
                                 "*ELASTIC\n"
                                 "2.1e11, 0.29\n"
                                 "*DENSITY\n"
                                 "7850\n"
                                 "*SHELL SECTION, ELSET=E, MATERIAL=STEEL\n"
                                 "0.004\n";

/* A heap copy of the first len bytes of text, with no terminator. */
static char *exact_copy(const char *text, size_t len)
{
  char *p = malloc(len ? len : 1);
  if (p)
    memcpy(p, text, len);
  return p;
}

/* fb_mesh_read_inp_string on the first len bytes of text (an exact-size copy). */
static int read_prefix(const char *text, size_t len, const char *name, fb_mesh **m,
                       fb_shell_props *p, fb_err *err)
{
  char *copy = exact_copy(text, len);
  const int rc = fb_mesh_read_inp_string(copy, len, name, m, p, err);
  free(copy);
  return rc;
}

static int has(const fb_err *err, const char *expect)
{
  const char *shown = DESCRIBED(err);
  const int ok = strstr(shown, expect) != NULL;
  if (!ok)
    fprintf(stderr, "  expected \"%s\" in: %s\n", expect, shown);
  return ok;
}

/* Node and element data, sets and properties straight from the deck's numbers. */
static void test_plate(void)
{
  fb_mesh *m = NULL;
  fb_shell_props p = {0, 0, 0, 0, 7, 0.0};
  fb_err err;
  fb_err_clear(&err);
  CHECK(read_prefix(plate_deck, strlen(plate_deck), "plate.inp", &m, &p, &err) == FB_OK);
  CHECK(m != NULL);
  if (!m)
    return;
  CHECK(fb_mesh_nnodes(m) == 6 && fb_mesh_nelements(m) == 3);
  CHECK(fb_mesh_count(m, FB_ELEM_QUAD4) == 1 && fb_mesh_count(m, FB_ELEM_TRI3) == 2);
  const long n6 = fb_mesh_find_node_id(m, 6);
  CHECK(n6 == 5);
  if (n6 >= 0) {
    const double *x = fb_mesh_node_xyz(m, (size_t)n6);
    CHECK(x[0] == 1.0 && x[1] == 0.25 && x[2] == 0.125);
  }
  CHECK(fb_mesh_element_id(m, 2) == 12 && fb_mesh_element_type(m, 2) == FB_ELEM_TRI3);
  const size_t *en = fb_mesh_element_nodes(m, 2);
  CHECK(fb_mesh_node_id(m, en[0]) == 2 && fb_mesh_node_id(m, en[1]) == 6 &&
        fb_mesh_node_id(m, en[2]) == 5);
  const size_t *set = NULL;
  size_t n = 0;
  CHECK(fb_mesh_nset(m, "odd", &set, &n) == 1 && n == 3);
  for (size_t k = 0; k < n && k < 3; ++k)
    CHECK(fb_mesh_node_id(m, set[k]) == (long)(1 + 2 * k));
  CHECK(fb_mesh_nset(m, "ALL", &set, &n) == 1 && n == 6);
  CHECK(p.young == 2.1e11 && p.poisson == 0.29 && p.density == 7850 && p.thickness == 0.004);
  CHECK(p.drill_factor == 7); /* no Abaqus keyword: untouched */
  CHECK(fb_mesh_check(m, &err) == FB_OK);
  fb_mesh_free(&m);
}

/* The same deck read from a file gives the same mesh and properties. */
static void test_same_as_file(void)
{
  char path[TEST_PATH_MAX];
  test_tmp_path("flexbond_inp_string_XXXXXX", path, sizeof path);
  const int fd = mkstemp(path);
  CHECK(fd >= 0);
  if (fd < 0)
    return;
  const size_t len = strlen(plate_deck);
  CHECK(write(fd, plate_deck, len) == (ssize_t)len);
  close(fd);
  fb_mesh *a = NULL, *b = NULL;
  fb_shell_props pa = {0, 0, 0, 0, 0, 0.0}, pb = {0, 0, 0, 0, 0, 0.0};
  fb_err err;
  CHECK(fb_mesh_read_inp(path, &a, &pa, &err) == FB_OK);
  CHECK(read_prefix(plate_deck, len, "plate.inp", &b, &pb, &err) == FB_OK);
  remove(path);
  CHECK(a && b);
  if (!a || !b) {
    fb_mesh_free(&a);
    fb_mesh_free(&b);
    return;
  }
  CHECK(fb_mesh_nnodes(a) == fb_mesh_nnodes(b) && fb_mesh_nelements(a) == fb_mesh_nelements(b));
  for (size_t i = 0; i < fb_mesh_nnodes(a) && i < fb_mesh_nnodes(b); ++i)
    CHECK(memcmp(fb_mesh_node_xyz(a, i), fb_mesh_node_xyz(b, i), 3 * sizeof(double)) == 0);
  CHECK(fb_mesh_nnsets(a) == fb_mesh_nnsets(b));
  CHECK(memcmp(&pa, &pb, sizeof pa) == 0);
  fb_mesh_free(&a);
  fb_mesh_free(&b);
}

/* Text after len is never read: a deck whose first len bytes are complete reads, although
 * the bytes after them would be an error; one cut inside a line is an error on that line. */
static void test_length_bound(void)
{
  char buf[sizeof plate_deck + 32];
  snprintf(buf, sizeof buf, "%s*NGEN, NSET=X\n", plate_deck);
  fb_mesh *m = NULL;
  fb_err err;
  CHECK(read_prefix(buf, strlen(plate_deck), "plate.inp", &m, NULL, &err) == FB_OK);
  CHECK(m && fb_mesh_nelements(m) == 3);
  fb_mesh_free(&m);
  CHECK(read_prefix(buf, strlen(buf), "plate.inp", &m, NULL, &err) == FB_EPARSE && !m);
  CHECK(has(&err, "plate.inp:23: *NGEN is not supported"));
  /* Cut after "5, 0.5, " on line 7 (node 5): too few fields there. */
  const char *cut = strstr(plate_deck, "5, 0.5, 0.25");
  const size_t len = (size_t)(cut - plate_deck) + strlen("5, 0.5, ");
  CHECK(read_prefix(plate_deck, len, "plate.inp", &m, NULL, &err) == FB_EPARSE && !m);
  CHECK(has(&err, "plate.inp:7: node line needs 'id, x, y, z', not 2 fields"));
}

/* Errors name display_name (or "<string>") and the line; the properties stay untouched. */
static void test_errors(void)
{
  fb_mesh *m = NULL;
  fb_shell_props p = {1, 2, 3, 4, 5, 0.0};
  fb_err err;
  static const char bad_number[] = "*NODE\n1, 0, 0, 0\n2, 1, 1.0x, 0\n";
  CHECK(read_prefix(bad_number, sizeof bad_number - 1, "deck.inp", &m, &p, &err) == FB_EPARSE);
  CHECK(m == NULL && err.code == FB_EPARSE);
  CHECK(strncmp(err.msg, "deck.inp:3: ", 12) == 0);
  CHECK(has(&err, "y of node 2: not a number (read: '1.0x')"));
  CHECK(p.young == 1 && p.poisson == 2 && p.density == 3 && p.thickness == 4 &&
        p.drill_factor == 5);
  CHECK(read_prefix(bad_number, sizeof bad_number - 1, NULL, &m, &p, &err) == FB_EPARSE);
  CHECK(strncmp(err.msg, "<string>:3: ", 12) == 0);

  /* A NUL byte inside the text, line 3 column 5, and one as the last byte. */
  static const char nul[] = "*NODE\n1, 0, 0, 0\n2, 1\0, 0, 0\n";
  CHECK(read_prefix(nul, sizeof nul - 1, "nul.inp", &m, NULL, &err) == FB_EPARSE && !m);
  CHECK(has(&err, "nul.inp:3: binary data (byte 0x00 in column 5)"));
  static const char nul_end[] = "*NODE\n1, 0, 0, 0\n\0";
  CHECK(read_prefix(nul_end, sizeof nul_end - 1, "end.inp", &m, NULL, &err) == FB_EPARSE);
  CHECK(has(&err, "end.inp:3: binary data (byte 0x00 in column 1)"));

  CHECK(read_prefix("", 0, "empty.inp", &m, NULL, &err) == FB_EPARSE && !m);
  CHECK(has(&err, "empty.inp:1: empty file"));

  fb_mesh *sentinel = NULL;
  CHECK(fb_mesh_new(&sentinel, &err) == FB_OK);
  m = sentinel;
  CHECK(fb_mesh_read_inp_string(NULL, 3, "x.inp", &m, NULL, &err) == FB_EINVAL && !m);
  CHECK(has(&err, "text is NULL"));
  CHECK(fb_mesh_read_inp_string(plate_deck, 5, "x.inp", NULL, NULL, &err) == FB_EINVAL);
  CHECK(has(&err, "out is NULL"));
  fb_mesh_free(&sentinel);
}

int main(void)
{
  test_plate();
  test_same_as_file();
  test_length_bound();
  test_errors();
  return check_report("test_inp_string");
}
