/* flexbond sweep: a parameter study of a vehicle scenario (docs/sweep.md).
 * Every --set KEY=SPEC gives a key of the scenario file and its values;
 * the cases are their cartesian product. Each case loads the scenario
 * with its values replacing the file's (fb_scenario_load_overrides, so
 * the reader checks and converts them as its own), simulates one system
 * and reduces the run to metrics: the summary.json statistics of the
 * paper's seven outputs (cli_output_stats_of), the tire contact, the
 * driver's ride metrics and the solver's work. The cases run on a pool of POSIX threads; the
 * library keeps no global state, except that ARPACK (fb_fem_modes above 2000 DOFs) is not
 * reentrant, so System 2 hulls that large run one at a time. A case that fails leaves its
 * message in the `error` column and the others go on. DIR/sweep.csv and DIR/sweep.png are
 * written at the end, all or nothing. */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "flexbond/fem.h"
#include "flexbond/io.h"
#include "flexbond/ride.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "cli.h"

static const char sweep_usage[] =
    "usage: flexbond sweep SCENARIO.yaml --set KEY=SPEC [--set KEY=SPEC ...] -o DIR\n"
    "                      [--system rigid|flexible] [-j N] [--no-figures] [-q]\n"
    "\n"
    "Simulates the scenario once per combination of the values given by the\n"
    "--set options (their cartesian product, the first key varying slowest) and\n"
    "writes, once every case has run (docs/sweep.md):\n"
    "  DIR/sweep.csv   one row per case: the keys' values, then the metrics (peak,\n"
    "                  min and RMS of the paper's seven outputs as in summary.json,\n"
    "                  the smallest tire reaction, the contact-loss intervals, the\n"
    "                  driver's ride metrics, the solver's steps and time) and\n"
    "                  an `error` column\n"
    "  DIR/sweep.png   one panel per metric against the first key, one curve per\n"
    "                  combination of the other keys\n"
    "A case that fails does not stop the others; the exit status is then 4.\n"
    "\n"
    "  --set KEY=SPEC   KEY: a dotted path into the scenario (road.speed_kmh,\n"
    "                   suspensions.LF.spring_k, hull.mesh.generator.bulkheads[1])\n"
    "                   or a key name that occurs once in it (speed_kmh);\n"
    "                   SPEC: start:step:stop (stop included, to step/1e9; at most\n"
    "                   10000 values) or a list v1,v2,... (numbers, expressions or\n"
    "                   words such as zero,static); repeat for a grid\n"
    "  -o, --output DIR           output directory (required)\n"
    "  --system rigid|flexible    hull model (default rigid: System 1)\n"
    "  -j, --jobs N               cases run at once (default: the online CPUs)\n"
    "  --no-figures               no sweep.png\n"
    "  -q, --quiet                no progress lines on stderr\n"
    "  -h, --help                 this text\n";

/* Limits of a study: values per key (as the spec says), keys, cases. */
enum { SWEEP_MAX_VALUES = 10000, SWEEP_MAX_KEYS = 16, SWEEP_MAX_CASES = 100000 };
/* Most threads -j accepts. */
enum { SWEEP_MAX_JOBS = 1024 };
/* fb_fem_modes uses ARPACK above this many DOFs (the dense_limit that
 * src/vehicle/fe_hull.c and src/fem/reduce.c pass): such hulls run one
 * at a time. */
enum { SWEEP_DENSE_LIMIT = 2000 };

/* ---- Metrics of a case. */

enum {
  STAT_PEAK,
  STAT_MIN,
  STAT_RMS,
  NSTATS,
  /* peak, min, rms of output k at NSTATS k + STAT_* */
  M_MIN_TIRE_FORCE = NSTATS * FB_NOUTPUTS,
  M_CONTACT_LOSS_INTERVALS,
  /* The driver's ride metrics, as summary.json's "ride" (run.c). */
  M_RIDE_A_W_RMS,
  M_RIDE_MTVV,
  M_RIDE_VDV,
  M_RIDE_CREST_FACTOR,
  M_RIDE_JERK_PEAK,
  M_RIDE_JERK_RMS,
  M_SOLVER_STEPS,
  M_SOLVER_WALL_TIME,
  NMETRICS
};
static const char *const stat_names[NSTATS] = {"peak", "min", "rms"};
static const struct {
  const char *name, *unit;
} other_metrics[NMETRICS - M_MIN_TIRE_FORCE] = {
    {"min_tire_force", "N"},     {"contact_loss_intervals", "-"}, {"ride_a_w_rms", "m/s^2"},
    {"ride_mtvv", "m/s^2"},      {"ride_vdv", "m/s^1.75"},        {"ride_crest_factor", "-"},
    {"ride_jerk_peak", "m/s^3"}, {"ride_jerk_rms", "m/s^3"},      {"solver_steps", "-"},
    {"solver_wall_time", "s"},
};

