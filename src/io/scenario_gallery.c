/* SPDX-License-Identifier: BSD-3-Clause */
/* The scenario format's table with the galleries' entries
 * (scenario_internal.h): the format's own keys; for each road type a
 * section road.<type> whose keys are the type's declared parameters
 * (flexbond/param.h); for each hull source that declares parameters a
 * section hull.mesh.<source>; for each tire model a choice of
 * wheel.tire_contact and a section wheel.<model> of its parameters, at
 * the top level and in every corner's items; for each damper law with no
 * key of its own a section damper.<law> in every corner's items. Made
 * here once per set of galleries. */
#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/damper.h"
#include "flexbond/hull_source.h"
#include "flexbond/vehicle.h"

#include "core/util.h"
#include "io/scenario_internal.h"

struct sc_schema {
  sch_table table;            /* first: a schema is its table */
  sch_key *key;               /* owned, table.n of them */
  sch_table corner_table;     /* the corners' items, with the tire models */
  sch_key *corner_key;        /* owned, corner_table.n of them */
  const char **tire_name;     /* the tire models' names, NULL-terminated, owned array */
  const fb_tire_model **tire; /* the models, NULL-terminated, owned array */
  /* The envelope models' names and the models, NULL-terminated, owned
   * arrays. */
  const char **envelope_name;
  const fb_envelope_model **envelope;
  /* The damper laws with sections of their own, NULL-terminated, owned
   * array. */
  const fb_damper_law **damper;
  char **path; /* the generated keys' paths, owned */
  size_t npaths;
  atomic_size_t refs;
};

/* ---- The generated keys' hooks. */

/* The road type's section is there when it is the description's road. */
static int sc_road_present(const sch_key *k, const void *base)
{
  return ((const fb_scenario *)base)->road_type == k->data;
}

/* A new block of the section's type, before its keys fill it. */
static int sc_road_begin(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  const int rc = fb_scenario_set_road(base, k->data, NULL, r->c->err);
  return rc ? ml_blame(r->c, node) : FB_OK;
}

/* The type's prepare (a file read, alternatives resolved), its errors at
 * the key of their parameter, else at the section. */
static int sc_road_done(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  (void)k;
  if (!node)
    return FB_OK;
  const int rc = fb_scenario_prepare_road(base, r->c->err);
  if (!rc)
    return FB_OK;
  const fb_err *e = r->c->err;
  struct fy_node *at =
      e && e->part.kind == FB_PART_ROAD ? ml_get(node, e->part.field, NULL) : NULL;
  return ml_blame(r->c, at ? at : node);
}

/* A hull source's section is there when it is the description's
 * source. */
static int sc_hull_present(const sch_key *k, const void *base)
{
  const fb_scenario *s = base;
  return s->has_fe_hull && fb_scenario_hull_source(s) == k->data;
}

/* The description's source is the section's, its block new before the
 * section's keys fill it. */
static int sc_hull_begin(sch_reader *r, const sch_key *k, struct fy_node *node, void *base)
{
  const int rc = fb_scenario_set_hull_source(base, k->data, r->c->err);
  return rc ? ml_blame(r->c, node) : FB_OK;
}

/* An optional parameter left out (NaN, or no choice) is no value. */
static int sc_param_present(const sch_key *k, const void *base)
{
  const fb_param *p = k->data;
  if (k->store == SCH_STORE_NONE) /* read to be inherited, kept by no struct */
    return 0;
  if (p->need != FB_PARAM_OPTIONAL)
    return 1;
  const char *at = (const char *)base + k->offset;
  if (p->store == FB_PARAM_DOUBLE)
    return !isnan(*(const double *)(const void *)at);
  return p->store != FB_PARAM_INT || *(const int *)(const void *)at >= 0;
}

static const sch_ops sc_road_ops = {
    .begin = sc_road_begin, .done = sc_road_done, .present = sc_road_present};
static const sch_ops sc_param_ops = {.present = sc_param_present};
static const sch_ops sc_hull_ops = {.begin = sc_hull_begin, .present = sc_hull_present};

/* ---- Making the table. */

static const sch_type sc_param_types[] = {[FB_PARAM_REAL] = SCH_NUMBER,
                                          [FB_PARAM_WHOLE] = SCH_WHOLE,
                                          [FB_PARAM_CHOICE] = SCH_CHOICE,
                                          [FB_PARAM_FILE] = SCH_FILE,
                                          [FB_PARAM_REALS] = SCH_NUMBERS};
static const sch_store sc_param_stores[] = {[FB_PARAM_DOUBLE] = SCH_STORE_DOUBLE,
                                            [FB_PARAM_INT] = SCH_STORE_INT,
                                            [FB_PARAM_SIZE] = SCH_STORE_SIZE,
                                            [FB_PARAM_U64] = SCH_STORE_U64,
                                            [FB_PARAM_STRING] = SCH_STORE_STRING};
static const sch_need sc_param_needs[] = {[FB_PARAM_REQUIRED] = SCH_REQUIRED,
                                          [FB_PARAM_OPTIONAL] = SCH_OPTIONAL,
                                          [FB_PARAM_DEFAULT] = SCH_DEFAULT};

