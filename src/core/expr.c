/* SPDX-License-Identifier: BSD-3-Clause */
/* Arithmetic expressions (see flexbond/expr.h for the grammar).
 *
 * A recursive-descent parser, one function per grammar rule, compiles the
 * text to postfix code for a small stack machine (Aho, Lam, Sethi, Ullman,
 * "Compilers", 2nd ed., sec. 2.8: syntax-directed translation to postfix).
 * Parameters are looked up at parse time and become constants, so every
 * operator whose operands are all constants is evaluated while parsing
 * (constant folding). The evaluator runs the code on a fixed-size stack in
 * its own frame: it never allocates, and the parser refuses expressions
 * that would need a deeper stack.
 *
 * Unary minus binds looser than '^' (the grammar's unary := '-' unary |
 * power), so -2^2 = -(2^2) = -4 as in mathematics, and 2^-1 = 0.5. */
#include "flexbond/expr.h"

#include <assert.h>
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/textfile.h"
#include "core/util.h"

enum {
  EXPR_STACK_MAX = 64,   /* evaluation stack slots; a + (b + (c + ...)) needs one per level */
  EXPR_NEST_MAX = 200,   /* nested unary/parenthesis levels, bounds the parser's recursion */
  SUGGEST_NAME_MAX = 64, /* longer names get no did-you-mean suggestion */
  SUGGEST_DIST_MAX = 2   /* largest edit distance worth suggesting */
};

static const double CONST_PI = 3.14159265358979323846;
static const double CONST_E = 2.71828182845904523536;

/* Stack machine instructions: pushes (arity 0), then unary operators, then
 * binary ones; op_arity relies on this order. */
typedef enum opcode {
  OP_CONST,
  OP_TIME,
  OP_NEG,
  OP_SIN,
  OP_COS,
  OP_TAN,
  OP_ASIN,
  OP_ACOS,
  OP_ATAN,
  OP_EXP,
  OP_LOG,
  OP_LOG10,
  OP_SQRT,
  OP_ABS,
  OP_FLOOR,
  OP_CEIL,
  OP_SIGN,
  OP_STEP,
  OP_RAMP,
  OP_ADD,
  OP_SUB,
  OP_MUL,
  OP_DIV,
  OP_POW,
  OP_ATAN2,
  OP_MIN,
  OP_MAX
} opcode;

typedef struct instr {
  opcode op;
  double k; /* value pushed by OP_CONST */
} instr;

struct fb_expr {
  int uses_time;
  size_t n;
  instr code[];
};

typedef struct func_info {
  const char *name;
  opcode op;
  size_t min_args;
  size_t max_args; /* SIZE_MAX: any number >= min_args */
} func_info;

static const func_info FUNCS[] = {
    {"sin", OP_SIN, 1, 1},        {"cos", OP_COS, 1, 1},        {"tan", OP_TAN, 1, 1},
    {"asin", OP_ASIN, 1, 1},      {"acos", OP_ACOS, 1, 1},      {"atan", OP_ATAN, 1, 1},
    {"atan2", OP_ATAN2, 2, 2},    {"exp", OP_EXP, 1, 1},        {"log", OP_LOG, 1, 1},
    {"log10", OP_LOG10, 1, 1},    {"sqrt", OP_SQRT, 1, 1},      {"abs", OP_ABS, 1, 1},
    {"min", OP_MIN, 2, SIZE_MAX}, {"max", OP_MAX, 2, SIZE_MAX}, {"pow", OP_POW, 2, 2},
    {"floor", OP_FLOOR, 1, 1},    {"ceil", OP_CEIL, 1, 1},      {"sign", OP_SIGN, 1, 1},
    {"step", OP_STEP, 1, 1},      {"ramp", OP_RAMP, 1, 1},
};
static const size_t NFUNCS = sizeof FUNCS / sizeof FUNCS[0];

static size_t op_arity(opcode op)
{
  if (op <= OP_TIME)
    return 0;
  return op < OP_ADD ? 1 : 2;
}

