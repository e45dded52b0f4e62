/* SPDX-License-Identifier: BSD-3-Clause */
/* libFuzzer target: the model loader (fb_model_load_string, docs/model-format.md) on
 * arbitrary bytes and, for every model it accepts, the block diagram built from it
 * (fb_bd_build on the model's graph and probes: causality, schedule, probe targets).
 * Refused inputs are fine; a crash, a leak, undefined behaviour, an error without a
 * message or a slow input is a finding (docs/fuzzing.md).
 *
 * Relative file references (tables, Matrix Market files) resolve from FLEXBOND_FUZZ_DIR,
 * the source tree's tests/fuzz, which holds a few small data files for them; an input
 * that could name a special file such as /dev/zero is skipped (special_files.h). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "flexbond/bd.h"
#include "flexbond/model.h"

#include "special_files.h"

#ifndef FLEXBOND_FUZZ_DIR
#define FLEXBOND_FUZZ_DIR "."
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  const char *text = fuzz_yaml_text(data, size);
  if (!text)
    return 0;
  fb_err err;
  fb_model *model = NULL;
  const int rc = fb_model_load_string(text, size, "fuzz.yaml", FLEXBOND_FUZZ_DIR, &model, &err);
  /* A refusal must leave no model and say why; so must a diagram's. */
  if (rc) {
    if (rc != err.code || err.msg[0] == '\0' || model)
      abort();
    return 0;
  }
  size_t nprobes = 0;
  const fb_probe_spec *probes = fb_model_probes(model, &nprobes);
  fb_bd *bd = NULL;
  const int brc = fb_bd_build(fb_model_graph(model), probes, nprobes, &bd, &err);
  if (brc && (brc != err.code || err.msg[0] == '\0' || bd))
    abort();
  fb_bd_free(&bd);
  fb_model_free(&model);
  return 0;
}
