/* The journal of a sweep (sweep.h): DIR/sweep.partial.csv, which a
 * killed or interrupted sweep leaves behind and `--resume` reads back.
 *
 *   # flexbond sweep journal (docs/sweep.md), study 3f2a..., 12 cases
 *   case,status,<sweep.csv's header>
 *   4,FB_OK,<case 4's sweep.csv row>
 *
 * The rows come in the order the cases finish, each flushed at once: a
 * killed process loses only the cases it was running (a row it was
 * writing is torn, has no line end, and is dropped on resuming). The
 * metrics are printed to the last bit (sweep_format_double), so a resumed
 * sweep writes the same sweep.csv as one that was never stopped. The
 * study's fingerprint (the scenario file's bytes, the system, the keys and
 * their values) keeps a journal from being resumed by another study; an
 * exclusive flock(2) keeps two sweeps from writing one journal. */
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

static uint64_t fnv1a(uint64_t h, const void *data, size_t n)
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
  return fnv1a(h, text, strlen(text) + 1); /* with its NUL: "ab","c" != "a","bc" */
}

int sweep_study_fingerprint(const sweep_args *a, uint64_t *h, fb_err *err)
{
  FILE *fp = fopen(a->scenario_path, "rb");
  if (!fp)
    return fb_err_set(err, FB_EIO, "%s: cannot open: %s", a->scenario_path, strerror(errno));
  *h = UINT64_C(14695981039346656037);
  char buf[8192];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, fp)) > 0)
    *h = fnv1a(*h, buf, n);
  const int failed = ferror(fp);
  fclose(fp);
  if (failed)
    return fb_err_set(err, FB_EIO, "%s: cannot read", a->scenario_path);
  *h = fnv1a_text(*h, cli_system_label(a->sys));
  for (size_t k = 0; k < a->nkeys; ++k) {
    *h = fnv1a_text(*h, a->keys[k].path);
    for (size_t v = 0; v < a->keys[k].nvalues; ++v)
      *h = fnv1a_text(*h, a->keys[k].values[v]);
  }
  return FB_OK;
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
  sweep_csv_header(fp, a);
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

static int status_of_name(const char *name, int *status)
{
  for (int code = FB_OK; code <= FB_EINTR; ++code)
    if (!strcmp(name, fb_status_name(code))) {
      *status = code;
      return 1;
    }
  return 0;
}

/* Record r of the journal (at line) into cases: the case it names must
 * be one of the study's, not yet read, with its keys' values. */
static int read_row(const sweep_args *a, const char *path, size_t line, const csv_record *r,
                    sweep_case *cases, fb_err *err)
{
  const size_t want = 2 + a->nkeys + NMETRICS + 1;
  if (r->nfields != want)
    return fb_err_set(err, FB_EPARSE, "%s:%zu: %zu fields, expected %zu", path, line,
                      r->nfields, want);
  char *end = NULL;
  errno = 0;
  const unsigned long long i = strtoull(r->fields[0], &end, 10);
  if (end == r->fields[0] || *end || errno || i >= a->ncases || r->fields[0][0] == '-')
    return fb_err_set(err, FB_EPARSE, "%s:%zu: case '%s' is not one of 0..%zu", path, line,
                      r->fields[0], a->ncases - 1);
  sweep_case *c = &cases[i];
  if (c->done)
    return fb_err_set(err, FB_EPARSE, "%s:%zu: case %llu a second time", path, line, i);
  if (!status_of_name(r->fields[1], &c->status) || c->status == FB_EINTR)
    return fb_err_set(err, FB_EPARSE, "%s:%zu: status '%s' is not a flexbond status", path,
                      line, r->fields[1]);
  for (size_t k = 0; k < a->nkeys; ++k) {
    const char *value = a->keys[k].values[sweep_value_index(a, i, k)];
    if (strcmp(r->fields[2 + k], value) != 0)
      return fb_err_set(err, FB_EPARSE, "%s:%zu: case %llu has %s=%s, the study %s", path, line,
                        i, a->keys[k].key, r->fields[2 + k], value);
  }
  for (size_t m = 0; m < NMETRICS; ++m) {
    const char *text = r->fields[2 + a->nkeys + m];
    c->metric[m] = NAN;
    if (*text && !sweep_numeric_value(text, &c->metric[m]))
      return fb_err_set(err, FB_EPARSE, "%s:%zu: '%s' is not a finite number", path, line,
                        text);
  }
  const char *error = r->fields[want - 1];
  if ((c->status == FB_OK) != (*error == '\0'))
    return fb_err_set(err, FB_EPARSE, "%s:%zu: status %s with %s error", path, line,
                      r->fields[1], *error ? "an" : "no");
  c->error = *error ? strdup(error) : NULL;
  c->wall_seconds = NAN;
  c->done = 1;
  return FB_OK;
}

/* Reads text (the journal's len bytes) into cases; *keep is the length
 * of its complete records (a torn last row is cut off). */
