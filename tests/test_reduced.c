/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of the reduced-structure readers and checks (flexbond/reduced.h).
 *
 * The reference structure is one free-free Euler-Bernoulli beam element
 * (two nodes, six DOFs each, consistent mass; Przemieniecki, "Theory of
 * Matrix Structural Analysis", 1968, ch. 5 and 11), written by the test
 * in each format. Its twelve modes have closed forms, derived in the
 * comment of beam_closed_form. Each format's file is read, checked, and
 * its generalized eigenproblem solved (fb_fem_modes), the frequencies
 * compared with the closed form within what the file's written digits
 * allow (first-order perturbation of the Rayleigh quotient, below). Bad
 * matrices are crafted files, each refused by the check it breaks, at its
 * file and line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"
#include "flexbond/reduced.h"

#include "check.h"
#include "tmpdir.h"

enum { N = 12 };
static const double TWO_PI = 6.28318530717958647692;

/* Steel, 2 m long, a 100 x 50 mm solid rectangle. */
static const double E = 2.1e11, NU = 0.3, RHO = 7850.0, LEN = 2.0, B = 0.1, H = 0.05;

typedef struct beam {
  double K[N * N], M[N * N]; /* column-major */
  double A, Iy, Iz, J, Ip, G;
} beam;

/* Hermite bending of the DOFs idx (w1, theta1, w2, theta2), theta =
 * sign * the DOF's rotation. */
static void add_bending(beam *b, const int idx[4], const double sign[4], double EI)
{
  const double L = LEN, k = EI / (L * L * L), m = RHO * b->A * L / 420.0;
  const double kb[16] = {12,  6 * L,  -12, 6 * L,  6 * L, 4 * L * L, -6 * L, 2 * L * L,
                         -12, -6 * L, 12,  -6 * L, 6 * L, 2 * L * L, -6 * L, 4 * L * L};
  const double mb[16] = {156, 22 * L, 54,  -13 * L, 22 * L,  4 * L * L,  13 * L,  -3 * L * L,
                         54,  13 * L, 156, -22 * L, -13 * L, -3 * L * L, -22 * L, 4 * L * L};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      b->K[idx[i] + idx[j] * N] += sign[i] * sign[j] * k * kb[i + 4 * j];
      b->M[idx[i] + idx[j] * N] += sign[i] * sign[j] * m * mb[i + 4 * j];
    }
}

/* Two DOFs of a bar-like pair: stiffness s [1 -1; -1 1], mass m/6 [2 1; 1 2]. */
static void add_pair(beam *b, int i, int j, double s, double m)
{
  b->K[i + i * N] += s;
  b->K[j + j * N] += s;
  b->K[i + j * N] -= s;
  b->K[j + i * N] -= s;
  b->M[i + i * N] += m / 3.0;
  b->M[j + j * N] += m / 3.0;
  b->M[i + j * N] += m / 6.0;
  b->M[j + i * N] += m / 6.0;
}

/* The beam along x from node 1 (origin) to node 2 (LEN, 0, 0); DOFs ux,
 * uy, uz, rx, ry, rz of node 1, then node 2's. Bending in xy takes
 * theta = rz, in xz theta = -ry. */
static void beam_make(beam *b)
{
  memset(b, 0, sizeof *b);
  b->A = B * H;
  b->Iz = H * B * B * B / 12.0;
  b->Iy = B * H * H * H / 12.0;
  b->Ip = b->Iy + b->Iz;
  b->J = 0.5 * b->Ip; /* any torsion constant: the closed form takes it as given */
  b->G = E / (2.0 * (1.0 + NU));
  add_pair(b, 0, 6, E * b->A / LEN, RHO * b->A * LEN);
  add_pair(b, 3, 9, b->G * b->J / LEN, RHO * b->Ip * LEN);
  add_bending(b, (const int[4]){1, 5, 7, 11}, (const double[4]){1, 1, 1, 1}, E * b->Iz);
  add_bending(b, (const int[4]){2, 4, 8, 10}, (const double[4]){1, -1, 1, -1}, E * b->Iy);
}

