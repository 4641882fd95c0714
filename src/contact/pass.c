/* Contact forces: the composition of the kernels for every listed pair and
 * particle-wall contact, in the fixed order normal law -> dashpot ->
 * Coulomb limit -> tangential law -> torques.
 *
 * Conventions (SPEC §2): n = (r_i - r_j)/|r_i - r_j| points from j to i;
 * overlap delta = a_i + a_j - |r_i - r_j|; relative velocity of the contact
 * surfaces v_ij = v_i - v_j + a_i n x w_i + a_j n x w_j; ddelta/dt = -v_ij.n.
 * The force on i is f = f_n n + f_t, on j it is -f; torques are
 * l x f with the branch vectors l_i = -a_i n, l_j = +a_j n, i.e.
 * -a_i (n x f_t) on i and -a_j (n x f_t) on j. A wall is a partner of
 * infinite mass and radius whose surface moves only along its normal.
 *
 * A pass has three parts, each split over the threads in blocks of
 * independent items (the wall contacts in equal ones, the pairs and the
 * particles in dynamic shares, core/parallel.h), in one parallel region
 * with one barrier before the third:
 *  1. every listed pair: force and history, stored with the pair; one
 *     loop without branches over the flat list, run in SIMD lanes;
 *  2. every wall contact: force and history, stored with the contact;
 *  3. every particle: its background damping, then the forces of its
 *     pairs as i (its row), as j (its reverse row: in a periodic cell
 *     those with j itself, then those through an image of j) and of its
 *     wall contacts, each in list order; then the torques and, in a
 *     time step, the closing half kick (and in a chained step the next
 *     half kick and drift, see dem_sim_step).
 * The records compilation (contact/pass.h) reads the particle values of
 * the pairs and of the wall contacts from a copy of the particles in
 * records: each thread first writes its share of them, then a barrier; a
 * chained pass writes its particles' records right after their drift
 * instead, and the next pass (dem_sim_step: no rebuild in between; in a
 * periodic cell the positions stay in the frame of the build,
 * core/cell.h) skips the copy and the barrier, or split over ranks copies
 * only the ghosts, which their owners moved. With more than one thread
 * its chained steps between walls run without the barrier: each thread
 * owns a block of particles and computes every force they need
 * (blocks_thread, neighbor/blocks.h).
 * Every sum therefore runs in one fixed order, and the result is the same
 * bit for bit whatever the number of threads. The loop bodies are written
 * once as always-inline functions and instantiated per normal law of
 * DEM_NORMAL_MODELS (a literal in each parallel region; the models'
 * kernels are chosen in contact/models.h), so there is no function
 * pointer and no configuration branch per contact. A wall contact runs
 * the same model with the wall's parameters (dem_contact_wall_view).
 */
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <string.h>

#include "contact/models.h"
#include "contact/pair.h"
#include "contact/pass.h"
#include "contact/tangential.h"
#include "core/cell.h"
#include "core/parallel.h"
#if DEM_PASS_RECORDS && (defined(__x86_64__) || defined(__i386__))
#include <immintrin.h>
#include <x86intrin.h>
#endif

/* Pairs per round of the records and ring passes' pair loop. gcc gives
 * the loop as many lanes as its 32-bit state words (struct
 * dem_pairs.state) fill in the widest vectors: 16 with AVX-512 (each
 * double in two 512-bit halves), 8 with AVX2. With AVX-512, 8 records at
 * a time come into 512-bit rows (records_lanes), so that each half the
 * loop loads is one store of the transposes: 16 lanes from the 256-bit
 * transposes, whose halves two stores make, gained nothing
 * (docs/performance-log.md, session 38). */
#if defined(__AVX512F__)
#define DEM_PAIR_LANES 16
#else
#define DEM_PAIR_LANES 8
#endif

/* How many pairs ahead the records pass asks for the partners' records
 * (pair_range): at large N they come from main memory or L3 in an order
 * the hardware prefetchers cannot follow (one cell layer ahead, through
 * the list's indices). Two rounds of the loop ahead: a round asks for
 * the records of the round after next.
 * Measured (docs/performance-log.md, "Partners' records fetched ahead" and
 * session 38): with 8 lanes on Zen 4, N = 216000 13 % faster, 3375 and
 * 20000 the same, 8 pairs ahead gained half as much, 32 and 64 no more
 * than 16; with 16 lanes on Zen 5, the ring pass at N = 216000 8 %
 * faster at 32 pairs ahead than at 16. */
#define DEM_PREFETCH_PAIRS (2 * DEM_PAIR_LANES)

/* The records passes' round for the linear, Luding's and Hertz's laws
 * without resistances (between walls and in a periodic cell) in
 * intrinsics, groups of LIN_W pairs, and their wall contacts in such
 * groups, on CPUs with AVX2: 4 lanes in AVX2, 8 with AVX-512
 * (contact/pair_linear_simd.h: the same operations, in an order and with
 * a skip that took some 15-20 % off a step on Zen 1, and 7-11 % against
 * gcc's 16 lanes on an Intel Xeon with AVX-512, session 74; for Luding's
 * law 22 % off a step of biaxial2d-paper there, Hertz's 4 %, session
 * 78). */
#if DEM_PASS_RECORDS && defined(__AVX2__)
#define DEM_PAIR_LINEAR_SIMD 1
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
/* two groups of 8 side by side, one skip for both */
#define LIN_W 8
#define LIN_PAIRS 16
#define lin_pair_groups lin_pairs28
#define lin_walls lin_walls8
#else
/* one group of 4 at a time */
#define LIN_W 4
#define LIN_PAIRS 4
#define lin_pair_groups lin_pairs4
#define lin_walls lin_walls4
#endif
_Static_assert(DEM_PAIR_LANES % LIN_PAIRS == 0, "whole groups a round");
#include "contact/pair_linear_simd.h"
/* Whether the groups run the model set law (whatever its boundary and
 * dimension bits): the linear, Luding's or Hertz's law, without
 * resistances. */
#define GROUPS_LAW(law) GROUPS_MODELS_(DEM_SET_MODELS(law))
#define GROUPS_MODELS_(m)                                                      \
    ((m) == DEM_NORMAL_LINEAR || (m) == DEM_NORMAL_LUDING ||                   \
     (m) == DEM_NORMAL_HERTZ)
#else
#define DEM_PAIR_LINEAR_SIMD 0
#endif

/* How far ahead the ring pass asks for the cache lines of the streams it
 * goes down in order: the list's indices, history and states (pairs),
 * and the particles' arrays its chained kicks, drifts and records read
 * and write (particles). There are some 30 such streams at once, more
 * than the hardware prefetchers follow; at N = 216000, where they come
 * from main memory, asking for them took 8-10 % off the ring pass
 * between walls and 15-20 % in a periodic cell, and nothing from the
 * records pass, whose particle loop reads its forces from memory
 * (docs/performance-log.md, session 39). The ring is the pass the trial
 * picks at that size; while the arrays fit in L3 the requests cost a
 * little, and the trial then picks another pass. */
#define DEM_AHEAD_PAIRS 64
#define DEM_AHEAD_PARTICLES 32

/* particles summed before their kicks and drifts run (particle_range) */
#define DEM_KICK_BLOCK 32
/* the ring pass's groups in a cell are whole blocks, and whole groups
 * make up a virial block (virial_block) */
_Static_assert(DEM_RING_GROUP % DEM_KICK_BLOCK == 0 &&
                   DEM_VIR_BLOCK % DEM_RING_GROUP == 0,
               "the ring's groups: whole kick blocks, within a virial block");

/* the name of this compilation's entry point (contact/pass_loads.c
 * compiles this file again under another) */
#ifndef DEM_PASS_ENTRY
#define DEM_PASS_ENTRY DEM_PASS_NAME(dem__pass_gathers)
#endif

/* (one contact's force, pair_vals and finish_contact: contact/pair.h) */

/* Pair k, its particles' values read from the arrays. */
DEM_INLINE void pair_one(const int law, const struct pass *qp, int k,
                         const struct dem_contact_params *cp, double dt,
                         const struct dem_tangential *T, const double *cv,
                         const double *grad, const double *fm)
{
    struct pv pj = load_pv(qp, qp->cj[k]);
    if (law & DEM_SET_PERIODIC) { /* j's image: x_j + h s (as its image
                                     record has it, image_records) */
        double S[3];
        dem_img_shift(cv, qp->img[k], S);
        pj.x += S[0];
        pj.y += S[1];
        pj.z += S[2];
    }
    qp->F[k - qp->foff] =
        pair_vals(law, qp, k, load_pv(qp, qp->ci[k]), pj, cp, dt, T, grad, fm);
}

#if DEM_PASS_RECORDS
/* Particle records (struct contacts.rec, DEM_REC doubles): x y z r |
 * vx vy vz m | wx wy wz 0, 32-byte aligned, so that a pair's particle
 * loads three vectors and four pairs' values reach their SIMD lanes by
 * 4 x 4 transposes (eight by 8 x 4 ones with AVX-512).
 *
 * The transposes are written in GCC's vector extensions, so that these
 * compilations exist for every CPU: with AVX in 256-bit vectors (the
 * shuffles of AVX's unpacklo/hi and permute2f128), else in 128-bit
 * ones (SSE2's unpcklpd/unpckhpd, NEON's zip1/zip2; 256-bit vectors
 * there were moved element by element through the stack, and the pass
 * took twice as long). Only the AVX-512 transposes and the stores past
 * the caches are written for x86 alone. */
