/* SPDX-License-Identifier: BSD-3-Clause */
/* libFuzzer target: the gmsh MSH 4.1 reader (fb_mesh_read_msh_string,
 * flexbond/fem.h) on arbitrary bytes and, for every mesh it accepts, the mesh checks
 * (fb_mesh_check: node use, degenerate, warped and non-convex elements, node sets).
 * Refused inputs are fine; a crash, a leak, undefined behaviour, an error without a
 * message or a slow input is a finding (docs/fuzzing.md). The seed
 * corpus/msh/many_point_blocks.msh (12000 point entities, each with an element block of
 * its own, 0.6 MB) takes about 0.1 s here; a reader that searches every entity or every
 * set per block takes 3 s on it: a timeout at -timeout=2. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "flexbond/fem.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  static const char empty[1] = "";
  const char *text = data ? (const char *)data : empty;
  fb_err err;
  fb_mesh *mesh = NULL;
  const int rc = fb_mesh_read_msh_string(text, size, "fuzz.msh", &mesh, &err);
  /* A refusal must leave no mesh and say why. */
  if (rc && (rc != err.code || err.msg[0] == '\0' || mesh))
    abort();
  if (!rc) {
    const int crc = fb_mesh_check(mesh, &err);
    if (crc && (crc != err.code || err.msg[0] == '\0'))
      abort();
  }
  fb_mesh_free(&mesh);
  return 0;
}
