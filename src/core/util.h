/* SPDX-License-Identifier: BSD-3-Clause */
/* Small internal helpers shared by the library's modules. */
#ifndef FLEXBOND_CORE_UTIL_H
#define FLEXBOND_CORE_UTIL_H

#include <stddef.h>
#include <stdio.h>

#include "flexbond/error.h"
#include "flexbond/param.h"

#include "textfile.h" /* beside it: also found from src/cli, which has no src/ path */

/* Index of the first value of v[0..n) that is not finite; n if all are. */
size_t fb_first_nonfinite(const double *v, size_t n);
/* v for "%g" in a message: a NaN without the sign glibc prints ("-nan"),
 * which means nothing there. */
double fb_printable(double v);

/* Duplicate of s in fresh memory (NULL when out of memory). */
char *fb_strdup(const char *s);
/* printf-formatted text in fresh memory (NULL when out of memory). */
char *fb_strdup_printf(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Grows the array *arr of elements of size elsize (capacity *cap) so that
 * index n is valid, doubling; FB_ENOMEM (leaving *arr intact) on failure. */
int fb_grow(void **arr, size_t *cap, size_t n, size_t elsize);

/* The directory part of path in fresh memory: "." when path has no '/',
 * "/" for a file in the root (NULL when out of memory). */
char *fb_dirname(const char *path);
/* dir/name in fresh memory (NULL when out of memory). */
char *fb_path_join(const char *dir, const char *name);

/* A size in bytes as a message gives it, with the SI prefix that puts it
 * in [1, 1000): "512 B", "98.3 kB", "1.28 MB", "4.29 GB" (into buf). */
const char *fb_bytes_text(double bytes, char *buf, size_t size);
/* FB_OK when bytes fit in limit (0: no limit), else FB_ENOMEM with "WHAT
 * needs SIZE, more than the LIMIT allowed", WHAT printf-formatted from
 * fmt: the check a large allocation makes before it is tried. */
/* The largest order a dense eigen-solve (LAPACK dgeev) is asked to take:
 * 3000, where it took 20 s with eigenvectors on this project's reference
 * machine (2 cores, bench/README.md) and three n x n matrices take 216 MB.
 * Its time grows as n^3 and cannot be interrupted: 10000 states would be
 * some 12 minutes, 24000 (System 2 with every mode of a density-3 hull)
 * hours. */
#define FB_DENSE_EIG_MAX 3000
/* FB_OK when a dense eigen-solve of order n, holding nmatrices n x n
 * matrices, is within FB_DENSE_EIG_MAX and limit bytes (0: no limit);
 * else FB_ENOMEM saying what (printf-formatted from fmt) would need,
 * checked before anything is allocated. */
int fb_check_dense_eig(size_t n, size_t nmatrices, size_t limit, fb_err *err, const char *fmt,
                       ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
int fb_check_memory(double bytes, size_t limit, fb_err *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Wall time since *t0 (CLOCK_MONOTONIC), s. */
struct timespec;
double fb_seconds_since(const struct timespec *t0);

/* Ranges: FB_RANGE_* of flexbond/param.h. */
/* 1 if x lies within the bounds (x finite is the caller's). */
int fb_range_contains(unsigned bounds, double lo, double hi, double x);
/* The range as a message says it, into buf: "> 0", "in [0, 0.5)", "<= 1";
 * "" for none. */
void fb_range_text(unsigned bounds, double lo, double hi, char *buf, size_t size);

/* 1 if name is an identifier, [A-Za-z_][A-Za-z0-9_]* (NULL: 0): a name
 * an expression, a key or a C member can be. */
int fb_is_identifier(const char *name);

/* Candidate names for "did you mean" suggestions (suggest.c): name i of
 * ctx's n. */
typedef const char *(*fb_name_fn)(const void *ctx, size_t i);
/* The candidate closest to word by edit distance (about one edit per
 * three characters at most), or NULL if none is close. */
const char *fb_suggest(const char *word, size_t n, fb_name_fn name_at, const void *ctx);
/* Same over a NULL-terminated list of strings. */
const char *fb_suggest_list(const char *word, const char *const *list);

/* Input files are opened and read by core/textfile.h (fb_open_input,
 * fb_read_file), with their checks. */

#endif
