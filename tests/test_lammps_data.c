/* LAMMPS data files (atom_style sphere): a hand-written file parses to the
 * numbers it holds, velocities are matched by atom id, the writer round-trips
 * bit-exactly, malformed files give one message naming file and line, and
 * the peers' 2D packing (when present on this machine) reads completely;
 * the header alone reads as in the full read. */
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
#include "formats/lammps_data.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

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

/* Velocities listed in another order than the atoms, image flags on one
 * atom and not on the other, comments and blank lines. */
static const char *const small_file =
    "LAMMPS data file via write_data, version 29 Sep 2021, timestep = 10\n"
    "\n"
    "2 atoms\n"
    "1 atom types\n"
    "\n"
    "0.0 0.1 xlo xhi\n"
    "-0.05 0.05 ylo yhi   # a comment\n"
    "0.01 0.2 zlo zhi\n"
    "\n"
    "Atoms # sphere\n"
    "\n"
    "7 1 0.01 2000 0.02 0.03 0.04 0 1 0\n"
    "3 1 0.012 1999.5 0.05 -0.01 0.1\n"
    "\n"
    "Velocities\n"
    "\n"
    "3 1 2 3 4 5 6\n"
    "7 -1 -2 -3 -4 -5 -6\n";

static void small_file_parses_to_its_numbers(void **state)
{
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/small.data", tmpdir);
    write_text(path, small_file);
    struct dem_lammps_data d;
    struct dem_error err = {0};
    int rc = dem_lammps_data_read(&d, path, &err);
    if (rc)
        fail_msg("%s", err.msg);
    assert_int_equal(d.n, 2);
    assert_true(d.lo[0] == 0.0 && d.hi[0] == 0.1);
    assert_true(d.lo[1] == -0.05 && d.hi[1] == 0.05);
    assert_true(d.lo[2] == 0.01 && d.hi[2] == 0.2);
    assert_int_equal(d.id[0], 7);
    assert_int_equal(d.id[1], 3);
    assert_true(d.diameter[0] == 0.01 && d.density[0] == 2000.0);
    assert_true(d.x[0] == 0.02 && d.y[0] == 0.03 && d.z[0] == 0.04);
    assert_true(d.diameter[1] == 0.012 && d.density[1] == 1999.5);
    assert_true(d.x[1] == 0.05 && d.y[1] == -0.01 && d.z[1] == 0.1);
    assert_int_equal(d.has_velocities, 1);
    /* matched by id, not by line */
    assert_true(d.vx[0] == -1.0 && d.wz[0] == -6.0);
    assert_true(d.vx[1] == 1.0 && d.vy[1] == 2.0 && d.vz[1] == 3.0);
    assert_true(d.wx[1] == 4.0 && d.wy[1] == 5.0 && d.wz[1] == 6.0);
    dem_lammps_data_free(&d);
}

/* The header alone gives the count and the box of the full read, stops
 * at the first section (a broken Atoms section is not its business) and
 * refuses a broken header as the full read does. */
static void header_alone_gives_count_and_box(void **state)
{
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/small.data", tmpdir);
    write_text(path, small_file);
    struct dem_lammps_data d, h;
    struct dem_error err = {0};
    if (dem_lammps_data_read(&d, path, &err) ||
        dem_lammps_data_read_header(&h, path, &err))
        fail_msg("%s", err.msg);
    assert_int_equal(h.n, d.n);
    for (int a = 0; a < 3; a++)
        assert_true(h.lo[a] == d.lo[a] && h.hi[a] == d.hi[a]);
    assert_null(h.x);
    assert_null(h.id);
    dem_lammps_data_free(&d);
    dem_lammps_data_free(&h);

    write_text(path, "t\n\n3 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo "
                     "zhi\n\nAtoms\n\nnot an atom\n");
    if (dem_lammps_data_read_header(&h, path, &err))
        fail_msg("%s", err.msg);
    assert_int_equal(h.n, 3);
    assert_int_not_equal(dem_lammps_data_read(&d, path, &err), 0);

    write_text(path, "t\n\n-3 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo "
                     "zhi\n\nAtoms\n");
    assert_int_not_equal(dem_lammps_data_read_header(&h, path, &err), 0);
    if (!strstr(err.msg, ":3: bad atom count") || !strstr(err.msg, path))
        fail_msg("message '%s'", err.msg);
    assert_null(h.x);
}

