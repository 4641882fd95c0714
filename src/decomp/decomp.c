/* Domain decomposition: the grid of subdomains (decomp/decomp.h). */
#include "decomp/decomp.h"

#include <math.h>

#include "core/particles.h"

/* The narrowest subdomain of grid np over edges L. */
static double narrowest(const int np[3], const double L[3], int dim)
{
    double w = INFINITY;
    for (int a = 0; a < dim; a++)
        if (np[a] > 1 && L[a] / np[a] < w)
            w = L[a] / np[a];
    return w;
}

/* Area of the cuts of grid np over edges L: np_a - 1 faces across axis a
 * (2D: lengths). */
static double cut_area(const int np[3], const double L[3], int dim)
{
    const double z = dim == 3 ? L[2] : 1.0;
    return (np[0] - 1) * L[1] * z + (np[1] - 1) * L[0] * z +
           (np[2] - 1) * L[0] * L[1];
}

/* Of the factorisations of nranks whose subdomains are at least range
 * wide over edges L, the one with the least cut area (ties: more cuts
 * along x, fewer neighbours per subdomain) into best (all 0: none);
 * returns the widest narrowest subdomain of any factorisation. */
static double choose(int nranks, int dim, const double L[3], double range,
                     int best[3])
{
    double best_cut = INFINITY, widest = 0.0;
    best[0] = best[1] = best[2] = 0;
    for (int px = nranks; px >= 1; px--) {
        if (nranks % px)
            continue;
        for (int py = nranks / px; py >= 1; py--) {
            if ((nranks / px) % py)
                continue;
            const int pz = nranks / px / py;
            if (dim == 2 && pz != 1)
                continue;
            const int np[3] = {px, py, pz};
            const double w = narrowest(np, L, dim);
            if (w > widest)
                widest = w;
            if (w < range)
                continue;
            const double cut = cut_area(np, L, dim);
            if (cut < best_cut * (1.0 - 1e-12)) {
                best_cut = cut;
                best[0] = px;
                best[1] = py;
                best[2] = pz;
            }
        }
    }
    return widest;
}

static void edges(const double lo[3], const double hi[3], double L[3])
{
    for (int a = 0; a < 3; a++)
        L[a] = hi[a] - lo[a];
}

int dem_decomp_grid(struct dem_decomp *d, int nranks, int dim,
                    const double lo[3], const double hi[3], double range,
                    struct dem_error *err)
{
    if (nranks < 1)
        return dem_error_set(err, DEM_EUSAGE, "decomposition: %d ranks",
                             nranks);
    double L[3];
    edges(lo, hi, L);
    int best[3];
    const double widest = choose(nranks, dim, L, range, best);
    if (best[0] == 0)
        return dem_error_set(
            err, DEM_EUSAGE,
            "decomposition: %d ranks cut the box into subdomains at most "
            "%.4g m wide, narrower than the ghost range %.4g m (largest "
            "diameter plus skin); use fewer ranks",
            nranks, widest, range);
    d->nranks = nranks;
    d->dim = dim;
    for (int a = 0; a < 3; a++) {
        d->np[a] = best[a];
        d->lo[a] = lo[a];
        d->hi[a] = hi[a];
    }
    d->range = range;
    return DEM_OK;
}

int dem_decomp_resize(struct dem_decomp *d, const double lo[3],
                      const double hi[3], struct dem_error *err)
{
    double L[3];
    edges(lo, hi, L);
    int best[3];
    const double widest = choose(d->nranks, d->dim, L, d->range, best);
    if (best[0] == 0)
        return dem_error_set(
            err, DEM_EUSAGE,
            "decomposition: the box has shrunk so that %d ranks cut it "
            "into subdomains at most %.4g m wide, narrower than the ghost "
            "range %.4g m; use fewer ranks",
            d->nranks, widest, d->range);
    /* another grid when the box's shape calls for it: the present one
     * no longer fits, or the best cuts 10 % less (no flip-flopping
     * between two grids of nearly the same cut) */
    const double now = narrowest(d->np, L, d->dim) >= d->range
                           ? cut_area(d->np, L, d->dim)
                           : INFINITY;
    const int regrid = cut_area(best, L, d->dim) < DEM_DECOMP_REGRID * now;
    for (int a = 0; a < 3; a++) {
        if (regrid)
            d->np[a] = best[a];
        d->lo[a] = lo[a];
        d->hi[a] = hi[a];
    }
    return regrid;
}

