/* SPDX-License-Identifier: BSD-3-Clause */
/* Internal interface of the flexbond command: exit codes, the option
 * parser shared by the subcommands, and the subcommands themselves.
 * Only this program uses it; the library never prints or exits. */
#ifndef FLEXBOND_CLI_H
#define FLEXBOND_CLI_H

#include <stddef.h>
#include <stdio.h>

#include "flexbond/error.h"
#include "flexbond/hull_stress.h"
#include "flexbond/io.h"
#include "flexbond/model.h"
#include "flexbond/ride.h"
#include "flexbond/study.h"
#include "flexbond/vehicle.h"

/* The project's version (CMakeLists.txt's project(), as the library has it). */
#define CLI_VERSION FLEXBOND_VERSION_TEXT

/* OpenBLAS's own call (the library links libopenblas directly,
 * CMakeLists.txt's OPENBLAS_LIB), declared here rather than taken from a
 * cblas.h: which cblas.h the Debian alternatives select (OpenBLAS's or
 * the reference one, which lacks it) is not ours to choose. main sets one
 * thread for every command (main.c says why). */
void openblas_set_num_threads(int num_threads);

/* Threads a command's own computation may use beside its main one: 2
 * when the machine has two processors or more, else 1 (jobs.c). */
int cli_threads(void);

/* Exit codes of the program (the table is in main.c). */
enum cli_exit {
  CLI_EXIT_OK = 0,
  CLI_EXIT_USAGE = 1,
  CLI_EXIT_INPUT = 2,
  CLI_EXIT_CAUSAL = 3,
  CLI_EXIT_SOLVER = 4,
  CLI_EXIT_IO = 5,
  CLI_EXIT_NOMEM = 6,
  CLI_EXIT_INTERRUPTED = 130 /* 128 + SIGINT, as a shell reports a killed command */
};

/* One option a command accepts. The parser sets value: NULL when the
 * option is absent, its argument when it takes one, "" for a given flag.
 * A repeated option keeps its last value. */
typedef struct cli_option {
  const char *name;  /* long form, "--t-end" */
  const char *alias; /* short form, "-o", or NULL */
  int takes_value;   /* 1: "--name VALUE" or "--name=VALUE" */
  const char *value;
} cli_option;

/* Parses argv[1 .. argc-1] of command argv[0]: options into opts, the
 * other arguments into positional (at most max_positional, count in
 * *npositional). "--" ends the options; "-" alone is positional. Returns
 * CLI_EXIT_OK, or CLI_EXIT_USAGE after printing the problem to stderr. */
int cli_parse(int argc, char **argv, cli_option *opts, size_t nopts, const char **positional,
              size_t max_positional, size_t *npositional);

/* The common front of a command that takes one input file argument
 * (what names it in messages: "MODEL", "SCENARIO"): parses argv into opts
 * (which must include "--help"), prints usage for --help. Returns 1 when
 * the command should run with *path, 0 when it is done, with its exit
 * code in *exit_code. */
int cli_parse_file_command(int argc, char **argv, cli_option *opts, size_t nopts,
                           const char *usage, const char *what, const char **path,
                           int *exit_code);
/* cli_parse_file_command for a MODEL file. */
int cli_parse_model_command(int argc, char **argv, cli_option *opts, size_t nopts,
                            const char *usage, const char **model_path, int *exit_code);

/* ---- Interruption. cli_interrupt_install, called before any other
 * thread starts, makes SIGINT, SIGTERM and SIGHUP (those not ignored at
 * start) set a flag instead of killing the program, so that a long
 * command can stop cleanly: the simulations poll the flag through their
 * progress callback and fail with FB_EINTR (exit code 130), and an
 * interrupted command writes nothing (cli_outdir). A command that has not
 * stopped CLI_GRACE_MS after the signal (a phase that cannot poll), or a
 * second signal, is ended by the signal thread itself: it abandons the
 * open output directories and exits with 130 (interrupt.c). Returns 0,
 * or -1 if the signals could not be taken. */
int cli_interrupt_install(void);
/* Says that the command has returned and reports its own outcome: a
 * signal after this no longer ends the process early. */
void cli_interrupt_finish(void);
/* Leaves the stopping to the command alone: no early end after a signal
 * (an MPI rank must reach MPI_Finalize, or the job is aborted). */
