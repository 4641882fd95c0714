/* What one core of this machine can do, for the limit of the contact law
 * (docs/performance.md, "The limit on one core"): the throughput of
 * multiplies and adds (a * b + c in 256-bit vectors, and in 512-bit ones
 * where the build has AVX-512), square roots and divisions in the vector
 * width the compiler picks, the bandwidth of a triad a = b + s c from the L2
 * cache, the L3 cache and main memory, and that of main memory read
 * from 4 to 48 arrays at once. Built with the project (not run by CTest,
 * it is a timing):
 *
 *     build/dembox_limits      (one thread; stop other work first)
 *
 * Then the memory side of a chained step of the ring pass, at a small
 * and a large N: its streams in its order, with its requests ahead,
 * without its arithmetic. Its arrays start at different offsets within
 * their pages, as the engine's do; a last figure puts every one at the
 * start of a page, as a fresh process's large allocations are (before
 * session 88 every figure at the large N was taken so, and without the
 * requests ahead).
 *
 * Each kernel is timed 5 times; the fastest is printed. The loops work on
 * independent lanes, so that they measure throughput, not latency; check
 * with objdump -d that they use the vector instructions named.
 *
 * Last, with two CPUs or more, the time one cache line takes to pass from
 * CPU 0 to CPU 1 and back (two threads pinned to them take turns writing
 * it): tens of ns between cores that share an L3 cache, several times
 * more between two of a virtual machine's vCPUs that the host has put on
 * different L3 domains (docs/performance.md, "Why two threads gain so
 * unevenly here"). That alone, in a second or two, to label runs
 * by where the host has put the vCPUs (docs/parallel.md, "Threads or
 * ranks on one machine"):
 *
 *     build/dembox_limits --pingpong
 *
 * And what it costs to hand cache lines over: CPU 1 writes 640 lines
 * that CPU 0 then reads, 4000 times, once with ordinary stores and once
 * with non-temporal ones; ns per line for each side, with the ping-pong
 * before and after (docs/performance-log.md, session 43):
 *
 *     build/dembox_limits --handover
 *
 * Or the ring pass's streams at N = 3375 against N = 216000 swept once
 * for 1, 2, 4 or 8 steps (fronts FRONT_LAG layers of cells apart, each a
 * step behind the one before; ring_streams), in a cube and in a column
 * whose layers are N = 3375's, with and without the arrays of x, v and
 * omega: how far sweeping memory once for several steps would bring the
 * memory side of a step at large N towards its cost at small N (some 5
 * minutes; docs/performance-log.md, session 88):
 *
 *     build/dembox_limits --fronts
 *
 * Or those streams with the particles' 17 arrays apart against in one
 * array of blocks of 8 particles (each block holding 8 values of each
 * array in turn), N = 3375 against 216000, by turns (some 6 minutes;
 * docs/performance-log.md, session 93):
 *
 *     build/dembox_limits --layouts
 *
 * Or what a gathered load costs on this CPU: doubles picked by random
 * indices from a table in the L1 cache, 8 or 4 to a vector by the
 * hardware gather (vgatherdpd, AVX-512 or AVX2, where the build has it)
 * against one scalar load each, and against scalar loads put into a
 * vector (what gcc emits when told not to gather); ns per element, the
 * fastest of 5, in rounds. On CPUs under the Gather Data Sampling
 * mitigation (Intel Skylake to Ice Lake, CVE-2022-40982) and on Zen 1 the
 * gather is the slow one (docs/performance.md, "The tools"):
 *
 *     build/dembox_limits --gathers */
#define _GNU_SOURCE /* pthread_setaffinity_np */
#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#define LANES 64 /* independent values: enough to hide every latency */

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static double sink; /* keeps results alive */

/* Stops the program: the memory a measurement needs is not there. */
static void no_memory(void)
{
    fprintf(stderr, "limits: out of memory\n");
    exit(1);
}

/* acc = acc * b + c on NACC vectors of W doubles, reps times: 2 W flops
 * per vector. The build contracts nothing (-ffp-contract=off,
 * CMakeLists.txt: the same bits in every pass), so this is a multiply and
 * an add, each rounded, as in the engine's passes: not a fused
 * multiply-add. GCC's vectors of 4 doubles are 256 bits (AVX2; an
 * AVX-512 register holds two), of 8 are 512 bits; both stay in registers.
 * A CPU whose 512-bit units issue as many instructions a cycle as its
 * 256-bit ones does twice the flops in 512-bit vectors; one that runs
 * 512-bit work in two 256-bit halves, the same.
 *
 * NACC: independent accumulators, more than latency x pipes (a multiply then
 * an add, some 8 cycles, at up to two pairs a cycle), as many as the
 * vector registers hold: 32 with AVX-512, 16 without. */
