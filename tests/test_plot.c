/* Plots of a run folder (plot/): every script, data file and picture
 * appears, the loading stage is found from the data, and broken input
 * gives errors that name the file or the column. The timeseries is
 * written with the engine's own header and row writers, so the test
 * follows the real columns. */
#include <fcntl.h>
#include <math.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "contact/models.h"
#include "dembox.h"
#include "measure/measure.h"
#include "plot/plot.h"
#include "testutil.h"

static const char *const curve_plots[] = {
    "stress_strain", "volumetric_strain",
    "stress_ratio",  "deviatoric_stress_strain",
    "energies",      "mohr_circles",
};
#define NCURVES (sizeof curve_plots / sizeof curve_plots[0])

static char *make_dir(void)
{
    char tmpl[] = "/tmp/dembox_test_plot_XXXXXX";
    char *d = mkdtemp(tmpl);
    assert_non_null(d);
    return strdup(d);
}

static void remove_dir(char *dir)
{
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
    free(dir);
}

static void path_of(char *out, size_t n, const char *dir, const char *leaf)
{
    int k = snprintf(out, n, "%s/%s", dir, leaf);
    assert_true(k > 0 && (size_t)k < n);
}

/* text as the file dir/leaf */
static void write_text(const char *dir, const char *leaf, const char *text)
{
    char p[1024];
    path_of(p, sizeof p, dir, leaf);
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

static long file_size(const char *dir, const char *leaf)
{
    char p[1024];
    path_of(p, sizeof p, dir, leaf);
    struct stat st;
    return stat(p, &st) == 0 ? (long)st.st_size : -1;
}

static int have_gnuplot(void)
{
    return system("command -v gnuplot >/dev/null 2>&1") == 0;
}

/* The shear stress sigma_lw_xy of write_timeseries's loading stage, in
 * units of p0 (0: none). */
static double ts_shear = 0.0;

/* A biaxial-like history: stage 0 isotropic (all strains equal),
 * stage 1 compression along `axis` with a stress peak and dilation. */
static void write_timeseries(const char *dir, int dim, int axis, int rows)
{
    char p[1024];
    path_of(p, sizeof p, dir, "timeseries.csv");
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    dem_sample_write_header(f, dim);
    const double p0 = 500.0, L0 = 0.1;
    for (int k = 0; k < 2 * rows; k++) {
        struct dem_sample s;
        memset(&s, 0, sizeof s);
        const int stage = k < rows ? 0 : 1;
        const double u = (double)(k % rows + 1) / rows; /* 0..1 in stage */
        s.t = 1e-3 * (k + 1);
        s.stage = stage;
        for (int a = 0; a < dim; a++) {
            s.eps[a] = stage == 0 ? 0.05 * u : 0.0;
            s.sigma[a] = stage == 0 ? p0 * u : p0;
        }
        if (stage == 1) {
            const double ea = 0.2 * u;
            s.eps[axis] = ea;
            for (int a = 0; a < dim; a++)
                if (a != axis)
                    s.eps[a] = -0.1 * ea + 0.5 * ea * ea;
            s.sigma[axis] = p0 * (1.0 + 2.0 * ea / (0.02 + ea));
            s.eps_v = -0.3 * ea + 2.0 * ea * ea;
            s.sigma_lw[0][1] = s.sigma_lw[1][0] = ts_shear * p0;
        }
        for (int a = 0; a < dim; a++) {
            s.L[a] = L0 * (1.0 - s.eps[a]);
            s.wall_pos[2 * a] = 0.0;
            s.wall_pos[2 * a + 1] = s.L[a];
        }
        s.e_kin = 1e-3 * exp(-10.0 * u);
        s.e_rot = 1e-4 * exp(-10.0 * u);
        s.e_pot = 1e-2 * u;
        dem_sample_write_row(f, &s, dim);
    }
    assert_int_equal(fclose(f), 0);
}

/* A lattice of n x n (x n) particles filling the 0.1 m box, none
 * touching another (contacts_final.csv has no rows). */
static int write_particles(const char *dir, int dim, int with_forces)
{
    char p[1024], q[1024];
    path_of(p, sizeof p, dir, "contacts_final.csv");
    FILE *c = fopen(p, "w");
    assert_non_null(c);
    fprintf(c, "id_i,id_j,x,y,z,nx,ny,nz,delta,fn,ft_x,ft_y,ft_z,sliding\n");
    assert_int_equal(fclose(c), 0);
    path_of(p, sizeof p, dir, "particles_final.csv");
    path_of(q, sizeof q, dir, "forces_final.csv");
    FILE *f = fopen(p, "w"), *g = with_forces ? fopen(q, "w") : NULL;
    assert_non_null(f);
    fprintf(f, "# written by test_plot\nx,y,z,vx,vy,vz,wx,wy,wz,radius,"
               "mass\n");
    if (g)
        fprintf(g, "fsum\n");
    const int n = 10, nz = dim == 3 ? n : 1;
    const double a = 0.005;
    int count = 0;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                double x = a + 2 * a * i, y = a + 2 * a * j;
                double z = dim == 3 ? a + 2 * a * k : 0.0;
                fprintf(f, "%g,%g,%g,%g,%g,0,0,0,0,%g,0.001\n", x, y, z,
                        0.01 * i, 0.01 * j, a * (0.8 + 0.02 * i));
                if (g)
                    fprintf(g, "%g\n", (double)(i + j) * (1 + k % 2));
                count++;
            }
    assert_int_equal(fclose(f), 0);
    if (g)
        assert_int_equal(fclose(g), 0);
    return count;
}

