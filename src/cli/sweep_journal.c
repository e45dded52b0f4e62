/* SPDX-License-Identifier: BSD-3-Clause */
/* The journal of a sweep (sweep.h): DIR/sweep.partial.csv, which a
 * killed or interrupted sweep leaves behind and `--resume` reads back.
 *
 *   # flexbond sweep journal (docs/sweep.md), study 3f2a..., 12 cases; ...
 *   # written by flexbond 0.1.0
 *   # input 5d1e... examples/apc6x6_shock_table.yaml
 *   # input 9c07... examples/shock_front.csv
 *   case,status,<sweep.csv's header>
 *   4,FB_OK,<case 4's sweep.csv row>
 *   7,FB_EINVAL/set,<case 7's row: an error about a value its --set replaced>
 *
 * The rows come in the order the cases finish, each flushed at once: a
 * killed process loses only the cases it was running (a row it was
 * writing is torn, has no line end, and is dropped on resuming). They are
 * not fsync'ed: that costs milliseconds a row (docs/sweep.md), under the
 * pool's lock, and a crash of the machine costs only the cases of the rows
 * not yet written out. The metrics are printed to the last bit
 * (sweep_format_double), so a resumed sweep writes the same sweep.csv as
 * one that was never stopped. The study's fingerprint (flexbond's
 * version, the system, the keys and their values, and the bytes of every
 * file the study reads) keeps a journal from being resumed by another
 * study, or after a file it read has changed; the "# input" lines let the
 * refusal name that file (its path percent-encoded where it has a control
 * character or a '%', so that a line break in a directory's name cannot
 * break the line). An exclusive flock(2) keeps two sweeps from writing
 * one journal; it is opened without following a symbolic link, and only
 * as a regular file. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../core/textfile.h"
#include "cli.h"
#include "sweep.h"

struct sweep_journal {
  const sweep_args *a;
  char *path;
  FILE *fp;    /* holds the lock */
  size_t rows; /* cases in the file */
};

char *sweep_journal_path(const char *dir)
{
  return cli_join_path(dir, "sweep.partial.csv");
}

/* ---- The study's fingerprint: 64-bit FNV-1a (Fowler, Noll and Vo; the
 * offset basis and prime of the published parameters for 64 bits). */

uint64_t sweep_fnv1a(uint64_t h, const void *data, size_t n)
{
  const unsigned char *b = data;
  for (size_t i = 0; i < n; ++i) {
    h ^= b[i];
    h *= UINT64_C(1099511628211);
  }
  return h;
}

static uint64_t fnv1a_text(uint64_t h, const char *text)
{
  return sweep_fnv1a(h, text, strlen(text) + 1); /* with its NUL: "ab","c" != "a","bc" */
}

/* ---- The files a study reads: the scenario file, every file it names
 * (fb_scenario.inputs: damper tables, road profile, hull deck), and the
 * file every --set value of a file key names, since each case reads its
 * own. */

typedef struct study_inputs {
  uint64_t h;  /* the fingerprint so far */
  FILE *lines; /* "# input HASH PATH\n" per file; NULL: not wanted */
  char *dir;   /* the scenario's directory */
  char **seen; /* the paths hashed so far, each hashed once */
  size_t nseen, cap;
} study_inputs;

/* The directory of path in fresh memory, as the scenario reader takes it
 * (fb_dirname): "." for a bare name. NULL: out of memory. */
static char *dir_of(const char *path)
{
  const char *slash = strrchr(path, '/');
  const size_t len = !slash ? 1 : slash == path ? 1 : (size_t)(slash - path);
  char *dir = malloc(len + 1);
  if (dir) {
    memcpy(dir, !slash ? "." : path, len);
    dir[len] = '\0';
  }
  return dir;
}

/* 1 if the file at path has been added. */
static int seen_before(const study_inputs *in, const char *path)
{
  for (size_t i = 0; i < in->nseen; ++i)
    if (!strcmp(in->seen[i], path))
      return 1;
  return 0;
}

