/* SPDX-License-Identifier: BSD-3-Clause */
/* Unilateral compliant contact as two switched laws (see
 * fb_bg_add_unilateral_contact in flexbond/bg.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/bg.h"

#include "bg/bg_internal.h"

/* The force in contact is k q + (c + lambda q) f: Kelvin-Voigt (lambda
 * 0) or Hunt & Crossley's (c 0), whose damping grows with penetration. */
typedef struct contact_params {
  double k;      /* N/m (or the domain's effort per displacement) */
  double c;      /* N s/m */
  double lambda; /* N s/m^2 */
  /* Owned; NULL: the spring is k q. Otherwise its force in contact is
   * the table's phi(q) (fb_bg_add_table_contact), k unused. */
  fb_table_law *table;
} contact_params;

/* The spring's force in contact at compression q, and its slope. */
static double spring_force(const contact_params *p, double q, double *slope)
{
  if (p->table)
    return fb_table_law_eval(p->table, q, slope);
  if (slope)
    *slope = p->k;
  return p->k * q;
}

static void contact_free(void *ctx)
{
  contact_params *p = ctx;
  if (p)
    fb_table_law_free(&p->table);
  free(p);
}

/* The damping coefficient at compression q (> 0 in contact). */
static double damping_at(const contact_params *p, double q)
{
  return p->c + p->lambda * q;
}

enum { CONTACT = 0, RELEASED = 1 };
enum { SPRING_SEPARATED = 1, DAMPER_SEPARATED = 2 };

/* ---- Spring: xu = [q]. */

static int spring_eval(void *ctx, const fb_law_in *in, double *y)
{
  const contact_params *p = ctx;
  y[0] = in->mode == CONTACT ? spring_force(p, in->x[0], NULL) : 0.0;
  return 0;
}

static int spring_jacobian(void *ctx, const fb_law_in *in, double *jac)
{
  const contact_params *p = ctx;
  double slope = 0.0;
  if (in->mode == CONTACT)
    spring_force(p, in->x[0], &slope);
  jac[0] = slope;
  return 0;
}

static double spring_energy(void *ctx, size_t n, const double *x)
{
  const contact_params *p = ctx;
  (void)n;
  const double q = fmax(x[0], 0.0);
  return p->table ? fb_table_law_integral(p->table, q) : 0.5 * p->k * q * q;
}

static int spring_guards(void *ctx, const fb_law_in *in, double *g)
{
  (void)ctx;
  g[0] = in->x[0];
  return 0;
}

static int spring_switch(void *ctx, const fb_law_in *in, const int *sign, int *mode)
{
  (void)ctx;
  (void)in;
  *mode = sign[0] > 0 ? CONTACT : SPRING_SEPARATED;
  return 0;
}

/* The spring's ops: linear (affine in each mode, recognised as a contact
 * pair's by id) or tabulated (neither). */
#define CONTACT_SPRING_OPS(label, law_id, is_affine)                                           \
  {                                                                                            \
    .name = (label), .id = (law_id), .eval = spring_eval, .jacobian = spring_jacobian,         \
    .energy = spring_energy, .free = contact_free, .nguards = 1, .guards = spring_guards,      \
    .switch_mode = spring_switch, .affine = (is_affine)                                        \
  }
static const fb_law_ops spring_ops =
    CONTACT_SPRING_OPS("unilateral spring", FB_LAW_CONTACT_SPRING, 1);
static const fb_law_ops spring_table_ops =
    CONTACT_SPRING_OPS("unilateral table spring", FB_LAW_CUSTOM, 0);

/* ---- Damper: xu = [f, q] (own flow, then the spring's compression). */

static int damper_eval(void *ctx, const fb_law_in *in, double *y)
{
  const contact_params *p = ctx;
  const double f = in->x[0], q = in->x[1];
  y[0] = in->mode == CONTACT    ? damping_at(p, q) * f
         : in->mode == RELEASED ? -spring_force(p, q, NULL)
                                : 0.0;
  return 0;
}

