/* VTK XML writers (format: "VTK File Formats", Kitware, XML section). */
#include "formats/vtu.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/outfile.h"
#include "measure/network.h"

/* VTK cell type numbers (vtkCellType.h). */
enum { VTK_VERTEX = 1, VTK_LINE = 3, VTK_POLY_LINE = 4 };

static void header(FILE *f, const char *type)
{
    fprintf(f,
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"%s\" version=\"1.0\" "
            "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
            type);
}

/* Values of one or three double arrays, one particle per line and not
 * indented (indentation would add a third to the file). 9 significant
 * digits are more than a picture needs; 17 would double the size. */
static void array3(FILE *f, const char *name, int n, const double *a,
                   const double *b, const double *c)
{
    fprintf(f,
            "        <DataArray type=\"Float64\" Name=\"%s\" "
            "NumberOfComponents=\"3\" format=\"ascii\">\n",
            name);
    for (int i = 0; i < n; i++)
        fprintf(f, "%.9g %.9g %.9g\n", a[i], b[i], c[i]);
    fputs("        </DataArray>\n", f);
}

static void array1(FILE *f, const char *name, int n, const double *a)
{
    fprintf(f,
            "        <DataArray type=\"Float64\" Name=\"%s\" "
            "format=\"ascii\">\n",
            name);
    for (int i = 0; i < n; i++)
        fprintf(f, "%.9g\n", a[i]);
    fputs("        </DataArray>\n", f);
}

static void array1i(FILE *f, const char *name, int n, const int *a)
{
    fprintf(f,
            "        <DataArray type=\"Int32\" Name=\"%s\" "
            "format=\"ascii\">\n",
            name);
    for (int i = 0; i < n; i++)
        fprintf(f, "%d\n", a[i]);
    fputs("        </DataArray>\n", f);
}

/* Cells section: ncell cells of one type; conn lists the points of all
 * cells, ends[c] is where cell c's list ends. NULL conn and ends mean one
 * point per cell, cell c = point c. */
static void cells(FILE *f, int ncell, int type, const int *conn,
                  const int *ends)
{
    int nconn = ends ? (ncell > 0 ? ends[ncell - 1] : 0) : ncell;
    fputs("      <Cells>\n"
          "        <DataArray type=\"Int64\" Name=\"connectivity\" "
          "format=\"ascii\">\n",
          f);
    for (int k = 0; k < nconn; k++)
        fprintf(f, "%d\n", conn ? conn[k] : k);
    fputs("        </DataArray>\n"
          "        <DataArray type=\"Int64\" Name=\"offsets\" "
          "format=\"ascii\">\n",
          f);
    for (int c = 0; c < ncell; c++)
        fprintf(f, "%d\n", ends ? ends[c] : c + 1);
    fputs("        </DataArray>\n"
          "        <DataArray type=\"UInt8\" Name=\"types\" "
          "format=\"ascii\">\n",
          f);
    for (int c = 0; c < ncell; c++)
        fprintf(f, "%d\n", type);
    fputs("        </DataArray>\n"
          "      </Cells>\n",
          f);
}

int dem_vtu_write_particles(const char *path, const struct dem_particles *p,
                            struct dem_error *err)
{
    struct dem__outfile o;
    int rc = dem__outfile_open(&o, path, err);
    if (rc)
        return rc;
    FILE *f = o.f;
    int n = p->n > 0 ? p->n : 0;
    header(f, "UnstructuredGrid");
    fprintf(f,
            "  <UnstructuredGrid>\n"
            "    <Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n"
            "      <Points>\n",
            n, n);
    array3(f, "position", n, p->x, p->y, p->z);
    fputs("      </Points>\n", f);
    /* Vertex cells: cell i is point i. */
    cells(f, n, VTK_VERTEX, NULL, NULL);
    fputs("      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n", f);
    array1(f, "radius", n, p->r);
    array3(f, "velocity", n, p->vx, p->vy, p->vz);
    array3(f, "omega", n, p->wx, p->wy, p->wz);
    array1(f, "force", n, p->fsum);
    array1i(f, "coordination", n, p->ncontact);
    array1i(f, "id", n, p->id);
    fputs("      </PointData>\n"
          "    </Piece>\n"
          "  </UnstructuredGrid>\n"
          "</VTKFile>\n",
          f);
    return dem__outfile_commit(&o, err);
}

