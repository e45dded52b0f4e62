/* SPDX-License-Identifier: BSD-3-Clause */
/* Unit texts as SI base-unit exponents, for an FMU's UnitDefinitions
 * (FMI 3.0, section 2.4.3: a Unit's BaseUnit gives the exponents of
 * kg, m, s, A, K, mol, cd and rad, and value_SI = factor value + offset).
 * The symbols are the SI Brochure's (BIPM, 9th edition, 2019, tables 2
 * and 4) with the few non-SI units flexbond's files use (km/h, degrees). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fmu/fmu_internal.h"

typedef struct unit_symbol {
  const char *symbol;
  fmu_unit unit;
} unit_symbol;

/* Exponents in the order kg, m, s, A, K, mol, cd, rad; factor; offset. */
static const unit_symbol symbols[] = {
    {"1", {0, 0, 0, 0, 0, 0, 0, 0, 1.0, 0.0}},
    {"kg", {1, 0, 0, 0, 0, 0, 0, 0, 1.0, 0.0}},
    {"g", {1, 0, 0, 0, 0, 0, 0, 0, 1e-3, 0.0}},
    {"t", {1, 0, 0, 0, 0, 0, 0, 0, 1e3, 0.0}},
    {"m", {0, 1, 0, 0, 0, 0, 0, 0, 1.0, 0.0}},
    {"mm", {0, 1, 0, 0, 0, 0, 0, 0, 1e-3, 0.0}},
    {"km", {0, 1, 0, 0, 0, 0, 0, 0, 1e3, 0.0}},
    {"s", {0, 0, 1, 0, 0, 0, 0, 0, 1.0, 0.0}},
    {"min", {0, 0, 1, 0, 0, 0, 0, 0, 60.0, 0.0}},
    {"h", {0, 0, 1, 0, 0, 0, 0, 0, 3600.0, 0.0}},
    {"Hz", {0, 0, -1, 0, 0, 0, 0, 0, 1.0, 0.0}},
    {"N", {1, 1, -2, 0, 0, 0, 0, 0, 1.0, 0.0}},
    {"kN", {1, 1, -2, 0, 0, 0, 0, 0, 1e3, 0.0}},
    {"Pa", {1, -1, -2, 0, 0, 0, 0, 0, 1.0, 0.0}},
    {"MPa", {1, -1, -2, 0, 0, 0, 0, 0, 1e6, 0.0}},
    {"J", {1, 2, -2, 0, 0, 0, 0, 0, 1.0, 0.0}},
    {"W", {1, 2, -3, 0, 0, 0, 0, 0, 1.0, 0.0}},
    {"rad", {0, 0, 0, 0, 0, 0, 0, 1, 1.0, 0.0}},
    {"deg", {0, 0, 0, 0, 0, 0, 0, 1, 0.017453292519943295 /* pi / 180 */, 0.0}},
    {"K", {0, 0, 0, 0, 1, 0, 0, 0, 1.0, 0.0}},
    {"A", {0, 0, 0, 1, 0, 0, 0, 0, 1.0, 0.0}},
};

static const unit_symbol *find_symbol(const char *text, size_t len)
{
  for (size_t i = 0; i < sizeof symbols / sizeof *symbols; ++i)
    if (strlen(symbols[i].symbol) == len && strncmp(symbols[i].symbol, text, len) == 0)
      return &symbols[i];
  return NULL;
}

/* u *= symbol^power. */
static void multiply(fmu_unit *u, const fmu_unit *f, int power)
{
  u->kg += power * f->kg;
  u->m += power * f->m;
  u->s += power * f->s;
  u->A += power * f->A;
  u->K += power * f->K;
  u->mol += power * f->mol;
  u->cd += power * f->cd;
  u->rad += power * f->rad;
  u->factor *= pow(f->factor, power);
}

/* One factor "SYMBOL" or "SYMBOL^N" of text[0, len). */
static int parse_factor(const char *whole, const char *text, size_t len, int sign, fmu_unit *u,
                        fb_err *err)
{
  const char *caret = memchr(text, '^', len);
  const size_t symlen = caret ? (size_t)(caret - text) : len;
  long power = 1;
  if (caret) {
    char digits[8] = {0};
    const size_t nd = len - symlen - 1;
    char *end = NULL;
    if (nd == 0 || nd >= sizeof digits)
      return fb_err_set(err, FB_EINVAL, "unit '%s': a bad exponent", whole);
    memcpy(digits, caret + 1, nd);
    power = strtol(digits, &end, 10);
    if (*end || power == 0 || labs(power) > 8)
      return fb_err_set(err, FB_EINVAL, "unit '%s': a bad exponent", whole);
  }
  const unit_symbol *sym = find_symbol(text, symlen);
  if (!sym)
    return fb_err_set(err, FB_EINVAL, "unit '%s': no unit '%.*s'", whole, (int)symlen, text);
  multiply(u, &sym->unit, sign * (int)power);
  return FB_OK;
}

int fmu_unit_parse(const char *text, fmu_unit *u, fb_err *err)
{
  *u = (fmu_unit){0, 0, 0, 0, 0, 0, 0, 0, 1.0, 0.0};
  int sign = 1, rc = FB_OK;
  const char *p = text ? text : "";
  while (!rc && *p) {
    if (*p == ' ' || *p == '*') {
      ++p;
      continue;
    }
    if (*p == '/') {
      if (sign < 0)
        return fb_err_set(err, FB_EINVAL, "unit '%s': more than one '/'", text);
      sign = -1;
      ++p;
      continue;
    }
    const size_t len = strcspn(p, " */");
    rc = parse_factor(text, p, len, sign, u, err);
    p += len;
  }
  return rc;
}
