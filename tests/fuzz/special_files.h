/* SPDX-License-Identifier: BSD-3-Clause */
/* For the YAML fuzz targets: inputs that could name a special file are skipped. The model
 * and scenario loaders read every file a document names (tables, Matrix Market files,
 * road profiles) to its end. fb_open_input refuses devices and FIFOs, but /proc and /sys
 * hold "regular" files that block (/proc/kmsg) or run to gigabytes (/proc/kcore, which
 * root may read): findings about the machine, not the parsers (docs/fuzzing.md,
 * "Limits"). Relative references resolve inside tests/fuzz, so a path can reach /dev,
 * /proc or /sys only through one of those names after a '/', or by spelling it with a
 * double-quoted YAML escape (\x, \u, \U, \/, or an escaped line break joining two lines
 * without a space). */
#ifndef FLEXBOND_FUZZ_SPECIAL_FILES_H
#define FLEXBOND_FUZZ_SPECIAL_FILES_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* 1 if the size bytes at data contain word (at any byte offset). */
static int fuzz_contains(const uint8_t *data, size_t size, const char *word)
{
  const size_t n = strlen(word);
  for (size_t i = 0; i + n <= size; ++i)
    if (memcmp(data + i, word, n) == 0)
      return 1;
  return 0;
}

/* 1 if the input could name a file under /dev, /proc or /sys. */
static int fuzz_may_name_special_file(const uint8_t *data, size_t size)
{
  static const char *const words[] = {"/dev", "/proc", "/sys", "\\x", "\\u",
                                      "\\U",  "\\/",   "\\\n", "\\\r"};
  for (size_t k = 0; k < sizeof words / sizeof words[0]; ++k)
    if (fuzz_contains(data, size, words[k]))
      return 1;
  return 0;
}

/* The input as the loaders' text (never NULL, also for an empty input), or NULL when it
 * is to be skipped. */
static const char *fuzz_yaml_text(const uint8_t *data, size_t size)
{
  static const char empty[1] = "";
  if (fuzz_may_name_special_file(data, size))
    return NULL;
  return data ? (const char *)data : empty;
}

#endif
