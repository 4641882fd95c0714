/* Whole runs through dem_run: every built-in example for a few hundred
 * steps, an isotropic preparation that reaches its target, and a small 2D
 * biaxial test whose fixed walls stay put while the sample first compacts
 * and then dilates. */
#include "dembox.h"
#include "testutil.h"

#include <glob.h>
#include <locale.h>
#include <malloc.h>
#include <omp.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "contact/models.h"
#include "core/sim.h"
#include "formats/csvtable.h"
#include "io/fsutil.h"

#include "tmpdir.h"

static int exists(const char *dir, const char *name)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    struct stat st;
    return stat(path, &st) == 0 && st.st_size > 0;
}

static void run_text(const char *text, const char *name,
                     const char *const *sets, int nsets, long max_steps,
                     char *outdir, size_t n)
{
    struct dem_config c;
    struct dem_error err = {0};
    if (dem_config_parse(&c, text, name, sets, nsets, &err))
        fail_msg("%s: %s", name, err.msg);
    snprintf(outdir, n, "%s/%s", tmpdir, name);
    struct dem_run_options o = {
        .outdir = outdir, .threads = 1, .max_steps = max_steps};
    if (dem_run(&c, &o, &err) || dem_analyze(outdir, &err) ||
        dem_plot_run(outdir, &err))
        fail_msg("%s: %s", name, err.msg);
}

/* Read the named columns of OUTDIR/timeseries.csv. */
static void read_ts(const char *outdir, const struct dem__csv_want *want, int n,
                    struct dem__csv_table *t)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/timeseries.csv", outdir);
    struct dem_error err = {0};
    if (dem__csv_table_read(t, path, want, n, &err))
        fail_msg("%s", err.msg);
    assert_true(t->nrow > 0);
}

/* Options out of range (a caller other than the CLI, e.g. Python) are
 * refused with one line naming them, before anything is written; so is
 * an empty output folder, which joined to a file's name would name one
 * at the root of the file system. */
static void bad_run_options_are_refused(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_error err = {0};
    const struct dem_example *ex = dem_example_find("hold3d");
    assert_non_null(ex);
    if (dem_config_parse(&c, ex->text, "hold3d", 0, 0, &err))
        fail_msg("%s", err.msg);
    char out[1024];
    snprintf(out, sizeof out, "%s/bad-options", tmpdir);
    static const struct {
        int threads;
        long max_steps;
        int empty_outdir;
        const char *want;
    } rows[] = {
        {-3, 10, 0, "threads = -3: must be >= 0 (0 = every core)"},
        {1, -5, 0, "max_steps = -5: must be >= 0 (0 = no limit)"},
        {1, 10, 1, "empty output folder name"},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        struct dem_run_options o = {.outdir = rows[k].empty_outdir ? "" : out,
                                    .threads = rows[k].threads,
                                    .max_steps = rows[k].max_steps};
        assert_int_equal(dem_run(&c, &o, &err), DEM_EUSAGE);
        assert_string_equal(err.msg, rows[k].want);
        if (!rows[k].empty_outdir) {
            assert_int_equal(dem_run_resume(out, &o, &err), DEM_EUSAGE);
            assert_string_equal(err.msg, rows[k].want);
        }
        assert_true(access(out, F_OK) != 0);
    }
    assert_int_equal(dem_run(&c, NULL, &err), DEM_EUSAGE);
    assert_int_equal(dem_run_resume("", &(struct dem_run_options){0}, &err),
                     DEM_EUSAGE);
    assert_string_equal(err.msg, "empty folder name (before /checkpoint.bin)");
}

/* One writer per folder: while a run (here: a lock taken as dem_run
 * takes it) writes into a folder, a second run into it and a resume of
 * it are refused, naming the process; the files of the first are left
 * alone. After the holder ends, the run goes on, and its lock file is
 * left empty (two finished folders compare equal). */
static void a_second_writer_into_a_folder_is_refused(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_error err = {0};
    const struct dem_example *ex = dem_example_find("hold3d");
    if (dem_config_parse(&c, ex->text, "hold3d", 0, 0, &err))
        fail_msg("%s", err.msg);
    char out[1024], want[2400], path[1100];
    snprintf(out, sizeof out, "%s/locked", tmpdir);
    assert_int_equal(dem_mkdir_p(out, &err), 0);
    snprintf(path, sizeof path, "%s/keep.txt", out);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fclose(f);
    int fd = -1;
    assert_int_equal(dem_folder_lock(out, "run", &fd, &err), DEM_OK);
    assert_true(fd >= 0);
    snprintf(want, sizeof want,
             "%s: another dembox run is writing into this folder (process "
             "%ld, which holds %s/.dembox.lock); wait for it to end, or "
             "choose another folder",
             out, (long)getpid(), out);
    struct dem_run_options o = {.outdir = out, .threads = 1, .max_steps = 50};
    assert_int_equal(dem_run(&c, &o, &err), DEM_EUSAGE);
    assert_string_equal(err.msg, want);
    assert_int_equal(dem_run_resume(out, &o, &err), DEM_EUSAGE);
    assert_string_equal(err.msg, want);
    snprintf(path, sizeof path, "%s/config.cfg", out);
    assert_true(access(path, F_OK) != 0); /* nothing written */
    dem_folder_unlock(fd);

    if (dem_run(&c, &o, &err))
        fail_msg("%s", err.msg);
    snprintf(path, sizeof path, "%s/.dembox.lock", out);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    assert_int_equal(st.st_size, 0);
    snprintf(path, sizeof path, "%s/keep.txt", out);
    assert_int_equal(access(path, F_OK), 0); /* not a run's: kept */

    /* the analysis and the plots of the finished run are writers too: a
     * run started into the folder meanwhile (here: its lock) makes them
     * stop, naming it, and a run is refused while they write */
    assert_int_equal(dem_folder_lock(out, "run", &fd, &err), DEM_OK);
    assert_int_equal(dem_analyze(out, &err), DEM_EUSAGE);
    assert_string_equal(err.msg, want);
    assert_int_equal(dem_plot_run(out, &err), DEM_EUSAGE);
    assert_string_equal(err.msg, want);
    snprintf(path, sizeof path, "%s/summary.json", out);
    assert_true(access(path, F_OK) != 0);
    dem_folder_unlock(fd);
    assert_int_equal(dem_folder_lock(out, "analysis", &fd, &err), DEM_OK);
    assert_int_equal(dem_run(&c, &o, &err), DEM_EUSAGE);
    assert_non_null(strstr(err.msg, "another dembox analysis is writing"));
    dem_folder_unlock(fd);
    if (dem_analyze(out, &err))
        fail_msg("%s", err.msg);
}

/* The files a run removes at its start are matched in its own folder
 * only: a folder named run[12] is no pattern for run1 and run2. */
static void removal_patterns_are_the_leaf_only(void **state)
{
    (void)state;
    char d[3][256], f[512];
    static const char *const names[] = {"run1", "run2", "run[12]"};
    for (int k = 0; k < 3; k++) {
        snprintf(d[k], sizeof d[k], "%s/%s", tmpdir, names[k]);
        assert_int_equal(mkdir(d[k], 0755), 0);
        snprintf(f, sizeof f, "%s/%s/particles_00001.vtu", tmpdir, names[k]);
        FILE *o = fopen(f, "w");
        assert_non_null(o);
        fputs("a snapshot", o);
        fclose(o);
    }
    struct dem_error err = {0};
    assert_int_equal(dem_remove_in(d[2], "particles_*.vtu", &err), 0);
    assert_true(exists(d[0], "particles_00001.vtu"));
    assert_true(exists(d[1], "particles_00001.vtu"));
    assert_false(exists(d[2], "particles_00001.vtu"));
}

/* A run whose config file is its output folder's config.cfg (dembox run
 * config.cfg -o .) is refused before it writes: the run replaced the
 * user's file by the resolved config, comments lost. A folder's own
 * resolved config.cfg run again in place is fine. */
