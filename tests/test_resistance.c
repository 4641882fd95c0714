/* Rolling and torsion resistance (contact/resistance.h) through the whole
 * engine, against closed-form motions of one sphere on the bottom wall,
 * and the kernels' symmetry under swapping the particles and rotating the
 * frame.
 *
 * The sphere: a = 5 mm, rho = 2000 kg/m^3, m = 4/3 pi a^3 rho =
 * 1.0472e-3 kg, I = 2/5 m a^2. Against a wall the reduced radius is a, so
 * the rolling torque is at most a mu_r f_n and the torsion torque at most
 * a mu_o f_n (f_n = m g cos(theta) at rest on a wall tilted by theta).
 */
#include "testutil.h"

#include "contact/resistance.h"
#include "measure/measure.h"

#define A 5e-3
#define G 9.81

/* One sphere resting on the bottom wall (z = 0) of a 3D box, its overlap
 * the static one of gravity g tilted by theta about y (g = G (sin theta,
 * 0, -cos theta)); wall friction wall_mu, rolling and torsion as asked. */
static void sphere_on_wall(struct dem_sim *s, double theta, double wall_mu,
                           int rolling, double mu_r, int torsion, double mu_o)
{
    struct dem_config c;
    test_config(&c, 3);
    c.time_step = 2e-6;
    c.gravity[0] = G * sin(theta);
    c.gravity[2] = -G * cos(theta);
    c.contact.gamma_n = 1.0; /* a settled normal contact */
    c.contact.gamma_t = 0.05;
    c.contact.wall_mu = wall_mu;
    c.contact.rolling = rolling ? DEM_RESIST_LUDING : DEM_RESIST_NONE;
    c.contact.kr = 500.0;
    c.contact.gamma_r = 0.3; /* about a third of critical damping */
    c.contact.mu_r = c.contact.wall_mu_r = mu_r;
    c.contact.torsion = torsion ? DEM_RESIST_LUDING : DEM_RESIST_NONE;
    c.contact.ko = 200.0;
    c.contact.gamma_o = 0.2;
    c.contact.mu_o = c.contact.wall_mu_o = mu_o;
    test_sim(s, &c, 1, 0.0, 0.1);
    const double m = 4.0 / 3.0 * M_PI * A * A * A * c.particles.density;
    test_add(s, 0.05, 0.05, A - m * G * cos(theta) / c.contact.k, A);
    test_ready(s);
}

/* Least-squares slope of y against x. */
static double slope(const double *x, const double *y, int n)
{
    double mx = 0, my = 0, sxy = 0, sxx = 0;
    for (int k = 0; k < n; k++) {
        mx += x[k] / n;
        my += y[k] / n;
    }
    for (int k = 0; k < n; k++) {
        sxy += (x[k] - mx) * (y[k] - my);
        sxx += (x[k] - mx) * (x[k] - mx);
    }
    return sxy / sxx;
}

/* Rolling without slip at v0 = 0.1 m/s on a level wall: the rolling
 * torque a mu_r m g takes the power mu_r m g v from the kinetic energy
 * (7/10) m v^2 (translation plus rotation, v = a w), so
 * dv/dt = -(5/7) mu_r g = -0.70071 m/s^2 for mu_r = 0.1. Without rolling
 * resistance the sphere keeps its speed. */
static void rolling_friction_decelerates(void **state)
{
    (void)state;
    for (int on = 0; on <= 1; on++) {
        struct dem_sim s;
        sphere_on_wall(&s, 0.0, 1.0, on, 0.1, 0, 0.0);
        test_step(&s, 5000); /* settle */
        s.p.vx[0] = 0.1;
        s.p.wy[0] = 0.1 / A; /* w x (-a z) = -v: the contact point rests */
        test_step(&s, 2000);
        double t[40], v[40];
        for (int k = 0; k < 40; k++) {
            test_step(&s, 500);
            t[k] = s.t;
            v[k] = s.p.vx[0];
        }
        const double expect = on ? -5.0 / 7.0 * 0.1 * G : 0.0;
        print_message("rolling %s: dv/dt = %.6g m/s^2 (expected %.6g)\n",
                      on ? "on" : "off", slope(t, v, 40), expect);
        assert_close(slope(t, v, 40), expect, 0.01 * 5.0 / 7.0 * 0.1 * G);
        /* still rolling without slip */
        assert_close(s.p.wy[0] * A, s.p.vx[0], 1e-4);
        dem_sim_destroy(&s);
    }
}

