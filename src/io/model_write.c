/* SPDX-License-Identifier: BSD-3-Clause */
/* Writes a bond graph as a model file (fb_model_write in flexbond/model.h;
 * the format is docs/model-format.md).
 *
 * The graph is read back through its accessors (flexbond/bg.h). Each
 * subsystem instance "inst" (the elements and bonds named "inst.*")
 * becomes a definition in `subsystems`, written once per distinct text
 * (six equal suspension corners are one definition), and an element of
 * type that definition named inst: loading the file adopts it under the
 * same name, so every element and bond keeps its full name and the
 * probes their targets. A bond between parts of different instances is
 * written in their innermost common graph, reaching into an instance
 * through a port of its definition: the graph's own port of that name
 * where it has one (the names fb_bg_adopt kept), else a port made up for
 * the bond. Elements and bonds keep their order, so the loaded graph
 * numbers its states and junction ports as the written one did.
 *
 * Numbers are written in the shortest form that reads back as the same
 * double (at most 17 significant digits, enough for every binary64: IEEE
 * 754-2008, section 5.12.2). Matrices of more than FB_MODEL_INLINE_MAX
 * entries go to Matrix Market files beside the model (fb_mat_write_mtx,
 * the same %.17g). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/escape.h"
#include "flexbond/io.h"
#include "flexbond/model.h"
#include "flexbond/road.h"

#include "core/textfile.h"
#include "core/util.h"

/* A port of a definition being written. */
typedef struct mw_port {
  char *name, *at;
  fb_bg_dir dir;
} mw_port;

/* A graph of the file: the model (prefix "") or one instance ("a.",
 * "a.b."), with the ports its definition declares. */
typedef struct mw_scope {
  char *prefix;
  mw_port *ports;
  size_t nports, cap;
  const char *def; /* the definition written for it (a mw_def's name) */
} mw_scope;

typedef struct mw_def {
  char *name, *text;
} mw_def;

typedef struct mw {
  const fb_bg *bg;
  const char *dir, *name;
  fb_err *err;
  mw_scope *scopes;
  size_t nscopes, cap_scopes;
  mw_def *defs;
  size_t ndefs, cap_defs;
  char **files; /* written, relative to dir */
  size_t nfiles, cap_files;
  unsigned char *taken; /* per declared port of bg: used by a bond */
  size_t *bond_scope;   /* per bond */
  char **refs;          /* per bond: from and to references in its scope */
} mw;

/* ---- Text. */

/* The shortest "%.Ng" of v (N 15..17) that strtod reads back as v. An
 * integer beyond 2^53 gets an exponent: the loader refuses such an
 * integer written out, since not every one of them is a double. */
static void mw_format(double v, char *buf, size_t size)
{
  fb_format_shortest(v, 15, buf, size);
  if (fabs(v) > 9007199254740992.0 && !strpbrk(buf, ".e"))
    snprintf(buf, size, "%.16e", v);
}

static void mw_num(FILE *fp, double v)
{
  char buf[40];
  mw_format(v, buf, sizeof buf);
  fputs(buf, fp);
}

static void mw_nums(FILE *fp, const double *v, size_t n)
{
  fputc('[', fp);
  for (size_t i = 0; i < n; ++i) {
    if (i)
      fputs(i % 8 ? ", " : ",\n      ", fp);
    mw_num(fp, v[i]);
  }
  fputc(']', fp);
}

/* A name or text as a plain scalar when that reads back as it, else
 * double-quoted; FB_EINVAL for text a model may not hold. */
static int mw_str(const mw *w, FILE *fp, const char *s, const char *what)
{
  if (fb_yaml_is_plain(s)) {
    fputs(s, fp);
    return FB_OK;
  }
  if (fb_yaml_write_string(fp, s) == 0)
    return FB_OK;
  return fb_err_set(w->err, FB_EINVAL, "%s: text with a control character cannot be written",
                    what);
}

/* 1 if s is a model name: a letter or '_', then letters, digits, '_'. */
static int mw_is_name(const char *s)
{
  if (!s || !((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || *s == '_'))
    return 0;
  for (; *s; ++s)
    if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') ||
          *s == '_'))
      return 0;
  return 1;
}

/* A name or port reference (no control character can be in one). */
static void mw_plain(FILE *fp, const char *s)
{
  if (fb_yaml_is_plain(s))
    fputs(s, fp);
  else
    fb_yaml_write_string(fp, s);
}

static char *mw_printf(const char *fmt, const char *a, const char *b)
{
  const size_t n = strlen(fmt) + strlen(a) + strlen(b) + 1;
  char *s = malloc(n);
  if (s)
    snprintf(s, n, fmt, a, b);
  return s;
}

/* ---- Scopes. */

static long mw_scope_find(const mw *w, const char *prefix, size_t len)
{
  for (size_t i = 0; i < w->nscopes; ++i)
    if (strlen(w->scopes[i].prefix) == len && !strncmp(w->scopes[i].prefix, prefix, len))
      return (long)i;
  return -1;
}

static int mw_scope_add(mw *w, const char *prefix, size_t len)
{
  if (mw_scope_find(w, prefix, len) >= 0)
    return FB_OK;
  if (fb_grow((void **)&w->scopes, &w->cap_scopes, w->nscopes, sizeof *w->scopes))
    return fb_err_set(w->err, FB_ENOMEM, "out of memory");
  mw_scope *s = &w->scopes[w->nscopes];
  memset(s, 0, sizeof *s);
  if (!(s->prefix = malloc(len + 1)))
    return fb_err_set(w->err, FB_ENOMEM, "out of memory");
  memcpy(s->prefix, prefix, len);
  s->prefix[len] = '\0';
  w->nscopes++;
  return FB_OK;
}

