/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of the escaping writers (flexbond/escape.h): each over hostile strings (quotes,
 * backslashes, line breaks, tabs, other control bytes, markup, a DOT statement, a table
 * pipe, a formula, UTF-8 both well-formed and not), against the exact expected bytes;
 * then documents built from them are read back by independent readers where the machine
 * has them: Python's json, csv and xml.dom.minidom, which must give back the original
 * strings, and Graphviz's dot, which must accept the graph with one node per string. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/error.h"
#include "flexbond/escape.h"

#include "check.h"
#include "tmpdir.h"

typedef void write_fn(FILE *fp, const char *s);

/* What fn writes for s, in fresh memory. */
static char *capture(write_fn *fn, const char *s)
{
  char *text = NULL;
  size_t len = 0;
  FILE *fp = open_memstream(&text, &len);
  if (!fp)
    return NULL;
  fn(fp, s);
  fclose(fp);
  return text;
}

/* CHECK that fn writes exactly want for s; prints both when not. */
static void check_writes(const char *what, write_fn *fn, const char *s, const char *want)
{
  char *got = capture(fn, s);
  ++check_count;
  if (!got || strcmp(got, want) != 0) {
    ++check_failures;
    fprintf(stderr, "%s: got [%s], want [%s]\n", what, got ? got : "(null)", want);
  }
  free(got);
}

/* ---- The writers with one signature, for check_writes. */

static void csv_plain(FILE *fp, const char *s)
{
  fb_csv_write_field(fp, s, 0);
}

static void csv_text(FILE *fp, const char *s)
{
  fb_csv_write_field(fp, s, FB_CSV_TEXT);
}

static void csv_always(FILE *fp, const char *s)
{
  fb_csv_write_field(fp, s, FB_CSV_QUOTE_ALWAYS);
}

/* "NAME [UNIT]" with the unit a fixed hostile one. */
static void csv_header_cell(FILE *fp, const char *s)
{
  const char *const parts[] = {s, " [", "m,\"s\"", "]"};
  fb_csv_write_field_parts(fp, parts, 4, FB_CSV_TEXT);
}

/* Empty and NULL parts ahead of s: the guard looks at the first byte. */
static void csv_empty_parts(FILE *fp, const char *s)
{
  const char *const parts[] = {NULL, "", s};
  fb_csv_write_field_parts(fp, parts, 3, FB_CSV_TEXT);
}

/* The first 3 bytes of s. */
static void dot_three(FILE *fp, const char *s)
{
  fb_dot_write_text_n(fp, s, 3);
}

#define SMILE "\xF0\x9F\x98\x80" /* U+1F600 */
#define FFFD "\xEF\xBF\xBD"      /* U+FFFD */

static void test_json(void)
{
  check_writes("json quote", fb_json_write_string, "a\"b\\c", "\"a\\\"b\\\\c\"");
  check_writes("json breaks", fb_json_write_string, "l1\nl2\r\nx\ry\tz\b\f",
               "\"l1\\nl2\\r\\nx\\ry\\tz\\b\\f\"");
  check_writes("json controls", fb_json_write_string, "\x01\x1f\x7f", "\"\\u0001\\u001f\x7f\"");
  check_writes("json markup", fb_json_write_string, "</script><b>&amp;",
               "\"</script><b>&amp;\"");
  check_writes("json utf-8", fb_json_write_string, "\xC3\xA9 \xE6\x97\xA5 " SMILE,
               "\"\xC3\xA9 \xE6\x97\xA5 " SMILE "\"");
  check_writes("json malformed", fb_json_write_string, "\xFF\xC3(", "\"" FFFD FFFD "(\"");
  check_writes("json empty", fb_json_write_string, "", "\"\"");
  check_writes("json NULL", fb_json_write_string, NULL, "null");
}

static void number(FILE *fp, const char *s)
{
  fb_json_write_number(fp, strtod(s, NULL));
}

