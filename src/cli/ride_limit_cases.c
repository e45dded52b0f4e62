/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond ride-limit's cases (ride_limit.h): a round of the search's
 * points run as sweeps (fb_study_sweep: its thread pool, its interruption,
 * each case's scenario read with the --vary value, the speed and the
 * run's end as overrides), and the journal of finished cases,
 * DIR/ride_limit.partial.csv, that --resume reads back. The search is
 * deterministic, so a resumed study asks for the same points again and
 * finds the journaled ones there without running them. */
#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../core/textfile.h"
#include "../core/util.h"
#include "cli.h"
#include "ride_limit.h"
#include "sweep.h"

/* The run's end a case is read with, s: beyond any feature, so that the
 * reader's "bump inside the run" check holds at every speed; the case's
 * own end is then set by fb_study_ride_limit_duration. */
static const char LOAD_T_END[] = "3600";

size_t rl_ncurves(const rl_args *a)
{
  return a->nsystems * a->nvalues;
}

/* ---- A round: the cases of one system, run as one sweep. */

typedef struct rl_round {
  rl_args *a;
  int sys;             /* index into a->systems */
  const size_t *value; /* each case's --vary value (the round's cases) */
  const double *speed; /* each case's speed, m/s */
  double *metric;      /* each case's measured metric */
  fb_study_sweep *sw;  /* the round's sweep */
} rl_round;

/* Case i's scenario: the file with the --vary value, the speed and a far
 * run's end as overrides, then the run's end of fb_study_ride_limit_duration. */
static int load_case(void *ctx, size_t i, const fb_scenario_override *ov, size_t n,
                     fb_scenario **out, fb_err *err)
{
  const rl_round *r = ctx;
  (void)n;
  char vary_label[1024], speed[32], speed_label[64];
  snprintf(vary_label, sizeof vary_label, "--vary %s=%s", r->a->vary_key, ov[0].value);
  snprintf(speed, sizeof speed, "%.17g", r->speed[i] * 3.6);
  snprintf(speed_label, sizeof speed_label, "at %.4g km/h", r->speed[i] * 3.6);
  const fb_scenario_override all[3] = {
      {.key = ov[0].key, .value = ov[0].value, .label = vary_label},
      {.key = "road.speed_kmh", .value = speed, .label = speed_label},
      {.key = "simulation.t_end",
       .value = LOAD_T_END,
       .label = "(t_end as ride-limit sets it)"}};
  int rc = fb_scenario_load_overrides(r->a->scenario_path, all, 3, out, err);
  if (rc == FB_OK)
    rc = fb_study_ride_limit_duration(*out, r->a->course_length, r->a->settle, err);
  return rc;
}

int rl_check_values(rl_args *a, fb_err *err)
{
  const double lo = a->opts.v_lo;
  for (size_t v = 0; v < a->nvalues; ++v) {
    rl_round r = {a, 0, &v, &lo, NULL, NULL};
    const fb_scenario_override ov = {.key = a->vary_path, .value = a->values[v]};
    fb_scenario *s = NULL;
    const int rc = load_case(&r, 0, &ov, 1, &s, err);
    fb_scenario_free(&s);
    if (rc != FB_OK)
      return rc;
  }
  return FB_OK;
}

static int measure_case(void *ctx, size_t i, const fb_scenario *s, const fb_result *res,
                        fb_err *err)
{
  const rl_round *r = ctx;
  return fb_study_ride_limit_measure(s, res, r->a->output, r->a->metric, &r->metric[i], err);
}

/* The journal's row of a finished case, flushed at once: a killed study
 * loses only the cases it was running. A message is one line (the
 * library's messages are; a line break would be replaced). */
static int journal_append(rl_args *a, const rl_done *d, fb_err *err)
{
  if (!a->journal || a->journal_failed)
    return FB_OK;
  char metric[32];
  sweep_format_double(d->metric, metric, sizeof metric);
  fprintf(a->journal, "%d,%zu,%.17g,%d,%s,", d->sys, d->value, d->speed, d->status,
          isnan(d->metric) ? "nan" : metric);
  for (const char *p = d->error ? d->error : ""; *p; ++p)
    fputc(*p == '\n' || *p == '\r' ? ' ' : *p, a->journal);
  fputc('\n', a->journal);
  if (fflush(a->journal) != 0 || ferror(a->journal)) {
    a->journal_failed = 1;
    return fb_err_set(err, FB_EIO, "cannot write the journal in %s: %s", a->out_dir,
                      strerror(errno));
  }
  return FB_OK;
}

/* Appends a finished case to a->done (error copied). */
static int add_done(rl_args *a, const rl_done *d, fb_err *err)
{
  if (fb_grow((void **)&a->done, &a->cap_done, a->ndone, sizeof *a->done) != 0)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu cases", a->ndone + 1);
  a->done[a->ndone] = *d;
  a->done[a->ndone].error = d->error ? fb_strdup(d->error) : NULL;
  ++a->ndone;
  return FB_OK;
}

int rl_record(rl_args *a, const rl_done *d, int rank, fb_err *err)
{
  pthread_mutex_lock(&a->lock);
  int rc = add_done(a, d, err);
  if (rc == FB_OK)
    rc = journal_append(a, d, err);
  ++a->nrun;
  if (!a->quiet) {
    char where[32] = "";
    if (rank >= 0)
      snprintf(where, sizeof where, " on rank %d", rank);
    const char *system = cli_system_label(a->systems[d->sys]);
    if (d->status == FB_OK)
      cli_say("flexbond ride-limit: %s, %s=%s, %.4g km/h: %s = %.6g%s, %.3g s", system,
              a->vary_key, a->values[d->value], d->speed * 3.6,
              fb_study_ride_limit_metric_name(a->metric), d->metric, where, d->wall_seconds);
    else
      cli_say("flexbond ride-limit: %s, %s=%s, %.4g km/h: failed%s: %s", system, a->vary_key,
              a->values[d->value], d->speed * 3.6, where,
              d->error ? d->error : "out of memory");
  }
  pthread_mutex_unlock(&a->lock);
  return rc;
}

/* Under the sweep's lock: the case is recorded (rl_record). */
static int case_finished(void *ctx, size_t i, fb_err *err)
{
  rl_round *r = ctx;
  fb_study_sweep_case c;
  fb_study_sweep_case_get(r->sw, i, &c);
  const rl_done d = {.sys = r->sys,
                     .value = r->value[i],
                     .speed = r->speed[i],
                     .status = c.status,
                     .metric = c.status == FB_OK ? r->metric[i] : NAN,
                     .wall_seconds = c.wall_seconds,
                     .error = c.status == FB_OK ? NULL : (char *)c.error};
  return rl_record(r->a, &d, r->a->mpi_size > 0 ? 0 : -1, err);
}

const rl_done *rl_find_done(const rl_args *a, int sys, size_t v, double speed)
{
  for (size_t i = 0; i < a->ndone; ++i)
    if (a->done[i].sys == sys && a->done[i].value == v && a->done[i].speed == speed)
      return &a->done[i];
  return NULL;
}

/* Runs the n cases of system sys (values value[], speeds speed[]) as one
 * sweep on a->jobs threads. */
int rl_run_round(rl_args *a, int sys, const size_t *value, const double *speed, size_t n,
                 fb_err *err)
{
  double *metric = malloc(n * sizeof *metric);
  const char **texts = malloc(n * sizeof *texts);
  if (!metric || !texts) {
    free(metric);
    free(texts);
    return fb_err_set(err, FB_ENOMEM, "out of memory for %zu cases", n);
  }
  for (size_t i = 0; i < n; ++i) {
    metric[i] = NAN;
    texts[i] = a->values[value[i]];
  }
  rl_round r = {a, sys, value, speed, metric, NULL};
  const fb_study_sweep_axis axis = {.key = a->vary_path, .values = texts, .nvalues = n};
  const fb_study_sweep_ops ops = {.load = load_case,
                                  .locate = sweep_locate_case,
                                  .stop = sweep_interrupted,
                                  .finished = case_finished,
                                  .measure = measure_case,
                                  .ctx = &r};
  int rc = fb_study_sweep_new(a->base, a->systems[sys], &axis, 1, &ops, &r.sw, err);
  if (rc == FB_OK)
    rc = fb_study_sweep_run(r.sw, a->jobs, err);
  if (rc == FB_OK || rc == FB_EINTR)
    rc = cli_check_interrupt(err) != FB_OK ? FB_EINTR : rc;
  fb_study_sweep_free(&r.sw);
  free(metric);
  free(texts);
  return rc;
}

/* The points of system sys not yet done into value[], speed[]; their count. */
static size_t points_to_run(const rl_args *a, int sys, const fb_study_ride_limit_point *pts,
                            size_t n, size_t *value, double *speed)
{
  size_t m = 0;
  for (size_t p = 0; p < n; ++p) {
    const size_t v = pts[p].curve % a->nvalues;
    if ((int)(pts[p].curve / a->nvalues) == sys && !rl_find_done(a, sys, v, pts[p].speed)) {
      value[m] = v;
      speed[m++] = pts[p].speed;
    }
  }
  return m;
}

/* A curve's first failure message, kept for ride_limit.csv. */
static void note_failure(rl_args *a, size_t curve, const rl_done *d)
{
  if (a->curve_error[curve])
    return;
  char text[FB_ERR_MSG_MAX + 64];
  snprintf(text, sizeof text, "at %.4g km/h: %s", d->speed * 3.6,
           d->error ? d->error
                    : "the metric is not defined (a window shorter than it needs, or "
                      "absorbed power without a K(f) table)");
  a->curve_error[curve] = fb_strdup(text);
}

/* The points of every system not yet done into sys[], value[], speed[];
 * their count. */
static size_t all_points_to_run(const rl_args *a, const fb_study_ride_limit_point *pts,
                                size_t n, int *sys, size_t *value, double *speed)
{
  size_t m = 0;
  for (size_t s = 0; s < a->nsystems; ++s) {
    const size_t k = points_to_run(a, (int)s, pts, n, value + m, speed + m);
    for (size_t i = 0; i < k; ++i)
      sys[m + i] = (int)s;
    m += k;
  }
  return m;
}

/* Runs the round's points not yet done: each system's as one sweep on
 * threads, or all of them across the ranks of an MPI job. */
static int run_points(rl_args *a, const fb_study_ride_limit_point *pts, size_t n, int *sys,
                      size_t *value, double *speed, fb_err *err)
{
  const size_t m = all_points_to_run(a, pts, n, sys, value, speed);
  if (m > 0 && !a->quiet)
    cli_say("flexbond ride-limit: %zu run%s", m, m == 1 ? "" : "s");
  if (a->mpi_round)
    return m > 0 ? a->mpi_round(a, sys, value, speed, m, err) : FB_OK;
  int rc = FB_OK;
  for (size_t i = 0; rc == FB_OK && i < m;) {
    size_t j = i;
    while (j < m && sys[j] == sys[i])
      ++j;
    rc = rl_run_round(a, sys[i], value + i, speed + i, j - i, err);
    i = j;
  }
  return rc;
}

int rl_eval(void *ctx, const fb_study_ride_limit_point *pts, size_t n, double *metric,
            fb_err *err)
{
  rl_args *a = ctx;
  size_t *value = malloc((n ? n : 1) * sizeof *value);
  double *speed = malloc((n ? n : 1) * sizeof *speed);
  int *sys = malloc((n ? n : 1) * sizeof *sys);
  int rc = value && speed && sys ? run_points(a, pts, n, sys, value, speed, err)
                                 : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t p = 0; rc == FB_OK && p < n; ++p) {
    const size_t curve = pts[p].curve;
    const rl_done *d =
        rl_find_done(a, (int)(curve / a->nvalues), curve % a->nvalues, pts[p].speed);
    metric[p] = d && d->status == FB_OK ? d->metric : NAN;
    if (d && isnan(metric[p]))
      note_failure(a, curve, d);
    if (!d) /* a case the sweep did not finish: stopped */
      rc = fb_err_set(err, FB_EINTR, "ride-limit: stopped with cases not run");
  }
  free(value);
  free(speed);
  free(sys);
  return rc;
}

