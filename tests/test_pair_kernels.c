/* The force pass's rounds written in intrinsics compute the very
 * operations of the kernels they spell out: the same bits as pair_vals
 * and wall_vals (contact/pair.h), one contact at a time in scalar code,
 * for touching and open pairs and wall contacts, sticking and sliding
 * contacts, with and without friction. test_dynamics compares the
 * passes on the CPU that runs it; this test runs the groups of
 * contact/pair_linear_simd.h of both widths the CPU has, 4 lanes in AVX2
 * and 8 in AVX-512, also where the build's own pass never runs one of
 * them. */
#include <stdlib.h>

#include "contact/pair.h"
#include "testutil.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define TEST_SIMD 1
/* Contacts 0 <= k < n (a multiple of 8) by the groups of width W, pairs
 * or (wall set) wall contacts against the walls walls, each group
 * skipping the sliding case where no touching contact slides if skip is
 * set; returns the number of groups in which none slid. Each width's
 * function is compiled for its own instructions, so that the one of 4
 * runs on a CPU without AVX-512. */
#define GROUPS_(W)                                                             \
    static int groups##W(                                                      \
        int law, int wall, int two, const struct pass *q, int n,               \
        const double *rec, const struct dem_wall *walls,                       \
        const struct dem_contact_params *cp, const double *cell, double dt,    \
        const struct dem_tangential *T, struct dem_contact_force *F, int skip) \
    {                                                                          \
        const double ik = T->kt > 0.0 ? 1.0 / T->kt : 0.0;                     \
        _Alignas(64) double wr[DEM_MAX_WALLS * DEM_REC];                       \
        lin_wall_rows(walls, wr);                                              \
        const double *fm = cell, *grad = cell ? cell + 6 : NULL;               \
        int none = 0;                                                          \
        for (int k = 0; k < n; k += two ? 2 * W : W)                           \
            none += !(wall  ? lin_walls##W(law, q, k, rec, wr, cp, dt, T, ik,  \
                                           F + k, skip)                        \
                      : two ? lin_pairs2##W(law, q, k, rec, cp, fm, grad, dt,  \
                                            T, ik, F + k, skip)                \
                            : lin_pairs##W(law, q, k, rec, cp, fm, grad, dt,   \
                                           T, ik, F + k, skip));               \
        return none;                                                           \
    }
#pragma GCC push_options
#pragma GCC target("avx2")
#define LIN_W 4
#include "contact/pair_linear_simd.h"
#undef LIN_W
GROUPS_(4)
#pragma GCC pop_options
#pragma GCC push_options
#pragma GCC target("avx2,avx512f,avx512dq,avx512vl")
#define LIN_W 8
#include "contact/pair_linear_simd.h"
#undef LIN_W
GROUPS_(8)
#pragma GCC pop_options

/* the groups of width w (4 or 8) with the normal law law, pairs of them
 * side by side with one skip for both if two is set (pairs only), the
 * walls walls; the pairs in a periodic cell with cell (the frame's map,
 * then the affine gradient: lin_pair_test's fm and grad), else between
 * walls (NULL) */
static int groups(int law, int w, int two, int wall, const struct pass *q,
                  int n, const double *rec, const struct dem_wall *walls,
                  const struct dem_contact_params *cp, const double *cell,
                  double dt, const struct dem_tangential *T,
                  struct dem_contact_force *F, int skip)
{
    return w == 8 ? groups8(law, wall, two, q, n, rec, walls, cp, cell, dt, T,
                            F, skip)
                  : groups4(law, wall, two, q, n, rec, walls, cp, cell, dt, T,
                            F, skip);
}
#else
#define TEST_SIMD 0
#endif

#define NP 1024 /* pairs, each of its own two particles */

static double urand(unsigned *s, double lo, double hi)
{
    *s = *s * 1103515245u + 12345u;
    return lo + (hi - lo) * (double)(*s >> 8) / 16777216.0;
}

