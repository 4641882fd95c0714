/* Particle CSV reader and writer (see particles_csv.h for the format). */
#include "formats/particles_csv.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/fsutil.h"
#include "io/outfile.h"

enum {
    COL_X,
    COL_Y,
    COL_Z,
    COL_VX,
    COL_VY,
    COL_VZ,
    COL_WX,
    COL_WY,
    COL_WZ,
    COL_RADIUS,
    COL_MASS,
    NCOL
};

/* Column names in the order particles_final.csv writes them. */
static const char *const col_name[NCOL] = {
    "x", "y", "z", "vx", "vy", "vz", "wx", "wy", "wz", "radius", "mass"};

#define COL_LIST "x,y,z,vx,vy,vz,wx,wy,wz,radius,mass"

/* Strip leading and trailing blanks in place; returns the new start. */
static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        s[--n] = '\0';
    return s;
}

/* Cut s at every comma; fields[] receives up to max trimmed pointers.
 * Returns the number of fields in the line (may exceed max). */
static int split(char *s, char **fields, int max)
{
    int n = 0;
    for (;;) {
        char *comma = strchr(s, ',');
        if (comma)
            *comma = '\0';
        if (n < max)
            fields[n] = trim(s);
        n++;
        if (!comma)
            return n;
        s = comma + 1;
    }
}

/* 1 if the whole field is a finite number (stored in *v). */
static int parse_number(const char *s, double *v)
{
    if (*s == '\0')
        return 0;
    char *end;
    errno = 0;
    double d = strtod(s, &end);
    /* ERANGE on underflow still yields a usable (tiny) value; only the
     * overflow to +-HUGE_VAL is rejected, by isfinite below. */
    if (end == s || *end != '\0' || !isfinite(d))
        return 0;
    *v = d;
    return 1;
}

/* State of one read, so every error path can release everything at once. */
struct reader {
    const char *path;
    FILE *f;    /* borrowed: the caller opens and closes it */
    char *line; /* getline buffer */
    size_t line_cap;
    double *rows; /* NCOL values per particle */
    int *lines;   /* file line of each particle */
    int n, cap;   /* particles read, rows allocated */
};

static void reader_free(struct reader *r)
{
    free(r->line);
    free(r->rows);
    free(r->lines);
    memset(r, 0, sizeof *r);
}

static int reader_grow(struct reader *r, struct dem_error *err)
{
    if (r->n < r->cap)
        return DEM_OK;
    if (r->n >= DEM_MAX_PARTICLES)
        return dem_error_set(err, DEM_ECONFIG,
                             "%s: more than %d particles, the most dembox "
                             "takes",
                             r->path, DEM_MAX_PARTICLES);
    int cap = r->cap ? 2 * r->cap : 256;
    cap = cap < DEM_MAX_PARTICLES ? cap : DEM_MAX_PARTICLES;
    double *rows = realloc(r->rows, (size_t)cap * NCOL * sizeof *rows);
    if (!rows)
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", r->path);
    r->rows = rows;
    int *lines = realloc(r->lines, (size_t)cap * sizeof *lines);
    if (!lines)
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", r->path);
    r->lines = lines;
    r->cap = cap;
    return DEM_OK;
}

