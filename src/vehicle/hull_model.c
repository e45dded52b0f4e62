/* SPDX-License-Identifier: BSD-3-Clause */
/* System 2's hull realised once (vehicle_internal.h, vehicle_hull): its
 * finite-element K and M assembled once, one eigen-solve, the basis its
 * coordinates need, and the bond-graph fragment made from them as often as
 * a diagram is built (the paper's Fig. 5, upper right: the matrices as
 * multiport I, C and R fields on the hull's velocity multibond, and
 * transformers to the attachment and load points).
 *
 * The coordinates (hull.fe.coordinates, hull.fe.modes): the nodal
 * displacements (the sparse M, K and B = beta K: the reference); every
 * free-free mode (a dense eigen-solve: the same model, diagonal); the N
 * lowest modes and the residual flexibility of every pattern; or (auto)
 * the rigid-body modes and blocks of load-dependent Ritz vectors from the
 * patterns, as many as the receptances over the excitation's band need
 * (fb_hull_excitation_hz, FB_HULL_BLOCK_TOL). The patterns are every force the rest of the
 * vehicle puts on the hull (each attachment point's, the load, whose
 * points carry equal shares) and every output read from the hull's
 * deformation (a torsion angle: with its static influence in the basis the
 * output's static response is exact for any load, the dual of the force
 * patterns). In modal coordinates M = I, K = diag(lambda) and B = beta K =
 * diag(beta lambda). */
#include <cblas.h>
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "vehicle/vehicle_internal.h"

/* Free-free modes the nodal coordinates solve for, for beta and the
 * report: the six rigid-body modes and six elastic ones. */
#define NODAL_REPORT_MODES 12
/* The receptances of the block criterion (FB_HULL_BLOCK_TOL) are compared
 * at this many frequencies evenly over the band: steps of 0.03 Hz over the
 * reference vehicle's 12.6 Hz, a thirteenth of the half-power width of its
 * first elastic mode (2 zeta f1 = 0.41 Hz), so that no resonance in the
 * band passes between two of them. */
#define BLOCK_FREQUENCIES 400
/* Most blocks auto adds: 12 blocks of the reference vehicle's 10 patterns
 * are 120 vectors, where 3 to 6 meet the tolerance on every example. */
#define MAX_BLOCKS 12

static const double two_pi = 6.28318530717958647692;

struct vehicle_hull {
  fb_fe_hull *fe;
  fb_mat *K; /* the structure's stiffness */
  fb_mat *M; /* the mass it moves with: structure, declared masses, a lumped payload */
  fb_fem_modal *modal;  /* (K, M) in modal coordinates: the factor and the modes */
  size_t memory_limit;  /* bytes for any factorisation and eigen-solve */
  size_t list_modes;    /* free-free modes to solve at least, for a listing */
  fb_progress progress; /* hears of the stages, may stop them */
  double *F;            /* ndof x nf: the patterns of the static correction */
  size_t nf;
  double *A; /* ndof x nadded: the vectors beside the kept modes */
  size_t nadded;
  size_t nlast;         /* the last block's among them */
  size_t nkeep;         /* modes kept */
  double *T, *lambda;   /* ndof x nb, nb: the basis (modal coordinates) */
  size_t nb;            /* the hull's coordinates */
  double *T2, *lambda2; /* the error estimator's basis (auto: made with the basis; else
                           when first asked) */
  size_t nb2;
  double *free_hz; /* the free-free frequencies solved */
  double *rigid;   /* ndof x 6: its rigid-body motions (null vectors of K) */
  fb_hull_basis info;
};

void vehicle_hull_free(vehicle_hull **h)
{
  if (!h || !*h)
    return;
  fb_fe_hull_free(&(*h)->fe);
  fb_mat_free(&(*h)->K);
  fb_mat_free(&(*h)->M);
  fb_fem_modal_free(&(*h)->modal);
  free((*h)->F);
  free((*h)->A);
  free((*h)->T);
  free((*h)->lambda);
  free((*h)->T2);
  free((*h)->lambda2);
  free((*h)->free_hz);
  free((*h)->rigid);
  free(*h);
  *h = NULL;
}

const fb_fe_hull *vehicle_hull_fe(const vehicle_hull *h)
{
  return h->fe;
}

const fb_hull_basis *vehicle_hull_basis(const vehicle_hull *h)
{
  return &h->info;
}

/* ---- The band of hull.fe.modes: auto. */

/* The highest frequency (Hz) in the road's input at the scenario's
 * speed: the road type's own (top_hz) or V over the road's shortest
 * wavelength (fb_road_shortest_wavelength). */
static double road_hz(const fb_scenario *s)
{
  const fb_road_type *t = s->road_type;
  if (!t)
    return 0.0;
  if (t->ops->top_hz)
    return t->ops->top_hz(s->road.bytes, s->speed);
  const fb_road_layout layout = fb_scenario_road_layout(s);
  fb_road *road = NULL;
  if (t->ops->make(s->road.bytes, &layout, &road, NULL))
    return 0.0;
  const double w = fb_road_shortest_wavelength(road);
  fb_road_free(&road);
  return w > 0 && isfinite(w) ? s->speed / w : 0.0;
}

/* A bogie's highest natural frequency on a fixed hull, Hz: its beam's
 * bounce on the pivot's spring and the two tires, or its pitch on the
 * tires about the pivot, the wheels riding with it (the two motions taken
 * apart: exact for a,b-symmetric beams, a bound's estimate otherwise);
 * 0 for a bogie whose corners are not found (the check refuses it). */
static double bogie_top_hz(const fb_scenario *s, const fb_bogie *b)
{
  const long f = fb_scenario_corner_find(s, b->front), r = fb_scenario_corner_find(s, b->rear);
  if (f < 0 || r < 0)
    return 0.0;
  const fb_corner_params *cf = &s->corner[f], *cr = &s->corner[r];
  const double a = cf->x - b->pivot_x, bb = b->pivot_x - cr->x;
  const double bounce = (b->spring_k + cf->tire_k + cr->tire_k) /
                        (b->beam_mass + cf->wheel_mass + cr->wheel_mass);
  const double pitch = (cf->tire_k * a * a + cr->tire_k * bb * bb) /
                       (b->beam_inertia + cf->wheel_mass * a * a + cr->wheel_mass * bb * bb);
  return sqrt(fmax(bounce, pitch)) / two_pi;
}

double fb_hull_excitation_hz(const fb_scenario *s)
{
  double f = road_hz(s);
  for (size_t c = 0; c < s->ncorners; ++c) {
    const fb_corner_params *cp = &s->corner[c];
    if (fb_scenario_corner_bogie(s, c) >= 0) /* its beam's, below */
      continue;
    const double k = cp->motion_ratio * cp->motion_ratio * cp->spring_k + cp->tire_k;
    f = fmax(f, sqrt(k / cp->wheel_mass) / two_pi);
  }
  for (size_t i = 0; i < s->nbogies; ++i)
    f = fmax(f, bogie_top_hz(s, &s->bogie[i]));
  for (size_t b = 0; b < s->nmounts; ++b)
    f = fmax(f, sqrt(s->mount[b].stiffness / s->mount[b].mass) / two_pi);
  for (size_t b = 0; b < s->nbodies; ++b)
    f = fmax(f, vehicle_body_top_hz(&s->body[b]));
  return f;
}

/* ---- Realisation. */

/* The hull's mass as built and, with a lumped payload, the mass it moves
 * with (*M, new; *built, new or NULL when they are the same). */
