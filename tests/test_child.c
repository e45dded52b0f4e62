/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of the pieces every generated file passes through on its way
 * out: exclusive temporary files and directories (core/tmpfile.h), the
 * child-process runner (io/child.h) and the PNG check
 * (io/plot_internal.h, fb_png_check).
 *
 * Each check is made against what the mechanism exists for: a link
 * planted at a temporary name is never followed, a child that hangs is
 * killed at its time-out and leaves no process behind, a child starts in
 * a process group of its own with no signal blocked, and a PNG cut
 * anywhere, or with one byte changed, is refused. */
/* realpath(3) with a NULL buffer is XSI (POSIX.1-2008). */
/* NOLINTNEXTLINE(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp): POSIX's macro */
#define _XOPEN_SOURCE 700

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "flexbond/io.h"

#include "check.h"
#include "core/tmpfile.h"
#include "io/child.h"
#include "io/plot_internal.h"

static char root[256];

static const char *in_root(char *buf, size_t size, const char *name)
{
  snprintf(buf, size, "%s/%s", root, name);
  return buf;
}

/* Number of entries of root besides . and .. */
static int count_entries(void)
{
  DIR *d = opendir(root);
  int n = 0;
  for (struct dirent *e; d && (e = readdir(d)) != NULL;)
    n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
  if (d)
    closedir(d);
  return n;
}

