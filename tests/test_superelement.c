/* SPDX-License-Identifier: BSD-3-Clause */
/* A mesh's superelement (fb_mesh_set_superelement) and Guyan's
 * condensation (fb_fem_guyan), against hand derivations. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/fem.h"

#include "check.h"

/* Three masses on two springs k in a line, the middle one condensed:
 * K = k [1 -1 0; -1 2 -1; 0 -1 1], M = diag(m1, m2, m3). K_oo = 2k,
 * K_or = [-k -k], so T's middle row is [1/2 1/2]: the middle mass moves
 * as the average of its neighbours. kr = K_rr - K_ro K_oo^-1 K_or
 * = k [1 0; 0 1] - k^2 / (2k) [1 1; 1 1] = k/2 [1 -1; -1 1] (the two
 * springs in series), mr = T' M T = [m1 + m2/4, m2/4; m2/4, m3 + m2/4].
 * Exact arithmetic in binary (k, m powers of two over small integers):
 * 1e-15 relative. */
static void test_guyan_chain(void)
{
  fb_err err;
  const double k = 1000.0, m1 = 2.0, m2 = 4.0, m3 = 8.0;
  const size_t r[] = {0, 0, 1, 1, 1, 2, 2}, c[] = {0, 1, 0, 1, 2, 1, 2};
  const double kv[] = {k, -k, -k, 2 * k, -k, -k, k};
  const size_t mr_[] = {0, 1, 2};
  const double mv[] = {m1, m2, m3};
  fb_mat *K = NULL, *M = NULL;
  CHECK(fb_mat_new_triplets(3, 3, 7, r, c, kv, &K, &err) == FB_OK);
  CHECK(fb_mat_new_triplets(3, 3, 3, mr_, mr_, mv, &M, &err) == FB_OK);
  const size_t keep[] = {0, 2};
  double kr[4], mr[4];
  CHECK(fb_fem_guyan(K, M, keep, 2, kr, mr, &err) == FB_OK);
  const double kw[4] = {k / 2, -k / 2, -k / 2, k / 2};
  const double mw[4] = {m1 + m2 / 4, m2 / 4, m2 / 4, m3 + m2 / 4};
  for (int i = 0; i < 4; ++i) {
    CHECK(fabs(kr[i] - kw[i]) <= 1e-15 * k);
    CHECK(fabs(mr[i] - mw[i]) <= 1e-15 * m3);
  }
  /* Bad kept DOFs: not increasing, all of them. */
  const size_t bad[] = {2, 0}, all[] = {0, 1, 2};
  CHECK(fb_fem_guyan(K, M, bad, 2, kr, mr, &err) == FB_EINVAL);
  CHECK(fb_fem_guyan(K, M, all, 3, kr, mr, &err) == FB_EINVAL);
  fb_mat_free(&K);
  fb_mat_free(&M);
}

/* A mesh of two nodes carrying only a superelement: assembly gives its
 * matrices back at the nodes' DOFs (the second node first in the
 * superelement: its rows land at 6..11), a copy keeps it, the mesh
 * passes its checks, and its mass properties are those of the two point
 * masses its M holds on the translations (m_a at x = 0, m_b at x = 2:
 * centre at 2 m_b / (m_a + m_b), Izz = m_a m_b / (m_a + m_b) 2^2). */
static void test_mesh_superelement(void)
{
  fb_err err;
  fb_mesh *m = NULL, *copy = NULL;
  size_t a = 0, b = 0;
  CHECK(fb_mesh_new(&m, &err) == FB_OK);
  CHECK(fb_mesh_add_node(m, 1, 0, 0, 0, &a, &err) == FB_OK);
  CHECK(fb_mesh_add_node(m, 2, 2, 0, 0, &b, &err) == FB_OK);
  CHECK(fb_mesh_check(m, &err) == FB_EMODEL); /* nothing uses the nodes yet */
  double k[144] = {0}, mass[144] = {0};
  const double ma = 3.0, mb = 1.0;
  for (size_t i = 0; i < 12; ++i)
    for (size_t j = 0; j < 12; ++j)
      k[j * 12 + i] = (i == j ? 10.0 : 0.0) + (double)((i * 7 + j * 7) % 5);
  for (size_t i = 0; i < 3; ++i) {
    mass[i * 12 + i] = mb;             /* the superelement's first node: b */
    mass[(i + 6) * 12 + (i + 6)] = ma; /* its second: a */
  }
  const size_t nodes[2] = {b, a};
  CHECK(fb_mesh_set_superelement(m, 2, nodes, k, mass, &err) == FB_OK);
  const size_t bad[2] = {0, 7};
  CHECK(fb_mesh_set_superelement(m, 2, bad, k, mass, &err) == FB_EINVAL);
  CHECK(fb_mesh_check(m, &err) == FB_OK);
  CHECK(fb_mesh_clone(m, &copy, &err) == FB_OK);
  fb_mat *K = NULL, *M = NULL;
  fb_shell_props p = {200e9, 0.3, 7850, 0.01, 1e-4, 0};
  CHECK(copy && fb_fem_assemble(copy, &p, FB_MASS_CONSISTENT, &K, &M, &err) == FB_OK);
  int same = K != NULL;
  for (size_t i = 0; same && i < 12; ++i)
    for (size_t j = 0; j < 12; ++j) {
      /* superelement row i is node nodes[i / 6]'s DOF i % 6 */
      const size_t gi = 6 * nodes[i / 6] + i % 6, gj = 6 * nodes[j / 6] + j % 6;
      same = same && fb_mat_get(K, gi, gj) == k[j * 12 + i];
    }
  CHECK(same);
  double total = 0, cg[3], inertia[9];
  CHECK(fb_fem_mass_properties(copy, M, &total, cg, inertia, &err) == FB_OK);
  CHECK(fabs(total - (ma + mb)) <= 1e-14 * total);
  CHECK(fabs(cg[0] - 2 * mb / (ma + mb)) <= 1e-14);
  CHECK(fabs(inertia[8] - ma * mb / (ma + mb) * 4) <= 1e-14 * inertia[8]);
  double total2 = 0, cg2[3], inertia2[9];
  CHECK(fb_fem_mesh_mass_properties(copy, &p, FB_MASS_CONSISTENT, &total2, cg2, inertia2,
                                    &err) == FB_OK);
  CHECK(fabs(total2 - total) <= 1e-14 * total && fabs(cg2[0] - cg[0]) <= 1e-14 &&
        fabs(inertia2[8] - inertia[8]) <= 1e-14 * inertia[8]);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mesh_free(&copy);
  fb_mesh_free(&m);
}

int main(void)
{
  test_guyan_chain();
  test_mesh_superelement();
  return check_report(__FILE__);
}
