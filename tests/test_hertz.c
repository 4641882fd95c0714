/* The Hertz-Mindlin model (contact/model_hertz.h) through the whole
 * engine: head-on collisions of two equal spheres and of a sphere with a
 * wall, against Hertz's contact time and the restitution asked for.
 *
 * Spheres a = 5 mm, rho = 2000 kg/m^3 (m = 1.0472e-3 kg), E = 1e7 Pa,
 * nu = 0.25: E* = E / (2 (1 - nu^2)) = 5.3333e6 Pa; a pair has
 * R* = a/2, m* = m/2, a sphere on a wall R* = a, m* = m. An elastic
 * collision at relative speed v lasts t_c = 2.868 (m*^2/(R* E*^2 v))^(1/5)
 * (from 1/2 m* v^2 = 2/5 K delta_max^(5/2), K = 4/3 E* sqrt(R*), and
 * t_c = 2.9432 delta_max / v): 1.1486 ms for the pair at 1 m/s.
 */
#include "testutil.h"

#include "contact/models.h"

#define A 5e-3

static void hertz_config(struct dem_config *c, double e)
{
    test_config(c, 3);
    c->time_step = 1e-6;
    c->contact.normal = DEM_NORMAL_HERTZ;
    c->contact.E = 1e7;
    c->contact.nu = 0.25;
    c->contact.restitution = e;
    c->contact.v_impact = 1.0;
    c->contact.mu_s = c->contact.mu_d = 0.0;
}

/* Contact duration and restitution of a head-on collision at relative
 * speed v: two spheres (wall = 0) or a sphere and the bottom wall. */
static void collide(double e, double v, int wall, double *tc, double *rest)
{
    struct dem_config c;
    hertz_config(&c, e);
    struct dem_sim s;
    test_sim(&s, &c, 2, 0.0, 0.1);
    if (wall) {
        test_add(&s, 0.05, 0.05, A + 1e-5, A);
        s.p.vz[0] = -v;
    } else {
        test_add(&s, 0.05 - A - 5e-6, 0.05, 0.05, A);
        test_add(&s, 0.05 + A + 5e-6, 0.05, 0.05, A);
        s.p.vx[0] = 0.5 * v;
        s.p.vx[1] = -0.5 * v;
    }
    test_ready(&s);
    double t_in = -1, t_out = -1;
    for (int k = 0; k < 200000 && t_out < 0; k++) {
        test_step(&s, 1);
        const double gap =
            wall ? s.p.z[0] - A : fabs(s.p.x[1] - s.p.x[0]) - 2 * A;
        if (gap < 0 && t_in < 0)
            t_in = s.t;
        if (gap >= 0 && t_in >= 0)
            t_out = s.t;
    }
    assert_true(t_out > 0);
    *tc = t_out - t_in;
    *rest = wall ? s.p.vz[0] / v : (s.p.vx[1] - s.p.vx[0]) / v;
    dem_sim_destroy(&s);
}

static double hertz_time(double mstar, double rstar, double v)
{
    const double es = 1e7 / (2.0 * (1.0 - 0.25 * 0.25));
    return 2.868 * pow(mstar * mstar / (rstar * es * es * v), 0.2);
}

/* Elastic (e = 1): the contact time of Hertz over a decade of speeds, and
 * the sphere leaves as fast as it came. */
static void elastic_collision_lasts_the_hertz_time(void **state)
{
    (void)state;
    const double m = 4.0 / 3.0 * M_PI * A * A * A * 2000.0;
    const double speeds[] = {0.1, 0.316, 1.0};
    for (int wall = 0; wall <= 1; wall++)
        for (int k = 0; k < 3; k++) {
            double tc, e;
            collide(1.0, speeds[k], wall, &tc, &e);
            const double expect = wall
                                      ? hertz_time(m, A, speeds[k])
                                      : hertz_time(0.5 * m, 0.5 * A, speeds[k]);
            print_message("%s, v = %.3g m/s: t_c = %.6g ms (Hertz %.6g), "
                          "e = %.6f\n",
                          wall ? "wall" : "pair", speeds[k], 1e3 * tc,
                          1e3 * expect, e);
            assert_rel(tc, expect, 3e-3);
            assert_rel(e, 1.0, 1e-4);
        }
}

/* e = 0.7 and 0.3: the restitution asked for at every speed. */
static void restitution_is_the_one_asked_for_at_any_speed(void **state)
{
    (void)state;
    const double speeds[] = {0.1, 0.316, 1.0};
    const double target[] = {0.7, 0.3};
    for (int t = 0; t < 2; t++)
        for (int wall = 0; wall <= 1; wall++)
            for (int k = 0; k < 3; k++) {
                double tc, e;
                collide(target[t], speeds[k], wall, &tc, &e);
                print_message("target %.2f, %s, v = %.3g m/s: e = %.6f\n",
                              target[t], wall ? "wall" : "pair", speeds[k], e);
                assert_rel(e, target[t], 3e-3);
            }
}

/* The scaled collision behind the damping: alpha = 0 is elastic, the
 * restitution falls with alpha (to 0.04 at alpha = 1.6; from about 2 on
 * the sphere creeps back without ever leaving: e = 0), and _derive
 * inverts it. */
static void derived_damping_inverts_the_restitution(void **state)
{
    (void)state;
    assert_rel(dem_hertz_restitution(0.0), 1.0, 1e-6);
    double last = 1.0;
    for (double a = 0.1; a < 2.0; a *= 2.0) {
        const double e = dem_hertz_restitution(a);
        assert_true(e < last && e > 0.0);
        last = e;
    }
    assert_true(dem_hertz_restitution(3.2) == 0.0);
    struct dem_contact_params p = {0};
    p.normal = DEM_NORMAL_HERTZ;
    for (double e = 0.1; e < 1.0; e += 0.2) {
        p.restitution = e;
        dem_contact_derive(&p);
        assert_rel(dem_hertz_restitution(p.hertz_alpha), e, 1e-9);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(derived_damping_inverts_the_restitution),
        cmocka_unit_test(elastic_collision_lasts_the_hertz_time),
        cmocka_unit_test(restitution_is_the_one_asked_for_at_any_speed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