/* min/max that return NaN if either argument is NaN (C's fmin/fmax drop
 * the NaN, which would hide a domain error upstream). */
static double min_nan(double a, double b)
{
  return (isnan(a) || isnan(b)) ? a + b : fmin(a, b);
}

static double max_nan(double a, double b)
{
  return (isnan(a) || isnan(b)) ? a + b : fmax(a, b);
}

/* sign, step and ramp pass NaN through for the same reason. */
static double sign_of(double x)
{
  if (x > 0.0)
    return 1.0;
  return x < 0.0 ? -1.0 : x; /* 0, -0 and NaN are returned as they are */
}

static double step_of(double x)
{
  if (isnan(x))
    return x;
  return x >= 0.0 ? 1.0 : 0.0;
}

static double ramp_of(double x)
{
  if (isnan(x))
    return x;
  return x > 0.0 ? x : 0.0;
}

/* Applies operator op (arity 1 or 2) to a, or to a and b. Shared by the
 * evaluator and constant folding so both compute bit-identical values. */
static double apply_op(opcode op, double a, double b)
{
  switch (op) {
  case OP_NEG: return -a;
  case OP_SIN: return sin(a);
  case OP_COS: return cos(a);
  case OP_TAN: return tan(a);
  case OP_ASIN: return asin(a);
  case OP_ACOS: return acos(a);
  case OP_ATAN: return atan(a);
  case OP_EXP: return exp(a);
  case OP_LOG: return log(a);
  case OP_LOG10: return log10(a);
  case OP_SQRT: return sqrt(a);
  case OP_ABS: return fabs(a);
  case OP_FLOOR: return floor(a);
  case OP_CEIL: return ceil(a);
  case OP_SIGN: return sign_of(a);
  case OP_STEP: return step_of(a);
  case OP_RAMP: return ramp_of(a);
  case OP_ADD: return a + b;
  case OP_SUB: return a - b;
  case OP_MUL: return a * b;
  case OP_DIV: return a / b;
  case OP_POW: return pow(a, b);
  case OP_ATAN2: return atan2(a, b);
  case OP_MIN: return min_nan(a, b);
  case OP_MAX: return max_nan(a, b);
  case OP_CONST:
  case OP_TIME: break; /* pushes, handled by the caller */
  }
  return NAN;
}

/* Runs the code; the parser guarantees it leaves exactly one value and
 * never holds more than EXPR_STACK_MAX. */
double fb_expr_eval(const fb_expr *e, double t)
{
  double stack[EXPR_STACK_MAX];
  size_t sp = 0;
  for (size_t i = 0; i < e->n; ++i) {
    const instr *in = &e->code[i];
    const size_t arity = op_arity(in->op);
    assert(sp >= arity && (arity > 0 || sp < EXPR_STACK_MAX));
    switch (arity) {
    case 0: stack[sp++] = in->op == OP_TIME ? t : in->k; break;
    case 1: stack[sp - 1] = apply_op(in->op, stack[sp - 1], 0.0); break;
    default:
      --sp;
      stack[sp - 1] = apply_op(in->op, stack[sp - 1], stack[sp]);
      break;
    }
  }
  assert(sp == 1);
  return stack[0];
}

int fb_expr_uses_time(const fb_expr *e)
{
  return e->uses_time;
}

/* ---- Parser ---- */

typedef struct parser {
  const char *text;
  size_t pos; /* byte offset of the next unread character */
  const fb_symtab *syms;
  instr *code;
  size_t n, capacity;
  size_t depth;       /* stack height after running the code emitted so far */
  size_t nesting;     /* current recursion level of parse_unary */
  size_t time_column; /* 1-based column of the first use of t, 0 if none */
  fb_err *err;
} parser;

