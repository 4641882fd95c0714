/* Placement: reproducible radii and positions, the right radius
 * distributions, no overlaps, everything inside the box, and clear errors
 * when the particles cannot be placed. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "core/particles.h"
#include "core/placement.h"
#include "core/rng.h"
#include "formats/particles_csv.h"

/* The config defaults of SPEC §8, filled by hand (the parser lives in
 * another module). */
static void config_defaults(struct dem_config *c, int dim, int placement,
                            int count)
{
    memset(c, 0, sizeof *c);
    c->dim = dim;
    c->seed = 1;
    c->particles.count = count;
    c->particles.density = 2000.0; /* kg/m^3 */
    c->particles.distribution = DEM_DIST_GAUSSIAN;
    c->particles.mean = 5.0e-3; /* m */
    c->particles.std = 0.7e-3;  /* m */
    c->particles.min = 3.0e-3;  /* m */
    c->particles.max = 0.0;     /* m; not given: no upper cut */
    c->particles.placement = placement;
    c->particles.mass_model = DEM_MASS_SPHERE;
}

static int place(struct dem_particles *p, const struct dem_config *c,
                 double lo[3], double hi[3], struct dem_error *err)
{
    struct dem_rng g;
    dem_rng_seed(&g, c->seed);
    if (c->particles.placement != DEM_PLACE_FILE)
        return dem_place_particles(p, c, &g, NULL, lo, hi, err);
    /* a file's particles are read (and checked against box.size) first */
    struct dem_particles given;
    int rc = dem_particles_load(&given, c, err);
    if (!rc)
        rc = dem_place_particles(p, c, &g, &given, lo, hi, err);
    else
        memset(p, 0, sizeof *p);
    dem_particles_free(&given);
    return rc;
}

static void place_ok(struct dem_particles *p, const struct dem_config *c,
                     double lo[3], double hi[3])
{
    struct dem_error err = {0};
    int rc = place(p, c, lo, hi, &err);
    if (rc != DEM_OK)
        fail_msg("placement failed: %s", err.msg);
}

/* Brute force over all pairs: strictly apart, and every particle inside
 * [lo, hi] on the active axes. */
static void assert_no_overlap_inside(const struct dem_particles *p, int dim,
                                     const double lo[3], const double hi[3])
{
    for (int i = 0; i < p->n; i++) {
        const double c[3] = {p->x[i], p->y[i], p->z[i]};
        for (int a = 0; a < dim; a++)
            if (!(c[a] - p->r[i] >= lo[a] && c[a] + p->r[i] <= hi[a]))
                fail_msg("particle %d sticks out of the box on axis %d: "
                         "centre %g radius %g box [%g, %g]",
                         i, a, c[a], p->r[i], lo[a], hi[a]);
        if (dim == 2)
            assert_true(p->z[i] == 0.0);
        for (int j = i + 1; j < p->n; j++) {
            double dx = p->x[i] - p->x[j], dy = p->y[i] - p->y[j],
                   dz = p->z[i] - p->z[j], s = p->r[i] + p->r[j];
            if (!(dx * dx + dy * dy + dz * dz > s * s))
                fail_msg("particles %d and %d overlap", i, j);
        }
    }
    if (dim == 2) {
        double rmax = 0.0;
        for (int i = 0; i < p->n; i++)
            rmax = fmax(rmax, p->r[i]);
        assert_true(lo[2] == -rmax && hi[2] == rmax);
    }
}

