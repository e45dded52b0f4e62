/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: where System 2's hull mesh comes from, a gallery of sources.
 *
 * A hull source is content (a name, one line of documentation) and ops
 * that make the mesh for a description: the built-in generator
 * (fb_hull_source_generator: the paper's hull from the description's
 * points and its hull_mesh parameters) and a file
 * (fb_hull_source_deck: an Abaqus/CalculiX deck or a gmsh 4.1 mesh,
 * read once). A program adds its own to a gallery
 * (fb_hull_source_gallery_add) and sets it on its descriptions
 * (fb_scenario_set_hull_source); the library asks the source, never
 * which source it is (docs/architecture.md, "Adding a hull source").
 *
 * Every mesh a source gives carries the node sets of
 * fb_hull_mesh_generate (LOAD, SUSP_<CORNER>, the mounts', MASS_<NAME>,
 * FRONT_EDGE, REAR_EDGE, ALL) or couples the points to its surface
 * (hull.mesh.coupling); the conformance harness of
 * tests/test_hull_source.c checks every source of the gallery for it. */
#ifndef FLEXBOND_HULL_SOURCE_H
#define FLEXBOND_HULL_SOURCE_H

#include <stddef.h>
#include <stdint.h>

#include "flexbond/error.h"
#include "flexbond/fem.h"
#include "flexbond/param.h"
#include "flexbond/vehicle.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The ops of a hull source. A source either reads its mesh once, when the
 * description is loaded (read), in a frame of its own that the library
 * moves to the structure's centre of mass; or makes it from the
 * description whenever it is needed (make, key and centroid). Errors
 * about a value of the description name its part (fb_err.part). NULL ops
 * are noted. */
typedef struct fb_hull_source_ops {
  /* The rules between the description's values that concern this source
   * (fb_scenario_check calls it). NULL: none. */
  int (*check)(const fb_scenario *s, fb_err *err);
  /* Reads the source's mesh, once (*out new, owned by the caller).
   * NULL: the source makes it (make). */
  int (*read)(const fb_scenario *s, fb_mesh **out, fb_err *err);
  /* The mesh for the description as it is now (*out new). */
  int (*make)(const fb_scenario *s, fb_mesh **out, fb_err *err);
  /* A fingerprint of everything make reads: equal keys, the same mesh
   * (the description's cached mesh is current while its key is). */
  uint64_t (*key)(const fb_scenario *s);
  /* Where make's structure has its centre of mass, in the description's
   * frame, before the mesh is made: *x and *z (its height in the frame,
   * the generator's above its floor), and *length, the hull's length (m),
   * the scale a given centre of mass is compared at. The mesh make gives
   * has that centre of mass at its origin. */
  void (*centroid)(const fb_scenario *s, double *x, double *z, double *length);
  /* The refinement the mesh is made at (d x d elements for each of the
   * coarsest mesh's); 0: the source is not refined (a file is used as it
   * is). NULL: 0. */
  int (*density)(const fb_scenario *s);
  /* One clause for a report: "the built-in generator at density 2",
   * "the deck hull.inp", into buf (n bytes, truncated). */
  void (*describe)(const fb_scenario *s, char *buf, size_t n);
  /* Marks an error of the mesh it gave (err's message and part) as its
   * own: a file names itself. NULL: nothing to add. */
  void (*blame)(const fb_scenario *s, fb_err *err);
} fb_hull_source_ops;

struct fb_hull_source {
  const char *name; /* letters, digits and '_', not from a digit: "generator" */
  const char *doc;  /* one line */
  /* The values it reads from the description's hull_params (numbers,
   * choices, lists and files: the block is copied by value, its files'
   * paths duplicated, and freed with the description), flexbond/param.h.
   * A maker of descriptions names them in its own words (a scenario
   * file's keys hull.mesh.<source>.<param>). The generator and the deck
   * declare none: the scenario format's own keys fill hull_deck and
   * hull_mesh. */
  const fb_param *param;
  size_t nparams;
  size_t params_size; /* <= FB_HULL_SOURCE_PARAMS_MAX */
  const fb_hull_source_ops *ops;
  /* 1 if every mesh it gives has a node of its own at each of the
   * description's points (its one-node sets): a coupling
   * (fb_scenario.coupling) then changes nothing, as every point meets its
   * node. 0: not known. */
  int nodes_at_points;
};

/* 0 if src is a sound source: a well-formed name and documentation,
 * sound declarations of its parameters (fb_params_declared) in a
 * block that fits, describe, and either read alone or make with key and
 * centroid.
 * FB_EINVAL naming the fault otherwise. */
int fb_hull_source_check(const fb_hull_source *src, fb_err *err);

/* The built-in sources. */
extern const fb_hull_source fb_hull_source_generator;
extern const fb_hull_source fb_hull_source_deck;
/* A structure reduced elsewhere: Matrix Market or DMIG stiffness and mass
 * over interface nodes (docs/reduced-hulls.md). */
extern const fb_hull_source fb_hull_source_reduced;

/* The source of s's hull: the one set, else the generator. */
const fb_hull_source *fb_scenario_hull_source(const fb_scenario *s);
/* Sets src (borrowed: it must outlive s and its copies) as s's source:
 * when it is another than s's, drops the mesh s keeps from the one before
 * and starts a new block (zeroed, the declared defaults). FB_EINVAL when
 * src is not sound. Errors about a parameter of the block name it
 * (FB_PART_HULL_SOURCE). */
int fb_scenario_set_hull_source(fb_scenario *s, const fb_hull_source *src, fb_err *err);
/* Reads the mesh of a source that reads one into s's hull_source_mesh
 * (a maker of descriptions calls it once, after fb_scenario_check and
 * before fb_vehicle_hull_complete); nothing for one that makes it. */
int fb_scenario_read_hull(fb_scenario *s, fb_err *err);
/* 1 if s's hull mesh is one its source reads, in a frame of its own,
 * which the loader moves with the positions to the structure's centre of
 * mass (fb_vehicle_hull_complete); 0 for one made in s's frame. */
int fb_scenario_hull_read_in_own_frame(const fb_scenario *s);
/* The refinement s's mesh is made at; 0: its source is not refined. */
int fb_scenario_hull_density(const fb_scenario *s);
/* One clause describing s's mesh source, into buf (n bytes). */
void fb_scenario_hull_describe(const fb_scenario *s, char *buf, size_t n);

/* fb_hull_source_gallery (flexbond/vehicle.h) is a set of hull sources:
 * the built-in ones, and those a program adds. */

/* A gallery of the built-in sources (*out new). FB_ENOMEM. */
int fb_hull_source_gallery_new(fb_hull_source_gallery **out, fb_err *err);
/* Adds src (borrowed: it must outlive the gallery). FB_EINVAL when src
 * is not sound (fb_hull_source_check) or its name is taken. */
int fb_hull_source_gallery_add(fb_hull_source_gallery *g, const fb_hull_source *src,
                               fb_err *err);
size_t fb_hull_source_gallery_count(const fb_hull_source_gallery *g);
/* Source i in the order added (built-ins first), NULL out of range. */
const fb_hull_source *fb_hull_source_gallery_at(const fb_hull_source_gallery *g, size_t i);
/* The source named name, NULL if none. */
const fb_hull_source *fb_hull_source_gallery_find(const fb_hull_source_gallery *g,
                                                  const char *name);
void fb_hull_source_gallery_free(fb_hull_source_gallery **g);

#ifdef __cplusplus
}
#endif
#endif
