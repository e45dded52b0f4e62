/* SPDX-License-Identifier: BSD-3-Clause */
/* Ride-comfort metrics (flexbond/ride.h): the analytic Wk weighting
 * against the ISO 2631-1 table, the digital filter's steady-state gain
 * against its own frequency response and the analytic one, the metrics
 * of a pure sine against their closed forms, the absorbed power of sines
 * and of a broadband record against closed forms and Parseval, the
 * fb_result helper against the array function, and the error paths. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/ride.h"

#include "check.h"
#include "result_util.h"

static const double PI = 3.14159265358979323846;
static const double FS = 1000.0; /* Hz, the project's output rate */

/* ISO 2631-1:1997 Table 3, Wk weighting factors (the standard lists them
 * x 1000) at nominal one-third-octave band centres. */
static const double table_freq[] = {0.5, 1, 2, 4, 5, 8, 16, 31.5, 63};
static const double table_wk[] = {0.418, 0.482, 0.531, 0.967, 1.039,
                                  1.036, 0.768, 0.405, 0.186};
enum { TABLE_N = sizeof table_freq / sizeof table_freq[0] };

/* Relative frequency compression tan(x)/x - 1, x = pi f / fs, of a
 * bilinear transform (Oppenheim & Schafer, "Discrete-Time Signal
 * Processing", 3rd ed., sec. 7.2). */
static double warp(double f, double fs)
{
  const double x = PI * f / fs;
  return tan(x) / x - 1;
}

/* r.m.s. of x[k0..k1-1]. */
static double rms(const double *x, size_t k0, size_t k1)
{
  double s = 0;
  for (size_t k = k0; k < k1; ++k)
    s += x[k] * x[k];
  return sqrt(s / (double)(k1 - k0));
}

/* x[k] = amp sin(2 pi f k / fs), k < n. */
static double *sine(double amp, double f, double fs, size_t n)
{
  double *x = malloc(n * sizeof *x);
  for (size_t k = 0; x && k < n; ++k)
    x[k] = amp * sin(2 * PI * f * (double)k / fs);
  return x;
}

static void test_wk_table(void)
{
  /* The table has three significant digits (rounding <= 0.27 % of these
   * values) at nominal frequencies: 0.5 % relative, as adjacent bands
   * differ by more in most of the range. */
  for (int i = 0; i < TABLE_N; ++i)
    CHECK_NEAR(fb_ride_wk_magnitude(table_freq[i]), table_wk[i], 0.005 * table_wk[i]);
  /* The band-limiting high-pass blocks DC exactly. */
  CHECK(fb_ride_wk_magnitude(0) == 0);
  CHECK(isnan(fb_ride_wk_magnitude(-1)));
  CHECK(isnan(fb_ride_wk_digital_magnitude(10, 200)));
  CHECK(isnan(fb_ride_wk_digital_magnitude(600, FS)));
}

/* Filters a unit sine of f for 14 s and returns the r.m.s. gain over the
 * whole periods in [10 s, 14 s): by then the slowest transient (the 0.4
 * Hz high-pass, decay rate zeta w1 = 1.78 /s) is down to 2e-8. */
static double filtered_sine_gain(double f)
{
  const size_t n = (size_t)(14 * FS), k0 = (size_t)(10 * FS);
  /* 4 s hold 4 f periods only for f a multiple of 0.25 Hz: 31.5 and 0.5
   * Hz are (31.5 = 126 / 4), as are the others. */
  double *x = sine(1.0, f, FS, n);
  double gain = NAN;
  if (x && fb_ride_wk_filter(x, n, FS, x, NULL) == FB_OK)
    gain = rms(x, k0, n) * sqrt(2.0);
  free(x);
  return gain;
}

