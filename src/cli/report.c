/* SPDX-License-Identifier: BSD-3-Clause */
/* flexbond run's statistics and its DIR/report.md (docs/report.md): the
 * scenario, the assumptions, the runs, the mode tables and pictures, the
 * figures, the comparison of System 2 with System 1 and a paragraph of
 * conclusions. Every sentence of the conclusions is chosen by comparing
 * this run's numbers with the thresholds below; nothing is written in
 * advance. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "flexbond/escape.h"
#include "flexbond/hull_source.h"
#include "flexbond/io.h"
#include "flexbond/sim.h"
#include "flexbond/vehicle.h"

#include "cli.h"

/* 180 / pi; M_PI is not in C11. */
#define DEGREES_PER_RADIAN 57.295779513082320877

/* num / den, NaN when den is 0 (a ratio to nothing says nothing). */
static double ratio(double num, double den)
{
  return den != 0 ? num / den : NAN;
}

/* ---- Markdown. */

/* Every string from the inputs (names, paths, units, messages) goes
 * through fb_md_write_text (flexbond/escape.h), so that it prints as it
 * is and makes no link, image, HTML or table cell of its own; the texts
 * of this file are Markdown already. */

/* v to 4 significant digits in buf (32 bytes suffice), in fixed notation
 * from 1e-3 to 1e6 (%g would print 20003 as 2e+04), "-" for a
 * non-finite value. Returns buf. */
static const char *number_text(double v, char *buf, size_t size)
{
  const double a = fabs(v);
  if (!isfinite(v))
    snprintf(buf, size, "-");
  else if (a >= 1e-3 && a < 1e6)
    snprintf(buf, size, "%.*f", (int)fmax(0, 3 - floor(log10(a))), v);
  else
    snprintf(buf, size, "%.4g", v);
  return buf;
}

static void md_number(FILE *fp, double v)
{
  char buf[32];
  fputs(number_text(v, buf, sizeof buf), fp);
}

/* "v unit": v as md_number, the unit (from the model) escaped. */
static void md_value_unit(FILE *fp, double v, const char *unit)
{
  md_number(fp, v);
  fputc(' ', fp);
  fb_md_write_text(fp, unit);
}

/* A fraction as a signed or unsigned percentage, "-" for a non-finite one. */
static void md_percent(FILE *fp, double fraction, int sign)
{
  /* A change that rounds to zero prints as +0.0 %, never -0.0 %. */
  if (isfinite(fraction))
    fprintf(fp, sign ? "%+.1f %%" : "%.1f %%",
            fabs(100 * fraction) < 0.05 ? 0.0 : 100 * fraction);
  else
    fputs("-", fp);
}

/* The scenario's road in the report's words, its road type's own
 * ("over the bump", "on the ISO 8608 class C road"), escaped; capital: at
 * a sentence's start. */
static void write_road(FILE *fp, const fb_scenario *s, int capital)
{
  char road[256];
  fb_road_phrase(s->road_type, &s->road, road, sizeof road);
  if (capital && road[0] >= 'a' && road[0] <= 'z')
    road[0] = (char)(road[0] - 'a' + 'A');
  fb_md_write_text(fp, road);
}

/* ---- Scenario. */

/* When every wheel enters the road's window and leaves it (meets the
 * road's feature, a bump, and leaves it): derived from the corners'
 * positions, the speed and the road. */
static void write_corner_timing(FILE *fp, const fb_study_report *rep)
{
  const fb_scenario *s = fb_study_report_scenario(rep);
  fputs("\n| corner | x, y [m] | entry, exit [s] |\n|---|---|---|\n", fp);
  for (size_t c = 0; c < s->ncorners; ++c) {
    const fb_corner_params *p = &s->corner[c];
    double w[2], x = 0.0, y = 0.0;
    fb_study_report_wheel_window(rep, c, w);
    fb_scenario_corner_position(s, c, &x, &y);
    fputs("| ", fp);
    fb_md_write_text(fp, p->name);
    fprintf(fp, " | %.10g, %.10g | %.4f, %.4f |\n", x, y, w[0], w[1]);
  }
}

/* One row of the values table (an fb_scenario_value_fn). */
static int write_value_row(const fb_scenario_value *v, void *ctx)
{
  FILE *fp = ctx;
  /* No code spans: inside one the escapes of fb_md_write_text would show. */
  fputs("| ", fp);
  fb_md_write_text(fp, v->key);
  fputs(" | ", fp);
  fb_md_write_text(fp, v->value);
  fputs(" | ", fp);
  fb_md_write_text(fp, v->unit);
  fputs(" | ", fp);
  fb_md_write_text(fp, v->path ? v->path : "default");
  fputs(" | ", fp);
  fb_md_write_text(fp, v->doc);
  fputs(" |\n", fp);
  return 0;
}

/* The hull's declared masses, a row of the scenario table (none: no row). */
static void write_point_masses(FILE *fp, const fb_scenario *s)
{
  if (!s->npoint_masses)
    return;
  double o[3];
  fb_scenario_frame_offset(s, o);
  fputs("| hull masses | ", fp);
  for (size_t k = 0; k < s->npoint_masses; ++k) {
    const fb_hull_point_mass *m = &s->point_mass[k];
    fputs(k ? "; " : "", fp);
    fb_md_write_text(fp, m->name);
    fprintf(fp, " %.10g kg at x, y = %.10g, %.10g m", m->mass, o[0] + m->x, o[1] + m->y);
  }
  fprintf(fp,
          " (%.10g kg in all, on the floor, besides the structure above: in both systems' "
          "inertia; their weight is part of load.total_weight) |\n",
          fb_scenario_point_masses_total(s));
}

/* "N things" for each part the vehicle has, "1 thing" for one. */
static void write_count(FILE *fp, int *first, size_t n, const char *one, const char *many)
{
  if (!n)
    return;
  fprintf(fp, "%s%zu %s", *first ? "" : ", ", n, n == 1 ? one : many);
  *first = 0;
}

/* The scenario's parts by kind, those it has. */
static void write_layout(FILE *fp, const fb_scenario *s)
{
  int first = 1;
  write_count(fp, &first, s->ncorners, "corner", "corners");
  write_count(fp, &first, s->nmounts, "mounted body on a spring", "mounted bodies on springs");
  write_count(fp, &first, s->nbodies, "rigid body on bushings", "rigid bodies on bushings");
  write_count(fp, &first, s->nbogies, "walking-beam bogie", "walking-beam bogies");
  write_count(fp, &first, s->nantiroll_bars, "anti-roll bar", "anti-roll bars");
  write_count(fp, &first, s->noutputs, "output", "outputs");
}

static void write_scenario(FILE *fp, const cli_run_outputs *o)
{
  const fb_scenario *s = o->scenario;
  fputs("## Scenario\n\n| | |\n|---|---|\n| name | ", fp);
  fb_md_write_text(fp, cli_scenario_name(s));
  fputs(" |\n| file | ", fp);
  fb_md_write_text(fp, s->path ? s->path : "-");
  fputs(" |\n| systems | ", fp);
  for (size_t i = 0; i < o->nruns; ++i)
    fprintf(fp, "%s%s", i ? ", " : "", cli_system_label(o->runs[i].sys));
  fputs(" |\n| layout | ", fp);
  write_layout(fp, s);
  fputs(" |\n", fp);
  if (s->frame_origin) {
    fputs("| frame | the file's positions are from ", fp);
    fb_md_write_text(fp, s->frame_origin);
    fprintf(fp,
            "; the hull's centre of mass is at x, y, z = %.10g, %.10g, %.10g m there. The "
            "positions below and the pictures are in this frame; rotations (pitch, roll) "
            "are about the centre of mass |\n",
            s->hull_cg_x, s->hull_cg_y, s->hull_cg_z);
  } else if (fb_scenario_hull_read_in_own_frame(s)) {
    fprintf(fp,
            "| frame | the deck's: its structure's centre of mass is at x, y, z = %.10g, "
            "%.10g, %.10g m there. The positions below and the pictures are in this frame; "
            "rotations (pitch, roll) are about the centre of mass |\n",
            s->hull_cg_x, s->hull_cg_y, s->hull_cg_z);
  } else {
    fputs("| frame | the file's positions are from the hull structure's centre of mass, and so "
          "are the positions below and the pictures |\n",
          fp);
  }
  fprintf(fp,
          "| hull | %.10g kg, Ixx %.10g kg m^2, Iyy %.10g kg m^2 about its centre of mass "
          "(%s) |\n"
          "| road window | the vehicle ",
          s->hull_mass, s->hull_ixx, s->hull_iyy,
          s->hull_mass_given ? "the file's, checked against its mesh when it has one"
                             : "its finite-element mesh's");
  write_road(fp, s, 0);
  fprintf(fp, ", from %.4f s (first wheel's entry) to %.4f s (last wheel's exit) |\n",
          o->bump_window[0], o->bump_window[1]);
  write_point_masses(fp, s);
  write_corner_timing(fp, o->report);
  fputs("\nEvery value the run used, as the scenario format declares it "
        "(docs/scenario-format.md), and where the file gave it:\n\n"
        "| key | value | unit | from | meaning |\n|---|---|---|---|---|\n",
        fp);
  fb_scenario_each_value(s, write_value_row, fp);
}

