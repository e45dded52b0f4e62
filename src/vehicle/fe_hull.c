/* SPDX-License-Identifier: BSD-3-Clause */
/* System 2's finite-element hull: node-set resolution, free-free modes,
 * and the modes of the whole undamped vehicle (flexbond/vehicle.h). */
#include <assert.h>
#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "flexbond/hull_source.h"
#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

void fb_fe_hull_free(fb_fe_hull **h)
{
  if (!h || !*h)
    return;
  fb_mesh_free(&(*h)->mesh);
  free((*h)->attach_node);
  free((*h)->load_node);
  for (size_t a = 0; (*h)->attach_coupling && a < (*h)->nattach; ++a)
    fb_hull_coupling_free(&(*h)->attach_coupling[a]);
  free((*h)->attach_coupling);
  for (size_t k = 0; (*h)->load_coupling && k < (*h)->nload; ++k)
    fb_hull_coupling_free(&(*h)->load_coupling[k]);
  free((*h)->load_coupling);
  for (size_t b = 0; (*h)->bushing_rows && b < 6 * (*h)->nbushings; ++b)
    fb_hull_coupling_free(&(*h)->bushing_rows[b]);
  free((*h)->bushing_rows);
  free((*h)->bushing_index);
  free((*h)->bushing_single_node);
  free((*h)->point_mass_node);
  free((*h)->point_mass);
  free(*h);
  *h = NULL;
}

/* The nodes of set `name`, which must hold exactly `count` nodes. */
static int nset_nodes(const fb_mesh *m, const char *name, size_t count, const size_t **nodes,
                      fb_err *err)
{
  size_t n = 0;
  if (!fb_mesh_nset(m, name, nodes, &n))
    return fb_err_set(err, FB_EMODEL,
                      "the mesh has no node set %s (the vehicle needs LOAD, one set per "
                      "mounted body named as it in capitals, SUSP_<CORNER> per corner, "
                      "MASS_<NAME> per hull mass, FRONT_EDGE and REAR_EDGE: "
                      "docs/hull-mesh.md)",
                      name);
  if (n != count)
    return fb_err_set(err, FB_EMODEL, "the mesh's node set %s has %zu nodes, expected %zu",
                      name, n, count);
  return FB_OK;
}

/* Where a point of the description is: its part (kind and index), and
 * the members of its x and y (both "" for a load point, one item). */
typedef struct point_part {
  int kind;
  size_t index;
  const char *x, *y;
} point_part;

/* Checks that node sits at (x, y) in the hull's axes (within 1 mm). The
 * error is about the point's coordinate that is off (fb_err.part). */
static int check_at(const fb_mesh *m, size_t node, const char *what, const point_part *pp,
                    double x, double y, fb_err *err)
{
  const double *p = fb_mesh_node_xyz(m, node);
  const int x_off = fabs(p[0] - x) > 1e-3;
  if (!x_off && fabs(p[1] - y) <= 1e-3)
    return FB_OK;
  fb_err_set(err, FB_EMODEL,
             "the scenario puts %s at (%.6g, %.6g) m, the mesh's node %ld at (%.6g, %.6g) m "
             "(they must agree within 1 mm)",
             what, x, y, fb_mesh_node_id(m, node), p[0], p[1]);
  return fb_err_set_part(err, pp->kind, pp->index, FB_ERR_NO_ELEMENT, x_off ? pp->x : pp->y),
         FB_EMODEL;
}

/* Mesh node set of attachment a ("SUSP_LF", "DRIVER"; a new string), its
 * part and point. */
static int attach_names(const fb_scenario *s, size_t a, char **set, point_part *pp, double *x,
                        double *y)
{
  if (a < s->ncorners) {
    const fb_corner_params *c = &s->corner[a];
    *set = fb_strdup_printf("SUSP_%s", c->name);
    *pp = (point_part){FB_PART_CORNER, a, "x", "y"};
    *x = c->x;
    *y = c->y;
  } else {
    const fb_mount *mt = &s->mount[a - s->ncorners];
    *set = fb_strdup(mt->name);
    for (char *p = *set; p && *p; ++p)
      *p = (char)toupper((unsigned char)*p);
    *pp = (point_part){FB_PART_MOUNT, a - s->ncorners, "x", "y"};
    *x = mt->x;
    *y = mt->y;
  }
  return *set ? FB_OK : FB_ENOMEM;
}

/* Attachment a's node, and its coupling: the node of its one-node set
 * within 1 mm of the point; with hull.mesh.coupling, any such node as it
 * is, else the scenario's coupling (fb_hull_coupling_build), whose errors
 * are about the point. */
static int attach_one(const fb_scenario *s, fb_fe_hull *h, size_t a, const char *set,
                      const point_part *pp, double x, double y, fb_err *err)
{
  const size_t *nodes = NULL;
  size_t n = 0;
  if (s->coupling != FB_COUPLING_NONE) {
    const double *p = fb_mesh_nset(h->mesh, set, &nodes, &n) && n == 1
                          ? fb_mesh_node_xyz(h->mesh, nodes[0])
                          : NULL;
    const int on_node = p && fabs(p[0] - x) <= 1e-3 && fabs(p[1] - y) <= 1e-3;
    if (!on_node) {
      const int rc = fb_hull_coupling_build(s, h->mesh, set, x, y, &h->attach_coupling[a],
                                            &h->attach_node[a], err);
      return rc ? fb_err_set_part(err, pp->kind, pp->index, FB_ERR_NO_ELEMENT, ""), rc : FB_OK;
    }
  }
  int rc = nset_nodes(h->mesh, set, 1, &nodes, err);
  if (!rc)
    rc = check_at(h->mesh, nodes[0], set, pp, x, y, err);
  if (!rc)
    h->attach_node[a] = nodes[0];
  return rc ? rc : fb_hull_coupling_node(nodes[0], &h->attach_coupling[a], err);
}

/* A bushing on one node: a rigid lever from the node to the point, its
 * motion the node's six transported (v + omega x r, the node's rotations
 * included), rows[0 .. 6) new. Its force bends the plate at one node: a
 * local mode the loader warns of (fb_fe_hull_point_stiffness). */
static int lever6(const fb_mesh *m, size_t node, const double *x0, fb_hull_coupling *rows,
                  fb_err *err)
{
  const double *p = fb_mesh_node_xyz(m, node);
  const double r[3] = {x0[0] - p[0], x0[1] - p[1], x0[2] - p[2]};
  double t[36];
  vehicle_rigid_transport(r, t);
  memset(rows, 0, 6 * sizeof *rows);
  for (size_t l = 0; l < 6; ++l) {
    rows[l].dof = malloc(6 * sizeof *rows[l].dof);
    rows[l].w = malloc(6 * sizeof *rows[l].w);
    if (!rows[l].dof || !rows[l].w)
      return fb_err_set(err, FB_ENOMEM, "out of memory for a coupling");
    rows[l].n = 6;
    for (size_t c = 0; c < 6; ++c) {
      rows[l].dof[c] = 6 * node + c;
      rows[l].w[c] = t[6 * l + c];
    }
  }
  return FB_OK;
}

