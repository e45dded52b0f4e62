/* SPDX-License-Identifier: BSD-3-Clause */
/* fb_fmu_export (flexbond/fmu.h): a scenario packaged as an FMI 3.0 FMU.
 *
 * The vehicle is realised once, to list the variables (fmu_model); the
 * binary recomputes the same table when instantiated and compares the
 * tokens. The scenario and the files it names are copied into a private
 * folder beside the destination, below resources/model/ in the layout
 * they have under the folder they share, loaded from there to prove the
 * copy reads nothing outside it, and zipped with the binary and the
 * libraries ldd finds it needs (all but the C library's own, which every
 * x86_64 Linux has). The FMU appears at its path only when complete
 * (fb_zip_commit renames it into place). */
/* realpath(3) is XSI (POSIX.1-2008). */
/* NOLINTNEXTLINE(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp): POSIX's macro */
#define _XOPEN_SOURCE 700

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "flexbond/fmu.h"
#include "flexbond/io.h"

#include "core/tmpfile.h"
#include "core/util.h"
#include "fmu/fmu_description.h"
#include "fmu/fmu_internal.h"
#include "io/child.h"
#include "io/zip.h"

#ifndef FLEXBOND_FMU_RUNTIME_INSTALLED
#define FLEXBOND_FMU_RUNTIME_INSTALLED ""
#endif
#ifndef FLEXBOND_FMU_RUNTIME_BUILD
#define FLEXBOND_FMU_RUNTIME_BUILD ""
#endif

/* The binary's sources (sources/ of the FMU), beside the binary in
 * fmu-sources/. */
static const char *const source_files[] = {"fmu/runtime.c", "fmu/fmi3.h", "fmu/fmu_internal.h",
                                           "core/util.h", "core/textfile.h"};
enum { NSOURCES = sizeof source_files / sizeof *source_files };

