/* SPDX-License-Identifier: BSD-3-Clause */
/* A file as a hull source (flexbond/hull_source.h): an Abaqus/CalculiX
 * deck (.inp) or a gmsh mesh (.msh 4.1) at hull_deck, read once and used
 * as it is. One source for both formats: fb_mesh_read_file tells them
 * apart by their content, and everything after the read (the node sets,
 * the frame, the report) is the same for both. */
#include <stdio.h>

#include "flexbond/hull_source.h"

static int deck_check(const fb_scenario *s, fb_err *err)
{
  if (s->hull_deck && s->hull_deck[0])
    return FB_OK;
  fb_err_set(err, FB_EINVAL, "a mesh file's path is needed");
  return fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_deck)), FB_EINVAL;
}

static int deck_read(const fb_scenario *s, fb_mesh **out, fb_err *err)
{
  const int rc = deck_check(s, err);
  return rc ? rc : fb_mesh_read_file(s->hull_deck, out, err);
}

static void deck_describe(const fb_scenario *s, char *buf, size_t n)
{
  snprintf(buf, n, "the deck %s", s->hull_deck ? s->hull_deck : "(none)");
}

/* A deck's errors of size and of its node sets, which keep no line, name
 * the deck; a node that is off stays the error of the scenario's point. */
static void deck_blame(const fb_scenario *s, fb_err *err)
{
  fb_err_prefix(err, "%s: ", s->hull_deck ? s->hull_deck : "(no deck)");
  if (err && !err->part.kind)
    fb_err_set_part(err, FB_PART_AT(FB_PART_VEHICLE, 0, hull_deck));
}

static const fb_hull_source_ops deck_ops = {
    .check = deck_check, .read = deck_read, .describe = deck_describe, .blame = deck_blame};

const fb_hull_source fb_hull_source_deck = {
    .name = "deck",
    .doc = "an Abaqus/CalculiX deck (.inp) or a gmsh mesh (.msh, format 4.1) with the "
           "scenario's node sets, used as it is",
    .ops = &deck_ops};