/* ---- Assumptions. */

static void write_payload(FILE *fp, const fb_scenario *s)
{
  if (s->payload == FB_PAYLOAD_WEIGHT_ONLY) {
    fprintf(fp,
            "- Payload: weight only (`weight-only`, the paper's prescribed efforts): the "
            "%.10g N act at the %zu load point%s and add no mass; the hull's inertia is its "
            "own%s.\n",
            s->total_weight, s->nload, s->nload == 1 ? "" : "s",
            s->npoint_masses ? " (its structure's and its masses')" : "");
    return;
  }
  const double payload = fb_scenario_payload_mass(s);
  char masses[64] = "";
  if (s->npoint_masses)
    snprintf(masses, sizeof masses, " - %.10g kg (the hull masses)",
             fb_scenario_point_masses_total(s));
  fprintf(fp,
          "- Payload: lumped (`lumped`): its mass, %.10g N / %.10g m/s^2 - %.10g kg%s = %.6g "
          "kg, is spread equally over the %zu load point%s (%.6g kg each).\n",
          s->total_weight, s->gravity, s->hull_mass, masses, payload, s->nload,
          s->nload == 1 ? "" : "s", payload / (double)s->nload);
}

/* The plates whose section overrides the material above, by element
 * set (a deck's *SHELL SECTION or hull.sections), with their elements. */
static void write_sections(FILE *fp, const fb_mesh *m)
{
  size_t shown = 0;
  for (size_t i = 0; i < fb_mesh_nsections(m); ++i) {
    const size_t n = fb_mesh_section_nelements(m, (long)i);
    if (n == 0)
      continue;
    const fb_shell_props *p = fb_mesh_section_props(m, i);
    fputs(shown++ ? "; "
                  : "  Plates with a section of their own (the material above elsewhere): ",
          fp);
    fb_md_write_text(fp, fb_mesh_section_elset(m, i));
    fprintf(fp, " (%zu elements) %.10g m, E = %.10g GPa, nu = %.10g, rho = %.10g kg/m^3", n,
            p->thickness, p->young / 1e9, p->poisson, p->density);
    if (p->nonstructural_mass > 0.0)
      fprintf(fp, ", + %.10g kg/m^2 non-structural", p->nonstructural_mass);
  }
  if (shown)
    fputs(".\n", fp);
}

/* The System 2 run of o (NULL if it did not run). */
static const cli_run_system *flexible_run(const cli_run_outputs *o)
{
  for (size_t i = 0; i < o->nruns; ++i)
    if (o->runs[i].sys == FB_SYSTEM_FLEXIBLE)
      return &o->runs[i];
  return NULL;
}

/* The estimated error of each output from the modal basis, when it was
 * estimated. */
static void write_basis_error(FILE *fp, const cli_run_outputs *o)
{
  const cli_run_system *r = flexible_run(o);
  if (!r || !r->basis_error)
    return;
  const fb_scenario *s = o->scenario;
  size_t worst = 0;
  fb_study_run_worst_basis_error(fb_study_report_run(o->report, (size_t)(r - o->runs)),
                                 s->noutputs, &worst);
  fprintf(fp,
          "  Its estimated error, the largest difference from the same run with the basis's "
          "next block of load-dependent Ritz vectors from the road window's start (%.4f s) to "
          "the end, over each output's range there: at most %.2g %% (",
          o->bump_window[0], s->noutputs ? 100.0 * r->basis_error[worst] : 0.0);
  if (s->noutputs)
    fb_md_write_text(fp, s->output[worst].label);
  fputs("); ", fp);
  for (size_t k = 0; k < s->noutputs; ++k) {
    fputs(k ? ", " : "", fp);
    fb_md_write_text(fp, s->output[k].name);
    fprintf(fp, " %.2g %%", 100.0 * r->basis_error[k]);
  }
  fputs(". The settling from a zero start excites every mode and is not part of this "
        "estimate.",
        fp);
  if (s->noutputs && r->basis_error[worst] > FB_STUDY_BASIS_ERROR_NOTABLE)
    fputs(" Above 0.1 %, a higher `hull.fe.cutoff_hz` (or `--hull-cutoff`) keeps more modes "
          "and lowers it.",
          fp);
  fputc('\n', fp);
}

/* The auto basis: its blocks, where they start from, and the band. */
static void write_auto_basis(FILE *fp, const fb_scenario *s, const fb_hull_basis *b)
{
  fprintf(fp,
          "- System 2's hull model: in modal coordinates, its %zu rigid-body modes and %zu "
          "blocks of load-dependent Ritz vectors, %zu vectors in all, from %zu patterns (every "
          "attachment point's force, the load and every output read from the hull's "
          "deformation): the first block their static response with inertia relief, each "
          "next one the stiffness's inverse times the mass times the one before. Blocks "
          "were added until the next changed the hull's receptances between the patterns by "
          "%.2g of their scale at most (below %.2g) over 0 to %.4g Hz, ",
          b->nrigid, b->nblocks, b->nstatic, b->npatterns, b->block_change, FB_HULL_BLOCK_TOL,
          b->cutoff_hz);
  if (isfinite(b->excitation_hz))
    fprintf(fp,
            "the highest frequency that reaches the hull (the wheels' hop%s and the mounted "
            "bodies' natural frequencies on a fixed hull, and the road's at this speed)",
            s->nbogies ? ", the bogies' bounce and pitch" : "");
  else
    fputs("the scenario's cut-off", fp);
  fprintf(fp,
          ": %zu coordinates in place of %zu nodal DOFs (docs/hull-mesh.md, \"The modal "
          "basis\"), ",
          b->ncoords, b->ndof);
}

static void write_hull_order(FILE *fp, const cli_run_outputs *o)
{
  const fb_hull_basis *b = o->basis;
  if (b->coordinates == FB_HULL_NODAL)
    fprintf(fp, "- System 2's hull model: full order, all %zu nodal DOFs (6 per node), ",
            b->ndof);
  else if (b->ncoords >= b->ndof)
    fprintf(fp,
            "- System 2's hull model: full order in modal coordinates, every one of the "
            "%zu free-free modes of its nodal DOFs (`all`, a dense eigen-solve), ",
            b->ndof);
  else if (b->kind == FB_HULL_MODES_AUTO)
    write_auto_basis(fp, o->scenario, b);
  else
    fprintf(fp,
            "- System 2's hull model: in modal coordinates, its %zu lowest free-free modes "
            "(%zu rigid-body modes) and %zu residual-flexibility vectors (the static response "
            "the modes miss to each of %zu patterns: every attachment point's force, the load "
            "and every output read from the hull's deformation): %zu coordinates in place of "
            "%zu nodal DOFs (docs/hull-mesh.md, \"The modal basis\"), ",
            b->nmodes, b->nrigid, b->nstatic, b->npatterns, b->ncoords, b->ndof);
  fprintf(fp, "as set by %s.\n", o->hull_modes_source);
  write_basis_error(fp, o);
}

/* Room for a hull source's description (a path and a few words). */
#define HULL_SOURCE_TEXT 1024

/* The estimated mesh error of a refined hull (fb_study_mesh_error). */
static void write_mesh_error(FILE *fp, const fb_scenario *s)
{
  double band[2];
  if (!fb_study_mesh_error(s, band)) {
    char what[HULL_SOURCE_TEXT];
    fb_scenario_hull_describe(s, what, sizeof what);
    fputs("- Mesh convergence: not estimated for ", fp);
    fb_md_write_text(fp, what);
    fputs(", used as it is; compare with a finer mesh of the same hull.\n", fp);
    return;
  }
  fprintf(fp,
          "- Mesh convergence (an estimate, not computed in this run): at density %d the "
          "hull's first ten elastic free-free frequencies are about %.2g %% to %.2g %% above "
          "their converged values (the reference hull's measured %.0f %% to %.0f %% at "
          "density 1, falling as 1 / density^2; docs/hull-mesh.md, \"Convergence\"). The "
          "reference vehicle's suspension modes moved by less than 0.1 %% from density 1 to "
          "2.\n",
          fb_scenario_hull_density(s), 100 * band[0], 100 * band[1],
          100 * FB_STUDY_MESH_ERROR_LOW, 100 * FB_STUDY_MESH_ERROR_HIGH);
}

