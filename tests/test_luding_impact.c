/* Hysteretic adhesive contact (Luding) through the full engine
 * (dem_sim_step): head-on impacts of a pair and against a wall compared
 * with the analytic restitution, the capture threshold, a prescribed
 * overlap path of a wall contact, and the phi_f refinement.
 *
 * Without viscosity a head-on impact loads along k1 to delta_max and
 * unloads along the k2 line and the adhesive branch -kc delta
 * (docs/physics.md); for constant k2
 *   r^2 = k1/k2 - kc (k2 - k1)^2 / (k1 k2 (k2 + kc)),
 * capture for kc >= k1^2/(k2 - 2 k1). Expected values are computed here
 * from these formulas; the kernel helpers of contact/luding.h are only
 * used where a test says so, and then checked against the closed form. */
#include "testutil.h"

#include "contact/luding.h"

static const double RHO = 2000.0; /* kg/m^3 (test_config) */

/* Relative tolerance of a restitution coefficient. With dt = t_c/2000 the
 * engine agrees with the analytic values to ~1e-7 (~1e-6 for the small
 * r = 0.14 near capture); 1e-4 still leaves a wide margin. */
static const double R_TOL = 1e-4;

static double mass(double a)
{
    return 4.0 / 3.0 * M_PI * RHO * a * a * a;
}

/* Closed form of docs/physics.md for constant k2 (may be negative). */
static double closed_r2(double k1, double k2, double kc)
{
    return k1 / k2 - kc * (k2 - k1) * (k2 - k1) / (k1 * k2 * (k2 + kc));
}

/* Luding config without viscosity and friction; time step t_c/2000 with
 * t_c = pi sqrt(m/k2) of reduced mass m. */
static void luding_config(struct dem_config *c, double k1, double k2, double kc,
                          double wall_kc, double phi, double m)
{
    test_config(c, 3);
    c->contact.normal = DEM_NORMAL_LUDING;
    c->contact.k1 = k1;
    c->contact.k2 = k2;
    c->contact.kc = kc;
    c->contact.wall_kc = wall_kc;
    c->contact.phi_f = phi;
    c->contact.gamma_n = 0.0;
    c->contact.kt = 0.0;
    c->contact.mu_s = 0.0;
    c->contact.mu_d = 0.0;
    c->time_step = M_PI * sqrt(m / k2) / 2000.0;
}

struct impact {
    double vrel;    /* m/s; relative normal velocity after the contact,
                       > 0 separating (0 if captured) */
    int separated;  /* 1 if the contact ended within the time limit */
    double tc;      /* s; contact duration (if separated) */
    double pmax;    /* kg m/s; largest |total momentum| along the run */
    double min_gap; /* m; smallest gap after the first contact */
    double max_gap; /* m; largest gap after the first contact, until the
                       contact ends (< 0: stayed in contact) */
    /* over the second half of a run that reached tmax (captured):
     * smallest and largest overlap and largest |relative velocity| */
    double late_dlo, late_dhi, late_vmax;
};

#define IMPACT_INIT                                                            \
    {                                                                          \
        0.0, 0, 0.0, 0.0, INFINITY, -INFINITY, INFINITY, -INFINITY, 0.0        \
    }

static void late_sample(struct impact *I, double gap, double v)
{
    if (-gap < I->late_dlo)
        I->late_dlo = -gap;
    if (-gap > I->late_dhi)
        I->late_dhi = -gap;
    if (fabs(v) > I->late_vmax)
        I->late_vmax = fabs(v);
}

/* Head-on pair impact at relative speed v0 in the centre-of-mass frame,
 * radii a1 (left) and a2 (right); runs until the contact ends or tmax
 * after first contact. */