/* path as a journal line holds it: every byte below 0x20, DEL and '%'
 * itself percent-encoded (%0A for a line break), everything else as it
 * is. The line stays one line whatever the path, an ordinary path is its
 * own bytes, and two paths never write the same text (the encoding is
 * one to one), so the journal's lines are compared with the study's
 * encoded text by text. */
static void write_path(FILE *fp, const char *path)
{
  for (const unsigned char *c = (const unsigned char *)path; *c; ++c)
    if (*c < 0x20 || *c == 0x7f || *c == '%')
      fprintf(fp, "%%%02X", *c);
    else
      fputc(*c, fp);
}

/* Adds the file at path (not seen before), with its bytes text (NULL: it
 * cannot be read): its hash to the fingerprint and its line. */
static int add_input(study_inputs *in, const char *path, const char *text, size_t len,
                     fb_err *err)
{
  if (in->nseen == in->cap) {
    const size_t cap = in->cap ? 2 * in->cap : 16;
    char **grown = realloc(in->seen, cap * sizeof *grown);
    if (!grown)
      return fb_err_set(err, FB_ENOMEM, "out of memory for the study's files");
    in->seen = grown;
    in->cap = cap;
  }
  if (!(in->seen[in->nseen] = strdup(path)))
    return fb_err_set(err, FB_ENOMEM, "out of memory for the study's files");
  ++in->nseen;
  /* A file that cannot be read fails its cases, not the study; that it
   * could not is part of the study, so that it is not resumed once the
   * file is back. */
  char hash[32] = "unreadable";
  if (text)
    snprintf(hash, sizeof hash, "%016llx",
             (unsigned long long)sweep_fnv1a(UINT64_C(14695981039346656037), text, len));
  in->h = fnv1a_text(in->h, hash);
  if (in->lines) {
    fprintf(in->lines, "# input %s ", hash);
    write_path(in->lines, path);
    fputc('\n', in->lines);
  }
  return FB_OK;
}

/* Adds the file at path (resolved), once. */
static int add_file(study_inputs *in, const char *path, fb_err *err)
{
  if (seen_before(in, path))
    return FB_OK;
  char *text = NULL;
  size_t len = 0;
  /* Read as every reader of the study reads it (fb_read_file: a regular
   * file within FB_INPUT_MAX_BYTES), so that a device or an endless file
   * is refused here too instead of filling the memory. One it refuses
   * keeps text NULL: its cases fail with the same message. */
  fb_err scratch;
  fb_err_clear(&scratch);
  const int read = fb_read_file(path, &text, &len, &scratch);
  const int rc = read == FB_ENOMEM ? fb_err_set(err, FB_ENOMEM, "%s: out of memory", path)
                                   : add_input(in, path, read ? NULL : text, len, err);
  free(text);
  return rc;
}

/* Adds the file a --set value names, resolved as the scenario reader
 * resolves it: relative to the scenario's directory. */
static int add_reference(study_inputs *in, const char *ref, fb_err *err)
{
  if (!ref[0])
    return FB_OK; /* the reader refuses it: a failed case */
  char *path = ref[0] == '/' ? strdup(ref) : cli_join_path(in->dir, ref);
  if (!path)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the study's files");
  const int rc = add_file(in, path, err);
  free(path);
  return rc;
}

/* 1 if a --set key (its last segment) names a file, as the scenario
 * format's file references do (suspensions.*.damper_table.file,
 * road.profile.file, hull.mesh.deck; docs/scenario-format.md). */
static int is_file_key(const char *key)
{
  return !strcmp(key, "file") || !strcmp(key, "deck");
}

/* The files the scenario names, as its reader resolved them
 * (fb_scenario.inputs). */
