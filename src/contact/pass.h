/* The force pass (contact/pass.c): what it reads and its entry points.
 *
 * The pass is compiled up to four times (CMakeLists.txt): once as the
 * compiler likes it, which on CPUs with AVX2 or AVX-512 loads each SIMD
 * lane's particle data with hardware gathers; once with gathers switched
 * off (each lane's values from scalar loads); and twice reading the
 * pairs' particle values from records of 12 doubles (x y z r, v m, w) by
 * transposes, neither gathers nor one load per lane, on any CPU
 * (contact/pass_records.c), the second of them keeping the
 * pairs' forces of a chained step in a ring per thread in cache instead
 * of the list's array (contact/pass_ring.c). All compute the same
 * operations in the same order, so their results are the same bit for
 * bit; on some CPUs (Intel Skylake to Ice Lake with the Gather Data
 * Sampling mitigation) gathers are several times slower, on others
 * faster. contact/forces.c times them now and then and runs the fastest.
 * Each compilation is built in parts, the normal laws shared among them
 * (contact/pass.c, DEM_PASS_PARTS).
 */
#ifndef DEM_CONTACT_PASS_H
#define DEM_CONTACT_PASS_H

#include "core/sim.h"

/* Pairs the ring pass (contact/pass_ring.c) computes at a time before it
 * finishes the particles whose rows they complete: DEM_RING_CHUNK, halved
 * down to DEM_RING_CHUNK_MIN while a thread's share of the list would
 * hold fewer than DEM_RING_CHUNKS chunks (unless struct
 * dem_pairs.ring_chunk says otherwise); its rings hold at least the
 * list's reach (struct dem_pairs) plus a chunk. Against chunks of 1024
 * always, 4096 took 2-5 % off at N = 216000 (one and two threads,
 * between walls and in a cell) and changed nothing at 3375 and 20000
 * with one thread, but cost 2 % at N = 3375 with two, whose blocks then
 * held about one chunk each (Zen 4, one process by turns,
 * docs/performance-log.md, session 90). */
#define DEM_RING_CHUNK 4096
#define DEM_RING_CHUNK_MIN 1024
#define DEM_RING_CHUNKS 8

/* The arrays one pass works on, read into locals once, so that the
 * compiler need not reload an array pointer from its struct after a
 * store. */
struct pass {
    const double *x, *y, *z, *vx, *vy, *vz, *wx, *wy, *wz, *r, *m;
    const int *ci, *cj;
    const int *img; /* periodic cell: the image of j (core/cell.h) */
    const int *cjr; /* the record of j the records pass reads: cj, or in a
                       periodic cell struct dem_pairs.jrec; pair k's at
                       cjr[k - roff] */
    int roff;       /* 0, or the first pair of a block's own cjr
                       (neighbor/blocks.h) */
#define HIST_ARRAY_(MODEL, name, unit, swap, doc) double *name;
    DEM_CONTACT_HISTORY(HIST_ARRAY_) /* the history values' arrays */
#undef HIST_ARRAY_
    int *state;
    struct dem_contact_force *F; /* stored forces, entry k's at F[k - foff] */
    int foff;                    /* 0, or a ring's offset (contact/pass.c) */
    double *M; /* the resistances' torques on i, 3 per entry (only with a
                  resistance on) */
    double *A; /* wall contacts: struct dem_contact_forces.axial */
};

/* The closing half kick of a step (h = dt/2, g gravity), or none. */
struct kick {
    int on;                  /* the closing half kick */
    int chain;               /* then also the next step's half kick and drift */
    double h, dt, cut, g[3]; /* s, s, m (dem_sim_drift_cut), m/s^2 */
};

