/* SPDX-License-Identifier: BSD-3-Clause */
/* Temporary files and directories beside a destination, created
 * exclusively: the one way the library makes a file or directory that it
 * later renames into place. */
#ifndef FLEXBOND_CORE_TMPFILE_H
#define FLEXBOND_CORE_TMPFILE_H

/* Creates a new, empty file for writing in the directory of path, named
 * ".BASE.XXXXXX.tmp" (BASE path's last component, X random letters), with
 * O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC and mode 0666 less the umask,
 * as fopen would make it. O_EXCL never opens a file that is already there,
 * and a symbolic link at the name counts as there (POSIX.1-2008, open:
 * "If O_CREAT and O_EXCL are set ... symbolic link ... fail"), so a name
 * planted by someone who can write the directory is skipped, never
 * followed; another random name is tried. On success *fd is the open
 * descriptor and *tmp_path its name in fresh memory (the caller frees it,
 * and removes the file if it does not rename it). Returns 0 or an errno
 * value (ENOMEM; EEXIST when every try met an existing name). */
int fb_tmpfile_create(const char *path, int *fd, char **tmp_path);

/* Creates a new directory, mode 0700, in the directory of path, named
 * ".flexbond-TAG-XXXXXX" (mkdtemp(3): exclusive creation, no link
 * followed). *dir is its name in fresh memory (the caller frees it).
 * Returns 0 or an errno value. */
int fb_tmpdir_create(const char *path, const char *tag, char **dir);

#endif
