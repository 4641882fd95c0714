/* The periodic cell: its lattice, the affine map of a step, wrapping and
 * the Lees-Edwards re-map (core/cell.h). */
#include "core/cell.h"

#include <math.h>
#include <omp.h>

#include "contact/pass.h"
#include "core/parallel.h"
#include "core/sim.h"

/* h as a full matrix. */
static void matrix_of(const double v[6], double h[3][3])
{
    const double m[3][3] = {
        {v[0], v[1], v[2]}, {0.0, v[3], v[4]}, {0.0, 0.0, v[5]}};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            h[a][b] = m[a][b];
}

/* The inverse of h (upper triangular), with Lz = 0 (2D) taken as 1. */
static void inverse_of(const double v[6], double g[3][3])
{
    const double Lx = v[0], txy = v[1], txz = v[2], Ly = v[3], tyz = v[4],
                 Lz = v[5] > 0.0 ? v[5] : 1.0;
    const double m[3][3] = {
        {1.0 / Lx, -txy / (Lx * Ly), (txy * tyz - txz * Ly) / (Lx * Ly * Lz)},
        {0.0, 1.0 / Ly, -tyz / (Ly * Lz)},
        {0.0, 0.0, 1.0 / Lz}};
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            g[a][b] = m[a][b];
}

void dem_lattice_widths(const struct dem_lattice *c, int dim, double w[3])
{
    double g[3][3];
    inverse_of(c->v, g);
    /* the planes s_a = const are {x : g[a] . x = const}: their distance
     * for a unit step of s_a is 1/|g[a]| */
    for (int a = 0; a < 3; a++) {
        const double n2 = g[a][0] * g[a][0] + g[a][1] * g[a][1] +
                          (dim == 3 ? g[a][2] * g[a][2] : 0.0);
        w[a] = a < dim ? 1.0 / sqrt(n2) : 0.0;
    }
}

void dem_sim_lattice(const struct dem_sim *s, struct dem_lattice *c)
{
    for (int a = 0; a < 3; a++)
        c->lo[a] = a < s->dim ? s->wall[2 * a].pos : 0.0;
    double L[3];
    dem_sim_box(s, L, 0);
    const int d3 = s->dim == 3;
    c->v[0] = L[0];
    c->v[1] = s->cell.tilt[DEM_TILT_XY].pos;
    c->v[2] = d3 ? s->cell.tilt[DEM_TILT_XZ].pos : 0.0;
    c->v[3] = L[1];
    c->v[4] = d3 ? s->cell.tilt[DEM_TILT_YZ].pos : 0.0;
    c->v[5] = d3 ? L[2] : 0.0;
}

void dem_sim_cell_grad(const struct dem_sim *s, double grad[6])
{
    const int d3 = s->dim == 3;
    const struct dem_wall *W = s->wall;
    const double vdot[6] = {W[1].vel - W[0].vel,
                            s->cell.tilt[DEM_TILT_XY].vel,
                            d3 ? s->cell.tilt[DEM_TILT_XZ].vel : 0.0,
                            W[3].vel - W[2].vel,
                            d3 ? s->cell.tilt[DEM_TILT_YZ].vel : 0.0,
                            d3 ? W[5].vel - W[4].vel : 0.0};
    struct dem_lattice c;
    dem_sim_lattice(s, &c);
    double hd[3][3], g[3][3], L[3][3] = {{0}};
    matrix_of(vdot, hd);
    inverse_of(c.v, g);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            for (int k = 0; k < 3; k++)
                L[a][b] += hd[a][k] * g[k][b];
    grad[0] = L[0][0];
    grad[1] = L[0][1];
    grad[2] = L[0][2];
    grad[3] = L[1][1];
    grad[4] = L[1][2];
    grad[5] = L[2][2];
}

/* x <- to.lo + M (x - from.lo) with M = h_to h_from^-1 (upper
 * triangular) for particles i0 <= i < i1 of coordinate arrays X, Y, Z
 * (distinct: restrict lets the loop run in SIMD lanes). */
static inline void map_set(double *restrict X, double *restrict Y,
                           double *restrict Z, int i0, int i1, double M[3][3],
                           const double lf[3], const double lt[3])
{
    const double m00 = M[0][0], m01 = M[0][1], m02 = M[0][2], m11 = M[1][1],
                 m12 = M[1][2], m22 = M[2][2];
    for (int i = i0; i < i1; i++) {
        const double dx = X[i] - lf[0], dy = Y[i] - lf[1], dz = Z[i] - lf[2];
        X[i] = lt[0] + m00 * dx + m01 * dy + m02 * dz;
        Y[i] = lt[1] + m11 * dy + m12 * dz;
        Z[i] = lt[2] + m22 * dz;
    }
}

/* particles mapped at a time, their positions then copied to their
 * records while still in the L1 cache */