static struct impact pair_impact(const struct dem_config *c, double a1,
                                 double a2, double v0, double tmax)
{
    struct impact out = IMPACT_INIT;
    struct dem_sim s;
    test_sim(&s, c, 2, -0.1, 0.1);
    test_add(&s, -a1 - 1e-7, 0, 0, a1);
    test_add(&s, a2 + 1e-7, 0, 0, a2);
    const double m1 = s.p.m[0], m2 = s.p.m[1];
    assert_rel(m1, mass(a1), 1e-14);
    assert_rel(m2, mass(a2), 1e-14);
    s.p.vx[0] = v0 * m2 / (m1 + m2);
    s.p.vx[1] = -v0 * m1 / (m1 + m2);
    test_ready(&s);
    double t_in = -1.0;
    for (long k = 0; k < 100000000; k++) {
        test_step(&s, 1);
        double p = fabs(m1 * s.p.vx[0] + m2 * s.p.vx[1]);
        if (p > out.pmax)
            out.pmax = p;
        double gap = s.p.x[1] - s.p.x[0] - a1 - a2;
        if (gap < 0.0 && t_in < 0.0)
            t_in = s.t;
        if (t_in < 0.0)
            continue;
        if (gap < out.min_gap)
            out.min_gap = gap;
        if (gap > out.max_gap)
            out.max_gap = gap;
        if (gap >= 0.0) {
            out.separated = 1;
            out.tc = s.t - t_in;
            break;
        }
        if (s.t - t_in > 0.5 * tmax)
            late_sample(&out, gap, s.p.vx[1] - s.p.vx[0]);
        if (s.t - t_in > tmax)
            break;
    }
    assert_true(t_in >= 0.0);
    out.vrel = s.p.vx[1] - s.p.vx[0];
    /* the pair moves only along x */
    assert_close(s.p.vy[0], 0.0, 0.0);
    assert_close(s.p.vz[1], 0.0, 0.0);
    dem_sim_destroy(&s);
    return out;
}

/* A sphere of radius a hits the fixed x-min wall at speed v0. */
static struct impact wall_impact(const struct dem_config *c, double a,
                                 double v0, double tmax)
{
    struct impact out = IMPACT_INIT;
    struct dem_sim s;
    test_sim(&s, c, 1, 0.0, 0.1);
    test_add(&s, a + 1e-7, 0.05, 0.05, a);
    assert_rel(s.p.m[0], mass(a), 1e-14);
    s.p.vx[0] = -v0;
    test_ready(&s);
    double t_in = -1.0;
    for (long k = 0; k < 100000000; k++) {
        test_step(&s, 1);
        double gap = s.p.x[0] - a;
        if (gap < 0.0 && t_in < 0.0)
            t_in = s.t;
        if (t_in < 0.0)
            continue;
        if (gap < out.min_gap)
            out.min_gap = gap;
        if (gap > out.max_gap)
            out.max_gap = gap;
        if (gap >= 0.0) {
            out.separated = 1;
            out.tc = s.t - t_in;
            break;
        }
        if (s.t - t_in > 0.5 * tmax)
            late_sample(&out, gap, s.p.vx[0]);
        if (s.t - t_in > tmax)
            break;
    }
    assert_true(t_in >= 0.0);
    out.vrel = s.p.vx[0];
    /* the fixed wall did not move */
    assert_close(s.wall[0].pos, 0.0, 0.0);
    dem_sim_destroy(&s);
    return out;
}

/* A captured impact (r^2 < 0, constant k2) unloads along the k2 line and
 * the adhesive branch and stops on -kc delta at delta_s, where the
 * missing energy r^2 E_in equals the work -kc delta_s^2/2 still needed to
 * separate: delta_s = delta_max sqrt(-r^2 k1/kc) (valid when delta_s <
 * delta_min). The re-mapped line then passes through (delta_s, -kc delta_s)
 * with delta_0 = (k2 + kc) delta_s/k2 and the contact oscillates
 * elastically on it between delta_s and 2 delta_0 - delta_s, forever (no
 * dashpot), with speed amplitude sqrt(k2/m) (delta_0 - delta_s). */