static int hull_masses(const fb_scenario *s, const fb_fe_hull *fe, fb_mat *mstruct, fb_mat **M,
                       fb_mat **built, fb_err *err)
{
  *built = NULL;
  fb_mat *m = NULL;
  int rc = fb_mat_clone(mstruct, &m, err);
  if (!rc)
    rc = fb_fe_hull_add_masses(fe, 0, 0.0, &m, err);
  if (rc || s->payload != FB_PAYLOAD_LUMPED) {
    *M = m;
    return rc;
  }
  /* The structure with its declared masses and the payload's shares. */
  fb_mat *lumped = NULL;
  rc = fb_mat_clone(mstruct, &lumped, err);
  const double each = fb_scenario_payload_mass(s) / (double)fe->nload;
  if (!rc)
    rc = fb_fe_hull_add_masses(fe, fe->nload, each, &lumped, err);
  *M = lumped;
  *built = m;
  if (rc) {
    fb_mat_free(M);
    fb_mat_free(built);
  }
  return rc;
}

/* K and M, assembled once. */
static int assemble(const fb_scenario *s, vehicle_hull *h, fb_mat **built,
                    const fb_progress *pr, fb_vehicle_work *w, fb_err *err)
{
  char stage[96];
  snprintf(stage, sizeof stage, "assembly of the hull's K and M (%zu elements, %zu DOFs)",
           fb_mesh_nelements(h->fe->mesh), 6 * fb_mesh_nnodes(h->fe->mesh));
  fb_mat *mstruct = NULL;
  int rc = fb_progress_report(pr, stage, 0.0, err);
  if (!rc)
    rc = fb_fem_assemble(h->fe->mesh, &h->fe->props, h->fe->mass_kind, &h->K, &mstruct, err);
  if (!rc) {
    w->assemblies++;
    rc = hull_masses(s, h->fe, mstruct, &h->M, built, err);
  }
  fb_mat_free(&mstruct);
  return rc ? rc : fb_progress_report(pr, stage, 1.0, err);
}

/* 1 if output o is a pattern: a torsion, a point's translation or an
 * element's surface stress (the rigid-body motions are in every basis
 * already). */
static int output_pattern(const fb_output_spec *o)
{
  vehicle_hull_motion how;
  return fb_vehicle_output_hull_fit(o) >= 0 || vehicle_output_hull_stress(o) ||
         (vehicle_output_hull_motion(o, &how) && how.coordinate < 0);
}

/* The patterns the static correction restores: each attachment point's
 * vertical force (its coupling's row), the load (its points' rows, equal
 * shares), and each output read from the hull's deformation (its
 * weights over the nodal DOFs: a torsion's, a point's translation's, a
 * surface stress's row of its element's recovery matrix). */
static int patterns(const fb_scenario *s, vehicle_hull *h, fb_err *err)
{
  const fb_fe_hull *fe = h->fe;
  const size_t n = h->info.ndof;
  size_t nout = 0;
  for (size_t o = 0; o < s->noutputs; ++o)
    nout += output_pattern(&s->output[o]);
  const size_t nrows = 6 * fe->nbushings; /* each bushing's force and moment */
  h->nf = fe->nattach + nrows + 1 + nout;
  h->F = calloc(n * h->nf, sizeof *h->F);
  if (!h->F)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu static patterns", h->nf);
  for (size_t a = 0; a < fe->nattach; ++a)
    for (size_t i = 0; i < fe->attach_coupling[a].n; ++i)
      h->F[a * n + fe->attach_coupling[a].dof[i]] += fe->attach_coupling[a].w[i];
  for (size_t r = 0; r < nrows; ++r)
    for (size_t i = 0; i < fe->bushing_rows[r].n; ++i)
      h->F[(fe->nattach + r) * n + fe->bushing_rows[r].dof[i]] += fe->bushing_rows[r].w[i];
  double *load = h->F + (fe->nattach + nrows) * n, *out = load + n;
  for (size_t k = 0; k < fe->nload; ++k)
    for (size_t i = 0; i < fe->load_coupling[k].n; ++i)
      load[fe->load_coupling[k].dof[i]] += fe->load_coupling[k].w[i];
  int rc = FB_OK;
  for (size_t o = 0; !rc && o < s->noutputs; ++o) {
    const int fit = fb_vehicle_output_hull_fit(&s->output[o]);
    if (fit >= 0)
      rc = fb_fe_hull_torsion_weights(fe, fit, out, err);
    else if (vehicle_output_hull_stress(&s->output[o]))
      rc = vehicle_hull_stress_weights(fe->mesh, &fe->props, &s->output[o], o, out, err);
    else if (output_pattern(&s->output[o]))
      rc = vehicle_hull_point_weights(fe->mesh, &s->output[o], o, out, err);
    out += output_pattern(&s->output[o]) ? n : 0;
  }
  h->info.npatterns = h->nf;
  return rc;
}

/* beta from the first elastic free-free mode of the hull as built: the
 * solved modes' own when they are of that hull, else an eigen-solve of
 * (K, M as built) for it. */
static int hull_beta(const fb_scenario *s, vehicle_hull *h, const fb_mat *built,
                     const fb_eig_opts *o, fb_vehicle_work *w, fb_err *err)
{
  const fb_hull_basis *b = &h->info;
  if (!built && b->nfree > b->nfree_rigid) {
    h->info.f1_hz = b->free_hz[b->nfree_rigid];
    return fb_fe_hull_beta(s->hull_damping_ratio, b->nfree_rigid, h->info.f1_hz, &h->info.beta,
                           err);
  }
  double f[FB_HULL_BETA_MODES];
  size_t nrigid = 0;
  fb_eig_info info;
  int rc = fb_fe_hull_frequencies(h->K, built ? built : h->M, FB_HULL_BETA_MODES, o, f, &nrigid,
                                  &info, err);
  if (!rc) {
    w->hull_eigensolves++;
    w->factorisations += info.factor_bytes > 0;
    h->info.f1_hz = f[FB_HULL_BETA_MODES - 1];
    rc = fb_fe_hull_beta(s->hull_damping_ratio, nrigid, h->info.f1_hz, &h->info.beta, err);
  }
  return rc;
}

/* Nodal coordinates: the report's free-free frequencies (and the
 * listing's), which give beta, by fb_fe_hull_frequencies. */
static int realise_nodal(const fb_scenario *s, vehicle_hull *h, const fb_mat *built,
                         const fb_eig_opts *o, fb_vehicle_work *w, fb_err *err)
{
  const size_t n = h->info.ndof;
  size_t count = h->list_modes > NODAL_REPORT_MODES ? h->list_modes : NODAL_REPORT_MODES;
  if (count > n)
    count = n;
  h->free_hz = malloc(count * sizeof *h->free_hz);
  if (!h->free_hz)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  size_t nrigid = 0;
  int rc = fb_fe_hull_frequencies(h->K, built ? built : h->M, count, o, h->free_hz, &nrigid,
                                  &h->info.eig, err);
  if (!rc) {
    w->hull_eigensolves++;
    w->factorisations += h->info.eig.factor_bytes > 0;
    h->info.nfree = count;
    h->info.nfree_rigid = nrigid;
    h->info.free_hz = h->free_hz;
    h->info.ncoords = n;
    h->nb = n;
    rc = hull_beta(s, h, built, o, w, err);
  }
  return rc;
}

/* The larger of a and b. */
static size_t max_size(size_t a, size_t b)
{
  return a > b ? a : b;
}

/* The modes the kind asks for (nmodes of fb_fem_modal_solve), at least
 * the listing's: every mode for `all`; N and the next for a count (the
 * report's first mode left out); for `auto` the rigid-body modes and the
 * first elastic one (beta's) and the band its basis converges over. */
