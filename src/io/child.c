/* SPDX-License-Identifier: BSD-3-Clause */
/* Child processes (see io/child.h).
 *
 * fork and execve rather than posix_spawn, because the child must do two
 * things posix_spawn cannot: change to its directory (so that no path of
 * the user's, which may hold any character, ever appears in a script the
 * child reads) and ask the kernel to kill it when its parent dies
 * (prctl(PR_SET_PDEATHSIG), Linux). Between fork and execve the child
 * calls only async-signal-safe functions (POSIX.1-2008, 2.4.3), as a
 * child of a threaded process must; the program is found in PATH before
 * the fork for that reason. The parent polls waitpid with a growing
 * pause, which serves the time-out without a timer or SIGCHLD handler. */
#include "io/child.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "core/util.h"

/* The environment handed to the child (POSIX.1-2008, exec: the
 * application declares it). */
extern char **environ;

/* Bytes of the child's log quoted in a failure message; a bound above the
 * signal numbers of Linux (64) for resetting them all. */
enum { LOG_TAIL = 600, CHILD_LAST_SIGNAL = 65 };

/* The first executable program in the directories of PATH (or, without
 * PATH, /usr/bin:/bin), in fresh memory; NULL if there is none (errno
 * ENOENT) or out of memory. */
static char *find_program(const char *program)
{
  const char *path = getenv("PATH");
  if (!path || !*path)
    path = "/usr/bin:/bin";
  const size_t plen = strlen(program);
  for (const char *p = path;; ++p) {
    const char *end = strchr(p, ':');
    const size_t dlen = end ? (size_t)(end - p) : strlen(p);
    char *full = malloc(dlen + plen + 3);
    if (!full)
      return NULL;
    /* An empty entry means the current directory (POSIX.1-2008, 8.3). */
    snprintf(full, dlen + plen + 3, "%.*s/%s", dlen ? (int)dlen : 1, dlen ? p : ".", program);
    struct stat st;
    if (stat(full, &st) == 0 && S_ISREG(st.st_mode) && access(full, X_OK) == 0)
      return full;
    free(full);
    if (!end)
      break;
    p = end;
  }
  errno = ENOENT;
  return NULL;
}