static int add_scenario_references(study_inputs *in, const char *path, fb_err *err)
{
  fb_scenario *s = NULL;
  /* It loaded a moment ago (set_up): a failure now is a lack of memory
   * or a file changed meanwhile, and its message says which. */
  int rc = fb_scenario_load(path, &s, err);
  for (size_t i = 0; rc == FB_OK && i < s->ninputs; ++i)
    rc = add_file(in, s->inputs[i], err);
  fb_scenario_free(&s);
  return rc;
}

static int study_inputs_add_all(const sweep_args *a, study_inputs *in, fb_err *err)
{
  in->h = fnv1a_text(in->h, "flexbond " CLI_VERSION);
  in->h = fnv1a_text(in->h, cli_system_label(a->sys));
  for (size_t k = 0; k < a->nkeys; ++k) {
    in->h = fnv1a_text(in->h, a->keys[k].path);
    for (size_t v = 0; v < a->keys[k].nvalues; ++v)
      in->h = fnv1a_text(in->h, a->keys[k].values[v]);
  }
  char *text = NULL;
  size_t len = 0;
  if (fb_read_file(a->scenario_path, &text, &len, err) != FB_OK)
    return err->code;
  int rc = add_input(in, a->scenario_path, text, len, err);
  if (rc == FB_OK)
    rc = add_scenario_references(in, a->scenario_path, err);
  free(text);
  /* A --set value of a file key names a file too: each case reads its own. */
  for (size_t k = 0; rc == FB_OK && k < a->nkeys; ++k) {
    const char *dot = strrchr(a->keys[k].path, '.');
    if (!is_file_key(dot ? dot + 1 : a->keys[k].path))
      continue;
    for (size_t v = 0; rc == FB_OK && v < a->keys[k].nvalues; ++v)
      rc = add_reference(in, a->keys[k].values[v], err);
  }
  return rc;
}

int sweep_study_fingerprint(const sweep_args *a, uint64_t *fingerprint, char **inputs,
                            fb_err *err)
{
  study_inputs in = {.h = UINT64_C(14695981039346656037)};
  size_t size = 0;
  if (inputs)
    *inputs = NULL;
  in.dir = dir_of(a->scenario_path);
  int rc = in.dir ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (rc == FB_OK && inputs && !(in.lines = open_memstream(inputs, &size)))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for the study's files");
  if (rc == FB_OK)
    rc = study_inputs_add_all(a, &in, err);
  if (in.lines && fclose(in.lines) != 0 && rc == FB_OK)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for the study's files");
  if (rc != FB_OK && inputs) {
    free(*inputs);
    *inputs = NULL;
  }
  for (size_t i = 0; i < in.nseen; ++i)
    free(in.seen[i]);
  free(in.seen);
  free(in.dir);
  *fingerprint = in.h;
  return rc;
}

/* The first line, with its '\n'. */
static void first_line(const sweep_args *a, uint64_t fingerprint, char *buf, size_t size)
{
  snprintf(buf, size,
           "# flexbond sweep journal (docs/sweep.md), study %016llx, %zu cases; resume with "
           "--resume\n",
           (unsigned long long)fingerprint, a->ncases);
}

/* The second line (the columns), in fresh memory. */
static char *header_line(const sweep_args *a)
{
  char *text = NULL;
  size_t len = 0;
  FILE *fp = open_memstream(&text, &len);
  if (!fp)
    return NULL;
  fputs("case,status,", fp);
  /* Always with the units: --plain-header changes sweep.csv only, so a
   * study resumed with or without it finds its journal. */
  sweep_csv_header(fp, a, FB_CSV_HEADER_UNITS);
  if (fclose(fp) != 0) {
    free(text);
    return NULL;
  }
  return text;
}

/* ---- Reading it back. */

/* One CSV record (RFC 4180) from text[*pos..len): its fields, unquoted,
 * in fresh memory (fields[k] into one buffer *store). 0 when the record
 * has no line end (a torn last row). */
typedef struct csv_record {
  char *store;
  char **fields;
  size_t nfields;
} csv_record;

static void csv_record_free(csv_record *r)
{
  free(r->store);
  free(r->fields);
  *r = (csv_record){0};
}

