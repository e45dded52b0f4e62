/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond freq: the frequency response of a vehicle scenario's outputs
 * to the road, from its descriptor form (fb_bd_descriptor,
 * fb_descriptor_freq_response; docs/frequency-response.md):
 *   DIR/freq_system1.csv, freq_system2.csv   |H| and phase per output and track
 *   DIR/bode_<OUTPUT>.png                    both systems and tracks overlaid
 * The input is a road height on one track, 1 m at the leading wheel, which
 * the track's other wheels meet later by their distance behind it at the
 * scenario's speed (fb_vehicle_freq_response). */
#include "freq.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "flexbond/bd.h"
#include "flexbond/escape.h"
#include "flexbond/io.h"
#include "flexbond/vehicle.h"

#include "cli.h"

static const char freq_usage[] =
    "usage: flexbond freq SCENARIO.yaml -o DIR [--system rigid|flexible|both]\n"
    "                     [--f-min HZ] [--f-max HZ] [--points N] [--no-figures]\n"
    "                     [--road-class A..H] [--tracks independent|identical]\n"
    "\n"
    "Frequency response of the scenario's outputs to the road: H = C (j w E - A)^-1 B\n"
    "from the vehicle's descriptor form (as flexbond export writes it), for a road\n"
    "height on the left and on the right track, 1 m at the leading wheel, which the\n"
    "track's other wheels meet later by their distance behind it at road.speed_kmh.\n"
    "  DIR/freq_system1.csv    frequency [Hz], then per output and track |H| [unit/m]\n"
    "  DIR/freq_system2.csv    and phase [deg] (in (-180, 180])\n"
    "  DIR/bode_<OUTPUT>.png   |H| and phase, both systems and tracks overlaid\n"
    "On an ISO 8608 road also the ride from its spectrum, without a time run:\n"
    "  DIR/psd_system1.csv ... each output's PSD over the road's band [unit^2/Hz]\n"
    "  DIR/ride_psd.json       the driver's ISO 2631-1 a_w and each output's r.m.s.\n"
    "Power outputs, products of two signals, have no frequency response and are left\n"
    "out. Unilateral tires are taken in contact, their linear branch; a vehicle\n"
    "with a nonlinear law (a damper table) is linearised at its static equilibrium\n"
    "under gravity, and the output says so.\n"
    "\n"
    "options:\n"
    "  -o, --output DIR                 output directory (required)\n"
    "  --system rigid|flexible|both     which hull model (default both)\n"
    "  --f-min HZ, --f-max HZ           frequency range (default 0.1 to 100 Hz)\n"
    "  --points N                       frequencies, evenly spaced on a log scale\n"
    "                                   (default 301: 100 per decade)\n"
    "  --no-figures                     write the CSV files only\n"
    "  --road-class A..H                the ride from an ISO 8608 road of that class\n"
    "                                   (band 0.011 to 2.83 cycles/m); by default the\n"
    "                                   scenario's road when it is an ISO 8608 one\n"
    "  --tracks independent|identical   the road's two tracks (default independent,\n"
    "                                   as the ISO 8608 generator makes them)\n"
    "  --strict                         refuse implausible values instead of warning\n"
    "  -h, --help                       this text\n";

static const char *const system_choices[] = {"rigid", "flexible", "both"};
static const char *const track_choices[] = {"independent", "identical"};

static const char *const track_names[NTRACKS] = {"left", "right"};

/* The complex amplitude of output o on track t at frequency k. */
static const double *amplitude(const freq_study *fs, int sys, size_t k, int t, size_t o)
{
  return cli_freq_amplitude(fs->h[sys], fs->nrows[sys], k, t, fs->row[sys][o]);
}

