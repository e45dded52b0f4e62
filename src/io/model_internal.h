/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: internals of the YAML model loader (src/io/model*.c).
 *
 * The loader walks a libfyaml document tree. Every error is reported as
 * "FILE:LINE:COL: KEY: message", where KEY is the path of the offending
 * node (e.g. "subsystems.corner.elements[2].k"); see ml_fail(). Subsystem
 * definitions are re-read from the tree for each instance, so the loader
 * keeps no copies of the document beyond what it hands to the graph. */
#ifndef FLEXBOND_IO_MODEL_INTERNAL_H
#define FLEXBOND_IO_MODEL_INTERNAL_H

#include <libfyaml.h>
#include <stddef.h>

#include "flexbond/bg.h"
#include "flexbond/error.h"
#include "flexbond/expr.h"
#include "flexbond/mat.h"

/* A subsystem instance under construction, innermost first; the chain is
 * appended to messages so an error inside a definition says which
 * instance (and so which parameter values) triggered it. */
typedef struct ml_frame {
  const char *instance;         /* instance name */
  struct fy_node *at;           /* the instance's element mapping */
  const struct ml_frame *outer; /* enclosing instance, NULL at top level */
} ml_frame;

/* Loader state shared by all sections. */
/* The files a document names, resolved, each once in reading order
 * (owned strings). */
typedef struct ml_paths {
  char **path;
  size_t n, cap;
} ml_paths;
void ml_paths_release(ml_paths *p);

/* Where each element and bond of the model's graph was written, by its
 * full name in that graph ("front.Ks", "front.b1": instance names joined
 * by '.'), for errors the graph raises after loading (fb_err.origin,
 * fb_model_blame): its key path ("bonds[2]"), line and column, and tail,
 * the instance chain " (in instance 'front' at FILE:LINE:COL)" or ""
 * (owned strings). */
typedef struct ml_site {
  int kind; /* FB_ORIGIN_ELEMENT or FB_ORIGIN_BOND */
  char *name, *tail;
  char *key;        /* "" at the document's root */
  int line, column; /* 0 unknown */
} ml_site;

/* The sites of one file (file: its display name, owned). */
typedef struct ml_sites {
  ml_site *site;
  size_t n, cap;
  char *file;
} ml_sites;
void ml_sites_release(ml_sites *s);
/* The site of kind named name, or NULL. */
const ml_site *ml_sites_find(const ml_sites *s, int kind, const char *name);
/* Records in err the file, line, column and key of site (of sites). */
void ml_site_set_fields(const ml_sites *sites, const ml_site *site, fb_err *err);
/* "FILE:LINE:COL: KEY: " of site (of sites), as ml_fail begins a
 * message, into buf (size bytes). */
void ml_site_head(const ml_sites *sites, const ml_site *site, char *buf, size_t size);

/* What a file may legally say but almost never means (fb_model_warning):
 * each an fb_err, located as an error would be (owned array). */
typedef struct ml_warnings {
  fb_err *warning;
  size_t n, cap;
} ml_warnings;
void ml_warnings_release(ml_warnings *w);
/* model_warn.c: appends to w one warning per bond written in the file
 * (its site in sites; the instances of one definition share it) whose
 * from end is an I, C or R element of bg: the motion is the same, but the element's state and
 * the bond's effort and power read with the opposite sign to the usual
 * drawing; with a nonlinear law (a table, a contact), compression and
 * extension swap and the motion differs. FB_ENOMEM only. */
int ml_warn_power_out(const fb_bg *bg, const ml_sites *sites, ml_warnings *w, fb_err *err);

typedef struct ml_ctx {
  const char *file;         /* display name used in messages */
  const char *base_dir;     /* directory for relative file references */
  fb_err *err;              /* never NULL inside the loader */
  struct fy_node *defs;     /* the `subsystems` mapping, or NULL */
  size_t ndefs;             /* number of definitions in defs */
  unsigned char *used;      /* used[i]: definition i has been instantiated */
  const fb_symtab *globals; /* the model's `parameters` */
  fb_bg_domain domain;      /* model default bond domain */
  const ml_frame *frames;   /* innermost instance being built, or NULL */
  ml_paths *inputs;         /* where ml_resolve_path records, or NULL */
  ml_sites *sites;          /* where ml_site_record records, or NULL (while
                               building graphs the model does not keep) */
} ml_ctx;

/* A name declared in a graph being built: an element or a subsystem
 * instance. Used to check port references before handing them to fb_bg. */
typedef struct ml_entry {
  const char *name;     /* borrowed from the document */
  fb_bg_kind kind;      /* element kind (meaningless for instances) */
  size_t nports;        /* numbered ports ("E.1" .. "E.n"); 1 for one-ports */
  long def;             /* definition index of an instance, -1 for elements */
  struct fy_node *node; /* the element's mapping, for "first defined at" */
} ml_entry;

