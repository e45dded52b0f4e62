/* Small internal helpers shared by the library's modules. */
#ifndef FLEXBOND_CORE_UTIL_H
#define FLEXBOND_CORE_UTIL_H

#include <stddef.h>
#include <stdio.h>

#include "flexbond/error.h"

/* Index of the first value of v[0..n) that is not finite; n if all are. */
size_t fb_first_nonfinite(const double *v, size_t n);
/* v for "%g" in a message: a NaN without the sign glibc prints ("-nan"),
 * which means nothing there. */
double fb_printable(double v);

/* Duplicate of s in fresh memory (NULL when out of memory). */
char *fb_strdup(const char *s);

/* Grows the array *arr of elements of size elsize (capacity *cap) so that
 * index n is valid, doubling; FB_ENOMEM (leaving *arr intact) on failure. */
int fb_grow(void **arr, size_t *cap, size_t n, size_t elsize);

/* The directory part of path in fresh memory: "." when path has no '/',
 * "/" for a file in the root (NULL when out of memory). */
char *fb_dirname(const char *path);

/* Reads the whole file at path into a new NUL-terminated buffer (*text,
 * *len bytes before the NUL; the caller frees *text). FB_EIO naming the
 * path and the system's reason when it cannot be opened or read. */
int fb_read_file(const char *path, char **text, size_t *len, fb_err *err);
/* fopen(path, mode) for reading an input file, which must be a regular
 * file: a directory, a device (/dev/zero would never end, a terminal
 * would wait) or a FIFO (would block) is refused. NULL with FB_EIO
 * "path: cannot open: ..." or "path: cannot read: Is a directory" (or
 * "not a regular file") in err. */
FILE *fb_open_input(const char *path, const char *mode, fb_err *err);

#endif
