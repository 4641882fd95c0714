/* Walls: prescribed profiles, the cyclic target stress, a stress-controlled
 * wall that settles where the packing's force balances sigma A, and the
 * Love-Weber stress of a relaxed packing equal to the wall stress. */
#include "testutil.h"

#include "contact/state.h"
#include "core/rng.h"
#include "measure/measure.h"
#include "measure/network.h"

static void strain_profiles_start_and_end_at_rest(void **state)
{
    (void)state;
    struct dem_wall w;
    memset(&w, 0, sizeof w);
    w.pos = 1.0;
    const double T = 2.0, D = -0.1;
    double x, v;
    dem_wall_set_strain(&w, DEM_PROFILE_COSINE, D, T, 5.0);
    dem_wall_strain_state(&w, 5.0, &x, &v);
    assert_close(x, 1.0, 1e-15);
    assert_close(v, 0.0, 1e-15);
    dem_wall_strain_state(&w, 6.0, &x, &v);
    assert_close(x, 1.0 + D / 2, 1e-15);
    assert_close(v, D * M_PI / (2 * T), 1e-15); /* peak speed at T/2 */
    dem_wall_strain_state(&w, 7.0, &x, &v);
    assert_close(x, 1.0 + D, 1e-15);
    assert_close(v, 0.0, 1e-15);
    dem_wall_strain_state(&w, 9.0, &x, &v); /* holds after T */
    assert_close(x, 1.0 + D, 1e-15);
    assert_close(v, 0.0, 0.0);
    dem_wall_set_strain(&w, DEM_PROFILE_LINEAR, D, T, 0.0);
    dem_wall_strain_state(&w, 0.5, &x, &v);
    assert_close(x, 1.0 + D * 0.25, 1e-15);
    assert_close(v, D / T, 1e-15);
    dem_wall_strain_state(&w, 2.0 + 1e-6, &x, &v); /* after T: at rest */
    assert_close(v, 0.0, 0.0);
    /* a ramp of one step (constant_volume's lateral walls), read at the
     * step's end: its velocity D/dt whichever way t + dt - t rounds (it
     * read 0 in 43 % of the steps of a run; a read-only review, session
     * 107) */
    int zero = 0;
    for (int k = 0; k < 20000; k++) {
        /* early, and at t = 8 to 48 s of a step of 1.47e-7 s (where an
         * ulp of t is 4e-9 to 2e-8 of the step) */
        const double dt = k < 10000 ? 2e-5 : 1.4733e-7,
                     t = k < 10000 ? 0.0631 + k * 1.37e-5
                                   : 8.0 + (k - 10000) * 4.00013e-3;
        w.pos = 1.0;
        dem_wall_set_strain(&w, DEM_PROFILE_LINEAR, D, dt, t);
        dem_wall_strain_state(&w, t + dt, &x, &v);
        zero += v == 0.0;
        /* (late, t + dt - t itself is off by an ulp of t: 1e-8 of D) */
        assert_close(x, 1.0 + D, k < 10000 ? 1e-12 : 1e-7 * fabs(D));
    }
    assert_int_equal(zero, 0);
    w.pos = 1.0;
    dem_wall_set_strain(&w, DEM_PROFILE_CYCLIC, D, T, 0.0);
    dem_wall_strain_state(&w, 1.0, &x, &v);
    assert_close(x, 1.0 + D, 1e-15);
    dem_wall_strain_state(&w, 2.0, &x, &v);
    assert_close(x, 1.0, 1e-15);
    assert_close(v, 0.0, 1e-15);
    /* sine: both ways, +D at T/4, -D at 3T/4, back at T with the speed
     * it started with, 2 pi D/T */
    dem_wall_set_strain(&w, DEM_PROFILE_SINE, D, T, 0.0);
    dem_wall_strain_state(&w, 0.0, &x, &v);
    assert_close(v, 2.0 * M_PI * D / T, 1e-15);
    dem_wall_strain_state(&w, 0.5, &x, &v);
    assert_close(x, 1.0 + D, 1e-15);
    dem_wall_strain_state(&w, 1.5, &x, &v);
    assert_close(x, 1.0 - D, 1e-15);
    dem_wall_strain_state(&w, 2.0, &x, &v);
    assert_close(x, 1.0, 1e-15);
    assert_close(v, 2.0 * M_PI * D / T, 1e-15);
    /* every profile's velocity is its position's rate: a central
     * difference at times where the speed is not 0 (the cyclic one
     * moved at 2 pi D/T, twice its position's rate, and no test read its
     * speed away from its ends: a review of the tests, session 115) */
    static const int prof[4] = {DEM_PROFILE_LINEAR, DEM_PROFILE_COSINE,
                                DEM_PROFILE_CYCLIC, DEM_PROFILE_SINE};
    const double h = 1e-6;
    for (int q = 0; q < 4; q++)
        for (int k = 1; k < 8; k++) {
            const double t = 0.2347 * k; /* within T = 2 s */
            double xa, xb, vt;
            w.pos = 1.0;
            dem_wall_set_strain(&w, prof[q], D, T, 0.0);
            dem_wall_strain_state(&w, t - h, &xa, &vt);
            dem_wall_strain_state(&w, t + h, &xb, &vt);
            dem_wall_strain_state(&w, t, &x, &v);
            if (fabs((xb - xa) / (2 * h) - v) > 1e-7 * fabs(D))
                fail_msg("profile %d at t = %g: v = %.9g, dx/dt = %.9g",
                         prof[q], t, v, (xb - xa) / (2 * h));
        }
    /* and the cyclic one's at a quarter period: pi D/T, half way */
    dem_wall_set_strain(&w, DEM_PROFILE_CYCLIC, D, T, 0.0);
    dem_wall_strain_state(&w, 0.5, &x, &v);
    assert_close(x, 1.0 + 0.5 * D, 1e-15);
    assert_close(v, M_PI * D / T, 1e-15);
}