/* Name of metric m ("tire_force_LF_peak") into buf. */
static void metric_name(size_t m, char *buf, size_t size)
{
  if (m < M_MIN_TIRE_FORCE)
    snprintf(buf, size, "%s_%s", fb_vehicle_output_name((int)(m / NSTATS)),
             stat_names[m % NSTATS]);
  else
    snprintf(buf, size, "%s", other_metrics[m - M_MIN_TIRE_FORCE].name);
}

static const char *metric_unit(size_t m)
{
  return m < M_MIN_TIRE_FORCE ? fb_vehicle_output_unit((int)(m / NSTATS))
                              : other_metrics[m - M_MIN_TIRE_FORCE].unit;
}

/* ---- The study. */

/* One swept key and its values (texts, as the overrides take them). */
typedef struct sweep_key {
  const char *key; /* as given */
  char *path;      /* the full dotted path it names */
  char **values;
  size_t nvalues;
} sweep_key;

/* The outcome of one case. */
typedef struct sweep_case {
  int status;              /* FB_OK or what failed */
  char *error;             /* its message (NULL when ok or out of memory) */
  double metric[NMETRICS]; /* NaN when failed */
} sweep_case;

typedef struct sweep_args {
  const char *scenario_path, *out_dir;
  fb_system sys;
  size_t jobs;
  int quiet, figures;
  sweep_key keys[SWEEP_MAX_KEYS];
  size_t nkeys, ncases;
  const char *scenario_name; /* for titles */
} sweep_args;

/* What the worker threads share. */
typedef struct sweep_pool {
  const sweep_args *a;
  sweep_case *cases;
  pthread_mutex_t lock;   /* next, done and stderr */
  pthread_mutex_t arpack; /* held while a large System 2 hull runs */
  size_t next, done;
} sweep_pool;

/* Index of key k's value in case i: the first key varies slowest. */
static size_t value_index(const sweep_args *a, size_t i, size_t k)
{
  for (size_t j = a->nkeys; j-- > k + 1;)
    i /= a->keys[j].nvalues;
  return i % a->keys[k].nvalues;
}

/* "key=value, key=value" of case i into buf. */
static void case_label(const sweep_args *a, size_t i, size_t first_key, char *buf, size_t size)
{
  size_t len = 0;
  buf[0] = '\0';
  for (size_t k = first_key; k < a->nkeys && len + 1 < size; ++k) {
    int n = snprintf(buf + len, size - len, "%s%s=%s", k > first_key ? ", " : "",
                     a->keys[k].key, a->keys[k].values[value_index(a, i, k)]);
    len = n > 0 && len + (size_t)n < size ? len + (size_t)n : size - 1;
  }
}

/* [first wheel's bump entry, last wheel's bump exit], as run's. */
static void bump_window(const fb_scenario *s, double window[2])
{
  window[0] = INFINITY;
  window[1] = -INFINITY;
  for (int c = 0; c < FB_NCORNERS; ++c) {
    window[0] = fmin(window[0], fb_scenario_bump_entry(s, c));
    window[1] = fmax(window[1], fb_scenario_bump_exit(s, c));
  }
}

/* The smallest normal reaction of any tire from the first bump entry to
 * the end of the run (not from t = 0: under `initial: zero` every tire
 * starts unloaded, at 0 N). */
static int min_tire_force(const fb_result *r, const double window[2], double *out, fb_err *err)
{
  *out = INFINITY;
  for (int c = 0; c < FB_NCORNERS; ++c) {
    char name[32];
    snprintf(name, sizeof name, "contact_force_%s", fb_corner_name(c));
    const long j = fb_result_find(r, name);
    if (j < 1)
      return fb_err_set(err, FB_EINVAL, "sweep: the result has no output '%s'", name);
    for (size_t k = 0; k < fb_result_nsamples(r); ++k) {
      const double *row = fb_result_row(r, k);
      if (row[0] >= window[0])
        *out = fmin(*out, row[j]);
    }
  }
  return FB_OK;
}

/* The contact-loss intervals (fb_vehicle_contact_loss) that end after
 * the first bump entry. */
static int contact_loss_intervals(const fb_result *r, const double window[2], double *out,
                                  fb_err *err)
{
  fb_contact_loss *iv = NULL;
  size_t n = 0, count = 0;
  int rc = fb_vehicle_contact_loss(r, &iv, &n, err);
  for (size_t i = 0; rc == FB_OK && i < n; ++i)
    count += iv[i].t_end >= window[0];
  free(iv);
  *out = (double)count;
  return rc;
}

/* The driver's ride metrics (flexbond/ride.h, default options) over
 * [first bump entry, end of the run], as run puts them in summary.json;
 * NaN when the library refuses the window (shorter than the 1 s running
 * r.m.s.): a missing metric, not a failed case. */
