/* Threads that own their particles (neighbor/blocks.h). */
#include <stdlib.h>
#include <string.h>

#include "core/particles.h"
#include "neighbor/blocks.h"
#include "neighbor/pairs.h"

/* Block k's arrays freed (its ranges kept). */
static void block_free(struct dem_block *k)
{
    for (int p = 0; p < 2; p++) {
        free(k->rj[p]);
        free(k->ri2[p]);
        free(k->rj2[p]);
        k->rj[p] = k->ri2[p] = k->rj2[p] = NULL;
    }
#define HIST_FREE_(MODEL, name, unit, swap, doc)                               \
    free(k->name);                                                             \
    k->name = NULL;
    DEM_CONTACT_HISTORY(HIST_FREE_)
#undef HIST_FREE_
    free(k->state);
    free(k->F);
    free(k->M);
    free(k->tw);
    k->tw = NULL;
    k->state = NULL;
    k->F = NULL;
    k->M = NULL;
    k->cap = 0;
}

/* What B holds for one list freed (the balance kept). */
static void list_free(struct dem_blocks *B)
{
    for (int t = 0; B->t && t < B->nt; t++)
        block_free(&B->t[t]);
    free(B->t);
    free(B->gix);
    B->t = NULL;
    B->gix = NULL;
    B->nt = 0;
}

void dem_blocks_free(struct dem_blocks *B)
{
    list_free(B);
    free(B->shift);
    free(B->busy);
    memset(B, 0, sizeof *B);
}

/* Passes after which the threads' times move the cuts (also without a
 * new list: a quiet packing keeps one for 10^5 steps and more), if the
 * slowest took more than BALANCE_OFF over the mean; and how far they move
 * them towards equal times at once. */
enum { BALANCE_PASSES = 1000 };
#define BALANCE_OFF 0.01
#define BALANCE_GAIN 0.5

/* Whether the threads' times since the set-up call for new cuts. */
static int off_balance(const struct dem_blocks *B)
{
    if (!B->t || B->shift_nt != B->nt || B->passes < BALANCE_PASSES)
        return 0;
    double S = 0.0, M = 0.0;
    for (int t = 0; t < B->nt; t++) {
        const double b = (double)B->busy[8 * t];
        S += b;
        M = b > M ? b : M;
    }
    return M > (1.0 + BALANCE_OFF) * S / B->nt;
}

/* The cuts moved by the last list's times: where the first t + 1
 * threads took more than (t + 1)/nt of the time, cut t moves back by
 * GAIN times that share of the work (at most a quarter of a block). */
static void rebalance(struct dem_blocks *B, int nt)
{
    double S = 0.0;
    for (int t = 0; t < nt; t++)
        S += (double)B->busy[8 * t];
    if (S <= 0.0 || B->passes < BALANCE_PASSES)
        return;
    const double cap = 0.25 * (double)B->work / nt;
    double acc = 0.0;
    for (int t = 0; t + 1 < nt; t++) {
        acc += (double)B->busy[8 * t];
        const double excess = acc / S - (double)(t + 1) / nt;
        double x = B->shift[t] - BALANCE_GAIN * excess * (double)B->work;
        B->shift[t] = x > cap ? cap : x < -cap ? -cap : x;
    }
}

/* The balance's arrays for nt threads (kept if they are), the times
 * cleared; 0 on success. */
static int balance_reserve(struct dem_blocks *B, int nt)
{
    if (B->shift_nt != nt) {
        free(B->shift);
        free(B->busy);
        B->shift = calloc((size_t)nt, sizeof *B->shift);
        B->busy = aligned_alloc(64, 64 * (size_t)nt);
        B->shift_nt = B->shift && B->busy ? nt : 0;
        if (!B->shift_nt)
            return -1;
    }
    memset(B->busy, 0, 64 * (size_t)nt);
    B->passes = 0;
    return 0;
}