/* The pairs' particle records and their histories and states before the
 * step, at random: the gaps from 6 % overlap to 6 % apart, the springs
 * from 1e-7 to 1e-3 m (the largest slide), Luding's largest overlaps
 * from 0 to 9 % (h[3]: below and above the overlaps), Hertz-Mindlin's
 * last tangential stiffness from 0 to 3000 N/m (h[4]: about the k_t of
 * hertz()'s contacts, below and above; every seventh 0, a new contact),
 * every combination of the state bits. */
#define NH 5 /* history values: xi_x, xi_y, xi_z, dmax, kt_last */
struct pairs_data {
    double *rec, h[NH][NP];
    int ci[NP], cj[NP], state[NP];
    /* wall contact k: particle k's record in wrec against wall wj[k] */
    double *wrec;
    int wi[NP], wj[NP];
    struct dem_wall walls[DEM_MAX_WALLS];
};

/* 0, or DEM_SET_PLANE: the pairs of a 2D sample (make_pairs puts them
 * in the x-y plane, turning about z; the laws run with the plane bit) */
static int plane;

static void make_pairs(struct pairs_data *D)
{
    unsigned s = 12345u;
    D->rec = aligned_alloc(64, sizeof(double) * DEM_REC * 2 * NP);
    assert_non_null(D->rec);
    for (int k = 0; k < NP; k++) {
        double *a = D->rec + DEM_REC * 2 * k, *b = a + DEM_REC;
        const double ra = urand(&s, 0.8e-3, 1.2e-3),
                     rb = urand(&s, 0.8e-3, 1.2e-3);
        double u[3], un = 0.0;
        for (int e = 0; e < 3; e++) {
            u[e] = urand(&s, -1.0, 1.0);
            un += u[e] * u[e];
        }
        if (plane) {
            un -= u[2] * u[2];
            u[2] = 0.0;
        }
        un = sqrt(un);
        const double dist = (ra + rb) * urand(&s, 0.94, 1.06);
        for (int e = 0; e < 3; e++) {
            a[e] = urand(&s, -0.01, 0.01);
            b[e] = a[e] - dist * u[e] / un;
            a[4 + e] = urand(&s, -0.1, 0.1);
            b[4 + e] = urand(&s, -0.1, 0.1);
            a[8 + e] = urand(&s, -20.0, 20.0);
            b[8 + e] = urand(&s, -20.0, 20.0);
            D->h[e][k] = urand(&s, -1.0, 1.0) * pow(10.0, urand(&s, -7, -3));
        }
        if (plane) { /* z, v_z, w_x, w_y and the spring's z: 0 */
            a[2] = b[2] = a[6] = b[6] = 0.0;
            a[8] = b[8] = a[9] = b[9] = 0.0;
            D->h[2][k] = 0.0;
        }
        D->h[3][k] = (ra + rb) * urand(&s, 0.0, 0.09);
        D->h[4][k] = k % 7 ? urand(&s, 0.0, 3000.0) : 0.0;
        a[3] = ra;
        b[3] = rb;
        a[7] = b[7] = 1e-5;
        a[11] = b[11] = 0.0;
        D->ci[k] = 2 * k;
        D->cj[k] = 2 * k + 1;
        D->state[k] = k % 4; /* none, active, sliding, both */
    }
    /* the six faces of a box, each moving along its axis; wall contact k
     * with face k % 6 (a particle of pair k), its gap as a pair's */
    memset(D->walls, 0, sizeof D->walls);
    for (int w = 0; w < DEM_MAX_WALLS; w++) {
        D->walls[w].axis = w / 2;
        D->walls[w].side = w % 2;
        D->walls[w].pos = w % 2 ? 0.02 : -0.02;
        D->walls[w].vel = urand(&s, -0.05, 0.05);
    }
    D->wrec = aligned_alloc(64, sizeof(double) * DEM_REC * NP);
    assert_non_null(D->wrec);
    for (int k = 0; k < NP; k++) {
        double *o = D->wrec + DEM_REC * k;
        memcpy(o, D->rec + DEM_REC * 2 * k, sizeof(double) * DEM_REC);
        const struct dem_wall *W = &D->walls[k % DEM_MAX_WALLS];
        const double sgn = W->side ? -1.0 : 1.0;
        o[W->axis] = W->pos + sgn * o[3] * urand(&s, 0.94, 1.06);
        D->wi[k] = k;
        D->wj[k] = k % DEM_MAX_WALLS;
        if (plane && W->axis == 2) { /* no z walls in 2D: an x or y one */
            const struct dem_wall *V = &D->walls[k % 4];
            o[2] = 0.0;
            o[V->axis] =
                V->pos + (V->side ? -1.0 : 1.0) * o[3] * urand(&s, 0.94, 1.06);
            D->wj[k] = k % 4;
        }
    }
}

