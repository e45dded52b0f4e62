/* SPDX-License-Identifier: BSD-3-Clause */
/* fmu_import: a small FMI 3.0 importer of our own, to test the FMUs that
 * `flexbond fmu` writes from the outside, as a simulation tool would use
 * them: it reads the unzipped FMU's modelDescription.xml with libxml2,
 * dlopens the binary and resolves the 75 functions by name. It is not
 * linked with flexbond, so it sees only what the FMU exports.
 *
 * usage: fmu_import [--h H] cs DIR STEP T_END OUT.csv [[@]NAME=VALUE ...]
 *        fmu_import [--h H] me DIR STEP T_END OUT.csv [[@]NAME=VALUE ...]
 *        fmu_import [--h H] checks DIR
 *
 * cs: co-simulation with a fixed communication step STEP (s) to T_END.
 * me: model exchange integrated here with classical RK4 at the fixed
 *     internal step H (--h, default 1e-4 s), time events from
 *     fmi3UpdateDiscreteStates' nextEventTime landed on exactly, state
 *     events from a sign change of an event indicator across a step.
 * Both write OUT.csv: "t,<outputs in value-reference order>", one row at
 * t = 0 (after fmi3ExitInitializationMode) and one every STEP. NAME=VALUE
 * sets a parameter or input by name before initialisation, @NAME=VALUE
 * an input after it (before the first step).
 * checks: the protocol checks (run_checks below), one line each, OK or
 * FAIL; exit status 1 if any fails.
 *
 * Exit status: 0 done (all checks OK), 1 a check or a call failed, 2 bad
 * usage or an FMU that cannot be loaded. Every message the FMU logs goes
 * to stderr as "[STATUS category] message". */
#define _XOPEN_SOURCE 700 /* realpath */

#include <dlfcn.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmu/fmi3.h"

/* ---- Logging. The one piece of mutable global state: how many fmi3Error
 * messages the FMU logged, so that a check can see that a refused call
 * said why. The callback has no other way to report to the check than
 * its instance environment, and the instantiation-token check has no
 * instance to ask; a counter shared by all instances is what the checks
 * need (they run one after the other, single-threaded). */
static long log_errors;

static const char *status_name(fmi3Status s)
{
  switch (s) {
  case fmi3OK: return "OK";
  case fmi3Warning: return "Warning";
  case fmi3Discard: return "Discard";
  case fmi3Error: return "Error";
  case fmi3Fatal: return "Fatal";
  }
  return "?";
}

static void log_message(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category,
                        fmi3String message)
{
  (void)env;
  if (status == fmi3Error)
    ++log_errors;
  fprintf(stderr, "[%s %s] %s\n", status_name(status), category ? category : "-",
          message ? message : "");
}

/* ---- The model description. */

typedef enum causality { C_OTHER, C_INPUT, C_OUTPUT, C_PARAMETER } causality;

typedef struct var {
  char *name;
  fmi3ValueReference vr;
  causality causality;
} var;

typedef struct fmu {
  char *dir;
  char *resources; /* absolute, with a trailing '/' */
  char *id;        /* modelIdentifier */
  char *token;
  double stop_time, step_size; /* DefaultExperiment; 0 if absent */
  var *vars;
  size_t nvars;
  fmi3ValueReference *out; /* the outputs' value references, ascending */
  size_t nout;
  size_t ncsv; /* outputs written to the CSV: the first ncsv (all by default) */
  size_t nstates, nindicators;
  void *dl;
#define FB_MEMBER(name) name##TYPE *name;
  FB_FMI3_FOR_EACH_FUNCTION(FB_MEMBER)
#undef FB_MEMBER
} fmu;

static char *attr_dup(xmlNode *n, const char *name)
{
  xmlChar *v = xmlGetProp(n, (const xmlChar *)name);
  if (!v)
    return NULL;
  char *s = strdup((const char *)v);
  xmlFree(v);
  return s;
}

static double attr_double(xmlNode *n, const char *name, double fallback)
{
  char *s = attr_dup(n, name);
  double v = fallback;
  if (s) {
    char *end = NULL;
    v = strtod(s, &end);
    if (end == s || *end)
      v = fallback;
  }
  free(s);
  return v;
}

static int is_element(xmlNode *n, const char *name)
{
  return n->type == XML_ELEMENT_NODE && !strcmp((const char *)n->name, name);
}

static int cmp_vr(const void *a, const void *b)
{
  const fmi3ValueReference x = *(const fmi3ValueReference *)a;
  const fmi3ValueReference y = *(const fmi3ValueReference *)b;
  return (x > y) - (x < y);
}

static int parse_variables(fmu *u, xmlNode *mv)
{
  size_t cap = 0;
  for (xmlNode *n = mv->children; n; n = n->next)
    cap += n->type == XML_ELEMENT_NODE;
  u->vars = calloc(cap + 1, sizeof *u->vars);
  u->out = calloc(cap + 1, sizeof *u->out);
  if (!u->vars || !u->out)
    return -1;
  for (xmlNode *n = mv->children; n; n = n->next) {
    if (!is_element(n, "Float64"))
      continue; /* the FMU declares Float64 variables only; others are ignored */
    var *v = &u->vars[u->nvars];
    v->name = attr_dup(n, "name");
    const double vr = attr_double(n, "valueReference", -1);
    char *c = attr_dup(n, "causality");
    if (!v->name || !(vr >= 0 && vr <= UINT32_MAX)) {
      free(c);
      fprintf(stderr, "fmu_import: a Float64 without a name or valueReference\n");
      return -1;
    }
    v->vr = (fmi3ValueReference)vr;
    v->causality = !c                        ? C_OTHER
                   : !strcmp(c, "input")     ? C_INPUT
                   : !strcmp(c, "output")    ? C_OUTPUT
                   : !strcmp(c, "parameter") ? C_PARAMETER
                                             : C_OTHER;
    free(c);
    if (v->causality == C_OUTPUT)
      u->out[u->nout++] = v->vr;
    ++u->nvars;
  }
  qsort(u->out, u->nout, sizeof *u->out, cmp_vr);
  return 0;
}

