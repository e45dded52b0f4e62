/* SPDX-License-Identifier: BSD-3-Clause */
/* The hull-source gallery (flexbond/hull_source.h): registration, one
 * conformance harness that every source of a gallery passes (the built-in
 * generator, deck and reduced, and a toy source a program registers at run time:
 * a flat rectangular plate made with the fem module's mesh API), and the
 * toy source used from a scenario file with its errors at its keys. */
#include <ctype.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/fem.h"
#include "flexbond/hull_source.h"
#include "flexbond/vehicle.h"

#include "check.h"
#include "tmpdir.h"
#include "vehicle_util.h"

/* ---- The toy source: a flat plate at z = 0, x from x_rear to x_front,
 * y within +-width / 2, whose grid lines pass through every point of the
 * scenario (load points, suspension and mount points, hull masses), each
 * interval split in `splits`; the points' node sets are those nodes, the
 * edge lines its short edges. */

typedef struct plate_params {
  double x_rear, x_front, width; /* m */
  size_t splits;
} plate_params;

static const fb_param plate_param[] = {
    {.name = "x_rear",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(plate_params, x_rear),
     .unit = "m",
     .need = FB_PARAM_REQUIRED,
     .doc = "rear edge"},
    {.name = "x_front",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(plate_params, x_front),
     .unit = "m",
     .need = FB_PARAM_REQUIRED,
     .doc = "front edge, > x_rear"},
    {.name = "width",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(plate_params, width),
     .unit = "m",
     .range = FB_RANGE_LO | FB_RANGE_LO_OPEN,
     .need = FB_PARAM_REQUIRED,
     .doc = "between the long edges"},
    {.name = "splits",
     .kind = FB_PARAM_WHOLE,
     .store = FB_PARAM_SIZE,
     .offset = offsetof(plate_params, splits),
     .range = FB_RANGE_LO | FB_RANGE_HI,
     .lo = 1,
     .hi = 8,
     .need = FB_PARAM_DEFAULT,
     .def = 2,
     .doc = "elements between two neighbouring grid lines"},
};

static const plate_params *plate_of(const fb_scenario *s)
{
  return (const plate_params *)(const void *)s->hull_params.bytes;
}

static int plate_check(const fb_scenario *s, fb_err *err)
{
  const plate_params *p = plate_of(s);
  if (p->x_front > p->x_rear)
    return FB_OK;
  fb_err_set(err, FB_EINVAL, "must be > x_rear = %g m (got %g)", p->x_rear, p->x_front);
  return fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "x_front"), FB_EINVAL;
}

/* Grid lines closer than this are one (the generator's bound, 1 mm). */
#define PLATE_MERGE 1e-3

typedef struct plate_grid {
  double *x, *y; /* sorted, distinct lines */
  size_t nx, ny;
} plate_grid;

static int by_value(const void *a, const void *b)
{
  const double u = *(const double *)a, v = *(const double *)b;
  return (u > v) - (u < v);
}

/* The n lines of v sorted, merged, each interval split in k; *out new. */
static size_t plate_lines(double *v, size_t n, size_t k, double **out)
{
  qsort(v, n, sizeof *v, by_value);
  size_t m = 0;
  for (size_t i = 0; i < n; ++i)
    if (!m || v[i] - v[m - 1] > PLATE_MERGE)
      v[m++] = v[i];
  double *l = malloc(((m - 1) * k + 1) * sizeof *l);
  if (!l)
    return 0;
  for (size_t i = 0; i + 1 < m; ++i)
    for (size_t j = 0; j < k; ++j)
      l[i * k + j] = v[i] + (v[i + 1] - v[i]) * (double)j / (double)k;
  l[(m - 1) * k] = v[m - 1];
  *out = l;
  return (m - 1) * k + 1;
}

static size_t plate_npoints(const fb_scenario *s)
{
  return s->nload + s->ncorners + s->nmounts + s->npoint_masses;
}

