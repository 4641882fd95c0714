/* Verlet lists of particle pairs and particle-wall contacts, built from a
 * cell grid, each entry carrying its contact history.
 *
 * A pair (i, j), i < j, is listed when the gap |r_i - r_j| - a_i - a_j is
 * below the sum of the two particles' reaches (struct dem_particles.reach,
 * each at most half the skin); a particle-wall contact (i, w) when the
 * particle's gap to the wall plane is below its reach plus half the skin.
 * Both lists are sorted by i (then j or w) and indexed by i (CSR), so that
 * the history of a contact is found again after a rebuild by a short scan
 * of its particle's old row, without hashing, also when the particles
 * have been re-ordered in memory.
 *
 * The lists are rebuilt when some particle has moved further than its
 * reach or some wall more than half the skin since the last build (both
 * measured in the frame of the box or cell, core/sim.h), so no contact
 * can be missed in between. At a rebuild the particles may be
 * re-ordered in cell order (see dem_pairs_build) so that neighbours are
 * close in memory.
 *
 * Each entry also has room for the force of the last pass (the force on
 * i and n x f_t), at the same index. A particle sums the forces of its
 * pairs as i from its row and those of its pairs as j through the reverse
 * rows (rstart, rpair); every sum runs in a fixed order whatever the
 * number of threads.
 */
#ifndef DEM_NEIGHBOR_PAIRS_H
#define DEM_NEIGHBOR_PAIRS_H

#include <limits.h>

#include "core/cell.h"
#include "dembox.h"
#include "neighbor/blocks.h"

struct dem_particles;

/* Contact entries and the history each carries. */
struct dem_contact_list {
    int n;   /* entries */
    int cap; /* allocated entries */
    int *i;  /* particle */
    int *j;  /* partner: particle (> i) or wall index */
    int *img; /* in a periodic cell: the image of j the pair touches
                 (dem_img_code, core/cell.h); not kept otherwise */
#define DEM_LIST_HISTORY_(MODEL, name, unit, swap, doc) double *name;
    DEM_CONTACT_HISTORY(DEM_LIST_HISTORY_) /* the history values
                                              (dembox_models.h) */
#undef DEM_LIST_HISTORY_
    int *state; /* DEM_CONTACT_* bits (contact/state.h); an int, not a
                   byte, so that the force loop vectorises with 256-bit
                   vectors too (gcc 12 does not mix byte masks with
                   double lanes there) */
    int *start; /* n_particles + 1 row offsets by i */
    int start_cap;
};

/* Force of one entry in the last force pass: the six numbers of a
 * contact together in one 48-byte record (the array aligned to a cache
 * line). The force pass stores a round's records from its SIMD lanes by
 * transposes (contact/pass.c, forces_from_lanes); the sums over a
 * particle's pairs as j read them through an index. Records of 64 bytes,
 * a cache line each with two pads, were a quarter more to write and read
 * back at every step (docs/performance-log.md, session 69). */
struct dem_contact_force {
    double f[3]; /* N; force on i (on j it is the opposite) */
    double c[3]; /* N; n x f_t: torque on i is -a_i c, on j -a_j c */
};
#define DEM_CONTACT_FORCE_ALIGN 64

/* Forces of a list's entries (same index as the list). */
struct dem_contact_forces {
    int cap;
    struct dem_contact_force *v;
    double *m; /* N m; 3 per entry: the torque of the rolling and torsion
                  resistances on i (on j the opposite); written and read
                  only with a resistance on (struct dem_pairs.torques) */
    double *axial; /* N; wall contacts only (NULL for pairs): the force on
                      the wall along its axis, outward positive, which the
                      walls' sums read instead of the records (a record's
                      line per contact would pass between threads) */
    double *handed; /* N; wall contacts only: a copy of axial that the
                       records pass with threads owning their blocks
                       writes past the caches for the walls' sums
                       (neighbor/blocks.h) */
};