static int cmp_double(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* The twelve natural frequencies (Hz), ascending: six rigid-body modes at
 * 0; axial, omega^2 = 12 E / (rho L^2) (two DOFs: K = EA/L [1 -1; -1 1],
 * M = rho A L / 6 [2 1; 1 2], the antisymmetric vector); torsion,
 * 12 G J / (rho Ip L^2) alike; and in each bending plane the symmetric
 * mode (v, theta, v, -theta), reduced to K_s = EI/L^3 [0 0; 0 4 L^2],
 * M_s = rho A L / 420 [420 70 L; 70 L 14 L^2]: omega^2 = 720 EI /
 * (rho A L^4); the antisymmetric one (v, theta, -v, theta), K_a = EI/L^3
 * [48 24 L; 24 L 12 L^2], M_a = rho A L / 420 [204 18 L; 18 L 2 L^2]:
 * det = 84 mu^2 - 1680 mu, mu = 20, omega^2 = 8400 EI / (rho A L^4). */
static void beam_closed_form(const beam *b, double *f)
{
  const double L = LEN, L2 = L * L, L4 = L2 * L2;
  const double w2[6] = {12.0 * E / (RHO * L2),
                        12.0 * b->G * b->J / (RHO * b->Ip * L2),
                        720.0 * E * b->Iz / (RHO * b->A * L4),
                        8400.0 * E * b->Iz / (RHO * b->A * L4),
                        720.0 * E * b->Iy / (RHO * b->A * L4),
                        8400.0 * E * b->Iy / (RHO * b->A * L4)};
  for (int i = 0; i < 6; ++i) {
    f[i] = 0.0;
    f[6 + i] = sqrt(w2[i]) / TWO_PI;
  }
  qsort(f, N, sizeof *f, cmp_double);
}

/* The relative error of each elastic eigenvalue that entries rounded to
 * relative p can make, to first order (the Rayleigh quotient's change,
 * x' dK x / x' K x - x' dM x / x' M x, |dK_ij| <= p |K_ij|): p (x'|K|x /
 * x'Kx + x'|M|x / x'Mx), |x| taken entrywise, for the exact modes x. */
static double rounding_bound(const beam *b, const double *x, double p)
{
  double num_k = 0, den_k = 0, num_m = 0, den_m = 0;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      num_k += fabs(x[i]) * fabs(b->K[i + j * N]) * fabs(x[j]);
      den_k += x[i] * b->K[i + j * N] * x[j];
      num_m += fabs(x[i]) * fabs(b->M[i + j * N]) * fabs(x[j]);
      den_m += x[i] * b->M[i + j * N] * x[j];
    }
  return p * (num_k / den_k + num_m / den_m);
}

static const char *tmp(const char *name)
{
  static char buf[8][TEST_PATH_MAX];
  static int k;
  k = (k + 1) % 8;
  return test_tmp_path(name, buf[k], sizeof buf[k]);
}

static void write_text(const char *path, const char *text)
{
  FILE *fp = fopen(path, "w");
  if (!fp) {
    perror(path);
    exit(1);
  }
  fputs(text, fp);
  fclose(fp);
}

/* v in 8 columns the way Nastran writes small fields: the most digits
 * that fit, the exponent's letter left out ("-1.234+5"). */
static void nastran8(double v, char *out)
{
  for (int d = 7; d >= 0; --d) {
    char tmpb[32], mant[48];
    snprintf(tmpb, sizeof tmpb, "%.*e", d, v);
    char *e = strchr(tmpb, 'e');
    *e = '\0';
    snprintf(mant, sizeof mant, "%s%c%d", tmpb, e[1], abs(atoi(e + 1)));
    if (strlen(mant) <= 8) {
      strcpy(out, mant);
      return;
    }
  }
  strcpy(out, "0.");
}

typedef enum dmig_form { SMALL, LARGE, FREE } dmig_form;

static const char *form_name[3] = {"small field", "large field", "free field"};

/* A DMIG matrix: the header, then a column entry per column with its
 * rows (symmetric: the upper triangle, rows <= column). */
/* DOF i's grid and component: the beam's, two nodes of six. */
typedef struct dof_map {
  int n;
  long grid[64];
  int comp[64];
} dof_map;

static dof_map beam_map(void)
{
  dof_map m = {.n = N};
  for (int i = 0; i < N; ++i) {
    m.grid[i] = 1 + i / 6;
    m.comp[i] = 1 + i % 6;
  }
  return m;
}

static void write_dmig_map(FILE *fp, dmig_form form, const char *name, const double *a, int ifo,
                           const dof_map *map)
{
  const int n = map->n;
  if (form == SMALL)
    fprintf(fp, "DMIG    %-8s0       %-8d2\n", name, ifo);
  else if (form == LARGE)
    fprintf(fp, "DMIG*   %-16s%16d%16d%16d\n*       %16d\n", name, 0, ifo, 2, 0);
  else
    fprintf(fp, "DMIG,%s,0,%d,2,0\n", name, ifo);
  for (int j = 0; j < n; ++j) {
    const long gj = map->grid[j];
    const int cj = map->comp[j];
    if (form == SMALL)
      fprintf(fp, "DMIG    %-8s%-8ld%-8d", name, gj, cj);
    else if (form == LARGE)
      fprintf(fp, "DMIG*   %-16s%16ld%16d\n", name, gj, cj);
    else
      fprintf(fp, "DMIG,%s,%ld,%d,", name, gj, cj);
    int slot = 0; /* small field: groups on the line so far (1 on the first) */
    for (int i = 0; i < (ifo == 6 ? j + 1 : n); ++i) {
      const double v = a[i + j * n];
      if (v == 0.0)
        continue;
      const long gi = map->grid[i];
      const int ci = map->comp[i];
      if (form == SMALL) {
        char num[16];
        nastran8(v, num);
        if (slot == 0)
          fprintf(fp, "        %-8ld%-8d%-8s\n", gi, ci, num);
        else
          fprintf(fp, "+       %-8ld%-8d%-8s\n", gi, ci, num);
        ++slot;
      } else if (form == LARGE) {
        char num[32];
        snprintf(num, sizeof num, "%16.9E", v);
        *strchr(num, 'E') = 'D';
        fprintf(fp, "*       %16ld%16d%16s\n", gi, ci, num);
      } else {
        /* Every digit a double has, with its sign: 24 or 25 characters. */
        fprintf(fp, ",%ld,%d,%+.17e\n", gi, ci, v);
        ++slot;
      }
    }
    if (form != LARGE && slot == 0)
      fprintf(fp, "\n");
  }
}

