/* SPDX-License-Identifier: BSD-3-Clause */
/* The binary of a flexbond FMU: the FMI 3.0 functions (src/fmu/fmi3.h)
 * over a vehicle stepper (flexbond/vehicle.h) built from the scenario in
 * the FMU's resources/ (docs/fmi.md).
 *
 * Co-simulation: fmi3DoStep advances the stepper, so flexbond's own
 * integrator (CVODE's BDF with the block diagram's Newton matrix) takes
 * the step, with the road's kinks as stop times and the switched laws'
 * guards (a tire leaving the road) as located events inside it.
 *
 * Model exchange: the importer integrates. The FMU evaluates the
 * stepper's diagram at the importer's time and state: the derivatives,
 * the outputs and the switched laws' guards, whose zero crossings are
 * the event indicators; the road's kinks are time events
 * (nextEventTime). With the road as an input its height enters the
 * tires' displacement states, q = p + B (z - z0) (the stepper's road
 * coupling B; z0 the heights at the end of initialisation): the state
 * the importer integrates is p, which the road's height does not move,
 * so the height is an input of the model as the rate is.
 *
 * The calling sequence is FMI 3.0's state machine (sections 3.2 and
 * 4.2): a function called in a state that does not allow it returns
 * fmi3Error and logs why, and changes nothing. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"

#include "core/util.h"
#include "fmu/fmi3.h"
#include "fmu/fmu_internal.h"

/* The states of FMI 3.0's state machines that this FMU has (no
 * configuration mode, no clocks, no event mode in co-simulation). */
typedef enum fmu_state {
  ST_INSTANTIATED = 1 << 0,
  ST_INIT = 1 << 1,       /* Initialization Mode */
  ST_EVENT = 1 << 2,      /* ME: Event Mode */
  ST_CONTINUOUS = 1 << 3, /* ME: Continuous-Time Mode */
  ST_STEP = 1 << 4,       /* CS: Step Mode */
  ST_TERMINATED = 1 << 5,
  ST_FAILED = 1 << 6 /* after fmi3Error: reset or free */
} fmu_state;

enum { ST_RUNNING = ST_INIT | ST_EVENT | ST_CONTINUOUS | ST_STEP | ST_TERMINATED };

typedef enum fmu_interface { IF_MODEL_EXCHANGE, IF_CO_SIMULATION } fmu_interface;

typedef struct fmu {
  fmu_interface kind;
  char *name;
  char *resources; /* the resource folder, with its trailing '/' */
  fmi3InstanceEnvironment env;
  fmi3LogMessageCallback log;
  int logging;
  fmu_state state;
  fmu_config cfg;
  char *scenario_path;
  fb_vehicle_stepper *st;
  fmu_model *model;
  size_t n;            /* continuous states */
  size_t ni, np;       /* inputs, parameters */
  double *u;           /* ni: the inputs as the importer set them */
  double *u_model;     /* ni: as the model reads them (road heights less z0) */
  double *z0;          /* per input: the road heights at the end of initialisation */
  double *param;       /* np: the parameters' values */
  double *param_built; /* np: the values the stepper's vehicle was built with */
  double *x0;          /* n: the initial state (the scenario's) */
  double time;         /* ME: the importer's time; CS: the stepper's */
  double *p;           /* ME: n, the importer's states */
  double *x;           /* n: the diagram's state (ME: p + B (z - z0)) */
  double *xdot;        /* n */
  double *y;           /* outputs */
  double *g, *g_last;  /* guards now, and at the last accepted step or event */
  int *crossed;
  double *bps; /* the road's breakpoints, s */
  size_t nbps;
  /* Within one fmi3GetFloat64 call: the outputs, derivatives and
   * guards already evaluated (each once for all the values asked). */
  int have_y, have_xdot, have_g;
  double tolerance; /* 0: the scenario's */
  double stop_time;
  int stop_defined;
} fmu;

/* ---- Logging: the importer's callback, FMI's categories (2.4.5). */

static void say(fmu *f, fmi3Status status, const char *category, const char *fmt, ...)
{
  if (!f || !f->log || (!f->logging && status == fmi3OK))
    return;
  char msg[FB_ERR_MSG_MAX + 256];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  f->log(f->env, status, category, msg);
}

/* fmi3Error after a library error: the message logged, the FMU failed
 * (FMI 3.0, 2.2.3: after fmi3Error only reset or free). */
static fmi3Status fail(fmu *f, const char *what, const fb_err *err)
{
  say(f, fmi3Error, "logStatusError", "%s: %s", what, err->msg);
  f->state = ST_FAILED;
  return fmi3Error;
}

/* fmi3Error for a call the FMU refuses without failing: a wrong state or
 * argument; nothing changed. */
static fmi3Status refuse(fmu *f, const char *fmt, ...)
{
  if (!f || !f->log)
    return fmi3Error;
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  f->log(f->env, fmi3Error, "logStatusError", msg);
  return fmi3Error;
}

static const char *state_name(fmu_state s)
{
  switch (s) {
  case ST_INSTANTIATED: return "Instantiated";
  case ST_INIT: return "Initialization Mode";
  case ST_EVENT: return "Event Mode";
  case ST_CONTINUOUS: return "Continuous-Time Mode";
  case ST_STEP: return "Step Mode";
  case ST_TERMINATED: return "Terminated";
  case ST_FAILED: return "the state after an error";
  }
  return "?";
}

/* FMI's state machine: FB_OK if f may call fn now (allowed: a mask of
 * fmu_state), else logged. */
static int allowed(fmu *f, const char *fn, unsigned allowed_states)
{
  if (!f)
    return 0;
  if ((unsigned)f->state & allowed_states)
    return 1;
  refuse(f, "%s: not allowed in %s", fn, state_name(f->state));
  return 0;
}

static int is_me(fmu *f, const char *fn)
{
  if (f->kind == IF_MODEL_EXCHANGE)
    return 1;
  refuse(f, "%s: a model exchange function, and this instance is a co-simulation one", fn);
  return 0;
}

static int is_cs(fmu *f, const char *fn)
{
  if (f->kind == IF_CO_SIMULATION)
    return 1;
  refuse(f, "%s: a co-simulation function, and this instance is a model exchange one", fn);
  return 0;
}

/* ---- Building the vehicle. */

static void release_arrays(fmu *f)
{
  free(f->u);
  free(f->u_model);
  free(f->z0);
  free(f->param);
  free(f->param_built);
  free(f->x0);
  free(f->p);
  free(f->x);
  free(f->xdot);
  free(f->y);
  free(f->g);
  free(f->g_last);
  free(f->crossed);
  free(f->bps);
  f->u = f->u_model = f->z0 = f->param = f->param_built = f->x0 = NULL;
  f->p = f->x = f->xdot = f->y = f->g = f->g_last = f->bps = NULL;
  f->crossed = NULL;
}

static int alloc_arrays(fmu *f, fb_err *err)
{
  const fmu_model *m = f->model;
  f->n = m->nstates;
  f->ni = m->ninputs;
  f->np = m->nparameters;
  f->u = calloc(f->ni + 1, sizeof *f->u);
  f->u_model = calloc(f->ni + 1, sizeof *f->u_model);
  f->z0 = calloc(f->ni + 1, sizeof *f->z0);
  f->param = calloc(f->np + 1, sizeof *f->param);
  f->param_built = calloc(f->np + 1, sizeof *f->param_built);
  f->x0 = calloc(f->n + 1, sizeof *f->x0);
  f->p = calloc(f->n + 1, sizeof *f->p);
  f->x = calloc(f->n + 1, sizeof *f->x);
  f->xdot = calloc(f->n + 1, sizeof *f->xdot);
  f->y = calloc(m->noutputs + 1, sizeof *f->y);
  f->g = calloc(m->nindicators + 1, sizeof *f->g);
  f->g_last = calloc(m->nindicators + 1, sizeof *f->g_last);
  f->crossed = calloc(m->nindicators + 1, sizeof *f->crossed);
  if (!f->u || !f->u_model || !f->z0 || !f->param || !f->param_built || !f->x0 || !f->p ||
      !f->x || !f->xdot || !f->y || !f->g || !f->g_last || !f->crossed)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  return FB_OK;
}

