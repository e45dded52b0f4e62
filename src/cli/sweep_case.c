/* SPDX-License-Identifier: BSD-3-Clause */
/* The cases of flexbond sweep as the command sees them (sweep.h): the
 * study layer's sweep (fb_study_sweep) runs and measures them; here are
 * its callbacks (a case's scenario, read with its --set values, and what
 * a finished case says) and the names --plot takes; sweep.csv's rows are
 * sweep_csv.c's. */
#include <stdio.h>
#include <string.h>

#include "flexbond/sim.h"

#include "../core/textfile.h"
#include "cli.h"
#include "sweep.h"

/* ---- The study's callbacks (fb_study_sweep_ops), on the pool's threads. */

/* Case i's scenario: the file read with the case's --set values in place
 * of its own (fb_scenario_load_overrides, so the reader checks and
 * converts them as its own). */
static int load_case(void *ctx, size_t i, const fb_scenario_override *ov, size_t n,
                     fb_scenario **out, fb_err *err)
{
  const sweep_args *a = ctx;
  int rc = fb_scenario_load_overrides(a->scenario_path, ov, n, out, err);
  /* The scenario's warnings were said once, at the start; a case says
   * those about its own swept values (located at the --set), and under
   * --strict such a value fails the case, as any bad input of a case. */
  if (rc == FB_OK && a->strict)
    rc = cli_scenario_warnings(*out, 1, err);
  for (size_t w = 0; rc == FB_OK && !a->quiet && w < fb_scenario_nwarnings(*out); ++w)
    if (fb_scenario_warning(*out, w)->source == FB_SOURCE_OVERRIDE)
      cli_say("flexbond: warning: case %zu: %s", i + 1, fb_scenario_warning(*out, w)->msg);
  return rc;
}

/* The reader sets the source of an error about a value a --set replaced
 * (fb_scenario_load_overrides); one found later, by locating it. */
int sweep_locate_case(void *ctx, const fb_scenario *s, fb_err *err)
{
  (void)ctx;
  return fb_scenario_locate(s, err);
}

int sweep_interrupted(void *ctx)
{
  (void)ctx;
  return cli_interrupted();
}

/* "flexbond sweep: case 3/12 (speed_kmh=15): ok, 1713 steps, 0.015 s". */
static void report_case(const sweep_args *a, size_t i)
{
  fb_study_sweep_case c;
  fb_study_sweep_case_get(a->study, i, &c);
  char label[512], where[32] = "";
  sweep_case_label(a, i, 0, label, sizeof label);
  if (a->mpi)
    snprintf(where, sizeof where, " on rank %d", c.worker);
  const size_t steps = fb_study_sweep_metric_other(a->study, FB_STUDY_SWEEP_SOLVER_STEPS);
  if (c.status == FB_OK)
    cli_say("flexbond sweep: case %zu/%zu (%s): ok%s, %.0f steps, %.3g s", i + 1, a->ncases,
            label, where, c.metric[steps], c.wall_seconds);
  else
    cli_say("flexbond sweep: case %zu/%zu (%s): failed%s: %s", i + 1, a->ncases, label, where,
            c.error ? c.error : "out of memory");
}

/* A finished case (under the study's lock): its journal row, then its
 * progress line. Once the journal cannot be written the study stops
 * (a case run then would be lost to --resume); the cases still running
 * are said, not journaled. */
static int case_finished(void *ctx, size_t i, fb_err *err)
{
  sweep_args *a = ctx;
  int rc = FB_OK;
  if (a->journal && !a->journal_failed) {
    rc = sweep_journal_append(a->journal, i, err);
    a->journal_failed = rc != FB_OK;
  }
  if (!a->quiet)
    report_case(a, i);
  return rc;
}