/* Records FB_EPARSE with "column N: " (1-based) before the message. */
static int parse_error(parser *p, size_t pos, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static int parse_error(parser *p, size_t pos, const char *fmt, ...)
{
  char msg[FB_ERR_MSG_MAX];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return fb_err_set(p->err, FB_EPARSE, "column %zu: %s", pos + 1, msg);
}

/* Describes the character at pos for "found ..." in messages. */
static const char *describe_at(const parser *p, size_t pos, char *buf, size_t size)
{
  unsigned char c = (unsigned char)p->text[pos];
  if (c == '\0')
    snprintf(buf, size, "end of expression");
  else if (isprint(c))
    snprintf(buf, size, "'%c'", c);
  else
    snprintf(buf, size, "byte 0x%02x", (unsigned)c);
  return buf;
}

static void skip_space(parser *p)
{
  while (isspace((unsigned char)p->text[p->pos]))
    ++p->pos;
}

static int is_name_start(char c)
{
  return isalpha((unsigned char)c) || c == '_';
}

static int is_name_char(char c)
{
  return isalnum((unsigned char)c) || c == '_';
}

static int reserve_code(parser *p)
{
  if (fb_grow((void **)&p->code, &p->capacity, p->n, sizeof *p->code))
    return fb_err_set(p->err, FB_ENOMEM, "out of memory parsing an expression");
  return FB_OK;
}

/* Emits a push of a constant (op OP_CONST, value k) or of t (OP_TIME);
 * pos is the token's offset, for the error if the stack would overflow. */
static int emit_push(parser *p, opcode op, double k, size_t pos)
{
  if (p->depth == EXPR_STACK_MAX)
    return parse_error(p, pos,
                       "expression too complex (needs more than %d intermediate values)",
                       EXPR_STACK_MAX);
  int status = reserve_code(p);
  if (status != FB_OK)
    return status;
  p->code[p->n].op = op;
  p->code[p->n].k = k;
  ++p->n;
  ++p->depth;
  return FB_OK;
}

static int is_const_at(const parser *p, size_t from_end)
{
  return p->n >= from_end && p->code[p->n - from_end].op == OP_CONST;
}

/* Emits operator op, folding it into a constant when its operands are
 * constants. In postfix code an operand that ends with a push is exactly
 * that push, so checking the last one or two instructions suffices. */
static int emit_op(parser *p, opcode op)
{
  size_t arity = op_arity(op);
  if (arity == 1 && is_const_at(p, 1)) {
    p->code[p->n - 1].k = apply_op(op, p->code[p->n - 1].k, 0.0);
    return FB_OK;
  }
  if (arity == 2 && is_const_at(p, 1) && is_const_at(p, 2)) {
    p->code[p->n - 2].k = apply_op(op, p->code[p->n - 2].k, p->code[p->n - 1].k);
    --p->n;
    --p->depth;
    return FB_OK;
  }
  int status = reserve_code(p);
  if (status != FB_OK)
    return status;
  p->code[p->n].op = op;
  p->code[p->n].k = 0.0;
  ++p->n;
  p->depth -= arity - 1;
  return FB_OK;
}

/* ---- Did-you-mean suggestions ---- */

static size_t min3(size_t a, size_t b, size_t c)
{
  size_t m = a < b ? a : b;
  return m < c ? m : c;
}

/* Edit distance with adjacent transpositions counted as one edit (the
 * "optimal string alignment" variant of Damerau, Comm. ACM 7(3), 1964),
 * by the row-by-row dynamic programme of Wagner & Fischer, J. ACM 21(1),
 * 1974. SIZE_MAX for names of SUGGEST_NAME_MAX characters or more. */
static size_t edit_distance(const char *a, const char *b)
{
  size_t la = strlen(a), lb = strlen(b);
  if (la >= SUGGEST_NAME_MAX || lb >= SUGGEST_NAME_MAX)
    return SIZE_MAX;
  size_t rows[3][SUGGEST_NAME_MAX + 1]; /* row i lives in rows[i % 3] */
  for (size_t j = 0; j <= lb; ++j)
    rows[0][j] = j;
  for (size_t i = 1; i <= la; ++i) {
    size_t *cur = rows[i % 3];
    const size_t *prev = rows[(i - 1) % 3];
    const size_t *prev2 = rows[(i + 1) % 3]; /* row i - 2 */
    cur[0] = i;
    for (size_t j = 1; j <= lb; ++j) {
      size_t cost = a[i - 1] != b[j - 1];
      size_t best = min3(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost);
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
          prev2[j - 2] + 1 < best)
        best = prev2[j - 2] + 1;
      cur[j] = best;
    }
  }
  return rows[la % 3][lb];
}

