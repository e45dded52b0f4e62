/* SPDX-License-Identifier: BSD-3-Clause */
/* libFuzzer target: the vehicle scenario loader (fb_scenario_load_string,
 * docs/scenario-format.md) on arbitrary bytes and, for every scenario it accepts, the
 * separate physical check fb_scenario_check again (it must still pass). Nothing is
 * simulated. Refused inputs are fine; a crash, a leak, undefined behaviour, an error
 * without a message or a slow input is a finding (docs/fuzzing.md).
 *
 * fb_scenario_load_string resolves relative file references (road profiles, damper
 * tables) from the working directory: the runners (make fuzz, the CTest replay) start
 * the target in tests/fuzz, which holds a few small data files for them; an input that
 * could name a special file such as /dev/zero is skipped (special_files.h). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "flexbond/vehicle.h"

#include "special_files.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  const char *text = fuzz_yaml_text(data, size);
  if (!text)
    return 0;
  fb_err err;
  fb_scenario *s = NULL;
  const int rc = fb_scenario_load_string(text, size, "fuzz.yaml", &s, &err);
  /* A refusal must leave no scenario and say why. */
  if (rc && (rc != err.code || err.msg[0] == '\0' || s))
    abort();
  /* The loader runs the check itself: an accepted scenario passes it. */
  if (!rc && fb_scenario_check(s, &err) != FB_OK)
    abort();
  fb_scenario_free(&s);
  return 0;
}