static int read_journal(const sweep_args *a, const char *path, const char *text, size_t len,
                        uint64_t fingerprint, sweep_case *cases, size_t *resumed, size_t *keep,
                        fb_err *err)
{
  char expected[256];
  first_line(a, fingerprint, expected, sizeof expected);
  const size_t first = strlen(expected);
  if (len < first || memcmp(text, expected, first) != 0)
    return fb_err_set(err, FB_EINVAL,
                      "%s: the journal of another study (a different scenario file, system or "
                      "--set values): remove it to start afresh",
                      path);
  char *header = header_line(a);
  if (!header)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  const size_t hlen = strlen(header);
  const int same = len >= first + hlen && !memcmp(text + first, header, hlen);
  free(header);
  /* The fingerprint holds the keys' paths, the header the keys as typed:
   * speed_kmh and road.speed_kmh are one study with other columns. */
  if (!same)
    return fb_err_set(err, FB_EINVAL,
                      "%s:2: the journal's columns are not this sweep's (the --set keys "
                      "spelled otherwise, or another flexbond): give the keys as they were, or "
                      "remove it to start afresh",
                      path);
  size_t pos = first + hlen, line = 3;
  *keep = pos;
  *resumed = 0;
  for (;;) {
    csv_record r = {0};
    const size_t start = pos;
    const int got = pos < len ? csv_read_record(text, len, &pos, &r) : 0;
    int rc = got < 0 ? fb_err_set(err, FB_ENOMEM, "%s: out of memory", path)
             : got   ? read_row(a, path, line, &r, cases, err)
                     : FB_OK;
    for (size_t p = start; got > 0 && p < pos; ++p)
      line += text[p] == '\n';
    csv_record_free(&r);
    if (rc != FB_OK || got <= 0)
      return rc;
    *keep = pos;
    ++*resumed;
  }
}

/* ---- Opening, appending, closing. */

static int read_all(int fd, const char *path, char **text, size_t *len, fb_err *err)
{
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
static int load_or_start(const sweep_args *a, sweep_journal *j, int fd, sweep_case *cases,
                         size_t *resumed, fb_err *err)
{
  uint64_t fingerprint = 0;
  char *text = NULL;
  size_t len = 0, keep = 0;
  int rc = sweep_study_fingerprint(a, &fingerprint, err);
  if (rc == FB_OK)
    rc = read_all(fd, j->path, &text, &len, err);
  if (rc == FB_OK && len > 0)
    rc = read_journal(a, j->path, text, len, fingerprint, cases, resumed, &keep, err);
  free(text);
  if (rc == FB_OK && (ftruncate(fd, (off_t)keep) != 0 || lseek(fd, 0, SEEK_END) < 0))
    rc = fb_err_set(err, FB_EIO, "%s: %s", j->path, strerror(errno));
  if (rc == FB_OK && keep == 0) {
    char first[256], *header = header_line(a);
    first_line(a, fingerprint, first, sizeof first);
    if (!header)
      rc = fb_err_set(err, FB_ENOMEM, "%s: out of memory", j->path);
    else if (fputs(first, j->fp) < 0 || fputs(header, j->fp) < 0 || fflush(j->fp) != 0)
      rc = fb_err_set(err, FB_EIO, "%s: cannot write: %s", j->path, strerror(errno));
    free(header);
  }
  return rc;
}

int sweep_journal_open(const sweep_args *a, const char *dir, sweep_case *cases, size_t *resumed,
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
  const int fd = open(j->path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  int rc = FB_OK, locked = 0;
  struct stat st = {0};
  if (fd < 0)
    rc = fb_err_set(err, FB_EIO, "%s: cannot open: %s", j->path, strerror(errno));
  else if (flock(fd, LOCK_EX | LOCK_NB) != 0)
    rc = fb_err_set(err, FB_EIO, "%s: %s", j->path,
                    errno == EWOULDBLOCK
                        ? "another flexbond sweep is writing into this directory"
                        : strerror(errno));
  else
    locked = 1;
  if (rc == FB_OK && (fstat(fd, &st) != 0 || !(j->fp = fdopen(fd, "r+"))))
    rc = fb_err_set(err, FB_EIO, "%s: %s", j->path, strerror(errno));
  if (rc == FB_OK && !a->resume && st.st_size > 0)
    rc =
        fb_err_set(err, FB_EINVAL,
                   "%s: an earlier sweep into this directory stopped before it finished: add "
                   "--resume to run only its missing cases, or remove the file to start afresh",
                   j->path);
  if (rc == FB_OK)
    rc = load_or_start(a, j, fd, cases, resumed, err);
  if (rc != FB_OK) {
    /* A journal this call started (none was there) goes with it, so the
     * directory is as before; another sweep's, or an earlier one, stays. */
    if (locked && st.st_size == 0)
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

int sweep_journal_append(sweep_journal *j, size_t i, const sweep_case *c, fb_err *err)
{
  fprintf(j->fp, "%zu,%s,", i, fb_status_name(c->status));
  sweep_csv_row(j->fp, j->a, i, c);
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
