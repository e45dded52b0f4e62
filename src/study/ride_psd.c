/* SPDX-License-Identifier: BSD-3-Clause */
/* The study layer's ride from a road spectrum (flexbond/study.h): the
 * outputs' PSDs from an ISO 8608 road's spectrum and the vehicle's
 * frequency response, S_y(f) = sum over the tracks' cross-spectra of
 * H S_road H* (Bendat & Piersol, "Random Data", 4th ed., sec. 6.1), their
 * r.m.s. values and the driver's ISO 2631-1 weighted r.m.s. a_w from the
 * Wk-weighted PSD (ISO 2631-1:1997, 6.4.2: a_w is the r.m.s. of the
 * weighted acceleration), without a time run. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>

#include "flexbond/study.h"

#include "study_internal.h"

struct fb_study_ride_psd {
  fb_study_psd_road road;
  int linearised;
  size_t noutputs, nfreq;
  double *freq_hz;  /* nfreq */
  double *road_psd; /* nfreq, m^2/Hz per track */
  double **psd;     /* noutputs: each output's PSD (nfreq), NULL for a power */
  double *rms;      /* noutputs */
  size_t a_w_output;
  double *weighted; /* nfreq: a_w's output Wk-weighted, NULL when none */
  double a_w;
};

/* The one place that reads the scenario's road: its kind and ISO 8608
 * parameters. */
int fb_study_ride_psd_iso8608(const fb_scenario *s, char road_class,
                              fb_road_iso8608_params *iso)
{
  fb_road_iso8608_defaults(iso);
  if (road_class) {
    iso->road_class = road_class;
    return 1;
  }
  return fb_scenario_road_random(s, iso);
}

static int ride_road(const fb_scenario *s, const fb_road_iso8608_params *iso, int identical,
                     fb_study_psd_road *road, fb_err *err)
{
  int rc = fb_road_iso8608_params_gd0(iso, &road->gd0, err);
  if (rc)
    return rc;
  if (!(iso->n_min > 0.0 && iso->n_max > iso->n_min && isfinite(iso->n_max)))
    return fb_err_set(err, FB_EINVAL,
                      "the road's band %g to %g cycles/m is not 0 < n_min < n_max", iso->n_min,
                      iso->n_max);
  road->road_class = (char)toupper((unsigned char)iso->road_class);
  road->n_min = iso->n_min;
  road->n_max = iso->n_max;
  road->speed = s->speed;
  road->identical = identical != 0;
  return FB_OK;
}

/* Output o's PSD at every band frequency from the response h of ds. */
static void output_psd(const fb_study_ride_psd *r, const fb_descriptor *ds, const double *h,
                       size_t o, double *psd)
{
  for (size_t k = 0; k < r->nfreq; ++k)
    psd[k] = fb_ride_two_track_psd(fb_study_response_at(ds, h, o, FB_ROAD_LEFT, k),
                                   fb_study_response_at(ds, h, o, FB_ROAD_RIGHT, k),
                                   r->road_psd[k], r->road.identical);
}

/* Every output's PSD and r.m.s., then a_w from the ride output's. */
static int spectra(fb_study_ride_psd *r, const fb_descriptor *ds, const double *h, fb_err *err)
{
  for (size_t o = 0; o < r->noutputs; ++o) {
    r->rms[o] = NAN;
    if (ds->output_is_product[o])
      continue;
    r->psd[o] = malloc((r->nfreq + 1) * sizeof *r->psd[o]);
    if (!r->psd[o])
      return fb_err_set(err, FB_ENOMEM, "out of memory for a PSD");
    output_psd(r, ds, h, o, r->psd[o]);
    r->rms[o] = sqrt(fb_ride_psd_integral(r->freq_hz, r->psd[o], r->nfreq));
  }
  r->a_w = NAN;
  if (r->a_w_output >= r->noutputs || !r->psd[r->a_w_output])
    return FB_OK;
  r->weighted = malloc((r->nfreq + 1) * sizeof *r->weighted);
  if (!r->weighted)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a PSD");
  for (size_t k = 0; k < r->nfreq; ++k) {
    const double w = fb_ride_wk_magnitude(r->freq_hz[k]);
    r->weighted[k] = w * w * r->psd[r->a_w_output][k];
  }
  r->a_w = sqrt(fb_ride_psd_integral(r->freq_hz, r->weighted, r->nfreq));
  return FB_OK;
}

