/* SPDX-License-Identifier: BSD-3-Clause */
/* A private directory for one test process: made by mkdtemp under $TMPDIR
 * (else /tmp) at the first call and removed, with everything in it, when
 * the process exits. A test's files go there under fixed names, so that
 * nothing another process left in /tmp (a stray /tmp/h.inp) can change
 * what the test sees, and parallel tests never meet. */
#ifndef FLEXBOND_TEST_TMPDIR_H
#define FLEXBOND_TEST_TMPDIR_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Room for a path in the directory: the directory itself keeps to
 * TEST_ROOT_MAX (a longer $TMPDIR gives way to /tmp), the rest is for the
 * names the tests choose. */
enum { TEST_PATH_MAX = 256, TEST_ROOT_MAX = 128 };

static char test_tmpdir_root[TEST_ROOT_MAX];

/* Removes path and, for a directory, everything under it (symbolic links
 * are removed, never followed). */
static inline void test_remove_tree(const char *path)
{
  struct stat st;
  if (lstat(path, &st) != 0)
    return;
  if (S_ISDIR(st.st_mode)) {
    DIR *d = opendir(path);
    const struct dirent *e;
    while (d && (e = readdir(d)) != NULL) {
      if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
        continue;
      char child[4096];
      if (snprintf(child, sizeof child, "%s/%s", path, e->d_name) < (int)sizeof child)
        test_remove_tree(child);
    }
    if (d)
      closedir(d);
    rmdir(path);
  } else {
    unlink(path);
  }
}

static inline void test_tmpdir_remove(void)
{
  test_remove_tree(test_tmpdir_root);
}

/* The process's private directory; a test cannot go on without one, so a
 * failure to make it ends the process with the reason. */
static inline const char *test_tmpdir(void)
{
  if (test_tmpdir_root[0])
    return test_tmpdir_root;
  const char *base = getenv("TMPDIR");
  if (!base || !*base || strlen(base) + sizeof "/flexbond_test.XXXXXX" > TEST_ROOT_MAX)
    base = "/tmp";
  snprintf(test_tmpdir_root, sizeof test_tmpdir_root, "%s/flexbond_test.XXXXXX", base);
  if (!mkdtemp(test_tmpdir_root)) {
    perror(test_tmpdir_root);
    abort();
  }
  atexit(test_tmpdir_remove);
  return test_tmpdir_root;
}

/* "<private directory>/name" into buf (size bytes); buf. */
static inline char *test_tmp_path(const char *name, char *buf, size_t size)
{
  const int n = snprintf(buf, size, "%s/%s", test_tmpdir(), name);
  if (n < 0 || (size_t)n >= size) {
    fprintf(stderr, "test_tmp_path: %s/%s is too long\n", test_tmpdir(), name);
    abort();
  }
  return buf;
}

#endif