/* A copy of "<section>.<entry>[.<param>]", kept by the schema. */
static const char *sc_key_path(sc_schema *sc, const char *section, const char *entry,
                               const fb_param *p)
{
  char *path = fb_strdup_printf("%s.%s%s%s", section, entry, p ? "." : "", p ? p->name : "");
  if (path)
    sc->path[sc->npaths++] = path;
  return path;
}

/* The key of parameter p at path, its block at offset block in the
 * struct its table fills. */
static sch_key sc_param_key(const char *path, const fb_param *p, size_t block)
{
  const sch_key k = {
      .path = path,
      .type = sc_param_types[p->kind],
      .unit = p->unit,
      .bounds = p->range,
      .lo = p->lo,
      .hi = p->hi,
      .need = sc_param_needs[p->need],
      .def = p->def,
      .def_list = p->def_list,
      .choices = p->choices,
      .min_items = p->kind == FB_PARAM_REALS ? p->count : 0,
      .max_items = p->kind == FB_PARAM_REALS ? p->count : 0,
      .doc = p->doc,
      .why = p->why,
      .plausible_lo = p->plausible_lo,
      .plausible_hi = p->plausible_hi,
      .plausible_why = p->plausible_why,
      .store = sc_param_stores[p->store],
      .offset = block + p->offset,
      .ops = &sc_param_ops,
      .scale = p->scale,
      .data = p,
  };
  return k;
}

/* A gallery entry's keys at key[*n] on: the section key (its path
 * <prefix>.<name> filled in here), then one key per parameter, stored in
 * the block at offset block of the struct its table fills. */
static int sc_entry_keys(sc_schema *sc, sch_key section, const char *prefix, const char *name,
                         const fb_param *param, size_t nparams, size_t block, sch_key *key,
                         size_t *n, fb_err *err)
{
  if (!(section.path = sc_key_path(sc, prefix, name, NULL)))
    return fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
  key[(*n)++] = section;
  for (size_t i = 0; i < nparams; ++i) {
    const char *path = sc_key_path(sc, prefix, name, &param[i]);
    if (!path)
      return fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
    key[(*n)++] = sc_param_key(path, &param[i], block);
  }
  return FB_OK;
}

/* The keys of type t from sc->key[*n] on. */
static int sc_type_keys(sc_schema *sc, const fb_road_type *t, size_t *n, fb_err *err)
{
  const sch_key section = {.type = SCH_SECTION,
                           .need = SCH_REQUIRED,
                           .one_of = "road",
                           .doc = t->doc,
                           .ops = &sc_road_ops,
                           .data = t};
  return sc_entry_keys(sc, section, "road", t->name, t->param, t->nparams,
                       offsetof(fb_scenario, road), sc->key, n, err);
}

/* The keys of hull source src from sc->key[*n] on: a section
 * hull.mesh.<source>, one of the format's "mesh", and its parameters; a
 * source that declares none (a built-in one) has the format's own. */
static int sc_hull_keys(sc_schema *sc, const fb_hull_source *src, size_t *n, fb_err *err)
{
  if (!src->nparams)
    return FB_OK;
  const sch_key section = {.type = SCH_SECTION,
                           .need = SCH_REQUIRED,
                           .one_of = "mesh",
                           .doc = src->doc,
                           .ops = &sc_hull_ops,
                           .data = src};
  return sc_entry_keys(sc, section, "hull.mesh", src->name, src->param, src->nparams,
                       offsetof(fb_scenario, hull_params), sc->key, n, err);
}

/* ---- Tire models: a choice, and a section of parameters per model. */

/* A corner's section wheel.<model> is there when it is the corner's
 * model. */
static int sc_tire_present(const sch_key *k, const void *base)
{
  return fb_corner_tire_model(base) == k->data;
}

static const sch_ops sc_tire_ops = {.present = sc_tire_present};

/* The section wheel.<name> of one model (data: the model) and its
 * parameters' keys at key[*n] on, at sc->key or sc->corner_key (corner:
 * stored in the corner's block at offset block, present by ops; else
 * only read, to be inherited). */
static int sc_wheel_section_keys(sc_schema *sc, const char *name, const fb_param *param,
                                 size_t nparams, const void *data, int corner, size_t block,
                                 const sch_ops *ops, sch_key *key, size_t *n, fb_err *err)
{
  const char *path = sc_key_path(sc, "wheel", name, NULL);
  if (!path)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
  key[(*n)++] = (sch_key){.path = path,
                          .type = SCH_SECTION,
                          .need = SCH_OPTIONAL,
                          .doc = corner ? "this corner's parameters of the model, where they "
                                          "differ from the top-level `wheel`'s"
                                        : "the parameters of that model, for every corner "
                                          "whose tire it is unless the corner gives its own",
                          .ops = corner ? ops : NULL,
                          .data = data};
  for (size_t i = 0; i < nparams; ++i) {
    if (!(path = sc_key_path(sc, "wheel", name, &param[i])))
      return fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
    sch_key k = sc_param_key(path, &param[i], block);
    /* Left out in a corner: the top level's (sc_corner_params); the top
     * level's is only read, to be inherited. */
    if (corner)
      k.need = SCH_OPTIONAL;
    else
      k.store = SCH_STORE_NONE;
    key[(*n)++] = k;
  }
  return FB_OK;
}