/* A thread's buffer of rows (struct dem_pairs.rowbuf). */
struct dem_row_buf {
    int *v;
    size_t cap; /* ints allocated in v */
};

/* The most particles (owned and ghosts) a periodic cell's list takes:
 * its rows hold a partner j as j << 6 | image code in an int. */
#define DEM_PAIRS_PERIODIC_MAX ((1 << 25) - 1)
/* The most pairs a list takes: the kernels index the torque arrays by
 * 3 k in an int. */
#define DEM_PAIRS_MAX (INT_MAX / 3)

/* The walls a list's wall contacts name (j), DEM_MAX_WALLS of core/sim.h. */
#define DEM_PAIRS_WALLS 6

struct dem_pairs {
    struct dem_contact_list cur;  /* particle pairs the force loop uses */
    struct dem_contact_list old;  /* the previous pairs, for the history */
    struct dem_contact_list wcur; /* particle-wall contacts (j = wall) */
    struct dem_contact_list wold; /* the previous ones */
    struct dem_contact_forces f;  /* forces of cur, pair k at k */
    struct dem_contact_forces wf; /* forces of wcur, entry k at k */
    int *rstart;                  /* n_particles + 1: rows of rpair by j */
    int *rpair; /* cur.n: the pairs grouped by their j particle: particle
                   j is j of rpair[rstart[j]..rstart[j+1]), first those
                   with j itself, then from rimg[j] on (periodic cell)
                   those with an image of j, each part in list order */
    int *rimg;  /* n_particles + 1: see rpair */
    int rpair_cap;
    int *wall_order; /* wcur.n: the wall contacts grouped by wall, each
                        group in list order: wall w's are wall_order[
                        wall_start[w] .. wall_start[w + 1]) (the walls'
                        sums, contact/forces.c) */
    int wall_order_cap;
    int wall_start[DEM_PAIRS_WALLS + 1];
    int reach;  /* the largest span of pairs from a particle's first pair
                   as j (with j itself, not an image) to the end of the
                   rows of its group (DEM_RING_GROUP; the ring
                   pass's window, contact/pass.c) */
    int *cross; /* periodic cell: the pairs with an image of j other
                   than j itself, grouped by the image, each group in
                   list order: image g's are cross[cross_start[g] ..
                   cross_start[g + 1]) */
    int ncross, cross_cap;
    int cross_start[DEM_IMG_CODES + 1];
    int *imgk; /* periodic cell: the same ncross pairs in list order */
    int *jrec; /* periodic cell, one per pair: the record the records pass
                  reads for j (contact/pass.c), j itself or, for the m-th
                  pair of imgk, n + m: an image record, j's record with
                  its position shifted to the image */
    /* cell grid (periodic: over the fractional coordinates) */
    int nc[3];       /* cells per axis */
    double lo[3];    /* m; lower corner */
    double inv_h[3]; /* 1/m; inverse cell edge */
    int *cell_start; /* ncell + 1 offsets into cell_list */
    int *cell_list;  /* particles sorted by cell */
    int *cell_of;    /* cell of each particle */
    int periodic;    /* 1: the grid is the periodic cell's */
    struct dem_lattice lat; /* that cell at the build */
    int ncell_cap;
    struct dem_row_buf *rowbuf; /* one per thread of a build: the rows
                                   the thread found (build_pairs), kept
                                   so that no build allocates and first
                                   touches them again */
    int rowbuf_n;               /* the most threads a build has had */
    /* re-ordering */
    int *old_of;         /* old index of each particle after a re-order */
    double *scratch;     /* one particle array of doubles */
    int nalloc;          /* allocated length of the per-particle arrays */
    double wall_pos0[6]; /* m; wall positions at the last build */
    /* what the contact models in force keep (set by the force pass's
     * setup, contact/forces.c) */
    int nghost; /* domain decomposition (src/decomp): the last nghost
                   particles are ghosts, copies of neighbouring subdomains'
                   particles, the others this subdomain's own; a build
                   lists no pair of two ghosts and no wall contact of a
                   ghost. 0: no ghosts */
    unsigned hist; /* bit k: the k-th value of DEM_CONTACT_HISTORY is
                      kept (carried at a rebuild); the others are never
                      read or written */
    int torques;   /* 1: the entries' resistance torques (forces.m) */
    double *rec;   /* rec_cap records of DEM_REC doubles, 64-byte aligned:
                      the force pass's copy of the particles
                      (contact/pass.c), x y z r | vx vy vz m | wx wy wz 0,
                      then in a periodic cell the image records (jrec) */
    int rec_cap;
    int rec_fresh;   /* set by dem_sim_step for its pass: no own particle
                        has moved since the last pass, which was chained
                        (ghosts may have: their records are filled at
                        every pass) */
    int rec_written; /* the last pass was chained and wrote rec */
    struct dem_contact_force *ring; /* the ring pass's force records, one
                                       ring per thread (contact/forces.c) */
    size_t ring_cap;                /* entries allocated in ring */
    int *ring_wait;   /* 4 per thread: the ring pass's block and waiting
                         particles (dem_pairs_row_block) */
    int *ring_done;   /* DEM_RING_DONE per thread, 64-byte aligned: in
                         the first, the pairs a ring pass's thread has
                         done (contact/pass.c) */
    int ring_threads; /* threads ring_wait has room for */
    unsigned long long *share; /* 2 DEM_SHARE_LINE per thread, 64-byte
                                  aligned: the passes' shares
                                  (struct contacts.share) */
    int share_threads;         /* threads share has room for */
    int ring_chunk;    /* the ring pass's pairs per chunk, a power of two;
                          0: as DEM_RING_CHUNK says (contact/pass.h;
                          the tests set fewer) */
    unsigned long gen; /* the list's generation: one more at each build
                          or restore (dem_pairs_reverse) */
    struct dem_blocks blocks; /* the threads' own blocks of the records
                                 pass (neighbor/blocks.h) */
};