static void write_dmig(FILE *fp, dmig_form form, const char *name, const double *a, int ifo)
{
  const dof_map map = beam_map();
  write_dmig_map(fp, form, name, a, ifo, &map);
}

static const char beam_nodes[] = "# the beam's two nodes\n1, 0, 0, 0\n2, 2, 0, 0\n";

/* Reads the beam in one format and compares its frequencies. */
static void check_beam_modes(const beam *b, const fb_reduced *r, double p, const char *what)
{
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_reduced_ndofs(r) == N);
  CHECK(fb_reduced_check(r, &err) == FB_OK);
  if (err.code)
    fprintf(stderr, "%s: %s\n", what, err.msg);
  double f[N], exact[N], x[N * N];
  beam_closed_form(b, exact);
  /* Rigid-body motions made exact: a file's rounding leaves them an
   * energy of its precision, which an 8-column file makes a negative
   * eigenvalue (fb_reduced_stiffness_projected). An exact K is unchanged
   * by it: the free-field file's to 1e-12 of its largest entry. */
  fb_mat *Kp = NULL;
  CHECK(fb_reduced_stiffness_projected(r, &Kp, &err) == FB_OK);
  if (!Kp)
    return;
  if (p < 1e-15) {
    double diff = 0.0, big = 0.0;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) {
        const double k0 = fb_mat_get(fb_reduced_stiffness(r), (size_t)i, (size_t)j);
        diff = fmax(diff, fabs(fb_mat_get(Kp, (size_t)i, (size_t)j) - k0));
        big = fmax(big, fabs(k0));
      }
    CHECK(diff <= 1e-12 * big);
  }
  const int rc = fb_fem_modes(Kp, fb_reduced_mass(r), N, NULL, f, x, &err);
  fb_mat_free(&Kp);
  CHECK(rc == FB_OK);
  if (rc) {
    fprintf(stderr, "%s: %s\n", what, err.msg);
    return;
  }
  /* The exact modes of the exact matrices, for the rounding bound. */
  double xe[N * N], fe[N];
  fb_mat *Ke = NULL, *Me = NULL;
  fb_mat_new_dense(N, N, b->K, &Ke, &err);
  fb_mat_new_dense(N, N, b->M, &Me, &err);
  CHECK(fb_fem_modes(Ke, Me, N, NULL, fe, xe, &err) == FB_OK);
  fb_mat_free(&Ke);
  fb_mat_free(&Me);
  double worst = 0.0;
  for (int i = 0; i < N; ++i) {
    if (exact[i] == 0.0) {
      /* Rigid: round-off of the scale sqrt(K/M), well below 1e-3 Hz
       * (the first elastic mode is 30 Hz). */
      CHECK(f[i] < 1e-3);
      continue;
    }
    /* Eigenvalue bound halved for the frequency, doubled for safety (a
     * first-order bound), plus the solver's 1e-9. */
    const double tol = rounding_bound(b, xe + (size_t)i * N, p) + 1e-9;
    const double rel = fabs(f[i] - exact[i]) / exact[i];
    if (rel > worst)
      worst = rel;
    CHECK_NEAR(f[i], exact[i], tol * exact[i]);
  }
  fprintf(stderr, "%s: largest relative frequency error %.3g\n", what, worst);
}

static void test_dmig_beam(void)
{
  beam b;
  beam_make(&b);
  const char *nodes = tmp("beam_nodes.csv");
  write_text(nodes, beam_nodes);
  /* Digits each form writes: 4 at least in 8 columns, 10 in "%16.9E",
   * 17 in "%+.17e". */
  const double precision[3] = {5e-4, 5e-10, 5e-17};
  for (int form = SMALL; form <= FREE; ++form) {
    const char *path = tmp("beam.pch");
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (!fp)
      return;
    fprintf(fp, "$ a free-free beam element, %s\nBEGIN BULK\n", form_name[form]);
    write_dmig(fp, (dmig_form)form, "KAAX", b.K, 6);
    /* The mass as a square matrix (IFO 1) in one of the forms. */
    write_dmig(fp, (dmig_form)form, "MAAX", b.M, form == LARGE ? 1 : 6);
    fprintf(fp, "ENDDATA\n");
    fclose(fp);
    fb_reduced *r = NULL;
    fb_err err;
    fb_err_clear(&err);
    const int rc = fb_reduced_read_dmig(path, "KAAX", "MAAX", nodes, &r, &err);
    CHECK(rc == FB_OK);
    if (rc) {
      fprintf(stderr, "%s: %s\n", form_name[form], err.msg);
      continue;
    }
    CHECK(fb_reduced_find_dof(r, 2, 6) == 11);
    CHECK(fb_reduced_node_xyz(r, 1)[0] == 2.0);
    check_beam_modes(&b, r, precision[form], form_name[form]);
    fb_reduced_free(&r);
  }
}