typedef struct suggestion {
  const char *name; /* the unknown name */
  const char *best; /* closest candidate so far, NULL if none */
  size_t dist;      /* its distance; candidates must beat it */
} suggestion;

/* Accepts distances <= SUGGEST_DIST_MAX and below the name's length, so a
 * one-letter typo is not "corrected" to an unrelated one-letter name. */
static void suggestion_init(suggestion *s, const char *name)
{
  size_t len = strlen(name);
  s->name = name;
  s->best = NULL;
  s->dist = len < SUGGEST_DIST_MAX + 1 ? len : SUGGEST_DIST_MAX + 1;
}

static void suggestion_consider(suggestion *s, const char *candidate)
{
  size_t d = edit_distance(s->name, candidate);
  if (d < s->dist) {
    s->best = candidate;
    s->dist = d;
  }
}

static void suggest_functions(suggestion *s)
{
  for (size_t i = 0; i < NFUNCS; ++i)
    suggestion_consider(s, FUNCS[i].name);
}

/* Writes " (did you mean 'x'?)" or "" to buf. */
static const char *suggestion_text(const suggestion *s, char *buf, size_t size)
{
  if (s->best)
    snprintf(buf, size, " (did you mean '%s'?)", s->best);
  else
    buf[0] = '\0';
  return buf;
}

/* ---- Grammar rules ---- */

static int parse_expr(parser *p);
static int parse_unary(parser *p);

static const func_info *find_func(const char *name)
{
  for (size_t i = 0; i < NFUNCS; ++i)
    if (strcmp(FUNCS[i].name, name) == 0)
      return &FUNCS[i];
  return NULL;
}

/* C-style decimal: digits [. digits] | . digits, then [eE [+-] digits].
 * Hexadecimal, inf and nan are not numbers here. */
static int parse_number(parser *p)
{
  size_t start = p->pos;
  const char *s = p->text;
  while (isdigit((unsigned char)s[p->pos]))
    ++p->pos;
  if (s[p->pos] == '.')
    ++p->pos;
  while (isdigit((unsigned char)s[p->pos]))
    ++p->pos;
  if (s[p->pos] == 'e' || s[p->pos] == 'E') {
    size_t exp = p->pos + 1;
    if (s[exp] == '+' || s[exp] == '-')
      ++exp;
    if (!isdigit((unsigned char)s[exp]))
      return parse_error(p, start, "expected digits in the exponent of number '%.*s'",
                         (int)(exp - start), s + start);
    p->pos = exp;
    while (isdigit((unsigned char)s[p->pos]))
      ++p->pos;
  }
  /* strtod on a copy: on the text it could read past the token (0x1p3). */
  char *token = strndup(s + start, p->pos - start);
  if (!token)
    return fb_err_set(p->err, FB_ENOMEM, "out of memory parsing an expression");
  char *end = NULL;
  errno = 0;
  double value = strtod(token, &end);
  int complete = *end == '\0';
  int overflow = errno == ERANGE && isinf(value);
  fb_err why;
  const int inexact = complete && !overflow && fb_decimal_check_exact(token, value, &why);
  free(token);
  if (!complete)
    return parse_error(p, start, "cannot convert number '%.*s' (is LC_NUMERIC not \"C\"?)",
                       (int)(p->pos - start), s + start);
  if (overflow)
    return parse_error(p, start, "number '%.*s' is too large for a double",
                       (int)(p->pos - start), s + start);
  if (inexact)
    return parse_error(p, start, "%s", why.msg);
  return emit_push(p, OP_CONST, value, start);
}