/* The sections of every model of g after the choice. */
static int sc_tire_keys(sc_schema *sc, const fb_tire_gallery *g, int corner, sch_key *key,
                        size_t *n, fb_err *err)
{
  int rc = FB_OK;
  for (size_t j = 0; !rc && j < fb_tire_gallery_count(g); ++j) {
    const fb_tire_model *m = fb_tire_gallery_at(g, j);
    if (m->nparams) /* else nothing to give */
      rc = sc_wheel_section_keys(sc, m->name, m->param, m->nparams, m, corner,
                                 offsetof(fb_corner_params, tire), &sc_tire_ops, key, n, err);
  }
  return rc;
}

/* A corner's section wheel.<model> of an envelope model is there when
 * it is the corner's model. */
static int sc_envelope_present(const sch_key *k, const void *base)
{
  return fb_corner_envelope_model(base) == k->data;
}

static const sch_ops sc_envelope_ops = {.present = sc_envelope_present};

/* The sections of every envelope model of g after the choice. */
static int sc_envelope_keys(sc_schema *sc, const fb_envelope_gallery *g, int corner,
                            sch_key *key, size_t *n, fb_err *err)
{
  int rc = FB_OK;
  for (size_t j = 0; !rc && j < fb_envelope_gallery_count(g); ++j) {
    const fb_envelope_model *m = fb_envelope_gallery_at(g, j);
    if (m->nparams)
      rc = sc_wheel_section_keys(sc, m->name, m->param, m->nparams, m, corner,
                                 offsetof(fb_corner_params, envelope), &sc_envelope_ops, key, n,
                                 err);
  }
  return rc;
}

/* Stores v (in the written unit) as p's value in block. */
static void sc_param_store(const fb_param *p, double v, void *block)
{
  void *at = (char *)block + p->offset;
  switch (p->store) {
  case FB_PARAM_DOUBLE: *(double *)at = v * (p->scale != 0.0 ? p->scale : 1.0); break;
  case FB_PARAM_INT: *(int *)at = (int)v; break;
  case FB_PARAM_SIZE: *(size_t *)at = (size_t)v; break;
  case FB_PARAM_U64: *(uint64_t *)at = (uint64_t)v; break;
  case FB_PARAM_STRING: break;
  }
}

/* An entry's name: its first member (core/registry.h). */
static const char *sc_entry_name(const void *entry)
{
  return *(const char *const *)entry;
}

/* A section of another of models (NULL-terminated) than m written in
 * the corner's wheel: the choice's, whose models are what ("tire"). */
static int sc_wheel_foreign(sch_reader *r, const void *const *models, const void *m,
                            struct fy_node *node, const char *what, const char *choice)
{
  struct fy_node *wheel = node ? ml_get(node, "wheel", NULL) : NULL;
  for (size_t j = 0; wheel && models[j]; ++j) {
    const char *x = sc_entry_name(models[j]);
    struct fy_node *key = NULL;
    if (models[j] != m && (ml_get(wheel, x, &key), key))
      return ml_fail_key(r->c, wheel, key, FB_EPARSE,
                         "the parameters of a `%s` %s, but this corner's %s is `%s` (%s)", x,
                         what, what, sc_entry_name(m), choice);
  }
  return FB_OK;
}

/* The corner's entry of the choice at path choice (list: the corners'
 * items), given or inherited: the choice key's models (data) at the
 * index read; NULL when none. */
static const void *sc_corner_choice(sch_reader *r, const sch_key *list, const char *item_path,
                                    const char *choice, const void *const **models)
{
  const sch_key *k = sch_key_of(list->items, choice);
  *models = k ? k->data : NULL;
  char path[SCH_PATH_MAX + 64];
  snprintf(path, sizeof path, "%s.%s", item_path, choice);
  const sch_origin *o = sch_origin_find(r, path);
  size_t n = 0;
  while (*models && (*models)[n])
    ++n;
  const size_t i = o ? (size_t)o->number : 0;
  if (i < n)
    return (*models)[i];
  fb_err_set(r->c->err, FB_EINVAL, "%s: no entry chosen", path);
  return NULL;
}

/* The tire table of corner c (at node, its key paths under item_path)
 * when its model m is the one the items' SC_TIRE_TABLE key reads (its
 * data): the corner's own, else the top level's, recorded as the
 * corner's; required then. */