static void check_captured(const struct impact *I, double k1, double k2,
                           double kc, double m, double v0)
{
    assert_false(I->separated);
    /* the contact never opened after the first touch */
    assert_true(I->max_gap < 0.0);
    const double dmax = v0 * sqrt(m / k1);
    const double r2 = closed_r2(k1, k2, kc);
    assert_true(r2 < 0.0);
    const double ds = dmax * sqrt(-r2 * k1 / kc);
    const double dmin = k2 * (1.0 - k1 / k2) * dmax / (k2 + kc);
    assert_true(ds < dmin);
    const double d0 = (k2 + kc) / k2 * ds;
    const double vamp = sqrt(k2 / m) * (d0 - ds);
    assert_rel(-I->min_gap, dmax, 2e-3);
    assert_rel(I->late_dlo, ds, 2e-3);
    assert_rel(I->late_dhi, 2.0 * d0 - ds, 2e-3);
    /* the relative speed left is the small oscillation in the well */
    assert_true(I->late_vmax <= 1.02 * vamp);
    assert_true(I->late_vmax >= 0.9 * vamp);
    assert_true(vamp < 0.05 * v0);
    printf("  captured: overlap oscillates in [%.6g, %.6g] m (analytic "
           "[%.6g, %.6g]), |v_rel| <= %.4g m/s (analytic %.4g, v0 %.2g)\n",
           I->late_dlo, I->late_dhi, ds, 2.0 * d0 - ds, I->late_vmax, vamp, v0);
}

/* ---- pair -------------------------------------------------------------- */

static const double A1 = 5e-3, A2 = 3.5e-3; /* m; mass ratio 2.9 */

static double pair_mij(void)
{
    return mass(A1) * mass(A2) / (mass(A1) + mass(A2));
}

/* Contact duration without adhesion at speed v0: a quarter period on k1
 * in, a quarter period on k2 out to the force-free overlap delta_0, then
 * free flight over delta_0 at the rebound speed. */
static double tc_no_adhesion(double k1, double k2, double m, double v0)
{
    double d0 = (1.0 - k1 / k2) * v0 * sqrt(m / k1);
    return 0.5 * M_PI * (sqrt(m / k1) + sqrt(m / k2)) +
           d0 / (sqrt(k1 / k2) * v0);
}

/* 1. kc = 0: r = sqrt(k1/k2), at two speeds (independent of v0). */
static void pair_no_adhesion_rebounds_with_sqrt_k1_over_k2(void **state)
{
    (void)state;
    const double k1 = 5e4, k2 = 1e5, m = pair_mij();
    struct dem_config c;
    luding_config(&c, k1, k2, 0.0, 0.0, 0.0, m);
    const double speeds[2] = {0.3, 1.0};
    for (int i = 0; i < 2; i++) {
        const double v0 = speeds[i];
        struct impact I = pair_impact(&c, A1, A2, v0, 1.0);
        assert_true(I.separated);
        assert_rel(I.vrel / v0, sqrt(k1 / k2), R_TOL);
        assert_close(I.tc, tc_no_adhesion(k1, k2, m, v0), 2.0 * c.time_step);
        /* delta_max = v0 sqrt(m/k1) */
        assert_rel(-I.min_gap, v0 * sqrt(m / k1), 2e-3);
        assert_true(I.pmax <= 1e-14 * mass(A1) * v0);
        printf("  pair kc=0 v0=%.2f: r = %.10f (analytic %.10f, rel err "
               "%.2e), |p| <= %.2e kg m/s\n",
               v0, I.vrel / v0, sqrt(k1 / k2),
               I.vrel / v0 / sqrt(k1 / k2) - 1.0, I.pmax);
    }
}

