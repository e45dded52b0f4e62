/* SPDX-License-Identifier: BSD-3-Clause */
/* Every part of a description that the library names in an error
 * (fb_err.part) maps back to a key of the scenario format, so that an
 * error found below io is located at its value's line and key
 * (fb_scenario_locate); and a description without a file gets the
 * part in the description's own words.
 *
 * The parts are read from the library's sources (src/vehicle, src/sim:
 * FB_PART_AT(kind, i, member), fb_part_member_(kind, member), the check's
 * field tables F(struct, member, ...) and fail(err, kind, i, "member",
 * ...)), so that a part added there without a key here fails this test
 * rather than a user's error message. */
#include <dirent.h>
#include <regex.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "check.h"
#include "core/textfile.h"
#include "io/scenario_internal.h"

#define EXAMPLE "../examples/truck6x6_bogie.yaml"

/* The 6x6 truck (an anti-roll bar, bogies) with a hull section and a
 * mounted rigid body added (no example has them). */
static fb_scenario *load_truck(void)
{
  char *text = NULL;
  size_t len = 0;
  fb_err err;
  CHECK(fb_read_file(EXAMPLE, &text, &len, &err) == FB_OK);
  const char *at = text ? strstr(text, "\n  masses:") : NULL;
  CHECK(at != NULL);
  if (!at) {
    free(text);
    return NULL;
  }
  static const char section[] = "\n  sections: [{set: FLOOR, thickness: 0.012}]";
  const size_t head = (size_t)(at - text);
  static const char body[] =
      "\nbodies: [{name: box, mass: 50, x: 0, y: 0, z: 1, Ixx: 2, Iyy: 2, Izz: 3,\n"
      "          bushings: [{x: 0, y: 0, z: 0.8, stiffness: [1, 1, 1, 1, 1, 1],\n"
      "                      node_set: LOAD}]}]\n";
  char *edited = malloc(len + sizeof section + sizeof body);
  fb_scenario *s = NULL;
  if (edited) {
    memcpy(edited, text, head);
    memcpy(edited + head, section, sizeof section - 1);
    memcpy(edited + head + sizeof section - 1, at, len - head + 1);
    strcat(edited, body);
    CHECK(fb_scenario_load_string(edited, strlen(edited), EXAMPLE, &s, &err) == FB_OK);
  }
  free(edited);
  free(text);
  return s;
}

static int kind_of(const char *name)
{
  static const struct {
    const char *name;
    int kind;
  } kinds[] = {{"FB_PART_VEHICLE", FB_PART_VEHICLE},
               {"fb_scenario", FB_PART_VEHICLE},
               {"FB_PART_CORNER", FB_PART_CORNER},
               {"fb_corner_params", FB_PART_CORNER},
               {"FB_PART_MOUNT", FB_PART_MOUNT},
               {"fb_mount", FB_PART_MOUNT},
               {"FB_PART_HULL_MASS", FB_PART_HULL_MASS},
               {"fb_hull_point_mass", FB_PART_HULL_MASS},
               {"FB_PART_SECTION", FB_PART_SECTION},
               {"fb_hull_section", FB_PART_SECTION},
               {"FB_PART_OUTPUT", FB_PART_OUTPUT},
               {"fb_output_spec", FB_PART_OUTPUT},
               {"FB_PART_LOAD_POINT", FB_PART_LOAD_POINT},
               {"FB_PART_ANTIROLL_BAR", FB_PART_ANTIROLL_BAR},
               {"fb_antiroll_bar", FB_PART_ANTIROLL_BAR},
               {"FB_PART_BOGIE", FB_PART_BOGIE},
               {"fb_bogie", FB_PART_BOGIE},
               {"FB_PART_BODY", FB_PART_BODY},
               {"fb_body", FB_PART_BODY},
               {"FB_PART_BUSHING", FB_PART_BUSHING},
               {"fb_bushing", FB_PART_BUSHING}};
  for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; ++i)
    if (!strcmp(kinds[i].name, name))
      return kinds[i].kind;
  return FB_PART_NONE;
}