typedef double dem_v2 __attribute__((vector_size(16), aligned(8)));
typedef long long dem_v2i __attribute__((vector_size(16)));
#if defined(__AVX__)
typedef double dem_v4 __attribute__((vector_size(32), aligned(8)));
typedef long long dem_v4i __attribute__((vector_size(32)));
#endif
/* Lanes of a and b (b's numbered on from a's), in gcc's spelling or in
 * clang's. */
#if defined(__clang__)
#define SHUF2_(a, b, i, j) __builtin_shufflevector(a, b, i, j)
#define SHUF4_(a, b, i, j, k, l) __builtin_shufflevector(a, b, i, j, k, l)
#else
#define SHUF2_(a, b, i, j) __builtin_shuffle(a, b, (dem_v2i){i, j})
#define SHUF4_(a, b, i, j, k, l) __builtin_shuffle(a, b, (dem_v4i){i, j, k, l})
#endif

/* A vector's doubles at p (32-byte aligned for 4, 16 for 2) past the
 * caches where the CPU has such stores (x86: the reader is another core,
 * after pass_fence), else by an ordinary store. */
#if defined(__AVX__)
#define STREAM4_(p, v) _mm256_stream_pd(p, (__m256d)(v))
#endif
#if defined(__SSE2__)
#define STREAM2_(p, v) _mm_stream_pd(p, (__m128d)(v))
#else
#define STREAM2_(p, v) (*(dem_v2 *)(void *)(p) = (v))
#endif

/* The stores past the caches (STREAM2_, STREAM4_) done before what
 * follows. */
DEM_INLINE void pass_fence(void)
{
#if defined(__SSE2__)
    _mm_sfence();
#endif
}

/* A spinning thread's pause: the core's hint that this is a wait. */
DEM_INLINE void spin_pause(void)
{
#if defined(__SSE2__)
    _mm_pause();
#elif defined(__aarch64__)
    __asm__ __volatile__("yield");
#endif
}

/* A clock of the core for the threads' balance (neighbor/blocks.h): only
 * the threads' ratios count. */
DEM_INLINE unsigned long long pass_ticks(void)
{
#if defined(__x86_64__) || defined(__i386__)
    return __rdtsc();
#elif defined(__aarch64__)
    unsigned long long v;
    __asm__ __volatile__("mrs %0, cntvct_el0" : "=r"(v));
    return v;
#else
    return (unsigned long long)(omp_get_wtime() * 1e9);
#endif
}

/* The 4 x 4 transpose of the rows of 4 doubles at a[0..4) into those at
 * r[0..4): r[u] gets element u of each; with stream (a literal) past the
 * caches (r 32-byte aligned). */
DEM_INLINE void transpose4(const double *const a[4], double *const r[4],
                           const int stream)
{
#if defined(__AVX__)
    const dem_v4 x0 = *(const dem_v4 *)(const void *)a[0],
                 x1 = *(const dem_v4 *)(const void *)a[1],
                 x2 = *(const dem_v4 *)(const void *)a[2],
                 x3 = *(const dem_v4 *)(const void *)a[3];
    /* unpacklo and unpackhi of each pair of rows, then their low halves
     * (permute2f128 0x20) and their high ones (0x31) */
    const dem_v4 t0 = SHUF4_(x0, x1, 0, 4, 2, 6);
    const dem_v4 t1 = SHUF4_(x0, x1, 1, 5, 3, 7);
    const dem_v4 t2 = SHUF4_(x2, x3, 0, 4, 2, 6);
    const dem_v4 t3 = SHUF4_(x2, x3, 1, 5, 3, 7);
    const dem_v4 y[4] = {SHUF4_(t0, t2, 0, 1, 4, 5), SHUF4_(t1, t3, 0, 1, 4, 5),
                         SHUF4_(t0, t2, 2, 3, 6, 7),
                         SHUF4_(t1, t3, 2, 3, 6, 7)};
    for (int u = 0; u < 4; u++) {
        if (stream)
            STREAM4_(r[u], y[u]);
        else
            *(dem_v4 *)(void *)r[u] = y[u];
    }
#else
    for (int h = 0; h < 2; h++) { /* elements 2h and 2h + 1 */
        dem_v2 x[4];
        for (int e = 0; e < 4; e++)
            x[e] = *(const dem_v2 *)(const void *)(a[e] + 2 * h);
        for (int q = 0; q < 2; q++) { /* rows 0, 1, then 2, 3 */
            const dem_v2 y[2] = {SHUF2_(x[2 * q], x[2 * q + 1], 0, 2),
                                 SHUF2_(x[2 * q], x[2 * q + 1], 1, 3)};
            for (int u = 0; u < 2; u++) {
                if (stream)
                    STREAM2_(r[2 * h + u] + 2 * q, y[u]);
                else
                    *(dem_v2 *)(void *)(r[2 * h + u] + 2 * q) = y[u];
            }
        }
    }
#endif
}

/* Particles i0 <= i < i1 into the records from o on (particle i's at
 * o + DEM_REC (i - i0)), four at a time by transposes; with stream (a
 * literal) past the caches, for ghost records (neighbor/blocks.h: the
 * caller fences). With plane (a literal: a 2D sample, whose passes never
 * read z, v_z, w_x and w_y) those are written 0 without reading their
 * arrays. */
DEM_INLINE void records_fill(double *restrict o, const struct dem_particles *P,
                             int i0, int i1, const int stream, const int plane)
{
    static const double zero[4] = {0.0};
    int i = i0;
    for (; i + 4 <= i1; i += 4, o += 4 * DEM_REC) {
        const double *const a[3][4] = {
            {P->x + i, P->y + i, plane ? zero : P->z + i, P->r + i},
            {P->vx + i, P->vy + i, plane ? zero : P->vz + i, P->m + i},
            {plane ? zero : P->wx + i, plane ? zero : P->wy + i, P->wz + i,
             zero}};
        for (int b = 0; b < 3; b++) {
            double *const r[4] = {o + 4 * b, o + DEM_REC + 4 * b,
                                  o + 2 * DEM_REC + 4 * b,
                                  o + 3 * DEM_REC + 4 * b};
            transpose4(a[b], r, stream);
        }
    }
    for (; i < i1; i++, o += DEM_REC) {
        _Alignas(32) const double v[DEM_REC] = {P->x[i],
                                                P->y[i],
                                                plane ? 0.0 : P->z[i],
                                                P->r[i],
                                                P->vx[i],
                                                P->vy[i],
                                                plane ? 0.0 : P->vz[i],
                                                P->m[i],
                                                plane ? 0.0 : P->wx[i],
                                                plane ? 0.0 : P->wy[i],
                                                P->wz[i],
                                                0.0};
        for (int u = 0; u < DEM_REC; u += 2) {
            const dem_v2 w = *(const dem_v2 *)(const void *)(v + u);
            if (stream)
                STREAM2_(o + u, w);
            else
                *(dem_v2 *)(void *)(o + u) = w;
        }
    }
}

/* Particles i0 <= i < i1 into their records (struct contacts.rec); plane
 * as records_fill's. */
DEM_INLINE void records_own(double *rec, const struct dem_particles *P, int i0,
                            int i1, const int plane)
{
    records_fill(rec + DEM_REC * (size_t)i0, P, i0, i1, 0, plane);
}

/* In a periodic cell, the image records of the pairs k0 <= k < k1 that
 * touch an image of j (struct dem_pairs.jrec): j's record, its position
 * shifted to the image, so that the pair loop reads a record as for any
 * other pair (a shift decoded and applied in every lane took 6 % of the
 * pass, docs/performance-log.md). They are filled every pass from j's
 * records, which must hold the present state, the shift taken from the
 * pass's table (decoding it here took most of the copy's time, in its
 * integer to double conversions, docs/performance-log.md). */
DEM_INLINE void image_records(const struct contacts *c, int k0, int k1)
{
    const struct dem_pairs *pl = c->pl;
    const int *imgk = pl->imgk;
    for (int m = dem_first_at_least(imgk, pl->ncross, k0);
         m < pl->ncross && imgk[m] < k1; m++) {
        const int k = imgk[m];
        const double *s = c->rec + DEM_REC * (size_t)c->q.cj[k];
        double *o = c->rec + DEM_REC * (size_t)c->q.cjr[k];
        /* x y z r plus the shift and 0 */
        const double *S = c->shift[c->q.img[k]];
        for (int u = 0; u < 4; u++)
            o[u] = s[u] + S[u];
        for (int u = 4; u < DEM_REC; u++)
            o[u] = s[u];
    }
}

