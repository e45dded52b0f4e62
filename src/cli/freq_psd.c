/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond freq on a random road: the outputs' PSDs from the road's
 * spectrum and the frequency response, S_y(f) = sum over the tracks'
 * cross-spectra of H S_road H*, their r.m.s. values and the driver's
 * ISO 2631-1 weighted r.m.s. a_w from the Wk-weighted PSD, without a time
 * run (docs/frequency-response.md, "Ride from a road spectrum"):
 *   DIR/psd_systemN.csv   frequency [Hz], the road's PSD, each output's PSD
 *   DIR/ride_psd.json     the road, its tracks (independent or identical), a_w
 *                         and the r.m.s. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/escape.h"
#include "flexbond/ride.h"
#include "flexbond/road.h"

#include "freq.h"

/* Frequencies over the road's band: enough that the trapezoidal rule in
 * log f resolves the narrowest resonance (the wheel hop, damping ratio
 * 0.2 or more: a width of 40 % of its frequency) with some 30 points. */
enum { PSD_POINTS = 600 };

int cli_freq_psd_setup(freq_study *fs, char road_class, int identical, fb_err *err)
{
  const fb_scenario *s = fs->s;
  freq_psd *p = &fs->psd;
  fb_road_iso8608_params iso;
  fb_road_iso8608_defaults(&iso);
  const int random = !road_class && fb_scenario_road_random(s, &iso);
  if (!random && !road_class)
    return FB_OK;
  if (!random)
    iso.road_class = road_class;
  int rc = fb_road_iso8608_gd0(iso.road_class, &p->gd0, err);
  if (rc)
    return rc;
  p->on = 1;
  p->road_class = (char)toupper((unsigned char)iso.road_class);
  p->n_min = iso.n_min;
  p->n_max = iso.n_max;
  p->identical = identical;
  p->nfreq = PSD_POINTS;
  p->freq_hz = malloc(PSD_POINTS * sizeof *p->freq_hz);
  if (!p->freq_hz)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  const double lo = s->speed * p->n_min, hi = s->speed * p->n_max;
  for (size_t k = 0; k < PSD_POINTS; ++k)
    p->freq_hz[k] = lo * pow(hi / lo, (double)k / (PSD_POINTS - 1));
  return FB_OK;
}

int cli_freq_psd_respond(freq_study *fs, int sys, const fb_descriptor *ds, fb_err *err)
{
  freq_psd *p = &fs->psd;
  p->h[sys] = malloc((2 * NTRACKS * ds->nrows_c * p->nfreq + 1) * sizeof *p->h[sys]);
  if (!p->h[sys])
    return fb_err_set(err, FB_ENOMEM, "out of memory for a frequency response");
  return fb_vehicle_freq_response(fs->s, ds, p->freq_hz, p->nfreq, p->h[sys], err);
}

void cli_freq_psd_free(freq_psd *p)
{
  free(p->freq_hz);
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys)
    free(p->h[sys]);
}

/* The PSD of output o of system sys at band frequency k (its unit^2/Hz):
 * each track a realisation of the road's PSD, independent or identical
 * (fb_ride_two_track_psd). */
static double output_psd(const freq_study *fs, int sys, size_t o, size_t k)
{
  const freq_psd *p = &fs->psd;
  const size_t r = fs->row[sys][o], n = fs->nrows[sys];
  return fb_ride_two_track_psd(cli_freq_amplitude(p->h[sys], n, k, FB_ROAD_LEFT, r),
                               cli_freq_amplitude(p->h[sys], n, k, FB_ROAD_RIGHT, r),
                               fb_ride_road_psd(p->gd0, fs->s->speed, p->freq_hz[k]),
                               p->identical);
}

/* The r.m.s. of output o (Wk-weighted when weighted is 1), NAN for a power
 * output; *psd is scratch of nfreq values. */
static double output_rms(const freq_study *fs, int sys, size_t o, int weighted, double *psd)
{
  if (fs->row[sys][o] == (size_t)-1)
    return NAN;
  const freq_psd *p = &fs->psd;
  for (size_t k = 0; k < p->nfreq; ++k) {
    const double w = weighted ? fb_ride_wk_magnitude(p->freq_hz[k]) : 1.0;
    psd[k] = w * w * output_psd(fs, sys, o, k);
  }
  return sqrt(fb_ride_psd_integral(p->freq_hz, psd, p->nfreq));
}

/* "unit^2/Hz", parenthesised for a compound unit. */
static void psd_unit(const char *unit, char *buf, size_t size)
{
  snprintf(buf, size, strpbrk(unit, "/ *^") ? "(%s)^2/Hz" : "%s^2/Hz", unit);
}

typedef struct psd_csv {
  const freq_study *fs;
  int sys;
} psd_csv;

