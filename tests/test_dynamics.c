/* Equations of motion: energy conservation without dissipation over many
 * contacts, and 2D runs that never leave the plane. */
#include "testutil.h"

#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "measure/measure.h"

static void gas(struct dem_sim *s, int dim, int nside, double a, double v,
                uint64_t seed)
{
    struct dem_rng g;
    dem_rng_seed(&g, seed);
    const double h = 0.1 / nside;
    int nz = dim == 3 ? nside : 1;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < nside; j++)
            for (int i = 0; i < nside; i++) {
                double r = a * (0.7 + 0.3 * dem_rng_uniform(&g));
                int id = test_add(s, (i + 0.5) * h, (j + 0.5) * h,
                                  dim == 3 ? (k + 0.5) * h : 0.0, r);
                s->p.vx[id] = v * (2 * dem_rng_uniform(&g) - 1);
                s->p.vy[id] = v * (2 * dem_rng_uniform(&g) - 1);
                if (dim == 3)
                    s->p.vz[id] = v * (2 * dem_rng_uniform(&g) - 1);
            }
}

static double total_energy(struct dem_sim *s)
{
    /* recompute forces with measurement on: same state, same forces */
    s->measure = 1;
    dem_sim_forces(s);
    struct dem_sample smp;
    const double L0[3] = {1, 1, 1};
    dem_measure(s, L0, 1.0, 0.0, 0, &smp);
    return smp.e_kin + smp.e_rot + smp.e_pot;
}

/* Frictionless, undamped elastic spheres in a closed box: total energy
 * (kinetic + elastic) is conserved over thousands of collisions, also when
 * the particles are re-ordered at every rebuild. */
static void energy_conserved(int reorder)
{
    struct dem_config c;
    test_config(&c, 3);
    c.contact.mu_s = c.contact.mu_d = 0.0;
    c.contact.gamma_n = 0.0;
    c.time_step = 2e-5; /* t_c / 50 for the lightest pair */
    struct dem_sim s;
    const int nside = 6;
    test_sim(&s, &c, nside * nside * nside, 0.0, 0.1);
    s.reorder = reorder;
    gas(&s, 3, nside, 7e-3, 0.5, 5);
    test_ready(&s);
    double e0 = total_energy(&s);
    long contacts = 0;
    for (int k = 0; k < 100; k++) {
        s.measure = 1;
        test_step(&s, 100);
        contacts += (long)s.sums.n_pp;
    }
    double e1 = total_energy(&s);
    /* contacts seen at 100 samples: many collisions happened */
    assert_true(contacts > 500);
    assert_rel(e1, e0, 2e-3);
    dem_sim_destroy(&s);
}

static void energy_conserved_without_damping(void **state)
{
    (void)state;
    energy_conserved(0);
    energy_conserved(1);
}

/* 2D: z, v_z, w_x and w_y stay exactly zero, with friction, rotation,
 * walls and gravity in the plane. */
static void two_d_stays_in_plane(void **state)
{
    (void)state;
    struct dem_config c;
    test_config(&c, 2);
    c.gravity[1] = -9.81;
    c.contact.gamma_n = 0.05;
    c.contact.gamma_t = 0.01;
    c.contact.wall_mu = 0.3;
    c.damping.gamma_br = 0.05;
    c.time_step = 2e-5;
    struct dem_sim s;
    test_sim(&s, &c, 100, 0.0, 0.1);
    gas(&s, 2, 10, 5e-3, 0.5, 6);
    for (int i = 0; i < s.p.n; i++)
        s.p.wz[i] = 10.0 * (i % 3 - 1);
    test_ready(&s);
    test_step(&s, 5000);
    int moved = 0; /* of the discs that started without spin */
    for (int i = 0; i < s.p.n; i++) {
        assert_true(s.p.z[i] == 0.0);
        assert_true(s.p.vz[i] == 0.0);
        assert_true(s.p.wx[i] == 0.0);
        assert_true(s.p.wy[i] == 0.0);
        moved += i % 3 == 1 && fabs(s.p.wz[i]) > 0.0;
    }
    /* friction turned most of them (the others' spins only decay) */
    if (moved < 25)
        fail_msg("%d of 33 discs turned", moved);
    dem_sim_destroy(&s);
}

