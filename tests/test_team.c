/* The run's team of threads by timing (protocol/team.c) on a machine
 * made up here: a step takes a set time on the full team and another on
 * one thread, which a test may change from a step on or spoil for some
 * steps (a list build, a moment the host takes a vCPU away). The team
 * must be the faster one between trials, find a lasting change at the
 * next trial, keep its team for spoiled slices, and space its trials
 * out while they keep the team. */
#include "testutil.h"

#include "protocol/team.h"

/* The made-up machine's clock, which each step moves on. */
static double now;
static double clock_here(void)
{
    return now;
}

/* A step takes full_s on the full team and one_s on one thread; from
 * step `from` on late_full and late_one; steps [spoil_from, spoil_to)
 * take spoil times as long on the team in spoiled (0 full, 1 one). */
struct machine {
    double full_s, one_s, late_full, late_one;
    long from, spoil_from, spoil_to;
    int spoiled;
    double spoil;
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
    /* trials at 0.05 s, then 1, 2, 4, ... 64 s apart: 0.05 + 1 + 2 + 4 +
     * 8 + 16 + 32 < 100 s, a seventh at 63.05 + 64 > 100 s */
    assert_int_equal(T.trials, 7);
    assert_int_equal(R.one_steps, 7L * DEM_TEAM_SLICES / 2 * DEM_TEAM_SLICE);
    char buf[96];
    dem_team_tally(&T, buf, sizeof buf);
    assert_string_equal(buf, "2 threads, one thread in 0 % of the steps "
                             "(7 trials, 0 changes)");
    /* one thread faster: after the first trial (0.05 s in, about 400
     * steps) on one thread */
    const struct machine fast1 = {
        .full_s = 1.25e-4, .one_s = 1e-4, .from = 1L << 40};
    setup(&T, 2);
    run(&T, &fast1, 1000000, &R);
    assert_int_equal(T.use, 1);
    assert_int_equal(T.changes, 1);
    assert_in_range(R.last_change, 400,
                    400 + DEM_TEAM_PEEK + DEM_TEAM_SLICES * DEM_TEAM_SLICE);
    /* on two threads: the steps before the first trial, and the trials'
     * slices */
    assert_int_equal(R.full_steps,
                     R.last_change - DEM_TEAM_SLICES * DEM_TEAM_SLICE +
                         T.trials * DEM_TEAM_SLICES / 2 * DEM_TEAM_SLICE);
}

/* Within DEM_TEAM_MARGIN the team in use stays. */
static void a_near_tie_keeps_the_team(void **state)
{
    (void)state;
    struct dem_team T;
    struct record R;
    const struct machine tie = {
        .full_s = 1.02e-4, .one_s = 1e-4, .from = 1L << 40};
    setup(&T, 2);
    run(&T, &tie, 200000, &R);
    assert_int_equal(T.use, 2);
    assert_int_equal(T.changes, 0);
    assert_true(T.trials >= 4);
}

/* The host moves the vCPUs 30 s into the run, and one thread becomes
 * the faster: the trials, 32 s apart by then, find it at the next one,
 * and come 1, 2, 4, ... s apart again after the change. */
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
    /* trials at 0.05, 1.05, 3.05, 7.05, 15.05, 31.05 s: the one at 31.05
     * s, at 2e-4 s a step by then about step 305250, finds it; then
     * trials 1, 3, 7, 15 and 31 s after it, in the 44 s left */
    assert_in_range(R.last_change, 305000, 305000 + 2000);
    assert_int_equal(T.trials, 11);
}

/* Slices that a list build or the host spoils decide nothing: each
 * team's fastest slice is its time. */
static void a_spoiled_slice_does_not_decide(void **state)
{
    (void)state;
    struct dem_team T;
    struct record R;
    /* the first trial's first slice of two threads (the clock read
     * after 16 steps, 0.05 s in: step 512) ten times as slow */
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
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_team_of_one_has_no_trials),
        cmocka_unit_test(the_faster_team_runs_between_trials),
        cmocka_unit_test(a_near_tie_keeps_the_team),
        cmocka_unit_test(a_lasting_change_is_found_at_the_next_trial),
        cmocka_unit_test(a_spoiled_slice_does_not_decide),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
