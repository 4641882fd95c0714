/* Hysteretic adhesive contact (Luding): the kernels of contact/luding.h
 * against analytic results. Expected values are computed here from the
 * equations of docs/physics.md, never by calling the kernel under test. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "contact/luding.h"
#include "core/rng.h"

/* Relative comparison with a floor; prints both values on failure. */
#define assert_close(got, want, rtol, atol)                                    \
    do {                                                                       \
        double g_ = (got), w_ = (want);                                        \
        if (!(fabs(g_ - w_) <= (atol) + (rtol)*fabs(w_))) {                    \
            print_error("%s = %.17g, expected %.17g\n", #got, g_, w_);         \
            fail();                                                            \
        }                                                                      \
    } while (0)

/* Luding et al. values: k2 = 1e5 N/m, k1/k2 = 1/2; kc/k2 = 0.2; two 1 mm
 * discs. */
static const double K2 = 1e5, K1 = 0.5e5, KC = 0.2e5; /* N/m */
static const double A12 = 0.5e-3;                     /* m */

/* ---- independent reference formulas ---------------------------------- */

/* delta*_max = k2/(k2 - k1) phi_f 2 a12 (Luding 2008 Eq. 7), m */
static double ref_dstar(double k1, double k2, double phi, double a12)
{
    return k2 / (k2 - k1) * phi * 2.0 * a12;
}

/* k2^(delta_max) (Luding 2008 Eq. 8); phi = 0: constant k2 */
static double ref_k2hat(double dmax, double k1, double k2, double phi,
                        double a12)
{
    if (phi == 0.0)
        return k2;
    double ds = ref_dstar(k1, k2, phi, a12);
    return dmax < ds ? k1 + (k2 - k1) * dmax / ds : k2;
}

/* delta_0 = (1 - k1/k2^) min(delta_max, delta*_max) */
static double ref_delta0(double dmax, double k1, double k2, double phi,
                         double a12)
{
    double d = dmax;
    if (phi > 0.0 && d > ref_dstar(k1, k2, phi, a12))
        d = ref_dstar(k1, k2, phi, a12);
    return (1.0 - k1 / ref_k2hat(d, k1, k2, phi, a12)) * d;
}

/* Re-mapped delta_max by bisection of (k2^(x) + kc) delta = (k2^(x) - k1) x,
 * a method independent of the kernel's closed-form root. */
static double ref_remap(double delta, double k1, double k2, double kc,
                        double phi, double a12)
{
    double lo = delta, hi = ref_dstar(k1, k2, phi, a12);
    for (int i = 0; i < 200; i++) {
        double x = 0.5 * (lo + hi);
        double k = ref_k2hat(x, k1, k2, phi, a12);
        if ((k + kc) * delta > (k - k1) * x)
            lo = x;
        else
            hi = x;
    }
    return 0.5 * (lo + hi);
}

static double maxd(double a, double b)
{
    return a > b ? a : b;
}

/* Drive the kernel along delta from a to b in n equal steps; at each sample
 * compare with want(delta). */
typedef double (*ref_fn)(double delta, const double *p);

static void drive(double a, double b, int n, double *dmax,
                  const struct dem_luding *L, double a12, ref_fn want,
                  const double *p, double fscale)
{
    for (int i = 1; i <= n; i++) {
        double d = a + (b - a) * i / n;
        double f = dem_luding_force(d, dmax, L, a12);
        assert_close(f, want(d, p), 1e-10, 1e-10 * fscale);
    }
}

/* The reference branches of a path segment: p = {k1, k2, kc, k2^, delta_0,
 * x, dstar, delta_0*} as needed. */
static double seg_virgin(double d, const double *p)
{
    return p[0] * d;
}

static double seg_unload(double d, const double *p)
{
    return maxd(p[3] * (d - p[4]), -p[2] * d);
}
static double seg_reload(double d, const double *p)
{
    /* along the re-mapped line up to x, then k1, then the limit branch */
    if (d <= p[5])
        return p[3] * (d - p[4]);
    if (d <= p[6])
        return p[0] * d;
    return p[1] * (d - p[7]);
}

/* ---- tests ------------------------------------------------------------ */

static void seed_law_follows_piecewise_path(void **state)
{
    (void)state;
    const struct dem_luding L = {K1, K2, KC, 0.0};
    const double d1 = 1e-5, da = 2e-6, d2 = 1.5e-5, d3 = 1e-6; /* m */
    const double fs = K2 * d2;
    double dmax = 0.0;

    double p1[8] = {K1, K2, KC};
    drive(0.0, d1, 1000, &dmax, &L, A12, seg_virgin, p1, fs);
    assert_close(dmax, d1, 1e-15, 0.0);

    /* unload past delta_min = k2 delta_0/(k2 + kc) onto -kc delta */
    double d01 = (1.0 - K1 / K2) * d1;
    assert_true(da < K2 * d01 / (K2 + KC));
    double p2[8] = {K1, K2, KC, K2, d01};
    drive(d1, da, 1000, &dmax, &L, A12, seg_unload, p2, fs);
    double x = (K2 + KC) / (K2 - K1) * da; /* re-mapped history */
    assert_close(dmax, x, 1e-12, 0.0);

    /* reload from the adhesive branch along k2, past d1 on k1 */
    double p3[8] = {K1, K2, KC, K2, (1.0 - K1 / K2) * x, x, INFINITY, 0.0};
    drive(da, d2, 1000, &dmax, &L, A12, seg_reload, p3, fs);
    assert_close(dmax, d2, 1e-15, 0.0);

    double p4[8] = {K1, K2, KC, K2, (1.0 - K1 / K2) * d2};
    drive(d2, d3, 1000, &dmax, &L, A12, seg_unload, p4, fs);
    assert_close(dmax, (K2 + KC) / (K2 - K1) * d3, 1e-12, 0.0);
}

static void refined_law_follows_piecewise_path(void **state)
{
    (void)state;
    const double phi = 0.01; /* delta* = 2e-5 m, delta_0* = 1e-5 m */
    const struct dem_luding L = {K1, K2, KC, phi};
    const double ds = ref_dstar(K1, K2, phi, A12);
    const double d0s = phi * 2.0 * A12;
    const double d1 = 1e-5, da = 1e-6, d2 = 3e-5, d3 = 5e-7; /* m */
    const double fs = K2 * d2;
    assert_close(ds, 2e-5, 1e-14, 0.0);
    double dmax = 0.0;

    double p1[8] = {K1, K2, KC};
    drive(0.0, d1, 1000, &dmax, &L, A12, seg_virgin, p1, fs);

    double k1h = ref_k2hat(d1, K1, K2, phi, A12);
    double d01 = ref_delta0(d1, K1, K2, phi, A12);
    assert_close(k1h, 0.75e5, 1e-14, 0.0);
    assert_true(da < k1h * d01 / (k1h + KC));
    double p2[8] = {K1, K2, KC, k1h, d01};
    drive(d1, da, 1000, &dmax, &L, A12, seg_unload, p2, fs);
    double x = ref_remap(da, K1, K2, KC, phi, A12);
    assert_close(dmax, x, 1e-12, 0.0);

    /* reload past delta* onto the elastic limit branch */
    double p3[8] = {K1,
                    K2,
                    KC,
                    ref_k2hat(x, K1, K2, phi, A12),
                    ref_delta0(x, K1, K2, phi, A12),
                    x,
                    ds,
                    d0s};
    drive(da, d2, 2000, &dmax, &L, A12, seg_reload, p3, fs);
    assert_close(dmax, d2, 1e-15, 0.0);

    /* unload on the limit branch, through tension, to near separation */
    double p4[8] = {K1, K2, KC, K2, d0s};
    drive(d2, d3, 2000, &dmax, &L, A12, seg_unload, p4, fs);
    assert_close(dmax, ref_remap(d3, K1, K2, KC, phi, A12), 1e-12, 0.0);
}

static void plastic_limit_overlap_matches_luding_eq7(void **state)
{
    (void)state;
    const struct dem_luding L = {K1, K2, KC, 0.05};
    /* wall contact: a12 is the particle radius */
    for (double a = 1e-4; a < 1e-2; a *= 3.0) {
        double ds = dem_luding_dstar(&L, a);
        assert_close(ds, K2 / (K2 - K1) * 0.05 * 2.0 * a, 1e-14, 0.0);
        double k, d0;
        dem_luding_line(ds, &L, a, &k, &d0);
        assert_close(k, K2, 1e-14, 0.0);
        assert_close(d0, 0.05 * 2.0 * a, 1e-14, 0.0); /* phi_f 2 a12 */
        dem_luding_line(0.5 * ds, &L, a, &k, &d0);
        assert_close(k, 0.5 * (K1 + K2), 1e-14, 0.0);
    }
    const struct dem_luding S = {K1, K2, KC, 0.0};
    assert_true(isinf(dem_luding_dstar(&S, A12)));
}

/* f_min = -kc k2^ delta_0/(k2^ + kc) at delta_min = k2^ delta_0/(k2^ + kc);
 * for constant k2: -kc (k2 - k1) delta_max/(k2 + kc). */
static void largest_attraction_is_fmin(void **state)
{
    (void)state;
    const double phis[2] = {0.0, 0.01};
    for (int lw = 0; lw < 2; lw++) {
        const struct dem_luding L = {K1, K2, KC, phis[lw]};
        const double dms[3] = {3e-6, 1.2e-5, 4e-5};
        for (int j = 0; j < 3; j++) {
            double dm = dms[j];
            double k = ref_k2hat(dm, K1, K2, phis[lw], A12);
            double d0 = ref_delta0(dm, K1, K2, phis[lw], A12);
            double fmin = -KC * k * d0 / (k + KC);
            double dmin = k * d0 / (k + KC);
            if (lw == 0)
                assert_close(fmin, -KC * (K2 - K1) * dm / (K2 + KC), 1e-14,
                             0.0);
            double dmax = 0.0;
            dem_luding_force(dm, &dmax, &L, A12);
            /* exactly at delta_min both branches give f_min */
            double hist = dmax;
            assert_close(dem_luding_force(dmin, &hist, &L, A12), fmin, 1e-12,
                         0.0);
            /* scan the unloading path: the minimum is f_min at delta_min */
            const int n = 20000;
            double best = INFINITY, at = 0.0;
            for (int i = 1; i < n; i++) {
                double d = dm * (1.0 - (double)i / n);
                double f = dem_luding_force(d, &dmax, &L, A12);
                if (f < best) {
                    best = f;
                    at = d;
                }
            }
            assert_true(best >= fmin - 1e-12 * fabs(fmin));
            assert_close(best, fmin, 0.0, (K2 + KC) * dm / n);
            assert_close(at, dmin, 0.0, 1.01 * dm / n);
        }
    }
}

/* Trapezoidal work of the kernel force along delta from a to b, J. */
static double work(double a, double b, int n, double *dmax,
                   const struct dem_luding *L, double a12)
{
    double w = 0.0, fprev = dem_luding_force(a, dmax, L, a12);
    for (int i = 1; i <= n; i++) {
        double d = a + (b - a) * i / n;
        double f = dem_luding_force(d, dmax, L, a12);
        w += 0.5 * (f + fprev) * (d - (a + (b - a) * (i - 1) / n));
        fprev = f;
    }
    return w;
}

/* Load 0 -> d1 -> 0: the loop area is
 *   W_in - W_out = k1 d1^2/2 - [f1^2/(2 k2^) - kc k2^ delta_0^2/(2(k2^+kc))]
 * (for kc = 0: k1 d1^2 (1 - k1/k2^)/2). */
static void loop_dissipation_equals_enclosed_area(void **state)
{
    (void)state;
    const double cases[4][3] = {/* kc, phi_f, d1 */
                                {0.0, 0.0, 1e-5},
                                {KC, 0.0, 1e-5},
                                {KC, 0.01, 1e-5},
                                {2 * K2, 0.0, 1e-5}};
    for (int c = 0; c < 4; c++) {
        const double kc = cases[c][0], phi = cases[c][1], d1 = cases[c][2];
        const struct dem_luding L = {K1, K2, kc, phi};
        double k = ref_k2hat(d1, K1, K2, phi, A12);
        double d0 = ref_delta0(d1, K1, K2, phi, A12);
        double f1 = K1 * d1;
        double diss = 0.5 * K1 * d1 * d1 -
                      (0.5 * f1 * f1 / k - 0.5 * kc * k * d0 * d0 / (k + kc));
        if (kc == 0.0)
            assert_close(diss, 0.5 * K1 * d1 * d1 * (1.0 - K1 / k), 1e-14, 0.0);
        double dmax = 0.0;
        const int n = 100000;
        double w = work(1e-30, d1, n, &dmax, &L, A12);
        w += work(d1, 1e-30, n, &dmax, &L, A12);
        assert_close(w, diss, 1e-6, 0.0);
        /* and the helpers agree with the same analytic area */
        assert_close(dem_luding_loading_work(d1, &L, A12) -
                         dem_luding_unloading_work(d1, &L, A12),
                     diss, 1e-13, 0.0);
    }
}

/* Along any path f is piecewise linear in delta with slopes k1, k2^ <= k2,
 * and -kc: |df| <= max(k2, kc) |d delta|. Also -kc delta <= f <= envelope. */
static void force_is_continuous_along_random_path(void **state)
{
    (void)state;
    struct dem_rng g;
    dem_rng_seed(&g, 2024);
    const double phis[2] = {0.0, 0.01};
    const double kcs[2] = {KC, 3.0 * K2};
    for (int lw = 0; lw < 4; lw++) {
        const struct dem_luding L = {K1, K2, kcs[lw / 2], phis[lw % 2]};
        const double lip = maxd(K2, L.kc);
        double d = 1e-7, dmax = 0.0;
        double f = dem_luding_force(d, &dmax, &L, A12);
        for (int i = 0; i < 200000; i++) {
            /* mostly small steps, sometimes jumps across several branches */
            double h = dem_rng_uniform(&g) < 0.05 ? 2e-5 : 5e-7;
            double dn = d + h * (2.0 * dem_rng_uniform(&g) - 1.0) + 1e-9;
            if (dn <= 0.0) {
                /* separation: the caller drops the history */
                dmax = 0.0;
                d = 1e-9;
                f = dem_luding_force(d, &dmax, &L, A12);
                continue;
            }
            double fn = dem_luding_force(dn, &dmax, &L, A12);
            double tiny = 1e-12 * K2 * 1e-4;
            assert_true(fabs(fn - f) <= lip * fabs(dn - d) * (1 + 1e-9) + tiny);
            assert_true(fn >= -L.kc * dn - tiny);
            assert_true(fn <= dem_luding_envelope(dn, &L, A12) + tiny);
            assert_true(dmax >= dn);
            d = dn;
            f = fn;
        }
    }
}

static void coulomb_force_never_negative(void **state)
{
    (void)state;
    struct dem_rng g;
    dem_rng_seed(&g, 7);
    for (int i = 0; i < 100000; i++) {
        double fn = 2.0 * (2.0 * dem_rng_uniform(&g) - 1.0);
        double d = 1e-5 * dem_rng_uniform(&g);
        double kc = 1e5 * dem_rng_uniform(&g);
        double fc = dem_luding_coulomb_force(fn, d, kc);
        assert_true(fc >= 0.0);
        assert_close(fc, maxd(fn + kc * d, 0.0), 1e-15, 0.0);
    }
    /* on the adhesive branch (no dashpot) the Coulomb force is zero */
    assert_true(dem_luding_coulomb_force(-KC * 3e-6, 3e-6, KC) == 0.0);
}

/* e_pot = f^2/(2 k2^) equals the work given back returning along the line to
 * the force-free overlap delta_0: downwards for f > 0, upwards for f < 0
 * (tensile part of the line, and the adhesive branch after re-mapping). */
static void elastic_energy_is_work_given_back(void **state)
{
    (void)state;
    const double phis[2] = {0.0, 0.01};
    for (int lw = 0; lw < 2; lw++) {
        const double phi = phis[lw];
        const struct dem_luding L = {K1, K2, KC, phi};
        const double d1s[2] = {1e-5, 3e-5}; /* below and above delta* */
        for (int j = 0; j < 2; j++) {
            double d1 = d1s[j];
            double k = ref_k2hat(d1, K1, K2, phi, A12);
            double d0 = ref_delta0(d1, K1, K2, phi, A12);
            double dmin = k * d0 / (k + KC);
            /* probes: virgin point, compressive line, tensile line */
            const double probes[3] = {d1, 0.5 * (d0 + d1), 0.5 * (dmin + d0)};
            for (int q = 0; q < 3; q++) {
                double dm = 0.0;
                dem_luding_force(d1, &dm, &L, A12);
                double dp = probes[q];
                double f = dem_luding_force(dp, &dm, &L, A12);
                double e = dem_luding_energy(dp, dm, &L, A12);
                assert_close(e, 0.5 * f * f / k, 1e-12, 0.0);
                double h = dm;
                double w = fabs(work(dp, d0, 100000, &h, &L, A12));
                assert_close(e, w, 1e-8, 1e-20);
            }
            /* adhesive branch: pull to delta_a < delta_min, then e is the
             * work given back reloading along the re-mapped line */
            double dm = 0.0;
            dem_luding_force(d1, &dm, &L, A12);
            double da = 0.5 * dmin;
            work(d1, da, 10000, &dm, &L, A12);
            double f = dem_luding_force(da, &dm, &L, A12);
            assert_close(f, -KC * da, 1e-12, 0.0);
            double kx = ref_k2hat(dm, K1, K2, phi, A12);
            double d0x = ref_delta0(dm, K1, K2, phi, A12);
            double e = dem_luding_energy(da, dm, &L, A12);
            assert_close(e, 0.5 * KC * KC * da * da / kx, 1e-10, 0.0);
            double h = dm;
            double w = -work(da, d0x, 100000, &h, &L, A12);
            assert_close(e, w, 1e-8, 1e-20);
        }
    }
}

/* m delta'' = -f_hys(delta), delta(0) = 0, delta'(0) = v0, velocity Verlet.
 * Returns the separation speed, or -1 if the pair is still in contact after
 * 100 loading periods (captured). */
static double impact(const struct dem_luding *L, double a12, double m,
                     double v0)
{
    const double dt = 1e-4 * sqrt(m / L->k2);
    const long nmax = (long)(100.0 * 3.141592653589793 * sqrt(m / L->k1) / dt);
    double d = 0.0, v = v0, dmax = 0.0, a = 0.0;
    for (long i = 0; i < nmax; i++) {
        v += 0.5 * dt * a;
        d += dt * v;
        if (d <= 0.0)
            return -v; /* no force once the contact is open */
        a = -dem_luding_force(d, &dmax, L, a12) / m;
        v += 0.5 * dt * a;
    }
    return -1.0;
}

static const double MIJ = 4.2e-6; /* kg; two 1 mm spheres, rho = 2000 */

static void restitution_without_adhesion_is_sqrt_k1_over_k2(void **state)
{
    (void)state;
    const struct dem_luding L = {K1, K2, 0.0, 0.0};
    for (double v0 = 0.01; v0 < 2.0; v0 *= 4.0) {
        assert_close(dem_luding_restitution(v0, MIJ, &L, A12), sqrt(K1 / K2),
                     1e-14, 0.0);
        assert_close(impact(&L, A12, MIJ, v0) / v0, sqrt(K1 / K2), 1e-6, 0.0);
    }
}

/* r^2 = k1/k2 - kc (k2 - k1)^2/(k1 k2 (k2 + kc)), independent of v0;
 * for k1 = k2/2 this is 1/(2 (1 + kc/k2)). */
static void restitution_with_adhesion_matches_analytic(void **state)
{
    (void)state;
    const double k1s[2] = {0.5 * K2, 0.3 * K2};
    for (int a = 0; a < 2; a++) {
        for (double kc = 0.05 * K2; kc < 5.0 * K2; kc *= 3.0) {
            const double k1 = k1s[a];
            const struct dem_luding L = {k1, K2, kc, 0.0};
            double r2 =
                k1 / K2 - kc * (K2 - k1) * (K2 - k1) / (k1 * K2 * (K2 + kc));
            if (a == 0)
                assert_close(r2, 1.0 / (2.0 * (1.0 + kc / K2)), 1e-13, 0.0);
            if (r2 <= 0.0)
                continue; /* captured: see the capture test */
            double v0 = 0.1;
            assert_close(dem_luding_restitution_sq(v0, MIJ, &L, A12), r2, 1e-12,
                         0.0);
            assert_close(impact(&L, A12, MIJ, v0) / v0, sqrt(r2), 1e-6, 0.0);
        }
    }
}

/* Capture for kc >= k1^2/(k2 - 2 k1), i.e. kc/k2 >= q^2/(1 - 2q), q = k1/k2. */
static void capture_threshold_separates_rebound_and_sticking(void **state)
{
    (void)state;
    const double k1 = 0.2 * K2;
    const double kcs = k1 * k1 / (K2 - 2.0 * k1);
    const struct dem_luding T = {k1, K2, kcs, 0.0};
    assert_close(dem_luding_capture_kc(&T), kcs, 1e-14, 0.0);
    assert_close(dem_luding_restitution_sq(0.1, MIJ, &T, A12), 0.0, 0.0, 1e-12);

    const struct dem_luding below = {k1, K2, 0.8 * kcs, 0.0};
    double r = dem_luding_restitution(0.1, MIJ, &below, A12);
    assert_true(r > 0.05);
    assert_close(impact(&below, A12, MIJ, 0.1) / 0.1, r, 1e-6, 0.0);

    const struct dem_luding above = {k1, K2, 1.25 * kcs, 0.0};
    assert_true(dem_luding_restitution_sq(0.1, MIJ, &above, A12) < 0.0);
    assert_true(dem_luding_restitution(0.1, MIJ, &above, A12) == 0.0);
    assert_true(impact(&above, A12, MIJ, 0.1) < 0.0);

    /* the seed's k1/k2 = 1/2 never captures */
    const struct dem_luding seed = {K1, K2, 100.0 * K2, 0.0};
    assert_true(isinf(dem_luding_capture_kc(&seed)));
    assert_true(impact(&seed, A12, MIJ, 0.1) > 0.0);
}

/* With the phi_f refinement r depends on v0 through k2^(delta_max): nearly
 * elastic at low speed, captured around delta_max ~ delta*, and again
 * rebounding when the elastic limit branch dominates. */
static void refined_restitution_depends_on_impact_speed(void **state)
{
    (void)state;
    const double k1 = 0.2 * K2, kc = 0.2 * K2, phi = 0.01;
    const struct dem_luding L = {k1, K2, kc, phi};
    const double ds = ref_dstar(k1, K2, phi, A12);
    const double vs = ds * sqrt(k1 / MIJ); /* speed that just reaches ds */
    const double fr[3] = {0.1, 1.0, 10.0};
    for (int i = 0; i < 3; i++) {
        double v0 = fr[i] * vs;
        double dm = dem_luding_impact_overlap(v0, MIJ, &L, A12);
        /* reference: energy balance written out for this case */
        double ein, eout;
        double k = ref_k2hat(dm, k1, K2, phi, A12);
        double d0 = ref_delta0(dm, k1, K2, phi, A12);
        if (dm <= ds) {
            ein = 0.5 * k1 * dm * dm;
            eout = 0.5 * k1 * k1 * dm * dm / k;
        } else {
            double d0s = phi * 2.0 * A12;
            double w0 = (ds - d0s) * (ds - d0s);
            ein =
                0.5 * k1 * ds * ds + 0.5 * K2 * ((dm - d0s) * (dm - d0s) - w0);
            eout = 0.5 * K2 * (dm - d0s) * (dm - d0s);
        }
        assert_close(ein, 0.5 * MIJ * v0 * v0, 1e-12, 0.0);
        double dmin = k * d0 / (k + kc);
        eout -= 0.5 * k * (d0 - dmin) * (d0 - dmin) + 0.5 * kc * dmin * dmin;
        double r2 = eout / ein;
        assert_close(dem_luding_restitution_sq(v0, MIJ, &L, A12), r2, 1e-12,
                     1e-14);
        double vr = impact(&L, A12, MIJ, v0);
        if (i == 1) {
            assert_true(r2 < 0.0);
            assert_true(vr < 0.0);
        } else {
            assert_true(r2 > 0.0);
            assert_close(vr / v0, sqrt(r2), 1e-6, 0.0);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(seed_law_follows_piecewise_path),
        cmocka_unit_test(refined_law_follows_piecewise_path),
        cmocka_unit_test(plastic_limit_overlap_matches_luding_eq7),
        cmocka_unit_test(largest_attraction_is_fmin),
        cmocka_unit_test(loop_dissipation_equals_enclosed_area),
        cmocka_unit_test(force_is_continuous_along_random_path),
        cmocka_unit_test(coulomb_force_never_negative),
        cmocka_unit_test(elastic_energy_is_work_given_back),
        cmocka_unit_test(restitution_without_adhesion_is_sqrt_k1_over_k2),
        cmocka_unit_test(restitution_with_adhesion_matches_analytic),
        cmocka_unit_test(capture_threshold_separates_rebound_and_sticking),
        cmocka_unit_test(refined_restitution_depends_on_impact_speed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