/* The road's breakpoints (time events for model exchange). */
static int collect_breakpoints(fmu *f, fb_err *err)
{
  const fb_bd *bd = fb_vehicle_stepper_diagram(f->st);
  const size_t bound = fb_bd_breakpoints(bd, NULL, 0);
  free(f->bps);
  f->bps = malloc((bound + 1) * sizeof *f->bps);
  if (!f->bps)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu breakpoints", bound);
  f->nbps = fb_bd_breakpoints(bd, f->bps, bound);
  return FB_OK;
}

/* The scenario with the parameters at values (NULL: the file's) and the
 * importer's tolerance (*s new). */
static int load_scenario(const fmu *f, const double *values, fb_scenario **s, fb_err *err)
{
  const int rc = fmu_scenario_load(f->scenario_path, &f->cfg, values, s, err);
  if (!rc && f->tolerance > 0)
    (*s)->rtol = f->tolerance;
  return rc;
}

/* A stepper of the scenario with the parameters at values (NULL: the
 * file's), replacing f's (*st new). */
static int new_stepper(fmu *f, const double *values, fb_vehicle_stepper **st, fb_err *err)
{
  fb_scenario *s = NULL;
  fb_vehicle_opts o;
  fb_vehicle_opts_default(&o);
  o.road_inputs = f->cfg.road_inputs;
  int rc = load_scenario(f, values, &s, err);
  if (!rc)
    rc = fb_vehicle_stepper_new(s, f->cfg.system, &o, st, err);
  fb_scenario_free(&s);
  return rc;
}

/* Reads the FMU's choices and builds its vehicle and table; checks the
 * importer's token against the table's. */
static int build(fmu *f, const char *token, fb_err *err)
{
  char *cfg_path = fb_strdup_printf("%s%s", f->resources, FMU_CONFIG_NAME);
  int rc = cfg_path ? fmu_config_read(cfg_path, &f->cfg, err)
                    : fb_err_set(err, FB_ENOMEM, "out of memory");
  free(cfg_path);
  if (!rc && !(f->scenario_path = fb_strdup_printf("%s%s", f->resources, f->cfg.scenario)))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = new_stepper(f, NULL, &f->st, err);
  fb_scenario *s = NULL;
  double *start = calloc(f->cfg.nparameters + 1, sizeof *start);
  const char **unit = calloc(f->cfg.nparameters + 1, sizeof *unit);
  if (!rc && (!start || !unit))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc && f->cfg.nparameters)
    rc = fmu_scenario_load(f->scenario_path, &f->cfg, NULL, &s, err);
  for (size_t p = 0; !rc && p < f->cfg.nparameters; ++p)
    rc = fmu_parameter_value(s, f->cfg.parameter[p], &start[p], &unit[p], err);
  if (!rc)
    rc = fmu_model_new(f->st, &f->cfg, start, unit, &f->model, err);
  fb_scenario_free(&s);
  free(unit);
  if (!rc && token && strcmp(token, f->model->token) != 0)
    rc = fb_err_set(err, FB_EINVAL,
                    "the instantiation token %s is not this FMU's %s: the model description "
                    "and the binary come from different builds",
                    token, f->model->token);
  if (!rc)
    rc = alloc_arrays(f, err);
  if (!rc) {
    memcpy(f->param, start, f->np * sizeof *start);
    memcpy(f->param_built, start, f->np * sizeof *start);
    if (f->n)
      memcpy(f->x0, fb_vehicle_stepper_state(f->st), f->n * sizeof *f->x0);
    rc = collect_breakpoints(f, err);
  }
  free(start);
  return rc;
}

static void destroy(fmu *f)
{
  if (!f)
    return;
  fb_vehicle_stepper_free(&f->st);
  fmu_model_free(&f->model);
  fmu_config_release(&f->cfg);
  release_arrays(f);
  free(f->scenario_path);
  free(f->resources);
  free(f->name);
  free(f);
}

/* The instance's name and resource folder (with its trailing '/'),
 * copied. */
static int keep_names(fmu *f, const char *name, const char *resources, fb_err *err)
{
  const size_t len = strlen(resources);
  f->name = fb_strdup(name);
  f->resources = fb_strdup_printf("%s%s", resources, resources[len - 1] == '/' ? "" : "/");
  return f->name && f->resources ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
}

static fmu *instantiate(fmu_interface kind, fmi3String name, fmi3String token,
                        fmi3String resources, fmi3Boolean logging, fmi3InstanceEnvironment env,
                        fmi3LogMessageCallback log)
{
  fmu *f = calloc(1, sizeof *f);
  if (!f)
    return NULL;
  f->kind = kind;
  f->env = env;
  f->log = log;
  f->logging = logging;
  f->state = ST_INSTANTIATED;
  fb_err err;
  fb_err_clear(&err);
  int rc = FB_OK;
  if (!name || !*name)
    rc = fb_err_set(&err, FB_EINVAL, "the instance name is empty");
  else if (!resources || !*resources)
    rc = fb_err_set(&err, FB_EINVAL, "no resource path: the FMU needs its resources/ folder");
  else
    rc = keep_names(f, name, resources, &err);
  if (!rc)
    rc = build(f, token, &err);
  if (rc) {
    say(f, fmi3Error, "logStatusError", "%s: %s", name ? name : "(no name)", err.msg);
    destroy(f);
    return NULL;
  }
  say(f, fmi3OK, "logEvents", "%s: %zu states, %zu inputs, %zu outputs, %zu parameters",
      f->name, f->n, f->ni, f->model->noutputs, f->np);
  return f;
}

/* The last time the importer may reach: its stopTime when it gave one,
 * else the FMU's horizon (FMI 3.0, fmi3EnterInitializationMode: past a
 * defined stopTime the FMU returns fmi3Error). */
static double last_time(const fmu *f)
{
  return f->stop_defined ? f->stop_time : f->cfg.t_end;
}

/* ---- The model's values. */

/* u as the stepper reads it: road heights relative to the start's. */
static void model_inputs(fmu *f)
{
  for (size_t i = 0; i < f->ni; ++i)
    f->u_model[i] = f->u[i] - f->z0[i];
}

/* ME: the diagram's state x from the importer's p and the road's
 * heights, and the inputs held. */
static void me_state(fmu *f)
{
  model_inputs(f);
  fb_vehicle_stepper_hold_inputs(f->st, f->u_model);
  memcpy(f->x, f->p, f->n * sizeof *f->x);
  const double *b = fb_vehicle_stepper_road_coupling(f->st);
  const fb_scenario *s = fb_vehicle_stepper_scenario(f->st);
  for (size_t c = 0; b && c < s->ncorners; ++c) {
    const double z = f->u_model[FB_VEHICLE_NINPUTS + 2 * c]; /* the stepper's layout */
    for (size_t i = 0; z != 0.0 && i < f->n; ++i)
      f->x[i] += b[c * f->n + i] * z;
  }
}

/* ME: the derivatives of p at the importer's (t, p, u) into f->xdot. */
static int me_derivatives(fmu *f, fb_err *err)
{
  me_state(f);
  fb_bd *bd = fb_vehicle_stepper_diagram(f->st);
  if (fb_bd_rhs(bd, f->time, f->x, f->xdot) != 0)
    return fb_err_set(err, FB_ESOLVER, "the derivatives at t = %g s: %s", f->time,
                      fb_bd_last_error(bd));
  const double *b = fb_vehicle_stepper_road_coupling(f->st);
  const fb_scenario *s = fb_vehicle_stepper_scenario(f->st);
  for (size_t c = 0; b && c < s->ncorners; ++c) {
    const double zdot = f->u_model[FB_VEHICLE_NINPUTS + 2 * c + 1];
    for (size_t i = 0; i < f->n; ++i)
      f->xdot[i] -= b[c * f->n + i] * zdot;
  }
  return FB_OK;
}

static int me_outputs(fmu *f, fb_err *err)
{
  me_state(f);
  fb_bd *bd = fb_vehicle_stepper_diagram(f->st);
  if (fb_bd_outputs(bd, f->time, f->x, f->y) != 0)
    return fb_err_set(err, FB_ESOLVER, "the outputs at t = %g s: %s", f->time,
                      fb_bd_last_error(bd));
  return FB_OK;
}