/* Parse the header line: map[k] = column of field k. */
static int parse_header(char *line, const char *path, int lineno, int dim,
                        int map[NCOL + 1], int *nfield, int present[NCOL],
                        struct dem_error *err)
{
    /* One slot more than there are columns: a longer header must hold a
     * duplicate or unknown name among its first NCOL + 1 fields, which the
     * loop reports before map[] could overflow. */
    char *fields[NCOL + 1];
    int nf = split(line, fields, NCOL + 1);
    if (nf > NCOL + 1)
        nf = NCOL + 1;
    for (int c = 0; c < NCOL; c++)
        present[c] = 0;
    for (int k = 0; k < nf; k++) {
        char *name = fields[k];
        size_t len = strlen(name);
        /* Spreadsheets may quote the header names. */
        if (len >= 2 && name[0] == '"' && name[len - 1] == '"') {
            name[len - 1] = '\0';
            name++;
        }
        double dummy;
        if (k == 0 && parse_number(name, &dummy))
            return dem_error_set(
                err, DEM_ECONFIG,
                "%s:%d: no header line: expected column names (" COL_LIST
                ") before the numbers",
                path, lineno);
        int c = 0;
        while (c < NCOL && strcmp(name, col_name[c]) != 0)
            c++;
        if (c == NCOL)
            return dem_error_set(err, DEM_ECONFIG,
                                 "%s:%d: unknown column '%.64s' "
                                 "(known: " COL_LIST ")",
                                 path, lineno, name);
        if (present[c])
            return dem_error_set(err, DEM_ECONFIG,
                                 "%s:%d: duplicate column '%s'", path, lineno,
                                 col_name[c]);
        present[c] = 1;
        map[k] = c;
    }
    static const int required[] = {COL_X, COL_Y, COL_Z, COL_RADIUS};
    for (size_t k = 0; k < sizeof required / sizeof required[0]; k++) {
        int c = required[k];
        if (c == COL_Z && dim == 2)
            continue;
        if (!present[c])
            return dem_error_set(
                err, DEM_ECONFIG, "%s:%d: missing required column '%s'%s", path,
                lineno, col_name[c], c == COL_Z ? " (3D run)" : "");
    }
    *nfield = nf;
    return DEM_OK;
}

/* Parse one particle row into row[NCOL] (absent columns 0). */
static int parse_row(char *line, const char *path, int lineno, int dim,
                     const int map[NCOL + 1], const int present[NCOL],
                     int nfield, double row[NCOL], struct dem_error *err)
{
    char *fields[NCOL];
    int nf = split(line, fields, NCOL);
    if (nf != nfield)
        return dem_error_set(err, DEM_ECONFIG,
                             "%s:%d: %d fields but the header names %d columns",
                             path, lineno, nf, nfield);
    for (int c = 0; c < NCOL; c++)
        row[c] = 0.0;
    for (int k = 0; k < nf; k++) {
        int c = map[k];
        if (!parse_number(fields[k], &row[c]))
            return dem_error_set(err, DEM_ECONFIG,
                                 "%s:%d: column '%s': '%.40s' is not a finite "
                                 "number",
                                 path, lineno, col_name[c], fields[k]);
    }
    if (!(row[COL_RADIUS] > 0.0))
        return dem_error_set(err, DEM_ECONFIG,
                             "%s:%d: column 'radius': must be > 0, got %g",
                             path, lineno, row[COL_RADIUS]);
    if (present[COL_MASS] && !(row[COL_MASS] > 0.0))
        return dem_error_set(err, DEM_ECONFIG,
                             "%s:%d: column 'mass': must be > 0, got %g", path,
                             lineno, row[COL_MASS]);
    if (dim == 2) {
        /* Discs move in the x-y plane and spin about z only. */
        static const int planar[] = {COL_Z, COL_VZ, COL_WX, COL_WY};
        for (size_t k = 0; k < sizeof planar / sizeof planar[0]; k++)
            if (row[planar[k]] != 0.0)
                return dem_error_set(err, DEM_ECONFIG,
                                     "%s:%d: column '%s': must be 0 in 2D, "
                                     "got %g",
                                     path, lineno, col_name[planar[k]],
                                     row[planar[k]]);
    }
    return DEM_OK;
}

