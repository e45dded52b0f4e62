/* SPDX-License-Identifier: BSD-3-Clause */
/* docs/vehicle-outputs.md lists every signal kind of the library's table
 * (fb_vehicle_output_kinds) as a row "| `signal` | subject | unit |
 * `default name` |", and no kind the table lacks: the page cannot drift
 * from the code that measures the signals. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "check.h"
#include "core/textfile.h"

static const char *subject_word(fb_output_subject s)
{
  switch (s) {
  case FB_OUTPUT_OF_CORNER: return "corner";
  case FB_OUTPUT_OF_MOUNT: return "mount";
  case FB_OUTPUT_OF_BODY: return "body";
  case FB_OUTPUT_OF_HULL: return "hull";
  case FB_OUTPUT_OF_BOND: return "bond";
  case FB_OUTPUT_OF_HULL_POINT: return "hull point";
  case FB_OUTPUT_OF_BOGIE: return "bogie";
  case FB_OUTPUT_OF_HULL_STRESS: return "hull element";
  }
  return "?";
}

int main(void)
{
  char *doc = NULL;
  size_t doc_len = 0;
  CHECK(fb_read_file("../docs/vehicle-outputs.md", &doc, &doc_len, NULL) == FB_OK);
  size_t n = 0;
  const fb_output_kind *k = fb_vehicle_output_kinds(&n);
  CHECK(n > 0);
  for (size_t i = 0; doc && i < n; ++i) {
    /* A bond signal's unit is its bond's domain's ("domain"), except a
     * power's, W in every domain. */
    const char *unit = k[i].unit ? k[i].unit : strcmp(k[i].signal, "power") ? "domain" : "W";
    char row[256];
    snprintf(row, sizeof row, "| `%s` | %s | %s | `%s` |", k[i].signal,
             subject_word(k[i].subject), unit, k[i].name);
    CHECK(strstr(doc, row) != NULL);
    if (!strstr(doc, row))
      fprintf(stderr, "docs/vehicle-outputs.md lacks the row %s\n", row);
    CHECK(fb_vehicle_output_kind_find(k[i].signal) == &k[i]);
  }
  /* Every row of the kinds' table names a kind of the library. */
  const char *table = doc ? strstr(doc, "| signal | of | unit |") : NULL;
  CHECK(table != NULL);
  size_t rows = 0;
  for (const char *p = table ? strstr(table, "\n| `") : NULL; p; p = strstr(p + 1, "\n| `")) {
    char signal[64] = "";
    if (sscanf(p, "\n| `%63[^`]`", signal) == 1) {
      CHECK(fb_vehicle_output_kind_find(signal) != NULL);
      if (!fb_vehicle_output_kind_find(signal))
        fprintf(stderr, "docs/vehicle-outputs.md names an unknown kind '%s'\n", signal);
      ++rows;
    }
    const char *end = strstr(p + 1, "\n\n");
    const char *next = strstr(p + 1, "\n| `");
    if (end && next && end < next)
      break;
  }
  CHECK(rows == n);
  free(doc);
  return check_report("test_outputs_doc");
}
