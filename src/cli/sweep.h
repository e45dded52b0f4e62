/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond sweep, inside the command (docs/sweep.md): the study, its
 * cases and their metrics (sweep_case.c), the journal a killed sweep
 * resumes from (sweep_journal.c), the pool that runs the cases on
 * threads (sweep_pool.c) and, in an MPI build, across ranks
 * (sweep_mpi.c). sweep.c parses the command line and writes the files. */
#ifndef FLEXBOND_CLI_SWEEP_H
#define FLEXBOND_CLI_SWEEP_H

#include <pthread.h>
#include <stdint.h>
#include <stdio.h>

#include "flexbond/io.h"
#include "flexbond/vehicle.h"

/* Limits of a study: values per key (as the spec says), keys, cases.
 * The cases are the product of the keys' counts, so two keys at the
 * values' limit would make 1e8: checked on the command line, before
 * anything is allocated for them. 100000 cases keep a study within what
 * one command can hold and finish (docs/sweep.md, "Limits"): a case takes
 * 272 bytes (sweep_case) and 240 more for the figure, 50 MB in all; its
 * journal row about 520 bytes, so a journal of every case is some 52 MB,
 * which --resume reads back whole within an input file's 256 MiB
 * (FB_INPUT_MAX_BYTES), as it would at up to 2.6 KB a row (a failed
 * case's long message in each), where a million cases would not resume;
 * and a System 1 case takes 15-25 ms on one core, 100000 of them about
 * 40 core-minutes (1e8: 27 GB of cases before the first runs, and three
 * weeks of a core). */
enum { SWEEP_MAX_VALUES = 10000, SWEEP_MAX_KEYS = 16, SWEEP_MAX_CASES = 100000 };

/* The metrics of a case, in sweep.csv's order: peak, min and rms of
 * every output of the scenario (output k's at SWEEP_NSTATS k +
 * SWEEP_STAT_*), then the others (sweep_metric_other). */
enum { SWEEP_STAT_PEAK, SWEEP_STAT_MIN, SWEEP_STAT_RMS, SWEEP_NSTATS };
enum {
  M_MIN_TIRE_FORCE,
  M_CONTACT_LOSS_INTERVALS,
  /* The ride metrics of the first mounted body's acceleration among the
   * outputs, as summary.json's "ride" (run.c). */
  M_RIDE_A_W_RMS,
  M_RIDE_MTVV,
  M_RIDE_VDV,
  M_RIDE_CREST_FACTOR,
  M_RIDE_JERK_PEAK,
  M_RIDE_JERK_RMS,
  M_SOLVER_STEPS,
  SWEEP_NOTHER
};
/* Most outputs a swept scenario may list: a case's metrics are a fixed
 * array (one MPI message, one journal row). */
enum {
  SWEEP_MAX_OUTPUTS = 64,
  SWEEP_MAX_METRICS = SWEEP_NSTATS * SWEEP_MAX_OUTPUTS + SWEEP_NOTHER
};
/* Most panels of sweep.png (--plot): 16 panels of a 4 x 4 grid are
 * still readable on a screen. */
enum { SWEEP_MAX_PLOTS = 16 };

/* One swept key and its values (texts, as the overrides take them). */
typedef struct sweep_key {
  const char *key; /* as given */
  char *path;      /* the full dotted path it names */
  char **values;
  size_t nvalues;
} sweep_key;

typedef struct sweep_args {
  const char *scenario_path, *out_dir;
  fb_system sys;
  size_t jobs;
  int quiet, figures, resume, mpi;
  int strict;           /* --strict: a case with an implausible value fails as a bad input */
  fb_csv_header header; /* of sweep.csv (--plain-header: names only) */
  sweep_key keys[SWEEP_MAX_KEYS];
  size_t nkeys, ncases;
  const char *scenario_name; /* for titles */
  /* The scenario as the file gives it (no override): its outputs name
   * the metrics, and every case must have the same ones. */
  fb_scenario *base; /* owned */
  size_t nmetrics;   /* SWEEP_NSTATS base->noutputs + SWEEP_NOTHER */
  /* The metrics sweep.png draws, a panel each (--plot, or the default of
   * sweep_default_plots). */
  size_t plot[SWEEP_MAX_PLOTS];
  size_t nplots;
} sweep_args;

