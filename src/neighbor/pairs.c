#include "neighbor/pairs.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/cell.h"
#include "core/parallel.h"
#include "core/particles.h"
#include "wall/wall.h"

static void list_free(struct dem_contact_list *l)
{
    free(l->i);
    free(l->j);
    free(l->img);
#define HIST_FREE_(MODEL, name, unit, swap, doc) free(l->name);
    DEM_CONTACT_HISTORY(HIST_FREE_)
#undef HIST_FREE_
    free(l->state);
    free(l->start);
    memset(l, 0, sizeof *l);
}

static void forces_free(struct dem_contact_forces *f)
{
    free(f->v);
    free(f->m);
    free(f->axial);
    free(f->handed);
    memset(f, 0, sizeof *f);
}

void dem_pairs_free(struct dem_pairs *pl)
{
    list_free(&pl->cur);
    list_free(&pl->old);
    list_free(&pl->wcur);
    list_free(&pl->wold);
    forces_free(&pl->f);
    forces_free(&pl->wf);
    free(pl->rstart);
    free(pl->rimg);
    free(pl->rpair);
    free(pl->wall_order);
    free(pl->cross);
    free(pl->imgk);
    free(pl->jrec);
    free(pl->cell_start);
    free(pl->cell_list);
    free(pl->cell_of);
    for (int t = 0; t < pl->rowbuf_n; t++)
        free(pl->rowbuf[t].v);
    free(pl->rowbuf);
    free(pl->old_of);
    dem_particles_array_free(pl->scratch);
    free(pl->rec);
    free(pl->ring);
    free(pl->ring_wait);
    free(pl->ring_done);
    free(pl->share);
    dem_blocks_free(&pl->blocks);
    memset(pl, 0, sizeof *pl);
}

/* Grow an array to c elements; 0 on success. */
#define GROW(ptr, c)                                                           \
    (((ptr) = grow_((ptr), (size_t)(c) * sizeof *(ptr))) == NULL)

static void *grow_(void *p, size_t bytes)
{
    void *q = realloc(p, bytes ? bytes : 1);
    if (!q)
        free(p);
    return q;
}

static int list_reserve(struct dem_contact_list *l, int cap)
{
    if (cap <= l->cap)
        return 0;
    int c = l->cap ? l->cap : 1024;
    while (c < cap)
        c += c / 2;
    if (GROW(l->i, c) || GROW(l->j, c) || GROW(l->img, c) || GROW(l->state, c))
        return -1;
#define HIST_GROW_(MODEL, name, unit, swap, doc)                               \
    if (GROW(l->name, c))                                                      \
        return -1;
    DEM_CONTACT_HISTORY(HIST_GROW_)
#undef HIST_GROW_
    l->cap = c;
    return 0;
}

/* The force records at cap entries, on a cache-line boundary (see
 * struct dem_contact_force), the first have entries kept. */
static int grow_records(struct dem_contact_force **v, int have, int cap)
{
    void *q = NULL;
    if (posix_memalign(&q, DEM_CONTACT_FORCE_ALIGN, (size_t)cap * sizeof **v) !=
        0)
        return -1;
    if (*v && have > 0)
        memcpy(q, *v, (size_t)have * sizeof **v);
    free(*v);
    *v = q;
    return 0;
}

/* axial: the wall contacts' (struct dem_contact_forces.axial) */
static int forces_reserve(struct dem_contact_forces *f, int cap, int axial)
{
    if (cap <= f->cap)
        return 0;
    if (grow_records(&f->v, f->cap, cap) || GROW(f->m, 3 * (size_t)cap) ||
        (axial && (GROW(f->axial, cap) || GROW(f->handed, cap))))
        return -1;
    f->cap = cap;
    return 0;
}

/* Stored forces of n entries set to zero (the force loop writes only
 * contacts that are closed or have just opened), by the threads in
 * blocks of entries in order, so that each thread clears about the
 * entries its force pass takes (dem_pairs_row_block). Cleared by one
 * thread they took 0.7 ms a build at N = 20000 with one thread or two,
 * an eighth of a one-thread build (Zen 5, docs/performance-log.md). */
static void forces_zero(struct dem_contact_forces *f, int n, int torques)
{
    enum { CHUNK = 2048 };
    const int nchunk = (n + CHUNK - 1) / CHUNK;
#pragma omp parallel for schedule(static) if (nchunk > 1)
    for (int c = 0; c < nchunk; c++) {
        const size_t k0 = (size_t)c * CHUNK;
        const size_t m = c + 1 < nchunk ? CHUNK : (size_t)n - k0;
        memset(f->v + k0, 0, m * sizeof *f->v);
        if (torques)
            memset(f->m + 3 * k0, 0, 3 * m * sizeof *f->m);
    }
}

/* Room for nrec of the force pass's particle records (contact/pass.c),
 * aligned for whole-vector loads. Growing them loses what they held; if
 * out of memory the old ones are kept. */
static int records_reserve(struct dem_pairs *pl, int nrec)
{
    if (nrec <= pl->rec_cap)
        return 0;
    const int c = nrec + nrec / 4;
    double *r = aligned_alloc(
        64, ((size_t)c * DEM_REC * sizeof(double) + 63) / 64 * 64);
    if (!r) /* the old ones kept */
        return -1;
    free(pl->rec);
    pl->rec = r;
    pl->rec_cap = c;
    pl->rec_written = 0;
    pl->blocks.written = 0;
    return 0;
}

