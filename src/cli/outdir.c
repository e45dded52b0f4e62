/* Output directories written all or nothing (see cli_outdir in cli.h).
 * Files are written into a hidden staging directory inside DIR (the same
 * file system, so that rename moves them) and moved into DIR only once
 * every file of the command is complete; a command that fails or is
 * interrupted removes its staging directory and leaves DIR's previous
 * contents as they were. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "flexbond/io.h"

#include "cli.h"

static int is_directory(const char *path)
{
  struct stat st;
  return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

int cli_outdir_open(cli_outdir *od, const char *dir, fb_err *err)
{
  *od = (cli_outdir){.dir = dir, .stage = NULL, .created = !is_directory(dir)};
  int rc = fb_mkdir_p(dir, err);
  if (rc)
    return rc;
  od->stage = cli_join_path(dir, ".flexbond-staging-XXXXXX");
  if (!od->stage)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", dir);
  if (!mkdtemp(od->stage)) {
    rc = fb_err_set(err, FB_EIO, "%s: cannot create a staging directory: %s", dir,
                    strerror(errno));
    free(od->stage);
    od->stage = NULL;
    if (od->created)
      rmdir(dir);
  }
  return rc;
}

char *cli_outdir_path(const cli_outdir *od, const char *name, fb_err *err)
{
  char *path = cli_join_path(od->stage, name);
  if (!path)
    fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  return path;
}

int cli_outdir_keep(cli_outdir *od, char *path, fb_err *err)
{
  char **grown = realloc(od->files, (od->nfiles + 1) * sizeof *grown);
  if (!grown) {
    remove(path);
    free(path);
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  }
  od->files = grown;
  od->files[od->nfiles++] = path;
  return FB_OK;
}

int cli_outdir_write(cli_outdir *od, const char *name, cli_writer write, const void *ctx,
                     fb_err *err)
{
  char *path = cli_outdir_path(od, name, err);
  if (!path)
    return FB_ENOMEM;
  fb_out *out = NULL;
  int rc = fb_out_open(path, &out, err);
  if (rc == FB_OK) {
    write(fb_out_stream(out), ctx);
    /* Write errors stick to the stream; commit reports them. */
    rc = fb_out_commit(&out, err);
  }
  if (rc == FB_OK)
    return cli_outdir_keep(od, path, err);
  free(path);
  return rc;
}

/* The final path dir/name of staged file i, and the path its previous
 * version is kept at while the files are moved (stage/name.previous). */
static char *final_path(const cli_outdir *od, size_t i)
{
  const char *slash = strrchr(od->files[i], '/');
  return cli_join_path(od->dir, slash ? slash + 1 : od->files[i]);
}

static char *backup_path(const cli_outdir *od, size_t i)
{
  const size_t n = strlen(od->files[i]) + sizeof ".previous";
  char *p = malloc(n);
  if (p)
    snprintf(p, n, "%s.previous", od->files[i]);
  return p;
}

/* Puts the previous versions of files 0 .. n-1 back (a move failed). */
static void roll_back(const cli_outdir *od, size_t n, const unsigned char *had_previous)
{
  for (size_t i = n; i-- > 0;) {
    char *final = final_path(od, i), *backup = backup_path(od, i);
    if (final && backup) {
      if (had_previous[i])
        rename(backup, final);
      else
        remove(final);
    }
    free(final);
    free(backup);
  }
}

/* Moves staged file i into place, keeping the file it replaces as its
 * backup; *had_previous says whether there was one. */
static int move_one(const cli_outdir *od, size_t i, unsigned char *had_previous, fb_err *err)
{
  char *final = final_path(od, i), *backup = backup_path(od, i);
  int rc = final && backup ? FB_OK : fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  struct stat st;
  *had_previous = rc == FB_OK && lstat(final, &st) == 0;
  if (rc == FB_OK && *had_previous && S_ISDIR(st.st_mode))
    rc = fb_err_set(err, FB_EIO, "%s: cannot replace a directory with the new file", final);
  if (rc == FB_OK && *had_previous && rename(final, backup) != 0)
    rc = fb_err_set(err, FB_EIO, "%s: cannot set the previous file aside: %s", final,
                    strerror(errno));
  if (rc == FB_OK && rename(od->files[i], final) != 0) {
    rc = fb_err_set(err, FB_EIO, "%s: cannot move the new file into place: %s", final,
                    strerror(errno));
    if (*had_previous)
      rename(backup, final);
  }
  free(final);
  free(backup);
  return rc;
}

/* Moves every staged file into dir, all or none: a file replaced is kept
 * aside until every move has succeeded, and put back if one fails. */
static int commit(const cli_outdir *od, fb_err *err)
{
  unsigned char *had_previous = calloc(od->nfiles + 1, 1);
  if (!had_previous)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  int rc = FB_OK;
  size_t moved = 0;
  while (rc == FB_OK && moved < od->nfiles) {
    rc = move_one(od, moved, &had_previous[moved], err);
    moved += rc == FB_OK;
  }
  if (rc != FB_OK)
    roll_back(od, moved, had_previous);
  for (size_t i = 0; rc == FB_OK && i < od->nfiles; ++i) {
    char *backup = had_previous[i] ? backup_path(od, i) : NULL;
    if (backup)
      remove(backup);
    free(backup);
  }
  free(had_previous);
  return rc;
}

int cli_outdir_close(cli_outdir *od, int status, fb_err *err)
{
  /* An interruption that arrives while the files are written still
   * leaves DIR as it was. */
  if (status == FB_OK && od->stage)
    status = cli_check_interrupt(err);
  if (status == FB_OK)
    status = commit(od, err);
  for (size_t i = 0; i < od->nfiles; ++i) {
    remove(od->files[i]); /* what is still staged: nothing after a commit */
    free(od->files[i]);
  }
  free(od->files);
  if (od->stage)
    rmdir(od->stage);
  free(od->stage);
  /* rmdir fails, harmlessly, if the directory holds anything else. */
  if (status != FB_OK && od->created)
    rmdir(od->dir);
  *od = (cli_outdir){.dir = od->dir};
  return status;
}

void cli_nothing_written(fb_err *err, const char *dir)
{
  /* Said where a user may wonder about the previous results: after a run
   * was interrupted or failed on its way, not for a bad input, which is
   * refused before anything starts. */
  const int late = err->code == FB_ESOLVER || err->code == FB_EINTR || err->code == FB_EIO ||
                   err->code == FB_ENOMEM;
  if (!late || !dir)
    return;
  const size_t len = strlen(err->msg);
  struct stat st;
  if (stat(dir, &st) == 0)
    snprintf(err->msg + len, sizeof err->msg - len,
             "; nothing was written: %s holds what it held before", dir);
  else
    snprintf(err->msg + len, sizeof err->msg - len, "; nothing was written (%s not created)",
             dir);
}