/* Every instance prefix of every element name, in order of appearance. */
static int mw_collect_scopes(mw *w)
{
  int rc = mw_scope_add(w, "", 0);
  for (size_t i = 0; !rc && i < fb_bg_nelements(w->bg); ++i) {
    const char *name = fb_bg_element_name(w->bg, i);
    for (const char *p = strchr(name, '.'); !rc && p; p = strchr(p + 1, '.'))
      rc = mw_scope_add(w, name, (size_t)(p - name) + 1);
  }
  return rc;
}

/* Length of the longest instance prefix common to the names a and b. */
static size_t mw_common_prefix(const char *a, const char *b)
{
  size_t best = 0;
  for (size_t i = 0; a[i] && a[i] == b[i]; ++i)
    if (a[i] == '.')
      best = i + 1;
  return best;
}

/* ---- Port references. */

static int mw_port_add(mw *w, size_t scope, char *name, char *at, fb_bg_dir dir)
{
  mw_scope *s = &w->scopes[scope];
  if (!name || !at || fb_grow((void **)&s->ports, &s->cap, s->nports, sizeof *s->ports)) {
    free(name);
    free(at);
    return fb_err_set(w->err, FB_ENOMEM, "out of memory");
  }
  s->ports[s->nports++] = (mw_port){name, at, dir};
  return FB_OK;
}

/* A declared port of bg named "inst.p" (inst the child scope's prefix)
 * on element e's port k with direction dir and not taken yet, preferring
 * the one the bond's made-up name "from->to" names: its index, or -1. */
static long mw_declared_port(const mw *w, const char *child, size_t e, size_t k, fb_bg_dir dir,
                             const char *bond_name)
{
  const int junction = !fb_bg_element_has_fixed_ports(w->bg, e);
  long first = -1;
  for (size_t i = 0; i < fb_bg_ndeclared_ports(w->bg); ++i) {
    fb_bg_port_info p;
    fb_bg_declared_port(w->bg, i, &p);
    const size_t len = strlen(child);
    if (p.exported || w->taken[i] || p.element != e || p.dir != dir ||
        strncmp(p.name, child, len) != 0 || strchr(p.name + len, '.') ||
        p.port != (junction ? FB_BG_ANY_PORT : k))
      continue;
    const size_t n = strlen(p.name);
    const char *arrow = strstr(bond_name, "->");
    if (arrow &&
        (dir == FB_PORT_OUT ? (size_t)(arrow - bond_name) == n && !strncmp(bond_name, p.name, n)
                            : !strcmp(arrow + 2, p.name)))
      return (long)i;
    if (first < 0)
      first = (long)i;
  }
  return first;
}

static int mw_end_ref(mw *w, size_t b, int to_end, size_t scope, char **out);

/* A port name for bond b's end in child scope c that the graph did not
 * keep: the one the bond's made-up name "inst.p->..." shows, so that the
 * name comes back, else "bondN_in" / "bondN_out". */
static void mw_port_name(const mw *w, size_t b, int to_end, size_t c, char *buf, size_t size)
{
  const char *prefix = w->scopes[c].prefix, *bond = fb_bg_bond_name(w->bg, b);
  const size_t clen = strlen(prefix);
  size_t plen = clen - 1; /* the enclosing scope's prefix */
  while (plen > 0 && prefix[plen - 1] != '.')
    --plen;
  snprintf(buf, size, "bond%zu_%s", b + 1, to_end ? "in" : "out");
  const char *local = bond + plen,
             *arrow = strncmp(bond, prefix, plen) != 0 ? NULL : strstr(local, "->");
  if (!arrow)
    return;
  const char *part = to_end ? arrow + 2 : local;
  const size_t n = to_end ? strlen(part) : (size_t)(arrow - local);
  const size_t ilen = clen - plen; /* "inst." */
  if (n <= ilen || strncmp(part, prefix + plen, ilen) != 0 || n - ilen >= size)
    return;
  char cand[256];
  snprintf(cand, sizeof cand, "%.*s", (int)(n - ilen), part + ilen);
  for (size_t i = 0; i < w->scopes[c].nports; ++i)
    if (!strcmp(w->scopes[c].ports[i].name, cand))
      return;
  if (mw_is_name(cand))
    snprintf(buf, size, "%s", cand);
}

/* The name, in the definition of child scope c, of the port that bond b's
 * end reaches element e through; the port is declared there. */
static int mw_child_port(mw *w, size_t b, int to_end, size_t c, char **out)
{
  const size_t e = to_end ? fb_bg_bond_to(w->bg, b) : fb_bg_bond_from(w->bg, b);
  const size_t k = to_end ? fb_bg_bond_to_port(w->bg, b) : fb_bg_bond_from_port(w->bg, b);
  const fb_bg_dir dir = to_end ? FB_PORT_IN : FB_PORT_OUT;
  const char *prefix = w->scopes[c].prefix;
  const long pd = mw_declared_port(w, prefix, e, k, dir, fb_bg_bond_name(w->bg, b));
  char made[256];
  mw_port_name(w, b, to_end, c, made, sizeof made);
  const char *name = made;
  if (pd >= 0) {
    fb_bg_port_info p;
    fb_bg_declared_port(w->bg, (size_t)pd, &p);
    w->taken[pd] = 1;
    name = p.name + strlen(prefix);
  }
  char *at = NULL;
  int rc = mw_end_ref(w, b, to_end, c, &at);
  if (!rc)
    rc = mw_port_add(w, c, fb_strdup(name), at, dir);
  if (!rc && !(*out = fb_strdup(name)))
    rc = fb_err_set(w->err, FB_ENOMEM, "out of memory");
  return rc;
}

/* The reference to element e's port k as written in scope: "E", "E.k",
 * "H.whole", or "inst.port" for a part of an instance. */