static void test_json_numbers(void)
{
  check_writes("number", number, "1.5", "1.5");
  check_writes("number exp", number, "1e300", "1e+300");
  check_writes("number -0", number, "-0", "-0");
  check_writes("number 10 digits", number, "0.1234567890123", "0.123456789");
  check_writes("number nan", number, "nan", "null");
  check_writes("number inf", number, "inf", "null");
  check_writes("number -inf", number, "-inf", "null");
}

static void test_dot(void)
{
  check_writes("dot quote", fb_dot_write_text, "a\"b\\c", "a\\\"b\\\\c");
  check_writes("dot statement", fb_dot_write_text, "\"]; x -> y; [\"", "\\\"]; x -> y; [\\\"");
  check_writes("dot breaks", fb_dot_write_text, "l1\nl2\r\nx\ry", "l1\\nl2\\nx\\ny");
  check_writes("dot controls", fb_dot_write_text, "t\tx\x01\x7f", "t" FFFD "x" FFFD FFFD);
  check_writes("dot markup", fb_dot_write_text, "<b>&{|}", "<b>&{|}");
  check_writes("dot utf-8", fb_dot_write_text, "\xC3\xA9" SMILE, "\xC3\xA9" SMILE);
  check_writes("dot prefix", dot_three, "abc.def", "abc");
  check_writes("dot prefix cuts a character", dot_three, "ab\xC3\xA9", "ab" FFFD);
  check_writes("dot prefix of a short string", dot_three, "a", "a");
}

static void test_markdown(void)
{
  check_writes("md html", fb_md_write_text, "</script><b>&amp;",
               "&lt;/script&gt;&lt;b&gt;&amp;amp;");
  check_writes("md pipe", fb_md_write_text, "a|b", "a\\|b");
  check_writes("md image", fb_md_write_text, "![x](http://e/y.png)",
               "!\\[x\\](http://e/y.png)");
  check_writes("md emphasis", fb_md_write_text, "`*_#~", "\\`\\*\\_\\#\\~");
  check_writes("md backslash", fb_md_write_text, "a\"b\\c", "a\"b\\\\c");
  check_writes("md breaks", fb_md_write_text, "l1\nl2\r\n# x\ty", "l1 l2  \\# x y");
  check_writes("md ordinary", fb_md_write_text, "../examples/apc6x6.yaml (v2), 10 km/h",
               "../examples/apc6x6.yaml (v2), 10 km/h");
  check_writes("md utf-8", fb_md_write_text, "\xC3\xA9" SMILE, "\xC3\xA9" SMILE);
}

static void test_csv(void)
{
  check_writes("csv plain", csv_plain, "tire_force_LF", "tire_force_LF");
  check_writes("csv comma", csv_plain, "a,b", "\"a,b\"");
  check_writes("csv quote", csv_plain, "a\"b", "\"a\"\"b\"");
  check_writes("csv breaks", csv_plain, "l1\nl2\rx", "\"l1\nl2\rx\"");
  check_writes("csv formula, not text", csv_plain, "=cmd()", "=cmd()");
  check_writes("csv formula", csv_text, "=cmd()", "'=cmd()");
  check_writes("csv plus", csv_text, "+1", "'+1");
  check_writes("csv minus", csv_text, "-x", "'-x");
  check_writes("csv at", csv_text, "@SUM(A1)", "'@SUM(A1)");
  check_writes("csv tab", csv_text, "\tx", "'\tx");
  check_writes("csv CR", csv_text, "\rx", "\"'\rx\"");
  check_writes("csv formula and comma", csv_text, "=a,b", "\"'=a,b\"");
  check_writes("csv formula inside", csv_text, "a=b", "a=b");
  check_writes("csv quote always", csv_always, "x", "\"x\"");
  check_writes("csv header cell", csv_header_cell, "v", "\"v [m,\"\"s\"\"]\"");
  check_writes("csv header cell formula", csv_header_cell, "=x", "\"'=x [m,\"\"s\"\"]\"");
  check_writes("csv empty parts", csv_empty_parts, "=x", "'=x");
  check_writes("csv utf-8", csv_plain, "\xC3\xA9" SMILE, "\xC3\xA9" SMILE);
  check_writes("csv empty", csv_text, "", "");
}