/* Point k of the scenario, load points first. */
static void plate_point(const fb_scenario *s, size_t k, double *x, double *y)
{
  if (k < s->nload) {
    *x = s->load_x[k], *y = s->load_y[k];
    return;
  }
  k -= s->nload;
  if (k < s->ncorners) {
    *x = s->corner[k].x, *y = s->corner[k].y;
    return;
  }
  k -= s->ncorners;
  if (k < s->nmounts) {
    *x = s->mount[k].x, *y = s->mount[k].y;
    return;
  }
  k -= s->nmounts;
  *x = s->point_mass[k].x, *y = s->point_mass[k].y;
}

static int plate_grid_new(const fb_scenario *s, plate_grid *g, fb_err *err)
{
  const plate_params *p = plate_of(s);
  const size_t n = plate_npoints(s) + 2;
  double *xs = malloc(n * sizeof *xs), *ys = malloc(n * sizeof *ys);
  g->nx = g->ny = 0;
  if (xs && ys) {
    xs[0] = p->x_rear, xs[1] = p->x_front, ys[0] = -0.5 * p->width, ys[1] = 0.5 * p->width;
    for (size_t k = 0; k + 2 < n; ++k)
      plate_point(s, k, &xs[k + 2], &ys[k + 2]);
    g->nx = plate_lines(xs, n, p->splits, &g->x);
    g->ny = plate_lines(ys, n, p->splits, &g->y);
  }
  free(xs);
  free(ys);
  return g->nx && g->ny ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
}

/* The line of l nearest v. */
static size_t plate_nearest(const double *l, size_t n, double v)
{
  size_t best = 0;
  for (size_t i = 1; i < n; ++i)
    if (fabs(l[i] - v) < fabs(l[best] - v))
      best = i;
  return best;
}

static size_t plate_node_at(const plate_grid *g, double x, double y)
{
  return plate_nearest(g->x, g->nx, x) * g->ny + plate_nearest(g->y, g->ny, y);
}

static int plate_nodes(const plate_grid *g, fb_mesh *m, fb_err *err)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < g->nx; ++i)
    for (size_t j = 0; !rc && j < g->ny; ++j)
      rc = fb_mesh_add_node(m, (long)(i * g->ny + j) + 1, g->x[i], g->y[j], 0.0, NULL, err);
  return rc;
}

static int plate_elements(const plate_grid *g, fb_mesh *m, fb_err *err)
{
  int rc = FB_OK;
  long e = 0;
  for (size_t i = 0; !rc && i + 1 < g->nx; ++i)
    for (size_t j = 0; !rc && j + 1 < g->ny; ++j) {
      const size_t a = i * g->ny + j, b = a + g->ny; /* counter-clockwise from +z */
      const size_t q[4] = {a, b, b + 1, a + 1};
      rc = fb_mesh_add_element(m, ++e, FB_ELEM_QUAD4, q, err);
    }
  return rc;
}

/* "<prefix><NAME>" with name in capitals, into buf. */
static const char *plate_set_name(char *buf, size_t size, const char *prefix, const char *name)
{
  size_t k = (size_t)snprintf(buf, size, "%s", prefix);
  for (size_t i = 0; name[i] && k + 1 < size; ++i)
    buf[k++] = (char)toupper((unsigned char)name[i]);
  buf[k] = '\0';
  return buf;
}

/* The node set of point k (after the load points): one node. */
static int plate_point_set(const fb_scenario *s, const plate_grid *g, size_t k, fb_mesh *m,
                           fb_err *err)
{
  char set[128];
  double x = 0, y = 0;
  plate_point(s, s->nload + k, &x, &y);
  const size_t node = plate_node_at(g, x, y);
  if (k < s->ncorners)
    plate_set_name(set, sizeof set, "SUSP_", s->corner[k].name);
  else if (k < s->ncorners + s->nmounts)
    plate_set_name(set, sizeof set, "", s->mount[k - s->ncorners].name);
  else
    plate_set_name(set, sizeof set, "MASS_", s->point_mass[k - s->ncorners - s->nmounts].name);
  return fb_mesh_add_nset(m, set, 1, &node, err);
}

