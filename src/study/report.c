/* SPDX-License-Identifier: BSD-3-Clause */
/* The data of a run's report (flexbond/study.h): the runs, their
 * comparisons and the findings a report states, decided here once so that
 * every front end states the same. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/hull_source.h"
#include "flexbond/study.h"

enum { NCMP = 2 }; /* FB_STUDY_CMP_SYSTEM2, FB_STUDY_CMP_CONVERGED */

struct fb_study_report {
  const fb_scenario *s; /* borrowed */
  fb_study_run runs[2];
  size_t nruns;
  fb_study_run converged;
  int has_converged;
  double window[2];
  fb_output_cmp *cmp[NCMP]; /* s->noutputs each, owned; NULL when not compared */
  fb_result *diff[NCMP];    /* owned; NULL when not compared */
};

/* System 1 against other (System 2 on either mesh) into comparison kind. */
static int compare_with(fb_study_report *rep, const fb_study_run *other, fb_study_cmp_kind kind,
                        fb_err *err)
{
  const size_t n = rep->s->noutputs;
  rep->cmp[kind] = calloc(n ? n : 1, sizeof *rep->cmp[kind]);
  if (!rep->cmp[kind])
    return fb_err_set(err, FB_ENOMEM, "out of memory for a report's comparison");
  return fb_study_compare(rep->s, rep->runs[0].res, other->res, rep->runs[0].sum, other->sum,
                          rep->cmp[kind], &rep->diff[kind], err);
}

int fb_study_report_new(const fb_scenario *s, const fb_study_run *runs, size_t nruns,
                        const fb_study_run *converged, fb_study_report **out, fb_err *err)
{
  *out = NULL;
  if (!s || !runs || nruns < 1 || nruns > 2 || (converged && nruns != 2))
    return fb_err_set(err, FB_EINVAL,
                      "fb_study_report_new: one or two runs, a converged one only with two");
  fb_study_report *rep = calloc(1, sizeof *rep);
  if (!rep)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a report");
  rep->s = s;
  rep->nruns = nruns;
  memcpy(rep->runs, runs, nruns * sizeof *runs);
  if (converged) {
    rep->converged = *converged;
    rep->has_converged = 1;
  }
  fb_run_summary_window(runs[0].sum, rep->window);
  int rc = nruns == 2 ? compare_with(rep, &rep->runs[1], FB_STUDY_CMP_SYSTEM2, err) : FB_OK;
  if (rc == FB_OK && converged)
    rc = compare_with(rep, converged, FB_STUDY_CMP_CONVERGED, err);
  if (rc != FB_OK) {
    fb_study_report_free(&rep);
    return rc;
  }
  *out = rep;
  return FB_OK;
}

void fb_study_report_free(fb_study_report **rep)
{
  if (!rep || !*rep)
    return;
  for (size_t i = 0; i < NCMP; ++i) {
    free((*rep)->cmp[i]);
    fb_result_free(&(*rep)->diff[i]);
  }
  free(*rep);
  *rep = NULL;
}

const fb_scenario *fb_study_report_scenario(const fb_study_report *rep)
{
  return rep->s;
}

size_t fb_study_report_nruns(const fb_study_report *rep)
{
  return rep->nruns;
}

const fb_study_run *fb_study_report_run(const fb_study_report *rep, size_t i)
{
  return i < rep->nruns ? &rep->runs[i] : NULL;
}

const fb_study_run *fb_study_report_converged(const fb_study_report *rep)
{
  return rep->has_converged ? &rep->converged : NULL;
}

void fb_study_report_window(const fb_study_report *rep, double window[2])
{
  window[0] = rep->window[0];
  window[1] = rep->window[1];
}

void fb_study_report_wheel_window(const fb_study_report *rep, size_t c, double window[2])
{
  window[0] = fb_scenario_road_entry(rep->s, (int)c);
  window[1] = fb_scenario_road_exit(rep->s, (int)c);
}

const char *fb_study_report_unit(const fb_study_report *rep, size_t k)
{
  return fb_result_col_unit(rep->runs[0].res, fb_run_summary_column(rep->runs[0].sum, k));
}

size_t fb_study_report_tires_with(const fb_study_report *rep, const fb_tire_model *m)
{
  size_t n = 0;
  for (size_t c = 0; c < rep->s->ncorners; ++c)
    n += fb_corner_tire_model(&rep->s->corner[c]) == m;
  return n;
}

const fb_output_cmp *fb_study_report_cmp(const fb_study_report *rep, fb_study_cmp_kind kind)
{
  return (unsigned)kind < NCMP ? rep->cmp[kind] : NULL;
}

const fb_result *fb_study_report_diff(const fb_study_report *rep, fb_study_cmp_kind kind)
{
  return (unsigned)kind < NCMP ? rep->diff[kind] : NULL;
}

/* ---- Findings. */

int fb_study_mesh_error(const fb_scenario *s, double band[2])
{
  const int density = s->has_fe_hull ? fb_scenario_hull_density(s) : 0;
  if (density < 1) /* a mesh used as it is: nothing refines it */
    return 0;
  const double d2 = (double)density * (double)density;
  band[0] = FB_STUDY_MESH_ERROR_LOW / d2;
  band[1] = FB_STUDY_MESH_ERROR_HIGH / d2;
  return 1;
}

/* rel_diff of a varying output (System 1's range not 0) is finite. */
static int notable(const fb_output_cmp *c)
{
  return isfinite(c->rel_diff) && c->rel_diff > FB_STUDY_NOTABLE_DIFF;
}

