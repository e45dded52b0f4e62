/* SPDX-License-Identifier: BSD-3-Clause */
/* Time integration with SUNDIALS CVODE 6.4 (see flexbond/sim.h).
 *
 * Method: variable-order, variable-step BDF with modified Newton iteration
 * (Hindmarsh et al., "SUNDIALS", ACM TOMS 31(3), 2005, sec. 2.1). The
 * Newton systems (I - gamma J) dx = b are solved through the diagram's
 * augmented linearisation P(gamma) (src/sim/auglin.h), factorised by KLU.
 *
 * How the solver is attached. A SUNLINEARSOLVER_MATRIX_EMBEDDED solver is
 * never set up by CVODE 6.4: cvLsInitialize (src/cvode/cvode_ls.c) sets
 * the setup hook to NULL and turns the gamma-ratio solution scaling off
 * for that type; with libsundials_cvode 6.4.1 it got zero setup calls and
 * CVodeSetLinearSolutionScaling returned CVLS_ILL_INPUT. It would have to
 * refactorise inside every solve and guess when the matrix is stale.
 * Instead the solver is a DIRECT one over a matrix object without storage
 * of its own, "filled" by a linear-system function (CVodeSetLinSysFn).
 * CVODE then decides when P(gamma) is rebuilt (convergence failures,
 * gamma changed by more than 30 %, every 20 steps) and whether the
 * Jacobian part may be reused (jok), as for its own matrix solvers, and
 * cvLsSolve rescales each Newton correction by 2 / (1 + gamma /
 * gamma_setup) when gamma changed since the factorisation (solution
 * scaling: CVODE user guide, CVodeSetLinearSolutionScaling and the
 * "IVP solution" section; it corrects a solve with factors of an older
 * I - gamma_setup J), which is our case.
 *
 * Outputs are interpolated at the sample times with CVodeGetDky, so they
 * never shorten the steps. Integration stops exactly at every breakpoint
 * and restarts there with CVodeReInit (order 1, fresh history), because
 * the inputs are not smooth across it. */
#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <math.h>
#include <nvector/nvector_serial.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <time.h>

#include "flexbond/sim.h"

#include "core/util.h"
#include "sim/auglin.h"
#include "sim/nvector.h"
#include "sim/sim_internal.h"

/* Everything one run needs, reachable from CVODE's callbacks: the
 * stepper of flexbond/sim.h. fb_sim_run is a stepper that records the
 * samples (res) and is advanced once to t_end. */
struct fb_sim_stepper {
  fb_bd *bd;
  fb_sim_opts o;           /* the caller's options, x0 and breakpoints not kept */
  const fb_sim_opts *opts; /* &o */
  size_t n;                /* states */
  SUNContext sunctx;
  void *cvode;
  N_Vector y;    /* state at the integrator's current time */
  N_Vector ysam; /* state interpolated at a sample time */
  SUNMatrix shell;
  SUNLinearSolver ls;
  fb_auglin *lin;
  double *v0, *v1; /* augmented values P0, P1 per triplet */
  int have_values; /* v0, v1 hold a valid evaluation */
  int linear;      /* v0, v1 change only at events (fb_bd_is_piecewise_linear) */
  int jac_failed;  /* the last linearisation of the model failed */
  double gamma;    /* gamma of the matrix CVODE asked for last */
  double t_limit;  /* end of the current segment (breakpoint or stop time) */
  double t_left;   /* the double just below t_limit */
  double t_now;    /* time the integrator has reached */
  double *extra;   /* opts' breakpoints (a copy: a stepper outlives the caller's array) */
  size_t nextra;
  double *bps; /* breakpoints strictly inside (t_now at the last (re)start, t_end) */
  size_t nbps;
  size_t next_bp;      /* the first breakpoint not yet reached */
  int pending_restart; /* a mode changed within roundoff of a stop time: restart there */
  int failed;          /* an advance failed: the integrator's state is not to be trusted */
  fb_sample_grid grid;
  size_t next_sample;
  fb_result *res;    /* the samples (fb_sim_run), NULL for a caller's stepper */
  long steps_before; /* steps of the segments before the current one */
  char cvode_msg[1024];
  fb_err lin_err;
  int *crossed;     /* per guard: CVODE's root directions at an event */
  fb_sim_stats acc; /* the counters of the segments before the current one */
  /* The latest non-finite value that cv_rhs or cv_linsys met during the
   * current CVode call (cleared before each): if CVODE gives up, that is
   * why. It is explained (fb_sim_explain_nonfinite walks the diagram)
   * only then, from the model time and state kept here: a recoverable
   * probe that CVODE steps back from costs no more than this copy. */
  int has_nonfinite;
  int nonfinite_jacobian; /* the Newton matrix, not a derivative */
  double nonfinite_t;
  size_t nonfinite_state; /* whose derivative ... */
  double nonfinite_value; /* ... was this */
  N_Vector ybad;          /* the state of that evaluation */
};
typedef struct fb_sim_stepper sim_run;

/* ---- Model callbacks. */

/* Inputs are evaluated on each segment as the continuation of their
 * values inside it: at the segment's end (a breakpoint) the left limit
 * is used, so a step at the breakpoint does not leak into the last step
 * before it. CVODE does evaluate f exactly at the stop time when its last
 * step lands there (seen with 6.4.1). */
static double model_time(const sim_run *run, double t)
{
  return t < run->t_limit ? t : run->t_left;
}

/* Keeps the evaluation at (t, y) that met a non-finite value (the
 * derivative f_i of state i, or the Newton matrix), for the failure
 * message if CVODE gives up. */
static void note_nonfinite(sim_run *run, double t, N_Vector y, int jacobian, size_t i,
                           double f_i)
{
  N_VScale(1.0, y, run->ybad);
  run->nonfinite_t = t;
  run->nonfinite_jacobian = jacobian;
  run->nonfinite_state = i;
  run->nonfinite_value = f_i;
  run->has_nonfinite = 1;
}

/* CVRhsFn: 0 ok, >0 recoverable (CVODE retries with a smaller step), <0
 * fatal, as fb_bd_rhs. A derivative that is not finite is recoverable:
 * the CVODE user guide (CVRhsFn) says a recoverable return "is typically
 * used to flag a value of the dependent variable y that is illegal in
 * some way", and CVODE then repeats the nonlinear solve or cuts the
 * step, so a step that probed past a log(1.5 - t) is retried shorter and
 * may stay clear of it. One pass over ydot per call; the diagram is
 * walked only when that pass fails. */
static int cv_rhs(double t, N_Vector y, N_Vector ydot, void *user_data)
{
  sim_run *run = user_data;
  const double tm = model_time(run, t), *x = N_VGetArrayPointer(y);
  double *f = N_VGetArrayPointer(ydot);
  const int rc = fb_bd_rhs(run->bd, tm, x, f);
  if (rc != 0)
    return rc > 0 ? 1 : -1;
  const size_t bad = fb_first_nonfinite(f, run->n);
  if (bad == run->n)
    return 0;
  note_nonfinite(run, tm, y, 0, bad, f[bad]);
  return 1;
}