static int mw_end_ref(mw *w, size_t b, int to_end, size_t scope, char **out)
{
  const fb_bg *bg = w->bg;
  const size_t e = to_end ? fb_bg_bond_to(bg, b) : fb_bg_bond_from(bg, b);
  const size_t k = to_end ? fb_bg_bond_to_port(bg, b) : fb_bg_bond_from_port(bg, b);
  const char *local = fb_bg_element_name(bg, e) + strlen(w->scopes[scope].prefix);
  const char *dot = strchr(local, '.');
  *out = NULL;
  if (dot) {
    const size_t plen = strlen(w->scopes[scope].prefix) + (size_t)(dot - local) + 1;
    const long c = mw_scope_find(w, fb_bg_element_name(bg, e), plen);
    char *port = NULL;
    int rc = c < 0 ? fb_err_set(w->err, FB_EINVAL, "internal: no scope for '%s'", local)
                   : mw_child_port(w, b, to_end, (size_t)c, &port);
    if (rc)
      return rc;
    char inst[256];
    snprintf(inst, sizeof inst, "%.*s", (int)(dot - local), local);
    *out = mw_printf("%s.%s", inst, port);
    free(port);
    return *out ? FB_OK : fb_err_set(w->err, FB_ENOMEM, "out of memory");
  }
  const size_t nports = fb_bg_element_nports(bg, e);
  char slot[32] = "";
  if (fb_bg_element_has_fixed_ports(bg, e) && fb_bg_element_kind(bg, e) == FB_BG_COMPOSITE &&
      k + 1 == nports)
    snprintf(slot, sizeof slot, "whole");
  else if (fb_bg_element_has_fixed_ports(bg, e) && nports > 1)
    snprintf(slot, sizeof slot, "%zu", k + 1);
  *out = *slot ? mw_printf("%s.%s", local, slot) : fb_strdup(local);
  return *out ? FB_OK : fb_err_set(w->err, FB_ENOMEM, "out of memory");
}

/* The prefix of from one instance out from len (0 stays 0). */
static size_t mw_outer(const char *from, size_t len)
{
  if (len > 0)
    --len;
  while (len > 0 && from[len - 1] != '.')
    --len;
  return len;
}

/* The ports scopes had before a tentative placement, to undo it. */
static void mw_undo_ports(mw *w, size_t nscopes, const size_t *nports,
                          const unsigned char *taken)
{
  for (size_t i = 0; i < nscopes; ++i)
    while (w->scopes[i].nports > nports[i]) {
      mw_port *p = &w->scopes[i].ports[--w->scopes[i].nports];
      free(p->name);
      free(p->at);
    }
  memcpy(w->taken, taken, fb_bg_ndeclared_ports(w->bg));
}

/* Places bond b in the scope of prefix length len: its ends' references
 * there. 1 when its name can be written there (a model name, or the name
 * "from->to" a model gives an unnamed bond), 0 when not (undone), < 0 on
 * an error (rc in *rc). */
static int mw_try_scope(mw *w, size_t b, size_t len, int *rc)
{
  const fb_bg *bg = w->bg;
  const char *from = fb_bg_element_name(bg, fb_bg_bond_from(bg, b));
  const char *name = fb_bg_bond_name(bg, b);
  const long s = mw_scope_find(w, from, len);
  if (s < 0 || strncmp(name, from, len) != 0)
    return 0;
  const size_t nscopes = w->nscopes; /* placing a bond adds ports, no scopes */
  size_t *nports = malloc((nscopes + 1) * sizeof *nports);
  unsigned char *taken = malloc(fb_bg_ndeclared_ports(bg) + 1);
  if (!nports || !taken) {
    free(nports);
    free(taken);
    *rc = fb_err_set(w->err, FB_ENOMEM, "out of memory");
    return -1;
  }
  for (size_t i = 0; i < nscopes; ++i)
    nports[i] = w->scopes[i].nports;
  memcpy(taken, w->taken, fb_bg_ndeclared_ports(bg));
  char **ref = &w->refs[2 * b];
  *rc = mw_end_ref(w, b, 0, (size_t)s, &ref[0]);
  if (!*rc)
    *rc = mw_end_ref(w, b, 1, (size_t)s, &ref[1]);
  int fits = 0;
  if (!*rc) {
    const char *local = name + len;
    const size_t n = strlen(ref[0]);
    fits = mw_is_name(local) || (!strncmp(local, ref[0], n) && !strncmp(local + n, "->", 2) &&
                                 !strcmp(local + n + 2, ref[1]));
  }
  if (!fits) {
    mw_undo_ports(w, nscopes, nports, taken);
    free(ref[0]);
    free(ref[1]);
    ref[0] = ref[1] = NULL;
  } else {
    w->bond_scope[b] = (size_t)s;
  }
  free(nports);
  free(taken);
  return *rc ? -1 : fits;
}

/* The scope of bond b: the innermost graph holding both its ends whose
 * prefix its name carries (fb_bg_adopt prefixed it) and where its name
 * can be written; then its ends' references there. */
static int mw_place_bond(mw *w, size_t b)
{
  const fb_bg *bg = w->bg;
  const char *from = fb_bg_element_name(bg, fb_bg_bond_from(bg, b));
  const char *to = fb_bg_element_name(bg, fb_bg_bond_to(bg, b));
  int rc = FB_OK;
  for (size_t len = mw_common_prefix(from, to);; len = mw_outer(from, len)) {
    const int placed = mw_try_scope(w, b, len, &rc);
    if (placed)
      return placed < 0 ? rc : FB_OK;
    if (len == 0)
      break;
  }
  return fb_err_set(w->err, FB_EINVAL,
                    "bond '%s': its name is no model name and not the one a model gives an "
                    "unnamed bond in any graph that holds both its ends",
                    fb_bg_bond_name(bg, b));
}

/* ---- Values. */

static const char *mw_domain_name(fb_bg_domain d)
{
  static const char *const names[] = {"translation", "rotation", "electrical", "hydraulic",
                                      "generic"};
  return (int)d >= 0 && d <= FB_DOMAIN_GENERIC ? names[d] : "generic";
}

/* A piecewise track's pieces, each with the numbers its kind takes
 * (model_road.c): s_begin, s_end, then its parameters. */