static int me_guards(fmu *f, double *g, fb_err *err)
{
  me_state(f);
  fb_bd *bd = fb_vehicle_stepper_diagram(f->st);
  if (fb_bd_guards(bd, f->time, f->x, g) != 0)
    return fb_err_set(err, FB_ESOLVER, "the event indicators at t = %g s: %s", f->time,
                      fb_bd_last_error(bd));
  return FB_OK;
}

/* CS: the pending inputs and parameters given to the stepper. */
static int cs_apply(fmu *f, fb_err *err)
{
  int rc = FB_OK;
  if (f->np && memcmp(f->param, f->param_built, f->np * sizeof *f->param) != 0) {
    fb_scenario *s = NULL;
    rc = load_scenario(f, f->param, &s, err);
    if (!rc)
      rc = fb_vehicle_stepper_set_scenario(f->st, s, err);
    fb_scenario_free(&s);
    if (!rc)
      memcpy(f->param_built, f->param, f->np * sizeof *f->param);
  }
  model_inputs(f);
  if (!rc)
    rc = fb_vehicle_stepper_set_inputs(f->st, f->u_model, err);
  return rc;
}

/* The value of variable vr now. */
static int get_value(fmu *f, size_t vr, double *value, fb_err *err)
{
  const fmu_var *v = &f->model->var[vr];
  int rc = FB_OK;
  switch (v->kind) {
  case FMU_VAR_TIME:
    *value = f->kind == IF_CO_SIMULATION ? fb_vehicle_stepper_time(f->st) : f->time;
    break;
  case FMU_VAR_INPUT: *value = f->u[v->index]; break;
  case FMU_VAR_PARAMETER: *value = f->param[v->index]; break;
  case FMU_VAR_OUTPUT:
    if (!f->have_y)
      rc = f->kind == IF_CO_SIMULATION ? fb_vehicle_stepper_outputs(f->st, f->y, err)
                                       : me_outputs(f, err);
    f->have_y = !rc;
    *value = f->y[v->index];
    break;
  case FMU_VAR_STATE:
    *value = f->kind == IF_CO_SIMULATION ? fb_vehicle_stepper_state(f->st)[v->index]
                                         : f->p[v->index];
    break;
  case FMU_VAR_DERIVATIVE:
    if (f->have_xdot) {
      /* evaluated for an earlier value of this call */
    } else if (f->kind == IF_CO_SIMULATION) {
      fb_bd *bd = fb_vehicle_stepper_diagram(f->st);
      if (fb_bd_rhs(bd, fb_vehicle_stepper_time(f->st), fb_vehicle_stepper_state(f->st),
                    f->xdot) != 0)
        rc = fb_err_set(err, FB_ESOLVER, "the derivatives: %s", fb_bd_last_error(bd));
    } else {
      rc = me_derivatives(f, err);
    }
    f->have_xdot = !rc;
    *value = f->xdot[v->index];
    break;
  case FMU_VAR_INDICATOR:
    if (f->have_g) {
      /* evaluated for an earlier value of this call */
    } else if (f->kind == IF_MODEL_EXCHANGE) {
      rc = me_guards(f, f->g, err);
    } else {
      fb_bd *bd = fb_vehicle_stepper_diagram(f->st);
      if (fb_bd_guards(bd, fb_vehicle_stepper_time(f->st), fb_vehicle_stepper_state(f->st),
                       f->g) != 0)
        rc = fb_err_set(err, FB_ESOLVER, "the event indicators: %s", fb_bd_last_error(bd));
    }
    f->have_g = !rc;
    *value = f->g[v->index];
    break;
  }
  return rc;
}

/* May the importer set variable v now (FMI 3.0, 2.2.7.2)? */
static int settable(fmu *f, const fmu_var *v)
{
  if (v->kind == FMU_VAR_INPUT)
    return (f->state & (ST_INSTANTIATED | ST_INIT | ST_EVENT | ST_CONTINUOUS | ST_STEP)) != 0;
  if (v->kind == FMU_VAR_PARAMETER && v->fixed) /* before initialisation ends */
    return (f->state & (ST_INSTANTIATED | ST_INIT)) != 0;
  if (v->kind == FMU_VAR_PARAMETER) /* tunable: not while the importer integrates */
    return (f->state & (ST_INSTANTIATED | ST_INIT | ST_EVENT | ST_STEP)) != 0;
  return 0;
}

/* ---- Common functions (FMI 3.0, 2.3). */

const char *fmi3GetVersion(void)
{
  return FB_FMI3_VERSION;
}

fmi3Status fmi3SetDebugLogging(fmi3Instance instance, fmi3Boolean loggingOn, size_t nCategories,
                               const fmi3String categories[])
{
  fmu *f = instance;
  if (!f)
    return fmi3Error;
  (void)nCategories;
  (void)categories;
  f->logging = loggingOn;
  return fmi3OK;
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String instanceName,
                                          fmi3String instantiationToken,
                                          fmi3String resourcePath, fmi3Boolean visible,
                                          fmi3Boolean loggingOn,
                                          fmi3InstanceEnvironment instanceEnvironment,
                                          fmi3LogMessageCallback logMessage)
{
  (void)visible;
  return instantiate(IF_MODEL_EXCHANGE, instanceName, instantiationToken, resourcePath,
                     loggingOn, instanceEnvironment, logMessage);
}

fmi3Instance fmi3InstantiateCoSimulation(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate)
{
  (void)visible;
  (void)earlyReturnAllowed;
  (void)requiredIntermediateVariables;
  (void)intermediateUpdate;
  if (eventModeUsed) {
    /* hasEventMode is false in the description: events are handled
     * inside fmi3DoStep. */
    if (logMessage)
      logMessage(instanceEnvironment, fmi3Error, "logStatusError",
                 "this FMU has no co-simulation event mode (hasEventMode=\"false\")");
    return NULL;
  }
  if (nRequiredIntermediateVariables && logMessage)
    logMessage(instanceEnvironment, fmi3Warning, "logStatusWarning",
               "no intermediate updates: the required intermediate variables are ignored");
  return instantiate(IF_CO_SIMULATION, instanceName, instantiationToken, resourcePath,
                     loggingOn, instanceEnvironment, logMessage);
}

fmi3Instance fmi3InstantiateScheduledExecution(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
    fmi3LockPreemptionCallback lockPreemption, fmi3UnlockPreemptionCallback unlockPreemption)
{
  (void)instanceName;
  (void)instantiationToken;
  (void)resourcePath;
  (void)visible;
  (void)loggingOn;
  (void)clockUpdate;
  (void)lockPreemption;
  (void)unlockPreemption;
  if (logMessage)
    logMessage(instanceEnvironment, fmi3Error, "logStatusError",
               "this FMU has no scheduled execution interface");
  return NULL;
}

void fmi3FreeInstance(fmi3Instance instance)
{
  destroy(instance);
}

fmi3Status fmi3EnterInitializationMode(fmi3Instance instance, fmi3Boolean toleranceDefined,
                                       fmi3Float64 tolerance, fmi3Float64 startTime,
                                       fmi3Boolean stopTimeDefined, fmi3Float64 stopTime)
{
  fmu *f = instance;
  if (!allowed(f, "fmi3EnterInitializationMode", ST_INSTANTIATED))
    return fmi3Error;
  if (startTime != 0.0)
    return refuse(f,
                  "fmi3EnterInitializationMode: startTime = %g s: the vehicle's run starts "
                  "at 0 (the road is placed in time from there)",
                  startTime);
  if (toleranceDefined && !(tolerance > 0 && tolerance < 1))
    return refuse(f, "fmi3EnterInitializationMode: tolerance %g: must be in (0, 1)", tolerance);
  if (stopTimeDefined && !(stopTime > 0))
    return refuse(f, "fmi3EnterInitializationMode: stopTime = %g s: must be after the start, 0",
                  stopTime);
  if (stopTimeDefined && stopTime > f->cfg.t_end * (1 + 1e-12))
    return refuse(f,
                  "fmi3EnterInitializationMode: stopTime = %g s: this FMU runs to %g s at most "
                  "(flexbond fmu --t-end sets that)",
                  stopTime, f->cfg.t_end);
  f->tolerance = toleranceDefined ? tolerance : 0.0;
  f->stop_defined = stopTimeDefined;
  f->stop_time = stopTime;
  f->time = 0.0;
  f->state = ST_INIT;
  return fmi3OK;
}

/* The vehicle for the parameters and tolerance the importer chose, at
 * its initial state. */