static void test_mtx_beam(void)
{
  beam b;
  beam_make(&b);
  fb_err err;
  fb_err_clear(&err);
  fb_mat *K = NULL, *M = NULL;
  fb_mat_new_dense(N, N, b.K, &K, &err);
  fb_mat_new_dense(N, N, b.M, &M, &err);
  const char *kp = tmp("K.mtx"), *mp = tmp("M.mtx"), *np = tmp("mtx_nodes.csv");
  CHECK(fb_mat_write_mtx(K, kp, &err) == FB_OK);
  CHECK(fb_mat_write_mtx(M, mp, &err) == FB_OK);
  fb_mat_free(&K);
  fb_mat_free(&M);
  write_text(np, "1, 0, 0, 0, 123456\n2, 2.0, 0, 0, 654321\n");
  fb_reduced *r = NULL;
  CHECK(fb_reduced_read_mtx(kp, mp, np, &r, &err) == FB_OK);
  if (r) {
    check_beam_modes(&b, r, 5e-17, "Matrix Market");
    fb_reduced_free(&r);
  }
  /* A nodes file of 2 translations-only nodes: 6 rows, not 12. */
  write_text(np, "1, 0, 0, 0, 123\n2, 2.0, 0, 0, 123\n");
  CHECK(fb_reduced_read_mtx(kp, mp, np, &r, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "K.mtx:2: the matrix has 12 rows, expected 6") != NULL);
  write_text(np, "1, 0, 0, 0, 123\n2, 2.0, 0, 0, 1237\n");
  CHECK(fb_reduced_read_mtx(kp, mp, np, &r, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "mtx_nodes.csv:2: components") != NULL);
}

/* The beam in CalculiX's layout: one DOF per element node, the lower
 * triangle row by row, four numbers a line, as ccx 2.20 writes it. */
static void write_ccx(const char *path, const double *a, int truncate)
{
  FILE *fp = fopen(path, "w");
  if (!fp)
    return;
  fprintf(fp,
          "**\n** GENERATION OF SUBSTRUCTURE\n*USER ELEMENT,NODES=%10d,LINEAR\n"
          "** ELEMENT NODES\n**",
          N);
  for (int i = 0; i < N; ++i)
    fprintf(fp, "%10d,%s", 1 + i / 6, i == 9 ? "\n**" : "");
  fprintf(fp, "\n%10d\n", 1);
  for (int i = 1; i < N; ++i)
    fprintf(fp, "%10d,%10d\n", i + 1, 1 + i % 6);
  fprintf(fp, "*MATRIX,TYPE=STIFFNESS\n");
  int count = 0;
  for (int i = 0; i < N - truncate; ++i) {
    for (int j = 0; j <= i; ++j) {
      fprintf(fp, "% .13E,", a[i + j * N]);
      if (++count % 4 == 0 && j < i)
        fprintf(fp, "\n");
    }
    fprintf(fp, "\n");
    count = 0;
  }
  fclose(fp);
}

static void test_ccx_layout(void)
{
  beam b;
  beam_make(&b);
  const char *path = tmp("beam_ccx.mtx"), *nodes = tmp("beam_nodes.csv");
  write_text(nodes, beam_nodes);
  write_ccx(path, b.K, 0);
  fb_reduced *r = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_reduced_read_ccx(path, nodes, &r, &err) == FB_OK);
  if (r) {
    CHECK(fb_reduced_ndofs(r) == N);
    CHECK(fb_reduced_mass(r) == NULL);
    /* 14 significant digits: each entry to 5e-14 of itself. */
    double worst = 0.0;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) {
        const double ref = b.K[i + j * N];
        const double got = fb_mat_get(fb_reduced_stiffness(r), (size_t)i, (size_t)j);
        const double rel = fabs(got - ref) / (fabs(ref) > 0 ? fabs(ref) : 1.0);
        worst = rel > worst ? rel : worst;
      }
    CHECK(worst <= 5e-14);
    CHECK(fb_reduced_check(r, &err) == FB_OK);
    fb_reduced_free(&r);
  }
  write_ccx(path, b.K, 1);
  CHECK(fb_reduced_read_ccx(path, nodes, &r, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "beam_ccx.mtx:40: the matrix ends after 66 of its 78") != NULL);
}

/* Reads path as DMIG K (and M, when m is not NULL) and expects its
 * reading or its check to fail with FB_EMODEL or FB_EPARSE, the message
 * holding want. */