static void assert_png(const char *plotdir, const char *name)
{
    char leaf[256], p[1024];
    snprintf(leaf, sizeof leaf, "%s.png", name);
    path_of(p, sizeof p, plotdir, leaf);
    FILE *f = fopen(p, "rb");
    if (!f)
        fail_msg("%s was not written", p);
    unsigned char magic[8] = {0};
    size_t got = fread(magic, 1, 8, f);
    fclose(f);
    static const unsigned char png[8] = {0x89, 'P',  'N',  'G',
                                         '\r', '\n', 0x1a, '\n'};
    if (got != 8 || memcmp(magic, png, 8) != 0)
        fail_msg("%s is not a PNG file", p);
    long size = file_size(plotdir, leaf);
    if (size <= 1024)
        fail_msg("%s has only %ld bytes", p, size);
}

static void assert_outputs(const char *dir)
{
    char plotdir[1024];
    path_of(plotdir, sizeof plotdir, dir, "plots");
    for (size_t k = 0; k < NCURVES; k++) {
        char leaf[256];
        snprintf(leaf, sizeof leaf, "%s.gp", curve_plots[k]);
        if (file_size(plotdir, leaf) <= 0)
            fail_msg("plots/%s missing or empty", leaf);
        snprintf(leaf, sizeof leaf, "%s.dat", curve_plots[k]);
        if (file_size(plotdir, leaf) <= 0)
            fail_msg("plots/%s missing or empty", leaf);
        if (have_gnuplot())
            assert_png(plotdir, curve_plots[k]);
    }
    assert_png(plotdir, "particles");
}

/* 1 if the file dir/leaf contains s. */
static int file_contains(const char *dir, const char *leaf, const char *s)
{
    char p[1024], line[4096];
    path_of(p, sizeof p, dir, leaf);
    FILE *f = fopen(p, "r");
    if (!f)
        return 0;
    int found = 0;
    while (!found && fgets(line, sizeof line, f))
        found = strstr(line, s) != NULL;
    fclose(f);
    return found;
}

static void run_ok(const char *dir)
{
    struct dem_error err = {0};
    int rc = dem_plot_run(dir, &err);
    if (rc)
        fail_msg("dem_plot_run: %s", err.msg);
}

static void biaxial_2d_writes_every_script_and_picture(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 200);
    write_particles(dir, 2, 0);
    run_ok(dir);
    assert_outputs(dir);
    remove_dir(dir);
}

/* The compression stage, not the larger isotropic strain, is the loading
 * stage, and its axis is the one that departs from the others. */
static void loading_stage_is_the_anisotropic_one(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 3, 0, 50);
    write_particles(dir, 3, 1);
    run_ok(dir);
    assert_true(file_contains(dir, "plots/stress_strain.dat",
                              "3D, loading stage 1, loading axis x"));
    assert_true(file_contains(dir, "plots/stress_strain.gp", "σ_{zz}"));
    /* the loading axis' stress solid, the equal lateral ones (here both
     * p0) dashed and dash-dot, so that neither hides the other */
    assert_true(file_contains(dir, "plots/stress_strain.gp",
                              "using 1:2 with lines linewidth 2 dashtype 1 "));
    assert_true(file_contains(dir, "plots/stress_strain.gp",
                              "using 1:3 with lines linewidth 2 dashtype 2 "));
    assert_true(file_contains(dir, "plots/stress_strain.gp",
                              "using 1:4 with lines linewidth 2 dashtype 4 "));
    assert_outputs(dir);
    remove_dir(dir);
}

