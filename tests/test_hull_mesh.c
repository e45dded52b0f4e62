/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of System 2's hull mesh (fb_hull_mesh_params_default,
 * fb_hull_mesh_generate; flexbond/vehicle.h, docs/hull-mesh.md) on the
 * reference scenario:
 *  - 28 triangles and 212 quadrilaterals at density 1, four times as many
 *    at density 2, fb_mesh_check clean;
 *  - every special point a node of its set at the scenario's (x, y) on the
 *    floor, LOAD in the scenario's order, the torsion edges' end nodes;
 *  - mass, centre of mass and inertias from the consistent mass matrix
 *    (fb_fem_assemble + fb_fem_mass_properties) against the paper's Table
 *    2 and against closed-form thin-plate integrals of the parameters;
 *  - a closed hull: every edge shared by two elements, traversed in
 *    opposite directions (outward normals), except the bulkheads' rims,
 *    shared by three; the volume enclosed by the outer plates (divergence
 *    theorem) equals the box-plus-wedge volume;
 *  - the error paths. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#include "apc_layout.h"
#include "check.h"

#define SCENARIO "../examples/apc6x6.yaml"
/* Node coordinates are sums and products of a few doubles of size < 10 m:
 * round-off is below 1e-14 m; 1e-12 m leaves room. */
#define POS_TOL 1e-12

static int contains(const char *msg, const char *part)
{
  return strstr(msg, part) != NULL;
}

/* ---- Closed-form thin-plate mass properties of the parameters, in the
 * hull frame (x as given, z above the floor): area integrals of 1, x, z,
 * x^2, y^2, z^2 over the plates' mid-surfaces. */

typedef struct moments {
  double a, x, z, xx, yy, zz;
} moments;

static void add_moments(moments *m, const moments *p)
{
  m->a += p->a;
  m->x += p->x;
  m->z += p->z;
  m->xx += p->xx;
  m->yy += p->yy;
  m->zz += p->zz;
}

/* A plate of width w across y (symmetric) whose section in the x-z plane
 * is the segment (x0, z0) - (x1, z1): with t in [0, 1] along it,
 * int x^2 = w L int (x0 + t dx)^2 dt = w L (x0^2 + x0 dx + dx^2 / 3). */
static moments strip(double w, double x0, double z0, double x1, double z1)
{
  const double dx = x1 - x0, dz = z1 - z0, len = hypot(dx, dz), a = w * len;
  return (moments){a,
                   a * (x0 + 0.5 * dx),
                   a * (z0 + 0.5 * dz),
                   a * (x0 * x0 + x0 * dx + dx * dx / 3.0),
                   len * w * w * w / 12.0,
                   a * (z0 * z0 + z0 * dz + dz * dz / 3.0)};
}

/* A triangle in the plane y = y0 with corners (x_i, z_i): centroid and
 * second moments int x^2 = A/6 (x1^2 + x2^2 + x3^2 + x1 x2 + x2 x3 + x3 x1)
 * (e.g. Zienkiewicz & Taylor, "The Finite Element Method", vol. 1, the
 * area-coordinate integral int L1^a L2^b L3^c = a! b! c! 2A / (a+b+c+2)!). */
static moments side_triangle(double y0, const double *x, const double *z)
{
  const double a = 0.5 * fabs((x[1] - x[0]) * (z[2] - z[0]) - (x[2] - x[0]) * (z[1] - z[0]));
  const double sxx =
      x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[0] * x[1] + x[1] * x[2] + x[2] * x[0];
  const double szz =
      z[0] * z[0] + z[1] * z[1] + z[2] * z[2] + z[0] * z[1] + z[1] * z[2] + z[2] * z[0];
  return (moments){a,
                   a * (x[0] + x[1] + x[2]) / 3.0,
                   a * (z[0] + z[1] + z[2]) / 3.0,
                   a * sxx / 6.0,
                   a * y0 * y0,
                   a * szz / 6.0};
}

