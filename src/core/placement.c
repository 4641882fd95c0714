/* Initial particle placement (see placement.h).
 *
 * Radius distributions (SPEC §1): mono (all = mean); uniform in [min, max];
 * Gaussian N(mean, std) redrawn until inside [min, max] (and > 0).
 *
 * Lattice: square/cubic, spacing 2 r_max (1 + DEM_LATTICE_GAP), filled
 * x fastest, then y, then z; the box is the lattice extent or the given
 * box.size with the lattice centred in it (at a spacing down to 2 r_max
 * where the box is narrower than the lattice with its gap).
 *
 * Random: random sequential insertion, largest particles first, each
 * centre uniform over the positions that keep the particle inside the box
 * (in a periodic cell, over the whole cell, overlaps counted through the
 * faces: a gas without empty bands along them), rejected on overlap with
 * any particle already placed. A cell grid of edge >= 2 r_max limits the
 * overlap test to the 3^dim neighbouring cells, so the whole insertion
 * costs O(N) for a dilute box.
 */
#include "core/placement.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Tries for one Gaussian radius before the distribution is declared
 * (numerically) empty inside [min, max]. */
#define DEM_GAUSS_MAX_DRAWS 100000

static int box_given(const struct dem_config *cfg, int dim)
{
    for (int a = 0; a < dim; a++)
        if (cfg->box.size[a] != 0.0)
            return 1;
    return 0;
}

static int check_box(const struct dem_config *cfg, int dim,
                     struct dem_error *err)
{
    for (int a = 0; a < dim; a++) {
        double L = cfg->box.size[a];
        if (!(L > 0.0) || !isfinite(L))
            return dem_error_set(err, DEM_ECONFIG,
                                 "box.size: component %d must be a positive "
                                 "length (m), got %g",
                                 a, L);
    }
    return DEM_OK;
}

/* One radius (m) from the configured distribution. */
static int draw_radius(const struct dem_config *cfg, struct dem_rng *rng,
                       double *r, struct dem_error *err)
{
    double mean = cfg->particles.mean, sd = cfg->particles.std;
    double lo = cfg->particles.min, hi = cfg->particles.max;
    if (cfg->particles.distribution == DEM_DIST_GAUSSIAN && !(hi > 0.0))
        hi = INFINITY; /* no upper cut */
    switch (cfg->particles.distribution) {
    case DEM_DIST_UNIFORM:
        if (!(lo > 0.0) || !(hi >= lo) || !isfinite(hi))
            return dem_error_set(err, DEM_ECONFIG,
                                 "particles.radius.min: uniform radii need "
                                 "0 < min <= max, got min %g max %g (m)",
                                 lo, hi);
        *r = lo + (hi - lo) * dem_rng_uniform(rng);
        return DEM_OK;
    case DEM_DIST_GAUSSIAN:
        if (!(sd > 0.0) || !isfinite(sd) || !isfinite(mean))
            return dem_error_set(err, DEM_ECONFIG,
                                 "particles.radius.std: Gaussian radii need a "
                                 "positive standard deviation, got %g (m)",
                                 sd);
        for (int k = 0; k < DEM_GAUSS_MAX_DRAWS; k++) {
            double x = mean + sd * dem_rng_normal(rng);
            if (x >= lo && x <= hi && x > 0.0) {
                *r = x;
                return DEM_OK;
            }
        }
        return dem_error_set(err, DEM_ECONFIG,
                             "particles.radius.min: a Gaussian of mean %g and "
                             "std %g almost never falls in [min %g, max %g] "
                             "(m); widen the cuts",
                             mean, sd, lo, hi);
    default:
        if (!(mean > 0.0) || !isfinite(mean))
            return dem_error_set(err, DEM_ECONFIG,
                                 "particles.radius.mean: must be a positive "
                                 "radius (m), got %g",
                                 mean);
        *r = mean;
        return DEM_OK;
    }
}

/* Allocate p and add cfg->particles.count particles at the origin with
 * drawn radii; returns r_max (m) in *rmax. */