static int sc_corner_tire_table(sch_reader *r, const sch_key *list, struct fy_node *node,
                                const char *item_path, fb_corner_params *c,
                                const fb_tire_model *m)
{
  const sch_key *k = sch_key_of(list->items, SC_TIRE_TABLE);
  struct fy_node *wheel = node ? ml_get(node, "wheel", NULL) : NULL;
  struct fy_node *key = NULL;
  struct fy_node *table = wheel ? ml_get(wheel, "tire_table", &key) : NULL;
  if (k && k->data != m && table)
    return ml_fail_key(r->c, wheel, key, FB_EPARSE,
                       "the table of a `%s` tire, but this corner's tire is `%s` (%s)",
                       ((const fb_tire_model *)k->data)->name, m->name, SC_TIRE_CHOICE);
  if (!k || k->data != m)
    return FB_OK;
  char path[SCH_PATH_MAX + 64];
  snprintf(path, sizeof path, "%s.%s", item_path, SC_TIRE_TABLE);
  int rc = FB_OK;
  if (!table && node) {
    struct fy_node *top = ml_get(fy_document_root(fy_node_document(node)), "wheel", NULL);
    table = top ? ml_get(top, "tire_table", NULL) : NULL;
    rc = table ? sch_origin_inherit(r, path, SC_TIRE_TABLE) : FB_OK;
  }
  if (!rc && !table)
    return ml_fail(r->c, node, FB_EPARSE,
                   "missing required key '%s': a `%s` tire's force-deflection table, here or "
                   "at the top-level wheel",
                   SC_TIRE_TABLE, m->name);
  fb_table_law *law = NULL;
  if (!rc)
    rc = ml_table_law(r->c, r->c->globals, table, &law);
  const double *x = NULL, *f = NULL;
  const size_t n = rc ? 0 : fb_table_law_knots(law, &x, &f);
  if (!rc && n > FB_TIRE_MAX_POINTS)
    rc = ml_fail(r->c, table, FB_EINVAL, "a tire table has at most %d points (got %zu)",
                 (int)FB_TIRE_MAX_POINTS, n);
  if (!rc) {
    fb_tire_table_params *p = (fb_tire_table_params *)(void *)c->tire.bytes;
    p->npoints = n;
    memcpy(p->deflection, x, n * sizeof *x);
    memcpy(p->force, f, n * sizeof *f);
  }
  fb_table_law_free(&law);
  return rc;
}

/* The parameters of a corner's model name into its block: each value
 * as read (its origin's number), the corner's own (under item_path),
 * else the top level's, recorded as the corner's. */
static int sc_corner_params(sch_reader *r, const char *item_path, const char *name,
                            const fb_param *param, size_t nparams, void *block)
{
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < nparams; ++i) {
    const fb_param *p = &param[i];
    char top[SCH_PATH_MAX], path[SCH_PATH_MAX + 64];
    snprintf(top, sizeof top, "wheel.%s.%s", name, p->name);
    snprintf(path, sizeof path, "%s.%s", item_path, top);
    const sch_origin *o = sch_origin_find(r, path);
    const int own = o != NULL;
    if (!own)
      o = sch_origin_find(r, top);
    if (o)
      sc_param_store(p, o->number, block);
    if (o && !own)
      rc = sch_origin_inherit(r, path, top);
  }
  return rc;
}

int sc_corner_tire(sch_reader *r, const sch_key *list, struct fy_node *node,
                   const char *item_path, fb_corner_params *c)
{
  const void *const *models = NULL;
  const fb_tire_model *m = sc_corner_choice(r, list, item_path, SC_TIRE_CHOICE, &models);
  if (!m)
    return FB_EINVAL;
  int rc = fb_corner_set_tire(c, m, NULL, r->c->err);
  if (!rc)
    rc = sc_wheel_foreign(r, models, m, node, "tire", SC_TIRE_CHOICE);
  if (!rc)
    rc = sc_corner_params(r, item_path, m->name, m->param, m->nparams, c->tire.bytes);
  return rc ? rc : sc_corner_tire_table(r, list, node, item_path, c, m);
}

static const void *sc_tire_of(const fb_corner_params *c)
{
  return fb_corner_tire_model(c);
}

static const void *sc_envelope_of(const fb_corner_params *c)
{
  return fb_corner_envelope_model(c);
}

/* The top level's section wheel.<model> of each of models (NULL-
 * terminated; what they are: "tire") that no corner has (of: a corner's
 * model) refused at its key: its values would reach none. */
static int sc_sections_used(sch_reader *r, struct fy_node *root, const fb_scenario *s,
                            const void *const *models,
                            const void *(*of)(const fb_corner_params *), const char *what,
                            const char *choice)
{
  struct fy_node *wheel = ml_get(root, "wheel", NULL);
  for (size_t j = 0; models && wheel && models[j]; ++j) {
    struct fy_node *key = NULL;
    if (!ml_get(wheel, sc_entry_name(models[j]), &key) || !key)
      continue;
    size_t users = 0;
    for (size_t c = 0; c < s->ncorners; ++c)
      users += of(&s->corner[c]) == models[j];
    if (!users)
      return ml_fail_key(r->c, wheel, key, FB_EPARSE,
                         "no corner's %s is %s (%s chooses the %ss): its values would "
                         "reach none",
                         what, sc_entry_name(models[j]), choice, what);
  }
  return FB_OK;
}

