/* SPDX-License-Identifier: BSD-3-Clause */
/* The kind of a YAML input file, by its root mapping's keys (see
 * io/input_kind.h): decided on the parsed document, never on its text,
 * so a comment or a quoted "scenario:" cannot mislead it. */
#include "io/input_kind.h"

#include <stdlib.h>

#include "core/textfile.h"
#include "io/model_internal.h"

fb_input_kind fb_input_kind_of(const char *path)
{
  char *text = NULL;
  size_t len = 0;
  fb_input_kind kind = FB_INPUT_MODEL;
  /* The reasons are the model loader's to give: this error is dropped. */
  fb_err ignored;
  fb_err_clear(&ignored);
  if (fb_read_file(path, &text, &len, &ignored) != FB_OK)
    return kind;
  ml_yaml y;
  /* ml_yaml_parse initialises y on every path, so it is always released. */
  if (ml_yaml_parse(text, len, path, &y, &ignored) == FB_OK) {
    struct fy_node *root = fy_document_root(y.doc);
    if (root && fy_node_is_mapping(root) &&
        fy_node_mapping_lookup_by_string(root, "scenario", FY_NT) != NULL)
      kind = FB_INPUT_SCENARIO;
  }
  ml_yaml_release(&y);
  free(text);
  return kind;
}