/* Read every row of the file into r. */
static int read_rows(struct reader *r, int dim, int *has_mass,
                     struct dem_error *err)
{
    int map[NCOL + 1], present[NCOL], nfield = 0, have_header = 0, lineno = 0;
    long long bytes = 0;
    ssize_t len;
    errno = 0;
    while ((len = getline(&r->line, &r->line_cap, r->f)) != -1) {
        lineno++;
        bytes += len;
        /* The line would silently end at a NUL byte. */
        if (memchr(r->line, '\0', (size_t)len))
            return dem_error_set(err, DEM_ECONFIG,
                                 "%s:%d: NUL byte: a particle file is text, "
                                 "not binary",
                                 r->path, lineno);
        char *s = trim(r->line);
        if (*s == '\0' || *s == '#')
            continue;
        if (!have_header) {
            int rc = parse_header(s, r->path, lineno, dim, map, &nfield,
                                  present, err);
            if (rc)
                return rc;
            have_header = 1;
            continue;
        }
        int rc = reader_grow(r, err);
        if (rc)
            return rc;
        rc = parse_row(s, r->path, lineno, dim, map, present, nfield,
                       &r->rows[(size_t)r->n * NCOL], err);
        if (rc)
            return rc;
        r->lines[r->n++] = lineno;
    }
    if (ferror(r->f))
        return dem_error_set(err, DEM_EIO, "%s:%d: read error: %s", r->path,
                             lineno + 1, strerror(errno));
    if (bytes == 0)
        return dem_error_set(err, DEM_ECONFIG,
                             "%s:1: empty file (expected a header line "
                             "naming the columns " COL_LIST ")",
                             r->path);
    if (!have_header)
        return dem_error_set(err, DEM_ECONFIG,
                             "%s:%d: no header line (only comments and blank "
                             "lines)",
                             r->path, lineno);
    if (r->n == 0)
        return dem_error_set(err, DEM_ECONFIG,
                             "%s:%d: no particles after the header", r->path,
                             lineno);
    *has_mass = present[COL_MASS];
    return DEM_OK;
}

int dem_particles_read_csv_stream(struct dem_particles *p, FILE *f,
                                  const char *path, int dim, double density,
                                  int mass_model, int **lines,
                                  struct dem_error *err)
{
    memset(p, 0, sizeof *p);
    if (lines)
        *lines = NULL;
    struct reader r = {0};
    r.path = path;
    r.f = f;
    int has_mass = 0;
    int rc = read_rows(&r, dim, &has_mass, err);
    if (rc == DEM_OK)
        rc = dem_particles_init(p, r.n, err);
    if (rc) {
        reader_free(&r);
        return rc;
    }
    for (int i = 0; i < r.n; i++) {
        const double *row = r.rows + (size_t)i * NCOL;
        double a = row[COL_RADIUS];
        double m, I;
        if (has_mass) {
            /* Same expressions as dem_particle_mass so that a file written
             * by dembox reloads to bit-identical inverse inertia. */
            m = row[COL_MASS];
            I = (mass_model == DEM_MASS_DISC && dim == 2) ? 0.5 * m * a * a
                                                          : 0.4 * m * a * a;
        } else {
            dem_particle_mass(a, density, mass_model, dim, &m, &I);
        }
        if (!dem_particle_mass_in_range(m, I)) {
            /* which of the two is out of range, for the message */
            const int m_ok = dem_particle_mass_in_range(m, 1.0);
            if (!m_ok && has_mass)
                rc = dem_error_set(err, DEM_ECONFIG,
                                   "%s:%d: column 'mass': %g kg is out of "
                                   "range (1/mass is not finite)",
                                   path, r.lines[i], m);
            else if (!m_ok)
                rc = dem_error_set(err, DEM_ECONFIG,
                                   "%s:%d: column 'radius': %g m gives a "
                                   "mass of %g kg (density %g kg/m^3), out "
                                   "of range",
                                   path, r.lines[i], a, m, density);
            else
                rc = dem_error_set(err, DEM_ECONFIG,
                                   "%s:%d: column '%s': radius %g m and mass "
                                   "%g kg give a moment of inertia of %g kg "
                                   "m^2, out of range",
                                   path, r.lines[i],
                                   has_mass ? "mass" : "radius", a, m, I);
            dem_particles_free(p);
            reader_free(&r);
            return rc;
        }
        dem_particles_add(p, row[COL_X], row[COL_Y], row[COL_Z], a, density,
                          mass_model, dim);
        p->vx[i] = row[COL_VX];
        p->vy[i] = row[COL_VY];
        p->vz[i] = row[COL_VZ];
        p->wx[i] = row[COL_WX];
        p->wy[i] = row[COL_WY];
        p->wz[i] = row[COL_WZ];
        p->m[i] = m;
        p->inv_m[i] = 1.0 / m;
        p->inv_I[i] = 1.0 / I;
    }
    if (lines) {
        *lines = r.lines;
        r.lines = NULL;
    }
    reader_free(&r);
    return DEM_OK;
}

