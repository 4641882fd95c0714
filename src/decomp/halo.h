/* A sample split over MPI ranks by domain decomposition (issue 19,
 * docs/parallel.md "Domain decomposition").
 *
 * Each rank keeps the particles of its subdomain (decomp/decomp.h) and
 * copies of the particles of the others within the ghost range. A pair
 * across a cut is computed by both ranks, each for its own particle
 * (LAMMPS's "newton off"): no forces travel back, and each rank sums
 * its particles' forces alone. Per step the ranks agree on whether to
 * rebuild the lists and, without a rebuild, send the ghosts' positions,
 * velocities and spins to the ranks that hold them (messages to and
 * from the neighbours only, the counts known from the rebuild); after
 * the force pass the walls' forces are summed, so that every rank moves
 * the walls alike. That sum is one allreduce, which also carries whether
 * a chained pass's drift (core/sim.h) calls for a rebuild anywhere; only
 * a step that is not chained needs an allreduce of its own for that. At a
 * rebuild the subdomains follow the walls, particles move to their new
 * subdomain with the records of their contacts (neighbor/records.h), and
 * each rank takes its ghosts anew.
 *
 * A measured pass sums over all ranks (a pair across a cut joins the
 * sums of the rank whose particle has the smaller id), and so does
 * dem_measure over the particles, the rattlers' cascade included (a
 * round's removals reach the ghosts before the next round). A rebuild
 * re-orders each rank's own particles in cell order (the ghosts keep
 * their places). Outputs and checkpoints see the whole sample gathered
 * on rank 0 (dem_halo_collect). Not yet: a periodic cell.
 */
#ifndef DEM_DECOMP_HALO_H
#define DEM_DECOMP_HALO_H

#include "core/sim.h"

/* Split s, the same whole sample on every rank of the MPI world, over
 * the ranks: each keeps its subdomain's particles and takes its ghosts;
 * the step then exchanges what it must (s->halo). MPI must have been
 * started (dem_mpi_init). A grid whose subdomains are narrower than the
 * ghost range, a periodic cell, a sample of more than INT_MAX / 29
 * particles (74 million; the gathers' counts) or a build without MPI:
 * an error, the same on every rank, and s unchanged. Out of memory on any rank:
 * an error on every rank; s unchanged when it came before the split, else s
 * holds this rank's part (the run is to stop). */
int dem_halo_start(struct dem_sim *s, struct dem_error *err);

/* The own particles of every rank, gathered on rank 0 in the order of
 * their ids into out (initialised here, free with dem_particles_free;
 * empty on the other ranks). */
int dem_halo_gather(const struct dem_sim *s, struct dem_particles *out,
                    struct dem_error *err);

/* The whole sample, gathered on rank 0 into whole as one undivided
 * simulation at the same step, for outputs and checkpoints: particles in
 * the order of their ids, the contacts with their history, the lists
 * built anew, the contacts' forces those of the run's last pass, like
 * the particles' and the walls'.
 * Free with dem_sim_destroy. On the other ranks whole is zeroed.
 * Collective: every rank calls it; the status is rank 0's (out of memory
 * on another rank: the same status there). */
int dem_halo_collect(const struct dem_sim *s, struct dem_sim *whole,
                     struct dem_error *err);

/* Rank 0's v[0..n) on every rank (nothing without MPI). */
void dem_halo_bcast(int *v, int n);
/* (dem_mpi_any: 1 on every rank when flag is set on some rank) */

/* Wait for every rank of the MPI world (nothing without MPI or before
 * it started). */
void dem_halo_barrier(void);

/* How much room the box leaves the ranks' subdomains, as
 * dem_decomp_room: below 1 the next rebuild fails. The same on every
 * rank (every rank holds the walls); infinite for a sample not split. */
double dem_halo_room(const struct dem_sim *s);

/* Free what dem_halo_start allocated; s->halo becomes NULL. */
void dem_halo_stop(struct dem_sim *s);

#endif
