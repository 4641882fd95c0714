/* LAMMPS data files, atom_style sphere (see lammps_data.h for the format). */
#include "formats/lammps_data.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/sim.h"
#include "io/fsutil.h"
#include "io/outfile.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define MAX_FIELDS 16

/* State of one read, so every error path releases everything at once. */
struct reader {
    const char *path;
    FILE *f;
    char *line; /* getline buffer */
    size_t cap;
    int lineno; /* line number of line */
    struct dem_lammps_data *d;
    struct dem_error *err;
    char style[32]; /* the line's comment's first word ("" for none): a
                       section's atom style, as in "Atoms # sphere" */
};

/* Cut the '#' comment, split at blanks; returns the number of fields
 * (at most max are stored). */
static int split(char *s, char **fields, int max)
{
    char *hash = strchr(s, '#');
    if (hash)
        *hash = '\0';
    int n = 0;
    for (char *save = NULL, *tok = strtok_r(s, " \t\r\n", &save); tok;
         tok = strtok_r(NULL, " \t\r\n", &save)) {
        if (n < max)
            fields[n] = tok;
        n++;
    }
    return n;
}

static int number(const char *s, double *v)
{
    char *end;
    errno = 0;
    double d = strtod(s, &end);
    if (end == s || *end != '\0' || !isfinite(d))
        return 0;
    *v = d;
    return 1;
}

static int integer(const char *s, long *v)
{
    char *end;
    errno = 0;
    long k = strtol(s, &end, 10);
    if (end == s || *end != '\0' || errno)
        return 0;
    *v = k;
    return 1;
}

static int fail(struct reader *r, int code, const char *what, const char *s)
{
    return dem_error_set(r->err, code, "%s:%d: %s%s%s", r->path, r->lineno,
                         what, s ? " " : "", s ? s : "");
}

/* Next line split into fields; 0 fields for a blank or comment line;
 * -1 at the end of the file. */
static int next_fields(struct reader *r, char **fields, int *nf)
{
    if (getline(&r->line, &r->cap, r->f) < 0)
        return -1;
    r->lineno++;
    r->style[0] = '\0';
    const char *hash = strchr(r->line, '#');
    if (hash)
        sscanf(hash + 1, "%31s", r->style);
    *nf = split(r->line, fields, MAX_FIELDS);
    return 0;
}

/* Room for cap atoms in the arrays of the Atoms section. They grow with
 * the atoms read, so that a header announcing a billion atoms in a short
 * file costs no memory. */
static int grow_atoms(struct dem_lammps_data *d, size_t cap)
{
    int *id = realloc(d->id, cap * sizeof *id);
    if (!id)
        return -1;
    d->id = id;
    double **a[] = {&d->diameter, &d->density, &d->x, &d->y, &d->z};
    for (size_t k = 0; k < sizeof a / sizeof a[0]; k++) {
        double *v = realloc(*a[k], cap * sizeof(double));
        if (!v)
            return -1;
        *a[k] = v;
    }
    return 0;
}

/* The velocities of all d->n atoms, zero until a Velocities section sets
 * them (after the Atoms section, which proved the count). */
static int alloc_velocities(struct dem_lammps_data *d)
{
    double **a[] = {&d->vx, &d->vy, &d->vz, &d->wx, &d->wy, &d->wz};
    int ok = 1;
    for (size_t k = 0; k < sizeof a / sizeof a[0]; k++) {
        *a[k] = calloc((size_t)d->n, sizeof(double));
        ok = ok && *a[k];
    }
    return ok ? 0 : -1;
}

void dem_lammps_data_free(struct dem_lammps_data *d)
{
    free(d->id);
    free(d->diameter);
    free(d->density);
    free(d->x);
    free(d->y);
    free(d->z);
    free(d->vx);
    free(d->vy);
    free(d->vz);
    free(d->wx);
    free(d->wy);
    free(d->wz);
    memset(d, 0, sizeof *d);
}

/* Index of atom id in the sorted (id, index) table, or -1. */
struct id_index {
    int id, index;
};

static int cmp_id(const void *a, const void *b)
{
    int x = ((const struct id_index *)a)->id;
    int y = ((const struct id_index *)b)->id;
    return (x > y) - (x < y);
}