/* 2. kc > 0: r from dem_luding_restitution and from the closed form. */
static void pair_adhesion_rebound_matches_closed_form(void **state)
{
    (void)state;
    const double k1 = 5e4, k2 = 1e5, kc = 2e4, v0 = 0.5, m = pair_mij();
    const double a12 = A1 * A2 / (A1 + A2);
    struct dem_config c;
    luding_config(&c, k1, k2, kc, 0.0, 0.0, m);
    const struct dem_luding L = {k1, k2, kc, 0.0};
    const double r_closed = sqrt(closed_r2(k1, k2, kc));
    const double r_kernel = dem_luding_restitution(v0, m, &L, a12);
    assert_rel(r_kernel, r_closed, 1e-12);
    assert_true(r_closed < sqrt(k1 / k2) - 0.05); /* adhesion matters */
    struct impact I = pair_impact(&c, A1, A2, v0, 1.0);
    assert_true(I.separated);
    assert_rel(I.vrel / v0, r_kernel, R_TOL);
    assert_rel(I.vrel / v0, r_closed, R_TOL);
    assert_true(I.pmax <= 1e-14 * mass(A1) * v0);
    printf("  pair kc=%.0f: r = %.10f (closed form %.10f, rel err %.2e)\n", kc,
           I.vrel / v0, r_closed, I.vrel / v0 / r_closed - 1.0);
}

/* 3. small k1/k2: captured above the threshold, rebound below it. */
static void pair_capture_threshold(void **state)
{
    (void)state;
    const double k1 = 1e4, k2 = 1e5, v0 = 0.5, m = pair_mij();
    const struct dem_luding L0 = {k1, k2, 0.0, 0.0};
    const double kcs = k1 * k1 / (k2 - 2.0 * k1);
    assert_rel(dem_luding_capture_kc(&L0), kcs, 1e-14);
    /* threshold: r^2 = 0 there */
    assert_close(closed_r2(k1, k2, kcs), 0.0, 1e-14);
    const double tmax = 200.0 * M_PI * sqrt(m / k1); /* 100 k1 periods */

    /* 1.2 x threshold: the pair never separates */
    struct dem_config c;
    luding_config(&c, k1, k2, 1.2 * kcs, 0.0, 0.0, m);
    struct impact I = pair_impact(&c, A1, A2, v0, tmax);
    printf("  pair kc=1.2 kc*, %.3g s:\n", tmax);
    check_captured(&I, k1, k2, 1.2 * kcs, m, v0);
    assert_true(I.pmax <= 1e-14 * mass(A1) * v0);

    /* 0.8 x threshold: rebound with the (small) analytic r */
    luding_config(&c, k1, k2, 0.8 * kcs, 0.0, 0.0, m);
    const double r = sqrt(closed_r2(k1, k2, 0.8 * kcs));
    I = pair_impact(&c, A1, A2, v0, tmax);
    assert_true(I.separated);
    assert_rel(I.vrel / v0, r, R_TOL);
    assert_true(I.pmax <= 1e-14 * mass(A1) * v0);
    printf("  pair kc=0.8 kc*: r = %.10f (analytic %.10f, rel err %.2e)\n",
           I.vrel / v0, r, I.vrel / v0 / r - 1.0);
}

/* ---- wall -------------------------------------------------------------- */

/* 4. the same checks against the fixed x-min wall: m_ij = m, a12 = a,
 * adhesion from wall_kc (the pair kc is set to a different value that
 * must not be used). */
