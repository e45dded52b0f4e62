/* SPDX-License-Identifier: BSD-3-Clause */
/* A structure reduced in another finite-element tool as a hull source
 * (flexbond/hull_source.h, docs/reduced-hulls.md): its stiffness and mass
 * over the six DOFs of each interface node, read from Matrix Market files
 * or a Nastran DMIG punch file, checked (fb_reduced_check) before anything
 * is computed from them, and given to System 2 as a mesh of the interface
 * nodes carrying one superelement (fb_mesh_set_superelement): System 2's
 * hull then assembles, takes its free-free modal basis and its mass
 * properties from the superelement's matrices as from a shell mesh's.
 *
 * Each point of the vehicle (a corner's suspension point, a mount, a load
 * point, an edge's end, a hull mass) meets the interface node nearest to
 * it in plan: the node sets SUSP_<CORNER>, the mounts', LOAD, FRONT_EDGE,
 * REAR_EDGE and MASS_<NAME> are made of those nodes, and System 2 checks
 * each against its point (within 1 mm, fe_hull.c), so a point that is not
 * on an interface node is an error at the point's key. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/hull_source.h"
#include "flexbond/reduced.h"

#include "core/textfile.h"
#include "core/util.h"

typedef struct reduced_params {
  int format;   /* REDUCED_MTX or REDUCED_DMIG */
  char *k;      /* Matrix Market: K's file; DMIG: the punch file */
  char *m;      /* Matrix Market: M's file (DMIG: unused) */
  char *nodes;  /* the interface nodes' positions */
  char *attach; /* lines "SET, node id": a point's node by its id (NULL: none) */
} reduced_params;

enum { REDUCED_MTX, REDUCED_DMIG };

/* The longest set name the attach file may give (a deck's, Abaqus'). */
enum { REDUCED_SET_MAX = 80 };

static const char *const reduced_formats[] = {"mtx", "dmig", NULL};

/* Nastran's names of the matrices EXTSEOUT(DMIGPCH) punches for an
 * external superelement's boundary: stiffness KAAX, mass MAAX (MSC Nastran
 * Superelements User's Guide, "External Superelements"). */
static const char *const DMIG_K = "KAAX";
static const char *const DMIG_M = "MAAX";

static const fb_param reduced_param[] = {
    {.name = "format",
     .kind = FB_PARAM_CHOICE,
     .store = FB_PARAM_INT,
     .offset = offsetof(reduced_params, format),
     .need = FB_PARAM_DEFAULT,
     .def = REDUCED_MTX,
     .choices = reduced_formats,
     .doc = "mtx: Matrix Market K and M; dmig: a Nastran DMIG punch file with KAAX and MAAX"},
    {.name = "k",
     .kind = FB_PARAM_FILE,
     .store = FB_PARAM_STRING,
     .offset = offsetof(reduced_params, k),
     .need = FB_PARAM_REQUIRED,
     .doc = "the stiffness (mtx), or the punch file holding both matrices (dmig)"},
    {.name = "m",
     .kind = FB_PARAM_FILE,
     .store = FB_PARAM_STRING,
     .offset = offsetof(reduced_params, m),
     .need = FB_PARAM_OPTIONAL,
     .doc = "the mass (mtx: required; dmig: not given, the punch file's MAAX)"},
    {.name = "nodes",
     .kind = FB_PARAM_FILE,
     .store = FB_PARAM_STRING,
     .offset = offsetof(reduced_params, nodes),
     .need = FB_PARAM_REQUIRED,
     .doc = "the interface nodes, lines `id, x, y, z` (m), with `123456` after them for mtx"},
    {.name = "attach",
     .kind = FB_PARAM_FILE,
     .store = FB_PARAM_STRING,
     .offset = offsetof(reduced_params, attach),
     .need = FB_PARAM_OPTIONAL,
     .doc = "lines `SET, id`: the interface node of a corner's (`SUSP_LF`), mount's "
            "(`DRIVER`) or hull mass's (`MASS_<NAME>`) point by its id; other points take "
            "the nearest"},
};

static const reduced_params *reduced_of(const fb_scenario *s)
{
  return (const reduced_params *)s->hull_params.bytes;
}