static double now_s(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A name made by fb_tmpfile_create is new, hidden, beside its
 * destination and never a planted link: a link at every name is
 * impossible to plant ahead, so the check plants one at the name the
 * first call returned and makes the same call again, many times. */
static void test_tmpfile(void)
{
  char dest[300], victim[300];
  in_root(dest, sizeof dest, "out.csv");
  in_root(victim, sizeof victim, "victim");
  FILE *v = fopen(victim, "w");
  fputs("keep", v);
  fclose(v);
  for (int i = 0; i < 200; ++i) {
    int fd = -1;
    char *tmp = NULL;
    CHECK(fb_tmpfile_create(dest, &fd, &tmp) == 0);
    if (!tmp)
      return;
    CHECK(strncmp(tmp, root, strlen(root)) == 0 && strstr(tmp, "/.out.csv.") != NULL);
    struct stat st;
    CHECK(fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size == 0);
    close(fd);
    /* Replace the file by a link to the victim: whoever asks next must
     * not open it. */
    unlink(tmp);
    CHECK(symlink(victim, tmp) == 0);
    int fd2 = -1;
    char *tmp2 = NULL;
    CHECK(fb_tmpfile_create(dest, &fd2, &tmp2) == 0);
    CHECK(tmp2 && strcmp(tmp, tmp2) != 0);
    if (fd2 >= 0) {
      CHECK(write(fd2, "x", 1) == 1);
      close(fd2);
    }
    if (tmp2)
      unlink(tmp2);
    unlink(tmp);
    free(tmp);
    free(tmp2);
  }
  char buf[8] = {0};
  v = fopen(victim, "r");
  CHECK(v && fread(buf, 1, sizeof buf - 1, v) == 4 && strcmp(buf, "keep") == 0);
  if (v)
    fclose(v);
  unlink(victim);
  CHECK(count_entries() == 0);

  /* fb_out: a link planted at the old, predictable name of earlier
   * versions ("path.tmp.PID") is neither followed nor removed. */
  char planted[320];
  snprintf(planted, sizeof planted, "%s.tmp.%ld", dest, (long)getpid());
  v = fopen(victim, "w");
  fputs("keep", v);
  fclose(v);
  CHECK(symlink(victim, planted) == 0);
  fb_out *o = NULL;
  fb_err err;
  CHECK(fb_out_open(dest, &o, &err) == FB_OK);
  if (o) {
    fputs("new data\n", fb_out_stream(o));
    CHECK(fb_out_commit(&o, &err) == FB_OK);
  }
  struct stat st;
  CHECK(lstat(dest, &st) == 0 && S_ISREG(st.st_mode) && st.st_size == 9);
  CHECK(lstat(victim, &st) == 0 && st.st_size == 4);
  unlink(planted);
  unlink(victim);
  unlink(dest);

  char *dir = NULL;
  CHECK(fb_tmpdir_create(dest, "plot", &dir) == 0);
  CHECK(dir && lstat(dir, &st) == 0 && S_ISDIR(st.st_mode) && (st.st_mode & 077) == 0);
  if (dir)
    rmdir(dir);
  free(dir);
  CHECK(count_entries() == 0);
}

/* 1 if process pid has ended: no such process, or a zombie. */
static int is_dead(pid_t pid)
{
  char path[64], stat_line[512] = "";
  snprintf(path, sizeof path, "/proc/%ld/stat", (long)pid);
  FILE *fp = fopen(path, "r");
  if (!fp)
    return 1;
  const int got = fgets(stat_line, sizeof stat_line, fp) != NULL;
  fclose(fp);
  const char *paren = strrchr(stat_line, ')');
  return got && paren && paren[1] == ' ' && paren[2] == 'Z';
}

/* Runs "sh -c script" in root with time-out seconds; the status. */
static int run_sh(const char *script, double timeout, fb_err *err)
{
  char sh[] = "sh", c[] = "-c";
  char *s = strdup(script);
  char *argv[] = {sh, c, s, NULL};
  const fb_child_spec spec = {
      .program = "sh", .argv = argv, .cwd = root, .log = "child.log", .timeout_s = timeout};
  fb_err_clear(err);
  const int rc = fb_child_run(&spec, "test", err);
  free(s);
  char log[300];
  unlink(in_root(log, sizeof log, "child.log"));
  return rc;
}

static void test_child(void)
{
  fb_err err;
  char path[300];
  /* It runs in cwd, with stdin from /dev/null (read finds no line), and
   * its output lands in the log (quoted in a failure). */
  CHECK(run_sh("read x && exit 3; pwd -P > where.txt", 5, &err) == FB_OK);
  char where[300] = "", *real = realpath(root, NULL);
  FILE *w = fopen(in_root(path, sizeof path, "where.txt"), "r");
  CHECK(w && fgets(where, sizeof where, w) && real && strncmp(where, real, strlen(real)) == 0 &&
        where[strlen(real)] == '\n');
  if (w)
    fclose(w);
  free(real);
  unlink(path);
  CHECK(run_sh("echo 'gnuplot said: no'; exit 4", 5, &err) == FB_EIO);
  CHECK(strstr(err.msg, "exit status 4") != NULL);
  CHECK(strstr(err.msg, "gnuplot said: no") != NULL);
  /* Its own process group, no signal blocked, and none of the signals
   * that stop a program (HUP 1, INT 2, QUIT 3, PIPE 13, TERM 15: mask
   * 0x5007) ignored, whatever flexbond inherited; on failure the log
   * shows the masks. */
  CHECK(run_sh("grep -E '^Sig(Blk|Ign)' /proc/$$/status; "
               "test \"$(awk '{print $5}' /proc/$$/stat)\" = \"$$\" || exit 5; "
               "blk=$(awk '/^SigBlk/ {print $2}' /proc/$$/status); "
               "ign=$(awk '/^SigIgn/ {print $2}' /proc/$$/status); "
               "[ $((0x$blk)) -eq 0 ] || exit 6; [ $((0x$ign & 0x5007)) -eq 0 ] || exit 7",
               5, &err) == FB_OK);
  if (err.code)
    fprintf(stderr, "  %s\n", err.msg);
  /* A child killed by a signal is a failure that says so. */
  CHECK(run_sh("kill -9 $$", 5, &err) == FB_EIO);
  CHECK(strstr(err.msg, "signal 9") != NULL);
  /* A child that hangs, with a grandchild in its group, is killed at its
   * time-out, group and all, and the call returns soon after. */
  const double t0 = now_s();
  CHECK(run_sh("sleep 30 & echo $! > grandchild.pid; sleep 30", 0.3, &err) == FB_EIO);
  const double took = now_s() - t0;
  CHECK(took < 2.0);
  CHECK(strstr(err.msg, "did not finish within 0.3 s") != NULL);
  FILE *fp = fopen(in_root(path, sizeof path, "grandchild.pid"), "r");
  long gc = 0;
  CHECK(fp && fscanf(fp, "%ld", &gc) == 1);
  if (fp)
    fclose(fp);
  unlink(path);
  /* Killed: gone, or a zombie until whoever adopted it reaps it (a
   * container's first process may never). */
  int gone = 0;
  for (int i = 0; i < 100 && !gone; ++i) {
    gone = gc > 0 && is_dead((pid_t)gc);
    const struct timespec pause = {0, 10000000};
    if (!gone)
      nanosleep(&pause, NULL);
  }
  CHECK(gone);
  /* A program that is not there. */
  char none[] = "flexbond-no-such-program";
  char *argv[] = {none, NULL};
  const fb_child_spec spec = {
      .program = none, .argv = argv, .cwd = root, .log = "child.log", .timeout_s = 1};
  CHECK(fb_child_run(&spec, "test", &err) == FB_EIO);
  CHECK(strstr(err.msg, "not found in PATH") != NULL);
  CHECK(count_entries() == 0);
}

/* A small valid PNG: 1x1, greyscale (IHDR, IDAT of a zlib stream of the
 * one filter byte and the pixel, IEND), with its CRCs. */
static const unsigned char tiny_png[] = {
    0x89, 'P',  'N',  'G',  '\r', '\n', 0x1a, '\n', 0x00, 0x00, 0x00, 0x0d, 'I',  'H',
    'D',  'R',  0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x00, 0x00, 0x00,
    0x00, 0x3a, 0x7e, 0x9b, 0x55, 0x00, 0x00, 0x00, 0x0a, 'I',  'D',  'A',  'T',  0x78,
    0x9c, 0x63, 0x60, 0x00, 0x00, 0x00, 0x02, 0x00, 0x01, 0x48, 0xaf, 0xa4, 0x71, 0x00,
    0x00, 0x00, 0x00, 'I',  'E',  'N',  'D',  0xae, 0x42, 0x60, 0x82};

static int check_bytes(const unsigned char *data, size_t n)
{
  char path[300];
  in_root(path, sizeof path, "t.png");
  FILE *fp = fopen(path, "wb");
  if (n)
    fwrite(data, 1, n, fp);
  fclose(fp);
  fb_err err;
  const int rc = fb_png_check(path, &err);
  unlink(path);
  return rc;
}

static void test_png(void)
{
  const size_t n = sizeof tiny_png;
  CHECK(check_bytes(tiny_png, n) == FB_OK);
  /* Cut at every length: never complete. */
  int cut_refused = 1;
  for (size_t k = 0; k < n; ++k)
    cut_refused &= check_bytes(tiny_png, k) == FB_EIO;
  CHECK(cut_refused);
  /* One byte changed anywhere: refused (signature, a length, a type, the
   * data under a CRC, or a CRC itself). */
  unsigned char copy[sizeof tiny_png];
  int flip_refused = 1;
  for (size_t k = 0; k < n; ++k) {
    memcpy(copy, tiny_png, n);
    copy[k] ^= 0x01;
    flip_refused &= check_bytes(copy, n) == FB_EIO;
  }
  CHECK(flip_refused);
  /* Data after IEND. */
  unsigned char longer[sizeof tiny_png + 1];
  memcpy(longer, tiny_png, n);
  longer[n] = 0;
  CHECK(check_bytes(longer, n + 1) == FB_EIO);
  /* A link is not read through. */
  char path[300], target[300];
  in_root(target, sizeof target, "real.png");
  FILE *fp = fopen(target, "wb");
  fwrite(tiny_png, 1, n, fp);
  fclose(fp);
  CHECK(symlink(target, in_root(path, sizeof path, "link.png")) == 0);
  fb_err err;
  CHECK(fb_png_check(path, &err) == FB_EIO);
  unlink(path);
  unlink(target);
  CHECK(count_entries() == 0);
}

int main(void)
{
  snprintf(root, sizeof root, "%s/fb_test_child.XXXXXX",
           getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  if (!mkdtemp(root)) {
    perror(root);
    return 1;
  }
  test_tmpfile();
  test_child();
  test_png();
  rmdir(root);
  return check_report("test_child");
}
