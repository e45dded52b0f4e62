/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of the schema engine (src/io/schema.c) on a toy format of its
 * own: reading (types, defaults, inheritance, unknown keys, alternatives,
 * lists and their origins), the range check, the visit of a struct's
 * values and the Markdown tables. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/schema.h"

/* ---- The toy format: a box with a colour, a speed in km/h, a shape
 * given one of two ways, and a list of named items that inherit a
 * default weight. */

typedef struct toy_item {
  char *name;
  double weight;
} toy_item;

typedef struct toy {
  char *title;
  double width;   /* m */
  double speed;   /* m/s, written in km/h */
  int colour;     /* index of toy_colours */
  int count;      /* whole number */
  double radius;  /* one of radius */
  double side;    /* or side */
  toy_item *item; /* allocated by the reader */
  size_t nitems;
} toy;

static double toy_to_ms(double v)
{
  return v / 3.6;
}

static double toy_to_kmh(double v)
{
  return v * 3.6;
}

static int toy_item_end(sch_reader *r, const sch_key *k, struct fy_node *node,
                        const char *item_path, size_t mark, void *base, void *item)
{
  (void)k;
  (void)node;
  (void)base;
  char prefix[64];
  snprintf(prefix, sizeof prefix, "items.%s", ((toy_item *)item)->name);
  return sch_origins_relabel(r, mark, item_path, prefix, 0);
}

static const sch_ops toy_kmh = {.to_struct = toy_to_ms, .from_struct = toy_to_kmh};
static const sch_ops toy_items_ops = {.item_end = toy_item_end};
static const char *const toy_colours[] = {"red", "green", "blue", NULL};

static const sch_key toy_item_keys[] = {
    {.path = "name",
     .type = SCH_NAME,
     .doc = "item name",
     .store = SCH_STORE_STRING,
     .offset = offsetof(toy_item, name)},
    {.path = "weight",
     .type = SCH_NUMBER,
     .unit = "kg",
     .bounds = SCH_LO | SCH_LO_OPEN,
     .need = SCH_INHERIT,
     .inherit = "box.weight",
     .doc = "item weight",
     .store = SCH_STORE_DOUBLE,
     .offset = offsetof(toy_item, weight)},
};
static const sch_table toy_item_table = {toy_item_keys, 2, NULL};

static const sch_key toy_keys[] = {
    {.path = "title",
     .type = SCH_TEXT,
     .doc = "the title",
     .store = SCH_STORE_STRING,
     .offset = offsetof(toy, title)},
    {.path = "box", .type = SCH_SECTION, .doc = "the box"},
    {.path = "box.width",
     .type = SCH_NUMBER,
     .unit = "m",
     .bounds = SCH_LO | SCH_LO_OPEN,
     .doc = "width",
     .store = SCH_STORE_DOUBLE,
     .offset = offsetof(toy, width)},
    {.path = "box.speed",
     .type = SCH_NUMBER,
     .unit = "km/h",
     .bounds = SCH_LO | SCH_HI,
     .lo = 0,
     .hi = 90,
     .doc = "speed",
     .store = SCH_STORE_DOUBLE,
     .offset = offsetof(toy, speed),
     .ops = &toy_kmh},
    {.path = "box.colour",
     .type = SCH_CHOICE,
     .choices = toy_colours,
     .need = SCH_DEFAULT,
     .def = 2,
     .doc = "colour",
     .store = SCH_STORE_INT,
     .offset = offsetof(toy, colour)},
    {.path = "box.count",
     .type = SCH_WHOLE,
     .bounds = SCH_LO | SCH_HI,
     .lo = 1,
     .hi = 9,
     .need = SCH_DEFAULT,
     .def = 3,
     .doc = "count",
     .store = SCH_STORE_INT,
     .offset = offsetof(toy, count)},
    {.path = "box.weight",
     .type = SCH_NUMBER,
     .unit = "kg",
     .need = SCH_OPTIONAL,
     .doc = "every item's weight unless it gives its own"},
    {.path = "box.radius",
     .type = SCH_NUMBER,
     .unit = "m",
     .one_of = "shape",
     .doc = "round",
     .store = SCH_STORE_DOUBLE,
     .offset = offsetof(toy, radius)},
    {.path = "box.side",
     .type = SCH_NUMBER,
     .unit = "m",
     .one_of = "shape",
     .doc = "square",
     .store = SCH_STORE_DOUBLE,
     .offset = offsetof(toy, side)},
    {.path = "items",
     .type = SCH_LIST,
     .need = SCH_OPTIONAL,
     .doc = "the items",
     .items = &toy_item_table,
     .view = "items",
     .offset = offsetof(toy, item),
     .count_at = offsetof(toy, nitems),
     .item_size = sizeof(toy_item),
     .named = 1,
     .ops = &toy_items_ops},
};
static const sch_table toy_table = {toy_keys, sizeof toy_keys / sizeof toy_keys[0], NULL};