static int exists(const char *path)
{
  struct stat st;
  return path && *path && stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

const char *fb_fmu_runtime_path(void)
{
  const char *env = getenv("FLEXBOND_FMU_RUNTIME");
  if (env && *env)
    return env;
  if (exists(FLEXBOND_FMU_RUNTIME_INSTALLED))
    return FLEXBOND_FMU_RUNTIME_INSTALLED;
  if (exists(FLEXBOND_FMU_RUNTIME_BUILD))
    return FLEXBOND_FMU_RUNTIME_BUILD;
  return NULL;
}

/* ---- The export's state. */

typedef struct exporter {
  const fb_fmu_export_opts *o;
  const char *scenario_path;
  char *dir;   /* the private folder */
  char **made; /* files and folders made in it, to remove */
  size_t nmade;
  fmu_config cfg;
  fb_scenario *s;
  fb_vehicle_stepper *st;
  fmu_model *model;
  char id[128];
  char *root;    /* the folder the scenario's files share */
  char **member; /* resources' members, under resources/ */
  char **copy;   /* and their copies' paths */
  size_t nmembers;
  char **lib_name, **lib_path; /* bundled libraries */
  size_t nlibs;
} exporter;

static int remember(exporter *x, char *path, fb_err *err)
{
  char **grown = path ? realloc(x->made, (x->nmade + 1) * sizeof *grown) : NULL;
  if (!grown) {
    free(path);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  x->made = grown;
  x->made[x->nmade++] = path;
  return FB_OK;
}

/* Removes what the export made in its folder, newest first, then the
 * folder. */
static void cleanup(exporter *x)
{
  for (size_t k = x->nmade; k-- > 0;) {
    if (remove(x->made[k]) != 0 && errno != ENOENT)
      (void)rmdir(x->made[k]);
    free(x->made[k]);
  }
  free(x->made);
  if (x->dir)
    (void)rmdir(x->dir);
  free(x->dir);
  for (size_t k = 0; k < x->nmembers; ++k) {
    free(x->member[k]);
    free(x->copy[k]);
  }
  free(x->member);
  free(x->copy);
  for (size_t k = 0; k < x->nlibs; ++k) {
    free(x->lib_name[k]);
    free(x->lib_path[k]);
  }
  free(x->lib_name);
  free(x->lib_path);
  free(x->root);
  fmu_model_free(&x->model);
  fb_vehicle_stepper_free(&x->st);
  fb_scenario_free(&x->s);
  fmu_config_release(&x->cfg);
}

/* ---- Options and the vehicle. */

static int is_identifier(const char *s)
{
  if (!s || !*s || strlen(s) >= 128 || (s[0] >= '0' && s[0] <= '9'))
    return 0;
  for (const char *p = s; *p; ++p)
    if (!(*p == '_' || (*p >= '0' && *p <= '9') || ((*p | 32) >= 'a' && (*p | 32) <= 'z')))
      return 0;
  return 1;
}

int fb_fmu_model_identifier_valid(const char *id)
{
  return is_identifier(id);
}

/* The identifier from the scenario's name: letters, digits and '_'. */
static void identifier_of(const char *name, char *id, size_t size)
{
  size_t k = 0;
  if (!name || !(name[0] == '_' || ((name[0] | 32) >= 'a' && (name[0] | 32) <= 'z')))
    id[k++] = 'v';
  for (const char *p = name ? name : ""; *p && k + 1 < size; ++p) {
    const int keep = (*p >= '0' && *p <= '9') || ((*p | 32) >= 'a' && (*p | 32) <= 'z');
    char ch = '_';
    if (keep)
      ch = *p;
    id[k++] = ch;
  }
  id[k] = '\0';
}

static int check_opts(exporter *x, fb_err *err)
{
  const fb_fmu_export_opts *o = x->o;
  if (o->system != FB_SYSTEM_RIGID && o->system != FB_SYSTEM_FLEXIBLE)
    return fb_err_set(err, FB_EINVAL, "no system %d", (int)o->system);
  if (o->model_identifier && !is_identifier(o->model_identifier)) {
    fb_err_set(err, FB_EINVAL,
               "model identifier '%s': must be a C identifier (letters, digits, '_') of at "
               "most 127 characters",
               o->model_identifier);
    fb_err_set_key(err, "model_identifier");
    return FB_EINVAL;
  }
  if (!(o->t_end >= 0) || o->t_end > 1e7) {
    fb_err_set(err, FB_EINVAL, "t_end %g s: must be > 0 (0: the scenario's) and at most 1e7 s",
               o->t_end);
    fb_err_set_key(err, "t_end");
    return FB_EINVAL;
  }
  return FB_OK;
}

/* An override of a key that is also a parameter gives the parameter its
 * start value (the loaded scenario has it) and is dropped: the FMU sets
 * that key from the parameter, and a key set twice is an error. */
static int drop_parameter_sets(exporter *x, fb_err *err)
{
  fmu_config *c = &x->cfg;
  size_t kept = 0;
  int rc = FB_OK;
  for (size_t i = 0; i < c->nsets; ++i) {
    char *full = NULL;
    int is_parameter = 0;
    rc = rc ? rc : fb_scenario_override_key(x->scenario_path, c->set[i].key, &full, err);
    for (size_t p = 0; !rc && p < c->nparameters; ++p)
      is_parameter |= !strcmp(full, c->parameter[p]);
    free(full);
    if (!rc && is_parameter) {
      free((char *)c->set[i].key);
      free((char *)c->set[i].value);
    } else {
      c->set[kept++] = c->set[i];
    }
  }
  c->nsets = kept;
  return rc;
}

/* The config: the choices, the parameters' full keys. */
static int make_config(exporter *x, fb_err *err)
{
  const fb_fmu_export_opts *o = x->o;
  fmu_config *c = &x->cfg;
  c->system = o->system;
  c->road_inputs = o->road_inputs;
  c->parameter = calloc(o->nparameters + 1, sizeof *c->parameter);
  c->set = calloc(o->noverrides + 1, sizeof *c->set);
  if (!c->parameter || !c->set)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; i < o->noverrides; ++i) {
    char *key = fb_strdup(o->overrides[i].key), *value = fb_strdup(o->overrides[i].value);
    if (!key || !value) {
      free(key);
      free(value);
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    }
    /* Owned by the config from here (fmu_config_release). */
    c->set[c->nsets++] = (fb_scenario_override){.key = key, .value = value, .label = NULL};
  }
  /* The keys and values are c's, freed by cleanup. */
  /* NOLINTNEXTLINE(clang-analyzer-unix.Malloc) */
  int rc = fb_scenario_load_overrides(x->scenario_path, c->set, c->nsets, &x->s, err);
  for (size_t p = 0; !rc && p < o->nparameters; ++p) {
    rc = fb_scenario_override_key(x->scenario_path, o->parameters[p], &c->parameter[p], err);
    c->nparameters += rc == FB_OK;
    for (size_t q = 0; !rc && q < p; ++q)
      if (!strcmp(c->parameter[q], c->parameter[p]))
        rc = fb_err_set(err, FB_EINVAL, "%s: a parameter twice", c->parameter[p]);
    if (!rc && !strcmp(c->parameter[p], "simulation.t_end"))
      rc = fb_err_set(err, FB_EINVAL,
                      "simulation.t_end: the FMU's horizon is no parameter (the importer's "
                      "stopTime, up to flexbond fmu --t-end, ends its run)");
    if (!rc && c->road_inputs && fmu_parameter_fixed(c->parameter[p]))
      rc = fb_err_set(err, FB_EINVAL,
                      "%s: a value of the scenario's road, which an FMU whose road is its "
                      "inputs does not use",
                      c->parameter[p]);
    if (rc)
      fb_err_set_key(err, "parameters");
  }
  if (!rc)
    rc = drop_parameter_sets(x, err);
  if (!rc)
    c->t_end = o->t_end > 0 ? o->t_end : x->s->t_end;
  return rc;
}

/* The vehicle and its table, as the FMU's binary will make them. */
static int make_model(exporter *x, fb_err *err)
{
  const size_t np = x->cfg.nparameters;
  double *start = calloc(np + 1, sizeof *start);
  const char **unit = calloc(np + 1, sizeof *unit);
  fb_scenario *s = NULL;
  int rc = start && unit ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t p = 0; !rc && p < np; ++p) {
    rc = fmu_parameter_value(x->s, x->cfg.parameter[p], &start[p], &unit[p], err);
    if (rc)
      fb_err_set_key(err, "parameters");
  }
  if (!rc)
    rc = fmu_scenario_load(x->scenario_path, &x->cfg, NULL, &s, err);
  fb_vehicle_opts vo;
  fb_vehicle_opts_default(&vo);
  vo.road_inputs = x->cfg.road_inputs;
  vo.progress = x->o->progress;
  if (!rc)
    rc = fb_vehicle_stepper_new(s, x->cfg.system, &vo, &x->st, err);
  if (!rc)
    rc = fmu_model_new(x->st, &x->cfg, start, unit, &x->model, err);
  fb_scenario_free(&s);
  free(start);
  free(unit);
  return rc;
}

