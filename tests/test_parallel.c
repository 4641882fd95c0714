/* The threads' work split (core/parallel.h): the equal blocks cover the
 * items on their multiples, and the dynamic shares hand out every item
 * exactly once, whatever the threads' pace, on the blocks' multiples,
 * taking from a thread held back. */
#include "testutil.h"

#include <omp.h>
#include <stdlib.h>
#include <time.h>

#include "core/parallel.h"

static void blocks_cover_items_on_multiples(void **state)
{
    (void)state;
    const int ns[] = {0, 1, 7, 64, 1000, 4097};
    for (size_t a = 0; a < sizeof ns / sizeof *ns; a++)
        for (int g = 1; g <= 256; g *= 8)
            for (int nt = 1; nt <= 5; nt++) {
                const int n = ns[a];
                assert_int_equal(dem_block_aligned(n, 0, nt, g), 0);
                assert_int_equal(dem_block_aligned(n, nt, nt, g), n);
                for (int t = 0; t < nt; t++) {
                    const int b = dem_block_aligned(n, t, nt, g),
                              e = dem_block_aligned(n, t + 1, nt, g);
                    assert_true(b <= e);
                    assert_true(b % g == 0 || b == n);
                }
            }
}

/* A pause of about us microseconds, with the thread busy (as a thread the
 * host holds back looks to the others). */
static void pause_us(double us)
{
    struct timespec t0, t;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    do
        clock_gettime(CLOCK_MONOTONIC, &t);
    while (1e6 * (double)(t.tv_sec - t0.tv_sec) +
               1e-3 * (double)(t.tv_nsec - t0.tv_nsec) <
           us);
}

/* n items shared by nt threads, chunk at least, on multiples of g;
 * thread 0 pauses after each take when slow is set. Every item is taken
 * once, each take within one block and starting on a multiple of g;
 * returns the items of block 0 that other threads took. */
static int share_once(int n, int g, int chunk, int nt, int slow,
                      unsigned long long *ctr)
{
    int *by = malloc((size_t)(n > 0 ? n : 1) * sizeof *by);
    for (int i = 0; i < n; i++)
        by[i] = -1;
    for (int b = 0; ctr && b < nt; b++)
        ctr[DEM_SHARE_LINE * b] = 0;
    int bad = 0;
#pragma omp parallel num_threads(nt) reduction(+ : bad)
    {
        const int t = omp_get_thread_num(), m = omp_get_num_threads();
        struct dem_share S = {ctr, n, g, chunk, t, m, 0};
        int lo, hi, end;
        while (dem_share_take(&S, &lo, &hi, &end)) {
            /* within one block, on its multiples */
            int blk = -1;
            for (int b = 0; b < m; b++)
                if (end == dem_block_aligned(n, b + 1, m, g) &&
                    lo >= dem_block_aligned(n, b, m, g))
                    blk = b;
            bad += blk < 0 || lo >= hi || hi > end ||
                   (lo - dem_block_aligned(n, blk, m, g)) % g != 0;
            for (int i = lo; i < hi; i++) {
                int was;
#pragma omp atomic capture
                {
                    was = by[i];
                    by[i] = t;
                }
                bad += was != -1;
            }
            if (slow && t == 0)
                pause_us(50000.0);
        }
    }
    assert_int_equal(bad, 0);
    int others = 0;
    for (int i = 0; i < n; i++) {
        assert_true(by[i] >= 0); /* every item taken */
        others += i < dem_block_aligned(n, 1, nt, g) && by[i] != 0;
    }
    free(by);
    return others;
}

static void shares_take_every_item_once(void **state)
{
    (void)state;
    unsigned long long *ctr =
        aligned_alloc(64, 5 * DEM_SHARE_LINE * sizeof *ctr);
    const int ns[] = {0, 1, 7, 64, 1000, 4097};
    for (size_t a = 0; a < sizeof ns / sizeof *ns; a++)
        for (int g = 1; g <= 8; g *= 8)
            for (int nt = 1; nt <= 4; nt++) {
                share_once(ns[a], g, g, nt, 0, ctr);
                share_once(ns[a], g, 4 * g, nt, 0, ctr);
                /* without counters each thread takes its own block */
                assert_int_equal(share_once(ns[a], g, g, nt, 0, NULL), 0);
            }
    free(ctr);
}

/* A thread held back leaves the back of its block to the others (more
 * threads than the machine has cores still run: they take turns). */
static void shares_take_from_a_thread_held_back(void **state)
{
    (void)state;
    unsigned long long *ctr =
        aligned_alloc(64, 3 * DEM_SHARE_LINE * sizeof *ctr);
    for (int nt = 2; nt <= 3; nt++) {
        /* thread 0 takes half of its block, then pauses 50 ms after
         * each take: the others have long taken the rest */
        assert_true(share_once(3000, 8, 16, nt, 1, ctr) > 0);
    }
    free(ctr);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(blocks_cover_items_on_multiples),
        cmocka_unit_test(shares_take_every_item_once),
        cmocka_unit_test(shares_take_from_a_thread_held_back),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