static int modes_wanted(const fb_scenario *s, vehicle_hull *h, size_t *nmodes, fb_err *err)
{
  const size_t n = h->info.ndof;
  h->info.cutoff_hz = h->info.excitation_hz = NAN;
  *nmodes = 0;
  switch (s->hull_modes_kind) {
  case FB_HULL_MODES_ALL: *nmodes = n; return FB_OK;
  case FB_HULL_MODES_COUNT:
    if ((size_t)s->hull_modes > n) {
      fb_err_set(err, FB_EINVAL, "%d modes, more than the hull's %zu degrees of freedom",
                 s->hull_modes, n);
      return fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_modes)), FB_EINVAL;
    }
    *nmodes =
        max_size((size_t)s->hull_modes < n ? (size_t)s->hull_modes + 1 : n, h->list_modes);
    break;
  case FB_HULL_MODES_AUTO:
    if (s->hull_cutoff_hz > 0)
      h->info.cutoff_hz = s->hull_cutoff_hz;
    else
      h->info.cutoff_hz = h->info.excitation_hz = fb_hull_excitation_hz(s);
    *nmodes = max_size(FB_HULL_BETA_MODES, h->list_modes);
    break;
  default:
    return fb_err_set(err, FB_EINVAL, "unknown kind of modes %d", (int)s->hull_modes_kind),
           fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_modes)), FB_EINVAL;
  }
  if (*nmodes > n)
    *nmodes = n;
  return FB_OK;
}

/* How many of the solved modes the basis keeps: every one for `all`, N
 * for a count, the rigid-body ones for `auto`. A band of the file's own
 * must reach the first elastic mode (below it the user asked for no
 * dynamics of the hull's own); the rule's may lie below that mode, for a
 * stiff hull. */
static int modes_kept(const fb_scenario *s, vehicle_hull *h, fb_err *err)
{
  const fb_hull_basis *b = &h->info;
  const size_t nsolved = fb_fem_modal_nmodes(h->modal), nrigid = b->nfree_rigid;
  const double *f = fb_fem_modal_freq_hz(h->modal);
  size_t keep = nsolved;
  if (s->hull_modes_kind == FB_HULL_MODES_COUNT)
    keep = (size_t)s->hull_modes;
  else if (s->hull_modes_kind == FB_HULL_MODES_AUTO) {
    keep = nrigid;
    if (s->hull_cutoff_hz > 0 && nrigid < nsolved && s->hull_cutoff_hz < f[nrigid]) {
      fb_err_set(err, FB_EINVAL,
                 "a cut-off of %g Hz is below the hull's first elastic mode, at %.4g Hz: the "
                 "basis would represent no dynamics of the hull's own",
                 s->hull_cutoff_hz, f[nrigid]);
      return fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_cutoff_hz)), FB_EINVAL;
    }
  }
  if (keep < nrigid) {
    fb_err_set(err, FB_EINVAL,
               "%zu modes leave out rigid-body modes of the hull (it has %zu): keep at least "
               "those",
               keep, nrigid);
    return fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_modes)), FB_EINVAL;
  }
  h->nkeep = keep;
  return FB_OK;
}

/* ---- hull.fe.modes: auto, blocks of load-dependent Ritz vectors. */

/* The auto basis's space while it grows: the added vectors A (ndof x
 * na, M-orthonormal and M-orthogonal to the kept rigid-body modes), their
 * stiffness Kr = A'KA and their patterns' components AF = A'F, extended
 * block by block (K is applied once to each vector). A leading na x na of
 * Kr is the stiffness of the basis of the first na vectors: T'MT = I
 * needs nothing. */
typedef struct block_space {
  size_t na, cap;
  double *Kr; /* cap x cap */
  double *AF; /* cap x nf */
} block_space;

/* The Ritz solution of the first na vectors of a block_space: lambda and
 * Y (Kr's leading block = Y diag(lambda) Y'), and P = Y' AF, the patterns'
 * components along the Ritz vectors A Y. */
typedef struct ritz_basis {
  size_t na;
  double *lambda, *Y, *P;
} ritz_basis;

static void ritz_basis_free(ritz_basis *r)
{
  free(r->lambda);
  free(r->Y);
  free(r->P);
  *r = (ritz_basis){0, NULL, NULL, NULL};
}

static void block_space_free(block_space *b)
{
  free(b->Kr);
  free(b->AF);
}

/* Adds the vectors of A from b->na to na to b: their K products, their
 * rows and columns of Kr and their rows of AF. */
static int block_space_grow(const vehicle_hull *h, block_space *b, size_t na, fb_err *err)
{
  const size_t n = h->info.ndof, nf = h->nf, nb = na - b->na;
  if (na > b->cap) {
    const size_t cap = 2 * na;
    double *Kr = calloc(cap * cap, sizeof *Kr), *AF = calloc(cap * nf, sizeof *AF);
    if (!Kr || !AF) {
      free(Kr);
      free(AF);
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    }
    for (size_t j = 0; b->Kr && j < b->na; ++j)
      memcpy(Kr + j * cap, b->Kr + j * b->cap, b->na * sizeof *Kr);
    for (size_t f = 0; b->AF && f < nf; ++f)
      memcpy(AF + f * cap, b->AF + f * b->cap, b->na * sizeof *AF);
    block_space_free(b);
    b->Kr = Kr;
    b->AF = AF;
    b->cap = cap;
  }
  double *KA = malloc(n * (nb ? nb : 1) * sizeof *KA);
  if (!KA)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t j = 0; j < nb; ++j)
    fb_mat_gemv(h->K, 1.0, h->A + (b->na + j) * n, 0.0, KA + j * n);
  /* Kr[0:na, new] = A' (K A_new), and its mirror. */
  cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, (int)na, (int)nb, (int)n, 1.0, h->A,
              (int)n, KA, (int)n, 0.0, b->Kr + b->na * b->cap, (int)b->cap);
  for (size_t j = b->na; j < na; ++j)
    for (size_t i = 0; i < b->na; ++i)
      b->Kr[i * b->cap + j] = b->Kr[j * b->cap + i];
  cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, (int)nb, (int)nf, (int)n, 1.0,
              h->A + b->na * n, (int)n, h->F, (int)n, 0.0, b->AF + b->na, (int)b->cap);
  free(KA);
  b->na = na;
  return FB_OK;
}

/* The Ritz solution of the first na vectors of b. */
static int ritz_of(const block_space *b, size_t na, size_t nf, ritz_basis *r, fb_err *err)
{
  r->na = na;
  r->lambda = malloc((na ? na : 1) * sizeof *r->lambda);
  r->Y = malloc((na ? na * na : 1) * sizeof *r->Y);
  r->P = malloc((na ? na * nf : 1) * sizeof *r->P);
  if (!r->lambda || !r->Y || !r->P)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t j = 0; j < na; ++j)
    memcpy(r->Y + j * na, b->Kr + j * b->cap, na * sizeof *r->Y);
  if (na && LAPACKE_dsyev(LAPACK_COL_MAJOR, 'V', 'U', (lapack_int)na, r->Y, (lapack_int)na,
                          r->lambda))
    return fb_err_set(err, FB_ESOLVER, "the hull's Ritz vectors: LAPACK dsyev failed");
  if (na)
    cblas_dgemm(CblasColMajor, CblasTrans, CblasNoTrans, (int)na, (int)nf, (int)na, 1.0, r->Y,
                (int)na, b->AF, (int)b->cap, 0.0, r->P, (int)na);
  return FB_OK;
}

/* The receptance between patterns a and b at omega (rad/s) along the
 * Ritz vectors of r (the rigid-body modes, the same in every basis, left
 * out): sum over k of P_ka P_kb / (lambda_k - omega^2 + i omega beta
 * lambda_k). */
static double complex receptance(const ritz_basis *r, size_t a, size_t b, double omega,
                                 double beta)
{
  double complex h = 0.0;
  for (size_t k = 0; k < r->na; ++k)
    h += r->P[k + a * r->na] * r->P[k + b * r->na] /
         (r->lambda[k] - omega * omega + I * omega * beta * r->lambda[k]);
  return h;
}

/* The largest change of the receptances from basis r to the larger one
 * next, over the band (0, band_hz], each pair (a, b) of patterns over its
 * scale sqrt(max |H_aa| max |H_bb|) in next (a cross term is bounded by
 * it at a static load, and round-off's zero entries need no threshold). */
