/* SPDX-License-Identifier: BSD-3-Clause */
/* A result (fb_result) built by hand for tests of what reads results:
 * nsamples rows of ncols columns named names[] with units[], its data
 * (row-major) to be filled by the caller; NULL when memory runs out. */
#ifndef FLEXBOND_TESTS_RESULT_UTIL_H
#define FLEXBOND_TESTS_RESULT_UTIL_H

#include <stdlib.h>
#include <string.h>

#include "sim/sim_internal.h"

static fb_result *test_result_new(size_t nsamples, size_t ncols, const char *const *names,
                                  const char *const *units)
{
  fb_result *r = calloc(1, sizeof *r);
  if (!r)
    return NULL;
  r->nsamples = nsamples;
  r->ncols = ncols;
  r->names = calloc(ncols, sizeof *r->names);
  r->units = calloc(ncols, sizeof *r->units);
  r->data = malloc(nsamples * ncols * sizeof *r->data);
  int ok = r->names && r->units && r->data;
  for (size_t j = 0; ok && j < ncols; ++j) {
    r->names[j] = strdup(names[j]);
    r->units[j] = strdup(units[j]);
    ok = r->names[j] && r->units[j];
  }
  if (!ok)
    fb_result_free(&r);
  return r;
}

#endif