static int unknown_name_error(parser *p, const char *name, size_t start)
{
  suggestion s;
  suggestion_init(&s, name);
  for (size_t i = 0; i < fb_symtab_size(p->syms); ++i)
    suggestion_consider(&s, fb_symtab_name(p->syms, i));
  suggestion_consider(&s, "t");
  suggestion_consider(&s, "pi");
  suggestion_consider(&s, "e");
  suggest_functions(&s);
  char hint[SUGGEST_NAME_MAX + 32];
  return parse_error(p, start, "unknown name '%s'%s", name,
                     suggestion_text(&s, hint, sizeof hint));
}

/* A name not followed by '(': parameter, then t, then pi and e. */
static int parse_variable(parser *p, const char *name, size_t start)
{
  double value;
  if (fb_symtab_get(p->syms, name, &value))
    return emit_push(p, OP_CONST, value, start);
  if (strcmp(name, "t") == 0) {
    if (!p->time_column)
      p->time_column = start + 1;
    return emit_push(p, OP_TIME, 0.0, start);
  }
  if (strcmp(name, "pi") == 0)
    return emit_push(p, OP_CONST, CONST_PI, start);
  if (strcmp(name, "e") == 0)
    return emit_push(p, OP_CONST, CONST_E, start);
  if (find_func(name))
    return parse_error(p, p->pos, "expected '(' after function name '%s'", name);
  return unknown_name_error(p, name, start);
}

static int unknown_function_error(parser *p, const char *name, size_t start)
{
  if (fb_symtab_get(p->syms, name, NULL))
    return parse_error(p, start, "'%s' is a parameter, not a function", name);
  suggestion s;
  suggestion_init(&s, name);
  suggest_functions(&s);
  char hint[SUGGEST_NAME_MAX + 32];
  return parse_error(p, start, "unknown function '%s'%s", name,
                     suggestion_text(&s, hint, sizeof hint));
}

static int arity_error(parser *p, const func_info *f, size_t nargs, size_t start)
{
  if (f->max_args == SIZE_MAX)
    return parse_error(p, start,
                       "wrong number of arguments to '%s' (expected at least %zu, got %zu)",
                       f->name, f->min_args, nargs);
  return parse_error(p, start, "wrong number of arguments to '%s' (expected %zu, got %zu)",
                     f->name, f->min_args, nargs);
}

/* Comma-separated arguments up to and including ')'; p->pos is just past
 * '('. Variadic functions (min, max) are emitted as a chain of binary
 * operators, one after each argument beyond the first. */
static int parse_arguments(parser *p, const func_info *f, size_t *nargs)
{
  *nargs = 0;
  skip_space(p);
  if (p->text[p->pos] == ')') {
    ++p->pos;
    return FB_OK;
  }
  for (;;) {
    int status = parse_expr(p);
    if (status == FB_OK && ++*nargs >= 2 && f->max_args == SIZE_MAX)
      status = emit_op(p, f->op);
    if (status != FB_OK)
      return status;
    skip_space(p);
    if (p->text[p->pos] != ',')
      break;
    ++p->pos;
  }
  if (p->text[p->pos] != ')') {
    char found[32];
    return parse_error(p, p->pos, "expected ')' after argument list of '%s', found %s", f->name,
                       describe_at(p, p->pos, found, sizeof found));
  }
  ++p->pos;
  return FB_OK;
}

/* name '(' args ')' with p->pos at '('. */
static int parse_call(parser *p, const char *name, size_t start)
{
  const func_info *f = find_func(name);
  if (!f)
    return unknown_function_error(p, name, start);
  ++p->pos;
  size_t nargs;
  int status = parse_arguments(p, f, &nargs);
  if (status != FB_OK)
    return status;
  if (nargs < f->min_args || nargs > f->max_args)
    return arity_error(p, f, nargs, start);
  return f->max_args == SIZE_MAX ? FB_OK : emit_op(p, f->op);
}

static int parse_name(parser *p)
{
  size_t start = p->pos;
  while (is_name_char(p->text[p->pos]))
    ++p->pos;
  char *name = strndup(p->text + start, p->pos - start);
  if (!name)
    return fb_err_set(p->err, FB_ENOMEM, "out of memory parsing an expression");
  skip_space(p);
  int status =
      p->text[p->pos] == '(' ? parse_call(p, name, start) : parse_variable(p, name, start);
  free(name);
  return status;
}

