/* SPDX-License-Identifier: BSD-3-Clause */
/* ZIP archive writer (see io/zip.h), written from PKWARE's APPNOTE.TXT,
 * .ZIP File Format Specification, version 6.3.x. Section numbers below
 * are that document's.
 *
 * Layout (4.3.6): for each member a local file header (4.3.7) and its
 * data, then the central directory headers (4.3.12) and the end of
 * central directory record (4.3.16). All integers are little-endian
 * (4.4.1.1). No data descriptor (bit 3 clear): each local header is
 * written with placeholder CRC and sizes, the data are streamed after it,
 * and the header is then rewritten in place with the final values.
 *
 * Compression: method 8, deflate (4.4.5; RFC 1951), raw deflate by zlib
 * (deflateInit2 with windowBits -15: no zlib header or trailer), at
 * zlib's default level, which APPNOTE 4.4.4 calls "normal" (flag bits 1
 * and 2 clear). A member whose deflated form would be no smaller than
 * itself is stored instead (method 0): the deflate pass is cut short as
 * soon as its output reaches the member's size, the file is truncated
 * back to the start of the data and the data are copied as they are. The
 * CRC-32 (4.4.7) is zlib's crc32().
 *
 * Every header carries: version needed to extract 20 (4.4.3.2, 2.0:
 * deflate), version made by 0x0314 (4.4.2: upper byte 3, UNIX; lower byte
 * 20, 2.0), general purpose flag bit 11 (4.4.4: names in UTF-8,
 * Appendix D), the date 1980-01-01 00:00 in MS-DOS format (4.4.6: date
 * (year - 1980) << 9 | month << 5 | day = 0x0021, time 0), and the Unix
 * mode in the upper 16 bits of the external attributes (4.4.15, with
 * version made by 3: S_IFREG | 0644 or 0755), as Info-ZIP's zip and
 * Python's zipfile read them. */
/* ftruncate and fsync. */
/* NOLINTNEXTLINE(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp): POSIX's macro */
#define _XOPEN_SOURCE 700

#include "io/zip.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
/* zlib's z_stream with a const next_in (zlib 1.2.5.2 and later). */
#define ZLIB_CONST
#include <zlib.h>

#include "core/tmpfile.h"

enum {
  LOCAL_HEADER_SIZE = 30,   /* 4.3.7, without name and extra field */
  CENTRAL_HEADER_SIZE = 46, /* 4.3.12, without name, extra field and comment */
  END_RECORD_SIZE = 22,     /* 4.3.16, without comment */
  VERSION_NEEDED = 20,
  VERSION_MADE_BY = 3 << 8 | 20,
  FLAG_UTF8 = 1 << 11,
  METHOD_STORED = 0,
  METHOD_DEFLATE = 8,
  DOS_TIME = 0,
  DOS_DATE = 1 << 5 | 1,   /* 1980 (year 0 in bits 9-15), January, the 1st */
  NAME_MAX_BYTES = 0xFFFF, /* the 2-byte name length field */
  CHUNK = 64 * 1024        /* bytes read, and deflated, at a time */
};

#define SIG_LOCAL 0x04034b50u
#define SIG_CENTRAL 0x02014b50u
#define SIG_END 0x06054b50u
/* Failures that are no errno value (errno values are positive and small;
 * a read's are returned negated, -errno). */
#define SRC_CHANGED (-0x10000) /* a file changed while it was read */
#define ZLIB_FAILED (-0x10001) /* deflate refused its own stream */
#define MODE_FILE 0100644u
#define MODE_EXEC 0100755u

/* One member as the central directory describes it. */
typedef struct zip_entry {
  char *name;
  size_t name_len;
  uint32_t crc, csize, usize, offset, mode;
  uint16_t method;
} zip_entry;

struct fb_zip {
  char *path;       /* destination */
  char *tmp_path;   /* the temporary file beside it */
  int fd;           /* tmp_path, open for writing; -1 once closed */
  int broken;       /* a failed member could not be rolled back */
  uint64_t offset;  /* bytes written so far: where the next member goes */
  uint64_t cd_size; /* the central directory's size for the entries so far */
  zip_entry *entries;
  size_t nentries, cap;
  size_t *slots; /* open-addressing set of names: entry index + 1, 0 empty */
  size_t nslots; /* a power of two, more than twice nentries */
  z_stream zs;
  int zs_ready;
  unsigned char *in, *out; /* CHUNK bytes each */
};