/* Whether run_threads runs in a periodic cell (1) or between walls (0),
 * with rolling and torsion resistance (1) or without (0), and its
 * normal law: the linear law, Luding's (adhesive, with a plasticity
 * depth that its contacts exceed) or Hertz's, at about the linear law's
 * stiffness. */
static int run_cell;
static int run_resist;
static int run_normal = DEM_NORMAL_LINEAR;
/* and in 2D (run_dim 2: discs, gravity along y, rolling resistance
 * only), with the passes of the plane (DEM_SET_PLANE) or, with
 * run_plane_off, the 3D passes, which compute the plane's zeros */
static int run_dim = 3;
static int run_plane_off;
/* > 0: the chained steps of run_threads change their team between the
 * given threads and one every run_team steps, as a run's team by timing
 * does (protocol/team.h) */
static int run_team;

/* Positions and spins by particle id (all of them) after a frictional,
 * damped run with re-ordering, between walls or (run_cell) in a periodic
 * cell compressed and sheared, on the given number of threads; the steps
 * chained (test_step) or one by one; with the force pass pass (the
 * environment variable DEMBOX_PASS; NULL: unset, chosen by timing). Then,
 * from out[RUN_PARTICLES], the walls' positions and the cell's stress
 * (its virial, whose last bits the particles feel only through the
 * servo). */
#define RUN_PARTICLES (6 * 729) /* the most a run has: 9^3 in a 3D cell */
#define RUN_OUT (RUN_PARTICLES + 6 + 9)
static void run_threads(int threads, int chained, const char *pass, double *out)
{
    omp_set_num_threads(threads);
    if (pass)
        setenv("DEMBOX_PASS", pass, 1);
    else
        unsetenv("DEMBOX_PASS");
    struct dem_config c;
    const int dim = run_dim;
    test_config(&c, dim);
    c.contact.gamma_n = 0.05;
    c.contact.gamma_t = 0.01;
    c.contact.wall_mu = 0.2;
    c.damping.gamma_b = 0.01;
    c.damping.gamma_br = 0.02;
    c.gravity[dim - 1] = run_cell ? 0.0 : -9.81;
    c.time_step = 2e-5;
    if (run_cell)
        c.box.boundary = DEM_BOUNDARY_PERIODIC;
    c.contact.normal = run_normal;
    c.contact.k1 = 2500.0;
    c.contact.k2 = 5000.0;
    c.contact.kc = 1000.0;
    c.contact.phi_f = 0.005;
    c.contact.E = 1e7;
    c.contact.nu = 0.25;
    c.contact.restitution = 0.5;
    if (run_resist) {
        c.contact.rolling = DEM_RESIST_LUDING;
        c.contact.torsion = dim == 3 ? DEM_RESIST_LUDING : DEM_RESIST_NONE;
        c.contact.kr = 50.0;
        c.contact.gamma_r = 0.01;
        c.contact.mu_r = c.contact.wall_mu_r = 0.1;
        c.contact.ko = 20.0;
        c.contact.gamma_o = 0.01;
        c.contact.mu_o = c.contact.wall_mu_o = 0.1;
    }
    struct dem_sim s;
    /* in the cell 729 particles: two threads split a virial block
     * unless they keep to its bounds, and 729 % 8 particles are left
     * over after the SIMD lanes */
    const int nside = dim == 2 ? (run_cell ? 23 : 22) : run_cell ? 9 : 8;
    test_sim(&s, &c, dim == 2 ? nside * nside : nside * nside * nside, 0.0,
             0.1);
    s.reorder = 1;
    gas(&s, dim, nside,
        dim == 2   ? (run_cell ? 2.1e-3 : 2.2e-3)
        : run_cell ? 5e-3
                   : 6e-3,
        0.3, 9);
    test_ready(&s);
    assert_int_equal(s.pass.plane, dim == 2);
    if (run_plane_off)
        s.pass.plane = 0;
    /* the ring pass in chunks of 64 pairs (of some 1000): each thread
     * finishes its particles in many pieces */
    s.pairs.ring_chunk = 64;
    dem_wall_set_stress(&s.wall[2 * dim - 1], 0.05, 5.0, 0.0, 200.0, 0.0, 0.0,
                        0.0);
    if (run_cell) /* shear along x by a fifth of the cell */
        dem_wall_set_strain(&s.cell.tilt[dim == 2 ? DEM_TILT_XY : DEM_TILT_XZ],
                            DEM_PROFILE_LINEAR, 0.02, 0.06, s.t);
    if (chained && run_team) {
        for (int k = 0; k < 3000; k++) {
            struct dem_error err = {0};
            omp_set_num_threads(k / run_team % 2 ? 1 : threads);
            s.chain = k + 1 < 3000;
            assert_int_equal(dem_sim_step(&s, &err), DEM_OK);
        }
        omp_set_num_threads(threads);
    } else if (chained) {
        test_step(&s, 3000);
    } else {
        for (int k = 0; k < 3000; k++) {
            struct dem_error err = {0};
            assert_int_equal(dem_sim_step(&s, &err), DEM_OK);
        }
    }
    assert_true(s.nbuild > 3);
    /* the records pass's chained steps between walls: with "blocks"
     * each thread owns its block (neighbor/blocks.h), with "records"
     * never */
    if (threads > 1 && chained && !run_cell && pass &&
        !strcmp(pass, "blocks")) {
        assert_true(s.pass.with_blocks > 1000);
        /* each block starts on a cache line of the particles' arrays
         * (core/particles.h) */
        const struct dem_blocks *B = &s.pairs.blocks;
        assert_int_equal(B->nt, threads);
        for (int t = 0; t < B->nt; t++)
            assert_int_equal(B->t[t].a % DEM_PARTICLE_LINE, 0);
    }
    if (pass && !strcmp(pass, "records"))
        assert_int_equal(s.pass.with_blocks, 0);
    /* every particle (the ids are 0..n-1), the slots beyond n zero: a
     * buffer reused from an earlier run keeps nothing of it */
    assert_true(6 * s.p.n <= RUN_PARTICLES);
    memset(out, 0, RUN_OUT * sizeof *out);
    for (int i = 0; i < s.p.n; i++) {
        assert_true(s.p.id[i] >= 0 && s.p.id[i] < s.p.n);
        double *o = out + 6 * s.p.id[i];
        o[0] = s.p.x[i];
        o[1] = s.p.y[i];
        o[2] = s.p.z[i];
        o[3] = s.p.wx[i];
        o[4] = s.p.wy[i];
        o[5] = s.p.wz[i];
    }
    for (int w = 0; w < 6; w++)
        out[RUN_PARTICLES + w] = s.wall[w].pos;
    for (int u = 0; u < 9; u++)
        out[RUN_PARTICLES + 6 + u] = s.cell.stress[u / 3][u % 3];
    dem_sim_destroy(&s);
    /* the run's threads, whichever team each pass ran on ("single") */
    assert_int_equal(omp_get_max_threads(), threads);
    omp_set_num_threads(1);
    unsetenv("DEMBOX_PASS");
}

