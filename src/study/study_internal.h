/* SPDX-License-Identifier: BSD-3-Clause */
/* Shared by the study layer's frequency response (freq.c) and its ride
 * from a road spectrum (ride_psd.c). */
#ifndef FLEXBOND_STUDY_INTERNAL_H
#define FLEXBOND_STUDY_INTERNAL_H

#include <stddef.h>

#include "flexbond/bd.h"
#include "flexbond/study.h"

struct fb_study_freq {
  const fb_scenario *s; /* the vehicle's, borrowed */
  fb_descriptor *ds;    /* the linear model, owned */
  size_t nfreq;
  double *freq_hz; /* nfreq, owned */
  double *h;       /* fb_descriptor_freq_response's layout, owned */
};

/* Room for ds's response at nfreq frequencies on both tracks into *h
 * (new; free). */
int fb_study_response_alloc(const fb_descriptor *ds, size_t nfreq, double **h, fb_err *err);
/* Output o's complex amplitude on track at frequency k of a response h
 * of ds (fb_vehicle_freq_response's layout); NULL for a power output or
 * an index out of range. */
const double *fb_study_response_at(const fb_descriptor *ds, const double *h, size_t o,
                                   int track, size_t k);

#endif