static int plate_sets(const fb_scenario *s, const plate_grid *g, fb_mesh *m, fb_err *err)
{
  const size_t nn = g->nx * g->ny, ne = (g->nx - 1) * (g->ny - 1);
  size_t *all = malloc((nn + s->nload) * sizeof *all);
  if (!all)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t k = 0; k < nn; ++k)
    all[k] = k;
  int rc = fb_mesh_add_elset(m, "PLATE", ne, all, err);
  if (!rc)
    rc = fb_mesh_add_nset(m, "ALL", nn, all, err);
  for (size_t k = 0; k < s->nload; ++k)
    all[k] = plate_node_at(g, s->load_x[k], s->load_y[k]);
  if (!rc)
    rc = fb_mesh_add_nset(m, "LOAD", s->nload, all, err);
  const size_t front[2] = {(g->nx - 1) * g->ny + g->ny - 1, (g->nx - 1) * g->ny};
  const size_t rear[2] = {g->ny - 1, 0}; /* left (y > 0) first */
  if (!rc)
    rc = fb_mesh_add_nset(m, "FRONT_EDGE", 2, front, err);
  if (!rc)
    rc = fb_mesh_add_nset(m, "REAR_EDGE", 2, rear, err);
  for (size_t k = 0; !rc && k + s->nload < plate_npoints(s); ++k)
    rc = plate_point_set(s, g, k, m, err);
  free(all);
  return rc;
}

static int plate_make(const fb_scenario *s, fb_mesh **out, fb_err *err)
{
  plate_grid g = {NULL, NULL, 0, 0};
  fb_mesh *m = NULL;
  int rc = plate_grid_new(s, &g, err);
  if (!rc)
    rc = fb_mesh_new(&m, err);
  if (!rc)
    rc = plate_nodes(&g, m, err);
  if (!rc)
    rc = plate_elements(&g, m, err);
  if (!rc)
    rc = plate_sets(s, &g, m, err);
  free(g.x);
  free(g.y);
  if (rc)
    fb_mesh_free(&m);
  *out = m;
  return rc;
}

/* FNV-1a over the block and the points: all the plate reads. */
static uint64_t plate_hash(uint64_t h, const void *bytes, size_t n)
{
  const unsigned char *b = bytes;
  for (size_t i = 0; i < n; ++i)
    h = (h ^ b[i]) * 1099511628211u;
  return h;
}

static uint64_t plate_key(const fb_scenario *s)
{
  uint64_t h = plate_hash(1469598103934665603u, s->hull_params.bytes, sizeof(plate_params));
  for (size_t k = 0; k < plate_npoints(s); ++k) {
    double xy[2];
    plate_point(s, k, &xy[0], &xy[1]);
    h = plate_hash(h, xy, sizeof xy);
  }
  return h;
}

static void plate_centroid(const fb_scenario *s, double *x, double *z, double *length)
{
  const plate_params *p = plate_of(s);
  *x = 0.5 * (p->x_rear + p->x_front);
  *z = 0.0;
  *length = p->x_front - p->x_rear;
}

static void plate_describe(const fb_scenario *s, char *buf, size_t n)
{
  snprintf(buf, n, "a flat plate, %zu elements between grid lines", plate_of(s)->splits);
}

static const fb_hull_source_ops plate_ops = {.check = plate_check,
                                             .make = plate_make,
                                             .key = plate_key,
                                             .centroid = plate_centroid,
                                             .describe = plate_describe};

static const fb_hull_source plate = {.name = "plate",
                                     .doc = "a flat rectangular plate",
                                     .param = plate_param,
                                     .nparams = sizeof plate_param / sizeof plate_param[0],
                                     .params_size = sizeof(plate_params),
                                     .ops = &plate_ops};

/* ---- Scenarios for each source, from the example's text. */

/* text with its cut characters from at replaced by with; text is freed,
 * the result new (NULL: at is NULL, or out of memory). */
static char *spliced(char *text, const char *at, size_t cut, const char *with)
{
  char *out = NULL;
  if (at) {
    const size_t n = strlen(text) + strlen(with) + 1;
    out = malloc(n);
    if (out)
      snprintf(out, n, "%.*s%s%s", (int)(at - text), text, with, at + cut);
  }
  free(text);
  return out;
}

