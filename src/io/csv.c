/* SPDX-License-Identifier: BSD-3-Clause */
/* CSV output of simulation results (see flexbond/io.h).
 *
 * The header cells are text fields of fb_csv_write_field_parts
 * (flexbond/escape.h): RFC 4180 quoting when a name or a unit holds a
 * comma, a double quote or a line break, and a ' before one that starts
 * with = + - @ (a spreadsheet would run it as a formula); ordinary names
 * are written as they are. Values are written with %.10g: ten
 * significant digits are more than the solver's tolerances resolve (rtol
 * >= 1e-10 in practice), and keep the files compact. */
#include <stdio.h>

#include "flexbond/escape.h"
#include "flexbond/io.h"

/* Header cell "name [unit]", or "name" when the unit is missing, as one
 * CSV text field. */
static void write_header_cell(FILE *fp, const char *name, const char *unit)
{
  const char *const parts[] = {name, " [", unit, "]"};
  fb_csv_write_field_parts(fp, parts, unit && *unit ? 4 : 1, FB_CSV_TEXT);
}

static void write_header(FILE *fp, const fb_result *r, size_t ncols, fb_csv_header header)
{
  int with_units = header == FB_CSV_HEADER_UNITS;
  /* Column 0 is time whatever the result names it. */
  write_header_cell(fp, "t", with_units ? "s" : NULL);
  for (size_t j = 1; j < ncols; ++j) {
    fputc(',', fp);
    write_header_cell(fp, fb_result_col_name(r, j),
                      with_units ? fb_result_col_unit(r, j) : NULL);
  }
  fputc('\n', fp);
}

static void write_rows(FILE *fp, const fb_result *r, size_t ncols)
{
  size_t nsamples = fb_result_nsamples(r);
  for (size_t k = 0; k < nsamples; ++k) {
    const double *row = fb_result_row(r, k);
    for (size_t j = 0; j < ncols; ++j)
      fprintf(fp, j ? ",%.10g" : "%.10g", row[j]);
    fputc('\n', fp);
  }
}

void fb_result_print_csv_columns(FILE *fp, const fb_result *r, size_t ncols,
                                 fb_csv_header header)
{
  if (ncols > fb_result_ncols(r))
    ncols = fb_result_ncols(r);
  write_header(fp, r, ncols, header);
  write_rows(fp, r, ncols);
}

void fb_result_print_csv(FILE *fp, const fb_result *r, fb_csv_header header)
{
  fb_result_print_csv_columns(fp, r, fb_result_ncols(r), header);
}

int fb_result_write_csv(const fb_result *r, const char *path, fb_err *err)
{
  fb_out *out = NULL;
  int rc = fb_out_open(path, &out, err);
  if (rc != FB_OK)
    return rc;
  fb_result_print_csv(fb_out_stream(out), r, FB_CSV_HEADER_UNITS);
  /* Write errors stick to the stream; commit reports them. */
  return fb_out_commit(&out, err);
}
