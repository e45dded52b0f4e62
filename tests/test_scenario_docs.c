/* SPDX-License-Identifier: BSD-3-Clause */
/* docs/scenario-format.md holds, between its schema:begin and schema:end
 * markers, exactly the key tables the loader's own table writes
 * (fb_scenario_schema_markdown): the reference cannot drift from the
 * reader. On a mismatch the tables to paste are printed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/textfile.h"
#include "io/scenario_internal.h"

#define DOC "../docs/scenario-format.md"
#define BEGIN "<!-- schema:begin -->\n"
#define END "<!-- schema:end -->"

int main(void)
{
  char *doc = NULL;
  size_t doc_len = 0;
  CHECK(fb_read_file(DOC, &doc, &doc_len, NULL) == FB_OK);
  char *gen = NULL;
  size_t len = 0;
  FILE *fp = open_memstream(&gen, &len);
  CHECK(fp != NULL);
  if (!doc || !fp)
    return check_report("test_scenario_docs");
  CHECK(fb_scenario_schema_markdown(fp, NULL) == FB_OK);
  fclose(fp);
  char *begin = strstr(doc, BEGIN);
  char *end = begin ? strstr(begin, END) : NULL;
  CHECK(begin && end);
  if (begin && end) {
    begin += strlen(BEGIN);
    *end = '\0';
    const int same = !strcmp(begin, gen);
    CHECK(same);
    if (!same)
      fprintf(stderr, "%s differs from the schema; its tables should be:\n%s", DOC, gen);
  }
  free(gen);
  free(doc);
  return check_report("test_scenario_docs");
}
