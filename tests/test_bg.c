/* SPDX-License-Identifier: BSD-3-Clause */
/* Bond graph core: construction, subsystems and ports, causality
 * assignment and its diagnostics. */
#include <string.h>

#include "flexbond/bg.h"

#include "bgtest_util.h"
#include "check.h"

/* Mass-spring-damper driven by a force: Se -> 1 -> {I, C, R}. */
static fb_bg *msd(fb_err *err)
{
  fb_bg *bg = NULL;
  MUST(fb_bg_new("msd", &bg, err), err);
  MUST(add_const_source(bg, "F", FB_BG_SE, 1.0, err), err);
  MUST(fb_bg_add_junction(bg, "J", FB_BG_J1, 1, err), err);
  MUST(add_scalar(bg, "m", FB_BG_I, 2.0, err), err);
  MUST(add_scalar(bg, "k", FB_BG_C, 50.0, err), err);
  MUST(add_scalar(bg, "r", FB_BG_R, 3.0, err), err);
  MUST(fb_bg_connect(bg, "b1", "F", "J", err), err);
  MUST(fb_bg_connect(bg, "b2", "J", "m", err), err);
  MUST(fb_bg_connect(bg, "b3", "J", "k", err), err);
  MUST(fb_bg_connect(bg, "b4", "J", "r", err), err);
  return bg;
}

static int stroke_at(const fb_bg *bg, const char *bond, const char *elem)
{
  long b = fb_bg_find_bond(bg, bond);
  long e = fb_bg_find_element(bg, elem);
  int head = fb_bg_bond_effort_to_head(bg, (size_t)b);
  size_t end = head ? fb_bg_bond_to(bg, (size_t)b) : fb_bg_bond_from(bg, (size_t)b);
  return head >= 0 && end == (size_t)e;
}

static void test_msd_causality(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = msd(&err);
  MUST(fb_bg_assign_causality(bg, &err), &err);
  /* Integral causality: I receives effort, C imposes it; the 1-junction's
   * flow is set by the I; Se imposes effort; R then gets its flow. */
  CHECK(stroke_at(bg, "b1", "J"));
  CHECK(stroke_at(bg, "b2", "m"));
  CHECK(stroke_at(bg, "b3", "J"));
  CHECK(stroke_at(bg, "b4", "J"));
  CHECK(fb_bg_nelements(bg) == 5 && fb_bg_nbonds(bg) == 4);
  fb_bg_free(&bg);
  CHECK(bg == NULL);
}

static void test_derivative_causality(void)
{
  fb_err err;
  fb_err_clear(&err);
  /* Two masses on one 1-junction: the second is dependent. */
  fb_bg *bg = msd(&err);
  MUST(add_scalar(bg, "m2", FB_BG_I, 1.0, &err), &err);
  MUST(fb_bg_connect(bg, "b5", "J", "m2", &err), &err);
  int rc = fb_bg_assign_causality(bg, &err);
  CHECK(rc == FB_ECAUSAL);
  CHECK(strstr(err.msg, "I 'm2' is in derivative causality on bond 'b5'") != NULL);
  CHECK(strstr(err.msg, "I 'm'") != NULL);
  /* The origin names the dependent element for the model's file location. */
  CHECK(err.origin == FB_ORIGIN_ELEMENT &&
        (long)err.origin_index == fb_bg_find_element(bg, "m2"));
  fb_bg_free(&bg);
}

static void test_conflict(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  MUST(fb_bg_new("conflict", &bg, &err), &err);
  MUST(add_const_source(bg, "E1", FB_BG_SE, 1.0, &err), &err);
  MUST(add_const_source(bg, "E2", FB_BG_SE, 2.0, &err), &err);
  MUST(fb_bg_add_junction(bg, "J0", FB_BG_J0, 1, &err), &err);
  MUST(add_scalar(bg, "c", FB_BG_C, 1.0, &err), &err);
  MUST(fb_bg_connect(bg, "a", "E1", "J0", &err), &err);
  MUST(fb_bg_connect(bg, "b", "E2", "J0", &err), &err);
  MUST(fb_bg_connect(bg, "c", "J0", "c", &err), &err);
  CHECK(fb_bg_assign_causality(bg, &err) == FB_ECAUSAL);
  CHECK(strstr(err.msg, "bond 'b' ('E2' -> 'J0')") != NULL);
  CHECK(strstr(err.msg, "Se 'E1'") != NULL && strstr(err.msg, "Se 'E2'") != NULL);
  CHECK(err.origin == FB_ORIGIN_BOND && (long)err.origin_index == fb_bg_find_bond(bg, "b"));
  /* A later error with no origin of its own does not keep this one. */
  fb_err_set(&err, FB_EINVAL, "unrelated");
  CHECK(err.origin == FB_ORIGIN_NONE);
  fb_bg_free(&bg);
}