static void the_config_file_is_not_overwritten_by_its_run(void **state)
{
    (void)state;
    char out[512], path[1100];
    snprintf(out, sizeof out, "%s/in-place", tmpdir);
    assert_int_equal(dem_mkdir_p(out, &(struct dem_error){0}), 0);
    snprintf(path, sizeof path, "%s/config.cfg", out);
    const struct dem_example *ex = dem_example_find("hold3d");
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fprintf(f, "# my notes on this test\n%s", ex->text);
    fclose(f);
    struct dem_config c;
    struct dem_error err = {0};
    if (dem_config_load_file(&c, path, NULL, 0, &err))
        fail_msg("%s", err.msg);
    struct dem_run_options o = {.outdir = out, .threads = 1, .max_steps = 50};
    assert_int_equal(dem_run(&c, &o, &err), DEM_EUSAGE);
    assert_non_null(strstr(err.msg, "/in-place/config.cfg: the config file "
                                    "of this run is its output folder's "
                                    "config.cfg, which the run replaces"));
    char *text = dem_read_text(path, &err);
    assert_non_null(text);
    assert_true(!strncmp(text, "# my notes on this test\n", 24));
    free(text);
    assert_true(!exists(out, "timeseries.csv"));

    /* into another folder, then that folder's config.cfg run in place */
    char other[512];
    snprintf(other, sizeof other, "%s/in-place/again", tmpdir);
    o.outdir = other;
    if (dem_run(&c, &o, &err))
        fail_msg("%s", err.msg);
    snprintf(path, sizeof path, "%s/config.cfg", other);
    if (dem_config_load_file(&c, path, NULL, 0, &err))
        fail_msg("%s", err.msg);
    /* a picture of the earlier run does not outlive this one's start;
     * a file of the user's there stays */
    snprintf(path, sizeof path, "%s/plots", other);
    assert_int_equal(dem_mkdir_p(path, &err), 0);
    snprintf(path, sizeof path, "%s/plots/shear.png", other);
    f = fopen(path, "w");
    assert_non_null(f);
    fputs("an old picture", f);
    fclose(f);
    assert_true(exists(other, "plots/shear.png"));
    snprintf(path, sizeof path, "%s/plots/my_shear.gp", other);
    f = fopen(path, "w");
    assert_non_null(f);
    fputs("plot 'shear.dat'", f);
    fclose(f);
    if (dem_run(&c, &o, &err))
        fail_msg("%s", err.msg);
    assert_true(exists(other, "timeseries.csv"));
    assert_false(exists(other, "plots/shear.png"));
    assert_true(exists(other, "plots/my_shear.gp"));
}

static void every_example_runs_a_few_hundred_steps(void **state)
{
    (void)state;
    for (int k = 0; k < dem_n_examples; k++) {
        char out[1024];
        run_text(dem_examples[k].text, dem_examples[k].name, 0, 0, 300, out,
                 sizeof out);
        assert_true(exists(out, "config.cfg"));
        assert_true(exists(out, "timeseries.csv"));
        assert_true(exists(out, "particles_final.csv"));
        assert_true(exists(out, "plots/particles.png"));
        assert_false(exists(out, "timeseries.csv.part"));
    }
}

static const char *const small_2d =
    "dimension = 2; seed = 3; time_step = \"auto\";\n"
    "particles = { count = 150; radius = { distribution = \"uniform\";"
    " min = 0.5e-3; max = 1.5e-3; }; placement = \"random\";"
    " volume_fraction = 0.4; };\n"
    "contact = { normal = \"luding\"; k1 = 5.0e4; k2 = 1.0e5; gamma_n = 0.1;"
    " kt = 2.0e4; gamma_t = 0.02; mu = 0.5; };\n"
    "damping = { gamma_b = 1.0e-5; gamma_br = 0.0; };\n"
    "walls = { mass = 0.01; gamma = 2.0; max_speed = 0.5; };\n"
    "stages = ( { type = \"isotropic\"; pressure = 500.0; tolerance = 1.0e-4;"
    " max_time = 0.1; mu = 0.0; },\n"
    " { type = \"compress\"; axis = \"y\"; strain = 0.12; duration = 0.06;"
    " pressure = 500.0; } );\n"
    "output = { interval = 2.0e-4; snapshot_interval = 0.0; };\n";

/* The preparation ends relaxed: every wall at the target within 2%, the
 * Love-Weber stress agreeing, E_kin/E_pot below the tolerance. */
static void isotropic_stage_reaches_target_pressure(void **state)
{
    (void)state;
    char out[1024];
    const char *sets[] = {"stages=( { type = \"isotropic\"; pressure = 500.0;"
                          " tolerance = 1.0e-4; max_time = 0.1; mu = 0.0; } )"};
    run_text(small_2d, "isotropic2d", sets, 1, 0, out, sizeof out);
    static const struct dem__csv_want want[] = {
        DEM_CSV_FINITE("xmin_force", 1),  DEM_CSV_FINITE("xmax_force", 1),
        DEM_CSV_FINITE("ymin_force", 1),  DEM_CSV_FINITE("ymax_force", 1),
        DEM_CSV_FINITE("Lx", 1),          DEM_CSV_FINITE("Ly", 1),
        DEM_CSV_FINITE("sigma_lw_xx", 1), DEM_CSV_FINITE("sigma_lw_yy", 1),
        DEM_CSV_FINITE("e_kin", 1),       DEM_CSV_FINITE("e_rot", 1),
        DEM_CSV_FINITE("e_pot", 1),       DEM_CSV_FINITE("t", 1)};
    struct dem__csv_table t;
    read_ts(out, want, 12, &t);
    size_t r = t.nrow - 1;
    double Lx = t.col[4][r], Ly = t.col[5][r];
    const double p = 500.0;
    /* x walls carry sigma Ly, y walls sigma Lx (2D: stress = force/length),
     * each within the stage's criterion, 1 % (2 % was asked here: the
     * criterion at 1.9 % passed; a review of the tests, session 115) */
    assert_rel(t.col[0][r] / Ly, p, 0.01);
    assert_rel(t.col[1][r] / Ly, p, 0.01);
    assert_rel(t.col[2][r] / Lx, p, 0.01);
    assert_rel(t.col[3][r] / Lx, p, 0.01);
    assert_rel(t.col[6][r], p, 0.02);
    assert_rel(t.col[7][r], p, 0.02);
    assert_true(t.col[8][r] + t.col[9][r] < 1e-4 * t.col[10][r]);
    /* it ended on the criterion, not on max_time */
    assert_true(t.col[11][r] < 0.1 - 1e-3);
    dem__csv_table_free(&t);
}

/* Luding et al. Fig. 3: the left and bottom walls are fixed, the top wall
 * closes on the cosine profile, the right wall keeps the side stress; a dense
 * sample first compacts and then dilates. */
/* The contact pictures' data of the run in out (suffix "": the end,
 * "_peak": the peak) are densities: P(f/<f>) over its bins of 0.1 (and
 * what lies beyond the last) and E(theta) over the circle integrate to
 * 1, and the mean of f/<f> is 1. */
static void contact_densities(const char *out, const char *suffix)
{
    char path[2048], line[512];
    double integral[2] = {0, 0}, first_moment = 0.0;
    long beyond = 0, pairs = 0;
    for (int q = 0; q < 2; q++) {
        snprintf(path, sizeof path, "%s/plots/%s%s.dat", out,
                 q ? "contact_normals" : "force_distribution", suffix);
        FILE *f = fopen(path, "r");
        assert_non_null(f);
        double last_theta = -1, x, y;
        while (fgets(line, sizeof line, f)) {
            if (line[0] == '#') {
                const char *p = strstr(line, "over the ");
                if (p)
                    pairs = atol(p + 9);
                p = strstr(line, "; ");
                if (q == 0 && p && strstr(line, "beyond"))
                    beyond = atol(p + 2);
                continue;
            }
            if (sscanf(line, "%lf %lf", &x, &y) != 2)
                continue; /* an empty bin ("?") */
            if (q == 0) {
                integral[0] += 0.1 * y;
                first_moment += 0.1 * x * y;
            } else if (last_theta >= 0 && x > last_theta) {
                integral[1] += (x - last_theta) * M_PI / 180.0 * y;
            }
            last_theta = x;
        }
        fclose(f);
    }
    assert_true(pairs > 100);
    assert_close(integral[0] + (double)beyond / pairs, 1.0, 1e-6);
    assert_close(integral[1], 1.0, 1e-6);
    assert_close(first_moment, 1.0, 0.05 + (double)beyond / pairs * 6.0);
}

/* Every contacts snapshot of out with the token after the first `key`
 * (up to a quote or white space) replaced by repl; their texts before
 * kept in keep[] (restored with repl NULL). Returns the count. */
static int edit_snapshots(const char *out, const char *key, const char *repl,
                          char **keep, int nkeep)
{
    char pat[2048];
    snprintf(pat, sizeof pat, "%s/contacts_*.vtu", out);
    glob_t g;
    assert_int_equal(glob(pat, 0, NULL, &g), 0);
    assert_true(g.gl_pathc <= (size_t)nkeep);
    for (size_t q = 0; q < g.gl_pathc; q++) {
        FILE *f;
        if (!repl) {
            f = fopen(g.gl_pathv[q], "w");
            assert_non_null(f);
            fputs(keep[q], f);
            fclose(f);
            free(keep[q]);
            continue;
        }
        keep[q] = dem_read_text(g.gl_pathv[q], NULL);
        assert_non_null(keep[q]);
        const char *at = strstr(keep[q], key);
        assert_non_null(at);
        at += strlen(key);
        at += strspn(at, " \n");
        const char *end = at + strcspn(at, "\" \n");
        f = fopen(g.gl_pathv[q], "w");
        assert_non_null(f);
        fprintf(f, "%.*s%s%s", (int)(at - keep[q]), keep[q], repl, end);
        fclose(f);
    }
    const int n = (int)g.gl_pathc;
    globfree(&g);
    return n;
}