int sweep_study_new(sweep_args *a, fb_err *err)
{
  fb_study_sweep_axis axes[SWEEP_MAX_KEYS];
  for (size_t k = 0; k < a->nkeys; ++k)
    axes[k] = (fb_study_sweep_axis){.key = a->keys[k].key,
                                    .values = (const char *const *)a->keys[k].values,
                                    .nvalues = a->keys[k].nvalues};
  const fb_study_sweep_ops ops = {.load = load_case,
                                  .locate = sweep_locate_case,
                                  .stop = sweep_interrupted,
                                  .finished = case_finished,
                                  .ctx = a};
  const int rc = fb_study_sweep_new(a->base, a->sys, axes, a->nkeys, &ops, &a->study, err);
  a->nmetrics = rc == FB_OK ? fb_study_sweep_nmetrics(a->study) : 0;
  return rc;
}

/* Name of metric m into buf. */
static void metric_name(const sweep_args *a, size_t m, char *buf, size_t size)
{
  fb_study_sweep_metric_name(a->study, m, buf, size);
}

/* OUTPUT:STAT: one of output OUTPUT's statistics, by its column name
 * OUTPUT_STAT; -1 if none is. */
static int find_stat(const sweep_args *a, const char *spec, const char *colon, size_t *m)
{
  const size_t len = (size_t)(colon - spec);
  char want[FB_ERR_KEY_MAX], name[FB_ERR_KEY_MAX];
  snprintf(want, sizeof want, "%.*s_%s", (int)len, spec, colon + 1);
  for (size_t k = 0; k < a->base->noutputs; ++k) {
    if (strlen(a->base->output[k].name) != len ||
        strncmp(a->base->output[k].name, spec, len) != 0)
      continue;
    for (size_t st = 0; st < FB_STUDY_SWEEP_NSTATS; ++st) {
      metric_name(a, FB_STUDY_SWEEP_NSTATS * k + st, name, sizeof name);
      if (!strcmp(name, want)) {
        *m = FB_STUDY_SWEEP_NSTATS * k + st;
        return 0;
      }
    }
  }
  return -1;
}

int sweep_metric_find(const sweep_args *a, const char *spec, size_t *m)
{
  const char *colon = strchr(spec, ':');
  if (colon)
    return find_stat(a, spec, colon, m);
  for (size_t k = 0; k < a->base->noutputs; ++k)
    if (!strcmp(a->base->output[k].name, spec)) {
      *m = FB_STUDY_SWEEP_NSTATS * k + FB_STUDY_SWEEP_PEAK;
      return 0;
    }
  for (size_t i = 0; i < a->nmetrics; ++i) {
    char name[FB_ERR_KEY_MAX];
    metric_name(a, i, name, sizeof name);
    if (!strcmp(name, spec)) {
      *m = i;
      return 0;
    }
  }
  return -1;
}

void sweep_default_plots(sweep_args *a)
{
  a->nplots = 0;
  if (a->base->noutputs > 0)
    a->plot[a->nplots++] = FB_STUDY_SWEEP_PEAK;
  a->plot[a->nplots++] = fb_study_sweep_metric_other(a->study, FB_STUDY_SWEEP_MIN_TIRE_FORCE);
  if (fb_study_ride_output(a->base) < a->base->noutputs)
    a->plot[a->nplots++] = fb_study_sweep_metric_other(a->study, FB_STUDY_SWEEP_RIDE_A_W_RMS);
  a->plot[a->nplots++] =
      fb_study_sweep_metric_other(a->study, FB_STUDY_SWEEP_CONTACT_LOSS_INTERVALS);
}

/* "key=value, key=value" of case i into buf. */
void sweep_case_label(const sweep_args *a, size_t i, size_t first_key, char *buf, size_t size)
{
  size_t len = 0;
  buf[0] = '\0';
  for (size_t k = first_key; k < a->nkeys && len + 1 < size; ++k) {
    len = fb_text_append(buf, size, len, "%s%s=%s", k > first_key ? ", " : "", a->keys[k].key,
                         fb_study_sweep_case_value(a->study, i, k));
  }
}