/* ---- resources/: the scenario's files, copied. */

/* The longest folder prefix a and b share (a modified in place). */
static void common_folder(char *a, const char *b)
{
  size_t k = 0, cut = 0;
  while (a[k] && a[k] == b[k]) {
    if (a[k] == '/')
      cut = k;
    ++k;
  }
  if (!a[k] && (b[k] == '/' || !b[k]))
    cut = k;
  a[cut ? cut : 1] = '\0';
}

static int add_member(exporter *x, const char *real, fb_err *err)
{
  const size_t nroot = strlen(x->root);
  const char *rel = real + nroot + (x->root[nroot - 1] != '/');
  char **m = realloc(x->member, (x->nmembers + 1) * sizeof *m);
  if (m)
    x->member = m;
  char **c = m ? realloc(x->copy, (x->nmembers + 1) * sizeof *c) : NULL;
  if (c)
    x->copy = c;
  if (!m || !c)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  x->member[x->nmembers] = fb_strdup_printf("model/%s", rel);
  x->copy[x->nmembers] = fb_strdup(real);
  x->nmembers++;
  return x->member[x->nmembers - 1] && x->copy[x->nmembers - 1]
             ? FB_OK
             : fb_err_set(err, FB_ENOMEM, "out of memory");
}

/* The scenario and its inputs by their real paths, below their shared
 * folder. */