/* 2 sigma = 2 p0 + Dsigma [1 - cos(2 pi t/t0)] (David et al.) at sampled times.
 */
static void cyclic_target_follows_formula(void **state)
{
    (void)state;
    struct dem_wall w;
    memset(&w, 0, sizeof w);
    const double p0 = 1000.0, ds = 200.0, t0 = 10.0, ts = 3.0;
    dem_wall_set_stress(&w, 2.0, 200.0, 0.0, p0, ds, t0, ts);
    for (int k = 0; k <= 40; k++) {
        double t = ts + 0.37 * k;
        double expect = p0 + 0.5 * ds * (1 - cos(2 * M_PI * (t - ts) / t0));
        assert_close(dem_wall_target_stress(&w, t), expect, 1e-9);
    }
    assert_close(dem_wall_target_stress(&w, ts + t0 / 2), p0 + ds, 1e-9);
}

/* A 2D square packing: polydisperse discs on a lattice. */
static void lattice_2d(struct dem_sim *s, int nside, double a, uint64_t seed)
{
    struct dem_rng g;
    dem_rng_seed(&g, seed);
    for (int j = 0; j < nside; j++)
        for (int i = 0; i < nside; i++)
            test_add(s, (2 * i + 1) * a, (2 * j + 1) * a, 0.0,
                     a * (0.8 + 0.2 * dem_rng_uniform(&g)));
}

static void relax(struct dem_sim *s, double tmax)
{
    const double L0[3] = {1, 1, 1};
    struct dem_sample smp;
    while (s->t < tmax) {
        s->measure = 1;
        test_step(s, 500);
        dem_measure(s, L0, 1.0, 0.0, 0, &smp);
        if (smp.e_kin + smp.e_rot < 1e-8 * smp.e_pot &&
            fabs(s->wall[3].vel) < 1e-7)
            return;
    }
    fail_msg("did not relax by t = %g s", tmax);
}

/* Only the top wall is stress-controlled; it comes to rest where the
 * packing pushes it out with exactly sigma times the current face length. */
static void stress_wall_balances_pressure(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 2);
    c.contact.gamma_n = 0.05;
    c.damping.gamma_b = 0.2;
    c.time_step = 2e-5;
    c.walls.mass = 0.05;
    c.walls.gamma = 5.0;
    const int nside = 8;
    const double a = 5e-3, L = 2 * nside * a;
    struct dem_sim s;
    test_sim(&s, &c, nside * nside, 0.0, L);
    lattice_2d(&s, nside, a, 3);
    test_ready(&s);
    const double sigma = 500.0; /* N/m */
    dem_wall_set_stress(&s.wall[3], c.walls.mass, c.walls.gamma, 0, sigma, 0, 0,
                        s.t);
    relax(&s, 20.0);
    double A = dem_sim_wall_area(&s, 3);
    assert_rel(s.wall[3].force, sigma * A, 1e-4);
    /* the fixed bottom wall carries the same load */
    assert_rel(s.wall[2].force, sigma * A, 1e-3);
    dem_sim_destroy(&s);
}

