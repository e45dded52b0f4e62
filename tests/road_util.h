/* SPDX-License-Identifier: BSD-3-Clause */
/* The road parameters of a test's scenario, whose road type the test
 * knows (checked). Header-only test helper. */
#ifndef FLEXBOND_TESTS_ROAD_UTIL_H
#define FLEXBOND_TESTS_ROAD_UTIL_H

#include <stdint.h>

#include "flexbond/vehicle.h"

#include "check.h"

/* The block of s's road, for reading or, when s is the test's own,
 * writing. */
static inline void *road_block(const fb_scenario *s, const fb_road_type *t)
{
  CHECK(s->road_type == t);
  return (void *)(uintptr_t)s->road.bytes;
}

static inline fb_road_bump_params *road_bump(const fb_scenario *s)
{
  return road_block(s, &fb_road_type_bump);
}

static inline fb_road_random_params *road_random(const fb_scenario *s)
{
  return road_block(s, &fb_road_type_iso8608);
}

#endif