/* The records of particles idx[0..DEM_PAIR_LANES) as 12 rows of lanes. */
DEM_INLINE void records_lanes(const double *rec, const int *idx,
                              double (*o)[DEM_PAIR_LANES])
{
#if DEM_PAIR_LINEAR_SIMD && LIN_W == 8
    /* 8 records at a time (lin_rows8) */
    for (int g = 0; g < DEM_PAIR_LANES; g += 8) {
        const double *r[8];
        for (int l = 0; l < 8; l++)
            r[l] = rec + DEM_REC * (size_t)idx[g + l];
        for (int b = 0; b < DEM_REC; b += 4) {
            __m512d z[4];
            lin_rows8(r, b, z);
            for (int u = 0; u < 4; u++)
                _mm512_store_pd(&o[b + u][g], z[u]);
        }
    }
#else
    for (int g = 0; g < DEM_PAIR_LANES; g += 4) {
        const double *r0 = rec + DEM_REC * (size_t)idx[g],
                     *r1 = rec + DEM_REC * (size_t)idx[g + 1],
                     *r2 = rec + DEM_REC * (size_t)idx[g + 2],
                     *r3 = rec + DEM_REC * (size_t)idx[g + 3];
        for (int b = 0; b < DEM_REC; b += 4) {
            const double *const a[4] = {r0 + b, r1 + b, r2 + b, r3 + b};
            double *const t[4] = {&o[b][g], &o[b + 1][g], &o[b + 2][g],
                                  &o[b + 3][g]};
            transpose4(a, t, 0);
        }
    }
#endif
}

/* Lane l of records_lanes's rows o: that particle's values for a pair. */
DEM_INLINE struct pv lanes_pv(double (*o)[DEM_PAIR_LANES], int l)
{
    const struct pv p = {o[0][l], o[1][l], o[2][l], o[3][l],
                         o[4][l], o[5][l], o[6][l], o[7][l],
                         o[8][l], o[9][l], o[10][l]};
    return p;
}

/* Force record o into lane l of rows O[0..6) (forces_from_lanes). */
DEM_INLINE void lanes_set(double (*O)[DEM_PAIR_LANES], int l,
                          const struct dem_contact_force o)
{
    for (int e = 0; e < 3; e++) {
        O[e][l] = o.f[e];
        O[3 + e][l] = o.c[e];
    }
}

_Static_assert(sizeof(struct dem_contact_force) == 6 * sizeof(double),
               "a force record: f and c, 48 bytes");

/* The force records of DEM_PAIR_LANES consecutive contacts from rows
 * o[0..6) of lanes (f x y z, c x y z) into F[0..DEM_PAIR_LANES), by
 * transposes. Stored lane by lane, the records took a fifth of the pair
 * loop's instructions and it ran 10-15 % slower (docs/performance-log.md,
 * session 54). */
DEM_INLINE void forces_from_lanes(struct dem_contact_force *F,
                                  double (*o)[DEM_PAIR_LANES])
{
#if DEM_PAIR_LINEAR_SIMD && LIN_W == 8
    /* per 8 lanes an 8 x 8 transpose (lin_store_forces8) */
    for (int g = 0; g < DEM_PAIR_LANES; g += 8) {
        __m512d r[6];
        for (int e = 0; e < 6; e++)
            r[e] = _mm512_load_pd(&o[e][g]);
        lin_store_forces8(F + g, r);
    }
#else
    double *d = (double *)(void *)F; /* the records as rows of 6 */
    /* per 4 lanes a 4 x 4 transpose of f and c x into each record's
     * first 4 doubles, then c y and c z two records at a time */
    for (int g = 0; g < DEM_PAIR_LANES; g += 4, d += 24) {
        const double *const a[4] = {&o[0][g], &o[1][g], &o[2][g], &o[3][g]};
        double *const t[4] = {d, d + 6, d + 12, d + 18};
        transpose4(a, t, 0);
        for (int u = 0; u < 4; u += 2) {
            const dem_v2 y = *(const dem_v2 *)(const void *)&o[4][g + u],
                         w = *(const dem_v2 *)(const void *)&o[5][g + u];
            *(dem_v2 *)(void *)(d + 6 * u + 4) = SHUF2_(y, w, 0, 2);
            *(dem_v2 *)(void *)(d + 6 * u + 10) = SHUF2_(y, w, 1, 3);
        }
    }
#endif
}
#endif

/* Forces and history updates of pairs k0 <= k < k1 (the thread's pairs
 * go on to kend), in SIMD lanes; ahead: the records compilations ask for
 * the list's streams of the pairs that many ahead (a literal, 0: not);
 * ahead_i (a literal): they ask for the i records as for the j records
 * (else those run in order). */
DEM_INLINE void pair_range(const int law, const struct pass q, int k0, int k1,
                           int kend, const struct dem_contact_params *cp,
                           double dt, const double *cv, const double *grad,
                           const double *fm, const double *rec, const int ahead,
                           const int ahead_i)
{
    (void)ahead_i;
    const struct dem_tangential T = {cp->kt, cp->gamma_t, cp->mu_s, cp->mu_d};
    /* 1/k_t as dem_coulomb_spring has it (DEM_PAIR_LINEAR_SIMD) */
    const double ik = T.kt > 0.0 ? 1.0 / T.kt : 0.0;
    (void)ik;
    /* local copies, which no store of the loop can change */
    const double gv[6] = {grad[0], grad[1], grad[2], grad[3], grad[4], grad[5]};
    const double mv[6] = {fm[0], fm[1], fm[2], fm[3], fm[4], fm[5]};
    const struct dem_contact_params cpv = *cp;
    grad = gv;
    fm = mv;
    cp = &cpv;
    int k = k0;
    (void)rec;
    (void)kend;
    (void)ahead;
#if DEM_PASS_RECORDS
#if DEM_PAIR_LINEAR_SIMD
    struct lin_skip skip = {1, 0, 0};
#endif
    for (; k + DEM_PAIR_LANES <= k1; k += DEM_PAIR_LANES) {
        _Alignas(64) double A[DEM_REC][DEM_PAIR_LANES],
            B[DEM_REC][DEM_PAIR_LANES];
        /* the j records of the pairs DEM_PREFETCH_PAIRS ahead (up to
         * kend), both cache lines of each (the i records run in order) */
        if (k + DEM_PREFETCH_PAIRS + DEM_PAIR_LANES <= kend)
            for (int l = 0; l < DEM_PAIR_LANES; l++) {
                const double *r =
                    rec + DEM_REC * (size_t)q.cjr[k + DEM_PREFETCH_PAIRS + l -
                                                  q.roff];
                __builtin_prefetch(r, 0, 3);
                __builtin_prefetch(r + 8, 0, 3);
                if (ahead_i) {
                    const int ia = q.ci[k + DEM_PREFETCH_PAIRS + l];
                    const double *o = rec + DEM_REC * (size_t)ia;
                    __builtin_prefetch(o, 0, 3);
                    __builtin_prefetch(o + 8, 0, 3);
                }
            }
        /* the list's streams a round of pairs reads: asking for the line
         * of a round's first 4-byte value and of every 8th double covers
         * every line of them */
        if (ahead && k + ahead + DEM_PAIR_LANES <= kend) {
            const int u = k + ahead;
            __builtin_prefetch(q.ci + u, 0, 3);
            __builtin_prefetch(q.cjr + (u - q.roff), 0, 3);
            __builtin_prefetch(q.state + u, 1, 3);
            for (int e = 0; e < DEM_PAIR_LANES; e += 8) {
#define HIST_AHEAD_(MODEL, name, unit, swap, doc)                              \
    if (DEM_MODEL_USES(law, MODEL))                                            \
        __builtin_prefetch(q.name + u + e, 1, 3);
                DEM_CONTACT_HISTORY(HIST_AHEAD_)
#undef HIST_AHEAD_
            }
        }
#if DEM_PAIR_LINEAR_SIMD
        if (GROUPS_LAW(law)) {
            for (int g = 0; g < DEM_PAIR_LANES; g += LIN_PAIRS)
                lin_skip_count(
                    &skip, lin_pair_groups(law, &q, k + g, rec, cp,
                                           law & DEM_SET_PERIODIC ? fm : NULL,
                                           law & DEM_SET_PERIODIC ? grad : NULL,
                                           dt, &T, ik, q.F + (k + g - q.foff),
                                           skip.branch));
            continue;
        }
#endif
        records_lanes(rec, q.ci + k, A);
        records_lanes(rec, q.cjr + (k - q.roff), B);
        _Alignas(64) double O[6][DEM_PAIR_LANES];
#pragma omp simd
        for (int l = 0; l < DEM_PAIR_LANES; l++) {
            lanes_set(O, l,
                      pair_vals(law, &q, k + l, lanes_pv(A, l), lanes_pv(B, l),
                                cp, dt, &T, grad, fm));
        }
        forces_from_lanes(q.F + (k - q.foff), O);
    }
    /* the rest from the records too (the same values as in the arrays,
     * which with threads that own their blocks another thread may be
     * moving on already, neighbor/blocks.h) */
    (void)cv;
#pragma omp simd
    for (int kk = k; kk < k1; kk++)
        q.F[kk - q.foff] =
            pair_vals(law, &q, kk, record_pv(rec + DEM_REC * (size_t)q.ci[kk]),
                      record_pv(rec + DEM_REC * (size_t)q.cjr[kk - q.roff]), cp,
                      dt, &T, grad, fm);
#else
#pragma omp simd
    for (int kk = k; kk < k1; kk++)
        pair_one(law, &q, kk, cp, dt, &T, cv, grad, fm);
#endif
}

