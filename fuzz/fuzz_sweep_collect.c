/* libFuzzer harness for `dembox sweep --collect` (dem_sweep_collect): the
 * cross-run analysis and the plots of a sweep whose runs' files were not
 * written by dembox as they are (edited, truncated, kept as numbers only
 * and collected again, from another version).
 *
 * The first byte's two low bits choose one of four grids over a built-in
 * example; the config.cfg of every point is written once, at start, as a
 * sweep writes it. The rest of the input is the runs' files: first run
 * 0's summary.json, then after each line "@@Nx" the file x (s
 * summary.json, t timeseries.csv) of run N (a digit, modulo the grid's
 * runs). A run without a summary.json is an unfinished one. The plots'
 * gnuplot is a command that does not exist (DEMBOX_GNUPLOT): their data
 * and scripts are written, not drawn.
 * Any crash, leak or sanitizer report (float-to-int overflow included), a
 * message that is empty or not one line, a sweep.json that the project's
 * own JSON reader cannot read back or that a refusal left behind, or a
 * plot script that could run a command (plots.h), is a finding.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dembox.h"
#include "io/fsutil.h"
#include "oracles.h"
#include "plots.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define NGRIDS 4
#define MAXRUNS 8

/* Each grid exercises a part of the analysis: the flow function and the
 * void-ratio fit over pressures; friction against μ; cohesion against kc
 * with ensembles over seeds; cyclic runs (verdicts, strain increments). */
static const struct {
    const char *example;
    const char *params[3];
} grids[NGRIDS] = {
    {"biaxial2d", {"stages.0.pressure,stages.1.pressure=100,200,400,800"}},
    {"biaxial2d", {"stages.1.pressure=200,800", "contact.mu=0.1,0.5"}},
    {"biaxial2d",
     {"stages.1.pressure=200,800", "contact.kc=0,2e4", "seed=1,2"}},
    {"cyclic3d", {"contact.mu=0.1,0.5", "seed=1,2"}},
};

static char dir[96];
static struct dem_sweep_grid grid[NGRIDS];
static char names[NGRIDS][MAXRUNS][DEM_SWEEP_RUNNAME_MAX + 8];
static int nruns[NGRIDS];

static void out_of(char *out, size_t n, int g)
{
    snprintf(out, n, "%s/g%d", dir, g);
}

static void run_file(char *out, size_t n, int g, int r, const char *name)
{
    snprintf(out, n, "%s/g%d/runs/%s/%s", dir, g, names[g][r], name);
}

static void put(const char *path, const uint8_t *p, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f || (n && fwrite(p, 1, n, f) != n) || fclose(f))
        abort();
}

/* The grids' folders and every point's config.cfg, as dem_sweep_run
 * leaves them. */
static void make_grid(int g)
{
    struct dem_error err = {0};
    for (int k = 0; k < 3 && grids[g].params[k]; k++)
        if (dem_sweep_param_add(&grid[g], grids[g].params[k], &err))
            abort();
    const long n = dem_sweep_grid_size(&grid[g]);
    if (n > MAXRUNS)
        abort();
    nruns[g] = (int)n;
    dem_sweep_point_names(&grid[g], names[g]);
    const struct dem_example *ex = dem_example_find(grids[g].example);
    char path[512];
    snprintf(path, sizeof path, "%s/g%d.cfg", dir, g);
    if (!ex)
        abort();
    put(path, (const uint8_t *)ex->text, strlen(ex->text));
    for (int r = 0; r < nruns[g]; r++) {
        char sets[DEM_SWEEP_MAX_PARAMS * DEM_SWEEP_MAX_KEYS]
                 [DEM_NAME_MAX + DEM_SWEEP_VALUE_MAX];
        const int ns = dem_sweep_point_sets(&grid[g], r, sets,
                                            (int)(sizeof sets / sizeof *sets));
        const char *setp[sizeof sets / sizeof *sets];
        for (int k = 0; k < ns; k++)
            setp[k] = sets[k];
        struct dem_config *c = malloc(sizeof *c);
        if (!c || dem_config_load_file(c, path, setp, ns, &err))
            abort();
        char folder[512], cfg[600];
        snprintf(folder, sizeof folder, "%s/g%d/runs/%s", dir, g, names[g][r]);
        if (dem_mkdir_p(folder, &err))
            abort();
        run_file(cfg, sizeof cfg, g, r, "config.cfg");
        FILE *f = fopen(cfg, "w");
        if (!f)
            abort();
        dem_config_write(c, f);
        if (fclose(f))
            abort();
        free(c);
    }
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    fuzz_plot_folder(dir, sizeof dir, "sweep");
    for (int g = 0; g < NGRIDS; g++)
        make_grid(g);
    return 0;
}

/* The runs' files of this input in grid g's folders. */
static void write_runs(int g, const uint8_t *data, size_t size)
{
    char path[700];
    for (int r = 0; r < nruns[g]; r++) {
        run_file(path, sizeof path, g, r, "summary.json");
        unlink(path);
        run_file(path, sizeof path, g, r, "timeseries.csv");
        unlink(path);
    }
    int run = 0;
    const char *name = "summary.json";
    size_t at = 1;
    while (at <= size) {
        /* the next line "@@Nx" from at, or the end */
        size_t end = size, next = size + 1;
        int nrun = -1;
        const char *nname = NULL;
        for (size_t q = at; q + 3 < size; q++)
            if ((q == at || data[q - 1] == '\n') && data[q] == '@' &&
                data[q + 1] == '@' && data[q + 2] >= '0' &&
                data[q + 2] <= '9' &&
                (data[q + 3] == 's' || data[q + 3] == 't')) {
                end = q;
                nrun = (data[q + 2] - '0') % nruns[g];
                nname = data[q + 3] == 's' ? "summary.json" : "timeseries.csv";
                next = q + 4;
                while (next < size && data[next] != '\n')
                    next++;
                next++;
                break;
            }
        run_file(path, sizeof path, g, run, name);
        put(path, data + at, end - at);
        if (!nname)
            break;
        run = nrun;
        name = nname;
        at = next;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > 1 << 16)
        return 0;
    const int g = data[0] % NGRIDS;
    write_runs(g, data, size);
    char out[160], path[200];
    out_of(out, sizeof out, g);
    snprintf(path, sizeof path, "%s/sweep.json", out);
    unlink(path);
    char target[160];
    snprintf(target, sizeof target, "%s/g%d.cfg", dir, g);
    struct dem_sweep_options o = {
        .target = target, .outdir = out, .jobs = 1, .threads = 1, .quiet = 1};
    struct dem_error err = {0};
    if (dem_sweep_collect(&grid[g], &o, &err)) {
        fuzz_one_line(&err);
        if (access(path, F_OK) == 0)
            abort(); /* a refusal leaves no sweep.json that looks done */
    } else {
        fuzz_json_reads_back(path);
    }
    snprintf(path, sizeof path, "%s/plots", out);
    fuzz_gp_scripts_inert(path);
    return 0;
}