static void biaxial_fixed_walls_and_dilatancy(void **state)
{
    (void)state;
    char out[1024];
    const char *snap[] = {"output.snapshot_interval=0.01"};
    run_text(small_2d, "biaxial2d-small", snap, 1, 0, out, sizeof out);
    /* the contact pictures at the peak, from the snapshot nearest to it
     * (and none in the isotropic run of snapshots_and_dump_cover_...) */
    contact_densities(out, "_peak");
    char gpath[2048], line[512];
    snprintf(gpath, sizeof gpath, "%s/plots/force_distribution_peak.gp", out);
    FILE *g = fopen(gpath, "r");
    assert_non_null(g);
    int titled = 0;
    while (fgets(line, sizeof line, g))
        titled |= strstr(line, "at the peak (snapshot at t = ") != NULL;
    fclose(g);
    assert_true(titled);
    static const struct dem__csv_want want[] = {
        DEM_CSV_FINITE("stage", 1),    DEM_CSV_FINITE("xmin_pos", 1),
        DEM_CSV_FINITE("ymin_pos", 1), DEM_CSV_FINITE("eps_v", 1),
        DEM_CSV_FINITE("eps_yy", 1),   DEM_CSV_FINITE("sigma_xx", 1)};
    struct dem__csv_table t;
    read_ts(out, want, 6, &t);
    size_t first = 0;
    while (first < t.nrow && t.col[0][first] < 1.0)
        first++;
    assert_true(first + 10 < t.nrow);
    double x0 = t.col[1][first], y0 = t.col[2][first];
    double vmin = 0.0, e_at_min = 0.0;
    for (size_t r = first; r < t.nrow; r++) {
        assert_true(t.col[1][r] == x0);
        assert_true(t.col[2][r] == y0);
        if (t.col[3][r] < vmin) {
            vmin = t.col[3][r];
            e_at_min = t.col[4][r];
        }
    }
    double vend = t.col[3][t.nrow - 1];
    /* compaction first ... */
    assert_true(vmin < -1e-3);
    assert_true(e_at_min > 0.0 && e_at_min < 0.1);
    /* ... then dilatancy well above the minimum */
    assert_true(vend > vmin + 5e-3);
    /* the axial strain reached its target */
    assert_close(t.col[4][t.nrow - 1], 0.12, 1e-3);
    dem__csv_table_free(&t);

    /* a damaged contacts snapshot (a cell count beyond what the file
     * holds; a force that is not a number) is refused naming the file,
     * not read past its arrays */
    static const char *const edits[][2] = {
        {"NumberOfCells=\"", "2305843009213693952"},
        {"Name=\"normal_force\" format=\"ascii\">", "nan"}};
    for (int e = 0; e < 2; e++) {
        char *keep[64];
        const int n = edit_snapshots(out, edits[e][0], edits[e][1], keep, 64);
        assert_true(n > 2);
        struct dem_error err = {0};
        assert_int_equal(dem_plot_run(out, &err), DEM_EIO);
        if (!strstr(err.msg, "contacts_") ||
            !strstr(err.msg, "not a contacts snapshot of dembox"))
            fail_msg("%s", err.msg);
        edit_snapshots(out, edits[e][0], NULL, keep, 64);
    }
    struct dem_error err = {0};
    if (dem_plot_run(out, &err))
        fail_msg("%s", err.msg);
}

/* A pressure far beyond what the contacts can carry: the run stops with a
 * diagnosis naming the particle, leaves the state for inspection and no
 * output that looks complete. */
static void overlap_blow_up_is_diagnosed(void **state)
{
    (void)state;
    const char *text =
        "dimension = 3; seed = 1; time_step = 2.0e-5;\n"
        "particles = { count = 27; radius = { distribution = \"mono\";"
        " mean = 5.0e-3; }; placement = \"lattice\"; };\n"
        "walls = { mass = 0.01; gamma = 1.0; };\n"
        "stages = ( { type = \"isotropic\"; pressure = 1.0e6; max_time = 0.5; "
        "} );\n"
        "output = { interval = 1.0e-3; snapshot_interval = 0.0; };\n";
    struct dem_config c;
    struct dem_error err = {0};
    assert_int_equal(dem_config_parse(&c, text, "blowup", 0, 0, &err), 0);
    char out[1024];
    snprintf(out, sizeof out, "%s/blowup", tmpdir);
    struct dem_run_options o = {.outdir = out, .threads = 1};
    assert_int_equal(dem_run(&c, &o, &err), DEM_EUNSTABLE);
    assert_non_null(strstr(err.msg, "particle"));
    assert_non_null(strstr(err.msg, "overlaps"));
    assert_null(strchr(err.msg, '\n'));
    assert_true(exists(out, "particles_unstable.csv"));
    assert_false(exists(out, "timeseries.csv"));
    assert_false(exists(out, "particles_final.csv"));
    assert_true(exists(out, "timeseries.csv.part"));
}

/* A time step near the contact duration (bypassing the config check, as a
 * test of the safety net) makes the integration unstable: with every wall
 * fixed and no gravity nothing may raise the energy, and the run stops. */
static void energy_growth_is_diagnosed(void **state)
{
    (void)state;
    char dir[1024], file[2048];
    snprintf(dir, sizeof dir, "%s/egrowth-in", tmpdir);
    mkdir(dir, 0755);
    snprintf(file, sizeof file, "%s/gas.csv", dir);
    FILE *f = fopen(file, "w");
    assert_non_null(f);
    fprintf(f, "x,y,z,vx,vy,vz,radius\n");
    for (int k = 0; k < 8; k++)
        fprintf(f, "%g,%g,%g,%g,%g,%g,5e-3\n", 0.01 + 0.02 * (k % 2),
                0.01 + 0.02 * ((k / 2) % 2), 0.01 + 0.02 * (k / 4),
                0.3 * (k % 3 - 1), 0.3 * ((k + 1) % 3 - 1),
                0.2 * (k % 2 ? 1 : -1));
    fclose(f);
    /* a hold alone, and a hold after a compression at constant volume,
     * whose walls stay strain-controlled at the end of their profiles
     * (the check was left off after any stage that moved a wall) */
    static const char *const stages[] = {
        "stages = ( { type = \"hold\"; duration = 2.0; } );\n",
        "stages = ( { type = \"constant_volume\"; strain = 1.0e-3; "
        "duration = 2.0e-3; }, { type = \"hold\"; duration = 2.0; } );\n"};
    for (int q = 0; q < 2; q++) {
        char text[4096];
        snprintf(text, sizeof text,
                 "dimension = 3; seed = 1; time_step = 2.0e-5;\n"
                 "particles = { placement = \"file\"; file = \"%s\"; };\n"
                 "box = { size = [0.04, 0.04, 0.04]; };\n"
                 "contact = { gamma_n = 0.0; gamma_t = 0.0; mu = 0.0; };\n"
                 "damping = { gamma_b = 0.0; gamma_br = 0.0; };\n"
                 "%s"
                 "output = { interval = 2.0e-3; snapshot_interval = 0.0; "
                 "};\n",
                 file, stages[q]);
        struct dem_config c;
        struct dem_error err = {0};
        assert_int_equal(dem_config_parse(&c, text, "egrowth", 0, 0, &err), 0);
        c.time_step = 0.8 * dem_contact_time(&c);
        char out[1024];
        snprintf(out, sizeof out, "%s/egrowth%d", tmpdir, q);
        struct dem_run_options o = {.outdir = out, .threads = 1};
        assert_int_equal(dem_run(&c, &o, &err), DEM_EUNSTABLE);
        if (!strstr(err.msg, "energy grew") || !strstr(err.msg, "time step"))
            fail_msg("stages %d: %s", q, err.msg);
    }
}

/* time_step = "auto" with a particle file of particles ten times
 * smaller than the distribution keys' (a thousandth of the mass): the
 * step is t_c/50 of the file's particles, not of the keys', and the
 * resolved config says so. */
/* A config of 5 mm mono radius keys over a file of eight 0.5 mm spheres
 * in folder NAME, with `step` as its time_step and `extra` added. */
static void small_file_config(struct dem_config *c, const char *name,
                              const char *step, const char *extra)
{
    char dir[1024], file[2048];
    snprintf(dir, sizeof dir, "%s/%s", tmpdir, name);
    mkdir(dir, 0755);
    snprintf(file, sizeof file, "%s/small.csv", dir);
    FILE *f = fopen(file, "w");
    assert_non_null(f);
    fprintf(f, "x,y,z,radius\n");
    for (int k = 0; k < 8; k++)
        fprintf(f, "%g,%g,%g,5e-4\n", 0.002 + 0.002 * (k % 2),
                0.002 + 0.002 * ((k / 2) % 2), 0.002 + 0.002 * (k / 4));
    fclose(f);
    char text[4096];
    snprintf(text, sizeof text,
             "dimension = 3; time_step = %s;\n"
             "particles = { placement = \"file\"; file = \"%s\"; "
             "radius = { distribution = \"mono\"; mean = 5.0e-3; }; };\n"
             "box = { size = [0.006, 0.006, 0.006]; };\n"
             "stages = ( { type = \"hold\"; duration = 1.0e-3; } );\n%s",
             step, file, extra);
    struct dem_error err = {0};
    if (dem_config_parse(c, text, name, 0, 0, &err))
        fail_msg("%s", err.msg);
}