/* Wall contacts k0 <= k < k1, with the wall's parameters cp
 * (dem_contact_wall_view), in SIMD lanes as pair_range (in groups for
 * the laws pair_range runs in groups); the records
 * compilations read the particles' values from their records (rec). */
DEM_INLINE void wall_range(const int law, const struct pass q, int k0, int k1,
                           const struct dem_contact_params *cp, double dt,
                           const struct dem_wall *walls, const double *rec)
{
    /* a local copy, which no store of the loop can change */
    const struct dem_contact_params cpv = *cp;
    cp = &cpv;
    const struct dem_tangential T = {cp->kt, cp->gamma_t, cp->mu_s, cp->mu_d};
    int k = k0;
    (void)rec;
#if DEM_PAIR_LINEAR_SIMD
    if (GROUPS_LAW(law)) {
        const double ik = T.kt > 0.0 ? 1.0 / T.kt : 0.0;
        _Alignas(64) double wr[DEM_MAX_WALLS * DEM_REC];
        lin_wall_rows(walls, wr);
        struct lin_skip skip = {1, 0, 0};
        for (; k + LIN_W <= k1; k += LIN_W)
            lin_skip_count(&skip, lin_walls(law, &q, k, rec, wr, cp, dt, &T, ik,
                                            q.F + (k - q.foff), skip.branch));
    }
#endif
#if DEM_PASS_RECORDS
    for (; k + DEM_PAIR_LANES <= k1; k += DEM_PAIR_LANES) {
        _Alignas(64) double A[DEM_REC][DEM_PAIR_LANES];
        records_lanes(rec, q.ci + k, A);
        _Alignas(64) double O[6][DEM_PAIR_LANES];
#pragma omp simd
        for (int l = 0; l < DEM_PAIR_LANES; l++)
            lanes_set(
                O, l,
                wall_vals(law, &q, k + l, lanes_pv(A, l), cp, dt, walls, &T));
        forces_from_lanes(q.F + (k - q.foff), O);
    }
#pragma omp simd
    for (int kk = k; kk < k1; kk++)
        q.F[kk - q.foff] =
            wall_vals(law, &q, kk, record_pv(rec + DEM_REC * (size_t)q.ci[kk]),
                      cp, dt, walls, &T);
#else
#pragma omp simd
    for (int kk = k; kk < k1; kk++)
        q.F[kk - q.foff] =
            wall_vals(law, &q, kk, load_pv(&q, q.ci[kk]), cp, dt, walls, &T);
#endif
}

#if defined(__GNUC__)
/* Eight doubles as one value of GCC's and clang's vector extension
 * (lowered to the widest vectors the target has), loaded and stored
 * unaligned with memcpy (never passed to or returned from a function:
 * without AVX-512 that would change the ABI, -Wpsabi). */
typedef double dem_lanes8 __attribute__((vector_size(64), aligned(8)));
#endif

/* The periodic cell's virial as a pass sums it (virial_block): the
 * virial blocks' sums (struct contacts.vir), the current block's 8 lanes
 * of partial sums, and the end of the particles the caller takes. */
struct virial {
    double *vir;
    _Alignas(64) double w[9][8];
    int end;
    const double *fm; /* the frame's map (struct contacts.fr) */
};

/* Particle i's share of the periodic cell's virial, added to lane i % 8
 * of w; f its contacts' sum. The same arithmetic as virial_lanes, so a
 * particle adds the same bits either way. With plane (a literal: a 2D
 * sample, z, v_z and f_z zero) only the x-y block: the others stay +0,
 * as their sums of zeros come out (a lane's sum starts at +0 and adding
 * -0 leaves it +0). */
DEM_INLINE void virial_add(const int plane, const struct dem_particles *P,
                           const double *fm, int i, double fx, double fy,
                           double fz, double (*w)[8])
{
    const int D = plane ? 2 : 3;
    const double x = P->x[i], y = P->y[i], z = plane ? 0.0 : P->z[i];
    const double X[3] = {plane ? fm[0] * x + fm[1] * y
                               : fm[0] * x + fm[1] * y + fm[2] * z,
                         plane ? fm[3] * y : fm[3] * y + fm[4] * z, fm[5] * z},
                 U[3] = {P->vx[i], P->vy[i], plane ? 0.0 : P->vz[i]},
                 f[3] = {fx, fy, fz};
    const int l = i % 8;
    for (int a = 0; a < D; a++) {
        const double mu = P->m[i] * U[a];
        for (int c = 0; c < D; c++)
            w[3 * a + c][l] += X[a] * f[c] + mu * U[c];
    }
}

/* The virial of particles ib + u, from u on (ib + u a multiple of 8) in
 * groups of 8 while they end by ue, particle ib + u + l in lane l of w;
 * f[.][u] their contacts' sums. Returns the u it stopped at. */
DEM_INLINE int virial_lanes(const int plane, const struct dem_particles *P,
                            const double *fm, int ib, int u, int ue,
                            double (*f)[DEM_KICK_BLOCK], double (*w)[8])
{
    const int D = plane ? 2 : 3; /* as virial_add */
#if defined(__GNUC__)
    /* The lanes' sums as values, not in memory: the same arithmetic as
     * virial_add, in the same order, so the same bits. With w updated in
     * memory (the loop below) the cell's pass took 10 % longer at N =
     * 3375 on Zen 4, more than this loop's own work: GCC 12 left the sums
     * in memory and the inlined block slowed the pair loop around it too
     * (docs/performance-log.md). */
    const double *restrict X[3] = {P->x, P->y, P->z},
                           *restrict U[3] = {P->vx, P->vy, P->vz};
    const double m[6] = {fm[0], fm[1], fm[2], fm[3], fm[4], fm[5]};
    dem_lanes8 s[9];
    for (int c = 0; c < 9; c++)
        memcpy(&s[c], w[c], sizeof s[c]);
    for (; u + 8 <= ue; u += 8) {
        const int i = ib + u;
        dem_lanes8 mi, y[3], x[3], v[3], g[3];
        memcpy(&mi, P->m + i, sizeof mi);
        for (int a = 0; a < D; a++) {
            memcpy(&y[a], X[a] + i, sizeof y[a]);
            memcpy(&v[a], U[a] + i, sizeof v[a]);
            memcpy(&g[a], f[a] + u, sizeof g[a]);
        }
        /* the position mapped from the frame, as virial_add */
        if (plane) {
            x[0] = m[0] * y[0] + m[1] * y[1];
            x[1] = m[3] * y[1];
        } else {
            x[0] = m[0] * y[0] + m[1] * y[1] + m[2] * y[2];
            x[1] = m[3] * y[1] + m[4] * y[2];
            x[2] = m[5] * y[2];
        }
        for (int a = 0; a < D; a++) {
            const dem_lanes8 mu = mi * v[a];
            for (int c = 0; c < D; c++)
                s[3 * a + c] += x[a] * g[c] + mu * v[c];
        }
    }
    for (int c = 0; c < 9; c++)
        memcpy(w[c], &s[c], sizeof s[c]);
#else
    for (; u + 8 <= ue; u += 8)
        for (int l = 0; l < 8; l++)
            virial_add(plane, P, fm, ib + u + l, f[0][u + l], f[1][u + l],
                       f[2][u + l], w);
#endif
    return u;
}

/* After particle end - 1: at the end of its virial block, or at V->end,
 * the lanes summed in order into the block's sums and cleared. */
DEM_INLINE void virial_flush(struct virial *V, int end)
{
    if (end % DEM_VIR_BLOCK && end != V->end)
        return;
    double *o = V->vir + 9 * ((end - 1) / DEM_VIR_BLOCK);
    for (int c = 0; c < 9; c++) {
        double t = 0.0;
        for (int l = 0; l < 8; l++) {
            t += V->w[c][l];
            V->w[c][l] = 0.0;
        }
        o[c] = t;
    }
}

/* virial_block for a piece that starts off lane 0 or crosses a virial
 * block (the ring pass's pieces). Not inlined: inlined, this general
 * loop made the cell's stored pass 15 % slower at N = 3375 on Zen 4
 * (the pair loop around it, as virial_lanes says). */
DEM_INLINE void virial_pieces_in(const int plane, const struct dem_particles *P,
                                 int ib, int nb, double (*f)[DEM_KICK_BLOCK],
                                 struct virial *V)
{
    const double *fm = V->fm;
    const double m[6] = {fm[0], fm[1], fm[2], fm[3], fm[4], fm[5]};
    for (int u = 0; u < nb;) {
        /* up to the end of this virial block */
        const int be = (ib + u) / DEM_VIR_BLOCK * DEM_VIR_BLOCK + DEM_VIR_BLOCK;
        const int ue = be - ib < nb ? be - ib : nb;
        for (; u < ue && (ib + u) % 8; u++) /* up to lane 0 */
            virial_add(plane, P, m, ib + u, f[0][u], f[1][u], f[2][u], V->w);
        u = virial_lanes(plane, P, m, ib, u, ue, f, V->w);
        for (; u < ue; u++)
            virial_add(plane, P, m, ib + u, f[0][u], f[1][u], f[2][u], V->w);
        virial_flush(V, ib + u);
    }
}
static __attribute__((noinline)) void
virial_pieces(int plane, const struct dem_particles *P, int ib, int nb,
              double (*f)[DEM_KICK_BLOCK], struct virial *V)
{
    if (plane)
        virial_pieces_in(1, P, ib, nb, f, V);
    else
        virial_pieces_in(0, P, ib, nb, f, V);
}