static int collect_files(exporter *x, fb_err *err)
{
  char real[PATH_MAX];
  if (!realpath(x->scenario_path, real))
    return fb_err_set(err, FB_EIO, "%s: %s", x->scenario_path, strerror(errno));
  if (!(x->root = fb_strdup(real)))
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  char *slash = strrchr(x->root, '/');
  slash[slash == x->root] = '\0';
  for (size_t i = 0; i < x->s->ninputs; ++i) {
    char r[PATH_MAX];
    if (!realpath(x->s->inputs[i], r))
      return fb_err_set(err, FB_EIO, "%s: %s", x->s->inputs[i], strerror(errno));
    common_folder(x->root, r);
  }
  int rc = add_member(x, real, err);
  for (size_t i = 0; !rc && i < x->s->ninputs; ++i) {
    char r[PATH_MAX];
    rc = realpath(x->s->inputs[i], r)
             ? add_member(x, r, err)
             : fb_err_set(err, FB_EIO, "%s: %s", x->s->inputs[i], strerror(errno));
  }
  return rc;
}

/* The FMU's path: not a folder, not one of the files it packages (the
 * scenario, its data, the binary). */
static int check_destination(const exporter *x, const char *fmu_path, fb_err *err)
{
  struct stat st;
  if (stat(fmu_path, &st) == 0 && S_ISDIR(st.st_mode))
    return fb_err_set(err, FB_EIO, "%s: a folder, not a file to write the FMU to", fmu_path);
  char real[PATH_MAX];
  if (!realpath(fmu_path, real))
    return FB_OK; /* not there yet: no file it could be */
  for (size_t k = 0; k < x->nmembers; ++k)
    if (!strcmp(real, x->copy[k]))
      return fb_err_set(err, FB_EINVAL, "%s: the FMU would overwrite %s, which it packages",
                        fmu_path, x->copy[k]);
  return FB_OK;
}

/* Makes every folder of path below x->dir (path itself excluded). */
static int make_folders(exporter *x, const char *path, fb_err *err)
{
  char *p = fb_strdup(path);
  int rc = p ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (char *s = p ? p + strlen(x->dir) + 1 : NULL; !rc && s && (s = strchr(s, '/')); ++s) {
    *s = '\0';
    if (mkdir(p, 0700) == 0)
      rc = remember(x, fb_strdup(p), err);
    else if (errno != EEXIST)
      rc = fb_err_set(err, FB_EIO, "%s: %s", p, strerror(errno));
    *s = '/';
  }
  free(p);
  return rc;
}

static int copy_file(const char *from, const char *to, fb_err *err)
{
  FILE *in = fopen(from, "rb");
  if (!in)
    return fb_err_set(err, FB_EIO, "%s: %s", from, strerror(errno));
  FILE *out = fopen(to, "wbx");
  int rc = out ? FB_OK : fb_err_set(err, FB_EIO, "%s: %s", to, strerror(errno));
  char buf[1 << 16];
  size_t n;
  while (!rc && (n = fread(buf, 1, sizeof buf, in)) > 0)
    if (fwrite(buf, 1, n, out) != n)
      rc = fb_err_set(err, FB_EIO, "%s: %s", to, strerror(errno));
  if (!rc && ferror(in))
    rc = fb_err_set(err, FB_EIO, "%s: read error", from);
  fclose(in);
  if (out && fclose(out) != 0 && !rc)
    rc = fb_err_set(err, FB_EIO, "%s: %s", to, strerror(errno));
  return rc;
}

/* resources/ in the private folder: the copies and the config. */
static int stage_resources(exporter *x, fb_err *err)
{
  int rc = FB_OK;
  for (size_t k = 0; !rc && k < x->nmembers; ++k) {
    char *to = fb_strdup_printf("%s/resources/%s", x->dir, x->member[k]);
    rc = to ? make_folders(x, to, err) : fb_err_set(err, FB_ENOMEM, "out of memory");
    if (!rc)
      rc = copy_file(x->copy[k], to, err);
    if (!rc)
      rc = remember(x, fb_strdup(to), err);
    free(x->copy[k]);
    x->copy[k] = to;
  }
  x->cfg.scenario = rc ? NULL : fb_strdup(x->member[0]);
  if (!rc && !x->cfg.scenario)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  char *path = rc ? NULL : fb_strdup_printf("%s/resources/" FMU_CONFIG_NAME, x->dir);
  FILE *fp = path ? fopen(path, "wx") : NULL;
  if (!rc && !fp)
    rc = fb_err_set(err, FB_EIO, "%s: %s", path ? path : "resources", strerror(errno));
  if (!rc)
    rc = fmu_config_write(&x->cfg, fp, err);
  if (fp && fclose(fp) != 0 && !rc)
    rc = fb_err_set(err, FB_EIO, "%s: %s", path, strerror(errno));
  if (path)
    rc = remember(x, path, err) || rc;
  return rc;
}

