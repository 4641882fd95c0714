/* Linked cells find exactly the pairs brute force finds, for polydisperse
 * radii in 2D and 3D, and the contact history survives a rebuild. */
#include "testutil.h"

#include <stdlib.h>

#include "contact/tangential.h"
#include "core/rng.h"

static int cmp_pair(const void *a, const void *b)
{
    const long *x = a, *y = b;
    return (*x > *y) - (*x < *y);
}

static void check_same_pairs(int dim, int reorder)
{
    struct dem_config c;
    test_config(&c, dim);
    struct dem_sim s;
    const int n = 1500;
    test_sim(&s, &c, n, 0.0, 0.2);
    s.reorder = reorder;
    struct dem_rng g;
    dem_rng_seed(&g, 99 + dim);
    for (int i = 0; i < n; i++) {
        /* radii spread over a factor 6; positions may overlap and poke
         * through the walls */
        double r = 1e-3 + 5e-3 * dem_rng_uniform(&g);
        double z = dim == 3 ? -0.01 + 0.22 * dem_rng_uniform(&g) : 0.0;
        test_add(&s, -0.01 + 0.22 * dem_rng_uniform(&g),
                 -0.01 + 0.22 * dem_rng_uniform(&g), z, r);
    }
    test_ready(&s);
    for (int round = 0; round < 2; round++) {
        int *bi, *bj;
        int nb = dem_pairs_brute(&s.p, dim, s.skin, NULL, &bi, &bj, NULL);
        assert_true(nb > 100);
        const struct dem_contact_list *L = &s.pairs.cur;
        assert_int_equal(L->n, nb);
        long *a = malloc((size_t)nb * sizeof *a),
             *b = malloc((size_t)nb * sizeof *b);
        for (int k = 0; k < nb; k++) {
            a[k] = (long)bi[k] * n + bj[k];
            b[k] = (long)L->i[k] * n + L->j[k];
            assert_true(L->i[k] < L->j[k]);
        }
        qsort(a, (size_t)nb, sizeof *a, cmp_pair);
        /* the list is kept sorted by (i, j), which the history merge needs */
        for (int k = 1; k < nb; k++)
            assert_true(b[k - 1] < b[k]);
        for (int k = 0; k < nb; k++)
            assert_true(a[k] == b[k]);
        free(a);
        free(b);
        free(bi);
        free(bj);
        /* move everything a little and build again */
        for (int i = 0; i < n; i++) {
            s.p.x[i] += 2e-3 * (dem_rng_uniform(&g) - 0.5);
            s.p.y[i] += 2e-3 * (dem_rng_uniform(&g) - 0.5);
        }
        struct dem_error err;
        assert_int_equal(dem_sim_rebuild(&s, &err), 0);
    }
    dem_sim_destroy(&s);
}

static void cells_find_brute_force_pairs_3d(void **state)
{
    (void)state;
    check_same_pairs(3, 0);
    check_same_pairs(3, 1);
}

static void cells_find_brute_force_pairs_2d(void **state)
{
    (void)state;
    check_same_pairs(2, 0);
    check_same_pairs(2, 1);
}

/* Re-ordering the particles in cell order changes no force: a pair whose
 * particles swap places in memory (i < j turns into j < i) keeps its
 * springs as seen from each particle, so the force and torque on every
 * particle (found by its id) are the same before and after a rebuild that
 * permutes the particles, up to the order of summation. The tangential
 * and torsion springs change sign with the pair's orientation, the
 * rolling spring does not (contact/resistance.h). */