static void expect_bad(const char *text, const char *nodes_text, int with_mass,
                       const char *want)
{
  const char *path = tmp("bad.pch"), *nodes = tmp("bad_nodes.csv");
  write_text(path, text);
  write_text(nodes, nodes_text);
  fb_reduced *r = NULL;
  fb_err err;
  fb_err_clear(&err);
  int rc = fb_reduced_read_dmig(path, "K", with_mass ? "M" : NULL, nodes, &r, &err);
  if (!rc)
    rc = fb_reduced_check(r, &err);
  fb_reduced_free(&r);
  CHECK(rc == FB_EMODEL || rc == FB_EPARSE);
  CHECK(strstr(err.msg, want) != NULL);
  if (!strstr(err.msg, want))
    fprintf(stderr, "  expected '%s' in: %s\n", want, err.msg);
}

/* The beam's K (and M) in free field with one extra text after. */
static char *beam_dmig(const beam *b, int with_mass)
{
  char *buf = NULL;
  size_t len = 0;
  FILE *fp = open_memstream(&buf, &len);
  write_dmig(fp, FREE, "K", b->K, 6);
  if (with_mass)
    write_dmig(fp, FREE, "M", b->M, 6);
  fclose(fp);
  return buf;
}

/* Two bars from the beam's ends to node 3 at (1, 1, 1): node 3 may move
 * along (0, -1, 1), perpendicular to both, without energy. */
static void add_bars(double *K, int n)
{
  const double d[2][3] = {{1, 1, 1}, {-1, 1, 1}};
  const int from[2] = {0, 6};
  const double k = 1e8;
  for (int bar = 0; bar < 2; ++bar)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double v = k * d[bar][i] * d[bar][j] / 3.0;
        const int a = from[bar] + i, c = from[bar] + j, p = 12 + i, q = 12 + j;
        K[a + c * n] += v;
        K[p + q * n] += v;
        K[a + q * n] -= v;
        K[p + c * n] -= v;
      }
}

static void test_bad(void)
{
  beam b;
  beam_make(&b);
  /* Not symmetric: a square K whose (1, 2) differs from (2, 1). */
  expect_bad("DMIG,K,0,1,2,0\nDMIG,K,1,1,,1,1,1.0+3\n,2,1,-1.0+3\n"
             "DMIG,K,2,1,,1,1,-1.1+3\n,2,1,1.0+3\n",
             beam_nodes, 0, "bad.pch:3: K is not symmetric");
  /* An entry and its mirror in a symmetric matrix. */
  expect_bad("DMIG,K,0,6,2,0\nDMIG,K,1,1,,1,1,1.0+3\n,2,1,-1.0+3\n"
             "DMIG,K,2,1,,1,1,-1.0+3\n,2,1,1.0+3\n",
             beam_nodes, 0,
             "bad.pch:4: K: entry (node 2 component 1, node 1 component 1) given "
             "again (first on line 3)");
  /* A node that is not in the nodes file. */
  expect_bad("DMIG,K,0,6,2,0\nDMIG,K,1,1,,1,1,1.0+3\nDMIG,K,7,3,,7,3,1.0+3\n", beam_nodes, 0,
             "bad.pch:3: K: node 7 is not among the interface nodes");
  /* Scalar points, complex and rectangular matrices are not read. */
  expect_bad("DMIG,K,0,6,2,0\nDMIG,K,1,0,,1,1,1.0\n", beam_nodes, 0, "bad.pch:2: component");
  expect_bad("DMIG,K,0,6,3,0\n", beam_nodes, 0, "bad.pch:1: TIN");
  expect_bad("DMIG,K,0,9,2,2\n", beam_nodes, 0, "bad.pch:1: IFO");
  expect_bad("DMIG    K       0       6       2\nDMIG    K       1       1               "
             "1       1       1.x+3\n",
             beam_nodes, 0, "bad.pch:2: value: not a number");
  expect_bad("DMIG,K,0,6,2,0\n", beam_nodes, 1, "no DMIG matrix named M");
  /* A field longer than any number is refused at its line, not cut. */
  expect_bad("DMIG,K,0,6,2,0\nDMIG,K,1,1,,1,1,1.000000000000000000000000000000000000000000000"
             "000000000000000000000000001\n",
             beam_nodes, 0, "bad.pch:2: a field of 74 characters, longer than any number");

  char *text = NULL;
  beam bad;
  /* A grounded spring: node 1's ux held. */
  bad = b;
  bad.K[0] += 1e6;
  text = beam_dmig(&bad, 0);
  expect_bad(text, beam_nodes, 0, "K is not free-free: its translation along x has energy");
  free(text);
  /* A mass that is not semi-definite (a coupling larger than the
   * diagonal). */
  bad = b;
  bad.M[3 + 9 * N] = bad.M[9 + 3 * N] = 10.0 * bad.M[3 + 3 * N];
  text = beam_dmig(&bad, 1);
  expect_bad(text, beam_nodes, 1, "M is not positive semi-definite");
  free(text);
  /* The negative mass at its line: column 3's entry, on the line of
   * its column entry (rows 1 and 2 of column 3 are zero). */
  bad = b;
  bad.M[2 + 2 * N] = -1.0;
  text = beam_dmig(&bad, 1);
  {
    int line = 1, at = 0;
    for (const char *p = text; *p; ++p) {
      if (!strncmp(p, "DMIG,M,1,3,", 11))
        at = line;
      line += *p == '\n';
    }
    char want[128];
    snprintf(want, sizeof want,
             "bad.pch:%d: M(node 1 uz, node 1 uz) = -1: a mass must not be "
             "negative",
             at);
    expect_bad(text, beam_nodes, 1, want);
  }
  free(text);
  /* A mechanism: node 3 on two bars. */
  {
    enum { N3 = 15 };
    double K3[N3 * N3] = {0};
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j)
        K3[i + j * N3] = b.K[i + j * N];
    add_bars(K3, N3);
    char *buf = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&buf, &len);
    fprintf(fp, "DMIG,K,0,6,2,0\n");
    for (int j = 0; j < N3; ++j) {
      const int gj = j < 12 ? 1 + j / 6 : 3, cj = j < 12 ? 1 + j % 6 : 1 + j - 12;
      fprintf(fp, "DMIG,K,%d,%d,\n", gj, cj);
      for (int i = 0; i <= j; ++i)
        if (K3[i + j * N3] != 0.0)
          fprintf(fp, ",%d,%d,%.17g\n", i < 12 ? 1 + i / 6 : 3, i < 12 ? 1 + i % 6 : 1 + i - 12,
                  K3[i + j * N3]);
    }
    fclose(fp);
    expect_bad(buf, "1, 0, 0, 0\n2, 2, 0, 0\n3, 1, 1, 1\n", 0,
               "K has 1 zero-energy mode besides its 6 rigid-body motions (a mechanism or a "
               "DOF without stiffness, largest at node 3 u");
    free(buf);
  }
}

