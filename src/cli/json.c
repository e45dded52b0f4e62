/* SPDX-License-Identifier: BSD-3-Clause */
/* JSON text written by hand for the commands' summary files (cli.h). */
#include <stdio.h>

#include "flexbond/escape.h"

#include "cli.h"

/* The commands' name for the one JSON string writer, kept for cli.h's
 * callers: the escaping is fb_json_write_string's (RFC 8259). */
void cli_json_string(FILE *fp, const char *s)
{
  fb_json_write_string(fp, s);
}
