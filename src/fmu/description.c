/* SPDX-License-Identifier: BSD-3-Clause */
/* modelDescription.xml and sources/buildDescription.xml of a flexbond
 * FMU, as FMI 3.0 (v3.0.2) lays them out: section 2.4 (the model
 * description: units 2.4.3, log categories 2.4.5, default experiment
 * 2.4.6, variables 2.4.7, model structure 2.4.8) and 2.5.1.2 (the build
 * description). Every name and text from the scenario passes
 * fb_xml_write_attr. */
#include <stdlib.h>
#include <string.h>

#include "flexbond/escape.h"

#include "core/textfile.h"
#include "fmu/fmu_description.h"

static void attr(FILE *fp, const char *name, const char *value)
{
  fprintf(fp, " %s=\"", name);
  fb_xml_write_attr(fp, value);
  fputc('"', fp);
}

/* Index of unit u among the first n variables' units, -1 if new. */
static long unit_seen(const fmu_model *m, size_t n, const char *u)
{
  for (size_t k = 0; k < n; ++k)
    if (!strcmp(m->var[k].unit, u))
      return (long)k;
  return -1;
}

static void write_base_unit(FILE *fp, const fmu_unit *u)
{
  fputs("<BaseUnit", fp);
  const int e[8] = {u->kg, u->m, u->s, u->A, u->K, u->mol, u->cd, u->rad};
  static const char *const names[8] = {"kg", "m", "s", "A", "K", "mol", "cd", "rad"};
  for (int i = 0; i < 8; ++i)
    if (e[i])
      fprintf(fp, " %s=\"%d\"", names[i], e[i]);
  if (u->factor != 1.0) {
    char factor[40];
    fb_format_shortest(u->factor, 1, factor, sizeof factor);
    fprintf(fp, " factor=\"%s\"", factor);
  }
  fputs("/>", fp);
}

/* <UnitDefinitions>: every unit a variable has, once, with its SI base
 * units when flexbond knows the symbols (a unit it does not know is
 * declared by name alone, as 2.4.3 allows). */
static void write_units(FILE *fp, const fmu_model *m)
{
  int any = 0;
  for (size_t k = 0; k < m->nvars; ++k)
    any |= *m->var[k].unit != '\0';
  if (!any)
    return;
  fputs("  <UnitDefinitions>\n", fp);
  for (size_t k = 0; k < m->nvars; ++k) {
    const char *u = m->var[k].unit;
    if (!*u || unit_seen(m, k, u) >= 0)
      continue;
    fputs("    <Unit", fp);
    attr(fp, "name", u);
    fmu_unit base;
    if (fmu_unit_parse(u, &base, NULL) == FB_OK) {
      fputs(">", fp);
      write_base_unit(fp, &base);
      fputs("</Unit>\n", fp);
    } else {
      fputs("/>\n", fp);
    }
  }
  fputs("  </UnitDefinitions>\n", fp);
}

static const char *causality(fmu_var_kind k)
{
  switch (k) {
  case FMU_VAR_TIME: return "independent";
  case FMU_VAR_INPUT: return "input";
  case FMU_VAR_OUTPUT: return "output";
  case FMU_VAR_PARAMETER: return "parameter";
  default: return "local";
  }
}

static void write_variable(FILE *fp, const fmu_model *m, size_t vr, const char *description)
{
  const fmu_var *v = &m->var[vr];
  fputs("    <Float64", fp);
  attr(fp, "name", v->name);
  fprintf(fp, " valueReference=\"%zu\"", vr);
  if (description)
    attr(fp, "description", description);
  fprintf(fp, " causality=\"%s\" variability=\"%s\"", causality(v->kind),
          v->kind != FMU_VAR_PARAMETER ? "continuous"
          : v->fixed                   ? "fixed"
                                       : "tunable");
  if (v->kind == FMU_VAR_STATE || v->kind == FMU_VAR_DERIVATIVE || v->kind == FMU_VAR_INDICATOR)
    fputs(" initial=\"calculated\"", fp);
  if (*v->unit)
    attr(fp, "unit", v->unit);
  if (v->kind == FMU_VAR_INPUT || v->kind == FMU_VAR_PARAMETER) {
    char start[40];
    fb_format_shortest(v->start, 1, start, sizeof start); /* reads back as v->start */
    fprintf(fp, " start=\"%s\"", start);
  }
  if (v->kind == FMU_VAR_DERIVATIVE)
    fprintf(fp, " derivative=\"%zu\"", m->first_state + v->index);
  fputs("/>\n", fp);
}

/* What an input is (the stepper's, flexbond/vehicle.h). */
static const char *input_doc(const fmu_var *v)
{
  if (v->index == 0)
    return "vertical force on the load, shared by the load points, up positive";
  return (v->index - FB_VEHICLE_NINPUTS) % 2
             ? "the road's vertical rate under the wheel, up positive"
             : "the road's height under the wheel, up positive, from where it is at the end "
               "of initialisation";
}