/* CVRootFn: the switched laws' guards. A failure is fatal for CVODE. */
static int cv_roots(double t, N_Vector y, double *g, void *user_data)
{
  sim_run *run = user_data;
  return fb_bd_guards(run->bd, model_time(run, t), N_VGetArrayPointer(y), g) == 0 ? 0 : -1;
}

/* CVLsLinSysFn: "forms" P(gamma) by refreshing the augmented values when
 * CVODE says the Jacobian is stale (!jok) or none exist yet; a linear
 * diagram's values never change, so they are evaluated once and are
 * always current (jcur). The factorisation happens in ls_setup. */
static int cv_linsys(double t, N_Vector y, N_Vector fy, SUNMatrix A, booleantype jok,
                     booleantype *jcur, double gamma, void *user_data, N_Vector tmp1,
                     N_Vector tmp2, N_Vector tmp3)
{
  (void)fy;
  (void)A;
  (void)tmp1;
  (void)tmp2;
  (void)tmp3;
  sim_run *run = user_data;
  const int evaluate = !run->have_values || (!jok && !run->linear);
  if (evaluate) {
    run->have_values = 0;
    const int rc =
        fb_bd_aug_values(run->bd, model_time(run, t), N_VGetArrayPointer(y), run->v0, run->v1);
    run->jac_failed = rc != 0;
    if (rc != 0)
      return rc > 0 ? 1 : -1;
    /* A non-finite entry would reach the factorisation; recoverable, as
     * for the right-hand side (cv_rhs). */
    const size_t nnz = fb_bd_aug_nnz(run->bd);
    if (fb_first_nonfinite(run->v0, nnz) < nnz || fb_first_nonfinite(run->v1, nnz) < nnz) {
      note_nonfinite(run, model_time(run, t), y, 1, 0, 0.0);
      return 1;
    }
    run->have_values = 1;
  }
  *jcur = evaluate || run->linear;
  run->gamma = gamma;
  return 0;
}

/* CVErrHandlerFn: keeps CVODE quiet and remembers its last error for the
 * message fb_sim_run returns. Warnings (positive codes) are dropped. */
static void cv_error(int error_code, const char *module, const char *function, char *msg,
                     void *user_data)
{
  (void)module;
  sim_run *run = user_data;
  if (error_code < 0)
    snprintf(run->cvode_msg, sizeof run->cvode_msg, "%s: %s", function, msg);
}

/* ---- The linear solver and its storage-less matrix. */

static SUNMatrix_ID shell_id(SUNMatrix A)
{
  (void)A;
  return SUNMATRIX_CUSTOM;
}

static SUNLinearSolver_Type ls_type(SUNLinearSolver S)
{
  (void)S;
  return SUNLINEARSOLVER_DIRECT;
}

static SUNLinearSolver_ID ls_id(SUNLinearSolver S)
{
  (void)S;
  return SUNLINEARSOLVER_CUSTOM;
}

/* Factorises P(gamma) with the values cv_linsys left. A singular matrix
 * is a recoverable failure (positive flag): CVODE retries with a smaller
 * step, i.e. another gamma. */
static int ls_setup(SUNLinearSolver S, SUNMatrix A)
{
  (void)A;
  sim_run *run = S->content;
  const int rc = fb_auglin_setup(run->lin, run->gamma, run->v0, run->v1, &run->lin_err);
  if (rc == FB_OK)
    return SUNLS_SUCCESS;
  return rc == FB_ESOLVER ? SUNLS_LUFACT_FAIL : SUNLS_PACKAGE_FAIL_UNREC;
}

static int ls_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, double tol)
{
  (void)A;
  (void)tol; /* a direct solve is exact to rounding */
  sim_run *run = S->content;
  const int rc =
      fb_auglin_solve(run->lin, N_VGetArrayPointer(b), N_VGetArrayPointer(x), &run->lin_err);
  return rc == FB_OK ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_UNREC;
}

static int make_linear_solver(sim_run *run, fb_err *err)
{
  run->shell = SUNMatNewEmpty(run->sunctx);
  run->ls = SUNLinSolNewEmpty(run->sunctx);
  if (!run->shell || !run->ls)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating the CVODE linear solver");
  run->shell->ops->getid = shell_id;
  run->ls->content = run;
  run->ls->ops->gettype = ls_type;
  run->ls->ops->getid = ls_id;
  run->ls->ops->setup = ls_setup;
  run->ls->ops->solve = ls_solve;
  return FB_OK;
}

/* Builds the augmented Newton solver from the diagram's pattern. */
static int make_auglin(sim_run *run, fb_err *err)
{
  const size_t nnz = fb_bd_aug_nnz(run->bd);
  run->v0 = malloc((nnz ? nnz : 1) * sizeof *run->v0);
  run->v1 = malloc((nnz ? nnz : 1) * sizeof *run->v1);
  if (!run->v0 || !run->v1)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the augmented Newton matrix");
  return fb_auglin_new_bd(run->bd, &run->lin, err);
}

/* ---- Error messages. */

static const char *flag_hint(int flag)
{
  switch (flag) {
  case CV_TOO_MUCH_WORK:
    return "too many steps; raise max_steps (the solver's step budget), or check for "
           "stiffness or a too small max_step";
  case CV_TOO_MUCH_ACC:
    return "the tolerances are tighter than double precision allows; loosen rtol or atol";
  case CV_ERR_FAILURE:
    return "the error test failed repeatedly; the tolerances may be too tight, or an input "
           "has a discontinuity that is not a breakpoint";
  case CV_CONV_FAILURE:
  case CV_LSETUP_FAIL:
  case CV_LSOLVE_FAIL:
    return "the Newton iteration failed; the Newton matrix may be singular, or the model "
           "has a discontinuity";
  case CV_RTFUNC_FAIL:
    return "evaluating the guards of the switched laws (contact conditions) failed";
  case CV_RHSFUNC_FAIL:
  case CV_FIRST_RHSFUNC_ERR:
  case CV_REPTD_RHSFUNC_ERR:
  case CV_UNREC_RHSFUNC_ERR: return "evaluating the model failed";
  default: return "the integration failed";
  }
}

/* "; the largest local error ... is in state S": the state
 * whose weighted local error estimate was the largest at the last step
 * attempt (CVodeGetEstLocalErrors and CVodeGetErrWeights, which the CVODE
 * user guide suggests after a failure to find the culprit); "" if CVODE
 * has none yet. */