/* What one force pass reads, gathered once. */
struct contacts {
    struct pass q, wq;                 /* pairs, wall contacts */
    struct dem_contact_params cp, cpw; /* pairs, wall contacts */
    struct dem_wall walls[DEM_MAX_WALLS];
    const struct dem_particles *P;
    const struct dem_pairs *pl;
    double dt;     /* s; the springs' time step, 0 for a re-evaluation */
    double gb, gr; /* background damping, kg/s */
    int np, nw, n; /* pairs, wall contacts, particles */
    /* periodic cell (core/cell.h) */
    int periodic;   /* 1: run the pass of the set with DEM_SET_PERIODIC */
    int plane;      /* 1: run the pass of the set with DEM_SET_PLANE */
    double cv[6];   /* m; the lattice of the frame, struct dem_lattice.v:
                       the images' shifts of the pass's positions */
    struct dem_frame fr; /* the positions' frame now (core/cell.h): a
                            pair's distance is fr.m times theirs, and so
                            is a position in the virial; a drift moves
                            one by dt fr.g v; between walls the box's
                            map of the list's check, fr.b */
    /* m; image code g's shift (dem_img_shift of cv), then 0, as
     * image_records adds it to a record (contact/pass.c) */
    _Alignas(32) double shift[DEM_IMG_CODES][4];
    double grad[6]; /* 1/s; the affine velocity gradient, upper triangle */
    double *rec;    /* the records pass's particle records (contact/pass.c),
                       12 doubles per particle, 32-byte aligned */
    int rec_fresh;  /* 1: rec holds every own particle's present state
                       (the records pass of the chained step before
                       wrote them, and nothing has moved one since); the
                       ghosts' are filled at every pass */
    double *vir;    /* N m; the virial sum x (x) f + m v (x) v of each
                       block of DEM_VIR_BLOCK particles, 9 values each */
    struct dem_contact_force *ring; /* the ring pass's rings, ring_mask + 1
                                       entries per thread, or NULL */
    int ring_mask;
    int ring_chunk; /* pairs per chunk, a power of two */
    int *wait; /* the ring pass: thread t's block [wait[4t], wait[4t + 3])
                  and its particles that wait for the barrier,
                  [wait[4t], wait[4t + 1]) and [wait[4t + 2], wait[4t + 3])
                  (dem_pairs_row_block); the thread empties the second
                  range at its start, as it finishes it in stream */
    int *done; /* the ring pass: thread t's pairs done, in
                  done[DEM_RING_DONE * t] (a cache line each) */
    /* the counters of the shares of the pairs, then of the particles
     * (struct dem_share), DEM_SHARE_LINE per thread each, or NULL */
    unsigned long long *share;
    /* the records pass's chained steps with threads that own their
     * particles (neighbor/blocks.h), or NULL */
    const struct dem_blocks *blocks;
    int blocks_fresh; /* 1: the half of the ghost records it reads and
                         the twins' history hold the present state */
    int *blocks_ran;  /* set to 1 by a pass that ran with them */
};

/* A build for a CPU level (-DDEM_NATIVE=OFF) compiles the pass once
 * more for each higher level the compiler knows, x86-64-v3 (AVX2 and
 * FMA; DEM_PASS_V3) and x86-64-v4 (AVX-512; DEM_PASS_V4), and
 * contact/forces.c runs the highest this CPU has (CMakeLists.txt,
 * DEM_DISPATCH). Each of those compilations has DEM_PASS_ISA set to its
 * level, and its entry points carry it: dem__pass_records_v4. */
#define DEM_PASS_CAT_(f, l) f##_v##l
#define DEM_PASS_CAT(f, l) DEM_PASS_CAT_(f, l)
#ifdef DEM_PASS_ISA
#define DEM_PASS_NAME(f) DEM_PASS_CAT(f, DEM_PASS_ISA)
#else
#define DEM_PASS_NAME(f) f
#endif

/* One force pass: forces and history of every pair and wall contact,
 * then every particle's sums (and kicks, per K). Returns whether a
 * particle has moved further than its reach less K.cut (chained steps),
 * else 0. */
#define DEM_PASS_ENTRIES_(S)                                                   \
    int S(dem__pass_gathers)(const struct contacts *c, struct kick K);         \
    /* the same code without hardware gathers (contact/pass_loads.c) */        \
    int S(dem__pass_loads)(const struct contacts *c, struct kick K);           \
    /* the pairs' particle values from records (contact/pass_records.c) */     \
    int S(dem__pass_records)(const struct contacts *c, struct kick K);         \
    /* the records pass whose chained steps keep the pairs' forces in a        \
     * ring per thread (contact/pass_ring.c) */                                \
    int S(dem__pass_ring)(const struct contacts *c, struct kick K);
#define DEM_PASS_PLAIN_(f) f
#define DEM_PASS_V3_(f) f##_v3
#define DEM_PASS_V4_(f) f##_v4
DEM_PASS_ENTRIES_(DEM_PASS_PLAIN_)
#ifdef DEM_PASS_ISA
/* a level's compilation calls its own (the ring pass the records pass) */
DEM_PASS_ENTRIES_(DEM_PASS_NAME)
#endif
#if DEM_PASS_V3
DEM_PASS_ENTRIES_(DEM_PASS_V3_)
#endif
#if DEM_PASS_V4
DEM_PASS_ENTRIES_(DEM_PASS_V4_)
#endif

#endif
