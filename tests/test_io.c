/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of the atomic output files and fb_mkdir_p (flexbond/io.h).
 *
 * Everything happens in a fresh directory from mkdtemp, and after every
 * operation the test lists that directory, so a stray "*.tmp.PID" file
 * left behind by commit or abort is caught. */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "flexbond/bd.h"
#include "flexbond/bg.h"
#include "flexbond/io.h"
#include "flexbond/sim.h"

#include "bgtest_util.h"
#include "check.h"

static char root[256];

/* root/name in buf. */
static const char *in_root(char *buf, size_t size, const char *name)
{
  snprintf(buf, size, "%s/%s", root, name);
  return buf;
}

static void write_text(const char *path, const char *text)
{
  FILE *fp = fopen(path, "w");
  if (!fp) {
    perror(path);
    return;
  }
  fputs(text, fp);
  fclose(fp);
}

/* The whole file in buf (NUL-terminated), or "<missing>". */
static const char *read_text(const char *path, char *buf, size_t size)
{
  FILE *fp = fopen(path, "r");
  if (!fp)
    return "<missing>";
  size_t n = fread(buf, 1, size - 1, fp);
  buf[n] = '\0';
  fclose(fp);
  return buf;
}

static int is_dir(const char *path)
{
  struct stat st;
  return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

static int compare_names(const void *a, const void *b)
{
  return strcmp(a, b);
}

/* Entries of dir other than "." and "..", joined by spaces in sorted
 * order into buf, so a test compares the listing with one string. */
static const char *listing(const char *dir, char *buf, size_t size)
{
  char names[16][256];
  size_t n = 0;
  DIR *d = opendir(dir);
  if (!d)
    return "<no dir>";
  for (struct dirent *e = readdir(d); e && n < 16; e = readdir(d)) {
    if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
      snprintf(names[n++], sizeof names[0], "%s", e->d_name);
  }
  closedir(d);
  qsort(names, n, sizeof names[0], compare_names);
  buf[0] = '\0';
  for (size_t i = 0; i < n; ++i) {
    strncat(buf, i ? " " : "", size - strlen(buf) - 1);
    strncat(buf, names[i], size - strlen(buf) - 1);
  }
  return buf;
}

/* Removes path and, if it is a directory, everything below it. */
static void remove_tree(const char *path)
{
  struct stat st;
  if (lstat(path, &st) != 0)
    return;
  if (S_ISDIR(st.st_mode)) {
    chmod(path, 0700);
    DIR *d = opendir(path);
    for (struct dirent *e = d ? readdir(d) : NULL; e; e = readdir(d)) {
      if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
        continue;
      char child[1024];
      snprintf(child, sizeof child, "%s/%s", path, e->d_name);
      remove_tree(child);
    }
    if (d)
      closedir(d);
  }
  remove(path);
}

static void test_commit_creates_file(void)
{
  char path[512], buf[256], list[256];
  fb_err err;
  fb_err_clear(&err);
  fb_out *o = NULL;
  CHECK(fb_out_open(in_root(path, sizeof path, "a.txt"), &o, &err) == FB_OK);
  CHECK(o != NULL);
  /* Until commit the data lives only in the temporary file, hidden and
   * beside it: ".a.txt.XXXXXX.tmp". */
  const char *tmp_name = listing(root, list, sizeof list);
  CHECK(strncmp(tmp_name, ".a.txt.", 7) == 0 && strlen(tmp_name) == 17 &&
        strcmp(tmp_name + 13, ".tmp") == 0);
  fputs("hello\n", fb_out_stream(o));
  fprintf(fb_out_stream(o), "%d\n", 42);
  CHECK(fb_out_commit(&o, &err) == FB_OK);
  CHECK(o == NULL);
  CHECK(strcmp(read_text(path, buf, sizeof buf), "hello\n42\n") == 0);
  CHECK(strcmp(listing(root, list, sizeof list), "a.txt") == 0);
  remove(path);
}

static void test_commit_replaces_file(void)
{
  char path[512], buf[256], list[256];
  fb_err err;
  fb_out *o = NULL;
  write_text(in_root(path, sizeof path, "b.txt"), "old contents\n");
  CHECK(fb_out_open(path, &o, &err) == FB_OK);
  /* The old file stays readable while the new one is written. */
  CHECK(strcmp(read_text(path, buf, sizeof buf), "old contents\n") == 0);
  fputs("new\n", fb_out_stream(o));
  CHECK(fb_out_commit(&o, &err) == FB_OK);
  CHECK(strcmp(read_text(path, buf, sizeof buf), "new\n") == 0);
  CHECK(strcmp(listing(root, list, sizeof list), "b.txt") == 0);
  remove(path);
}

static void test_abort(void)
{
  char path[512], buf[256], list[256];
  fb_out *o = NULL;
  CHECK(fb_out_open(in_root(path, sizeof path, "c.txt"), &o, NULL) == FB_OK);
  fputs("discarded\n", fb_out_stream(o));
  fb_out_abort(&o);
  CHECK(o == NULL);
  CHECK(strcmp(listing(root, list, sizeof list), "") == 0);

  /* An existing file is left exactly as it was. */
  write_text(path, "keep me\n");
  CHECK(fb_out_open(path, &o, NULL) == FB_OK);
  fputs("discarded\n", fb_out_stream(o));
  fb_out_abort(&o);
  CHECK(strcmp(read_text(path, buf, sizeof buf), "keep me\n") == 0);
  CHECK(strcmp(listing(root, list, sizeof list), "c.txt") == 0);
  remove(path);

  /* Both accept a NULL handle: abort does nothing, commit refuses. */
  fb_out_abort(&o);
  fb_out_abort(NULL);
  fb_err err;
  CHECK(fb_out_commit(&o, &err) == FB_EINVAL);
}

/* The message names the path and the system's reason. */
static void check_io_error(int rc, const fb_err *err, const char *path, int errnum)
{
  CHECK(rc == FB_EIO);
  CHECK(err->code == FB_EIO);
  CHECK(strstr(err->msg, path) != NULL);
  CHECK(strstr(err->msg, strerror(errnum)) != NULL);
  if (rc != FB_EIO || !strstr(err->msg, strerror(errnum)))
    fprintf(stderr, "  message was: %s\n", err->msg);
}

static void test_open_errors(void)
{
  char path[512], file[512], list[256];
  fb_err err;
  fb_out *o = NULL;

  int rc = fb_out_open(in_root(path, sizeof path, "no/such/dir/out.csv"), &o, &err);
  check_io_error(rc, &err, path, ENOENT);
  CHECK(o == NULL);

  /* A regular file where a directory should be. */
  write_text(in_root(file, sizeof file, "plain"), "x");
  rc = fb_out_open(in_root(path, sizeof path, "plain/out.csv"), &o, &err);
  check_io_error(rc, &err, path, ENOTDIR);
  remove(file);

  /* A read-only directory; root may write anywhere, so only as a user. */
  if (geteuid() != 0) {
    char dir[512];
    mkdir(in_root(dir, sizeof dir, "ro"), 0500);
    in_root(path, sizeof path, "ro/out.csv");
    rc = fb_out_open(path, &o, &err);
    check_io_error(rc, &err, path, EACCES);
    CHECK(strcmp(listing(dir, list, sizeof list), "") == 0);
    remove_tree(dir);
  }

  rc = fb_out_open("", &o, &err);
  CHECK(rc == FB_EINVAL);
  CHECK(strcmp(listing(root, list, sizeof list), "") == 0);
}

/* A destination that is a directory is refused at open, with nothing
 * created; one that becomes a directory after open makes the rename fail
 * at commit, and the temporary file goes. */
static void test_commit_rename_error(void)
{
  char path[512], list[256];
  fb_err err;
  fb_out *o = NULL;
  mkdir(in_root(path, sizeof path, "adir"), 0700);
  check_io_error(fb_out_open(path, &o, &err), &err, path, EISDIR);
  CHECK(o == NULL);
  CHECK(strcmp(listing(root, list, sizeof list), "adir") == 0);
  remove_tree(path);

  in_root(path, sizeof path, "later_dir");
  CHECK(fb_out_open(path, &o, &err) == FB_OK);
  if (!o)
    return;
  fputs("data\n", fb_out_stream(o));
  mkdir(path, 0700);
  int rc = fb_out_commit(&o, &err);
  check_io_error(rc, &err, path, EISDIR);
  CHECK(o == NULL);
  CHECK(is_dir(path));
  CHECK(strcmp(listing(root, list, sizeof list), "later_dir") == 0);
  remove_tree(path);
}

/* A write that fails as on a full disk: the file size limit makes write(2)
 * fail with EFBIG once the file would exceed 4 KiB (SIGXFSZ ignored so the
 * process survives, POSIX setrlimit). The 64 KiB written exceed stdio's
 * buffer, so the failure happens inside fputs and must still be reported by
 * commit through the stream's error flag, or at the final flush. */
static void test_commit_write_error(void)
{
  char path[512], list[256];
  fb_err err;
  fb_out *o = NULL;
  struct rlimit old_limit, small_limit;
  CHECK(getrlimit(RLIMIT_FSIZE, &old_limit) == 0);
  small_limit = old_limit;
  small_limit.rlim_cur = 4096;
  void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);

  CHECK(fb_out_open(in_root(path, sizeof path, "big.csv"), &o, &err) == FB_OK);
  CHECK(setrlimit(RLIMIT_FSIZE, &small_limit) == 0);
  for (int i = 0; i < 4096; ++i)
    fputs("0123456789abcde\n", fb_out_stream(o));
  int rc = fb_out_commit(&o, &err);
  CHECK(setrlimit(RLIMIT_FSIZE, &old_limit) == 0);
  signal(SIGXFSZ, old_handler);

  CHECK(rc == FB_EIO);
  CHECK(strstr(err.msg, path) != NULL);
  CHECK(strstr(err.msg, "write failed") != NULL);
  CHECK(o == NULL);
  CHECK(strcmp(listing(root, list, sizeof list), "") == 0);
}