/* Where a member's bytes come from: memory, or a file read in chunks. */
typedef struct zip_src {
  const unsigned char *data; /* memory; NULL for a file */
  size_t size;               /* the whole, as known before reading */
  size_t pos;
  int fd; /* the file; -1 for memory */
  const char *path;
  unsigned char *buf; /* CHUNK bytes for a file's reads */
} zip_src;

static void put16(unsigned char *p, unsigned v)
{
  p[0] = (unsigned char)(v & 0xFFu);
  p[1] = (unsigned char)(v >> 8 & 0xFFu);
}

static void put32(unsigned char *p, uint32_t v)
{
  p[0] = (unsigned char)(v & 0xFFu);
  p[1] = (unsigned char)(v >> 8 & 0xFFu);
  p[2] = (unsigned char)(v >> 16 & 0xFFu);
  p[3] = (unsigned char)(v >> 24 & 0xFFu);
}

/* Writes all n bytes of p to fd at its offset, through short writes and
 * EINTR. Returns 0 or an errno value (EIO for a write that wrote nothing). */
static int write_all(int fd, const void *p, size_t n)
{
  const unsigned char *b = p;
  while (n > 0) {
    const ssize_t w = write(fd, b, n);
    if (w < 0 && errno == EINTR)
      continue;
    if (w <= 0)
      return w < 0 ? errno : EIO;
    b += w;
    n -= (size_t)w;
  }
  return 0;
}

/* write_all at offset off, leaving fd's offset as it was. */
static int pwrite_all(int fd, const void *p, size_t n, off_t off)
{
  const unsigned char *b = p;
  while (n > 0) {
    const ssize_t w = pwrite(fd, b, n, off);
    if (w < 0 && errno == EINTR)
      continue;
    if (w <= 0)
      return w < 0 ? errno : EIO;
    b += w;
    n -= (size_t)w;
    off += w;
  }
  return 0;
}

/* 1 if name[0..n) is well-formed UTF-8 (RFC 3629: no overlong forms, no
 * surrogates, nothing above U+10FFFF). */
static int is_utf8(const unsigned char *s, size_t n)
{
  size_t i = 0;
  while (i < n) {
    const unsigned c = s[i];
    size_t len;
    unsigned lo = 0x80, hi = 0xBF;
    if (c < 0x80) {
      ++i;
      continue;
    }
    if (c >= 0xC2 && c <= 0xDF) {
      len = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
      len = 3;
      if (c == 0xE0)
        lo = 0xA0;
      else if (c == 0xED)
        hi = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
      len = 4;
      if (c == 0xF0)
        lo = 0x90;
      else if (c == 0xF4)
        hi = 0x8F;
    } else {
      return 0;
    }
    if (n - i < len || s[i + 1] < lo || s[i + 1] > hi)
      return 0;
    for (size_t k = 2; k < len; ++k)
      if (s[i + k] < 0x80 || s[i + k] > 0xBF)
        return 0;
    i += len;
  }
  return 1;
}

/* NULL if name is an acceptable member name, else what is wrong with it. */
static const char *name_problem(const char *name)
{
  if (!name || !*name)
    return "an empty name";
  const size_t n = strlen(name);
  if (n > NAME_MAX_BYTES)
    return "a name longer than 65535 bytes";
  if (name[0] == '/')
    return "an absolute path (leading '/')";
  if (strchr(name, '\\'))
    return "a backslash in the name (the separator is '/')";
  if (!is_utf8((const unsigned char *)name, n))
    return "a name that is not valid UTF-8";
  for (const char *c = name;;) {
    const char *end = strchr(c, '/');
    const size_t len = end ? (size_t)(end - c) : strlen(c);
    if (len == 0)
      return "an empty path component ('//' or a trailing '/')";
    if (len == 2 && c[0] == '.' && c[1] == '.')
      return "a '..' path component";
    if (len == 1 && c[0] == '.')
      return "a '.' path component";
    if (!end)
      return NULL;
    c = end + 1;
  }
}

/* FNV-1a (Fowler, Noll, Vo) of s[0..n). */
static size_t name_hash(const char *s, size_t n)
{
  uint64_t h = 0xcbf29ce484222325ULL;
  for (size_t i = 0; i < n; ++i) {
    h ^= (unsigned char)s[i];
    h *= 0x100000001b3ULL;
  }
  return (size_t)h;
}

