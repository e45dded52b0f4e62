/* SPDX-License-Identifier: BSD-3-Clause */
/* Output directories written all or nothing (see cli_outdir in cli.h).
 *
 * Files are written into a hidden staging directory inside DIR (the same
 * file system, so that rename moves them) and moved into DIR only once
 * every file of the command is complete; a command that fails or is
 * interrupted removes its staging directory and leaves DIR's previous
 * contents as they were.
 *
 * Three more things make DIR hold one result at a time:
 * - a lock: DIR/.flexbond.lock, held with flock(2) from open to close, so
 *   that a second command into DIR is refused at once instead of mixing
 *   its files with the first's (a sweep takes the same lock). The file is
 *   removed by its holder; a command that locks it checks that the name
 *   still leads to the file it locked, since the holder may have removed
 *   it in between (then it tries again with the new file).
 * - a manifest: DIR/.flexbond-manifest lists, per command, the files that
 *   command put there, each with the inode, size and modification time it
 *   had. A commit removes the files its command wrote before and does not
 *   write now (a run with both systems, then a rigid one: system2.csv
 *   goes), and only those, and only while they are still the file it
 *   wrote (same inode, size and time): a file flexbond did not write, one
 *   a user has since replaced or edited, or another command's, is never
 *   touched.
 * - clean-up: holding the lock means no other command is staging into
 *   DIR, so any staging directory found there is a killed command's and
 *   is removed. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "flexbond/escape.h"
#include "flexbond/io.h"

#include "../core/textfile.h"
#include "cli.h"

static const char lock_name[] = ".flexbond.lock";
static const char manifest_name[] = ".flexbond-manifest";
static const char stage_prefix[] = ".flexbond-staging-";

/* A manifest holds at most this many entries (a run writes about twenty
 * files, modes about forty; the bound keeps a damaged manifest from
 * costing memory or time: each entry is compared with those before it). */
enum { MANIFEST_MAX_ENTRIES = 10000, LOCK_TRIES = 100, STAGE_REMOVE_PASSES = 50 };

/* ---- Removing what a command made. */

/* Removes the entry name of the directory open as dir_fd: a directory
 * with its contents down to depth levels, anything else by unlink. Never
 * follows a symbolic link (a link is removed as itself). */
static void remove_entry_at(int dir_fd, const char *name, int depth)
{
  struct stat st;
  if (fstatat(dir_fd, name, &st, AT_SYMLINK_NOFOLLOW) != 0)
    return;
  if (!S_ISDIR(st.st_mode)) {
    unlinkat(dir_fd, name, 0);
    return;
  }
  const int fd =
      depth > 0 ? openat(dir_fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC) : -1;
  DIR *d = fd >= 0 ? fdopendir(fd) : NULL;
  if (!d && fd >= 0)
    close(fd);
  for (struct dirent *e; d && (e = readdir(d)) != NULL;)
    if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
      remove_entry_at(dirfd(d), e->d_name, depth - 1);
  if (d)
    closedir(d);
  unlinkat(dir_fd, name, AT_REMOVEDIR);
}

/* Removes the staging directory path and what is in it (its files and
 * the private directories of gnuplot runs inside). Called by the signal
 * thread too, while the command may still be creating a file it had
 * begun: what appears after a pass is removed by the next, until the
 * directory is gone (a few passes at most; bounded all the same). */
static void remove_stage(const char *path)
{
  struct stat st;
  for (int pass = 0; path && pass < STAGE_REMOVE_PASSES; ++pass) {
    remove_entry_at(AT_FDCWD, path, 2);
    if (fstatat(AT_FDCWD, path, &st, AT_SYMLINK_NOFOLLOW) != 0)
      return;
    const struct timespec pause = {0, 2000000};
    nanosleep(&pause, NULL);
  }
}

/* 1 if name is a staging directory's name: the prefix and mkdtemp's six
 * characters. */
static int is_stage_name(const char *name)
{
  const size_t n = sizeof stage_prefix - 1;
  return strncmp(name, stage_prefix, n) == 0 && strlen(name + n) == 6;
}

/* 1 if name in dir_fd is a directory of this user's that only they may
 * enter, as mkdtemp makes a staging directory: a directory a user made
 * with such a name is not taken for one. */
