/* SPDX-License-Identifier: BSD-3-Clause */
/* Nastran DMIG entries (flexbond/reduced.h), as the MSC/NX Nastran Quick
 * Reference Guide's "DMIG" bulk data entry defines them: a header entry
 * (NAME, "0", IFO, TIN, TOUT, POLAR, blank, NCOL) and column entries
 * (NAME, GJ, CJ, blank, then G, C, A, B groups of four fields, two per
 * line of eight fields). Bulk data field formats: small (eight columns a
 * field, fields 2 to 9 of a line), large ("DMIG*": sixteen columns, four
 * fields a line, continued on lines starting with '*') and free
 * (comma-separated). Real numbers take Nastran's forms ("1.5+6", "1.5D+6",
 * "1.5E6"). */
#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/textfile.h"
#include "fem/reduced_internal.h"

/* DMIG_FIELD_MAX: room for any number a writer prints (a double's 17
 * digits with sign, point and exponent take 24); a longer field is refused
 * at its line, never cut. */
enum { DMIG_MAX_FIELDS = 8, DMIG_FIELD_MAX = 64 };

/* One card: its fields after the first (the entry's name), with the line
 * each came from. */
typedef struct dmig_card {
  char (*f)[DMIG_FIELD_MAX];
  size_t *line;
  size_t n, cap;
  int small; /* a small-field card: 8-column numbers */
} dmig_card;

typedef struct dmig_state {
  fb_text_reader r;
  char *pending; /* a line read past the card, owned */
  size_t pending_line;
} dmig_state;

static int dmig_error(const dmig_state *s, size_t line, const char *what, const char *tok)
{
  fb_err_set(s->r.err, FB_EPARSE, "%s:%zu: %s", s->r.path, line, what);
  if (tok)
    fb_err_set_excerpt(s->r.err, tok, strlen(tok));
  return FB_EPARSE;
}

static int card_push(const dmig_state *s, dmig_card *c, const char *text, size_t len,
                     size_t line)
{
  if (c->n == c->cap) {
    const size_t nc = c->cap ? 2 * c->cap : 32;
    char(*f)[DMIG_FIELD_MAX] = realloc(c->f, nc * sizeof *f);
    if (f)
      c->f = f;
    size_t *l = realloc(c->line, nc * sizeof *l);
    if (l)
      c->line = l;
    if (!f || !l)
      return FB_ENOMEM;
    c->cap = nc;
  }
  while (len && (*text == ' ' || *text == '\t')) {
    ++text;
    --len;
  }
  while (len && (text[len - 1] == ' ' || text[len - 1] == '\t'))
    --len;
  if (len >= DMIG_FIELD_MAX) {
    fb_err_set(s->r.err, FB_EPARSE, "%s:%zu: a field of %zu characters, longer than any number",
               s->r.path, line, len);
    return FB_EPARSE;
  }
  memcpy(c->f[c->n], text, len);
  c->f[c->n][len] = '\0';
  c->line[c->n++] = line;
  return FB_OK;
}

/* The data fields of one line: free (commas), large (4 of 16 columns
 * after 8) or small (8 of 8 columns after 8). */
static int line_fields(const dmig_state *s, dmig_card *c, const char *line, size_t line_no,
                       int large)
{
  const size_t len = strlen(line);
  if (strchr(line, ',')) {
    const char *p = strchr(line, ',') + 1; /* past the first field */
    size_t k = 0;
    for (; k < DMIG_MAX_FIELDS; ++k) {
      const char *comma = strchr(p, ',');
      const size_t n = comma ? (size_t)(comma - p) : strlen(p);
      const int rc = card_push(s, c, p, n, line_no);
      if (rc)
        return rc;
      if (!comma)
        break;
      p = comma + 1;
    }
    for (++k; k < DMIG_MAX_FIELDS; ++k)
      if (card_push(s, c, "", 0, line_no))
        return FB_ENOMEM;
    return FB_OK;
  }
  const size_t width = large ? 16 : 8, count = large ? 4 : 8;
  for (size_t k = 0; k < count; ++k) {
    const size_t at = 8 + k * width;
    const size_t n = at >= len ? 0 : (len - at < width ? len - at : width);
    const int rc = card_push(s, c, at < len ? line + at : "", n, line_no);
    if (rc)
      return rc;
  }
  return FB_OK;
}

/* A line continues the card before it when its first field is a
 * continuation mark or blank. */
static int is_continuation(const char *line)
{
  return line[0] == '+' || line[0] == '*' || line[0] == ' ' || line[0] == ',' ||
         line[0] == '\t';
}