/* The band's frequencies and the road's PSD there, then the response. */
static int respond(fb_study_ride_psd *r, const fb_study_freq *lin, double **h, fb_err *err)
{
  r->freq_hz = malloc(r->nfreq * sizeof *r->freq_hz);
  r->road_psd = malloc(r->nfreq * sizeof *r->road_psd);
  r->psd = calloc(r->noutputs + 1, sizeof *r->psd);
  r->rms = calloc(r->noutputs + 1, sizeof *r->rms);
  if (!r->freq_hz || !r->road_psd || !r->psd || !r->rms)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  const fb_study_psd_road *road = &r->road;
  fb_study_freq_log_grid(road->speed * road->n_min, road->speed * road->n_max, r->nfreq,
                         r->freq_hz);
  for (size_t k = 0; k < r->nfreq; ++k)
    r->road_psd[k] = fb_ride_road_psd(road->gd0, road->speed, r->freq_hz[k]);
  int rc = fb_study_response_alloc(lin->ds, r->nfreq, h, err);
  return rc ? rc : fb_vehicle_freq_response(lin->s, lin->ds, r->freq_hz, r->nfreq, *h, err);
}

int fb_study_ride_psd_new(const fb_study_freq *lin, const fb_road_iso8608_params *iso,
                          int identical, fb_study_ride_psd **out, fb_err *err)
{
  *out = NULL;
  fb_study_ride_psd *r = calloc(1, sizeof *r);
  if (!r)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  r->linearised = lin->ds->linearised;
  r->noutputs = lin->s->noutputs;
  r->nfreq = FB_STUDY_RIDE_PSD_POINTS;
  r->a_w_output = fb_study_ride_output(lin->s);
  double *h = NULL;
  int rc = ride_road(lin->s, iso, identical, &r->road, err);
  if (!rc)
    rc = respond(r, lin, &h, err);
  if (!rc)
    rc = spectra(r, lin->ds, h, err);
  free(h);
  if (rc)
    fb_study_ride_psd_free(&r);
  *out = r;
  return rc;
}

void fb_study_ride_psd_free(fb_study_ride_psd **r)
{
  if (!r || !*r)
    return;
  for (size_t o = 0; (*r)->psd && o < (*r)->noutputs; ++o)
    free((*r)->psd[o]);
  free((*r)->psd);
  free((*r)->rms);
  free((*r)->weighted);
  free((*r)->road_psd);
  free((*r)->freq_hz);
  free(*r);
  *r = NULL;
}

const fb_study_psd_road *fb_study_ride_psd_road(const fb_study_ride_psd *r)
{
  return &r->road;
}

int fb_study_ride_psd_linearised(const fb_study_ride_psd *r)
{
  return r->linearised;
}

size_t fb_study_ride_psd_nfreq(const fb_study_ride_psd *r)
{
  return r->nfreq;
}

const double *fb_study_ride_psd_hz(const fb_study_ride_psd *r)
{
  return r->freq_hz;
}

const double *fb_study_ride_psd_road_psd(const fb_study_ride_psd *r)
{
  return r->road_psd;
}

const double *fb_study_ride_psd_output(const fb_study_ride_psd *r, size_t o)
{
  return o < r->noutputs ? r->psd[o] : NULL;
}

double fb_study_ride_psd_rms(const fb_study_ride_psd *r, size_t o)
{
  return o < r->noutputs ? r->rms[o] : NAN;
}

size_t fb_study_ride_psd_a_w_output(const fb_study_ride_psd *r)
{
  return r->a_w_output;
}

const double *fb_study_ride_psd_weighted(const fb_study_ride_psd *r)
{
  return r->weighted;
}

double fb_study_ride_psd_a_w(const fb_study_ride_psd *r)
{
  return r->a_w;
}
