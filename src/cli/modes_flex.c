/* flexbond modes --system flexible: modal analysis of System 2 (the
 * paper's Figs. 3 and 4): the free-free hull's modes and the whole
 * undamped vehicle's, printed and, with -o DIR, written as
 *   DIR/hull_modes.csv   mode,frequency_hz,kind (rigid | elastic)
 *   DIR/modes.csv        mode,frequency_hz,description
 *   DIR/mode_NN.vtu      each vehicle mode's hull displacement (ParaView)
 *   DIR/mode_NN.png      modes 1, 2, 8 and 10 as deformed wireframes with
 *                        the driver and the engine drawn as cubes
 *                        (cli_write_mode_pictures, which run uses too). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/escape.h"
#include "flexbond/io.h"
#include "flexbond/vehicle.h"

#include "cli.h"

enum { HULL_MODES = 30, VEHICLE_MODES = 20 };

typedef struct flex_modes {
  const fb_scenario *s;
  const fb_fe_hull *hull;
  double hull_freq[HULL_MODES];
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

/* The modes of the paper's Figs. 3 and 4. */
const size_t cli_pictured_modes[CLI_NPICTURED_MODES] = {1, 2, 8, 10};

void cli_mode_picture_name(size_t mode, char *buf, size_t size)
{
  snprintf(buf, size, "mode_%02zu.png", mode);
}

/* The mounted bodies' cubes: 0.4 m above their floor nodes, moved by
 * their own vertical displacement (scaled). */
static void cubes(const fb_scenario *s, const fb_fe_hull *hull, const double *v, double scale,
                  double *xyz)
{
  const fb_mesh *m = hull->mesh;
  size_t nh = 6 * fb_mesh_nnodes(m);
  for (size_t b = 0; b < s->nmounts; ++b) {
    const double *p = fb_mesh_node_xyz(m, hull->attach_node[s->ncorners + b]);
    xyz[3 * b] = p[0];
    xyz[3 * b + 1] = p[1];
    xyz[3 * b + 2] = p[2] + 0.4 + scale * v[nh + (size_t)b];
  }
}

int cli_write_mode_pictures(cli_outdir *od, const fb_scenario *s, const fb_fe_hull *hull,
                            const fb_mode_set *ms, fb_err *err)
{
  double *cube_xyz = malloc((3 * s->nmounts + 1) * sizeof *cube_xyz);
  int rc = cube_xyz ? FB_OK : fb_err_set(err, FB_ENOMEM, "out of memory");
  for (size_t i = 0; !rc && i < CLI_NPICTURED_MODES; ++i) {
    size_t k = cli_pictured_modes[i] - 1;
    if (k >= ms->nmodes)
      continue;
    const double *v = ms->shapes + k * ms->ndof;
    /* Shapes are normalised to a largest displacement of 1: draw it as
     * 0.5 m, visible on a 6 m hull. */
    const double scale = 0.5;
    cubes(s, hull, v, scale, cube_xyz);
    char name[32], title[160];
    cli_mode_picture_name(k + 1, name, sizeof name);
    snprintf(title, sizeof title, "System 2, mode %zu: %.3f Hz, %s", k + 1, ms->freq_hz[k],
             ms->description[k]);
    char *path = cli_outdir_path(od, name, err);
    rc = path ? fb_plot_mesh_png(hull->mesh, v, scale, cube_xyz, s->nmounts, 0.3, title, path,
                                 err)
              : err->code;
    if (!rc)
      rc = cli_outdir_keep(od, path, err);
    else
      free(path);
  }
  free(cube_xyz);
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
    rc = path ? fb_mesh_write_vtu_fields(fm->hull->mesh, ms->shapes + k * ms->ndof, &frequency,
                                         1, path, err)
              : err->code;
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
  printf("%s: free-free hull (%zu nodes, %zu S3 + %zu S4): %zu rigid-body modes, then\n",
         fm->s->name, fb_mesh_nnodes(fm->hull->mesh),
         fb_mesh_count(fm->hull->mesh, FB_ELEM_TRI3),
         fb_mesh_count(fm->hull->mesh, FB_ELEM_QUAD4), fm->nrigid);
  for (size_t k = fm->nrigid; k < fm->nhull && k < fm->nrigid + 10; ++k)
    printf("  hull mode %2zu  %10.4f Hz\n", k + 1, fm->hull_freq[k]);
  printf("\nSystem 2, undamped (%zu horizontal rigid-body modes of zero frequency left "
         "out):\n%4s  %12s  %s\n",
         fm->vehicle->nfree, "#", "f_n [Hz]", "description");
  for (size_t k = 0; k < fm->vehicle->nmodes; ++k)
    printf("%4zu  %12.6g  %s\n", k + 1, fm->vehicle->freq_hz[k], fm->vehicle->description[k]);
}

int cli_modes_flexible(const char *path, const char *out_dir)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  fb_fe_hull *hull = NULL;
  flex_modes fm = {0};
  int rc = fb_scenario_load(path, &s, &err);
  /* The directory is held (locked) from here to the end. */
  cli_outdir od;
  const int opened =
      !rc && out_dir && (rc = cli_outdir_open(&od, out_dir, "modes", &err)) == FB_OK;
  if (!rc)
    rc = fb_vehicle_fe_hull(s, &hull, &err);
  fm.s = s;
  fm.hull = hull;
  if (!rc) {
    fm.nhull = HULL_MODES;
    rc = fb_fe_hull_free_modes(hull, fm.nhull, fm.hull_freq, &fm.nrigid, &err);
  }
  if (!rc)
    rc = fb_vehicle_flexible_modes(s, hull, VEHICLE_MODES, &fm.vehicle, &err);
  if (!rc && out_dir)
    rc = write_files(&od, &fm, &err);
  if (opened)
    rc = cli_outdir_close(&od, rc, &err);
  if (!rc) {
    print_tables(&fm);
    rc = cli_flush_stdout(&err);
  }
  fb_mode_set_free(&fm.vehicle);
  fb_fe_hull_free(&hull);
  rc = cli_report_scenario(s, rc, &err);
  fb_scenario_free(&s);
  return rc;
}