/* Parts the library names through a variable rather than a literal: the
 * generator's parameters (hull_mesh.c's param_part), the points' axes. */
static const struct {
  int kind;
  const char *field;
} computed[] = {
    {FB_PART_VEHICLE, "hull_mesh.width"},
    {FB_PART_VEHICLE, "hull_mesh.height"},
    {FB_PART_VEHICLE, "hull_mesh.nose_length"},
    {FB_PART_VEHICLE, "hull_mesh.x_front"},
    {FB_PART_VEHICLE, "hull_mesh.nose_height"},
    {FB_PART_VEHICLE, "hull_mesh.side_rows"},
    {FB_PART_VEHICLE, "hull_mesh.nose_rows"},
    {FB_PART_VEHICLE, "hull_mesh.nose_rung_divisions"},
    {FB_PART_VEHICLE, "hull_mesh.density"},
    {FB_PART_VEHICLE, "t_end"},
    {FB_PART_VEHICLE, "sample_rate"},
    {FB_PART_VEHICLE, "max_step"},
    {FB_PART_VEHICLE, "max_steps"},
    {FB_PART_VEHICLE, "rtol"},
    {FB_PART_VEHICLE, "atol"},
    {FB_PART_CORNER, "x"},
    {FB_PART_CORNER, "y"},
    {FB_PART_MOUNT, "x"},
    {FB_PART_MOUNT, "y"},
    {FB_PART_HULL_MASS, "x"},
    {FB_PART_HULL_MASS, "y"},
};

/* Members of the description that no key of the format gives, by design:
 * a road kind is the section the file writes, a profile's data what its
 * file holds, road_iso the section whose parameters its constructor
 * names. Their errors are located at their section or not at all. */
static int keyless(int kind, const char *field)
{
  static const char *const vehicle[] = {"road_kind", "road_profile_data", NULL};
  for (size_t i = 0; kind == FB_PART_VEHICLE && vehicle[i]; ++i)
    if (!strcmp(field, vehicle[i]))
      return 1;
  return 0;
}

static size_t nchecked;

/* part (kind, field) of s maps to a key of the format. */
static void expect_key(const fb_scenario *s, int kind, const char *field, const char *where)
{
  if (keyless(kind, field))
    return;
  fb_err_part p = {kind, 0, FB_ERR_NO_ELEMENT, ""};
  snprintf(p.field, sizeof p.field, "%s", field);
  char key[FB_ERR_KEY_MAX];
  const int mapped = sc_part_key(s, &p, key, sizeof key);
  CHECK(mapped);
  if (!mapped)
    fprintf(stderr, "  %s: part %d '%s' maps to no key of the format\n", where, kind, field);
  ++nchecked;
}

/* Every match of pattern (kind at group gk, member at gm) in text. */
static void scan(const fb_scenario *s, const char *text, const char *pattern, int gk, int gm,
                 const char *where)
{
  regex_t re;
  CHECK(regcomp(&re, pattern, REG_EXTENDED) == 0);
  regmatch_t m[4];
  for (const char *at = text; regexec(&re, at, 4, m, 0) == 0; at += m[0].rm_eo) {
    char kind[64], member[FB_ERR_FIELD_MAX];
    snprintf(kind, sizeof kind, "%.*s", (int)(m[gk].rm_eo - m[gk].rm_so), at + m[gk].rm_so);
    snprintf(member, sizeof member, "%.*s", (int)(m[gm].rm_eo - m[gm].rm_so), at + m[gm].rm_so);
    const int k = kind_of(kind);
    if (k != FB_PART_NONE)
      expect_key(s, k, member, where);
  }
  regfree(&re);
}

