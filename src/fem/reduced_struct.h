/* SPDX-License-Identifier: BSD-3-Clause */
/* The reduced structure's fields, for its own files only. */
#ifndef FLEXBOND_FEM_REDUCED_STRUCT_H
#define FLEXBOND_FEM_REDUCED_STRUCT_H

#include "fem/reduced_internal.h"

/* Where stored entry (i, j) was written (one per entry the file gave; a
 * symmetric file's entry stands for (i, j) with i >= j). */
typedef struct reduced_where {
  size_t i, j, line;
} reduced_where;

/* [0] is K's, [1] M's. */
struct fb_reduced {
  reduced_nodes nodes;
  size_t ndof;
  size_t *dof_node;        /* index into nodes */
  int *dof_comp;           /* 1..6 */
  fb_mat *K, *M;           /* owned; M NULL when the files give none */
  char *path[2];           /* owned; the files the matrices came from */
  reduced_where *where[2]; /* owned; NULL when the format keeps no lines */
  size_t nwhere[2];
  double precision[2]; /* relative rounding of the files' numbers */
};

#endif
