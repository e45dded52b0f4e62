/* Atomic output files and directory creation (see flexbond/io.h).
 *
 * An output is written to "path.tmp.PID" next to its destination and
 * renamed into place once flushed and synced: rename(2) within one file
 * system replaces the destination atomically (POSIX.1-2008, rename), so a
 * reader sees either the old complete file or the new complete one, never
 * a truncated one. The PID suffix keeps concurrent runs from sharing a
 * temporary file. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "flexbond/io.h"

struct fb_out {
  FILE *fp;
  char *path;     /* destination */
  char *tmp_path; /* "path.tmp.PID", where the data goes until commit */
};

static char *copy_string(const char *s)
{
  size_t n = strlen(s) + 1;
  char *copy = malloc(n);
  if (copy)
    memcpy(copy, s, n);
  return copy;
}

/* "path.tmp.PID" in fresh memory, NULL when out of memory. */
static char *make_tmp_path(const char *path)
{
  const char *fmt = "%s.tmp.%ld";
  long pid = (long)getpid();
  int n = snprintf(NULL, 0, fmt, path, pid);
  if (n < 0)
    return NULL;
  char *tmp = malloc((size_t)n + 1);
  if (tmp)
    snprintf(tmp, (size_t)n + 1, fmt, path, pid);
  return tmp;
}

static void out_destroy(fb_out *o)
{
  free(o->tmp_path);
  free(o->path);
  free(o);
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
  o->tmp_path = make_tmp_path(path);
  if (!o->path || !o->tmp_path) {
    out_destroy(o);
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  }
  o->fp = fopen(o->tmp_path, "w");
  if (!o->fp) {
    int saved = errno;
    out_destroy(o);
    return fb_err_set(err, FB_EIO, "%s: cannot create file: %s", path, strerror(saved));
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

int fb_out_commit(fb_out **o, fb_err *err)
{
  if (!o || !*o)
    return fb_err_set(err, FB_EINVAL, "fb_out_commit: no open output");
  fb_out *out = *o;
  *o = NULL;
  int rc = FB_OK;
  int status = flush_and_close(out);
  if (status != 0) {
    rc = fb_err_set(err, FB_EIO, "%s: write failed: %s", out->path, strerror(status));
  } else if (rename(out->tmp_path, out->path) != 0) {
    rc = fb_err_set(err, FB_EIO, "%s: cannot move '%s' into place: %s", out->path,
                    out->tmp_path, strerror(errno));
  }
  if (rc != FB_OK)
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
  remove(out->tmp_path);
  out_destroy(out);
}

/* mkdir of one component of dir (whole is dir, for the message) that
 * accepts an existing directory but not an existing file. */
static int make_one_dir(const char *component, const char *whole, fb_err *err)
{
  if (mkdir(component, 0777) == 0)
    return FB_OK;
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

int fb_mkdir_p(const char *dir, fb_err *err)
{
  if (!dir || !*dir)
    return fb_err_set(err, FB_EINVAL, "directory: empty path");
  char *prefix = copy_string(dir);
  if (!prefix)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", dir);
  int rc = FB_OK;
  /* Create each proper prefix ending before a '/', then dir itself; the
   * leading '/' of an absolute path and repeated slashes are skipped. */
  for (char *p = prefix + 1; *p && rc == FB_OK; ++p) {
    if (*p != '/' || p[-1] == '/')
      continue;
    *p = '\0';
    rc = make_one_dir(prefix, dir, err);
    *p = '/';
  }
  if (rc == FB_OK)
    rc = make_one_dir(dir, dir, err);
  free(prefix);
  return rc;
}
