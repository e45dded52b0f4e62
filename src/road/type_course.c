/* SPDX-License-Identifier: BSD-3-Clause */
/* The road gallery's course (docs/roads.md, "Courses"): obstacles of the
 * obstacle types one after another, read from a small text file, one a
 * line:
 *
 *     # type    at (m)   the type's own parameters
 *     cleat     at=0     height=0.05 length=0.2 ramp_length=0.02
 *     pothole   at=6     depth=0.06 length=0.5 track=right
 *
 * Each line's values are read by the type's declarations (fb_param: the
 * name, unit scale, range, choices), checked by its rules, and placed as
 * the type places one obstacle; the course is crossed obliquely as one
 * (its angle and first contact), each obstacle at its distance along
 * it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/road.h"

#include "core/textfile.h"
#include "core/util.h"
#include "road/obstacle.h"
#include "road/road_internal.h"

/* The types a course's line may name. */
static const fb_road_type *const course_types[] = {
    &fb_road_type_halfround, &fb_road_type_step,    &fb_road_type_cleat,
    &fb_road_type_trapezoid, &fb_road_type_pothole, &fb_road_type_washboard,
};
#define COURSE_NTYPES (sizeof course_types / sizeof course_types[0])
/* Most obstacles in a course. */
#define COURSE_MAX_ITEMS 1000

struct fb_road_course_item {
  const fb_road_type *type;
  double at;   /* m, along the course */
  size_t line; /* in the file */
  fb_road_params block;
};

static const fb_param course_params[] = {
    {.name = "file",
     .kind = FB_PARAM_FILE,
     .store = FB_PARAM_STRING,
     .offset = offsetof(fb_road_course_params, file),
     .need = FB_PARAM_REQUIRED,
     .doc = "the course: one obstacle a line, `<type> at=<m> <key>=<value> ...` "
            "(docs/roads.md, \"Courses\")"},
    {.name = "angle_deg",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_course_params, angle),
     .unit = "deg",
     .scale = 3.14159265358979323846 / 180,
     .range = FB_RANGE_LO | FB_RANGE_HI | FB_RANGE_HI_OPEN,
     .hi = 90,
     .need = FB_PARAM_DEFAULT,
     .doc = "angle of the obstacles' leading edges to the lateral axis, left side first"},
    {.name = "first_contact",
     .kind = FB_PARAM_REAL,
     .store = FB_PARAM_DOUBLE,
     .offset = offsetof(fb_road_course_params, first_contact),
     .unit = "s",
     .range = FB_RANGE_LO,
     .need = FB_PARAM_REQUIRED,
     .doc = "time the first corner's wheel meets the course's start (`at=0`)"},
};

/* A layout to check an obstacle's rules and find its edges by, before
 * the vehicle's is known: neither depends on it. */
static const fb_road_layout COURSE_NOMINAL = {1.0, 1.0, 0.0, 0.5};

/* ---- Reading the file. */

typedef struct course_reader {
  fb_text_reader text;
  fb_road_course_params *p;
} course_reader;

/* Refuses the current line: "path:line: " and the message. */
static int line_fail(const course_reader *r, const char *fmt, const char *a, const char *b)
{
  char msg[FB_ERR_MSG_MAX];
  snprintf(msg, sizeof msg, fmt, a, b);
  return fb_err_set(r->text.err, FB_EPARSE, "%s:%zu: %s", r->text.path, r->text.line_no, msg);
}

static const fb_road_type *course_type(const char *name)
{
  for (size_t i = 0; i < COURSE_NTYPES; ++i)
    if (!strcmp(course_types[i]->name, name))
      return course_types[i];
  return NULL;
}

/* Stores the text value of parameter d into block (its written unit
 * scaled; a whole number; a choice by name). */
static int course_value(const course_reader *r, const fb_param *d, const char *text,
                        void *block)
{
  char *at = (char *)block + d->offset;
  if (d->kind == FB_PARAM_CHOICE) {
    for (int c = 0; d->choices[c]; ++c)
      if (!strcmp(d->choices[c], text)) {
        *(int *)(void *)at = c;
        return FB_OK;
      }
    return line_fail(r, "%s: not one of its choices (got '%s')", d->name, text);
  }
  double v = 0.0;
  if (fb_parse_decimal_field(text, &v, r->text.err))
    return line_fail(r, "%s: %s", d->name, r->text.err->msg);
  if (d->kind == FB_PARAM_WHOLE) {
    if (!(v >= 0 && v == floor(v) && v <= 1e15))
      return line_fail(r, "%s: must be a whole number (got '%s')", d->name, text);
    *(size_t *)(void *)at = (size_t)v;
    return FB_OK;
  }
  *(double *)(void *)at = v * (d->scale != 0.0 ? d->scale : 1.0);
  return FB_OK;
}

