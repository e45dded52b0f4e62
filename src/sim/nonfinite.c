/* SPDX-License-Identifier: BSD-3-Clause */
/* Messages for non-finite values met while simulating (sim_internal.h):
 * what was not finite, where the value starts in the diagram
 * (fb_bd_explain_nonfinite), and what usually causes it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "sim/sim_internal.h"

static const char *hint(fb_bd_nonfinite_kind kind)
{
  switch (kind) {
  case FB_NONFINITE_VALUE:
  case FB_NONFINITE_JACOBIAN:
    return "a law or time function evaluated outside its domain: log or sqrt of a negative "
           "number, a division by zero";
  case FB_NONFINITE_STATE:
    return "the solution grew without bound: the model is unstable, or an input grows "
           "without bound";
  case FB_NONFINITE_NONE: break;
  }
  return "the values were finite when evaluated again: a law that does not return the same "
         "value for the same inputs?";
}

fb_bd_nonfinite_kind fb_sim_explain_nonfinite(fb_bd *bd, double t, const double *x,
                                              int jacobian, const char *what, char *buf,
                                              size_t size)
{
  char where[FB_SIM_NONFINITE_MAX];
  const fb_bd_nonfinite_kind kind =
      fb_bd_explain_nonfinite(bd, t, x, jacobian, where, sizeof where);
  if (kind)
    snprintf(buf, size, "%s; the non-finite value starts at %s; hint: %s", what, where,
             hint(kind));
  else if (fb_bd_last_error(bd)[0])
    snprintf(buf, size, "%s; evaluating the diagram again failed: %s", what,
             fb_bd_last_error(bd));
  else
    snprintf(buf, size, "%s; hint: %s", what, hint(kind));
  return kind;
}