static int parse_description(fmu *u)
{
  char path[PATH_MAX];
  snprintf(path, sizeof path, "%s/modelDescription.xml", u->dir);
  xmlDoc *doc = xmlReadFile(path, NULL, XML_PARSE_NONET);
  if (!doc) {
    fprintf(stderr, "fmu_import: %s: not readable XML\n", path);
    return -1;
  }
  int rc = 0;
  xmlNode *root = xmlDocGetRootElement(doc);
  if (!root || !is_element(root, "fmiModelDescription")) {
    fprintf(stderr, "fmu_import: %s: no fmiModelDescription\n", path);
    rc = -1;
  }
  if (!rc)
    u->token = attr_dup(root, "instantiationToken");
  for (xmlNode *n = rc ? NULL : root->children; n && !rc; n = n->next) {
    if ((is_element(n, "CoSimulation") || is_element(n, "ModelExchange")) && !u->id)
      u->id = attr_dup(n, "modelIdentifier");
    else if (is_element(n, "DefaultExperiment")) {
      u->stop_time = attr_double(n, "stopTime", 0);
      u->step_size = attr_double(n, "stepSize", 0);
    } else if (is_element(n, "ModelVariables"))
      rc = parse_variables(u, n);
    else if (is_element(n, "ModelStructure"))
      for (xmlNode *s = n->children; s; s = s->next) {
        u->nindicators += is_element(s, "EventIndicator");
        u->nstates += is_element(s, "ContinuousStateDerivative");
      }
  }
  xmlFreeDoc(doc);
  if (!rc && (!u->id || !u->token)) {
    fprintf(stderr, "fmu_import: %s: no modelIdentifier or instantiationToken\n", path);
    rc = -1;
  }
  return rc;
}

/* Resolves every one of the 75 functions: an FMU missing one is not an
 * FMI 3.0 FMU (every function is exported, supported or not). */
