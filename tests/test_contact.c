/* Contact laws against analytic results: head-on collisions (contact
 * duration and restitution, pair and wall), the Coulomb limit with static
 * and dynamic friction, and the rolling sphere that checks the torque sign
 * and the tangential law. */
#include "testutil.h"

#include "contact/tangential.h"

/* omega = sqrt(k/m - eta^2), eta = gamma/(2m), t_c = pi/omega, r = exp(-eta
 * t_c) */
static void analytic(double k, double gamma, double m, double *tc, double *r)
{
    double eta = gamma / (2.0 * m);
    double w = sqrt(k / m - eta * eta);
    *tc = M_PI / w;
    *r = exp(-eta * *tc);
}

static double mass(double a)
{
    return 4.0 / 3.0 * M_PI * 2000.0 * a * a * a;
}

/* Two spheres of radii 5 mm and 3.5 mm (mass ratio 2.9) approach head-on. */
static void pair_collision_matches_analytic_tc_and_r(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 3);
    c.contact.gamma_n = 0.05;
    const double a1 = 5e-3, a2 = 3.5e-3, v0 = 0.2;
    const double m1 = mass(a1), m2 = mass(a2), mij = m1 * m2 / (m1 + m2);
    double tc, r;
    analytic(c.contact.k, c.contact.gamma_n, mij, &tc, &r);
    c.time_step = tc / 2000.0;
    struct dem_sim s;
    test_sim(&s, &c, 2, -0.1, 0.1);
    test_add(&s, -a1 - 1e-5, 0, 0, a1);
    test_add(&s, a2 + 1e-5, 0, 0, a2);
    s.p.vx[0] = v0 * m2 / (m1 + m2);
    s.p.vx[1] = -v0 * m1 / (m1 + m2);
    test_ready(&s);
    double t_in = -1, t_out = -1;
    for (long k = 0; k < 200000 && t_out < 0; k++) {
        test_step(&s, 1);
        double gap = s.p.x[1] - s.p.x[0] - a1 - a2;
        if (gap < 0 && t_in < 0)
            t_in = s.t;
        if (gap >= 0 && t_in >= 0)
            t_out = s.t;
    }
    assert_true(t_out > 0);
    double vrel = s.p.vx[1] - s.p.vx[0];
    /* the contact times are known to one step */
    assert_close(t_out - t_in, tc, 1.5 * c.time_step);
    assert_rel(vrel / v0, r, 2e-3);
    /* momentum is conserved exactly by the pair force */
    assert_close(m1 * s.p.vx[0] + m2 * s.p.vx[1], 0.0, 1e-15);
    dem_sim_destroy(&s);
}

/* A sphere hits the fixed x-min wall: the wall is a partner of infinite
 * mass, m_ij = m. */
static void wall_collision_matches_analytic_tc_and_r(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 3);
    c.contact.gamma_n = 0.05;
    const double a = 5e-3, v0 = 0.2, m = mass(a);
    double tc, r;
    analytic(c.contact.k, c.contact.gamma_n, m, &tc, &r);
    c.time_step = tc / 2000.0;
    struct dem_sim s;
    test_sim(&s, &c, 1, 0.0, 0.1);
    test_add(&s, a + 1e-5, 0.05, 0.05, a);
    s.p.vx[0] = -v0;
    test_ready(&s);
    double t_in = -1, t_out = -1;
    for (long k = 0; k < 200000 && t_out < 0; k++) {
        test_step(&s, 1);
        double gap = s.p.x[0] - a;
        if (gap < 0 && t_in < 0)
            t_in = s.t;
        if (gap >= 0 && t_in >= 0)
            t_out = s.t;
    }
    assert_true(t_out > 0);
    assert_close(t_out - t_in, tc, 1.5 * c.time_step);
    assert_rel(s.p.vx[0] / v0, r, 2e-3);
    dem_sim_destroy(&s);
}

/* Kernel-level Coulomb test: a contact with a fixed normal force is driven
 * tangentially at constant speed, then backwards. It sticks with f = k_t xi
 * until |f| exceeds mu_s f_n, slides with |f| = mu_d f_n, and sticks again
 * when the drive reverses, with the force then falling linearly. */