/* On a wall tilted by theta the sphere rolls unless the rolling torque
 * can hold the friction's torque: a m g sin(theta) <= a mu_r m g
 * cos(theta), i.e. tan(theta) <= mu_r. Below (tan theta = 0.8 mu_r) it
 * stays; above (1.5 mu_r) it accelerates at
 * (5/7) g (sin theta - mu_r cos theta) = 0.34637 m/s^2 for mu_r = 0.1. */
static void incline_holds_below_the_rolling_limit(void **state)
{
    (void)state;
    const double mu_r = 0.1;
    struct dem_sim s;
    sphere_on_wall(&s, atan(0.8 * mu_r), 1.0, 1, mu_r, 0, 0.0);
    test_step(&s, 20000);
    const double x0 = s.p.x[0];
    test_step(&s, 20000);
    print_message("incline below: |v| = %.3g m/s, moved %.3g m in 40 ms\n",
                  fabs(s.p.vx[0]), fabs(s.p.x[0] - x0));
    assert_true(fabs(s.p.vx[0]) < 1e-5);
    assert_true(fabs(s.p.x[0] - x0) < 1e-7);
    dem_sim_destroy(&s);

    const double th = atan(1.5 * mu_r);
    sphere_on_wall(&s, th, 1.0, 1, mu_r, 0, 0.0);
    test_step(&s, 5000);
    double t[40], v[40];
    for (int k = 0; k < 40; k++) {
        test_step(&s, 500);
        t[k] = s.t;
        v[k] = s.p.vx[0];
    }
    const double expect = 5.0 / 7.0 * G * (sin(th) - mu_r * cos(th));
    print_message("incline above: dv/dt = %.6g m/s^2 (expected %.6g)\n",
                  slope(t, v, 40), expect);
    assert_rel(slope(t, v, 40), expect, 0.01);
    dem_sim_destroy(&s);
}

/* A sphere spinning at 10 rad/s about the wall's normal: the torsion
 * torque a mu_o m g against I = 2/5 m a^2 gives
 * dw/dt = -(5/2) mu_o g / a = -490.5 rad/s^2 for mu_o = 0.1, so it stops
 * after 20.4 ms. Without torsion resistance (and frictionless about the
 * normal: the contact point of a spin about n does not slide) it spins
 * on. */
static void torsion_friction_stops_a_spin(void **state)
{
    (void)state;
    for (int on = 0; on <= 1; on++) {
        struct dem_sim s;
        sphere_on_wall(&s, 0.0, 1.0, 0, 0.0, on, 0.1);
        test_step(&s, 5000);
        s.p.wz[0] = 10.0;
        test_step(&s, 500);
        double t[20], w[20];
        for (int k = 0; k < 20; k++) {
            test_step(&s, 200);
            t[k] = s.t;
            w[k] = s.p.wz[0];
        }
        const double expect = on ? -2.5 * 0.1 * G / A : 0.0;
        print_message("torsion %s: dw/dt = %.6g rad/s^2 (expected %.6g)\n",
                      on ? "on" : "off", slope(t, w, 20), expect);
        assert_close(slope(t, w, 20), expect, 0.01 * 2.5 * 0.1 * G / A);
        if (on) {
            test_step(&s, 30000); /* 60 ms more: stopped (the torsion
                                     dashpot damps the spring) */
            if (!(fabs(s.p.wz[0]) < 1e-2))
                fail_msg("wz = %g", s.p.wz[0]);
        }
        dem_sim_destroy(&s);
    }
}

