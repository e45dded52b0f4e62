/* SPDX-License-Identifier: BSD-3-Clause */
/* System 1 of examples/apc6x6.yaml (the paper's 6x6 APC with the rigid
 * hull) written by hand as 28 ODEs and integrated with CVODE as flexbond
 * integrates it (src/sim/cvode.c): BDF up to order 5, scalar rtol/atol,
 * no step limit, a dense Newton matrix I - gamma J formed by a linear-
 * system function from the constant Jacobian (always current), the setup
 * refreshed only when gamma moves (LSetupFrequency 1000, as flexbond does
 * for a linear model), one step at a time with a stop and a restart
 * (CVodeReInit) at every kink of the road, and the outputs interpolated
 * at the samples with CVodeGetDky. No flexbond code is used: this is the
 * baseline its solver time is measured against (bench/README.md).
 *
 * States, in flexbond's order (`flexbond export --system rigid`,
 * model.json): the hull's momenta (bounce, roll, pitch); per mount
 * (driver, engine) its momentum and spring compression; per corner (LF,
 * RF, LM, RM, LR, RR) wheel momentum, spring compression and tire
 * compression; and the three integrals of the hull's velocities that
 * flexbond keeps for the torsion output (zero weights on a rigid hull,
 * but the error control sees them, so they are kept here too).
 *
 * Usage: system1_hand [-o FILE.csv] [--rtol X] [--atol Y] [--repeat N]
 * Writes the columns of `flexbond run examples/apc6x6.yaml --system rigid`
 * (system1.csv, %.10g) and prints on stderr the solver time (wall, and
 * the thread's CPU time) of each of the N runs in one process (N > 1),
 * their median and the solver statistics. */
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <time.h>

/* ---- The vehicle (examples/apc6x6.yaml; docs/reference-vehicle.md). */

#define NCORNERS 6
#define NMOUNTS 2
#define NLOAD 56
#define NSTATES (3 + 2 * NMOUNTS + 3 * NCORNERS + 3)

static const double GRAVITY = 9.81;
static const double HULL_M[3] = {4041.72, 4173.49, 15175.96}; /* mass, Ixx, Iyy */
static const double TOTAL_WEIGHT = 117720.0;                  /* hull plus payload, N */

typedef struct mount {
  double mass, k, c, x, y;
} mount;
static const mount MOUNTS[NMOUNTS] = {
    {100.0, 19620.0, 1400.0, 2.10, 0.55},    /* driver plus seat */
    {500.0, 122625.0, 24761.0, 1.70, -0.55}, /* engine */
};

typedef struct corner {
  double k, c, x, y;
} corner;
/* LF, RF, LM, RM, LR, RR: spring, shock absorber, hull attachment point. */
static const corner CORNERS[NCORNERS] = {
    {145300.0, 25744.0, 1.90, 1.05},  {145300.0, 25744.0, 1.90, -1.05},
    {345550.0, 25744.0, 0.40, 1.05},  {345550.0, 25744.0, 0.40, -1.05},
    {602100.0, 39656.0, -1.00, 1.05}, {602100.0, 39656.0, -1.00, -1.05},
};
static const char *const CORNER_NAMES[NCORNERS] = {"LF", "RF", "LM", "RM", "LR", "RR"};
static const double WHEEL_MASS = 175.0, TIRE_K = 500000.0, TIRE_C = 140000.0;
static const double MOTION_RATIO = 1.0;

/* The 56 load points: a 14 x 4 grid. */
static const double LOAD_X[14] = {-2.00, -1.70, -1.35, -1.00, -0.75, -0.45, -0.15,
                                  0.10,  0.40,  0.65,  0.95,  1.30,  1.90,  2.10};
static const double LOAD_Y[4] = {-1.05, -0.55, 0.55, 1.05};