static void test_mkdir_p(void)
{
  char dir[512], file[512], path[512], list[256];
  fb_err err;
  CHECK(fb_mkdir_p(in_root(dir, sizeof dir, "x/y/z"), &err) == FB_OK);
  CHECK(is_dir(dir));
  /* Existing directories are fine: a second call and a trailing slash. */
  CHECK(fb_mkdir_p(dir, &err) == FB_OK);
  CHECK(fb_mkdir_p(in_root(dir, sizeof dir, "x//y/w/"), &err) == FB_OK);
  CHECK(is_dir(in_root(dir, sizeof dir, "x/y/w")));
  CHECK(strcmp(listing(in_root(dir, sizeof dir, "x/y"), list, sizeof list), "w z") == 0);

  /* A component that is a file: the message names the path asked for and
   * the component that failed. */
  write_text(in_root(file, sizeof file, "x/f"), "x");
  int rc = fb_mkdir_p(in_root(path, sizeof path, "x/f/g"), &err);
  CHECK(rc == FB_EIO);
  CHECK(strstr(err.msg, path) != NULL);
  CHECK(strstr(err.msg, "'") != NULL && strstr(err.msg, file) != NULL);
  CHECK(strstr(err.msg, "not a directory") != NULL);
  /* The last component is a file. */
  rc = fb_mkdir_p(file, &err);
  CHECK(rc == FB_EIO);
  CHECK(strstr(err.msg, file) != NULL);

  CHECK(fb_mkdir_p("", &err) == FB_EINVAL);
  remove_tree(in_root(dir, sizeof dir, "x"));
  CHECK(strcmp(listing(root, list, sizeof list), "") == 0);
}