static void test_unconnected_and_dims(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  MUST(fb_bg_new("dims", &bg, &err), &err);
  MUST(fb_bg_add_junction(bg, "J3", FB_BG_J1, 3, &err), &err);
  MUST(add_scalar(bg, "m", FB_BG_I, 1.0, &err), &err);
  CHECK(fb_bg_connect(bg, "x", "J3", "m", &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "'J3' has dimension 3") && strstr(err.msg, "'m' has dimension 1"));
  CHECK(fb_bg_assign_causality(bg, &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "I 'm': port 1 is not connected") != NULL);
  CHECK(err.origin == FB_ORIGIN_ELEMENT &&
        (long)err.origin_index == fb_bg_find_element(bg, "m"));
  CHECK(fb_bg_connect(bg, "y", "J3", "nowhere", &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "unknown element or port 'nowhere'") != NULL);
  CHECK(add_scalar(bg, "m", FB_BG_C, 1.0, &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "duplicate element name 'm'") != NULL);
  fb_bg_free(&bg);
}

/* A spring-mass fragment with one input port, used twice. */
static fb_bg *corner(double k, fb_err *err)
{
  fb_bg *c = NULL;
  MUST(fb_bg_new("corner", &c, err), err);
  MUST(fb_bg_add_junction(c, "J", FB_BG_J1, 1, err), err);
  MUST(add_scalar(c, "k", FB_BG_C, k, err), err);
  MUST(fb_bg_connect(c, "bk", "J", "k", err), err);
  MUST(fb_bg_add_port(c, "top", "J", FB_PORT_IN, err), err);
  return c;
}

static void test_subsystems(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  MUST(fb_bg_new("car", &bg, &err), &err);
  MUST(add_const_source(bg, "v", FB_BG_SF, 1.0, &err), &err);
  /* Common velocity, efforts add: the corners' springs act in parallel. */
  MUST(fb_bg_add_junction(bg, "J0", FB_BG_J1, 1, &err), &err);
  MUST(fb_bg_connect(bg, "bv", "v", "J0", &err), &err);
  fb_bg *c1 = corner(10.0, &err), *c2 = corner(20.0, &err);
  /* A fragment's labels of its components are kept through adoption,
   * where its element's name is prefixed. */
  const char *const spring[1] = {"front spring"};
  MUST(fb_bg_set_labels(c1, "k", spring, &err), &err);
  CHECK(fb_bg_set_labels(c1, "nothing", spring, &err) == FB_EMODEL);
  MUST(fb_bg_adopt(bg, &c1, "front", &err), &err);
  MUST(fb_bg_adopt(bg, &c2, "rear", &err), &err);
  CHECK(c1 == NULL && c2 == NULL);
  CHECK(fb_bg_find_element(bg, "front.k") >= 0 && fb_bg_find_element(bg, "rear.J") >= 0);
  const long fk = fb_bg_find_element(bg, "front.k"), rk = fb_bg_find_element(bg, "rear.k");
  CHECK(fk >= 0 && fb_bg_element_label(bg, (size_t)fk, 0) &&
        !strcmp(fb_bg_element_label(bg, (size_t)fk, 0), "front spring"));
  CHECK(fk >= 0 && !fb_bg_element_label(bg, (size_t)fk, 1));
  CHECK(rk >= 0 && !fb_bg_element_label(bg, (size_t)rk, 0));
  CHECK(fb_bg_find_bond(bg, "rear.bk") >= 0);
  /* Power leaves the junction into both corners' input ports. */
  MUST(fb_bg_connect(bg, "bf", "J0", "front.top", &err), &err);
  /* Wrong direction: power out of an input port. */
  CHECK(fb_bg_connect(bg, "bad", "rear.top", "J0", &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "'rear.top'") && strstr(err.msg, "'J0'") &&
        strstr(err.msg, "input (power in)"));
  MUST(fb_bg_connect(bg, "br", "J0", "rear.top", &err), &err);
  CHECK(fb_bg_connect(bg, "again", "J0", "rear.top", &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "already connected") != NULL);
  MUST(fb_bg_assign_causality(bg, &err), &err);
  CHECK(stroke_at(bg, "front.bk", "front.J"));
  /* Nesting: a fragment that re-exports an adopted fragment's port. */
  fb_bg *outer = NULL;
  MUST(fb_bg_new("outer", &outer, &err), &err);
  fb_bg *inner = corner(5.0, &err);
  MUST(fb_bg_adopt(outer, &inner, "in", &err), &err);
  CHECK(fb_bg_add_port(outer, "p", "in.top", FB_PORT_OUT, &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "opposite power direction") != NULL);
  /* Without an fb_err the failure is still a failure. */
  CHECK(fb_bg_add_port(outer, "p", "in.no_such_port", FB_PORT_IN, NULL) != FB_OK);
  MUST(fb_bg_add_port(outer, "p", "in.top", FB_PORT_IN, &err), &err);
  MUST(fb_bg_adopt(bg, &outer, "nest", &err), &err);
  MUST(add_const_source(bg, "v2", FB_BG_SF, 1.0, &err), &err);
  MUST(fb_bg_connect(bg, "bn", "v2", "nest.p", &err), &err);
  CHECK(fb_bg_find_element(bg, "nest.in.k") >= 0);
  MUST(fb_bg_assign_causality(bg, &err), &err);
  fb_bg_free(&bg);
}