/* The periodic cell's virial (contact/forces.c) of particles
 * ib <= i < ib + nb, with contact forces f (the sums of their pairs and
 * no damping): sum_contacts b (x) f, b = m (x_i - x_j') with m the
 * frame's map (V->fm), is sum_i (m x_i) (x) f_i (m x_i is the position
 * now less one offset for all, whose share sums to zero with the pair
 * forces) minus the images' shifts now (summed after the pass), plus the
 * kinetic part
 * m u (x) u. Particle i adds to lane i % 8 of V->w, in particle order; at
 * the end of each virial block of DEM_VIR_BLOCK particles (or at V->end)
 * the lanes are summed in order into V->vir and cleared. A caller that
 * finishes its particles in pieces (the ring pass) keeps V from one piece
 * to the next: the sums are the same bits however the particles are cut,
 * as long as one thread takes each virial block's particles in order. */
DEM_INLINE void virial_block(const int plane, const struct dem_particles *P,
                             int ib, int nb, double (*f)[DEM_KICK_BLOCK],
                             struct virial *V)
{
    if (ib % 8 || ib / DEM_VIR_BLOCK != (ib + nb - 1) / DEM_VIR_BLOCK) {
        virial_pieces(plane, P, ib, nb, f, V);
        return;
    }
    /* a piece from lane 0 within one virial block (every piece of the
     * stored pass: DEM_KICK_BLOCK divides DEM_VIR_BLOCK) */
    int u = virial_lanes(plane, P, V->fm, ib, 0, nb, f, V->w);
    for (; u < nb; u++) /* a range's last particles */
        virial_add(plane, P, V->fm, ib + u, f[0][u], f[1][u], f[2][u], V->w);
    virial_flush(V, ib + nb);
}

/* What a thread that owns its block (neighbor/blocks.h) reads and writes
 * besides the list's arrays: its twins' forces and resistance torques,
 * F[u] and M[3 u] for the u = tw[q - q0] of a reverse row's entry q whose
 * pair is below k0 (an earlier block's); and the ghost records of its
 * particles in [lo[r], hi[r]) for the next pass, from ghost[at[r]] on. */
struct own {
    const struct dem_contact_force *F;
    const double *M;
    const int *tw;
    int q0, k0;
    double *ghost;
    int lo[2], hi[2], at[2];
};

/* A particle's row is summed DEM_SUM_GROUP records at a time
 * (particle_range), with sum_neutral in place of the records past its
 * end. Added, -0.0 leaves every double as it is (x + -0.0 is x, also
 * for x = -0.0), so the sum is the same bits as over the row alone. The
 * loop then ends where a group ends, nearly always after the first,
 * instead of at the row's end, which varies from one particle to the
 * next: on Zen 1 that took 2-3 % off a step at N = 3375 and 20000. An
 * empty row skips the group (in a loose packing most rows are empty,
 * and four neutral records cost more than that branch). The
 * reverse rows and the walls' contacts summed alike were slower
 * (docs/performance-log.md, session 70). The address of a record past
 * the row is formed as an integer (it may lie past the array) and never
 * read. */
#define DEM_SUM_GROUP 4
static const struct dem_contact_force sum_neutral = {{-0.0, -0.0, -0.0},
                                                     {-0.0, -0.0, -0.0}};

/* a if c, else b, by a conditional move: the compiler would branch on
 * c (it sees that sum_neutral's sums change nothing) */
DEM_INLINE uintptr_t sum_pick(int c, uintptr_t a, uintptr_t b)
{
#if defined(__x86_64__) && defined(__GNUC__)
    __asm__("test %1, %1\n\tcmovz %2, %0" : "+r"(a) : "r"(c), "r"(b) : "cc");
    return a;
#else
    return c ? a : b;
#endif
}

/* Particles i0 <= i < i1: background damping plus the forces of the
 * pairs as i (the particle's row), as j (its reverse row), pair k's
 * read from F[(k - kb) & fmask] (but in a periodic cell the pairs through
 * an image of j from the list's array), and of the wall contacts; then the
 * torques, and the half kick if asked for. With K.chain the particle
 * then goes on into the next step: its half kick and drift
 * (dem_particle_kick and _drift, as the first pass of a step in
 * core/sim.c), and the force and torque are not stored (nothing reads
 * them before they are computed again). Returns then whether a particle
 * has moved further than its reach (less K.cut) since the last list
 * build. In a cell the particles' virial goes to V (virial_block).
 * K.chain is a literal in each caller, so it costs no branch, and so is
 * K.on in a chained step; in the others K.on is read once per block of
 * particles (it is 0 only in the pass without a kick, which runs once,
 * at a sample's start: dem_sim_forces). */
