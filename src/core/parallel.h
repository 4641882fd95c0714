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

/* Dynamic shares of a phase's n items among the nt threads of a
 * parallel region. Thread t's block as dem_block_aligned cuts them (on
 * multiples of g) is its own: it takes it from the front, half of it
 * first, then half of what is left, down to chunk items (a multiple of
 * g) at a time; once its block is empty it takes single chunks from the
 * back of the other threads' blocks. A thread the host holds back for a
 * while so leaves the rest of its block to the others, where an equal
 * cut had them wait for it at the end of the phase, and a thread that is
 * not held back pays one atomic operation on a cache line of its own
 * per take. Taken from the back, the items another thread takes in two
 * phases in a row are mostly those of the same rows. Which thread takes
 * an item must change no result (contact/pass.c). */
#define DEM_SHARE_LINE 8 /* counters per block: one cache line */
struct dem_share {
    /* block b's chunks taken from its front (the low 32 bits) and from
     * its back (the high ones) in ctr[DEM_SHARE_LINE * b], all 0 before
     * the phase; NULL: each thread takes its own block whole (as does a
     * thread alone) */
    unsigned long long *ctr;
    int n, g, chunk, t, nt;
    int u; /* blocks done with: t's, t + 1's, ... (modulo nt); 0 at first */
};

/* The next items [*lo, *hi) of S for its thread, *end the end of their
 * block; 0 when every block is empty. */
static inline int dem_share_take(struct dem_share *S, int *lo, int *hi,
                                 int *end)
{
    if (!S->ctr || S->nt == 1) {
        *lo = dem_block_aligned(S->n, S->t, S->nt, S->g);
        *hi = *end = dem_block_aligned(S->n, S->t + 1, S->nt, S->g);
        return S->u++ == 0 && *lo < *hi;
    }
    const unsigned long long low = 0xffffffffull;
    for (; S->u < S->nt; S->u++) {
        const int b = (S->t + S->u) % S->nt, own = S->u == 0;
        const int a = dem_block_aligned(S->n, b, S->nt, S->g),
                  e = dem_block_aligned(S->n, b + 1, S->nt, S->g);
        const unsigned long long nch =
            (unsigned long long)((e - a + S->chunk - 1) / S->chunk);
        unsigned long long *ctr = S->ctr + DEM_SHARE_LINE * b, m = 1,
                           v = __atomic_load_n(ctr, __ATOMIC_RELAXED);
        /* (a failed exchange reloads v; a successful one leaves the
         * counts before the take there) */
        while ((v & low) + (v >> 32) < nch) {
            m = own ? (nch - (v & low) - (v >> 32) + 1) / 2 : 1;
            if (__atomic_compare_exchange_n(ctr, &v, v + (own ? m : 1ull << 32),
                                            1, __ATOMIC_RELAXED,
                                            __ATOMIC_RELAXED))
                break;
        }
        if ((v & low) + (v >> 32) >= nch)
            continue;
        const int q = own ? (int)(v & low) : (int)(nch - 1 - (v >> 32));
        *lo = a + q * S->chunk;
        *hi = e - *lo > (int)m * S->chunk ? *lo + (int)m * S->chunk : e;
        *end = e;
        return 1;
    }
    return 0;
}

#endif