static int add_with_radii(struct dem_particles *p, const struct dem_config *cfg,
                          int dim, struct dem_rng *rng, double *rmax,
                          struct dem_error *err)
{
    int n = cfg->particles.count;
    if (n <= 0)
        return dem_error_set(err, DEM_ECONFIG,
                             "particles.count: must be at least 1, got %d", n);
    int rc = dem_particles_init(p, n, err);
    if (rc)
        return rc;
    *rmax = 0.0;
    for (int i = 0; i < n; i++) {
        double r = 0.0;
        rc = draw_radius(cfg, rng, &r, err);
        if (rc)
            return rc;
        dem_particles_add(p, 0.0, 0.0, 0.0, r, cfg->particles.density,
                          cfg->particles.mass_model, dim);
        if (r > *rmax)
            *rmax = r;
    }
    return DEM_OK;
}

static long long ipow(long long b, int e)
{
    long long r = 1;
    while (e-- > 0)
        r *= b;
    return r;
}

/* "[Lx, Ly]" or "[Lx, Ly, Lz]" for messages. */
static void format_size(char *buf, size_t len, const double *L, int dim)
{
    if (dim == 3)
        snprintf(buf, len, "[%g, %g, %g]", L[0], L[1], L[2]);
    else
        snprintf(buf, len, "[%g, %g]", L[0], L[1]);
}

static int place_lattice(struct dem_particles *p, const struct dem_config *cfg,
                         int dim, double rmax, double lo[3], double hi[3],
                         struct dem_error *err)
{
    /* Smallest n_side with n_side^dim >= n, corrected in integers because
     * pow() may round either way at perfect powers. */
    long long n = p->n;
    long long side = (long long)ceil(pow((double)n, 1.0 / dim));
    if (side < 1)
        side = 1;
    while (side > 1 && ipow(side - 1, dim) >= n)
        side--;
    while (ipow(side, dim) < n)
        side++;
    double s = 2.0 * rmax * (1.0 + DEM_LATTICE_GAP); /* m; spacing */
    double extent = (double)side * s;                /* m */

    double origin[3] = {0.0, 0.0, 0.0}; /* m; lattice corner */
    if (box_given(cfg, dim)) {
        int rc = check_box(cfg, dim, err);
        if (rc)
            return rc;
        /* a box that holds the lattice only without its gap (a crystal of
         * touching particles, e.g. a periodic cell of side 2 r_max per
         * particle) takes it at the spacing that fits, to a rounding */
        for (int a = 0; a < dim; a++) {
            const double fit = cfg->box.size[a] / (double)side;
            if (fit < 2.0 * rmax * (1.0 - 1e-12)) {
                char size[96];
                format_size(size, sizeof size, cfg->box.size, dim);
                return dem_error_set(
                    err, DEM_ECONFIG,
                    "particles.count: %d particles of largest radius %g m "
                    "need a lattice of %.9g m per side but box.size is %s m",
                    p->n, rmax, (double)side * 2.0 * rmax, size);
            }
            if (fit < s)
                s = fit;
        }
        extent = (double)side * s;
        for (int a = 0; a < dim; a++) {
            lo[a] = 0.0;
            hi[a] = cfg->box.size[a];
            origin[a] = 0.5 * (cfg->box.size[a] - extent);
        }
    } else {
        for (int a = 0; a < dim; a++) {
            lo[a] = 0.0;
            hi[a] = extent;
        }
    }
    for (int i = 0; i < p->n; i++) {
        long long k = i;
        p->x[i] = origin[0] + ((double)(k % side) + 0.5) * s;
        p->y[i] = origin[1] + ((double)((k / side) % side) + 0.5) * s;
        p->z[i] = dim == 3 ? origin[2] + ((double)(k / (side * side)) + 0.5) * s
                           : 0.0;
    }
    return DEM_OK;
}

/* Insertion order: largest first (small ones fill the gaps), ties by
 * index so the order is fully determined. */
struct by_radius {
    double r;
    int i;
};

