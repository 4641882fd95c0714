/* Domain decomposition (src/decomp) and contact records
 * (neighbor/records.h), in one process: the grid is chosen from the rank
 * count and the box, a subdomain narrower than the ghost range is
 * refused, every ghost lies near a face of its subdomain and between
 * near subdomains (what halo.c searches), the records restore every
 * contact after an arbitrary shuffle of the particles, and a sample split
 * into subdomains with their ghosts gives every particle the force and
 * torque of the undivided sample. */
#include "testutil.h"

#include <math.h>
#include <stdlib.h>

#include "core/rng.h"
#include "decomp/decomp.h"
#include "neighbor/records.h"

static void grid_follows_the_box(void **state)
{
    (void)state;
    struct dem_decomp d;
    struct dem_error err = {0};
    const double lo[3] = {0, 0, 0};
    const double cube[3] = {1, 1, 1}, rod[3] = {4, 1, 1}, flat[3] = {3, 2, 0};
    const struct {
        int ranks, dim;
        const double *hi;
        int np[3];
    } cases[] = {
        {1, 3, cube, {1, 1, 1}}, {2, 3, cube, {2, 1, 1}},
        {4, 3, cube, {2, 2, 1}}, {8, 3, cube, {2, 2, 2}},
        {4, 3, rod, {4, 1, 1}},  {8, 3, rod, {8, 1, 1}},
        {6, 2, flat, {3, 2, 1}}, {3, 2, flat, {3, 1, 1}},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        assert_int_equal(dem_decomp_grid(&d, cases[k].ranks, cases[k].dim, lo,
                                         cases[k].hi, 0.1, &err),
                         0);
        for (int a = 0; a < 3; a++)
            assert_int_equal(d.np[a], cases[k].np[a]);
    }
    /* every point has one owner, inside its bounds */
    assert_int_equal(dem_decomp_grid(&d, 8, 3, lo, rod, 0.1, &err), 0);
    struct dem_rng g;
    dem_rng_seed(&g, 3);
    for (int k = 0; k < 1000; k++) {
        const double x[3] = {-0.1 + 4.2 * dem_rng_uniform(&g),
                             -0.1 + 1.2 * dem_rng_uniform(&g),
                             -0.1 + 1.2 * dem_rng_uniform(&g)};
        const int r = dem_decomp_owner(&d, x);
        assert_true(r >= 0 && r < 8);
        double bl[3], bh[3];
        dem_decomp_bounds(&d, r, bl, bh);
        for (int a = 0; a < 3; a++)
            assert_true(x[a] >= bl[a] - 1e-12 && x[a] <= bh[a] + 1e-12);
        assert_true(dem_decomp_is_ghost(&d, r, x));
        /* halo.c looks for ghosts only near a face, among near ranks */
        for (int o = 0; o < 8; o++)
            if (o != r && dem_decomp_is_ghost(&d, o, x))
                assert_true(dem_decomp_near(&d, r, o) &&
                            dem_decomp_at_face(&d, r, x));
    }
    /* a position far outside goes to the slab at its side, NaN (a
     * blow-up between checks) to the first: no conversion to an int out
     * of its range */
    const double far[3] = {1e300, 0.5, 0.5}, back[3] = {-1e300, 0.5, 0.5},
                 nan3[3] = {NAN, NAN, NAN};
    assert_int_equal(dem_decomp_owner(&d, far), 7);
    assert_int_equal(dem_decomp_owner(&d, back), 0);
    assert_int_equal(dem_decomp_owner(&d, nan3), 0);
    /* 8 slabs 0.5 wide along the rod, range 0.1: each is near its two
     * neighbours only; a point 0.05 from a cut is at a face, one in the
     * middle of a slab or 0.05 from a wall is not */
    for (int a = 0; a < 8; a++)
        for (int b = 0; b < 8; b++)
            if (a != b)
                assert_int_equal(dem_decomp_near(&d, a, b), abs(a - b) == 1);
    const double cut[3] = {0.55, 0.5, 0.5}, mid[3] = {0.75, 0.5, 0.5},
                 wall[3] = {0.05, 0.5, 0.5};
    assert_true(dem_decomp_at_face(&d, 1, cut));
    assert_false(dem_decomp_at_face(&d, 1, mid));
    assert_false(dem_decomp_at_face(&d, 0, wall));
    /* 64 ranks in a box 0.5 wide: subdomains of 0.125 at best, range
     * 0.2: refused, naming the range */
    const double small[3] = {0.5, 0.5, 0.5};
    assert_int_equal(dem_decomp_grid(&d, 64, 3, lo, small, 0.2, &err),
                     DEM_EUSAGE);
    assert_non_null(strstr(err.msg, "ghost range 0.2 m"));
    /* a box that shrinks under its grid: 4 slabs of 0.4 would be
     * narrower than the range, 2 x 2 fits; shrunk further, none fits */
    assert_int_equal(dem_decomp_grid(&d, 4, 3, lo, rod, 0.5, &err), 0);
    const double shrunk[3] = {1.6, 1, 1}, tiny[3] = {0.9, 0.9, 0.9};
    assert_int_equal(dem_decomp_resize(&d, lo, shrunk, &err), 1);
    assert_int_equal(d.np[0] * 10 + d.np[1] * 100 + d.np[2], 2 * 10 + 200 + 1);
    assert_int_equal(dem_decomp_resize(&d, lo, tiny, &err), DEM_EUSAGE);
    assert_non_null(strstr(err.msg, "ghost range 0.5 m"));
    /* a box whose shape changes: the grid follows only when another one
     * cuts 10 % less (2 ranks in 2D: one cut across the longer side) */
    const double square[3] = {1, 1, 0}, taller[3] = {1, 1.05, 0},
                 tall[3] = {1, 1.2, 0};
    assert_int_equal(dem_decomp_grid(&d, 2, 2, lo, square, 0.1, &err), 0);
    assert_int_equal(d.np[0], 2);
    assert_int_equal(dem_decomp_resize(&d, lo, taller, &err), 0);
    assert_int_equal(d.np[0], 2);
    assert_int_equal(dem_decomp_resize(&d, lo, tall, &err), 1);
    assert_int_equal(d.np[1], 2);
    assert_int_equal(dem_decomp_resize(&d, lo, square, &err), 0);
    assert_int_equal(d.np[1], 2);
    assert_true(fabs(d.hi[1] - 1.0) < 1e-15);
}