static void same_seed_gives_same_radii_and_positions(void **state)
{
    (void)state;
    for (int dim = 2; dim <= 3; dim++) {
        struct dem_config c;
        struct dem_particles a, b, l;
        double lo[3], hi[3], lo2[3], hi2[3];
        config_defaults(&c, dim, DEM_PLACE_RANDOM, 500);
        c.seed = 1234;
        place_ok(&a, &c, lo, hi);
        place_ok(&b, &c, lo2, hi2);
        assert_int_equal(a.n, 500);
        assert_memory_equal(a.r, b.r, (size_t)a.n * sizeof *a.r);
        assert_memory_equal(a.x, b.x, (size_t)a.n * sizeof *a.x);
        assert_memory_equal(a.y, b.y, (size_t)a.n * sizeof *a.y);
        assert_memory_equal(a.z, b.z, (size_t)a.n * sizeof *a.z);
        assert_memory_equal(lo, lo2, sizeof lo);
        assert_memory_equal(hi, hi2, sizeof hi);
        for (int i = 0; i < a.n; i++)
            assert_int_equal(a.id[i], i);

        /* Radii are drawn before positions: the lattice gets the same. */
        c.particles.placement = DEM_PLACE_LATTICE;
        place_ok(&l, &c, lo, hi);
        assert_memory_equal(a.r, l.r, (size_t)a.n * sizeof *a.r);
        dem_particles_free(&l);

        /* Another seed, other radii. */
        c.seed = 1235;
        place_ok(&l, &c, lo, hi);
        assert_memory_not_equal(a.r, l.r, (size_t)a.n * sizeof *a.r);
        dem_particles_free(&l);
        dem_particles_free(&a);
        dem_particles_free(&b);
    }
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void uniform_radii_have_the_midpoint_mean(void **state)
{
    (void)state;
    const int n = 20000;
    struct dem_config c;
    struct dem_particles p;
    double lo[3], hi[3];
    config_defaults(&c, 3, DEM_PLACE_LATTICE, n);
    c.particles.distribution = DEM_DIST_UNIFORM;
    c.particles.min = 1.0e-3;
    c.particles.max = 3.0e-3;
    place_ok(&p, &c, lo, hi);
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        assert_true(p.r[i] >= 1.0e-3 && p.r[i] <= 3.0e-3);
        sum += p.r[i];
    }
    double se = (3.0e-3 - 1.0e-3) / sqrt(12.0 * n); /* m; standard error */
    double mean = sum / n;
    if (fabs(mean - 2.0e-3) > 3.0 * se)
        fail_msg("uniform mean %g, expected 2e-3 +- %g", mean, 3.0 * se);
    /* and the shape: the Kolmogorov-Smirnov distance of the sorted radii
     * from F(r) = (r - min)/(max - min) below its 0.1 % critical value,
     * 1.95/sqrt(n) (constant radii, or a triangle on [1, 3] mm, are far
     * beyond it) */
    double *r = malloc((size_t)n * sizeof *r);
    assert_non_null(r);
    memcpy(r, p.r, (size_t)n * sizeof *r);
    qsort(r, (size_t)n, sizeof *r, cmp_double);
    double D = 0.0;
    for (int i = 0; i < n; i++) {
        const double F = (r[i] - 1.0e-3) / 2.0e-3;
        D = fmax(D, fmax(fabs((i + 1.0) / n - F), fabs((double)i / n - F)));
    }
    free(r);
    if (!(D < 1.95 / sqrt((double)n)))
        fail_msg("uniform radii: Kolmogorov-Smirnov distance %g >= %g", D,
                 1.95 / sqrt((double)n));
    dem_particles_free(&p);
}

/* Standard normal density and distribution function. */
static double npdf(double x)
{
    return exp(-0.5 * x * x) / sqrt(2.0 * M_PI);
}
static double ncdf(double x)
{
    return 0.5 * erfc(-x / sqrt(2.0));
}

static void gaussian_radii_follow_the_truncated_normal(void **state)
{
    (void)state;
    const int n = 20000;
    /* A cut close to the mean on both sides, so truncation shifts the
     * mean visibly: (mu, sigma) = (5, 1) mm cut to [4.5, 8] mm. */
    const double mu = 5.0e-3, sd = 1.0e-3, rmin = 4.5e-3, rmax = 8.0e-3;
    struct dem_config c;
    struct dem_particles p;
    double lo[3], hi[3];
    config_defaults(&c, 2, DEM_PLACE_LATTICE, n);
    c.particles.mean = mu;
    c.particles.std = sd;
    c.particles.min = rmin;
    c.particles.max = rmax;
    place_ok(&p, &c, lo, hi);
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; i++) {
        if (!(p.r[i] >= rmin && p.r[i] <= rmax))
            fail_msg("radius %g outside [%g, %g]", p.r[i], rmin, rmax);
        sum += p.r[i];
        sum2 += p.r[i] * p.r[i];
    }
    /* Truncated normal: mean = mu + sd (phi(al) - phi(be)) / Z,
     * var = sd^2 [1 + (al phi(al) - be phi(be)) / Z - ((phi(al) -
     * phi(be)) / Z)^2], Z = Phi(be) - Phi(al). */
    double al = (rmin - mu) / sd, be = (rmax - mu) / sd;
    double Z = ncdf(be) - ncdf(al);
    double shift = (npdf(al) - npdf(be)) / Z;
    double tmean = mu + sd * shift;
    double tvar =
        sd * sd * (1.0 + (al * npdf(al) - be * npdf(be)) / Z - shift * shift);
    double mean = sum / n, var = sum2 / n - mean * mean;
    double se = sqrt(tvar / n);
    if (fabs(mean - tmean) > 4.0 * se)
        fail_msg("gaussian mean %g, truncated-normal mean %g +- %g", mean,
                 tmean, 4.0 * se);
    /* The untruncated mean is far outside that band: the test can tell. */
    assert_true(fabs(mu - tmean) > 20.0 * se);
    assert_true(fabs(var - tvar) < 0.05 * tvar);
    dem_particles_free(&p);
}