static int receptance_change(const ritz_basis *r, const ritz_basis *next, size_t nf,
                             double beta, double band_hz, double *change, fb_err *err)
{
  double *peak = calloc(nf ? nf : 1, sizeof *peak);
  if (!peak)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  const double step = two_pi * band_hz / BLOCK_FREQUENCIES;
  for (size_t a = 0; a < nf; ++a)
    for (size_t k = 1; k <= BLOCK_FREQUENCIES; ++k)
      peak[a] = fmax(peak[a], cabs(receptance(next, a, a, step * (double)k, beta)));
  *change = 0.0;
  for (size_t a = 0; a < nf; ++a)
    for (size_t b = a; b < nf; ++b) {
      const double scale = sqrt(peak[a] * peak[b]);
      for (size_t k = 1; scale > 0 && k <= BLOCK_FREQUENCIES; ++k) {
        const double omega = step * (double)k;
        const double d =
            cabs(receptance(next, a, b, omega, beta) - receptance(r, a, b, omega, beta));
        *change = fmax(*change, d / scale);
      }
    }
  free(peak);
  return FB_OK;
}

/* Checks that nb vectors of ndof (the vectors, the basis and the next)
 * fit the memory limit. */
static int check_basis_memory(const vehicle_hull *h, size_t nb, fb_err *err)
{
  const double bytes = 8.0 * 3.0 * (double)nb * (double)h->info.ndof;
  return fb_check_memory(bytes, h->memory_limit, err,
                         "the hull's basis of %zu vectors of %zu DOFs", nb, h->info.ndof);
}

/* The kept modes and the Ritz vectors A Y of r: *T (ndof x (nkeep + na))
 * and *lambda, new. */
static int basis_of(const vehicle_hull *h, const ritz_basis *r, double **T, double **lambda,
                    fb_err *err)
{
  const size_t n = h->info.ndof, nk = h->nkeep, nb = nk + r->na;
  *T = malloc(n * nb * sizeof **T);
  *lambda = malloc(nb * sizeof **lambda);
  if (!*T || !*lambda)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  memcpy(*T, fb_fem_modal_shapes(h->modal), n * nk * sizeof **T);
  memcpy(*lambda, fb_fem_modal_lambda(h->modal), nk * sizeof **lambda);
  memcpy(*lambda + nk, r->lambda, r->na * sizeof **lambda);
  if (r->na)
    cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, (int)n, (int)r->na, (int)r->na, 1.0,
                h->A, (int)n, r->Y, (int)r->na, 0.0, *T + n * nk, (int)n);
  return FB_OK;
}

/* The auto basis: the residual flexibility of the patterns, then one
 * block after another until the next changes the receptances by less
 * than FB_HULL_BLOCK_TOL; T is the basis before that block, T2 (the
 * estimator's) with it. */
static int auto_blocks(vehicle_hull *h, fb_err *err)
{
  block_space space = {0, 0, NULL, NULL};
  ritz_basis cur = {0, NULL, NULL, NULL}, next = {0, NULL, NULL, NULL};
  size_t nlast = 0, blocks = 0;
  char stage[96];
  snprintf(stage, sizeof stage, "load-dependent Ritz vectors of %zu DOFs from %zu patterns",
           h->info.ndof, h->nf);
  int rc = fb_progress_report(&h->progress, stage, 0.0, err);
  if (!rc)
    rc = fb_fem_modal_extend(h->modal, h->nkeep, h->F, h->nf, &h->A, &h->nadded, &nlast, err);
  h->info.nstatic = nlast;
  if (!rc)
    rc = block_space_grow(h, &space, h->nadded, err);
  if (!rc)
    rc = ritz_of(&space, h->nadded, h->nf, &cur, err);
  for (blocks = 1; !rc; ++blocks) {
    const size_t before = h->nadded, last = nlast;
    rc = fb_progress_report(&h->progress, stage, -1.0, err);
    if (!rc)
      rc = check_basis_memory(h, h->nkeep + h->nadded + nlast, err);
    if (!rc)
      rc = fb_fem_modal_extend(h->modal, h->nkeep, h->F, h->nf, &h->A, &h->nadded, &nlast, err);
    if (!rc)
      rc = block_space_grow(h, &space, h->nadded, err);
    if (!rc)
      rc = ritz_of(&space, h->nadded, h->nf, &next, err);
    if (!rc)
      rc = receptance_change(&cur, &next, h->nf, h->info.beta, h->info.cutoff_hz,
                             &h->info.block_change, err);
    /* The basis is the one before the block that changed nothing more
     * (or no block came: the space is spanned). */
    if (!rc &&
        (h->info.block_change <= FB_HULL_BLOCK_TOL || nlast == 0 || blocks + 1 >= MAX_BLOCKS)) {
      h->nadded = before;
      h->nlast = last;
      break;
    }
    ritz_basis_free(&cur);
    cur = next;
    next = (ritz_basis){0, NULL, NULL, NULL};
  }
  if (!rc)
    rc = basis_of(h, &cur, &h->T, &h->lambda, err);
  if (!rc)
    rc = basis_of(h, &next, &h->T2, &h->lambda2, err);
  if (!rc) {
    h->nb = h->nkeep + cur.na;
    h->nb2 = h->nkeep + next.na;
    h->info.nestimate = h->nb2;
    h->info.nblocks = blocks;
    rc = fb_progress_report(&h->progress, stage, 1.0, err);
  }
  ritz_basis_free(&cur);
  ritz_basis_free(&next);
  block_space_free(&space);
  return rc;
}

/* A count or every mode: the kept modes and the residual flexibility of
 * the patterns. */
static int count_basis(vehicle_hull *h, fb_err *err)
{
  size_t nstatic = 0;
  int rc =
      fb_fem_modal_extend(h->modal, h->nkeep, h->F, h->nf, &h->A, &h->nadded, &nstatic, err);
  h->nlast = nstatic;
  h->info.nstatic = nstatic;
  h->info.nblocks = 1;
  if (!rc)
    rc = fb_fem_modal_ritz(h->modal, h->nkeep, h->A, h->nadded, &h->T, &h->lambda, err);
  if (!rc)
    h->nb = h->nkeep + h->nadded;
  return rc;
}

/* Modal coordinates: one eigen-solve and the basis. beta comes first: the
 * auto basis's criterion weighs the receptances with the damping. */
static int realise_modal(const fb_scenario *s, vehicle_hull *h, const fb_mat *built,
                         const fb_eig_opts *o, fb_vehicle_work *w, fb_err *err)
{
  size_t nmodes = 0;
  fb_eig_opts opts = *o;
  if (s->hull_modes_kind == FB_HULL_MODES_ALL)
    opts.method = FB_EIG_DENSE;
  int rc = modes_wanted(s, h, &nmodes, err);
  if (!rc)
    rc = fb_fem_modal_new(h->K, h->M, &opts, &h->modal, err);
  if (!rc)
    rc = fb_fem_modal_solve(h->modal, nmodes, 0.0, err);
  if (!rc) {
    w->hull_eigensolves++;
    h->info.eig = fb_fem_modal_info(h->modal);
    h->info.nfree = fb_fem_modal_nmodes(h->modal);
    h->info.nfree_rigid = fb_fem_modal_nrigid(h->modal);
    h->info.free_hz = fb_fem_modal_freq_hz(h->modal);
    rc = hull_beta(s, h, built, o, w, err);
  }
  if (!rc)
    rc = modes_kept(s, h, err);
  if (!rc)
    rc = patterns(s, h, err);
  if (!rc)
    rc = s->hull_modes_kind == FB_HULL_MODES_AUTO ? auto_blocks(h, err) : count_basis(h, err);
  if (!rc) {
    /* The factorisation, made once for the Lanczos steps or the static
     * correction, whichever came first. */
    h->info.eig = fb_fem_modal_info(h->modal);
    w->factorisations += h->info.eig.factor_bytes > 0;
    h->info.nmodes = h->nkeep;
    h->info.nrigid = h->info.nfree_rigid;
    h->info.nstatic = h->nadded;
    h->info.ncoords = h->nb;
  }
  return rc;
}

/* The hull's rigid-body motions, which the Lanczos solves need not find
 * (null vectors of its K), into h->rigid and o's given vectors. */
