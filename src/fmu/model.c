/* SPDX-License-Identifier: BSD-3-Clause */
/* The variables of a flexbond FMU (fmu_model), in value-reference order:
 * time; the stepper's inputs; its outputs; the tunable parameters; with
 * the continuous states, their derivatives and the event indicators
 * that model exchange exposes (FMI 3.0, sections 2.4.7 and 3). */
#include <stdlib.h>
#include <string.h>

#include "flexbond/bd.h"
#include "flexbond/io.h"

#include "core/util.h"
#include "fmu/fmu_internal.h"

void fmu_model_free(fmu_model **m)
{
  if (!m || !*m)
    return;
  for (size_t k = 0; k < (*m)->nvars; ++k) {
    free((*m)->var[k].name);
    free((*m)->var[k].unit_owned);
  }
  free((*m)->var);
  free(*m);
  *m = NULL;
}

/* Appends a variable named by name (taken over: NULL means out of
 * memory). */
static int add(fmu_model *m, fmu_var_kind kind, size_t index, char *name, const char *unit,
               double start, const char *doc, fb_err *err)
{
  if (!name)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the FMU's variables");
  fmu_var *v = &m->var[m->nvars++];
  *v = (fmu_var){name, kind, index, "", NULL, start, 0, doc};
  if (unit && *unit && !(v->unit = v->unit_owned = fb_strdup(unit)))
    return fb_err_set(err, FB_ENOMEM, "out of memory for the FMU's variables");
  return FB_OK;
}

/* FNV-1a, 64 bits (Fowler, Noll and Vo), over a string and its NUL. */
static uint64_t digest(uint64_t h, const char *s)
{
  for (const unsigned char *p = (const unsigned char *)s;; ++p) {
    h = (h ^ *p) * 0x100000001b3ull;
    if (!*p)
      return h;
  }
}

/* The token: a digest of every variable's name, kind and unit and the
 * library's version, so a binary from another build, or a description
 * edited by hand, is refused when instantiated. */
static void make_token(fmu_model *m)
{
  uint64_t h = digest(0xcbf29ce484222325ull, FLEXBOND_VERSION_TEXT);
  for (size_t k = 0; k < m->nvars; ++k) {
    char kind[8];
    snprintf(kind, sizeof kind, "%d", (int)m->var[k].kind);
    h = digest(digest(digest(h, m->var[k].name), kind), m->var[k].unit);
  }
  snprintf(m->token, sizeof m->token, "{flexbond-%016llx}", (unsigned long long)h);
}

static int add_signals(fmu_model *m, fb_vehicle_stepper *st, const fmu_config *c,
                       const double *param_start, const char *const *param_unit, fb_err *err)
{
  int rc = add(m, FMU_VAR_TIME, 0, fb_strdup("time"), "s", 0.0, "simulation time", err);
  m->first_input = m->nvars;
  for (size_t i = 0; !rc && i < m->ninputs; ++i)
    rc = add(m, FMU_VAR_INPUT, i, fb_strdup(fb_vehicle_stepper_input_name(st, i)),
             fb_vehicle_stepper_input_unit(st, i), 0.0, NULL, err);
  m->first_output = m->nvars;
  for (size_t o = 0; !rc && o < m->noutputs; ++o)
    rc = add(m, FMU_VAR_OUTPUT, o, fb_strdup(fb_vehicle_stepper_output_name(st, o)),
             fb_vehicle_stepper_output_unit(st, o), 0.0, NULL, err);
  m->first_parameter = m->nvars;
  for (size_t p = 0; !rc && p < m->nparameters; ++p) {
    rc = add(m, FMU_VAR_PARAMETER, p, fb_strdup(c->parameter[p]), param_unit[p], param_start[p],
             NULL, err);
    if (!rc)
      m->var[m->nvars - 1].fixed = fmu_parameter_fixed(c->parameter[p]);
  }
  return rc;
}

static int add_model_exchange(fmu_model *m, fb_vehicle_stepper *st, fb_err *err)
{
  const fb_bd *bd = fb_vehicle_stepper_diagram(st);
  int rc = FB_OK;
  m->first_state = m->nvars;
  for (size_t i = 0; !rc && i < m->nstates; ++i)
    rc = add(m, FMU_VAR_STATE, i, fb_strdup(fb_bd_state_name(bd, i)), NULL, 0.0, NULL, err);
  m->first_derivative = m->nvars;
  for (size_t i = 0; !rc && i < m->nstates; ++i)
    rc = add(m, FMU_VAR_DERIVATIVE, i, fb_strdup_printf("der(%s)", fb_bd_state_name(bd, i)),
             NULL, 0.0, NULL, err);
  m->first_indicator = m->nvars;
  for (size_t g = 0; !rc && g < m->nindicators; ++g)
    rc = add(m, FMU_VAR_INDICATOR, g,
             fb_strdup_printf("guard[%zu](%s)", g + 1, fb_bd_guard_element(bd, g)), NULL, 0.0,
             NULL, err);
  return rc;
}