/* Torsion edges (hull.edges). */
static const double EDGE_FRONT_X = 2.47813311938948, EDGE_REAR_X = -2.65798412344113;
static const double EDGE_LEFT_Y = 1.05, EDGE_RIGHT_Y = -1.05;

/* The oblique (1 - cos) bump. */
static const double BUMP_H = 0.10, BUMP_L = 3.70, BUMP_ANGLE_DEG = 45.0, FIRST_CONTACT = 5.0;
static const double SPEED_KMH = 10.0;
static const double PI = 3.14159265358979323846;

/* The study. */
static const double T_END = 15.0, SAMPLE_RATE = 1000.0;
static const double RTOL = 1e-6, ATOL = 1e-8;

/* State indices. */
enum { HULL = 0, MOUNT0 = 3, CORNER0 = 3 + 2 * NMOUNTS, TORSION0 = CORNER0 + 3 * NCORNERS };

#define NOUT 7

/* ---- The model. */

typedef struct model {
  double speed;                 /* m/s */
  double entry[NCORNERS];       /* each wheel's bump entry time */
  double gen_load[3];           /* the load's generalised force on the hull */
  double rm[NMOUNTS][3];        /* rigid rows [1, y, -x] of the attachment points */
  double rc[NCORNERS][3];       /* ... of the corners */
  double torsion_w[3];          /* weights of the torsion output on the integrals */
  double jac[NSTATES][NSTATES]; /* the constant Jacobian, row-major */
  double t_limit, t_left;       /* the current segment's end and the double below it */
} model;

static void rigid_row(double x, double y, double *r)
{
  r[0] = 1.0;
  r[1] = y;
  r[2] = -x;
}

/* Vertical velocity of the road under corner c at model time t:
 * V z'(s) for the bump z(s) = (h/2)(1 - cos(2 pi s / L)), 0 <= s <= L. */
static double road_rate(const model *m, int c, double t)
{
  const double s = m->speed * (t - m->entry[c]);
  if (s < 0.0 || s > BUMP_L)
    return 0.0;
  return m->speed * PI * BUMP_H / BUMP_L * sin(2.0 * PI * s / BUMP_L);
}

/* x' = f(t, x); also the driver's acceleration and the signals the
 * outputs read (sig: LF tire force, LM shock power, LR tire power), when
 * asked. */
typedef struct signals {
  double tire_force[NCORNERS], shock_power[NCORNERS], tire_power[NCORNERS];
} signals;

static void rhs(const model *m, double t, const double *x, double *dx, signals *sig)
{
  double v[3];
  for (int i = 0; i < 3; ++i) {
    v[i] = x[HULL + i] / HULL_M[i];
    dx[HULL + i] = m->gen_load[i];
    dx[TORSION0 + i] = v[i];
  }
  for (int b = 0; b < NMOUNTS; ++b) {
    const mount *mt = &MOUNTS[b];
    const double *r = m->rm[b];
    const double va = r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    const double vrel = va - x[MOUNT0 + 2 * b] / mt->mass;
    const double f = mt->k * x[MOUNT0 + 2 * b + 1] + mt->c * vrel;
    dx[MOUNT0 + 2 * b] = -mt->mass * GRAVITY + f;
    dx[MOUNT0 + 2 * b + 1] = vrel;
    for (int i = 0; i < 3; ++i)
      dx[HULL + i] -= r[i] * f;
  }
  for (int c = 0; c < NCORNERS; ++c) {
    const corner *cn = &CORNERS[c];
    const double *r = m->rc[c], *xc = x + CORNER0 + 3 * c;
    double *dxc = dx + CORNER0 + 3 * c;
    const double va = r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    const double vw = xc[0] / WHEEL_MASS;
    const double vsp = MOTION_RATIO * (vw - va);
    const double fd = cn->c * vsp;
    const double es = MOTION_RATIO * (cn->k * xc[1] + fd);
    const double vt = road_rate(m, c, t) - vw;
    const double ftd = TIRE_C * vt;
    const double ft = TIRE_K * xc[2] + ftd;
    dxc[0] = -WHEEL_MASS * GRAVITY + ft - es;
    dxc[1] = vsp;
    dxc[2] = vt;
    for (int i = 0; i < 3; ++i)
      dx[HULL + i] += r[i] * es;
    if (sig) {
      sig->tire_force[c] = ft;
      sig->shock_power[c] = fd * vsp;
      sig->tire_power[c] = ftd * vt;
    }
  }
}