/* A graph being built (the model itself or one subsystem instance) with
 * the parameter table its expressions see. */
typedef struct ml_scope {
  fb_bg *bg;
  const fb_symtab *syms;
  ml_entry *entries;
  size_t nentries, capacity;
} ml_scope;

/* ---- model_yaml.c: document, locations, messages, typed getters. */

/* A parsed document with the parser and diagnostics that own it. */
typedef struct ml_yaml {
  struct fy_diag *diag;
  struct fy_parser *parser;
  struct fy_document *doc;
} ml_yaml;

/* Parses exactly one YAML document from text and resolves its aliases
 * and merge keys. A scalar whose text holds a NUL (a "\0" escape) or a
 * key with any control character is refused, located. FB_EPARSE with "FILE:LINE:COL: YAML:
 * message" (libfyaml's first diagnostic) on a syntax error, and at the alias that crosses the
 * bound, before anything is copied, if the aliases would expand the document to more than
 * 100000 nodes or ten times its written node count, whichever is more, or nest it more than 256
 * levels deep (model_yaml.c, "Bounding alias expansion"); nothing is printed. */
int ml_yaml_parse(const char *text, size_t len, const char *file, ml_yaml *y, fb_err *err);
void ml_yaml_release(ml_yaml *y);

/* Records "FILE:LINE:COL: KEY: message" (plus the instance chain) for the
 * node at; returns code. */
