/* SPDX-License-Identifier: BSD-3-Clause */
/* fb_model_write: a bond graph written as a model file and loaded back.
 *   1. a hand-built graph with every element kind, every source kind the
 *      format holds (roads of every kind, a piecewise one among them), a nested subsystem, a
 * bond domain and every probe option is rebuilt part for part: names, kinds, ports, bonds,
 * every matrix entry, modulus, initial state, table knot and contact parameter equal (==),
 * every source equal at its breakpoints and between them;
 *   2. what the format cannot hold (a C callback, a
 *      control character, a bad model name) is refused with FB_EINVAL
 *      naming the part, and nothing is left in the directory;
 *   3. the vehicle scenarios (System 1 and its variants with unilateral
 *      tire contact and a static start, a shock-absorber table, an ISO
 *      8608 road, a course of obstacles; System 2 once) written, loaded and simulated as
 *      `flexbond sim` does give fb_vehicle_simulate's every column to
 *      1e-9 of its range;
 *   4. the YAML string escaper and the loader's new keys. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/escape.h"
#include "flexbond/model.h"
#include "flexbond/road.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "bgtest_util.h"
#include "check.h"
#include "tmpdir.h"

/* ---- Scratch directories. */

static char *make_dir(void)
{
  char tmpl[TEST_PATH_MAX];
  test_tmp_path("fb_model_write_XXXXXX", tmpl, sizeof tmpl);
  char *d = mkdtemp(tmpl);
  return d ? strdup(d) : NULL;
}

/* Number of entries in dir besides . and .. */
static int dir_count(const char *dir)
{
  DIR *d = opendir(dir);
  int n = 0;
  for (struct dirent *e = d ? readdir(d) : NULL; e; e = readdir(d))
    n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
  if (d)
    closedir(d);
  return n;
}

static void remove_dir(char *dir)
{
  DIR *d = opendir(dir);
  for (struct dirent *e = d ? readdir(d) : NULL; e; e = readdir(d)) {
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
      remove(path);
  }
  if (d)
    closedir(d);
  rmdir(dir);
  free(dir);
}

static void free_files(char **files, size_t n)
{
  for (size_t i = 0; i < n; ++i)
    free(files[i]);
  free(files);
}

/* Writes bg into a fresh directory and loads it back; *dir is the
 * directory (the caller removes it). */
static fb_model *round_trip(const fb_bg *bg, const fb_probe_spec *p, size_t np,
                            const fb_sim_opts *o, fb_model_initial initial, const char *name,
                            char **dir)
{
  fb_err err;
  char **files = NULL;
  size_t nfiles = 0;
  fb_model *m = NULL;
  *dir = make_dir();
  CHECK(*dir != NULL);
  if (!*dir)
    return NULL;
  MUST(fb_model_write(bg, p, np, o, initial, *dir, name, &files, &nfiles, &err), &err);
  CHECK(nfiles >= 1 && (int)nfiles == dir_count(*dir));
  free_files(files, nfiles);
  char path[1024];
  snprintf(path, sizeof path, "%s/%s.yaml", *dir, name);
  MUST(fb_model_load(path, &m, &err), &err);
  return m;
}

/* ---- 1. Every element kind. */

static fb_tfun *road_source(int kind, int velocity)
{
  fb_err err;
  fb_road *road = NULL;
  fb_tfun *f = NULL;
  fb_road_iso8608_params iso;
  fb_road_iso8608_defaults(&iso);
  iso.seed = 77;
  iso.nharmonics = 64;
  iso.fade_length = 3;
  const double s[] = {0, 1, 2.5, 4}, zl[] = {0, 0.02, -0.01, 0}, zr[] = {0, 0.01, 0.03, 0};
  const fb_road_piece pieces[] = {{FB_ROAD_PIECE_ARC, 0.0, 0.3, {0.2, -0.05, 0.25, 0, 0}},
                                  {FB_ROAD_PIECE_LINE, 0.3, 0.9, {0.1, -0.05, 0, 0, 0}},
                                  {FB_ROAD_PIECE_WAVE, 0.9, 2.0, {0.07, 0.01, 0.02, 9, 0.1}}};
  if (kind == 0)
    MUST(fb_road_new_oblique_bump(0.1, 3.7, 0.3, 2.1, &road, &err), &err);
  else if (kind == 1)
    MUST(fb_road_new_iso8608(&iso, &road, &err), &err);
  else if (kind == 2)
    MUST(fb_road_new_profile(4, s, zl, zr, &road, &err), &err);
  else /* a piecewise track of every piece's kind, with a face at 0.3 */
    MUST(fb_road_new_pieces(0, NULL, 3, pieces, &road, &err), &err);
  if (velocity)
    MUST(fb_road_wheel_velocity(road, FB_ROAD_RIGHT, 2.5, -1.25, &f, &err), &err);
  else
    MUST(fb_road_wheel_height(road, FB_ROAD_RIGHT, 2.5, -1.25, &f, &err), &err);
  fb_road_free(&road);
  return f;
}

