/* SPDX-License-Identifier: BSD-3-Clause */
/* fb_json_check (src/core/json_check.c) against RFC 8259's grammar: the
 * texts it must take, the ones it must refuse (each breaks one rule),
 * and the files flexbond writes. */
#include <stdio.h>
#include <string.h>

#include "flexbond/escape.h"

#include "check.h"

static void expect(const char *text, int valid, size_t at)
{
  size_t offset = 99;
  const int rc = fb_json_check(text, strlen(text), &offset);
  const int ok = valid ? rc == 0 && offset == 0 : rc == -1 && offset == at;
  CHECK(ok);
  if (!ok)
    fprintf(stderr, "  '%s': got %d at %zu, wanted %s at %zu\n", text, rc, offset,
            valid ? "valid" : "invalid", at);
}

int main(void)
{
  /* Valid: every kind of value, whitespace, escapes, UTF-8. */
  expect("{}", 1, 0);
  expect(" [ ] \n", 1, 0);
  expect("0", 1, 0);
  expect("-0.5e+10", 1, 0);
  expect("1E-3", 1, 0);
  expect("\"a\\\"b\\\\c\\/\\b\\f\\n\\r\\t\\u00e9\"", 1, 0);
  expect("\"\xc2\xb5rad \xe2\x82\xac \xf0\x9f\x98\x80\"", 1, 0); /* micro, euro, an emoji */
  expect("{\"a\": [1, 2.5, true, false, null, {\"b\": {}}], \"c\": \"d\"}", 1, 0);
  /* Invalid, at the byte where the rule breaks. */
  expect("", 0, 0);
  expect("{\"LF\"{\"value\": 1}}", 0, 5); /* a member without its colon */
  expect("{\"a\": 1,}", 0, 8);            /* a trailing comma */
  expect("[1 2]", 0, 3);
  expect("01", 0, 1); /* a leading zero */
  expect("1.", 0, 2);
  expect(".5", 0, 0);
  expect("1e", 0, 2);
  expect("NaN", 0, 0);
  expect("nul", 0, 3);
  expect("{a: 1}", 0, 1); /* an unquoted key */
  expect("'a'", 0, 0);
  expect("\"tab\there\"", 0, 5); /* a raw control character */
  expect("\"\\x\"", 0, 3);
  expect("\"\\u12G4\"", 0, 5);
  expect("\"open", 0, 5);
  expect("\"\xc0\xaf\"", 0, 2);         /* an overlong '/' */
  expect("\"\xed\xa0\x80\"", 0, 2);     /* a UTF-16 surrogate */
  expect("\"\xf4\x90\x80\x80\"", 0, 2); /* beyond U+10FFFF */
  expect("\"\xe2\x82\"", 0, 3);         /* a sequence cut short */
  expect("{} {}", 0, 3);                /* two texts */
  /* A NUL inside is no JSON text. */
  CHECK(fb_json_check("[1]\0", 4, NULL) == -1);
  CHECK(fb_json_check(NULL, 0, NULL) == -1);
  /* Nesting: 256 levels are taken, 257 refused. */
  char deep[600];
  for (int depth = 256; depth <= 257; ++depth) {
    size_t n = 0;
    for (int k = 0; k < depth; ++k)
      deep[n++] = '[';
    for (int k = 0; k < depth; ++k)
      deep[n++] = ']';
    deep[n] = '\0';
    CHECK(fb_json_check(deep, n, NULL) == (depth <= 256 ? 0 : -1));
  }
  return check_report("test_json_check");
}