static int cmp_radius_desc(const void *a, const void *b)
{
    const struct by_radius *u = a, *v = b;
    if (u->r != v->r)
        return u->r > v->r ? -1 : 1;
    return (u->i > v->i) - (u->i < v->i);
}

/* Cell grid for the overlap test during insertion. */
struct grid {
    int nc[3];   /* cells per axis */
    double edge; /* m; cell edge, >= 2 r_max */
    double lo[3];
    double period[3]; /* m; a periodic cell's edge along the axis (the grid
                         then spans [lo, lo + period) and its cells wrap),
                         or 0 */
    int *head;        /* first particle in each cell, -1 = empty */
    int *next;        /* next particle in the same cell */
};

static int grid_cell(const struct grid *g, int a, double x)
{
    /* clamped as a double: x far outside the grid (or an edge grown to
     * infinity) gives no int overflow or NaN cast */
    const double f = floor((x - g->lo[a]) / g->edge);
    /* The last cell absorbs the remainder L - nc edge, so it is wider. */
    if (!(f >= 0.0))
        return 0;
    return f >= g->nc[a] ? g->nc[a] - 1 : (int)f;
}

/* The separation b - a along axis a, through the nearest image in a
 * periodic cell. */
static double grid_sep(const struct grid *g, int a, double d)
{
    const double P = g->period[a];
    return P > 0.0 ? d - P * nearbyint(d / P) : d;
}

/* The first particle in g closer to the sphere (x, y, z, r) than scale
 * times the sum of their radii (touching counts), or -1. */
static int within(const struct grid *g, const struct dem_particles *p, double x,
                  double y, double z, double r, double scale)
{
    int c[3] = {grid_cell(g, 0, x), grid_cell(g, 1, y), grid_cell(g, 2, z)};
    int c0[3], c1[3];
    for (int a = 0; a < 3; a++) {
        if (g->period[a] > 0.0 && g->nc[a] >= 3) { /* through the faces */
            c0[a] = c[a] - 1;
            c1[a] = c[a] + 1;
        } else if (g->period[a] > 0.0) { /* every cell, each once */
            c0[a] = 0;
            c1[a] = g->nc[a] - 1;
        } else {
            c0[a] = c[a] > 0 ? c[a] - 1 : 0;
            c1[a] = c[a] < g->nc[a] - 1 ? c[a] + 1 : g->nc[a] - 1;
        }
    }
    for (int kk = c0[2]; kk <= c1[2]; kk++)
        for (int jj = c0[1]; jj <= c1[1]; jj++)
            for (int ii = c0[0]; ii <= c1[0]; ii++) {
                const int i = (ii + g->nc[0]) % g->nc[0],
                          j = (jj + g->nc[1]) % g->nc[1],
                          k = (kk + g->nc[2]) % g->nc[2];
                int cell = (k * g->nc[1] + j) * g->nc[0] + i;
                for (int q = g->head[cell]; q >= 0; q = g->next[q]) {
                    double dx = grid_sep(g, 0, p->x[q] - x),
                           dy = grid_sep(g, 1, p->y[q] - y),
                           dz = grid_sep(g, 2, p->z[q] - z),
                           s = scale * (p->r[q] + r);
                    if (dx * dx + dy * dy + dz * dz <= s * s)
                        return q;
                }
            }
    return -1;
}

/* g over [lo, lo + L] (L 0 on an axis without extent) for n particles:
 * cells of edge g->edge (set by the caller: >= 2 r_max), coarsened when
 * the box is so large that the grid would hold many more cells than
 * particles; every cell empty. 0, or -1 out of memory. */