static void write_fe_hull(FILE *fp, const cli_run_outputs *o)
{
  const fb_scenario *s = o->scenario;
  const fb_mesh *m = o->hull->mesh;
  fputs("- System 2's hull mesh: ", fp);
  char what[HULL_SOURCE_TEXT];
  fb_scenario_hull_describe(s, what, sizeof what);
  fb_md_write_text(fp, what);
  if (fb_mesh_nelements(m) == 0)
    fprintf(fp,
            ": a free-free superelement over %zu interface nodes (%zu DOFs), its stiffness "
            "and mass as the files give them (the scenario's material and thickness are not "
            "used); its free-free modes are those of K and M, stiffer than the structure's "
            "when the tool reduced it statically (Guyan; docs/reduced-hulls.md).\n",
            fb_mesh_nnodes(m), 6 * fb_mesh_nnodes(m));
  else
    fprintf(fp,
            ": %zu nodes, %zu triangles (S3) and %zu quadrilaterals (S4), flat shells with 6 "
            "DOFs per node. Material E = %.10g GPa, nu = %.10g, rho = %.10g kg/m^3, thickness "
            "%.10g m; %s mass matrix; drilling stiffness factor %.3g.\n",
            fb_mesh_nnodes(m), fb_mesh_count(m, FB_ELEM_TRI3), fb_mesh_count(m, FB_ELEM_QUAD4),
            s->young / 1e9, s->poisson, s->density, s->thickness,
            s->hull_mass_matrix == FB_MASS_LUMPED ? "lumped" : "consistent",
            s->hull_drill_factor);
  write_sections(fp, m);
  fprintf(fp,
          "- System 2's structural damping: B = beta K with beta = %.4g s, so that the %s "
          "first elastic free-free mode (%.4g Hz) has a damping ratio of %.3g "
          "(stiffness-proportional only, which leaves the rigid-body motion undamped).\n",
          o->basis->beta,
          s->npoint_masses ? "hull's (with its declared masses)" : "bare hull's",
          o->basis->f1_hz, s->hull_damping_ratio);
  write_mesh_error(fp, s);
  write_hull_order(fp, o);
}

/* A gallery entry's "NAME, MEANING", each escaped (a program's own entry
 * may name itself anything). */
static void write_named(FILE *fp, const char *name, const char *meaning)
{
  fb_md_write_text(fp, name);
  fputs(", ", fp);
  fb_md_write_text(fp, meaning);
}

/* Corner c's shock absorber in a report's words: its law's line for its
 * values, else the law's name and meaning (plain text: the writer escapes
 * it, a program's own law may write anything). */
static void damper_line(const fb_corner_params *c, char *buf, size_t size)
{
  const fb_damper_law *l = fb_corner_damper_law(c);
  if (l->ops->describe)
    l->ops->describe(c->damper.bytes, buf, size);
  else
    snprintf(buf, size, "%s, %s", l->name, l->meaning);
}

/* Corner c's spring in a report's words: its law's line for its values,
 * else the law's name and meaning (plain text, as damper_line's). */
static void spring_line(const fb_corner_params *c, char *buf, size_t size)
{
  const fb_spring_law *l = fb_corner_spring_law(c);
  const fb_spring_context ctx = fb_corner_spring_context(c);
  if (l->ops->describe)
    l->ops->describe(c->spring.bytes, &ctx, buf, size);
  else
    snprintf(buf, size, "%s, %s", l->name, l->meaning);
}

/* Appends stop st's words (which: "bump", "rebound") to buf, n bytes
 * long; the new length. */
static size_t stop_words(const char *which, const fb_stop *st, char *buf, size_t size, size_t n)
{
  if (!st->given)
    return n;
  int w = st->npoints ? snprintf(buf + n, size - n, "%s%s at %g m, a table of %zu points",
                                 n ? "; " : "", which, st->gap, st->npoints)
                      : snprintf(buf + n, size - n, "%s%s at %g m, %g N/m", n ? "; " : "",
                                 which, st->gap, st->rate);
  n += w > 0 && (size_t)w < size - n ? (size_t)w : 0;
  if (st->damping > 0.0) {
    w = snprintf(buf + n, size - n, ", %g N s/m", st->damping);
    n += w > 0 && (size_t)w < size - n ? (size_t)w : 0;
  }
  return n;
}

/* Corner c's stops in a report's words ("none" without). */
static void stops_line(const fb_corner_params *c, char *buf, size_t size)
{
  buf[0] = '\0';
  const size_t n = stop_words("bump", &c->stops.bump, buf, size, 0);
  if (!stop_words("rebound", &c->stops.rebound, buf, size, n))
    snprintf(buf, size, "none");
}

typedef void (*corner_words)(const fb_corner_params *c, char *buf, size_t size);

/* 1 if corner c has its own spring, damper and stops; a bogie's wheel
 * rides on the beam, whose pivot has the spring and the damper. */
static int own_suspension(const fb_scenario *s, size_t c)
{
  return fb_scenario_corner_bogie(s, c) < 0;
}

/* 1 if corners c and k have their own suspensions and words says the
 * same of them (line: k's words). */
static int alike(const fb_scenario *s, corner_words words, size_t c, const char *line)
{
  char other[192];
  if (!own_suspension(s, c))
    return 0;
  words(&s->corner[c], other, sizeof other);
  return !strcmp(line, other);
}

/* One item of the Assumptions: title, then the corners with their own
 * suspensions (own_suspension) words says alike together, in the order
 * the corners first name them; no item when no corner has one. */
static void write_corners_alike(FILE *fp, const fb_scenario *s, const char *title,
                                corner_words words)
{
  size_t groups = 0;
  for (size_t k = 0; k < s->ncorners; ++k) {
    if (!own_suspension(s, k))
      continue;
    char line[192];
    words(&s->corner[k], line, sizeof line);
    size_t seen = 0;
    for (size_t c = 0; c < k; ++c)
      seen += alike(s, words, c, line);
    if (seen)
      continue;
    fprintf(fp, groups++ ? "; " : "- %s: ", title);
    for (size_t c = k, i = 0; c < s->ncorners; ++c)
      if (alike(s, words, c, line)) {
        fputs(i++ ? ", " : "", fp);
        fb_md_write_text(fp, s->corner[c].name);
      }
    fputs(": ", fp);
    fb_md_write_text(fp, line);
  }
  if (groups)
    fputs(".\n", fp);
}

/* The walking-beam bogies, one line each (fb_bogie): their wheels, the
 * lever, the beam and the pivot's spring and damper. */
static void write_bogies(FILE *fp, const fb_scenario *s)
{
  if (!s->nbogies)
    return;
  fputs("- Walking-beam bogies: the wheels of two corners on one side ride at the ends of a "
        "beam that pitches freely about its pivot, and the pivot rides on its spring and "
        "damper to the hull; those corners' own springs, dampers and motion ratios are not "
        "used (docs/scenario-format.md, \"Walking-beam bogies\").\n",
        fp);
  for (size_t i = 0; i < s->nbogies; ++i) {
    const fb_bogie *b = &s->bogie[i];
    const long f = fb_scenario_corner_find(s, b->front),
               r = fb_scenario_corner_find(s, b->rear);
    if (f < 0 || r < 0) /* fb_scenario_check finds both */
      continue;
    fputs("  - ", fp);
    fb_md_write_text(fp, b->name);
    fputs(": ", fp);
    fb_md_write_text(fp, b->front);
    fprintf(fp, " at a = %.10g m ahead of the pivot, ", s->corner[f].x - b->pivot_x);
    fb_md_write_text(fp, b->rear);
    fprintf(fp,
            " at b = %.10g m behind it; the beam %.10g kg, %.10g kg m^2 in pitch about the "
            "pivot; the pivot's spring %.10g N/m, its damper %.10g N s/m.\n",
            b->pivot_x - s->corner[r].x, b->beam_mass, b->beam_inertia, b->spring_k,
            b->damper_c);
  }
}

/* The anti-roll bars (fb_antiroll_bar): their corners and rates. */
static void write_antiroll_bars(FILE *fp, const fb_scenario *s)
{
  for (size_t i = 0; i < s->nantiroll_bars; ++i) {
    const fb_antiroll_bar *b = &s->antiroll_bar[i];
    fputs(i ? "; "
            : "- Anti-roll bars (rates at each wheel in roll, equal and opposite "
              "travels; a wheel lifted alone meets half): ",
          fp);
    fb_md_write_text(fp, b->name);
    fputs(" (", fp);
    fb_md_write_text(fp, b->left);
    fputs(", ", fp);
    fb_md_write_text(fp, b->right);
    fprintf(fp, "): %.10g N/m", b->stiffness);
    if (b->damping > 0.0)
      fprintf(fp, ", %.10g N s/m", b->damping);
  }
  if (s->nantiroll_bars)
    fputs(".\n", fp);
}

/* Body b's bushing j's hull side in System 2 (fb_bushing): its node set,
 * or the surface's nodes within a radius (0: the scenario's). */
static void write_bushing_coupling(FILE *fp, const fb_scenario *s, const fb_bushing *u)
{
  if (u->node_set) {
    fputs(", in System 2 coupled to the node set ", fp);
    fb_md_write_text(fp, u->node_set);
    return;
  }
  const char *surface = u->surface ? u->surface : s->coupling_surface;
  if (!surface)
    return;
  fputs(", in System 2 coupled to the nodes of ", fp);
  fb_md_write_text(fp, surface);
  fprintf(fp, " within %.10g m", u->radius > 0.0 ? u->radius : s->coupling_radius);
}

/* The mounted rigid bodies (fb_body), one line each: mass, what they are
 * mounted on and their bushings. */