static void scripts_rerun_from_the_plots_folder(void **state)
{
    (void)state;
    if (!have_gnuplot())
        skip();
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 30);
    write_particles(dir, 2, 0);
    run_ok(dir);
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "cd '%s/plots' && rm stress_strain.png && gnuplot "
             "stress_strain.gp 2>/dev/null",
             dir);
    assert_int_equal(system(cmd), 0);
    char plotdir[1024];
    path_of(plotdir, sizeof plotdir, dir, "plots");
    assert_png(plotdir, "stress_strain");
    remove_dir(dir);
}

static void missing_gnuplot_still_writes_scripts(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 30);
    write_particles(dir, 2, 0);
    /* a picture left by an earlier plotting no longer matches the data */
    char p[1024];
    path_of(p, sizeof p, dir, "plots");
    assert_int_equal(mkdir(p, 0755), 0);
    path_of(p, sizeof p, dir, "plots/stress_strain.png");
    FILE *old = fopen(p, "w");
    assert_non_null(old);
    fclose(old);
    setenv("DEMBOX_GNUPLOT", "dembox-no-such-gnuplot", 1);
    struct dem_error err = {0};
    int rc = dem_plot_run(dir, &err);
    unsetenv("DEMBOX_GNUPLOT");
    assert_int_equal(rc, 0);
    assert_true(file_size(dir, "plots/stress_strain.gp") > 0);
    assert_int_equal(file_size(dir, "plots/stress_strain.png"), -1);
    assert_true(file_size(dir, "plots/particles.png") > 1024);
    remove_dir(dir);
}

static void missing_timeseries_names_the_file(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_particles(dir, 2, 0);
    struct dem_error err = {0};
    assert_int_not_equal(dem_plot_run(dir, &err), 0);
    char want[1200];
    snprintf(want, sizeof want,
             "%s: not a dembox run folder (no "
             "timeseries.csv)",
             dir);
    assert_string_equal(err.msg, want);

    /* a stopped run (only timeseries.csv.part) is said to be one, as by
     * dem_analyze (which needs config.cfg too); and so is a folder that
     * is not there */
    write_text(dir, "timeseries.csv.part", "t\n0\n");
    assert_int_not_equal(dem_plot_run(dir, &err), 0);
    snprintf(want, sizeof want,
             "%s: the run has not finished (only "
             "timeseries.csv.part, no timeseries.csv)",
             dir);
    assert_string_equal(err.msg, want);
    char gone[1024];
    snprintf(gone, sizeof gone, "%s", dir);
    remove_dir(dir);
    assert_int_not_equal(dem_plot_run(gone, &err), 0);
    snprintf(want, sizeof want, "%s: no such folder", gone);
    assert_string_equal(err.msg, want);
}

/* Drop column `name` from the header and every row of timeseries.csv. */
static void drop_column(const char *dir, const char *name)
{
    char p[1024], line[8192];
    path_of(p, sizeof p, dir, "timeseries.csv");
    FILE *f = fopen(p, "r");
    assert_non_null(f);
    char *out = NULL;
    size_t outlen = 0;
    FILE *o = open_memstream(&out, &outlen);
    int drop = -1;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        int col = 0;
        const char *sep = "";
        for (char *tok = strtok(line, ","); tok;
             tok = strtok(NULL, ","), col++) {
            if (drop < 0 && !strcmp(tok, name))
                drop = col;
            if (col == drop)
                continue;
            fprintf(o, "%s%s", sep, tok);
            sep = ",";
        }
        fputc('\n', o);
    }
    fclose(f);
    fclose(o);
    assert_true(drop >= 0);
    f = fopen(p, "w");
    fputs(out, f);
    fclose(f);
    free(out);
}

static void missing_column_names_the_column(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 10);
    write_particles(dir, 2, 0);
    drop_column(dir, "sigma_yy");
    struct dem_error err = {0};
    assert_int_not_equal(dem_plot_run(dir, &err), 0);
    assert_non_null(strstr(err.msg, "'sigma_yy'"));
    assert_non_null(strstr(err.msg, "timeseries.csv"));
    remove_dir(dir);
}

static void header_only_timeseries_is_a_clear_error(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 0);
    write_particles(dir, 2, 0);
    struct dem_error err = {0};
    assert_int_not_equal(dem_plot_run(dir, &err), 0);
    assert_non_null(strstr(err.msg, "no data rows"));
    remove_dir(dir);
}

static void forces_file_of_wrong_length_is_an_error(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 10);
    write_particles(dir, 2, 0);
    write_text(dir, "forces_final.csv", "fsum\n1\n2\n");
    struct dem_error err = {0};
    assert_int_not_equal(dem_plot_run(dir, &err), 0);
    assert_non_null(strstr(err.msg, "forces_final.csv"));
    remove_dir(dir);
}