static int reduced_fail(fb_err *err, const char *field)
{
  return fb_err_set_part(err, FB_PART_HULL_SOURCE, 0, FB_ERR_NO_ELEMENT, field),
         err ? err->code : FB_EINVAL;
}

/* A hull needs a mass (Matrix Market's M), and a structure's own node
 * sets (coupling to a surface needs its elements). */
static int reduced_check(const fb_scenario *s, fb_err *err)
{
  const reduced_params *p = reduced_of(s);
  if (p->format == REDUCED_MTX && !(p->m && p->m[0]))
    return fb_err_set(err, FB_EINVAL, "a hull needs its mass: the file of M"),
           reduced_fail(err, "m");
  if (p->format == REDUCED_DMIG && p->m)
    return fb_err_set(err, FB_EINVAL,
                      "a DMIG file holds both matrices (%s and %s): give it as k alone", DMIG_K,
                      DMIG_M),
           reduced_fail(err, "m");
  if (s->coupling != FB_COUPLING_NONE)
    return fb_err_set(err, FB_EINVAL,
                      "a reduced hull has no surface to couple to: its points meet its "
                      "interface nodes"),
           fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, coupling)), FB_EINVAL;
  return FB_OK;
}

/* Every interface node with all six DOFs: System 2's hull numbers six
 * per node, and a node's missing rotations would have neither stiffness
 * nor mass. */
static int reduced_six_each(const fb_reduced *r, fb_err *err)
{
  for (size_t i = 0; i < fb_reduced_nnodes(r); ++i) {
    const long id = fb_reduced_node_id(r, i);
    int have = 0;
    for (int c = 1; c <= 6; ++c)
      have += fb_reduced_find_dof(r, id, c) >= 0;
    if (have != 0 && have != 6)
      return fb_err_set(err, FB_EMODEL,
                        "interface node %ld has %d of its 6 DOFs: a hull needs all six of each "
                        "node (condense onto components 123456)",
                        id, have);
  }
  return FB_OK;
}

/* The mesh of the interface nodes that have DOFs, in the nodes file's
 * order, index[i] the mesh node of r's node i (or SIZE_MAX). */
static int reduced_nodes(const fb_reduced *r, fb_mesh *m, size_t *index, fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < fb_reduced_nnodes(r); ++i) {
    const long id = fb_reduced_node_id(r, i);
    const double *x = fb_reduced_node_xyz(r, i);
    index[i] = SIZE_MAX;
    if (fb_reduced_find_dof(r, id, 1) >= 0)
      rc = fb_mesh_add_node(m, id, x[0], x[1], x[2], &index[i], err);
  }
  return rc;
}

/* The superelement over the mesh's nodes: K with its rigid-body motions
 * exact (fb_reduced_stiffness_projected) and M, each DOF at its node's
 * place (6 a + component - 1). */
static int reduced_superelement(const fb_reduced *r, const size_t *index, fb_mesh *m,
                                fb_err *err)
{
  const size_t nn = fb_mesh_nnodes(m), d = 6 * nn, n = fb_reduced_ndofs(r);
  fb_mat *kp = NULL;
  /* A checked superelement has at least six DOFs on at least one node. */
  if (!nn || !n)
    return fb_err_set(err, FB_EINVAL, "a superelement without DOFs");
  size_t *nodes = malloc(nn * sizeof *nodes), *at = malloc(n * sizeof *at);
  double *k = calloc(d * d, sizeof *k), *ms = calloc(d * d, sizeof *ms);
  int rc = nodes && at && k && ms ? fb_reduced_stiffness_projected(r, &kp, err)
                                  : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t a = 0; !rc && a < nn; ++a)
    nodes[a] = a;
  for (size_t i = 0; !rc && i < n; ++i) {
    const long node = fb_reduced_dof_node(r, i);
    size_t a = 0;
    while (fb_reduced_node_id(r, a) != node)
      ++a;
    at[i] = 6 * index[a] + (size_t)fb_reduced_dof_component(r, i) - 1;
  }
  const fb_mat *mass = fb_reduced_mass(r);
  for (size_t j = 0; !rc && j < n; ++j)
    for (size_t i = 0; i < n; ++i) {
      k[at[j] * d + at[i]] = fb_mat_get(kp, i, j);
      ms[at[j] * d + at[i]] = fb_mat_get(mass, i, j);
    }
  if (!rc)
    rc = fb_mesh_set_superelement(m, nn, nodes, k, ms, err);
  fb_mat_free(&kp);
  free(nodes);
  free(at);
  free(k);
  free(ms);
  return rc;
}