static void ride_metrics(const fb_result *r, const double window[2], double *m)
{
  for (size_t k = M_RIDE_A_W_RMS; k <= M_RIDE_JERK_RMS; ++k)
    m[k] = NAN;
  const size_t n = fb_result_nsamples(r);
  if (n < 2)
    return;
  const double t_first = fb_result_row(r, 0)[0], t_last = fb_result_row(r, n - 1)[0];
  /* The last sample stands for one sampling interval (ride.h). */
  const double t0 = fmax(window[0], t_first),
               t1 = t_last + (t_last - t_first) / (double)(n - 1);
  fb_ride_opts opts;
  fb_ride_opts_default(&opts);
  fb_ride_metrics ride;
  fb_err err;
  if (fb_ride_metrics_result(r, "driver_acc", t0, t1, &opts, &ride, &err) != FB_OK)
    return;
  m[M_RIDE_A_W_RMS] = ride.a_w_rms;
  m[M_RIDE_MTVV] = ride.mtvv;
  m[M_RIDE_VDV] = ride.vdv;
  m[M_RIDE_CREST_FACTOR] = ride.crest;
  m[M_RIDE_JERK_PEAK] = ride.jerk_peak;
  m[M_RIDE_JERK_RMS] = ride.jerk_rms;
}

/* Every metric of a successful run r of scenario s into m. */
static int case_metrics(const fb_scenario *s, const fb_result *r, double *m, fb_err *err)
{
  double window[2];
  bump_window(s, window);
  for (int k = 0; k < FB_NOUTPUTS; ++k) {
    const long j = fb_result_find(r, fb_vehicle_output_name(k));
    if (j < 1)
      return fb_err_set(err, FB_EINVAL, "sweep: the result has no output '%s'",
                        fb_vehicle_output_name(k));
    const cli_output_stats st = cli_output_stats_of(r, (size_t)j, window);
    m[NSTATS * k + STAT_PEAK] = st.peak;
    m[NSTATS * k + STAT_MIN] = st.min;
    m[NSTATS * k + STAT_RMS] = st.rms;
  }
  const fb_sim_stats *st = fb_result_stats(r);
  m[M_SOLVER_STEPS] = (double)st->steps;
  m[M_SOLVER_WALL_TIME] = st->wall_seconds;
  ride_metrics(r, window, m);
  int rc = min_tire_force(r, window, &m[M_MIN_TIRE_FORCE], err);
  if (rc == FB_OK)
    rc = contact_loss_intervals(r, window, &m[M_CONTACT_LOSS_INTERVALS], err);
  return rc;
}

/* 1 in *serial when s's finite-element hull is large enough for ARPACK. */
static int needs_serial(const sweep_args *a, const fb_scenario *s, int *serial, fb_err *err)
{
  *serial = 0;
  if (a->sys != FB_SYSTEM_FLEXIBLE)
    return FB_OK;
  fb_fe_hull *hull = NULL;
  int rc = fb_vehicle_fe_hull(s, &hull, err);
  if (rc == FB_OK)
    *serial = 6 * fb_mesh_nnodes(hull->mesh) > SWEEP_DENSE_LIMIT;
  fb_fe_hull_free(&hull);
  return rc;
}

/* fb_sim_progress_fn: stops a case's simulation once interrupted. */
static int stop_when_interrupted(void *ctx, double t, double t_end)
{
  (void)ctx;
  (void)t;
  (void)t_end;
  return cli_interrupted();
}

static int simulate_case(sweep_pool *p, const fb_scenario *s, fb_result **res, fb_err *err)
{
  int serial = 0;
  int rc = needs_serial(p->a, s, &serial, err);
  if (rc != FB_OK)
    return rc;
  if (serial)
    pthread_mutex_lock(&p->arpack);
  rc = fb_vehicle_simulate_progress(s, p->a->sys, stop_when_interrupted, NULL, res, err);
  if (serial)
    pthread_mutex_unlock(&p->arpack);
  return rc;
}

/* Runs case i into p->cases[i]. */
static void run_case(sweep_pool *p, size_t i)
{
  const sweep_args *a = p->a;
  sweep_case *c = &p->cases[i];
  fb_scenario_override ov[SWEEP_MAX_KEYS];
  for (size_t k = 0; k < a->nkeys; ++k)
    ov[k] = (fb_scenario_override){a->keys[k].key, a->keys[k].values[value_index(a, i, k)]};
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  fb_result *res = NULL;
  int rc = fb_scenario_load_overrides(a->scenario_path, ov, a->nkeys, &s, &err);
  if (rc == FB_OK)
    rc = simulate_case(p, s, &res, &err);
  if (rc == FB_OK)
    rc = case_metrics(s, res, c->metric, &err);
  c->status = rc;
  if (rc != FB_OK) {
    for (size_t m = 0; m < NMETRICS; ++m)
      c->metric[m] = NAN;
    c->error = malloc(strlen(err.msg) + 1);
    if (c->error)
      memcpy(c->error, err.msg, strlen(err.msg) + 1);
  }
  fb_result_free(&res);
  fb_scenario_free(&s);
}