static void wall_impacts_match_analytic(void **state)
{
    (void)state;
    const double a = 5e-3, m = mass(a), v0 = 0.5;
    struct dem_config c;

    /* no adhesion */
    double k1 = 5e4, k2 = 1e5;
    luding_config(&c, k1, k2, 3e4, 0.0, 0.0, m);
    struct impact I = wall_impact(&c, a, v0, 1.0);
    assert_true(I.separated);
    assert_rel(I.vrel / v0, sqrt(k1 / k2), R_TOL);
    assert_close(I.tc, tc_no_adhesion(k1, k2, m, v0), 2.0 * c.time_step);
    assert_rel(-I.min_gap, v0 * sqrt(m / k1), 2e-3);
    printf("  wall kc=0: r = %.10f (analytic %.10f, rel err %.2e)\n",
           I.vrel / v0, sqrt(k1 / k2), I.vrel / v0 / sqrt(k1 / k2) - 1.0);

    /* adhesion */
    const double kc = 2e4;
    luding_config(&c, k1, k2, 0.0, kc, 0.0, m);
    const struct dem_luding L = {k1, k2, kc, 0.0};
    const double r_closed = sqrt(closed_r2(k1, k2, kc));
    const double r_kernel = dem_luding_restitution(v0, m, &L, a);
    assert_rel(r_kernel, r_closed, 1e-12);
    I = wall_impact(&c, a, v0, 1.0);
    assert_true(I.separated);
    assert_rel(I.vrel / v0, r_kernel, R_TOL);
    assert_rel(I.vrel / v0, r_closed, R_TOL);
    printf("  wall kc=%.0f: r = %.10f (closed form %.10f, rel err %.2e)\n", kc,
           I.vrel / v0, r_closed, I.vrel / v0 / r_closed - 1.0);

    /* capture threshold */
    k1 = 1e4;
    const double kcs = k1 * k1 / (k2 - 2.0 * k1);
    const double tmax = 200.0 * M_PI * sqrt(m / k1);
    luding_config(&c, k1, k2, 0.0, 1.2 * kcs, 0.0, m);
    I = wall_impact(&c, a, v0, tmax);
    printf("  wall kc=1.2 kc*, %.3g s:\n", tmax);
    check_captured(&I, k1, k2, 1.2 * kcs, m, v0);

    luding_config(&c, k1, k2, 100.0 * kcs, 0.8 * kcs, 0.0, m);
    const double r = sqrt(closed_r2(k1, k2, 0.8 * kcs));
    I = wall_impact(&c, a, v0, tmax);
    assert_true(I.separated);
    assert_rel(I.vrel / v0, r, R_TOL);
    printf("  wall kc=0.8 kc*: r = %.10f (analytic %.10f, rel err %.2e)\n",
           I.vrel / v0, r, I.vrel / v0 / r - 1.0);
}

/* ---- prescribed overlap path of a wall contact -------------------------- */

/* Independent reference of the constant-k2 law along a path: state dmax,
 * force at overlap d (> 0). */
static double ref_force(double d, double *dmax, double k1, double k2, double kc)
{
    if (d >= *dmax) {
        *dmax = d;
        return k1 * d;
    }
    double d0 = (1.0 - k1 / k2) * *dmax;
    double f = k2 * (d - d0);
    if (f > -kc * d)
        return f;
    /* adhesive branch: the line is moved through (d, -kc d) */
    *dmax = (k2 + kc) / (k2 - k1) * d;
    return -kc * d;
}

/* Target overlap of the path at sample k of the segments
 * 0 -> d1 -> du -> d2 -> 0, each in N steps. */
static double path_delta(int k, int N, const double *nodes)
{
    int seg = k / N;
    if (seg >= 4)
        return nodes[4];
    double t = (double)(k - seg * N) / N;
    return nodes[seg] + (nodes[seg + 1] - nodes[seg]) * t;
}

/* 5. a particle is moved into the x-min wall and back by prescribing its
 * position each step (its velocity is set so that the engine's drift
 * lands on the target); the wall force follows the piecewise law, the
 * largest attractions are f_min of each history and the loop area of the
 * closed path is the analytic dissipated energy. */