/* The attach file: a one-node set's interface node by its id. */
typedef struct attach_line {
  char set[REDUCED_SET_MAX + 1]; /* in capitals */
  long id;
  size_t line;
  int used;
} attach_line;

typedef struct attach_map {
  const char *path;
  attach_line *line;
  size_t n, cap;
} attach_map;

static int attach_fail(const attach_map *a, size_t line, fb_err *err, const char *what)
{
  return fb_err_set(err, FB_EPARSE, "%s:%zu: %s", a->path, line, what),
         reduced_fail(err, "attach");
}

/* One line "SET, id" of the attach file. */
static int attach_parse(attach_map *a, const char *text, size_t line_no, fb_err *err)
{
  const char *comma = strchr(text, ',');
  size_t len = comma ? (size_t)(comma - text) : 0;
  while (len && (text[len - 1] == ' ' || text[len - 1] == '\t'))
    --len;
  int ok = comma && len && len <= REDUCED_SET_MAX && isalpha((unsigned char)text[0]);
  for (size_t i = 0; ok && i < len; ++i)
    ok = isalnum((unsigned char)text[i]) || text[i] == '_';
  char *end = NULL;
  errno = 0;
  const long id = ok ? strtol(comma + 1, &end, 10) : 0;
  while (end && (*end == ' ' || *end == '\t'))
    ++end;
  if (!ok || errno || id <= 0 || !end || *end)
    return attach_fail(a, line_no, err,
                       "expected 'SET, id': a node set's name (letters, digits, '_') and an "
                       "interface node's id");
  if (fb_grow((void **)&a->line, &a->cap, a->n, sizeof *a->line))
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  attach_line *l = &a->line[a->n++];
  *l = (attach_line){.id = id, .line = line_no};
  for (size_t i = 0; i < len; ++i)
    l->set[i] = (char)toupper((unsigned char)text[i]);
  for (size_t k = 0; k + 1 < a->n; ++k)
    if (!strcmp(a->line[k].set, l->set))
      return attach_fail(a, line_no, err, "the set is given again");
  return FB_OK;
}

static int attach_read(const char *path, attach_map *a, fb_err *err)
{
  *a = (attach_map){.path = path};
  if (!path)
    return FB_OK;
  fb_text_reader r;
  int rc = fb_text_open(&r, path, "attach", err);
  if (rc)
    reduced_fail(err, "attach");
  for (char *line = NULL; !rc;) {
    rc = fb_text_next_data_line(&r, '#', &line);
    if (rc)
      reduced_fail(err, "attach");
    if (rc || !line)
      break;
    rc = attach_parse(a, line, r.line_no, err);
  }
  fb_text_close(&r);
  return rc;
}

/* The attach file's node for set (in capitals), or -1 when it names
 * none; an error at the file's line when its id is no interface node. */
static int attach_node(attach_map *a, const fb_mesh *m, const char *set, long *node,
                       fb_err *err)
{
  *node = -1;
  for (size_t k = 0; k < a->n; ++k)
    if (!strcmp(a->line[k].set, set)) {
      a->line[k].used = 1;
      *node = fb_mesh_find_node_id(m, a->line[k].id);
      if (*node < 0)
        return attach_fail(a, a->line[k].line, err,
                           "the node is no interface node (a node of the nodes file that the "
                           "matrices name)");
    }
  return FB_OK;
}

/* Every line of the attach file names a set the vehicle has. */
static int attach_all_used(const attach_map *a, fb_err *err)
{
  for (size_t k = 0; k < a->n; ++k)
    if (!a->line[k].used)
      return attach_fail(a, a->line[k].line, err,
                         "no corner (SUSP_<CORNER>), mount or hull mass (MASS_<NAME>) of the "
                         "scenario has this set");
  return FB_OK;
}

