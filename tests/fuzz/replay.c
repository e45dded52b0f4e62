/* SPDX-License-Identifier: BSD-3-Clause */
/* Replays inputs through a fuzz target without libFuzzer: main() runs
 * LLVMFuzzerTestOneInput once on every file named on the command line and on every file
 * of every directory named (not recursing; names starting with '.' are skipped, so a
 * .keep file holds an empty directory in git). Linked with one tests/fuzz/fuzz_*.c, it
 * makes the replay_* programs that CTest runs over the committed corpora and crash
 * inputs (tests/fuzz/corpus/NAME, tests/fuzz/regressions/NAME), with gcc or clang: a
 * crash or a sanitizer report fails the run. Exit status 1 when a path cannot be read. */
#include <dirent.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The whole file at path in a buffer of exactly its size (so that the sanitizers catch
 * a read past the end), NULL and a message on failure. */
static uint8_t *read_input(const char *path, size_t *size)
{
  FILE *fp = fopen(path, "rb");
  if (!fp) {
    perror(path);
    return NULL;
  }
  uint8_t *data = NULL;
  long n = -1;
  if (fseek(fp, 0, SEEK_END) == 0 && (n = ftell(fp)) >= 0 && fseek(fp, 0, SEEK_SET) == 0)
    data = malloc(n > 0 ? (size_t)n : 1);
  if (data && fread(data, 1, (size_t)n, fp) != (size_t)n) {
    free(data);
    data = NULL;
  }
  fclose(fp);
  if (!data)
    fprintf(stderr, "%s: cannot read\n", path);
  *size = data ? (size_t)n : 0;
  return data;
}

/* Runs the target on one file; 1 when it cannot be read. */
static int replay_file(const char *path)
{
  size_t size = 0;
  uint8_t *data = read_input(path, &size);
  if (!data)
    return 1;
  fprintf(stderr, "replay: %s (%zu bytes)\n", path, size);
  LLVMFuzzerTestOneInput(data, size);
  free(data);
  return 0;
}

static int skip_entry(const struct dirent *e)
{
  return e->d_name[0] != '.';
}

/* Runs the target on the regular files of dir, in name order; *count of them. */
static int replay_dir(const char *dir, size_t *count)
{
  struct dirent **names = NULL;
  const int n = scandir(dir, &names, skip_entry, alphasort);
  if (n < 0) {
    perror(dir);
    return 1;
  }
  int failed = 0;
  for (int i = 0; i < n; ++i) {
    const size_t len = strlen(dir) + strlen(names[i]->d_name) + 2;
    char *path = malloc(len);
    struct stat st;
    if (!path) {
      failed = 1;
    } else {
      snprintf(path, len, "%s/%s", dir, names[i]->d_name);
      if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) {
        failed |= replay_file(path);
        ++*count;
      }
    }
    free(path);
    free(names[i]);
  }
  free(names);
  return failed;
}

int main(int argc, char **argv)
{
  if (argc < 2) {
    fprintf(stderr, "usage: %s FILE_OR_DIRECTORY...\n", argv[0]);
    return 2;
  }
  int failed = 0;
  size_t count = 0;
  for (int i = 1; i < argc; ++i) {
    struct stat st;
    if (stat(argv[i], &st) != 0) {
      perror(argv[i]);
      failed = 1;
    } else if (S_ISDIR(st.st_mode)) {
      failed |= replay_dir(argv[i], &count);
    } else {
      failed |= replay_file(argv[i]);
      ++count;
    }
  }
  fprintf(stderr, "replay: %zu inputs%s\n", count, failed ? ", some unreadable" : "");
  return failed;
}
