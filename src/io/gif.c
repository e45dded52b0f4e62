/* SPDX-License-Identifier: BSD-3-Clause */
/* Is a file a complete GIF image, and of how many frames?
 * (io/plot_internal.h, fb_gif_check.)
 *
 * gnuplot's animated GIF terminal may exit 0 having written part of a file
 * (a full disk), so an animation is read back before it is committed. The
 * walk follows the GIF89a specification (CompuServe, "Graphics
 * Interchange Format, Version 89a", 1990): the 6-byte header "GIF87a" or
 * "GIF89a" (sec. 17); the logical screen descriptor, 7 bytes with a
 * non-zero width and height (sec. 18) and, when its packed field's top bit
 * is set, a global colour table of 3 x 2^(N+1) bytes (sec. 19); then
 * blocks: an extension, 0x21 and a label followed by data sub-blocks (a
 * size byte and that many bytes) up to an empty one (secs. 15, 23-26); an
 * image, 0x2C, a 9-byte descriptor (sec. 20), its local colour table when
 * flagged, the LZW minimum code size (2 .. 8 in a GIF89a decoder, sec.
 * 22; 12-bit codes allow up to 11) and data sub-blocks; and the trailer
 * 0x3B, which must end the file (sec. 27). */
#include <stdlib.h>

#include "io/plot_internal.h"

/* A walk through the file's bytes; pos never passes n. */
typedef struct gif_walk {
  const unsigned char *data;
  size_t n, pos;
  size_t frames;
} gif_walk;

static unsigned le16(const unsigned char *p)
{
  return (unsigned)p[0] | (unsigned)p[1] << 8;
}

/* Skips count bytes; 0 if the file ends first. */
static int skip(gif_walk *w, size_t count)
{
  if (w->n - w->pos < count)
    return 0;
  w->pos += count;
  return 1;
}

/* Skips a colour table when the packed field flags one. */
static int skip_colour_table(gif_walk *w, unsigned packed)
{
  return !(packed & 0x80) || skip(w, (size_t)3 << ((packed & 7) + 1));
}

/* Skips data sub-blocks up to and with the empty one. */
static int skip_sub_blocks(gif_walk *w)
{
  for (;;) {
    if (w->pos >= w->n)
      return 0;
    const size_t size = w->data[w->pos++];
    if (size == 0)
      return 1;
    if (!skip(w, size))
      return 0;
  }
}

/* The image block after its 0x2C separator; NULL or what is wrong. */
static const char *image_block(gif_walk *w)
{
  if (w->n - w->pos < 9)
    return "an image descriptor is cut short";
  const unsigned char *d = w->data + w->pos;
  if (le16(d + 4) == 0 || le16(d + 6) == 0)
    return "an image has no width or height";
  w->pos += 9;
  if (!skip_colour_table(w, d[8]))
    return "a local colour table is cut short";
  if (w->pos >= w->n || w->data[w->pos] < 2 || w->data[w->pos] > 11)
    return "an image's LZW code size is missing or out of 2..11";
  ++w->pos;
  if (!skip_sub_blocks(w))
    return "an image's data is cut short";
  ++w->frames;
  return NULL;
}

/* NULL if data is a complete GIF, else what is wrong; w->frames counts
 * its images. */
static const char *gif_problem(gif_walk *w)
{
  const unsigned char *d = w->data;
  if (w->n < 13 || d[0] != 'G' || d[1] != 'I' || d[2] != 'F' || d[3] != '8' ||
      (d[4] != '7' && d[4] != '9') || d[5] != 'a')
    return "no GIF header and screen descriptor";
  if (le16(d + 6) == 0 || le16(d + 8) == 0)
    return "the screen has no width or height";
  w->pos = 13;
  if (!skip_colour_table(w, d[10]))
    return "the global colour table is cut short";
  while (w->pos < w->n) {
    const unsigned char block = d[w->pos++];
    if (block == 0x3B)
      return w->pos != w->n ? "bytes after the trailer"
             : !w->frames   ? "no image before the trailer"
                            : NULL;
    if (block == 0x21) {
      if (!skip(w, 1) || !skip_sub_blocks(w))
        return "an extension is cut short";
    } else if (block == 0x2C) {
      const char *problem = image_block(w);
      if (problem)
        return problem;
    } else {
      return "a block of an unknown kind";
    }
  }
  return "the file ends before its trailer";
}

int fb_gif_frames(const char *path, size_t *nframes, fb_err *err)
{
  *nframes = 0;
  unsigned char *data = NULL;
  size_t n = 0;
  int rc = fb_image_read(path, &data, &n, err);
  gif_walk w = {data, n, 0, 0};
  const char *problem = rc == FB_OK ? gif_problem(&w) : NULL;
  if (problem)
    rc = fb_err_set(err, FB_EIO, "not a complete GIF image: %s", problem);
  else if (rc == FB_OK)
    *nframes = w.frames;
  free(data);
  return rc;
}

int fb_gif_check(const char *path, fb_err *err)
{
  size_t nframes = 0;
  return fb_gif_frames(path, &nframes, err);
}