#if defined(__AVX512F__)
#define NACC 24
#else
#define NACC 12
#endif
#define MULADD_RATE(W)                                                         \
    typedef double v##W __attribute__((vector_size(8 * W)));                   \
    static double muladd_rate_##W(long reps)                                   \
    {                                                                          \
        v##W acc[NACC] = {0}, b = {0}, c = {0};                                \
        for (int l = 0; l < W; l++) {                                          \
            b[l] = 0.999999999;                                                \
            c[l] = 1e-9;                                                       \
        }                                                                      \
        for (int k = 0; k < NACC; k++)                                         \
            for (int l = 0; l < W; l++)                                        \
                acc[k][l] = 1.0 + k + l;                                       \
        double t = now();                                                      \
        for (long r = 0; r < reps; r++) {                                      \
            _Pragma("GCC unroll 24") for (int k = 0; k < NACC; k++)            \
            {                                                                  \
                acc[k] = acc[k] * b + c;                                       \
            }                                                                  \
        }                                                                      \
        t = now() - t;                                                         \
        for (int k = 0; k < NACC; k++)                                         \
            sink += acc[k][0] + acc[k][W - 1];                                 \
        return 2.0 * W * NACC * reps / t;                                      \
    }
MULADD_RATE(4)
#if defined(__AVX512F__)
MULADD_RATE(8)
#endif

/* Square roots (op 0) or divisions (op 1) of LANES values, reps times,
 * each lane depending on its last result (the lanes are independent);
 * returns lanes per second. */
static double divider_rate(int op, long reps)
{
    double a[LANES], b[LANES];
    for (int k = 0; k < LANES; k++) {
        a[k] = 2.0 + 1e-3 * k;
        b[k] = 1.0;
    }
    double t = now();
    for (long r = 0; r < reps; r++) {
        if (op == 0)
            for (int k = 0; k < LANES; k++)
                b[k] = sqrt(b[k] + a[k]);
        else
            for (int k = 0; k < LANES; k++)
                b[k] = a[k] / (b[k] + 1.0);
    }
    t = now() - t;
    for (int k = 0; k < LANES; k++)
        sink += b[k];
    return (double)LANES * reps / t;
}

/* Triad over three arrays of n doubles: bytes moved per second (24 per
 * element: two reads, one write; the write's read for ownership is not
 * counted, as in STREAM), the best of tries. Every array is written
 * before the clock starts: a first touch of a page costs a fault, some
 * 12 us on the virtual machines of 2026-12 (0.33 GB/s), and an array set
 * to zeros after malloc becomes calloc's untouched pages (gcc), which
 * made this triad report 4-6 GB/s from memory where it streams 32-36
 * (docs/performance-log.md, session 63). */
static double triad(size_t n, int reps, int tries)
{
    double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b),
           *c = malloc(n * sizeof *c);
    if (!a || !b || !c)
        no_memory();
    for (size_t k = 0; k < n; k++) {
        a[k] = 3.0;
        b[k] = 1.0;
        c[k] = 2.0;
    }
    double best = INFINITY;
    for (int u = 0; u < tries; u++) {
        double t = now();
        for (int r = 0; r < reps; r++) {
            for (size_t k = 0; k < n; k++)
                a[k] = b[k] + 0.5 * c[k];
            sink += a[r % n];
        }
        t = now() - t;
        best = t < best ? t : best;
    }
    free(a);
    free(b);
    free(c);
    return 24.0 * n * reps / best;
}

/* S arrays (S even) of the doubles at buf[0..n) in order, the first half
 * read and the second half updated (read and written), 8 elements of
 * each at a time, as a pass goes down its streams: bytes read per second,
 * the best of tries. The ring pass goes down some 30 such streams at
 * N = 216000 (ring_streams). */
static double streams_rate(double *buf, size_t n, int S, int tries)
{
    const size_t m = n / (size_t)S / 8 * 8; /* each array's length */
    double *a[64];                          /* S <= 64 */
    for (int s = 0; s < S; s++)
        a[s] = buf + (size_t)s * m;
    double best = INFINITY;
    for (int u = 0; u < tries; u++) {
        double t = now();
        for (size_t k = 0; k < m; k += 8) {
            double acc = 0.0;
            for (int s = 0; s < S / 2; s++)
                for (int e = 0; e < 8; e++)
                    acc += a[s][k + e];
            for (int s = S / 2; s < S; s++)
                for (int e = 0; e < 8; e++)
                    a[s][k + e] += 1e-300 * acc;
        }
        t = now() - t;
        best = t < best ? t : best;
    }
    sink += buf[n / 2];
    return 8.0 * (double)m * S / best;
}

#define FRONT_LAG 2      /* layers of cells between two fronts */
#define FRONT_CHUNK 1024 /* particles a front visits before the other */

/* The streams of the ring pass (ring_streams below): its arrays, and
 * what one particle's visit reads and writes. */
struct streams {
    const int *start, *rstart, *wstart, *ci, *cj, *rpair;
    int *state;
    double *h[3];
    const double *ro[8];
    double *rw[9], *rec;
    double *blk; /* the particles' 17 values in blocks (LAYOUT_BLOCKS) */
    int mask, arrays, n, np;
    int ahead; /* ask for the streams ahead, as the ring pass does */
};

/* Where the particles' arrays lie (ring_streams): each at the start of
 * a page (aliased), each at its own line of its page (staggered, as the
 * engine's), or all 17 in one array of blocks of BLOCK particles, block
 * b holding BLOCK values of each array in turn (an array of structures
 * of arrays: one stream instead of 17, each value's lanes still whole
 * vectors). */
enum { LAYOUT_ALIASED, LAYOUT_STAGGERED, LAYOUT_BLOCKS };
#define BLOCK 8
#define BLOCK_VALUES 17 /* 8 the kicks and drift read, 9 they write */