static int rigid_motions(vehicle_hull *h, fb_eig_opts *o, fb_err *err)
{
  h->rigid = malloc(6 * h->info.ndof * sizeof *h->rigid);
  if (!h->rigid)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  double centroid[3] = {0.0, 0.0, 0.0};
  const size_t nn = fb_mesh_nnodes(h->fe->mesh);
  for (size_t i = 0; i < nn; ++i)
    for (int k = 0; k < 3; ++k)
      centroid[k] += fb_mesh_node_xyz(h->fe->mesh, i)[k] / (double)nn;
  fb_mesh_rigid_modes(h->fe->mesh, centroid, h->rigid);
  o->null_vectors = h->rigid;
  o->nnull = 6;
  return FB_OK;
}

int vehicle_hull_new(const fb_scenario *s, const fb_vehicle_opts *vo, fb_vehicle_work *w,
                     vehicle_hull **out, fb_err *err)
{
  *out = NULL;
  vehicle_hull *h = calloc(1, sizeof *h);
  if (!h)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  fb_mat *built = NULL;
  fb_eig_opts o;
  fb_eig_opts_default(&o);
  fb_vehicle_opts defaults;
  fb_vehicle_opts_default(&defaults);
  if (!vo)
    vo = &defaults;
  const fb_progress *pr = &vo->progress;
  o.memory_limit = h->memory_limit =
      vo->memory_limit ? vo->memory_limit : FB_VEHICLE_MEMORY_LIMIT;
  o.threads = vo->threads;
  o.progress = vo->progress;
  h->list_modes = vo->hull_modes;
  h->progress = vo->progress;
  const int generated = !vehicle_source_mesh_current(s);
  int rc = fb_vehicle_fe_hull(s, &h->fe, err);
  if (!rc) {
    w->mesh_generations += generated;
    h->info.coordinates = s->hull_coordinates;
    h->info.kind = s->hull_modes_kind;
    h->info.ndof = 6 * fb_mesh_nnodes(h->fe->mesh);
    h->info.cutoff_hz = h->info.excitation_hz = NAN;
    rc = assemble(s, h, &built, pr, w, err);
  }
  if (!rc)
    rc = rigid_motions(h, &o, err);
  if (!rc)
    rc = s->hull_coordinates == FB_HULL_NODAL ? realise_nodal(s, h, built, &o, w, err)
                                              : realise_modal(s, h, built, &o, w, err);
  fb_mat_free(&built);
  if (rc) {
    vehicle_hull_free(&h);
    /* An error about a part of the description keeps it (the caller
     * locates it); any other gets the context. */
    if (err && !err->part.kind && rc != FB_EINTR)
      fb_err_prefix(err, "flexible hull: ");
    return rc;
  }
  *out = h;
  return FB_OK;
}

/* The estimator's basis: the same kept modes and patterns, with the next
 * load-dependent Ritz block (made with an auto basis already). */
static int enriched_basis(vehicle_hull *h, fb_err *err)
{
  if (h->T2)
    return FB_OK;
  if (!h->modal || h->info.coordinates != FB_HULL_MODAL || h->nb >= h->info.ndof)
    return fb_err_set(err, FB_EINVAL,
                      "the basis error is estimated for a reduced modal hull only");
  /* The basis's vectors, then the block after its last. */
  size_t nadded = h->nadded, nlast = h->nlast;
  double *A = malloc(h->info.ndof * (nadded ? nadded : 1) * sizeof *A);
  int rc = A ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc) {
    memcpy(A, h->A, h->info.ndof * nadded * sizeof *A);
    rc = fb_fem_modal_extend(h->modal, h->nkeep, h->F, h->nf, &A, &nadded, &nlast, err);
  }
  if (!rc)
    rc = fb_fem_modal_ritz(h->modal, h->nkeep, A, nadded, &h->T2, &h->lambda2, err);
  free(A);
  if (!rc) {
    h->nb2 = h->nkeep + nadded;
    h->info.nestimate = h->nb2;
  }
  return rc;
}

/* ---- The fragment. */

/* Matrix transformer from the hull's coordinates to the vertical
 * velocity of each of the n points: the rows of their couplings over the
 * nodal DOFs (for a point on a node, a selection), or with a basis T (ndof
 * x nb) those rows times T. */
static int add_selection(fb_bg *bg, const char *name, size_t n, const fb_hull_coupling *rows_of,
                         size_t ndof, const double *T, size_t nb, fb_err *err)
{
  fb_mat *t = NULL;
  int rc = FB_OK;
  if (T) {
    double *rows = calloc(n * nb, sizeof *rows);
    rc = rows ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
    for (size_t j = 0; !rc && j < nb; ++j)
      for (size_t i = 0; i < n; ++i)
        for (size_t k = 0; k < rows_of[i].n; ++k)
          rows[j * n + i] += rows_of[i].w[k] * T[j * ndof + rows_of[i].dof[k]];
    if (!rc)
      rc = fb_mat_new_dense(n, nb, rows, &t, err);
    free(rows);
    return rc ? rc : fb_bg_add_mtf(bg, name, &t, err);
  }
  size_t nnz = 0;
  for (size_t i = 0; i < n; ++i)
    nnz += rows_of[i].n;
  size_t *r = malloc((nnz + 1) * sizeof *r), *c = malloc((nnz + 1) * sizeof *c);
  double *v = malloc((nnz + 1) * sizeof *v);
  rc = r && c && v ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  nnz = 0;
  for (size_t i = 0; !rc && i < n; ++i)
    for (size_t k = 0; k < rows_of[i].n; ++k) {
      r[nnz] = i;
      c[nnz] = rows_of[i].dof[k];
      v[nnz++] = rows_of[i].w[k];
    }
  if (!rc)
    rc = fb_mat_new_triplets(n, ndof, nnz, r, c, v, &t, err);
  free(r);
  free(c);
  free(v);
  return rc ? rc : fb_bg_add_mtf(bg, name, &t, err);
}

/* The fields' matrices in the hull's coordinates (new): the nodal M, K
 * and beta K, or over a basis with eigenvalues lambda (nb) I, diag(lambda)
 * and diag(beta lambda). */
typedef struct hull_fields {
  fb_mat *M, *K, *B;
} hull_fields;

static void hull_fields_free(hull_fields *f)
{
  fb_mat_free(&f->M);
  fb_mat_free(&f->K);
  fb_mat_free(&f->B);
}

static int make_fields(const vehicle_hull *h, const double *lambda, size_t nb, hull_fields *f,
                       fb_err *err)
{
  const double beta = h->info.beta;
  if (!lambda) {
    int rc = fb_mat_clone(h->M, &f->M, err);
    if (!rc)
      rc = fb_mat_clone(h->K, &f->K, err);
    return rc ? rc : fb_mat_axpby(beta, h->K, 0.0, NULL, &f->B, err);
  }
  double *v = malloc(nb * sizeof *v);
  int rc = v ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; !rc && i < nb; ++i)
    v[i] = 1.0;
  if (!rc)
    rc = fb_mat_new_diag(nb, v, &f->M, err);
  if (!rc)
    rc = fb_mat_new_diag(nb, lambda, &f->K, err);
  for (size_t i = 0; !rc && i < nb; ++i)
    v[i] = beta * lambda[i];
  if (!rc)
    rc = fb_mat_new_diag(nb, v, &f->B, err);
  free(v);
  return rc;
}

/* The fragment's bonds, {name, from, to}: every one a multibond (of the
 * hull's coordinates, its attachment points or its load points). */
static const char *const bonds[][3] = {
    {"b_mass", "J", "mass"},
    {"b_stiffness", "J", "stiffness"},
    {"b_damping", "J", "damping"},
    {"b_attach_in", "J", "to_attach.1"},
    {"b_attach", "to_attach.2", "attach"},
    {"b_load_in", "J", "to_load.1"},
    {"b_load", "to_load.2", "load"},
};
enum { NBONDS = sizeof bonds / sizeof bonds[0] };