static void write_rigid_bodies(FILE *fp, const fb_scenario *s)
{
  if (!s->nbodies)
    return;
  fputs("- Mounted rigid bodies, in six degrees of freedom at small motions, each on its "
        "bushings (six-component springs and dampers) to the hull or to another body; their "
        "weights are their own, beside load.total_weight (docs/scenario-format.md, \"Mounted "
        "rigid bodies\"); the hull moves in six degrees of freedom with them.\n",
        fp);
  for (size_t b = 0; b < s->nbodies; ++b) {
    const fb_body *body = &s->body[b];
    fputs("  - ", fp);
    fb_md_write_text(fp, body->name);
    fprintf(fp, ": %.10g kg on ", body->mass);
    fb_md_write_text(fp, body->parent ? body->parent : "the hull");
    fprintf(fp, ", %zu bushing%s", body->nbushings, body->nbushings == 1 ? "" : "s");
    if (!body->parent && s->has_fe_hull)
      for (size_t j = 0; j < body->nbushings; ++j)
        write_bushing_coupling(fp, s, &body->bushing[j]);
    fputs(".\n", fp);
  }
}

/* The shock absorbers, the springs and, where a corner has them, the
 * stops, of the corners with their own; the bogies and the anti-roll
 * bars. */
static void write_suspensions(FILE *fp, const fb_scenario *s)
{
  write_corners_alike(fp, s, "Shock absorbers", damper_line);
  write_corners_alike(fp, s, "Springs", spring_line);
  int stops = 0;
  for (size_t c = 0; c < s->ncorners; ++c)
    stops |= own_suspension(s, c) && fb_stops_any(&s->corner[c].stops);
  if (stops)
    write_corners_alike(fp, s, "Bump and rebound stops (gap, rate, damping)", stops_line);
  write_bogies(fp, s);
  write_antiroll_bars(fp, s);
  write_rigid_bodies(fp, s);
}

static void write_assumptions(FILE *fp, const cli_run_outputs *o)
{
  const fb_scenario *s = o->scenario;
  fputs("\n## Assumptions\n\n", fp);
  if (s->initial == FB_INITIAL_ZERO)
    fputs("- Initial state: every state zero with gravity switched on at t = 0 (`zero`, the "
          "paper's protocol); the vehicle settles before the road window.\n",
          fp);
  else
    fputs("- Initial state: the static equilibrium under gravity and the load (`static`).\n",
          fp);
  write_payload(fp, s);
  write_suspensions(fp, s);
  fprintf(fp, "- Solver: CVODE, variable-order BDF, rtol %.3g, atol %.3g, ", s->rtol, s->atol);
  if (s->max_step > 0)
    fprintf(fp, "steps at most %.6g s", s->max_step);
  else
    fputs("no step limit", fp);
  fputs("; outputs from the interpolating polynomial, breakpoints at every wheel's entry "
        "into the road window and exit.\n"
        "- Outputs: the scenario's list (docs/vehicle-outputs.md), compressions positive",
        fp);
  if (fb_study_report_torsion_output(o->report) < s->noutputs)
    fputs("; a torsion angle is the roll of the hull's front edge line minus that of its rear "
          "edge line, identically 0 for the rigid hull",
          fp);
  fputs(".\n", fp);
  if (o->hull && o->basis)
    write_fe_hull(fp, o);
  if (o->note)
    fprintf(fp, "- Systems: %s.\n", o->note);
}

/* ---- Runs and modes. */

static void write_runs(FILE *fp, const cli_run_outputs *o)
{
  fputs("\n## Runs\n\n| system | file | samples | steps | rhs evals | wall time [s] |\n"
        "|---|---|---|---|---|---|\n",
        fp);
  for (size_t i = 0; i < o->nruns; ++i) {
    const fb_sim_stats *st = fb_result_stats(o->runs[i].res);
    fprintf(fp, "| %s | system%d.csv | %zu | %ld | %ld | %.3g |\n",
            cli_system_label(o->runs[i].sys), (int)o->runs[i].sys,
            fb_result_nsamples(o->runs[i].res), st->steps, st->rhs_evals, st->wall_seconds);
  }
}

static void write_mode_row(FILE *fp, size_t k, double freq_hz, const char *description)
{
  fprintf(fp, "| %zu | %.4f | ", k + 1, freq_hz);
  fb_md_write_text(fp, description);
  fputs(" |\n", fp);
}

static void write_modes1(FILE *fp, const cli_run_outputs *o)
{
  /* The zero modes: the support's self-stress, and the free horizontal
   * motions of a hull in six degrees of freedom. */
  const size_t nfree = fb_vehicle_free_motions(o->scenario);
  const size_t nself = o->nstatic1 > nfree ? o->nstatic1 - nfree : 0;
  fprintf(fp,
          "\n### System 1 (rigid hull)\n\nUndamped natural frequencies (every damper "
          "removed) at the static equilibrium, each with the part of the vehicle that holds "
          "most of its kinetic energy; %zu zero mode%s of the statically indeterminate "
          "support",
          nself, nself == 1 ? "" : "s");
  if (o->nstatic1 > nself)
    fprintf(fp, " and %zu of the vehicle's free surge, sway and yaw", o->nstatic1 - nself);
  fputs(" left out.\n\n| mode | f_n [Hz] | description |\n|---|---|---|\n", fp);
  for (size_t k = 0; k < o->nmodes1; ++k)
    write_mode_row(fp, k, o->modes1[k].freq_hz, o->modes1[k].description);
}

static void write_mode_pictures(FILE *fp, const cli_run_outputs *o)
{
  const fb_mode_set *ms = o->modes2;
  if (!o->figures) {
    fputs("\nNo mode pictures: the run had `--no-figures`.\n", fp);
    return;
  }
  if (fb_mesh_nelements(o->hull->mesh) == 0) {
    fputs("\nNo mode pictures: the hull is a superelement, whose interface nodes have no "
          "surface to draw.\n",
          fp);
    return;
  }
  size_t pictured[CLI_MAX_PICTURED_MODES];
  const size_t npictured =
      cli_pictured_modes(o->scenario, ms, pictured, CLI_MAX_PICTURED_MODES);
  fputs(
      o->scenario->npictured_modes
          ? "\nThe modes the scenario lists (`report.mode_pictures` or `--picture-modes`):\n"
          : "\nThe modes pictured are chosen by what they are: the first of the hull's "
            "bounce, roll and pitch, each mounted body's (the first it holds the most kinetic "
            "energy in, else the one it holds its largest share in), the first wheel hop and "
            "the first two elastic "
            "modes of the hull.\n",
      fp);
  /* A kind the rule names that the listed modes lack is said, not
   * pictured. */
  size_t nelastic = 0, nhop = 0;
  for (size_t k = 0; ms->part && k < ms->nmodes; ++k) {
    nelastic += ms->part[k].kind == FB_MODE_HULL_ELASTIC;
    nhop += ms->part[k].kind == FB_MODE_WHEEL;
  }
  static const char *const lacking[4] = {NULL, "a wheel hop", "an elastic mode of the hull",
                                         "an elastic mode of the hull or a wheel hop"};
  const int lacks = 2 * (nelastic == 0) + (nhop == 0);
  if (!o->scenario->npictured_modes && ms->part && lacks)
    fprintf(fp, "None of the %zu modes listed is %s.\n", ms->nmodes, lacking[lacks]);
  /* One picture per paragraph: a viewer shows them one under another. */
  for (size_t i = 0; i < npictured; ++i) {
    const size_t k = pictured[i];
    char name[32];
    cli_mode_picture_name(k + 1, name, sizeof name);
    fprintf(fp, "\n![System 2, mode %zu: %.3f Hz, ", k + 1, ms->freq_hz[k]);
    fb_md_write_text(fp, ms->description[k]);
    fprintf(fp, "](%s)\n", name);
  }
}

static void write_modes2(FILE *fp, const cli_run_outputs *o)
{
  const fb_mode_set *ms = o->modes2;
  fprintf(fp,
          "\n### System 2 (flexible hull)\n\nThe %zu lowest modes of the whole undamped "
          "vehicle (the finite-element hull%s with the mounted bodies, the suspensions and "
          "the tires at its attachment points), each normalised so that its largest "
          "displacement over the mounted bodies and the hull is 1; %zu horizontal rigid-body "
          "mode%s of zero frequency left out.\n\n| mode | f_n [Hz] | description |\n"
          "|---|---|---|\n",
          ms->nmodes,
          o->basis && o->basis->ncoords < o->basis->ndof
              ? " in its modal basis, the modes within the band the basis converged over "
                "(`flexbond modes --system flexible` gives the nodal model's)"
              : "",
          ms->nfree, ms->nfree == 1 ? "" : "s");
  for (size_t k = 0; k < ms->nmodes; ++k)
    write_mode_row(fp, k, ms->freq_hz[k], ms->description[k]);
  write_mode_pictures(fp, o);
}

/* ---- Figures and tables of the outputs. */

/* The model of every system that ran: its multibond graph (the paper's
 * Fig. 5) and its block diagram (Fig. 6), drawn by run from the graph it
 * simulated (docs/diagrams.md). */
