/* SPDX-License-Identifier: BSD-3-Clause */
/* SIGINT, SIGTERM and SIGHUP (see cli_interrupt_install in cli.h).
 *
 * The handler only sets a flag and writes a byte into a pipe (both
 * async-signal-safe, POSIX.1-2008, 2.4.3); a thread of its own reads the
 * pipe and does the rest, since it may lock a mutex, remove files and
 * print, which a handler may not. (sigwait in that thread alone would
 * need the signals blocked in every other thread, and OpenBLAS starts
 * its threads, with an empty mask, before main runs.) The flag is what
 * the long computations poll (the simulations through their progress
 * callback, the sweep's workers), so that the command stops by itself and
 * says what it stopped. Some phases cannot poll (a dense eigen-solve in
 * LAPACK, a figure being drawn by gnuplot): if the command has not
 * finished CLI_GRACE_MS after the signal, or at a second signal, the
 * thread abandons the open output directories itself (cli_outdir_abandon:
 * what was staged is removed, the directory holds what it held before),
 * reports, and ends the process with exit 130. Children die with it
 * (io/child.h: PR_SET_PDEATHSIG).
 *
 * This is the one piece of process-wide state of the program, because
 * signals are process-wide: the flag (a lock-free atomic, read by the
 * sweep's threads without the lock; C11 5.1.2.4 and 7.14.1.1p5), the
 * pipe, and the registry of open output directories under a mutex, which
 * a commit also holds, so that the thread never abandons a directory in
 * the middle of a commit. */
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

_Static_assert(ATOMIC_INT_LOCK_FREE == 2, "the flag is read without the lock");

/* How long the command has to stop by itself after a signal, ms; and,
 * once it has seen the flag (it is winding down: freeing a long run's
 * results, removing what it staged, under a loaded machine or a
 * sanitizer), how much longer it may take to say so itself. */
#define CLI_GRACE_MS 300
#define CLI_WIND_DOWN_MS 2000

/* Output directories open at once in one command: a sweep's and the
 * directory of its figure at most. */
enum { CLI_MAX_GUARDED = 4 };

/* What an interrupted command says, by itself or through the thread. */
static const char interrupted_msg[] = "interrupted (SIGINT, SIGTERM or SIGHUP)";

static atomic_int interrupted;
static atomic_int seen; /* cli_interrupted has answered 1 */
/* The handler's pipe: [0] read by the thread, [1] written by the handler
 * (non-blocking: a full pipe already says enough). */
static int wake[2] = {-1, -1};

static struct {
  pthread_mutex_t lock;
  const cli_outdir *open[CLI_MAX_GUARDED];
  void (*abandon[CLI_MAX_GUARDED])(const cli_outdir *od);
  int committed;   /* a commit has put new results in place */
  int finished;    /* the command has returned: it reports itself */
  int polled_only; /* cli_interrupt_polled_only */
} guard = {.lock = PTHREAD_MUTEX_INITIALIZER};

/* The set-up stage a command is in (cli_stage_progress), for the thread
 * to name when it lasts: under guard.lock. */
static struct {
  char line[FB_ERR_MSG_MAX + 1]; /* what to say, newline included */
  struct timespec start;
  int active, said;
} stage;

/* How often the thread looks at the stage, ms. */
#define CLI_STAGE_POLL_MS 100

static void on_signal(int sig)
{
  (void)sig;
  const int saved = errno;
  atomic_store(&interrupted, 1);
  const char byte = 1;
  ssize_t ignored = write(wake[1], &byte, 1);
  (void)ignored;
  errno = saved;
}

/* Writes the whole of text to stderr with write(2), not stdio: the main
 * thread may hold stderr's lock. */
static void say(const char *text)
{
  size_t left = strlen(text);
  while (left > 0) {
    const ssize_t n = write(STDERR_FILENO, text, left);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return;
    text += n;
    left -= (size_t)n;
  }
}

/* With guard.lock held: abandons every open output directory, says so and
 * ends the process. */
static void stop_now(void)
{
  char msg[FB_ERR_MSG_MAX];
  size_t len = (size_t)snprintf(msg, sizeof msg, "flexbond: %s", interrupted_msg);
  for (size_t i = 0; i < CLI_MAX_GUARDED; ++i) {
    const cli_outdir *od = guard.open[i];
    if (!od)
      continue;
    guard.abandon[i](od);
    char dir[1024]; /* escaped, as every message (fb_err_escape) */
    fb_err_escape(dir, sizeof dir, od->dir);
    if (len < sizeof msg && od->interrupt_note)
      len += (size_t)snprintf(msg + len, sizeof msg - len, "; %s", od->interrupt_note);
    else if (len < sizeof msg)
      len += (size_t)snprintf(msg + len, sizeof msg - len,
                              od->ncreated > 0
                                  ? "; nothing was written (%s not created)"
                                  : "; nothing was written: %s holds what it held before",
                              dir);
  }
  if (len < sizeof msg - 1)
    msg[len++] = '\n';
  msg[len < sizeof msg ? len : sizeof msg - 1] = '\0';
  say(msg);
  _exit(CLI_EXIT_INTERRUPTED);
}

/* Waits for a byte in the pipe, at most timeout_ms (-1: no limit); 1 if
 * one came. */
static int wait_for_signal(int timeout_ms)
{
  struct pollfd p = {.fd = wake[0], .events = POLLIN, .revents = 0};
  int n;
  while ((n = poll(&p, 1, timeout_ms)) < 0 && errno == EINTR)
    ;
  char byte;
  return n > 0 && read(wake[0], &byte, 1) == 1;
}