static int next_line(dmig_state *s, char **line, size_t *line_no)
{
  if (s->pending) {
    *line = s->pending;
    *line_no = s->pending_line;
    s->pending = NULL;
    return FB_OK;
  }
  char *l = NULL;
  for (;;) {
    const int rc = fb_text_next_line(&s->r, &l);
    if (rc)
      return rc;
    if (!l || (l[0] != '$' && l[strspn(l, " \t")] != '\0'))
      break;
  }
  *line = l ? strdup(l) : NULL;
  *line_no = s->r.line_no;
  if (l && !*line)
    return fb_err_set(s->r.err, FB_ENOMEM, "out of memory reading %s", s->r.path);
  return FB_OK;
}

/* The next DMIG card of any name (*found 0 at the end of the file). */
static int next_card(dmig_state *s, dmig_card *c, size_t *first_line, int *found)
{
  c->n = 0;
  *found = 0;
  for (;;) {
    char *line = NULL;
    size_t no = 0;
    int rc = next_line(s, &line, &no);
    if (rc || !line)
      return rc;
    if (strncasecmp(line, "DMIG", 4) != 0 || (line[4] && !strchr("* ,\t", line[4]))) {
      free(line);
      continue;
    }
    const int large = line[4] == '*';
    c->small = !large && !strchr(line, ',');
    *first_line = no;
    rc = line_fields(s, c, line, no, large);
    free(line);
    while (!rc) {
      rc = next_line(s, &line, &no);
      if (rc || !line)
        break;
      if (!is_continuation(line)) {
        s->pending = line;
        s->pending_line = no;
        break;
      }
      rc = line_fields(s, c, line, no, large);
      free(line);
    }
    if (rc)
      return rc == FB_ENOMEM
                 ? fb_err_set(s->r.err, FB_ENOMEM, "out of memory reading %s", s->r.path)
                 : rc;
    *found = 1;
    return FB_OK;
  }
}

static int parse_int(const char *tok, long *v)
{
  char *end;
  errno = 0;
  *v = strtol(tok, &end, 10);
  return !errno && end != tok && *end == '\0';
}

/* A Nastran real: D for E, an exponent's sign without its letter. */
static int parse_real(const dmig_state *s, size_t line, const char *tok, double *v, int *digits)
{
  char buf[DMIG_FIELD_MAX + 2];
  size_t k = 0, i = 0;
  for (; tok[i] && k + 2 < sizeof buf; ++i) {
    const char ch = tok[i];
    if ((ch == '+' || ch == '-') && i > 0 &&
        (isdigit((unsigned char)tok[i - 1]) || tok[i - 1] == '.'))
      buf[k++] = 'E';
    if (ch == 'd' || ch == 'D')
      buf[k++] = 'E';
    else
      buf[k++] = ch;
  }
  buf[k] = '\0';
  if (tok[i]) { /* more letters for E than the buffer holds */
    fb_err_set(s->r.err, FB_EPARSE, "not a number");
    fb_err_set_excerpt(s->r.err, tok, strlen(tok));
    return fb_err_prefix(s->r.err, "%s:%zu: value: ", s->r.path, line);
  }
  if (fb_parse_decimal_field(buf, v, s->r.err)) {
    fb_err_set_excerpt(s->r.err, tok, strlen(tok));
    return fb_err_prefix(s->r.err, "%s:%zu: value: ", s->r.path, line);
  }
  *digits = reduced_digits(tok);
  return FB_OK;
}

static int grid_comp(const dmig_state *s, const dmig_card *c, size_t k, long *g, int *comp)
{
  long cv;
  if (!parse_int(c->f[k], g) || *g <= 0)
    return dmig_error(s, c->line[k], "grid point: not an integer > 0", c->f[k]);
  if (!c->f[k + 1][0] || !parse_int(c->f[k + 1], &cv) || cv < 1 || cv > 6)
    return dmig_error(s, c->line[k + 1],
                      "component: expected 1 to 6 (scalar and extra points are not read)",
                      c->f[k + 1]);
  *comp = (int)cv;
  return FB_OK;
}