static void write_model(FILE *fp, const cli_run_outputs *o)
{
  if (!o->figures)
    return;
  fputs("\n## Model\n\nEach system's multibond graph, one box per subsystem instance "
        "(causal strokes, multibond dimensions in brackets), and its block diagram: the top "
        "level with one block per subsystem, one level down inside each (docs/diagrams.md).\n",
        fp);
  /* Not numbered: the scenario's own figure numbers may be anything. */
  static const char *const captions[CLI_RUN_NDIAGRAMS] = {"Multibond graph", "Block diagram"};
  for (size_t i = 0; i < o->nruns; ++i)
    for (size_t k = 0; k < CLI_RUN_NDIAGRAMS; ++k) {
      char name[64];
      cli_run_diagram_file(k, o->runs[i].sys, name, sizeof name);
      fprintf(fp, "\n![%s, %s](%s)\n", captions[k], cli_system_label(o->runs[i].sys), name);
    }
}

/* Output k in the Figures' words: its figure number, else its title. */
static void write_figure_name(FILE *fp, const fb_output_spec *fig)
{
  if (fig->figure > 0)
    fprintf(fp, "Fig. %d", fig->figure);
  else
    fb_md_write_text(fp, fig->title);
}

/* The window figure k shows (cli_run_figure_window over System 1's run);
 * 0 when it shows the whole run. */
static int figure_window(const cli_run_outputs *o, size_t k, double w[2])
{
  cli_run_figure_window(&o->scenario->output[k], o->runs[0].res, &w[0], &w[1]);
  return w[0] < w[1];
}

/* Which span each figure shows: the whole run, except the figures whose
 * outputs have a window (`window`) the run covers, grouped by window; an
 * output's window outside the run is said too. */
static void write_figure_windows(FILE *fp, const cli_run_outputs *o)
{
  const fb_scenario *s = o->scenario;
  size_t groups = 0;
  for (size_t k = 0; k < s->noutputs; ++k) {
    double w[2], other[2];
    if (!figure_window(o, k, w))
      continue;
    size_t seen = 0;
    for (size_t j = 0; j < k; ++j)
      seen += figure_window(o, j, other) && other[0] == w[0] && other[1] == w[1];
    if (seen)
      continue;
    fputs(groups++ ? "; "
                   : "A figure shows the whole run, except where its output has a "
                     "window (`window`): ",
          fp);
    size_t n = 0;
    for (size_t j = k; j < s->noutputs; ++j)
      n += figure_window(o, j, other) && other[0] == w[0] && other[1] == w[1];
    for (size_t j = k, i = 0; j < s->noutputs; ++j)
      if (figure_window(o, j, other) && other[0] == w[0] && other[1] == w[1]) {
        fputs(i == 0 ? "" : i + 1 == n ? " and " : ", ", fp);
        write_figure_name(fp, &s->output[j]);
        ++i;
      }
    fprintf(fp, ", from %.10g to %.10g s", w[0], w[1]);
  }
  fputs(groups ? "." : "Each figure shows the whole run.", fp);
  for (size_t k = 0; k < s->noutputs; ++k) {
    const fb_output_spec *fig = &s->output[k];
    double w[2];
    if (!(fig->window[0] < fig->window[1]) || figure_window(o, k, w))
      continue;
    fputc(' ', fp);
    write_figure_name(fp, fig);
    fprintf(fp, " shows the whole run: its window, %.10g to %.10g s, lies outside it.",
            fig->window[0], fig->window[1]);
  }
}

static void write_figures(FILE *fp, const cli_run_outputs *o)
{
  fputs("\n## Figures\n\n", fp);
  if (!o->figures) {
    fputs("No figures: the run had `--no-figures`. The curves are in the CSV files.\n", fp);
    return;
  }
  write_figure_windows(fp, o);
  fputs(o->diff ? " Each figure shows both systems above and System 2 - System 1 below.\n"
                : "\n",
        fp);
  for (size_t k = 0; k < o->scenario->noutputs; ++k) {
    const fb_output_spec *fig = &o->scenario->output[k];
    char name[FB_ERR_KEY_MAX];
    cli_run_figure_file(fig, name, sizeof name);
    fputs("\n![", fp);
    if (fig->figure > 0)
      fprintf(fp, "Fig. %d. ", fig->figure);
    fb_md_write_text(fp, fig->title);
    fprintf(fp, "](%s)\n", name);
  }
}

/* The Bode figures of the systems that ran (cli_bode_write_figures). */
static void write_frequency_response(FILE *fp, const cli_run_outputs *o)
{
  if (!o->figures)
    return;
  fputs("\n## Frequency response\n\n", fp);
  const fb_study_freq *fs = o->freq[0] ? o->freq[0] : o->freq[1];
  if (!fs) {
    fputs("Not computed: ", fp);
    fb_md_write_text(fp, o->freq_note);
    fputs("\n", fp);
    return;
  }
  const double *f = fb_study_freq_hz(fs);
  fprintf(fp,
          "Each output's response to a road height on the left or on the right track, 1 m at "
          "the leading wheel, which the track's other wheels meet later by their distance "
          "behind it at %.4g km/h: |H| and phase from %g to %g Hz, from the vehicle's linear "
          "model (`flexbond freq`, docs/frequency-response.md)%s. Power outputs have none.\n",
          3.6 * o->scenario->speed, f[0], f[fb_study_freq_nfreq(fs) - 1],
          (o->freq[0] && fb_study_freq_linearised(o->freq[0])) ||
                  (o->freq[1] && fb_study_freq_linearised(o->freq[1]))
              ? "; its nonlinear laws are linearised at the static equilibrium"
              : "");
  for (size_t k = 0; k < o->scenario->noutputs; ++k) {
    if (!fb_study_freq_has_output(fs, k))
      continue;
    fputs("\n![", fp);
    fb_md_write_text(fp, o->scenario->output[k].title);
    /* An output's name is letters, digits and '_' (checked at load), as
     * in the figures' links above. */
    fprintf(fp, ": frequency response](bode_%s.png)\n", o->scenario->output[k].name);
  }
}

/* The animation of each system that ran (flexbond run --animate). */
static void write_animation(FILE *fp, const cli_run_outputs *o)
{
  if (!o->animate || !o->animate->enabled)
    return;
  fputs("\n## Animation\n\n", fp);
  fprintf(fp,
          "Each system's motion in the road window at %g frames per second of the run's "
          "time (linear between its samples), every displacement from the vehicle's state "
          "at the window's start, as the first wheel enters it. The hull's points are "
          "drawn at their position plus the displacement times the stated factor; the "
          "mounted bodies (cubes) and the wheels are schematic, to the hull's size. "
          "ParaView opens the `.pvd` time series: the displacement in metres is point data "
          "(`displacement`), `part` tells the hull (0), the bodies (1) and the wheels (2) "
          "apart (docs/animation.md).\n",
          o->animate->fps);
  for (size_t i = 0; i < o->nruns; ++i) {
    const cli_animation_info *a = &o->runs[i].anim;
    char pvd[64], gif[64];
    cli_animation_file(o->runs[i].sys, "pvd", 0, pvd, sizeof pvd);
    cli_animation_file(o->runs[i].sys, "gif", 0, gif, sizeof gif);
    fprintf(fp,
            "\n%s: %zu frames from t = %.3f to %.3f s, the largest displacement %.4g m, "
            "drawn %.3g times; `%s`.\n",
            cli_system_label(o->runs[i].sys), a->nframes, a->t0, a->t1, a->umax, a->warp, pvd);
    if (a->gif) {
      fprintf(fp, "\n![%s ", cli_system_label(o->runs[i].sys));
      write_road(fp, o->scenario, 0);
      fprintf(fp, "](%s)\n", gif);
    } else if (o->animate->gif) {
      fputs("\nNo GIF: the hull is a superelement, whose interface nodes have no surface to "
            "draw.\n",
            fp);
    }
  }
}

/* "| quantity | unit |" of output k. */
static void write_output_cells(FILE *fp, const cli_run_outputs *o, size_t k)
{
  fputs("| ", fp);
  fb_md_write_text(fp, o->scenario->output[k].label);
  fputs(" | ", fp);
  fb_md_write_text(fp, fb_study_report_unit(o->report, k));
  fputs(" |", fp);
}

static void write_cells(FILE *fp, const double *v, size_t n)
{
  for (size_t i = 0; i < n; ++i) {
    fputc(' ', fp);
    md_number(fp, v[i]);
    fputs(" |", fp);
  }
}

static void write_comparison_table(FILE *fp, const cli_run_outputs *o)
{
  const size_t nout = o->scenario->noutputs;
  fprintf(fp,
          "\n## Comparison\n\nPeaks and the largest difference from the road window's start "
          "(%.4f s) to the end of the run, RMS over the road window (%.4f s to %.4f s); "
          "the last column is the largest |System 2 - System 1| relative to System 1's "
          "peak-to-peak range there.\n\n"
          "| output | unit | peak S1 | peak S2 | peak change | RMS S1 | RMS S2 | "
          "max abs S2 - S1 | at t [s] | / S1 range |\n"
          "|---|---|---|---|---|---|---|---|---|---|\n",
          o->bump_window[0], o->bump_window[0], o->bump_window[1]);
  for (size_t k = 0; k < nout; ++k) {
    const fb_output_stats *s1 = fb_run_summary_output(o->runs[0].sum, k),
                          *s2 = fb_run_summary_output(o->runs[1].sum, k);
    const fb_output_cmp *c = &o->cmp[k];
    write_output_cells(fp, o, k);
    write_cells(fp, (const double[]){s1->peak, s2->peak}, 2);
    fputc(' ', fp);
    md_percent(fp, c->peak_change, 1);
    fputs(" |", fp);
    write_cells(fp, (const double[]){s1->rms, s2->rms, c->max_diff, c->max_diff_time}, 4);
    fputc(' ', fp);
    md_percent(fp, c->rel_diff, 0);
    fputs(" |\n", fp);
  }
}