int sc_tire_sections_used(sch_reader *r, const sch_table *t, struct fy_node *root,
                          const fb_scenario *s)
{
  const sch_key *choice = sch_key_of(t, SC_TIRE_CHOICE);
  int rc = sc_sections_used(r, root, s, choice ? choice->data : NULL, sc_tire_of, "tire",
                            SC_TIRE_CHOICE);
  if (rc)
    return rc;
  /* The top level's tire table, for the model its key names. */
  struct fy_node *wheel = ml_get(root, "wheel", NULL);
  const sch_key *table = sch_key_of(t, SC_TIRE_TABLE);
  struct fy_node *key = NULL;
  if (!table || !wheel || !ml_get(wheel, "tire_table", &key) || !key)
    return FB_OK;
  for (size_t c = 0; c < s->ncorners; ++c)
    if (fb_corner_tire_model(&s->corner[c]) == table->data)
      return FB_OK;
  return ml_fail_key(
      r->c, wheel, key, FB_EPARSE,
      "no corner's tire is %s (%s chooses the tires): the table would reach none",
      ((const fb_tire_model *)table->data)->name, SC_TIRE_CHOICE);
}

int sc_envelope_sections_used(sch_reader *r, const sch_table *t, struct fy_node *root,
                              const fb_scenario *s)
{
  const sch_key *choice = sch_key_of(t, SC_ENVELOPE_CHOICE);
  return sc_sections_used(r, root, s, choice ? choice->data : NULL, sc_envelope_of, "envelope",
                          SC_ENVELOPE_CHOICE);
}

int sc_corner_envelope(sch_reader *r, const sch_key *list, struct fy_node *node,
                       const char *item_path, fb_corner_params *c)
{
  const void *const *models = NULL;
  const fb_envelope_model *m =
      sc_corner_choice(r, list, item_path, SC_ENVELOPE_CHOICE, &models);
  if (!m)
    return FB_EINVAL;
  int rc = fb_corner_set_envelope(c, m, NULL, r->c->err);
  if (!rc)
    rc = sc_wheel_foreign(r, models, m, node, "envelope", SC_ENVELOPE_CHOICE);
  if (!rc)
    rc = sc_corner_params(r, item_path, m->name, m->param, m->nparams, c->envelope.bytes);
  /* The tire's radius: the corner's own (stored as read), else the top
   * level's, recorded as the corner's. */
  char path[SCH_PATH_MAX + 64];
  snprintf(path, sizeof path, "%s.%s", item_path, SC_TIRE_RADIUS);
  const sch_origin *o = NULL;
  if (!rc && !sch_origin_find(r, path) && (o = sch_origin_find(r, SC_TIRE_RADIUS))) {
    c->tire_radius = o->number;
    rc = sch_origin_inherit(r, path, SC_TIRE_RADIUS);
  }
  return rc;
}

/* ---- Damper laws: a section of parameters per law, in every corner. */

/* A corner's section damper.<law> is there when it is the corner's law. */
static int sc_damper_law_present(const sch_key *k, const void *base)
{
  return fb_corner_damper_law(base) == k->data;
}

/* The section damper is there when the corner's law is one of its
 * sections' (k->data, NULL-terminated), not given by a key of its own. */
static int sc_damper_section_present(const sch_key *k, const void *base)
{
  const fb_damper_law *l = fb_corner_damper_law(base);
  for (const fb_damper_law *const *d = k->data; *d; ++d)
    if (*d == l)
      return 1;
  return 0;
}

/* A new block of the section's law, before its keys fill it. */
static int sc_damper_law_begin(sch_reader *r, const sch_key *k, struct fy_node *node,
                               void *base)
{
  const int rc = fb_corner_set_damper(base, k->data, NULL, r->c->err);
  return rc ? ml_blame(r->c, node) : FB_OK;
}

static const sch_ops sc_damper_law_ops = {.begin = sc_damper_law_begin,
                                          .present = sc_damper_law_present};
/* A damper section written names one law of its sections: with none to
 * name (the gallery's laws all have keys of their own), it is refused,
 * since it would leave the corner without a shock absorber. */
static int sc_damper_section_done(sch_reader *r, const sch_key *k, struct fy_node *node,
                                  void *base)
{
  (void)base;
  const fb_damper_law *const *laws = k->data;
  if (!node || laws[0])
    return FB_OK;
  return ml_fail(r->c, node, FB_EPARSE,
                 "no damper law is written as a section here: the built-in ones are "
                 "`damper_c` (linear) and `damper_table`; a program's own law, in the gallery "
                 "it loads with, is `damper: {<law>: {...}}`");
}

static const sch_ops sc_damper_section_ops = {.present = sc_damper_section_present,
                                              .done = sc_damper_section_done};

/* 1 if a key of the corners' own table gives law l (damper_c the linear
 * law, damper_table the table): such a law needs no section. */
static int sc_damper_keyed(const fb_damper_law *l)
{
  for (size_t i = 0; i < sc_corner_format.n; ++i)
    if (sc_corner_format.key[i].data == l)
      return 1;
  return 0;
}