static int parse_parenthesized(parser *p)
{
  size_t open = p->pos;
  ++p->pos;
  int status = parse_expr(p);
  if (status != FB_OK)
    return status;
  skip_space(p);
  if (p->text[p->pos] != ')') {
    char found[32];
    return parse_error(p, p->pos, "expected ')' to close '(' at column %zu, found %s", open + 1,
                       describe_at(p, p->pos, found, sizeof found));
  }
  ++p->pos;
  return FB_OK;
}

/* atom := number | name | name '(' expr (',' expr)* ')' | '(' expr ')' */
static int parse_atom(parser *p)
{
  skip_space(p);
  const char *s = p->text + p->pos;
  if (isdigit((unsigned char)s[0]) || (s[0] == '.' && isdigit((unsigned char)s[1])))
    return parse_number(p);
  if (is_name_start(s[0]))
    return parse_name(p);
  if (s[0] == '(')
    return parse_parenthesized(p);
  char found[32];
  return parse_error(p, p->pos, "expected a number, name or '(', found %s",
                     describe_at(p, p->pos, found, sizeof found));
}

/* power := atom ('^' unary)?  -- right associative through unary. */
static int parse_power(parser *p)
{
  int status = parse_atom(p);
  if (status != FB_OK)
    return status;
  skip_space(p);
  if (p->text[p->pos] != '^')
    return FB_OK;
  ++p->pos;
  status = parse_unary(p);
  return status != FB_OK ? status : emit_op(p, OP_POW);
}

/* unary := ('-'|'+') unary | power. Every recursion of the parser passes
 * through here, so counting levels here bounds the C stack it uses. */
static int parse_unary(parser *p)
{
  skip_space(p);
  if (p->nesting == EXPR_NEST_MAX)
    return parse_error(p, p->pos, "expression nested too deeply (more than %d levels)",
                       EXPR_NEST_MAX);
  ++p->nesting;
  int status;
  char c = p->text[p->pos];
  if (c == '-' || c == '+') {
    ++p->pos;
    status = parse_unary(p);
    if (status == FB_OK && c == '-')
      status = emit_op(p, OP_NEG);
  } else {
    status = parse_power(p);
  }
  --p->nesting;
  return status;
}

/* term := unary (('*'|'/') unary)* */
static int parse_term(parser *p)
{
  int status = parse_unary(p);
  for (;;) {
    if (status != FB_OK)
      return status;
    skip_space(p);
    char c = p->text[p->pos];
    if (c != '*' && c != '/')
      return FB_OK;
    ++p->pos;
    status = parse_unary(p);
    if (status == FB_OK)
      status = emit_op(p, c == '*' ? OP_MUL : OP_DIV);
  }
}

/* expr := term (('+'|'-') term)* */
static int parse_expr(parser *p)
{
  int status = parse_term(p);
  for (;;) {
    if (status != FB_OK)
      return status;
    skip_space(p);
    char c = p->text[p->pos];
    if (c != '+' && c != '-')
      return FB_OK;
    ++p->pos;
    status = parse_term(p);
    if (status == FB_OK)
      status = emit_op(p, c == '+' ? OP_ADD : OP_SUB);
  }
}

/* The whole text as one expression, then the end. */
static int parse_all(parser *p)
{
  skip_space(p);
  if (p->text[p->pos] == '\0')
    return parse_error(p, p->pos, "empty expression");
  int status = parse_expr(p);
  if (status != FB_OK)
    return status;
  skip_space(p);
  if (p->text[p->pos] != '\0') {
    char found[32];
    return parse_error(p, p->pos, "expected an operator or end of expression, found %s",
                       describe_at(p, p->pos, found, sizeof found));
  }
  return FB_OK;
}