/* Sum over all plates; mass, centre (x, z) and inertias about it. */
static void plate_properties(const fb_hull_mesh_params *p, double rho_t, double *mass,
                             double *cx, double *cz, double *ixx, double *iyy)
{
  const double w = p->width, h = p->height, xr = p->x_rear, xf = p->x_front;
  const double xn = xf + p->nose_length, zn = p->nose_height, half = 0.5 * w;
  moments m = {0};
  const moments floor = strip(w, xr, 0, xf, 0), roof = strip(w, xr, h, xf, h);
  const moments rear = strip(w, xr, 0, xr, h);
  const moments low = strip(w, xf, 0, xn, zn), up = strip(w, xn, zn, xf, h);
  add_moments(&m, &floor);
  add_moments(&m, &roof);
  add_moments(&m, &rear);
  add_moments(&m, &low);
  add_moments(&m, &up);
  for (size_t b = 0; b < p->nbulkheads; ++b) {
    const moments bk = strip(w, p->bulkhead_x[b], 0, p->bulkhead_x[b], h);
    add_moments(&m, &bk);
  }
  /* Side walls: the box rectangle as two triangles, and the nose one. */
  const double t1x[3] = {xr, xf, xf}, t1z[3] = {0, 0, h};
  const double t2x[3] = {xr, xf, xr}, t2z[3] = {0, h, h};
  const double t3x[3] = {xf, xn, xf}, t3z[3] = {0, zn, h};
  for (int side = 0; side < 2; ++side) {
    const double y0 = side ? half : -half;
    const moments s1 = side_triangle(y0, t1x, t1z), s2 = side_triangle(y0, t2x, t2z);
    const moments s3 = side_triangle(y0, t3x, t3z);
    add_moments(&m, &s1);
    add_moments(&m, &s2);
    add_moments(&m, &s3);
  }
  *mass = rho_t * m.a;
  *cx = m.x / m.a;
  *cz = m.z / m.a;
  /* Parallel axes: int (z - cz)^2 = int z^2 - A cz^2; y is symmetric. */
  *ixx = rho_t * (m.yy + m.zz - m.a * *cz * *cz);
  *iyy = rho_t * (m.xx - m.a * *cx * *cx + m.zz - m.a * *cz * *cz);
}

/* ---- Mesh checks. */

