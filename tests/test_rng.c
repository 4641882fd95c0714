/* Seeded RNG: reproducible streams and the right moments. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core/rng.h"

static void same_seed_gives_same_stream(void **state)
{
    (void)state;
    struct dem_rng a, b;
    dem_rng_seed(&a, 42);
    dem_rng_seed(&b, 42);
    for (int i = 0; i < 1000; i++)
        assert_int_equal(dem_rng_u64(&a), dem_rng_u64(&b));
    dem_rng_seed(&b, 43);
    assert_int_not_equal(dem_rng_u64(&a), dem_rng_u64(&b));
}

static void uniform_and_normal_moments(void **state)
{
    (void)state;
    struct dem_rng g;
    dem_rng_seed(&g, 7);
    const int n = 200000;
    double su = 0, su2 = 0, sn = 0, sn2 = 0;
    for (int i = 0; i < n; i++) {
        double u = dem_rng_uniform(&g), z = dem_rng_normal(&g);
        assert_true(u >= 0.0 && u < 1.0);
        su += u;
        su2 += u * u;
        sn += z;
        sn2 += z * z;
    }
    /* standard errors: 0.29/sqrt(n) = 6.5e-4 and 1/sqrt(n) = 2.2e-3 */
    assert_true(fabs(su / n - 0.5) < 4e-3);
    assert_true(fabs(su2 / n - su / n * su / n - 1.0 / 12.0) < 2e-3);
    assert_true(fabs(sn / n) < 1e-2);
    assert_true(fabs(sn2 / n - 1.0) < 1e-2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(same_seed_gives_same_stream),
        cmocka_unit_test(uniform_and_normal_moments),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
