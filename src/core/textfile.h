/* SPDX-License-Identifier: BSD-3-Clause */
/* Line-by-line reading of the text data files that models and scenarios
 * reference (CSV tables, road profiles, Matrix Market), with the checks
 * they share: lines are counted for "FILE:LINE: " messages, a file that
 * is not UTF-8 text is refused as binary data at its first bad byte
 * (getline's lines are then safe to treat as C strings: a NUL inside one
 * would silently cut it), a UTF-8 byte-order mark at the start is
 * skipped, and numbers are read as plain decimals only. */
#ifndef FLEXBOND_CORE_TEXTFILE_H
#define FLEXBOND_CORE_TEXTFILE_H

#include <stddef.h>
#include <stdio.h>

#include "flexbond/error.h"

/* The largest input file flexbond reads: 256 MiB (docs/errors.md,
 * "Limits"). The YAML loaders and the deck reader hold a whole file in
 * memory, libfyaml's tree several times more, and the sweep's fingerprint
 * reads every file of the study once more; the largest input of any
 * study, a road profile at 1 mm spacing over 10 km, is about 200 MB.
 * Checked before reading, from the open file's size, so that a sparse or
 * runaway file costs nothing; the reading stops there too, for a file
 * that grows meanwhile or one that reports no size. */
#define FB_INPUT_MAX_BYTES ((size_t)256 << 20)

/* FB_OK if fd, open on path, is a regular file of at most
 * FB_INPUT_MAX_BYTES, else FB_EIO "path: cannot read: Is a directory",
 * "... not a regular file (a device, pipe or socket)" or "path: cannot
 * read: N MB, more than the 256 MiB an input file may hold". */
int fb_input_check_fd(int fd, const char *path, fb_err *err);

/* fopen(path, mode) for reading an input file, the one way flexbond opens
 * one: it must be a regular file (a directory, a device: /dev/zero would
 * never end, a terminal would wait; a FIFO would block) of at most
 * FB_INPUT_MAX_BYTES (fb_input_check_fd). The file is opened without
 * blocking, so a FIFO is refused instead of waited on, and /proc's files
 * that would wait fail their read. NULL with FB_EIO "path: cannot open:
 * ..." or fb_input_check_fd's message in err. */
FILE *fb_open_input(const char *path, const char *mode, fb_err *err);

/* Reads the whole file at path (fb_open_input) into a new NUL-terminated
 * buffer (*text, *len bytes before the NUL; the caller frees *text).
 * FB_EIO naming the path and the system's reason when it cannot be opened
 * or read, or grows past FB_INPUT_MAX_BYTES while read; FB_ENOMEM. */
int fb_read_file(const char *path, char **text, size_t *len, fb_err *err);

/* One open file; the fields are read-only for the caller. */
typedef struct fb_text_reader {
  const char *path;   /* borrowed: names the file in messages */
  const char *format; /* borrowed: "CSV", "Matrix Market", in the binary-data message */
  FILE *fp;
  char *line;     /* the current line, owned, without its end of line */
  size_t cap;     /* bytes allocated for line */
  size_t line_no; /* 1-based number of line; 0 before the first */
  size_t bytes;   /* read so far, at most FB_INPUT_MAX_BYTES */
  fb_err *err;
} fb_text_reader;

/* Opens path for reading with fb_open_input (a regular file of at most
 * FB_INPUT_MAX_BYTES). *r
 * is initialised even on failure, so fb_text_close may always follow.
 * FB_EIO "path: cannot open: ..." when the file cannot be opened. */
int fb_text_open(fb_text_reader *r, const char *path, const char *format, fb_err *err);

/* Reads the next line into r->line and points *line at it, without its
 * "\n" or "\r\n"; *line is NULL at the end of the file. A UTF-8
 * byte-order mark at the start of the file is dropped. FB_EPARSE
 * "path:line: binary data (byte 0xNN in column C): not a FORMAT text file
 * (expected UTF-8 text)" at a NUL or another control character than tab,
 * DEL or invalid UTF-8 (C counts characters from 1); FB_EIO on a read
 * error or past FB_INPUT_MAX_BYTES, FB_ENOMEM. */
int fb_text_next_line(fb_text_reader *r, char **line);

/* Like fb_text_next_line, skipping blank lines and lines whose first
 * character after blanks is comment; the line returned has its leading
 * and trailing blanks (spaces and tabs) cut. */