/* A pass over the pairs with the history and state arrays h, st. */
static struct pass pass_of(const struct pairs_data *D, double (*h)[NP], int *st,
                           int wall, double *A)
{
    struct pass q;
    memset(&q, 0, sizeof q);
    q.ci = wall ? D->wi : D->ci;
    q.cj = q.cjr = wall ? D->wj : D->cj;
    q.A = A;
    q.xi_x = h[0];
    q.xi_y = h[1];
    q.xi_z = h[2];
    q.dmax = h[3];
    q.kt_last = h[4];
    q.state = st;
    return q;
}

/* What one comparison found: touching contacts that stick and that slide,
 * open ones, the groups in which none slid; with Luding's law the
 * touching contacts whose largest overlap grew (virgin loading), stayed
 * (on their un-/re-loading line) and fell (re-mapped on the adhesive
 * branch); with Hertz-Mindlin's those whose tangential stiffness grew
 * (their springs rescaled) and fell (kept). */
struct counts {
    int stick, slide, open, calm, virgin, line, remap, stiffer, softer;
};

/* One parameter set cp (its normal law cp.normal): the groups of width w
 * of pairs (wall 0; two of them at a time with two set) or of wall
 * contacts (wall 1), with the sliding case always computed (skip 0) or
 * skipped in groups where no touching contact slides (skip 1), against
 * pair_vals or wall_vals, bit for bit, the forces on the walls too; the
 * pairs in a periodic cell with cell (its frame's map and affine
 * gradient, lin_pair_test), else between walls (NULL). */
static struct counts compare(const struct pairs_data *D,
                             struct dem_contact_params cp, const double *cell,
                             int w, int two, int wall, int skip)
{
    static double h0[NH][NP], h1[NH][NP], A0[NP], A1[NP];
    static int s0[NP], s1[NP];
    static struct dem_contact_force F0[NP], F1[NP];
    const int law = cp.normal | plane;
    memcpy(h0, D->h, sizeof h0);
    memcpy(h1, D->h, sizeof h1);
    memcpy(s0, D->state, sizeof s0);
    memcpy(s1, D->state, sizeof s1);
    memset(F0, 0xff, sizeof F0);
    memset(F1, 0xff, sizeof F1);
    memset(A0, 0xff, sizeof A0);
    memset(A1, 0xff, sizeof A1);
    const double dt = 1e-5, zero[6] = {0.0};
    const struct dem_tangential T = {cp.kt, cp.gamma_t, cp.mu_s, cp.mu_d};
    const struct pass q0 = pass_of(D, h0, s0, wall, A0),
                      q1 = pass_of(D, h1, s1, wall, A1);
    const double *rec = wall ? D->wrec : D->rec;
    for (int k = 0; k < NP; k++) {
        const struct pv pi = record_pv(rec + DEM_REC * (size_t)q0.ci[k]);
        F0[k] = wall   ? wall_vals(law, &q0, k, pi, &cp, dt, D->walls, &T)
                : cell ? pair_vals(law | DEM_SET_PERIODIC, &q0, k, pi,
                                   record_pv(rec + DEM_REC * (size_t)q0.cj[k]),
                                   &cp, dt, &T, cell + 6, cell)
                       : pair_vals(law, &q0, k, pi,
                                   record_pv(rec + DEM_REC * (size_t)q0.cj[k]),
                                   &cp, dt, &T, zero, zero);
    }
    struct counts c = {0};
#if TEST_SIMD
    c.calm = groups(law, w, two, wall, &q1, NP, rec, D->walls, &cp, cell, dt,
                    &T, F1, skip);
#else
    (void)q1;
    (void)w;
    (void)two;
    (void)skip;
#endif
    assert_memory_equal(F0, F1, sizeof F0);
    assert_memory_equal(h0, h1, sizeof h0);
    assert_memory_equal(s0, s1, sizeof s0);
    if (wall)
        assert_memory_equal(A0, A1, sizeof A0);
    for (int k = 0; k < NP; k++) {
        if (!(s0[k] & DEM_CONTACT_ACTIVE)) {
            c.open++;
            continue;
        }
        ++*(s0[k] & DEM_CONTACT_SLIDING ? &c.slide : &c.stick);
        if (cp.normal == DEM_NORMAL_LUDING)
            ++*(h0[3][k] > D->h[3][k]   ? &c.virgin
                : h0[3][k] < D->h[3][k] ? &c.remap
                                        : &c.line);
        if (cp.normal == DEM_NORMAL_HERTZ)
            ++*(h0[4][k] > D->h[4][k] ? &c.stiffer : &c.softer);
    }
    return c;
}