/* All walls stress-controlled at p in 3D: once relaxed (E_kin < 1e-12
 * E_pot, where each wall's servo has met p to 1e-8), the Love-Weber
 * stress (contacts and walls, kinetic part included) equals the wall
 * stress on every axis: every particle's net force is then zero, and
 * sum b f / V = F/A holds to that residual (1.6e-8 measured; a wall
 * contact's point off the plane by delta/2, finding 163, is 1e-4). */
static void love_weber_equals_wall_stress(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 3);
    c.contact.gamma_n = 0.05;
    c.contact.gamma_t = 0.01;
    c.damping.gamma_b = 0.2;
    c.damping.gamma_br = 0.05;
    c.time_step = 2e-5;
    c.walls.mass = 0.05;
    c.walls.gamma = 5.0;
    const int nside = 5;
    const double a = 5e-3, L = 2 * nside * a;
    struct dem_sim s;
    test_sim(&s, &c, nside * nside * nside, 0.0, L);
    struct dem_rng g;
    dem_rng_seed(&g, 11);
    for (int k = 0; k < nside; k++)
        for (int j = 0; j < nside; j++)
            for (int i = 0; i < nside; i++)
                test_add(&s, (2 * i + 1) * a, (2 * j + 1) * a, (2 * k + 1) * a,
                         a * (0.75 + 0.25 * dem_rng_uniform(&g)));
    test_ready(&s);
    const double p = 1000.0;
    for (int w = 0; w < 6; w++)
        dem_wall_set_stress(&s.wall[w], c.walls.mass, c.walls.gamma, 0, p, 0, 0,
                            s.t);
    const double L0[3] = {1, 1, 1};
    struct dem_sample smp;
    int relaxed = 0;
    while (s.t < 20.0 && !relaxed) {
        s.measure = 1;
        test_step(&s, 500);
        dem_measure(&s, L0, 1.0, 0.0, 0, &smp);
        relaxed = smp.e_kin + smp.e_rot < 1e-12 * smp.e_pot;
    }
    assert_true(relaxed);
    for (int a3 = 0; a3 < 3; a3++) {
        assert_rel(smp.sigma[a3], p, 1e-6);
        assert_rel(smp.sigma_lw[a3][a3], smp.sigma[a3], 1e-6);
    }
    assert_true(smp.coordination > 3.0);
    /* at rest few contacts slide (9 of the 241 pairs sit at their
     * Coulomb limit): the frictionless walls' contacts (wall_mu = 0), at
     * their zero limit every step, are not counted (they set a floor of
     * n_pw/(n_pp + n_pw), here 98 of 339, 0.29: 0.32 in all) */
    assert_true(smp.n_pw > 0.2 * (smp.n_pp + smp.n_pw));
    assert_true(smp.sliding_fraction < 0.1);
    /* the contact network (contacts_final.csv, the snapshots) gives the
     * same sum of b (x) f: a wall's contact point is on its plane, where
     * the stress takes it (in the middle of the overlap, outside the box,
     * its sum was larger by sum (delta/2) f over the wall contacts) */
    s.measure = 1; /* (the sums of this step's forces) */
    test_step(&s, 1);
    struct dem_network net;
    struct dem_error err = {0};
    assert_int_equal(dem_network_build(&s, &net, &err), DEM_OK);
    assert_int_equal(net.n - net.npair, s.sums.n_pw);
    double W[3][3] = {{0}};
    for (int k = 0; k < net.n; k++) {
        const struct dem_network_contact *q = &net.c[k];
        for (int a3 = 0; a3 < 3; a3++)
            for (int b3 = 0; b3 < 3; b3++)
                W[a3][b3] += q->b[a3] * (q->fn * q->n[b3] + q->ft[b3]);
    }
    for (int a3 = 0; a3 < 3; a3++)
        for (int b3 = 0; b3 < 3; b3++)
            assert_true(fabs(W[a3][b3] - s.sums.fabric_stress[a3][b3]) <
                        1e-12 * fabs(s.sums.fabric_stress[0][0]));
    dem_network_free(&net);
    dem_sim_destroy(&s);
}

