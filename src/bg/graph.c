/* SPDX-License-Identifier: BSD-3-Clause */
/* Bond graph construction: elements, bonds, ports and subsystem adoption. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bg/bg_internal.h"

const char *fb_bg_kind_name(fb_bg_kind kind)
{
  switch (kind) {
  case FB_BG_SE: return "Se";
  case FB_BG_SF: return "Sf";
  case FB_BG_I: return "I";
  case FB_BG_C: return "C";
  case FB_BG_R: return "R";
  case FB_BG_TF: return "TF";
  case FB_BG_GY: return "GY";
  case FB_BG_MTF: return "MTF";
  case FB_BG_J0: return "0-junction";
  case FB_BG_J1: return "1-junction";
  case FB_BG_COMPOSITE: return "composite";
  }
  return "?";
}

const char *fb_bg_domain_unit(fb_bg_domain d, int which)
{
  static const char *const units[5][4] = {
      {"N", "m/s", "N s", "m"}, {"N m", "rad/s", "N m s", "rad"},
      {"V", "A", "V s", "C"},   {"Pa", "m^3/s", "Pa s", "m^3"},
      {"1", "1", "1", "1"},
  };
  if ((int)d < 0 || d > FB_DOMAIN_GENERIC || which < 0 || which > 3)
    return "?";
  return units[d][which];
}

void fb_bg_describe(const fb_bg *bg, size_t e, char *buf, size_t size)
{
  snprintf(buf, size, "%s '%s'", fb_bg_kind_name(bg->elems[e].kind), bg->elems[e].name);
}

int fb_bg_new(const char *name, fb_bg **out, fb_err *err)
{
  *out = NULL;
  fb_bg *bg = calloc(1, sizeof *bg);
  if (!bg || !(bg->name = fb_strdup(name ? name : "model"))) {
    free(bg);
    return fb_err_set(err, FB_ENOMEM, "out of memory creating graph");
  }
  bg->domain = FB_DOMAIN_TRANSLATION;
  *out = bg;
  return FB_OK;
}

static void elem_release(fb_bg_elem *el)
{
  free(el->name);
  free(el->port_dims);
  free(el->bonds);
  fb_mat_free(&el->law);
  if (el->law_ops && el->law_ops->free)
    el->law_ops->free(el->law_ctx);
  if (el->values) {
    for (size_t i = 0; i < el->dim; ++i)
      fb_tfun_free(&el->values[i]);
    free(el->values);
  }
  free(el->x0);
  free(el->mod_src);
  for (size_t i = 0; el->labels && i < el->dim; ++i)
    free(el->labels[i]);
  free(el->labels);
}

int fb_bg_set_labels(fb_bg *bg, const char *element, const char *const *labels, fb_err *err)
{
  const long i = fb_bg_find_element(bg, element);
  if (i < 0)
    return fb_err_set(err, FB_EMODEL, "no element '%s' to label", element);
  fb_bg_elem *el = &bg->elems[i];
  char **copy = calloc(el->dim, sizeof *copy);
  int ok = copy != NULL;
  for (size_t k = 0; ok && k < el->dim; ++k)
    ok = (copy[k] = fb_strdup(labels[k])) != NULL;
  if (!ok) {
    for (size_t k = 0; copy && k < el->dim; ++k)
      free(copy[k]);
    free(copy);
    return fb_err_set(err, FB_ENOMEM, "out of memory labelling '%s'", element);
  }
  for (size_t k = 0; el->labels && k < el->dim; ++k)
    free(el->labels[k]);
  free(el->labels);
  el->labels = copy;
  return FB_OK;
}

const char *fb_bg_element_label(const fb_bg *bg, size_t i, size_t component)
{
  if (i >= bg->nelems || component >= bg->elems[i].dim || !bg->elems[i].labels)
    return NULL;
  return bg->elems[i].labels[component];
}

void fb_bg_free(fb_bg **bgp)
{
  if (!bgp || !*bgp)
    return;
  fb_bg *bg = *bgp;
  for (size_t i = 0; i < bg->nelems; ++i)
    elem_release(&bg->elems[i]);
  for (size_t i = 0; i < bg->nbonds; ++i)
    free(bg->bonds[i].name);
  for (size_t i = 0; i < bg->nports; ++i)
    free(bg->ports[i].name);
  for (size_t i = 0; i < bg->ninstances; ++i)
    free(bg->instances[i]);
  free(bg->elems);
  free(bg->bonds);
  free(bg->ports);
  free(bg->instances);
  free(bg->name);
  free(bg);
  *bgp = NULL;
}

const char *fb_bg_name(const fb_bg *bg)
{
  return bg->name;
}

void fb_bg_set_domain(fb_bg *bg, fb_bg_domain domain)
{
  bg->domain = domain;
}

long fb_bg_find_element(const fb_bg *bg, const char *name)
{
  for (size_t i = 0; i < bg->nelems; ++i)
    if (strcmp(bg->elems[i].name, name) == 0)
      return (long)i;
  return -1;
}

long fb_bg_find_bond(const fb_bg *bg, const char *name)
{
  for (size_t i = 0; i < bg->nbonds; ++i)
    if (strcmp(bg->bonds[i].name, name) == 0)
      return (long)i;
  return -1;
}

static int find_instance(const fb_bg *bg, const char *name)
{
  for (size_t i = 0; i < bg->ninstances; ++i)
    if (strcmp(bg->instances[i], name) == 0)
      return 1;
  return 0;
}

/* Checks that name can name a new element or instance of bg. */
int fb_bg_check_new_name(const fb_bg *bg, const char *name, fb_err *err)
{
  if (!name || !*name)
    return fb_err_set(err, FB_EMODEL, "empty element name");
  if (strchr(name, '.'))
    return fb_err_set(err, FB_EMODEL, "name '%s' may not contain '.'", name);
  if (fb_bg_find_element(bg, name) >= 0)
    return fb_err_set(err, FB_EMODEL, "duplicate element name '%s'", name);
  if (find_instance(bg, name))
    return fb_err_set(err, FB_EMODEL, "name '%s' is already a subsystem instance", name);
  return FB_OK;
}