/* ---- System 2 at the converged mesh. */

static void write_converged_intro(FILE *fp, const cli_run_outputs *o)
{
  const fb_scenario *s = o->scenario;
  const fb_hull_basis *b = o->converged_basis;
  fprintf(fp,
          "\n## At a converged mesh\n\nThe mesh at density %d makes the hull too stiff "
          "(Assumptions, \"Mesh convergence\"). System 2 ran again on the hull refined to "
          "density %d "
          "(`hull.mesh.converged_density`; `system2_converged.csv`): %zu DOFs in the %zu "
          "coordinates of its automatic modal basis, its first elastic free-free mode at %.4g "
          "Hz against %.4g Hz at "
          "density %d",
          fb_scenario_hull_density(s), o->converged_density, b->ndof, b->ncoords, b->f1_hz,
          o->basis ? o->basis->f1_hz : NAN, fb_scenario_hull_density(s));
  const double e =
      fb_study_run_worst_basis_error(fb_study_report_converged(o->report), s->noutputs, NULL);
  if (isfinite(e))
    fprintf(fp, ", its basis's estimated error at most %.2g %% of an output's range", 100 * e);
  fputs(". Each mesh's System 2 against System 1 ", fp);
  write_road(fp, s, 0);
  fprintf(fp,
          ", as in the Comparison; the "
          "last column is the two meshes' System 2 against each other, over System 1's "
          "range.\n\n| output | unit | max abs S2 - S1 / S1 range, density %d | the same, "
          "density %d | peak change, density %d | peak change, density %d | max abs S2 "
          "(density %d) - S2 (density %d) / S1 range |\n|---|---|---|---|---|---|---|\n",
          fb_scenario_hull_density(s), o->converged_density, fb_scenario_hull_density(s),
          o->converged_density, o->converged_density, fb_scenario_hull_density(s));
}

static void write_converged(FILE *fp, const cli_run_outputs *o)
{
  const fb_scenario *s = o->scenario;
  if (!o->cmp_converged) {
    if (o->diff && s->hull_converged_density && !fb_scenario_hull_density(s))
      fputs("\n## At a converged mesh\n\n`hull.mesh.converged_density` refines the "
            "generator's mesh; this hull's mesh is used as it is: no second mesh ran.\n",
            fp);
    else if (o->diff && s->hull_converged_density)
      fprintf(fp,
              "\n## At a converged mesh\n\nThis run's mesh (density %d) is at or above "
              "`hull.mesh.converged_density` = %d: no second mesh ran.\n",
              fb_scenario_hull_density(s), s->hull_converged_density);
    return;
  }
  write_converged_intro(fp, o);
  for (size_t k = 0; k < s->noutputs; ++k) {
    const fb_output_cmp *c1 = &o->cmp[k], *c3 = &o->cmp_converged[k];
    write_output_cells(fp, o, k);
    const double cells[] = {c1->rel_diff, c3->rel_diff, c1->peak_change, c3->peak_change,
                            fb_study_report_mesh_diff(o->report, k)};
    const int signed_cell[] = {0, 0, 1, 1, 0};
    for (size_t i = 0; i < sizeof cells / sizeof cells[0]; ++i) {
      fputc(' ', fp);
      md_percent(fp, cells[i], signed_cell[i]);
      fputs(" |", fp);
    }
    fputc('\n', fp);
  }
}

static void write_outputs_table(FILE *fp, const cli_run_outputs *o)
{
  const size_t nout = o->scenario->noutputs;
  fprintf(fp,
          "\n## Outputs\n\n%s. Static value before the road window, extremes from its start "
          "(%.4f s) to the end of the run, RMS over the road window (%.4f s to %.4f "
          "s).\n\n| output | unit | static | peak | at t [s] | min | at t [s] | RMS |\n"
          "|---|---|---|---|---|---|---|---|\n",
          cli_system_label(o->runs[0].sys), o->bump_window[0], o->bump_window[0],
          o->bump_window[1]);
  for (size_t k = 0; k < nout; ++k) {
    const fb_output_stats *st = fb_run_summary_output(o->runs[0].sum, k);
    write_output_cells(fp, o, k);
    write_cells(fp,
                (const double[]){st->static_value, st->peak, st->peak_time, st->min,
                                 st->min_time, st->rms},
                6);
    fputc('\n', fp);
  }
}

/* ---- Conclusions: one paragraph, each sentence picked by the numbers. */

/* "Over the bump, System 2 departs from System 1 by up to ...":
 * the largest relative difference and which outputs pass FB_STUDY_NOTABLE_DIFF. */
static void conclude_differences(FILE *fp, const cli_run_outputs *o)
{
  const size_t nout = o->scenario->noutputs;
  const fb_study_differences d = fb_study_report_differences(o->report, FB_STUDY_CMP_SYSTEM2);
  const size_t largest = d.largest, nnotable = d.nnotable, nfinite = d.nvarying;
  if (largest == nout) {
    fputs("No output of System 1 varies ", fp);
    write_road(fp, o->scenario, 0);
    fputs(", so no difference can be scaled.", fp);
    return;
  }
  write_road(fp, o->scenario, 1);
  fprintf(fp,
          ", System 2 departs from System 1 by up to %.1f %% of System 1's "
          "peak-to-peak range, in the ",
          100 * o->cmp[largest].rel_diff);
  fb_md_write_text(fp, o->scenario->output[largest].label);
  fprintf(fp, " (at t = %.3f s)", o->cmp[largest].max_diff_time);
  if (nnotable == 0) {
    fprintf(fp, "; all %zu outputs that vary in System 1 agree within %.0f %%.", nfinite,
            100 * FB_STUDY_NOTABLE_DIFF);
    return;
  }
  fprintf(fp, "; %zu of the %zu outputs that vary in System 1 %s by more than %.0f %% (",
          nnotable, nfinite, nnotable == 1 ? "differs" : "differ", 100 * FB_STUDY_NOTABLE_DIFF);
  size_t listed = 0;
  for (size_t k = 0; k < nout; ++k)
    if (fb_study_report_notable(o->report, FB_STUDY_CMP_SYSTEM2, k)) {
      fputs(listed++ ? ", " : "", fp);
      fb_md_write_text(fp, o->scenario->output[k].label);
      fprintf(fp, " %.1f %%", 100 * o->cmp[k].rel_diff);
    }
  fputs(").", fp);
}

/* One clause on run's torsion angle: identically zero (the rigid hull's
 * by construction), or how far the hull twists over the bump. first:
 * the clause opens the sentence. */
static void torsion_clause(FILE *fp, const fb_scenario *s, const fb_study_run *r, size_t k,
                           int first)
{
  const fb_output_stats *st = fb_run_summary_output(r->sum, k);
  const char *unit = fb_result_col_unit(r->res, fb_run_summary_column(r->sum, k));
  const char *hull = r->sys == FB_SYSTEM_RIGID ? "rigid" : "flexible";
  fprintf(fp, "%s %s hull's torsion angle ", first ? " The" : "; the", hull);
  if (fb_study_run_max_abs(r, k) == 0) {
    fputs("is identically zero", fp);
    return;
  }
  fputs("reaches ", fp);
  md_value_unit(fp, fmax(fabs(st->peak), fabs(st->min)), unit);
  fputc(' ', fp);
  write_road(fp, s, 0);
  fputs(" (", fp);
  md_value_unit(fp, st->peak, unit);
  fprintf(fp, " at %.3f s, ", st->peak_time);
  md_value_unit(fp, st->min, unit);
  fprintf(fp, " at %.3f s; static ", st->min_time);
  md_value_unit(fp, st->static_value, unit);
  fputc(')', fp);
}

/* The torsion angles of every run, in one sentence. */
static void conclude_torsion(FILE *fp, const cli_run_outputs *o)
{
  const size_t k = fb_study_report_torsion_output(o->report);
  if (k == o->scenario->noutputs)
    return; /* not among the outputs */
  for (size_t i = 0; i < o->nruns; ++i)
    torsion_clause(fp, o->scenario, fb_study_report_run(o->report, i), k, i == 0);
  fputc('.', fp);
}