int fb_fe_hull_point_stiffness(const fb_fe_hull *h, size_t ncorners, size_t node, double *k,
                               fb_err *err)
{
  *k = NAN;
  fb_mat *K = NULL, *Kc = NULL;
  fb_chol *chol = NULL;
  const size_t n = 6 * fb_mesh_nnodes(h->mesh);
  size_t nfixed = 0;
  size_t *fixed = malloc((6 * ncorners + 1) * sizeof *fixed);
  size_t *keep = malloc(n * sizeof *keep);
  double *b = calloc(n, sizeof *b);
  int rc = fixed && keep && b ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  /* Every DOF of each corner's attachment node (the corners come first
   * among h's attachment points), each node once. */
  for (size_t c = 0; !rc && c < ncorners && c < h->nattach; ++c) {
    int seen = 0;
    for (size_t f = 0; f < nfixed; ++f)
      seen |= fixed[f] == 6 * h->attach_node[c];
    for (size_t d = 0; !seen && d < 6; ++d)
      fixed[nfixed++] = 6 * h->attach_node[c] + d;
  }
  if (!rc)
    rc = fb_fem_assemble(h->mesh, &h->props, h->mass_kind, &K, NULL, err);
  if (!rc)
    rc = fb_fem_free_dofs(n, fixed, nfixed, keep, err);
  if (!rc)
    rc = fb_fem_submatrix(K, keep, n - nfixed, &Kc, err);
  if (!rc)
    rc = fb_chol_new(Kc, 0, &chol, err);
  size_t at = n;
  for (size_t i = 0; !rc && i < n - nfixed; ++i)
    if (keep[i] == 6 * node + 2)
      at = i;
  if (!rc && at == n)
    rc = fb_err_set(err, FB_EINVAL, "node %zu is a suspension point's", node);
  if (!rc) {
    b[at] = 1.0;
    rc = fb_chol_solve(chol, b, 1, err);
  }
  if (!rc)
    *k = 1.0 / b[at];
  fb_chol_free(&chol);
  fb_mat_free(&Kc);
  fb_mat_free(&K);
  free(fixed);
  free(keep);
  free(b);
  return rc;
}

/* Each bushing of a body on the hull: its six rows over the nodes of its
 * node set, or of the coupling surface within its radius (the
 * scenario's coupling radius when it gives none) in plan; errors about
 * the bushing (FB_PART_BUSHING). */
static int resolve_bushings(const fb_scenario *s, fb_fe_hull *h, fb_err *err)
{
  const size_t nk = fb_scenario_nbushings(s);
  size_t b = 0, j = 0;
  h->bushing_index = malloc((nk ? nk : 1) * sizeof *h->bushing_index);
  h->bushing_rows = calloc(6 * (nk ? nk : 1), sizeof *h->bushing_rows);
  h->bushing_single_node = malloc((nk ? nk : 1) * sizeof *h->bushing_single_node);
  int rc = h->bushing_index && h->bushing_rows && h->bushing_single_node
               ? FB_OK
               : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t k = 0; !rc && fb_scenario_bushing_at(s, k, &b, &j); ++k) {
    if (s->body[b].parent)
      continue;
    const fb_bushing *u = &s->body[b].bushing[j];
    const double x0[3] = {u->x, u->y, u->z};
    size_t *nodes = NULL, n = 0;
    char what[160];
    snprintf(what, sizeof what, "body %s's bushing %zu", s->body[b].name, j);
    rc = vehicle_bushing_nodes(s, h->mesh, u, &nodes, &n, err);
    if (!rc)
      h->bushing_single_node[h->nbushings] = n == 1 ? nodes[0] : (size_t)-1;
    if (!rc && n == 1)
      rc = lever6(h->mesh, nodes[0], x0, &h->bushing_rows[6 * h->nbushings], err);
    else if (!rc)
      rc = fb_hull_coupling6_build(h->mesh, nodes, n, x0, what,
                                   &h->bushing_rows[6 * h->nbushings], err);
    free(nodes);
    if (rc)
      return fb_err_set_part(err, FB_PART_BUSHING, k, FB_ERR_NO_ELEMENT,
                             u->node_set ? "node_set" : "radius"),
             rc;
    h->bushing_index[h->nbushings++] = k;
  }
  return rc;
}

static int resolve_attach(const fb_scenario *s, fb_fe_hull *h, fb_err *err)
{
  h->nattach = fb_scenario_nattach(s);
  h->attach_node = malloc((h->nattach ? h->nattach : 1) * sizeof *h->attach_node);
  h->attach_coupling = calloc(h->nattach ? h->nattach : 1, sizeof *h->attach_coupling);
  int rc = h->attach_node && h->attach_coupling ? FB_OK
                                                : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t a = 0; !rc && a < h->nattach; ++a) {
    char *set = NULL;
    point_part pp;
    double x = 0.0, y = 0.0;
    rc = attach_names(s, a, &set, &pp, &x, &y);
    if (rc)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory");
    if (!rc)
      rc = attach_one(s, h, a, set, &pp, x, y, err);
    free(set);
  }
  return rc;
}

/* The position in nodes[0 .. n) of a node not yet used within 1 mm of
 * (x, y) in plan: guess first (a set in the scenario's order), then any;
 * guess itself when there is none (check_at then reports it). */
static size_t match_node(const fb_mesh *m, const size_t *nodes, size_t n,
                         const unsigned char *used, size_t guess, double x, double y)
{
  for (size_t i = 0; i <= n; ++i) {
    const size_t j = i == 0 ? guess : i - 1;
    const double *p = fb_mesh_node_xyz(m, nodes[j]);
    if (!used[j] && fabs(p[0] - x) <= 1e-3 && fabs(p[1] - y) <= 1e-3)
      return j;
  }
  return guess;
}

/* LOAD's nodes in the scenario's load-point order (the set may list them
 * in any), FRONT_EDGE's and REAR_EDGE's left end (larger y) first. */
static int resolve_load_and_edges(const fb_scenario *s, fb_fe_hull *h, fb_err *err)
{
  const size_t *nodes = NULL;
  unsigned char *used = calloc(s->nload ? s->nload : 1, 1);
  int rc = used ? nset_nodes(h->mesh, "LOAD", s->nload, &nodes, err)
                : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc && !(h->load_node = malloc(s->nload * sizeof *h->load_node)))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc && !(h->load_coupling = calloc(s->nload, sizeof *h->load_coupling)))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t k = 0; !rc && k < s->nload; ++k) {
    char what[32];
    snprintf(what, sizeof what, "LOAD node %zu", k + 1);
    const point_part pp = {FB_PART_LOAD_POINT, k, "", ""};
    const size_t j = match_node(h->mesh, nodes, s->nload, used, k, s->load_x[k], s->load_y[k]);
    used[j] = 1;
    rc = check_at(h->mesh, nodes[j], what, &pp, s->load_x[k], s->load_y[k], err);
    h->load_node[k] = nodes[j];
    if (!rc)
      rc = fb_hull_coupling_node(nodes[j], &h->load_coupling[k], err);
  }
  free(used);
  h->nload = s->nload;
  const char *const edges[2] = {"FRONT_EDGE", "REAR_EDGE"};
  const char *const edge_x[2] = {fb_part_member_(FB_PART_VEHICLE, edge_front_x),
                                 fb_part_member_(FB_PART_VEHICLE, edge_rear_x)};
  for (int k = 0; !rc && k < 2; ++k) {
    rc = nset_nodes(h->mesh, edges[k], 2, &nodes, err);
    const int swap =
        !rc && fb_mesh_node_xyz(h->mesh, nodes[0])[1] < fb_mesh_node_xyz(h->mesh, nodes[1])[1];
    const size_t left = rc ? 0 : nodes[swap], right = rc ? 0 : nodes[!swap];
    const double x = k == 0 ? s->edge_front_x : s->edge_rear_x;
    char what[32];
    snprintf(what, sizeof what, "%s's left end", edges[k]);
    point_part pp = {FB_PART_VEHICLE, 0, edge_x[k],
                     fb_part_member_(FB_PART_VEHICLE, edge_left_y)};
    if (!rc)
      rc = check_at(h->mesh, left, what, &pp, x, s->edge_left_y, err);
    snprintf(what, sizeof what, "%s's right end", edges[k]);
    pp.y = fb_part_member_(FB_PART_VEHICLE, edge_right_y);
    if (!rc)
      rc = check_at(h->mesh, right, what, &pp, x, s->edge_right_y, err);
    h->edge_node[2 * k] = left;
    h->edge_node[2 * k + 1] = right;
  }
  return rc;
}

