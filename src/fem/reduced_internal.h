/* SPDX-License-Identifier: BSD-3-Clause */
/* What the readers of reduced structures share (src/fem/reduced*.c). */
#ifndef FLEXBOND_FEM_REDUCED_INTERNAL_H
#define FLEXBOND_FEM_REDUCED_INTERNAL_H

#include <stddef.h>

#include "flexbond/reduced.h"

/* One matrix entry as a file wrote it: row (node id, component), column,
 * value and the line it is on. */
typedef struct reduced_entry {
  long node_i, node_j;
  int comp_i, comp_j;
  double val;
  size_t line;
} reduced_entry;

/* A matrix's entries as read. one_triangle: the file gives one triangle
 * of a symmetric matrix (each off-diagonal entry stands for its mirror
 * too, and giving both is an error); precision: the relative rounding of
 * the file's numbers (reduced_precision). */
typedef struct reduced_list {
  const char *path; /* borrowed */
  const char *name; /* "K" or "M" */
  reduced_entry *e;
  size_t n, cap;
  int one_triangle;
  double precision;
  size_t max; /* most entries it may have (0: any): see reduced_list_push */
} reduced_list;

/* A node id and its index, the nodes file's ids sorted for lookup. */
typedef struct reduced_node_key {
  long id;
  size_t index;
} reduced_node_key;

/* The interface nodes of a nodes file: ids, positions, and each node's
 * components (a bit per component 1..6; 0 when the file names none). At
 * most FB_REDUCED_MAX_DOFS of them (each has a DOF at least). */
typedef struct reduced_nodes {
  size_t n;
  reduced_node_key *sorted; /* by id: reduced_node_index */
  long *id;
  double *xyz;
  unsigned *comps;
  size_t *line;
  const char *path; /* borrowed */
} reduced_nodes;

int reduced_nodes_read(const char *path, reduced_nodes *nodes, fb_err *err);
/* reduced_nodes_read for a format whose matrices name their DOFs
 * (format: "DMIG"): a components field is an error at its line. */
int reduced_nodes_read_plain(const char *path, const char *format, reduced_nodes *nodes,
                             fb_err *err);
void reduced_nodes_free(reduced_nodes *nodes);

/* Appends e; past l->max entries FB_EPARSE at e's line: a matrix over d
 * DOFs has at most d^2 entries that are not given twice, so a file cannot
 * make the reader hold more than that (reduced_list_cap). */
int reduced_list_push(reduced_list *l, const reduced_entry *e, fb_err *err);
/* The most entries a matrix over the DOFs of nodes may have: d^2 with d
 * = 6 per node, at most FB_REDUCED_MAX_DOFS. */
size_t reduced_list_cap(const reduced_nodes *nodes);
/* The index of node id among nodes, or -1. */
long reduced_node_index(const reduced_nodes *nodes, long id);
void reduced_list_free(reduced_list *l);

/* The relative precision of numbers written with digits significant
 * digits, those below 4 counted as 4 (an exact value such as "1.+6" is
 * written short; 4 is the fewest an 8-column field holds): 0.5e-(d-1). */
double reduced_precision(int digits);
/* Significant digits of a decimal number's mantissa (leading zeros
 * excluded, trailing ones included); 0 for a zero. */
int reduced_digits(const char *text);

/* The structure from entries: the DOFs they name (each node in nodes, at
 * the line that names it otherwise), ordered by the nodes file's order
 * then component; entries given twice (or, for one triangle, with their
 * mirror) are errors at their line. m may be NULL. *out new. */
int reduced_build(reduced_nodes *nodes, reduced_list *k, reduced_list *m, fb_reduced **out,
                  fb_err *err);
/* The structure from matrices over the nodes file's DOFs (Matrix Market):
 * takes K, M (M may be NULL) and the nodes. */
int reduced_adopt(reduced_nodes *nodes, fb_mat *K, fb_mat *M, const char *k_path,
                  const char *m_path, double precision, fb_reduced **out, fb_err *err);

#endif