DEM_INLINE int particle_range(const int law, int i0, int i1,
                              const struct dem_particles *P,
                              const struct dem_pairs *pl,
                              const struct dem_contact_force *F, int kb,
                              int fmask, double gb, double gr,
                              const struct kick K, struct virial *V,
                              const struct dem_frame *fr, double *rec,
                              const int ahead, const struct own *O)
{
    (void)rec;
    const int cell = (law & DEM_SET_PERIODIC) != 0;
    /* in 2D f_z, c_x, c_y and the torques' x and y are zero: not summed,
     * and v_z, w_x, w_y and z are not kicked or moved */
    const int plane = DEM_SET_IN_PLANE(law);
    const double *restrict M = pl->f.m, *restrict WM = pl->wf.m;
    double far = 0.0; /* the largest overshoot (chained) */
    const int *restrict start = pl->cur.start, *restrict rpair = pl->rpair;
    /* the kicks write these through P: no restrict */
    const double *vx = P->vx, *vy = P->vy, *vz = P->vz;
    const double *wx = P->wx, *wy = P->wy, *wz = P->wz;
    const double *restrict r = P->r;
    const double hg[3] = {K.h * K.g[0], K.h * K.g[1], K.h * K.g[2]};
    /* the frame's inverse map (cell), as locals no store changes */
    const double *g = fr->g, s2 = fr->s2;
    const double fi[6] = {g[0], g[1], g[2], g[3], g[4], g[5]};
    double *restrict ofx = P->fx, *restrict ofy = P->fy, *restrict ofz = P->fz;
    double *restrict otx = P->tx, *restrict oty = P->ty, *restrict otz = P->tz;
    const int *restrict rstart = pl->rstart, *restrict wstart = pl->wcur.start,
                        *restrict rimg = pl->rimg;
    const struct dem_contact_force *restrict WF = pl->wf.v, *FL = pl->f.v;
    /* The sums of a block of particles first, then the block's kicks and
     * drifts in SIMD lanes (as scalar code, one particle after the other,
     * they took a quarter of a chained step); each particle's arithmetic
     * is the same either way, so the results are the same bits. */
    double bf[6][DEM_KICK_BLOCK]; /* the block's forces and torques */
    double bc[3][DEM_KICK_BLOCK]; /* its contacts' forces (cell) */
    /* a local copy of the arrays' pointers: the kicks' stores cannot
     * change them, so the lanes' accesses are consecutive, not scatters */
    const struct dem_particles Q = *P;
    for (int i = i0; i < i1; i++) {
        /* a chained step's streams, particles ahead (a literal, 0: not):
         * every 8 particles one line of each array (8 doubles; the row
         * starts' lines of 16 ints are asked for twice) */
        if (ahead && K.chain && i % 8 == 0 && i + ahead < Q.n) {
            const int u = i + ahead;
            /* (in 2D those of z, v_z, w_x, w_y, last, are not used) */
            const double *const in[] = {Q.x0,    Q.y0,    Q.r,     Q.m,
                                        Q.inv_m, Q.inv_I, Q.reach, Q.z0};
            double *const out[] = {Q.x, Q.y,  Q.vx, Q.vy, Q.wz,
                                   Q.z, Q.vz, Q.wx, Q.wy};
            const int nin = (int)(sizeof in / sizeof *in) - plane,
                      nout = (int)(sizeof out / sizeof *out) - 4 * plane;
            for (int e = 0; e < nin; e++)
                __builtin_prefetch(in[e] + u, 0, 3);
            for (int e = 0; e < nout; e++)
                __builtin_prefetch(out[e] + u, 1, 3);
            __builtin_prefetch(start + u, 0, 3);
            __builtin_prefetch(rstart + u, 0, 3);
            __builtin_prefetch(wstart + u, 0, 3);
        }
        const double a = r[i];
        /* in a cell the damping comes after the contacts' sum (the
         * virial takes that sum) */
        double fx = cell ? 0.0 : -gb * vx[i], fy = cell ? 0.0 : -gb * vy[i],
               fz = cell || plane ? 0.0 : -gb * vz[i];
        double cx = 0.0, cy = 0.0, cz = 0.0; /* sums of n x f_t */
        /* the resistances' torques: on i as i, the opposite as j, summed
         * in the loops of the forces (each sum in its own order: the
         * same bits as in loops of their own, which cost a particle
         * three more loop exits) */
        double mx = 0.0, my = 0.0, mz = 0.0;
        /* the row in groups (DEM_SUM_GROUP, sum_pick above) */
        for (int k = start[i], k1 = start[i + 1]; k < k1; k += DEM_SUM_GROUP) {
            for (int t = 0; t < DEM_SUM_GROUP; t++) {
                const struct dem_contact_force *o = (const void *)sum_pick(
                    k + t < k1,
                    (uintptr_t)F + sizeof *F * (size_t)((k + t - kb) & fmask),
                    (uintptr_t)&sum_neutral);
                fx += o->f[0];
                fy += o->f[1];
                if (!plane) {
                    fz += o->f[2];
                    cx += o->c[0];
                    cy += o->c[1];
                }
                cz += o->c[2];
                if (DEM_SET_TORQUES(law)) {
                    const double *m = (const void *)sum_pick(
                        k + t < k1,
                        (uintptr_t)M + 3 * sizeof *M * (size_t)(k + t),
                        (uintptr_t)sum_neutral.f);
                    if (!plane) {
                        mx += m[0];
                        my += m[1];
                    }
                    mz += m[2];
                }
            }
        }
        /* (from a ring in a cell those with j itself, then those
         * through an image of j, which are in the list's array: the
         * order of every pass; a literal fmask of -1, the list's array,
         * reads them all alike) */
        const int qi = cell && fmask != -1 ? rimg[i] : rstart[i + 1];
        for (int q = rstart[i]; q < rstart[i + 1]; q++) {
            const struct dem_contact_force *o =
                q < qi ? &F[(rpair[q] - kb) & fmask] : &FL[rpair[q]];
            if (O && rpair[q] < O->k0) /* a twin: its own copy */
                o = &O->F[O->tw[q - O->q0]];
            fx -= o->f[0];
            fy -= o->f[1];
            if (!plane) {
                fz -= o->f[2];
                cx += o->c[0];
                cy += o->c[1];
            }
            cz += o->c[2];
            if (DEM_SET_TORQUES(law)) {
                const double *m = O && rpair[q] < O->k0
                                      ? &O->M[3 * O->tw[q - O->q0]]
                                      : &M[3 * rpair[q]];
                if (!plane) {
                    mx -= m[0];
                    my -= m[1];
                }
                mz -= m[2];
            }
        }
        for (int k = wstart[i]; k < wstart[i + 1]; k++) {
            fx += WF[k].f[0];
            fy += WF[k].f[1];
            if (!plane) {
                fz += WF[k].f[2];
                cx += WF[k].c[0];
                cy += WF[k].c[1];
            }
            cz += WF[k].c[2];
            if (DEM_SET_TORQUES(law)) {
                if (!plane) {
                    mx += WM[3 * k];
                    my += WM[3 * k + 1];
                }
                mz += WM[3 * k + 2];
            }
        }
        const int b = (i - i0) % DEM_KICK_BLOCK, ib = i - b;
        if (cell) {
            /* the contacts' sum for the virial, then the damping */
            bc[0][b] = fx;
            bc[1][b] = fy;
            bc[2][b] = fz;
            fx -= gb * vx[i];
            fy -= gb * vy[i];
            if (!plane)
                fz -= gb * vz[i];
        }
        const double g = gr * a * a;
        double tx = plane ? 0.0 : -g * wx[i] - a * cx,
               ty = plane ? 0.0 : -g * wy[i] - a * cy, tz = -g * wz[i] - a * cz;
        if (DEM_SET_TORQUES(law)) {
            if (!plane) {
                tx += mx;
                ty += my;
            }
            tz += mz;
        }
        if (!K.chain) {
            ofx[i] = fx;
            ofy[i] = fy;
            ofz[i] = fz;
            otx[i] = tx;
            oty[i] = ty;
            otz[i] = tz;
        }
        bf[0][b] = fx;
        bf[1][b] = fy;
        bf[2][b] = fz;
        bf[3][b] = tx;
        bf[4][b] = ty;
        bf[5][b] = tz;
        if (b + 1 < DEM_KICK_BLOCK && i + 1 < i1)
            continue;
        if (cell) /* before the kicks: the velocities of the pass */
            virial_block(plane, &Q, ib, b + 1, bc, V);
        /* the block's kicks and drifts, in SIMD lanes */
        if (K.on && !K.chain) {
#pragma omp simd
            for (int u = 0; u <= b; u++)
                dem_particle_kick(plane, &Q, ib + u, K.h, hg, bf[0][u],
                                  bf[1][u], bf[2][u], bf[3][u], bf[4][u],
                                  bf[5][u]);
        }
        if (K.chain) {
            /* the box's map since the build (walls), loaded where the
             * drift uses it rather than live through the pair loops */
            const double *bm = fr->b;
            const double bb[6] = {bm[0], bm[1], bm[2], bm[3], bm[4], bm[5]};
#pragma omp simd reduction(max : far)
            for (int u = 0; u <= b; u++) {
                const int k = ib + u;
                dem_particle_kick(plane, &Q, k, K.h, hg, bf[0][u], bf[1][u],
                                  bf[2][u], bf[3][u], bf[4][u], bf[5][u]);
                dem_particle_kick(plane, &Q, k, K.h, hg, bf[0][u], bf[1][u],
                                  bf[2][u], bf[3][u], bf[4][u], bf[5][u]);
                const double d2 =
                    cell ? dem_particle_drift_frame(plane, &Q, k, K.dt, fi, s2)
                         : dem_particle_drift(plane, &Q, k, K.dt, bb);
                const double o = dem_particle_overshoot(&Q, k, d2, K.cut);
                far = o > far ? o : far;
            }
#if DEM_PASS_RECORDS
            /* the next pass reads the block's records as they are now */
            records_own(rec, &Q, ib, ib + b + 1, plane);
            for (int r = 0; O && r < 2; r++) { /* and its ghost records */
                const int lo = ib > O->lo[r] ? ib : O->lo[r],
                          hi = ib + b + 1 < O->hi[r] ? ib + b + 1 : O->hi[r];
                const size_t at = (size_t)(O->at[r] + lo - O->lo[r]);
                if (lo < hi)
                    records_fill(O->ghost + DEM_REC * at, &Q, lo, hi, 1, plane);
            }
#endif
        }
    }
    return K.chain && far > 0.0;
}

#if DEM_PASS_RING
/* Thread t's share of a chained pass with the pairs' forces in a ring
 * (contacts.ring, ring_mask + 1 entries per thread, at least the list's
 * reach (struct dem_pairs) plus a chunk): the thread takes the rows of a
 * block of particles, ring_chunk pairs at a time, and after each
 * chunk computes the wall contacts of the particles whose rows it
 * completed and sums, kicks and moves them on. Every row holds j > i,
 * so such a particle's pairs as j lie in rows before its own: all of
 * them are done, within the ring's reach, and no pair still to come reads
 * its record. Only the particles with a pair as j in another thread's
 * rows (dem_pairs_row_block) must wait. Those of the first range wait
 * for the barrier, after which the threads share all blocks' first
 * ranges equally; the chunks holding their pairs (below start[d], or
 * from kt on: the block's first pair with a j beyond it) are copied to
 * the list's force array too, which they read from. In a periodic cell
 * every pair through an image is copied there as well after its chunk,
 * and read from there (particle_range: they are left out of the reach,
 * so a ring is as small as between walls, docs/performance-log.md); the
 * cell's stress sums them after the pass (contact/forces.c). So the
 * second range (the last layer, with pairs through the z faces in the
 * earlier blocks' first rows) waits only until every earlier thread has
 * published (c->done, after each chunk) that it is past those pairs
 * (below kw), and is finished in stream. The blocks and the waiting
 * ranges are cut at multiples of DEM_VIR_BLOCK, so each virial block is
 * summed by one thread in particle order (virial_block). The forces never
 * leave the cache otherwise. Each sum runs over the same values in the
 * same order as in the stored pass: the same bits. */
