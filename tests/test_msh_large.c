/* SPDX-License-Identifier: BSD-3-Clause */
/* The gmsh reader (fb_mesh_read_msh, src/fem/msh.c) on a large file;
 * tests/test_mesh.c has the small ones. 150000 point entities, each the
 * only element of a block of its own, over a 500 x 300 grid of
 * quadrilaterals on one surface: a 14 MB file, as gmsh writes a hull with
 * a physical point at every node. Reading searched every entity and every
 * set for each block, and took 10 s (RelWithDebInfo; 68 s in Debug); it
 * is linear in the file now, about 0.5 s. No time is asserted: the test's
 * CTest TIMEOUT (CMakeLists.txt) fails it if reading goes quadratic again
 * (hours under valgrind). The file is written in a directory of its own
 * (mkdtemp under $TMPDIR), removed at the end. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/fem.h"

#include "check.h"

enum { NX = 500, NY = 300, NPOINTS = NX * NY, NQUADS = (NX - 1) * (NY - 1) };

/* Entity tag of point i: a permutation of 1 .. NPOINTS (7919 is a prime
 * that does not divide NPOINTS), so that entities are neither in tag order
 * nor in the order of their blocks. */
static long point_tag(long i)
{
  return (i * 7919) % NPOINTS + 1;
}

/* Physical groups: every point in POINTS (0, 1) and an unnamed group
 * (0, 9); the even points (nodes 1, 3, ...) also in EVEN (0, 2); the
 * surface in PLATE (2, 3). */
static void write_head(FILE *fp)
{
  fputs("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
        "$PhysicalNames\n3\n2 3 \"PLATE\"\n0 2 \"EVEN\"\n0 1 \"POINTS\"\n$EndPhysicalNames\n",
        fp);
  fprintf(fp, "$Entities\n%d 0 1 0\n", NPOINTS);
  for (long i = 0; i < NPOINTS; ++i)
    fprintf(fp, "%ld %ld %ld 0 %s\n", point_tag(i), i % NX, i / NX,
            i % 2 ? "2 9 1" : "3 1 9 2");
  fprintf(fp, "1 0 0 0 %d %d 0 1 3 0\n$EndEntities\n", NX - 1, NY - 1);
}

/* Node i + 1 at (i % NX, i / NX, 0), in one block on the surface. */
static void write_nodes(FILE *fp)
{
  fprintf(fp, "$Nodes\n1 %d 1 %d\n2 1 0 %d\n", NPOINTS, NPOINTS, NPOINTS);
  for (long i = 0; i < NPOINTS; ++i)
    fprintf(fp, "%ld\n", i + 1);
  for (long i = 0; i < NPOINTS; ++i)
    fprintf(fp, "%ld %ld 0\n", i % NX, i / NX);
  fputs("$EndNodes\n", fp);
}

/* The quadrilaterals (tags 1 .. NQUADS) in one block, then the points'
 * blocks from the last point to the first. */
static void write_elements(FILE *fp)
{
  fprintf(fp, "$Elements\n%d %d 1 %d\n2 1 3 %d\n", NPOINTS + 1, NQUADS + NPOINTS,
          NQUADS + NPOINTS, NQUADS);
  long tag = 0;
  for (long y = 0; y + 1 < NY; ++y)
    for (long x = 0; x + 1 < NX; ++x) {
      const long a = y * NX + x + 1;
      fprintf(fp, "%ld %ld %ld %ld %ld\n", ++tag, a, a + 1, a + 1 + NX, a + NX);
    }
  for (long i = NPOINTS - 1; i >= 0; --i)
    fprintf(fp, "0 %ld 15 1\n%ld %ld\n", point_tag(i), ++tag, i + 1);
  fputs("$EndElements\n", fp);
}

static int write_file(const char *path)
{
  FILE *fp = fopen(path, "w");
  if (!fp)
    return 1;
  write_head(fp);
  write_nodes(fp);
  write_elements(fp);
  return fclose(fp) != 0;
}

/* Set members: n of them, each a node of the parity odd_ids (1: odd ids,
 * 0: any), the first with id first. */
static void check_nset(const fb_mesh *m, const char *name, size_t n, int odd_ids, long first)
{
  const size_t *items = NULL;
  size_t count = 0;
  CHECK(fb_mesh_nset(m, name, &items, &count) && count == n);
  if (count != n)
    fprintf(stderr, "  %s: %zu nodes, expected %zu\n", name, count, n);
  size_t wrong = 0;
  for (size_t k = 0; k < count; ++k)
    wrong += odd_ids && fb_mesh_node_id(m, items[k]) % 2 == 0;
  CHECK(wrong == 0);
  CHECK(count > 0 && fb_mesh_node_id(m, items[0]) == first);
}

static void check_mesh(const fb_mesh *m)
{
  CHECK(fb_mesh_nnodes(m) == NPOINTS && fb_mesh_nelements(m) == NQUADS);
  /* Members in the order of the blocks: the last point's first. */
  check_nset(m, "POINTS", NPOINTS, 0, NPOINTS);
  check_nset(m, "EVEN", NPOINTS / 2, 1, NPOINTS - 1);
  check_nset(m, "PLATE", NPOINTS, 0, 1);
  size_t n = 0;
  CHECK(fb_mesh_elset(m, "PLATE", NULL, &n) && n == NQUADS);
  CHECK(fb_mesh_nnsets(m) == 3 && fb_mesh_nelsets(m) == 1);
  CHECK(fb_mesh_check(m, NULL) == FB_OK);
}

int main(void)
{
  const char *tmp = getenv("TMPDIR");
  char dir[512], path[600];
  snprintf(dir, sizeof dir, "%s/flexbond_msh_large_XXXXXX", tmp && *tmp ? tmp : "/tmp");
  if (!mkdtemp(dir)) {
    perror("mkdtemp");
    return 1;
  }
  snprintf(path, sizeof path, "%s/points.msh", dir);
  CHECK(write_file(path) == 0);
  fb_mesh *m = NULL;
  fb_err err;
  fb_err_clear(&err);
  const int rc = fb_mesh_read_msh(path, &m, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  %s\n", err.msg);
  else
    check_mesh(m);
  fb_mesh_free(&m);
  remove(path);
  rmdir(dir);
  return check_report("test_msh_large");
}
