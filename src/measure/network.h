/* The contact network of the current state: every closed contact with
 * its partners, contact point, normal, overlap and force (for the
 * contacts_*.vtu snapshots and contacts_final.csv, docs/outputs.md). */
#ifndef DEM_MEASURE_NETWORK_H
#define DEM_MEASURE_NETWORK_H

#include <stdio.h>

#include "contact/history.h"
#include "core/sim.h"

struct dem_network_contact {
    int i;        /* particle index (engine order; p->id[i] its id) */
    int j;        /* partner: particle index, or -1 - w for wall w */
    double x[3];  /* m; contact point: the middle of the overlap; on a
                     wall, the point on its plane */
    double n[3];  /* unit normal, from the partner to i */
    double delta; /* m; overlap */
    double fn;    /* N; normal force on i (> 0 repulsive) */
    double ft[3]; /* N; tangential force on i */
    int sliding;  /* 1: at the Coulomb limit */
    int image;    /* periodic cell: 1 when i touches an image of j */
    double b[3];  /* m; branch vector from the partner's centre (the
                     image's) to i's; a wall: from the contact point */
    double h[DEM_NHISTORY]; /* the history values (DEM_CONTACT_HISTORY's
                               lines) of the models in force (hist) */
};

struct dem_network {
    int n; /* closed contacts: the pairs first, then the wall contacts */
    int npair;
    unsigned hist; /* bit k: the contacts' h[k] is kept by the models in
                      force (struct dem_pairs.hist); the others are 0 */
    struct dem_network_contact *c;
};

/* The closed contacts of s from its stored contact forces (the last force
 * pass, at the current positions when called at a sample). */
int dem_network_build(const struct dem_sim *s, struct dem_network *net,
                      struct dem_error *err);
void dem_network_free(struct dem_network *net);

/* The columns of the history values net keeps, each as sep then its name
 * (dem_history_name), and a contact's values, each as sep then fmt: the
 * last columns of every contact output. */
void dem_network_history_header(FILE *f, const struct dem_network *net,
                                 const char *sep);
void dem_network_history_row(FILE *f, const struct dem_network *net,
                             const struct dem_network_contact *c,
                             const char *sep, const char *fmt);

#endif
