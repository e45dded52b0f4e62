/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond run --animate: each system's motion over the bump window as a
 * ParaView time series and an animated GIF (docs/animation.md).
 *
 * The frames are taken at a fixed rate from the run's samples (linear
 * between them: fb_vehicle_motion_at). The hull is System 2's finite-
 * element mesh, and for System 1 the same mesh moved rigidly (or, without
 * a finite-element hull, a plate over the scenario's points); the mounted
 * bodies and the wheels are placed as the mode pictures place them
 * (modes_flex.c): schematic, to the hull's size. Every displacement is
 * relative to the first frame (the window's start, where the vehicle
 * stands settled), so the pictures show what the bump does, not the
 * gravity settling before it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flexbond/escape.h"
#include "flexbond/io.h"
#include "flexbond/vehicle.h"

#include "cli.h"

/* A frame's drawing: its time, the hull's six displacements per node
 * and the parts' markers (bodies, then wheels). */
typedef struct anim_frame {
  double t;
  double *u;              /* 6 nnodes */
  double *attach_dz;      /* nattach */
  fb_plot_body *body;     /* nmounts */
  fb_plot_wheel *wheel;   /* ncorners */
  fb_vtu_marker *markers; /* nmounts + ncorners */
} anim_frame;

/* One system's animation. */
typedef struct anim {
  const fb_scenario *s;
  const fb_vehicle_motion *m;
  const fb_hull_stress *stress;  /* System 2's recovery, or NULL */
  fb_shell_stress_state *states; /* a frame's, nelements (owned) with stress */
  double *von_mises;             /* a frame's, Pa, nelements (owned) with stress */
  fb_mesh *own_mesh;             /* System 1's display mesh (owned), NULL in System 2 */
  const fb_mesh *mesh;
  double floor_z, extent; /* m: the hull's lowest node, its largest extent */
  anim_frame ref;         /* the vehicle at the first frame's time, as the run has it */
  anim_frame *frames;
  size_t nframes;
  double umax; /* m, the largest displacement of any frame */
  double warp; /* drawn per m of displacement */
} anim;

/* The plate System 1 is drawn as without a finite-element hull: one
 * quadrilateral over the corners, mounts and load points (at z = 0). */
static int plate_mesh(const fb_scenario *s, fb_mesh **out, fb_err *err)
{
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  const size_t na = fb_scenario_nattach(s);
  for (size_t a = 0; a < na + s->nload; ++a) {
    const double x = a < s->ncorners ? s->corner[a].x
                     : a < na        ? s->mount[a - s->ncorners].x
                                     : s->load_x[a - na];
    const double y = a < s->ncorners ? s->corner[a].y
                     : a < na        ? s->mount[a - s->ncorners].y
                                     : s->load_y[a - na];
    lo[0] = fmin(lo[0], x);
    hi[0] = fmax(hi[0], x);
    lo[1] = fmin(lo[1], y);
    hi[1] = fmax(hi[1], y);
  }
  /* Points on one line still make a plate: a tenth of the length wide. */
  const double pad = 0.05 * fmax(hi[0] - lo[0], hi[1] - lo[1]);
  int rc = fb_mesh_new(out, err);
  size_t nodes[4];
  const double xy[4][2] = {{lo[0] - pad, lo[1] - pad},
                           {hi[0] + pad, lo[1] - pad},
                           {hi[0] + pad, hi[1] + pad},
                           {lo[0] - pad, hi[1] + pad}};
  for (size_t k = 0; !rc && k < 4; ++k)
    rc = fb_mesh_add_node(*out, (long)k + 1, xy[k][0], xy[k][1], 0.0, &nodes[k], err);
  if (!rc)
    rc = fb_mesh_add_element(*out, 1, FB_ELEM_QUAD4, nodes, err);
  return rc;
}

/* System 1's display mesh: the finite-element hull's when the scenario
 * has one (its mesh alone, no eigen-solve), else the plate. */
static int rigid_mesh(const fb_scenario *s, fb_mesh **out, fb_err *err)
{
  if (!s->has_fe_hull)
    return plate_mesh(s, out, err);
  fb_fe_hull *fe = NULL;
  int rc = fb_vehicle_fe_hull(s, &fe, err);
  if (!rc) {
    *out = fe->mesh;
    fe->mesh = NULL;
  }
  fb_fe_hull_free(&fe);
  return rc;
}

static void mesh_bounds(anim *an)
{
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < fb_mesh_nnodes(an->mesh); ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = fmin(lo[k], fb_mesh_node_xyz(an->mesh, i)[k]);
      hi[k] = fmax(hi[k], fb_mesh_node_xyz(an->mesh, i)[k]);
    }
  an->floor_z = lo[2];
  an->extent = fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
}