/* The slot of name in z's set: the one holding it, or the empty one
 * where it would go. */
static size_t name_slot(const fb_zip *z, const char *name, size_t n)
{
  size_t i = name_hash(name, n) & (z->nslots - 1);
  while (z->slots[i]) {
    const zip_entry *e = &z->entries[z->slots[i] - 1];
    if (e->name_len == n && memcmp(e->name, name, n) == 0)
      return i;
    i = (i + 1) & (z->nslots - 1);
  }
  return i;
}

/* Room for one more entry in z->entries and its set. Returns FB_OK or
 * FB_ENOMEM; z is unchanged but for capacity. */
static int reserve_entry(fb_zip *z, const char *name, fb_err *err)
{
  if (z->nentries == z->cap) {
    const size_t cap = z->cap ? 2 * z->cap : 16;
    zip_entry *grown = realloc(z->entries, cap * sizeof *grown);
    if (!grown)
      return fb_err_set(err, FB_ENOMEM, "%s: %s: out of memory", z->path, name),
             fb_err_set_key(err, "%s", name), FB_ENOMEM;
    z->entries = grown;
    z->cap = cap;
  }
  if (2 * (z->nentries + 1) < z->nslots)
    return FB_OK;
  const size_t nslots = z->nslots ? 2 * z->nslots : 64;
  size_t *slots = calloc(nslots, sizeof *slots);
  if (!slots)
    return fb_err_set(err, FB_ENOMEM, "%s: %s: out of memory", z->path, name),
           fb_err_set_key(err, "%s", name), FB_ENOMEM;
  free(z->slots);
  z->slots = slots;
  z->nslots = nslots;
  for (size_t k = 0; k < z->nentries; ++k) {
    const zip_entry *e = &z->entries[k];
    slots[name_slot(z, e->name, e->name_len)] = k + 1;
  }
  return FB_OK;
}

/* Closes and removes the temporary file (if still there) and frees z. */
static void zip_destroy(fb_zip *z)
{
  if (z->fd >= 0)
    close(z->fd);
  if (z->tmp_path)
    remove(z->tmp_path);
  if (z->zs_ready)
    deflateEnd(&z->zs);
  for (size_t k = 0; k < z->nentries; ++k)
    free(z->entries[k].name);
  free(z->entries);
  free(z->slots);
  free(z->in);
  free(z->out);
  free(z->tmp_path);
  free(z->path);
  free(z);
}

/* Contract: see io/zip.h. On failure nothing is left on disk or in
 * memory and *out is NULL. */
int fb_zip_create(const char *path, fb_zip **out, fb_err *err)
{
  *out = NULL;
  if (!path || !*path)
    return fb_err_set(err, FB_EINVAL, "archive: empty path");
  struct stat st;
  if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISLNK(st.st_mode))
    return fb_err_set(err, FB_EINVAL, "%s: cannot write an archive there: %s", path,
                      S_ISDIR(st.st_mode) ? "it is a directory" : "not a regular file");
  fb_zip *z = calloc(1, sizeof *z);
  if (!z)
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  z->fd = -1;
  const size_t n = strlen(path) + 1;
  z->path = malloc(n);
  z->in = malloc(CHUNK);
  z->out = malloc(CHUNK);
  if (!z->path || !z->in || !z->out) {
    zip_destroy(z);
    return fb_err_set(err, FB_ENOMEM, "%s: out of memory", path);
  }
  memcpy(z->path, path, n);
  /* Raw deflate (windowBits -15), zlib's defaults otherwise: level 6,
   * memLevel 8. The stream is reset, not remade, for each member. */
  const int zrc =
      deflateInit2(&z->zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY);
  if (zrc != Z_OK) {
    zip_destroy(z);
    return fb_err_set(err, zrc == Z_MEM_ERROR ? FB_ENOMEM : FB_EIO,
                      "%s: cannot start deflate (zlib %s)", path, zlibVersion());
  }
  z->zs_ready = 1;
  const int e = fb_tmpfile_create(path, &z->fd, &z->tmp_path);
  if (e != 0) {
    zip_destroy(z);
    return fb_err_set(err, e == ENOMEM ? FB_ENOMEM : FB_EIO, "%s: cannot create file: %s", path,
                      strerror(e));
  }
  *out = z;
  return FB_OK;
}

