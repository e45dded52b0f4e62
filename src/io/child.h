/* SPDX-License-Identifier: BSD-3-Clause */
/* Child processes of the library (gnuplot, Graphviz's dot), run the one
 * way that is safe to interrupt and to time out. */
#ifndef FLEXBOND_IO_CHILD_H
#define FLEXBOND_IO_CHILD_H

#include <stddef.h>

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

/* Checks a file a child wrote; FB_OK or an error saying what is wrong. */
typedef int (*fb_child_check_fn)(const char *path, fb_err *err);

/* Runs the child (fb_child_run) that is to write the file `name` in its
 * directory spec->cwd, then checks that file with check: a program that
 * exits 0 without a complete file is a failure too ("what: PROGRAM exited
 * 0 but ..."). *out: the file's path (new; NULL on failure). */
int fb_child_make(const fb_child_spec *spec, const char *name, fb_child_check_fn check,
                  const char *what, char **out, fb_err *err);

/* Removes the files names[0 .. n) a child's run left in dir, then dir,
 * and frees dir (the path of a private directory: fb_tmpdir_create). */
void fb_child_dir_remove(char *dir, const char *const *names, size_t n);

#endif
