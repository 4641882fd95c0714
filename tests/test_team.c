/* The run's team of threads by timing (protocol/team.c) on a machine
 * made up here: a step takes a set time on the full team and another on
 * one thread, which a test may change from a step on or spoil for some
 * steps (a list build, a moment the host takes a vCPU away). The team
 * must be the faster one between trials, find a lasting change at the
 * next trial, keep its team for spoiled slices and a spoiled trial, and
 * space its trials out while they keep the team. */
#include "testutil.h"

#include "protocol/team.h"

#include <math.h>

/* The made-up machine's clock, which each step moves on. */
static double now;
static double clock_here(void)
{
    return now;
}

/* A step takes full_s on the full team and one_s on one thread; from
 * step `from` on late_full and late_one; steps [spoil_from, spoil_to)
 * take spoil times as long on the team in spoiled (0 full, 1 one).
 * shared > 0: another program shares a vCPU with the full team, which
 * has it for shared s, then waits shared s (its steps then take
 * held_s), and so on. */
struct machine {
    double full_s, one_s, late_full, late_one;
    long from, spoil_from, spoil_to;
    int spoiled;
    double spoil, shared, held_s;
};

/* What the steps of a run did: the steps on the full team and on one
 * thread, and the step at which the team in use last changed (-1:
 * never). */
struct record {
    long full_steps, one_steps, last_change;
};

static void run(struct dem_team *T, const struct machine *M, long steps,
                struct record *R)
{
    memset(R, 0, sizeof *R);
    R->last_change = -1;
    int was = T->use;
    for (long k = 0; k < steps; k++) {
        const int nt = dem_team_next(T);
        assert_true(nt == 1 || nt == T->full);
        const int one = nt == 1;
        R->full_steps += !one;
        R->one_steps += one;
        double t = k >= M->from ? (one ? M->late_one : M->late_full)
                                : (one ? M->one_s : M->full_s);
        if (k >= M->spoil_from && k < M->spoil_to && one == M->spoiled)
            t *= M->spoil;
        if (M->shared > 0.0 && !one && fmod(now, 2.0 * M->shared) >= M->shared)
            t = M->held_s;
        now += t;
        if (T->use != was)
            R->last_change = k;
        was = T->use;
    }
}

static void setup(struct dem_team *T, int full)
{
    now = 1000.0;
    dem_team_init(T, full, clock_here);
}

/* One thread, or a team of one, never tries another. */
static void a_team_of_one_has_no_trials(void **state)
{
    (void)state;
    struct dem_team T;
    struct record R;
    const struct machine M = {.full_s = 1e-3, .one_s = 1e-5, .from = 1L << 40};
    for (int full = 0; full < 2; full++) {
        setup(&T, full);
        run(&T, &M, 20000, &R);
        assert_int_equal(R.one_steps, 20000);
        assert_int_equal(T.trials, 0);
        char buf[96];
        dem_team_tally(&T, buf, sizeof buf);
        assert_string_equal(buf, "");
    }
}

/* Where two threads are faster the run stays on them but for the
 * trials' slices of one thread; where one is faster it goes to one at
 * the first trial and stays there but for the trials' slices of two. */
static void the_faster_team_runs_between_trials(void **state)
{
    (void)state;
    struct dem_team T;
    struct record R;
    /* 100 s of steps of 1e-4 s on two threads */
    const struct machine fast2 = {
        .full_s = 1e-4, .one_s = 1.8e-4, .from = 1L << 40};
    setup(&T, 2);
    run(&T, &fast2, 1000000, &R);
    assert_int_equal(T.use, 2);
    assert_int_equal(T.changes, 0);
    /* a trial of 8 slices of 0.02 s takes 0.16 s, so trials come at
     * least 0.16 / DEM_TEAM_SHARE = 4 s apart: at 0.05 s, then after 4,
     * 4, 4, 8, 16, 32 s (37 s in), the next 64 s later, past 100 s */
    assert_int_equal(T.trials, 7);
    /* a slice of one thread: 112 steps of 1.8e-4 s */
    assert_int_equal(R.one_steps, 7L * DEM_TEAM_SLICES / 2 * 112);
    char buf[96];
    dem_team_tally(&T, buf, sizeof buf);
    assert_string_equal(buf, "2 threads, one thread in 0 % of the steps "
                             "(7 trials, 0 changes)");
    /* one thread faster: after the first trial (0.05 s in, about 400
     * steps) on one thread */
    const struct machine fast1 = {
        .full_s = 1.3e-4, .one_s = 1.05e-4, .from = 1L << 40};
    setup(&T, 2);
    run(&T, &fast1, 1000000, &R);
    assert_int_equal(T.use, 1);
    assert_int_equal(T.changes, 1);
    /* slices of 154 steps on two threads, 191 on one; two trials, the
     * second at once, confirming the first */
    const long trial = DEM_TEAM_SLICES / 2 * (154 + 191);
    assert_in_range(R.last_change, 385 + 2 * trial,
                    385 + 2 * DEM_TEAM_PEEK + 2 * trial);
    /* on two threads: the steps before the first trial and between the
     * two, and the trials' slices */
    assert_int_equal(R.full_steps, R.last_change - 2 * trial +
                                       T.trials * DEM_TEAM_SLICES / 2 * 154);
}