/* Particle i's value e of the 17 (the 8 only read, then x, v, omega) */
static inline double *particle_value(const struct streams *S, int e, int i)
{
    if (S->blk)
        return S->blk + (size_t)(i / BLOCK) * BLOCK * BLOCK_VALUES +
               (size_t)e * BLOCK + (size_t)(i % BLOCK);
    return e < 8 ? (double *)S->ro[e] + i : S->rw[e - 8] + i;
}

#define AHEAD_PAIRS 64     /* contact/pass.c's DEM_AHEAD_PAIRS */
#define AHEAD_PARTICLES 32 /* and DEM_AHEAD_PARTICLES */
#define AHEAD_RECORDS 32   /* and DEM_PREFETCH_PAIRS with 16 lanes */

/* Particle i's visit: its row's pairs into ring, the row and its
 * reverse row summed back, its kicks and drift. */
static inline void ring_visit(const struct streams *S, double *ring, int i)
{
    /* locals, so that the stores through int and double pointers do not
     * make the compiler read S's members again */
    const int *start = S->start, *rstart = S->rstart, *ci = S->ci, *cj = S->cj,
              *rpair = S->rpair;
    int *state = S->state;
    double *h0 = S->h[0], *h1 = S->h[1], *h2 = S->h[2], *rec = S->rec;
    const int mask = S->mask, k0 = start[i], k1 = start[i + 1];
    double fx = 0.0, fy = 0.0;
    if (S->ahead && i % 8 == 0 && i + AHEAD_PARTICLES < S->n) {
        /* every 8 particles a line of each array, as particle_range */
        const int u = i + AHEAD_PARTICLES;
        for (int e = 0; e < 8; e++)
            __builtin_prefetch(particle_value(S, e, u), 0, 3);
        for (int e = 8; S->arrays && e < BLOCK_VALUES; e++)
            __builtin_prefetch(particle_value(S, e, u), 1, 3);
        __builtin_prefetch(start + u, 0, 3);
        __builtin_prefetch(rstart + u, 0, 3);
        __builtin_prefetch(S->wstart + u, 0, 3);
    }
    for (int k = k0; k < k1; k++) {
        if (S->ahead && k + AHEAD_PAIRS < S->np) {
            /* the partners' records a round ahead, the list's streams
             * further (every 8th pair: a line of each), as pair_range */
            const double *r = rec + 12 * (size_t)cj[k + AHEAD_RECORDS];
            __builtin_prefetch(r, 0, 3);
            __builtin_prefetch(r + 8, 0, 3);
            if ((k & 7) == 0) {
                const int u = k + AHEAD_PAIRS;
                __builtin_prefetch(ci + u, 0, 3);
                __builtin_prefetch(cj + u, 0, 3);
                __builtin_prefetch(state + u, 1, 3);
                __builtin_prefetch(h0 + u, 1, 3);
                __builtin_prefetch(h1 + u, 1, 3);
                __builtin_prefetch(h2 + u, 1, 3);
            }
        }
        const double *a = rec + 12 * (size_t)ci[k],
                     *b = rec + 12 * (size_t)cj[k];
        const double d = a[0] + b[0] + b[11];
        state[k] ^= 1;
        double *o = ring + 6 * (size_t)(k & mask);
        h0[k] += d;
        h1[k] += d;
        h2[k] += d;
        o[0] = o[1] = o[2] = d;
        o[3] = h0[k];
        o[4] = h1[k];
        o[5] = h2[k];
    }
    for (int k = k0; k < k1; k++) {
        const double *o = ring + 6 * (size_t)(k & mask);
        fx += o[0] + o[1] + o[2];
        fy += o[3] + o[4] + o[5];
    }
    for (int q = rstart[i]; q < rstart[i + 1]; q++) {
        const double *o = ring + 6 * (size_t)(rpair[q] & mask);
        fx -= o[0] + o[1] + o[2];
        fy += o[3] + o[4] + o[5];
    }
    fx += S->wstart[i] + S->wstart[i + 1];
    for (int e = 0; e < 8; e++)
        fy += *particle_value(S, e, i);
    const double u = 1e-300 * fx + 1e-300 * fy;
    double *w = rec + 12 * (size_t)i;
    for (int e = 0; e < 12; e++) {
        if (S->arrays && e < 9) {
            double *v = particle_value(S, 8 + e, i);
            *v += u;
            w[e] = *v;
        } else {
            w[e] += u;
        }
    }
}