static void wall_prescribed_path_follows_law(void **state)
{
    (void)state;
    const double k1 = 5e4, k2 = 1e5, kc = 2e4, a = 5e-3;
    const double d1 = 2e-5, du = 2e-6, d2 = 3e-5; /* m */
    /* the path ends 0.1 um off the wall so that the contact surely ends */
    const double nodes[5] = {0.0, d1, du, d2, -1e-7};
    const int N = 4000;
    struct dem_config c;
    /* the pair kc (7e4) differs on purpose: the wall must use wall_kc */
    luding_config(&c, k1, k2, 7e4, kc, 0.0, mass(a));
    c.time_step = 1e-6;
    struct dem_sim s;
    test_sim(&s, &c, 1, 0.0, 0.1);
    test_add(&s, a, 0.05, 0.05, a); /* touching, delta = 0 */
    test_ready(&s);
    const double dt = s.dt;

    /* du lies on the adhesive branch after loading to d1 */
    const double d01 = (1.0 - k1 / k2) * d1;
    const double dmin1 = k2 * d01 / (k2 + kc);
    assert_true(du < dmin1);

    double ref_dmax = 0.0, area = 0.0, prev_d = 0.0, prev_f = 0.0;
    double fmin_seg[4] = {0, 0, 0, 0}, maxerr = 0.0;
    for (int k = 1; k <= 4 * N; k++) {
        const double target = a - path_delta(k, N, nodes);
        /* v after the first half kick is (target - x)/dt */
        s.p.vx[0] =
            (target - s.p.x[0]) / dt - 0.5 * dt * s.p.inv_m[0] * s.p.fx[0];
        test_step(&s, 1);
        const double d = a - s.p.x[0]; /* the overlap the engine saw */
        assert_close(d, a - target, 1e-17);
        const double f = s.wall[0].force;
        /* the force on the particle points away from the wall (+x), the
         * wall feels its opposite, an outward push of the same size */
        assert_close(s.p.fx[0], f, 0.0);
        double want = 0.0;
        if (d > 0.0)
            want = ref_force(d, &ref_dmax, k1, k2, kc);
        else
            ref_dmax = 0.0;
        double err = fabs(f - want);
        if (err > maxerr)
            maxerr = err;
        assert_close(f, want, 1e-10 * k2 * d2);
        int seg = (k - 1) / N;
        if (f < fmin_seg[seg])
            fmin_seg[seg] = f;
        area += 0.5 * (f + prev_f) * (d - prev_d);
        prev_d = d;
        prev_f = f;
    }
    /* the contact ended at delta = 0 and its history was dropped */
    assert_close(prev_d, -1e-7, 1e-17);
    {
        /* particle 0's entry for wall 0 (x min), still listed (within the
         * skin) but without history */
        const struct dem_contact_list *W = &s.pairs.wcur;
        int found = 0;
        for (int k = 0; k < W->n; k++)
            if (W->i[k] == 0 && W->j[k] == 0) {
                found = 1;
                assert_close(W->dmax[k], 0.0, 0.0);
                assert_int_equal(W->state[k], 0);
            }
        assert_true(found);
    }

    /* largest attraction of each unloading: -kc (k2 - k1) dmax/(k2 + kc);
     * the path samples delta every |step| so the sampled minimum is within
     * one slope times one step of it */
    const double fmin1 = -kc * (k2 - k1) * d1 / (k2 + kc);
    const double fmin2 = -kc * (k2 - k1) * d2 / (k2 + kc);
    const double stepd = d2 / N;
    assert_close(fmin_seg[1], fmin1, k2 * stepd);
    assert_close(fmin_seg[3], fmin2, k2 * stepd);
    assert_true(fmin_seg[1] >= fmin1 - 1e-12);
    assert_true(fmin_seg[3] >= fmin2 - 1e-12);

    /* dissipated energy of the closed path, segment by segment */
    const double W1 = 0.5 * k1 * d1 * d1; /* virgin loading */
    /* unloading d1 -> du: line to delta_min, then -kc delta */
    const double W2 =
        0.5 * k2 * ((dmin1 - d01) * (dmin1 - d01) - (d1 - d01) * (d1 - d01)) -
        0.5 * kc * (du * du - dmin1 * dmin1);
    /* reloading du -> d2: re-mapped line up to x, then k1 */
    const double x = (k2 + kc) / (k2 - k1) * du, d0x = (1.0 - k1 / k2) * x;
    const double W3 =
        0.5 * k2 * ((x - d0x) * (x - d0x) - (du - d0x) * (du - d0x)) +
        0.5 * k1 * (d2 * d2 - x * x);
    /* unloading d2 -> 0: E_out = f1^2/(2 k2) - kc k2 d0^2/(2 (k2 + kc)) */
    const double d02 = (1.0 - k1 / k2) * d2;
    const double W4 =
        -(0.5 * k1 * k1 * d2 * d2 / k2 - 0.5 * kc * k2 * d02 * d02 / (k2 + kc));
    const double diss = W1 + W2 + W3 + W4;
    /* cross-check W1 + W4: the first cycle of an impact to d2 */
    assert_rel(0.5 * k1 * d2 * d2 + W4,
               0.5 * k1 * d2 * d2 * (1.0 - closed_r2(k1, k2, kc)), 1e-12);
    assert_true(diss > 0.0);
    /* trapezoids are exact on linear pieces; a kink costs O(k dd^2) */
    assert_rel(area, diss, 1e-4);
    printf("  wall path: max |f - f_ref| = %.3g N; f_min %.10g / %.10g N "
           "(analytic %.10g / %.10g); loop area %.10g J, analytic %.10g J "
           "(rel err %.2e)\n",
           maxerr, fmin_seg[1], fmin_seg[3], fmin1, fmin2, area, diss,
           area / diss - 1.0);
    dem_sim_destroy(&s);
}