/* The placement the course gives every obstacle, which no line may. */
static int course_own(const char *key)
{
  return !strcmp(key, "angle_deg") || !strcmp(key, "first_contact");
}

/* One `key=value` of item it; given[i] marks its type's parameter i. */
static int course_pair(const course_reader *r, fb_road_course_item *it, char *pair,
                       unsigned char *given)
{
  char *eq = strchr(pair, '=');
  if (!eq || eq == pair || !eq[1])
    return line_fail(r, "expected key=value (got '%s')%s", pair, "");
  *eq = '\0';
  const char *key = pair, *value = eq + 1;
  if (!strcmp(key, "at")) {
    if (given[0])
      return line_fail(r, "%s is given twice%s", "at", "");
    if (fb_parse_decimal_field(value, &it->at, r->text.err))
      return line_fail(r, "%s: %s", "at", r->text.err->msg);
    given[0] = 1;
    return FB_OK;
  }
  if (course_own(key))
    return line_fail(r,
                     "%s is the course's own, the same for every obstacle: give it for the %s",
                     key, "course");
  for (size_t i = 0; i < it->type->nparams; ++i)
    if (!strcmp(it->type->param[i].name, key)) {
      if (given[1 + i])
        return line_fail(r, "%s is given twice%s", key, "");
      given[1 + i] = 1;
      return course_value(r, &it->type->param[i], value, it->block.bytes);
    }
  return line_fail(r, "a %s has no parameter '%s'", it->type->name, key);
}

/* The item's values against its type's declarations and rules. */
static int course_item_check(const course_reader *r, const fb_road_course_item *it,
                             const unsigned char *given)
{
  const fb_road_type *t = it->type;
  if (!given[0])
    return line_fail(r, "the %s needs its distance along the course, at=<m>%s", t->name, "");
  for (size_t i = 0; i < t->nparams; ++i)
    if (t->param[i].need == FB_PARAM_REQUIRED && !given[1 + i] && !course_own(t->param[i].name))
      return line_fail(r, "the %s needs its %s", t->name, t->param[i].name);
  fb_err *err = r->text.err;
  int rc = fb_params_check(t->param, t->nparams, it->block.bytes, err);
  if (!rc && t->ops->check)
    rc = t->ops->check(it->block.bytes, &COURSE_NOMINAL, err);
  if (!rc)
    return FB_OK;
  char field[FB_ERR_FIELD_MAX];
  snprintf(field, sizeof field, "%s", err->part.field);
  return line_fail(r, "%s: %s", field, err->msg);
}

/* One line: `<type> at=<m> key=value ...`, into a new item. */
static int course_line(course_reader *r, char *text)
{
  fb_road_course_params *p = r->p;
  char *comment = strchr(text, '#'); /* a comment after the values */
  if (comment)
    *comment = '\0';
  char *save = NULL, *word = strtok_r(text, " \t", &save);
  const fb_road_type *t = course_type(word);
  if (!t)
    return line_fail(r,
                     "'%s' is no obstacle type: expected halfround, step, cleat, trapezoid, "
                     "pothole or washboard%s",
                     word, "");
  if (p->nitems == COURSE_MAX_ITEMS)
    return line_fail(r, "more than %s obstacles%s", "1000", "");
  fb_road_course_item *grown = realloc(p->item, (p->nitems + 1) * sizeof *grown);
  if (!grown)
    return fb_err_set(r->text.err, FB_ENOMEM, "out of memory reading a course");
  p->item = grown;
  fb_road_course_item *it = &p->item[p->nitems++];
  it->type = t;
  it->at = NAN;
  it->line = r->text.line_no;
  fb_road_params_init(t, &it->block);
  unsigned char given[1 + 32] = {0};
  if (t->nparams > 32)
    return line_fail(r, "the %s declares too many parameters%s", t->name, "");
  int rc = FB_OK;
  while (!rc && (word = strtok_r(NULL, " \t", &save)))
    rc = course_pair(r, it, word, given);
  if (!rc)
    rc = course_item_check(r, it, given);
  if (!rc && p->nitems > 1 && !(it->at >= it[-1].at))
    rc = line_fail(r,
                   "the obstacles are listed in order along the course: this one is before "
                   "the one above it%s%s",
                   "", "");
  return rc;
}

/* The obstacle's advice for a point-contact tire, with its line, if it
 * has edges. */
static void course_hint(fb_road_course_params *p, const fb_road_course_item *it)
{
  fb_road *road = NULL;
  fb_err err;
  if (p->edge_hint[0] || it->type->ops->make(it->block.bytes, &COURSE_NOMINAL, &road, &err))
    return;
  if (fb_road_edges(road, FB_ROAD_LEFT, NULL, 0) + fb_road_edges(road, FB_ROAD_RIGHT, NULL, 0))
    snprintf(p->edge_hint, sizeof p->edge_hint, "%s:%zu: %s", p->file, it->line,
             it->type->ops->edge_hint(it->block.bytes));
  fb_road_free(&road);
}

