/* SPDX-License-Identifier: BSD-3-Clause */
/* The road as the input of a vehicle's frequency response: two tracks,
 * each a profile the wheels on it meet one after the other on a straight
 * run at the scenario's speed (the wheelbase filter of ride analysis:
 * Wong, "Theory of Ground Vehicles", 4th ed., 2008, ch. 7; Mitschke &
 * Wallentowitz, "Dynamik der Kraftfahrzeuge", 5th ed., 2014, ch. 32). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "flexbond/vehicle.h"

int fb_vehicle_rate_inputs(const fb_scenario *s, const fb_descriptor *ds, size_t *rate_input,
                           fb_err *err)
{
  if (ds->ninputs != s->ncorners)
    return fb_err_set(err, FB_EMODEL,
                      "the vehicle has %zu time-varying sources, expected the %zu road "
                      "velocities",
                      ds->ninputs, s->ncorners);
  for (size_t c = 0; c < s->ncorners; ++c) {
    char want[FB_ERR_KEY_MAX];
    snprintf(want, sizeof want, "road.v_%s", s->corner[c].name);
    size_t j = 0;
    while (j < ds->ninputs && strcmp(ds->input_names[j], want) != 0)
      ++j;
    if (j == ds->ninputs)
      return fb_err_set(err, FB_EMODEL, "no road velocity source '%s'", want);
    rate_input[c] = j;
  }
  return FB_OK;
}

double fb_vehicle_wheel_delay(const fb_scenario *s, size_t corner)
{
  double lead = s->corner[0].x;
  for (size_t c = 1; c < s->ncorners; ++c)
    lead = fmax(lead, s->corner[c].x);
  return (lead - s->corner[corner].x) / s->speed;
}

void fb_vehicle_track_inputs(const fb_scenario *s, const size_t *rate_input, double omega,
                             double *u)
{
  const size_t n = s->ncorners;
  memset(u, 0, 2 * FB_ROAD_NTRACKS * n * sizeof *u);
  for (size_t c = 0; c < n; ++c) {
    const int track = s->corner[c].y > 0 ? FB_ROAD_LEFT : FB_ROAD_RIGHT;
    /* h(t - tau) = e^{j omega (t - tau)}: its rate is j omega e^{-j omega tau}. */
    const double phase = -omega * fb_vehicle_wheel_delay(s, c);
    double *uc = u + 2 * ((size_t)track * n + rate_input[c]);
    uc[0] = -omega * sin(phase);
    uc[1] = omega * cos(phase);
  }
}
