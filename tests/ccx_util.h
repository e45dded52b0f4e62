/* SPDX-License-Identifier: BSD-3-Clause */
/* Helpers of the tests that solve a deck with CalculiX (`ccx`, Debian
 * calculix-ccx) and compare its shell stresses with flexbond's
 * (test_shell_stress_ccx.c, test_hull_stress_ccx.c): whether ccx is
 * there, a run in the test's private directory, and the stresses of the
 * .dat file's *EL PRINT S reduced to a shell's surfaces.
 *
 * CalculiX expands each shell into a solid one element thick: an S4 into
 * a C3D8I with 2 x 2 x 2 integration points, points 1-4 in the layer
 * zeta = -1/sqrt(3) (the side opposite the normal), 5-8 in the layer
 * +1/sqrt(3); an S3 into a C3D6 with one point at the triangle's centroid
 * in each layer, 1 below, 2 above. ccx 2.20 prints an expanded shell's
 * stresses in the element's own axes, which are flexbond's
 * (fb_shell_stress_axes: x along edge 1-2, z the normal): measured on the
 * hull of test_hull_stress_ccx, whose side walls' in-plane shear is the
 * printed sxy, not sxz (read as global components, the twist's plate
 * interiors would differ from flexbond's by 56 % rms instead of 1.5 %).
 * The in-plane mean of a layer's points is its value at the element
 * centre (exact for a field bilinear in xi, eta); the stress is linear
 * through the thickness, so the surfaces are m +- (s_top_layer -
 * s_bottom_layer) sqrt(3) / 2 with m the layers' mean. */
#ifndef FLEXBOND_TEST_CCX_UTIL_H
#define FLEXBOND_TEST_CCX_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/fem.h"

#include "tmpdir.h"

/* Integration points kept per element (an S4's eight; an S3 uses two). */
enum { CCX_POINTS = 8 };

/* 1 if ccx is on the PATH; else 0 after telling why the test (name) is
 * skipped. */
static inline int ccx_available(const char *name)
{
  if (system("command -v ccx >/dev/null 2>&1") == 0)
    return 1;
  fprintf(stderr, "%s: skipped: no ccx on the PATH (Debian: apt-get install calculix-ccx)\n",
          name);
  return 0;
}

/* Runs ccx on job.inp in the test's private directory (its output in
 * job.log there): 1 if it ran and exited with 0; else 0, with the log's
 * end on stderr. */
static inline int ccx_run(const char *job)
{
  char cmd[2 * TEST_PATH_MAX];
  const int n =
      snprintf(cmd, sizeof cmd, "cd '%s' && ccx -i %s >%s.log 2>&1", test_tmpdir(), job, job);
  if (n < 0 || (size_t)n >= sizeof cmd)
    return 0;
  const int status = system(cmd);
  if (status == 0)
    return 1;
  /* The directory goes when the test ends: the log's end goes to stderr. */
  fprintf(stderr, "ccx -i %s failed (status %d); the end of its output:\n", job, status);
  if (snprintf(cmd, sizeof cmd, "tail -n 8 '%s/%s.log' >&2", test_tmpdir(), job) <
          (int)sizeof cmd &&
      system(cmd) != 0)
    fprintf(stderr, "(no output)\n");
  return 0;
}

/* Reads a .dat file's stress lines (elem, point, sxx syy szz sxy sxz
 * syz) into s (per element index of m, CCX_POINTS points x 6 components).
 * Returns the lines read. */
static inline size_t ccx_read_stresses(const char *path, const fb_mesh *m, double *s)
{
  FILE *fp = fopen(path, "r");
  char line[512];
  size_t nread = 0;
  if (!fp)
    return 0;
  while (fgets(line, sizeof line, fp)) {
    long elem, point;
    double v[6];
    if (sscanf(line, "%ld %ld %lf %lf %lf %lf %lf %lf", &elem, &point, v, v + 1, v + 2, v + 3,
               v + 4, v + 5) != 8)
      continue;
    const long e = fb_mesh_find_element_id(m, elem);
    if (e < 0 || point < 1 || point > CCX_POINTS)
      continue;
    memcpy(s + ((size_t)e * CCX_POINTS + (size_t)(point - 1)) * 6, v, sizeof v);
    ++nread;
  }
  fclose(fp);
  return nread;
}

/* The integration points ccx prints for element e of m. */
static inline size_t ccx_points(const fb_mesh *m, size_t e)
{
  return fb_mesh_element_type(m, e) == FB_ELEM_QUAD4 ? 8 : 2;
}

/* CalculiX's surface stresses (xx, yy, xy) of element e of m in the
 * element's axes at the top (the normal's side) and bottom, from its
 * integration points (s: ccx_read_stresses). */
static inline void ccx_surfaces(const double *s, const fb_mesh *m, size_t e, double *top,
                                double *bottom)
{
  static const size_t comp[3] = {0, 1, 3}; /* sxx syy sxy */
  const size_t npts = ccx_points(m, e), half = npts / 2;
  for (size_t k = 0; k < 3; ++k) {
    double low = 0.0, high = 0.0;
    for (size_t p = 0; p < half; ++p) {
      low += s[(e * CCX_POINTS + p) * 6 + comp[k]] / (double)half;
      high += s[(e * CCX_POINTS + half + p) * 6 + comp[k]] / (double)half;
    }
    const double mean = (low + high) / 2.0, slope = (high - low) * sqrt(3.0) / 2.0;
    top[k] = mean + slope;
    bottom[k] = mean - slope;
  }
}

/* The plane-stress von Mises stress of (sigma_x, sigma_y, tau_xy). */
static inline double ccx_von_mises(const double *s)
{
  return sqrt(s[0] * s[0] - s[0] * s[1] + s[1] * s[1] + 3.0 * s[2] * s[2]);
}

#endif