static void test_twoports_and_composite(void)
{
  fb_err err;
  fb_err_clear(&err);
  fb_bg *bg = NULL;
  MUST(fb_bg_new("tp", &bg, &err), &err);
  MUST(add_const_source(bg, "E", FB_BG_SE, 1.0, &err), &err);
  MUST(fb_bg_add_tf(bg, "T", FB_BG_TF, 1, 2.0, &err), &err);
  MUST(add_scalar(bg, "m", FB_BG_I, 1.0, &err), &err);
  MUST(fb_bg_connect(bg, "b1", "E", "T.1", &err), &err);
  /* Reversed orientation on port 2 is refused by causality's checks. */
  MUST(fb_bg_connect(bg, "b2", "m", "T.2", &err), &err);
  CHECK(fb_bg_assign_causality(bg, &err) == FB_EMODEL);
  CHECK(strstr(err.msg, "TF 'T'") != NULL);
  fb_bg_free(&bg);

  /* A TF between the two ports of one 2-port I field: both ports want
   * integral causality, so the TF would get the effort from both sides. */
  MUST(fb_bg_new("tf_conflict", &bg, &err), &err);
  const size_t ones[2] = {1, 1};
  const double md[2] = {2.0, 3.0};
  fb_mat *mm = NULL;
  MUST(fb_mat_new_diag(2, md, &mm, &err), &err);
  MUST(fb_bg_add_field(bg, "I", FB_BG_I, 2, ones, &mm, &err), &err);
  MUST(fb_bg_add_tf(bg, "T", FB_BG_TF, 1, 2.0, &err), &err);
  MUST(fb_bg_connect(bg, "b1", "I.1", "T.1", &err), &err);
  MUST(fb_bg_connect(bg, "b2", "T.2", "I.2", &err), &err);
  CHECK(fb_bg_assign_causality(bg, &err) == FB_ECAUSAL);
  CHECK(strstr(err.msg, "TF 'T'") && strstr(err.msg, "'b1'") && strstr(err.msg, "'b2'"));
  CHECK(err.origin == FB_ORIGIN_ELEMENT &&
        (long)err.origin_index == fb_bg_find_element(bg, "T"));
  fb_bg_free(&bg);

  /* Composite: two scalar bonds stacked into one 2-dimensional multibond. */
  MUST(fb_bg_new("comp", &bg, &err), &err);
  const size_t parts[2] = {1, 1};
  MUST(fb_bg_add_composite(bg, "H", 2, parts, &err), &err);
  MUST(add_const_source(bg, "E1", FB_BG_SE, 1.0, &err), &err);
  MUST(add_const_source(bg, "E2", FB_BG_SE, 2.0, &err), &err);
  MUST(fb_bg_add_junction(bg, "J", FB_BG_J1, 2, &err), &err);
  MUST(fb_bg_connect(bg, "p1", "E1", "H.1", &err), &err);
  MUST(fb_bg_connect(bg, "p2", "E2", "H.2", &err), &err);
  MUST(fb_bg_connect(bg, "w", "H.whole", "J", &err), &err);
  CHECK(fb_bg_bond_dim(bg, (size_t)fb_bg_find_bond(bg, "w")) == 2);
  fb_mat *m = NULL;
  const double d[2] = {1.0, 2.0};
  const size_t two = 2;
  MUST(fb_mat_new_diag(2, d, &m, &err), &err);
  MUST(fb_bg_add_field(bg, "M", FB_BG_I, 1, &two, &m, &err), &err);
  MUST(fb_bg_connect(bg, "bm", "J", "M", &err), &err);
  MUST(fb_bg_assign_causality(bg, &err), &err);
  CHECK(stroke_at(bg, "w", "J"));
  CHECK(stroke_at(bg, "bm", "M"));
  fb_bg_free(&bg);
}

int main(void)
{
  test_msd_causality();
  test_derivative_causality();
  test_conflict();
  test_unconnected_and_dims();
  test_subsystems();
  test_twoports_and_composite();
  return check_report("test_bg");
}
