/* particles.png of a finished run: the final packing of
 * particles_final.csv in the final box, each particle coloured by its
 * contact force sum from forces_final.csv (by its speed when that file
 * is absent), drawn by dem__plot_particles.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/fsutil.h"
#include "plot/plot.h"

enum pk_col { PK_X, PK_Y, PK_Z, PK_VX, PK_VY, PK_VZ, PK_R, PK_NCOL };

static const struct dem__csv_want pk_want[PK_NCOL] = {
    [PK_X] = DEM_CSV_FINITE("x", 1),      [PK_Y] = DEM_CSV_FINITE("y", 1),
    [PK_Z] = DEM_CSV_FINITE("z", 0),      [PK_VX] = DEM_CSV_FINITE("vx", 0),
    [PK_VY] = DEM_CSV_FINITE("vy", 0),    [PK_VZ] = DEM_CSV_FINITE("vz", 0),
    [PK_R] = DEM_CSV_FINITE("radius", 1),
};

/* Extent of the packing, for a timeseries without wall positions. */
static void packing_box(struct dem__plot_packing *w)
{
    const struct dem__plot_packing *pk = w;
    for (int a = 0; a < 3; a++) {
        w->lo[a] = INFINITY;
        w->hi[a] = -INFINITY;
    }
    for (int i = 0; i < pk->n; i++) {
        const double c[3] = {pk->x[i], pk->y[i], pk->z ? pk->z[i] : 0.0};
        for (int a = 0; a < 3; a++) {
            w->lo[a] = fmin(w->lo[a], c[a] - pk->r[i]);
            w->hi[a] = fmax(w->hi[a], c[a] + pk->r[i]);
        }
    }
}

/* Read forces_final.csv (optional) into fsum (NULL if absent). */
static int read_forces(const char *outdir, size_t n, double **fsum,
                       struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    *fsum = NULL;
    int rc = dem_path_join(path, sizeof path, outdir, "forces_final.csv", err);
    if (rc)
        return rc;
    FILE *probe = fopen(path, "r");
    if (!probe)
        return errno == ENOENT
                   ? DEM_OK
                   : dem_error_set(err, DEM_EIO, "%s: cannot open: %s", path,
                                   strerror(errno));
    fclose(probe);
    static const struct dem__csv_want want[1] = {DEM_CSV_FINITE("fsum", 1)};
    struct dem__csv_table t;
    rc = dem__csv_table_read(&t, path, want, 1, err);
    if (rc)
        return rc;
    if (t.nrow != n) {
        dem__csv_table_free(&t);
        return dem_error_set(err, DEM_EIO,
                             "%s: %zu rows, but particles_final.csv has %zu "
                             "particles",
                             path, t.nrow, n);
    }
    *fsum = t.col[0];
    t.col[0] = NULL;
    dem__csv_table_free(&t);
    return DEM_OK;
}

int dem__plot_read_packing(const char *outdir, struct dem__csv_table *pt,
                           struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    const int rc =
        dem_path_join(path, sizeof path, outdir, "particles_final.csv", err);
    return rc ? rc : dem__csv_table_read(pt, path, pk_want, PK_NCOL, err);
}

int dem__plot_packing_3d(const struct dem__csv_table *pt)
{
    for (size_t i = 0; pt->col[PK_Z] && i < pt->nrow; i++)
        if (pt->col[PK_Z][i] != 0.0)
            return 1;
    return 0;
}

/* Read OUTDIR/contacts_final.csv (optional) into t; 1 when read. */
static int read_chains(const char *outdir, struct dem__csv_table *t,
                       struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    if (dem_path_join(path, sizeof path, outdir, "contacts_final.csv", err))
        return 0;
    FILE *probe = fopen(path, "r");
    if (!probe)
        return 0;
    fclose(probe);
    static const struct dem__csv_want want[6] = {
        DEM_CSV_FINITE("id_i", 1), DEM_CSV_FINITE("id_j", 1),
        DEM_CSV_FINITE("fn", 1),   DEM_CSV_FINITE("x", 1),
        DEM_CSV_FINITE("y", 1),    DEM_CSV_FINITE("delta", 1)};
    struct dem_error e = {0};
    if (dem__csv_table_read(t, path, want, 6, &e)) {
        dem_warn(err, "%s; particles.png without force chains", e.msg);
        return 0;
    }
    return 1;
}