/* A gaussian whose max is not given has no upper cut, whatever its
 * size: radii about 1 m (scaled units) keep their mean and spread (a
 * default cut at 1 m made them a half-normal of mean 0.92 m). */
static void gaussian_without_max_is_not_cut(void **state)
{
    (void)state;
    const int n = 20000;
    struct dem_config c;
    struct dem_error err = {0};
    const char *sets[] = {
        "particles.count=20000", "dimension=2", "particles.radius.mean=1.0",
        "particles.radius.std=0.1", "particles.radius.min=0.5"};
    if (dem_config_parse(&c, "", "test", sets, 5, &err))
        fail_msg("%s", err.msg);
    struct dem_particles p;
    double lo[3], hi[3], sum = 0.0, sum2 = 0.0, top = 0.0;
    place_ok(&p, &c, lo, hi);
    for (int i = 0; i < n; i++) {
        sum += p.r[i];
        sum2 += p.r[i] * p.r[i];
        top = p.r[i] > top ? p.r[i] : top;
    }
    const double mean = sum / n, sd = sqrt(sum2 / n - mean * mean);
    if (!(fabs(mean - 1.0) < 4.0 * 0.1 / sqrt(n) && fabs(sd - 0.1) < 0.005))
        fail_msg("mean %g m, spread %g m: not a normal of 1 and 0.1", mean, sd);
    assert_true(top > 1.3);
    dem_particles_free(&p);
}

static void lattice_has_no_overlaps_and_fits_its_box(void **state)
{
    (void)state;
    for (int dim = 2; dim <= 3; dim++) {
        struct dem_config c;
        struct dem_particles p;
        double lo[3], hi[3];
        /* 27 = 3^3 in 3D; 27 needs a 6 x 6 square in 2D. */
        config_defaults(&c, dim, DEM_PLACE_LATTICE, 27);
        place_ok(&p, &c, lo, hi);
        assert_no_overlap_inside(&p, dim, lo, hi);
        double rmax = 0.0;
        for (int i = 0; i < p.n; i++)
            rmax = fmax(rmax, p.r[i]);
        int side = dim == 3 ? 3 : 6;
        double extent = side * 2.0 * rmax * (1.0 + DEM_LATTICE_GAP);
        for (int a = 0; a < dim; a++) {
            assert_true(lo[a] == 0.0);
            assert_true(fabs(hi[a] - extent) < 1e-12 * extent);
        }
        dem_particles_free(&p);

        /* In a given box the lattice sits centred. */
        config_defaults(&c, dim, DEM_PLACE_LATTICE, 400);
        c.box.size[0] = 0.3;
        c.box.size[1] = 0.25;
        c.box.size[2] = dim == 3 ? 0.2 : 0.0;
        c.particles.distribution = DEM_DIST_MONO;
        place_ok(&p, &c, lo, hi);
        assert_no_overlap_inside(&p, dim, lo, hi);
        assert_true(hi[0] == 0.3 && hi[1] == 0.25);
        double xmin = 1.0, xmax = 0.0;
        for (int i = 0; i < p.n; i++) {
            xmin = fmin(xmin, p.x[i]);
            xmax = fmax(xmax, p.x[i]);
        }
        assert_true(fabs(0.5 * (xmin + xmax) - 0.15) < 1e-12);
        dem_particles_free(&p);
    }
}