static int csv_read_record(const char *text, size_t len, size_t *pos, csv_record *r)
{
  *r = (csv_record){0};
  size_t p = *pos, n = 0, cap = 8;
  r->store = malloc(len - p + 1);
  r->fields = malloc(cap * sizeof *r->fields);
  if (!r->store || !r->fields)
    return -1;
  r->fields[r->nfields++] = r->store;
  int quoted = 0;
  for (; p < len; ++p) {
    const char ch = text[p];
    if (quoted) {
      if (ch == '"' && p + 1 < len && text[p + 1] == '"')
        r->store[n++] = text[++p];
      else if (ch == '"')
        quoted = 0;
      else
        r->store[n++] = ch;
    } else if (ch == '"') {
      quoted = 1;
    } else if (ch == ',') {
      r->store[n++] = '\0';
      if (r->nfields == cap) {
        char **grown = realloc(r->fields, 2 * cap * sizeof *grown);
        if (!grown)
          return -1;
        r->fields = grown;
        cap *= 2;
      }
      r->fields[r->nfields++] = r->store + n;
    } else if (ch == '\n') {
      r->store[n] = '\0';
      *pos = p + 1;
      return 1;
    } else {
      r->store[n++] = ch;
    }
  }
  return 0;
}

/* The status field: a status name, with "/set" when the case's error is
 * about a value its --set replaced (fb_study_sweep_case.at_value). */
static int status_of_name(const char *field, int *status, int *at_value)
{
  static const char set[] = "/set";
  const size_t len = strlen(field), nset = sizeof set - 1;
  *at_value = len > nset && !strcmp(field + len - nset, set);
  const size_t name_len = *at_value ? len - nset : len;
  for (int code = FB_OK; code <= FB_EINTR; ++code) {
    const char *name = fb_status_name(code);
    if (strlen(name) == name_len && !strncmp(field, name, name_len)) {
      *status = code;
      return 1;
    }
  }
  return 0;
}

/* The metrics of a row, from its first metric's field on, into m
 * (a->nmetrics; NaN for an empty field). */
static int read_metrics(const sweep_args *a, const char *path, size_t line, char *const *fields,
                        double *m, fb_err *err)
{
  for (size_t k = 0; k < a->nmetrics; ++k) {
    m[k] = NAN;
    if (*fields[k] && !sweep_numeric_value(fields[k], &m[k]))
      return fb_err_set(err, FB_EPARSE, "%s:%zu: '%s' is not a finite number", path, line,
                        fields[k]);
  }
  return FB_OK;
}

/* Record r of the journal (at line) into the study: the case it names
 * must be one of the study's, not yet read, with its keys' values. m:
 * room for a->nmetrics metrics. */