/* A folder whose config is 3D and whose files hold 2D data is not one
 * run's: its loading axis z is one the data lack (the labels once read
 * outside an array for it; found by fuzz_run_folder). */
/* The first two numbers of the last data row of dir/leaf. */
static void last_row(const char *dir, const char *leaf, double *x, double *y)
{
    char p[1024], line[512];
    path_of(p, sizeof p, dir, leaf);
    FILE *f = fopen(p, "r");
    assert_non_null(f);
    *x = *y = NAN;
    while (fgets(line, sizeof line, f))
        if (line[0] != '#' && line[0] != '\n')
            sscanf(line, "%lf %lf", x, y);
    fclose(f);
}

/* The stress ratio drawn as the analysis takes it, major stress first:
 * in an extension (strain < 0) the lateral stress over the axial one. */
static void stress_ratio_of_an_extension_is_lateral_over_axial(void **state)
{
    (void)state;
    for (int ext = 0; ext < 2; ext++) {
        char *dir = make_dir();
        write_timeseries(dir, 2, 1, 50);
        write_particles(dir, 2, 0);
        char cfg[512];
        snprintf(cfg, sizeof cfg,
                 "dimension = 2;\ntime_step = 1.0e-6;\n"
                 "stages = (\n"
                 "  { type = \"isotropic\"; pressure = 500.0; },\n"
                 "  { type = \"compress\"; axis = \"y\"; strain = %s; "
                 "duration = 1.0; pressure = 500.0; }\n"
                 ");\n",
                 ext ? "-0.2" : "0.2");
        write_text(dir, "config.cfg", cfg);
        run_ok(dir);
        assert_true(file_contains(dir, "plots/stress_ratio.gp",
                                  ext ? "(σ_{xx} − σ_{yy})/(σ_{xx} + σ_{yy})"
                                      : "(σ_{yy} − σ_{xx})/(σ_{yy} + σ_{xx})"));
        /* the data's axial stress is the larger: the ratio drawn in the
         * extension's frame is negative */
        double x, y;
        last_row(dir, "plots/stress_ratio.dat", &x, &y);
        assert_true(isfinite(y));
        assert_true(ext ? y < 0.0 : y > 0.0);
        remove_dir(dir);
    }
}

/* A 3D run folder in a new dir whose compression is along axis (0, 1,
 * 2), its particles and config; returns the dir. */
static char *write_3d_loading(int axis)
{
    char *dir = make_dir();
    write_timeseries(dir, 3, axis, 50);
    write_particles(dir, 3, 0);
    char cfg[512];
    snprintf(cfg, sizeof cfg,
             "dimension = 3;\ntime_step = 1.0e-6;\n"
             "stages = (\n"
             "  { type = \"isotropic\"; pressure = 500.0; },\n"
             "  { type = \"compress\"; axis = \"%c\"; strain = 0.2; "
             "duration = 1.0; pressure = 500.0; }\n"
             ");\n",
             "xyz"[axis]);
    write_text(dir, "config.cfg", cfg);
    return dir;
}

/* The deviatoric plot is of the loading axis against the mean of the
 * others, as summary.json's cycles: a 3D loading along z drew x against
 * y, two lateral axes, a line about 0 (a read-only review, session 108). */
static void deviatoric_plot_follows_the_loading_axis(void **state)
{
    (void)state;
    char *dir = write_3d_loading(2);
    run_ok(dir);
    double x, y;
    last_row(dir, "plots/deviatoric_stress_strain.dat", &x, &y);
    /* the last row: eps_z 0.2, the laterals' 0; sigma_z = 500 (1 + 0.4
     * / 0.22), the laterals' 500 */
    assert_close(x, 0.2, 1e-9);
    assert_close(y, 2.0 / 3.0 * 500.0 * 0.4 / 0.22, 1e-6);
    assert_true(file_contains(dir, "plots/deviatoric_stress_strain.gp",
                              "σ_D = 2(σ_{zz} − σ_{lat})/3"));
    remove_dir(dir);
}

/* The 3D rose of the contact normals is on the plane of the loading
 * axis (up) and the first other one: normals along y, a loading along y,
 * all in the sectors at 90 and 270 degrees (projected on x-z, as always
 * until session 108, they were points at the origin: no rose at all). */