static void coulomb_limit_stick_slip_and_back(void **state)
{
    (void)state;
    const struct dem_tangential T = {1000.0, 0.0, 0.6, 0.4};
    const struct dem_vec3 n = {0, 0, 1};
    const double fn = 1.0, dt = 1e-3, v = 1e-5;
    struct dem_vec3 xi = {0, 0, 0}, ft;
    int st = DEM_CONTACT_ACTIVE;
    struct dem_vec3 vij = {v, 0, 0};
    int first_slide = -1;
    double fmax = 0.0;
    for (int k = 0; k < 100000; k++) {
        /* force if it sticks: the spring stretched by this step */
        double expect_static = -T.kt * (xi.x + v * dt);
        ft = dem_tangential_force(n, vij, fn, dt, &T, &xi, &st);
        double f = fabs(ft.x);
        fmax = f > fmax ? f : fmax;
        assert_true(f <= T.mu_s * fn + 1e-12);
        if (st & DEM_CONTACT_SLIDING) {
            /* sliding: exactly the dynamic limit */
            assert_close(f, T.mu_d * fn, 1e-12);
            if (first_slide < 0) {
                first_slide = k;
                /* the test force has just exceeded mu_s f_n */
                assert_true(fabs(expect_static) > T.mu_s * fn);
                assert_true(fabs(expect_static) - T.kt * v * dt <=
                            T.mu_s * fn + 1e-12);
            }
        } else {
            assert_close(ft.x, expect_static, 1e-12);
        }
        assert_close(ft.y, 0.0, 0.0);
    }
    assert_true(first_slide > 0);
    assert_close(fmax, T.mu_s * fn, T.kt * v * dt + 1e-12);
    /* reverse the drive: the contact sticks and the force rises linearly
     * from where it was, through zero, up to +mu_s f_n, where it slides */
    vij.x = -v;
    const double f_end = ft.x;
    double prev = f_end;
    int k_slide = -1;
    for (int k = 0; k < 200000 && k_slide < 0; k++) {
        ft = dem_tangential_force(n, vij, fn, dt, &T, &xi, &st);
        if (st & DEM_CONTACT_SLIDING) {
            k_slide = k;
            assert_close(ft.x, T.mu_d * fn, 1e-12);
        } else {
            /* every step, the first one too, stretches the spring by
             * v dt before the force: no lag behind the drive */
            assert_close(ft.x - prev, T.kt * v * dt, 1e-12);
            prev = ft.x;
        }
    }
    assert_true(f_end < 0.0);
    double expect = (T.mu_s * fn - f_end) / (T.kt * v * dt);
    assert_close((double)k_slide, expect, 1.0);
}

/* A sphere launched sliding without spin on a frictional floor ends
 * rolling at 5/7 of its speed, with a w = v (Coulomb friction decelerates
 * it while its torque spins it up). */
static void sliding_sphere_ends_rolling_at_five_sevenths(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 3);
    c.gravity[2] = -9.81;
    c.contact.gamma_n = 0.05;
    c.contact.wall_mu = 0.4;
    /* tangential viscosity damps the spring's oscillation once it rolls
     * (it does not change the sliding force, mu_d f_n exactly) */
    c.contact.gamma_t = 0.05;
    c.time_step = 2e-6;
    const double a = 5e-3, v0 = 0.1, m = mass(a);
    struct dem_sim s;
    test_sim(&s, &c, 1, 0.0, 1.0);
    test_add(&s, 0.1, 0.5, a - m * 9.81 / c.contact.k, a);
    s.p.vx[0] = v0;
    test_ready(&s);
    /* sliding lasts 2 v0 / (7 mu g) = 7.3 ms; then the spring relaxes */
    test_step(&s, 25000);
    double v = s.p.vx[0], w = s.p.wy[0];
    assert_rel(v, 5.0 / 7.0 * v0, 5e-3);
    /* rolling in +x on a floor below: w_y = +v/a */
    assert_rel(a * w, v, 5e-3);
    assert_close(s.p.vy[0], 0.0, 1e-12);
    dem_sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(pair_collision_matches_analytic_tc_and_r),
        cmocka_unit_test(wall_collision_matches_analytic_tc_and_r),
        cmocka_unit_test(coulomb_limit_stick_slip_and_back),
        cmocka_unit_test(sliding_sphere_ends_rolling_at_five_sevenths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