static void check_counts(const fb_mesh *m, int density)
{
  const size_t d2 = (size_t)density * (size_t)density;
  CHECK(fb_mesh_count(m, FB_ELEM_TRI3) == 28 * d2);
  CHECK(fb_mesh_count(m, FB_ELEM_QUAD4) == 212 * d2);
  CHECK(fb_mesh_nelements(m) == 240 * d2);
  fb_err err;
  const int rc = fb_mesh_check(m, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  fb_mesh_check: %s\n", err.msg);
}

/* The one node of set `name` is at (x, y, z). */
static void check_single(const fb_mesh *m, const char *name, double x, double y, double z)
{
  const size_t *nodes = NULL;
  size_t n = 0;
  CHECK(fb_mesh_nset(m, name, &nodes, &n) && n == 1);
  if (n != 1)
    return;
  const double *p = fb_mesh_node_xyz(m, nodes[0]);
  CHECK_NEAR(p[0], x, POS_TOL);
  CHECK_NEAR(p[1], y, POS_TOL);
  CHECK_NEAR(p[2], z, POS_TOL);
}

static void check_edge(const fb_mesh *m, const char *name, double x, double half, double z)
{
  const size_t *nodes = NULL;
  size_t n = 0;
  CHECK(fb_mesh_nset(m, name, &nodes, &n) && n == 2);
  if (n != 2)
    return;
  const double *l = fb_mesh_node_xyz(m, nodes[0]), *r = fb_mesh_node_xyz(m, nodes[1]);
  CHECK_NEAR(l[0], x, POS_TOL);
  CHECK_NEAR(r[0], x, POS_TOL);
  CHECK_NEAR(l[1], half, POS_TOL); /* left end first */
  CHECK_NEAR(r[1], -half, POS_TOL);
  CHECK_NEAR(l[2], z, POS_TOL);
  CHECK_NEAR(r[2], z, POS_TOL);
}

/* Special points on the floor z_floor at the scenario's (x, y). */
static void check_sets(const fb_mesh *m, const fb_scenario *s, const fb_hull_mesh_params *p,
                       double cx, double z_floor)
{
  static const char *const susp[APC_NCORNERS] = {"SUSP_LF", "SUSP_RF", "SUSP_LM",
                                                 "SUSP_RM", "SUSP_LR", "SUSP_RR"};
  for (int c = 0; c < APC_NCORNERS; ++c)
    check_single(m, susp[c], s->corner[c].x, s->corner[c].y, z_floor);
  check_single(m, "DRIVER", APC_DRIVER(s)->x, APC_DRIVER(s)->y, z_floor);
  check_single(m, "ENGINE", APC_ENGINE(s)->x, APC_ENGINE(s)->y, z_floor);
  const size_t *load = NULL;
  size_t n = 0;
  CHECK(fb_mesh_nset(m, "LOAD", &load, &n) && n == 56 && n == s->nload);
  for (size_t i = 0; i < n && i < s->nload; ++i) {
    const double *q = fb_mesh_node_xyz(m, load[i]);
    CHECK(fabs(q[0] - s->load_x[i]) <= POS_TOL && fabs(q[1] - s->load_y[i]) <= POS_TOL &&
          fabs(q[2] - z_floor) <= POS_TOL);
  }
  check_edge(m, "FRONT_EDGE", p->x_front - cx, 0.5 * p->width, z_floor);
  check_edge(m, "REAR_EDGE", p->x_rear - cx, 0.5 * p->width, z_floor);
  CHECK(fb_mesh_nset(m, "ALL", &load, &n) && n == fb_mesh_nnodes(m));
}

/* ---- Closedness. */

typedef struct edge_use {
  size_t a, b; /* a < b */
  int forward; /* the element runs a -> b */
} edge_use;

static int cmp_edge(const void *p, const void *q)
{
  const edge_use *u = p, *v = q;
  if (u->a != v->a)
    return u->a < v->a ? -1 : 1;
  return (u->b > v->b) - (u->b < v->b);
}

/* 1 if element e lies in a bulkhead plane x = bulkhead (mesh frame). */
static int on_bulkhead(const fb_mesh *m, size_t e, const double *bulk, size_t nb)
{
  const size_t *nodes = fb_mesh_element_nodes(m, e);
  const size_t nn = (size_t)fb_mesh_element_type(m, e);
  for (size_t k = 0; k < nb; ++k) {
    size_t on = 0;
    for (size_t i = 0; i < nn; ++i)
      on += fabs(fb_mesh_node_xyz(m, nodes[i])[0] - bulk[k]) <= POS_TOL;
    if (on == nn)
      return 1;
  }
  return 0;
}

/* Every edge of the outer plates is shared by exactly two of them, run in
 * opposite directions; bulkheads add a third element on their rims
 * (2 (ny - 1) + 2 side_rows edges per bulkhead and per density step), and
 * no edge is used by one element or by more than three. */
static void check_closed(const fb_mesh *m, const double *bulk, size_t nb, size_t rim_edges)
{
  const size_t ne = fb_mesh_nelements(m);
  edge_use *u = malloc(4 * ne * sizeof *u);
  if (!u) {
    CHECK(u != NULL);
    return;
  }
  size_t n = 0;
  for (size_t e = 0; e < ne; ++e) {
    if (on_bulkhead(m, e, bulk, nb))
      continue;
    const size_t *nodes = fb_mesh_element_nodes(m, e);
    const size_t nn = (size_t)fb_mesh_element_type(m, e);
    for (size_t i = 0; i < nn; ++i) {
      const size_t a = nodes[i], b = nodes[(i + 1) % nn];
      u[n++] = (edge_use){a < b ? a : b, a < b ? b : a, a < b};
    }
  }
  qsort(u, n, sizeof *u, cmp_edge);
  size_t bad = 0;
  for (size_t i = 0; i < n;) {
    size_t j = i;
    while (j < n && u[j].a == u[i].a && u[j].b == u[i].b)
      ++j;
    bad += !(j - i == 2 && u[i].forward != u[i + 1].forward);
    i = j;
  }
  CHECK(bad == 0);
  /* Bulkhead edges: each rim edge is one of the outer edges above. */
  size_t rim = 0, inner = 0;
  for (size_t e = 0; e < ne; ++e) {
    if (!on_bulkhead(m, e, bulk, nb))
      continue;
    const size_t *nodes = fb_mesh_element_nodes(m, e);
    const size_t nn = (size_t)fb_mesh_element_type(m, e);
    for (size_t i = 0; i < nn; ++i) {
      const size_t a = nodes[i], b = nodes[(i + 1) % nn];
      const edge_use key = {a < b ? a : b, a < b ? b : a, 0};
      if (bsearch(&key, u, n, sizeof *u, cmp_edge))
        ++rim;
      else
        ++inner;
    }
  }
  CHECK(rim == rim_edges);
  /* Inner bulkhead edges are shared by two bulkhead elements: 4 per quad
   * minus the rim, each counted twice. */
  CHECK(inner % 2 == 0);
  free(u);
}

/* Volume enclosed by the outer plates, (1/3) sum of x . (area vector)
 * (divergence theorem with div r = 3; r . n is constant on a flat
 * element, the area vector of a flat quadrilateral is half the cross
 * product of its diagonals). */
static double enclosed_volume(const fb_mesh *m, const double *bulk, size_t nb)
{
  double v = 0.0;
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e) {
    if (on_bulkhead(m, e, bulk, nb))
      continue;
    const size_t *nodes = fb_mesh_element_nodes(m, e);
    const int quad = fb_mesh_element_type(m, e) == FB_ELEM_QUAD4;
    const double *x0 = fb_mesh_node_xyz(m, nodes[0]), *x1 = fb_mesh_node_xyz(m, nodes[1]);
    const double *x2 = fb_mesh_node_xyz(m, nodes[2]);
    const double *x3 = quad ? fb_mesh_node_xyz(m, nodes[3]) : x0;
    double d1[3], d2[3];
    for (int k = 0; k < 3; ++k) {
      d1[k] = quad ? x2[k] - x0[k] : x1[k] - x0[k];
      d2[k] = quad ? x3[k] - x1[k] : x2[k] - x0[k];
    }
    const double nx = 0.5 * (d1[1] * d2[2] - d1[2] * d2[1]);
    const double ny = 0.5 * (d1[2] * d2[0] - d1[0] * d2[2]);
    const double nz = 0.5 * (d1[0] * d2[1] - d1[1] * d2[0]);
    v += (x0[0] * nx + x0[1] * ny + x0[2] * nz) / 3.0;
  }
  return v;
}