static double now_s(void)
{
  struct timespec ts = {0, 0};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* In the child, after fork: only async-signal-safe calls. Never returns. */
static void child_exec(const char *file, char *const *argv, const char *cwd, int in_fd,
                       int log_fd, pid_t parent)
{
  setpgid(0, 0);
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  /* The parent may have died before prctl took effect. */
  if (getppid() != parent)
    _exit(127);
  sigset_t none;
  sigemptyset(&none);
  sigprocmask(SIG_SETMASK, &none, NULL);
  /* Every signal at its default action, an ignored one too (exec keeps
   * SIG_IGN): a shell's background job ignores SIGINT, and the child is
   * to start the same wherever flexbond was started. Numbers past the
   * last signal fail with EINVAL, harmlessly. */
  struct sigaction dfl;
  memset(&dfl, 0, sizeof dfl);
  dfl.sa_handler = SIG_DFL;
  for (int sig = 1; sig < CHILD_LAST_SIGNAL; ++sig)
    if (sig != SIGKILL && sig != SIGSTOP)
      sigaction(sig, &dfl, NULL);
  if (chdir(cwd) != 0 || dup2(in_fd, STDIN_FILENO) < 0 || dup2(log_fd, STDOUT_FILENO) < 0 ||
      dup2(log_fd, STDERR_FILENO) < 0)
    _exit(127);
  execve(file, argv, environ);
  _exit(127);
}

/* Waits for pid until deadline (a now_s time); 1 with *status when it
 * exited, 0 at the deadline, -1 on a waitpid error (errno). */
static int wait_until(pid_t pid, double deadline, int *status)
{
  long pause_ns = 1000000; /* 1 ms, doubled up to 32 ms: short plots stay quick */
  for (;;) {
    const pid_t w = waitpid(pid, status, WNOHANG);
    if (w == pid)
      return 1;
    if (w < 0 && errno != EINTR)
      return -1;
    if (now_s() >= deadline)
      return 0;
    const struct timespec pause = {0, pause_ns};
    nanosleep(&pause, NULL);
    if (pause_ns < 32000000)
      pause_ns *= 2;
  }
}

/* The last LOG_TAIL bytes of the log at log_path, one line (control
 * characters as spaces), into buf; "" if there is none. */
static void log_tail(const char *log_path, char *buf, size_t size)
{
  buf[0] = '\0';
  const int fd = open(log_path, O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0)
    return;
  const off_t end = lseek(fd, 0, SEEK_END);
  const off_t from = end > LOG_TAIL ? end - LOG_TAIL : 0;
  char text[LOG_TAIL + 1];
  ssize_t got = lseek(fd, from, SEEK_SET) == from ? read(fd, text, LOG_TAIL) : -1;
  close(fd);
  if (got <= 0)
    return;
  while (got > 0 && (unsigned char)text[got - 1] <= ' ')
    --got;
  text[got] = '\0';
  for (ssize_t i = 0; i < got; ++i)
    if ((unsigned char)text[i] < ' ' || text[i] == 0x7f)
      text[i] = ' ';
  snprintf(buf, size, ": %s", text);
}

/* Opens /dev/null for reading and the new log at log_path for writing,
 * both close-on-exec (the child's dup2 copies lose the flag). 0 or the
 * errno value of the open that failed (nothing is left open then). */
static int open_streams(const char *log_path, int *in_fd, int *log_fd)
{
  *log_fd = -1;
  *in_fd = open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (*in_fd < 0)
    return errno;
  *log_fd = open(log_path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (*log_fd >= 0)
    return 0;
  const int e = errno;
  close(*in_fd);
  *in_fd = -1;
  return e;
}

/* Below this much free space (bytes) a child's silent failure is put
 * down to a full file system: a figure or a picture is some 10 kB to
 * 1 MB, and by the time the child has ended, it (or another job beside
 * it) may have removed what it had written, so that "nothing free" is
 * seldom what is seen. */
#define FULL_DISK_BYTES (1024.0 * 1024.0)

/* Why a child that said nothing may have failed: its directory's file
 * system is (nearly) full, so that its log could not be written either,
 * as ": " and strerror(ENOSPC) with what is free into buf; "" otherwise. */
static void full_disk(const char *dir, char *buf, size_t size)
{
  struct statvfs st;
  buf[0] = '\0';
  if (statvfs(dir, &st) != 0)
    return;
  const double free_bytes = (double)st.f_bavail * (double)st.f_frsize;
  if (free_bytes < FULL_DISK_BYTES) {
    char text[32];
    snprintf(buf, size, ": %s (%s free now)", strerror(ENOSPC),
             fb_bytes_text(free_bytes, text, sizeof text));
  }
}

/* The outcome of a child that ended with status. Its log's tail says
 * why; a signal is named (SIGXFSZ: "File size limit exceeded"); a silent
 * failure on a full file system says so. */
static int report_status(const fb_child_spec *spec, const char *log_path, const char *what,
                         int status, fb_err *err)
{
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
    return FB_OK;
  char tail[LOG_TAIL + 8];
  log_tail(log_path, tail, sizeof tail);
  if (!tail[0])
    full_disk(spec->cwd, tail, sizeof tail);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
    return fb_err_set(err, FB_EIO, "%s: %s could not be started%s", what, spec->program, tail);
  if (WIFEXITED(status))
    return fb_err_set(err, FB_EIO, "%s: %s failed (exit status %d)%s", what, spec->program,
                      WEXITSTATUS(status), tail);
  return fb_err_set(err, FB_EIO, "%s: %s was killed by signal %d (%s)%s", what, spec->program,
                    WTERMSIG(status), strsignal(WTERMSIG(status)), tail);
}

/* fb_child_run with the log at log_path (spec->cwd/spec->log). */
static int run_logged(const fb_child_spec *spec, const char *log_path, const char *what,
                      fb_err *err)
{
  char *file = find_program(spec->program);
  if (!file)
    return errno == ENOMEM ? fb_err_set(err, FB_ENOMEM, "%s: out of memory", what)
                           : fb_err_set(err, FB_EIO, "%s: cannot start %s: not found in PATH",
                                        what, spec->program);
  int in_fd = -1, log_fd = -1;
  int e = open_streams(log_path, &in_fd, &log_fd);
  if (e != 0) {
    free(file);
    return fb_err_set(err, e == ENOMEM ? FB_ENOMEM : FB_EIO, "%s: cannot start %s: %s", what,
                      spec->program, strerror(e));
  }
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0)
    child_exec(file, spec->argv, spec->cwd, in_fd, log_fd, parent);
  e = errno;
  close(in_fd);
  close(log_fd);
  free(file);
  if (pid < 0)
    return fb_err_set(err, FB_EIO, "%s: cannot start %s: %s", what, spec->program, strerror(e));
  /* Also here, so the group exists before any kill below (no race with
   * the child's own call); EACCES once the child has exec'ed is fine. */
  setpgid(pid, pid);
  int status = 0;
  const int done = wait_until(pid, now_s() + spec->timeout_s, &status);
  if (done == 1)
    return report_status(spec, log_path, what, status, err);
  e = errno;
  kill(-pid, SIGKILL);
  kill(pid, SIGKILL);
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
    ;
  if (done == 0)
    return fb_err_set(err, FB_EIO, "%s: %s did not finish within %g s and was killed", what,
                      spec->program, spec->timeout_s);
  return fb_err_set(err, FB_EIO, "%s: waiting for %s: %s", what, spec->program, strerror(e));
}

int fb_child_run(const fb_child_spec *spec, const char *what, fb_err *err)
{
  char *log_path = fb_path_join(spec->cwd, spec->log);
  const int rc = log_path ? run_logged(spec, log_path, what, err)
                          : fb_err_set(err, FB_ENOMEM, "%s: out of memory", what);
  free(log_path);
  return rc;
}

int fb_child_make(const fb_child_spec *spec, const char *name, fb_child_check_fn check,
                  const char *what, char **out, fb_err *err)
{
  *out = NULL;
  int rc = fb_child_run(spec, what, err);
  char *file = rc == FB_OK ? fb_path_join(spec->cwd, name) : NULL;
  if (rc == FB_OK && !file)
    rc = fb_err_set(err, FB_ENOMEM, "%s: out of memory", what);
  if (rc == FB_OK && check(file, err) != FB_OK)
    rc = fb_err_prefix(err, "%s: %s exited 0 but ", what, spec->program);
  if (rc == FB_OK)
    *out = file;
  else
    free(file);
  return rc;
}

void fb_child_dir_remove(char *dir, const char *const *names, size_t n)
{
  for (size_t i = 0; i < n; ++i) {
    char *p = fb_path_join(dir, names[i]);
    if (p)
      remove(p);
    free(p);
  }
  rmdir(dir);
  free(dir);
}