static int grid_make(struct grid *g, const double lo[3], const double L[3],
                     int n)
{
    for (;;) {
        double total = 1.0;
        for (int a = 0; a < 3; a++) {
            double c = floor(L[a] / g->edge);
            g->nc[a] = !(c >= 1.0) ? 1 : (c > 1e9 ? 1000000000 : (int)c);
            total *= g->nc[a];
        }
        if (total <= 8.0 * n + 64.0)
            break;
        g->edge *= 1.25;
    }
    for (int a = 0; a < 3; a++)
        g->lo[a] = lo[a];
    const size_t ncell = (size_t)g->nc[0] * (size_t)g->nc[1] * (size_t)g->nc[2];
    g->head = malloc(ncell * sizeof *g->head);
    g->next = malloc((size_t)(n > 0 ? n : 1) * sizeof *g->next);
    if (!g->head || !g->next) {
        free(g->head);
        free(g->next);
        g->head = g->next = NULL;
        return -1;
    }
    for (size_t c = 0; c < ncell; c++)
        g->head[c] = -1;
    return 0;
}

/* Particle i, at its position, into g. */
static void grid_insert(struct grid *g, const struct dem_particles *p, int i)
{
    const int cell =
        (grid_cell(g, 2, p->z[i]) * g->nc[1] + grid_cell(g, 1, p->y[i])) *
            g->nc[0] +
        grid_cell(g, 0, p->x[i]);
    g->next[i] = g->head[cell];
    g->head[cell] = i;
}

static int place_random(struct dem_particles *p, const struct dem_config *cfg,
                        int dim, struct dem_rng *rng, double rmax, double lo[3],
                        double hi[3], struct dem_error *err)
{
    int n = p->n;
    double L[3] = {0.0, 0.0, 0.0}; /* m; box edges */
    const char *key;               /* what to change when it does not fit */
    if (box_given(cfg, dim)) {
        int rc = check_box(cfg, dim, err);
        if (rc)
            return rc;
        for (int a = 0; a < dim; a++)
            L[a] = cfg->box.size[a];
        key = "enlarge box.size";
    } else {
        double phi = cfg->particles.volume_fraction;
        if (!(phi > 0.0) || !isfinite(phi))
            phi = dim == 3 ? DEM_RANDOM_FRACTION_3D : DEM_RANDOM_FRACTION_2D;
        double vs = 0.0; /* m^3 (2D: m^2); solid volume */
        for (int i = 0; i < n; i++)
            vs += dim == 3 ? 4.0 / 3.0 * M_PI * p->r[i] * p->r[i] * p->r[i]
                           : M_PI * p->r[i] * p->r[i];
        double side = dim == 3 ? cbrt(vs / phi) : sqrt(vs / phi);
        for (int a = 0; a < dim; a++)
            L[a] = side;
        key = "lower particles.volume_fraction";
    }
    double volume = dim == 3 ? L[0] * L[1] * L[2] : L[0] * L[1];
    const int cell = cfg->box.boundary == DEM_BOUNDARY_PERIODIC;
    for (int a = 0; a < dim; a++)
        if (L[a] < 2.0 * rmax) { /* (only a given box.size can be) */
            char size[96];
            format_size(size, sizeof size, L, dim);
            return dem_error_set(err, DEM_ECONFIG,
                                 "box.size: a particle of radius %g m is "
                                 "wider than the box along %c (box.size is "
                                 "%s m)",
                                 rmax, "xyz"[a], size);
        }

    /* Cells of edge 2 r_max; the grid starts at the box's corner (2D: z
     * spans the slab of one largest diameter) */
    struct grid g = {.edge = 2.0 * rmax};
    for (int a = 0; cell && a < dim; a++)
        g.period[a] = L[a];
    const double glo[3] = {0.0, 0.0, dim == 2 ? -rmax : 0.0};
    const double gL[3] = {L[0], L[1], dim == 3 ? L[2] : 0.0};
    struct by_radius *order = malloc((size_t)n * sizeof *order);
    if (grid_make(&g, glo, gL, n) || !order) {
        free(g.head);
        free(g.next);
        free(order);
        return dem_error_set(err, DEM_ENOMEM,
                             "particles: out of memory placing %d particles",
                             n);
    }
    for (int i = 0; i < n; i++) {
        order[i].r = p->r[i];
        order[i].i = i;
    }
    qsort(order, (size_t)n, sizeof *order, cmp_radius_desc);

    int rc = DEM_OK;
    for (int k = 0; k < n && rc == DEM_OK; k++) {
        int i = order[k].i;
        double r = p->r[i], pos[3] = {0.0, 0.0, 0.0};
        int placed = 0;
        for (int t = 0; t < DEM_PLACE_MAX_ATTEMPTS && !placed; t++) {
            int fits = 1;
            /* Draw every coordinate even when one cannot fit, so the
             * stream consumed does not depend on the outcome. */
            for (int a = 0; a < dim; a++) {
                /* m; room for the centre: between walls the particle
                 * keeps inside, in a cell the whole cell */
                double free_len = cell ? L[a] : L[a] - 2.0 * r;
                pos[a] = (cell ? 0.0 : r) + free_len * dem_rng_uniform(rng);
                if (cell && pos[a] >= L[a]) /* (L u rounded up to L) */
                    pos[a] = 0.0;
                fits = fits && free_len >= 0.0;
            }
            placed = fits && within(&g, p, pos[0], pos[1], pos[2], r, 1.0) < 0;
        }
        if (!placed) {
            double vs = 0.0;
            for (int q = 0; q < n; q++)
                vs += dim == 3 ? 4.0 / 3.0 * M_PI * p->r[q] * p->r[q] * p->r[q]
                               : M_PI * p->r[q] * p->r[q];
            rc = dem_error_set(
                err, DEM_ECONFIG,
                "particles.count: could not place particle %d of %d "
                "(radius %g m) without overlap after %d attempts in a box "
                "of solid fraction %.3g; lower particles.count or %s",
                k + 1, n, r, DEM_PLACE_MAX_ATTEMPTS, vs / volume, key);
            break;
        }
        p->x[i] = pos[0];
        p->y[i] = pos[1];
        p->z[i] = pos[2];
        grid_insert(&g, p, i);
    }
    free(g.head);
    free(g.next);
    free(order);
    if (rc)
        return rc;
    for (int a = 0; a < dim; a++) {
        lo[a] = 0.0;
        hi[a] = L[a];
    }
    return DEM_OK;
}

