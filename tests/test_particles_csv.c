/* Particle CSV: bit-exact round trip and one precise message per kind of
 * malformed file. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "core/particles.h"
#include "core/rng.h"
#include "formats/particles_csv.h"

#include "tmpdir.h"

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Swap particles i and j in memory, as a spatial re-ordering would. */
static void swap_particles(struct dem_particles *p, int i, int j)
{
    double *arrays[] = {p->x,  p->y,  p->z, p->vx, p->vy,    p->vz,   p->wx,
                        p->wy, p->wz, p->r, p->m,  p->inv_m, p->inv_I};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++) {
        double t = arrays[k][i];
        arrays[k][i] = arrays[k][j];
        arrays[k][j] = t;
    }
    int t = p->id[i];
    p->id[i] = p->id[j];
    p->id[j] = t;
}

static void check_round_trip(int dim, int mass_model)
{
    const int n = 257;
    const double rho = 2650.0; /* kg/m^3 */
    struct dem_particles a, b;
    struct dem_error err = {0};
    struct dem_rng g;
    dem_rng_seed(&g, 11);
    assert_int_equal(dem_particles_init(&a, n, &err), DEM_OK);
    for (int i = 0; i < n; i++) {
        /* Values with full 53-bit mantissas, spanning many decades. */
        double r = 1e-4 * (1.0 + dem_rng_uniform(&g)) * pow(10.0, i % 5);
        double x = dem_rng_normal(&g) * 0.1, y = dem_rng_normal(&g) / 3.0;
        double z = dim == 3 ? dem_rng_normal(&g) * 1e-7 : 0.0;
        assert_int_equal(
            dem_particles_add(&a, x, y, z, r, rho, mass_model, dim), i);
        a.vx[i] = dem_rng_normal(&g);
        a.vy[i] = -dem_rng_uniform(&g) * 1e-300; /* subnormal range too */
        a.wz[i] = dem_rng_normal(&g) * 1e5;
        if (dim == 3) {
            a.vz[i] = dem_rng_normal(&g);
            a.wx[i] = dem_rng_normal(&g);
            a.wy[i] = dem_rng_normal(&g);
        }
    }
    a.vx[3] = -0.0;
    /* Re-order in memory: reverse, then a few swaps. */
    for (int i = 0; i < n / 2; i++)
        swap_particles(&a, i, n - 1 - i);
    swap_particles(&a, 0, 100);
    swap_particles(&a, 7, 8);

    char path[128];
    snprintf(path, sizeof path, "%s/rt%d_%d.csv", tmpdir, dim, mass_model);
    assert_int_equal(dem_particles_write_csv(&a, path, &err), DEM_OK);
    char tmp[140];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    assert_int_equal(access(tmp, F_OK), -1); /* renamed away */

    assert_int_equal(
        dem_particles_read_csv(&b, path, dim, rho, mass_model, &err), DEM_OK);
    assert_int_equal(b.n, n);
    for (int i = 0; i < n; i++) {
        int j = b.id[i];
        assert_int_equal(j, i); /* rows come back in original order */
        int k = 0;
        while (a.id[k] != j)
            k++;
        assert_true(same_bits(a.x[k], b.x[i]));
        assert_true(same_bits(a.y[k], b.y[i]));
        assert_true(same_bits(a.z[k], b.z[i]));
        assert_true(same_bits(a.vx[k], b.vx[i]));
        assert_true(same_bits(a.vy[k], b.vy[i]));
        assert_true(same_bits(a.vz[k], b.vz[i]));
        assert_true(same_bits(a.wx[k], b.wx[i]));
        assert_true(same_bits(a.wy[k], b.wy[i]));
        assert_true(same_bits(a.wz[k], b.wz[i]));
        assert_true(same_bits(a.r[k], b.r[i]));
        assert_true(same_bits(a.m[k], b.m[i]));
        assert_true(same_bits(a.inv_m[k], b.inv_m[i]));
        assert_true(same_bits(a.inv_I[k], b.inv_I[i]));
    }
    dem_particles_free(&a);
    dem_particles_free(&b);
}

static void write_then_read_is_bit_identical_3d(void **state)
{
    (void)state;
    check_round_trip(3, DEM_MASS_SPHERE);
}

static void write_then_read_is_bit_identical_2d_disc(void **state)
{
    (void)state;
    check_round_trip(2, DEM_MASS_DISC);
}