/* "flexbond sweep: case 3/12 (speed_kmh=15): ok, 1713 steps, 0.015 s". */
static void report_case(sweep_pool *p, size_t i)
{
  const sweep_case *c = &p->cases[i];
  pthread_mutex_lock(&p->lock);
  ++p->done;
  if (!p->a->quiet) {
    char label[512];
    case_label(p->a, i, 0, label, sizeof label);
    if (c->status == FB_OK)
      fprintf(stderr, "flexbond sweep: case %zu/%zu (%s): ok, %.0f steps, %.3g s\n", i + 1,
              p->a->ncases, label, c->metric[M_SOLVER_STEPS], c->metric[M_SOLVER_WALL_TIME]);
    else
      fprintf(stderr, "flexbond sweep: case %zu/%zu (%s): failed: %s\n", i + 1, p->a->ncases,
              label, c->error ? c->error : "out of memory");
  }
  pthread_mutex_unlock(&p->lock);
}

/* A thread of the pool: takes the next case until none is left, or
 * until the command is interrupted. */
static void *worker(void *arg)
{
  sweep_pool *p = arg;
  for (;;) {
    pthread_mutex_lock(&p->lock);
    const size_t i = p->next < p->a->ncases && !cli_interrupted() ? p->next++ : SIZE_MAX;
    pthread_mutex_unlock(&p->lock);
    if (i == SIZE_MAX)
      return NULL;
    run_case(p, i);
    report_case(p, i);
  }
}

/* Runs every case on min(jobs, ncases) threads, this one among them (if
 * a thread cannot be started, the others do its share). */
static void run_cases(const sweep_args *a, sweep_case *cases)
{
  sweep_pool p = {.a = a, .cases = cases, .next = 0, .done = 0};
  pthread_mutex_init(&p.lock, NULL);
  pthread_mutex_init(&p.arpack, NULL);
  size_t nthreads = a->jobs < a->ncases ? a->jobs : a->ncases;
  pthread_t *threads = nthreads > 1 ? malloc((nthreads - 1) * sizeof *threads) : NULL;
  size_t started = 0;
  while (threads && started + 1 < nthreads &&
         pthread_create(&threads[started], NULL, worker, &p) == 0)
    ++started;
  worker(&p);
  for (size_t t = 0; t < started; ++t)
    pthread_join(threads[t], NULL);
  free(threads);
  pthread_mutex_destroy(&p.arpack);
  pthread_mutex_destroy(&p.lock);
}

/* ---- Output files. */

/* A CSV cell: quoted (RFC 4180, section 2) when it holds a comma, a
 * quote or a line break. */
static void csv_text(FILE *fp, const char *text)
{
  if (!strpbrk(text, ",\"\r\n")) {
    fputs(text, fp);
    return;
  }
  fputc('"', fp);
  for (const char *t = text; *t; ++t) {
    if (*t == '"')
      fputc('"', fp);
    fputc(*t, fp);
  }
  fputc('"', fp);
}

/* What the files are made of. */
typedef struct sweep_outputs {
  const sweep_args *a;
  const sweep_case *cases;
} sweep_outputs;

/* sweep.csv (a cli_writer over a sweep_outputs): the keys, the metrics
 * in %.10g (empty when not finite or failed) and the error. */
static void write_csv(FILE *fp, const void *ctx)
{
  const sweep_outputs *o = ctx;
  const sweep_args *a = o->a;
  for (size_t k = 0; k < a->nkeys; ++k) {
    csv_text(fp, a->keys[k].key);
    fputc(',', fp);
  }
  for (size_t m = 0; m < NMETRICS; ++m) {
    char name[64];
    metric_name(m, name, sizeof name);
    fprintf(fp, "%s,", name);
  }
  fputs("error\n", fp);
  for (size_t i = 0; i < a->ncases; ++i) {
    const sweep_case *c = &o->cases[i];
    for (size_t k = 0; k < a->nkeys; ++k) {
      csv_text(fp, a->keys[k].values[value_index(a, i, k)]);
      fputc(',', fp);
    }
    for (size_t m = 0; m < NMETRICS; ++m) {
      if (isfinite(c->metric[m]))
        fprintf(fp, "%.10g", c->metric[m]);
      fputc(',', fp);
    }
    if (c->status != FB_OK)
      csv_text(fp, c->error ? c->error : "out of memory");
    fputc('\n', fp);
  }
}

/* Value as a number if the whole text is one (for the x axis). */
static int numeric_value(const char *text, double *out)
{
  char *end = NULL;
  errno = 0;
  *out = strtod(text, &end);
  return end != text && *end == '\0' && errno != ERANGE && isfinite(*out);
}

