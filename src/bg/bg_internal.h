/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal layout of a bond graph, shared by src/bg and src/bd. */
#ifndef FLEXBOND_BG_INTERNAL_H
#define FLEXBOND_BG_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "flexbond/bg.h"

#include "core/util.h"

#define FB_NONE SIZE_MAX

/* Causal stroke of a bond: which end receives the effort. */
enum { FB_STROKE_UNSET = -1, FB_STROKE_AT_FROM = 0, FB_STROKE_AT_TO = 1 };

typedef struct fb_bg_elem {
  char *name;
  fb_bg_kind kind;
  size_t dim;        /* junction/TF/GY/source dimension; stacked dim of fields/MTF */
  int fixed_ports;   /* 1: ports are numbered slots; 0: junction (grows) */
  size_t nports;     /* slots (fixed) or bonds attached (junction) */
  size_t cap;        /* capacity of bonds[] for junctions */
  size_t *port_dims; /* fixed: dimension of each slot */
  size_t *bonds;     /* bond at each slot (FB_NONE if unconnected) */
  fb_mat *law;       /* field M, K or R; MTF T */
  const fb_law_ops *law_ops;
  void *law_ctx;
  double modulus;   /* TF ratio, GY modulus */
  fb_tfun **values; /* sources: dim functions */
  double *x0;       /* storage fields: initial state, dim values */
  size_t *mod_src;  /* modulated R: the storage elements whose states it reads */
  size_t nmod;
  char **labels; /* dim labels of its components for a reader (owned), NULL: none */
} fb_bg_elem;

typedef struct fb_bg_bond {
  char *name;
  size_t dim;
  fb_bg_domain domain;
  size_t from, to;           /* element indices, power from -> to */
  size_t from_slot, to_slot; /* slot at each element */
  int stroke;                /* FB_STROKE_* */
  size_t cause;              /* element whose choice fixed the stroke */
} fb_bg_bond;

/* A port name visible in the graph: exported ports of the graph itself
 * (exported = 1, for its parent) and ports of adopted subsystems
 * ("inst.p", exported = 0, connectable here). */
typedef struct fb_bg_portdef {
  char *name;
  fb_bg_dir dir;
  int exported;
  int used;    /* connected or re-exported */
  size_t elem; /* target element */
  size_t slot; /* target slot, FB_NONE for a junction (adds a slot) */
  size_t dim;
} fb_bg_portdef;

struct fb_bg {
  char *name;
  fb_bg_domain domain;
  fb_bg_elem *elems;
  size_t nelems, cap_elems;
  fb_bg_bond *bonds;
  size_t nbonds, cap_bonds;
  fb_bg_portdef *ports;
  size_t nports, cap_ports;
  char **instances; /* names of adopted subsystems */
  size_t ninstances, cap_instances;
  int causal; /* 1 once causality has been assigned */
};

/* 1 if element e receives the effort of bond b (causal stroke at e). */
int fb_bg_receives_effort(const fb_bg *bg, size_t b, size_t e);
/* +1 if bond b points into element e, -1 if it points out of it. */
int fb_bg_orientation(const fb_bg *bg, size_t b, size_t e);
/* FB_OK if name may name a new element of bg (non-empty, no '.', not an
 * element or subsystem instance yet); FB_EMODEL saying why otherwise. */
int fb_bg_check_new_name(const fb_bg *bg, const char *name, fb_err *err);
/* "I 'Ms'" style description of an element for messages. */
void fb_bg_describe(const fb_bg *bg, size_t e, char *buf, size_t size);

/* ---- Subsystem instances as element names show them (src/bg/groups.c),
 * for the pictures of a graph: adopting a subsystem prefixes its element
 * names "inst.", so an element "a.b.x" sits in instance "a.b", itself in
 * "a". Every prefix of an element name is a group, also one that holds no
 * element of its own ("a" when only "a.b" has elements). */
typedef struct fb_bg_groups {
  size_t n;
  const char **name; /* group i is name[i][0 .. len[i]): borrowed from bg's element names */
  size_t *len;
  size_t *parent;  /* enclosing group, FB_NONE at the top level */
  size_t *of_elem; /* per element: its innermost group, FB_NONE at the top level */
} fb_bg_groups;

/* Finds the groups of bg into *g (arrays new; free them with
 * fb_bg_groups_free). Groups are ordered by first appearance, an
 * enclosing group before the groups it holds. FB_ENOMEM. */
int fb_bg_groups_make(const fb_bg *bg, fb_bg_groups *g, fb_err *err);
void fb_bg_groups_free(fb_bg_groups *g);
/* The outermost group that holds group i (i itself at the top level). */
size_t fb_bg_groups_top(const fb_bg_groups *g, size_t i);
/* name without the prefix of group i ("a.b.x" in "a.b" -> "x"); name when
 * i is FB_NONE or name does not start with the group's name and a '.'. */
const char *fb_bg_groups_strip(const fb_bg_groups *g, size_t i, const char *name);

#endif