/* fb_expr_parse that also reports the column of the first t (0 if none). */
static int parse_text(const char *text, const fb_symtab *syms, fb_expr **out,
                      size_t *time_column, fb_err *err)
{
  if (!out)
    return fb_err_set(err, FB_EINVAL, "fb_expr_parse: out is NULL");
  *out = NULL;
  if (!text)
    return fb_err_set(err, FB_EINVAL, "fb_expr_parse: text is NULL");
  parser p = {.text = text, .syms = syms, .err = err};
  int status = parse_all(&p);
  if (status == FB_OK) {
    fb_expr *e = malloc(sizeof *e + p.n * sizeof e->code[0]);
    if (e) {
      e->uses_time = p.time_column != 0;
      e->n = p.n;
      memcpy(e->code, p.code, p.n * sizeof e->code[0]);
      *out = e;
      *time_column = p.time_column;
    } else {
      status = fb_err_set(err, FB_ENOMEM, "out of memory parsing an expression");
    }
  }
  free(p.code);
  return status;
}

int fb_expr_parse(const char *text, const fb_symtab *syms, fb_expr **out, fb_err *err)
{
  size_t time_column;
  return parse_text(text, syms, out, &time_column, err);
}

int fb_expr_clone(const fb_expr *e, fb_expr **out, fb_err *err)
{
  if (!e || !out)
    return fb_err_set(err, FB_EINVAL, "fb_expr_clone: expression or out is NULL");
  size_t size = sizeof *e + e->n * sizeof e->code[0];
  *out = malloc(size);
  if (!*out)
    return fb_err_set(err, FB_ENOMEM, "out of memory copying an expression");
  memcpy(*out, e, size);
  return FB_OK;
}

void fb_expr_free(fb_expr **e)
{
  if (!e)
    return;
  free(*e);
  *e = NULL;
}

int fb_expr_eval_const(const char *text, const fb_symtab *syms, double *value, fb_err *err)
{
  if (!value)
    return fb_err_set(err, FB_EINVAL, "fb_expr_eval_const: value is NULL");
  fb_expr *e = NULL;
  size_t time_column = 0;
  int status = parse_text(text, syms, &e, &time_column, err);
  if (status != FB_OK)
    return status;
  double v = fb_expr_eval(e, 0.0);
  fb_expr_free(&e);
  if (time_column)
    return fb_err_set(err, FB_EPARSE, "column %zu: expression depends on time t", time_column);
  if (!isfinite(v))
    return fb_err_set(err, FB_EINVAL,
                      "value is not finite (got %g; division by zero, overflow, or a "
                      "function outside its domain?)",
                      v);
  *value = v;
  return FB_OK;
}

/* ---- Writing an expression back (fb_expr_write).
 *
 * The code is a postfix program; each value on the stack becomes the text
 * of its subexpression with the precedence of its outermost operator,
 * and an operand is parenthesised only where the grammar would otherwise
 * group it differently, so the text parses to the same program: the
 * operations in the same order, on the same constants (written in the
 * shortest form strtod reads back exactly), hence the same values. */

enum { PREC_ADD = 1, PREC_MUL = 2, PREC_NEG = 3, PREC_POW = 4, PREC_ATOM = 5 };

typedef struct expr_text {
  char *s;
  int prec;
} expr_text;

static char *text_join(const char *a, const char *b, const char *c, const char *d,
                       const char *e)
{
  const size_t n = strlen(a) + strlen(b) + strlen(c) + strlen(d) + strlen(e) + 1;
  char *s = malloc(n);
  if (s)
    snprintf(s, n, "%s%s%s%s%s", a, b, c, d, e);
  return s;
}

/* x, in parentheses when its precedence is below min, or when it starts
 * with a minus and is the operand of an infix operator (min > 0): the
 * grammar reads "a * -b" too, but "a * (-b)" says it plainly. */
static char *text_operand(const expr_text *x, int min)
{
  const int wrap = x->prec < min || (min > 0 && min != PREC_POW && x->prec == PREC_NEG);
  return wrap ? text_join("(", x->s, ")", "", "") : text_join(x->s, "", "", "", "");
}