static void contact_rose_is_on_the_loading_axis(void **state)
{
    (void)state;
    char *dir = write_3d_loading(1);
    write_text(dir, "contacts_final.csv",
               "id_i,id_j,x,y,z,nx,ny,nz,delta,fn,ft_x,ft_y,ft_z,sliding\n"
               "0,1,0.01,0.01,0.01,0,1,0,1e-6,1.0,0,0,0,0\n"
               "2,3,0.03,0.01,0.01,0,-1,0,1e-6,2.0,0,0,0,0\n");
    run_ok(dir);
    assert_true(file_contains(dir, "plots/contact_normals.dat",
                              "from x towards y (3D normals projected on x-y)"));
    char p[1024], line[512];
    path_of(p, sizeof p, dir, "plots/contact_normals.dat");
    FILE *f = fopen(p, "r");
    assert_non_null(f);
    double best = -1.0, at = NAN;
    while (fgets(line, sizeof line, f)) {
        double th, e;
        if (line[0] != '#' && sscanf(line, "%lf %lf", &th, &e) == 2 &&
            e > best) {
            best = e;
            at = th;
        }
    }
    fclose(f);
    assert_true(best > 0.0);
    assert_close(at, 90.0, 1e-9); /* the sector [90, 100) */
    remove_dir(dir);
}

static void config_of_another_dimension_is_an_error(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 10);
    write_particles(dir, 2, 0);
    const struct dem_example *ex = dem_example_find("triaxial3d");
    assert_non_null(ex);
    write_text(dir, "config.cfg", ex->text);
    struct dem_error err = {0};
    assert_int_not_equal(dem_plot_run(dir, &err), 0);
    assert_non_null(strstr(err.msg, "config.cfg is not 2D"));
    remove_dir(dir);
}

/* A cyclic run's summary.json gives a picture of the strain per cycle:
 * every cycle a row of the data file with its gain and its accumulated
 * strain, a negative gain drawn as an open circle, the verdict in the
 * key; a run without cycles gets none. */
static void cycles_of_the_summary_are_drawn(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 3, 0, 30);
    write_particles(dir, 3, 0);
    run_ok(dir);
    assert_int_equal(file_size(dir, "plots/strain_accumulation.dat"), -1);
    char p[1024];
    path_of(p, sizeof p, dir, "summary.json");
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    fprintf(f, "{\"peak\": {\"sin_phi\": null}, \"cyclic_stage\": 1, "
               "\"cycles\": ["
               "{\"index\": 1, \"strain_end\": 2e-05, "
               "\"strain_increment\": 2e-05},"
               "{\"index\": 2, \"strain_end\": 2.1e-05, "
               "\"strain_increment\": 1e-06},"
               "{\"index\": 3, \"strain_end\": 2.05e-05, "
               "\"strain_increment\": -5e-07}], "
               "\"verdict\": \"shakedown\"}\n");
    assert_int_equal(fclose(f), 0);
    run_ok(dir);
    assert_true(file_contains(dir, "plots/strain_accumulation.dat",
                              "1 2e-05 0 2e-05 0 1"));
    assert_true(file_contains(dir, "plots/strain_accumulation.dat",
                              "2 1e-06 0 2.1e-05 0 1"));
    assert_true(file_contains(dir, "plots/strain_accumulation.dat",
                              "3 -5e-07 0 2.05e-05 0 1"));
    assert_true(file_contains(dir, "plots/strain_accumulation.gp",
                              "verdict: shakedown"));
    assert_true(
        file_contains(dir, "plots/strain_accumulation.gp", "open: negative"));
    /* one run: no error bars, whose glyph the key showed of errors 0 */
    assert_true(
        file_contains(dir, "plots/strain_accumulation.gp", "linespoints"));
    assert_false(file_contains(dir, "plots/strain_accumulation.gp", "yerror"));
    assert_outputs(dir);
    if (have_gnuplot()) {
        char plotdir[1024];
        path_of(plotdir, sizeof plotdir, dir, "plots");
        assert_png(plotdir, "strain_accumulation");
    }
    /* the summary gone (a run of another kind into the folder, say): the
     * picture of its cycles goes with it */
    assert_int_equal(remove(p), 0);
    run_ok(dir);
    assert_int_equal(file_size(dir, "plots/strain_accumulation.dat"), -1);
    assert_int_equal(file_size(dir, "plots/strain_accumulation.gp"), -1);
    assert_int_equal(file_size(dir, "plots/strain_accumulation.png"), -1);
    assert_outputs(dir);
    remove_dir(dir);
}

/* The Mohr circles' peak is summary.json's: the circle at the row of its
 * strain, the line at its (smoothed) sin phi, as stress_ratio.png's
 * mark; not the raw largest ratio, here at the end of loading. */