static void random_placement_has_no_overlaps_in_2d_and_3d(void **state)
{
    (void)state;
    for (int dim = 2; dim <= 3; dim++) {
        struct dem_config c;
        struct dem_particles p;
        double lo[3], hi[3];
        config_defaults(&c, dim, DEM_PLACE_RANDOM, 3000);
        place_ok(&p, &c, lo, hi);
        assert_int_equal(p.n, 3000);
        assert_no_overlap_inside(&p, dim, lo, hi);
        /* The derived box holds the default solid fraction. */
        double vs = 0.0, vbox = 1.0;
        for (int i = 0; i < p.n; i++)
            vs += dim == 3 ? 4.0 / 3.0 * M_PI * pow(p.r[i], 3)
                           : M_PI * p.r[i] * p.r[i];
        for (int a = 0; a < dim; a++)
            vbox *= hi[a] - lo[a];
        double want = dim == 3 ? 0.1 : 0.2;
        assert_true(fabs(vs / vbox - want) < 1e-9);
        dem_particles_free(&p);

        /* A denser box, and a given box with a uniform distribution. */
        config_defaults(&c, dim, DEM_PLACE_RANDOM, 2000);
        c.particles.volume_fraction = dim == 3 ? 0.25 : 0.4;
        place_ok(&p, &c, lo, hi);
        assert_no_overlap_inside(&p, dim, lo, hi);
        dem_particles_free(&p);

        config_defaults(&c, dim, DEM_PLACE_RANDOM, 1000);
        c.particles.distribution = DEM_DIST_UNIFORM;
        c.particles.min = 1e-3;
        c.particles.max = 4e-3;
        c.box.size[0] = 0.4;
        c.box.size[1] = 0.2;
        c.box.size[2] = 0.1;
        place_ok(&p, &c, lo, hi);
        assert_true(hi[0] == 0.4 && hi[1] == 0.2);
        assert_no_overlap_inside(&p, dim, lo, hi);
        dem_particles_free(&p);
    }
}

static void lattice_too_big_for_the_box_names_particles_count(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_particles p;
    struct dem_error err = {0};
    double lo[3], hi[3];
    config_defaults(&c, 3, DEM_PLACE_LATTICE, 1000);
    c.particles.distribution = DEM_DIST_MONO;
    c.box.size[0] = c.box.size[1] = c.box.size[2] = 0.05;
    assert_int_equal(place(&p, &c, lo, hi, &err), DEM_ECONFIG);
    assert_non_null(strstr(err.msg, "particles.count"));
    assert_non_null(strstr(err.msg, "box.size"));
    assert_int_equal(p.n, 0);
    assert_null(p.r);
}

static void impossible_random_placement_is_an_error(void **state)
{
    (void)state;
    for (int dim = 2; dim <= 3; dim++) {
        struct dem_config c;
        struct dem_particles p;
        struct dem_error err = {0};
        double lo[3], hi[3];
        config_defaults(&c, dim, DEM_PLACE_RANDOM, 500);
        c.particles.volume_fraction = 0.9;
        assert_int_equal(place(&p, &c, lo, hi, &err), DEM_ECONFIG);
        assert_non_null(strstr(err.msg, "particles.count"));
        assert_non_null(strstr(err.msg, "could not place"));
        assert_null(strchr(err.msg, '\n'));
        assert_int_equal(p.n, 0);
    }
}

static void bad_radius_parameters_are_errors_not_hangs(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_particles p;
    struct dem_error err = {0};
    double lo[3], hi[3];
    config_defaults(&c, 3, DEM_PLACE_LATTICE, 10);
    c.particles.min = 1.0; /* 1400 standard deviations above the mean */
    c.particles.max = 2.0;
    assert_int_equal(place(&p, &c, lo, hi, &err), DEM_ECONFIG);
    assert_non_null(strstr(err.msg, "particles.radius"));
    config_defaults(&c, 3, DEM_PLACE_LATTICE, 0);
    assert_int_equal(place(&p, &c, lo, hi, &err), DEM_ECONFIG);
    assert_non_null(strstr(err.msg, "particles.count"));
}