static fb_mat *dense(size_t r, size_t c, const double *rowmajor)
{
  fb_err err;
  fb_mat *m = NULL;
  MUST(fb_mat_new_dense_rowmajor(r, c, rowmajor, &m, &err), &err);
  return m;
}

/* A subsystem with a nested one: inner (a mass on a junction, port p)
 * inside mid (a spring on a 0-junction, ports top and bottom). */
static fb_bg *mid_subsystem(void)
{
  fb_err err;
  fb_bg *inner = NULL, *mid = NULL;
  const size_t one = 1;
  fb_mat *m = dense(1, 1, (const double[]){3.5});
  MUST(fb_bg_new("inner", &inner, &err), &err);
  MUST(fb_bg_add_field(inner, "M", FB_BG_I, 1, &one, &m, &err), &err);
  MUST(fb_bg_add_junction(inner, "v", FB_BG_J1, 1, &err), &err);
  MUST(fb_bg_connect(inner, "b_m", "v", "M", &err), &err);
  MUST(fb_bg_add_port(inner, "p", "v", FB_PORT_IN, &err), &err);
  fb_mat *kc = dense(1, 1, (const double[]){77});
  MUST(fb_bg_add_field(inner, "Kc", FB_BG_C, 1, &one, &kc, &err), &err);
  MUST(fb_bg_new("mid", &mid, &err), &err);
  fb_mat *k = dense(1, 1, (const double[]){1234.5});
  MUST(fb_bg_add_field(mid, "K", FB_BG_C, 1, &one, &k, &err), &err);
  MUST(fb_bg_add_junction(mid, "f", FB_BG_J0, 1, &err), &err);
  MUST(fb_bg_adopt(mid, &inner, "in", &err), &err);
  MUST(fb_bg_connect(mid, "b_k", "f", "K", &err), &err);
  MUST(fb_bg_connect(mid, NULL, "f", "in.p", &err), &err); /* "f->in.p" */
  /* Named by mid after the inner parts: it belongs to mid, not to in. */
  MUST(fb_bg_connect(mid, NULL, "in.v", "in.Kc", &err), &err);
  MUST(fb_bg_add_port(mid, "top", "f", FB_PORT_IN, &err), &err);
  return mid;
}

