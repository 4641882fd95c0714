/* libFuzzer harness for the LAMMPS data files of `dembox bench --data`
 * (issue 14: an unreadable or inconsistent data file stops with a
 * one-line error naming the cause, never a crash or a wrong timing).
 *
 * The bytes are read twice:
 *   - from memory (fmemopen) by the reader alone. An accepted file must
 *     hold what the reader promises (formats/lammps_data.h): at least one
 *     atom, ids unique and positive, diameters and densities positive and
 *     finite with a sphere's mass and inertia in range, every centre
 *     within the box by at most its diameter, finite velocities; a refused
 *     one leaves the data empty.
 *   - as a file by the benchmark's own start (dem_bench_from_data: the
 *     workload's config, the packing's checks), in 3D or in 2D and between
 *     walls or in a periodic cell as the first byte says, and when it
 *     builds, 20 chained steps and a measurement of the state. A step may
 *     refuse to go on (an error), never crash.
 * Any crash, leak, sanitizer report (float-to-int overflow included) or
 * message that is empty or not one line is a finding.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench/bench.h"
#include "core/particles.h"
#include "formats/lammps_data.h"
#include "measure/measure.h"
#include "memfile.h"
#include "oracles.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static int cmp_int(const void *a, const void *b)
{
    const int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* What an accepted file promises. */
static void check_data(const struct dem_lammps_data *d)
{
    if (d->n < 1 || !d->id || !d->x || !d->vx || !d->wz)
        abort();
    int *ids = malloc((size_t)d->n * sizeof *ids);
    if (!ids)
        abort();
    memcpy(ids, d->id, (size_t)d->n * sizeof *ids);
    qsort(ids, (size_t)d->n, sizeof *ids, cmp_int);
    for (int k = 0; k < d->n; k++)
        if (ids[k] < 1 || (k > 0 && ids[k] == ids[k - 1]))
            abort();
    free(ids);
    for (int a = 0; a < 3; a++)
        if (!isfinite(d->lo[a]) || !isfinite(d->hi[a]) ||
            !(d->hi[a] > d->lo[a]))
            abort();
    for (int k = 0; k < d->n; k++) {
        const double D = d->diameter[k], c[3] = {d->x[k], d->y[k], d->z[k]};
        double m, I;
        dem_particle_mass(0.5 * D, d->density[k], DEM_MASS_SPHERE, 3, &m, &I);
        if (!(D > 0) || !isfinite(D) || !(d->density[k] > 0) ||
            !isfinite(d->density[k]) || !dem_particle_mass_in_range(m, I))
            abort();
        for (int a = 0; a < 3; a++)
            if (!(c[a] >= d->lo[a] - D && c[a] <= d->hi[a] + D))
                abort();
        const double v[6] = {d->vx[k], d->vy[k], d->vz[k],
                             d->wx[k], d->wy[k], d->wz[k]};
        for (int e = 0; e < 6; e++)
            if (!isfinite(v[e]) || (!d->has_velocities && v[e] != 0.0))
                abort();
    }
}

static void read_from_memory(const uint8_t *data, size_t size)
{
    FILE *f = fuzz_memfile(data, size);
    if (!f)
        return;
    struct dem_lammps_data d;
    struct dem_error err = {0};
    const int rc = dem_lammps_data_read_stream(&d, f, "fuzz.data", &err);
    fclose(f);
    if (rc != DEM_OK) {
        fuzz_one_line(&err);
        if (d.n != 0 || d.id || d.x || d.vx)
            abort(); /* on error the data are left empty */
        return;
    }
    check_data(&d);
    dem_lammps_data_free(&d);
}

/* The benchmark's start from the same bytes as a file, then a few steps. */
static void bench_start(const uint8_t *data, size_t size)
{
    static char path[512];
    if (!path[0])
        fuzz_tmp_path(path, sizeof path, "lammps.data");
    fuzz_write_file(path, data, size);
    const int dim = size && (data[0] & 1) ? 2 : 3;
    const int periodic = size && (data[0] & 2);
    struct dem_sim s;
    struct dem_error err = {0};
    int rc = dem_bench_from_data(&s, dim, periodic, path, &err);
    unlink(path);
    if (rc != DEM_OK) {
        fuzz_one_line(&err);
        return;
    }
    double L0[3], V0;
    dem_sim_box(&s, L0, &V0);
    for (int k = 0; k < 20 && rc == DEM_OK; k++) {
        s.chain = k + 1 < 20; /* the last step measures */
        s.measure = !s.chain;
        rc = dem_sim_step(&s, &err);
    }
    if (rc != DEM_OK)
        fuzz_one_line(&err);
    else {
        struct dem_sample smp;
        dem_measure(&s, L0, V0, 0.0, 0, &smp);
    }
    dem_sim_destroy(&s);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 1 << 16)
        return 0;
    read_from_memory(data, size);
    bench_start(data, size);
    return 0;
}