static void mw_road_pieces(FILE *fp, const fb_road_wheel_info *r)
{
  static const char *const kind[] = {"line", "arc", "wave"};
  static const size_t nparams[] = {2, 3, 5};
  fputs(", pieces: [", fp);
  for (size_t i = 0; i < r->npieces; ++i) {
    const fb_road_piece *p = &r->pieces[i];
    fprintf(fp, "%s{%s: [", i ? ",\n      " : "", kind[p->kind]);
    mw_num(fp, p->s_begin);
    fputs(", ", fp);
    mw_num(fp, p->s_end);
    for (size_t k = 0; k < nparams[p->kind]; ++k) {
      fputs(", ", fp);
      mw_num(fp, p->p[k]);
    }
    fputs("]}", fp);
  }
  fputs("]}}", fp);
}

static int mw_road(const mw *w, FILE *fp, const fb_road_wheel_info *r, const char *elem)
{
  fputs("{road: {speed: ", fp);
  mw_num(fp, r->speed);
  fputs(", s0: ", fp);
  mw_num(fp, r->s0);
  if (!r->velocity)
    fputs(", output: height", fp);
  switch (r->kind) {
  case FB_ROAD_WHEEL_BUMP:
    fputs(", bump: {at: ", fp);
    mw_num(fp, r->bump_start);
    fputs(", height: ", fp);
    mw_num(fp, r->bump_height);
    fputs(", length: ", fp);
    mw_num(fp, r->bump_length);
    fputs("}}}", fp);
    return FB_OK;
  case FB_ROAD_WHEEL_ISO8608: {
    /* Seeds are read as numbers: exact up to 2^53. */
    if (r->iso.seed > (UINT64_C(1) << 53) ||
        !((r->iso.road_class >= 'A' && r->iso.road_class <= 'H') ||
          (r->iso.road_class >= 'a' && r->iso.road_class <= 'h')))
      return fb_err_set(
          w->err, FB_EINVAL,
          "source '%s': an ISO 8608 road with seed %llu or class code %d cannot be "
          "written (seeds up to 2^53, classes A to H)",
          elem, (unsigned long long)r->iso.seed, r->iso.road_class);
    fprintf(fp, ", iso8608: {class: \"%c\", seed: %llu, n_min: ", r->iso.road_class,
            (unsigned long long)r->iso.seed);
    mw_num(fp, r->iso.n_min);
    fputs(", n_max: ", fp);
    mw_num(fp, r->iso.n_max);
    fprintf(fp, ", harmonics: %zu, fade_length: ", r->iso.nharmonics);
    mw_num(fp, r->iso.fade_length);
    if (r->iso.gd0 > 0) { /* a road given by its r.m.s.: its own Gd(n0) */
      fputs(", gd0: ", fp);
      mw_num(fp, r->iso.gd0);
    }
    fprintf(fp, ", track: %s}}}", r->track == FB_ROAD_LEFT ? "left" : "right");
    return FB_OK;
  }
  case FB_ROAD_WHEEL_PROFILE:
    fputs(", profile: {points: [", fp);
    for (size_t i = 0; i < r->nknots; ++i) {
      fputs(i ? (i % 4 ? ", [" : ",\n      [") : "[", fp);
      mw_num(fp, r->knot_s[i]);
      fputs(", ", fp);
      mw_num(fp, r->knot_z[i]);
      fputc(']', fp);
    }
    fputs("]}}}", fp);
    return FB_OK;
  case FB_ROAD_WHEEL_PIECES: mw_road_pieces(fp, r); return FB_OK;
  }
  return fb_err_set(w->err, FB_EINVAL, "source '%s': unknown road kind", elem);
}

/* One component of a source as a source value. */
static int mw_tfun(const mw *w, FILE *fp, const fb_tfun *f, const char *elem)
{
  fb_tfun_info t;
  fb_road_wheel_info road;
  fb_tfun_describe(f, &t);
  switch (t.kind) {
  case FB_TFUN_CONST: mw_num(fp, t.value); return FB_OK;
  case FB_TFUN_STEP:
    fputs("{step: {time: ", fp);
    mw_num(fp, t.t0);
    fputs(", before: ", fp);
    mw_num(fp, t.before);
    fputs(", after: ", fp);
    mw_num(fp, t.after);
    fputs("}}", fp);
    return FB_OK;
  case FB_TFUN_SINE:
    fputs("{sine: {amplitude: ", fp);
    mw_num(fp, t.amplitude);
    fputs(", frequency: ", fp);
    mw_num(fp, t.freq_hz);
    fputs(", phase: ", fp);
    mw_num(fp, t.phase_rad);
    fputs(", offset: ", fp);
    mw_num(fp, t.offset);
    fputs("}}", fp);
    return FB_OK;
  case FB_TFUN_TABLE:
    fputs("{table: {points: [", fp);
    for (size_t i = 0; i < t.n; ++i) {
      fputs(i ? ", [" : "[", fp);
      mw_num(fp, t.times[i]);
      fputs(", ", fp);
      mw_num(fp, t.values[i]);
      fputc(']', fp);
    }
    fputs("]}}", fp);
    return FB_OK;
  case FB_TFUN_CALLBACK:
    if (fb_road_wheel_describe(f, &road))
      return mw_road(w, fp, &road, elem);
    break;
  case FB_TFUN_EXPR: {
    /* An expression of t, quoted: it holds ',' and parentheses, which a
     * flow mapping would read. */
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    int bad = !m || fb_expr_write(t.expr, m) != 0;
    if (m && fclose(m))
      bad = 1;
    if (!bad)
      bad = fb_yaml_write_string(fp, text) != 0;
    free(text);
    if (!bad)
      return FB_OK;
    break;
  }
  }
  return fb_err_set(w->err, FB_EINVAL,
                    "source '%s': its value is %s, which a model file cannot hold (only "
                    "constants, expressions, steps, sines, tables and road wheels are written)",
                    elem,
                    t.kind == FB_TFUN_EXPR ? "an expression that cannot be written back"
                                           : "a C callback");
}