DEM_INLINE int ring_thread(const int law, const struct contacts *c,
                           const struct kick K, int t, int nt)
{
    const struct dem_pairs *pl = c->pl;
    const int *start = pl->cur.start, *wstart = pl->wcur.start,
              *imgk = pl->imgk;
    const int cell = (law & DEM_SET_PERIODIC) != 0,
              g = cell ? DEM_VIR_BLOCK : 1;
    int *W = c->wait + 4 * t, kt, kw;
    dem_pairs_row_block(pl, c->n, t, nt, g, W, &kt, &kw);
    const int i0 = W[0], d = W[1], s = W[2], i1 = W[3];
    /* the second range is finished in stream, not after the barrier */
    W[2] = i1;
    int *done = c->done + DEM_RING_DONE * t;
    const int k0 = start[i0], k1 = start[i1];
    if (cell) /* the images' records of the thread's own pairs */
        image_records(c, k0, k1);
    const int kd = start[d], mask = c->ring_mask;
    /* pair k's force at ring[(k - k0) & mask]; a chunk never wraps (the
     * size is a multiple of the chunk's), so in the pair loop it is
     * at q.F[k - q.foff], consecutive as in the list's array */
    struct dem_contact_force *ring = c->ring + (size_t)t * ((size_t)mask + 1);
    struct pass q = c->q;
    q.F = ring;
    struct virial V = {c->vir, {{0.0}}, i1, c->fr.m};
    int moved = 0;
    int p = d, w = i0; /* next particle to finish, next one's walls */
    int m = cell ? dem_first_at_least(imgk, pl->ncross, k0) : 0;
    for (int kc = k0;;) {
        const int ke = k1 - kc > c->ring_chunk ? kc + c->ring_chunk : k1;
        q.foff = kc - ((kc - k0) & mask);
        pair_range(law, q, kc, ke, k1, &c->cp, c->dt, c->cv, c->grad, c->fr.m,
                   c->rec, DEM_AHEAD_PAIRS, 0);
        const int all = kc < kd || ke > kt; /* some of its forces wait */
        if (all)
            for (int k = kc; k < ke; k++)
                c->q.F[k] = q.F[k - q.foff];
        for (; cell && m < pl->ncross && imgk[m] < ke; m++)
            if (!all)
                c->q.F[imgk[m]] = q.F[imgk[m] - q.foff];
        /* the chunk's forces that other threads read are stored: say so */
#pragma omp atomic write release
        *done = ke;
        int e = w; /* the particles whose rows end in the chunk */
        while (e < i1 && start[e + 1] <= ke)
            e++;
        wall_range(law, c->wq, wstart[w], wstart[e], &c->cpw, c->dt, c->walls,
                   c->rec);
        w = e;
        if (e > s && kw) {
            /* the second range reads the earlier threads' pairs through
             * an image below kw: wait until they are stored (they come
             * in those threads' first chunks, so this rarely spins) */
            for (int u = 0; u < t; u++)
                while (1) {
                    int k;
#pragma omp atomic read acquire
                    k = c->done[DEM_RING_DONE * u];
                    if (k >= kw)
                        break;
                    spin_pause();
                }
            kw = 0;
        }
        /* finished in whole groups (but the last), so that the kicks and
         * a cell's virial run in full blocks (the list's reach counts the
         * wait) */
        const int G = DEM_RING_GROUP, f = e < i1 ? e / G * G : e;
        if (f > p) {
            moved |= particle_range(law, p, f, c->P, pl, ring, k0, mask, c->gb,
                                    c->gr, K, &V, &c->fr, c->rec,
                                    DEM_AHEAD_PARTICLES, NULL);
            p = f;
        }
        if (ke == k1)
            break;
        kc = ke;
    }
    /* all done (a later thread may wait for pairs beyond this block) */
#pragma omp atomic write release
    *done = INT_MAX;
#pragma omp barrier
    /* the waiting particles of all blocks, shared out in equal parts (in
     * a cell whole virial blocks: every range but the last is made of
     * them) */
    int nwait = 0;
    for (int r = 0; r < 2 * nt; r++)
        nwait += c->wait[2 * r + 1] - c->wait[2 * r];
    const int u0 = dem_block_aligned(nwait, t, nt, g),
              u1 = dem_block_aligned(nwait, t + 1, nt, g);
    for (int r = 0, u = 0; r < 2 * nt && u < u1; r++) {
        const int a = c->wait[2 * r], e = c->wait[2 * r + 1];
        const int lo = u0 > u ? a + (u0 - u) : a,
                  hi = u1 < u + (e - a) ? a + (u1 - u) : e;
        if (lo < hi) {
            V.end = hi;
            moved |= particle_range(law, lo, hi, c->P, pl, c->q.F, 0, -1, c->gb,
                                    c->gr, K, &V, &c->fr, c->rec,
                                    DEM_AHEAD_PARTICLES, NULL);
        }
        u += e - a;
    }
    return moved;
}
#endif

#if DEM_PASS_RECORDS && !DEM_PASS_RING
/* The wall contacts w0 <= k < w1's axial values (struct pass.A) copied
 * to H past the caches: the walls' sums read them there after the pass
 * (contact/forces.c), and the thread's next pass writes its own copy
 * without waiting for another core to drop those lines. */
DEM_INLINE void axial_handover(double *H, const double *A, int w0, int w1)
{
    int u = w0;
    if (u < w1 && ((uintptr_t)(H + u) & 15)) {
        H[u] = A[u];
        u++;
    }
    for (; u + 2 <= w1; u += 2) {
#if defined(__SSE2__)
        _mm_stream_pd(H + u, _mm_loadu_pd(A + u));
#else
        H[u] = A[u];
        H[u + 1] = A[u + 1];
#endif
    }
    if (u < w1)
        H[u] = A[u];
}

/* Thread t's share of a chained pass between walls in which each thread
 * owns its block (neighbor/blocks.h): its rows, its twins (the earlier
 * blocks' pairs with its particles as j, again, with their own history),
 * its wall contacts, then its particles, with no barrier. Every pair's
 * force and history in the list are those its rows' thread computed;
 * each sum runs over the same values in the same order as in the other
 * passes: the same bits. */
DEM_INLINE int blocks_thread(const int law, const struct contacts *c,
                             const struct kick K, int t)
{
    const struct dem_blocks *B = c->blocks;
    const struct dem_block *k = &B->t[t];
    const int h = B->half, s = k->g > k->d ? k->g : k->d,
              plane = DEM_SET_IN_PLANE(law);
    double *ghosts = c->rec + DEM_REC * (size_t)B->base;
    if (!c->blocks_fresh) {
        /* the records it reads of its own particles and of the others
         * (from the arrays: the state now), the twins' history from the
         * list, before any thread changes it */
        if (!c->rec_fresh)
            records_own(c->rec, c->P, k->a, k->b, plane);
        double *g = ghosts + DEM_REC * (size_t)h * (size_t)B->ng;
        records_fill(g + DEM_REC * (size_t)k->ga, c->P, k->a, k->d, 0, plane);
        records_fill(g + DEM_REC * (size_t)k->gg, c->P, s, k->b, 0, plane);
        const int *rpair = c->pl->rpair;
        for (int u = k->q0; u < k->q1; u++) {
            const int v = k->tw[u - k->q0], p = rpair[u];
            if (v < 0)
                continue;
#define TWIN_HISTORY_(MODEL, name, unit, swap, doc)                            \
    if (DEM_MODEL_USES(law, MODEL))                                           \
        k->name[v] = c->q.name[p];
            DEM_CONTACT_HISTORY(TWIN_HISTORY_)
#undef TWIN_HISTORY_
            k->state[v] = c->q.state[p];
        }
#pragma omp barrier
    }
    const unsigned long long t0 = pass_ticks(); /* for the balance */
    /* its rows: with j in the block, then with some j beyond it */
    struct pass q = c->q;
    pair_range(law, q, k->k0, k->kt, k->kt, &c->cp, c->dt, c->cv, c->grad,
               c->fr.m, c->rec, 0, 0);
    q.cjr = k->rj[h];
    q.roff = k->kt;
    pair_range(law, q, k->kt, k->k1, k->k1, &c->cp, c->dt, c->cv, c->grad,
               c->fr.m, c->rec, 0, 0);
    /* its twins, numbered from 0 in its own arrays */
    struct pass w = c->q;
    w.ci = k->ri2[h];
    w.cjr = k->rj2[h];
    w.roff = 0;
#define TWIN_ARRAY_(MODEL, name, unit, swap, doc) w.name = k->name;
    DEM_CONTACT_HISTORY(TWIN_ARRAY_)
#undef TWIN_ARRAY_
    w.state = k->state;
    w.F = k->F;
    w.foff = 0;
    w.M = k->M;
    /* (their i records are ghosts, from memory: asked for ahead) */
    pair_range(law, w, 0, k->nd, k->nd, &c->cp, c->dt, c->cv, c->grad, c->fr.m,
               c->rec, 0, 1);
    const int *wstart = c->pl->wcur.start;
    wall_range(law, c->wq, wstart[k->a], wstart[k->b], &c->cpw, c->dt,
               c->walls, c->rec);
    axial_handover(c->pl->wf.handed, c->wq.A, wstart[k->a], wstart[k->b]);
    const struct own O = {k->F,
                          k->M,
                          k->tw,
                          k->q0,
                          k->k0,
                          ghosts + DEM_REC * (size_t)(1 - h) * (size_t)B->ng,
                          {k->a, s},
                          {k->d, k->b},
                          {k->ga, k->gg}};
    struct virial V = {c->vir, {{0.0}}, k->b, c->fr.m};
    const int moved =
        particle_range(law, k->a, k->b, c->P, c->pl, c->q.F, 0, -1, c->gb,
                       c->gr, K, &V, &c->fr, c->rec, 0, &O);
    pass_fence(); /* the ghost records out before the pass ends */
    B->busy[8 * t] += pass_ticks() - t0;
    return moved;
}
#endif

/* The smallest takes of the shares of a pass's pairs and particles
 * (core/parallel.h): each about a microsecond's work, so that a thread
 * waits at most that long for the other's last take. Against 512 and 64
 * (session 83), 128 and 16 took 1.5-2 % off a step of cyclic3d-paper's
 * cyclic stage and 2-4.5 % at N = 3375 in the benchmark, on two L3s
 * (64 and 8, or 256 and 32, less; docs/performance-log.md, session 84). */