/* The copy loaded as the FMU will load it: it must read nothing outside
 * resources/ (a path the file writes as absolute would). */
static int check_resources(exporter *x, fb_err *err)
{
  char *res = fb_strdup_printf("%s/resources/", x->dir);
  char *scen = res ? fb_strdup_printf("%s%s", res, x->cfg.scenario) : NULL;
  fb_scenario *s = NULL;
  int rc = scen ? fmu_scenario_load(scen, &x->cfg, NULL, &s, err)
                : fb_err_set(err, FB_ENOMEM, "out of memory");
  char real_res[PATH_MAX];
  if (!rc && !realpath(res, real_res))
    rc = fb_err_set(err, FB_EIO, "%s: %s", res, strerror(errno));
  for (size_t i = 0; !rc && i < s->ninputs; ++i) {
    char r[PATH_MAX];
    if (!realpath(s->inputs[i], r) || strncmp(r, real_res, strlen(real_res)) != 0)
      rc =
          fb_err_set(err, FB_EINVAL,
                     "%s: the scenario names %s by an absolute path; the FMU's copy would read "
                     "it from outside the FMU: write the path relative to the scenario",
                     x->scenario_path, s->inputs[i]);
  }
  fb_scenario_free(&s);
  free(scen);
  free(res);
  return rc;
}

/* ---- binaries/: the binary and its libraries. */

/* The C library's own (glibc): on every x86_64 Linux, and tied to its
 * dynamic loader, so never bundled. */
static int system_library(const char *name)
{
  static const char *const glibc[] = {"libc.so.",    "libm.so.",  "libpthread.so.",
                                      "libdl.so.",   "librt.so.", "libresolv.so.",
                                      "libutil.so.", "ld-linux",  "linux-vdso"};
  for (size_t i = 0; i < sizeof glibc / sizeof *glibc; ++i)
    if (!strncmp(name, glibc[i], strlen(glibc[i])))
      return 1;
  return 0;
}

static int add_library(exporter *x, const char *name, const char *path, fb_err *err)
{
  char **n = realloc(x->lib_name, (x->nlibs + 1) * sizeof *n);
  if (n)
    x->lib_name = n;
  char **p = n ? realloc(x->lib_path, (x->nlibs + 1) * sizeof *p) : NULL;
  if (p)
    x->lib_path = p;
  if (!n || !p)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  x->lib_name[x->nlibs] = fb_strdup(name);
  x->lib_path[x->nlibs] = fb_strdup(path);
  x->nlibs++;
  return x->lib_name[x->nlibs - 1] && x->lib_path[x->nlibs - 1]
             ? FB_OK
             : fb_err_set(err, FB_ENOMEM, "out of memory");
}

/* One line of ldd's listing: "NAME => PATH (ADDRESS)", "NAME => not
 * found", or a line without "=>" (the loader, the vDSO). */
static int ldd_line(exporter *x, char *line, fb_err *err)
{
  char name[256], arrow[8], path[PATH_MAX];
  if (sscanf(line, " %255s %7s %4095s", name, arrow, path) != 3 || strcmp(arrow, "=>") != 0)
    return FB_OK;
  if (system_library(name))
    return FB_OK;
  if (!strcmp(path, "not"))
    return fb_err_set(err, FB_EIO, "the FMU's binary needs %s, which is not installed", name);
  if (strchr(name, '/'))
    return fb_err_set(err, FB_EIO, "ldd named a library '%s'", name);
  return add_library(x, name, path, err);
}

