/* SPDX-License-Identifier: BSD-3-Clause */
/* A vehicle's frequency response to the road (docs/frequency-response.md):
 * its linear descriptor form, at the static equilibrium when a law is
 * nonlinear, and H = C (j omega E - A)^-1 B for a road height on each
 * track (road_response.c's inputs). */
#include <stdlib.h>

#include "flexbond/bd.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "vehicle/vehicle_internal.h"

/* A nonlinear vehicle's descriptor form at its static equilibrium under
 * gravity, reached from the initial state as flexbond run --initial
 * static does (fb_sim_static_state). */
static int linearise(fb_bd *bd, fb_descriptor **ds, fb_err *err)
{
  const size_t n = fb_bd_nstates(bd);
  double *x0 = malloc((n + 1) * sizeof *x0), *x = malloc((n + 1) * sizeof *x);
  int rc = x0 && x ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc) {
    fb_bd_initial_state(bd, x0);
    rc = fb_sim_static_state(bd, 0.0, x0, x, err);
  }
  if (!rc)
    rc = fb_bd_descriptor_at(bd, 0.0, x, ds, err);
  free(x0);
  free(x);
  return rc;
}

int fb_vehicle_diagram_descriptor(fb_bd *bd, fb_descriptor **out, fb_err *err)
{
  return fb_bd_is_linear(bd) ? fb_bd_descriptor(bd, out, err) : linearise(bd, out, err);
}

void fb_scenario_tires_in_contact(fb_scenario *s)
{
  for (size_t c = 0; c < s->ncorners; ++c) {
    const fb_tire_model *linear = fb_corner_tire_model(&s->corner[c])->in_contact;
    if (linear) /* a model of a sound gallery: its in_contact is sound */
      fb_corner_set_tire(&s->corner[c], linear, NULL, NULL);
  }
}

typedef struct track_ctx {
  const fb_scenario *s;
  const size_t *rate_input;
} track_ctx;

static void track_input(void *ctx, double omega, double *u)
{
  const track_ctx *t = ctx;
  fb_vehicle_track_inputs(t->s, t->rate_input, omega, u);
}

int fb_vehicle_freq_response(const fb_scenario *s, const fb_descriptor *ds,
                             const double *freq_hz, size_t nfreq, double *h, fb_err *err)
{
  size_t *rate_input = calloc(s->ncorners + 1, sizeof *rate_input);
  if (!rate_input)
    return fb_err_set(err, FB_ENOMEM, "out of memory for a frequency response");
  int rc = fb_vehicle_rate_inputs(s, ds, rate_input, err);
  const track_ctx tc = {s, rate_input};
  if (!rc)
    rc = fb_descriptor_freq_response(ds, freq_hz, nfreq, FB_ROAD_NTRACKS, track_input,
                                     (void *)&tc, h, err);
  free(rate_input);
  return rc;
}