/* The node of each declared hull mass, MASS_<NAME>: one node, at the
 * mass's (x, y). A missing or wrong set is the mass's error. */
static int resolve_point_masses(const fb_scenario *s, fb_fe_hull *h, fb_err *err)
{
  const size_t n = s->npoint_masses;
  h->point_mass_node = malloc((n ? n : 1) * sizeof *h->point_mass_node);
  h->point_mass = malloc((n ? n : 1) * sizeof *h->point_mass);
  int rc =
      h->point_mass_node && h->point_mass ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t k = 0; !rc && k < n; ++k) {
    const fb_hull_point_mass *m = &s->point_mass[k];
    char *set = fb_strdup_printf("MASS_%s", m->name);
    const point_part pp = {FB_PART_HULL_MASS, k, "x", "y"};
    const size_t *nodes = NULL;
    for (char *c = set; c && *c; ++c)
      *c = (char)toupper((unsigned char)*c);
    if (!set)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory");
    if (!rc && (rc = nset_nodes(h->mesh, set, 1, &nodes, err)))
      fb_err_set_part(err, FB_PART_HULL_MASS, k, FB_ERR_NO_ELEMENT, "");
    if (!rc)
      rc = check_at(h->mesh, nodes[0], set, &pp, m->x, m->y, err);
    if (!rc) {
      h->point_mass_node[k] = nodes[0];
      h->point_mass[k] = m->mass;
    }
    free(set);
  }
  h->npoint_masses = rc ? 0 : n;
  return rc;
}

/* The element set names of the mesh, "A, B, C" into buf (cut at size). */
static void elset_names(const fb_mesh *m, char *buf, size_t size)
{
  size_t used = 0;
  buf[0] = '\0';
  for (size_t i = 0; i < fb_mesh_nelsets(m) && used + 1 < size; ++i) {
    const int n =
        snprintf(buf + used, size - used, "%s%s", i ? ", " : "", fb_mesh_elset_name(m, i));
    used += n > 0 ? (size_t)n : 0;
  }
}

/* hull.sections onto the mesh, in the file's order (a later one takes
 * the elements it shares with an earlier one, and with a deck's own
 * sections). A set the mesh lacks, or one named twice, is the item's
 * error. */
static int apply_sections(const fb_scenario *s, fb_mesh *m, fb_err *err)
{
  for (size_t i = 0; i < s->nsections; ++i) {
    const fb_hull_section *sec = &s->section[i];
    for (size_t j = 0; j < i; ++j)
      if (strcasecmp(s->section[j].set, sec->set) == 0) {
        fb_err_set(err, FB_EINVAL, "element set '%s' has a section already (section %zu)",
                   sec->set, j);
        return fb_err_set_part(err, FB_PART_AT(FB_PART_SECTION, i, set)), FB_EINVAL;
      }
    if (!fb_mesh_elset(m, sec->set, NULL, NULL)) {
      char names[512];
      elset_names(m, names, sizeof names);
      fb_err_set(err, FB_EINVAL, "the hull mesh has no element set '%s' (its sets: %s)",
                 sec->set, names[0] ? names : "none");
      return fb_err_set_part(err, FB_PART_AT(FB_PART_SECTION, i, set)), FB_EINVAL;
    }
    const fb_shell_props p = {sec->young,     sec->poisson, sec->density,
                              sec->thickness, 0.0,          sec->nonstructural_mass};
    const int rc = fb_mesh_set_section(m, sec->set, &p, err);
    if (rc)
      return fb_err_set_part(err, FB_PART_SECTION, i, FB_ERR_NO_ELEMENT, ""), rc;
  }
  return FB_OK;
}

int fb_fe_hull_new(const fb_scenario *s, fb_mesh **mesh, const fb_shell_props *props,
                   fb_mass_kind mass_kind, fb_fe_hull **out, fb_err *err)
{
  *out = NULL;
  fb_fe_hull *h = calloc(1, sizeof *h);
  if (!h) {
    fb_mesh_free(mesh);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  h->mesh = *mesh;
  *mesh = NULL;
  h->props = *props;
  h->mass_kind = mass_kind;
  int rc = fb_mesh_check(h->mesh, err);
  if (!rc)
    rc = apply_sections(s, h->mesh, err);
  if (!rc)
    rc = resolve_attach(s, h, err);
  if (!rc)
    rc = resolve_load_and_edges(s, h, err);
  if (!rc)
    rc = resolve_point_masses(s, h, err);
  if (!rc)
    rc = resolve_bushings(s, h, err);
  if (rc) {
    fb_fe_hull_free(&h);
    return rc;
  }
  *out = h;
  return FB_OK;
}

int vehicle_source_mesh_current(const fb_scenario *s)
{
  if (!s->hull_source_mesh)
    return 0;
  const fb_hull_source *src = fb_scenario_hull_source(s);
  return !src->ops->key || s->hull_source_key == src->ops->key(s);
}

/* System 2's hull from a mesh (taken over), whatever made it: the
 * generator, a deck or a gmsh file meet here, so the size bound they
 * share is checked here, after a file is read (the generator checks it
 * before it builds the mesh, hull_mesh.c). */
static int fe_hull_of_mesh(const fb_scenario *s, fb_mesh **mesh, const fb_shell_props *props,
                           fb_fe_hull **out, fb_err *err)
{
  const size_t n = fb_mesh_nelements(*mesh);
  const int rc = vehicle_hull_check_size((double)n, "", err);
  if (rc) {
    fb_mesh_free(mesh);
    return fb_err_prefix(err, "the mesh has %zu elements, ", n), rc;
  }
  return fb_fe_hull_new(s, mesh, props, s->hull_mass_matrix, out, err);
}

int fb_vehicle_fe_hull(const fb_scenario *s, fb_fe_hull **out, fb_err *err)
{
  *out = NULL;
  if (!s->has_fe_hull)
    return fb_err_set(err, FB_EINVAL,
                      "System 2 needs the hull's finite-element model: a mesh and its "
                      "elements (docs/scenario-format.md)"),
           fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, has_fe_hull)), FB_EINVAL;
  /* The scenario's material and thickness apply to the elements that
   * neither a deck's *SHELL SECTION nor hull.sections give properties. */
  const fb_shell_props props = {s->young,     s->poisson,           s->density,
                                s->thickness, s->hull_drill_factor, 0.0};
  const fb_hull_source *src = fb_scenario_hull_source(s);
  fb_mesh *mesh = NULL;
  int rc = FB_OK;
  if (vehicle_source_mesh_current(s))
    rc = fb_mesh_clone(s->hull_source_mesh, &mesh, err);
  else if (src->ops->make)
    /* A description the loader did not complete, or changed since: the
     * source's errors about a value name its part (the caller locates
     * it); the generator's others start with "hull mesh:". */
    rc = src->ops->make(s, &mesh, err);
  else
    rc = fb_err_set(err, FB_EINVAL,
                    "the hull's mesh is not read (the scenario's hull_source_mesh; "
                    "fb_scenario_read_hull reads it)");
  /* The errors of the mesh a source gave are its own. */
  if (!rc)
    rc = fe_hull_of_mesh(s, &mesh, &props, out, err);
  if (rc && src->ops->blame)
    src->ops->blame(s, err);
  return rc;
}