static int is_own_private_dir(int dir_fd, const char *name)
{
  struct stat st;
  return fstatat(dir_fd, name, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISDIR(st.st_mode) &&
         st.st_uid == geteuid() && (st.st_mode & 077) == 0;
}

/* Removes the staging directories of killed commands from dir (the lock
 * is held: no live command is staging there). */
static void remove_stale_stages(const char *dir)
{
  const int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  DIR *d = fd >= 0 ? fdopendir(fd) : NULL;
  if (!d) {
    if (fd >= 0)
      close(fd);
    return;
  }
  for (struct dirent *e; (e = readdir(d)) != NULL;)
    if (is_stage_name(e->d_name) && is_own_private_dir(dirfd(d), e->d_name))
      remove_entry_at(dirfd(d), e->d_name, 2);
  closedir(d);
}

/* Removes the directories this command created for od->dir, deepest
 * first, each only if empty (rmdir), by the very paths it made them with. */
static void remove_created(const cli_outdir *od)
{
  for (size_t i = od->ncreated; i-- > 0;)
    rmdir(od->created_dirs[i]);
}

/* Releases the lock: the holder removes the file, then closes it. */
static void release_lock(const cli_outdir *od)
{
  if (od->lock_fd < 0)
    return;
  if (od->lock_path)
    unlink(od->lock_path);
  close(od->lock_fd);
}

void cli_outdir_abandon(const cli_outdir *od)
{
  if (od->stage)
    remove_stage(od->stage);
  release_lock(od);
  remove_created(od);
}

/* ---- Opening. */

/* Takes DIR's lock into od->lock_fd. */
static int take_lock(cli_outdir *od, fb_err *err)
{
  od->lock_path = cli_join_path(od->dir, lock_name);
  if (!od->lock_path)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  for (int try = 0; try < LOCK_TRIES; ++try) {
    const int fd = open(od->lock_path, O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0)
      return fb_err_set(err, FB_EIO, "%s: cannot create the lock file: %s", od->lock_path,
                        strerror(errno));
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      close(fd);
      if (e == EWOULDBLOCK)
        return fb_err_set(err, FB_EIO,
                          "%s: another flexbond command is writing into this directory "
                          "(it holds %s); wait for it to finish, or choose another -o",
                          od->dir, lock_name);
      return fb_err_set(err, FB_EIO, "%s: cannot lock: %s", od->lock_path, strerror(e));
    }
    struct stat held, named;
    if (fstat(fd, &held) == 0 && lstat(od->lock_path, &named) == 0 &&
        held.st_dev == named.st_dev && held.st_ino == named.st_ino) {
      od->lock_fd = fd;
      return FB_OK;
    }
    close(fd); /* its holder removed it meanwhile: lock the new one */
  }
  return fb_err_set(err, FB_EIO, "%s: cannot lock: the lock file keeps changing",
                    od->lock_path);
}

static int make_stage(cli_outdir *od, fb_err *err)
{
  char name[sizeof stage_prefix + 6];
  snprintf(name, sizeof name, "%sXXXXXX", stage_prefix);
  od->stage = cli_join_path(od->dir, name);
  if (!od->stage)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  if (mkdtemp(od->stage))
    return FB_OK;
  const int rc = fb_err_set(err, FB_EIO, "%s: cannot create a staging directory: %s", od->dir,
                            strerror(errno));
  free(od->stage);
  od->stage = NULL;
  return rc;
}

/* Frees what od owns (not the files it names). */
static void outdir_free(cli_outdir *od)
{
  for (size_t i = 0; i < od->nfiles; ++i)
    free(od->files[i]);
  free(od->files);
  free(od->stage);
  free(od->lock_path);
  for (size_t i = 0; i < od->ncreated; ++i)
    free(od->created_dirs[i]);
  free(od->created_dirs);
  *od = (cli_outdir){.dir = od->dir, .command = od->command, .lock_fd = -1};
}

int cli_outdir_open(cli_outdir *od, const char *dir, const char *command, fb_err *err)
{
  *od = (cli_outdir){.dir = dir, .command = command, .lock_fd = -1};
  int rc = fb_mkdir_p_created(dir, &od->created_dirs, &od->ncreated, err);
  if (rc == FB_OK)
    rc = take_lock(od, err);
  if (rc == FB_OK)
    remove_stale_stages(dir);
  if (rc == FB_OK && cli_guard_add(od, cli_outdir_abandon) != 0)
    rc = fb_err_set(err, FB_EINVAL, "%s: too many output directories open at once", dir);
  if (rc != FB_OK) {
    cli_outdir_abandon(od);
    outdir_free(od);
  }
  return rc;
}