/* The mass of small_file_config's 0.5 mm spheres, kg. */
static double small_file_mass(const struct dem_config *c)
{
    double m;
    dem_particle_mass(5e-4, c->particles.density, c->particles.mass_model, 3,
                      &m, NULL);
    return m;
}

/* The time step OUTDIR/config.cfg resolved to. */
static double resolved_step(const char *outdir)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/config.cfg", outdir);
    struct dem_config r;
    struct dem_error err = {0};
    if (dem_config_load_file(&r, path, NULL, 0, &err))
        fail_msg("%s", err.msg);
    return r.time_step;
}

static void auto_step_follows_a_particle_file(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_error err = {0};
    small_file_config(&c, "autostep", "\"auto\"", "");
    const double m = small_file_mass(&c);
    const double want = dem_contact_time_of(&c, 5e-4, m) / 50;
    assert_true(want < 0.05 * c.time_step); /* the keys' step: 30x longer */
    char out[1024];
    snprintf(out, sizeof out, "%s/autostep-run", tmpdir);
    struct dem_run_options o = {.outdir = out, .threads = 1, .max_steps = 20};
    if (dem_run(&c, &o, &err))
        fail_msg("%s", err.msg);
    assert_true(resolved_step(out) == want);
}

/* The explicit viscosities' limit, gamma dt/m < 1, is taken at a
 * particle file's lightest particle too: a background viscosity the
 * keys' 5 mm spheres take at gamma dt/m = 0.002 is 2 at the file's
 * 0.5 mm ones, at a step of t_c/20 of theirs. Given, that step is
 * refused naming the key and the file; "auto" takes half the limit. */
static void viscosity_limit_follows_a_particle_file(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_error err = {0};
    small_file_config(&c, "viscfile", "\"auto\"", "");
    const double m = small_file_mass(&c);
    const double dt = dem_contact_time_of(&c, 5e-4, m) / 20,
                 gamma = 2.0 * m / dt;
    char extra[256], step[64];
    snprintf(extra, sizeof extra, "damping = { gamma_b = %.17g; };\n", gamma);
    snprintf(step, sizeof step, "%.17g", dt);
    small_file_config(&c, "viscfile", step, extra);
    char out[1024];
    snprintf(out, sizeof out, "%s/viscfile-given", tmpdir);
    struct dem_run_options o = {.outdir = out, .threads = 1, .max_steps = 20};
    assert_int_equal(dem_run(&c, &o, &err), DEM_ECONFIG);
    assert_non_null(strstr(err.msg, "damping.gamma_b"));
    assert_non_null(strstr(err.msg, "particles.file"));
    small_file_config(&c, "viscfile", "\"auto\"", extra);
    snprintf(out, sizeof out, "%s/viscfile-auto", tmpdir);
    err = (struct dem_error){0};
    if (dem_run(&c, &o, &err))
        fail_msg("%s", err.msg);
    const double want = 0.5 * m / gamma; /* 0.25 dt, below t_c/50 */
    assert_true(fabs(resolved_step(out) - want) <= 1e-12 * want);
}

static int same_file(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    int same = fa && fb;
    while (same) {
        int ca = fgetc(fa), cb = fgetc(fb);
        same = ca == cb;
        if (ca == EOF || cb == EOF)
            break;
    }
    if (fa)
        fclose(fa);
    if (fb)
        fclose(fb);
    return same;
}

/* The same config and seed give the same run, bit for bit; another seed
 * gives another one. */
static void same_seed_same_output(void **state)
{
    (void)state;
    char o1[1024], o2[1024], o3[1024], p1[2048], p2[2048], p3[2048];
    const char *seed5[] = {"seed=5"};
    run_text(small_2d, "repeat-a", 0, 0, 3000, o1, sizeof o1);
    run_text(small_2d, "repeat-b", 0, 0, 3000, o2, sizeof o2);
    run_text(small_2d, "repeat-c", seed5, 1, 3000, o3, sizeof o3);
    const char *files[] = {"timeseries.csv", "particles_final.csv"};
    for (int k = 0; k < 2; k++) {
        snprintf(p1, sizeof p1, "%s/%s", o1, files[k]);
        snprintf(p2, sizeof p2, "%s/%s", o2, files[k]);
        snprintf(p3, sizeof p3, "%s/%s", o3, files[k]);
        assert_true(same_file(p1, p2));
        assert_false(same_file(p1, p3));
    }
}

/* contacts_final.csv ends with the history values of the models in
 * force: in a relaxed adhesive packing each pair's normal force is
 * Luding's law at its overlap and its dmax (the dashpot's share is below
 * 1e-3 of the mean force there), and no dmax is below its overlap. */
static void contact_history_columns_follow_the_law(void **state)
{
    (void)state;
    char out[1024], path[2048];
    const char *sets[] = {"stages=( { type = \"isotropic\"; pressure = 500.0;"
                          " tolerance = 1.0e-5; max_time = 0.1; } )",
                          "contact.kc=5.0e4"};
    run_text(small_2d, "history-cols", sets, 2, 0, out, sizeof out);
    static const struct dem__csv_want want[] = {
        DEM_CSV_FINITE("id_j", 1), DEM_CSV_FINITE("delta", 1),
        DEM_CSV_FINITE("fn", 1),   DEM_CSV_FINITE("dmax", 1),
        DEM_CSV_FINITE("xi_x", 1), DEM_CSV_FINITE("xi_y", 1)};
    struct dem__csv_table t;
    struct dem_error err = {0};
    snprintf(path, sizeof path, "%s/contacts_final.csv", out);
    if (dem__csv_table_read(&t, path, want, 6, &err))
        fail_msg("%s", err.msg);
    assert_true(t.nrow > 100);
    const struct dem_luding L = {5.0e4, 1.0e5, 5.0e4, 0.0};
    double mean = 0.0, worst = 0.0;
    int pairs = 0, unloaded = 0;
    for (size_t k = 0; k < t.nrow; k++) {
        const double delta = t.col[1][k], dmax = t.col[3][k];
        assert_true(dmax >= delta * (1.0 - 1e-12));
        if (t.col[0][k] < 0) /* a wall: kc = contact.wall_kc (0) */
            continue;
        double h = dmax;
        const double f = dem_luding_force(delta, &h, &L, 0.0);
        worst = fmax(worst, fabs(t.col[2][k] - f));
        mean += fabs(t.col[2][k]);
        unloaded += delta < 0.99 * dmax;
        pairs++;
    }
    mean /= pairs;
    assert_true(worst < 1e-3 * mean);
    assert_true(unloaded > 0); /* some contacts are off the k1 envelope */
    dem__csv_table_free(&t);
}

/* The number of DataSet lines of a PVD file and the last one's time. */
static int pvd_entries(const char *outdir, const char *name, double *last)
{
    char path[2048], line[512];
    snprintf(path, sizeof path, "%s/%s", outdir, name);
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    int n = 0;
    while (fgets(line, sizeof line, f)) {
        const char *t = strstr(line, "timestep=\"");
        if (t) {
            n++;
            *last = atof(t + strlen("timestep=\""));
        }
    }
    fclose(f);
    return n;
}

/* Snapshots and dump frames cover the whole run: the initial state, every
 * interval, and the final state when the run does not end on one; the
 * box has its own PVD with the same times; a new run in the folder
 * removes the snapshots of the earlier one. */