/* The memory side of a chained step of the ring pass (contact/pass.c)
 * on n particles with `pairs` listed pairs each, without its arithmetic:
 * the same arrays, element sizes and order of access, with one addition
 * or copy per value. The particles lie in cell order about one per cell,
 * as in the benchmark's packings: a layer of cells holds L = n^(2/3) of
 * them, a row R = n^(1/3). Per particle i, in order:
 *  - per pair k of its row: the list's i and j (4 B each), its state
 *    (4 B) and three history values, read and written; the 96-byte
 *    records of i and j (j one of eight neighbours ahead: the next
 *    particle, the next row, the layer above and its neighbours); a
 *    48-byte force record stored into a ring;
 *  - the row's force records summed back, and those of its pairs as j
 *    (its reverse row, through a 4-byte index: the rows of the
 *    particles one, a row and a layer before it; before session 88
 *    as many records a layer behind in order);
 *  - three row starts, the 8 arrays the kicks and the drift only read,
 *    and, if `arrays`, the 9 they write (x, v, omega); its record
 *    written.
 * Once n is large everything but the ring streams from main memory.
 * With `fronts` F > 1, one sweep does F steps, as a pass that swept
 * memory once for F steps would: front f visits the particles f x
 * FRONT_LAG layers behind the first, with a ring of its own, so that the
 * data between the fronts (FRONT_LAG x L particles, about 400 B each:
 * 2.9 MB at N = 216000) may come from the caches. The fronts take turns
 * by FRONT_CHUNK particles (turns of one particle took twice as long);
 * reps must be a multiple of F.
 * With `ahead`, each visit asks for the streams' lines ahead as the ring
 * pass does (AHEAD_PAIRS, AHEAD_PARTICLES, AHEAD_RECORDS). `layout`
 * places the arrays (LAYOUT_*): aliased, all at the same offset within
 * their pages, else each at its own (struct arena); with LAYOUT_BLOCKS
 * the particles' 17 arrays are one of blocks (BLOCK).
 * With row > 0 the particles lie in a column of row x row cells instead
 * of a cube (L = row^2), as they would in a pass that swept a sample
 * column by column: the data between two fronts then fit in the L2.
 * Returns ns per particle-step, the fastest of 5 timings of reps steps;
 * a negative value if out of memory. */
/* The arrays of one ring_streams, each zero and on its own pages: every
 * one at the start of a 4 KiB page (aliased: element k of each array at
 * the same offset in its page, as separate mappings of the C library
 * place large arrays in a fresh process) or, with stagger, each 5 lines
 * further on within its page than the one before (as the engine places
 * its particle arrays, core/particles.c; docs/performance-log.md,
 * session 88). */
#define ARENA_MAX 32
struct arena {
    void *base[ARENA_MAX];
    int k, stagger;
};

static void *arena_zero(struct arena *A, size_t bytes)
{
    if (A->k == ARENA_MAX)
        return NULL;
    char *b = calloc(bytes + 2 * 4096, 1);
    if (!b)
        return NULL;
    A->base[A->k] = b;
    const size_t page = (4096 - (uintptr_t)b % 4096) % 4096,
                 line = A->stagger ? (size_t)(5 * A->k % 64) * 64 : 0;
    A->k++;
    return b + page + line;
}

static void arena_free(struct arena *A)
{
    for (int k = 0; k < A->k; k++)
        free(A->base[k]);
    A->k = 0;
}

static double ring_streams(int n, double pairs, int arrays, int fronts,
                           int reps, int row, int ahead, int layout)
{
    const int R = row > 0 ? row : (int)lround(cbrt(n)), L = R * R;
    const int off[8] = {1, R, L - R, L, L + R, R + 1, L + 1, L - 1};
    struct arena A = {{NULL}, 0, layout != LAYOUT_ALIASED};
    /* the three row starts are three streams, as in the pass: the
     * rows', the reverse rows' (rstart), the walls' all 0 (no wall
     * contact) */
    int *start = arena_zero(&A, ((size_t)n + 1) * sizeof *start),
        *wstart = arena_zero(&A, ((size_t)n + 1) * sizeof *wstart);
    if (!start || !wstart) {
        arena_free(&A);
        return -1.0;
    }
    for (int i = 0; i <= n; i++)
        start[i] = (int)(i * pairs);
    const size_t np = (size_t)start[n];
    const int back = (int)(pairs * L); /* pairs a layer behind */
    int size = 1024;
    while (size < back + 1024)
        size *= 2;
    const int mask = size - 1;
    int *rstart = arena_zero(&A, ((size_t)n + 1) * sizeof *rstart),
        *ci = arena_zero(&A, np * sizeof *ci),
        *cj = arena_zero(&A, np * sizeof *cj),
        *state = arena_zero(&A, np * sizeof *state),
        *rpair = arena_zero(&A, np * sizeof *rpair);
    double *h[3], *ro[8] = {NULL}, *rw[9] = {NULL};
    int ok = rstart && ci && cj && state && rpair;
    for (int e = 0; e < 3; e++)
        ok &= (h[e] = arena_zero(&A, np * sizeof *h[e])) != NULL;
    double *blk = NULL;
    if (layout == LAYOUT_BLOCKS) {
        const size_t blocks = ((size_t)n + BLOCK - 1) / BLOCK;
        ok &= (blk = arena_zero(&A, blocks * BLOCK * BLOCK_VALUES *
                                        sizeof *blk)) != NULL;
    } else { /* (in blocks, ro and rw stay NULL: particle_value) */
        for (int e = 0; e < 8; e++)
            ok &= (ro[e] = arena_zero(&A, (size_t)n * sizeof *ro[e])) != NULL;
        for (int e = 0; e < 9; e++)
            ok &= (rw[e] = arena_zero(&A, (size_t)n * sizeof *rw[e])) != NULL;
    }
    double *rec = arena_zero(&A, 12 * (size_t)n * sizeof *rec),
           *ring =
               arena_zero(&A, 6 * (size_t)size * (size_t)fronts * sizeof *ring);
    ok &= rec && ring;
    double best = INFINITY;
    if (ok) {
        for (int i = 0; i < n; i++)
            for (int k = start[i]; k < start[i + 1]; k++) {
                const int j = i + off[(k - start[i]) % 8];
                ci[k] = i;
                cj[k] = j < n ? j : n - 1;
            }
        /* the reverse rows: particle j's pairs as j, in list order (wstart
         * counts them, then is zeroed again) */
        for (size_t k = 0; k < np; k++)
            rstart[cj[k] + 1]++;
        for (int i = 0; i < n; i++)
            rstart[i + 1] += rstart[i];
        for (size_t k = 0; k < np; k++)
            rpair[rstart[cj[k]] + wstart[cj[k]]++] = (int)k;
        memset(wstart, 0, ((size_t)n + 1) * sizeof *wstart);
        struct streams S = {
            start, rstart, wstart, ci,  cj,   rpair,  state, {h[0], h[1], h[2]},
            {0},   {0},    rec,    blk, mask, arrays, n,     (int)np,
            ahead};
        for (int e = 0; e < 8; e++)
            S.ro[e] = ro[e];
        for (int e = 0; e < 9; e++)
            S.rw[e] = rw[e];
        const int gap = FRONT_LAG * L, chunk = FRONT_CHUNK;
        for (int t = 0; t < 5; t++) {
            const double t0 = now();
            for (int s = 0; s < reps; s += fronts)
                for (int c = 0; c < n + (fronts - 1) * gap; c += chunk)
                    for (int f = 0; f < fronts; f++) {
                        double *rf = ring + 6 * (size_t)size * (size_t)f;
                        const int lo = c - f * gap;
                        for (int i = lo < 0 ? 0 : lo; i < lo + chunk && i < n;
                             i++)
                            ring_visit(&S, rf, i);
                    }
            best = fmin(best, now() - t0);
        }
        sink += rec[0] + h[0][0];
    }
    arena_free(&A);
    return ok ? 1e9 * best / ((double)reps * n) : -1.0;
}

