#include "neighbor/pairs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/particles.h"

static void list_free(struct dem_pair_list *l)
{
    free(l->i);
    free(l->j);
    free(l->xi_x);
    free(l->xi_y);
    free(l->xi_z);
    free(l->dmax);
    free(l->state);
    memset(l, 0, sizeof *l);
}

void dem_pairs_free(struct dem_pairs *pl)
{
    list_free(&pl->cur);
    list_free(&pl->old);
    free(pl->cell_head);
    free(pl->cell_next);
    memset(pl, 0, sizeof *pl);
}

static int list_reserve(struct dem_pair_list *l, int cap)
{
    if (cap <= l->cap)
        return 0;
    int c = l->cap ? l->cap : 1024;
    while (c < cap)
        c *= 2;
    void *p;
#define GROW_(field)                                                         \
    p = realloc(l->field, (size_t)c * sizeof *l->field);                     \
    if (!p)                                                                  \
        return -1;                                                           \
    l->field = p;
    GROW_(i)
    GROW_(j)
    GROW_(xi_x)
    GROW_(xi_y)
    GROW_(xi_z)
    GROW_(dmax)
    GROW_(state)
#undef GROW_
    l->cap = c;
    return 0;
}

static int cell_index(const struct dem_pairs *pl, double x, double y,
                      double z, int c[3])
{
    const double pos[3] = {x, y, z};
    for (int a = 0; a < 3; a++) {
        int k = (int)floor((pos[a] - pl->lo[a]) * pl->inv_h[a]);
        c[a] = k < 0 ? 0 : (k >= pl->nc[a] ? pl->nc[a] - 1 : k);
    }
    return (c[2] * pl->nc[1] + c[1]) * pl->nc[0] + c[0];
}

/* Sort the j of one particle's new entries (a handful) by insertion. */
static void sort_tail(int *j, int from, int to)
{
    for (int a = from + 1; a < to; a++) {
        int v = j[a], b = a - 1;
        while (b >= from && j[b] > v) {
            j[b + 1] = j[b];
            b--;
        }
        j[b + 1] = v;
    }
}

