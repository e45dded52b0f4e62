/* SPDX-License-Identifier: BSD-3-Clause */
/* The stresses of System 2's hull over a run (src/vehicle/hull_stress.c,
 * docs/stresses.md "Over a run"): the shell elements' recovery
 * (flexbond/fem.h, fb_shell_stress) built once per vehicle and applied to
 * the hull coordinates a run recorded (fb_vehicle_motion). In modal
 * coordinates the recovery holds the stress modes S_e = D_e Phi of the
 * hull's basis, so a sample costs 6 m multiply-adds per element (m
 * coordinates) without forming the displacements; in nodal coordinates
 * it applies each element's D_e to its nodes' values. The stresses are
 * the total ones: the hull's coordinates at t = 0 (with
 * simulation.initial: static, its deflection under the vehicle's weight)
 * plus the run's change from them. */
#ifndef FLEXBOND_HULL_STRESS_H
#define FLEXBOND_HULL_STRESS_H

#include <stddef.h>

#include "flexbond/error.h"
#include "flexbond/fem.h"
#include "flexbond/vehicle.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fb_hull_stress fb_hull_stress;

/* The surface of a shell element a stress is at (fb_shell_stress_state's
 * top: z = +t/2, the side the element's normal points to). */
typedef enum fb_hull_surface {
  FB_HULL_SURFACE_TOP = 0,
  FB_HULL_SURFACE_BOTTOM = 1
} fb_hull_surface;
/* "top" or "bottom". */
const char *fb_hull_surface_name(fb_hull_surface s);

/* 1 if v's hull has shell elements whose stresses fb_hull_stress_new can
 * recover: System 2 on a mesh of shells; 0 for System 1 and for a hull
 * given as a superelement (hull.mesh.reduced), which has none. */
int fb_hull_stress_possible(const fb_vehicle *v);

/* The recovery of v's hull (System 2 with shells, fb_hull_stress_possible:
 * FB_EINVAL otherwise): its
 * elements' recovery matrices and, in modal coordinates, the stress modes
 * of its basis, formed here once. *out is new (fb_hull_stress_free) and
 * borrows v's hull mesh: v must outlive it. With v's
 * fb_vehicle_opts.threads 2 its peaks are tracked on two threads.
 * Errors as fb_shell_stress_new
 * and fb_shell_stress_modes. */
int fb_hull_stress_new(const fb_vehicle *v, fb_hull_stress **out, fb_err *err);
/* Accepts NULL and sets *hs to NULL. */
void fb_hull_stress_free(fb_hull_stress **hs);
size_t fb_hull_stress_nelements(const fb_hull_stress *hs);
/* The mesh the stresses are of (borrowed from the vehicle). */
const fb_mesh *fb_hull_stress_mesh(const fb_hull_stress *hs);

/* Every element's state at time t of the run m (a motion of the vehicle
 * hs was made of: FB_EINVAL if its hull's coordinates differ), from the
 * hull's coordinates interpolated linearly between samples
 * (fb_vehicle_motion_coords_at; stresses are linear in them, so the
 * stress components are the samples' interpolated), clamped to the
 * samples' span. states: nelements, the caller's. FB_ENOMEM. */
int fb_hull_stress_at(const fb_hull_stress *hs, const fb_vehicle_motion *m, double t,
                      fb_shell_stress_state *states, fb_err *err);

/* Planes a stress range is searched on: normals every 180 /
 * FB_HULL_STRESS_PLANES degrees in the element's plane. On a plane at
 * most 5 degrees from the worst, a proportional range of principal values
 * (d1, d2) shows d1 - (1 - cos 10 deg) (d1 - d2) / 2: 0.76 % less for a
 * uniaxial range, 1.5 % for pure shear. */
#define FB_HULL_STRESS_PLANES 18

/* Per element, over the samples of a run at or after t_from (s): the
 * peak von Mises stress (the larger surface's), the time and surface of
 * its first occurrence, and a stress range for fatigue, by a critical
 * plane search: per surface and plane the range (max - min over the
 * samples) of the normal stress on the plane, the largest of them. The
 * normal stress keeps its sign, so a reversal from tension to compression
 * is a full range, which von Mises (never negative) would fold in half;
 * a fixed plane does not jump as the signed absolute-maximum principal
 * stress does when the two principal stresses have opposite signs and
 * nearly equal magnitudes (shear), where its sign flips from one sample to
 * the next and doubles the range. The peak is over the samples the run
 * recorded (its output sampling): a peak between two samples is missed.
 * Arrays nelements long, owned by the struct. */
typedef struct fb_hull_stress_peaks {
  size_t nelements;
  size_t nsamples;          /* the samples taken (t >= t_from) */
  double *von_mises;        /* peak, Pa */
  double *time;             /* s */
  fb_hull_surface *surface; /* the peak's */
  double *range;            /* Pa */
  fb_hull_surface *range_surface;
} fb_hull_stress_peaks;
/* The peaks of run m (as fb_hull_stress_at) into *out (new:
 * fb_hull_stress_peaks_free). FB_EINVAL if no sample is at or after
 * t_from; FB_ENOMEM. */
int fb_hull_stress_peaks_of(const fb_hull_stress *hs, const fb_vehicle_motion *m, double t_from,
                            fb_hull_stress_peaks **out, fb_err *err);
/* Accepts NULL and sets *p to NULL. */
void fb_hull_stress_peaks_free(fb_hull_stress_peaks **p);
/* The indices of the n elements of largest peak von Mises stress,
 * largest first (ties: the lower index first), into order (n <=
 * nelements; the caller's). FB_ENOMEM. */
int fb_hull_stress_peaks_top(const fb_hull_stress_peaks *p, size_t n, size_t *order,
                             fb_err *err);

#ifdef __cplusplus
}
#endif

#endif