static int find_libraries(exporter *x, const char *runtime, fb_err *err)
{
  char *const argv[] = {"ldd", (char *)runtime, NULL};
  const fb_child_spec spec = {"ldd", argv, x->dir, "ldd.txt", 60.0};
  int rc = fb_child_run(&spec, "listing the FMU binary's libraries (ldd)", err);
  char *log = fb_strdup_printf("%s/ldd.txt", x->dir);
  if (log)
    rc = remember(x, fb_strdup(log), err) || rc;
  FILE *fp = !rc && log ? fopen(log, "r") : NULL;
  if (!rc && !fp)
    rc = fb_err_set(err, FB_EIO, "ldd's listing: %s", strerror(errno));
  char line[PATH_MAX + 512];
  while (!rc && fp && fgets(line, sizeof line, fp))
    rc = ldd_line(x, line, err);
  if (fp)
    fclose(fp);
  free(log);
  return rc;
}

/* ---- The archive. */

static int add_text(fb_zip *z, const char *name, const fmu_description *d,
                    int (*write)(FILE *, const fmu_description *, fb_err *), fb_err *err)
{
  char *buf = NULL;
  size_t len = 0;
  FILE *fp = open_memstream(&buf, &len);
  if (!fp)
    return fb_err_set(err, FB_ENOMEM, "out of memory for %s", name);
  int rc = write(fp, d, err);
  if (fclose(fp) != 0 && !rc)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for %s", name);
  if (!rc)
    rc = fb_zip_add(z, name, buf, len, 0, err);
  free(buf);
  return rc;
}

/* The folder of path (new). */
static char *folder_of(const char *path)
{
  char *d = fb_strdup(path);
  char *slash = d ? strrchr(d, '/') : NULL;
  if (slash)
    *slash = '\0';
  return d;
}

static int add_sources(fb_zip *z, const char *runtime, const fmu_description *d, fb_err *err)
{
  char *dir = folder_of(runtime);
  int rc = dir ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t k = 0; !rc && k < NSOURCES; ++k) {
    char *from = fb_strdup_printf("%s/fmu-sources/%s", dir, source_files[k]);
    char *name = fb_strdup_printf("sources/%s", source_files[k]);
    rc = from && name ? fb_zip_add_file(z, name, from, 0, err)
                      : fb_err_set(err, FB_ENOMEM, "out of memory");
    free(from);
    free(name);
  }
  free(dir);
  if (!rc)
    rc = add_text(z, "sources/buildDescription.xml", d, fmu_write_build_description, err);
  return rc;
}

static int write_archive(exporter *x, const char *runtime, const char *fmu_path,
                         fb_fmu_info *info, fb_err *err)
{
  const fb_scenario *s = fb_vehicle_stepper_scenario(x->st);
  const char *sources[] = {"fmu/runtime.c"};
  char *what = fb_strdup_printf("%s: a flexbond vehicle, System %d, the road %s", s->name,
                                x->cfg.system == FB_SYSTEM_FLEXIBLE ? 2 : 1,
                                x->cfg.road_inputs ? "as inputs" : "of the scenario");
  const fmu_description d = {x->model,
                             s->name,
                             x->id,
                             what ? what : "",
                             FLEXBOND_VERSION_TEXT,
                             x->cfg.t_end,
                             1.0 / s->sample_rate,
                             s->rtol,
                             sources,
                             1};
  fb_zip *z = NULL;
  int rc =
      what ? fb_zip_create(fmu_path, &z, err) : fb_err_set(err, FB_ENOMEM, "out of memory");
  if (!rc)
    rc = add_text(z, "modelDescription.xml", &d, fmu_write_model_description, err);
  char *bin = fb_strdup_printf("binaries/x86_64-linux/%s.so", x->id);
  if (!rc)
    rc = bin ? fb_zip_add_file(z, bin, runtime, 1, err)
             : fb_err_set(err, FB_ENOMEM, "out of memory");
  free(bin);
  for (size_t k = 0; !rc && k < x->nlibs; ++k) {
    char *name = fb_strdup_printf("binaries/x86_64-linux/%s", x->lib_name[k]);
    rc = name ? fb_zip_add_file(z, name, x->lib_path[k], 1, err)
              : fb_err_set(err, FB_ENOMEM, "out of memory");
    free(name);
  }
  char *cfg = fb_strdup_printf("%s/resources/" FMU_CONFIG_NAME, x->dir);
  if (!rc)
    rc = cfg ? fb_zip_add_file(z, "resources/" FMU_CONFIG_NAME, cfg, 0, err)
             : fb_err_set(err, FB_ENOMEM, "out of memory");
  free(cfg);
  for (size_t k = 0; !rc && k < x->nmembers; ++k) {
    char *name = fb_strdup_printf("resources/%s", x->member[k]);
    rc = name ? fb_zip_add_file(z, name, x->copy[k], 0, err)
              : fb_err_set(err, FB_ENOMEM, "out of memory");
    free(name);
  }
  if (!rc)
    rc = add_sources(z, runtime, &d, err);
  free(what);
  if (rc) {
    fb_zip_free(&z);
    return rc;
  }
  rc = fb_zip_commit(z, err);
  struct stat st;
  if (!rc && info && stat(fmu_path, &st) == 0)
    info->bytes = (size_t)st.st_size;
  return rc;
}

