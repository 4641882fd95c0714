/* `dembox bench` with two counts of threads by turns (--threads T,U):
 * every step runs, one chain of them whose passes change their count of
 * threads from one slice to the next, and the run ends in the same bits
 * as one count alone; and the bad input. */
#include "testutil.h"

#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "dembox.h"
#include "tmpdir.h"

static struct dem_bench_options options(int threads, int versus, long steps)
{
    struct dem_bench_options o;
    memset(&o, 0, sizeof o);
    o.dim = 3;
    o.n = 300;
    o.steps = steps;
    o.threads = threads;
    o.versus = versus;
    o.cache_dir = tmpdir; /* prepared once, by the first run */
    o.quiet = 1;
    return o;
}

static struct dem_bench_result bench(int threads, int versus, long steps)
{
    const struct dem_bench_options o = options(threads, versus, steps);
    struct dem_bench_result r;
    struct dem_error err = {0, "", NULL, NULL};
    const int rc = dem_bench_run(&o, &r, &err);
    if (rc)
        fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(rc, DEM_OK);
    return r;
}

static void by_turns_same_bits_as_one_count(void **state)
{
    (void)state;
    /* forced passes too (those of this build): the blocks pass's ghost
     * records and the ring's per-thread rings must not carry a count's
     * state into the other's */
    const char *passes[] = {
        NULL,
        "gathers",
#if DEM_HAVE_PASS_RECORDS
        "blocks",
        "ring",
        "single",
        "records"
#endif
    };
    for (size_t a = 0; a < sizeof passes / sizeof *passes; a++) {
        if (passes[a])
            setenv("DEMBOX_PASS", passes[a], 1);
        else
            unsetenv("DEMBOX_PASS");
        const long steps = 120;
        const struct dem_bench_result one = bench(1, 0, steps),
                                      two = bench(2, 0, steps),
                                      turns = bench(1, 2, steps),
                                      back = bench(2, 1, steps);
        assert_true(one.p_end != one.p_start); /* the wall moved */
        assert_memory_equal(&one.p_end, &two.p_end, sizeof one.p_end);
        assert_memory_equal(&one.p_end, &turns.p_end, sizeof one.p_end);
        assert_memory_equal(&one.p_end, &back.p_end, sizeof one.p_end);
        assert_memory_equal(&one.z_end, &turns.z_end, sizeof one.z_end);
        /* 12 steps a slice (a tenth), the first round not counted */
        assert_int_equal(one.versus, 0);
        assert_int_equal(turns.versus, 2);
        assert_int_equal(turns.slice, 12);
        assert_int_equal(turns.turn_steps[0] + turns.turn_steps[1],
                         steps - 2 * turns.slice);
        assert_int_equal(turns.turn_steps[0], turns.turn_steps[1]);
        assert_int_equal(turns.rounds, 4);
        assert_true(turns.ratio[1] > 0.0 && turns.ratio[1] <= turns.ratio[0] &&
                    turns.ratio[0] <= turns.ratio[2]);
        assert_int_equal(one.turn_steps[0], steps);
        /* one count: the spread of its slices after the first */
        assert_int_equal(one.slice, 12);
        assert_int_equal(one.spread_slices, 9);
        assert_true(one.spread[1] > 0.0 && one.spread[1] <= one.spread[0] &&
                    one.spread[0] <= one.spread[2]);
        assert_int_equal(turns.spread_slices, 0);
        /* the loop ended in the second count's slice (the tenth), and
         * says it is outside a loop by turns again */
        assert_int_equal(dem_bench_turn(), 0);
    }
    unsetenv("DEMBOX_PASS");
}

static void by_turns_needs_rounds(void **state)
{
    (void)state;
    const struct dem_bench_options o = options(1, 2, 15);
    struct dem_bench_result r;
    struct dem_error err = {0, "", NULL, NULL};
    assert_int_equal(dem_bench_run(&o, &r, &err), DEM_EUSAGE);
    assert_non_null(strstr(err.msg, "--threads T,U needs --steps 16"));
    /* and both counts: the default count against U would be U against U */
    const struct dem_bench_options o0 = options(0, 2, 32);
    assert_int_equal(dem_bench_run(&o0, &r, &err), DEM_EUSAGE);
    assert_non_null(strstr(err.msg, "versus = 2 needs threads >= 1"));
    assert_int_equal(dem_bench_slice(3375, 20000), 592);
    assert_int_equal(dem_bench_slice(20000, 3000), 100);
    assert_int_equal(dem_bench_slice(216000, 20000), 9);
    assert_int_equal(dem_bench_slice(300, 30), 3);
    assert_int_equal(dem_bench_slice(300, 16), 2);
}

/* Copy file a to b, the first byte of its line 1 (the comment) turned to
 * `first`: the same size, another content. */
static void copy_with(const char *a, const char *b, char first)
{
    FILE *in = fopen(a, "rb"), *out = fopen(b, "wb");
    assert_non_null(in);
    assert_non_null(out);
    int c, k = 0;
    while ((c = fgetc(in)) != EOF)
        fputc(k++ == 0 ? first : c, out);
    fclose(in);
    assert_int_equal(fclose(out), 0);
}

/* The cache of a packing prepared from a data file is the file's: one of
 * the same name and size but other bytes (a packing made again) is
 * prepared anew, not taken for the old one; the same bytes again are
 * reused. */
static void cache_follows_the_data_files_bytes(void **state)
{
    (void)state;
    const struct dem_bench_result first = bench(1, 0, 20);
    char a[1200], b[1200];
    snprintf(a, sizeof a, "%s/a", tmpdir);
    snprintf(b, sizeof b, "%s/b", tmpdir);
    assert_int_equal(mkdir(a, 0755), 0);
    assert_int_equal(mkdir(b, 0755), 0);
    snprintf(a, sizeof a, "%s/a/pack.data", tmpdir);
    snprintf(b, sizeof b, "%s/b/pack.data", tmpdir);
    copy_with(first.cache, a, '#');
    copy_with(first.cache, b, ' ');
    struct dem_bench_options o = options(1, 0, 20);
    struct dem_bench_result r;
    struct dem_error err = {0, "", NULL, NULL};
    const char *files[] = {a, b, a};
    const int hit[] = {0, 0, 1};
    for (int k = 0; k < 3; k++) {
        o.data = files[k];
        if (dem_bench_run(&o, &r, &err))
            fail_msg("%s", err.msg);
        assert_int_equal(r.cache_hit, hit[k]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(by_turns_same_bits_as_one_count),
        cmocka_unit_test(by_turns_needs_rounds),
        cmocka_unit_test(cache_follows_the_data_files_bytes),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
