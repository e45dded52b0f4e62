/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: status codes and error context.
 *
 * Every fallible function returns an int status (FB_OK on success) and, when
 * given a non-NULL fb_err, records a human-readable message there. Callers
 * add context (file:line, element or bond names) with fb_err_prefix() as the
 * error travels up. No function prints or exits; only the CLI does. */
#ifndef FLEXBOND_ERROR_H
#define FLEXBOND_ERROR_H

#include <stdarg.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum fb_status {
  FB_OK = 0,
  FB_ENOMEM = 1,  /* allocation failed */
  FB_EINVAL = 2,  /* invalid argument or parameter value */
  FB_EPARSE = 3,  /* malformed input text (YAML, CSV, expression, mtx) */
  FB_EMODEL = 4,  /* structurally invalid model (names, ports, dimensions) */
  FB_ECAUSAL = 5, /* causality: derivative causality, conflict, algebraic loop */
  FB_ESOLVER = 6, /* numerical failure (singular matrix, CVODE error) */
  FB_EIO = 7,     /* file could not be read or written */
  FB_EINTR = 8    /* interrupted: the caller asked to stop (fb_sim_progress_fn) */
};

#define FB_ERR_MSG_MAX 4096

/* What in a bond graph an error is about (fb_err.origin): set where the
 * error is raised (src/bg) so that whoever built the graph from a file
 * can name the file, line and key of its cause (fb_model_blame) without
 * reading the message. */
enum fb_err_origin {
  FB_ORIGIN_NONE = 0,    /* not about one part of a graph, or not known */
  FB_ORIGIN_ELEMENT = 1, /* element origin_index of the graph */
  FB_ORIGIN_BOND = 2     /* bond origin_index of the graph */
};

/* Where the value an error is about came from (fb_err.source). */
enum fb_err_source {
  FB_SOURCE_NONE = 0,    /* not known, or not about an input value */
  FB_SOURCE_FILE = 1,    /* written in fb_err.file at line:column */
  FB_SOURCE_OPTION = 2,  /* a command-line option (fb_err.source_text: "--t-end") */
  FB_SOURCE_OVERRIDE = 3 /* an override of a file's value
                            (fb_err.source_text: "--set KEY=VALUE") */
};

enum {
  FB_ERR_FILE_MAX = 1024,
  FB_ERR_KEY_MAX = 256,
  FB_ERR_SOURCE_MAX = 512,
  FB_ERR_EXCERPT_MAX = 72, /* 64 bytes of text, its escapes and "..." */
  FB_ERR_FIELD_MAX = 64
};

/* fb_err_part.element of a part that is no element of an array. */
#define FB_ERR_NO_ELEMENT ((size_t)-1)

/* What part of a description an error is about, as typed fields set
 * where the error arises (fb_err.part): which item (kind, a number the
 * describing layer defines, such as enum fb_part_kind of vehicle.h; 0
 * none), which one of its list (index), which of its members (field, its
 * name in the item's struct: "spring_k", "hull_mesh.x_rear"; "" the whole
 * item) and which element of an array member. Whoever made the
 * description says where that part came from (a file's line and key, an
 * override, a program's argument) without the layer that raised the error
 * knowing any of them, and without reading the message. */
typedef struct fb_err_part {
  int kind;
  size_t index;
  size_t element; /* FB_ERR_NO_ELEMENT: none */
  char field[FB_ERR_FIELD_MAX];
} fb_err_part;

/* An error is a value: its code, its message, and, as fields set where
 * the error arises, what it is about. Nobody parses msg to find these. */
typedef struct fb_err {
  int code;                 /* last status recorded, FB_OK when clear */
  char msg[FB_ERR_MSG_MAX]; /* NUL-terminated message, "" when clear */
  int origin;               /* enum fb_err_origin; fb_err_set resets it */
  size_t origin_index;      /* element or bond index, with origin */
  /* The input value concerned; fb_err_set resets them all. msg already
   * names them for a reader ("FILE:LINE:COL: KEY: ..."); these are for
   * programs. */
  char key[FB_ERR_KEY_MAX];            /* key path in its file ("suspensions.axles[1].x",
                                          "simulation.rtol"), or the name of a
                                          setting ("rtol"); "" none */
  char file[FB_ERR_FILE_MAX];          /* file of the value, "" none */
  int line, column;                    /* 1-based, 0 unknown */
  int source;                          /* enum fb_err_source */
  char source_text[FB_ERR_SOURCE_MAX]; /* the option or override, "" none */
  /* The text of a data file (a table, a profile, a matrix, a mesh) the
   * error is about: the one field that failed, escaped and cut at 64
   * bytes; "" none. msg never quotes a data file's text, so that a
   * message may go into an output file (sweep.csv) and a file named by
   * mistake (/etc/shadow) is not copied anywhere; a front end may show
   * this to its user beside msg. */
  char excerpt[FB_ERR_EXCERPT_MAX];
  /* The part of a description the error is about (kind 0: none); reset
   * by fb_err_set. */
  fb_err_part part;
  /* Where in msg the text about the value starts, after where it came
   * from (fb_err_prefix_location: a file's "FILE:LINE:COL: KEY: ") and
   * any context prefixed after that (an override's): a front end that
   * says where the value came from in its own terms (a Python argument's
   * path) shows msg + text_start after it. 0: no location. */
  size_t text_start;
} fb_err;