static void toy_free(toy *t)
{
  free(t->title);
  for (size_t i = 0; i < t->nitems; ++i)
    free(t->item[i].name);
  free(t->item);
  memset(t, 0, sizeof *t);
}

/* Reads text into t with the nov overrides ov; r keeps the origins
 * (release it after). */
static int toy_read_with(const char *text, sch_override *ov, size_t nov, toy *t, sch_reader *r,
                         fb_err *err)
{
  ml_yaml y;
  memset(&y, 0, sizeof y);
  memset(t, 0, sizeof *t);
  static ml_ctx c;
  memset(&c, 0, sizeof c);
  c.file = "toy.yaml";
  c.base_dir = ".";
  c.err = err;
  fb_err_clear(err);
  *r = (sch_reader){.c = &c, .ov = ov, .nov = nov};
  int rc = ml_yaml_parse(text, strlen(text), c.file, &y, err);
  if (!rc)
    rc = sch_read(r, &toy_table, fy_document_root(y.doc), t);
  ml_yaml_release(&y);
  return rc;
}

static int toy_read(const char *text, toy *t, sch_reader *r, fb_err *err)
{
  return toy_read_with(text, NULL, 0, t, r, err);
}

static const char good[] = "title: a toy\n"              /* 1 */
                           "box:\n"                      /* 2 */
                           "  width: 2 * 0.5\n"          /* 3 */
                           "  speed: 36\n"               /* 4 */
                           "  weight: 7\n"               /* 5 */
                           "  side: 0.25\n"              /* 6 */
                           "items:\n"                    /* 7 */
                           "  - {name: a}\n"             /* 8 */
                           "  - {name: b, weight: 3}\n"; /* 9 */

static void test_read_good(void)
{
  toy t;
  sch_reader r;
  fb_err err;
  int rc = toy_read(good, &t, &r, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "%s\n", err.msg);
  CHECK(t.title && !strcmp(t.title, "a toy"));
  CHECK(t.width == 1.0);
  CHECK_NEAR(t.speed, 10.0, 1e-12);
  CHECK(t.colour == 2 && t.count == 3); /* defaults */
  CHECK(t.side == 0.25 && t.radius == 0);
  CHECK(t.nitems == 2 && !strcmp(t.item[0].name, "a") && !strcmp(t.item[1].name, "b"));
  CHECK(t.item[0].weight == 7 && t.item[1].weight == 3); /* inherited, own */
  /* Origins: logical keys of the items, the inherited value's path. */
  const sch_origin *o = sch_origin_find(&r, "items.a.weight");
  CHECK(o && !strcmp(o->path, "box.weight") && o->line == 5 && o->column == 11);
  o = sch_origin_find(&r, "items.b.weight");
  CHECK(o && !strcmp(o->path, "items[1].weight") && o->line == 9);
  o = sch_origin_find(&r, "box.speed");
  CHECK(o && o->given && o->line == 4 && o->column == 10);
  o = sch_origin_find(&r, "box.count");
  CHECK(o && !o->given);
  sch_reader_release(&r);
  toy_free(&t);
}

/* One bad document: status, message start and the error's fields. */
static void expect_bad(const char *text, int code, const char *msg, const char *key, int line)
{
  toy t;
  sch_reader r;
  fb_err err;
  int rc = toy_read(text, &t, &r, &err);
  CHECK(rc == code);
  CHECK(strstr(err.msg, msg) == err.msg);
  CHECK(!strcmp(err.key, key));
  CHECK(err.line == line && !strcmp(err.file, "toy.yaml"));
  if (rc != code || strstr(err.msg, msg) != err.msg || strcmp(err.key, key) || err.line != line)
    fprintf(stderr, "got %d '%s' key '%s' line %d\n", rc, err.msg, err.key, err.line);
  sch_reader_release(&r);
  toy_free(&t);
}