static int read_atoms(struct reader *r, int *seen)
{
    struct dem_lammps_data *d = r->d;
    char *f[MAX_FIELDS];
    int nf, k = 0;
    size_t cap = 0;
    while (k < d->n) {
        if ((size_t)k == cap) {
            const size_t more = cap ? 2 * cap : 1024;
            cap = more < (size_t)d->n ? more : (size_t)d->n;
            if (grow_atoms(d, cap))
                return dem_error_set(r->err, DEM_ENOMEM,
                                     "%s: out of memory", r->path);
        }
        if (next_fields(r, f, &nf) < 0)
            return dem_error_set(r->err, DEM_EIO,
                                 "%s:%d: Atoms: file ends after %d of %d atoms",
                                 r->path, r->lineno, k, d->n);
        if (nf == 0)
            continue;
        if (nf != 7 && nf != 10)
            return dem_error_set(r->err, DEM_EIO,
                                 "%s:%d: Atoms: %d columns, expected 7 or 10 "
                                 "(atom_style sphere: id type diameter "
                                 "density x y z [ix iy iz])",
                                 r->path, r->lineno, nf);
        long id, type;
        double v[5];
        if (!integer(f[0], &id) || id < 1 || id > 2147483647L)
            return fail(r, DEM_EIO, "Atoms: bad atom id", f[0]);
        if (!integer(f[1], &type))
            return fail(r, DEM_EIO, "Atoms: bad atom type", f[1]);
        for (int c = 0; c < 5; c++)
            if (!number(f[2 + c], &v[c]))
                return fail(r, DEM_EIO, "Atoms: bad number", f[2 + c]);
        for (int c = 7; c < nf; c++) { /* the image flags */
            long flag;
            if (!integer(f[c], &flag))
                return fail(r, DEM_EIO, "Atoms: bad image flag", f[c]);
        }
        if (!(v[0] > 0.0))
            return fail(r, DEM_EIO, "Atoms: diameter must be > 0, got", f[2]);
        if (!(v[1] > 0.0))
            return fail(r, DEM_EIO, "Atoms: density must be > 0, got", f[3]);
        /* a sphere wider than the box is no packing; the test below,
         * which allows a diameter's slack, would let any centre pass */
        for (int a = 0; a < 2; a++)
            if (!(v[0] <= d->hi[a] - d->lo[a]))
                return dem_error_set(
                    r->err, DEM_EIO,
                    "%s:%d: Atoms: atom %ld's diameter %.17g exceeds the "
                    "box's extent along %c (%.17g)",
                    r->path, r->lineno, id, v[0], "xy"[a],
                    d->hi[a] - d->lo[a]);
        /* write_data wraps every position into the box, and a periodic
         * cell's particles leave it by less than a skin between wraps; a
         * centre further out than the particle's diameter is a broken
         * file (a box of walls built around it would be absurd) */
        for (int a = 0; a < 3; a++)
            if (!(v[2 + a] >= d->lo[a] - v[0] && v[2 + a] <= d->hi[a] + v[0]))
                return dem_error_set(
                    r->err, DEM_EIO,
                    "%s:%d: Atoms: atom %ld at %c = %.17g lies outside the "
                    "box (%clo %chi %.17g %.17g) by more than its diameter",
                    r->path, r->lineno, id, "xyz"[a], v[2 + a], "xyz"[a],
                    "xyz"[a], d->lo[a], d->hi[a]);
        /* the mass every reader of these files gives the atom (a sphere's,
         * dem_lammps_data_sim) */
        double m, I;
        dem_particle_mass(0.5 * v[0], v[1], DEM_MASS_SPHERE, 3, &m, &I);
        if (!dem_particle_mass_in_range(m, I))
            return dem_error_set(
                r->err, DEM_EIO,
                "%s:%d: Atoms: atom %ld's diameter %.17g and density %.17g "
                "give a mass of %.17g kg and a moment of inertia of %.17g "
                "kg m^2, out of range",
                r->path, r->lineno, id, v[0], v[1], m, I);
        d->id[k] = (int)id;
        d->diameter[k] = v[0];
        d->density[k] = v[1];
        d->x[k] = v[2];
        d->y[k] = v[3];
        d->z[k] = v[4];
        k++;
    }
    if (alloc_velocities(d))
        return dem_error_set(r->err, DEM_ENOMEM, "%s: out of memory", r->path);
    *seen = 1;
    return DEM_OK;
}

