/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: a file format declared as a table of keys (src/io/schema.c).
 *
 * Each key of a YAML format is declared once, in an sch_table: its path,
 * type, unit, range, default, choices, one line of documentation, and
 * where its value goes in the C struct being filled. From that one table
 * the engine reads a document (types, unknown keys with "did you mean"
 * suggestions, required keys, defaults, keys inherited from others),
 * checks a struct's values against the ranges, visits every value, and
 * writes the format's reference tables in Markdown. Rules between keys
 * that a table cannot state are the format's own hooks (sch_ops).
 *
 * Paths are relative to their table: "hull.material.young" in the root
 * table; a list's items have a table of their own ("spring_k" in the
 * items of "suspensions.axles"), written "suspensions.axles[].spring_k"
 * in the documentation. Errors are the model loader's located ones
 * (io/model_internal.h): "FILE:LINE:COL: KEY: message".
 *
 * A reader may be given overrides, values to read in place of the file's
 * at full key paths ("suspensions.axles[1].spring_k"). */
#ifndef FLEXBOND_IO_SCHEMA_H
#define FLEXBOND_IO_SCHEMA_H

#include <stddef.h>
#include <stdio.h>

#include "core/util.h"
#include "io/model_internal.h"

typedef enum sch_type {
  SCH_NUMBER,  /* a number or an expression over `parameters`, finite */
  SCH_WHOLE,   /* a whole number in the key's range */
  SCH_CHOICE,  /* one of the key's choices; its index is the value */
  SCH_NAME,    /* letters, digits and '_', starting with a letter or '_' */
  SCH_TEXT,    /* one line of text (or several with sch_key.lines) */
  SCH_FILE,    /* a file name, resolved from the document's directory */
  SCH_NUMBERS, /* a list of numbers */
  SCH_SECTION, /* a mapping of keys of its own */
  SCH_LIST,    /* a list of mappings, each read with the key's item table */
  SCH_CUSTOM   /* read by sch_ops.read (a value of several shapes) */
} sch_type;

/* Where a value goes: the C type at sch_key.offset in the struct filled,
 * or nowhere (a value only inherited or only checked, or stored by a
 * hook). */
typedef enum sch_store {
  SCH_STORE_NONE,
  SCH_STORE_DOUBLE,
  SCH_STORE_INT,
  SCH_STORE_LONG,
  SCH_STORE_SIZE,
  SCH_STORE_U64,
  SCH_STORE_STRING /* char *, owned by the struct */
} sch_store;

typedef enum sch_need {
  SCH_REQUIRED, /* must be written (in a section that is there) */
  SCH_OPTIONAL, /* may be left out: nothing is stored */
  SCH_DEFAULT,  /* left out: sch_key.def (or sch_key.def_list) */
  SCH_INHERIT   /* left out: the value of the root key sch_key.inherit */
} sch_need;

/* Ends of a range, sch_key.bounds. Open ends exclude their bound. */
enum {
  SCH_LO = FB_RANGE_LO,
  SCH_HI = FB_RANGE_HI,
  SCH_LO_OPEN = FB_RANGE_LO_OPEN,
  SCH_HI_OPEN = FB_RANGE_HI_OPEN
};

/* Longest key path. */
enum { SCH_PATH_MAX = 256 };

typedef struct sch_key sch_key;
typedef struct sch_table sch_table;
typedef struct sch_reader sch_reader;

/* The format's code for what a table cannot say; every member may be
 * NULL. base is the struct the key's table fills (an item's for a key of
 * an item table). */
typedef struct sch_ops {
  /* SCH_CUSTOM: reads the value at node into base. */
  int (*read)(sch_reader *r, const sch_key *k, struct fy_node *node, void *base);
  /* SCH_NUMBERS not stored as doubles: stores the n numbers read (at
   * node; NULL for the default) into base. */
  int (*store_list)(sch_reader *r, const sch_key *k, struct fy_node *node, const double *v,
                    size_t n, void *base);
  /* SCH_NUMBER: the stored value of a value in the file's unit and back
   * (km/h to m/s); the identity when NULL. */
  double (*to_struct)(double v);
  double (*from_struct)(double v);
  /* SCH_CUSTOM and SCH_NUMBERS not stored as doubles: the stored value
   * as text, for sch_each_value. */
  void (*format)(const sch_key *k, const void *base, char *buf, size_t size);
  /* 0 when the value is absent from base (a section left out, the other
   * of two alternatives): sch_check and sch_each_value skip it and, for
   * a section, every key in it. */
  int (*present)(const sch_key *k, const void *base);
  /* SCH_SECTION: before its keys are read, when the file has it. */
  int (*begin)(sch_reader *r, const sch_key *k, struct fy_node *node, void *base);
  /* SCH_SECTION (and the root, through sch_table.done): after its keys
   * are read; node is NULL when the section was left out. */
  int (*done)(sch_reader *r, const sch_key *k, struct fy_node *node, void *base);
  /* SCH_LIST: after an item (at node, its origins recorded from mark
   * on, under the key path item_path) is read into item (the first of
   * the sch_key.per_item it makes). */
  int (*item_end)(sch_reader *r, const sch_key *k, struct fy_node *node, const char *item_path,
                  size_t mark, void *base, void *item);
} sch_ops;