/* The figure's arrays: x per value of the first key, y per metric,
 * curve (combination of the other keys) and value, the curves, the
 * panels and the legends. */
typedef struct sweep_figure {
  double *x, *y;
  fb_plot_xy_series *series;
  fb_plot_xy_panel panels[NMETRICS];
  char (*legends)[256];
  char (*ylabels)[96];
  int categorical; /* the first key's values are not all numbers */
} sweep_figure;

static void sweep_figure_free(sweep_figure *f)
{
  free(f->x);
  free(f->y);
  free(f->series);
  free(f->legends);
  free(f->ylabels);
}

/* Fills f from the cases; FB_ENOMEM. */
static int build_figure(const sweep_args *a, const sweep_case *cases, sweep_figure *f,
                        fb_err *err)
{
  const size_t nx = a->keys[0].nvalues, ncurves = a->ncases / nx;
  f->x = malloc(nx * sizeof *f->x);
  f->y = malloc(NMETRICS * a->ncases * sizeof *f->y);
  f->series = malloc(NMETRICS * ncurves * sizeof *f->series);
  f->legends = malloc(ncurves * sizeof *f->legends);
  f->ylabels = malloc(NMETRICS * sizeof *f->ylabels);
  if (!f->x || !f->y || !f->series || !f->legends || !f->ylabels)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the figure of %zu cases", a->ncases);
  f->categorical = 0;
  for (size_t v = 0; v < nx; ++v)
    f->categorical |= !numeric_value(a->keys[0].values[v], &f->x[v]);
  for (size_t v = 0; f->categorical && v < nx; ++v)
    f->x[v] = (double)v;
  for (size_t r = 0; r < ncurves; ++r)
    /* Case r of the first value: the other keys' values of curve r. */
    case_label(a, r, 1, f->legends[r], sizeof f->legends[r]);
  for (size_t m = 0; m < NMETRICS; ++m) {
    char name[64];
    metric_name(m, name, sizeof name);
    snprintf(f->ylabels[m], sizeof f->ylabels[m], "%s [%s]", name, metric_unit(m));
    for (size_t r = 0; r < ncurves; ++r) {
      double *y = &f->y[(m * ncurves + r) * nx];
      for (size_t v = 0; v < nx; ++v)
        y[v] = cases[v * ncurves + r].metric[m];
      /* The key once, in the first panel; none for a single curve. */
      f->series[m * ncurves + r] = (fb_plot_xy_series){
          .x = f->x, .y = y, .n = nx, .legend = m == 0 && ncurves > 1 ? f->legends[r] : NULL};
    }
    f->panels[m] = (fb_plot_xy_panel){
        .series = &f->series[m * ncurves], .nseries = ncurves, .ylabel = f->ylabels[m]};
  }
  return FB_OK;
}

/* DIR/sweep.png: every metric against the first key. */
static int write_figure(cli_outdir *od, const sweep_args *a, const sweep_case *cases,
                        fb_err *err)
{
  sweep_figure f = {0};
  char title[512];
  snprintf(title, sizeof title, "flexbond sweep: %s, %s, %zu cases", a->scenario_name,
           cli_system_label(a->sys), a->ncases);
  int rc = build_figure(a, cases, &f, err);
  char *path = rc == FB_OK ? cli_outdir_path(od, "sweep.png", err) : NULL;
  if (rc == FB_OK && !path)
    rc = FB_ENOMEM;
  if (rc == FB_OK) {
    fb_plot_xy_opts opts;
    fb_plot_xy_opts_default(&opts);
    opts.title = title;
    opts.xlabel = a->keys[0].key;
    opts.xtic_labels = f.categorical ? (const char *const *)a->keys[0].values : NULL;
    opts.nxtics = f.categorical ? a->keys[0].nvalues : 0;
    rc = fb_plot_xy_png(f.panels, NMETRICS, &opts, path, err);
    if (rc == FB_OK) {
      rc = cli_outdir_keep(od, path, err);
      path = NULL;
    }
  }
  free(path);
  sweep_figure_free(&f);
  return rc;
}

/* The figure first (gnuplot is the likelier failure), then the CSV. */
static int write_outputs(const sweep_args *a, const sweep_case *cases, fb_err *err)
{
  cli_outdir od;
  const sweep_outputs o = {a, cases};
  int rc = cli_outdir_open(&od, a->out_dir, err);
  if (rc == FB_OK && a->figures)
    rc = write_figure(&od, a, cases, err);
  if (rc == FB_OK)
    rc = cli_outdir_write(&od, "sweep.csv", write_csv, &o, err);
  return cli_outdir_close(&od, rc, err);
}

/* ---- The command line. */

