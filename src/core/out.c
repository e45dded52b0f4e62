/* SPDX-License-Identifier: BSD-3-Clause */
/* Atomic output files and directory creation (see flexbond/out.h).
 *
 * An output is written to a temporary file next to its destination
 * (fb_tmpfile_create: created exclusively, never through a link planted at
 * its name) and renamed into place once flushed and synced: rename(2)
 * within one file system replaces the destination atomically
 * (POSIX.1-2008, rename), so a reader sees either the old complete file or
 * the new complete one, never a truncated one.
 *
 * A destination that is a symbolic link is followed: the file it names is
 * replaced and the link kept. A destination that exists but is not a
 * regular file (a terminal, /dev/null, a FIFO), or is the file behind a
 * standard stream (/dev/stdout redirected by the shell), cannot be
 * replaced by a rename, and must not be: the output is held in an
 * anonymous temporary file and copied into the destination, opened as it
 * is, on commit, so that a failed run still sends nothing there. */
/* realpath(3) with a NULL buffer is XSI (POSIX.1-2008). */
/* NOLINTNEXTLINE(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp): POSIX's macro */
#define _XOPEN_SOURCE 700

#include "flexbond/out.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "core/tmpfile.h"

struct fb_out {
  FILE *fp;
  char *path;     /* destination as given, for messages */
  char *target;   /* the file renamed over: path, or the file a link names */
  char *tmp_path; /* the temporary file beside target, where the data goes until commit;
                     NULL for a destination that is not a regular file
                     (fp is then an anonymous tmpfile copied on commit) */
};

static char *copy_string(const char *s)
{
  size_t n = strlen(s) + 1;
  char *copy = malloc(n);
  if (copy)
    memcpy(copy, s, n);
  return copy;
}

static void out_destroy(fb_out *o)
{
  free(o->tmp_path);
  free(o->target);
  free(o->path);
  free(o);
}

/* 1 if st is the file behind one of the standard streams: /dev/stdout
 * when the shell redirected it into a file, which the redirection, not a
 * rename, must keep writing (">>" appends). */
static int is_standard_stream(const struct stat *st)
{
  for (int fd = 0; fd <= 2; ++fd) {
    struct stat s;
    if (fstat(fd, &s) == 0 && s.st_dev == st->st_dev && s.st_ino == st->st_ino)
      return 1;
  }
  return 0;
}

/* Where the data of o goes: o->target (path itself, or the regular file
 * a symbolic link at path names), or, for an existing destination that is
 * not a regular file, no target (the data then go to a tmpfile). */
static int out_resolve(fb_out *o, fb_err *err)
{
  struct stat st, lst;
  if (lstat(o->path, &lst) != 0) {
    if (errno != ENOENT)
      return fb_err_set(err, FB_EIO, "%s: cannot create file: %s", o->path, strerror(errno));
    o->target = copy_string(o->path);
  } else if (stat(o->path, &st) != 0) {
    return fb_err_set(err, FB_EIO, "%s: cannot create file: a symbolic link to nothing (%s)",
                      o->path, strerror(errno));
  } else if (S_ISDIR(st.st_mode)) {
    return fb_err_set(err, FB_EIO, "%s: cannot create file: Is a directory", o->path);
  } else if (!S_ISREG(st.st_mode) || (S_ISLNK(lst.st_mode) && is_standard_stream(&st))) {
    return FB_OK;
  } else if (S_ISLNK(lst.st_mode)) {
    o->target = realpath(o->path, NULL);
    if (!o->target && errno != ENOMEM)
      return fb_err_set(err, FB_EIO, "%s: cannot follow the link: %s", o->path,
                        strerror(errno));
  } else {
    o->target = copy_string(o->path);
  }
  if (!o->target)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", o->path);
  return FB_OK;
}

/* Opens o->fp: a new temporary file beside o->target, or, without a
 * target, an anonymous one. */
static int out_create(fb_out *o, fb_err *err)
{
  if (!o->target) {
    o->fp = tmpfile();
    return o->fp ? FB_OK
                 : fb_err_set(err, FB_EIO, "%s: cannot create file: %s", o->path,
                              strerror(errno));
  }
  int fd = -1;
  const int e = fb_tmpfile_create(o->target, &fd, &o->tmp_path);
  if (e == ENOMEM)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", o->path);
  if (e != 0)
    return fb_err_set(err, FB_EIO, "%s: cannot create file: %s", o->path, strerror(e));
  o->fp = fdopen(fd, "w");
  if (!o->fp) {
    const int saved = errno;
    close(fd);
    return fb_err_set(err, FB_EIO, "%s: cannot create file: %s", o->path, strerror(saved));
  }
  return FB_OK;
}

int fb_out_open(const char *path, fb_out **out, fb_err *err)
{
  *out = NULL;
  if (!path || !*path)
    return fb_err_set(err, FB_EINVAL, "output file: empty path");
  fb_out *o = calloc(1, sizeof *o);
  if (!o)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  o->path = copy_string(path);
  int rc =
      o->path ? out_resolve(o, err) : fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  if (!rc)
    rc = out_create(o, err);
  if (rc) {
    if (o->tmp_path)
      remove(o->tmp_path);
    out_destroy(o);
    return rc;
  }
  *out = o;
  return FB_OK;
}

FILE *fb_out_stream(fb_out *o)
{
  return o->fp;
}

/* Flushes, checks the stream's error flag (set by any failed write since
 * open), syncs and closes. Always closes o->fp. Returns 0 or an errno
 * value; EIO stands in when a write failed earlier and errno is stale. */