int dem_particles_read_csv_lines(struct dem_particles *p, const char *path,
                                 int dim, double density, int mass_model,
                                 int **lines, struct dem_error *err)
{
    memset(p, 0, sizeof *p);
    if (lines)
        *lines = NULL;
    FILE *f;
    int rc = dem_open_text(&f, path, "a particle file", err);
    if (rc)
        return rc;
    rc = dem_particles_read_csv_stream(p, f, path, dim, density, mass_model,
                                           lines, err);
    fclose(f);
    return rc;
}

int dem_particles_read_csv(struct dem_particles *p, const char *path, int dim,
                           double density, int mass_model,
                           struct dem_error *err)
{
    return dem_particles_read_csv_lines(p, path, dim, density, mass_model, NULL,
                                        err);
}

/* Sort key for writing rows in original order. */
struct id_index {
    int id, index;
};

static int cmp_id(const void *a, const void *b)
{
    const struct id_index *u = a, *v = b;
    if (u->id != v->id)
        return u->id < v->id ? -1 : 1;
    return (u->index > v->index) - (u->index < v->index);
}

/* Particle indices sorted by original id (particles may be re-ordered in
 * memory); NULL when out of memory. */
static int *id_order(const struct dem_particles *p)
{
    int n = p->n > 0 ? p->n : 0;
    struct id_index *order = malloc((size_t)(n > 0 ? n : 1) * sizeof *order);
    int *idx = malloc((size_t)(n > 0 ? n : 1) * sizeof *idx);
    if (!order || !idx) {
        free(order);
        free(idx);
        return 0;
    }
    for (int i = 0; i < n; i++) {
        order[i].id = p->id[i];
        order[i].index = i;
    }
    qsort(order, (size_t)n, sizeof *order, cmp_id);
    for (int k = 0; k < n; k++)
        idx[k] = order[k].index;
    free(order);
    return idx;
}

int dem_particles_write_csv(const struct dem_particles *p, const char *path,
                            struct dem_error *err)
{
    int *order = id_order(p);
    if (!order)
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    struct dem__outfile o;
    int rc = dem__outfile_open(&o, path, err);
    if (rc) {
        free(order);
        return rc;
    }
    fputs(COL_LIST "\n", o.f);
    for (int k = 0; k < p->n; k++) {
        int i = order[k];
        fprintf(o.f,
                "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
                "%.17g\n",
                p->x[i], p->y[i], p->z[i], p->vx[i], p->vy[i], p->vz[i],
                p->wx[i], p->wy[i], p->wz[i], p->r[i], p->m[i]);
    }
    free(order);
    return dem__outfile_commit(&o, err);
}

int dem_particles_write_forces_csv(const struct dem_particles *p,
                                   const char *path, struct dem_error *err)
{
    int *order = id_order(p);
    if (!order)
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    struct dem__outfile o;
    int rc = dem__outfile_open(&o, path, err);
    if (rc) {
        free(order);
        return rc;
    }
    fputs("fsum,coordination\n", o.f);
    for (int k = 0; k < p->n; k++)
        fprintf(o.f, "%.10g,%d\n", p->fsum[order[k]], p->ncontact[order[k]]);
    free(order);
    return dem__outfile_commit(&o, err);
}

