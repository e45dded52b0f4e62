/* SPDX-License-Identifier: BSD-3-Clause */
/* VTK XML unstructured grid output (see flexbond/fem.h), ASCII.
 *
 * Layout per the XML formats of "VTK File Formats" (The VTK User's Guide,
 * Kitware, 11th ed.): one Piece with Points (Float64 x 3), Cells
 * (connectivity, offsets, types: VTK_TRIANGLE = 5, VTK_QUAD = 9, whose
 * node orders match S3 and S4), PointData and CellData. Point data:
 * "node_id" (the user ids), "displacement" and "rotation" (3 components
 * each) when DOF values are given, and "nset_<name>" (Int32, 1 for the
 * members of each node set; the prefix keeps set names from colliding with
 * the other arrays). Cell data: "element_id", then the frame's cell
 * arrays (Float64). Coordinates are written with
 * %.17g (exact), field values with %.10g (beyond the resolution of any
 * modal or static solution).
 *
 * An animation's frame (fb_mesh_write_vtu_frame) draws the nodes at
 * X + warp u and appends its markers (bodies, wheels) as points with a
 * VTK_VERTEX cell each; every point array then covers them too (node_id
 * and element_id -1, rotation and node-set flags 0) and an Int32 "part"
 * tells them apart (0 for the mesh's nodes). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "flexbond/escape.h"
#include "flexbond/out.h"

#include "fem/mesh_internal.h"

enum { VTK_VERTEX = 1, VTK_TRIANGLE = 5, VTK_QUAD = 9 };

/* The DataArray's start tag; name (a node set's, from the deck) goes
 * through fb_xml_write_attr (flexbond/escape.h), so no name can close the
 * attribute or the tag, or put a character XML 1.0 forbids in the file. */
static void open_array(FILE *fp, const char *type, const char *name, int ncomp)
{
  fprintf(fp, "        <DataArray type=\"%s\" Name=\"", type);
  fb_xml_write_attr(fp, name);
  fputc('"', fp);
  if (ncomp > 1)
    fprintf(fp, " NumberOfComponents=\"%d\"", ncomp);
  fputs(" format=\"ascii\">\n", fp);
}

static void close_array(FILE *fp)
{
  fputs("        </DataArray>\n", fp);
}

/* Components first..first+2 of every node's 6 DOF values, then each
 * marker's (its vertical displacement, or no rotation). */
static void write_dof_vector(FILE *fp, const fb_mesh *m, const fb_vtu_frame *f, size_t first,
                             const char *name)
{
  open_array(fp, "Float64", name, 3);
  for (size_t i = 0; i < fb_mesh_nnodes(m); ++i) {
    const double *v = &f->dof_values[6 * i + first];
    fprintf(fp, "          %.10g %.10g %.10g\n", v[0], v[1], v[2]);
  }
  for (size_t k = 0; k < f->nmarkers; ++k)
    fprintf(fp, "          0 0 %.10g\n", first == 0 ? f->markers[k].dz : 0.0);
  close_array(fp);
}

/* n more values of an Int32 or Int64 array, value each. */
static void write_repeated(FILE *fp, size_t n, long value)
{
  for (size_t k = 0; k < n; ++k)
    fprintf(fp, "          %ld\n", value);
}

/* Flags of the members of node set s, through a scratch array. */
static void write_nset_flags(FILE *fp, const fb_mesh *m, size_t s, size_t nmarkers,
                             unsigned char *member)
{
  const char *name = fb_mesh_nset_name(m, s);
  const size_t *nodes = NULL;
  size_t n = 0;
  fb_mesh_nset(m, name, &nodes, &n);
  const size_t nnodes = fb_mesh_nnodes(m);
  for (size_t i = 0; i < nnodes; ++i)
    member[i] = 0;
  for (size_t k = 0; k < n; ++k)
    member[nodes[k]] = 1;
  char array[FB_MESH_NAME_MAX + 8];
  snprintf(array, sizeof array, "nset_%s", name);
  open_array(fp, "Int32", array, 1);
  for (size_t i = 0; i < nnodes; ++i)
    fprintf(fp, "%s%d%s", i % 20 == 0 ? "          " : " ", member[i],
            i % 20 == 19 || i + 1 == nnodes ? "\n" : "");
  write_repeated(fp, nmarkers, 0);
  close_array(fp);
}

