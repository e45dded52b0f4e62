/* SPDX-License-Identifier: BSD-3-Clause */
/* ISO 8608:2016 random road profiles as sums of harmonics with random
 * phases (docs/roads.md).
 *
 * The standard classifies roads by their one-sided displacement PSD
 * Gd(n) = Gd(n0) (n / n0)^-w, n0 = 0.1 cycles/m, w = 2, with the class's
 * geometric-mean Gd(n0) 16e-6 m^3 for class A, four times more for each
 * class after it (ISO 8608:2016, its road classification table). A track is generated
 * as z(s) = sum_k a_k cos(2 pi n_k s + p_k) over the midpoints n_k of
 * equal sub-bands of width dn of [n_min, n_max], with a_k^2 / 2 =
 * Gd(n_k) dn, so the variance of each harmonic is the PSD's content of its
 * sub-band (the method of Shinozuka & Jan, J. Sound Vib. 25(1), 1972,
 * with deterministic amplitudes). */
#include <math.h>

#include "flexbond/road.h"

#include "road/road_internal.h"

static const double TWO_PI = 6.28318530717958647693;
static const double ISO_N0 = 0.1;        /* cycles/m */
static const double ISO_GD0_A = 16.0e-6; /* m^3, class A */

void fb_road_iso8608_defaults(fb_road_iso8608_params *p)
{
  p->road_class = 'C';
  p->seed = 1;
  p->n_min = 0.011; /* ISO 8608's band for classification */
  p->n_max = 2.83;
  p->nharmonics = 1024;
  p->fade_length = 0.0;
  p->gd0 = 0.0;
}

int fb_road_iso8608_gd0(char road_class, double *gd0, fb_err *err)
{
  const char upper =
      (char)(road_class >= 'a' && road_class <= 'h' ? road_class - 'a' + 'A' : road_class);
  if (upper < 'A' || upper > 'H')
    return fb_err_set(err, FB_EINVAL,
                      "ISO 8608 road class '%c' (code %d): expected a letter A to H",
                      road_class >= 32 && road_class < 127 ? road_class : '?', road_class);
  *gd0 = ISO_GD0_A * pow(4.0, (double)(upper - 'A'));
  return FB_OK;
}

int fb_road_iso8608_params_gd0(const fb_road_iso8608_params *p, double *gd0, fb_err *err)
{
  if (p->gd0 > 0.0 && isfinite(p->gd0)) {
    *gd0 = p->gd0;
    return FB_OK;
  }
  if (p->gd0 != 0.0)
    return fb_err_set(err, FB_EINVAL, "ISO 8608 road: Gd(n0) must be > 0 m^3 (got %g)", p->gd0);
  return fb_road_iso8608_gd0(p->road_class, gd0, err);
}

/* The integral of Gd(n) = Gd(n0) (n / n0)^-2 over [n_min, n_max] is
 * Gd(n0) n0^2 (1 / n_min - 1 / n_max): the variance of a track whose
 * one-sided PSD it is (ISO 8608:2016, the PSD's definition: its integral
 * over a band is the mean square of the profile in that band). */
double fb_road_iso8608_rms_gd0(double rms, double n_min, double n_max)
{
  return rms * rms / (ISO_N0 * ISO_N0 * (1.0 / n_min - 1.0 / n_max));
}

char fb_road_iso8608_class_of(double gd0)
{
  const double k = round(log(gd0 / ISO_GD0_A) / log(4.0));
  return (char)('A' + (k < 0 ? 0 : k > 7 ? 7 : (int)k));
}

/* ---- Random numbers: xoshiro256** (Blackman & Vigna, "Scrambled linear
 * pseudorandom number generators", ACM TOMS 47(4), 2021), its state seeded
 * from the 64-bit seed by splitmix64 (Steele, Lea & Flood, OOPSLA 2014),
 * as its authors recommend. Local state: no global generator. */

typedef struct rng {
  uint64_t s[4];
} rng;

static uint64_t splitmix64(uint64_t *x)
{
  uint64_t z = (*x += UINT64_C(0x9e3779b97f4a7c15));
  z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
  z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
  return z ^ (z >> 31);
}