char *cli_outdir_path(cli_outdir *od, const char *name, fb_err *err)
{
  /* Under the guard's lock, which the signal thread holds from the
   * moment it abandons od until the process ends: no staging directory
   * is made, and no new file named, after it has looked. */
  cli_guard_lock();
  /* Made at the first file: a command killed while it computes leaves
   * no staging directory behind. */
  char *path = NULL;
  if (od->stage || make_stage(od, err) == FB_OK) {
    path = cli_join_path(od->stage, name);
    if (!path)
      fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  }
  cli_guard_unlock(0);
  return path;
}

/* Under the guard's lock, as cli_outdir_path: jobs on two threads
 * (cli_jobs_run) keep files at once, and the signal thread reads the
 * list when it abandons od. */
int cli_outdir_keep(cli_outdir *od, char *path, fb_err *err)
{
  cli_guard_lock();
  char **grown = realloc(od->files, (od->nfiles + 1) * sizeof *grown);
  if (grown) {
    od->files = grown;
    od->files[od->nfiles++] = path;
  }
  cli_guard_unlock(0);
  if (!grown) {
    remove(path);
    free(path);
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  }
  return FB_OK;
}

/* A staged file whose format flexbond can read back is checked before it
 * is kept: a .json file must be JSON (fb_json_check). FB_EIO otherwise:
 * the file is not what it should be, whatever wrote it. */
static int check_written(const char *path, const char *name, fb_err *err)
{
  const size_t n = strlen(name);
  if (n < 5 || strcmp(name + n - 5, ".json") != 0)
    return FB_OK;
  char *text = NULL;
  size_t len = 0, at = 0;
  int rc = fb_read_file(path, &text, &len, err);
  if (rc == FB_OK && fb_json_check(text, len, &at) != 0)
    rc = fb_err_set(err, FB_EIO,
                    "%s: the file written is not valid JSON (at byte %zu); nothing "
                    "is kept: a defect of flexbond, please report it",
                    name, at);
  free(text);
  return rc;
}

int cli_outdir_write(cli_outdir *od, const char *name, cli_writer write, const void *ctx,
                     fb_err *err)
{
  char *path = cli_outdir_path(od, name, err);
  if (!path)
    return err->code; /* out of memory, or no staging directory */
  fb_out *out = NULL;
  int rc = fb_out_open(path, &out, err);
  if (rc == FB_OK) {
    write(fb_out_stream(out), ctx);
    /* Write errors stick to the stream; commit reports them. */
    rc = fb_out_commit(&out, err);
  }
  if (rc == FB_OK)
    rc = check_written(path, name, err);
  if (rc == FB_OK)
    return cli_outdir_keep(od, path, err);
  remove(path);
  free(path);
  return rc;
}

/* ---- The manifest. */

typedef struct manifest_entry {
  char *command; /* owned */
  char *name;    /* owned: a plain file name in DIR */
  unsigned long long ino, size;
  long long mtime, mtime_ns; /* s and ns: an edit within the second shows */
} manifest_entry;

typedef struct manifest {
  manifest_entry *e;
  size_t n;
} manifest;

static void manifest_free(manifest *m)
{
  for (size_t i = 0; i < m->n; ++i) {
    free(m->e[i].command);
    free(m->e[i].name);
  }
  free(m->e);
  *m = (manifest){NULL, 0};
}

/* The name of staged file i, without its directory. */
static const char *staged_name(const cli_outdir *od, size_t i)
{
  const char *slash = strrchr(od->files[i], '/');
  return slash ? slash + 1 : od->files[i];
}

/* 1 if od stages a file called name. */
static int stages(const cli_outdir *od, const char *name)
{
  for (size_t i = 0; i < od->nfiles; ++i)
    if (strcmp(staged_name(od, i), name) == 0)
      return 1;
  return 0;
}

/* 1 if name may be acted on: a plain name in DIR, not one of ours. A
 * manifest is a file in DIR that anyone who can write DIR can change, so
 * a line naming another directory ("../x", "/etc/x") is ignored. */
static int is_plain_name(const char *name)
{
  if (!*name || strcmp(name, ".") == 0 || strcmp(name, "..") == 0 ||
      strncmp(name, ".flexbond", 9) == 0)
    return 0;
  for (const char *c = name; *c; ++c)
    if (*c == '/' || (unsigned char)*c < 0x20 || *c == 0x7f)
      return 0;
  return 1;
}