struct sch_key {
  const char *path; /* relative to the table, segments joined by '.' */
  sch_type type;
  const char *unit; /* NULL for none */
  unsigned bounds;  /* SCH_LO | SCH_HI | SCH_*_OPEN, 0: any finite value */
  double lo, hi;    /* in the file's unit */
  sch_need need;
  double def;                  /* SCH_DEFAULT: number, whole or choice index */
  const double *def_list;      /* SCH_DEFAULT of SCH_NUMBERS */
  const char *inherit;         /* SCH_INHERIT: the root key's path */
  const char *one_of;          /* keys of one mapping with the same label: at most
                                  one written, exactly one if all are required */
  const char *const *choices;  /* SCH_CHOICE, NULL-terminated */
  size_t min_items, max_items; /* SCH_NUMBERS, SCH_LIST; max 0: no limit */
  int lines;                   /* SCH_TEXT: line breaks allowed */
  /* A position along the vehicle's axis 1 (x), 2 (y) or 3 (z), or
   * SCH_AXIS_POINT: a point, SCH_NUMBERS of 3 doubles [x, y, z]; in the
   * file's frame as written, stored relative to the hull's centre of mass
   * once the loader has completed the description; 0: none. */
  int axis;
  const char *type_doc; /* SCH_CUSTOM: the type for the documentation */
  const char *doc;      /* one line */
  const char *why;      /* why the range is what it is, added to a range error
                           ("about a day of solver steps ..."); may be NULL */
  /* What real vehicles have, in the file's unit (plausible_why says so):
   * a value outside is legal but almost never meant (20 for a thickness
   * in m, meant as mm), a warning at its file:line (sch_check_plausible).
   * plausible_why NULL: no such range. */
  double plausible_lo, plausible_hi;
  const char *plausible_why;
  /* The unit a slip most often means (a thickness in mm), which the
   * warning also gives the value in: value * plausible_scale
   * plausible_unit. NULL: none. */
  const char *plausible_unit;
  double plausible_scale;
  sch_store store;        /* SCH_NUMBERS: SCH_STORE_DOUBLE, max_items of them at offset */
  size_t offset;          /* SCH_LIST: of the pointer to its items (allocated) */
  const sch_table *items; /* SCH_LIST */
  const char *view;       /* SCH_LIST: the logical name of the struct's items
                             ("corners"); lists with one view fill the same items */
  /* SCH_LIST, and SCH_NUMBERS stored of no fixed length: the items'
   * number (a size_t) is at count_at. SCH_LIST: each item is item_size
   * bytes, and an item of the file makes per_item of them (0: one).
   * named: they are visited by their key "name" ("corners.LF"), else by
   * index. */
  size_t count_at, item_size, per_item;
  int named;
  const sch_ops *ops;
  /* The description's member the key gives (its name in the struct its
   * table fills: "spring_k", "hull_mesh.x_rear"), set by the store macros
   * or, for a section or a custom value, by the table: what maps an
   * error's fb_err.part back to the key. NULL: none. */
  const char *member;
  /* SCH_NUMBER stored as a double: the stored value is the file's times
   * scale (0: 1; after ops->to_struct, if any). */
  double scale;
  /* What the hooks of a generated key need (a road type, a parameter's
   * declaration); NULL for the table's own keys. */
  const void *data;
};

struct sch_table {
  const sch_key *key;
  size_t n;
  /* After the whole table is read (node: its mapping). */
  int (*done)(sch_reader *r, struct fy_node *node, void *base);
};

/* Where a value was read from, and the value, for inheritance. */
typedef struct sch_origin {
  char *key;  /* logical key path (sch_origins_relabel renames items') */
  char *path; /* key path in the file */
  int line, column;
  int given;            /* 0: a default, at the section it would be in */
  double number;        /* SCH_NUMBER, SCH_WHOLE, SCH_CHOICE */
  const char *override; /* the label of the override read there, else NULL */
} sch_origin;

/* A value to read in place of the file's ("--set road.bump.height=0.2"),
 * as if the file had it at path: a key the file leaves out is added at
 * its section (made too when the file leaves that out), every other key
 * keeps the file's value. */
