/* SPDX-License-Identifier: BSD-3-Clause */
/* sweep.csv's text (sweep.h): its header and rows, as the command writes
 * them and the resume journal (sweep_journal.c) reads them back. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "flexbond/escape.h"

#include "../core/textfile.h"
#include "cli.h"
#include "sweep.h"

/* ---- sweep.csv */

/* Value as a number if the whole text is one: the specs' numbers, the x
 * axis, the journal's metrics. fb_parse_decimal, as the data files and the
 * other options read numbers: strtod alone takes "0x10", "inf" and "nan". */
int sweep_numeric_value(const char *text, double *out)
{
  return fb_parse_decimal(text, out, NULL) == FB_OK;
}

void sweep_format_double(double x, char *buf, size_t size)
{
  fb_format_shortest(x, 15, buf, size);
}

/* The fields go through fb_csv_write_field (flexbond/escape.h, RFC 4180
 * quoting). The keys are text, guarded against being read as spreadsheet
 * formulas (FB_CSV_TEXT). The keys' values are not guarded: the journal
 * (sweep_journal.c) compares them with the study's byte for byte on
 * resuming, and most are numbers, "-1" among them. Nor are the errors:
 * each starts with flexbond's own words ("--set KEY=VALUE: ..."), and a '
 * would come before every one (docs/outputs.md). */
void sweep_key_label(const sweep_args *a, size_t k, char *buf, size_t size)
{
  const char *unit = fb_scenario_key_unit(a->keys[k].path);
  if (unit)
    snprintf(buf, size, "%s [%s]", a->keys[k].key, unit);
  else
    snprintf(buf, size, "%s", a->keys[k].key);
}

void sweep_csv_header(FILE *fp, const sweep_args *a, fb_csv_header header)
{
  for (size_t k = 0; k < a->nkeys; ++k) {
    char cell[FB_ERR_KEY_MAX + 64];
    if (header == FB_CSV_HEADER_UNITS)
      sweep_key_label(a, k, cell, sizeof cell);
    else
      snprintf(cell, sizeof cell, "%s", a->keys[k].key);
    fb_csv_write_field(fp, cell, FB_CSV_TEXT);
    fputc(',', fp);
  }
  for (size_t m = 0; m < a->nmetrics; ++m) {
    char name[FB_ERR_KEY_MAX], cell[FB_ERR_KEY_MAX + 64];
    fb_study_sweep_metric_name(a->study, m, name, sizeof name);
    const char *unit = fb_study_sweep_metric_unit(a->study, m);
    /* "-": a count or a ratio, no unit to give. */
    if (header == FB_CSV_HEADER_UNITS && strcmp(unit, "-") != 0)
      snprintf(cell, sizeof cell, "%s [%s]", name, unit);
    else
      snprintf(cell, sizeof cell, "%s", name);
    fb_csv_write_field(fp, cell, FB_CSV_TEXT);
    fputc(',', fp);
  }
  fputs("error\n", fp);
}

/* The keys' values, the metrics (empty when not finite or failed) and
 * the error. */
void sweep_csv_row(FILE *fp, const sweep_args *a, size_t i)
{
  fb_study_sweep_case c;
  fb_study_sweep_case_get(a->study, i, &c);
  for (size_t k = 0; k < a->nkeys; ++k) {
    fb_csv_write_field(fp, fb_study_sweep_case_value(a->study, i, k), 0);
    fputc(',', fp);
  }
  for (size_t m = 0; m < a->nmetrics; ++m) {
    if (isfinite(c.metric[m])) {
      char text[32];
      sweep_format_double(c.metric[m], text, sizeof text);
      fputs(text, fp);
    }
    fputc(',', fp);
  }
  if (c.status != FB_OK)
    fb_csv_write_field(fp, c.error ? c.error : "out of memory", 0);
  fputc('\n', fp);
}
