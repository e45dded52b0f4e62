/* SPDX-License-Identifier: BSD-3-Clause */
/* Sampled simulation results (see flexbond/sim.h). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/sim.h"

#include "sim/sim_internal.h"

void fb_result_free(fb_result **r)
{
  if (!r || !*r)
    return;
  fb_result *res = *r;
  for (size_t j = 0; j < res->ncols; ++j) {
    if (res->names)
      free(res->names[j]);
    if (res->units)
      free(res->units[j]);
  }
  free(res->names);
  free(res->units);
  free(res->data);
  free(res);
  *r = NULL;
}

/* strdup that maps NULL to "". */
static char *copy_text(const char *s)
{
  return strdup(s ? s : "");
}

static int copy_columns(fb_result *r, const fb_bd *bd)
{
  r->names[0] = copy_text("t");
  r->units[0] = copy_text("s");
  if (!r->names[0] || !r->units[0])
    return FB_ENOMEM;
  for (size_t j = 1; j < r->ncols; ++j) {
    r->names[j] = copy_text(fb_bd_output_name(bd, j - 1));
    r->units[j] = copy_text(fb_bd_output_unit(bd, j - 1));
    if (!r->names[j] || !r->units[j])
      return FB_ENOMEM;
  }
  return FB_OK;
}

int fb_result_alloc(const fb_bd *bd, size_t nsamples, fb_result **out, fb_err *err)
{
  *out = NULL;
  const size_t ncols = 1 + fb_bd_noutputs(bd);
  if (nsamples > SIZE_MAX / sizeof(double) / ncols)
    return fb_err_set(err, FB_ENOMEM, "result of %zu samples x %zu columns is too large",
                      nsamples, ncols);
  fb_result *r = calloc(1, sizeof *r);
  if (!r)
    return fb_err_set(err, FB_ENOMEM, "out of memory allocating the result");
  r->nsamples = nsamples;
  r->ncols = ncols;
  r->names = calloc(ncols, sizeof *r->names);
  r->units = calloc(ncols, sizeof *r->units);
  r->data = malloc((nsamples ? nsamples : 1) * ncols * sizeof *r->data);
  if (!r->names || !r->units || !r->data || copy_columns(r, bd) != FB_OK) {
    fb_result_free(&r);
    return fb_err_set(err, FB_ENOMEM, "out of memory allocating %zu samples x %zu columns",
                      nsamples, ncols);
  }
  *out = r;
  return FB_OK;
}

int fb_result_truncate(fb_result *r, size_t ncols, fb_err *err)
{
  if (ncols == 0 || ncols > r->ncols)
    return fb_err_set(err, FB_EINVAL, "cannot keep %zu of a result's %zu columns", ncols,
                      r->ncols);
  for (size_t j = ncols; j < r->ncols; ++j) {
    free(r->names[j]);
    free(r->units[j]);
  }
  /* Row k moves to k ncols, never ahead of where it was read. */
  for (size_t k = 0; k < r->nsamples; ++k)
    memmove(r->data + k * ncols, r->data + k * r->ncols, ncols * sizeof *r->data);
  r->ncols = ncols;
  return FB_OK;
}

size_t fb_result_nsamples(const fb_result *r)
{
  return r->nsamples;
}

size_t fb_result_ncols(const fb_result *r)
{
  return r->ncols;
}

const char *fb_result_col_name(const fb_result *r, size_t j)
{
  return j < r->ncols ? r->names[j] : NULL;
}

const char *fb_result_col_unit(const fb_result *r, size_t j)
{
  return j < r->ncols ? r->units[j] : NULL;
}

const double *fb_result_row(const fb_result *r, size_t k)
{
  return k < r->nsamples ? r->data + k * r->ncols : NULL;
}

long fb_result_find(const fb_result *r, const char *name)
{
  for (size_t j = 0; j < r->ncols; ++j)
    if (strcmp(r->names[j], name) == 0)
      return (long)j;
  return -1;
}

const fb_sim_stats *fb_result_stats(const fb_result *r)
{
  return &r->stats;
}