int dem_pairs_records_reserve(struct dem_pairs *pl, int nrec)
{
    return records_reserve(pl, nrec);
}

/* Per-particle arrays for n particles (row offsets need n + 1). */
static int particles_reserve(struct dem_pairs *pl, int n, int cap)
{
    if (n + 1 <= pl->nalloc)
        return 0;
    int c = n + 1;
    struct dem_contact_list *lists[4] = {&pl->cur, &pl->old, &pl->wcur,
                                         &pl->wold};
    for (int k = 0; k < 4; k++) {
        if (GROW(lists[k]->start, c))
            return -1;
        /* an empty history: no rows yet */
        if (lists[k]->start_cap == 0)
            memset(lists[k]->start, 0, (size_t)c * sizeof(int));
        lists[k]->start_cap = c;
    }
    if (GROW(pl->rstart, c) || GROW(pl->rimg, c) || GROW(pl->cell_of, c) ||
        GROW(pl->cell_list, c) || GROW(pl->old_of, c))
        return -1;
    /* the permutation swaps this with the particles' arrays: same length
     * and alignment */
    dem_particles_array_free(pl->scratch);
    pl->scratch =
        dem_particles_array((size_t)(cap > c ? cap : c), sizeof *pl->scratch);
    if (!pl->scratch)
        return -1;
    if (records_reserve(pl, c))
        return -1;
    pl->nalloc = c;
    return 0;
}

static int cell_index(const struct dem_pairs *pl, const double pos[3])
{
    int c[3];
    for (int a = 0; a < 3; a++) {
        /* clamped as a double: a position far outside the grid (or NaN,
         * in a blow-up that the run has still to diagnose) converts to
         * no int */
        const double u = floor((pos[a] - pl->lo[a]) * pl->inv_h[a]);
        c[a] = !(u >= 0.0) ? 0 : u >= pl->nc[a] ? pl->nc[a] - 1 : (int)u;
    }
    return (c[2] * pl->nc[1] + c[1]) * pl->nc[0] + c[0];
}

/* Where particle i sits on the grid: its position, or in a periodic
 * cell its fractional coordinates. */
static void grid_coord(const struct dem_pairs *pl,
                       const struct dem_particles *p, int i, double c[3])
{
    const double x[3] = {p->x[i], p->y[i], p->z[i]};
    if (pl->periodic)
        dem_lattice_frac(&pl->lat, x, c);
    else
        for (int a = 0; a < 3; a++)
            c[a] = x[a];
}

/* The grid: cells at least one interaction range (2 rmax + skin) wide,
 * over [lo, hi] or, in a periodic cell, over the fractional coordinates
 * [0, 1) with as many cells per axis as the cell's width holds ranges. */
static int setup_grid(struct dem_pairs *pl, const struct dem_particles *p,
                      int dim, double skin, const double lo[3],
                      const double hi[3], const struct dem_lattice *cell,
                      struct dem_error *err)
{
    double rmax = 0.0;
    for (int i = 0; i < p->n; i++)
        rmax = p->r[i] > rmax ? p->r[i] : rmax;
    const double h = 2.0 * rmax + skin;
    double width[3] = {0.0, 0.0, 0.0};
    pl->periodic = cell != NULL;
    if (cell) {
        pl->lat = *cell;
        dem_lattice_widths(cell, dim, width);
        for (int a = 0; a < dim; a++)
            if (!(width[a] > 2.0 * h))
                return dem_error_set(
                    err, DEM_EUNSTABLE,
                    "the periodic cell is %.4g m wide across its %c faces, "
                    "less than two interaction ranges (2 x %.4g m: the "
                    "largest diameter plus the skin); a pair would touch "
                    "two images of each other",
                    width[a], "xyz"[a], h);
    }
    long ncell = 1;
    for (int a = 0; a < 3; a++) {
        const int flat = a == 2 && dim == 2;
        double span = cell ? width[a] : hi[a] - lo[a];
        /* at least one cell; at most 4096, which bounds the grid's memory
         * for very large, sparse boxes (compared as a double: the ratio
         * may exceed any int) */
        const double q = flat ? 1.0 : span / h;
        const int k = !(q >= 1.0) ? 1 : q >= 4096.0 ? 4096 : (int)q;
        pl->nc[a] = k;
        pl->lo[a] = cell ? 0.0 : lo[a];
        pl->inv_h[a] = flat ? 0.0 : cell ? k : k / (span > 0 ? span : h);
        ncell *= k;
    }
    /* no more cells than particles are needed: coarser cells are still
     * at least one range wide. Between walls only grids of more than
     * 2^20 cells are made coarser (a sparse sample in a large box, whose
     * grid would fill memory), so that a dense sample's order of
     * particles (dem_pairs_reorder) stays as it was. */
    while (ncell > 2L * p->n + 27 && (cell || ncell > 1L << 20)) {
        ncell = 1;
        for (int a = 0; a < dim; a++) {
            pl->nc[a] = pl->nc[a] > 1 ? pl->nc[a] / 2 : 1;
            const double span = hi[a] - lo[a];
            pl->inv_h[a] = cell ? pl->nc[a] : pl->nc[a] / (span > 0 ? span : h);
            ncell *= pl->nc[a];
        }
    }
    if (ncell > 64L * 1024 * 1024)
        return dem_error_set(err, DEM_ENOMEM,
                             "neighbour grid of %ld cells is too large", ncell);
    if (ncell + 1 > pl->ncell_cap) {
        if (GROW(pl->cell_start, ncell + 1))
            return dem_error_set(err, DEM_ENOMEM, "out of memory (cells)");
        pl->ncell_cap = (int)ncell + 1;
    }
    return DEM_OK;
}

