/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond modes --system flexible: modal analysis of System 2 (the
 * paper's Figs. 3 and 4): the free-free hull's modes and the whole
 * undamped vehicle's, printed and, with -o DIR, written as
 *   DIR/hull_modes.csv   mode,frequency_hz,kind (rigid | elastic)
 *   DIR/modes.csv        mode,frequency_hz,description
 *   DIR/mode_NN.vtu      each vehicle mode's hull displacement (ParaView)
 *   DIR/mode_NN.png      modes 1, 2, 8 and 10: the hull, the mounted bodies
 *                        (cubes) and the wheels at rest and displaced
 *                        (cli_write_mode_pictures, which run uses too). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/escape.h"
#include "flexbond/io.h"
#include "flexbond/vehicle.h"

#include "cli.h"

/* The hull's free-free modes listed (the six rigid-body ones and the 24
 * lowest elastic ones) and the vehicle's. */
enum { HULL_MODES = 30, VEHICLE_MODES = 20 };

typedef struct flex_modes {
  const fb_scenario *s;
  const fb_fe_hull *hull;
  const double *hull_freq; /* the free-free modes the vehicle's hull solved */
  size_t nhull, nrigid;
  fb_mode_set *vehicle;
} flex_modes;

static void write_hull_csv(FILE *fp, const void *ctx)
{
  const flex_modes *fm = ctx;
  fputs("mode,frequency_hz,kind\n", fp);
  for (size_t k = 0; k < fm->nhull; ++k)
    fprintf(fp, "%zu,%.10g,%s\n", k + 1, fm->hull_freq[k],
            k < fm->nrigid ? "rigid" : "elastic");
}

static void write_modes_csv(FILE *fp, const void *ctx)
{
  const flex_modes *fm = ctx;
  fputs("mode,frequency_hz,description\n", fp);
  for (size_t k = 0; k < fm->vehicle->nmodes; ++k) {
    fprintf(fp, "%zu,%.10g,", k + 1, fm->vehicle->freq_hz[k]);
    /* A text field, quoted as it always was (RFC 4180: flexbond/escape.h). */
    fb_csv_write_field(fp, fm->vehicle->description[k], FB_CSV_QUOTE_ALWAYS | FB_CSV_TEXT);
    fputc('\n', fp);
  }
}

size_t cli_pictured_modes(const fb_scenario *s, const fb_mode_set *ms, size_t *out, size_t max)
{
  if (!s->npictured_modes)
    return fb_mode_set_pictured(ms, out, max);
  size_t n = 0;
  for (size_t i = 0; i < s->npictured_modes && n < max; ++i) {
    const size_t k = (size_t)s->pictured_modes[i] - 1;
    if (k < ms->nmodes)
      out[n++] = k;
  }
  return n;
}

int cli_picture_modes_option(const char *cmd, const char *list, cli_mode_list *out)
{
  size_t n = 0;
  const char *p = list;
  while (*p) {
    char *end = NULL;
    errno = 0;
    const unsigned long m = *p >= '0' && *p <= '9' ? strtoul(p, &end, 10) : 0;
    if (m < 1 || errno || m > 1000000 || n == FB_PICTURED_MODES_MAX || (*end && *end != ','))
      return cli_usage_error(cmd,
                             "option '--picture-modes' needs up to %d mode numbers from 1, "
                             "separated by commas (got '%s')",
                             (int)FB_PICTURED_MODES_MAX, list);
    out->mode[n++] = (double)m;
    p = *end ? end + 1 : end;
  }
  if (n == 0)
    return cli_usage_error(cmd, "option '--picture-modes' needs a mode number (got '%s')",
                           list);
  out->n = n;
  return CLI_EXIT_OK;
}

void cli_mode_list_apply(const cli_mode_list *l, fb_scenario *s)
{
  if (!l->n)
    return;
  for (size_t i = 0; i < l->n; ++i)
    s->pictured_modes[i] = l->mode[i];
  s->npictured_modes = l->n;
}

void cli_mode_picture_name(size_t mode, char *buf, size_t size)
{
  snprintf(buf, size, "mode_%02zu.png", mode);
}

/* The picture's parts, drawn to the hull's size: its largest extent L
 * (m). The largest displacement is drawn 0.08 L long, which makes a mode
 * plain and leaves the hull recognisable; a body is a cube of 0.05 L
 * resting on its attachment point, a wheel a circle of radius 0.07 L
 * (schematic: the model knows the wheel's mass, not its size). */
typedef struct mode_parts {
  fb_plot_body *body;
  fb_plot_wheel *wheel;
  double extent;
} mode_parts;

static double mesh_extent(const fb_mesh *m)
{
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < fb_mesh_nnodes(m); ++i)
    for (int k = 0; k < 3; ++k) {
      lo[k] = fmin(lo[k], fb_mesh_node_xyz(m, i)[k]);
      hi[k] = fmax(hi[k], fb_mesh_node_xyz(m, i)[k]);
    }
  return fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
}