/* A relative particles.file is relative to the folder dembox runs in.
 * Where it is missing there but lies beside the config file (source),
 * the message says so: the commonest slip of a config kept with its
 * particle file in another folder. Returns rc. */
static int not_beside_config(int rc, const char *path, const char *source,
                             struct dem_error *err)
{
    const char *slash = strrchr(source, '/');
    char near[DEM_PATH_MAX];
    if (rc != DEM_EIO || path[0] == '/' || !slash || access(path, F_OK) == 0)
        return rc;
    const int n = snprintf(near, sizeof near, "%.*s/%s", (int)(slash - source),
                           source, path);
    if (n < 0 || (size_t)n >= sizeof near || access(near, F_OK) != 0)
        return rc;
    return dem_error_set(err, rc,
                         "%s: no such file in the folder dembox runs in (a "
                         "relative particles.file is relative to it, not "
                         "to the config file's folder); %s exists: give "
                         "that path",
                         path, near);
}

int dem_particles_load(struct dem_particles *p, const struct dem_config *cfg,
                       struct dem_error *err)
{
    const char *path = cfg->particles.file;
    const int dim = cfg->dim == 2 ? 2 : 3;
    int *lines = NULL;
    int rc =
        dem_particles_read_csv_lines(p, path, dim, cfg->particles.density,
                                     cfg->particles.mass_model, &lines, err);
    if (rc)
        return not_beside_config(rc, path, cfg->source, err);
    /* a given box.size has positive lengths (config validation) */
    int given = 0;
    for (int a = 0; a < dim; a++)
        given |= cfg->box.size[a] != 0.0;
    /* in a periodic cell (whose size config validation requires here) a
     * position counts modulo the period: each centre is taken into [0,
     * L), so that a cell's particles_final.csv, whose cell need not start
     * at 0, is read as the same packing (an unsheared one: a tilt is not
     * in the file) */
    if (cfg->box.boundary == DEM_BOUNDARY_PERIODIC) {
        double *c[3] = {p->x, p->y, p->z};
        for (int a = 0; a < dim && !rc; a++) {
            const double L = cfg->box.size[a];
            for (int i = 0; i < p->n; i++) {
                /* a centre a million periods out keeps its place in the
                 * cell to about 1e-10 L; far beyond, the digits that
                 * place it are gone (at 1e20 m in a 1 cm cell the wrap
                 * gave centres thousands of metres outside it, at 1e308
                 * minus infinity) */
                if (!(fabs(c[a][i]) <= 1e6 * L)) {
                    rc = dem_error_set(err, DEM_ECONFIG,
                                       "%s:%d: particle at %c = %g m lies "
                                       "more than a million periods (%g m) "
                                       "from the periodic cell: its place "
                                       "in the cell is lost to rounding",
                                       path, lines[i], "xyz"[a], c[a][i], L);
                    break;
                }
                /* fmod is exact: the centre's own place in [0, L) */
                double w = fmod(c[a][i], L) + 0.0; /* (-0.0 to 0.0) */
                w += w < 0.0 ? L : 0.0;
                c[a][i] = w < L ? w : 0.0; /* (-tiny + L rounds to L) */
            }
        }
        given = 0;
    }
    for (int i = 0; i < p->n && given && !rc; i++) {
        const double c[3] = {p->x[i], p->y[i], p->z[i]};
        for (int a = 0; a < dim; a++)
            if (c[a] - p->r[i] < 0.0 || c[a] + p->r[i] > cfg->box.size[a]) {
                rc = dem_error_set(err, DEM_ECONFIG,
                                   "%s:%d: particle at %c = %g m with radius "
                                   "%g m is not inside box.size (0 to %g m)",
                                   path, lines[i], "xyz"[a], c[a], p -> r[i],
                                   cfg -> box.size[a]);
                break;
            }
    }
    free(lines);
    if (rc)
        dem_particles_free(p);
    return rc;
}
