/* The periodic cell: its lattice, the frame of the engine's positions,
 * wrapping and the Lees-Edwards re-map (core/cell.h). */
#include "core/cell.h"

#include <math.h>
#include <omp.h>

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

/* m = h_to h_from^-1 and its inverse g (upper triangular, as
 * struct dem_lattice.v); 2D: z stays. */
static void frame_of(const struct dem_lattice *from,
                     const struct dem_lattice *to, int dim, double m[6],
                     double g[6])
{
    double h[3][3], gi[3][3], hb[3][3], gn[3][3];
    double M[3][3] = {{0}}, G[3][3] = {{0}};
    matrix_of(to->v, h);
    inverse_of(from->v, gi);
    matrix_of(from->v, hb);
    inverse_of(to->v, gn);
    if (dim == 2)
        h[2][2] = hb[2][2] = 1.0;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            for (int k = 0; k < 3; k++) {
                M[a][b] += h[a][k] * gi[k][b];
                G[a][b] += hb[a][k] * gn[k][b];
            }
    const double mv[6] = {M[0][0], M[0][1], M[0][2], M[1][1], M[1][2], M[2][2]};
    const double gv[6] = {G[0][0], G[0][1], G[0][2], G[1][1], G[1][2], G[2][2]};
    for (int u = 0; u < 6; u++) {
        m[u] = mv[u];
        g[u] = gv[u];
    }
}

void dem_sim_cell_frame(const struct dem_sim *s, struct dem_frame *f)
{
    struct dem_lattice now;
    dem_sim_lattice(s, &now);
    frame_of(&s->cell.built, &now, s->dim, f->m, f->g);
    const double *m = f->m;
    const double e = sqrt((m[0] - 1.0) * (m[0] - 1.0) + m[1] * m[1] +
                          m[2] * m[2] + (m[3] - 1.0) * (m[3] - 1.0) +
                          m[4] * m[4] + (m[5] - 1.0) * (m[5] - 1.0));
    f->s2 = (1.0 + e) * (1.0 + e);
    for (int k = 0; k < 3; k++) { /* the box's map: the cell's is m */
        f->b[k] = 1.0;
        f->b[3 + k] = 0.0;
    }
}

struct dem_particles dem_sim_engine_particles(const struct dem_sim *s)
{
    struct dem_particles e = s->p;
    if (s->cell.on) {
        e.x = s->p.xs;
        e.y = s->p.ys;
        e.z = s->p.zs;
    }
    return e;
}

void dem_sim_cell_positions(struct dem_sim *s)
{
    const struct dem_lattice *b = &s->cell.built;
    struct dem_lattice now;
    dem_sim_lattice(s, &now);
    struct dem_frame f;
    dem_sim_cell_frame(s, &f);
    const double *m = f.m;
    const struct dem_particles *p = &s->p;
    const double *restrict xs = p->xs, *restrict ys = p->ys,
                           *restrict zs = p->zs;
    double *restrict X = p->x, *restrict Y = p->y, *restrict Z = p->z;
    const double *lb = b->lo, *lo = now.lo;
    const int n = p->n;
#pragma omp parallel for simd schedule(static)
    for (int i = 0; i < n; i++) {
        const double dx = xs[i] - lb[0], dy = ys[i] - lb[1], dz = zs[i] - lb[2];
        X[i] = lo[0] + m[0] * dx + m[1] * dy + m[2] * dz;
        Y[i] = lo[1] + m[3] * dy + m[4] * dz;
        Z[i] = lo[2] + m[5] * dz;
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
    /* yz first: its re-map takes the third edge (xz, yz, Lz) back by m
     * times the second, (xy, Ly, 0), which moves xz by m xy too (a
     * lattice vector only so); xz is then re-mapped with the rest */
    static const int order[3] = {DEM_TILT_YZ, DEM_TILT_XY, DEM_TILT_XZ};
    for (int q = 0; q < 3; q++) {
        const int k = order[q];
        struct dem_wall *T = &s->cell.tilt[k];
        const double L = tilt_length(&c, k);
        if (!(fabs(T->pos) > 0.5 * L))
            continue;
        const double m = round(T->pos / L), d = L * m;
        T->pos -= d;
        T->x0 -= d; /* a strain-controlled tilt goes on from here */
        s->cell.remapped[k] += d;
        if (k == DEM_TILT_YZ) {
            struct dem_wall *X = &s->cell.tilt[DEM_TILT_XZ];
            const double dx = m * s->cell.tilt[DEM_TILT_XY].pos;
            X->pos -= dx;
            X->x0 -= dx;
            s->cell.remapped[DEM_TILT_XZ] += dx;
        }
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
    return sqrt(n2) * s->range;
}