int dem_vtu_write_box(const char *path, const double lo[3], const double hi[3],
                      const double tilt[3], int dim, struct dem_error *err)
{
    struct dem__outfile o;
    int rc = dem__outfile_open(&o, path, err);
    if (rc)
        return rc;
    FILE *f = o.f;
    /* The corners: 2D the 4 at z = 0, 3D the 8 (bottom face counter-
     * clockwise, then the top face). The box is drawn as lines, so that
     * ParaView shows it as a wireframe around the packing, not as a solid
     * that hides it: 2D one polyline back to the first corner, 3D the 12
     * edges as lines. */
    double pts[8][3];
    int npts = dim == 2 ? 4 : 8;
    for (int k = 0; k < npts; k++) {
        int ix = (k & 1) ^ ((k >> 1) & 1); /* 0 1 1 0 around a face */
        int iy = (k >> 1) & 1;
        const int iz = k >= 4;
        pts[k][0] = ix ? hi[0] : lo[0];
        pts[k][1] = iy ? hi[1] : lo[1];
        pts[k][2] = dim == 2 ? 0.0 : (iz ? hi[2] : lo[2]);
        if (tilt) {
            pts[k][0] += iy * tilt[0] + iz * tilt[1];
            pts[k][1] += iz * tilt[2];
        }
    }
    static const int loop2d[5] = {0, 1, 2, 3, 0};
    static const int edges[24] = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6,
                                  6, 7, 7, 4, 0, 4, 1, 5, 2, 6, 3, 7};
    static const int ends2d[1] = {5};
    static const int ends3d[12] = {2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24};
    const int ncell = dim == 2 ? 1 : 12;
    header(f, "UnstructuredGrid");
    fprintf(f,
            "  <UnstructuredGrid>\n"
            "    <Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n"
            "      <Points>\n"
            "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" "
            "format=\"ascii\">\n",
            npts, ncell);
    for (int k = 0; k < npts; k++)
        fprintf(f, "%.17g %.17g %.17g\n", pts[k][0], pts[k][1], pts[k][2]);
    fputs("        </DataArray>\n"
          "      </Points>\n",
          f);
    cells(f, ncell, dim == 2 ? VTK_POLY_LINE : VTK_LINE,
          dim == 2 ? loop2d : edges, dim == 2 ? ends2d : ends3d);
    fputs("    </Piece>\n"
          "  </UnstructuredGrid>\n"
          "</VTKFile>\n",
          f);
    return dem__outfile_commit(&o, err);
}

/* A file name as an XML attribute value. */
static void put_attr(FILE *f, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&':
            fputs("&amp;", f);
            break;
        case '<':
            fputs("&lt;", f);
            break;
        case '>':
            fputs("&gt;", f);
            break;
        case '"':
            fputs("&quot;", f);
            break;
        default:
            fputc(*s, f);
        }
    }
}