/* A constant force F on a mass m from rest: p(t) = F t, v(t) = F t / m.
 * Simulated 0..1 s with 10 samples per second. */
#define CSV_FORCE (2.0 / 3.0) /* N; values with many digits test %.10g */
#define CSV_MASS 7.0          /* kg */

static int simulate_mass(fb_bg **bg, fb_bd **bd, fb_result **res, fb_err *err)
{
  /* The second probe's name needs CSV quoting: a comma and a quote. */
  const fb_probe_spec probes[2] = {{"p", FB_PROBE_STATE, "m", 0, 0, 1.0, NULL, NULL, 0},
                                   {"v,\"m\"", FB_PROBE_FLOW, "b", 0, 0, 1.0, "m/s", NULL, 0}};
  int rc = fb_bg_new("csv", bg, err);
  if (!rc)
    rc = add_const_source(*bg, "F", FB_BG_SE, CSV_FORCE, err);
  if (!rc)
    rc = add_scalar(*bg, "m", FB_BG_I, CSV_MASS, err);
  if (!rc)
    rc = fb_bg_connect(*bg, "b", "F", "m", err);
  if (!rc)
    rc = fb_bd_build(*bg, probes, 2, bd, err);
  fb_sim_opts opts;
  fb_sim_opts_default(&opts);
  opts.t_end = 1.0;
  opts.sample_rate = 10.0;
  if (!rc)
    rc = fb_sim_run(*bd, &opts, res, err);
  return rc;
}