/* The widths of groups this CPU runs: 4 with AVX2, 8 with AVX-512 (F,
 * DQ and VL) too; 0 without AVX2 (or on another CPU), and the test is
 * skipped. */
static int widths(void)
{
#if TEST_SIMD
    if (!__builtin_cpu_supports("avx2"))
        return 0;
    if (__builtin_cpu_supports("avx512f") &&
        __builtin_cpu_supports("avx512dq") &&
        __builtin_cpu_supports("avx512vl"))
        return 8;
    return 4;
#else
    return 0;
#endif
}

/* The contacts (make_pairs) and the law's parameters with friction;
 * skips the test without AVX2. */
static struct dem_contact_params setup(struct pairs_data *D)
{
    if (!widths())
        skip();
    make_pairs(D);
    struct dem_config c;
    test_config(&c, 3);
    struct dem_contact_params cp = c.contact;
    cp.gamma_n = 0.05;
    cp.gamma_t = 0.01;
    cp.mu_s = 0.5;
    cp.mu_d = 0.4;
    return cp;
}

/* Luding's law in the variants its groups take apart: i = 0 the seed law
 * (constant k2) without adhesion, 1 with adhesion, 2 with the plasticity
 * depth phi_f (delta*_max about the overlaps), 3 that with k1 = k2 (no
 * plasticity: delta*_max infinite). */
static struct dem_contact_params luding(struct dem_contact_params cp, int i)
{
    cp.normal = DEM_NORMAL_LUDING;
    cp.k1 = 5e4;
    cp.k2 = 1e5;
    cp.kc = i ? 2e4 : 0.0;
    cp.phi_f = i >= 2 ? 0.05 : 0.0;
    if (i == 3)
        cp.k1 = cp.k2;
    return cp;
}

/* Hertz-Mindlin (E = 1e7 Pa, nu = 0.25, restitution 0.5): a stiffness
 * and a viscosity of its own at each contact for the tangential law. */
static struct dem_contact_params hertz(struct dem_contact_params cp)
{
    cp.normal = DEM_NORMAL_HERTZ;
    cp.E = 1e7;
    cp.nu = 0.25;
    cp.restitution = 0.5;
    dem_contact_derive(&cp);
    return cp;
}

/* Luding's branches taken by many touching contacts (with k1 = k2 the
 * contact is elastic: its line is its virgin load, never re-mapped). */
static void luding_branches(struct counts c, int i)
{
    assert_true(c.virgin > 50 && c.line > 50);
    if (i < 3)
        assert_true(c.remap > 50);
    else
        assert_int_equal(c.remap, 0);
}