/* The particles' arrays one by one (staggered) against in blocks, N =
 * 3375 against 216000 at the periodic cell's pairs per particle, by
 * turns over LAYOUT_ROUNDS rounds: each case's median and range of ns
 * per particle-step, and of the ratio of the two sizes within a round. */
#define LAYOUT_ROUNDS 7
static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void print_spread(double *v, int k)
{
    qsort(v, (size_t)k, sizeof *v, cmp_double);
    printf("%.2f (%.2f-%.2f)", v[k / 2], v[0], v[k - 1]);
}

static void layouts(void)
{
    const double pp = 3.32;
    const int ns[2] = {3375, 216000},
              layout[2] = {LAYOUT_STAGGERED, LAYOUT_BLOCKS};
    double t[2][2][LAYOUT_ROUNDS], q[2][LAYOUT_ROUNDS];
    for (int r = 0; r < LAYOUT_ROUNDS; r++)
        for (int l = 0; l < 2; l++) {
            for (int s = 0; s < 2; s++) {
                const int reps = 12 * ((int)(5e6 / ns[s]) + 1);
                t[l][s][r] =
                    ring_streams(ns[s], pp, 1, 1, reps, 0, 1, layout[l]);
                if (t[l][s][r] < 0.0)
                    no_memory();
            }
            q[l][r] = t[l][1][r] / t[l][0][r];
        }
    printf("ring pass's streams, no arithmetic, %.2f pairs per particle, "
           "%d rounds by turns, ns per particle-step, median (range):\n",
           pp, LAYOUT_ROUNDS);
    for (int l = 0; l < 2; l++) {
        printf("  %s: N = 3375 ", l ? "the particles' 17 arrays in blocks "
                                      "of 8"
                                    : "the particles' 17 arrays apart");
        print_spread(t[l][0], LAYOUT_ROUNDS);
        printf(", N = 216000 ");
        print_spread(t[l][1], LAYOUT_ROUNDS);
        printf(", 216000 / 3375 ");
        print_spread(q[l], LAYOUT_ROUNDS);
        printf("\n");
    }
}

static double best(double (*f)(long), long reps)
{
    double m = 0.0;
    for (int k = 0; k < 5; k++) {
        double v = f(reps);
        m = v > m ? v : m;
    }
    return m;
}

/* The gathers' measurement (--gathers): GATHER_TABLE doubles picked by
 * GATHER_PICKS random indices, both in the L1 cache; reps passes. */
#define GATHER_TABLE 2048
#define GATHER_PICKS 2048
static double gather_table[GATHER_TABLE];
static int32_t gather_index[GATHER_PICKS];

/* One scalar load per element into 8 independent sums. Each index
 * passes through an empty asm, which keeps the compiler from vectorising
 * the loop (or it would gather here too). */
static double gather_scalar(long reps)
{
    double acc[8] = {0};
    double t = now();
    for (long r = 0; r < reps; r++)
        for (int j = 0; j < GATHER_PICKS; j += 8)
            for (int k = 0; k < 8; k++) {
                int32_t i = gather_index[j + k];
                __asm__("" : "+r"(i));
                acc[k] += gather_table[i];
            }
    t = now() - t;
    for (int k = 0; k < 8; k++)
        sink += acc[k];
    return (double)reps * GATHER_PICKS / t;
}

