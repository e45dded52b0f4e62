/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond: escaping of strings for the documents it writes, one writer
 * per output language (docs/outputs.md).
 *
 * Names, units, titles and paths come from the user (a model, a scenario,
 * the command line, or any string a program passes through the API). Every
 * one that goes into a generated document goes through the writer of that
 * document's language, so that no string can end a quoted field, add a
 * statement, a record, a link or markup, or make the document unreadable
 * to a conforming reader. Each writer writes to a stream; write errors
 * stick to it (ferror) as for any other fprintf.
 *
 * Shared rules: text is taken as UTF-8. A well-formed sequence (RFC 3629,
 * section 4: no overlong form, no surrogate, at most U+10FFFF) is kept
 * byte for byte; a malformed byte is written as U+FFFD, the replacement
 * character (JSON, XML and Graphviz read UTF-8 and refuse or mangle
 * anything else). A NULL string writes as the empty one (JSON: null). */
#ifndef FLEXBOND_ESCAPE_H
#define FLEXBOND_ESCAPE_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- JSON (RFC 8259). */

/* s as one JSON string, quotes included (section 7): '"' and '\' are
 * escaped, the control characters U+0000..U+001F (which a string may not
 * hold raw) become \b \f \n \r \t or \u00XX; everything else, '/' and
 * U+007F included, is written as it is. NULL writes null. */
void fb_json_write_string(FILE *fp, const char *s);
/* v as a JSON number ("%.10g": ten significant digits), or null when it
 * is not finite: section 6 has no NaN or infinity, and a bare nan or inf
 * makes the whole text invalid. */
void fb_json_write_number(FILE *fp, double v);
/* 0 if text[0..len) is one JSON text (RFC 8259: a value with whitespace
 * around it, strict numbers and strings, valid UTF-8, nested at most 256
 * deep), -1 otherwise with *offset (if not NULL) at about the first byte
 * that is not (src/core/json_check.c). A file written as JSON is checked
 * with it before it is committed. */
int fb_json_check(const char *text, size_t len, size_t *offset);

/* ---- Graphviz DOT ("The DOT Language", graphviz.org: the ID rules). */

/* s as the inside of a double-quoted DOT ID, without the quotes. '"' is
 * written \" (the grammar's only escape in a quoted string) and '\' is
 * written \\, so that a label shows it (a lone backslash would start one
 * of the label escapes \n \l \N ...). A line feed becomes \n, the label
 * escape of a line break; a carriage return before a line feed is dropped
 * and a lone one becomes \n too. Other control characters (U+0000..U+001F,
 * U+007F) become U+FFFD. No raw line break is written: a statement is
 * never split. */
void fb_dot_write_text(FILE *fp, const char *s);
/* The same for the first n bytes of s (fewer if it ends first). */
void fb_dot_write_text_n(FILE *fp, const char *s, size_t n);

/* ---- Markdown (CommonMark 0.31, with GitHub's tables). */

/* s as inline text, for a paragraph, a heading, a table cell or a link's
 * text: the ASCII punctuation that opens inline syntax, \ ` * _ [ ] # | ~,
 * is backslash-escaped (CommonMark 2.4; \| for the pipe of a GFM table
 * cell; with [ and ] escaped, no ( ) or ! can make a link or an image),
 * and & < > are written as the entities &amp; &lt; &gt; (2.5), so the
 * input makes no raw HTML (6.6), autolink (6.5) or entity reference of
 * its own. Control characters (line breaks included: a text never starts
 * a new block or table row) become spaces. */
void fb_md_write_text(FILE *fp, const char *s);

/* ---- CSV (RFC 4180). */

enum fb_csv_flags {
  /* Enclose the field in double quotes even when RFC 4180 does not need
   * it (for a file that always quoted a column). */
  FB_CSV_QUOTE_ALWAYS = 1,
  /* The field is text, not a number: if it starts with = + - @, a tab or
   * a carriage return, a spreadsheet would read it as a formula (CSV
   * injection, OWASP): it is written with a ' in front, which those
   * programs take as "text" and other readers keep as part of the field.
   * Leave the flag off for a field that must read back exactly (a
   * number, a value compared on reading). */
  FB_CSV_TEXT = 2
};

/* s as one CSV field: enclosed in double quotes, each inner '"' doubled,
 * when it holds a comma, a double quote, CR or LF (section 2, rules 6-7);
 * as it is otherwise. flags: fb_csv_flags. */
void fb_csv_write_field(FILE *fp, const char *s, unsigned flags);
/* One field holding the concatenation of parts[0..nparts) (NULL parts are
 * empty), quoted and guarded as a whole, e.g. {name, " [", unit, "]"}. */
void fb_csv_write_field_parts(FILE *fp, const char *const *parts, size_t nparts,
                              unsigned flags);

/* ---- XML 1.0 (fifth edition). */

/* s as character data: & < > as &amp; &lt; &gt; (section 2.4; '>' so that
 * "]]>" never appears), a carriage return as &#13; (section 2.11 would
 * turn it into a line feed). The control characters XML 1.0 forbids even
 * as references (section 2.2: U+0000..U+001F but tab, line feed and
 * carriage return) and U+FFFE, U+FFFF become U+FFFD. */
void fb_xml_write_text(FILE *fp, const char *s);
/* s as an attribute value in double or single quotes, without them: as
 * fb_xml_write_text, and " ' as &quot; &apos;, tab, line feed and
 * carriage return as &#9; &#10; &#13; (section 3.3.3 would normalise them
 * to spaces). */
void fb_xml_write_attr(FILE *fp, const char *s);

/* ---- YAML 1.2 (model files, fb_model_write). */

/* s as one double-quoted YAML scalar, quotes included (YAML 1.2, section
 * 7.3.1): '"' and '\\' are escaped, everything else is written as it is
 * (valid UTF-8 kept, a malformed byte as U+FFFD), so the scalar reads
 * back as s. Text with a control character (C0, DEL, C1: one that a
 * model's loader refuses in one-line text) is refused instead: nothing
 * is written and -1 returned; 0 otherwise. NULL writes "". */
int fb_yaml_write_string(FILE *fp, const char *s);
/* 1 if s may be written as a plain YAML scalar that every YAML reader
 * reads back as the same string: a letter or '_' followed by letters,
 * digits, '_' and '.', and not one of the words YAML 1.1 readers take
 * for a boolean or null (true, no, on, null, y, ...). */
int fb_yaml_is_plain(const char *s);

#ifdef __cplusplus
}
#endif

#endif