/* ---- The reference hull. */

static void check_mass(const fb_mesh *m, const fb_scenario *s, const fb_hull_mesh_params *p,
                       double *mass_out)
{
  const double rho_t = s->density * s->thickness;
  double mass, cx, cz, ixx, iyy;
  plate_properties(p, rho_t, &mass, &cx, &cz, &ixx, &iyy);
  /* The fitted defaults meet Table 2 to round-off in exact plate
   * integrals (the fit's residual is 1e-15). */
  CHECK_NEAR(mass, s->hull_mass, 1e-9 * s->hull_mass);
  CHECK_NEAR(ixx, s->hull_ixx, 1e-9 * s->hull_ixx);
  CHECK_NEAR(iyy, s->hull_iyy, 1e-9 * s->hull_iyy);
  CHECK_NEAR(cx, 0.0, 1e-9);

  const fb_shell_props sp = {s->young, s->poisson, s->density, s->thickness, 0.0, 0.0};
  fb_err err;
  fb_mat *M = NULL;
  double fe_mass = 0, cg[3] = {1, 1, 1}, inertia[9] = {0};
  int rc = fb_fem_assemble(m, &sp, FB_MASS_CONSISTENT, NULL, &M, &err);
  if (rc == FB_OK)
    rc = fb_fem_mass_properties(m, M, &fe_mass, cg, inertia, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "  FE mass properties: %s\n", err.msg);
  fb_mat_free(&M);
  /* The brief's requirement: Table 2 within 0.5 %. */
  CHECK_NEAR(fe_mass, s->hull_mass, 0.005 * s->hull_mass);
  CHECK_NEAR(inertia[0], s->hull_ixx, 0.005 * s->hull_ixx);
  CHECK_NEAR(inertia[4], s->hull_iyy, 0.005 * s->hull_iyy);
  /* Against the plate integrals: the consistent mass of linear and
   * bilinear elements integrates x^2, y^2, z^2 exactly on flat elements;
   * what it adds is rotary inertia rho t^3 / 12 per unit area, m t^2 / 12
   * = 0.024 kg m^2 (6e-6 of Ixx): 1e-5 relative bounds it. Mass: exact. */
  CHECK_NEAR(fe_mass, mass, 1e-12 * mass);
  CHECK_NEAR(inertia[0], ixx, 1e-5 * ixx);
  CHECK_NEAR(inertia[4], iyy, 1e-5 * iyy);
  /* Centre of mass at the origin: the mesh was shifted by the plates'
   * centroid; round-off of coordinates below 10 m. */
  for (int k = 0; k < 3; ++k)
    CHECK_NEAR(cg[k], 0.0, 1e-12);
  /* Symmetric about y = 0: no Ixy, Iyz. */
  CHECK_NEAR(inertia[1], 0.0, 1e-9 * ixx);
  CHECK_NEAR(inertia[5], 0.0, 1e-9 * ixx);
  *mass_out = fe_mass;
}

