/* The force pass's timing trials (contact/trials.c) on a machine made
 * up here: each variant's pass takes a set time, which a test may change
 * from a step on, or for one trial (a moment the host spoils). The
 * trials must run the fastest variant between them, let a lasting change
 * through, and not hand the steps to a slower variant for one spoiled
 * trial. */
#include "testutil.h"

#include "contact/trials.h"

/* A made-up machine: variant v's pass takes cost[v] s, from step `from`
 * on late[v] instead; the passes of `spoiled` take spoil times as long
 * in trial number `spoil_trial` (counted from 1, 0: none). */
struct machine {
    double cost[DEM_MAX_PASSES], late[DEM_MAX_PASSES];
    long from;
    int spoiled, spoil_trial;
    double spoil;
};

/* What steps of a run did: each variant's passes, its timed passes
 * (trials), the trials begun, and the first step at which variant
 * `watch` was the one in use (-1: never). */
struct record {
    long runs[DEM_MAX_PASSES], timed[DEM_MAX_PASSES];
    int trials, in_trials[DEM_MAX_PASSES];
    int watch;
    long first_in_use;
};

static void run(struct dem_pass_choice *C, const struct machine *M, long steps,
                struct record *R)
{
    memset(R->runs, 0, sizeof R->runs);
    memset(R->timed, 0, sizeof R->timed);
    memset(R->in_trials, 0, sizeof R->in_trials);
    R->trials = 0;
    R->first_in_use = -1;
    int was_in_trial = 0, seen[DEM_MAX_PASSES] = {0};
    unsigned set = 0, ran = 0; /* the trial's variants, and those timed */
    for (long k = 0; k < steps; k++) {
        int timed;
        const int v = dem_trials_next(C, &timed);
        R->runs[v]++;
        if (!timed || !was_in_trial) /* a trial ended: all its set ran */
            assert_int_equal(ran, set);
        if (!timed)
            assert_int_equal(dem_trials_set(C), 0);
        if (timed) {
            if (!was_in_trial) {
                R->trials++;
                memset(seen, 0, sizeof seen);
                set = dem_trials_set(C);
                ran = 0;
            }
            /* (dem_trials_set, for DEMBOX_TRIALS_LOG: the same all
             * through a trial, and the variants it times) */
            assert_int_equal(dem_trials_set(C), set);
            ran |= 1u << v;
            if (!seen[v]++)
                R->in_trials[v]++;
            R->timed[v]++;
            double t = k >= M->from ? M->late[v] : M->cost[v];
            if (R->trials == M->spoil_trial && v == M->spoiled)
                t *= M->spoil;
            dem_trials_time(C, t);
        }
        was_in_trial = timed;
        if (R->first_in_use < 0 && C->current == R->watch)
            R->first_in_use = k;
    }
}

static void setup(struct dem_pass_choice *C, int nvar, int first)
{
    memset(C, 0, sizeof *C);
    C->forced = -1;
    dem_trials_init(C, nvar, first);
}

static long sum(const long *a, int n)
{
    long s = 0;
    for (int v = 0; v < n; v++)
        s += a[v];
    return s;
}

/* Variant 1 the fastest, 0 the default before the first trial: from
 * the first trial on, 1 runs every pass but the trials' (no second trial
 * for the first choice), and wins every trial. Variants 0 and 2,
 * within TRIAL_FAR (1.25) of it, are timed in every trial; variant 3, twice as
 * slow, sits out 1, 3, 7, 7, ... trials after each it ran in. */
static void fastest_runs_and_far_losers_sit_out(void **state)
{
    (void)state;
    struct dem_pass_choice C;
    setup(&C, 4, 0);
    const struct machine M = {{0.95, 0.8, 0.9, 1.6}, {0}, 1L << 40, -1, 0, 1};
    struct record R = {.watch = 1};
    const long steps = DEM_TRIAL_FIRST + 40L * DEM_TRIAL_EVERY;
    run(&C, &M, steps, &R);
    assert_int_equal(C.current, 1);
    /* a trial starts at step 49, then 2000 steps after the last began,
     * plus its passes but one (15, with variant 3 20): 40 of them */
    assert_int_equal(R.trials, 40);
    assert_int_equal(C.won[1], 40);
    assert_int_equal(sum(C.won, 4), 40);
    assert_int_equal(C.proposed, 0);
    /* switched right after the first trial (4 variants, 5 passes each) */
    assert_int_equal(R.first_in_use,
                     DEM_TRIAL_FIRST - 2 + 4 * DEM_TRIAL_ROUNDS);
    assert_int_equal(R.in_trials[0], 40);
    assert_int_equal(R.in_trials[2], 40);
    /* trials 1, 3, 7, 15, 23, 31, 39 */
    assert_int_equal(R.in_trials[3], 7);
    /* every pass not in a trial ran the fastest variant */
    assert_int_equal(R.runs[1] - R.timed[1],
                     steps - sum(R.timed, 4) - (DEM_TRIAL_FIRST - 1));
    assert_int_equal(R.runs[0] - R.timed[0], DEM_TRIAL_FIRST - 1);
    /* its best figure is its pass time */
    assert_true(C.best[1] == 0.8);
}