#if defined(__AVX512F__)
#define GATHER_WIDTH 8
#define GATHER_NAME "vgatherdpd zmm, 8 lanes"
typedef __m512d gvec;
static inline gvec gather_hw(const int32_t *i)
{
    return _mm512_i32gather_pd(_mm256_loadu_si256((const __m256i *)i),
                               gather_table, 8);
}
static inline gvec gather_sw(const int32_t *i)
{
    const double *a = gather_table;
    return _mm512_set_pd(a[i[7]], a[i[6]], a[i[5]], a[i[4]], a[i[3]], a[i[2]],
                         a[i[1]], a[i[0]]);
}
#elif defined(__AVX2__)
#define GATHER_WIDTH 4
#define GATHER_NAME "vgatherdpd ymm, 4 lanes"
typedef __m256d gvec;
static inline gvec gather_hw(const int32_t *i)
{
    return _mm256_i32gather_pd(gather_table,
                               _mm_loadu_si128((const __m128i *)i), 8);
}
static inline gvec gather_sw(const int32_t *i)
{
    const double *a = gather_table;
    return _mm256_set_pd(a[i[3]], a[i[2]], a[i[1]], a[i[0]]);
}
#endif

#ifdef GATHER_WIDTH
/* A vector of GATHER_WIDTH elements at a time, by the hardware gather
 * (hw 1) or by scalar loads put into a vector (hw 0), into 4 sums (the
 * intrinsics' vector types take GCC's operators and subscripts). */
static double gather_vector(int hw, long reps)
{
    gvec acc[4] = {{0}, {0}, {0}, {0}};
    double t = now();
    for (long r = 0; r < reps; r++)
        for (int j = 0; j < GATHER_PICKS; j += 4 * GATHER_WIDTH)
            for (int k = 0; k < 4; k++) {
                const int32_t *i = gather_index + j + k * GATHER_WIDTH;
                acc[k] += hw ? gather_hw(i) : gather_sw(i);
            }
    t = now() - t;
    for (int k = 0; k < 4; k++)
        for (int l = 0; l < GATHER_WIDTH; l++)
            sink += acc[k][l];
    return (double)reps * GATHER_PICKS / t;
}
static double gather_hardware(long reps)
{
    return gather_vector(1, reps);
}
static double gather_inserted(long reps)
{
    return gather_vector(0, reps);
}
#endif

/* --gathers: ns per element of each way, in rounds by turns. */
static void gathers(void)
{
    uint64_t x = 88172645463325252u;
    for (int k = 0; k < GATHER_TABLE; k++)
        gather_table[k] = 1.0 + 1e-6 * k;
    for (int k = 0; k < GATHER_PICKS; k++) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        gather_index[k] = (int32_t)(x % GATHER_TABLE);
    }
    const long reps = 20000;
#ifdef GATHER_WIDTH
    printf("doubles by random indices from an L1-resident table, ns per "
           "element (fastest of 5): %s, the same loads scalar, and scalar "
           "loads put into a vector\n",
           GATHER_NAME);
    for (int round = 1; round <= 3; round++) {
        const double hw = 1e9 / best(gather_hardware, reps),
                     sc = 1e9 / best(gather_scalar, reps),
                     in = 1e9 / best(gather_inserted, reps);
        printf("round %d: gather %.3f, scalar %.3f, inserted %.3f; "
               "gather / scalar %.2f\n",
               round, hw, sc, in, hw / sc);
    }
#else
    printf("doubles by random indices from an L1-resident table, ns per "
           "element (fastest of 5): this build has no vector gather "
           "(neither AVX-512 nor AVX2); scalar loads %.3f\n",
           1e9 / best(gather_scalar, reps));
#endif
}

static double sqrt_rate(long reps) { return divider_rate(0, reps); }
static double div_rate(long reps) { return divider_rate(1, reps); }

/* The ping-pong's line: CPU 0 writes the odd counts, CPU 1 the even
 * ones, each when it sees the other's. */
static _Alignas(64) _Atomic long pong;
#define PONG_ROUNDS 1000000L

static void *pong_side(void *arg)
{
    (void)arg;
    for (long i = 1; i < 2 * PONG_ROUNDS; i += 2) {
        while (atomic_load_explicit(&pong, memory_order_acquire) != i)
            ;
        atomic_store_explicit(&pong, i + 1, memory_order_release);
    }
    return NULL;
}

/* The calling thread pinned to CPU 0 and fn started in *t pinned to
 * CPU 1; non-zero if either cannot be done. */
static int start_pair(pthread_t *t, void *(*fn)(void *))
{
    cpu_set_t set;
    pthread_attr_t attr;
    CPU_ZERO(&set);
    CPU_SET(0, &set);
    if (pthread_setaffinity_np(pthread_self(), sizeof set, &set))
        return 1;
    CPU_ZERO(&set);
    CPU_SET(1, &set);
    /* the other side starts pinned to CPU 1, or not at all */
    if (pthread_attr_init(&attr))
        return 1;
    const int bad = pthread_attr_setaffinity_np(&attr, sizeof set, &set) ||
                    pthread_create(t, &attr, fn, NULL);
    pthread_attr_destroy(&attr);
    return bad;
}

/* ns per one-way pass of a cache line between CPUs 0 and 1, or a
 * negative value if the threads cannot be pinned there. */
static double pingpong(void)
{
    pthread_t t;
    atomic_store(&pong, 0);
    if (start_pair(&t, pong_side))
        return -1.0;
    const double t0 = now();
    for (long i = 0; i < 2 * PONG_ROUNDS; i += 2) {
        atomic_store_explicit(&pong, i + 1, memory_order_release);
        while (atomic_load_explicit(&pong, memory_order_acquire) != i + 2)
            ;
    }
    const double t1 = now();
    pthread_join(t, NULL);
    return 1e9 * (t1 - t0) / (2.0 * PONG_ROUNDS);
}