int fmu_parameter_fixed(const char *key)
{
  /* The scenario format's road section (docs/scenario-format.md). */
  return strncmp(key, "road.", 5) == 0;
}

int fmu_model_new(fb_vehicle_stepper *st, const fmu_config *c, const double *param_start,
                  const char *const *param_unit, fmu_model **out, fb_err *err)
{
  *out = NULL;
  fmu_model *m = calloc(1, sizeof *m);
  if (!m)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the FMU's variables");
  const fb_bd *bd = fb_vehicle_stepper_diagram(st);
  m->ninputs = fb_vehicle_stepper_ninputs(st);
  m->noutputs = fb_vehicle_stepper_noutputs(st);
  m->nparameters = c->nparameters;
  m->nstates = fb_bd_nstates(bd);
  m->nindicators = fb_bd_nguards(bd);
  const size_t total =
      1 + m->ninputs + m->noutputs + m->nparameters + 2 * m->nstates + m->nindicators;
  m->var = calloc(total, sizeof *m->var);
  int rc = m->var ? add_signals(m, st, c, param_start, param_unit, err)
                  : fb_err_set(err, FB_ENOMEM, "out of memory for %zu variables", total);
  if (!rc)
    rc = add_model_exchange(m, st, err);
  if (rc) {
    fmu_model_free(&m);
    return rc;
  }
  make_token(m);
  *out = m;
  return FB_OK;
}

/* fmu_parameter_value's search. */
typedef struct param_search {
  const char *key;
  const char *text; /* found: the value as the file has it */
  const char *unit;
  char buf[256];
} param_search;

static int match_value(const fb_scenario_value *v, void *ctx)
{
  param_search *ps = ctx;
  if (!v->path || strcmp(v->path, ps->key) != 0)
    return 0;
  snprintf(ps->buf, sizeof ps->buf, "%s", v->value);
  ps->text = ps->buf;
  ps->unit = v->unit;
  return 1;
}

int fmu_parameter_value(const fb_scenario *s, const char *key, double *value, const char **unit,
                        fb_err *err)
{
  param_search ps = {key, NULL, "", {0}};
  fb_scenario_each_value(s, match_value, &ps);
  char *end = NULL;
  const double v = ps.text ? strtod(ps.text, &end) : 0.0;
  int rc = FB_OK;
  if (!ps.text)
    rc = fb_err_set(err, FB_EINVAL,
                    "%s: the scenario file does not write this value; write it there to make "
                    "it a parameter",
                    key);
  else if (end == ps.text || *end)
    rc = fb_err_set(err, FB_EINVAL, "%s: '%s' is not a number, so no parameter", key, ps.text);
  if (rc) {
    fb_err_set_key(err, "%s", key);
    return rc;
  }
  *value = v;
  *unit = ps.unit;
  return FB_OK;
}

int fmu_scenario_load(const char *path, const fmu_config *c, const double *values,
                      fb_scenario **out, fb_err *err)
{
  const size_t n = c->nsets + (values ? c->nparameters : 0) + 1;
  fb_scenario_override *ov = calloc(n, sizeof *ov);
  char(*text)[32] = calloc(c->nparameters + 1, sizeof *text);
  int rc = ov && text ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  size_t k = 0;
  for (size_t i = 0; !rc && i < c->nsets; ++i)
    ov[k++] = c->set[i];
  for (size_t p = 0; !rc && values && p < c->nparameters; ++p) {
    snprintf(text[p], sizeof text[p], "%.17g", values[p]);
    ov[k++] = (fb_scenario_override){
        .key = c->parameter[p], .value = text[p], .label = "the FMU's parameter"};
  }
  char t_end[32];
  /* With the road as inputs the scenario's road is not driven on, and the
   * horizon is set on the scenario read, not through its file, whose
   * check would hold it against the road's obstacles. */
  if (!rc && c->t_end > 0 && !c->road_inputs) {
    snprintf(t_end, sizeof t_end, "%.17g", c->t_end);
    ov[k++] = (fb_scenario_override){.key = "simulation.t_end",
                                     .value = t_end,
                                     .label = "the FMU's horizon (flexbond fmu --t-end)"};
  }
  if (!rc)
    rc = fb_scenario_load_overrides(path, ov, k, out, err);
  if (!rc && c->t_end > 0 && c->road_inputs)
    (*out)->t_end = c->t_end;
  free(ov);
  free(text);
  return rc;
}