static double ms_since(const struct timespec *t0)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return 1e3 * (double)(t.tv_sec - t0->tv_sec) + 1e-6 * (double)(t.tv_nsec - t0->tv_nsec);
}

/* With guard.lock held: names the stage once it has run long enough. */
static void say_stage_if_due(void)
{
  if (stage.active && !stage.said && ms_since(&stage.start) >= CLI_STAGE_SILENT_MS) {
    say(stage.line);
    stage.said = 1;
  }
}

int cli_stage_progress(void *ctx, const char *what, double fraction)
{
  const cli_stage *c = ctx;
  pthread_mutex_lock(&guard.lock);
  if (fraction == 0.0 && !c->quiet) {
    fb_err line; /* formatted and escaped as every message */
    fb_err_set(&line, FB_OK, "flexbond %s: %s: %s ...", c->command, c->subject, what);
    snprintf(stage.line, sizeof stage.line, "%s\n", line.msg);
    clock_gettime(CLOCK_MONOTONIC, &stage.start);
    stage.active = 1;
    stage.said = 0;
  } else if (fraction >= 1.0) {
    stage.active = 0;
  } else {
    say_stage_if_due();
  }
  pthread_mutex_unlock(&guard.lock);
  return cli_interrupted();
}

static void *watch(void *arg)
{
  (void)arg;
  while (!wait_for_signal(CLI_STAGE_POLL_MS)) {
    pthread_mutex_lock(&guard.lock);
    say_stage_if_due();
    pthread_mutex_unlock(&guard.lock);
  }
  /* A second signal, or the grace period over. */
  if (!wait_for_signal(CLI_GRACE_MS) && atomic_load(&seen))
    wait_for_signal(CLI_WIND_DOWN_MS);
  pthread_mutex_lock(&guard.lock);
  if (!guard.committed && !guard.finished && !guard.polled_only)
    stop_now();
  /* The results are in place, or the command is reporting: it ends by
   * itself. */
  pthread_mutex_unlock(&guard.lock);
  return NULL;
}

/* Installs on_signal for sig (SA_RESTART: a read or write of the
 * command's own goes on rather than failing with EINTR). With
 * unless_ignored, a signal that is ignored stays so: nohup ignores
 * SIGHUP, and that is the user's choice. SIGINT and SIGTERM are taken in
 * any case: a shell script's background job starts with SIGINT ignored,
 * and its `kill -INT` must still stop the command cleanly. */
static int take(int sig, int unless_ignored)
{
  struct sigaction sa, old;
  if (unless_ignored && sigaction(sig, NULL, &old) == 0 && old.sa_handler == SIG_IGN)
    return 0;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  return sigaction(sig, &sa, NULL);
}

static int make_pipe(void)
{
  if (pipe(wake) != 0)
    return -1;
  for (int i = 0; i < 2; ++i)
    if (fcntl(wake[i], F_SETFD, FD_CLOEXEC) != 0)
      return -1;
  const int flags = fcntl(wake[1], F_GETFL);
  return flags < 0 || fcntl(wake[1], F_SETFL, flags | O_NONBLOCK) != 0 ? -1 : 0;
}

int cli_interrupt_install(void)
{
  if (make_pipe() != 0)
    return -1;
  pthread_t thread;
  pthread_attr_t attr;
  int rc = pthread_attr_init(&attr);
  if (rc == 0) {
    pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
    rc = pthread_create(&thread, &attr, watch, NULL);
    pthread_attr_destroy(&attr);
  }
  if (rc != 0)
    return -1;
  return take(SIGINT, 0) == 0 && take(SIGTERM, 0) == 0 && take(SIGHUP, 1) == 0 ? 0 : -1;
}

void cli_interrupt_polled_only(void)
{
  pthread_mutex_lock(&guard.lock);
  guard.polled_only = 1;
  pthread_mutex_unlock(&guard.lock);
}

void cli_interrupt_finish(void)
{
  pthread_mutex_lock(&guard.lock);
  guard.finished = 1;
  pthread_mutex_unlock(&guard.lock);
}

int cli_interrupted(void)
{
  if (atomic_load(&interrupted) == 0)
    return 0;
  atomic_store(&seen, 1);
  return 1;
}

int cli_check_interrupt(fb_err *err)
{
  if (!cli_interrupted())
    return FB_OK;
  return fb_err_set(err, FB_EINTR, "%s", interrupted_msg);
}

int cli_guard_add(const cli_outdir *od, void (*abandon)(const cli_outdir *od))
{
  int rc = -1;
  pthread_mutex_lock(&guard.lock);
  for (size_t i = 0; i < CLI_MAX_GUARDED && rc != 0; ++i)
    if (!guard.open[i]) {
      guard.open[i] = od;
      guard.abandon[i] = abandon;
      rc = 0;
    }
  pthread_mutex_unlock(&guard.lock);
  return rc;
}

void cli_guard_remove(const cli_outdir *od)
{
  for (size_t i = 0; i < CLI_MAX_GUARDED; ++i)
    if (guard.open[i] == od)
      guard.open[i] = NULL;
}

void cli_guard_lock(void)
{
  pthread_mutex_lock(&guard.lock);
}

void cli_guard_unlock(int committed)
{
  guard.committed |= committed;
  pthread_mutex_unlock(&guard.lock);
}