static int read_row(const sweep_args *a, const char *path, size_t line, const csv_record *r,
                    double *m, fb_err *err)
{
  const size_t want = 2 + a->nkeys + a->nmetrics + 1;
  /* want >= 3 (the case, its status, its error); said for the analyzer,
   * which lets the sum wrap around */
  if (r->nfields < 3 || r->nfields != want)
    return fb_err_set(err, FB_EPARSE, "%s:%zu: %zu fields, expected %zu", path, line,
                      r->nfields, want);
  char *end = NULL;
  errno = 0;
  const unsigned long long i = strtoull(r->fields[0], &end, 10);
  if (end == r->fields[0] || *end || errno || i >= a->ncases || r->fields[0][0] == '-')
    return fb_err_set(err, FB_EPARSE, "%s:%zu: case '%s' is not one of 0..%zu", path, line,
                      r->fields[0], a->ncases - 1);
  if (fb_study_sweep_case_done(a->study, i))
    return fb_err_set(err, FB_EPARSE, "%s:%zu: case %llu a second time", path, line, i);
  fb_study_sweep_case c = {.metric = m, .wall_seconds = NAN};
  if (!status_of_name(r->fields[1], &c.status, &c.at_value) || c.status == FB_EINTR ||
      (c.at_value && c.status == FB_OK))
    return fb_err_set(err, FB_EPARSE, "%s:%zu: status '%s' is not a flexbond status", path,
                      line, r->fields[1]);
  for (size_t k = 0; k < a->nkeys; ++k) {
    const char *value = fb_study_sweep_case_value(a->study, i, k);
    if (strcmp(r->fields[2 + k], value) != 0)
      return fb_err_set(err, FB_EPARSE, "%s:%zu: case %llu has %s=%s, the study %s", path, line,
                        i, a->keys[k].key, r->fields[2 + k], value);
  }
  const int rc = read_metrics(a, path, line, r->fields + 2 + a->nkeys, m, err);
  if (rc != FB_OK)
    return rc;
  const char *error = r->fields[want - 1];
  if ((c.status == FB_OK) != (*error == '\0'))
    return fb_err_set(err, FB_EPARSE, "%s:%zu: status %s with %s error", path, line,
                      r->fields[1], *error ? "an" : "no");
  c.error = *error ? error : NULL;
  fb_study_sweep_record(a->study, (size_t)i, &c);
  return FB_OK;
}

/* The line after "# written by " in the journal's comments. */
static const char version_line[] = "# written by flexbond " CLI_VERSION "\n";

/* The end of the line at text[p..len) (past its '\n', or len). */
static size_t line_end(const char *text, size_t len, size_t p)
{
  const char *nl = memchr(text + p, '\n', len - p);
  return nl ? (size_t)(nl - text) + 1 : len;
}

/* A line "# input HASH PATH\n" of the journal or of the study's inputs:
 * its two fields, each with its length (without the '\n'). */
typedef struct input_line {
  const char *hash, *path;
  size_t hash_len, path_len;
} input_line;

/* line[0..n) (with its '\n') into *out; 0 if it is not an input line. */
static int parse_input_line(const char *line, size_t n, input_line *out)
{
  static const char tag[] = "# input ";
  const size_t t = sizeof tag - 1;
  if (n <= t || memcmp(line, tag, t) != 0 || line[n - 1] != '\n')
    return 0;
  const char *space = memchr(line + t, ' ', n - t);
  if (!space)
    return 0;
  *out = (input_line){.hash = line + t,
                      .hash_len = (size_t)(space - line) - t,
                      .path = space + 1,
                      .path_len = (size_t)(line + n - 1 - (space + 1))};
  return 1;
}

static int hex_digit(char c)
{
  return c >= '0' && c <= '9'   ? c - '0'
         : c >= 'a' && c <= 'f' ? c - 'a' + 10
         : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                : -1;
}

/* The byte of the encoded path p[0..n) at *i, decoded (write_path's %XX,
 * in either case: a journal edited by hand still compares), *i moved past
 * it. A '%' without two hex digits after it stands for itself. */
static unsigned char path_byte(const char *p, size_t n, size_t *i)
{
  const int hi = *i + 2 < n && p[*i] == '%' ? hex_digit(p[*i + 1]) : -1,
            lo = hi >= 0 ? hex_digit(p[*i + 2]) : -1;
  if (lo < 0)
    return (unsigned char)p[(*i)++];
  *i += 3;
  return (unsigned char)(16 * hi + lo);
}

/* 1 if two input lines name the same path, byte for byte once decoded. */
static int same_path(const input_line *x, const input_line *y)
{
  size_t i = 0, j = 0;
  while (i < x->path_len && j < y->path_len)
    if (path_byte(x->path, x->path_len, &i) != path_byte(y->path, y->path_len, &j))
      return 0;
  return i == x->path_len && j == y->path_len;
}

/* The study's input line (in inputs) of the file that old names, into
 * *now; 0 if this study reads no file of that name. */
