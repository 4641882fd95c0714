/* libFuzzer harness for the particle CSV reader: arbitrary bytes as a
 * particle file, read from memory (fmemopen) in 2D and in 3D, with the
 * sphere and the disc mass model. Any crash, leak, sanitizer report,
 * message that is not one line, or particle that comes back with a
 * non-finite or non-positive radius, mass or inverse mass or inertia is a
 * finding.
 *
 * Then the same bytes as a run's particles.file (files of at most 64
 * particles): the sample built as `dembox run` builds it
 * (dem_particles_load: the box's checks, a periodic cell's wrap; the
 * overlaps; dem_sim_create), between walls or in a periodic cell, with
 * box.size given or not, as the sum of the bytes says, and 10 steps.
 * Refused: one line; built: every centre and velocity finite (a
 * session-112 review found a centre at 1e308 wrapped to minus
 * infinity).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <unistd.h>

#include "core/sim.h"
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

/* The bytes as a run's particle file: the sample `dembox run` builds. */
static void sample_of(const uint8_t *data, size_t size)
{
    static char path[512];
    if (!path[0]) {
        fuzz_tmp_path(path, sizeof path, "sample.csv");
        if (strpbrk(path, "\"\\")) /* (it goes into the config's text) */
            snprintf(path, sizeof path, "/tmp/dembox_fuzz_sample_%ld.csv",
                     (long)getpid());
    }
    unsigned mode = 0;
    for (size_t k = 0; k < size; k++)
        mode += data[k];
    const int dim = mode & 1 ? 2 : 3, periodic = (mode & 2) != 0,
              sized = periodic || (mode & 4);
    char text[1024], box[160] = "";
    if (sized)
        snprintf(box, sizeof box, "box = { size = [0.02, 0.02, %s];%s };\n",
                 dim == 3 ? "0.02" : "0.0",
                 periodic ? " boundary = \"periodic\";" : "");
    snprintf(text, sizeof text,
             "dimension = %d; time_step = \"auto\";\n%s"
             "particles = { placement = \"file\"; file = \"%s\";\n"
             "  radius = { distribution = \"mono\"; mean = 5.0e-4; }; };\n"
             "contact = { k = 1000.0; mu = 0.3; };\n"
             "stages = ( { type = \"hold\"; duration = 1.0e-3; } );\n",
             dim, box, path);
    struct dem_config c;
    struct dem_error err = {0};
    if (dem_config_parse(&c, text, "fuzz.cfg", NULL, 0, &err)) {
        fprintf(stderr, "the harness's own config: %s\n", err.msg);
        abort(); /* the config is this harness's, not the input */
    }
    fuzz_write_file(path, data, size);
    struct dem_particles given = {0};
    int rc = dem_particles_load(&given, &c, &err);
    unlink(path);
    if (rc == DEM_OK && given.n > 64) { /* (the steps' time is the limit) */
        dem_particles_free(&given);
        return;
    }
    struct dem_sim s;
    if (rc == DEM_OK)
        rc = dem_sim_create(&s, &c, &given, &err);
    dem_particles_free(&given);
    if (rc != DEM_OK) {
        fuzz_one_line(&err);
        return;
    }
    for (int k = 0; k < 10 && rc == DEM_OK; k++)
        rc = dem_sim_step(&s, &err);
    if (rc != DEM_OK)
        fuzz_one_line(&err);
    const struct dem_particles *P = &s.p;
    for (int i = 0; i < P->n && rc == DEM_OK; i++) {
        const double v[6] = {P->x[i],  P->y[i],  P->z[i],
                             P->vx[i], P->vy[i], P->vz[i]};
        for (int k = 0; k < 6; k++)
            if (!isfinite(v[k]))
                abort();
    }
    dem_sim_destroy(&s);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 1 << 16)
        return 0;
    read_as(data, size, 2, DEM_MASS_DISC);
    read_as(data, size, 3, DEM_MASS_SPHERE);
    sample_of(data, size);
    return 0;
}