/* The next piece of src: *p and *n (0 at its end). A file that holds
 * more than src->size bytes is an error. Returns 0, SRC_CHANGED for such
 * a file, or an errno value. */
static int src_next(zip_src *src, const unsigned char **p, size_t *n)
{
  if (src->fd < 0) {
    const size_t left = src->size - src->pos;
    *n = left < CHUNK ? left : CHUNK;
    *p = src->data + src->pos;
    src->pos += *n;
    return 0;
  }
  for (;;) {
    const ssize_t r = read(src->fd, src->buf, CHUNK);
    if (r < 0 && errno == EINTR)
      continue;
    if (r < 0)
      return errno;
    if ((size_t)r > src->size - src->pos)
      return SRC_CHANGED;
    *p = src->buf;
    *n = (size_t)r;
    src->pos += (size_t)r;
    return 0;
  }
}

/* Back to src's first byte. Returns 0 or an errno value. */
static int src_rewind(zip_src *src)
{
  src->pos = 0;
  if (src->fd >= 0 && lseek(src->fd, 0, SEEK_SET) != 0)
    return errno;
  return 0;
}

/* Records the failure of member name: FB_EIO (FB_ENOMEM) with the reason e: an
 * errno value of a write, -errno of a read, SRC_CHANGED or ZLIB_FAILED. */
static void member_io_error(const fb_zip *z, const char *name, const zip_src *src, int e,
                            fb_err *err)
{
  if (e == SRC_CHANGED)
    fb_err_set(err, FB_EIO, "%s: %s: '%s' changed while it was read", z->path, name, src->path);
  else if (e == ZLIB_FAILED)
    fb_err_set(err, FB_EIO, "%s: %s: deflate failed (zlib %s)", z->path, name, zlibVersion());
  else if (e < 0)
    fb_err_set(err, FB_EIO, "%s: %s: cannot read '%s': %s", z->path, name, src->path,
               strerror(-e));
  else if (e == ENOMEM)
    fb_err_set(err, FB_ENOMEM, "%s: %s: out of memory", z->path, name);
  else
    fb_err_set(err, FB_EIO, "%s: %s: write failed: %s", z->path, name, strerror(e));
  fb_err_set_key(err, "%s", name);
}

/* Read errors are returned negated (-errno), write errors as they are,
 * so that the message says which side failed. */
static int src_next_tagged(zip_src *src, const unsigned char **p, size_t *n)
{
  const int e = src_next(src, p, n);
  return e == 0 || e == SRC_CHANGED ? e : -e;
}

/* The deflate pass: streams src through deflate into z's file. *csize is
 * what it wrote, *crc the CRC-32 of what it read; *stored is set (and
 * the pass cut short) as soon as the output reaches src->size, where
 * storing is no worse. Returns 0, an errno value (negated for a read),
 * SRC_CHANGED or ZLIB_FAILED. */
static int deflate_pass(fb_zip *z, zip_src *src, uint32_t *crc, uint64_t *csize, int *stored)
{
  *stored = 0;
  *csize = 0;
  uLong c = crc32(0L, Z_NULL, 0);
  if (deflateReset(&z->zs) != Z_OK)
    return ZLIB_FAILED;
  int flush = Z_NO_FLUSH;
  while (flush != Z_FINISH) {
    const unsigned char *p = NULL;
    size_t n = 0;
    const int e = src_next_tagged(src, &p, &n);
    if (e)
      return e;
    if (n == 0) /* a file's end is its read of nothing: one that grew is found */
      flush = Z_FINISH;
    c = crc32(c, p, (uInt)n);
    z->zs.next_in = p;
    z->zs.avail_in = (uInt)n;
    int zrc;
    do {
      z->zs.next_out = z->out;
      z->zs.avail_out = CHUNK;
      zrc = deflate(&z->zs, flush);
      if (zrc == Z_STREAM_ERROR)
        return ZLIB_FAILED;
      const size_t have = CHUNK - z->zs.avail_out;
      *csize += have;
      if (*csize >= src->size) {
        *stored = 1;
        return 0;
      }
      const int we = write_all(z->fd, z->out, have);
      if (we)
        return we;
    } while (z->zs.avail_out == 0 || (flush == Z_FINISH && zrc != Z_STREAM_END));
  }
  /* A file shorter than it was when its size was taken. */
  if (src->pos != src->size)
    return SRC_CHANGED;
  *crc = (uint32_t)c;
  return 0;
}

