/* SPDX-License-Identifier: BSD-3-Clause */
/* An FMU's build choices in resources/ (fmu_config): written by the
 * exporter, read by the FMU when it is instantiated. One line per
 * choice, a word and its value:
 *   flexbond-fmu 1
 *   scenario model/apc6x6.yaml
 *   system rigid | flexible
 *   road scenario | inputs
 *   t_end 15
 *   parameter road.speed_kmh
 *   set KEY=VALUE */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "core/util.h"
#include "fmu/fmu_internal.h"

void fmu_config_release(fmu_config *c)
{
  free(c->scenario);
  for (size_t i = 0; i < c->nparameters; ++i)
    free(c->parameter[i]);
  free(c->parameter);
  for (size_t i = 0; i < c->nsets; ++i) {
    free((char *)c->set[i].key);
    free((char *)c->set[i].value);
  }
  free(c->set);
  *c = (fmu_config){0};
}

static int one_line(const char *what, const char *s, fb_err *err)
{
  if (!s || strpbrk(s, "\r\n"))
    return fb_err_set(err, FB_EINVAL, "%s: must be one line of text", what);
  return FB_OK;
}

int fmu_config_write(const fmu_config *c, FILE *fp, fb_err *err)
{
  int rc = one_line("the scenario's path", c->scenario, err);
  for (size_t i = 0; !rc && i < c->nparameters; ++i)
    rc = one_line("a parameter", c->parameter[i], err);
  for (size_t i = 0; !rc && i < c->nsets; ++i)
    rc = one_line("an override", c->set[i].key, err) ||
         one_line("an override", c->set[i].value, err);
  if (rc)
    return FB_EINVAL;
  fprintf(fp, "flexbond-fmu 1\nscenario %s\nsystem %s\nroad %s\nt_end %.17g\n", c->scenario,
          c->system == FB_SYSTEM_FLEXIBLE ? "flexible" : "rigid",
          c->road_inputs ? "inputs" : "scenario", c->t_end);
  for (size_t i = 0; i < c->nparameters; ++i)
    fprintf(fp, "parameter %s\n", c->parameter[i]);
  for (size_t i = 0; i < c->nsets; ++i)
    fprintf(fp, "set %s=%s\n", c->set[i].key, c->set[i].value);
  return ferror(fp) ? fb_err_set(err, FB_EIO, "writing the FMU's choices failed") : FB_OK;
}

/* Appends a copy of text to the list *items (*n of them). */
static int append(char ***items, size_t *n, const char *text)
{
  char **grown = realloc(*items, (*n + 1) * sizeof *grown);
  if (!grown)
    return FB_ENOMEM;
  *items = grown;
  if (!(grown[*n] = fb_strdup(text)))
    return FB_ENOMEM;
  ++*n;
  return FB_OK;
}

static int add_set(fmu_config *c, const char *text)
{
  const char *eq = strchr(text, '=');
  if (!eq)
    return FB_EPARSE;
  fb_scenario_override *grown = realloc(c->set, (c->nsets + 1) * sizeof *grown);
  if (!grown)
    return FB_ENOMEM;
  c->set = grown;
  char *key = fb_strdup(text), *value = fb_strdup(eq + 1);
  if (key)
    key[eq - text] = '\0';
  if (!key || !value) {
    free(key);
    free(value);
    return FB_ENOMEM;
  }
  grown[c->nsets++] = (fb_scenario_override){.key = key, .value = value, .label = NULL};
  return FB_OK;
}

/* One line "word value" into c. */
static int read_line(fmu_config *c, const char *word, const char *value, int *seen_magic)
{
  if (!strcmp(word, "flexbond-fmu"))
    return (*seen_magic = !strcmp(value, "1")) ? FB_OK : FB_EPARSE;
  if (!*seen_magic)
    return FB_EPARSE;
  if (!strcmp(word, "scenario"))
    return (c->scenario = fb_strdup(value)) ? FB_OK : FB_ENOMEM;
  if (!strcmp(word, "system")) {
    c->system = !strcmp(value, "flexible") ? FB_SYSTEM_FLEXIBLE : FB_SYSTEM_RIGID;
    return !strcmp(value, "flexible") || !strcmp(value, "rigid") ? FB_OK : FB_EPARSE;
  }
  if (!strcmp(word, "road")) {
    c->road_inputs = !strcmp(value, "inputs");
    return c->road_inputs || !strcmp(value, "scenario") ? FB_OK : FB_EPARSE;
  }
  if (!strcmp(word, "t_end")) {
    char *end = NULL;
    c->t_end = strtod(value, &end);
    return *value && !*end && c->t_end > 0 ? FB_OK : FB_EPARSE;
  }
  if (!strcmp(word, "parameter"))
    return append(&c->parameter, &c->nparameters, value);
  if (!strcmp(word, "set"))
    return add_set(c, value);
  return FB_EPARSE;
}

int fmu_config_read(const char *path, fmu_config *c, fb_err *err)
{
  *c = (fmu_config){0};
  FILE *fp = fopen(path, "r");
  if (!fp)
    return fb_err_set(err, FB_EIO, "%s: cannot open: %s", path, strerror(errno));
  char line[4096];
  int rc = FB_OK, magic = 0;
  long lineno = 0;
  while (!rc && fgets(line, sizeof line, fp)) {
    ++lineno;
    const size_t len = strcspn(line, "\r\n");
    if (!line[len] && !feof(fp))
      rc = fb_err_set(err, FB_EPARSE, "%s:%ld: a line longer than %zu bytes", path, lineno,
                      sizeof line - 2);
    line[len] = '\0';
    char *space = strchr(line, ' ');
    if (!rc && !space)
      rc = fb_err_set(err, FB_EPARSE, "%s:%ld: expected 'WORD VALUE'", path, lineno);
    if (!rc) {
      *space = '\0';
      rc = read_line(c, line, space + 1, &magic);
      if (rc)
        fb_err_set(err, rc, "%s:%ld: %s", path, lineno,
                   rc == FB_ENOMEM ? "out of memory" : "not a line of an FMU's choices");
    }
  }
  if (!rc && ferror(fp))
    rc = fb_err_set(err, FB_EIO, "%s: read error", path);
  fclose(fp);
  if (!rc && (!magic || !c->scenario))
    rc = fb_err_set(err, FB_EPARSE, "%s: not an FMU's choices (no scenario)", path);
  if (rc)
    fmu_config_release(c);
  return rc;
}
