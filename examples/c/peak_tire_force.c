/* SPDX-License-Identifier: BSD-3-Clause */
/* A program on the installed library (docs/python.md has the same from
 * Python): load a scenario, simulate System 1, read one output.
 *
 *   cc peak_tire_force.c $(pkg-config --cflags --libs flexbond) -o peak
 *   ./peak examples/apc6x6.yaml tire_force_LF
 */
#include <stdio.h>
#include <stdlib.h>

#include <flexbond/sim.h>
#include <flexbond/vehicle.h>

int main(int argc, char **argv)
{
  if (argc != 3) {
    fprintf(stderr, "usage: %s SCENARIO.yaml OUTPUT\n", argv[0]);
    return 1;
  }
  fb_err err;
  fb_scenario *s = NULL; /* ours: fb_scenario_free */
  fb_result *r = NULL;   /* ours: fb_result_free */
  int rc = fb_scenario_load(argv[1], &s, &err);
  if (rc == FB_OK)
    rc = fb_vehicle_simulate(s, FB_SYSTEM_RIGID, &r, &err);
  const long col = rc == FB_OK ? fb_result_find(r, argv[2]) : -1;
  if (rc == FB_OK && col < 0)
    rc = fb_err_set(&err, FB_EINVAL, "no output '%s'", argv[2]);
  if (rc == FB_OK) {
    double peak = fb_result_row(r, 0)[col], t_peak = 0.0;
    for (size_t k = 1; k < fb_result_nsamples(r); ++k) {
      const double *row = fb_result_row(r, k); /* t, then the outputs */
      if (row[col] > peak) {
        peak = row[col];
        t_peak = row[0];
      }
    }
    printf("%s: peak %.6g %s at t = %.4g s\n", argv[2], peak,
           fb_result_col_unit(r, (size_t)col), t_peak);
  } else {
    fprintf(stderr, "%s\n", err.msg);
  }
  fb_result_free(&r);
  fb_scenario_free(&s);
  return rc == FB_OK ? 0 : 2;
}