/* Appends value text to key k (copied). */
static int add_value(sweep_key *k, const char *text, size_t len)
{
  char **values = realloc(k->values, (k->nvalues + 1) * sizeof *values);
  if (!values)
    return 0;
  k->values = values;
  k->values[k->nvalues] = malloc(len + 1);
  if (!k->values[k->nvalues])
    return 0;
  memcpy(k->values[k->nvalues], text, len);
  k->values[k->nvalues++][len] = '\0';
  return 1;
}

static void sweep_key_free(sweep_key *k)
{
  for (size_t v = 0; v < k->nvalues; ++v)
    free(k->values[v]);
  free(k->values);
  free(k->path);
}

/* A finite number, the whole text. */
static int spec_number(const char *cmd, const char *set, const char *text, double *out)
{
  if (numeric_value(text, out))
    return CLI_EXIT_OK;
  return cli_usage_error(cmd, "--set %s: '%s' is not a finite number", set, text);
}

/* start:step:stop: start + i step for i = 0, 1, ... while it does not
 * pass stop by more than step/1e9 (so 0.1:0.1:0.3 includes 0.3 despite
 * rounding). Each value is printed to 15 significant digits, which
 * removes that rounding (0.30000000000000004 becomes 0.3) and keeps
 * every decimal the user typed. */
static int parse_range(const char *cmd, const char *set, char *spec, sweep_key *k)
{
  char *parts[3] = {spec, NULL, NULL};
  parts[1] = strchr(spec, ':');
  parts[2] = parts[1] ? strchr(parts[1] + 1, ':') : NULL;
  if (!parts[2] || strchr(parts[2] + 1, ':'))
    return cli_usage_error(cmd, "--set %s: a range is start:step:stop", set);
  *parts[1]++ = '\0';
  *parts[2]++ = '\0';
  double v[3];
  for (int i = 0; i < 3; ++i) {
    int rc = spec_number(cmd, set, parts[i], &v[i]);
    if (rc != CLI_EXIT_OK)
      return rc;
  }
  const double start = v[0], step = v[1], stop = v[2];
  const double steps = step != 0 ? (stop - start) / step : -1;
  if (!(steps >= -1e-9))
    return cli_usage_error(cmd, "--set %s: step %g does not lead from %g to %g", set, step,
                           start, stop);
  if (!(steps + 1e-9 < SWEEP_MAX_VALUES))
    return cli_usage_error(cmd, "--set %s: more than %d values", set, SWEEP_MAX_VALUES);
  const size_t n = (size_t)floor(steps + 1e-9) + 1;
  for (size_t i = 0; i < n; ++i) {
    double x = start + (double)i * step;
    /* A sum that should be 0 (-0.1 + 0.1) prints as 0, not 1.4e-17. */
    if (fabs(x) < 1e-9 * fabs(step))
      x = 0;
    char text[32];
    snprintf(text, sizeof text, "%.15g", x + 0.0);
    if (!add_value(k, text, strlen(text)))
      return cli_usage_error(cmd, "out of memory");
  }
  return CLI_EXIT_OK;
}

/* v1,v2,...: each value's text, spaces around it removed. */
static int parse_list(const char *cmd, const char *set, const char *spec, sweep_key *k)
{
  const char *p = spec;
  for (;;) {
    size_t len = strcspn(p, ",");
    const char *item = p;
    while (len > 0 && *item == ' ') {
      ++item;
      --len;
    }
    while (len > 0 && item[len - 1] == ' ')
      --len;
    if (len == 0)
      return cli_usage_error(cmd, "--set %s: empty value in the list", set);
    if (k->nvalues == SWEEP_MAX_VALUES)
      return cli_usage_error(cmd, "--set %s: more than %d values", set, SWEEP_MAX_VALUES);
    if (!add_value(k, item, len))
      return cli_usage_error(cmd, "out of memory");
    p = item + len;
    p += strspn(p, " ");
    if (*p == '\0')
      return CLI_EXIT_OK;
    ++p; /* the comma */
  }
}

/* KEY=SPEC of one --set into k (k->key points into set). */
static int parse_set(const char *cmd, char *set, sweep_key *k)
{
  char *eq = strchr(set, '=');
  if (!eq || eq == set || eq[1] == '\0')
    return cli_usage_error(cmd, "--set needs KEY=SPEC (got '%s')", set);
  /* Messages name the whole option: copy the spec before splitting. */
  char spec[1024];
  if (strlen(eq + 1) >= sizeof spec)
    return cli_usage_error(cmd, "--set %s: the spec is too long", set);
  snprintf(spec, sizeof spec, "%s", eq + 1);
  int rc = strchr(spec, ':') ? parse_range(cmd, set, spec, k) : parse_list(cmd, set, spec, k);
  *eq = '\0';
  k->key = set;
  return rc;
}

/* Takes the --set options out of argv (they repeat, which cli_parse
 * does not keep) into sets; the other arguments go to rest. Options
 * that take a value are skipped with it, so a value is never read as an
 * option. */