/* A frictional sample with rolling and torsion resistance, stepped so
 * that its contacts carry history; walls at 0 and 0.1. */
static void sample(struct dem_sim *s, int dim, int n)
{
    struct dem_config c;
    test_config(&c, dim);
    c.contact.rolling = DEM_RESIST_LUDING;
    c.contact.kr = 500.0;
    c.contact.mu_r = c.contact.wall_mu_r = 0.1;
    if (dim == 3) {
        c.contact.torsion = DEM_RESIST_LUDING;
        c.contact.ko = 200.0;
        c.contact.mu_o = c.contact.wall_mu_o = 0.1;
    }
    c.contact.wall_mu = 0.3;
    test_sim(s, &c, n, 0.0, 0.1);
    struct dem_rng g;
    dem_rng_seed(&g, 11 + dim);
    for (int i = 0; i < n; i++) {
        const double r = 3e-3 + 2e-3 * dem_rng_uniform(&g);
        test_add(s, 0.1 * dem_rng_uniform(&g), 0.1 * dem_rng_uniform(&g),
                 dim == 3 ? 0.1 * dem_rng_uniform(&g) : 0.0, r);
    }
    for (int i = 0; i < n; i++) {
        s->p.vx[i] = 0.02 * (dem_rng_uniform(&g) - 0.5);
        s->p.vy[i] = 0.02 * (dem_rng_uniform(&g) - 0.5);
        s->p.wz[i] = 4.0 * (dem_rng_uniform(&g) - 0.5);
        if (dim == 3) {
            s->p.vz[i] = 0.02 * (dem_rng_uniform(&g) - 0.5);
            s->p.wx[i] = 4.0 * (dem_rng_uniform(&g) - 0.5);
        }
    }
    test_ready(s);
    test_step(s, 30);
    /* a fresh list, as a subdomain's build makes */
    struct dem_error err = {0};
    assert_int_equal(dem_sim_rebuild(s, &err), 0);
    dem_sim_forces(s);
}

