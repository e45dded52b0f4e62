/* SPDX-License-Identifier: BSD-3-Clause */
/* The modes of a vehicle worth a picture, chosen by what they are
 * (fb_mode_set_pictured, flexbond/vehicle.h): each kind of motion a
 * reader looks for once, from what the mode set says holds each mode's
 * kinetic energy (fb_mode_set.part, .mount_share), never from its text. */
#include "flexbond/vehicle.h"

/* The first mode whose part is (kind, index); any index when any_index;
 * ms->nmodes when there is none. */
static size_t first_of(const fb_mode_set *ms, fb_mode_part_kind kind, size_t index,
                       int any_index)
{
  for (size_t k = 0; k < ms->nmodes; ++k)
    if (ms->part[k].kind == kind && (any_index || ms->part[k].index == index))
      return k;
  return ms->nmodes;
}

/* Mounted body b's mode: the first it holds the largest share of the
 * kinetic energy in, else (two bodies on the hull near one frequency share
 * their modes: the paper's driver holds the most of the engine's) the mode
 * that gives it its largest share (ms->nmodes when it moves in none). */
static size_t mount_mode(const fb_mode_set *ms, size_t b)
{
  size_t best = first_of(ms, FB_MODE_MOUNT, b, 0);
  if (best < ms->nmodes)
    return best;
  double share = 0.0;
  for (size_t k = 0; k < ms->nmodes; ++k)
    if (ms->mount_share[k * ms->nmounts + b] > share) {
      share = ms->mount_share[k * ms->nmounts + b];
      best = k;
    }
  return best;
}

/* 1 if mode k is one fb_mode_set_pictured chooses. */
static int is_pictured(const fb_mode_set *ms, size_t k)
{
  const fb_mode_part *p = &ms->part[k];
  switch (p->kind) {
  case FB_MODE_HULL_RIGID:
    return (p->index == FB_MODE_BOUNCE || p->index == FB_MODE_ROLL ||
            p->index == FB_MODE_PITCH) &&
           first_of(ms, FB_MODE_HULL_RIGID, p->index, 0) == k;
  case FB_MODE_WHEEL:
    if (first_of(ms, FB_MODE_WHEEL, 0, 1) == k)
      return 1;
    break;
  case FB_MODE_HULL_ELASTIC: {
    size_t before = 0;
    for (size_t j = 0; j < k; ++j)
      before += ms->part[j].kind == FB_MODE_HULL_ELASTIC;
    if (before < FB_MODE_PICTURED_ELASTIC)
      return 1;
    break;
  }
  case FB_MODE_MOUNT:
  case FB_MODE_BOGIE: break;
  }
  for (size_t b = 0; ms->mount_share && b < ms->nmounts; ++b)
    if (mount_mode(ms, b) == k)
      return 1;
  return 0;
}

size_t fb_mode_set_pictured(const fb_mode_set *ms, size_t *out, size_t max)
{
  size_t count = 0;
  for (size_t k = 0; ms && ms->part && k < ms->nmodes && count < max; ++k)
    if (is_pictured(ms, k))
      out[count++] = k;
  return count;
}