/* Records, for the error just set, the part of a description it is about
 * (fb_err_part; field copied, cut to fit). Returns err->code, FB_OK if err
 * is NULL: a raiser returns its own status, `return fb_err_set(err,
 * FB_EINVAL, ...), fb_err_set_part(err, ...), FB_EINVAL;`, so that a call
 * without an fb_err still fails. */
int fb_err_set_part(fb_err *err, int kind, size_t index, size_t element, const char *field);

/* Records, for the error just set, the key path or setting name it is
 * about (printf-formatted; err->msg is not changed). Returns err->code
 * (FB_OK if err is NULL), so raisers write
 * `return fb_err_set_key(err, "rtol"), rc;` or chain it after fb_err_set. */
int fb_err_set_key(fb_err *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Records the file position of the error's value (file copied; line and
 * column 1-based, 0 unknown) and source FB_SOURCE_FILE. */
void fb_err_set_location(fb_err *err, const char *file, int line, int column);
/* Records that the value came from an option or override (source:
 * enum fb_err_source, text copied: "--t-end", "--set KEY=VALUE"). */
void fb_err_set_source(fb_err *err, int source, const char *text);

/* Resets err to FB_OK with an empty message. err may be NULL. */
void fb_err_clear(fb_err *err);

/* Records that the error just set in err is about element or bond index
 * of the graph the failing call was given (origin: enum fb_err_origin).
 * Returns code, so raisers write
 * `return fb_err_set_origin(err, FB_ORIGIN_BOND, b, fb_err_set(err, ...));`.
 * err may be NULL. */
int fb_err_set_origin(fb_err *err, int origin, size_t index, int code);

/* Records code and a printf-formatted message, replacing any previous one
 * (and its origin). Returns code, so callers write `return fb_err_set(err, FB_EINVAL, ...);`.
 * err may be NULL (the message is then dropped). */
int fb_err_set(fb_err *err, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* fb_err_set with the arguments as a va_list (for functions that take
 * printf arguments of their own and add fields after the message). */
int fb_err_vset(fb_err *err, int code, const char *fmt, va_list ap)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 0)))
#endif
    ;

#if defined(__clang_analyzer__)
/* For the static analyzer only (`make tidy`): it cannot see into error.c, so
 * without this it explores paths where fb_err_set returns FB_OK and reports
 * impossible NULL dereferences after `if (rc) return rc;`. The compiled code
 * never sees this macro. */
#define fb_err_set(err, code, ...) (fb_err_set((err), (code), __VA_ARGS__), (code))
#define fb_err_set_origin(err, origin, index, code)                                            \
  (fb_err_set_origin((err), (origin), (index), (code)), (code))
#endif

/* Prepends printf-formatted context to the recorded message (the context is
 * inserted verbatim, include the separator, e.g. "model.yaml:12: "); the
 * origin is kept.
 * Returns err->code (FB_OK if err is NULL). */
int fb_err_prefix(fb_err *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* fb_err_prefix for the prefix that says where the value came from
 * ("FILE:LINE:COL: KEY: "): fb_err.text_start then marks the text after
 * it. A plain fb_err_prefix before any location is part of the text (it
 * builds the sentence); after one, it is context (an override's label)
 * and text_start moves with the text. */
int fb_err_prefix_location(fb_err *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Records the data-file text the error just set is about (fb_err.excerpt):
 * the first n bytes of text (n at most what it holds), escaped as
 * fb_err_escape does, cut at 64 bytes with "...". */
void fb_err_set_excerpt(fb_err *err, const char *text, size_t n);

/* The message as a user reads it, into buf (size bytes): msg and, when
 * there is one, the excerpt after it: "...: not a number (read: 'abc')".
 * For a terminal or an exception, not for a file. Returns buf. */
char *fb_err_describe(const fb_err *err, char *buf, size_t size);

/* Appends printf-formatted text to the recorded message (as far as it
 * fits). Returns err->code (FB_OK if err is NULL). */
int fb_err_append(fb_err *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* text into out (size bytes, NUL-terminated, cut short to fit) as one line
 * of printable text: every control character (U+0000..U+001F, U+007F and,
 * in UTF-8, U+0080..U+009F) as a C escape: \n, \r, \t, \xHH, \u00HH. A
 * message is one line whatever text it quotes; every message that
 * fb_err_set, fb_err_vset, fb_err_prefix and fb_err_append record passes
 * through this, as does the key of fb_err_set_key. */
void fb_err_escape(char *out, size_t size, const char *text);

/* A long computation's report to whoever asked for it, and their way to
 * stop it. fn is called when a stage begins (fraction 0), as it goes
 * (fraction in (0, 1), or -1 when it cannot tell how far it is), and when
 * it ends (fraction 1), with a phrase that says what the stage does and on
 * how much ("eigen-solve of 11964 DOFs by block Lanczos"). Between the
 * begin and the end it is called at least every few tenths of a second of
 * work wherever the stage can poll. A nonzero return stops the
 * computation, which then fails with FB_EINTR. A NULL fn is no report. */
typedef int (*fb_progress_fn)(void *ctx, const char *stage, double fraction);
typedef struct fb_progress {
  fb_progress_fn fn;
  void *ctx;
} fb_progress;
/* Calls p's fn (if p and fn are not NULL): FB_OK to go on, FB_EINTR with
 * the message "interrupted during STAGE" when it asks to stop. */
int fb_progress_report(const fb_progress *p, const char *stage, double fraction, fb_err *err);

/* Short constant name of a status code, e.g. "FB_EPARSE". */
const char *fb_status_name(int code);

#ifdef __cplusplus
}
#endif
#endif