fb_study_differences fb_study_report_differences(const fb_study_report *rep,
                                                 fb_study_cmp_kind kind)
{
  const size_t n = rep->s->noutputs;
  fb_study_differences d = {n, 0, 0};
  const fb_output_cmp *cmp = fb_study_report_cmp(rep, kind);
  for (size_t k = 0; cmp && k < n; ++k) {
    const double r = cmp[k].rel_diff;
    if (!isfinite(r))
      continue;
    ++d.nvarying;
    d.nnotable += r > FB_STUDY_NOTABLE_DIFF;
    if (d.largest == n || r > cmp[d.largest].rel_diff)
      d.largest = k;
  }
  return d;
}

int fb_study_report_notable(const fb_study_report *rep, fb_study_cmp_kind kind, size_t k)
{
  const fb_output_cmp *cmp = fb_study_report_cmp(rep, kind);
  return cmp && k < rep->s->noutputs && notable(&cmp[k]);
}

size_t fb_study_report_largest_rms_change(const fb_study_report *rep)
{
  const size_t n = rep->s->noutputs;
  const fb_output_cmp *cmp = rep->cmp[FB_STUDY_CMP_SYSTEM2];
  size_t largest = n;
  for (size_t k = 0; cmp && k < n; ++k) {
    const double r = cmp[k].rms_change;
    if (isfinite(r) && (largest == n || fabs(r) > fabs(cmp[largest].rms_change)))
      largest = k;
  }
  return largest;
}

size_t fb_study_report_mesh_crossings(const fb_study_report *rep)
{
  const fb_output_cmp *c1 = rep->cmp[FB_STUDY_CMP_SYSTEM2],
                      *c3 = rep->cmp[FB_STUDY_CMP_CONVERGED];
  size_t changed = 0;
  /* An output that does not vary on the first mesh crosses no line. */
  for (size_t k = 0; c1 && c3 && k < rep->s->noutputs; ++k)
    changed += isfinite(c1[k].rel_diff) && (c1[k].rel_diff > FB_STUDY_NOTABLE_DIFF) !=
                                               (c3[k].rel_diff > FB_STUDY_NOTABLE_DIFF);
  return changed;
}

double fb_study_report_mesh_diff(const fb_study_report *rep, size_t k)
{
  const fb_result *a = rep->diff[FB_STUDY_CMP_CONVERGED], *b = rep->diff[FB_STUDY_CMP_SYSTEM2];
  if (!a || !b || k >= rep->s->noutputs || !(rep->cmp[FB_STUDY_CMP_SYSTEM2][k].range1 > 0))
    return NAN;
  /* Both differences have System 1's columns and samples. */
  const size_t col = fb_run_summary_column(rep->runs[0].sum, k);
  double m = 0;
  for (size_t i = 0; i < fb_result_nsamples(a) && i < fb_result_nsamples(b); ++i)
    if (fb_result_row(a, i)[0] >= rep->window[0])
      m = fmax(m, fabs(fb_result_row(a, i)[col] - fb_result_row(b, i)[col]));
  return m / rep->cmp[FB_STUDY_CMP_SYSTEM2][k].range1;
}

size_t fb_study_report_torsion_output(const fb_study_report *rep)
{
  size_t k = 0;
  while (k < rep->s->noutputs && strcmp(rep->s->output[k].signal, "torsion") != 0)
    ++k;
  return k;
}

double fb_study_run_max_abs(const fb_study_run *r, size_t k)
{
  const size_t col = fb_run_summary_column(r->sum, k);
  double m = 0;
  for (size_t i = 0; col > 0 && i < fb_result_nsamples(r->res); ++i)
    m = fmax(m, fabs(fb_result_row(r->res, i)[col]));
  return m;
}

double fb_study_run_worst_basis_error(const fb_study_run *r, size_t noutputs, size_t *k)
{
  size_t worst = 0;
  for (size_t j = 1; r->basis_error && j < noutputs; ++j)
    if (r->basis_error[j] > r->basis_error[worst])
      worst = j;
  if (k)
    *k = worst;
  /* fmax passes over a NaN error (an output that does not vary). */
  double m = r->basis_error ? 0.0 : NAN;
  for (size_t j = 0; r->basis_error && j < noutputs; ++j)
    m = fmax(m, r->basis_error[j]);
  return m;
}

size_t fb_study_report_largest_growth(const fb_study_report *rep, double *factor)
{
  const size_t n = rep->s->noutputs;
  size_t largest = n;
  double best = 0;
  for (size_t k = 0; k < n; ++k) {
    const fb_output_stats *st = fb_run_summary_output(rep->runs[0].sum, k);
    const double f = st->static_value != 0 ? st->peak / st->static_value : NAN;
    if (fabs(st->static_value) >= FB_STUDY_NOTABLE_DIFF * (st->peak - st->min) && isfinite(f) &&
        f > 1.0 && f > best) {
      best = f;
      largest = k;
    }
  }
  if (factor)
    *factor = best;
  return largest;
}

void fb_study_report_contact_extremes(const fb_study_report *rep, const fb_study_run *r,
                                      size_t *c_ratio, size_t *c_min)
{
  size_t most = 0, least = 0;
  for (size_t c = 1; c < rep->s->ncorners; ++c) {
    /* A NaN ratio (no static reaction) never wins. */
    if (fb_run_summary_contact_ratio(r->sum, c) > fb_run_summary_contact_ratio(r->sum, most))
      most = c;
    if (fb_run_summary_contact(r->sum, c)->min < fb_run_summary_contact(r->sum, least)->min)
      least = c;
  }
  if (c_ratio)
    *c_ratio = most;
  if (c_min)
    *c_min = least;
}