int fb_text_next_data_line(fb_text_reader *r, char comment, char **line);

/* Closes the file and frees the line buffer; r may be closed twice. */
void fb_text_close(fb_text_reader *r);

/* Length of the well-formed UTF-8 sequence at s (n >= 1 bytes left), or 0
 * if there is none: a stray continuation byte, a bad lead byte, a
 * truncated sequence, an overlong form, a surrogate or a code point above
 * U+10FFFF (The Unicode Standard 15.0, section 3.9, Table 3-7). */
size_t fb_utf8_length(const unsigned char *s, size_t n);

/* Offset of the first byte of text[0..len) that makes it binary data: a
 * byte that starts no well-formed UTF-8 sequence (fb_utf8_length), a
 * control character other than tab (and, with line_ends, line feed and
 * carriage return), or DEL; len if there is none. *line and *col
 * (1-based; columns count characters) locate it. */
size_t fb_text_find_binary(const char *text, size_t len, int line_ends, size_t *line,
                           size_t *col);

/* Splits the line at text[*pos] (text holds len bytes and a NUL after
 * them) off in place: its line feed, and a carriage return before it, are
 * cut; *line points at it and *pos moves past it. Returns 0, or the
 * 1-based column of its first control byte other than tab (binary data,
 * which the caller refuses at that line). *pos must be below len. */
size_t fb_text_split_line(char *text, size_t len, size_t *pos, char **line);

/* A copy of text[0..len) with a NUL after it (*copy new, free() it), for
 * the readers that split a caller's text in place; FB_ENOMEM naming name. */
int fb_text_copy(const char *text, size_t len, const char *name, char **copy, fb_err *err);

/* Offset of the first control character of text[0..len): C0 (U+0000 ..
 * U+001F), DEL, or C1 (U+0080 .. U+009F, the UTF-8 bytes C2 80 .. C2 9F;
 * two bytes); tab, line feed and carriage return excepted when layout is
 * 1. *code gets its code point; len if there is none. One-line text
 * (names, units, --set values) may hold none of them: a line break would
 * start a line of an output file's own syntax. */
size_t fb_text_find_control(const char *text, size_t len, int layout, unsigned *code);

/* Parses the whole of text as a plain decimal number: an optional sign,
 * digits with at most one '.' (at least one digit), an optional exponent
 * (e or E, optional sign, digits). No blanks around it. FB_EPARSE with the
 * message "'TEXT' is not a number" (nothing strtod reads either: "abc",
 * "", "2.5.1"), "'TEXT' is not a decimal number" (hexadecimal: "0x10",
 * "0x1p3") or "'TEXT' is not a finite number" ("inf", "nan", or beyond
 * the range of a double: "1e999"), for the caller to prefix with
 * fb_err_prefix ("FILE:LINE: column 'z': "). *out is set only on success. */
int fb_parse_decimal(const char *text, double *out, fb_err *err);
/* fb_parse_decimal for a field of a data file (a table, a profile, a
 * matrix, a mesh): the message says what is wrong without quoting text
 * ("not a number"), which goes to fb_err.excerpt, so that no data file's
 * text reaches a message (or the output file a message may go into). */
int fb_parse_decimal_field(const char *text, double *out, fb_err *err);
/* FB_OK unless the decimal text, which strtod read as v, is not the
 * number written: an integer (digits, a sign allowed) above 2^53 in
 * magnitude, which a double cannot hold exactly, or a number with a
 * nonzero digit that is too small for a double and reads as 0. FB_EINVAL
 * saying which otherwise. Every reader of numbers (fb_parse_decimal, the
 * YAML loaders, expressions) checks with it. */
int fb_decimal_check_exact(const char *text, double v, fb_err *err);
/* The shortest "%.Ng" of v, N from min_digits to 17, that strtod reads
 * back as v (17 significant digits always do: C11 5.2.4.2.2,
 * DECIMAL_DIG), into buf. min_digits sets when an exponent appears: with
 * 15, every integer up to 1e15 is written out ("1000000", not "1e+06"). */
void fb_format_shortest(double v, int min_digits, char *buf, size_t size);

/* Appends printf-formatted text to the text buf (size bytes) holds in its
 * first len, and returns the new length: size - 1 once the text no longer
 * fits (it is then cut there, so the caller's loop may stop at
 * len + 1 >= size). buf stays NUL-terminated. */
size_t fb_text_append(char *buf, size_t size, size_t len, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

#endif