/* The measured quantities from their definitions, on a lattice at rest
 * whose walls are given forces by hand: sigma along an axis the mean of
 * its two walls' F/A (walls that differ), q (3D sqrt(3 J2) = 2p for
 * (3p, p, p); 2D the Mohr radius), p, the solid fraction and the void
 * ratio from the radii and the box. (3D q, the two walls' mean, and
 * (V - Vs)/Vs survived mutations: a review of the tests, session 115.) */
static void measures_follow_their_definitions(void **state)
{
    (void)state;
    for (int dim = 2; dim <= 3; dim++) {
        struct dem_config c;
        test_config(&c, dim);
        const int nside = 4, n = dim == 3 ? 64 : 16;
        const double a = 5e-3, L = 2 * nside * a;
        struct dem_sim s;
        test_sim(&s, &c, n, 0.0, L);
        double vs = 0.0;
        for (int k = 0; k < (dim == 3 ? nside : 1); k++)
            for (int j = 0; j < nside; j++)
                for (int i = 0; i < nside; i++) {
                    const double r = a * (0.6 + 0.1 * ((i + 2 * j + k) % 4));
                    test_add(&s, (2 * i + 1) * a, (2 * j + 1) * a,
                             dim == 3 ? (2 * k + 1) * a : 0.0, r);
                    vs +=
                        dim == 3 ? 4.0 / 3.0 * M_PI * r * r * r : M_PI * r * r;
                }
        test_ready(&s);
        /* sigma_x: walls at 0.9 p and 1.1 p, sigma_y = 3p, sigma_z = p */
        const double p = 100.0, A = dim == 3 ? L * L : L;
        const double sig[3][2] = {{0.9 * p, 1.1 * p}, {3 * p, 3 * p}, {p, p}};
        for (int w = 0; w < 2 * dim; w++)
            s.wall[w].force = sig[w / 2][w % 2] * A;
        const double L0[3] = {L, L, dim == 3 ? L : 0.0};
        const double V = dim == 3 ? L * L * L : L * L;
        struct dem_sample smp;
        dem_measure(&s, L0, V, 0.0, 0, &smp);
        assert_rel(smp.sigma_wall[0], 0.9 * p, 1e-12);
        assert_rel(smp.sigma_wall[1], 1.1 * p, 1e-12);
        assert_rel(smp.sigma[0], p, 1e-12);
        assert_rel(smp.sigma[1], 3 * p, 1e-12);
        assert_rel(smp.p, dim == 3 ? 5.0 / 3.0 * p : 2 * p, 1e-12);
        assert_rel(smp.q, dim == 3 ? 2 * p : p, 1e-12);
        assert_rel(smp.solid_fraction, vs / V, 1e-12);
        assert_rel(smp.void_ratio, (V - vs) / vs, 1e-12);
        /* the inertial number of the fastest strain rate (the y walls
         * closing at 0.01 m/s): I = rate d sqrt(rho_eff/p), here
         * rate sqrt(m d/F), F = p d^2 in 3D and p d in 2D (the 3D force
         * scale as the 2D one survived a mutation) */
        s.wall[3].vel = -0.01;
        dem_measure(&s, L0, V, 0.0, 0, &smp);
        double m = 0.0, d = 0.0;
        for (int i = 0; i < s.p.n; i++) {
            m += s.p.m[i] / s.p.n;
            d += 2.0 * s.p.r[i] / s.p.n;
        }
        const double F = smp.p * (dim == 3 ? d * d : d);
        assert_rel(smp.inertial_number, 0.01 / L * sqrt(m * d / F), 1e-12);
        dem_sim_destroy(&s);
    }
}

/* One pair of spheres of radii a and 2a overlapping by delta along x:
 * the overlap ratio is delta over the smaller radius, the fabric n (x) n
 * is diag(1, 0, 0), and the contact point (contacts_final.csv's x, y, z)
 * is the middle of the overlap, a - delta/2 from the small sphere's
 * centre. (Each survived a mutation: the larger radius, b (x) b, the
 * point on the far side; a review of the tests, session 115.) */