static void test_xml(void)
{
  check_writes("xml markup", fb_xml_write_text, "</script><b>&amp;",
               "&lt;/script&gt;&lt;b&gt;&amp;amp;");
  check_writes("xml cdata end", fb_xml_write_text, "]]>", "]]&gt;");
  check_writes("xml text quotes", fb_xml_write_text, "\"'", "\"'");
  check_writes("xml text breaks", fb_xml_write_text, "a\tb\nc\rd", "a\tb\nc&#13;d");
  check_writes("xml attr quotes", fb_xml_write_attr, "a\"b'c", "a&quot;b&apos;c");
  check_writes("xml attr breaks", fb_xml_write_attr, "a\tb\nc\rd", "a&#9;b&#10;c&#13;d");
  check_writes("xml controls", fb_xml_write_attr, "\x01\x1f\x7f", FFFD FFFD "\x7f");
  check_writes("xml nonchars", fb_xml_write_text, "\xEF\xBF\xBE\xEF\xBF\xBF", FFFD FFFD);
  check_writes("xml utf-8", fb_xml_write_text, "\xC3\xA9\xE6\x97\xA5" SMILE,
               "\xC3\xA9\xE6\x97\xA5" SMILE);
  /* RFC 3629's ill-formed sequences: one U+FFFD per byte. */
  check_writes("overlong 2", fb_xml_write_text, "\xC0\xAF", FFFD FFFD);
  check_writes("overlong 3", fb_xml_write_text, "\xE0\x80\xAF", FFFD FFFD FFFD);
  check_writes("surrogate", fb_xml_write_text, "\xED\xA0\x80", FFFD FFFD FFFD);
  check_writes("above U+10FFFF", fb_xml_write_text, "\xF4\x90\x80\x80", FFFD FFFD FFFD FFFD);
  check_writes("truncated", fb_xml_write_text, "\xE6\x97", FFFD FFFD);
  check_writes("lone continuation", fb_xml_write_text, "a\x80z", "a" FFFD "z");
  check_writes("xml NULL", fb_xml_write_text, NULL, "");
}

/* ---- Read back by other programs. */

/* Hostile strings, all well-formed UTF-8, so that a reader gives each back. */
static const char *const hostile[] = {
    "a\"b\\c",
    "l1\nl2\r\nx\ry",
    "tab\there",
    "</script><b>&amp;",
    "\"]; x -> y; [\"",
    "a|b,c",
    "=cmd()",
    "'quoted'",
    ("\xC3\xA9 \xE6\x97\xA5 " SMILE),
    "\x01\x02\x1f\x7f control",
    "\\",
    "",
};
enum { NHOSTILE = sizeof hostile / sizeof hostile[0] };

static int have(const char *program)
{
  char cmd[128];
  snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", program);
  return system(cmd) == 0;
}

/* Runs cmd (a shell command); CHECKs that it exits 0. */
static void check_command(const char *what, const char *cmd)
{
  ++check_count;
  int rc = system(cmd);
  if (rc != 0) {
    ++check_failures;
    fprintf(stderr, "%s: `%s` failed (%d)\n", what, cmd, rc);
  }
}

typedef void write_doc_fn(FILE *fp);

/* dir/name written by fn; 0 (CHECKed) if it cannot be. */
static int write_document(const char *dir, const char *name, write_doc_fn *fn)
{
  char path[512];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  FILE *fp = fopen(path, "wb");
  CHECK(fp != NULL);
  if (!fp)
    return 0;
  fn(fp);
  return fclose(fp) == 0;
}

/* The strings as they are, NUL-separated, for the readers to compare with. */
static void write_raw(FILE *fp)
{
  for (size_t i = 0; i < NHOSTILE; ++i)
    fwrite(hostile[i], 1, strlen(hostile[i]) + 1, fp);
}