/* text with the part from start (after skip characters) up to end
 * (kept) replaced by with (NULL: a marker missing). */
static char *replaced(char *text, const char *start, size_t skip, const char *end,
                      const char *with)
{
  const char *from = text ? strstr(text, start) : NULL;
  const char *to = from ? strstr(from + skip, end) : NULL;
  return spliced(text, to ? from + skip : NULL, to ? (size_t)(to - from) - skip : 0, with);
}

/* The example with its hull.mesh section replaced by mesh, and, when the
 * mesh is not the paper's hull, without its typed mass and inertias. */
static char *example_with_mesh(const char *mesh, int untyped)
{
  char *text = read_text("../examples/apc6x6.yaml");
  text = replaced(text, "\n  mesh:\n", 1, "\n  fe:\n", mesh);
  if (untyped)
    text = replaced(text, "hull:\n", 6, "  material:", "");
  return text;
}

static const char *const PLATE_MESH = "  mesh:\n"
                                      "    plate:\n"
                                      "      x_rear: -2.65798412344113\n"
                                      "      x_front: 2.47813311938948\n"
                                      "      width: 2.10";

/* The example's hull written as a deck in the test's directory. */
static const char *example_deck(void)
{
  static char path[4096];
  fb_err err;
  fb_scenario *s = NULL;
  fb_fe_hull *h = NULL;
  test_tmp_path("hull.inp", path, sizeof path);
  CHECK(fb_scenario_load("../examples/apc6x6.yaml", &s, &err) == FB_OK);
  CHECK(s && fb_vehicle_fe_hull(s, &h, &err) == FB_OK);
  CHECK(h && fb_mesh_write_inp(h->mesh, &h->props, path, &err) == FB_OK);
  fb_fe_hull_free(&h);
  fb_scenario_free(&s);
  return path;
}

/* examples/apc6x6_reduced.yaml, its files named by absolute paths (a
 * scenario loaded from text has no directory of its own). */
static char *example_reduced(void)
{
  char dir[4096], mesh[3 * 4096 + 200];
  CHECK(getcwd(dir, sizeof dir - 16) != NULL);
  strcat(dir, "/../examples");
  snprintf(mesh, sizeof mesh,
           "  mesh:\n    reduced:\n      k: %s/apc6x6_reduced_K.mtx\n"
           "      m: %s/apc6x6_reduced_M.mtx\n      nodes: %s/apc6x6_reduced_nodes.csv\n",
           dir, dir, dir);
  return replaced(read_text("../examples/apc6x6_reduced.yaml"), "  mesh:\n    reduced:", 0,
                  "  fe:\n", mesh);
}

/* A scenario whose hull comes from source src, loaded with gallery g;
 * mesh text into *yaml (new) so that a test can spoil it. */
static char *source_yaml(const fb_hull_source *src)
{
  if (!strcmp(src->name, "generator"))
    return read_text("../examples/apc6x6.yaml");
  if (!strcmp(src->name, "deck")) {
    char mesh[4200];
    snprintf(mesh, sizeof mesh, "  mesh:\n    deck: %s", example_deck());
    return example_with_mesh(mesh, 0);
  }
  if (!strcmp(src->name, "plate"))
    return example_with_mesh(PLATE_MESH, 1);
  if (!strcmp(src->name, "reduced"))
    return example_reduced();
  return NULL; /* a source the harness cannot use: a failure below */
}

static int load_yaml(const char *yaml, const fb_hull_source_gallery *g, fb_scenario **out,
                     fb_err *err)
{
  const fb_scenario_load_opts opts = {.hull_sources = g};
  return yaml ? load_text_with(yaml, &opts, out, err) : FB_EIO;
}

/* text with its first from replaced by to (NULL: from missing). */
static char *replaced_once(char *text, const char *from, const char *to)
{
  return spliced(text, text ? strstr(text, from) : NULL, strlen(from), to);
}