/* Index of the other metric M_* (after the outputs' statistics). */
size_t sweep_metric_other(const sweep_args *a, size_t m);

/* The outcome of one case. */
typedef struct sweep_case {
  int done;                         /* it has run (or was read back from the journal) */
  int status;                       /* FB_OK or what failed */
  char *error;                      /* its message (NULL when ok or out of memory) */
  double metric[SWEEP_MAX_METRICS]; /* a->nmetrics used; NaN when failed or not computed */
  int at_value;        /* the error is about a value a --set of the case replaced */
  double wall_seconds; /* of its simulation; NaN when resumed */
  int rank;            /* the MPI rank that ran it (0 without MPI) */
} sweep_case;

/* ---- sweep_case.c */

/* Index of key k's value in case i: the first key varies slowest. */
size_t sweep_value_index(const sweep_args *a, size_t i, size_t k);
/* "key=value, key=value" of case i from key first_key on, into buf. */
void sweep_case_label(const sweep_args *a, size_t i, size_t first_key, char *buf, size_t size);
/* Name ("tire_force_LF_peak") and unit of metric m. */
void sweep_metric_name(const sweep_args *a, size_t m, char *buf, size_t size);
const char *sweep_metric_unit(const sweep_args *a, size_t m);
/* The metric a --plot value names: OUTPUT[:STAT] (an output of the
 * scenario, STAT peak (default), min or rms), another metric by its
 * name (min_tire_force, ride_a_w_rms, ...), or any column name of
 * sweep.csv (tire_force_LF_rms). 0 and *m set, or -1. */
int sweep_metric_find(const sweep_args *a, const char *spec, size_t *m);
/* The default panels of sweep.png into a->plot: the first output's peak,
 * the smallest tire reaction, the ride's a_w r.m.s. (when an output is a
 * mounted body's acceleration) and the number of contact-loss
 * intervals: the load, the contact, the comfort and the lift-off. */
void sweep_default_plots(sweep_args *a);
/* Loads, simulates and measures case i into c (not c->done or c->rank).
 * Cases run at once on any hull: each case's eigen-solve is its own (the
 * solver holds no shared state), so none waits for another's. */
void sweep_run_case(const sweep_args *a, size_t i, sweep_case *c);
/* Key k as given with the unit the file writes it in, "speed_kmh
 * [km/h]" (the key alone when it has none), into buf. */
void sweep_key_label(const sweep_args *a, size_t k, char *buf, size_t size);
/* sweep.csv's header line and case i's row, each with its '\n'; the
 * keys' and metrics' cells "name [unit]" (FB_CSV_HEADER_UNITS; a count
 * or ratio, unit "-", has none) or names only. */
void sweep_csv_header(FILE *fp, const sweep_args *a, fb_csv_header header);
void sweep_csv_row(FILE *fp, const sweep_args *a, size_t i, const sweep_case *c);
/* The shortest text that reads back as x ("%.15g" to "%.17g"), so that
 * sweep.csv holds every bit. */
void sweep_format_double(double x, char *buf, size_t size);
/* 1 if the whole text is a finite decimal number (fb_parse_decimal: no
 * hexadecimal, inf or nan), into *out. */
int sweep_numeric_value(const char *text, double *out);

/* ---- sweep_journal.c: DIR/sweep.partial.csv, one row per finished case
 * in the order they finish, flushed at once, so that a killed sweep
 * process loses at most the cases it was running. */
