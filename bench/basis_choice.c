/* SPDX-License-Identifier: BSD-3-Clause */
/* Work-precision study of the reduced basis of System 2's finite-element
 * hull, which chose the library's (src/vehicle/hull_model.c,
 * hull.fe.modes: auto) among
 *   modes          the free-free modes alone (truncation);
 *   modes_static   the modes plus a static (residual-flexibility)
 *                  correction for every attachment, load and output
 *                  pattern (fb_fem_modal_basis with order 1; MacNeal,
 *                  Comput. Struct. 1, 1971);
 *   ritz           load-dependent Ritz vectors (E. L. Wilson, M.-W. Yuan
 *                  & J. M. Dickens, "Dynamic analysis by direct
 *                  superposition of Ritz vectors", Earthq. Eng. Struct.
 *                  Dyn. 10, 1982): only the rigid-body modes kept and
 *                  1, 2, 3 ... blocks of the Krylov sequence K^+ M u
 *                  started from the patterns (fb_fem_modal_basis, order):
 *                  the library's choice;
 *   craig_bampton  R. R. Craig & M. C. C. Bampton, "Coupling of
 *                  substructures for dynamic analyses", AIAA J. 6(7),
 *                  1968: a constraint mode per interface DOF (the hull's
 *                  static shape for a unit displacement there, the other
 *                  interface DOFs held) plus the lowest normal modes of
 *                  the hull with its interface held.
 *   modes_3fexc    modes up to 3 x f_exc with the static correction, the
 *                  rule the study was first made to check, as a marker
 *                  on the modes_static curve;
 *   library        the library's basis for the scenario (as many Ritz
 *                  blocks as FB_HULL_BLOCK_TOL asks for, read from the
 *                  realised vehicle), as a marker on the ritz curve.
 *
 * Precision: the hull alone, damped as the vehicle damps it (B = beta K,
 * beta = 2 zeta / omega_1 of its first elastic free-free mode), driven by
 * the patterns that are forces (each attachment point's, the load) and
 * observed through every pattern (attachment and load displacements, the
 * torsion angles): the receptance H(w) = F' (K + i w beta K - w^2 M)^-1
 * F_forces on NFREQ frequencies evenly spaced from F_LOW_HZ to f_exc, the
 * highest frequency that reaches the hull. The reference is the modal
 * superposition over every mode of a dense eigen-solve, exact for this
 * proportional damping (a rigid-body mode's term is -1/w^2: finite for
 * w > 0; the rigid-body modes are the exact motions, see exact_rigid).
 * A basis T (ndof x m) gives H_red = F'T (Kr + i w beta Kr - w^2 Mr)^-1
 * T'F_forces with Kr = T'KT and Mr = T'MT; its error is the largest
 * |H_red - H_ref| over entries and frequencies, each entry's divided by
 * that entry's largest |H_ref| over the frequencies. Entries that are 0
 * are left out: those whose largest |H_ref| is below ZERO_REL of their
 * row's (the same output's) largest, which symmetry makes 0 and round-off
 * does not (the torsion under the load, symmetric about the hull's
 * centre line: 5e-6 of the torsion row at density 1, 2e-5 at density 2,
 * against 2e-4 for the smallest entry that is not 0). Work: m, the
 * coordinates the simulation integrates; the seconds each basis took to
 * build are recorded too (every eigen-solve and factorisation it needs
 * included).
 *
 * Usage: basis_choice SCENARIO.yaml [F_EXC_HZ|auto [DENSITY ...]]
 * (build/basis_choice; default: auto, the library's rule
 * fb_hull_excitation_hz; density 1). CSV
 * "method,density,coordinates,error,build_seconds" on stdout, progress on
 * stderr. */
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

/* The frequency grid (Hz): every elastic mode is damped at least as the
 * first (zeta = 2 % x f / f_1 for B = beta K), so a resonance in the band
 * is at least 0.04 f_1 wide at half power (0.4 Hz for the reference
 * vehicle's 10.3 Hz), some six steps of this grid. */