/* ---- The journal. */

char *rl_journal_path(const rl_args *a)
{
  return fb_path_join(a->out_dir, "ride_limit.partial.csv");
}

/* The study's fingerprint: flexbond's version, the scenario file's bytes
 * and every setting that changes a case or the search's points. */
static int fingerprint(const rl_args *a, uint64_t *h, fb_err *err)
{
  char *text = NULL;
  size_t len = 0;
  const int rc = fb_read_file(a->scenario_path, &text, &len, err);
  if (rc != FB_OK)
    return rc;
  uint64_t f = sweep_fnv1a(UINT64_C(14695981039346656037), "flexbond " CLI_VERSION,
                           strlen("flexbond " CLI_VERSION) + 1);
  f = sweep_fnv1a(f, text, len);
  free(text);
  char line[256];
  snprintf(line, sizeof line, "%s|%s|%.17g|%.17g|%.17g|%.17g|%.17g|%zu|%.17g|%.17g|%zu",
           fb_study_ride_limit_metric_name(a->metric), a->base->output[a->output].name,
           a->opts.limit, a->opts.v_lo, a->opts.v_hi, a->opts.coarse_step, a->opts.tol,
           a->opts.refine_points, a->course_length, a->settle, a->nsystems);
  f = sweep_fnv1a(f, line, strlen(line) + 1);
  for (size_t s = 0; s < a->nsystems; ++s)
    f = sweep_fnv1a(f, &a->systems[s], sizeof a->systems[s]);
  f = sweep_fnv1a(f, a->vary_path, strlen(a->vary_path) + 1);
  for (size_t v = 0; v < a->nvalues; ++v)
    f = sweep_fnv1a(f, a->values[v], strlen(a->values[v]) + 1);
  *h = f;
  return FB_OK;
}