static void course_clear(fb_road_course_params *p)
{
  free(p->item);
  p->item = NULL;
  p->nitems = 0;
  p->edge_hint[0] = '\0';
}

/* Reads the file once, here: the road is made from what was read. */
static int course_prepare(void *params, fb_err *err)
{
  fb_road_course_params *p = params;
  course_clear(p);
  course_reader r = {.p = p};
  int rc = fb_text_open(&r.text, p->file, "course", err);
  char *text = NULL;
  while (!rc && !(rc = fb_text_next_data_line(&r.text, '#', &text)) && text)
    rc = course_line(&r, text);
  if (!rc && !p->nitems)
    rc =
        fb_err_set(err, FB_EPARSE, "%s: no obstacles (one a line: <type> at=<m> ...)", p->file);
  fb_text_close(&r.text);
  for (size_t i = 0; !rc && i < p->nitems; ++i)
    course_hint(p, &p->item[i]);
  if (rc)
    course_clear(p);
  return rc ? (fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "file"), rc) : FB_OK;
}

static int course_check(const void *params, const fb_road_layout *l, fb_err *err)
{
  (void)l;
  if (((const fb_road_course_params *)params)->nitems)
    return FB_OK;
  return fb_err_set(err, FB_EINVAL, "the course was not read (prepare reads it)"),
         fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "file"), FB_EINVAL;
}

/* ---- Making the road: each obstacle's own road, its pieces between
 * its feature's ends moved to its place, one after another at the
 * height the steps before it left, flat between them. */

typedef struct course_track {
  fb_road_piece *piece; /* owned */
  size_t n, cap;
  double end, z; /* where the last obstacle ended, and the height there */
} course_track;

static int track_add(course_track *t, fb_road_piece q, fb_err *err)
{
  if (t->n == t->cap) {
    const size_t cap = t->cap ? 2 * t->cap : 32;
    fb_road_piece *grown = realloc(t->piece, cap * sizeof *grown);
    if (!grown)
      return fb_err_set(err, FB_ENOMEM, "out of memory for a course's road");
    t->piece = grown;
    t->cap = cap;
  }
  t->piece[t->n++] = q;
  return FB_OK;
}

static fb_road_piece course_flat(double a, double b, double z)
{
  return (fb_road_piece){FB_ROAD_PIECE_LINE, a, b, {z, 0.0, 0.0, 0.0, 0.0}};
}

/* Item it's pieces on track k of its own road (between its feature's
 * ends: not its own flat lead-in and lead-out), moved by its distance
 * along the course and the height reached, after a flat stretch from
 * where the track's last obstacle ended. */
static int course_place(const char *file, const fb_road_course_item *it,
                        const fb_road_params *block, const fb_road *road,
                        const fb_road_layout *l, int k, course_track *t, fb_err *err)
{
  if (!road->track[k].n) /* a flat track: not on it */
    return FB_OK;
  double b = 0.0, e = 0.0;
  it->type->ops->feature(block->bytes, l, k, &b, &e);
  const double begin = b + it->at;
  if (begin < t->end)
    return fb_err_set(err, FB_EINVAL,
                      "%s:%zu: the %s at %g m overlaps the obstacle before it on the %s track, "
                      "which ends %g m further along",
                      file, it->line, it->type->name, it->at,
                      k == FB_ROAD_LEFT ? "left" : "right", t->end - begin),
           fb_err_set_part(err, 0, 0, FB_ERR_NO_ELEMENT, "file"), FB_EINVAL;
  int rc = FB_OK;
  if (!t->n) /* the first: a flat metre before it */
    rc = track_add(t, course_flat(begin - 1.0, begin, 0.0), err);
  else if (begin > t->end)
    rc = track_add(t, course_flat(t->end, begin, t->z), err);
  double last = begin;
  const fb_road_piece *own = road_pieces_of(road->data[k]);
  /* Its lead-out begins where the feature ends, to rounding. */
  const double tail = e - 1e-9 * fmax(1.0, fabs(e));
  for (size_t i = 0; !rc && i < road->track[k].n; ++i) {
    fb_road_piece q = own[i];
    if (q.s_end <= b || q.s_begin >= tail)
      continue;
    q.s_begin += it->at;
    q.s_end += it->at;
    if (q.kind == FB_ROAD_PIECE_ARC)
      q.p[0] += it->at;
    q.p[q.kind == FB_ROAD_PIECE_ARC ? 1 : 0] += t->z;
    rc = track_add(t, q, err);
    last = q.s_end;
  }
  t->end = last;
  t->z += fb_road_height(road, k, e + 1.0); /* a step's rise */
  return rc;
}

