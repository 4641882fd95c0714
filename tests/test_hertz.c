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
 *
 * And the tangential spring, one pair driven along a path of overlaps
 * and tangential displacements: it never gives back more work than it
 * took (its stiffness follows the overlap, so it is rescaled as the
 * contact loads: dem_spring_rescale).
 */
#include "testutil.h"

#include "contact/models.h"
#include "contact/pair.h"

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

/* The time step rule bounds the Hertz dashpot too, which the damping
 * check (dem_damping_step) leaves out: its rate gamma/m* = alpha
 * omega/sqrt(1.5), omega = sqrt(dF/ddelta / m*), has alpha below about 2
 * for any restitution above 0, and at the largest step the config
 * accepts (a fifth of dem_step_time: of the impact at v_impact, and of
 * Mindlin's tangential mode, 2.2 times faster) gamma dt/m* at the
 * impact's deepest overlap stays far below 2, where the explicit dashpot
 * would reverse the velocity it damps: 0.43 at e = 0.001 (alpha 2.04),
 * and no speed grows. (At that coarse a step the restitution is 0.15,
 * not 0.001: "auto" takes a tenth of it.) */
static void the_step_rule_bounds_the_hertz_dashpot(void **state)
{
    (void)state;
    struct dem_config c;
    hertz_config(&c, 0.001);
    dem_model_hertz_derive(&c.contact);
    c.time_step = dem_step_time(&c) / 5.0;
    struct dem_sim s;
    test_sim(&s, &c, 1, 0.0, 0.1);
    test_add(&s, 0.05, 0.05, A + 1e-6, A);
    s.p.vz[0] = -c.contact.v_impact;
    test_ready(&s);
    const double m = s.p.m[0];
    double dmax = 0.0, vmax = 0.0;
    for (int k = 0; k < 2000; k++) {
        test_step(&s, 1);
        dmax = fmax(dmax, A - s.p.z[0]);
        vmax = fmax(vmax, fabs(s.p.vz[0]));
    }
    const double rate = c.contact.hertz_gn * sqrt(sqrt(A) * m) *
                        sqrt(sqrt(dmax)) * c.time_step / m;
    assert_true(c.contact.hertz_alpha > 2.0 && c.contact.hertz_alpha < 2.1);
    assert_true(dmax > 0.0 && rate > 0.3 && rate < 1.0);
    assert_true(vmax <= c.contact.v_impact);
    dem_sim_destroy(&s);
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

/* One pair, sphere i driven at a given velocity against a resting j, by
 * the engine's kernel (pair_vals): the tangential force's work on the
 * driver and the spring's energy. */
struct drive {
    double h[DEM_NHISTORY];
    int state, ci, cj;
    struct pass q;
    struct pv pi, pj;
    struct dem_contact_params cp;
    struct dem_tangential T;
    double dt;
    double work;  /* J, done by the driver against the tangential force */
    double worst; /* the least of work - energy seen, J */
    double emax;  /* the largest spring energy seen, J */
    double ft;    /* |f_t| of the last step, N */
    int slid;     /* steps that ended sliding */
};

static void drive_init(struct drive *D, double mu, double delta)
{
    memset(D, 0, sizeof *D);
    struct dem_config c;
    hertz_config(&c, 1.0); /* elastic: no dashpot, only the spring */
    c.contact.mu_s = c.contact.mu_d = mu;
    D->cp = c.contact;
    dem_contact_derive(&D->cp);
    D->T = (struct dem_tangential){D->cp.kt, D->cp.gamma_t, mu, mu};
    D->dt = 1e-6;
    D->worst = INFINITY;
    D->cj = 1;
    D->q.ci = &D->ci;
    D->q.cj = D->q.cjr = &D->cj;
    D->q.state = &D->state;
    int k = 0;
#define DRIVE_HIST_(MODEL, name, unit, swap, doc) D->q.name = &D->h[k++];
    DEM_CONTACT_HISTORY(DRIVE_HIST_)
#undef DRIVE_HIST_
    const double m = 4.0 / 3.0 * M_PI * A * A * A * 2000.0;
    D->pi = (struct pv){.r = A, .m = m};
    D->pj = (struct pv){.x = -(2.0 * A - delta), .r = A, .m = m};
}

/* Moves i by (ux, uy) in n steps at constant velocity (the drift, then
 * the force at the new positions with the velocity of the drift, as a
 * velocity-Verlet step). */
static void drive_leg(struct drive *D, double ux, double uy, int n)
{
    const double zero[6] = {0.0};
    D->pi.vx = ux / (n * D->dt);
    D->pi.vy = uy / (n * D->dt);
    for (int s = 0; s < n; s++) {
        D->pi.x += D->pi.vx * D->dt;
        D->pi.y += D->pi.vy * D->dt;
        const struct dem_contact_force o =
            pair_vals(DEM_NORMAL_HERTZ, &D->q, 0, D->pi, D->pj, &D->cp, D->dt,
                      &D->T, zero, zero);
        const double bx = D->pi.x - D->pj.x, by = D->pi.y - D->pj.y,
                     d = sqrt(bx * bx + by * by), nx = bx / d, ny = by / d;
        const double fn = o.f[0] * nx + o.f[1] * ny;
        const double ftx = o.f[0] - fn * nx, fty = o.f[1] - fn * ny;
        D->work -= (ftx * D->pi.vx + fty * D->pi.vy) * D->dt;
        const struct dem_vec3 xi = {D->q.xi_x[0], D->q.xi_y[0], D->q.xi_z[0]};
        const double e = dem_tangential_energy(xi, D->q.kt_last[0]);
        D->ft = sqrt(ftx * ftx + fty * fty);
        D->slid += (D->state & DEM_CONTACT_SLIDING) != 0;
        D->emax = e > D->emax ? e : D->emax;
        D->worst = D->work - e < D->worst ? D->work - e : D->worst;
    }
}

/* The pair's overlap, m. */
static double drive_overlap(const struct drive *D)
{
    const double bx = D->pi.x - D->pj.x, by = D->pi.y - D->pj.y;
    return 2.0 * A - sqrt(bx * bx + by * by);
}

/* Presses i by dd towards j along their normal in n steps (dd < 0:
 * draws it away), so that the tangential spring is not stretched. */
static void drive_press(struct drive *D, double dd, int n)
{
    const double bx = D->pi.x - D->pj.x, by = D->pi.y - D->pj.y,
                 d = sqrt(bx * bx + by * by);
    drive_leg(D, -dd * bx / d, -dd * by / d, n);
}

/* A spring stretched at overlap delta and the contact then loaded to 4
 * delta keeps its force (k_t doubles, the spring halves); unloaded back
 * to delta, the force halves with k_t (the spring kept). Round the
 * cycle stretch, load, stretch back, unload, the driver has put in at
 * least the energy the spring holds, at every step: with the spring kept
 * as a displacement at the current k_t, stretching it back at 4 delta
 * gave twice the work that stretching it at delta took. Again with
 * friction that lets it slide, over cycles of other sizes. */
static void tangential_spring_gives_back_no_more_than_it_took(void **state)
{
    (void)state;
    const double d1 = 1e-5, s1 = 2e-6; /* m: f_t / f_n about 0.26 */
    struct drive D;
    drive_init(&D, 10.0, d1);
    drive_leg(&D, 0.0, s1, 200);
    const double f1 = D.ft, w1 = D.work;
    assert_rel(w1, 0.5 * f1 * s1, 0.01); /* 1/2 k_t s^2 */
    drive_press(&D, 3.0 * d1, 200);      /* loaded to 4 delta */
    const double d4 = drive_overlap(&D);
    print_message("stretched at delta: |f_t| = %.6g N; loaded to 4 delta: "
                  "%.6g N\n",
                  f1, D.ft);
    assert_rel(D.ft, f1, 1e-6);
    assert_true(D.emax <= w1 * (1.0 + 1e-9));
    drive_press(&D, -3.0 * d1, 200); /* and back */
    print_message("unloaded to delta: %.6g N\n", D.ft);
    /* k_t falls as sqrt(delta): the force to about half (the stretch
     * moved i off its line and left an overlap s^2/(2 d) below delta) */
    assert_rel(D.ft, f1 * sqrt(drive_overlap(&D) / d4), 1e-9);
    assert_rel(D.ft, 0.5 * f1, 1e-4);
    drive_press(&D, 3.0 * d1, 200);
    drive_leg(&D, 0.0, -s1, 200); /* stretched back at 4 delta */
    drive_press(&D, -3.0 * d1, 200);
    print_message("cycle: work put in %.6g J, least margin over the "
                  "spring's energy %.3g J\n",
                  D.work, D.worst);
    assert_true(D.worst >= -1e-9 * D.emax && D.slid == 0);
    assert_true(D.work > 0.2 * w1); /* most of it still held */
    /* cycles of other sizes, sticking (mu = 10) and sliding (mu = 0.3) */
    for (int f = 0; f < 2; f++) {
        drive_init(&D, f ? 0.3 : 10.0, d1);
        for (int c = 1; c <= 6; c++) {
            const double dd = d1 * c / 2.0, ss = s1 * (c % 3 + 1) / 2.0;
            drive_leg(&D, 0.0, ss, 100);
            drive_press(&D, dd, 100);
            drive_leg(&D, 0.0, -2.0 * ss, 100);
            drive_press(&D, -dd, 100);
            drive_leg(&D, 0.0, ss, 100);
        }
        print_message("mu = %g: work put in %.6g J, least margin %.3g J, "
                      "largest energy %.3g J, %d of 3000 steps sliding\n",
                      f ? 0.3 : 10.0, D.work, D.worst, D.emax, D.slid);
        assert_true(D.worst >= -1e-9 * D.emax && D.emax > 0.0);
        assert_true(f ? D.slid > 100 : D.slid == 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(derived_damping_inverts_the_restitution),
        cmocka_unit_test(the_step_rule_bounds_the_hertz_dashpot),
        cmocka_unit_test(elastic_collision_lasts_the_hertz_time),
        cmocka_unit_test(restitution_is_the_one_asked_for_at_any_speed),
        cmocka_unit_test(tangential_spring_gives_back_no_more_than_it_took),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
