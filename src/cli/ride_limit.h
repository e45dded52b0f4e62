/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond ride-limit, inside the command (docs/ride-limit.md). The study
 * layer searches (fb_study_ride_limit); ride_limit_cases.c evaluates its
 * rounds of points as sweeps on the sweep's threads (fb_study_sweep, one
 * per round and system) and keeps every finished case in the journal a
 * killed study resumes from; ride_limit.c parses the command line and
 * writes the files. */
#ifndef FLEXBOND_CLI_RIDE_LIMIT_H
#define FLEXBOND_CLI_RIDE_LIMIT_H

#include <pthread.h>
#include <stdio.h>

#include "flexbond/study.h"
#include "flexbond/vehicle.h"

/* Most values of --vary (curves per system). */
enum { RL_MAX_VALUES = 1000 };

/* A finished case as the journal keeps it. */
typedef struct rl_done {
  int sys;      /* 0 rigid, 1 flexible */
  size_t value; /* index of the --vary value */
  double speed; /* m/s */
  int status;
  double metric;
  double wall_seconds; /* of its run; NaN read back from the journal */
  char *error;         /* owned; NULL when ok */
} rl_done;

typedef struct rl_args {
  const char *scenario_path, *out_dir;
  const char *vary_key; /* as given */
  char *vary_path;      /* the dotted path it names (owned) */
  char **values;        /* owned, nvalues */
  size_t nvalues;
  size_t metric, output; /* the metric's index in the study's table; the output's */
  fb_study_ride_limit_opts opts;
  double course_length, settle; /* m, s */
  fb_system systems[2];
  size_t nsystems, jobs;
  int quiet, figures, resume;
  fb_scenario *base; /* owned: the scenario as the file has it */
  const char *scenario_name;
  /* The cases finished (read back from the journal, then run), owned. */
  rl_done *done;
  size_t ndone, cap_done, nresumed, nrun;
  FILE *journal; /* DIR/ride_limit.partial.csv while the study runs */
  int journal_failed;
  /* Guards done, the journal and the progress lines (rl_record): rank 0
   * of an MPI job records its own runs and those of the other ranks at
   * once. */
  pthread_mutex_t lock;
  int mpi_size; /* ranks of the MPI job (--mpi), 0 without */
  /* Under --mpi, how a round's runs go to the ranks (rl_mpi_round, handed
   * in by the command so the cases need not call the transport that
   * calls them back); NULL on threads. */
  int (*mpi_round)(struct rl_args *a, const int *sys, const size_t *value, const double *speed,
                   size_t n, fb_err *err);
  /* Each curve's (system x value) first failure message, owned. */
  char **curve_error;
  fb_study_ride_limit_curve *curves;
} rl_args;

/* The curves: system s's value v is curve s * nvalues + v. */
size_t rl_ncurves(const rl_args *a);

/* fb_study_ride_limit_eval_fn over an rl_args: the points not yet in
 * a->done run as sweeps, a round's cases on a->jobs threads. */
int rl_eval(void *ctx, const fb_study_ride_limit_point *pts, size_t n, double *metric,
            fb_err *err);

/* Records a finished run (its error copied): a->done, the journal, its
 * progress line (rank >= 0: the rank that ran it), under a->lock. */
int rl_record(rl_args *a, const rl_done *d, int rank, fb_err *err);
/* The finished run of system sys, value v at speed (m/s), or NULL. */
const rl_done *rl_find_done(const rl_args *a, int sys, size_t v, double speed);
/* Loads each --vary value's scenario as its runs will (at the lowest
 * speed), so that a value the scenario refuses is refused before any
 * run: FB_OK, or the first value's error. */
int rl_check_values(rl_args *a, fb_err *err);
/* Runs the n runs of system sys (values value[], speeds speed[], m/s) as
 * one sweep on a->jobs threads, each recorded (rl_record). */
int rl_run_round(rl_args *a, int sys, const size_t *value, const double *speed, size_t n,
                 fb_err *err);

#ifdef FLEXBOND_MPI
/* ---- ride_limit_mpi.c (an MPI build): rank 0 hands a round's runs to
 * the ranks one at a time and runs runs itself on a thread; the other
 * ranks run what they are given. */
/* Rank 0: runs sys[i], value[i], speed[i] (i < n) across the ranks. */
int rl_mpi_round(rl_args *a, const int *sys, const size_t *value, const double *speed, size_t n,
                 fb_err *err);
/* Every other rank: runs the runs rank 0 gives until it says stop. */
void rl_mpi_work(rl_args *a);
/* Rank 0, at the end: every other rank stops. */
void rl_mpi_stop(int size);
#endif

/* DIR/ride_limit.partial.csv: opened (created) for the study; an existing
 * one is read back into a->done with a->resume (it must be of the same
 * study: same fingerprint), refused otherwise (FB_EINVAL). */
int rl_journal_open(rl_args *a, fb_err *err);
/* Closes it; removes the file when remove_file. */
void rl_journal_close(rl_args *a, int remove_file);
/* Its path, in fresh memory (NULL: out of memory). */
char *rl_journal_path(const rl_args *a);

#endif