/* Appends an element with nports fixed slots (or a junction when
 * port_dims is NULL) and returns it in *out. */
static int add_elem(fb_bg *bg, const char *name, fb_bg_kind kind, size_t dim, size_t nports,
                    const size_t *port_dims, fb_bg_elem **out, fb_err *err)
{
  int rc = fb_bg_check_new_name(bg, name, err);
  if (rc)
    return rc;
  if (dim == 0)
    return fb_err_set(err, FB_EMODEL, "element '%s': dimension must be >= 1", name);
  if (fb_grow((void **)&bg->elems, &bg->cap_elems, bg->nelems, sizeof *bg->elems))
    return fb_err_set(err, FB_ENOMEM, "out of memory adding '%s'", name);
  fb_bg_elem *el = &bg->elems[bg->nelems];
  memset(el, 0, sizeof *el);
  el->kind = kind;
  el->dim = dim;
  el->fixed_ports = port_dims != NULL;
  el->name = fb_strdup(name);
  if (!el->name)
    return fb_err_set(err, FB_ENOMEM, "out of memory adding '%s'", name);
  if (port_dims) {
    el->nports = nports;
    el->port_dims = malloc(nports * sizeof *el->port_dims);
    el->bonds = malloc(nports * sizeof *el->bonds);
    if (!el->port_dims || !el->bonds) {
      elem_release(el);
      return fb_err_set(err, FB_ENOMEM, "out of memory adding '%s'", name);
    }
    for (size_t i = 0; i < nports; ++i) {
      el->port_dims[i] = port_dims[i];
      el->bonds[i] = FB_NONE;
    }
  }
  bg->nelems++;
  *out = el;
  return FB_OK;
}

int fb_bg_add_source(fb_bg *bg, const char *name, fb_bg_kind kind, size_t dim, fb_tfun **values,
                     fb_err *err)
{
  fb_bg_elem *el = NULL;
  int rc = FB_OK;
  if (kind != FB_BG_SE && kind != FB_BG_SF)
    rc = fb_err_set(err, FB_EINVAL, "'%s': a source must be Se or Sf", name);
  for (size_t i = 0; !rc && i < dim; ++i)
    if (!values[i])
      rc = fb_err_set(err, FB_EINVAL, "'%s': component %zu has no time function", name, i + 1);
  if (!rc)
    rc = add_elem(bg, name, kind, dim, 1, &dim, &el, err);
  /* NOLINTNEXTLINE(bugprone-sizeof-expression): an array of pointers, sized by its element */
  if (!rc && !(el->values = calloc(dim, sizeof *el->values))) {
    rc = fb_err_set(err, FB_ENOMEM, "out of memory adding '%s'", name);
    bg->nelems--;
    elem_release(el);
  }
  for (size_t i = 0; i < dim; ++i) {
    if (!rc) {
      el->values[i] = values[i];
      values[i] = NULL;
    } else {
      fb_tfun_free(&values[i]);
    }
  }
  return rc;
}