static void snapshots_and_dump_cover_start_and_end(void **state)
{
    (void)state;
    char out[1024], path[2048];
    /* 0.012 s of isotropic stage (max_time), snapshots every 0.005 s:
     * t = 0, 0.005, 0.010 and the end */
    const char *sets[] = {"stages=( { type = \"isotropic\"; pressure = 500.0;"
                          " tolerance = 1.0e-9; max_time = 0.012; } )",
                          "output.snapshot_interval=0.005",
                          "output.dump_interval=0.005"};
    run_text(small_2d, "snapend", sets, 3, 0, out, sizeof out);
    double last_p = -1, last_b = -1;
    assert_int_equal(pvd_entries(out, "particles.pvd", &last_p), 4);
    assert_int_equal(pvd_entries(out, "box.pvd", &last_b), 4);
    assert_true(fabs(last_p - 0.012) < 1e-6);
    assert_true(last_b == last_p);
    assert_true(exists(out, "particles_00003.vtu"));
    assert_true(exists(out, "box_00003.vtu"));
    /* the dump: frames at steps 0, ..., and the last step */
    snprintf(path, sizeof path, "%s/dump.lammpstrj", out);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[512];
    long first = -1, lastf = -1;
    int frames = 0, want_step = 0;
    while (fgets(line, sizeof line, f)) {
        if (want_step) {
            lastf = atol(line);
            if (first < 0)
                first = lastf;
            frames++;
        }
        want_step = !strncmp(line, "ITEM: TIMESTEP", 14);
    }
    fclose(f);
    assert_int_equal(first, 0);
    assert_int_equal(frames, 4);
    assert_int_equal(pvd_entries(out, "contacts.pvd", &last_b), 4);
    assert_true(exists(out, "contacts_00003.vtu"));
    /* contacts_final.csv holds every contact: the sums of |fn| per
     * particle are forces_final.csv's fsum, and the coordinations match */
    struct dem__csv_table ct, ft;
    struct dem_error err = {0};
    static const struct dem__csv_want cw[] = {
        DEM_CSV_FINITE("id_i", 1), DEM_CSV_FINITE("id_j", 1),
        DEM_CSV_FINITE("fn", 1), DEM_CSV_FINITE("nx", 1),
        DEM_CSV_FINITE("ny", 1)};
    static const struct dem__csv_want fw[] = {
        DEM_CSV_FINITE("fsum", 1), DEM_CSV_FINITE("coordination", 1)};
    snprintf(path, sizeof path, "%s/contacts_final.csv", out);
    if (dem__csv_table_read(&ct, path, cw, 5, &err))
        fail_msg("%s", err.msg);
    snprintf(path, sizeof path, "%s/forces_final.csv", out);
    if (dem__csv_table_read(&ft, path, fw, 2, &err))
        fail_msg("%s", err.msg);
    assert_true(ct.nrow > 100);
    double *sum = calloc(ft.nrow, sizeof *sum);
    double *cnt = calloc(ft.nrow, sizeof *cnt);
    assert_non_null(sum);
    assert_non_null(cnt);
    for (size_t k = 0; k < ct.nrow; k++) {
        const int i = (int)ct.col[0][k], j = (int)ct.col[1][k];
        assert_true(i >= 0 && (size_t)i < ft.nrow);
        assert_close(hypot(ct.col[3][k], ct.col[4][k]), 1.0, 1e-12);
        sum[i] += fabs(ct.col[2][k]);
        cnt[i] += 1;
        if (j >= 0) {
            sum[j] += fabs(ct.col[2][k]);
            cnt[j] += 1;
        }
    }
    for (size_t i = 0; i < ft.nrow; i++) {
        assert_close(sum[i], ft.col[0][i], 1e-9 * (1.0 + ft.col[0][i]));
        assert_close(cnt[i], ft.col[1][i], 0.0);
    }
    free(sum);
    free(cnt);
    /* dump_local.lammpstrj: the same 4 frames, and its last one is
     * contacts_final.csv (ids 1-based as in dump.lammpstrj) */
    snprintf(path, sizeof path, "%s/dump_local.lammpstrj", out);
    f = fopen(path, "r");
    assert_non_null(f);
    int lframes = 0, entries = -1, row = -1;
    long lfirst = -1;
    while (fgets(line, sizeof line, f)) {
        if (!strncmp(line, "ITEM: TIMESTEP", 14)) {
            assert_non_null(fgets(line, sizeof line, f));
            lfirst = lframes++ ? lfirst : atol(line);
            row = -1;
        } else if (!strncmp(line, "ITEM: NUMBER OF ENTRIES", 23)) {
            assert_non_null(fgets(line, sizeof line, f));
            entries = atoi(line);
        } else if (!strncmp(line,
                            "ITEM: ENTRIES id1 id2 x y z nx ny nz "
                            "delta fn",
                            45)) {
            row = 0;
        } else if (row >= 0 && lframes == 4) {
            int id1, id2;
            double v[8];
            assert_int_equal(sscanf(line,
                                    "%d %d %lf %lf %lf %lf %lf %lf "
                                    "%lf %lf",
                                    &id1, &id2, &v[0], &v[1], &v[2], &v[3],
                                    &v[4], &v[5], &v[6], &v[7]),
                             10);
            assert_true((size_t)row < ct.nrow);
            assert_int_equal(id1 - 1, (int)ct.col[0][row]);
            assert_int_equal(id2 > 0 ? id2 - 1 : id2, (int)ct.col[1][row]);
            assert_close(v[7], ct.col[2][row], 1e-9 * fabs(ct.col[2][row]));
            row++;
        }
    }
    fclose(f);
    assert_int_equal(lfirst, 0);
    assert_int_equal(lframes, 4);
    assert_int_equal(entries, (int)ct.nrow);
    assert_int_equal(row, (int)ct.nrow);
    dem__csv_table_free(&ct);
    dem__csv_table_free(&ft);
    contact_densities(out, "");
    assert_false(exists(out, "plots/force_distribution_peak.dat"));
    /* a second run with fewer snapshots leaves none of the first's, nor
     * the temporaries a killed process left of any output */
    static const char *const left[] = {
        "particles_00003.vtu.tmp", "particles_final.csv.tmp",
        "summary.json.tmp", "timeseries.csv.tmp", "checkpoint.bin.tmp"};
    for (size_t k = 0; k < sizeof left / sizeof *left; k++) {
        snprintf(path, sizeof path, "%s/%s", out, left[k]);
        FILE *t = fopen(path, "w");
        assert_non_null(t);
        fclose(t);
    }
    const char *sets2[] = {sets[0], "output.snapshot_interval=0.01"};
    run_text(small_2d, "snapend", sets2, 2, 0, out, sizeof out);
    assert_int_equal(pvd_entries(out, "particles.pvd", &last_p), 3);
    assert_false(exists(out, "particles_00003.vtu"));
    assert_false(exists(out, "box_00003.vtu"));
    assert_false(exists(out, "dump.lammpstrj"));
    for (size_t k = 0; k < sizeof left / sizeof *left; k++)
        if (exists(out, left[k]))
            fail_msg("%s left", left[k]);
}

/* threads = 0: every core or one, whichever runs the steps faster,
 * timed now and then in the run (protocol/team.h): on two cores the
 * timing line says what the trials chose, the outputs are those of one
 * thread to the bit, and the process's count is as it was afterwards. */
static void threads_left_to_the_library_are_chosen_by_timing(void **state)
{
    (void)state;
    /* as on two cores (CTest sets OMP_NUM_THREADS=1) */
    const int given = omp_get_max_threads(), cores = 2;
    omp_set_num_threads(cores);
    char o1[1024], o0[1024], p1[2048], p0[2048];
    /* (a compression long enough for the steps below on any CPU) */
    const char *sets[] = {"stages.1.duration=10.0"};
    run_text(small_2d, "team-1", sets, 1, 6000, o1, sizeof o1);
    struct dem_config c;
    struct dem_error err = {0};
    if (dem_config_parse(&c, small_2d, "team-0", sets, 1, &err))
        fail_msg("%s", err.msg);
    snprintf(o0, sizeof o0, "%s/team-0", tmpdir);
    struct dem_run_timing T;
    /* long enough for a trial, DEM_TEAM_FIRST s into the run, in the
     * sanitizers' builds and on a fast CPU */
    long steps = 6000;
    for (;;) {
        struct dem_run_options o = {
            .outdir = o0, .max_steps = steps, .timing = &T};
        if (dem_run(&c, &o, &err))
            fail_msg("%s", err.msg);
        assert_int_equal(omp_get_max_threads(), cores);
        if (T.team[0] || steps > 1000000)
            break;
        steps *= 4;
    }
    assert_non_null(strstr(T.team, "2 threads, one thread in "));
    snprintf(p0, sizeof p0, "%s/timing.txt", o0);
    char *line = dem_read_text(p0, &err);
    assert_non_null(line);
    assert_non_null(strstr(line, ", 2 threads, "));
    assert_non_null(strstr(line, "; threads by timing: 2 threads, one "));
    free(line);
    if (steps != 6000)
        run_text(small_2d, "team-1", sets, 1, steps, o1, sizeof o1);
    const char *files[] = {"timeseries.csv", "particles_final.csv"};
    for (int k = 0; k < 2; k++) {
        snprintf(p1, sizeof p1, "%s/%s", o1, files[k]);
        snprintf(p0, sizeof p0, "%s/%s", o0, files[k]);
        assert_true(same_file(p1, p0));
    }
    omp_set_num_threads(given);
}

/* The range of column 1 of t in
 * each of the stages 0..n-1 (column 0): lo[k], hi[k] (+-INFINITY in a
 * stage without rows). */