int fb_fe_hull_frequencies(const fb_mat *K, const fb_mat *M, size_t nmodes,
                           const fb_eig_opts *o, double *freq_hz, size_t *nrigid,
                           fb_eig_info *info, fb_err *err)
{
  fb_eig_opts opts;
  if (o)
    opts = *o;
  else
    fb_eig_opts_default(&opts);
  const size_t n = fb_mat_nrows(K);
  if (nmodes > n)
    nmodes = n;
  opts.values_only = 1;
  fb_fem_modal *fm = NULL;
  int rc = fb_fem_modal_new(K, M, &opts, &fm, err);
  if (!rc)
    rc = fb_fem_modal_solve(fm, nmodes, 0.0, err);
  if (!rc) {
    memcpy(freq_hz, fb_fem_modal_freq_hz(fm), nmodes * sizeof *freq_hz);
    *nrigid = fb_fem_modal_nrigid(fm);
    if (info)
      *info = fb_fem_modal_info(fm);
  }
  fb_fem_modal_free(&fm);
  return rc;
}

int fb_fe_hull_free_modes(const fb_fe_hull *h, size_t nmodes, double *freq_hz, size_t *nrigid,
                          fb_err *err)
{
  fb_mat *K = NULL, *M = NULL;
  *nrigid = 0;
  int rc = fb_fem_assemble(h->mesh, &h->props, h->mass_kind, &K, NULL, err);
  if (!rc)
    rc = fb_fe_hull_mass_matrix(h, &M, err);
  if (!rc)
    rc = fb_fe_hull_frequencies(K, M, nmodes, NULL, freq_hz, nrigid, NULL, err);
  fb_mat_free(&K);
  fb_mat_free(&M);
  return rc;
}

int fb_fe_hull_beta(double zeta, size_t nrigid, double f1_hz, double *beta, fb_err *err)
{
  if (nrigid != 6 || !(f1_hz > 0))
    return fb_err_set(err, FB_ESOLVER,
                      "hull damping: expected six rigid-body modes then an elastic one (got "
                      "%zu rigid, next at %g Hz)",
                      nrigid, f1_hz);
  *beta = 2.0 * zeta / (6.28318530717958647692 * f1_hz);
  return FB_OK;
}

int fb_fe_hull_damping(const fb_fe_hull *h, double zeta, double *beta, fb_mat **B, fb_err *err)
{
  if (B)
    *B = NULL;
  double f[FB_HULL_BETA_MODES];
  size_t nrigid = 0;
  fb_mat *K = NULL, *M = NULL;
  int rc = fb_fem_assemble(h->mesh, &h->props, h->mass_kind, &K, NULL, err);
  if (!rc)
    rc = fb_fe_hull_mass_matrix(h, &M, err);
  if (!rc)
    rc = fb_fe_hull_frequencies(K, M, FB_HULL_BETA_MODES, NULL, f, &nrigid, NULL, err);
  if (!rc)
    rc = fb_fe_hull_beta(zeta, nrigid, f[FB_HULL_BETA_MODES - 1], beta, err);
  if (!rc && B)
    rc = fb_mat_axpby(*beta, K, 0.0, NULL, B, err);
  fb_mat_free(&K);
  fb_mat_free(&M);
  return rc;
}

void fb_mode_set_free(fb_mode_set **m)
{
  if (!m || !*m)
    return;
  free((*m)->freq_hz);
  free((*m)->shapes);
  free((*m)->description);
  free((*m)->part);
  free((*m)->mount_share);
  free(*m);
  *m = NULL;
}

/* Triplet list of the whole vehicle's K or M. */
typedef struct trips {
  size_t n;
  size_t cap_r, cap_c, cap_v; /* one per array: fb_grow updates its own */
  size_t *r, *c;
  double *v;
} trips;

static int trips_push(trips *t, size_t r, size_t c, double v)
{
  if (fb_grow((void **)&t->r, &t->cap_r, t->n, sizeof *t->r) ||
      fb_grow((void **)&t->c, &t->cap_c, t->n, sizeof *t->c) ||
      fb_grow((void **)&t->v, &t->cap_v, t->n, sizeof *t->v))
    return FB_ENOMEM;
  t->r[t->n] = r;
  t->c[t->n] = c;
  t->v[t->n++] = v;
  return FB_OK;
}

static void trips_free(trips *t)
{
  free(t->r);
  free(t->c);
  free(t->v);
}

typedef struct trips_visit {
  trips *t;
  int failed;
} trips_visit;

static void visit_push(void *ctx, size_t r, size_t c, double v)
{
  trips_visit *tv = ctx;
  tv->failed |= trips_push(tv->t, r, c, v) != FB_OK;
}

/* A spring k between DOFs a and b (b == SIZE_MAX: to the ground). */
static int add_spring(trips *t, size_t a, size_t b, double k)
{
  int rc = trips_push(t, a, a, k);
  if (!rc && b != (size_t)-1) {
    rc = trips_push(t, b, b, k);
    if (!rc)
      rc = trips_push(t, a, b, -k);
    if (!rc)
      rc = trips_push(t, b, a, -k);
  }
  return rc;
}

/* A spring k between DOF a and a coupling's point (sum w_j u_dof_j):
 * k (e_a - w)(e_a - w)'. */
static int add_coupled_spring(trips *t, size_t a, const fb_hull_coupling *c, double k)
{
  int rc = trips_push(t, a, a, k);
  for (size_t i = 0; !rc && i < c->n; ++i) {
    rc = trips_push(t, a, c->dof[i], -k * c->w[i]);
    if (!rc)
      rc = trips_push(t, c->dof[i], a, -k * c->w[i]);
    for (size_t j = 0; !rc && j < c->n; ++j)
      rc = trips_push(t, c->dof[i], c->dof[j], k * c->w[i] * c->w[j]);
  }
  return rc;
}

/* k r r' added to t, r a combination of two wheels' travels relative to
 * the hull: r = sa (e_a - c_a) + sb (e_b - c_b) over the DOFs (an
 * anti-roll bar's stiffness on its twist, sa = 1 and sb = -1; a bogie's
 * pivot spring, sa and sb its lever's weights). */
static int add_wheels_spring(trips *t, size_t a, const fb_hull_coupling *ca, double sa,
                             size_t b, const fb_hull_coupling *cb, double sb, double k)
{
  const size_t n = 2 + ca->n + cb->n;
  size_t *dof = malloc(n * sizeof *dof);
  double *w = malloc(n * sizeof *w);
  int rc = dof && w ? FB_OK : FB_ENOMEM;
  if (!rc) {
    dof[0] = a, w[0] = sa;
    dof[1] = b, w[1] = sb;
    for (size_t i = 0; i < ca->n; ++i)
      dof[2 + i] = ca->dof[i], w[2 + i] = -sa * ca->w[i];
    for (size_t i = 0; i < cb->n; ++i)
      dof[2 + ca->n + i] = cb->dof[i], w[2 + ca->n + i] = -sb * cb->w[i];
  }
  for (size_t i = 0; !rc && i < n; ++i)
    for (size_t j = 0; !rc && j < n; ++j)
      rc = trips_push(t, dof[i], dof[j], k * w[i] * w[j]);
  free(dof);
  free(w);
  return rc;
}