/* Counting sort of the particles by cell: cell_start and cell_list. */
static void sort_by_cell(struct dem_pairs *pl, const struct dem_particles *p)
{
    const int ncell = pl->nc[0] * pl->nc[1] * pl->nc[2];
    int *cs = pl->cell_start;
    memset(cs, 0, (size_t)(ncell + 1) * sizeof *cs);
    const int n = p->n;
    int *cell_of = pl->cell_of;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        double c[3];
        grid_coord(pl, p, i, c);
        cell_of[i] = cell_index(pl, c);
    }
    for (int i = 0; i < n; i++)
        cs[cell_of[i] + 1]++;
    for (int c = 0; c < ncell; c++)
        cs[c + 1] += cs[c];
    /* stable: particles of a cell stay in index order */
    for (int i = 0; i < p->n; i++)
        pl->cell_list[cs[pl->cell_of[i]]++] = i;
    for (int c = ncell; c > 0; c--)
        cs[c] = cs[c - 1];
    cs[0] = 0;
}

/* Index in the old list of the entry (a, b) of old row a, or -1. */
static int old_find(const struct dem_contact_list *o, int a, int b)
{
    for (int k = o->start[a]; k < o->start[a + 1]; k++)
        if (o->j[k] == b)
            return k;
    return -1;
}

/* Entry k of L takes the history of entry o of O (none: o < 0), the
 * values of mask hist (struct dem_pairs.hist) only; flip: the pair's
 * particles have changed roles (old i is new j), so each value is
 * multiplied by its swap factor (DEM_CONTACT_HISTORY). */
static void carry_history(struct dem_contact_list *L, int k,
                          const struct dem_contact_list *O, int o, int flip,
                          unsigned hist)
{
    unsigned bit = 1;
#define HIST_CARRY_(MODEL, name, unit, swap, doc)                              \
    if (hist & bit)                                                            \
        L->name[k] = o < 0 ? 0.0 : flip ? (swap)*O->name[o] : O->name[o];      \
    bit <<= 1;
    DEM_CONTACT_HISTORY(HIST_CARRY_)
#undef HIST_CARRY_
    L->state[k] = o >= 0 ? O->state[o] : 0;
}

static void swap_lists(struct dem_contact_list *a, struct dem_contact_list *b)
{
    struct dem_contact_list t = *a;
    *a = *b;
    *b = t;
}

/* Insert key into the sorted row out[0..m). */
static void row_insert(int *out, int m, int key)
{
    int b = m - 1;
    while (b >= 0 && out[b] > key) {
        out[b + 1] = out[b];
        b--;
    }
    out[b + 1] = key;
}

/* Whether particles i and j are closer than the sum of their reaches
 * (radius plus reach each): the one test of the searches between walls. */
static inline int within_reach(const struct dem_particles *p, int i, int j)
{
    const double ddx = p->x[i] - p->x[j], ddy = p->y[i] - p->y[j],
                 ddz = p->z[i] - p->z[j];
    const double cut = p->r[i] + p->r[j] + (p->reach[i] + p->reach[j]);
    return !(ddx * ddx + ddy * ddy + ddz * ddz >= cut * cut);
}

/* The neighbours j > i of particle i closer than the sum of their
 * reaches, written to out (when not NULL) sorted by j; returns how many
 * there are. */
static int row_of(const struct dem_pairs *pl, const struct dem_particles *p,
                  int zr, int i, int *out)
{
    const int c = pl->cell_of[i];
    const int cx = c % pl->nc[0], cy = (c / pl->nc[0]) % pl->nc[1],
              cz = c / (pl->nc[0] * pl->nc[1]);
    int m = 0;
    for (int dz = -zr; dz <= zr; dz++) {
        int z = cz + dz;
        if (z < 0 || z >= pl->nc[2])
            continue;
        for (int dy = -1; dy <= 1; dy++) {
            int y = cy + dy;
            if (y < 0 || y >= pl->nc[1])
                continue;
            for (int dx = -1; dx <= 1; dx++) {
                int x = cx + dx;
                if (x < 0 || x >= pl->nc[0])
                    continue;
                int cc = (z * pl->nc[1] + y) * pl->nc[0] + x;
                for (int q = pl->cell_start[cc]; q < pl->cell_start[cc + 1];
                     q++) {
                    const int j = pl->cell_list[q];
                    if (j <= i || !within_reach(p, i, j))
                        continue;
                    if (out) /* a row holds a handful of pairs */
                        row_insert(out, m, j);
                    m++;
                }
            }
        }
    }
    return m;
}

