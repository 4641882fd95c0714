/* Friction never creates energy: the tangential spring must hold the
 * displacement at the time of its force (src/contact/tangential.h). A
 * spring that lags one step behind the positions adds a force k_t dt v_t,
 * a negative damping of k_t dt = 0.02 kg/s at the papers' k_t = 1000 N/m
 * and dt = 2e-5 s, larger than their gamma_t = 0.01 kg/s. Every case here
 * runs at those parameters with gamma_t zero or small, where such a lag
 * shows at once.
 *
 * The energy that velocity Verlet keeps is the leapfrog energy
 *   E_n = sum 1/2 m v(n-1/2).v(n+1/2) + 1/2 I w(n-1/2).w(n+1/2) + U(x_n),
 * with v(n -+ 1/2) = v_n -+ dt F_n/(2m): for any system of linear springs
 * (here: a sphere sticking on a plane, whose springs are linear in the
 * positions) it is conserved exactly, and dashpots and sliding only lower
 * it. In terms of the synchronised velocities after a step,
 *   E_n = E_kin + E_rot - sum dt^2 (|F|^2/(8 m) + |T|^2/(8 I)) + U.
 * The plain total energy E_kin + E_rot + U oscillates by O((w dt)^2)
 * instead, which would hide a slow gain. */
#include "testutil.h"

#include "core/rng.h"
#include "measure/measure.h"

static double mass(double a)
{
    return 4.0 / 3.0 * M_PI * 2000.0 * a * a * a;
}

/* One unchained step with measurement: the forces and torques of the new
 * positions are stored and s->sums holds the contacts' elastic energy. */
static void step_measured(struct dem_sim *s)
{
    struct dem_error err = {0};
    s->measure = 1;
    if (dem_sim_step(s, &err))
        fail_msg("step %ld: %s", s->step, err.msg);
}

/* Leapfrog energy (see the file comment), J, with the gravitational
 * energy measured from height z_ref. */
static double leapfrog_energy(const struct dem_sim *s, double z_ref)
{
    const struct dem_particles *P = &s->p;
    const double *g = s->cfg.gravity, h2 = s->dt * s->dt / 8.0;
    double e = s->sums.e_pot;
    for (int i = 0; i < P->n; i++) {
        const double m = P->m[i], iI = P->inv_I[i];
        const double F[3] = {P->fx[i] + m * g[0], P->fy[i] + m * g[1],
                             P->fz[i] + m * g[2]};
        const double v2 =
            P->vx[i] * P->vx[i] + P->vy[i] * P->vy[i] + P->vz[i] * P->vz[i];
        const double w2 =
            P->wx[i] * P->wx[i] + P->wy[i] * P->wy[i] + P->wz[i] * P->wz[i];
        const double F2 = F[0] * F[0] + F[1] * F[1] + F[2] * F[2];
        const double T2 =
            P->tx[i] * P->tx[i] + P->ty[i] * P->ty[i] + P->tz[i] * P->tz[i];
        e += 0.5 * m * v2 - h2 * F2 / m + 0.5 * w2 / iI - h2 * T2 * iI;
        e -= m * (g[0] * P->x[i] + g[1] * P->y[i] + g[2] * (P->z[i] - z_ref));
    }
    return e;
}

/* David et al.'s material at the papers' time step, friction on, no
 * background damping. */
static void papers_material(struct dem_config *c, double gamma_t)
{
    test_config(c, 3);
    c->time_step = 2e-5;
    c->contact.kt = 1000.0;
    c->contact.gamma_n = 0.05;
    c->contact.gamma_t = gamma_t;
    c->contact.mu_s = c->contact.mu_d = 0.5;
    c->contact.wall_mu = 0.4;
}

/* A sphere of radius a resting on the z-min wall of a large box, at its
 * equilibrium overlap, launched along x at v0 without spin. */
static void sphere_on_floor(struct dem_sim *s, const struct dem_config *c,
                            double v0)
{
    const double a = 5e-3, m = mass(a);
    test_sim(s, c, 1, 0.0, 1.0);
    test_add(s, 0.1, 0.5, a + m * c->gravity[2] / c->contact.k, a);
    s->p.vx[0] = v0;
    test_ready(s);
}