/* One line of the Velocities section into done[] (blank: nothing); *k
 * counts the atoms read. */
static int read_velocity(struct reader *r, const struct id_index *map,
                         unsigned char *done, int *k)
{
    struct dem_lammps_data *d = r->d;
    char *f[MAX_FIELDS];
    int nf;
    if (next_fields(r, f, &nf) < 0)
        return dem_error_set(
            r->err, DEM_EIO, "%s:%d: Velocities: file ends after %d of %d atoms",
            r->path, r->lineno, *k, d->n);
    if (nf == 0)
        return DEM_OK;
    if (nf != 7)
        return dem_error_set(r->err, DEM_EIO,
                             "%s:%d: Velocities: %d columns, expected 7 "
                             "(id vx vy vz wx wy wz)",
                             r->path, r->lineno, nf);
    long id;
    double v[6];
    /* (an id beyond an int must not wrap onto another atom's) */
    if (!integer(f[0], &id) || id < 1 || id > 2147483647L)
        return fail(r, DEM_EIO, "Velocities: bad atom id", f[0]);
    struct id_index key = {(int)id, 0};
    const struct id_index *hit =
        bsearch(&key, map, (size_t)d->n, sizeof *map, cmp_id);
    if (!hit)
        return fail(r, DEM_EIO, "Velocities: no atom with id", f[0]);
    const int i = hit->index;
    if (done[i])
        return fail(r, DEM_EIO, "Velocities: a second line for atom", f[0]);
    for (int c = 0; c < 6; c++)
        if (!number(f[1 + c], &v[c]))
            return fail(r, DEM_EIO, "Velocities: bad number", f[1 + c]);
    d->vx[i] = v[0];
    d->vy[i] = v[1];
    d->vz[i] = v[2];
    d->wx[i] = v[3];
    d->wy[i] = v[4];
    d->wz[i] = v[5];
    done[i] = 1;
    ++*k;
    return DEM_OK;
}

/* The Velocities section: one line for each atom. */
static int read_velocities(struct reader *r, const struct id_index *map)
{
    struct dem_lammps_data *d = r->d;
    unsigned char *done = calloc((size_t)d->n, 1);
    if (!done)
        return dem_error_set(r->err, DEM_ENOMEM, "%s: out of memory", r->path);
    int rc = DEM_OK, k = 0;
    while (k < d->n && !rc)
        rc = read_velocity(r, map, done, &k);
    free(done);
    if (!rc)
        d->has_velocities = 1;
    return rc;
}

/* Sorted id table; error on a repeated id. */
static int build_map(struct reader *r, struct id_index **out)
{
    struct dem_lammps_data *d = r->d;
    struct id_index *map = malloc((size_t)d->n * sizeof *map);
    if (!map)
        return dem_error_set(r->err, DEM_ENOMEM, "%s: out of memory", r->path);
    for (int i = 0; i < d->n; i++) {
        map[i].id = d->id[i];
        map[i].index = i;
    }
    qsort(map, (size_t)d->n, sizeof *map, cmp_id);
    for (int i = 1; i < d->n; i++)
        if (map[i].id == map[i - 1].id) {
            int id = map[i].id;
            free(map);
            return dem_error_set(r->err, DEM_EIO,
                                 "%s: Atoms: atom id %d appears twice", r->path,
                                 id);
        }
    *out = map;
    return DEM_OK;
}

/* The title line and the header, up to the first section name, which is
 * left in f (nf fields). Fills d->n, lo and hi. */