void cli_interrupt_polled_only(void);
/* 1 once SIGINT or SIGTERM has arrived. */
int cli_interrupted(void);
/* FB_EINTR with a message once interrupted, else FB_OK. */
int cli_check_interrupt(fb_err *err);

/* ---- Long set-up stages (interrupt.c). A command passes cli_stage_progress
 * with a cli_stage as the fb_progress of a long computation (a vehicle's
 * realisation): a stage still running after CLI_STAGE_SILENT_MS is named
 * once on stderr, "flexbond COMMAND: SUBJECT: STAGE ...", by the signal
 * thread when the stage cannot call back meanwhile (a factorisation), and
 * an interruption stops the computation at its next call (FB_EINTR). */
#define CLI_STAGE_SILENT_MS 1000
typedef struct cli_stage {
  const char *command; /* "run" */
  const char *subject; /* "apc6x6: System 2 (flexible hull)" */
  int quiet;           /* -q: nothing said */
} cli_stage;
int cli_stage_progress(void *ctx, const char *stage, double fraction);

/* Index in *out of the option's value text among choices[0..nchoices), or
 * a usage error listing the choices. */
int cli_choice(const char *cmd, const char *name, const char *text, const char *const *choices,
               size_t nchoices, int *out);

/* Prints "flexbond CMD: <message>" and a pointer to CMD --help to stderr;
 * returns CLI_EXIT_USAGE. */
/* Loads the scenario at path as fb_scenario_load does and says its
 * plausibility warnings on stderr ("flexbond: warning: FILE:LINE:COL:
 * KEY: ..."); strict (--strict): the first of them is an error instead
 * (FB_EINVAL, the warning's fields), and *s is freed. */
int cli_scenario_load(const char *path, int strict, fb_scenario **s, fb_err *err);
/* The warnings of a loaded s as cli_scenario_load says them; strict: the
 * first as an error. */
int cli_scenario_warnings(const fb_scenario *s, int strict, fb_err *err);

/* A status line on stderr, printf-formatted like a message: the control
 * characters of the text it quotes (a scenario's name, a directory) are
 * escaped (fb_err_escape), so that a line stays a line. cli_say ends it
 * with a line break, cli_say_more does not. */