static void file_placement_box_from_bounds_or_given(void **state)
{
    (void)state;
    char dir[] = "/tmp/dembox_place_XXXXXX";
    assert_non_null(mkdtemp(dir));
    struct dem_config c;
    struct dem_particles p;
    struct dem_error err = {0};
    double lo[3], hi[3];
    config_defaults(&c, 2, DEM_PLACE_FILE, 0);
    snprintf(c.particles.file, sizeof c.particles.file, "%s/p.csv", dir);
    FILE *f = fopen(c.particles.file, "w");
    assert_non_null(f);
    fputs("x,y,radius\n0.1,0.1,0.01\n0.2,0.15,0.02\n# c\n0.3,0.1,0.01\n", f);
    fclose(f);

    place_ok(&p, &c, lo, hi);
    assert_int_equal(p.n, 3);
    assert_no_overlap_inside(&p, 2, lo, hi);
    /* Bounding box grown by a small margin: particles do not touch. */
    assert_true(lo[0] < 0.09 && lo[0] > 0.089);
    assert_true(hi[1] > 0.17 && hi[1] < 0.171);
    dem_particles_free(&p);

    /* In a box too small the first particle outside is named by line. */
    c.box.size[0] = 0.305;
    c.box.size[1] = 0.5;
    assert_int_equal(place(&p, &c, lo, hi, &err), DEM_ECONFIG);
    char want[2400];
    snprintf(want, sizeof want, "%s:5:", c.particles.file);
    if (strncmp(err.msg, want, strlen(want)) != 0)
        fail_msg("message \"%s\" does not start with \"%s\"", err.msg, want);
    assert_int_equal(p.n, 0);

    c.box.size[0] = 0.4;
    place_ok(&p, &c, lo, hi);
    assert_true(lo[0] == 0.0 && hi[0] == 0.4 && hi[1] == 0.5);
    dem_particles_free(&p);

    /* A periodic cell (a cell's particles_final.csv, whose cell need not
     * start at 0): each centre taken modulo the period, so that a sphere
     * may reach through a face, and one beyond it is its image's place;
     * the pairs' distances through the nearest image stay as they were */
    c.box.boundary = DEM_BOUNDARY_PERIODIC;
    c.box.size[0] = 0.25;
    c.box.size[1] = 0.5;
    place_ok(&p, &c, lo, hi);
    static const double wx[3] = {0.1, 0.2, 0.05}, wy[3] = {0.1, 0.15, 0.1};
    for (int i = 0; i < 3; i++) {
        assert_true(fabs(p.x[i] - wx[i]) < 1e-15);
        assert_true(fabs(p.y[i] - wy[i]) < 1e-15);
    }
    dem_particles_free(&p);
    /* a centre far out: a million periods is taken (into the cell to
     * rounding), beyond that its place in the cell is lost, and it is
     * refused by line (at 1e20 the wrap left it thousands of metres
     * outside, at 1e308 at minus infinity: a fuzzing review, session
     * 112) */
    const char *far[] = {"-2500.1", "1e20", "1e308", "-1e308"};
    for (int k = 0; k < 4; k++) {
        f = fopen(c.particles.file, "w");
        assert_non_null(f);
        fprintf(f, "x,y,radius\n0.1,0.1,0.01\n%s,0.3,0.01\n", far[k]);
        fclose(f);
        if (k == 0) { /* -2500.1 = -10001 L + 0.15 */
            place_ok(&p, &c, lo, hi);
            assert_true(fabs(p.x[1] - 0.15) < 1e-10);
            dem_particles_free(&p);
            continue;
        }
        assert_int_equal(place(&p, &c, lo, hi, &err), DEM_ECONFIG);
        snprintf(want, sizeof want, "%s:3: particle at x = ", c.particles.file);
        if (strncmp(err.msg, want, strlen(want)) != 0 ||
            !strstr(err.msg, "million periods"))
            fail_msg("message \"%s\"", err.msg);
    }
    c.box.boundary = DEM_BOUNDARY_WALLS;

    /* A relative file is relative to the folder dembox runs in; one that
     * lies beside the config file instead is named so in the message */
    char beside[1100];
    snprintf(beside, sizeof beside, "%s/beside-its-config.csv", dir);
    assert_int_equal(rename(c.particles.file, beside), 0);
    snprintf(c.particles.file, sizeof c.particles.file,
             "beside-its-config.csv");
    snprintf(c.source, sizeof c.source, "%s/c.cfg", dir);
    assert_int_equal(place(&p, &c, lo, hi, &err), DEM_EIO);
    snprintf(want, sizeof want,
             "beside-its-config.csv: no such file in the folder dembox runs "
             "in (a relative particles.file is relative to it, not to the "
             "config file's folder); %s exists: give that path",
             beside);
    assert_string_equal(err.msg, want);
    snprintf(c.source, sizeof c.source, "c.cfg"); /* from here: no hint */
    assert_int_equal(place(&p, &c, lo, hi, &err), DEM_EIO);
    assert_non_null(strstr(err.msg, "beside-its-config.csv: cannot open: "));
    remove(beside);
    remove(dir);
}