static int same_file_now(const char *inputs, const input_line *old, input_line *now)
{
  const size_t len = strlen(inputs);
  for (size_t p = 0, next; p < len; p = next) {
    next = line_end(inputs, len, p);
    if (parse_input_line(inputs + p, next - p, now) && same_path(old, now))
      return 1;
  }
  return 0;
}

/* Why the journal text[0..len) is not of this study, whose files are
 * inputs: another flexbond wrote it, a file both read has changed since,
 * or another scenario file, system or --set values. Always FB_EINVAL. */
static int another_study(const char *path, const char *text, size_t len, const char *inputs,
                         fb_err *err)
{
  static const char written[] = "# written by ";
  int versioned = 0;
  /* The comments after the first line. */
  for (size_t p = line_end(text, len, 0), next; p < len && text[p] == '#'; p = next) {
    next = line_end(text, len, p);
    const char *line = text + p;
    const size_t n = next - p;
    input_line old, now;
    if (n > sizeof written && !memcmp(line, written, sizeof written - 1)) {
      versioned = 1;
      if (n != strlen(version_line) || memcmp(line, version_line, n) != 0)
        return fb_err_set(err, FB_EINVAL,
                          "%s: the journal of another study: it was %.*s, this is flexbond "
                          "%s: remove it to start afresh",
                          path, (int)(n - 3), line + 2, CLI_VERSION);
    } else if (parse_input_line(line, n, &old) && same_file_now(inputs, &old, &now) &&
               (old.hash_len != now.hash_len ||
                memcmp(old.hash, now.hash, old.hash_len) != 0)) {
      /* The file as this study writes it (percent-encoded): one line. */
      const int unreadable =
          now.hash_len == strlen("unreadable") && !memcmp(now.hash, "unreadable", now.hash_len);
      return fb_err_set(err, FB_EINVAL,
                        "%s: the journal of another study: %.*s %s since the journal was "
                        "written, and the cases it holds were computed from what it held "
                        "then: restore the file, or remove the journal to start afresh",
                        path, (int)now.path_len, now.path,
                        unreadable ? "cannot be read" : "has changed");
    }
  }
  if (!versioned)
    return fb_err_set(err, FB_EINVAL,
                      "%s: the journal of another study: an older flexbond wrote it (this is "
                      "flexbond %s): remove it to start afresh",
                      path, CLI_VERSION);
  return fb_err_set(err, FB_EINVAL,
                    "%s: the journal of another study (a different scenario file, system or "
                    "--set values): remove it to start afresh",
                    path);
}

/* Reads text (the journal's len bytes) into cases; *keep is the length
 * of its complete records (a torn last row is cut off). fingerprint and
 * inputs: this study's. */
static int read_journal(const sweep_args *a, const char *path, const char *text, size_t len,
                        uint64_t fingerprint, const char *inputs, size_t *resumed, size_t *keep,
                        fb_err *err)
{
  char expected[256];
  first_line(a, fingerprint, expected, sizeof expected);
  const size_t first = strlen(expected);
  if (len < first || memcmp(text, expected, first) != 0)
    return another_study(path, text, len, inputs, err);
  /* The comments (flexbond's version, the files read) are not compared:
   * the fingerprint holds what matters of them, and a file's path
   * depends on how the scenario was named on the command line. */
  size_t pos = first, line = 2;
  while (pos < len && text[pos] == '#') {
    pos = line_end(text, len, pos);
    ++line;
  }
  char *header = header_line(a);
  if (!header)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  const size_t hlen = strlen(header);
  const int same = len >= pos + hlen && !memcmp(text + pos, header, hlen);
  free(header);
  /* The fingerprint holds the keys' paths, the header the keys as typed:
   * speed_kmh and road.speed_kmh are one study with other columns. */
  if (!same)
    return fb_err_set(err, FB_EINVAL,
                      "%s:%zu: the journal's columns are not this sweep's (the --set keys "
                      "spelled otherwise, or another flexbond): give the keys as they were, or "
                      "remove it to start afresh",
                      path, line);
  pos += hlen;
  ++line;
  *keep = pos;
  *resumed = 0;
  double *m = malloc(a->nmetrics * sizeof *m);
  if (!m)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  for (;;) {
    csv_record r = {0};
    const size_t start = pos;
    const int got = pos < len ? csv_read_record(text, len, &pos, &r) : 0;
    int rc = got < 0 ? fb_err_set(err, FB_ENOMEM, "%s: out of memory", path)
             : got   ? read_row(a, path, line, &r, m, err)
                     : FB_OK;
    for (size_t p = start; got > 0 && p < pos; ++p)
      line += text[p] == '\n';
    csv_record_free(&r);
    if (rc != FB_OK || got <= 0) {
      free(m);
      return rc;
    }
    *keep = pos;
    ++*resumed;
  }
}