const char *vehicle_flexible_hull_bond(size_t i)
{
  return i < NBONDS ? bonds[i][0] : NULL;
}

/* The port "bushing_<k>" (IN, dimension 6) of the hull's b-th bushing,
 * its six rows as a transformer "to_bushing_<k>" from the hull's
 * coordinates, as the rigid hull's (vehicle_add_bushing_port). */
static int bushing_port(const fb_fe_hull *fe, size_t b, const double *T, size_t ndof, size_t nb,
                        fb_bg *bg, fb_err *err)
{
  const size_t k = fe->bushing_index[b];
  char mtf[48];
  snprintf(mtf, sizeof mtf, "to_bushing_%zu", k);
  const int rc = add_selection(bg, mtf, 6, &fe->bushing_rows[6 * b], ndof, T, nb, err);
  return rc ? rc : vehicle_wire_bushing_port(bg, "J", k, err);
}

static int hull_graph(const fb_fe_hull *fe, hull_fields *f, const double *T, size_t ndof,
                      size_t nb, fb_bg *bg, fb_err *err)
{
  int rc = fb_bg_add_field(bg, "mass", FB_BG_I, 1, &nb, &f->M, err);
  if (!rc)
    rc = fb_bg_add_field(bg, "stiffness", FB_BG_C, 1, &nb, &f->K, err);
  if (!rc)
    rc = fb_bg_add_field(bg, "damping", FB_BG_R, 1, &nb, &f->B, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "J", FB_BG_J1, nb, err);
  if (!rc)
    rc = add_selection(bg, "to_attach", fe->nattach, fe->attach_coupling, ndof, T, nb, err);
  if (!rc)
    rc = add_selection(bg, "to_load", fe->nload, fe->load_coupling, ndof, T, nb, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "attach", FB_BG_J1, fe->nattach, err);
  if (!rc)
    rc = fb_bg_add_junction(bg, "load", FB_BG_J1, fe->nload, err);
  for (size_t i = 0; !rc && i < NBONDS; ++i)
    rc = fb_bg_connect(bg, bonds[i][0], bonds[i][1], bonds[i][2], err);
  if (!rc)
    rc = fb_bg_add_port(bg, "attach", "attach", FB_PORT_IN, err);
  if (!rc)
    rc = fb_bg_add_port(bg, "load", "load", FB_PORT_IN, err);
  for (size_t b = 0; !rc && b < fe->nbushings; ++b)
    rc = bushing_port(fe, b, T, ndof, nb, bg, err);
  return rc;
}

/* The torsion weights over the hull's coordinates: the nodal ones w, or
 * over a basis (u = T q) T' w. */
static void to_coordinates(const double *T, size_t ndof, size_t nb, const double *w,
                           double *out)
{
  for (size_t j = 0; j < nb; ++j) {
    if (!T) {
      out[j] = w[j];
      continue;
    }
    double sum = 0.0;
    for (size_t i = 0; i < ndof; ++i)
      sum += w[i] * T[j * ndof + i];
    out[j] = sum;
  }
}

/* Torsion: roll of the front edge minus roll of the rear edge over the
 * nodal displacements (the C field's state), by the edges' end nodes and
 * by the least-squares line of every node along each edge. */