static void optional_columns_any_order_and_mass_from_density(void **state)
{
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/opt.csv", tmpdir);
    write_text(path, "# written by hand\r\n"
                     "\r\n"
                     " radius , y, x ,wz\r\n"
                     "0.5, 2, 1, 3\r\n"
                     "\n"
                     "# another comment\n"
                     "0.25,-1,-2,0\n");
    struct dem_particles p;
    struct dem_error err = {0};
    const double rho = 1000.0;
    assert_int_equal(
        dem_particles_read_csv(&p, path, 2, rho, DEM_MASS_SPHERE, &err),
        DEM_OK);
    assert_int_equal(p.n, 2);
    assert_true(p.x[0] == 1.0 && p.y[0] == 2.0 && p.z[0] == 0.0);
    assert_true(p.wz[0] == 3.0 && p.vx[0] == 0.0);
    assert_true(p.x[1] == -2.0 && p.r[1] == 0.25);
    double m, I;
    dem_particle_mass(0.5, rho, DEM_MASS_SPHERE, 2, &m, &I);
    assert_true(fabs(m - 4.0 / 3.0 * M_PI * rho * 0.125) < 1e-12 * m);
    assert_true(same_bits(p.m[0], m));
    assert_true(same_bits(p.inv_I[0], 1.0 / I));
    dem_particles_free(&p);

    /* the same with a UTF-8 byte order mark before the header (a
     * spreadsheet's "CSV UTF-8"): it was read as part of the first
     * column's name, "unknown column" */
    write_text(path, "\xEF\xBB\xBFradius,y,x\r\n0.5,2,1\r\n");
    assert_int_equal(
        dem_particles_read_csv(&p, path, 2, rho, DEM_MASS_SPHERE, &err),
        DEM_OK);
    assert_true(p.n == 1 && p.r[0] == 0.5 && p.x[0] == 1.0);
    dem_particles_free(&p);

    /* Disc in 2D: m = pi rho a^2, I = m a^2 / 2. */
    dem_particle_mass(0.5, rho, DEM_MASS_DISC, 2, &m, &I);
    assert_true(fabs(m - M_PI * rho * 0.25) < 1e-12 * m);
    assert_true(fabs(I - 0.5 * m * 0.25) < 1e-12 * I);
}

struct bad_case {
    const char *what;
    int dim;
    const char *text;
    int code;         /* expected status */
    int line;         /* expected line in "FILE:LINE:" */
    const char *says; /* expected substring naming the column or fault */
};

static const struct bad_case bad_cases[] = {
    {"empty file", 3, "", DEM_ECONFIG, 1, "empty file"},
    {"only comments", 3, "# c\n\n# d\n", DEM_ECONFIG, 3, "no header"},
    {"numbers first", 3, "1,2,3,0.1\n", DEM_ECONFIG, 1, "no header"},
    {"unknown column", 3, "x,y,z,radius,foo\n0,0,0,1,2\n", DEM_ECONFIG, 1,
     "unknown column 'foo'"},
    {"duplicate column", 3, "#h\nx,y,z,radius,x\n", DEM_ECONFIG, 2,
     "duplicate column 'x'"},
    {"too many header fields", 3, "x,y,z,vx,vy,vz,wx,wy,wz,radius,mass,x,y\n",
     DEM_ECONFIG, 1, "duplicate column 'x'"},
    {"missing z in 3D", 3, "x,y,radius\n0,0,1\n", DEM_ECONFIG, 1,
     "missing required column 'z'"},
    {"missing radius", 2, "x,y\n0,0\n", DEM_ECONFIG, 1,
     "missing required column 'radius'"},
    {"missing x", 2, "y,radius\n0,1\n", DEM_ECONFIG, 1,
     "missing required column 'x'"},
    {"short row", 3, "x,y,z,radius\n0,0,0,1\n0,0,0\n", DEM_ECONFIG, 3,
     "3 fields"},
    {"long row", 3, "x,y,z,radius\n0,0,0,1,5\n", DEM_ECONFIG, 2, "5 fields"},
    {"text", 3, "x,y,z,radius\n# c\n0,abc,0,1\n", DEM_ECONFIG, 3, "column 'y'"},
    {"nan", 3, "x,y,z,radius\n0,0,nan,1\n", DEM_ECONFIG, 2, "column 'z'"},
    {"inf", 3, "x,y,z,radius\n-inf,0,0,1\n", DEM_ECONFIG, 2, "column 'x'"},
    {"overflow", 3, "x,y,z,radius\n0,0,0,1e999\n", DEM_ECONFIG, 2,
     "column 'radius'"},
    {"trailing junk", 3, "x,y,z,radius\n0,0,0,0.5x\n", DEM_ECONFIG, 2,
     "column 'radius'"},
    {"empty field", 3, "x,y,z,radius\n0,,0,1\n", DEM_ECONFIG, 2, "column 'y'"},
    {"zero radius", 3, "x,y,z,radius\n0,0,0,1\n1,1,1,0\n", DEM_ECONFIG, 3,
     "column 'radius'"},
    {"negative radius", 3, "x,y,z,radius\n0,0,0,-1\n", DEM_ECONFIG, 2,
     "column 'radius'"},
    {"zero mass", 3, "x,y,z,radius,mass\n0,0,0,1,0\n", DEM_ECONFIG, 2,
     "column 'mass'"},
    /* found by fuzz_particles_csv: finite inputs, unusable mass */
    {"mass overflows", 3, "x,y,z,radius\n0,0,0,1\n0,0,0,1e200\n", DEM_ECONFIG,
     3, "column 'radius': 1e+200 m gives a mass of inf kg"},
    {"mass underflows", 3, "x,y,z,radius\n0,0,0,1e-200\n", DEM_ECONFIG, 2,
     "column 'radius'"},
    {"inertia underflows", 3, "x,y,z,radius,mass\n0,0,0,1e-3,1e-303\n",
     DEM_ECONFIG, 2,
     "column 'mass': radius 0.001 m and mass 1e-303 kg give "
     "a moment of inertia of 4e-310 kg m^2"},
    {"inverse mass overflows", 3, "x,y,z,radius,mass\n0,0,0,0.1,1e-320\n",
     DEM_ECONFIG, 2, "column 'mass': 9.99989e-321 kg is out of range"},
    {"inertia overflows", 3, "x,y,z,radius,mass\n0,0,0,1e160,1e10\n",
     DEM_ECONFIG, 2, "column 'mass'"},
    {"header only", 3, "x,y,z,radius\n\n", DEM_ECONFIG, 2, "no particles"},
    {"2D nonzero z", 2, "x,y,z,radius\n0,0,0,1\n0,0,1e-3,1\n", DEM_ECONFIG, 3,
     "column 'z'"},
    {"2D nonzero vz", 2, "x,y,vz,radius\n0,0,1,1\n", DEM_ECONFIG, 2,
     "column 'vz'"},
    {"2D nonzero wx", 2, "x,y,radius,wx\n0,0,1,2\n", DEM_ECONFIG, 2,
     "column 'wx'"},
};