/* The springs alone (no limit reached, no dashpot, frictionless wall so
 * that rolling does not drag the centre): the sphere turns back and forth
 * about y at w0 = a sqrt(k_r / I) = sqrt(k_r / (0.4 m)) = 1092.7 rad/s
 * (k_r = 500 N/m), and about z at sqrt(k_o / (0.4 m)) = 691.1 rad/s
 * (k_o = 200 N/m); the spin's energy and the spring's add up to a
 * constant. */
static void rolling_and_torsion_springs_oscillate(void **state)
{
    (void)state;
    for (int axis = 1; axis <= 2; axis++) {
        struct dem_sim s;
        sphere_on_wall(&s, 0.0, 0.0, axis == 1, 100.0, axis == 2, 100.0);
        s.cp.gamma_n = s.cp.gamma_t = s.cp.gamma_r = s.cp.gamma_o = 0.0;
        double *w = axis == 1 ? s.p.wy : s.p.wz;
        w[0] = 1.0;
        const double m = s.p.m[0], k = axis == 1 ? 500.0 : 200.0;
        const double w0 = sqrt(k / (0.4 * m));
        /* zero crossings of the spin over about 6 periods */
        double last = w[0], first_t = -1, last_t = -1;
        int crossings = 0;
        double emin = INFINITY, emax = -INFINITY;
        const int steps = (int)(6 * 2 * M_PI / w0 / s.dt);
        for (int k2 = 0; k2 < steps; k2++) {
            test_step(&s, 1);
            if ((last > 0) != (w[0] > 0)) {
                /* linear interpolation of the crossing */
                const double tc = s.t - s.dt * w[0] / (w[0] - last);
                if (first_t < 0)
                    first_t = tc;
                last_t = tc;
                crossings++;
            }
            last = w[0];
            if (k2 % 50 == 0) {
                s.measure = 1;
                dem_sim_forces(&s);
                const double I = 0.4 * m * A * A;
                /* the normal spring's energy is constant (at rest) */
                const double e = 0.5 * I * w[0] * w[0] + s.sums.e_pot;
                emin = fmin(emin, e);
                emax = fmax(emax, e);
            }
        }
        if (crossings < 10)
            fail_msg("%d crossings, w now %g, t %g steps %d", crossings, w[0],
                     s.t, steps);
        const double period = 2.0 * (last_t - first_t) / (crossings - 1);
        print_message("%s spring: period %.6g ms (expected %.6g), energy "
                      "varies by %.2g of the spin's\n",
                      axis == 1 ? "rolling" : "torsion", 1e3 * period,
                      1e3 * 2 * M_PI / w0,
                      (emax - emin) / (0.5 * 0.4 * m * A * A));
        assert_rel(period, 2 * M_PI / w0, 2e-3);
        const double e_spin = 0.5 * 0.4 * m * A * A; /* at w = 1 rad/s */
        if (!(emax - emin < 1e-3 * e_spin))
            fail_msg("energy from %g to %g J, spin %g J", emin, emax, e_spin);
        dem_sim_destroy(&s);
    }
}

static struct dem_vec3 rot(const double R[3][3], struct dem_vec3 v)
{
    struct dem_vec3 o = {R[0][0] * v.x + R[0][1] * v.y + R[0][2] * v.z,
                         R[1][0] * v.x + R[1][1] * v.y + R[1][2] * v.z,
                         R[2][0] * v.x + R[2][1] * v.y + R[2][2] * v.z};
    return o;
}

static struct dem_vec3 neg(struct dem_vec3 v)
{
    struct dem_vec3 o = {-v.x, -v.y, -v.z};
    return o;
}

/* The kernels: swapping i and j (n -> -n, dw -> -dw, the springs as the
 * other side sees them) gives the opposite torque, i.e. the same torque
 * pair; rotating every input by R rotates the torque by R. Checked for a
 * sticking and a sliding contact of each kind. */