/* The Jacobian of rhs, written out: dva/dp_hull = r ./ M. */
static void jacobian(model *m)
{
  memset(m->jac, 0, sizeof m->jac);
  double(*J)[NSTATES] = m->jac;
  for (int i = 0; i < 3; ++i)
    J[TORSION0 + i][HULL + i] = 1.0 / HULL_M[i];
  for (int b = 0; b < NMOUNTS; ++b) {
    const mount *mt = &MOUNTS[b];
    const double *r = m->rm[b];
    const int p = MOUNT0 + 2 * b, q = p + 1;
    for (int j = 0; j < 3; ++j) {
      const double g = r[j] / HULL_M[j];
      J[q][HULL + j] += g;
      J[p][HULL + j] += mt->c * g;
      for (int i = 0; i < 3; ++i)
        J[HULL + i][HULL + j] -= r[i] * mt->c * g;
    }
    J[q][p] = -1.0 / mt->mass;
    J[p][p] = -mt->c / mt->mass;
    J[p][q] = mt->k;
    for (int i = 0; i < 3; ++i) {
      J[HULL + i][p] += r[i] * mt->c / mt->mass;
      J[HULL + i][q] -= r[i] * mt->k;
    }
  }
  const double mr2 = MOTION_RATIO * MOTION_RATIO;
  for (int c = 0; c < NCORNERS; ++c) {
    const corner *cn = &CORNERS[c];
    const double *r = m->rc[c];
    const int w = CORNER0 + 3 * c, s = w + 1, t = w + 2;
    for (int j = 0; j < 3; ++j) {
      const double g = r[j] / HULL_M[j];
      J[s][HULL + j] -= MOTION_RATIO * g;
      J[w][HULL + j] += mr2 * cn->c * g;
      for (int i = 0; i < 3; ++i)
        J[HULL + i][HULL + j] -= r[i] * mr2 * cn->c * g;
    }
    J[s][w] = MOTION_RATIO / WHEEL_MASS;
    J[t][w] = -1.0 / WHEEL_MASS;
    J[w][w] = -(TIRE_C + mr2 * cn->c) / WHEEL_MASS;
    J[w][s] = -MOTION_RATIO * cn->k;
    J[w][t] = TIRE_K;
    for (int i = 0; i < 3; ++i) {
      J[HULL + i][s] += r[i] * MOTION_RATIO * cn->k;
      J[HULL + i][w] += r[i] * mr2 * cn->c / WHEEL_MASS;
    }
  }
}

static void model_init(model *m)
{
  memset(m, 0, sizeof *m);
  m->speed = SPEED_KMH / 3.6;
  const double tan_a = tan(BUMP_ANGLE_DEG * PI / 180.0);
  for (int c = 0; c < NCORNERS; ++c) {
    const corner *cn = &CORNERS[c];
    m->entry[c] =
        FIRST_CONTACT + ((CORNERS[0].x - cn->x) + (CORNERS[0].y - cn->y) * tan_a) / m->speed;
    rigid_row(cn->x, cn->y, m->rc[c]);
  }
  for (int b = 0; b < NMOUNTS; ++b)
    rigid_row(MOUNTS[b].x, MOUNTS[b].y, m->rm[b]);
  const double each = -TOTAL_WEIGHT / NLOAD;
  for (int i = 0; i < 14; ++i)
    for (int j = 0; j < 4; ++j) {
      double r[3];
      rigid_row(LOAD_X[i], LOAD_Y[j], r);
      for (int k = 0; k < 3; ++k)
        m->gen_load[k] += r[k] * each;
    }
  double fl[3], fr[3], rl[3], rr[3];
  rigid_row(EDGE_FRONT_X, EDGE_LEFT_Y, fl);
  rigid_row(EDGE_FRONT_X, EDGE_RIGHT_Y, fr);
  rigid_row(EDGE_REAR_X, EDGE_LEFT_Y, rl);
  rigid_row(EDGE_REAR_X, EDGE_RIGHT_Y, rr);
  const double dy = EDGE_LEFT_Y - EDGE_RIGHT_Y;
  for (int i = 0; i < 3; ++i)
    m->torsion_w[i] = (fl[i] - fr[i]) / dy - (rl[i] - rr[i]) / dy;
  jacobian(m);
}

