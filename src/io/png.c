/* SPDX-License-Identifier: BSD-3-Clause */
/* Is a file a complete PNG image? (io/plot_internal.h, fb_png_check.)
 *
 * A child that draws a PNG may exit 0 having written nothing or half of
 * it (gnuplot does on a full disk), so every image is read back before it
 * is committed. The checks follow the PNG specification (W3C, Portable
 * Network Graphics (PNG) Specification, 2nd ed., 2003): the 8-byte
 * signature (5.2); then chunks of a 4-byte big-endian length at most
 * 2^31 - 1, a 4-byte type of ASCII letters, the data and a CRC-32 of type
 * and data (5.3; the CRC of ISO 3309 / ITU-T V.42, Annex D); IHDR first
 * with 13 bytes and a non-zero width and height (11.2.2); and IEND, empty,
 * as the last chunk, ending the file (11.2.5). Every CRC is checked, so a
 * file cut or overwritten inside a chunk is found too. */
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/plot_internal.h"

static uint32_t be32(const unsigned char *p)
{
  return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | (uint32_t)p[3];
}

/* CRC-32 of the PNG specification, Annex D (reflected polynomial
 * 0xedb88320), bit by bit: a figure is at most a few hundred kB, so no
 * table is worth keeping. */
static uint32_t crc32_png(const unsigned char *p, size_t n)
{
  uint32_t c = 0xffffffffu;
  for (size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k)
      c = c & 1u ? 0xedb88320u ^ (c >> 1) : c >> 1;
  }
  return c ^ 0xffffffffu;
}

static int is_chunk_type(const unsigned char *t)
{
  for (int i = 0; i < 4; ++i)
    if (!((t[i] >= 'A' && t[i] <= 'Z') || (t[i] >= 'a' && t[i] <= 'z')))
      return 0;
  return 1;
}

/* NULL if data[0..n) is a complete PNG, else what is wrong with it. */
static const char *png_problem(const unsigned char *data, size_t n)
{
  static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (n == 0 || !data)
    return "the file is empty";
  if (n < sizeof signature || memcmp(data, signature, sizeof signature) != 0)
    return "no PNG signature";
  size_t at = sizeof signature;
  for (int first = 1;; first = 0) {
    if (n - at < 12)
      return "the file ends inside a chunk (truncated)";
    const uint32_t len = be32(data + at);
    const unsigned char *type = data + at + 4;
    if (len > 0x7fffffffu || !is_chunk_type(type))
      return "a chunk header is damaged";
    if (n - at - 12 < len)
      return "the file ends inside a chunk (truncated)";
    if (crc32_png(type, 4 + (size_t)len) != be32(type + 4 + len))
      return "a chunk's CRC does not match its data";
    if (first && (memcmp(type, "IHDR", 4) != 0 || len != 13 || be32(type + 4) == 0 ||
                  be32(type + 8) == 0))
      return "the first chunk is not a valid IHDR";
    at += 12 + (size_t)len;
    if (memcmp(type, "IEND", 4) == 0)
      return len != 0 ? "IEND is not empty" : at != n ? "data after the IEND chunk" : NULL;
  }
}

int fb_image_read(const char *path, unsigned char **data, size_t *n, fb_err *err)
{
  *data = NULL;
  *n = 0;
  const int fd = open(path, O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
  struct stat st;
  if (fd < 0 || fstat(fd, &st) != 0) {
    const int e = errno;
    if (fd >= 0)
      close(fd);
    return fb_err_set(err, FB_EIO, "cannot read the image back: %s", strerror(e));
  }
  int rc = FB_OK;
  if (!S_ISREG(st.st_mode) || st.st_size > FB_IMAGE_MAX_BYTES)
    rc = fb_err_set(err, FB_EIO, "the image is not a regular file of at most %ld bytes",
                    FB_IMAGE_MAX_BYTES);
  else if (st.st_size > 0 && !(*data = malloc((size_t)st.st_size)))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  while (rc == FB_OK && *n < (size_t)st.st_size) {
    const ssize_t got = read(fd, *data + *n, (size_t)st.st_size - *n);
    if (got < 0 && errno == EINTR)
      continue;
    if (got <= 0) {
      rc = got < 0 ? fb_err_set(err, FB_EIO, "cannot read the image back: %s", strerror(errno))
                   : FB_OK;
      break;
    }
    *n += (size_t)got;
  }
  close(fd);
  return rc;
}

int fb_png_check(const char *path, fb_err *err)
{
  unsigned char *data = NULL;
  size_t n = 0;
  int rc = fb_image_read(path, &data, &n, err);
  const char *problem = rc == FB_OK ? png_problem(data, n) : NULL;
  if (problem)
    rc = fb_err_set(err, FB_EIO, "not a complete PNG image: %s", problem);
  free(data);
  return rc;
}