static int split_sets(int argc, char **argv, char **rest, int *nrest, char **sets,
                      size_t *nsets)
{
  static const char *const with_value[] = {"-o", "--output", "--system", "-j", "--jobs"};
  *nrest = 0;
  *nsets = 0;
  int i = 0;
  for (; i < argc && strcmp(argv[i], "--") != 0; ++i) {
    if (!strncmp(argv[i], "--set=", 6)) {
      sets[(*nsets)++] = argv[i] + 6;
      continue;
    }
    if (!strcmp(argv[i], "--set")) {
      if (i + 1 == argc)
        return cli_usage_error(argv[0], "option '--set' needs a value (KEY=SPEC)");
      sets[(*nsets)++] = argv[++i];
      continue;
    }
    rest[(*nrest)++] = argv[i];
    for (size_t o = 0; o < sizeof with_value / sizeof with_value[0]; ++o)
      if (!strcmp(argv[i], with_value[o]) && i + 1 < argc) {
        rest[(*nrest)++] = argv[++i];
        break;
      }
  }
  for (; i < argc; ++i)
    rest[(*nrest)++] = argv[i];
  return CLI_EXIT_OK;
}

/* -j N: 1 .. SWEEP_MAX_JOBS; default: the online CPUs. */
static int parse_jobs(const char *cmd, const char *text, size_t *jobs)
{
  if (!text) {
    const long n = sysconf(_SC_NPROCESSORS_ONLN);
    *jobs = n > 0 ? (size_t)n : 1;
    return CLI_EXIT_OK;
  }
  char *end = NULL;
  errno = 0;
  const long n = strtol(text, &end, 10);
  if (end == text || *end != '\0' || errno == ERANGE || n < 1 || n > SWEEP_MAX_JOBS)
    return cli_usage_error(cmd, "option '-j' needs an integer in 1..%d (got '%s')",
                           SWEEP_MAX_JOBS, text);
  *jobs = (size_t)n;
  return CLI_EXIT_OK;
}

/* Parses every --set into a->keys and counts the cases. */
static int parse_keys(const char *cmd, char **sets, size_t nsets, sweep_args *a)
{
  if (nsets == 0)
    return cli_usage_error(cmd, "nothing to sweep: give at least one --set KEY=SPEC");
  if (nsets > SWEEP_MAX_KEYS)
    return cli_usage_error(cmd, "at most %d --set options", SWEEP_MAX_KEYS);
  a->ncases = 1;
  for (size_t k = 0; k < nsets; ++k) {
    a->nkeys = k + 1;
    int rc = parse_set(cmd, sets[k], &a->keys[k]);
    if (rc != CLI_EXIT_OK)
      return rc;
    if (a->ncases * a->keys[k].nvalues > SWEEP_MAX_CASES)
      return cli_usage_error(cmd, "more than %d cases", SWEEP_MAX_CASES);
    a->ncases *= a->keys[k].nvalues;
  }
  return CLI_EXIT_OK;
}

/* Each key names one replaceable value of the scenario, and no two keys
 * the same one: usage errors naming the candidates otherwise. */
static int resolve_keys(const char *cmd, sweep_args *a)
{
  fb_err err;
  for (size_t k = 0; k < a->nkeys; ++k) {
    int rc = fb_scenario_override_key(a->scenario_path, a->keys[k].key, &a->keys[k].path, &err);
    if (rc == FB_EINVAL)
      return cli_usage_error(cmd, "--set %s: %s", a->keys[k].key, err.msg);
    if (rc != FB_OK)
      return cli_report(rc, &err);
    for (size_t j = 0; j < k; ++j)
      if (!strcmp(a->keys[j].path, a->keys[k].path))
        return cli_usage_error(cmd, "--set %s and --set %s both set %s", a->keys[j].key,
                               a->keys[k].key, a->keys[k].path);
  }
  return CLI_EXIT_OK;
}

/* The scenario as it is must load (an input error otherwise), and have a
 * finite-element hull for --system flexible. */
static int check_scenario(const char *cmd, sweep_args *a, char **name)
{
  fb_err err;
  fb_scenario *s = NULL;
  int rc = fb_scenario_load(a->scenario_path, &s, &err);
  if (rc != FB_OK)
    return cli_report(rc, &err);
  int exit_code = CLI_EXIT_OK;
  if (a->sys == FB_SYSTEM_FLEXIBLE && !s->has_fe_hull)
    exit_code = cli_usage_error(cmd, "--system flexible: the scenario has no finite-element "
                                     "hull (hull.mesh and hull.fe)");
  const char *n = cli_scenario_name(s);
  *name = malloc(strlen(n) + 1);
  if (*name)
    memcpy(*name, n, strlen(n) + 1);
  a->scenario_name = *name ? *name : "scenario";
  fb_scenario_free(&s);
  return exit_code;
}