static void write_then_read_is_bit_exact(void **state)
{
    (void)state;
    struct dem_particles p;
    struct dem_error err = {0};
    assert_int_equal(dem_particles_init(&p, 3, &err), 0);
    const double r[3] = {4.1e-3, 5.0e-3, 6.3e-3};
    for (int i = 0; i < 3; i++) {
        int k = dem_particles_add(&p, 0.01 * (i + 1) + 1e-9 / 3.0,
                                  0.02 / 3.0 * (i + 1), 0.1 / 7.0 * i, r[i],
                                  2000.0, DEM_MASS_SPHERE, 3);
        assert_int_equal(k, i);
        p.vx[i] = 1.0 / 3.0 * i;
        p.wz[i] = -2.0 / 7.0;
    }
    /* a re-ordered engine keeps the original index in id */
    p.id[0] = 2;
    p.id[2] = 0;
    char path[128];
    snprintf(path, sizeof path, "%s/round.data", tmpdir);
    const double lo[3] = {0.0, -0.01, 0.0}, hi[3] = {0.1, 0.09, 0.1};
    assert_int_equal(dem_lammps_data_write(path, &p, lo, hi, 0, &err), 0);
    struct dem_lammps_data d;
    int rc = dem_lammps_data_read(&d, path, &err);
    if (rc)
        fail_msg("%s", err.msg);
    assert_int_equal(d.n, 3);
    for (int a = 0; a < 3; a++)
        assert_true(same_bits(d.lo[a], lo[a]) && same_bits(d.hi[a], hi[a]));
    for (int i = 0; i < 3; i++) {
        assert_int_equal(d.id[i], p.id[i] + 1);
        assert_true(same_bits(d.x[i], p.x[i]));
        assert_true(same_bits(d.y[i], p.y[i]));
        assert_true(same_bits(d.z[i], p.z[i]));
        assert_true(same_bits(d.vx[i], p.vx[i]));
        assert_true(same_bits(d.wz[i], p.wz[i]));
        assert_true(same_bits(0.5 * d.diameter[i], p.r[i]));
        /* the density recovered from the mass gives the mass back */
        double m =
            4.0 / 3.0 * M_PI * d.density[i] * pow(0.5 * d.diameter[i], 3);
        assert_true(fabs(m / p.m[i] - 1.0) < 1e-14);
    }
    dem_lammps_data_free(&d);
    dem_particles_free(&p);
}

/* Each malformed file, the line its message must name and a word of it. */
static void malformed_files_name_file_and_line(void **state)
{
    (void)state;
    static const struct {
        const char *text;
        const char *expect;
    } cases[] = {
        {"t\n\n2 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 0.1 2000 0.5 0.5\n",
         ":10: Atoms: 6 columns"},
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 -0.1 2000 0.5 0.5 0.5\n",
         ":10: Atoms: diameter must be > 0"},
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n\nAtoms\n\n"
         "1 1 0.1 2000 0.5 0.5 0.5\n",
         "no \"zlo zhi\" line"},
        {"t\n\n2 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 0.1 2000 0.5 0.5 0.5\n",
         "file ends after 1 of 2 atoms"},
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 0.1 2000 0.5 0.5 0.5\n\nVelocities\n\n2 0 0 0 0 0 0\n",
         ":14: Velocities: no atom with id 2"},
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n0 0 0 xy xz "
         "yz\n",
         ":7: triclinic"},
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nMasses\n\n1 "
         "1.0\n",
         ":8: unsupported section or line: Masses"},
        {"t\n\n2 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "4 1 0.1 2000 0.5 0.5 0.5\n4 1 0.1 2000 0.2 0.5 0.5\n",
         "atom id 4 appears twice"},
        /* another atom style of 7 columns (peri: id type volume density
         * x y z), and image flags that are not integers */
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms # "
         "peri\n\n1 1 0.1 2000 0.5 0.5 0.5\n",
         ":8: Atoms # peri: atom_style sphere expected"},
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms # "
         "sphere\n\n1 1 0.1 2000 0.5 0.5 0.5 0 0 abc\n",
         ":10: Atoms: bad image flag abc"},
        /* further out than its diameter: a broken file (a periodic
         * cell's particles leave the box by less than a skin) */
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 0.1 2000 0.5 1.2 0.5\n",
         ":10: Atoms: atom 1 at y = 1.2 lies outside the box"},
        /* an id beyond an int, which would wrap onto atom 1's */
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 0.1 2000 0.5 0.5 0.5\n\nVelocities\n\n4294967297 1 0 0 0 0 "
         "0\n",
         ":14: Velocities: bad atom id 4294967297"},
        /* one atom twice, the other never */
        {"t\n\n2 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 0.1 2000 0.5 0.5 0.5\n2 1 0.1 2000 0.2 0.5 0.5\n\nVelocities\n"
         "\n1 1 0 0 0 0 0\n1 0 0 0 0 0 0\n",
         ":16: Velocities: a second line for atom 1"},
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 0.1 2000 0.5 0.5 0.5\n\nVelocities\n\n1 0 0 0 0 0 0\n\n"
         "Velocities\n\n1 0 0 0 0 0 0\n",
         ":16: second Velocities section"},
        /* (the id table of the first was leaked: the ASan build checks) */
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 0.1 2000 0.5 0.5 0.5\n\nAtoms\n\n1 1 0.1 2000 0.5 0.5 0.5\n",
         ":12: second Atoms section"},
        /* a diameter whose sphere's mass underflows to 0: 1/m = inf */
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 1e-300 2000 0.5 0.5 0.5\n",
         ":10: Atoms: atom 1's diameter 1e-300 and density "
         "2000 give a mass of 0 kg"},
        /* and a density whose mass overflows */
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 0.5 1e308 0.5 0.5 0.5\n",
         ":10: Atoms: atom 1's diameter 0.5 and density 1e+308 give a mass "
         "of inf kg"},
        /* a header announcing the most atoms dembox takes in a short
         * file: refused at its end, with memory for the atoms read only */
        {"t\n\n100000000 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\n"
         "Atoms\n\n1 1 0.1 2000 0.5 0.5 0.5\n",
         "file ends after 1 of 100000000 atoms"},
        /* one more than that */
        {"t\n\n100000001 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\n"
         "Atoms\n\n1 1 0.1 2000 0.5 0.5 0.5\n",
         ":3: 100000001 atoms: more than the 100000000 dembox takes"},
        /* a sphere wider than the box (that slack would let it pass) */
        {"t\n\n1 atoms\n0 1 xlo xhi\n0 2 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
         "1 1 1e300 2000 0.5 1.2 0.5\n",
         ":10: Atoms: atom 1's diameter 1.0000000000000001e+300 exceeds the "
         "box's extent along x"},
    };
    char path[128];
    snprintf(path, sizeof path, "%s/bad.data", tmpdir);
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        write_text(path, cases[k].text);
        struct dem_lammps_data d;
        struct dem_error err = {0};
        int rc = dem_lammps_data_read(&d, path, &err);
        if (rc == 0)
            fail_msg("case %zu: accepted", k);
        if (!strstr(err.msg, cases[k].expect) || !strstr(err.msg, path))
            fail_msg("case %zu: message '%s' lacks '%s'", k, err.msg,
                     cases[k].expect);
        assert_null(d.x);
    }
}