/* The pairs' groups of the normal law of cp0 against pair_vals, between
 * walls (cell NULL) or in a periodic cell (cell as groups takes it). */
static void pairs_match(struct dem_contact_params cp0, const double *cell,
                        struct pairs_data *D)
{
    const double id[6] = {1.0, 0.0, 0.0, 1.0, 0.0, 1.0}; /* the frame's map */
    const double *fm = cell ? cell : id;
    for (int w = 4; w <= widths(); w *= 2)
        for (int two = 0; two < 2; two++) {
            const int gs = two ? 2 * w : w, ng = NP / gs; /* group size */
            int openg = 0;
            /* groups of gs open pairs (their gaps in the cell now) */
            for (int k = 0; k < NP; k += gs) {
                int n = 0;
                for (int l = 0; l < gs; l++) {
                    const double *a = D->rec + DEM_REC * (size_t)D->ci[k + l],
                                 *b = D->rec + DEM_REC * (size_t)D->cj[k + l];
                    const double dx = a[0] - b[0], dy = a[1] - b[1],
                                 dz = a[2] - b[2];
                    const double ex = fm[0] * dx + fm[1] * dy + fm[2] * dz,
                                 ey = fm[3] * dy + fm[4] * dz, ez = fm[5] * dz;
                    n += ex * ex + ey * ey + ez * ez >=
                         (a[3] + b[3]) * (a[3] + b[3]);
                }
                openg += n == gs;
            }
            /* (the other laws' forces differ: fewer contacts slide with
             * the linear law's, many of Luding's have no normal force, on
             * the adhesive branch or below their plastic overlap) */
            const int lin = cp0.normal == DEM_NORMAL_LINEAR,
                      many = lin && !plane ? 100 : 50; /* (the plane's
                      spins about z alone slide fewer: 95 of 1024) */
            for (int skip = 0; skip < 2; skip++) {
                struct dem_contact_params cp = cp0;
                struct counts c = compare(D, cp, cell, w, two, 0, skip);
                /* every branch of the law taken by many pairs */
                assert_true(c.stick > many && c.slide > many && c.open > 100);
                if (cp.normal == DEM_NORMAL_HERTZ)
                    assert_true(c.stiffer > 100 && c.softer > 100);
                /* high friction: few slide, and most groups have none
                 * that does (their sliding case skipped with skip 1) */
                cp.mu_s = cp.mu_d = 50.0;
                c = compare(D, cp, cell, w, two, 0, skip);
                if (!lin) {
                    assert_true(c.stick > 300 && c.calm > 0 && c.calm < ng);
                } else {
                    /* (in the plane none slides at all here) */
                    assert_true((plane || c.slide > 0) && c.slide < 20 &&
                                c.stick > 300);
                    assert_true(c.calm > ng * (two ? 2 : 3) / 4 &&
                                (plane ? c.calm <= ng : c.calm < ng));
                }
                /* without friction every contact slides, with no
                 * friction force */
                cp.mu_s = cp.mu_d = 0.0;
                c = compare(D, cp, cell, w, two, 0, skip);
                assert_int_equal(c.stick, 0);
                assert_int_equal(c.calm, openg);
                /* the same with -0 (the sliding force's zeros take its
                 * sign), and static friction without dynamic */
                cp.mu_s = cp.mu_d = -0.0;
                c = compare(D, cp, cell, w, two, 0, skip);
                assert_int_equal(c.stick, 0);
                cp.mu_s = 0.5;
                c = compare(D, cp, cell, w, two, 0, skip);
                assert_true(c.stick > many && c.slide > many);
                cp.mu_s = cp.mu_d = 0.0;
                /* without a tangential spring (1/k_t taken as 0; Hertz's
                 * at each contact, 0 where the gap is open) */
                cp.kt = 0.0;
                c = compare(D, cp, cell, w, two, 0, skip);
                assert_true(c.slide > 100);
            }
            /* Luding's law, each of its variants */
            if (cp0.normal == DEM_NORMAL_LUDING)
                for (int i = 0; i < 4; i++)
                    for (int skip = 0; skip < 2; skip++)
                        luding_branches(
                            compare(D, luding(cp0, i), cell, w, two, 0, skip),
                            i);
        }
}