/* The particles j0 <= j < j1 within reach of i (within_reach)
 * appended to out from m on, in index order; returns the new m. Every
 * candidate is written, and only a hit moves m on: no branch that the
 * hits' pattern would mispredict. */
static int range_hits(const struct dem_particles *p, int i, int j0, int j1,
                      int *out, int m)
{
    for (int j = j0; j < j1; j++) {
        out[m] = j;
        m += within_reach(p, i, j);
    }
    return m;
}

/* row_of for particles in cell order (dem_pairs_build re-ordered them and
 * there are no ghosts): a cell's particles are a range of indices and the
 * ranges follow the cells' order, so every j > i lies after i in its own
 * cell or in a later cell, and the three cells x - 1 .. x + 1 of one y
 * and z are one range. A row is then five ranges (two in 2D) read in
 * order, already sorted by j: half the cells of row_of and no look-up in
 * cell_list. The same pairs in the same order. out has room for
 * (zr ? 27 : 9) times the fullest cell's particles (build_pairs), more
 * than these ranges hold. */
static int row_of_ordered(const struct dem_pairs *pl,
                          const struct dem_particles *p, int zr, int i,
                          int *out)
{
    const int nx = pl->nc[0], ny = pl->nc[1], nz = pl->nc[2];
    const int c = pl->cell_of[i];
    const int cx = c % nx, cy = (c / nx) % ny, cz = c / (nx * ny);
    const int x0 = cx > 0 ? cx - 1 : 0, x1 = cx + 1 < nx ? cx + 1 : nx - 1;
    const int *cs = pl->cell_start;
    /* i's own cell after i and the cell after it on the same row */
    int m = range_hits(p, i, i + 1, cs[c - cx + x1 + 1], out, 0);
    for (int dz = 0; dz <= zr; dz++) {
        const int z = cz + dz;
        if (z >= nz)
            break;
        for (int dy = dz ? -1 : 1; dy <= 1; dy++) {
            const int y = cy + dy;
            if (y < 0 || y >= ny)
                continue;
            const int row = (z * ny + y) * nx;
            m = range_hits(p, i, cs[row + x0], cs[row + x1 + 1], out, m);
        }
    }
    return m;
}

/* In a periodic cell: the neighbours j > i of particle i closer than the
 * sum of their reaches through any image, written to out (when not NULL)
 * sorted, as
 * j << 6 | image code; returns how many there are. The grid is over the
 * fractional coordinates, so a neighbour cell beyond a face is the cell
 * at the other side, seen through the image one lattice vector away. */
static int row_of_cell(const struct dem_pairs *pl,
                       const struct dem_particles *p, int zr, int i,
                       int ordered, int *out)
{
    const int c = pl->cell_of[i];
    const int cx = c % pl->nc[0], cy = (c / pl->nc[0]) % pl->nc[1],
              cz = c / (pl->nc[0] * pl->nc[1]);
    const int cc3[3] = {cx, cy, cz};
    int m = 0;
    for (int dz = -zr; dz <= zr; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                const int d[3] = {dx, dy, dz};
                int w[3], sh[3];
                for (int a = 0; a < 3; a++) {
                    w[a] = cc3[a] + d[a];
                    sh[a] = w[a] < 0 ? -1 : w[a] >= pl->nc[a] ? 1 : 0;
                    w[a] -= sh[a] * pl->nc[a];
                }
                const int code = dem_img_code(sh[0], sh[1], sh[2]);
                double S[3];
                dem_img_shift(pl->lat.v, code, S);
                const int cc = (w[2] * pl->nc[1] + w[1]) * pl->nc[0] + w[0];
                if (ordered && cc < c) /* only j < i there (row_of_ordered) */
                    continue;
                for (int q = pl->cell_start[cc]; q < pl->cell_start[cc + 1];
                     q++) {
                    const int j = pl->cell_list[q];
                    if (j <= i)
                        continue;
                    const double ddx = p->x[i] - p->x[j] - S[0];
                    const double ddy = p->y[i] - p->y[j] - S[1];
                    const double ddz = p->z[i] - p->z[j] - S[2];
                    const double cut =
                        p->r[i] + p->r[j] + (p->reach[i] + p->reach[j]);
                    if (ddx * ddx + ddy * ddy + ddz * ddz >= cut * cut)
                        continue;
                    if (out)
                        row_insert(out, m, j << 6 | code);
                    m++;
                }
            }
    return m;
}

/* Room for nt threads' row buffers (struct dem_pairs.rowbuf); 0 on
 * success. */
static int rowbuf_reserve(struct dem_pairs *pl, int nt)
{
    if (nt <= pl->rowbuf_n)
        return 0;
    struct dem_row_buf *b = realloc(pl->rowbuf, (size_t)nt * sizeof *b);
    if (!b)
        return -1;
    memset(b + pl->rowbuf_n, 0, (size_t)(nt - pl->rowbuf_n) * sizeof *b);
    pl->rowbuf = b;
    pl->rowbuf_n = nt;
    return 0;
}