typedef struct sch_override {
  char path[SCH_PATH_MAX];       /* full key path in the file ("outputs[0].figure") */
  const char *value;             /* its text, one scalar as it is (never YAML structure) */
  char label[FB_ERR_SOURCE_MAX]; /* "--set KEY=VALUE": the source of its origins and
                                    errors; "": errors unlabelled (a path checked alone) */
  struct fy_node *node;          /* set by sch_place: the value in the document */
  int read;                      /* set by sch_read: a step of the reader took it */
} sch_override;

struct sch_reader {
  ml_ctx *c; /* file, errors, `parameters` */
  void *user;
  sch_override *ov; /* the overrides, NULL if none (not owned) */
  size_t nov;
  sch_origin *origin; /* in reading order, owned */
  size_t norigins, cap;
};

/* Reads the mapping root (its key paths from "") into base, r's
 * overrides in place of the file's values (sch_place first). An error in
 * an override's value, and one that no step of the reader took, names it
 * ("--set K=V: FILE:LINE:COL: KEY: ...", its source FB_SOURCE_OVERRIDE). */
int sch_read(sch_reader *r, const sch_table *t, struct fy_node *root, void *base);
void sch_reader_release(sch_reader *r);
/* Puts each override's value into the document at its path, at the line
 * and column of the value it replaces (of the section it goes into when
 * the file leaves the key out), so that the reader's every step and
 * message sees it there. FB_EINVAL naming the override for a path that
 * is malformed or names no value of t and the file (no such key, with a
 * suggestion; an item beyond a list's; a section or a list). */
int sch_place(sch_reader *r, const sch_table *t, struct fy_node *root);
/* Names o, if it has a label, as the source of the error in err: the
 * label before its message. */
void sch_blame_override(fb_err *err, const sch_override *o);
/* "a, b, c": the names of t's keys in its mapping at table path pre. */
void sch_key_names(const sch_table *t, const char *pre, char *buf, size_t size);

/* Appends the items that one item of list k makes to base's (zeroed),
 * *item the first. */
int sch_list_add(const sch_reader *r, const sch_key *k, void *base, void **item);
/* The key of t at path, NULL if none. */
const sch_key *sch_key_of(const sch_table *t, const char *path);
/* The key a full path of a file names ("suspensions.axles[0].spring_k":
 * the items' key spring_k of list suspensions.axles; "...bulkheads[1]": a
 * number of the list bulkheads), NULL if none. */
const sch_key *sch_key_at_path(const sch_table *t, const char *path);
/* An item's name (list k's items named), NULL if none. */
const char *sch_item_name(const sch_key *k, const void *item);

/* Records that the value at node (a key the table does not list, such
 * as one point of a list) has the key path key. */
int sch_record(sch_reader *r, const char *key, struct fy_node *node);
/* For the origins from mark on whose key starts with item_path: the key
 * with that prefix replaced by prefix ("corners.LF"), in place, or on
 * copies appended when copy is set (an item that makes two). */
int sch_origins_relabel(sch_reader *r, size_t mark, const char *item_path, const char *prefix,
                        int copy);
/* Records that the value at key path key is the one read at from (its
 * origin copied: an inherited value). FB_EINVAL when from has none. */
int sch_origin_inherit(sch_reader *r, const char *key, const char *from);
/* The origin of the value read at path, NULL if none. */
const sch_origin *sch_origin_find(const sch_reader *r, const char *path);

/* One value of a struct, for sch_check and sch_each_value. */
enum { SCH_AXIS_POINT = 4 };

typedef struct sch_value {
  const sch_key *key;
  const char *path; /* logical key path ("corners.LF.spring_k") */
  const void *base; /* the struct holding it */
  double number;    /* in the file's unit (SCH_NUMBER, SCH_WHOLE, SCH_CHOICE) */
  const char *text; /* the stored text (a string, a choice), else NULL */
} sch_value;

typedef int (*sch_value_fn)(const sch_value *v, void *ctx);

/* Calls fn for every value of base the table stores, present, in table
 * order, items in their order; stops at fn's first nonzero return. */
int sch_each(const sch_table *t, const void *base, sch_value_fn fn, void *ctx);
/* The range check of one value: FB_OK, or FB_EINVAL with the message
 * "must be > 0 N/m (got -1)" and err's key set to v->path (unlocated). */
int sch_check_value(const sch_value *v, fb_err *err);
/* 1 if v (a number) lies outside its key's plausible range, with the
 * warning "VALUE UNIT is implausible: WHY" in w ("VALUE UNIT is
 * implausible: VALUE UNIT = VALUE' UNIT'; WHY" with a plausible_unit),
 * its key v->path
 * (unlocated); else 0, w untouched. */
int sch_check_plausible(const sch_value *v, fb_err *w);
/* v's value as text ("145300", "bilateral"). */
void sch_format(const sch_value *v, char *buf, size_t size);

/* Writes the table's keys as Markdown tables: one per section of the
 * root (keys of the root itself first), one per item table. */
void sch_markdown(const sch_table *t, FILE *fp);

#endif
