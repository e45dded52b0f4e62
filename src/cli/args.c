/* SPDX-License-Identifier: BSD-3-Clause */
/* Option parsing, numeric option values and error reporting shared by the
 * subcommands (see cli.h). A small hand-written parser instead of
 * getopt_long, which is a GNU extension. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
/* fb_parse_decimal: numbers on the command line are read as in the data
 * files (CSV, mtx, decks, the model and scenario YAML). */
#include "../core/textfile.h"

static void say(const char *end, const char *fmt, va_list ap)
{
  fb_err e;
  fb_err_vset(&e, FB_OK, fmt, ap);
  fprintf(stderr, "%s%s", e.msg, end);
}

void cli_say(const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  say("\n", fmt, ap);
  va_end(ap);
}

void cli_say_more(const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  say("", fmt, ap);
  va_end(ap);
}

/* The parentheses keep the analyzer-only macro of cli.h from expanding here. */
int(cli_usage_error)(const char *cmd, const char *fmt, ...)
{
  /* Through fb_err_vset, as every message: one line, its quoted text's
   * control characters escaped. */
  fb_err e;
  va_list ap;
  va_start(ap, fmt);
  fb_err_vset(&e, FB_EINVAL, fmt, ap);
  va_end(ap);
  fprintf(stderr, "flexbond %s: %s\nTry 'flexbond %s --help'.\n", cmd, e.msg, cmd);
  return CLI_EXIT_USAGE;
}

/* The option whose long form is the first name_len characters of arg, or
 * whose short form is arg; NULL if none. */
static cli_option *find_option(cli_option *opts, size_t nopts, const char *arg, size_t name_len)
{
  for (size_t i = 0; i < nopts; ++i) {
    if (strlen(opts[i].name) == name_len && strncmp(opts[i].name, arg, name_len) == 0)
      return &opts[i];
    if (opts[i].alias && strcmp(opts[i].alias, arg) == 0)
      return &opts[i];
  }
  return NULL;
}

/* Handles the option at argv[*i], advancing *i past a separate value. */
static int parse_option(int argc, char **argv, int *i, cli_option *opts, size_t nopts)
{
  const char *arg = argv[*i];
  const char *eq = strncmp(arg, "--", 2) == 0 ? strchr(arg, '=') : NULL;
  size_t name_len = eq ? (size_t)(eq - arg) : strlen(arg);
  cli_option *opt = find_option(opts, nopts, arg, name_len);
  if (!opt)
    return cli_usage_error(argv[0], "unknown option '%.*s'", (int)name_len, arg);
  if (!opt->takes_value) {
    if (eq)
      return cli_usage_error(argv[0], "option '%s' takes no value", opt->name);
    opt->value = "";
    return CLI_EXIT_OK;
  }
  if (eq) {
    opt->value = eq + 1;
    return CLI_EXIT_OK;
  }
  if (*i + 1 >= argc)
    return cli_usage_error(argv[0], "option '%s' needs a value", arg);
  *i += 1;
  opt->value = argv[*i];
  return CLI_EXIT_OK;
}

int cli_parse(int argc, char **argv, cli_option *opts, size_t nopts, const char **positional,
              size_t max_positional, size_t *npositional)
{
  *npositional = 0;
  int options_done = 0;
  for (int i = 1; i < argc; ++i) {
    const char *arg = argv[i];
    if (!options_done && strcmp(arg, "--") == 0) {
      options_done = 1;
      continue;
    }
    if (!options_done && arg[0] == '-' && arg[1] != '\0') {
      int rc = parse_option(argc, argv, &i, opts, nopts);
      if (rc != CLI_EXIT_OK)
        return rc;
      continue;
    }
    if (*npositional == max_positional)
      return cli_usage_error(argv[0], "unexpected argument '%s'", arg);
    positional[(*npositional)++] = arg;
  }
  return CLI_EXIT_OK;
}

int cli_positive_number(const char *cmd, const char *name, const char *text, double *out)
{
  double v = 0;
  /* A plain decimal: strtod alone would take hexadecimal ("0x10",
   * "0x1p-10"), "inf" and "nan". Values beyond the range of double
   * (overflow) are refused by fb_parse_decimal, underflow to 0 by v > 0. */
  if (fb_parse_decimal(text, &v, NULL) != FB_OK || !(v > 0.0))
    return cli_usage_error(
        cmd, "option '%s' needs a finite number > 0 in decimal digits (got '%s')", name, text);
  *out = v;
  return CLI_EXIT_OK;
}