/* Reads "COMMAND INO SIZE MTIME MTIME_NS NAME" into command (at most size
 * bytes) and *e; 0 if the line is not one. */
static int parse_line(const char *line, char *command, size_t size, manifest_entry *e,
                      const char **name)
{
  int n = 0;
  char fmt[48];
  snprintf(fmt, sizeof fmt, "%%%zu[a-z] %%llu %%llu %%lld %%lld %%n", size - 1);
  if (sscanf(line, fmt, command, &e->ino, &e->size, &e->mtime, &e->mtime_ns, &n) != 5 || n == 0)
    return 0;
  *name = line + n;
  return is_plain_name(*name);
}

/* Adds an entry of a manifest line to m; other lines are ignored. */
static int manifest_add_line(manifest *m, const char *line)
{
  char command[32];
  manifest_entry parsed = {NULL, NULL, 0, 0, 0, 0};
  const char *name = NULL;
  if (!parse_line(line, command, sizeof command, &parsed, &name) ||
      m->n >= MANIFEST_MAX_ENTRIES)
    return FB_OK;
  /* A name is one file: a repeated line (an edited manifest) would set
   * the same file aside twice. */
  for (size_t i = 0; i < m->n; ++i)
    if (strcmp(m->e[i].name, name) == 0)
      return FB_OK;
  manifest_entry *grown = realloc(m->e, (m->n + 1) * sizeof *grown);
  if (!grown)
    return FB_ENOMEM;
  m->e = grown;
  manifest_entry *e = &m->e[m->n];
  *e = parsed;
  e->command = malloc(strlen(command) + 1);
  e->name = malloc(strlen(name) + 1);
  if (!e->command || !e->name) {
    free(e->command);
    free(e->name);
    return FB_ENOMEM;
  }
  memcpy(e->command, command, strlen(command) + 1);
  memcpy(e->name, name, strlen(name) + 1);
  ++m->n;
  return FB_OK;
}

/* Reads DIR's manifest (none: empty) through the checked reader. A
 * manifest that cannot be read is taken as empty: nothing is removed. */
static int manifest_read(const cli_outdir *od, manifest *m, fb_err *err)
{
  *m = (manifest){NULL, 0};
  char *path = cli_join_path(od->dir, manifest_name);
  if (!path)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  struct stat st;
  fb_text_reader r;
  fb_err ignored;
  int rc = FB_OK;
  /* Only a manifest this user wrote, that nobody else may change, is
   * believed: in a directory others can write (a sticky /tmp), a planted
   * one could name a file of ours to remove. */
  if (lstat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_uid == geteuid() &&
      (st.st_mode & 022) == 0 && st.st_nlink == 1 &&
      fb_text_open(&r, path, "manifest", &ignored) == FB_OK) {
    char *line = NULL;
    while (rc == FB_OK && fb_text_next_data_line(&r, '#', &line) == FB_OK && line)
      rc = manifest_add_line(m, line);
    fb_text_close(&r);
  }
  free(path);
  if (rc != FB_OK) {
    manifest_free(m);
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  }
  return FB_OK;
}

typedef struct manifest_writer {
  const cli_outdir *od;
  const manifest *previous;
} manifest_writer;

/* The new manifest: the other commands' files that this one does not
 * replace, then this command's. */
static void write_manifest(FILE *fp, const void *ctx)
{
  const manifest_writer *w = ctx;
  fputs("# Files flexbond wrote here, per command: a command's next run into this\n"
        "# directory replaces its own files and removes those it no longer writes.\n",
        fp);
  for (size_t i = 0; i < w->previous->n; ++i) {
    const manifest_entry *e = &w->previous->e[i];
    if (strcmp(e->command, w->od->command) != 0 && !stages(w->od, e->name))
      fprintf(fp, "%s %llu %llu %lld %lld %s\n", e->command, e->ino, e->size, e->mtime,
              e->mtime_ns, e->name);
  }
  /* A rename keeps the inode, size and time the staged file has now. */
  for (size_t i = 0; i < w->od->nfiles; ++i) {
    struct stat st;
    if (lstat(w->od->files[i], &st) == 0)
      fprintf(fp, "%s %llu %llu %lld %lld %s\n", w->od->command, (unsigned long long)st.st_ino,
              (unsigned long long)st.st_size, (long long)st.st_mtim.tv_sec,
              (long long)st.st_mtim.tv_nsec, staged_name(w->od, i));
  }
}

/* 1 if st is the file that e recorded: ours (this user's), with the
 * inode, size and modification time it had. */
