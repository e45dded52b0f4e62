/* SPDX-License-Identifier: BSD-3-Clause */
/* Shared by flexbond freq (freq.c) and its ride from a road spectrum
 * (freq_psd.c). */
#ifndef FLEXBOND_CLI_FREQ_H
#define FLEXBOND_CLI_FREQ_H

#include <stddef.h>

#include "flexbond/bd.h"
#include "flexbond/vehicle.h"

#include "cli.h"

enum { FREQ_MAX_POINTS = 100000, NTRACKS = FB_ROAD_NTRACKS };

/* The ride from a road spectrum: an ISO 8608 road (the scenario's, or the
 * class --road-class names, over ISO 8608's band), its tracks independent
 * (as fb_road_new_iso8608 makes them) or identical. */
typedef struct freq_psd {
  int on;
  char road_class;
  double gd0;          /* m^3, at 0.1 cycles/m */
  double n_min, n_max; /* band, cycles/m */
  int identical;       /* 1: both tracks one profile */
  size_t nfreq;        /* the band's frequencies, evenly spaced on a log scale */
  double *freq_hz;
  double *h[CLI_MAX_SYSTEMS]; /* the response there, fb_descriptor_freq_response's layout */
} freq_psd;

/* What the command computes. */
typedef struct freq_study { /* also struct freq_study in cli.h */
  const fb_scenario *s;     /* the caller's */
  size_t nfreq;
  double *freq_hz;
  int ran[CLI_MAX_SYSTEMS];        /* System 1, System 2 */
  int linearised[CLI_MAX_SYSTEMS]; /* 1: at the static equilibrium */
  double *h[CLI_MAX_SYSTEMS];      /* fb_descriptor_freq_response's layout */
  size_t nrows[CLI_MAX_SYSTEMS];
  size_t *row[CLI_MAX_SYSTEMS]; /* per output: its row of C, (size_t)-1 for a power */
  double seconds[CLI_MAX_SYSTEMS];
  freq_psd psd;
} freq_study;

/* Complex amplitude (re, im) of row r of C on track t at frequency k of a
 * response h with nrows rows and NTRACKS cases. */
static inline const double *cli_freq_amplitude(const double *h, size_t nrows, size_t k, int t,
                                               size_t r)
{
  return h + 2 * ((k * NTRACKS + (size_t)t) * nrows + r);
}

/* The response of the realised vehicles (System 1's, System 2's; NULL:
 * not asked) at points frequencies from f_min to f_max evenly spaced on a
 * log scale, and over the road's band when fs->psd is on. */
int cli_freq_compute(freq_study *fs, fb_vehicle *const vehicles[CLI_MAX_SYSTEMS], double f_min,
                     double f_max, size_t points, fb_err *err);
/* The Bode figures bode_<OUTPUT>.png, one per output with a response. */
int cli_freq_write_figures(cli_outdir *od, const freq_study *fs, fb_err *err);
void cli_freq_study_free(freq_study *fs);

/* Sets up fs->psd from the scenario's road or road_class (0: none) and
 * identical; FB_EINVAL for a class outside A .. H. */
int cli_freq_psd_setup(freq_study *fs, char road_class, int identical, fb_err *err);
/* The response of system sys over the road's band (fs->psd.h[sys]). */
int cli_freq_psd_respond(freq_study *fs, int sys, const fb_descriptor *ds, fb_err *err);
/* DIR/psd_systemN.csv and DIR/ride_psd.json. */
int cli_freq_psd_write(cli_outdir *od, const freq_study *fs, fb_err *err);
void cli_freq_psd_print(const freq_study *fs);
void cli_freq_psd_free(freq_psd *p);

#endif
