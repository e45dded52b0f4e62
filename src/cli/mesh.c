/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond mesh: the System 2 hull mesh of a scenario (generated or
 * imported), its mass properties, and its export as an Abaqus/CalculiX
 * deck (.inp) or a VTK unstructured grid (.vtu). */
#include <stdio.h>
#include <string.h>

#include "flexbond/hull_source.h"
#include "flexbond/vehicle.h"

#include "cli.h"

static const char mesh_usage[] =
    "usage: flexbond mesh SCENARIO.yaml [--export FILE.inp|FILE.vtu]\n"
    "                     [--export-matrices DIR]\n"
    "\n"
    "Builds the scenario's finite-element hull (hull.mesh: the generator or an\n"
    "imported deck), checks it, and prints its element counts, mass, centre of\n"
    "mass and inertias (the structure's, then with the hull.masses on it).\n"
    "Positions, printed and written, are in the file's frame (frame.origin;\n"
    "a deck's own; else the hull's centre of mass).\n"
    "--export writes it as an Abaqus/CalculiX input deck (*NODE, *ELEMENT\n"
    "S3/S4, *NSET LOAD, one per mount and corner (SUSP_<CORNER>), MASS_<NAME>,\n"
    "FRONT_EDGE, REAR_EDGE, ALL, *MATERIAL, *SHELL SECTION, and each hull mass\n"
    "as a MASS element with its *MASS) or, for a .vtu name, as a VTK file for\n"
    "ParaView.\n"
    "--export-matrices writes into DIR the hull structure's own stiffness and\n"
    "mass matrices as Matrix Market files (K.mtx, M.mtx; the hull.masses left\n"
    "out), dofs.csv naming each row (node id and ux uy uz rx ry rz) and the\n"
    "deck they belong to (hull.inp), all or none.\n"
    "\n"
    "options:\n"
    "  --export FILE           write the mesh (.inp or .vtu, by the name's ending)\n"
    "  --export-matrices DIR   write K.mtx, M.mtx, dofs.csv and hull.inp into DIR\n"
    "  --strict                refuse implausible values instead of warning\n"
    "  -h, --help              this text\n";

static int ends_with(const char *s, const char *tail)
{
  size_t n = strlen(s), m = strlen(tail);
  return n >= m && strcmp(s + n - m, tail) == 0;
}

/* Prints the mass properties of the structure (as_built 0) or of the
 * hull with its declared masses, the centre of mass in the file's frame
 * (o: fb_scenario_frame_offset). */
static int print_mass(const fb_fe_hull *h, const double *o, int as_built, fb_err *err)
{
  fb_hull_mass_props p;
  const int rc = fb_fe_hull_mass_props(h, as_built, &p, err);
  if (rc)
    return rc;
  if (as_built)
    printf("with its %zu hull masses: ", h->npoint_masses);
  printf("mass %.6g kg, centre of mass (%.4g, %.4g, %.4g) m\n", p.mass, o[0] + p.cg[0],
         o[1] + p.cg[1], o[2] + p.cg[2]);
  printf("%sabout the centre of mass: Ixx %.6g, Iyy %.6g, Izz %.6g, Ixz %.4g kg m^2\n",
         as_built ? "  " : "", p.inertia[0], p.inertia[4], p.inertia[8], p.inertia[2]);
  return FB_OK;
}

/* One line per section (sec -1: the elements without one, which take
 * the scenario's hull.material): elements, area, plate and mass. */
static void print_section(const fb_fe_hull *h, long sec)
{
  const fb_hull_section_totals t = fb_fe_hull_section_totals(h, sec);
  if (t.nelements == 0)
    return;
  const fb_shell_props *p = sec >= 0 ? fb_mesh_section_props(h->mesh, (size_t)sec) : &h->props;
  printf("  %-16s %5zu elements, %8.4g m^2, %g m, E %g Pa, nu %g, %g kg/m^3",
         sec >= 0 ? fb_mesh_section_elset(h->mesh, (size_t)sec) : "hull.material", t.nelements,
         t.area, p->thickness, p->young, p->poisson, p->density);
  if (p->nonstructural_mass > 0.0)
    printf(" + %g kg/m^2", p->nonstructural_mass);
  printf(": %.6g kg\n", t.mass);
}