#define NFREQ 200
#define F_LOW_HZ 0.25
/* The cut-off of the modes_3fexc marker, in f_exc. */
#define MODES_CUTOFF_FACTOR 3.0
/* An entry of H is 0 below this fraction of its row's largest (above). */
#define ZERO_REL 1e-4
/* Most steps of the iterative refinement of a Craig-Bampton constraint
 * mode (each gains a factor sigma / lambda_1 of the held hull, ~1e-3). */
#define REFINE_MAX 10

static const double two_pi = 6.28318530717958647692;

/* The sizes tried: modes kept (modes, modes_static), Ritz blocks (ritz),
 * fixed-interface modes (craig_bampton). */
static const size_t mode_counts[] = {8, 10, 12, 15, 20, 25, 30, 36, 44, 52, 64, 80, 100, 120};
static const size_t ritz_orders[] = {1, 2, 3, 4, 5, 6, 7, 8};
static const size_t cb_counts[] = {4, 6, 8, 12, 16, 20, 25, 30, 40, 50, 60, 80, 100};
#define COUNT(a) (sizeof(a) / sizeof(a)[0])

/* One density's hull, its patterns and its reference receptance. */
typedef struct study {
  int density;
  fb_scenario *s;
  fb_fe_hull *fe;
  fb_mat *K, *M;
  size_t n;          /* nodal DOFs */
  double *F;         /* n x nf: the patterns, the nforce forces first */
  size_t nf, nforce; /* patterns, and the forces among them */
  double *rigid;     /* n x 6: rigid-body motions, null vectors of K */
  double fexc, beta; /* Hz; s */
  double omega[NFREQ];
  double complex *href; /* NFREQ x nf x nforce: H_ref(w)[o + nf c] */
  double *hmax;         /* nf x nforce: each entry's largest |H_ref| */
} study;

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Progress on stderr, so that stdout stays the CSV. */
static void say(const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  fputs("basis_choice: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
}

static int fail(const fb_err *err)
{
  fprintf(stderr, "basis_choice: %s\n", err->msg);
  return 1;
}

static int nomem(fb_err *err)
{
  return fb_err_set(err, FB_ENOMEM, "out of memory");
}

static void study_free(study *st)
{
  fb_scenario_free(&st->s);
  fb_fe_hull_free(&st->fe);
  fb_mat_free(&st->K);
  fb_mat_free(&st->M);
  free(st->F);
  free(st->rigid);
  free(st->href);
  free(st->hmax);
}

/* The patterns of hull_model.c's patterns(), from the public structs: each
 * attachment point's vertical force (its coupling's row), the load (every
 * load point's row, equal shares) and each output read from the hull's
 * deformation (its torsion weights: fit 1 for torsion_fit, 0 for the
 * paper's torsion). */
static int patterns(study *st, fb_err *err)
{
  const fb_fe_hull *fe = st->fe;
  const size_t n = st->n;
  size_t nout = 0;
  for (size_t o = 0; o < st->s->noutputs; ++o) {
    const fb_output_kind *k = fb_vehicle_output_kind_find(st->s->output[o].signal);
    nout += k && k->subject == FB_OUTPUT_OF_HULL;
  }
  st->nforce = fe->nattach + 1;
  st->nf = st->nforce + nout;
  if (!(st->F = calloc(n * st->nf, sizeof *st->F)))
    return nomem(err);
  for (size_t a = 0; a < fe->nattach; ++a)
    for (size_t i = 0; i < fe->attach_coupling[a].n; ++i)
      st->F[a * n + fe->attach_coupling[a].dof[i]] += fe->attach_coupling[a].w[i];
  double *load = st->F + fe->nattach * n, *out = load + n;
  for (size_t k = 0; k < fe->nload; ++k)
    for (size_t i = 0; i < fe->load_coupling[k].n; ++i)
      load[fe->load_coupling[k].dof[i]] += fe->load_coupling[k].w[i];
  int rc = FB_OK;
  for (size_t o = 0; !rc && o < st->s->noutputs; ++o) {
    const char *signal = st->s->output[o].signal;
    const fb_output_kind *k = fb_vehicle_output_kind_find(signal);
    if (k && k->subject == FB_OUTPUT_OF_HULL) {
      rc = fb_fe_hull_torsion_weights(fe, strcmp(signal, "torsion_fit") == 0, out, err);
      out += n;
    }
  }
  return rc;
}

/* The scenario at the density, its hull's K and M as built (structure and
 * declared masses, as the vehicle's hull moves with them for a
 * weight-only payload), the patterns and the rigid-body motions about the
 * nodes' centroid (hull_model.c's null vectors for the Lanczos solves). */
static int load(const char *path, int density, study *st, fb_err *err)
{
  char value[16];
  snprintf(value, sizeof value, "%d", density);
  const fb_scenario_override ov = {.key = "hull.mesh.density", .value = value};
  st->density = density;
  int rc = fb_scenario_load_overrides(path, &ov, 1, &st->s, err);
  if (!rc)
    rc = fb_vehicle_fe_hull(st->s, &st->fe, err);
  if (!rc)
    rc = fb_fem_assemble(st->fe->mesh, &st->fe->props, st->fe->mass_kind, &st->K, NULL, err);
  if (!rc)
    rc = fb_fe_hull_mass_matrix(st->fe, &st->M, err);
  if (rc)
    return rc;
  const size_t nn = fb_mesh_nnodes(st->fe->mesh);
  st->n = 6 * nn;
  if (!(st->rigid = malloc(6 * st->n * sizeof *st->rigid)))
    return nomem(err);
  double c[3] = {0.0, 0.0, 0.0};
  for (size_t i = 0; i < nn; ++i)
    for (int k = 0; k < 3; ++k)
      c[k] += fb_mesh_node_xyz(st->fe->mesh, i)[k] / (double)nn;
  fb_mesh_rigid_modes(st->fe->mesh, c, st->rigid);
  return patterns(st, err);
}

/* The options of the library's own solves: its defaults (Lanczos above
 * FB_EIG_DENSE_AUTO_DOFS) told the rigid-body motions. */
static fb_eig_opts lanczos_opts(const study *st)
{
  fb_eig_opts o;
  fb_eig_opts_default(&o);
  o.null_vectors = st->rigid;
  o.nnull = 6;
  return o;
}

/* H_ref by superposition over every mode (nmodes of them, M-orthonormal
 * shapes phi, eigenvalues lambda): sum_k (F' phi_k)(phi_k' F_forces) /
 * (lambda_k (1 + i w beta) - w^2), and each entry's largest modulus. */
static int superpose(study *st, size_t nmodes, const double *phi, const double *lambda,
                     fb_err *err)
{
  const size_t n = st->n, nf = st->nf, nc = st->nforce;
  double *a = malloc(nf * nmodes * sizeof *a); /* a[o + nf k] = F_o' phi_k */
  st->href = calloc(NFREQ * nf * nc, sizeof *st->href);
  st->hmax = calloc(nf * nc, sizeof *st->hmax);
  if (!a || !st->href || !st->hmax) {
    free(a);
    return nomem(err);
  }
  for (size_t k = 0; k < nmodes; ++k)
    for (size_t o = 0; o < nf; ++o) {
      double d = 0.0;
      for (size_t i = 0; i < n; ++i)
        d += st->F[o * n + i] * phi[k * n + i];
      a[o + nf * k] = d;
    }
  for (size_t f = 0; f < NFREQ; ++f) {
    const double w = st->omega[f];
    double complex *h = st->href + f * nf * nc;
    for (size_t k = 0; k < nmodes; ++k) {
      const double complex g = 1.0 / (lambda[k] * (1.0 + I * w * st->beta) - w * w);
      for (size_t c = 0; c < nc; ++c)
        for (size_t o = 0; o < nf; ++o)
          h[o + nf * c] += a[o + nf * k] * a[c + nf * k] * g;
    }
    for (size_t e = 0; e < nf * nc; ++e)
      st->hmax[e] = fmax(st->hmax[e], cabs(h[e]));
  }
  for (size_t o = 0; o < nf; ++o) {
    double rowmax = 0.0;
    for (size_t c = 0; c < nc; ++c)
      rowmax = fmax(rowmax, st->hmax[o + nf * c]);
    for (size_t c = 0; c < nc; ++c)
      if (st->hmax[o + nf * c] < ZERO_REL * rowmax)
        st->hmax[o + nf * c] = 0.0;
  }
  free(a);
  return FB_OK;
}

/* The dense solve's modes with its six rigid-body ones replaced by the
 * exact motions (st->rigid, M-orthonormalised by Gram-Schmidt) and the
 * elastic ones freed of them: LAPACK's vectors of a zero eigenvalue are
 * accurate only to about eps lambda_max / lambda_1 (~1e-6 here), and
 * their error, divided by w^2 at the lowest frequency, would swamp the
 * small entries (the torsion under the symmetric load). */
static int exact_rigid(const study *st, double *phi, fb_err *err)
{
  const size_t n = st->n;
  double *mr = malloc(6 * n * sizeof *mr); /* M times each rigid mode */
  if (!mr)
    return nomem(err);
  memcpy(phi, st->rigid, 6 * n * sizeof *phi);
  for (size_t r = 0; r < 6; ++r) {
    double *v = phi + r * n;
    for (size_t q = 0; q < r; ++q) {
      double d = 0.0;
      for (size_t i = 0; i < n; ++i)
        d += mr[q * n + i] * v[i];
      for (size_t i = 0; i < n; ++i)
        v[i] -= d * phi[q * n + i];
    }
    fb_mat_gemv(st->M, 1.0, v, 0.0, mr + r * n);
    double d = 0.0;
    for (size_t i = 0; i < n; ++i)
      d += mr[r * n + i] * v[i];
    d = 1.0 / sqrt(d);
    for (size_t i = 0; i < n; ++i) {
      v[i] *= d;
      mr[r * n + i] *= d;
    }
  }
  for (size_t k = 6; k < n; ++k)
    for (size_t r = 0; r < 6; ++r) {
      double d = 0.0;
      for (size_t i = 0; i < n; ++i)
        d += mr[r * n + i] * phi[k * n + i];
      for (size_t i = 0; i < n; ++i)
        phi[k * n + i] -= d * phi[r * n + i];
    }
  free(mr);
  return FB_OK;
}

/* The reference: every mode of (K, M) by LAPACK, beta from the first
 * elastic one (fb_fe_hull_beta's rule, the scenario's damping ratio), and
 * the frequency grid up to f_exc. */
static int reference(study *st, fb_err *err)
{
  fb_eig_opts o;
  fb_eig_opts_default(&o);
  o.method = FB_EIG_DENSE;
  fb_fem_modal *fm = NULL;
  say("density %d: dense eigen-solve of all %zu DOFs (the reference)", st->density, st->n);
  const double t0 = now();
  int rc = fb_fem_modal_new(st->K, st->M, &o, &fm, err);
  if (!rc)
    rc = fb_fem_modal_solve(fm, st->n, 0.0, err);
  if (rc) {
    fb_fem_modal_free(&fm);
    return rc;
  }
  const size_t nrigid = fb_fem_modal_nrigid(fm);
  const double *hz = fb_fem_modal_freq_hz(fm);
  rc = fb_fe_hull_beta(st->s->hull_damping_ratio, nrigid, hz[nrigid], &st->beta, err);
  size_t below = 0; /* the modes up to 3 f_exc */
  while (below < st->n && hz[below] <= MODES_CUTOFF_FACTOR * st->fexc)
    ++below;
  say("density %d: %.1f s; first elastic mode %.3f Hz, beta %.4g s, %zu modes up to %.2f Hz "
      "(%g x f_exc %.2f Hz), highest %.4g Hz",
      st->density, now() - t0, hz[nrigid], st->beta, below, MODES_CUTOFF_FACTOR * st->fexc,
      MODES_CUTOFF_FACTOR, st->fexc, hz[st->n - 1]);
  for (size_t f = 0; f < NFREQ; ++f)
    st->omega[f] = two_pi * (F_LOW_HZ + (st->fexc - F_LOW_HZ) * (double)f / (NFREQ - 1));
  double *phi = NULL;
  if (!rc && nrigid != 6)
    rc = fb_err_set(err, FB_ESOLVER, "%zu rigid-body modes, not 6", nrigid);
  if (!rc && !(phi = malloc(st->n * st->n * sizeof *phi)))
    rc = nomem(err);
  if (!rc) {
    memcpy(phi, fb_fem_modal_shapes(fm), st->n * st->n * sizeof *phi);
    rc = exact_rigid(st, phi, err);
  }
  if (!rc)
    rc = superpose(st, st->n, phi, fb_fem_modal_lambda(fm), err);
  free(phi);
  fb_fem_modal_free(&fm);
  return rc;
}

/* out = T' A T (m x m, column-major, symmetrised) for sparse A. */
static int project(const fb_mat *A, const double *T, size_t n, size_t m, double *out,
                   fb_err *err)
{
  double *y = malloc(n * sizeof *y);
  if (!y)
    return nomem(err);
  for (size_t j = 0; j < m; ++j) {
    fb_mat_gemv(A, 1.0, T + j * n, 0.0, y);
    for (size_t i = 0; i <= j; ++i) {
      double d = 0.0;
      for (size_t k = 0; k < n; ++k)
        d += T[i * n + k] * y[k];
      out[i + m * j] = out[j + m * i] = d;
    }
  }
  free(y);
  return FB_OK;
}

/* The error of the basis T (n x m) against the reference: see the top. */
static int basis_error(const study *st, const double *T, size_t m, double *error, fb_err *err)
{
  const size_t n = st->n, nf = st->nf, nc = st->nforce;
  double *kr = malloc(m * m * sizeof *kr), *mr = malloc(m * m * sizeof *mr);
  double *g = malloc(nf * m * sizeof *g); /* g[o + nf j] = F_o' T_j */
  double complex *a = malloc(m * m * sizeof *a), *x = malloc(m * nc * sizeof *x);
  lapack_int *piv = malloc(m * sizeof *piv);
  int rc = kr && mr && g && a && x && piv ? FB_OK : nomem(err);
  if (!rc)
    rc = project(st->K, T, n, m, kr, err);
  if (!rc)
    rc = project(st->M, T, n, m, mr, err);
  for (size_t j = 0; !rc && j < m; ++j)
    for (size_t o = 0; o < nf; ++o) {
      double d = 0.0;
      for (size_t i = 0; i < n; ++i)
        d += st->F[o * n + i] * T[j * n + i];
      g[o + nf * j] = d;
    }
  double worst = 0.0;
  for (size_t f = 0; !rc && f < NFREQ; ++f) {
    const double w = st->omega[f];
    const double complex kf = 1.0 + I * w * st->beta;
    for (size_t e = 0; e < m * m; ++e)
      a[e] = kr[e] * kf - w * w * mr[e];
    for (size_t c = 0; c < nc; ++c)
      for (size_t j = 0; j < m; ++j)
        x[j + m * c] = g[c + nf * j];
    const lapack_int info = LAPACKE_zgesv(LAPACK_COL_MAJOR, (lapack_int)m, (lapack_int)nc, a,
                                          (lapack_int)m, piv, x, (lapack_int)m);
    if (info != 0) {
      rc = fb_err_set(err, FB_ESOLVER, "zgesv: info %d at %g Hz", (int)info, w / two_pi);
      break;
    }
    const double complex *href = st->href + f * nf * nc;
    for (size_t c = 0; c < nc; ++c)
      for (size_t o = 0; o < nf; ++o) {
        if (st->hmax[o + nf * c] == 0.0)
          continue;
        double complex h = 0.0;
        for (size_t j = 0; j < m; ++j)
          h += g[o + nf * j] * x[j + m * c];
        worst = fmax(worst, cabs(h - href[o + nf * c]) / st->hmax[o + nf * c]);
      }
  }
  *error = worst;
  free(kr);
  free(mr);
  free(g);
  free(a);
  free(x);
  free(piv);
  return rc;
}

/* The CSV row of a basis built in seconds (T freed here). */
static int report(const study *st, const char *method, double *T, size_t m, double seconds,
                  fb_err *err)
{
  double e = 0.0;
  int rc = basis_error(st, T, m, &e, err);
  free(T);
  if (!rc) {
    printf("%s,%d,%zu,%.6e,%.6f\n", method, st->density, m, e, seconds);
    fflush(stdout);
  }
  return rc;
}

/* (a) The nmodes lowest free-free modes alone. */
static int modes_only(const study *st, size_t nmodes, double **T, size_t *m, fb_err *err)
{
  const fb_eig_opts o = lanczos_opts(st);
  fb_fem_modal *fm = NULL;
  int rc = fb_fem_modal_new(st->K, st->M, &o, &fm, err);
  if (!rc)
    rc = fb_fem_modal_solve(fm, nmodes, 0.0, err);
  if (!rc && !(*T = malloc(st->n * nmodes * sizeof **T)))
    rc = nomem(err);
  if (!rc) {
    memcpy(*T, fb_fem_modal_shapes(fm), st->n * nmodes * sizeof **T);
    *m = nmodes;
  }
  fb_fem_modal_free(&fm);
  return rc;
}

/* (b) and (c): the nmodes lowest modes (nmodes 0: every one up to cutoff
 * Hz, the first elastic one at least, as hull_model.c's modes_kept) and
 * order blocks of fb_fem_modal_basis; nmodes 6 with order > 1 is the
 * load-dependent Ritz basis, the rigid-body modes its start. */
static int modes_basis(const study *st, size_t nmodes, double cutoff, size_t order, double **T,
                       size_t *m, fb_err *err)
{
  const fb_eig_opts o = lanczos_opts(st);
  fb_fem_modal *fm = NULL;
  double *lambda = NULL;
  size_t nstatic = 0;
  int rc = fb_fem_modal_new(st->K, st->M, &o, &fm, err);
  if (!rc)
    rc = fb_fem_modal_solve(fm, nmodes, cutoff, err);
  size_t keep = nmodes;
  if (!rc && nmodes == 0) {
    const size_t nrigid = fb_fem_modal_nrigid(fm), nsolved = fb_fem_modal_nmodes(fm);
    const double *hz = fb_fem_modal_freq_hz(fm);
    keep = nrigid;
    while (keep < nsolved && hz[keep] <= cutoff)
      ++keep;
    keep += keep == nrigid && nrigid < nsolved;
  }
  if (!rc)
    rc = fb_fem_modal_basis(fm, keep, st->F, st->nf, order, T, &lambda, m, &nstatic, err);
  free(lambda);
  fb_fem_modal_free(&fm);
  return rc;
}

/* The interface of the Craig-Bampton basis: every DOF an attachment point
 * or a load point drives (with the scenario's default couplings, the
 * vertical u_z of its node, 6 node + 2: 57 DOFs for the reference
 * vehicle, whose suspension points and driver's seat are load points
 * too), each once, marked 1 in mark[]. */
static void interface_dofs(const study *st, char *mark)
{
  const fb_fe_hull *fe = st->fe;
  for (size_t p = 0; p < fe->nattach + fe->nload; ++p) {
    const fb_hull_coupling *c =
        p < fe->nattach ? &fe->attach_coupling[p] : &fe->load_coupling[p - fe->nattach];
    for (size_t i = 0; i < c->n; ++i)
      mark[c->dof[i]] = 1;
  }
}

/* The constraint modes into T's first nb columns: column b is 1 at the
 * interface DOF bdof[b], 0 at the others, and x_b = -Kii^+ K_ib e_b on
 * the interior. The hull stays free in x, y and yaw with the vertical
 * interface DOFs held, so Kii is singular: the factor is of Kii + sigma
 * Mii, sigma = 1e-8 trace(K) / trace(M), and iterative refinement
 * against Kii itself (x += (Kii + sigma Mii)^-1 (r - Kii x)) removes the
 * shift from the elastic part of x (by sigma / (lambda_k + sigma) per
 * step; the part along x, y and yaw is left as it is, and the
 * fixed-interface modes' first three, at 0 Hz, span it). Measured: the
 * shift alone (no refinement) multiplies the error of this basis by 2.6,
 * as it bends the rigid-body heave, roll and pitch, which the constraint
 * modes make, by sigma / lambda and that rides on their 1/w^2 amplitude. */
static int constraint_modes(const study *st, const fb_mat *kii, const fb_mat *mii,
                            const size_t *bdof, size_t nb, const size_t *idof, size_t ni,
                            double *T, fb_err *err)
{
  const size_t n = st->n;
  double tk = 0.0, tm = 0.0;
  for (size_t i = 0; i < n; ++i) {
    tk += fb_mat_get(st->K, i, i);
    tm += fb_mat_get(st->M, i, i);
  }
  fb_chol *chol = NULL;
  double *rhs = malloc(ni * nb * sizeof *rhs), *x = calloc(ni * nb, sizeof *x),
         *r = malloc(ni * nb * sizeof *r), *e = calloc(n, sizeof *e),
         *ke = malloc(n * sizeof *ke);
  int rc = rhs && x && r && e && ke ? FB_OK : nomem(err);
  if (!rc)
    rc = fb_chol_new_sum(1.0, kii, 1e-8 * tk / tm, mii, 0, &chol, err);
  for (size_t b = 0; !rc && b < nb; ++b) {
    e[bdof[b]] = 1.0;
    fb_mat_gemv(st->K, 1.0, e, 0.0, ke);
    e[bdof[b]] = 0.0;
    for (size_t i = 0; i < ni; ++i)
      rhs[b * ni + i] = -ke[idof[i]];
  }
  /* x starts at 0, so the first step is the shifted solve itself. */
  double step = INFINITY, size = 0.0;
  for (int it = 0; !rc && it < REFINE_MAX && step > 1e-14 * size; ++it) {
    memcpy(r, rhs, ni * nb * sizeof *r);
    for (size_t b = 0; b < nb; ++b)
      fb_mat_gemv(kii, -1.0, x + b * ni, 1.0, r + b * ni);
    rc = fb_chol_solve(chol, r, nb, err);
    step = size = 0.0;
    for (size_t i = 0; !rc && i < ni * nb; ++i) {
      x[i] += r[i];
      step = fmax(step, fabs(r[i]));
      size = fmax(size, fabs(x[i]));
    }
  }
  for (size_t b = 0; !rc && b < nb; ++b) {
    T[b * n + bdof[b]] = 1.0;
    for (size_t i = 0; i < ni; ++i)
      T[b * n + idof[i]] = x[b * ni + i];
  }
  fb_chol_free(&chol);
  free(rhs);
  free(x);
  free(r);
  free(e);
  free(ke);
  return rc;
}

/* (d) Craig-Bampton: the constraint modes of the interface and the nmodes
 * lowest normal modes of the hull with its interface held (fb_fem_modes
 * on the interior's Kii, Mii; the first three are its free x, y and yaw
 * at 0 Hz), T = [Psi Phi] over the nodal DOFs. */
static int craig_bampton(const study *st, size_t nmodes, double **T, size_t *m, fb_err *err)
{
  const size_t n = st->n;
  char *mark = calloc(n, 1);
  size_t *bdof = malloc(n * sizeof *bdof), *idof = malloc(n * sizeof *idof);
  double *hz = malloc(nmodes * sizeof *hz), *phi = NULL;
  fb_mat *kii = NULL, *mii = NULL;
  int rc = mark && bdof && idof && hz ? FB_OK : nomem(err);
  size_t nb = 0, ni = 0;
  if (!rc) {
    interface_dofs(st, mark);
    for (size_t i = 0; i < n; ++i) {
      if (mark[i])
        bdof[nb++] = i;
      else
        idof[ni++] = i;
    }
    rc = fb_fem_submatrix(st->K, idof, ni, &kii, err);
  }
  if (!rc)
    rc = fb_fem_submatrix(st->M, idof, ni, &mii, err);
  if (!rc && (!(*T = calloc(n * (nb + nmodes), sizeof **T)) ||
              !(phi = malloc(ni * nmodes * sizeof *phi))))
    rc = nomem(err);
  if (!rc)
    rc = constraint_modes(st, kii, mii, bdof, nb, idof, ni, *T, err);
  if (!rc) {
    fb_eig_opts o;
    fb_eig_opts_default(&o);
    rc = fb_fem_modes(kii, mii, nmodes, &o, hz, phi, err);
  }
  for (size_t k = 0; !rc && k < nmodes; ++k)
    for (size_t i = 0; i < ni; ++i)
      (*T)[(nb + k) * n + idof[i]] = phi[k * ni + i];
  if (rc) {
    free(*T);
    *T = NULL;
  }
  *m = nb + nmodes;
  fb_mat_free(&kii);
  fb_mat_free(&mii);
  free(mark);
  free(bdof);
  free(idof);
  free(hz);
  free(phi);
  return rc;
}

/* Every method's bases at one density. */
static int run_methods(const study *st, fb_err *err)
{
  int rc = FB_OK;
  double *T = NULL, t0 = 0.0;
  size_t m = 0;
  say("density %d: modes and modes + static correction, %zu to %zu modes", st->density,
      mode_counts[0], mode_counts[COUNT(mode_counts) - 1]);
  for (size_t k = 0; !rc && k < COUNT(mode_counts); ++k) {
    t0 = now();
    rc = modes_only(st, mode_counts[k], &T, &m, err);
    if (!rc)
      rc = report(st, "modes", T, m, now() - t0, err);
    t0 = now();
    if (!rc)
      rc = modes_basis(st, mode_counts[k], 0.0, 1, &T, &m, err);
    if (!rc)
      rc = report(st, "modes_static", T, m, now() - t0, err);
  }
  say("density %d: load-dependent Ritz vectors, orders %zu to %zu", st->density, ritz_orders[0],
      ritz_orders[COUNT(ritz_orders) - 1]);
  for (size_t k = 0; !rc && k < COUNT(ritz_orders); ++k) {
    t0 = now();
    rc = modes_basis(st, 6, 0.0, ritz_orders[k], &T, &m, err);
    if (!rc)
      rc = report(st, "ritz", T, m, now() - t0, err);
  }
  say("density %d: Craig-Bampton, %zu to %zu fixed-interface modes", st->density, cb_counts[0],
      cb_counts[COUNT(cb_counts) - 1]);
  for (size_t k = 0; !rc && k < COUNT(cb_counts); ++k) {
    t0 = now();
    rc = craig_bampton(st, cb_counts[k], &T, &m, err);
    if (!rc)
      rc = report(st, "craig_bampton", T, m, now() - t0, err);
  }
  t0 = now();
  if (!rc)
    rc = modes_basis(st, 0, MODES_CUTOFF_FACTOR * st->fexc, 1, &T, &m, err);
  if (!rc)
    rc = report(st, "modes_3fexc", T, m, now() - t0, err);
  /* The library's: its blocks, from the vehicle it realises. */
  fb_vehicle *v = NULL;
  t0 = now();
  if (!rc)
    rc = fb_vehicle_new(st->s, FB_SYSTEM_FLEXIBLE, NULL, &v, err);
  const size_t blocks = v ? fb_vehicle_hull_basis(v)->nblocks : 0;
  fb_vehicle_free(&v);
  if (!rc)
    rc = modes_basis(st, 6, 0.0, blocks, &T, &m, err);
  if (!rc)
    rc = report(st, "library", T, m, now() - t0, err);
  return rc;
}

int main(int argc, char **argv)
{
  if (argc < 2) {
    fprintf(stderr, "usage: %s SCENARIO.yaml [F_EXC_HZ|auto [DENSITY ...]]\n", argv[0]);
    return 2;
  }
  double fexc = argc > 2 && strcmp(argv[2], "auto") != 0 ? atof(argv[2]) : 0.0;
  if (argc > 2 && strcmp(argv[2], "auto") != 0 && !(fexc > F_LOW_HZ)) {
    fprintf(stderr, "basis_choice: f_exc %s: not a frequency above %g Hz\n", argv[2], F_LOW_HZ);
    return 2;
  }
  printf("method,density,coordinates,error,build_seconds\n");
  fb_err err;
  fb_err_clear(&err);
  const int ndensities = argc > 3 ? argc - 3 : 1;
  for (int d = 0; d < ndensities; ++d) {
    const char *arg = argc > 3 ? argv[3 + d] : "1";
    const int density = atoi(arg);
    if (density < 1) {
      fprintf(stderr, "basis_choice: density %s: not a positive integer\n", arg);
      return 2;
    }
    study st = {0};
    const double t0 = now();
    int rc = load(argv[1], density, &st, &err);
    if (!rc) {
      const double rule = fb_hull_excitation_hz(st.s);
      st.fexc = fexc > 0 ? fexc : rule;
      say("density %d: %zu DOFs, %zu patterns (%zu forces), f_exc %.4g Hz (the rule's %.4g Hz)",
          density, st.n, st.nf, st.nforce, st.fexc, rule);
      rc = reference(&st, &err);
    }
    if (!rc)
      rc = run_methods(&st, &err);
    study_free(&st);
    if (rc)
      return fail(&err);
    say("density %d: done in %.1f s", density, now() - t0);
  }
  return 0;
}