static fb_bg *every_kind(void)
{
  fb_err err;
  fb_bg *bg = NULL;
  MUST(fb_bg_new("every", &bg, &err), &err);
  const size_t one = 1, two[2] = {1, 1}, three = 3;
  /* Sources: a vector of mixed kinds, a broadcast one, roads. */
  fb_tfun *f[6] = {NULL};
  MUST(fb_tfun_new_const(-9.81, &f[0], &err), &err);
  MUST(fb_tfun_new_step(0.25, 1.0 / 3.0, 7.5, &f[1], &err), &err);
  MUST(fb_tfun_new_sine(0.2, 1.7, 0.1, -0.05, &f[2], &err), &err);
  MUST(fb_tfun_new_table(3, (const double[]){0, 0.5, 2}, (const double[]){0, 1e-7, -3}, &f[3],
                         &err),
       &err);
  MUST(fb_bg_add_source(bg, "mix", FB_BG_SE, 4, f, &err), &err);
  for (int i = 0; i < 3; ++i)
    MUST(fb_tfun_new_const(0.1 + 0.2, &f[i], &err), &err); /* 0.30000000000000004 */
  MUST(fb_bg_add_source(bg, "same", FB_BG_SE, 3, f, &err), &err);
  /* Expressions of t with every operator, nested minus signs and
   * associativity that the text must keep. */
  static const char *const exprs[] = {
      "0.1 * sin(2 * pi * 3 * t) - -2 ^ -0.5 * t / (1 + t) + (t - (1 - t)) / (2 / (t + 3))",
      "min(t, 0.5, 2 * t) - max(-t, atan2(t, 2)) + pow(t + 1, -(t - 2)) + -(-t) ^ 2",
      "step(t - 0.3) * ramp(t - 0.1) + abs(sign(t - 0.2)) * floor(10 * t) / ceil(t + 1e-300)",
      /* One expression over two lines (clang's -Wstring-concatenation
       * wants the parentheses). */
      ("exp(-t) * log(1 + t) + log10(2 + t) + sqrt(t + 1) + tan(t / 9) + asin(t / 9) + "
       "acos(t / 9) + atan(t) + cos(t) + 1e-17 * t + 1.2345678901234568e17 * t")};
  for (size_t i = 0; i < 4; ++i) {
    fb_expr *e = NULL;
    MUST(fb_expr_parse(exprs[i], NULL, &e, &err), &err);
    MUST(fb_tfun_new_expr(&e, &f[i], &err), &err);
  }
  MUST(fb_bg_add_source(bg, "expr", FB_BG_SE, 4, f, &err), &err);
  for (int k = 0; k < 4; ++k) {
    char name[16];
    snprintf(name, sizeof name, "road%d", k);
    f[0] = road_source(k, k != 1);
    MUST(fb_bg_add_source(bg, name, FB_BG_SF, 1, &f[0], &err), &err);
  }
  /* Fields: scalar, 2-port matrix, 3-dim, a 5x5 (to a .mtx file). */
  fb_mat *m = dense(1, 1, (const double[]){250});
  MUST(fb_bg_add_field(bg, "Ms", FB_BG_I, 1, &one, &m, &err), &err);
  MUST(fb_bg_set_initial(bg, "Ms", 1, (const double[]){12.5}, &err), &err);
  m = dense(2, 2, (const double[]){3e4, -1e4, -1e4, 1e4});
  MUST(fb_bg_add_field(bg, "K2", FB_BG_C, 2, two, &m, &err), &err);
  MUST(fb_bg_set_initial(bg, "K2", 2, (const double[]){1e-3, -2e-3}, &err), &err);
  m = dense(3, 3, (const double[]){2, 0.5, 0, 0.5, 3, 0.25, 0, 0.25, 4});
  MUST(fb_bg_add_field(bg, "R3", FB_BG_R, 1, &three, &m, &err), &err);
  double big[25];
  for (int i = 0; i < 25; ++i)
    big[i] = i / 5 == i % 5 ? 10.0 + i : 0.1 / (1 + abs(i / 5 - i % 5));
  const size_t five = 5;
  m = dense(5, 5, big);
  MUST(fb_bg_add_field(bg, "I5", FB_BG_I, 1, &five, &m, &err), &err);
  fb_table_law *law = NULL;
  MUST(fb_table_law_new(4, (const double[]){-1, 0, 0.5, 1},
                        (const double[]){-2e3, 0, 3e3, 4.5e3}, &law, &err),
       &err);
  MUST(fb_bg_add_r_table(bg, "D", &law, &err), &err);
  MUST(fb_bg_add_unilateral_contact(bg, "tk", "tc", 5e5, 1.4e5, &err), &err);
  MUST(fb_bg_add_tf(bg, "arm", FB_BG_TF, 1, 0.7, &err), &err);
  MUST(fb_bg_add_tf(bg, "gy", FB_BG_GY, 2, -3.25, &err), &err);
  m = dense(2, 3, (const double[]){1, 0.5, -2, 0, 1, 3});
  MUST(fb_bg_add_mtf(bg, "T", &m, &err), &err);
  double tb[18];
  for (int i = 0; i < 18; ++i)
    tb[i] = i % 4 ? 0.0 : 1.0 / (i + 1);
  m = dense(6, 3, tb);
  MUST(fb_bg_add_mtf(bg, "Tbig", &m, &err), &err);
  MUST(fb_bg_add_junction(bg, "J1", FB_BG_J1, 1, &err), &err);
  MUST(fb_bg_add_junction(bg, "J0", FB_BG_J0, 3, &err), &err);
  MUST(fb_bg_add_composite(bg, "H", 2, (const size_t[]){1, 2}, &err), &err);
  fb_bg *mid = mid_subsystem();
  MUST(fb_bg_adopt(bg, &mid, "mid", &err), &err);
  fb_bg_set_domain(bg, FB_DOMAIN_ROTATION);
  MUST(fb_bg_connect(bg, "b_ms", "J1", "Ms", &err), &err);
  fb_bg_set_domain(bg, FB_DOMAIN_TRANSLATION);
  MUST(fb_bg_connect(bg, "b_road", "road0", "J1", &err), &err);
  MUST(fb_bg_connect(bg, "b_arm", "J1", "arm.1", &err), &err);
  MUST(fb_bg_connect(bg, NULL, "arm.2", "mid.top", &err), &err);
  MUST(fb_bg_connect(bg, "b_d", "J1", "D", &err), &err);
  MUST(fb_bg_connect(bg, "b_tk", "J1", "tk", &err), &err);
  MUST(fb_bg_connect(bg, "b_tc", "J1", "tc", &err), &err);
  MUST(fb_bg_connect(bg, "b_same", "same", "J0", &err), &err);
  MUST(fb_bg_add_junction(bg, "J4", FB_BG_J0, 4, &err), &err);
  MUST(fb_bg_connect(bg, "b_expr", "expr", "J4", &err), &err);
  MUST(fb_bg_connect(bg, "b_r3", "J0", "R3", &err), &err);
  MUST(fb_bg_connect(bg, "b_t", "J0", "T.1", &err), &err);
  MUST(fb_bg_connect(bg, "b_h", "T.2", "gy.1", &err), &err);
  MUST(fb_bg_connect(bg, "b_gy", "gy.2", "H.2", &err), &err);
  return bg;
}

