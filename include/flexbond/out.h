/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: output files and directories. Every file is written to a
 * temporary name in its destination directory and renamed into place
 * only when complete, so a failed run never leaves a half-written file.
 * Below every module that writes files (src/core). */
#ifndef FLEXBOND_OUT_H
#define FLEXBOND_OUT_H

#include <stddef.h>
#include <stdio.h>

#include "flexbond/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An output file being written: fb_out_open creates a temporary file
 * ".NAME.XXXXXX.tmp" beside path, exclusively (a file or a symbolic link
 * already at that name is never opened), fb_out_commit flushes, closes and
 * renames it to path, fb_out_abort removes it. Exactly one of commit/abort must follow a
 * successful open. A path that is a symbolic link is followed (the file it names is replaced,
 * the link kept); one that exists and is not a regular file (a FIFO, /dev/stdout on a terminal,
 * a device) gets the whole output copied in by fb_out_commit, and nothing on abort. A directory
 * or a link to nothing is refused (FB_EIO). */
typedef struct fb_out fb_out;
int fb_out_open(const char *path, fb_out **out, fb_err *err);
FILE *fb_out_stream(fb_out *o);
/* Checks every write made through the stream (disk full, I/O error). */
int fb_out_commit(fb_out **o, fb_err *err);
void fb_out_abort(fb_out **o);

/* Creates directory dir and its missing parents (mode 0777 & ~umask). */
int fb_mkdir_p(const char *dir, fb_err *err);
/* fb_mkdir_p that also returns the directories it created, in the order
 * it created them, each as the path it gave mkdir (*created, *ncreated:
 * fresh memory, the caller frees the strings and the array), so that a
 * caller that fails can remove exactly those, deepest first, whatever
 * "." and ".." dir holds; none if dir was there already. On failure, what
 * was created is left as it is and listed. created may be NULL. */
int fb_mkdir_p_created(const char *dir, char ***created, size_t *ncreated, fb_err *err);

#ifdef __cplusplus
}
#endif
#endif