static void mohr_peak_is_the_summary_peak(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 200);
    write_particles(dir, 2, 0);
    write_text(dir, "summary.json",
               "{\"peak\": {\"sin_phi\": 0.31, \"strain\": 0.1}}\n");
    run_ok(dir);
    char want[128];
    assert_true(
        file_contains(dir, "plots/mohr_circles.dat", "# peak: t = 0.3 s,"));
    snprintf(want, sizeof want, "phi = %.9g deg", asin(0.31) * 180.0 / M_PI);
    assert_true(file_contains(dir, "plots/mohr_circles.dat", want));
    /* before an analysis: the largest ratio, at the end */
    path_of(want, sizeof want, dir, "summary.json");
    assert_int_equal(remove(want), 0);
    run_ok(dir);
    assert_true(
        file_contains(dir, "plots/mohr_circles.dat", "# peak: t = 0.4 s,"));
    remove_dir(dir);
}

/* Where the analysis found no peak (summary.json's peak null: a curve
 * whose largest ratio is not above its plateau, a cyclic stage), the
 * pictures mark none: not the raw maximum as "peak" (they did, beside a
 * summary saying there was none). The critical state, where there is
 * one, is drawn as its level in stress_ratio.png and its line in
 * mohr_circles.png, whose first circle is then the largest ratio's,
 * named so, without a tangent of its own. */
static void a_summary_without_a_peak_marks_none(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 200);
    write_particles(dir, 2, 0);
    write_text(dir, "summary.json",
               "{\"peak\": {\"sin_phi\": null, \"strain\": null}, "
               "\"critical\": {\"sin_phi\": 0.2, \"sin_phi_se\": 0.01}}\n");
    run_ok(dir);
    assert_false(file_contains(dir, "plots/stress_ratio.gp", "peak"));
    assert_true(file_contains(dir, "plots/stress_ratio.gp",
                              "0.2 with lines dashtype 3"));
    assert_true(file_contains(dir, "plots/stress_ratio.gp",
                              "critical state 0.2 ± 0.01 (summary.json)"));
    assert_true(file_contains(dir, "plots/mohr_circles.dat",
                              "# largest stress ratio: t = 0.4 s,"));
    assert_false(file_contains(dir, "plots/mohr_circles.dat", "# tangent"));
    char want[128];
    snprintf(want, sizeof want,
             "# critical state tau = sigma tan(phi), phi = %.9g deg",
             asin(0.2) * 180.0 / M_PI);
    assert_true(file_contains(dir, "plots/mohr_circles.dat", want));
    /* with a peak: its mark and tangent, and the critical line too */
    write_text(dir, "summary.json",
               "{\"peak\": {\"sin_phi\": 0.31, \"strain\": 0.1}, "
               "\"critical\": {\"sin_phi\": 0.2}}\n");
    run_ok(dir);
    assert_true(file_contains(dir, "plots/stress_ratio.gp", "peak"));
    assert_true(file_contains(dir, "plots/mohr_circles.dat", "# tangent"));
    assert_true(file_contains(dir, "plots/mohr_circles.dat", want));
    remove_dir(dir);
}

/* A run whose config.cfg has no loading stage (an isotropic compression
 * and a simple shear) has no loading curves: they were drawn against the
 * strain of the most anisotropic stage, here the shear's ε_yy, which the
 * servo moves back and forth, under a title of wall stresses "during
 * loading" in a cell without walls. The energies stay. */
static void a_run_without_a_loading_stage_draws_no_loading_curves(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 20);
    write_particles(dir, 2, 0);
    const struct dem_example *ex = dem_example_find("shear2d");
    assert_non_null(ex);
    write_text(dir, "config.cfg", ex->text);
    run_ok(dir);
    static const char *const loading[] = {
        "stress_strain", "volumetric_strain", "stress_ratio",
        "deviatoric_stress_strain", "mohr_circles"};
    for (size_t k = 0; k < sizeof loading / sizeof *loading; k++) {
        char leaf[128];
        snprintf(leaf, sizeof leaf, "plots/%s.gp", loading[k]);
        assert_int_equal(file_size(dir, leaf), -1);
    }
    assert_true(file_size(dir, "plots/energies.gp") > 0);
    remove_dir(dir);
}

/* In a periodic cell the Mohr circle is the cell stress's, its shear
 * stress included: here sigma_xy = 0.3 p0 beside sigma_xx = p0 and
 * sigma_yy = 3 p0 at the end of loading, whose circle has centre 2 p0
 * and radius sqrt(p0^2 + (0.3 p0)^2); the diagonal alone gave radius p0. */
