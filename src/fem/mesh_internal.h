/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal helpers shared by the mesh modules (mesh.c, mesh_check.c,
 * inp.c, vtu.c). */
#ifndef FLEXBOND_FEM_MESH_INTERNAL_H
#define FLEXBOND_FEM_MESH_INTERNAL_H

#include <stdint.h>

#include "flexbond/fem.h"

/* Longest node set name accepted (Abaqus labels are at most 80
 * characters). */
#define FB_MESH_NAME_MAX 80

/* Abaqus name of an element type, "S3" or "S4" ("?" for anything else). */
const char *fb_mesh_type_name(fb_elem_type type);

/* Number of nodes of an element type: 3, 4, or 0 if type is invalid. */
size_t fb_mesh_type_nodes(fb_elem_type type);

/* 1 if name can name a node set: 1 to FB_MESH_NAME_MAX characters from
 * [A-Za-z0-9_.-], starting with a letter or '_'. The restriction keeps
 * names valid unquoted in Abaqus decks and in XML attributes. */
int fb_mesh_name_ok(const char *name);

/* A hash of a set name that ignores case, as set names do (fb_mesh_nset):
 * for tables keyed by set names. */
uint64_t fb_mesh_name_key(const char *name);

/* The element tests of fb_mesh_check (degenerate, warped), element by
 * element in index order: the first failure is recorded (FB_EMODEL) and
 * its element index stored in *bad. Lets a reader report the element at
 * its own place in the file. */
int fb_mesh_check_elements(const fb_mesh *m, size_t *bad, fb_err *err);

#endif