/* The stored pass: copies src as it is into z's file; *crc its CRC-32.
 * Returns 0, an errno value (negated for a read) or SRC_CHANGED. */
static int store_pass(fb_zip *z, zip_src *src, uint32_t *crc)
{
  uLong c = crc32(0L, Z_NULL, 0);
  for (;;) {
    const unsigned char *p = NULL;
    size_t n = 0;
    const int e = src_next_tagged(src, &p, &n);
    if (e)
      return e;
    if (n == 0)
      break;
    c = crc32(c, p, (uInt)n);
    const int we = write_all(z->fd, p, n);
    if (we)
      return we;
  }
  if (src->pos != src->size)
    return SRC_CHANGED;
  *crc = (uint32_t)c;
  return 0;
}

/* The local file header of 4.3.7 into h (LOCAL_HEADER_SIZE bytes). */
static void local_header(unsigned char *h, const zip_entry *e)
{
  put32(h, SIG_LOCAL);
  put16(h + 4, VERSION_NEEDED);
  put16(h + 6, FLAG_UTF8);
  put16(h + 8, e->method);
  put16(h + 10, DOS_TIME);
  put16(h + 12, DOS_DATE);
  put32(h + 14, e->crc);
  put32(h + 18, e->csize);
  put32(h + 22, e->usize);
  put16(h + 26, (unsigned)e->name_len);
  put16(h + 28, 0); /* no extra field */
}

/* Writes the member name from src at z->offset: header, data, header
 * rewritten with the final CRC and sizes. Fills *e (but for its name).
 * Returns 0 or a failure as member_io_error takes it; the file may then
 * hold part of the member. */
static int write_member(fb_zip *z, const char *name, zip_src *src, zip_entry *e)
{
  unsigned char h[LOCAL_HEADER_SIZE];
  e->offset = (uint32_t)z->offset;
  e->usize = (uint32_t)src->size;
  e->method = METHOD_STORED;
  e->crc = 0;
  e->csize = 0;
  local_header(h, e);
  int rc = write_all(z->fd, h, sizeof h);
  if (!rc)
    rc = write_all(z->fd, name, e->name_len);
  if (rc)
    return rc;
  const uint64_t data_start = z->offset + LOCAL_HEADER_SIZE + e->name_len;
  int stored = 1;
  uint64_t csize = 0;
  if (src->size > 0) {
    rc = deflate_pass(z, src, &e->crc, &csize, &stored);
    if (rc)
      return rc;
  }
  if (stored && src->size > 0) {
    if (ftruncate(z->fd, (off_t)data_start) != 0 ||
        lseek(z->fd, (off_t)data_start, SEEK_SET) != (off_t)data_start)
      return errno;
    rc = src_rewind(src);
    if (rc)
      return -rc;
    rc = store_pass(z, src, &e->crc);
    if (rc)
      return rc;
    csize = src->size;
  }
  e->method = stored ? METHOD_STORED : METHOD_DEFLATE;
  e->csize = (uint32_t)csize;
  local_header(h, e);
  rc = pwrite_all(z->fd, h, sizeof h, (off_t)z->offset);
  if (rc)
    return rc;
  z->offset = data_start + csize;
  return 0;
}

/* Checks name and the limits, then writes the member from src. On failure
 * the archive is as before (rolled back), or marked broken. */