/* The vertical displacement of attachment point a in the shape v: its
 * coupling row, as the hull's transformer reads it. */
static double attach_dz(const fb_fe_hull *hull, size_t a, const double *v)
{
  const fb_hull_coupling *c = &hull->attach_coupling[a];
  double dz = 0.0;
  for (size_t i = 0; i < c->n; ++i)
    dz += c->w[i] * v[c->dof[i]];
  return dz;
}

/* Bodies and wheels of mode shape v (hull, then the mounted bodies' and
 * the wheels' vertical motion: fb_vehicle_structural_modes). */
static void fill_parts(const fb_scenario *s, const fb_fe_hull *hull, const double *v,
                       mode_parts *mp)
{
  const size_t nh = 6 * fb_mesh_nnodes(hull->mesh);
  const double side = 0.05 * mp->extent;
  for (size_t b = 0; b < s->nmounts; ++b) {
    const size_t a = s->ncorners + b;
    const double z = fb_mesh_node_xyz(hull->mesh, hull->attach_node[a])[2];
    mp->body[b] = (fb_plot_body){{s->mount[b].x, s->mount[b].y, z + 0.5 * side}, v[nh + b]};
  }
  for (size_t c = 0; c < s->ncorners; ++c) {
    const double z = fb_mesh_node_xyz(hull->mesh, hull->attach_node[c])[2];
    mp->wheel[c] = (fb_plot_wheel){
        {s->corner[c].x, s->corner[c].y, z}, attach_dz(hull, c, v), v[nh + s->nmounts + c]};
  }
}

int cli_write_mode_pictures(cli_outdir *od, const fb_scenario *s, const fb_fe_hull *hull,
                            const fb_mode_set *ms, fb_err *err)
{
  /* A superelement (a reduced hull) has no surface to draw: no pictures,
   * which the report says (report.c). */
  if (fb_mesh_nelements(hull->mesh) == 0)
    return FB_OK;
  mode_parts mp = {malloc((s->nmounts + 1) * sizeof *mp.body),
                   malloc((s->ncorners + 1) * sizeof *mp.wheel), mesh_extent(hull->mesh)};
  int rc = mp.body && mp.wheel ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  size_t pictured[CLI_MAX_PICTURED_MODES];
  const size_t npictured = cli_pictured_modes(s, ms, pictured, CLI_MAX_PICTURED_MODES);
  for (size_t i = 0; !rc && i < npictured; ++i) {
    const size_t k = pictured[i];
    const double *v = ms->shapes + k * ms->ndof;
    fill_parts(s, hull, v, &mp);
    char name[32], title[160], subtitle[200];
    cli_mode_picture_name(k + 1, name, sizeof name);
    snprintf(title, sizeof title, "System 2, mode %zu: %.3f Hz, %s", k + 1, ms->freq_hz[k],
             ms->description[k]);
    const double drawn = 0.08 * mp.extent;
    snprintf(subtitle, sizeof subtitle,
             "shape normalised to a largest hull or body translation of 1; the largest "
             "displacement drawn %.2f m long; grey: at rest",
             drawn);
    fb_plot_mode pic = {.mesh = hull->mesh,
                        .shape = v,
                        .largest_drawn = drawn,
                        .body = mp.body,
                        .nbodies = s->nmounts,
                        .body_side = 0.05 * mp.extent,
                        .wheel = mp.wheel,
                        .nwheels = s->ncorners,
                        .wheel_radius = 0.07 * mp.extent,
                        .title = title,
                        .subtitle = subtitle};
    fb_scenario_frame_offset(s, pic.origin);
    char *path = cli_outdir_path(od, name, err);
    rc = path ? fb_plot_mode_png(&pic, path, err) : err->code;
    if (!rc)
      rc = cli_outdir_keep(od, path, err);
    else
      free(path);
  }
  free(mp.body);
  free(mp.wheel);
  return rc;
}