int fb_bg_set_source(fb_bg *bg, const char *name, size_t k, fb_tfun **f, fb_err *err)
{
  const long i = fb_bg_find_element(bg, name);
  int rc = FB_OK;
  if (i < 0 || !bg->elems[i].values)
    rc = fb_err_set(err, FB_EMODEL, "'%s': no such source", name);
  else if (k >= bg->elems[i].dim)
    rc =
        fb_err_set(err, FB_EINVAL, "'%s': component %zu of %zu", name, k + 1, bg->elems[i].dim);
  else if (!*f)
    rc = fb_err_set(err, FB_EINVAL, "'%s': component %zu has no time function", name, k + 1);
  if (rc) {
    fb_tfun_free(f);
    return rc;
  }
  fb_tfun_free(&bg->elems[i].values[k]);
  bg->elems[i].values[k] = *f;
  *f = NULL;
  return FB_OK;
}

static int is_field_kind(fb_bg_kind kind)
{
  return kind == FB_BG_I || kind == FB_BG_C || kind == FB_BG_R;
}

/* Common part of linear and nonlinear fields. */
static int add_field_shell(fb_bg *bg, const char *name, fb_bg_kind kind, size_t nports,
                           const size_t *port_dims, fb_bg_elem **out, fb_err *err)
{
  if (!is_field_kind(kind))
    return fb_err_set(err, FB_EINVAL, "'%s': a field must be I, C or R", name);
  if (nports == 0)
    return fb_err_set(err, FB_EMODEL, "'%s': a field needs at least one port", name);
  size_t n = 0;
  for (size_t i = 0; i < nports; ++i) {
    if (port_dims[i] == 0)
      return fb_err_set(err, FB_EMODEL, "'%s': port %zu has dimension 0", name, i + 1);
    n += port_dims[i];
  }
  return add_elem(bg, name, kind, n, nports, port_dims, out, err);
}

int fb_bg_add_field(fb_bg *bg, const char *name, fb_bg_kind kind, size_t nports,
                    const size_t *port_dims, fb_mat **law, fb_err *err)
{
  fb_bg_elem *el = NULL;
  int rc = add_field_shell(bg, name, kind, nports, port_dims, &el, err);
  if (!rc && (!*law || fb_mat_nrows(*law) != el->dim || fb_mat_ncols(*law) != el->dim)) {
    rc = fb_err_set(err, FB_EMODEL, "%s '%s': law must be %zu x %zu (sum of port dimensions)",
                    fb_bg_kind_name(kind), name, el->dim, el->dim);
    bg->nelems--;
    elem_release(el);
  }
  if (!rc) {
    el->law = *law;
    *law = NULL;
  }
  fb_mat_free(law);
  return rc;
}

int fb_bg_add_field_law(fb_bg *bg, const char *name, fb_bg_kind kind, size_t nports,
                        const size_t *port_dims, const fb_law_ops *ops, void *ctx, fb_err *err)
{
  fb_bg_elem *el = NULL;
  int rc = FB_OK;
  if (!ops || !ops->eval || !ops->jacobian)
    rc = fb_err_set(err, FB_EINVAL, "'%s': a nonlinear law needs eval and jacobian functions",
                    name);
  else if (ops->nguards && (!ops->guards || !ops->switch_mode))
    rc = fb_err_set(err, FB_EINVAL, "'%s': a switched law needs guards and switch_mode", name);
  if (!rc)
    rc = add_field_shell(bg, name, kind, nports, port_dims, &el, err);
  if (rc) {
    if (ops && ops->free)
      ops->free(ctx);
    return rc;
  }
  el->law_ops = ops;
  el->law_ctx = ctx;
  return FB_OK;
}

int fb_bg_modulate(fb_bg *bg, const char *element, size_t nsources, const char *const *sources,
                   fb_err *err)
{
  const long e = fb_bg_find_element(bg, element);
  if (e < 0)
    return fb_err_set(err, FB_EMODEL, "modulation: no element '%s'", element);
  fb_bg_elem *el = &bg->elems[e];
  if (el->kind != FB_BG_R || !el->law_ops)
    return fb_err_set(err, FB_EMODEL,
                      "modulation of '%s': only an R with a nonlinear law can be modulated",
                      element);
  if (el->nmod)
    return fb_err_set(err, FB_EMODEL, "modulation of '%s': already modulated", element);
  if (nsources == 0)
    return fb_err_set(err, FB_EMODEL, "modulation of '%s': no source given", element);
  size_t *src = malloc(nsources * sizeof *src);
  if (!src)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t k = 0; k < nsources; ++k) {
    const long s = fb_bg_find_element(bg, sources[k]);
    const int storage =
        s >= 0 && (bg->elems[s].kind == FB_BG_I || bg->elems[s].kind == FB_BG_C);
    if (!storage) {
      free(src);
      return fb_err_set(err, FB_EMODEL,
                        s < 0 ? "modulation of '%s': no element '%s'"
                              : "modulation of '%s': '%s' is not a storage element (I or C)",
                        element, sources[k]);
    }
    src[k] = (size_t)s;
  }
  el->mod_src = src;
  el->nmod = nsources;
  return FB_OK;
}