/* A deck's own point masses (MASS elements), part of the structure. */
static void print_point_masses(const fb_mesh *m)
{
  const size_t n = fb_mesh_npoint_masses(m);
  double sum = 0.0;
  for (size_t i = 0; i < n; ++i)
    sum += fb_mesh_point_mass(m, i);
  if (n)
    printf("  %zu point masses (MASS elements): %.6g kg\n", n, sum);
}

/* Which frame the positions printed and written are in. */
static void print_frame(const fb_scenario *s)
{
  if (s->frame_origin)
    printf("positions in the file's frame, from %s\n", s->frame_origin);
  else if (fb_scenario_hull_read_in_own_frame(s))
    printf("positions in the deck's frame\n");
  else
    printf("positions from the hull structure's centre of mass (the file's frame)\n");
}

static int print_properties(const fb_scenario *s, const fb_fe_hull *h, fb_err *err)
{
  const fb_mesh *m = h->mesh;
  double o[3];
  fb_scenario_frame_offset(s, o);
  if (fb_mesh_nelements(m) == 0) {
    printf("hull: a superelement over %zu interface nodes (%zu DOFs)\n", fb_mesh_nnodes(m),
           6 * fb_mesh_nnodes(m));
  } else {
    printf("hull mesh: %zu nodes, %zu S3 + %zu S4 elements", fb_mesh_nnodes(m),
           fb_mesh_count(m, FB_ELEM_TRI3), fb_mesh_count(m, FB_ELEM_QUAD4));
    if (fb_mesh_nsections(m) == 0)
      printf(", %g m plates\n", h->props.thickness);
    else
      printf(", sections:\n");
  }
  for (long sec = -1; fb_mesh_nsections(m) && sec < (long)fb_mesh_nsections(m); ++sec)
    print_section(h, sec);
  print_point_masses(m);
  print_frame(s);
  int rc = print_mass(h, o, 0, err);
  return rc || !h->npoint_masses ? rc : print_mass(h, o, 1, err);
}

/* ---- --export-matrices. */

static void write_mtx(FILE *fp, const void *a)
{
  fb_mat_print_mtx(fp, a);
}

/* The hull's mesh, its nodes in the file's frame (*out new: a deck
 * written from it reads back with the file's positions), as built (with
 * the hull.masses as point masses: --export) or the structure alone (the
 * deck --export-matrices' K and M belong to). */
static int file_frame_mesh(const fb_scenario *s, const fb_fe_hull *h, int as_built,
                           fb_mesh **out, fb_err *err)
{
  const int rc =
      as_built ? fb_fe_hull_mesh_as_built(h, out, err) : fb_mesh_clone(h->mesh, out, err);
  double o[3];
  fb_scenario_frame_offset(s, o);
  if (!rc)
    fb_mesh_translate(*out, o[0], o[1], o[2]);
  return rc;
}

typedef struct deck_out {
  const fb_mesh *mesh; /* in the file's frame */
  const fb_shell_props *props;
} deck_out;

static void write_deck(FILE *fp, const void *ctx)
{
  const deck_out *d = ctx;
  fb_mesh_print_inp(fp, d->mesh, d->props);
}

/* Row r (1-based, as in the .mtx files) is node_id's DOF r % 6: the
 * assembly's order, six per node in node order (fem.h). */