/* ---- Opening, appending, closing. */

static int read_all(int fd, const char *path, char **text, size_t *len, fb_err *err)
{
  /* The input files' checks (a link to a device, a journal grown past
   * FB_INPUT_MAX_BYTES), before the size below is allocated. */
  int rc = fb_input_check_fd(fd, path, err);
  if (rc != FB_OK)
    return rc;
  struct stat st;
  if (fstat(fd, &st) != 0)
    return fb_err_set(err, FB_EIO, "%s: %s", path, strerror(errno));
  *len = (size_t)st.st_size;
  *text = malloc(*len + 1);
  if (!*text)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory for %zu bytes", path, *len);
  size_t got = 0;
  while (got < *len) {
    const ssize_t n = read(fd, *text + got, *len - got);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
      return fb_err_set(err, FB_EIO, "%s: cannot read: %s", path,
                        n < 0 ? strerror(errno) : "it shrank");
    got += (size_t)n;
  }
  (*text)[*len] = '\0';
  return FB_OK;
}

/* Reads an existing journal into cases, or starts an empty one: the
 * file is then cut to what is kept and positioned at its end. */
static int load_or_start(const sweep_args *a, sweep_journal *j, int fd, size_t *resumed,
                         fb_err *err)
{
  uint64_t fingerprint = 0;
  char *text = NULL, *inputs = NULL;
  size_t len = 0, keep = 0;
  int rc = sweep_study_fingerprint(a, &fingerprint, &inputs, err);
  if (rc == FB_OK)
    rc = read_all(fd, j->path, &text, &len, err);
  if (rc == FB_OK && len > 0)
    rc = read_journal(a, j->path, text, len, fingerprint, inputs, resumed, &keep, err);
  free(text);
  if (rc == FB_OK && (ftruncate(fd, (off_t)keep) != 0 || lseek(fd, 0, SEEK_END) < 0))
    rc = fb_err_set(err, FB_EIO, "%s: %s", j->path, strerror(errno));
  if (rc == FB_OK && keep == 0) {
    char first[256], *header = header_line(a);
    first_line(a, fingerprint, first, sizeof first);
    if (!header)
      rc = fb_err_set(err, FB_ENOMEM, "%s: out of memory", j->path);
    else if (fputs(first, j->fp) < 0 || fputs(version_line, j->fp) < 0 ||
             fputs(inputs, j->fp) < 0 || fputs(header, j->fp) < 0 || fflush(j->fp) != 0)
      rc = fb_err_set(err, FB_EIO, "%s: cannot write: %s", j->path, strerror(errno));
    free(header);
  }
  free(inputs);
  return rc;
}

/* Opens (creates) the journal's file at path into *fd: a regular file,
 * never through a symbolic link (O_NOFOLLOW), which someone could have
 * planted in DIR to make the sweep write and truncate another file.
 * O_NONBLOCK keeps a FIFO planted there from blocking the open until it
 * is refused; it is cleared again for the regular file. FB_EIO. */