static const char *func_name(opcode op)
{
  for (size_t i = 0; i < NFUNCS; ++i)
    if (FUNCS[i].op == op)
      return FUNCS[i].name;
  return "?";
}

static int text_push(const instr *in, expr_text *x)
{
  char buf[40];
  if (in->op == OP_TIME) {
    x->prec = PREC_ATOM;
    return (x->s = text_join("t", "", "", "", "")) ? 0 : -1;
  }
  if (!isfinite(in->k))
    return -1;
  for (int digits = 15; digits <= 17; ++digits) {
    snprintf(buf, sizeof buf, "%.*g", digits, in->k);
    if (strtod(buf, NULL) == in->k)
      break;
  }
  /* Beyond 2^53 the parser refuses an integer without exponent. */
  if (fabs(in->k) > 9007199254740992.0 && !strpbrk(buf, ".e"))
    snprintf(buf, sizeof buf, "%.16e", in->k);
  x->prec = in->k < 0 || (in->k == 0 && signbit(in->k)) ? PREC_NEG : PREC_ATOM;
  return (x->s = text_join(buf, "", "", "", "")) ? 0 : -1;
}

static int text_unary(opcode op, expr_text *x)
{
  char *a = text_operand(x, op == OP_NEG ? PREC_POW : 0);
  char *s = !a             ? NULL
            : op == OP_NEG ? text_join("-", a, "", "", "")
                           : text_join(func_name(op), "(", a, ")", "");
  free(a);
  free(x->s);
  x->s = s;
  x->prec = op == OP_NEG ? PREC_NEG : PREC_ATOM;
  return s ? 0 : -1;
}

static int text_binary(opcode op, expr_text *x, expr_text *y)
{
  static const struct {
    opcode op;
    const char *sym;
    int prec;
  } infix[] = {{OP_ADD, " + ", PREC_ADD},
               {OP_SUB, " - ", PREC_ADD},
               {OP_MUL, " * ", PREC_MUL},
               {OP_DIV, " / ", PREC_MUL}};
  char *s = NULL;
  int prec = PREC_ATOM;
  for (size_t i = 0; i < 4 && !s; ++i)
    if (infix[i].op == op) {
      /* Left associative: the left operand may be of equal precedence. */
      char *a = text_operand(x, infix[i].prec), *b = text_operand(y, infix[i].prec + 1);
      s = a && b ? text_join(a, infix[i].sym, b, "", "") : NULL;
      prec = infix[i].prec;
      free(a);
      free(b);
      if (!s)
        return -1;
    }
  if (!s)
    s = text_join(func_name(op), "(", x->s, ", ", y->s);
  char *closed = s && prec == PREC_ATOM ? text_join(s, ")", "", "", "") : s;
  if (closed != s)
    free(s);
  free(x->s);
  free(y->s);
  y->s = NULL;
  x->s = closed;
  x->prec = prec;
  return closed ? 0 : -1;
}

int fb_expr_write(const fb_expr *e, FILE *fp)
{
  expr_text *stack = calloc(e->n + 1, sizeof *stack);
  size_t sp = 0;
  int rc = stack ? 0 : -1;
  for (size_t i = 0; rc == 0 && i < e->n; ++i) {
    const instr *in = &e->code[i];
    const size_t arity = op_arity(in->op);
    if (arity > sp || !(arity == 0 || stack[sp - 1].s) || !(arity < 2 || stack[sp - 2].s))
      rc = -1; /* not the parser's code */
    else if (arity == 0)
      rc = text_push(in, &stack[sp++]);
    else if (arity == 1)
      rc = text_unary(in->op, &stack[sp - 1]);
    else
      rc = text_binary(in->op, &stack[sp - 2], &stack[sp - 1]), --sp;
  }
  if (rc == 0 && sp == 1)
    fputs(stack[0].s, fp);
  for (size_t i = 0; stack && i <= e->n; ++i)
    free(stack[i].s);
  free(stack);
  return rc == 0 && sp == 1 ? 0 : -1;
}