static void same_matrix(const fb_mat *a, const fb_mat *b)
{
  CHECK((a == NULL) == (b == NULL));
  if (!a || !b)
    return;
  CHECK(fb_mat_nrows(a) == fb_mat_nrows(b) && fb_mat_ncols(a) == fb_mat_ncols(b));
  int equal = 1;
  for (size_t i = 0; i < fb_mat_nrows(a) && i < fb_mat_nrows(b); ++i)
    for (size_t j = 0; j < fb_mat_ncols(a) && j < fb_mat_ncols(b); ++j)
      equal = equal && fb_mat_get(a, i, j) == fb_mat_get(b, i, j);
  CHECK(equal);
}

/* Equal at the breakpoints, just around them, and on a grid. */
static void same_tfun(const fb_tfun *a, const fb_tfun *b)
{
  double ba[16], bb[16];
  const size_t na = fb_tfun_breakpoints(a, ba, 16), nb = fb_tfun_breakpoints(b, bb, 16);
  CHECK(na == nb);
  int equal = 1;
  for (size_t i = 0; i < na && i < nb && i < 16; ++i) {
    equal = equal && ba[i] == bb[i];
    for (int d = -1; d <= 1; ++d)
      equal = equal && fb_tfun_eval(a, ba[i] + d * 1e-9) == fb_tfun_eval(b, ba[i] + d * 1e-9);
  }
  for (int k = -10; k <= 100; ++k)
    equal = equal && fb_tfun_eval(a, 0.0137 * k) == fb_tfun_eval(b, 0.0137 * k);
  CHECK(equal);
}

static void same_element(const fb_bg *a, size_t i, const fb_bg *b, size_t j)
{
  CHECK(!strcmp(fb_bg_element_name(a, i), fb_bg_element_name(b, j)));
  CHECK(fb_bg_element_kind(a, i) == fb_bg_element_kind(b, j));
  CHECK(fb_bg_element_dim(a, i) == fb_bg_element_dim(b, j));
  const size_t np = fb_bg_element_nports(a, i);
  CHECK(np == fb_bg_element_nports(b, j));
  for (size_t k = 0; k < np && k < fb_bg_element_nports(b, j); ++k)
    CHECK(fb_bg_element_port_dim(a, i, k) == fb_bg_element_port_dim(b, j, k));
  same_matrix(fb_bg_element_matrix(a, i), fb_bg_element_matrix(b, j));
  CHECK(fb_bg_element_modulus(a, i) == fb_bg_element_modulus(b, j));
  for (size_t k = 0; fb_bg_element_source(a, i, k); ++k)
    same_tfun(fb_bg_element_source(a, i, k), fb_bg_element_source(b, j, k));
  const double *xa = fb_bg_element_initial(a, i), *xb = fb_bg_element_initial(b, j);
  CHECK((xa == NULL) == (xb == NULL));
  for (size_t k = 0; xa && xb && k < fb_bg_element_dim(a, i); ++k)
    CHECK(xa[k] == xb[k]);
  const fb_table_law *ta = fb_bg_element_table_law(a, i), *tb = fb_bg_element_table_law(b, j);
  CHECK((ta == NULL) == (tb == NULL));
  if (ta && tb) {
    const double *x1, *y1, *x2, *y2;
    const size_t n1 = fb_table_law_knots(ta, &x1, &y1), n2 = fb_table_law_knots(tb, &x2, &y2);
    CHECK(n1 == n2);
    for (size_t k = 0; k < n1 && k < n2; ++k)
      CHECK(x1[k] == x2[k] && y1[k] == y2[k]);
  }
  fb_bg_contact ca, cb;
  const int is_a = fb_bg_element_contact(a, i, &ca), is_b = fb_bg_element_contact(b, j, &cb);
  CHECK(is_a == is_b);
  if (is_a && is_b)
    CHECK(ca.k == cb.k && ca.c == cb.c && ca.spring == cb.spring && ca.damper == cb.damper);
}

