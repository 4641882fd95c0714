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

/* The same with every boundary on a multiple of g (the last block ends
 * at n): items grouped g by g never straddle two threads. */
static inline int dem_block_aligned(int n, int t, int nt, int g)
{
    const int b = (int)((long)((n + g - 1) / g) * t / nt) * g;
    return b < n ? b : n;
}

#endif