/* Room in b for need ints; 0 on success (else b is unchanged). */
static int rowbuf_grow(struct dem_row_buf *b, size_t need)
{
    if (need <= b->cap)
        return 0;
    size_t cap = 2 * b->cap > need ? 2 * b->cap : need;
    int *v = realloc(b->v, cap * sizeof *v);
    if (!v)
        return -1;
    b->v = v;
    b->cap = cap;
    return 0;
}

/* One pass over the particles in equal blocks, one per thread: each
 * thread writes its rows to its own buffer, then, once the offsets are
 * known, copies them into the list. The history of every pair is then
 * found in the old list. The list is the same for any number of threads.
 * The buffers are kept from build to build: allocated anew, thread 0's
 * came from fresh pages at every build, and their first touch made its
 * half of the rows take about twice thread 1's (N = 20000, Zen 5). */
static int build_pairs(struct dem_pairs *pl, const struct dem_particles *p,
                       int dim, int ordered, struct dem_error *err)
{
    struct dem_contact_list *L = &pl->cur;
    const struct dem_contact_list *O = &pl->old;
    const int zr = dim == 3 ? 1 : 0;
    const int n = p->n;
    /* no row is longer than the particles of the cells around it */
    const int ncell = pl->nc[0] * pl->nc[1] * pl->nc[2];
    int occ = 1;
    for (int c = 0; c < ncell; c++)
        if (pl->cell_start[c + 1] - pl->cell_start[c] > occ)
            occ = pl->cell_start[c + 1] - pl->cell_start[c];
    const int longest = (zr ? 27 : 9) * occ;
    int *start = L->start;
    int failed = 0;
    long long total = 0;
    if (pl->periodic && n > DEM_PAIRS_PERIODIC_MAX)
        return dem_error_set(err, DEM_ENOMEM,
                             "a periodic cell's pair list takes at most %d "
                             "particles, not %d",
                             DEM_PAIRS_PERIODIC_MAX, n);
#pragma omp parallel
    {
        const int nt = omp_get_num_threads(), t = omp_get_thread_num();
        const int i0 = dem_block(n, t, nt), i1 = dem_block(n, t + 1, nt);
#pragma omp single
        if (rowbuf_reserve(pl, nt))
            failed = 1;
        /* the single's barrier: failed and pl->rowbuf are set */
        struct dem_row_buf *rb = failed ? NULL : &pl->rowbuf[t];
        size_t m = 0;
        int *buf = NULL;
        if (rb && rowbuf_grow(rb, (size_t)longest + 4096) == 0)
            buf = rb->v;
        for (int i = i0; buf && i < i1; i++) {
            if (rowbuf_grow(rb, m + (size_t)longest)) {
                buf = NULL;
                break;
            }
            buf = rb->v;
            /* a ghost's partners j > i are ghosts too: no row */
            int cnt = i >= n - pl->nghost ? 0
                      : pl->periodic
                          ? row_of_cell(pl, p, zr, i, ordered, buf + m)
                      : ordered ? row_of_ordered(pl, p, zr, i, buf + m)
                                : row_of(pl, p, zr, i, buf + m);
            start[i + 1] = cnt;
            m += (size_t)cnt;
        }
        if (!buf) {
#pragma omp atomic write
            failed = 1;
        }
#pragma omp barrier
#pragma omp single
        {
            start[0] = 0;
            for (int i = 0; !failed && i < n; i++)
                total += start[i + 1];
            if (!failed && total > DEM_PAIRS_MAX)
                failed = 2;
            if (!failed) {
                for (int i = 0; i < n; i++)
                    start[i + 1] += start[i];
                if (list_reserve(L, start[n]))
                    failed = 1;
                else
                    L->n = start[n];
            }
        }
        if (!failed && m > 0) {
            memcpy(L->j + start[i0], buf, m * sizeof *buf);
            for (int i = i0; i < i1; i++)
                for (int k = start[i]; k < start[i + 1]; k++) {
                    L->i[k] = i;
                    if (pl->periodic) {
                        L->img[k] = L->j[k] & 63;
                        L->j[k] >>= 6;
                    }
                }
        }
    }
    if (failed == 2)
        return dem_error_set(err, DEM_ENOMEM,
                             "%lld particle pairs within reach, more than "
                             "the pair list's %d: fewer particles, or "
                             "the sample split over more MPI ranks",
                             total, DEM_PAIRS_MAX);
    if (failed)
        return dem_error_set(err, DEM_ENOMEM, "out of memory (pair list)");
    const int np = L->n;
#pragma omp parallel for schedule(static)
    for (int k = 0; k < np; k++) {
        int a = pl->old_of[L->i[k]], b = pl->old_of[L->j[k]];
        int o = O->n ? (a < b ? old_find(O, a, b) : old_find(O, b, a)) : -1;
        carry_history(L, k, O, o, a > b, pl->hist);
    }
    return DEM_OK;
}

/* Whether particle i is listed with wall w: not further than the wall's
 * half of the skin plus its reach (so listed if its gap is not a number,
 * as within_reach). */
static int wall_near(const struct dem_particles *p, int i,
                     const struct dem_wall *w, double skin)
{
    const double pos[3] = {p->x[i], p->y[i], p->z[i]};
    const double sgn = w->side ? -1.0 : 1.0;
    const double gap = sgn * (pos[w->axis] - w->pos) - p->r[i];
    return !(gap >= p->reach[i] + 0.5 * skin);
}