/* Every law's pairs' groups against pair_vals, between walls (cell
 * NULL) or in a periodic cell. */
static void laws_match(const double *cell)
{
    struct pairs_data D;
    const struct dem_contact_params cp = setup(&D);
    pairs_match(cp, cell, &D);
    pairs_match(luding(cp, 1), cell, &D);
    pairs_match(hertz(cp), cell, &D);
    free(D.rec);
    free(D.wrec);
}

static void groups_match_pair_vals(void **state)
{
    (void)state;
    laws_match(NULL);
}

/* In a periodic cell: the frame's map, sheared and stretched by a few
 * per cent (struct dem_frame.m, upper triangle), and an affine gradient
 * whose velocities across a contact (some 0.02 m/s) are those of the
 * particles' own, as pair_vals takes them. */
static void cell_groups_match_pair_vals(void **state)
{
    (void)state;
    const double cell[12] = {1.02, 0.03, -0.02, 0.97, 0.025, 1.01,
                             8.0,  -5.0, 6.0,   -7.0, 4.0,   9.0};
    laws_match(cell);
}

static void wall_groups_match_wall_vals(void **state)
{
    (void)state;
    struct pairs_data D;
    const struct dem_contact_params cp0 = setup(&D);
    for (int w = 4; w <= widths(); w *= 2) {
        const int ng = NP / w;
        for (int law = 0; law < 3; law++)
            for (int skip = 0; skip < 2; skip++) {
                struct dem_contact_params cp = law == 2   ? hertz(cp0)
                                               : law == 1 ? luding(cp0, 1)
                                                          : cp0;
                struct counts c = compare(&D, cp, NULL, w, 0, 1, skip);
                assert_true(c.stick > 100 && c.slide > 100 && c.open > 100);
                if (law == 2)
                    assert_true(c.stiffer > 100 && c.softer > 100);
                cp.mu_s = cp.mu_d = 50.0;
                c = compare(&D, cp, NULL, w, 0, 1, skip);
                if (law) {
                    assert_true(c.stick > 300 && c.calm > 0 && c.calm < ng);
                } else {
                    assert_true(c.slide < 20 && c.stick > 300);
                    assert_true(c.calm > ng * 3 / 4 && c.calm < ng);
                }
                /* frictionless walls (the papers' examples) */
                cp.mu_s = cp.mu_d = 0.0;
                c = compare(&D, cp, NULL, w, 0, 1, skip);
                assert_int_equal(c.stick, 0);
                assert_true(c.slide > 300);
                cp.mu_s = cp.mu_d = -0.0;
                c = compare(&D, cp, NULL, w, 0, 1, skip);
                assert_int_equal(c.stick, 0);
                cp.mu_s = cp.mu_d = 0.0;
                cp.kt = 0.0;
                c = compare(&D, cp, NULL, w, 0, 1, skip);
                assert_true(c.slide > 300);
            }
        for (int i = 0; i < 4; i++)
            for (int skip = 0; skip < 2; skip++)
                luding_branches(
                    compare(&D, luding(cp0, i), NULL, w, 0, 1, skip), i);
    }
    free(D.rec);
    free(D.wrec);
}

/* The same in a 2D sample (the plane bit: z terms left out, the same
 * bits), pairs between walls and in a cell, and wall contacts. */
static void plane_groups_match_their_scalar_law(void **state)
{
    plane = DEM_SET_PLANE;
    groups_match_pair_vals(state);
    cell_groups_match_pair_vals(state);
    wall_groups_match_wall_vals(state);
    plane = 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(groups_match_pair_vals),
        cmocka_unit_test(cell_groups_match_pair_vals),
        cmocka_unit_test(wall_groups_match_wall_vals),
        cmocka_unit_test(plane_groups_match_their_scalar_law),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