/* `value:` of a source: one value (with `dim` when every component has
 * it), or a list. */
static int mw_source(const mw *w, FILE *fp, size_t e, const char *elem)
{
  const size_t dim = fb_bg_element_dim(w->bg, e);
  char **text = calloc(dim, sizeof *text);
  size_t *len = calloc(dim, sizeof *len);
  int rc = text && len ? FB_OK : fb_err_set(w->err, FB_ENOMEM, "out of memory");
  int same = 1;
  for (size_t k = 0; !rc && k < dim; ++k) {
    FILE *m = open_memstream(&text[k], &len[k]);
    rc = m ? mw_tfun(w, m, fb_bg_element_source(w->bg, e, k), elem)
           : fb_err_set(w->err, FB_ENOMEM, "out of memory");
    if (m && fclose(m) && !rc)
      rc = fb_err_set(w->err, FB_ENOMEM, "out of memory");
    same = same && (k == 0 || !strcmp(text[k], text[0]));
  }
  if (!rc && dim == 1)
    fprintf(fp, ", value: %s", text[0]);
  else if (!rc && same)
    fprintf(fp, ", dim: %zu, value: %s", dim, text[0]);
  for (size_t k = 0; !rc && !same && k < dim; ++k)
    fprintf(fp, "%s%s", k ? ", " : ", value: [", text[k]);
  if (!rc && !same)
    fputc(']', fp);
  for (size_t k = 0; text && k < dim; ++k)
    free(text[k]);
  free(text);
  free(len);
  return rc;
}

static int mw_record_file(mw *w, const char *file)
{
  char *copy = fb_strdup(file);
  if (!copy || fb_grow((void **)&w->files, &w->cap_files, w->nfiles, sizeof *w->files)) {
    free(copy);
    return fb_err_set(w->err, FB_ENOMEM, "out of memory");
  }
  w->files[w->nfiles++] = copy;
  return FB_OK;
}

/* A matrix inline (a list of rows) when small, else as DIR/NAME.ELEM.mtx
 * (ELEM the element's full name). */
