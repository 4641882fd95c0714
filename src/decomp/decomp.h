/* Domain decomposition: the box split into a grid of subdomains, one per
 * rank (issue 19; docs/parallel.md, "Domain decomposition").
 *
 * The grid divides the box between the walls into np[0] x np[1] x np[2]
 * equal subdomains (np[2] = 1 in 2D); as the walls move, the same
 * fractions of the box are taken again at every neighbour-list build, so
 * the subdomains deform with the sample, and when the box's shape has
 * changed enough another grid is chosen (dem_decomp_resize). A
 * particle belongs to the subdomain its centre is in (beyond a wall: the
 * subdomain at that wall). A subdomain's ghosts are the particles of the
 * others whose centres lie within the ghost range of it: the largest
 * diameter plus the neighbour skin, so that every pair a build lists
 * with an own particle has its partner at hand, until the next build.
 *
 * Rank r is subdomain (ix, iy, iz) with r = ix + np[0] (iy + np[1] iz).
 */
#ifndef DEM_DECOMP_DECOMP_H
#define DEM_DECOMP_DECOMP_H

#include "dembox.h"

struct dem_particles;

struct dem_decomp {
    int nranks;
    int dim;
    int np[3];           /* subdomains per axis */
    double lo[3], hi[3]; /* m; the box split */
    double range;        /* m; ghost range */
};

/* Choose the grid for nranks subdomains of the box [lo, hi] (dim 2 or
 * 3): of the factorisations np[0] np[1] np[2] = nranks, the one whose
 * cuts have the least area (fewest ghosts), ties to more cuts along x
 * (fewer neighbours).
 * A subdomain narrower than the ghost range along some axis in every
 * factorisation is refused (DEM_EUSAGE, naming the rank count, the
 * narrowest width and the range). */
int dem_decomp_grid(struct dem_decomp *d, int nranks, int dim,
                    const double lo[3], const double hi[3], double range,
                    struct dem_error *err);

/* A grid whose cut area is below this share of the present one's
 * replaces it at a resize. */
#define DEM_DECOMP_REGRID 0.9

/* The grid over a new box (the walls have moved): the same one, unless
 * it no longer fits (a subdomain narrower than the ghost range) or the
 * box's shape has changed so that another factorisation cuts less than
 * DEM_DECOMP_REGRID of its area; then that one (the particles move to
 * their new subdomains at the rebuild that follows). Returns 1 when the
 * grid changed, 0 when not, or DEM_EUSAGE when no grid fits the box. */
int dem_decomp_resize(struct dem_decomp *d, const double lo[3],
                      const double hi[3], struct dem_error *err);

/* The widest subdomains any grid of d's ranks cuts the box [lo, hi]
 * into, over the ghost range: below 1 no grid fits it (a rebuild would
 * fail). */
double dem_decomp_room(const struct dem_decomp *d, const double lo[3],
                       const double hi[3]);

/* The rank whose subdomain holds the point. */
int dem_decomp_owner(const struct dem_decomp *d, const double x[3]);

/* Bounds of rank's subdomain; a face on the box's boundary is at
 * -/+ infinity (particles poking through a wall stay with it). */
void dem_decomp_bounds(const struct dem_decomp *d, int rank, double lo[3],
                       double hi[3]);

/* Whether a point of another subdomain is a ghost of rank's: within the
 * ghost range of its bounds. */
int dem_decomp_is_ghost(const struct dem_decomp *d, int rank,
                        const double x[3]);

/* Whether the subdomains of ranks a and b come within the ghost range
 * of each other: only then can one take particles of the other as
 * ghosts (a is not b). */
int dem_decomp_near(const struct dem_decomp *d, int a, int b);

/* Whether a point of rank's subdomain lies within the ghost range of
 * one of its faces that is not on the box's boundary: only then can it
 * be a ghost of another subdomain. */
int dem_decomp_at_face(const struct dem_decomp *d, int rank,
                       const double x[3]);

/* Indices into p of rank's own particles (in p's order), then of its
 * ghosts (in p's order): written to list (room for p->n), their numbers
 * to *nown and *nghost. */
void dem_decomp_select(const struct dem_decomp *d, int rank,
                       const struct dem_particles *p, int *list, int *nown,
                       int *nghost);

#endif
