/* Seeded pseudo-random numbers: xoshiro256** (Blackman & Vigna 2018,
 * "Scrambled linear pseudorandom number generators") seeded through
 * splitmix64. Written here from the published description; the state is
 * plain data so that it can be checkpointed.
 */
#ifndef DEM_CORE_RNG_H
#define DEM_CORE_RNG_H

#include <stdint.h>

struct dem_rng {
    uint64_t s[4]; /* generator state */
};

void dem_rng_seed(struct dem_rng *g, uint64_t seed);
uint64_t dem_rng_u64(struct dem_rng *g);
/* Uniform in [0, 1). */
double dem_rng_uniform(struct dem_rng *g);
/* Standard normal (Box-Muller, one value per call, no cached state). */
double dem_rng_normal(struct dem_rng *g);

#endif