/* Whether run_threads gives the same numbers bit for bit both ways. */
static void assert_same_runs(int threads_a, int chained_a, const char *pass_a,
                             int threads_b, int chained_b, const char *pass_b)
{
    const int n = RUN_OUT;
    double *a = calloc((size_t)n, sizeof *a), *b = calloc((size_t)n, sizeof *b);
    run_threads(threads_a, chained_a, pass_a, a);
    run_threads(threads_b, chained_b, pass_b, b);
    assert_memory_equal(a, b, (size_t)n * sizeof *a);
    free(a);
    free(b);
}

/* The force sums run in a fixed order (contact/forces.c), so one and two
 * threads give the same run bit for bit. */
static void threads_give_identical_results(void **state)
{
    (void)state;
    assert_same_runs(1, 1, NULL, 2, 1, NULL);
    run_cell = 1; /* the cell's stress too (its virial, contact/pass.c) */
    assert_same_runs(1, 1, NULL, 2, 1, NULL);
    run_cell = 0;
    run_resist = 1; /* the resistances' torques too */
    assert_same_runs(1, 1, NULL, 2, 1, NULL);
    assert_same_runs(1, 1, "gathers", 2, 0, "gathers");
    run_resist = 0;
}

/* A chained step does the next step's half kick and drift in its force
 * pass (dem_sim_step): the same arithmetic, so the same run bit for bit
 * as steps one by one. */
static void chained_steps_give_identical_results(void **state)
{
    (void)state;
    assert_same_runs(1, 1, NULL, 1, 0, NULL);
    run_cell = 1;
    assert_same_runs(1, 1, NULL, 1, 0, NULL);
    run_cell = 0;
}