static int is_recorded_file(const struct stat *st, const manifest_entry *e)
{
  return S_ISREG(st->st_mode) && st->st_uid == geteuid() &&
         (unsigned long long)st->st_ino == e->ino &&
         (unsigned long long)st->st_size == e->size &&
         (long long)st->st_mtim.tv_sec == e->mtime &&
         (long long)st->st_mtim.tv_nsec == e->mtime_ns;
}

/* FB_EIO if od would replace a file another command wrote into DIR and
 * that is still as it wrote it: `freq -o D` after `run -o D` would take
 * over run's bode_*.png, and a later `freq --no-figures -o D` remove them
 * from under run's report.md. Each command's files stay its own; the
 * user chooses another directory (or removes the files). */
static int check_takeover(const cli_outdir *od, const manifest *previous, fb_err *err)
{
  struct stat st;
  for (size_t i = 0; i < previous->n; ++i) {
    const manifest_entry *e = &previous->e[i];
    if (strcmp(e->command, od->command) == 0 || !stages(od, e->name))
      continue;
    char *final = cli_join_path(od->dir, e->name);
    const int theirs = final && lstat(final, &st) == 0 && is_recorded_file(&st, e);
    free(final);
    if (theirs)
      return fb_err_set(err, FB_EIO,
                        "%s/%s is flexbond %s's, which this %s would replace: a command "
                        "never replaces another's files; write into another directory, or "
                        "remove %s's files first",
                        od->dir, e->name, e->command, od->command, e->command);
  }
  return FB_OK;
}

/* ---- Committing. */

/* One rename of the commit: from -> to, undone by to -> from. */
typedef struct move {
  char *from, *to;
} move;

typedef struct moves {
  move *m;
  size_t n, done;
} moves;

static int moves_add(moves *mv, char *from, char *to)
{
  move *grown = from && to ? realloc(mv->m, (mv->n + 1) * sizeof *grown) : NULL;
  if (!grown) {
    free(from);
    free(to);
    return FB_ENOMEM;
  }
  mv->m = grown;
  mv->m[mv->n++] = (move){from, to};
  return FB_OK;
}

static void moves_free(moves *mv)
{
  for (size_t i = 0; i < mv->n; ++i) {
    free(mv->m[i].from);
    free(mv->m[i].to);
  }
  free(mv->m);
}

/* "stage/NAME.previous": where the file DIR/NAME is kept during the
 * commit. */
static char *aside_path(const cli_outdir *od, const char *name)
{
  const size_t n = strlen(od->stage) + strlen(name) + sizeof "/.previous";
  char *p = malloc(n);
  if (p)
    snprintf(p, n, "%s/%s.previous", od->stage, name);
  return p;
}

/* Plans the renames: every file DIR/NAME that is there and will be
 * replaced or removed goes aside first, then every staged file into DIR.
 * removed: this command's files of the previous manifest that it no
 * longer writes, while they are the files it wrote (is_recorded_file). */
static int plan(const cli_outdir *od, const manifest *previous, moves *mv)
{
  int rc = FB_OK;
  struct stat st;
  for (size_t i = 0; rc == FB_OK && i < previous->n; ++i) {
    const manifest_entry *e = &previous->e[i];
    char *final = cli_join_path(od->dir, e->name);
    if (final && strcmp(e->command, od->command) == 0 && !stages(od, e->name) &&
        lstat(final, &st) == 0 && is_recorded_file(&st, e))
      rc = moves_add(mv, final, aside_path(od, e->name));
    else
      free(final);
  }
  for (size_t i = 0; rc == FB_OK && i < od->nfiles; ++i) {
    const char *name = staged_name(od, i);
    char *final = cli_join_path(od->dir, name);
    if (final && lstat(final, &st) == 0 && !S_ISDIR(st.st_mode))
      rc = moves_add(mv, final, aside_path(od, name));
    else
      free(final);
  }
  for (size_t i = 0; rc == FB_OK && i < od->nfiles; ++i) {
    const size_t n = strlen(od->files[i]) + 1;
    char *from = malloc(n);
    if (from)
      memcpy(from, od->files[i], n);
    rc = moves_add(mv, from, cli_join_path(od->dir, staged_name(od, i)));
  }
  return rc;
}

/* Undoes the renames done so far, last first. */
static void roll_back(moves *mv)
{
  while (mv->done > 0) {
    const move *m = &mv->m[--mv->done];
    rename(m->to, m->from);
  }
}

