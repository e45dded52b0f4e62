/* SPDX-License-Identifier: BSD-3-Clause */
/* The ZIP archive writer (io/zip.h): archives read back by a minimal
 * reader of this test's own (PKWARE APPNOTE.TXT 4.3.7, 4.3.12, 4.3.16,
 * inflated with zlib), by Python's zipfile and by Info-ZIP's unzip when
 * they are installed; names and sizes refused; an abandoned archive leaves
 * nothing behind; the same members give the same bytes. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

#include "check.h"
#include "io/zip.h"
#include "tmpdir.h"

/* ---- test data ---- */

static uint64_t rng_state = 0x2545F4914F6CDD1DULL;

static unsigned char next_byte(void)
{
  /* xorshift64 (Marsaglia 2003) */
  rng_state ^= rng_state << 13;
  rng_state ^= rng_state >> 7;
  rng_state ^= rng_state << 17;
  return (unsigned char)(rng_state >> 32);
}

static unsigned char *random_bytes(size_t n)
{
  unsigned char *p = malloc(n);
  if (!p)
    abort();
  for (size_t i = 0; i < n; ++i)
    p[i] = next_byte();
  return p;
}

/* n bytes of text lines such as a CSV of results: compressible. */
static unsigned char *text_bytes(size_t n)
{
  unsigned char *p = malloc(n + 64);
  if (!p)
    abort();
  size_t at = 0;
  for (unsigned i = 0; at < n; ++i)
    at += (size_t)snprintf((char *)p + at, 64, "%u,%.4f,%.4f,body.z\n", i, i * 0.001,
                           (double)(i % 97) * 0.25);
  return p;
}

static double seconds_now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int write_file(const char *path, const void *data, size_t n)
{
  FILE *f = fopen(path, "wb");
  if (!f)
    return -1;
  const int ok = fwrite(data, 1, n, f) == n;
  return fclose(f) == 0 && ok ? 0 : -1;
}

static unsigned char *read_file(const char *path, size_t *n)
{
  *n = 0;
  FILE *f = fopen(path, "rb");
  if (!f)
    return NULL;
  size_t cap = 1 << 16, len = 0;
  unsigned char *p = malloc(cap);
  size_t r;
  while (p && (r = fread(p + len, 1, cap - len, f)) > 0) {
    len += r;
    if (len == cap) {
      unsigned char *g = realloc(p, cap *= 2);
      if (!g)
        free(p);
      p = g;
    }
  }
  fclose(f);
  *n = len;
  return p;
}

/* ---- a minimal reader, from APPNOTE.TXT ---- */

typedef struct member {
  char name[256];
  unsigned method, flags, version_made_by, version_needed, time, date;
  uint32_t crc, csize, usize, external;
  unsigned char *data; /* inflated or copied: usize bytes */
} member;

typedef struct archive {
  member *m;
  size_t n;
} archive;

static unsigned get16(const unsigned char *p)
{
  return (unsigned)p[0] | (unsigned)p[1] << 8;
}