/* Launched at 0.1 m/s, the sphere slides for 7 ms and then rolls: the
 * energy falls while it slides and then stays. Launched at 1 mm/s, it
 * never slides: the tangential spring
 * stops the contact point and then swings it to and fro (amplitude 0.5
 * um, force 0.13 mu m g). With gamma_t = 0 nothing damps this
 * oscillation, so a lagging spring pumps it up exponentially, until the
 * contact slides (the sphere ends rolling backwards at 1.2 v0, with 17
 * times its launch energy). The leapfrog energy must never rise: seen
 * here at most 3e-24 J (gamma_t = 0, round-off) and 1.6e-18 J per step
 * (gamma_t > 0: the dashpot uses the half-step velocity, which costs a
 * third-order error where the oscillation turns) against 5.2e-10 J of
 * kinetic energy at launch; a lagging spring gains up to 1e-8 J in a
 * step. */
static void rolling_sphere_never_gains_energy(void **state)
{
    (void)state;
    const double gammas[] = {0.0, 1e-3, 0.0, 1e-3};
    const double speeds[] = {1e-3, 1e-3, 0.1, 0.1};
    for (int g = 0; g < 4; g++) {
        struct dem_config c;
        papers_material(&c, gammas[g]);
        c.gravity[2] = -9.81;
        const double v0 = speeds[g];
        struct dem_sim s;
        sphere_on_floor(&s, &c, v0);
        step_measured(&s);
        const double z_ref = s.p.z[0];
        double e_prev = leapfrog_energy(&s, z_ref), e0 = e_prev;
        const double e_kin0 = 0.5 * s.p.m[0] * v0 * v0;
        double worst = -INFINITY;
        for (int k = 0; k < 50000; k++) {
            step_measured(&s);
            const double e = leapfrog_energy(&s, z_ref);
            if (e - e_prev > worst)
                worst = e - e_prev;
            e_prev = e;
        }
        print_message("v0 = %g m/s, gamma_t = %g: largest rise per step "
                      "%.3g J, E(1 s) - E(0) = %.3g J, E_kin(0) = %.3g J, "
                      "v/v0 = %.4f\n",
                      v0, gammas[g], worst, e_prev - e0, e_kin0,
                      s.p.vx[0] / v0);
        assert_true(worst <= 1e-6 * e_kin0);
        assert_true(e_prev <= e0 + 1e-9 * e_kin0);
        dem_sim_destroy(&s);
    }
}

/* A sphere launched at v0 = 0.1 m/s without spin on a frictional floor
 * slides for 2 v0/(7 mu g) = 7.3 ms, then rolls at 5/7 v0 with a w = v
 * (Coulomb friction decelerates it while its torque spins it up; after
 * that the angular momentum about the contact line is conserved). Checked
 * for k_t dt / gamma_t = 0.1, 1 and 10; a lagging spring, whose negative
 * damping k_t dt exceeds gamma_t from 1 on, ends faster than 5/7 v0. The
 * rolling velocity still carries the spring's lightly damped oscillation,
 * so v and w are averaged over the last 20 ms (6 of its periods). */
static void sliding_sphere_ends_rolling_at_five_sevenths(void **state)
{
    (void)state;
    const double ratios[] = {0.1, 1.0, 10.0};
    for (int q = 0; q < 3; q++) {
        struct dem_config c;
        papers_material(&c, 1000.0 * 2e-5 / ratios[q]);
        c.gravity[2] = -9.81;
        const double v0 = 0.1, a = 5e-3;
        struct dem_sim s;
        sphere_on_floor(&s, &c, v0);
        test_step(&s, 100000); /* 2 s */
        double v = 0.0, w = 0.0;
        const int n = 1000;
        for (int k = 0; k < n; k++) {
            test_step(&s, 1);
            v += s.p.vx[0] / n;
            w += s.p.wy[0] / n;
        }
        print_message("k_t dt/gamma_t = %g: v/v0 = %.5f (5/7 = %.5f), a w/v "
                      "= %.5f\n",
                      ratios[q], v / v0, 5.0 / 7.0, a * w / v);
        assert_rel(v, 5.0 / 7.0 * v0, 1e-3);
        /* rolling in +x on a floor below: w_y = +v/a */
        assert_rel(a * w, v, 1e-3);
        assert_close(s.p.vy[0], 0.0, 1e-12);
        dem_sim_destroy(&s);
    }
}

/* Two spheres (radii 5 and 4 mm) collide obliquely, the second one
 * spinning, with gamma_n = 0: the normal spring is conservative, and the
 * tangential spring (gamma_t zero or small) sticks for most of the
 * contact, so the energy can only fall, during the contact and after it.
 * Impact parameters from near head-on to grazing, two spins. */