/* Lines handed over from CPU 1 to CPU 0: round r, CPU 1 writes every
 * line whole when hand_turn is 2r + 1 (with hand_stream past the caches,
 * non-temporal), then sets it to 2r + 2, and CPU 0 reads them. */
enum { HAND_LINES = 640, HAND_ROUNDS = 4000 };
static _Alignas(64) double hand_buf[8 * HAND_LINES];
static _Alignas(64) _Atomic long hand_turn;
static int hand_stream;
static double hand_write_s; /* CPU 1's time writing */

static void hand_write(double v)
{
    for (int l = 0; l < HAND_LINES; l++) {
        double *o = hand_buf + 8 * l;
#if defined(__SSE2__)
        if (hand_stream) {
            for (int u = 0; u < 8; u += 2)
                _mm_stream_pd(o + u, _mm_set1_pd(v));
            continue;
        }
#endif
        for (int u = 0; u < 8; u++)
            o[u] = v;
    }
#if defined(__SSE2__)
    _mm_sfence();
#endif
}

static void *hand_side(void *arg)
{
    (void)arg;
    for (long r = 0; r < HAND_ROUNDS; r++) {
        while (atomic_load_explicit(&hand_turn, memory_order_acquire) !=
               2 * r + 1)
            ;
        const double t0 = now();
        hand_write((double)r);
        hand_write_s += now() - t0;
        atomic_store_explicit(&hand_turn, 2 * r + 2, memory_order_release);
    }
    return NULL;
}

/* ns per line for CPU 1 to write and for CPU 0 to read; 1 if the
 * threads cannot be pinned. */
static int handover(int stream, double *wr, double *rd)
{
    pthread_t t;
    hand_stream = stream;
    hand_write_s = 0.0;
    atomic_store(&hand_turn, 0);
    if (start_pair(&t, hand_side))
        return 1;
    double read_s = 0.0, s = 0.0;
    for (long r = 0; r < HAND_ROUNDS; r++) {
        atomic_store_explicit(&hand_turn, 2 * r + 1, memory_order_release);
        while (atomic_load_explicit(&hand_turn, memory_order_acquire) !=
               2 * r + 2)
            ;
        const double t0 = now();
        for (int l = 0; l < HAND_LINES; l++)
            s += hand_buf[8 * l];
        read_s += now() - t0;
    }
    pthread_join(t, NULL);
    sink += s;
    *wr = 1e9 * hand_write_s / ((double)HAND_ROUNDS * HAND_LINES);
    *rd = 1e9 * read_s / ((double)HAND_ROUNDS * HAND_LINES);
    return 0;
}

/* The ping-pong's line of output, measured k times; 0, or 1 when the
 * machine has one CPU or the threads cannot be pinned. */
static int pingpong_line(int k)
{
    if (sysconf(_SC_NPROCESSORS_ONLN) < 2) {
        printf("cache line CPU 0 <-> 1: one CPU only\n");
        return 1;
    }
    /* each measured apart: the host may move the vCPUs in between */
    printf("cache line CPU 0 <-> 1:");
    for (int u = 0; u < k; u++) {
        const double ns = pingpong();
        if (ns < 0.0) {
            printf(" (cannot pin threads to CPUs 0 and 1)\n");
            return 1;
        }
        printf(" %.0f", ns);
    }
    printf(" ns per one-way pass\n");
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && !strcmp(argv[1], "--pingpong"))
        return pingpong_line(5);
    if (argc == 2 && !strcmp(argv[1], "--handover")) {
        if (pingpong_line(3))
            return 1;
        double w[2], r[2];
#if defined(__SSE2__)
        const int modes = 2;
#else
        const int modes = 1; /* no non-temporal stores to compare */
#endif
        for (int m = 0; m < modes; m++)
            if (handover(m, &w[m], &r[m]))
                return 1;
        printf("%d lines from CPU 1 to CPU 0, ns per line to write and to "
               "read: in the caches %.1f and %.1f",
               HAND_LINES, w[0], r[0]);
        if (modes > 1)
            printf(", non-temporal %.1f and %.1f", w[1], r[1]);
        printf("\n");
        return pingpong_line(3);
    }
    if (argc > 1 && strcmp(argv[1], "--fronts") == 0) {
        /* the ring pass's streams at the periodic cell's pairs per
         * particle at both sizes, N = 3375 against 216000 swept by 1, 2,
         * 4 and 8 fronts (steps a sweep), in a cube and in a column; each
         * value also over N = 3375's */
        const double pp = 3.32;
        const int r3 = 12 * ((int)(5e6 / 3375) + 1),
                  r2 = 12 * ((int)(5e6 / 216000) + 1);
        printf("ring pass's streams, no arithmetic, %.2f pairs per "
               "particle, ns per particle-step (and over N = 3375's):\n",
               pp);
        for (int arrays = 1; arrays >= 0; arrays--) {
            const double small =
                ring_streams(3375, pp, arrays, 1, r3, 0, 1, LAYOUT_STAGGERED);
            if (small < 0.0)
                no_memory();
            printf("%s the arrays of x, v, omega: N = 3375 %.1f\n",
                   arrays ? "with" : "without", small);
            for (int row = 0; row <= 15; row += 15) {
                printf("  N = 216000 in a %s, 1, 2, 4, 8 steps a sweep:",
                       row ? "column of 15 x 15 cells" : "cube");
                for (int f = 1; f <= 8; f *= 2) {
                    const double v = ring_streams(216000, pp, arrays, f, r2,
                                                  row, 1, LAYOUT_STAGGERED);
                    if (v < 0.0)
                        no_memory();
                    printf(" %.1f (%.2f)%s", v, v / small, f < 8 ? "," : "\n");
                }
            }
        }
        return 0;
    }
    if (argc == 2 && !strcmp(argv[1], "--layouts")) {
        layouts();
        return 0;
    }
    if (argc == 2 && !strcmp(argv[1], "--gathers")) {
        gathers();
        return 0;
    }
    if (argc > 1) {
        fprintf(stderr, "usage: dembox_limits [--pingpong | --handover | "
                        "--fronts | --layouts | --gathers]\n");
        return 2;
    }