int vehicle_bogie_wheels(const fb_scenario *s, size_t i, long *f, long *r, double *m, double *w)
{
  const fb_bogie *b = &s->bogie[i];
  *f = fb_scenario_corner_find(s, b->front);
  *r = fb_scenario_corner_find(s, b->rear);
  if (*f < 0 || *r < 0) /* fb_scenario_check finds both */
    return 0;
  const double a = s->corner[*f].x - b->pivot_x, bb = b->pivot_x - s->corner[*r].x;
  const double len = a + bb;
  w[0] = bb / len;
  w[1] = a / len;
  /* Kinetic energy 1/2 (m_f zf'^2 + m_r zr'^2 + m_b v'^2 + J th'^2) with
   * v = w0 zf + w1 zr, th = (zr - zf) / len. */
  const double dz[2] = {-1.0 / len, 1.0 / len};
  for (int p = 0; p < 2; ++p)
    for (int q = 0; q < 2; ++q)
      m[2 * p + q] = b->beam_mass * w[p] * w[q] + b->beam_inertia * dz[p] * dz[q];
  m[0] += s->corner[*f].wheel_mass;
  m[3] += s->corner[*r].wheel_mass;
  return 1;
}

/* *M plus the hull's declared masses and mass `each` on each of the first
 * nload load nodes (0: none), every one on its node's three
 * translations; *M is replaced, and left as it is when there are none. */
int fb_fe_hull_add_masses(const fb_fe_hull *h, size_t nload, double each, fb_mat **M,
                          fb_err *err)
{
  if (!h->npoint_masses && !nload)
    return FB_OK;
  trips t = {0};
  trips_visit tv = {&t, 0};
  fb_mat_foreach(*M, visit_push, &tv);
  for (size_t k = 0; k < h->npoint_masses + nload; ++k) {
    const size_t node =
        k < h->npoint_masses ? h->point_mass_node[k] : h->load_node[k - h->npoint_masses];
    const double m = k < h->npoint_masses ? h->point_mass[k] : each;
    for (size_t d = 0; d < 3; ++d)
      tv.failed |= trips_push(&t, 6 * node + d, 6 * node + d, m) != FB_OK;
  }
  size_t n = fb_mat_nrows(*M);
  fb_mat_free(M);
  int rc = tv.failed ? fb_err_set(err, FB_ENOMEM, "out of memory")
                     : fb_mat_new_triplets(n, n, t.n, t.r, t.c, t.v, M, err);
  trips_free(&t);
  return rc;
}

int fb_fe_hull_mass_matrix(const fb_fe_hull *h, fb_mat **M, fb_err *err)
{
  int rc = fb_fem_assemble(h->mesh, &h->props, h->mass_kind, NULL, M, err);
  return rc ? rc : fb_fe_hull_add_masses(h, 0, 0.0, M, err);
}

size_t vehicle_nlumped(const fb_scenario *s)
{
  return s->nmounts + s->ncorners + 6 * s->nbodies;
}

/* rows[l] += sign times row l of the rigid transport of body i's point
 * p, over its DOFs from base + 6 i. */
static int body_rows(const fb_scenario *s, size_t i, const double *p, size_t base, double sign,
                     fb_hull_coupling *rows, fb_err *err)
{
  const fb_body *b = &s->body[i];
  const double r[3] = {p[0] - b->x, p[1] - b->y, p[2] - b->z};
  double t[36];
  vehicle_rigid_transport(r, t);
  for (int l = 0; l < 6; ++l) {
    fb_hull_coupling *row = &rows[l];
    size_t *dof = realloc(row->dof, (row->n + 6) * sizeof *dof);
    if (dof)
      row->dof = dof;
    double *w = dof ? realloc(row->w, (row->n + 6) * sizeof *w) : NULL;
    if (!w)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    row->w = w;
    for (size_t c = 0; c < 6; ++c) {
      row->dof[row->n] = base + 6 * i + c;
      row->w[row->n++] = sign * t[6 * l + c];
    }
  }
  return FB_OK;
}

int vehicle_bushing_relative_rows(const fb_scenario *s, const fb_fe_hull *fe, size_t k,
                                  size_t base, fb_hull_coupling *rows, fb_err *err)
{
  size_t b = 0, j = 0;
  memset(rows, 0, 6 * sizeof *rows);
  if (!fb_scenario_bushing_at(s, k, &b, &j))
    return fb_err_set(err, FB_EINVAL, "no bushing %zu", k);
  const fb_body *body = &s->body[b];
  const double p[3] = {body->bushing[j].x, body->bushing[j].y, body->bushing[j].z};
  int rc = FB_OK;
  if (body->parent) {
    rc = body_rows(s, (size_t)fb_scenario_body_find(s, body->parent), p, base, 1.0, rows, err);
  } else {
    size_t on = 0;
    while (on < fe->nbushings && fe->bushing_index[on] != k)
      ++on;
    if (on == fe->nbushings)
      rc = fb_err_set(err, FB_EINVAL, "bushing %zu is not coupled to the hull", k);
    for (int l = 0; !rc && l < 6; ++l) {
      const fb_hull_coupling *c = &fe->bushing_rows[6 * on + (size_t)l];
      rows[l].dof = malloc((c->n ? c->n : 1) * sizeof *rows[l].dof);
      rows[l].w = malloc((c->n ? c->n : 1) * sizeof *rows[l].w);
      if (!rows[l].dof || !rows[l].w)
        rc = fb_err_set(err, FB_ENOMEM, "out of memory");
      else {
        memcpy(rows[l].dof, c->dof, c->n * sizeof *c->dof);
        memcpy(rows[l].w, c->w, c->n * sizeof *c->w);
        rows[l].n = c->n;
      }
    }
  }
  if (!rc)
    rc = body_rows(s, b, p, base, -1.0, rows, err);
  if (rc)
    for (int l = 0; l < 6; ++l)
      fb_hull_coupling_free(&rows[l]);
  return rc;
}

/* The bodies' inertias and their bushings' springs, K G' K_b G over each
 * bushing's relative rows G, into the triplets; body i's DOFs from base
 * + 6 i. */
static int add_bodies(const fb_scenario *s, const fb_fe_hull *h, size_t base, trips *tk,
                      trips *tm, fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < s->nbodies; ++i) {
    double m[36];
    vehicle_body_inertia6(&s->body[i], m);
    for (size_t r = 0; !rc && r < 36; ++r)
      if (m[r] != 0.0)
        rc = trips_push(tm, base + 6 * i + r / 6, base + 6 * i + r % 6, m[r]);
  }
  if (rc)
    return fb_err_set(err, FB_ENOMEM, "out of memory assembling System 2");
  size_t b = 0, j = 0;
  for (size_t k = 0; !rc && fb_scenario_bushing_at(s, k, &b, &j); ++k) {
    fb_hull_coupling g[6];
    const double *kb = s->body[b].bushing[j].k;
    rc = vehicle_bushing_relative_rows(s, h, k, base, g, err);
    for (int l = 0; !rc && l < 6; ++l)
      for (int m = 0; !rc && m < 6; ++m)
        for (size_t p = 0; kb[6 * l + m] != 0.0 && !rc && p < g[l].n; ++p)
          for (size_t q = 0; !rc && q < g[m].n; ++q)
            if (trips_push(tk, g[l].dof[p], g[m].dof[q], kb[6 * l + m] * g[l].w[p] * g[m].w[q]))
              rc = fb_err_set(err, FB_ENOMEM, "out of memory assembling System 2");
    for (int l = 0; l < 6; ++l)
      fb_hull_coupling_free(&g[l]);
  }
  return rc;
}