/* ---- phi_f refinement -------------------------------------------------- */

/* Independent restitution of the refined law for delta_max below
 * delta*_max: k2^ = k1 + (k2 - k1) dmax/d*, delta_0 = (1 - k1/k2^) dmax. */
static double refined_r2(double k1, double k2, double kc, double dstar,
                         double dmax)
{
    double kh = k1 + (k2 - k1) * dmax / dstar;
    double d0 = (1.0 - k1 / kh) * dmax;
    double ein = 0.5 * k1 * dmax * dmax;
    double f1 = k1 * dmax;
    double eout = 0.5 * f1 * f1 / kh - 0.5 * kc * kh * d0 * d0 / (kh + kc);
    return eout / ein;
}

/* 6. phi_f > 0: r depends on v0; below delta*_max (k2^ < k2) and beyond it
 * (elastic limit branch). */
static void pair_refined_law_rebound(void **state)
{
    (void)state;
    const double k1 = 5e4, k2 = 1e5, kc = 1e4, phi = 0.01, m = pair_mij();
    const double a12 = A1 * A2 / (A1 + A2);
    const double dstar = k2 / (k2 - k1) * phi * 2.0 * a12;
    const struct dem_luding L = {k1, k2, kc, phi};
    struct dem_config c;
    luding_config(&c, k1, k2, kc, 0.0, phi, m);
    const double speeds[2] = {0.8, 2.0};
    for (int i = 0; i < 2; i++) {
        const double v0 = speeds[i];
        const double dmax = v0 * sqrt(m / k1);
        const double r = dem_luding_restitution(v0, m, &L, a12);
        if (i == 0) {
            /* below the plastic limit: independent closed form */
            assert_true(dmax < dstar);
            assert_rel(r * r, refined_r2(k1, k2, kc, dstar, dmax), 1e-12);
        } else {
            assert_true(v0 * v0 * m > k1 * dstar * dstar);
        }
        struct impact I = pair_impact(&c, A1, A2, v0, 1.0);
        assert_true(I.separated);
        assert_rel(I.vrel / v0, r, R_TOL);
        assert_rel(-I.min_gap, dem_luding_impact_overlap(v0, m, &L, a12), 2e-3);
        assert_true(I.pmax <= 1e-14 * mass(A1) * v0);
        printf("  pair phi_f=%.2f v0=%.1f (dmax/d* = %.3f): r = %.10f "
               "(kernel %.10f, rel err %.2e), seed-law r = %.4f\n",
               phi, v0, -I.min_gap / dstar, I.vrel / v0, r,
               I.vrel / v0 / r - 1.0, sqrt(closed_r2(k1, k2, kc)));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(pair_no_adhesion_rebounds_with_sqrt_k1_over_k2),
        cmocka_unit_test(pair_adhesion_rebound_matches_closed_form),
        cmocka_unit_test(pair_capture_threshold),
        cmocka_unit_test(wall_impacts_match_analytic),
        cmocka_unit_test(wall_prescribed_path_follows_law),
        cmocka_unit_test(pair_refined_law_rebound),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