/* Room for c pairs in each of block k's arrays; 0 on success. */
static int block_reserve(struct dem_block *k, int c)
{
    if (c <= k->cap)
        return 0;
    block_free(k);
    c += c / 4 + 16;
    int bad = 0;
    for (int p = 0; p < 2; p++) {
        bad |= !(k->rj[p] = malloc((size_t)c * sizeof(int)));
        bad |= !(k->ri2[p] = malloc((size_t)c * sizeof(int)));
        bad |= !(k->rj2[p] = malloc((size_t)c * sizeof(int)));
    }
#define HIST_ALLOC_(MODEL, name, unit, swap, doc)                              \
    bad |= !(k->name = malloc((size_t)c * sizeof(double)));
    DEM_CONTACT_HISTORY(HIST_ALLOC_)
#undef HIST_ALLOC_
    bad |= !(k->state = malloc((size_t)c * sizeof(int)));
    bad |= !(k->tw = malloc((size_t)c * sizeof(int)));
    bad |= !(k->M = malloc(3 * (size_t)c * sizeof(double)));
    void *f = NULL;
    if (posix_memalign(&f, DEM_CONTACT_FORCE_ALIGN,
                       (size_t)c * sizeof(struct dem_contact_force)))
        bad = 1;
    k->F = f;
    if (bad) {
        block_free(k);
        return -1;
    }
    k->cap = c;
    return 0;
}

/* The record particle x has in a pass that reads half h: its own, if
 * it is in [a, b), else its ghost record; -1 if it has none. */
static int record_of(const struct dem_blocks *B, int x, int a, int b, int h)
{
    if (x >= a && x < b)
        return x;
    return B->gix[x] < 0 ? -1 : B->base + h * B->ng + B->gix[x];
}

/* A twin's weight in a thread's work (dem_pairs_cut): its records come
 * from memory, and it costs about 1.5 pairs (docs/performance-log.md,
 * session 44). */
enum { WTWIN = 3 };

/* Block k's ranges for its rows [a, b): d, kt and its twins' count. */
static void block_ranges(struct dem_block *k, const struct dem_pairs *pl,
                         int a, int b)
{
    const int *start = pl->cur.start, *cj = pl->cur.j, *rstart = pl->rstart,
              *rpair = pl->rpair;
    k->a = a;
    k->b = b;
    k->k0 = start[a];
    k->k1 = start[b];
    /* the first pair of its rows with j beyond the block */
    for (k->kt = k->k0; k->kt < k->k1 && cj[k->kt] < b; k->kt++)
        ;
    /* [a, d): the particles with a pair as j in an earlier block (the
     * first of a reverse row is its earliest) */
    k->d = a;
    for (int i = a; i < b; i++)
        if (rstart[i] < rstart[i + 1] && rpair[rstart[i]] < k->k0)
            k->d = i + 1;
    k->q0 = rstart[a];
    k->q1 = rstart[k->d];
    k->nd = 0;
    for (int q = k->q0; q < k->q1; q++)
        k->nd += rpair[q] < k->k0;
}