static int respond(freq_study *fs, int sys, const fb_descriptor *ds, fb_err *err)
{
  const fb_scenario *s = fs->s;
  fs->row[sys] = calloc(s->noutputs + 1, sizeof *fs->row[sys]);
  fs->h[sys] = malloc((2 * NTRACKS * ds->nrows_c * fs->nfreq + 1) * sizeof *fs->h[sys]);
  if (!fs->row[sys] || !fs->h[sys])
    return fb_err_set(err, FB_ENOMEM, "out of memory for a frequency response");
  fs->nrows[sys] = ds->nrows_c;
  for (size_t o = 0; o < s->noutputs; ++o)
    fs->row[sys][o] = ds->output_is_product[o] ? (size_t)-1 : ds->output_row[o];
  int rc = fb_vehicle_freq_response(s, ds, fs->freq_hz, fs->nfreq, fs->h[sys], err);
  if (!rc && fs->psd.on)
    rc = cli_freq_psd_respond(fs, sys, ds, err);
  return rc;
}

static int run_system(freq_study *fs, int sys, fb_vehicle *v, fb_err *err)
{
  fb_descriptor *ds = NULL;
  struct timespec start, end;
  clock_gettime(CLOCK_MONOTONIC, &start);
  int rc = fb_vehicle_linearise(v, &ds, err);
  if (!rc) {
    fs->linearised[sys] = ds->linearised;
    rc = respond(fs, sys, ds, err);
  }
  clock_gettime(CLOCK_MONOTONIC, &end);
  fs->seconds[sys] =
      (double)(end.tv_sec - start.tv_sec) + 1e-9 * (double)(end.tv_nsec - start.tv_nsec);
  if (!rc)
    fs->ran[sys] = 1;
  fb_descriptor_free(&ds);
  return rc ? fb_err_prefix(
                  err, "%s: ", cli_system_label(sys ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID))
            : FB_OK;
}

/* ---- Files. */

/* The unit of |H|: the output's per metre of road. */
static void gain_unit(const char *unit, char *buf, size_t size)
{
  const int compound = strpbrk(unit, "/ *") != NULL;
  snprintf(buf, size, compound ? "(%s)/m" : "%s/m", unit);
}

/* Phase in degrees, in (-180, 180], of output o on track t at every
 * frequency. Not unwrapped: the wheelbase filter's notches are zeros
 * close to the imaginary axis, across which the phase has no one
 * continuation. */
static void phases(const freq_study *fs, int sys, int t, size_t o, double *deg)
{
  for (size_t k = 0; k < fs->nfreq; ++k) {
    const double *z = amplitude(fs, sys, k, t, o);
    deg[k] = atan2(z[1], z[0]) * 180.0 / 3.14159265358979323846;
  }
}

typedef struct csv_ctx {
  const freq_study *fs;
  int sys;
  double *phase; /* noutputs x NTRACKS x nfreq */
} csv_ctx;

/* The header; power outputs (row -1) have no columns. */
static void write_header(FILE *fp, const fb_scenario *s, const size_t *row)
{
  fputs("frequency [Hz]", fp);
  for (size_t o = 0; o < s->noutputs; ++o)
    for (int t = 0; t < NTRACKS && row[o] != (size_t)-1; ++t) {
      char unit[64];
      gain_unit(s->output[o].unit, unit, sizeof unit);
      const char *mag[] = {s->output[o].name, "/", track_names[t], " |H| [", unit, "]"};
      const char *ph[] = {s->output[o].name, "/", track_names[t], " phase [deg]"};
      fputc(',', fp);
      fb_csv_write_field_parts(fp, mag, 6, FB_CSV_TEXT);
      fputc(',', fp);
      fb_csv_write_field_parts(fp, ph, 4, FB_CSV_TEXT);
    }
  fputc('\n', fp);
}