/* A centre outside the box by less than its diameter is read as written
 * (a periodic cell's particle between two wraps). */
static void centres_just_outside_the_box_are_kept(void **state)
{
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/edge.data", tmpdir);
    write_text(path, "t\n\n2 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo "
                     "zhi\n\nAtoms\n\n1 1 0.1 2000 -0.09 0.5 0.5\n"
                     "2 1 0.1 2000 0.5 0.5 1.09\n");
    struct dem_lammps_data d;
    struct dem_error err = {0};
    assert_int_equal(dem_lammps_data_read(&d, path, &err), 0);
    assert_true(same_bits(d.x[0], -0.09));
    assert_true(same_bits(d.z[1], 1.09));
    dem_lammps_data_free(&d);
}

/* The peers' prepared 2D packing, if this machine has it
 * ($DEMBOX_BENCH_DATA, else ../shared/bench/data next to the source tree). */
static void peers_packing_reads_completely(void **state)
{
    (void)state;
    const char *dir = getenv("DEMBOX_BENCH_DATA");
    const char *src = getenv("DEMBOX_SOURCE_DIR");
    char path[1024];
    if (dir && *dir)
        snprintf(path, sizeof path, "%s/pack2d_1950.data", dir);
    else if (src && *src)
        snprintf(path, sizeof path, "%s/../shared/bench/data/pack2d_1950.data",
                 src);
    else
        skip();
    if (access(path, R_OK) != 0)
        skip();
    struct dem_lammps_data d;
    struct dem_error err = {0};
    int rc = dem_lammps_data_read(&d, path, &err);
    if (rc)
        fail_msg("%s", err.msg);
    assert_int_equal(d.n, 1950);
    assert_int_equal(d.has_velocities, 1);
    for (int i = 0; i < d.n; i++) {
        /* radii U[0.5, 1.5] mm, positions inside the periodic box */
        assert_true(d.diameter[i] >= 1e-3 - 1e-12 &&
                    d.diameter[i] <= 3e-3 + 1e-12);
        assert_true(d.x[i] >= d.lo[0] && d.x[i] <= d.hi[0]);
        assert_true(d.y[i] >= d.lo[1] && d.y[i] <= d.hi[1]);
        assert_true(fabs(d.z[i]) < 1e-12);
        assert_true(fabs(d.density[i] / 2000.0 - 1.0) < 1e-9);
    }
    dem_lammps_data_free(&d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(small_file_parses_to_its_numbers),
        cmocka_unit_test(header_alone_gives_count_and_box),
        cmocka_unit_test(write_then_read_is_bit_exact),
        cmocka_unit_test(malformed_files_name_file_and_line),
        cmocka_unit_test(centres_just_outside_the_box_are_kept),
        cmocka_unit_test(peers_packing_reads_completely),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
