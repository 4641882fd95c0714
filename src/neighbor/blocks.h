/* Threads that own their particles: the records pass's chained steps
 * between walls (contact/pass.c) split the particles into one block per
 * thread, and each thread computes every force its block needs, sums,
 * kicks and moves it, with no barrier and without writing a cache line
 * that another thread reads in the same pass.
 *
 * Thread t takes the rows of its block [a, b) and, a second time, the
 * pairs of earlier blocks whose j is its own: the twins, which it
 * computes with its own copy of their history into its own force
 * records, in the same arithmetic, so that both copies stay the same
 * bits and its particles' sums read the same values as from the list.
 * The particles a thread reads of another block (the j of its rows
 * beyond b, the i and j of its twins) it reads from ghost records,
 * which their owner writes past the caches (non-temporal stores) right
 * after their drift, into the half of the ghost records the next pass
 * reads: a pass reads half p and writes half 1 - p, so no thread writes
 * a record another one may still read.
 *
 * The cut between the blocks is set for equal estimated work, then
 * moved by the threads' measured times (struct dem_blocks.shift).
 *
 * Why: with two threads on two L3 caches (two chiplets of an AMD EPYC), a
 * line one thread writes after the other has read it waits for the other
 * cache to drop its copy; the pairs' forces and the particles' records
 * across the cut between the blocks made two threads a third slower
 * there (docs/performance-log.md, sessions 42 to 44).
 */
#ifndef DEM_NEIGHBOR_BLOCKS_H
#define DEM_NEIGHBOR_BLOCKS_H

#include "dembox_models.h"

struct dem_pairs;
struct dem_contact_force;

/* Thread t's share. */
struct dem_block {
    int a, d, b;   /* its block [a, b); [a, d): particles with a pair as j
                      in an earlier block */
    int g;         /* [g, b): particles a later block's twins read */
    int k0, kt, k1; /* its rows' pairs [k0, k1); from kt on some j >= b */
    int nd, cap;   /* its twins: the nd pairs k < k0 with j in [a, b) */
    int q0, q1;    /* the reverse rows of [a, d), rpair[q0..q1) */
    int *tw;       /* q0 <= q < q1: twin tw[q - q0] is pair rpair[q] (if
                      rpair[q] < k0) */
    int ga, gg;     /* the ghost record (within a half) of particle a and
                       of particle max(g, d): the ranges [a, d) and
                       [max(g, d), b) in order */
    int *rj[2];     /* half p: the record of j of its pairs [kt, k1) */
    int *ri2[2], *rj2[2]; /* half p: the records of i and j of its twins */
    /* the twins' history, state, forces and resistance torques */
#define DEM_BLOCK_HIST_(MODEL, name, unit, swap, doc) double *name;
    DEM_CONTACT_HISTORY(DEM_BLOCK_HIST_)
#undef DEM_BLOCK_HIST_
    int *state;
    struct dem_contact_force *F;
    double *M;
};

struct dem_blocks {
    int nt;             /* threads (0: none set up) */
    unsigned long gen;  /* the list's generation they were set up for */
    int n;              /* particles */
    int base;           /* the first ghost record (records after base) */
    int ng;             /* ghost records per half */
    int half;           /* the half the next pass reads */
    int written;        /* the last pass was one of these and wrote them:
                           the half to read holds the present state, and
                           the twins' history that of the list */
    struct dem_block *t;
    int *gix; /* n: a particle's ghost record within a half, or -1 */
    /* The balance, kept from list to list: the cuts' shifts from equal
     * estimated work (nt - 1, in the units of that estimate), and the
     * time-stamp counter's cycles each thread's share of the passes took
     * since the set-up (busy[8 t], a cache line each), which move the
     * cuts at the next set-up. The results do not depend on the cuts. */
    double *shift;
    unsigned long long *busy;
    int shift_nt;
    long work;   /* the estimated work of all blocks at the set-up */
    long passes; /* passes run since it */
};

/* Set up (or keep) the blocks of nt threads for the list's present
 * pairs and n particles; the records array must then hold base + 2 ng
 * records (the caller reserves them). Returns 0, or -1 if out of memory
 * or if the list cannot be split so (the pass then runs without). */
int dem_blocks_setup(struct dem_blocks *B, const struct dem_pairs *pl, int n,
                     int nt);

void dem_blocks_free(struct dem_blocks *B);

#endif
