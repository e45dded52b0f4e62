/* SPDX-License-Identifier: BSD-3-Clause */
/* The scenario format's table with a road gallery's types
 * (scenario_internal.h): the format's own keys, and for each road type
 * a section road.<type> whose keys are the type's declared parameters
 * (flexbond/param.h), made here once per gallery. */
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/vehicle.h"

#include "core/util.h"
#include "io/scenario_internal.h"

struct sc_schema {
  sch_table table; /* first: a schema is its table */
  sch_key *key;    /* owned, table.n of them */
  char **path;     /* the generated keys' paths, owned */
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

/* An optional parameter left out (NaN, or no choice) is no value. */
static int sc_param_present(const sch_key *k, const void *base)
{
  const fb_param *p = k->data;
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

/* A copy of "road.<type>[.<param>]", kept by the schema. */
static const char *sc_key_path(sc_schema *sc, const fb_road_type *t, const fb_param *p)
{
  char *path = fb_strdup_printf("road.%s%s%s", t->name, p ? "." : "", p ? p->name : "");
  if (path)
    sc->path[sc->npaths++] = path;
  return path;
}

static sch_key sc_param_key(const char *path, const fb_param *p)
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
      .offset = offsetof(fb_scenario, road) + p->offset,
      .ops = &sc_param_ops,
      .scale = p->scale,
      .data = p,
  };
  return k;
}

/* The keys of type t from sc->key[*n] on. */
static int sc_type_keys(sc_schema *sc, const fb_road_type *t, size_t *n, fb_err *err)
{
  const char *path = sc_key_path(sc, t, NULL);
  if (!path)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
  sc->key[(*n)++] = (sch_key){.path = path,
                              .type = SCH_SECTION,
                              .need = SCH_REQUIRED,
                              .one_of = "road",
                              .doc = t->doc,
                              .ops = &sc_road_ops,
                              .data = t};
  for (size_t i = 0; i < t->nparams; ++i) {
    if (!(path = sc_key_path(sc, t, &t->param[i])))
      return fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
    sc->key[(*n)++] = sc_param_key(path, &t->param[i]);
  }
  return FB_OK;
}

/* The generated keys' count: a section and its parameters per type. */
static size_t sc_gallery_keys(const fb_road_gallery *g)
{
  size_t n = 0;
  for (size_t i = 0; i < fb_road_gallery_count(g); ++i)
    n += 1 + fb_road_gallery_at(g, i)->nparams;
  return n;
}

static int sc_schema_fill(sc_schema *sc, const fb_road_gallery *g, fb_err *err)
{
  const sch_table *own = &sc_format;
  const size_t extra = sc_gallery_keys(g);
  sc->key = calloc(own->n + extra, sizeof *sc->key);
  sc->path = calloc(extra ? extra : 1, sizeof *sc->path);
  if (!sc->key || !sc->path)
    return fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
  size_t n = 0;
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < own->n; ++i) {
    sc->key[n++] = own->key[i];
    /* The road's types follow its own keys. */
    for (size_t j = 0;
         !rc && !strcmp(own->key[i].path, SC_ROAD_TYPES_AFTER) && j < fb_road_gallery_count(g);
         ++j)
      rc = sc_type_keys(sc, fb_road_gallery_at(g, j), &n, err);
  }
  sc->table = (sch_table){sc->key, n, own->done};
  return rc;
}

int sc_schema_new(const fb_road_gallery *g, sc_schema **out, fb_err *err)
{
  *out = NULL;
  fb_road_gallery *builtin = NULL;
  int rc = g ? FB_OK : fb_road_gallery_new(&builtin, err);
  sc_schema *sc = rc ? NULL : calloc(1, sizeof *sc);
  if (!rc && !sc)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for the scenario format");
  if (!rc) {
    atomic_init(&sc->refs, 1);
    rc = sc_schema_fill(sc, g ? g : builtin, err);
  }
  fb_road_gallery_free(&builtin);
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
  /* A description no file gave: the built-in types, and its own. */
  fb_road_gallery *g = NULL;
  int rc = fb_road_gallery_new(&g, err);
  if (!rc && s && s->road_type && !fb_road_gallery_find(g, s->road_type->name))
    rc = fb_road_gallery_add(g, s->road_type, err);
  if (!rc)
    rc = sc_schema_new(g, out, err);
  fb_road_gallery_free(&g);
  return rc;
}
