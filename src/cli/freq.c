/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond freq: the frequency response of a vehicle scenario's outputs
 * to the road and, on an ISO 8608 road, the ride from its spectrum, as the
 * study layer computes them (fb_study_freq, fb_study_ride_psd;
 * docs/frequency-response.md), written:
 *   DIR/freq_system1.csv, freq_system2.csv   |H| and phase per output and track
 *   DIR/bode_<OUTPUT>.png                    both systems and tracks overlaid (bode.c)
 *   DIR/psd_systemN.csv, ride_psd.json       the ride (freq_psd.c)
 * The input is a road height on one track, 1 m at the leading wheel, which
 * the track's other wheels meet later by their distance behind it at the
 * scenario's speed (fb_vehicle_freq_response). */
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
    "  DIR/ride_psd.json       a mount's ISO 2631-1 a_w and each output's r.m.s.\n"
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

/* What the command computes: per system (System 1, System 2; NULL when
 * not asked) its frequency response and, on an ISO 8608 road, its ride
 * from the road's spectrum (owned). */
typedef struct freq_study {
  fb_study_freq *fr[CLI_MAX_SYSTEMS];
  fb_study_ride_psd *psd[CLI_MAX_SYSTEMS];
  double seconds[CLI_MAX_SYSTEMS];
} freq_study;

static double seconds_since(const struct timespec *start)
{
  struct timespec end;
  clock_gettime(CLOCK_MONOTONIC, &end);
  return (double)(end.tv_sec - start->tv_sec) + 1e-9 * (double)(end.tv_nsec - start->tv_nsec);
}

/* System sys's response at freq_hz and, with iso (NULL: none), its ride
 * on that road. */
static int run_system(freq_study *fs, int sys, fb_vehicle *v, const double *freq_hz,
                      size_t nfreq, const fb_road_iso8608_params *iso, int identical,
                      fb_err *err)
{
  struct timespec start;
  clock_gettime(CLOCK_MONOTONIC, &start);
  int rc = fb_study_freq_new(v, freq_hz, nfreq, &fs->fr[sys], err);
  if (!rc && iso)
    rc = fb_study_ride_psd_new(fs->fr[sys], iso, identical, &fs->psd[sys], err);
  fs->seconds[sys] = seconds_since(&start);
  return rc ? fb_err_prefix(
                  err, "%s: ", cli_system_label(sys ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID))
            : FB_OK;
}

static void free_study(freq_study *fs)
{
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys) {
    fb_study_freq_free(&fs->fr[sys]);
    fb_study_ride_psd_free(&fs->psd[sys]);
  }
}

/* ---- Files. */

/* The header; power outputs have no columns. */
static void write_header(FILE *fp, const fb_study_freq *f)
{
  const fb_scenario *s = fb_study_freq_scenario(f);
  fputs("frequency [Hz]", fp);
  for (size_t o = 0; o < s->noutputs; ++o)
    for (int t = 0; t < FB_ROAD_NTRACKS && fb_study_freq_has_output(f, o); ++t) {
      char unit[64];
      cli_gain_unit(s->output[o].unit, unit, sizeof unit);
      const char *mag[] = {s->output[o].name, "/", cli_track_names[t], " |H| [", unit, "]"};
      const char *ph[] = {s->output[o].name, "/", cli_track_names[t], " phase [deg]"};
      fputc(',', fp);
      fb_csv_write_field_parts(fp, mag, 6, FB_CSV_TEXT);
      fputc(',', fp);
      fb_csv_write_field_parts(fp, ph, 4, FB_CSV_TEXT);
    }
  fputc('\n', fp);
}

/* freq_systemN.csv: |H| and phase per output and track. */
static void write_csv(FILE *fp, const void *ctx)
{
  const fb_study_freq *f = ctx;
  const fb_scenario *s = fb_study_freq_scenario(f);
  write_header(fp, f);
  for (size_t k = 0; k < fb_study_freq_nfreq(f); ++k) {
    fprintf(fp, "%.10g", fb_study_freq_hz(f)[k]);
    for (size_t o = 0; o < s->noutputs; ++o)
      for (int t = 0; t < FB_ROAD_NTRACKS && fb_study_freq_has_output(f, o); ++t) {
        const double *z = fb_study_freq_at(f, o, t, k);
        fprintf(fp, ",%.10g,%.8g", hypot(z[0], z[1]), cli_phase_deg(z));
      }
    fputc('\n', fp);
  }
}

static int write_files(cli_outdir *od, const fb_scenario *s, const freq_study *fs, int figures,
                       fb_err *err)
{
  int rc = FB_OK;
  for (int sys = 0; sys < CLI_MAX_SYSTEMS && !rc; ++sys)
    if (fs->fr[sys])
      rc = cli_outdir_write(od, sys ? "freq_system2.csv" : "freq_system1.csv", write_csv,
                            fs->fr[sys], err);
  if (!rc && figures)
    rc = cli_bode_write_figures(od, fs->fr, err);
  if (!rc && (fs->psd[0] || fs->psd[1]))
    rc = cli_ride_psd_write(od, s, fs->psd, err);
  return rc;
}