/* A value of the source's section spoilt: the load fails at key. */
static void check_refused(const fb_hull_source_gallery *g, const fb_hull_source *src,
                          const char *from, const char *to, const char *key)
{
  char *bad = replaced_once(source_yaml(src), from, to);
  CHECK(bad != NULL);
  fb_err err;
  fb_err_clear(&err);
  const int rc = load_yaml(bad, g, NULL, &err);
  CHECK(rc != FB_OK && strstr(err.msg, key) != NULL);
  if (rc == FB_OK || !strstr(err.msg, key))
    fprintf(stderr, "  %s: wanted an error at %s, got %d: %s\n", src->name, key, rc, err.msg);
  else
    fprintf(stderr, "%s refused: %s\n", src->name, err.msg);
  free(bad);
}

/* ---- The harness. */

/* Every attachment point of s meets the hull: a node set of its own (one
 * node), or the scenario's coupling. */
static int has_set(const fb_mesh *m, const char *prefix, const char *name)
{
  char set[128];
  const size_t *nodes = NULL;
  size_t n = 0;
  return fb_mesh_nset(m, plate_set_name(set, sizeof set, prefix, name), &nodes, &n) && n == 1;
}

static void check_attachments(const fb_scenario *s, const fb_fe_hull *h)
{
  const int coupled = s->coupling != FB_COUPLING_NONE;
  for (size_t c = 0; c < s->ncorners; ++c)
    CHECK(coupled || has_set(h->mesh, "SUSP_", s->corner[c].name));
  for (size_t b = 0; b < s->nmounts; ++b)
    CHECK(coupled || has_set(h->mesh, "", s->mount[b].name));
  CHECK(h->nattach == fb_scenario_nattach(s) && h->nload == s->nload);
  const size_t nn = fb_mesh_nnodes(h->mesh);
  for (size_t k = 0; k < h->nattach; ++k)
    CHECK(h->attach_node[k] < nn);
  for (size_t k = 0; k < 4; ++k)
    CHECK(h->edge_node[k] < nn);
}

/* The 12 lowest free-free modes: six rigid-body ones at 0 Hz, then an
 * elastic one. A free body has exactly six (three translations, three
 * rotations); a mechanism (a node tied to nothing, a missing stiffness)
 * adds zero-energy modes, a fixed node removes some. The solver reports
 * the modes it finds rigid at 0; 1e-3 of the first elastic one bounds any
 * it would report otherwise (rounding gives sqrt(eps |K| / |M|) / 2 pi,
 * orders of magnitude below). */
static void check_modes(const fb_fe_hull *h, const char *name)
{
  fb_err err;
  double f[12];
  size_t nrigid = 0;
  CHECK(fb_fe_hull_free_modes(h, 12, f, &nrigid, &err) == FB_OK);
  CHECK(nrigid == 6 && f[6] > 0);
  double worst = 0;
  for (int k = 0; k < 6; ++k)
    worst = fmax(worst, fabs(f[k]));
  CHECK(worst < 1e-3 * f[6]);
  fprintf(stderr, "%s: rigid-body modes within %.2e Hz of 0, first elastic %.4g Hz\n", name,
          worst, f[6]);
}

/* The mass properties the loader completed: finite, positive, and the
 * mesh's (a typed value agrees within the loader's tolerance). */
static void check_mass(const fb_scenario *s, const fb_fe_hull *h, const char *name)
{
  fb_err err;
  double mass = 0, cg[3] = {0}, inertia[9] = {0};
  CHECK(fb_fem_mesh_mass_properties(h->mesh, &h->props, h->mass_kind, &mass, cg, inertia,
                                    &err) == FB_OK);
  CHECK(isfinite(s->hull_mass) && s->hull_mass > 0 && isfinite(s->hull_ixx) &&
        s->hull_ixx > 0 && isfinite(s->hull_iyy) && s->hull_iyy > 0);
  CHECK(fabs(s->hull_mass - mass) <= 1e-2 * mass);
  fprintf(stderr, "%s: mass %.6g kg (mesh %.6g), Ixx %.6g, Iyy %.6g kg m^2\n", name,
          s->hull_mass, mass, s->hull_ixx, s->hull_iyy);
}