static void scan_sources(const fb_scenario *s, const char *dir)
{
  DIR *d = opendir(dir);
  CHECK(d != NULL);
  for (struct dirent *e = d ? readdir(d) : NULL; e; e = readdir(d)) {
    const size_t n = strlen(e->d_name);
    if (n < 3 || strcmp(e->d_name + n - 2, ".c") != 0)
      continue;
    char path[512], *text = NULL;
    size_t len = 0;
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    if (fb_read_file(path, &text, &len, NULL) != FB_OK)
      continue;
    scan(s, text, "FB_PART_(AT|ELEMENT)\\((FB_PART_[A-Z_]+), [^,]+, ([a-z_.]+)", 2, 3, path);
    scan(s, text, "fb_part_member_\\((FB_PART_[A-Z_]+), ([a-z_.]+)\\)", 1, 2, path);
    scan(s, text, "\\bF\\((fb_[a-z_]+), ([a-z_]+),", 1, 2, path);
    scan(s, text, "fail\\(err, (FB_PART_[A-Z_]+), [^,]+, \"([a-z_.]+)\"", 1, 2, path);
    free(text);
  }
  if (d)
    closedir(d);
}

/* A description made without a file: the part in its own words. */
static void test_without_file(const fb_scenario *base)
{
  fb_scenario *s = NULL;
  fb_err err;
  CHECK(fb_scenario_clone(base, &s, &err) == FB_OK && s);
  if (!s)
    return;
  s->source->ops->free(s->source);
  s->source = NULL;
  s->mount[0].stiffness = -2;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL &&
        PART_IS(&err, FB_PART_MOUNT, 0, "stiffness"));
  fb_scenario_locate(s, &err);
  CHECK(strstr(err.msg, "mount[0] (") == err.msg &&
        strstr(err.msg, ").stiffness: must be > 0 N/m (got -2)") != NULL);
  fb_scenario_free(&s);
}

/* With its file: the same error at the value's line and key. */
static void test_located(fb_scenario *s)
{
  fb_err err;
  const double was = s->mount[0].stiffness;
  s->mount[0].stiffness = -2;
  CHECK(fb_scenario_check(s, &err) == FB_EINVAL);
  fb_scenario_locate(s, &err);
  CHECK(!strcmp(err.file, EXAMPLE) && err.line > 0 && !strcmp(err.key, "mounts[0].stiffness") &&
        strstr(err.msg, ".stiffness: must be > 0 N/m (got -2)") != NULL);
  s->mount[0].stiffness = was;
  /* A section's member, and an element of an array member. */
  fb_err_set(&err, FB_EINVAL, "test");
  fb_err_set_part(&err, FB_PART_AT(FB_PART_SECTION, 0, thickness));
  fb_scenario_locate(&(*s), &err);
  CHECK(!strcmp(err.key, "hull.sections[0].thickness") && err.line > 0);
  fb_err_set(&err, FB_EINVAL, "test");
  fb_err_set_part(&err, FB_PART_ELEMENT(FB_PART_VEHICLE, 0, hull_mesh.bulkhead_x, 1));
  fb_scenario_locate(s, &err);
  CHECK(!strcmp(err.key, "hull.mesh.generator.bulkheads[1]") && err.line > 0);
}

int main(void)
{
  fb_scenario *s = load_truck();
  if (!s)
    return check_report("test_parts");
  CHECK(s->nsections == 1 && s->npoint_masses > 0 && s->nmounts > 0 && s->noutputs > 0 &&
        s->nantiroll_bars == 1 && s->nbogies == 2);
  scan_sources(s, "../src/vehicle");
  scan_sources(s, "../src/sim");
  for (size_t i = 0; i < sizeof computed / sizeof computed[0]; ++i)
    expect_key(s, computed[i].kind, computed[i].field, "computed");
  /* The scan found the library's parts (about 80 when written). */
  CHECK(nchecked > 60);
  test_without_file(s);
  test_located(s);
  fb_scenario_free(&s);
  return check_report("test_parts");
}