static void test_read_bad(void)
{
  expect_bad("title: x\nbox: {width: 1, speed: 1, radius: 1, widht: 2}\n", FB_EPARSE,
             "toy.yaml:2:38: box.widht: unknown key 'widht' (did you mean 'width'?)",
             "box.widht", 2);
  expect_bad("title: x\nbox: {speed: 1, radius: 1}\n", FB_EPARSE,
             "toy.yaml:2:6: box: missing required key 'width'", "box", 2);
  expect_bad("title: x\nbox: {width: 1, speed: 1, radius: 1, side: 2}\n", FB_EPARSE,
             "toy.yaml:2:38: box.side: give either 'radius' or 'side', not both", "box.side",
             2);
  expect_bad("title: x\nbox: {width: 1, speed: 1}\n", FB_EPARSE,
             "toy.yaml:2:6: box: missing one of 'radius', 'side'", "box", 2);
  expect_bad("title: x\nbox: {width: 1, speed: 1, radius: 1, colour: bleu}\n", FB_EPARSE,
             "toy.yaml:2:46: box.colour: unknown value 'bleu' (did you mean 'blue'?)",
             "box.colour", 2);
  expect_bad("title: x\nbox: {width: 1, speed: 1, radius: 1, count: 10}\n", FB_EINVAL,
             "toy.yaml:2:45: box.count: must be an integer from 1 to 9", "box.count", 2);
  expect_bad("title: x\nbox: {width: 1, speed: 1, radius: 1}\nitems: [{name: a}]\n", FB_EPARSE,
             "toy.yaml:3:9: items[0]: missing required key 'items[0].weight'", "items[0]", 3);
}

/* ---- Checking and visiting a struct. */

typedef struct toy_visit {
  char seen[512];
  fb_err err;
  int failed;
} toy_visit;

static int toy_collect(const sch_value *v, void *ctx)
{
  toy_visit *t = ctx;
  char text[64];
  sch_format(v, text, sizeof text);
  size_t len = strlen(t->seen);
  snprintf(t->seen + len, sizeof t->seen - len, "%s=%s;", v->path, text);
  if (!t->failed && sch_check_value(v, &t->err))
    t->failed = 1;
  return 0;
}

static void test_each_and_check(void)
{
  toy t;
  sch_reader r;
  fb_err err;
  CHECK(toy_read(good, &t, &r, &err) == FB_OK);
  sch_reader_release(&r);
  toy_visit v;
  memset(&v, 0, sizeof v);
  sch_each(&toy_table, &t, toy_collect, &v);
  CHECK(!strcmp(v.seen, "title=a toy;box.width=1;box.speed=36;box.colour=blue;box.count=3;"
                        "box.radius=0;box.side=0.25;items.a.name=a;items.a.weight=7;"
                        "items.b.name=b;items.b.weight=3;"));
  if (strcmp(v.seen, "title=a toy;box.width=1;box.speed=36;box.colour=blue;box.count=3;"
                     "box.radius=0;box.side=0.25;items.a.name=a;items.a.weight=7;"
                     "items.b.name=b;items.b.weight=3;"))
    fprintf(stderr, "seen: %s\n", v.seen);
  CHECK(!v.failed);
  /* Out of range after loading: the message in the file's unit, the
   * bound compared in the stored one (90 km/h exactly). */
  t.speed = 90 / 3.6;
  t.item[1].weight = -1;
  memset(&v, 0, sizeof v);
  sch_each(&toy_table, &t, toy_collect, &v);
  CHECK(v.failed && !strcmp(v.err.msg, "must be > 0 kg (got -1)"));
  CHECK(!strcmp(v.err.key, "items.b.weight"));
  t.speed = 91 / 3.6;
  memset(&v, 0, sizeof v);
  sch_each(&toy_table, &t, toy_collect, &v);
  CHECK(v.failed && !strcmp(v.err.msg, "must be in [0, 90] km/h (got 91)"));
  toy_free(&t);
}