/* The whole number at *p up to the next ',' (moved past it), into *out;
 * 0 when there is none or it runs into anything else. */
static int journal_whole(char **p, long long *out)
{
  char *end = NULL;
  errno = 0;
  *out = strtoll(*p, &end, 10);
  if (end == *p || *end != ',' || errno)
    return 0;
  *p = end + 1;
  return 1;
}

/* One journal row into d (error in fresh memory); 0 if it is malformed
 * (a row cut short by a kill: ignored). Fields: system, value, speed
 * (m/s), status, metric ("nan" when not defined), then the error's text
 * to the end of the line. */
static int parse_row(const rl_args *a, char *line, rl_done *d)
{
  char *p = line, *end = NULL;
  long long sys = 0, value = 0, status = 0;
  if (!journal_whole(&p, &sys) || !journal_whole(&p, &value))
    return 0;
  d->speed = strtod(p, &end);
  if (end == p || *end != ',')
    return 0;
  p = end + 1;
  if (!journal_whole(&p, &status))
    return 0;
  char *comma = strchr(p, ',');
  if (!comma || sys < 0 || (size_t)sys >= a->nsystems || value < 0 ||
      (size_t)value >= a->nvalues || status < INT_MIN || status > INT_MAX)
    return 0;
  *comma = '\0';
  d->metric = strcmp(p, "nan") != 0 ? strtod(p, &end) : NAN;
  if (strcmp(p, "nan") != 0 && (end == p || *end))
    return 0;
  d->sys = (int)sys;
  d->value = (size_t)value;
  d->status = (int)status;
  d->wall_seconds = NAN;
  d->error = comma[1] ? fb_strdup(comma + 1) : NULL;
  return 1;
}