/* A Python script run over dir: it reads raw.bin into want (a list of str) and then
 * body. */
static void check_python(const char *what, const char *dir, const char *body)
{
  char cmd[4096];
  snprintf(cmd, sizeof cmd,
           "cd '%s' && python3 -c '\n"
           "import csv, json, re, xml.dom.minidom\n"
           "want = open(\"raw.bin\", \"rb\").read().decode(\"utf-8\").split(\"\\0\")[:-1]\n"
           "%s'",
           dir, body);
  check_command(what, cmd);
}

static void write_json(FILE *fp)
{
  fputs("{\"strings\": [", fp);
  for (size_t i = 0; i < NHOSTILE; ++i) {
    fputs(i ? ", " : "", fp);
    fb_json_write_string(fp, hostile[i]);
  }
  fputs("], \"numbers\": [", fp);
  const double numbers[] = {1.5, NAN, INFINITY, -INFINITY, -0.0, 1e-300};
  for (size_t i = 0; i < sizeof numbers / sizeof numbers[0]; ++i) {
    fputs(i ? ", " : "", fp);
    fb_json_write_number(fp, numbers[i]);
  }
  fputs("]}\n", fp);
}

static void check_json_reads_back(const char *dir)
{
  if (!write_document(dir, "strings.json", write_json))
    return;
  check_python("json reads back", dir,
               "d = json.load(open(\"strings.json\", encoding=\"utf-8\"))\n"
               "assert d[\"strings\"] == want, d[\"strings\"]\n"
               "assert d[\"numbers\"] == [1.5, None, None, None, -0.0, 1e-300], d\n");
}

static void write_csv(FILE *fp)
{
  /* Two rows: the strings as they are, then as text fields (guarded). */
  for (unsigned flags = 0; flags <= FB_CSV_TEXT; flags += FB_CSV_TEXT) {
    for (size_t i = 0; i < NHOSTILE; ++i) {
      fputs(i ? "," : "", fp);
      fb_csv_write_field(fp, hostile[i], flags);
    }
    fputs("\r\n", fp);
  }
}

static void check_csv_reads_back(const char *dir)
{
  if (!write_document(dir, "strings.csv", write_csv))
    return;
  check_python(
      "csv reads back", dir,
      "rows = list(csv.reader(open(\"strings.csv\", newline=\"\", encoding=\"utf-8\")))\n"
      "assert len(rows) == 2, rows\n"
      "assert rows[0] == want, rows[0]\n"
      "guard = [\"\\x27\" + w if w[:1] in (\"=\", \"+\", \"-\", \"@\", \"\\t\", \"\\r\") "
      "else w for w in want]\n"
      "assert rows[1] == guard, rows[1]\n");
}

static void write_xml(FILE *fp)
{
  fputs("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<strings>\n", fp);
  for (size_t i = 0; i < NHOSTILE; ++i) {
    fputs("  <s a=\"", fp);
    fb_xml_write_attr(fp, hostile[i]);
    fputs("\" b='", fp);
    fb_xml_write_attr(fp, hostile[i]);
    fputs("'>", fp);
    fb_xml_write_text(fp, hostile[i]);
    fputs("</s>\n", fp);
  }
  fputs("</strings>\n", fp);
}

static void check_xml_reads_back(const char *dir)
{
  if (!write_document(dir, "strings.xml", write_xml))
    return;
  /* The controls XML cannot hold come back as U+FFFD. */
  check_python(
      "xml reads back", dir,
      "doc = xml.dom.minidom.parse(\"strings.xml\")\n"
      "want = [re.sub(\"[\\x00-\\x08\\x0b\\x0c\\x0e-\\x1f]\", \"\\ufffd\", w) for w in "
      "want]\n"
      "s = doc.getElementsByTagName(\"s\")\n"
      "assert [e.getAttribute(\"a\") for e in s] == want\n"
      "assert [e.getAttribute(\"b\") for e in s] == want\n"
      "text = [\"\".join(n.data for n in e.childNodes) for e in s]\n"
      "assert text == want, text\n");
}