int fb_bg_set_initial(fb_bg *bg, const char *name, size_t n, const double *x0, fb_err *err)
{
  long e = fb_bg_find_element(bg, name);
  if (e < 0)
    return fb_err_set(err, FB_EMODEL, "initial state: no element '%s'", name);
  fb_bg_elem *el = &bg->elems[e];
  if (el->kind != FB_BG_I && el->kind != FB_BG_C)
    return fb_err_set(err, FB_EMODEL, "initial state: '%s' is %s, not a storage element", name,
                      fb_bg_kind_name(el->kind));
  if (n != el->dim)
    return fb_err_set(err, FB_EMODEL, "initial state of '%s': %zu values given, %zu expected",
                      name, n, el->dim);
  if (!el->x0 && !(el->x0 = calloc(n, sizeof *el->x0)))
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  memcpy(el->x0, x0, n * sizeof *x0);
  return FB_OK;
}

int fb_bg_add_tf(fb_bg *bg, const char *name, fb_bg_kind kind, size_t dim, double modulus,
                 fb_err *err)
{
  if (kind != FB_BG_TF && kind != FB_BG_GY)
    return fb_err_set(err, FB_EINVAL, "'%s': expected TF or GY", name);
  const size_t dims[2] = {dim, dim};
  fb_bg_elem *el = NULL;
  int rc = add_elem(bg, name, kind, dim, 2, dims, &el, err);
  if (!rc)
    el->modulus = modulus;
  return rc;
}

int fb_bg_add_mtf(fb_bg *bg, const char *name, fb_mat **T, fb_err *err)
{
  fb_bg_elem *el = NULL;
  int rc = FB_OK;
  if (!*T)
    rc = fb_err_set(err, FB_EINVAL, "MTF '%s': no matrix", name);
  if (!rc) {
    const size_t dims[2] = {fb_mat_ncols(*T), fb_mat_nrows(*T)};
    rc = add_elem(bg, name, FB_BG_MTF, dims[0] + dims[1], 2, dims, &el, err);
  }
  if (!rc) {
    el->law = *T;
    *T = NULL;
  }
  fb_mat_free(T);
  return rc;
}

int fb_bg_add_junction(fb_bg *bg, const char *name, fb_bg_kind kind, size_t dim, fb_err *err)
{
  if (kind != FB_BG_J0 && kind != FB_BG_J1)
    return fb_err_set(err, FB_EINVAL, "'%s': expected a 0- or 1-junction", name);
  fb_bg_elem *el = NULL;
  return add_elem(bg, name, kind, dim, 0, NULL, &el, err);
}

int fb_bg_add_composite(fb_bg *bg, const char *name, size_t nparts, const size_t *part_dims,
                        fb_err *err)
{
  if (nparts == 0)
    return fb_err_set(err, FB_EMODEL, "composite '%s': needs at least one part", name);
  size_t *dims = malloc((nparts + 1) * sizeof *dims);
  if (!dims)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  size_t whole = 0;
  for (size_t i = 0; i < nparts; ++i) {
    dims[i] = part_dims[i];
    whole += part_dims[i];
  }
  dims[nparts] = whole;
  fb_bg_elem *el = NULL;
  int rc = FB_OK;
  for (size_t i = 0; !rc && i < nparts; ++i)
    if (part_dims[i] == 0)
      rc = fb_err_set(err, FB_EMODEL, "composite '%s': part %zu has dimension 0", name, i + 1);
  if (!rc)
    rc = add_elem(bg, name, FB_BG_COMPOSITE, whole, nparts + 1, dims, &el, err);
  free(dims);
  return rc;
}

/* ---- Port references. */

typedef struct port_ref {
  size_t elem;
  size_t slot; /* FB_NONE: new junction slot */
  size_t dim;
  long portdef; /* index in bg->ports when reached through a subsystem port */
} port_ref;