static void fill_info(const exporter *x, fb_fmu_info *info)
{
  snprintf(info->model_identifier, sizeof info->model_identifier, "%s", x->id);
  info->nstates = x->model->nstates;
  info->ninputs = x->model->ninputs;
  info->noutputs = x->model->noutputs;
  info->nparameters = x->model->nparameters;
  info->nindicators = x->model->nindicators;
  info->nlibraries = x->nlibs;
}

int fb_fmu_export(const char *scenario_path, const fb_fmu_export_opts *o, const char *fmu_path,
                  fb_fmu_info *info, fb_err *err)
{
  if (!scenario_path || !o || !fmu_path)
    return fb_err_set(err, FB_EINVAL, "fb_fmu_export: a NULL argument");
  exporter x = {.o = o, .scenario_path = scenario_path};
  const char *runtime = o->runtime ? o->runtime : fb_fmu_runtime_path();
  int rc = check_opts(&x, err);
  if (!rc && !exists(runtime))
    rc = fb_err_set(err, FB_EIO,
                    "the FMU binary %s is not there (build flexbond's flexbond_fmu target, or "
                    "set FLEXBOND_FMU_RUNTIME)",
                    runtime ? runtime : "(none found)");
  if (!rc)
    rc = make_config(&x, err);
  if (!rc && o->model_identifier)
    snprintf(x.id, sizeof x.id, "%s", o->model_identifier);
  else if (!rc)
    identifier_of(x.s->name, x.id, sizeof x.id);
  if (!rc)
    rc = fb_progress_report(&o->progress, "realising the vehicle", 0.0, err);
  if (!rc)
    rc = make_model(&x, err);
  if (!rc) {
    const int e = fb_tmpdir_create(fmu_path, "fmu", &x.dir);
    if (e)
      rc = fb_err_set(err, FB_EIO, "%s: cannot make a folder beside it: %s", fmu_path,
                      strerror(e));
  }
  if (!rc)
    rc = collect_files(&x, err);
  if (!rc)
    rc = check_destination(&x, fmu_path, err);
  if (!rc) {
    char *res = fb_strdup_printf("%s/resources", x.dir);
    if (res && mkdir(res, 0700) == 0) {
      rc = remember(&x, res, err);
    } else {
      rc = fb_err_set(err, FB_EIO, "resources/: %s", res ? strerror(errno) : "out of memory");
      free(res);
    }
  }
  if (!rc)
    rc = stage_resources(&x, err);
  if (!rc)
    rc = check_resources(&x, err);
  if (!rc)
    rc = fb_progress_report(&o->progress, "bundling the binary's libraries", 0.0, err);
  if (!rc)
    rc = find_libraries(&x, runtime, err);
  if (!rc)
    rc = fb_progress_report(&o->progress, "writing the FMU", 0.0, err);
  if (!rc)
    rc = write_archive(&x, runtime, fmu_path, info, err);
  if (!rc && info)
    fill_info(&x, info);
  cleanup(&x);
  return rc;
}