/* Renames in order; FB_EIO (all undone) at the first that fails. A
 * directory where a new file goes is refused before anything moves. */
static int apply(const cli_outdir *od, moves *mv, fb_err *err)
{
  struct stat st;
  for (size_t i = 0; i < od->nfiles; ++i) {
    char *final = cli_join_path(od->dir, staged_name(od, i));
    const int is_dir = final && lstat(final, &st) == 0 && S_ISDIR(st.st_mode);
    free(final);
    if (is_dir)
      return fb_err_set(err, FB_EIO, "%s/%s: cannot replace a directory with the new file",
                        od->dir, staged_name(od, i));
  }
  for (mv->done = 0; mv->done < mv->n; ++mv->done) {
    const move *m = &mv->m[mv->done];
    if (rename(m->from, m->to) != 0) {
      const int rc =
          fb_err_set(err, FB_EIO, "%s: cannot move into place: %s", m->from, strerror(errno));
      roll_back(mv);
      return rc;
    }
  }
  return FB_OK;
}

/* Moves every staged file into dir and the files it replaces or removes
 * aside, all or none; the interruption is checked once more when all is
 * in place, and undone then, so that a signal that arrives during the
 * commit leaves the previous result. Under the guard's lock, which the
 * signal thread takes before it abandons the directory. */
static int by_path(const void *a, const void *b)
{
  return strcmp(*(char *const *)a, *(char *const *)b);
}

static int commit(cli_outdir *od, fb_err *err)
{
  /* In name order: jobs on two threads (cli_jobs_run) stage files in
   * either order, and the manifest and the moves should not depend on
   * it. */
  qsort(od->files, od->nfiles, sizeof *od->files, by_path);
  manifest previous;
  int rc = manifest_read(od, &previous, err);
  if (rc == FB_OK)
    rc = check_takeover(od, &previous, err);
  const manifest_writer w = {od, &previous};
  if (rc == FB_OK)
    rc = cli_outdir_write(od, manifest_name, write_manifest, &w, err);
  /* Writable by its owner alone, as manifest_read requires. */
  if (rc == FB_OK && chmod(od->files[od->nfiles - 1], 0644) != 0)
    rc = fb_err_set(err, FB_EIO, "%s: %s", od->files[od->nfiles - 1], strerror(errno));
  moves mv = {NULL, 0, 0};
  if (rc == FB_OK && plan(od, &previous, &mv) != FB_OK)
    rc = fb_err_set(err, FB_ENOMEM, "%s: out of memory", od->dir);
  cli_guard_lock();
  if (rc == FB_OK)
    rc = cli_check_interrupt(err);
  if (rc == FB_OK)
    rc = apply(od, &mv, err);
  if (rc == FB_OK && cli_check_interrupt(err) != FB_OK) {
    roll_back(&mv);
    rc = FB_EINTR;
  }
  cli_guard_unlock(rc == FB_OK);
  moves_free(&mv);
  manifest_free(&previous);
  return rc;
}

/* Appends to err's message that nothing was written to dir. */
static void nothing_written(fb_err *err, const char *dir)
{
  /* Said where a user may wonder about the previous results: after a run
   * was interrupted or failed on its way, not for a bad input, which is
   * refused before anything starts. */
  const int late = err->code == FB_ESOLVER || err->code == FB_EINTR || err->code == FB_EIO ||
                   err->code == FB_ENOMEM;
  if (!late || !dir)
    return;
  struct stat st;
  if (stat(dir, &st) == 0)
    fb_err_append(err, "; nothing was written: %s holds what it held before", dir);
  else
    fb_err_append(err, "; nothing was written (%s not created)", dir);
}

int cli_outdir_close(cli_outdir *od, int status, fb_err *err)
{
  if (status == FB_OK && od->stage)
    status = commit(od, err);
  /* The stage holds, after a commit, only the files set aside; after a
   * failure, the new files too. Under the guard's lock: the signal thread
   * must not release the lock a second time (by then the lock file may be
   * another command's). */
  cli_guard_lock();
  if (status == FB_OK) {
    remove_stage(od->stage);
    release_lock(od);
  } else {
    cli_outdir_abandon(od);
  }
  cli_guard_remove(od);
  cli_guard_unlock(0);
  const char *dir = od->dir;
  const int noted = od->failure_noted;
  outdir_free(od);
  if (status != FB_OK && !noted)
    nothing_written(err, dir);
  return status;
}