static void write_csv(FILE *fp, const void *ctx)
{
  const csv_ctx *c = ctx;
  const freq_study *fs = c->fs;
  const fb_scenario *s = fs->s;
  write_header(fp, s, fs->row[c->sys]);
  for (size_t k = 0; k < fs->nfreq; ++k) {
    fprintf(fp, "%.10g", fs->freq_hz[k]);
    for (size_t o = 0; o < s->noutputs; ++o)
      for (int t = 0; t < NTRACKS && fs->row[c->sys][o] != (size_t)-1; ++t) {
        const double *z = amplitude(fs, c->sys, k, t, o);
        fprintf(fp, ",%.10g,%.8g", hypot(z[0], z[1]),
                c->phase[(o * NTRACKS + (size_t)t) * fs->nfreq + k]);
      }
    fputc('\n', fp);
  }
}

/* Every output's phases of system sys. */
static double *all_phases(const freq_study *fs, int sys)
{
  const size_t n = fs->s->noutputs * NTRACKS * fs->nfreq;
  double *phase = calloc(n + 1, sizeof *phase);
  for (size_t o = 0; phase && o < fs->s->noutputs; ++o)
    for (int t = 0; t < NTRACKS && fs->row[sys][o] != (size_t)-1; ++t)
      phases(fs, sys, t, o, phase + (o * NTRACKS + (size_t)t) * fs->nfreq);
  return phase;
}

/* The curves of one output's Bode figure: |H| and phase per system and
 * track. */
typedef struct bode {
  double *mag[CLI_MAX_SYSTEMS][NTRACKS];
  fb_plot_xy_series ms[2 * NTRACKS], ps[2 * NTRACKS];
  char legend[2 * NTRACKS][48];
} bode;

static int draw_bode(cli_outdir *od, const freq_study *fs, double *const *phase, size_t o,
                     fb_err *err)
{
  const fb_scenario *s = fs->s;
  bode b;
  memset(&b, 0, sizeof b);
  size_t n = 0;
  int rc = FB_OK;
  for (int sys = 0; sys < CLI_MAX_SYSTEMS && !rc; ++sys)
    for (int t = 0; fs->ran[sys] && t < NTRACKS && !rc; ++t) {
      double *mag = malloc((fs->nfreq + 1) * sizeof *mag);
      b.mag[sys][t] = mag;
      if (!mag) {
        rc = fb_err_set(err, FB_ENOMEM, "out of memory for a Bode figure");
        break;
      }
      for (size_t k = 0; k < fs->nfreq; ++k) {
        const double *z = amplitude(fs, sys, k, t, o);
        mag[k] = hypot(z[0], z[1]);
      }
      snprintf(b.legend[n], sizeof b.legend[n], "System %d, %s track", sys + 1, track_names[t]);
      b.ms[n] = (fb_plot_xy_series){fs->freq_hz, mag, fs->nfreq, b.legend[n]};
      b.ps[n] =
          (fb_plot_xy_series){fs->freq_hz, phase[sys] + (o * NTRACKS + (size_t)t) * fs->nfreq,
                              fs->nfreq, NULL}; /* the key is above */
      ++n;
    }
  char unit[64], ylabel[96], title[160], name[FB_ERR_KEY_MAX + 16];
  gain_unit(s->output[o].unit, unit, sizeof unit);
  snprintf(ylabel, sizeof ylabel, "|H| [%s]", unit);
  snprintf(title, sizeof title, "%s: frequency response to the road (%.4g km/h)%s",
           s->output[o].name, 3.6 * s->speed,
           fs->linearised[0] || fs->linearised[1] ? ", linearised at the static equilibrium"
                                                  : "");
  const fb_plot_xy_panel panels[2] = {
      {.series = b.ms, .nseries = n, .ylabel = ylabel, .unit = NULL, .log_y = 1},
      {.series = b.ps, .nseries = n, .ylabel = "phase [deg]", .unit = NULL, .log_y = 0}};
  fb_plot_xy_opts opts;
  fb_plot_xy_opts_default(&opts);
  opts.title = title;
  opts.xlabel = "frequency [Hz]";
  opts.columns = 1;
  opts.panel_width = 900;
  opts.panel_height = 300;
  opts.log_x = 1;
  opts.lines = 1;
  snprintf(name, sizeof name, "bode_%s.png", s->output[o].name);
  char *path = rc ? NULL : cli_outdir_path(od, name, err);
  if (!rc)
    rc = path ? fb_plot_xy_png(panels, 2, &opts, path, err) : err->code;
  if (!rc)
    rc = cli_outdir_keep(od, path, err);
  else
    free(path);
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys)
    for (int t = 0; t < NTRACKS; ++t)
      free(b.mag[sys][t]);
  return rc;
}