int fb_vehicle_matrices(const fb_scenario *s, const fb_fe_hull *h, const fb_mat *kh,
                        const fb_mat *mh, fb_mat **K, fb_mat **M, fb_err *err)
{
  int rc = FB_OK;
  const size_t nm = s->nmounts;
  size_t nh = fb_mat_nrows(kh), n = nh + vehicle_nlumped(s);
  trips tk = {0}, tm = {0};
  trips_visit vk = {&tk, 0}, vm = {&tm, 0};
  fb_mat_foreach(kh, visit_push, &vk);
  fb_mat_foreach(mh, visit_push, &vm);
  rc = vk.failed || vm.failed ? FB_ENOMEM : FB_OK;
  for (size_t b = 0; !rc && b < nm; ++b) {
    rc = add_coupled_spring(&tk, nh + b, &h->attach_coupling[s->ncorners + b],
                            s->mount[b].stiffness);
    if (!rc)
      rc = trips_push(&tm, nh + b, nh + b, s->mount[b].mass);
  }
  for (size_t c = 0; !rc && c < s->ncorners; ++c) {
    const fb_corner_params *cp = &s->corner[c];
    const size_t wheel = nh + nm + c;
    const int own = vehicle_corner_bogie(s, c, NULL) < 0; /* else the bogie's, below */
    /* Spring travel = r x wheel travel: stiffness r^2 k at the wheel. */
    if (own)
      rc = add_coupled_spring(&tk, wheel, &h->attach_coupling[c],
                              cp->motion_ratio * cp->motion_ratio * cp->spring_k);
    if (!rc)
      rc = add_spring(&tk, wheel, (size_t)-1, cp->tire_k);
    if (!rc && own)
      rc = trips_push(&tm, wheel, wheel, cp->wheel_mass);
  }
  /* Each bogie over its wheels' DOFs: the beam's and wheels' inertia, the
   * pivot's spring on the lever's average of the wheels' travels. */
  for (size_t i = 0; !rc && i < s->nbogies; ++i) {
    long f = -1, r = -1;
    double m[4], w[2];
    if (!vehicle_bogie_wheels(s, i, &f, &r, m, w))
      continue;
    const size_t at[2] = {nh + nm + (size_t)f, nh + nm + (size_t)r};
    for (int p = 0; !rc && p < 4; ++p)
      rc = trips_push(&tm, at[p / 2], at[p % 2], m[p]);
    if (!rc)
      rc = add_wheels_spring(&tk, at[0], &h->attach_coupling[f], w[0], at[1],
                             &h->attach_coupling[r], w[1], s->bogie[i].spring_k);
  }
  /* Each anti-roll bar: half its rate in roll on the twist (fb_antiroll_bar). */
  for (size_t i = 0; !rc && i < s->nantiroll_bars; ++i) {
    const long l = fb_scenario_corner_find(s, s->antiroll_bar[i].left);
    const long r = fb_scenario_corner_find(s, s->antiroll_bar[i].right);
    if (l >= 0 && r >= 0) /* fb_scenario_check found both */
      rc = add_wheels_spring(&tk, nh + nm + (size_t)l, &h->attach_coupling[l], 1.0,
                             nh + nm + (size_t)r, &h->attach_coupling[r], -1.0,
                             0.5 * s->antiroll_bar[i].stiffness);
  }
  if (rc)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory assembling System 2");
  if (!rc)
    rc = add_bodies(s, h, nh + nm + s->ncorners, &tk, &tm, err);
  if (!rc)
    rc = fb_mat_new_triplets(n, n, tk.n, tk.r, tk.c, tk.v, K, err);
  if (!rc)
    rc = fb_mat_new_triplets(n, n, tm.n, tm.r, tm.c, tm.v, M, err);
  trips_free(&tk);
  trips_free(&tm);
  return rc;
}

typedef struct describe_ctx {
  const fb_mat *mh; /* the hull's mass */
  double *r, *mr;   /* rigid modes and M_h r (nh x 6 each) */
  double *mv;       /* M v, ndof */
  size_t nh, ndof;
  const fb_scenario *s; /* names and masses of the mounts and corners after the hull's DOFs */
} describe_ctx;

/* d->mv = M v for the whole vehicle's M (fb_vehicle_matrices'): the
 * hull's, then each body's and each wheel's mass. */
static void mass_times(const describe_ctx *d, const double *v)
{
  const fb_scenario *s = d->s;
  fb_mat_gemv(d->mh, 1.0, v, 0.0, d->mv);
  for (size_t b = 0; b < s->nmounts; ++b)
    d->mv[d->nh + b] = s->mount[b].mass * v[d->nh + b];
  const double *vw = v + d->nh + s->nmounts;
  double *mw = d->mv + d->nh + s->nmounts;
  for (size_t c = 0; c < s->ncorners; ++c)
    mw[c] = s->corner[c].wheel_mass * vw[c];
  for (size_t i = 0; i < s->nbogies; ++i) {
    long f = -1, r = -1;
    double m[4], w[2];
    if (!vehicle_bogie_wheels(s, i, &f, &r, m, w))
      continue;
    mw[f] = m[0] * vw[f] + m[1] * vw[r];
    mw[r] = m[2] * vw[f] + m[3] * vw[r];
  }
  const size_t base = d->nh + s->nmounts + s->ncorners;
  for (size_t b = 0; b < s->nbodies; ++b) {
    double m[36];
    vehicle_body_inertia6(&s->body[b], m);
    for (size_t r = 0; r < 6; ++r) {
      double sum = 0.0;
      for (size_t c = 0; c < 6; ++c)
        sum += m[6 * r + c] * v[base + 6 * b + c];
      d->mv[base + 6 * b + r] = sum;
    }
  }
}

/* The hull's kinetic energy split by M_h-orthogonal projection onto its
 * six rigid-body modes: energy[k] of rigid component k (diagonal part of
 * the projection) and energy[6] the elastic remainder. */