/* In a periodic cell the random gas fills the cell through its faces:
 * no two particles overlap through the nearest image, every centre is in
 * [0, L), and the centres within a radius of a face are as many as a
 * uniform gas puts there (before, none: an empty band along each face). */
static void random_placement_in_a_cell_fills_it_through_its_faces(void **state)
{
    (void)state;
    for (int dim = 2; dim <= 3; dim++) {
        struct dem_config c;
        struct dem_particles p;
        double lo[3], hi[3];
        /* solid fractions of about 0.3 (2D) and 0.1 */
        config_defaults(&c, dim, DEM_PLACE_RANDOM, dim == 2 ? 150 : 1500);
        c.box.boundary = DEM_BOUNDARY_PERIODIC;
        for (int a = 0; a < 3; a++)
            c.box.size[a] = a < dim ? 0.2 : 0.0;
        place_ok(&p, &c, lo, hi);
        const double L = 0.2;
        int near = 0; /* centres within their radius of an x or y face */
        double want = 0.0;
        for (int i = 0; i < p.n; i++) {
            const double c3[3] = {p.x[i], p.y[i], p.z[i]};
            for (int a = 0; a < dim; a++) {
                assert_true(c3[a] >= 0.0 && c3[a] < L);
                near += c3[a] < p.r[i] || c3[a] > L - p.r[i];
                want += 2.0 * p.r[i] / L;
            }
            for (int j = i + 1; j < p.n; j++) {
                double d2 = 0.0;
                for (int a = 0; a < dim; a++) {
                    const double cj = a == 0   ? p.x[j]
                                      : a == 1 ? p.y[j]
                                               : p.z[j];
                    double d = c3[a] - cj;
                    d -= L * nearbyint(d / L);
                    d2 += d * d;
                }
                const double s = p.r[i] + p.r[j];
                if (!(d2 > s * s))
                    fail_msg("%dD: particles %d and %d overlap through the "
                             "cell's faces",
                             dim, i, j);
            }
        }
        /* a Poisson count: within 5 standard deviations of its mean (15
         * in 2D, 226 in 3D), and not 0 (2D: probability e^-15) */
        if (near == 0 || fabs(near - want) > 5.0 * sqrt(want))
            fail_msg("%dD: %d centres within a radius of a face, a uniform "
                     "gas puts %.1f there",
                     dim, near, want);
        dem_particles_free(&p);
    }
}

/* A particle file's overlap check in a periodic cell counts the pairs
 * through its faces (before, two centres 0.2 mm apart across a face
 * passed, and the run stopped at its first step as unstable); a file
 * that spans more than any box is refused. */
static void file_overlap_through_a_cell_face_is_an_error(void **state)
{
    (void)state;
    char dir[] = "/tmp/dembox_place_XXXXXX";
    assert_non_null(mkdtemp(dir));
    struct dem_config c;
    struct dem_particles p;
    struct dem_error err = {0};
    double lo[3], hi[3];
    config_defaults(&c, 2, DEM_PLACE_FILE, 0);
    c.box.boundary = DEM_BOUNDARY_PERIODIC;
    c.box.size[0] = c.box.size[1] = 0.2;
    snprintf(c.particles.file, sizeof c.particles.file, "%s/p.csv", dir);
    FILE *f = fopen(c.particles.file, "w");
    assert_non_null(f);
    fputs("x,y,radius\n0.0001,0.1,0.005\n0.1,0.1,0.005\n0.1999,0.1002,0.005\n",
          f);
    fclose(f);
    assert_int_equal(place(&p, &c, lo, hi, &err), DEM_ECONFIG);
    if (!strstr(err.msg, "particles 1 and 3 have centres 0.000282843 m apart"))
        fail_msg("message: %s", err.msg);
    /* the same two a cell's width minus 10 mm apart: no overlap */
    f = fopen(c.particles.file, "w");
    assert_non_null(f);
    fputs("x,y,radius\n0.0051,0.1,0.005\n0.1,0.1,0.005\n0.1949,0.1,0.005\n", f);
    fclose(f);
    place_ok(&p, &c, lo, hi);
    assert_int_equal(p.n, 3);
    dem_particles_free(&p);

    /* between walls without box.size, centres whose bounding box is not
     * finite are refused (before, the run began in a box of infinite
     * size, and its first particle's non-finite position was blamed on
     * the time step) */
    c.box.boundary = DEM_BOUNDARY_WALLS;
    c.box.size[0] = c.box.size[1] = 0.0;
    f = fopen(c.particles.file, "w");
    assert_non_null(f);
    fputs("x,y,radius\n-1e308,0,0.001\n1e308,0,0.001\n", f);
    fclose(f);
    assert_int_equal(place(&p, &c, lo, hi, &err), DEM_ECONFIG);
    if (!strstr(err.msg, "the particles span more than any box along x"))
        fail_msg("message: %s", err.msg);
    remove(c.particles.file);
    remove(dir);
}