static int read_header(struct reader *r, char **f, int *nf)
{
    struct dem_lammps_data *d = r->d;
    int have_box[3] = {0, 0, 0};
    long natoms = -1;
    /* the first line is a title, whatever it says */
    if (next_fields(r, f, nf) < 0)
        return dem_error_set(r->err, DEM_EIO, "%s: empty file", r->path);
    static const char *const bounds[3][2] = {
        {"xlo", "xhi"}, {"ylo", "yhi"}, {"zlo", "zhi"}};
    for (;;) {
        if (next_fields(r, f, nf) < 0)
            return dem_error_set(r->err, DEM_EIO, "%s: no Atoms section",
                                 r->path);
        if (*nf == 0)
            continue;
        if (*nf == 2 && !strcmp(f[1], "atoms")) {
            if (!integer(f[0], &natoms) || natoms < 1)
                return fail(r, DEM_EIO, "bad atom count", f[0]);
            if (natoms > DEM_MAX_PARTICLES)
                return dem_error_set(r->err, DEM_EIO,
                                     "%s:%d: %ld atoms: more than the %d "
                                     "dembox takes",
                                     r->path, r->lineno, natoms,
                                     DEM_MAX_PARTICLES);
            continue;
        }
        if (*nf == 3 && !strcmp(f[1], "atom") && !strcmp(f[2], "types"))
            continue;
        if (*nf == 6 && !strcmp(f[3], "xy"))
            return fail(r, DEM_EIO,
                        "triclinic boxes (xy xz yz) are not "
                        "supported",
                        0);
        int axis = -1;
        for (int a = 0; a < 3; a++)
            if (*nf == 4 && !strcmp(f[2], bounds[a][0]) &&
                !strcmp(f[3], bounds[a][1]))
                axis = a;
        if (axis >= 0) {
            if (!number(f[0], &d->lo[axis]) || !number(f[1], &d->hi[axis]) ||
                !(d->hi[axis] > d->lo[axis]))
                return fail(r, DEM_EIO, "bad box bounds for", bounds[axis][0]);
            have_box[axis] = 1;
            continue;
        }
        break; /* the first section name */
    }
    if (natoms < 0)
        return fail(r, DEM_EIO, "section before the \"N atoms\" line:", f[0]);
    for (int a = 0; a < 3; a++)
        if (!have_box[a])
            return dem_error_set(r->err, DEM_EIO, "%s: no \"%s %s\" line",
                                 r->path, bounds[a][0], bounds[a][1]);
    d->n = (int)natoms;
    return DEM_OK;
}

static int read_body(struct reader *r)
{
    struct dem_lammps_data *d = r->d;
    char *f[MAX_FIELDS];
    int nf, atoms = 0;
    struct id_index *map = 0;
    int rc = read_header(r, f, &nf);
    if (rc)
        return rc;
    /* sections: f holds the name of the current one (comment cut) */
    for (;;) {
        if (nf == 0) {
            /* blank */
        } else if (nf == 1 && !strcmp(f[0], "Atoms")) {
            if (atoms) {
                rc = fail(r, DEM_EIO, "second Atoms section", 0);
                break;
            }
            /* another style of 7 or 10 columns (peri: id type volume
             * density x y z) would pass the count of columns */
            if (r->style[0] && strcmp(r->style, "sphere")) {
                rc = dem_error_set(r->err, DEM_EIO,
                                   "%s:%d: Atoms # %s: atom_style sphere "
                                   "expected (id type diameter density x y z)",
                                   r->path, r->lineno, r->style);
                break;
            }
            rc = read_atoms(r, &atoms);
            if (!rc)
                rc = build_map(r, &map);
            if (rc)
                break;
        } else if (nf == 1 && !strcmp(f[0], "Velocities")) {
            if (!atoms || d->has_velocities) {
                rc = fail(r, DEM_EIO,
                          atoms ? "second Velocities section"
                                : "Velocities before Atoms",
                          0);
                break;
            }
            rc = read_velocities(r, map);
            if (rc)
                break;
        } else {
            rc = fail(r, DEM_EIO, "unsupported section or line:", f[0]);
            break;
        }
        /* "Atoms # sphere": its style checked above; a section without
         * one is taken for sphere, and its column count checked */
        if (next_fields(r, f, &nf) < 0)
            break;
    }
    free(map);
    if (!rc && !atoms)
        rc = dem_error_set(r->err, DEM_EIO, "%s: no Atoms section", r->path);
    return rc;
}