/* A new simulation with the configuration and walls of s holding the
 * particles list[0..n) of s in that order, the first nown its own. */
static void part_of(struct dem_sim *t, const struct dem_sim *s, const int *list,
                    int n, int nown)
{
    double lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = s->wall[2 * a].pos;
        hi[a] = a < s->dim ? s->wall[2 * a + 1].pos : 0.0;
    }
    struct dem_error err = {0};
    assert_int_equal(dem_sim_create_empty(t, &s->cfg, n, lo, hi, &err), 0);
    for (int k = 0; k < n; k++)
        assert_true(dem_particles_append_copy(&t->p, &s->p, list[k]) == k);
    t->pairs.nghost = n - nown;
    test_ready(t);
    /* the skin of the whole sample, not of the part's mean radius, and
     * its particles' reaches (a subdomain's ghosts bring their owners') */
    t->skin = s->skin;
    for (int k = 0; k < n; k++)
        t->p.reach[k] = s->p.reach[list[k]];
    assert_int_equal(dem_sim_derive(t, &err), 0);
    assert_int_equal(dem_sim_rebuild(t, &err), 0);
}

/* Force and torque on particle i of t equal those on the particle of the
 * same id in s (to 1e-12 of the largest). */
static void same_forces(const struct dem_sim *t, int n, const struct dem_sim *s)
{
    int *at = malloc((size_t)s->p.n * sizeof *at);
    double fmax = 0.0, tmax = 0.0;
    for (int i = 0; i < s->p.n; i++) {
        at[s->p.id[i]] = i;
        fmax = fmax > fabs(s->p.fx[i]) ? fmax : fabs(s->p.fx[i]);
        tmax = tmax > fabs(s->p.tz[i]) ? tmax : fabs(s->p.tz[i]);
    }
    for (int i = 0; i < n; i++) {
        const int q = at[t->p.id[i]];
        assert_true(fabs(t->p.fx[i] - s->p.fx[q]) <= 1e-12 * fmax);
        assert_true(fabs(t->p.fy[i] - s->p.fy[q]) <= 1e-12 * fmax);
        assert_true(fabs(t->p.fz[i] - s->p.fz[q]) <= 1e-12 * fmax);
        assert_true(fabs(t->p.tx[i] - s->p.tx[q]) <= 1e-12 * tmax);
        assert_true(fabs(t->p.ty[i] - s->p.ty[q]) <= 1e-12 * tmax);
        assert_true(fabs(t->p.tz[i] - s->p.tz[q]) <= 1e-12 * tmax);
    }
    free(at);
}

/* The particles shuffled at random into a new simulation: without the
 * records the forces differ (the springs are lost), with them they are
 * the same. */
static void records_survive_a_shuffle(void **state)
{
    (void)state;
    for (int dim = 2; dim <= 3; dim++) {
        struct dem_sim s;
        const int n = dim == 3 ? 500 : 300;
        sample(&s, dim, n);
        int active = 0;
        for (int k = 0; k < s.pairs.cur.n; k++)
            active += s.pairs.cur.state[k] != 0;
        assert_true(active > 50);
        struct dem_records r = {0};
        assert_int_equal(dem_records_export(&r, &s.pairs, &s.p, s.p.n), 0);
        dem_records_sort(&r);
        int *list = malloc((size_t)n * sizeof *list);
        for (int i = 0; i < n; i++)
            list[i] = i;
        struct dem_rng g;
        dem_rng_seed(&g, 7);
        for (int i = n - 1; i > 0; i--) {
            int k = (int)(dem_rng_uniform(&g) * (i + 1));
            k = k > i ? i : k;
            const int t = list[i];
            list[i] = list[k];
            list[k] = t;
        }
        struct dem_sim t;
        part_of(&t, &s, list, n, n);
        dem_sim_forces(&t);
        double diff = 0.0;
        for (int i = 0; i < n; i++)
            diff += fabs(t.p.fx[i] - s.p.fx[list[i]]);
        assert_true(diff > 1e-6); /* the springs matter */
        dem_records_import(&r, &t.pairs, &t.p);
        dem_sim_forces(&t);
        same_forces(&t, n, &s);
        dem_sim_destroy(&t);
        dem_records_free(&r);
        free(list);
        dem_sim_destroy(&s);
    }
}