double dem_decomp_room(const struct dem_decomp *d, const double lo[3],
                       const double hi[3])
{
    double L[3];
    int best[3];
    edges(lo, hi, L);
    return choose(d->nranks, d->dim, L, d->range, best) / d->range;
}

/* Index along axis a of the slab holding coordinate x. */
static int slab(const struct dem_decomp *d, int a, double x)
{
    const double L = d->hi[a] - d->lo[a];
    if (d->np[a] == 1 || !(L > 0.0))
        return 0;
    /* clamped as a double: a position far outside (or NaN, in a
     * blow-up the run has still to diagnose) converts to no int */
    const double u = floor((x - d->lo[a]) / L * d->np[a]);
    return !(u >= 0.0) ? 0 : u >= d->np[a] ? d->np[a] - 1 : (int)u;
}

int dem_decomp_owner(const struct dem_decomp *d, const double x[3])
{
    return slab(d, 0, x[0]) +
           d->np[0] * (slab(d, 1, x[1]) + d->np[1] * slab(d, 2, x[2]));
}

void dem_decomp_bounds(const struct dem_decomp *d, int rank, double lo[3],
                       double hi[3])
{
    const int c[3] = {rank % d->np[0], (rank / d->np[0]) % d->np[1],
                      rank / (d->np[0] * d->np[1])};
    for (int a = 0; a < 3; a++) {
        const double L = d->hi[a] - d->lo[a];
        /* the same arithmetic as slab(): a point is inside exactly the
         * bounds of the slab it is assigned to (up to the rounding of
         * the division, covered by the ghost range) */
        lo[a] = c[a] == 0 ? -INFINITY : d->lo[a] + L * c[a] / d->np[a];
        hi[a] = c[a] == d->np[a] - 1 ? INFINITY
                                     : d->lo[a] + L * (c[a] + 1) / d->np[a];
    }
}

/* Squared distance between the boxes [alo, ahi] and [blo, bhi] (a point:
 * alo = ahi). */
static double gap2(const double alo[3], const double ahi[3],
                   const double blo[3], const double bhi[3])
{
    double s = 0.0;
    for (int k = 0; k < 3; k++) {
        const double g = blo[k] > ahi[k]   ? blo[k] - ahi[k]
                         : alo[k] > bhi[k] ? alo[k] - bhi[k]
                                           : 0.0;
        s += g * g;
    }
    return s;
}

int dem_decomp_is_ghost(const struct dem_decomp *d, int rank, const double x[3])
{
    double lo[3], hi[3];
    dem_decomp_bounds(d, rank, lo, hi);
    return gap2(x, x, lo, hi) < d->range * d->range;
}

int dem_decomp_near(const struct dem_decomp *d, int a, int b)
{
    double alo[3], ahi[3], blo[3], bhi[3];
    dem_decomp_bounds(d, a, alo, ahi);
    dem_decomp_bounds(d, b, blo, bhi);
    /* no point of a is closer to b than a's box is (a point of a lies in
     * a's bounds up to the rounding that the slack covers) */
    const double r = d->range * (1.0 + 1e-9);
    return gap2(alo, ahi, blo, bhi) < r * r;
}

int dem_decomp_at_face(const struct dem_decomp *d, int rank, const double x[3])
{
    double lo[3], hi[3];
    dem_decomp_bounds(d, rank, lo, hi);
    /* a point of another subdomain is at least as far from x as the
     * nearest face of this one (an infinite face: no other side) */
    for (int a = 0; a < 3; a++)
        if (x[a] - lo[a] < d->range || hi[a] - x[a] < d->range)
            return 1;
    return 0;
}

void dem_decomp_select(const struct dem_decomp *d, int rank,
                       const struct dem_particles *p, int *list, int *nown,
                       int *nghost)
{
    int m = 0;
    for (int i = 0; i < p->n; i++) {
        const double x[3] = {p->x[i], p->y[i], p->z[i]};
        if (dem_decomp_owner(d, x) == rank)
            list[m++] = i;
    }
    *nown = m;
    for (int i = 0; i < p->n; i++) {
        const double x[3] = {p->x[i], p->y[i], p->z[i]};
        if (dem_decomp_owner(d, x) != rank && dem_decomp_is_ghost(d, rank, x))
            list[m++] = i;
    }
    *nghost = m - *nown;
}