/* Runs the study; the exit code. */
static int sweep(const sweep_args *a)
{
  sweep_case *cases = calloc(a->ncases, sizeof *cases);
  fb_err err;
  fb_err_clear(&err);
  if (!cases)
    return cli_report(fb_err_set(&err, FB_ENOMEM, "out of memory for %zu cases", a->ncases),
                      &err);
  run_cases(a, cases);
  size_t failed = 0, input_errors = 0;
  for (size_t i = 0; i < a->ncases; ++i) {
    failed += cases[i].status != FB_OK;
    /* An input error at a swept value (the reader's message then starts
     * with the option that set it) belongs to its case. */
    const int at_value = cases[i].error && strncmp(cases[i].error, "--set ", 6) == 0;
    input_errors += !at_value && (cli_exit_code(cases[i].status) == CLI_EXIT_INPUT ||
                                  cli_exit_code(cases[i].status) == CLI_EXIT_IO);
  }
  int rc = cli_check_interrupt(&err);
  /* Every case refused for an input none of its values touches (a bad
   * deck all cases share, say): the study is at fault, not its cases. */
  if (rc == FB_OK && input_errors == a->ncases)
    rc = fb_err_set(&err, cases[0].status, "every case failed on its input; the first: %s",
                    cases[0].error ? cases[0].error : "(out of memory)");
  if (rc == FB_OK)
    rc = write_outputs(a, cases, &err);
  if (rc == FB_OK && !a->quiet)
    fprintf(stderr, "flexbond sweep: %s: %zu cases, %zu failed -> %s\n", a->scenario_name,
            a->ncases, failed, a->out_dir);
  for (size_t i = 0; i < a->ncases; ++i)
    free(cases[i].error);
  free(cases);
  if (rc != FB_OK) {
    cli_nothing_written(&err, a->out_dir);
    return cli_report(rc, &err);
  }
  return failed ? CLI_EXIT_SOLVER : CLI_EXIT_OK;
}

/* The options after the --set ones are taken out. */
static int parse_options(int argc, char **argv, sweep_args *a, int *go)
{
  enum { OPT_OUT, OPT_SYSTEM, OPT_JOBS, OPT_NO_FIGURES, OPT_QUIET, OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {
      [OPT_OUT] = {"--output", "-o", 1, NULL},
      [OPT_SYSTEM] = {"--system", NULL, 1, NULL},
      [OPT_JOBS] = {"--jobs", "-j", 1, NULL},
      [OPT_NO_FIGURES] = {"--no-figures", NULL, 0, NULL},
      [OPT_QUIET] = {"--quiet", "-q", 0, NULL},
      [OPT_HELP] = {"--help", "-h", 0, NULL},
  };
  static const char *const systems[] = {"rigid", "flexible"};
  int rc;
  *go = cli_parse_file_command(argc, argv, opts, NOPTS, sweep_usage, "SCENARIO",
                               &a->scenario_path, &rc);
  if (!*go)
    return rc;
  a->out_dir = opts[OPT_OUT].value;
  if (!a->out_dir || !*a->out_dir)
    return cli_usage_error(argv[0], "missing output directory (-o DIR)");
  a->quiet = opts[OPT_QUIET].value != NULL;
  a->figures = opts[OPT_NO_FIGURES].value == NULL;
  int system = 0;
  rc = opts[OPT_SYSTEM].value
           ? cli_choice(argv[0], "--system", opts[OPT_SYSTEM].value, systems, 2, &system)
           : CLI_EXIT_OK;
  a->sys = system ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID;
  return rc == CLI_EXIT_OK ? parse_jobs(argv[0], opts[OPT_JOBS].value, &a->jobs) : rc;
}

int cli_cmd_sweep(int argc, char **argv)
{
  sweep_args a = {0};
  char **rest = malloc((size_t)argc * sizeof *rest),
       **sets = malloc((size_t)argc * sizeof *sets);
  char *name = NULL;
  size_t nsets = 0;
  int nrest = 0, go = 0;
  int rc = rest && sets ? split_sets(argc, argv, rest, &nrest, sets, &nsets)
                        : cli_usage_error(argv[0], "out of memory");
  if (rc == CLI_EXIT_OK)
    rc = parse_options(nrest, rest, &a, &go);
  if (rc == CLI_EXIT_OK && go)
    rc = parse_keys(argv[0], sets, nsets, &a);
  if (rc == CLI_EXIT_OK && go)
    rc = check_scenario(argv[0], &a, &name);
  if (rc == CLI_EXIT_OK && go)
    rc = resolve_keys(argv[0], &a);
  if (rc == CLI_EXIT_OK && go)
    rc = sweep(&a);
  for (size_t k = 0; k < a.nkeys; ++k)
    sweep_key_free(&a.keys[k]);
  free(name);
  free(sets);
  free(rest);
  return rc;
}
