/* SPDX-License-Identifier: BSD-3-Clause */
/* Times the vehicle simulation of a scenario (fb_vehicle_simulate: block
 * diagram build, static state if asked, CVODE run with 1 kHz sampling),
 * RUNS times in one process, and prints each run's wall time, the calling
 * thread's CPU time (less disturbed than the wall time by other work on a
 * shared machine) and solver statistics. Usage: bench_vehicle
 * SCENARIO.yaml [RUNS] [rigid|flexible] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "flexbond/vehicle.h"

static double clock_seconds(clockid_t id)
{
  struct timespec ts;
  clock_gettime(id, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
  if (argc < 2) {
    fprintf(stderr, "usage: %s SCENARIO.yaml [RUNS] [rigid|flexible]\n", argv[0]);
    return 1;
  }
  int runs = argc > 2 ? atoi(argv[2]) : 11;
  fb_system sys =
      argc > 3 && strcmp(argv[3], "flexible") == 0 ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID;
  if (runs < 1)
    runs = 1;
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  if (fb_scenario_load(argv[1], &s, &err)) {
    fprintf(stderr, "%s\n", err.msg);
    return 1;
  }
  double *wall = malloc(2 * (size_t)runs * sizeof *wall), *cpu = wall + runs;
  int rc = wall ? 0 : 1;
  for (int i = 0; !rc && i < runs; ++i) {
    fb_result *r = NULL;
    double t0 = clock_seconds(CLOCK_MONOTONIC), c0 = clock_seconds(CLOCK_THREAD_CPUTIME_ID);
    rc = fb_vehicle_simulate(s, sys, &r, &err);
    wall[i] = clock_seconds(CLOCK_MONOTONIC) - t0;
    cpu[i] = clock_seconds(CLOCK_THREAD_CPUTIME_ID) - c0;
    if (rc) {
      fprintf(stderr, "%s\n", err.msg);
      break;
    }
    const fb_sim_stats *st = fb_result_stats(r);
    printf("run %d: %.2f ms (integration %.2f ms, cpu %.2f ms), %ld steps, %ld rhs evals, %ld "
           "Newton matrices, %ld factorisations\n",
           i + 1, 1e3 * wall[i], 1e3 * st->wall_seconds, 1e3 * cpu[i], st->steps, st->rhs_evals,
           st->newton_setups, st->factorizations);
    fb_result_free(&r);
  }
  if (!rc) {
    qsort(wall, (size_t)runs, sizeof *wall, cmp_double);
    qsort(cpu, (size_t)runs, sizeof *cpu, cmp_double);
    printf("median %.2f ms, min %.2f ms over %d runs (cpu: median %.2f ms)\n",
           1e3 * wall[runs / 2], 1e3 * wall[0], runs, 1e3 * cpu[runs / 2]);
  }
  free(wall);
  fb_scenario_free(&s);
  return rc;
}