static int write_point_data(FILE *fp, const fb_mesh *m, const fb_vtu_frame *f, fb_err *err)
{
  const size_t nnodes = fb_mesh_nnodes(m);
  fprintf(fp, "      <PointData%s>\n", f->dof_values ? " Vectors=\"displacement\"" : "");
  open_array(fp, "Int64", "node_id", 1);
  for (size_t i = 0; i < nnodes; ++i)
    fprintf(fp, "          %ld\n", fb_mesh_node_id(m, i));
  write_repeated(fp, f->nmarkers, -1);
  close_array(fp);
  if (f->dof_values) {
    write_dof_vector(fp, m, f, 0, "displacement");
    write_dof_vector(fp, m, f, 3, "rotation");
  }
  if (f->nmarkers) {
    open_array(fp, "Int32", "part", 1);
    write_repeated(fp, nnodes, 0);
    for (size_t k = 0; k < f->nmarkers; ++k)
      fprintf(fp, "          %d\n", f->markers[k].part);
    close_array(fp);
  }
  unsigned char *member = malloc(nnodes ? nnodes : 1);
  if (!member)
    return fb_err_set(err, FB_ENOMEM, "out of memory writing node sets");
  for (size_t s = 0; s < fb_mesh_nnsets(m); ++s)
    write_nset_flags(fp, m, s, f->nmarkers, member);
  free(member);
  fputs("      </PointData>\n", fp);
  return FB_OK;
}

static void write_cell_data(FILE *fp, const fb_mesh *m, const fb_vtu_frame *f)
{
  fputs("      <CellData>\n", fp);
  open_array(fp, "Int64", "element_id", 1);
  for (size_t e = 0; e < fb_mesh_nelements(m); ++e)
    fprintf(fp, "          %ld\n", fb_mesh_element_id(m, e));
  write_repeated(fp, f->nmarkers, -1);
  close_array(fp);
  for (size_t a = 0; a < f->ncell_arrays; ++a) {
    open_array(fp, "Float64", f->cell_arrays[a].name, 1);
    for (size_t e = 0; e < fb_mesh_nelements(m); ++e)
      fprintf(fp, "          %.10g\n", f->cell_arrays[a].values[e]);
    write_repeated(fp, f->nmarkers, 0);
    close_array(fp);
  }
  fputs("      </CellData>\n", fp);
}

static void write_points(FILE *fp, const fb_mesh *m, const fb_vtu_frame *f)
{
  fputs("      <Points>\n", fp);
  fputs("        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n", fp);
  const double w = f->dof_values ? f->warp : 0.0;
  for (size_t i = 0; i < fb_mesh_nnodes(m); ++i) {
    const double *p = fb_mesh_node_xyz(m, i), *u = w != 0.0 ? &f->dof_values[6 * i] : NULL;
    const double *o = f->origin;
    fprintf(fp, "          %.17g %.17g %.17g\n", o[0] + p[0] + (u ? w * u[0] : 0.0),
            o[1] + p[1] + (u ? w * u[1] : 0.0), o[2] + p[2] + (u ? w * u[2] : 0.0));
  }
  for (size_t k = 0; k < f->nmarkers; ++k) {
    const double *p = f->markers[k].xyz, *o = f->origin;
    fprintf(fp, "          %.17g %.17g %.17g\n", o[0] + p[0], o[1] + p[1],
            o[2] + p[2] + f->warp * f->markers[k].dz);
  }
  close_array(fp);
  fputs("      </Points>\n", fp);
}

static void write_cells(FILE *fp, const fb_mesh *m, size_t nmarkers)
{
  const size_t ne = fb_mesh_nelements(m);
  fputs("      <Cells>\n", fp);
  open_array(fp, "Int64", "connectivity", 1);
  for (size_t e = 0; e < ne; ++e) {
    const size_t *nd = fb_mesh_element_nodes(m, e);
    fputs("         ", fp);
    for (size_t k = 0; k < fb_mesh_type_nodes(fb_mesh_element_type(m, e)); ++k)
      fprintf(fp, " %zu", nd[k]);
    fputc('\n', fp);
  }
  for (size_t k = 0; k < nmarkers; ++k)
    fprintf(fp, "          %zu\n", fb_mesh_nnodes(m) + k);
  close_array(fp);
  open_array(fp, "Int64", "offsets", 1);
  size_t offset = 0;
  for (size_t e = 0; e < ne; ++e) {
    offset += fb_mesh_type_nodes(fb_mesh_element_type(m, e));
    fprintf(fp, "          %zu\n", offset);
  }
  for (size_t k = 0; k < nmarkers; ++k)
    fprintf(fp, "          %zu\n", offset + k + 1);
  close_array(fp);
  open_array(fp, "UInt8", "types", 1);
  for (size_t e = 0; e < ne; ++e)
    fprintf(fp, "          %d\n",
            fb_mesh_element_type(m, e) == FB_ELEM_TRI3 ? VTK_TRIANGLE : VTK_QUAD);
  write_repeated(fp, nmarkers, VTK_VERTEX);
  close_array(fp);
  fputs("      </Cells>\n", fp);
}

/* dof_values, if given, must be finite (a NaN would poison the colour
 * scale of every field in ParaView). */