static void forces_survive_reordering(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 3);
    c.contact.rolling = DEM_RESIST_LUDING;
    c.contact.kr = 500.0;
    c.contact.mu_r = c.contact.wall_mu_r = 0.1;
    c.contact.torsion = DEM_RESIST_LUDING;
    c.contact.ko = 200.0;
    c.contact.mu_o = c.contact.wall_mu_o = 0.1;
    struct dem_sim s;
    const int n = 400;
    test_sim(&s, &c, n, 0.0, 0.1);
    struct dem_rng g;
    dem_rng_seed(&g, 5);
    for (int i = 0; i < n; i++)
        test_add(&s, 0.1 * dem_rng_uniform(&g), 0.1 * dem_rng_uniform(&g),
                 0.1 * dem_rng_uniform(&g), 6e-3);
    for (int i = 0; i < n; i++) {
        s.p.vx[i] = 0.01 * (dem_rng_uniform(&g) - 0.5);
        s.p.vy[i] = 0.01 * (dem_rng_uniform(&g) - 0.5);
        s.p.wz[i] = 2.0 * (dem_rng_uniform(&g) - 0.5);
        s.p.wx[i] = 2.0 * (dem_rng_uniform(&g) - 0.5);
    }
    test_ready(&s);
    test_step(&s, 20);
    dem_sim_forces(&s);
    double *f = malloc((size_t)6 * n * sizeof *f);
    double scale = 0.0;
    for (int i = 0; i < n; i++) {
        const double v[6] = {s.p.fx[i], s.p.fy[i], s.p.fz[i],
                             s.p.tx[i], s.p.ty[i], s.p.tz[i]};
        for (int k = 0; k < 6; k++) {
            f[6 * s.p.id[i] + k] = v[k];
            scale = fmax(scale, fabs(v[k]));
        }
    }
    const struct dem_contact_list *L = &s.pairs.cur;
    int active = 0;
    for (int k = 0; k < L->n; k++)
        active += L->state[k] != 0;
    assert_true(active > 20);
    s.reorder = 1;
    struct dem_error err;
    assert_int_equal(dem_sim_rebuild(&s, &err), 0);
    /* the order changed, also within pairs ... */
    int moved = 0, flipped = 0;
    for (int i = 0; i < n; i++)
        moved += s.p.id[i] != i;
    for (int k = 0; k < L->n; k++)
        flipped += L->state[k] && s.p.id[L->i[k]] > s.p.id[L->j[k]];
    assert_true(moved > n / 2);
    assert_true(flipped > 5);
    /* ... the forces did not */
    dem_sim_forces(&s);
    for (int i = 0; i < n; i++) {
        const double v[6] = {s.p.fx[i], s.p.fy[i], s.p.fz[i],
                             s.p.tx[i], s.p.ty[i], s.p.tz[i]};
        for (int k = 0; k < 6; k++)
            assert_true(fabs(v[k] - f[6 * s.p.id[i] + k]) <= 1e-12 * scale);
    }
    free(f);
    dem_sim_destroy(&s);
}

/* A contact's tangential spring and dmax are carried over a rebuild. */
static void history_survives_rebuild(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 3);
    struct dem_sim s;
    test_sim(&s, &c, 4, 0.0, 0.1);
    test_add(&s, 0.03, 0.05, 0.05, 5e-3);
    test_add(&s, 0.0399, 0.05, 0.05, 5e-3);
    test_add(&s, 0.07, 0.05, 0.05, 5e-3);
    test_add(&s, 0.0799, 0.05, 0.05, 5e-3);
    s.p.vy[0] = 1e-3;
    test_ready(&s);
    test_step(&s, 10);
    const struct dem_contact_list *L = &s.pairs.cur;
    assert_int_equal(L->n, 2);
    double xi = L->xi_y[0];
    assert_true(xi != 0.0);
    struct dem_error err;
    assert_int_equal(dem_sim_rebuild(&s, &err), 0);
    assert_int_equal(L->n, 2);
    assert_true(L->xi_y[0] == xi);
    assert_true(L->state[0] & DEM_CONTACT_ACTIVE);
    dem_sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cells_find_brute_force_pairs_3d),
        cmocka_unit_test(cells_find_brute_force_pairs_2d),
        cmocka_unit_test(history_survives_rebuild),
        cmocka_unit_test(forces_survive_reordering),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