static void write_dofs(FILE *fp, const void *hull)
{
  static const char *const names[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  const fb_fe_hull *h = hull;
  fputs("row,node,dof\n", fp);
  for (size_t i = 0; i < fb_mesh_nnodes(h->mesh); ++i)
    for (size_t k = 0; k < 6; ++k)
      fprintf(fp, "%zu,%ld,%s\n", 6 * i + k + 1, fb_mesh_node_id(h->mesh, i), names[k]);
}

static int export_matrices(const fb_scenario *s, const fb_fe_hull *h, const char *dir,
                           fb_err *err)
{
  fb_mat *K = NULL, *M = NULL;
  fb_mesh *placed = NULL;
  int rc = fb_fe_hull_matrices(h, &K, &M, err);
  if (rc == FB_OK)
    rc = file_frame_mesh(s, h, 0, &placed, err);
  const deck_out deck = {placed, &h->props};
  cli_outdir od;
  const int opened = rc == FB_OK && (rc = cli_outdir_open(&od, dir, "mesh", err)) == FB_OK;
  if (rc == FB_OK)
    rc = cli_outdir_write(&od, "K.mtx", write_mtx, K, err);
  if (rc == FB_OK)
    rc = cli_outdir_write(&od, "M.mtx", write_mtx, M, err);
  if (rc == FB_OK)
    rc = cli_outdir_write(&od, "dofs.csv", write_dofs, h, err);
  if (rc == FB_OK)
    rc = cli_outdir_write(&od, "hull.inp", write_deck, &deck, err);
  if (opened)
    rc = cli_outdir_close(&od, rc, err);
  if (rc == FB_OK)
    printf("wrote %s: K.mtx, M.mtx (%zu x %zu), dofs.csv, hull.inp\n", dir, fb_mat_nrows(K),
           fb_mat_ncols(K));
  fb_mat_free(&K);
  fb_mat_free(&M);
  fb_mesh_free(&placed);
  return rc;
}

static int run(const char *path, const char *export_path, const char *matrices_dir, int strict)
{
  fb_err err;
  fb_err_clear(&err);
  fb_scenario *s = NULL;
  fb_fe_hull *h = NULL;
  int rc = cli_scenario_load(path, strict, &s, &err);
  if (!rc)
    rc = fb_vehicle_fe_hull(s, &h, &err);
  /* A signal during the mesh: the file is not written. */
  if (!rc && (export_path || matrices_dir))
    rc = cli_check_interrupt(&err);
  /* A superelement's matrices are no deck's or VTU's elements:
   * --export-matrices writes them. */
  if (!rc && export_path && fb_mesh_nelements(h->mesh) == 0)
    rc = fb_err_set(&err, FB_EINVAL,
                    "--export %s: the hull is a superelement, whose interface nodes have no "
                    "elements to write (--export-matrices writes its K and M)",
                    export_path);
  fb_mesh *placed = NULL;
  if (!rc && export_path)
    rc = file_frame_mesh(s, h, 1, &placed, &err);
  if (!rc && export_path)
    rc = ends_with(export_path, ".vtu")
             ? fb_mesh_write_vtu(placed, NULL, export_path, &err)
             : fb_mesh_write_inp(placed, &h->props, export_path, &err);
  fb_mesh_free(&placed);
  if (!rc)
    rc = print_properties(s, h, &err);
  if (!rc && export_path)
    printf("wrote %s\n", export_path);
  if (!rc && matrices_dir)
    rc = export_matrices(s, h, matrices_dir, &err);
  if (!rc)
    rc = cli_flush_stdout(&err);
  fb_fe_hull_free(&h);
  rc = cli_report_scenario(s, rc, &err);
  fb_scenario_free(&s);
  return rc;
}

int cli_cmd_mesh(int argc, char **argv)
{
  enum { OPT_EXPORT, OPT_MATRICES, OPT_STRICT, OPT_HELP, NOPTS };
  cli_option opts[NOPTS] = {[OPT_EXPORT] = {"--export", NULL, 1, NULL},
                            [OPT_MATRICES] = {"--export-matrices", NULL, 1, NULL},
                            [OPT_STRICT] = {"--strict", NULL, 0, NULL},
                            [OPT_HELP] = {"--help", "-h", 0, NULL}};
  const char *path;
  int rc;
  if (!cli_parse_file_command(argc, argv, opts, NOPTS, mesh_usage, "SCENARIO", &path, &rc))
    return rc;
  const char *out = opts[OPT_EXPORT].value;
  if (out && !ends_with(out, ".inp") && !ends_with(out, ".vtu"))
    return cli_usage_error(argv[0], "--export needs a .inp or .vtu file name (got '%s')", out);
  const char *dir = opts[OPT_MATRICES].value;
  if (dir && !*dir)
    return cli_usage_error(argv[0], "--export-matrices needs a directory");
  return run(path, out, dir, opts[OPT_STRICT].value != NULL);
}