static int initial_vehicle(fmu *f, fb_err *err)
{
  int rc = FB_OK;
  if ((f->np && memcmp(f->param, f->param_built, f->np * sizeof *f->param) != 0) ||
      f->tolerance > 0) {
    fb_vehicle_stepper *st = NULL;
    rc = new_stepper(f, f->param, &st, err);
    if (!rc && fb_vehicle_stepper_nstates(st) != f->n)
      rc = fb_err_set(err, FB_EINVAL, "the parameters change the model's states");
    if (rc) {
      fb_vehicle_stepper_free(&st);
      return rc;
    }
    fb_vehicle_stepper_free(&f->st);
    f->st = st;
    memcpy(f->param_built, f->param, f->np * sizeof *f->param);
    if (f->n)
      memcpy(f->x0, fb_vehicle_stepper_state(f->st), f->n * sizeof *f->x0);
    rc = collect_breakpoints(f, err);
  }
  /* The road's heights now are the wheels' start: z0. */
  for (size_t i = FB_VEHICLE_NINPUTS; i < f->ni; i += 2)
    f->z0[i] = f->u[i];
  memcpy(f->p, f->x0, f->n * sizeof *f->p);
  if (!rc)
    rc = fb_vehicle_stepper_set_state(f->st, 0.0, f->x0, err);
  if (!rc && f->kind == IF_CO_SIMULATION)
    rc = cs_apply(f, err);
  return rc;
}

fmi3Status fmi3ExitInitializationMode(fmi3Instance instance)
{
  fmu *f = instance;
  if (!allowed(f, "fmi3ExitInitializationMode", ST_INIT))
    return fmi3Error;
  fb_err err;
  fb_err_clear(&err);
  if (initial_vehicle(f, &err))
    return fail(f, "fmi3ExitInitializationMode", &err);
  if (f->kind == IF_MODEL_EXCHANGE) {
    /* Event Mode: the modes chosen from the start's guards. */
    me_state(f);
    int changed = 0;
    fb_bd *bd = fb_vehicle_stepper_diagram(f->st);
    if (fb_bd_sync_modes(bd, f->time, f->x, &changed) != 0) {
      fb_err_set(&err, FB_ESOLVER, "%s", fb_bd_last_error(bd));
      return fail(f, "fmi3ExitInitializationMode", &err);
    }
    f->state = ST_EVENT;
  } else {
    f->state = ST_STEP;
  }
  return fmi3OK;
}

fmi3Status fmi3EnterEventMode(fmi3Instance instance)
{
  fmu *f = instance;
  if (!f || !is_me(f, "fmi3EnterEventMode") || !allowed(f, "fmi3EnterEventMode", ST_CONTINUOUS))
    return fmi3Error;
  f->state = ST_EVENT;
  return fmi3OK;
}

fmi3Status fmi3Terminate(fmi3Instance instance)
{
  fmu *f = instance;
  if (!allowed(f, "fmi3Terminate", ST_EVENT | ST_CONTINUOUS | ST_STEP))
    return fmi3Error;
  f->state = ST_TERMINATED;
  return fmi3OK;
}

fmi3Status fmi3Reset(fmi3Instance instance)
{
  fmu *f = instance;
  if (!f)
    return fmi3Error;
  /* The parameters and inputs as instantiated, the vehicle at its start. */
  fb_err err;
  fb_err_clear(&err);
  for (size_t p = 0; p < f->np; ++p)
    f->param[p] = f->model->var[f->model->first_parameter + p].start;
  memset(f->u, 0, f->ni * sizeof *f->u);
  memset(f->z0, 0, f->ni * sizeof *f->z0);
  f->tolerance = 0.0;
  f->time = 0.0;
  f->state = ST_INSTANTIATED;
  model_inputs(f);
  fb_vehicle_stepper_hold_inputs(f->st, f->u_model);
  int rc = FB_OK;
  if (f->np && memcmp(f->param, f->param_built, f->np * sizeof *f->param) != 0) {
    fb_vehicle_stepper *st = NULL;
    rc = new_stepper(f, NULL, &st, &err);
    if (!rc) {
      fb_vehicle_stepper_free(&f->st);
      f->st = st;
      memcpy(f->param_built, f->param, f->np * sizeof *f->param);
      rc = collect_breakpoints(f, &err);
    }
  }
  if (!rc)
    rc = fb_vehicle_stepper_set_state(f->st, 0.0, f->x0, &err);
  return rc ? fail(f, "fmi3Reset", &err) : fmi3OK;
}

/* The variable vr refers to, or NULL (logged). */
static const fmu_var *find_var(fmu *f, const char *fn, fmi3ValueReference vr)
{
  if (vr < f->model->nvars)
    return &f->model->var[vr];
  refuse(f, "%s: no Float64 variable has value reference %u", fn, (unsigned)vr);
  return NULL;
}

fmi3Status fmi3GetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Float64 values[], size_t nValues)
{
  fmu *f = instance;
  if (!allowed(f, "fmi3GetFloat64", ST_RUNNING | ST_INSTANTIATED))
    return fmi3Error;
  if (nValues != nValueReferences)
    return refuse(f, "fmi3GetFloat64: %zu values for %zu value references (all are scalars)",
                  nValues, nValueReferences);
  fb_err err;
  fb_err_clear(&err);
  f->have_y = f->have_xdot = f->have_g = 0; /* the state may have changed since */
  for (size_t k = 0; k < nValueReferences; ++k) {
    const fmu_var *v = find_var(f, "fmi3GetFloat64", valueReferences[k]);
    if (!v)
      return fmi3Error;
    if (f->state == ST_INSTANTIATED && v->kind != FMU_VAR_INPUT &&
        v->kind != FMU_VAR_PARAMETER && v->kind != FMU_VAR_TIME)
      return refuse(f, "fmi3GetFloat64: %s is computed only from Initialization Mode on",
                    v->name);
    if (get_value(f, valueReferences[k], &values[k], &err))
      return fail(f, "fmi3GetFloat64", &err);
  }
  return fmi3OK;
}

/* 0 if the parameters among vr[0 .. n) at values make a scenario the
 * reader accepts (read and checked as a file is: a value it refuses is
 * refused when set, not at the next step), else refused (logged). */
static int set_parameters_check(fmu *f, const fmi3ValueReference vr[], size_t n,
                                const double values[])
{
  int any = 0;
  for (size_t k = 0; k < n; ++k)
    any |= f->model->var[vr[k]].kind == FMU_VAR_PARAMETER;
  if (!any)
    return 0;
  double *param = malloc(f->np * sizeof *param);
  if (!param) {
    refuse(f, "fmi3SetFloat64: out of memory");
    return -1;
  }
  memcpy(param, f->param, f->np * sizeof *param);
  for (size_t k = 0; k < n; ++k)
    if (f->model->var[vr[k]].kind == FMU_VAR_PARAMETER)
      param[f->model->var[vr[k]].index] = values[k];
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *sc = NULL;
  /* The description's own check too, but for the road's rules when the
   * road is an input (the vehicle does not drive on the scenario's). */
  const int rc = load_scenario(f, param, &sc, &err) ||
                 (!f->cfg.road_inputs && fb_scenario_check(sc, &err));
  fb_scenario_free(&sc);
  free(param);
  if (rc)
    refuse(f, "fmi3SetFloat64: %s", err.msg);
  return rc ? -1 : 0;
}

fmi3Status fmi3SetFloat64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Float64 values[], size_t nValues)
{
  fmu *f = instance;
  if (!allowed(f, "fmi3SetFloat64",
               ST_INSTANTIATED | ST_INIT | ST_EVENT | ST_CONTINUOUS | ST_STEP))
    return fmi3Error;
  if (nValues != nValueReferences)
    return refuse(f, "fmi3SetFloat64: %zu values for %zu value references (all are scalars)",
                  nValues, nValueReferences);
  /* Every one checked before any is set: a refused call changes nothing. */
  for (size_t k = 0; k < nValueReferences; ++k) {
    const fmu_var *v = find_var(f, "fmi3SetFloat64", valueReferences[k]);
    if (!v)
      return fmi3Error;
    if (!settable(f, v))
      return refuse(f, "fmi3SetFloat64: %s (value reference %u) cannot be set in %s", v->name,
                    (unsigned)valueReferences[k], state_name(f->state));
    if (!isfinite(values[k]))
      return refuse(f, "fmi3SetFloat64: %s = %g is not finite", v->name, values[k]);
  }
  if (set_parameters_check(f, valueReferences, nValueReferences, values))
    return fmi3Error;
  for (size_t k = 0; k < nValueReferences; ++k) {
    const fmu_var *v = &f->model->var[valueReferences[k]];
    if (v->kind == FMU_VAR_INPUT)
      f->u[v->index] = values[k];
    else
      f->param[v->index] = values[k];
  }
  return fmi3OK;
}