/* The sample split over K subdomains: each takes its own particles and
 * its ghosts and the records of its own particles' contacts; every own
 * particle then feels the force of the undivided sample, and every pair
 * of the sample is listed once in the subdomain of its particles or in
 * both subdomains of a pair across a cut. */
static void split(int dim, int nranks)
{
    struct dem_sim s;
    const int n = dim == 3 ? 1500 : 800;
    sample(&s, dim, n);
    double lo[3], hi[3], rmax = 0.0;
    for (int a = 0; a < 3; a++) {
        lo[a] = s.wall[2 * a].pos;
        hi[a] = a < dim ? s.wall[2 * a + 1].pos : 0.0;
    }
    for (int i = 0; i < n; i++)
        rmax = rmax > s.p.r[i] ? rmax : s.p.r[i];
    struct dem_decomp d;
    struct dem_error err = {0};
    assert_int_equal(
        dem_decomp_grid(&d, nranks, dim, lo, hi, 2 * rmax + s.skin, &err), 0);
    int *list = malloc((size_t)n * sizeof *list);
    long owned = 0, listed = 0, ghost_pairs = 0;
    for (int rank = 0; rank < nranks; rank++) {
        int nown, nghost;
        dem_decomp_select(&d, rank, &s.p, list, &nown, &nghost);
        assert_true(nown > 0 && nghost > 0);
        owned += nown;
        /* the records of the own particles' contacts, as the particles
         * would bring them */
        struct dem_records all = {0}, r = {0};
        assert_int_equal(dem_records_export(&all, &s.pairs, &s.p, s.p.n), 0);
        char *own = calloc((size_t)n, 1);
        for (int k = 0; k < nown; k++)
            own[s.p.id[list[k]]] = 1;
        r.v = malloc((size_t)(all.n > 0 ? all.n : 1) * sizeof *r.v);
        r.cap = all.n;
        for (int k = 0; k < all.n; k++)
            if (own[all.v[k].self])
                r.v[r.n++] = all.v[k];
        dem_records_sort(&r);
        struct dem_sim t;
        part_of(&t, &s, list, nown + nghost, nown);
        dem_records_import(&r, &t.pairs, &t.p);
        dem_sim_forces(&t);
        same_forces(&t, nown, &s);
        listed += t.pairs.cur.n;
        for (int k = 0; k < t.pairs.cur.n; k++)
            ghost_pairs += t.pairs.cur.j[k] >= nown;
        dem_records_free(&r);
        dem_records_free(&all);
        free(own);
        dem_sim_destroy(&t);
    }
    assert_int_equal(owned, n);
    /* pairs across a cut are listed twice */
    assert_true(ghost_pairs > 0 && ghost_pairs % 2 == 0);
    assert_int_equal(listed - ghost_pairs / 2, s.pairs.cur.n);
    free(list);
    dem_sim_destroy(&s);
}

static void split_gives_the_same_forces(void **state)
{
    (void)state;
    split(2, 2);
    split(2, 6);
    split(3, 4);
    split(3, 8);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(grid_follows_the_box),
        cmocka_unit_test(records_survive_a_shuffle),
        cmocka_unit_test(split_gives_the_same_forces),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