static void same_graph(const fb_bg *a, const fb_bg *b)
{
  CHECK(fb_bg_nelements(a) == fb_bg_nelements(b));
  CHECK(fb_bg_nbonds(a) == fb_bg_nbonds(b));
  CHECK(fb_bg_default_domain(a) == fb_bg_default_domain(b));
  for (size_t i = 0; i < fb_bg_nelements(a) && i < fb_bg_nelements(b); ++i)
    same_element(a, i, b, i);
  for (size_t i = 0; i < fb_bg_nbonds(a) && i < fb_bg_nbonds(b); ++i) {
    CHECK(!strcmp(fb_bg_bond_name(a, i), fb_bg_bond_name(b, i)));
    CHECK(fb_bg_bond_from(a, i) == fb_bg_bond_from(b, i));
    CHECK(fb_bg_bond_to(a, i) == fb_bg_bond_to(b, i));
    CHECK(fb_bg_bond_from_port(a, i) == fb_bg_bond_from_port(b, i));
    CHECK(fb_bg_bond_to_port(a, i) == fb_bg_bond_to_port(b, i));
    CHECK(fb_bg_bond_domain(a, i) == fb_bg_bond_domain(b, i));
    CHECK(fb_bg_bond_dim(a, i) == fb_bg_bond_dim(b, i));
  }
}

static void test_every_kind(void)
{
  fb_bg *bg = every_kind();
  const double w[3] = {0.5, -0.25, 1e-300};
  const fb_probe_spec probes[] = {
      {"x", FB_PROBE_FLOW, "b_ms", -1, 1, 1.0, "rad", NULL, 0},
      {"f2", FB_PROBE_EFFORT, "b_r3", 1, 0, 2.5, "in\"N\\", NULL, 0},
      {"p", FB_PROBE_POWER, "b_d", -1, 0, 1.0, NULL, NULL, 0},
      {"q", FB_PROBE_STATE, "K2", 0, 0, 1.0, NULL, NULL, 0},
      {"E", FB_PROBE_ENERGY, "mid.in.M", -1, 0, 1.0, NULL, NULL, 0},
      {"wsum", FB_PROBE_FLOW, "b_r3", -1, 1, 1.0, "m", w, 3},
  };
  const size_t np = sizeof probes / sizeof probes[0];
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  o.t_start = 0.125;
  o.t_end = 2.0 / 3.0;
  o.rtol = 1e-7;
  o.atol = 3e-10;
  o.max_step = 0.01;
  o.sample_rate = 512;
  o.max_order = 4;
  o.max_steps = 12345;
  const double bp[2] = {0.2, 0.3};
  o.breakpoints = bp;
  o.nbreakpoints = 2;
  char *dir = NULL;
  fb_model *m =
      bg ? round_trip(bg, probes, np, &o, FB_MODEL_INITIAL_STATIC, "every", &dir) : NULL;
  CHECK(m != NULL);
  if (m) {
    same_graph(bg, fb_model_graph(m));
    size_t n = 0;
    const fb_probe_spec *q = fb_model_probes(m, &n);
    CHECK(n == np);
    for (size_t i = 0; i < n && i < np; ++i) {
      CHECK(!strcmp(q[i].name, probes[i].name) && !strcmp(q[i].target, probes[i].target));
      CHECK(q[i].kind == probes[i].kind && q[i].component == probes[i].component);
      CHECK(q[i].integrate == probes[i].integrate && q[i].gain == probes[i].gain);
      CHECK((q[i].unit == NULL) == (probes[i].unit == NULL));
      CHECK(!q[i].unit || !strcmp(q[i].unit, probes[i].unit));
      CHECK(q[i].nweights == probes[i].nweights);
      for (size_t k = 0; k < q[i].nweights && k < probes[i].nweights; ++k)
        CHECK(q[i].weights[k] == probes[i].weights[k]);
    }
    const fb_sim_opts *r = fb_model_sim_opts(m);
    CHECK(r->t_start == o.t_start && r->t_end == o.t_end && r->rtol == o.rtol);
    CHECK(r->atol == o.atol && r->max_step == o.max_step && r->sample_rate == o.sample_rate);
    CHECK(r->max_order == o.max_order && r->max_steps == o.max_steps);
    CHECK(r->nbreakpoints == 2 && r->breakpoints[0] == bp[0] && r->breakpoints[1] == bp[1]);
    CHECK(fb_model_initial_choice(m) == FB_MODEL_INITIAL_STATIC);
    /* The made-up name of an unnamed bond into a subsystem came back. */
    CHECK(fb_bg_find_bond(fb_model_graph(m), "arm.2->mid.top") >= 0);
    CHECK(fb_bg_find_bond(fb_model_graph(m), "mid.f->in.p") >= 0);
    CHECK(fb_bg_find_bond(fb_model_graph(m), "mid.in.v->in.Kc") >= 0);
  }
  fb_model_free(&m);
  if (dir)
    remove_dir(dir);
  fb_bg_free(&bg);
}

