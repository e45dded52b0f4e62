/* SPDX-License-Identifier: BSD-3-Clause */
/* The study layer's frequency response of a vehicle (flexbond/study.h):
 * its linear model, kept for a ride from a road spectrum, and its response
 * to each track's road height, for every front end alike. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/study.h"

#include "study_internal.h"

/* Evenly spaced in log f, interpolated between the logarithms: the ratio
 * f_max / f_min itself may overflow (1e9 / 1e-300). */
void fb_study_freq_log_grid(double f_min, double f_max, size_t n, double *freq_hz)
{
  const double log_min = log(f_min), log_max = log(f_max);
  for (size_t k = 0; k < n; ++k)
    freq_hz[k] =
        exp(log_min + (log_max - log_min) * (n > 1 ? (double)k / (double)(n - 1) : 0.0));
  freq_hz[0] = f_min;
  if (n > 1)
    freq_hz[n - 1] = f_max;
}

int fb_study_response_alloc(const fb_descriptor *ds, size_t nfreq, double **h, fb_err *err)
{
  *h = malloc((2 * FB_ROAD_NTRACKS * ds->nrows_c * nfreq + 1) * sizeof **h);
  return *h ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory for a frequency response");
}

int fb_study_freq_new(fb_vehicle *v, const double *freq_hz, size_t nfreq, fb_study_freq **out,
                      fb_err *err)
{
  *out = NULL;
  if (nfreq > FB_STUDY_FREQ_MAX_POINTS)
    return fb_err_set(err, FB_EINVAL, "%zu frequencies: at most %zu", nfreq,
                      FB_STUDY_FREQ_MAX_POINTS);
  fb_study_freq *f = calloc(1, sizeof *f);
  if (!f)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  f->s = fb_vehicle_scenario(v);
  f->nfreq = nfreq;
  f->freq_hz = malloc((nfreq + 1) * sizeof *f->freq_hz);
  int rc = f->freq_hz ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc && nfreq)
    memcpy(f->freq_hz, freq_hz, nfreq * sizeof *freq_hz);
  if (!rc)
    rc = fb_vehicle_linearise(v, &f->ds, err);
  if (!rc)
    rc = fb_study_response_alloc(f->ds, nfreq, &f->h, err);
  if (!rc && nfreq)
    rc = fb_vehicle_freq_response(f->s, f->ds, f->freq_hz, nfreq, f->h, err);
  if (rc)
    fb_study_freq_free(&f);
  *out = f;
  return rc;
}

void fb_study_freq_free(fb_study_freq **f)
{
  if (!f || !*f)
    return;
  fb_descriptor_free(&(*f)->ds);
  free((*f)->freq_hz);
  free((*f)->h);
  free(*f);
  *f = NULL;
}

const double *fb_study_response_at(const fb_descriptor *ds, const double *h, size_t o,
                                   int track, size_t k)
{
  if (o >= ds->noutputs || ds->output_is_product[o] || track < 0 || track >= FB_ROAD_NTRACKS)
    return NULL;
  /* fb_descriptor_freq_response's layout: frequency, then case, then row. */
  return h + 2 * ((k * FB_ROAD_NTRACKS + (size_t)track) * ds->nrows_c + ds->output_row[o]);
}

const fb_scenario *fb_study_freq_scenario(const fb_study_freq *f)
{
  return f->s;
}

size_t fb_study_freq_nfreq(const fb_study_freq *f)
{
  return f->nfreq;
}

const double *fb_study_freq_hz(const fb_study_freq *f)
{
  return f->freq_hz;
}

int fb_study_freq_linearised(const fb_study_freq *f)
{
  return f->ds->linearised;
}

int fb_study_freq_has_output(const fb_study_freq *f, size_t o)
{
  return o < f->ds->noutputs && !f->ds->output_is_product[o];
}

const double *fb_study_freq_at(const fb_study_freq *f, size_t o, int track, size_t k)
{
  return k < f->nfreq ? fb_study_response_at(f->ds, f->h, o, track, k) : NULL;
}

double fb_study_freq_peak(const fb_study_freq *f, size_t o, size_t *k, int *track)
{
  if (!fb_study_freq_has_output(f, o))
    return NAN;
  double big = -1.0;
  for (size_t i = 0; i < f->nfreq; ++i)
    for (int t = 0; t < FB_ROAD_NTRACKS; ++t) {
      const double *z = fb_study_freq_at(f, o, t, i);
      if (hypot(z[0], z[1]) > big) {
        big = hypot(z[0], z[1]);
        if (k)
          *k = i;
        if (track)
          *track = t;
      }
    }
  return f->nfreq ? big : NAN;
}