#if defined(__AVX512F__)
    printf("mul+add: %.1f Gflop/s in 256-bit vectors, %.1f in 512-bit\n",
           1e-9 * best(muladd_rate_4, 2000000),
           1e-9 * best(muladd_rate_8, 2000000));
#else
    printf("mul+add: %.1f Gflop/s\n", 1e-9 * best(muladd_rate_4, 2000000));
#endif
    printf("sqrt:   %.3f G lanes/s (%.2f ns each)\n",
           1e-9 * best(sqrt_rate, 500000), 1e9 / best(sqrt_rate, 500000));
    printf("divide: %.3f G lanes/s (%.2f ns each)\n",
           1e-9 * best(div_rate, 500000), 1e9 / best(div_rate, 500000));
    const size_t sizes[3] = {8192, 262144, 33554432}; /* 192 KB, 6 MB, 768 MB */
    const char *where[3] = {"L2", "L3", "memory"};
    for (int s = 0; s < 3; s++)
        printf("triad %-6s (%5.0f KB): %.1f GB/s\n", where[s],
               24.0 * sizes[s] / 1024,
               1e-9 * triad(sizes[s], (int)(2e8 / sizes[s]) + 1, 5));
    {
        /* 384 MB, far beyond the caches, written once (first touch) */
        const size_t n = (size_t)48 << 20;
        double *buf = malloc(n * sizeof *buf);
        if (!buf)
            no_memory();
        for (size_t k = 0; k < n; k++)
            buf[k] = 1.0;
        printf("memory, S streams at once (half read, half updated), GB/s "
               "read:");
        const int S[] = {4, 8, 16, 24, 32, 48};
        for (int u = 0; u < (int)(sizeof S / sizeof *S); u++)
            printf(" %d: %.1f%s", S[u], 1e-9 * streams_rate(buf, n, S[u], 4),
                   u + 1 < (int)(sizeof S / sizeof *S) ? "," : "\n");
        free(buf);
    }
    /* the benchmark's packings: listed pairs per particle at N = 3375
     * and 216000 (docs/performance-log.md, "Issue 14 on Zen 5") */
    const int ns[2] = {3375, 216000};
    const double pairs[2] = {3.06, 3.89};
    printf("ring pass's streams, no arithmetic, ns per particle-step:\n");
    for (int s = 0; s < 2; s++) {
        const int reps = 2 * ((int)(5e6 / ns[s]) + 1);
        const double all = ring_streams(ns[s], pairs[s], 1, 1, reps, 0, 1,
                                        LAYOUT_STAGGERED),
                     rec = ring_streams(ns[s], pairs[s], 0, 1, reps, 0, 1,
                                        LAYOUT_STAGGERED),
                     two = ring_streams(ns[s], pairs[s], 1, 2, reps, 0, 1,
                                        LAYOUT_STAGGERED);
        if (all < 0.0 || rec < 0.0 || two < 0.0)
            no_memory();
        printf("  N = %d, %.2f pairs per particle: %.1f (without the "
               "arrays of x, v, omega: %.1f; two steps a sweep, the "
               "second 2 layers behind: %.1f)\n",
               ns[s], pairs[s], all, rec, two);
    }
    /* N = 216000 in a column with the layers of N = 3375: two fronts 2
     * layers apart (2 x 225 particles) have their data in the L2 */
    const int reps = 2 * ((int)(5e6 / ns[1]) + 1);
    const double col1 = ring_streams(ns[1], pairs[1], 1, 1, reps, 15, 1,
                                     LAYOUT_STAGGERED),
                 col2 = ring_streams(ns[1], pairs[1], 1, 2, reps, 15, 1,
                                     LAYOUT_STAGGERED);
    /* and with every array at the start of a page */
    const double alias =
        ring_streams(ns[1], pairs[1], 1, 1, reps, 0, 1, LAYOUT_ALIASED);
    if (col1 < 0.0 || col2 < 0.0 || alias < 0.0)
        no_memory();
    printf("  N = %d in a column of 15 x 15 cells: %.1f (two steps a "
           "sweep: %.1f)\n",
           ns[1], col1, col2);
    printf("  N = %d with every array at the start of a page: %.1f\n", ns[1],
           alias);
    if (sysconf(_SC_NPROCESSORS_ONLN) >= 2)
        pingpong_line(5);
    return sink == 42.0;
}