/* ---- 2. Refusals. */

static double not_a_road(double t, void *ctx)
{
  (void)ctx;
  return t;
}

/* fb_model_write of a graph with one source f: FB_EINVAL naming it, and
 * an empty directory. */
static void check_refused(fb_tfun *f, const char *probe_name, const char *model_name,
                          const char *want)
{
  fb_err err;
  fb_bg *bg = NULL;
  MUST(fb_bg_new("r", &bg, &err), &err);
  MUST(fb_bg_add_source(bg, "src", FB_BG_SE, 1, &f, &err), &err);
  MUST(fb_bg_add_junction(bg, "j", FB_BG_J1, 1, &err), &err);
  MUST(fb_bg_connect(bg, "b", "src", "j", &err), &err);
  const fb_probe_spec p = {probe_name, FB_PROBE_EFFORT, "b", -1, 0, 1.0, NULL, NULL, 0};
  fb_sim_opts o;
  fb_sim_opts_default(&o);
  char *dir = make_dir();
  char **files = NULL;
  size_t n = 7;
  fb_err_clear(&err);
  CHECK(fb_model_write(bg, &p, 1, &o, FB_MODEL_INITIAL_GIVEN, dir, model_name, &files, &n,
                       &err) == FB_EINVAL);
  CHECK(strstr(err.msg, want) != NULL);
  if (!strstr(err.msg, want))
    fprintf(stderr, "  got \"%s\", want \"%s\"\n", err.msg, want);
  CHECK(files == NULL && n == 0 && dir_count(dir) == 0);
  remove_dir(dir);
  fb_bg_free(&bg);
}

static void test_refusals(void)
{
  fb_err err;
  fb_tfun *f = NULL;
  MUST(fb_tfun_new_callback(not_a_road, NULL, 0, NULL, &f, &err), &err);
  check_refused(f, "ok", "m", "source 'src': its value is a C callback");
  MUST(fb_tfun_new_const(1, &f, &err), &err);
  check_refused(f, "bad\nname", "m", "probe 'bad");
  MUST(fb_tfun_new_const(1, &f, &err), &err);
  check_refused(f, "ok", "9lives", "model name '9lives'");
}

/* ---- 3. The vehicle scenarios. */

/* fb_model_load + fb_bd_build + fb_model_initial_state + fb_sim_run, as
 * `flexbond sim` does. */
static fb_result *simulate_model(fb_model *m)
{
  fb_err err;
  fb_bd *bd = NULL;
  fb_result *res = NULL;
  size_t np = 0;
  const fb_probe_spec *p = fb_model_probes(m, &np);
  MUST(fb_bd_build(fb_model_graph(m), p, np, &bd, &err), &err);
  double *x0 = bd ? malloc((fb_bd_nstates(bd) + 1) * sizeof *x0) : NULL;
  if (x0)
    MUST(fb_model_initial_state(m, bd, x0, &err), &err);
  fb_sim_opts o = *fb_model_sim_opts(m);
  o.x0 = x0;
  if (x0)
    MUST(fb_sim_run(bd, &o, &res, &err), &err);
  free(x0);
  fb_bd_free(&bd);
  return res;
}