static int open_file(const char *path, int *fd, fb_err *err)
{
  *fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  if (*fd < 0)
    return fb_err_set(err, FB_EIO, "%s: cannot open: %s", path,
                      errno == ELOOP ? "it is a symbolic link, which the journal is not "
                                       "written through: remove it"
                                     : strerror(errno));
  struct stat st;
  int rc = FB_OK;
  /* fstat, then clearing O_NONBLOCK: either failing is the system's
   * reason; a file that is not regular is ours to explain. */
  const int sys_failed =
      fstat(*fd, &st) != 0 ||
      (S_ISREG(st.st_mode) && fcntl(*fd, F_SETFL, fcntl(*fd, F_GETFL) & ~O_NONBLOCK) != 0);
  if (sys_failed)
    rc = fb_err_set(err, FB_EIO, "%s: %s", path, strerror(errno));
  else if (!S_ISREG(st.st_mode))
    rc = fb_err_set(err, FB_EIO,
                    "%s: cannot open: not a regular file (a device, pipe or socket), which "
                    "cannot be the journal: remove it",
                    path);
  if (rc != FB_OK) {
    close(*fd);
    *fd = -1;
  }
  return rc;
}

int sweep_journal_open(const sweep_args *a, const char *dir, size_t *resumed,
                       sweep_journal **out, fb_err *err)
{
  *out = NULL;
  *resumed = 0;
  sweep_journal *j = calloc(1, sizeof *j);
  if (!j || !(j->path = sweep_journal_path(dir))) {
    free(j);
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", dir);
  }
  j->a = a;
  int fd = -1;
  int rc = open_file(j->path, &fd, err);
  struct stat st = {0};
  if (rc == FB_OK && flock(fd, LOCK_EX | LOCK_NB) != 0)
    rc = fb_err_set(err, FB_EIO, "%s: %s", j->path,
                    errno == EWOULDBLOCK
                        ? "another flexbond sweep is writing into this directory"
                        : strerror(errno));
  const int locked = rc == FB_OK;
  if (rc == FB_OK && (fstat(fd, &st) != 0 || !(j->fp = fdopen(fd, "r+"))))
    rc = fb_err_set(err, FB_EIO, "%s: %s", j->path, strerror(errno));
  if (rc == FB_OK && !a->resume && st.st_size > 0)
    rc =
        fb_err_set(err, FB_EINVAL,
                   "%s: an earlier sweep into this directory stopped before it finished: add "
                   "--resume to run only its missing cases, or remove the file to start afresh",
                   j->path);
  if (rc == FB_OK)
    rc = load_or_start(a, j, fd, resumed, err);
  if (rc != FB_OK) {
    /* A journal this call started (none was there) goes with it, so the
     * directory is as before; another sweep's, or an earlier one, stays,
     * and so does a link or a device (refused by open_file). */
    if (locked && st.st_size == 0 && S_ISREG(st.st_mode))
      unlink(j->path);
    if (j->fp)
      fclose(j->fp);
    else if (fd >= 0)
      close(fd);
    free(j->path);
    free(j);
    return rc;
  }
  j->rows = *resumed;
  *out = j;
  return FB_OK;
}

int sweep_journal_append(sweep_journal *j, size_t i, fb_err *err)
{
  fb_study_sweep_case c;
  fb_study_sweep_case_get(j->a->study, i, &c);
  fprintf(j->fp, "%zu,%s%s,", i, fb_status_name(c.status), c.at_value ? "/set" : "");
  sweep_csv_row(j->fp, j->a, i);
  if (fflush(j->fp) != 0 || ferror(j->fp))
    return fb_err_set(err, FB_EIO, "%s: cannot write: %s", j->path, strerror(errno));
  ++j->rows;
  return FB_OK;
}

size_t sweep_journal_rows(const sweep_journal *j)
{
  return j->rows;
}

void sweep_journal_close(sweep_journal **j, int remove_file)
{
  if (!j || !*j)
    return;
  if (remove_file)
    unlink((*j)->path);
  fclose((*j)->fp);
  free((*j)->path);
  free(*j);
  *j = NULL;
}