/* The particle-wall list, row by row in particle order, in two passes
 * over the particles in blocks: one counts each row, one writes it and
 * carries its history. */
static int build_walls(struct dem_pairs *pl, const struct dem_particles *p,
                       double skin, const struct dem_wall *w, int nwall,
                       struct dem_error *err)
{
    struct dem_contact_list *L = &pl->wcur;
    const struct dem_contact_list *O = &pl->wold;
    const int n = p->n, nown = n - pl->nghost;
    int *start = L->start;
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        int cnt = 0;
        for (int k = 0; i < nown && k < nwall; k++)
            cnt += wall_near(p, i, &w[k], skin);
        start[i + 1] = cnt;
    }
    start[0] = 0;
    for (int i = 0; i < n; i++)
        start[i + 1] += start[i];
    if (list_reserve(L, start[n]))
        return dem_error_set(err, DEM_ENOMEM, "out of memory (wall contacts)");
    L->n = start[n];
#pragma omp parallel for schedule(static)
    for (int i = 0; i < nown; i++) {
        int e = start[i];
        for (int k = 0; e < start[i + 1] && k < nwall; k++) {
            if (!wall_near(p, i, &w[k], skin))
                continue;
            L->i[e] = i;
            L->j[e] = k;
            const int o = O->n ? old_find(O, pl->old_of[i], k) : -1;
            carry_history(L, e, O, o, 0, pl->hist);
            e++;
        }
    }
    return DEM_OK;
}

/* Items 0 <= k < n by their key in [0, nb), those whose key is skip
 * left out: a counting sort, stable (each key's items in order, so that
 * a sum over them keeps the list's order). Key b's items are
 * out[start[b] .. start[b + 1]); start has nb + 1 entries. */
static void stable_buckets(const int *key, int n, int nb, int skip, int *start,
                           int *out)
{
    memset(start, 0, (size_t)(nb + 1) * sizeof *start);
    for (int k = 0; k < n; k++)
        if (key[k] != skip)
            start[key[k] + 1]++;
    for (int b = 0; b < nb; b++)
        start[b + 1] += start[b];
    for (int k = 0; k < n; k++)
        if (key[k] != skip)
            out[start[key[k]]++] = k;
    for (int b = nb; b > 0; b--)
        start[b] = start[b - 1];
    start[0] = 0;
}

int dem_pairs_cross(struct dem_pairs *pl, int n)
{
    const struct dem_contact_list *L = &pl->cur;
    int *start = pl->cross_start;
    for (int g = 0; g <= DEM_IMG_CODES; g++)
        start[g] = 0;
    pl->ncross = 0;
    if (!pl->periodic)
        return 0;
    if (L->n > pl->cross_cap) {
        if (GROW(pl->cross, L->cap) || GROW(pl->imgk, L->cap) ||
            GROW(pl->jrec, L->cap))
            return -1;
        pl->cross_cap = L->cap;
    }
    /* j's record for each pair: the image records follow the particles' */
    int m = 0;
    for (int k = 0; k < L->n; k++) {
        const int through = L->img[k] != DEM_IMG_NONE;
        pl->jrec[k] = through ? n + m : L->j[k];
        if (through)
            pl->imgk[m++] = k;
    }
    if (records_reserve(pl, n + m))
        return -1;
    /* by image, each image's pairs in list order (contact/forces.c sums
     * over them) */
    stable_buckets(L->img, L->n, DEM_IMG_CODES, DEM_IMG_NONE, start, pl->cross);
    pl->ncross = start[DEM_IMG_CODES];
    return 0;
}

int dem_pairs_reverse(struct dem_pairs *pl, int n)
{
    const struct dem_contact_list *L = &pl->cur;
    pl->gen++;
    if (L->n > pl->rpair_cap) {
        if (GROW(pl->rpair, L->cap))
            return -1;
        pl->rpair_cap = L->cap;
    }
    int *rs = pl->rstart, *ri = pl->rimg;
    memset(rs, 0, (size_t)(n + 1) * sizeof *rs);
    for (int k = 0; k < L->n; k++)
        rs[L->j[k] + 1]++;
    for (int i = 0; i < n; i++)
        rs[i + 1] += rs[i];
    /* each row's pairs with j itself first, then those through an image,
     * each part in list order; rs[j] runs to the end of the row */
    const int cell = pl->periodic;
    for (int k = 0; k < L->n; k++)
        if (!cell || L->img[k] == DEM_IMG_NONE)
            pl->rpair[rs[L->j[k]]++] = k;
    for (int i = 0; i < n; i++)
        ri[i] = rs[i];
    for (int k = 0; cell && k < L->n; k++)
        if (L->img[k] != DEM_IMG_NONE)
            pl->rpair[rs[L->j[k]]++] = k;
    for (int i = n; i > 0; i--)
        rs[i] = rs[i - 1];
    rs[0] = 0;
    /* the reach: every row holds j > i, so a particle's pairs as j with j
     * itself lie in rows before its own and the first of them opens its
     * span (those through an image the ring pass reads from the list's
     * array); the span ends where the ring pass finishes the particle,
     * after the rows of its group. A subdomain's ghosts have none: the
     * rank sums no forces for them (decomp/halo.h), so their pairs' forces
     * need not stay in the ring (with them the reach took in most of the
     * list, as the ghosts come after all own particles) */
    const int *start = L->start, G = DEM_RING_GROUP;
    int reach = 0;
    for (int i = 0; i < n - pl->nghost; i++) {
        const int first = rs[i] < ri[i] ? pl->rpair[rs[i]] : start[i];
        const int ge = (i / G + 1) * G;
        const int span = start[ge < n ? ge : n] - first;
        reach = span > reach ? span : reach;
    }
    pl->reach = reach;
    /* the wall contacts by wall, each wall's in list order */
    const struct dem_contact_list *W = &pl->wcur;
    if (W->n > pl->wall_order_cap) {
        if (GROW(pl->wall_order, W->cap))
            return -1;
        pl->wall_order_cap = W->cap;
    }
    stable_buckets(W->j, W->n, DEM_PAIRS_WALLS, -1, pl->wall_start,
                   pl->wall_order);
    return 0;
}