/* A run's team by timing (protocol/team.h) changes between any two
 * steps, chained or not, a list build, the records or the rings a pass
 * left for the next: the same run bit for bit as on one thread, with the
 * passes chosen by timing (every 37 steps, and at every step) and with
 * the blocks and the ring forced, between walls; in a cell too. */
static void teams_changing_between_steps_give_identical_results(void **state)
{
    (void)state;
    double *ref = calloc(RUN_OUT, sizeof *ref),
           *got = calloc(RUN_OUT, sizeof *got);
    const size_t size = RUN_OUT * sizeof *ref;
    for (int cell = 0; cell < 2; cell++) {
        run_cell = cell;
        run_team = 0;
        run_threads(1, 1, NULL, ref);
        run_team = 37;
        run_threads(2, 1, NULL, got);
        assert_memory_equal(got, ref, size);
        if (cell)
            continue;
#if DEM_HAVE_PASS_RECORDS
        run_threads(2, 1, "blocks", got);
        assert_memory_equal(got, ref, size);
        run_threads(2, 1, "ring", got);
        assert_memory_equal(got, ref, size);
#endif
        run_team = 1;
        run_threads(2, 1, NULL, got);
        assert_memory_equal(got, ref, size);
    }
    run_cell = run_team = 0;
    free(ref);
    free(got);
}

/* The force pass compiled with and without hardware gathers, and with
 * the pairs' particle values from records, computes the same operations
 * (contact/pass.h): each alone, and both by turns as the
 * timing trials run them (3000 steps: two trials), give the same run bit
 * for bit. An unknown DEMBOX_PASS is refused. */
static void force_passes_give_identical_results(void **state)
{
    (void)state;
    assert_same_runs(1, 1, "gathers", 1, 1, NULL);
#if DEM_PASS_LOADS
    assert_same_runs(1, 1, "gathers", 1, 1, "loads");
    assert_same_runs(2, 1, "loads", 1, 1, NULL);
#endif
#if DEM_HAVE_PASS_RECORDS
    /* chained: the records written at the drift are read by the next
     * pass; one by one: filled at every pass */
    assert_same_runs(1, 1, "gathers", 1, 1, "records");
    assert_same_runs(2, 1, "records", 1, 0, "records");
    /* threads that own their blocks (neighbor/blocks.h); three own
     * blocks thinner than the pairs' reach: a block's twins come from
     * both earlier blocks */
    assert_same_runs(2, 1, "blocks", 1, 0, "records");
    assert_same_runs(3, 1, "blocks", 1, 1, "gathers");
    /* the ring pass: chained, the forces in rings (with two threads the
     * first particles of the second block wait for the barrier) */
    assert_same_runs(1, 1, "ring", 1, 0, "records");
    assert_same_runs(2, 1, "ring", 1, 1, "gathers");
    /* the records pass on one of two threads, the other idle */
    assert_same_runs(2, 1, "single", 2, 1, "blocks");
    /* with the rolling and torsion resistances, whose torques the pairs
     * keep beside their forces */
    run_resist = 1;
    assert_same_runs(1, 1, "ring", 1, 0, "records");
    assert_same_runs(2, 1, "ring", 1, 1, "gathers");
    assert_same_runs(2, 1, "blocks", 1, 1, "gathers"); /* twins' torques */
    run_resist = 0;
    /* Luding's law, whose groups keep its history of largest overlaps,
     * and Hertz's, whose tangential law's stiffness and viscosity are
     * each contact's, between walls and in a cell */
    static const int laws[] = {DEM_NORMAL_LUDING, DEM_NORMAL_HERTZ};
    for (int u = 0; u < 2; u++) {
        run_normal = laws[u];
        assert_same_runs(1, 1, "gathers", 1, 1, "records");
        assert_same_runs(2, 1, "ring", 1, 0, "gathers");
        /* the blocks' twins copy and update dmax and kt_last */
        assert_same_runs(3, 1, "blocks", 1, 1, "gathers");
        run_cell = 1;
        assert_same_runs(2, 1, "gathers", 1, 1, "records");
        assert_same_runs(2, 1, "ring", 1, 0, "records");
        run_cell = 0;
    }
    run_normal = DEM_NORMAL_LINEAR;
    run_cell = 1;
    assert_same_runs(2, 1, "gathers", 1, 1, "records");
    /* the ring in a cell: the pairs through an image read from the
     * list's array, the virial's blocks summed in pieces; with two
     * threads the second block's last particles wait too (pairs through
     * the z faces from the first block) */
    assert_same_runs(1, 1, "ring", 1, 0, "records");
    assert_same_runs(2, 1, "ring", 1, 1, "records");
    assert_same_runs(2, 1, "single", 1, 0, "gathers");
    /* four threads: a thread waits on several earlier ones, image pairs
     * of more than one earlier block, and the waiting particles shared
     * over more than two ranges; blocks on four threads between walls */
    assert_same_runs(4, 1, "ring", 1, 0, "records");
    run_cell = 0;
    assert_same_runs(4, 1, "blocks", 1, 0, "records");
    /* the resistances in a 3D cell */
    run_cell = run_resist = 1;
    assert_same_runs(2, 1, "ring", 1, 0, "gathers");
    run_cell = run_resist = 0;
#endif
    struct dem_config c;
    test_config(&c, 3);
    struct dem_sim s;
    test_sim(&s, &c, 1, 0.0, 0.1);
    test_add(&s, 0.05, 0.05, 0.05, 0.01);
    setenv("DEMBOX_PASS", "scatters", 1);
    struct dem_error err = {0};
    assert_int_equal(dem_sim_ready(&s, &err), DEM_EUSAGE);
    assert_non_null(strstr(err.msg, "DEMBOX_PASS: 'scatters'"));
    unsetenv("DEMBOX_PASS");
    dem_sim_destroy(&s);
}

