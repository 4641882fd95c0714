/* Verlet pair list built from a linked-cell grid, with contact history
 * stored next to each pair.
 *
 * A pair (i, j), i < j in the current particle order, is listed when the
 * gap |r_i - r_j| - a_i - a_j is below the skin. The list is sorted by
 * (i, j) so that history carries over a rebuild by one merge of the old and
 * the new list, without hashing. The list is rebuilt when some particle has moved more than half
 * the skin since the last build; a wall moving does not need a rebuild
 * because wall contacts are checked every step.
 */
#ifndef DEM_NEIGHBOR_PAIRS_H
#define DEM_NEIGHBOR_PAIRS_H

#include "dembox.h"

struct dem_particles;

/* Pair entries and the history each carries. */
struct dem_pair_list {
    int n;              /* listed pairs */
    int cap;            /* allocated entries */
    int *i, *j;         /* particle indices, i < j, sorted by (i, j) */
    double *xi_x, *xi_y, *xi_z; /* m; tangential spring of the contact */
    double *dmax;       /* m; largest overlap reached (luding history) */
    unsigned char *state; /* DEM_CONTACT_* bits (contact/tangential.h) */
};

struct dem_pairs {
    struct dem_pair_list cur; /* the list the force loop uses */
    struct dem_pair_list old; /* the previous list, kept for the merge */
    /* linked-cell grid */
    int nc[3];          /* cells per axis */
    double lo[3];       /* m; lower corner of the grid */
    double inv_h[3];    /* 1/m; inverse cell edge */
    int *cell_head;     /* first particle of each cell, -1 = empty */
    int *cell_next;     /* next particle in the same cell */
    int ncell_cap;      /* allocated cells */
    int next_cap;       /* allocated length of cell_next */
};

void dem_pairs_free(struct dem_pairs *pl);

/* Build the list for particles p with the given skin (m) inside the
 * bounding box [lo, hi] (m), carrying the history of pairs that were
 * already listed. dim = 2 uses one layer of cells in z. */
int dem_pairs_build(struct dem_pairs *pl, const struct dem_particles *p,
                    int dim, double skin, const double lo[3],
                    const double hi[3], struct dem_error *err);

/* Reference: all pairs with gap below skin by brute force O(N^2); for tests.
 * Fills pi/pj (caller frees) and returns the count, or a negative status. */
int dem_pairs_brute(const struct dem_particles *p, int dim, double skin,
                    int **pi, int **pj);

#endif