/* Particles of a file whose centres are closer than half the sum of
 * their radii (a row given twice: centres 0 apart, whose contact normal
 * is 0/0; or lengths in other units): an error naming both, 1-based in
 * the file's order; in a periodic cell (period: its edges, the centres
 * already in [0, period)) through its faces too. No packing of a run
 * overlaps so far. */
static int check_file_overlaps(const struct dem_particles *p, int dim,
                               double rmax, const double *period,
                               const char *file, struct dem_error *err)
{
    const int n = p->n;
    double lo[3] = {0.0, 0.0, 0.0}, L[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < dim; a++) { /* the centres' bounding box */
        const double *c = a == 0 ? p->x : a == 1 ? p->y : p->z;
        double hi = c[0];
        lo[a] = c[0];
        for (int i = 1; i < n; i++) {
            lo[a] = c[i] < lo[a] ? c[i] : lo[a];
            hi = c[i] > hi ? c[i] : hi;
        }
        L[a] = hi - lo[a];
        if (period) {
            lo[a] = 0.0;
            L[a] = period[a];
        }
    }
    struct grid g = {.edge = 2.0 * rmax};
    for (int a = 0; period && a < dim; a++)
        g.period[a] = period[a];
    if (grid_make(&g, lo, L, n))
        return dem_error_set(err, DEM_ENOMEM,
                             "particles: out of memory checking %d particles",
                             n);
    int rc = DEM_OK;
    for (int i = 0; !rc && i < n; i++) {
        const int q = within(&g, p, p->x[i], p->y[i], p->z[i], p->r[i], 0.5);
        if (q >= 0) {
            const double dx = grid_sep(&g, 0, p->x[q] - p->x[i]),
                         dy = grid_sep(&g, 1, p->y[q] - p->y[i]),
                         dz = grid_sep(&g, 2, p->z[q] - p->z[i]);
            rc = dem_error_set(
                err, DEM_ECONFIG,
                "particles.file = %s: particles %d and %d have centres %g m "
                "apart, less than half the sum of their radii (%g m): a row "
                "given twice, or lengths in other units?",
                file, q + 1, i + 1, sqrt(dx * dx + dy * dy + dz * dz),
                0.5 * (p->r[q] + p->r[i]));
        } else {
            grid_insert(&g, p, i);
        }
    }
    free(g.head);
    free(g.next);
    return rc;
}