static void mohr_circles_of_a_cell_take_its_shear_stress(void **state)
{
    (void)state;
    char *dir = make_dir();
    ts_shear = 0.3;
    write_timeseries(dir, 2, 1, 20);
    ts_shear = 0.0;
    write_particles(dir, 2, 0);
    write_text(dir, "config.cfg",
               "dimension = 2;\n"
               "particles = { count = 100; volume_fraction = 0.4; };\n"
               "box = { boundary = \"periodic\"; };\n"
               "stages = ( { type = \"isotropic\"; pressure = 500.0; },\n"
               "  { type = \"compress\"; strain = 0.2; duration = 0.3;\n"
               "    pressure = 500.0; } );\n");
    run_ok(dir);
    /* the last row: eps_a = 0.2, sigma_a = p0 (1 + 0.4/0.22) */
    const double p0 = 500.0, sa = p0 * (1.0 + 0.4 / 0.22),
                 c = 0.5 * (sa + p0), h = 0.5 * (sa - p0),
                 r = sqrt(h * h + 0.09 * p0 * p0);
    char want[160];
    snprintf(want, sizeof want,
             "# end of loading: t = 0.04 s, sigma_1 = %.9g, sigma_3 = %.9g",
             c + r, c - r);
    if (!file_contains(dir, "plots/mohr_circles.dat", want))
        fail_msg("mohr_circles.dat lacks '%s'", want);
    remove_dir(dir);
}

/* A run folder named "-run", given as a relative path: gnuplot's cd does
 * not take it for an option. */
static void a_folder_named_like_an_option_is_plotted(void **state)
{
    (void)state;
    if (!have_gnuplot())
        skip();
    char *dir = make_dir(), cwd[1024];
    assert_non_null(getcwd(cwd, sizeof cwd));
    assert_int_equal(chdir(dir), 0);
    assert_int_equal(mkdir("-run", 0755), 0);
    write_timeseries("-run", 2, 1, 50);
    write_particles("-run", 2, 0);
    run_ok("-run");
    assert_png("-run/plots", "stress_strain");
    assert_int_equal(chdir(cwd), 0);
    remove_dir(dir);
}

/* The warnings of a call, one per line, into a buffer of 2048 bytes. */
static void collect_warning(const char *line, void *user)
{
    char *all = user;
    const size_t len = strlen(all);
    snprintf(all + len, 2048 - len, "%s\n", line);
}

/* The config is read back for the loading stage: its warnings were the
 * run's (a time step above t_c/10 here) and are not given again, neither
 * to the caller nor on stderr. */
static void config_warnings_are_not_given_again(void **state)
{
    (void)state;
    char *dir = make_dir();
    write_timeseries(dir, 2, 1, 50);
    write_particles(dir, 2, 0);
    const struct dem_example *ex = dem_example_find("biaxial2d");
    assert_non_null(ex);
    struct dem_config c;
    char warned[2048] = "", set[64];
    struct dem_error err = {.warn = collect_warning, .warn_user = warned};
    assert_int_equal(dem_config_parse(&c, ex->text, "t", 0, 0, &err), 0);
    snprintf(set, sizeof set, "time_step=%.17g", 0.15 * dem_contact_time(&c));
    const char *sets[] = {set};
    assert_int_equal(dem_config_parse(&c, ex->text, "t", sets, 1, &err), 0);
    assert_non_null(strstr(warned, "above t_c/10"));
    char path[512];
    path_of(path, sizeof path, dir, "config.cfg");
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    assert_int_equal(dem_config_write(&c, f), 0);
    assert_int_equal(fclose(f), 0);

    warned[0] = '\0';
    path_of(path, sizeof path, dir, "stderr.txt");
    fflush(stderr);
    const int saved = dup(2), fd = open(path, O_WRONLY | O_CREAT, 0600);
    assert_true(saved >= 0 && fd >= 0);
    dup2(fd, 2);
    const int rc = dem_plot_run(dir, &err);
    fflush(stderr);
    dup2(saved, 2);
    close(fd);
    close(saved);
    if (rc)
        fail_msg("dem_plot_run: %s", err.msg);
    assert_string_equal(warned, "");
    assert_false(file_contains(dir, "stderr.txt", "warning"));
    /* a folder without its contacts is drawn without their pictures, but
     * not without a word (session 115) */
    path_of(path, sizeof path, dir, "contacts_final.csv");
    assert_int_equal(remove(path), 0);
    assert_int_equal(dem_plot_run(dir, &err), 0);
    if (!strstr(warned, "contacts_final.csv: No such file or directory: the "
                        "pictures of the contact network"))
        fail_msg("warnings '%s'", warned);
    remove_dir(dir);
}

/* A summary.json that dem_analyze did not write (an edited verdict that
 * would end the key's string in the gnuplot script and add a command
 * line, a sin phi above 1) is left out with one warning naming the file
 * and the value: the pictures are drawn without it, and nothing of it
 * reaches a script. */