/* ---- The command. */

static void print_system(const fb_study_freq *f, int sys, double seconds)
{
  const fb_scenario *s = fb_study_freq_scenario(f);
  printf("%s (%.2f s%s): largest |H|\n",
         cli_system_label(sys ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID), seconds,
         fb_study_freq_linearised(f) ? "; nonlinear, linearised at its static equilibrium"
                                     : "");
  for (size_t o = 0; o < s->noutputs; ++o) {
    if (!fb_study_freq_has_output(f, o)) {
      printf("  %-20s a power: no frequency response\n", s->output[o].name);
      continue;
    }
    size_t best = 0;
    int track = FB_ROAD_LEFT;
    const double big = fb_study_freq_peak(f, o, &best, &track);
    char unit[64];
    cli_gain_unit(s->output[o].unit, unit, sizeof unit);
    printf("  %-20s %12.5g %s at %.4g Hz, %s track\n", s->output[o].name, big, unit,
           fb_study_freq_hz(f)[best], cli_track_names[track]);
  }
}

static void print_summary(const freq_study *fs, const fb_scenario *s)
{
  const fb_study_freq *any = fs->fr[0] ? fs->fr[0] : fs->fr[1];
  const size_t nfreq = fb_study_freq_nfreq(any);
  const double *f = fb_study_freq_hz(any);
  printf("%s: frequency response to the road at %.4g km/h, %zu frequencies from %g to %g Hz\n",
         cli_scenario_name(s), 3.6 * s->speed, nfreq, f[0], f[nfreq - 1]);
  size_t unilateral = 0;
  for (size_t c = 0; c < s->ncorners; ++c)
    unilateral += fb_corner_tire_model(&s->corner[c])->in_contact != NULL;
  if (unilateral)
    printf("%zu unilateral tires taken in contact (their linear branch at rest)\n", unilateral);
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys)
    if (fs->fr[sys])
      print_system(fs->fr[sys], sys, fs->seconds[sys]);
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

/* Each asked system realised, its linear model made from it and its
 * response computed, then the vehicle freed. */
static int compute(freq_study *fs, const fb_scenario *s, const freq_args *a,
                   const fb_road_iso8608_params *iso, fb_err *err)
{
  double *freq_hz = malloc(a->points * sizeof *freq_hz);
  if (!freq_hz)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  fb_study_freq_log_grid(a->f_min, a->f_max, a->points, freq_hz);
  int rc = FB_OK;
  for (int sys = 0; !rc && sys < CLI_MAX_SYSTEMS; ++sys) {
    if (!a->systems[sys])
      continue;
    const fb_system which = sys ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID;
    cli_stage stage = {"freq", cli_system_label(which), 0};
    fb_vehicle_opts vo;
    fb_vehicle_opts_default(&vo);
    vo.progress = (fb_progress){cli_stage_progress, &stage};
    fb_vehicle *v = NULL;
    rc = fb_vehicle_new(s, which, &vo, &v, err);
    if (!rc)
      rc = run_system(fs, sys, v, freq_hz, a->points, iso, a->identical, err);
    fb_vehicle_free(&v);
  }
  free(freq_hz);
  return rc;
}

static int study(const freq_args *a)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  freq_study fs = {0};
  fb_road_iso8608_params iso;
  int rc = cli_scenario_load(a->path, a->strict, &s, &err);
  const int ride = !rc && fb_study_ride_psd_iso8608(s, a->road_class, &iso);
  if (!rc && a->tracks_given && !ride) {
    fb_scenario_free(&s);
    return cli_usage_error("freq", "--tracks is for the ride from an ISO 8608 road, and the "
                                   "scenario's road is none: add --road-class");
  }
  cli_outdir od;
  const int opened = !rc && (rc = cli_outdir_open(&od, a->dir, "freq", &err)) == FB_OK;
  if (!rc)
    rc = compute(&fs, s, a, ride ? &iso : NULL, &err);
  if (!rc)
    rc = write_files(&od, s, &fs, a->figures, &err);
  if (opened)
    rc = cli_outdir_close(&od, rc, &err);
  if (!rc) {
    print_summary(&fs, s);
    if (ride)
      cli_ride_psd_print(s, fs.psd);
    rc = cli_flush_stdout(&err);
  }
  free_study(&fs);
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
  if (points != floor(points) || points < 2 || points > (int)FB_STUDY_FREQ_MAX_POINTS)
    return cli_usage_error(argv[0], "--points: %s is not a whole number from 2 to %d",
                           opts[OPT_POINTS].value, (int)FB_STUDY_FREQ_MAX_POINTS);
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
