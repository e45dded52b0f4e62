/* JSON text written by hand for the commands' summary files (cli.h). */
#include <stdio.h>

#include "cli.h"

void cli_json_string(FILE *fp, const char *s)
{
  fputc('"', fp);
  for (const unsigned char *c = (const unsigned char *)s; *c; ++c) {
    if (*c == '"' || *c == '\\')
      fprintf(fp, "\\%c", *c);
    else if (*c < 0x20)
      fprintf(fp, "\\u%04x", *c);
    else
      fputc(*c, fp);
  }
  fputc('"', fp);
}