static int flexible_torsion(const fb_fe_hull *fe, const double *T, size_t ndof, size_t nb,
                            fb_hull *hull, fb_err *err)
{
  double *w = calloc(ndof, sizeof *w);
  hull->torsion_weights = calloc(nb, sizeof *hull->torsion_weights);
  hull->torsion_fit_weights = calloc(nb, sizeof *hull->torsion_fit_weights);
  hull->torsion_target = fb_strdup("stiffness");
  if (!w || !hull->torsion_weights || !hull->torsion_fit_weights || !hull->torsion_target) {
    free(w);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  hull->torsion_kind = FB_PROBE_STATE;
  hull->torsion_integrate = 0;
  hull->ntorsion = nb;
  int rc = FB_OK;
  for (int fit = 0; fit < 2 && !rc; ++fit) {
    rc = fb_fe_hull_torsion_weights(fe, fit, w, err);
    if (!rc)
      to_coordinates(T, ndof, nb, w, fit ? hull->torsion_fit_weights : hull->torsion_weights);
  }
  free(w);
  return rc;
}

/* The nodal weights w (ndof) of output o read from the hull's motion:
 * its point's (hull_point.c) or its rigid-body coordinate's fit. */
static int motion_nodal_weights(const vehicle_hull *h, const fb_output_spec *o, size_t index,
                                const vehicle_hull_motion *how, double *w, fb_err *err)
{
  if (how->coordinate < 0)
    return vehicle_hull_point_weights(h->fe->mesh, o, index, w, err);
  return vehicle_hull_rigid_fit(h->fe->mesh, h->M, how->coordinate, w, err);
}

/* A surface stress, w' u over the nodal displacements u = T q of the
 * stiffness field's state (the hull's deformation itself, as a
 * torsion's: with a static initial state its static stress too), w the
 * component's row of its element's recovery matrix; weights T' w (w
 * (ndof) and q (nb) scratch). */
static int stress_reading(const vehicle_hull *h, const fb_output_spec *o, size_t index,
                          const double *T, size_t nb, double *w, double *q, fb_hull_reading *r,
                          fb_err *err)
{
  int rc = vehicle_hull_stress_weights(h->fe->mesh, &h->fe->props, o, index, w, err);
  if (rc)
    return rc;
  to_coordinates(T, h->info.ndof, nb, w, q);
  return vehicle_hull_reading_set(r, "stiffness", FB_PROBE_STATE, 0, q, nb, err);
}

/* The outputs read from the hull's motion, w' u over the nodal
 * displacements u = T q: a displacement from t = 0 is the integrated
 * flow of b_mass (q') weighted by T' w, a velocity its flow, and an
 * acceleration w' T q'' with q'' = M_q^-1 p' (p' the effort on the mass
 * field's bond b_mass): over a basis M_q = I, the weights T' w; nodal,
 * M^-1 w (one solve with M's factor, M symmetric). */
static int flexible_readings(const fb_scenario *s, const vehicle_hull *h, const double *T,
                             size_t nb, fb_hull *hull, fb_err *err)
{
  const size_t ndof = h->info.ndof;
  double *w = malloc(ndof * sizeof *w), *q = malloc(nb * sizeof *q);
  fb_chol *mfactor = NULL;
  int rc = w && q ? vehicle_hull_readings_new(s, hull, err)
                  : fb_err_set(err, FB_ENOMEM, "out of memory");
  vehicle_hull_motion how;
  for (size_t o = 0; !rc && o < s->noutputs; ++o) {
    if (vehicle_output_hull_stress(&s->output[o])) {
      rc = stress_reading(h, &s->output[o], o, T, nb, w, q, &hull->reading[o], err);
      continue;
    }
    if (!vehicle_output_hull_motion(&s->output[o], &how))
      continue;
    rc = motion_nodal_weights(h, &s->output[o], o, &how, w, err);
    if (!rc && how.derivative == 2 && !T && !mfactor)
      rc = fb_chol_new(h->M, h->memory_limit, &mfactor, err);
    if (!rc && how.derivative == 2 && !T)
      rc = fb_chol_solve(mfactor, w, 1, err);
    if (rc)
      break;
    to_coordinates(T, ndof, nb, w, q);
    rc = vehicle_hull_reading_set(&hull->reading[o], "b_mass",
                                  how.derivative == 2 ? FB_PROBE_EFFORT : FB_PROBE_FLOW,
                                  how.derivative == 0, q, nb, err);
  }
  fb_chol_free(&mfactor);
  free(w);
  free(q);
  return rc;
}

/* The basis a fragment uses: none (nodal), the run's or the estimator's. */
static void fragment_basis(const vehicle_hull *h, int enriched, const double **T,
                           const double **lambda, size_t *nb)
{
  *T = enriched ? h->T2 : h->T;
  *lambda = enriched ? h->lambda2 : h->lambda;
  *nb = enriched ? h->nb2 : h->nb;
}

int vehicle_hull_fragment(const fb_scenario *s, vehicle_hull *h, int enriched, fb_hull **out,
                          fb_err *err)
{
  *out = NULL;
  int rc = enriched ? enriched_basis(h, err) : FB_OK;
  if (rc)
    return rc;
  const double *T = NULL, *lambda = NULL;
  size_t nb = 0;
  fragment_basis(h, enriched, &T, &lambda, &nb);
  fb_hull *hull = calloc(1, sizeof *hull);
  hull_fields f = {NULL, NULL, NULL};
  rc = hull ? fb_bg_new("flexible_hull", &hull->graph, err)
            : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = make_fields(h, lambda, nb, &f, err);
  if (!rc)
    rc = hull_graph(h->fe, &f, T, h->info.ndof, nb, hull->graph, err);
  if (!rc)
    rc = flexible_torsion(h->fe, T, h->info.ndof, nb, hull, err);
  if (!rc)
    rc = flexible_readings(s, h, T, nb, hull, err);
  if (!rc)
    hull->carries_bodies = 1;
  hull_fields_free(&f);
  if (rc) {
    fb_hull_free(&hull);
    return rc;
  }
  *out = hull;
  return FB_OK;
}

int fb_vehicle_flexible_hull(const fb_scenario *s, const fb_fe_hull *h, fb_hull **out,
                             fb_err *err)
{
  (void)h;
  *out = NULL;
  fb_vehicle_work w;
  memset(&w, 0, sizeof w);
  vehicle_hull *vh = NULL;
  int rc = vehicle_hull_new(s, NULL, &w, &vh, err);
  if (!rc)
    rc = vehicle_hull_fragment(s, vh, 0, out, err);
  vehicle_hull_free(&vh);
  return rc;
}

/* ---- The undamped System 2's modes. */

/* The reduced row t (nb) of a coupling: t_j = sum_l w_l T[j][dof_l]. */
static void reduced_row(const vehicle_hull *h, const fb_hull_coupling *c, double *t)
{
  for (size_t j = 0; j < h->nb; ++j) {
    t[j] = 0.0;
    for (size_t l = 0; l < c->n; ++l)
      t[j] += c->w[l] * h->T[j * h->info.ndof + c->dof[l]];
  }
}

/* k r r' added to K (nv x nv, column-major), r (room for nv + nb) a
 * combination of two wheels' travels relative to the hull over the
 * reduced variables: sa (e_wa - t_a) + sb (e_wb - t_b), t the reduced rows
 * of the couplings ca and cb (an anti-roll bar's stiffness on its twist,
 * sa = 1, sb = -1; a bogie's pivot spring, its lever's weights). */
static void add_reduced_twist(const vehicle_hull *h, size_t nv, size_t wa,
                              const fb_hull_coupling *ca, double sa, size_t wb,
                              const fb_hull_coupling *cb, double sb, double k, double *r,
                              double *K)
{
  const size_t nb = h->nb;
  memset(r, 0, nv * sizeof *r);
  reduced_row(h, ca, r);
  for (size_t j = 0; j < nb; ++j)
    r[j] *= -sa;
  double *tb = r + nv; /* scratch */
  reduced_row(h, cb, tb);
  for (size_t j = 0; j < nb; ++j)
    r[j] -= sb * tb[j];
  r[wa] += sa;
  r[wb] += sb;
  for (size_t j = 0; j < nv; ++j)
    for (size_t i = 0; i < nv; ++i)
      K[j * nv + i] += k * r[i] * r[j];
}

/* The rigid bodies in the reduced matrices (nv x nv, column-major):
 * their inertias, and each bushing's K G' K_b G with its relative rows
 * G (vehicle_bushing_relative_rows over the nodal layout) taken to the
 * basis, u = T q for the hull's part. */
static int reduced_bodies(const fb_scenario *s, const vehicle_hull *h, size_t nv, double *K,
                          double *M, fb_err *err)
{
  const size_t nb = h->nb, ndof = h->info.ndof, base = nb + s->nmounts + s->ncorners;
  for (size_t i = 0; i < s->nbodies; ++i) {
    double m[36];
    vehicle_body_inertia6(&s->body[i], m);
    for (size_t r = 0; r < 6; ++r)
      for (size_t c = 0; c < 6; ++c)
        M[(base + 6 * i + c) * nv + base + 6 * i + r] = m[6 * r + c];
  }
  double *g = malloc(6 * nv * sizeof *g);
  if (!g)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  int rc = FB_OK;
  size_t b = 0, j = 0;
  for (size_t k = 0; !rc && fb_scenario_bushing_at(s, k, &b, &j); ++k) {
    fb_hull_coupling rows[6];
    rc = vehicle_bushing_relative_rows(s, h->fe, k, ndof + s->nmounts + s->ncorners, rows, err);
    memset(g, 0, 6 * nv * sizeof *g);
    for (int l = 0; !rc && l < 6; ++l) {
      double *gl = g + (size_t)l * nv;
      for (size_t e = 0; e < rows[l].n; ++e) {
        const size_t d = rows[l].dof[e];
        if (d >= ndof) { /* a body's own DOF */
          gl[d - ndof + nb] += rows[l].w[e];
          continue;
        }
        for (size_t q = 0; q < nb; ++q)
          gl[q] += rows[l].w[e] * h->T[q * ndof + d];
      }
    }
    for (int l = 0; !rc && l < 6; ++l)
      fb_hull_coupling_free(&rows[l]);
    const double *kb = s->body[b].bushing[j].k;
    for (int l = 0; !rc && l < 6; ++l)
      for (int m = 0; m < 6; ++m) {
        if (kb[6 * l + m] == 0.0)
          continue;
        for (size_t c = 0; c < nv; ++c)
          for (size_t r = 0; g[(size_t)m * nv + c] != 0.0 && r < nv; ++r)
            K[c * nv + r] += kb[6 * l + m] * g[(size_t)l * nv + r] * g[(size_t)m * nv + c];
      }
  }
  free(g);
  return rc;
}

/* Over a basis: the hull's coordinates q (M = I, K = diag(lambda)), then
 * the bodies' and the wheels' motions, the springs through the points'
 * rows t_a = coupling row times T: the Ritz matrices of
 * fb_vehicle_matrices' K and M, dense (*k and *m, n x n column-major,
 * new). */
static int reduced_matrices(const fb_scenario *s, const vehicle_hull *h, double **k, double **m,
                            size_t *n, fb_err *err)
{
  const fb_fe_hull *fe = h->fe;
  const size_t nb = h->nb, nm = s->nmounts;
  const size_t nv = nb + vehicle_nlumped(s);
  double *K = calloc(nv * nv, sizeof *K), *M = calloc(nv * nv, sizeof *M);
  /* A reduced row (nb), or a bar's or bogie's (nv, and nb of scratch). */
  double *t = malloc((nv + nb) * sizeof *t);
  if (!K || !M || !t) {
    free(K);
    free(M);
    free(t);
    return fb_err_set(err, FB_ENOMEM, "out of memory for System 2's %zu x %zu matrices", nv,
                      nv);
  }
  for (size_t i = 0; i < nb; ++i) {
    K[i * nv + i] = h->lambda[i];
    M[i * nv + i] = 1.0;
  }
  for (size_t a = 0; a < fe->nattach; ++a) {
    /* Attachment a is corner a (its wheel) or mount a - ncorners. */
    const int corner = a < s->ncorners;
    const size_t body = corner ? nb + nm + a : nb + (a - s->ncorners);
    const fb_corner_params *cp = corner ? &s->corner[a] : NULL;
    /* A bogie's wheel has no spring of its own: the bogie's is below. */
    const double ks = !corner ? s->mount[a - s->ncorners].stiffness
                      : vehicle_corner_bogie(s, a, NULL) >= 0
                          ? 0.0
                          : cp->motion_ratio * cp->motion_ratio * cp->spring_k;
    reduced_row(h, &fe->attach_coupling[a], t);
    /* k (e_body - t)(e_body - t)' */
    for (size_t j = 0; j < nb; ++j) {
      for (size_t i = 0; i < nb; ++i)
        K[j * nv + i] += ks * t[i] * t[j];
      K[j * nv + body] -= ks * t[j];
      K[body * nv + j] -= ks * t[j];
    }
    K[body * nv + body] += ks + (corner ? cp->tire_k : 0.0);
    M[body * nv + body] = corner ? cp->wheel_mass : s->mount[a - s->ncorners].mass;
  }
  for (size_t i = 0; i < s->nantiroll_bars; ++i) {
    const long l = fb_scenario_corner_find(s, s->antiroll_bar[i].left);
    const long r = fb_scenario_corner_find(s, s->antiroll_bar[i].right);
    if (l >= 0 && r >= 0) /* fb_scenario_check found both */
      add_reduced_twist(h, nv, nb + nm + (size_t)l, &fe->attach_coupling[l], 1.0,
                        nb + nm + (size_t)r, &fe->attach_coupling[r], -1.0,
                        0.5 * s->antiroll_bar[i].stiffness, t, K);
  }
  for (size_t i = 0; i < s->nbogies; ++i) {
    long f = -1, r = -1;
    double mb[4], w[2];
    if (!vehicle_bogie_wheels(s, i, &f, &r, mb, w))
      continue;
    const size_t at[2] = {nb + nm + (size_t)f, nb + nm + (size_t)r};
    for (int p = 0; p < 4; ++p)
      M[at[p % 2] * nv + at[p / 2]] = mb[p];
    add_reduced_twist(h, nv, at[0], &fe->attach_coupling[f], w[0], at[1],
                      &fe->attach_coupling[r], w[1], s->bogie[i].spring_k, t, K);
  }
  free(t);
  const int rc = reduced_bodies(s, h, nv, K, M, err);
  if (rc) {
    free(K);
    free(M);
    return rc;
  }
  *k = K;
  *m = M;
  *n = nv;
  return FB_OK;
}

/* The reduced modes' shapes over fb_vehicle_matrices' DOFs: T q for the
 * hull, the bodies' and wheels' own (*shapes new, nv modes). */
static int expand_shapes(const vehicle_hull *h, const double *z, size_t nv, size_t nmodes,
                         size_t nfull, double **shapes, fb_err *err)
{
  const size_t nb = h->nb, ndof = h->info.ndof;
  double *v = malloc(nfull * nmodes * sizeof *v);
  if (!v)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu mode shapes", nmodes);
  for (size_t k = 0; k < nmodes; ++k) {
    const double *q = z + k * nv;
    double *u = v + k * nfull;
    for (size_t i = 0; i < ndof; ++i) {
      double sum = 0.0;
      for (size_t j = 0; j < nb; ++j)
        sum += h->T[j * ndof + i] * q[j];
      u[i] = sum;
    }
    memcpy(u + ndof, q + nb, (nv - nb) * sizeof *u);
  }
  *shapes = v;
  return FB_OK;
}

/* The Ritz modes of the reduced System 2 up to the basis's cut-off (all
 * when the basis has none), at most nwant + 3 (the free horizontal
 * rigid-body modes left out afterwards), into *freq and *shapes (new). */
static int reduced_modes(const fb_scenario *s, const vehicle_hull *h, size_t nwant,
                         size_t nfull, double **freq, double **shapes, size_t *count,
                         fb_err *err)
{
  double *k = NULL, *m = NULL;
  size_t nv = 0;
  int rc = reduced_matrices(s, h, &k, &m, &nv, err);
  double *w = rc ? NULL : malloc(nv * sizeof *w);
  if (!rc && !w)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc && LAPACKE_dsygvd(LAPACK_COL_MAJOR, 1, 'V', 'U', (lapack_int)nv, k, (lapack_int)nv, m,
                            (lapack_int)nv, w))
    rc = fb_err_set(err, FB_ESOLVER, "System 2's reduced modes: LAPACK dsygvd failed");
  size_t n = 0;
  const double cutoff = isnan(h->info.cutoff_hz) ? INFINITY : h->info.cutoff_hz;
  while (!rc && n < nv && n < nwant + 3 && sqrt(fmax(w[n], 0.0)) / two_pi <= cutoff)
    ++n;
  for (size_t i = 0; !rc && i < n; ++i)
    w[i] = sqrt(fmax(w[i], 0.0)) / two_pi;
  if (!rc)
    rc = expand_shapes(h, k, nv, n, nfull, shapes, err);
  free(k);
  free(m);
  if (rc) {
    free(w);
    return rc;
  }
  *freq = w;
  *count = n;
  return FB_OK;
}