static void test_filter_gain(void)
{
  for (int i = 0; i < TABLE_N; ++i) {
    const double f = table_freq[i], gain = filtered_sine_gain(f);
    const double digital = fb_ride_wk_digital_magnitude(f, FS),
                 analytic = fb_ride_wk_magnitude(f);
    /* Recursion in time against the transfer function evaluated on the
     * unit circle: equal up to the 2e-8 transient left and rounding. */
    CHECK_NEAR(gain, digital, 1e-6 * digital);
    /* Against the analog |Wk|: the sections' gain errors are the warping
     * times their log-log slopes, which add up to less than 2 here. */
    CHECK_NEAR(gain, analytic, (2 * warp(f, FS) + 1e-6) * analytic);
  }
  /* The documented errors at 1 kHz (docs/ride-metrics.md): 0.75 % low at
   * 63 Hz, 3.3 % low at 100 Hz, to the 0.01 % printed. */
  CHECK_NEAR(fb_ride_wk_digital_magnitude(63, FS) / fb_ride_wk_magnitude(63) - 1, -0.0075,
             1e-4);
  CHECK_NEAR(fb_ride_wk_digital_magnitude(100, FS) / fb_ride_wk_magnitude(100) - 1, -0.033,
             5e-4);
}

/* A sine sampled at 1 kHz for 21 s, evaluated over [10, 20) (so every
 * jerk sample has both neighbours): 4 Hz puts whole periods in every 1 s
 * running window and a sample on every crest of the cosine (fs / f = 250
 * samples per period). */
static void test_sine_metrics(void)
{
  const double amp = 2.0, f = 4.0, t_eval = 10.0, w = 2 * PI * f, h = 1 / FS;
  const size_t n = (size_t)(21 * FS);
  double *a = sine(amp, f, FS, n);
  fb_ride_metrics m;
  fb_err err;
  CHECK(a && fb_ride_metrics_window(a, n, FS, 10, 20, NULL, &m, &err) == FB_OK);
  const double wk = fb_ride_wk_magnitude(f), a_w = wk * amp / sqrt(2.0);
  /* Filter error against the analog weighting at 4 Hz: 2 warp = 1.1e-4
   * (see test_filter_gain); rectangle sums of sin^2 and sin^4 over whole
   * periods are exact. */
  const double tol = 2 * warp(f, FS) + 1e-6;
  CHECK_NEAR(m.a_w_rms, a_w, tol * a_w);
  const double vdv = wk * amp * pow(3 * t_eval / 8, 0.25);
  CHECK_NEAR(m.vdv, vdv, tol * vdv);
  /* Against the digital filter's own gain the only error left is the
   * start-up transient, 2e-8 after 10 s (see filtered_sine_gain). */
  const double wk_digital = fb_ride_wk_digital_magnitude(f, FS);
  CHECK_NEAR(m.a_w_rms, wk_digital * amp / sqrt(2.0), 1e-6 * a_w);
  CHECK_NEAR(m.vdv, wk_digital * amp * pow(3 * t_eval / 8, 0.25), 1e-6 * vdv);
  /* Steady state: every 1 s window holds 4 whole periods. */
  CHECK_NEAR(m.mtvv, m.a_w_rms, 1e-6 * m.a_w_rms);
  /* The filtered sine's crest falls between samples by at most half a
   * step: the sampled peak is low by at most 1 - cos(pi f / fs) = 7.9e-5. */
  CHECK_NEAR(m.crest, sqrt(2.0), sqrt(2.0) * (1 - cos(PI * f / FS)) + 1e-6);
  CHECK(m.crest <= sqrt(2.0) * (1 + 1e-6));
  /* Central differences of a sine have amplitude w A sin(w h)/(w h)
   * exactly; their bias against w A is (w h)^2 / 6 = 1.05e-4. */
  const double jerk_amp = w * amp, sinc = sin(w * h) / (w * h);
  CHECK_NEAR(m.jerk_peak, jerk_amp * sinc, 1e-9 * jerk_amp);
  CHECK_NEAR(m.jerk_rms, jerk_amp * sinc / sqrt(2.0), 1e-9 * jerk_amp);
  CHECK_NEAR(m.jerk_peak, jerk_amp, (w * h) * (w * h) / 6 * 1.01 * jerk_amp);
  CHECK_NEAR(m.jerk_rms, jerk_amp / sqrt(2.0), (w * h) * (w * h) / 6 * 1.01 * jerk_amp);
  CHECK_NEAR(m.duration, t_eval, 1e-12);
  /* The built-in absorbed-power filter (test_ride_military.c): a sine's
   * power is K_d(f) A^2 / 2 in steady state. */
  CHECK_NEAR(m.absorbed_power, fb_ride_absorbed_digital_coef(f, FS) * amp * amp / 2,
             1e-9 * m.absorbed_power);
  free(a);
}