static int damper_jacobian(void *ctx, const fb_law_in *in, double *jac)
{
  const contact_params *p = ctx;
  const double f = in->x[0], q = in->x[1];
  double slope = 0.0;
  spring_force(p, q, &slope);
  jac[0] = in->mode == CONTACT ? damping_at(p, q) : 0.0; /* de/df */
  jac[1] = in->mode == CONTACT    ? p->lambda * f        /* de/dq */
           : in->mode == RELEASED ? -slope
                                  : 0.0;
  return 0;
}

/* Guard 1, the force the pair would give without the clamp, means nothing
 * once separated: a constant there. */
static int damper_guards(void *ctx, const fb_law_in *in, double *g)
{
  const contact_params *p = ctx;
  const double f = in->x[0], q = in->x[1];
  g[0] = q;
  g[1] = in->mode == DAMPER_SEPARATED ? 1.0 : spring_force(p, q, NULL) + damping_at(p, q) * f;
  return 0;
}

/* Leaving separation, guard 1 was the constant: its value decides, and
 * where it is exactly zero the next round (in contact, with guard 1 live)
 * settles which way it moves. */
static int damper_switch(void *ctx, const fb_law_in *in, const int *sign, int *mode)
{
  const contact_params *p = ctx;
  const double f = in->x[0], q = in->x[1];
  const int force_sign = in->mode == DAMPER_SEPARATED
                             ? (spring_force(p, q, NULL) + damping_at(p, q) * f >= 0.0 ? 1 : -1)
                             : sign[1];
  if (sign[0] < 0)
    *mode = DAMPER_SEPARATED;
  else
    *mode = force_sign > 0 ? CONTACT : RELEASED;
  return 0;
}

/* The damper's ops, with lambda 0 (affine in each mode) or > 0 (its
 * contact branch is bilinear in f and q, so the Newton matrix changes
 * between events too). */
#define CONTACT_DAMPER_OPS(label, law_id, is_affine)                                           \
  {                                                                                            \
    .name = (label), .id = (law_id), .eval = damper_eval, .jacobian = damper_jacobian,         \
    .free = contact_free, .nguards = 2, .guards = damper_guards, .switch_mode = damper_switch, \
    .affine = (is_affine), .passive = 1                                                        \
  }
static const fb_law_ops damper_ops =
    CONTACT_DAMPER_OPS("unilateral damper", FB_LAW_CONTACT_DAMPER, 1);
static const fb_law_ops damper_hc_ops =
    CONTACT_DAMPER_OPS("unilateral Hunt-Crossley damper", FB_LAW_CONTACT_DAMPER, 0);
/* Not FB_LAW_CONTACT_DAMPER: fb_bg_element_contact describes a linear
 * spring only. */
static const fb_law_ops damper_table_ops =
    CONTACT_DAMPER_OPS("unilateral damper of a table spring", FB_LAW_CUSTOM, 0);

/* A law of ops with params (their table none) and its own copy of
 * table's knots (NULL: none) as its context. */
static int add_law(fb_bg *bg, const char *name, fb_bg_kind kind, const fb_law_ops *ops,
                   const contact_params *params, const fb_table_law *table, fb_err *err)
{
  static const size_t one_port[1] = {1};
  contact_params *p = malloc(sizeof *p);
  if (!p)
    return fb_err_set(err, FB_ENOMEM, "out of memory");
  *p = *params;
  const double *x = NULL, *y = NULL;
  const size_t n = table ? fb_table_law_knots(table, &x, &y) : 0;
  int rc = n ? fb_table_law_new(n, x, y, &p->table, err) : FB_OK;
  if (rc) {
    free(p);
    return rc;
  }
  return fb_bg_add_field_law(bg, name, kind, 1, one_port, ops, p, err);
}

/* The pair for either damping law (at most one of c, lambda nonzero),
 * the spring's force table's (NULL: k q). */
static int add_contact(fb_bg *bg, const char *spring, const char *damper,
                       const contact_params *p, const fb_table_law *table, fb_err *err)
{
  /* Both names are checked first, so that a refusal adds neither. */
  int rc = fb_bg_check_new_name(bg, spring, err);
  if (!rc)
    rc = fb_bg_check_new_name(bg, damper, err);
  if (!rc && strcmp(spring, damper) == 0)
    rc = fb_err_set(err, FB_EMODEL, "unilateral contact: spring and damper both named '%s'",
                    spring);
  if (!rc)
    rc = add_law(bg, spring, FB_BG_C, table ? &spring_table_ops : &spring_ops, p, table, err);
  if (!rc)
    rc = add_law(bg, damper, FB_BG_R,
                 table             ? &damper_table_ops
                 : p->lambda > 0.0 ? &damper_hc_ops
                                   : &damper_ops,
                 p, table, err);
  if (!rc)
    rc = fb_bg_modulate(bg, damper, 1, &spring, err);
  return rc;
}