static void write_psd_csv(FILE *fp, const void *ctx)
{
  const psd_csv *c = ctx;
  const freq_study *fs = c->fs;
  const fb_scenario *s = fs->s;
  const size_t acc = fb_study_ride_output(s);
  fputs("frequency [Hz],road [m^2/Hz]", fp);
  for (size_t o = 0; o < s->noutputs; ++o) {
    if (fs->row[c->sys][o] == (size_t)-1)
      continue;
    char unit[80];
    psd_unit(s->output[o].unit, unit, sizeof unit);
    const char *parts[] = {s->output[o].name, " [", unit, "]"};
    fputc(',', fp);
    fb_csv_write_field_parts(fp, parts, 4, FB_CSV_TEXT);
    if (o == acc) {
      const char *w[] = {s->output[o].name, " Wk-weighted [", unit, "]"};
      fputc(',', fp);
      fb_csv_write_field_parts(fp, w, 4, FB_CSV_TEXT);
    }
  }
  fputc('\n', fp);
  for (size_t k = 0; k < fs->psd.nfreq; ++k) {
    const double f = fs->psd.freq_hz[k];
    fprintf(fp, "%.10g,%.10g", f, fb_ride_road_psd(fs->psd.gd0, s->speed, f));
    for (size_t o = 0; o < s->noutputs; ++o) {
      if (fs->row[c->sys][o] == (size_t)-1)
        continue;
      const double y = output_psd(fs, c->sys, o, k);
      fprintf(fp, ",%.10g", y);
      if (o == acc) {
        const double w = fb_ride_wk_magnitude(f);
        fprintf(fp, ",%.10g", w * w * y);
      }
    }
    fputc('\n', fp);
  }
}

static void write_system_json(FILE *fp, const freq_study *fs, int sys, double *scratch)
{
  const fb_scenario *s = fs->s;
  const size_t acc = fb_study_ride_output(s);
  fprintf(fp,
          "    \"linearised\": %s,\n    \"a_w_rms\": ", fs->linearised[sys] ? "true" : "false");
  fb_json_write_number(fp, acc < s->noutputs ? output_rms(fs, sys, acc, 1, scratch) : NAN);
  fputs(",\n    \"a_w_output\": ", fp);
  if (acc < s->noutputs)
    cli_json_string(fp, s->output[acc].name);
  else
    fputs("null", fp);
  fputs(",\n    \"rms\": {", fp);
  int first = 1;
  for (size_t o = 0; o < s->noutputs; ++o) {
    if (fs->row[sys][o] == (size_t)-1)
      continue;
    fputs(first ? "\n      " : ",\n      ", fp);
    first = 0;
    cli_json_string(fp, s->output[o].name);
    fputs(": ", fp);
    fb_json_write_number(fp, output_rms(fs, sys, o, 0, scratch));
  }
  fputs("\n    }", fp);
}

typedef struct ride_json {
  const freq_study *fs;
  double *scratch; /* nfreq values */
} ride_json;

static void write_ride_json(FILE *fp, const void *ctx)
{
  const ride_json *rj = ctx;
  const freq_study *fs = rj->fs;
  const freq_psd *p = &fs->psd;
  fprintf(fp, "{\n  \"road\": {\"class\": \"%c\", \"gd0_m3\": ", p->road_class);
  fb_json_write_number(fp, p->gd0);
  fputs(", \"band_cycles_per_m\": [", fp);
  fb_json_write_number(fp, p->n_min);
  fputs(", ", fp);
  fb_json_write_number(fp, p->n_max);
  fputs("], \"speed_m_s\": ", fp);
  fb_json_write_number(fp, fs->s->speed);
  fprintf(fp, ", \"tracks\": \"%s\"}", p->identical ? "identical" : "independent");
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys) {
    if (!fs->ran[sys])
      continue;
    fprintf(fp, ",\n  \"system%d\": {\n", sys + 1);
    write_system_json(fp, fs, sys, rj->scratch);
    fputs("\n  }", fp);
  }
  fputs("\n}\n", fp);
}

int cli_freq_psd_write(cli_outdir *od, const freq_study *fs, fb_err *err)
{
  int rc = FB_OK;
  for (int sys = 0; sys < CLI_MAX_SYSTEMS && !rc; ++sys) {
    if (!fs->ran[sys])
      continue;
    const psd_csv c = {fs, sys};
    rc = cli_outdir_write(od, sys ? "psd_system2.csv" : "psd_system1.csv", write_psd_csv, &c,
                          err);
  }
  const ride_json rj = {fs, rc ? NULL : malloc((fs->psd.nfreq + 1) * sizeof(double))};
  if (!rc && !rj.scratch)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = cli_outdir_write(od, "ride_psd.json", write_ride_json, &rj, err);
  free(rj.scratch);
  return rc;
}

void cli_freq_psd_print(const freq_study *fs)
{
  const fb_scenario *s = fs->s;
  const freq_psd *p = &fs->psd;
  double *scratch = malloc((p->nfreq + 1) * sizeof *scratch);
  if (!scratch)
    return;
  printf("ride from the road spectrum: ISO 8608 class %c, %g to %g cycles/m (%.3g to %.3g Hz), "
         "%s tracks\n",
         p->road_class, p->n_min, p->n_max, p->freq_hz[0], p->freq_hz[p->nfreq - 1],
         p->identical ? "identical" : "independent");
  const size_t acc = fb_study_ride_output(s);
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys) {
    if (!fs->ran[sys])
      continue;
    printf("  %s:", cli_system_label(sys ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID));
    if (acc < s->noutputs)
      printf(" a_w %.4g m/s^2 (%s);", output_rms(fs, sys, acc, 1, scratch),
             s->output[acc].name);
    else
      printf(" no a_w (no output of signal acc);");
    printf(" r.m.s.");
    for (size_t o = 0; o < s->noutputs; ++o)
      if (fs->row[sys][o] != (size_t)-1)
        printf(" %s %.4g %s", s->output[o].name, output_rms(fs, sys, o, 0, scratch),
               s->output[o].unit);
    printf("\n");
  }
  free(scratch);
}
