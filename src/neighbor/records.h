/* Contact histories keyed by particle ids.
 *
 * A rebuild finds a contact's history again through the map from new to
 * old particle indices (neighbor/pairs.h). Where particles change places
 * beyond that map, as when they move between the subdomains of a domain
 * decomposition (src/decomp), each contact's history travels as records:
 * one contact seen from one of its particles ("self" as i). A pair gives
 * a record for each of its particles, the second with its values times
 * their swap factors (DEM_CONTACT_HISTORY), so that the record of either
 * particle restores the pair whatever the order of the two in memory; a
 * wall contact gives one. A record also carries the contact's forces of
 * the last pass, likewise as seen from self.
 */
#ifndef DEM_NEIGHBOR_RECORDS_H
#define DEM_NEIGHBOR_RECORDS_H

#include "contact/history.h"
#include "neighbor/pairs.h"

struct dem_particles;

struct dem_contact_record {
    int self;               /* id of the particle */
    int wall;               /* 1: other is a wall index, 0: a particle's id */
    int other;              /* the partner */
    int state;              /* DEM_CONTACT_* bits */
    double h[DEM_NHISTORY]; /* the history values as seen from self (the
                               values pl->hist does not keep are 0) */
    /* the contact's forces in the last force pass, as seen from self
     * (struct dem_contact_force; outputs of a gathered sample show them) */
    double f[3]; /* N; the force on self */
    double c[3]; /* N; n x f_t, the same from either particle */
    double m[3]; /* N m; the resistance torque on self (0 without) */
};

struct dem_records {
    int n, cap;
    struct dem_contact_record *v;
    /* after dem_records_sort, the records in order: v[order[q]] for
     * 0 <= q < n, those of self = lo + b from q = first[b] to first[b +
     * 1] (0 <= b < nfirst); NULL (nfirst 0): not sorted, or no records */
    int *order, *first;
    int lo, nfirst;
};

/* Append the records of every contact of pl's current lists that has a
 * state (an active contact) and whose particle is among the first nself
 * of p (a pair: a record for each of its particles among them). 0, or
 * DEM_ENOMEM. */
int dem_records_export(struct dem_records *r, const struct dem_pairs *pl,
                       const struct dem_particles *p, int nself);
/* The same for the particles among the first nself whose mark is set
 * (mark NULL: all of them). */
int dem_records_export_marked(struct dem_records *r,
                              const struct dem_pairs *pl,
                              const struct dem_particles *p, int nself,
                              const unsigned char *mark);
/* Order by (self, wall, other), as dem_records_of and
 * dem_records_import need: an index (order, first); the records stay
 * where they are. Appending records afterwards calls for another sort.
 * 0, or DEM_ENOMEM (then no index). */
int dem_records_sort(struct dem_records *r);
/* The records of particle id after dem_records_sort: v[order[q]] for
 * *a <= q < *b, by (wall, other). */
void dem_records_of(const struct dem_records *r, int id, int *a, int *b);
/* Every entry of pl's current lists takes the history of its record in r
 * (sorted): a pair (i, j) that of self = id i as it is, or else that of
 * self = id j times the swap factors; none (all zero) without a record. */
void dem_records_import(const struct dem_records *r, struct dem_pairs *pl,
                        const struct dem_particles *p);
void dem_records_free(struct dem_records *r);

#endif