static void test_reference(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load(SCENARIO, &s, &err) == FB_OK);
  if (!s)
    return;
  fb_hull_mesh_params p;
  CHECK(fb_hull_mesh_params_default(s, &p, &err) == FB_OK);
  CHECK(p.width == 2.10 && p.density == 1 && p.nbulkheads == 3);

  double mass1 = 0.0, mass2 = 0.0, cx, cz, unused;
  plate_properties(&p, 1.0, &unused, &cx, &cz, &unused, &unused);
  const double bulk[3] = {p.bulkhead_x[0] - cx, p.bulkhead_x[1] - cx, p.bulkhead_x[2] - cx};
  /* Box plus the nose's wedge: w (h L + h d / 2). */
  const double volume = p.width * p.height * (p.x_front - p.x_rear + 0.5 * p.nose_length);
  for (int density = 1; density <= 2; ++density) {
    p.density = density;
    fb_mesh *m = NULL;
    const int rc = fb_hull_mesh_generate(s, &p, &m, &err);
    CHECK(rc == FB_OK);
    if (rc) {
      fprintf(stderr, "  fb_hull_mesh_generate: %s\n", err.msg);
      continue;
    }
    check_counts(m, density);
    check_sets(m, s, &p, cx, -cz);
    /* Rim of each bulkhead: 2 x 3 floor/roof intervals + 2 x 2 side rows. */
    check_closed(m, bulk, 3, 3 * 10 * (size_t)density);
    /* Each volume term is below 1e2 m^3 with relative round-off 1e-16. */
    CHECK_NEAR(enclosed_volume(m, bulk, 3), volume, 1e-10 * volume);
    check_mass(m, s, &p, density == 1 ? &mass1 : &mass2);
    fb_mesh_free(&m);
  }
  /* Refinement keeps the geometry: the same mass up to summation order. */
  CHECK_NEAR(mass2, mass1, 1e-12 * mass1);

  /* p NULL means the defaults: the same mesh. */
  fb_mesh *a = NULL;
  CHECK(fb_hull_mesh_generate(s, NULL, &a, &err) == FB_OK);
  if (a) {
    CHECK(fb_mesh_count(a, FB_ELEM_TRI3) == 28 && fb_mesh_count(a, FB_ELEM_QUAD4) == 212);
    fb_mesh_free(&a);
  }
  fb_scenario_free(&s);
}

/* ---- Error paths. */

/* Generates with one parameter changed; expects FB_EINVAL naming it, and
 * no mesh. */