static long find_portdef(const fb_bg *bg, const char *name, int exported)
{
  for (size_t i = 0; i < bg->nports; ++i)
    if (bg->ports[i].exported == exported && strcmp(bg->ports[i].name, name) == 0)
      return (long)i;
  return -1;
}

/* Parses a port number k (1..n) or "whole" into a 0-based slot. */
static int parse_slot(const fb_bg_elem *el, const char *spec, size_t *slot)
{
  if (el->kind == FB_BG_COMPOSITE && strcmp(spec, "whole") == 0) {
    *slot = el->nports - 1;
    return 1;
  }
  char *end = NULL;
  unsigned long k = strtoul(spec, &end, 10);
  if (!*spec || *end || k < 1 || k > el->nports)
    return 0;
  *slot = k - 1;
  return 1;
}

static int resolve(const fb_bg *bg, const char *ref, port_ref *pr, fb_err *err)
{
  pr->portdef = find_portdef(bg, ref, 0);
  if (pr->portdef >= 0) {
    const fb_bg_portdef *pd = &bg->ports[pr->portdef];
    pr->elem = pd->elem;
    pr->slot = pd->slot;
    pr->dim = pd->dim;
    return FB_OK;
  }
  long e = fb_bg_find_element(bg, ref);
  if (e >= 0) {
    const fb_bg_elem *el = &bg->elems[e];
    pr->elem = (size_t)e;
    pr->dim = el->dim;
    if (!el->fixed_ports) {
      pr->slot = FB_NONE;
      return FB_OK;
    }
    if (el->nports != 1)
      return fb_err_set(err, FB_EMODEL, "'%s' has %zu ports: name one as '%s.1' .. '%s.%zu'%s",
                        ref, el->nports, ref, ref, el->nports,
                        el->kind == FB_BG_COMPOSITE ? " or '.whole'" : "");
    pr->slot = 0;
    pr->dim = el->port_dims[0];
    return FB_OK;
  }
  const char *dot = strrchr(ref, '.');
  if (dot) {
    char *base = fb_strdup(ref);
    if (!base)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    base[dot - ref] = '\0';
    e = fb_bg_find_element(bg, base);
    free(base);
    if (e >= 0 && bg->elems[e].fixed_ports) {
      if (!parse_slot(&bg->elems[e], dot + 1, &pr->slot))
        return fb_err_set(err, FB_EMODEL, "'%s': %s has no port '%s' (ports 1..%zu)", ref,
                          bg->elems[e].name, dot + 1, bg->elems[e].nports);
      pr->elem = (size_t)e;
      pr->dim = bg->elems[e].port_dims[pr->slot];
      return FB_OK;
    }
  }
  return fb_err_set(err, FB_EMODEL, "unknown element or port '%s'", ref);
}

/* Attaches bond b at pr's element; returns the slot used. */
static int attach(fb_bg *bg, const port_ref *pr, const char *ref, size_t b, size_t *slot,
                  fb_err *err)
{
  fb_bg_elem *el = &bg->elems[pr->elem];
  if (pr->slot == FB_NONE) {
    if (fb_grow((void **)&el->bonds, &el->cap, el->nports, sizeof *el->bonds))
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    el->bonds[el->nports] = b;
    *slot = el->nports++;
    return FB_OK;
  }
  if (el->bonds[pr->slot] != FB_NONE)
    return fb_err_set(err, FB_EMODEL, "port '%s' is already connected by bond '%s'", ref,
                      bg->bonds[el->bonds[pr->slot]].name);
  el->bonds[pr->slot] = b;
  *slot = pr->slot;
  return FB_OK;
}

static void detach(fb_bg *bg, size_t elem, size_t slot)
{
  fb_bg_elem *el = &bg->elems[elem];
  if (el->fixed_ports)
    el->bonds[slot] = FB_NONE;
  else
    el->nports--; /* the slot just added is the last one */
}

/* Checks that the subsystem ports at the ends agree with the bond's power
 * direction: power leaves through `from` and enters through `to`. */
static int check_directions(const fb_bg *bg, const char *from, const port_ref *a,
                            const char *to, const port_ref *b, fb_err *err)
{
  int bad_from = a->portdef >= 0 && bg->ports[a->portdef].dir != FB_PORT_OUT;
  int bad_to = b->portdef >= 0 && bg->ports[b->portdef].dir != FB_PORT_IN;
  if (!bad_from && !bad_to)
    return FB_OK;
  return fb_err_set(err, FB_EMODEL,
                    "cannot connect '%s' to '%s': power flows from '%s' to '%s', but '%s' is "
                    "declared as an %s port",
                    from, to, from, to, bad_from ? from : to,
                    bad_from ? "input (power in)" : "output (power out)");
}