/* Outputs at (t, x): tire_force_LF, spring_defl_RF, torsion, driver_acc,
 * shock_power_LM, tire_defl_RM, tire_power_LR. */
static void outputs(const model *m, double t, const double *x, double *y)
{
  double dx[NSTATES];
  signals sig;
  rhs(m, t, x, dx, &sig);
  y[0] = sig.tire_force[0];
  y[1] = x[CORNER0 + 3 * 1 + 1];
  y[2] = 0.0 + m->torsion_w[0] * x[TORSION0] + m->torsion_w[1] * x[TORSION0 + 1] +
         m->torsion_w[2] * x[TORSION0 + 2];
  y[3] = dx[MOUNT0] / MOUNTS[0].mass;
  y[4] = sig.shock_power[2];
  y[5] = x[CORNER0 + 3 * 3 + 2];
  y[6] = sig.tire_power[4];
}

/* ---- CVODE callbacks. */

/* Inputs at the end of a segment take their left limit (as flexbond). */
static double model_time(const model *m, double t)
{
  return t < m->t_limit ? t : m->t_left;
}

static int cv_rhs(double t, N_Vector y, N_Vector ydot, void *user_data)
{
  const model *m = user_data;
  rhs(m, model_time(m, t), N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), NULL);
  return 0;
}

/* A = I - gamma J from the constant Jacobian: always current. */
static int cv_linsys(double t, N_Vector y, N_Vector fy, SUNMatrix A, booleantype jok,
                     booleantype *jcur, double gamma, void *user_data, N_Vector tmp1,
                     N_Vector tmp2, N_Vector tmp3)
{
  (void)t;
  (void)y;
  (void)fy;
  (void)jok;
  (void)tmp1;
  (void)tmp2;
  (void)tmp3;
  const model *m = user_data;
  for (sunindextype j = 0; j < NSTATES; ++j) {
    double *col = SUNDenseMatrix_Column(A, j);
    for (sunindextype i = 0; i < NSTATES; ++i)
      col[i] = (i == j ? 1.0 : 0.0) - gamma * m->jac[i][j];
  }
  *jcur = SUNTRUE;
  return 0;
}

/* ---- The run. */

typedef struct stats {
  long steps, rhs_evals, setups, newton_iters, err_fails;
  double seconds, cpu_seconds; /* wall, and the thread's CPU time */
} stats;