static void malformed_files_name_file_line_and_column(void **state)
{
    (void)state;
    size_t ncase = sizeof bad_cases / sizeof bad_cases[0];
    for (size_t k = 0; k < ncase; k++) {
        const struct bad_case *c = &bad_cases[k];
        char path[128], want[200];
        snprintf(path, sizeof path, "%s/bad%02zu.csv", tmpdir, k);
        write_text(path, c->text);
        struct dem_particles p;
        struct dem_error err = {0};
        int rc = dem_particles_read_csv(&p, path, c->dim, 2000.0,
                                        DEM_MASS_SPHERE, &err);
        snprintf(want, sizeof want, "%s:%d: ", path, c->line);
        if (rc != c->code || strncmp(err.msg, want, strlen(want)) != 0 ||
            !strstr(err.msg, c->says) || strchr(err.msg, '\n'))
            fail_msg("case '%s': rc %d, message \"%s\"; wanted rc %d, "
                     "prefix \"%s\" and \"%s\"",
                     c->what, rc, err.msg, c->code, want, c->says);
        assert_int_equal(p.n, 0);
        assert_null(p.x);
    }
}

/* Found by fuzz_particles_csv: the line used to end silently at a NUL. */
static void nul_byte_is_an_error_with_its_line(void **state)
{
    (void)state;
    static const char text[] = "x,y,radius\n0,0,1\n1,0,1\0,5\n";
    FILE *f = fmemopen((void *)text, sizeof text - 1, "r");
    assert_non_null(f);
    struct dem_particles p;
    struct dem_error err = {0};
    int *lines = 0;
    int rc = dem_particles_read_csv_stream(&p, f, "mem.csv", 2, 2000.0,
                                           DEM_MASS_DISC, &lines, &err);
    fclose(f);
    assert_int_equal(rc, DEM_ECONFIG);
    assert_string_equal(err.msg,
                        "mem.csv:3: NUL byte: a particle file is text, not "
                        "binary");
    assert_int_equal(p.n, 0);
    assert_null(lines);
}

static void missing_file_is_an_io_error(void **state)
{
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/does-not-exist.csv", tmpdir);
    struct dem_particles p;
    struct dem_error err = {0};
    assert_int_equal(
        dem_particles_read_csv(&p, path, 3, 2000.0, DEM_MASS_SPHERE, &err),
        DEM_EIO);
    assert_non_null(strstr(err.msg, path));
}

static void unwritable_path_is_an_io_error(void **state)
{
    (void)state;
    struct dem_particles p;
    struct dem_error err = {0};
    assert_int_equal(dem_particles_init(&p, 1, &err), DEM_OK);
    dem_particles_add(&p, 0, 0, 0, 1e-3, 2000.0, DEM_MASS_SPHERE, 3);
    char path[128];
    snprintf(path, sizeof path, "%s/no/such/dir/p.csv", tmpdir);
    assert_int_equal(dem_particles_write_csv(&p, path, &err), DEM_EIO);
    assert_non_null(strstr(err.msg, path));
    dem_particles_free(&p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(write_then_read_is_bit_identical_3d),
        cmocka_unit_test(write_then_read_is_bit_identical_2d_disc),
        cmocka_unit_test(optional_columns_any_order_and_mass_from_density),
        cmocka_unit_test(malformed_files_name_file_line_and_column),
        cmocka_unit_test(nul_byte_is_an_error_with_its_line),
        cmocka_unit_test(missing_file_is_an_io_error),
        cmocka_unit_test(unwritable_path_is_an_io_error),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