/* Every column of b within 1e-9 of a's range of a's: the written model is
 * the assembled graph value for value and every matrix keeps its storage
 * (mtx.c writes dense ones as arrays), so the runs differ at most by the
 * rounding of sums taken in another order, far below this. */
static void same_result(const fb_result *a, const fb_result *b, const char *what)
{
  CHECK(fb_result_ncols(a) == fb_result_ncols(b));
  CHECK(fb_result_nsamples(a) == fb_result_nsamples(b));
  if (fb_result_ncols(a) != fb_result_ncols(b) ||
      fb_result_nsamples(a) != fb_result_nsamples(b))
    return;
  const size_t ns = fb_result_nsamples(a);
  for (size_t j = 0; j < fb_result_ncols(a); ++j) {
    CHECK(!strcmp(fb_result_col_name(a, j), fb_result_col_name(b, j)));
    double lo = INFINITY, hi = -INFINITY, diff = 0;
    for (size_t k = 0; k < ns; ++k) {
      const double x = fb_result_row(a, k)[j], y = fb_result_row(b, k)[j];
      lo = fmin(lo, x);
      hi = fmax(hi, x);
      diff = fmax(diff, fabs(x - y));
    }
    CHECK(diff <= 1e-9 * (hi - lo));
    fprintf(stderr, "  %s %-16s range %-12.6g max diff %.3g\n", what, fb_result_col_name(a, j),
            hi - lo, diff);
  }
}

static void vehicle_case(const char *path, fb_system sys, const char *t_end)
{
  fb_err err;
  fb_scenario *s = NULL;
  const fb_scenario_override ov = {.key = "simulation.t_end", .value = t_end};
  MUST(fb_scenario_load_overrides(path, &ov, t_end ? 1 : 0, &s, &err), &err);
  if (!s)
    return;
  fb_bg *graph = NULL;
  fb_probe_spec *probes = NULL;
  size_t np = 0;
  fb_sim_opts o;
  fb_vehicle_sim_opts(s, &o);
  MUST(fb_vehicle_graph(s, sys, &graph, &probes, &np, &err), &err);
  char *dir = NULL;
  const fb_model_initial initial =
      s->initial == FB_INITIAL_STATIC ? FB_MODEL_INITIAL_STATIC : FB_MODEL_INITIAL_ZERO;
  fb_model *m = graph ? round_trip(graph, probes, np, &o, initial, s->name, &dir) : NULL;
  if (m)
    same_graph(graph, fb_model_graph(m));
  fb_result *mine = m ? simulate_model(m) : NULL, *ref = NULL;
  MUST(fb_vehicle_simulate(s, sys, &ref, &err), &err);
  CHECK(mine && ref);
  if (mine && ref)
    same_result(ref, mine, path);
  fb_result_free(&mine);
  fb_result_free(&ref);
  fb_model_free(&m);
  if (dir)
    remove_dir(dir);
  fb_vehicle_probes_free(&probes, np);
  fb_bg_free(&graph);
  fb_scenario_free(&s);
}

/* ---- 4. Escaper and loader keys. */

static void test_yaml_escape(void)
{
  char *buf = NULL;
  size_t len = 0;
  FILE *fp = open_memstream(&buf, &len);
  CHECK(fb_yaml_write_string(fp, "a\"b\\c \xc3\xa9") == 0);
  CHECK(fb_yaml_write_string(fp, "tab\there") == -1);
  CHECK(fb_yaml_write_string(fp, "c1 \xc2\x85") == -1);
  fclose(fp);
  CHECK(buf && !strcmp(buf, "\"a\\\"b\\\\c \xc3\xa9\""));
  free(buf);
  CHECK(fb_yaml_is_plain("susp_LF.b_tire") && fb_yaml_is_plain("_x1"));
  CHECK(!fb_yaml_is_plain("N") && !fb_yaml_is_plain("Off") && !fb_yaml_is_plain("null"));
  CHECK(!fb_yaml_is_plain("1a") && !fb_yaml_is_plain("") && !fb_yaml_is_plain("m/s"));
}