int dem_vtu_write_contacts(const struct dem_particles *p,
                           const struct dem_network *net, const char *path,
                           struct dem_error *err)
{
    /* points: the particle centres, then one contact point per wall
     * contact, then the partner's image centre of each contact through
     * a periodic image; cells: a line per contact (centre to centre,
     * centre to the contact point on the wall, centre to the image, which
     * lies outside the cell) */
    const int n = p->n > 0 ? p->n : 0, nc = net->n, nw = net->n - net->npair;
    int nimg = 0;
    for (int k = 0; k < net->npair; k++)
        nimg += net->c[k].image;
    int *conn = malloc(2 * (size_t)(nc > 0 ? nc : 1) * sizeof *conn);
    int *ends = malloc((size_t)(nc > 0 ? nc : 1) * sizeof *ends);
    if (!conn || !ends) {
        free(conn);
        free(ends);
        return dem_error_set(err, DEM_ENOMEM, "out of memory (contacts)");
    }
    for (int k = 0, m = 0; k < nc; k++) {
        conn[2 * k] = net->c[k].i;
        conn[2 * k + 1] = k >= net->npair ? n + k - net->npair
                          : net->c[k].image ? n + nw + m++
                                            : net->c[k].j;
        ends[k] = 2 * k + 2;
    }
    struct dem__outfile o;
    int rc = dem__outfile_open(&o, path, err);
    if (rc) {
        free(conn);
        free(ends);
        return rc;
    }
    FILE *f = o.f;
    header(f, "UnstructuredGrid");
    fprintf(f,
            "  <UnstructuredGrid>\n"
            "    <Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n"
            "      <Points>\n"
            "        <DataArray type=\"Float64\" Name=\"position\" "
            "NumberOfComponents=\"3\" format=\"ascii\">\n",
            n + nw + nimg, nc);
    for (int i = 0; i < n; i++)
        fprintf(f, "%.9g %.9g %.9g\n", p->x[i], p->y[i], p->z[i]);
    for (int k = net->npair; k < nc; k++)
        fprintf(f, "%.9g %.9g %.9g\n", net->c[k].x[0], net->c[k].x[1],
                net->c[k].x[2]);
    for (int k = 0; k < net->npair; k++) {
        const struct dem_network_contact *c = &net->c[k];
        if (c->image)
            fprintf(f, "%.9g %.9g %.9g\n", p->x[c->i] - c->b[0],
                    p->y[c->i] - c->b[1], p->z[c->i] - c->b[2]);
    }
    fputs("        </DataArray>\n"
          "      </Points>\n",
          f);
    cells(f, nc, VTK_LINE, conn, ends);
    fputs("      <CellData Scalars=\"normal_force\" Vectors=\"branch\">\n", f);
    static const char *const names[] = {"normal_force", "tangential_force",
                                        "overlap",      "sliding",
                                        "partner",      "branch"};
    for (int q = 0; q < 6; q++) {
        fprintf(f,
                "        <DataArray type=\"%s\" Name=\"%s\"%s "
                "format=\"ascii\">\n",
                q == 3 || q == 4 ? "Int32" : "Float64", names[q],
                q == 5 ? " NumberOfComponents=\"3\"" : "");
        for (int k = 0; k < nc; k++) {
            const struct dem_network_contact *c = &net->c[k];
            const int j = c->j;
            if (q == 0)
                fprintf(f, "%.9g\n", c->fn);
            else if (q == 1)
                fprintf(f, "%.9g\n",
                        sqrt(c->ft[0] * c->ft[0] + c->ft[1] * c->ft[1] +
                             c->ft[2] * c->ft[2]));
            else if (q == 2)
                fprintf(f, "%.9g\n", c->delta);
            else if (q == 3)
                fprintf(f, "%d\n", c->sliding);
            else if (q == 4) /* the partner's id, or -1 - w for wall w */
                fprintf(f, "%d\n", j >= 0 ? p->id[j] : j);
            else /* branch: from the partner's centre (or the contact
                    point on a wall) to i's */
                fprintf(f, "%.9g %.9g %.9g\n", c->b[0], c->b[1], c->b[2]);
        }
        fputs("        </DataArray>\n", f);
    }
    for (int q = 0; q < DEM_NHISTORY; q++) { /* the history values */
        if (!(net->hist >> q & 1u))
            continue;
        fprintf(f,
                "        <DataArray type=\"Float64\" Name=\"%s\" "
                "format=\"ascii\">\n",
                dem_history_name(q));
        for (int k = 0; k < nc; k++)
            fprintf(f, "%.9g\n", net->c[k].h[q]);
        fputs("        </DataArray>\n", f);
    }
    fputs("      </CellData>\n"
          "    </Piece>\n"
          "  </UnstructuredGrid>\n"
          "</VTKFile>\n",
          f);
    free(conn);
    free(ends);
    return dem__outfile_commit(&o, err);
}

/* The end of every PVD file dem_pvd_write and dem_pvd_append write. */
static const char pvd_tail[] = "  </Collection>\n"
                               "</VTKFile>\n";

static void pvd_dataset(FILE *f, double time, const char *file)
{
    fprintf(f,
            "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" "
            "file=\"",
            time);
    put_attr(f, file);
    fputs("\"/>\n", f);
}

int dem_pvd_write(const char *path, int n, const double *times,
                  const char *const *files, struct dem_error *err)
{
    struct dem__outfile o;
    int rc = dem__outfile_open(&o, path, err);
    if (rc)
        return rc;
    FILE *f = o.f;
    header(f, "Collection");
    fputs("  <Collection>\n", f);
    for (int k = 0; k < n; k++)
        pvd_dataset(f, times[k], files[k]);
    fputs(pvd_tail, f);
    return dem__outfile_commit(&o, err);
}

int dem_pvd_append(const char *path, double time, const char *file,
                   struct dem_error *err)
{
    FILE *f = fopen(path, "r+");
    if (!f)
        return dem_error_set(err, DEM_EIO, "%s: cannot open for appending: %s",
                             path, strerror(errno));
    const long len = (long)sizeof pvd_tail - 1;
    char end[sizeof pvd_tail];
    int bad = fseek(f, -len, SEEK_END) != 0 ||
              fread(end, 1, (size_t)len, f) != (size_t)len ||
              memcmp(end, pvd_tail, (size_t)len) != 0;
    if (bad) {
        fclose(f);
        return dem_error_set(err, DEM_EIO,
                             "%s: does not end as a PVD collection", path);
    }
    /* (a seek between the read and the writes, as C requires) */
    errno = 0;
    bad = fseek(f, -len, SEEK_END) != 0;
    if (!bad) {
        pvd_dataset(f, time, file);
        fputs(pvd_tail, f);
        bad = ferror(f) || fflush(f) != 0;
    }
    int e = errno;
    if (fclose(f) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    if (bad)
        return dem_error_set(err, DEM_EIO, "%s: write failed: %s", path,
                             e ? strerror(e) : "I/O error");
    return DEM_OK;
}