int ml_fail(const ml_ctx *c, struct fy_node *at, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* As ml_fail for the key node `key` of mapping map (the key node has no
 * parent link in libfyaml, so the path is built from map). */
int ml_fail_key(const ml_ctx *c, struct fy_node *map, struct fy_node *key, int code,
                const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
#if defined(__clang_analyzer__)
/* For the static analyzer only, as fb_err_set in flexbond/error.h: both return their code. */
#define ml_fail(c, at, code, ...) (ml_fail((c), (at), (code), __VA_ARGS__), (code))
#define ml_fail_key(c, map, key, code, ...)                                                    \
  (ml_fail_key((c), (map), (key), (code), __VA_ARGS__), (code))
#endif
/* Prefixes the message already in c->err (from a library call) with the
 * location of at, appends the instance chain; returns c->err->code. */
int ml_blame(const ml_ctx *c, struct fy_node *at);
/* As ml_blame without the key path, for messages that name their key. */
int ml_blame_located(const ml_ctx *c, struct fy_node *at);
/* Records in c->sites (if any) that the element or bond (kind, as
 * fb_err.origin) named name in the graph being built was written at node
 * at, under its full name in the model's graph. */
int ml_site_record(const ml_ctx *c, int kind, const char *name, struct fy_node *at);
/* 1-based line of node n, 0 if unknown. */
int ml_line(struct fy_node *n);
/* 1-based line and column of node n (or of its nearest ancestor that
 * has them: alias copies have none); 0 if unknown. */
int ml_mark(struct fy_node *n, int *line, int *col);

/* 1 if n is absent or a YAML null (empty, ~, null). */
int ml_is_null(struct fy_node *n);
/* Value of key in map; NULL if absent. *key_node gets the key (may be NULL). */
struct fy_node *ml_get(struct fy_node *map, const char *key, struct fy_node **key_node);
/* As ml_get, but an absent or null key is an error naming the key. */
int ml_require(const ml_ctx *c, struct fy_node *map, const char *key, struct fy_node **out);
/* FB_EPARSE unless n is a mapping / a sequence; what names the expectation. */
int ml_expect_map(const ml_ctx *c, struct fy_node *n, const char *what);
int ml_expect_seq(const ml_ctx *c, struct fy_node *n, const char *what);
/* Every key of map must be in the NULL-terminated list allowed. */
int ml_check_keys(const ml_ctx *c, struct fy_node *map, const char *const *allowed);
/* The two formats' files are told apart by their root's key: a model
 * file's "model", a scenario file's "scenario" (io/input_kind.h). Given
 * the root of a document read as the format whose key is own, FB_EPARSE at
 * the other format's key when the root has it and not own: the file is the
 * other kind, and the message says which commands read it. */
int ml_refuse_other_format(const ml_ctx *c, struct fy_node *root, const char *own);
/* Scalar text (owned by the document) that is one line: a name, unit,
 * label, file name, choice or reference. Every string value the loaders
 * take goes through here, so a control character (a line break, tab,
 * escape, DEL; model_yaml.c, "Text of scalars") is refused at its
 * FILE:LINE:COL: KEY before it can reach an output file. */
int ml_string(const ml_ctx *c, struct fy_node *n, const char **out);
/* As ml_string for free text (a description), which may hold tabs and
 * line breaks but no other control character. */
int ml_text(const ml_ctx *c, struct fy_node *n, const char **out);
/* 1 if s starts with a letter or '_' and has only letters, digits, '_'. */
int ml_is_identifier(const char *s);
/* The longest name: a scenario's names become mesh node sets behind a
 * prefix of up to 5 characters ("SUSP_LF", "MASS_BATTERY"), and a node
 * set's name, an Abaqus label, has at most 80 (FB_MESH_NAME_MAX); 64
 * leaves room, and a longer name is a slip, not a need. */
#define ML_NAME_MAX 64
/* A name of 1 to ML_NAME_MAX letters, digits and '_', not starting with a
 * digit (what: "element name", ...). */
int ml_name(const ml_ctx *c, struct fy_node *n, const char *what, const char **out);
/* YAML boolean true/false (also yes/no, on/off). */
int ml_bool(const ml_ctx *c, struct fy_node *n, int *out);
/* A number or a constant expression over syms; finite. */
int ml_number(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, double *out);
/* Optional number: *out keeps its value (the default) when key is absent. */
int ml_opt_number(const ml_ctx *c, struct fy_node *map, const char *key, const fb_symtab *syms,
                  double *out);
/* An integer in [lo, hi], given as a number or expression. */
int ml_count(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, size_t lo, size_t hi,
             size_t *out);
/* Joins base_dir and a relative path (absolute paths are kept) into a new
 * string the caller frees, and records it in c->inputs. */
int ml_resolve_path(const ml_ctx *c, struct fy_node *at, const char *path, char **out);

/* ---- model_values.c: vectors, matrices, time functions. */

/* A list of numbers (or a single one when allow_scalar) of exactly n
 * entries, or any length >= 1 when n is 0; *out is malloc'd, *len set. */
int ml_vector(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, size_t want,
              int allow_scalar, double **out, size_t *len);
/* A matrix: a list of rows, {diagonal: [..]} or {mtx: file}. */
int ml_matrix(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, fb_mat **out);
/* A force-velocity table `{file, velocity, force}` (CSV columns, velocity
 * default "v") or `{points: [[v, F], ...]}` into a new *law; errors at the
 * table's YAML location (and the CSV's path:line). */
int ml_table_law(const ml_ctx *c, const fb_symtab *syms, struct fy_node *table,
                 fb_table_law **law);
/* A source value: number or expression of t, {step:..}, {sine:..},
 * {table:..}. */
int ml_tfun(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, fb_tfun **out);

/* ---- model_road.c: `{road: {speed, s0, output, bump|iso8608|profile}}`,
 * a road wheel's velocity or height (fb_road_wheel_new). */
int ml_tfun_road(const ml_ctx *c, struct fy_node *n, const fb_symtab *syms, fb_tfun **out);

/* ---- model_contact.c: the `contact` element type, a unilateral
 * spring-damper pair (fb_bg_add_unilateral_contact). */
int ml_contact(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *name, ml_entry *e);

/* ---- model_elements.c. */

/* Adds the element described by mapping el to scope s and records it in
 * the scope's entries. */
int ml_add_element(ml_ctx *c, ml_scope *s, struct fy_node *el);
/* 1 if name is a built-in element type ("I", "0", "composite", ...). */
int ml_is_builtin_type(const char *name);
/* Entry named name in s, or NULL. */
const ml_entry *ml_scope_find(const ml_scope *s, const char *name);
/* Appends an entry (name borrowed). */
int ml_scope_add(const ml_ctx *c, ml_scope *s, const ml_entry *e);
void ml_scope_release(ml_scope *s);

/* ---- model_subsys.c: definitions, instances, ports, bonds. */

/* Checks the `subsystems` mapping (names, shapes) and rejects recursive
 * definitions, naming the chain. */
int ml_defs_check(ml_ctx *c);
/* Index of the definition named name, -1 if none. */
long ml_def_find(const ml_ctx *c, const char *name);
/* Name of definition i. */
const char *ml_def_name(const ml_ctx *c, size_t i);
/* Builds definition def into a new graph and adopts it into s under the
 * name of element el (whose `parameters` override the defaults). */
int ml_instantiate(ml_ctx *c, ml_scope *s, struct fy_node *el, const char *instance,
                   size_t def);
/* Builds each definition never instantiated once with its defaults, so
 * errors in unused definitions are still reported. */
int ml_defs_validate_unused(ml_ctx *c);
/* Adds the `elements` and `bonds` of body (the model root or a definition). */
int ml_build_body(ml_ctx *c, ml_scope *s, struct fy_node *body);
/* Evaluates the mapping defaults (name: number or expression, in order;
 * may be NULL) into tab, each seeing the names before it. A name defined
 * in given (may be NULL: an instance's overrides, already evaluated) takes
 * that value instead. */
int ml_parameters(const ml_ctx *c, struct fy_node *defaults, fb_symtab *tab,
                  const fb_symtab *given);
/* Domain name ("translation", ...) to enum. */
int ml_domain(const ml_ctx *c, struct fy_node *n, fb_bg_domain *out);

#endif