static uint64_t rotl(uint64_t x, int k)
{
  return (x << k) | (x >> (64 - k));
}

static void rng_seed(rng *r, uint64_t seed)
{
  for (int i = 0; i < 4; ++i)
    r->s[i] = splitmix64(&seed);
}

static uint64_t rng_next(rng *r)
{
  uint64_t *s = r->s;
  const uint64_t result = rotl(s[1] * 5, 7) * 9;
  const uint64_t t = s[1] << 17;
  s[2] ^= s[0];
  s[3] ^= s[1];
  s[1] ^= s[2];
  s[0] ^= s[3];
  s[2] ^= t;
  s[3] = rotl(s[3], 45);
  return result;
}

/* Uniform in [0, 1) with 53 random bits. */
static double rng_uniform(rng *r)
{
  return (double)(rng_next(r) >> 11) * 0x1.0p-53;
}

static int check_params(const fb_road_iso8608_params *p, double *gd0, fb_err *err)
{
  int rc = fb_road_iso8608_params_gd0(p, gd0, err);
  if (rc)
    return rc;
  if (!(isfinite(p->n_min) && p->n_min > 0.0))
    return fb_err_set(err, FB_EINVAL, "ISO 8608 road: n_min must be > 0 cycles/m (got %g)",
                      p->n_min);
  if (!(isfinite(p->n_max) && p->n_max > p->n_min))
    return fb_err_set(err, FB_EINVAL,
                      "ISO 8608 road: n_max must be > n_min = %g cycles/m (got %g)", p->n_min,
                      p->n_max);
  if (p->nharmonics < 1 || p->nharmonics > FB_ROAD_ISO8608_MAX_HARMONICS)
    return fb_err_set(err, FB_EINVAL, "ISO 8608 road: nharmonics must be in 1 .. %zu (got %zu)",
                      FB_ROAD_ISO8608_MAX_HARMONICS, p->nharmonics);
  if (!(isfinite(p->fade_length) && p->fade_length >= 0.0))
    return fb_err_set(err, FB_EINVAL, "ISO 8608 road: fade_length must be >= 0 m (got %g)",
                      p->fade_length);
  return FB_OK;
}

/* Fills one track's A_k cos(phi_k) and A_k sin(phi_k) arrays, drawing n
 * phases phi_k from r; harmonic k is at n_k = n_min + (k + 1/2) dn with
 * amplitude A_k = sqrt(2 Gd(n_k) dn). */
static void fill_track(const fb_road_iso8608_params *p, double gd0, rng *r, double *data)
{
  const size_t n = p->nharmonics;
  const double dn = (p->n_max - p->n_min) / (double)n;
  for (size_t k = 0; k < n; ++k) {
    const double nk = p->n_min + ((double)k + 0.5) * dn;
    const double ratio = ISO_N0 / nk;
    const double amplitude = sqrt(2.0 * gd0 * ratio * ratio * dn);
    const double phase = TWO_PI * rng_uniform(r);
    data[k] = amplitude * cos(phase);
    data[n + k] = amplitude * sin(phase);
  }
}

int fb_road_new_iso8608(const fb_road_iso8608_params *p, fb_road **out, fb_err *err)
{
  if (!p || !out)
    return fb_err_set(err, FB_EINVAL, "ISO 8608 road: NULL argument");
  *out = NULL;
  double gd0 = 0.0;
  int rc = check_params(p, &gd0, err);
  if (rc)
    return rc;
  const double dn = (p->n_max - p->n_min) / (double)p->nharmonics;
  const road_track track = {ROAD_HARMONICS,
                            p->nharmonics,
                            {p->fade_length, TWO_PI * (p->n_min + 0.5 * dn), TWO_PI * dn}};
  rc = road_alloc(&track, &track, out, err);
  if (rc)
    return rc;
  rng r;
  rng_seed(&r, p->seed);
  fill_track(p, gd0, &r, (*out)->data[FB_ROAD_LEFT]);
  fill_track(p, gd0, &r, (*out)->data[FB_ROAD_RIGHT]);
  for (int k = 0; k < FB_ROAD_NTRACKS; ++k)
    (*out)->origin[k] = (road_origin){1, *p, k};
  return FB_OK;
}