static int read_stream(struct dem_lammps_data *d, FILE *f, const char *path,
                       int header_only, struct dem_error *err)
{
    memset(d, 0, sizeof *d);
    struct reader r = {path, f, 0, 0, 0, d, err, ""};
    char *fields[MAX_FIELDS];
    int nf;
    int rc = header_only ? read_header(&r, fields, &nf) : read_body(&r);
    if (!rc && ferror(f))
        rc = dem_error_set(err, DEM_EIO, "%s: read error", path);
    free(r.line);
    if (rc)
        dem_lammps_data_free(d);
    return rc;
}

static int read_file(struct dem_lammps_data *d, const char *path,
                     int header_only, struct dem_error *err)
{
    memset(d, 0, sizeof *d);
    FILE *f;
    int rc = dem_open_text(&f, path, "a LAMMPS data file", err);
    if (rc)
        return rc;
    rc = read_stream(d, f, path, header_only, err);
    fclose(f);
    return rc;
}

int dem_lammps_data_read(struct dem_lammps_data *d, const char *path,
                         struct dem_error *err)
{
    return read_file(d, path, 0, err);
}

int dem_lammps_data_read_stream(struct dem_lammps_data *d, FILE *f,
                                const char *path, struct dem_error *err)
{
    return read_stream(d, f, path, 0, err);
}

int dem_lammps_data_read_header(struct dem_lammps_data *d, const char *path,
                                struct dem_error *err)
{
    return read_file(d, path, 1, err);
}

int dem_lammps_data_write(const char *path, const struct dem_particles *p,
                          const double lo[3], const double hi[3],
                          const char *comment, struct dem_error *err)
{
    struct dem__outfile o;
    int rc = dem__outfile_open(&o, path, err);
    if (rc)
        return rc;
    fprintf(o.f, "%s\n\n%d atoms\n1 atom types\n\n",
            comment ? comment : "LAMMPS data file written by dembox", p->n);
    static const char *const ax[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; a++)
        fprintf(o.f, "%.17g %.17g %slo %shi\n", lo[a], hi[a], ax[a], ax[a]);
    fputs("\nAtoms # sphere\n\n", o.f);
    for (int i = 0; i < p->n; i++) {
        double a = p->r[i];
        double rho = p->m[i] / (4.0 / 3.0 * M_PI * a * a * a);
        fprintf(o.f, "%d 1 %.17g %.17g %.17g %.17g %.17g\n", p->id[i] + 1,
                2.0 * a, rho, p->x[i], p->y[i], p->z[i]);
    }
    fputs("\nVelocities\n\n", o.f);
    for (int i = 0; i < p->n; i++)
        fprintf(o.f, "%d %.17g %.17g %.17g %.17g %.17g %.17g\n", p->id[i] + 1,
                p->vx[i], p->vy[i], p->vz[i], p->wx[i], p->wy[i], p->wz[i]);
    return dem__outfile_commit(&o, err);
}

int dem_lammps_data_sim(struct dem_sim *s, const struct dem_config *cfg,
                        const struct dem_lammps_data *d, const double lo[3],
                        const double hi[3], struct dem_error *err)
{
    int rc = dem_sim_create_empty(s, cfg, d->n, lo, hi, err);
    if (rc)
        return rc;
    s->reorder = 1; /* as dem_sim_create: in cell order at every build */
    for (int k = 0; k < d->n; k++) {
        int i = dem_particles_add(&s->p, d->x[k], d->y[k], d->z[k],
                                  0.5 * d->diameter[k], d->density[k],
                                  DEM_MASS_SPHERE, cfg->dim);
        if (i < 0) {
            dem_sim_destroy(s);
            return dem_error_set(err, DEM_EINTERNAL,
                                 "particle %d of the data file", k);
        }
        s->p.vx[i] = d->vx[k];
        s->p.vy[i] = d->vy[k];
        s->p.vz[i] = cfg->dim == 2 ? 0.0 : d->vz[k];
        s->p.wz[i] = d->wz[k];
        if (cfg->dim == 3) {
            s->p.wx[i] = d->wx[k];
            s->p.wy[i] = d->wy[k];
        }
    }
    rc = dem_sim_ready(s, err);
    if (rc)
        dem_sim_destroy(s);
    return rc;
}