static int flush_and_close(fb_out *o)
{
  int status = 0;
  errno = 0;
  if (fflush(o->fp) != 0)
    status = errno ? errno : EIO;
  else if (ferror(o->fp))
    status = EIO;
  else if (fsync(fileno(o->fp)) != 0)
    status = errno;
  errno = 0;
  if (fclose(o->fp) != 0 && status == 0)
    status = errno ? errno : EIO;
  o->fp = NULL;
  return status;
}

/* Copies the complete output held in o->fp into the destination that is
 * not a regular file (or is a standard stream's), opened for appending
 * as it is: a FIFO waits for its reader, and a file behind /dev/stdout
 * keeps what the shell's ">>" kept. Closes o->fp. Returns 0 or an errno
 * value. */
static int copy_to_stream(fb_out *o)
{
  errno = 0;
  int status = 0;
  if (fflush(o->fp) != 0 || ferror(o->fp))
    status = errno ? errno : EIO;
  FILE *dst = status ? NULL : fopen(o->path, "a");
  if (!status && !dst)
    status = errno;
  if (dst) {
    rewind(o->fp);
    char buf[8192];
    size_t n;
    errno = 0;
    while (!status && (n = fread(buf, 1, sizeof buf, o->fp)) > 0)
      if (fwrite(buf, 1, n, dst) != n)
        status = errno ? errno : EIO;
    if (!status && ferror(o->fp))
      status = EIO;
    errno = 0;
    if (fclose(dst) != 0 && !status)
      status = errno ? errno : EIO;
  }
  fclose(o->fp);
  o->fp = NULL;
  return status;
}

int fb_out_commit(fb_out **o, fb_err *err)
{
  if (!o || !*o)
    return fb_err_set(err, FB_EINVAL, "fb_out_commit: no open output");
  fb_out *out = *o;
  *o = NULL;
  int rc = FB_OK;
  int status = out->tmp_path ? flush_and_close(out) : copy_to_stream(out);
  if (status != 0) {
    rc = fb_err_set(err, FB_EIO, "%s: write failed: %s", out->path, strerror(status));
  } else if (out->tmp_path && rename(out->tmp_path, out->target) != 0) {
    rc = fb_err_set(err, FB_EIO, "%s: cannot move '%s' into place: %s", out->path,
                    out->tmp_path, strerror(errno));
  }
  if (rc != FB_OK && out->tmp_path)
    remove(out->tmp_path);
  out_destroy(out);
  return rc;
}

void fb_out_abort(fb_out **o)
{
  if (!o || !*o)
    return;
  fb_out *out = *o;
  *o = NULL;
  fclose(out->fp);
  if (out->tmp_path)
    remove(out->tmp_path);
  out_destroy(out);
}

/* mkdir of one component of dir (whole is dir, for the message) that
 * accepts an existing directory but not an existing file; *made says
 * whether this call created it. */
static int make_one_dir(const char *component, const char *whole, int *made, fb_err *err)
{
  *made = 0;
  if (mkdir(component, 0777) == 0) {
    *made = 1;
    return FB_OK;
  }
  int saved = errno;
  struct stat st;
  if (saved == EEXIST && stat(component, &st) == 0 && S_ISDIR(st.st_mode))
    return FB_OK;
  const char *reason = saved == EEXIST ? "exists and is not a directory" : strerror(saved);
  if (strcmp(component, whole) == 0)
    return fb_err_set(err, FB_EIO, "%s: cannot create directory: %s", whole, reason);
  return fb_err_set(err, FB_EIO, "%s: cannot create directory '%s': %s", whole, component,
                    reason);
}

/* Appends prefix, just created, to the list *created (of *ncreated). */
static int note_created(const char *prefix, int made, char ***created, size_t *ncreated,
                        fb_err *err)
{
  if (!made || !created)
    return FB_OK;
  char **grown = realloc(*created, (*ncreated + 1) * sizeof *grown);
  char *copy = grown ? copy_string(prefix) : NULL;
  if (grown)
    *created = grown;
  if (!copy)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", prefix);
  (*created)[(*ncreated)++] = copy;
  return FB_OK;
}

int fb_mkdir_p_created(const char *dir, char ***created, size_t *ncreated, fb_err *err)
{
  if (created) {
    *created = NULL;
    *ncreated = 0;
  }
  if (!dir || !*dir)
    return fb_err_set(err, FB_EINVAL, "directory: empty path");
  char *prefix = copy_string(dir);
  if (!prefix)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", dir);
  int rc = FB_OK, made = 0;
  /* Create each proper prefix ending before a '/', then dir itself; the
   * leading '/' of an absolute path and repeated slashes are skipped. */
  for (char *p = prefix + 1; *p && rc == FB_OK; ++p) {
    if (*p != '/' || p[-1] == '/')
      continue;
    *p = '\0';
    rc = make_one_dir(prefix, dir, &made, err);
    if (rc == FB_OK)
      rc = note_created(prefix, made, created, ncreated, err);
    *p = '/';
  }
  if (rc == FB_OK)
    rc = make_one_dir(dir, dir, &made, err);
  if (rc == FB_OK)
    rc = note_created(dir, made, created, ncreated, err);
  free(prefix);
  return rc;
}

int fb_mkdir_p(const char *dir, fb_err *err)
{
  return fb_mkdir_p_created(dir, NULL, NULL, err);
}