int dem_pairs_build(struct dem_pairs *pl, const struct dem_particles *p,
                    int dim, double skin, const double lo[3],
                    const double hi[3], struct dem_error *err)
{
    const int n = p->n;
    double rmax = 0.0;
    for (int i = 0; i < n; i++)
        rmax = p->r[i] > rmax ? p->r[i] : rmax;
    const double h = 2.0 * rmax + skin;
    long ncell = 1;
    for (int a = 0; a < 3; a++) {
        double span = hi[a] - lo[a];
        int k = (a == 2 && dim == 2) ? 1 : (int)(span / h);
        if (k < 1)
            k = 1;
        /* bound the grid's memory for very large, sparse boxes */
        if (k > 4096)
            k = 4096;
        pl->nc[a] = k;
        pl->lo[a] = lo[a];
        pl->inv_h[a] = (a == 2 && dim == 2) ? 0.0 : k / (span > 0 ? span : h);
        ncell *= k;
    }
    if (ncell > 64L * 1024 * 1024)
        return dem_error_set(err, DEM_ENOMEM,
                             "neighbour grid of %ld cells is too large", ncell);
    if (ncell > pl->ncell_cap) {
        free(pl->cell_head);
        pl->cell_head = malloc((size_t)ncell * sizeof *pl->cell_head);
        if (!pl->cell_head)
            return dem_error_set(err, DEM_ENOMEM, "out of memory (cells)");
        pl->ncell_cap = (int)ncell;
    }
    if (n > pl->next_cap) {
        free(pl->cell_next);
        pl->cell_next = malloc((size_t)n * sizeof *pl->cell_next);
        if (!pl->cell_next)
            return dem_error_set(err, DEM_ENOMEM, "out of memory (cells)");
        pl->next_cap = n;
    }
    for (long c = 0; c < ncell; c++)
        pl->cell_head[c] = -1;
    /* insert in reverse order so that each cell lists particles ascending */
    for (int i = n - 1; i >= 0; i--) {
        int c3[3];
        int c = cell_index(pl, p->x[i], p->y[i], p->z[i], c3);
        pl->cell_next[i] = pl->cell_head[c];
        pl->cell_head[c] = i;
    }

    /* the current list becomes the old one; build the new list */
    struct dem_pair_list tmp = pl->old;
    pl->old = pl->cur;
    pl->cur = tmp;
    struct dem_pair_list *L = &pl->cur;
    L->n = 0;
    const int zr = dim == 3 ? 1 : 0;
    for (int i = 0; i < n; i++) {
        int c3[3];
        cell_index(pl, p->x[i], p->y[i], p->z[i], c3);
        const int first = L->n;
        for (int dz = -zr; dz <= zr; dz++) {
            int cz = c3[2] + dz;
            if (cz < 0 || cz >= pl->nc[2])
                continue;
            for (int dy = -1; dy <= 1; dy++) {
                int cy = c3[1] + dy;
                if (cy < 0 || cy >= pl->nc[1])
                    continue;
                for (int dx = -1; dx <= 1; dx++) {
                    int cx = c3[0] + dx;
                    if (cx < 0 || cx >= pl->nc[0])
                        continue;
                    int c = (cz * pl->nc[1] + cy) * pl->nc[0] + cx;
                    for (int j = pl->cell_head[c]; j >= 0;
                         j = pl->cell_next[j]) {
                        if (j <= i)
                            continue;
                        double ddx = p->x[i] - p->x[j];
                        double ddy = p->y[i] - p->y[j];
                        double ddz = p->z[i] - p->z[j];
                        double cut = p->r[i] + p->r[j] + skin;
                        if (ddx * ddx + ddy * ddy + ddz * ddz >= cut * cut)
                            continue;
                        if (L->n >= L->cap && list_reserve(L, L->n + 1))
                            return dem_error_set(err, DEM_ENOMEM,
                                                 "out of memory (pair list)");
                        L->i[L->n] = i;
                        L->j[L->n] = j;
                        L->n++;
                    }
                }
            }
        }
        sort_tail(L->j, first, L->n);
    }

    /* carry the history of pairs listed before: both lists are sorted by
     * (i, j), so one merge pass finds every surviving pair */
    const struct dem_pair_list *O = &pl->old;
    int o = 0;
    for (int k = 0; k < L->n; k++) {
        const int i = L->i[k], j = L->j[k];
        while (o < O->n && (O->i[o] < i || (O->i[o] == i && O->j[o] < j)))
            o++;
        if (o < O->n && O->i[o] == i && O->j[o] == j) {
            L->xi_x[k] = O->xi_x[o];
            L->xi_y[k] = O->xi_y[o];
            L->xi_z[k] = O->xi_z[o];
            L->dmax[k] = O->dmax[o];
            L->state[k] = O->state[o];
        } else {
            L->xi_x[k] = L->xi_y[k] = L->xi_z[k] = 0.0;
            L->dmax[k] = 0.0;
            L->state[k] = 0;
        }
    }
    return DEM_OK;
}

int dem_pairs_brute(const struct dem_particles *p, int dim, double skin,
                    int **pi, int **pj)
{
    (void)dim;
    int cap = 1024, n = 0;
    int *a = malloc((size_t)cap * sizeof *a), *b = malloc((size_t)cap * sizeof *b);
    if (!a || !b)
        goto fail;
    for (int i = 0; i < p->n; i++)
        for (int j = i + 1; j < p->n; j++) {
            double dx = p->x[i] - p->x[j], dy = p->y[i] - p->y[j],
                   dz = p->z[i] - p->z[j];
            double cut = p->r[i] + p->r[j] + skin;
            if (dx * dx + dy * dy + dz * dz >= cut * cut)
                continue;
            if (n == cap) {
                cap *= 2;
                int *na = realloc(a, (size_t)cap * sizeof *a);
                if (!na)
                    goto fail;
                a = na;
                int *nb = realloc(b, (size_t)cap * sizeof *b);
                if (!nb)
                    goto fail;
                b = nb;
            }
            a[n] = i;
            b[n] = j;
            n++;
        }
    *pi = a;
    *pj = b;
    return n;
fail:
    free(a);
    free(b);
    return DEM_ENOMEM;
}