/* The CSV files (csv 1) and the Bode figures (figures 1). */
static int write_files(cli_outdir *od, const freq_study *fs, int csv, int figures, fb_err *err)
{
  double *phase[CLI_MAX_SYSTEMS] = {NULL, NULL};
  int rc = FB_OK;
  for (int sys = 0; sys < CLI_MAX_SYSTEMS && !rc; ++sys) {
    if (!fs->ran[sys])
      continue;
    phase[sys] = all_phases(fs, sys);
    if (!phase[sys]) {
      rc = fb_err_set(err, FB_ENOMEM, "out of memory for the phases");
      break;
    }
    const csv_ctx c = {fs, sys, phase[sys]};
    if (csv)
      rc = cli_outdir_write(od, sys ? "freq_system2.csv" : "freq_system1.csv", write_csv, &c,
                            err);
  }
  for (size_t o = 0; figures && !rc && o < fs->s->noutputs; ++o) {
    const int sys = fs->ran[0] ? 0 : 1;
    if (fs->row[sys][o] != (size_t)-1)
      rc = draw_bode(od, fs, phase, o, err);
  }
  free(phase[0]);
  free(phase[1]);
  return rc;
}

/* ---- The command. */

static void print_summary(const freq_study *fs, const fb_scenario *file)
{
  const fb_scenario *s = fs->s;
  printf("%s: frequency response to the road at %.4g km/h, %zu frequencies from %g to %g Hz\n",
         cli_scenario_name(s), 3.6 * s->speed, fs->nfreq, fs->freq_hz[0],
         fs->freq_hz[fs->nfreq - 1]);
  size_t unilateral = 0;
  for (size_t c = 0; c < file->ncorners; ++c)
    unilateral += file->corner[c].tire_contact == FB_TIRE_UNILATERAL;
  if (unilateral)
    printf("%zu unilateral tires taken in contact (their linear branch at rest)\n", unilateral);
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys) {
    if (!fs->ran[sys])
      continue;
    printf("%s (%.2f s%s): largest |H|\n",
           cli_system_label(sys ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID), fs->seconds[sys],
           fs->linearised[sys] ? "; nonlinear, linearised at its static equilibrium" : "");
    for (size_t o = 0; o < s->noutputs; ++o) {
      if (fs->row[sys][o] == (size_t)-1) {
        printf("  %-20s a power: no frequency response\n", s->output[o].name);
        continue;
      }
      size_t best = 0;
      int track = FB_ROAD_LEFT;
      double big = -1.0;
      for (size_t k = 0; k < fs->nfreq; ++k)
        for (int t = 0; t < NTRACKS; ++t) {
          const double *z = amplitude(fs, sys, k, t, o);
          if (hypot(z[0], z[1]) > big) {
            big = hypot(z[0], z[1]);
            best = k;
            track = t;
          }
        }
      char unit[64];
      gain_unit(s->output[o].unit, unit, sizeof unit);
      printf("  %-20s %12.5g %s at %.4g Hz, %s track\n", s->output[o].name, big, unit,
             fs->freq_hz[best], track_names[track]);
    }
  }
}

typedef struct freq_args {
  const char *path, *dir;
  int systems[CLI_MAX_SYSTEMS];
  double f_min, f_max;
  size_t points;
  int figures;
  char road_class;  /* 0: the scenario's road */
  int identical;    /* tracks */
  int strict;       /* --strict */
  int tracks_given; /* --tracks */
} freq_args;

