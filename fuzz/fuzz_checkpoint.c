/* libFuzzer harness for the checkpoint reader.
 *
 * A checkpoint carries a length field, the build that wrote it and a
 * CRC-32, so almost every mutated file is refused at the door. To reach the
 * reader's checks of the counts, the sections and every index, the harness
 * first makes a real checkpoint with this very build (a tiny run stopped
 * by the stop_after_steps hook) and uses it as a template, one of three
 * (a 2D adhesive luding sample between walls with wall friction; a 3D
 * hertz sample with rolling and torsion resistance; a 2D periodic cell
 * stopped in a shear stage past its Lees-Edwards re-map):
 *   - an input whose first byte is even is read as it is (the door);
 *   - otherwise the first byte's next bits choose the template and the
 *     rest of the input is a list of edits (4 bytes of offset, 1 byte of
 *     value) applied to it, whose length field and checksum are then set
 *     right, as the writer would.
 * Any crash, leak, sanitizer report or message that is not one line is a
 * finding; an accepted file must give a simulation that can be freed, and
 * a template without edits must be accepted.
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

#define NTMPL 3
static unsigned char *tmpl[NTMPL]; /* valid checkpoints of this build */
static size_t tmpl_n[NTMPL];

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

static const char *const hertz3d =
    "dimension = 3; seed = 3; time_step = \"auto\";\n"
    "particles = { count = 12; radius = { distribution = \"uniform\";"
    " min = 0.5e-3; max = 1.0e-3; }; placement = \"random\";"
    " volume_fraction = 0.2; };\n"
    "contact = { normal = \"hertz\"; E = 1.0e7; nu = 0.25; restitution = "
    "0.5; mu = 0.5; rolling = \"luding\"; torsion = \"luding\"; wall_mu = "
    "0.2; wall_mu_r = 0.05; };\n"
    "walls = { mass = 0.01; gamma = 2.0; max_speed = 0.5; };\n"
    "stages = ( { type = \"isotropic\"; pressure = 500.0; max_time = 1.0; } "
    ");\n"
    "output = { interval = 1.0e-5; snapshot_interval = 0.0;"
    " checkpoint_interval = 0.0; };\n";

/* (3000 steps: the shear at gamma 0.95, re-mapped at 0.5) */
static const char *const cell2d =
    "dimension = 2; seed = 4; time_step = \"auto\";\n"
    "box = { boundary = \"periodic\"; };\n"
    "particles = { count = 12; radius = { distribution = \"uniform\";"
    " min = 0.5e-3; max = 1.5e-3; }; placement = \"random\";"
    " volume_fraction = 0.4; };\n"
    "contact = { normal = \"luding\"; k1 = 5.0e4; k2 = 1.0e5; gamma_n = 0.1;"
    " kt = 2.0e4; gamma_t = 0.02; mu = 0.5; };\n"
    "walls = { mass = 0.01; gamma = 2.0; max_speed = 0.5; };\n"
    "stages = ( { type = \"isotropic\"; pressure = 500.0; max_time = 1.0e-4; "
    "}, { type = \"shear\"; shear_strain = 1.0; duration = 4.0e-4; "
    "pressure = 500.0; } );\n"
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

/* Template k: the checkpoint of its config's run stopped after 3000
 * steps. */
static void make_template(int k, const char *text)
{
    char dir[512], path[600];
    fuzz_tmp_path(dir, sizeof dir, "ckpt_tmpl");
    struct dem_config c;
    struct dem_error err = {0};
    if (dem_config_parse(&c, text, "fuzz template", 0, 0, &err)) {
        fprintf(stderr, "template %d: %s\n", k, err.msg);
        abort();
    }
    struct dem_run_options o;
    memset(&o, 0, sizeof o);
    o.outdir = dir;
    o.threads = 1;
    o.stop_after_steps = 3000;
    if (dem_run(&c, &o, &err) != DEM_EINTERRUPTED) {
        fprintf(stderr, "template %d: %s\n", k, err.msg);
        abort();
    }
    snprintf(path, sizeof path, "%s/checkpoint.bin", dir);
    FILE *f = fopen(path, "rb");
    if (!f || fseek(f, 0, SEEK_END) != 0)
        abort();
    tmpl_n[k] = (size_t)ftell(f);
    rewind(f);
    tmpl[k] = malloc(tmpl_n[k]);
    if (!tmpl[k] || fread(tmpl[k], 1, tmpl_n[k], f) != tmpl_n[k])
        abort();
    fclose(f);
    if (nftw(dir, remove_one, 16, FTW_DEPTH | FTW_PHYS) != 0)
        abort();
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *const text[NTMPL] = {tiny, hertz3d, cell2d};
    for (int k = 0; k < NTMPL; k++)
        make_template(k, text[k]);
    return 0;
}

/* The bytes as a checkpoint file: 1 when accepted. */
static int read_file(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    if (size && fwrite(data, 1, size, f) != size) {
        fclose(f);
        return 0;
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
        return 0;
    }
    free(config);
    dem_ckpt_run_free(&run);
    dem_sim_destroy(&s);
    return 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[512];
    fuzz_tmp_path(path, sizeof path, "ckpt.bin");
    if (size == 0 || !(data[0] & 1)) {
        read_file(path, data, size);
    } else {
        const int t = (data[0] >> 1) % NTMPL;
        const size_t n = tmpl_n[t];
        unsigned char *copy = malloc(n);
        if (!copy)
            return 0;
        memcpy(copy, tmpl[t], n);
        for (size_t k = 1; k + 5 <= size; k += 5) {
            uint32_t off;
            memcpy(&off, data + k, 4);
            copy[off % n] = data[k + 4];
        }
        uint64_t length = n;
        memcpy(copy + 20, &length, 8);
        uint32_t crc = dem_crc32(0, copy, n - 4);
        memcpy(copy + n - 4, &crc, 4);
        if (!read_file(path, copy, n) && size < 6)
            abort(); /* the template itself, refused */
        free(copy);
    }
    remove(path);
    return 0;
}