static int mw_matrix(mw *w, FILE *fp, const fb_mat *a, size_t e)
{
  const size_t r = fb_mat_nrows(a), c = fb_mat_ncols(a);
  if (r * c <= FB_MODEL_INLINE_MAX) {
    fputc('[', fp);
    for (size_t i = 0; i < r; ++i) {
      fputs(i ? ", [" : "[", fp);
      for (size_t j = 0; j < c; ++j) {
        if (j)
          fputs(", ", fp);
        mw_num(fp, fb_mat_get(a, i, j));
      }
      fputc(']', fp);
    }
    fputc(']', fp);
    return FB_OK;
  }
  char *file = mw_printf("%s.%s.mtx", w->name, fb_bg_element_name(w->bg, e));
  char *path = file ? fb_path_join(w->dir, file) : NULL;
  int rc =
      path ? fb_mat_write_mtx(a, path, w->err) : fb_err_set(w->err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = mw_record_file(w, file);
  if (!rc)
    fprintf(fp, "{mtx: %s}", file); /* a model name and element names: plain */
  free(path);
  free(file);
  return rc;
}

/* I, C, R with a matrix law: the scalar key of a one-port of dimension
 * 1 that the loader accepts, else `matrix` (and `ports` when several). */
static int mw_linear_field(mw *w, FILE *fp, size_t e)
{
  const fb_bg *bg = w->bg;
  const fb_bg_kind kind = fb_bg_element_kind(bg, e);
  const fb_mat *law = fb_bg_element_matrix(bg, e);
  const size_t np = fb_bg_element_nports(bg, e);
  const double v = fb_mat_get(law, 0, 0);
  if (np == 1 && fb_bg_element_dim(bg, e) == 1 && (kind == FB_BG_R ? v >= 0 : v > 0)) {
    fprintf(fp, ", %s: ", kind == FB_BG_I ? "m" : kind == FB_BG_C ? "k" : "r");
    mw_num(fp, v);
    return FB_OK;
  }
  if (np > 1) {
    fputs(", ports: [", fp);
    for (size_t k = 0; k < np; ++k)
      fprintf(fp, "%s%zu", k ? ", " : "", fb_bg_element_port_dim(bg, e, k));
    fputc(']', fp);
  }
  fputs(", matrix: ", fp);
  return mw_matrix(w, fp, law, e);
}

/* Fields: linear, tabulated, or the spring of a unilateral contact. */
static int mw_field(mw *w, FILE *fp, size_t e, const char *elem)
{
  const fb_bg *bg = w->bg;
  const fb_table_law *table = fb_bg_element_table_law(bg, e);
  fb_bg_contact contact;
  int rc = FB_OK;
  if (fb_bg_element_matrix(bg, e)) {
    rc = mw_linear_field(w, fp, e);
  } else if (table) {
    const double *x = NULL, *y = NULL;
    const size_t n = fb_table_law_knots(table, &x, &y);
    fputs(", table: {points: [", fp);
    for (size_t i = 0; i < n; ++i) {
      fputs(i ? ", [" : "[", fp);
      mw_num(fp, x[i]);
      fputs(", ", fp);
      mw_num(fp, y[i]);
      fputc(']', fp);
    }
    fputs("]}", fp);
  } else if (fb_bg_element_contact(bg, e, &contact) && contact.spring == e) {
    const char *damper = fb_bg_element_name(bg, contact.damper);
    fputs(", k: ", fp);
    mw_num(fp, contact.k);
    fputs(contact.lambda > 0.0 ? ", lambda: " : ", c: ", fp);
    mw_num(fp, contact.lambda > 0.0 ? contact.lambda : contact.c);
    fputs(", damper: ", fp);
    mw_plain(fp, strrchr(damper, '.') ? strrchr(damper, '.') + 1 : damper);
  } else {
    const fb_law_ops *ops = fb_bg_element_law(bg, e, NULL);
    return fb_err_set(w->err, FB_EINVAL,
                      "%s '%s': its nonlinear law '%s' cannot be written in a model file "
                      "(only tables and unilateral contacts are)",
                      fb_bg_kind_name(fb_bg_element_kind(bg, e)), elem,
                      ops && ops->name ? ops->name : "?");
  }
  const double *x0 = fb_bg_element_initial(bg, e);
  if (!rc && x0) {
    fputs(", initial: ", fp);
    mw_nums(fp, x0, fb_bg_element_dim(bg, e));
  }
  return rc;
}

/* The type key and the kind's own keys of element e. */
static int mw_element_body(mw *w, FILE *fp, size_t e, const char *elem)
{
  const fb_bg *bg = w->bg;
  const fb_bg_kind kind = fb_bg_element_kind(bg, e);
  const size_t dim = fb_bg_element_dim(bg, e);
  fb_bg_contact contact;
  const int is_contact = fb_bg_element_contact(bg, e, &contact);
  static const char *const types[] = {"Se", "Sf",  "I", "C", "R",        "TF",
                                      "GY", "MTF", "0", "1", "composite"};
  fprintf(fp, ", type: %s", is_contact ? "contact" : types[kind]);
  switch (kind) {
  case FB_BG_SE:
  case FB_BG_SF: return mw_source(w, fp, e, elem);
  case FB_BG_I:
  case FB_BG_C:
  case FB_BG_R: return mw_field(w, fp, e, elem);
  case FB_BG_TF:
  case FB_BG_GY:
    fputs(kind == FB_BG_TF ? ", ratio: " : ", r: ", fp);
    mw_num(fp, fb_bg_element_modulus(bg, e));
    break;
  case FB_BG_MTF:
    fputs(", matrix: ", fp);
    return mw_matrix(w, fp, fb_bg_element_matrix(bg, e), e);
  case FB_BG_J0:
  case FB_BG_J1: break;
  case FB_BG_COMPOSITE:
    fputs(", parts: [", fp);
    for (size_t k = 0; k + 1 < fb_bg_element_nports(bg, e); ++k)
      fprintf(fp, "%s%zu", k ? ", " : "", fb_bg_element_port_dim(bg, e, k));
    fputc(']', fp);
    return FB_OK;
  }
  if (dim > 1)
    fprintf(fp, ", dim: %zu", dim);
  return FB_OK;
}

/* ---- Bodies and definitions. */

static int mw_elements(mw *w, FILE *fp, size_t scope)
{
  const fb_bg *bg = w->bg;
  const char *prefix = w->scopes[scope].prefix;
  const size_t plen = strlen(prefix);
  unsigned char *done = calloc(w->nscopes + 1, 1);
  int rc = done ? FB_OK : fb_err_set(w->err, FB_ENOMEM, "out of memory");
  fputs("elements:\n", fp);
  size_t count = 0;
  for (size_t e = 0; !rc && e < fb_bg_nelements(bg); ++e) {
    const char *full = fb_bg_element_name(bg, e);
    if (strncmp(full, prefix, plen) != 0)
      continue;
    const char *local = full + plen, *dot = strchr(local, '.');
    fb_bg_contact contact;
    if (dot) {
      const long c = mw_scope_find(w, full, plen + (size_t)(dot - local) + 1);
      if (c >= 0 && !done[c]) {
        done[c] = 1;
        char inst[256];
        snprintf(inst, sizeof inst, "%.*s", (int)(dot - local), local);
        fputs("  - {name: ", fp);
        mw_plain(fp, inst);
        fputs(", type: ", fp);
        mw_plain(fp, w->scopes[c].def);
        fputs("}\n", fp);
        ++count;
      }
      continue;
    }
    if (fb_bg_element_contact(bg, e, &contact) && contact.damper == e)
      continue; /* written with its spring */
    if (!mw_is_name(local))
      rc = fb_err_set(w->err, FB_EINVAL, "element '%s': '%s' is not a model name", full, local);
    if (!rc) {
      fputs("  - {name: ", fp);
      mw_plain(fp, local);
      rc = mw_element_body(w, fp, e, full);
      fputs("}\n", fp);
      ++count;
    }
  }
  if (!rc && count == 0)
    fputs("  []\n", fp);
  free(done);
  return rc;
}

static int mw_bonds(mw *w, FILE *fp, size_t scope)
{
  const fb_bg *bg = w->bg;
  const size_t plen = strlen(w->scopes[scope].prefix);
  int any = 0;
  for (size_t b = 0; b < fb_bg_nbonds(bg); ++b) {
    if (w->bond_scope[b] != scope)
      continue;
    const char *name = fb_bg_bond_name(bg, b), *local = name + plen;
    const char *from = w->refs[2 * b], *to = w->refs[2 * b + 1];
    char made[1024];
    snprintf(made, sizeof made, "%s->%s", from, to);
    const int named = mw_is_name(local);
    if (!named && strcmp(local, made) != 0)
      return fb_err_set(w->err, FB_EINVAL,
                        "bond '%s': its name is no model name and not the one a model gives "
                        "an unnamed bond ('%s')",
                        name, made);
    fprintf(fp, "%s  - {", any ? "" : "bonds:\n");
    if (named) {
      fputs("name: ", fp);
      mw_plain(fp, local);
      fputs(", ", fp);
    }
    fputs("from: ", fp);
    mw_plain(fp, from);
    fputs(", to: ", fp);
    mw_plain(fp, to);
    if (fb_bg_bond_domain(bg, b) != fb_bg_default_domain(bg))
      fprintf(fp, ", domain: %s", mw_domain_name(fb_bg_bond_domain(bg, b)));
    fputs("}\n", fp);
    any = 1;
  }
  return FB_OK;
}

/* The body (ports, elements, bonds) of scope, at indentation 0. */
static int mw_body(mw *w, size_t scope, char **text)
{
  size_t len = 0;
  FILE *fp = open_memstream(text, &len);
  if (!fp)
    return fb_err_set(w->err, FB_ENOMEM, "out of memory");
  const mw_scope *s = &w->scopes[scope];
  for (size_t i = 0; i < s->nports; ++i) {
    fprintf(fp, "%s  - {name: ", i ? "" : "ports:\n");
    mw_plain(fp, s->ports[i].name);
    fputs(", at: ", fp);
    mw_plain(fp, s->ports[i].at);
    fprintf(fp, ", direction: %s}\n", s->ports[i].dir == FB_PORT_IN ? "in" : "out");
  }
  int rc = mw_elements(w, fp, scope);
  if (!rc)
    rc = mw_bonds(w, fp, scope);
  if (fclose(fp) && !rc)
    rc = fb_err_set(w->err, FB_ENOMEM, "out of memory");
  return rc;
}

/* A definition name for scope: its prefix with '_' for '.', made unique
 * and different from the built-in types. */
static char *mw_def_name(const mw *w, const char *prefix)
{
  char base[256];
  snprintf(base, sizeof base, "%.*s", (int)strlen(prefix) - 1, prefix);
  for (char *p = base; *p; ++p)
    if (*p == '.')
      *p = '_';
  static const char *const builtin[] = {"Se",        "Sf",      "I",   "C",    "R",
                                        "TF",        "GY",      "MTF", "zero", "one",
                                        "composite", "contact", NULL};
  char name[300];
  for (int n = 0;; ++n) {
    if (n)
      snprintf(name, sizeof name, "%s_%d", base, n + 1);
    else
      snprintf(name, sizeof name, "%s", base);
    int clash = 0;
    for (size_t i = 0; builtin[i] && !clash; ++i)
      clash = !strcmp(name, builtin[i]);
    for (size_t i = 0; i < w->ndefs && !clash; ++i)
      clash = !strcmp(name, w->defs[i].name);
    if (!clash)
      return fb_strdup(name);
  }
}

/* Writes scope's definition, or finds an equal one. */
static int mw_define(mw *w, size_t scope)
{
  char *text = NULL;
  int rc = mw_body(w, scope, &text);
  for (size_t i = 0; !rc && i < w->ndefs; ++i)
    if (!strcmp(w->defs[i].text, text)) {
      w->scopes[scope].def = w->defs[i].name;
      free(text);
      return FB_OK;
    }
  char *name = rc ? NULL : mw_def_name(w, w->scopes[scope].prefix);
  if (!rc && (!name || fb_grow((void **)&w->defs, &w->cap_defs, w->ndefs, sizeof *w->defs)))
    rc = fb_err_set(w->err, FB_ENOMEM, "out of memory");
  if (rc) {
    free(text);
    free(name);
    return rc;
  }
  w->defs[w->ndefs++] = (mw_def){name, text};
  w->scopes[scope].def = name;
  return FB_OK;
}

/* Number of '.' in s: the nesting depth of a prefix. */
static size_t mw_depth(const char *s)
{
  size_t n = 0;
  for (; *s; ++s)
    n += *s == '.';
  return n;
}

/* Definitions innermost first, so each names the definitions it uses. */
static int mw_define_all(mw *w)
{
  size_t deepest = 0;
  for (size_t i = 0; i < w->nscopes; ++i)
    deepest = mw_depth(w->scopes[i].prefix) > deepest ? mw_depth(w->scopes[i].prefix) : deepest;
  int rc = FB_OK;
  for (size_t d = deepest; !rc && d > 0; --d)
    for (size_t i = 1; !rc && i < w->nscopes; ++i)
      if (mw_depth(w->scopes[i].prefix) == d)
        rc = mw_define(w, i);
  return rc;
}

/* ---- The document. */

static int mw_probes(const mw *w, FILE *fp, const fb_probe_spec *p, size_t n)
{
  static const char *const kinds[] = {"effort", "flow", "power", "state", "energy"};
  int rc = FB_OK;
  if (n)
    fputs("probes:\n", fp);
  for (size_t i = 0; !rc && i < n; ++i) {
    char what[300];
    snprintf(what, sizeof what, "probe '%s'", p[i].name ? p[i].name : "");
    if (p[i].gain != 1.0 && !p[i].unit)
      return fb_err_set(w->err, FB_EINVAL, "%s: a gain without a unit cannot be written", what);
    fputs("  - name: ", fp);
    rc = mw_str(w, fp, p[i].name, what);
    fprintf(fp, "\n    %s: ", kinds[p[i].kind]);
    if (!rc)
      rc = mw_str(w, fp, p[i].target, what);
    if (p[i].component >= 0)
      fprintf(fp, "\n    component: %ld", p[i].component + 1);
    if (p[i].integrate)
      fputs("\n    integrate: true", fp);
    if (p[i].gain != 1.0) {
      fputs("\n    gain: ", fp);
      mw_num(fp, p[i].gain);
    }
    if (!rc && p[i].unit) {
      fputs("\n    unit: ", fp);
      rc = mw_str(w, fp, p[i].unit, what);
    }
    if (p[i].nweights) {
      fputs("\n    weights: ", fp);
      mw_nums(fp, p[i].weights, p[i].nweights);
    }
    fputc('\n', fp);
  }
  return rc;
}

static void mw_simulation(FILE *fp, const fb_sim_opts *o, fb_model_initial initial)
{
  static const char *const initials[] = {"given", "zero", "static"};
  const struct {
    const char *key;
    double v;
  } reals[] = {{"t_start", o->t_start},   {"t_end", o->t_end},
               {"rtol", o->rtol},         {"atol", o->atol},
               {"max_step", o->max_step}, {"sample_rate", o->sample_rate}};
  fputs("simulation:\n", fp);
  for (size_t i = 0; i < sizeof reals / sizeof reals[0]; ++i) {
    fprintf(fp, "  %s: ", reals[i].key);
    mw_num(fp, reals[i].v);
    fputc('\n', fp);
  }
  fprintf(fp, "  max_order: %d\n  max_steps: %ld\n  stability_limit_detection: %s\n",
          o->max_order, o->max_steps, o->stability_limit_detection ? "true" : "false");
  if (o->nbreakpoints) {
    fputs("  breakpoints: ", fp);
    mw_nums(fp, o->breakpoints, o->nbreakpoints);
    fputc('\n', fp);
  }
  fprintf(fp, "  initial: %s\n", initials[initial]);
}

/* The definitions, indented under `subsystems`. */
static void mw_subsystems(const mw *w, FILE *fp)
{
  if (w->ndefs)
    fputs("subsystems:\n", fp);
  for (size_t i = 0; i < w->ndefs; ++i) {
    fputs("  ", fp);
    mw_plain(fp, w->defs[i].name);
    fputs(":\n", fp);
    for (const char *line = w->defs[i].text; *line;) {
      const char *end = strchr(line, '\n');
      const size_t n = end ? (size_t)(end - line) : strlen(line);
      fprintf(fp, "    %.*s\n", (int)n, line);
      line += n + (end ? 1 : 0);
    }
  }
}

static int mw_document(mw *w, FILE *fp, const fb_probe_spec *probes, size_t nprobes,
                       const fb_sim_opts *opts, fb_model_initial initial)
{
  fprintf(fp,
          "# Written by flexbond (fb_model_write) from the bond graph '%s'.\n"
          "# Matrices of more than %d entries are in the .mtx files beside this one.\n",
          w->name, FB_MODEL_INLINE_MAX);
  fprintf(fp, "model: %s\ndomain: %s\n", w->name, mw_domain_name(fb_bg_default_domain(w->bg)));
  mw_subsystems(w, fp);
  char *root = NULL;
  int rc = mw_body(w, 0, &root);
  if (!rc)
    fputs(root, fp);
  free(root);
  if (!rc)
    rc = mw_probes(w, fp, probes, nprobes);
  if (!rc)
    mw_simulation(fp, opts, initial);
  return rc;
}

static int mw_write_yaml(mw *w, const fb_probe_spec *probes, size_t nprobes,
                         const fb_sim_opts *opts, fb_model_initial initial)
{
  char *file = mw_printf("%s%s.yaml", "", w->name);
  char *path = file ? fb_path_join(w->dir, file) : NULL;
  fb_out *out = NULL;
  int rc =
      path ? fb_out_open(path, &out, w->err) : fb_err_set(w->err, FB_ENOMEM, "out of memory");
  if (!rc) {
    rc = mw_document(w, fb_out_stream(out), probes, nprobes, opts, initial);
    if (rc)
      fb_out_abort(&out);
    else
      rc = fb_out_commit(&out, w->err);
  }
  if (!rc)
    rc = mw_record_file(w, file);
  free(path);
  free(file);
  return rc;
}

/* Frees w; on failure (failed) removes the files written, and frees
 * their names unless they were handed to the caller (kept). */
static void mw_release(mw *w, int failed, int kept)
{
  for (size_t i = 0; i < w->nscopes; ++i) {
    for (size_t k = 0; k < w->scopes[i].nports; ++k) {
      free(w->scopes[i].ports[k].name);
      free(w->scopes[i].ports[k].at);
    }
    free(w->scopes[i].ports);
    free(w->scopes[i].prefix);
  }
  free(w->scopes);
  for (size_t i = 0; i < w->ndefs; ++i) {
    free(w->defs[i].name);
    free(w->defs[i].text);
  }
  free(w->defs);
  for (size_t i = 0; w->refs && i < 2 * fb_bg_nbonds(w->bg); ++i)
    free(w->refs[i]);
  free(w->refs);
  free(w->bond_scope);
  free(w->taken);
  for (size_t i = 0; i < w->nfiles; ++i) {
    char *path = failed ? fb_path_join(w->dir, w->files[i]) : NULL;
    if (path)
      remove(path);
    free(path);
    if (!kept)
      free(w->files[i]);
  }
  if (!kept)
    free(w->files);
}

int fb_model_write(const fb_bg *bg, const fb_probe_spec *probes, size_t nprobes,
                   const fb_sim_opts *opts, fb_model_initial initial, const char *dir,
                   const char *name, char ***files, size_t *nfiles, fb_err *err)
{
  if (files)
    *files = NULL;
  if (nfiles)
    *nfiles = 0;
  if (!bg || !opts || !dir || (nprobes && !probes))
    return fb_err_set(err, FB_EINVAL, "fb_model_write: NULL argument");
  if (!mw_is_name(name))
    return fb_err_set(err, FB_EINVAL,
                      "model name '%s': must start with a letter or '_' and hold only letters, "
                      "digits and '_'",
                      name ? name : "");
  if ((int)initial < 0 || initial > FB_MODEL_INITIAL_STATIC)
    return fb_err_set(err, FB_EINVAL, "fb_model_write: unknown initial state choice %d",
                      (int)initial);
  mw w = {.bg = bg, .dir = dir, .name = name, .err = err};
  const size_t nb = fb_bg_nbonds(bg);
  w.taken = calloc(fb_bg_ndeclared_ports(bg) + 1, 1);
  w.bond_scope = calloc(nb + 1, sizeof *w.bond_scope);
  w.refs = calloc(2 * nb + 1, sizeof *w.refs);
  int rc =
      w.taken && w.bond_scope && w.refs ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = mw_collect_scopes(&w);
  for (size_t b = 0; !rc && b < nb; ++b)
    rc = mw_place_bond(&w, b);
  if (!rc)
    rc = mw_define_all(&w);
  if (!rc)
    rc = mw_write_yaml(&w, probes, nprobes, opts, initial);
  if (!rc && files) {
    *files = w.files;
    *nfiles = w.nfiles;
  }
  mw_release(&w, rc != FB_OK, rc == FB_OK && files);
  return rc;
}
