/* libFuzzer harness for the checkpoint reader.
 *
 * A checkpoint carries a length field, the build that wrote it and a
 * CRC-32, so almost every mutated file is refused at the door. To reach the
 * reader's checks of the counts, the sections and every index, the harness
 * first makes a real checkpoint with this very build (a tiny run stopped
 * by the stop_after_steps hook) and uses it as a template:
 *   - an input whose first byte is even is read as it is (the door);
 *   - otherwise the rest of the input is a list of edits (4 bytes of
 *     offset, 1 byte of value) applied to the template, whose length field
 *     and checksum are then set right, as the writer would.
 * Any crash, leak, sanitizer report or message that is not one line is a
 * finding; an accepted file must give a simulation that can be freed.
 */
#define _XOPEN_SOURCE 700 /* nftw */
#include <ftw.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dembox.h"
#include "io/checkpoint.h"
#include "memfile.h"
#include "oracles.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static unsigned char *tmpl; /* a valid checkpoint of this build */
static size_t tmpl_n;

static const char *const tiny =
    "dimension = 2; seed = 2; time_step = \"auto\";\n"
    "particles = { count = 12; radius = { distribution = \"uniform\";"
    " min = 0.5e-3; max = 1.5e-3; }; placement = \"random\";"
    " volume_fraction = 0.4; };\n"
    "contact = { normal = \"luding\"; k1 = 5.0e4; k2 = 1.0e5; kc = 1.0e4;"
    " gamma_n = 0.1; kt = 2.0e4; gamma_t = 0.02; mu = 0.5; wall_mu = 0.2; };\n"
    "walls = { mass = 0.01; gamma = 2.0; max_speed = 0.5; };\n"
    "stages = ( { type = \"isotropic\"; pressure = 500.0; max_time = 1.0; } "
    ");\n"
    "output = { interval = 1.0e-5; snapshot_interval = 0.0;"
    " checkpoint_interval = 0.0; };\n";

/* nftw: the template run's folder, its files first (no shell: the
 * path is TMPDIR's, whatever it holds) */
static int remove_one(const char *path, const struct stat *st, int type,
                      struct FTW *ftw)
{
    (void)st;
    (void)type;
    (void)ftw;
    return remove(path);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    char dir[512], path[600];
    fuzz_tmp_path(dir, sizeof dir, "ckpt_tmpl");
    struct dem_config c;
    struct dem_error err = {0};
    if (dem_config_parse(&c, tiny, "fuzz template", 0, 0, &err))
        abort();
    struct dem_run_options o;
    memset(&o, 0, sizeof o);
    o.outdir = dir;
    o.threads = 1;
    o.stop_after_steps = 3000;
    if (dem_run(&c, &o, &err) != DEM_EINTERRUPTED)
        abort();
    snprintf(path, sizeof path, "%s/checkpoint.bin", dir);
    FILE *f = fopen(path, "rb");
    if (!f || fseek(f, 0, SEEK_END) != 0)
        abort();
    tmpl_n = (size_t)ftell(f);
    rewind(f);
    tmpl = malloc(tmpl_n);
    if (!tmpl || fread(tmpl, 1, tmpl_n, f) != tmpl_n)
        abort();
    fclose(f);
    if (nftw(dir, remove_one, 16, FTW_DEPTH | FTW_PHYS) != 0)
        abort();
    return 0;
}

static void read_file(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return;
    if (size && fwrite(data, 1, size, f) != size) {
        fclose(f);
        return;
    }
    fclose(f);
    struct dem_sim s;
    struct dem_ckpt_run run;
    char *config = 0;
    struct dem_error err = {0};
    int rc = dem_checkpoint_read(path, &s, &config, &run, NULL, 0, &err);
    if (rc != DEM_OK && strstr(err.msg, "written by another build")) {
        /* as --any-build reads it: then it names that build, on one
         * printable line */
        char other[200];
        rc = dem_checkpoint_read(path, &s, &config, &run, other, sizeof other,
                                 &err);
        for (const char *c = other; rc == DEM_OK && *c; c++)
            if ((unsigned char)*c < 32 || (unsigned char)*c > 126)
                abort();
        if (rc == DEM_OK && !other[0])
            abort();
    }
    if (rc != DEM_OK) {
        fuzz_one_line(&err);
        return;
    }
    free(config);
    dem_ckpt_run_free(&run);
    dem_sim_destroy(&s);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[512];
    fuzz_tmp_path(path, sizeof path, "ckpt.bin");
    if (size == 0 || !(data[0] & 1)) {
        read_file(path, data, size);
    } else {
        unsigned char *copy = malloc(tmpl_n);
        if (!copy)
            return 0;
        memcpy(copy, tmpl, tmpl_n);
        for (size_t k = 1; k + 5 <= size; k += 5) {
            uint32_t off;
            memcpy(&off, data + k, 4);
            copy[off % tmpl_n] = data[k + 4];
        }
        uint64_t length = tmpl_n;
        memcpy(copy + 20, &length, 8);
        uint32_t crc = dem_crc32(0, copy, tmpl_n - 4);
        memcpy(copy + tmpl_n - 4, &crc, 4);
        read_file(path, copy, tmpl_n);
        free(copy);
    }
    remove(path);
    return 0;
}