static int add_member(fb_zip *z, const char *name, zip_src *src, int executable, fb_err *err)
{
  if (!z)
    return fb_err_set(err, FB_EINVAL, "archive: no archive");
  if (z->broken)
    return fb_err_set(err, FB_EIO, "%s: an earlier write failed and could not be undone",
                      z->path);
  const char *problem = name_problem(name);
  if (problem)
    return fb_err_set(err, FB_EINVAL, "%s: member '%s': %s", z->path, name ? name : "",
                      problem),
           fb_err_set_key(err, "%s", name ? name : ""), FB_EINVAL;
  const size_t n = strlen(name);
  if (z->nslots && z->slots[name_slot(z, name, n)])
    return fb_err_set(err, FB_EINVAL, "%s: member '%s' is already in the archive", z->path,
                      name),
           fb_err_set_key(err, "%s", name), FB_EINVAL;
  if (z->nentries >= FB_ZIP_MAX_ENTRIES)
    return fb_err_set(err, FB_EINVAL,
                      "%s: member '%s': an archive holds at most %u members without ZIP64",
                      z->path, name, FB_ZIP_MAX_ENTRIES),
           fb_err_set_key(err, "%s", name), FB_EINVAL;
  if (src->size > FB_ZIP_MAX_SIZE)
    return fb_err_set(err, FB_EINVAL, "%s: member '%s': %zu bytes, more than %u without ZIP64",
                      z->path, name, src->size, FB_ZIP_MAX_SIZE),
           fb_err_set_key(err, "%s", name), FB_EINVAL;
  /* The archive's size once finished, with this member at its largest
   * (stored): local header, data, and the central directory with it. */
  const uint64_t total = z->offset + LOCAL_HEADER_SIZE + n + src->size + z->cd_size +
                         CENTRAL_HEADER_SIZE + n + END_RECORD_SIZE;
  if (total > FB_ZIP_MAX_SIZE)
    return fb_err_set(err, FB_EINVAL,
                      "%s: member '%s': the archive would grow over %u bytes without ZIP64",
                      z->path, name, FB_ZIP_MAX_SIZE),
           fb_err_set_key(err, "%s", name), FB_EINVAL;
  int rc = reserve_entry(z, name, err);
  if (rc)
    return rc;
  zip_entry e = {.name = malloc(n + 1), .name_len = n};
  if (!e.name)
    return fb_err_set(err, FB_ENOMEM, "%s: %s: out of memory", z->path, name),
           fb_err_set_key(err, "%s", name), FB_ENOMEM;
  memcpy(e.name, name, n + 1);
  e.mode = executable ? MODE_EXEC : MODE_FILE;
  const uint64_t start = z->offset;
  const int we = write_member(z, name, src, &e);
  if (we) {
    free(e.name);
    const int code = we == ENOMEM ? FB_ENOMEM : FB_EIO;
    member_io_error(z, name, src, we, err);
    z->offset = start;
    if (ftruncate(z->fd, (off_t)start) != 0 ||
        lseek(z->fd, (off_t)start, SEEK_SET) != (off_t)start)
      z->broken = 1;
    return code;
  }
  z->entries[z->nentries] = e;
  z->slots[name_slot(z, name, n)] = ++z->nentries;
  z->cd_size += CENTRAL_HEADER_SIZE + n;
  return FB_OK;
}

/* Contract: see io/zip.h. */
int fb_zip_add(fb_zip *z, const char *name, const void *data, size_t size, int executable,
               fb_err *err)
{
  if (size > 0 && !data)
    return fb_err_set(err, FB_EINVAL, "archive: member '%s': no data", name ? name : ""),
           fb_err_set_key(err, "%s", name ? name : ""), FB_EINVAL;
  zip_src src = {.data = data, .size = size, .fd = -1};
  return add_member(z, name, &src, executable, err);
}

/* Contract: see io/zip.h. The source file is always closed before
 * return. */
int fb_zip_add_file(fb_zip *z, const char *name, const char *src_path, int executable,
                    fb_err *err)
{
  if (!z)
    return fb_err_set(err, FB_EINVAL, "archive: no archive");
  if (!src_path || !*src_path)
    return fb_err_set(err, FB_EINVAL, "%s: member '%s': no source file", z->path,
                      name ? name : ""),
           fb_err_set_key(err, "%s", name ? name : ""), FB_EINVAL;
  const int fd = open(src_path, O_RDONLY | O_CLOEXEC);
  struct stat st;
  memset(&st, 0, sizeof st);
  const char *why = NULL;
  if (fd < 0 || fstat(fd, &st) != 0)
    why = strerror(errno);
  else if (!S_ISREG(st.st_mode))
    why = S_ISDIR(st.st_mode) ? "it is a directory" : "not a regular file";
  if (why) {
    fb_err_set(err, FB_EIO, "%s: member '%s': cannot read '%s': %s", z->path, name ? name : "",
               src_path, why);
    fb_err_set_key(err, "%s", name ? name : "");
    if (fd >= 0)
      close(fd);
    return FB_EIO;
  }
  int rc;
  if ((uint64_t)st.st_size > FB_ZIP_MAX_SIZE) {
    rc = fb_err_set(err, FB_EINVAL,
                    "%s: member '%s': '%s' has %lld bytes, more than %u without ZIP64", z->path,
                    name ? name : "", src_path, (long long)st.st_size, FB_ZIP_MAX_SIZE);
    fb_err_set_key(err, "%s", name ? name : "");
  } else {
    zip_src src = {.size = (size_t)st.st_size, .fd = fd, .path = src_path, .buf = z->in};
    rc = add_member(z, name, &src, executable, err);
  }
  close(fd);
  return rc;
}