/* A superelement of flexbond's own making: a flat 1.2 x 0.8 m steel
 * plate of 8 x 6 S4 shells (5 mm), condensed by the test onto the
 * translations of four nodes (Guyan, "Reduction of stiffness and mass
 * matrices", AIAA J. 3(2), 1965: K_rr - K_ro K_oo^-1 K_or, and the mass
 * through T = [I; -K_oo^-1 K_or]), written as large-field DMIG, read and
 * checked: six rigid-body modes to the file's precision, no others. Then
 * a load at a retained DOF, the plate held statically determinately at
 * three retained nodes: the full model's displacements at the retained
 * DOFs and the file's reduced model's agree (Guyan is exact for loads at
 * retained DOFs), to the file's ten digits times the condition of the
 * supported K_red (measured: below 1e-8). */
enum { PX = 8, PY = 6, NR = 12 };

static long plate_id(int i, int j)
{
  return 1 + i + (PX + 1) * j;
}

/* In increasing node id. */
static const int plate_ret[4][2] = {{0, 0}, {PX, 0}, {PX / 2, PY / 2}, {PX, PY}};

/* Solves the symmetric positive definite rows keep[0 .. nk) of a (dense,
 * n x n) for the right-hand side b in place. */
static int solve_kept(const fb_mat *a, const size_t *keep, size_t nk, double *b, fb_err *err)
{
  fb_mat *sub = NULL;
  fb_chol *c = NULL;
  int rc = fb_fem_submatrix(a, keep, nk, &sub, err);
  if (!rc)
    rc = fb_chol_new(sub, 0, &c, err);
  if (!rc)
    rc = fb_chol_solve(c, b, 1, err);
  fb_chol_free(&c);
  fb_mat_free(&sub);
  return rc;
}