/* Lists in sc->damper the laws of g with a section: those with no key
 * of their own (the section names the law, so a law without parameters
 * has one too, written {}). */
static int sc_damper_laws(sc_schema *sc, const fb_damper_gallery *g, fb_err *err)
{
  sc->damper = calloc(fb_damper_gallery_count(g) + 1, sizeof(const fb_damper_law *));
  if (!sc->damper)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
  size_t n = 0;
  for (size_t j = 0; j < fb_damper_gallery_count(g); ++j) {
    const fb_damper_law *l = fb_damper_gallery_at(g, j);
    if (!sc_damper_keyed(l))
      sc->damper[n++] = l;
  }
  return FB_OK;
}

/* The sections of sc->damper's laws at key[*n] on. */
static int sc_damper_keys(sc_schema *sc, sch_key *key, size_t *n, fb_err *err)
{
  int rc = FB_OK;
  for (size_t j = 0; !rc && sc->damper[j]; ++j) {
    const fb_damper_law *l = sc->damper[j];
    const sch_key section = {.type = SCH_SECTION,
                             .need = SCH_REQUIRED,
                             .one_of = "damper_law",
                             .doc = l->doc,
                             .ops = &sc_damper_law_ops,
                             .data = l};
    rc = sc_entry_keys(sc, section, SC_DAMPER_SECTION, l->name, l->param, l->nparams,
                       offsetof(fb_corner_params, damper), key, n, err);
  }
  return rc;
}

/* The galleries a table is made with. */
typedef struct sc_galleries {
  const fb_road_gallery *roads;
  const fb_tire_gallery *tires;
  const fb_hull_source_gallery *hulls;
  const fb_damper_gallery *dampers;
  const fb_envelope_gallery *envelopes;
} sc_galleries;

/* The generated keys' count: a section and its parameters per entry. */
static size_t sc_gallery_keys(const sc_galleries *gal)
{
  const fb_road_gallery *roads = gal->roads;
  const fb_tire_gallery *tires = gal->tires;
  const fb_hull_source_gallery *hulls = gal->hulls;
  size_t n = 0;
  for (size_t i = 0; i < fb_damper_gallery_count(gal->dampers); ++i)
    n += 1 + fb_damper_gallery_at(gal->dampers, i)->nparams;
  for (size_t i = 0; i < fb_hull_source_gallery_count(hulls); ++i)
    n += 1 + fb_hull_source_gallery_at(hulls, i)->nparams;
  for (size_t i = 0; i < fb_road_gallery_count(roads); ++i)
    n += 1 + fb_road_gallery_at(roads, i)->nparams;
  for (size_t i = 0; i < fb_tire_gallery_count(tires); ++i)
    n += 1 + fb_tire_gallery_at(tires, i)->nparams;
  for (size_t i = 0; i < fb_envelope_gallery_count(gal->envelopes); ++i)
    n += 1 + fb_envelope_gallery_at(gal->envelopes, i)->nparams;
  return n;
}

/* One entry of a gallery: its name and doc. */
typedef void (*sc_entry_fn)(const void *g, size_t j, const char **name, const char **doc);

/* A top-level choice's documentation: lead (owned, may be NULL), then
 * each of the gallery's n entries' name and doc, kept by the schema;
 * NULL when out of memory. */
static const char *sc_choice_doc(sc_schema *sc, char *lead, const void *g, size_t n,
                                 sc_entry_fn entry)
{
  char *doc = lead;
  for (size_t j = 0; doc && j < n; ++j) {
    const char *name = NULL, *text = NULL;
    entry(g, j, &name, &text);
    char *more = fb_strdup_printf("%s%s `%s`: %s", doc, j ? ";" : ":", name, text);
    free(doc);
    doc = more;
  }
  if (doc)
    sc->path[sc->npaths++] = doc;
  return doc;
}

static void sc_tire_entry(const void *g, size_t j, const char **name, const char **doc)
{
  const fb_tire_model *m = fb_tire_gallery_at(g, j);
  *name = m->name;
  *doc = m->doc;
}

static void sc_envelope_entry(const void *g, size_t j, const char **name, const char **doc)
{
  const fb_envelope_model *m = fb_envelope_gallery_at(g, j);
  *name = m->name;
  *doc = m->doc;
}

/* The top-level tire model choice's documentation. */
static const char *sc_tire_doc(sc_schema *sc, const fb_tire_gallery *g)
{
  return sc_choice_doc(sc, fb_strdup("how every tire meets the road, a tire model"), g,
                       fb_tire_gallery_count(g), sc_tire_entry);
}

/* The top-level envelope choice's documentation. */
static const char *sc_envelope_doc(sc_schema *sc, const fb_envelope_gallery *g)
{
  return sc_choice_doc(sc,
                       fb_strdup("how every tire envelops the road, an envelope model (docs/"
                                 "tire-envelope.md)"),
                       g, fb_envelope_gallery_count(g), sc_envelope_entry);
}