static void conform(const fb_hull_source_gallery *g, const fb_hull_source *src)
{
  fb_err err;
  fb_err_clear(&err);
  char *yaml = source_yaml(src);
  CHECK(yaml != NULL); /* every source of the gallery has a scenario here */
  fb_scenario *s = NULL;
  const int rc = load_yaml(yaml, g, &s, &err);
  free(yaml);
  CHECK(rc == FB_OK);
  if (rc) {
    fprintf(stderr, "  %s: %s\n", src->name, err.msg);
    fb_scenario_free(&s);
    return;
  }
  CHECK(fb_scenario_hull_source(s) == src);
  fb_fe_hull *h = NULL;
  CHECK(fb_vehicle_fe_hull(s, &h, &err) == FB_OK);
  if (h) {
    CHECK(fb_mesh_check(h->mesh, &err) == FB_OK);
    check_attachments(s, h);
    check_mass(s, h, src->name);
    check_modes(h, src->name);
  }
  char what[256];
  fb_scenario_hull_describe(s, what, sizeof what);
  CHECK(what[0] != '\0');
  /* A copy has the same source and mesh. */
  fb_scenario *copy = NULL;
  CHECK(fb_scenario_clone(s, &copy, &err) == FB_OK);
  CHECK(copy && fb_scenario_hull_source(copy) == src);
  fb_fe_hull_free(&h);
  fb_scenario_free(&copy);
  fb_scenario_free(&s);
}

static void test_conformance(const fb_hull_source_gallery *g)
{
  for (size_t i = 0; i < fb_hull_source_gallery_count(g); ++i)
    conform(g, fb_hull_source_gallery_at(g, i));
  /* Out of range at their keys. */
  const fb_hull_source *gen = fb_hull_source_gallery_find(g, "generator");
  const fb_hull_source *deck = fb_hull_source_gallery_find(g, "deck");
  const fb_hull_source *pl = fb_hull_source_gallery_find(g, "plate");
  check_refused(g, gen, "width: 2.10 ", "width: -2.10", "hull.mesh.generator.width");
  check_refused(g, gen, "side_rows: 2", "side_rows: 0", "hull.mesh.generator.side_rows");
  check_refused(g, deck, "\n    deck: ", "\n    deck: /no-such-dir", "hull.mesh.deck");
  const fb_hull_source *red = fb_hull_source_gallery_find(g, "reduced");
  check_refused(g, red, "reduced_M.mtx", "reduced_none.mtx", "hull.mesh.reduced.m");
  check_refused(g, red, "    reduced:\n", "    reduced:\n      format: cdb\n",
                "hull.mesh.reduced.format");
  check_refused(g, pl, "width: 2.10", "width: -2.10", "hull.mesh.plate.width");
  check_refused(g, pl, "      x_front: 2.47813311938948", "      x_front: -3",
                "hull.mesh.plate.x_front");
  check_refused(g, pl, "    plate:\n", "    plate:\n      splits: 0\n",
                "hull.mesh.plate.splits");
}

/* ---- Registration. */

static const fb_hull_source_ops half_ops = {.make = plate_make, .describe = plate_describe};

static void test_registration(fb_hull_source_gallery *g)
{
  fb_err err;
  CHECK(fb_hull_source_gallery_count(g) == 3);
  CHECK(fb_hull_source_gallery_find(g, "generator") == &fb_hull_source_generator);
  CHECK(fb_hull_source_gallery_find(g, "deck") == &fb_hull_source_deck);
  CHECK(fb_hull_source_gallery_find(g, "reduced") == &fb_hull_source_reduced);
  CHECK(fb_hull_source_gallery_find(g, "plate") == NULL);
  CHECK(fb_hull_source_gallery_at(g, 3) == NULL);
  CHECK(fb_hull_source_gallery_add(g, &plate, &err) == FB_OK);
  CHECK(fb_hull_source_gallery_add(g, &plate, &err) == FB_EINVAL &&
        strstr(err.msg, "already") != NULL);
  /* A source that makes its mesh says from what and where its centre is. */
  const fb_hull_source half = {.name = "half", .doc = "no key", .ops = &half_ops};
  CHECK(fb_hull_source_gallery_add(g, &half, &err) == FB_EINVAL &&
        strstr(err.msg, "key") != NULL);
  const fb_hull_source bad_name = {.name = "2d", .doc = "x", .ops = &plate_ops};
  CHECK(fb_hull_source_gallery_add(g, &bad_name, &err) == FB_EINVAL);
  CHECK(fb_hull_source_gallery_count(g) == 4);
}