static void hull_energies(const describe_ctx *d, const double *v, double *energy)
{
  double g[36], b[6], c[6] = {0}, total = 0.0;
  for (size_t i = 0; i < d->nh; ++i)
    total += v[i] * d->mv[i];
  for (int j = 0; j < 6; ++j) {
    b[j] = 0.0;
    for (size_t i = 0; i < d->nh; ++i)
      b[j] += d->mr[j * d->nh + i] * v[i];
    for (int k = 0; k < 6; ++k) {
      double gjk = 0.0;
      for (size_t i = 0; i < d->nh; ++i)
        gjk += d->r[j * d->nh + i] * d->mr[k * d->nh + i];
      g[k * 6 + j] = gjk;
    }
  }
  /* c = G^-1 b by Cholesky (G: Gram matrix of the rigid modes, SPD). */
  double l[36] = {0};
  for (int j = 0; j < 6; ++j) {
    double sum = g[j * 6 + j];
    for (int k = 0; k < j; ++k)
      sum -= l[k * 6 + j] * l[k * 6 + j];
    l[j * 6 + j] = sqrt(sum > 0 ? sum : 1e-300);
    for (int i = j + 1; i < 6; ++i) {
      double t = g[j * 6 + i];
      for (int k = 0; k < j; ++k)
        t -= l[k * 6 + i] * l[k * 6 + j];
      l[j * 6 + i] = t / l[j * 6 + j];
    }
  }
  for (int i = 0; i < 6; ++i) {
    double t = b[i];
    for (int k = 0; k < i; ++k)
      t -= l[k * 6 + i] * c[k];
    c[i] = t / l[i * 6 + i];
  }
  for (int i = 5; i >= 0; --i) {
    double t = c[i];
    for (int k = i + 1; k < 6; ++k)
      t -= l[i * 6 + k] * c[k];
    c[i] = t / l[i * 6 + i];
  }
  double rigid = 0.0;
  for (int j = 0; j < 6; ++j) {
    rigid += b[j] * c[j];
    energy[j] = c[j] * c[j] * g[j * 6 + j];
  }
  energy[6] = fmax(total - rigid, 0.0);
}

/* Each bogie's share of mode v's kinetic energy, as its beam's bounce and
 * pitch (the motions System 1's beam is labelled by, fb_vehicle_bogie):
 * the wheels' travels zf, zr give the pivot's v = w0 zf + w1 zr and the
 * pitch th = (zr - zf) / len (vehicle_bogie_wheels); each motion's energy
 * is the diagonal part of the beam's (with its wheels) kinetic energy,
 * M00 v^2 and M11 th^2, as the hull's rigid motions are split
 * (hull_energies). Where one passes *best, it names the mode. */
static void bogie_motions(const describe_ctx *d, const double *v, char *name, size_t size,
                          fb_mode_part *part, double *best)
{
  const fb_scenario *s = d->s;
  const double *vw = v + d->nh + s->nmounts;
  for (size_t i = 0; i < s->nbogies; ++i) {
    long f = -1, r = -1;
    double m[4], w[2];
    if (!vehicle_bogie_wheels(s, i, &f, &r, m, w))
      continue;
    const fb_bogie *b = &s->bogie[i];
    const double a = s->corner[f].x - b->pivot_x, bb = b->pivot_x - s->corner[r].x;
    const double mf = s->corner[f].wheel_mass, mr = s->corner[r].wheel_mass;
    const double pivot = w[0] * vw[f] + w[1] * vw[r], pitch = (vw[r] - vw[f]) / (a + bb);
    const double e[2] = {(b->beam_mass + mf + mr) * pivot * pivot,
                         (b->beam_inertia + mf * a * a + mr * bb * bb) * pitch * pitch};
    static const char *const motion[2] = {"bogie bounce", "bogie pitch"};
    for (int k = 0; k < 2; ++k)
      if (e[k] > *best) {
        *best = e[k];
        snprintf(name, size, "%s %s", motion[k], b->name);
        *part = (fb_mode_part){FB_MODE_BOGIE, i};
      }
  }
}

/* Names the part of the vehicle holding the largest share of the mode's
 * kinetic energy: a rigid motion of the hull, its elastic deformation,
 * one lumped body, a bogie's beam or a rigid body (*part); each mounted
 * body's share into mount_share[0 .. nmounts + nbodies) (the mounts',
 * then the rigid bodies', fb_mode_set.mount_share). */
static void describe_mode(const describe_ctx *d, const double *v, char *out, size_t size,
                          fb_mode_part *part, double *mount_share)
{
  static const char *const hull_names[7] = {"hull surge",  "hull sway",  "hull bounce",
                                            "hull roll",   "hull pitch", "hull yaw",
                                            "hull elastic"};
  mass_times(d, v);
  double total = 0.0, energy[7], best = -1.0;
  for (size_t i = 0; i < d->ndof; ++i)
    total += v[i] * d->mv[i];
  hull_energies(d, v, energy);
  char name[80] = "?";
  for (int k = 0; k < 7; ++k)
    if (energy[k] > best) {
      best = energy[k];
      snprintf(name, sizeof name, "%s", hull_names[k]);
      *part = k < 6 ? (fb_mode_part){FB_MODE_HULL_RIGID, (size_t)k}
                    : (fb_mode_part){FB_MODE_HULL_ELASTIC, 0};
    }
  const size_t nbase = d->nh + d->s->nmounts + d->s->ncorners;
  for (size_t i = d->nh; i < nbase; ++i) {
    double e = v[i] * d->mv[i];
    const size_t b = i - d->nh;
    if (b < d->s->nmounts)
      mount_share[b] = total > 0 ? e / total : 0.0;
    /* A bogie's wheels move with its beam: the beam's motions below. */
    if (e <= best ||
        (b >= d->s->nmounts && vehicle_corner_bogie(d->s, b - d->s->nmounts, NULL) >= 0))
      continue;
    best = e;
    if (b < d->s->nmounts) {
      snprintf(name, sizeof name, "%s", d->s->mount[b].name);
      *part = (fb_mode_part){FB_MODE_MOUNT, b};
    } else {
      snprintf(name, sizeof name, "wheel hop %s", d->s->corner[b - d->s->nmounts].name);
      *part = (fb_mode_part){FB_MODE_WHEEL, b - d->s->nmounts};
    }
  }
  bogie_motions(d, v, name, sizeof name, part, &best);
  /* A rigid body's six motions together. */
  const size_t nm = d->s->nmounts;
  for (size_t b = 0; b < d->s->nbodies; ++b) {
    double e = 0.0;
    for (size_t c = 0; c < 6; ++c)
      e += v[nbase + 6 * b + c] * d->mv[nbase + 6 * b + c];
    mount_share[nm + b] = total > 0 ? e / total : 0.0;
    if (e > best) {
      best = e;
      snprintf(name, sizeof name, "%.31s", d->s->body[b].name);
      *part = (fb_mode_part){FB_MODE_MOUNT, nm + b};
    }
  }
  snprintf(out, size, "%s (%.0f%%)", name, total > 0 ? 100.0 * best / total : 0.0);
}

/* Scales v so that the largest displacement over the hull nodes (length
 * of the translation) and the mounted bodies is 1, and positive. */
static void normalise(const fb_fe_hull *h, size_t nh, size_t nmounts, double *v, size_t ndof)
{
  double big = 0.0, sign = 1.0;
  for (size_t i = 0; i < fb_mesh_nnodes(h->mesh); ++i) {
    const double *u = v + 6 * i;
    double len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (len > big) {
      big = len;
      int k = fabs(u[0]) >= fabs(u[1]) && fabs(u[0]) >= fabs(u[2]) ? 0
              : fabs(u[1]) >= fabs(u[2])                           ? 1
                                                                   : 2;
      sign = u[k] < 0 ? -1.0 : 1.0;
    }
  }
  for (size_t i = nh; i < nh + nmounts; ++i)
    if (fabs(v[i]) > big) {
      big = fabs(v[i]);
      sign = v[i] < 0 ? -1.0 : 1.0;
    }
  if (big > 0)
    for (size_t i = 0; i < ndof; ++i)
      v[i] *= sign / big;
}