/* A column entry's G, C, A(, B) groups into l. */
static int column_card(const dmig_state *s, const dmig_card *c, reduced_list *l, int *digits)
{
  long gj;
  int cj;
  if (c->n < 4)
    return dmig_error(s, c->line[0], "column entry: expected NAME, GJ, CJ", NULL);
  int rc = grid_comp(s, c, 1, &gj, &cj);
  for (size_t k = 4; !rc && k + 2 < c->n + 1 && k < c->n; k += 4) {
    if (!c->f[k][0])
      continue; /* a blank group: the rest of a line */
    if (k + 2 >= c->n)
      return dmig_error(s, c->line[k], "column entry: a row without its value", NULL);
    reduced_entry e = {.node_j = gj, .comp_j = cj, .line = c->line[k + 2]};
    rc = grid_comp(s, c, k, &e.node_i, &e.comp_i);
    int d = 0;
    if (!rc)
      rc = parse_real(s, c->line[k + 2], c->f[k + 2], &e.val, &d);
    if (!rc && k + 3 < c->n && c->f[k + 3][0])
      rc = dmig_error(s, c->line[k + 3], "an imaginary part in a real matrix (TIN 1 or 2)",
                      c->f[k + 3]);
    if (!rc && e.val != 0.0 && d < *digits)
      *digits = d;
    if (!rc)
      rc = reduced_list_push(l, &e, s->r.err);
  }
  return rc;
}

static int header_card(const dmig_state *s, const dmig_card *c, reduced_list *l)
{
  long ifo, tin;
  if (c->n < 4 || !parse_int(c->f[3], &tin))
    return dmig_error(s, c->line[0], "header entry: expected NAME, 0, IFO, TIN", NULL);
  if (!parse_int(c->f[2], &ifo) || (ifo != 1 && ifo != 6))
    return dmig_error(s, c->line[2],
                      "IFO: expected 6 (symmetric) or 1 (square); a stiffness or mass is one "
                      "of them",
                      c->f[2]);
  if (tin != 1 && tin != 2)
    return dmig_error(s, c->line[3],
                      "TIN: expected 1 or 2 (real); complex matrices are not "
                      "read",
                      c->f[3]);
  l->one_triangle = ifo == 6;
  return FB_OK;
}

/* Every card of the matrices named k->name (k's name is the DMIG name
 * here) and m's. */
static int read_cards(dmig_state *s, const char *names[2], reduced_list *lists[2])
{
  dmig_card c = {0};
  int rc = FB_OK, headers[2] = {0, 0}, digits[2] = {99, 99};
  size_t first = 0;
  for (;;) {
    int found = 0;
    rc = next_card(s, &c, &first, &found);
    if (rc || !found)
      break;
    for (int k = 0; k < 2 && !rc; ++k) {
      if (!lists[k] || c.n < 2 || strcasecmp(c.f[0], names[k]) != 0)
        continue;
      if (!strcmp(c.f[1], "0")) {
        if (headers[k]++)
          rc = dmig_error(s, first, "a second header entry of the matrix", NULL);
        else
          rc = header_card(s, &c, lists[k]);
      } else if (!headers[k]) {
        rc = dmig_error(s, first, "a column entry before its matrix's header entry", NULL);
      } else {
        rc = column_card(s, &c, lists[k], &digits[k]);
      }
    }
    if (rc)
      break;
  }
  for (int k = 0; k < 2 && !rc; ++k)
    if (lists[k] && !headers[k])
      rc = fb_err_set(s->r.err, FB_EPARSE, "%s:%zu: no DMIG matrix named %s", s->r.path,
                      s->r.line_no ? s->r.line_no : 1, names[k]);
  for (int k = 0; k < 2; ++k)
    if (lists[k])
      lists[k]->precision = reduced_precision(digits[k] == 99 ? 17 : digits[k]);
  free(c.f);
  free(c.line);
  free(s->pending);
  s->pending = NULL;
  return rc;
}

int fb_reduced_read_dmig(const char *path, const char *k_name, const char *m_name,
                         const char *nodes_path, fb_reduced **out, fb_err *err)
{
  if (!out || !path || !k_name || !nodes_path)
    return fb_err_set(err, FB_EINVAL, "reduced structure: a path, name or the output is NULL");
  *out = NULL;
  reduced_nodes nodes;
  int rc = reduced_nodes_read_plain(nodes_path, "DMIG", &nodes, err);
  if (rc)
    return rc;
  const size_t cap = reduced_list_cap(&nodes);
  reduced_list k = {.path = path, .name = "K", .max = cap},
               m = {.path = path, .name = "M", .max = cap};
  dmig_state s = {0};
  rc = fb_text_open(&s.r, path, "DMIG", err);
  if (!rc) {
    const char *names[2] = {k_name, m_name};
    reduced_list *lists[2] = {&k, m_name ? &m : NULL};
    rc = read_cards(&s, names, lists);
  }
  fb_text_close(&s.r);
  if (!rc)
    rc = reduced_build(&nodes, &k, m_name ? &m : NULL, out, err);
  reduced_list_free(&k);
  reduced_list_free(&m);
  reduced_nodes_free(&nodes);
  return rc;
}