/* Every string as a node's ID and as its label: one node each. */
static void write_dot(FILE *fp)
{
  fputs("digraph \"", fp);
  fb_dot_write_text(fp, "g\"] ; h -> i; [\"");
  fputs("\" {\n", fp);
  for (size_t i = 0; i < NHOSTILE; ++i) {
    fprintf(fp, "  \"%zu ", i);
    fb_dot_write_text(fp, hostile[i]);
    fputs("\" [label=\"", fp);
    fb_dot_write_text(fp, hostile[i]);
    fputs("\"];\n", fp);
  }
  fputs("}\n", fp);
}

static void check_dot_reads_back(const char *dir)
{
  if (!write_document(dir, "strings.dot", write_dot))
    return;
  char cmd[1024];
  snprintf(cmd, sizeof cmd,
           "cd '%s' && dot -Tsvg strings.dot >strings.svg 2>dot.err && test ! -s dot.err && "
           "test \"$(grep -c '<g id=\"node' strings.svg)\" -eq %d",
           dir, (int)NHOSTILE);
  check_command("dot reads back with one node per string", cmd);
}

/* Every document in dir, read back by the readers the machine has. */
static void read_back(const char *dir)
{
  if (!write_document(dir, "raw.bin", write_raw))
    return;
  if (have("python3")) {
    check_json_reads_back(dir);
    check_csv_reads_back(dir);
    check_xml_reads_back(dir);
  } else {
    fprintf(stderr, "test_escape: no python3: the JSON, CSV and XML readers not run\n");
  }
  if (have("dot"))
    check_dot_reads_back(dir);
  else
    fprintf(stderr, "test_escape: no dot (Graphviz): the DOT reader not run\n");
}

static void test_readers(void)
{
  char dir[TEST_PATH_MAX];
  test_tmp_path("fb_test_escape.XXXXXX", dir, sizeof dir);
  if (!mkdtemp(dir)) {
    CHECK(!"mkdtemp");
    return;
  }
  read_back(dir);
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0)
    fprintf(stderr, "test_escape: could not remove %s\n", dir);
}

/* Messages are one line whatever text they quote: fb_err_set, _prefix,
 * _append and _set_key escape control characters, and a cut keeps the
 * message a valid NUL-terminated prefix. */