int fb_mode_set_new(size_t nmodes, size_t ndof, fb_mode_set **out, fb_err *err)
{
  fb_mode_set *ms = calloc(1, sizeof *ms);
  if (ms) {
    ms->nmodes = nmodes;
    ms->ndof = ndof;
    ms->freq_hz = malloc(nmodes * sizeof *ms->freq_hz);
    ms->shapes = malloc(nmodes * ndof * sizeof *ms->shapes);
    ms->description = calloc(nmodes, sizeof *ms->description);
    ms->part = calloc(nmodes ? nmodes : 1, sizeof *ms->part);
  }
  if (!ms || !ms->freq_hz || !ms->shapes || !ms->description || !ms->part) {
    fb_mode_set_free(&ms);
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu modes", nmodes);
  }
  *out = ms;
  return FB_OK;
}

/* 1 if mode v is a free horizontal rigid-body motion of the hull (surge,
 * sway, yaw: no spring resists them), by its shape rather than its
 * frequency, whose round-off grows with the stiffness: 90 % or more of the
 * kinetic energy in those three rigid components. */
static int is_free_mode(const describe_ctx *d, const double *v)
{
  mass_times(d, v);
  double total = 0.0, energy[7];
  for (size_t i = 0; i < d->ndof; ++i)
    total += v[i] * d->mv[i];
  hull_energies(d, v, energy);
  /* Rigid bodies go along with the hull, their surge, sway and yaw
   * with its; but a body's own yaw on its bushings, with the hull all
   * but still, is no free motion: the hull's share must lead. */
  double bodies = 0.0;
  const size_t base = d->nh + d->s->nmounts + d->s->ncorners;
  for (size_t b = 0; b < d->s->nbodies; ++b)
    for (size_t c = 0; c < 6; c += c == 1 ? 4 : 1)
      bodies += v[base + 6 * b + c] * d->mv[base + 6 * b + c];
  const double hull = energy[0] + energy[1] + energy[5];
  return total > 0 && hull + bodies >= 0.9 * total && hull >= bodies;
}

/* Copies the modes that are not free rigid-body motions into ms (at most
 * ms->nmodes), counting the others in ms->nfree. */
static void keep_supported(const describe_ctx *d, const double *freq, const double *shapes,
                           size_t nwant, fb_mode_set *ms)
{
  size_t kept = 0;
  ms->nfree = 0;
  for (size_t k = 0; k < nwant && kept < ms->nmodes; ++k) {
    const double *v = shapes + k * d->ndof;
    if (is_free_mode(d, v)) {
      ms->nfree++;
      continue;
    }
    ms->freq_hz[kept] = freq[k];
    memcpy(ms->shapes + kept * d->ndof, v, d->ndof * sizeof *v);
    kept++;
  }
  ms->nmodes = kept;
}

int fb_vehicle_mode_set_fill(const fb_scenario *s, const fb_fe_hull *h, const fb_mat *mh,
                             const double *freq, const double *shapes, size_t nwant,
                             fb_mode_set *ms, fb_err *err)
{
  const size_t nh = fb_mat_nrows(mh);
  describe_ctx d = {mh, NULL, NULL, NULL, nh, nh + vehicle_nlumped(s), s};
  double mass, cg[3], inertia[9];
  int rc = fb_fem_mass_properties(h->mesh, mh, &mass, cg, inertia, err);
  if (!rc) {
    d.r = malloc(6 * d.nh * sizeof *d.r);
    d.mr = malloc(6 * d.nh * sizeof *d.mr);
    d.mv = malloc(d.ndof * sizeof *d.mv);
    ms->nmounts = s->nmounts + s->nbodies;
    ms->mount_share = calloc(ms->nmodes * ms->nmounts + 1, sizeof *ms->mount_share);
    if (!d.r || !d.mr || !d.mv || !ms->mount_share)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  if (!rc) {
    fb_mesh_rigid_modes(h->mesh, cg, d.r);
    for (int j = 0; j < 6; ++j)
      fb_mat_gemv(mh, 1.0, d.r + j * d.nh, 0.0, d.mr + j * d.nh);
    keep_supported(&d, freq, shapes, nwant, ms);
  }
  for (size_t k = 0; !rc && k < ms->nmodes; ++k) {
    double *v = ms->shapes + k * d.ndof;
    describe_mode(&d, v, ms->description[k], sizeof ms->description[k], &ms->part[k],
                  ms->mount_share + k * ms->nmounts);
    normalise(h, d.nh, s->nmounts, v, d.ndof);
  }
  free(d.r);
  free(d.mr);
  free(d.mv);
  return rc;
}

/* A node lies in an edge's transverse section when it is this close to
 * the plane x = the edge's x (the tolerance for attachment points). */
#define EDGE_LINE_TOL 1e-3

/* w += sign times edge's roll over the nodal DOFs: the slope dz/dy of the
 * line through its two end nodes (fit 0, the paper's definition), or the
 * rotation about the x axis of the edge's whole transverse section, every
 * node of the floor, walls and roof at that x, fitted by least squares as
 * a rigid rotation (fit 1). Under a point load at an end node the paper's
 * measure reads a displacement that grows without bound as the mesh is
 * refined (an in-plane point load on the side wall); the section's fit
 * averages it with the rest of the ring (tests/test_torsion.c). */
static int edge_roll(const fb_fe_hull *h, int edge, int fit, double sign, double *w)
{
  const size_t left = h->edge_node[2 * edge], right = h->edge_node[2 * edge + 1];
  const double *a = fb_mesh_node_xyz(h->mesh, left), *b = fb_mesh_node_xyz(h->mesh, right);
  if (!fit) {
    const double dy = a[1] - b[1];
    w[6 * left + 2] += sign / dy;
    w[6 * right + 2] -= sign / dy;
    return FB_OK;
  }
  /* The rigid rotation about the x axis through the section's centroid
   * that fits its nodes' (uy, uz) best: theta = sum (y' uz - z' uy) /
   * sum (y'^2 + z'^2), y' and z' from the centroid. */
  const double x0 = 0.5 * (a[0] + b[0]);
  const size_t nn = fb_mesh_nnodes(h->mesh);
  unsigned char *on = calloc(nn, 1);
  if (!on)
    return FB_ENOMEM;
  double yc = 0.0, zc = 0.0, srr = 0.0;
  size_t count = 0;
  for (size_t i = 0; i < nn; ++i) {
    const double *p = fb_mesh_node_xyz(h->mesh, i);
    on[i] = fabs(p[0] - x0) <= EDGE_LINE_TOL;
    if (on[i]) {
      yc += p[1];
      zc += p[2];
      ++count;
    }
  }
  yc /= (double)count;
  zc /= (double)count;
  for (size_t i = 0; i < nn; ++i)
    if (on[i]) {
      const double *p = fb_mesh_node_xyz(h->mesh, i);
      srr += (p[1] - yc) * (p[1] - yc) + (p[2] - zc) * (p[2] - zc);
    }
  for (size_t i = 0; i < nn; ++i)
    if (on[i]) {
      const double *p = fb_mesh_node_xyz(h->mesh, i);
      w[6 * i + 2] += sign * (p[1] - yc) / srr;
      w[6 * i + 1] -= sign * (p[2] - zc) / srr;
    }
  free(on);
  return FB_OK;
}

int fb_fe_hull_torsion_weights(const fb_fe_hull *h, int fit, double *w, fb_err *err)
{
  memset(w, 0, 6 * fb_mesh_nnodes(h->mesh) * sizeof *w);
  int rc = edge_roll(h, 0, fit, 1.0, w);
  if (!rc)
    rc = edge_roll(h, 1, fit, -1.0, w);
  return rc ? fb_err_set(err, FB_ENOMEM, "out of memory") : FB_OK;
}