/* Peak changes beyond FB_STUDY_NOTABLE_CHANGE, and the largest RMS change. */
static void conclude_peaks(FILE *fp, const cli_run_outputs *o)
{
  const size_t nout = o->scenario->noutputs;
  const size_t largest_rms = fb_study_report_largest_rms_change(o->report);
  size_t listed = 0;
  for (size_t k = 0; k < nout; ++k) {
    const double p = o->cmp[k].peak_change;
    if (!isfinite(p) || fabs(p) <= FB_STUDY_NOTABLE_CHANGE)
      continue;
    fprintf(fp, "%s%s the peak of the ", listed++ ? ", " : " Compared with System 1, System 2 ",
            p > 0 ? "raises" : "lowers");
    fb_md_write_text(fp, o->scenario->output[k].label);
    fprintf(fp, " by %.1f %% (", 100 * fabs(p));
    md_number(fp, fb_run_summary_output(o->runs[0].sum, k)->peak);
    fputs(" to ", fp);
    md_value_unit(fp, fb_run_summary_output(o->runs[1].sum, k)->peak,
                  fb_study_report_unit(o->report, k));
    fputc(')', fp);
  }
  if (listed)
    fputc('.', fp);
  else
    fprintf(fp, " Every peak with a non-zero System 1 value changes by %.0f %% or less.",
            100 * FB_STUDY_NOTABLE_CHANGE);
  if (largest_rms < nout) {
    fputs(" The largest change of an RMS ", fp);
    write_road(fp, o->scenario, 0);
    fputs(" is the ", fp);
    fb_md_write_text(fp, o->scenario->output[largest_rms].label);
    fprintf(fp, "'s, %+.1f %%.", 100 * o->cmp[largest_rms].rms_change);
  }
}

/* With one system: the output that grows the most on the road
 * relative to its static value (fb_study_report_largest_growth). */
static void conclude_single(FILE *fp, const cli_run_outputs *o)
{
  const size_t nout = o->scenario->noutputs;
  const cli_run_system *r = &o->runs[0];
  fprintf(fp, "Only %s ran, so nothing is compared (%s).", cli_system_label(r->sys),
          o->scenario->has_fe_hull ? "`--system both` runs both"
                                   : "the scenario has no finite-element hull for System 2");
  double factor = 0;
  const size_t largest = fb_study_report_largest_growth(o->report, &factor);
  if (largest < nout) {
    const fb_output_stats *st = fb_run_summary_output(r->sum, largest);
    const char *unit = fb_result_col_unit(r->res, fb_run_summary_column(r->sum, largest));
    fputc(' ', fp);
    write_road(fp, o->scenario, 1);
    fputs(", the ", fp);
    fb_md_write_text(fp, o->scenario->output[largest].label);
    fputs(" grows the most relative to its static value: its peak, ", fp);
    md_value_unit(fp, st->peak, unit);
    fprintf(fp, " at %.3f s, is %.3g times its static ", st->peak_time, factor);
    md_value_unit(fp, st->static_value, unit);
    fputc('.', fp);
  }
  if (r->sys == FB_SYSTEM_FLEXIBLE)
    conclude_torsion(fp, o);
}

/* ---- Ride comfort of a mounted body (src/ride, docs/ride-metrics.md). */

/* The ride table's rows: label, unit and value. */
enum { NRIDE_ROWS = 12 };
static const char *const ride_labels[NRIDE_ROWS][2] = {
    {"Wk-weighted r.m.s. a_w (ISO 2631-1)", "m/s^2"},
    {"MTVV (1 s running r.m.s.)", "m/s^2"},
    {"VDV", "m/s^1.75"},
    {"VDV / 8.5 (ISO 2631-1 caution zone)", "-"},
    {"crest factor", "-"},
    {"crest factor above 9 (1: use VDV)", "-"},
    {"jerk peak", "m/s^3"},
    {"jerk r.m.s.", "m/s^3"},
    {"absorbed power (limit 6 W)", "W"},
    {"NRMM peak, 30 Hz low-pass (limit 2.5 g = 24.5)", "m/s^2"},
    {"ISO 2631-5 dose D_z", "m/s^2"},
    {"ISO 2631-5 S_ed (window as the day)", "MPa"},
};

static double ride_value(const fb_ride_metrics *m, size_t row)
{
  const double values[NRIDE_ROWS] = {m->a_w_rms,   m->mtvv,     m->vdv,
                                     m->vdv_ratio, m->crest,    m->crest_over_9,
                                     m->jerk_peak, m->jerk_rms, m->absorbed_power,
                                     m->nrmm_peak, m->dz,       m->se};
  return values[row];
}

static void write_ride(FILE *fp, const cli_run_outputs *o)
{
  const size_t kr = fb_study_ride_output(o->scenario);
  fputs("\n## Ride comfort", fp);
  if (kr < o->scenario->noutputs) {
    fputs(" (", fp);
    fb_md_write_text(fp, o->scenario->output[kr].label);
    fputc(')', fp);
  }
  fputs("\n\n", fp);
  const cli_run_system *first = NULL;
  fb_ride_metrics ride[CLI_MAX_SYSTEMS];
  int has[CLI_MAX_SYSTEMS] = {0};
  double window[2] = {0, 0};
  for (size_t i = 0; i < o->nruns && i < CLI_MAX_SYSTEMS; ++i) {
    const cli_run_system *r = &o->runs[i];
    const char *note = NULL;
    has[i] = fb_run_summary_ride(r->sum, &ride[i], first ? NULL : window, &note);
    if (has[i]) {
      if (!first)
        first = r;
      continue;
    }
    fprintf(fp, "%s: no ride metrics (", cli_system_label(r->sys));
    fb_md_write_text(fp, note);
    fputs(").\n\n", fp);
  }
  if (!first)
    return;
  fputs("The output `", fp);
  fb_md_write_text(fp, o->scenario->output[kr].name);
  fprintf(fp,
          "`, from the first wheel's entry into the road window (%.3f s) to "
          "the end of the run (%.3f s), weighted and evaluated per ISO 2631-1:1997, with the "
          "military measures: Pradko & Lee's absorbed power against 6 W, the NRMM peak "
          "against 2.5 g and the ISO 2631-5:2004 vertical spinal dose (flexbond's "
          "docs/ride-metrics.md).\n\n| metric | unit |",
          window[0], window[1]);
  for (size_t i = 0; i < o->nruns && i < CLI_MAX_SYSTEMS; ++i)
    if (has[i])
      fprintf(fp, " %s |", cli_system_label(o->runs[i].sys));
  fputs("\n|---|---|", fp);
  for (size_t i = 0; i < o->nruns && i < CLI_MAX_SYSTEMS; ++i)
    if (has[i])
      fputs("---|", fp);
  fputc('\n', fp);
  for (size_t k = 0; k < NRIDE_ROWS; ++k) {
    fprintf(fp, "| %s | %s |", ride_labels[k][0], ride_labels[k][1]);
    for (size_t i = 0; i < o->nruns && i < CLI_MAX_SYSTEMS; ++i) {
      if (!has[i])
        continue;
      fputc(' ', fp);
      md_number(fp, ride_value(&ride[i], k));
      fputs(" |", fp);
    }
    fputc('\n', fp);
  }
}

/* ---- Tire contact: the verdict of each system, from its reactions. */

/* How many of s's corners have a tire that can pull. */
static size_t corners_pulling(const fb_scenario *s)
{
  size_t n = 0;
  for (size_t c = 0; c < s->ncorners; ++c)
    n += fb_corner_tire_model(&s->corner[c])->pulls != 0;
  return n;
}

/* The tires whose reaction spikes, or the largest ratio when none does. */
static void write_contact_spikes(FILE *fp, const fb_study_report *rep, const fb_study_run *r)
{
  const fb_scenario *s = fb_study_report_scenario(rep);
  char peak[32], stat[32];
  size_t n = 0, c_max = 0;
  fb_study_report_contact_extremes(rep, r, &c_max, NULL);
  int constant_damper = 0; /* a spiking tire's damper has a constant coefficient */
  for (size_t c = 0; c < s->ncorners; ++c) {
    if (!fb_run_summary_contact_spike(r->sum, c))
      continue;
    constant_damper |= !fb_corner_tire_model(&s->corner[c])->soft_landing;
    fputs(n++ ? "; "
              : "  Reaction spikes, above " CLI_CONTACT_SPIKE_TEXT
                " times the static reaction: ",
          fp);
    fb_md_write_text(fp, s->corner[c].name);
    fprintf(fp, " %s N at %.3f s (%.1f times its static %s N)",
            number_text(fb_run_summary_contact(r->sum, c)->peak, peak, sizeof peak),
            fb_run_summary_contact(r->sum, c)->peak_time,
            fb_run_summary_contact_ratio(r->sum, c),
            number_text(fb_run_summary_contact(r->sum, c)->static_value, stat, sizeof stat));
  }
  if (n) {
    fputs(constant_damper
              ? ". A tire damper of constant coefficient meets a landing wheel with tire_c "
                "times its speed at once; `wheel.tire_contact: hunt_crossley` lets the "
                "damping grow from zero with the deflection (docs/scenario-format.md).\n"
              : ".\n",
          fp);
    return;
  }
  fprintf(fp, "  No reaction exceeds " CLI_CONTACT_SPIKE_TEXT
              " times its static value (the largest, ");
  fb_md_write_text(fp, s->corner[c_max].name);
  fprintf(fp, ", %.2f times).\n", fb_run_summary_contact_ratio(r->sum, c_max));
}

