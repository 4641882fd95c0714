/* Static work split for OpenMP threads. */
#ifndef DEM_CORE_PARALLEL_H
#define DEM_CORE_PARALLEL_H

/* First item of thread t's share when n items are split into nt equal
 * contiguous blocks (thread t takes [dem_block(n, t, nt),
 * dem_block(n, t + 1, nt))). */
static inline int dem_block(int n, int t, int nt)
{
    return (int)((long)n * t / nt);
}

#endif