static void oblique_collision_returns_no_more_energy(void **state)
{
    (void)state;
    const double gammas[] = {0.0, 1e-3};
    const double offsets[] = {0.2, 0.5, 0.8}; /* impact parameter / (a1+a2) */
    const double spins[] = {0.0, 40.0};       /* rad/s, about z */
    for (int g = 0; g < 2; g++)
        for (int o = 0; o < 3; o++)
            for (int w = 0; w < 2; w++) {
                struct dem_config c;
                papers_material(&c, gammas[g]);
                c.contact.gamma_n = 0.0;
                const double a1 = 5e-3, a2 = 4e-3, v0 = 0.1;
                struct dem_sim s;
                test_sim(&s, &c, 2, -0.2, 0.2);
                test_add(&s, -a1 - 1e-4, 0.0, 0.0, a1);
                test_add(&s, a2 + 1e-4, offsets[o] * (a1 + a2), 0.0, a2);
                s.p.vx[0] = v0;
                s.p.wz[1] = spins[w];
                test_ready(&s);
                step_measured(&s);
                const double e0 = leapfrog_energy(&s, 0.0);
                double e_max = e0;
                int touched = 0;
                for (int k = 0; k < 2000; k++) {
                    step_measured(&s);
                    const double e = leapfrog_energy(&s, 0.0);
                    e_max = e > e_max ? e : e_max;
                    touched |= s.sums.n_pp > 0;
                }
                const double e1 = leapfrog_energy(&s, 0.0);
                assert_true(touched);
                assert_int_equal(s.sums.n_pp, 0); /* apart again */
                print_message("gamma_t = %g, b = %.1f, w = %g: E1/E0 - 1 = "
                              "%.3g, max E/E0 - 1 = %.3g\n",
                              gammas[g], offsets[o], spins[w], e1 / e0 - 1.0,
                              e_max / e0 - 1.0);
                /* seen at most 3.6e-6 (a grazing contact opening and
                 * closing); a lagging spring reaches 6e-4 to 1.3e-2 */
                assert_true(e_max <= e0 * (1.0 + 1e-4));
                assert_true(e1 <= e0);
                dem_sim_destroy(&s);
            }
}

/* A dense packing of 125 spheres, squeezed in a closed box and relaxed
 * with background damping, is then given a small random kick and left to
 * itself without damping: its contacts stay closed and stick, so nothing
 * can raise the leapfrog energy but contacts that open or close (an
 * integrator error at each). A lagging spring makes such a packing
 * self-excited: contacts start to slide and the energy jumps. */
static void packing_left_alone_never_gains_energy(void **state)
{
    (void)state;
    const double gammas[] = {0.0, 1e-3};
    for (int g = 0; g < 2; g++) {
        struct dem_config c;
        papers_material(&c, gammas[g]);
        c.damping.gamma_b = 0.05;
        c.damping.gamma_br = 0.05;
        struct dem_sim s;
        const int nside = 5;
        const double h = 0.05 / nside;
        test_sim(&s, &c, nside * nside * nside, 0.0, 0.05);
        struct dem_rng rng;
        dem_rng_seed(&rng, 7);
        for (int k = 0; k < nside; k++)
            for (int j = 0; j < nside; j++)
                for (int i = 0; i < nside; i++) {
                    const double r =
                        0.52 * h * (0.95 + 0.1 * dem_rng_uniform(&rng));
                    test_add(&s, (i + 0.5) * h, (j + 0.5) * h, (k + 0.5) * h,
                             r);
                }
        test_ready(&s);
        test_step(&s, 20000); /* relax with background damping */
        s.cfg.damping.gamma_b = 0.0;
        s.cfg.damping.gamma_br = 0.0;
        /* a small kick so that every contact works */
        for (int i = 0; i < s.p.n; i++) {
            s.p.vx[i] += 1e-4 * (2 * dem_rng_uniform(&rng) - 1);
            s.p.wy[i] += 1e-2 * (2 * dem_rng_uniform(&rng) - 1);
        }
        step_measured(&s);
        const double e0 = leapfrog_energy(&s, 0.0);
        double worst = -INFINITY, e = e0, e_prev = e0;
        for (int k = 0; k < 20000; k++) {
            step_measured(&s);
            e = leapfrog_energy(&s, 0.0);
            worst = e - e_prev > worst ? e - e_prev : worst;
            e_prev = e;
        }
        print_message("gamma_t = %g: E0 = %.4g J (E_pot %.3g), E(0.4 s)/E0 - "
                      "1 = %.3g, largest rise per step %.3g J, Z = %.2f, "
                      "sliding %ld\n",
                      gammas[g], e0, s.sums.e_pot, e / e0 - 1.0, worst,
                      2.0 * (double)s.sums.n_pp / s.p.n, s.sums.n_sliding);
        /* seen: E falls by 1.7e-9 E0, rises at most by 5e-16 J in a step;
         * a lagging spring: rises by 4e-4 J in a step */
        assert_true(e <= e0);
        assert_true(worst <= 1e-9 * e0);
        dem_sim_destroy(&s);
    }
}