static void test_shell_guyan(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_mesh *m = NULL;
  CHECK(fb_mesh_new(&m, &err) == FB_OK);
  for (int j = 0; j <= PY; ++j)
    for (int i = 0; i <= PX; ++i)
      CHECK(fb_mesh_add_node(m, plate_id(i, j), 1.2 * i / PX, 0.8 * j / PY, 0.0, NULL, &err) ==
            FB_OK);
  for (int j = 0; j < PY; ++j)
    for (int i = 0; i < PX; ++i) {
      const size_t q[4] = {(size_t)(plate_id(i, j) - 1), (size_t)(plate_id(i + 1, j) - 1),
                           (size_t)(plate_id(i + 1, j + 1) - 1),
                           (size_t)(plate_id(i, j + 1) - 1)};
      CHECK(fb_mesh_add_element(m, 1 + i + PX * j, FB_ELEM_QUAD4, q, &err) == FB_OK);
    }
  const fb_shell_props props = {
      .young = 2.1e11, .poisson = 0.3, .density = 7850, .thickness = 0.005};
  fb_mat *K = NULL, *M = NULL;
  CHECK(fb_fem_assemble(m, &props, FB_MASS_CONSISTENT, &K, &M, &err) == FB_OK);
  const size_t n = 6 * fb_mesh_nnodes(m);
  size_t ret[NR], *other = malloc(n * sizeof *other);
  dof_map map = {.n = NR};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 3; ++c) {
      const long id = plate_id(plate_ret[r][0], plate_ret[r][1]);
      ret[3 * r + c] = 6 * (size_t)(id - 1) + (size_t)c;
      map.grid[3 * r + c] = id;
      map.comp[3 * r + c] = c + 1;
    }
  size_t no = 0;
  for (size_t d = 0, k = 0; d < n; ++d) {
    if (k < NR && ret[k] == d)
      ++k;
    else
      other[no++] = d;
  }
  /* X = K_oo^-1 K_or, column by column. */
  double *X = calloc(no * NR, sizeof *X), *col = malloc(n * sizeof *col);
  double kred[NR * NR], mred[NR * NR];
  for (int c = 0; c < NR && !err.code; ++c) {
    for (size_t i = 0; i < no; ++i)
      X[i + no * (size_t)c] = fb_mat_get(K, other[i], ret[c]);
    CHECK(solve_kept(K, other, no, X + no * (size_t)c, &err) == FB_OK);
  }
  /* T's columns: e_c at the retained DOFs, -X at the others. */
  double *T = calloc(n * NR, sizeof *T), *KT = malloc(n * sizeof *KT);
  for (int c = 0; c < NR; ++c) {
    T[ret[c] + n * (size_t)c] = 1.0;
    for (size_t i = 0; i < no; ++i)
      T[other[i] + n * (size_t)c] = -X[i + no * (size_t)c];
  }
  for (int b = 0; b < NR; ++b)
    for (int pass = 0; pass < 2; ++pass) {
      fb_mat_gemv(pass ? M : K, 1.0, T + n * (size_t)b, 0.0, KT);
      for (int a = 0; a < NR; ++a) {
        double sum = 0.0;
        for (size_t i = 0; i < n; ++i)
          sum += T[i + n * (size_t)a] * KT[i];
        (pass ? mred : kred)[a + NR * b] = sum;
      }
    }
  const char *path = tmp("plate.pch"), *nodes = tmp("plate_nodes.csv");
  FILE *fp = fopen(path, "w");
  if (fp) {
    write_dmig_map(fp, LARGE, "KAAX", kred, 6, &map);
    write_dmig_map(fp, LARGE, "MAAX", mred, 6, &map);
    fclose(fp);
  }
  fp = fopen(nodes, "w");
  if (fp) {
    for (int r = 0; r < 4; ++r)
      fprintf(fp, "%ld, %.17g, %.17g, 0\n", plate_id(plate_ret[r][0], plate_ret[r][1]),
              1.2 * plate_ret[r][0] / PX, 0.8 * plate_ret[r][1] / PY);
    fclose(fp);
  }
  fb_reduced *r = NULL;
  CHECK(fb_reduced_read_dmig(path, "KAAX", "MAAX", nodes, &r, &err) == FB_OK);
  if (r) {
    CHECK(fb_reduced_check(r, &err) == FB_OK);
    if (err.code)
      fprintf(stderr, "plate: %s\n", err.msg);
    /* Held at node 1 (x, y, z), node 9 (y, z) and the centre node 32 (z);
     * 1 kN down at the far corner, node 63. */
    const size_t held_red[6] = {0, 1, 2, 4, 5, 8};
    size_t keep_red[NR - 6], nkr = 0;
    for (size_t d = 0, k = 0; d < NR; ++d) {
      if (k < 6 && held_red[k] == d)
        ++k;
      else
        keep_red[nkr++] = d;
    }
    size_t held_full[6], *keep_full = malloc(n * sizeof *keep_full);
    for (int k = 0; k < 6; ++k)
      held_full[k] = ret[held_red[k]];
    CHECK(fb_fem_free_dofs(n, held_full, 6, keep_full, &err) == FB_OK);
    double ured[NR - 6] = {0}, *ufull = calloc(n, sizeof *ufull);
    for (size_t k = 0; k < nkr; ++k)
      ured[k] = keep_red[k] == 11 ? -1000.0 : 0.0;
    for (size_t k = 0; k < n - 6; ++k)
      ufull[k] = keep_full[k] == ret[11] ? -1000.0 : 0.0;
    CHECK(solve_kept(fb_reduced_stiffness(r), keep_red, nkr, ured, &err) == FB_OK);
    CHECK(solve_kept(K, keep_full, n - 6, ufull, &err) == FB_OK);
    double worst = 0.0, big = 0.0;
    for (size_t k = 0; k < nkr; ++k) {
      size_t at = 0;
      while (keep_full[at] != ret[keep_red[k]])
        ++at;
      worst = fmax(worst, fabs(ured[k] - ufull[at]));
      big = fmax(big, fabs(ufull[at]));
    }
    CHECK(worst <= 1e-8 * big);
    fprintf(stderr, "plate: Guyan static at the retained DOFs, full vs DMIG: %.3g of %.3g m\n",
            worst, big);
    free(keep_full);
    free(ufull);
    fb_reduced_free(&r);
  } else {
    fprintf(stderr, "plate: %s\n", err.msg);
  }
  free(T);
  free(KT);
  free(X);
  free(col);
  free(other);
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mesh_free(&m);
}