/* The records-like variant 0 is the faster; in one trial the host spoils
 * all its passes (3x), and variant 1 wins that trial. The second trial,
 * DEM_TRIAL_RECHECK steps later, does not confirm it: variant 1 runs no
 * pass outside the trials, where without the second trial it would have
 * run DEM_TRIAL_EVERY of them. */
static void one_spoiled_trial_changes_nothing(void **state)
{
    (void)state;
    struct dem_pass_choice C;
    setup(&C, 2, 1);
    const struct machine M = {{1.0, 1.2}, {0}, 1L << 40, 0, 3, 3.0};
    struct record R = {.watch = 0};
    run(&C, &M, DEM_TRIAL_FIRST + 7L * DEM_TRIAL_EVERY, &R);
    assert_int_equal(C.current, 0);
    assert_int_equal(C.proposed, 1);
    assert_int_equal(C.confirmed, 0);
    /* 7 trials and the second one of the spoiled trial */
    assert_int_equal(R.trials, 8);
    assert_int_equal(sum(C.won, 2), 7);
    assert_int_equal(C.won[0], 7);
    /* after the first trial variant 1 ran in the trials only */
    assert_int_equal(R.runs[1] - R.timed[1], DEM_TRIAL_FIRST - 1);
}

/* From step `from` on, variant 1 is the faster: the first trial after it
 * proposes variant 1, the second confirms it DEM_TRIAL_RECHECK steps
 * later, and it runs from then on. Equal times (before) change
 * nothing: the variant in use keeps a tie. */
static void lasting_change_is_confirmed(void **state)
{
    (void)state;
    struct dem_pass_choice C;
    setup(&C, 2, 0);
    const long from = DEM_TRIAL_FIRST + 3L * DEM_TRIAL_EVERY + 500;
    const struct machine M = {{1.0, 1.0}, {1.0, 0.7}, from, -1, 0, 1};
    struct record R = {.watch = 1};
    run(&C, &M, DEM_TRIAL_FIRST + 8L * DEM_TRIAL_EVERY, &R);
    assert_int_equal(C.current, 1);
    assert_int_equal(C.proposed, 1);
    assert_int_equal(C.confirmed, 1);
    /* trials of 2 variants begin every DEM_TRIAL_EVERY + 9 steps from
     * step 49; the 5th, the first after the change, proposes variant 1,
     * and the last pass of the second trial, DEM_TRIAL_RECHECK steps
     * after the 5th's last, makes it the one in use */
    const long L = 2 * DEM_TRIAL_ROUNDS,
               trial5 = DEM_TRIAL_FIRST - 1 + 4 * (DEM_TRIAL_EVERY + L - 1);
    assert_int_equal(R.first_in_use, trial5 + 2 * (L - 1) + DEM_TRIAL_RECHECK);
    /* and 3 trials more after the second one */
    assert_int_equal(C.won[0], 4);
    assert_int_equal(C.won[1], 4);
}

/* A variant that would run as another one (struct dem_pass_choice.alike:
 * the one with the threads' own blocks while the passes have none, the
 * one on one thread in a run of one) sits out the trials, even when it
 * won the trial whose second trial is to come. */
static void variant_alike_another_sits_out(void **state)
{
    (void)state;
    struct dem_pass_choice C;
    setup(&C, 3, 0);
    const struct machine M = {{1.0, 1.1, 0.5}, {0}, 1L << 40, -1, 0, 1};
    struct record R = {.watch = 2};
    C.alike = 1u << 2;
    run(&C, &M, DEM_TRIAL_FIRST + 2L * DEM_TRIAL_EVERY, &R);
    assert_int_equal(R.timed[2], 0);
    assert_int_equal(C.current, 0);
    /* no longer alike, it wins the next trial, and its second one */
    C.alike = 0;
    run(&C, &M, DEM_TRIAL_EVERY + 2L * DEM_TRIAL_RECHECK, &R);
    assert_int_equal(C.current, 2);
    assert_int_equal(C.confirmed, 1);
    /* a second trial proposed, and the variant alike again before it runs */
    setup(&C, 3, 0);
    const struct machine N = {{1.0, 1.1, 1.2}, {1.0, 1.1, 0.5}, 100, -1, 0, 1};
    run(&C, &N, DEM_TRIAL_FIRST + DEM_TRIAL_EVERY + 50, &R);
    assert_int_equal(C.confirm, 2);
    C.alike = 1u << 2;
    run(&C, &N, 2L * DEM_TRIAL_RECHECK, &R);
    assert_int_equal(C.confirm, -1);
    assert_int_equal(C.current, 0);
    assert_int_equal(C.confirmed, 0);
    assert_int_equal(R.timed[2], 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fastest_runs_and_far_losers_sit_out),
        cmocka_unit_test(one_spoiled_trial_changes_nothing),
        cmocka_unit_test(lasting_change_is_confirmed),
        cmocka_unit_test(variant_alike_another_sits_out),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