/* Copies table own into key (room for own->n and the galleries' keys):
 * after SC_TIRE_CHOICE the tire models' choices and sections, after
 * SC_ROAD_TYPES_AFTER the road types' and after SC_HULL_SOURCES_AFTER
 * the hull sources' (roads and hulls NULL: none); *n keys. */
static int sc_copy_with(sc_schema *sc, const sch_table *own, const sc_galleries *gal,
                        int corner, sch_key *key, size_t *n, fb_err *err)
{
  const fb_road_gallery *roads = gal->roads;
  const fb_tire_gallery *tires = gal->tires;
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < own->n; ++i) {
    sch_key *k = &key[(*n)++];
    *k = own->key[i];
    if (k->items == &sc_corner_format) /* the corners' lists read the corners with them */
      k->items = &sc->corner_table;
    if (!strcmp(k->path, SC_TIRE_CHOICE)) {
      k->choices = sc->tire_name;
      k->data = sc->tire; /* the models, for sc_corner_tire */
      if (!corner && !(k->doc = sc_tire_doc(sc, tires)))
        rc = fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
      if (!rc)
        rc = sc_tire_keys(sc, tires, corner, key, n, err);
    }
    if (!rc && !strcmp(k->path, SC_ENVELOPE_CHOICE)) {
      k->choices = sc->envelope_name;
      k->data = sc->envelope; /* the models, for sc_corner_envelope */
      if (!corner && !(k->doc = sc_envelope_doc(sc, gal->envelopes)))
        rc = fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
      if (!rc)
        rc = sc_envelope_keys(sc, gal->envelopes, corner, key, n, err);
    }
    if (!rc && corner && !strcmp(k->path, SC_DAMPER_SECTION)) {
      k->ops = &sc_damper_section_ops;
      k->data = sc->damper;
      rc = sc_damper_keys(sc, key, n, err);
    }
    for (size_t j = 0; !rc && roads && !strcmp(k->path, SC_ROAD_TYPES_AFTER) &&
                       j < fb_road_gallery_count(roads);
         ++j)
      rc = sc_type_keys(sc, fb_road_gallery_at(roads, j), n, err);
    for (size_t j = 0; !rc && gal->hulls && !strcmp(k->path, SC_HULL_SOURCES_AFTER) &&
                       j < fb_hull_source_gallery_count(gal->hulls);
         ++j)
      rc = sc_hull_keys(sc, fb_hull_source_gallery_at(gal->hulls, j), n, err);
  }
  return rc;
}

static int sc_schema_fill(sc_schema *sc, const sc_galleries *gal, fb_err *err)
{
  const sch_table *own = &sc_format;
  const fb_tire_gallery *tires = gal->tires;
  const size_t extra = sc_gallery_keys(gal), ntires = fb_tire_gallery_count(tires);
  sc->key = calloc(own->n + extra, sizeof *sc->key);
  sc->corner_key = calloc(sc_corner_format.n + extra, sizeof *sc->corner_key);
  sc->path = calloc(2 * extra + 3, sizeof *sc->path); /* and the choices' docs */
  sc->tire_name = calloc(ntires + 1, sizeof *sc->tire_name);
  sc->tire = calloc(ntires + 1, sizeof(const fb_tire_model *));
  const size_t nenv = fb_envelope_gallery_count(gal->envelopes);
  sc->envelope_name = calloc(nenv + 1, sizeof *sc->envelope_name);
  sc->envelope = calloc(nenv + 1, sizeof(const fb_envelope_model *));
  if (!sc->key || !sc->corner_key || !sc->path || !sc->tire_name || !sc->tire ||
      !sc->envelope_name || !sc->envelope)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
  for (size_t i = 0; i < ntires; ++i) {
    sc->tire[i] = fb_tire_gallery_at(tires, i);
    sc->tire_name[i] = sc->tire[i]->name;
  }
  for (size_t i = 0; i < nenv; ++i) {
    sc->envelope[i] = fb_envelope_gallery_at(gal->envelopes, i);
    sc->envelope_name[i] = sc->envelope[i]->name;
  }
  size_t nc = 0, n = 0;
  const sc_galleries corner_gal = {.tires = tires, .envelopes = gal->envelopes};
  int rc = sc_damper_laws(sc, gal->dampers, err);
  if (!rc)
    rc = sc_copy_with(sc, &sc_corner_format, &corner_gal, 1, sc->corner_key, &nc, err);
  sc->corner_table = (sch_table){sc->corner_key, nc, sc_corner_format.done};
  if (!rc)
    rc = sc_copy_with(sc, own, gal, 0, sc->key, &n, err);
  sc->table = (sch_table){sc->key, n, own->done};
  return rc;
}

/* o's galleries, the built-in ones where o names none (made into
 * *own, which the caller frees with sc_galleries_release). */
typedef struct sc_builtin {
  fb_road_gallery *roads;
  fb_tire_gallery *tires;
  fb_hull_source_gallery *hulls;
  fb_damper_gallery *dampers;
  fb_envelope_gallery *envelopes;
} sc_builtin;