static void expect_error(const fb_scenario *s, const fb_hull_mesh_params *p, const char *part1,
                         const char *part2)
{
  fb_err err;
  fb_mesh *m = (fb_mesh *)&err; /* must come back NULL */
  const int rc = fb_hull_mesh_generate(s, p, &m, &err);
  /* The error names the part of the description it is about
   * (fb_err.part); the loader's origins give its key in the file. */
  const int typed = err.part.kind != FB_PART_NONE;
  fb_scenario_locate(s, &err);
  const char *text = err.msg;
  CHECK(typed);
  CHECK(rc == FB_EINVAL && m == NULL);
  CHECK(contains(text, part1));
  CHECK(!part2 || contains(text, part2));
  if (rc != FB_EINVAL || !contains(text, part1) || (part2 && !contains(text, part2)))
    fprintf(stderr, "  expected '%s' / '%s', got: %s\n", part1, part2 ? part2 : "", text);
  if (rc == FB_OK)
    fb_mesh_free(&m);
}

static void test_errors(void)
{
  fb_err err;
  fb_scenario *s = NULL;
  CHECK(fb_scenario_load(SCENARIO, &s, &err) == FB_OK);
  if (!s)
    return;
  fb_hull_mesh_params p0, p;
  fb_hull_mesh_params_default(s, &p0, &err);
  fb_mesh *m = NULL;

  CHECK(fb_hull_mesh_params_default(NULL, &p, &err) == FB_EINVAL &&
        contains(err.msg, "NULL argument"));
  CHECK(fb_hull_mesh_generate(NULL, &p0, &m, &err) == FB_EINVAL &&
        contains(err.msg, "NULL argument"));
  CHECK(fb_hull_mesh_generate(s, &p0, NULL, &err) == FB_EINVAL);

  p = p0;
  p.density = 0;
  expect_error(s, &p, "density must be in 1 .. 64 (got 0)", NULL);
  /* Refused from the coarse mesh's 240 elements, before any of the
   * refined 983040 is allocated; density 16 (61440) is the most. */
  p = p0;
  p.density = 64;
  expect_error(s, &p,
               "hull.mesh.density: 64 refines the generated mesh's 240 elements into 983040, "
               "which would need about 64.4 GB",
               "density 16 for this mesh");
  p.density = 17;
  expect_error(s, &p, "hull.mesh.density: 17 refines", "into 69360");
  p = p0;
  p.nose_rows = 0;
  expect_error(s, &p, "nose_rows", NULL);
  p = p0;
  p.height = -1;
  expect_error(s, &p, "height must be > 0 (got -1)", NULL);
  p = p0;
  p.nose_height = p.height;
  expect_error(s, &p, "nose_height must be in (0, height", NULL);
  p = p0;
  p.x_front = p.x_rear;
  expect_error(s, &p, "x_front", "must be > x_rear");
  p = p0;
  p.bulkhead_x[2] = 3.0;
  expect_error(s, &p, "bulkhead_x[2] = 3 must lie inside the box", NULL);
  p = p0;
  p.nbulkheads = FB_HULL_MAX_BULKHEADS + 1;
  expect_error(s, &p, "at most 8 bulkheads", NULL);
  p = p0;
  p.bulkhead_x[1] = p.bulkhead_x[2];
  expect_error(s, &p, "hull.mesh.generator.bulkheads[2]: coincides with bulkhead 1", NULL);
  /* The floor is narrower than the suspension track. */
  p = p0;
  p.width = 2.0;
  expect_error(s, &p,
               "suspensions.axles[0].y: (1.9, 1.05) m lies outside the generated hull's floor",
               NULL);

  fb_scenario *c = NULL;
  CHECK(fb_scenario_clone(s, &c, &err) == FB_OK);
  if (c) {
    c->load_x[5] = 5.0;
    expect_error(c, &p0, "load.points[5]: (5, -0.55) m lies outside the generated hull's floor",
                 NULL);
    /* A load point 0.5 mm behind the rear axle's line (its bulkhead,
     * suspension points and three more load points). */
    c->load_x[5] = s->load_x[5];
    c->load_x[12] = -1.0005;
    expect_error(c, &p0, "load point 12", "must coincide or be at least 0.001 m apart");
    c->load_x[12] = s->load_x[12];
    c->load_x[5] = c->load_x[4];
    c->load_y[5] = c->load_y[4];
    expect_error(c, &p0, "load.points: the 56 points fall on only 55 nodes", NULL);
    fb_scenario_free(&c);
  }
  fb_scenario_free(&s);
}

int main(void)
{
  test_reference();
  test_errors();
  return check_report("test_hull_mesh");
}