/* The whole record from rest: the filter's start-up transient counts, so
 * a_w differs from the steady value, but less than over the window it
 * decays in; MTVV, the largest 1 s value, is at least the steady value's
 * (the start-up overshoots). fb_ride_metrics_compute equals the window
 * [0, n / fs). */
static void test_compute_whole_record(void)
{
  const size_t n = (size_t)(20 * FS);
  double *a = sine(1.0, 4.0, FS, n);
  fb_ride_metrics whole, window;
  CHECK(a && fb_ride_metrics_compute(a, n, FS, NULL, &whole, NULL) == FB_OK);
  CHECK(a && fb_ride_metrics_window(a, n, FS, 0, 20, NULL, &window, NULL) == FB_OK);
  CHECK(whole.a_w_rms == window.a_w_rms && whole.mtvv == window.mtvv);
  CHECK(whole.vdv == window.vdv && whole.jerk_peak == window.jerk_peak);
  const double steady = fb_ride_wk_magnitude(4.0) / sqrt(2.0);
  /* Transient energy ~ (step response's ~1 m/s^2 over ~0.6 s) spread on
   * 20 s: within 3 % of the steady value. */
  CHECK_NEAR(whole.a_w_rms, steady, 0.03 * steady);
  CHECK(whole.mtvv >= steady * (1 - 1e-6));
  CHECK_NEAR(whole.duration, 20.0, 1e-12);
  free(a);
}

/* A K(f) table for the tests (not the published coefficients). */
static const double kf_freq[] = {1, 2, 4, 8, 16};
static const double kf_coef[] = {0.02, 0.05, 0.1, 0.08, 0.03};

static void test_absorbed_power_sines(void)
{
  const fb_ride_kf_table kf = {kf_freq, kf_coef, 5};
  const double amp = 1.5, t_eval = 10.0;
  const size_t n = (size_t)(t_eval * FS);
  double watts = -1;
  /* A sine on a tabulated frequency over whole periods is one spectral
   * line of mean square A^2 / 2: P = K(4) A^2 / 2; the DFT sums are
   * exact up to rounding (1e-12 relative). */
  double *a = sine(amp, 4.0, FS, n);
  CHECK(a && fb_ride_absorbed_power(a, n, FS, &kf, &watts, NULL) == FB_OK);
  CHECK_NEAR(watts, 0.1 * amp * amp / 2, 1e-10);
  free(a);
  /* Between points, K is log-log interpolated: at 5.6 Hz, K(4) (K(8) /
   * K(4))^(log2(5.6 / 4)). */
  a = sine(amp, 5.6, FS, n);
  CHECK(a && fb_ride_absorbed_power(a, n, FS, &kf, &watts, NULL) == FB_OK);
  const double k56 = 0.1 * pow(0.8, log2(5.6 / 4.0));
  CHECK_NEAR(watts, k56 * amp * amp / 2, 1e-10);
  free(a);
  /* Outside the table nothing is absorbed. */
  a = sine(amp, 30.0, FS, n);
  CHECK(a && fb_ride_absorbed_power(a, n, FS, &kf, &watts, NULL) == FB_OK);
  CHECK_NEAR(watts, 0, 1e-12);
  free(a);
  /* Through the metrics: the same value over the window [10, 20) of a
   * 20 s record. */
  a = sine(amp, 4.0, FS, 2 * n);
  fb_ride_opts opts;
  fb_ride_opts_default(&opts);
  opts.absorbed_kf = &kf;
  fb_ride_metrics m;
  CHECK(a && fb_ride_metrics_window(a, 2 * n, FS, 10, 20, &opts, &m, NULL) == FB_OK);
  CHECK_NEAR(m.absorbed_power, 0.1 * amp * amp / 2, 1e-10);
  free(a);
}