int dem_pairs_cut(const int *start, int n, long target)
{
    int lo = 0, hi = n;
    while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        if (DEM_WORK_PAIR * (long)start[mid] + DEM_WORK_PARTICLE * (long)mid <
            target)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* The first particle of block t when the rows of particles 0 <= i < n
 * (np pairs) are split in blocks of about equal work (dem_pairs_cut), on
 * a multiple of g. With pairs alone a periodic cell's first block, whose
 * rows hold the pairs through the z faces, had 4 % fewer particles and
 * finished first. */
static int row_block(const int *start, int n, int np, int t, int nt, int g)
{
    if (t >= nt)
        return n;
    const long target =
        (DEM_WORK_PAIR * (long)np + DEM_WORK_PARTICLE * (long)n) * t / nt;
    return dem_pairs_cut(start, n, target) / g * g;
}

void dem_pairs_row_block(const struct dem_pairs *pl, int n, int t, int nt,
                         int g, int w[4], int *kt, int *kw)
{
    const int *start = pl->cur.start, *rstart = pl->rstart, *rimg = pl->rimg,
              *rpair = pl->rpair, np = start[n];
    const int a = row_block(start, n, np, t, nt, g),
              b = row_block(start, n, np, t + 1, nt, g), k0 = start[a];
    /* a particle's first pair as j with j itself (its reverse row) lies
     * at most the reach before the end of its row, so only the block's
     * particles whose rows end within the reach after its first pair can
     * have one in an earlier block */
    int d = a, e = b;
    for (int i = a; i < b && start[i + 1] < k0 + pl->reach; i++)
        if (rstart[i] < rimg[i] && rpair[rstart[i]] < k0)
            d = i + 1;
    /* in a periodic cell a pair through an image can join the block's
     * first particle with any later one (those through the z faces join
     * the first and last layers of cells): those of earlier blocks extend
     * the first range if their j is in the block's first half, else they
     * open the second */
    const int mid = a + (b - a) / 2;
    for (int m = 0; pl->periodic && m < pl->ncross && pl->imgk[m] < k0; m++) {
        const int j = pl->cur.j[pl->imgk[m]];
        if (j >= a && j < mid)
            d = j + 1 > d ? j + 1 : d;
        else if (j >= mid && j < b)
            e = j < e ? j : e;
    }
    d = (d + g - 1) / g * g;
    d = d < b ? d : b;
    e = e < b ? e / g * g : b;
    w[0] = a;
    w[1] = d;
    w[2] = e > d ? e : d;
    w[3] = b;
    /* kw: the end of the earlier blocks' pairs (all through an image)
     * that the second range's particles have as j */
    int kj = 0;
    for (int m = 0; pl->periodic && m < pl->ncross && pl->imgk[m] < k0; m++) {
        const int j = pl->cur.j[pl->imgk[m]];
        if (j >= w[2] && j < b)
            kj = pl->imgk[m] + 1;
    }
    *kw = kj;
    /* kt: the first of the block's pairs with j beyond it (the first
     * pair as j at or after k0 of each later particle whose rows end
     * within the reach after the block's end: no other can have one).
     * Own particles only: a ghost's sums are its owner's
     * (decomp/halo.h) */
    const int k1 = start[b];
    int k = k1;
    for (int i = b; i < n && start[i + 1] < k1 + pl->reach; i++)
        for (int u = rstart[i]; u < rimg[i]; u++)
            if (rpair[u] >= k0) {
                k = rpair[u] < k ? rpair[u] : k;
                break;
            }
    *kt = k;
}

int dem_pairs_build(struct dem_pairs *pl, struct dem_particles *p, int dim,
                    double skin, const double lo[3], const double hi[3],
                    const struct dem_wall *w, int nwall,
                    const struct dem_lattice *cell, int reorder,
                    struct dem_error *err)
{
    const int n = p->n;
    if (particles_reserve(pl, n, p->cap))
        return dem_error_set(err, DEM_ENOMEM, "out of memory (neighbours)");
    int rc = setup_grid(pl, p, dim, skin, lo, hi, cell, err);
    if (rc)
        return rc;
    sort_by_cell(pl, p);
    const int ncell = pl->nc[0] * pl->nc[1] * pl->nc[2];
    if (reorder && pl->nghost == 0) {
        /* particles in cell order: neighbours are close in memory */
        memcpy(pl->old_of, pl->cell_list, (size_t)n * sizeof *pl->old_of);
        dem_particles_permute(p, pl->old_of, &pl->scratch);
        for (int k = 0; k < n; k++)
            pl->cell_list[k] = k;
        for (int c = 0; c < ncell; c++)
            for (int q = pl->cell_start[c]; q < pl->cell_start[c + 1]; q++)
                pl->cell_of[q] = c;
    } else if (reorder) {
        /* a subdomain: its own particles in cell order, the ghosts stay
         * where they are (the exchanges address them by index) */
        const int nown = n - pl->nghost;
        int m = 0;
        for (int q = 0; q < n; q++)
            if (pl->cell_list[q] < nown)
                pl->old_of[m++] = pl->cell_list[q];
        for (int k = nown; k < n; k++)
            pl->old_of[k] = k;
        dem_particles_permute(p, pl->old_of, &pl->scratch);
        int *new_of = pl->rstart; /* scratch: dem_pairs_reverse fills it */
        for (int k = 0; k < n; k++)
            new_of[pl->old_of[k]] = k;
        for (int q = 0; q < n; q++)
            pl->cell_list[q] = new_of[pl->cell_list[q]];
        for (int c = 0; c < ncell; c++)
            for (int q = pl->cell_start[c]; q < pl->cell_start[c + 1]; q++)
                pl->cell_of[pl->cell_list[q]] = c;
    } else {
        for (int k = 0; k < n; k++)
            pl->old_of[k] = k;
    }
    /* the current lists become the old ones, whose rows are indexed by
     * the particles' indices before the re-order */
    swap_lists(&pl->cur, &pl->old);
    swap_lists(&pl->wcur, &pl->wold);
    rc = build_pairs(pl, p, dim, reorder && pl->nghost == 0, err);
    if (!rc)
        rc = build_walls(pl, p, skin, w, nwall, err);
    if (rc)
        return rc;
    if (dem_pairs_reverse(pl, n) || dem_pairs_cross(pl, n) ||
        forces_reserve(&pl->f, pl->cur.cap, 0) ||
        forces_reserve(&pl->wf, pl->wcur.cap, 1))
        return dem_error_set(err, DEM_ENOMEM, "out of memory (neighbours)");
    forces_zero(&pl->f, pl->cur.n, pl->torques);
    forces_zero(&pl->wf, pl->wcur.n, pl->torques);
    for (int k = 0; k < nwall && k < 6; k++)
        pl->wall_pos0[k] = w[k].pos;
    return DEM_OK;
}

int dem_pairs_reserve(struct dem_pairs *pl, int n, int cap, int npair, int nwc)
{
    npair = npair > 0 ? npair : 1;
    nwc = nwc > 0 ? nwc : 1;
    if (particles_reserve(pl, n, cap) || list_reserve(&pl->cur, npair) ||
        list_reserve(&pl->wcur, nwc) ||
        forces_reserve(&pl->f, pl->cur.cap, 0) ||
        forces_reserve(&pl->wf, pl->wcur.cap, 1))
        return DEM_ENOMEM;
    if (pl->cur.cap > pl->rpair_cap) {
        if (GROW(pl->rpair, pl->cur.cap))
            return DEM_ENOMEM;
        pl->rpair_cap = pl->cur.cap;
    }
    return DEM_OK;
}

int dem_pairs_brute(const struct dem_particles *p, int dim, double skin,
                    const double *reach, const struct dem_lattice *cell,
                    int **pi, int **pj, int **pimg)
{
    int cap = 1024, n = 0;
    int *a = malloc((size_t)cap * sizeof *a),
        *b = malloc((size_t)cap * sizeof *b),
        *g = malloc((size_t)cap * sizeof *g);
    const int si = cell ? 1 : 0, sk = cell && dim == 3 ? 1 : 0;
    if (!a || !b || !g)
        goto fail;
    for (int i = 0; i < p->n; i++)
        for (int j = i + 1; j < p->n; j++)
            for (int sz = -sk; sz <= sk; sz++)
                for (int sy = -si; sy <= si; sy++)
                    for (int sx = -si; sx <= si; sx++) {
                        const int code = dem_img_code(sx, sy, sz);
                        double S[3] = {0.0, 0.0, 0.0};
                        if (cell)
                            dem_img_shift(cell->v, code, S);
                        double dx = p->x[i] - p->x[j] - S[0],
                               dy = p->y[i] - p->y[j] - S[1],
                               dz = p->z[i] - p->z[j] - S[2];
                        double cut = p->r[i] + p->r[j] + skin;
                        if (reach)
                            cut += reach[i] + reach[j];
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
                            int *ng = realloc(g, (size_t)cap * sizeof *g);
                            if (!ng)
                                goto fail;
                            g = ng;
                        }
                        a[n] = i;
                        b[n] = j;
                        g[n] = code;
                        n++;
                    }
    *pi = a;
    *pj = b;
    if (pimg)
        *pimg = g;
    else
        free(g);
    return n;
fail:
    free(a);
    free(b);
    free(g);
    return DEM_ENOMEM;
}