int fb_bg_connect(fb_bg *bg, const char *name, const char *from, const char *to, fb_err *err)
{
  port_ref a, b;
  int rc = resolve(bg, from, &a, err);
  if (!rc)
    rc = resolve(bg, to, &b, err);
  if (rc)
    return rc;
  char autoname[256];
  if (!name) {
    snprintf(autoname, sizeof autoname, "%s->%s", from, to);
    name = autoname;
  }
  if (fb_bg_find_bond(bg, name) >= 0)
    return fb_err_set(err, FB_EMODEL, "duplicate bond name '%s'", name);
  if (a.elem == b.elem)
    return fb_err_set(err, FB_EMODEL, "bond '%s' connects '%s' to itself", name, from);
  if (a.dim != b.dim)
    return fb_err_set(err, FB_EMODEL,
                      "bond '%s': dimension mismatch: '%s' has dimension %zu, '%s' has "
                      "dimension %zu",
                      name, from, a.dim, to, b.dim);
  rc = check_directions(bg, from, &a, to, &b, err);
  for (int k = 0; !rc && k < 2; ++k) {
    const port_ref *p = k ? &b : &a;
    if (p->portdef >= 0 && bg->ports[p->portdef].used)
      rc = fb_err_set(err, FB_EMODEL, "port '%s' is already connected", k ? to : from);
  }
  if (rc)
    return rc;
  if (fb_grow((void **)&bg->bonds, &bg->cap_bonds, bg->nbonds, sizeof *bg->bonds))
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  size_t id = bg->nbonds;
  fb_bg_bond *bd = &bg->bonds[id];
  memset(bd, 0, sizeof *bd);
  bd->name = fb_strdup(name);
  if (!bd->name)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  bd->dim = a.dim;
  bd->domain = bg->domain;
  bd->from = a.elem;
  bd->to = b.elem;
  bd->stroke = FB_STROKE_UNSET;
  bd->cause = FB_NONE;
  rc = attach(bg, &a, from, id, &bd->from_slot, err);
  if (!rc) {
    rc = attach(bg, &b, to, id, &bd->to_slot, err);
    if (rc)
      detach(bg, a.elem, bd->from_slot);
  }
  if (rc) {
    free(bd->name);
    return rc;
  }
  if (a.portdef >= 0)
    bg->ports[a.portdef].used = 1;
  if (b.portdef >= 0)
    bg->ports[b.portdef].used = 1;
  bg->nbonds++;
  bg->causal = 0;
  return FB_OK;
}

int fb_bg_set_bond_domain(fb_bg *bg, const char *bond, fb_bg_domain domain, fb_err *err)
{
  long b = fb_bg_find_bond(bg, bond);
  if (b < 0)
    return fb_err_set(err, FB_EMODEL, "no bond '%s'", bond);
  bg->bonds[b].domain = domain;
  return FB_OK;
}

/* ---- Subsystems. */

static int push_portdef(fb_bg *bg, char *name, fb_bg_dir dir, int exported, size_t elem,
                        size_t slot, size_t dim, fb_err *err)
{
  if (fb_grow((void **)&bg->ports, &bg->cap_ports, bg->nports, sizeof *bg->ports)) {
    free(name);
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  }
  fb_bg_portdef *pd = &bg->ports[bg->nports++];
  pd->name = name;
  pd->dir = dir;
  pd->exported = exported;
  pd->used = 0;
  pd->elem = elem;
  pd->slot = slot;
  pd->dim = dim;
  return FB_OK;
}

int fb_bg_add_port(fb_bg *bg, const char *port_name, const char *target, fb_bg_dir dir,
                   fb_err *err)
{
  if (!port_name || !*port_name || strchr(port_name, '.'))
    return fb_err_set(err, FB_EMODEL, "port name '%s' must be non-empty without '.'",
                      port_name ? port_name : "");
  if (find_portdef(bg, port_name, 1) >= 0)
    return fb_err_set(err, FB_EMODEL, "duplicate port '%s'", port_name);
  port_ref pr;
  int rc = resolve(bg, target, &pr, err);
  if (rc) {
    fb_err_prefix(err, "port '%s': ", port_name);
    return rc;
  }
  if (pr.portdef >= 0) {
    fb_bg_portdef *inner = &bg->ports[pr.portdef];
    if (inner->used)
      return fb_err_set(err, FB_EMODEL, "port '%s': '%s' is already connected", port_name,
                        target);
    if (inner->dir != dir)
      return fb_err_set(err, FB_EMODEL,
                        "port '%s' re-exports '%s' with the opposite power direction",
                        port_name, target);
  } else if (pr.slot != FB_NONE && bg->elems[pr.elem].bonds[pr.slot] != FB_NONE) {
    return fb_err_set(err, FB_EMODEL, "port '%s': '%s' is already connected", port_name,
                      target);
  }
  char *name = fb_strdup(port_name);
  if (!name)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  rc = push_portdef(bg, name, dir, 1, pr.elem, pr.slot, pr.dim, err);
  if (!rc && pr.portdef >= 0)
    bg->ports[pr.portdef].used = 1; /* re-exported: no longer connectable here */
  return rc;
}