/* With K constant over every line (first line fs/n to Nyquist), the
 * absorbed power is K times the record's variance (Parseval), computed
 * here in the time domain; for n even and odd (the Nyquist line counts
 * once). The record is deterministic broadband noise plus a mean. */
static void test_absorbed_power_parseval(void)
{
  for (size_t n = 2000; n <= 2001; ++n) {
    double *a = malloc(n * sizeof *a);
    unsigned long state = 12345;
    double mean = 0;
    for (size_t k = 0; a && k < n; ++k) {
      state = (state * 1103515245UL + 12345UL) % 2147483648UL;
      a[k] = 0.7 + (double)state / 2147483648.0 - 0.5;
      mean += a[k] / (double)n;
    }
    double var = 0;
    for (size_t k = 0; a && k < n; ++k)
      var += (a[k] - mean) * (a[k] - mean) / (double)n;
    const double flat_freq[] = {0.1, FS / 2}, flat_coef[] = {0.25, 0.25};
    const fb_ride_kf_table kf = {flat_freq, flat_coef, 2};
    double watts = -1;
    CHECK(a && fb_ride_absorbed_power(a, n, FS, &kf, &watts, NULL) == FB_OK);
    /* n lines of O(n) sums each: rounding ~n eps relative. */
    CHECK_NEAR(watts, 0.25 * var, 1e-10 * var);
    free(a);
  }
}

/* A result with columns t (from 2 s at 1 kHz), "other" and driver_acc (a
 * sine), built by hand. */
static fb_result *make_result(size_t n, double t_first)
{
  const char *const names[] = {"t", "other", "driver_acc"}, *const units[] = {"s", "1",
                                                                              "m/s^2"};
  fb_result *r = test_result_new(n, 3, names, units);
  for (size_t k = 0; r && k < n; ++k) {
    double *row = r->data + 3 * k;
    row[0] = t_first + (double)k / FS;
    row[1] = 0;
    row[2] = 1.2 * sin(2 * PI * 3.0 * (double)k / FS);
  }
  return r;
}

static void test_result_helper(void)
{
  const size_t n = 15001;
  fb_result *r = make_result(n, 2.0);
  double *a = malloc(n * sizeof *a);
  CHECK(r && a);
  if (!r || !a) {
    free(a);
    fb_result_free(&r);
    return;
  }
  for (size_t k = 0; k < n; ++k)
    a[k] = fb_result_row(r, k)[2];
  fb_ride_metrics from_result, from_array;
  fb_err err;
  CHECK(fb_ride_metrics_result(r, "driver_acc", 7, 17, NULL, &from_result, &err) == FB_OK);
  CHECK(fb_ride_metrics_window(a, n, FS, 5, 15, NULL, &from_array, &err) == FB_OK);
  /* The same samples through the same code: equal up to the sample rate
   * recovered from the time column (1e-12 relative). */
  CHECK_NEAR(from_result.a_w_rms, from_array.a_w_rms, 1e-12);
  CHECK_NEAR(from_result.vdv, from_array.vdv, 1e-11);
  CHECK_NEAR(from_result.mtvv, from_array.mtvv, 1e-12);
  CHECK_NEAR(from_result.jerk_rms, from_array.jerk_rms, 1e-9);
  CHECK_NEAR(from_result.duration, 10.0, 1e-9);
  /* Missing column, irregular time step. */
  CHECK(fb_ride_metrics_result(r, "nope", 7, 17, NULL, &from_result, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "no output column 'nope'") != NULL);
  r->data[3 * 100] += 0.0004;
  CHECK(fb_ride_metrics_result(r, "driver_acc", 7, 17, NULL, &from_result, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "not uniformly sampled: step 100") != NULL);
  free(a);
  fb_result_free(&r);
}