/* The mesh node nearest to (x, y) in plan. */
static size_t reduced_nearest(const fb_mesh *m, double x, double y)
{
  size_t best = 0;
  double dbest = INFINITY;
  for (size_t i = 0; i < fb_mesh_nnodes(m); ++i) {
    const double *p = fb_mesh_node_xyz(m, i);
    const double dist = hypot(p[0] - x, p[1] - y);
    if (dist < dbest) {
      dbest = dist;
      best = i;
    }
  }
  return best;
}

/* Where a set's points are in the description, for an error about one:
 * part kind at field, point i's index i when per_point, else 0 (kind 0:
 * System 2 checks the set's one node against its point itself,
 * fe_hull.c). */
typedef struct set_part {
  int kind;
  int per_point;
  const char *field;
} set_part;

/* A node set of the nodes nearest to the n points (x[i], y[i]), named
 * prefix + name in capitals; a one-node set the attach file names takes
 * its node. Each point of a set of several is checked here, within 1 mm
 * as System 2 checks a deck's: two points that took the same node would
 * make one member of the set. */
static int reduced_set(fb_mesh *m, attach_map *a, const char *prefix, const char *name,
                       size_t n, const double *x, const double *y, set_part part, fb_err *err)
{
  char *set = fb_strdup_printf("%s%s", prefix, name);
  size_t *nodes = malloc((n ? n : 1) * sizeof *nodes);
  int rc = set && nodes ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (char *c = set; c && *c; ++c)
    *c = (char)toupper((unsigned char)*c);
  long given = -1;
  if (!rc && n == 1)
    rc = attach_node(a, m, set, &given, err);
  for (size_t i = 0; !rc && i < n; ++i) {
    nodes[i] = given >= 0 ? (size_t)given : reduced_nearest(m, x[i], y[i]);
    const double *p = fb_mesh_node_xyz(m, nodes[i]);
    if (part.kind && hypot(p[0] - x[i], p[1] - y[i]) > 1e-3)
      rc = fb_err_set(err, FB_EMODEL,
                      "the scenario puts a point of %s at (%.6g, %.6g) m, the nearest "
                      "interface node, %ld, at (%.6g, %.6g) m (they must agree within 1 mm)",
                      set, x[i], y[i], fb_mesh_node_id(m, nodes[i]), p[0], p[1]),
      fb_err_set_part(err, part.kind, part.per_point ? i : 0, FB_ERR_NO_ELEMENT, part.field);
  }
  if (!rc)
    rc = fb_mesh_add_nset(m, set, n, nodes, err);
  free(set);
  free(nodes);
  return rc;
}

/* The sets System 2 meets the vehicle through (fe_hull.c), and ALL. */
static int reduced_sets(const fb_scenario *s, fb_mesh *m, fb_err *err)
{
  const set_part one = {0, 0, ""};
  attach_map a;
  int rc = attach_read(reduced_of(s)->attach, &a, err);
  for (size_t c = 0; !rc && c < s->ncorners; ++c)
    rc = reduced_set(m, &a, "SUSP_", s->corner[c].name, 1, &s->corner[c].x, &s->corner[c].y,
                     one, err);
  for (size_t b = 0; !rc && b < s->nmounts; ++b)
    rc = reduced_set(m, &a, "", s->mount[b].name, 1, &s->mount[b].x, &s->mount[b].y, one, err);
  for (size_t k = 0; !rc && k < s->npoint_masses; ++k)
    rc = reduced_set(m, &a, "MASS_", s->point_mass[k].name, 1, &s->point_mass[k].x,
                     &s->point_mass[k].y, one, err);
  if (!rc)
    rc = attach_all_used(&a, err);
  free(a.line);
  if (!rc)
    rc = reduced_set(m, &a, "", "LOAD", s->nload, s->load_x, s->load_y,
                     (set_part){FB_PART_LOAD_POINT, 1, ""}, err);
  const double ex[2] = {s->edge_front_x, s->edge_front_x},
               rx[2] = {s->edge_rear_x, s->edge_rear_x},
               ey[2] = {s->edge_left_y, s->edge_right_y};
  if (!rc)
    rc = reduced_set(
        m, &a, "", "FRONT_EDGE", 2, ex, ey,
        (set_part){FB_PART_VEHICLE, 0, fb_part_member_(FB_PART_VEHICLE, edge_front_x)}, err);
  if (!rc)
    rc = reduced_set(
        m, &a, "", "REAR_EDGE", 2, rx, ey,
        (set_part){FB_PART_VEHICLE, 0, fb_part_member_(FB_PART_VEHICLE, edge_rear_x)}, err);
  size_t *all = malloc((fb_mesh_nnodes(m) ? fb_mesh_nnodes(m) : 1) * sizeof *all);
  for (size_t i = 0; all && i < fb_mesh_nnodes(m); ++i)
    all[i] = i;
  if (!rc)
    rc = all ? fb_mesh_add_nset(m, "ALL", fb_mesh_nnodes(m), all, err)
             : fb_err_set(err, FB_ENOMEM, "out of memory");
  free(all);
  return rc;
}