static int sc_galleries_of(const fb_scenario_load_opts *o, sc_builtin *own, sc_galleries *gal,
                           fb_err *err)
{
  *own = (sc_builtin){0};
  *gal = (sc_galleries){o ? o->roads : NULL, o ? o->tires : NULL, o ? o->hull_sources : NULL,
                        o ? o->dampers : NULL, o ? o->envelopes : NULL};
  int rc = gal->roads ? FB_OK : fb_road_gallery_new(&own->roads, err);
  if (!rc && !gal->tires)
    rc = fb_tire_gallery_new(&own->tires, err);
  if (!rc && !gal->hulls)
    rc = fb_hull_source_gallery_new(&own->hulls, err);
  if (!rc && !gal->dampers)
    rc = fb_damper_gallery_new(&own->dampers, err);
  if (!rc && !gal->envelopes)
    rc = fb_envelope_gallery_new(&own->envelopes, err);
  gal->roads = gal->roads ? gal->roads : own->roads;
  gal->tires = gal->tires ? gal->tires : own->tires;
  gal->hulls = gal->hulls ? gal->hulls : own->hulls;
  gal->dampers = gal->dampers ? gal->dampers : own->dampers;
  gal->envelopes = gal->envelopes ? gal->envelopes : own->envelopes;
  return rc;
}

static void sc_galleries_release(sc_builtin *own)
{
  fb_road_gallery_free(&own->roads);
  fb_tire_gallery_free(&own->tires);
  fb_hull_source_gallery_free(&own->hulls);
  fb_damper_gallery_free(&own->dampers);
  fb_envelope_gallery_free(&own->envelopes);
}

int sc_schema_new(const fb_scenario_load_opts *o, sc_schema **out, fb_err *err)
{
  *out = NULL;
  sc_builtin own;
  sc_galleries gal;
  int rc = sc_galleries_of(o, &own, &gal, err);
  sc_schema *sc = rc ? NULL : calloc(1, sizeof *sc);
  if (!rc && !sc)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
  if (!rc) {
    atomic_init(&sc->refs, 1);
    rc = sc_schema_fill(sc, &gal, err);
  }
  sc_galleries_release(&own);
  if (rc)
    sc_schema_release(&sc);
  *out = sc;
  return rc;
}

sc_schema *sc_schema_share(sc_schema *sc)
{
  if (sc)
    atomic_fetch_add(&sc->refs, 1);
  return sc;
}

void sc_schema_release(sc_schema **sc)
{
  if (!sc || !*sc)
    return;
  if (atomic_fetch_sub(&(*sc)->refs, 1) == 1) {
    for (size_t i = 0; i < (*sc)->npaths; ++i)
      free((*sc)->path[i]);
    free((*sc)->path);
    free((*sc)->key);
    free((*sc)->corner_key);
    free((void *)(*sc)->tire_name);
    free((void *)(*sc)->tire);
    free((void *)(*sc)->envelope_name);
    free((void *)(*sc)->envelope);
    free((void *)(*sc)->damper);
    free(*sc);
  }
  *sc = NULL;
}

const sch_table *sc_schema_table(const sc_schema *sc)
{
  return &sc->table;
}

int sc_schema_of(const fb_scenario *s, sc_schema **out, fb_err *err)
{
  const sc_source *src = sc_source_of(s);
  if (src && src->schema) {
    *out = sc_schema_share(src->schema);
    return FB_OK;
  }
  /* A description no file gave: the built-in entries, and its own. */
  sc_builtin own;
  sc_galleries gal;
  int rc = sc_galleries_of(NULL, &own, &gal, err);
  if (!rc && s && s->hull_source &&
      !fb_hull_source_gallery_find(gal.hulls, s->hull_source->name))
    rc = fb_hull_source_gallery_add(own.hulls, s->hull_source, err);
  if (!rc && s && s->road_type && !fb_road_gallery_find(gal.roads, s->road_type->name))
    rc = fb_road_gallery_add(own.roads, s->road_type, err);
  for (size_t c = 0; !rc && s && c < s->ncorners; ++c) {
    const fb_tire_model *m = fb_corner_tire_model(&s->corner[c]);
    const fb_damper_law *l = fb_corner_damper_law(&s->corner[c]);
    if (!fb_tire_gallery_find(gal.tires, m->name))
      rc = fb_tire_gallery_add(own.tires, m, err);
    if (!rc && !fb_damper_gallery_find(gal.dampers, l->name))
      rc = fb_damper_gallery_add(own.dampers, l, err);
    const fb_envelope_model *e = fb_corner_envelope_model(&s->corner[c]);
    if (!rc && !fb_envelope_gallery_find(gal.envelopes, e->name))
      rc = fb_envelope_gallery_add(own.envelopes, e, err);
  }
  const fb_scenario_load_opts o = {.roads = own.roads,
                                   .tires = own.tires,
                                   .hull_sources = own.hulls,
                                   .dampers = own.dampers,
                                   .envelopes = own.envelopes};
  if (!rc)
    rc = sc_schema_new(&o, out, err);
  sc_galleries_release(&own);
  return rc;
}