/* The types this FMU has no variable of: any value reference is wrong. */
static fmi3Status no_such_type(fmi3Instance instance, const char *fn, size_t nvr)
{
  fmu *f = instance;
  if (!f)
    return fmi3Error;
  if (!nvr)
    return fmi3OK;
  return refuse(f, "%s: this FMU has Float64 variables only", fn);
}

fmi3Status fmi3GetFloat32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Float32 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetFloat32", nValueReferences);
}

fmi3Status fmi3GetInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                       size_t nValueReferences, fmi3Int8 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetInt8", nValueReferences);
}

fmi3Status fmi3GetUInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3UInt8 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetUInt8", nValueReferences);
}

fmi3Status fmi3GetInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Int16 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetInt16", nValueReferences);
}

fmi3Status fmi3GetUInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, fmi3UInt16 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetUInt16", nValueReferences);
}

fmi3Status fmi3GetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Int32 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetInt32", nValueReferences);
}

fmi3Status fmi3GetUInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, fmi3UInt32 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetUInt32", nValueReferences);
}

fmi3Status fmi3GetInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Int64 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetInt64", nValueReferences);
}

fmi3Status fmi3GetUInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, fmi3UInt64 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetUInt64", nValueReferences);
}

fmi3Status fmi3GetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, fmi3Boolean values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetBoolean", nValueReferences);
}

fmi3Status fmi3GetString(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, fmi3String values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetString", nValueReferences);
}

fmi3Status fmi3GetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, size_t valueSizes[], fmi3Binary values[],
                         size_t nValues)
{
  (void)valueReferences;
  (void)valueSizes;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3GetBinary", nValueReferences);
}

fmi3Status fmi3GetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, fmi3Clock values[])
{
  (void)valueReferences;
  (void)values;
  return no_such_type(instance, "fmi3GetClock", nValueReferences);
}

fmi3Status fmi3SetFloat32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Float32 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetFloat32", nValueReferences);
}

fmi3Status fmi3SetInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                       size_t nValueReferences, const fmi3Int8 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetInt8", nValueReferences);
}

fmi3Status fmi3SetUInt8(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3UInt8 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetUInt8", nValueReferences);
}

fmi3Status fmi3SetInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Int16 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetInt16", nValueReferences);
}

fmi3Status fmi3SetUInt16(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const fmi3UInt16 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetUInt16", nValueReferences);
}

fmi3Status fmi3SetInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Int32 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetInt32", nValueReferences);
}

fmi3Status fmi3SetUInt32(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const fmi3UInt32 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetUInt32", nValueReferences);
}

fmi3Status fmi3SetInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Int64 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetInt64", nValueReferences);
}

fmi3Status fmi3SetUInt64(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const fmi3UInt64 values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetUInt64", nValueReferences);
}

fmi3Status fmi3SetBoolean(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                          size_t nValueReferences, const fmi3Boolean values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetBoolean", nValueReferences);
}

fmi3Status fmi3SetString(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const fmi3String values[], size_t nValues)
{
  (void)valueReferences;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetString", nValueReferences);
}

fmi3Status fmi3SetBinary(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                         size_t nValueReferences, const size_t valueSizes[],
                         const fmi3Binary values[], size_t nValues)
{
  (void)valueReferences;
  (void)valueSizes;
  (void)values;
  (void)nValues;
  return no_such_type(instance, "fmi3SetBinary", nValueReferences);
}

fmi3Status fmi3SetClock(fmi3Instance instance, const fmi3ValueReference valueReferences[],
                        size_t nValueReferences, const fmi3Clock values[])
{
  (void)valueReferences;
  (void)values;
  return no_such_type(instance, "fmi3SetClock", nValueReferences);
}

/* A capability the description declares absent (FMI 3.0 lets an FMU
 * without it return fmi3Error). */
static fmi3Status unsupported(fmi3Instance instance, const char *fn, const char *why)
{
  return instance ? refuse(instance, "%s: %s", fn, why) : fmi3Error;
}

fmi3Status fmi3GetNumberOfVariableDependencies(fmi3Instance instance,
                                               fmi3ValueReference valueReference,
                                               size_t *nDependencies)
{
  (void)valueReference;
  (void)nDependencies;
  return unsupported(instance, "fmi3GetNumberOfVariableDependencies",
                     "dependencies are not declared: every unknown may depend on every known");
}

fmi3Status fmi3GetVariableDependencies(fmi3Instance instance, fmi3ValueReference dependent,
                                       size_t elementIndicesOfDependent[],
                                       fmi3ValueReference independents[],
                                       size_t elementIndicesOfIndependents[],
                                       fmi3DependencyKind dependencyKinds[],
                                       size_t nDependencies)
{
  (void)dependent;
  (void)elementIndicesOfDependent;
  (void)independents;
  (void)elementIndicesOfIndependents;
  (void)dependencyKinds;
  (void)nDependencies;
  return unsupported(instance, "fmi3GetVariableDependencies",
                     "dependencies are not declared: every unknown may depend on every known");
}

/* ---- FMU states (FMI 3.0, 2.2.11): one block of doubles, serialised as
 * it is. Layout: magic, version, kind, n, ni, np, then time, the
 * state (CS: the stepper's x; ME: p), u, z0, param, the inputs as the
 * stepper holds them (the road's heights where the road is then), and
 * the state machine's state: a state set after an error brings the
 * instance back to where it was (FMI 3.0, 2.2.3). A state is checked
 * whole before any of it is used: a refused one changes nothing. */

enum { SNAP_MAGIC = 0x46424d55 /* "FBMU" */, SNAP_VERSION = 1, SNAP_HEAD = 6 };

typedef struct snapshot {
  size_t size; /* doubles */
  double v[];
} snapshot;

static size_t snap_doubles(const fmu *f)
{
  return SNAP_HEAD + 1 + f->n + 3 * f->ni + f->np + 1;
}

/* The instance's stepper restarted at its own state: a state taken and
 * one restored go on identically (both from a fresh integrator). */
static int cs_restart_here(fmu *f, fb_err *err)
{
  const double t = fb_vehicle_stepper_time(f->st);
  return fb_vehicle_stepper_set_state(f->st, t, fb_vehicle_stepper_state(f->st), err);
}

fmi3Status fmi3GetFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
  fmu *f = instance;
  if (!allowed(f, "fmi3GetFMUState",
               ST_INIT | ST_EVENT | ST_CONTINUOUS | ST_STEP | ST_TERMINATED | ST_INSTANTIATED))
    return fmi3Error;
  if (!FMUState)
    return refuse(f, "fmi3GetFMUState: FMUState is NULL");
  fb_err err;
  fb_err_clear(&err);
  if (f->kind == IF_CO_SIMULATION && f->state != ST_INSTANTIATED && f->state != ST_INIT &&
      cs_restart_here(f, &err))
    return fail(f, "fmi3GetFMUState", &err);
  const size_t nd = snap_doubles(f);
  snapshot *s = *FMUState ? *FMUState : malloc(sizeof *s + nd * sizeof(double));
  if (!s)
    return refuse(f, "fmi3GetFMUState: out of memory");
  s->size = nd;
  double *v = s->v;
  const double head[SNAP_HEAD] = {SNAP_MAGIC,   SNAP_VERSION,  f->kind,
                                  (double)f->n, (double)f->ni, (double)f->np};
  memcpy(v, head, sizeof head);
  v += SNAP_HEAD;
  *v++ = f->kind == IF_CO_SIMULATION ? fb_vehicle_stepper_time(f->st) : f->time;
  if (f->n)
    memcpy(v, f->kind == IF_CO_SIMULATION ? fb_vehicle_stepper_state(f->st) : f->p,
           f->n * sizeof *v);
  v += f->n;
  memcpy(v, f->u, f->ni * sizeof *v);
  v += f->ni;
  memcpy(v, f->z0, f->ni * sizeof *v);
  v += f->ni;
  memcpy(v, f->param, f->np * sizeof *v);
  v += f->np;
  for (size_t i = 0; i < f->ni; ++i)
    v[i] = fb_vehicle_stepper_input(f->st, i);
  v += f->ni;
  *v = (double)f->state;
  *FMUState = s;
  return fmi3OK;
}

