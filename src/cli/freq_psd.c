/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond freq on a random road: the outputs' PSDs from the road's
 * spectrum and the frequency response, S_y(f) = sum over the tracks'
 * cross-spectra of H S_road H*, their r.m.s. values and the driver's
 * ISO 2631-1 weighted r.m.s. a_w from the Wk-weighted PSD, without a time
 * run (docs/frequency-response.md, "Ride from a road spectrum"), as the
 * study layer computes them (fb_study_ride_psd), written:
 *   DIR/psd_systemN.csv   frequency [Hz], the road's PSD, each output's PSD
 *   DIR/ride_psd.json     the road, its tracks (independent or identical), a_w
 *                         and the r.m.s. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/escape.h"
#include "flexbond/io.h"
#include "flexbond/study.h"

#include "cli.h"

/* "unit^2/Hz", parenthesised for a compound unit. */
static void psd_unit(const char *unit, char *buf, size_t size)
{
  snprintf(buf, size, strpbrk(unit, "/ *^") ? "(%s)^2/Hz" : "%s^2/Hz", unit);
}

typedef struct psd_csv {
  const fb_scenario *s;
  const fb_study_ride_psd *r;
} psd_csv;

static void write_psd_header(FILE *fp, const psd_csv *c)
{
  const fb_scenario *s = c->s;
  const size_t acc = fb_study_ride_psd_a_w_output(c->r);
  fputs("frequency [Hz],road [m^2/Hz]", fp);
  for (size_t o = 0; o < s->noutputs; ++o) {
    if (!fb_study_ride_psd_output(c->r, o))
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
}

static void write_psd_csv(FILE *fp, const void *ctx)
{
  const psd_csv *c = ctx;
  const fb_study_ride_psd *r = c->r;
  const size_t acc = fb_study_ride_psd_a_w_output(r);
  write_psd_header(fp, c);
  for (size_t k = 0; k < fb_study_ride_psd_nfreq(r); ++k) {
    fprintf(fp, "%.10g,%.10g", fb_study_ride_psd_hz(r)[k], fb_study_ride_psd_road_psd(r)[k]);
    for (size_t o = 0; o < c->s->noutputs; ++o) {
      const double *y = fb_study_ride_psd_output(r, o);
      if (!y)
        continue;
      fprintf(fp, ",%.10g", y[k]);
      if (o == acc)
        fprintf(fp, ",%.10g", fb_study_ride_psd_weighted(r)[k]);
    }
    fputc('\n', fp);
  }
}

static void write_system_json(FILE *fp, const fb_scenario *s, const fb_study_ride_psd *r)
{
  const size_t acc = fb_study_ride_psd_a_w_output(r);
  fprintf(fp, "    \"linearised\": %s,\n    \"a_w_rms\": ",
          fb_study_ride_psd_linearised(r) ? "true" : "false");
  fb_json_write_number(fp, fb_study_ride_psd_a_w(r));
  fputs(",\n    \"a_w_output\": ", fp);
  if (acc < s->noutputs)
    cli_json_string(fp, s->output[acc].name);
  else
    fputs("null", fp);
  fputs(",\n    \"rms\": {", fp);
  int first = 1;
  for (size_t o = 0; o < s->noutputs; ++o) {
    if (!fb_study_ride_psd_output(r, o))
      continue;
    fputs(first ? "\n      " : ",\n      ", fp);
    first = 0;
    cli_json_string(fp, s->output[o].name);
    fputs(": ", fp);
    fb_json_write_number(fp, fb_study_ride_psd_rms(r, o));
  }
  fputs("\n    }", fp);
}

typedef struct ride_json {
  const fb_scenario *s;
  fb_study_ride_psd *const *r; /* CLI_MAX_SYSTEMS, NULL: not run */
} ride_json;

static void write_ride_json(FILE *fp, const void *ctx)
{
  const ride_json *rj = ctx;
  const fb_study_psd_road *p = fb_study_ride_psd_road(rj->r[0] ? rj->r[0] : rj->r[1]);
  fprintf(fp, "{\n  \"road\": {\"class\": \"%c\", \"gd0_m3\": ", p->road_class);
  fb_json_write_number(fp, p->gd0);
  fputs(", \"band_cycles_per_m\": [", fp);
  fb_json_write_number(fp, p->n_min);
  fputs(", ", fp);
  fb_json_write_number(fp, p->n_max);
  fputs("], \"speed_m_s\": ", fp);
  fb_json_write_number(fp, p->speed);
  fprintf(fp, ", \"tracks\": \"%s\"}", p->identical ? "identical" : "independent");
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys) {
    if (!rj->r[sys])
      continue;
    fprintf(fp, ",\n  \"system%d\": {\n", sys + 1);
    write_system_json(fp, rj->s, rj->r[sys]);
    fputs("\n  }", fp);
  }
  fputs("\n}\n", fp);
}

int cli_ride_psd_write(cli_outdir *od, const fb_scenario *s,
                       fb_study_ride_psd *const r[CLI_MAX_SYSTEMS], fb_err *err)
{
  int rc = FB_OK;
  for (int sys = 0; sys < CLI_MAX_SYSTEMS && !rc; ++sys) {
    if (!r[sys])
      continue;
    const psd_csv c = {s, r[sys]};
    rc = cli_outdir_write(od, sys ? "psd_system2.csv" : "psd_system1.csv", write_psd_csv, &c,
                          err);
  }
  const ride_json rj = {s, r};
  return rc ? rc : cli_outdir_write(od, "ride_psd.json", write_ride_json, &rj, err);
}

static void print_system(const fb_scenario *s, const fb_study_ride_psd *r, int sys)
{
  const size_t acc = fb_study_ride_psd_a_w_output(r);
  printf("  %s:", cli_system_label(sys ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID));
  if (acc < s->noutputs)
    printf(" a_w %.4g m/s^2 (%s);", fb_study_ride_psd_a_w(r), s->output[acc].name);
  else
    printf(" no a_w (no output of signal acc);");
  printf(" r.m.s.");
  for (size_t o = 0; o < s->noutputs; ++o)
    if (fb_study_ride_psd_output(r, o))
      printf(" %s %.4g %s", s->output[o].name, fb_study_ride_psd_rms(r, o), s->output[o].unit);
  printf("\n");
}

void cli_ride_psd_print(const fb_scenario *s, fb_study_ride_psd *const r[CLI_MAX_SYSTEMS])
{
  const fb_study_ride_psd *any = r[0] ? r[0] : r[1];
  if (!any)
    return;
  const fb_study_psd_road *p = fb_study_ride_psd_road(any);
  const double *f = fb_study_ride_psd_hz(any);
  printf("ride from the road spectrum: ISO 8608 class %c, %g to %g cycles/m (%.3g to %.3g Hz), "
         "%s tracks\n",
         p->road_class, p->n_min, p->n_max, f[0], f[fb_study_ride_psd_nfreq(any) - 1],
         p->identical ? "identical" : "independent");
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys)
    if (r[sys])
      print_system(s, r[sys], sys);
}