void cli_say(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
void cli_say_more(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;
int cli_usage_error(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
#if defined(__clang_analyzer__)
/* For the static analyzer only (`make tidy`), which does not follow calls to variadic
 * functions: the value is CLI_EXIT_USAGE. */
#define cli_usage_error(cmd, ...) (cli_usage_error((cmd), __VA_ARGS__), CLI_EXIT_USAGE)
#endif

/* Converts the value of option name to a finite number > 0 in *out, or
 * reports a usage error naming the option. */
int cli_positive_number(const char *cmd, const char *name, const char *text, double *out);

/* Exit code for a library status. */
int cli_exit_code(int status);

/* Prints "flexbond: <err->msg>" to stderr and returns the exit code for
 * status (status, not err->code, decides: it is what the call returned). */
int cli_report(int status, const fb_err *err);
/* cli_report for an error of a command that loaded scenario s (NULL when
 * it did not load): an error about one of its values (fb_err.key) is
 * first located in its file (fb_scenario_locate). */
int cli_report_scenario(const fb_scenario *s, int status, fb_err *err);
/* Prints each of the model's warnings (fb_model_warning) to stderr as
 * "flexbond: warning: <msg>"; they do not change the exit status. */
void cli_report_warnings(const fb_model *m);

/* Flushes stdout: FB_OK if everything printed so far got through, else
 * FB_EIO with the reason (a closed pipe, a full disk). */
int cli_flush_stdout(fb_err *err);

/* s as a JSON string: fb_json_write_string (flexbond/escape.h). */
void cli_json_string(FILE *fp, const char *s);

/* Prints text (a usage text) to stdout; returns the exit code. */
int cli_print_help(const char *text);

/* dir/name in fresh memory (no doubled '/'), NULL when out of memory. */
char *cli_join_path(const char *dir, const char *name);

/* The files one command writes into an output directory, all or nothing.
 * cli_outdir_open creates dir (and its missing parents), takes dir's lock
 * (dir/.flexbond.lock, flock(2): a second command into dir is refused with
 * FB_EIO while one holds it; a sweep holds it for its whole run), removes
 * the staging directories that killed commands left there; the first file
 * makes a hidden staging directory inside dir (".flexbond-staging-XXXXXX").
 * Files are written there and recorded with cli_outdir_keep; only when the
 * command has succeeded does cli_outdir_close move them into dir, each by a
 * rename, keeping every file it replaces aside until all moves have
 * succeeded (and putting them back if one fails), and removes the files
 * that the same command wrote there before and no longer writes (as
 * dir/.flexbond-manifest lists them; no other file of dir is touched). A
 * failed or interrupted command removes the staging directory, and the
 * directories it created if they are empty: dir's previous contents stay
 * as they were. */
typedef struct cli_outdir {
  const char *dir;     /* borrowed: the destination */
  const char *command; /* borrowed: the command's name, for the manifest ("run") */
  char *stage;         /* the staging directory, owned */
  char **created_dirs; /* owned: the directories open created, in order */
  size_t ncreated;     /* 0: dir was there before cli_outdir_open */
  char *lock_path;     /* owned: dir/.flexbond.lock */
  int lock_fd;         /* holds the lock; -1 when none is held */
  char **files;        /* staged files, owned */
  size_t nfiles;
  /* borrowed, or NULL: what the signal thread says of dir when it ends
   * the command early, instead of "nothing was written" (a sweep's journal) */
  const char *interrupt_note;
  /* 1: the command has said in err what became of dir on its failure (a
   * sweep's kept journal); else cli_outdir_close says nothing was written */
  int failure_noted;
} cli_outdir;

/* Opens dir for command (see above). */
int cli_outdir_open(cli_outdir *od, const char *dir, const char *command, fb_err *err);
/* The staging path of file name (a plain file name), in fresh memory, or
 * NULL with the reason (FB_ENOMEM, FB_EIO) recorded in err. The staging
 * directory is made at the first call. */
char *cli_outdir_path(cli_outdir *od, const char *name, fb_err *err);
/* Records the staged file path (taken over, freed by close). If that
 * fails (out of memory) the file is removed and freed at once. */
int cli_outdir_keep(cli_outdir *od, char *path, fb_err *err);
/* Writes the staged file name (fb_out): write(fp, ctx) prints its
 * content; the file is then committed and recorded. */
typedef void (*cli_writer)(FILE *fp, const void *ctx);
int cli_outdir_write(cli_outdir *od, const char *name, cli_writer write, const void *ctx,
                     fb_err *err);
/* Finishes. With status FB_OK (and no interruption meanwhile) moves the
 * staged files into dir; otherwise, or if a move fails (FB_EIO in err),
 * removes what is staged and, for a failure on the way (not a bad input,
 * refused before anything started), appends to err's message that nothing
 * was written and what dir holds. Releases the lock, removes the staging
 * directory, frees the record; returns the final status. Every command
 * with an output directory ends through here, so that each says the same. */
int cli_outdir_close(cli_outdir *od, int status, fb_err *err);
/* Removes what od staged, releases its lock and removes the directories
 * it created (if empty), freeing nothing: what a failed close does, and
 * what the signal thread does before the process ends (interrupt.c). */
void cli_outdir_abandon(const cli_outdir *od);

/* Independent jobs writing into one output directory (a run's figures,
 * each mostly waiting for its gnuplot or dot): run(od, ctx, err) each,
 * on this thread and, with more than one CPU, one more (cli_threads).
 * cli_outdir_path, cli_outdir_keep and cli_outdir_write may be called
 * from both. Once a job fails or the command is interrupted no further
 * job starts; the status is the first failed job's in the array's order
 * (its message in err), else FB_EINTR when interrupted, else FB_OK. */
typedef struct cli_job {
  int (*run)(cli_outdir *od, const void *ctx, fb_err *err);
  const void *ctx;
} cli_job;
int cli_jobs_run(cli_outdir *od, const cli_job *jobs, size_t n, fb_err *err);

/* The open output directories, for the signal thread (interrupt.c): an
 * outdir is added by cli_outdir_open (0, or -1 when too many are open)
 * and removed by cli_outdir_close, which holds the guard's lock then
 * (cli_guard_remove does not take it); a commit holds the lock too, so
 * that the signal thread never abandons a directory in the middle of
 * one, and says when it has put results in place (committed 1), after
 * which a signal no longer stops the command. */
/* abandon: what the signal thread calls on od (cli_outdir_abandon,
 * handed in so that the guard does not call back into outdir.c). */
int cli_guard_add(const cli_outdir *od, void (*abandon)(const cli_outdir *od));
void cli_guard_remove(const cli_outdir *od);
void cli_guard_lock(void);
void cli_guard_unlock(int committed);

/* Subcommands: argv[0] is the command name, as for main. Each returns the
 * program's exit code. */
int cli_cmd_sim(int argc, char **argv);
int cli_cmd_diagram(int argc, char **argv);
int cli_cmd_causality(int argc, char **argv);
int cli_cmd_eig(int argc, char **argv);
int cli_cmd_run(int argc, char **argv);
int cli_cmd_modes(int argc, char **argv);
int cli_cmd_mesh(int argc, char **argv);
int cli_cmd_export(int argc, char **argv);
int cli_cmd_fmu(int argc, char **argv);
int cli_cmd_freq(int argc, char **argv);
int cli_cmd_sweep(int argc, char **argv);
int cli_cmd_ride_limit(int argc, char **argv);
int cli_cmd_model(int argc, char **argv);
/* The modes --picture-modes lists (n 0: none given). */
typedef struct cli_mode_list {
  size_t n;
  double mode[FB_PICTURED_MODES_MAX];
} cli_mode_list;
/* Modal analysis of System 2 (modes --system flexible); out_dir may be
 * NULL (print only); strict: --strict. Returns the exit code. */
int cli_modes_flexible(const char *path, const char *out_dir, int strict,
                       const cli_mode_list *pictured);

/* ---- System 2's mode pictures (modes_flex.c), drawn by modes --system
 * flexible and by run. */

/* The most modes pictured: the listed ones, or those chosen by kind. */
enum { CLI_MAX_PICTURED_MODES = 32 };
/* The modes of ms pictured (0-based, into out, at most max; returns how
 * many): those s lists (report.mode_pictures or --picture-modes) that ms holds, in
 * their order, else those fb_mode_set_pictured chooses by what they are. */
size_t cli_pictured_modes(const fb_scenario *s, const fb_mode_set *ms, size_t *out, size_t max);
/* --picture-modes LIST ("1,3,7": whole numbers from 1, at most
 * FB_PICTURED_MODES_MAX) into *out; a usage error of cmd otherwise.
 * Returns the exit code. */
int cli_picture_modes_option(const char *cmd, const char *list, cli_mode_list *out);
/* Puts l's modes, when it has any, in s's list in place of the file's. */
void cli_mode_list_apply(const cli_mode_list *l, fb_scenario *s);
/* "mode_NN.png", the picture of 1-based mode number mode, into buf. */
void cli_mode_picture_name(size_t mode, char *buf, size_t size);
/* Writes the picture of every pictured mode that ms holds: the hull, the
 * mounted bodies and the wheels at rest and displaced (fb_plot_mode_png). */
int cli_write_mode_pictures(cli_outdir *od, const fb_scenario *s, const fb_fe_hull *hull,
                            const fb_mode_set *ms, fb_err *err);

/* Kinds of diagram of a graph (diagram.c, cli_diagram_file). */
typedef enum cli_diagram_kind {
  CLI_DIAGRAM_FLAT,      /* the block diagram, every block in one level */
  CLI_DIAGRAM_BLOCKS,    /* the block diagram in two levels (Fig. 6) */
  CLI_DIAGRAM_BOND_GRAPH /* the multibond graph with its strokes (Fig. 5) */
} cli_diagram_kind;

/* ---- flexbond run (run.c) and its report.md (report.c, described in
 * docs/report.md). */

enum { CLI_MAX_SYSTEMS = 2 };

/* The figure of output o, "figNN_NAME.png" (its figure number) or
 * "fig_NAME.png", into buf. */
void cli_run_figure_file(const fb_output_spec *o, char *buf, size_t size);
/* The window output o's figure shows over the run of r: the output's
 * window clipped to the run, or, when it has none or they do not overlap,
 * *t_min = *t_max = 0 (the whole run). */
void cli_run_figure_window(const fb_output_spec *o, const fb_result *r, double *t_min,
                           double *t_max);
/* The number of diagrams run draws per system, and the file of diagram
 * k < CLI_RUN_NDIAGRAMS of system sys ("fig05_bond_graph_system1.png",
 * "fig06_block_diagram_system1.png": the paper's Figs. 5 and 6). */
enum { CLI_RUN_NDIAGRAMS = 2 };
void cli_run_diagram_file(size_t k, fb_system sys, char *buf, size_t size);
/* The kind of diagram k < CLI_RUN_NDIAGRAMS (names.c). */
cli_diagram_kind cli_run_diagram_kind(size_t k);

/* ---- flexbond run --animate (animate.c, docs/animation.md). */
enum { CLI_ANIMATE_MAX_FRAMES = 10000 };
typedef struct cli_animate_opts {
  int enabled;  /* --animate */
  double fps;   /* frames per second of the run's time, > 0 */
  double scale; /* drawn per m of displacement; 0: the largest drawn 0.08 L */
  int gif;      /* 0 with --no-figures: the ParaView files alone */
} cli_animate_opts;
/* What an animation showed, for the report. */
typedef struct cli_animation_info {
  size_t nframes;
  double t0, t1; /* the first and last frames' times, s */
  double warp;   /* the displacements' drawing factor */
  double umax;   /* m, the largest displacement of any frame */
  int gif;
} cli_animation_info;
/* The number of frames at fps over window within the run's t_first..t_last
 * into *n; FB_EINVAL naming --animate-fps unless 1..CLI_ANIMATE_MAX_FRAMES:
 * run asks before it simulates, with the run's span. */
int cli_animate_frame_count(const double window[2], double t_first, double t_last, double fps,
                            size_t *n, fb_err *err);
/* "animation_systemN.pvd" (ext "pvd"), ".gif", or frame's
 * "animation_systemN_FFFF.vtu" (ext "vtu"). */
void cli_animation_file(fb_system sys, const char *ext, size_t frame, char *buf, size_t size);
/* m's frames over window (the bump window) at o's rate into od: a .vtu
 * per frame, the .pvd naming them and, with o->gif, the animated GIF. */
/* stress (System 2's recovery, or NULL): each .vtu carries the von Mises
 * stress per element at its time as cell data "von_mises" (Pa). */
int cli_write_animation(cli_outdir *od, const fb_scenario *s, const fb_vehicle_motion *m,
                        const fb_hull_stress *stress, const double window[2],
                        const cli_animate_opts *o, cli_animation_info *info, fb_err *err);

/* FB_CONTACT_SPIKE_RATIO (flexbond/study.h) for messages. */
#define CLI_CONTACT_SPIKE_TEXT "3"

/* One simulated system. */
typedef struct cli_run_system {
  fb_system sys;
  const char *label; /* what the messages call it: cli_system_label(sys) unless set */
  fb_result *res;
  /* Its outputs' and tires' statistics, contact losses and ride metrics
   * (flexbond/study.h; owned). */
  fb_run_summary *sum;
  /* With --animate: the run's motion (owned) and its animation. */
  fb_vehicle_motion *motion;
  cli_animation_info anim;
  /* System 2 with a reduced modal hull: the estimated error of each output
   * from its basis (fb_vehicle_basis_error; s->noutputs, owned), else NULL. */
  double *basis_error;
  /* System 2 unless --no-stress: its hull's stress recovery and the peaks
   * per element over the samples from stress_from (s) on (owned), else
   * NULL. */
  fb_hull_stress *stress;
  fb_hull_stress_peaks *peaks;
  double stress_from;
} cli_run_system;

/* ---- Hull stresses (stress.c; docs/stresses.md "Over a run"). */

#define CLI_STRESS_CSV "stress_peaks.csv"
#define CLI_STRESS_VTU "stress_peak.vtu"
#define CLI_STRESS_PNG "stress_peak.png"
/* run's stress recovery of v (System 2) and its peaks over run->motion's
 * samples at or after t_from (s) into run->stress, run->peaks. */
int cli_run_stress(const fb_vehicle *v, double t_from, cli_run_system *run, fb_err *err);
void cli_run_stress_free(cli_run_system *run);
/* DIR/stress_peaks.csv, DIR/stress_peak.vtu and, with figures,
 * DIR/stress_peak.png of run (its peaks computed). */
int cli_write_stress_files(cli_outdir *od, const fb_scenario *s, const cli_run_system *run,
                           int figures, fb_err *err);

/* Everything run writes. */
typedef struct cli_run_outputs {
  const fb_scenario *scenario;
  const cli_run_system *runs; /* System 1 first when both */
  size_t nruns;
  /* The report's data (flexbond/study.h; borrowed): the runs, their
   * comparisons and the findings report.md and summary.json state. Of it,
   * System 2 minus System 1 and each output's comparison (s->noutputs),
   * NULL unless both ran. */
  const fb_study_report *report;
  const fb_result *diff;
  const fb_output_cmp *cmp;
  double bump_window[2]; /* first wheel's bump entry, last wheel's exit, s */
  int figures;           /* 0 with --no-figures */
  fb_csv_header header;  /* of systemN.csv (--plain-header) */
  /* System 1's undamped modes, when it ran. */
  const fb_mode *modes1;
  size_t nmodes1, nstatic1;
  /* The realised vehicles, as runs (to draw their diagrams). */
  fb_vehicle *vehicles[CLI_MAX_SYSTEMS];
  /* System 2's hull, its basis and its undamped modes, when it ran. */
  const fb_fe_hull *hull;
  const fb_hull_basis *basis;
  const fb_mode_set *modes2;
  const char *hull_modes_source; /* what set scenario->hull_modes (Markdown) */
  /* System 2 again on the hull refined to hull.mesh.converged_density,
   * when the scenario asks for it and System 2 ran on a coarser mesh: its
   * run (system2_converged.csv), its basis and its density; against
   * System 1 (diff_converged, cmp_converged: s->noutputs) when both ran.
   * NULL and 0 otherwise. */
  const cli_run_system *converged;
  const fb_hull_basis *converged_basis;
  int converged_density;
  const fb_result *diff_converged;
  const fb_output_cmp *cmp_converged;
  const char *note;      /* why a system did not run, or NULL */
  const char *no_stress; /* why System 2's hull stresses were not computed, or NULL */
  /* The frequency response of each system that ran, by system (flexbond
   * freq's bode_<OUTPUT>.png; borrowed), NULL without figures or when it
   * failed: then freq_note says why. */
  fb_study_freq *freq[CLI_MAX_SYSTEMS];
  char freq_note[FB_ERR_MSG_MAX];
  const cli_animate_opts *animate; /* --animate's settings */
} cli_run_outputs;

/* "System 1 (rigid hull)", "System 2 (flexible hull)". */
const char *cli_system_label(fb_system sys);
/* The scenario's name, else its path, else "scenario". */
const char *cli_scenario_name(const fb_scenario *s);
/* report.md (a cli_writer over a cli_run_outputs). */
void cli_write_report_md(FILE *fp, const void *ctx);
/* report.md's "Hull stresses" (the hot spots), when a run has peaks. */
void cli_write_stress_report(FILE *fp, const cli_run_outputs *o);

/* ---- Frequency responses (flexbond freq, and run's report), as the
 * study layer computes them (flexbond/study.h). */

/* The tracks' names, "left" and "right". */
extern const char *const cli_track_names[FB_ROAD_NTRACKS];
/* The unit of |H|, the output's unit per metre of road, into buf. */
void cli_gain_unit(const char *unit, char *buf, size_t size);
/* The phase of a complex amplitude z (re, im), degrees in (-180, 180]. */
double cli_phase_deg(const double z[2]);
/* bode_<OUTPUT>.png for each output with a response: |H| and phase of
 * each system's response fr[sys] (NULL: not run) and track overlaid. */
int cli_bode_write_figures(cli_outdir *od, fb_study_freq *const fr[CLI_MAX_SYSTEMS],
                           fb_err *err);
/* The ride from a road spectrum of each system r[sys] (NULL: not run) of
 * s: DIR/psd_systemN.csv and DIR/ride_psd.json, and its lines on stdout. */
int cli_ride_psd_write(cli_outdir *od, const fb_scenario *s,
                       fb_study_ride_psd *const r[CLI_MAX_SYSTEMS], fb_err *err);
void cli_ride_psd_print(const fb_scenario *s, fb_study_ride_psd *const r[CLI_MAX_SYSTEMS]);

/* ---- Diagrams of a graph (diagram.c, docs/diagrams.md): the paper's
 * Figs. 5 and 6, for `flexbond diagram` and the report. */
/* Writes the diagram of kind of graph g to path, all or nothing, the type
 * by path's extension: .svg or .png the picture Graphviz's dot draws of
 * it (io/graphviz.h), any other the DOT text. The block diagrams are
 * built with the probes p[0 .. np) (borrowed for the call), drawn as
 * meters. Assigns g's causality
 * (fb_bg_assign_causality), which changes g; nothing else is kept. A
 * signal meanwhile: FB_EINTR, nothing written. */
int cli_diagram_file(fb_bg *g, const fb_probe_spec *p, size_t np, cli_diagram_kind kind,
                     const char *path, fb_err *err);

#endif