/* The central directory header of 4.3.12 for e into h
 * (CENTRAL_HEADER_SIZE bytes, then the name). */
static void central_header(unsigned char *h, const zip_entry *e)
{
  put32(h, SIG_CENTRAL);
  put16(h + 4, VERSION_MADE_BY);
  put16(h + 6, VERSION_NEEDED);
  put16(h + 8, FLAG_UTF8);
  put16(h + 10, e->method);
  put16(h + 12, DOS_TIME);
  put16(h + 14, DOS_DATE);
  put32(h + 16, e->crc);
  put32(h + 20, e->csize);
  put32(h + 24, e->usize);
  put16(h + 28, (unsigned)e->name_len);
  put16(h + 30, 0);             /* extra field length */
  put16(h + 32, 0);             /* comment length */
  put16(h + 34, 0);             /* disk number start */
  put16(h + 36, 0);             /* internal attributes: binary */
  put32(h + 38, e->mode << 16); /* external attributes: the Unix mode */
  put32(h + 42, e->offset);
  memcpy(h + CENTRAL_HEADER_SIZE, e->name, e->name_len);
}

/* The central directory and its end record (4.3.16) in fresh memory,
 * *n bytes; NULL when out of memory. */
static unsigned char *central_directory(const fb_zip *z, size_t *n)
{
  *n = (size_t)z->cd_size + END_RECORD_SIZE;
  unsigned char *cd = malloc(*n);
  if (!cd)
    return NULL;
  unsigned char *p = cd;
  for (size_t k = 0; k < z->nentries; ++k) {
    central_header(p, &z->entries[k]);
    p += CENTRAL_HEADER_SIZE + z->entries[k].name_len;
  }
  put32(p, SIG_END);
  put16(p + 4, 0);                      /* number of this disk */
  put16(p + 6, 0);                      /* disk of the central directory */
  put16(p + 8, (unsigned)z->nentries);  /* entries on this disk */
  put16(p + 10, (unsigned)z->nentries); /* entries in all */
  put32(p + 12, (uint32_t)z->cd_size);  /* size of the central directory */
  put32(p + 16, (uint32_t)z->offset);   /* its offset */
  put16(p + 20, 0);                     /* comment length */
  return cd;
}

/* Contract: see io/zip.h. */
int fb_zip_commit(fb_zip *z, fb_err *err)
{
  if (!z)
    return fb_err_set(err, FB_EINVAL, "archive: no archive to commit");
  if (z->broken) {
    const int rc =
        fb_err_set(err, FB_EIO, "%s: an earlier write failed and could not be undone", z->path);
    zip_destroy(z);
    return rc;
  }
  size_t n = 0;
  unsigned char *cd = central_directory(z, &n);
  if (!cd) {
    const int rc = fb_err_set(err, FB_ENOMEM, "%s: out of memory", z->path);
    zip_destroy(z);
    return rc;
  }
  int e = write_all(z->fd, cd, n);
  free(cd);
  if (!e && fsync(z->fd) != 0)
    e = errno;
  const int fd = z->fd;
  z->fd = -1;
  if (close(fd) != 0 && !e)
    e = errno;
  int rc = FB_OK;
  if (e)
    rc = fb_err_set(err, FB_EIO, "%s: write failed: %s", z->path, strerror(e));
  else if (rename(z->tmp_path, z->path) != 0)
    rc = fb_err_set(err, FB_EIO, "%s: cannot move '%s' into place: %s", z->path, z->tmp_path,
                    strerror(errno));
  if (rc == FB_OK) {
    free(z->tmp_path); /* renamed: nothing to remove */
    z->tmp_path = NULL;
  }
  zip_destroy(z);
  return rc;
}

/* Contract: see io/zip.h. */
void fb_zip_free(fb_zip **z)
{
  if (!z || !*z)
    return;
  zip_destroy(*z);
  *z = NULL;
}
