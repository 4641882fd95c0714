/* libFuzzer harness for what reads a run's folder back: `dembox analyze`
 * (dem_analyze) and `dembox plot` (dem_plot_run), on files that a run did
 * not write as they are (edited, truncated, from another tool).
 *
 * The input is a run folder in one text: the first byte's two low bits
 * choose the config.cfg among four built-in examples (biaxial2d,
 * shear2d, cyclic3d, triaxial3d), its third whether the plots are made
 * too (they take some 100 ms an input, the analysis a few); the rest is
 * timeseries.csv up to a line "@@X", after which come the files named by X: p
 * particles_final.csv, c contacts_final.csv, f forces_final.csv, s summary.json
 * (read by the plots), t timeseries.csv again, g config.cfg in place of the
 * example's (the record's reader, and the stages no example has: constant_p, a
 * held shear stress, hertz). The plots' gnuplot is a command that does not
 * exist (DEMBOX_GNUPLOT): their data and scripts are written, not drawn
 * (a gnuplot started per picture took 70 ms an input); the particle
 * picture is drawn (cairo).
 * Any crash, leak or sanitizer report (float-to-int overflow included), or
 * a message that is empty or not one line, is a finding; so are a plot
 * script that could run a command (plots.h), a
 * summary.json left by a refused analysis, and one that the project's own
 * JSON reader cannot read back.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "dembox.h"
#include "oracles.h"
#include "plots.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char dir[96];

static const char *const examples[4] = {"biaxial2d", "shear2d", "cyclic3d",
                                        "triaxial3d"};
static const char *const files[] = {"config.cfg",          "timeseries.csv",
                                    "particles_final.csv", "contacts_final.csv",
                                    "forces_final.csv",    "summary.json"};

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    fuzz_plot_folder(dir, sizeof dir, "run");
    return 0;
}

static void path_of(char *out, size_t n, const char *name)
{
    snprintf(out, n, "%s/%s", dir, name);
}

static void put(const char *name, const uint8_t *p, size_t n)
{
    char path[160];
    path_of(path, sizeof path, name);
    FILE *f = fopen(path, "wb");
    if (!f || (n && fwrite(p, 1, n, f) != n) || fclose(f))
        abort();
}

/* The folder of this input: config.cfg and the files of the text;
 * returns 1 if the text held a summary.json. */
static int write_folder(const uint8_t *data, size_t size)
{
    int summary = 0;
    char path[160];
    for (size_t k = 0; k < sizeof files / sizeof *files; k++) {
        path_of(path, sizeof path, files[k]);
        unlink(path);
    }
    const struct dem_example *ex = dem_example_find(examples[data[0] % 4]);
    if (!ex)
        abort();
    put("config.cfg", (const uint8_t *)ex->text, strlen(ex->text));
    const char *name = "timeseries.csv";
    size_t at = 1;
    while (at <= size) {
        /* the next line "@@X" from at, or the end */
        size_t end = at, next = size + 1;
        const char *nname = NULL;
        for (size_t q = at; q + 2 < size; q++)
            if ((q == at || data[q - 1] == '\n') && data[q] == '@' &&
                data[q + 1] == '@') {
                static const char *const by[] = {
                    ['p'] = "particles_final.csv", ['c'] = "contacts_final.csv",
                    ['f'] = "forces_final.csv",    ['s'] = "summary.json",
                    ['t'] = "timeseries.csv",      ['g'] = "config.cfg"};
                const uint8_t x = data[q + 2];
                if (x < sizeof by / sizeof *by && by[x]) {
                    end = q;
                    nname = by[x];
                    next = q + 3;
                    while (next < size && data[next] != '\n')
                        next++;
                    next++;
                    break;
                }
            }
        if (!nname)
            end = size;
        put(name, data + at, end - at);
        summary |= !strcmp(name, "summary.json");
        if (!nname)
            break;
        name = nname;
        at = next;
    }
    return summary;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > 1 << 16)
        return 0;
    const int given = write_folder(data, size);
    char path[160];
    path_of(path, sizeof path, "summary.json");
    struct dem_error err = {0};
    if (dem_analyze(dir, &err)) {
        fuzz_one_line(&err);
        if (!given && access(path, F_OK) == 0)
            abort(); /* a refused analysis leaves no summary */
    } else {
        fuzz_json_reads_back(path);
    }
    memset(&err, 0, sizeof err);
    if ((data[0] & 4) && dem_plot_run(dir, &err))
        fuzz_one_line(&err);
    if (data[0] & 4) {
        path_of(path, sizeof path, "plots");
        fuzz_gp_scripts_inert(path);
    }
    return 0;
}