/* The bounds (docs/errors.md, "Limits"): 3000 DOFs, and a CalculiX
 * NODES= the file cannot hold, refused before its arrays are made. */
static void test_limits(void)
{
  const char *path = tmp("big.pch"), *nodes = tmp("big_nodes.csv");
  FILE *fp = fopen(path, "w"), *np = fopen(nodes, "w");
  CHECK(fp && np);
  if (!fp || !np)
    return;
  fprintf(fp, "DMIG,K,0,6,2,0\n");
  for (int g = 1; g <= 501; ++g) {
    fprintf(np, "%d, %d, 0, 0\n", g, g);
    for (int c = 1; c <= 6; ++c)
      fprintf(fp, "DMIG,K,%d,%d,,%d,%d,1.0\n", g, c, g, c);
  }
  fclose(fp);
  fclose(np);
  fb_reduced *r = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_reduced_read_dmig(path, "K", NULL, nodes, &r, &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "big.pch: 3006 DOFs, more than the 3000") != NULL);
  const char *ccx = tmp("big_ccx.mtx");
  write_text(ccx, "*USER ELEMENT,NODES=  2000,LINEAR\n** ELEMENT NODES\n**  1,\n");
  CHECK(fb_reduced_read_ccx(ccx, nodes, &r, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "big_ccx.mtx:1: *USER ELEMENT: NODES= gives a matrix larger than the "
                        "file can hold") != NULL);
  write_text(ccx, "*USER ELEMENT,NODES=  4000,LINEAR\n");
  CHECK(fb_reduced_read_ccx(ccx, nodes, &r, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "more nodes than the 3000 DOFs") != NULL);
  CHECK(r == NULL);
  /* Two nodes have 12 DOFs at most, so 144 entries: the 145th (line 146)
   * is refused while read, however long the file. */
  fp = fopen(path, "w");
  if (!fp)
    return;
  fprintf(fp, "DMIG,K,0,1,2,0\n");
  for (int e = 0; e < 200; ++e)
    fprintf(fp, "DMIG,K,1,1,,1,1,1.0\n");
  fclose(fp);
  CHECK(fb_reduced_read_dmig(path, "K", NULL, "data/reduced/beam_nodes.csv", &r, &err) ==
        FB_EPARSE);
  CHECK(strstr(err.msg, "big.pch:146: K: more than the 144 entries") != NULL);
  /* A node given twice, at its second line. */
  write_text(nodes, "1, 0, 0, 0\n2, 1, 0, 0\n# again\n1, 2, 0, 0\n");
  CHECK(fb_reduced_read_dmig(path, "K", NULL, nodes, &r, &err) == FB_EPARSE);
  CHECK(strstr(err.msg, "big_nodes.csv:4: node 1 given twice (first on line 1)") != NULL);
}

/* The fixture data/reduced/beam.pch: the same element with exact values
 * chosen by hand (L = 1 m, EA = 1e6 N, GJ = EI = 1e4 N m^2, rho A L =
 * 420 kg, rho Ip L = 42 kg m^2), in 8-column fields. Its frequencies:
 * 12 EA / (m L), 12 GJ / (I L), 720 and 8400 EI / (m L^3) (m = rho A L,
 * I = rho Ip L; beam_closed_form's with these values), to the solver's
 * 1e-9: every number of the file is exact. */
static void test_fixture_beam(void)
{
  fb_reduced *r = NULL;
  fb_err err;
  fb_err_clear(&err);
  CHECK(fb_reduced_read_dmig("data/reduced/beam.pch", "KBEAM", "MBEAM",
                             "data/reduced/beam_nodes.csv", &r, &err) == FB_OK);
  if (!r) {
    fprintf(stderr, "fixture: %s\n", err.msg);
    return;
  }
  CHECK(fb_reduced_check(r, &err) == FB_OK);
  const double w2[6] = {12e6 / 420,  12e4 / 42,    720e4 / 420,
                        720e4 / 420, 8400e4 / 420, 8400e4 / 420};
  double exact[N], f[N];
  for (int i = 0; i < 6; ++i) {
    exact[i] = 0.0;
    exact[6 + i] = sqrt(w2[i]) / TWO_PI;
  }
  qsort(exact, N, sizeof *exact, cmp_double);
  CHECK(fb_fem_modes(fb_reduced_stiffness(r), fb_reduced_mass(r), N, NULL, f, NULL, &err) ==
        FB_OK);
  for (int i = 0; i < N; ++i) {
    if (exact[i] == 0.0)
      CHECK(f[i] < 1e-3);
    else
      CHECK_NEAR(f[i], exact[i], 1e-9 * exact[i]);
  }
  fb_reduced_free(&r);
}

int main(void)
{
  test_fixture_beam();
  test_dmig_beam();
  test_mtx_beam();
  test_ccx_layout();
  test_shell_guyan();
  test_limits();
  test_bad();
  return check_report("test_reduced");
}
