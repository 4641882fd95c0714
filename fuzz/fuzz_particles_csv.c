/* libFuzzer harness for the particle CSV reader: arbitrary bytes as a
 * particle file, read from memory (fmemopen) in 2D and in 3D, with the
 * sphere and the disc mass model. Any crash, leak, sanitizer report,
 * message that is not one line, or particle that comes back with a
 * non-finite or non-positive radius, mass or inverse mass or inertia is a
 * finding.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dembox.h"
#include "formats/particles_csv.h"
#include "memfile.h"
#include "oracles.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void read_as(const uint8_t *data, size_t size, int dim, int model)
{
    FILE *f = fuzz_memfile(data, size);
    if (!f)
        return;
    struct dem_particles p;
    struct dem_error err = {0};
    int *lines = 0;
    int rc = dem_particles_read_csv_stream(&p, f, "fuzz.csv", dim, 2000.0,
                                           model, &lines, &err);
    fclose(f);
    if (rc != DEM_OK) {
        fuzz_one_line(&err);
        if (p.n != 0 || lines)
            abort(); /* on error the particles are left empty */
        return;
    }
    for (int i = 0; i < p.n; i++) {
        const double v[] = {p.r[i], p.m[i], p.inv_m[i], p.inv_I[i]};
        for (int k = 0; k < 4; k++)
            if (!(v[k] > 0) || !isfinite(v[k]))
                abort();
        if (lines[i] < 1)
            abort();
        if (dim == 2 && p.z[i] != 0)
            abort();
    }
    free(lines);
    dem_particles_free(&p);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 1 << 16)
        return 0;
    read_as(data, size, 2, DEM_MASS_DISC);
    read_as(data, size, 3, DEM_MASS_SPHERE);
    return 0;
}