static void test_errors(void)
{
  const size_t n = 3000;
  double *a = sine(1.0, 2.0, FS, n);
  fb_ride_metrics m;
  fb_err err;
  double aw[4];
  if (!a) {
    CHECK(a != NULL);
    return;
  }
  /* Too few samples for the 1 s running window. */
  CHECK(fb_ride_metrics_compute(a, 500, FS, NULL, &m, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "500 samples (0.5 s) are too few") != NULL);
  CHECK(fb_ride_wk_filter(a, 0, FS, aw, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "no samples") != NULL);
  /* Sample rate not positive, not finite, too low. */
  const double bad_rates[] = {0, -1000, NAN, 200};
  for (int i = 0; i < 4; ++i) {
    CHECK(fb_ride_metrics_compute(a, n, bad_rates[i], NULL, &m, &err) == FB_EINVAL);
    CHECK(strstr(err.msg, "is too low: the Wk weighting needs at least 400 Hz") != NULL);
  }
  CHECK(fb_ride_wk_filter(a, 4, 399.0, aw, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "399 Hz") != NULL);
  /* A NaN sample, named with its time. */
  a[1234] = NAN;
  CHECK(fb_ride_metrics_compute(a, n, FS, NULL, &m, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "sample 1234 (t = 1.234 s) is not finite") != NULL);
  a[1234] = 0;
  /* Window outside the record, empty window, running window too long. */
  CHECK(fb_ride_metrics_window(a, n, FS, 1, 4, NULL, &m, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "window [1, 4) s is not an interval inside the record [0, 3) s") !=
        NULL);
  CHECK(fb_ride_metrics_window(a, n, FS, 2, 2, NULL, &m, &err) == FB_EINVAL);
  fb_ride_opts opts;
  fb_ride_opts_default(&opts);
  opts.integration_time = 5;
  CHECK(fb_ride_metrics_compute(a, n, FS, &opts, &m, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "running r.m.s. window of 5 s (5000 samples)") != NULL);
  opts.integration_time = 0;
  CHECK(fb_ride_metrics_compute(a, n, FS, &opts, &m, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "integration time 0 s is not positive") != NULL);
  /* Malformed K(f) tables. */
  const double freq_down[] = {2, 1}, coef_ok[] = {1, 1}, freq_ok[] = {1, 2},
               coef_zero[] = {1, 0};
  const fb_ride_kf_table down = {freq_down, coef_ok, 2}, zero = {freq_ok, coef_zero, 2},
                         one = {freq_ok, coef_ok, 1};
  double watts;
  CHECK(fb_ride_absorbed_power(a, n, FS, &down, &watts, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "frequency 1 (1 Hz) is not positive and above") != NULL);
  CHECK(fb_ride_absorbed_power(a, n, FS, &zero, &watts, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "coefficient 1 (0) is not positive") != NULL);
  CHECK(fb_ride_absorbed_power(a, n, FS, &one, &watts, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "at least 2 points (got 1)") != NULL);
  CHECK(fb_ride_absorbed_power(a, n, -5, &one, &watts, &err) == FB_EINVAL);
  CHECK(strstr(err.msg, "sample rate -5 Hz is not positive") != NULL);
  free(a);
}

int main(void)
{
  test_wk_table();
  test_filter_gain();
  test_sine_metrics();
  test_compute_whole_record();
  test_absorbed_power_sines();
  test_absorbed_power_parseval();
  test_result_helper();
  test_errors();
  return check_report("test_ride");
}