static char *prefixed(const char *prefix, const char *name)
{
  size_t n = strlen(prefix) + strlen(name) + 2;
  char *s = malloc(n);
  if (s)
    snprintf(s, n, "%s.%s", prefix, name);
  return s;
}

/* Renames every element, bond and exported port of child with the
 * instance prefix. */
static int prefix_names(fb_bg *child, const char *inst, fb_err *err)
{
  for (size_t i = 0; i < child->nelems; ++i) {
    char *s = prefixed(inst, child->elems[i].name);
    if (!s)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    free(child->elems[i].name);
    child->elems[i].name = s;
  }
  for (size_t i = 0; i < child->nbonds; ++i) {
    char *s = prefixed(inst, child->bonds[i].name);
    if (!s)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    free(child->bonds[i].name);
    child->bonds[i].name = s;
  }
  for (size_t i = 0; i < child->nports; ++i) {
    if (!child->ports[i].exported)
      continue;
    char *s = prefixed(inst, child->ports[i].name);
    if (!s)
      return fb_err_set(err, FB_ENOMEM, "out of memory");
    free(child->ports[i].name);
    child->ports[i].name = s;
  }
  return FB_OK;
}

static int reserve_all(fb_bg *p, const fb_bg *c)
{
  if (fb_grow((void **)&p->elems, &p->cap_elems, p->nelems + c->nelems, sizeof *p->elems) ||
      fb_grow((void **)&p->bonds, &p->cap_bonds, p->nbonds + c->nbonds, sizeof *p->bonds) ||
      fb_grow((void **)&p->ports, &p->cap_ports, p->nports + c->nports, sizeof *p->ports) ||
      fb_grow((void **)&p->instances, &p->cap_instances, p->ninstances, sizeof *p->instances))
    return FB_ENOMEM;
  return FB_OK;
}

int fb_bg_adopt(fb_bg *parent, fb_bg **childp, const char *instance_name, fb_err *err)
{
  fb_bg *child = *childp;
  *childp = NULL;
  int rc = fb_bg_check_new_name(parent, instance_name, err);
  if (!rc)
    rc = prefix_names(child, instance_name, err);
  if (!rc && reserve_all(parent, child))
    rc = fb_err_set(err, FB_ENOMEM, "out of memory adopting '%s'", instance_name);
  char *inst = rc ? NULL : fb_strdup(instance_name);
  if (!rc && !inst)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory");
  if (rc) {
    fb_bg_free(&child);
    return rc;
  }
  /* Child names are prefixed, so they cannot collide with the parent's. */
  size_t eoff = parent->nelems, boff = parent->nbonds;
  for (size_t i = 0; i < child->nelems; ++i) {
    fb_bg_elem *el = &child->elems[i];
    for (size_t k = 0; k < el->nports; ++k)
      if (el->bonds[k] != FB_NONE)
        el->bonds[k] += boff;
    for (size_t k = 0; k < el->nmod; ++k)
      el->mod_src[k] += eoff;
    parent->elems[parent->nelems++] = *el;
  }
  for (size_t i = 0; i < child->nbonds; ++i) {
    fb_bg_bond *bd = &child->bonds[i];
    bd->from += eoff;
    bd->to += eoff;
    bd->stroke = FB_STROKE_UNSET;
    parent->bonds[parent->nbonds++] = *bd;
  }
  /* Exported ports become the parent's connectable "inst.port" entries;
   * inner subsystems' ports stay encapsulated. Capacity was reserved. */
  for (size_t i = 0; i < child->nports; ++i) {
    fb_bg_portdef *pd = &child->ports[i];
    if (!pd->exported)
      continue;
    fb_bg_portdef *np = &parent->ports[parent->nports++];
    *np = *pd;
    np->exported = 0;
    np->used = 0;
    np->elem += eoff;
    pd->name = NULL;
  }
  parent->instances[parent->ninstances++] = inst;
  parent->causal = 0;
  /* The parent now owns the elements' and bonds' contents. */
  child->nelems = child->nbonds = 0;
  fb_bg_free(&child);
  return FB_OK;
}