static uint32_t get32(const unsigned char *p)
{
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static void archive_free(archive *a)
{
  for (size_t i = 0; i < a->n; ++i)
    free(a->m[i].data);
  free(a->m);
  a->m = NULL;
  a->n = 0;
}

/* Inflates (raw deflate) src[0..csize) into dst[0..usize): 0 when it
 * ends exactly there. */
static int inflate_exact(const unsigned char *src, uint32_t csize, unsigned char *dst,
                         uint32_t usize)
{
  z_stream s;
  memset(&s, 0, sizeof s);
  if (inflateInit2(&s, -15) != Z_OK)
    return -1;
  unsigned char spare;
  s.next_in = (Bytef *)(uintptr_t)src;
  s.avail_in = csize;
  s.next_out = usize ? dst : &spare;
  s.avail_out = usize;
  const int rc = inflate(&s, Z_FINISH);
  const int ok = rc == Z_STREAM_END && s.avail_in == 0 && s.total_out == usize;
  inflateEnd(&s);
  return ok ? 0 : -1;
}

/* Reads the archive at path: every check of the format is a CHECK; 0 if
 * it could be walked to the end. */
static int archive_read(const char *path, archive *a)
{
  a->m = NULL;
  a->n = 0;
  size_t size = 0;
  unsigned char *z = read_file(path, &size);
  if (!z || size < 22) {
    free(z);
    CHECK(!"archive readable");
    return -1;
  }
  /* 4.3.16: the end record, without a comment, is the last 22 bytes. */
  const unsigned char *end = z + size - 22;
  int ok = 1;
  CHECK(get32(end) == 0x06054b50u);
  CHECK(get16(end + 4) == 0 && get16(end + 6) == 0);
  const unsigned count = get16(end + 10);
  CHECK(get16(end + 8) == count);
  const uint32_t cd_size = get32(end + 12), cd_off = get32(end + 16);
  CHECK(get16(end + 20) == 0);
  CHECK((uint64_t)cd_off + cd_size == size - 22);
  if ((uint64_t)cd_off + cd_size != size - 22)
    ok = 0;
  a->m = calloc(count ? count : 1, sizeof *a->m);
  if (!a->m)
    abort();
  size_t at = cd_off, local_end = 0;
  for (unsigned k = 0; ok && k < count; ++k) {
    if (at + 46 > size - 22 || get32(z + at) != 0x02014b50u) {
      CHECK(!"central directory header");
      ok = 0;
      break;
    }
    /* 4.3.12 */
    const unsigned char *c = z + at;
    member *m = &a->m[a->n];
    m->version_made_by = get16(c + 4);
    m->version_needed = get16(c + 6);
    m->flags = get16(c + 8);
    m->method = get16(c + 10);
    m->time = get16(c + 12);
    m->date = get16(c + 14);
    m->crc = get32(c + 16);
    m->csize = get32(c + 20);
    m->usize = get32(c + 24);
    const unsigned name_len = get16(c + 28), extra_len = get16(c + 30),
                   comment_len = get16(c + 32);
    CHECK(extra_len == 0 && comment_len == 0);
    CHECK(get16(c + 34) == 0 && get16(c + 36) == 0);
    m->external = get32(c + 38);
    const uint32_t off = get32(c + 42);
    if (name_len >= sizeof m->name || at + 46 + name_len > size) {
      CHECK(!"name fits");
      ok = 0;
      break;
    }
    memcpy(m->name, c + 46, name_len);
    at += 46 + name_len + extra_len + comment_len;
    /* 4.3.7: the local header agrees with the central one. */
    const unsigned char *l = z + off;
    if ((uint64_t)off + 30 + name_len > cd_off || get32(l) != 0x04034b50u) {
      CHECK(!"local header");
      ok = 0;
      break;
    }
    CHECK(off == local_end); /* members back to back from offset 0 */
    CHECK(get16(l + 4) == m->version_needed && get16(l + 6) == m->flags);
    CHECK(get16(l + 8) == m->method && get16(l + 10) == m->time && get16(l + 12) == m->date);
    CHECK(get32(l + 14) == m->crc && get32(l + 18) == m->csize && get32(l + 22) == m->usize);
    CHECK(get16(l + 26) == name_len && get16(l + 28) == 0);
    CHECK(memcmp(l + 30, m->name, name_len) == 0);
    const size_t data_off = (size_t)off + 30 + name_len;
    if (data_off + m->csize > cd_off) {
      CHECK(!"member data inside the archive");
      ok = 0;
      break;
    }
    local_end = data_off + m->csize;
    m->data = malloc(m->usize ? m->usize : 1);
    if (!m->data)
      abort();
    ++a->n;
    if (m->method == 0) {
      CHECK(m->csize == m->usize);
      memcpy(m->data, z + data_off, m->usize);
    } else {
      CHECK(m->method == 8);
      CHECK(inflate_exact(z + data_off, m->csize, m->data, m->usize) == 0);
    }
    CHECK(crc32(crc32(0L, Z_NULL, 0), m->data, m->usize) == m->crc);
    /* What every member of ours has. */
    CHECK(m->version_made_by == (3u << 8 | 20u));
    CHECK(m->version_needed == 20);
    CHECK(m->flags == 0x0800);
    CHECK(m->time == 0 && m->date == (1u << 5 | 1u));
  }
  CHECK(local_end == cd_off);
  CHECK(at == (size_t)cd_off + cd_size);
  CHECK(a->n == count);
  free(z);
  return ok ? 0 : -1;
}

static const member *find(const archive *a, const char *name)
{
  for (size_t i = 0; i < a->n; ++i)
    if (!strcmp(a->m[i].name, name))
      return &a->m[i];
  return NULL;
}

/* ---- external readers ---- */

static int have_program(const char *name)
{
  char cmd[128];
  snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", name);
  return system(cmd) == 0;
}

static int run(const char *fmt, const char *a, const char *b)
{
  char cmd[1024];
  snprintf(cmd, sizeof cmd, fmt, a, b);
  return system(cmd);
}

/* ---- the tests ---- */

enum { BIG = 3 * 1024 * 1024, RANDOM = 1024 * 1024, DISK = 200 * 1000, DISK_RANDOM = 300000 };

typedef struct data_set {
  unsigned char *big, *random, *disk, *disk_random;
  char disk_path[TEST_PATH_MAX], disk_random_path[TEST_PATH_MAX];
} data_set;

static const char XML[] = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                          "<fmiModelDescription fmiVersion=\"3.0\" modelName=\"apc\"/>\n";
static const unsigned char SO[] = {0x7f, 'E', 'L', 'F', 2, 1, 1,    0, 0, 0, 0, 0,
                                   0,    0,   0,   0,   3, 0, 0x3e, 0, 1, 0, 0, 0};

/* The members of the test archive, into path. Times the whole and the
 * 3 MB member into *t_all and *t_big. */
static int write_archive(const char *path, const data_set *d, double *t_all, double *t_big)
{
  fb_err err;
  fb_err_clear(&err);
  fb_zip *z = NULL;
  const double t0 = seconds_now();
  int rc = fb_zip_create(path, &z, &err);
  CHECK(rc == FB_OK && z);
  if (rc)
    return rc;
  CHECK(fb_zip_add(z, "modelDescription.xml", XML, strlen(XML), 0, &err) == FB_OK);
  CHECK(fb_zip_add(z, "resources/empty.txt", NULL, 0, 0, &err) == FB_OK);
  const double t1 = seconds_now();
  CHECK(fb_zip_add(z, "resources/big.csv", d->big, BIG, 0, &err) == FB_OK);
  const double t2 = seconds_now();
  CHECK(fb_zip_add(z, "resources/random.bin", d->random, RANDOM, 0, &err) == FB_OK);
  CHECK(fb_zip_add(z, "binaries/x86_64-linux/apc.so", SO, sizeof SO, 1, &err) == FB_OK);
  CHECK(fb_zip_add_file(z, "resources/disk.csv", d->disk_path, 0, &err) == FB_OK);
  CHECK(fb_zip_add_file(z, "resources/disk_random.bin", d->disk_random_path, 0, &err) == FB_OK);
  CHECK(fb_zip_add(z, "resources/donn\xc3\xa9\x65s/\xe2\x82\xac.txt", "euro\n", 5, 0, &err) ==
        FB_OK);
  rc = fb_zip_commit(z, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "%s\n", err.msg);
  if (t_all)
    *t_all = seconds_now() - t0;
  if (t_big)
    *t_big = t2 - t1;
  return rc;
}

static void check_member(const archive *a, const char *name, const void *data, size_t n,
                         unsigned method, uint32_t mode)
{
  const member *m = find(a, name);
  CHECK(m != NULL);
  if (!m) {
    fprintf(stderr, "no member %s\n", name);
    return;
  }
  CHECK(m->usize == n);
  CHECK(m->usize == n && (n == 0 || memcmp(m->data, data, n) == 0));
  CHECK(m->method == method);
  CHECK(m->external == mode << 16);
  if (m->method != method)
    fprintf(stderr, "%s: method %u, expected %u\n", name, m->method, method);
}

static void test_members(const data_set *d)
{
  char path[TEST_PATH_MAX], again[TEST_PATH_MAX];
  test_tmp_path("model.fmu", path, sizeof path);
  test_tmp_path("model2.fmu", again, sizeof again);
  double t_all = 0, t_big = 0;
  if (write_archive(path, d, &t_all, &t_big))
    return;
  archive a;
  CHECK(archive_read(path, &a) == 0);
  CHECK(a.n == 8);
  check_member(&a, "modelDescription.xml", XML, strlen(XML), 8, 0100644);
  check_member(&a, "resources/empty.txt", "", 0, 0, 0100644);
  check_member(&a, "resources/big.csv", d->big, BIG, 8, 0100644);
  check_member(&a, "resources/random.bin", d->random, RANDOM, 0, 0100644);
  check_member(&a, "binaries/x86_64-linux/apc.so", SO, sizeof SO, 8, 0100755);
  check_member(&a, "resources/disk.csv", d->disk, DISK, 8, 0100644);
  check_member(&a, "resources/disk_random.bin", d->disk_random, DISK_RANDOM, 0, 0100644);
  check_member(&a, "resources/donn\xc3\xa9\x65s/\xe2\x82\xac.txt", "euro\n", 5, 0, 0100644);
  const member *big = find(&a, "resources/big.csv");
  struct stat st;
  CHECK(stat(path, &st) == 0);
  fprintf(stderr,
          "test_zip: 3 MB text member deflated to %u bytes (%.2f%%) in %.3f s; "
          "archive of %zu members, %lld bytes, written in %.3f s\n",
          big ? big->csize : 0, big ? 100.0 * big->csize / big->usize : 0.0, t_big, a.n,
          (long long)st.st_size, t_all);
  if (big)
    CHECK(big->csize < BIG / 4);
  archive_free(&a);

  /* The same members give the same bytes. */
  if (write_archive(again, d, NULL, NULL) == FB_OK) {
    size_t n1 = 0, n2 = 0;
    unsigned char *b1 = read_file(path, &n1), *b2 = read_file(again, &n2);
    CHECK(b1 && b2 && n1 == n2 && memcmp(b1, b2, n1) == 0);
    free(b1);
    free(b2);
  }

  if (have_program("python3")) {
    CHECK(run("python3 -c 'import zipfile,sys; z=zipfile.ZipFile(sys.argv[1]); "
              "assert z.testzip() is None' '%s'%s",
              path, "") == 0);
    /* zipfile's view of the mode and the UTF-8 name. */
    CHECK(run("python3 -c 'import zipfile,sys; z=zipfile.ZipFile(sys.argv[1]); "
              "i=z.getinfo(\"binaries/x86_64-linux/apc.so\"); assert "
              "i.external_attr>>16==0o100755; "
              "assert \"resources/donn\\u00e9es/\\u20ac.txt\" in z.namelist()' '%s'%s",
              path, "") == 0);
  } else {
    fprintf(stderr, "test_zip: no python3, its zipfile check skipped\n");
  }
  if (have_program("unzip")) {
    CHECK(run("unzip -tq '%s' >/dev/null%s", path, "") == 0);
    char dir[TEST_PATH_MAX], so[TEST_PATH_MAX + 64];
    test_tmp_path("unzipped", dir, sizeof dir);
    CHECK(run("unzip -q '%s' -d '%s'", path, dir) == 0);
    snprintf(so, sizeof so, "%s/binaries/x86_64-linux/apc.so", dir);
    CHECK(stat(so, &st) == 0 && (st.st_mode & 0777) == 0755);
    snprintf(so, sizeof so, "%s/modelDescription.xml", dir);
    CHECK(stat(so, &st) == 0 && (st.st_mode & 0111) == 0);
  } else {
    fprintf(stderr, "test_zip: no unzip, its check skipped\n");
  }
}

/* Entries of dir other than "." and "..". */
static int entries_in(const char *dir)
{
  DIR *d = opendir(dir);
  if (!d)
    return -1;
  int n = 0;
  const struct dirent *e;
  while ((e = readdir(d)) != NULL)
    if (strcmp(e->d_name, ".") && strcmp(e->d_name, ".."))
      ++n;
  closedir(d);
  return n;
}

static void test_refusals(void)
{
  char dir[TEST_PATH_MAX], path[TEST_PATH_MAX + 16];
  test_tmp_path("refusals", dir, sizeof dir);
  CHECK(mkdir(dir, 0700) == 0);
  snprintf(path, sizeof path, "%s/r.fmu", dir);
  fb_err err;
  fb_err_clear(&err);
  fb_zip *z = NULL;
  CHECK(fb_zip_create(path, &z, &err) == FB_OK);
  if (!z)
    return;
  static const char *const bad[] = {
      "",         "/abs.txt", "a\\b.txt",     "a//b.txt", "a/",
      "../x",     "a/../b",   "..",           "a/./b",    ".",
      "\xff.txt", "\xc0\xaf", "\xed\xa0\x80", "\xe2\x82", "\xf4\x90\x80\x80",
      "a/b/"};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; ++i) {
    fb_err_clear(&err);
    const int rc = fb_zip_add(z, bad[i], "x", 1, 0, &err);
    CHECK(rc == FB_EINVAL);
    CHECK(err.code == FB_EINVAL);
    if (rc != FB_EINVAL)
      fprintf(stderr, "name %zu accepted\n", i);
    /* The key names the member (as fb_err_set_key escapes it). */
    if (bad[i][0] && (unsigned char)bad[i][0] < 0x80)
      CHECK(!strcmp(err.key, bad[i]));
  }
  CHECK(fb_zip_add(z, "a.txt", "one", 3, 0, &err) == FB_OK);
  /* Refused without an fb_err too. */
  CHECK(fb_zip_add(z, "../x", "x", 1, 0, NULL) == FB_EINVAL);
  CHECK(fb_zip_add(z, "a.txt", "x", 1, 0, NULL) == FB_EINVAL);
  CHECK(fb_zip_add_file(z, "b.txt", "no/such/file", 0, NULL) == FB_EIO);
  fb_err_clear(&err);
  CHECK(fb_zip_add(z, "a.txt", "two", 3, 0, &err) == FB_EINVAL);
  CHECK(!strcmp(err.key, "a.txt"));
  fb_err_clear(&err);
  CHECK(fb_zip_add_file(z, "dup.txt", "no/such/file", 0, &err) == FB_EIO);
  CHECK(!strcmp(err.key, "dup.txt"));
  CHECK(fb_zip_add_file(z, "dup.txt", dir, 0, &err) == FB_EIO); /* a directory */
  CHECK(fb_zip_add(z, "dup.txt", "ok", 2, 0, &err) == FB_OK);
  CHECK(fb_zip_add(z, "a.TXT", "three", 5, 0, &err) == FB_OK); /* names are case-sensitive */

  /* Sizes over the ZIP limit, refused before anything is read. */
#if SIZE_MAX > 0xFFFFFFFFu
  fb_err_clear(&err);
  CHECK(fb_zip_add(z, "huge.bin", "x", (size_t)0x100000000ULL, 0, &err) == FB_EINVAL);
  CHECK(!strcmp(err.key, "huge.bin"));
#endif
  char sparse[TEST_PATH_MAX + 16];
  snprintf(sparse, sizeof sparse, "%s.sparse", dir);
  const int fd = open(sparse, O_WRONLY | O_CREAT | O_TRUNC, 0600);
  CHECK(fd >= 0);
  if (fd >= 0) {
    CHECK(ftruncate(fd, (off_t)0x100000001LL) == 0);
    close(fd);
    fb_err_clear(&err);
    const double t0 = seconds_now();
    CHECK(fb_zip_add_file(z, "sparse.bin", sparse, 0, &err) == FB_EINVAL);
    CHECK(seconds_now() - t0 < 1.0); /* refused by its size, not read */
    CHECK(!strcmp(err.key, "sparse.bin"));
    unlink(sparse);
  }
  CHECK(fb_zip_commit(z, &err) == FB_OK);
  archive a;
  CHECK(archive_read(path, &a) == 0);
  CHECK(a.n == 3);
  check_member(&a, "a.txt", "one", 3, 0, 0100644);
  check_member(&a, "dup.txt", "ok", 2, 0, 0100644);
  archive_free(&a);
  CHECK(entries_in(dir) == 1); /* r.fmu alone: no temporary file */

  /* A destination that is a directory. */
  z = NULL;
  CHECK(fb_zip_create(dir, &z, &err) == FB_EINVAL && z == NULL);
  CHECK(fb_zip_create("", &z, &err) == FB_EINVAL && z == NULL);
  CHECK(fb_zip_commit(NULL, &err) == FB_EINVAL);
  fb_zip_free(NULL);
  fb_zip_free(&z);
}