static int check_dofs(const fb_mesh *m, const double *dof, const char *path, fb_err *err)
{
  static const char *const names[6] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  for (size_t i = 0; dof && i < 6 * fb_mesh_nnodes(m); ++i) {
    if (!isfinite(dof[i]))
      return fb_err_set(err, FB_EINVAL, "%s: DOF value %zu (%s of node %ld) is not finite",
                        path, i, names[i % 6], fb_mesh_node_id(m, i / 6));
  }
  return FB_OK;
}

/* The grid's field data: one Float64 value per name (VTK's FieldData of
 * a dataset, which ParaView shows in its information panel). */
static void write_field_data(FILE *fp, const fb_vtu_field *fields, size_t nfields)
{
  if (!nfields)
    return;
  fputs("    <FieldData>\n", fp);
  for (size_t k = 0; k < nfields; ++k) {
    fputs("      <DataArray type=\"Float64\" Name=\"", fp);
    fb_xml_write_attr(fp, fields[k].name);
    fprintf(fp, "\" NumberOfTuples=\"1\" format=\"ascii\">%.17g</DataArray>\n",
            fields[k].value);
  }
  fputs("    </FieldData>\n", fp);
}

int fb_mesh_write_vtu(const fb_mesh *m, const double *dof_values, const char *path, fb_err *err)
{
  return fb_mesh_write_vtu_fields(m, dof_values, NULL, 0, path, err);
}

int fb_mesh_write_vtu_fields(const fb_mesh *m, const double *dof_values,
                             const fb_vtu_field *fields, size_t nfields, const char *path,
                             fb_err *err)
{
  const fb_vtu_frame f = {.dof_values = dof_values, .fields = fields, .nfields = nfields};
  return fb_mesh_write_vtu_frame(m, &f, path, err);
}

/* The frame's numbers: finite, so that ParaView's colour scales and the
 * points' positions mean something. */
static int check_frame(const fb_mesh *m, const fb_vtu_frame *f, const char *path, fb_err *err)
{
  for (size_t k = 0; k < f->nfields; ++k)
    if (!f->fields[k].name || !isfinite(f->fields[k].value))
      return fb_err_set(err, FB_EINVAL, "%s: field %zu has no name or is not finite", path, k);
  for (size_t a = 0; a < f->ncell_arrays; ++a) {
    if (!f->cell_arrays[a].name || !f->cell_arrays[a].values)
      return fb_err_set(err, FB_EINVAL, "%s: cell array %zu has no name or values", path, a);
    for (size_t e = 0; e < fb_mesh_nelements(m); ++e)
      if (!isfinite(f->cell_arrays[a].values[e]))
        return fb_err_set(err, FB_EINVAL, "%s: cell array %s is not finite at element %ld",
                          path, f->cell_arrays[a].name, fb_mesh_element_id(m, e));
  }
  if (!isfinite(f->warp))
    return fb_err_set(err, FB_EINVAL, "%s: the warp factor is not finite", path);
  if (!isfinite(f->origin[0]) || !isfinite(f->origin[1]) || !isfinite(f->origin[2]))
    return fb_err_set(err, FB_EINVAL, "%s: the origin is not finite", path);
  for (size_t k = 0; k < f->nmarkers; ++k) {
    const fb_vtu_marker *mk = &f->markers[k];
    if (!isfinite(mk->xyz[0]) || !isfinite(mk->xyz[1]) || !isfinite(mk->xyz[2]) ||
        !isfinite(mk->dz))
      return fb_err_set(err, FB_EINVAL, "%s: marker %zu is not finite", path, k);
  }
  return check_dofs(m, f->dof_values, path, err);
}

int fb_mesh_write_vtu_frame(const fb_mesh *m, const fb_vtu_frame *f, const char *path,
                            fb_err *err)
{
  if (!m || !f || !path)
    return fb_err_set(err, FB_EINVAL, "fb_mesh_write_vtu: mesh, frame or path is NULL");
  int rc = check_frame(m, f, path, err);
  fb_out *out = NULL;
  if (!rc)
    rc = fb_out_open(path, &out, err);
  if (rc)
    return rc;
  FILE *fp = fb_out_stream(out);
  fputs("<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\""
        " header_type=\"UInt64\">\n  <UnstructuredGrid>\n",
        fp);
  write_field_data(fp, f->fields, f->nfields);
  fprintf(fp, "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n",
          fb_mesh_nnodes(m) + f->nmarkers, fb_mesh_nelements(m) + f->nmarkers);
  rc = write_point_data(fp, m, f, err);
  if (rc) {
    fb_out_abort(&out);
    return rc;
  }
  write_cell_data(fp, m, f);
  write_points(fp, m, f);
  write_cells(fp, m, f->nmarkers);
  fputs("    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n", fp);
  return fb_out_commit(&out, err);
}