static void worst_state(const sim_run *run, char *buf, size_t size)
{
  buf[0] = '\0';
  N_Vector ele = N_VClone(run->y), ewt = N_VClone(run->y);
  if (ele && ewt && CVodeGetEstLocalErrors(run->cvode, ele) == CV_SUCCESS &&
      CVodeGetErrWeights(run->cvode, ewt) == CV_SUCCESS) {
    const double *e = N_VGetArrayPointer(ele), *w = N_VGetArrayPointer(ewt);
    size_t worst = 0;
    double largest = 0.0;
    for (size_t i = 0; i < run->n; ++i)
      if (fabs(e[i] * w[i]) > largest) {
        largest = fabs(e[i] * w[i]);
        worst = i;
      }
    /* State names carry their element's ("susp_LF.wheel.p"). */
    if (largest > 0.0 && isfinite(largest))
      snprintf(buf, size, "; the largest local error (%.3g times its tolerance) is in state %s",
               largest, fb_bd_state_name(run->bd, worst));
  }
  if (ele)
    N_VDestroy(ele);
  if (ewt)
    N_VDestroy(ewt);
}

/* Whether the local error estimates name the culprit of a failure with
 * this flag: they do after failed error tests or Newton iterations, and
 * for the step that ran out of work or accuracy; other flags (an illegal
 * input, a stop time too close) leave them stale or meaningless. */
static int local_errors_tell(int flag)
{
  return flag == CV_ERR_FAILURE || flag == CV_CONV_FAILURE || flag == CV_TOO_MUCH_WORK ||
         flag == CV_TOO_MUCH_ACC;
}

/* "the derivative of state S is nan ...", with the model time of the
 * evaluation when it reads differently from t. */
static void nonfinite_clause(const sim_run *run, double t, char *buf, size_t size)
{
  char what[300], explained[FB_SIM_NONFINITE_MAX];
  if (run->nonfinite_jacobian)
    snprintf(what, sizeof what, "the Newton matrix is not finite");
  else
    snprintf(what, sizeof what, "the derivative of state %s is %g",
             fb_bd_state_name(run->bd, run->nonfinite_state),
             fb_printable(run->nonfinite_value));
  fb_sim_explain_nonfinite(run->bd, run->nonfinite_t, N_VGetArrayPointer(run->ybad),
                           run->nonfinite_jacobian, what, explained, sizeof explained);
  char at[32], now[32];
  snprintf(at, sizeof at, "%.6g", run->nonfinite_t);
  snprintf(now, sizeof now, "%.6g", t);
  if (strcmp(at, now) == 0)
    snprintf(buf, size, "%s", explained);
  else
    snprintf(buf, size, "at t = %s s, %s", at, explained);
}

/* Whether CVODE gave up on what cv_rhs and cv_linsys flag as
 * recoverable: repeated or unrecoverable right-hand side failures, or
 * failed Newton iterations and error tests. A law that fails outright
 * (CV_RHSFUNC_FAIL) says why itself. */
static int gave_up_retrying(int flag)
{
  return flag == CV_REPTD_RHSFUNC_ERR || flag == CV_FIRST_RHSFUNC_ERR ||
         flag == CV_UNREC_RHSFUNC_ERR || flag == CV_CONV_FAILURE || flag == CV_ERR_FAILURE;
}

/* The solver setting a flag's hint names (fb_sim_opts field, for
 * err->key), or NULL. */
static const char *flag_key(int flag)
{
  return flag == CV_TOO_MUCH_WORK ? "max_steps" : flag == CV_TOO_MUCH_ACC ? "rtol" : NULL;
}

/* FB_ESOLVER "at t = ... s: CVODE <flag>: <hint>" with whatever CVODE,
 * the Newton solver and the diagram said. A non-finite value met during
 * the failed call explains the failure: CVODE gave up retrying it
 * (CV_REPTD_RHSFUNC_ERR, CV_FIRST_RHSFUNC_ERR, or CV_CONV_FAILURE when
 * the Newton matrix was not finite), so it takes the hint's place. */
static int cvode_failure(const sim_run *run, int flag, double t, fb_err *err)
{
  char *name = CVodeGetReturnFlagName(flag); /* malloc'ed in CVODE 6.4 */
  if (run->has_nonfinite && gave_up_retrying(flag)) {
    char clause[FB_SIM_NONFINITE_MAX + 128];
    nonfinite_clause(run, t, clause, sizeof clause);
    fb_err_set(err, FB_ESOLVER, "at t = %.6g s: CVODE %s: %s%s%s", t,
               name ? name : "(unknown flag)", clause, run->cvode_msg[0] ? "; " : "",
               run->cvode_msg);
    free(name);
    return FB_ESOLVER;
  }
  const char *model = fb_bd_last_error(run->bd);
  const char *lin = run->lin_err.msg;
  /* A linearisation failure surfaces as a Newton set-up failure. */
  const char *hint = flag_hint(run->jac_failed ? CV_RHSFUNC_FAIL : flag);
  char culprit[512] = "";
  if (local_errors_tell(flag))
    worst_state(run, culprit, sizeof culprit);
  const long singular = fb_auglin_singular_unknown(run->lin);
  if (singular >= 0 && (flag == CV_LSETUP_FAIL || flag == CV_CONV_FAILURE)) {
    char unknown[256];
    fb_bd_aug_unknown_name(run->bd, (size_t)singular, unknown, sizeof unknown);
    snprintf(culprit, sizeof culprit,
             "; the Newton matrix has no pivot for %s (a mass, stiffness or damping that is "
             "zero or cancels out there)",
             unknown);
  }
  fb_err_set(err, FB_ESOLVER, "at t = %.6g s: CVODE %s: %s%s%s%s%s%s%s%s", t,
             name ? name : "(unknown flag)", hint, culprit, run->cvode_msg[0] ? "; " : "",
             run->cvode_msg, lin[0] ? "; " : "", lin, model && model[0] ? "; model: " : "",
             model ? model : "");
  if (!run->jac_failed && flag_key(flag))
    fb_err_set_key(err, "%s", flag_key(flag));
  free(name);
  return FB_ESOLVER;
}

/* A CVODE set-up call returned flag. */
static int setup_failure(const sim_run *run, const char *call, int flag, fb_err *err)
{
  char *name = CVodeGetReturnFlagName(flag);
  fb_err_set(err, FB_ESOLVER, "CVODE set-up: %s returned %s%s%s", call,
             name ? name : "(unknown flag)", run->cvode_msg[0] ? ": " : "", run->cvode_msg);
  free(name);
  return FB_ESOLVER;
}

/* ---- Set-up and tear-down. */

static int cv_call(const sim_run *run, const char *call, int flag, fb_err *err)
{
  return flag < 0 ? setup_failure(run, call, flag, err) : FB_OK;
}

