/* Child processes of the library (gnuplot), run the one way that is safe
 * to interrupt and to time out. */
#ifndef FLEXBOND_IO_CHILD_H
#define FLEXBOND_IO_CHILD_H

#include "flexbond/error.h"

/* A program to run: program is searched in PATH, argv[0] names it,
 * argv ends with NULL; the child starts in directory cwd with its
 * standard input from /dev/null and its standard output and error into
 * the new file log (in cwd), and is killed after timeout_s seconds. */
typedef struct fb_child_spec {
  const char *program;
  char *const *argv;
  const char *cwd;
  const char *log;
  double timeout_s;
} fb_child_spec;

/* Runs the child and waits for it. The child is the leader of a process
 * group of its own, so that a terminal's Ctrl-C (sent to the foreground
 * group) reaches this process, which decides, and not the child; it gets
 * SIGKILL when the thread that started it ends (PR_SET_PDEATHSIG), so a
 * process that exits on a signal leaves no child behind; it starts with
 * no signal blocked and every signal's default action. FB_OK when it
 * exited with status 0; otherwise FB_EIO with a message "what: ..." (its
 * exit status or signal, a time-out, or why it could not start). */
int fb_child_run(const fb_child_spec *spec, const char *what, fb_err *err);

#endif
