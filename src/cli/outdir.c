/* Output directories written all or nothing (see cli_outdir in cli.h):
 * a command that fails after some of its files are in place takes them
 * back, so a failed run leaves no output behind. */
#include <stdio.h>
#include <stdlib.h>
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
  *od = (cli_outdir){.dir = dir, .created = !is_directory(dir), .files = NULL, .nfiles = 0};
  return fb_mkdir_p(dir, err);
}

char *cli_outdir_path(const cli_outdir *od, const char *name, fb_err *err)
{
  char *path = cli_join_path(od->dir, name);
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

int cli_outdir_close(cli_outdir *od, int status)
{
  for (size_t i = 0; i < od->nfiles; ++i) {
    if (status != FB_OK)
      remove(od->files[i]);
    free(od->files[i]);
  }
  free(od->files);
  /* rmdir fails, harmlessly, if the directory holds anything else. */
  if (status != FB_OK && od->created)
    rmdir(od->dir);
  *od = (cli_outdir){.dir = od->dir, .created = 0, .files = NULL, .nfiles = 0};
  return status;
}