/* ints per thread in struct dem_pairs.ring_done: one cache line */
#define DEM_RING_DONE 16

/* The ring pass finishes particles in whole groups of this many, from a
 * multiple of it (but at the end of a thread's particles): in a periodic
 * cell so that the virial runs in full SIMD blocks, and between walls so
 * that the kicks and drifts do (single particles there took 4-5 % more
 * time at N = 3375 and 1-3 % at 216000 on Zen 4, one process by turns,
 * docs/performance-log.md, session 90). A particle's span in the list's
 * reach ends with its group's rows. */
#define DEM_RING_GROUP 32

/* Doubles per particle record (struct dem_pairs.rec). */
#define DEM_REC 12

struct dem_wall;

void dem_pairs_free(struct dem_pairs *pl);

/* Build both lists for particles p with the given skin (m; the cells'
 * size and the walls' half of it; every reach at most half of it), grid over
 * [lo, hi] (m), walls w[0..nwall), carrying the history of contacts that
 * were listed before. With reorder set, the particles are first sorted in
 * cell order (p's arrays are permuted; p->id keeps the original index).
 * dim = 2 uses one layer of cells in z. With a periodic lattice (else
 * NULL) the grid covers the cell instead of [lo, hi], the particles must
 * be inside it, and pairs are found across its faces, each with the
 * image of j it touches; the cell must be wider than two interaction
 * ranges (else DEM_ERANGE). With ghosts (pl->nghost) only the own
 * particles are re-ordered (among themselves); the ghosts keep their
 * places. */
int dem_pairs_build(struct dem_pairs *pl, struct dem_particles *p, int dim,
                    double skin, const double lo[3], const double hi[3],
                    const struct dem_wall *w, int nwall,
                    const struct dem_lattice *cell, int reorder,
                    struct dem_error *err);