static void a_pair_measures_its_overlap_normal_and_point(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 3);
    struct dem_sim s;
    test_sim(&s, &c, 2, 0.0, 0.1);
    const double a = 5e-3, delta = 1e-4, x0 = 0.03;
    test_add(&s, x0, 0.05, 0.05, a);
    test_add(&s, x0 + 3 * a - delta, 0.05, 0.05, 2 * a);
    test_ready(&s);
    s.measure = 1;
    test_step(&s, 1); /* (one step of 1e-6 s: the overlap moves by 1e-10) */
    assert_int_equal(s.sums.n_pp, 1);
    assert_rel(s.sums.max_overlap_ratio, delta / a, 1e-5);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            assert_close(s.sums.fabric[i][j], i == 0 && j == 0 ? 1.0 : 0.0,
                         1e-12);
    struct dem_network net;
    struct dem_error err = {0};
    assert_int_equal(dem_network_build(&s, &net, &err), DEM_OK);
    assert_int_equal(net.npair, 1);
    assert_rel(net.c[0].x[0], x0 + a - 0.5 * delta, 1e-6);
    assert_close(net.c[0].x[1], 0.05, 1e-12);
    assert_close(net.c[0].x[2], 0.05, 1e-12);
    assert_rel(net.c[0].delta, delta, 1e-5);
    dem_network_free(&net);
    /* its stored energy: 1/2 k delta^2, no sliding (the linear law) */
    assert_rel(s.sums.e_pot, 0.5 * c.contact.k * delta * delta, 1e-5);
    dem_sim_destroy(&s);

    /* with Hertz's law (8/15) E* sqrt(R*) delta^(5/2), R* = a 2a/(3a):
     * the law's effective radius (0.5 R survived a mutation) */
    c.contact.normal = DEM_NORMAL_HERTZ;
    c.contact.E = 1e7;
    c.contact.nu = 0.3;
    test_sim(&s, &c, 2, 0.0, 0.1);
    test_add(&s, x0, 0.05, 0.05, a);
    test_add(&s, x0 + 3 * a - delta, 0.05, 0.05, 2 * a);
    test_ready(&s);
    s.measure = 1;
    test_step(&s, 1);
    const double es = c.contact.E / (2.0 * (1.0 - 0.09));
    assert_rel(s.sums.e_pot,
               8.0 / 15.0 * es * sqrt(2.0 * a / 3.0) * pow(delta, 2.5), 1e-5);
    dem_sim_destroy(&s);
}

/* Rattlers: particles with fewer contacts (walls counted) than can hold
 * one in equilibrium, 2 with friction, d + 1 without, removed until
 * every survivor has that many among survivors. A square (cubic)
 * lattice of r layers between its side walls and on the floor, each
 * pair overlapping by delta, has none: every particle has d + 1 or more
 * (2D: a top corner has its wall, its neighbour and the one below). On
 * it stand two columns: A, of 3, on its corner against the side wall(s),
 * each of whose members has d + 1 contacts (walls, below, above) but the
 * top one d; and B, of 2, on an inner particle, whose members have 2 but
 * the top one 1. With friction B goes and A stands; without, the removal
 * of either column's top cascades down it, one a round, and stops at the
 * lattice. The coordination without the rattlers counts the lattice's
 * pairs and the standing column's. (Before, 2D took fewer than 2 and 3D
 * fewer than 4 with or without friction.) */