static void test_messages(void)
{
  fb_err err;
  fb_err_set(&err, FB_EINVAL, "--plot %s: no such metric",
             "a\nb\rc\td\x01"
             "e\x7f\xc2\x85"
             "f");
  CHECK(!strcmp(err.msg, "--plot a\\nb\\rc\\td\\x01e\\x7f\\u0085f: no such metric"));
  fb_err_prefix(&err, "%s: ", "dir\nname");
  CHECK(!strncmp(err.msg, "dir\\nname: --plot a\\nb", 22));
  fb_err_append(&err, "; kept in %s", "x\ny");
  CHECK(strstr(err.msg, "; kept in x\\ny") && !strchr(err.msg, '\n'));
  fb_err_set_key(&err, "%s", "k\ney");
  CHECK(!strcmp(err.key, "k\\ney"));
  /* Bytes that are not UTF-8 (a lone continuation, an 8-bit CSI, a cut
   * sequence) are \xHH: nothing but whole characters reaches a terminal. */
  fb_err_set(&err, FB_EINVAL, "%s",
             "a\xff\x9b"
             "31m\xc3");
  CHECK(!strcmp(err.msg, "a\\xff\\x9b31m\\xc3"));
  /* An excerpt is cut at a character's start. */
  char utf[70];
  memset(utf, 'a', 63);
  memcpy(utf + 63, "\xc3\xa9z", 4);
  fb_err_set_excerpt(&err, utf, strlen(utf));
  CHECK(strlen(err.excerpt) == 63 + 3 && !strcmp(err.excerpt + 63, "..."));
  /* UTF-8 beyond C1 is text, not a control character. */
  fb_err_set(&err, FB_EINVAL, "%s", "\xc3\xa9\xc2\xa0");
  CHECK(!strcmp(err.msg, "\xc3\xa9\xc2\xa0"));
  /* Cut short: whole escapes only. */
  char out[5];
  fb_err_escape(out, sizeof out, "ab\ncd");
  CHECK(!strcmp(out, "ab\\n"));
  fb_err_escape(out, sizeof out, "abcd\n");
  CHECK(!strcmp(out, "abcd"));
  /* An excerpt keeps 64 bytes of a data file's field, escaped, and says
   * when it left anything out; describe shows it, msg never. */
  fb_err_set(&err, FB_EPARSE, "f.csv:3: column 'v': not a number");
  fb_err_set_excerpt(&err, "a\nb", 3);
  CHECK(!strcmp(err.excerpt, "a\\nb"));
  char shown[FB_ERR_MSG_MAX + FB_ERR_EXCERPT_MAX + 16];
  CHECK(!strcmp(fb_err_describe(&err, shown, sizeof shown),
                "f.csv:3: column 'v': not a number (read: 'a\\nb')"));
  char field[100];
  memset(field, 'x', sizeof field - 1);
  field[sizeof field - 1] = '\0';
  fb_err_set_excerpt(&err, field, strlen(field));
  CHECK(strlen(err.excerpt) == 64 + 3 && !strcmp(err.excerpt + 64, "..."));
  memset(field, '\x01', 64);
  field[64] = '\0';
  fb_err_set_excerpt(&err, field, 64); /* 64 escapes of 4 bytes do not fit */
  CHECK(strlen(err.excerpt) < FB_ERR_EXCERPT_MAX && strstr(err.excerpt, "...") != NULL);
  fb_err_set(&err, FB_EPARSE, "new");
  CHECK(err.excerpt[0] == '\0'); /* a new error has none */
  /* A message of the longest text stays within the field. */
  char *big = malloc(3 * FB_ERR_MSG_MAX);
  if (big) {
    memset(big, '\n', 3 * FB_ERR_MSG_MAX - 1);
    big[3 * FB_ERR_MSG_MAX - 1] = '\0';
    fb_err_set(&err, FB_EINVAL, "%s", big);
    CHECK(strlen(err.msg) < FB_ERR_MSG_MAX && !strchr(err.msg, '\n'));
    free(big);
  }
}

/* fb_err.text_start: the text after where the value came from. A
 * prefix before any location builds the sentence; the location marks
 * where it starts; context after that (an override's label) leaves the
 * mark on the same text. */
static void test_text_start(void)
{
  fb_err err;
  fb_err_set(&err, FB_EINVAL, "which would need %d GB", 64);
  fb_err_prefix(&err, "64 refines the mesh, ");
  CHECK(err.text_start == 0);
  fb_err_prefix_location(&err, "s.yaml:3:4: %s: ", "hull.mesh.density");
  fb_err_prefix(&err, "--set density=64: ");
  CHECK(!strcmp(err.msg, "--set density=64: s.yaml:3:4: hull.mesh.density: 64 refines the "
                         "mesh, which would need 64 GB"));
  CHECK(!strcmp(err.msg + err.text_start, "64 refines the mesh, which would need 64 GB"));
  fb_err_set(&err, FB_EINVAL, "new");
  CHECK(err.text_start == 0);
  /* A location longer than what is left of the message: the mark stays
   * inside it. */
  char loc[FB_ERR_MSG_MAX];
  memset(loc, 'x', sizeof loc - 10);
  loc[sizeof loc - 10] = '\0';
  fb_err_prefix_location(&err, "%s: ", loc);
  CHECK(err.text_start <= strlen(err.msg));
}

int main(void)
{
  test_text_start();
  test_messages();
  test_json();
  test_json_numbers();
  test_dot();
  test_markdown();
  test_csv();
  test_xml();
  test_readers();
  return check_report("test_escape");
}