/* What a contact-loss interval is, for the tire models the corners have. */
static void write_loss_kinds(FILE *fp, const fb_study_report *rep, size_t nloss)
{
  const fb_scenario *s = fb_study_report_scenario(rep);
  const size_t bilateral = corners_pulling(s);
  fprintf(fp, "%zu interval%s where a tire", nloss, nloss == 1 ? "" : "s");
  if (bilateral == s->ncorners)
    fputs("'s normal reaction is tensile (the linear tire pulls the wheel down; a real one "
          "would leave the road):",
          fp);
  else if (bilateral == 0)
    fputs(" carries no load (its reaction is zero: the wheel is leaving or off the road):", fp);
  else
    fputs(" carries no load (a unilateral tire's reaction is zero: the wheel is leaving or off "
          "the road; a bilateral one's is tensile, given with its lowest value):",
          fp);
}

static void write_contact_verdict(FILE *fp, const fb_study_report *rep, const fb_study_run *r)
{
  const fb_scenario *s = fb_study_report_scenario(rep);
  char force[32];
  fprintf(fp, "- %s: ", cli_system_label(r->sys));
  if (fb_run_summary_nlosses(r->sum) == 0) {
    size_t c_min = 0;
    fb_study_report_contact_extremes(rep, r, NULL, &c_min);
    fprintf(fp,
            "every tire stays in compression over the whole run; from the road window's start "
            "on, the smallest normal reaction is %s N (",
            number_text(fb_run_summary_contact(r->sum, c_min)->min, force, sizeof force));
    fb_md_write_text(fp, s->corner[c_min].name);
    fprintf(fp, " tire, t = %.3f s).\n", fb_run_summary_contact(r->sum, c_min)->min_time);
    return;
  }
  write_loss_kinds(fp, rep, fb_run_summary_nlosses(r->sum));
  for (size_t i = 0; i < fb_run_summary_nlosses(r->sum); ++i) {
    const fb_contact_loss *t = fb_run_summary_loss(r->sum, i);
    fputs(i ? "; " : " ", fp);
    fb_md_write_text(fp, s->corner[t->corner].name);
    fprintf(fp, " from %.3f to %.3f s", t->t_start, t->t_end);
    if (fb_corner_tire_model(&s->corner[t->corner])->pulls)
      fprintf(fp, " (down to %s N at %.3f s)", number_text(t->min_force, force, sizeof force),
              t->t_min);
  }
  fputs(".\n", fp);
}

/* What each tire model present means, with its corners when they
 * differ: the models in the order the corners first name them. */
static void write_tire_models(FILE *fp, const fb_study_report *rep)
{
  const fb_scenario *s = fb_study_report_scenario(rep);
  for (size_t k = 0; k < s->ncorners; ++k) {
    const fb_tire_model *m = fb_corner_tire_model(&s->corner[k]);
    size_t seen = 0;
    for (size_t c = 0; c < k; ++c)
      seen += fb_corner_tire_model(&s->corner[c]) == m;
    if (seen)
      continue;
    fputs(k ? "; " : "", fp);
    if (fb_study_report_tires_with(rep, m) == s->ncorners) {
      fputs("every tire is ", fp);
      write_named(fp, m->name, m->meaning);
      continue;
    }
    for (size_t c = k, i = 0; c < s->ncorners; ++c)
      if (fb_corner_tire_model(&s->corner[c]) == m) {
        fputs(i++ ? ", " : "", fp);
        fb_md_write_text(fp, s->corner[c].name);
      }
    fputs(": ", fp);
    write_named(fp, m->name, m->meaning);
  }
  fputs(" (`wheel.tire_contact`).", fp);
}

static void write_contact(FILE *fp, const cli_run_outputs *o)
{
  fputs("\n## Tire contact\n\nThe normal reaction of every tire (tire spring plus tire "
        "damper, compression positive) over the whole run; ",
        fp);
  write_tire_models(fp, o->report);
  fputs(" A reaction above " CLI_CONTACT_SPIKE_TEXT
        " times its static value (just before the road window) is flagged as a spike: "
        "the ride over a road moves a tire's load about its static value, an impact "
        "multiplies it.\n\n",
        fp);
  for (size_t i = 0; i < o->nruns; ++i) {
    write_contact_verdict(fp, o->report, fb_study_report_run(o->report, i));
    write_contact_spikes(fp, o->report, fb_study_report_run(o->report, i));
  }
}

/* "At the converged mesh ...": whether the comparison's verdict (which
 * outputs differ by more than FB_STUDY_NOTABLE_DIFF) is the same on the refined
 * hull, and by how much the largest difference moved. */
static void conclude_converged(FILE *fp, const cli_run_outputs *o)
{
  if (!o->cmp_converged)
    return;
  const size_t nout = o->scenario->noutputs;
  const fb_study_differences d1 = fb_study_report_differences(o->report, FB_STUDY_CMP_SYSTEM2),
                             d3 =
                                 fb_study_report_differences(o->report, FB_STUDY_CMP_CONVERGED);
  if (d1.largest == nout || d3.largest == nout)
    return;
  const size_t changed = fb_study_report_mesh_crossings(o->report);
  fprintf(fp,
          " At the converged mesh (density %d) System 2 departs from System 1 by up to %.1f %% "
          "of System 1's range, in the ",
          o->converged_density, 100 * o->cmp_converged[d3.largest].rel_diff);
  fb_md_write_text(fp, o->scenario->output[d3.largest].label);
  fprintf(fp, ", against %.1f %% at density %d: ", 100 * o->cmp[d1.largest].rel_diff,
          fb_scenario_hull_density(o->scenario));
  if (changed == 0 && d3.nnotable == 0)
    fprintf(fp,
            "the conclusion stands, every output that varies agrees within %.0f %% on "
            "both meshes.",
            100 * FB_STUDY_NOTABLE_DIFF);
  else if (changed == 0)
    fprintf(fp, "the same %zu output%s differ%s by more than %.0f %% on both meshes.",
            d3.nnotable, d3.nnotable == 1 ? "" : "s", d3.nnotable == 1 ? "s" : "",
            100 * FB_STUDY_NOTABLE_DIFF);
  else
    fprintf(fp,
            "the conclusion changes for %zu output%s, which cross%s the %.0f %% line between "
            "the meshes (the table \"At a converged mesh\").",
            changed, changed == 1 ? "" : "s", changed == 1 ? "es" : "",
            100 * FB_STUDY_NOTABLE_DIFF);
  /* What the softer hull does change: how far it twists. */
  const size_t t = fb_study_report_torsion_output(o->report);
  const cli_run_system *flexible = flexible_run(o);
  if (t == nout || !flexible)
    return;
  const fb_study_run *r1 = fb_study_report_run(o->report, (size_t)(flexible - o->runs)),
                     *r3 = fb_study_report_converged(o->report);
  const double a1 = fb_study_run_max_abs(r1, t), a3 = fb_study_run_max_abs(r3, t);
  const char *unit = fb_result_col_unit(r3->res, fb_run_summary_column(r3->sum, t));
  fputs(" The flexible hull's torsion angle reaches ", fp);
  md_value_unit(fp, a3, unit);
  fputs(" at the converged mesh against ", fp);
  md_value_unit(fp, a1, unit);
  fputs(" (", fp);
  md_percent(fp, ratio(a3 - a1, a1), 1);
  fputs(").", fp);
}

static void write_conclusions(FILE *fp, const cli_run_outputs *o)
{
  fputs("\n## Conclusions\n\n", fp);
  if (o->diff) {
    conclude_differences(fp, o);
    conclude_torsion(fp, o);
    conclude_peaks(fp, o);
    conclude_converged(fp, o);
  } else {
    conclude_single(fp, o);
  }
  fputc('\n', fp);
}

void cli_write_report_md(FILE *fp, const void *ctx)
{
  const cli_run_outputs *o = ctx;
  fputs("# ", fp);
  fb_md_write_text(fp, cli_scenario_name(o->scenario));
  fputs(o->diff ? ": rigid and flexible hull " : ": the vehicle ", fp);
  write_road(fp, o->scenario, 0);
  fputs("\n\n", fp);
  fputs(
      "Written by `flexbond run` (version " CLI_VERSION "); every number comes from this "
      "run. The CSV files hold the curves, summary.json the statistics at full precision.\n\n",
      fp);
  write_scenario(fp, o);
  write_assumptions(fp, o);
  write_runs(fp, o);
  fputs("\n## Modes\n", fp);
  if (o->modes1)
    write_modes1(fp, o);
  if (o->modes2)
    write_modes2(fp, o);
  write_model(fp, o);
  write_figures(fp, o);
  write_frequency_response(fp, o);
  write_animation(fp, o);
  cli_write_stress_report(fp, o);
  if (o->diff) {
    write_comparison_table(fp, o);
    write_converged(fp, o);
  } else
    write_outputs_table(fp, o);
  write_ride(fp, o);
  write_contact(fp, o);
  write_conclusions(fp, o);
}