/* On the nodal matrices, sparse: nwant + 3 lowest modes. */
static int nodal_modes(const vehicle_hull *h, const fb_mat *K, const fb_mat *M, size_t nwant,
                       double **freq, double **shapes, size_t *count, fb_vehicle_work *w,
                       fb_err *err)
{
  const size_t n = fb_mat_nrows(K), nm = nwant + 3 < n ? nwant + 3 : n;
  fb_eig_opts o;
  fb_eig_opts_default(&o);
  o.memory_limit = h->memory_limit;
  fb_fem_modal *fm = NULL;
  int rc = fb_fem_modal_new(K, M, &o, &fm, err);
  if (!rc)
    rc = fb_fem_modal_solve(fm, nm, 0.0, err);
  if (!rc) {
    w->factorisations += fb_fem_modal_info(fm).factor_bytes > 0;
    *freq = malloc(nm * sizeof **freq);
    *shapes = malloc(n * nm * sizeof **shapes);
    if (!*freq || !*shapes)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory for %zu modes", nm);
  }
  if (!rc) {
    memcpy(*freq, fb_fem_modal_freq_hz(fm), nm * sizeof **freq);
    memcpy(*shapes, fb_fem_modal_shapes(fm), n * nm * sizeof **shapes);
    *count = nm;
  }
  fb_fem_modal_free(&fm);
  return rc;
}

int vehicle_hull_structural_modes(const fb_scenario *s, vehicle_hull *h, size_t nmodes,
                                  int exact, fb_vehicle_work *w, fb_mode_set **out, fb_err *err)
{
  *out = NULL;
  fb_mat *K = NULL, *M = NULL;
  double *freq = NULL, *shapes = NULL;
  size_t count = 0;
  const int reduced = !exact && h->info.coordinates == FB_HULL_MODAL && h->nb < h->info.ndof;
  const size_t nfull = h->info.ndof + vehicle_nlumped(s);
  /* Reduced: a dense problem over the basis; else the sparse matrices of
   * the whole vehicle. */
  int rc = reduced ? reduced_modes(s, h, nmodes, nfull, &freq, &shapes, &count, err)
                   : fb_vehicle_matrices(s, h->fe, h->K, h->M, &K, &M, err);
  if (!rc && !reduced)
    rc = nodal_modes(h, K, M, nmodes, &freq, &shapes, &count, w, err);
  fb_mode_set *ms = NULL;
  if (!rc) {
    w->vehicle_eigensolves++;
    rc = fb_mode_set_new(nmodes, nfull, &ms, err);
  }
  if (!rc) {
    ms->nsolved = count;
    rc = fb_vehicle_mode_set_fill(s, h->fe, h->M, freq, shapes, count, ms, err);
  }
  free(freq);
  free(shapes);
  fb_mat_free(&K);
  fb_mat_free(&M);
  if (rc) {
    fb_mode_set_free(&ms);
    return rc;
  }
  *out = ms;
  return FB_OK;
}

const double *vehicle_hull_coordinate_basis(const vehicle_hull *h, size_t *nb)
{
  *nb = h->nb;
  return h->info.coordinates == FB_HULL_MODAL ? h->T : NULL;
}