static void summary_not_written_by_analyze_is_left_out(void **state)
{
    (void)state;
    static const struct {
        const char *summary, *warning;
    } rows[] = {
        {"{\"cyclic_stage\": 1, \"cycles\": [{\"strain_end\": 1e-5, "
         "\"strain_increment\": 1e-5}], \"verdict\": \"x\\\" noenhanced\\n"
         "system \\\"touch injected\\\"\\n#\"}",
         "verdict is not \"ratcheting\", \"shakedown\" or null"},
        {"{\"peak\": {\"sin_phi\": 1.5, \"strain\": 0.01}}",
         "peak.sin_phi = 1.5 is not in [-1, 1]"},
        {"{\"cyclic_stage\": 1, \"cycles\": [1e-5]}",
         "cycles[0] is not an object"},
        {"{\"peak\": {\"sin_phi\": 0.5, \"strain\": \"0.01\"}}",
         "peak.strain is a string, not a number or null"},
        {"{\"peak\": {\"sin_phi\": 0.5, \"strain\": 1e999}}",
         "invalid JSON at byte 36: number out of the range of a double"},
        /* the control: what dem_analyze writes is drawn */
        {"{\"peak\": {\"sin_phi\": 0.5, \"strain\": 1e-3}}", NULL},
    };
    for (size_t k = 0; k < sizeof rows / sizeof *rows; k++) {
        char *dir = make_dir();
        write_timeseries(dir, 3, 0, 30);
        write_particles(dir, 3, 0);
        write_text(dir, "summary.json", rows[k].summary);
        char warned[2048] = "";
        struct dem_error err = {.warn = collect_warning, .warn_user = warned};
        if (dem_plot_run(dir, &err))
            fail_msg("row %zu: %s", k, err.msg);
        const int drawn = rows[k].warning == NULL;
        if (drawn ? strstr(warned, "summary.json") != NULL
                  : !strstr(warned, rows[k].warning) ||
                        !strstr(warned, "summary.json"))
            fail_msg("row %zu: warnings '%s'", k, warned);
        assert_int_equal(file_size(dir, "plots/strain_accumulation.dat"), -1);
        assert_int_equal(file_size(dir, "plots/strain_accumulation.gp"), -1);
        assert_int_equal(
            file_contains(dir, "plots/stress_ratio.gp", "(summary.json)"),
            drawn);
        remove_dir(dir);
    }
}

/* A text bound for a gnuplot string cannot end it, end the line, or
 * hold a backquote (gnuplot runs `...` as a shell command even inside
 * double quotes); the rest is kept. */
static void texts_for_gnuplot_strings_are_made_inert(void **state)
{
    (void)state;
    char s[] = "mu=0.5 \"\nsystem \"touch x\"\n# `touch y` a\\b\tc\x7f";
    dem__gp_text(s);
    assert_string_equal(s, "mu=0.5 ' system 'touch x' # 'touch y' a/b c ");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(biaxial_2d_writes_every_script_and_picture),
        cmocka_unit_test(loading_stage_is_the_anisotropic_one),
        cmocka_unit_test(scripts_rerun_from_the_plots_folder),
        cmocka_unit_test(missing_gnuplot_still_writes_scripts),
        cmocka_unit_test(missing_timeseries_names_the_file),
        cmocka_unit_test(missing_column_names_the_column),
        cmocka_unit_test(header_only_timeseries_is_a_clear_error),
        cmocka_unit_test(forces_file_of_wrong_length_is_an_error),
        cmocka_unit_test(config_of_another_dimension_is_an_error),
        cmocka_unit_test(stress_ratio_of_an_extension_is_lateral_over_axial),
        cmocka_unit_test(deviatoric_plot_follows_the_loading_axis),
        cmocka_unit_test(contact_rose_is_on_the_loading_axis),
        cmocka_unit_test(cycles_of_the_summary_are_drawn),
        cmocka_unit_test(mohr_peak_is_the_summary_peak),
        cmocka_unit_test(a_summary_without_a_peak_marks_none),
        cmocka_unit_test(a_run_without_a_loading_stage_draws_no_loading_curves),
        cmocka_unit_test(mohr_circles_of_a_cell_take_its_shear_stress),
        cmocka_unit_test(a_folder_named_like_an_option_is_plotted),
        cmocka_unit_test(config_warnings_are_not_given_again),
        cmocka_unit_test(summary_not_written_by_analyze_is_left_out),
        cmocka_unit_test(texts_for_gnuplot_strings_are_made_inert),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