/* Checks the rows of the CSV file at fp against the closed form. */
static void check_csv_rows(FILE *fp)
{
  /* The exact solution is linear in t, which BDF of every order and
   * CVODE's interpolating polynomial reproduce up to rounding, so the
   * error is dominated by the 10 significant digits of %.10g: at most
   * 5e-10 relative on values below 1, so 1e-9 absolute. */
  const double tol = 1e-9;
  int rows = 0;
  double t, p, v;
  char extra;
  char line[256];
  while (fgets(line, sizeof line, fp)) {
    CHECK(sscanf(line, "%lf,%lf,%lf%c", &t, &p, &v, &extra) == 4 && extra == '\n');
    CHECK_NEAR(t, rows * 0.1, 1e-12);
    CHECK_NEAR(p, CSV_FORCE * t, tol);
    CHECK_NEAR(v, CSV_FORCE * t / CSV_MASS, tol);
    ++rows;
  }
  CHECK(rows == 11);
}

static void test_result_csv(void)
{
  char path[512], list[256], line[256], expected[256];
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  fb_bd *bd = NULL;
  fb_result *res = NULL;
  MUST(simulate_mass(&bg, &bd, &res, &err), &err);
  if (res) {
    CHECK(fb_result_write_csv(res, in_root(path, sizeof path, "r.csv"), &err) == FB_OK);
    CHECK(strcmp(listing(root, list, sizeof list), "r.csv") == 0);
    FILE *fp = fopen(path, "r");
    CHECK(fp != NULL);
    /* Time is "t [s]"; the state's unit comes from the domain (whatever
     * the library calls it); the flow's was given, and the field is quoted
     * with the inner quotes doubled (RFC 4180). */
    snprintf(expected, sizeof expected, "t [s],p [%s],\"v,\"\"m\"\" [m/s]\"\n",
             fb_result_col_unit(res, 1));
    CHECK(fp && fgets(line, sizeof line, fp) && strcmp(line, expected) == 0);
    if (fp) {
      check_csv_rows(fp);
      fclose(fp);
    }
    remove(path);

    int rc = fb_result_write_csv(res, in_root(path, sizeof path, "none/r.csv"), &err);
    check_io_error(rc, &err, path, ENOENT);
  }
  fb_result_free(&res);
  fb_bd_free(&bd);
  fb_bg_free(&bg);
  CHECK(strcmp(listing(root, list, sizeof list), "") == 0);
}

int main(void)
{
  const char *tmpdir = getenv("TMPDIR");
  snprintf(root, sizeof root, "%s/fb_test_io.XXXXXX", tmpdir && *tmpdir ? tmpdir : "/tmp");
  if (!mkdtemp(root)) {
    perror(root);
    return 1;
  }
  test_commit_creates_file();
  test_commit_replaces_file();
  test_abort();
  test_open_errors();
  test_commit_rename_error();
  test_commit_write_error();
  test_mkdir_p();
  test_result_csv();
  remove_tree(root);
  return check_report("test_io");
}