/* Each file given opens: one that does not is the error of its own key
 * (the readers' later errors name their file and line, at k). */
static int reduced_files_open(const reduced_params *p, fb_err *err)
{
  const char *const path[4] = {p->k, p->m, p->nodes, p->attach}, *const field[4] = {"k", "m",
                                                                                    "nodes",
                                                                                    "attach"};
  for (int i = 0; i < 4; ++i) {
    FILE *fp = path[i] ? fb_open_input(path[i], "rb", err) : NULL;
    if (path[i] && !fp)
      return reduced_fail(err, field[i]);
    if (fp)
      fclose(fp);
  }
  return FB_OK;
}

static int reduced_read_files(const reduced_params *p, fb_reduced **r, fb_err *err)
{
  const int rc = reduced_files_open(p, err);
  if (rc)
    return rc;
  return p->format == REDUCED_DMIG
             ? fb_reduced_read_dmig(p->k, DMIG_K, DMIG_M, p->nodes, r, err)
             : fb_reduced_read_mtx(p->k, p->m, p->nodes, r, err);
}

static int reduced_read(const fb_scenario *s, fb_mesh **out, fb_err *err)
{
  *out = NULL;
  const reduced_params *p = reduced_of(s);
  fb_reduced *r = NULL;
  fb_mesh *m = NULL;
  size_t *index = NULL;
  int rc = reduced_check(s, err);
  if (!rc)
    rc = reduced_read_files(p, &r, err);
  /* Nothing is computed from matrices that fail their checks. */
  if (!rc)
    rc = fb_reduced_check(r, err);
  if (!rc && !fb_reduced_mass(r))
    rc = fb_err_set(err, FB_EMODEL, "%s: a hull needs its mass (M)", p->k);
  if (!rc)
    rc = reduced_six_each(r, err);
  if (!rc)
    rc = fb_mesh_new(&m, err);
  if (!rc && !(index = calloc(fb_reduced_nnodes(r), sizeof *index)))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = reduced_nodes(r, m, index, err);
  if (!rc)
    rc = reduced_superelement(r, index, m, err);
  if (!rc)
    rc = reduced_sets(s, m, err);
  if (rc && err && !err->part.kind)
    reduced_fail(err, "k");
  free(index);
  fb_reduced_free(&r);
  if (rc)
    fb_mesh_free(&m);
  *out = m;
  return rc;
}

static void reduced_describe(const fb_scenario *s, char *buf, size_t n)
{
  const reduced_params *p = reduced_of(s);
  if (p->format == REDUCED_DMIG)
    snprintf(buf, n, "the superelement of the DMIG file %s (interface %s)", p->k ? p->k : "",
             p->nodes ? p->nodes : "");
  else
    snprintf(buf, n, "the superelement of %s and %s (interface %s)", p->k ? p->k : "",
             p->m ? p->m : "", p->nodes ? p->nodes : "");
}

static const fb_hull_source_ops reduced_ops = {
    .check = reduced_check, .read = reduced_read, .describe = reduced_describe};

const fb_hull_source fb_hull_source_reduced = {
    .name = "reduced",
    .doc = "a structure reduced in another finite-element tool (a free-free superelement: "
           "stiffness and mass over its interface nodes' six DOFs, docs/reduced-hulls.md)",
    .param = reduced_param,
    .nparams = sizeof reduced_param / sizeof reduced_param[0],
    .params_size = sizeof(reduced_params),
    .ops = &reduced_ops};