/* A value stored in another unit prints as the file wrote it: 30 km/h is
 * stored as 30 / 3.6 m/s, which converts back to 30.000000000000004
 * (123.456 to 123.45600000000002); ten significant digits hide that
 * round-off. */
static void test_format_converted(void)
{
  toy t;
  sch_reader r;
  fb_err err;
  CHECK(toy_read(good, &t, &r, &err) == FB_OK);
  sch_reader_release(&r);
  const double kmh[] = {30, 123.456};
  const char *const want[] = {"box.speed=30;", "box.speed=123.456;"};
  for (size_t i = 0; i < 2; ++i) {
    CHECK(toy_to_kmh(toy_to_ms(kmh[i])) != kmh[i]); /* the round-off is there */
    t.speed = toy_to_ms(kmh[i]);
    toy_visit v;
    memset(&v, 0, sizeof v);
    sch_each(&toy_table, &t, toy_collect, &v);
    CHECK(strstr(v.seen, want[i]) != NULL);
    if (!strstr(v.seen, want[i]))
      fprintf(stderr, "seen: %s\n", v.seen);
  }
  toy_free(&t);
}

/* Overrides: a value the file has, a default it leaves out (at its
 * section's place), an item's key; a key the table does not have, named
 * with a suggestion and the override as the source. */
static void test_overrides(void)
{
  toy t;
  sch_reader r;
  fb_err err;
  sch_override ov[] = {{.path = "box.speed", .value = "72", .label = "--set speed=72"},
                       {.path = "box.count", .value = "5", .label = "--set count=5"},
                       {.path = "items[0].weight", .value = "2", .label = "--set w=2"}};
  int rc = toy_read_with(good, ov, 3, &t, &r, &err);
  CHECK(rc == FB_OK);
  if (rc)
    fprintf(stderr, "%s\n", err.msg);
  CHECK_NEAR(t.speed, 20.0, 1e-12);
  CHECK(t.count == 5 && t.nitems == 2 && t.item[0].weight == 2 && t.item[1].weight == 3);
  const sch_origin *o = sch_origin_find(&r, "box.count");
  CHECK(o && o->given && o->line == 3 && o->column == 3 && o->override &&
        !strcmp(o->override, "--set count=5"));
  o = sch_origin_find(&r, "box.speed");
  CHECK(o && o->line == 4 && o->column == 10 && !strcmp(o->override, "--set speed=72"));
  CHECK(ov[0].read && ov[1].read && ov[2].read);
  sch_reader_release(&r);
  toy_free(&t);
  sch_override typo = {.path = "box.widht", .value = "1", .label = "--set box.widht=1"};
  CHECK(toy_read_with(good, &typo, 1, &t, &r, &err) == FB_EINVAL);
  const char *want =
      "--set box.widht=1: toy.yaml:3:3: box: has no key 'widht' (did you mean 'width'?";
  CHECK(!strncmp(err.msg, want, strlen(want)));
  CHECK(err.source == FB_SOURCE_OVERRIDE && !strcmp(err.source_text, "--set box.widht=1") &&
        !strcmp(err.key, "box") && err.line == 3);
  sch_reader_release(&r);
  toy_free(&t);
}

static void test_markdown(void)
{
  char *buf = NULL;
  size_t len = 0;
  FILE *fp = open_memstream(&buf, &len);
  CHECK(fp != NULL);
  if (!fp)
    return;
  sch_markdown(&toy_table, fp);
  fclose(fp);
  CHECK(strstr(buf, "#### `box`\n") != NULL);
  CHECK(strstr(buf, "| `box.speed` | number | km/h | in [0, 90] | required | speed |\n"));
  CHECK(strstr(buf, "| `box.colour` | `red` \\| `green` \\| `blue` |  |  | `blue` | colour |"));
  CHECK(
      strstr(buf, "| `box.side` | number | m |  | exactly one of `radius`, `side` | square |"));
  CHECK(strstr(buf, "#### Each item of `items`\n"));
  CHECK(strstr(buf, "| `weight` | number | kg | > 0 | `box.weight` | item weight |"));
  free(buf);
}

int main(void)
{
  test_read_good();
  test_read_bad();
  test_each_and_check();
  test_format_converted();
  test_overrides();
  test_markdown();
  return check_report("test_schema");
}