/* fb_zip_free without commit: nothing at the destination, no temporary
 * file, and a file already there untouched. */
static void test_abandon(const data_set *d)
{
  char dir[TEST_PATH_MAX], path[TEST_PATH_MAX + 16];
  test_tmp_path("abandon", dir, sizeof dir);
  CHECK(mkdir(dir, 0700) == 0);
  snprintf(path, sizeof path, "%s/gone.fmu", dir);
  fb_err err;
  fb_zip *z = NULL;
  CHECK(fb_zip_create(path, &z, &err) == FB_OK);
  CHECK(fb_zip_add(z, "resources/big.csv", d->big, BIG, 0, &err) == FB_OK);
  CHECK(entries_in(dir) == 1); /* the temporary file */
  fb_zip_free(&z);
  CHECK(z == NULL);
  CHECK(entries_in(dir) == 0);
  CHECK(access(path, F_OK) != 0);

  CHECK(write_file(path, "old", 3) == 0);
  CHECK(fb_zip_create(path, &z, &err) == FB_OK);
  CHECK(fb_zip_add(z, "x.txt", "new", 3, 0, &err) == FB_OK);
  fb_zip_free(&z);
  size_t n = 0;
  unsigned char *old = read_file(path, &n);
  CHECK(old && n == 3 && memcmp(old, "old", 3) == 0);
  free(old);
  CHECK(entries_in(dir) == 1);
}