static const char *var_doc(const fmu_var *v)
{
  switch (v->kind) {
  case FMU_VAR_TIME: return "time from the start of the run";
  case FMU_VAR_INPUT: return input_doc(v);
  case FMU_VAR_PARAMETER: return "a value of the scenario file, in the file's unit";
  case FMU_VAR_STATE: return "a state of the block diagram (model exchange)";
  case FMU_VAR_INDICATOR: return "a switched law's guard: a mode changes where it crosses zero";
  default: return NULL;
  }
}

static void write_structure(FILE *fp, const fmu_model *m)
{
  fputs("  <ModelStructure>\n", fp);
  for (size_t o = 0; o < m->noutputs; ++o)
    fprintf(fp, "    <Output valueReference=\"%zu\"/>\n", m->first_output + o);
  for (size_t i = 0; i < m->nstates; ++i)
    fprintf(fp, "    <ContinuousStateDerivative valueReference=\"%zu\"/>\n",
            m->first_derivative + i);
  for (size_t o = 0; o < m->noutputs; ++o)
    fprintf(fp, "    <InitialUnknown valueReference=\"%zu\"/>\n", m->first_output + o);
  for (size_t i = 0; i < m->nstates; ++i)
    fprintf(fp, "    <InitialUnknown valueReference=\"%zu\"/>\n", m->first_state + i);
  for (size_t i = 0; i < m->nstates; ++i)
    fprintf(fp, "    <InitialUnknown valueReference=\"%zu\"/>\n", m->first_derivative + i);
  for (size_t g = 0; g < m->nindicators; ++g)
    fprintf(fp, "    <EventIndicator valueReference=\"%zu\"/>\n", m->first_indicator + g);
  fputs("  </ModelStructure>\n", fp);
}

/* The interface elements' common attributes. */
static void write_interface(FILE *fp, const char *element, const char *id, const char *extra)
{
  fprintf(fp, "  <%s", element);
  attr(fp, "modelIdentifier", id);
  fprintf(fp, " canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\"%s/>\n", extra);
}

int fmu_write_model_description(FILE *fp, const fmu_description *d, fb_err *err)
{
  const fmu_model *m = d->model;
  fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<fmiModelDescription fmiVersion=\"3.0\"",
        fp);
  attr(fp, "modelName", d->model_name);
  attr(fp, "instantiationToken", m->token);
  attr(fp, "description", d->description);
  attr(fp, "generationTool", "flexbond " FLEXBOND_VERSION_TEXT);
  attr(fp, "version", d->version);
  fputs(" variableNamingConvention=\"flat\">\n", fp);
  write_interface(fp, "ModelExchange", d->model_identifier,
                  " needsCompletedIntegratorStep=\"false\"");
  write_interface(fp, "CoSimulation", d->model_identifier,
                  " canHandleVariableCommunicationStepSize=\"true\" hasEventMode=\"false\"");
  write_units(fp, m);
  fputs("  <LogCategories>\n"
        "    <Category name=\"logEvents\" description=\"the model's events and set-up\"/>\n"
        "    <Category name=\"logStatusWarning\"/>\n"
        "    <Category name=\"logStatusError\" description=\"why a call failed\"/>\n"
        "  </LogCategories>\n",
        fp);
  char stop[40], step[40], tol[40];
  fb_format_shortest(d->stop_time, 1, stop, sizeof stop);
  fb_format_shortest(d->step_size, 1, step, sizeof step);
  fb_format_shortest(d->tolerance, 1, tol, sizeof tol);
  fprintf(fp,
          "  <DefaultExperiment startTime=\"0\" stopTime=\"%s\" tolerance=\"%s\" "
          "stepSize=\"%s\"/>\n",
          stop, tol, step);
  fputs("  <ModelVariables>\n", fp);
  for (size_t k = 0; k < m->nvars; ++k)
    write_variable(fp, m, k, var_doc(&m->var[k]));
  fputs("  </ModelVariables>\n", fp);
  write_structure(fp, m);
  fputs("</fmiModelDescription>\n", fp);
  return ferror(fp) ? fb_err_set(err, FB_EIO, "writing modelDescription.xml failed") : FB_OK;
}

int fmu_write_build_description(FILE *fp, const fmu_description *d, fb_err *err)
{
  fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        "<fmiBuildDescription fmiVersion=\"3.0\">\n  <BuildConfiguration",
        fp);
  attr(fp, "modelIdentifier", d->model_identifier);
  fputs(" description=\"the FMU's binary: its own source over the flexbond library\">\n"
        "    <SourceFileSet language=\"C11\">\n",
        fp);
  for (size_t k = 0; k < d->nsources; ++k) {
    fputs("      <SourceFile", fp);
    attr(fp, "name", d->sources[k]);
    fputs("/>\n", fp);
  }
  fputs("      <IncludeDirectory name=\".\"/>\n    </SourceFileSet>\n", fp);
  fputs("    <Library name=\"flexbond\" version=\"" FLEXBOND_VERSION_TEXT
        "\" external=\"true\" "
        "description=\"libflexbond and its headers (pkg-config flexbond), with SUNDIALS, "
        "SuiteSparse, LAPACKE, OpenBLAS, libfyaml and zlib\"/>\n",
        fp);
  fputs("  </BuildConfiguration>\n</fmiBuildDescription>\n", fp);
  return ferror(fp) ? fb_err_set(err, FB_EIO, "writing buildDescription.xml failed") : FB_OK;
}