/* Writes every mode's VTU and the pictured modes' PNGs. */
static int write_shapes(cli_outdir *od, const flex_modes *fm, fb_err *err)
{
  const fb_mode_set *ms = fm->vehicle;
  int rc = FB_OK;
  for (size_t k = 0; !rc && k < ms->nmodes; ++k) {
    char name[32];
    snprintf(name, sizeof name, "mode_%02zu.vtu", k + 1);
    char *path = cli_outdir_path(od, name, err);
    const fb_vtu_field frequency = {"frequency_hz", ms->freq_hz[k]};
    fb_vtu_frame frame = {
        .dof_values = ms->shapes + k * ms->ndof, .fields = &frequency, .nfields = 1};
    fb_scenario_frame_offset(fm->s, frame.origin);
    rc = path ? fb_mesh_write_vtu_frame(fm->hull->mesh, &frame, path, err) : err->code;
    if (!rc)
      rc = cli_outdir_keep(od, path, err);
    else
      free(path);
  }
  return rc ? rc : cli_write_mode_pictures(od, fm->s, fm->hull, ms, err);
}

static int write_files(cli_outdir *od, const flex_modes *fm, fb_err *err)
{
  int rc = cli_outdir_write(od, "hull_modes.csv", write_hull_csv, fm, err);
  if (!rc)
    rc = cli_outdir_write(od, "modes.csv", write_modes_csv, fm, err);
  if (!rc)
    rc = write_shapes(od, fm, err);
  return rc;
}

static void print_tables(const flex_modes *fm)
{
  const fb_mesh *m = fm->hull->mesh;
  if (fb_mesh_nelements(m) == 0)
    printf("%s: free-free hull (a superelement over %zu interface nodes): %zu rigid-body "
           "modes, then\n",
           fm->s->name, fb_mesh_nnodes(m), fm->nrigid);
  else
    printf("%s: free-free hull (%zu nodes, %zu S3 + %zu S4): %zu rigid-body modes, then\n",
           fm->s->name, fb_mesh_nnodes(m), fb_mesh_count(m, FB_ELEM_TRI3),
           fb_mesh_count(m, FB_ELEM_QUAD4), fm->nrigid);
  for (size_t k = fm->nrigid; k < fm->nhull && k < fm->nrigid + 10; ++k)
    printf("  hull mode %2zu  %10.4f Hz\n", k + 1, fm->hull_freq[k]);
  printf("\nSystem 2, undamped (%zu horizontal rigid-body modes of zero frequency left "
         "out):\n%4s  %12s  %s\n",
         fm->vehicle->nfree, "#", "f_n [Hz]", "description");
  for (size_t k = 0; k < fm->vehicle->nmodes; ++k)
    printf("%4zu  %12.6g  %s\n", k + 1, fm->vehicle->freq_hz[k], fm->vehicle->description[k]);
}

int cli_modes_flexible(const char *path, const char *out_dir, int strict,
                       const cli_mode_list *pictured)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  fb_vehicle *v = NULL;
  flex_modes fm = {0};
  int rc = cli_scenario_load(path, strict, &s, &err);
  if (!rc)
    cli_mode_list_apply(pictured, s);
  /* The directory is held (locked) from here to the end. */
  cli_outdir od;
  const int opened =
      !rc && out_dir && (rc = cli_outdir_open(&od, out_dir, "modes", &err)) == FB_OK;
  cli_stage stage = {"modes", cli_system_label(FB_SYSTEM_FLEXIBLE), 0};
  fb_vehicle_opts vo;
  fb_vehicle_opts_default(&vo);
  vo.progress = (fb_progress){cli_stage_progress, &stage};
  vo.threads = cli_threads();
  vo.hull_modes = HULL_MODES;
  /* One realisation: its hull's eigen-solve gives the free-free modes, its
   * basis the whole vehicle's. */
  if (!rc)
    rc = fb_vehicle_new(s, FB_SYSTEM_FLEXIBLE, &vo, &v, &err);
  fm.s = s;
  if (!rc) {
    const fb_hull_basis *b = fb_vehicle_hull_basis(v);
    fm.hull = fb_vehicle_fe_hull_of(v);
    fm.hull_freq = b->free_hz;
    fm.nhull = b->nfree;
    fm.nrigid = b->nfree_rigid;
    /* The modes command's are the model's own, not its basis's. */
    rc = fb_vehicle_structural_modes(v, VEHICLE_MODES, 1, &fm.vehicle, &err);
  }
  if (!rc && out_dir)
    rc = write_files(&od, &fm, &err);
  if (opened)
    rc = cli_outdir_close(&od, rc, &err);
  /* fm.hull is set whenever the vehicle was made, as rc says. */
  if (!rc && fm.hull) {
    print_tables(&fm);
    rc = cli_flush_stdout(&err);
  }
  fb_mode_set_free(&fm.vehicle);
  fb_vehicle_free(&v);
  rc = cli_report_scenario(s, rc, &err);
  fb_scenario_free(&s);
  return rc;
}