int cli_exit_code(int status)
{
  switch (status) {
  case FB_OK: return CLI_EXIT_OK;
  case FB_ENOMEM: return CLI_EXIT_NOMEM;
  case FB_ECAUSAL: return CLI_EXIT_CAUSAL;
  case FB_ESOLVER: return CLI_EXIT_SOLVER;
  case FB_EIO: return CLI_EXIT_IO;
  case FB_EINTR: return CLI_EXIT_INTERRUPTED;
  /* FB_EPARSE, FB_EINVAL, FB_EMODEL: the input is at fault. */
  default: return CLI_EXIT_INPUT;
  }
}

int cli_report(int status, const fb_err *err)
{
  if (status == FB_OK)
    return CLI_EXIT_OK;
  char shown[FB_ERR_MSG_MAX + FB_ERR_EXCERPT_MAX + 16];
  const char *msg =
      err && err->msg[0] ? fb_err_describe(err, shown, sizeof shown) : fb_status_name(status);
  fprintf(stderr, "flexbond: %s\n", msg);
  return cli_exit_code(status);
}

int cli_scenario_warnings(const fb_scenario *s, int strict, fb_err *err)
{
  const size_t n = fb_scenario_nwarnings(s);
  if (strict && n) {
    *err = *fb_scenario_warning(s, 0);
    err->code = FB_EINVAL;
    return fb_err_append(err, " (--strict refuses implausible values: %zu in this scenario)",
                         n);
  }
  for (size_t i = 0; i < n; ++i)
    cli_say("flexbond: warning: %s", fb_scenario_warning(s, i)->msg);
  return FB_OK;
}

int cli_scenario_load(const char *path, int strict, fb_scenario **s, fb_err *err)
{
  int rc = fb_scenario_load(path, s, err);
  if (rc == FB_OK)
    rc = cli_scenario_warnings(*s, strict, err);
  if (rc != FB_OK)
    fb_scenario_free(s);
  return rc;
}

void cli_report_warnings(const fb_model *m)
{
  for (size_t i = 0; i < fb_model_nwarnings(m); ++i)
    fprintf(stderr, "flexbond: warning: %s\n", fb_model_warning(m, i)->msg);
}

int cli_report_scenario(const fb_scenario *s, int status, fb_err *err)
{
  if (status != FB_OK && s && err)
    fb_scenario_locate(s, err);
  return cli_report(status, err);
}

int cli_flush_stdout(fb_err *err)
{
  errno = 0;
  if (fflush(stdout) == 0 && !ferror(stdout))
    return FB_OK;
  return fb_err_set(err, FB_EIO, "standard output: write failed: %s",
                    strerror(errno ? errno : EIO));
}

int cli_print_help(const char *text)
{
  fb_err err;
  fb_err_clear(&err);
  fputs(text, stdout);
  return cli_report(cli_flush_stdout(&err), &err);
}

int cli_parse_file_command(int argc, char **argv, cli_option *opts, size_t nopts,
                           const char *usage, const char *what, const char **path,
                           int *exit_code)
{
  size_t npos = 0;
  *path = NULL;
  *exit_code = cli_parse(argc, argv, opts, nopts, path, 1, &npos);
  if (*exit_code != CLI_EXIT_OK)
    return 0;
  for (size_t i = 0; i < nopts; ++i)
    if (strcmp(opts[i].name, "--help") == 0 && opts[i].value) {
      *exit_code = cli_print_help(usage);
      return 0;
    }
  if (npos != 1) {
    *exit_code = cli_usage_error(argv[0], "missing %s file", what);
    return 0;
  }
  return 1;
}

int cli_parse_model_command(int argc, char **argv, cli_option *opts, size_t nopts,
                            const char *usage, const char **model_path, int *exit_code)
{
  return cli_parse_file_command(argc, argv, opts, nopts, usage, "MODEL", model_path, exit_code);
}

int cli_choice(const char *cmd, const char *name, const char *text, const char *const *choices,
               size_t nchoices, int *out)
{
  for (size_t i = 0; i < nchoices; ++i)
    if (strcmp(text, choices[i]) == 0) {
      *out = (int)i;
      return CLI_EXIT_OK;
    }
  char list[256] = "";
  size_t used = 0;
  for (size_t i = 0; i < nchoices && used < sizeof list; ++i) {
    int n = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", choices[i]);
    used += n > 0 ? (size_t)n : 0;
  }
  return cli_usage_error(cmd, "option '%s' must be one of %s (got '%s')", name, list, text);
}

char *cli_join_path(const char *dir, const char *name)
{
  size_t dlen = strlen(dir);
  int has_slash = dlen > 0 && dir[dlen - 1] == '/';
  size_t n = dlen + !has_slash + strlen(name) + 1;
  char *path = malloc(n);
  if (path)
    snprintf(path, n, "%s%s%s", dir, has_slash ? "" : "/", name);
  return path;
}
