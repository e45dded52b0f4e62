/* SPDX-License-Identifier: BSD-3-Clause */
/* fb_mode_set_pictured (src/vehicle/mode_pictures.c) on mode sets written
 * by hand, each expected set worked out from the rules in
 * flexbond/vehicle.h: the first bounce, roll and pitch of the hull, each
 * mounted body's mode, the first wheel hop, the first two elastic modes. */
#include <stddef.h>

#include "flexbond/vehicle.h"

#include "check.h"

#define HULL(j)                                                                                \
  {                                                                                            \
    FB_MODE_HULL_RIGID, (j)                                                                    \
  }
#define ELASTIC                                                                                \
  {                                                                                            \
    FB_MODE_HULL_ELASTIC, 0                                                                    \
  }
#define MOUNT(b)                                                                               \
  {                                                                                            \
    FB_MODE_MOUNT, (b)                                                                         \
  }
#define WHEEL(c)                                                                               \
  {                                                                                            \
    FB_MODE_WHEEL, (c)                                                                         \
  }

/* 1 if out[0 .. n) is want[0 .. nwant). */
static int same(const size_t *out, size_t n, const size_t *want, size_t nwant)
{
  if (n != nwant)
    return 0;
  for (size_t i = 0; i < n; ++i)
    if (out[i] != want[i])
      return 0;
  return 1;
}

/* The paper's vehicle as flexbond modes --system flexible describes it
 * (examples/apc6x6.yaml): pitch, driver, driver again (the engine's mode,
 * which the driver holds the most of), roll, bounce, six wheel hops
 * around an elastic mode, then elastic modes. Mount 0 (driver) is the
 * first to dominate mode 1; mount 1 (engine) dominates none, and its
 * largest share is in mode 2. Chosen: pitch 0, driver 1, engine 2, roll
 * 3, bounce 4, first hop 5, elastic 7 and 12. */
static void test_paper_vehicle(void)
{
  fb_mode_part part[14] = {HULL(FB_MODE_PITCH),
                           MOUNT(0),
                           MOUNT(0),
                           HULL(FB_MODE_ROLL),
                           HULL(FB_MODE_BOUNCE),
                           WHEEL(0),
                           WHEEL(1),
                           ELASTIC,
                           WHEEL(2),
                           WHEEL(3),
                           WHEEL(4),
                           WHEEL(5),
                           ELASTIC,
                           ELASTIC};
  double share[14 * 2] = {0};
  share[1 * 2 + 0] = 0.42;
  share[1 * 2 + 1] = 0.30;
  share[2 * 2 + 0] = 0.43;
  share[2 * 2 + 1] = 0.41;
  share[3 * 2 + 1] = 0.05;
  const fb_mode_set ms = {.nmodes = 14, .part = part, .nmounts = 2, .mount_share = share};
  size_t out[16];
  const size_t want[] = {0, 1, 2, 3, 4, 5, 7, 12};
  const size_t n = fb_mode_set_pictured(&ms, out, 16);
  CHECK(same(out, n, want, sizeof want / sizeof want[0]));
  /* At most max, the first ones. */
  CHECK(fb_mode_set_pictured(&ms, out, 3) == 3 && out[2] == 2);
}

/* A turret-like mount that dominates a mode of its own (mode 2), a hull
 * with no supported roll among the modes kept, no wheel hop and one
 * elastic mode: bounce 0, pitch 1, turret 2, elastic 3. */
static void test_turret(void)
{
  fb_mode_part part[5] = {HULL(FB_MODE_BOUNCE), HULL(FB_MODE_PITCH), MOUNT(0), ELASTIC,
                          HULL(FB_MODE_BOUNCE)};
  double share[5] = {0.1, 0.2, 0.9, 0.0, 0.3};
  const fb_mode_set ms = {.nmodes = 5, .part = part, .nmounts = 1, .mount_share = share};
  size_t out[8];
  const size_t want[] = {0, 1, 2, 3};
  CHECK(same(out, fb_mode_set_pictured(&ms, out, 8), want, 4));
}

/* A mount that moves in no mode adds none; an empty set, none at all. */
static void test_none(void)
{
  fb_mode_part part[2] = {ELASTIC, HULL(FB_MODE_PITCH)};
  double share[2] = {0.0, 0.0};
  const fb_mode_set ms = {.nmodes = 2, .part = part, .nmounts = 1, .mount_share = share};
  size_t out[4];
  const size_t want[] = {0, 1};
  CHECK(same(out, fb_mode_set_pictured(&ms, out, 4), want, 2));
  const fb_mode_set empty = {.nmodes = 0, .part = part};
  CHECK(fb_mode_set_pictured(&empty, out, 4) == 0);
  CHECK(fb_mode_set_pictured(NULL, out, 4) == 0);
}

int main(void)
{
  test_paper_vehicle();
  test_turret();
  test_none();
  return check_report("test_mode_pictures");
}