/* Item i's block with the course's angle. */
static fb_road_params course_block(const fb_road_course_params *p, size_t i)
{
  fb_road_params b = p->item[i].block;
  ((fb_road_obstacle_params *)(void *)b.bytes)->angle = p->angle;
  return b;
}

static int course_make(const void *params, const fb_road_layout *l, fb_road **out, fb_err *err)
{
  const fb_road_course_params *p = params;
  *out = NULL;
  course_track t[FB_ROAD_NTRACKS] = {{NULL, 0, 0, -INFINITY, 0.0},
                                     {NULL, 0, 0, -INFINITY, 0.0}};
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < p->nitems; ++i) {
    fb_road *road = NULL;
    const fb_road_params b = course_block(p, i);
    rc = p->item[i].type->ops->make(b.bytes, l, &road, err);
    for (int k = 0; !rc && k < FB_ROAD_NTRACKS; ++k)
      rc = course_place(p->file, &p->item[i], &b, road, l, k, &t[k], err);
    fb_road_free(&road);
  }
  for (int k = 0; !rc && k < FB_ROAD_NTRACKS; ++k)
    if (t[k].n)
      rc = track_add(&t[k], course_flat(t[k].end, t[k].end + 1.0, t[k].z), err);
  if (!rc)
    rc = fb_road_new_pieces(t[0].n, t[0].piece, t[1].n, t[1].piece, out, err);
  free(t[0].piece);
  free(t[1].piece);
  return rc;
}

static double course_wheel_start(const void *params, const fb_road_layout *l, double x,
                                 double y)
{
  const fb_road_course_params *p = params;
  return road_oblique_wheel_start(p->angle, p->first_contact, l, x, y);
}

/* From the first obstacle's start to the last one's end on the track
 * (a vertical step's end is its face: it has no length, but is there). */
static void course_feature(const void *params, const fb_road_layout *l, int track,
                           double *begin, double *end)
{
  const fb_road_course_params *p = params;
  *begin = INFINITY;
  *end = -INFINITY;
  for (size_t i = 0; i < p->nitems; ++i) {
    double b = 0.0, e = 0.0;
    const fb_road_params block = course_block(p, i);
    if (!road_obstacle_on_track(block.bytes, track))
      continue;
    p->item[i].type->ops->feature(block.bytes, l, track, &b, &e);
    *begin = fmin(*begin, b + p->item[i].at);
    *end = fmax(*end, e + p->item[i].at);
  }
  if (*begin > *end) /* a flat track: no obstacle on it */
    *begin = *end = road_oblique_edge(p->angle, l, track);
}

static double course_top_hz(const void *params, double speed)
{
  const fb_road_course_params *p = params;
  double hz = 0.0;
  for (size_t i = 0; i < p->nitems; ++i)
    hz = fmax(hz, p->item[i].type->ops->top_hz(p->item[i].block.bytes, speed));
  return hz;
}

static int course_copy(void *to, const void *from, fb_err *err)
{
  fb_road_course_params *t = to;
  const fb_road_course_params *f = from;
  t->file = NULL;
  t->item = NULL;
  if (f->file && !(t->file = fb_strdup(f->file)))
    return fb_err_set(err, FB_ENOMEM, "out of memory for a course's name");
  if (f->nitems && !(t->item = malloc(f->nitems * sizeof *t->item))) {
    free(t->file);
    return fb_err_set(err, FB_ENOMEM, "out of memory for a course");
  }
  if (f->nitems)
    memcpy(t->item, f->item, f->nitems * sizeof *t->item); /* obstacles own nothing */
  return FB_OK;
}

static void course_release(void *params)
{
  fb_road_course_params *p = params;
  free(p->file);
  p->file = NULL;
  course_clear(p);
}

static void course_phrase(const void *params, char *buf, size_t n)
{
  const fb_road_course_params *p = params;
  snprintf(buf, n, "over a course of %zu obstacle%s", p->nitems, p->nitems == 1 ? "" : "s");
}

static const char *course_edge_hint(const void *params)
{
  const fb_road_course_params *p = params;
  return p->edge_hint[0] ? p->edge_hint : NULL;
}

static const fb_road_type_ops course_ops = {.prepare = course_prepare,
                                            .check = course_check,
                                            .make = course_make,
                                            .wheel_start = course_wheel_start,
                                            .feature = course_feature,
                                            .top_hz = course_top_hz,
                                            .copy = course_copy,
                                            .release = course_release,
                                            .phrase = course_phrase,
                                            .edge_hint = course_edge_hint};

const fb_road_type fb_road_type_course = {
    .name = "course",
    .doc = "a course of obstacles listed in a file (docs/roads.md, \"Courses\")",
    .param = course_params,
    .nparams = sizeof course_params / sizeof course_params[0],
    .params_size = sizeof(fb_road_course_params),
    .ops = &course_ops,
};