static void stage_ranges(const struct dem__csv_table *t, int n, double *lo,
                         double *hi)
{
    for (int k = 0; k < n; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (size_t r = 0; r < t->nrow; r++) {
        const int k = (int)t->col[0][r];
        assert_true(k >= 0 && k < n);
        const double v = t->col[1][r];
        lo[k] = fmin(lo[k], v);
        hi[k] = fmax(hi[k], v);
    }
}

/* A program that set a locale with a decimal comma (Python's
 * locale.setlocale(LC_ALL, "de_DE.UTF-8"), a Qt application) gets the
 * same files as the C locale: the library writes and reads its numbers
 * in the C locale's (core/numeric.h). Before, timeseries.csv had "0,5",
 * summary.json was no JSON and the analysis refused the run's own files
 * (a read-only review of the outputs, session 109). Skipped where no
 * such locale can be made (localedef and Debian's locales package). */
static void a_decimal_comma_locale_writes_the_same_files(void **state)
{
    (void)state;
    char dir[1024], cmd[2300];
    snprintf(dir, sizeof dir, "%s/locales", tmpdir);
    mkdir(dir, 0755);
    snprintf(cmd, sizeof cmd,
             "localedef -i de_DE -f UTF-8 %s/de_DE.UTF-8 >/dev/null 2>&1", dir);
    char comma[16] = "";
    if (system(cmd) == 0 && setenv("LOCPATH", dir, 1) == 0 &&
        setlocale(LC_ALL, "de_DE.UTF-8"))
        snprintf(comma, sizeof comma, "%g", 0.5);
    if (strcmp(comma, "0,5") != 0) {
        setlocale(LC_ALL, "C");
        unsetenv("LOCPATH");
        print_message("no locale with a decimal comma here: skipped\n");
        skip();
    }
    char out[2][1024];
    for (int k = 0; k < 2; k++) {
        if (k) {
            setlocale(LC_ALL, "C");
            unsetenv("LOCPATH");
        }
        /* (one source name for both: config.cfg names it) */
        struct dem_config c;
        struct dem_error err = {0};
        snprintf(out[k], sizeof out[k], "%s/%s", tmpdir, k ? "point" : "comma");
        struct dem_run_options o = {
            .outdir = out[k], .threads = 1, .max_steps = 1000};
        if (dem_config_parse(&c, small_2d, "locale", NULL, 0, &err) ||
            dem_run(&c, &o, &err) || dem_analyze(out[k], &err) ||
            dem_plot_run(out[k], &err))
            fail_msg("%s: %s", out[k], err.msg);
    }
    static const char *const files[] = {"timeseries.csv", "summary.json",
                                        "config.cfg", "particles_final.csv",
                                        "plots/stress_strain.gp"};
    for (size_t k = 0; k < sizeof files / sizeof *files; k++) {
        char a[1100], b[1100];
        snprintf(a, sizeof a, "%s/%s", out[0], files[k]);
        snprintf(b, sizeof b, "%s/%s", out[1], files[k]);
        if (!same_file(a, b))
            fail_msg("%s differs from the C locale's", a);
    }
}

/* shear2d of 100 discs, a sample every 2e-5 s, no snapshots: an
 * isotropic stage of at most 2e-4 s, then the stages of after (libconfig
 * groups, comma-separated), into tmpdir/name (its path in out). */
static void run_small_shear(const char *name, const char *after, char *out,
                            size_t n)
{
    const struct dem_example *ex = dem_example_find("shear2d");
    assert_non_null(ex);
    char stages[1024];
    snprintf(stages, sizeof stages,
             "stages=({type=\"isotropic\";pressure=500.0;max_time=2e-4;},%s)",
             after);
    const char *const sets[] = {"particles.count=100", "output.interval=2e-5",
                                "output.snapshot_interval=0", stages};
    run_text(ex->text, name, sets, 4, 0, out, n);
}

/* A stage after a shear stage does not go on shearing: every stage but
 * hold (which keeps every mode, SPEC) fixes the cell's tilts, and only a
 * shear stage drives one. Before, a stress-controlled tilt kept its servo
 * through the compression that followed, which sheared the sample
 * without a word. */
static void a_stage_after_shear_holds_the_tilt(void **state)
{
    (void)state;
    char out[1024];
    run_small_shear("after-shear",
                    "{type=\"shear\";shear_stress=100.0;duration=2e-4;"
                    "pressure=500.0;},"
                    "{type=\"compress\";axis=\"y\";strain=0.001;"
                    "duration=2e-4;pressure=500.0;},"
                    "{type=\"hold\";duration=1e-4;}",
                    out, sizeof out);
    static const struct dem__csv_want want[] = {DEM_CSV_FINITE("stage", 1),
                                                DEM_CSV_FINITE("gamma_xy", 1)};
    struct dem__csv_table t;
    read_ts(out, want, 2, &t);
    /* gamma_xy by stage: the tilt over the stage's fixed reference L_y */
    double lo[4], hi[4];
    stage_ranges(&t, 4, lo, hi);
    /* the shear moved the tilt; the compression, which moves the x
     * faces, sheared nothing: its tilt kept its share of L_x, and
     * gamma_xy, F_xy of the stage's reference, is 0 to round-off in it
     * and in the hold after it */
    assert_true(hi[1] - lo[1] > 1e-5);
    for (int k = 2; k < 4; k++)
        assert_true(fabs(lo[k]) < 1e-15 && fabs(hi[k]) < 1e-15);
    dem__csv_table_free(&t);
}

/* A strain-controlled shear stage ends at its shear_strain while the
 * sample dilates: gamma_xy is the tilt since the reference over the
 * reference L_y, the one the control scales shear_strain by; so does a
 * second shear stage. Before, gamma_xy divided the tilt
 * by the current L_y, and shear2d's stage ended 3.5 % short of its
 * shear_strain (a read-only review, session 108). */
static void a_shear_stage_ends_at_its_shear_strain(void **state)
{
    (void)state;
    char out[1024];
    run_small_shear("shear-strain",
                    "{type=\"shear\";shear_strain=0.05;duration=4e-4;"
                    "pressure=500.0;},"
                    "{type=\"shear\";shear_strain=0.03;duration=4e-4;"
                    "pressure=500.0;}",
                    out, sizeof out);
    static const struct dem__csv_want want[] = {DEM_CSV_FINITE("stage", 1),
                                                DEM_CSV_FINITE("Ly", 1),
                                                DEM_CSV_FINITE("gamma_xy", 1)};
    struct dem__csv_table t;
    read_ts(out, want, 3, &t);
    double lo[3], hi[3];
    stage_ranges(&t, 3, lo, hi); /* L_y by stage */
    /* L_y moved during the shear (so that the old measure would miss) */
    assert_true(hi[1] - lo[1] > 1e-4 * hi[1]);
    /* each stage's last row: its own shear_strain, the second counted
     * from its own start as the eps columns are (counted from the run's
     * start over the second stage's L0_y, it ended at 0.08 less the
     * first's 0.05 rescaled); timeseries.csv gives 10 digits */
    const double want_end[3] = {NAN, 0.05, 0.03};
    for (int k = 1; k < 3; k++) {
        size_t last = 0;
        for (size_t r = 0; r < t.nrow; r++)
            if (t.col[0][r] == k)
                last = r;
        assert_close(t.col[2][last], want_end[k], 1e-9);
    }
    dem__csv_table_free(&t);
}

struct warnings {
    int n;
    char text[4096];
};

static void keep_warnings(const char *line, void *user)
{
    struct warnings *w = user;
    w->n++;
    const size_t len = strlen(w->text);
    snprintf(w->text + len, sizeof w->text - len, "%s\n", line);
}

/* Run text with sets into tmpdir/name: the warnings of the run (not of
 * the config's parsing) in *w. */
static void run_warnings(const char *text, const char *name,
                         const char *const *sets, int nsets, struct warnings *w)
{
    struct dem_config c;
    struct dem_error err = {.warn = keep_warnings, .warn_user = w};
    memset(w, 0, sizeof *w);
    if (dem_config_parse(&c, text, name, sets, nsets, &err))
        fail_msg("%s", err.msg);
    memset(w, 0, sizeof *w);
    char out[1024];
    snprintf(out, sizeof out, "%s/%s", tmpdir, name);
    struct dem_run_options o = {.outdir = out, .threads = 1};
    if (dem_run(&c, &o, &err))
        fail_msg("%s", err.msg);
}

/* A stress servo held at walls.max_speed does not follow its target: a
 * shear_stress of 400 N/m met 245 on average at the cap, and the
 * summary said that tau followed it, without a word (a read-only review,
 * session 108). The stage now ends with a warning naming the servo; the
 * isotropic stage, which compresses a gas at the cap by design, does
 * not warn. */
static void a_servo_at_its_speed_cap_is_warned_of(void **state)
{
    (void)state;
    const struct dem_example *ex = dem_example_find("shear2d");
    assert_non_null(ex);
    const char *const sets[] = {
        "particles.count=100", "output.interval=2e-5",
        "output.snapshot_interval=0", "walls.max_speed=1e-4",
        "stages=({type=\"isotropic\";pressure=500.0;max_time=2e-4;},"
        "{type=\"shear\";shear_stress=400.0;duration=2e-3;pressure=500.0;})"};
    struct warnings w;
    run_warnings(ex->text, "capped", sets, 5, &w);
    if (!strstr(w.text, "stage 1: stress servos at walls.max_speed = "
                        "0.0001 m/s") ||
        !strstr(w.text, "the xy tilt (100 %)"))
        fail_msg("warnings: %s", w.text);
    assert_null(strstr(w.text, "stage 0: stress servos"));
}

/* A stress servo too heavy and viscous for the particles keeps off its
 * target: biaxial2d's millimetre discs between walls of the defaults
 * (2 kg, 200 kg/s, made for 5 mm spheres) see their lateral stress
 * climb (docs/config.md's example: 500 to 809 N/m), which no warning
 * said (a new user's first hour, session 113). The stage now ends with
 * one naming the walls; with the example's walls (0.01 kg, 2 kg/s) it
 * does not. */
static void a_servo_off_its_target_is_warned_of(void **state)
{
    (void)state;
    const struct dem_example *ex = dem_example_find("biaxial2d");
    assert_non_null(ex);
    const char *const sets[] = {
        "particles.count=100",    "output.snapshot_interval=0",
        "stages.0.max_time=0.05", "stages.1.duration=0.03",
        "stages.1.strain=0.05",   "walls.mass=2",
        "walls.gamma=200",        "damping.gamma_b=0.2"};
    struct warnings w;
    run_warnings(ex->text, "servo-heavy", sets, 8, &w);
    if (!strstr(w.text, "stage 1: stress servos off their targets by more "
                        "than 10 % on average over the stage's samples: the "
                        "x m"))
        fail_msg("warnings: %s", w.text);
    run_warnings(ex->text, "servo-fit", sets, 5, &w);
    if (strstr(w.text, "off their targets"))
        fail_msg("warnings: %s", w.text);
}

/* A constant_p path that asks for tension: a cohesive sample prepared
 * at 500 N/m and then held at p = 20 keeps sigma_1 near 600, above 2 p,
 * so the lateral target 2 p - sigma_1 is below 0 and held at 0 by walls
 * that only push; the mean stress is not p there. The stage said
 * nothing (a read-only review of the stages, session 112); it now warns,
 * naming the walls and their share of steps. */
static void a_constant_p_path_into_tension_is_warned_of(void **state)
{
    (void)state;
    const struct dem_example *ex = dem_example_find("biaxial2d-cohesive");
    assert_non_null(ex);
    const char *const sets[] = {
        "particles.count=100", "output.snapshot_interval=0",
        "stages=({type=\"isotropic\";pressure=500.0;max_time=0.02;},"
        "{type=\"constant_p\";axis=\"y\";strain=0.1;duration=0.02;"
        "pressure=20.0;})"};
    struct warnings w;
    run_warnings(ex->text, "tension", sets, 3, &w);
    if (!strstr(w.text, "stage 1: the stress path asked for tension, and "
                        "the targets were held at 0") ||
        !strstr(w.text, "the x min wall (") ||
        !strstr(w.text, "the x max wall ("))
        fail_msg("warnings: %s", w.text);
    assert_null(strstr(w.text, "the y min wall ("));
    assert_null(strstr(w.text, "stage 0: the stress path"));
}

/* An isotropic stage ends at rest, its walls' servos included: the
 * particles' kinetic energy with the walls' 1/2 walls.mass v^2 below
 * tolerance times E_pot at the stage's last row. Before, the particles'
 * alone counted, and biaxial2d's stage ended with the walls swinging at
 * 0.015 m/s, their stresses ringing by 3 % about the target through the
 * stage after (session 109). */
static void an_isotropic_stage_ends_with_its_walls_at_rest(void **state)
{
    (void)state;
    const struct dem_example *ex = dem_example_find("biaxial2d");
    assert_non_null(ex);
    const char *const sets[] = {"particles.count=100",
                                "output.snapshot_interval=0",
                                "stages.1={type=\"hold\";duration=1e-3;}"};
    char out[1024];
    run_text(ex->text, "iso-rest", sets, 3, 0, out, sizeof out);
    static const struct dem__csv_want want[] = {
        DEM_CSV_FINITE("stage", 1),    DEM_CSV_FINITE("e_kin", 1),
        DEM_CSV_FINITE("e_rot", 1),    DEM_CSV_FINITE("e_pot", 1),
        DEM_CSV_FINITE("xmin_vel", 1), DEM_CSV_FINITE("xmax_vel", 1),
        DEM_CSV_FINITE("ymin_vel", 1), DEM_CSV_FINITE("ymax_vel", 1)};
    struct dem__csv_table t;
    read_ts(out, want, 8, &t);
    size_t r = 0; /* the isotropic stage's last row */
    while (r + 1 < t.nrow && t.col[0][r + 1] == 0.0)
        r++;
    assert_true(t.col[0][r] == 0.0 && r + 1 < t.nrow);
    double e = t.col[1][r] + t.col[2][r];
    for (int w = 0; w < 4; w++) /* walls.mass = 0.01 kg in biaxial2d */
        e += 0.5 * 0.01 * t.col[4 + w][r] * t.col[4 + w][r];
    assert_true(e < 1e-4 * t.col[3][r]);
    dem__csv_table_free(&t);
}

/* A stage whose criterion holds at the sample its max time ends on ended
 * on its criterion: an isotropic stage after one at the same pressure,
 * with max_time one output interval, is at rest at its one sample. It
 * was warned of as having reached max_time before relaxing (a read-only
 * review, session 110). */
static void a_stage_at_rest_on_its_last_sample_is_not_timed_out(void **state)
{
    (void)state;
    const struct dem_example *ex = dem_example_find("biaxial2d");
    assert_non_null(ex);
    const char *const sets[] = {
        "particles.count=100", "output.snapshot_interval=0",
        "stages.1={type=\"isotropic\";pressure=500.0;tolerance=1.0e-2;"
        "max_time=1.0e-4;}"};
    struct warnings w;
    run_warnings(ex->text, "iso-last", sets, 3, &w);
    if (strstr(w.text, "reached max_time"))
        fail_msg("%s", w.text);
}

/* A hold after an isotropic stage counts its own steps at the speed
 * cap: it keeps the walls' modes, and before it counted the isotropic
 * compression of the gas at the cap as its own, warning of 39 % at the
 * cap in biaxial2d's walls that moved at 0.015 m/s (session 109). */
static void a_hold_counts_only_its_own_servo_steps(void **state)
{
    (void)state;
    const struct dem_example *ex = dem_example_find("biaxial2d");
    assert_non_null(ex);
    const char *const sets[] = {"particles.count=100",
                                "output.snapshot_interval=0",
                                "stages.1={type=\"hold\";duration=0.005;}"};
    struct warnings w;
    run_warnings(ex->text, "hold-servo", sets, 3, &w);
    if (strstr(w.text, "stress servos at walls.max_speed"))
        fail_msg("warnings: %s", w.text);
}

/* A hold after a cyclic stage keeps the walls as they are: the cyclic
 * target stops at its value (here p0, after whole cycles) instead of
 * cycling on. Before, sigma_xx rose from 960 to 1510 over the hold of
 * half a period, following the next cycle (a read-only review, session
 * 107). */
static void a_hold_after_cycles_stops_the_cycling(void **state)
{
    (void)state;
    const struct dem_example *ex = dem_example_find("hold3d");
    assert_non_null(ex);
    const char *const sets[] = {
        "output.interval=5e-3", "output.snapshot_interval=0",
        "stages=({type=\"isotropic\";pressure=1000.0;tolerance=1e-4;"
        "max_time=0.05;},"
        "{type=\"cyclic\";axis=\"x\";pressure=1000.0;amplitude=500.0;"
        "period=0.1;cycles=1;},"
        "{type=\"hold\";duration=0.05;})"};
    char out[1024];
    run_text(ex->text, "cycles-hold", sets, 3, 0, out, sizeof out);
    static const struct dem__csv_want want[] = {DEM_CSV_FINITE("stage", 1),
                                                DEM_CSV_FINITE("sigma_xx", 1)};
    struct dem__csv_table t;
    read_ts(out, want, 2, &t);
    double top1 = 0.0, top2 = 0.0;
    int n2 = 0;
    for (size_t r = 0; r < t.nrow; r++) {
        const double sx = t.col[1][r];
        if (t.col[0][r] == 1.0)
            top1 = fmax(top1, sx);
        if (t.col[0][r] == 2.0) {
            top2 = fmax(top2, sx);
            n2++;
        }
    }
    assert_true(n2 >= 5);
    assert_true(top1 > 1350.0); /* the cycle reached p0 + amplitude */
    assert_true(top2 < 1100.0); /* the hold stayed about p0 */
    dem__csv_table_free(&t);
}

/* The same for a periodic cell's tilt: a hold after a cyclic shear
 * keeps the shear where it stands (the tilt went on cycling). */
static void a_hold_after_a_cyclic_shear_stops_the_tilt(void **state)
{
    (void)state;
    char out[1024];
    run_small_shear("shear-hold",
                    "{type=\"shear\";shear_strain=0.01;duration=4e-4;"
                    "profile=\"sine\";cycles=1;pressure=500.0;},"
                    "{type=\"hold\";duration=2e-4;}",
                    out, sizeof out);
    static const struct dem__csv_want want[] = {DEM_CSV_FINITE("stage", 1),
                                                DEM_CSV_FINITE("gamma_xy", 1)};
    struct dem__csv_table t;
    read_ts(out, want, 2, &t);
    double lo[3], hi[3];
    stage_ranges(&t, 3, lo, hi);
    assert_true(hi[1] - lo[1] > 0.015); /* the shear went both ways */
    assert_true(isfinite(lo[2]));
    assert_true(hi[2] - lo[2] <= 1e-8); /* the hold kept it */
    dem__csv_table_free(&t);
}

/* A hold with relax ends when the packing is at rest (E_kin/E_pot below
 * it; SPEC's "relax / hold ... until a criterion holds"), long before
 * its duration; without relax it runs the whole duration. */
static void a_hold_with_relax_ends_at_rest(void **state)
{
    (void)state;
    const struct dem_example *ex = dem_example_find("hold3d");
    assert_non_null(ex);
    static const struct dem__csv_want want[] = {
        DEM_CSV_FINITE("t", 1), DEM_CSV_FINITE("stage", 1),
        DEM_CSV_FINITE("e_kin", 1), DEM_CSV_FINITE("e_rot", 1),
        DEM_CSV_FINITE("e_pot", 1)};
    double end[2];
    for (int k = 0; k < 2; k++) {
        const char *const sets[] = {
            "output.snapshot_interval=0", "stages.1.duration=0.5",
            k ? "stages.1.relax=1e-3" : "stages.1.relax=0"};
        char out[1024];
        run_text(ex->text, k ? "hold-relax" : "hold-full", sets, 3, 0, out,
                 sizeof out);
        struct dem__csv_table t;
        read_ts(out, want, 5, &t);
        const size_t r = t.nrow - 1;
        assert_true(t.col[1][r] == 1.0);
        end[k] = t.col[0][r];
        if (k) /* at rest where it ended */
            assert_true(t.col[2][r] + t.col[3][r] < 1e-3 * t.col[4][r]);
        dem__csv_table_free(&t);
    }
    assert_true(end[1] < 0.5 * end[0]);
}

static void keep_line(const char *line, void *user)
{
    snprintf((char *)user, 1024, "%s", line);
}

/* Bytes in use on the heap (glibc). */
static double heap_in_use(void)
{
    const struct mallinfo2 m = mallinfo2();
    return (double)m.uordblks + (double)m.hblkhd;
}

/* A sample too large for the machine is refused before anything is
 * allocated, naming the key; one that may not fit is a warning. The two
 * bytes-per-particle figures bracket what a sample takes when it is
 * created (2D and 3D, 20000 particles: measured on the heap). */
static void memory_a_sample_takes_is_checked_first(void **state)
{
    (void)state;
    struct dem_error err = {0};
    const double GB = 1e9;
    assert_int_equal(dem_sim_memory_check(100000000, 1,
                                          "particles.count = "
                                          "100000000",
                                          24 * GB, 24 * GB, &err),
                     DEM_ENOMEM);
    assert_string_equal(err.msg,
                        "particles.count = 100000000: a run of 100000000 "
                        "particles takes at least 30 GB of memory (300 bytes "
                        "per particle before its first step, about 1.2 kB "
                        "once packed), more than this machine's 24 GB");
    char warned[1024] = "";
    struct dem_error w = {0, "", keep_line, warned};
    assert_int_equal(
        dem_sim_memory_check(10000000, 1, "k", 24 * GB, 8 * GB, &w), DEM_OK);
    assert_string_equal(warned, "k: a packed sample of 10000000 particles "
                                "takes about 12 GB of memory (1.2 kB per "
                                "particle), more than the 8 GB available "
                                "now: expect swapping, or the out-of-memory "
                                "killer to end the run");
    warned[0] = '\0';
    assert_int_equal(
        dem_sim_memory_check(10000000, 1, "k", 24 * GB, 16 * GB, &w), DEM_OK);
    assert_int_equal(dem_sim_memory_check(100000000, 1, "k", 0, 0, &w), DEM_OK);
    assert_string_equal(warned, "");
    /* MPI ranks on one machine each hold the whole sample (a split run
     * builds it on every rank; a sweep's ranks each run one): 32 ranks
     * of 10^7 particles are refused where one fits easily, and 2 ranks
     * warned of where one is not */
    assert_int_equal(
        dem_sim_memory_check(10000000, 32, "k", 24 * GB, 24 * GB, &err),
        DEM_ENOMEM);
    assert_string_equal(err.msg,
                        "k: a run of 10000000 particles on each of 32 MPI "
                        "ranks takes at least 96 GB of memory (300 bytes per "
                        "particle before its first step, about 1.2 kB once "
                        "packed), more than this machine's 24 GB");
    assert_int_equal(
        dem_sim_memory_check(10000000, 2, "k", 96 * GB, 16 * GB, &w), DEM_OK);
    assert_string_equal(warned,
                        "k: a packed sample of 10000000 particles on each of "
                        "2 MPI ranks takes about 24 GB of memory (1.2 kB per "
                        "particle), more than the 16 GB available now: expect "
                        "swapping, or the out-of-memory killer to end the "
                        "run");
    warned[0] = '\0';

#if defined(__SANITIZE_ADDRESS__)
    /* AddressSanitizer's own allocator: glibc's counts stay still */
    print_message("(the heap is not measured under AddressSanitizer)\n");
    return;
#endif
    for (int dim = 2; dim <= 3; dim++) {
        struct dem_config c;
        const char *sets[] = {dim == 2 ? "dimension=2" : "dimension=3",
                              "particles.count=20000"};
        if (dem_config_parse(&c, "", "memory", sets, 2, &err))
            fail_msg("%s", err.msg);
        const double before = heap_in_use();
        struct dem_sim s;
        if (dem_sim_create(&s, &c, NULL, &err))
            fail_msg("%s", err.msg);
        const double per = (heap_in_use() - before) / 20000.0;
        dem_sim_destroy(&s);
        if (per < DEM_SIM_BYTES_LEAST || per > DEM_SIM_BYTES_PACKED)
            fail_msg("%dD: %.0f bytes per particle, outside [%d, %.0f]", dim,
                     per, DEM_SIM_BYTES_LEAST, DEM_SIM_BYTES_PACKED);
        print_message("%dD: %.0f bytes per particle when created\n", dim, per);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bad_run_options_are_refused),
        cmocka_unit_test(a_second_writer_into_a_folder_is_refused),
        cmocka_unit_test(removal_patterns_are_the_leaf_only),
        cmocka_unit_test(the_config_file_is_not_overwritten_by_its_run),
        cmocka_unit_test(every_example_runs_a_few_hundred_steps),
        cmocka_unit_test(isotropic_stage_reaches_target_pressure),
        cmocka_unit_test(biaxial_fixed_walls_and_dilatancy),
        cmocka_unit_test(same_seed_same_output),
        cmocka_unit_test(snapshots_and_dump_cover_start_and_end),
        cmocka_unit_test(contact_history_columns_follow_the_law),
        cmocka_unit_test(overlap_blow_up_is_diagnosed),
        cmocka_unit_test(energy_growth_is_diagnosed),
        cmocka_unit_test(auto_step_follows_a_particle_file),
        cmocka_unit_test(viscosity_limit_follows_a_particle_file),
        cmocka_unit_test(memory_a_sample_takes_is_checked_first),
        cmocka_unit_test(a_stage_after_shear_holds_the_tilt),
        cmocka_unit_test(a_shear_stage_ends_at_its_shear_strain),
        cmocka_unit_test(a_decimal_comma_locale_writes_the_same_files),
        cmocka_unit_test(a_servo_at_its_speed_cap_is_warned_of),
        cmocka_unit_test(a_servo_off_its_target_is_warned_of),
        cmocka_unit_test(a_constant_p_path_into_tension_is_warned_of),
        cmocka_unit_test(a_hold_counts_only_its_own_servo_steps),
        cmocka_unit_test(an_isotropic_stage_ends_with_its_walls_at_rest),
        cmocka_unit_test(a_stage_at_rest_on_its_last_sample_is_not_timed_out),
        cmocka_unit_test(a_hold_after_cycles_stops_the_cycling),
        cmocka_unit_test(a_hold_after_a_cyclic_shear_stops_the_tilt),
        cmocka_unit_test(a_hold_with_relax_ends_at_rest),
        cmocka_unit_test(threads_left_to_the_library_are_chosen_by_timing),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