static void check_load_error(const char *text, const char *want)
{
  fb_err err;
  fb_model *m = NULL;
  CHECK(fb_model_load_string(text, strlen(text), "bad.yaml", NULL, &m, &err) != FB_OK);
  CHECK(strstr(err.msg, want) != NULL);
  if (!strstr(err.msg, want))
    fprintf(stderr, "  got \"%s\", want \"%s\"\n", err.msg, want);
  fb_model_free(&m);
}

static void test_loader_keys(void)
{
  check_load_error(
      "model: m\nelements:\n  - {name: r, type: Sf, value: {road: {speed: 0, bump: "
      "{height: 0.1, length: 1}}}}\n",
      "bad.yaml:3:47: elements[0].value.road.speed: must be > 0 m/s (got 0)");
  check_load_error(
      "model: m\nelements:\n  - {name: r, type: Sf, value: {road: {speed: 1}}}\n",
      "elements[0].value.road: give exactly one of 'bump', 'iso8608', 'profile' or 'pieces'");
  check_load_error("model: m\nelements:\n  - {name: r, type: Sf, value: {road: {speed: 1, "
                   "pieces: [{line: [0, 1, 0.1]}]}}}\n",
                   "elements[0].value.road.pieces[0].line: expected 4 values");
  check_load_error("model: m\nelements:\n  - {name: r, type: Sf, value: {road: {speed: 1, "
                   "pieces: [{arc: [0, 1, 0.2, 0, 0.2]}]}}}\n",
                   "road pieces: left track, piece 1 leaves its circle");
  check_load_error("model: m\nelements:\n  - {name: r, type: Sf, value: {road: {speed: 1, "
                   "iso8608: {class: Q}}}}\n",
                   "ISO 8608 road class 'Q'");
  check_load_error("model: m\nelements:\n  - {name: k, type: contact, k: -1, damper: d}\n",
                   "bad.yaml:3:33: elements[0].k: must be > 0 (got -1)");
  check_load_error("model: m\nelements:\n  - {name: k, type: contact, k: 1, damper: k}\n",
                   "the damper needs a name of its own");
  check_load_error(
      "model: m\nelements:\n  - {name: M, type: I, m: 1, dim: 2}\n  - {name: j, "
      "type: 1, dim: 2}\nbonds: [[j, M, b]]\nprobes:\n  - {flow: b, weights: [1]}\n",
      "probes[0].weights: expected 2 values");
  check_load_error("model: m\nelements: []\nsimulation: {initial: warm}\n",
                   "simulation.initial: expected given, zero or static (got 'warm')");
  /* The solver check's key, located by the loader. */
  check_load_error("model: m\nelements: []\nsimulation:\n  rtol: 2\n",
                   "bad.yaml:4:9: simulation.rtol: must be in (0, 1), got 2");
  check_load_error("model: m\nelements: []\nsimulation: {t_end: 0}\n",
                   "simulation.t_end: must be finite and greater than t_start");
}

/* Without arguments every part but System 2; with "flexible" (CTest's
 * test_model_write_flexible) System 2 alone. */
int main(int argc, char **argv)
{
  if (argc > 1 && !strcmp(argv[1], "flexible")) {
    /* System 2 once, to 8.5 s: every wheel has crossed the bump by 8.1 s
     * (the last, right rear, meets it 16.8 + 2.1 m behind the start at
     * 2.78 m/s and leaves it 3.7 m later), and the full 15 s would double
     * the test's time. */
    vehicle_case("../examples/apc6x6.yaml", FB_SYSTEM_FLEXIBLE, "8.5");
    return check_report("test_model_write_flexible");
  }
  test_yaml_escape();
  test_loader_keys();
  test_every_kind();
  test_refusals();
  vehicle_case("../examples/apc6x6.yaml", FB_SYSTEM_RIGID, NULL);
  vehicle_case("../examples/apc6x6_liftoff.yaml", FB_SYSTEM_RIGID, NULL);
  vehicle_case("../examples/apc6x6_shock_table.yaml", FB_SYSTEM_RIGID, NULL);
  vehicle_case("../examples/apc6x6_iso_road.yaml", FB_SYSTEM_RIGID, NULL);
  vehicle_case("../examples/apc6x6_obstacles.yaml", FB_SYSTEM_RIGID, NULL);
  return check_report("test_model_write");
}