/* Reads an existing journal back into a->done; FB_EINVAL when it is of
 * another study. */
static int read_back(rl_args *a, const char *path, uint64_t h, fb_err *err)
{
  char *text = NULL;
  size_t len = 0;
  int rc = fb_read_file(path, &text, &len, err);
  if (rc != FB_OK)
    return rc;
  char head[64];
  snprintf(head, sizeof head, "# flexbond ride-limit journal %016" PRIx64, h);
  if (strncmp(text, head, strlen(head)) != 0) {
    free(text);
    return fb_err_set(err, FB_EINVAL,
                      "%s is the journal of another study (another scenario file or other "
                      "options): remove it, or give the options it was made with",
                      path);
  }
  size_t pos = 0;
  char *line = NULL;
  fb_text_split_line(text, len, &pos, &line); /* the header */
  while (rc == FB_OK && pos < len) {
    const size_t start = pos;
    fb_text_split_line(text, len, &pos, &line);
    rl_done d;
    /* A last row without its line break was cut short by a kill. */
    const int whole = pos <= len && pos > start && text[pos - 1] == '\0';
    if (whole && parse_row(a, line, &d)) {
      rc = add_done(a, &d, err);
      free(d.error);
    }
  }
  free(text);
  a->nresumed = a->ndone;
  return rc;
}

int rl_journal_open(rl_args *a, fb_err *err)
{
  uint64_t h = 0;
  int rc = fingerprint(a, &h, err);
  char *path = rc == FB_OK ? rl_journal_path(a) : NULL;
  if (rc == FB_OK && !path)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  FILE *old = rc == FB_OK ? fopen(path, "r") : NULL;
  if (old) {
    fclose(old);
    rc = a->resume ? read_back(a, path, h, err)
                   : fb_err_set(err, FB_EINVAL,
                                "%s holds an unfinished study: run the same command with "
                                "--resume to finish it, or remove the file",
                                path);
  }
  if (rc == FB_OK && !(a->journal = fopen(path, "a")))
    rc = fb_err_set(err, FB_EIO, "cannot write %s: %s", path, strerror(errno));
  if (rc == FB_OK && !old) {
    fprintf(a->journal, "# flexbond ride-limit journal %016" PRIx64 "\n", h);
    if (fflush(a->journal) != 0)
      rc = fb_err_set(err, FB_EIO, "cannot write %s: %s", path, strerror(errno));
  }
  free(path);
  return rc;
}

void rl_journal_close(rl_args *a, int remove_file)
{
  if (a->journal)
    fclose(a->journal);
  a->journal = NULL;
  char *path = remove_file ? rl_journal_path(a) : NULL;
  if (path)
    remove(path);
  free(path);
}