/* The passes of a 2D sample (DEM_SET_PLANE) leave out the zeros of the
 * plane (z, v_z, w_x, w_y, f_z, the torques' x and y) and give the run
 * of the 3D passes, which compute them, to the last bit; and as those,
 * the same bits for any threads, chained steps and pass (the groups of
 * the records passes and gcc's lanes of the gathers pass). Between walls
 * and in a sheared cell, with each normal law and the rolling
 * resistance. */
static void plane_passes_give_the_3d_run(void **state)
{
    (void)state;
    run_dim = 2;
    const int n = RUN_OUT;
    double *a = calloc((size_t)n, sizeof *a), *b = calloc((size_t)n, sizeof *b);
    static const int laws[] = {DEM_NORMAL_LINEAR, DEM_NORMAL_LUDING,
                               DEM_NORMAL_HERTZ};
#if DEM_HAVE_PASS_RECORDS
    static const char *const pass[] = {"gathers", "ring"};
#else
    static const char *const pass[] = {"gathers", NULL};
#endif
    for (int cell = 0; cell < 2; cell++)
        for (int u = 0; u < 4; u++) {
            run_cell = cell;
            run_normal = laws[u % 3];
            run_resist = u == 3;
            run_plane_off = 1;
            run_threads(1, 0, NULL, b);
            run_plane_off = 0;
            for (int v = 0; v < 2; v++) {
                run_threads(v + 1, 1, pass[v], a);
                assert_memory_equal(a, b, (size_t)n * sizeof *a);
            }
            int moved = 0; /* discs that turned */
            for (int i = 0; i < RUN_PARTICLES / 6; i++)
                moved += a[6 * i + 5] != 0.0;
            assert_true(moved > 400);
        }
    run_cell = run_resist = 0;
    run_normal = DEM_NORMAL_LINEAR;
#if DEM_HAVE_PASS_RECORDS
    assert_same_runs(1, 1, "gathers", 2, 1, "ring");
    assert_same_runs(2, 1, "blocks", 1, 0, "records");
    run_cell = 1;
    assert_same_runs(2, 1, "ring", 1, 1, "gathers");
    run_cell = 0;
#endif
    free(a);
    free(b);
    run_dim = 3;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(energy_conserved_without_damping),
        cmocka_unit_test(two_d_stays_in_plane),
        cmocka_unit_test(threads_give_identical_results),
        cmocka_unit_test(chained_steps_give_identical_results),
        cmocka_unit_test(force_passes_give_identical_results),
        cmocka_unit_test(teams_changing_between_steps_give_identical_results),
        cmocka_unit_test(plane_passes_give_the_3d_run),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