static void kernels_are_symmetric_and_objective(void **state)
{
    (void)state;
    const double c = cos(0.7), sn = sin(0.7), c2 = cos(-1.1), s2 = sin(-1.1);
    /* R = R_x(-1.1) R_z(0.7) */
    const double R[3][3] = {
        {c, -sn, 0}, {c2 * sn, c2 * c, -s2}, {s2 * sn, s2 * c, c2}};
    const double len = sqrt(0.3 * 0.3 + 0.5 * 0.5 + 0.81 * 0.81);
    const struct dem_vec3 n = {0.3 / len, -0.5 / len, 0.81 / len};
    const struct dem_vec3 dw = {12.0, -7.0, 30.0};
    for (int slide = 0; slide <= 1; slide++) {
        const double mu = slide ? 0.001 : 10.0;
        const struct dem_tangential T = {500.0, 0.01, mu, mu};
        for (int kind = 0; kind < 2; kind++) {
            /* swapped, the rolling velocity -a n x dw is the same and the
             * torsion velocity a (n . dw) n the opposite */
            struct dem_vec3 x1 = {1e-6, 2e-6, -1e-6};
            struct dem_vec3 x2 = kind ? neg(x1) : x1, x3 = rot(R, x1);
            int s1 = 0, s2b = 0, s3 = 0;
            struct dem_vec3 (*f)(struct dem_vec3, struct dem_vec3, double,
                                 double, double, const struct dem_tangential *,
                                 struct dem_vec3 *, int *) =
                kind ? dem_torsion_torque : dem_rolling_torque;
            const struct dem_vec3 q1 =
                f(n, dw, 2.5e-3, 0.05, 1e-5, &T, &x1, &s1);
            const struct dem_vec3 q2 =
                f(neg(n), neg(dw), 2.5e-3, 0.05, 1e-5, &T, &x2, &s2b);
            const struct dem_vec3 q3 =
                f(rot(R, n), rot(R, dw), 2.5e-3, 0.05, 1e-5, &T, &x3, &s3);
            const double scale = fabs(q1.x) + fabs(q1.y) + fabs(q1.z);
            assert_true(scale > 0.0);
            assert_close(q2.x, -q1.x, 1e-12 * scale);
            assert_close(q2.y, -q1.y, 1e-12 * scale);
            assert_close(q2.z, -q1.z, 1e-12 * scale);
            const struct dem_vec3 rq = rot(R, q1);
            assert_close(q3.x, rq.x, 1e-12 * scale);
            assert_close(q3.y, rq.y, 1e-12 * scale);
            assert_close(q3.z, rq.z, 1e-12 * scale);
            assert_int_equal(s1, s3);
            assert_int_equal(s1 != 0, slide);
            /* at the limit the torque is a mu f_c */
            if (slide)
                assert_rel(sqrt(q1.x * q1.x + q1.y * q1.y + q1.z * q1.z),
                           2.5e-3 * mu * 0.05, 1e-12);
        }
    }
}

/* A 2D sample with torsion, built without the config's checks: the
 * force pass has no instance of it, so making the simulation ready must
 * refuse it rather than run without forces. */
static void torsion_in_2d_is_refused_when_built_by_hand(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 2);
    c.contact.torsion = DEM_RESIST_LUDING;
    c.contact.ko = 200.0;
    c.contact.mu_o = 0.1;
    struct dem_sim s;
    test_sim(&s, &c, 2, 0.0, 0.1);
    test_add(&s, 0.05, 0.05, 0.0, A);
    struct dem_error err = {0};
    assert_int_equal(dem_sim_ready(&s, &err), DEM_ECONFIG);
    assert_non_null(strstr(err.msg, "contact.torsion"));
    dem_sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(kernels_are_symmetric_and_objective),
        cmocka_unit_test(rolling_friction_decelerates),
        cmocka_unit_test(incline_holds_below_the_rolling_limit),
        cmocka_unit_test(torsion_friction_stops_a_spin),
        cmocka_unit_test(rolling_and_torsion_springs_oscillate),
        cmocka_unit_test(torsion_in_2d_is_refused_when_built_by_hand),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
