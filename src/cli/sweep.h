/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond sweep, inside the command (docs/sweep.md). The study layer
 * holds the sweep (flexbond/study.h: the grid, each case's run and
 * metrics, the threads); the command gives it each case's scenario and
 * says and writes what comes out: sweep_case.c (a case's scenario, its
 * progress line, sweep.csv's rows), the journal a killed sweep resumes
 * from (sweep_journal.c) and, in an MPI build, the transport of cases
 * across ranks (sweep_mpi.c). sweep.c parses the command line and writes
 * the files. */
#ifndef FLEXBOND_CLI_SWEEP_H
#define FLEXBOND_CLI_SWEEP_H

#include <stdint.h>
#include <stdio.h>

#include "flexbond/io.h"
#include "flexbond/study.h"
#include "flexbond/vehicle.h"

/* Limits of a study: values per key (as the spec says), keys, cases
 * (the library's: flexbond/study.h). The cases are the product of the
 * keys' counts, so two keys at the values' limit would make 1e8: checked
 * on the command line, before anything is allocated for them. 100000
 * cases keep a study within what one command can hold and finish
 * (docs/sweep.md, "Limits"): a journal row takes about 520 bytes, so a
 * journal of every case is some 52 MB, which --resume reads back whole
 * within an input file's 256 MiB (FB_INPUT_MAX_BYTES), as it would at up
 * to 2.6 KB a row (a failed case's long message in each), where a
 * million cases would not resume. */
enum {
  SWEEP_MAX_VALUES = 10000,
  SWEEP_MAX_KEYS = FB_STUDY_SWEEP_MAX_AXES,
  SWEEP_MAX_CASES = (int)FB_STUDY_SWEEP_MAX_CASES
};

/* Most outputs a swept scenario may list: a case's metrics cross the
 * network as one MPI message of a fixed size (sweep_mpi.c). */
enum {
  SWEEP_MAX_OUTPUTS = 64,
  SWEEP_MAX_METRICS = FB_STUDY_SWEEP_NSTATS * SWEEP_MAX_OUTPUTS + FB_STUDY_SWEEP_NOTHER
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

typedef struct sweep_journal sweep_journal;

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
  size_t nmetrics;   /* fb_study_sweep_nmetrics */
  /* The cases and their outcomes (sweep_study_new; owned), run by the
   * study layer, which calls back sweep_case.c for each case's scenario
   * and when a case finishes. */
  fb_study_sweep *study;
  /* Where a finished case goes (sweep_journal_open; NULL: nowhere), and
   * whether writing it has failed, after which no row is written. */
  sweep_journal *journal;
  int journal_failed;
  /* The metrics sweep.png draws, a panel each (--plot, or the default of
   * sweep_default_plots). */
  size_t plot[SWEEP_MAX_PLOTS];
  size_t nplots;
} sweep_args;

/* ---- sweep_case.c */

/* The study of a (its keys, values and system) into a->study, its cases
 * made and reported by the command: each case's scenario read with its
 * --set values, its warnings said (and refused under --strict), an
 * interrupt stopping it; each finished case journaled and its progress
 * line said. */
int sweep_study_new(sweep_args *a, fb_err *err);
/* fb_study_sweep_ops' locate (fb_scenario_locate) and stop (an
 * interruption: cli_interrupted), ctx unused: every sweep's. */
int sweep_locate_case(void *ctx, const fb_scenario *s, fb_err *err);
int sweep_interrupted(void *ctx);
/* "key=value, key=value" of case i from key first_key on, into buf. */
void sweep_case_label(const sweep_args *a, size_t i, size_t first_key, char *buf, size_t size);
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
/* Key k as given with the unit the file writes it in, "speed_kmh
 * [km/h]" (the key alone when it has none), into buf. */
void sweep_key_label(const sweep_args *a, size_t k, char *buf, size_t size);
/* sweep.csv's header line and case i's row, each with its '\n'; the
 * keys' and metrics' cells "name [unit]" (FB_CSV_HEADER_UNITS; a count
 * or ratio, unit "-", has none) or names only. */
void sweep_csv_header(FILE *fp, const sweep_args *a, fb_csv_header header);
void sweep_csv_row(FILE *fp, const sweep_args *a, size_t i);
/* The shortest text that reads back as x ("%.15g" to "%.17g"), so that
 * sweep.csv holds every bit. */
void sweep_format_double(double x, char *buf, size_t size);
/* 1 if the whole text is a finite decimal number (fb_parse_decimal: no
 * hexadecimal, inf or nan), into *out. */
int sweep_numeric_value(const char *text, double *out);

/* ---- sweep_journal.c: DIR/sweep.partial.csv, one row per finished case
 * in the order they finish, flushed at once, so that a killed sweep
 * process loses at most the cases it was running. */
/* Opens (creates) the journal in dir, locked against a second sweep. An
 * existing journal is read back into a->study's cases (recorded done,
 * *resumed counted) when a->resume, and refused otherwise; it must be of
 * the same study (sweep_study_fingerprint). */
int sweep_journal_open(const sweep_args *a, const char *dir, size_t *resumed, sweep_journal **j,
                       fb_err *err);
/* Appends case i (finished, not interrupted) and flushes. */
int sweep_journal_append(sweep_journal *j, size_t i, fb_err *err);
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
/* -j N (text; NULL: the online CPUs) into *jobs, 1 .. 1024, or a usage
 * error of cmd. */
int sweep_parse_jobs(const char *cmd, const char *text, size_t *jobs);
/* 64-bit FNV-1a of data[0 .. n) continuing from h (the offset basis
 * 14695981039346656037 to start): the journals' fingerprints. */
uint64_t sweep_fnv1a(uint64_t h, const void *data, size_t n);
/* The journal's path in dir, in fresh memory (NULL: out of memory). */
char *sweep_journal_path(const char *dir);

/* 1 if the arguments ask for --mpi (before a "--"). */
int sweep_wants_mpi(int argc, char **argv);

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
/* sweep_mpi_agree on this rank's exit code so far (*exit_code) and
 * fingerprint: 1 when every rank agreed; else 0, rank 0 having said which
 * rank did not ("rank 3 could not set the study up, or read FILES ...")
 * and *exit_code its status. */
int sweep_mpi_agreed(int rank, uint64_t fingerprint, const char *files, int *exit_code);
/* A rank other than 0 sends its stderr to /dev/null while it sets the
 * study up (rank 0 alone speaks): the saved stderr for
 * sweep_mpi_unsilence (-1 on rank 0), which puts it back. */
int sweep_mpi_silence(int rank);
void sweep_mpi_unsilence(int saved);
/* Waits, polling with a pause, for a message of tag from any rank; its
 * source rank. */
int sweep_mpi_wait(int tag);
/* Rank 0's go (1: the cases will be handed out; 0: they will not) to
 * every rank, which returns it. */
int sweep_mpi_go(int go);
/* Rank 0: runs every case not done across the ranks, and on one thread
 * of its own; what stopped the local thread (fb_study_sweep_run). */
int sweep_mpi_coordinate(const sweep_args *a, int size, fb_err *err);
/* Every other rank: runs the cases rank 0 gives until it says stop. */
void sweep_mpi_work(const sweep_args *a);
/* Rank 0's exit code to every rank; MPI_Finalize. */
int sweep_mpi_finish(int exit_code);
#endif

#endif
