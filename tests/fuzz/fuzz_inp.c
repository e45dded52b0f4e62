/* SPDX-License-Identifier: BSD-3-Clause */
/* libFuzzer target: the Abaqus/CalculiX deck reader (fb_mesh_read_inp_string,
 * flexbond/fem.h) on arbitrary bytes and, for every mesh it accepts, the mesh checks
 * (fb_mesh_check: node use, degenerate, warped and non-convex elements, node sets) and
 * its sets, which must hold each member once however often the deck names it (sets
 * that name sets, src/fem/inp.c) and its added masses, which must be finite, >= 0 and on
 * its nodes. Refused inputs are fine; a crash, a leak, undefined
 * behaviour, an error without a message, a set with a repeated member, a bad added mass, or a
 * slow or memory-hungry input (a reader that multiplies set references) is a finding
 * (docs/fuzzing.md). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "flexbond/fem.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* 1 if every node set (elements 0) or element set (1) of m holds distinct members
 * of the mesh: one stamp per node or element, the set's index + 1, so the check
 * costs O(mesh + members). */
static int sets_distinct(const fb_mesh *m, int elements)
{
  const size_t universe = elements ? fb_mesh_nelements(m) : fb_mesh_nnodes(m);
  const size_t nsets = elements ? fb_mesh_nelsets(m) : fb_mesh_nnsets(m);
  size_t *stamp = calloc(universe ? universe : 1, sizeof *stamp);
  if (!stamp)
    abort();
  int ok = 1;
  for (size_t s = 0; s < nsets && ok; ++s) {
    const size_t *items = NULL;
    size_t n = 0;
    if (elements)
      fb_mesh_elset(m, fb_mesh_elset_name(m, s), &items, &n);
    else
      fb_mesh_nset(m, fb_mesh_nset_name(m, s), &items, &n);
    for (size_t k = 0; k < n && ok; ++k) {
      ok = items[k] < universe && stamp[items[k]] != s + 1;
      if (ok)
        stamp[items[k]] = s + 1;
    }
  }
  free(stamp);
  return ok;
}

/* 1 if every point mass is on a node of m and every mass, point or per area, is finite
 * and >= 0 (the reader's *MASS and *NONSTRUCTURAL MASS). */
static int masses_sound(const fb_mesh *m)
{
  for (size_t i = 0; i < fb_mesh_npoint_masses(m); ++i) {
    const double v = fb_mesh_point_mass(m, i);
    if (fb_mesh_point_mass_node(m, i) >= fb_mesh_nnodes(m) || !(v >= 0.0 && isfinite(v)))
      return 0;
  }
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    const double v = fb_mesh_element_nonstructural(m, e);
    if (!(v >= 0.0 && isfinite(v)))
      return 0;
  }
  return 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  static const char empty[1] = "";
  const char *text = data ? (const char *)data : empty;
  fb_err err;
  fb_mesh *mesh = NULL;
  fb_shell_props props = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const int rc = fb_mesh_read_inp_string(text, size, "fuzz.inp", &mesh, &props, &err);
  /* A refusal must leave no mesh and say why. */
  if (rc && (rc != err.code || err.msg[0] == '\0' || mesh))
    abort();
  if (!rc) {
    const int crc = fb_mesh_check(mesh, &err);
    if (crc && (crc != err.code || err.msg[0] == '\0'))
      abort();
    if (!sets_distinct(mesh, 0) || !sets_distinct(mesh, 1) || !masses_sound(mesh))
      abort();
  }
  fb_mesh_free(&mesh);
  return 0;
}
