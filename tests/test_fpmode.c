/* Subnormal numbers flushed to zero on every thread of a run's team, and
 * the caller's mode given back (core/fpmode.h). */
#include <float.h>
#include <omp.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "core/fpmode.h"

#define NT 2

/* On each of NT threads: 1 if DBL_MIN / 4 comes out 0 (results flushed)
 * and 1 if the smallest subnormal reads as 0 (inputs flushed). */
static void probe(int out_made[NT], int in_read[NT])
{
    memset(out_made, 0, NT * sizeof *out_made);
    memset(in_read, 0, NT * sizeof *in_read);
#pragma omp parallel num_threads(NT)
    {
        const int t = omp_get_thread_num();
        volatile double normal = DBL_MIN, quarter = 0.25, one = 1.0;
        const uint64_t bits = 1; /* 4.9e-324 */
        volatile double sub;
        memcpy((void *)&sub, &bits, sizeof bits);
        out_made[t] = normal * quarter == 0.0;
        in_read[t] = sub * one == 0.0;
    }
}

static void flushed_on_every_thread_then_restored(void **state)
{
    (void)state;
    omp_set_num_threads(NT);
    int made[NT], read[NT];
    probe(made, read);
    for (int t = 0; t < NT; t++) /* the default: gradual underflow */
        assert_true(!made[t] && !read[t]);
    struct dem_fpmode fp;
    if (!dem_fpmode_flush(&fp))
        skip(); /* no flush mode known on this CPU */
    probe(made, read);
    for (int t = 0; t < NT; t++)
        assert_true(made[t] && read[t]);
    dem_fpmode_restore(&fp);
    probe(made, read);
    for (int t = 0; t < NT; t++)
        assert_true(!made[t] && !read[t]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(flushed_on_every_thread_then_restored),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