int cli_freq_compute(freq_study *fs, fb_vehicle *const vehicles[CLI_MAX_SYSTEMS], double f_min,
                     double f_max, size_t points, fb_err *err)
{
  fs->nfreq = points;
  fs->freq_hz = calloc(points, sizeof *fs->freq_hz);
  if (!fs->freq_hz)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  /* Evenly spaced in log f, interpolated between the logarithms: the
   * ratio f_max / f_min itself may overflow (1e9 / 1e-300). The ends are
   * the given values exactly. */
  const double log_min = log(f_min), log_max = log(f_max);
  for (size_t k = 0; k < points; ++k)
    fs->freq_hz[k] = exp(log_min + (log_max - log_min) *
                                       (points > 1 ? (double)k / (double)(points - 1) : 0.0));
  fs->freq_hz[0] = f_min;
  if (points > 1)
    fs->freq_hz[points - 1] = f_max;
  int rc = FB_OK;
  for (int sys = 0; !rc && sys < CLI_MAX_SYSTEMS; ++sys)
    if (vehicles[sys])
      rc = run_system(fs, sys, vehicles[sys], err);
  return rc;
}

int cli_freq_write_figures(cli_outdir *od, const freq_study *fs, fb_err *err)
{
  return write_files(od, fs, 0, 1, err);
}

void cli_freq_study_free(freq_study *fs)
{
  cli_freq_psd_free(&fs->psd);
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys) {
    free(fs->h[sys]);
    free(fs->row[sys]);
  }
  free(fs->freq_hz);
}

static int study(const freq_args *a)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  freq_study fs = {0};
  int rc = cli_scenario_load(a->path, a->strict, &s, &err);
  fs.s = s;
  if (!rc)
    rc = cli_freq_psd_setup(&fs, a->road_class, a->identical, &err);
  if (!rc && a->tracks_given && !fs.psd.on) {
    cli_freq_study_free(&fs);
    fb_scenario_free(&s);
    return cli_usage_error("freq", "--tracks is for the ride from an ISO 8608 road, and the "
                                   "scenario's road is none: add --road-class");
  }
  cli_outdir od;
  const int opened = !rc && (rc = cli_outdir_open(&od, a->dir, "freq", &err)) == FB_OK;
  /* Each system realised once; its linear model is made from it. */
  fb_vehicle *vehicles[CLI_MAX_SYSTEMS] = {NULL, NULL};
  cli_stage stages[CLI_MAX_SYSTEMS];
  for (int sys = 0; !rc && sys < CLI_MAX_SYSTEMS; ++sys) {
    const fb_system which = sys ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID;
    stages[sys] = (cli_stage){"freq", cli_system_label(which), 0};
    fb_vehicle_opts vo;
    fb_vehicle_opts_default(&vo);
    vo.progress = (fb_progress){cli_stage_progress, &stages[sys]};
    if (a->systems[sys])
      rc = fb_vehicle_new(s, which, &vo, &vehicles[sys], &err);
  }
  if (!rc)
    rc = cli_freq_compute(&fs, vehicles, a->f_min, a->f_max, a->points, &err);
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys)
    fb_vehicle_free(&vehicles[sys]);
  if (!rc)
    rc = write_files(&od, &fs, 1, a->figures, &err);
  if (!rc && fs.psd.on)
    rc = cli_freq_psd_write(&od, &fs, &err);
  if (opened)
    rc = cli_outdir_close(&od, rc, &err);
  if (!rc) {
    print_summary(&fs, s);
    if (fs.psd.on)
      cli_freq_psd_print(&fs);
    rc = cli_flush_stdout(&err);
  }
  cli_freq_study_free(&fs);
  rc = cli_report_scenario(s, rc, &err);
  fb_scenario_free(&s);
  return rc;
}