/* FB_OK if s is a state of an instance like f. */
static int snap_fits(const fmu *f, const snapshot *s)
{
  return s->size == snap_doubles(f) && s->v[0] == SNAP_MAGIC && s->v[1] == SNAP_VERSION &&
         s->v[2] == f->kind && s->v[3] == (double)f->n && s->v[4] == (double)f->ni &&
         s->v[5] == (double)f->np;
}

/* The states a snapshot of f may hold: those its interface has. */
static int snap_mode_valid(const fmu *f, double mode)
{
  const unsigned ok = ST_INSTANTIATED | ST_INIT | ST_TERMINATED |
                      (f->kind == IF_CO_SIMULATION ? ST_STEP : ST_EVENT | ST_CONTINUOUS);
  if (!(mode >= 1 && mode <= ST_FAILED) || mode != floor(mode))
    return 0;
  const unsigned m = (unsigned)mode;
  return (m & (m - 1)) == 0 && (m & ok) != 0; /* one state, one of those */
}

/* NULL if every value of s is one f can take, else what is wrong. */
static const char *snap_invalid(const fmu *f, const snapshot *s)
{
  const double *v = s->v + SNAP_HEAD;
  const double t = v[0], t_end = f->cfg.t_end;
  if (!(t >= 0 && t <= t_end * (1 + 1e-12)))
    return "its time is not one of the run";
  for (size_t k = 1; k < s->size - SNAP_HEAD - 1; ++k)
    if (!isfinite(v[k]))
      return "a value is not finite";
  return snap_mode_valid(f, s->v[s->size - 1]) ? NULL : "its state machine's state is none";
}

fmi3Status fmi3SetFMUState(fmi3Instance instance, fmi3FMUState FMUState)
{
  fmu *f = instance;
  if (!allowed(f, "fmi3SetFMUState",
               ST_INIT | ST_EVENT | ST_CONTINUOUS | ST_STEP | ST_TERMINATED | ST_INSTANTIATED |
                   ST_FAILED))
    return fmi3Error;
  const snapshot *s = FMUState;
  if (!s || !snap_fits(f, s))
    return refuse(f, "fmi3SetFMUState: not a state of this FMU");
  const char *why = snap_invalid(f, s);
  if (why)
    return refuse(f, "fmi3SetFMUState: not a state of this FMU: %s", why);
  const double *v = s->v + SNAP_HEAD;
  const double t = v[0];
  const double *x = v + 1;
  const double *u = x + f->n, *z0 = u + f->ni, *param = z0 + f->ni, *held = param + f->np;
  fb_err err;
  fb_err_clear(&err);
  /* Other parameters: the vehicle they make, built first, from the start
   * (the state is set below): a state refused changes nothing. */
  fb_vehicle_stepper *st = NULL;
  if (f->np && memcmp(param, f->param_built, f->np * sizeof *param) != 0 &&
      new_stepper(f, param, &st, &err))
    return refuse(f, "fmi3SetFMUState: its parameters make no vehicle: %s", err.msg);
  if (st && fb_vehicle_stepper_nstates(st) != f->n) {
    fb_vehicle_stepper_free(&st);
    return refuse(f, "fmi3SetFMUState: its parameters make a vehicle with other states");
  }
  if (st) {
    fb_vehicle_stepper_free(&f->st);
    f->st = st;
    memcpy(f->param_built, param, f->np * sizeof *param);
    if (collect_breakpoints(f, &err))
      return fail(f, "fmi3SetFMUState", &err);
  }
  memcpy(f->u, u, f->ni * sizeof *u);
  memcpy(f->z0, z0, f->ni * sizeof *z0);
  memcpy(f->param, param, f->np * sizeof *param);
  fb_vehicle_stepper_hold_inputs(f->st, held);
  if (f->kind == IF_CO_SIMULATION && fb_vehicle_stepper_set_state(f->st, t, x, &err))
    return fail(f, "fmi3SetFMUState", &err);
  f->time = t;
  if (f->kind == IF_MODEL_EXCHANGE) {
    memcpy(f->p, x, f->n * sizeof *x);
    me_state(f);
    int changed = 0;
    fb_bd *bd = fb_vehicle_stepper_diagram(f->st);
    if (fb_bd_sync_modes(bd, t, f->x, &changed) != 0) {
      fb_err_set(&err, FB_ESOLVER, "choosing modes: %s", fb_bd_last_error(bd));
      return fail(f, "fmi3SetFMUState", &err);
    }
    /* The guards' signs there: an event is a change from them. */
    if (me_guards(f, f->g_last, &err))
      return fail(f, "fmi3SetFMUState", &err);
  }
  f->state = (fmu_state)(unsigned)s->v[s->size - 1];
  return fmi3OK;
}

/* cppcheck-suppress constParameter ; the standard's signature (fmi3FreeFMUStateTYPE) */
fmi3Status fmi3FreeFMUState(fmi3Instance instance, fmi3FMUState *FMUState)
{
  if (!instance)
    return fmi3Error;
  if (FMUState) {
    free(*FMUState);
    *FMUState = NULL;
  }
  return fmi3OK;
}

fmi3Status fmi3SerializedFMUStateSize(fmi3Instance instance, fmi3FMUState FMUState,
                                      size_t *size)
{
  fmu *f = instance;
  if (!f)
    return fmi3Error;
  const snapshot *s = FMUState;
  if (!s || !size || !snap_fits(f, s))
    return refuse(f, "fmi3SerializedFMUStateSize: not a state of this FMU");
  *size = s->size * sizeof(double);
  return fmi3OK;
}

fmi3Status fmi3SerializeFMUState(fmi3Instance instance, fmi3FMUState FMUState,
                                 fmi3Byte serializedState[], size_t size)
{
  fmu *f = instance;
  if (!f)
    return fmi3Error;
  const snapshot *s = FMUState;
  if (!s || !snap_fits(f, s) || size != s->size * sizeof(double) || !serializedState)
    return refuse(f, "fmi3SerializeFMUState: not a state of this FMU, or %zu bytes for %zu",
                  size, s ? s->size * sizeof(double) : 0);
  memcpy(serializedState, s->v, size);
  return fmi3OK;
}

fmi3Status fmi3DeserializeFMUState(fmi3Instance instance, const fmi3Byte serializedState[],
                                   size_t size, fmi3FMUState *FMUState)
{
  fmu *f = instance;
  if (!f)
    return fmi3Error;
  const size_t nd = snap_doubles(f);
  if (!serializedState || !FMUState || size != nd * sizeof(double))
    return refuse(f, "fmi3DeserializeFMUState: %zu bytes, a state of this FMU has %zu", size,
                  nd * sizeof(double));
  snapshot *s = malloc(sizeof *s + size);
  if (!s)
    return refuse(f, "fmi3DeserializeFMUState: out of memory");
  s->size = nd;
  memcpy(s->v, serializedState, size);
  if (!snap_fits(f, s)) {
    free(s);
    return refuse(f, "fmi3DeserializeFMUState: the bytes are not a state of this FMU");
  }
  free(*FMUState);
  *FMUState = s;
  return fmi3OK;
}

fmi3Status fmi3GetDirectionalDerivative(fmi3Instance instance,
                                        const fmi3ValueReference unknowns[], size_t nUnknowns,
                                        const fmi3ValueReference knowns[], size_t nKnowns,
                                        const fmi3Float64 seed[], size_t nSeed,
                                        fmi3Float64 sensitivity[], size_t nSensitivity)
{
  (void)unknowns;
  (void)nUnknowns;
  (void)knowns;
  (void)nKnowns;
  (void)seed;
  (void)nSeed;
  (void)sensitivity;
  (void)nSensitivity;
  return unsupported(instance, "fmi3GetDirectionalDerivative",
                     "providesDirectionalDerivatives is false");
}