int cli_animate_frame_count(const double window[2], double t_first, double t_last, double fps,
                            size_t *n, fb_err *err)
{
  const double t0 = fmax(window[0], t_first), t1 = fmin(window[1], t_last);
  const double count = t1 >= t0 ? floor((t1 - t0) * fps + 1e-9) + 1 : 0;
  if (!(count >= 1) || count > CLI_ANIMATE_MAX_FRAMES)
    return fb_err_set(err, FB_EINVAL,
                      "option '--animate-fps': %g frames/s over t = %g..%g s make %.0f "
                      "frames, not 1..%d",
                      fps, t0, t1, count, CLI_ANIMATE_MAX_FRAMES);
  *n = (size_t)count;
  return FB_OK;
}

/* The frame times: from the window's start every 1 / fps up to its end,
 * within the run. */
static int frame_times(const anim *an, const double window[2], double fps, fb_err *err,
                       size_t *n)
{
  const fb_vehicle_motion *m = an->m;
  return cli_animate_frame_count(window, m->samples[0],
                                 m->samples[(m->nsamples - 1) * m->width], fps, n, err);
}

static void frame_free(anim_frame *f)
{
  free(f->u);
  free(f->attach_dz);
  free(f->body);
  free(f->wheel);
  free(f->markers);
}

static void anim_free(anim *an)
{
  for (size_t k = 0; an->frames && k < an->nframes; ++k)
    frame_free(&an->frames[k]);
  frame_free(&an->ref);
  free(an->frames);
  free(an->states);
  free(an->von_mises);
  fb_mesh_free(&an->own_mesh);
}

/* Frame f at time t: the motion less ref's (none when ref is NULL),
 * then its parts placed as the mode pictures place them; the largest
 * displacement into an->umax. */
static int fill_frame(anim *an, anim_frame *f, double t, const anim_frame *ref, fb_err *err)
{
  const fb_scenario *s = an->s;
  const size_t nn = fb_mesh_nnodes(an->mesh), na = fb_scenario_nattach(s);
  const size_t nparts = s->nmounts + s->ncorners;
  double *dz = malloc((nparts + 1) * sizeof *dz); /* the bodies', then the wheels' */
  f->t = t;
  f->u = malloc(6 * nn * sizeof *f->u);
  f->attach_dz = malloc((na + 1) * sizeof *f->attach_dz);
  f->body = malloc((s->nmounts + 1) * sizeof *f->body);
  f->wheel = malloc((s->ncorners + 1) * sizeof *f->wheel);
  f->markers = malloc((nparts + 1) * sizeof *f->markers);
  int rc = dz && f->u && f->attach_dz && f->body && f->wheel && f->markers
               ? fb_vehicle_motion_at(an->m, an->mesh, t, f->u, f->attach_dz, dz,
                                      dz + s->nmounts, err)
               : fb_err_set(err, FB_ENOMEM, "out of memory for the animation");
  for (size_t i = 0; !rc && ref && i < 6 * nn; ++i)
    f->u[i] -= ref->u[i];
  for (size_t a = 0; !rc && ref && a < na; ++a)
    f->attach_dz[a] -= ref->attach_dz[a];
  for (size_t p = 0; !rc && ref && p < nparts; ++p)
    dz[p] -= ref->markers[p].dz;
  const double side = 0.05 * an->extent, radius = 0.07 * an->extent;
  for (size_t b = 0; !rc && b < s->nmounts; ++b) {
    f->body[b] =
        (fb_plot_body){{s->mount[b].x, s->mount[b].y, an->floor_z + 0.5 * side}, dz[b]};
    f->markers[b] =
        (fb_vtu_marker){{f->body[b].xyz[0], f->body[b].xyz[1], f->body[b].xyz[2]}, dz[b], 1};
    an->umax = fmax(an->umax, fabs(dz[b]));
  }
  for (size_t c = 0; !rc && c < s->ncorners; ++c) {
    const double wheel_dz = dz[s->nmounts + c];
    f->wheel[c] = (fb_plot_wheel){
        {s->corner[c].x, s->corner[c].y, an->floor_z}, f->attach_dz[c], wheel_dz};
    /* The wheel's centre: its rim's top half a radius below the hull. */
    f->markers[s->nmounts + c] = (fb_vtu_marker){
        {s->corner[c].x, s->corner[c].y, an->floor_z - 1.5 * radius}, wheel_dz, 2};
    an->umax = fmax(an->umax, fmax(fabs(wheel_dz), fabs(f->attach_dz[c])));
  }
  for (size_t i = 0; !rc && i < nn; ++i) {
    const double *u = f->u + 6 * i;
    an->umax = fmax(an->umax, sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]));
  }
  free(dz);
  return rc;
}