/* A box that holds the lattice only without its gap (a crystal of
 * touching particles) takes it at the spacing that fits: 100 discs of
 * radius 5 mm in 0.1 m x 0.1 m, 1000 spheres in a cell of 0.1 m. Before,
 * it was refused, naming a lattice of "0.1 m per side" for a box.size of
 * [0.1, 0.1]. */
static void lattice_fits_a_box_of_touching_particles(void **state)
{
    (void)state;
    for (int dim = 2; dim <= 3; dim++) {
        struct dem_config c;
        struct dem_particles p;
        double lo[3], hi[3];
        config_defaults(&c, dim, DEM_PLACE_LATTICE, dim == 2 ? 100 : 1000);
        c.particles.distribution = DEM_DIST_MONO;
        if (dim == 3)
            c.box.boundary = DEM_BOUNDARY_PERIODIC;
        for (int a = 0; a < dim; a++)
            c.box.size[a] = 0.1;
        place_ok(&p, &c, lo, hi);
        assert_true(fabs(p.x[1] - p.x[0] - 0.01) < 1e-15);
        for (int i = 0; i < p.n; i++) {
            const double c3[3] = {p.x[i], p.y[i], p.z[i]};
            for (int a = 0; a < dim; a++)
                assert_true(c3[a] - p.r[i] >= -1e-15 &&
                            c3[a] + p.r[i] <= 0.1 + 1e-15);
        }
        dem_particles_free(&p);
        /* a box a part in 10^9 narrower is refused with what it needs */
        struct dem_error err = {0};
        c.box.size[0] = 0.1 * (1.0 - 1e-9);
        assert_int_equal(place(&p, &c, lo, hi, &err), DEM_ECONFIG);
        assert_non_null(strstr(err.msg, "need a lattice of 0.1 m per side"));
    }
}

/* A particle wider than a given box along one axis is named as such,
 * not as an overlap after a thousand tries. */
static void a_particle_wider_than_the_box_is_named(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_particles p;
    struct dem_error err = {0};
    double lo[3], hi[3];
    config_defaults(&c, 3, DEM_PLACE_RANDOM, 10);
    c.box.size[0] = c.box.size[1] = 0.2;
    c.box.size[2] = 0.008; /* the largest radius is above 4 mm */
    assert_int_equal(place(&p, &c, lo, hi, &err), DEM_ECONFIG);
    if (!strstr(err.msg, "box.size: a particle of radius") ||
        !strstr(err.msg, "is wider than the box along z"))
        fail_msg("message: %s", err.msg);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(same_seed_gives_same_radii_and_positions),
        cmocka_unit_test(uniform_radii_have_the_midpoint_mean),
        cmocka_unit_test(gaussian_radii_follow_the_truncated_normal),
        cmocka_unit_test(gaussian_without_max_is_not_cut),
        cmocka_unit_test(lattice_has_no_overlaps_and_fits_its_box),
        cmocka_unit_test(random_placement_has_no_overlaps_in_2d_and_3d),
        cmocka_unit_test(lattice_too_big_for_the_box_names_particles_count),
        cmocka_unit_test(impossible_random_placement_is_an_error),
        cmocka_unit_test(bad_radius_parameters_are_errors_not_hangs),
        cmocka_unit_test(file_placement_box_from_bounds_or_given),
        cmocka_unit_test(random_placement_in_a_cell_fills_it_through_its_faces),
        cmocka_unit_test(file_overlap_through_a_cell_face_is_an_error),
        cmocka_unit_test(lattice_fits_a_box_of_touching_particles),
        cmocka_unit_test(a_particle_wider_than_the_box_is_named),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
