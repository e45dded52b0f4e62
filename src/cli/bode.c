/* SPDX-License-Identifier: BSD-3-Clause */
/* The Bode figures of a frequency response (fb_study_freq), drawn by
 * flexbond freq and by flexbond run for its report:
 *   DIR/bode_<OUTPUT>.png   |H| and phase, both systems and tracks overlaid */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/io.h"

#include "cli.h"

const char *const cli_track_names[FB_ROAD_NTRACKS] = {"left", "right"};

void cli_gain_unit(const char *unit, char *buf, size_t size)
{
  if (!unit) { /* a bond's output: its unit is its domain's, which the scenario does not hold */
    snprintf(buf, size, "per m");
    return;
  }
  const int compound = strpbrk(unit, "/ *") != NULL;
  snprintf(buf, size, compound ? "(%s)/m" : "%s/m", unit);
}

/* Not unwrapped: the wheelbase filter's notches are zeros close to the
 * imaginary axis, across which the phase has no one continuation. */
double cli_phase_deg(const double z[2])
{
  return atan2(z[1], z[0]) * 180.0 / 3.14159265358979323846;
}

/* The curves of one output's figure: |H| and phase per system and track. */
typedef struct bode {
  double *mag[CLI_MAX_SYSTEMS][FB_ROAD_NTRACKS], *phase[CLI_MAX_SYSTEMS][FB_ROAD_NTRACKS];
  fb_plot_xy_series ms[2 * FB_ROAD_NTRACKS], ps[2 * FB_ROAD_NTRACKS];
  char legend[2 * FB_ROAD_NTRACKS][48];
  size_t n;
} bode;

static int add_curve(bode *b, const fb_study_freq *f, int sys, int t, size_t o, fb_err *err)
{
  const size_t nfreq = fb_study_freq_nfreq(f);
  double *mag = malloc((nfreq + 1) * sizeof *mag), *phase = malloc((nfreq + 1) * sizeof *phase);
  b->mag[sys][t] = mag;
  b->phase[sys][t] = phase;
  if (!mag || !phase)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a Bode figure");
  for (size_t k = 0; k < nfreq; ++k) {
    const double *z = fb_study_freq_at(f, o, t, k);
    mag[k] = hypot(z[0], z[1]);
    phase[k] = cli_phase_deg(z);
  }
  snprintf(b->legend[b->n], sizeof b->legend[b->n], "System %d, %s track", sys + 1,
           cli_track_names[t]);
  b->ms[b->n] = (fb_plot_xy_series){fb_study_freq_hz(f), mag, nfreq, b->legend[b->n]};
  b->ps[b->n] = (fb_plot_xy_series){fb_study_freq_hz(f), phase, nfreq, NULL}; /* key above */
  ++b->n;
  return FB_OK;
}

static int plot(cli_outdir *od, const fb_scenario *s, const bode *b, size_t o, int linearised,
                fb_err *err)
{
  char unit[64], ylabel[96], title[160], name[FB_ERR_KEY_MAX + 16];
  cli_gain_unit(s->output[o].unit, unit, sizeof unit);
  snprintf(ylabel, sizeof ylabel, "|H| [%s]", unit);
  snprintf(title, sizeof title, "%s: frequency response to the road (%.4g km/h)%s",
           s->output[o].name, 3.6 * s->speed,
           linearised ? ", linearised at the static equilibrium" : "");
  const fb_plot_xy_panel panels[2] = {
      {.series = b->ms, .nseries = b->n, .ylabel = ylabel, .unit = NULL, .log_y = 1},
      {.series = b->ps, .nseries = b->n, .ylabel = "phase [deg]", .unit = NULL, .log_y = 0}};
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
  char *path = cli_outdir_path(od, name, err);
  int rc = path ? fb_plot_xy_png(panels, 2, &opts, path, err) : err->code;
  if (!rc)
    return cli_outdir_keep(od, path, err);
  free(path);
  return rc;
}

static int draw(cli_outdir *od, fb_study_freq *const fr[CLI_MAX_SYSTEMS], size_t o, fb_err *err)
{
  bode b;
  memset(&b, 0, sizeof b);
  int rc = FB_OK, linearised = 0;
  const fb_scenario *s = NULL;
  for (int sys = 0; sys < CLI_MAX_SYSTEMS && !rc; ++sys)
    for (int t = 0; fr[sys] && t < FB_ROAD_NTRACKS && !rc; ++t) {
      s = fb_study_freq_scenario(fr[sys]);
      linearised |= fb_study_freq_linearised(fr[sys]);
      rc = add_curve(&b, fr[sys], sys, t, o, err);
    }
  if (!rc)
    rc = plot(od, s, &b, o, linearised, err);
  for (int sys = 0; sys < CLI_MAX_SYSTEMS; ++sys)
    for (int t = 0; t < FB_ROAD_NTRACKS; ++t) {
      free(b.mag[sys][t]);
      free(b.phase[sys][t]);
    }
  return rc;
}

int cli_bode_write_figures(cli_outdir *od, fb_study_freq *const fr[CLI_MAX_SYSTEMS],
                           fb_err *err)
{
  const fb_study_freq *any = fr[0] ? fr[0] : fr[1];
  if (!any)
    return FB_OK;
  const fb_scenario *s = fb_study_freq_scenario(any);
  int rc = FB_OK;
  for (size_t o = 0; !rc && o < s->noutputs; ++o)
    if (fb_study_freq_has_output(any, o))
      rc = draw(od, fr, o, err);
  return rc;
}
