/* SPDX-License-Identifier: BSD-3-Clause */
/* A ZIP archive writer for FMU files (an FMU is a ZIP archive holding
 * modelDescription.xml, the shared libraries under binaries/<platform>/ and resources/).
 *
 * The format is that of PKWARE's APPNOTE.TXT (.ZIP File Format
 * Specification, version 6.3.x): local file headers (4.3.7), the central
 * directory (4.3.12) and its end record (4.3.16). Members are deflated
 * (method 8, raw deflate by zlib) or stored (method 0) when deflating
 * would not make them smaller. No ZIP64: an archive or member over
 * 0xFFFFFFFF bytes or of more than 65535 members is refused before
 * anything of it is written. Every member has the fixed date 1980-01-01
 * 00:00, so that the same members give a byte-identical archive, and Unix
 * permissions (0644, or 0755 for an executable), so that an extracted
 * shared library keeps its execute bit.
 *
 * The archive is written to a temporary file beside its destination and
 * renamed into place by fb_zip_commit: no half-written archive ever
 * appears at the destination. */
#ifndef FLEXBOND_IO_ZIP_H
#define FLEXBOND_IO_ZIP_H

#include <stddef.h>

#include "flexbond/error.h"

typedef struct fb_zip fb_zip;

/* The largest member, archive and member count without ZIP64. */
#define FB_ZIP_MAX_SIZE 0xFFFFFFFFu
#define FB_ZIP_MAX_ENTRIES 65535u

/* Starts an archive to be written at path: a new temporary file is
 * created exclusively in path's directory (core/tmpfile.h) and nothing is
 * done at path itself until fb_zip_commit. On success *out is the
 * archive, owned by the caller until fb_zip_commit or fb_zip_free. On
 * failure *out is NULL, no file is left behind, and err says why: FB_EINVAL
 * (empty path, or path is an existing directory or other non-regular
 * file), FB_ENOMEM, FB_EIO (the temporary file cannot be created). */
int fb_zip_create(const char *path, fb_zip **out, fb_err *err);

/* Adds the member name (a relative path with '/' separators; see below)
 * holding size bytes of data (not kept: copied into the archive before
 * return; NULL allowed when size is 0), with mode 0755 if executable is
 * nonzero, else 0644. name must be valid UTF-8, non-empty, at most 65535
 * bytes, without a leading '/', a backslash, an empty, "." or ".."
 * component, and unique in the archive; otherwise FB_EINVAL with err's key
 * the name. A member over FB_ZIP_MAX_SIZE bytes, one more than
 * FB_ZIP_MAX_ENTRIES, or one that would take the archive over
 * FB_ZIP_MAX_SIZE is refused with FB_EINVAL before anything is written.
 * On any failure the archive is as it was before the call (FB_EIO or
 * FB_ENOMEM while writing rolls the temporary file back; if even that
 * fails, every later call but fb_zip_free fails). */
int fb_zip_add(fb_zip *z, const char *name, const void *data, size_t size, int executable,
               fb_err *err);

/* fb_zip_add of the content of the regular file src_path, read in chunks
 * and streamed through deflate (never held whole in memory). Its size is
 * checked against the limits before anything is written; a file that
 * changes size or content while it is read is refused with FB_EIO. The
 * member's mode comes from executable, not from src_path's mode. Failures
 * as fb_zip_add's, plus FB_EIO when src_path cannot be opened or read or
 * is not a regular file. */
int fb_zip_add_file(fb_zip *z, const char *name, const char *src_path, int executable,
                    fb_err *err);

/* Finishes the archive: writes the central directory and its end record,
 * flushes, fsyncs and closes the temporary file and renames it onto the
 * destination (replacing a file there atomically). z is freed whatever
 * the outcome (the caller must not use it again). On failure (FB_EIO,
 * FB_ENOMEM, or FB_EINVAL for a NULL z) the temporary file is removed and
 * the destination is left as it was. */
int fb_zip_commit(fb_zip *z, fb_err *err);

/* Abandons the archive: closes and removes the temporary file, frees *z
 * and sets it to NULL. The destination is left as it was. z and *z may be
 * NULL. */
void fb_zip_free(fb_zip **z);

#endif