/* ---- Inspection. */

size_t fb_bg_nelements(const fb_bg *bg)
{
  return bg->nelems;
}
size_t fb_bg_nbonds(const fb_bg *bg)
{
  return bg->nbonds;
}
const char *fb_bg_element_name(const fb_bg *bg, size_t i)
{
  return bg->elems[i].name;
}
fb_bg_kind fb_bg_element_kind(const fb_bg *bg, size_t i)
{
  return bg->elems[i].kind;
}
size_t fb_bg_element_dim(const fb_bg *bg, size_t i)
{
  return bg->elems[i].dim;
}
const char *fb_bg_bond_name(const fb_bg *bg, size_t i)
{
  return bg->bonds[i].name;
}
size_t fb_bg_bond_dim(const fb_bg *bg, size_t i)
{
  return bg->bonds[i].dim;
}
fb_bg_domain fb_bg_bond_domain(const fb_bg *bg, size_t i)
{
  return bg->bonds[i].domain;
}
size_t fb_bg_bond_from(const fb_bg *bg, size_t i)
{
  return bg->bonds[i].from;
}
size_t fb_bg_bond_to(const fb_bg *bg, size_t i)
{
  return bg->bonds[i].to;
}
int fb_bg_bond_effort_to_head(const fb_bg *bg, size_t i)
{
  return bg->bonds[i].stroke;
}

int fb_bg_receives_effort(const fb_bg *bg, size_t b, size_t e)
{
  const fb_bg_bond *bd = &bg->bonds[b];
  return (bd->stroke == FB_STROKE_AT_TO && bd->to == e) ||
         (bd->stroke == FB_STROKE_AT_FROM && bd->from == e);
}

int fb_bg_orientation(const fb_bg *bg, size_t b, size_t e)
{
  return bg->bonds[b].to == e ? 1 : -1;
}

/* ---- Read-only access for writers (bg.h, "Reading a graph back"). */

fb_bg_domain fb_bg_default_domain(const fb_bg *bg)
{
  return bg->domain;
}
size_t fb_bg_element_nports(const fb_bg *bg, size_t i)
{
  return bg->elems[i].nports;
}
size_t fb_bg_element_port_dim(const fb_bg *bg, size_t i, size_t k)
{
  const fb_bg_elem *el = &bg->elems[i];
  return el->fixed_ports ? el->port_dims[k] : el->dim;
}
int fb_bg_element_has_fixed_ports(const fb_bg *bg, size_t i)
{
  return bg->elems[i].fixed_ports;
}
const fb_mat *fb_bg_element_matrix(const fb_bg *bg, size_t i)
{
  return bg->elems[i].law;
}
const fb_law_ops *fb_bg_element_law(const fb_bg *bg, size_t i, const void **ctx)
{
  if (ctx)
    *ctx = bg->elems[i].law_ctx;
  return bg->elems[i].law_ops;
}
double fb_bg_element_modulus(const fb_bg *bg, size_t i)
{
  return bg->elems[i].modulus;
}
const fb_tfun *fb_bg_element_source(const fb_bg *bg, size_t i, size_t k)
{
  const fb_bg_elem *el = &bg->elems[i];
  return el->values && k < el->dim ? el->values[k] : NULL;
}
const double *fb_bg_element_initial(const fb_bg *bg, size_t i)
{
  return bg->elems[i].x0;
}
size_t fb_bg_bond_from_port(const fb_bg *bg, size_t i)
{
  return bg->bonds[i].from_slot;
}
size_t fb_bg_bond_to_port(const fb_bg *bg, size_t i)
{
  return bg->bonds[i].to_slot;
}
size_t fb_bg_ndeclared_ports(const fb_bg *bg)
{
  return bg->nports;
}
int fb_bg_declared_port(const fb_bg *bg, size_t i, fb_bg_port_info *out)
{
  if (i >= bg->nports)
    return FB_EINVAL;
  const fb_bg_portdef *pd = &bg->ports[i];
  *out = (fb_bg_port_info){pd->name, pd->dir, pd->exported, pd->elem,
                           pd->slot == FB_NONE ? FB_BG_ANY_PORT : pd->slot};
  return FB_OK;
}
