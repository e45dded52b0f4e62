/* SPDX-License-Identifier: BSD-3-Clause */
/* CalculiX's own substructure file (fb_reduced_read_ccx) on a deck of
 * the test's: a 6 x 4 x 2 block of C3D8 bricks (1 x 1 x 0.5 each,
 * E = 210000, nu = 0.3), four corners retained with their translations.
 * Skipped (exit 77) when ccx is not on the PATH.
 *
 * What ccx 2.20 writes was measured here: the file reads as its layout
 * says (12 DOFs, the retained nodes and components in order), and the
 * retained corner's diagonal is the one C3D8 element's at that corner in
 * closed form. For a trilinear brick a x b x c, full 2 x 2 x 2
 * integration (exact for these products), the corner's
 * int N1,x^2 dV = b c / (9 a) (and alike), so K_xx = (lambda + 2 mu)
 * b c / (9 a) + mu (c a / (9 b) + a b / (9 c)) = 38141.03: the rows of
 * the assembled stiffness at the retained DOFs with every other DOF held,
 * not the condensation K_rr - K_ro K_oo^-1 K_or, whose diagonal is
 * strictly smaller wherever the corner has neighbours (K_ro != 0).
 * fb_reduced_check refuses it as a superelement that is not free-free,
 * which is what it is. (ccx 2.20 aborts on a single-element deck and
 * writes zeros for S4 shells: docs/reduced-hulls.md.) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/reduced.h"

#include "check.h"
#include "tmpdir.h"

enum { NX = 6, NY = 4, NZ = 2 };

static int node_id(int i, int j, int k)
{
  return 1 + i + (NX + 1) * (j + (NY + 1) * k);
}

/* 1 if an executable ccx is on the PATH. */
static int have_ccx(void)
{
  const char *path = getenv("PATH");
  if (!path)
    return 0;
  char buf[4096];
  for (const char *p = path; *p;) {
    const size_t n = strcspn(p, ":");
    if (n > 0 && n + 5 < sizeof buf) {
      memcpy(buf, p, n);
      strcpy(buf + n, "/ccx");
      if (access(buf, X_OK) == 0)
        return 1;
    }
    p += n + (p[n] == ':');
  }
  return 0;
}

static const int retained[4][3] = {{0, 0, 0}, {NX, 0, 0}, {NX, NY, 0}, {0, NY, NZ}};

static int write_deck(const char *path)
{
  FILE *fp = fopen(path, "w");
  if (!fp)
    return 0;
  fprintf(fp, "*NODE,NSET=NALL\n");
  for (int k = 0; k <= NZ; ++k)
    for (int j = 0; j <= NY; ++j)
      for (int i = 0; i <= NX; ++i)
        fprintf(fp, "%d,%d,%d,%g\n", node_id(i, j, k), i, j, 0.5 * k);
  fprintf(fp, "*ELEMENT,TYPE=C3D8,ELSET=EALL\n");
  int e = 1;
  for (int k = 0; k < NZ; ++k)
    for (int j = 0; j < NY; ++j)
      for (int i = 0; i < NX; ++i)
        fprintf(fp, "%d,%d,%d,%d,%d,%d,%d,%d,%d\n", e++, node_id(i, j, k), node_id(i + 1, j, k),
                node_id(i + 1, j + 1, k), node_id(i, j + 1, k), node_id(i, j, k + 1),
                node_id(i + 1, j, k + 1), node_id(i + 1, j + 1, k + 1),
                node_id(i, j + 1, k + 1));
  fprintf(fp, "*MATERIAL,NAME=STEEL\n*ELASTIC\n210000,0.3\n"
              "*SOLID SECTION,ELSET=EALL,MATERIAL=STEEL\n*STEP\n*SUBSTRUCTURE GENERATE\n"
              "*RETAINED NODAL DOFS\n");
  for (int r = 0; r < 4; ++r)
    fprintf(fp, "%d,1,3\n", node_id(retained[r][0], retained[r][1], retained[r][2]));
  fprintf(fp, "*SUBSTRUCTURE MATRIX OUTPUT,STIFFNESS=YES,OUTPUT FILE=USER DEFINED,"
              "FILE NAME=kred\n*END STEP\n");
  return fclose(fp) == 0;
}

int main(void)
{
  if (!have_ccx()) {
    fprintf(stderr, "test_reduced_ccx: skipped: no ccx on the PATH (CalculiX 2.20: "
                    "apt-get install calculix-ccx)\n");
    return 77;
  }
  char deck[TEST_PATH_MAX], nodes[TEST_PATH_MAX], mtx[TEST_PATH_MAX], cmd[3 * TEST_PATH_MAX];
  test_tmp_path("block.inp", deck, sizeof deck);
  test_tmp_path("nodes.csv", nodes, sizeof nodes);
  test_tmp_path("kred.mtx", mtx, sizeof mtx);
  CHECK(write_deck(deck));
  FILE *fp = fopen(nodes, "w");
  CHECK(fp != NULL);
  if (!fp)
    return check_report("test_reduced_ccx");
  for (int r = 0; r < 4; ++r)
    fprintf(fp, "%d, %d, %d, %g\n", node_id(retained[r][0], retained[r][1], retained[r][2]),
            retained[r][0], retained[r][1], 0.5 * retained[r][2]);
  fclose(fp);
  snprintf(cmd, sizeof cmd, "cd '%s' && ccx block > ccx.log 2>&1", test_tmpdir());
  CHECK(system(cmd) == 0);

  fb_reduced *r = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_reduced_read_ccx(mtx, nodes, &r, &err) == FB_OK);
  if (!r) {
    fprintf(stderr, "%s\n", err.msg);
    return check_report("test_reduced_ccx");
  }
  CHECK(fb_reduced_ndofs(r) == 12);
  for (size_t d = 0; d < 12 && fb_reduced_ndofs(r) == 12; ++d) {
    const int *p = retained[d / 3];
    CHECK(fb_reduced_dof_node(r, d) == node_id(p[0], p[1], p[2]));
    CHECK(fb_reduced_dof_component(r, d) == (int)(d % 3) + 1);
  }
  /* The corner brick: a = b = 1, c = 0.5. */
  const double young = 210000.0, nu = 0.3, a = 1.0, b = 1.0, c = 0.5;
  const double lambda = young * nu / ((1 + nu) * (1 - 2 * nu)), mu = young / (2 * (1 + nu));
  const double kxx =
      (lambda + 2 * mu) * b * c / (9 * a) + mu * (c * a / (9 * b) + a * b / (9 * c));
  const double kzz =
      (lambda + 2 * mu) * a * b / (9 * c) + mu * (b * c / (9 * a) + c * a / (9 * b));
  /* ccx writes 13 significant digits: 5e-13 of the value. */
  CHECK_NEAR(fb_mat_get(fb_reduced_stiffness(r), 0, 0), kxx, 5e-13 * kxx);
  CHECK_NEAR(fb_mat_get(fb_reduced_stiffness(r), 2, 2), kzz, 5e-13 * kzz);
  const int rc = fb_reduced_check(r, &err);
  CHECK(rc == FB_EMODEL && strstr(err.msg, "K is not free-free") != NULL);
  fprintf(stderr, "test_reduced_ccx: K(1 ux, 1 ux) = %.13g (one brick: %.13g); the check: %s\n",
          fb_mat_get(fb_reduced_stiffness(r), 0, 0), kxx, err.msg);
  fb_reduced_free(&r);
  return check_report("test_reduced_ccx");
}