int dem_blocks_setup(struct dem_blocks *B, const struct dem_pairs *pl, int n,
                     int nt)
{
    if (B->nt == nt && B->gen == pl->gen && B->n == n && !off_balance(B))
        return B->t ? 0 : -1; /* set up, or found not to split */
    if (B->shift_nt == nt)
        rebalance(B, nt);
    list_free(B);
    B->t = calloc((size_t)nt, sizeof *B->t);
    B->gix = malloc((size_t)(n > 0 ? n : 1) * sizeof *B->gix);
    if (!B->t || !B->gix || balance_reserve(B, nt)) {
        dem_blocks_free(B);
        return -1;
    }
    B->nt = nt;
    const int *start = pl->cur.start, *ci = pl->cur.i, *cj = pl->cur.j,
              *rpair = pl->rpair;
    /* equal work, then again with each block's twins counted: blocks
     * 0..t-1 take t/nt of it, C(a_t) + WTWIN (their twins) */
    const long all =
        DEM_WORK_PAIR * (long)start[n] + DEM_WORK_PARTICLE * (long)n;
    for (int t = 0; t < nt; t++) {
        const int b =
            t + 1 < nt ? dem_pairs_cut(start, n, all * (t + 1) / nt) : n;
        block_ranges(&B->t[t], pl, dem_pairs_cut(start, n, all * t / nt), b);
    }
    long twins = 0;
    for (int t = 0; t < nt; t++)
        twins += B->t[t].nd;
    const long work = all + WTWIN * twins;
    B->work = work;
    long before = 0; /* the twins of blocks 0..t */
    int a = 0;
    for (int t = 0; t < nt; t++) {
        before += B->t[t].nd;
        const long target = work * (t + 1) / nt - WTWIN * before +
                            (t + 1 < nt ? (long)B->shift[t] : 0);
        int b = t + 1 < nt ? dem_pairs_cut(start, n, target) : n;
        /* each block's particles start on a cache line of their arrays
         * (core/particles.h): the kicks' vectors then never straddle two */
        if (t + 1 < nt)
            b -= b % DEM_PARTICLE_LINE;
        b = b > a ? b : a;
        block_ranges(&B->t[t], pl, a, b);
        a = b;
    }
    /* [g, b): what the later blocks' twins read, from their first i on
     * (the twins are in list order, so i grows) */
    B->ng = 0;
    for (int t = 0; t < nt; t++) {
        struct dem_block *k = &B->t[t];
        k->g = k->b;
        for (int u = t + 1; u < nt; u++) {
            const struct dem_block *l = &B->t[u];
            for (int q = l->q0; q < l->q1; q++)
                if (rpair[q] < l->k0 && ci[rpair[q]] < k->g)
                    k->g = ci[rpair[q]];
        }
        k->g = k->g > k->a ? k->g : k->a;
        const int s = k->g > k->d ? k->g : k->d;
        k->ga = B->ng;
        B->ng += k->d - k->a;
        k->gg = B->ng;
        B->ng += k->b - s;
        for (int x = k->a; x < k->b; x++)
            B->gix[x] = x < k->d ? k->ga + (x - k->a)
                        : x >= s ? k->gg + (x - s)
                                 : -1;
    }
    B->base = n;
    B->n = n;
    B->half = 0;
    B->written = 0;
    /* every record a block reads of another one, in both halves, and
     * its twins in the order of its particles' reverse rows */
    for (int t = 0; t < nt; t++) {
        struct dem_block *k = &B->t[t];
        const int nj = k->k1 - k->kt, nq = k->q1 - k->q0;
        int c = nj > k->nd ? nj : k->nd;
        if (block_reserve(k, c > nq ? c : nq)) {
            list_free(B);
            return -1;
        }
        int u = 0;
        for (int q = k->q0; q < k->q1; q++)
            k->tw[q - k->q0] = rpair[q] < k->k0 ? u++ : -1;
        for (int h = 0; h < 2; h++) {
            int bad = 0;
            for (int q = k->kt; q < k->k1; q++)
                bad |= (k->rj[h][q - k->kt] =
                            record_of(B, cj[q], k->a, k->b, h)) < 0;
            for (int q = k->q0; q < k->q1; q++) {
                if (k->tw[q - k->q0] < 0)
                    continue;
                const int p = rpair[q], v = k->tw[q - k->q0];
                bad |= (k->ri2[h][v] = record_of(B, ci[p], k->a, k->b, h)) < 0;
                bad |= (k->rj2[h][v] = record_of(B, cj[p], k->a, k->b, h)) < 0;
            }
            if (bad) { /* not split as the blocks assume: none for
                          this list */
                list_free(B);
                B->nt = nt;
                B->n = n;
                B->gen = pl->gen;
                return -1;
            }
        }
    }
    B->gen = pl->gen;
    return 0;
}