static int build(anim *an, const double window[2], const cli_animate_opts *o, fb_err *err)
{
  int rc = FB_OK;
  if (an->m->mesh)
    an->mesh = an->m->mesh;
  else if ((rc = rigid_mesh(an->s, &an->own_mesh, err)) == FB_OK)
    an->mesh = an->own_mesh;
  if (!rc && an->m->nsamples == 0)
    rc = fb_err_set(err, FB_EINVAL, "the run has no samples to animate");
  if (!rc) {
    mesh_bounds(an);
    rc = frame_times(an, window, o->fps, err, &an->nframes);
  }
  an->frames = rc ? NULL : calloc(an->nframes, sizeof *an->frames);
  if (!rc && !an->frames)
    rc = fb_err_set(err, FB_ENOMEM, "out of memory for %zu frames", an->nframes);
  /* The motion from the first frame's state on: the vehicle as the
   * first wheel reaches the bump, settled under its weight by then (the
   * paper's start switches gravity on at t = 0), so that the frames show
   * the crossing rather than the settling. */
  const double t0 = fmax(window[0], an->m->samples[0]);
  if (!rc)
    rc = fill_frame(an, &an->ref, t0, NULL, err);
  an->umax = 0.0;
  for (size_t k = 0; !rc && k < an->nframes; ++k)
    rc = fill_frame(an, &an->frames[k], t0 + (double)k / o->fps, &an->ref, err);
  /* The largest displacement drawn 0.08 L long, as in the mode pictures. */
  an->warp = o->scale > 0 ? o->scale : an->umax > 0 ? 0.08 * an->extent / an->umax : 1.0;
  return rc;
}

void cli_animation_file(fb_system sys, const char *ext, size_t frame, char *buf, size_t size)
{
  if (!strcmp(ext, "vtu"))
    snprintf(buf, size, "animation_system%d_%04zu.vtu", (int)sys, frame);
  else
    snprintf(buf, size, "animation_system%d.%s", (int)sys, ext);
}

/* ---- ParaView: a .vtu per frame and the .pvd collection naming them. */

/* The von Mises stress per element at frame f's time (the larger
 * surface's, the total stress), into an->von_mises. */
static int frame_stress(const anim *an, const anim_frame *f, fb_err *err)
{
  int rc = fb_hull_stress_at(an->stress, an->m, f->t, an->states, err);
  for (size_t e = 0; !rc && e < fb_hull_stress_nelements(an->stress); ++e)
    an->von_mises[e] = an->states[e].von_mises_max;
  return rc;
}

static int write_vtu(cli_outdir *od, const anim *an, size_t k, fb_err *err)
{
  const anim_frame *f = &an->frames[k];
  const fb_vtu_field fields[2] = {{"TimeValue", f->t}, {"warp_factor", an->warp}};
  const fb_vtu_cell_array cells = {"von_mises", an->von_mises};
  fb_vtu_frame frame = {.dof_values = f->u,
                        .warp = an->warp,
                        .markers = f->markers,
                        .nmarkers = an->s->nmounts + an->s->ncorners,
                        .fields = fields,
                        .nfields = 2,
                        .cell_arrays = an->stress ? &cells : NULL,
                        .ncell_arrays = an->stress ? 1 : 0};
  if (an->stress) {
    const int rc = frame_stress(an, f, err);
    if (rc)
      return rc;
  }
  fb_scenario_frame_offset(an->s, frame.origin);
  char name[64];
  cli_animation_file(an->m->sys, "vtu", k, name, sizeof name);
  char *path = cli_outdir_path(od, name, err);
  int rc = path ? fb_mesh_write_vtu_frame(an->mesh, &frame, path, err) : err->code;
  if (!rc)
    return cli_outdir_keep(od, path, err);
  free(path);
  return rc;
}

/* ParaView's collection format (VTK File Formats, "PVD"): one DataSet
 * per frame with its time. */