static double clock_seconds(clockid_t id)
{
  struct timespec ts;
  clock_gettime(id, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static int check(int flag, const char *call)
{
  if (flag < 0)
    fprintf(stderr, "system1_hand: %s failed with flag %d\n", call, flag);
  return flag < 0;
}

static void add_stats(void *cv, stats *st)
{
  long v = 0;
  CVodeGetNumSteps(cv, &v);
  st->steps += v;
  CVodeGetNumRhsEvals(cv, &v);
  st->rhs_evals += v;
  CVodeGetNumLinSolvSetups(cv, &v);
  st->setups += v;
  CVodeGetNumNonlinSolvIters(cv, &v);
  st->newton_iters += v;
  CVodeGetNumErrTestFails(cv, &v);
  st->err_fails += v;
}

/* The run from the all-zero state: nsamples rows of 1 + NOUT columns into
 * table. The timed part is what flexbond's fb_sim_run times: CVODE's set-
 * up, the integration and the outputs at the samples. */
static int simulate(model *m, double rtol, double atol, size_t nsamples, double *table,
                    stats *st)
{
  const double t0 = clock_seconds(CLOCK_MONOTONIC), c0 = clock_seconds(CLOCK_THREAD_CPUTIME_ID);
  memset(st, 0, sizeof *st);
  SUNContext ctx = NULL;
  if (SUNContext_Create(NULL, &ctx) != 0)
    return 1;
  N_Vector y = N_VNew_Serial(NSTATES, ctx), ysam = N_VNew_Serial(NSTATES, ctx);
  SUNMatrix A = SUNDenseMatrix(NSTATES, NSTATES, ctx);
  SUNLinearSolver ls = A && y ? SUNLinSol_Dense(y, A, ctx) : NULL;
  void *cv = CVodeCreate(CV_BDF, ctx);
  int bad = !y || !ysam || !A || !ls || !cv;
  if (!bad) {
    N_VConst(0.0, y);
    bad = check(CVodeInit(cv, cv_rhs, 0.0, y), "CVodeInit") ||
          check(CVodeSetUserData(cv, m), "CVodeSetUserData") ||
          check(CVodeSStolerances(cv, rtol, atol), "CVodeSStolerances") ||
          check(CVodeSetMaxOrd(cv, 5), "CVodeSetMaxOrd") ||
          check(CVodeSetMaxStep(cv, 0.0), "CVodeSetMaxStep") ||
          check(CVodeSetLinearSolver(cv, ls, A), "CVodeSetLinearSolver") ||
          check(CVodeSetLinSysFn(cv, cv_linsys), "CVodeSetLinSysFn") ||
          check(CVodeSetLinearSolutionScaling(cv, SUNTRUE), "CVodeSetLinearSolutionScaling") ||
          check(CVodeSetLSetupFrequency(cv, 1000), "CVodeSetLSetupFrequency");
  }
  /* The road's kinks: each wheel's bump entry and exit, sorted. */
  double bps[2 * NCORNERS + 1];
  for (int c = 0; c < NCORNERS; ++c) {
    bps[2 * c] = m->entry[c];
    bps[2 * c + 1] = m->entry[c] + BUMP_L / m->speed;
  }
  qsort(bps, 2 * NCORNERS, sizeof *bps, cmp_double);
  bps[2 * NCORNERS] = T_END;
  table[0] = 0.0;
  outputs(m, 0.0, N_VGetArrayPointer(y), table + 1);
  size_t next = 1;
  double t = 0.0;
  for (int seg = 0; !bad && seg <= 2 * NCORNERS; ++seg) {
    if (seg > 0) {
      add_stats(cv, st);
      bad = check(CVodeReInit(cv, t, y), "CVodeReInit");
    }
    const double t_stop = bps[seg];
    m->t_limit = t_stop;
    m->t_left = nextafter(t_stop, -INFINITY);
    bad = bad || check(CVodeSetStopTime(cv, t_stop), "CVodeSetStopTime");
    int flag = 0;
    while (!bad && flag != CV_TSTOP_RETURN) {
      flag = CVode(cv, t_stop, y, &t, CV_ONE_STEP);
      bad = check(flag, "CVode");
      for (; !bad && next < nsamples; ++next) {
        const double ts = next + 1 == nsamples ? T_END : (double)next / SAMPLE_RATE;
        if (ts > t)
          break;
        bad = check(CVodeGetDky(cv, ts, 0, ysam), "CVodeGetDky");
        double *row = table + next * (1 + NOUT);
        row[0] = ts;
        outputs(m, ts, N_VGetArrayPointer(ysam), row + 1);
      }
    }
  }
  if (!bad) {
    add_stats(cv, st);
    bad = next != nsamples;
  }
  if (cv)
    CVodeFree(&cv);
  if (ls)
    SUNLinSolFree(ls);
  if (A)
    SUNMatDestroy(A);
  if (y)
    N_VDestroy(y);
  if (ysam)
    N_VDestroy(ysam);
  SUNContext_Free(&ctx);
  st->seconds = clock_seconds(CLOCK_MONOTONIC) - t0;
  st->cpu_seconds = clock_seconds(CLOCK_THREAD_CPUTIME_ID) - c0;
  return bad;
}

static int write_csv(const char *path, size_t nsamples, const double *table)
{
  FILE *fp = fopen(path, "w");
  if (!fp) {
    perror(path);
    return 1;
  }
  fprintf(fp,
          "t,tire_force_%s,spring_defl_%s,torsion,driver_acc,shock_power_%s,tire_defl_%s,"
          "tire_power_%s\n",
          CORNER_NAMES[0], CORNER_NAMES[1], CORNER_NAMES[2], CORNER_NAMES[3], CORNER_NAMES[4]);
  for (size_t k = 0; k < nsamples; ++k) {
    const double *row = table + k * (1 + NOUT);
    for (int j = 0; j <= NOUT; ++j)
      fprintf(fp, j ? ",%.10g" : "%.10g", row[j]);
    fputc('\n', fp);
  }
  if (fclose(fp) != 0) {
    perror(path);
    return 1;
  }
  return 0;
}

int main(int argc, char **argv)
{
  const char *out = NULL;
  double rtol = RTOL, atol = ATOL;
  int repeat = 1;
  for (int i = 1; i < argc; ++i) {
    const int more = i + 1 < argc;
    if (!strcmp(argv[i], "-o") && more)
      out = argv[++i];
    else if (!strcmp(argv[i], "--rtol") && more)
      rtol = atof(argv[++i]);
    else if (!strcmp(argv[i], "--atol") && more)
      atol = atof(argv[++i]);
    else if (!strcmp(argv[i], "--repeat") && more)
      repeat = atoi(argv[++i]);
    else {
      fprintf(stderr, "usage: %s [-o FILE.csv] [--rtol X] [--atol Y] [--repeat N]\n", argv[0]);
      return 1;
    }
  }
  if (repeat < 1 || !(rtol > 0.0) || !(atol > 0.0)) {
    fprintf(stderr, "system1_hand: --repeat >= 1, --rtol > 0 and --atol > 0\n");
    return 1;
  }
  model m;
  model_init(&m);
  const size_t nsamples = (size_t)floor(T_END * SAMPLE_RATE + 0.5) + 1;
  double *table = malloc(nsamples * (1 + NOUT) * sizeof *table);
  double *secs = malloc((size_t)repeat * sizeof *secs);
  int rc = table && secs ? 0 : 1;
  stats st;
  for (int r = 0; !rc && r < repeat; ++r) {
    rc = simulate(&m, rtol, atol, nsamples, table, &st);
    secs[r] = st.seconds;
    if (!rc && repeat > 1)
      fprintf(stderr, "run %d: solver %.3f ms (cpu %.3f ms)\n", r + 1, 1e3 * secs[r],
              1e3 * st.cpu_seconds);
  }
  if (!rc) {
    qsort(secs, (size_t)repeat, sizeof *secs, cmp_double);
    fprintf(stderr,
            "system1_hand: %zu samples, %ld steps, %ld rhs evals, %ld Newton setups, %ld "
            "Newton iterations, %ld error test failures; solver %.3f ms (median of %d)\n",
            nsamples, st.steps, st.rhs_evals, st.setups, st.newton_iters, st.err_fails,
            1e3 * secs[repeat / 2], repeat);
  }
  if (!rc && out)
    rc = write_csv(out, nsamples, table);
  free(table);
  free(secs);
  return rc;
}