static int load_binary(fmu *u)
{
  char path[PATH_MAX];
  snprintf(path, sizeof path, "%s/binaries/x86_64-linux/%s.so", u->dir, u->id);
  /* RTLD_NODELETE: dlclose leaves the binary and its libraries mapped.
   * The FMU bundles libgomp (OpenBLAS's), whose initialiser keeps 8
   * bytes for the process's life; unmapped, nothing would point at
   * them and a leak checker (valgrind, LeakSanitizer) would call them
   * lost. FMU importers keep such libraries loaded for the same reason. */
  u->dl = dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
  if (!u->dl) {
    fprintf(stderr, "fmu_import: dlopen %s: %s\n", path, dlerror());
    return -1;
  }
  int missing = 0;
  void *sym = NULL;
  /* memcpy: ISO C has no conversion of an object pointer to a function
   * pointer; POSIX guarantees the representation is the same. */
#define FB_RESOLVE(name)                                                                       \
  sym = dlsym(u->dl, #name);                                                                   \
  if (!sym) {                                                                                  \
    fprintf(stderr, "fmu_import: %s: %s is missing\n", path, #name);                           \
    ++missing;                                                                                 \
  }                                                                                            \
  memcpy(&u->name, &sym, sizeof u->name);
  FB_FMI3_FOR_EACH_FUNCTION(FB_RESOLVE)
#undef FB_RESOLVE
  return missing ? -1 : 0;
}

static void fmu_close(fmu *u)
{
  for (size_t k = 0; k < u->nvars; ++k)
    free(u->vars[k].name);
  free(u->vars);
  free(u->out);
  free(u->id);
  free(u->token);
  free(u->resources);
  free(u->dir);
  if (u->dl && dlclose(u->dl) != 0)
    fprintf(stderr, "fmu_import: dlclose: %s\n", dlerror());
}

static int fmu_open(const char *dir, fmu *u)
{
  memset(u, 0, sizeof *u);
  char abs[PATH_MAX];
  if (!realpath(dir, abs)) {
    fprintf(stderr, "fmu_import: %s: no such folder\n", dir);
    return -1;
  }
  u->dir = strdup(abs);
  u->resources = malloc(strlen(abs) + sizeof "/resources/");
  if (!u->dir || !u->resources)
    return -1;
  sprintf(u->resources, "%s/resources/", abs);
  if (parse_description(u) || load_binary(u))
    return -1;
  return 0;
}

static const var *find_var(const fmu *u, const char *name)
{
  for (size_t k = 0; k < u->nvars; ++k)
    if (!strcmp(u->vars[k].name, name))
      return &u->vars[k];
  return NULL;
}

/* ---- Instances. */

static fmi3Instance new_cs(const fmu *u, const char *name)
{
  return u->fmi3InstantiateCoSimulation(name, u->token, u->resources, fmi3False, fmi3False,
                                        fmi3False, fmi3False, NULL, 0, NULL, log_message, NULL);
}

static fmi3Instance new_me(const fmu *u, const char *name)
{
  return u->fmi3InstantiateModelExchange(name, u->token, u->resources, fmi3False, fmi3False,
                                         NULL, log_message);
}

/* Sets the NAME=VALUE assignments (parameters or inputs) of sets; with
 * after, those written @NAME=VALUE instead, which are set after
 * initialisation (a road height's step: the heights at the end of
 * initialisation are the road's zero). */
static int apply_sets(const fmu *u, fmi3Instance inst, char **sets, size_t nsets, int after)
{
  for (size_t k = 0; k < nsets; ++k) {
    if ((sets[k][0] == '@') != after)
      continue;
    const char *text = sets[k] + after;
    const char *eq = strchr(text, '=');
    char name[512];
    if (!eq || (size_t)(eq - text) >= sizeof name) {
      fprintf(stderr, "fmu_import: %s: not NAME=VALUE\n", sets[k]);
      return -1;
    }
    memcpy(name, text, (size_t)(eq - text));
    name[eq - text] = '\0';
    char *end = NULL;
    const double value = strtod(eq + 1, &end);
    const var *v = find_var(u, name);
    if (end == eq + 1 || *end || !v ||
        (v->causality != C_PARAMETER && v->causality != C_INPUT)) {
      fprintf(stderr, "fmu_import: %s: not a parameter or input with a number\n", sets[k]);
      return -1;
    }
    if (u->fmi3SetFloat64(inst, &v->vr, 1, &value, 1) != fmi3OK)
      return -1;
  }
  return 0;
}

static int initialise(const fmu *u, fmi3Instance inst, char **sets, size_t nsets)
{
  if (apply_sets(u, inst, sets, nsets, 0))
    return -1;
  if (u->fmi3EnterInitializationMode(inst, fmi3False, 0.0, 0.0, fmi3False, 0.0) != fmi3OK)
    return -1;
  if (u->fmi3ExitInitializationMode(inst) != fmi3OK)
    return -1;
  return apply_sets(u, inst, sets, nsets, 1);
}

static int get_outputs(const fmu *u, fmi3Instance inst, double *y)
{
  return u->fmi3GetFloat64(inst, u->out, u->nout, y, u->nout) == fmi3OK ? 0 : -1;
}

/* A row with the digits flexbond run's CSV has (10 significant: the
 * comparisons allow far more than their rounding, and the benchmark
 * (bench/fmu.sh) then writes the same text as the run it is set
 * against). */
static void write_row(FILE *fp, double t, const double *y, size_t n)
{
  fprintf(fp, "%.10g", t);
  for (size_t k = 0; k < n; ++k)
    fprintf(fp, ",%.10g", y[k]);
  fputc('\n', fp);
}

/* Co-simulation steps i0 .. i0+n-1 of size step: communication points
 * i * step computed from the index (not summed), so that two runs of the
 * same steps call the FMU with the same doubles. The outputs after each
 * step into rec (n rows of nout) and/or fp. */
static int cs_steps(const fmu *u, fmi3Instance inst, long i0, long n, double step, double *rec,
                    FILE *fp)
{
  double *y = calloc(u->nout + 1, sizeof *y);
  int rc = y ? 0 : -1;
  for (long i = i0; !rc && i < i0 + n; ++i) {
    const double t = (double)i * step, t_next = (double)(i + 1) * step;
    fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
    double last = 0.0;
    if (u->fmi3DoStep(inst, t, t_next - t, fmi3True, &event, &terminate, &early, &last) !=
            fmi3OK ||
        get_outputs(u, inst, y)) {
      fprintf(stderr, "fmu_import: co-simulation step at t = %.9g s failed\n", t);
      rc = -1;
      break;
    }
    if (rec)
      memcpy(rec + (size_t)(i - i0) * u->nout, y, u->nout * sizeof *y);
    if (fp)
      write_row(fp, t_next, y, u->ncsv);
  }
  free(y);
  return rc;
}

/* ---- Model exchange: the importer's integrator.
 *
 * Classical RK4 at a fixed step h. A time event (nextEventTime: the
 * road's kinks) ends a step exactly there. A state event is detected by
 * a sign change of an event indicator between the start and the end of
 * a step, and located by bisection of that step: RK4 from the step's
 * start over half the length, and so on, to 1e-10 s (a tire landing on
 * its damper makes the force jump by c v, which decays in m / c =
 * 1.25 ms: a switch h = 0.1 ms late would be seen as 7 % of that force's
 * range in the next sample). fmi3EnterEventMode just after the root. */

typedef struct me_sim {
  size_t n, ng;
  double t;
  long row; /* the next row's index: its time is row * step */
  int te_defined;
  double te; /* the next time event */
  double *x, *xs, *k1, *k2, *k3, *k4, *g, *g_prev, *x0;
  long events;
} me_sim;

static void me_free(me_sim *s)
{
  free(s->x);
  free(s->xs);
  free(s->k1);
  free(s->k2);
  free(s->k3);
  free(s->k4);
  free(s->g);
  free(s->g_prev);
  free(s->x0);
}

static int me_alloc(const fmu *u, me_sim *s)
{
  memset(s, 0, sizeof *s);
  s->n = u->nstates;
  s->ng = u->nindicators;
  double **a[] = {&s->x, &s->xs, &s->k1, &s->k2, &s->k3, &s->k4, &s->x0};
  for (size_t k = 0; k < sizeof a / sizeof *a; ++k)
    if (!(*a[k] = calloc(s->n + 1, sizeof(double))))
      return -1;
  s->g = calloc(s->ng + 1, sizeof *s->g);
  s->g_prev = calloc(s->ng + 1, sizeof *s->g_prev);
  return s->g && s->g_prev ? 0 : -1;
}

/* In Event Mode: the event iteration, then Continuous-Time Mode with
 * the states and indicators read back. */
static int me_event(const fmu *u, fmi3Instance inst, me_sim *s)
{
  fmi3Boolean need = fmi3True, terminate = fmi3False, nominals = fmi3False, values = fmi3False,
              defined = fmi3False;
  double next = 0.0;
  for (int it = 0; need; ++it) {
    if (it == 100 || u->fmi3UpdateDiscreteStates(inst, &need, &terminate, &nominals, &values,
                                                 &defined, &next) != fmi3OK) {
      fprintf(stderr, "fmu_import: the event iteration at t = %.9g s failed\n", s->t);
      return -1;
    }
  }
  s->te_defined = defined;
  s->te = next;
  ++s->events;
  if (u->fmi3EnterContinuousTimeMode(inst) != fmi3OK ||
      u->fmi3GetContinuousStates(inst, s->x, s->n) != fmi3OK ||
      u->fmi3GetEventIndicators(inst, s->g_prev, s->ng) != fmi3OK)
    return -1;
  return 0;
}

static int me_start(const fmu *u, fmi3Instance inst, char **sets, size_t nsets, me_sim *s)
{
  if (initialise(u, inst, sets, nsets))
    return -1;
  s->t = 0.0;
  s->row = 1; /* row 0 is the start's, written by the caller */
  return me_event(u, inst, s);
}

static int me_rhs(const fmu *u, fmi3Instance inst, const me_sim *s, double t, const double *x,
                  double *dx)
{
  if (u->fmi3SetTime(inst, t) != fmi3OK ||
      u->fmi3SetContinuousStates(inst, x, s->n) != fmi3OK ||
      u->fmi3GetContinuousStateDerivatives(inst, dx, s->n) != fmi3OK)
    return -1;
  return 0;
}

static int rk4(const fmu *u, fmi3Instance inst, me_sim *s, double dt)
{
  const size_t n = s->n;
  const double t = s->t;
  if (me_rhs(u, inst, s, t, s->x, s->k1))
    return -1;
  for (size_t i = 0; i < n; ++i)
    s->xs[i] = s->x[i] + 0.5 * dt * s->k1[i];
  if (me_rhs(u, inst, s, t + 0.5 * dt, s->xs, s->k2))
    return -1;
  for (size_t i = 0; i < n; ++i)
    s->xs[i] = s->x[i] + 0.5 * dt * s->k2[i];
  if (me_rhs(u, inst, s, t + 0.5 * dt, s->xs, s->k3))
    return -1;
  for (size_t i = 0; i < n; ++i)
    s->xs[i] = s->x[i] + dt * s->k3[i];
  if (me_rhs(u, inst, s, t + dt, s->xs, s->k4))
    return -1;
  for (size_t i = 0; i < n; ++i)
    s->x[i] += dt / 6.0 * (s->k1[i] + 2.0 * s->k2[i] + 2.0 * s->k3[i] + s->k4[i]);
  s->t = t + dt;
  return 0;
}

/* The indicators at (s->t, s->x) into s->g; 1 if one changed sign from
 * s->g_prev, 0 if none, -1 on failure. */
static int indicators_crossed(const fmu *u, fmi3Instance inst, me_sim *s)
{
  if (u->fmi3SetTime(inst, s->t) != fmi3OK ||
      u->fmi3SetContinuousStates(inst, s->x, s->n) != fmi3OK ||
      u->fmi3GetEventIndicators(inst, s->g, s->ng) != fmi3OK)
    return -1;
  for (size_t k = 0; k < s->ng; ++k)
    if ((s->g_prev[k] <= 0) != (s->g[k] <= 0))
      return 1;
  return 0;
}

/* A sign change in the step from (t0, s->x0) of length dt: s moved to
 * just after its first root, by bisection of the step's length. */
static int locate_root(const fmu *u, fmi3Instance inst, me_sim *s, double t0, double dt)
{
  double lo = 0.0, hi = dt;
  while (hi - lo > 1e-10) {
    const double mid = 0.5 * (lo + hi);
    memcpy(s->x, s->x0, s->n * sizeof *s->x);
    s->t = t0;
    if (rk4(u, inst, s, mid))
      return -1;
    const int crossed = indicators_crossed(u, inst, s);
    if (crossed < 0)
      return -1;
    if (crossed)
      hi = mid;
    else
      lo = mid;
  }
  memcpy(s->x, s->x0, s->n * sizeof *s->x);
  s->t = t0;
  if (rk4(u, inst, s, hi))
    return -1;
  s->t = t0 + hi;
  return indicators_crossed(u, inst, s) < 0 ? -1 : 0;
}

/* Integrates until nrows more rows (every step s) are out, into rec
 * (nrows x nout) and/or fp. Step ends: the next multiple of h, the next
 * row's time, the next time event, whichever comes first, so that rows
 * and events are landed on exactly. */
static int me_rows(const fmu *u, fmi3Instance inst, me_sim *s, double h, double step,
                   long nrows, double *rec, FILE *fp)
{
  double *y = calloc(u->nout + 1, sizeof *y);
  if (!y)
    return -1;
  int rc = 0;
  const long last_row = s->row + nrows;
  while (!rc && s->row < last_row) {
    const double eps = 1e-12 * fmax(1.0, s->t);
    const double t_row = (double)s->row * step;
    double target = (floor(s->t / h + 1e-6) + 1.0) * h;
    if (t_row < target)
      target = t_row;
    int time_event = 0;
    if (s->te_defined && s->te > s->t + eps && s->te <= target + eps) {
      target = s->te;
      time_event = 1;
    }
    if (fabs(target - t_row) <= eps)
      target = t_row;
    const double t0 = s->t;
    memcpy(s->x0, s->x, s->n * sizeof *s->x);
    if (rk4(u, inst, s, target - s->t)) {
      rc = -1;
      break;
    }
    s->t = target;
    const int crossed = s->ng ? indicators_crossed(u, inst, s) : 0;
    if (crossed < 0 || (crossed > 0 && locate_root(u, inst, s, t0, target - t0))) {
      rc = -1;
      break;
    }
    if (crossed > 0)
      time_event = 0; /* the root comes first: the time event is still ahead */
    fmi3Boolean enter = fmi3False, terminate = fmi3False;
    if (u->fmi3SetTime(inst, s->t) != fmi3OK ||
        u->fmi3SetContinuousStates(inst, s->x, s->n) != fmi3OK ||
        u->fmi3GetEventIndicators(inst, s->g, s->ng) != fmi3OK ||
        u->fmi3CompletedIntegratorStep(inst, fmi3True, &enter, &terminate) != fmi3OK) {
      rc = -1;
      break;
    }
    int state_event = 0;
    for (size_t k = 0; k < s->ng; ++k)
      state_event |= (s->g_prev[k] <= 0) != (s->g[k] <= 0);
    if (time_event || state_event || enter) {
      if (u->fmi3EnterEventMode(inst) != fmi3OK || me_event(u, inst, s)) {
        rc = -1;
        break;
      }
    } else {
      memcpy(s->g_prev, s->g, s->ng * sizeof *s->g);
    }
    if (s->t == t_row) {
      if (get_outputs(u, inst, y)) {
        rc = -1;
        break;
      }
      if (rec)
        memcpy(rec + (size_t)(s->row - (last_row - nrows)) * u->nout, y, u->nout * sizeof *y);
      if (fp)
        write_row(fp, s->t, y, u->ncsv);
      ++s->row;
    }
  }
  if (rc)
    fprintf(stderr, "fmu_import: model exchange at t = %.9g s failed\n", s->t);
  free(y);
  return rc;
}

/* ---- cs and me: a run written to a CSV file. */

static int simulate(const fmu *u, int me, double h, double step, double t_end, const char *csv,
                    char **sets, size_t nsets)
{
  FILE *fp = fopen(csv, "w");
  if (!fp) {
    fprintf(stderr, "fmu_import: %s: cannot write\n", csv);
    return 2;
  }
  fputs("t", fp);
  for (size_t k = 0; k < u->ncsv; ++k)
    for (size_t v = 0; v < u->nvars; ++v)
      if (u->vars[v].vr == u->out[k]) {
        fprintf(fp, ",%s", u->vars[v].name);
        break;
      }
  fputc('\n', fp);
  const long nsteps = lround(t_end / step);
  double *y = calloc(u->nout + 1, sizeof *y);
  fmi3Instance inst = me ? new_me(u, "run") : new_cs(u, "run");
  int rc = y && inst ? 0 : 1;
  me_sim s;
  memset(&s, 0, sizeof s);
  if (!rc && me)
    rc = me_alloc(u, &s) || me_start(u, inst, sets, nsets, &s);
  else if (!rc)
    rc = initialise(u, inst, sets, nsets);
  if (!rc && !get_outputs(u, inst, y))
    write_row(fp, 0.0, y, u->ncsv);
  else
    rc = 1;
  if (!rc)
    rc = me ? me_rows(u, inst, &s, h, step, nsteps, NULL, fp) != 0
            : cs_steps(u, inst, 0, nsteps, step, NULL, fp) != 0;
  if (!rc && u->fmi3Terminate(inst) != fmi3OK)
    rc = 1;
  if (me && !rc)
    fprintf(stderr, "fmu_import: model exchange: %ld event iterations\n", s.events);
  me_free(&s);
  if (inst)
    u->fmi3FreeInstance(inst);
  free(y);
  if (fclose(fp) != 0)
    rc = 1;
  return rc;
}

/* ---- checks. */

typedef struct checks {
  int failures;
  int total;
} checks;

static void check(checks *c, int ok, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  printf("%s ", ok ? "OK  " : "FAIL");
  vprintf(fmt, ap);
  putchar('\n');
  va_end(ap);
  fflush(stdout);
  c->total++;
  c->failures += !ok;
}

/* A call FMI's state machine forbids (or with a wrong argument): fmi3Error
 * and at least one fmi3Error message logged. */
#define EXPECT_REFUSED(c, what, call)                                                          \
  do {                                                                                         \
    const long before_ = log_errors;                                                           \
    const fmi3Status st_ = (call);                                                             \
    check(c, st_ == fmi3Error && log_errors > before_,                                         \
          "refused: %s (status %s, %ld error message(s) logged)", what, status_name(st_),      \
          log_errors - before_);                                                               \
  } while (0)

static int step_ok(const fmu *u, fmi3Instance inst, double t, double dt)
{
  fmi3Boolean e = fmi3False, term = fmi3False, early = fmi3False;
  double last = 0;
  return u->fmi3DoStep(inst, t, dt, fmi3True, &e, &term, &early, &last) == fmi3OK;
}

/* Step of the checks' runs, and their lengths: short, to keep the checks
 * a few seconds; the start (free fall onto the tires) has the fastest
 * transients of the run, tires landing and lifting. */
enum { CHK_STEPS = 150 };
static const double CHK_STEP = 1e-3;

/* FMI 3.0 (2.2.3) asks for fmi3Error and a logged reason on a call the
 * state machine forbids or with an illegal argument; it lets an FMU be
 * unusable after any fmi3Error. This FMU promises more (src/fmu/runtime.c:
 * a refused call changes nothing), so the instances are used on after
 * the refused calls, and the checks see that they still step. */
static void check_state_machine(const fmu *u, checks *c)
{
  fmi3Instance a = new_cs(u, "state-machine-cs");
  if (!a) {
    check(c, 0, "co-simulation instance for the state machine checks");
    return;
  }
  const fmi3ValueReference out0 = u->out[0], bad_vr = UINT32_MAX - 7;
  const double one = 1.0;
  double y = 0;
  EXPECT_REFUSED(c, "fmi3DoStep in Instantiated",
                 u->fmi3DoStep(a, 0, CHK_STEP, fmi3True, NULL, NULL, NULL, NULL));
  EXPECT_REFUSED(c, "fmi3ExitInitializationMode before fmi3EnterInitializationMode",
                 u->fmi3ExitInitializationMode(a));
  check(c, u->fmi3EnterInitializationMode(a, fmi3False, 0, 0, fmi3False, 0) == fmi3OK,
        "fmi3EnterInitializationMode after the refused calls");
  EXPECT_REFUSED(c, "fmi3EnterInitializationMode twice",
                 u->fmi3EnterInitializationMode(a, fmi3False, 0, 0, fmi3False, 0));
  EXPECT_REFUSED(c, "fmi3DoStep in Initialization Mode",
                 u->fmi3DoStep(a, 0, CHK_STEP, fmi3True, NULL, NULL, NULL, NULL));
  check(c, u->fmi3ExitInitializationMode(a) == fmi3OK,
        "fmi3ExitInitializationMode after the refused calls");
  double x[1] = {0};
  EXPECT_REFUSED(c, "fmi3SetContinuousStates on a co-simulation instance",
                 u->fmi3SetContinuousStates(a, x, 0));
  EXPECT_REFUSED(c, "fmi3EnterContinuousTimeMode on a co-simulation instance",
                 u->fmi3EnterContinuousTimeMode(a));
  EXPECT_REFUSED(c, "fmi3SetFloat64 of an output", u->fmi3SetFloat64(a, &out0, 1, &one, 1));
  EXPECT_REFUSED(c, "fmi3GetFloat64 of an unknown value reference",
                 u->fmi3GetFloat64(a, &bad_vr, 1, &y, 1));
  EXPECT_REFUSED(c, "fmi3DoStep from the wrong communication point",
                 u->fmi3DoStep(a, 0.5, CHK_STEP, fmi3True, NULL, NULL, NULL, NULL));
  EXPECT_REFUSED(c, "fmi3DoStep with a negative step",
                 u->fmi3DoStep(a, 0, -CHK_STEP, fmi3True, NULL, NULL, NULL, NULL));
  EXPECT_REFUSED(c, "fmi3EnterInitializationMode in Step Mode",
                 u->fmi3EnterInitializationMode(a, fmi3False, 0, 0, fmi3False, 0));
  check(c, step_ok(u, a, 0, CHK_STEP) && u->fmi3GetFloat64(a, &out0, 1, &y, 1) == fmi3OK,
        "the co-simulation instance steps after the refused calls");
  check(c, u->fmi3Terminate(a) == fmi3OK, "fmi3Terminate in Step Mode");
  EXPECT_REFUSED(c, "fmi3DoStep in Terminated",
                 u->fmi3DoStep(a, CHK_STEP, CHK_STEP, fmi3True, NULL, NULL, NULL, NULL));
  u->fmi3FreeInstance(a);

  fmi3Instance m = new_me(u, "state-machine-me");
  if (!m) {
    check(c, 0, "model exchange instance for the state machine checks");
    return;
  }
  EXPECT_REFUSED(c, "fmi3DoStep on a model exchange instance",
                 u->fmi3DoStep(m, 0, CHK_STEP, fmi3True, NULL, NULL, NULL, NULL));
  EXPECT_REFUSED(c, "fmi3SetTime in Instantiated", u->fmi3SetTime(m, 0.1));
  check(c, u->fmi3EnterInitializationMode(m, fmi3False, 0, 0, fmi3False, 0) == fmi3OK,
        "fmi3EnterInitializationMode (model exchange)");
  EXPECT_REFUSED(c, "fmi3EnterContinuousTimeMode from Initialization Mode",
                 u->fmi3EnterContinuousTimeMode(m));
  EXPECT_REFUSED(c, "fmi3EnterEventMode from Initialization Mode", u->fmi3EnterEventMode(m));
  check(c, u->fmi3ExitInitializationMode(m) == fmi3OK,
        "fmi3ExitInitializationMode (model exchange) after the refused calls");
  EXPECT_REFUSED(c, "fmi3CompletedIntegratorStep in Event Mode",
                 u->fmi3CompletedIntegratorStep(m, fmi3True, NULL, NULL));
  me_sim s;
  int ok = !me_alloc(u, &s);
  if (ok)
    EXPECT_REFUSED(c, "fmi3SetContinuousStates in Event Mode",
                   u->fmi3SetContinuousStates(m, s.x, s.n));
  if (ok)
    EXPECT_REFUSED(c, "fmi3SetContinuousStates with the wrong count",
                   u->fmi3SetContinuousStates(m, s.x, s.n + 1));
  ok = ok && !me_event(u, m, &s);
  if (ok)
    EXPECT_REFUSED(c, "fmi3UpdateDiscreteStates in Continuous-Time Mode",
                   u->fmi3UpdateDiscreteStates(m, NULL, NULL, NULL, NULL, NULL, NULL));
  ok = ok && !me_rows(u, m, &s, 1e-4, CHK_STEP, 5, NULL, NULL);
  check(c, ok, "the model exchange instance integrates after the refused calls");
  me_free(&s);
  u->fmi3FreeInstance(m);
}

static int cs_run(const fmu *u, fmi3Instance inst, char **sets, size_t nsets, long n,
                  double *rec)
{
  return initialise(u, inst, sets, nsets) || cs_steps(u, inst, 0, n, CHK_STEP, rec, NULL);
}

static int same_bits(const double *a, const double *b, size_t n)
{
  return memcmp(a, b, n * sizeof *a) == 0;
}

/* Where two records first differ, for the messages. */
static double max_abs_diff(const double *a, const double *b, size_t n)
{
  double d = 0;
  for (size_t k = 0; k < n; ++k)
    d = fmax(d, fabs(a[k] - b[k]));
  return d;
}

static void check_two_instances(const fmu *u, checks *c, double *lone, double *ra, double *rb)
{
  const size_t nrec = (size_t)CHK_STEPS * u->nout;
  fmi3Instance l = new_cs(u, "lone");
  int ok = l && !cs_run(u, l, NULL, 0, CHK_STEPS, lone);
  if (l)
    u->fmi3FreeInstance(l);
  check(c, ok, "a lone co-simulation run of %d steps", CHK_STEPS);
  if (!ok)
    return;
  /* Both alive at once, stepped in turn. */
  fmi3Instance a = new_cs(u, "twin-a"), b = new_cs(u, "twin-b");
  char load[] = "load_force=5000";
  char *sets[] = {load};
  ok = a && b && !initialise(u, a, NULL, 0) && !initialise(u, b, sets, 1);
  for (long i = 0; ok && i < CHK_STEPS; ++i)
    ok = !cs_steps(u, a, i, 1, CHK_STEP, ra + (size_t)i * u->nout, NULL) &&
         !cs_steps(u, b, i, 1, CHK_STEP, rb + (size_t)i * u->nout, NULL);
  check(c, ok, "two co-simulation instances at once, one with load_force = 5000 N");
  if (ok) {
    check(c, same_bits(lone, ra, nrec),
          "the unchanged instance equals the lone run to the bit (max |diff| %g)",
          max_abs_diff(lone, ra, nrec));
    check(c, max_abs_diff(ra, rb, nrec) > 0,
          "the instance with load_force = 5000 N differs (max |diff| %g)",
          max_abs_diff(ra, rb, nrec));
  }
  if (a)
    u->fmi3FreeInstance(a);
  if (b)
    u->fmi3FreeInstance(b);
}

static void check_reset(const fmu *u, checks *c, const double *fresh, double *rec)
{
  const size_t nrec = (size_t)CHK_STEPS * u->nout;
  fmi3Instance a = new_cs(u, "reset");
  char load[] = "load_force=2000";
  char *sets[] = {load};
  /* A run with another input first: fmi3Reset must also bring the
   * inputs back to their start values. */
  int ok = a && !cs_run(u, a, sets, 1, CHK_STEPS / 2, rec);
  ok = ok && u->fmi3Reset(a) == fmi3OK;
  check(c, ok, "fmi3Reset after a co-simulation run to t = %g s", CHK_STEPS / 2 * CHK_STEP);
  ok = ok && !cs_run(u, a, NULL, 0, CHK_STEPS, rec);
  check(c, ok && same_bits(fresh, rec, nrec),
        "after fmi3Reset the run equals a fresh instance's to the bit (max |diff| %g)",
        ok ? max_abs_diff(fresh, rec, nrec) : NAN);
  /* Reset from the state after an error (a failed DoStep is hard to
   * provoke; a refused call is not one): from Terminated. */
  ok = ok && u->fmi3Terminate(a) == fmi3OK && u->fmi3Reset(a) == fmi3OK &&
       !cs_run(u, a, NULL, 0, CHK_STEPS, rec);
  check(c, ok && same_bits(fresh, rec, nrec),
        "fmi3Reset from Terminated, then the same run to the bit");
  if (a)
    u->fmi3FreeInstance(a);
}

/* A serialized state changed by (k, mask, nan): byte k XORed with mask,
 * or with nan the double at byte k made NaN; it must be refused at
 * fmi3DeserializeFMUState or at fmi3SetFMUState, and the instance must
 * take the good state after it (FMI 3.0, 2.2.3: after fmi3Error an
 * instance goes on after fmi3SetFMUState of an earlier state). */
static void check_corrupt(const fmu *u, checks *c, fmi3Instance inst, const fmi3Byte *bytes,
                          size_t size, fmi3FMUState good, size_t k, fmi3Byte mask, int nan,
                          const char *what)
{
  fmi3Byte *bad = malloc(size);
  if (!bad || k + (nan ? sizeof(double) : 1) > size) {
    free(bad);
    check(c, 0, "a corrupted state of %zu bytes at byte %zu", size, k);
    return;
  }
  memcpy(bad, bytes, size);
  if (nan) {
    const double q = NAN;
    memcpy(bad + k, &q, sizeof q);
  } else {
    bad[k] ^= mask;
  }
  fmi3FMUState st = NULL;
  const long before = log_errors;
  fmi3Status s = u->fmi3DeserializeFMUState(inst, bad, size, &st);
  const char *where = "fmi3DeserializeFMUState";
  if (s == fmi3OK) {
    where = "fmi3SetFMUState";
    s = u->fmi3SetFMUState(inst, st);
  }
  check(c, s == fmi3Error && log_errors > before,
        "refused: a serialized state with %s corrupted (byte %zu): %s returned %s", what, k,
        where, status_name(s));
  if (st && u->fmi3FreeFMUState(inst, &st) != fmi3OK)
    check(c, 0, "fmi3FreeFMUState");
  free(bad);
  check(c, u->fmi3SetFMUState(inst, good) == fmi3OK,
        "fmi3SetFMUState of the good state after the one with %s corrupted", what);
}

static void check_cs_states(const fmu *u, checks *c, double *ya, double *yb)
{
  const long n1 = CHK_STEPS / 3, n2 = CHK_STEPS - n1;
  const size_t nrec = (size_t)n2 * u->nout;
  fmi3Instance a = new_cs(u, "fmu-state-cs");
  fmi3FMUState st = NULL, st2 = NULL;
  int ok = a && !cs_run(u, a, NULL, 0, n1, ya) && u->fmi3GetFMUState(a, &st) == fmi3OK &&
           !cs_steps(u, a, n1, n2, CHK_STEP, ya, NULL);
  ok = ok && u->fmi3SetFMUState(a, st) == fmi3OK && !cs_steps(u, a, n1, n2, CHK_STEP, yb, NULL);
  check(c, ok && same_bits(ya, yb, nrec),
        "co-simulation: fmi3SetFMUState at t1 = %g s, run to t2 = %g s again: the same outputs "
        "to the bit (max |diff| %g)",
        n1 * CHK_STEP, CHK_STEPS * CHK_STEP, ok ? max_abs_diff(ya, yb, nrec) : NAN);
  size_t size = 0;
  fmi3Byte *bytes = NULL;
  ok = ok && u->fmi3SerializedFMUStateSize(a, st, &size) == fmi3OK && size > 0 &&
       (bytes = malloc(size)) && u->fmi3SerializeFMUState(a, st, bytes, size) == fmi3OK &&
       u->fmi3FreeFMUState(a, &st) == fmi3OK && !st &&
       u->fmi3DeserializeFMUState(a, bytes, size, &st2) == fmi3OK &&
       u->fmi3SetFMUState(a, st2) == fmi3OK && !cs_steps(u, a, n1, n2, CHK_STEP, yb, NULL);
  check(c, ok && same_bits(ya, yb, nrec),
        "co-simulation: serialized (%zu bytes), freed, deserialized, set: the same outputs to "
        "the bit (max |diff| %g)",
        size, ok ? max_abs_diff(ya, yb, nrec) : NAN);
  if (ok) {
    fmi3FMUState junk = NULL;
    EXPECT_REFUSED(c, "fmi3DeserializeFMUState of one byte too few",
                   u->fmi3DeserializeFMUState(a, bytes, size - 1, &junk));
    EXPECT_REFUSED(c, "fmi3SerializeFMUState into one byte too few",
                   u->fmi3SerializeFMUState(a, st2, bytes, size - 1));
    if (junk)
      u->fmi3FreeFMUState(a, &junk);
    /* The layout is the FMU's own (src/fmu/runtime.c: six doubles of
     * header, the time, the states, ..., the state machine's state
     * last); an importer may not know it, but the corruptions are
     * chosen to hit each kind of field. */
    check_corrupt(u, c, a, bytes, size, st2, 0, 0xff, 0, "its first byte (the magic number)");
    check_corrupt(u, c, a, bytes, size, st2, 2 * sizeof(double) + 7, 0x40, 0,
                  "the interface kind");
    check_corrupt(u, c, a, bytes, size, st2, size - 1, 0x80, 0,
                  "its last byte (the sign of the state machine's state)");
    check_corrupt(u, c, a, bytes, size, st2, size - 2, 0x0f, 0,
                  "its last double (the state machine's state: 31, no state)");
    check_corrupt(u, c, a, bytes, size, st2, 7 * sizeof(double), 0, 1,
                  "the first continuous state (made NaN)");
    check_corrupt(u, c, a, bytes, size, st2, 6 * sizeof(double), 0, 1, "the time (made NaN)");
    /* The instance still takes the good state after the refusals. */
    ok = u->fmi3SetFMUState(a, st2) == fmi3OK && !cs_steps(u, a, n1, n2, CHK_STEP, yb, NULL);
    check(c, ok && same_bits(ya, yb, nrec),
          "co-simulation: after the refused states the good one still gives the same outputs");
  }
  free(bytes);
  if (a && st)
    u->fmi3FreeFMUState(a, &st);
  if (a && st2)
    u->fmi3FreeFMUState(a, &st2);
  if (a)
    u->fmi3FreeInstance(a);
}

/* Model exchange: the importer's integrator's own state saved beside the
 * FMU's (its time, next row, next time event, indicators at the last
 * step). */
typedef struct me_saved {
  double t, te;
  long row;
  int te_defined;
  double *g_prev;
} me_saved;

static void me_save(const me_sim *s, me_saved *v)
{
  v->t = s->t;
  v->te = s->te;
  v->row = s->row;
  v->te_defined = s->te_defined;
  memcpy(v->g_prev, s->g_prev, s->ng * sizeof *s->g_prev);
}

static int me_restore(const fmu *u, fmi3Instance inst, me_sim *s, const me_saved *v)
{
  s->t = v->t;
  s->te = v->te;
  s->row = v->row;
  s->te_defined = v->te_defined;
  memcpy(s->g_prev, v->g_prev, s->ng * sizeof *s->g_prev);
  return u->fmi3GetContinuousStates(inst, s->x, s->n) == fmi3OK ? 0 : -1;
}

static void check_me_states(const fmu *u, checks *c, double *ya, double *yb, double h)
{
  const long n1 = CHK_STEPS / 3, n2 = CHK_STEPS - n1;
  const size_t nrec = (size_t)n2 * u->nout;
  fmi3Instance m = new_me(u, "fmu-state-me");
  me_sim s;
  me_saved v = {0};
  fmi3FMUState st = NULL, st2 = NULL;
  int ok = !me_alloc(u, &s) && (v.g_prev = calloc(s.ng + 1, sizeof(double)));
  ok = ok && m && !me_start(u, m, NULL, 0, &s) &&
       !me_rows(u, m, &s, h, CHK_STEP, n1, NULL, NULL);
  ok = ok && u->fmi3GetFMUState(m, &st) == fmi3OK;
  if (ok)
    me_save(&s, &v);
  const long events_before = s.events;
  ok = ok && !me_rows(u, m, &s, h, CHK_STEP, n2, ya, NULL);
  const long events = s.events - events_before;
  ok = ok && u->fmi3SetFMUState(m, st) == fmi3OK && !me_restore(u, m, &s, &v) &&
       !me_rows(u, m, &s, h, CHK_STEP, n2, yb, NULL);
  check(c, ok && same_bits(ya, yb, nrec),
        "model exchange: fmi3SetFMUState at t1 = %g s, integrated to t2 = %g s again (%ld "
        "events between): the same outputs to the bit (max |diff| %g)",
        n1 * CHK_STEP, CHK_STEPS * CHK_STEP, events, ok ? max_abs_diff(ya, yb, nrec) : NAN);
  size_t size = 0;
  fmi3Byte *bytes = NULL;
  ok = ok && u->fmi3SerializedFMUStateSize(m, st, &size) == fmi3OK && size > 0 &&
       (bytes = malloc(size)) && u->fmi3SerializeFMUState(m, st, bytes, size) == fmi3OK &&
       u->fmi3FreeFMUState(m, &st) == fmi3OK &&
       u->fmi3DeserializeFMUState(m, bytes, size, &st2) == fmi3OK &&
       u->fmi3SetFMUState(m, st2) == fmi3OK && !me_restore(u, m, &s, &v) &&
       !me_rows(u, m, &s, h, CHK_STEP, n2, yb, NULL);
  check(c, ok && same_bits(ya, yb, nrec),
        "model exchange: serialized (%zu bytes), freed, deserialized, set: the same outputs to "
        "the bit (max |diff| %g)",
        size, ok ? max_abs_diff(ya, yb, nrec) : NAN);
  if (ok) {
    check_corrupt(u, c, m, bytes, size, st2, 0, 0xff, 0, "its first byte (the magic number)");
    check_corrupt(u, c, m, bytes, size, st2, size - 1, 0x80, 0,
                  "its last byte (the sign of the state machine's state)");
    check_corrupt(u, c, m, bytes, size, st2, 7 * sizeof(double), 0, 1,
                  "the first continuous state (made NaN)");
  }
  free(bytes);
  if (m && st)
    u->fmi3FreeFMUState(m, &st);
  if (m && st2)
    u->fmi3FreeFMUState(m, &st2);
  if (m)
    u->fmi3FreeInstance(m);
  free(v.g_prev);
  me_free(&s);
}

static void check_instantiation(const fmu *u, checks *c)
{
  const long before = log_errors;
  fmi3Instance a = u->fmi3InstantiateCoSimulation("bad-token", "{not-this-fmu}", u->resources,
                                                  fmi3False, fmi3False, fmi3False, fmi3False,
                                                  NULL, 0, NULL, log_message, NULL);
  check(c, !a && log_errors > before,
        "co-simulation with a wrong instantiation token: NULL and a logged reason");
  if (a)
    u->fmi3FreeInstance(a);
  const long before_me = log_errors;
  fmi3Instance m = u->fmi3InstantiateModelExchange("bad-token", "{not-this-fmu}", u->resources,
                                                   fmi3False, fmi3False, NULL, log_message);
  check(c, !m && log_errors > before_me,
        "model exchange with a wrong instantiation token: NULL and a logged reason");
  if (m)
    u->fmi3FreeInstance(m);
  a = u->fmi3InstantiateCoSimulation("no-resources", u->token, NULL, fmi3False, fmi3False,
                                     fmi3False, fmi3False, NULL, 0, NULL, log_message, NULL);
  check(c, !a, "co-simulation with a NULL resource path: NULL");
  if (a)
    u->fmi3FreeInstance(a);
  a = u->fmi3InstantiateCoSimulation("no-log", "{not-this-fmu}", u->resources, fmi3False,
                                     fmi3False, fmi3False, fmi3False, NULL, 0, NULL, NULL,
                                     NULL);
  check(c, !a, "a wrong token without a log callback: NULL (and no crash)");
  if (a)
    u->fmi3FreeInstance(a);
  /* fmi3FreeInstance(NULL) is allowed (FMI 3.0, 2.3.1). */
  u->fmi3FreeInstance(NULL);
  check(c, 1, "fmi3FreeInstance(NULL) returns");
}

static int run_checks(const fmu *u, double h)
{
  checks c = {0, 0};
  const char *version = u->fmi3GetVersion();
  check(&c, version && !strcmp(version, "3.0"), "fmi3GetVersion() is \"3.0\" (got \"%s\")",
        version ? version : "(null)");
  check(&c, u->nout > 0, "%zu outputs, %zu states, %zu event indicators in the description",
        u->nout, u->nstates, u->nindicators);
  if (!u->nout)
    return 1;
  check_instantiation(u, &c);
  check_state_machine(u, &c);
  const size_t nrec = (size_t)CHK_STEPS * u->nout;
  double *r0 = calloc(nrec, sizeof *r0), *r1 = calloc(nrec, sizeof *r1),
         *r2 = calloc(nrec, sizeof *r2);
  if (r0 && r1 && r2) {
    check_two_instances(u, &c, r0, r1, r2);
    check_reset(u, &c, r0, r1);
    check_cs_states(u, &c, r1, r2);
    check_me_states(u, &c, r1, r2, h);
  } else {
    check(&c, 0, "memory");
  }
  free(r0);
  free(r1);
  free(r2);
  printf("%d of %d checks failed\n", c.failures, c.total);
  return c.failures ? 1 : 0;
}

static int usage(void)
{
  fputs("usage: fmu_import [--h H] [--columns N] cs|me DIR STEP T_END OUT.csv "
        "[[@]NAME=VALUE ...]\n"
        "       fmu_import [--h H] checks DIR\n"
        "--columns N: write the first N outputs only (all are read at every step)\n",
        stderr);
  return 2;
}

static int positive(const char *text, double *v)
{
  char *end = NULL;
  *v = strtod(text, &end);
  return end != text && !*end && *v > 0 && isfinite(*v);
}

int main(int argc, char **argv)
{
  int a = 1;
  double h = 1e-4;
  double columns = 0;
  for (int more = 1; more && a + 1 < argc;) {
    if (!strcmp(argv[a], "--h") && positive(argv[a + 1], &h))
      a += 2;
    else if (!strcmp(argv[a], "--columns") && positive(argv[a + 1], &columns) &&
             columns == floor(columns))
      a += 2;
    else if (!strcmp(argv[a], "--h") || !strcmp(argv[a], "--columns"))
      return usage();
    else
      more = 0;
  }
  if (argc - a < 2)
    return usage();
  const char *mode = argv[a];
  const int is_checks = !strcmp(mode, "checks");
  const int me = !strcmp(mode, "me");
  if (!is_checks && !me && strcmp(mode, "cs"))
    return usage();
  double step = 0, t_end = 0;
  if (!is_checks &&
      (argc - a < 5 || !positive(argv[a + 2], &step) || !positive(argv[a + 3], &t_end)))
    return usage();
  LIBXML_TEST_VERSION
  fmu u;
  int rc = fmu_open(argv[a + 1], &u) ? 2 : 0;
  if (!rc)
    u.ncsv = columns > 0 && (size_t)columns < u.nout ? (size_t)columns : u.nout;
  if (!rc && is_checks)
    rc = run_checks(&u, h);
  else if (!rc)
    rc = simulate(&u, me, h, step, t_end, argv[a + 4], argv + a + 5, (size_t)(argc - a - 5));
  fmu_close(&u);
  xmlCleanupParser();
  return rc;
}