#define DEM_SHARE_PAIRS 128
#define DEM_SHARE_PARTICLES 16

/* Thread t's share of a pass, in one parallel region: an equal block of
 * the wall contacts, then the pairs in dynamic shares (struct
 * dem_share), then (once every contact force is stored) the particles to
 * sum, kick and move on, in shares too. Every pair and every particle is
 * computed alone, each sum in its own order, so which thread takes which
 * changes no result. With two threads on Zen 3 the shares took 0-15 %
 * (median 5 %) off the pass at N = 3375 and 20000 with the vCPUs on one
 * L3, and cost 1-3 % in most runs on two (docs/performance-log.md,
 * session 83). */
DEM_INLINE int contacts_thread(const int law, const struct contacts *c,
                               const struct kick K, int t, int nt)
{
#if DEM_PASS_RECORDS && !DEM_PASS_RING
    /* a literal: no cell here */
    if (!(law & DEM_SET_PERIODIC) && K.chain && c->blocks &&
        c->blocks->nt == nt) {
        if (t == 0) /* (a team of another size runs without) */
            *c->blocks_ran = 1;
        return blocks_thread(law, c, K, t);
    }
#endif
#if DEM_PASS_RECORDS
    /* every particle's record, or only the ghosts' when the chained pass
     * before wrote the own ones (a subdomain's ghosts: their owners
     * moved them, decomp/halo.h) */
    const int f0 = c->rec_fresh ? c->n : 0, nf = c->P->n - f0;
    if (nf > 0) {
        records_own(c->rec, c->P, f0 + dem_block(nf, t, nt),
                    f0 + dem_block(nf, t + 1, nt), DEM_SET_IN_PLANE(law));
#pragma omp barrier
    }
#endif
#if DEM_PASS_RING
    /* (the entry point runs every other pass as the records pass) */
    return ring_thread(law, c, K, t, nt);
#else
    wall_range(law, c->wq, dem_block(c->nw, t, nt), dem_block(c->nw, t + 1, nt),
               &c->cpw, c->dt, c->walls, c->rec);
    int lo, hi, end;
    struct dem_share S = {c->share, c->np, 1, DEM_SHARE_PAIRS, t, nt, 0};
    while (dem_share_take(&S, &lo, &hi, &end)) {
#if DEM_PASS_RECORDS
        /* the images' records of the chunk's pairs */
        if (law & DEM_SET_PERIODIC)
            image_records(c, lo, hi);
#endif
        pair_range(law, c->q, lo, hi, end, &c->cp, c->dt, c->cv, c->grad,
                   c->fr.m, c->rec, 0, 0);
    }
#pragma omp barrier
    /* in a cell whole virial blocks (each summed by one thread); else
     * chunks start on a cache line of the particles' arrays
     * (core/particles.h) */
    const int cell = (law & DEM_SET_PERIODIC) != 0,
              g = cell ? DEM_VIR_BLOCK : DEM_PARTICLE_LINE;
    const int chunk = cell ? DEM_VIR_BLOCK : DEM_SHARE_PARTICLES;
    unsigned long long *pc = c->share ? c->share + DEM_SHARE_LINE * nt : NULL;
    struct dem_share U = {pc, c->n, g, chunk, t, nt, 0};
    struct virial V = {c->vir, {{0.0}}, 0, c->fr.m};
    int moved = 0;
    while (dem_share_take(&U, &lo, &hi, &end)) {
        V.end = hi;
        moved |= particle_range(law, lo, hi, c->P, c->pl, c->q.F, 0, -1, c->gb,
                                c->gr, K, &V, &c->fr, c->rec, 0, NULL);
    }
    return moved;
#endif
}

/* One instance per model set and kind of step (literals), so that each
 * outlined parallel region is compiled for them alone: a chained step,
 * or one step's closing kick (K.on 1) or none (0, once at a sample's
 * start). The ring pass has only chained steps (DEM_PASS_ENTRY). */
#define CONTACTS(LAW, ON, CHAIN)                                               \
    do {                                                                       \
        _Pragma("omp parallel reduction(| : moved)")                           \
        {                                                                      \
            /* CHAIN literal inside the outlined region */                     \
            const struct kick k_ = {ON,   CHAIN, K.h,                          \
                                    K.dt, K.cut, {K.g[0], K.g[1], K.g[2]}};    \
            moved = contacts_thread(LAW, c, k_, omp_get_thread_num(),          \
                                    omp_get_num_threads());                    \
        }                                                                      \
    } while (0)

/* The pass in parts (CMakeLists.txt compiles each of its compilations
 * in DEM_PASS_PARTS translation units, to share them among a build's
 * cores): part p has the model sets whose normal law's index is p modulo
 * DEM_PASS_PARTS, in its own entry point, PART_ENTRY(p); part 0 also
 * has the pass's, which calls the part of the contacts' law. A set of
 * another part is a constant false condition, and the compiler drops its
 * code before it optimises it. */
#ifndef DEM_PASS_PARTS
#define DEM_PASS_PARTS 1
#define DEM_PASS_PART 0
#endif
#define IN_PART(SET) (((SET)&DEM_SET_NORMAL) % DEM_PASS_PARTS == DEM_PASS_PART)
#define PART_ENTRY__(entry, p) entry##_part##p
#define PART_ENTRY_(entry, p) PART_ENTRY__(entry, p)
#define PART_ENTRY(p) PART_ENTRY_(DEM_PASS_ENTRY, p)

#if DEM_PASS_RING
#define CONTACTS_KICKS(SET)                                                    \
    case SET:                                                                  \
        if (IN_PART(SET))                                                      \
            CONTACTS(SET, 1, 1);                                               \
        break;
#else
#define CONTACTS_KICKS(SET)                                                    \
    case SET:                                                                  \
        if (!IN_PART(SET))                                                     \
            break;                                                             \
        if (K.chain)                                                           \
            CONTACTS(SET, 1, 1);                                               \
        else                                                                   \
            CONTACTS(SET, K.on, 0);                                            \
        break;
#endif

/* every combination of the resistances with each normal law */
#define RESIST_COUNT_(TAG, name, doc) +1
_Static_assert(0 DEM_CONTACT_RESISTANCES(RESIST_COUNT_) == 2,
               "list every combination of the resistances below");
#undef RESIST_COUNT_

#if DEM_PASS_PARTS > 1
#define THIS_ENTRY PART_ENTRY(DEM_PASS_PART)
#else
#define THIS_ENTRY DEM_PASS_ENTRY
#endif
int THIS_ENTRY(const struct contacts *c, const struct kick K)
{
    int moved = 0;
#if DEM_PASS_RING
    /* a step that is not chained, or a list without rings, runs as in
     * the records pass: the same code, compiled once */
    if (!K.chain || !c->ring)
        return DEM_PASS_NAME(dem__pass_records)(c, K);
    for (int t = 0; t < omp_get_max_threads(); t++) /* no pairs done yet */
        c->done[DEM_RING_DONE * t] = 0;
#endif
    switch (dem_contact_set(&c->cp) | (c->periodic ? DEM_SET_PERIODIC : 0) |
            (c->plane ? DEM_SET_PLANE : 0)) {
        /* (in 2D no torsion: the config refuses it, contact/models.c) */
#define CONTACTS_OF_(TAG, name)                                                \
    CONTACTS_KICKS(DEM_NORMAL_##TAG)                                           \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_ROLLING)                         \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_TORSION)                         \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_ROLLING | DEM_SET_TORSION)       \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_PERIODIC)                        \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_ROLLING | DEM_SET_PERIODIC)      \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_TORSION | DEM_SET_PERIODIC)      \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_ROLLING | DEM_SET_TORSION |      \
                   DEM_SET_PERIODIC)                                           \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_PLANE)                           \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_ROLLING | DEM_SET_PLANE)         \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_PERIODIC | DEM_SET_PLANE)        \
    CONTACTS_KICKS(DEM_NORMAL_##TAG | DEM_SET_ROLLING | DEM_SET_PERIODIC |     \
                   DEM_SET_PLANE)
        DEM_NORMAL_MODELS(CONTACTS_OF_)
#undef CONTACTS_OF_
    }
    return moved;
}

#if DEM_PASS_PARTS > 1 && DEM_PASS_PART == 0
#if DEM_PASS_PARTS > 4
#error "contact/pass.c: the entry below calls at most 4 parts"
#endif
int PART_ENTRY(1)(const struct contacts *c, struct kick K);
#if DEM_PASS_PARTS > 2
int PART_ENTRY(2)(const struct contacts *c, struct kick K);
#endif
#if DEM_PASS_PARTS > 3
int PART_ENTRY(3)(const struct contacts *c, struct kick K);
#endif

int DEM_PASS_ENTRY(const struct contacts *c, const struct kick K)
{
    switch (c->cp.normal % DEM_PASS_PARTS) {
    case 0:
        return PART_ENTRY(0)(c, K);
    case 1:
        return PART_ENTRY(1)(c, K);
#if DEM_PASS_PARTS > 2
    case 2:
        return PART_ENTRY(2)(c, K);
#endif
#if DEM_PASS_PARTS > 3
    case 3:
        return PART_ENTRY(3)(c, K);
#endif
    }
    return 0; /* (not reached) */
}
#endif