/* 64 spheres of config c on a 4 x 4 x 4 lattice, slightly pressed,
 * with random velocities and spins (about z, and about x too with
 * spin_x), run 2000 steps: their positions and spins into x[64 * 6],
 * the elastic energy of the last step into *e_pot. */
static void run_64(const struct dem_config *c, int spin_x, double *x,
                   double *e_pot)
{
    struct dem_sim s;
    test_sim(&s, c, 64, 0.0, 0.04);
    struct dem_rng rng;
    dem_rng_seed(&rng, 3);
    for (int k = 0; k < 64; k++) {
        const int id =
            test_add(&s, 0.005 + 0.01 * (k % 4), 0.005 + 0.01 * (k / 4 % 4),
                     0.005 + 0.01 * (k / 16), 5.2e-3);
        s.p.vx[id] = 0.05 * (2 * dem_rng_uniform(&rng) - 1);
        s.p.wz[id] = 5.0 * (2 * dem_rng_uniform(&rng) - 1);
        if (spin_x)
            s.p.wx[id] = 5.0 * (2 * dem_rng_uniform(&rng) - 1);
    }
    test_ready(&s);
    test_step(&s, 2000);
    step_measured(&s);
    *e_pot = s.sums.e_pot;
    assert_true(s.sums.n_pp > 0 && *e_pot > 0.0);
    for (int i = 0; i < 64; i++) {
        const double v[6] = {s.p.x[i],  s.p.y[i],  s.p.z[i],
                             s.p.wx[i], s.p.wy[i], s.p.wz[i]};
        memcpy(&x[6 * i], v, sizeof v);
    }
    dem_sim_destroy(&s);
}

/* Without friction the tangential force is zero whatever k_t is, so a
 * frictionless run with k_t = 0 (accepted by the config) and one with
 * k_t = 1000 N/m are the same bit for bit, and so is their elastic
 * energy: a frictionless contact's spring holds the dashpot's share
 * -gamma_t v_t/k_t (dem_coulomb_spring_in) but no energy (counted, it
 * was 1/2 gamma_t^2 v_t^2/k_t a contact with k_t = 1000 N/m and 0 with
 * k_t = 0). */
static void frictionless_runs_do_not_depend_on_kt(void **state)
{
    (void)state;
    double x[2][64 * 6], e_pot[2];
    const double kts[] = {0.0, 1000.0};
    for (int q = 0; q < 2; q++) {
        struct dem_config c;
        papers_material(&c, 0.01);
        c.contact.kt = kts[q];
        c.contact.mu_s = c.contact.mu_d = c.contact.wall_mu = 0.0;
        run_64(&c, 0, x[q], &e_pot[q]);
    }
    assert_memory_equal(x[0], x[1], sizeof x[0]);
    assert_memory_equal(&e_pot[0], &e_pot[1], sizeof e_pot[0]);
}

/* The same for the rolling and torsion resistances at a zero limit (mu_r
 * = mu_o = 0, the walls' defaults): no torque whatever their springs'
 * stiffness, the same run bit for bit with k_r = k_o = 20 and 2000, and
 * the same elastic energy (counted, their springs' dashpot shares were
 * 1/2 gamma^2 v^2/k a contact). */
static void resistances_at_a_zero_limit_store_no_energy(void **state)
{
    (void)state;
    double x[2][64 * 6], e_pot[2];
    const double ks[] = {20.0, 2000.0};
    for (int q = 0; q < 2; q++) {
        struct dem_config c;
        papers_material(&c, 0.5);
        c.contact.rolling = c.contact.torsion = DEM_RESIST_LUDING;
        c.contact.kr = c.contact.ko = ks[q];
        c.contact.gamma_r = c.contact.gamma_o = 0.01;
        c.contact.mu_r = c.contact.mu_o = 0.0;
        c.contact.wall_mu_r = c.contact.wall_mu_o = 0.0;
        run_64(&c, 1, x[q], &e_pot[q]);
    }
    assert_memory_equal(x[0], x[1], sizeof x[0]);
    assert_memory_equal(&e_pot[0], &e_pot[1], sizeof e_pot[0]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rolling_sphere_never_gains_energy),
        cmocka_unit_test(sliding_sphere_ends_rolling_at_five_sevenths),
        cmocka_unit_test(oblique_collision_returns_no_more_energy),
        cmocka_unit_test(packing_left_alone_never_gains_energy),
        cmocka_unit_test(frictionless_runs_do_not_depend_on_kt),
        cmocka_unit_test(resistances_at_a_zero_limit_store_no_energy),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