/* Initial state: x0 (opts->x0) or the graph's, finite. */
static int initial_state(sim_run *run, const double *x0, fb_err *err)
{
  double *y = N_VGetArrayPointer(run->y);
  if (x0)
    memcpy(y, x0, run->n * sizeof *y);
  else
    fb_bd_initial_state(run->bd, y);
  for (size_t i = 0; i < run->n; ++i)
    if (!isfinite(y[i])) {
      fb_err_set(err, FB_EINVAL, "initial state x0[%zu] (%s): must be finite, got %g", i,
                 fb_bd_state_name(run->bd, i), y[i]);
      fb_err_set_key(err, "x0[%zu]", i);
      return FB_EINVAL;
    }
  return FB_OK;
}

static int make_cvode(sim_run *run, fb_err *err)
{
  const fb_sim_opts *o = run->opts;
  run->cvode = CVodeCreate(CV_BDF, run->sunctx);
  if (!run->cvode)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating CVODE");
  int rc = cv_call(run, "CVodeSetErrHandlerFn", CVodeSetErrHandlerFn(run->cvode, cv_error, run),
                   err);
  if (rc == FB_OK)
    rc = cv_call(run, "CVodeInit", CVodeInit(run->cvode, cv_rhs, o->t_start, run->y), err);
  if (rc == FB_OK)
    rc = cv_call(run, "CVodeSetUserData", CVodeSetUserData(run->cvode, run), err);
  if (rc == FB_OK)
    rc =
        cv_call(run, "CVodeSStolerances", CVodeSStolerances(run->cvode, o->rtol, o->atol), err);
  if (rc == FB_OK)
    rc = cv_call(run, "CVodeSetMaxOrd", CVodeSetMaxOrd(run->cvode, o->max_order), err);
  /* CVODE's hmax = 0 means no limit too, as for max_step. */
  if (rc == FB_OK)
    rc = cv_call(run, "CVodeSetMaxStep", CVodeSetMaxStep(run->cvode, o->max_step), err);
  /* Measured on examples/apc6x6.yaml: System 2's steps fall by 12 %
   * (modal hull) and 15 % (nodal), at the same largest error against an
   * rtol 1e-10 run (4.5e-6 of the torsion's range); System 1's do not
   * change (bench/README.md). */
  if (rc == FB_OK)
    rc = cv_call(
        run, "CVodeSetStabLimDet",
        CVodeSetStabLimDet(run->cvode, o->stability_limit_detection ? SUNTRUE : SUNFALSE), err);
  if (rc == FB_OK)
    rc = make_linear_solver(run, err);
  if (rc == FB_OK)
    rc = cv_call(run, "CVodeSetLinearSolver",
                 CVodeSetLinearSolver(run->cvode, run->ls, run->shell), err);
  if (rc == FB_OK)
    rc = cv_call(run, "CVodeSetLinSysFn", CVodeSetLinSysFn(run->cvode, cv_linsys), err);
  /* The default for matrix-based solvers with BDF, made explicit. */
  if (rc == FB_OK)
    rc = cv_call(run, "CVodeSetLinearSolutionScaling",
                 CVodeSetLinearSolutionScaling(run->cvode, SUNTRUE), err);
  /* A linear time-invariant Newton subsystem never makes the Newton
   * matrix stale except through gamma, which CVODE watches by itself
   * (a new setup when gamma changes by 30 %): the refresh every 20 steps
   * meant for a changing Jacobian only costs factorisations (System 2:
   * 348 -> 190 on a 3 s run, 21 % faster). */
  if (rc == FB_OK && run->linear)
    rc =
        cv_call(run, "CVodeSetLSetupFrequency", CVodeSetLSetupFrequency(run->cvode, 1000), err);
  const size_t nguards = fb_bd_nguards(run->bd);
  if (rc == FB_OK && nguards)
    rc = cv_call(run, "CVodeRootInit", CVodeRootInit(run->cvode, (int)nguards, cv_roots), err);
  /* CVODE leaves a guard that is exactly zero where a segment starts out
   * of its watch until it moves away; sync_modes has already chosen the
   * mode from the side it moves to, so that is expected, not worth a
   * warning. */
  if (rc == FB_OK && nguards)
    rc =
        cv_call(run, "CVodeSetNoInactiveRootWarn", CVodeSetNoInactiveRootWarn(run->cvode), err);
  return rc;
}

static void run_free(sim_run *run)
{
  if (run->cvode)
    CVodeFree(&run->cvode);
  if (run->ls)
    SUNLinSolFreeEmpty(run->ls);
  if (run->shell)
    SUNMatFreeEmpty(run->shell);
  if (run->y)
    N_VDestroy(run->y);
  if (run->ysam)
    N_VDestroy(run->ysam);
  if (run->ybad)
    N_VDestroy(run->ybad);
  if (run->sunctx)
    SUNContext_Free(&run->sunctx);
  fb_auglin_free(&run->lin);
  free(run->v0);
  free(run->v1);
  free(run->bps);
  free(run->extra);
  free(run->crossed);
}

/* ---- Breakpoints. */