/* The plate against its closed forms: a thin plate of L x W, mass
 * rho t L W, Ixx = m W^2 / 12 and Iyy = m L^2 / 12 about its centre (the
 * thickness's share, m t^2 / 12, is 1e-5 of them: the shell's mass matrix
 * has it, hence a tolerance of 1e-4 relative). Its cached mesh follows a
 * moved point (its key), and it describes itself. */
static void test_plate(const fb_hull_source_gallery *g)
{
  fb_err err;
  char *yaml = example_with_mesh(PLATE_MESH, 1);
  fb_scenario *s = NULL;
  CHECK(load_yaml(yaml, g, &s, &err) == FB_OK);
  free(yaml);
  if (!s)
    return;
  const double length = 2.47813311938948 + 2.65798412344113, width = 2.10;
  const double mass = s->density * s->thickness * length * width;
  CHECK_NEAR(s->hull_mass, mass, 1e-4 * mass);
  CHECK_NEAR(s->hull_ixx, mass * width * width / 12, 1e-4 * mass * width * width / 12);
  CHECK_NEAR(s->hull_iyy, mass * length * length / 12, 1e-4 * mass * length * length / 12);
  char what[256];
  fb_scenario_hull_describe(s, what, sizeof what);
  CHECK(!strcmp(what, "a flat plate, 2 elements between grid lines"));
  CHECK(fb_scenario_hull_density(s) == 0);
  /* The engine moved 0.25 m back: the cached mesh has no node there, a
   * new one has (fe_hull.c matches each point's node within 1 mm). */
  s->mount[1].x -= 0.25;
  fb_fe_hull *h = NULL;
  CHECK(fb_vehicle_fe_hull(s, &h, &err) == FB_OK);
  const size_t *node = NULL;
  size_t n = 0;
  CHECK(h && fb_mesh_nset(h->mesh, "ENGINE", &node, &n) && n == 1 &&
        fabs(fb_mesh_node_xyz(h->mesh, node[0])[0] - s->mount[1].x) < 1e-9);
  fb_fe_hull_free(&h);
  fb_scenario_free(&s);
  /* Its keys take a value in place of the file's, as the format's do. */
  const fb_scenario_override ov = {.key = "hull.mesh.plate.splits", .value = "3"};
  const fb_scenario_load_opts opts = {.hull_sources = g, .overrides = &ov, .noverrides = 1};
  yaml = example_with_mesh(PLATE_MESH, 1);
  CHECK(yaml && load_text_with(yaml, &opts, &s, &err) == FB_OK);
  free(yaml);
  if (s)
    fb_scenario_hull_describe(s, what, sizeof what);
  CHECK(s && !strcmp(what, "a flat plate, 3 elements between grid lines"));
  fb_scenario_free(&s);
}

/* Without the program's gallery the format has no such section. */
static void test_unknown(void)
{
  fb_err err;
  char *yaml = example_with_mesh(PLATE_MESH, 1);
  CHECK(yaml && load_yaml(yaml, NULL, NULL, &err) != FB_OK &&
        strstr(err.msg, "hull.mesh.plate") != NULL);
  free(yaml);
}

int main(void)
{
  fb_hull_source_gallery *g = NULL;
  fb_err err;
  CHECK(fb_hull_source_gallery_new(&g, &err) == FB_OK);
  if (!g)
    return check_report("test_hull_source");
  test_registration(g);
  test_conformance(g);
  test_plate(g);
  test_unknown();
  fb_hull_source_gallery_free(&g);
  return check_report("test_hull_source");
}
