/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: arithmetic expressions over named parameters and time, and
 * time functions used by modulated sources.
 *
 * Expression grammar (precedence low to high):
 *   expr   := term (('+'|'-') term)*
 *   term   := unary (('*'|'/') unary)*
 *   unary  := ('-'|'+') unary | power
 *   power  := atom ('^' unary)?            (right associative)
 *   atom   := number | name | name '(' expr (',' expr)* ')' | '(' expr ')'
 * Names are looked up in an fb_symtab when the expression is parsed; the
 * name `t` (time, s) is free unless the table defines it. Constants: pi, e.
 * Functions: sin cos tan asin acos atan atan2 exp log log10 sqrt abs
 * min max pow floor ceil sign step(x) (1 for x >= 0 else 0) ramp(x)
 * (max(x, 0)). */
#ifndef FLEXBOND_EXPR_H
#define FLEXBOND_EXPR_H

#include <stddef.h>
#include <stdio.h>

#include "flexbond/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A table of named constants (parameters). Names are copied. */
typedef struct fb_symtab fb_symtab;
int fb_symtab_new(fb_symtab **out, fb_err *err);
void fb_symtab_free(fb_symtab **tab);
/* Defines or redefines name. */
int fb_symtab_set(fb_symtab *tab, const char *name, double value, fb_err *err);
/* Returns 1 and stores the value if name is defined, 0 otherwise. */
int fb_symtab_get(const fb_symtab *tab, const char *name, double *value);
/* Copy of all definitions of src into dst (dst's own entries of the same
 * name are replaced). */
int fb_symtab_merge(fb_symtab *dst, const fb_symtab *src, fb_err *err);
size_t fb_symtab_size(const fb_symtab *tab);
/* Name of the i-th entry in definition order, NULL if i is out of range. */
const char *fb_symtab_name(const fb_symtab *tab, size_t i);

typedef struct fb_expr fb_expr;
/* Parses text. Unknown names (other than t) and syntax errors are
 * FB_EPARSE with the column (1-based) in the message, e.g.
 * "column 7: unknown name 'kss' (did you mean 'ks'?)". syms may be NULL. */
int fb_expr_parse(const char *text, const fb_symtab *syms, fb_expr **out, fb_err *err);
double fb_expr_eval(const fb_expr *e, double t);
/* 1 if the value depends on t. */
int fb_expr_uses_time(const fb_expr *e);
int fb_expr_clone(const fb_expr *e, fb_expr **out, fb_err *err);
void fb_expr_free(fb_expr **e);
/* Parses and evaluates a time-independent expression; FB_EPARSE if it
 * uses t, FB_EINVAL if the value is not finite. */
int fb_expr_eval_const(const char *text, const fb_symtab *syms, double *value, fb_err *err);

/* Writes e as text that fb_expr_parse reads back as the same expression
 * (the same operations in the same order on the same constants, so the
 * same values for every t): parameters appear as their values, numbers
 * in at most 17 significant digits, parentheses only where needed.
 * Returns 0, or -1 (out of memory, or a constant that is not finite). */
int fb_expr_write(const fb_expr *e, FILE *fp);

/* A scalar function of time u(t). */
typedef struct fb_tfun fb_tfun;
int fb_tfun_new_const(double value, fb_tfun **out, fb_err *err);
/* before for t < t0, after for t >= t0. Breakpoint at t0. */
int fb_tfun_new_step(double t0, double before, double after, fb_tfun **out, fb_err *err);
/* offset + amplitude * sin(2 pi freq_hz t + phase_rad). */
int fb_tfun_new_sine(double amplitude, double freq_hz, double phase_rad, double offset,
                     fb_tfun **out, fb_err *err);
/* Piecewise-linear through (times[i], values[i]), times strictly
 * increasing, n >= 1, held constant outside. Arrays are copied.
 * Breakpoints at every interior knot. */
int fb_tfun_new_table(size_t n, const double *times, const double *values, fb_tfun **out,
                      fb_err *err);
/* Reads a table from a CSV file with a header line; time_col and
 * value_col name header columns. Errors say path:line. */
int fb_tfun_new_table_csv(const char *path, const char *time_col, const char *value_col,
                          fb_tfun **out, fb_err *err);
/* Takes ownership of *e (sets it to NULL). */
int fb_tfun_new_expr(fb_expr **e, fb_tfun **out, fb_err *err);
/* User callback: fn(t, ctx). The caller keeps ownership of ctx and must
 * keep it alive as long as the function. Optional breakpoints copied. */
typedef double (*fb_tfun_fn)(double t, void *ctx);
int fb_tfun_new_callback(fb_tfun_fn fn, void *ctx, size_t nbreak, const double *breakpoints,
                         fb_tfun **out, fb_err *err);
/* As fb_tfun_new_callback, but the function keeps its own copy of the
 * ctx_size bytes at ctx (plain data without pointers), so the caller need
 * not keep ctx alive; clones copy it again. */
int fb_tfun_new_callback_copy(fb_tfun_fn fn, const void *ctx, size_t ctx_size, size_t nbreak,
                              const double *breakpoints, fb_tfun **out, fb_err *err);
int fb_tfun_clone(const fb_tfun *f, fb_tfun **out, fb_err *err);
void fb_tfun_free(fb_tfun **f);

double fb_tfun_eval(const fb_tfun *f, double t);
/* 1 if the value never changes (a constant, or an expression without t). */
int fb_tfun_is_constant(const fb_tfun *f);
/* Times where u or its slope jumps (sorted, ascending). Returns how many
 * there are; writes at most max of them to bp (bp may be NULL). */
size_t fb_tfun_breakpoints(const fb_tfun *f, double *bp, size_t max);

/* What a time function is, for writers (fb_model_write): its kind and
 * the parameters it was made from. Pointers are the function's own,
 * valid while it lives. */
typedef enum fb_tfun_kind {
  FB_TFUN_CONST,
  FB_TFUN_STEP,
  FB_TFUN_SINE,
  FB_TFUN_TABLE,
  FB_TFUN_EXPR,
  FB_TFUN_CALLBACK
} fb_tfun_kind;
typedef struct fb_tfun_info {
  fb_tfun_kind kind;
  double value;                                 /* CONST */
  double t0, before, after;                     /* STEP */
  double amplitude, freq_hz, phase_rad, offset; /* SINE */
  size_t n;                                     /* TABLE: knots */
  const double *times, *values;                 /* TABLE */
  const fb_expr *expr;                          /* EXPR */
  fb_tfun_fn fn;                                /* CALLBACK: the function */
  const void *ctx;                              /* CALLBACK: its context */
} fb_tfun_info;
/* Fills *out (unused fields zero or NULL). */
void fb_tfun_describe(const fb_tfun *f, fb_tfun_info *out);

#ifdef __cplusplus
}
#endif
#endif