typedef struct sweep_journal sweep_journal;
/* Opens (creates) the journal in dir, locked against a second sweep. An
 * existing journal is read back into cases (their done flag set, *resumed
 * counted) when a->resume, and refused otherwise; it must be of the same
 * study (sweep_study_fingerprint). */
int sweep_journal_open(const sweep_args *a, const char *dir, sweep_case *cases, size_t *resumed,
                       sweep_journal **j, fb_err *err);
/* Appends case i (finished, not interrupted) and flushes. */
int sweep_journal_append(sweep_journal *j, size_t i, const sweep_case *c, fb_err *err);
/* The cases the journal holds: read back and appended. */
size_t sweep_journal_rows(const sweep_journal *j);
/* Closes; removes the file when remove_file. */
void sweep_journal_close(sweep_journal **j, int remove_file);
/* The study's fingerprint: a hash of flexbond's version, the system, the
 * keys' paths and their values, and the bytes of every file the study
 * reads (the scenario file, every file it names: fb_scenario.inputs,
 * and every --set value of a `file` or `deck` key; one that cannot be
 * read counts as such). With inputs, also one line "# input HASH PATH\n" per
 * file into *inputs (fresh memory, the caller frees it; PATH with every
 * byte below 0x20, DEL and '%' percent-encoded), which the journal keeps
 * to name a file that has changed. */
int sweep_study_fingerprint(const sweep_args *a, uint64_t *fingerprint, char **inputs,
                            fb_err *err);
/* The journal's path in dir, in fresh memory (NULL: out of memory). */
char *sweep_journal_path(const char *dir);

/* ---- sweep_pool.c: who takes which case, and what happens when one
 * finishes, shared by the threads and (on rank 0) the MPI coordinator. */
typedef struct sweep_pool {
  const sweep_args *a;
  sweep_case *cases;
  sweep_journal *journal;
  pthread_mutex_t lock; /* next, finished, journal_rc and stderr */
  size_t next;          /* the first case not handed out */
  size_t finished;      /* cases finished in this run */
  int journal_rc;       /* the first journal failure */
  fb_err journal_err;
} sweep_pool;

void sweep_pool_init(sweep_pool *p, const sweep_args *a, sweep_case *cases,
                     sweep_journal *journal);
void sweep_pool_destroy(sweep_pool *p);
/* The next case not done, or 0 when none is left, the command was
 * interrupted or the journal failed. */
int sweep_pool_take(sweep_pool *p, size_t *i);
/* Records that case i (in p->cases) has finished: journal and progress. */
void sweep_pool_finish(sweep_pool *p, size_t i);
/* A thread of the pool: takes and runs cases until none is left. */
void *sweep_pool_worker(void *pool);
/* Runs every case not done on min(jobs, cases left) threads. */
void sweep_pool_run(sweep_pool *p, size_t jobs);

#ifdef FLEXBOND_MPI
/* ---- sweep_mpi.c (an MPI build): rank 0 hands the cases out one at a
 * time and runs cases itself on one thread; every other rank runs the
 * cases it is given. */
/* MPI_Init_thread; this rank and the number of ranks. */
int sweep_mpi_init(int *rank, int *size, fb_err *err);
/* 1 on every rank if setup failed on any (ok: this rank's own verdict)
 * or found a study of another fingerprint than rank 0's (another
 * scenario file, say), with the first such rank in *bad_rank. */
int sweep_mpi_agree(int ok, uint64_t fingerprint, int *bad_rank);
/* Rank 0's go (1: the cases will be handed out; 0: they will not) to
 * every rank, which returns it. */
int sweep_mpi_go(int go);
/* Rank 0: runs every case not done across the ranks. */
void sweep_mpi_coordinate(sweep_pool *p, int size);
/* Every other rank: runs the cases rank 0 gives until it says stop. */
void sweep_mpi_work(const sweep_args *a);
/* Rank 0's exit code to every rank; MPI_Finalize. */
int sweep_mpi_finish(int exit_code);
#endif

#endif