int dem__plot_run_particles(const char *outdir, const char *plotdir,
                            const struct dem__csv_table *pt, int dim,
                            const double *lo, const double *hi, int cell,
                            struct dem_error *err)
{
    double *fsum = NULL, *speed = NULL, *wx = NULL, *wcx = NULL;
    int rc = read_forces(outdir, pt->nrow, &fsum, err);
    if (rc)
        return rc;
    struct dem__plot_packing pk = {.n = (int)pt->nrow,
                                   .dim = dim,
                                   .x = pt->col[PK_X],
                                   .y = pt->col[PK_Y],
                                   .z = pt->col[PK_Z],
                                   .r = pt->col[PK_R],
                                   .value = fsum,
                                   .value_label = "contact force sum Σ|f| (N)"};
    if (!fsum) {
        speed = malloc((pt->nrow ? pt->nrow : 1) * sizeof *speed);
        if (!speed)
            return dem_error_set(err, DEM_ENOMEM, "out of memory");
        for (size_t i = 0; i < pt->nrow; i++) {
            double v2 = 0.0;
            for (int k = PK_VX; k <= PK_VZ; k++)
                if (pt->col[k])
                    v2 += pt->col[k][i] * pt->col[k][i];
            speed[i] = sqrt(v2);
        }
        pk.value = speed;
        pk.value_label = "speed |v| (m/s), no forces_final.csv";
    }
    if (lo && hi && pk.n > 0) {
        memcpy(pk.lo, lo, sizeof pk.lo);
        memcpy(pk.hi, hi, sizeof pk.hi);
    } else {
        packing_box(&pk);
    }
    struct dem__csv_table chains;
    const int have = read_chains(outdir, &chains, err);
    if (have) {
        pk.nchain = (int)chains.nrow;
        pk.chain_i = chains.col[0];
        pk.chain_j = chains.col[1];
        pk.chain_fn = chains.col[2];
        pk.chain_cx = chains.col[3];
        pk.chain_cy = chains.col[4];
        pk.chain_delta = chains.col[5];
    }
    /* a periodic cell: each centre at its image in [lo, hi) along x (a
     * lattice vector of any cell, sheared or not: a sheared cell's
     * parallelogram fills the box), its contacts' points moved with it;
     * a pair whose partner moved otherwise is drawn as through an image */
    const double Lx = lo && hi ? hi[0] - lo[0] : 0.0;
    if (cell && Lx > 0.0 && pk.n > 0) {
        wx = malloc((size_t)pk.n * sizeof *wx);
        wcx = malloc((size_t)(pk.nchain > 0 ? pk.nchain : 1) * sizeof *wcx);
        if (!wx || !wcx) {
            rc = dem_error_set(err, DEM_ENOMEM, "out of memory");
        } else {
            for (int i = 0; i < pk.n; i++)
                wx[i] = pk.x[i] - Lx * floor((pk.x[i] - lo[0]) / Lx);
            for (int k = 0; k < pk.nchain; k++) {
                const double ci = pk.chain_i[k];
                wcx[k] = pk.chain_cx[k];
                if (ci >= 0.0 && ci < pk.n)
                    wcx[k] += wx[(int)ci] - pk.x[(int)ci];
            }
            pk.x = wx;
            pk.chain_cx = wcx;
        }
    }
    char png[DEM_PATH_MAX];
    if (!rc)
        rc = dem_path_join(png, sizeof png, plotdir, "particles.png", err);
    if (!rc)
        rc = dem__plot_particles(&pk, png, err);
    if (have)
        dem__csv_table_free(&chains);
    free(fsum);
    free(speed);
    free(wx);
    free(wcx);
    return rc;
}