/* Allocate room for n particles (arrays of at least cap doubles for the
 * re-ordering), npair pairs and nwc wall contacts, as a build would, so
 * that a checkpoint can fill cur, wcur, f, wf, rstart and rpair directly.
 * The lists keep their counts; a later build works as usual. */
int dem_pairs_reserve(struct dem_pairs *pl, int n, int cap, int npair, int nwc);

/* Room for nrec particle records (struct dem_pairs.rec); growing them
 * loses what they held (rec_written and blocks.written are then 0).
 * 0 on success. */
int dem_pairs_records_reserve(struct dem_pairs *pl, int nrec);

/* The list of pairs through an image (cross, grouped by the image; imgk,
 * in list order) and each pair's record of j (jrec, with room in rec for
 * the image records after those of the n particles), from cur's images;
 * none unless the grid is a periodic cell's. A build makes them; a
 * checkpoint that fills cur calls it. 0 or -1 (out of memory). */
int dem_pairs_cross(struct dem_pairs *pl, int n);

/* The reverse rows of particles 0 <= i < n (rstart, rpair, rimg) and
 * the list's reach (struct dem_pairs) from cur and, in a periodic cell
 * (pl->periodic), its images; and the wall contacts of wcur by wall
 * (wall_order). A build makes them; a checkpoint that fills the lists
 * calls it. 0 or -1 (out of memory). */
int dem_pairs_reverse(struct dem_pairs *pl, int n);

/* The first index i < n of the ascending a with a[i] >= k (n if none). */
static inline int dem_first_at_least(const int *a, int n, int k)
{
    int lo = 0, hi = n;
    while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        if (a[mid] < k)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* A thread's work on a pair and on a particle (its sums, kicks and
 * drift: about 1.5 pairs, what the profiles give at N = 3375 and 216000,
 * docs/performance.md), in the units that split the rows into blocks. */
#define DEM_WORK_PAIR 2
#define DEM_WORK_PARTICLE 3

/* The first particle x whose rows start at work DEM_WORK_PAIR start[x] +
 * DEM_WORK_PARTICLE x of at least target (n if none), start being the
 * rows' offsets of particles 0 <= i < n. */
int dem_pairs_cut(const int *start, int n, long target);

/* Block t of nt of the rows of particles 0 <= i < n, of about equal
 * work (pairs and particles) and cut at a multiple of g: [w[0], w[3]);
 * and its particles that have a pair as j in an earlier block: those in
 * [w[0], w[1]) and in [w[2], w[3]), each range cut at a multiple of g
 * too (the last block ends at n). Every other particle of the block has
 * all its pairs, as i and as j, in the block's rows. For the ring pass
 * (contact/pass.c), whose threads finish a particle as soon as its pairs
 * are done: the first range waits for a barrier (it needs the earlier
 * block's last pairs); the second, a periodic cell's last particles,
 * needs only pairs through an image of the earlier blocks, all below
 * *kw (0 if none), which their threads compute first. *kt: the block's
 * first pair with j itself (not an image) that a first range of a later
 * block reads (start[w[3]] if none): every pair of the block from
 * start[w[1]] up to it joins two particles of [w[1], w[3]), or is
 * through an image. */
void dem_pairs_row_block(const struct dem_pairs *pl, int n, int t, int nt,
                         int g, int w[4], int *kt, int *kw);

/* Reference: all pairs with gap below skin plus, with reach (else NULL),
 * the sum of the two reaches, by brute force O(N^2); for tests. Fills pi/pj
 * (caller frees) and returns the count, or a negative status. With a periodic
 * lattice (else NULL) every image of j is tried, and pimg (when not NULL;
 * caller frees) gets the image of each pair. */
int dem_pairs_brute(const struct dem_particles *p, int dim, double skin,
                    const double *reach, const struct dem_lattice *cell,
                    int **pi, int **pj, int **pimg);

#endif