/* Within DEM_TEAM_MARGIN the team in use stays. */
static void a_near_tie_keeps_the_team(void **state)
{
    (void)state;
    struct dem_team T;
    struct record R;
    const struct machine tie = {
        .full_s = 1.03e-4, .one_s = 1.01e-4, .from = 1L << 40};
    setup(&T, 2);
    run(&T, &tie, 200000, &R);
    assert_int_equal(T.use, 2);
    assert_int_equal(T.changes, 0);
    assert_true(T.trials >= 4);
}

/* The host moves the vCPUs 30 s into the run, and one thread becomes
 * the faster: the trials, 16 s apart by then, find it at the next one,
 * and come 4, 4, 4, 8, 16 s apart again after the change. */
static void a_lasting_change_is_found_at_the_next_trial(void **state)
{
    (void)state;
    struct dem_team T;
    struct record R;
    const struct machine moved = {.full_s = 1e-4,
                                  .one_s = 1.5e-4,
                                  .late_full = 2e-4,
                                  .late_one = 1.5e-4,
                                  .from = 300000};
    setup(&T, 2);
    run(&T, &moved, 600000, &R);
    assert_int_equal(T.use, 1);
    assert_int_equal(T.changes, 1);
    /* trials at 0.05, 4.2, 8.4, 12.5, 20.7 and 36.9 s: the last of them,
     * at 2e-4 s a step by then about step 334500, finds it, a second at
     * once confirms it; then trials 4, 8, 12, 20 and 36 s after it, in
     * the 40 s left */
    assert_in_range(R.last_change, 333000, 337000);
    assert_int_equal(T.trials, 12);
}

/* A moment in which the host holds a vCPU back, long enough to slow
 * the full team in a whole trial, changes nothing: the second trial
 * does not confirm it. */
static void a_trial_the_host_spoils_changes_nothing(void **state)
{
    (void)state;
    struct dem_team T;
    struct record R;
    /* the first trial, from step 511 (0.05 s in), its slices of two
     * threads 67 steps of 3e-4 s, of one 134 of 1.5e-4 s */
    const struct machine held = {.full_s = 1e-4,
                                 .one_s = 1.5e-4,
                                 .from = 1L << 40,
                                 .spoil_from = 500,
                                 .spoil_to = 511 + 4 * (67 + 134),
                                 .spoiled = 0,
                                 .spoil = 3.0};
    setup(&T, 2);
    run(&T, &held, 20000, &R);
    assert_int_equal(T.trials, 2);
    assert_int_equal(T.changes, 0);
    assert_int_equal(R.last_change, -1);
}

/* Slices that a list build or the host spoils decide nothing: a team's
 * time is its slices' median. */
static void a_spoiled_slice_does_not_decide(void **state)
{
    (void)state;
    struct dem_team T;
    struct record R;
    /* the first trial's first slice of two threads (the clock read
     * after 16 steps, 0.05 s in: step 511) ten times as slow */
    const struct machine spoilt = {.full_s = 1e-4,
                                   .one_s = 1.5e-4,
                                   .from = 1L << 40,
                                   .spoil_from = 500,
                                   .spoil_to = 560,
                                   .spoiled = 0,
                                   .spoil = 10.0};
    setup(&T, 2);
    run(&T, &spoilt, 20000, &R);
    assert_true(T.trials >= 1);
    assert_int_equal(T.changes, 0);
    assert_int_equal(R.last_change, -1);
    /* nor a lucky one: two threads slower than one but in the first
     * trial's first slice (from step 255), twice as fast there */
    const struct machine lucky = {.full_s = 2e-4,
                                  .one_s = 1.5e-4,
                                  .from = 1L << 40,
                                  .spoil_from = 250,
                                  .spoil_to = 460,
                                  .spoiled = 0,
                                  .spoil = 0.5};
    setup(&T, 2);
    run(&T, &lucky, 15000, &R);
    assert_int_equal(T.trials, 2); /* (the second confirming the first) */
    assert_int_equal(T.use, 1);
}

/* Another program shares a vCPU of the full team: for 3 ms in 6 the
 * team's steps take 1e-4 s, for the other 3 ms 2e-3 s (1.9e-4 s a step
 * on average), one thread's 1.5e-4 s. The fastest of short slices would
 * see 1e-4; the trials take one thread. */
static void a_vcpu_shared_with_another_program_is_seen(void **state)
{
    (void)state;
    struct dem_team T;
    struct record R;
    const struct machine busy = {.full_s = 1e-4,
                                 .one_s = 1.5e-4,
                                 .from = 1L << 40,
                                 .shared = 3e-3,
                                 .held_s = 2e-3};
    setup(&T, 2);
    run(&T, &busy, 20000, &R);
    assert_int_equal(T.trials, 2);
    assert_int_equal(T.use, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_team_of_one_has_no_trials),
        cmocka_unit_test(the_faster_team_runs_between_trials),
        cmocka_unit_test(a_near_tie_keeps_the_team),
        cmocka_unit_test(a_lasting_change_is_found_at_the_next_trial),
        cmocka_unit_test(a_trial_the_host_spoils_changes_nothing),
        cmocka_unit_test(a_spoiled_slice_does_not_decide),
        cmocka_unit_test(a_vcpu_shared_with_another_program_is_seen),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