static int compare_doubles(const void *a, const void *b)
{
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* run->bps = the sources' and opts' breakpoints strictly inside (t_from,
 * t_end), sorted, without near duplicates: times closer than
 * fb_sim_same_time_tol are one, since CVODE cannot start a segment
 * shorter than a few roundoffs of its end points (CV_TOO_CLOSE). Called
 * at the start and again after a change of the diagram's inputs, whose
 * time functions may have breakpoints of their own. */
static int collect_breakpoints(sim_run *run, double t_from, fb_err *err)
{
  const fb_sim_opts *o = run->opts;
  const size_t bound = fb_bd_breakpoints(run->bd, NULL, 0);
  free(run->bps);
  run->nbps = run->next_bp = 0;
  run->bps = malloc((bound + run->nextra + 1) * sizeof *run->bps);
  if (!run->bps)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu breakpoints", bound + run->nextra);
  const size_t nsrc = fb_bd_breakpoints(run->bd, run->bps, bound);
  const size_t total = nsrc + run->nextra;
  if (run->nextra)
    memcpy(run->bps + nsrc, run->extra, run->nextra * sizeof *run->bps);
  qsort(run->bps, total, sizeof *run->bps, compare_doubles);
  double last = t_from;
  run->nbps = 0;
  run->next_bp = 0;
  for (size_t i = 0; i < total; ++i) {
    const double t = run->bps[i];
    if (t - last > fb_sim_same_time_tol(t, last) &&
        o->t_end - t > fb_sim_same_time_tol(t, o->t_end))
      last = run->bps[run->nbps++] = t;
  }
  return FB_OK;
}

/* ---- Sampling. */

/* The outputs at (t, x) into y, every one finite. */
static int eval_outputs(sim_run *run, double t, const double *x, double *y, fb_err *err)
{
  if (fb_bd_outputs(run->bd, t, x, y) != 0)
    return fb_err_set(err, FB_ESOLVER, "at t = %.6g s: evaluating the outputs failed: %s", t,
                      fb_bd_last_error(run->bd));
  /* An output the dynamics do not need (a power probe, an energy) is
   * not checked by cv_rhs; a non-finite one must not reach the caller. */
  const size_t nout = fb_bd_noutputs(run->bd), bad = fb_first_nonfinite(y, nout);
  if (bad < nout) {
    char what[300], msg[FB_SIM_NONFINITE_MAX];
    snprintf(what, sizeof what, "output %s is %g", fb_bd_output_name(run->bd, bad),
             fb_printable(y[bad]));
    fb_sim_explain_nonfinite(run->bd, t, x, 0, what, msg, sizeof msg);
    return fb_err_set(err, FB_ESOLVER, "at t = %.6g s: %s", t, msg);
  }
  return FB_OK;
}

/* Writes row k of the result: t, then the outputs at state x. */
static int write_sample(sim_run *run, size_t k, double t, const double *x, fb_err *err)
{
  double *row = run->res->data + k * run->res->ncols;
  row[0] = t;
  return eval_outputs(run, t, x, row + 1, err);
}

/* Every pending sample at or before tcur, interpolated within the last
 * step by CVODE's Nordsieck polynomial; none for a stepper that does not
 * record. */
static int emit_samples(sim_run *run, double tcur, fb_err *err)
{
  while (run->res && run->next_sample < run->grid.n) {
    const double t = fb_sample_grid_time(&run->grid, run->next_sample);
    if (t > tcur)
      break;
    const int flag = CVodeGetDky(run->cvode, t, 0, run->ysam);
    if (flag < 0)
      return cvode_failure(run, flag, t, err);
    const int rc = write_sample(run, run->next_sample, t, N_VGetArrayPointer(run->ysam), err);
    if (rc != FB_OK)
      return rc;
    ++run->next_sample;
  }
  return FB_OK;
}

/* ---- Stepping. */

/* CVODE's first call after a (re)start evaluates f at the state there,
 * where no shorter step can help (CV_FIRST_RHSFUNC_ERR): a non-finite
 * derivative there is reported at once, as the state's. ysam is free
 * until the next sample is interpolated. */
static int check_initial_rhs(sim_run *run, fb_err *err)
{
  const double t = run->t_now, *x = N_VGetArrayPointer(run->y);
  double *f = N_VGetArrayPointer(run->ysam);
  if (fb_bd_rhs(run->bd, t, x, f) != 0)
    return FB_OK; /* a failing law: CVODE reports it with its flag */
  const size_t bad = fb_first_nonfinite(f, run->n);
  if (bad == run->n)
    return FB_OK;
  char what[300], msg[FB_SIM_NONFINITE_MAX];
  snprintf(what, sizeof what, "the derivative of state %s is %g at the %s state",
           fb_bd_state_name(run->bd, bad), fb_printable(f[bad]),
           t == run->opts->t_start ? "initial" : "restart");
  fb_sim_explain_nonfinite(run->bd, t, x, 0, what, msg, sizeof msg);
  return fb_err_set(err, FB_ESOLVER, "at t = %.6g s: %s", t, msg);
}

/* A guard more than a check: CVODE does not accept a step whose state
 * is not finite (its weighted norms of the correction and of the local
 * error are then NaN or inf, and "norm <= 1" fails), and cv_rhs refuses
 * non-finite derivatives, so a non-finite value stops the run through
 * cvode_failure or check_progress with its origin. */
static int check_finite_state(const sim_run *run, double t, fb_err *err)
{
  const double *y = N_VGetArrayPointer(run->y);
  for (size_t i = 0; i < run->n; ++i)
    if (!isfinite(y[i]))
      return fb_err_set(err, FB_ESOLVER,
                        "at t = %.6g s: state %s became %g; the model diverged or a law "
                        "returned a non-finite value",
                        t, fb_bd_state_name(run->bd, i), fb_printable(y[i]));
  return FB_OK;
}

/* CVODE accepts steps so small that t + h rounds to t (it only warns),
 * e.g. when the model turns non-finite just ahead and every step towards
 * it is cut until it vanishes; without this check such a run would spin
 * until max_steps. */
static int check_progress(const sim_run *run, double t_before, fb_err *err)
{
  if (run->t_now > t_before)
    return FB_OK;
  double h = 0;
  CVodeGetLastStep(run->cvode, &h);
  if (run->has_nonfinite) {
    char clause[FB_SIM_NONFINITE_MAX + 128];
    nonfinite_clause(run, run->t_now, clause, sizeof clause);
    return fb_err_set(err, FB_ESOLVER,
                      "at t = %.6g s: CVODE step size %g no longer advances t: every longer "
                      "step meets a value that is not finite: %s",
                      run->t_now, h, clause);
  }
  return fb_err_set(err, FB_ESOLVER,
                    "at t = %.6g s: CVODE step size %g no longer advances t; the model is "
                    "probably singular, or not finite, just after this time%s%s",
                    run->t_now, h, fb_bd_last_error(run->bd)[0] ? "; model: " : "",
                    fb_bd_last_error(run->bd));
}

/* opts->max_steps bounds the whole run. CVODE's own limit
 * (CVodeSetMaxNumSteps) counts steps per CVode call, and in CV_ONE_STEP
 * mode every call takes one step, so the budget is kept here. */
static int check_budget(const sim_run *run, double t, fb_err *err)
{
  long nst = 0;
  CVodeGetNumSteps(run->cvode, &nst);
  if (run->steps_before + nst < run->opts->max_steps)
    return FB_OK;
  char *name = CVodeGetReturnFlagName(CV_TOO_MUCH_WORK);
  char culprit[512];
  worst_state(run, culprit, sizeof culprit);
  fb_err_set(err, FB_ESOLVER, "at t = %.6g s: CVODE %s: %s (%ld steps taken)%s", t,
             name ? name : "CV_TOO_MUCH_WORK", flag_hint(CV_TOO_MUCH_WORK),
             run->opts->max_steps, culprit);
  fb_err_set_key(err, "max_steps");
  free(name);
  return FB_ESOLVER;
}

/* s = run->acc plus the counters of the current segment (CVodeReInit
 * resets CVODE's own). */
static void current_stats(const sim_run *run, fb_sim_stats *s)
{
  *s = run->acc;
  if (!run->cvode)
    return;
  long v = 0;
  CVodeGetNumSteps(run->cvode, &v);
  s->steps += v;
  CVodeGetNumRhsEvals(run->cvode, &v);
  s->rhs_evals += v;
  CVodeGetNumLinSolvSetups(run->cvode, &v);
  s->newton_setups += v;
  CVodeGetNumNonlinSolvIters(run->cvode, &v);
  s->newton_iters += v;
  CVodeGetNumNonlinSolvConvFails(run->cvode, &v);
  s->newton_conv_fails += v;
  CVodeGetNumErrTestFails(run->cvode, &v);
  s->err_test_fails += v;
  CVodeGetLastOrder(run->cvode, &s->last_order);
  s->factorizations = fb_auglin_nfactorizations(run->lin);
}

/* Adds the counters of the segment just finished to run->acc, before a
 * restart (CVodeReInit resets them). */
static void add_segment_stats(sim_run *run)
{
  const long before = run->acc.steps;
  current_stats(run, &run->acc);
  run->steps_before += run->acc.steps - before;
}

/* Makes the switched laws' modes consistent with the state at t, where
 * the integration (re)starts (fb_bd_sync_modes). */
static int sync_modes(sim_run *run, double t, int *changed, fb_err *err)
{
  if (fb_bd_sync_modes(run->bd, t, N_VGetArrayPointer(run->y), changed) != 0)
    return fb_err_set(err, FB_ESOLVER, "at t = %.6g s: choosing the modes failed: %s", t,
                      fb_bd_last_error(run->bd));
  if (*changed)
    run->have_values = 0; /* the linearisation belongs to the old modes */
  return FB_OK;
}

/* Restarts the integration at the current time and state: order 1, a
 * fresh history, since the right-hand side is not smooth across it. */
static int restart_here(sim_run *run, fb_err *err)
{
  add_segment_stats(run);
  run->pending_restart = 0;
  return cv_call(run, "CVodeReInit", CVodeReInit(run->cvode, run->t_now, run->y), err);
}

/* CVODE stopped at a zero crossing of guards (CV_ROOT_RETURN), with
 * run->y the state there: the laws choose their next modes, and if one
 * changed the integration restarts from this point, because the right-
 * hand side is not smooth across it. The samples up to the event were
 * written with the modes before it. */
static int handle_event(sim_run *run, double t_stop, fb_err *err)
{
  int flag = CVodeGetRootInfo(run->cvode, run->crossed);
  if (flag < 0)
    return setup_failure(run, "CVodeGetRootInfo", flag, err);
  int changed = 0;
  if (fb_bd_switch_modes(run->bd, model_time(run, run->t_now), N_VGetArrayPointer(run->y),
                         run->crossed, &changed) != 0)
    return fb_err_set(err, FB_ESOLVER, "at t = %.6g s: switching modes failed: %s", run->t_now,
                      fb_bd_last_error(run->bd));
  if (!changed)
    return FB_OK;
  run->acc.events++;
  run->have_values = 0; /* the linearisation belongs to the old modes */
  /* Within roundoff of the segment's end CVODE cannot restart (the
   * interval is too short); what is left of the segment is that roundoff,
   * and the next segment starts afresh (at a breakpoint, or through
   * pending_restart at a caller's stop time). */
  if (t_stop - run->t_now <= fb_sim_same_time_tol(t_stop, run->t_now)) {
    run->pending_restart = 1;
    return FB_OK;
  }
  int rc = restart_here(run, err);
  if (rc == FB_OK)
    rc = cv_call(run, "CVodeSetStopTime", CVodeSetStopTime(run->cvode, t_stop), err);
  return rc;
}

/* One internal step towards t_stop, with its checks, samples and event. */
static int take_step(sim_run *run, double t_stop, int *flag, fb_err *err)
{
  int rc = check_budget(run, run->t_now, err);
  if (rc != FB_OK)
    return rc;
  const double t_before = run->t_now;
  run->has_nonfinite = 0; /* what the callbacks meet during this step */
  /* tout = t_stop only bounds the initial step-size estimate. */
  *flag = CVode(run->cvode, t_stop, run->y, &run->t_now, CV_ONE_STEP);
  if (*flag < 0)
    return cvode_failure(run, *flag, run->t_now, err);
  /* Failures CVODE recovered from are no news. */
  run->lin_err.msg[0] = '\0';
  run->jac_failed = 0;
  rc = check_progress(run, t_before, err);
  if (rc == FB_OK)
    rc = check_finite_state(run, run->t_now, err);
  if (rc == FB_OK)
    rc = emit_samples(run, run->t_now, err);
  if (rc == FB_OK && *flag == CV_ROOT_RETURN)
    rc = handle_event(run, t_stop, err);
  return rc;
}

/* Integrates from the current time to t_stop, one internal step at a
 * time, sampling after each step. CVODE lands on t_stop exactly
 * (CVodeSetStopTime): a caller's stop time costs a shortened step, not
 * a restart. */
static int integrate_segment(sim_run *run, double t_stop, fb_err *err)
{
  run->t_limit = t_stop;
  run->t_left = nextafter(t_stop, -INFINITY);
  int flag = CVodeSetStopTime(run->cvode, t_stop);
  if (flag < 0)
    return setup_failure(run, "CVodeSetStopTime", flag, err);
  do {
    const int rc = take_step(run, t_stop, &flag, err);
    if (rc != FB_OK)
      return rc;
    if (run->opts->progress &&
        run->opts->progress(run->opts->progress_ctx, run->t_now, run->opts->t_end) != 0)
      return fb_err_set(err, FB_EINTR, "at t = %.6g s: the simulation was interrupted",
                        run->t_now);
  } while (flag != CV_TSTOP_RETURN);
  run->t_now = t_stop; /* CVODE returns tstop itself; no roundoff left to carry */
  return FB_OK;
}

/* The restart at breakpoint t: an input may jump there and move a guard
 * across zero with no crossing for the root-finding to locate, so the
 * modes are made consistent with the new segment's inputs (a change
 * counts as an event); a sample exactly at t is then rewritten with them
 * (it shows the right limit). */
static int restart_at_breakpoint(sim_run *run, double t, fb_err *err)
{
  int changed = 0;
  int rc = restart_here(run, err);
  if (rc == FB_OK)
    rc = sync_modes(run, t, &changed, err);
  if (rc != FB_OK || !changed)
    return rc;
  run->acc.events++;
  if (!run->res)
    return FB_OK;
  const size_t last = run->next_sample - 1;
  const double t_last = fb_sample_grid_time(&run->grid, last);
  if (fabs(t_last - t) <= fb_sim_same_time_tol(t_last, t))
    rc = write_sample(run, last, t_last, N_VGetArrayPointer(run->y), err);
  return rc;
}

/* The segments from the current time to t: a stop at every breakpoint
 * on the way, with a restart there (also at t itself when t is one, so
 * that the state at t is the right limit the next advance starts
 * from). */
static int integrate_to(sim_run *run, double t, fb_err *err)
{
  int rc = FB_OK;
  while (rc == FB_OK && t - run->t_now > fb_sim_same_time_tol(t, run->t_now)) {
    if (run->pending_restart)
      rc = restart_here(run, err);
    const int to_bp =
        run->next_bp < run->nbps &&
        run->bps[run->next_bp] - t <= fb_sim_same_time_tol(t, run->bps[run->next_bp]);
    const double stop = to_bp ? run->bps[run->next_bp] : t;
    if (rc == FB_OK)
      rc = integrate_segment(run, stop, err);
    if (rc == FB_OK && to_bp) {
      rc = restart_at_breakpoint(run, stop, err);
      run->next_bp++;
    }
  }
  return rc;
}

/* One CVode call towards t in CV_NORMAL mode, the segment ending at
 * limit (a breakpoint or t_end, at or after t): CVODE steps as far as it
 * chooses, past t when its step does, and returns the state at t from
 * its interpolating polynomial, of the order of its local error; its
 * root search stops at t, so a root beyond t is found on the way to the
 * next target, with the modes of before it until then (CVODE User
 * Guide, "CVode", itask CV_NORMAL, and its rootfinding section). A
 * return after the call's step limit (CV_TOO_MUCH_WORK: CVODE's mxstep
 * counts steps per call) goes on from where it stopped; the run's own
 * budget is kept by check_budget. */
static int normal_call(sim_run *run, double t, double limit, fb_err *err)
{
  run->t_limit = limit;
  run->t_left = nextafter(limit, -INFINITY);
  int flag = CVodeSetStopTime(run->cvode, limit);
  if (flag < 0)
    return setup_failure(run, "CVodeSetStopTime", flag, err);
  int rc = check_budget(run, run->t_now, err);
  if (rc != FB_OK)
    return rc;
  run->has_nonfinite = 0;
  double t_ret = run->t_now;
  flag = CVode(run->cvode, t, run->y, &t_ret, CV_NORMAL);
  if (flag < 0 && flag != CV_TOO_MUCH_WORK)
    return cvode_failure(run, flag, t_ret, err);
  run->lin_err.msg[0] = '\0';
  run->jac_failed = 0;
  run->t_now = flag == CV_TSTOP_RETURN ? limit : t_ret;
  rc = check_finite_state(run, run->t_now, err);
  if (rc == FB_OK && flag == CV_ROOT_RETURN)
    rc = handle_event(run, limit, err);
  if (rc == FB_OK && run->opts->progress &&
      run->opts->progress(run->opts->progress_ctx, run->t_now, run->opts->t_end) != 0)
    rc = fb_err_set(err, FB_EINTR, "at t = %.6g s: the simulation was interrupted", run->t_now);
  return rc;
}

/* A caller's advance to t (a stepper records no samples): CVODE lands
 * exactly on the breakpoints and t_end only, and gives the state at t
 * by interpolation (normal_call), so a co-simulation's communication
 * points cost no shortened steps. The integrator may be past t after
 * the call; a change at t restarts it from the state at t
 * (restart_here). */
static int advance_to(sim_run *run, double t, fb_err *err)
{
  int rc = FB_OK;
  while (rc == FB_OK && t - run->t_now > fb_sim_same_time_tol(t, run->t_now)) {
    if (run->pending_restart)
      rc = restart_here(run, err);
    const int bp_ahead = run->next_bp < run->nbps;
    const double bp = bp_ahead ? run->bps[run->next_bp] : run->o.t_end;
    if (rc == FB_OK && bp_ahead && bp - t <= fb_sim_same_time_tol(t, bp)) {
      /* A breakpoint up to t: landed on exactly (CVODE returns at its
       * stop time), restarted there; a root or the call's step limit on
       * the way returns earlier, and the loop goes on. */
      rc = normal_call(run, bp, bp, err);
      if (rc == FB_OK && bp - run->t_now <= fb_sim_same_time_tol(bp, run->t_now)) {
        run->t_now = bp;
        rc = restart_at_breakpoint(run, bp, err);
        run->next_bp++;
      }
    } else if (rc == FB_OK) {
      rc = normal_call(run, t, bp, err);
    }
  }
  return rc;
}

/* A diagram without states is algebraic: outputs at each sample time. */
static int sample_static(sim_run *run, fb_err *err)
{
  const double none = 0;
  for (size_t k = 0; k < run->grid.n; ++k) {
    const int rc = write_sample(run, k, fb_sample_grid_time(&run->grid, k), &none, err);
    if (rc != FB_OK)
      return rc;
  }
  return FB_OK;
}

/* Copies opts' breakpoints, which the stepper outlives. */
static int keep_breakpoints(sim_run *run, const fb_sim_opts *opts, fb_err *err)
{
  run->nextra = opts->nbreakpoints;
  run->extra = malloc((run->nextra + 1) * sizeof *run->extra);
  if (!run->extra)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu breakpoints", run->nextra);
  if (run->nextra)
    memcpy(run->extra, opts->breakpoints, run->nextra * sizeof *run->extra);
  return FB_OK;
}

/* The integrator at opts->t_start, x0 (NULL: the graph's). */
static int start_dynamic(sim_run *run, const double *x0, fb_err *err)
{
  if (SUNContext_Create(NULL, &run->sunctx) != 0)
    return fb_err_set(err, FB_ENOMEM, "out of memory creating the SUNDIALS context");
  /* CVODE clones its own vectors from y, with y's operations. */
  run->y = fb_sim_nvector_new(run->n, run->sunctx);
  run->ysam = fb_sim_nvector_new(run->n, run->sunctx);
  run->ybad = fb_sim_nvector_new(run->n, run->sunctx);
  if (!run->y || !run->ysam || !run->ybad)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the state vectors");
  /* A diagram linear within each mode has a constant Newton matrix
   * between events; the values are refreshed after each event. */
  run->linear = fb_bd_is_linear(run->bd) || fb_bd_is_piecewise_linear(run->bd);
  run->crossed = calloc(fb_bd_nguards(run->bd) + 1, sizeof *run->crossed);
  if (!run->crossed)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the guards");
  int rc = initial_state(run, x0, err);
  int changed = 0;
  if (rc == FB_OK)
    rc = sync_modes(run, run->opts->t_start, &changed, err);
  if (rc == FB_OK)
    rc = check_initial_rhs(run, err);
  if (rc == FB_OK)
    rc = collect_breakpoints(run, run->opts->t_start, err);
  if (rc == FB_OK)
    rc = make_auglin(run, err);
  if (rc == FB_OK)
    rc = make_cvode(run, err);
  return rc;
}

/* A stepper over bd at opts->t_start (checked options), recording into
 * res when not NULL (taken over). */
static int stepper_new(fb_bd *bd, const fb_sim_opts *opts, fb_result *res, sim_run **out,
                       fb_err *err)
{
  *out = NULL;
  sim_run *run = calloc(1, sizeof *run);
  if (!run) {
    fb_result_free(&res);
    return fb_err_set(err, FB_ENOMEM, "out of memory for a simulation");
  }
  run->bd = bd;
  run->o = *opts;
  run->o.x0 = NULL;
  run->o.breakpoints = NULL;
  run->opts = &run->o;
  run->n = fb_bd_nstates(bd);
  run->t_now = opts->t_start;
  run->res = res;
  fb_err_clear(&run->lin_err);
  fb_sample_grid_init(&run->grid, opts);
  int rc = keep_breakpoints(run, opts, err);
  if (rc == FB_OK && run->n)
    rc = start_dynamic(run, opts->x0, err);
  if (rc == FB_OK && res && run->n)
    rc = write_sample(run, 0, fb_sample_grid_time(&run->grid, 0), N_VGetArrayPointer(run->y),
                      err);
  run->next_sample = 1;
  if (rc != FB_OK) {
    fb_sim_stepper_free(&run);
    return rc;
  }
  *out = run;
  return FB_OK;
}

int fb_sim_stepper_create(fb_bd *bd, const fb_sim_opts *opts, fb_sim_stepper **out, fb_err *err)
{
  *out = NULL;
  /* Nothing is recorded: the samples' count and memory, which the check
   * bounds for a run, are no limit on a stepper (a co-simulation may go
   * on for days); one sample over the horizon passes that part. */
  fb_sim_opts checked = *opts;
  checked.noutputs = fb_bd_noutputs(bd);
  const double horizon = opts->t_end - opts->t_start;
  if (horizon > 0 && isfinite(horizon))
    checked.sample_rate = 1.0 / horizon;
  int rc = fb_sim_opts_check(&checked, err);
  if (rc == FB_OK)
    rc = stepper_new(bd, &checked, NULL, out, err);
  return rc;
}

void fb_sim_stepper_free(fb_sim_stepper **st)
{
  if (!st || !*st)
    return;
  run_free(*st);
  fb_result_free(&(*st)->res);
  free(*st);
  *st = NULL;
}

int fb_sim_stepper_advance(fb_sim_stepper *st, double t, fb_err *err)
{
  if (st->failed)
    return fb_err_set(err, FB_EINVAL,
                      "the simulation failed earlier, at t = %.6g s; it cannot go on",
                      st->t_now);
  if (!(t >= st->t_now) || t - st->o.t_end > fb_sim_same_time_tol(t, st->o.t_end)) {
    fb_err_set(err, FB_EINVAL, "advance to t = %g s: must be in [%.9g, %.9g] s (now to t_end)",
               t, st->t_now, st->o.t_end);
    fb_err_set_key(err, "t");
    return FB_EINVAL;
  }
  if (!st->n) {
    st->t_now = t;
    return FB_OK;
  }
  const int rc = advance_to(st, fmin(t, st->o.t_end), err);
  st->failed = rc != FB_OK && rc != FB_EINTR;
  return rc;
}

int fb_sim_stepper_reset(fb_sim_stepper *st, fb_err *err)
{
  if (st->failed)
    return fb_err_set(err, FB_EINVAL,
                      "the simulation failed earlier, at t = %.6g s; it cannot go on",
                      st->t_now);
  if (!st->n)
    return FB_OK;
  int changed = 0;
  int rc = restart_here(st, err);
  st->have_values = 0; /* the linearisation belongs to the old inputs or parameters */
  if (rc == FB_OK)
    rc = sync_modes(st, st->t_now, &changed, err);
  st->acc.events += changed;
  if (rc == FB_OK)
    rc = check_initial_rhs(st, err);
  if (rc == FB_OK)
    rc = collect_breakpoints(st, st->t_now, err);
  st->failed = rc != FB_OK;
  return rc;
}

int fb_sim_stepper_set_state(fb_sim_stepper *st, double t, const double *x, fb_err *err)
{
  if (!(t >= st->o.t_start - fb_sim_same_time_tol(t, st->o.t_start)) ||
      t - st->o.t_end > fb_sim_same_time_tol(t, st->o.t_end)) {
    fb_err_set(err, FB_EINVAL, "set the state at t = %g s: must be in [%.9g, %.9g] s", t,
               st->o.t_start, st->o.t_end);
    fb_err_set_key(err, "t");
    return FB_EINVAL;
  }
  if (!x && st->n)
    return fb_err_set(err, FB_EINVAL, "set the state: no state given");
  for (size_t i = 0; i < st->n; ++i)
    if (!isfinite(x[i])) {
      fb_err_set(err, FB_EINVAL, "set the state: %s = %g is not finite",
                 fb_bd_state_name(st->bd, i), x[i]);
      fb_err_set_key(err, "%s", fb_bd_state_name(st->bd, i));
      return FB_EINVAL;
    }
  st->t_now = t;
  if (!st->n)
    return FB_OK;
  memcpy(N_VGetArrayPointer(st->y), x, st->n * sizeof *x);
  st->failed = 0; /* the failure belonged to the state now replaced */
  return fb_sim_stepper_reset(st, err);
}

double fb_sim_stepper_time(const fb_sim_stepper *st)
{
  return st->t_now;
}

size_t fb_sim_stepper_nstates(const fb_sim_stepper *st)
{
  return st->n;
}

const double *fb_sim_stepper_state(const fb_sim_stepper *st)
{
  return st->n ? N_VGetArrayPointer(st->y) : NULL;
}

int fb_sim_stepper_outputs(fb_sim_stepper *st, double *y, fb_err *err)
{
  const double none = 0;
  return eval_outputs(st, st->t_now, st->n ? N_VGetArrayPointer(st->y) : &none, y, err);
}

void fb_sim_stepper_stats(const fb_sim_stepper *st, fb_sim_stats *stats)
{
  current_stats(st, stats);
}

int fb_sim_run(fb_bd *bd, const fb_sim_opts *opts, fb_result **out, fb_err *err)
{
  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  *out = NULL;
  /* With the diagram's own output count, which the caller's opts may not
   * know: the result's memory is estimated before it is allocated. */
  fb_sim_opts checked = *opts;
  checked.noutputs = fb_bd_noutputs(bd);
  int rc = fb_sim_opts_check(&checked, err);
  if (rc != FB_OK)
    return rc;
  fb_sample_grid grid;
  fb_sample_grid_init(&grid, opts);
  fb_result *res = NULL;
  rc = fb_result_alloc(bd, grid.n, &res, err);
  sim_run *run = NULL;
  if (rc == FB_OK)
    rc = stepper_new(bd, opts, res, &run, err);
  if (rc == FB_OK)
    rc = run->n ? integrate_to(run, opts->t_end, err) : sample_static(run, err);
  if (rc == FB_OK && run->n && run->next_sample != run->grid.n)
    rc = fb_err_set(err, FB_ESOLVER, "internal: %zu of %zu samples written", run->next_sample,
                    run->grid.n);
  if (rc == FB_OK) {
    current_stats(run, &run->res->stats);
    run->res->stats.wall_seconds = fb_seconds_since(&t0);
    *out = run->res;
    run->res = NULL;
  }
  fb_sim_stepper_free(&run);
  return rc;
}