static void rattlers_cascade_down_a_column(void **state)
{
    (void)state;
    for (int run = 0; run < 4; run++) {
        const int dim = 2 + run / 2, frictional = run % 2;
        struct dem_config c;
        test_config(&c, dim);
        if (!frictional)
            c.contact.mu_s = c.contact.mu_d = 0.0;
        const int m = 6, r = 2, ka = 3, kb = 2;
        const double a = 5e-3, delta = 1e-5, sp = 2 * a - delta;
        const int nlat = dim == 3 ? m * m * r : m * r;
        struct dem_sim s;
        test_sim(&s, &c, nlat + ka + kb, 0.0, m * sp);
        const double o = a - delta / 2;
        /* (x, y, up): 2D layers along y, 3D along z */
        for (int i = 0; i < nlat; i++) {
            const double x = o + (i % m) * sp,
                         y = dim == 3 ? o + ((i / m) % m) * sp : 0.0,
                         up = o + (dim == 3 ? i / (m * m) : i / m) * sp;
            test_add(&s, x, dim == 3 ? y : up, dim == 3 ? up : 0.0, a);
        }
        for (int j = 1; j <= ka + kb; j++) {
            const double x = j <= ka ? o : o + 3 * sp,
                         up = o + (r - 1 + (j <= ka ? j : j - ka)) * sp;
            test_add(&s, x, dim == 3 ? x : up, dim == 3 ? up : 0.0, a);
        }
        test_ready(&s);
        /* lattice pairs: m - 1 on each line along each axis */
        const long pairs = dim == 3
                               ? 2L * (m - 1) * m * r + (long)m * m * (r - 1)
                               : (long)(m - 1) * r + (long)m * (r - 1);
        assert_int_equal(s.sums.n_pp, pairs + ka + kb);
        const double L0[3] = {1, 1, 1};
        struct dem_sample smp;
        dem_measure(&s, L0, 1.0, 0.0, 0, &smp);
        const int gone = frictional ? kb : ka + kb;
        const long kept = frictional ? pairs + ka : pairs;
        assert_rel(smp.rattler_fraction, (double)gone / (nlat + ka + kb),
                   1e-15);
        assert_rel(smp.coordination_nr, 2.0 * kept / (nlat + ka + kb - gone),
                   1e-15);
        dem_sim_destroy(&s);
    }
}

/* A contact at a zero Coulomb limit "slides" with no force (the slip
 * bit the force pass needs) but is not counted as sliding: here a pair
 * opening faster than its dashpot allows (k delta = 0.05 N against
 * gamma_n ddot = 1 N: f_n < 0, f_C = 0) while its surfaces slip, beside
 * a pair at rest under load (sticking). The sliding fraction is 0 of 1
 * contact with friction (before, 1 of 2: 0.5), and the network's flag of
 * the opening pair 0. */
static void a_contact_at_a_zero_limit_is_not_sliding(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 3);
    c.contact.gamma_n = 10.0;
    c.contact.mu_s = c.contact.mu_d = 0.5;
    c.time_step = 1e-6;
    struct dem_sim s;
    test_sim(&s, &c, 4, 0.0, 0.1);
    const double a = 5e-3, delta = 1e-5;
    test_add(&s, 0.02, 0.05, 0.05, a);
    test_add(&s, 0.02 + 2 * a - delta, 0.05, 0.05, a);
    test_add(&s, 0.07, 0.05, 0.05, a);
    test_add(&s, 0.07 + 2 * a - delta, 0.05, 0.05, a);
    s.p.vx[0] = -0.05; /* opening at 0.1 m/s */
    s.p.vx[1] = 0.05;
    s.p.vy[0] = 0.05; /* and slipping */
    test_ready(&s);   /* the forces, with the sums */
    assert_int_equal(s.sums.n_pp, 2);
    const struct dem_contact_list *L = &s.pairs.cur;
    int slipping = 0;
    for (int k = 0; k < L->n; k++)
        slipping += (L->state[k] & DEM_CONTACT_SLIDING) != 0;
    assert_int_equal(slipping, 1); /* the force pass's bit */
    const double L0[3] = {1, 1, 1};
    struct dem_sample smp;
    dem_measure(&s, L0, 1.0, 0.0, 0, &smp);
    assert_true(smp.sliding_fraction == 0.0);
    struct dem_network nw;
    struct dem_error err = {0};
    assert_int_equal(dem_network_build(&s, &nw, &err), 0);
    assert_int_equal(nw.npair, 2);
    for (int k = 0; k < nw.npair; k++)
        assert_int_equal(nw.c[k].sliding, 0);
    dem_network_free(&nw);
    dem_sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(strain_profiles_start_and_end_at_rest),
        cmocka_unit_test(cyclic_target_follows_formula),
        cmocka_unit_test(stress_wall_balances_pressure),
        cmocka_unit_test(love_weber_equals_wall_stress),
        cmocka_unit_test(measures_follow_their_definitions),
        cmocka_unit_test(a_pair_measures_its_overlap_normal_and_point),
        cmocka_unit_test(a_contact_at_a_zero_limit_is_not_sliding),
        cmocka_unit_test(rattlers_cascade_down_a_column),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