int cli_cmd_freq(int argc, char **argv)
{
  enum {
    OPT_SYSTEM,
    OPT_OUT,
    OPT_FMIN,
    OPT_FMAX,
    OPT_POINTS,
    OPT_NOFIG,
    OPT_CLASS,
    OPT_TRACKS,
    OPT_STRICT,
    OPT_HELP,
    NOPTS
  };
  cli_option opts[NOPTS] = {[OPT_SYSTEM] = {"--system", NULL, 1, NULL},
                            [OPT_OUT] = {"--output", "-o", 1, NULL},
                            [OPT_FMIN] = {"--f-min", NULL, 1, NULL},
                            [OPT_FMAX] = {"--f-max", NULL, 1, NULL},
                            [OPT_POINTS] = {"--points", NULL, 1, NULL},
                            [OPT_NOFIG] = {"--no-figures", NULL, 0, NULL},
                            [OPT_CLASS] = {"--road-class", NULL, 1, NULL},
                            [OPT_TRACKS] = {"--tracks", NULL, 1, NULL},
                            [OPT_STRICT] = {"--strict", NULL, 0, NULL},
                            [OPT_HELP] = {"--help", "-h", 0, NULL}};
  freq_args a = {.f_min = 0.1, .f_max = 100.0, .points = 301, .systems = {1, 1}};
  int rc;
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, freq_usage, "SCENARIO", &a.path, &rc))
    return rc;
  a.strict = opts[OPT_STRICT].value != NULL;
  int choice = 2;
  if (opts[OPT_SYSTEM].value)
    rc = cli_choice(argv[0], "--system", opts[OPT_SYSTEM].value, system_choices, 3, &choice);
  a.systems[0] = choice != 1;
  a.systems[1] = choice != 0;
  if (rc == CLI_EXIT_OK && opts[OPT_FMIN].value)
    rc = cli_positive_number(argv[0], "--f-min", opts[OPT_FMIN].value, &a.f_min);
  if (rc == CLI_EXIT_OK && opts[OPT_FMAX].value)
    rc = cli_positive_number(argv[0], "--f-max", opts[OPT_FMAX].value, &a.f_max);
  double points = (double)a.points;
  if (rc == CLI_EXIT_OK && opts[OPT_POINTS].value)
    rc = cli_positive_number(argv[0], "--points", opts[OPT_POINTS].value, &points);
  int tracks = 0;
  if (rc == CLI_EXIT_OK && opts[OPT_TRACKS].value)
    rc = cli_choice(argv[0], "--tracks", opts[OPT_TRACKS].value, track_choices, 2, &tracks);
  if (rc != CLI_EXIT_OK)
    return rc;
  a.identical = tracks == 1;
  a.tracks_given = opts[OPT_TRACKS].value != NULL;
  const char *cls = opts[OPT_CLASS].value;
  if (cls && (strlen(cls) != 1 || !strchr("ABCDEFGHabcdefgh", cls[0])))
    return cli_usage_error(argv[0], "--road-class: '%s' is not an ISO 8608 class A to H", cls);
  if (cls)
    a.road_class = cls[0];
  if (points != floor(points) || points < 2 || points > FREQ_MAX_POINTS)
    return cli_usage_error(argv[0], "--points: %s is not a whole number from 2 to %d",
                           opts[OPT_POINTS].value, FREQ_MAX_POINTS);
  if (a.f_max > FB_FREQ_MAX_HZ)
    return cli_usage_error(argv[0], "--f-max (%g Hz) must be at most %g Hz", a.f_max,
                           FB_FREQ_MAX_HZ);
  if (!(a.f_max > a.f_min))
    return cli_usage_error(argv[0], "--f-max (%g Hz) must be above --f-min (%g Hz)", a.f_max,
                           a.f_min);
  if (!opts[OPT_OUT].value)
    return cli_usage_error(argv[0], "missing output directory (-o DIR)");
  a.points = (size_t)points;
  a.dir = opts[OPT_OUT].value;
  a.figures = opts[OPT_NOFIG].value == NULL;
  return study(&a);
}