int fb_bg_add_unilateral_contact(fb_bg *bg, const char *spring, const char *damper, double k,
                                 double c, fb_err *err)
{
  if (!(isfinite(k) && k > 0.0) || !(isfinite(c) && c >= 0.0))
    return fb_err_set(err, FB_EINVAL,
                      "unilateral contact '%s'/'%s': needs a finite stiffness > 0 and damping "
                      ">= 0 (got k = %g, c = %g)",
                      spring, damper, k, c);
  const contact_params p = {k, c, 0.0, NULL};
  return add_contact(bg, spring, damper, &p, NULL, err);
}

int fb_bg_add_hunt_crossley_contact(fb_bg *bg, const char *spring, const char *damper, double k,
                                    double lambda, fb_err *err)
{
  if (!(isfinite(k) && k > 0.0) || !(isfinite(lambda) && lambda >= 0.0))
    return fb_err_set(err, FB_EINVAL,
                      "Hunt-Crossley contact '%s'/'%s': needs a finite stiffness > 0 and "
                      "damping per penetration >= 0 (got k = %g, lambda = %g)",
                      spring, damper, k, lambda);
  const contact_params p = {k, 0.0, lambda, NULL};
  return add_contact(bg, spring, damper, &p, NULL, err);
}

int fb_bg_add_table_contact(fb_bg *bg, const char *spring, const char *damper,
                            const fb_table_law *law, double c, fb_err *err)
{
  if (!law || !(isfinite(c) && c >= 0.0))
    return fb_err_set(err, FB_EINVAL,
                      "table contact '%s'/'%s': needs a table and damping >= 0 (got c = %g)",
                      spring, damper, c);
  const double *x = NULL, *y = NULL;
  const size_t n = fb_table_law_knots(law, &x, &y);
  int rc = fb_table_law_check_monotone(law, err);
  if (!rc && !(x[0] == 0.0 && y[0] == 0.0))
    rc = fb_err_set(err, FB_EINVAL,
                    "table contact '%s': its table starts at (0, 0), where contact begins "
                    "(got (%g, %g))",
                    spring, x[0], y[0]);
  if (!rc && !(y[n - 1] > 0.0))
    rc = fb_err_set(err, FB_EINVAL, "table contact '%s': its forces are all 0", spring);
  if (rc)
    return rc;
  const contact_params p = {0.0, c, 0.0, NULL};
  return add_contact(bg, spring, damper, &p, law, err);
}

/* 1 if element i has the law of that id. */
static int has_law(const fb_bg *bg, size_t i, fb_law_id id)
{
  return bg->elems[i].law_ops && bg->elems[i].law_ops->id == id;
}

/* The damper is recognised by its law and finds its spring through its
 * modulation (fb_bg_add_unilateral_contact makes the spring its only
 * modulator); a spring looks for the damper modulated by it. */
int fb_bg_element_contact(const fb_bg *bg, size_t i, fb_bg_contact *out)
{
  size_t damper = FB_NONE;
  if (has_law(bg, i, FB_LAW_CONTACT_DAMPER) && bg->elems[i].nmod == 1)
    damper = i;
  for (size_t j = 0;
       damper == FB_NONE && has_law(bg, i, FB_LAW_CONTACT_SPRING) && j < bg->nelems; ++j)
    if (has_law(bg, j, FB_LAW_CONTACT_DAMPER) && bg->elems[j].nmod == 1 &&
        bg->elems[j].mod_src[0] == i)
      damper = j;
  if (damper == FB_NONE)
    return 0;
  const fb_bg_elem *d = &bg->elems[damper];
  const contact_params *p = d->law_ctx;
  *out = (fb_bg_contact){d->mod_src[0], damper, p->k, p->c, p->lambda};
  return 1;
}