fmi3Status fmi3GetAdjointDerivative(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                    size_t nUnknowns, const fmi3ValueReference knowns[],
                                    size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                    fmi3Float64 sensitivity[], size_t nSensitivity)
{
  (void)unknowns;
  (void)nUnknowns;
  (void)knowns;
  (void)nKnowns;
  (void)seed;
  (void)nSeed;
  (void)sensitivity;
  (void)nSensitivity;
  return unsupported(instance, "fmi3GetAdjointDerivative",
                     "providesAdjointDerivatives is false");
}

fmi3Status fmi3EnterConfigurationMode(fmi3Instance instance)
{
  return unsupported(instance, "fmi3EnterConfigurationMode",
                     "the FMU has no structural parameters");
}

fmi3Status fmi3ExitConfigurationMode(fmi3Instance instance)
{
  return unsupported(instance, "fmi3ExitConfigurationMode",
                     "the FMU has no structural parameters");
}

fmi3Status fmi3GetIntervalDecimal(fmi3Instance instance,
                                  const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, fmi3Float64 intervals[],
                                  fmi3IntervalQualifier qualifiers[])
{
  (void)valueReferences;
  (void)nValueReferences;
  (void)intervals;
  (void)qualifiers;
  return unsupported(instance, "fmi3GetIntervalDecimal", "the FMU has no clocks");
}

fmi3Status fmi3GetIntervalFraction(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, fmi3UInt64 counters[],
                                   fmi3UInt64 resolutions[], fmi3IntervalQualifier qualifiers[])
{
  (void)valueReferences;
  (void)nValueReferences;
  (void)counters;
  (void)resolutions;
  (void)qualifiers;
  return unsupported(instance, "fmi3GetIntervalFraction", "the FMU has no clocks");
}

fmi3Status fmi3GetShiftDecimal(fmi3Instance instance,
                               const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, fmi3Float64 shifts[])
{
  (void)valueReferences;
  (void)nValueReferences;
  (void)shifts;
  return unsupported(instance, "fmi3GetShiftDecimal", "the FMU has no clocks");
}

fmi3Status fmi3GetShiftFraction(fmi3Instance instance,
                                const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, fmi3UInt64 counters[],
                                fmi3UInt64 resolutions[])
{
  (void)valueReferences;
  (void)nValueReferences;
  (void)counters;
  (void)resolutions;
  return unsupported(instance, "fmi3GetShiftFraction", "the FMU has no clocks");
}

fmi3Status fmi3SetIntervalDecimal(fmi3Instance instance,
                                  const fmi3ValueReference valueReferences[],
                                  size_t nValueReferences, const fmi3Float64 intervals[])
{
  (void)valueReferences;
  (void)nValueReferences;
  (void)intervals;
  return unsupported(instance, "fmi3SetIntervalDecimal", "the FMU has no clocks");
}

fmi3Status fmi3SetIntervalFraction(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, const fmi3UInt64 counters[],
                                   const fmi3UInt64 resolutions[])
{
  (void)valueReferences;
  (void)nValueReferences;
  (void)counters;
  (void)resolutions;
  return unsupported(instance, "fmi3SetIntervalFraction", "the FMU has no clocks");
}

fmi3Status fmi3SetShiftDecimal(fmi3Instance instance,
                               const fmi3ValueReference valueReferences[],
                               size_t nValueReferences, const fmi3Float64 shifts[])
{
  (void)valueReferences;
  (void)nValueReferences;
  (void)shifts;
  return unsupported(instance, "fmi3SetShiftDecimal", "the FMU has no clocks");
}

fmi3Status fmi3SetShiftFraction(fmi3Instance instance,
                                const fmi3ValueReference valueReferences[],
                                size_t nValueReferences, const fmi3UInt64 counters[],
                                const fmi3UInt64 resolutions[])
{
  (void)valueReferences;
  (void)nValueReferences;
  (void)counters;
  (void)resolutions;
  return unsupported(instance, "fmi3SetShiftFraction", "the FMU has no clocks");
}

fmi3Status fmi3EvaluateDiscreteStates(fmi3Instance instance)
{
  return unsupported(instance, "fmi3EvaluateDiscreteStates", "the FMU has no clocks");
}

/* The first road breakpoint after t, if any. */
static int next_breakpoint(const fmu *f, double t, double *next)
{
  for (size_t k = 0; k < f->nbps; ++k)
    if (f->bps[k] > t * (1 + 1e-14) + 1e-14) {
      *next = f->bps[k];
      return 1;
    }
  return 0;
}

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance,
                                    fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation,
                                    fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged,
                                    fmi3Boolean *nextEventTimeDefined,
                                    fmi3Float64 *nextEventTime)
{
  fmu *f = instance;
  if (!f || !is_me(f, "fmi3UpdateDiscreteStates") ||
      !allowed(f, "fmi3UpdateDiscreteStates", ST_EVENT))
    return fmi3Error;
  fb_err err;
  fb_err_clear(&err);
  /* A guard whose sign differs from the last accepted step's has
   * crossed: its law switches as it would inside CVODE's run. */
  if (me_guards(f, f->g, &err))
    return fail(f, "fmi3UpdateDiscreteStates", &err);
  fb_bd *bd = fb_vehicle_stepper_diagram(f->st);
  for (size_t k = 0; k < f->model->nindicators; ++k)
    f->crossed[k] = (f->g_last[k] <= 0) != (f->g[k] <= 0) ? (f->g[k] > 0 ? 1 : -1) : 0;
  int changed = 0;
  if (fb_bd_switch_modes(bd, f->time, f->x, f->crossed, &changed) != 0) {
    fb_err_set(&err, FB_ESOLVER, "switching modes: %s", fb_bd_last_error(bd));
    return fail(f, "fmi3UpdateDiscreteStates", &err);
  }
  /* At a road kink the input's jump may move a guard across zero with no
   * crossing to see: the modes are chosen afresh there, as a CVODE run
   * does at a stop time (fb_bd_sync_modes). */
  int synced = 0;
  for (size_t k = 0; !changed && k < f->nbps; ++k)
    if (fabs(f->bps[k] - f->time) <= 1e-9 * fmax(1.0, f->time) &&
        fb_bd_sync_modes(bd, f->time, f->x, &synced) != 0) {
      fb_err_set(&err, FB_ESOLVER, "choosing modes: %s", fb_bd_last_error(bd));
      return fail(f, "fmi3UpdateDiscreteStates", &err);
    }
  changed |= synced;
  if (changed && me_guards(f, f->g, &err))
    return fail(f, "fmi3UpdateDiscreteStates", &err);
  memcpy(f->g_last, f->g, f->model->nindicators * sizeof *f->g);
  double next = 0.0;
  const int defined = next_breakpoint(f, f->time, &next);
  if (discreteStatesNeedUpdate)
    *discreteStatesNeedUpdate = false;
  if (terminateSimulation)
    *terminateSimulation = false;
  if (nominalsOfContinuousStatesChanged)
    *nominalsOfContinuousStatesChanged = false;
  if (valuesOfContinuousStatesChanged)
    *valuesOfContinuousStatesChanged = false;
  if (nextEventTimeDefined)
    *nextEventTimeDefined = defined;
  if (nextEventTime)
    *nextEventTime = defined ? next : 0.0;
  say(f, fmi3OK, "logEvents", "event at t = %.9g s: %s", f->time,
      changed ? "a law switched" : "no law switched");
  return fmi3OK;
}

/* ---- Model exchange (FMI 3.0, 3.2). */

fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance)
{
  fmu *f = instance;
  if (!f || !is_me(f, "fmi3EnterContinuousTimeMode") ||
      !allowed(f, "fmi3EnterContinuousTimeMode", ST_EVENT))
    return fmi3Error;
  fb_err err;
  fb_err_clear(&err);
  if (me_guards(f, f->g_last, &err))
    return fail(f, "fmi3EnterContinuousTimeMode", &err);
  f->state = ST_CONTINUOUS;
  return fmi3OK;
}

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance,
                                       fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode,
                                       fmi3Boolean *terminateSimulation)
{
  fmu *f = instance;
  (void)noSetFMUStatePriorToCurrentPoint;
  if (!f || !is_me(f, "fmi3CompletedIntegratorStep") ||
      !allowed(f, "fmi3CompletedIntegratorStep", ST_CONTINUOUS))
    return fmi3Error;
  if (enterEventMode)
    *enterEventMode = false;
  if (terminateSimulation)
    *terminateSimulation = false;
  return fmi3OK;
}

fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time)
{
  fmu *f = instance;
  if (!f || !is_me(f, "fmi3SetTime") || !allowed(f, "fmi3SetTime", ST_EVENT | ST_CONTINUOUS))
    return fmi3Error;
  if (!isfinite(time) || time < 0 || time > last_time(f) * (1 + 1e-12))
    return refuse(f, "fmi3SetTime: t = %g s is not a time of this run (0 to %g s%s)", time,
                  last_time(f), f->stop_defined ? ", the stopTime given" : "");
  f->time = time;
  return fmi3OK;
}

fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
  fmu *f = instance;
  if (!f || !is_me(f, "fmi3SetContinuousStates") ||
      !allowed(f, "fmi3SetContinuousStates", ST_CONTINUOUS))
    return fmi3Error;
  if (nContinuousStates != f->n)
    return refuse(f, "fmi3SetContinuousStates: %zu states given, the model has %zu",
                  nContinuousStates, f->n);
  for (size_t i = 0; i < f->n; ++i)
    if (!isfinite(continuousStates[i]))
      return refuse(f, "fmi3SetContinuousStates: %s = %g is not finite",
                    f->model->var[f->model->first_state + i].name, continuousStates[i]);
  memcpy(f->p, continuousStates, f->n * sizeof *f->p);
  return fmi3OK;
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 derivatives[],
                                             size_t nContinuousStates)
{
  fmu *f = instance;
  if (!f || !is_me(f, "fmi3GetContinuousStateDerivatives") ||
      !allowed(f, "fmi3GetContinuousStateDerivatives",
               ST_INIT | ST_EVENT | ST_CONTINUOUS | ST_TERMINATED))
    return fmi3Error;
  if (nContinuousStates != f->n)
    return refuse(f, "fmi3GetContinuousStateDerivatives: room for %zu, the model has %zu",
                  nContinuousStates, f->n);
  fb_err err;
  fb_err_clear(&err);
  if (me_derivatives(f, &err))
    return fail(f, "fmi3GetContinuousStateDerivatives", &err);
  memcpy(derivatives, f->xdot, f->n * sizeof *f->xdot);
  return fmi3OK;
}

fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 eventIndicators[],
                                  size_t nEventIndicators)
{
  fmu *f = instance;
  if (!f || !is_me(f, "fmi3GetEventIndicators") ||
      !allowed(f, "fmi3GetEventIndicators", ST_INIT | ST_EVENT | ST_CONTINUOUS | ST_TERMINATED))
    return fmi3Error;
  if (nEventIndicators != f->model->nindicators)
    return refuse(f, "fmi3GetEventIndicators: room for %zu, the model has %zu",
                  nEventIndicators, f->model->nindicators);
  fb_err err;
  fb_err_clear(&err);
  if (me_guards(f, f->g, &err))
    return fail(f, "fmi3GetEventIndicators", &err);
  memcpy(eventIndicators, f->g, nEventIndicators * sizeof *f->g);
  return fmi3OK;
}

fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 continuousStates[],
                                   size_t nContinuousStates)
{
  fmu *f = instance;
  if (!f || !is_me(f, "fmi3GetContinuousStates") ||
      !allowed(f, "fmi3GetContinuousStates",
               ST_INIT | ST_EVENT | ST_CONTINUOUS | ST_TERMINATED))
    return fmi3Error;
  if (nContinuousStates != f->n)
    return refuse(f, "fmi3GetContinuousStates: room for %zu, the model has %zu",
                  nContinuousStates, f->n);
  memcpy(continuousStates, f->p, f->n * sizeof *f->p);
  return fmi3OK;
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 nominals[],
                                             size_t nContinuousStates)
{
  fmu *f = instance;
  if (!f || !is_me(f, "fmi3GetNominalsOfContinuousStates") ||
      !allowed(f, "fmi3GetNominalsOfContinuousStates",
               ST_INSTANTIATED | ST_EVENT | ST_CONTINUOUS | ST_TERMINATED))
    return fmi3Error;
  if (nContinuousStates != f->n)
    return refuse(f, "fmi3GetNominalsOfContinuousStates: room for %zu, the model has %zu",
                  nContinuousStates, f->n);
  for (size_t i = 0; i < f->n; ++i)
    nominals[i] = 1.0;
  return fmi3OK;
}

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t *nEventIndicators)
{
  fmu *f = instance;
  if (!f || !nEventIndicators)
    return fmi3Error;
  *nEventIndicators = f->model->nindicators;
  return fmi3OK;
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t *nContinuousStates)
{
  fmu *f = instance;
  if (!f || !nContinuousStates)
    return fmi3Error;
  *nContinuousStates = f->n;
  return fmi3OK;
}

/* ---- Co-simulation (FMI 3.0, 4.2). */

fmi3Status fmi3EnterStepMode(fmi3Instance instance)
{
  fmu *f = instance;
  if (!f || !is_cs(f, "fmi3EnterStepMode"))
    return fmi3Error;
  return refuse(f, "fmi3EnterStepMode: the FMU has no co-simulation event mode; "
                   "fmi3ExitInitializationMode enters Step Mode");
}

fmi3Status fmi3GetOutputDerivatives(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Int32 orders[],
                                    fmi3Float64 values[], size_t nValues)
{
  (void)valueReferences;
  (void)nValueReferences;
  (void)orders;
  (void)values;
  (void)nValues;
  return unsupported(instance, "fmi3GetOutputDerivatives", "maxOutputDerivativeOrder is 0");
}

fmi3Status fmi3DoStep(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                      fmi3Float64 communicationStepSize,
                      fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                      fmi3Boolean *eventHandlingNeeded, fmi3Boolean *terminateSimulation,
                      fmi3Boolean *earlyReturn, fmi3Float64 *lastSuccessfulTime)
{
  fmu *f = instance;
  (void)noSetFMUStatePriorToCurrentPoint;
  if (!f || !is_cs(f, "fmi3DoStep") || !allowed(f, "fmi3DoStep", ST_STEP))
    return fmi3Error;
  const double now = fb_vehicle_stepper_time(f->st);
  const double t_end = fb_vehicle_stepper_scenario(f->st)->t_end;
  const double tol = 1e-9 * fmax(1.0, fabs(now));
  if (fabs(currentCommunicationPoint - now) > tol)
    return refuse(f,
                  "fmi3DoStep: currentCommunicationPoint %.17g s is not the FMU's time %.17g s",
                  currentCommunicationPoint, now);
  if (!(communicationStepSize > 0) || !isfinite(communicationStepSize))
    return refuse(f, "fmi3DoStep: communicationStepSize %g s must be > 0",
                  communicationStepSize);
  const double target = now + communicationStepSize;
  if (target > t_end * (1 + 1e-12) + tol)
    return refuse(f,
                  "fmi3DoStep: a step to %.9g s passes the FMU's horizon %.9g s "
                  "(flexbond fmu --t-end sets it)",
                  target, t_end);
  if (f->stop_defined && target > f->stop_time * (1 + 1e-12) + tol)
    return refuse(f,
                  "fmi3DoStep: a step to %.9g s passes the stopTime %.9g s given at "
                  "fmi3EnterInitializationMode",
                  target, f->stop_time);
  fb_err err;
  fb_err_clear(&err);
  int rc = cs_apply(f, &err);
  if (!rc)
    rc = fb_vehicle_stepper_advance(f->st, fmin(target, t_end), &err);
  if (eventHandlingNeeded)
    *eventHandlingNeeded = false;
  if (terminateSimulation)
    *terminateSimulation = false;
  if (earlyReturn)
    *earlyReturn = false;
  if (lastSuccessfulTime)
    *lastSuccessfulTime = fb_vehicle_stepper_time(f->st);
  if (rc)
    return fail(f, "fmi3DoStep", &err);
  return fmi3OK;
}

/* ---- Scheduled execution: not provided. */

fmi3Status fmi3ActivateModelPartition(fmi3Instance instance, fmi3ValueReference clockReference,
                                      fmi3Float64 activationTime)
{
  (void)clockReference;
  (void)activationTime;
  return unsupported(instance, "fmi3ActivateModelPartition",
                     "the FMU has no scheduled execution interface");
}