static void write_pvd(FILE *fp, const void *ctx)
{
  const anim *an = ctx;
  fputs("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
        "  <Collection>\n",
        fp);
  for (size_t k = 0; k < an->nframes; ++k) {
    char name[64];
    cli_animation_file(an->m->sys, "vtu", k, name, sizeof name);
    fprintf(fp, "    <DataSet timestep=\"%.17g\" part=\"0\" file=\"", an->frames[k].t);
    fb_xml_write_attr(fp, name);
    fputs("\"/>\n", fp);
  }
  fputs("  </Collection>\n</VTKFile>\n", fp);
}

/* ---- The GIF. */

static int write_gif(cli_outdir *od, const anim *an, const cli_animate_opts *o, fb_err *err)
{
  const fb_scenario *s = an->s;
  fb_plot_mode *pics = calloc(an->nframes, sizeof *pics);
  char(*subtitle)[200] = calloc(an->nframes, sizeof *subtitle);
  char title[200], name[64], road[160];
  int rc = pics && subtitle ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  /* The road's own words (a file's name among them: gnuplot quotes the
   * title). */
  fb_road_phrase(s->road_type, &s->road, road, sizeof road);
  snprintf(title, sizeof title, "%s %s", cli_system_label(an->m->sys), road);
  for (size_t k = 0; !rc && k < an->nframes; ++k) {
    const anim_frame *f = &an->frames[k];
    snprintf(subtitle[k], sizeof subtitle[k],
             "t = %.3f s; displacements from t = %.3f s drawn %.3g times; grey: at t = %.3f s",
             f->t, an->frames[0].t, an->warp, an->frames[0].t);
    pics[k] = (fb_plot_mode){.mesh = an->mesh,
                             .shape = f->u,
                             .largest_drawn = an->warp * an->umax,
                             .body = f->body,
                             .nbodies = s->nmounts,
                             .body_side = 0.05 * an->extent,
                             .wheel = f->wheel,
                             .nwheels = s->ncorners,
                             .wheel_radius = 0.07 * an->extent,
                             .title = title,
                             .subtitle = subtitle[k],
                             .colour_label = "displacement [m]"};
    fb_scenario_frame_offset(s, pics[k].origin);
    /* A still vehicle is drawn at rest, with any positive length. */
    if (!(pics[k].largest_drawn > 0))
      pics[k].largest_drawn = 1.0;
  }
  cli_animation_file(an->m->sys, "gif", 0, name, sizeof name);
  char *path = rc ? NULL : cli_outdir_path(od, name, err);
  if (!rc)
    rc = path ? fb_plot_mode_gif(pics, an->nframes, 1.0 / o->fps, path, err) : err->code;
  if (!rc)
    rc = cli_outdir_keep(od, path, err);
  else
    free(path);
  free(pics);
  free(subtitle);
  return rc;
}

int cli_write_animation(cli_outdir *od, const fb_scenario *s, const fb_vehicle_motion *m,
                        const fb_hull_stress *stress, const double window[2],
                        const cli_animate_opts *o, cli_animation_info *info, fb_err *err)
{
  anim an = {.s = s, .m = m, .stress = stress};
  int rc = build(&an, window, o, err);
  if (!rc && stress) {
    const size_t ne = fb_hull_stress_nelements(stress);
    an.states = malloc((ne ? ne : 1) * sizeof *an.states);
    an.von_mises = malloc((ne ? ne : 1) * sizeof *an.von_mises);
    if (!an.states || !an.von_mises)
      rc = fb_err_set(err, FB_ENOMEM, "out of memory for the stresses of %zu elements", ne);
  }
  for (size_t k = 0; !rc && k < an.nframes; ++k)
    rc = write_vtu(od, &an, k, err);
  if (!rc) {
    char name[64];
    cli_animation_file(m->sys, "pvd", 0, name, sizeof name);
    rc = cli_outdir_write(od, name, write_pvd, &an, err);
  }
  /* A superelement (a reduced hull) has no surface to draw: its VTU
   * frames hold its nodes' motion, and no GIF is made (info->gif). */
  const int gif = o->gif && fb_mesh_nelements(an.mesh) > 0;
  if (!rc && gif)
    rc = write_gif(od, &an, o, err);
  if (!rc) {
    info->nframes = an.nframes;
    info->t0 = an.frames[0].t;
    info->t1 = an.frames[an.nframes - 1].t;
    info->warp = an.warp;
    info->umax = an.umax;
    info->gif = gif;
  }
  anim_free(&an);
  return rc;
}