/* The particles read from particles.file (given, taken over), in box.size
 * or in their bounding box. */
static int place_file(struct dem_particles *p, struct dem_particles *given,
                      const struct dem_config *cfg, int dim, double *rmax,
                      double lo[3], double hi[3], struct dem_error *err)
{
    *p = *given;
    memset(given, 0, sizeof *given);
    *rmax = 0.0;
    for (int i = 0; i < p->n; i++)
        if (p->r[i] > *rmax)
            *rmax = p->r[i];
    const int rc = check_file_overlaps(
        p, dim, *rmax,
        cfg->box.boundary == DEM_BOUNDARY_PERIODIC ? cfg->box.size : NULL,
        cfg->particles.file, err);
    if (rc)
        return rc;
    if (box_given(cfg, dim)) {
        for (int a = 0; a < dim; a++) {
            lo[a] = 0.0;
            hi[a] = cfg->box.size[a];
        }
        return DEM_OK;
    }
    /* Bounding box grown by a thousandth of the largest radius, so the
     * walls start just clear of every particle. */
    double margin = 1e-3 * *rmax; /* m */
    for (int a = 0; a < dim; a++) {
        const double *c = a == 0 ? p->x : a == 1 ? p->y : p->z;
        lo[a] = c[0] - p->r[0];
        hi[a] = c[0] + p->r[0];
        for (int i = 1; i < p->n; i++) {
            if (c[i] - p->r[i] < lo[a])
                lo[a] = c[i] - p->r[i];
            if (c[i] + p->r[i] > hi[a])
                hi[a] = c[i] + p->r[i];
        }
        lo[a] -= margin;
        hi[a] += margin;
        if (!isfinite(hi[a] - lo[a])) /* e.g. centres at -1e308 and 1e308 */
            return dem_error_set(err, DEM_ECONFIG,
                                 "particles.file = %s: the particles span "
                                 "more than any box along %c (from %g to %g "
                                 "m)",
                                 cfg->particles.file, "xyz"[a], lo[a], hi[a]);
    }
    return DEM_OK;
}

int dem_place_particles(struct dem_particles *p, const struct dem_config *cfg,
                        struct dem_rng *rng, struct dem_particles *given,
                        double lo[3], double hi[3], struct dem_error *err)
{
    memset(p, 0, sizeof *p);
    int dim = cfg->dim == 2 ? 2 : 3;
    double rmax = 0.0; /* m */
    int rc = DEM_OK;
    if (cfg->particles.placement == DEM_PLACE_FILE) {
        if (!given || given->n < 1)
            return dem_error_set(err, DEM_EINTERNAL,
                                 "particles.placement = \"file\": the "
                                 "particles of %s were not read",
                                 cfg->particles.file);
        rc = place_file(p, given, cfg, dim, &rmax, lo, hi, err);
    } else {
        rc = add_with_radii(p, cfg, dim, rng, &rmax, err);
        if (rc == DEM_OK && cfg->particles.placement == DEM_PLACE_RANDOM)
            rc = place_random(p, cfg, dim, rng, rmax, lo, hi, err);
        else if (rc == DEM_OK)
            rc = place_lattice(p, cfg, dim, rmax, lo, hi, err);
    }
    if (rc) {
        dem_particles_free(p);
        return rc;
    }
    if (dim == 2) {
        /* The engine has no z walls in 2D; a slab one diameter thick keeps
         * box volumes and pictures meaningful. */
        lo[2] = -rmax;
        hi[2] = rmax;
    }
    for (int i = 0; i < p->n; i++) {
        if (dim == 2)
            p->z[i] = 0.0;
        p->x0[i] = p->x[i];
        p->y0[i] = p->y[i];
        p->z0[i] = p->z[i];
    }
    return DEM_OK;
}