#define DEM_MAP_BLOCK 256

static void map_range(const struct dem_sim *s, int i0, int i1,
                      double M[3][3], const double lf[3], const double lt[3])
{
    const struct dem_particles *p = &s->p;
    map_set(p->x0, p->y0, p->z0, i0, i1, M, lf, lt);
    for (int b = i0; b < i1; b += DEM_MAP_BLOCK) {
        const int e = i1 - b > DEM_MAP_BLOCK ? b + DEM_MAP_BLOCK : i1;
        map_set(p->x, p->y, p->z, b, e, M, lf, lt);
#if DEM_HAVE_PASS_RECORDS
        /* records a chained records pass wrote move with their particles,
         * so that the next pass need not copy them again: their positions
         * copied from the arrays, the same bits as mapped (mapped in
         * place, strided, they took 2 % of a cell's step at N = 3375) */
        if (s->pairs.rec_written)
            dem_records_positions(s->pairs.rec, p, b, e);
#endif
    }
}

void dem_sim_cell_map(struct dem_sim *s, const struct dem_lattice *from,
                      const struct dem_lattice *to)
{
    double h[3][3], g[3][3], M[3][3] = {{0}};
    matrix_of(to->v, h);
    if (s->dim == 2)
        h[2][2] = 1.0; /* z stays */
    inverse_of(from->v, g);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            for (int k = 0; k < 3; k++)
                M[a][b] += h[a][k] * g[k][b];
    const int n = s->p.n;
    /* Each thread maps the particles whose sums, kicks and drifts it ran
     * in the pass (dem_cell_block: the same blocks), which are in its
     * cache. In one thread the map of another's particles took twice as
     * long (N = 3375, two threads, Zen 4: the cell's loop 10 % slower,
     * docs/performance.md), and so it did at N = 1000: a parallel region
     * costs less than that at any size measured. */
#pragma omp parallel
    {
        const int nt = omp_get_num_threads(), t = omp_get_thread_num();
        map_range(s, dem_cell_block(n, t, nt), dem_cell_block(n, t + 1, nt),
                  M, from->lo, to->lo);
    }
}

void dem_sim_cell_wrap(struct dem_sim *s)
{
    struct dem_lattice c;
    dem_sim_lattice(s, &c);
    const struct dem_particles *p = &s->p;
    const int d3 = s->dim == 3;
    for (int i = 0; i < p->n; i++) {
        const double x[3] = {p->x[i], p->y[i], p->z[i]};
        double f[3];
        dem_lattice_frac(&c, x, f);
        const double k[3] = {floor(f[0]), floor(f[1]), d3 ? floor(f[2]) : 0.0};
        if (k[0] == 0.0 && k[1] == 0.0 && k[2] == 0.0)
            continue;
        p->x[i] -= k[0] * c.v[0] + k[1] * c.v[1] + k[2] * c.v[2];
        p->y[i] -= k[1] * c.v[3] + k[2] * c.v[4];
        p->z[i] -= k[2] * c.v[5];
    }
}

/* The tilt's shear direction's length: x for xy and xz, y for yz. */
static double tilt_length(const struct dem_lattice *c, int k)
{
    return k == DEM_TILT_YZ ? c->v[3] : c->v[0];
}

int dem_sim_cell_remap(struct dem_sim *s)
{
    struct dem_lattice c;
    dem_sim_lattice(s, &c);
    int changed = 0;
    for (int k = 0; k < 3; k++) {
        struct dem_wall *T = &s->cell.tilt[k];
        const double L = tilt_length(&c, k);
        if (!(fabs(T->pos) > 0.5 * L))
            continue;
        const double d = L * round(T->pos / L);
        T->pos -= d;
        T->x0 -= d; /* a strain-controlled tilt goes on from here */
        s->cell.remapped[k] += d;
        changed = 1;
    }
    return changed;
}

double dem_sim_cell_closure(const struct dem_sim *s)
{
    const struct dem_lattice *b = &s->cell.built;
    if (!(b->v[0] > 0.0)) /* no list built yet */
        return 0.0;
    struct dem_lattice c;
    dem_sim_lattice(s, &c);
    /* the map since the build, h h_b^-1, minus the identity: a pair at
     * distance <= range has moved by at most |M - 1| range relative to
     * its partner (Frobenius norm bounds the operator norm) */
    double h[3][3], g[3][3], n2 = 0.0;
    matrix_of(c.v, h);
    inverse_of(b->v, g);
    for (int a = 0; a < s->dim; a++)
        for (int bb = 0; bb < s->dim; bb++) {
            double m = (a == bb) ? -1.0 : 0.0;
            for (int k = 0; k < 3; k++)
                m += h[a][k] * g[k][bb];
            n2 += m * m;
        }
    return sqrt(n2) * s->cell.range;
}