/* 65535 members are the most without ZIP64: the next one is refused. */
static void test_many(void)
{
  char path[TEST_PATH_MAX];
  test_tmp_path("many.zip", path, sizeof path);
  fb_err err;
  fb_zip *z = NULL;
  CHECK(fb_zip_create(path, &z, &err) == FB_OK);
  if (!z)
    return;
  int failures = 0;
  char name[32];
  for (unsigned i = 0; i < 65535u; ++i) {
    snprintf(name, sizeof name, "%x", i);
    failures += fb_zip_add(z, name, NULL, 0, 0, &err) != FB_OK;
  }
  CHECK(failures == 0);
  fb_err_clear(&err);
  CHECK(fb_zip_add(z, "one-too-many", NULL, 0, 0, &err) == FB_EINVAL);
  CHECK(!strcmp(err.key, "one-too-many"));
  CHECK(fb_zip_add(z, "0", NULL, 0, 0, &err) == FB_EINVAL); /* still a duplicate */
  CHECK(fb_zip_commit(z, &err) == FB_OK);
  archive a;
  CHECK(archive_read(path, &a) == 0);
  CHECK(a.n == 65535u);
  CHECK(a.n > 0 && !strcmp(a.m[a.n - 1].name, "fffe"));
  archive_free(&a);
}

int main(void)
{
  data_set d = {0};
  d.big = text_bytes(BIG);
  d.random = random_bytes(RANDOM);
  d.disk = text_bytes(DISK);
  d.disk_random = random_bytes(DISK_RANDOM);
  test_tmp_path("disk.csv", d.disk_path, sizeof d.disk_path);
  test_tmp_path("disk_random.bin", d.disk_random_path, sizeof d.disk_random_path);
  CHECK(write_file(d.disk_path, d.disk, DISK) == 0);
  CHECK(write_file(d.disk_random_path, d.disk_random, DISK_RANDOM) == 0);

  test_members(&d);
  test_refusals();
  test_abandon(&d);
  test_many();

  free(d.big);
  free(d.random);
  free(d.disk);
  free(d.disk_random);
  return check_report("test_zip");
}
